//! Span traversal: exact covered spans per row, by stepping each edge's boundary column.
//!
//! Each edge's reduced function `K(i, j) = a·i + b·j + k` (see [`edge`](crate::raster::edge)) is `≥ 0`
//! on one side of a boundary column per row. For an edge that bounds the span's start (`a > 0`)
//! that column is `⌈−K(0, j)/a⌉`; for one that bounds its end (`a < 0`) it is `⌊K(0, j)/|a|⌋`.
//! Both are stepped from row to row like a Bresenham line: the column moves by the precomputed
//! quotient of `b / |a|`, the remainder accumulates, and one comparison carries it. So each row
//! costs two additions and a compare per edge, whatever the slope, and the decision is exact —
//! no rounding anywhere. Quotients below 4 are found by subtraction, so small triangles need no
//! division at all (Cortex-M0 has no divider).
//!
//! Of the edges that bound a row's start, only the tighter one is stepped: above the middle vertex
//! of that side it is the upper edge, below it the lower one (see `NarrowSpans`), so a row costs
//! two boundary steps in `i32`. Regions where a boundary column would leave ±2³⁰ (near-horizontal
//! edges of far off-screen triangles) step every crossing edge in `i64` instead. Small regions
//! (small triangles, up to about 8×6 pixels) skip the boundary set-up, whose divisions and edge
//! chains cost more than testing their few pixels: each pixel's edge values are stepped by one
//! addition per edge (`SmallSpans`).
//!
//! Edge functions are first tested at the corners of the clipped region: an edge that excludes
//! the whole region rejects the triangle, an edge that includes all of it is dropped. The edges
//! that remain cross the region, so their values there are below `|a|·(W+2) + |b|·H < 2^58` and
//! every stepped quantity fits `i64`.
//!
//! ```
//! use embedded_graphics::{prelude::*, primitives::Rectangle};
//! use embedded_raster::{raster::for_each_span, Coord};
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

use crate::fixed_point::{Coord, HALF_PIXEL, SUBPIXEL_BITS, SUBPIXEL_ONE};
use crate::raster::edge::{dot2, TriangleSetup};

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
///
/// Three walkers give the same exact spans: the common one steps one start and one end boundary
/// per row in `i32` (switching edges at the middle vertex); triangles whose boundaries leave the
/// `i32` range over the region (far off-screen slivers) step every crossing edge in `i64`; small
/// regions test their pixels one by one, with no boundary set-up.
#[derive(Debug, Clone)]
pub struct Spans {
    walk: Walk,
}

#[derive(Debug, Clone)]
enum Walk {
    Narrow(NarrowSpans),
    Wide(WideSpans),
    Small(SmallSpans),
}

/// How one edge function meets the region.
#[derive(Debug, Clone, Copy)]
enum Crossing {
    /// Every pixel of the region is inside the edge.
    Inside,
    /// The edge crosses the region: coefficients and value `k` at the region's top-left pixel.
    Cross { a: i64, b: i64, k: i64 },
}

/// Classifies the edges of `setup` against `region` into `out`; `false` if one excludes all of
/// it (nothing to draw).
// Written through `out`: returning the array (in an `Option` or not) costs a copy of it.
#[inline(always)]
fn classify(setup: &TriangleSetup, region: &Region, out: &mut [Crossing; 3]) -> bool {
    let (x0, y0) = (i64::from(region.x0), i64::from(region.y0));
    let (w, h) = (region.width() - 1, region.height() - 1);
    for (e, out) in setup.edges.iter().zip(out.iter_mut()) {
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
            return false;
        }
        *out = if min < 0 {
            // The edge crosses the region, so |k| ≤ |a|·w + |b|·h < 2^58: the i64 above is exact.
            Crossing::Cross { a: e.a, b: e.b, k }
        } else {
            Crossing::Inside
        };
    }
    true
}

