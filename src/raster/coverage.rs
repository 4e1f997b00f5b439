//! Anti-aliased coverage: the area of each pixel square inside a triangle, from the exact edge
//! functions.
//!
//! A row's pixels fall in three kinds, each found from the edge functions `E` at pixel centres
//! ([`TriangleSetup`]'s, exact integers): over a square `E` ranges over `E_c ± h` with
//! `h = 128·(|a| + |b|)`, so a square is wholly inside an edge where `E_c ≥ h`, wholly outside
//! where `E_c ≤ −h`, and cut by it in between. [`cover`] hands a [`CoverageSink`] the row's
//! run of squares inside all three edges as one span (the plain fill) and every square cut by an
//! edge and outside none with its area:
//!
//! * cut by one edge: the area of a unit square on one side of a line, in closed form — a
//!   trapezoid `½ + c/max(A, B)` where the line crosses two opposite sides, else a corner
//!   triangle `t²/(2AB)` or its complement;
//! * cut by two or three (near vertices, slivers, sub-pixel triangles): the square clipped by
//!   those edges as a polygon, its area by the shoelace formula.
//!
//! Each edge is normalised once a triangle to a line `A·u + B·v + C` with `|A|, |B| < 2¹²` and
//! `C` in 16 fractional bits of a pixel, so the arithmetic a pixel is 32- and 64-bit; the
//! direction's truncation moves the line by under 2⁻¹¹ px across a square, and coverage is
//! rounded to 2⁻¹⁶: every area within 2⁻⁹ of the exact one (`tests/antialias.rs` checks it
//! against the `f64` polygon clip of `reference::pixel_area`).
//!
//! Rows and their runs come from the same conditions solved for the column: a square can be cut
//! only where `E_c > −h` for every edge, and is inside where `E_c ≥ h` for all three.

use embedded_graphics::primitives::Rectangle;

use super::arith::div_floor_wide;
use super::edge::{EdgeFunction, TriangleSetup};
use crate::fixed_point::{Coord, SUBPIXEL_BITS};

/// Coverage of a whole pixel, 16 fractional bits.
pub(crate) const FULL: u32 = 1 << 16;

/// Bits of the normalised edge directions.
const DIRECTION_BITS: u32 = 12;

/// Where anti-aliased coverage goes: runs of wholly covered pixels and partly covered pixels
/// with their area.
pub(crate) trait CoverageSink {
    /// Pixels `x0 .. x1` of row `y`, each wholly inside the triangle.
    fn full(&mut self, y: i32, x0: i32, x1: i32);

    /// Pixel `(x, y)`, `coverage / 2¹⁶` of it inside the triangle (`0 < coverage ≤` [`FULL`]).
    fn partial(&mut self, x: i32, y: i32, coverage: u32);
}

/// An edge normalised for coverage: its line through a square is `a·u + b·v + C ≥ 0` for `u`, `v`
/// in 16 fractional bits of a pixel around the square's centre, where `C` is the exact edge value
/// there scaled by [`Self::scale`].
#[derive(Debug, Clone, Copy)]
struct CoverageEdge {
    edge: EdgeFunction,
    /// `128·(|a| + |b|)`: the most the edge function changes from a centre to its square's corners.
    half: i128,
    /// Normalised direction: `a`, `b` shifted right by `shift` (magnitudes, toward zero).
    a: i64,
    b: i64,
    /// Right shift of the exact edge values to `C` (negative: a left shift).
    shift: i32,
    /// `⌊2⁴⁰ / max(|a|, |b|)⌋`, `⌊2⁴⁰ / |a|⌋`, `⌊2⁴⁰ / |b|⌋` (0 for a zero component).
    recip_max: u64,
    recip_a: u64,
    recip_b: u64,
}

impl CoverageEdge {
    fn new(edge: EdgeFunction) -> Self {
        let m = edge.a.unsigned_abs().max(edge.b.unsigned_abs());
        let bits = 64 - m.leading_zeros();
        let s = bits.saturating_sub(DIRECTION_BITS);
        let norm = |v: i64| (v.unsigned_abs() >> s) as i64 * v.signum();
        let (a, b) = (norm(edge.a), norm(edge.b));
        let recip = |v: i64| (1u64 << 40).checked_div(v.unsigned_abs()).unwrap_or(0);
        CoverageEdge {
            edge,
            half: 128 * (i128::from(edge.a.unsigned_abs()) + i128::from(edge.b.unsigned_abs())),
            a,
            b,
            // E / (256·2^s) in 16 fractional bits: E·2^(8 − s).
            shift: s as i32 - 8,
            recip_max: recip(a.abs().max(b.abs())),
            recip_a: recip(a),
            recip_b: recip(b),
        }
    }

