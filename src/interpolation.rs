//! Barycentric attribute interpolation by fixed-point stepping.
//!
//! An attribute with vertex values `c_k` is the plane `c(p) = Σ c_k E_k(p) / (2·area)`, where
//! `E_k` is the exact edge function opposite vertex `k`. It is evaluated at pixel centres:
//!
//! * **Per row** the value at the span start comes from a 64-bit accumulator with 32 fractional
//!   bits, moved by exact multiples of the per-pixel and per-row gradients. Its error is at most
//!   2⁻³³ per pixel moved, so under 2⁻¹⁵ over the largest region it is used for.
//! * **Per pixel** a 32-bit value with 16 fractional bits is stepped by one addition. Spans are
//!   handed out in chunks of at most [`MAX_CHUNK`] pixels, each restarted from the row value, so the
//!   stepping error stays below 2⁻⁵.
//! * Triangles whose gradients or extent are too large for that bound (extreme slivers, regions of
//!   more than 2¹⁶ pixels) take an exact path instead: every row start is divided out in `i128`.
//!
//! Values carry a +½ offset, so truncating the integer part rounds to nearest: every output is
//! within ½ LSB plus 2⁻⁴ of the exact value, inside the promised 1 LSB.
//!
//! ```
//! use embedded_raster::{edge::TriangleSetup, interpolation::AttributePlane, traversal::Region, Coord};
//! use embedded_graphics::{prelude::*, primitives::Rectangle};
//!
//! let c = |x: i32, y: i32| (Coord::from_num(x), Coord::from_num(y));
//! let setup = TriangleSetup::new([c(0, 0), c(100, 0), c(0, 100)]).unwrap();
//! let region = Region::new(&setup, &Rectangle::new(Point::zero(), Size::new(100, 100))).unwrap();
//! // Value 0 at the first vertex, 200 at the second, 0 at the third: c = 2·x.
//! let mut plane = AttributePlane::new(&setup, [0, 200, 0], &region);
//! let start = plane.row_start(10, 20);
//! assert_eq!(start >> AttributePlane::FRACTION_BITS, 21); // 2 × 10.5
//! assert_eq!(plane.step(), 2 << AttributePlane::FRACTION_BITS);
//! // Values are fixed point with 16 fractional bits; steps are added with `wrapping_add`.
//! ```

use crate::edge::{dot2, TriangleSetup};
use crate::fixed_point::SUBPIXEL_BITS;
use crate::traversal::Region;

/// Fractional bits of the per-row accumulator.
const ROW_BITS: u32 = 32;

/// Longest run of pixels stepped from one exact restart.
pub const MAX_CHUNK: u32 = 4096;

/// Largest region (`width + height + 2`) the stepped path is used for.
const MAX_STEPPED_EXTENT: i64 = 1 << 16;

/// `round(n / d)` for `d > 0`, never panicking.
#[inline]
fn div_round(n: i128, d: i128) -> i128 {
    (n.saturating_mul(2).saturating_add(d))
        .checked_div_euclid(d.saturating_mul(2))
        .unwrap_or(0)
}

/// `floor(n / d)` for `d > 0`, never panicking.
#[inline]
fn div_floor(n: i128, d: i128) -> i128 {
    n.checked_div_euclid(d).unwrap_or(0)
}

/// `1 / area2`, normalised so that one division per triangle serves every attribute.
///
/// `recip = ⌊2^shift / area2⌋` with `shift = 61 + bitlen(area2)`, so `2^61 < recip ≤ 2^62` and
/// `num · 2^k / area2` is `num · recip >> (shift − k)` with a relative error below 2⁻⁶¹. Numerators
/// of 64 bits or more fall back to an exact `i128` division.
#[derive(Debug, Clone, Copy)]
pub struct InverseArea {
    area2: i128,
    recip: i128,
    shift: u32,
}

impl InverseArea {
    /// The reciprocal of a triangle's doubled area (`area2 > 0`, as in [`TriangleSetup`]).
    pub fn new(area2: i128) -> Self {
        // |area2| < 2^65 for any Coord vertices, so shift ≤ 126.
        let shift = 61 + (128 - area2.leading_zeros());
        let recip = 1u128
            .checked_shl(shift)
            .and_then(|n| n.checked_div(area2.unsigned_abs()))
            .unwrap_or(0) as i128;
        InverseArea {
            area2,
            recip,
            shift,
        }
    }

    /// `round(num · 2^k / area2)`, for `k ≤ 40`.
    #[inline]
    pub fn scale(&self, num: i128, k: u32) -> i128 {
        let s = self.shift.saturating_sub(k);
        if num.unsigned_abs() < 1 << 64 && s > 0 && self.recip > 0 {
            (num * self.recip + (1 << (s - 1))) >> s
        } else {
            div_round(num << k, self.area2)
        }
    }
}

#[derive(Debug, Clone, Copy)]
enum Mode {
    /// Accumulated value at `(x, y)` with [`ROW_BITS`] fractional bits (includes the +½).
    Stepped {
        dx: i64,
        dy: i64,
        value: i64,
        x: i64,
        y: i64,
    },
    /// Exact evaluation of `(256·(nx·x + ny·y) + n0) / area2` at each row start.
    Exact { x: i64, y: i64 },
}

