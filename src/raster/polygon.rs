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

use core::num::{NonZeroU32, NonZeroU64};

use super::arith::{div_rem_u32, div_rem_u64, mul_u32_wide};
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
/// stepped a row at a time.
///
/// At the centre `y_c` of a row the columns right of the edge from `(x_a, y_a)` down to
/// `(x_b, y_b)` are those with `256·i + 128 ≥ x_a + (y_c − y_a)·dx/dy`, i.e. `i ≥ n / D` with
/// `n = (y_c − y_a)·dx + (x_a − 128)·dy` and `D = 256·dy`: the column is `⌈n / D⌉`, and
/// `column·D − n` is its exact error, in `[0, D)`. A row adds `256·dx = ⌊dx/dy⌋·D + 256·(dx mod
/// dy)` to `n`, a multiple of 256 like `D`, so the error's low eight bits never change and its
/// high part `error` (in `[0, dy)`) carries it: every field fits 32 bits for any `Coord`.
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
    /// `⌊(column·D − n) / 256⌋`, in `[0, dy)`.
    error: u32,
    /// `dx mod dy`: what the error loses a row, and `dy − fraction`, what it gains when that
    /// carries the column one further.
    fraction: u32,
    carry: u32,
    /// +1 for an edge going down the screen, −1 up.
    winding: i32,
}

impl EdgeCrossing {
    /// The edge from `a` to `b` (raw sub-pixels) over the rows `top ..= bottom`, set up at its
    /// first row there; `None` if it crosses none of them (horizontal edges, edges between two
    /// centres' heights, edges outside).
    fn new(a: (i32, i32), b: (i32, i32), top: i32, bottom: i32) -> Option<EdgeCrossing> {
        Self::biased(a, b, top, bottom, HALF_PIXEL)
    }

    /// [`new`](Self::new) with the column `⌈(x − bias) / 256⌉` of the crossing `x` (`new`'s
    /// bias is 128: the first centre at or right of it; a line's is 256: the pixel whose
    /// centre is within `(−128, 128]` of it, plus one).
    pub(crate) fn biased(
        a: (i32, i32),
        b: (i32, i32),
        top: i32,
        bottom: i32,
        bias: i64,
    ) -> Option<EdgeCrossing> {
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
        // dy in 1 .. 2³², |dx| below 2³²; the first row's centre is `k` below `y_a`, k < dy.
        let dy = yb.abs_diff(ya);
        let dx = i64::from(xb) - i64::from(xa);
        let rows = NonZeroU32::new(dy)?;
        let yc = (i64::from(first) << SUBPIXEL_BITS) + HALF_PIXEL;
        let k = (yc - i64::from(ya)) as u32;
        // ⌊dx / dy⌋ and dx mod dy.
        let (q, r) = div_rem_u32(dx.unsigned_abs() as u32, rows);
        let (step, fraction) = match (dx < 0, r) {
            (false, _) => (i64::from(q), r),
            (true, 0) => (-i64::from(q), 0),
            (true, _) => (-i64::from(q) - 1, dy - r),
        };
        // n = dy·(k·step + x_a − 128) + k·fraction; with k·fraction = g·dy + h (h < dy),
        // n = dy·t + h where t = k·step + x_a − 128 + g: |k·step| < |dx| + dy < 2³³.
        let spill = mul_u32_wide(k, fraction);
        let (g, h) = if spill >> 32 == 0 {
            div_rem_u32(spill as u32, rows)
        } else {
            let (g, h) = div_rem_u64(spill, NonZeroU64::from(rows));
            (g as u32, h as u32)
        };
        let t = i64::from(k) * step + i64::from(xa) - bias + i64::from(g);
        // ⌈n / D⌉ = ⌈(t + h/dy) / 256⌉: t's own ceiling if h = 0, else ⌊t / 256⌋ + 1.
        let column = if h == 0 {
            -((-t) >> SUBPIXEL_BITS)
        } else {
            (t >> SUBPIXEL_BITS) + 1
        };
        // column·D − n = (256·column − t)·dy − h, with 256·column − t in 0 ..= 256.
        let over = ((column << SUBPIXEL_BITS) - t) as u32;
        let error = (mul_u32_wide(over, dy) - u64::from(h)) >> SUBPIXEL_BITS;
        Some(EdgeCrossing {
            first,
            last,
            column: column as i32,
            step: step as i32,
            error: error as u32,
            fraction,
            carry: dy - fraction,
            winding,
        })
    }

    /// To the next row's crossing: `n` grows by `⌊dx/dy⌋·D + 256·(dx mod dy)`.
    #[inline(always)]
    pub(crate) fn advance(&mut self) {
        self.column = self.column.wrapping_add(self.step);
        if self.error < self.fraction {
            self.error = self.error.wrapping_add(self.carry);
            self.column = self.column.wrapping_add(1);
        } else {
            self.error -= self.fraction;
        }
    }

    /// The column at the current row.
    #[inline(always)]
    pub(crate) fn column(&self) -> i32 {
        self.column
    }
}

/// Exchanges `edges[i]` and `edges[j]` (`i < j`; nothing if `j` is outside): without
/// `slice::swap`, whose bounds check stays where it is not inlined (opt-level "z").
#[inline]
fn swap(edges: &mut [EdgeCrossing], i: usize, j: usize) {
    if let Some((left, right)) = edges.split_at_mut_checked(j) {
        if let (Some(a), Some(b)) = (left.get_mut(i), right.first_mut()) {
            core::mem::swap(a, b);
        }
    }
}