impl Spans {
    /// Spans of `setup` inside `region`.
    // One copy for all callers; everything it calls is inlined into it, so the walker is built
    // in place in the returned value rather than copied there.
    #[inline(never)]
    pub fn new(setup: &TriangleSetup, region: Region) -> Spans {
        let crossings = &mut [Crossing::Inside; 3];
        if !classify(setup, &region, crossings) {
            return Spans::empty();
        }
        if region.height() * (region.width() - 2) <= SMALL_AREA {
            return Spans {
                walk: Walk::Small(SmallSpans::new(&region, crossings)),
            };
        }
        let walk = match NarrowSpans::new(setup, &region, crossings) {
            Some(narrow) => Walk::Narrow(narrow),
            None => Walk::Wide(WideSpans::new(&region, crossings)),
        };
        Spans { walk }
    }

    /// Spans of the triangle `v` inside `clip` (empty for degenerate triangles).
    #[inline(always)]
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
        Spans {
            walk: Walk::Narrow(NarrowSpans::empty()),
        }
    }

    /// Whether the spans are stepped in `i32` (the fast walker for regions wider than a few
    /// pixels).
    pub fn is_narrow(&self) -> bool {
        matches!(self.walk, Walk::Narrow(_))
    }

    /// Whether the region is narrow enough to be walked pixel by pixel.
    pub fn is_small(&self) -> bool {
        matches!(self.walk, Walk::Small(_))
    }
}

impl Iterator for Spans {
    type Item = Span;

    #[inline]
    fn next(&mut self) -> Option<Span> {
        match &mut self.walk {
            Walk::Narrow(n) => n.next(),
            Walk::Wide(w) => w.next(),
            Walk::Small(t) => t.next(),
        }
    }

    /// One dispatch per triangle; the walker's state then lives in registers.
    #[inline]
    fn fold<B, F: FnMut(B, Span) -> B>(self, init: B, f: F) -> B {
        match self.walk {
            Walk::Narrow(n) => n.fold(init, f),
            Walk::Wide(w) => fold_wide(w, init, f),
            Walk::Small(t) => t.fold(init, f),
        }
    }
}

/// The rare wide walk, out of line: its frame stays off the common path's stack.
#[inline(never)]
#[cold]
fn fold_wide<B, F: FnMut(B, Span) -> B>(w: WideSpans, init: B, f: F) -> B {
    w.fold(init, f)
}

/// A boundary column stepped in `i32`: the [`Boundary`] of one edge whose columns stay within
/// ±2³⁰ over the rows it is used for.
#[derive(Debug, Clone, Copy)]
struct Boundary32 {
    x: i32,
    rem: i32,
    m: i32,
    step: i32,
    rem_step: i32,
}

impl Boundary32 {
    /// A boundary that never limits the span: far left for starts, far right for ends.
    const fn open(x: i32) -> Self {
        Boundary32 {
            x,
            rem: 0,
            m: 1,
            step: 0,
            rem_step: 0,
        }
    }

    /// The `i64` boundary, if it and every column it reaches in the next `rows` rows fit.
    fn narrow(b: &Boundary, rows: i64) -> Option<Self> {
        const LIMIT: i64 = 1 << 30;
        // Each row moves the column by `step` and at most one carry.
        let reach = b
            .step
            .checked_abs()?
            .checked_add(1)?
            .checked_mul(rows.checked_add(1)?)?
            .checked_add(b.x.checked_abs()?)?;
        (b.m < LIMIT && reach < LIMIT).then_some(Boundary32 {
            x: b.x as i32,
            rem: b.rem as i32,
            m: b.m as i32,
            step: b.step as i32,
            rem_step: b.rem_step as i32,
        })
    }

    /// Moves to the next row; `carry` is −1 for start edges and +1 for end edges.
    #[inline(always)]
    fn advance(&mut self, carry: i32) {
        self.x += self.step;
        self.rem += self.rem_step;
        if self.rem >= self.m {
            self.rem -= self.m;
            self.x += carry;
        }
    }
}

/// Row at which nothing switches.
const NEVER: i32 = i32::MAX;

