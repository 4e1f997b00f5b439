//! Target-specific code, and the target facts the portable code branches on.
//!
//! Every `target_arch` decision of the crate is here or in `build.rs`, which names the targets
//! as `cfg`s (`armv6m`, `armv7m`, `arm_dsp`, `armv8m`, `rv32`, `sse2_rows`). The portable code asks the
//! constants below; the instruction-level code (SSE2 intrinsics, Thumb and RISC-V assembly)
//! lives in one file per target, each computing exactly what a portable function computes
//! (tested on the host, and by the firmware checksums in CI).

#[cfg(rv32)]
pub(crate) mod riscv32;
#[cfg(armv6m)]
pub(crate) mod thumbv6m;
#[cfg(armv7m)]
pub(crate) mod thumbv7m;
#[cfg(sse2_rows)]
pub(crate) mod x86_64;

use core::num::NonZeroU32;

#[cfg(rv32)]
pub(crate) use riscv32::blend_solid_565;
#[cfg(rv32)]
pub(crate) use riscv32::level_rows;
#[cfg(armv6m)]
pub(crate) use thumbv6m::blend_solid_565;
#[cfg(armv6m)]
pub(crate) use thumbv6m::depth_masked_nearest_565;
#[cfg(armv6m)]
pub(crate) use thumbv6m::masked_nearest_565;
#[cfg(armv6m)]
pub(crate) use thumbv6m::premultiplied_565;
#[cfg(arm_dsp)]
pub(crate) use thumbv7m::bilinear_span_565;
#[cfg(armv7m)]
pub(crate) use thumbv7m::blend_solid_565;
#[cfg(armv7m)]
pub(crate) use thumbv7m::dithered_565;
#[cfg(armv7m)]
pub(crate) use thumbv7m::level_rows;
#[cfg(armv7m)]
pub(crate) use thumbv7m::perspective_span;
#[cfg(armv7m)]
pub(crate) use thumbv7m::premultiplied_565;
#[cfg(armv7m)]
pub(crate) use thumbv7m::project_positions;
#[cfg(armv7m)]
pub(crate) use thumbv7m::textured_rows;
#[cfg(armv7m)]
pub(crate) use thumbv7m::{level_face, level_face_keeping, level_faces};
#[cfg(armv7m)]
pub(crate) use thumbv7m::{textured_face, textured_faces};

/// Pixels of a row of a tiny triangle's box, drawn at once on x86-64: one 16-bit lane each, one
/// SSE2 register.
pub const LANES: usize = 8;

/// ARMv6-M: no 32 × 32 → 64-bit multiply (every 64-bit product is a library call): products of
/// 32-bit factors are formed from 16-bit limbs.
pub(crate) const NO_LONG_MULTIPLY: bool = cfg!(armv6m);

/// ARMv6-M: no `clz` instruction (the library routine is a call of about the same length as a
/// few halving steps).
pub(crate) const NO_CLZ: bool = cfg!(armv6m);

/// A perspective span's chunks find their lengths from thresholds set once a span and their
/// alignment from a table, not by counting bits a chunk (`raster::perspective`): where there is
/// no `clz` instruction — ARMv6-M, and RV32 without the Zbb extension, whose leading-zero count
/// LLVM expands inline (about 20 instructions). Elsewhere on RV32 the inline count stays: it
/// beats [`NO_CLZ`]'s halving steps (a tiny triangle's set-up 453 instructions against 544).
pub(crate) const CHUNKS_BY_THRESHOLDS: bool =
    cfg!(any(armv6m, all(rv32, not(target_feature = "zbb"))));

/// A microcontroller core — Cortex-M, or RV32 (RISC-V's `riscv32` targets): branches are cheap
/// and predictable, loops are not vectorised, a 32-bit division (where there is a divider) costs
/// a few multiplies rather than a host's tens of cycles, and code size matters more than a
/// host's branch predictor.
pub(crate) const MCU: bool = cfg!(any(armv6m, armv7m, rv32));

/// ARMv6-M: the parts with the least flash (16–32 KB on a micro:bit's nRF51), where a loop's
/// second copy for speed costs more than it saves: code size first where the two conflict.
pub(crate) const SIZE_OVER_SPEED: bool = cfg!(armv6m);

/// A 32-bit hardware divider (ARMv7-M, and every host): a 32-bit division is one instruction
/// (on Cortex-M0 it is a library loop).
pub(crate) const HAS_DIVIDER: bool = !cfg!(armv6m);

/// A 64-bit host: a 64-bit division is one instruction (on Cortex-M it is a long library call).
pub(crate) const FAST_WIDE_DIVISION: bool = cfg!(target_pointer_width = "64");

/// ARMv7-M and RV32: the rows of a small depth-tested triangle with light levels (the 3D
/// pipeline's Gouraud fill) are drawn by one assembly loop ([`level_rows`]); elsewhere span by
/// span.
pub(crate) const LEVEL_ROWS: bool = cfg!(any(armv7m, rv32));

/// ARMv7-M: a small face of the 3D pipeline's Gouraud fill is set up (box, region, edges, runs
/// and its depth and level planes) by one assembly function ([`level_face`]) that hands it to
/// the row loop of [`level_rows`]; elsewhere by `raster::scan`.
pub(crate) const LEVEL_FACE: bool = cfg!(armv7m);

/// A clip's first column and row and its last column and row as [`level_face`] reads them,
/// kept once a draw where there is a face set-up (ARMv7-M); elsewhere nothing: the clip is in
/// the stack frame of every fill, and the micro:bit's stack has little to spare.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ClipBounds {
    #[cfg(armv7m)]
    bounds: [i32; 4],
}

impl ClipBounds {
    /// The bounds of a clip whose first column and row and last column and row are `bounds`.
    #[inline(always)]
    pub(crate) fn new(bounds: [i32; 4]) -> Self {
        #[cfg(not(armv7m))]
        let _ = bounds;
        ClipBounds {
            #[cfg(armv7m)]
            bounds,
        }
    }

    /// The four bounds (zeros where none are kept).
    #[inline(always)]
    fn words(self) -> [i32; 4] {
        #[cfg(armv7m)]
        return self.bounds;
        #[cfg(not(armv7m))]
        [0; 4]
    }
}

/// A vertex that [`level_face`] reads where it is.
///
/// # Safety
///
/// An implementor is at least 16 bytes and 4-byte aligned, with its position's x and y
/// (sub-pixels, `i32`) at bytes 0 and 4, its depth (`u16`) at byte 8 and its light level (8.8,
/// `u16`) at byte 12.
#[allow(unsafe_code)]
pub(crate) unsafe trait LevelVertex {}

/// A face for [`level_face`] (offsets are the assembly's): its vertices, read in place, the clip,
/// the buffers, and the rounding terms of the depth and level planes.
#[repr(C)]
// Read only where the assembly is.
#[cfg_attr(not(armv7m), allow(dead_code))]
pub(crate) struct LevelFace<'v> {
    /// 0, 4, 8: the vertices (`LevelVertex`s).
    vertices: [*const u8; 3],
    /// 12-24: the clip's first column and row, its last column and row.
    clip: [i32; 4],
    /// 28, 32: the colour and depth buffers ([`level_face`] sets them); 36: a buffer row in
    /// bytes; 40: the colour table.
    colors: *mut u16,
    depths: *mut u16,
    stride: u32,
    table: *const u16,
    /// 44, 48: the depth's and the level's rounding terms.
    half: [u32; 2],
    /// 52: where to write the set-up too ([`level_face_keeping`]), or null.
    setup: *mut SmallSetup,
    /// 56, 60: the rows drawn, first and last (a band's); the buffers' first row is the first.
    rows: [i32; 2],
    borrowed: core::marker::PhantomData<&'v ()>,
}

