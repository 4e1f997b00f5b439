//! The walk: the exact covered spans of a triangle over a region, top to bottom.
//!
//! Each edge's reduced function `K(i, j) = a·i + b·j + k` (see [`edge`](crate::raster::edge)) is
//! `≥ 0` on one side of a boundary column per row. For an edge that bounds the span's start
//! (`a > 0`) that column is `⌈−K(0, j)/a⌉`; for one that bounds its end (`a < 0`) it is
//! `⌊K(0, j)/|a|⌋`. Both are stepped from row to row like a Bresenham line: the column moves by
//! the precomputed quotient of `b / |a|`, the remainder accumulates, and one comparison carries
//! it. So each row costs two additions and a compare per boundary, whatever the slope, and the
//! decision is exact — no rounding anywhere.
//!
//! One [`Walk`] serves every triangle: one start and one end boundary a row, switching edges at
//! the middle vertex. The set-up is the compact one ([`compact`](crate::raster::compact),
//! 32-bit, bounding boxes under 2048 px, columns in `i32`) or the general one here (any
//! [`Coord`], columns in `i64`).
//!
//! The general set-up evaluates each edge function once, exactly, at the clipped region's first
//! pixel (`i64`, or `i128` for vertices beyond about two million pixels) and bounds it over the
//! region: an edge that excludes the whole region rejects the triangle, an edge that includes
//! all of it is dropped. The edges that remain cross the region, so their values there are
//! below `|a|·W + |b|·H < 2⁵⁷` and every stepped quantity fits `i64`.
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

use core::num::NonZeroU64;
use core::ops::{Add, Sub};

use embedded_graphics::primitives::Rectangle;

use crate::fixed_point::{Coord, HALF_PIXEL, SUBPIXEL_BITS, SUBPIXEL_ONE};
use crate::raster::arith::div_rem_u64;
use crate::raster::compact::CompactTriangle;
use crate::raster::edge::{owns_centres_on, TriangleSetup};

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
    /// Number of pixels in the span (0 for an empty one, `x_end ≤ x_start`; the walks hand out
    /// none of those).
    pub fn len(&self) -> u32 {
        if self.is_empty() {
            0
        } else {
            self.x_end.abs_diff(self.x_start)
        }
    }

    /// Whether the span has no pixel (`x_end ≤ x_start`).
    pub fn is_empty(&self) -> bool {
        self.x_end <= self.x_start
    }
}

/// `(⌊n / d⌋, n mod d)` for `d > 0`, from one unsigned division of the magnitudes.
// One copy for the general set-up's few divisions.
#[inline(never)]
fn div_mod_floor(n: i64, d: i64) -> (i64, i64) {
    let d = NonZeroU64::new(d.unsigned_abs()).unwrap_or(NonZeroU64::MIN);
    let (q, r) = div_rem_u64(n.unsigned_abs(), d);
    let d = d.get();
    // |n| ≤ 2⁶³, so the negated quotient fits.
    let q = q as i64;
    match (n < 0, r) {
        (false, _) => (q, r as i64),
        (true, 0) => (q.wrapping_neg(), 0),
        (true, r) => (q.wrapping_neg().wrapping_sub(1), (d - r) as i64),
    }
}

/// The integer width boundary columns are stepped in: `i32` for the compact set-up (edge
/// coefficients below 2¹⁹), `i64` for the general one.
pub(crate) trait Width: Copy + Ord + core::fmt::Debug {
    /// The remainders' type (`[0, m)`, `m` below 2¹⁹ for `i32` and 2³⁴ for `i64`).
    type Rem: Copy
        + Ord
        + Default
        + core::fmt::Debug
        + Add<Output = Self::Rem>
        + Sub<Output = Self::Rem>;
    /// Column offset 0 (the region's first column).
    const ZERO: Self;
    /// `self + other`, wrapping (never wraps under the walk's bounds).
    fn plus(self, other: Self) -> Self;
    /// `self + 1` (`up`) or `self − 1`, wrapping.
    fn carry(self, up: bool) -> Self;
    /// The region's last column offset, below 2²⁵.
    fn from_column(column: i32) -> Self;
    /// A column offset known to lie in `[0, last]`.
    fn column(self) -> u32;
}

