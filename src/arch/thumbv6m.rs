//! ARMv6-M (Cortex-M0/M0+): the 5-6-5 span loop and its dithered runs, the masked nearest texel
//! loop and its depth-tested form (the perspective-correct fill's unlit chunks), and the 5-6-5
//! blends of a constant colour at a constant opacity and of an alpha per vertex in Thumb-1
//! assembly.
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
//!
//! The dithered span ([`dithered_span_565`]) is the same pair loop over two words a pass: the
//! words of pixels `4k, 4k + 1` and `4k + 2, 4k + 3` differ by two lane steps plus the Bayer
//! offsets' difference, and the next pass's first word is the second plus two lane steps less
//! it, so one set of words steps by those two sets of steps (in high registers, one on the
//! stack): 28 instructions for four pixels, where LLVM's loop took 64 (the two streams of
//! `color::packed565::dithered_run_565` on the stack). Around it, every run of 32 pixels: the
//! test of its values at both ends (`run_stays_inside`'s), its lanes from the values, a first
//! pixel alone at an address of 2 mod 4, its words from the lanes and two constants a channel
//! found once a span, the values moved on — the span's set-up once, not a run's in Rust and a
//! call each. It stops before a run that fails the test and says where, for the clamped
//! definition in Rust. The same words, so the same pixels; CI checks the Cortex-M0 scene's
//! dithered triangles and its random dithered spans (values near and across the test's limits)
//! against the host's checksums.
//!
//! The masked nearest texel loop ([`masked_nearest_565`]): LLVM unrolls the portable loop
//! (`texture::span`'s `Affine` with the masked nearest sampler) four times but keeps the masks,
//! steps and texel pointer on the stack — 67 instructions for four pixels, ~140 a span around
//! them (18.5 of the 29 instructions a pixel of a large textured triangle). Here everything
//! stays in registers (the coordinates, masks, texel and pixel pointers in the low ones, the
//! steps and the end in high ones) and a pixel is 9 instructions: the byte offset of its texel
//! from the two coordinates shifted by 15 (not 16) and the masks doubled, one `ldrh`, one
//! `strh`, two adds; four pixels a loop pass, the first pass entered at the pixel that leaves a
//! multiple of four (a computed jump: no second copy for the remainder). It reads the texel the
//! portable loop reads at every pixel: `((y >> 15) & 2·rows) | ((x >> 15) & 2·x_mask)` is twice
//! `((y >> 16) & rows) | ((x >> 16) & x_mask)` bit for bit (the masks' bit 0 is clear after
//! doubling, and bit `k + 1` of `v >> 15` is bit `k` of `v >> 16`). The host tests that formula
//! against `Texture::sample`; CI checks the Cortex-M0 `fw_texture_bench` frames against the
//! host's.
//!
//! The depth-tested form ([`depth_masked_nearest_565`]) draws the pixels between two chunk ends
//! of the 3D perspective-correct fill: the same texel index, and a pixel drawn where `z >> 16`
//! is below the stored depth, compared as `z < depth << 16` (the same order for every 32-bit `z`
//! and 16-bit depth: `z >> 16 < d` exactly when `z < d·2¹⁶`) with `z` kept in a high register —
//! 18 instructions a drawn pixel, 7 where the test fails, four pixels a pass entered by the same
//! computed jump. LLVM's loop took about 45. The host tests the masked formula; CI checks the
//! Cortex-M0 `fw_texture_bench` frames (the perspective cases and 300 random perspective
//! triangles) and the M0 code's textured mesh frames against the host's.
//!
//! The blend loop ([`blend_solid_565`]): LLVM keeps the portable pair loop's masks and lanes on
//! the stack (25.6 instructions a pixel of a large translucent triangle). Here two pixels are
//! 20 instructions in registers — three field extractions, three `muls` by `256 − w` and adds
//! of the lanes' `s·w + 128` from high registers, three masks, two ORs — four words a pass, the
//! first pass entered by a computed jump as in the texel loop; a pixel at an address of 2 mod 4
//! at either end alone. It gives the portable loop's integers
//! (every lane below 2¹⁶); CI checks the Cortex-M0 scene's translucent triangles against the
//! host's checksum.
//!
//! The blend of an alpha per vertex ([`premultiplied_565`]): LLVM's loop on raw values keeps
//! most of the four planes and their steps on the stack (fw_bench: 64-67 instructions a pixel,
//! 60.67 pixel by pixel through the channels). Here the four planes and their steps stay in
//! registers and a pixel is 31 instructions: the factor, the three fields each shifted so that
//! one multiply by `f·2¹⁰` and one add of its plane (scaled by 4, 4 and 8) put its channel at
//! the top of the word, and the three packed. The host tests that arithmetic
//! (`color::blend`'s `premultiplied_pixel_v6m`) against the per-pixel definition on any planes;
//! CI checks that the Cortex-M0 firmware's scene (which blends such a triangle) has the host's
//! checksum.
#![allow(unsafe_code)]

use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;

use super::MaskedSpan565;

/// The entry of a function that uses r4-r11: saves them and lr (the AAPCS's callee-saved
/// registers; Thumb-1 pushes the high ones through low ones).
macro_rules! save_registers {
    () => {
        "push {{r4-r7, lr}}\nmov r4, r8\nmov r5, r9\nmov r6, r10\nmov r7, r11\npush {{r4-r7}}"
    };
}