/// The fast walker: one start and one end boundary per row.
///
/// The start edges (`a > 0`) of a triangle form a chain from its top vertex to its bottom vertex
/// through at most one middle vertex `V`, and so do the end edges. Above `V` the upper edge of
/// the chain is the tighter one (convexity: the lines cross only at `V`, and the real boundary of
/// the upper edge lies strictly inside the lower one's there, which the exact column rounding
/// preserves), below `V` the lower one. In the row through `V` both give the same column: both
/// are left edges (start) or both are not (end), so their tie rules agree. So each row steps just
/// the edge that bounds it, and the lower edge takes over in the first row whose centre is not
/// above `V`. Horizontal edges only limit the rows.
#[derive(Debug, Clone)]
struct NarrowSpans {
    start: Boundary32,
    end: Boundary32,
    /// The lower edge of each chain and the row it takes over in ([`NEVER`] if none).
    next_start: Boundary32,
    next_end: Boundary32,
    start_switch: i32,
    end_switch: i32,
    /// The first row at which an edge changes: `min(start_switch, end_switch)`.
    switch: i32,
    x0: i32,
    x1: i32,
    y: i32,
    y1: i32,
}

/// One chain (start or end edges) of a triangle over a region, before conversion to `i32`.
struct Chain {
    /// Boundary in the first row, and the lower edge with its first row (if it takes over).
    first: Option<Boundary>,
    next: Option<(Boundary, i64)>,
}

impl NarrowSpans {
    fn empty() -> Self {
        NarrowSpans {
            start: Boundary32::open(0),
            end: Boundary32::open(0),
            next_start: Boundary32::open(0),
            next_end: Boundary32::open(0),
            start_switch: NEVER,
            end_switch: NEVER,
            switch: NEVER,
            x0: 0,
            x1: -1,
            y: 1,
            y1: 0,
        }
    }

    /// The walker for the edges `crossings` of `setup` over `region`, or `None` if a boundary
    /// leaves the `i32` range.
    #[inline(always)]
    fn new(setup: &TriangleSetup, region: &Region, crossings: &[Crossing; 3]) -> Option<Self> {
        let (x0, mut y0) = (i64::from(region.x0), i64::from(region.y0));
        let mut y1 = i64::from(region.y1);
        let row0 = y0;
        // Horizontal edges limit the rows: `b·(j − row0) + k ≥ 0`.
        for c in crossings {
            if let Crossing::Cross { a: 0, b, k } = *c {
                if b > 0 {
                    // First row with b·d + k ≥ 0: d = ⌈−k/b⌉.
                    let (q, r) = div_mod_floor(-k, b);
                    y0 = y0.max(row0 + q + i64::from(r > 0));
                } else if b < 0 {
                    // Last row with k − |b|·d ≥ 0: d = ⌊k/|b|⌋.
                    y1 = y1.min(row0 + div_mod_floor(k, -b).0);
                }
            }
        }
        if y0 > y1 {
            return Some(Self::empty());
        }
        // The chains: edges with a > 0 bound starts, a < 0 ends.
        let chain = |start: bool| Self::chain(setup, crossings, start, (x0, row0), (y0, y1));
        let rows = y1 - y0 + 1;
        let convert = |c: Chain, open: i32| -> Option<(Boundary32, Boundary32, i32)> {
            let first = match c.first {
                Some(b) => Boundary32::narrow(&b, rows)?,
                None => Boundary32::open(open),
            };
            Some(match c.next {
                Some((b, row)) => (first, Boundary32::narrow(&b, y1 - row + 1)?, row as i32),
                None => (first, Boundary32::open(open), NEVER),
            })
        };
        // Open boundaries lie outside any region (|x| ≤ 2^31 − 1 there, within i32 here).
        let (start, next_start, start_switch) = convert(chain(true), i32::MIN)?;
        let (end, next_end, end_switch) = convert(chain(false), i32::MAX)?;
        Some(NarrowSpans {
            start,
            end,
            next_start,
            next_end,
            start_switch,
            end_switch,
            switch: start_switch.min(end_switch),
            x0: region.x0,
            x1: region.x1,
            // Within the region's rows, so within i32.
            y: y0 as i32,
            y1: y1 as i32,
        })
    }