/// [`Width`] for a signed integer type with its unsigned remainder type.
macro_rules! width {
    ($t:ty, $rem:ty) => {
        impl Width for $t {
            type Rem = $rem;
            const ZERO: Self = 0;
            #[inline(always)]
            fn plus(self, other: Self) -> Self {
                self.wrapping_add(other)
            }
            #[inline(always)]
            fn carry(self, up: bool) -> Self {
                if up {
                    self.wrapping_add(1)
                } else {
                    self.wrapping_sub(1)
                }
            }
            #[inline(always)]
            fn from_column(column: i32) -> Self {
                column.into()
            }
            #[inline(always)]
            fn column(self) -> u32 {
                self as u32
            }
        }
    };
}

width!(i32, u32);
width!(i64, u64);

/// One boundary of the rows' spans: the first covered column (an edge with `a > 0`, a start
/// boundary) or the last one (`a < 0`, an end boundary), as an offset from the region's first
/// column.
///
/// Row to row the column moves by `⌊b / |a|⌋` towards the edge's outside and the remainder `rem`
/// (the edge's reduced value at the column, in `[0, |a|)`) grows by `b mod |a|`; a carry moves
/// it one column more (left for start boundaries, right for end ones). Exact: no rounding.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Boundary<W: Width> {
    x: W,
    rem: W::Rem,
    step: W,
    rem_step: W::Rem,
    m: W::Rem,
}

impl<W: Width> Boundary<W> {
    /// The boundary with column `x`, remainder `rem` and per-row steps, for `|a| = m`.
    #[inline(always)]
    pub(crate) fn from_parts(x: W, rem: W::Rem, step: W, rem_step: W::Rem, m: W::Rem) -> Self {
        Boundary {
            x,
            rem,
            step,
            rem_step,
            m,
        }
    }

    /// The next row's boundary; `END` for end boundaries (the carry moves right).
    #[inline(always)]
    fn advance<const END: bool>(&mut self) {
        // rem, rem_step < m: no overflow; columns stay within the width's bound over the region.
        self.rem = self.rem + self.rem_step;
        self.x = self.x.plus(self.step);
        if self.rem >= self.m {
            self.rem = self.rem - self.m;
            self.x = self.x.carry(END);
        }
    }
}

/// The walk of a triangle over a region: the exact covered spans, top to bottom.
///
/// One start and one end boundary bound every row. The other side's chain of edges has one edge,
/// or two that meet at its middle vertex: above that vertex's row the upper edge binds, from its
/// row on the lower one (convexity: the lines cross only at the vertex, and the exact column
/// rounding preserves their order; in the row through the vertex both give the same column, as
/// both are left edges or both are not). So the rows come in two stretches, each with two fixed
/// boundaries and no per-row test for the switch. Horizontal edges only limit the rows.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Walk<W: Width> {
    /// The current row's start and end boundaries …
    left: Boundary<W>,
    right: Boundary<W>,
    /// … and the one that replaces the start (`next_left`) or end boundary at row offset
    /// `switch` (at most `rows`).
    next: Boundary<W>,
    next_left: bool,
    switch: u32,
    /// First column and row of the region.
    x0: i32,
    y0: i32,
    /// Last column offset (width − 1) and number of rows.
    last: i32,
    rows: u32,
    /// The next row to walk, as an offset from `y0`.
    row: u32,
}

impl<W: Width> Walk<W> {
    /// A walk with no rows.
    pub(crate) fn empty() -> Self {
        let none = Boundary::from_parts(
            W::ZERO,
            W::Rem::default(),
            W::ZERO,
            W::Rem::default(),
            W::Rem::default(),
        );
        Walk::new((none, none), (none, false, 0), (0, 0), -1, (0, 0))
    }

