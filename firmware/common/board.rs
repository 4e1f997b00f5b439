//! Firmware support shared by the `fw_*` examples (included with `#[path]`, firmware builds
//! only): which board the target runs on under QEMU, and a HardFault handler that reports the
//! faulting address and exits QEMU with failure instead of spinning until the CI timeout.

use cortex_m as _; // critical-section implementation (cortex-m-semihosting needs one)
use cortex_m_rt::{exception, ExceptionFrame};
use cortex_m_semihosting::debug;

/// The QEMU board of this target (see `.cargo/config.toml`).
#[cfg(not(target_has_atomic = "32"))] // thumbv6m: no compare-and-swap
pub const BOARD: &str = "microbit (Cortex-M0, thumbv6m-none-eabi)";
/// The QEMU board of this target (see `.cargo/config.toml`).
#[cfg(all(target_has_atomic = "32", target_abi = "eabihf"))]
pub const BOARD: &str = "mps2-an386 (Cortex-M4F, thumbv7em-none-eabihf)";
/// The QEMU board of this target (see `.cargo/config.toml`).
#[cfg(all(target_has_atomic = "32", not(target_abi = "eabihf")))]
pub const BOARD: &str = "mps2-an385 (Cortex-M3, thumbv7m-none-eabi)";

/// Framebuffer size: the micro:bit has 16 KiB of RAM, the MPS2 boards 4 MiB.
#[cfg(not(target_has_atomic = "32"))]
pub const SIZE: (u32, u32) = (64, 48);
/// Framebuffer size: the micro:bit has 16 KiB of RAM, the MPS2 boards 4 MiB.
#[cfg(target_has_atomic = "32")]
pub const SIZE: (u32, u32) = (128, 96);

/// Number of pixels of the framebuffer.
pub const PIXELS: usize = (SIZE.0 * SIZE.1) as usize;

/// Ends the QEMU run: exit code 0 on success, 1 on failure.
pub fn exit(success: bool) -> ! {
    debug::exit(if success {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    #[allow(clippy::empty_loop)]
    loop {}
}

#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    // Raw semihosting write: the fault may have hit inside `hprintln!`'s borrowed stdout.
    let pc = frame.pc();
    let mut message = *b"HardFault at pc=0x00000000\n";
    for (k, digit) in message[18..26].iter_mut().enumerate() {
        *digit = b"0123456789abcdef"[((pc >> (28 - 4 * k)) & 15) as usize];
    }
    if let Ok(mut stderr) = cortex_m_semihosting::hio::hstderr() {
        let _ = stderr.write_all(&message);
    }
    exit(false)
}
