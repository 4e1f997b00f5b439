//! Small triangles scanned: the size class under [`SMALL`] pixels, set up in 32-bit products
//! and drawn a row at a time by testing each pixel's edge values — no division an edge.
//!
//! A triangle of a few pixels has rows of one to four pixels, and the walk's set-up (two
//! divisions an edge, the edges sorted by height, the switch at the middle vertex) and the
//! compact planes' 64-bit gradients cost more than its pixels. Under 16 pixels across, every
//! edge coefficient and every edge value in the box fits far inside an `i32`, so the set-up is
//! a handful of 32-bit products: the doubled area, the three reduced edge values `K` at the
//! first pixel (inside iff `K ≥ 0`, the fill rule of [`owns_centres_on`] in the bias), stepped
//! by `a` per column and `b` per row — the integers the walk's boundaries derive from, so the
//! same pixels — and the attribute planes from one reciprocal of the area ([`small_planes`]).
//! Each row is scanned from the region's first column to the end of its run (a triangle is
//! convex: one run a row).
//!
//! The planes are within the compact planes' error bound but are not their integers, so
//! shaders opt in ([`SpanShader::scans_small`]): the 3D pipeline's depth-tested fills, whose
//! triangles are mostly this small and which scan them on every path. The 2D fills, whose
//! other paths walk, scan on cores with a divider with the compact walk's planes instead
//! ([`SpanShader::walk_planes`]: `Planes::compact` of the set-up the walk would make, the
//! same integers). Firmware drawing only 2D triangles on Cortex-M0 does not link it.

use embedded_graphics::primitives::Rectangle;

use core::num::NonZeroU32;

use super::arith::{leading_zeros_32, mul_i32_wide, reciprocal_63};
use super::compact::CompactSetup;
use super::plane::{Attributes, Planes};
use super::runs::SMALL;
use super::runs::{run_by_scan, Edge, ReciprocalRuns, RowBound, RowRuns, SmallScan};
use super::sink::SpanShader;
use super::walk::{bounds, Band, Region, Span};
use crate::arch::{SmallSetup, HAS_DIVIDER, MCU};
use crate::fixed_point::{Coord, HALF_PIXEL, SUBPIXEL_BITS};
use core::num::NonZeroU64;

// The Thumb-2 set-up of a small lit face (`arch::thumbv7m`'s `level_face`) has these in its
// instructions: the box's limit (4096 sub-pixels), the half pixel (0x80) and the sub-pixel bits
// (8), the planes' shift (`s = 38 − t` for 24 fractional bits) and the steps' limit (2¹⁴ LSB).
const _: () = assert!(SMALL << SUBPIXEL_BITS == 4096 && HALF_PIXEL == 0x80 && SUBPIXEL_BITS == 8);
const _: () = assert!(super::plane::STEP_BITS == 24);

/// A small triangle set up over a clip rectangle: its pixel region, edges and planes.
struct SmallTriangle<const N: usize> {
    /// Pixels of the scan: columns `x0 ..= x0 + last`, rows `y0 ..= y0 + rows`.
    x0: i32,
    y0: i32,
    last: u32,
    rows: u32,
    edges: [Edge; 3],
    planes: Planes<N>,
}

/// Why a triangle is not drawn here.
enum NotSmall {
    /// Nothing of it is inside the clip, or its vertices are collinear: nothing to draw at all.
    Empty,
    /// Too large, or a sliver whose planes need the compact set-up.
    Other,
}