/// A small face's set-up as [`level_face_keeping`] writes it: the row loop's block (its buffer
/// words zero), the region's first pixel, and whether the middle bound starts.
#[repr(C)]
pub(crate) struct SmallSetup {
    block: LevelBlock,
    x0: i32,
    y0: i32,
    middle_starts: u32,
}

impl SmallSetup {
    /// The region's first pixel and its rows as [`LevelRows`] has them (with no buffer: `first`
    /// and `width` 0).
    #[cfg_attr(not(armv7m), allow(dead_code))]
    pub(crate) fn rows(&self) -> ((i32, i32), LevelRows) {
        let b = &self.block;
        let bound = |k: usize| {
            (
                b.numerators[k],
                NonZeroU32::new(b.divisors[k]).unwrap_or(NonZeroU32::MIN),
                b.steps[k],
            )
        };
        let rows = LevelRows {
            first: 0,
            width: 0,
            columns: b.columns,
            rows: b.rows,
            bounds: [bound(0), bound(1), bound(2)],
            middle_starts: self.middle_starts != 0,
            depth: [b.depth, b.depth_column, b.depth_row],
            level: [b.level, b.level_column, b.level_row],
        };
        ((self.x0, self.y0), rows)
    }
}

/// What [`level_face_keeping`] did.
#[cfg_attr(not(armv7m), allow(dead_code))]
pub(crate) enum FaceSetup<'s> {
    /// Nothing of the face is inside its clip.
    Done,
    /// Not small, or a sliver: the portable set-up's to draw (nothing drawn).
    Declined,
    /// Its set-up (over the clip), and its rows in the face's rows drawn (there may be none).
    Ready(&'s SmallSetup),
}

/// [`level_face_keeping`] where there is none: declines.
#[cfg(not(armv7m))]
#[inline(always)]
pub(crate) fn level_face_keeping<'s, C: Copy>(
    _buffers: (&mut [C], &mut [u16], usize),
    _face: LevelFace<'_>,
    _table: &[C; 256],
    _setup: &'s mut core::mem::MaybeUninit<SmallSetup>,
) -> FaceSetup<'s> {
    FaceSetup::Declined
}

impl<'v> LevelFace<'v> {
    /// The face of `vertices` inside `clip` (its first column and row, its last column and
    /// row: [`ClipBounds`]), the planes rounded by `half`, drawn in rows `rows` (first and
    /// last: a band's, whose first is the buffers' first; every row is `[0, i32::MAX]`).
    #[inline(always)]
    pub(crate) fn new<V: LevelVertex>(
        vertices: [&'v V; 3],
        clip: ClipBounds,
        half: [u32; 2],
        rows: [i32; 2],
    ) -> Self {
        LevelFace {
            vertices: vertices.map(|v| (v as *const V).cast()),
            ..LevelFace::without_vertices(clip, half, rows)
        }
    }
}

impl LevelFace<'static> {
    /// The faces of a draw inside `clip`, the planes rounded by `half`, drawn in rows `rows`
    /// (as [`new`](Self::new)), without vertices: the [`FaceScan`]'s, which sets each face's
    /// vertices before its set-up ([`level_faces`]).
    #[inline(always)]
    pub(crate) fn without_vertices(clip: ClipBounds, half: [u32; 2], rows: [i32; 2]) -> Self {
        LevelFace {
            vertices: [core::ptr::null(); 3],
            clip: clip.words(),
            colors: core::ptr::null_mut(),
            depths: core::ptr::null_mut(),
            stride: 0,
            table: core::ptr::null(),
            half,
            setup: core::ptr::null_mut(),
            rows,
            borrowed: core::marker::PhantomData,
        }
    }
}

/// [`level_faces`] where there is no set-up: none.
#[cfg(not(armv7m))]
#[inline(always)]
pub(crate) fn level_faces<C: Copy>(
    _buffers: (&mut [C], &mut [u16], usize),
    _face: LevelFace<'static>,
    _table: &[C; 256],
) -> Option<LevelFace<'static>> {
    None
}

/// [`level_face`] where there is none: draws nothing and says so.
#[cfg(not(armv7m))]
#[inline(always)]
pub(crate) fn level_face<C: Copy>(
    _buffers: (&mut [C], &mut [u16], usize),
    _face: LevelFace<'_>,
    _table: &[C; 256],
) -> bool {
    false
}

/// ARMv6-M: an affine span of nearest texels from a power-of-two repeating texture of raw
/// Rgb565 words into Rgb565 pixels is one assembly loop ([`masked_nearest_565`]); elsewhere the
/// portable masked loop (`texture::span`), which LLVM keeps in registers there.
pub(crate) const MASKED_NEAREST_565: bool = cfg!(armv6m);

/// An affine span of nearest texels of a texture repeating on both axes with power-of-two
/// sides, whose texels are raw Rgb565 words: pixel `i` is `texels[row | column]` with `column =
/// ((x + i·dx) >> 16) & x_mask` and `row = ((y + i·dy) >> 16) & rows`, `y` and `dy` being the
/// 16.16 coordinate and step scaled by the row width (wrapping), as in `texture::span`'s masked
/// nearest loop.
///
/// Public in this private module: the argument of a hidden `GouraudColor` method, which no
/// implementation outside the crate can name.
#[derive(Clone, Copy, Debug)]
// Read only where the assembly is (and by the host's test of its arithmetic).
#[cfg_attr(not(any(armv6m, arm_dsp, test)), allow(dead_code))]
pub struct MaskedSpan565<'a> {
    /// The texels (row-major).
    pub(crate) texels: &'a [u16],
    /// The 16.16 texel `x` at the first pixel and its step a pixel.
    pub(crate) x: (i32, i32),
    /// `y`, likewise, both scaled by the row width (shifted left by its bits, wrapping).
    pub(crate) y: (i32, i32),
    /// The column mask (the width less one).
    pub(crate) x_mask: u32,
    /// The row mask in storage units: the height less one, times the width.
    pub(crate) rows: u32,
}

/// [`blend_solid_565`] where there is none (hosts: the portable loop, which LLVM vectorises):
/// blends nothing and says so. On Cortex-M and RV32 a constant colour at a constant opacity over
/// 5-6-5 pixels is one assembly loop, two pixels a word, the constants in registers.
#[cfg(not(any(armv6m, armv7m, rv32)))]
#[inline(always)]
pub(crate) fn blend_solid_565<C>(_pixels: &mut [C], _weights: &[u32; 4]) -> bool {
    false
}

/// A span of a dithered 5-6-5 fill for the target's loop ([`dithered_565`]; `color::packed565`'s
/// `dithered_565` defines its pixels): channels in raw order (top, middle, bottom). Each run of
/// 32 pixels (the last one shorter) starts from the values there, rounded to their lanes.
#[repr(C)]
#[cfg_attr(not(any(armv7m, test)), allow(dead_code))]
pub(crate) struct DitheredSpan565<'a> {
    /// 0: the channels at the span's first pixel (24 fractional bits, +½ included).
    pub(crate) value: &'a [u32; 3],
    /// 4: the lanes' steps a pixel, two of them in both halves of a word, and the channels'
    /// steps a pixel (`color::SpanSteps`' layout, its steps in raw order).
    pub(crate) steps: &'a [u32; 9],
    /// 8, 12: the Bayer offsets of the span's pixels 0 and 1, and 2 and 3, as words of two
    /// lanes with 11 fractional bits (`color`'s `bayer_pair`).
    pub(crate) first: u32,
    pub(crate) second: u32,
}

/// [`dithered_565`] where there is none (the portable loop draws the span; ARMv6-M's Thumb-1
/// loop is `thumbv6m::dithered_span_565`, which stops at a run it does not draw): draws nothing
/// and says so.
#[cfg(not(any(armv7m, armv6m)))]
#[inline(always)]
pub(crate) fn dithered_565<C>(_pixels: &mut [C], _span: &DitheredSpan565<'_>) -> bool {
    false
}

