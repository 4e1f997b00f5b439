//! ARMv7-M (Cortex-M3/M4/M7, and ARMv8-M Mainline: Cortex-M33 and after): the rows of a small depth-tested triangle with interpolated light
//! levels (the 3D pipeline's Gouraud fill) in Thumb-2 assembly, and the span loops of the
//! textured fills, of a constant colour blended at a constant opacity into 5-6-5 pixels and of
//! dithered 5-6-5 spans.
//!
//! The blend loop ([`blend_solid_565`]): LLVM unrolls the portable pair loop but reloads its
//! lanes from the stack. Here two pixels (a word) are 10 instructions on ARMv7E-M (11 on the
//! Cortex-M3, without `uxtb16`), every constant in a register, eight pixels a pass with one
//! `ldm` and one `stm`. It gives the portable loop's integers (every lane below 2¹⁶); CI checks
//! the M3 and M4 scenes' translucent triangles against the host's checksums.
//!
//! The dithered 5-6-5 span ([`dithered_565`]): the portable pairs (`color::packed565`'s
//! `dithered_run_565`) need fifteen registers, two word streams with their steps and the masks,
//! and LLVM spilled them (35 instructions for four pixels and about 100 a run of 32). Here four
//! pixels are 21 instructions, the bottom lanes' step reloaded from the frame, and the span's
//! test (its values at both ends inside the channels' ranges, in 64 bits), its constants and
//! each run's restart are in the same function. The integers of the portable loop; CI checks
//! the scene's dithered triangles and its random dithered spans (at and across the test's
//! limits) on every ARMv7-M board against the host's checksums.
//!
//! The DSP extension's code (`arm_dsp`: ARMv7E-M, and ARMv8-M Mainline with the `dsp` feature)
//! is in blocks that name the extension to the assembler (`dsp_directive!`) where the target
//! does not have it; CI runs it on the Cortex-M4 and on the Cortex-M33 with the feature.
//!
//! The triangles of a 3D mesh cover a few pixels each: spans of one or two pixels on four rows.
//! LLVM's code for them keeps the row state on the stack (it needs more registers than there
//! are), recomputes each span's slices and bounds and unrolls the pixel loop for long spans —
//! about 90 instructions a span beyond its pixels. Here the whole row loop is one function: the
//! three edge numerators and the row count stay in registers, the rest of a row's state is
//! loaded and stored with one `ldm`/`stm`, a row's run is three `sdiv`s (the division form of
//! the raster core's `RowRuns`), and a pixel is 12 instructions (7 where the depth test fails).
//!
//! It computes what the portable path (`RowRuns::run` and the depth fill's span loop with the
//! `Leveled` pixel) computes from the same integers: the same runs (a bound the portable code
//! reads as `⌊max(n, 0)/d⌋` is `sdiv`'s truncated `n/d` here, equal for `n > 0`; for `n ≤ 0` a
//! start bound is raised to 0 in both, and an end bound makes the run empty in both), the same
//! depth `z >> 16` tested and written where it is below the stored one, the same colour
//! `table[l >> 24]`, the planes stepped by the same wrapping additions (a span's first values
//! by `mla`, the wrapping `value + step·start`). The host tests the portable path; CI checks that
//! the Cortex-M3 and M4 firmware frames have the host's checksums.
//!
//! Bilinear texels (ARMv7E-M, [`bilinear_texel`]): the row loop and the perspective span loop
//! have variants that blend the four texels around the point with the DSP extension's dual
//! 16-bit products — a row's two texels are the halves of one word, their 7-bit-fraction
//! weights the halves of another — 57 instructions a drawn pixel; the integers of the portable
//! `texture::map::bilinear_by`, checked by `fw_texture_bench`'s random faces on the M4.
//!
//! The vertex stage ([`project_positions`]): LLVM keeps the sixteen matrix entries of the
//! transform on the stack and rounds each row apart (about 188 instructions a vertex); here a
//! row is one `ldm` of its entries and a 64-bit bias that carries its translation and rounding,
//! and three `smlal`, and the whole vertex 94 instructions. The integers of the portable
//! `direct_row` and `project_inverse`, which `fw_mesh_bench`'s depths frame checks vertex by
//! vertex on the boards.
//!
//! The face scan ([`scan_faces`]): LLVM's face loop took about 75 instructions a face up to the
//! cull, and the Rust around a kept face's set-up (the sink's plumbing, the face's record, the
//! buffer checks, the texel products) about 150 more. Here one loop decides each face from its
//! indices, clip codes and doubled area in 39, and calls the level or textured set-up on a kept
//! face itself; the pipeline gets back only the faces it must clip or fill otherwise. Its
//! verdicts are the portable `verdict`'s, which `fw_mesh_bench`'s frame counts check.
//!
//! The blend of an alpha per vertex over 5-6-5 pixels ([`premultiplied_pairs_565`]): LLVM
//! unrolls the portable pair loop and spills its planes (fw_bench: 43.18 instructions a pixel,
//! 33.42 pixel by pixel through the channels); here a pair of pixels is one word loaded and
//! stored and 43 instructions, the four planes and their steps in registers, and a first pixel
//! at 2 mod 4 and a last odd one are blended alone by the same function (23.62 a pixel). It computes `color::blend`'s `premultiplied_pixel_565` for each pixel,
//! which the host tests against the per-pixel definition; CI checks that the firmware's scene
//! (which blends such a triangle) has the host's checksum.
#![allow(unsafe_code)]

use super::DitheredSpan565;

use core::mem::MaybeUninit;

use embedded_graphics::pixelcolor::raw::RawU16;

#[cfg(arm_dsp)]
use super::MaskedSpan565;
use super::{FaceScan, ModelPosition, ProjectedPrefix, ProjectionBlock, FACE_BATCH};
use super::{FaceSetup, LevelBlock, LevelFace, LevelRows, PerspectiveSpan565, SmallSetup};
use super::{TexturedDraw, TexturedFace, TexturedFaces, TexturedRows, TexturedTemplate};
use super::{BILINEAR_ROWS, SCANNED_PERSPECTIVE};
use super::{SCANNED_CLIPPED, SCANNED_INVALID, SCANNED_KEPT};

/// The assembler directive that lets a block use the DSP extension's instructions where the
/// target itself does not have them (ARMv8-M Mainline, whose DSP extension is optional, with the
/// crate's `dsp` feature: the user's promise that the core has it); none elsewhere. LLVM's
/// assembler knows no `.arch_extension dsp`; the Cortex-M33 is the ARMv8-M Mainline core with
/// it, and its instructions are encoded alike on the later cores (M35P, M55, M85).
#[cfg(all(arm_dsp, armv8m))]
macro_rules! dsp_directive {
    () => {
        ".cpu cortex-m33"
    };
}
#[cfg(not(all(arm_dsp, armv8m)))]
macro_rules! dsp_directive {
    () => {
        ""
    };
}

/// The clamp of a row's run to the region's columns, start ≥ 0 and end ≤ columns (the word at
/// `$columns` of the block in r0), for runs `$start..$end` (`$t` scratch). A run that is not
/// empty needs it only where the clip cut columns off the region (see [`face_scan`]).
#[rustfmt::skip]
macro_rules! clamped_run {
    ($start:literal, $end:literal, $t:literal, $columns:literal) => {
        concat!(
            "bic ", $start, ", ", $start, ", ", $start, ", asr #31\n",
            "ldr ", $t, ", [r0, #", $columns, "]\n",
            "cmp ", $end, ", ", $t, "\n",
            "it gt\n",
            "movgt ", $end, ", ", $t, "\n",
        )
    };
}

/// One row of the loop, `$middle` folding the middle bound (r12) into the start (r10) or the end
/// (r11), `$clamp` the clamp to the columns (or none). Registers: r0 = the block, r1-r3 = the
/// numerators, lr = rows left; the rest are free.
macro_rules! level_row {
    ($middle:literal, $clamp:expr) => {
        concat!(
            // The run: three divisions (start ≥ 0, end ≤ columns).
            "ldrd r7, r8, [r0, #36]\n",
            "ldr r9, [r0, #44]\n",
            "sdiv r10, r1, r7\n",
            "sdiv r11, r3, r9\n",
            "sdiv r12, r2, r8\n",
            $clamp,
            $middle,
            "\n",
            "cmp r11, r10\n",
            "ble 3f\n",
            // The span: r4 = depth, r5 = level at its first pixel, r6 = its depth pointer, r9 =
            // past its last, r7/r8 = the column steps, r10 = the table, r11 = the colour offset.
            "ldm r0, {{r4, r5, r6}}\n",
            "ldrd r7, r8, [r0, #52]\n",
            "mla r4, r7, r10, r4\n",
            "mla r5, r8, r10, r5\n",
            "add r9, r6, r11, lsl #1\n",
            "add r6, r6, r10, lsl #1\n",
            "ldrd r10, r11, [r0, #60]\n",
            // The pixels, the planes stepped between them (not past the last).
            "b 8f\n",
            "2:\n",
            "add r4, r7\n",
            "add r5, r8\n",
            "8:\n",
            "ldrh r12, [r6], #2\n",
            "cmp r12, r4, lsr #16\n",
            "bls 4f\n",
            "lsr r12, r4, #16\n",
            "strh r12, [r6, #-2]\n",
            "lsr r12, r5, #24\n",
            "ldrh r12, [r10, r12, lsl #1]\n",
            "strh r12, [r6, r11]\n",
            "4:\n",
            "cmp r6, r9\n",
            "blo 2b\n",
            // The next row, if any (to 9 if none).
            "3:\n",
            "subs lr, #1\n",
            "beq 9f\n",
            "ldm r0, {{r4, r5, r6}}\n",
            "add r7, r0, #12\n",
            "ldm r7, {{r7, r8, r9, r10, r11, r12}}\n",
            "add r4, r7\n",
            "add r5, r8\n",
            "add r6, r9\n",
            "stm r0, {{r4, r5, r6}}\n",
            "add r1, r10\n",
            "add r2, r11\n",
            "add r3, r12\n",
        )
    };
}

