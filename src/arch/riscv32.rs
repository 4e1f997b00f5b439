//! RV32 with the M extension (`riscv32imc`, `riscv32imac`): the rows of a small depth-tested
//! triangle with interpolated light levels (the 3D pipeline's Gouraud fill) in assembly.
//!
//! The portable path draws a small face span by span, each span re-deriving its slices and
//! bounds. Here the whole row loop is one function with every value of the row state in a
//! register (RV32 has 31: the three edge numerators, their steps and divisors, the planes and
//! their steps, the table and the colour buffer's offset): a row's run is three `div`s (the
//! division form of the raster core's `RowRuns`), and a pixel is 14 instructions (7 where the
//! depth test fails).
//!
//! It computes what the portable path (`RowRuns::run` and the depth fill's span loop with the
//! `Leveled` pixel) computes from the same integers, as the Thumb-2 loop does (`thumbv7m`): the
//! same runs (`div` truncates as `sdiv` does, and a start bound below 0 is raised to 0 and an
//! end bound above the columns lowered to them in both), the same depth `z >> 16` tested and
//! written where it is below the stored one, the same colour `table[l >> 24]`, the planes
//! stepped by the same wrapping additions (a span's first values by `mul`, the wrapping `value +
//! step·start`). CI checks that the RV32 firmware's 3D frames and bands have the host's
//! checksums.
//!
//! The blend of a constant colour at a constant opacity over 5-6-5 pixels ([`blend_solid_565`]):
//! the portable pair loop takes 15.5 instructions a pixel here (LLVM reloads its masks and forms
//! the fields with a shift more each); here the masks and weights stay in registers and a word
//! (two pixels) is 18 instructions, the top and middle fields formed in place (10.75 a pixel
//! with the loop).
#![allow(unsafe_code)]

use embedded_graphics::pixelcolor::raw::RawU16;

use super::{LevelBlock, LevelRows};

core::arch::global_asm!(
    ".section .text.embedded_raster_level_rows_rv32,\"ax\",@progbits",
    // `global_asm!` is assembled without the target's features: `rv32` means M is there.
    ".option push",
    ".option arch, +m",
    ".p2align 2",
    ".global embedded_raster_level_rows_rv32",
    ".hidden embedded_raster_level_rows_rv32",
    ".type embedded_raster_level_rows_rv32,@function",
    // a0 = the block, a1 = whether the middle bound is a start bound.
    "embedded_raster_level_rows_rv32:",
    "addi sp, sp, -64",
    "sw ra, 60(sp)",
    "sw s0, 56(sp)",
    "sw s1, 52(sp)",
    "sw s2, 48(sp)",
    "sw s3, 44(sp)",
    "sw s4, 40(sp)",
    "sw s5, 36(sp)",
    "sw s6, 32(sp)",
    "sw s7, 28(sp)",
    "sw s8, 24(sp)",
    "sw s9, 20(sp)",
    "sw s10, 16(sp)",
    "sw s11, 12(sp)",
    // s0-s2: depth, level and depth pointer at the row's first column; s3-s5: their steps a
    // row; s6-s8: the numerators' steps a row; s9-s11: the divisors.
    "lw s0, 0(a0)",
    "lw s1, 4(a0)",
    "lw s2, 8(a0)",
    "lw s3, 12(a0)",
    "lw s4, 16(a0)",
    "lw s5, 20(a0)",
    "lw s6, 24(a0)",
    "lw s7, 28(a0)",
    "lw s8, 32(a0)",
    "lw s9, 36(a0)",
    "lw s10, 40(a0)",
    "lw s11, 44(a0)",
    // a2: the columns; a3, a4: depth and level steps a column; a5: the table; a6: the colour
    // pointer's offset from the depth pointer; a7, t3, t4: the start, middle and end
    // numerators; t5: rows left.
    "lw a2, 48(a0)",
    "lw a3, 52(a0)",
    "lw a4, 56(a0)",
    "lw a5, 60(a0)",
    "lw a6, 64(a0)",
    "sub a6, a6, s2",
    "lw a7, 68(a0)",
    "lw t3, 72(a0)",
    "lw t4, 76(a0)",
    "lw t5, 80(a0)",
    // A row's run in t0..t1: three divisions, start ≥ 0, end ≤ columns, the middle bound
    // (t2) folded into the start or the end.
    "1:",
    "div t0, a7, s9",
    "div t1, t4, s11",
    "div t2, t3, s10",
    "bgez t0, 2f",
    "li t0, 0",
    "2:",
    "bge a2, t1, 3f",
    "mv t1, a2",
    "3:",
    "beqz a1, 4f",
    "blt t2, t0, 5f",
    "mv t0, t2",
    "j 5f",
    "4:",
    "bge t2, t1, 5f",
    "mv t1, t2",
    "5:",
    "bge t0, t1, 7f",
    // The span: t2 = depth, t6 = level at its first pixel, t0 = its depth pointer, t1 = past
    // its last.
    "mul t2, t0, a3",
    "add t2, t2, s0",
    "mul t6, t0, a4",
    "add t6, t6, s1",
    "slli t0, t0, 1",
    "add t0, t0, s2",
    "slli t1, t1, 1",
    "add t1, t1, s2",
    "6:",
    "lhu a0, 0(t0)",
    "srli ra, t2, 16",
    "bgeu ra, a0, 8f",
    "sh ra, 0(t0)",
    "srli ra, t6, 24",
    "slli ra, ra, 1",
    "add ra, ra, a5",
    "lhu ra, 0(ra)",
    "add a0, t0, a6",
    "sh ra, 0(a0)",
    "8:",
    "add t2, t2, a3",
    "add t6, t6, a4",
    "addi t0, t0, 2",
    "bltu t0, t1, 6b",
    // The next row.
    "7:",
    "add s0, s0, s3",
    "add s1, s1, s4",
    "add s2, s2, s5",
    "add a7, a7, s6",
    "add t3, t3, s7",
    "add t4, t4, s8",
    "addi t5, t5, -1",
    "bnez t5, 1b",
    "lw ra, 60(sp)",
    "lw s0, 56(sp)",
    "lw s1, 52(sp)",
    "lw s2, 48(sp)",
    "lw s3, 44(sp)",
    "lw s4, 40(sp)",
    "lw s5, 36(sp)",
    "lw s6, 32(sp)",
    "lw s7, 28(sp)",
    "lw s8, 24(sp)",
    "lw s9, 20(sp)",
    "lw s10, 16(sp)",
    "lw s11, 12(sp)",
    "addi sp, sp, 64",
    "ret",
    ".size embedded_raster_level_rows_rv32, . - embedded_raster_level_rows_rv32",
    ".option pop",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_level_rows_rv32(block: *const LevelBlock, middle_starts: u32);
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
    let Some(block) = LevelBlock::new(colors, depths, rows, table) else {
        return false;
    };
    // SAFETY: the function writes only pixels of the region — rows `0..rows` from the first
    // pixel, `width` pixels apart, each in columns `start..end` with `0 ≤ start` and
    // `end ≤ columns` — which are inside both buffers (checked by `LevelBlock::new`), as 2-byte
    // aligned `u16`s (`C` is a 2-byte colour: a copy of the table's bytes is a copy of its
    // colours). It reads the table at `level >> 24 < 256` and the block, divides by the
    // non-zero divisors only, and saves and restores every register the RISC-V calling
    // convention asks it to (`ra`, `s0`-`s11`, `sp`).
    unsafe { embedded_raster_level_rows_rv32(&block, u32::from(rows.middle_starts)) };
    true
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
            "lw {value}, 0({p})",
            p = in(reg) start,
            value = out(reg) value,
            options(nostack, readonly, preserves_flags),
        );
    }
    // SAFETY: as `fill_eights` asks (the caller's promise).
    unsafe { fill_eights(start, end, value) };
}

