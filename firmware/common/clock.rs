//! Instruction counting for the firmware benchmarks (`fw_bench`, `fw_mesh_bench`; firmware
//! builds only, included with `#[path]`).
//!
//! Under QEMU's `-icount shift=0` every executed instruction advances the virtual clock by
//! exactly 1 ns. On Cortex-M, SysTick — a 24-bit down counter from the core clock, whose
//! exception counts the wraps — then measures instructions deterministically; the instructions
//! per tick are calibrated against a loop of known length (40 on the 25 MHz MPS2 boards, 62.5 on
//! the 16 MHz micro:bit). On RISC-V, QEMU's `minstret` reads the instruction count itself under
//! `-icount` (host time without it): one instruction a tick, which the calibration confirms.

use core::hint::black_box;

/// What counts: SysTick's ticks, or RISC-V's instructions retired.
#[cfg(target_arch = "arm")]
#[allow(dead_code)] // not every firmware names it
pub const SOURCE: &str = "SysTick";
/// What counts: SysTick's ticks, or RISC-V's instructions retired.
#[cfg(target_arch = "riscv32")]
#[allow(dead_code)] // not every firmware names it
pub const SOURCE: &str = "minstret";

#[cfg(target_arch = "arm")]
#[allow(unused_imports)] // not every firmware stops the clock
pub use systick::{now, start, stop};

#[cfg(target_arch = "arm")]
mod systick {
    use core::sync::atomic::{AtomicU32, Ordering};

    use cortex_m::peripheral::{syst::SystClkSource, SYST};
    use cortex_m_rt::exception;

    /// SysTick reload: the full 24 bits.
    const RELOAD: u32 = 0x00FF_FFFF;

    /// SysTick wraps since start.
    static WRAPS: AtomicU32 = AtomicU32::new(0);

    #[exception]
    fn SysTick() {
        // Only this handler writes; thumbv6m has no atomic read-modify-write.
        WRAPS.store(
            WRAPS.load(Ordering::Relaxed).wrapping_add(1),
            Ordering::Relaxed,
        );
    }

    /// SysTick, whose registers only this module touches.
    fn syst() -> SYST {
        // SAFETY: the firmware uses no other core peripheral handle for SysTick.
        unsafe { cortex_m::Peripherals::steal() }.SYST
    }

    /// Starts SysTick from the core clock with its wrap interrupt, and waits for its first
    /// reload (the counter reads 0 until then).
    pub fn start() {
        let mut syst = syst();
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        syst.enable_interrupt();
        syst.enable_counter();
        while SYST::get_current() == 0 {}
    }

    /// Stops SysTick (so that its exception frames do not count in stack measurements).
    #[allow(dead_code)]
    pub fn stop() {
        let mut syst = syst();
        syst.disable_interrupt();
        syst.disable_counter();
    }

    /// SysTick ticks since it was started.
    #[inline(always)]
    pub fn now() -> u64 {
        loop {
            let wraps = WRAPS.load(Ordering::SeqCst);
            let current = SYST::get_current();
            // A wrap between the two reads runs the handler at once; then read again.
            if WRAPS.load(Ordering::SeqCst) == wraps {
                return u64::from(wraps) * u64::from(RELOAD + 1) + u64::from(RELOAD - current);
            }
        }
    }
}

#[cfg(target_arch = "riscv32")]
#[allow(unused_imports)] // not every firmware stops the clock
pub use instret::{now, start, stop};

#[cfg(target_arch = "riscv32")]
mod instret {
    /// Nothing to start: `minstret` always counts.
    pub fn start() {}

    /// Nothing to stop (no interrupt).
    #[allow(dead_code)]
    pub fn stop() {}

    /// Instructions retired (`minstreth:minstret`, read again if the low half wrapped between).
    #[inline(always)]
    pub fn now() -> u64 {
        loop {
            let (high, low, again): (u32, u32, u32);
            // SAFETY: reads counters.
            unsafe {
                core::arch::asm!(
                    "csrr {0}, minstreth",
                    "csrr {1}, minstret",
                    "csrr {2}, minstreth",
                    out(reg) high,
                    out(reg) low,
                    out(reg) again,
                    options(nomem, nostack)
                );
            }
            if high == again {
                return (u64::from(high) << 32) | u64::from(low);
            }
        }
    }
}

/// Runs `2 n` instructions (a decrement and a branch per iteration).
#[inline(never)]
fn spin(n: u32) {
    // SAFETY: register-only loop.
    #[cfg(target_arch = "arm")]
    unsafe {
        core::arch::asm!(
            "2:",
            "subs {0}, #1",
            "bne 2b",
            inout(reg) n => _,
            options(nomem, nostack)
        );
    }
    // SAFETY: register-only loop.
    #[cfg(target_arch = "riscv32")]
    unsafe {
        core::arch::asm!(
            "2:",
            "addi {0}, {0}, -1",
            "bnez {0}, 2b",
            inout(reg) n => _,
            options(nomem, nostack)
        );
    }
}

/// Instructions per SysTick tick as a fraction `(instructions, ticks)`.
pub fn calibrate() -> (u64, u64) {
    let t0 = now();
    spin(100_000);
    let t1 = now();
    spin(1_100_000);
    let t2 = now();
    // The two calls differ by exactly 2 000 000 instructions.
    (2_000_000, (t2 - t1) - (t1 - t0))
}

/// Ticks of `reps` passes of `f`, minus the ticks of as many empty passes.
pub fn measure(reps: u32, mut f: impl FnMut()) -> u64 {
    let t0 = now();
    for _ in 0..black_box(reps) {
        f();
    }
    let t1 = now();
    for _ in 0..black_box(reps) {
        black_box(());
    }
    let t2 = now();
    (t1 - t0).saturating_sub(t2 - t1)
}

/// `ticks` in instructions, with the calibration `(instructions, ticks)` of [`calibrate`].
pub fn instructions(ticks: u64, (cal_instructions, cal_ticks): (u64, u64)) -> u64 {
    // Checked: the panic-free firmware (fw_band_microbit) links this too.
    (ticks * cal_instructions + cal_ticks / 2)
        .checked_div(cal_ticks)
        .unwrap_or(0)
}

/// `n / d` printed with two decimals, in integers only (`–` for `d = 0`).
pub struct Ratio(pub u64, pub u64);

impl core::fmt::Display for Ratio {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        if self.1 == 0 {
            return write!(f, "–");
        }
        let hundredths = (self.0 * 100 + self.1 / 2) / self.1;
        write!(f, "{}.{:02}", hundredths / 100, hundredths % 100)
    }
}
