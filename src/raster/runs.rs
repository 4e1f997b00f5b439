//! A small triangle's rows as runs: what the scan (`scan.rs`) finds them with and what a
//! shader that draws all of a small triangle's rows at once is handed
//! (the span shaders' `small_rows`).
//!
//! Below the span shaders: the shaders' trait names [`SmallScan`], and the scan sets its
//! triangles up into it.

use core::num::{NonZeroU32, NonZeroU64};

use super::edge::owns_centres_on;
use super::plane::Planes;
use super::walk::Band;
use crate::fixed_point::SUBPIXEL_BITS;

/// Width and height of a small triangle's vertex bounding box stay below this many pixels.
pub(crate) const SMALL: u32 = 16;

/// An edge: coefficients `a` (per column) and `b` (per row) and its reduced value `K` at the
/// first pixel.
#[derive(Clone, Copy)]
pub(crate) struct Edge {
    pub(crate) a: i32,
    pub(crate) b: i32,
    pub(crate) k: i32,
}

impl Edge {
    /// The edge from `s` to `e` (sub-pixels, relative to vertex 0), with `K` at the pixel
    /// centre `(cx, cy)` (relative to vertex 0 too), and its edge value there.
    #[inline(always)]
    pub(crate) fn new(s: (i32, i32), e: (i32, i32), (cx, cy): (i32, i32)) -> (Edge, i32) {
        let (a, b) = (s.1 - e.1, e.0 - s.0);
        // Within the box: coefficients and offsets below 2¹³, the value below 2²⁷.
        let value = a * (cx - s.0) + b * (cy - s.1);
        let bias = i32::from(!owns_centres_on(a.into(), b.into()));
        let k = (value - bias) >> SUBPIXEL_BITS;
        (Edge { a, b, k }, value)
    }
}

/// A small triangle's rows as a shader that draws them all at once sees them
/// (the span shaders' `small_rows`): its region's first pixel, its rows' runs and its planes.
pub(crate) struct SmallScan<'p, const N: usize> {
    pub(crate) x0: i32,
    pub(crate) y0: i32,
    pub(crate) rows: u32,
    pub(crate) runs: RowRuns,
    pub(crate) planes: &'p Planes<N>,
}

impl<const N: usize> SmallScan<'_, N> {
    /// The region's first pixel (its top-left one, inside the clip).
    #[inline(always)]
    pub(crate) fn origin(&self) -> (i32, i32) {
        (self.x0, self.y0)
    }

    /// The same rows with the origin's row counted from the first row of `band` (the rows of a
    /// band's buffer).
    #[inline(always)]
    pub(crate) fn in_band(&self, band: &Band) -> Self {
        SmallScan {
            y0: band.local(self.y0),
            runs: self.runs,
            planes: self.planes,
            ..*self
        }
    }

    /// Rows of the region, 1 to [`SMALL`].
    #[inline(always)]
    pub(crate) fn rows(&self) -> u32 {
        self.rows
    }

    /// The first row's runs; [`RowRuns::advance`] moves to the next.
    #[inline(always)]
    pub(crate) fn runs(&self) -> &RowRuns {
        &self.runs
    }

    /// The attribute planes, from the region's first pixel.
    #[inline(always)]
    pub(crate) fn planes(&self) -> &Planes<N> {
        self.planes
    }
}

/// A bound of the run of a row: `⌊max(n, 0) / d⌋` for the numerator `n` of the row and the
/// divisor `d`; `n` changes by `step` a row.
#[derive(Clone, Copy)]
pub(crate) struct RowBound {
    /// The numerator at the current row.
    pub(crate) numerator: i32,
    /// The divisor, 1 to 2¹³.
    pub(crate) divisor: NonZeroU32,
    /// The numerator's change from a row to the next.
    pub(crate) step: i32,
}

impl RowBound {
    /// The bound at the current row.
    #[inline(always)]
    fn at(&self) -> u32 {
        self.numerator.max(0) as u32 / self.divisor
    }
}

/// The covered runs of a small triangle's rows by one division an edge, the edges classified
/// once per triangle: `run_by_scan`'s runs (the same integers; tested).
///
/// An edge with `K` at the row's first column and `a` a column (`K ≥ 0` inside) is
/// * a start bound if `a > 0`: inside from column `⌈−K/a⌉ = ⌊(a − 1 − K)/a⌋` on when `K < 0`,
///   everywhere when `K ≥ 0` (the numerator `a − 1 − K` is then below `a`: the bound is 0);
/// * an end bound if `a < 0`: inside up to column `⌊K/|a|⌋`, so the run ends before
///   `⌊(K + |a|)/|a|⌋`, which is 0 (an empty run) for `K < 0`;
/// * horizontal (`a = 0`): inside everywhere or nowhere by the sign of `K`, which is the start
///   bound `⌊−16·K / 1⌋`: 0 for `K ≥ 0`, at least 16 (past every column) for `K < 0`.
///
/// The three `a` sum to 0 and at most one is 0 (else the triangle has no area), so there are
/// one or two start bounds and one or two end bounds: `bounds` holds a start bound, the middle
/// one (of either kind) and an end bound.
#[derive(Clone, Copy)]
pub(crate) struct RowRuns {
    /// Start bound, the middle bound, end bound.
    pub(crate) bounds: [RowBound; 3],
    /// Whether the middle bound is a start bound.
    pub(crate) middle_starts: bool,
    /// Columns of the region: runs end there at the latest.
    pub(crate) columns: u32,
}