/// One attribute (a colour channel, later depth) interpolated over a triangle.
#[derive(Debug, Clone, Copy)]
pub struct AttributePlane {
    mode: Mode,
    nx: i64,
    ny: i64,
    /// `Σ c_k·C_k`, needed by the exact path only.
    n0: i128,
    area2: i128,
    step: u32,
}

impl AttributePlane {
    /// Fractional bits of the values returned by [`row_start`](Self::row_start) and
    /// [`step`](Self::step).
    pub const FRACTION_BITS: u32 = 16;

    /// Sets up the plane through the vertex values `values` (in the triangle's input vertex order;
    /// at most 16 bits each) for traversal over `region`.
    pub fn new(setup: &TriangleSetup, values: [u16; 3], region: &Region) -> Self {
        Self::with_inverse(setup, &InverseArea::new(setup.area2), values, region)
    }

    /// [`new`](Self::new) with the triangle's reciprocal area computed once for all attributes.
    pub fn with_inverse(
        setup: &TriangleSetup,
        inverse: &InverseArea,
        values: [u16; 3],
        region: &Region,
    ) -> Self {
        // Oriented vertex values; Σ a_k = Σ b_k = 0, so Σ c_k·a_k = (c₁−c₀)·a₁ + (c₂−c₀)·a₂,
        // below 2⁵⁰ in magnitude for 16-bit values: exact in i64.
        let c = setup
            .order
            .map(|v| i64::from(values.get(v).copied().unwrap_or(0)));
        let [_, e1, e2] = &setup.edges;
        let (d1, d2) = (c[1] - c[0], c[2] - c[0]);
        let nx = d1 * e1.a + d2 * e2.a;
        let ny = d1 * e1.b + d2 * e2.b;
        let dx = inverse.scale(i128::from(nx), ROW_BITS + SUBPIXEL_BITS);
        // Two's complement, wrapping: adding it steps the value modulo 2^32, which is exact
        // whenever the stepped values stay in range, as they do inside the triangle.
        let step = ((dx + (1 << (ROW_BITS - Self::FRACTION_BITS - 1)))
            >> (ROW_BITS - Self::FRACTION_BITS)) as u32;
        let (x, y) = (i64::from(region.x0), i64::from(region.y0));
        let extent = region.width() + region.height() + 2;
        if extent <= MAX_STEPPED_EXTENT {
            let dy = inverse.scale(i128::from(ny), ROW_BITS + SUBPIXEL_BITS);
            // c(p) = c₀ + (nx·(p_x − x₀) + ny·(p_y − y₀)) / area2 with vertex 0 of the oriented
            // order: a small numerator for on-screen triangles, so no division is needed.
            let (vx, vy) = setup
                .vertices
                .get(setup.order[0])
                .copied()
                .unwrap_or((0, 0));
            let half = 1 << (SUBPIXEL_BITS - 1);
            let (px, py) = (
                (x << SUBPIXEL_BITS) + half - vx,
                (y << SUBPIXEL_BITS) + half - vy,
            );
            let small =
                (nx.unsigned_abs() | ny.unsigned_abs() | px.unsigned_abs() | py.unsigned_abs())
                    < 1 << 31;
            let offset = dot2(nx, px, ny, py, small);
            let value = (i128::from(c[0]) << ROW_BITS)
                + inverse.scale(offset, ROW_BITS)
                + (1 << (ROW_BITS - 1));
            // Anywhere the traversal can ask for, |value| ≤ |value₀| + (|dx| + |dy|)·extent.
            let bound = value.abs() + (dx.abs() + dy.abs()) * i128::from(extent);
            if bound < 1 << 62 {
                return AttributePlane {
                    mode: Mode::Stepped {
                        dx: dx as i64,
                        dy: dy as i64,
                        value: value as i64,
                        x,
                        y,
                    },
                    nx,
                    ny,
                    n0: 0,
                    area2: setup.area2,
                    step,
                };
            }
        }
        let n0 = setup
            .edges
            .iter()
            .zip(c)
            .map(|(e, c)| i128::from(c) * e.c)
            .sum();
        AttributePlane {
            mode: Mode::Exact { x, y },
            nx,
            ny,
            n0,
            area2: setup.area2,
            step,
        }
    }

    /// A plane with the same `value` everywhere.
    pub const fn constant(value: u16) -> Self {
        AttributePlane {
            mode: Mode::Exact { x: 0, y: 0 },
            nx: 0,
            ny: 0,
            n0: value as i128,
            area2: 1,
            step: 0,
        }
    }

    /// `Σ c_k E_k` at the centre of pixel `(x, y)`.
    #[inline]
    fn numerator(&self, x: i64, y: i64) -> i128 {
        (dot2(self.nx, x, self.ny, y, false) << SUBPIXEL_BITS) + self.n0
    }