/// The level row loop's function body (r0 = the block, r1 = whether the middle bound is a start
/// bound), each run clamped by `$clamp`.
macro_rules! level_rows_body {
    ($clamp:expr) => {
        concat!(
            "push {{r4-r11, lr}}\n",
            // The colour pointer as an offset from the depth pointer after its post-increment.
            "ldr r2, [r0, #8]\n",
            "ldr r3, [r0, #64]\n",
            "sub r3, r3, r2\n",
            "sub r3, r3, #2\n",
            "str r3, [r0, #64]\n",
            "add r12, r0, #68\n",
            "cmp r1, #0\n",
            "beq 5f\n",
            "ldm r12, {{r1, r2, r3, lr}}\n",
            "1:\n",
            level_row!("cmp r12, r10\nit gt\nmovgt r10, r12", $clamp),
            "b 1b\n",
            "9:\n",
            "pop {{r4-r11, pc}}\n",
            "5:\n",
            "ldm r12, {{r1, r2, r3, lr}}\n",
            "6:\n",
            level_row!("cmp r12, r11\nit lt\nmovlt r11, r12", $clamp),
            "b 6b\n",
            "9:\n",
            "pop {{r4-r11, pc}}\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_level_rows_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_level_rows_v7m",
    ".hidden embedded_raster_level_rows_v7m",
    ".type embedded_raster_level_rows_v7m,%function",
    ".thumb_func",
    // r0 = the block, r1 = whether the middle bound is a start bound.
    "embedded_raster_level_rows_v7m:",
    level_rows_body!(clamped_run!("r10", "r11", "r9", "48")),
    ".size embedded_raster_level_rows_v7m, . - embedded_raster_level_rows_v7m",
);

// The same rows where no run needs the clamp to the columns (the clip cut none off the region:
// `face_scan`'s word).
core::arch::global_asm!(
    ".section .text.embedded_raster_level_rows_inside_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_level_rows_inside_v7m",
    ".hidden embedded_raster_level_rows_inside_v7m",
    ".type embedded_raster_level_rows_inside_v7m,%function",
    ".thumb_func",
    "embedded_raster_level_rows_inside_v7m:",
    level_rows_body!(""),
    ".size embedded_raster_level_rows_inside_v7m, . - embedded_raster_level_rows_inside_v7m",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_level_rows_v7m(block: *mut LevelBlock, middle_starts: u32);
}

/// Draws the rows `rows` into `colors` and `depths` (row-major, `rows.width` pixels a row):
/// where a pixel of a row's run is nearer than `depths` holds, its depth and the colour of its
/// level from `table`. `false` without drawing anything if the region is not inside both buffers
/// (or `C` is not a 16-bit colour), so no input writes outside them.
#[inline(always)]
pub(crate) fn level_rows<C: Copy>(
    colors: &mut [C],
    depths: &mut [u16],
    rows: &LevelRows,
    table: &[C; 256],
) -> bool {
    let Some(mut block) = LevelBlock::new(colors, depths, rows, table) else {
        return false;
    };
    // SAFETY: the function writes only pixels of the region — rows `0..rows` from the first
    // pixel, `width` pixels apart, each in columns `start..end` with `0 ≤ start` and
    // `end ≤ columns` — which are inside both buffers (checked above), as 2-byte aligned `u16`s
    // (`C` is a 2-byte colour: a copy of the table's bytes is a copy of its colours). It reads
    // the table at `level >> 24 < 256`, reads and writes the block (its own), divides by the
    // non-zero divisors only, and saves and restores every register the AAPCS asks it to.
    unsafe { embedded_raster_level_rows_v7m(&mut block, u32::from(rows.middle_starts)) };
    true
}

/// What the textured row loop reads and updates: `TexturedRows` as pointers, the per-row state
/// first (offsets in the comments are the assembly's).
#[repr(C)]
struct TexturedBlock {
    /// 0-12: depth, `u`, `v` and level plane values at the row's first column; 16: the depth
    /// pointer there; 20-28: the bounds' numerators at the row.
    row: [u32; 5],
    numerators: [i32; 3],
    /// 32-60: their steps a row (the pointer's in bytes).
    row_steps: [u32; 5],
    numerator_steps: [i32; 3],
    /// 64-72: the divisors; 76: the region's columns.
    divisors: [u32; 3],
    columns: u32,
    /// 80-92: the four planes' steps a column.
    column_steps: [u32; 4],
    /// 96, 100: `u`'s map (base, down); 104, 108: `v`'s; 112: `y`'s shift.
    map_u: [u32; 2],
    map_v: [u32; 2],
    y_shift: u32,
    /// 116, 120: the texel steps a pixel (`y`'s shifted).
    texel_steps: [i32; 2],
    /// 124: the colour pointer's offset from the depth pointer, in bytes (wrapping).
    color_offset: u32,
    /// 128: rows left (at least one).
    rows: u32,
    /// 132: the texels; 136: the column mask; 140: the row mask.
    texels: *const u16,
    x_mask: u32,
    rows_mask: u32,
}

const _: () = assert!(core::mem::size_of::<TexturedBlock>() == 144);

/// The rows of the textured loop. `$middle` folds the middle bound (r2) into the start (r1) or
/// the end (r3); `$pixel` steps the planes to the pixel at r8 (the negative byte offset from the
/// run's end; entered at its label 8 for the run's first pixel) and draws it; `$offset` moves a
/// run's first coordinates (r5, r6: `y` before its shift) where the pixel wants them moved;
/// `$frame` is the bytes of the stack frame below the saved registers; `$clamp` clamps a run to
/// the region's columns ([`clamped_run`] by default, none where the clip cut none off). The block's pointer is at [sp, #16]; the per-pixel steps at [sp] (depth,
/// `x`, `y`, level); r11 = the texels, r12 = the column mask, lr = the row mask throughout.
macro_rules! textured_rows {
    ($middle:literal, $pixel:expr) => {
        textured_rows!($middle, $pixel, "", "20")
    };
    ($middle:literal, $pixel:expr, $offset:expr, $frame:literal) => {
        textured_rows!(
            $middle,
            $pixel,
            $offset,
            $frame,
            clamped_run!("r1", "r3", "r4", "76")
        )
    };
    ($middle:literal, $pixel:expr, $offset:expr, $frame:literal, $clamp:expr) => {
        concat!(
            "ldr r0, [sp, #16]\n",
            "ldr r6, [r0, #20]\n",
            "ldrd r7, r8, [r0, #24]\n",
            // The run (the block in r0, the numerators in r6-r8, as the step to the next row
            // leaves them): three divisions (`$clamp`: start ≥ 0, end ≤ columns).
            "1:\n",
            "ldrd r2, r3, [r0, #64]\n",
            "ldr r4, [r0, #72]\n",
            "sdiv r1, r6, r2\n",
            "sdiv r2, r7, r3\n",
            "sdiv r3, r8, r4\n",
            $clamp,
            $middle,
            "\n",
            "cmp r3, r1\n",
            "ble 3f\n",
            // The planes at the run's first pixel (r4-r7), the depth and colour pointers past its
            // end (r9, r10), minus its length (r8).
            "ldm r0, {{r4, r5, r6, r7, r9}}\n",
            "ldrd r2, r8, [r0, #80]\n",
            "mla r4, r2, r1, r4\n",
            "mla r5, r8, r1, r5\n",
            "ldrd r2, r8, [r0, #88]\n",
            "mla r6, r2, r1, r6\n",
            "mla r7, r8, r1, r7\n",
            "subs r8, r1, r3\n",
            "add r9, r9, r3, lsl #1\n",
            "ldr r2, [r0, #124]\n",
            "add r10, r9, r2\n",
            // The texel steps: a run of two takes its second pixel's own coordinates.
            "cmn r8, #2\n",
            "beq 5f\n",
            "ldrd r1, r2, [r0, #116]\n",
            "strd r1, r2, [sp, #4]\n",
            "6:\n",
            // The coordinates: x (r5), y shifted (r6); r8 the byte offset.
            "ldrd r1, r2, [r0, #96]\n",
            "lsr r5, r5, r2\n",
            "add r5, r5, r1\n",
            "ldrd r1, r2, [r0, #104]\n",
            "lsr r6, r6, r2\n",
            "add r6, r6, r1\n",
            $offset,
            "ldr r1, [r0, #112]\n",
            "lsl r6, r6, r1\n",
            "lsl r8, r8, #1\n",
            // The pixels, the planes stepped between them (not past the last).
            "b 8f\n",
            "2:\n",
            $pixel,
            "adds r8, #2\n",
            "bne 2b\n",
            // The next row, if any: the planes, the depth pointer and the numerators (words
            // 0-7) stepped by words 8-15.
            "3:\n",
            "ldr r0, [sp, #16]\n",
            "ldr r1, [r0, #128]\n",
            "subs r1, #1\n",
            "beq 9f\n",
            "str r1, [r0, #128]\n",
            "ldm r0, {{r1-r8}}\n",
            "ldrd r9, r10, [r0, #32]\n",
            "add r1, r9\n",
            "add r2, r10\n",
            "ldrd r9, r10, [r0, #40]\n",
            "add r3, r9\n",
            "add r4, r10\n",
            "ldrd r9, r10, [r0, #48]\n",
            "add r5, r9\n",
            "add r6, r10\n",
            "ldrd r9, r10, [r0, #56]\n",
            "add r7, r9\n",
            "add r8, r10\n",
            "stm r0, {{r1-r8}}\n",
            "b 1b\n",
            "9:\n",
            "add sp, #",
            $frame,
            "\n",
            "pop {{r4-r11, pc}}\n",
            // A run of two: the steps to the second pixel's coordinates.
            "5:\n",
            "ldr r3, [r0, #100]\n",
            "ldr r1, [r0, #84]\n",
            "add r1, r1, r5\n",
            "lsr r1, r1, r3\n",
            "lsr r2, r5, r3\n",
            "sub r1, r1, r2\n",
            "str r1, [sp, #4]\n",
            "ldr r3, [r0, #108]\n",
            "ldr r1, [r0, #88]\n",
            "add r1, r1, r6\n",
            "lsr r1, r1, r3\n",
            "lsr r2, r6, r3\n",
            "sub r1, r1, r2\n",
            "ldr r3, [r0, #112]\n",
            "lsl r1, r1, r3\n",
            "str r1, [sp, #8]\n",
            "b 6b\n",
        )
    };
}

/// The depth test of the pixel at r8 (r9 the depth pointer, r4 the depth plane): to `$skip`
/// unless nearer than the stored depth, which it then replaces. Clobbers r0.
macro_rules! depth_test {
    ($skip:literal) => {
        concat!(
            "ldrh r0, [r9, r8]\n",
            "cmp r0, r4, lsr #16\n",
            "bls ",
            $skip,
            "\n",
            "lsr r0, r4, #16\n",
            "strh r0, [r9, r8]\n",
        )
    };
}

/// The depth test and the texel's index and fetch (into r0) of the pixel at r8 (r9 the depth
/// pointer, r4 the depth, r5/r6 = x/y, r12/lr their masks, r11 the texels); `$skip` the next
/// pixel. Clobbers r1.
macro_rules! textured_texel {
    ($skip:literal) => {
        concat!(
            depth_test!($skip),
            texel_index!(),
            "ldrh r0, [r11, r0, lsl #1]\n",
        )
    };
}

/// The storage index (into r0) of the texel at r5/r6 = x/y (`y` shifted), r12/lr their masks:
/// `row | column`. Clobbers r1.
macro_rules! texel_index {
    () => {
        concat!(
            "and r0, lr, r6, lsr #16\n",
            "and r1, r12, r5, lsr #16\n",
            "orr r0, r0, r1\n",
        )
    };
}

/// The texel (r0) with each 5-6-5 channel `c` scaled to `(c·f + 2¹⁵) >> 16` for `$f`, stored
/// at the lit loop's pixel. Clobbers r2, r3 (and r1 with the DSP extension).
#[cfg(not(arm_dsp))]
macro_rules! scaled_texel {
    ($f:literal) => {
        concat!(
            "mov r3, #32768\n",
            "and r2, r0, #31\n",
            "mla r2, r2, ",
            $f,
            ", r3\n",
            "bic r0, r0, #31\n",
            "orr r0, r0, r2, lsr #16\n",
            "ubfx r2, r0, #5, #6\n",
            "mla r2, r2, ",
            $f,
            ", r3\n",
            "lsr r2, r2, #16\n",
            "bfi r0, r2, #5, #6\n",
            "lsr r2, r0, #11\n",
            "mla r2, r2, ",
            $f,
            ", r3\n",
            "lsr r2, r2, #16\n",
            "bfi r0, r2, #11, #5\n",
            "strh r0, [r10, r8]\n",
        )
    };
}

/// The same with the DSP extension: `f·2⁵` into r1, then [`scaled_by_f5`].
#[cfg(arm_dsp)]
macro_rules! scaled_texel {
    ($f:literal) => {
        concat!("lsl r1, ", $f, ", #5\n", scaled_by_f5!())
    };
}

/// The texel (r0) with each 5-6-5 channel `c` scaled to `(c·f + 2¹⁵) >> 16` for r1 = `f·2⁵`
/// (`f` below 2²⁰), stored at the lit loop's pixel, by the DSP extension's rounded high
/// product: `smmulr` gives `(a·b + 2³¹) >> 32`, which for `a = c·2¹¹` and `b = f·2⁵` (or `c·2⁵`
/// and `f·2¹¹`: each below 2³¹, the product exact in 64 bits) is `(c·f + 2¹⁵) >> 16`. Each
/// result's bits past its field are dropped (by `bfi` and the halfword store; for the `f` of the
/// loops, at most `2¹⁶·257/256`, none are set). Clobbers r1-r3.
#[cfg(arm_dsp)]
macro_rules! scaled_by_f5 {
    () => {
        concat!(
            // Red (c·2¹¹ in place), blue (moved up to c·2¹¹), green (c·2⁵ in place, f·2¹¹).
            "and r2, r0, #0xF800\n",
            "smmulr r2, r2, r1\n",
            "lsl r3, r0, #27\n",
            "lsr r3, r3, #16\n",
            "smmulr r3, r3, r1\n",
            "and r0, r0, #0x7E0\n",
            "lsl r1, r1, #6\n",
            "smmulr r0, r0, r1\n",
            "bfi r3, r0, #5, #6\n",
            "bfi r3, r2, #11, #5\n",
            "strh r3, [r10, r8]\n",
        )
    };
}

/// An unlit pixel, the loop's body from the step to it (the planes stepped, entered at 8 for a
/// run's first pixel): the texel as it is (the nearest one, or `$texel`'s, which skips to 4).
macro_rules! unlit_pixel {
    () => {
        unlit_pixel!(textured_texel!("4f"))
    };
    ($texel:expr) => {
        concat!(
            "ldm sp, {{r0-r2}}\n",
            "add r4, r0\n",
            "add r5, r1\n",
            "add r6, r2\n",
            "8:\n",
            $texel,
            "strh r0, [r10, r8]\n",
            "4:\n",
        )
    };
}

/// The texel (r0) lit by the level plane (r7) and stored at the lit loop's pixel: `f = ((l >>
/// 12)·257) >> 12`, each channel `c` replaced by `(c·f + 2¹⁵) >> 16`, blue, green, red (each
/// result's bits past its field dropped, as `bfi` drops them). Clobbers r1-r3.
#[cfg(not(arm_dsp))]
macro_rules! lit_texel {
    () => {
        concat!(
            "lsr r1, r7, #12\n",
            "add r1, r1, r1, lsl #8\n",
            "lsr r1, r1, #12\n",
            scaled_texel!("r1"),
        )
    };
}

/// The same with the DSP extension: `f·2⁵` as the low five bits of `((l >> 12)·257) >> 7`
/// cleared, then [`scaled_by_f5`] (15 instructions where the `mla`s take 17).
#[cfg(arm_dsp)]
macro_rules! lit_texel {
    () => {
        concat!(
            "lsr r1, r7, #12\n",
            "add r1, r1, r1, lsl #8\n",
            "lsr r1, r1, #7\n",
            "bic r1, r1, #31\n",
            scaled_by_f5!(),
        )
    };
}

/// A pixel lit by the level plane (r7), the loop's body from the step to it (as
/// [`unlit_pixel`]'s): the texel (the nearest one, or `$texel`'s, which skips to 4) scaled by
/// [`lit_texel`].
macro_rules! lit_pixel {
    () => {
        lit_pixel!(textured_texel!("4f"))
    };
    ($texel:expr) => {
        lit_pixel!($texel, lit_texel!())
    };
    ($texel:expr, $lit:expr) => {
        concat!(
            "ldm sp, {{r0-r3}}\n",
            "add r4, r0\n",
            "add r5, r1\n",
            "add r6, r2\n",
            "add r7, r3\n",
            "8:\n",
            $texel,
            $lit,
            "4:\n",
        )
    };
}

/// The bilinear texel of the pixel at r8 into r0 (ARMv7E-M), after the depth test and write
/// (as [`textured_texel`]'s), lit by the level `$f18` leaves in r4: see [`bilinear_blend`].
#[cfg(arm_dsp)]
macro_rules! bilinear_texel {
    ($skip:literal, $ys:literal, $f18:expr) => {
        concat!(depth_test!($skip), bilinear_blend!($ys, $f18))
    };
}

/// The bilinear blend into r0, lit: r5 = `x − ½ + 2⁻⁸` (16.16), r6 = `y − ½ + 2⁻⁸` shifted by
/// `y`'s shift, r12/lr the masks, r11 the texels; `[sp, #$ys]` (counted after the 16 bytes it
/// pushes) holds `y`'s shift plus 9; `$f18` leaves the level in r4 as a fraction of 18 bits
/// (below `2¹⁸·257/256`; 2¹⁸ unlit), reading r7 if it will (pushed, not yet changed).
///
/// The texels `(i, j)`, `(i + 1, j)`, `(i, j + 1)`, `(i + 1, j + 1)` around the point (each
/// index masked; row `j + 1` as `(j − rows_mask) & rows_mask`, which is `j` plus a row modulo
/// the texture), weighted by the 7-bit fractions `fx`, `fy` of the point's coordinates: each
/// channel's sum `s = Σ t·w` with `w` = `(128 − fx)·(128 − fy)`, `fx·(128 − fy)`, `(128 −
/// fx)·fy`, `fx·fy` — the two texels of a row as the halves of one word, their weights as the
/// halves of another, a row's products summed by one `smuad`/`smlad` — then `(s·f + 2³¹) >>
/// 32` by one `smmulr` (`s` below 2²⁰, `f` below 2¹⁹: exact), which is
/// `texture::map::Blend::lit` (and, at `f` = 2¹⁸, the rounded blend `(s + 2¹³) >> 14`). The
/// portable blend rounds the fractions of `x − ½` to 7 bits, `fx ≤ 128`; here `x − ½ + 2⁻⁸`'s
/// fraction is cut to 7 bits, and where the portable `fx` is 128 the index here is one more
/// with `fx` 0: the same texel weighted by the same 128, the same sum. No channel passes its
/// field (`63·257/256 + ½ < 64`). Clobbers r1-r3 (r4, r7, r9, r10 saved and restored).
#[cfg(arm_dsp)]
macro_rules! bilinear_blend {
    ($ys:literal, $f18:expr) => {
        concat!(
            "push {{r4, r7, r9, r10}}\n",
            $f18,
            // The rows j (r1) and j + 1 (r2) in storage units, the columns i (r0), i + 1 (r3).
            "and r1, lr, r6, lsr #16\n",
            "sub r2, r1, lr\n",
            "and r2, r2, lr\n",
            "and r0, r12, r5, lsr #16\n",
            "add r3, r5, #0x10000\n",
            "and r3, r12, r3, lsr #16\n",
            // The top row's texels (r7: i in the low half), the bottom row's (r9).
            "orr r7, r0, r1\n",
            "orr r9, r3, r1\n",
            "ldrh r7, [r11, r7, lsl #1]\n",
            "ldrh r9, [r11, r9, lsl #1]\n",
            "pkhbt r7, r7, r9, lsl #16\n",
            "orr r0, r0, r2\n",
            "orr r3, r3, r2\n",
            "ldrh r0, [r11, r0, lsl #1]\n",
            "ldrh r3, [r11, r3, lsl #1]\n",
            "pkhbt r9, r0, r3, lsl #16\n",
            // The weights: `(128 − fx) | fx << 16` (r0) times `128 − fy` (r1, the top row's)
            // and `fy` (r2, the bottom row's); each half at most 2¹⁴.
            "ubfx r0, r5, #9, #7\n",
            "ldr r1, [sp, #",
            $ys,
            "]\n",
            "lsr r1, r6, r1\n",
            "and r1, r1, #127\n",
            "rsb r0, r0, r0, lsl #16\n",
            "add r0, r0, #128\n",
            "mul r2, r0, r1\n",
            "rsb r1, r1, #128\n",
            "mul r1, r0, r1\n",
            // Blue, green, red: each field of both rows' texel pairs, weighted, summed, lit.
            "and r3, r7, #0x001F001F\n",
            "and r10, r9, #0x001F001F\n",
            "smuad r0, r3, r1\n",
            "smlad r0, r10, r2, r0\n",
            "smmulr r0, r0, r4\n",
            "lsr r3, r7, #5\n",
            "and r3, r3, #0x003F003F\n",
            "lsr r10, r9, #5\n",
            "and r10, r10, #0x003F003F\n",
            "smuad r3, r3, r1\n",
            "smlad r3, r10, r2, r3\n",
            "smmulr r3, r3, r4\n",
            "orr r0, r0, r3, lsl #5\n",
            "lsr r3, r7, #11\n",
            "and r3, r3, #0x001F001F\n",
            "lsr r10, r9, #11\n",
            "and r10, r10, #0x001F001F\n",
            "smuad r3, r3, r1\n",
            "smlad r3, r10, r2, r3\n",
            "smmulr r3, r3, r4\n",
            "orr r0, r0, r3, lsl #11\n",
            "pop {{r4, r7, r9, r10}}\n",
        )
    };
}

/// [`bilinear_blend`]'s level unlit: 2¹⁸.
#[cfg(arm_dsp)]
macro_rules! unlit_f18 {
    () => {
        "mov r4, #262144\n"
    };
}

/// [`bilinear_blend`]'s level from the level plane (r7): `((l >> 12)·257) >> 10`, the 18-bit
/// form of [`lit_texel`]'s `f`.
#[cfg(arm_dsp)]
macro_rules! plane_f18 {
    () => {
        "lsr r4, r7, #12\nadd r4, r4, r4, lsl #8\nlsr r4, r4, #10\n"
    };
}

/// Where the bilinear loops take a pixel's coordinates: `x` and `y` less ½ texel plus 2⁻⁸
/// (32,512 units of 2⁻¹⁶, an immediate Thumb-2 encodes), as [`bilinear_texel`] reads them.
const BILINEAR_OFFSET: i32 = (1 << 15) - (1 << 8);

/// A run's first coordinates moved for the bilinear pixel (by [`BILINEAR_OFFSET`]).
#[cfg(arm_dsp)]
macro_rules! bilinear_offset {
    () => {
        "sub r5, r5, #{bilinear_offset}\nsub r6, r6, #{bilinear_offset}\n"
    };
}

/// What every textured row loop keeps from its block (r0; the loop's frame at sp, 16 bytes or
/// more): the depth's and the level's steps a pixel (the block's words 80 and 92) at [sp] and
/// [sp, #12], and the texels, the column mask and the row mask (words 132-140) in r11, r12 and
/// lr. Clobbers r2, r3.
macro_rules! row_loop_state {
    () => {
        concat!(
            "ldr r2, [r0, #80]\n",
            "ldr r3, [r0, #92]\n",
            "str r2, [sp]\n",
            "str r3, [sp, #12]\n",
            "add r2, r0, #132\n",
            "ldm r2, {{r11, r12, lr}}\n",
        )
    };
}

/// The bilinear row loop's function body after its entry (r0 = the block, r1 = the variant,
/// bit 4 set), each run clamped by `$clamp`.
#[cfg(arm_dsp)]
macro_rules! bilinear_rows_body {
    ($clamp:expr) => {
        concat!(
            "push {{r4-r11, lr}}\n",
            // [sp]: the per-pixel steps; [sp, #16]: the block; [sp, #20]: `y`'s shift plus 9.
            "sub sp, #28\n",
            "str r0, [sp, #16]\n",
            "ldr r2, [r0, #112]\n",
            "add r2, r2, #9\n",
            "str r2, [sp, #20]\n",
            row_loop_state!(),
            "cmp r1, #6\n",
            "bhs 20f\n",
            "cmp r1, #4\n",
            "beq 11f\n",
            textured_rows!(
                "cmp r2, r1\nit gt\nmovgt r1, r2",
                unlit_pixel!(bilinear_texel!("4f", "36", unlit_f18!())),
                bilinear_offset!(),
                "28",
                $clamp
            ),
            "11:\n",
            textured_rows!(
                "cmp r2, r3\nit lt\nmovlt r3, r2",
                unlit_pixel!(bilinear_texel!("4f", "36", unlit_f18!())),
                bilinear_offset!(),
                "28",
                $clamp
            ),
            "20:\n",
            "cmp r1, #6\n",
            "beq 21f\n",
            textured_rows!(
                "cmp r2, r1\nit gt\nmovgt r1, r2",
                lit_pixel!(
                    bilinear_texel!("4f", "36", plane_f18!()),
                    "strh r0, [r10, r8]\n"
                ),
                bilinear_offset!(),
                "28",
                $clamp
            ),
            "21:\n",
            textured_rows!(
                "cmp r2, r3\nit lt\nmovlt r3, r2",
                lit_pixel!(
                    bilinear_texel!("4f", "36", plane_f18!()),
                    "strh r0, [r10, r8]\n"
                ),
                bilinear_offset!(),
                "28",
                $clamp
            ),
        )
    };
}

/// The inside rows' way to the variants they do not draw themselves (bit 4 or 8 set): the
/// bilinear rows without the clamp where the DSP extension is (they pass bit 8 on to the palette
/// rows without it), else the palette rows without it (bit 4 is never set there).
#[cfg(arm_dsp)]
macro_rules! inside_rows_other {
    () => {
        "bhs.w embedded_raster_bilinear_rows_inside_v7em"
    };
}
#[cfg(not(arm_dsp))]
macro_rules! inside_rows_other {
    () => {
        "bhs.w embedded_raster_palette_rows_inside_v7m"
    };
}

// The bilinear variants of the textured row loop (ARMv7E-M: `smuad`, `smlad` and `pkhbt` are
// the DSP extension's): entered from `embedded_raster_textured_rows_v7m` with its arguments,
// the variant's bit 4 set.
#[cfg(arm_dsp)]
core::arch::global_asm!(
    ".section .text.embedded_raster_bilinear_rows_v7em,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_bilinear_rows_v7em",
    ".hidden embedded_raster_bilinear_rows_v7em",
    ".type embedded_raster_bilinear_rows_v7em,%function",
    ".thumb_func",
    "embedded_raster_bilinear_rows_v7em:",
    "cmp r1, #8",
    "bhs.w embedded_raster_palette_rows_v7m",
    bilinear_rows_body!(clamped_run!("r1", "r3", "r4", "76")),
    ".size embedded_raster_bilinear_rows_v7em, . - embedded_raster_bilinear_rows_v7em",
    bilinear_offset = const BILINEAR_OFFSET,
);

// The same rows where no run needs the clamp to the columns (`face_scan`'s word): entered from
// `embedded_raster_textured_rows_inside_v7m` with its arguments, the variant's bit 4 set.
#[cfg(arm_dsp)]
core::arch::global_asm!(
    ".section .text.embedded_raster_bilinear_rows_inside_v7em,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_bilinear_rows_inside_v7em",
    ".hidden embedded_raster_bilinear_rows_inside_v7em",
    ".type embedded_raster_bilinear_rows_inside_v7em,%function",
    ".thumb_func",
    "embedded_raster_bilinear_rows_inside_v7em:",
    "cmp r1, #8",
    "bhs.w embedded_raster_palette_rows_inside_v7m",
    bilinear_rows_body!(""),
    ".size embedded_raster_bilinear_rows_inside_v7em, . - embedded_raster_bilinear_rows_inside_v7em",
    bilinear_offset = const BILINEAR_OFFSET,
);

// An affine span of bilinear texels (the 2D textured fill's, ARMv7E-M): r0 = the block of
// `bilinear_span_565`.
#[cfg(arm_dsp)]
core::arch::global_asm!(
    ".section .text.embedded_raster_bilinear_span_v7em,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_bilinear_span_v7em",
    ".hidden embedded_raster_bilinear_span_v7em",
    ".type embedded_raster_bilinear_span_v7em,%function",
    ".thumb_func",
    "embedded_raster_bilinear_span_v7em:",
    "push {{r4-r11, lr}}",
    // [sp]: `y`'s shift plus 9.
    "sub sp, #8",
    "ldr r1, [r0, #36]",
    "str r1, [sp]",
    // r9/r10 = the pixel and the end, r5/r4 = x and its step, r6/r8 = y (shifted) and its step.
    "ldrd r9, r10, [r0]",
    "ldrd r5, r4, [r0, #8]",
    "ldrd r6, r8, [r0, #16]",
    "ldr r11, [r0, #24]",
    "ldrd r12, lr, [r0, #28]",
    "1:",
    bilinear_blend!("16", unlit_f18!()),
    "strh r0, [r9], #2",
    "add r5, r5, r4",
    "add r6, r6, r8",
    "cmp r9, r10",
    "bne 1b",
    "add sp, #8",
    "pop {{r4-r11, pc}}",
    ".size embedded_raster_bilinear_span_v7em, . - embedded_raster_bilinear_span_v7em",
);

/// What the affine bilinear span's assembly reads (offsets are its).
#[cfg(arm_dsp)]
#[repr(C)]
struct BilinearSpanBlock {
    /// 0: the first pixel; 4: past the last.
    pixels: *mut u16,
    end: *mut u16,
    /// 8, 12: `x` (moved by [`BILINEAR_OFFSET`]) and its step; 16, 20: `y` (moved, then
    /// shifted by the row's bits) and its step (shifted).
    x: [i32; 2],
    y: [i32; 2],
    /// 24: the texels; 28: the column mask; 32: the row mask; 36: `y`'s shift plus 9.
    texels: *const u16,
    x_mask: u32,
    rows_mask: u32,
    y_shift_9: u32,
}

#[cfg(arm_dsp)]
extern "C" {
    /// The assembly function above.
    ///
    /// # Safety
    ///
    /// `block` is valid for reads; its pointers address at least one 2-byte aligned `u16`
    /// pixel between them; every index of at most `rows_mask | x_mask` is inside its texels;
    /// its shift is below 32.
    fn embedded_raster_bilinear_span_v7em(block: *const BilinearSpanBlock);
}

/// Fills `pixels` with the affine span `span` of bilinear texels (`texture::map::bilinear_by`'s
/// blend at `(x, y) + i·(dx, dy)`, `y` as [`MaskedSpan565`] scales it). `false` without
/// drawing anything if a texel index the masks allow is not inside `span.texels` or `C` is not
/// a 16-bit colour. `C` must be the 5-6-5 format whose raw value is the texels' (the caller's
/// promise).
#[cfg(arm_dsp)]
#[inline(always)]
pub(crate) fn bilinear_span_565<C: Copy>(pixels: &mut [C], span: &MaskedSpan565<'_>) -> bool {
    let y_shift = 32 - span.x_mask.leading_zeros();
    if !masked_texels::<C>(span.texels, span.x_mask, span.rows, &[y_shift]) {
        return false;
    }
    if pixels.is_empty() {
        return true;
    }
    let range = pixels.as_mut_ptr_range();
    let block = BilinearSpanBlock {
        pixels: range.start.cast(),
        end: range.end.cast(),
        x: [span.x.0.wrapping_sub(BILINEAR_OFFSET), span.x.1],
        y: [span.y.0.wrapping_sub(BILINEAR_OFFSET << y_shift), span.y.1],
        texels: span.texels.as_ptr(),
        x_mask: span.x_mask,
        rows_mask: span.rows,
        y_shift_9: y_shift + 9,
    };
    // SAFETY: the function writes the pixels from `start` to `end` (at least one, 2-byte
    // aligned `u16`s: `C` is a 2-byte colour whose raw value the texels are, the caller's
    // promise), reads the texels at indices of at most `rows | x_mask` (inside them, checked
    // above) with a shift below 32 (a mask's bits), reads the block, and saves and restores
    // every register the AAPCS asks it to, its stack frame its own.
    unsafe { embedded_raster_bilinear_span_v7em(&block) };
    true
}

/// The textured row loop's entry: the bilinear variants (bit 4) are another function's.
#[cfg(arm_dsp)]
macro_rules! bilinear_rows_entry {
    () => {
        "cmp r1, #4\nbhs.w embedded_raster_bilinear_rows_v7em\n"
    };
}

/// Without the DSP extension there are no bilinear variants: the palette's (bit 8) are another
/// function's.
#[cfg(not(arm_dsp))]
macro_rules! bilinear_rows_entry {
    () => {
        "cmp r1, #8\nbhs.w embedded_raster_palette_rows_v7m\n"
    };
}

/// The texel of the pixel at r8 from 4-bit palette indices (r11 their bytes, two a byte, the
/// even texel in the high nibble; `[sp, #20]` the 16 colours' raw words) into r0, after the
/// depth test, as [`textured_texel`] finds its index: `palette[(bytes[i >> 1] >> (4 − 4·(i &
/// 1))) & 15]`, as `Indexed4` reads it. Clobbers r1.
macro_rules! palette_texel {
    ($skip:literal) => {
        concat!(
            depth_test!($skip),
            texel_index!(),
            "lsr r1, r0, #1\n",
            "ldrb r1, [r11, r1]\n",
            "lsls r0, r0, #31\n",
            "it pl\n",
            "lsrpl r1, r1, #4\n",
            "and r1, r1, #15\n",
            "ldr r0, [sp, #20]\n",
            "ldrh r0, [r0, r1, lsl #1]\n",
        )
    };
}

/// The palette row loop's function body (r0 = the block, r1 = the variant, bit 8 set, r2 = the
/// palette's 16 raw words), each run clamped by `$clamp`.
macro_rules! palette_rows_body {
    ($clamp:expr) => {
        concat!(
            "push {{r4-r11, lr}}\n",
            // [sp]: the per-pixel steps; [sp, #16]: the block; [sp, #20]: the palette.
            "sub sp, #28\n",
            "str r0, [sp, #16]\n",
            "str r2, [sp, #20]\n",
            row_loop_state!(),
            "cmp r1, #10\n",
            "bhs 20f\n",
            "cmp r1, #8\n",
            "beq 11f\n",
            textured_rows!(
                "cmp r2, r1\nit gt\nmovgt r1, r2",
                unlit_pixel!(palette_texel!("4f")),
                "",
                "28",
                $clamp
            ),
            "11:\n",
            textured_rows!(
                "cmp r2, r3\nit lt\nmovlt r3, r2",
                unlit_pixel!(palette_texel!("4f")),
                "",
                "28",
                $clamp
            ),
            "20:\n",
            "cmp r1, #10\n",
            "beq 21f\n",
            textured_rows!(
                "cmp r2, r1\nit gt\nmovgt r1, r2",
                lit_pixel!(palette_texel!("4f")),
                "",
                "28",
                $clamp
            ),
            "21:\n",
            textured_rows!(
                "cmp r2, r3\nit lt\nmovlt r3, r2",
                lit_pixel!(palette_texel!("4f")),
                "",
                "28",
                $clamp
            ),
        )
    };
}

// The 4-bit palette variants of the textured row loop: entered from
// `embedded_raster_textured_rows_v7m` with its arguments, the variant's bit 8 set and r2 the
// palette's 16 raw words.
core::arch::global_asm!(
    ".section .text.embedded_raster_palette_rows_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_palette_rows_v7m",
    ".hidden embedded_raster_palette_rows_v7m",
    ".type embedded_raster_palette_rows_v7m,%function",
    ".thumb_func",
    "embedded_raster_palette_rows_v7m:",
    palette_rows_body!(clamped_run!("r1", "r3", "r4", "76")),
    ".size embedded_raster_palette_rows_v7m, . - embedded_raster_palette_rows_v7m",
);

// The same rows where no run needs the clamp to the columns (`face_scan`'s word): entered from
// the inside rows' entries with their arguments, the variant's bit 8 set.
core::arch::global_asm!(
    ".section .text.embedded_raster_palette_rows_inside_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_palette_rows_inside_v7m",
    ".hidden embedded_raster_palette_rows_inside_v7m",
    ".type embedded_raster_palette_rows_inside_v7m,%function",
    ".thumb_func",
    "embedded_raster_palette_rows_inside_v7m:",
    palette_rows_body!(""),
    ".size embedded_raster_palette_rows_inside_v7m, . - embedded_raster_palette_rows_inside_v7m",
);

core::arch::global_asm!(
    ".section .text.embedded_raster_textured_rows_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_textured_rows_v7m",
    ".hidden embedded_raster_textured_rows_v7m",
    ".type embedded_raster_textured_rows_v7m,%function",
    ".thumb_func",
    // r0 = the block, r1 = the variant: 1 if the middle bound is a start bound, plus 2 if lit,
    // plus 4 if bilinear (ARMv7E-M) or 8 if 4-bit palette indices (then r2 = the palette).
    "embedded_raster_textured_rows_v7m:",
    bilinear_rows_entry!(),
    "push {{r4-r11, lr}}",
    // [sp]: the per-pixel steps (the depth's and the level's; the coordinates' a run); [sp, #16]:
    // the block.
    "sub sp, #20",
    "str r0, [sp, #16]",
    row_loop_state!(),
    "cmp r1, #2",
    "bhs 20f",
    "cmp r1, #0",
    "beq 11f",
    textured_rows!("cmp r2, r1\nit gt\nmovgt r1, r2", unlit_pixel!()),
    "11:",
    textured_rows!("cmp r2, r3\nit lt\nmovlt r3, r2", unlit_pixel!()),
    "20:",
    "cmp r1, #2",
    "beq 21f",
    textured_rows!("cmp r2, r1\nit gt\nmovgt r1, r2", lit_pixel!()),
    "21:",
    textured_rows!("cmp r2, r3\nit lt\nmovlt r3, r2", lit_pixel!()),
    ".size embedded_raster_textured_rows_v7m, . - embedded_raster_textured_rows_v7m",
);

// The nearest variants (0-3) of the textured rows where no run needs the clamp to the columns
// (the clip cut none off the region: `face_scan`'s word); the others go on by
// `inside_rows_other`.
core::arch::global_asm!(
    ".section .text.embedded_raster_textured_rows_inside_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_textured_rows_inside_v7m",
    ".hidden embedded_raster_textured_rows_inside_v7m",
    ".type embedded_raster_textured_rows_inside_v7m,%function",
    ".thumb_func",
    "embedded_raster_textured_rows_inside_v7m:",
    "cmp r1, #4",
    inside_rows_other!(),
    "push {{r4-r11, lr}}",
    "sub sp, #20",
    "str r0, [sp, #16]",
    row_loop_state!(),
    // The variant's rows by a table of halfword offsets from the table (r1 below 4).
    "tbh [pc, r1, lsl #1]",
    "30:",
    ".hword (31f - 30b) / 2",
    ".hword (32f - 30b) / 2",
    ".hword (33f - 30b) / 2",
    ".hword (34f - 30b) / 2",
    "31:",
    textured_rows!(
        "cmp r2, r3\nit lt\nmovlt r3, r2",
        unlit_pixel!(),
        "",
        "20",
        ""
    ),
    "32:",
    textured_rows!(
        "cmp r2, r1\nit gt\nmovgt r1, r2",
        unlit_pixel!(),
        "",
        "20",
        ""
    ),
    "33:",
    textured_rows!(
        "cmp r2, r3\nit lt\nmovlt r3, r2",
        lit_pixel!(),
        "",
        "20",
        ""
    ),
    "34:",
    textured_rows!(
        "cmp r2, r1\nit gt\nmovgt r1, r2",
        lit_pixel!(),
        "",
        "20",
        ""
    ),
    ".size embedded_raster_textured_rows_inside_v7m, . - embedded_raster_textured_rows_inside_v7m",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_textured_rows_v7m(block: *mut TexturedBlock, variant: u32);
}

/// Draws the rows `rows` into `colors` and `depths` (row-major, `rows.region.width` pixels a
/// row) as [`TexturedRows`] describes. `false` without drawing anything if the region is not
/// inside both buffers, a texel index the masks allow is not inside `rows.texels`, a shift is
/// not below 32 or `C` is not a 16-bit colour, so no input reads or writes outside them. `C`
/// must be the 5-6-5 format whose raw value is the texels' (the caller's promise: the colours
/// written are those raw values).
#[inline(always)]
pub(crate) fn textured_rows<C: Copy>(
    colors: &mut [C],
    depths: &mut [u16],
    rows: &TexturedRows<'_>,
) -> bool {
    let region = &rows.region;
    let Some(stride) = region_stride(colors.len().min(depths.len()), region) else {
        return false;
    };
    let shifts = [rows.maps[0].1, rows.maps[1].1, rows.y_shift];
    if !masked_texels::<C>(rows.texels, rows.x_mask, rows.rows_mask, &shifts) {
        return false;
    }
    let [s, m, e] = region.bounds;
    let depths = depths.as_mut_ptr().wrapping_add(region.first);
    let colors: *mut u16 = colors.as_mut_ptr().wrapping_add(region.first).cast();
    let (level, variant) = match rows.level {
        Some(level) => (level, 2),
        None => ([0; 3], 0),
    };
    // Bilinear rows where the DSP extension is.
    if rows.bilinear && !BILINEAR_ROWS {
        return false;
    }
    let variant = variant | if rows.bilinear { 4 } else { 0 };
    let (u, v, z) = (rows.u, rows.v, region.depth);
    let mut block = TexturedBlock {
        row: [z[0], u[0], v[0], level[0], depths as usize as u32],
        numerators: [s.0, m.0, e.0],
        row_steps: [z[2], u[2], v[2], level[2], stride],
        numerator_steps: [s.2, m.2, e.2],
        divisors: [s.1.get(), m.1.get(), e.1.get()],
        columns: region.columns,
        column_steps: [z[1], u[1], v[1], level[1]],
        map_u: [rows.maps[0].0 as u32, rows.maps[0].1],
        map_v: [rows.maps[1].0 as u32, rows.maps[1].1],
        y_shift: rows.y_shift,
        texel_steps: [rows.texel_steps.0, rows.texel_steps.1 << rows.y_shift],
        color_offset: (colors as usize).wrapping_sub(depths as usize) as u32,
        rows: region.rows,
        texels: rows.texels.as_ptr(),
        x_mask: rows.x_mask,
        rows_mask: rows.rows_mask,
    };
    let variant = variant | u32::from(region.middle_starts);
    // SAFETY: the function writes only pixels of the region — rows `0..rows` from the first
    // pixel, `width` pixels apart, each in columns `start..end` with `0 ≤ start` and
    // `end ≤ columns` — which are inside both buffers (checked above), as 2-byte aligned `u16`s
    // (`C` is a 2-byte colour whose raw value the texels are, the caller's promise). It reads
    // the texels at indices of at most `rows_mask | x_mask`, inside them (checked above), reads
    // and writes the block (its own), divides by the non-zero divisors only, and saves and
    // restores every register the AAPCS asks it to, its stack frame its own.
    unsafe { embedded_raster_textured_rows_v7m(&mut block, variant) };
    true
}

/// What the perspective span's assembly reads and updates (offsets in the comments are the
/// assembly's).
#[repr(C)]
struct PerspectiveBlock {
    /// 0: the depth pointer at the chunk's first pixel; 4: the colour pointer's offset from it
    /// in bytes (wrapping); 8: pixels left.
    depths: *mut u16,
    color_offset: u32,
    left: u32,
    /// 12-20: the perspective planes at the chunk's first pixel; 24-32: their steps a pixel.
    planes: [u32; 3],
    steps: [u32; 3],
    /// 36-44, 48-56, 60-68: `u`, `v` and the level as `(base, d₁, d₂)`.
    u: [i32; 3],
    v: [i32; 3],
    level: [i32; 3],
    /// 72: the texels; 76: the column mask; 80: the row mask; 84: `y`'s shift.
    texels: *const u16,
    x_mask: u32,
    rows_mask: u32,
    y_shift: u32,
    /// 88, 92: the depth plane at the chunk's first pixel, its step.
    depth: u32,
    depth_step: u32,
    /// 96: the span's `raster::perspective::chunk_room`.
    chunk_room: i32,
}

const _: () = assert!(core::mem::size_of::<PerspectiveBlock>() == 100);

/// The perspective barycentrics (r1, r2) from the planes' values r5-r7, as
/// `raster::perspective::lambdas`: `q = max((r5 >> 16) − 128, 1)` (the margin off, saturating),
/// `r = 2³¹ / q`, `λₖ = (min(max((vₖ >> 16) − 128, 0), q)·r) >> 15`. Clobbers r3, r8.
macro_rules! lambdas {
    () => {
        concat!(
            "lsr r3, r5, #16\n",
            "subs r3, r3, #128\n",
            "it ls\n",
            "movls r3, #1\n",
            "mov r8, #0x80000000\n",
            "udiv r8, r8, r3\n",
            "lsr r1, r6, #16\n",
            "subs r1, r1, #128\n",
            "it lo\n",
            "movlo r1, #0\n",
            "cmp r1, r3\n",
            "it hi\n",
            "movhi r1, r3\n",
            "mul r1, r1, r8\n",
            "lsr r1, r1, #15\n",
            "lsr r2, r7, #16\n",
            "subs r2, r2, #128\n",
            "it lo\n",
            "movlo r2, #0\n",
            "cmp r2, r3\n",
            "it hi\n",
            "movhi r2, r3\n",
            "mul r2, r2, r8\n",
            "lsr r2, r2, #15\n",
        )
    };
}

/// `$acc += ⌊$l·$d / 2¹⁶⌋` (the 64-bit product's bits 16-47), as [`corrected`] adds each term;
/// `$d` and r11 clobbered.
macro_rules! lambda_term {
    ($acc:literal, $l:literal, $d:literal) => {
        concat!(
            "smull ",
            $d,
            ", r11, ",
            $l,
            ", ",
            $d,
            "\n",
            "lsr ",
            $d,
            ", ",
            $d,
            ", #16\n",
            "orr ",
            $d,
            ", ",
            $d,
            ", r11, lsl #16\n",
            "add ",
            $acc,
            ", ",
            $acc,
            ", ",
            $d,
            "\n",
        )
    };
}

/// An attribute at the barycentrics (r1, r2) into `$dst`: `base + ⌊λ₁·d₁ / 2¹⁶⌋ + ⌊λ₂·d₂ /
/// 2¹⁶⌋` (the 64-bit products' bits 16-47), from `(base, d₁, d₂)` at `$at` in the block (r0).
/// Clobbers r10, r11.
macro_rules! corrected {
    ($dst:literal, $at:literal, $d1:literal, $d2:literal) => {
        concat!(
            "ldr ",
            $dst,
            ", [r0, #",
            $at,
            "]\n",
            "ldr r10, [r0, #",
            $d1,
            "]\n",
            lambda_term!($dst, "r1", "r10"),
            "ldr r10, [r0, #",
            $d2,
            "]\n",
            lambda_term!($dst, "r2", "r10"),
        )
    };
}

/// The unlit loop over a chunk's pixels, at label `$top` (`$skip` where the depth test fails):
/// r1 = the offset of the pixel from r2 (depths) and r3 (colours), counting up to 0, r4/r5 =
/// the depth and its step, r6/r7 = x and its step, r8/r9 = y (shifted) and its step, r10 = the
/// texels, r11 = the column mask, r12 = the row mask. Clobbers r0 and lr.
macro_rules! unlit_pixels {
    ($top:literal, $skip:literal) => {
        concat!(
            $top,
            ":\n",
            "ldrh lr, [r2, r1]\n",
            "cmp lr, r4, lsr #16\n",
            "bls ",
            $skip,
            "f\n",
            "lsr lr, r4, #16\n",
            "strh lr, [r2, r1]\n",
            "and lr, r11, r6, lsr #16\n",
            "and r0, r12, r8, lsr #16\n",
            "orr lr, lr, r0\n",
            "ldrh lr, [r10, lr, lsl #1]\n",
            "strh lr, [r3, r1]\n",
            $skip,
            ":\n",
            "add r4, r5\n",
            "add r6, r7\n",
            "add r8, r9\n",
            "adds r1, #2\n",
            "bne ",
            $top,
            "b\n",
        )
    };
}

/// The unlit chunks' `x` and `y` at the chunk's end, from the barycentrics (r1, r2) as
/// [`corrected`] finds them (its six words read at once): `x` to r4, `y` to r7. Clobbers r3,
/// r5, r6, r9-r11.
macro_rules! unlit_chunk_end {
    () => {
        concat!(
            "add r3, r0, #36\n",
            "ldm r3, {{r4-r7, r9, r10}}\n",
            lambda_term!("r4", "r1", "r5"),
            lambda_term!("r4", "r2", "r6"),
            lambda_term!("r7", "r1", "r9"),
            lambda_term!("r7", "r2", "r10"),
        )
    };
}

/// `$d`, an attribute's difference over the chunk, as its step a pixel for a chunk shorter
/// than 16 (r3 = `⌈2¹⁶ / over⌉`): `(d >> 16)·r3 + ((d & 0xffff)·r3 >> 16)`, wrapping, as
/// `raster::perspective::step_over`. Clobbers r10.
macro_rules! step_over {
    ($d:literal) => {
        concat!(
            "uxth r10, ",
            $d,
            "\n",
            "mul r10, r10, r3\n",
            "lsr r10, r10, #16\n",
            "asr ",
            $d,
            ", ",
            $d,
            ", #16\n",
            "mla ",
            $d,
            ", ",
            $d,
            ", r3, r10\n",
        )
    };
}

/// The lit loop's step to the next pixel: the steps from [sp] (depth, x, y, level).
macro_rules! lit_step {
    () => {
        concat!(
            "34:\n",
            "ldm sp, {{r0-r3}}\n",
            "add r4, r0\n",
            "add r5, r1\n",
            "add r6, r2\n",
            "add r7, r3\n",
            "adds r8, #2\n",
        )
    };
}

/// The perspective span's bilinear loops (ARMv7E-M), entered at 50 from its dispatch with the
/// registers as the lit loop's set-up finds them (the block's `u` and `v` bases moved by
/// `−½ + 2⁻⁸` texel): unlit, lit with no clamp, lit with the level clamped — the lit loop's
/// with [`bilinear_texel`]'s texel (`y`'s shift plus 9 at [sp, #44]).
#[cfg(arm_dsp)]
macro_rules! perspective_bilinear {
    () => {
        concat!(
            "50:\n",
            "add r11, sp, #4\n",
            "stm r11, {{r4-r6}}\n",
            "ldr r11, [r0, #84]\n",
            "add r11, r11, #9\n",
            "str r11, [sp, #44]\n",
            "ldr r11, [sp, #20]\n",
            "cmp r11, #2\n",
            "beq 55f\n",
            "sub r11, r10, #1\n",
            "mla r11, r6, r11, r9\n",
            "add r6, r6, #65536\n",
            "cmp r6, #131072\n",
            "it ls\n",
            "cmpls r9, #65536\n",
            "it ls\n",
            "cmpls r11, #65536\n",
            // Unlit: `eq` from the compare, so `ls` too.
            "55:\n",
            "mov r5, r7\n",
            "mov r6, r8\n",
            "mov r7, r9\n",
            "mov r8, r1\n",
            "mov r9, r2\n",
            "mov r10, r3\n",
            "ldr r4, [r0, #88]\n",
            "add r1, r0, #72\n",
            "ldm r1, {{r11, r12, lr}}\n",
            "ldr r3, [sp, #20]\n",
            "bhi 57f\n",
            "cmp r3, #2\n",
            "beq 56f\n",
            "52:\n",
            bilinear_texel!("34f", "60", "lsl r4, r7, #2\n"),
            "strh r0, [r10, r8]\n",
            lit_step!(),
            "bne 52b\n",
            "b 9f\n",
            "56:\n",
            bilinear_texel!("34f", "60", unlit_f18!()),
            "strh r0, [r10, r8]\n",
            lit_step!(),
            "bne 56b\n",
            "b 9f\n",
            "57:\n",
            bilinear_texel!(
                "34f",
                "60",
                concat!(
                    "bic r4, r7, r7, asr #31\n",
                    "cmp r4, #65536\n",
                    "it hi\n",
                    "movhi r4, #65536\n",
                    "lsl r4, r4, #2\n",
                )
            ),
            "strh r0, [r10, r8]\n",
            lit_step!(),
            "bne 57b\n",
            "b 9f\n",
        )
    };
}

/// Without the DSP extension there are no bilinear loops (the span is declined before).
#[cfg(not(arm_dsp))]
macro_rules! perspective_bilinear {
    () => {
        ""
    };
}

/// The perspective span's dispatch on its flags (r11): lit (1), bilinear (2, ARMv7E-M) or
/// neither (falls through).
#[cfg(arm_dsp)]
macro_rules! perspective_dispatch {
    () => {
        "cmp r11, #1\nbeq 30f\nbhi 50f\n"
    };
}

/// Without the DSP extension: lit or not.
#[cfg(not(arm_dsp))]
macro_rules! perspective_dispatch {
    () => {
        "cmp r11, #0\nbne 30f\n"
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_perspective_span_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_perspective_span_v7m",
    ".hidden embedded_raster_perspective_span_v7m",
    ".type embedded_raster_perspective_span_v7m,%function",
    ".thumb_func",
    // r0 = the block (at least one pixel left), r1 = its flags: 1 if lit, plus 2 if bilinear
    // (ARMv7E-M). The levels at the chunks' ends are found only if lit (flag 1).
    "embedded_raster_perspective_span_v7m:",
    "push {{r4-r11, lr}}",
    // [sp]: the steps a pixel of the depth, x, y (shifted) and level; [sp, #16]: the block;
    // [sp, #20]: the flags; [sp, #24-32]: x, y and level at the chunk's first pixel; [sp, #36]:
    // the chunk's length's bits; [sp, #40]: the span's pixels; [sp, #44]: the bilinear loops'
    // `y` shift plus 9; [sp, #48]: the lit flag alone.
    "sub sp, #52",
    "str r0, [sp, #16]",
    "str r1, [sp, #20]",
    "and r2, r1, #1",
    "str r2, [sp, #48]",
    "ldr r1, [r0, #8]",
    "str r1, [sp, #40]",
    "ldr r1, [r0, #92]",
    "str r1, [sp]",
    // The attributes at the span's first pixel.
    "add r4, r0, #12",
    "ldm r4, {{r5-r7}}",
    lambdas!(),
    corrected!("r4", "36", "40", "44"),
    corrected!("r5", "48", "52", "56"),
    // Unlit nearest (flags 0) with a room of at least `NO_LIMIT` (−640): every chunk but the
    // last is 16 pixels, drawn by the chunk loop at 70 (no level, no length to pick).
    "ldr r3, [sp, #20]",
    "cbnz r3, 71f",
    "ldr r12, [r0, #96]",
    "cmn r12, #640",
    "blt 72f",
    "strd r4, r5, [sp, #24]",
    "ldr r3, [r0, #8]",
    "b 70f",
    "71:",
    "lsls r3, r3, #31",
    "beq 72f",
    corrected!("r6", "60", "64", "68"),
    "72:",
    "add r3, sp, #24",
    "stm r3, {{r4-r6}}",
    // The chunk's length 2^s, as `raster::perspective::chunk_shift` picks it from the room
    // (r12): 16 if the room is at least its `NO_LIMIT` (−640; then every chunk but the last has
    // 16 pixels, so every chunk's offset is a multiple of 16 and the alignment test at 40 would
    // not shorten it), else from the smaller q (r7) at the chunk's first pixel and min(16, left
    // − 1) on, the margin off (saturating, at least 2¹⁶), by its sixteenth-logarithm. s in r11
    // and [sp, #36]. Entered at 3 with the block in r0 and its pixels left in r3.
    "ldr r0, [sp, #16]",
    "ldr r3, [r0, #8]",
    "3:",
    "ldr r12, [r0, #96]",
    "mov r11, #4",
    "cmn r12, #640",
    "bge 41f",
    "ldr r5, [r0, #12]",
    "ldr r6, [r0, #24]",
    "subs r1, r3, #1",
    "cmp r1, #16",
    "it hi",
    "movhi r1, #16",
    "mla r7, r6, r1, r5",
    "cmp r7, r5",
    "it hi",
    "movhi r7, r5",
    "subs r7, r7, #0x800000",
    "it lo",
    "movlo r7, #0x10000",
    "cmp r7, #0x10000",
    "it lo",
    "movlo r7, #0x10000",
    "clz r1, r7",
    "rsb r2, r1, #27",
    "lsr r5, r7, r2",
    "and r5, r5, #15",
    "rsb r1, r1, #31",
    "add r5, r5, r1, lsl #4",
    "add r5, r5, r5, lsl #1",
    "add r12, r12, r5",
    "asr r11, r12, #5",
    "cmp r11, #4",
    "it gt",
    "movgt r11, #4",
    "bic r11, r11, r11, asr #31",
    // At most the trailing zeros of the chunk's offset from the span's first pixel (none
    // for the first chunk): every chunk inside an aligned chunk of 16.
    "40:",
    "ldr r1, [sp, #40]",
    "subs r1, r1, r3",
    "beq 41f",
    "rbit r1, r1",
    "clz r1, r1",
    "cmp r11, r1",
    "it hi",
    "movhi r11, r1",
    "41:",
    "str r11, [sp, #36]",
    // A chunk of 2^s pixels with more after it: its end values are the next chunk's first.
    "movs r1, #1",
    "lsl r1, r1, r11",
    "subs r12, r3, r1",
    "bls 20f",
    "str r12, [r0, #8]",
    "add r4, r0, #12",
    "ldm r4, {{r5-r10}}",
    "lsl r8, r8, r11",
    "add r5, r5, r8",
    "lsl r9, r9, r11",
    "add r6, r6, r9",
    "lsl r10, r10, r11",
    "add r7, r7, r10",
    "stm r4, {{r5-r7}}",
    lambdas!(),
    corrected!("r4", "36", "40", "44"),
    corrected!("r5", "48", "52", "56"),
    "ldr r3, [sp, #48]",
    "cbz r3, 5f",
    corrected!("r6", "60", "64", "68"),
    "5:",
    "add r3, sp, #24",
    "ldm r3, {{r7-r9}}",
    "stm r3, {{r4-r6}}",
    "ldr r3, [sp, #36]",
    "sub r4, r4, r7",
    "asr r4, r4, r3",
    "sub r5, r5, r8",
    "asr r5, r5, r3",
    "sub r6, r6, r9",
    "asr r6, r6, r3",
    "mov r10, #1",
    "lsl r10, r10, r3",
    "b 8f",
    // The last chunk: r3 = its pixels, r12 = `over` (one less: its end values are at its last
    // pixel).
    "20:",
    "movs r1, #0",
    "str r1, [r0, #8]",
    "subs r12, r3, #1",
    "beq 7f",
    "add r4, r0, #12",
    "ldm r4, {{r5-r10}}",
    "mla r5, r8, r12, r5",
    "mla r6, r9, r12, r6",
    "mla r7, r10, r12, r7",
    lambdas!(),
    corrected!("r4", "36", "40", "44"),
    corrected!("r5", "48", "52", "56"),
    "ldr r3, [sp, #48]",
    "cbz r3, 25f",
    corrected!("r6", "60", "64", "68"),
    "25:",
    "add r3, sp, #24",
    "ldm r3, {{r7-r9}}",
    "sub r4, r4, r7",
    "sub r5, r5, r8",
    "sub r6, r6, r9",
    "movw r3, #65535",
    "add r3, r3, r12",
    "udiv r3, r3, r12",
    step_over!("r4"),
    step_over!("r5"),
    step_over!("r6"),
    "add r10, r12, #1",
    "b 8f",
    // A last chunk of one pixel: no steps.
    "7:",
    "movs r4, #0",
    "movs r5, #0",
    "movs r6, #0",
    "add r3, sp, #24",
    "ldm r3, {{r7-r9}}",
    "mov r10, #1",
    // r4-r6 = the steps of x, y and the level, r7-r9 = their values, r10 = the chunk's pixels;
    // `y` shifted; r2 = the depth pointer past the chunk, r3 = the colour pointer likewise, r1 =
    // the byte offset of the chunk's first pixel from them.
    "8:",
    "ldr r3, [r0, #84]",
    "lsl r8, r8, r3",
    "lsl r5, r5, r3",
    "ldr r2, [r0]",
    "add r2, r2, r10, lsl #1",
    "str r2, [r0]",
    "ldr r3, [r0, #4]",
    "add r3, r3, r2",
    "rsb r1, r10, #0",
    "lsl r1, r1, #1",
    "ldr r11, [sp, #20]",
    perspective_dispatch!(),
    // Unlit: r1 = the offset, r2/r3 = the pointers, r4/r5 = the depth and its step, r6/r7 = x,
    // r8/r9 = y, r10 = the texels, r11 = the column mask, r12 = the row mask.
    "mov r6, r7",
    "mov r7, r4",
    "mov r9, r5",
    "ldr r5, [sp]",
    "ldr r4, [r0, #88]",
    "add lr, r0, #72",
    "ldm lr, {{r10-r12}}",
    unlit_pixels!("2", "4"),
    "b 9f",
    // Lit: the steps to [sp]; the flags `ls` if the level is inside 0..=2¹⁶ at the chunk's
    // first and last pixels and steps by at most 2¹⁶ (then it is inside at every pixel between,
    // and the loop needs no clamp), kept by the moves up to the `bhi`.
    "30:",
    "add r11, sp, #4",
    "stm r11, {{r4-r6}}",
    "sub r11, r10, #1",
    "mla r11, r6, r11, r9",
    "add r6, r6, #65536",
    "cmp r6, #131072",
    "it ls",
    "cmpls r9, #65536",
    "it ls",
    "cmpls r11, #65536",
    // r0-r3 scratch, r4 = the depth, r5 = x, r6 = y, r7 = the level, r8 = the offset, r9/r10 =
    // the pointers, r11 = the texels, r12 = the column mask, lr = the row mask.
    "mov r5, r7",
    "mov r6, r8",
    "mov r7, r9",
    "mov r8, r1",
    "mov r9, r2",
    "mov r10, r3",
    "ldr r4, [r0, #88]",
    "add r1, r0, #72",
    "bhi 36f",
    "ldm r1, {{r11, r12, lr}}",
    "32:",
    textured_texel!("34f"),
    scaled_texel!("r7"),
    lit_step!(),
    "bne 32b",
    "b 9f",
    // The level clamped at each pixel: f = min(max(level, 0), 2¹⁶) in r1.
    "36:",
    "ldm r1, {{r11, r12, lr}}",
    "37:",
    textured_texel!("34f"),
    "bic r1, r7, r7, asr #31",
    "cmp r1, #65536",
    "it hi",
    "movhi r1, #65536",
    scaled_texel!("r1"),
    lit_step!(),
    "bne 37b",
    "b 9f",
    perspective_bilinear!(),
    // The unlit chunks of 16 (entered with the block in r0 and its pixels left in r3): the
    // code above with the length 16 (shift 4) and no level; the last chunk at 75 (two steps,
    // not three), one of a single pixel at 7.
    "70:",
    "subs r12, r3, #16",
    "bls 75f",
    "str r12, [r0, #8]",
    "add r4, r0, #12",
    "ldm r4, {{r5-r10}}",
    "add r5, r5, r8, lsl #4",
    "add r6, r6, r9, lsl #4",
    "add r7, r7, r10, lsl #4",
    "stm r4, {{r5-r7}}",
    lambdas!(),
    unlit_chunk_end!(),
    // x and y at the chunk's first pixel to r6 and r8, their steps to r7 and r5.
    "ldrd r6, r8, [sp, #24]",
    "strd r4, r7, [sp, #24]",
    "sub r4, r4, r6",
    "sub r5, r7, r8",
    "asr r7, r4, #4",
    "asr r5, r5, #4",
    "mov r12, #16",
    "b 76f",
    // The last chunk, `r3` pixels (at most 16): its end values at its last pixel, `over` = r12
    // pixels on (one pixel: no steps, the code's at 7).
    "75:",
    "movs r1, #0",
    "str r1, [r0, #8]",
    "subs r12, r3, #1",
    "beq 7b",
    "add r4, r0, #12",
    "ldm r4, {{r5-r10}}",
    "mla r5, r8, r12, r5",
    "mla r6, r9, r12, r6",
    "mla r7, r10, r12, r7",
    lambdas!(),
    unlit_chunk_end!(),
    "ldrd r6, r8, [sp, #24]",
    "sub r4, r4, r6",
    "sub r5, r7, r8",
    "movw r3, #65535",
    "add r3, r3, r12",
    "udiv r3, r3, r12",
    step_over!("r4"),
    step_over!("r5"),
    "mov r7, r4",
    "add r12, r12, #1",
    // r6/r7 = x and its step, r8 = y, r5 its step, r12 = the chunk's pixels: `y` and its step
    // shifted to r8 and r9; the pointers past the chunk and the offset of its first pixel, as
    // at 8.
    "76:",
    "ldr r3, [r0, #84]",
    "lsl r8, r8, r3",
    "lsl r9, r5, r3",
    "ldr r2, [r0]",
    "add r2, r2, r12, lsl #1",
    "str r2, [r0]",
    "ldr r3, [r0, #4]",
    "add r3, r3, r2",
    "rsb r1, r12, #0",
    "lsl r1, r1, #1",
    "ldrd r4, r5, [r0, #88]",
    "add lr, r0, #72",
    "ldm lr, {{r10-r12}}",
    // The unlit loop at 2, its next chunk this one's.
    unlit_pixels!("73", "74"),
    // The next chunk, if any.
    "ldr r0, [sp, #16]",
    "str r4, [r0, #88]",
    "ldr r3, [r0, #8]",
    "cmp r3, #0",
    "bne 70b",
    "add sp, #52",
    "pop {{r4-r11, pc}}",
    // The depth plane kept for the next chunk; the next chunk, if any.
    "9:",
    "ldr r0, [sp, #16]",
    "str r4, [r0, #88]",
    "ldr r3, [r0, #8]",
    "cmp r3, #0",
    "bne 3b",
    "add sp, #52",
    "pop {{r4-r11, pc}}",
    ".size embedded_raster_perspective_span_v7m, . - embedded_raster_perspective_span_v7m",
);

extern "C" {
    /// The assembly function above.
    ///
    /// # Safety
    ///
    /// `block` is valid for reads and writes; its `left` is at least one and its pointers
    /// address `left` pixels of 2-byte aligned `u16` depths and colours; every index of at most
    /// `rows_mask | x_mask` is inside its texels; `y_shift` is below 32.
    fn embedded_raster_perspective_span_v7m(block: *mut PerspectiveBlock, flags: u32);
}

/// Draws the span `span` into the first pixels of `colors` and `depths` (as many as both
/// have) as [`PerspectiveSpan565`] describes. `false` without drawing anything if a texel
/// index the masks allow is not inside `span.texels`, the shift is not below 32 or `C` is not a
/// 16-bit colour, so no input reads or writes outside them. `C` must be the 5-6-5 format whose
/// raw value is the texels' (the caller's promise: the colours written are those raw values).
#[inline(always)]
pub(crate) fn perspective_span<C: Copy>(
    colors: &mut [C],
    depths: &mut [u16],
    span: &PerspectiveSpan565<'_>,
) -> bool {
    if !masked_texels::<C>(span.texels, span.x_mask, span.rows_mask, &[span.y_shift]) {
        return false;
    }
    let len = colors.len().min(depths.len());
    let Ok(left @ 1..) = u32::try_from(len) else {
        return len == 0;
    };
    let depth_pointer = depths.as_mut_ptr();
    let colors: *mut u16 = colors.as_mut_ptr().cast();
    let (level, lit) = match span.level {
        Some(level) => (level, 1),
        None => ([0; 3], 0),
    };
    // Bilinear where the DSP extension is: the coordinates moved by `−½ + 2⁻⁸` texel (the
    // bilinear loops' point, `bilinear_texel`).
    if span.bilinear && !BILINEAR_ROWS {
        return false;
    }
    let flags = lit | u32::from(span.bilinear) << 1;
    let offset = i32::from(span.bilinear) * BILINEAR_OFFSET;
    let moved = |[base, d1, d2]: [i32; 3]| [base.wrapping_sub(offset), d1, d2];
    let mut block = PerspectiveBlock {
        depths: depth_pointer,
        color_offset: (colors as usize).wrapping_sub(depth_pointer as usize) as u32,
        left,
        planes: span.planes,
        steps: span.steps,
        u: moved(span.u),
        v: moved(span.v),
        level,
        texels: span.texels.as_ptr(),
        x_mask: span.x_mask,
        rows_mask: span.rows_mask,
        y_shift: span.y_shift,
        depth: span.depth.0,
        depth_step: span.depth.1,
        chunk_room: span.chunk_room,
    };
    // SAFETY: `left` (at least one) is at most both buffers' lengths, which the function
    // writes the first `left` entries of, as 2-byte aligned `u16`s (`C` is a 2-byte colour whose
    // raw value the texels are, the caller's promise); it reads texels at indices of at most
    // `rows_mask | x_mask`, inside them, with `y_shift` below 32 (both checked above), reads and
    // writes the block (its own), divides by non-zero values only (`q ≥ 1`, `over ≥ 1`), and
    // saves and restores every register the AAPCS asks it to, its stack frame its own.
    unsafe { embedded_raster_perspective_span_v7m(&mut block, flags) };
    true
}

/// One pixel of the per-vertex alpha pair loop: `$d` holds the pixel's raw value in bits 0-15
/// (bits above: anything, ignored), r7 the transparency factor `f`, r2-r4 the colour planes;
/// the blended pixel goes to the high half of `$acc` (its low half unspecified) as
/// `color::blend`'s `premultiplied_pixel_565` computes it: the top field `(d & 0xF800)·f + top
/// plane` (scaled by 8: the field lands at bits 27-31), the others `⌊(d_field·f·2⁸ + plane) /
/// 2²⁴⌋` inserted at bits 21-26 and 16-20 (`bfi` keeps their low 6 and 5 bits, the channel's
/// mask). `$then` runs once the top field is in `$acc`. Clobbers r7 (left as `f·2⁸`) and `$tmp`.
macro_rules! premultiplied_pixel {
    ($d:literal, $acc:literal, $tmp:literal, $then:literal) => {
        concat!(
            "lsr r7, r5, #9\n",
            "add r7, r7, r7, lsl #8\n",
            "lsr r7, r7, #15\n",
            "and ",
            $acc,
            ", ",
            $d,
            ", #0xF800\n",
            "mla ",
            $acc,
            ", ",
            $acc,
            ", r7, r2\n",
            $then,
            "lsl r7, r7, #8\n",
            "ubfx ",
            $tmp,
            ", ",
            $d,
            ", #5, #6\n",
            "mla ",
            $tmp,
            ", ",
            $tmp,
            ", r7, r3\n",
            "lsr ",
            $tmp,
            ", ",
            $tmp,
            ", #24\n",
            "bfi ",
            $acc,
            ", ",
            $tmp,
            ", #21, #6\n",
            "and ",
            $tmp,
            ", ",
            $d,
            ", #31\n",
            "mla ",
            $tmp,
            ", ",
            $tmp,
            ", r7, r4\n",
            "lsr ",
            $tmp,
            ", ",
            $tmp,
            ", #24\n",
            "bfi ",
            $acc,
            ", ",
            $tmp,
            ", #16, #5\n",
            // The planes stepped a pixel.
            "add r2, r6\n",
            "add r3, r8\n",
            "add r4, r10\n",
            "add r5, r11\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_premultiplied_565_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_premultiplied_565_v7m",
    ".hidden embedded_raster_premultiplied_565_v7m",
    ".type embedded_raster_premultiplied_565_v7m,%function",
    ".thumb_func",
    // r0 = the pixels, r1 = their number (at least one), r2 = the planes: values (top scaled
    // by 8, middle, bottom, transparency) then their steps a pixel.
    "embedded_raster_premultiplied_565_v7m:",
    "push {{r4-r11, lr}}",
    "ldm r2, {{r2, r3, r4, r5, r6, r8, r10, r11}}",
    // A first pixel at 2 mod 4 alone: the pairs are aligned words.
    "tst r0, #2",
    "beq 2f",
    "ldrh r9, [r0]",
    premultiplied_pixel!("r9", "r12", "lr", ""),
    "lsr r12, r12, #16",
    "strh r12, [r0], #2",
    "subs r1, #1",
    "beq 4f",
    "2:",
    "subs r1, #2",
    "blo 3f",
    "1:",
    // r9 = both pixels, the left one in the low half.
    "ldr r9, [r0]",
    premultiplied_pixel!("r9", "r12", "lr", ""),
    // r12 = the left pixel, alone; then the right one, in lr, takes it as its low half.
    "lsr r12, r12, #16",
    "lsr r9, r9, #16",
    premultiplied_pixel!("r9", "lr", "r12", "bfi lr, r12, #0, #16\n"),
    "str lr, [r0], #4",
    "subs r1, #2",
    "bhs 1b",
    // r1 = −1 if a last pixel is left, −2 if not.
    "3:",
    "adds r1, #2",
    "beq 4f",
    "ldrh r9, [r0]",
    premultiplied_pixel!("r9", "r12", "lr", ""),
    "lsr r12, r12, #16",
    "strh r12, [r0]",
    "4:",
    "pop {{r4-r11, pc}}",
    ".size embedded_raster_premultiplied_565_v7m, . - embedded_raster_premultiplied_565_v7m",
);

extern "C" {
    /// The assembly function above.
    ///
    /// # Safety
    ///
    /// `pixels` addresses `len` (at least one) 2-byte aligned `u16`s, readable and writable;
    /// `planes` is readable.
    fn embedded_raster_premultiplied_565_v7m(pixels: *mut u16, len: usize, planes: *const [u32; 8]);
}

/// Blends the 5-6-5 pixels `pixels` (nothing if `C` is not a 16-bit colour) as
/// `color::blend`'s `premultiplied_pixel_565` does each, the planes `value` (raw order: top,
/// middle, bottom field, then transparency) stepped by `step` a pixel, wrapping.
#[inline(always)]
pub(crate) fn premultiplied_565<C>(pixels: &mut [C], value: [u32; 4], step: [u32; 4]) {
    if core::mem::size_of::<C>() != 2 || core::mem::align_of::<C>() != 2 || pixels.is_empty() {
        return;
    }
    // The top plane scaled by 8 (its channel depends on its low 29 bits only).
    let planes = [
        value[0] << 3,
        value[1],
        value[2],
        value[3],
        step[0] << 3,
        step[1],
        step[2],
        step[3],
    ];
    // SAFETY: `pixels` holds `pixels.len()` (at least one) 2-byte aligned 16-bit colours
    // (checked above), which the function reads and writes as `u16`s (pairs a word at a time,
    // from a 4-byte aligned address); it reads the eight words of `planes` and saves and
    // restores every register the AAPCS asks it to.
    unsafe {
        embedded_raster_premultiplied_565_v7m(pixels.as_mut_ptr().cast(), pixels.len(), &planes)
    };
}

/// The two pixels of a word of dithered 5-6-5 lanes (`$t`, `$m`, `$b`: the top, middle and
/// bottom lanes of both pixels) packed into r10: the top field as it is (bits 11-15 of each
/// half), the middle one shifted down 5 (r11 = 0x07E007E0), the bottom one down 11 (r12 =
/// 0x001F001F). Clobbers lr.
macro_rules! dithered_pair {
    ($t:literal, $m:literal, $b:literal) => {
        concat!(
            "and r10, ",
            $t,
            ", #0xF800F800\n",
            "and lr, r11, ",
            $m,
            ", lsr #5\n",
            "orr r10, r10, lr\n",
            "and lr, r12, ",
            $b,
            ", lsr #11\n",
            "orr r10, r10, lr\n",
        )
    };
}

/// One channel's words at a run's start: its value at the run's first pixel (`$v` of the frame
/// in lr) rounded to its lane `l` (`$round`, `$shift`), the word of the lanes of the run's
/// pixels 0 and 1 plus their offsets, `l·0x10001 + K₁`, into `$low` and the word of pixels 2
/// and 3, that plus `K₂`, into `$high`: `K₁` (at `$k1` of the frame) is the lane step shifted
/// up 16 plus the offsets of pixels 0-1, `K₂` (at `$k2`) two lane steps plus the offsets of
/// pixels 2-3 less those of 0-1. Clobbers r10.
#[rustfmt::skip]
macro_rules! dithered_words {
    ($low:literal, $high:literal, $v:literal, $k1:literal, $k2:literal, $round:literal,
     $shift:literal) => {
        concat!(
            "ldr ", $low, ", [lr, #", $v, "]\n",
            "add ", $low, ", ", $low, ", #", $round, "\n",
            "lsr ", $low, ", ", $low, ", #", $shift, "\n",
            "add ", $low, ", ", $low, ", ", $low, ", lsl #16\n",
            "ldr r10, [lr, #", $k1, "]\n",
            "add ", $low, ", ", $low, ", r10\n",
            "ldr r10, [lr, #", $k2, "]\n",
            "add ", $high, ", ", $low, ", r10\n",
        )
    };
}

/// [`embedded_raster_dithered_565_v7m`]'s test of one channel: its value `$v` at the first
/// pixel and at the last (r12 pixels on by its step `$s`) both at least 31/64 LSB and below its
/// maximum plus 33/64 (`$range`: the interval's width); otherwise the span is declined (90). The
/// last one exactly in 64 bits: the first one's offset (below the range, so non-negative) plus
/// the step times r12 by one `smlal`, then one 64-bit unsigned compare (a negative end is a huge
/// one). Clobbers r3 and lr.
#[rustfmt::skip]
macro_rules! dithered_inside {
    ($v:literal, $s:literal, $range:literal) => {
        concat!(
            "sub r3, ", $v, ", #0x7C0000\n",
            "cmp r3, ", $range, "\n",
            "bhs 90f\n",
            "mov lr, #0\n",
            "smlal r3, lr, ", $s, ", r12\n",
            "subs r3, r3, ", $range, "\n",
            "sbcs lr, lr, #0\n",
            "bhs 90f\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_dithered_565_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    ".p2align 2",
    ".global embedded_raster_dithered_565_v7m",
    ".hidden embedded_raster_dithered_565_v7m",
    ".type embedded_raster_dithered_565_v7m,%function",
    ".thumb_func",
    // r0 = pixels (2-byte aligned), r1 = pixel count (at least one), r2 = the span
    // (`DitheredSpan565`). Returns 1 in r0 if drawn, 0 if declined (nothing written).
    "embedded_raster_dithered_565_v7m:",
    "push {{r4-r11, lr}}",
    // [sp]: the bottom lanes' step over four pixels; [sp, #4]: the pixels after the current
    // run; [sp, #8-16]: the values at the run's first pixel; [sp, #20-28]: their steps over a
    // run; [sp, #32-40], [sp, #44-52]: each channel's K₁ and K₂ (`dithered_words`); [sp,
    // #56-60]: the top and middle lanes' steps over four pixels.
    "sub sp, #64",
    // Every lane inside its 16 bits, or declined: the values r4-r6, the steps r7-r9.
    "ldrd r3, lr, [r2]",
    "ldm r3, {{r4-r6}}",
    "add lr, lr, #24",
    "ldm lr, {{r7-r9}}",
    "sub r12, r1, #1",
    "movw r11, #0",
    "movt r11, #0x1F08",
    "add r10, r11, #0x20000000",
    dithered_inside!("r4", "r7", "r11"),
    dithered_inside!("r5", "r8", "r10"),
    dithered_inside!("r6", "r9", "r11"),
    // The span's constants into the frame.
    "lsl r7, r7, #5",
    "lsl r8, r8, #5",
    "lsl r9, r9, #5",
    "add lr, sp, #8",
    "stm lr, {{r4-r9}}",
    // K₁ from the lane steps (r4-r6) and the offsets of pixels 0-1 (r10, the middle lane's
    // halved: r12), K₂ from the double steps (r7-r9) and the offsets' difference (r3, r11).
    "ldr lr, [r2, #4]",
    "ldm lr, {{r4-r9}}",
    "ldrd r10, r11, [r2, #8]",
    "asr r12, r10, #1",
    "add r4, r10, r4, lsl #16",
    "add r5, r12, r5, lsl #16",
    "add r6, r10, r6, lsl #16",
    "add lr, sp, #32",
    "stm lr, {{r4-r6}}",
    "sub r3, r11, r10",
    "asr r11, r11, #1",
    "sub r11, r11, r12",
    "add r4, r7, r3",
    "add r5, r8, r11",
    "add r6, r9, r3",
    "add lr, sp, #44",
    "stm lr, {{r4-r6}}",
    "lsl r7, r7, #1",
    "lsl r8, r8, #1",
    "lsl r9, r9, #1",
    "str r9, [sp]",
    "strd r7, r8, [sp, #56]",
    "movw r11, #0x07E0",
    "movt r11, #0x07E0",
    "mov r12, #0x001F001F",
    // A run: at most 32 pixels from the exactly stepped values.
    "1:",
    "subs r3, r1, #32",
    "it lo",
    "movlo r3, #0",
    "str r3, [sp, #4]",
    "sub r1, r1, r3",
    "mov lr, sp",
    dithered_words!("r2", "r5", "8", "32", "44", "4096", "13"),
    dithered_words!("r3", "r6", "12", "36", "48", "8192", "14"),
    dithered_words!("r4", "r7", "16", "40", "52", "4096", "13"),
    "ldrd r8, r9, [sp, #56]",
    // Four pixels (two words) a pass while there are four.
    "subs r1, #4",
    "blo 5f",
    "4:",
    dithered_pair!("r2", "r3", "r4"),
    "str r10, [r0], #4",
    dithered_pair!("r5", "r6", "r7"),
    "str r10, [r0], #4",
    "ldr lr, [sp]",
    "add r2, r8",
    "add r5, r8",
    "add r3, r9",
    "add r6, r9",
    "add r4, lr",
    "add r7, lr",
    "subs r1, #4",
    "bhs 4b",
    // Then up to three: a word and a pixel of the next, a word, or a pixel.
    "5:",
    "adds r1, #4",
    "beq 8f",
    dithered_pair!("r2", "r3", "r4"),
    "cmp r1, #2",
    "blo 6f",
    "str r10, [r0], #4",
    "beq 8f",
    dithered_pair!("r5", "r6", "r7"),
    "6:",
    "strh r10, [r0], #2",
    // The next run, if any, from the values moved on by a run.
    "8:",
    "ldr r1, [sp, #4]",
    "cbz r1, 9f",
    "add lr, sp, #8",
    "ldm lr, {{r2-r7}}",
    "add r2, r5",
    "add r3, r6",
    "add r4, r7",
    "stm lr, {{r2-r4}}",
    "b 1b",
    "9:",
    "movs r0, #1",
    "add sp, #64",
    "pop {{r4-r11, pc}}",
    "90:",
    "movs r0, #0",
    "add sp, #64",
    "pop {{r4-r11, pc}}",
    ".size embedded_raster_dithered_565_v7m, . - embedded_raster_dithered_565_v7m",
);

extern "C" {
    /// The assembly function above.
    ///
    /// # Safety
    ///
    /// `pixels` addresses `len` (at least one) 2-byte aligned `u16`s; `span` is valid for
    /// reads.
    fn embedded_raster_dithered_565_v7m(
        pixels: *mut u16,
        len: usize,
        span: *const DitheredSpan565<'_>,
    ) -> u32;
}

/// Draws the dithered 5-6-5 span `span` into `pixels`, as [`DitheredSpan565`] describes it,
/// with runs of 32 pixels, if every lane stays inside its 16 bits (its values at the first and
/// last pixel in `[31/64, max + 33/64)` LSB); `false` without writing anything otherwise, or
/// if `C` is not a 16-bit colour.
#[inline(always)]
pub(crate) fn dithered_565<C>(pixels: &mut [C], span: &DitheredSpan565<'_>) -> bool {
    if core::mem::size_of::<C>() != 2 || core::mem::align_of::<C>() != 2 {
        return false;
    }
    if pixels.is_empty() {
        return true;
    }
    // SAFETY: `pixels` holds `pixels.len()` (at least one) 2-byte aligned 16-bit colours
    // (checked above), which the function writes as `u16`s (two at a time as a word, which
    // ARMv7-M stores at any address); it reads `span`, the arrays it refers to and its own
    // stack frame, and saves and
    // restores every register the AAPCS asks it to.
    unsafe { embedded_raster_dithered_565_v7m(pixels.as_mut_ptr().cast(), pixels.len(), span) != 0 }
}

/// Whether the loops may draw `C` from `texels` with these masks and shifts: `C` a 2-byte colour
/// (the 5-6-5 raw value the texels are), every index `row | column` (at most `rows_mask |
/// x_mask`) inside the texels, every shift below 32.
#[inline(always)]
fn masked_texels<C>(texels: &[u16], x_mask: u32, rows_mask: u32, shifts: &[u32]) -> bool {
    let colour = core::mem::size_of::<C>() == 2 && core::mem::align_of::<C>() == 2;
    let last = (rows_mask | x_mask) as usize;
    colour && last < texels.len() && shifts.iter().all(|&s| s <= 31)
}

/// The row stride in bytes of a region of `rows` inside buffers of `len` pixels, if it is
/// inside them and the stride fits 32 bits.
#[inline(always)]
fn region_stride(len: usize, rows: &LevelRows) -> Option<u32> {
    let (columns, count) = (rows.columns as usize, rows.rows as usize);
    let wide = |n: usize| n as u64;
    let last = wide(rows.first)
        + wide(count.wrapping_sub(1)) * wide(rows.width)
        + wide(columns.wrapping_sub(1));
    let inside = columns >= 1 && count >= 1 && columns <= rows.width && last < wide(len);
    if !inside {
        return None;
    }
    u32::try_from(rows.width.checked_mul(2)?).ok()
}

/// Two 5-6-5 pixels in `$d` (the right one in the high half) under the constant colour: r2 =
/// `256 − w`, r3 = the top field's `s·w + 128` times 8, r4 and r5 the middle and bottom fields'
/// (each in both halves of its word), r6 = 0x00F800F8, r7 = 0x003F003F; `$t` and `$m` are
/// clobbered. The top fields are taken 8 times their value (`(d >> 8) & 0x00F800F8`), so their
/// blended values land in place (bits 11–15 of each lane: `8·v < 2¹⁶` for `v ≤ 31·256 + 128`);
/// the middle and bottom lanes' blended values are bits 8–15 of theirs, which `uxtb16` and
/// `uxtab16` take (below 64, so the bytes hold them), the bottom one added into the lanes'
/// clear low bits: 10 instructions.
#[cfg(arm_dsp)]
#[rustfmt::skip]
macro_rules! blend_pair_v7m {
    ($d:literal, $t:literal, $m:literal) => {
        concat!(
            "and ", $t, ", r6, ", $d, ", lsr #8\n",
            "and ", $m, ", r7, ", $d, ", lsr #5\n",
            "and ", $d, ", ", $d, ", #0x001F001F\n",
            "mla ", $t, ", ", $t, ", r2, r3\n",
            "mla ", $m, ", ", $m, ", r2, r4\n",
            "mla ", $d, ", ", $d, ", r2, r5\n",
            "and ", $t, ", ", $t, ", #0xF800F800\n",
            "uxtb16 ", $m, ", ", $m, ", ror #8\n",
            "orr ", $t, ", ", $t, ", ", $m, ", lsl #5\n",
            "uxtab16 ", $d, ", ", $t, ", ", $d, ", ror #8\n",
        )
    };
}

/// The same on the Cortex-M3, which has no `uxtb16`/`uxtab16`: the middle and bottom lanes'
/// values taken with the mask 0x003F003F (the bottom ones are below 32) and the bottom ones
/// or'ed in: 11 instructions.
#[cfg(not(arm_dsp))]
#[rustfmt::skip]
macro_rules! blend_pair_v7m {
    ($d:literal, $t:literal, $m:literal) => {
        concat!(
            "and ", $t, ", r6, ", $d, ", lsr #8\n",
            "and ", $m, ", r7, ", $d, ", lsr #5\n",
            "and ", $d, ", ", $d, ", #0x001F001F\n",
            "mla ", $t, ", ", $t, ", r2, r3\n",
            "mla ", $m, ", ", $m, ", r2, r4\n",
            "mla ", $d, ", ", $d, ", r2, r5\n",
            "and ", $t, ", ", $t, ", #0xF800F800\n",
            "and ", $m, ", r7, ", $m, ", lsr #8\n",
            "orr ", $t, ", ", $t, ", ", $m, ", lsl #5\n",
            "and ", $d, ", r7, ", $d, ", lsr #8\n",
            "orr ", $d, ", ", $d, ", ", $t, "\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_blend_565_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_blend_565_v7m",
    ".hidden embedded_raster_blend_565_v7m",
    ".type embedded_raster_blend_565_v7m,%function",
    ".thumb_func",
    // r0 = pixels (2-byte aligned), r1 = pixel count, r2 = the weights: 256 − w and the top,
    // middle and bottom fields' s·w + 128 in both halves.
    "embedded_raster_blend_565_v7m:",
    "push {{r4-r11, lr}}",
    "ldm r2, {{r2, r3, r4, r5}}",
    "lsl r3, r3, #3",
    "mov r6, #0x00F800F8",
    "mov r7, #0x003F003F",
    // A first pixel at an address of 2 mod 4 alone (no pixels: nothing to do; from an aligned
    // address the count goes through the loops' tests as none).
    "tst r0, #2",
    "beq 1f",
    "cmp r1, #0",
    "it eq",
    "popeq {{r4-r11, pc}}",
    "ldrh r8, [r0]",
    blend_pair_v7m!("r8", "r12", "lr"),
    "strh r8, [r0], #2",
    "subs r1, #1",
    "1:",
    // Eight pixels (four words) a pass while there are eight.
    "subs r1, #8",
    "blo 3f",
    "2:",
    "ldm r0, {{r8-r11}}",
    blend_pair_v7m!("r8", "r12", "lr"),
    blend_pair_v7m!("r9", "r12", "lr"),
    blend_pair_v7m!("r10", "r12", "lr"),
    blend_pair_v7m!("r11", "r12", "lr"),
    "stm r0!, {{r8-r11}}",
    "subs r1, #8",
    "bhs 2b",
    // Then a word at a time, and a last pixel alone.
    "3:",
    "adds r1, #6",
    "blo 5f",
    "4:",
    "ldr r8, [r0]",
    blend_pair_v7m!("r8", "r12", "lr"),
    "str r8, [r0], #4",
    "subs r1, #2",
    "bhs 4b",
    "5:",
    "tst r1, #1",
    "beq 6f",
    "ldrh r8, [r0]",
    blend_pair_v7m!("r8", "r12", "lr"),
    "strh r8, [r0]",
    "6:",
    "pop {{r4-r11, pc}}",
    ".size embedded_raster_blend_565_v7m, . - embedded_raster_blend_565_v7m",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_blend_565_v7m(pixels: *mut u16, len: usize, weights: *const [u32; 4]);
}

/// Blends the constant colour of `weights` over every pixel of `pixels`, 5-6-5 colours (one
/// `u16` each, every raw value a colour: `C: From<RawU16>`): `weights` are `256 − w` and the raw top, middle and bottom
/// fields' `s·w + 128`, each in both halves of its word (`s·w + 128 ≤ 63·256 + 128`, the top
/// one at most `31·256 + 128`). Each field becomes `(pre + d·(256 − w)) >> 8`, as
/// `color::blend`'s portable loop gives it. `false` without writing anything if `C` is not a
/// 16-bit colour.
#[inline(always)]
pub(crate) fn blend_solid_565<C: From<RawU16>>(pixels: &mut [C], weights: &[u32; 4]) -> bool {
    if core::mem::size_of::<C>() != 2 || core::mem::align_of::<C>() != 2 {
        return false;
    }
    // SAFETY: the function reads and writes exactly `pixels.len()` consecutive 2-byte aligned
    // `u16`s from the slice's start, which are the slice's own (a 5-6-5 colour is one `u16`,
    // any bits a colour), words and `ldm`/`stm` blocks only at 4-byte aligned addresses, and
    // reads the four words of `weights`. It saves and restores every register the AAPCS asks
    // it to.
    unsafe { embedded_raster_blend_565_v7m(pixels.as_mut_ptr().cast(), pixels.len(), weights) }
    true
}

/// One edge's bound of a row's run (`raster::runs::RowRuns`'s), written into the block's next
/// start slot (r10, moving up from slot 0) or next end slot (r1, moving down from slot 2): `$a`,
/// `$b` are the edge's coefficients, `$v` its value at the first pixel centre (sub-pixels),
/// `$u` a scratch register. The fill rule's bias (1 unless `a > 0`, or `a = 0` and `b > 0`)
/// comes off `$v` before the value is reduced to whole pixels (`asr #8`).
#[rustfmt::skip]
macro_rules! edge_bound {
    ($a:literal, $b:literal, $v:literal, $u:literal, $div:literal, $step:literal, $num:literal) => {
        concat!(
            "cmp ", $a, ", #0\n",
            "ble 11f\n",
            // a > 0: a start bound, ⌊(a − 1 − k)/a⌋, the numerator less b a row.
            "str ", $a, ", [r10, #", $div, "]\n",
            "rsb ", $u, ", ", $b, ", #0\n",
            "str ", $u, ", [r10, #", $step, "]\n",
            "sub ", $u, ", ", $a, ", #1\n",
            "sub ", $u, ", ", $u, ", ", $v, ", asr #8\n",
            "str ", $u, ", [r10, #", $num, "]\n",
            "add r10, r10, #4\n",
            "b 13f\n",
            "11:\n",
            "beq 12f\n",
            // a < 0: an end bound, ⌊(k + |a|)/|a|⌋, the numerator plus b a row.
            "rsb ", $u, ", ", $a, ", #0\n",
            "str ", $u, ", [r1, #", $div, "]\n",
            "str ", $b, ", [r1, #", $step, "]\n",
            "sub ", $u, ", ", $v, ", #1\n",
            "asr ", $u, ", ", $u, ", #8\n",
            "sub ", $u, ", ", $u, ", ", $a, "\n",
            "str ", $u, ", [r1, #", $num, "]\n",
            "sub r1, r1, #4\n",
            "b 13f\n",
            "12:\n",
            // a = 0: a start bound −16·k over 1, the numerator less 16·b a row.
            "mov ", $u, ", #1\n",
            "str ", $u, ", [r10, #", $div, "]\n",
            "rsb ", $u, ", ", $b, ", #0\n",
            "lsl ", $u, ", ", $u, ", #4\n",
            "str ", $u, ", [r10, #", $step, "]\n",
            "mov ", $u, ", ", $v, "\n",
            "cmp ", $b, ", #0\n",
            "it le\n",
            "suble ", $u, ", ", $u, ", #1\n",
            "asr ", $u, ", ", $u, ", #8\n",
            "rsb ", $u, ", ", $u, ", #0\n",
            "lsl ", $u, ", ", $u, ", #4\n",
            "str ", $u, ", [r10, #", $num, "]\n",
            "add r10, r10, #4\n",
            "13:\n",
        )
    };
}

/// One attribute's vertex values (the `u16` at `$at` of each vertex, the oriented vertices'
/// addresses in r1-r3), its differences from vertex 0 stored at `$d` (d1, d2), its value term
/// (`base·2¹⁶ + half`, the half at `$half` of the face) at `$base`, and its numerators `nx =
/// d1·a1 + d2·a2`, `ny = d1·b1 + d2·b2` (the edges opposite oriented vertices 1 and 2: r6-r9 =
/// o1x, o1y, o2x, o2y) at `$n`, each numerator's magnitude (less one if negative: `n ^ (n >>
/// 31)`) or-ed into lr for [`numerators_within`]. Keeps r1-r3; clobbers r4, r5 and r10-r12.
#[rustfmt::skip]
macro_rules! attribute_numerators {
    ($at:literal, $d:literal, $half:literal, $base:literal, $n:literal) => {
        concat!(
            "ldrh r4, [r1, #", $at, "]\n",
            "ldrh r5, [r2, #", $at, "]\n",
            "ldrh r10, [r3, #", $at, "]\n",
            "sub r5, r5, r4\n",
            "sub r10, r10, r4\n",
            "strd r5, r10, [sp, #", $d, "]\n",
            "ldr r11, [r0, #", $half, "]\n",
            "add r4, r11, r4, lsl #16\n",
            "str r4, [sp, #", $base, "]\n",
            "mul r11, r5, r9\n",
            "mls r11, r10, r7, r11\n",
            "mul r12, r10, r6\n",
            "mls r12, r5, r8, r12\n",
            "strd r11, r12, [sp, #", $n, "]\n",
            "eor r4, r11, r11, asr #31\n",
            "orr lr, lr, r4\n",
            "eor r4, r12, r12, asr #31\n",
            "orr lr, lr, r4\n",
        )
    };
}

/// After the faces' [`attribute_numerators`] (lr = their magnitudes or-ed, from 0): declines the
/// face (90) unless every numerator is within the limit (r5, then r5 − 1): `|n| < limit` for
/// each where the or is below `limit − 1` (a magnitude taken one less, `|n| − 1`, for a negative
/// `n`). Where every `|n|` is below the limit but their or is not, the face is declined too
/// (the portable set-up draws it): only with a numerator of at least half the limit.
#[rustfmt::skip]
macro_rules! numerators_within {
    () => {
        concat!(
            "sub r5, r5, #1\n",
            "cmp lr, r5\n",
            "bhs 90f\n",
        )
    };
}

/// `$out = (n·r + 2^(s−1)) >> s` (low word) for `n` in `$n`: r9 = r, r10 = 2^(s−1), r11 = s,
/// r8 = 32 − s; r5, r6 scratch.
#[rustfmt::skip]
macro_rules! scaled_by_r {
    ($n:literal, $out:literal) => {
        concat!(
            "smull r5, r6, ", $n, ", r9\n",
            "adds r5, r5, r10\n",
            "adc r6, r6, #0\n",
            "lsr r5, r5, r11\n",
            "lsl r6, r6, r8\n",
            "orr ", $out, ", r5, r6\n",
        )
    };
}

/// One attribute's plane into the block: its value at the first pixel (`(d1·b1 + d2·b2 + 2⁷)
/// >> 8` plus the value term at `$base`; r3, r2 = b1, b2) at `$value`, its steps a column and a
/// row (the numerators at `$n` scaled by r) at `$column` and `$row`.
#[rustfmt::skip]
macro_rules! attribute_plane {
    ($d:literal, $base:literal, $n:literal, $value:literal, $column:literal, $row:literal) => {
        concat!(
            "ldrd r1, r4, [sp, #", $d, "]\n",
            "smull r5, r6, r1, r3\n",
            "smlal r5, r6, r4, r2\n",
            "adds r5, r5, #128\n",
            "adc r6, r6, #0\n",
            "lsr r5, r5, #8\n",
            "orr r5, r5, r6, lsl #24\n",
            "ldr r1, [sp, #", $base, "]\n",
            "add r5, r5, r1\n",
            "str r5, [sp, #", $value, "]\n",
            "ldrd r1, r4, [sp, #", $n, "]\n",
            scaled_by_r!("r1", "r1"),
            "str r1, [sp, #", $column, "]\n",
            scaled_by_r!("r4", "r4"),
            "str r4, [sp, #", $row, "]\n",
        )
    };
}

/// One digit `⌊rem·2¹⁶/d⌋` of the reciprocal's schoolbook division (`raster::arith`'s
/// `reciprocal_63_by_digits`): `$rem` = rem (below d), `$high` = d's top half, `$d` = d; the
/// digit in `$q`, the next remainder (low word) in `$rem`. The estimate `rem/high` is at most two
/// above the digit: it comes down by one for each of `q·d > rem·2¹⁶` and `q·d > rem·2¹⁶ + d`
/// (64-bit compares; `$pl`, `$ph` = q·d, `$sl`, `$sh` = rem·2¹⁶ plus what has been taken off,
/// `$t` scratch). The face set-ups' registers by default: r1 = rem, r3 = high, r12 = d, r5-r8 and
/// r10.
#[rustfmt::skip]
macro_rules! reciprocal_digit {
    ($q:literal) => {
        reciprocal_digit!($q, "r1", "r3", "r12", "r5", "r6", "r7", "r8", "r10")
    };
    ($q:literal, $rem:literal, $high:literal, $d:literal, $pl:literal, $ph:literal,
     $sl:literal, $sh:literal, $t:literal) => {
        concat!(
            "udiv ", $q, ", ", $rem, ", ", $high, "\n",
            "umull ", $pl, ", ", $ph, ", ", $q, ", ", $d, "\n",
            "lsl ", $sl, ", ", $rem, ", #16\n",
            "lsr ", $sh, ", ", $rem, ", #16\n",
            "subs ", $t, ", ", $sl, ", ", $pl, "\n",
            "sbcs ", $t, ", ", $sh, ", ", $ph, "\n",
            "bhs 14f\n",
            "sub ", $q, ", ", $q, ", #1\n",
            "adds ", $sl, ", ", $sl, ", ", $d, "\n",
            "adc ", $sh, ", ", $sh, ", #0\n",
            "subs ", $t, ", ", $sl, ", ", $pl, "\n",
            "sbcs ", $t, ", ", $sh, ", ", $ph, "\n",
            "bhs 14f\n",
            "sub ", $q, ", ", $q, ", #1\n",
            "add ", $sl, ", ", $sl, ", ", $d, "\n",
            "14:\n",
            "sub ", $rem, ", ", $sl, ", ", $pl, "\n",
        )
    };
}

/// `$lo` = the least and `$hi` the greatest of `$a`, `$b`, `$d` (`$lt`, `$gt` = "lt", "gt"
/// signed or "lo", "hi" unsigned; `$lo`, `$hi` other registers): 12 instructions.
#[rustfmt::skip]
macro_rules! minmax3 {
    ($lo:literal, $hi:literal, $a:literal, $b:literal, $d:literal, $lt:literal, $gt:literal) => {
        concat!(
            "mov ", $lo, ", ", $a, "\n",
            "mov ", $hi, ", ", $b, "\n",
            "cmp ", $a, ", ", $b, "\n",
            "itt ", $gt, "\n",
            "mov", $gt, " ", $lo, ", ", $b, "\n",
            "mov", $gt, " ", $hi, ", ", $a, "\n",
            "cmp ", $d, ", ", $lo, "\n",
            "it ", $lt, "\n",
            "mov", $lt, " ", $lo, ", ", $d, "\n",
            "cmp ", $d, ", ", $hi, "\n",
            "it ", $gt, "\n",
            "mov", $gt, " ", $hi, ", ", $d, "\n",
        )
    };
}

/// The face set-up's first part, as `raster::scan` computes it: the oriented vertices' addresses
/// (r1-r3 after `$load`) at `$ptrs` (and `$ptrs1`, 4 more), the box and the 16-px test,
/// the region inside the clip (r0's words at 12-24; its first column at `$x0`, first and last
/// rows at `$y0`, columns at `$columns`, rows at `$rows`), the doubled area (r4, made positive,
/// the vertices' addresses swapped for a negative one), the edges' bounds into the block (their
/// divisors at `$divisors`, steps a row at `$steps` and numerators at `$numerators`, starts
/// from slot 0, ends from slot 2), whether the middle bound starts at `$ms`, the edge values
/// l1, l2 at `$l12`, and the numerators' limit in r5; done (80) or declined (90) on the way;
/// r6-r9 = o1x, o1y, o2x, o2y after it. The word at `$inside` is left non-zero where the clip
/// cut no column off the region (then a row's run, if not empty, lies within the region's
/// columns: its pixel centres are the triangle's, inside the box), 0 where it did (the columns
/// are clipped by [`face_scan_clips`], which the function places out of the way).
#[rustfmt::skip]
macro_rules! face_scan {
    ($load:literal, $ptrs:literal, $ptrs1:literal, $x0:literal, $y0:literal, $columns:literal,
     $rows:literal, $divisors:literal, $steps:literal, $numerators:literal, $ms:literal,
     $l12:literal, $inside:literal) => {
        concat!(
            $load,
            "str r0, [sp, #", $inside, "]\n",
            "add r4, sp, #", $ptrs, "\n",
            "stm r4, {{r1, r2, r3}}\n",
            "ldrd r4, r5, [r1]\n",
            "ldrd r6, r7, [r2]\n",
            "ldrd r8, r9, [r3]\n",
            // The box: r10, r11 = least and greatest x, r1, r2 = y; each extent below 16 pixels.
            minmax3!("r10", "r11", "r4", "r6", "r8", "lt", "gt"),
            minmax3!("r1", "r2", "r5", "r7", "r9", "lt", "gt"),
            "sub r3, r11, r10\n",
            "cmp r3, #4096\n",
            "bhs 90f\n",
            "sub r3, r2, r1\n",
            "cmp r3, #4096\n",
            "bhs 90f\n",
            // The region: pixels whose centres are in the box, inside the clip (r10-r11 columns, r1-r2
            // rows; a first one `x >> 8`, one more if `x`'s fraction is past ½ — the carry of
            // comparing it with 129 —, a last one `x >> 8`, one less if the fraction is below ½);
            // none: done.
            "uxtb r3, r10\n",
            "asr r10, r10, #8\n",
            "cmp r3, #0x81\n",
            "adc r10, r10, #0\n",
            "ldr r3, [r0, #12]\n",
            "cmp r10, r3\n",
            "blt 71f\n",
            "72:\n",
            "uxtb r3, r11\n",
            "asr r11, r11, #8\n",
            "cmp r3, #0x80\n",
            "sbc r11, r11, #0\n",
            "ldr r3, [r0, #20]\n",
            "cmp r11, r3\n",
            "bgt 73f\n",
            "74:\n",
            "cmp r10, r11\n",
            "bgt 80f\n",
            "uxtb r3, r1\n",
            "asr r1, r1, #8\n",
            "cmp r3, #0x81\n",
            "adc r1, r1, #0\n",
            "ldr r3, [r0, #16]\n",
            "cmp r1, r3\n",
            "it lt\n",
            "movlt r1, r3\n",
            "uxtb r3, r2\n",
            "asr r2, r2, #8\n",
            "cmp r3, #0x80\n",
            "sbc r2, r2, #0\n",
            "ldr r3, [r0, #24]\n",
            "cmp r2, r3\n",
            "it gt\n",
            "movgt r2, r3\n",
            "cmp r1, r2\n",
            "bgt 80f\n",
            // The region: its first column and row, last row (the band's rows are taken at the end),
            // columns and rows.
            "str r10, [sp, #", $x0, "]\n",
            "strd r1, r2, [sp, #", $y0, "]\n",
            "sub r3, r11, r10\n",
            "add r3, r3, #1\n",
            "str r3, [sp, #", $columns, "]\n",
            "sub r3, r2, r1\n",
            "add r3, r3, #1\n",
            "str r3, [sp, #", $rows, "]\n",
            // The first pixel centre relative to vertex 0 (r10, r1), the other vertices too (r6-r9),
            // and the doubled area (r4): none, done; negative, vertices 1 and 2 swapped (and their
            // addresses).
            "lsl r10, r10, #8\n",
            "add r10, r10, #128\n",
            "sub r10, r10, r4\n",
            "lsl r1, r1, #8\n",
            "add r1, r1, #128\n",
            "sub r1, r1, r5\n",
            "sub r6, r6, r4\n",
            "sub r7, r7, r5\n",
            "sub r8, r8, r4\n",
            "sub r9, r9, r5\n",
            "mul r4, r6, r9\n",
            "mls r4, r7, r8, r4\n",
            "cmp r4, #0\n",
            "beq 80f\n",
            "bgt 1f\n",
            "rsb r4, r4, #0\n",
            "mov r3, r6\n",
            "mov r6, r8\n",
            "mov r8, r3\n",
            "mov r3, r7\n",
            "mov r7, r9\n",
            "mov r9, r3\n",
            "ldrd r2, r3, [sp, #", $ptrs1, "]\n",
            "strd r3, r2, [sp, #", $ptrs1, "]\n",
            "1:\n",
            // The edges' values at the first pixel: r2 = l1 (the edge from o2 to vertex 0), r3 = l2
            // (from vertex 0 to o1), r5 = the edge from o1 to o2's.
            "sub r2, r10, r8\n",
            "mul r2, r9, r2\n",
            "sub r3, r1, r9\n",
            "mls r2, r8, r3, r2\n",
            "mul r3, r6, r1\n",
            "mls r3, r7, r10, r3\n",
            "sub r11, r7, r9\n",
            "sub r12, r8, r6\n",
            "sub r5, r10, r6\n",
            "mul r5, r11, r5\n",
            "sub lr, r1, r7\n",
            "mla r5, r12, lr, r5\n",
            // The runs' bounds, starts from slot 0 up (r10), ends from slot 2 down (r1).
            "mov r10, sp\n",
            "add r1, sp, #8\n",
            edge_bound!("r11", "r12", "r5", "lr", $divisors, $steps, $numerators),
            "rsb r11, r8, #0\n",
            edge_bound!("r9", "r11", "r2", "r12", $divisors, $steps, $numerators),
            "rsb r11, r7, #0\n",
            edge_bound!("r11", "r6", "r3", "r12", $divisors, $steps, $numerators),
            "mov r12, sp\n",
            "sub r10, r10, r12\n",
            "lsr r10, r10, #3\n",
            "str r10, [sp, #", $ms, "]\n",
            "strd r2, r3, [sp, #", $l12, "]\n",
            // Steps of at most 2¹⁴ a pixel: the numerators' limit (r5), area·2¹⁴ (2³⁰ from 2¹⁶ up).
            "cmp r4, #0x10000\n",
            "ite lo\n",
            "lsllo r5, r4, #14\n",
            "movhs r5, #0x40000000\n",
        )
    };
}

/// [`face_scan`]'s columns clipped (the first at 71, the last at 73), each then marking the word
/// at `$inside` 0 and going back.
#[rustfmt::skip]
macro_rules! face_scan_clips {
    ($inside:literal) => {
        concat!(
            "71:\n",
            "mov r10, r3\n",
            "movs r3, #0\n",
            "str r3, [sp, #", $inside, "]\n",
            "b 72b\n",
            "73:\n",
            "mov r11, r3\n",
            "movs r3, #0\n",
            "str r3, [sp, #", $inside, "]\n",
            "b 74b\n",
        )
    };
}

/// The area's reciprocal and the barycentrics at the first pixel, as `raster::scan`'s
/// `small_planes`: r = ⌊2⁶³/d⌋ / 2 in r9, s in r11, 2^(s−1) in r10, 32 − s in r8, b1 in r3 and
/// b2 in r2 (l1, l2 read at `$l12`); a sliver declines (90).
#[rustfmt::skip]
macro_rules! face_reciprocal {
    ($l12:literal) => {
        concat!(
            // r = ⌊2⁶³/d⌋ / 2 for the area normalised, d = area·2ᵗ ≥ 2³¹ (2³¹ − 1 for d = 2³¹), in r9;
            // s = 38 − t in r11.
            "clz r11, r4\n",
            "lsl r12, r4, r11\n",
            "rsb r11, r11, #38\n",
            "cmp r12, #0x80000000\n",
            "bne 2f\n",
            "mvn r9, #0x80000000\n",
            "b 3f\n",
            "2:\n",
            "lsr r3, r12, #16\n",
            "mov r1, #0x80000000\n",
            reciprocal_digit!("r4"),
            reciprocal_digit!("r9"),
            "orr r9, r9, r4, lsl #16\n",
            "lsr r9, r9, #1\n",
            "3:\n",
            // r10 = 2^(s−1), r8 = 32 − s. The barycentrics of oriented vertices 1 and 2 at the first
            // pixel, b1 = r3 and b2 = r2 (a sliver, whose (l·r) >> (s + 29) is not −1 or 0, declines).
            "sub r10, r11, #1\n",
            "mov r5, #1\n",
            "lsl r10, r5, r10\n",
            "rsb r8, r11, #32\n",
            "ldrd r1, r2, [sp, #", $l12, "]\n",
            "sub r7, r11, #3\n",
            "smull r3, r4, r1, r9\n",
            "asr r5, r4, r7\n",
            "adds r5, r5, #1\n",
            "cmp r5, #1\n",
            "bhi 90f\n",
            "smull r1, r12, r2, r9\n",
            "asr r5, r12, r7\n",
            "adds r5, r5, #1\n",
            "cmp r5, #1\n",
            "bhi 90f\n",
            "adds r3, r3, r10\n",
            "adc r4, r4, #0\n",
            "lsr r3, r3, r11\n",
            "lsl r4, r4, r8\n",
            "orr r3, r3, r4\n",
            "adds r1, r1, r10\n",
            "adc r12, r12, #0\n",
            "lsr r1, r1, r11\n",
            "lsl r12, r12, r8\n",
            "orr r2, r1, r12\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_level_face_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_level_face_v7m",
    ".hidden embedded_raster_level_face_v7m",
    ".type embedded_raster_level_face_v7m,%function",
    ".thumb_func",
    // r0 = the face (`LevelFace`). Returns 0 if done (drawn, or nothing to draw), 1 if declined
    // (not small, or a sliver): nothing drawn; 2 if, given a set-up to fill, it wrote it (the
    // rows in the face's rows drawn, if any). The frame: the row loop's block at sp (84
    // bytes), then scratch: 84, 88 = l1, l2 (the edge values of oriented vertices 1 and 2 at
    // the first pixel); 92 = whether the middle bound starts; 96-108 = the depth's and the
    // level's d1, d2; 112-124 = their nx, ny; 128, 132 = their value terms; 136-144 = the
    // oriented vertices' addresses; 148, 152, 156 = the region's first column, first and last
    // rows; 160 = the result once drawn; 164 = whether the clip left the region's columns whole
    // (`face_scan`'s); 168, 172 = the area and the numerators' limit while the numerators are
    // found; 176..180 unused (the frame's 8-byte alignment).
    "embedded_raster_level_face_v7m:",
    "push {{r4-r11, lr}}",
    "sub sp, #180",
    face_scan!(
        "ldm r0, {{r1, r2, r3}}\n",
        "136",
        "140",
        "148",
        "152",
        "48",
        "80",
        "36",
        "24",
        "68",
        "92",
        "84",
        "164"
    ),
    "movs lr, #0",
    // The two attributes' numerators with the oriented vertices' addresses held in r1-r3 (the
    // area and the limit kept at 168 meanwhile).
    "strd r4, r5, [sp, #168]",
    "ldr r1, [sp, #136]",
    "ldrd r2, r3, [sp, #140]",
    attribute_numerators!("8", "96", "44", "128", "112"),
    attribute_numerators!("12", "104", "48", "132", "120"),
    "ldrd r4, r5, [sp, #168]",
    numerators_within!(),
    face_reciprocal!("84"),
    // The depth and level planes, then the rows; and, given a set-up to fill (a band's draw),
    // first the block, the region's first pixel and whether the middle bound starts there.
    attribute_plane!("96", "128", "112", "0", "52", "12"),
    attribute_plane!("104", "132", "120", "4", "56", "16"),
    // Given a set-up to fill (a band's draw keeping it for the bands below), the block over the
    // clip, the region's first pixel and whether the middle bound starts; the result (at sp +
    // 160) then 2, else 0.
    "ldr r2, [r0, #52]",
    "movs r3, #0",
    "str r3, [sp, #160]",
    "cbz r2, 4f",
    // (The buffer words are found after: zeros in the set-up, not the stack's leftovers.)
    "str r3, [sp, #8]",
    "str r3, [sp, #20]",
    "strd r3, r3, [sp, #60]",
    "mov r3, sp",
    "ldm r3!, {{r4-r11}}",
    "stm r2!, {{r4-r11}}",
    "ldm r3!, {{r4-r11}}",
    "stm r2!, {{r4-r11}}",
    "ldm r3!, {{r4-r8}}",
    "stm r2!, {{r4-r8}}",
    "ldr r4, [sp, #148]",
    "ldr r5, [sp, #152]",
    "ldr r6, [sp, #92]",
    "stm r2!, {{r4-r6}}",
    "movs r3, #2",
    "str r3, [sp, #160]",
    "4:",
    // The band's rows (r4 = its first, r5 = its last) of the region's (r1 = first, r3 =
    // last): rows above it skipped (the numerators and planes stepped by r6 rows), none in it,
    // done. Rows counted from the band's first in the buffers.
    "ldrd r1, r3, [sp, #152]",
    "ldrd r4, r5, [r0, #56]",
    "cmp r1, r4",
    "bge 6f",
    "cmp r3, r4",
    "blt 81f",
    "sub r6, r4, r1",
    "mov r1, r4",
    "ldrd r7, r8, [sp, #24]",
    "ldrd r9, r10, [sp, #68]",
    "mla r9, r7, r6, r9",
    "mla r10, r8, r6, r10",
    "strd r9, r10, [sp, #68]",
    "ldr r7, [sp, #32]",
    "ldr r9, [sp, #76]",
    "mla r9, r7, r6, r9",
    "str r9, [sp, #76]",
    "ldrd r7, r8, [sp, #12]",
    "ldrd r9, r10, [sp, #0]",
    "mla r9, r7, r6, r9",
    "mla r10, r8, r6, r10",
    "strd r9, r10, [sp, #0]",
    "6:",
    "cmp r3, r5",
    "it gt",
    "movgt r3, r5",
    "cmp r1, r3",
    "bgt 81f",
    "sub r3, r3, r1",
    "add r3, r3, #1",
    "str r3, [sp, #80]",
    "sub r1, r1, r4",
    // The stride, the buffers at the first pixel, the table; then the rows.
    "ldr r3, [r0, #36]",
    "str r3, [sp, #20]",
    "mul r3, r3, r1",
    "ldr r6, [sp, #148]",
    "add r3, r3, r6, lsl #1",
    "ldrd r11, r12, [r0, #28]",
    "add r11, r11, r3",
    "add r12, r12, r3",
    "str r11, [sp, #64]",
    "str r12, [sp, #8]",
    "ldr r3, [r0, #40]",
    "str r3, [sp, #60]",
    "mov r0, sp",
    "ldr r1, [sp, #92]",
    "ldr r3, [sp, #164]",
    "cbz r3, 7f",
    "bl embedded_raster_level_rows_inside_v7m",
    "b 81f",
    "7:",
    "bl embedded_raster_level_rows_v7m",
    "81:",
    "ldr r0, [sp, #160]",
    "add sp, #180",
    "pop {{r4-r11, pc}}",
    "80:",
    "movs r0, #0",
    "add sp, #180",
    "pop {{r4-r11, pc}}",
    "90:",
    "movs r0, #1",
    "add sp, #180",
    "pop {{r4-r11, pc}}",
    face_scan_clips!("164"),
    ".size embedded_raster_level_face_v7m, . - embedded_raster_level_face_v7m",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_level_face_v7m(face: *mut LevelFace<'_>) -> u32;
}

/// Sets up and draws the small face `face` with depth and light-level planes into `colors` and
/// `depths` (`width` pixels a row, the face's first row of rows the buffers' first), inside its
/// clip and rows: what `raster::scan` sets up for it and [`level_rows`] draws, from the same
/// integers. `true` if done (drawn, or nothing of it to draw); `false`, with nothing drawn, if
/// the face is not small or a sliver (the portable set-up's `NotSmall::Other`), or if the clip's
/// pixels in those rows are not inside the buffers or `C` is not a 16-bit colour.
#[inline(always)]
pub(crate) fn level_face<C: Copy>(
    buffers: (&mut [C], &mut [u16], usize),
    face: LevelFace<'_>,
    table: &[C; 256],
) -> bool {
    level_face_result(buffers, face, table) != 1
}

/// [`level_face`]'s call: 0 if done, 1 if declined, 2 if drawn with the set-up written out.
#[inline(always)]
fn level_face_result<C: Copy>(
    buffers: (&mut [C], &mut [u16], usize),
    face: LevelFace<'_>,
    table: &[C; 256],
) -> u32 {
    match with_buffers(buffers, face, table) {
        // SAFETY: the function reads the face and, through its addresses, 16 bytes of each
        // vertex (`LevelVertex`'s layout); given a set-up to fill (`face.setup` is null, as
        // `LevelFace::new` makes it, or a `MaybeUninit<SmallSetup>` of `level_face_keeping`), it
        // writes its 96 bytes; it writes only pixels of its region — rows and columns of the
        // clip (inside both buffers, `with_buffers` checked), at `row·stride + 2·column` bytes
        // from the buffers' starts, as 2-byte aligned `u16`s (`C` is a 2-byte colour: a copy of
        // the table's bytes is a copy of its colours) — through `level_rows`'s loop (see its
        // safety note), reads the table at `level >> 24 < 256`, divides by non-zero divisors
        // only (the area's top half is at least 2¹⁵), keeps its stack frame 8-byte aligned for
        // the call, and saves and restores every register the AAPCS asks it to.
        Ok(mut face) => unsafe { embedded_raster_level_face_v7m(&mut face) },
        Err(result) => result,
    }
}

/// Whether every pixel a face set-up may write — the clip `[x0, y0, x1, y1]`'s in rows `[first,
/// last]`, rows counted from `first` (at or above the top one, so the wrapping difference is the
/// true one) — is inside buffers of `len` pixels, `width` a row; `None` if nothing of the clip is
/// in the rows.
#[inline(always)]
fn clip_fits(clip: [i32; 4], rows: [i32; 2], len: usize, width: usize) -> Option<bool> {
    let ([x0, y0, x1, y1], [first, last]) = (clip, rows);
    let (top, bottom) = (y0.max(first), y1.min(last));
    if x0 > x1 || top > bottom {
        return None;
    }
    let row = u64::from(bottom.wrapping_sub(first) as u32);
    let last_pixel = row * (width as u64) + (x1 as u64);
    Some(x0 >= 0 && (x1 as u32) < width as u32 && last_pixel < len as u64)
}

/// `face` with the buffers and the table set, if every pixel of its clip in its rows is inside
/// both buffers (rows counted from the first of `rows`) and `C` is a 16-bit colour; else what
/// [`level_face_result`] returns for it: 0 (nothing of the clip in the rows, and no set-up to
/// write) or 1 (declined).
#[inline(always)]
fn with_buffers<'v, C: Copy>(
    (colors, depths, width): (&mut [C], &mut [u16], usize),
    mut face: LevelFace<'v>,
    table: &[C; 256],
) -> Result<LevelFace<'v>, u32> {
    if core::mem::size_of::<C>() != 2 || core::mem::align_of::<C>() != 2 {
        return Err(1);
    }
    let fits = clip_fits(face.clip, face.rows, colors.len().min(depths.len()), width);
    // Nothing of the clip in the rows: done, unless the set-up is wanted for the rows below.
    if fits.is_none() && face.setup.is_null() {
        return Err(0);
    }
    if fits == Some(false) || width > (u32::MAX / 2) as usize {
        return Err(1);
    }
    face.colors = colors.as_mut_ptr().cast();
    face.depths = depths.as_mut_ptr();
    face.stride = (width * 2) as u32;
    face.table = table.as_ptr().cast();
    Ok(face)
}

/// The level faces of a draw (`face`, from `LevelFace::without_vertices`) into `colors` and
/// `depths` (`width` pixels a row) with the colours of `table`, for a [`FaceScan`] to draw
/// its kept faces by [`level_face`]'s set-up: its buffers and table set, if every pixel of its
/// clip in its rows is inside both buffers and `C` is a 16-bit colour; else none (also when
/// nothing of the clip is in the rows).
#[inline(always)]
pub(crate) fn level_faces<C: Copy>(
    buffers: (&mut [C], &mut [u16], usize),
    face: LevelFace<'static>,
    table: &[C; 256],
) -> Option<LevelFace<'static>> {
    with_buffers(buffers, face, table).ok()
}

/// [`level_face`], its set-up (over the clip, before the rows outside `rows` are taken off)
/// written to `setup` for the bands below: done with nothing in the clip, declined (nothing
/// drawn), or drawn, with `setup` written.
#[inline(always)]
pub(crate) fn level_face_keeping<'s, C: Copy>(
    buffers: (&mut [C], &mut [u16], usize),
    mut face: LevelFace<'_>,
    table: &[C; 256],
    setup: &'s mut MaybeUninit<SmallSetup>,
) -> FaceSetup<'s> {
    face.setup = setup.as_mut_ptr();
    match level_face_result(buffers, face, table) {
        0 => FaceSetup::Done,
        // SAFETY: the function returns 2 once it has written all of the set-up (96 bytes: the
        // block's 21 words and three more), every bit pattern of which is a value of its fields
        // (integers and raw pointers).
        2 => FaceSetup::Ready(unsafe { setup.assume_init_ref() }),
        _ => FaceSetup::Declined,
    }
}

/// A vertex's record for the textured set-up at lr (which moves on by its 28 bytes): the 16
/// bytes at `$v` and the texel coordinates at r12 (which moves on by their 8). Clobbers r4-r9.
#[rustfmt::skip]
macro_rules! texel_record {
    ($v:literal) => {
        concat!(
            "ldm ", $v, ", {{r4-r7}}\n",
            "ldm r12!, {{r8, r9}}\n",
            "stm lr!, {{r4-r9}}\n",
            "add lr, lr, #4\n",
        )
    };
}

/// A texel coordinate (the `i32` at `$at` of the vertices r1-r3): its least value (signed) and
/// its spread (the greatest less it, wrapping) at `$out` and 4 more; the spread also in r7.
/// Clobbers r6, r8-r10.
#[rustfmt::skip]
macro_rules! coordinate_spread {
    ($at:literal, $out:literal) => {
        concat!(
            "ldr r6, [r1, #", $at, "]\n",
            "ldr r7, [r2, #", $at, "]\n",
            "ldr r8, [r3, #", $at, "]\n",
            minmax3!("r9", "r10", "r6", "r7", "r8", "lt", "gt"),
            "sub r7, r10, r9\n",
            "strd r9, r7, [sp, #", $out, "]\n",
        )
    };
}

/// `$v = ⌊$v / 2^$s + ½⌋` for `$s` from 0 (`texture::span::round_shift`), as `((v >> (s − 1)) +
/// 1) >> 1` (no carry out: `v >> (s − 1)` is below 2¹⁷ wherever it is taken); `$t` scratch.
#[rustfmt::skip]
macro_rules! round_shift {
    ($v:literal, $s:literal, $t:literal) => {
        concat!(
            "subs ", $t, ", ", $s, ", #1\n",
            "ittt pl\n",
            "lsrpl ", $v, ", ", $v, ", ", $t, "\n",
            "addpl ", $v, ", ", $v, ", #1\n",
            "lsrpl ", $v, ", ", $v, ", #1\n",
        )
    };
}

/// A texel coordinate's plane values and map, as `texture::PlaneMap::new`: the coordinate (the
/// `i32` at `$at` of the vertices r1-r3), its least value and spread at `$spread` (sp-relative),
/// the scale's shift (the least whose rounded spread is within 2¹⁶ − 256 steps), each vertex's
/// value `128 + round(c − least)` at `$value`, the map `(least − 128·2^shift, 16 − shift)` at
/// `$map` (sp-relative: the row loop's block); a shift of 17 declines (90). Clobbers r4-r11. (After the screen-space
/// bound has held, a spread is below 2²⁹, so the shift is at most 14 and `down` at least 2: the
/// decline here and `down` = 0 in the texel steps below are defence, never taken.)
#[rustfmt::skip]
macro_rules! plane_map {
    ($at:literal, $spread:literal, $value:literal, $map:literal) => {
        concat!(
            "ldrd r9, r10, [sp, #", $spread, "]\n",
            "clz r11, r10\n",
            "rsbs r11, r11, #16\n",
            "it mi\n",
            "movmi r11, #0\n",
            "mov r4, r10\n",
            round_shift!("r4", "r11", "r5"),
            "cmp r4, #0xff00\n",
            "it hi\n",
            "addhi r11, r11, #1\n",
            "cmp r11, #16\n",
            "bhi 90f\n",
            // Each value `128 + round(v / 2^s)` for `v = c − least` as `(2v >> s) + 257) >> 1`
            // (for s = 0 too), `2v` as `2c − 2·least` (wrapping; `v` is below 2²⁹).
            "lsl r10, r9, #1\n",
            "ldr r6, [r1, #", $at, "]\n",
            "ldr r7, [r2, #", $at, "]\n",
            "ldr r8, [r3, #", $at, "]\n",
            "rsb r6, r10, r6, lsl #1\n",
            "lsr r6, r6, r11\n",
            "add r6, r6, #257\n",
            "lsr r6, r6, #1\n",
            "strh r6, [r1, #", $value, "]\n",
            "rsb r7, r10, r7, lsl #1\n",
            "lsr r7, r7, r11\n",
            "add r7, r7, #257\n",
            "lsr r7, r7, #1\n",
            "strh r7, [r2, #", $value, "]\n",
            "rsb r8, r10, r8, lsl #1\n",
            "lsr r8, r8, r11\n",
            "add r8, r8, #257\n",
            "lsr r8, r8, #1\n",
            "strh r8, [r3, #", $value, "]\n",
            "movs r5, #128\n",
            "lsl r5, r5, r11\n",
            "sub r9, r9, r5\n",
            "rsb r11, r11, #16\n",
            "strd r9, r11, [sp, #", $map, "]\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_textured_face_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    dsp_directive!(),
    ".p2align 2",
    ".global embedded_raster_textured_face_v7m",
    ".hidden embedded_raster_textured_face_v7m",
    ".type embedded_raster_textured_face_v7m,%function",
    ".thumb_func",
    // r0 = the draw's template (`TexturedTemplate`), r1 = the face (`TexturedFace`). Returns 0 if done
    // (drawn, or nothing to draw), 1 if declined (not small, a sliver, or a coordinate's scale
    // past 2¹⁶), 3 if not within the screen-space bound: nothing drawn. The frame (byte ranges
    // end-exclusive): the textured row loop's block at sp (0..144; the coordinates' maps are
    // written into it at 96..112 first), then scratch: 144, 148 = l1, l2; 152 = whether the
    // middle bound starts; 156..188 = the depth's, `u`'s, `v`'s and the level's d1, d2;
    // 188..220 = their nx, ny; 220..236 = their value terms; 236..248 = the oriented records'
    // addresses; 248, 252, 256 = the region's first column, first and last rows; 260..276 =
    // the coordinates' least values and spreads; 276 = the face's address; 280 = whether the
    // clip left the region's columns whole (`face_scan`'s);
    // 284..368 = the vertices' records, 28 bytes each (a vertex's 16 bytes, its texel
    // coordinates at 16 and 20, `u`'s and `v`'s plane values at 24 and 26); 368..372 unused
    // (the frame's 8-byte alignment); 372..380 = the area and the numerators' limit while the
    // numerators are found.
    "embedded_raster_textured_face_v7m:",
    "push {{r4-r11, lr}}",
    "sub sp, #380",
    "str r1, [sp, #276]",
    // The vertices' records: each vertex's 16 bytes and its texel coordinates (the face's word
    // 36 addresses the three pairs), the plane values' 4 bytes after them; the levels 0 unless
    // lit (the face's word 28, bit 1).
    "ldr r12, [r1, #36]",
    "ldr r11, [r1, #28]",
    "ldm r1, {{r1, r2, r3}}",
    "add lr, sp, #284",
    texel_record!("r1"),
    texel_record!("r2"),
    texel_record!("r3"),
    "lsls r11, r11, #30",
    "bmi 24f",
    "movs r4, #0",
    "strh r4, [sp, #294]",
    "strh r4, [sp, #322]",
    "strh r4, [sp, #350]",
    "24:",
    // The screen-space bound (`texturing::nearly_affine`): r1-r3 = the records; their `q` in
    // a common scale (shifts apart by at most 8, else perspective), r5 = the ratio term
    // `q_max − q_min + 2^(most + 1)`, r4 = `4·q_min`. A `q` is `mantissa·2^shift`, and a
    // mantissa is below 2¹⁶ and at least 2¹⁵ where the shift is not 0 (`Inverse`), so the
    // least and the greatest `q` are those of the least and the greatest key `shift·2²⁴ +
    // mantissa` (the vertex's word 12 without its code byte): in the common scale the least is
    // its mantissa and the greatest its mantissa shifted by the shifts' difference.
    "add r1, sp, #284",
    "add r2, sp, #312",
    "add r3, sp, #340",
    "ldr r4, [r1, #12]",
    "ldr r5, [r2, #12]",
    "ldr r6, [r3, #12]",
    "bic r4, r4, #0x00FF0000",
    "bic r5, r5, #0x00FF0000",
    "bic r6, r6, #0x00FF0000",
    minmax3!("r7", "r8", "r4", "r5", "r6", "lo", "hi"),
    "lsr r9, r8, #24",
    "sub r9, r9, r7, lsr #24",
    "cmp r9, #8",
    "bhi 93f",
    "uxth r4, r7",
    "uxth r5, r8",
    "lsl r5, r5, r9",
    "sub r5, r5, r4",
    "movs r6, #2",
    "lsl r6, r6, r9",
    "add r5, r5, r6",
    "lsl r4, r4, #2",
    // The texel coordinates' least values and spreads (sp + 260-272), the larger spread
    // times the ratio against 2¹² times 4·q_min (1/16 texel).
    coordinate_spread!("16", "260"),
    coordinate_spread!("20", "268"),
    "ldr r6, [sp, #264]",
    "cmp r7, r6",
    "it lo",
    "movlo r7, r6",
    "umull r6, r7, r7, r5",
    "lsl r8, r4, #12",
    "lsr r9, r4, #20",
    "subs r8, r8, r6",
    "sbcs r9, r9, r7",
    "blo 93f",
    // Lit (the face's word 28, its bit 1 still r11's sign): the levels' spread times the ratio
    // against the bound (the template's word 52) times 4·q_min.
    "cmp r11, #0",
    "bge 23f",
    "ldrh r6, [r1, #10]",
    "ldrh r7, [r2, #10]",
    "ldrh r8, [r3, #10]",
    minmax3!("r9", "r10", "r6", "r7", "r8", "lo", "hi"),
    "sub r9, r10, r9",
    "umull r6, r7, r9, r5",
    "ldr r8, [r0, #52]",
    "umull r8, r9, r8, r4",
    "subs r8, r8, r6",
    "sbcs r9, r9, r7",
    "blo 93f",
    "23:",
    // The coordinates' planes (`texture::PlaneMap::new`): their values into the vertices, the
    // maps into the block; a scale past 2¹⁶ declines (its map shifts left).
    plane_map!("16", "260", "24", "96"),
    plane_map!("20", "268", "26", "104"),
    face_scan!("", "236", "240", "248", "252", "76", "128", "64", "52", "20", "152", "144", "280"),
    "movs lr, #0",
    // The four attributes' numerators with the oriented records' addresses held in r1-r3 (the
    // area and the limit kept at 372 meanwhile).
    "strd r4, r5, [sp, #372]",
    "ldr r1, [sp, #236]",
    "ldrd r2, r3, [sp, #240]",
    attribute_numerators!("8", "156", "28", "220", "188"),
    attribute_numerators!("24", "164", "32", "224", "196"),
    attribute_numerators!("26", "172", "36", "228", "204"),
    attribute_numerators!("10", "180", "40", "232", "212"),
    "ldrd r4, r5, [sp, #372]",
    numerators_within!(),
    face_reciprocal!("144"),
    attribute_plane!("156", "220", "188", "0", "80", "32"),
    attribute_plane!("164", "224", "196", "4", "84", "36"),
    attribute_plane!("172", "228", "204", "8", "88", "40"),
    attribute_plane!("180", "232", "212", "12", "92", "44"),
    // `y`'s shift (the template's word 8) to the block's 112, the texels (the face's word 24)
    // and the masks (the template's 44, 48) to 132-140.
    "ldr r1, [sp, #276]",
    "ldr r7, [r1, #24]",
    "ldrd r8, r9, [r0, #44]",
    "add r1, sp, #132",
    "stm r1, {{r7-r9}}",
    "ldr r6, [r0, #8]",
    "str r6, [sp, #112]",
    "ldr r3, [sp, #100]",
    "ldr r5, [sp, #108]",
    // The texel steps a pixel from the coordinates' steps a column (r1, r2), as
    // `PlaneMap::step`: `(s >> down) + ((s >> (down − 1)) & 1)`, or `s` for `down` = 0 (r3,
    // r5): `t = s >> (down − 1)`, then `t >> 1` plus the bit shifted out (the carry); `y`'s
    // shifted by r6.
    "ldrd r1, r2, [sp, #84]",
    "cbz r3, 21f",
    "sub r4, r3, #1",
    "asr r1, r1, r4",
    "asrs r1, r1, #1",
    "adc r1, r1, #0",
    "21:",
    "cbz r5, 22f",
    "sub r4, r5, #1",
    "asr r2, r2, r4",
    "asrs r2, r2, #1",
    "adc r2, r2, #0",
    "22:",
    "lsl r2, r2, r6",
    "strd r1, r2, [sp, #116]",
    // The band's rows (r4 = its first, r5 = its last) of the region's (r1 = first, r3 =
    // last): rows above it skipped (the numerators and planes stepped by r6 rows), none in it,
    // done. Rows counted from the band's first in the buffers.
    "ldrd r1, r3, [sp, #252]",
    "ldrd r4, r5, [r0, #0]",
    "cmp r1, r4",
    "bge 26f",
    "cmp r3, r4",
    "blt 80f",
    "sub r6, r4, r1",
    "mov r1, r4",
    "ldrd r7, r8, [sp, #52]",
    "ldrd r9, r10, [sp, #20]",
    "mla r9, r7, r6, r9",
    "mla r10, r8, r6, r10",
    "strd r9, r10, [sp, #20]",
    "ldr r7, [sp, #60]",
    "ldr r9, [sp, #28]",
    "mla r9, r7, r6, r9",
    "str r9, [sp, #28]",
    "ldrd r7, r8, [sp, #32]",
    "ldrd r9, r10, [sp, #0]",
    "mla r9, r7, r6, r9",
    "mla r10, r8, r6, r10",
    "strd r9, r10, [sp, #0]",
    "ldrd r7, r8, [sp, #40]",
    "ldrd r9, r10, [sp, #8]",
    "mla r9, r7, r6, r9",
    "mla r10, r8, r6, r10",
    "strd r9, r10, [sp, #8]",
    "26:",
    "cmp r3, r5",
    "it gt",
    "movgt r3, r5",
    "cmp r1, r3",
    "bgt 80f",
    "sub r3, r3, r1",
    "add r3, r3, #1",
    "str r3, [sp, #128]",
    "sub r1, r1, r4",
    // The stride, the depth pointer at the first pixel, the colour buffer's offset (the face's
    // words 20, 12, 16); then the rows (r1 = the variant: the middle bound's bit and the face's
    // word 28, r2 = its palette, word 32).
    "ldr r9, [sp, #276]",
    "ldr r3, [r9, #20]",
    "str r3, [sp, #48]",
    "mul r3, r3, r1",
    "ldr r6, [sp, #248]",
    "add r3, r3, r6, lsl #1",
    "ldrd r7, r8, [r9, #12]",
    "add r7, r7, r3",
    "str r7, [sp, #16]",
    "str r8, [sp, #124]",
    "ldr r1, [sp, #152]",
    "ldr r2, [r9, #28]",
    "orr r1, r1, r2",
    "ldr r2, [r9, #32]",
    "mov r0, sp",
    "ldr r3, [sp, #280]",
    "cbz r3, 27f",
    "bl embedded_raster_textured_rows_inside_v7m",
    "b 80f",
    "27:",
    "bl embedded_raster_textured_rows_v7m",
    "80:",
    "movs r0, #0",
    "add sp, #380",
    "pop {{r4-r11, pc}}",
    "90:",
    "movs r0, #1",
    "add sp, #380",
    "pop {{r4-r11, pc}}",
    "93:",
    "movs r0, #3",
    "add sp, #380",
    "pop {{r4-r11, pc}}",
    face_scan_clips!("280"),
    ".size embedded_raster_textured_face_v7m, . - embedded_raster_textured_face_v7m",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_textured_face_v7m(
        template: *const TexturedTemplate,
        face: *mut TexturedFace<'_>,
    ) -> u32;
}

/// Sets up and draws the small face `face` with depth, texel coordinate and light-level planes
/// into `colors` and `depths` (`width` pixels a row, the face's first row of rows the buffers'
/// first), inside its clip and rows: what `texturing`'s screen-space fill sets up for it (the
/// bound `nearly_affine`, the coordinates' `PlaneMap`s, `raster::scan`'s set-up with four
/// planes) and [`textured_rows`] draws, from the same integers. Done if drawn (or nothing of it
/// to draw); perspective, with nothing drawn, if the bound does not hold; declined, with
/// nothing drawn, if the face is not small or a sliver (the portable set-up's
/// `NotSmall::Other`), a coordinate's scale is past 2¹⁶, the clip's pixels in those rows are
/// not inside the buffers, a texel index the masks allow is not inside the texels, `y`'s shift
/// is not below 32 or `C` is not a 16-bit colour. `C` must be the 5-6-5 format whose raw value
/// is the texels' (the caller's promise, as [`textured_rows`]').
#[inline(always)]
pub(crate) fn textured_face<C: Copy>(
    buffers: (&mut [C], &mut [u16], usize),
    face: TexturedFace<'_>,
) -> TexturedDraw {
    let mut face = match textured_with_buffers(buffers, face) {
        Ok(face) => face,
        Err(draw) => return draw,
    };
    let template = face.template;
    // SAFETY: the function reads the template and the face, and through the face's addresses
    // the first 16 bytes of each of its three vertices (`ProjectedPrefix`es, borrowed by the
    // face) and their three pairs of texel coordinates (24 bytes); it writes only pixels of its
    // region — rows and columns of the clip (inside both buffers, checked by
    // `textured_with_buffers`), at `row·stride + 2·column` bytes from the buffers' starts, as
    // 2-byte aligned `u16`s (`C` is a 2-byte colour whose raw value the texels are, the
    // caller's promise) — through `textured_rows`'s loop (see its safety note), which reads
    // the texels at indices of at most `rows_mask | x_mask` (inside them, checked) with shifts
    // below 32 (the maps' at most 16, `y`'s checked); it divides by non-zero divisors only (the
    // area's top half is at least 2¹⁵), keeps its stack frame 8-byte aligned for the call, and
    // saves and restores every register the AAPCS asks it to.
    match unsafe { embedded_raster_textured_face_v7m(template, &mut face) } {
        0 => TexturedDraw::Done,
        3 => TexturedDraw::Perspective,
        _ => TexturedDraw::Declined,
    }
}

/// `face` with the buffers set, if its texels hold every index its masks allow, `y`'s shift is
/// below 32, `C` is a 16-bit colour and every pixel of its clip in its rows is inside both
/// buffers; else what [`textured_face`] returns for it (done: nothing of the clip in the rows).
#[inline(always)]
fn textured_with_buffers<'w, C: Copy>(
    (colors, depths, width): (&mut [C], &mut [u16], usize),
    mut face: TexturedFace<'w>,
) -> Result<TexturedFace<'w>, TexturedDraw> {
    let template = face.template;
    let last_texel = (template.rows_mask | template.x_mask) as usize;
    let colour = core::mem::size_of::<C>() == 2 && core::mem::align_of::<C>() == 2;
    if !colour || last_texel >= face.texels_len || template.y_shift > 31 {
        return Err(TexturedDraw::Declined);
    }
    match clip_fits(
        template.clip,
        template.rows,
        colors.len().min(depths.len()),
        width,
    ) {
        None => return Err(TexturedDraw::Done),
        Some(false) => return Err(TexturedDraw::Declined),
        Some(true) if width > (u32::MAX / 2) as usize => return Err(TexturedDraw::Declined),
        Some(true) => {}
    }
    face.depths = depths.as_mut_ptr();
    face.color_offset = (colors.as_mut_ptr() as usize).wrapping_sub(face.depths as usize) as u32;
    face.stride = (width * 2) as u32;
    Ok(face)
}

/// The textured faces `faces` of a draw into `colors` and `depths` (`width` pixels a row) for
/// a [`FaceScan`] to draw its kept faces by [`textured_face`]'s set-up: their face's buffers
/// set, if [`textured_face`] would draw into them (none where it would decline every face,
/// or where nothing of the clip is in the rows). `C` must be the 5-6-5 format whose raw value
/// is the texels' (the caller's promise).
#[inline(always)]
pub(crate) fn textured_faces<'w, C: Copy>(
    buffers: (&mut [C], &mut [u16], usize),
    mut faces: TexturedFaces<'w>,
) -> Option<TexturedFaces<'w>> {
    faces.face = textured_with_buffers(buffers, faces.face).ok()?;
    Some(faces)
}

/// One row of the transform (`three_d::vertex`'s `direct_row`): the row's three entries and its
/// 64-bit bias `t·2¹⁶ + 2¹⁵` from r0 (which moves on by the row's 20 bytes) into r7-r11, the
/// products with the position's r4-r6 added to the bias, the sum shifted down by 16 into `$out`
/// (its low 32 bits: the sum's, below 2⁴⁶ in magnitude, fits after the shift).
#[rustfmt::skip]
macro_rules! transform_row {
    ($out:literal) => {
        concat!(
            "ldm r0!, {{r7-r11}}\n",
            "smlal r10, r11, r7, r4\n",
            "smlal r10, r11, r8, r5\n",
            "smlal r10, r11, r9, r6\n",
            "lsr r10, r10, #16\n",
            "orr ", $out, ", r10, r11, lsl #16\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_project_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    ".p2align 2",
    ".global embedded_raster_project_v7m",
    ".hidden embedded_raster_project_v7m",
    ".type embedded_raster_project_v7m,%function",
    ".thumb_func",
    // r0 = the block (`ProjectionBlock`), r1 = the positions (12 bytes each), r2 = the vertices
    // (16 bytes each), r3 = their number (at least one). The frame: 0, 4, 8 = the clip-space
    // z, x and y of the vertex; 12 = the end of the vertices.
    "embedded_raster_project_v7m:",
    "push {{r4-r11, lr}}",
    "sub sp, #16",
    "add r3, r2, r3, lsl #4",
    "str r3, [sp, #12]",
    "1:",
    // The clip-space position: x, y and z to the frame, w in r4.
    "ldm r1!, {{r4-r6}}",
    transform_row!("r12"),
    transform_row!("lr"),
    transform_row!("r3"),
    "stm sp, {{r3, r12, lr}}",
    transform_row!("r4"),
    "sub r0, r0, #80",
    // w at least W_MIN (256), normalised: d = w·2ˢ in [2³¹, 2³²) (r4), s (r5) in [1, 23]; r =
    // ⌊2⁶³/d⌋ in r6 (2³² − 1 for d = 2³¹), two 16-bit digits.
    "cmp r4, #256",
    "it lt",
    "movlt r4, #256",
    "clz r5, r4",
    "lsl r4, r4, r5",
    "cmp r4, #0x80000000",
    "beq 50f",
    "lsr r7, r4, #16",
    "mov r8, #0x80000000",
    reciprocal_digit!("r9", "r8", "r7", "r4", "r10", "r11", "r12", "lr", "r3"),
    reciprocal_digit!("r6", "r8", "r7", "r4", "r10", "r11", "r12", "lr", "r3"),
    "orr r6, r6, r9, lsl #16",
    "51:",
    // k = ⌊h·r / 2²⁴⌋ for the half sizes (r7, r8); x and y (r4, r9) scaled by 2^(s − 7) (z in r3).
    "ldrd r7, r8, [r0, #88]",
    "umull r9, r10, r7, r6",
    "lsr r9, r9, #24",
    "orr r7, r9, r10, lsl #8",
    "umull r9, r10, r8, r6",
    "lsr r9, r9, #24",
    "orr r8, r9, r10, lsl #8",
    "ldm sp, {{r3, r4, r9}}",
    "subs r10, r5, #7",
    "bmi 60f",
    "lsl r4, r4, r10",
    "lsl r9, r9, r10",
    "61:",
    // The offsets ⌊(c·k + 2^(31 + e)) / 2³²⌋ >> e from the centre: x in r8, y in r9.
    "ldrd r11, r12, [r0, #100]",
    "smull r10, lr, r4, r7",
    "adds r10, r10, r11",
    "adc lr, lr, r12",
    "smull r4, r7, r9, r8",
    "adds r4, r4, r11",
    "adc r7, r7, r12",
    "ldr r10, [r0, #96]",
    "asr lr, lr, r10",
    "asr r7, r7, r10",
    "ldrd r8, r9, [r0, #80]",
    "add r8, r8, lr",
    "sub r9, r9, r7",
    // The depth (r10): 32767 + ⌊(z·2^(s − 1)·kz + 2⁴⁵) / 2⁴⁶⌋ for kz = ⌊32767·r / 2¹⁶⌋, clamped
    // to 0..=65534.
    "movw r12, #32767",
    "umull r10, r11, r6, r12",
    "lsr r10, r10, #16",
    "orr r10, r10, r11, lsl #16",
    "sub r11, r5, #1",
    "lsl r3, r3, r11",
    "smull r11, lr, r3, r10",
    "add lr, lr, #8192",
    "asr lr, lr, #14",
    "add lr, lr, r12",
    "usat r10, #16, lr",
    "cmp r10, r12, lsl #1",
    "it hi",
    "lslhi r10, r12, #1",
    // `q`: r's high half and s at 15 (r11, masked); the vertex; the next.
    "ldr r11, [r0, #108]",
    "lsr r6, r6, #16",
    "orr r6, r6, r5, lsl #24",
    "and r11, r11, r6",
    "ldr r3, [sp, #12]",
    "stm r2!, {{r8-r11}}",
    "cmp r2, r3",
    "bne 1b",
    "add sp, #16",
    "pop {{r4-r11, pc}}",
    "50:",
    "mvn r6, #0",
    "b 51b",
    // Far points (w ≥ 2²⁵, s < 7): x and y shifted down by 7 − s.
    "60:",
    "rsb r10, r10, #0",
    "asr r4, r4, r10",
    "asr r9, r9, r10",
    "b 61b",
    ".size embedded_raster_project_v7m, . - embedded_raster_project_v7m",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_project_v7m(
        block: *const ProjectionBlock,
        positions: *const u8,
        vertices: *mut u8,
        count: u32,
    );
}

/// Transforms, projects and maps to the viewport each position of `positions` into the vertex
/// of `out` at its index (as many as both have) as `block` describes: what `three_d`'s portable
/// vertex stage computes for a position inside the view volume (`direct_row`, `project_inverse`),
/// from the same integers — the clip code and the level 0, `q` kept or 0 by the block. The
/// caller's promise: every position is inside the view volume once transformed, and the
/// transform's sums stay below 2⁴⁶ in magnitude (its `direct` and `inside` draws); for other
/// positions the vertices are some integers, never a write outside `out`. Always `true`.
#[inline(always)]
pub(crate) fn project_positions<P: ModelPosition, V: ProjectedPrefix>(
    block: &ProjectionBlock,
    positions: &[P],
    out: &mut [V],
) -> bool {
    const {
        assert!(core::mem::size_of::<P>() == 12 && core::mem::align_of::<P>() >= 4);
        assert!(core::mem::size_of::<V>() == 16 && core::mem::align_of::<V>() >= 4);
    };
    let count = positions.len().min(out.len());
    if count == 0 {
        return true;
    }
    // SAFETY: the function reads the block and `count` positions of 12 bytes from
    // `positions`'s start (inside it: `P` is 12 bytes, asserted above), and writes `count`
    // vertices of 16 bytes from `out`'s start (inside it: `V` is 16 bytes), 4-byte aligned (both
    // types are); any 16 bytes are a `V` (`ProjectedPrefix`'s contract). Its divisions are by
    // `d`'s top half, at least 2¹⁵ (d > 2³¹ there), its shifts by amounts below 32; it keeps its
    // stack frame its own and saves and restores every register the AAPCS asks it to.
    unsafe {
        embedded_raster_project_v7m(
            block,
            positions.as_ptr().cast(),
            out.as_mut_ptr().cast(),
            count as u32,
        )
    };
    true
}

// The light levels of a draw's vertices (`light_levels`): r0 = the normals (12 bytes each), r1 =
// the level field of the first vertex (16 bytes apart), r2 = the count (at least 1), r3 = the
// light (`LevelLight`: the direction's three raw components, the ambient level, 2¹⁶ less it).
core::arch::global_asm!(
    ".section .text.embedded_raster_light_levels_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    ".p2align 2",
    ".global embedded_raster_light_levels_v7m",
    ".hidden embedded_raster_light_levels_v7m",
    ".type embedded_raster_light_levels_v7m,%function",
    ".thumb_func",
    "embedded_raster_light_levels_v7m:",
    "push {{r4-r11, lr}}",
    "ldm r3, {{r3-r7}}",
    "mov r8, #32768",
    "1:",
    // dot = n·l (64 bits, 30 fractional bits), rounded by 2¹³.
    "ldm r0!, {{r9-r11}}",
    "smull r12, lr, r9, r3",
    "smlal r12, lr, r10, r4",
    "smlal r12, lr, r11, r5",
    "adds r12, r12, #8192",
    "adc lr, lr, #0",
    // The diffuse term: 2³⁰ − 1 where the sum is that or more (or negative), shifted down by
    // 14, 0 where it is negative.
    "lsr r9, r12, #30",
    "orrs r9, r9, lr",
    "it ne",
    "mvnne r12, #0xC0000000",
    "lsr r12, r12, #14",
    "bic r12, r12, lr, asr #31",
    // The level: the ambient plus `((2¹⁶ − ambient)·d + 2¹⁵) >> 16`, times 255, over 256.
    "mla r12, r7, r12, r8",
    "add r12, r6, r12, lsr #16",
    "rsb r12, r12, r12, lsl #8",
    "lsr r12, r12, #8",
    "strh r12, [r1], #16",
    "subs r2, #1",
    "bne 1b",
    "pop {{r4-r11, pc}}",
    ".size embedded_raster_light_levels_v7m, . - embedded_raster_light_levels_v7m",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_light_levels_v7m(
        normals: *const u8,
        levels: *mut u8,
        count: u32,
        light: *const super::LevelLight,
    );
}

/// [`super::light_levels`]'s assembly call: `count` (at least 1) normals from `normals`, levels
/// from the field at `levels`.
///
/// # Safety
///
/// `normals` is valid for reads of `count` 12-byte normals (4-byte aligned) and `levels` for
/// writes of a `u16` at every 16 bytes from it, `count` of them (2-byte aligned); `light`'s
/// ambient level is at most 2¹⁶.
pub(super) unsafe fn light_levels(
    normals: *const u8,
    levels: *mut u8,
    count: u32,
    light: &super::LevelLight,
) {
    // SAFETY: the caller's promise; the function reads the light's five words, keeps its stack
    // frame its own and saves and restores every register the AAPCS asks it to.
    unsafe { embedded_raster_light_levels_v7m(normals, levels, count, light) }
}

/// A vertex's texel coordinates for the scan's textured faces: from the pair at index `$i` of
/// the texture coordinates (r8), `u·width` and `(2¹⁶ − v)·height` (r2, r3), as the pipeline's
/// saturating products where none saturates (one that would: to 17), stored at lr (which moves
/// on by 8). Clobbers r0, r1, r9.
#[rustfmt::skip]
macro_rules! texel_coordinates {
    ($i:literal) => {
        concat!(
            "add r9, r8, ", $i, ", lsl #3\n",
            "ldrd r0, r1, [r9]\n",
            "smull r0, r9, r0, r2\n",
            "cmp r9, r0, asr #31\n",
            "bne 17f\n",
            "rsbs r1, r1, #0x10000\n",
            "bvs 17f\n",
            "smull r1, r9, r1, r3\n",
            "cmp r9, r1, asr #31\n",
            "bne 17f\n",
            "strd r0, r1, [lr], #8\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_scan_faces_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    ".p2align 2",
    ".global embedded_raster_scan_faces_v7m",
    ".hidden embedded_raster_scan_faces_v7m",
    ".type embedded_raster_scan_faces_v7m,%function",
    ".thumb_func",
    // r0 = the scan (`FaceScan`), r1 = the entries, r2 = their room (at least one). Returns the
    // entries written. [sp]: the scan, [sp, #4]: the entries.
    "embedded_raster_scan_faces_v7m:",
    "push {{r0-r2, r4-r11, lr}}",
    "mov lr, r1",
    "add r11, r1, r2, lsl #2",
    "ldrd r12, r10, [r0, #16]",
    "ldm r0, {{r0-r3}}",
    // r0 = the next face, r1 = past the last, r2 = the scratch, r3 = its vertices, r12 = the
    // face's number times 4, r10 = the flip (its bit 0: level faces), lr = the next entry, r11 =
    // past the last.
    "cmp r0, r1",
    "bhs 9f",
    "1:",
    "ldrh r4, [r0]",
    "ldrh r5, [r0, #2]",
    "ldrh r6, [r0, #4]",
    "adds r0, r0, #6",
    "cmp r4, r3",
    "itt lo",
    "cmplo r5, r3",
    "cmplo r6, r3",
    "bhs 20f",
    "add r4, r2, r4, lsl #4",
    "add r5, r2, r5, lsl #4",
    "add r6, r2, r6, lsl #4",
    // Any vertex outside a clip plane (bits 0-6 of its code): to 30.
    "ldrb r7, [r4, #14]",
    "ldrb r8, [r5, #14]",
    "ldrb r9, [r6, #14]",
    "orr r7, r7, r8",
    "orr r7, r7, r9",
    "tst r7, #0x7f",
    "bne 30f",
    // The doubled area (r8:r7): none, to 40; kept if its sign differs from the flip's.
    "ldrd r7, r8, [r4]",
    "ldrd r4, r9, [r6]",
    "ldrd r5, r6, [r5]",
    "sub r5, r5, r7",
    "sub r9, r9, r8",
    "sub r4, r4, r7",
    "sub r6, r6, r8",
    "smull r7, r8, r5, r9",
    "smull r5, r9, r4, r6",
    "subs r7, r7, r5",
    "sbc r8, r8, r9",
    "orrs r7, r7, r8",
    "beq 40f",
    "teq r8, r10",
    "bmi 10f",
    // Culled (or counted): the next face.
    "2:",
    "add r12, r12, #4",
    "cmp r0, r1",
    "blo 1b",
    // Every face scanned, or the entries full (from 11): the scan's next face and number kept.
    "9:",
    "pop {{r1-r3}}",
    "str r0, [r1]",
    "str r12, [r1, #16]",
    "sub r0, lr, r2",
    "lsr r0, r0, #2",
    "pop {{r4-r11, pc}}",
    // Kept: drawn by the level set-up where the batch has level faces (the flip's bit 0; the
    // scan's word 32) and
    // every vertex a normal (bit 7 of the codes clear), unless it declines (1); drawn ones
    // counted (word 36).
    "10:",
    "tst r10, #1",
    "beq 19f",
    "ldr r7, [sp]",
    "ldr r7, [r7, #32]",
    "ldrh r4, [r0, #-6]",
    "ldrh r5, [r0, #-4]",
    "ldrh r6, [r0, #-2]",
    "add r4, r2, r4, lsl #4",
    "add r5, r2, r5, lsl #4",
    "add r6, r2, r6, lsl #4",
    "ldrb r8, [r4, #14]",
    "ldrb r9, [r5, #14]",
    "orr r8, r8, r9",
    "ldrb r9, [r6, #14]",
    "orr r8, r8, r9",
    "tst r8, #0x80",
    "bne 12f",
    "stm r7, {{r4-r6}}",
    "push {{r0-r3, r12, lr}}",
    "mov r0, r7",
    "bl embedded_raster_level_face_v7m",
    "mov r7, r0",
    "pop {{r0-r3, r12, lr}}",
    "cmp r7, #1",
    "beq 12f",
    "ldr r9, [sp]",
    "ldr r8, [r9, #36]",
    "add r8, r8, #1",
    "str r8, [r9, #36]",
    "b 2b",
    // No level faces: textured ones (the flip's bit 1), or the entry.
    "19:",
    "tst r10, #2",
    "bne 15f",
    // Its entry; the next face unless the entries are full, or the batch has level or textured
    // faces (the faces after it wait: the faces are drawn in order).
    "12:",
    "orr r4, r12, #{kept}",
    "str r4, [lr], #4",
    "11:",
    "tst r10, #3",
    "bne 13f",
    "cmp lr, r11",
    "blo 2b",
    "13:",
    "add r12, r12, #4",
    "b 9b",
    // Kept, with textured faces (the scan's word 40, r7 below): the face's vertices, lit as
    // the draw asks (word 64: every vertex with a normal), its texel coordinates `u·width` and
    // `(2¹⁶ − v)·height` (any index past the coordinates, or a product past `i32`: handed on
    // untried, 17), the set-up called: drawn (0, counted), perspective (3, an entry of its
    // kind) or declined (an entry). r0-r3, r12 and lr kept on the stack meanwhile.
    "15:",
    "push {{r0-r3, r12, lr}}",
    "ldr r7, [sp, #24]",
    "ldr r7, [r7, #40]",
    "ldrh r4, [r0, #-6]",
    "ldrh r5, [r0, #-4]",
    "ldrh r6, [r0, #-2]",
    "ldr r8, [r7, #52]",
    "cmp r4, r8",
    "itt lo",
    "cmplo r5, r8",
    "cmplo r6, r8",
    "bhs 17f",
    "add r1, r2, r4, lsl #4",
    "add r3, r2, r5, lsl #4",
    "add r12, r2, r6, lsl #4",
    "ldr r8, [r7, #64]",
    "cmp r8, #0",
    "beq 16f",
    "ldrb r8, [r1, #14]",
    "ldrb r9, [r3, #14]",
    "orr r8, r8, r9",
    "ldrb r9, [r12, #14]",
    "orr r8, r8, r9",
    "tst r8, #0x80",
    "bne 17f",
    "16:",
    "stm r7, {{r1, r3, r12}}",
    "ldr r8, [r7, #48]",
    "ldrd r2, r3, [r7, #56]",
    "add lr, r7, #68",
    texel_coordinates!("r4"),
    texel_coordinates!("r5"),
    texel_coordinates!("r6"),
    "ldr r0, [r7, #44]",
    "mov r1, r7",
    "bl embedded_raster_textured_face_v7m",
    "mov r7, r0",
    "pop {{r0-r3, r12, lr}}",
    "cbz r7, 18f",
    "cmp r7, #3",
    "bne 12b",
    "orr r4, r12, #{perspective}",
    "str r4, [lr], #4",
    "b 11b",
    "17:",
    "pop {{r0-r3, r12, lr}}",
    "b 12b",
    "18:",
    "ldr r9, [sp]",
    "ldr r8, [r9, #36]",
    "add r8, r8, #1",
    "str r8, [r9, #36]",
    "b 2b",
    // An index past the scratch.
    "20:",
    "orr r4, r12, #{invalid}",
    "str r4, [lr], #4",
    "b 11b",
    // Outside: all vertices outside one plane, rejected (counted); else to clip.
    "30:",
    "ldrb r7, [r4, #14]",
    "ldrb r8, [r5, #14]",
    "ldrb r9, [r6, #14]",
    "and r7, r7, r8",
    "and r7, r7, r9",
    "tst r7, #0x7f",
    "bne 31f",
    "orr r4, r12, #{clipped}",
    "str r4, [lr], #4",
    "b 11b",
    "31:",
    "ldr r4, [sp]",
    "ldr r5, [r4, #24]",
    "add r5, r5, #1",
    "str r5, [r4, #24]",
    "b 2b",
    // No area: degenerate (counted).
    "40:",
    "ldr r4, [sp]",
    "ldr r5, [r4, #28]",
    "add r5, r5, #1",
    "str r5, [r4, #28]",
    "b 2b",
    ".size embedded_raster_scan_faces_v7m, . - embedded_raster_scan_faces_v7m",
    kept = const SCANNED_KEPT,
    clipped = const SCANNED_CLIPPED,
    invalid = const SCANNED_INVALID,
    perspective = const SCANNED_PERSPECTIVE,
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_scan_faces_v7m(scan: *mut FaceScan<'_>, out: *mut u32, room: u32) -> u32;
}

/// Scans the faces of `scan` on from its next one as [`FaceScan`] describes, until every face
/// is scanned or `out` is full: the entries written to `out`'s start, how many. Kept faces are
/// drawn by [`level_face`]'s set-up where the scan has level faces (`FaceScan::next_batch`).
#[inline(always)]
pub(crate) fn scan_faces(scan: &mut FaceScan<'_>, out: &mut [u32; FACE_BATCH]) -> usize {
    const { assert!(core::mem::size_of::<FaceScan<'_>>() == 44) };
    // SAFETY: the function reads the scan's faces from `next` up to `end` (its borrowed
    // slice's, 2-byte aligned `u16`s) and, through an index below `vertices` (the borrowed
    // scratch's length), 16 bytes of that vertex (`FaceScan::new` takes only 16-byte
    // `ProjectedPrefix`es, 4-byte aligned) at `scratch + 16·index`; it writes the scan's
    // words 0, 16, 24, 28 and 36 (integers, and `next` moved on by whole faces up to `end`)
    // and at most `room` (`FACE_BATCH`, at least one) entries from `out`'s start, 4-byte
    // aligned. Given level faces (word 32: `level_faces`' face, its buffers set for this call
    // and not otherwise used during it), it writes a kept face's three vertex addresses (inside
    // the scratch, as above: `LevelVertex`es, a `ProjectedPrefix`'s layout) into its words 0-8
    // and calls `embedded_raster_level_face_v7m` on it, as `level_face` does (see its safety
    // note), its stack frame 8-byte aligned for the call. Given textured faces (word 40:
    // `textured_faces`' faces, likewise set for this call), it reads a kept face's three pairs
    // of texture coordinates at indices below their count (the borrowed slice's, 8-byte pairs,
    // 4-byte aligned), writes the three vertex addresses and the three coordinate pairs into the
    // faces' words 0-8 and 68-92 (whose word 36 addresses the pairs), and calls
    // `embedded_raster_textured_face_v7m` with its template (word 44) and face, as
    // `textured_face` does (see its safety note). It keeps its stack frame its own and saves
    // and restores every register the AAPCS asks it to.
    unsafe { embedded_raster_scan_faces_v7m(scan, out.as_mut_ptr(), FACE_BATCH as u32) as usize }
}

/// Sets the words from `start` up to `end`, a whole number of eights (at least one) apart, to
/// the word at `start`: [`fill_eights`] with the value loaded by the assembly (a pair of 16-bit
/// colours, whose bytes Rust does not read as an integer).
///
/// # Safety
///
/// As [`fill_eights`]'; the word at `start` is readable.
#[inline(always)]
pub(crate) unsafe fn repeat_first_word(start: *mut u32, end: *mut u32) {
    let value: u32;
    // SAFETY: reads the word at `start` (the caller's promise); touches no stack.
    unsafe {
        core::arch::asm!(
            "ldr {value}, [{p}]",
            p = in(reg) start,
            value = out(reg) value,
            options(nostack, readonly, preserves_flags),
        );
    }
    // SAFETY: as `fill_eights` asks (the caller's promise).
    unsafe { fill_eights(start, end, value) };
}

/// Sets the words from `start` up to `end`, a whole number of eights (at least one) apart: two
/// `stm`s of four registers and two loop instructions a pass (the library `memset` LLVM calls
/// for a byte-uniform word takes about 15 instructions for those 32 bytes, its store loop 10).
/// `super::fill_words`' loop.
///
/// # Safety
///
/// `start..end` is a range of writable, 4-byte aligned words whose length is a multiple of
/// eight, at least eight.
#[inline(always)]
pub(crate) unsafe fn fill_eights(start: *mut u32, end: *mut u32, value: u32) {
    // SAFETY: stores words only in `start..end` (the caller's promise); touches no stack and
    // reads no memory.
    unsafe {
        core::arch::asm!(
            "2:",
            "stm {p}!, {{r0, r1, r2, r3}}",
            "stm {p}!, {{r0, r1, r2, r3}}",
            "cmp {p}, {end}",
            "bne 2b",
            p = inout(reg) start => _,
            end = in(reg) end,
            in("r0") value,
            in("r1") value,
            in("r2") value,
            in("r3") value,
            options(nostack),
        );
    }
}
