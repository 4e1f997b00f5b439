//! Compact triangles: a bounding box under 2048 × 2048 pixels, set up and walked in 32-bit
//! arithmetic.
//!
//! Every triangle whose vertices lie within 2048 pixels of each other on both axes — anywhere in
//! the [`Coord`] range — is a compact triangle. For those, every edge value the walk needs fits
//! an `i32`, so the whole rasterizer is a few small loops: set-up forms a handful of 64-bit
//! products and one 32-bit reciprocal of the area (colour gradients; slivers divide exactly), and
//! each row steps one start and one end boundary column by a quotient and a remainder (see
//! [`walk`](crate::raster::walk)), switching edges at the middle vertex.
//!
//! [`GouraudTriangle::draw`](crate::GouraudTriangle) and
//! [`draw_into`](crate::GouraudTriangle::draw_into) take this path for compact triangles and the
//! general one (`i64`/`i128` set-up, the same walk) for the rest; on x86-64 `draw_into` draws
//! the smallest (under 8 × 8 px) from the same set-up a row of lanes at a time
//! (`tiny`). The `*_compact` methods take
//! only this path and reject larger triangles, which keeps a firmware that uses only them small:
//! the Gouraud rasterizer links in about 4.8 KB on a Cortex-M0 (see the README's footprint).
//!
//! Coverage is the same exact top-left rule as everywhere else. Colours are within 2⁻¹⁰ LSB of
//! the exact plane before the final truncation (the barycentric gradients carry 32 fractional
//! bits per pixel; values wrap modulo 2³², which is exact for the covered pixels).
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use embedded_raster::{raster::TooLarge, Coord, GouraudTriangle, SliceFramebuffer, Vertex};
//!
//! let mut pixels = [Rgb565::BLACK; 64 * 48];
//! let mut fb = SliceFramebuffer::new(&mut pixels, 64, 48).unwrap();
//! let v = |x: i32, y: i32, c| Vertex::new(Coord::from_num(x), Coord::from_num(y), c);
//! let small = GouraudTriangle::new([v(2, 2, Rgb565::RED), v(60, 10, Rgb565::GREEN), v(20, 45, Rgb565::BLUE)]);
//! assert_eq!(small.draw_into_compact(&mut fb), Ok(()));
//! assert_eq!(fb.get(3, 3).map(|c| c.r()), Some(30));
//! // 3000 pixels wide: not compact, nothing drawn.
//! let wide = GouraudTriangle::new([v(-1000, 0, Rgb565::RED), v(2000, 10, Rgb565::RED), v(0, 40, Rgb565::RED)]);
//! assert_eq!(wide.draw_into_compact(&mut fb), Err(TooLarge));
//! ```

use core::num::{NonZeroU32, NonZeroU64};

use embedded_graphics::primitives::Rectangle;

use crate::fixed_point::{Coord, HALF_PIXEL, SUBPIXEL_BITS};
use crate::raster::arith::{div_rem_u32, mul_i32_wide};
use crate::raster::edge::{last_centre_before, owns_centres_on};
use crate::raster::walk::{bounds, Boundary, Region, Walk};

/// Width and height of a compact triangle's bounding box stay below this many sub-pixel units
/// (2¹⁹, that is 2048 pixels).
pub const LIMIT: i64 = 1 << 19;

/// The triangle's bounding box is 2048 pixels or more wide or tall: the compact path does not
/// take it (nothing was drawn).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TooLarge;

impl core::fmt::Display for TooLarge {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "the compact path takes triangles under 2048 × 2048 pixels, given one 2048 pixels \
             or more wide or tall (nothing drawn; `draw_into` takes any size)"
        )
    }
}

impl core::error::Error for TooLarge {}

/// `(⌊n / d⌋, n mod d)` for `d > 0`, in 32 bits.
#[inline]
fn div_floor(n: i32, d: NonZeroU32) -> (i32, u32) {
    let (q, r) = div_rem_u32(n.unsigned_abs(), d);
    // |n| ≤ 2³¹, so the quotient's negation fits.
    match (n < 0, r) {
        (false, _) => (q as i32, r),
        (true, 0) => ((q as i32).wrapping_neg(), 0),
        (true, r) => ((q as i32).wrapping_neg().wrapping_sub(1), d.get() - r),
    }
}