/// The return of a function that began with `save_registers`: restores r4-r11, returns.
macro_rules! restore_registers {
    () => {
        "pop {{r4-r7}}\nmov r8, r4\nmov r9, r5\nmov r10, r6\nmov r11, r7\npop {{r4-r7, pc}}"
    };
}

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

/// A span of the dithered 5-6-5 fill for [`dithered_span_565`] (`color::packed565`'s
/// `dithered_565` defines its pixels): values and steps in raw order (top, middle, bottom).
#[repr(C)]
pub(crate) struct DitheredSpan565<'a> {
    /// 0: the channel values at the span's first pixel (24 fractional bits, +½ included); where
    /// [`dithered_span_565`] stops early, those at the first pixel it did not draw.
    pub(crate) value: [u32; 3],
    /// 12: the lanes' steps a pixel, two of them in both halves of a word, and the channels'
    /// steps a pixel (`color::SpanSteps`' layout, in raw order).
    pub(crate) steps: &'a [u32; 9],
    /// 16: the Bayer offsets of pixels 0 and 1, as a word of two lanes with 11 fractional bits
    /// (`color`'s `bayer_pair`): a run at an address of 2 mod 4 draws its first pixel alone
    /// with these.
    pub(crate) head: u32,
    /// 20, 24: those of the run's first two pixels at a 4-byte aligned address and of the two
    /// after them (pixels 0-1 and 2-3, or 1-2 and 3-4 after a first pixel alone).
    pub(crate) first: u32,
    pub(crate) second: u32,
}

/// One channel's test of a run (r2 = its pixels less one): its values at the run's first and
/// last pixels, less r6 (31/64 LSB), both below r7 (the range), else the run is not drawn (18);
/// the step at `$step` in `SpanSteps` (r3), the value at `$value` on the stack.
macro_rules! dithered_run_test {
    ($step:literal, $value:literal) => {
        concat!(
            "ldr r4, [r3, #",
            $step,
            "]\n",
            "muls r4, r2, r4\n",
            "ldr r5, [sp, #",
            $value,
            "]\n",
            "adds r4, r4, r5\n",
            "subs r4, r4, r6\n",
            "cmp r4, r7\n",
            "bhs 18b\n",
            "subs r5, r5, r6\n",
            "cmp r5, r7\n",
            "bhs 18b\n",
        )
    };
}

