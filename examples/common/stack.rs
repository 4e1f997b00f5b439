//! Stack high-water marks for the firmware examples (firmware builds only, included with
//! `#[path]`): the RAM below the stack pointer is painted with a pattern before a call, and the
//! lowest word the call changed tells how deep its stack went.

/// The pattern painted.
const PAINT: u32 = 0x5afe_57ac;

/// At most this many bytes below the caller's stack pointer are painted (the MPS2 boards have
/// megabytes of free RAM; the micro:bit's whole free RAM is below this).
const DEPTH: usize = 64 * 1024;

extern "C" {
    /// The end of the statics (cortex-m-rt's heap start): the stack grows down towards it.
    static mut __sheap: u32;
}

/// Runs `f` and returns its result with the bytes of stack it took below the caller's frame.
pub fn measure<T>(f: &mut impl FnMut() -> T) -> (T, u32) {
    let sp = cortex_m::register::msp::read() as usize;
    // Only the linker symbol's address is taken.
    let end_of_statics = core::ptr::addr_of_mut!(__sheap) as usize;
    let bottom = end_of_statics
        .max(sp.saturating_sub(DEPTH))
        .next_multiple_of(4);
    // This function's own frame (and the calls below) stay unpainted.
    let top = (sp - 256) & !3;
    let mut p = bottom;
    while p < top {
        // Safety: free RAM between the statics and the stack, word-aligned.
        unsafe { core::ptr::write_volatile(p as *mut u32, PAINT) };
        p += 4;
    }
    let result = f();
    let mut p = bottom;
    // Safety: as above.
    while p < top && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
        p += 4;
    }
    (result, (sp - p) as u32)
}