/// The boundary (see [`Walk`]) of the edge with coefficients `a ≠ 0`, `b` from the pixel centre at
/// `offset` (sub-pixels) from the edge's start vertex on; `None` if the edge's value there
/// does not fit (never inside a compact triangle's bounding box). One copy on Cortex-M0 (flash).
#[cfg_attr(armv6m, inline(never))]
#[cfg_attr(not(armv6m), inline(always))]
fn boundary(a: i32, b: i32, offset: (i32, i32)) -> Option<Boundary> {
    // |E| < 2·2¹⁹·2¹⁹ inside the bounding box, so K = ⌊E/256⌋ − t fits i32.
    let e = mul_i32_wide(a, offset.0) + mul_i32_wide(b, offset.1);
    let on_lattice = e & ((1 << SUBPIXEL_BITS) - 1) == 0;
    let owns = owns_centres_on(a.into(), b.into());
    let k = i32::try_from((e >> SUBPIXEL_BITS) - i64::from(on_lattice && !owns)).ok()?;
    let m = NonZeroU32::new(a.unsigned_abs()).unwrap_or(NonZeroU32::MIN);
    let (q, rem) = div_floor(k, m);
    let (qb, rem_step) = div_floor(b, m);
    if a > 0 {
        // Covered from ⌈−k/a⌉ = −⌊k/a⌋ on; the column moves left by ⌊b/a⌋ (+1 on a carry).
        Some(Boundary::from_parts(
            q.wrapping_neg(),
            rem,
            qb.wrapping_neg(),
            rem_step,
            m.get(),
        ))
    } else {
        // Covered up to ⌊k/|a|⌋.
        Some(Boundary::from_parts(q, rem, qb, rem_step, m.get()))
    }
}

/// What the compact set-up makes of a triangle over a clip rectangle.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Classified {
    /// Nothing inside the clip rectangle is covered (or the vertices are collinear).
    Empty,
    /// Compact, set up over the clip rectangle.
    Compact(CompactTriangle),
    /// Not compact, with the pixels of its bounding box inside the clip rectangle (if any).
    Large(Option<Region>),
}

impl Classified {
    /// What `compact` makes of a compact triangle, or else the region the general set-up
    /// starts from (`None` if nothing is covered): that of a triangle that is not compact, or of
    /// one that `compact` does not take.
    #[inline(always)]
    pub(crate) fn compact_or_region<T>(
        self,
        compact: impl FnOnce(&CompactTriangle) -> Result<T, TooLarge>,
    ) -> Result<T, Option<Region>> {
        match self {
            Classified::Empty => Err(None),
            Classified::Compact(triangle) => {
                compact(&triangle).map_err(|_| Some(triangle.region()))
            }
            Classified::Large(region) => Err(region),
        }
    }

    /// A compact triangle and its walk, or else the region the general set-up starts from
    /// (`None` if nothing is covered). [`compact_or_region`](Self::compact_or_region) for the
    /// walk, spelled out: through it the triangle is copied for the closure, which costs the
    /// Cortex-M0's `shade_dyn` 76–88 bytes of flash.
    #[inline(always)]
    pub(crate) fn walk(self) -> Result<(CompactTriangle, Walk), Option<Region>> {
        match self {
            Classified::Empty => Err(None),
            Classified::Compact(triangle) => match triangle.walk() {
                Ok(walk) => Ok((triangle, walk)),
                Err(TooLarge) => Err(Some(triangle.region())),
            },
            Classified::Large(region) => Err(region),
        }
    }
}

/// The oriented set-up of a compact triangle: what the colour planes need.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CompactSetup {
    /// Which input vertex each oriented vertex is.
    pub(crate) order: [usize; 3],
    /// Edge coefficients `a` (per sub-pixel in x) and `b` (in y) of the edges opposite oriented
    /// vertices 1 and 2.
    pub(crate) a: [i32; 2],
    pub(crate) b: [i32; 2],
    /// Twice the area, sub-pixel units squared (positive, below 2³⁸).
    pub(crate) area2: NonZeroU64,
    /// Offset of the first pixel centre of the walk from oriented vertex 0, sub-pixel units.
    pub(crate) dx: i32,
    pub(crate) dy: i32,
    /// The bounding box's width plus height in pixels, plus 2: a bound on the distance (in x
    /// plus y) from vertex 0 to any pixel the walk visits, below 2¹³.
    pub(crate) reach: u32,
}