    /// The start chain (`start`, edges with `a > 0`) or end chain of `crossings` over the rows
    /// `y0..=y1` of a region whose first column is `x0` and whose crossings are given at row `row0`.
    #[inline(always)]
    fn chain(
        setup: &TriangleSetup,
        crossings: &[Crossing; 3],
        start: bool,
        (x0, row0): (i64, i64),
        (y0, y1): (i64, i64),
    ) -> Chain {
        let mut found = [None; 2];
        let mut n = 0;
        for (i, c) in crossings.iter().enumerate() {
            if let Crossing::Cross { a, b, k } = *c {
                if a != 0 && (a > 0) == start {
                    if let Some(slot) = found.get_mut(n) {
                        *slot = Some((i, a, b, k));
                    }
                    n += 1;
                }
            }
        }
        let at = |a: i64, b: i64, k: i64, row: i64| Boundary::new(a, b, k + b * (row - row0), x0);
        match found {
            [Some((_, a, b, k)), None] => Chain {
                first: Some(at(a, b, k, y0)),
                next: None,
            },
            [Some((p, ap, bp, kp)), Some((q, aq, bq, kq))] => {
                // The shared vertex is the one neither edge is opposite; `edges[p]` runs to
                // the vertex opposite `edges[q]`, and is the upper edge if that one is above.
                let vertex = |k: usize| {
                    setup
                        .order
                        .get(k)
                        .and_then(|&v| setup.vertices.get(v))
                        .map_or(0, |v| v.1)
                };
                let vy = vertex(3 - p - q);
                let ((au, bu, ku), (al, bl, kl)) = if vertex(q) < vertex(p) {
                    ((ap, bp, kp), (aq, bq, kq))
                } else {
                    ((aq, bq, kq), (ap, bp, kp))
                };
                // First row whose centre (256·j + 128) is not above the vertex.
                let switch = (vy - HALF_PIXEL + SUBPIXEL_ONE - 1) >> SUBPIXEL_BITS;
                if switch <= y0 {
                    Chain {
                        first: Some(at(al, bl, kl, y0)),
                        next: None,
                    }
                } else if switch > y1 {
                    Chain {
                        first: Some(at(au, bu, ku, y0)),
                        next: None,
                    }
                } else {
                    Chain {
                        first: Some(at(au, bu, ku, y0)),
                        next: Some((at(al, bl, kl, switch), switch)),
                    }
                }
            }
            _ => Chain {
                first: None,
                next: None,
            },
        }
    }

    /// The span of row `y` between boundary columns `start` and `end`, clipped to `x0..=x1`.
    #[inline(always)]
    fn span(y: i32, start: i32, end: i32, x0: i32, x1: i32) -> Option<Span> {
        let (start, end) = (x0.max(start), x1.min(end));
        // `end ≤ x1 < 2^24`: no overflow.
        (start <= end).then_some(Span {
            y,
            x_start: start,
            x_end: end + 1,
        })
    }

    /// Takes over the lower edges whose row has come.
    #[cold]
    fn switch_edges(&mut self) {
        if self.y == self.start_switch {
            self.start = self.next_start;
            self.start_switch = NEVER;
        }
        if self.y == self.end_switch {
            self.end = self.next_end;
            self.end_switch = NEVER;
        }
        self.switch = self.start_switch.min(self.end_switch);
    }
}

impl Iterator for NarrowSpans {
    type Item = Span;

    /// The whole walk with its state in locals: rows in at most three stretches, each with fixed
    /// boundaries, so the row loop holds no switch test.
    #[inline(always)]
    fn fold<B, F: FnMut(B, Span) -> B>(self, init: B, mut f: F) -> B {
        let NarrowSpans {
            mut start,
            mut end,
            next_start,
            next_end,
            mut start_switch,
            mut end_switch,
            x0,
            x1,
            mut y,
            y1,
            ..
        } = self;
        let mut acc = init;
        loop {
            // Rows before the next switch (or to the last row), all with the same two edges.
            let last = start_switch.min(end_switch).saturating_sub(1).min(y1);
            while y <= last {
                let span = Self::span(y, start.x, end.x, x0, x1);
                start.advance(-1);
                end.advance(1);
                if let Some(span) = span {
                    acc = f(acc, span);
                }
                y += 1;
            }
            if y > y1 {
                return acc;
            }
            if y == start_switch {
                start = next_start;
                start_switch = NEVER;
            }
            if y == end_switch {
                end = next_end;
                end_switch = NEVER;
            }
        }
    }