/// [`bilinear_span_565`] where there is none (ARMv7E-M's dual products draw it): draws nothing
/// and says so.
#[cfg(not(arm_dsp))]
#[inline(always)]
pub(crate) fn bilinear_span_565<C: Copy>(_pixels: &mut [C], _span: &MaskedSpan565<'_>) -> bool {
    false
}

/// [`masked_nearest_565`] where there is none: draws nothing and says so.
#[cfg(not(armv6m))]
#[inline(always)]
pub(crate) fn masked_nearest_565(
    _pixels: &mut [embedded_graphics::pixelcolor::Rgb565],
    _span: &MaskedSpan565<'_>,
) -> bool {
    false
}

/// ARMv6-M: the pixels between two perspective-correct chunk ends of the 3D textured fill —
/// depth-tested nearest texels of a power-of-two repeating texture of raw Rgb565 words into
/// Rgb565 pixels, unlit — are one assembly loop ([`depth_masked_nearest_565`]); elsewhere the
/// portable pixel loop (on ARMv7-M the whole span is [`perspective_span`]).
pub(crate) const DEPTH_MASKED_565: bool = cfg!(armv6m);

/// [`depth_masked_nearest_565`] where there is none: draws nothing and says so.
#[cfg(not(armv6m))]
#[inline(always)]
pub(crate) fn depth_masked_nearest_565(
    _pixels: &mut [embedded_graphics::pixelcolor::Rgb565],
    _depths: &mut [u16],
    _span: &MaskedSpan565<'_>,
    _depth: (u32, u32),
) -> bool {
    false
}

/// A small triangle's rows in the division form of the raster core's `RowRuns`, over buffers
/// of `width` pixels a row.
#[derive(Clone, Copy, Debug)]
// Read only where the assembly is (elsewhere the row loop declines them).
#[cfg_attr(not(any(armv7m, rv32)), allow(dead_code))]
pub(crate) struct LevelRows {
    /// Index in the buffers of the region's top-left pixel.
    pub(crate) first: usize,
    /// Pixels of a buffer row.
    pub(crate) width: usize,
    /// Columns of the region: its rows' runs lie in `0..columns`.
    pub(crate) columns: u32,
    /// Rows of the region (at least one).
    pub(crate) rows: u32,
    /// The start bound, the middle bound and the end bound of the first row's run: numerator,
    /// divisor, the numerator's change a row.
    pub(crate) bounds: [(i32, NonZeroU32, i32); 3],
    /// Whether the middle bound is a start bound (else an end bound).
    pub(crate) middle_starts: bool,
    /// The depth plane (24 fractional bits of the 8.8 depth: the depth is `value >> 16`): at
    /// the first pixel, its step a column, its step a row.
    pub(crate) depth: [u32; 3],
    /// The light level plane (the level is `value >> 24`), likewise.
    pub(crate) level: [u32; 3],
}

/// What the row loops of [`level_rows`] read: [`LevelRows`] as pointers, the per-row state
/// first (offsets in the comments are the assembly's), built only for a region inside both
/// buffers.
#[repr(C)]
#[cfg_attr(not(any(armv7m, rv32)), allow(dead_code))]
pub(crate) struct LevelBlock {
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
    /// 64: the colour pointer at the region's first pixel (the Thumb-2 loop replaces it with
    /// its offset from the depth pointer, less 2).
    colors: *mut u16,
    /// 68, 72, 76: the numerators at the first row; 80: the rows.
    numerators: [i32; 3],
    rows: u32,
}

#[cfg(any(armv7m, rv32))]
const _: () = assert!(core::mem::size_of::<LevelBlock>() == 84);

// The offsets the Thumb-2 face set-up and row loop read and write (a field moved fails the
// build).
#[cfg(armv7m)]
const _: () = {
    use core::mem::{align_of, offset_of, size_of};
    type Face = LevelFace<'static>;
    assert!(offset_of!(Face, clip) == 12 && offset_of!(Face, colors) == 28);
    assert!(offset_of!(Face, depths) == 32 && offset_of!(Face, stride) == 36);
    assert!(offset_of!(Face, table) == 40 && offset_of!(Face, half) == 44);
    assert!(offset_of!(Face, setup) == 52 && offset_of!(Face, rows) == 56);
    assert!(offset_of!(LevelBlock, depths) == 8 && offset_of!(LevelBlock, depth_row) == 12);
    assert!(offset_of!(LevelBlock, stride) == 20 && offset_of!(LevelBlock, steps) == 24);
    assert!(offset_of!(LevelBlock, divisors) == 36 && offset_of!(LevelBlock, columns) == 48);
    assert!(offset_of!(LevelBlock, depth_column) == 52 && offset_of!(LevelBlock, table) == 60);
    assert!(offset_of!(LevelBlock, colors) == 64 && offset_of!(LevelBlock, numerators) == 68);
    assert!(offset_of!(LevelBlock, rows) == 80 && offset_of!(SmallSetup, x0) == 84);
    assert!(offset_of!(SmallSetup, middle_starts) == 92 && size_of::<SmallSetup>() == 96);
    type Template = TexturedTemplate;
    assert!(offset_of!(Template, rows) == 0 && offset_of!(Template, y_shift) == 8);
    assert!(offset_of!(Template, clip) == 12 && offset_of!(Template, half) == 28);
    assert!(offset_of!(Template, x_mask) == 44 && offset_of!(Template, rows_mask) == 48);
    assert!(offset_of!(Template, affine_level) == 52);
    type Textured = TexturedFace<'static>;
    assert!(offset_of!(Textured, vertices) == 0 && offset_of!(Textured, depths) == 12);
    assert!(offset_of!(Textured, color_offset) == 16 && offset_of!(Textured, stride) == 20);
    assert!(offset_of!(Textured, texels) == 24 && offset_of!(Textured, lit) == 28);
    assert!(offset_of!(Textured, palette) == 32 && offset_of!(Textured, coordinates) == 36);
    assert!(size_of::<VertexPrefix>() == 16 && align_of::<VertexPrefix>() == 4);
};

#[cfg(any(armv7m, rv32))]
impl LevelBlock {
    /// The block of `rows` over `colors` and `depths`, or `None` if the region is not inside
    /// both buffers or `C` is not a 16-bit colour (so no input makes a loop write outside them).
    #[inline(always)]
    pub(crate) fn new<C: Copy>(
        colors: &mut [C],
        depths: &mut [u16],
        rows: &LevelRows,
        table: &[C; 256],
    ) -> Option<Self> {
        if core::mem::size_of::<C>() != 2 || core::mem::align_of::<C>() != 2 {
            return None;
        }
        // The region's last pixel, in both buffers; its columns within a buffer row. In 64
        // bits: indices are 32-bit here, so the sum cannot wrap.
        let (columns, count) = (rows.columns as usize, rows.rows as usize);
        let wide = |n: usize| n as u64;
        let last = wide(rows.first)
            + wide(count.wrapping_sub(1)) * wide(rows.width)
            + wide(columns.wrapping_sub(1));
        let inside = columns >= 1
            && count >= 1
            && columns <= rows.width
            && last < wide(colors.len().min(depths.len()));
        // Strides and offsets in bytes fit 32 bits where the buffers do (a 32-bit address
        // space).
        if !inside || u32::try_from(rows.width * 2).is_err() {
            return None;
        }
        let [s, m, e] = rows.bounds;
        Some(Self {
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
        })
    }
}

/// [`level_rows`] where there is none: draws nothing and says so.
#[cfg(not(any(armv7m, rv32)))]
#[inline(always)]
pub(crate) fn level_rows<C: Copy>(
    _colors: &mut [C],
    _depths: &mut [u16],
    _rows: &LevelRows,
    _table: &[C; 256],
) -> bool {
    false
}