impl CompactSetup {
    /// The set-up of a triangle whose oriented vertices are input vertices `order`, with edges
    /// `(a, b)` opposite oriented vertices 1 and 2, doubled area `area2`, first pixel centre
    /// `first` relative to vertex 0 and vertex box `extent` (sub-pixels): the compact walk's, and
    /// the 2D fills' scan of a small triangle (`raster::scan`) takes the same.
    #[inline(always)]
    pub(crate) fn new(
        order: [usize; 3],
        (a, b): ([i32; 2], [i32; 2]),
        area2: NonZeroU64,
        first: (i32, i32),
        extent: (u32, u32),
    ) -> Self {
        CompactSetup {
            order,
            a,
            b,
            area2,
            dx: first.0,
            dy: first.1,
            reach: ((extent.0 + extent.1) >> SUBPIXEL_BITS) + 2,
        }
    }
}

/// A compact triangle oriented and placed over a clip rectangle: what its walks and colour
/// planes start from.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CompactTriangle {
    pub(crate) setup: CompactSetup,
    /// Vertex 0's position, sub-pixels.
    origin: (i32, i32),
    /// Oriented vertices relative to vertex 0.
    o: [(i32, i32); 3],
    /// Edges opposite oriented vertices 0, 1, 2: coefficients `(a, b)` and start vertices.
    pub(crate) coef: [(i32, i32); 3],
    pub(crate) starts: [(i32, i32); 3],
    /// Pixels of the walk: columns `x0..=x1`, rows `y0..=y1` (clipped, not empty).
    pub(crate) x0: i32,
    pub(crate) x1: i32,
    pub(crate) y0: i32,
    pub(crate) y1: i32,
    /// Width and height of the vertices' bounding box, sub-pixels (below [`LIMIT`]): what
    /// `tiny` rows check (x86-64 only).
    #[cfg_attr(not(sse2_rows), allow(dead_code))]
    pub(crate) extent: (u32, u32),
}

impl CompactTriangle {
    /// The triangle `v` over `clip`; `Ok(None)` if nothing inside `clip` is covered (or the
    /// vertices are collinear), `Err(TooLarge)` if the triangle is not compact.
    #[inline(always)]
    pub(crate) fn new(
        v: [(Coord, Coord); 3],
        clip: &Rectangle,
    ) -> Result<Option<CompactTriangle>, TooLarge> {
        match Self::classify(v, clip) {
            Classified::Compact(triangle) => Ok(Some(triangle)),
            Classified::Empty => Ok(None),
            Classified::Large(_) => Err(TooLarge),
        }
    }

    /// [`new`](Self::new), with the region of a triangle that is not compact: the general
    /// set-up's (one copy of the region's arithmetic for both set-ups).
    #[inline(always)]
    pub(crate) fn classify(v: [(Coord, Coord); 3], clip: &Rectangle) -> Classified {
        // In 32 bits throughout (Cortex-M0 forms each 64-bit operation from several).
        let p = v.map(|(x, y)| (x.to_bits(), y.to_bits()));
        let bounds = bounds(p);
        let [min_x, min_y, max_x, max_y] = bounds;
        // Pixels whose centres lie in the bounding box, clipped.
        let region = Region::within(bounds, clip);
        // The wrapping differences are the true ones (below 2³²).
        let limit = LIMIT as u32;
        let extent = (
            max_x.wrapping_sub(min_x) as u32,
            max_y.wrapping_sub(min_y) as u32,
        );
        if extent.0 >= limit || extent.1 >= limit {
            return Classified::Large(region);
        }
        // All but the centres on a horizontal bottom edge (below).
        let Some(Region { x0, x1, y0, mut y1 }) = region else {
            return Classified::Empty;
        };
        // Vertices relative to the first one: every difference is below 2¹⁹.
        let rel = p.map(|q| (q.0.wrapping_sub(p[0].0), q.1.wrapping_sub(p[0].1)));
        // Products of factors below 2¹⁹: no 64 × 64-bit library calls on Cortex-M0.
        let cross = |u: (i32, i32), w: (i32, i32)| mul_i32_wide(u.0, w.1) - mul_i32_wide(u.1, w.0);
        let area2 = cross(rel[1], rel[2]);
        let Some(area) = NonZeroU64::new(area2.unsigned_abs()) else {
            return Classified::Empty;
        };
        let order = if area2 > 0 { [0, 1, 2] } else { [0, 2, 1] };
        let o = order.map(|k| rel.get(k).copied().unwrap_or_default());

        // Edges opposite oriented vertices 0, 1, 2: from o[1] to o[2], o[2] to o[0], o[0] to o[1].
        let ends = [(o[1], o[2]), (o[2], o[0]), (o[0], o[1])];
        let coef = ends.map(|(s, e)| (s.1 - e.1, e.0 - s.0));
        // A horizontal edge only limits the rows, and only a bottom one needs it: it does not
        // own the centres on it (`last_row` states this for the general set-up; here it stays a
        // loop over the edges, which LLVM compiles into the inlined walks of the Cortex-M4
        // without costing their span loops registers).
        for (&(a, b), &(s, _)) in coef.iter().zip(&ends) {
            if a == 0 && !owns_centres_on(0, b.into()) {
                y1 = y1.min(last_centre_before(s.1.wrapping_add(p[0].1)));
            }
        }
        if y0 > y1 {
            return Classified::Empty;
        }
        // The first pixel centre relative to vertex 0: inside the bounding box (so within i32),
        // below 2¹⁹.
        let centre = |i: i32, v: i32| {
            (i << SUBPIXEL_BITS)
                .wrapping_add(HALF_PIXEL as i32)
                .wrapping_sub(v)
        };
        let (px, py) = (centre(x0, p[0].0), centre(y0, p[0].1));
        Classified::Compact(CompactTriangle {
            setup: CompactSetup::new(
                order,
                ([coef[1].0, coef[2].0], [coef[1].1, coef[2].1]),
                area,
                (px, py),
                extent,
            ),
            origin: p[0],
            o,
            coef,
            starts: ends.map(|e| e.0),
            x0,
            x1,
            y0,
            y1,
            extent,
        })
    }
}