/// The value at `$value` on the stack moved on by 32 pixels of its step at `$step` in
/// `SpanSteps` (r3).
macro_rules! dithered_advance {
    ($step:literal, $value:literal) => {
        concat!(
            "ldr r4, [r3, #",
            $step,
            "]\n",
            "lsls r4, r4, #5\n",
            "ldr r5, [sp, #",
            $value,
            "]\n",
            "adds r5, r5, r4\n",
            "str r5, [sp, #",
            $value,
            "]\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_dithered_span_565_v6m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    ".p2align 2",
    ".global embedded_raster_dithered_span_565_v6m",
    ".hidden embedded_raster_dithered_span_565_v6m",
    ".type embedded_raster_dithered_span_565_v6m,%function",
    ".thumb_func",
    // r0 = pixels (2-byte aligned), r1 = pixel count (at least one), r2 = the span
    // (`DitheredSpan565`). Returns the pixels drawn in r0.
    "embedded_raster_dithered_span_565_v6m:",
    save_registers!(),
    // [sp]: the bottom lanes' step from the word of pixels 2-3 to that of the next pixels 0-1;
    // [sp, #4]: the end of the run's passes of four pixels; [sp, #8]: the pixels after them;
    // [sp, #12-20]: the values at the run's first pixel; [sp, #24]: the pixels left after the
    // run; [sp, #28]: the span; [sp, #32]: its first pixel; [sp, #36]: its steps; [sp, #40-48]:
    // a run's constants a channel (its lane step << 16 plus the first pair's offsets, the middle
    // lane's halved); [sp, #52]: the offsets of a first pixel alone.
    "sub sp, #56",
    "str r1, [sp, #24]",
    "str r2, [sp, #28]",
    "str r0, [sp, #32]",
    "ldr r3, [r2, #12]",
    "str r3, [sp, #36]",
    "ldr r4, [r2]",
    "str r4, [sp, #12]",
    "ldr r4, [r2, #4]",
    "str r4, [sp, #16]",
    "ldr r4, [r2, #8]",
    "str r4, [sp, #20]",
    // Every channel's step below 2²⁶ in magnitude (4 LSB a pixel: a run's last value is then
    // exact modulo 2³²), or nothing is drawn here.
    "ldr r5, 84f",
    "ldr r4, [r3, #24]",
    "adds r4, r4, r5",
    "lsrs r4, r4, #27",
    "bne 18f",
    "ldr r4, [r3, #28]",
    "adds r4, r4, r5",
    "lsrs r4, r4, #27",
    "bne 18f",
    "ldr r4, [r3, #32]",
    "adds r4, r4, r5",
    "lsrs r4, r4, #27",
    "bne 18f",
    // The steps between the two words of a pass: from pixels 0-1 to 2-3 two lane steps plus
    // the offsets' difference (r8-r10), from 2-3 to the next 0-1 two lane steps less it (r11,
    // r12, [sp]); the middle lane's offsets are half the others'.
    "ldr r4, [r2, #20]",
    "ldr r5, [r2, #24]",
    "subs r6, r5, r4",
    "asrs r4, r4, #1",
    "asrs r5, r5, #1",
    "subs r7, r5, r4",
    "ldr r4, [r3, #12]",
    "adds r5, r4, r6",
    "mov r8, r5",
    "subs r5, r4, r6",
    "mov r11, r5",
    "ldr r4, [r3, #16]",
    "adds r5, r4, r7",
    "mov r9, r5",
    "subs r5, r4, r7",
    "mov r12, r5",
    "ldr r4, [r3, #20]",
    "adds r5, r4, r6",
    "mov r10, r5",
    "subs r5, r4, r6",
    "str r5, [sp]",
    // A run's words are its first lanes times 0x10001 plus these.
    "ldr r4, [r2, #20]",
    "ldr r5, [r3]",
    "lsls r5, r5, #16",
    "adds r5, r5, r4",
    "str r5, [sp, #40]",
    "ldr r5, [r3, #8]",
    "lsls r5, r5, #16",
    "adds r5, r5, r4",
    "str r5, [sp, #48]",
    "asrs r4, r4, #1",
    "ldr r5, [r3, #4]",
    "lsls r5, r5, #16",
    "adds r5, r5, r4",
    "str r5, [sp, #44]",
    "ldr r4, [r2, #16]",
    "str r4, [sp, #52]",
    "b 10f",
    // Stopped at a run whose values leave the channels' ranges: the values at its first pixel
    // back to the span; then (at 17 where every pixel is drawn) the pixels drawn to r0.
    "18:",
    "ldr r2, [sp, #28]",
    "ldr r4, [sp, #12]",
    "str r4, [r2]",
    "ldr r4, [sp, #16]",
    "str r4, [r2, #4]",
    "ldr r4, [sp, #20]",
    "str r4, [r2, #8]",
    "17:",
    "ldr r4, [sp, #32]",
    "subs r0, r0, r4",
    "lsrs r0, r0, #1",
    "add sp, #56",
    restore_registers!(),
    // A run of r1 = min(left, 32) pixels from r0, if its values at both ends are inside
    // [31/64, max + 33/64) LSB (`color::packed565`'s `run_stays_inside`).
    "10:",
    "ldr r1, [sp, #24]",
    "cmp r1, #32",
    "bls 11f",
    "movs r1, #32",
    "11:",
    "subs r2, r1, #1",
    "ldr r3, [sp, #36]",
    "ldr r6, 85f",
    "ldr r7, 86f",
    dithered_run_test!("24", "12"),
    dithered_run_test!("32", "20"),
    "ldr r7, 87f",
    dithered_run_test!("28", "16"),
    "ldr r4, [sp, #24]",
    "subs r4, r4, r1",
    "str r4, [sp, #24]",
    "str r1, [sp, #8]",
    // The lanes, `(value + 2^(k − 1)) >> k` (k = 13, 14, 13): top in lr, middle in r1, bottom
    // in r2; the masks in r3, r6, r7.
    "ldr r5, 88f",
    "ldr r4, [sp, #12]",
    "adds r4, r4, r5",
    "lsrs r4, r4, #13",
    "mov lr, r4",
    "ldr r2, [sp, #20]",
    "adds r2, r2, r5",
    "lsrs r2, r2, #13",
    "lsls r5, r5, #1",
    "ldr r1, [sp, #16]",
    "adds r1, r1, r5",
    "lsrs r1, r1, #14",
    "ldr r3, 4f",
    "ldr r6, 5f",
    "ldr r7, 6f",
    // At an address of 2 mod 4 the first pixel alone: its lanes plus the offsets of pixel 0
    // (the middle lane's halved), packed; then the lanes one step on.
    "lsls r4, r0, #30",
    "bpl 13f",
    "ldr r5, [sp, #52]",
    "mov r4, lr",
    "adds r4, r4, r5",
    "ands r4, r3",
    "adds r5, r5, r2",
    "lsrs r5, r5, #11",
    "ands r5, r7",
    "orrs r4, r5",
    "ldr r5, [sp, #52]",
    "asrs r5, r5, #1",
    "adds r5, r5, r1",
    "lsrs r5, r5, #5",
    "ands r5, r6",
    "orrs r4, r5",
    "strh r4, [r0]",
    "adds r0, #2",
    "ldr r4, [sp, #36]",
    "ldr r5, [r4]",
    "add lr, r5",
    "ldr r5, [r4, #4]",
    "adds r1, r1, r5",
    "ldr r5, [r4, #8]",
    "adds r2, r2, r5",
    "ldr r4, [sp, #8]",
    "subs r4, #1",
    "str r4, [sp, #8]",
    "13:",
    // The passes' end and the pixels after them; the words of the first two pixels.
    "ldr r4, [sp, #8]",
    "lsls r5, r4, #30",
    "lsrs r5, r5, #30",
    "str r5, [sp, #8]",
    "lsrs r4, r4, #2",
    "lsls r4, r4, #3",
    "adds r4, r0, r4",
    "str r4, [sp, #4]",
    "mov r4, lr",
    "lsls r5, r4, #16",
    "adds r4, r4, r5",
    "ldr r5, [sp, #40]",
    "adds r4, r4, r5",
    "mov lr, r4",
    "lsls r5, r1, #16",
    "adds r1, r1, r5",
    "ldr r5, [sp, #44]",
    "adds r1, r1, r5",
    "lsls r5, r2, #16",
    "adds r2, r2, r5",
    "ldr r5, [sp, #48]",
    "adds r2, r2, r5",
    "ldr r4, [sp, #4]",
    "cmp r0, r4",
    "bhs 3f",
    // Four pixels a pass: two words.
    "1:",
    pack_565!(),
    "stm r0!, {{r4}}",
    "add lr, r8",
    "add r1, r9",
    "add r2, r10",
    pack_565!(),
    "stm r0!, {{r4}}",
    "add lr, r11",
    "add r1, r12",
    "ldr r5, [sp]",
    "adds r2, r2, r5",
    "ldr r5, [sp, #4]",
    "cmp r0, r5",
    "blo 1b",
    // Then up to three: a word and a pixel of the next, a word, or a pixel.
    "3:",
    "ldr r5, [sp, #8]",
    "cmp r5, #0",
    "beq 8f",
    "cmp r5, #2",
    "blo 7f",
    pack_565!(),
    "stm r0!, {{r4}}",
    "ldr r5, [sp, #8]",
    "cmp r5, #2",
    "beq 8f",
    "add lr, r8",
    "add r1, r9",
    "add r2, r10",
    "7:",
    pack_565!(),
    "strh r4, [r0]",
    "adds r0, #2",
    // The next run, if any: the values 32 pixels on.
    "8:",
    "ldr r1, [sp, #24]",
    "cmp r1, #0",
    "bne 9f",
    "b 17b",
    "9:",
    "ldr r3, [sp, #36]",
    dithered_advance!("24", "12"),
    dithered_advance!("28", "16"),
    dithered_advance!("32", "20"),
    "b 10b",
    ".p2align 2",
    "4: .word 0xF800F800",
    "5: .word 0x07E007E0",
    "6: .word 0x001F001F",
    // 2²⁶; 31/64 LSB (`31 << 18`); the top and bottom channels' range above it
    // (`(31·64 + 33 − 31) << 18`), the middle one's (`(63·64 + 33 − 31) << 18`); 2¹².
    "84: .word 0x04000000",
    "85: .word 0x007C0000",
    "86: .word 0x1F080000",
    "87: .word 0x3F080000",
    "88: .word 0x00001000",
    ".size embedded_raster_dithered_span_565_v6m, . - embedded_raster_dithered_span_565_v6m",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_dithered_span_565_v6m(
        pixels: *mut u16,
        len: usize,
        span: *mut DitheredSpan565<'_>,
    ) -> usize;
}

/// Draws the dithered span `span` into the `len` pixels from `pixels`, run by run (32 pixels
/// from the first, its lanes restarted from the values each run): pixel `i` of a run the 5-6-5
/// packing of its lanes plus its Bayer offset, two pixels a word, as `color::packed565`'s
/// `dithered_run_565` computes it, while a run's values at both ends lie within 1/64 LSB of
/// the channels' ranges (`run_stays_inside`'s test, so every dithered lane stays inside its 16
/// bits). Returns the pixels drawn: all of them, or those before the first run that failed
/// the test (none if a channel steps by 4 LSB a pixel or more), whose values it leaves in
/// `span.value`.
///
/// # Safety
///
/// `pixels` must be valid for writes of `len` (at least one) consecutive `u16`s.
#[inline(always)]
pub(crate) unsafe fn dithered_span_565(
    pixels: *mut u16,
    len: usize,
    span: &mut DitheredSpan565<'_>,
) -> usize {
    // SAFETY: the function writes the `len` `u16`s from `pixels` (two at a time as a word at
    // 4-byte aligned addresses only, as ARMv6-M requires, one alone at 2 mod 4: the caller's
    // promise), reads the nine words of `span.steps` and writes `span.value`, uses its own stack
    // frame, and saves and restores every register the AAPCS asks it to.
    unsafe { embedded_raster_dithered_span_565_v6m(pixels, len, span) }
}

/// Whether the texels of `span` hold every index its masked loops form (`row | column ≤ rows |
/// x_mask`), so that they read nothing past them. The loops write `Rgb565` pixels as the raw
/// `u16`s they are.
#[inline(always)]
fn texels_cover(span: &MaskedSpan565<'_>) -> bool {
    // embedded-graphics' `Rgb565(RawU16(u16))`: one `u16`, whose raw bits are the colour's.
    const { assert!(core::mem::size_of::<Rgb565>() == 2 && core::mem::align_of::<Rgb565>() == 2) };
    ((span.rows | span.x_mask) as usize) < span.texels.len()
}

/// One pixel of the masked nearest loop, stored at `[r0, #$offset]`: r1 = x, r2 = y (scaled),
/// r3 = 2·x_mask, r4 = 2·rows, r5 = the texels, r8 / r9 = the steps; r6, r7 are clobbered.
macro_rules! masked_pixel {
    ($offset:literal) => {
        concat!(
            "asrs r6, r1, #15\n",
            "ands r6, r3\n",
            "asrs r7, r2, #15\n",
            "ands r7, r4\n",
            "orrs r6, r7\n",
            "ldrh r6, [r5, r6]\n",
            "strh r6, [r0, #",
            $offset,
            "]\n",
            "add r1, r8\n",
            "add r2, r9\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_masked_nearest_565_v6m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    ".p2align 2",
    ".global embedded_raster_masked_nearest_565_v6m",
    ".hidden embedded_raster_masked_nearest_565_v6m",
    ".type embedded_raster_masked_nearest_565_v6m,%function",
    ".thumb_func",
    // r0 = pixels (2-byte aligned), r1 = pixel count, r2 = texels, r3 = the walk: x, y,
    // x_mask, rows, dx, dy.
    "embedded_raster_masked_nearest_565_v6m:",
    "push {{r4-r7, lr}}",
    "mov r4, r8",
    "mov r5, r9",
    "push {{r4, r5}}",
    "mov r5, r2",
    // r12 = past the last pixel; nothing to draw for no pixels.
    "lsls r1, r1, #1",
    "beq 4f",
    "adds r1, r0, r1",
    "mov r12, r1",
    "ldm r3, {{r1, r2, r3, r4, r6, r7}}",
    "mov r8, r6",
    "mov r9, r7",
    "lsls r3, r3, #1",
    "lsls r4, r4, #1",
    // Into the four-pixel loop at its pixel m = (−count) mod 4, the pointer m pixels back (so
    // that the first pixel is stored at the first address and the passes end at the last):
    // r6 = 2m, a jump of 18m bytes from the loop's start, which the PC reads as (4 bytes past
    // the `add`): a pixel is nine instructions of 16 bits (ARMv6-M's only 32-bit ones are
    // `bl`, `mrs`, `msr` and the barriers).
    "mov r6, r12",
    "subs r6, r0, r6",
    "movs r7, #6",
    "ands r6, r7",
    "subs r0, r0, r6",
    "lsls r7, r6, #3",
    "adds r7, r7, r6",
    "add pc, r7",
    "nop",
    "3:",
    masked_pixel!("0"),
    masked_pixel!("2"),
    masked_pixel!("4"),
    masked_pixel!("6"),
    "adds r0, #8",
    "cmp r0, r12",
    "blo 3b",
    "4:",
    "pop {{r4, r5}}",
    "mov r8, r4",
    "mov r9, r5",
    "pop {{r4-r7, pc}}",
    ".size embedded_raster_masked_nearest_565_v6m, . - embedded_raster_masked_nearest_565_v6m",
);

extern "C" {
    /// The masked nearest loop above.
    ///
    /// # Safety
    ///
    /// `pixels` must be valid for writes of `len` consecutive, 2-byte aligned `u16`s, `walk`
    /// for reads of six aligned `u32`s, and `texels` for reads of the `u16`s at every index
    /// `i ≤ rows | x_mask` (`walk`'s third and fourth words, each below 2³⁰).
    fn embedded_raster_masked_nearest_565_v6m(
        pixels: *mut u16,
        len: usize,
        texels: *const u16,
        walk: *const [u32; 6],
    );
}

/// Fills `pixels` with the texels of `span` (see [`MaskedSpan565`]): pixel `i` gets the raw
/// word `texels[row | column]` of its coordinate, as the portable masked nearest loop gives it.
/// `false` without drawing anything if a masked index could reach past the texels, so no input
/// reads or writes out of bounds.
#[inline(always)]
pub(crate) fn masked_nearest_565(pixels: &mut [Rgb565], span: &MaskedSpan565<'_>) -> bool {
    if !texels_cover(span) {
        return false;
    }
    let walk = [
        span.x.0 as u32,
        span.y.0 as u32,
        span.x_mask,
        span.rows,
        span.x.1 as u32,
        span.y.1 as u32,
    ];
    // SAFETY: the function writes exactly `pixels.len()` consecutive 2-byte aligned `u16`s from
    // the slice's start, which are the slice's pixels (an `Rgb565` is one `u16`, any bits a
    // colour; the first pass's stores before the start are jumped over, its pointer m pixels
    // back only an address), and reads the six words of `walk` and texels at byte offsets
    // `((y >> 15) & 2·rows) | ((x >> 15) & 2·x_mask)`: even and at most `2·(rows | x_mask)`, so the `u16`
    // at index `rows | x_mask < texels.len()` or below (the masks are below `texels.len() < 2³⁰`, so
    // doubling them does not overflow). It saves and restores every register the AAPCS asks
    // it to.
    unsafe {
        embedded_raster_masked_nearest_565_v6m(
            pixels.as_mut_ptr().cast(),
            pixels.len(),
            span.texels.as_ptr(),
            &walk,
        );
    }
    true
}

/// One depth-tested pixel of the masked nearest loop at `[r0, #$offset]` (colour) and
/// `[r1, #$offset]` (depth): r2 = x, r3 = y (scaled), r4 = 2·x_mask, r5 = 2·rows, r8 = the
/// texels, r9 = z, r10 / r11 / r12 = the steps of x, y and z; r6, r7 are clobbered. Drawn where
/// `z >> 16` is below the stored depth, compared as `z < depth << 16` (the same order for
/// every `z` and 16-bit depth). The same number of instructions whatever the offset: the
/// loop's computed jump counts on it.
macro_rules! depth_masked_pixel {
    ($offset:literal) => {
        concat!(
            "ldrh r6, [r1, #",
            $offset,
            "]\n",
            "lsls r6, r6, #16\n",
            "cmp r9, r6\n",
            "bhs 5f\n",
            "mov r6, r9\n",
            "lsrs r6, r6, #16\n",
            "strh r6, [r1, #",
            $offset,
            "]\n",
            "asrs r6, r2, #15\n",
            "ands r6, r4\n",
            "asrs r7, r3, #15\n",
            "ands r7, r5\n",
            "orrs r6, r7\n",
            "add r6, r8\n",
            "ldrh r6, [r6]\n",
            "strh r6, [r0, #",
            $offset,
            "]\n",
            "5:\n",
            "add r2, r10\n",
            "add r3, r11\n",
            "add r9, r12\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_depth_masked_565_v6m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    ".p2align 2",
    ".global embedded_raster_depth_masked_565_v6m",
    ".hidden embedded_raster_depth_masked_565_v6m",
    ".type embedded_raster_depth_masked_565_v6m,%function",
    ".thumb_func",
    // r0 = pixels, r1 = depths (both 2-byte aligned), r2 = pixel count, r3 = the walk: dx, dy,
    // texels, z, dz, x, y, x_mask, rows.
    "embedded_raster_depth_masked_565_v6m:",
    save_registers!(),
    // lr = past the last pixel; nothing to draw for no pixels.
    "lsls r2, r2, #1",
    "beq 4f",
    "adds r2, r0, r2",
    "mov lr, r2",
    "ldm r3!, {{r4, r5, r6, r7}}",
    "mov r10, r4",
    "mov r11, r5",
    "mov r8, r6",
    "mov r9, r7",
    "ldm r3!, {{r4}}",
    "mov r12, r4",
    "ldm r3, {{r2, r3, r4, r5}}",
    "lsls r4, r4, #1",
    "lsls r5, r5, #1",
    // Into the four-pixel loop at its pixel m = (−count) mod 4, both pointers m pixels back:
    // r6 = 2m, a jump of 36m bytes (a pixel is eighteen 16-bit instructions) from the loop's
    // start, which the PC reads as 4 bytes past the `add`.
    "mov r6, lr",
    "subs r6, r0, r6",
    "movs r7, #6",
    "ands r6, r7",
    "subs r0, r0, r6",
    "subs r1, r1, r6",
    "lsls r7, r6, #4",
    "lsls r6, r6, #1",
    "adds r7, r7, r6",
    "add pc, r7",
    "nop",
    "3:",
    depth_masked_pixel!("0"),
    depth_masked_pixel!("2"),
    depth_masked_pixel!("4"),
    depth_masked_pixel!("6"),
    "adds r0, #8",
    "adds r1, #8",
    "cmp r0, lr",
    "blo 3b",
    "4:",
    restore_registers!(),
    ".size embedded_raster_depth_masked_565_v6m, . - embedded_raster_depth_masked_565_v6m",
);

extern "C" {
    /// The depth-tested masked nearest loop above.
    ///
    /// # Safety
    ///
    /// `pixels` and `depths` must each be valid for reads and writes of `len` consecutive,
    /// 2-byte aligned `u16`s, `walk` for reads of nine aligned `u32`s, and `texels` (its third
    /// word) for reads of the `u16`s at every index `i ≤ rows | x_mask` (its last two words,
    /// each below 2³⁰).
    fn embedded_raster_depth_masked_565_v6m(
        pixels: *mut u16,
        depths: *mut u16,
        len: usize,
        walk: *const [u32; 9],
    );
}

/// Draws the pixels of `span` (see [`MaskedSpan565`]) into `pixels` where they are nearer than
/// `depths`: pixel `i`, at depth `(z + i·dz) >> 16` for `depth = (z, dz)` (wrapping), is drawn
/// where that is below `depths[i]`, which it then replaces, with the raw word
/// `texels[row | column]` of its coordinate, as the portable depth-tested loop draws it.
/// `false` without drawing anything if a masked index could reach past the texels, so no input
/// reads or writes out of bounds.
#[inline(always)]
pub(crate) fn depth_masked_nearest_565(
    pixels: &mut [Rgb565],
    depths: &mut [u16],
    span: &MaskedSpan565<'_>,
    (z, dz): (u32, u32),
) -> bool {
    if !texels_cover(span) {
        return false;
    }
    let walk = [
        span.x.1 as u32,
        span.y.1 as u32,
        span.texels.as_ptr() as u32,
        z,
        dz,
        span.x.0 as u32,
        span.y.0 as u32,
        span.x_mask,
        span.rows,
    ];
    // SAFETY: the function reads and writes `min(pixels.len(), depths.len())` consecutive
    // 2-byte aligned `u16`s from each slice's start, which are the slices' own (an `Rgb565` is
    // one `u16`, any bits a colour; the first pass's accesses before the starts are jumped
    // over, its pointers m pixels back only addresses), reads the nine words of `walk`, and
    // reads texels at byte offsets `((y >> 15) & 2·rows) | ((x >> 15) & 2·x_mask)`: even and at
    // most `2·(rows | x_mask)`, so the `u16` at index `rows | x_mask < texels.len()` or below (the masks are below
    // `texels.len() < 2³⁰`, so doubling them does not overflow). It saves and restores every
    // register the AAPCS asks it to.
    unsafe {
        embedded_raster_depth_masked_565_v6m(
            pixels.as_mut_ptr().cast(),
            depths.as_mut_ptr(),
            pixels.len().min(depths.len()),
            &walk,
        );
    }
    true
}

/// Two 5-6-5 pixels in r2 (the right one in the high half) under the constant colour: r1 =
/// `256 − w`, r8, r9, r10 = the top, middle and bottom fields' `s·w + 128` (each in both
/// halves of its word), r5 = 0x001F001F, r6 = 0x003F003F, r7 = 0xF800F800; r3 and r4 are
/// clobbered. Each field of both pixels is one multiply and one add of a lane pair (every lane
/// below 2¹⁶), its blended value bits 8 and up of its lane: the top ones shifted into place and
/// masked, the middle ones masked and shifted, the bottom ones masked.
macro_rules! blend_pair_v6m {
    () => {
        "lsrs r3, r2, #11\nands r3, r5\nmuls r3, r1, r3\nadd r3, r8\nlsls r3, r3, #3\n\
         ands r3, r7\n\
         lsrs r4, r2, #5\nands r4, r6\nmuls r4, r1, r4\nadd r4, r9\nlsrs r4, r4, #8\n\
         ands r4, r6\nlsls r4, r4, #5\norrs r3, r4\n\
         ands r2, r5\nmuls r2, r1, r2\nadd r2, r10\nlsrs r2, r2, #8\nands r2, r5\norrs r2, r3"
    };
}

/// One word of the blend loop: two pixels at r0 blended ([`blend_pair_v6m`]) and stored, r0
/// advanced past them. The same length every time: the loop's computed jump counts on it.
macro_rules! blend_word_v6m {
    () => {
        concat!("ldr r2, [r0]\n", blend_pair_v6m!(), "\nstm r0!, {{r2}}")
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_blend_565_v6m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    ".p2align 2",
    ".global embedded_raster_blend_565_v6m",
    ".hidden embedded_raster_blend_565_v6m",
    ".type embedded_raster_blend_565_v6m,%function",
    ".thumb_func",
    // r0 = pixels (2-byte aligned), r1 = pixel count, r2 = the weights: 256 − w and the top,
    // middle and bottom fields' s·w + 128 in both halves.
    "embedded_raster_blend_565_v6m:",
    "lsls r1, r1, #1",
    "bne 0f",
    "bx lr",
    "0:",
    "push {{r4-r7, lr}}",
    "mov r4, r8",
    "mov r5, r9",
    "mov r6, r10",
    "push {{r4-r6}}",
    // r12 = past the last pixel.
    "adds r1, r0, r1",
    "mov r12, r1",
    "ldm r2!, {{r1, r3, r4, r5}}",
    "mov r8, r3",
    "mov r9, r4",
    "mov r10, r5",
    "ldr r5, 6f",
    "ldr r6, 7f",
    "ldr r7, 8f",
    // A first pixel at an address of 2 mod 4 alone.
    "lsls r3, r0, #30",
    "bpl 1f",
    "ldrh r2, [r0]",
    blend_pair_v6m!(),
    "strh r2, [r0]",
    "adds r0, #2",
    "1:",
    // lr = the end of the words; four a pass, the first pass entered at the word that leaves
    // a multiple of four: m = (−words) mod 4, a jump of 44m bytes from the loop's start (a word
    // is 22 instructions of 16 bits), which the PC reads as 4 bytes past the `add`.
    "mov r3, r12",
    "lsrs r3, r3, #2",
    "lsls r3, r3, #2",
    "mov lr, r3",
    "subs r3, r3, r0",
    "beq 4f",
    "rsbs r3, r3, #0",
    "movs r4, #12",
    "ands r3, r4",
    "lsls r4, r3, #3",
    "adds r4, r4, r3",
    "lsls r3, r3, #1",
    "adds r4, r4, r3",
    "add pc, r4",
    "nop",
    "3:",
    blend_word_v6m!(),
    blend_word_v6m!(),
    blend_word_v6m!(),
    blend_word_v6m!(),
    "cmp r0, lr",
    "blo 3b",
    // A last pixel alone.
    "4:",
    "cmp r0, r12",
    "bhs 5f",
    "ldrh r2, [r0]",
    blend_pair_v6m!(),
    "strh r2, [r0]",
    "5:",
    "pop {{r4-r6}}",
    "mov r8, r4",
    "mov r9, r5",
    "mov r10, r6",
    "pop {{r4-r7, pc}}",
    ".p2align 2",
    "6: .word 0x001F001F",
    "7: .word 0x003F003F",
    "8: .word 0xF800F800",
    ".size embedded_raster_blend_565_v6m, . - embedded_raster_blend_565_v6m",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_blend_565_v6m(pixels: *mut u16, len: usize, weights: *const [u32; 4]);
}

/// Blends the constant colour of `weights` over every pixel of `pixels`, 5-6-5 colours (one
/// `u16` each, every raw value a colour: `C: From<RawU16>`): `weights` are `256 − w` and the
/// raw top, middle and bottom fields' `s·w + 128`, each in both halves of its word (`s·w + 128
/// ≤ 63·256 + 128`). Each field becomes `(pre + d·(256 − w)) >> 8`, as `color::blend`'s
/// portable loop gives it. `false` without writing anything if `C` is not a 16-bit colour.
#[inline(always)]
pub(crate) fn blend_solid_565<C: From<RawU16>>(pixels: &mut [C], weights: &[u32; 4]) -> bool {
    if core::mem::size_of::<C>() != 2 || core::mem::align_of::<C>() != 2 {
        return false;
    }
    // SAFETY: the function reads and writes exactly `pixels.len()` consecutive 2-byte aligned
    // `u16`s from the slice's start, which are the slice's own (a 5-6-5 colour is one `u16`,
    // any bits a colour), words only at 4-byte aligned addresses (as ARMv6-M requires), and
    // reads the four words of `weights`. It saves and restores every register the AAPCS asks
    // it to.
    unsafe { embedded_raster_blend_565_v6m(pixels.as_mut_ptr().cast(), pixels.len(), weights) }
    true
}

// The per-vertex alpha blend of a 5-6-5 span ([`premultiplied_565`]), one pixel a pass:
// r0 = the end of the span, r1 = the byte offset of the pixel from it (negative, counting up to
// 0), r2 = the top plane, r3 = the factor `f·2¹⁰`, r4-r6 = the pixel and its channels, r7 = the
// transparency plane; r9, r10 = the middle and bottom planes (the colour planes in raw order,
// scaled by 4, 4 and 8), r11, r12, lr = the colour planes' steps, r8 the transparency plane's.
// 31 instructions a pixel.
core::arch::global_asm!(
    ".section .text.embedded_raster_premultiplied_565_v6m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    ".p2align 2",
    ".global embedded_raster_premultiplied_565_v6m",
    ".hidden embedded_raster_premultiplied_565_v6m",
    ".type embedded_raster_premultiplied_565_v6m,%function",
    ".thumb_func",
    // r0 = the pixels, r1 = their number (at least one), r2 = the planes' values then steps.
    "embedded_raster_premultiplied_565_v6m:",
    save_registers!(),
    "ldm r2!, {{r3-r6}}",
    "mov r9, r4",
    "mov r10, r5",
    "mov r7, r6",
    "ldm r2, {{r2, r4, r5, r6}}",
    "mov r11, r2",
    "mov r12, r4",
    "mov lr, r5",
    "mov r8, r6",
    "mov r2, r3",
    "lsls r1, r1, #1",
    "adds r0, r0, r1",
    "rsbs r1, r1, #0",
    "1:",
    "ldrh r6, [r0, r1]",
    // The factor ((t >> 9)·257) >> 15, times 2¹⁰.
    "lsrs r3, r7, #9",
    "lsls r4, r3, #8",
    "adds r3, r3, r4",
    "lsrs r3, r3, #15",
    "lsls r3, r3, #10",
    // Top: d_top·f·2¹⁰ + plane (scaled by 4: the channel at bits 26-30).
    "lsrs r4, r6, #11",
    "muls r4, r3, r4",
    "adds r4, r4, r2",
    // Middle: d_mid·f·2¹⁰ + plane (scaled by 4: the channel at bits 26-31).
    "lsls r5, r6, #21",
    "lsrs r5, r5, #26",
    "muls r5, r3, r5",
    "add r5, r9",
    // Bottom: d_bottom·2·f·2¹⁰ + plane (scaled by 8: the channel at bits 27-31).
    "lsls r6, r6, #27",
    "lsrs r6, r6, #26",
    "muls r6, r3, r6",
    "add r6, r10",
    // Packed: ((top << 6 | middle) << 5) | bottom (bit 31 of the top sum, not the channel's,
    // lands at bit 16: not stored).
    "lsrs r4, r4, #26",
    "lsls r4, r4, #6",
    "lsrs r5, r5, #26",
    "orrs r4, r5",
    "lsls r4, r4, #5",
    "lsrs r6, r6, #27",
    "orrs r4, r6",
    "strh r4, [r0, r1]",
    "add r2, r11",
    "add r9, r12",
    "add r10, lr",
    "add r7, r8",
    "adds r1, #2",
    "bne 1b",
    restore_registers!(),
    ".size embedded_raster_premultiplied_565_v6m, . - embedded_raster_premultiplied_565_v6m",
);

extern "C" {
    /// The assembly function above.
    ///
    /// # Safety
    ///
    /// `pixels` must be valid for reads and writes of `len` (at least one) consecutive, 2-byte
    /// aligned `u16`s, and `planes` for reads of eight aligned `u32`s.
    fn embedded_raster_premultiplied_565_v6m(pixels: *mut u16, len: usize, planes: *const [u32; 8]);
}

/// The per-vertex alpha blend over the 5-6-5 pixels `pixels` (nothing if `C` is not a 16-bit
/// colour): pixel `i` is `color::blend`'s `premultiplied_pixel_v6m` of its raw value with the
/// planes `value` (raw order: top, middle, bottom field, then transparency; unscaled) stepped
/// `i` times by `step`, wrapping.
#[inline(always)]
pub(crate) fn premultiplied_565<C>(pixels: &mut [C], value: [u32; 4], step: [u32; 4]) {
    if core::mem::size_of::<C>() != 2 || core::mem::align_of::<C>() != 2 || pixels.is_empty() {
        return;
    }
    // The planes scaled as the loop wants them (each channel's bits 0-28 or 0-29 kept: the
    // channel depends on no others).
    let scaled = |v: [u32; 4]| [v[0] << 2, v[1] << 2, v[2] << 3, v[3]];
    let (value, step) = (scaled(value), scaled(step));
    let planes = [
        value[0], value[1], value[2], value[3], step[0], step[1], step[2], step[3],
    ];
    // SAFETY: `pixels` holds `pixels.len()` (at least one) 2-byte aligned 16-bit colours (checked
    // above), which the function reads and writes as `u16`s, one at a time; it reads the eight
    // words of `planes` and saves and restores every register the AAPCS asks it to.
    unsafe {
        embedded_raster_premultiplied_565_v6m(pixels.as_mut_ptr().cast(), pixels.len(), &planes)
    };
}
