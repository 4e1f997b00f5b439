//! ARMv6-M (Cortex-M0/M0+): the 5-6-5 span loop in Thumb-1 assembly.
//!
//! LLVM keeps the loop's masks, steps and words in memory on Thumb-1 (26 instructions a pair of
//! pixels, ~70 a span around them). Here the pair loop keeps everything in registers and stores
//! each pair with one word store: the two lower channel words, the three masks, the pointer and
//! two temporaries in the low registers, the top channel word, the three double steps and the
//! last pixel's address in high ones — 14 instructions a pair. A span starting at an address of
//! 2 mod 4 writes its first pixel alone (ARMv6-M has no unaligned word stores).
//!
//! It computes what the portable loop (`color::packed565::run_565`) computes from the same lanes
//! wherever the lanes are in range, as they are at every covered pixel (the low half of each
//! 16-bit lane is the same modulo 2¹⁶ however the pair words are formed); the host tests that
//! loop, and CI checks that the Cortex-M0 firmware's scene has the host's checksum.
#![allow(unsafe_code)]

/// r4 = two pixels from the channel words lr (top), r1 (middle), r2 (bottom) with the masks
/// r3 = 0xF800F800, r6 = 0x07E007E0 and r7 = 0x001F001F: top & r3 | (middle >> 5) & r6 |
/// (bottom >> 11) & r7 (r5 is clobbered). Used by the pair loop and for the odd last pixel.
macro_rules! pack_565 {
    () => {
        "mov r4, lr\nands r4, r3\nlsrs r5, r1, #5\nands r5, r6\norrs r4, r5\n\
         lsrs r5, r2, #11\nands r5, r7\norrs r4, r5"
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
    // STEP_BITS fractional bits), r3 = SpanSteps (lane +0, double +12).
    "embedded_raster_565_span_v6m:",
    "push {{r4-r7, lr}}",
    "mov r4, r8",
    "mov r5, r9",
    "mov r6, r10",
    "push {{r4-r6}}",
    // r12 = the last pixel's address (pairs are stored while r0 is below it).
    "lsls r1, r1, #1",
    "adds r1, r0, r1",
    "subs r1, r1, #2",
    "mov r12, r1",
    // Lanes: top and bottom (v + 2^12) >> 13, middle (v + 2^13) >> 14, in r4, r1, r2.
    "ldr r4, [r2]",
    "ldr r1, [r2, #4]",
    "ldr r2, [r2, #8]",
    "movs r5, #1",
    "lsls r5, r5, #12",
    "adds r4, r4, r5",
    "lsrs r4, r4, #13",
    "adds r2, r2, r5",
    "lsrs r2, r2, #13",
    "lsls r5, r5, #1",
    "adds r1, r1, r5",
    "lsrs r1, r1, #14",
    // Word-aligned start: straight to the words.
    "lsls r5, r0, #30",
    "bpl 1f",
    // Else the first pixel alone (if any), from the lanes' low halves (top bits 11..16,
    // middle bits 10..16 to 5..11, bottom bits 11..16 to 0..5), and the lanes stepped once.
    "cmp r0, r12",
    "bhi 8f",
    "lsls r5, r4, #16",
    "lsrs r5, r5, #27",
    "lsls r5, r5, #11",
    "lsls r6, r1, #16",
    "lsrs r6, r6, #26",
    "lsls r6, r6, #5",
    "orrs r5, r6",
    "lsls r6, r2, #16",
    "lsrs r6, r6, #27",
    "orrs r5, r6",
    "strh r5, [r0]",
    "adds r0, #2",
    "ldm r3!, {{r5, r6, r7}}",
    "adds r4, r4, r5",
    "adds r1, r1, r6",
    "adds r2, r2, r7",
    "b 2f",
    "1:",
    // r5..r7 = lane steps; r3 then points at the double steps.
    "ldm r3!, {{r5, r6, r7}}",
    "2:",
    // Words: (lane + step) << 16 | lane; the top one in lr.
    "adds r5, r5, r4",
    "lsls r5, r5, #16",
    "adds r4, r4, r5",
    "mov lr, r4",
    "adds r6, r6, r1",
    "lsls r6, r6, #16",
    "adds r1, r1, r6",
    "adds r7, r7, r2",
    "lsls r7, r7, #16",
    "adds r2, r2, r7",
    // r8..r10 = steps of two pixels; r3, r6, r7 = masks.
    "ldm r3, {{r3, r4, r5}}",
    "mov r8, r3",
    "mov r9, r4",
    "mov r10, r5",
    "ldr r3, 4f",
    "ldr r6, 5f",
    "ldr r7, 6f",
    "cmp r0, r12",
    "bhs 7f",
    // One pair, one word store.
    "3:",
    pack_565!(),
    "stm r0!, {{r4}}",
    "add lr, r8",
    "add r1, r9",
    "add r2, r10",
    "cmp r0, r12",
    "blo 3b",
    // r0 = the last pixel's address: it is left, from the words' low halves.
    "7:",
    "bne 8f",
    pack_565!(),
    "strh r4, [r0]",
    "8:",
    "pop {{r4-r6}}",
    "mov r8, r4",
    "mov r9, r5",
    "mov r10, r6",
    "pop {{r4-r7, pc}}",
    ".p2align 2",
    "4: .word 0xF800F800",
    "5: .word 0x07E007E0",
    "6: .word 0x001F001F",
    ".size embedded_raster_565_span_v6m, . - embedded_raster_565_span_v6m",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_565_span_v6m(
        pixels: *mut u16,
        len: usize,
        values: *const [u32; 3],
        steps: *const [u32; 6],
    );
}

/// One run of the 5-6-5 span loop: `len` pixels from `pixels` with the channel values `values`
/// (raw order: top, middle, bottom channel, `color::STEP_BITS` fractional bits) and the steps
/// `steps` (the first six words of `color::SpanSteps`: lane steps, double lane steps).
///
/// # Safety
///
/// `pixels` must be valid for writes of `len` consecutive, 2-byte aligned `u16`s, and `steps`
/// valid for reads of six aligned `u32`s.
#[inline(always)]
pub(crate) unsafe fn span_565(
    pixels: *mut u16,
    len: usize,
    values: &[u32; 3],
    steps: *const [u32; 6],
) {
    // SAFETY: the function writes exactly `len` consecutive 16-bit pixels from `pixels` (word
    // stores only at 4-byte aligned addresses, as ARMv6-M requires) and reads the six words at
    // `steps` (the caller's promises) and the three of `values`; it saves and restores every
    // register the AAPCS asks it to.
    unsafe { embedded_raster_565_span_v6m(pixels, len, values, steps) }
}