    /// The walk of row offsets `first .. rows` from row `y0` and of columns `x0 ..= x0 + last`,
    /// starting with the boundaries `left` and `right` of row offset `first`; at row offset
    /// `switch` (if below `rows`) `next` replaces the start boundary (`next_left`) or the end
    /// one.
    #[inline(always)]
    pub(crate) fn new(
        (left, right): (Boundary<W>, Boundary<W>),
        (next, next_left, switch): (Boundary<W>, bool, u32),
        (x0, y0): (i32, i32),
        last: i32,
        (first, rows): (u32, u32),
    ) -> Self {
        let mut walk = Walk {
            left,
            right,
            next,
            next_left,
            switch: switch.min(rows),
            x0,
            y0,
            last,
            rows,
            row: first,
        };
        // From `switch` on, the walk has taken `next` (the invariant `fold` relies on).
        if walk.switch <= walk.row {
            walk.take_next();
        }
        walk
    }

    /// The span of the current row between the boundaries, clipped to the region, with its
    /// first column's offset from the region's first column.
    #[inline(always)]
    fn span(&self) -> Option<(Span, u32)> {
        let start = self.left.x.max(W::ZERO);
        let end = self.right.x.min(W::from_column(self.last));
        // 0 ≤ start ≤ end ≤ last < 2²⁵: the offsets fit.
        (start <= end).then(|| {
            let (start, end) = (start.column(), end.column());
            let x_start = self.x0.wrapping_add(start as i32);
            let span = Span {
                y: self.y0.wrapping_add(self.row as i32),
                x_start,
                x_end: self.x0.wrapping_add(end as i32).wrapping_add(1),
            };
            (span, start)
        })
    }

    /// Moves to the next row (the switch of boundaries included).
    #[inline(always)]
    fn advance(&mut self) {
        self.row += 1;
        self.left.advance::<false>();
        self.right.advance::<true>();
        if self.row == self.switch {
            self.take_next();
        }
    }

    #[inline(always)]
    fn take_next(&mut self) {
        if self.next_left {
            self.left = self.next;
        } else {
            self.right = self.next;
        }
    }

    /// Folds `f` over the covered spans from the current row on, top to bottom, handing it each
    /// span and its offsets from the region's first pixel: columns and rows.
    #[inline(always)]
    pub(crate) fn fold<B>(self, init: B, mut f: impl FnMut(B, Span, u32, u32) -> B) -> B {
        let Walk {
            mut left,
            mut right,
            next,
            next_left,
            switch,
            x0,
            y0,
            last,
            rows,
            mut row,
        } = self;
        let mut acc = init;
        // Two stretches of rows, the second after the switch: no per-row test for it. (From
        // `switch` on, `left` and `right` already hold the second stretch's boundaries.)
        let mut stop = if row < switch { switch } else { rows };
        loop {
            while row < stop {
                let start = left.x.max(W::ZERO);
                let end = right.x.min(W::from_column(last));
                if start <= end {
                    let (start, end) = (start.column(), end.column());
                    let span = Span {
                        y: y0.wrapping_add(row as i32),
                        x_start: x0.wrapping_add(start as i32),
                        x_end: x0.wrapping_add(end as i32).wrapping_add(1),
                    };
                    acc = f(acc, span, start, row);
                }
                row += 1;
                left.advance::<false>();
                right.advance::<true>();
            }
            if stop == rows {
                break;
            }
            stop = rows;
            if next_left {
                left = next;
            } else {
                right = next;
            }
        }
        acc
    }

    /// The next covered span with its column and row offsets, or `None` after the last row.
    #[inline]
    pub(crate) fn next_span(&mut self) -> Option<(Span, u32, u32)> {
        while self.row < self.rows {
            let row = self.row;
            let span = self.span();
            self.advance();
            if let Some((span, column)) = span {
                return Some((span, column, row));
            }
        }
        None
    }
}

/// The pixel rectangle a triangle is traversed over: its pixel bounding box clipped to a target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Region {
    /// First column.
    pub(crate) x0: i32,
    /// First row.
    pub(crate) y0: i32,
    /// Last column (inclusive).
    pub(crate) x1: i32,
    /// Last row (inclusive).
    pub(crate) y1: i32,
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
        // The edge's value at the region's top-left pixel (inside the bounding box, so the
        // products of a narrow triangle fit i64) and its range over the region: |a|·w and
        // |b|·h are below 2³²·2²⁴. An edge that crosses the region has |k| below their sum;
        // clamping the others keeps their sign and every sum here in i64.
        let k = e.reduced(e.exact_at(x0, y0, setup.narrow));
        let k = k.clamp(-(1 << 60), 1 << 60) as i64;
        let (da, db) = (e.a * w, e.b * h);
        let min = k + da.min(0) + db.min(0);
        let max = k + da.max(0) + db.max(0);
        if max < 0 {
            return false;
        }
        *out = if min < 0 {
            // The edge crosses the region, so |k| ≤ |a|·w + |b|·h < 2⁵⁷: not clamped.
            Crossing::Cross { a: e.a, b: e.b, k }
        } else {
            Crossing::Inside
        };
    }
    true
}