impl<const N: usize> SmallTriangle<N> {
    /// The triangle `v` with `attributes` over `clip`, if it is small (its vertices within
    /// [`SMALL`] pixels of each other on both axes, less a sub-pixel) and, for its own planes,
    /// not a sliver; with the compact walk's planes where `walk_planes` (any small triangle).
    #[inline(always)]
    fn new(
        v: [(Coord, Coord); 3],
        attributes: &Attributes<N>,
        clip: &Rectangle,
        walk_planes: bool,
    ) -> Result<Self, NotSmall> {
        let p = v.map(|(x, y)| (x.to_bits(), y.to_bits()));
        let [p0, p1, p2] = p;
        let bounds = bounds(p);
        let [min_x, min_y, max_x, max_y] = bounds;
        // The wrapping differences are the true ones (below 2³²).
        let limit = SMALL << SUBPIXEL_BITS;
        let (width, height) = (
            max_x.wrapping_sub(min_x) as u32,
            max_y.wrapping_sub(min_y) as u32,
        );
        if width >= limit || height >= limit {
            return Err(NotSmall::Other);
        }
        // Relative to vertex 0: below 2¹², so the doubled area is below 2²⁵.
        let rel = |p: (i32, i32)| (p.0.wrapping_sub(p0.0), p.1.wrapping_sub(p0.1));
        let (q1, q2) = (rel(p1), rel(p2));
        let area2 = q1.0 * q2.1 - q1.1 * q2.0;
        if area2 == 0 {
            return Err(NotSmall::Empty);
        }
        // Positive orientation: oriented vertices 1 and 2 swapped for a negative area.
        let swap = area2 < 0;
        let (o1, o2) = if swap { (q2, q1) } else { (q1, q2) };

        let Some(Region { x0, x1, y0, y1 }) = Region::within(bounds, clip) else {
            return Err(NotSmall::Empty);
        };
        // The first pixel centre relative to vertex 0: inside the box.
        let centre = |i: i32, v: i32| {
            (i << SUBPIXEL_BITS)
                .wrapping_add(HALF_PIXEL as i32)
                .wrapping_sub(v)
        };
        let first = (centre(x0, p0.0), centre(y0, p0.1));
        // Edges opposite oriented vertices 0, 1, 2; the last two's values at the first pixel
        // are the barycentrics of vertices 1 and 2 times the doubled area.
        let (e0, _) = Edge::new(o1, o2, first);
        let (e1, l1) = Edge::new(o2, (0, 0), first);
        let (e2, l2) = Edge::new((0, 0), o1, first);
        let planes = if walk_planes {
            // The compact walk's set-up of the same triangle over the same clip: its vertex 0,
            // orientation, edges and first pixel are these (the area is not zero: returned above).
            let setup = CompactSetup::new(
                if swap { [0, 2, 1] } else { [0, 1, 2] },
                ([e1.a, e2.a], [e1.b, e2.b]),
                NonZeroU64::MIN.saturating_add(u64::from(area2.unsigned_abs()) - 1),
                first,
                (width, height),
            );
            Planes::compact(&setup, attributes)
        } else {
            small_planes(attributes, swap, area2.unsigned_abs(), (e1, l1), (e2, l2))
                .ok_or(NotSmall::Other)?
        };
        Ok(SmallTriangle {
            x0,
            y0,
            last: (x1 - x0) as u32,
            rows: (y1 - y0) as u32,
            edges: [e0, e1, e2],
            planes,
        })
    }

    /// Hands `shader` the covered span of each row with the planes' values at its first pixel
    /// (or all rows at once, if it takes them: [`SpanShader::small_rows`]).
    #[inline(always)]
    fn draw<S: SpanShader<N>>(&self, shader: &mut S) {
        self.draw_runs(RowRuns::new(&self.edges, self.last + 1), shader);
    }

