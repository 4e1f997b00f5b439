//! ARMv7-M (Cortex-M3/M4/M7): the rows of a small depth-tested triangle with interpolated light
//! levels (the 3D pipeline's Gouraud fill) in Thumb-2 assembly.
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
#![allow(unsafe_code)]

use super::LevelRows;

/// What the assembly reads: `LevelRows` as pointers and the per-row state first (offsets in
/// the comments are the assembly's).
#[repr(C)]
struct Block {
    /// 0, 4, 8: depth and level at the row's first column, the depth pointer there.
    depth: u32,
    level: u32,
    depths: *mut u16,
    /// 12, 16, 20: their steps a row (the pointer's in bytes).
    depth_row: u32,
    level_row: u32,
    stride: u32,
    /// 24, 28, 32: the numerators' steps a row.
    steps: [i32; 3],
    /// 36, 40, 44: the divisors.
    divisors: [u32; 3],
    /// 48: the region's columns.
    columns: u32,
    /// 52, 56: depth and level steps a column.
    depth_column: u32,
    level_column: u32,
    /// 60: the colour table (256 entries).
    table: *const u16,
    /// 64: the colour pointer at the region's first pixel (the assembly replaces it with its
    /// offset from the depth pointer, less 2).
    colors: *mut u16,
    /// 68, 72, 76: the numerators at the first row; 80: the rows.
    numerators: [i32; 3],
    rows: u32,
}

const _: () = assert!(core::mem::size_of::<Block>() == 84);

/// One row of the loop, `$middle` folding the middle bound (r12) into the start (r10) or the end
/// (r11). Registers: r0 = the block, r1-r3 = the numerators, lr = rows left; the rest are free.
macro_rules! level_row {
    ($middle:literal) => {
        concat!(
            // The run: three divisions, start ≥ 0, end ≤ columns.
            "ldrd r7, r8, [r0, #36]\n",
            "ldr r9, [r0, #44]\n",
            "sdiv r10, r1, r7\n",
            "sdiv r11, r3, r9\n",
            "sdiv r12, r2, r8\n",
            "bic r10, r10, r10, asr #31\n",
            "ldr r9, [r0, #48]\n",
            "cmp r11, r9\n",
            "it gt\n",
            "movgt r11, r9\n",
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
            "2:\n",
            "ldrh r12, [r6], #2\n",
            "cmp r12, r4, lsr #16\n",
            "bls 4f\n",
            "lsr r12, r4, #16\n",
            "strh r12, [r6, #-2]\n",
            "lsr r12, r5, #24\n",
            "ldrh r12, [r10, r12, lsl #1]\n",
            "strh r12, [r6, r11]\n",
            "4:\n",
            "add r4, r7\n",
            "add r5, r8\n",
            "cmp r6, r9\n",
            "blo 2b\n",
            // The next row.
            "3:\n",
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
            "subs lr, #1\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_level_rows_v7m,\"ax\",%progbits",
    ".syntax unified",
    ".thumb",
    ".p2align 2",
    ".global embedded_raster_level_rows_v7m",
    ".hidden embedded_raster_level_rows_v7m",
    ".type embedded_raster_level_rows_v7m,%function",
    ".thumb_func",
    // r0 = the block, r1 = whether the middle bound is a start bound.
    "embedded_raster_level_rows_v7m:",
    "push {{r4-r11, lr}}",
    // The colour pointer as an offset from the depth pointer after its post-increment.
    "ldr r2, [r0, #8]",
    "ldr r3, [r0, #64]",
    "sub r3, r3, r2",
    "sub r3, r3, #2",
    "str r3, [r0, #64]",
    "add r12, r0, #68",
    "cmp r1, #0",
    "beq 5f",
    "ldm r12, {{r1, r2, r3, lr}}",
    "1:",
    level_row!("cmp r12, r10\nit gt\nmovgt r10, r12"),
    "bne 1b",
    "pop {{r4-r11, pc}}",
    "5:",
    "ldm r12, {{r1, r2, r3, lr}}",
    "6:",
    level_row!("cmp r12, r11\nit lt\nmovlt r11, r12"),
    "bne 6b",
    "pop {{r4-r11, pc}}",
    ".size embedded_raster_level_rows_v7m, . - embedded_raster_level_rows_v7m",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_level_rows_v7m(block: *mut Block, middle_starts: u32);
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
    if core::mem::size_of::<C>() != 2 || core::mem::align_of::<C>() != 2 {
        return false;
    }
    // The region's last pixel, in both buffers; its columns within a buffer row. In 64 bits:
    // indices are 32-bit here, so the sum cannot wrap.
    let (columns, count) = (rows.columns as usize, rows.rows as usize);
    let wide = |n: usize| n as u64;
    let last = wide(rows.first)
        + wide(count.wrapping_sub(1)) * wide(rows.width)
        + wide(columns.wrapping_sub(1));
    let inside = columns >= 1
        && count >= 1
        && columns <= rows.width
        && last < wide(colors.len().min(depths.len()));
    // Strides and offsets in bytes fit 32 bits where the buffers do (a 32-bit address space).
    if !inside || u32::try_from(rows.width * 2).is_err() {
        return false;
    }
    let [s, m, e] = rows.bounds;
    let mut block = Block {
        depth: rows.depth[0],
        level: rows.level[0],
        depths: depths.as_mut_ptr().wrapping_add(rows.first),
        depth_row: rows.depth[2],
        level_row: rows.level[2],
        stride: (rows.width * 2) as u32,
        steps: [s.2, m.2, e.2],
        divisors: [s.1.get(), m.1.get(), e.1.get()],
        columns: rows.columns,
        depth_column: rows.depth[1],
        level_column: rows.level[1],
        table: table.as_ptr().cast(),
        colors: colors.as_mut_ptr().wrapping_add(rows.first).cast(),
        numerators: [s.0, m.0, e.0],
        rows: rows.rows,
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
