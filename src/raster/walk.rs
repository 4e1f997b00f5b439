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
//! the middle vertex ([`Walk::assemble`]). Its columns are `i32` offsets from the region's first
//! column and its remainders `u32`, whatever the vertices: a boundary is only read in rows within
//! its edge's height, where its column lies between the edge's end points. The set-ups differ
//! only in how they find a boundary's first column: the compact one
//! (`compact.rs`, bounding boxes under 2048 px) in 32 bits, the general
//! one here (any [`Coord`]) from the edge's exact value at the boundary's first row (`i64`, or
//! `i128` for vertices beyond about two million pixels), divided once.
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

use core::convert::Infallible;
use core::num::NonZeroU64;
use core::ops::ControlFlow;

use embedded_graphics::primitives::Rectangle;

use crate::raster::arith::div_rem_u64;
use crate::raster::edge::{first_centre_from, last_centre_to, last_row, TriangleSetup};

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
fn div_mod_floor(n: i64, d: u64) -> (i64, u64) {
    let d = NonZeroU64::new(d).unwrap_or(NonZeroU64::MIN);
    let (q, r) = div_rem_u64(n.unsigned_abs(), d);
    let d = d.get();
    // |n| ≤ 2⁶³, so the negated quotient fits.
    let q = q as i64;
    match (n < 0, r) {
        (false, _) => (q, r),
        (true, 0) => (q.wrapping_neg(), 0),
        (true, r) => (q.wrapping_neg().wrapping_sub(1), d - r),
    }
}

/// One boundary of the rows' spans: the first covered column (an edge with `a > 0`, a start
/// boundary) or the last one (`a < 0`, an end boundary), as an offset from the region's first
/// column.
///
/// Row to row the column moves by `⌊b / |a|⌋` towards the edge's outside and the remainder `rem`
/// (the edge's reduced value at the column, in `[0, |a|)`) grows by `b mod |a|`; a carry moves
/// it one column more (left for start boundaries, right for end ones). Exact: no rounding.
///
/// `|a|` is below 2³² for every [`Coord`] (a difference of two raw `i32` heights), so the
/// remainders are `u32`; the carry is tested against `|a| − (b mod |a|)`, which cannot
/// overflow where `rem + (b mod |a|)` could. The column is an `i32` offset: a boundary is only
/// read in rows whose centres lie within its edge's height (see [`Walk`]), where the column
/// lies between the edge's end points, within 2²⁵ of the region.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Boundary {
    x: i32,
    rem: u32,
    step: i32,
    rem_step: u32,
    /// `|a| − rem_step`: a remainder at or above it carries.
    carry_at: u32,
}

impl Boundary {
    /// The boundary with column `x`, remainder `rem` and per-row steps, for `|a| = m`
    /// (`rem, rem_step < m`).
    #[inline(always)]
    pub(crate) fn from_parts(x: i32, rem: u32, step: i32, rem_step: u32, m: u32) -> Self {
        Boundary {
            x,
            rem,
            step,
            rem_step,
            carry_at: m.wrapping_sub(rem_step),
        }
    }