    /// [`draw`](Self::draw) with the runs of its first row (the edges' with a divider; the
    /// edges themselves are scanned without one).
    #[inline(always)]
    fn draw_runs<S: SpanShader<N>>(&self, mut runs: RowRuns, shader: &mut S) {
        let planes = &self.planes;
        let last = self.last;
        if HAS_DIVIDER {
            let scan = SmallScan {
                x0: self.x0,
                y0: self.y0,
                rows: self.rows + 1,
                runs,
                planes,
            };
            if shader.small_rows(&scan) {
                return;
            }
        }
        let (dx, dy) = (planes.step(), planes.row_step());
        let steps = shader.prepare(dx);
        let [e0, e1, e2] = self.edges;
        let (mut k0, mut k1, mut k2) = (e0.k, e1.k, e2.k);
        // The attributes at the row's first column, stepped row by row (wrapping, like
        // `Planes::at`).
        let mut row_values = planes.first();
        let mut y = self.y0;
        let mut reciprocal_runs = ReciprocalRuns::new(&runs);
        for _ in 0..self.rows + 1 {
            let (start, column) = if HAS_DIVIDER && !MCU {
                let run = reciprocal_runs.run();
                reciprocal_runs.advance();
                run
            } else if HAS_DIVIDER {
                let run = runs.run();
                runs.advance();
                run
            } else {
                let run = run_by_scan([(k0, e0.a), (k1, e1.a), (k2, e2.a)], last);
                (k0, k1, k2) = (k0 + e0.b, k1 + e1.b, k2 + e2.b);
                run
            };
            if column > start {
                let span = Span {
                    y,
                    x_start: self.x0 + start as i32,
                    x_end: self.x0 + column as i32,
                };
                let mut values = row_values;
                for k in 0..N {
                    values[k] = values[k].wrapping_add(dx[k].wrapping_mul(start));
                }
                shader.span(&steps, span, values);
                if shader.stopped() {
                    return;
                }
            }
            for k in 0..N {
                row_values[k] = row_values[k].wrapping_add(dy[k]);
            }
            // Past the last row only after it (which may be i32::MAX).
            y = y.wrapping_add(1);
        }
    }
}

/// Draws the triangle `v` with `attributes` inside `clip` through `shader` if it is small and
/// not a sliver (see [`SmallTriangle::new`]): `true` if it is done (drawn, or nothing to draw),
/// `false` with nothing drawn otherwise.
#[inline(always)]
pub(crate) fn shade<const N: usize, S: SpanShader<N>>(
    v: [(Coord, Coord); 3],
    attributes: &Attributes<N>,
    clip: &Rectangle,
    shader: &mut S,
) -> bool {
    match SmallTriangle::new(v, attributes, clip, shader.walk_planes()) {
        Ok(triangle) => {
            triangle.draw(shader);
            true
        }
        Err(NotSmall::Empty) => true,
        Err(NotSmall::Other) => false,
    }
}

/// [`shade`] for the rows of `band` only (see `band.rs`): the triangle is set up
/// over `clip` as `shade` sets it up, then its scan starts at the band's first row — the edge
/// values and the planes stepped there by whole rows, the integers the scan reaches — and
/// stops after the band's last. `None` if the triangle is not drawn here (not small), else
/// whether its set-up went into `keep` (if given, and it fits: `N ≤ 2`), for [`resume_rows`]
/// to draw other bands' rows of it.
#[inline(always)]
pub(crate) fn shade_rows<const N: usize, S: SpanShader<N>>(
    v: [(Coord, Coord); 3],
    attributes: &Attributes<N>,
    clip: &Rectangle,
    band: &Band,
    shader: &mut S,
    keep: Option<&mut impl KeptWords>,
) -> Option<bool> {
    match SmallTriangle::new(v, attributes, clip, shader.walk_planes()) {
        Ok(triangle) => {
            // The runs once, for the set-up kept and this band's rows.
            let runs = RowRuns::new(&triangle.edges, triangle.last + 1);
            let kept = keep.is_some_and(|k| triangle.keep(&runs, k));
            triangle.draw_rows(runs, band, shader);
            Some(kept)
        }
        Err(NotSmall::Empty) => Some(false),
        Err(NotSmall::Other) => None,
    }
}

/// Keeps the set-up [`level_face_keeping`] wrote for a small triangle in `keep`, as
/// [`shade_rows`] keeps its own (the integers of [`SmallTriangle::new`] and [`RowRuns::new`], up
/// to the order of two bounds of one kind, whose greater or lesser the runs take either way):
/// whether it did.
///
/// [`level_face_keeping`]: crate::arch::level_face_keeping
#[inline(always)]
pub(crate) fn keep_setup(setup: &SmallSetup, keep: &mut impl KeptWords) -> bool {
    let ((x0, y0), rows) = setup.rows();
    let bound = |(numerator, divisor, step)| RowBound {
        numerator,
        divisor,
        step,
    };
    let runs = RowRuns {
        bounds: rows.bounds.map(bound),
        middle_starts: rows.middle_starts,
        columns: rows.columns,
    };
    let (d, l) = (rows.depth, rows.level);
    let planes = Planes::from_parts([d[0], l[0]], [d[1], l[1]], [d[2], l[2]]);
    let region = (
        x0,
        y0,
        rows.columns.wrapping_sub(1),
        rows.rows.wrapping_sub(1),
    );
    SmallTriangle::from_runs(region, planes).keep(&runs, keep)
}

