//! ARMv6-M (Cortex-M0/M0+): the 5-6-5 span loop in Thumb-1 assembly.
//!
//! LLVM keeps the loop's masks, steps and words in memory on Thumb-1 (26 instructions a pair of
//! pixels, ~70 a span around them). Here the three channel words, two masks, the pointer and two
//! temporaries stay in the low registers and the steps, the end pointer and the odd-pixel flag in
//! high ones: 19 instructions a pair. It computes exactly what the portable loop
//! (`color::packed565::run_565`) computes, from the same lanes; the host tests that loop, and CI
//! checks that the Cortex-M0 firmware's scene has the host's checksum.
#![allow(unsafe_code)]

/// r4 = two pixels from the channel words r1 (top), r3 (middle), r2 (bottom) with the masks
/// r6 = 0xF800F800 and r7 = 0xFC00FC00: top & r6 | (middle & r7) >> 5 | (bottom & r6) >> 11
/// (r5 is clobbered). Used by the pair loop and for the odd last pixel.
macro_rules! pack_565 {
    () => {
        "mov r4, r1\nands r4, r6\nmov r5, r2\nands r5, r6\nlsrs r5, r5, #11\norrs r4, r5\n\
         mov r5, r3\nands r5, r7\nlsrs r5, r5, #5\norrs r4, r5"
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_565_span_v6m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    ".p2align 2",
    ".global embedded_raster_565_span_v6m",
    ".hidden embedded_raster_565_span_v6m",
    ".type embedded_raster_565_span_v6m,%function",
    ".thumb_func",
    // r0 = pixels (2-byte aligned), r1 = pixel count, r2 = channel values (raw order,
    // STEP_BITS fractional bits), r3 = SpanSteps (step +0, lane +12, double +24).
    "embedded_raster_565_span_v6m:",
    "push {{r4-r7, lr}}",
    "mov r4, r8",
    "mov r5, r9",
    "mov r6, r10",
    "push {{r4-r6}}",
    // lr = odd pixel count (the return address is on the stack), r12 = end of the pairs.
    "movs r4, #1",
    "ands r4, r1",
    "mov lr, r4",
    "lsrs r1, r1, #1",
    "lsls r1, r1, #2",
    "adds r1, r0, r1",
    "mov r12, r1",
    // r8..r10 = steps of two pixels; r4..r6 = steps of one (lanes).
    "ldr r4, [r3, #24]",
    "mov r8, r4",
    "ldr r4, [r3, #28]",
    "mov r9, r4",
    "ldr r4, [r3, #32]",
    "mov r10, r4",
    "ldr r4, [r3, #12]",
    "ldr r5, [r3, #16]",
    "ldr r6, [r3, #20]",
    // Lanes: top and bottom (v + 2^12) >> 13, middle (v + 2^13) >> 14, in r1, r3, r2.
    "ldr r1, [r2]",
    "ldr r3, [r2, #4]",
    "ldr r2, [r2, #8]",
    "movs r7, #1",
    "lsls r7, r7, #12",
    "adds r1, r1, r7",
    "lsrs r1, r1, #13",
    "adds r2, r2, r7",
    "lsrs r2, r2, #13",
    "lsls r7, r7, #1",
    "adds r3, r3, r7",
    "lsrs r3, r3, #14",
    // Words: (lane + step) << 16 | lane.
    "adds r4, r4, r1",
    "lsls r4, r4, #16",
    "adds r1, r1, r4",
    "adds r5, r5, r3",
    "lsls r5, r5, #16",
    "adds r3, r3, r5",
    "adds r6, r6, r2",
    "lsls r6, r6, #16",
    "adds r2, r2, r6",
    "ldr r6, 4f",
    "ldr r7, 5f",
    "cmp r0, r12",
    "beq 3f",
    // One pair.
    "2:",
    pack_565!(),
    "strh r4, [r0]",
    "lsrs r4, r4, #16",
    "strh r4, [r0, #2]",
    "add r1, r8",
    "add r3, r9",
    "add r2, r10",
    "adds r0, #4",
    "cmp r0, r12",
    "bne 2b",
    // The odd last pixel: the left lanes.
    "3:",
    "mov r4, lr",
    "cmp r4, #0",
    "beq 6f",
    pack_565!(),
    "strh r4, [r0]",
    "6:",
    "pop {{r4-r6}}",
    "mov r8, r4",
    "mov r9, r5",
    "mov r10, r6",
    "pop {{r4-r7, pc}}",
    ".p2align 2",
    "4: .word 0xF800F800",
    "5: .word 0xFC00FC00",
    ".size embedded_raster_565_span_v6m, . - embedded_raster_565_span_v6m",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_565_span_v6m(
        pixels: *mut u16,
        len: usize,
        values: *const [u32; 3],
        steps: *const [u32; 9],
    );
}

/// One run of the 5-6-5 span loop: `len` pixels from `pixels` with the channel values `values`
/// (raw order: top, middle, bottom channel, `color::STEP_BITS` fractional bits) and the steps
/// `steps` (the nine words of `color::SpanSteps`: plain steps, lane steps, double lane steps).
///
/// # Safety
///
/// `pixels` must be valid for writes of `len` consecutive, 2-byte aligned `u16`s, and `steps`
/// valid for reads of nine aligned `u32`s.
#[inline(always)]
pub(crate) unsafe fn span_565(
    pixels: *mut u16,
    len: usize,
    values: &[u32; 3],
    steps: *const [u32; 9],
) {
    // SAFETY: the function writes exactly `len` consecutive 16-bit pixels from `pixels` and reads
    // the nine words at `steps` (the caller's promises) and the three of `values`; it saves and
    // restores every register the AAPCS asks it to.
    unsafe { embedded_raster_565_span_v6m(pixels, len, values, steps) }
}