/// Sets the words from `start` up to `end`, a whole number of eights (at least one) apart:
/// eight stores and two loop instructions a pass (the library `memset` LLVM calls otherwise
/// stores one word a pass of three). `super::fill_words`' loop.
///
/// # Safety
///
/// `start..end` is a range of writable, 4-byte aligned words whose length is a multiple of
/// eight, at least eight.
#[inline(always)]
pub(crate) unsafe fn fill_eights(start: *mut u32, end: *mut u32, value: u32) {
    // SAFETY: stores words only in `start..end` (the caller's promise); touches no stack.
    unsafe {
        core::arch::asm!(
            "2:",
            "sw {value}, 0({p})",
            "sw {value}, 4({p})",
            "sw {value}, 8({p})",
            "sw {value}, 12({p})",
            "sw {value}, 16({p})",
            "sw {value}, 20({p})",
            "sw {value}, 24({p})",
            "sw {value}, 28({p})",
            "addi {p}, {p}, 32",
            "bltu {p}, {end}, 2b",
            p = inout(reg) start => _,
            end = in(reg) end,
            value = in(reg) value,
            options(nostack, preserves_flags),
        );
    }
}

/// Blends the two 5-6-5 pixels of the word `$d` (temporaries `$t`, `$m`), the weights and masks
/// in registers: a3 = `256 − w`; a4, a5, a6 = the top, middle and bottom fields' `s·w + 128` in
/// both halves, the top one shifted left by 3; a7 = 0x00F800F8, t3 = 0x003F003F, t4 =
/// 0xF800F800, t5 = 0x07E007E0, t6 = 0x001F001F. Each field `x = d·(256 − w) + s·w + 128` is
/// below 2¹³ (2¹⁴ the middle one), so the lanes never carry into each other: the top field
/// formed as `x·8` is in place under 0xF800, the middle one as `x >> 3` under 0x07E0.
#[rustfmt::skip]
macro_rules! blend_pair_rv32 {
    ($d:literal, $t:literal, $m:literal) => {
        concat!(
            "srli ", $t, ", ", $d, ", 8\n",
            "and ", $t, ", ", $t, ", a7\n",
            "mul ", $t, ", ", $t, ", a3\n",
            "add ", $t, ", ", $t, ", a4\n",
            "and ", $t, ", ", $t, ", t4\n",
            "srli ", $m, ", ", $d, ", 5\n",
            "and ", $m, ", ", $m, ", t3\n",
            "mul ", $m, ", ", $m, ", a3\n",
            "add ", $m, ", ", $m, ", a5\n",
            "srli ", $m, ", ", $m, ", 3\n",
            "and ", $m, ", ", $m, ", t5\n",
            "and ", $d, ", ", $d, ", t6\n",
            "mul ", $d, ", ", $d, ", a3\n",
            "add ", $d, ", ", $d, ", a6\n",
            "srli ", $d, ", ", $d, ", 8\n",
            "and ", $d, ", ", $d, ", t6\n",
            "or ", $d, ", ", $d, ", ", $t, "\n",
            "or ", $d, ", ", $d, ", ", $m, "\n",
        )
    };
}