impl RowRuns {
    /// The runs of the rows from the first of a region of `columns` columns (at most
    /// [`SMALL`]), for its edges `edges`.
    #[inline(always)]
    pub(crate) fn new(edges: &[Edge; 3], columns: u32) -> Self {
        // Each edge's bound, and whether it is an end bound. Below 2¹³ in magnitude: no
        // overflow.
        let bound = |e: &Edge| match NonZeroU32::new(e.a.unsigned_abs()) {
            None => {
                let numerator = -e.k * SMALL as i32;
                let step = -e.b * SMALL as i32;
                (
                    RowBound {
                        numerator,
                        divisor: NonZeroU32::MIN,
                        step,
                    },
                    false,
                )
            }
            Some(m) if e.a > 0 => {
                let (numerator, step) = (e.a - 1 - e.k, -e.b);
                (
                    RowBound {
                        numerator,
                        divisor: m,
                        step,
                    },
                    false,
                )
            }
            Some(m) => {
                let (numerator, step) = (e.k + m.get() as i32, e.b);
                (
                    RowBound {
                        numerator,
                        divisor: m,
                        step,
                    },
                    true,
                )
            }
        };
        let [mut b0, mut b1, mut b2] = [bound(&edges[0]), bound(&edges[1]), bound(&edges[2])];
        // An end bound last, then a start bound first.
        if !b2.1 {
            if b0.1 {
                (b0, b2) = (b2, b0);
            } else {
                (b1, b2) = (b2, b1);
            }
        }
        if b0.1 {
            (b0, b1) = (b1, b0);
        }
        RowRuns {
            bounds: [b0.0, b1.0, b2.0],
            middle_starts: !b1.1,
            columns,
        }
    }

    /// The current row's run `start..end` (columns from the region's first); empty if
    /// `end ≤ start`.
    #[inline(always)]
    pub(crate) fn run(&self) -> (u32, u32) {
        run_between(
            self.bounds.map(|b| b.at()),
            self.middle_starts,
            self.columns,
        )
    }

    /// Moves to the next row.
    #[inline(always)]
    pub(crate) fn advance(&mut self) {
        for b in &mut self.bounds {
            b.numerator += b.step;
        }
    }
}

/// The run `start..end` of a row between the values of its start bound, its middle bound (a
/// start bound if `middle_starts`, else an end bound) and its end bound, over `columns`.
#[inline(always)]
fn run_between([s, m, e]: [u32; 3], middle_starts: bool, columns: u32) -> (u32, u32) {
    let (mut start, mut end) = (s, e.min(columns));
    if middle_starts {
        start = start.max(m);
    } else {
        end = end.min(m);
    }
    (start, end)
}

/// [`RowRuns`] with each bound's division a multiply by its divisor's reciprocal, found once per
/// triangle: on a host, a division takes several times a multiply's latency (on Cortex-M it is
/// one instruction).
pub(crate) struct ReciprocalRuns {
    /// Start bound, middle bound, end bound: numerator, step, `⌊2³⁵ / d⌋ + 1` for the divisor `d`.
    bounds: [(i32, i32, u64); 3],
    middle_starts: bool,
    columns: u32,
}

impl ReciprocalRuns {
    #[inline(always)]
    pub(crate) fn new(runs: &RowRuns) -> Self {
        let reciprocal = |d: NonZeroU32| (1u64 << 35) / NonZeroU64::from(d) + 1;
        ReciprocalRuns {
            bounds: runs
                .bounds
                .map(|b| (b.numerator, b.step, reciprocal(b.divisor))),
            middle_starts: runs.middle_starts,
            columns: runs.columns,
        }
    }

    /// `⌊n / d⌋` for `n = max(numerator, 0)`. The reciprocal exceeds `2³⁵/d` by at most 1, so
    /// the product exceeds `2³⁵·n/d` by at most `n`, and the quotient is exact while `n·d < 2³⁵`:
    /// a small triangle's numerators stay below 2¹⁹ (2²² for the divisor 1 of a horizontal
    /// edge) and its divisors below 2¹³; the product stays below 2⁶⁴.
    #[inline(always)]
    fn at((numerator, _, reciprocal): (i32, i32, u64)) -> u32 {
        ((numerator.max(0) as u64 * reciprocal) >> 35) as u32
    }

    /// [`RowRuns::run`].
    #[inline(always)]
    pub(crate) fn run(&self) -> (u32, u32) {
        run_between(self.bounds.map(Self::at), self.middle_starts, self.columns)
    }

    /// [`RowRuns::advance`].
    #[inline(always)]
    pub(crate) fn advance(&mut self) {
        for b in &mut self.bounds {
            b.0 += b.1;
        }
    }
}

/// The covered run `start..end` (columns from the region's first; empty if `end ≤ start`) of a
/// row whose edges have the values `k` at its first column and steps `a` per column, over
/// columns `0 ..= last` (at most 15), by testing the columns from the first to the run's end (a
/// triangle is convex: one run a row).
#[inline(always)]
pub(crate) fn run_by_scan(edges: [(i32, i32); 3], last: u32) -> (u32, u32) {
    let [(mut c0, a0), (mut c1, a1), (mut c2, a2)] = edges;
    let mut column = 0;
    while (c0 | c1 | c2) < 0 && column <= last {
        (c0, c1, c2) = (c0 + a0, c1 + a1, c2 + a2);
        column += 1;
    }
    let start = column;
    while (c0 | c1 | c2) >= 0 && column <= last {
        (c0, c1, c2) = (c0 + a0, c1 + a1, c2 + a2);
        column += 1;
    }
    (start, column)
}