/// The boundary of the general set-up for edge coefficients `a ≠ 0`, `b` and reduced value `k`
/// at the region's first column: columns stay below 2⁵⁹ over the region (the crossing edges'
/// values there are below 2⁵⁸), remainders below 2³⁴.
fn general_boundary(a: i64, b: i64, k: i64) -> Boundary<i64> {
    let m = a.abs();
    let (q, rem) = div_mod_floor(k, m);
    let (step, rem_step) = div_mod_floor(b, m);
    // Remainders in [0, m): non-negative. A start boundary (a > 0) is the first x with
    // k + a·x ≥ 0, and moving one column left subtracts m; an end boundary the last x with
    // k − m·x ≥ 0, and moving one column right subtracts m.
    let toward_inside = |v: i64| if a > 0 { v.wrapping_neg() } else { v };
    Boundary::from_parts(
        toward_inside(q),
        rem as u64,
        toward_inside(step),
        rem_step as u64,
        m as u64,
    )
}

/// A boundary that never limits the span: far left (start) or far right (end) of any region.
const fn open_boundary(end: bool) -> Boundary<i64> {
    Boundary {
        x: if end { 1 << 40 } else { -(1 << 40) },
        rem: 0,
        step: 0,
        rem_step: 0,
        m: 1,
    }
}