    /// The value (+½, [`FRACTION_BITS`](Self::FRACTION_BITS) fractional bits) at pixel `(x, y)`,
    /// which becomes the reference for [`further`](Self::further). Called once per span.
    #[inline]
    pub fn row_start(&mut self, x: i32, y: i32) -> u32 {
        let (x, y) = (i64::from(x), i64::from(y));
        match &mut self.mode {
            Mode::Stepped {
                dx,
                dy,
                value,
                x: px,
                y: py,
            } => {
                if y == *py + 1 {
                    *value = value.wrapping_add(*dy);
                } else if y != *py {
                    *value = value.wrapping_add(dy.wrapping_mul(y - *py));
                }
                if x != *px {
                    *value = value.wrapping_add(dx.wrapping_mul(x - *px));
                }
                (*px, *py) = (x, y);
                (*value >> (ROW_BITS - Self::FRACTION_BITS)) as u32
            }
            Mode::Exact { x: px, y: py } => {
                (*px, *py) = (x, y);
                self.exact(x, y)
            }
        }
    }

    /// The value `offset` pixels to the right of the last [`row_start`](Self::row_start).
    #[inline]
    pub fn further(&self, offset: u32) -> u32 {
        let offset = i64::from(offset);
        match self.mode {
            Mode::Stepped { dx, value, .. } => {
                (value.wrapping_add(dx.wrapping_mul(offset)) >> (ROW_BITS - Self::FRACTION_BITS))
                    as u32
            }
            Mode::Exact { x, y } => self.exact(x + offset, y),
        }
    }

    /// Exact `floor(c·2^16) + 2^15` at pixel `(x, y)`.
    fn exact(&self, x: i64, y: i64) -> u32 {
        let f = Self::FRACTION_BITS;
        (div_floor(self.numerator(x, y) << f, self.area2) + (1 << (f - 1))) as u32
    }

    /// Per-pixel step in x ([`FRACTION_BITS`](Self::FRACTION_BITS) fractional bits), as a
    /// two's-complement `u32` to be added with `wrapping_add`. Exact modulo 2³² even when the
    /// gradient exceeds the attribute range (then no span is longer than one pixel).
    #[inline]
    pub fn step(&self) -> u32 {
        self.step
    }

    /// Whether the fast stepped path is in use (false: exact per-row division).
    pub fn is_stepped(&self) -> bool {
        matches!(self.mode, Mode::Stepped { .. })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Coord;
    use embedded_graphics::{prelude::*, primitives::Rectangle};

    fn plane(
        v: [(i32, i32); 3],
        values: [u16; 3],
        clip: Rectangle,
    ) -> Option<(AttributePlane, TriangleSetup)> {
        let setup = TriangleSetup::new(v.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y))))?;
        let region = Region::new(&setup, &clip)?;
        Some((AttributePlane::new(&setup, values, &region), setup))
    }

    #[test]
    fn exact_and_stepped_agree_at_vertices_scale() {
        // A right triangle where the plane is c = x (pixel units), evaluated at centres.
        let clip = Rectangle::new(Point::zero(), Size::new(64, 64));
        let (mut p, _) = plane([(0, 0), (64 * 256, 0), (0, 64 * 256)], [0, 64, 0], clip).unwrap();
        assert!(p.is_stepped());
        for y in 0..4 {
            for x in [0, 5, 17] {
                let v = p.row_start(x, y);
                let exact = (x as f64 + 0.5 + 0.5) * 65536.0;
                assert!(
                    (f64::from(v) - exact).abs() < 2.0,
                    "{x},{y}: {v} vs {exact}"
                );
                assert_eq!(p.further(3) >> 16, (x + 3 + 1) as u32);
            }
        }
    }

    #[test]
    fn reciprocal_scaling_matches_division() {
        let mut seed = 0x0123_4567_89ab_cdef_u64;
        let mut rnd = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for _ in 0..20_000 {
            let area2 = (i128::from(rnd()) << (rnd() % 2)) >> (rnd() % 64) | 1;
            let num = (i128::from(rnd() as i64) << (rnd() % 20)) >> (rnd() % 60);
            let k = (rnd() % 41) as u32;
            let inv = InverseArea::new(area2);
            let exact = div_round(num << k, area2);
            let got = inv.scale(num, k);
            assert!(
                (got - exact).abs() <= 1 + (exact.abs() >> 60),
                "{num} {k} {area2}"
            );
        }
    }

    #[test]
    fn huge_gradients_take_the_exact_path() {
        let clip = Rectangle::new(Point::zero(), Size::new(64, 64));
        // A needle 2/256 px wide and 60 px tall with full-range colour across it: gradients of
        // 2^15 LSB per pixel still fit the stepped path.
        let (p, _) = plane(
            [(128, 0), (129, 60 * 256), (127, 60 * 256)],
            [0, 255, 0],
            clip,
        )
        .unwrap();
        assert!(p.is_stepped());
        // A sliver of area 1/2^17 px² along a row: 2^30 LSB per pixel vertically does not.
        let l = 60 * 256;
        let (p, _) = plane(
            [(128, 128), (128 + l, 129), (129 + l, 129)],
            [0, 0, 255],
            clip,
        )
        .unwrap();
        assert!(!p.is_stepped());
    }
}