/// Draws the rows of `band` of the small triangle whose set-up [`shade_rows`] kept in `kept`:
/// what `shade_rows` draws there.
#[inline(always)]
pub(crate) fn resume_rows<const N: usize, S: SpanShader<N>>(
    kept: &impl KeptWords,
    band: &Band,
    shader: &mut S,
) {
    SmallTriangle::<N>::draw_kept(kept, band, shader);
}

/// Words of a kept set-up: the region's first pixel, its size, the three bounds of its rows'
/// runs (6) and two planes (6).
pub(crate) const KEPT_WORDS: usize = 14;

/// Where a small triangle's set-up over the frame's clip is kept by [`shade_rows`] to draw
/// the rows of later bands without setting it up again (a bin's triangles crossing bands): the
/// same integers, so the same pixels and values. Words `0..KEPT_WORDS`, written and read in
/// place (a bin keeps them in its storage: no copy of a set-up a band).
pub(crate) trait KeptWords {
    /// Word `i` (below [`KEPT_WORDS`]).
    fn word(&self, i: usize) -> u32;
    /// Sets word `i` (below [`KEPT_WORDS`]) to `w`.
    fn set_word(&mut self, i: usize, w: u32);
}

/// A set-up's words on their own.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Kept(pub(crate) [u32; KEPT_WORDS]);

impl KeptWords for Kept {
    #[inline(always)]
    fn word(&self, i: usize) -> u32 {
        self.0.get(i).copied().unwrap_or(0)
    }

    #[inline(always)]
    fn set_word(&mut self, i: usize, w: u32) {
        if let Some(v) = self.0.get_mut(i) {
            *v = w;
        }
    }
}

/// A bound's divisor (1 to 2¹², less one: 12 bits) and step (below 2¹⁷ in magnitude: the
/// other 20) in a word.
#[inline(always)]
fn pack_bound(b: &RowBound) -> u32 {
    (b.divisor.get() - 1) | (b.step as u32) << 12
}

/// The bound [`pack_bound`] put in `w`, with its numerator.
#[inline(always)]
fn unpack_bound(numerator: u32, w: u32) -> RowBound {
    RowBound {
        numerator: numerator as i32,
        divisor: NonZeroU32::new((w & 0xFFF) + 1).unwrap_or(NonZeroU32::MIN),
        step: w as i32 >> 12,
    }
}

impl<const N: usize> SmallTriangle<N> {
    /// A set-up whose rows come from its runs, not its edges (kept, or set up elsewhere): the
    /// region `(x0, y0, last, rows)` (its first pixel, last column and row offsets) and
    /// `planes`.
    #[inline(always)]
    fn from_runs((x0, y0, last, rows): (i32, i32, u32, u32), planes: Planes<N>) -> Self {
        let unused = Edge { a: 0, b: 0, k: 0 };
        SmallTriangle {
            x0,
            y0,
            last,
            rows,
            edges: [unused; 3],
            planes,
        }
    }

