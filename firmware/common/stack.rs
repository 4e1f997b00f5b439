//! Stack high-water marks for the firmware examples (firmware builds only, included with
//! `#[path]`): the RAM below the stack pointer is painted with a pattern before a call, and the
//! lowest word the call changed tells how deep its stack went ([`measure`]); or painted once at
//! the start of `main` ([`paint_run`]) and scanned at its end ([`high_water`]): the run's
//! deepest stack against the stack's size (from the statics' end to its top). On the micro:bit
//! (16 KiB of RAM, most of it buffers) a stack overflowing into the statics corrupts them
//! silently; `.ci/firmware.sh` requires the run's line there and a margin below the deepest
//! point.

use core::sync::atomic::{AtomicUsize, Ordering};

#[allow(dead_code)]
#[path = "plain_print.rs"]
mod plain_print;

/// The pattern painted.
const PAINT: u32 = 0x5afe_57ac;

/// At most this many bytes below the caller's stack pointer are painted (the MPS2 boards have
/// megabytes of free RAM; the micro:bit's whole free RAM is below this).
const DEPTH: usize = 64 * 1024;

extern "C" {
    /// The end of the statics (the runtime's heap start): the stack grows down towards it.
    static mut __sheap: u32;
    /// The top of the stack (its initial pointer), from the runtime's link.x.
    static _stack_start: u32;
}

/// The lowest word of the run's painting ([`paint_run`]; 0 before it).
static RUN_BOTTOM: AtomicUsize = AtomicUsize::new(0);
/// The lowest stack word found changed before [`measure`] painted over it (`usize::MAX`: none).
static RUN_LOWEST: AtomicUsize = AtomicUsize::new(usize::MAX);

/// Paints `bottom .. top` (word-aligned, free RAM below the stack pointer).
fn paint(bottom: usize, top: usize) {
    let mut p = bottom;
    while p < top {
        // Safety: free RAM between the statics and the stack, word-aligned.
        unsafe { core::ptr::write_volatile(p as *mut u32, PAINT) };
        p += 4;
    }
}

/// The lowest word of `bottom .. top` that is not the pattern (`top` if none).
fn lowest_changed(bottom: usize, top: usize) -> usize {
    let mut p = bottom;
    // Safety: as in `paint`.
    while p < top && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
        p += 4;
    }
    p
}

/// The lowest word to paint below the stack pointer `sp`: the statics' end, or [`DEPTH`] below.
fn floor(sp: usize) -> usize {
    // Only the linker symbol's address is taken.
    let end_of_statics = core::ptr::addr_of_mut!(__sheap) as usize;
    end_of_statics
        .max(sp.saturating_sub(DEPTH))
        .next_multiple_of(4)
}

/// Paints the free stack below the caller's frame (down to the statics' end; at most [`DEPTH`]
/// bytes): first thing in `main`, for [`high_water`] at its end.
#[allow(dead_code)] // not every firmware reports its run
#[inline(never)]
pub fn paint_run() {
    let sp = crate::board::stack_pointer();
    let bottom = floor(sp);
    paint(bottom, (sp - 256) & !3);
    RUN_BOTTOM.store(bottom, Ordering::Relaxed);
}

/// The run's stack high-water mark since [`paint_run`]: the bytes from the stack's top down to
/// the lowest word changed, and the stack's size (its top less the statics' end).
#[allow(dead_code)] // not every firmware reports its run
#[inline(never)]
pub fn high_water() -> (u32, u32) {
    let start = core::ptr::addr_of!(_stack_start) as usize;
    let end_of_statics = core::ptr::addr_of_mut!(__sheap) as usize;
    let size = start.saturating_sub(end_of_statics) as u32;
    let bottom = RUN_BOTTOM.load(Ordering::Relaxed);
    if bottom == 0 {
        return (0, size);
    }
    let sp = crate::board::stack_pointer();
    let lowest = lowest_changed(bottom, (sp - 256) & !3).min(RUN_LOWEST.load(Ordering::Relaxed));
    (start.saturating_sub(lowest) as u32, size)
}

/// Prints the run's line, `stack high-water: N bytes of M` ([`high_water`]), without
/// formatting machinery (panic-free firmware reports it too).
#[allow(dead_code)] // not every firmware reports its run
pub fn report() {
    let (used, size) = high_water();
    plain_print::print(b"stack high-water: ");
    plain_print::decimal(u64::from(used));
    plain_print::print(b" bytes of ");
    plain_print::decimal(u64::from(size));
    plain_print::print(b"\n");
}

/// Runs `f` and returns its result with the bytes of stack it took below the caller's frame.
#[allow(dead_code)] // not every firmware measures a call
pub fn measure<T>(f: &mut impl FnMut() -> T) -> (T, u32) {
    let sp = crate::board::stack_pointer();
    let bottom = floor(sp);
    // This function's own frame (and the calls below) stay unpainted.
    let top = (sp - 256) & !3;
    // The run's mark so far, before it is painted over.
    let run = RUN_BOTTOM.load(Ordering::Relaxed);
    if run != 0 {
        let lowest = lowest_changed(run, top).min(RUN_LOWEST.load(Ordering::Relaxed));
        RUN_LOWEST.store(lowest, Ordering::Relaxed);
    }
    paint(bottom, top);
    let result = f();
    let p = lowest_changed(bottom, top);
    (result, (sp - p) as u32)
}