    #[inline(always)]
    fn next(&mut self) -> Option<Span> {
        while self.y <= self.y1 {
            if self.y == self.switch {
                self.switch_edges();
            }
            let span = Self::span(self.y, self.start.x, self.end.x, self.x0, self.x1);
            self.start.advance(-1);
            self.end.advance(1);
            self.y += 1;
            if span.is_some() {
                return span;
            }
        }
        None
    }
}

/// Regions with `height · (width − 2)` at most this are walked pixel by pixel ([`SmallSpans`]).
///
/// Testing a pixel costs about 13 instructions on Cortex-M4 (three 64-bit edge values stepped and
/// their signs tested), the boundary walker about 430 of set-up and 35 a row, so testing is
/// cheaper while `h·(13w − 35) < 430`: `h·(w − 2) ≤ 40` follows that curve (all of an 8×6 or a
/// 4×20 region, any width of at most 2).
const SMALL_AREA: i64 = 40;

/// The walker for narrow regions (small triangles): each row's pixels are tested against the
/// crossing edges, stepped by `a` per pixel and `b` per row — no set-up beyond the edge values at
/// the region's corner, where the boundary walkers divide and build edge chains.
///
/// A row's covered pixels are contiguous (the triangle is convex), so the scan skips to the first
/// covered pixel and stops after the last.
#[derive(Debug, Clone)]
struct SmallSpans {
    /// `(a, b)` of the crossing edges and their values at `(x0, y)`; unused slots are all zero,
    /// which never excludes a pixel.
    steps: [(i64, i64); 3],
    row: [i64; 3],
    x0: i32,
    x1: i32,
    y: i32,
    y1: i32,
}

impl SmallSpans {
    fn new(region: &Region, crossings: &[Crossing; 3]) -> Self {
        let (mut steps, mut row) = ([(0, 0); 3], [0; 3]);
        let crossing = crossings.iter().filter_map(|c| match *c {
            Crossing::Cross { a, b, k } => Some(((a, b), k)),
            Crossing::Inside => None,
        });
        for ((step, value), (ab, k)) in steps.iter_mut().zip(row.iter_mut()).zip(crossing) {
            (*step, *value) = (ab, k);
        }
        SmallSpans {
            steps,
            row,
            x0: region.x0,
            x1: region.x1,
            y: region.y0,
            y1: region.y1,
        }
    }
}

impl Iterator for SmallSpans {
    type Item = Span;

    #[inline]
    fn next(&mut self) -> Option<Span> {
        // Crossing edges stay below 2^58 in magnitude over the region (see `crossings`); the
        // region's columns are within ±2^23 (the vertex range), so `x + 1` cannot overflow.
        let inside = |v: &[i64; 3]| v.iter().fold(0, |sign, &e| sign | e) >= 0;
        let steps = self.steps;
        let step = |v: &mut [i64; 3]| {
            for (value, &(a, _)) in v.iter_mut().zip(&steps) {
                *value += a;
            }
        };
        while self.y <= self.y1 {
            let mut v = self.row;
            for (value, &(_, b)) in self.row.iter_mut().zip(&steps) {
                *value += b;
            }
            let y = self.y;
            self.y += 1;
            let mut x = self.x0;
            while x <= self.x1 && !inside(&v) {
                x += 1;
                step(&mut v);
            }
            let start = x;
            while x <= self.x1 && inside(&v) {
                x += 1;
                step(&mut v);
            }
            if start < x {
                return Some(Span {
                    y,
                    x_start: start,
                    x_end: x,
                });
            }
        }
        None
    }
}