/// ARMv7-M: the rows of a small depth-tested face with nearest texels of a power-of-two
/// repeating texture of raw Rgb565 words into Rgb565 pixels, unlit or lit by a level plane (the
/// 3D pipeline's textured screen-space fill), are drawn by one assembly loop
/// ([`textured_rows`]); elsewhere by the portable row loop.
pub(crate) const TEXTURED_ROWS: bool = cfg!(armv7m);

/// ARMv7E-M: [`textured_rows`] and [`textured_face`] draw bilinear texels too (with the DSP
/// extension's dual 16-bit products).
pub(crate) const BILINEAR_ROWS: bool = cfg!(arm_dsp);

/// The rows of a small textured face for [`textured_rows`]: the region and its runs as
/// [`LevelRows`] has them, the planes of the depth, the texel coordinates and the light level,
/// how the coordinates' planes map to 16.16 texels, and the texture.
///
/// Pixel `column` of a row's run `start..end` (at least one pixel; the plane values `p` at
/// `start` are the row's values plus `start` column steps, wrapping) is depth-tested with
/// `z >> 16` against the stored depth (strictly nearer is drawn: depth and colour written) and
/// coloured with the texel at `x = base_u + (p_u >> down_u)` and `y = (base_v + (p_v >> down_v))
/// << y_shift` stepped by `texel_steps` a pixel (by the second pixel's own `x` and `y` less the
/// first's in a run of two), all wrapping: `texels[((y >> 16) & rows_mask) | ((x >> 16) &
/// x_mask)]`, raw, or with each 5-6-5 channel `c` scaled to `(c·f + 2¹⁵) >> 16` for the level
/// plane's `f = ((l >> 12)·257) >> 12` — the integers of the portable `SmallRows` loop with
/// the masked nearest sampler.
///
/// Public in this private module: the argument of a hidden `GouraudColor` method, which no
/// implementation outside the crate can name.
#[derive(Clone, Copy, Debug)]
// Read only where the assembly is (elsewhere the row loop declines them).
#[cfg_attr(not(armv7m), allow(dead_code))]
pub struct TexturedRows<'a> {
    /// The region, its runs and the depth plane (`level` unused).
    pub(crate) region: LevelRows,
    /// The horizontal texel coordinate's plane: value at the first pixel, step a column, step
    /// a row.
    pub(crate) u: [u32; 3],
    /// The vertical one's.
    pub(crate) v: [u32; 3],
    /// The light level's plane, if lit.
    pub(crate) level: Option<[u32; 3]>,
    /// The coordinates' planes as 16.16 texels: `(base, down)` for `u` and `v`.
    pub(crate) maps: [(i32, u32); 2],
    /// The texel coordinates' steps a pixel (16.16, `y`'s before its shift).
    pub(crate) texel_steps: (i32, i32),
    /// `y`'s shift: the bits of a texture row.
    pub(crate) y_shift: u32,
    /// The texels (row-major).
    pub(crate) texels: &'a [u16],
    /// The column mask (the width less one).
    pub(crate) x_mask: u32,
    /// The row mask in storage units: the height less one, times the width.
    pub(crate) rows_mask: u32,
    /// Bilinear rather than nearest (where [`BILINEAR_ROWS`]): the blend of
    /// `texture::map::bilinear_by` at `(x, y)` of the four texels around it, masked as above.
    pub(crate) bilinear: bool,
}

/// [`textured_rows`] where there is none: draws nothing and says so.
#[cfg(not(armv7m))]
#[inline(always)]
pub(crate) fn textured_rows<C: Copy>(
    _colors: &mut [C],
    _depths: &mut [u16],
    _rows: &TexturedRows<'_>,
) -> bool {
    false
}

/// ARMv7-M: a small face of the 3D pipeline's textured screen-space fill (nearest texels of a
/// power-of-two repeating texture of raw Rgb565 words, unlit or lit by a level plane) is set up
/// by one assembly function ([`textured_face`]: the set-up of [`level_face`] with the depth, the
/// two texel coordinates and the level as its four planes) that hands it to the row loop of
/// [`textured_rows`]; elsewhere by `raster::scan`.
pub(crate) const TEXTURED_FACE: bool = cfg!(armv7m);

/// A vertex of a [`TexturedFace`] that is not a [`ProjectedPrefix`] already (a face of the
/// general textured fill): its position (sub-pixels), depth and light level as the planes take
/// them, and its `q ∝ 1/w` as `mantissa · 2^shift`, laid out as a [`ProjectedPrefix`]'s.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct VertexPrefix {
    /// In native byte order: the position's x and y (`i32`) at 0 and 4, the depth and the level
    /// (`u16`) at 8 and 10, `q`'s mantissa (`u16`) at 12 and its shift (`u8`) at 15 (14 is not
    /// read).
    words: [u32; 4],
}

/// A vertex whose first 16 bytes [`textured_face`] and [`FaceScan`] read and [`project_positions`]
/// writes.
///
/// # Safety
///
/// An implementor is 4-byte aligned, at least 16 bytes, and its first 16 bytes are initialised
/// (no padding among them), any 16 bytes there are a value of the fields they hold (integers),
/// and they are laid out as a [`VertexPrefix`]'s: the position's x and y (sub-pixels, `i32`) at
/// bytes 0 and 4, the depth (`u16`) at 8, the light level (8.8, `u16`) at 10, `q`'s mantissa
/// (`u16`) at 12, the clip code (`u8`: the clip planes the vertex is outside in bits 0-6, bit 7
/// another flag) at 14 and `q`'s shift (`u8`) at 15.
#[allow(unsafe_code)]
pub(crate) unsafe trait ProjectedPrefix {}

// SAFETY: `repr(C)`, four `u32`s: 16 bytes, 4-byte aligned, every bit pattern a value, its
// fields where the trait says (its constructor's).
#[allow(unsafe_code)]
unsafe impl ProjectedPrefix for VertexPrefix {}

/// The word of the `u16`s `low` (at its lower address) and `high`, in native byte order.
#[inline(always)]
fn halves(low: u16, high: u16) -> u32 {
    let ([a, b], [c, d]) = (low.to_ne_bytes(), high.to_ne_bytes());
    u32::from_ne_bytes([a, b, c, d])
}

impl VertexPrefix {
    /// The vertex at `(x, y)` with `depth`, light `level` and `q` `(mantissa, shift)`.
    #[inline(always)]
    pub(crate) fn new((x, y): (i32, i32), depth: u16, level: u16, (q, q_shift): (u16, u8)) -> Self {
        let words = [
            x as u32,
            y as u32,
            halves(depth, level),
            halves(q, u16::from_ne_bytes([0, q_shift])),
        ];
        VertexPrefix { words }
    }
}

/// What [`textured_face`] did with a face.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(not(armv7m), allow(dead_code))]
pub enum TexturedDraw {
    /// Drawn, or nothing of it to draw.
    Done,
    /// Nothing drawn: the portable code's to draw.
    Declined,
    /// Nothing drawn: not within the screen-space bound, to draw perspective-correct.
    Perspective,
}

/// What the faces of a textured draw have in common for [`textured_face`] (offsets are the
/// assembly's): the rows drawn, `y`'s shift, the clip, the planes' rounding terms, the texels'
/// masks and the levels' screen-space bound. No addresses: a face's are its
/// [`TexturedFace`]'s.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
// Read only where the assembly is.
#[cfg_attr(not(armv7m), allow(dead_code))]
pub struct TexturedTemplate {
    /// 0, 4: the rows drawn, first and last (a band's); the buffers' first row is the first.
    rows: [i32; 2],
    /// 8: `y`'s shift (as [`TexturedRows`]).
    y_shift: u32,
    /// 12-24: the clip's first column and row, its last column and row (where a
    /// [`LevelFace`] has them: the set-ups share that code).
    clip: [i32; 4],
    /// 28-40: the four planes' rounding terms.
    half: [u32; 4],
    /// 44: the column mask; 48: the row mask (as [`TexturedRows`]).
    x_mask: u32,
    rows_mask: u32,
    /// 52: the screen-space bound of the levels (`texturing::affine_level`).
    affine_level: u32,
}