impl CompactTriangle {
    /// The pixels of the walk: the general set-up's region, should this one fail.
    #[inline(always)]
    pub(crate) fn region(&self) -> Region {
        Region {
            x0: self.x0,
            y0: self.y0,
            x1: self.x1,
            y1: self.y1,
        }
    }

    /// The walk of the triangle over its pixels; `Err` if an edge value does not fit 32 bits
    /// (never for a compact triangle).
    #[inline(always)]
    pub(crate) fn walk(&self) -> Result<Walk, TooLarge> {
        let (px, py) = (self.setup.dx, self.setup.dy);
        // Without bounds checks: k is always 0, 1 or 2.
        let pick = |k: usize| match k {
            0 => (self.coef[0], self.starts[0]),
            1 => (self.coef[1], self.starts[1]),
            _ => (self.coef[2], self.starts[2]),
        };
        // Edge k's boundary from the first pixel of row offset `row` on.
        let boundary = |k: usize, row: u32| {
            let ((a, b), s) = pick(k);
            // Inside the bounding box: below 2¹⁹ (and the row offset below 2¹¹ pixels).
            let offset = (
                px - s.0,
                py.wrapping_add((row as i32) << SUBPIXEL_BITS) - s.1,
            );
            boundary(a, b, offset).ok_or(TooLarge)
        };
        Walk::assemble(
            self.o.map(|v| v.1),
            self.origin.1,
            (self.x0, self.y0),
            self.x1 - self.x0,
            (0, (self.y1 - self.y0) as u32 + 1),
            boundary,
        )
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use std::string::ToString;

    use embedded_graphics::prelude::*;

    use super::*;

    /// The error's message: what the compact path takes and what it was given (issue #32,
    /// item 2).
    #[test]
    fn too_large_message() {
        assert_eq!(
            TooLarge.to_string(),
            "the compact path takes triangles under 2048 × 2048 pixels, given one 2048 pixels \
             or more wide or tall (nothing drawn; `draw_into` takes any size)"
        );
    }
    use crate::raster::edge::TriangleSetup;
    use crate::raster::plane::exact::check_channel_planes;
    use crate::raster::plane::{Attributes, Planes};

    /// Random compact triangles anywhere in the `Coord` range: bounding boxes from a sub-pixel to
    /// the limit, slivers included, and a 48 × 40 clip somewhere over the bounding box.
    fn random_cases(seed: u64, n: usize, mut check: impl FnMut([(i32, i32); 3], Rectangle)) {
        let mut next = crate::random(seed);
        let mut rnd = move |n: u64| next() % n;
        for i in 0..n {
            let size = (1 << rnd(20)).min(LIMIT - 1) as u64;
            let origin = match i % 3 {
                0 => (
                    rnd(1 << 16) as i64 - (1 << 15),
                    rnd(1 << 16) as i64 - (1 << 15),
                ),
                _ => (
                    rnd(1 << 32) as i64 - (1 << 31),
                    rnd(1 << 32) as i64 - (1 << 31),
                ),
            };
            let mut v = [(); 3].map(|_| (rnd(size) as i64, rnd(size) as i64));
            if i % 4 == 0 {
                // A sliver: the third vertex close to the line through the other two.
                let t = rnd(1025) as i64;
                let (a, b) = (v[0], v[1]);
                v[2] = (
                    a.0 + (b.0 - a.0) * t / 1024 + rnd(3) as i64 - 1,
                    a.1 + (b.1 - a.1) * t / 1024 + rnd(3) as i64 - 1,
                );
            }
            let clamp = |c: i64| c.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
            let v = v.map(|(x, y)| (clamp(origin.0 + x), clamp(origin.1 + y)));
            let (min_x, min_y) = (v.iter().map(|p| p.0).min(), v.iter().map(|p| p.1).min());
            let (Some(min_x), Some(min_y)) = (min_x, min_y) else {
                continue;
            };
            let mut at = |m: i32| (m >> 8) - 8 + rnd(size / 256 + 8) as i32;
            let clip = Rectangle::new(Point::new(at(min_x), at(min_y)), Size::new(48, 40));
            check(v, clip);
        }
    }

    fn coords(v: [(i32, i32); 3]) -> [(Coord, Coord); 3] {
        v.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y)))
    }

    /// The compact walk's spans are exactly the pixels the general (`i64`/`i128`) edge functions
    /// cover, pixel by pixel.
    #[test]
    fn spans_match_per_pixel_edge_tests() {
        let mut walked = 0;
        random_cases(0x00c0_ffee_1234_5678, 30_000, |v, clip| {
            let mut got = [[false; 48]; 40];
            if let Ok(Some(triangle)) = CompactTriangle::new(coords(v), &clip) {
                let spans = triangle.walk().expect("a compact walk");
                walked += 1;
                spans.fold((), |(), span, _, _| {
                    for x in span.x_start..span.x_end {
                        let (i, j) = (x - clip.top_left.x, span.y - clip.top_left.y);
                        let cell = usize::try_from(j)
                            .ok()
                            .and_then(|j| got.get_mut(j))
                            .and_then(|row| row.get_mut(usize::try_from(i).ok()?));
                        let cell =
                            cell.unwrap_or_else(|| panic!("{v:?}: ({x}, {}) outside", span.y));
                        assert!(!*cell, "{v:?}: ({x}, {}) twice", span.y);
                        *cell = true;
                    }
                });
            }
            let setup = TriangleSetup::new(coords(v));
            for (j, row) in got.iter().enumerate() {
                for (i, &cell) in row.iter().enumerate() {
                    let (x, y) = (clip.top_left.x + i as i32, clip.top_left.y + j as i32);
                    let want = setup.as_ref().is_some_and(|s| s.covers(x, y));
                    assert_eq!(cell, want, "{v:?}, clip {clip:?}, pixel ({x}, {y})");
                }
            }
        });
        assert!(walked > 5_000, "{walked}");
    }

    /// Colour accumulators against exact rationals (`i128`), at every pixel of the clip, modulo
    /// 2³² (the covered pixels' values are in range, so wrapping is exact there).
    #[test]
    fn colors_are_within_the_documented_error() {
        let checked = check_planes(4_000, |setup, attributes| {
            Some(Planes::compact(setup, attributes))
        });
        assert!(checked > 1_000_000, "{checked}");
    }

    /// Checks the planes `planes` makes (where it makes them) of random compact triangles over
    /// random clips; returns the values checked.
    fn check_planes(
        n: usize,
        planes: impl Fn(&CompactSetup, &Attributes<3>) -> Option<Planes<3>>,
    ) -> u64 {
        let mut next = crate::random(0x5eed_c010_0000_0001);
        let mut checked = 0u64;
        random_cases(0x0bad_cafe_8765_4321, n, |v, clip| {
            let Ok(Some(triangle)) = CompactTriangle::new(coords(v), &clip) else {
                return;
            };
            assert!(triangle.walk().is_ok());
            let setup = triangle.setup;
            let channels = [(); 3].map(|_| [(); 3].map(|_| next() as u8));
            let Some(colors) = planes(&setup, &Attributes::channels(channels)) else {
                return;
            };
            let region = (
                triangle.x0,
                triangle.y0,
                (triangle.x1 - triangle.x0) as u32,
                (triangle.y1 - triangle.y0) as u32,
            );
            checked +=
                check_channel_planes(v, &channels, region, |column, row| colors.at(column, row));
        });
        checked
    }
}