core::arch::global_asm!(
    ".section .text.embedded_raster_blend_565_rv32,\"ax\",@progbits",
    ".option push",
    ".option arch, +m",
    ".p2align 2",
    ".global embedded_raster_blend_565_rv32",
    ".hidden embedded_raster_blend_565_rv32",
    ".type embedded_raster_blend_565_rv32,@function",
    // a0 = pixels (2-byte aligned), a1 = pixel count, a2 = the weights.
    "embedded_raster_blend_565_rv32:",
    "lw a3, 0(a2)",
    "lw a4, 4(a2)",
    "slli a4, a4, 3",
    "lw a5, 8(a2)",
    "lw a6, 12(a2)",
    "li t6, 0x001F001F",
    "slli a7, t6, 3",
    "slli t4, t6, 11",
    "li t3, 0x003F003F",
    "slli t5, t3, 5",
    // A first pixel at an address of 2 mod 4 alone.
    "andi t0, a0, 2",
    "beqz t0, 1f",
    "beqz a1, 9f",
    "lhu t0, 0(a0)",
    blend_pair_rv32!("t0", "t1", "t2"),
    "sh t0, 0(a0)",
    "addi a0, a0, 2",
    "addi a1, a1, -1",
    // Four pixels (two words) a pass while there are four.
    "1:",
    "addi a1, a1, -4",
    "bltz a1, 3f",
    "2:",
    "lw t0, 0(a0)",
    "lw t1, 4(a0)",
    blend_pair_rv32!("t0", "t2", "a2"),
    blend_pair_rv32!("t1", "t2", "a2"),
    "sw t0, 0(a0)",
    "sw t1, 4(a0)",
    "addi a0, a0, 8",
    "addi a1, a1, -4",
    "bgez a1, 2b",
    // Then a word if two or three are left, and a last pixel alone.
    "3:",
    "andi t1, a1, 2",
    "beqz t1, 5f",
    "lw t0, 0(a0)",
    blend_pair_rv32!("t0", "t2", "a2"),
    "sw t0, 0(a0)",
    "addi a0, a0, 4",
    "5:",
    "andi t1, a1, 1",
    "beqz t1, 9f",
    "lhu t0, 0(a0)",
    blend_pair_rv32!("t0", "t2", "a2"),
    "sh t0, 0(a0)",
    "9:",
    "ret",
    ".size embedded_raster_blend_565_rv32, . - embedded_raster_blend_565_rv32",
    ".option pop",
);

extern "C" {
    /// The assembly function above.
    fn embedded_raster_blend_565_rv32(pixels: *mut u16, len: usize, weights: *const [u32; 4]);
}

/// Blends the constant colour of `weights` over every pixel of `pixels`, 5-6-5 colours (one
/// `u16` each, every raw value a colour: `C: From<RawU16>`): `weights` are `256 − w` and the
/// raw top, middle and bottom fields' `s·w + 128`, each in both halves of its word (`s·w + 128
/// ≤ 63·256 + 128`, the top one at most `31·256 + 128`). Each field becomes `(pre + d·(256 −
/// w)) >> 8`, as `color::blend`'s portable loop gives it. `false` without writing anything if
/// `C` is not a 16-bit colour.
#[inline(always)]
pub(crate) fn blend_solid_565<C: From<RawU16>>(pixels: &mut [C], weights: &[u32; 4]) -> bool {
    if core::mem::size_of::<C>() != 2 || core::mem::align_of::<C>() != 2 || pixels.len() < SHORT {
        return false;
    }
    // SAFETY: the function reads and writes exactly `pixels.len()` consecutive 2-byte aligned
    // `u16`s from the slice's start, which are the slice's own (a 5-6-5 colour is one `u16`,
    // any bits a colour), words only at 4-byte aligned addresses, and reads the four words of
    // `weights`; it uses only registers the calling convention lets it clobber, and no stack.
    unsafe { embedded_raster_blend_565_rv32(pixels.as_mut_ptr().cast(), pixels.len(), weights) }
    true
}

/// Spans shorter than this take the portable loop: the assembly's set-up (the weights and masks
/// into registers, a call) costs more than it saves on a few pixels.
const SHORT: usize = 12;
