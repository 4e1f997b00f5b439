//! Span traversal: exact covered spans per row, by stepping each edge's boundary column.
//!
//! Each edge's reduced function `K(i, j) = a·i + b·j + k` (see [`edge`](crate::edge)) is `≥ 0`
//! on one side of a boundary column per row. For an edge that bounds the span's start (`a > 0`)
//! that column is `⌈−K(0, j)/a⌉`; for one that bounds its end (`a < 0`) it is `⌊K(0, j)/|a|⌋`.
//! Both are stepped from row to row like a Bresenham line: the column moves by the precomputed
//! quotient of `b / |a|`, the remainder accumulates, and one comparison carries it. So each row
//! costs two additions and a compare per edge, whatever the slope, and the decision is exact —
//! no rounding anywhere. Quotients below 4 are found by subtraction, so small triangles need no
//! division at all (Cortex-M0 has no divider).
//!
//! Edge functions are first tested at the corners of the clipped region: an edge that excludes
//! the whole region rejects the triangle, an edge that includes all of it is dropped. The edges
//! that remain cross the region, so their values there are below `|a|·(W+2) + |b|·H < 2^58` and
//! every stepped quantity fits `i64`.
//!
//! ```
//! use embedded_graphics::{prelude::*, primitives::Rectangle};
//! use embedded_raster::{traversal::for_each_span, Coord};
//!
//! let c = |x: i32, y: i32| (Coord::from_num(x), Coord::from_num(y));
//! let clip = Rectangle::new(Point::zero(), Size::new(8, 8));
//! let mut pixels = 0;
//! // The upper-right half of a 4×4 square owns the centres on its diagonal (a left edge):
//! // 4 + 3 + 2 + 1 pixels; the lower-left half gets the other 0 + 1 + 2 + 3.
//! for_each_span([c(0, 0), c(4, 0), c(4, 4)], clip, |_y, x0, x1| pixels += x1 - x0);
//! assert_eq!(pixels, 10);
//! for_each_span([c(0, 0), c(4, 4), c(0, 4)], clip, |_y, x0, x1| pixels += x1 - x0);
//! assert_eq!(pixels, 16);
//! ```

use embedded_graphics::primitives::Rectangle;

use crate::edge::{dot2, TriangleSetup};
use crate::fixed_point::Coord;

/// A run of covered pixels `x_start..x_end` in row `y`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Span {
    /// The row.
    pub y: i32,
    /// First covered column.
    pub x_start: i32,
    /// One past the last covered column.
    pub x_end: i32,
}

impl Span {
    /// Number of pixels in the span (at least 1).
    pub fn len(&self) -> u32 {
        self.x_end.abs_diff(self.x_start)
    }

    /// Spans produced by the traversal are never empty.
    pub fn is_empty(&self) -> bool {
        self.x_end <= self.x_start
    }
}

/// `(⌊n / d⌋, n mod d)` for `d > 0`. Quotients of magnitude below 4 are found by subtraction.
#[inline]
fn div_mod_floor(n: i64, d: i64) -> (i64, i64) {
    if n >= 0 && n < 4 * d {
        let (mut q, mut r) = (0, n);
        while r >= d {
            r -= d;
            q += 1;
        }
        (q, r)
    } else if n < 0 && n >= -4 * d {
        let (mut q, mut r) = (0, n);
        while r < 0 {
            r += d;
            q -= 1;
        }
        (q, r)
    } else {
        let q = n.checked_div_euclid(d).unwrap_or(0);
        (q, n.wrapping_sub(q.wrapping_mul(d)))
    }
}

/// The boundary column of one edge, stepped exactly from row to row.
///
/// `rem` is the edge's reduced value at the boundary column, kept in `[0, m)` with `m = |a|`.
#[derive(Debug, Clone, Copy)]
struct Boundary {
    /// Boundary column: first inside column (start edges) or last one (end edges); unclamped.
    x: i64,
    rem: i64,
    m: i64,
    /// Column change per row before the carry, and remainder change per row.
    step: i64,
    rem_step: i64,
    /// Column change of the carry: −1 for start edges, +1 for end edges.
    carry: i64,
}

impl Boundary {
    /// For edge coefficients `a ≠ 0`, `b` and value `k` at `(x0, row)`.
    fn new(a: i64, b: i64, k: i64, x0: i64) -> Self {
        let m = a.abs();
        let (q, rem) = div_mod_floor(k, m);
        let (step, rem_step) = div_mod_floor(b, m);
        if a > 0 {
            // First x with k + a·(x − x0) ≥ 0; moving one column left subtracts m.
            Boundary {
                x: x0 - q,
                rem,
                m,
                step: -step,
                rem_step,
                carry: -1,
            }
        } else {
            // Last x with k − m·(x − x0) ≥ 0; moving one column right subtracts m.
            Boundary {
                x: x0 + q,
                rem,
                m,
                step,
                rem_step,
                carry: 1,
            }
        }
    }