impl TexturedTemplate {
    /// The template of a draw inside `clip` (see [`ClipBounds`]), its planes rounded by `half`,
    /// drawn in rows `rows` (as [`LevelFace::new`]'s), its texels addressed by `(x_mask,
    /// rows_mask, y_shift)` (as [`TexturedRows`] has them), a lit face's levels within
    /// `affine_level` of the perspective-correct ones in screen space (as the texel
    /// coordinates within 1/16 texel).
    #[inline(always)]
    pub(crate) fn new(
        clip: ClipBounds,
        half: [u32; 4],
        rows: [i32; 2],
        (x_mask, rows_mask, y_shift): (u32, u32, u32),
        affine_level: u32,
    ) -> Self {
        TexturedTemplate {
            rows,
            y_shift,
            clip: clip.words(),
            half,
            x_mask,
            rows_mask,
            affine_level,
        }
    }

    /// The template inside `clip`, drawn in rows `rows` instead (as [`new`](Self::new)'s).
    #[inline(always)]
    pub(crate) fn with_clip(&self, clip: ClipBounds, rows: [i32; 2]) -> Self {
        TexturedTemplate {
            clip: clip.words(),
            rows,
            ..*self
        }
    }

    /// The face of `vertices` with the 16.16 texel coordinates `coordinates` of a draw with this
    /// template, sampled from `texels` (which its masks address), lit by the vertices' levels
    /// if `lit` (their levels are not read otherwise).
    #[inline(always)]
    pub(crate) fn face<'w, V: ProjectedPrefix>(
        &'w self,
        vertices: [&'w V; 3],
        coordinates: &'w [[i32; 2]; 3],
        texels: FaceTexels<'w>,
        lit: bool,
    ) -> TexturedFace<'w> {
        TexturedFace {
            vertices: vertices.map(|v| (v as *const V).cast::<u8>()),
            coordinates: coordinates.as_ptr(),
            ..self.faces(texels, lit)
        }
    }

    /// [`face`](Self::face) without its vertices and coordinates: the faces of a
    /// [`TexturedFaces`], whose scan sets them.
    #[inline(always)]
    pub(crate) fn faces<'w>(&'w self, texels: FaceTexels<'w>, lit: bool) -> TexturedFace<'w> {
        TexturedFace {
            vertices: [core::ptr::null(); 3],
            depths: core::ptr::null_mut(),
            color_offset: 0,
            stride: 0,
            texels: texels.texels,
            lit: if lit { 2 } else { 0 } | texels.kind,
            palette: texels.palette,
            coordinates: core::ptr::null(),
            texels_len: texels.count,
            template: self,
            borrowed: core::marker::PhantomData,
        }
    }
}

/// A draw's [`TexturedTemplate`] as its frame keeps it: the template where the target has the
/// set-up ([`TEXTURED_FACE`]); elsewhere a type without values, so that `Option<TemplateSlot>`
/// takes no room.
#[cfg(armv7m)]
pub(crate) type TemplateSlot = TexturedTemplate;
/// A draw's [`TexturedTemplate`] as its frame keeps it: none here (no set-up).
#[cfg(not(armv7m))]
pub(crate) type TemplateSlot = core::convert::Infallible;

/// `template` in a slot, where the target keeps one.
#[inline(always)]
pub(crate) fn template_slot(template: TexturedTemplate) -> Option<TemplateSlot> {
    #[cfg(armv7m)]
    {
        Some(template)
    }
    #[cfg(not(armv7m))]
    {
        let _ = template;
        None
    }
}

/// The template in `slot`.
#[inline(always)]
pub(crate) fn slot_template(slot: &TemplateSlot) -> &TexturedTemplate {
    #[cfg(armv7m)]
    {
        slot
    }
    #[cfg(not(armv7m))]
    {
        match *slot {}
    }
}

/// A face for [`textured_face`] (offsets are the assembly's): its vertices, the buffers, its
/// texels and light, and its draw's [`TexturedTemplate`].
#[repr(C)]
// Read only where the assembly is.
#[cfg_attr(not(armv7m), allow(dead_code))]
pub struct TexturedFace<'w> {
    /// 0, 4, 8: the vertices ([`ProjectedPrefix`]es: their first 16 bytes are read).
    vertices: [*const u8; 3],
    /// 12: the depth buffer; 16: the colour buffer's offset from it in bytes (wrapping); 20: a
    /// buffer row in bytes ([`textured_face`] sets them).
    depths: *mut u16,
    color_offset: u32,
    stride: u32,
    /// 24: the texels (as [`TexturedRows`]).
    texels: *const u16,
    /// 28: the row loop's variant bits beside the middle bound's: 2 if lit by the level plane,
    /// 4 if bilinear, 8 if 4-bit palette indices; 32: the palette's 16 raw Rgb565 words
    /// (palette indices).
    lit: u32,
    palette: *const u16,
    /// 36: the vertices' texel coordinates (16.16), three pairs.
    coordinates: *const [i32; 2],
    /// The texels' count and the template (not the assembly's).
    texels_len: usize,
    template: &'w TexturedTemplate,
    borrowed: core::marker::PhantomData<&'w [u16]>,
}

/// The textured faces of a draw for a [`FaceScan`] ([`textured_faces`]): the [`TexturedFace`]
/// the set-up reads, whose vertices and texel coordinates the scan sets for each face, and
/// what those come from — the mesh's texture coordinates and the texture's size: `u·width`
/// and `(1 − v)·height` (16.16), as the pipeline scales them (offsets are the assembly's).
///
/// Public in this private module: the argument of a hidden `GouraudColor` method.
#[repr(C)]
// Read only where the assembly is.
#[cfg_attr(not(armv7m), allow(dead_code))]
pub struct TexturedFaces<'w> {
    /// 0: the face (its vertices and coordinates the scan's; 44: its template).
    face: TexturedFace<'w>,
    /// 48: the mesh's texture coordinates (raw `I16F16` pairs); 52: how many.
    uvs: *const [i32; 2],
    uvs_len: u32,
    /// 56, 60: the texture's width and height.
    size: [i32; 2],
    /// 64: whether the faces are lit (a face needs a normal at each vertex).
    lit: u32,
    /// 68: the face's texel coordinates (the scan's).
    coordinates: [[i32; 2]; 3],
}