/// The general walker: every crossing edge stepped in `i64`.
#[derive(Debug, Clone)]
struct WideSpans {
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

impl WideSpans {
    #[inline(never)]
    #[cold]
    fn new(region: &Region, crossings: &[Crossing; 3]) -> Self {
        let none = Boundary {
            x: 0,
            rem: 0,
            m: 1,
            step: 0,
            rem_step: 0,
            carry: 1,
        };
        let x0 = i64::from(region.x0);
        let mut spans = WideSpans {
            edges: [none; 3],
            starts: 0,
            ends: 0,
            horizontal: None,
            x0,
            x1: i64::from(region.x1),
            y: i64::from(region.y0),
            y1: i64::from(region.y1),
        };
        for c in crossings {
            let Crossing::Cross { a, b, k } = *c else {
                continue;
            };
            // Start edges fill `edges` from the front, end edges from the back.
            let slot = match a {
                0 => {
                    spans.horizontal = Some((b, k));
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
                *slot = Boundary::new(a, b, k, x0);
            }
        }
        spans
    }
}

impl Iterator for WideSpans {
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

    /// The `i32` walker (one edge per chain and row, switching at the middle vertex) and the
    /// pixel-by-pixel walker of narrow regions against the `i64` walker that steps every crossing
    /// edge, and all against per-pixel edge tests, over triangles from sub-pixel size to far
    /// beyond the clip, including near-horizontal slivers that force the wide walker.
    #[test]
    fn narrow_and_wide_walkers_agree() {
        let clip = Rectangle::new(Point::new(-3, -2), Size::new(31, 29));
        let mut next = crate::xorshift(0x0f1e_2d3c_4b5a_6978_u64);
        let mut rnd = |range: i64| (next() % (2 * range as u64 + 1)) as i64 - range;
        let (mut narrow, mut wide, mut small) = (0, 0, 0);
        for i in 0..20_000 {
            let range = [1 << 8, 1 << 12, 1 << 16, 1 << 24, 1 << 31][i % 5];
            let c = |r: i64| {
                Coord::from_bits((r + 12 * 256).clamp(i32::MIN.into(), i32::MAX.into()) as i32)
            };
            let mut v = [(); 3].map(|_| (c(rnd(range)), c(rnd(range))));
            if i % 7 == 0 {
                // A near-horizontal edge from far left to far right through the clip.
                let y = rnd(20 * 256);
                v[0] = (c(-(1 << 31)), c(y));
                v[1] = (c(1 << 31), c(y + rnd(300)));
            }
            let Some(setup) = TriangleSetup::new(v) else {
                continue;
            };
            let Some(region) = Region::new(&setup, &clip) else {
                continue;
            };
            let spans = Spans::new(&setup, region);
            let got: heapless::Vec<Span, 64> = spans.clone().collect();
            let mut crossings = [Crossing::Inside; 3];
            let general: heapless::Vec<Span, 64> = if classify(&setup, &region, &mut crossings) {
                WideSpans::new(&region, &crossings).collect()
            } else {
                heapless::Vec::new()
            };
            assert_eq!(got, general, "{v:?}");
            let folded = spans
                .clone()
                .fold(heapless::Vec::<Span, 64>::new(), |mut all, s| {
                    assert!(all.push(s).is_ok());
                    all
                });
            assert_eq!(folded, got, "fold and next differ: {v:?}");
            if spans.is_small() {
                small += 1;
            } else if spans.is_narrow() {
                narrow += 1;
            } else {
                wide += 1;
            }
            let mut covered = 0;
            for s in &got {
                for x in s.x_start..s.x_end {
                    assert!(setup.covers(x, s.y), "{v:?} ({x}, {})", s.y);
                }
                covered += s.len();
            }
            let brute = (clip.top_left.y..clip.top_left.y + 29)
                .flat_map(|y| (clip.top_left.x..clip.top_left.x + 31).map(move |x| (x, y)))
                .filter(|&(x, y)| setup.covers(x, y))
                .count();
            assert_eq!(covered as usize, brute, "{v:?}");
        }
        assert!(
            narrow > 5_000 && wide > 20 && small > 1_000,
            "narrow {narrow}, wide {wide}, small {small}"
        );
    }

    #[test]
    fn spans_match_per_pixel_edge_tests() {
        // Per-pixel evaluation of the same edge functions: checks the walking, not the rule.
        let clip = Rectangle::new(Point::new(-2, -1), Size::new(30, 29));
        let mut next = crate::xorshift(0x1234_5678_9abc_def0_u64);
        let mut rnd = |range: i32| (next() % (2 * range as u64 + 1)) as i32 - range;
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