    /// Moves to the next row: the value at the old column grows by `b`.
    #[inline(always)]
    fn advance(&mut self) {
        self.x += self.step;
        self.rem += self.rem_step;
        if self.rem >= self.m {
            self.rem -= self.m;
            self.x += self.carry;
        }
    }
}

/// The pixel rectangle a triangle is traversed over: its pixel bounding box clipped to a target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Region {
    /// First column.
    pub x0: i32,
    /// First row.
    pub y0: i32,
    /// Last column (inclusive).
    pub x1: i32,
    /// Last row (inclusive).
    pub y1: i32,
}

impl Region {
    /// The part of the triangle's pixel bounding box inside `clip`, or `None` if they don't meet.
    pub fn new(setup: &TriangleSetup, clip: &Rectangle) -> Option<Region> {
        let (bx0, by0, bx1, by1) = setup.pixel_bounds();
        let cx0 = i64::from(clip.top_left.x);
        let cy0 = i64::from(clip.top_left.y);
        let cx1 = cx0 + i64::from(clip.size.width) - 1;
        let cy1 = cy0 + i64::from(clip.size.height) - 1;
        let (x0, y0) = (bx0.max(cx0), by0.max(cy0));
        let (x1, y1) = (bx1.min(cx1), by1.min(cy1));
        // Both bounds are within ±2^23 (the vertex range) and within i32 (the clip): no truncation.
        (x0 <= x1 && y0 <= y1).then_some(Region {
            x0: x0 as i32,
            y0: y0 as i32,
            x1: x1 as i32,
            y1: y1 as i32,
        })
    }

    /// Columns in the region.
    pub fn width(&self) -> i64 {
        i64::from(self.x1) - i64::from(self.x0) + 1
    }

    /// Rows in the region.
    pub fn height(&self) -> i64 {
        i64::from(self.y1) - i64::from(self.y0) + 1
    }
}

/// Iterator over the covered spans of a triangle inside a clip rectangle, top to bottom.
#[derive(Debug, Clone)]
pub struct Spans {
    /// The first `starts` bound the span's start, the last `ends` its end.
    edges: [Boundary; 3],
    starts: usize,
    ends: usize,
    /// A horizontal crossing edge: `(b, value in the current row)`; the row is in iff value ≥ 0.
    horizontal: Option<(i64, i64)>,
    x0: i64,
    x1: i64,
    y: i64,
    y1: i64,
}

impl Spans {
    /// Spans of `setup` inside `region`.
    pub fn new(setup: &TriangleSetup, region: Region) -> Spans {
        let (x0, y0) = (i64::from(region.x0), i64::from(region.y0));
        let (x1, y1) = (i64::from(region.x1), i64::from(region.y1));
        let mut spans = Spans::empty();
        let (w, h) = (x1 - x0, y1 - y0);
        for e in &setup.edges {
            // The edge's value at the region's top-left pixel and its range over the region.
            let (k, min, max) = if e.narrow {
                // |a|, |b| < 2^30 and |x0|, |y0|, w, h < 2^24: well inside i64.
                let k = e.a * x0 + e.b * y0 + e.k as i64;
                let (da, db) = (e.a * w, e.b * h);
                let min = k + da.min(0) + db.min(0);
                (k, i128::from(min), i128::from(k + da.max(0) + db.max(0)))
            } else {
                let k = e.value_at(x0, y0);
                let (da, db) = (dot2(e.a, w, 0, 0, false), dot2(e.b, h, 0, 0, false));
                (
                    k as i64,
                    k + da.min(0) + db.min(0),
                    k + da.max(0) + db.max(0),
                )
            };
            if max < 0 {
                // No pixel of the region is inside this edge.
                return Spans::empty();
            }
            if min >= 0 {
                continue;
            }
            // The edge crosses the region, so |k| ≤ |a|·w + |b|·h < 2^58: the i64 above is exact.
            // Start edges fill `edges` from the front, end edges from the back.
            let slot = match e.a {
                0 => {
                    spans.horizontal = Some((e.b, k));
                    continue;
                }
                a if a > 0 => {
                    spans.starts += 1;
                    spans.starts - 1
                }
                _ => {
                    spans.ends += 1;
                    3 - spans.ends
                }
            };
            if let Some(slot) = spans.edges.get_mut(slot) {
                *slot = Boundary::new(e.a, e.b, k, x0);
            }
        }
        spans.x0 = x0;
        spans.x1 = x1;
        spans.y = y0;
        spans.y1 = y1;
        spans
    }

