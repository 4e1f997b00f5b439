//! Polygons: any number of closed contours, convex or not, self-intersecting, with holes, filled
//! by the non-zero or the even-odd rule, under the triangles' fill rule.
//!
//! A pixel is covered by where its centre lies. Each edge that is not horizontal crosses the
//! rows whose centres lie in `[y_top, y_bottom)` of it, and at such a row it adds its direction
//! (+1 downward, −1 upward) to the winding number of every centre at or right of the crossing.
//! A centre is inside where that winding number is non-zero (or odd). The ties are the top-left
//! rule's, for any orientation: a centre exactly on an edge counts as right of it, so it belongs
//! to the shape on the edge's right — a left edge owns it, a right edge does not — and a
//! horizontal edge limits the rows only through its neighbours' half-open intervals (a top edge
//! owns its centres, a bottom one does not). For three vertices that is exactly the triangles'
//! rule (`edge.rs`), so a polygon covers the same pixels as any triangulation of it drawn with
//! the same orientation, and two shapes sharing an edge never both cover a centre on it.
//!
//! Each edge's crossing is kept as the first pixel column whose centre counts as right of it,
//! stepped row by row as an exact quotient and remainder, set up once from the exact rational
//! crossing (`i64`, or `i128` for coordinates beyond ±2²¹ px), so no pixel depends on rounding.
//! A row sorts its edges by that column (insertion: from row to row they are nearly sorted)
//! and hands the runs where the winding number is inside to a span shader.

use embedded_graphics::primitives::Rectangle;

use super::arith::{div_floor_wide, div_rem_u64};
use super::edge::{first_centre_from, last_centre_before};
use super::sink::SpanShader;
use super::walk::Span;
use crate::fixed_point::{HALF_PIXEL, SUBPIXEL_BITS};

/// Which centres a polygon's winding numbers make inside.
///
/// The winding number of a point counts the contours' edges around it, each by its direction;
/// the two rules differ only where contours overlap themselves or each other.
///
/// # Examples
///
/// ```
/// use embedded_raster::FillRule;
///
/// assert!(FillRule::NonZero.inside(2));
/// assert!(!FillRule::EvenOdd.inside(2));
/// assert!(FillRule::EvenOdd.inside(-1));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum FillRule {
    /// Inside where the winding number is not zero: a contour inside another of the same
    /// direction fills, one of the opposite direction cuts a hole.
    #[default]
    NonZero,
    /// Inside where the winding number is odd: every nested contour cuts a hole, whatever its
    /// direction.
    EvenOdd,
}

impl FillRule {
    /// Whether a point of winding number `winding` is inside.
    #[inline(always)]
    pub const fn inside(self, winding: i32) -> bool {
        match self {
            FillRule::NonZero => winding != 0,
            FillRule::EvenOdd => winding & 1 != 0,
        }
    }
}

/// A polygon edge as a row's crossing: the first column whose centre counts as right of it,
/// stepped a row at a time. With `D = 256·dy` and the crossing's exact numerator `n` (the
/// column is `⌈n / D⌉`), `n = column·D − error`, `0 ≤ error < D`.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct EdgeCrossing {
    /// First and last row it crosses (clipped).
    first: i32,
    last: i32,
    /// The column at the current row. Inside the edge's rows it lies between its end points'
    /// columns, so it fits an `i32` for any `Coord`.
    column: i32,
    /// `⌊dx / dy⌋`: the column's whole step a row (wrapping: it fits an `i32` whenever the edge
    /// crosses two rows or more, `dy > 256`).
    step: i32,
    error: i64,
    /// `256·(dx mod dy)`: what the error loses a row.
    fraction: i64,
    denominator: i64,
    /// +1 for an edge going down the screen, −1 up.
    winding: i32,
}

/// Coordinates below this magnitude (2²⁹ sub-pixels) set up in `i64`: every product below 2⁶⁰.
const NARROW: i64 = 1 << 29;