    /// `C` of the exact edge value `e` at a centre (`|e| < half`).
    #[inline]
    fn line_offset(&self, e: i128) -> i64 {
        if self.shift >= 0 {
            (e >> self.shift) as i64
        } else {
            (e << -self.shift) as i64
        }
    }

    /// The area (16 fractional bits) of the unit square on the inside of this edge alone, its
    /// line at offset `c` from the centre.
    fn area(&self, c: i64) -> u32 {
        let (a, b) = (self.a.abs(), self.b.abs());
        let h = (a + b) << 15;
        if c >= h {
            return FULL;
        }
        if c <= -h {
            return 0;
        }
        let (m, n) = (a.max(b), a.min(b));
        if c.abs() <= (m - n) << 15 {
            // Crosses two opposite sides: ½ + c/m.
            let part = ((c.unsigned_abs() * self.recip_max) >> 40) as u32;
            return if c >= 0 {
                (FULL / 2 + part).min(FULL)
            } else {
                (FULL / 2).saturating_sub(part)
            };
        }
        // Cuts a corner: legs t/a and t/b (0 < t ≤ n·2¹⁶, so both below 2¹⁶ + 1).
        let t = (h - c.abs()) as u64;
        let legs = ((t * self.recip_a) >> 40) * ((t * self.recip_b) >> 40);
        let corner = (legs >> 17).min(u64::from(FULL)) as u32;
        if c >= 0 {
            FULL - corner
        } else {
            corner
        }
    }

    /// This edge's line, `a·u + b·v + c`, at `(u, v)`.
    #[inline]
    fn at(&self, c: i64, (u, v): (i64, i64)) -> i64 {
        self.a * u + self.b * v + c
    }
}

/// A pixel square as a polygon clipped by up to three lines: at most seven corners.
#[derive(Clone, Copy)]
struct Polygon {
    points: [(i64, i64); 8],
    len: usize,
}

impl Polygon {
    const HALF: i64 = 1 << 15;

    fn square() -> Self {
        let h = Self::HALF;
        let mut points = [(0, 0); 8];
        points[..4].copy_from_slice(&[(-h, -h), (h, -h), (h, h), (-h, h)]);
        Polygon { points, len: 4 }
    }

    /// The part where `line ≥ 0`.
    fn clip(&self, line: impl Fn((i64, i64)) -> i64) -> Self {
        let mut out = Polygon {
            points: [(0, 0); 8],
            len: 0,
        };
        let mut push = |p: (i64, i64)| {
            if let Some(slot) = out.points.get_mut(out.len) {
                *slot = p;
                out.len += 1;
            }
        };
        let points = self.points.get(..self.len).unwrap_or(&[]);
        for (i, &p) in points.iter().enumerate() {
            let q = points.get(i + 1).or(points.first()).copied().unwrap_or(p);
            let (lp, lq) = (line(p), line(q));
            if lp >= 0 {
                push(p);
            }
            if (lp >= 0) != (lq >= 0) {
                // lp and lq differ in sign: the denominator is nonzero, the ratio in [0, 1].
                let (d, t) = (i128::from(lp - lq), i128::from(lp));
                let cut = |p: i64, q: i64| p + (i128::from(q - p) * t / d) as i64;
                push((cut(p.0, q.0), cut(p.1, q.1)));
            }
        }
        out
    }

    /// The area in 16 fractional bits of a pixel.
    fn area(&self) -> u32 {
        let points = self.points.get(..self.len).unwrap_or(&[]);
        let mut twice = 0i64;
        for (i, &p) in points.iter().enumerate() {
            let q = points.get(i + 1).or(points.first()).copied().unwrap_or(p);
            twice += p.0 * q.1 - q.0 * p.1;
        }
        ((twice.unsigned_abs() + (1 << 16)) >> 17).min(u64::from(FULL)) as u32
    }
}