    /// Spans of the triangle `v` inside `clip` (empty for degenerate triangles).
    pub fn of_triangle(v: [(Coord, Coord); 3], clip: &Rectangle) -> Spans {
        // By reference: moving the setup out of the `Option` would copy it.
        let setup = TriangleSetup::new(v);
        setup
            .as_ref()
            .and_then(|s| Region::new(s, clip).map(|r| Spans::new(s, r)))
            .unwrap_or_else(Spans::empty)
    }

    /// An iterator with no spans.
    pub fn empty() -> Spans {
        let none = Boundary {
            x: 0,
            rem: 0,
            m: 1,
            step: 0,
            rem_step: 0,
            carry: 1,
        };
        Spans {
            edges: [none; 3],
            starts: 0,
            ends: 0,
            horizontal: None,
            x0: 0,
            x1: -1,
            y: 1,
            y1: 0,
        }
    }
}

impl Iterator for Spans {
    type Item = Span;

    #[inline]
    fn next(&mut self) -> Option<Span> {
        while self.y <= self.y1 {
            let (mut start, mut end) = (self.x0, self.x1);
            let (starts, ends) = (self.starts, self.ends);
            for e in self.edges.iter_mut().take(starts) {
                start = start.max(e.x);
                e.advance();
            }
            for e in self.edges.iter_mut().skip(3 - ends) {
                end = end.min(e.x);
                e.advance();
            }
            if let Some((b, k)) = &mut self.horizontal {
                if *k < 0 {
                    end = start - 1;
                }
                *k += *b;
            }
            let y = self.y;
            self.y += 1;
            if start <= end {
                // All three values lie inside the region, which lies inside i32.
                return Some(Span {
                    y: y as i32,
                    x_start: start as i32,
                    x_end: (end + 1) as i32,
                });
            }
        }
        None
    }
}

/// Calls `f(y, x_start, x_end)` for every covered span of the triangle `v` inside `clip`
/// (`x_end` exclusive), top to bottom. Degenerate triangles produce no spans.
pub fn for_each_span(v: [(Coord, Coord); 3], clip: Rectangle, mut f: impl FnMut(i32, i32, i32)) {
    for s in Spans::of_triangle(v, &clip) {
        f(s.y, s.x_start, s.x_end);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::prelude::*;

    fn brute(v: [(Coord, Coord); 3], clip: &Rectangle) -> [[bool; 40]; 40] {
        let mut m = [[false; 40]; 40];
        if let Some(s) = TriangleSetup::new(v) {
            for (j, row) in m.iter_mut().enumerate() {
                for (i, px) in row.iter_mut().enumerate() {
                    let p = Point::new(i as i32 - 4, j as i32 - 4);
                    *px = clip.contains(p) && s.covers(p.x, p.y);
                }
            }
        }
        m
    }

    #[test]
    fn div_mod_floor_matches_euclid() {
        for d in [1i64, 2, 3, 7, 256, 1 << 33] {
            for n in [
                -9 * d - 1,
                -4 * d - 1,
                -4 * d,
                -3 * d + 1,
                -1,
                0,
                1,
                d - 1,
                d,
                4 * d - 1,
                4 * d,
                1 << 57,
                -(1 << 57),
            ] {
                assert_eq!(
                    div_mod_floor(n, d),
                    (n.div_euclid(d), n.rem_euclid(d)),
                    "{n} / {d}"
                );
            }
        }
    }

    #[test]
    fn spans_match_per_pixel_edge_tests() {
        // Per-pixel evaluation of the same edge functions: checks the walking, not the rule.
        let clip = Rectangle::new(Point::new(-2, -1), Size::new(30, 29));
        let mut seed = 0x1234_5678_9abc_def0_u64;
        let mut rnd = |range: i32| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % (2 * range as u64 + 1)) as i32 - range
        };
        for _ in 0..3000 {
            let scale = [1, 16, 256][rnd(1).unsigned_abs() as usize + 1];
            let v = [(); 3].map(|_| {
                (
                    Coord::from_bits(rnd(20 * 256 / scale) * scale + 12 * 256),
                    Coord::from_bits(rnd(20 * 256 / scale) * scale + 12 * 256),
                )
            });
            let mut got = [[false; 40]; 40];
            for_each_span(v, clip, |y, x0, x1| {
                assert!(x0 < x1);
                for x in x0..x1 {
                    let cell = &mut got[(y + 4) as usize][(x + 4) as usize];
                    assert!(!*cell, "pixel drawn twice");
                    *cell = true;
                }
            });
            assert_eq!(got, brute(v, &clip), "{v:?}");
        }
    }
}