impl EdgeCrossing {
    /// The edge from `a` to `b` (raw sub-pixels) over the rows `top ..= bottom`, set up at its
    /// first row there; `None` if it crosses none of them (horizontal edges, edges between two
    /// centres' heights, edges outside).
    fn new(a: (i32, i32), b: (i32, i32), top: i32, bottom: i32) -> Option<EdgeCrossing> {
        let (winding, (xa, ya), (xb, yb)) = match a.1.cmp(&b.1) {
            core::cmp::Ordering::Less => (1, a, b),
            core::cmp::Ordering::Greater => (-1, b, a),
            core::cmp::Ordering::Equal => return None,
        };
        let first = first_centre_from(ya).max(top);
        let last = last_centre_before(yb).min(bottom);
        if first > last {
            return None;
        }
        let (xa, ya, xb, yb) = (i64::from(xa), i64::from(ya), i64::from(xb), i64::from(yb));
        let (dx, dy) = (xb - xa, yb - ya);
        let denominator = dy << SUBPIXEL_BITS;
        // The crossing at the first row's centre `yc`: the columns `i` right of it are those
        // with `256·i + 128 ≥ xa + (yc − ya)·dx/dy`, i.e. `i ≥ n / D` with
        // `n = (yc − ya)·dx + (xa − 128)·dy`.
        let yc = (i64::from(first) << SUBPIXEL_BITS) + HALF_PIXEL;
        let narrow = [xa, ya, xb, yb].iter().all(|v| v.abs() < NARROW);
        let (column, error) = if narrow {
            // |yc − ya| < dy < 2³⁰, |dx| < 2³⁰, |xa − 128| < 2²⁹ + 128: below 2⁶¹.
            ceil_div((yc - ya) * dx + (xa - HALF_PIXEL) * dy, denominator)
        } else {
            ceil_div_wide(
                i128::from(yc - ya) * i128::from(dx) + i128::from(xa - HALF_PIXEL) * i128::from(dy),
                denominator,
            )
        };
        // ⌊dx / dy⌋ and the remainder, by the unsigned division (dy > 0, |dx| < 2³³).
        let (q, r) = div_rem_u64(dx.unsigned_abs(), nonzero(dy));
        let (q, r) = (q as i64, r as i64);
        let (step, rest) = match (dx < 0, r) {
            (false, _) => (q, r),
            (true, 0) => (-q, 0),
            (true, _) => (-q - 1, dy - r),
        };
        Some(EdgeCrossing {
            first,
            last,
            column,
            step: step as i32,
            error,
            fraction: rest << SUBPIXEL_BITS,
            denominator,
            winding,
        })
    }

    /// To the next row's crossing: `n` grows by `256·dx = step·D + fraction`.
    #[inline(always)]
    fn advance(&mut self) {
        self.column = self.column.wrapping_add(self.step);
        self.error -= self.fraction;
        if self.error < 0 {
            self.error += self.denominator;
            self.column = self.column.wrapping_add(1);
        }
    }
}

fn nonzero(d: i64) -> core::num::NonZeroU64 {
    core::num::NonZeroU64::new(d.unsigned_abs()).unwrap_or(core::num::NonZeroU64::MIN)
}

/// `(⌈n / d⌉, ⌈n / d⌉·d − n)` for `d > 0`; the quotient is a column (it fits an `i32`).
fn ceil_div(n: i64, d: i64) -> (i32, i64) {
    let (q, r) = div_rem_u64(n.unsigned_abs(), nonzero(d));
    let (q, r) = (q as i64, r as i64);
    let (column, error) = match (n < 0, r) {
        (true, _) => (-q, r),
        (false, 0) => (q, 0),
        (false, _) => (q + 1, d - r),
    };
    (column as i32, error)
}

/// [`ceil_div`] of an `i128` numerator, out of line: only coordinates beyond ±2²¹ px need it.
#[inline(never)]
#[cold]
fn ceil_div_wide(n: i128, d: i64) -> (i32, i64) {
    let column = div_floor_wide(-n, i128::from(d)).wrapping_neg();
    let error = column * i128::from(d) - n;
    (column as i32, error as i64)
}

/// Sorts `edges` by their first row: a heap sort (no recursion, no allocation, no panic path).
fn sort_by_first_row(edges: &mut [EdgeCrossing]) {
    let key = |edges: &[EdgeCrossing], i: usize| edges.get(i).map_or(i32::MAX, |e| e.first);
    let sift_down = |edges: &mut [EdgeCrossing], mut root: usize, end: usize| loop {
        let mut child = 2 * root + 1;
        if child >= end {
            return;
        }
        if child + 1 < end && key(edges, child + 1) > key(edges, child) {
            child += 1;
        }
        if key(edges, root) >= key(edges, child) {
            return;
        }
        edges.swap(root, child);
        root = child;
    };
    let n = edges.len();
    for root in (0..n / 2).rev() {
        sift_down(edges, root, n);
    }
    for end in (1..n).rev() {
        edges.swap(0, end);
        sift_down(edges, 0, end);
    }
}