    /// Writes the set-up into `kept`, with `runs` (its first row's) in place of its edges, so
    /// that the bands below draw from them with no edge classified again. `false` (nothing
    /// written) for more than two planes, a region past 2¹⁶ pixels from the clip's origin (the
    /// first pixel takes one word), or no divider (the runs come from the edges' values).
    #[inline(always)]
    fn keep(&self, runs: &RowRuns, kept: &mut impl KeptWords) -> bool {
        if 8 + 3 * N > KEPT_WORDS || !HAS_DIVIDER {
            return false;
        }
        let (Ok(x0), Ok(y0)) = (u16::try_from(self.x0), u16::try_from(self.y0)) else {
            return false;
        };
        let [b0, b1, b2] = &runs.bounds;
        // The region's last column and row offsets are below 16 (a small triangle's box).
        let head = [
            u32::from(x0) | u32::from(y0) << 16,
            self.last | self.rows << 4 | u32::from(runs.middle_starts) << 8,
            b0.numerator as u32,
            b1.numerator as u32,
            b2.numerator as u32,
            pack_bound(b0),
            pack_bound(b1),
            pack_bound(b2),
        ];
        for (i, w) in head.into_iter().enumerate() {
            kept.set_word(i, w);
        }
        let planes = [
            self.planes.first(),
            self.planes.step(),
            self.planes.row_step(),
        ];
        for (p, plane) in planes.iter().enumerate() {
            for (k, w) in plane.iter().enumerate() {
                kept.set_word(8 + p * N + k, *w);
            }
        }
        true
    }

    /// Draws the rows of `band` of the set-up [`keep`](Self::keep) wrote into `kept`: what
    /// [`draw_rows`](Self::draw_rows) draws there from the set-up itself.
    #[inline(always)]
    fn draw_kept<S: SpanShader<N>>(kept: &impl KeptWords, band: &Band, shader: &mut S) {
        if 8 + 3 * N > KEPT_WORDS || !HAS_DIVIDER {
            return;
        }
        let w = |i: usize| kept.word(i);
        let (origin, size) = (w(0), w(1));
        let last = size & 15;
        let runs = RowRuns {
            bounds: [
                unpack_bound(w(2), w(5)),
                unpack_bound(w(3), w(6)),
                unpack_bound(w(4), w(7)),
            ],
            middle_starts: size & 1 << 8 != 0,
            columns: last + 1,
        };
        let plane = |from: usize| core::array::from_fn(|k| w(from + k));
        let planes = Planes::from_parts(plane(8), plane(8 + N), plane(8 + 2 * N));
        let (x0, y0) = ((origin & 0xFFFF) as i32, (origin >> 16) as i32);
        let triangle = SmallTriangle::from_runs((x0, y0, last, size >> 4 & 15), planes);
        triangle.draw_rows(runs, band, shader);
    }

    /// Draws the rows of `band` (see [`shade_rows`]), `runs` those of the region's first row.
    #[inline(always)]
    fn draw_rows<S: SpanShader<N>>(mut self, mut runs: RowRuns, band: &Band, shader: &mut S) {
        // Rows y0 ..= y0 + rows, below 16 of them: no overflow.
        let last = self.y0 + self.rows as i32;
        if self.y0 < band.first {
            if last < band.first {
                return;
            }
            let skip = (band.first - self.y0) as u32;
            for e in &mut self.edges {
                e.k += e.b * skip as i32;
            }
            for b in &mut runs.bounds {
                b.numerator += b.step * skip as i32;
            }
            self.planes = self.planes.advanced(skip);
            self.y0 = band.first;
            self.rows -= skip;
        }
        if last > band.last {
            if self.y0 > band.last {
                return;
            }
            self.rows = (band.last - self.y0) as u32;
        }
        self.draw_runs(runs, shader);
    }
}

/// `(n·r + 2^(s−1)) >> s` modulo 2³² for `s` in `[7, 31]`: a 32 × 32-bit product and shifts of
/// its halves, no 64-bit shift.
#[inline(always)]
fn scaled(n: i32, r: i32, s: u32) -> u32 {
    let p = mul_i32_wide(n, r).wrapping_add(i64::from(1u32 << (s - 1)));
    let (lo, hi) = (p as u32, (p >> 32) as u32);
    lo.wrapping_shr(s) | hi.wrapping_shl(32 - s)
}

