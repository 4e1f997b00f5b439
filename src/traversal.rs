//! Span traversal: exact covered spans per row, found by walking the edge functions.
//!
//! For every row of the triangle's pixel bounding box (clipped to the target), each edge keeps the
//! column where its edge function changes sign. Moving to the next row adds `B` to the edge value;
//! the boundary is then walked a pixel at a time (adding or subtracting `A`) until the sign flips.
//! Walking costs a few additions per boundary pixel, so a triangle costs O(width + height) of
//! traversal work plus the span fills — there is no per-pixel edge test and no division.
//!
//! Edge functions are first tested at the corners of the clipped region in `i128`: an edge that
//! excludes the whole region rejects the triangle, an edge that includes all of it is dropped. The
//! edges that remain cross the region, so their values inside it are bounded by
//! `|A|·(W+2) + |B|·H < 2^58` and are stepped exactly in `i64`.
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

/// Which side of the span an edge bounds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Side {
    /// `a > 0`: the edge value grows to the right; it bounds the span's start.
    Left,
    /// `a < 0`: it bounds the span's end.
    Right,
    /// `a = 0`: the whole row is in or out.
    Horizontal,
}

/// One crossing edge being walked down the rows.
#[derive(Debug, Clone, Copy)]
struct WalkEdge {
    a: i64,
    b: i64,
    side: Side,
    /// Boundary column: first inside column (left) or last inside column (right).
    x: i64,
    /// Reduced edge value at `(x, current row)`.
    k: i64,
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
    edges: [WalkEdge; 3],
    count: usize,
    x0: i64,
    x1: i64,
    y: i64,
    y1: i64,
    first: bool,
}

impl Spans {
    /// Spans of `setup` inside `region`.
    pub fn new(setup: &TriangleSetup, region: Region) -> Spans {
        let (x0, y0) = (i64::from(region.x0), i64::from(region.y0));
        let (x1, y1) = (i64::from(region.x1), i64::from(region.y1));
        let mut spans = Spans {
            edges: [WalkEdge {
                a: 0,
                b: 0,
                side: Side::Horizontal,
                x: 0,
                k: 0,
            }; 3],
            count: 0,
            x0,
            x1,
            y: y0,
            y1,
            first: true,
        };
        for e in &setup.edges {
            let k00 = e.value_at(x0, y0);
            let da = dot2(e.a, x1 - x0, 0, 0, e.narrow);
            let db = dot2(e.b, y1 - y0, 0, 0, e.narrow);
            let corners = [k00, k00 + da, k00 + db, k00 + da + db];
            let min = corners.iter().copied().min().unwrap_or(0);
            let max = corners.iter().copied().max().unwrap_or(0);
            if max < 0 {
                // No pixel of the region is inside this edge.
                spans.y = y1 + 1;
                spans.count = 0;
                return spans;
            }
            if min >= 0 {
                continue;
            }
            // The edge crosses the region: |K| ≤ |a|·W + |b|·H there, well inside i64.
            let (side, x, k) = match e.a {
                a if a > 0 => (Side::Left, x0, k00),
                a if a < 0 => (Side::Right, x1, k00 + da),
                _ => (Side::Horizontal, x0, k00),
            };
            if let Some(slot) = spans.edges.get_mut(spans.count) {
                *slot = WalkEdge {
                    a: e.a,
                    b: e.b,
                    side,
                    x,
                    k: k as i64,
                };
                spans.count += 1;
            }
        }
        spans
    }

    /// Spans of the triangle `v` inside `clip` (empty for degenerate triangles).
    pub fn of_triangle(v: [(Coord, Coord); 3], clip: &Rectangle) -> Spans {
        TriangleSetup::new(v)
            .and_then(|s| Region::new(&s, clip).map(|r| Spans::new(&s, r)))
            .unwrap_or_else(Spans::empty)
    }

    /// An iterator with no spans.
    pub fn empty() -> Spans {
        let edge = WalkEdge {
            a: 0,
            b: 0,
            side: Side::Horizontal,
            x: 0,
            k: 0,
        };
        Spans {
            edges: [edge; 3],
            count: 0,
            x0: 0,
            x1: -1,
            y: 1,
            y1: 0,
            first: false,
        }
    }

    /// Walks every crossing edge to the current row; returns the covered columns `[start, end]`.
    #[inline]
    fn walk_row(&mut self) -> (i64, i64) {
        let (x0, x1) = (self.x0, self.x1);
        let advance = !self.first;
        self.first = false;
        let (mut start, mut end) = (x0, x1);
        for e in self.edges.iter_mut().take(self.count) {
            if advance {
                e.k += e.b;
            }
            match e.side {
                Side::Left => {
                    if e.k < 0 {
                        while e.k < 0 && e.x <= x1 {
                            e.x += 1;
                            e.k += e.a;
                        }
                    } else {
                        while e.x > x0 && e.k - e.a >= 0 {
                            e.x -= 1;
                            e.k -= e.a;
                        }
                    }
                    start = start.max(e.x);
                }
                Side::Right => {
                    if e.k < 0 {
                        while e.k < 0 && e.x >= x0 {
                            e.x -= 1;
                            e.k -= e.a;
                        }
                    } else {
                        while e.x < x1 && e.k + e.a >= 0 {
                            e.x += 1;
                            e.k += e.a;
                        }
                    }
                    end = end.min(e.x);
                }
                Side::Horizontal => {
                    if e.k < 0 {
                        end = x0 - 1;
                    }
                }
            }
        }
        (start, end)
    }
}

impl Iterator for Spans {
    type Item = Span;

    #[inline]
    fn next(&mut self) -> Option<Span> {
        while self.y <= self.y1 {
            let (start, end) = self.walk_row();
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