#[cfg(all(armv7m, target_pointer_width = "32"))]
const _: () = {
    use core::mem::offset_of;
    assert!(offset_of!(TexturedFace<'_>, coordinates) == 36);
    assert!(offset_of!(TexturedFace<'_>, template) == 44);
    assert!(offset_of!(TexturedFaces<'_>, uvs) == 48 && offset_of!(TexturedFaces<'_>, size) == 56);
    assert!(offset_of!(TexturedFaces<'_>, lit) == 64);
    assert!(offset_of!(TexturedFaces<'_>, coordinates) == 68);
};

impl<'w> TexturedFaces<'w> {
    /// The faces of `face` (a template's, without vertices) with the texture coordinates `uvs`
    /// of a texture `size` texels across, lit if `lit`. `None` for a side past 2¹⁵ texels.
    #[inline(always)]
    pub(crate) fn new<U: CoordinatePair>(
        face: TexturedFace<'w>,
        uvs: &'w [U],
        size: (u32, u32),
        lit: bool,
    ) -> Option<Self> {
        const { assert!(core::mem::size_of::<U>() == 8 && core::mem::align_of::<U>() == 4) };
        if size.0 > 1 << 15 || size.1 > 1 << 15 {
            return None;
        }
        Some(TexturedFaces {
            face,
            uvs: uvs.as_ptr().cast(),
            uvs_len: u32::try_from(uvs.len()).unwrap_or(u32::MAX),
            size: [size.0 as i32, size.1 as i32],
            lit: u32::from(lit),
            coordinates: [[0; 2]; 3],
        })
    }
}

/// [`textured_faces`] where there is no set-up: none.
#[cfg(not(armv7m))]
#[inline(always)]
pub(crate) fn textured_faces<'w, C: Copy>(
    _buffers: (&mut [C], &mut [u16], usize),
    _faces: TexturedFaces<'w>,
) -> Option<TexturedFaces<'w>> {
    None
}

/// The texels of a [`TexturedFace`], each kind addressed by the same masks (`row | column`):
/// raw Rgb565 words read nearest or bilinear, or 4-bit palette indices with the raw words of
/// their 16 colours (their fields as the face has them).
#[derive(Clone, Copy, Debug)]
#[cfg_attr(not(armv7m), allow(dead_code))]
pub(crate) struct FaceTexels<'v> {
    /// The storage's address (words, or the indices' bytes).
    texels: *const u16,
    /// The texels it holds.
    count: usize,
    /// The row loop's variant bit: 0 nearest, 4 bilinear, 8 palette indices.
    kind: u32,
    /// The palette's 16 raw words (null unless palette indices).
    palette: *const u16,
    borrowed: core::marker::PhantomData<&'v [u16]>,
}

#[cfg_attr(not(armv7m), allow(dead_code))]
impl<'v> FaceTexels<'v> {
    /// Raw Rgb565 `words`, bilinear (where [`BILINEAR_ROWS`]) or nearest.
    #[inline(always)]
    pub(crate) fn words(words: &'v [u16], bilinear: bool) -> Self {
        FaceTexels {
            texels: words.as_ptr(),
            count: words.len(),
            kind: if bilinear { 4 } else { 0 },
            palette: core::ptr::null(),
            borrowed: core::marker::PhantomData,
        }
    }

    /// 4-bit palette `indices`, two a byte (the even texel in the high nibble), nearest, naming
    /// the colours whose raw Rgb565 words `palette` holds.
    #[inline(always)]
    pub(crate) fn palette4(indices: &'v [u8], palette: &'v [u16; 16]) -> Self {
        FaceTexels {
            // The indices' address as the texels' (the loop reads them by bytes).
            texels: indices.as_ptr().cast::<u16>(),
            count: indices.len().saturating_mul(2),
            kind: 8,
            palette: palette.as_ptr(),
            borrowed: core::marker::PhantomData,
        }
    }
}

/// [`textured_face`] where there is none: draws nothing and says so.
#[cfg(not(armv7m))]
#[inline(always)]
pub(crate) fn textured_face<C: Copy>(
    _buffers: (&mut [C], &mut [u16], usize),
    _face: TexturedFace<'_>,
) -> TexturedDraw {
    TexturedDraw::Declined
}

/// ARMv7-M: the vertex stage of a draw whose positions are all inside the view volume — the
/// transform, the perspective divide and the viewport mapping — is one assembly loop
/// ([`project_positions`]); elsewhere `three_d`'s portable loop.
pub(crate) const PROJECT_POSITIONS: bool = cfg!(armv7m);

/// A texture coordinate that a [`FaceScan`]'s textured faces read where it is.
///
/// # Safety
///
/// An implementor is 8 bytes, 4-byte aligned, every byte a field's: the raw `u` and `v`
/// (`I16F16` bits, `i32`) at bytes 0 and 4.
#[allow(unsafe_code)]
pub(crate) unsafe trait CoordinatePair {}

/// A model-space position that [`project_positions`] reads where it is.
///
/// # Safety
///
/// An implementor is 12 bytes, 4-byte aligned, every byte a field's: the raw `x`, `y` and `z`
/// (`I16F16` bits, `i32`) at bytes 0, 4 and 8.
#[allow(unsafe_code)]
pub(crate) unsafe trait ModelPosition {}

/// What the vertices of a draw have in common for [`project_positions`] (offsets are the
/// assembly's): `three_d`'s `VertexStage` with its transform rows' rounding folded in.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct ProjectionBlock {
    /// 0-80, 20 bytes a row of clip-space `x`, `y`, `z` and `w`: the row's first three
    /// entries (raw), then its translation `t` as the 64-bit `t·2¹⁶ + 2¹⁵` (low word first).
    rows: [[i32; 5]; 4],
    /// 80, 84: the viewport's centre (sub-pixels).
    centre: [i32; 2],
    /// 88, 92: the half sizes times 2ᵉ.
    half: [u32; 2],
    /// 96: `e`.
    exponent: u32,
    /// 100, 104: `2^(31 + e)`, low word first.
    round: [u32; 2],
    /// 108: the mask of the vertices' word at 12 (`q`'s mantissa and shift): all ones for a
    /// textured draw, none for others (their level and shift 0).
    q_mask: u32,
}

impl ProjectionBlock {
    /// The block of the raw model-view-projection matrix `mvp`, the viewport's `centre`, its
    /// half sizes times 2ᵉ `half`, `exponent` `e` and the offsets' rounding `round`
    /// (`2^(31 + e)`), keeping `q` if `textured`.
    pub(crate) fn new(
        mvp: &[[i32; 4]; 4],
        (centre, half, exponent, round): ((i32, i32), (u32, u32), u32, i64),
        textured: bool,
    ) -> Self {
        let rows = mvp.map(|[a, b, c, t]| {
            let bias = (i64::from(t) << 16) + (1 << 15);
            [a, b, c, bias as i32, (bias >> 32) as i32]
        });
        ProjectionBlock {
            rows,
            centre: [centre.0, centre.1],
            half: [half.0, half.1],
            exponent,
            round: [round as u32, (round >> 32) as u32],
            q_mask: if textured { u32::MAX } else { 0 },
        }
    }
}

/// ARMv7-M: the face stage's first look at each face of a mesh drawn from its vertex scratch —
/// indices in range, clip codes, the doubled area's sign and zero, the culled side — is one
/// assembly loop ([`FaceScan::next_batch`]) that hands on only the faces left to clip or fill;
/// elsewhere the pipeline's own loop decides each face.
pub(crate) const FACE_SCAN: bool = cfg!(armv7m);

/// The faces a [`FaceScan::next_batch`] hands on at most.
pub(crate) const FACE_BATCH: usize = 16;

/// A face entry of [`FaceScan::next_batch`]: the face's number times 4 plus its kind, this one
/// (every vertex inside the view volume, of non-zero area, facing the kept side: to fill).
#[cfg_attr(not(armv7m), allow(dead_code))]
pub(crate) const SCANNED_KEPT: u32 = 0;

/// A face entry's kind: a vertex outside a clip plane and not all of them outside the same one
/// (to clip).
pub(crate) const SCANNED_CLIPPED: u32 = 1;

/// A face entry's kind: the textured set-up found the face not within its screen-space bound
/// (`TexturedDraw::Perspective`: to draw perspective-correct).
#[cfg_attr(not(armv7m), allow(dead_code))]
pub(crate) const SCANNED_PERSPECTIVE: u32 = 3;

/// A face entry's kind: an index past the scratch.
#[cfg_attr(not(armv7m), allow(dead_code))]
pub(crate) const SCANNED_INVALID: u32 = 2;

/// The face scan of a mesh's faces over its vertex scratch ([`FACE_SCAN`]): for each face in
/// order, what the pipeline's verdict decides from the projected vertices alone (for a draw of
/// every row, faces of one side culled) — dropped and counted (all vertices outside one clip
/// plane: rejected; no area: degenerate; the other side: culled, the faces left over), or
/// handed on as an entry ([`SCANNED_KEPT`], [`SCANNED_CLIPPED`], [`SCANNED_INVALID`]).
///
/// The doubled area is the verdict's: `(x₁ − x₀)(y₂ − y₀) − (x₂ − x₀)(y₁ − y₀)` from wrapping
/// 32-bit differences, 64-bit products, wrapping.
#[derive(Debug)]
#[repr(C)]
// Read only where the assembly is (elsewhere `new` gives none).
#[cfg_attr(not(armv7m), allow(dead_code))]
pub(crate) struct FaceScan<'a> {
    /// 0: the next face's indices; 4: past the last face's.
    next: *const [u16; 3],
    end: *const [u16; 3],
    /// 8: the scratch's first vertex (16 bytes each, a [`ProjectedPrefix`]); 12: its vertices.
    scratch: *const u8,
    vertices: u32,
    /// 16: the next face's number times 4.
    number: u32,
    /// 20: the sign bit clear to keep the faces of negative doubled area, set for those of
    /// positive area (the other bits likewise); bit 0 set while `level` is not null.
    flip: u32,
    /// 24, 28: the faces rejected and degenerate so far.
    rejected: u32,
    degenerate: u32,
    /// 32: during a batch, the level faces its kept faces are drawn as ([`level_faces`]), or
    /// null; 36: the faces drawn so (or as textured faces); 40: during a batch, the textured
    /// faces its kept faces are drawn as ([`textured_faces`]), or null.
    level: *mut LevelFace<'static>,
    drawn: u32,
    textured: *mut TexturedFaces<'static>,
    borrows: core::marker::PhantomData<&'a [[u16; 3]]>,
}

impl<'a> FaceScan<'a> {
    /// The scan of `faces` over the vertices `scratch`, keeping the faces of negative doubled
    /// area (`keep_negative`, the pipeline's front faces) or of positive area. `None` where
    /// there is no scan, or for more than 2³⁰ faces.
    pub(crate) fn new<V: ProjectedPrefix>(
        faces: &'a [[u16; 3]],
        scratch: &'a [V],
        keep_negative: bool,
    ) -> Option<Self> {
        const { assert!(core::mem::size_of::<V>() == 16) };
        if !FACE_SCAN || faces.len() > 1 << 30 {
            return None;
        }
        let range = faces.as_ptr_range();
        Some(FaceScan {
            next: range.start,
            end: range.end,
            scratch: scratch.as_ptr().cast(),
            vertices: u32::try_from(scratch.len()).unwrap_or(u32::MAX),
            number: 0,
            flip: if keep_negative { 0 } else { u32::MAX },
            rejected: 0,
            degenerate: 0,
            level: core::ptr::null_mut(),
            drawn: 0,
            textured: core::ptr::null_mut(),
            borrows: core::marker::PhantomData,
        })
    }

    /// The next faces handed on (none once every face is scanned), into `out`. With `level`
    /// (the draw's [`level_faces`], its buffers borrowed for the call), a kept face whose
    /// vertices all have a normal (bit 7 of their codes clear) is drawn there by [`level_face`]
    /// and counted instead, unless the set-up declines it. With `textured` (the draw's
    /// [`textured_faces`], likewise; not with `level`), a kept face is drawn by
    /// [`textured_face`] and counted, unless it declines it (handed on) or finds it not within
    /// its bound (handed on as [`SCANNED_PERSPECTIVE`]); a face not lit as the draw asks (a
    /// vertex without a normal in a lit draw), with an index past the texture coordinates or
    /// a texel coordinate past `i32` is handed on untried. Every face handed on ends the
    /// batch where there are level or textured faces: the faces are drawn in order.
    #[inline(always)]
    pub(crate) fn next_batch<'o>(
        &mut self,
        out: &'o mut [u32; FACE_BATCH],
        level: Option<&mut LevelFace<'static>>,
        textured: Option<&mut TexturedFaces<'_>>,
    ) -> &'o [u32] {
        self.level = level.map_or(core::ptr::null_mut(), |face| face);
        self.textured = match textured {
            Some(faces) if self.level.is_null() => {
                faces.face.coordinates = faces.coordinates.as_ptr();
                (faces as *mut TexturedFaces<'_>).cast()
            }
            _ => core::ptr::null_mut(),
        };
        let bits = u32::from(!self.level.is_null()) | u32::from(!self.textured.is_null()) << 1;
        self.flip = (self.flip & !3) | bits;
        #[cfg(armv7m)]
        let count = thumbv7m::scan_faces(self, out);
        #[cfg(not(armv7m))]
        let count = 0;
        self.level = core::ptr::null_mut();
        self.textured = core::ptr::null_mut();
        &out[..count.min(FACE_BATCH)]
    }

    /// The faces rejected and degenerate among those scanned, and those drawn by
    /// [`level_face`].
    pub(crate) fn counts(&self) -> (u32, u32, u32) {
        (self.rejected, self.degenerate, self.drawn)
    }
}

/// A draw's light for [`light_levels`] (offsets are the assembly's): `three_d`'s `VertexLight`
/// for normals already in the light's space and of unit length.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
// Read only where the assembly is.
#[cfg_attr(not(armv7m), allow(dead_code))]
pub(crate) struct LevelLight {
    /// 0-8: the direction's raw components (14 fractional bits, within ±2¹⁴).
    direction: [i32; 3],
    /// 12: the ambient level (16 fractional bits, at most 2¹⁶); 16: 2¹⁶ less it.
    ambient: u32,
    diffuse: u32,
}

impl LevelLight {
    /// The light of `direction` and `ambient`, if they are in those ranges.
    #[inline(always)]
    pub(crate) fn new(direction: [i32; 3], ambient: u32) -> Option<Self> {
        let fits = direction.iter().all(|d| d.unsigned_abs() <= 1 << 14) && ambient <= 1 << 16;
        fits.then(|| LevelLight {
            direction,
            ambient,
            diffuse: (1 << 16) - ambient,
        })
    }
}

/// Which `u16` of a [`ProjectedPrefix`] vertex [`light_levels`] writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LevelField {
    /// The level at byte 12 (a Gouraud draw's).
    Level,
    /// The texel level at byte 10 (a textured draw's).
    TexelLevel,
}

/// ARMv7-M: writes into each vertex of `out` (its `field`) the light level of the normal of
/// `normals` at its index (as many as both have): `three_d`'s `VertexLight::level_of_unit`
/// from the same integers — `d = n·l + 2¹³` in 64 bits, `min(d, 2³⁰ − 1) >> 14` or 0 where
/// negative, the level `a + (((2¹⁶ − a)·d + 2¹⁵) >> 16)` (never past 2¹⁶ for `a ≤ 2¹⁶`, so
/// the portable clamp there changes nothing) times 255 over 256. `false`, nothing written,
/// elsewhere.
#[allow(unsafe_code)]
#[inline(always)]
pub(crate) fn light_levels<N: ModelPosition, V: ProjectedPrefix>(
    normals: &[N],
    out: &mut [V],
    field: LevelField,
    light: &LevelLight,
) -> bool {
    const {
        assert!(core::mem::size_of::<N>() == 12 && core::mem::align_of::<N>() >= 4);
        assert!(core::mem::size_of::<V>() == 16 && core::mem::align_of::<V>() >= 4);
    };
    if !cfg!(armv7m) {
        return false;
    }
    let count = normals.len().min(out.len());
    if count == 0 {
        return true;
    }
    let offset = match field {
        LevelField::Level => 12,
        LevelField::TexelLevel => 10,
    };
    // SAFETY: `count` normals of 12 bytes from `normals`'s start are inside it (`N` is 12
    // bytes, asserted above, 4-byte aligned), and the `u16` at `offset` (10 or 12, 2-byte
    // aligned) of each of the first `count` 16-byte vertices of `out` is inside it, any value
    // a valid one there (`ProjectedPrefix`'s contract); the light's ambient level is at most 2¹⁶
    // (`LevelLight::new`).
    #[cfg(armv7m)]
    unsafe {
        thumbv7m::light_levels(
            normals.as_ptr().cast(),
            out.as_mut_ptr().cast::<u8>().add(offset),
            count as u32,
            light,
        )
    };
    let _ = (offset, light);
    true
}

/// [`project_positions`] where there is none: writes nothing and says so.
#[cfg(not(armv7m))]
#[inline(always)]
pub(crate) fn project_positions<P: ModelPosition, V: ProjectedPrefix>(
    _block: &ProjectionBlock,
    _positions: &[P],
    _out: &mut [V],
) -> bool {
    false
}

/// ARMv7-M: a depth-tested span of the perspective-correct textured fill with nearest texels of
/// a power-of-two repeating texture of raw Rgb565 words into Rgb565 pixels, unlit or lit by a
/// perspective-correct level, chunks and pixels, is drawn by one assembly function
/// ([`perspective_span`]); elsewhere by the portable span loop.
pub(crate) const PERSPECTIVE_SPAN: bool = cfg!(armv7m);

/// One span of the perspective-correct textured fill for [`perspective_span`]: the integers of
/// the portable loop (`three_d::texturing`'s `PerspectiveSpan` with the masked nearest sampler).
///
/// The span is cut into chunks as `raster::perspective::chunk_shift` gives their lengths from
/// `chunk_room` (powers of two up to 16 pixels; the last one shorter). At a chunk's ends the
/// perspective barycentrics `(λ₁, λ₂)` come from the three planes' values there as
/// `raster::perspective::lambdas` finds them, and each attribute `(base, d₁, d₂)` is `base +
/// ⌊λ₁·d₁ / 2¹⁶⌋ + ⌊λ₂·d₂ / 2¹⁶⌋` (wrapping); between them the attributes step by
/// `raster::perspective::step_over`'s steps. A pixel is depth-tested with `z >> 16` against the
/// stored depth (strictly nearer is drawn: depth and colour written) and coloured with the texel
/// `texels[((y << y_shift >> 16) & rows_mask) | ((x >> 16) & x_mask)]`, raw, or with each 5-6-5
/// channel `c` scaled to `(c·f + 2¹⁵) >> 16` for the level `f` clamped to `0..=2¹⁶`.
///
/// Public in this private module: the argument of a hidden `GouraudColor` method, which no
/// implementation outside the crate can name.
#[derive(Clone, Copy, Debug)]
// Read only where the assembly is (elsewhere the span loop declines them).
#[cfg_attr(not(armv7m), allow(dead_code))]
pub struct PerspectiveSpan565<'a> {
    /// The depth plane's value at the first pixel and its step a pixel.
    pub(crate) depth: (u32, u32),
    /// The perspective planes' (`q`, `b₁·q`, `b₂·q`) values at the first pixel.
    pub(crate) planes: [u32; 3],
    /// Their steps a pixel.
    pub(crate) steps: [u32; 3],
    /// The texel coordinates (16.16) as `(base, d₁, d₂)`.
    pub(crate) u: [i32; 3],
    /// `v`, likewise.
    pub(crate) v: [i32; 3],
    /// The level (a 16-bit fraction) as `(base, d₁, d₂)`, if lit.
    pub(crate) level: Option<[i32; 3]>,
    /// The texels (row-major).
    pub(crate) texels: &'a [u16],
    /// The column mask (the width less one).
    pub(crate) x_mask: u32,
    /// The row mask in storage units: the height less one, times the width.
    pub(crate) rows_mask: u32,
    /// `y`'s shift: the bits of a texture row.
    pub(crate) y_shift: u32,
    /// The span's `raster::perspective::chunk_room`: each chunk's length from it.
    pub(crate) chunk_room: i32,
    /// Bilinear rather than nearest (where [`BILINEAR_ROWS`]): `texture::map::bilinear_by`'s
    /// blend of the four texels around the point, masked as the nearest one's.
    pub(crate) bilinear: bool,
}