/// Sorts `edges` by their first row: a heap sort (no recursion, no allocation, no panic path).
fn sort_by_first_row(edges: &mut [EdgeCrossing]) {
    let key = |edges: &[EdgeCrossing], i: usize| edges.get(i).map_or(i32::MIN, |e| e.first);
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
        swap(edges, root, child);
        root = child;
    };
    let n = edges.len();
    for root in (0..n / 2).rev() {
        sift_down(edges, root, n);
    }
    for end in (1..n).rev() {
        swap(edges, 0, end);
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
            swap(edges, j - 1, j);
            j -= 1;
        }
    }
}

/// The rows `y ..= stop` between edges `a` and `b`, the only ones crossing them: each row's run
/// between the two columns, then both step (past `stop` too). `true` if the shader stopped.
#[inline(always)]
fn two_edges<S: SpanShader<0>>(
    a: &mut EdgeCrossing,
    b: &mut EdgeCrossing,
    mut y: i32,
    stop: i32,
    (left, right): (i32, i32),
    shader: &mut S,
    steps: &S::Steps,
) -> bool {
    let (mut p, mut q) = (*a, *b);
    loop {
        let (l, r) = if p.column <= q.column {
            (p.column, q.column)
        } else {
            (q.column, p.column)
        };
        let (l, r) = (l.max(left).min(right), r.max(left).min(right));
        if l < r {
            let span = Span {
                y,
                x_start: l,
                x_end: r,
            };
            shader.span(steps, span, []);
            if shader.stopped() {
                return true;
            }
        }
        p.advance();
        q.advance();
        if y >= stop {
            break;
        }
        y += 1;
    }
    (*a, *b) = (p, q);
    false
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
    // Inside where `winding & mask ≠ 0`: every bit for the non-zero rule, the lowest for
    // even-odd.
    let mask = match rule {
        FillRule::NonZero => -1,
        FillRule::EvenOdd => 1,
    };
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
        // The last row before another edge starts.
        let upcoming = edges
            .get(next)
            .map_or(i32::MAX, |e| e.first.saturating_sub(1));
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
        if let [a, b] = row {
            // Two edges (every row of a convex polygon, most of a simple one): a closed
            // polygon's crossings of a row sum to zero, so their windings are +1 and −1 and the
            // run between them is inside under either rule. Rows go by in a tight loop until
            // one of them ends or another edge starts.
            let stop = a.last.min(b.last).min(upcoming);
            if two_edges(a, b, y, stop, (left, right), shader, &steps) {
                return;
            }
            y = stop;
        } else {
            sort_by_column(row);
            // The runs where the winding number is inside: where it changes from outside to
            // inside a span starts, where it changes back the span ends; the crossings at one
            // column are summed before the test.
            let (mut winding, mut inside, mut start) = (0, false, left);
            let mut crossings = row.iter().peekable();
            while let Some(edge) = crossings.next() {
                winding += edge.winding;
                if crossings.peek().is_some_and(|e| e.column == edge.column) {
                    continue;
                }
                if (winding & mask != 0) != inside {
                    inside = !inside;
                    let column = edge.column.max(left).min(right);
                    if inside {
                        start = column;
                    } else if column > start {
                        let span = Span {
                            y,
                            x_start: start,
                            x_end: column,
                        };
                        shader.span(&steps, span, []);
                        if shader.stopped() {
                            return;
                        }
                    }
                }
            }
            for edge in row.iter_mut() {
                edge.advance();
            }
        }
        // To the next row (every edge has stepped): those that ended on this one leave.
        let ended = edges
            .get(..active)
            .is_some_and(|row| row.iter().any(|e| e.last == y));
        if ended {
            let mut kept = 0;
            for i in 0..active {
                let Some(&edge) = edges.get(i) else { break };
                if edge.last > y {
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
        }
        y += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every row's column of random edges (huge ones too) against `⌈n / D⌉` in `i128`.
    #[test]
    fn crossings_step_exactly() {
        let mut rng = crate::random(7);
        for case in 0..20_000 {
            let mut coordinate = || {
                let v = rng() as i32;
                match case % 3 {
                    0 => v,
                    1 => v >> 12,
                    _ => v >> 20,
                }
            };
            let (a, b) = ((coordinate(), coordinate()), (coordinate(), coordinate()));
            let top = (a.1.min(b.1) >> 8) + (rng() % 5) as i32 - 2;
            let Some(mut edge) = EdgeCrossing::new(a, b, top, top + 40) else {
                continue;
            };
            let (up, down) = if a.1 < b.1 { (a, b) } else { (b, a) };
            let (xa, ya, dx, dy) = (
                i128::from(up.0),
                i128::from(up.1),
                i128::from(down.0) - i128::from(up.0),
                i128::from(down.1) - i128::from(up.1),
            );
            for row in edge.first..=edge.last {
                let yc = i128::from(row) * 256 + 128;
                let n = (yc - ya) * dx + (xa - 128) * dy;
                let d = 256 * dy;
                let exact = (n + d - 1).div_euclid(d);
                assert_eq!(i128::from(edge.column()), exact, "{a:?} {b:?} row {row}");
                edge.advance();
            }
        }
    }

    /// The size the polygon's docs state for a crossing (`Polygon`: 32 bytes a vertex).
    #[test]
    fn a_crossing_is_32_bytes() {
        assert_eq!(core::mem::size_of::<EdgeCrossing>(), 32);
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