/// The planes of a small triangle of doubled area `area2` (below 2²⁵; `swap`: its oriented
/// vertices 1 and 2 are input vertices 2 and 1) whose edges opposite oriented vertices 1 and 2 are `e1`, `e2` with their
/// values `l1`, `l2` at the first pixel; `None` for slivers whose attributes change by more than
/// 2¹⁴ LSB a pixel.
///
/// With `r = ⌊2⁶²/(area2·2ᵗ)⌋` (`t ≥ 7`, `r < 2³¹`), an attribute's step is
/// `Nx·2²⁴/area2 = Nx·r >> s`, `s = 38 − t`, for the exact numerator `Nx = Σ dₖ·aₖ` (below
/// 2³⁰), within `|step|·2⁻³⁰ + ½` units (below 2⁻¹⁶ LSB for steps under 2¹⁴ LSB); the
/// barycentrics at the first pixel likewise from the exact edge values (within 2⁻²³). Over the
/// at most 34 pixels (x plus y) of such a triangle from its vertex 0, every value stays within
/// 2⁻¹⁰ LSB of the exact plane, the bound of [`Planes::compact`].
#[inline(always)]
fn small_planes<const N: usize>(
    attributes: &Attributes<N>,
    swap: bool,
    area2: u32,
    (e1, l1): (Edge, i32),
    (e2, l2): (Edge, i32),
) -> Option<Planes<N>> {
    let t = leading_zeros_32(area2);
    // ⌊2⁶³/d⌋ ≤ 2³², clamped below 2³² and halved (in 32 bits): below 2³¹, a relative change
    // under 2⁻³⁰.
    let r = (reciprocal_63(area2 << t).min(u64::from(u32::MAX)) as u32 >> 1) as i32;
    let s = 38 - t;
    // Barycentrics of oriented vertices 1 and 2 at the first pixel, 24 fractional bits: below
    // 2⁸ for a first pixel in the box, and below 2³⁰ (else a sliver: `None`).
    // (l·r) >> (s + 29) in {−1, 0}, from the high word of the product (s + 29 > 32).
    let fits = |l: i32| {
        let high = (mul_i32_wide(l, r) >> 32) as i32;
        ((high >> (s - 3)) + 1) as u32 <= 1
    };
    if !fits(l1) || !fits(l2) {
        return None;
    }
    let (b1, b2) = (scaled(l1, r, s) as i32, scaled(l2, r, s) as i32);
    let [c0, c1, c2] = attributes.values;
    let (c1, c2) = if swap { (c2, c1) } else { (c1, c2) };
    // Steps of at most 2¹⁴ LSB a pixel: |Nx| < area2·2¹⁴ (below 2³⁹, and 2³⁰ suffices).
    let limit = if area2 < 1 << 16 {
        area2 << 14
    } else {
        1 << 30
    };
    let mut planes = Planes::zero();
    for k in 0..N {
        let base = i32::from(c0[k]);
        let (d1, d2) = (i32::from(c1[k]) - base, i32::from(c2[k]) - base);
        // |d| ≤ 2¹⁶ and |a|, |b| < 2¹³: below 2³⁰.
        let (nx, ny) = (d1 * e1.a + d2 * e2.a, d1 * e1.b + d2 * e2.b);
        if nx.unsigned_abs() >= limit || ny.unsigned_abs() >= limit {
            return None;
        }
        // 2⁻³² units: below 2⁴⁸. The vertex value `base·2²⁴` is a multiple of 2⁸: added after
        // the rounding shift, as `base·2¹⁶`, the same integer modulo 2³².
        let v = mul_i32_wide(d1, b1) + mul_i32_wide(d2, b2);
        let value = (((v + (1 << 7)) >> 8) as u32).wrapping_add((base as u32) << 16);
        let half = attributes.half[k];
        planes.set(
            k,
            value.wrapping_add(half),
            scaled(nx, r, s),
            scaled(ny, r, s),
        );
    }
    Some(planes)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::vec::Vec;

    use embedded_graphics::prelude::*;

    use super::*;
    use crate::raster::compact::{Classified, CompactTriangle};
    use crate::raster::edge::TriangleSetup;
    use crate::raster::edge::{first_centre_from, last_centre_to};
    use crate::raster::plane::exact::check_channel_planes;

    /// Random small triangles: boxes from a sub-pixel to 16 px (slivers and collinear ones
    /// included) anywhere in the `Coord` range, clips over and across them.
    fn cases(seed: u64, n: usize, mut check: impl FnMut([(Coord, Coord); 3], Rectangle)) {
        let mut next = crate::random(seed);
        for i in 0..n {
            let size = ((1 + next() % u64::from(SMALL << SUBPIXEL_BITS)) >> (next() % 5)).max(1);
            let origin = if i % 2 == 0 {
                ((next() % 4096) as i32 - 2048, (next() % 4096) as i32 - 2048)
            } else {
                (next() as i32, next() as i32)
            };
            let mut v = [(); 3].map(|_| {
                (
                    origin.0.wrapping_add((next() % size) as i32),
                    origin.1.wrapping_add((next() % size) as i32),
                )
            });
            if i % 5 == 0 {
                // On a line, or a hair off it.
                let (d0, d1) = (v[1].0.wrapping_sub(v[0].0), v[1].1.wrapping_sub(v[0].1));
                v[2] = (
                    v[1].0
                        .wrapping_add(d0)
                        .wrapping_add((next() % 3) as i32 - 1),
                    v[1].1.wrapping_add(d1),
                );
            }
            let mut px = |c: i32| (c >> SUBPIXEL_BITS).saturating_sub(4) + (next() % 6) as i32;
            let clip = Rectangle::new(
                Point::new(px(v[0].0), px(v[0].1)),
                Size::new((next() % 24) as u32, (next() % 24) as u32),
            );
            check(
                v.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y))),
                clip,
            );
        }
    }

    /// Records the spans and their values.
    struct Record(Vec<(Span, [u32; 2])>);

    impl SpanShader<2> for Record {
        type Steps = [u32; 2];
        fn prepare(&mut self, step: [u32; 2]) -> [u32; 2] {
            step
        }
        fn span(&mut self, _: &[u32; 2], span: Span, start: [u32; 2]) {
            self.0.push((span, start));
        }
        fn scans_small(&self) -> bool {
            true
        }
    }

    /// The runs by division are the runs by scanning (the firmware of cores without a divider
    /// scans) and by the reciprocals of a host, row after row, for random edges of triangles (their `a` sum to 0; horizontal
    /// edges included), empty and full rows included.
    #[test]
    fn runs_by_division_and_by_scan_agree() {
        let mut next = crate::random(0x5ca1_ab1e_0000_0003);
        let mut value = |bits: u32| (next() % (1 << bits)) as i32 - (1 << (bits - 1));
        let (mut partial, mut flat) = (0, 0);
        for i in 0..100_000 {
            let mut a = [value(13), value(13) >> (i % 4), 0];
            if i % 5 == 0 {
                a[i % 2] = 0;
            }
            a[2] = -a[0] - a[1];
            if a.iter().all(|&a| a == 0) || a[2].unsigned_abs() >= 1 << 13 {
                continue;
            }
            a.rotate_left(i % 3);
            let last = (value(5) & 15) as u32;
            let edges: [Edge; 3] = core::array::from_fn(|j| {
                let b = value(13) >> (i % 3);
                // Near the row's crossing of the region, or anywhere.
                let k = if i % 4 == 0 {
                    value(20)
                } else {
                    -a[j] * value(6) + value(9)
                };
                Edge { a: a[j], b, k }
            });
            flat += usize::from(a.contains(&0));
            let mut runs = RowRuns::new(&edges, last + 1);
            let mut reciprocal_runs = ReciprocalRuns::new(&runs);
            for row in 0..16 {
                let at = edges.map(|e| (e.k + row * e.b, e.a));
                let (s, e) = run_by_scan(at, last);
                let (ds, de) = runs.run();
                let scanned = if e > s { (s, e) } else { (0, 0) };
                let divided = if de > ds { (ds, de) } else { (0, 0) };
                assert_eq!(scanned, divided, "{at:?} {last}");
                assert_eq!(reciprocal_runs.run(), runs.run(), "{at:?} {last}");
                partial += usize::from(e > s && (s > 0 || e <= last));
                runs.advance();
                reciprocal_runs.advance();
            }
        }
        assert!(partial > 50_000 && flat > 10_000, "{partial} {flat}");
    }

    /// With the walk's planes (the 2D fills' scan), a scanned small triangle has the compact
    /// walk's integers: the same set-up of the same triangle over the same clip, slivers too.
    #[test]
    fn scan_with_walk_planes_has_the_walks_integers() {
        let mut same = 0;
        let mut next = crate::random(0x5ca1_ab1e_0000_0003);
        cases(0x5ca1_ab1e_0000_0004, 100_000, |v, clip| {
            let channels = [(); 3].map(|_| [next() as u8, next() as u8, next() as u8]);
            let attributes = Attributes::channels(channels);
            let Classified::Compact(walked) = CompactTriangle::classify(v, &clip) else {
                return;
            };
            let Ok(scanned) = SmallTriangle::new(v, &attributes, &clip, true) else {
                return;
            };
            let planes = Planes::compact(&walked.setup, &attributes);
            let parts = |p: &Planes<3>| (p.first(), p.step(), p.row_step());
            assert_eq!(parts(&scanned.planes), parts(&planes), "{v:?} {clip:?}");
            assert_eq!((scanned.x0, scanned.y0), (walked.x0, walked.y0));
            same += 1;
        });
        assert!(same > 20_000, "{same}");
    }

    /// Exactly the pixels of the per-pixel edge tests of the general set-up, once each, and
    /// attribute values within 2⁻¹⁰ LSB of the exact plane at every pixel of the region.
    #[test]
    fn spans_and_planes_are_exact() {
        let (mut drawn, mut values) = (0, 0u64);
        let mut next = crate::random(0x5ca1_ab1e_0000_0001);
        cases(0x5ca1_ab1e_0000_0002, 200_000, |v, clip| {
            let channels = [(); 3].map(|_| [next() as u8, next() as u8]);
            let attributes = Attributes::channels(channels);
            let mut record = Record(Vec::new());
            let done = shade(v, &attributes, &clip, &mut record);
            let setup = TriangleSetup::new(v);
            let in_clip = |x: i32, y: i32| {
                let (cx, cy) = (clip.top_left.x, clip.top_left.y);
                x >= cx
                    && y >= cy
                    && i64::from(x) < i64::from(cx) + i64::from(clip.size.width)
                    && i64::from(y) < i64::from(cy) + i64::from(clip.size.height)
            };
            if !done {
                assert!(record.0.is_empty());
                return;
            }
            let mut seen = std::collections::HashSet::new();
            for (span, _) in &record.0 {
                for x in span.x_start..span.x_end {
                    assert!(seen.insert((x, span.y)), "{v:?}: ({x}, {}) twice", span.y);
                }
            }
            // Every pixel of the box: covered iff the edge tests say so.
            let (x, y) = (v.map(|p| p.0.to_bits()), v.map(|p| p.1.to_bits()));
            let lo = |m: [i32; 3]| first_centre_from(m[0].min(m[1]).min(m[2]));
            let hi = |m: [i32; 3]| last_centre_to(m[0].max(m[1]).max(m[2]));
            for j in lo(y)..=hi(y) {
                for i in lo(x)..=hi(x) {
                    let want = in_clip(i, j) && setup.as_ref().is_some_and(|s| s.covers(i, j));
                    assert_eq!(seen.contains(&(i, j)), want, "{v:?} {clip:?} ({i}, {j})");
                }
            }
            drawn += seen.len();
            // Values against the exact barycentric interpolation, at each span's first pixel
            // and stepped along it.
            let Some(setup) = setup else { return };
            let _ = setup;
            let Ok(triangle) = SmallTriangle::new(v, &attributes, &clip, false) else {
                return;
            };
            let region = (triangle.x0, triangle.y0, triangle.last, triangle.rows);
            let raw = v.map(|(x, y)| (x.to_bits(), y.to_bits()));
            values += check_channel_planes(raw, &channels, region, |column, row| {
                triangle.planes.at(column, row)
            });
        });
        assert!(
            drawn > 80_000 && values > 500_000,
            "{drawn} pixels, {values} values"
        );
    }
}
