//! Firmware support shared by the `fw_*` examples (included with `#[path]`, firmware builds
//! only): which board the target runs on under QEMU, its runtime's entry attribute and
//! semihosting print, the stack pointer, and a fault handler that reports the faulting address
//! and exits QEMU with failure instead of spinning until the CI timeout.
//!
//! Cortex-M targets run on cortex-m-rt and cortex-m-semihosting, RISC-V ones on riscv-rt and
//! the `semihosting` crate (QEMU's `virt` machine).

#[cfg(target_arch = "arm")]
pub use arm::*;
#[cfg(target_arch = "riscv32")]
pub use riscv::*;

/// Number of pixels of the framebuffer.
pub const PIXELS: usize = (SIZE.0 * SIZE.1) as usize;

#[cfg(target_arch = "arm")]
mod arm {
    use cortex_m as _; // critical-section implementation (cortex-m-semihosting needs one)
    use cortex_m_rt::{exception, ExceptionFrame};
    use cortex_m_semihosting::debug;

    pub use cortex_m_rt::entry;
    #[allow(unused_imports)] // not every firmware prints with formatting
    pub use cortex_m_semihosting::hprintln;

    /// The QEMU board and core this runs on, from the core's part number (`CPUID`): the same
    /// thumbv7em build runs on the Cortex-M4F and M7 boards.
    pub fn name() -> &'static str {
        // SAFETY: a read of the System Control Block's CPUID register.
        let cpuid = unsafe { core::ptr::read_volatile(0xE000_ED00 as *const u32) };
        match (cpuid >> 4) & 0xFFF {
            0xC20 => "microbit (Cortex-M0, thumbv6m-none-eabi)",
            0xC23 => "mps2-an385 (Cortex-M3, thumbv7m-none-eabi)",
            0xC24 => "mps2-an386 (Cortex-M4F, thumbv7em-none-eabihf)",
            0xC27 => "mps2-an500 (Cortex-M7, thumbv7em-none-eabihf)",
            0xD21 => "mps2-an505 (Cortex-M33, thumbv8m.main-none-eabihf)",
            _ => "unknown Cortex-M",
        }
    }

    /// Framebuffer size: the micro:bit has 16 KiB of RAM, the MPS2 boards 4 MiB.
    #[cfg(not(target_has_atomic = "32"))]
    pub const SIZE: (u32, u32) = (64, 48);
    /// Framebuffer size: the micro:bit has 16 KiB of RAM, the MPS2 boards 4 MiB.
    #[cfg(target_has_atomic = "32")]
    pub const SIZE: (u32, u32) = (128, 96);

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

    /// The stack pointer.
    #[inline(always)]
    pub fn stack_pointer() -> usize {
        cortex_m::register::msp::read() as usize
    }

    #[exception]
    unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
        super::report_fault(frame.pc())
    }

    /// Writes `text` to the host's stderr without formatting (a fault may have hit inside
    /// `hprintln!`'s borrowed stdout).
    pub(super) fn raw_stderr(text: &[u8]) {
        if let Ok(mut stderr) = cortex_m_semihosting::hio::hstderr() {
            let _ = stderr.write_all(text);
        }
    }
}

#[cfg(target_arch = "riscv32")]
mod riscv {
    pub use riscv_rt::entry;
    #[allow(unused_imports)] // not every firmware prints with formatting
    pub use semihosting::println as hprintln;

    /// The QEMU board of this target (`.cargo/config.toml`: `virt`, machine mode, no firmware).
    pub fn name() -> &'static str {
        if cfg!(target_has_atomic = "32") {
            "virt (RV32IMAC, riscv32imac-unknown-none-elf)"
        } else {
            "virt (RV32IMC, riscv32imc-unknown-none-elf)"
        }
    }

    /// Framebuffer size: the MPS2 boards' (RISC-V parts have RAM for it).
    pub const SIZE: (u32, u32) = (128, 96);

    /// Ends the QEMU run: exit code 0 on success, 1 on failure.
    pub fn exit(success: bool) -> ! {
        semihosting::process::exit(if success { 0 } else { 1 })
    }

    /// The stack pointer.
    #[inline(always)]
    pub fn stack_pointer() -> usize {
        let sp: usize;
        // SAFETY: reads a register.
        unsafe { core::arch::asm!("mv {0}, sp", out(reg) sp, options(nomem, nostack)) };
        sp
    }

    /// Any exception (riscv-rt's default handler is a silent spin): report and fail.
    #[export_name = "ExceptionHandler"]
    fn exception_handler(_frame: &riscv_rt::TrapFrame) -> ! {
        let pc: usize;
        // SAFETY: reads a CSR.
        unsafe { core::arch::asm!("csrr {0}, mepc", out(reg) pc, options(nomem, nostack)) };
        super::report_fault(pc as u32)
    }

    /// Writes `text` to the host's stderr.
    pub(super) fn raw_stderr(text: &[u8]) {
        console_write(text, OPEN_APPEND);
    }

    /// Writes `text` to the host's stdout.
    pub fn print(text: &[u8]) {
        console_write(text, OPEN_WRITE);
    }

    /// `SYS_OPEN`'s modes "w" and "a": the console `:tt` opened so is stdout and stderr.
    const OPEN_WRITE: usize = 4;
    const OPEN_APPEND: usize = 8;

    /// Writes `text` to the host's console by semihosting's `SYS_OPEN` (`:tt`), `SYS_WRITE` and
    /// `SYS_CLOSE`, ignoring the answers: no loop over them and no file-handle checks, so no
    /// panic path at any opt-level (the `semihosting` crate's streams keep some at "s" and "z",
    /// which the panic-free firmware would not link with).
    fn console_write(text: &[u8], mode: usize) {
        const NAME: &[u8; 4] = b":tt\0";
        let open = [NAME.as_ptr() as usize, mode, 3];
        // SAFETY: each parameter block is what its call reads, alive across the call.
        unsafe {
            let handle = semihosting_call(0x01, open.as_ptr() as usize);
            if handle == usize::MAX {
                return;
            }
            let write = [handle, text.as_ptr() as usize, text.len()];
            semihosting_call(0x05, write.as_ptr() as usize);
            semihosting_call(0x02, [handle].as_ptr() as usize);
        }
    }

    /// A semihosting call (`op`, its argument), by the RISC-V semihosting sequence: the three
    /// uncompressed instructions QEMU recognises around the `ebreak`, in one aligned block.
    ///
    /// # Safety
    ///
    /// `arg` must be what call `op` expects: the address of its parameter block.
    unsafe fn semihosting_call(op: usize, arg: usize) -> usize {
        let result;
        core::arch::asm!(
            ".option push",
            ".option norvc",
            ".balign 16",
            "slli zero, zero, 0x1f",
            "ebreak",
            "srai zero, zero, 0x7",
            ".option pop",
            inout("a0") op => result,
            in("a1") arg,
            options(nostack, readonly),
        );
        result
    }
}

/// Prints the faulting address and exits with failure.
fn report_fault(pc: u32) -> ! {
    let mut message = *b"fault at pc=0x00000000\n";
    for (k, digit) in message[14..22].iter_mut().enumerate() {
        *digit = b"0123456789abcdef"[((pc >> (28 - 4 * k)) & 15) as usize];
    }
    raw_stderr(&message);
    exit(false)
}