/// [`perspective_span`] where there is none: draws nothing and says so.
#[cfg(not(armv7m))]
#[inline(always)]
pub(crate) fn perspective_span<C: Copy>(
    _colors: &mut [C],
    _depths: &mut [u16],
    _span: &PerspectiveSpan565<'_>,
) -> bool {
    false
}

/// Sets every entry of `entries` to `value`, the 4-byte-aligned middle a word (two entries) at
/// a time. A 16-bit buffer is only known to be 2-byte aligned where it is cleared, and LLVM
/// turns a fill at that alignment into the byte-granular `memset` call, on Cortex-M four times
/// the instructions of the word-aligned one it picks here (on RV32, whose library `memset` stores
/// a word a pass of three instructions, an unrolled loop of eight; on ARMv7-M two `stm`s of four
/// words a pass).
#[allow(unsafe_code)]
pub(crate) fn fill_u16(entries: &mut [u16], value: u16) {
    // SAFETY: any two `u16`s are a valid `u32` and any `u32` is two valid `u16`s; `align_to_mut`
    // gives the middle only what is aligned and in bounds.
    let (head, middle, tail) = unsafe { entries.align_to_mut::<u32>() };
    head.fill(value);
    let word = u32::from(value) * 0x0001_0001;
    fill_words(middle, word);
    tail.fill(value);
}