/// Sorts the row's active edges by column: insertion, as they are nearly sorted from the row
/// before (they change order only where edges cross).
#[inline(always)]
fn sort_by_column(edges: &mut [EdgeCrossing]) {
    for i in 1..edges.len() {
        let mut j = i;
        while j > 0 {
            let (Some(a), Some(b)) = (edges.get(j - 1), edges.get(j)) else {
                break;
            };
            if a.column <= b.column {
                break;
            }
            edges.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// Hands the covered spans inside `clip` of the polygon whose edges `edges` yields (pairs of
/// raw sub-pixel points; each contour closed by its last edge) to `shader`, top to bottom and
/// left to right, under `rule`. `scratch` holds one crossing an edge: edges past its length
/// are not drawn, so it must be at least as long as there are edges (the callers size it from
/// the polygon's capacity).
pub(crate) fn fill_polygon<S: SpanShader<0>>(
    edges: impl Iterator<Item = ((i32, i32), (i32, i32))>,
    scratch: &mut [EdgeCrossing],
    rule: FillRule,
    clip: &Rectangle,
    shader: &mut S,
) {
    let Some(bottom_right) = clip.bottom_right() else {
        return;
    };
    let (top, bottom) = (clip.top_left.y, bottom_right.y);
    let (left, right) = (clip.top_left.x, bottom_right.x.saturating_add(1));
    let mut count = 0;
    for (a, b) in edges {
        let Some(slot) = scratch.get_mut(count) else {
            break;
        };
        if let Some(edge) = EdgeCrossing::new(a, b, top, bottom) {
            *slot = edge;
            count += 1;
        }
    }
    let Some(edges) = scratch.get_mut(..count) else {
        return;
    };
    sort_by_first_row(edges);
    let steps = shader.prepare([]);
    // edges[..active] cross the current row; edges[next..] are still to come, sorted by their
    // first row; the slots between are free (active ≤ next).
    let (mut active, mut next) = (0, 0);
    let mut y = match edges.first() {
        Some(e) => e.first,
        None => return,
    };
    loop {
        while let Some(&edge) = edges.get(next).filter(|e| e.first <= y) {
            if let Some(slot) = edges.get_mut(active) {
                *slot = edge;
            }
            active += 1;
            next += 1;
        }
        let Some(row) = edges.get_mut(..active) else {
            return;
        };
        if row.is_empty() {
            match edges.get(next) {
                Some(e) => {
                    y = e.first;
                    continue;
                }
                None => return,
            }
        }
        sort_by_column(row);
        // The runs where the winding number is inside: at each column where it changes from
        // outside to inside a span starts, where it changes back the span ends.
        let (mut winding, mut start) = (0, left);
        let mut crossings = row.iter().peekable();
        while let Some(edge) = crossings.next() {
            let was_inside = rule.inside(winding);
            winding += edge.winding;
            // All the crossings at one column before the inside test.
            while let Some(same) = crossings.next_if(|e| e.column == edge.column) {
                winding += same.winding;
            }
            let column = edge.column.clamp(left, right);
            match (was_inside, rule.inside(winding)) {
                (false, true) => start = column,
                (true, false) if column > start => {
                    shader.span(
                        &steps,
                        Span {
                            y,
                            x_start: start,
                            x_end: column,
                        },
                        [],
                    );
                    if shader.stopped() {
                        return;
                    }
                }
                _ => {}
            }
        }
        // To the next row: the edges ending here leave, the others step.
        let mut kept = 0;
        for i in 0..active {
            let Some(&edge) = edges.get(i) else { break };
            if edge.last > y {
                let mut edge = edge;
                edge.advance();
                if let Some(slot) = edges.get_mut(kept) {
                    *slot = edge;
                }
                kept += 1;
            }
        }
        active = kept;
        if active == 0 && next >= edges.len() {
            return;
        }
        y += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ceil_division_is_exact() {
        let mut rng = crate::random(7);
        for _ in 0..100_000 {
            let n = (rng() as i64) >> (rng() % 40);
            let d = ((rng() >> 24) as i64 >> (rng() % 40)).max(1);
            let (q, e) = ceil_div(n >> 3, d);
            let exact = (i128::from(n >> 3) + i128::from(d) - 1).div_euclid(i128::from(d));
            if exact.abs() < i128::from(i32::MAX) {
                assert_eq!(i128::from(q), exact, "{n} / {d}");
                assert_eq!(i128::from(e), exact * i128::from(d) - i128::from(n >> 3));
            }
            let (qw, ew) = ceil_div_wide(i128::from(n >> 3), d);
            if exact.abs() < i128::from(i32::MAX) {
                assert_eq!((i128::from(qw), ew), (exact, e));
            }
        }
    }

    #[test]
    fn heap_sort_orders_by_first_row() {
        let mut rng = crate::random(3);
        for len in 0..40 {
            let mut edges = [EdgeCrossing::default(); 40];
            for e in edges.iter_mut().take(len) {
                e.first = (rng() % 17) as i32 - 8;
            }
            let mut expected: heapless::Vec<i32, 40> =
                edges[..len].iter().map(|e| e.first).collect();
            expected.sort_unstable();
            sort_by_first_row(&mut edges[..len]);
            assert!(edges[..len]
                .iter()
                .map(|e| e.first)
                .eq(expected.iter().copied()));
        }
    }
}