/// The walk of `setup` (any [`Coord`] vertices) over `region`, columns in `i64` (edges of the
/// general set-up can be near horizontal far off-screen; its triangles' spans are long, so the
/// width costs little).
// One copy for all callers; everything it calls is inlined into it.
#[inline(never)]
pub(crate) fn general_walk(setup: &TriangleSetup, region: &Region) -> Walk<i64> {
    // Open boundaries, not `Walk::empty`'s zeroed ones (a call to clear memory on Cortex-M).
    let open = (open_boundary(false), open_boundary(true));
    let no_rows = Walk::new(open, (open.0, true, 0), (0, 0), -1, (0, 0));
    let crossings = &mut [Crossing::Inside; 3];
    if !classify(setup, region, crossings) {
        return no_rows;
    }
    let row0 = i64::from(region.y0);
    let (mut y0, mut y1) = (row0, i64::from(region.y1));
    // Horizontal edges limit the rows: `b·(j − row0) + k ≥ 0`.
    for c in crossings.iter() {
        if let Crossing::Cross { a: 0, b, k } = *c {
            if owns_centres_on(0, b) {
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
        return no_rows;
    }
    // Each side's crossing edges (a > 0 bound the start, a < 0 the end): none, one, or two
    // that meet at that side's middle vertex; above its row the upper edge binds, from its row
    // on the lower one.
    let rows = y1 - row0 + 1;
    let mut first = [None; 2];
    let (mut next, mut next_left, mut switch) = (None, true, rows);
    for (side, first) in first.iter_mut().enumerate() {
        let start = side == 0;
        let mut found = [3usize; 2];
        let mut n = 0;
        for (k, c) in crossings.iter().enumerate() {
            if let Crossing::Cross { a, .. } = *c {
                if a != 0 && (a > 0) == start {
                    if let Some(slot) = found.get_mut(n) {
                        *slot = k;
                    }
                    n += 1;
                }
            }
        }
        let [p, q] = found;
        if q == 3 {
            *first = Some((p, y0));
            continue;
        }
        // The shared vertex is the one neither edge is opposite; `edges[p]` runs to the vertex
        // opposite `edges[q]`, and is the upper edge if that one is above.
        let vertex_y = |k: usize| {
            setup
                .order
                .get(k)
                .and_then(|&v| setup.vertices.get(v))
                .map_or(0, |v| v.1)
        };
        let (upper, lower) = if vertex_y(q) < vertex_y(p) {
            (p, q)
        } else {
            (q, p)
        };
        // First row whose centre (256·j + 128) is not above the shared vertex.
        let row = (vertex_y(3 - p - q) - HALF_PIXEL + SUBPIXEL_ONE - 1) >> SUBPIXEL_BITS;
        if row <= y0 {
            *first = Some((lower, y0));
        } else {
            *first = Some((upper, y0));
            if row <= y1 {
                (next, next_left, switch) = (Some((lower, row)), start, row - row0);
            }
        }
    }
    // The boundary of edge k from row `row` on; open (never limiting) for none.
    let boundary = |edge: Option<(usize, i64)>, end: bool| match edge {
        Some((k, row)) => match crossings.get(k) {
            Some(&Crossing::Cross { a, b, k }) => general_boundary(a, b, k + b * (row - row0)),
            _ => open_boundary(end),
        },
        None => open_boundary(end),
    };
    let [left, right] = first;
    // Within the region: rows and columns below 2²⁵.
    Walk::new(
        (boundary(left, false), boundary(right, true)),
        (boundary(next, !next_left), next_left, switch as u32),
        (region.x0, region.y0),
        region.x1 - region.x0,
        ((y0 - row0) as u32, rows as u32),
    )
}

/// Iterator over the covered spans of a triangle inside a clip rectangle, top to bottom: the
/// walk of the compact set-up (bounding boxes under 2048 px) or of the general one.
#[derive(Debug, Clone)]
pub struct Spans {
    walk: EitherWalk,
}

/// The walk of the compact set-up (columns in `i32`) or of the general one (`i64`).
#[derive(Debug, Clone, Copy)]
enum EitherWalk {
    Compact(Walk<i32>),
    General(Walk<i64>),
}

impl Spans {
    /// Spans of `setup` inside `region`.
    #[inline(always)]
    pub(crate) fn new(setup: &TriangleSetup, region: Region) -> Spans {
        Spans {
            walk: EitherWalk::General(general_walk(setup, &region)),
        }
    }

    /// The spans of a compact triangle.
    #[inline(always)]
    pub(crate) fn compact(walk: Walk<i32>) -> Spans {
        Spans {
            walk: EitherWalk::Compact(walk),
        }
    }

    /// Spans of the triangle `v` inside `clip` (empty for degenerate triangles).
    #[inline(always)]
    pub fn of_triangle(v: [(Coord, Coord); 3], clip: &Rectangle) -> Spans {
        match CompactTriangle::new(v, clip) {
            Ok(Some(triangle)) => {
                if let Ok(walk) = triangle.walk() {
                    return Spans::compact(walk);
                }
            }
            Ok(None) => return Spans::empty(),
            Err(_) => {}
        }
        Spans::general(v, clip)
    }

    /// [`of_triangle`](Self::of_triangle) through the general set-up, out of line: the
    /// compact set-up's spans then start in fewer instructions.
    #[inline(never)]
    fn general(v: [(Coord, Coord); 3], clip: &Rectangle) -> Spans {
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
            walk: EitherWalk::Compact(Walk::empty()),
        }
    }

    /// Whether the columns are stepped in `i32`: the walk of the compact set-up (bounding boxes
    /// under 2048 px); the general one steps them in `i64`.
    pub fn is_narrow(&self) -> bool {
        matches!(self.walk, EitherWalk::Compact(_))
    }
}

impl Iterator for Spans {
    type Item = Span;

    #[inline]
    fn next(&mut self) -> Option<Span> {
        match &mut self.walk {
            EitherWalk::Compact(w) => w.next_span(),
            EitherWalk::General(w) => w.next_span(),
        }
        .map(|(span, _, _)| span)
    }

    /// One dispatch per triangle; the walk's state then lives in registers.
    #[inline]
    fn fold<B, F: FnMut(B, Span) -> B>(self, init: B, mut f: F) -> B {
        match self.walk {
            EitherWalk::Compact(w) => w.fold(init, |acc, span, _, _| f(acc, span)),
            EitherWalk::General(w) => fold_general(w, init, f),
        }
    }
}

/// The general walk, out of line: its frame stays off the common path's stack.
#[inline(never)]
#[cold]
fn fold_general<B, F: FnMut(B, Span) -> B>(w: Walk<i64>, init: B, mut f: F) -> B {
    w.fold(init, |acc, span, _, _| f(acc, span))
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

    /// A span with its end before its start has no pixels (it used to report the distance).
    #[test]
    fn empty_spans_have_no_length() {
        let span = |x_start, x_end| Span {
            y: 0,
            x_start,
            x_end,
        };
        assert_eq!(span(5, 3).len(), 0);
        assert!(span(5, 3).is_empty() && span(4, 4).is_empty());
        assert_eq!(span(-3, 4).len(), 7);
        assert_eq!(span(i32::MIN, i32::MAX).len(), u32::MAX);
    }
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

    /// Both walks — the compact set-up's (`i32`) and the general one's (`i64`) — and both ways
    /// of consuming them (`fold` and `next`) against per-pixel edge tests, over triangles from
    /// sub-pixel size to far beyond the clip, including near-horizontal slivers through it whose
    /// columns leave the `i32` range.
    #[test]
    fn every_walk_matches_per_pixel_edge_tests() {
        let clip = Rectangle::new(Point::new(-3, -2), Size::new(31, 29));
        let mut next = crate::random(0x0f1e_2d3c_4b5a_6978_u64);
        let mut rnd = |range: i64| (next() % (2 * range as u64 + 1)) as i64 - range;
        let (mut general, mut beyond_i32, mut compact) = (0, 0, 0);
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
            let brute: heapless::Vec<Span, 64> = (clip.top_left.y..clip.top_left.y + 29)
                .filter_map(|y| {
                    let xs =
                        (clip.top_left.x..clip.top_left.x + 31).filter(|&x| setup.covers(x, y));
                    let (first, count) = xs.fold((None, 0), |(f, n), x| (f.or(Some(x)), n + 1));
                    first.map(|x_start| Span {
                        y,
                        x_start,
                        x_end: x_start + count,
                    })
                })
                .collect();
            let collect = |spans: Spans| -> heapless::Vec<Span, 64> { spans.collect() };
            let fold = |spans: Spans| {
                spans.fold(heapless::Vec::<Span, 64>::new(), |mut all, s| {
                    assert!(all.push(s).is_ok());
                    all
                })
            };
            let walk = Spans::new(&setup, region);
            assert_eq!(collect(walk.clone()), brute, "general next {v:?}");
            assert_eq!(fold(walk.clone()), brute, "general fold {v:?}");
            assert!(!walk.is_narrow());
            general += 1;
            // An edge whose boundary column reaches 2³⁰ or more from the region, with spans in
            // the clip.
            let steep = setup.edges.iter().any(|e| {
                let k = e.value_at(region.x0.into(), region.y0.into());
                let reach = k.abs() + i128::from(e.b.abs()) * i128::from(region.height());
                e.a != 0 && reach / i128::from(e.a.abs()) >= 1 << 30
            });
            if steep && !brute.is_empty() {
                beyond_i32 += 1;
            }
            if let Ok(Some(triangle)) = CompactTriangle::new(v, &clip) {
                let walk = Spans::compact(triangle.walk().expect("a compact walk"));
                assert_eq!(collect(walk.clone()), brute, "compact next {v:?}");
                assert_eq!(fold(walk), brute, "compact fold {v:?}");
                compact += 1;
            }
            // `brute` makes each row's covered pixels one run: check that they are.
            for s in &brute {
                for x in s.x_start..s.x_end {
                    assert!(setup.covers(x, s.y), "{v:?} ({x}, {})", s.y);
                }
            }
        }
        assert!(
            general > 10_000 && beyond_i32 > 500 && compact > 1_000,
            "general {general}, beyond i32 {beyond_i32}, compact {compact}"
        );
    }

    #[test]
    fn spans_match_per_pixel_edge_tests() {
        // Per-pixel evaluation of the same edge functions: checks the walking, not the rule.
        let clip = Rectangle::new(Point::new(-2, -1), Size::new(30, 29));
        let mut next = crate::random(0x1234_5678_9abc_def0_u64);
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