/// Sets the pixels of `pixels` after its first two to those two (the same colour), where `C` is
/// a 16-bit colour and the target has a loop of eight words a pass (RV32, ARMv7-M): `pixels`
/// starts at a 4-byte boundary and is a whole number of sixteen pixels long, at least sixteen.
/// `false`, with nothing written, elsewhere.
#[allow(unsafe_code)]
#[inline(always)]
pub(crate) fn repeat_first_pair<C: Copy>(pixels: &mut [C]) -> bool {
    let fits = core::mem::size_of::<C>() == 2
        && core::mem::align_of::<C>() == 2
        && pixels.as_ptr() as usize % 4 == 0
        && !pixels.is_empty()
        && pixels.len() % 16 == 0;
    if !cfg!(any(rv32, armv7m)) || !fits {
        return false;
    }
    let range = pixels.as_mut_ptr_range();
    let (start, end) = (range.start.cast::<u32>(), range.end.cast::<u32>());
    // SAFETY: `pixels` is writable, its first pixel 4-byte aligned and its 2-byte pixels a
    // multiple of sixteen (checked above): a range of 4-byte aligned words, a multiple of eight
    // of them and at least eight; each word is written with the bytes of the first, two
    // pixels, so each pixel gets the bytes of a pixel.
    #[cfg(rv32)]
    unsafe {
        riscv32::repeat_first_word(start, end)
    };
    #[cfg(armv7m)]
    unsafe {
        thumbv7m::repeat_first_word(start, end)
    };
    let _ = (start, end);
    true
}

/// Sets every word of `words` to `value`: where the target has a loop of eight words a pass of
/// its own (RV32, ARMv7-M: `fill_eights`), the whole eights by it, then the rest.
#[allow(unsafe_code)]
#[inline(always)]
fn fill_words(words: &mut [u32], value: u32) {
    #[cfg(any(rv32, armv7m))]
    let words = {
        let whole = words.len() & !7;
        let (eights, rest) = words.split_at_mut(whole);
        if !eights.is_empty() {
            let range = eights.as_mut_ptr_range();
            // SAFETY: `eights` is writable, its words 4-byte aligned, a multiple of eight of
            // them and at least eight.
            #[cfg(rv32)]
            unsafe {
                riscv32::fill_eights(range.start, range.end, value)
            };
            #[cfg(armv7m)]
            unsafe {
                thumbv7m::fill_eights(range.start, range.end, value)
            };
        }
        rest
    };
    words.fill(value);
}