/// The area inside a triangle of the square of a pixel whose exact edge values at the centre are
/// `e` (each edge `k` cuts the square: `|e[k]| < half`, or has it wholly inside).
fn square_area(edges: &[CoverageEdge; 3], e: [i128; 3]) -> u32 {
    let mut cut = [false; 3];
    for (k, edge) in edges.iter().enumerate() {
        if e[k] <= -edge.half {
            return 0;
        }
        cut[k] = e[k] < edge.half;
    }
    let offsets: [i64; 3] = core::array::from_fn(|k| {
        if cut[k] {
            edges[k].line_offset(e[k])
        } else {
            0
        }
    });
    match cut {
        [false, false, false] => FULL,
        [true, false, false] => edges[0].area(offsets[0]),
        [false, true, false] => edges[1].area(offsets[1]),
        [false, false, true] => edges[2].area(offsets[2]),
        _ => {
            let mut polygon = Polygon::square();
            for k in 0..3 {
                if cut[k] {
                    polygon = polygon.clip(|p| edges[k].at(offsets[k], p));
                }
            }
            polygon.area()
        }
    }
}

/// The columns `i` (inclusive bounds) where `s·i + k > t` (`strict`) or `≥ t`.
fn columns(s: i128, k: i128, t: i128, strict: bool) -> (i128, i128) {
    let all = (i128::MIN, i128::MAX);
    let none = (1, 0);
    match s {
        0 if k > t || (!strict && k == t) => all,
        0 => none,
        s if s > 0 => {
            let lo = if strict {
                div_floor_wide(t - k, s) + 1
            } else {
                -div_floor_wide(k - t, s)
            };
            (lo, i128::MAX)
        }
        s => {
            let s = -s;
            let hi = if strict {
                -div_floor_wide(t - k, s) - 1
            } else {
                div_floor_wide(k - t, s)
            };
            (i128::MIN, hi)
        }
    }
}

/// Hands `sink` every pixel of `clip` that the triangle `v` covers in part or whole, row by row
/// top to bottom: the wholly covered run of a row as one span, the others one by one with their
/// area. Degenerate triangles cover nothing.
pub(crate) fn cover(v: [(Coord, Coord); 3], clip: &Rectangle, sink: &mut impl CoverageSink) {
    let Some(setup) = TriangleSetup::new(v) else {
        return;
    };
    let Some(bottom_right) = clip.bottom_right() else {
        return;
    };
    let edges = [0, 1, 2].map(|k| CoverageEdge::new(setup.edge(k)));
    let ys = setup.oriented.map(|p| p.1);
    let (top, bottom) = (ys[0].min(ys[1]).min(ys[2]), ys[0].max(ys[1]).max(ys[2]));
    // Rows whose squares meet the open band between the lowest and highest vertex.
    let first = (top >> SUBPIXEL_BITS).max(clip.top_left.y);
    let last = ((bottom - 1) >> SUBPIXEL_BITS).min(bottom_right.y);
    let (x0, x1) = (i128::from(clip.top_left.x), i128::from(bottom_right.x));
    for y in first..=last {
        // Per edge: E = s·i + k at the centre of pixel (i, y).
        let k: [i128; 3] = edges.map(|e| e.edge.exact_at(0, i64::from(y), false));
        let s: [i128; 3] = edges.map(|e| i128::from(e.edge.a) << SUBPIXEL_BITS);
        let (mut lo, mut hi) = (x0, x1);
        let (mut inner_lo, mut inner_hi) = (x0, x1);
        for e in 0..3 {
            let (a, b) = columns(s[e], k[e], -edges[e].half, true);
            (lo, hi) = (lo.max(a), hi.min(b));
            let (a, b) = columns(s[e], k[e], edges[e].half, false);
            (inner_lo, inner_hi) = (inner_lo.max(a), inner_hi.min(b));
        }
        if lo > hi {
            continue;
        }
        let (inner_lo, inner_hi) = if inner_lo <= inner_hi {
            (inner_lo, inner_hi)
        } else {
            (hi + 1, hi)
        };
        // The cut squares left of the wholly covered run, the run, the cut squares right of it.
        let partial = |sink: &mut _, from: i128, to: i128| {
            for x in from..=to {
                let e: [i128; 3] = core::array::from_fn(|n| s[n] * x + k[n]);
                let area = square_area(&edges, e);
                if area > 0 {
                    CoverageSink::partial(sink, x as i32, y, area);
                }
            }
        };
        partial(sink, lo, (inner_lo - 1).min(hi));
        if inner_lo <= inner_hi {
            sink.full(y, inner_lo as i32, inner_hi as i32 + 1);
            partial(sink, inner_hi + 1, hi);
        }
    }
}