    /// The next row's boundary; `END` for end boundaries (the carry moves right).
    #[inline(always)]
    fn advance<const END: bool>(&mut self) {
        // Wrapping: past its edge's last row a boundary is no longer read.
        self.x = self.x.wrapping_add(self.step);
        if self.rem >= self.carry_at {
            // rem + rem_step − m, in [0, m).
            self.rem -= self.carry_at;
            self.x = if END {
                self.x.wrapping_add(1)
            } else {
                self.x.wrapping_sub(1)
            };
        } else {
            self.rem += self.rem_step;
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
pub(crate) struct Walk {
    /// The current row's start and end boundaries …
    left: Boundary,
    right: Boundary,
    /// … and the one that replaces the start (`next_left`) or end boundary at row offset
    /// `switch` (at most `rows`).
    next: Boundary,
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

impl Walk {
    /// A walk with no rows.
    pub(crate) fn empty() -> Self {
        let none = Boundary::from_parts(0, 0, 0, 0, 0);
        Walk::new((none, none), (none, false, 0), (0, 0), -1, (0, 0))
    }

    /// The walk of row offsets `first .. rows` from row `y0` and of columns `x0 ..= x0 + last`,
    /// starting with the boundaries `left` and `right` of row offset `first`; at row offset
    /// `switch` (if below `rows`) `next` replaces the start boundary (`next_left`) or the end
    /// one.
    #[inline(always)]
    pub(crate) fn new(
        (left, right): (Boundary, Boundary),
        (next, next_left, switch): (Boundary, bool, u32),
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

    /// The walk of an oriented triangle over the columns `origin.0 ..= origin.0 + last` and the
    /// row offsets `first .. rows` from `origin.1`. Its vertices are at heights `base + ys[k]`
    /// (sub-pixels), and `boundary(k, row)` is the boundary of the edge opposite vertex `k` at
    /// row offset `row`. The compact and the general set-up differ only in `boundary` (32-bit,
    /// or exact in `i64`/`i128`).
    ///
    /// The vertices by height: top, middle, bottom. The long edge (top to bottom, opposite the
    /// middle vertex) bounds one side of every row; the other side has the upper edge (opposite
    /// the bottom vertex) above the middle vertex's row and the lower one (opposite the top
    /// vertex) from that row on — in the row through the vertex both give the same column
    /// (convexity, and the exact column rounding). So each boundary is asked for, and read, only
    /// in rows whose centres lie within its edge's height. A horizontal upper or lower edge
    /// only limits the rows (the callers' row range).
    #[inline(always)]
    pub(crate) fn assemble<E>(
        ys: [i32; 3],
        base: i32,
        origin: (i32, i32),
        last: i32,
        (first, rows): (u32, u32),
        boundary: impl Fn(usize, u32) -> Result<Boundary, E>,
    ) -> Result<Walk, E> {
        let plan = Plan::new(ys, base, origin.1, (first, rows));
        let (pair_edge, next_edge) = (usize::from(plan.pair), usize::from(plan.next));
        let pair = boundary(pair_edge, first)?;
        let next = if next_edge == pair_edge {
            pair
        } else {
            boundary(next_edge, plan.switch.min(rows - 1))?
        };
        let single = boundary(usize::from(plan.single), first)?;
        let (left, right) = if plan.pair_left {
            (pair, single)
        } else {
            (single, pair)
        };
        Ok(Walk::new(
            (left, right),
            (next, plan.pair_left, plan.switch),
            origin,
            last,
            (first, rows),
        ))
    }

    /// The span of the current row between the boundaries, clipped to the region, with its
    /// first column's offset from the region's first column.
    #[inline(always)]
    fn span(&self) -> Option<(Span, u32)> {
        let start = self.left.x.max(0);
        let end = self.right.x.min(self.last);
        // 0 ≤ start ≤ end ≤ last < 2²⁵: the offsets fit.
        (start <= end).then(|| {
            let span = Span {
                y: self.y0.wrapping_add(self.row as i32),
                x_start: self.x0.wrapping_add(start),
                x_end: self.x0.wrapping_add(end).wrapping_add(1),
            };
            (span, start as u32)
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
        let folded = self.try_fold(
            init,
            #[inline(always)]
            |acc, span, column, row| {
                ControlFlow::<Infallible, B>::Continue(f(acc, span, column, row))
            },
        );
        match folded {
            ControlFlow::Continue(acc) => acc,
            ControlFlow::Break(never) => match never {},
        }
    }

    /// [`fold`](Self::fold) that ends at the first `Break` of `f`, the rows after it not walked.
    #[inline(always)]
    pub(crate) fn try_fold<B, R>(
        self,
        init: B,
        mut f: impl FnMut(B, Span, u32, u32) -> ControlFlow<R, B>,
    ) -> ControlFlow<R, B> {
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
                let start = left.x.max(0);
                let end = right.x.min(last);
                if start <= end {
                    let span = Span {
                        y: y0.wrapping_add(row as i32),
                        x_start: x0.wrapping_add(start),
                        x_end: x0.wrapping_add(end).wrapping_add(1),
                    };
                    acc = f(acc, span, start as u32, row)?;
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
        ControlFlow::Continue(acc)
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

/// The last pixel of `len` from `start` (saturating at the ends of `i32`).
#[inline(always)]
pub(crate) fn last_of(start: i32, len: u32) -> i32 {
    // `start + len − 1` clamped to `i32`, in 32 bits: biased by 2³¹, `i32`'s range is `u32`'s,
    // and the clamp is a saturating addition (or, for an empty length, subtraction).
    let biased = (start as u32) ^ (1 << 31);
    let end = match len.checked_sub(1) {
        Some(rest) => biased.saturating_add(rest),
        None => biased.saturating_sub(1),
    };
    (end ^ (1 << 31)) as i32
}

/// The bounding box `[min_x, min_y, max_x, max_y]` of the vertices `p`.
#[inline(always)]
pub(crate) fn bounds(p: [(i32, i32); 3]) -> [i32; 4] {
    let span = |a: i32, b: i32, c: i32| (a.min(b).min(c), a.max(b).max(c));
    let (min_x, max_x) = span(p[0].0, p[1].0, p[2].0);
    let (min_y, max_y) = span(p[0].1, p[1].1, p[2].1);
    [min_x, min_y, max_x, max_y]
}

/// Which edges bound a walk's rows, from the vertices' heights (see [`Walk::assemble`]): all
/// a set-up needs to ask for the walk's boundaries. One copy for both set-ups on Cortex-M0
/// (flash).
#[derive(Debug, Clone, Copy)]
struct Plan {
    /// The edge that bounds one side of every row (the long one, opposite the middle vertex).
    single: u8,
    /// The other side's edge in the first rows, and the one from row offset `switch` on (the
    /// same edge where that side has only one).
    pair: u8,
    next: u8,
    /// Whether `pair` and `next` bound the rows' start.
    pair_left: bool,
    switch: u32,
}

impl Plan {
    /// The plan of the rows `first .. rows` from row `origin_y` of a positively oriented
    /// triangle whose vertices are at heights `base + ys[k]` (sub-pixels).
    #[cfg_attr(armv6m, inline(never))]
    #[cfg_attr(not(armv6m), inline(always))]
    fn new(ys: [i32; 3], base: i32, origin_y: i32, (first, rows): (u32, u32)) -> Self {
        // The vertices by height, with their indices.
        let mut v = [(ys[0], 0), (ys[1], 1), (ys[2], 2)];
        if v[1].0 < v[0].0 {
            v.swap(0, 1);
        }
        if v[2].0 < v[1].0 {
            v.swap(1, 2);
            if v[1].0 < v[0].0 {
                v.swap(0, 1);
            }
        }
        let [(top_y, top), (middle_y, middle), (bottom_y, bottom)] = v;
        // The upper edge (opposite the bottom vertex) or the lower one (opposite the top vertex)
        // may be horizontal.
        let (pair, next, switch) = if top_y == middle_y {
            (top, top, rows)
        } else if middle_y == bottom_y {
            (bottom, bottom, rows)
        } else {
            // First row whose centre is not above the middle vertex, as an offset from the
            // origin. (`max` and `min`, not `clamp`: its bounds check is a panic path where it
            // is not inlined.)
            let switch = first_centre_from(middle_y.wrapping_add(base))
                .wrapping_sub(origin_y)
                .max(first as i32)
                .min(rows as i32) as u32;
            (bottom, top, switch)
        };
        // The long edge, from vertex `middle + 1` to `middle + 2`, bounds the rows' end if it
        // runs down, from the top vertex (its x coefficient, the first height less the second,
        // is then negative: the heights differ, the triangle not being degenerate).
        Plan {
            single: middle,
            pair,
            next,
            pair_left: matches!((middle, top), (0, 1) | (1, 2) | (2, 0)),
            switch,
        }
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
    #[cfg(test)]
    /// The part of the triangle's pixel bounding box inside `clip`, or `None` if they don't meet.
    pub fn new(setup: &TriangleSetup, clip: &Rectangle) -> Option<Region> {
        Region::within(bounds(setup.oriented), clip)
    }

    /// The pixels whose centres lie in the box `[min_x, min_y, max_x, max_y]` (raw [`Coord`]
    /// bits, see [`bounds`]), inside `clip`; `None` if there are none. In 32 bits: pixel
    /// indices of `Coord` positions and the clip's last pixel (clamped) fit `i32`.
    #[inline(always)]
    pub(crate) fn within(
        [min_x, min_y, max_x, max_y]: [i32; 4],
        clip: &Rectangle,
    ) -> Option<Region> {
        let (cx, cy) = (clip.top_left.x, clip.top_left.y);
        let region = Region {
            x0: first_centre_from(min_x).max(cx),
            x1: last_centre_to(max_x).min(last_of(cx, clip.size.width)),
            y0: first_centre_from(min_y).max(cy),
            y1: last_centre_to(max_y).min(last_of(cy, clip.size.height)),
        };
        (region.x0 <= region.x1 && region.y0 <= region.y1).then_some(region)
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

/// The boundary of the general set-up for an edge with coefficients `a ≠ 0`, `b` whose reduced
/// value at the walk's first column is `k`. Where the boundary is read (rows within its edge's
/// height) its column and every step between those rows fit `i32`; elsewhere the values wrap
/// unread.
fn general_boundary(a: i64, b: i64, k: i64) -> Boundary {
    // |a| < 2³²: a difference of two raw `i32` heights.
    let m = a.unsigned_abs();
    let (q, rem) = div_mod_floor(k, m);
    let (step, rem_step) = div_mod_floor(b, m);
    // Remainders in [0, m): non-negative. A start boundary (a > 0) is the first x with
    // k + a·x ≥ 0, and moving one column left subtracts m; an end boundary the last x with
    // k − m·x ≥ 0, and moving one column right subtracts m.
    let toward_inside = |v: i64| if a > 0 { v.wrapping_neg() } else { v } as i32;
    Boundary::from_parts(
        toward_inside(q),
        rem as u32,
        toward_inside(step),
        rem_step as u32,
        m as u32,
    )
}

/// Rows `first ..= last` of a frame, drawn into a buffer whose row 0 is `first`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Band {
    pub(crate) first: i32,
    pub(crate) last: i32,
}

impl Band {
    /// The rows of `y0 ..= y1` inside the band and how many rows of it come before them, or
    /// `None` if none is inside.
    #[inline(always)]
    pub(crate) fn restrict(&self, y0: i32, y1: i32) -> Option<(i32, i32, u32)> {
        let (start, end) = (y0.max(self.first), y1.min(self.last));
        // start ≥ y0: the difference is below 2³².
        (start <= end).then(|| (start, end, start.wrapping_sub(y0) as u32))
    }

    /// Row `y` of the frame as a row of the band's buffer.
    #[inline(always)]
    pub(crate) fn local(&self, y: i32) -> i32 {
        y.wrapping_sub(self.first)
    }

    /// Whether pixel rows `top ..= bottom` meet the band.
    #[inline(always)]
    pub(crate) fn meets(&self, top: i32, bottom: i32) -> bool {
        top <= self.last && bottom >= self.first
    }
}

/// A boundary that never limits a span: far left of any region (a start boundary) or far right
/// (an end one).
const fn open_boundary(end: bool) -> Boundary {
    Boundary {
        x: if end { 1 << 30 } else { -(1 << 30) },
        rem: 0,
        step: 0,
        rem_step: 0,
        carry_at: 1,
    }
}

/// The walk of `setup` (any [`Coord`] vertices) over the rows `rows.y0 ..= rows.y1` of
/// `region`, with columns and rows counted from the region's first pixel (the planes'
/// origin). The edge values are exact (`i64`, or `i128` far off-screen) at the first row
/// of each boundary; the walk itself is the compact set-up's.
// One copy for all callers; everything it calls is inlined into it.
#[inline(never)]
pub(crate) fn general_walk(setup: &TriangleSetup, region: &Region, rows: &Region) -> Walk {
    // Oriented vertices (raw `Coord` bits, so `i32`).
    let o = setup.oriented;
    // A horizontal bottom edge excludes the centres on it; every other limit of the rows is
    // the region's.
    let (y0, y1) = (rows.y0, rows.y1.min(last_row(o.map(|v| v.1))));
    // Row offsets from the region's first row (the planes' origin). A walk without rows (the
    // horizontal edges leave none) still comes from `assemble`: `Walk::empty`'s zeroed fields
    // would cost a call to clear memory on Cortex-M.
    let first = y0.wrapping_sub(region.y0) as u32;
    let (first, end) = if y0 > y1 {
        (first + 1, first + 1)
    } else {
        (first, y1.wrapping_sub(region.y0) as u32 + 1)
    };
    let x0 = i64::from(region.x0);
    let (width, height) = (region.width() - 1, region.height() - 1);
    let walk = Walk::assemble(
        o.map(|v| v.1),
        0,
        (region.x0, region.y0),
        region.x1.wrapping_sub(region.x0),
        (first, end),
        |k, row| {
            let e = setup.edge(k);
            let y = i64::from(region.y0) + i64::from(row);
            // Exact at a pixel of the bounding box; far off a used edge's rows the value is
            // clamped (only its sign and size matter there: the boundary is not read).
            let k = e.reduced(e.exact_at(x0, y, setup.narrow));
            let k = k.clamp(-(1 << 62), 1 << 62) as i64;
            // An edge with every pixel of the region inside (from this row down) never limits
            // a span: an open boundary, without the divisions (on Cortex-M0 a few thousand
            // instructions; big triangles over a small screen have such edges often).
            // |a|·w, |b|·h < 2³³·2²⁵.
            let low = k + (e.a * width).min(0) + (e.b * height).min(0);
            Ok::<_, core::convert::Infallible>(if low >= 0 {
                open_boundary(e.a < 0)
            } else {
                general_boundary(e.a, e.b, k)
            })
        },
    );
    match walk {
        Ok(walk) => walk,
        Err(never) => match never {},
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixed_point::Coord;
    use crate::raster::compact::CompactTriangle;
    use crate::raster::spans::{for_each_span, Spans};

    /// The last pixel of a length: `start + len − 1` clamped to `i32`, at the ends of both
    /// ranges and at random.
    #[test]
    fn last_of_is_the_clamped_end() {
        let check = |start: i32, len: u32| {
            let want = (i64::from(start) + i64::from(len) - 1)
                .clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
            assert_eq!(last_of(start, len), want, "{start} {len}");
        };
        let starts = [i32::MIN, i32::MIN + 1, -1, 0, 1, i32::MAX - 1, i32::MAX];
        let lens = [0, 1, 2, 1 << 31, u32::MAX - 1, u32::MAX];
        for start in starts {
            for len in lens {
                check(start, len);
            }
        }
        let mut next = crate::random(0x1a57_0f00_0000_0001);
        for _ in 0..100_000 {
            let (start, len) = (next() as i32, next() as u32 >> (next() % 32));
            check(start, len);
        }
    }

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
                    div_mod_floor(n, d as u64),
                    (n.div_euclid(d), n.rem_euclid(d) as u64),
                    "{n} / {d}"
                );
            }
        }
    }

    /// The walks of both set-ups — the compact one's and the general one's — and both ways of
    /// consuming them (`fold` and `next`) against per-pixel edge tests, over triangles from
    /// sub-pixel size to far beyond the clip, including near-horizontal slivers through it whose
    /// edges' columns leave the `i32` range outside the rows they bound.
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
            general += 1;
            // An edge whose boundary column reaches 2³⁰ or more from the region, with spans in
            // the clip.
            let steep = setup.edges().iter().any(|e| {
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
