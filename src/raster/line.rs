//! Thin lines: the pixels of a segment between sub-pixel end points under the diamond-exit rule
//! (Direct3D's aliased line rule, OpenGL's "diamond exit").
//!
//! Each pixel has a diamond test area around its centre, `|u| + |v| < ½ px` with `(u, v)` the
//! offset from the centre (y down). A segment from `P₀` to `P₁` draws a pixel when it meets the
//! pixel's diamond and `P₁` is not inside it: the segment leaves the diamond. The diamond's
//! boundary: for an x-major segment (`|dy| ≤ |dx|`) it includes its two lower edges and bottom
//! corner, for a y-major one the right corner too, and nothing else. So a segment ending on a
//! point does not draw that point's pixel, and the next segment of a polyline, starting there,
//! does: connected segments draw a shared vertex's pixel once and never skip one, and two
//! halves of a segment split at a point on it draw exactly the whole segment's pixels.
//!
//! Away from its ends a segment draws one pixel a column (x-major) or a row (y-major): the
//! pixel whose diamond's vertical (horizontal) diagonal the line crosses, with the bottom
//! (right) corner included. That is a crossing stepped exactly a column at a time, the polygon
//! edges' [`EdgeCrossing`] with the axes exchanged. Within a diamond's half-width of either end
//! the exact test decides each candidate pixel: the segment clipped to the diamond's four
//! half-planes in rational arithmetic (`i128` cross products), no rounding anywhere.

use embedded_graphics::primitives::Rectangle;

use super::polygon::EdgeCrossing;
use super::sink::SpanShader;
use super::walk::Span;
use crate::fixed_point::{HALF_PIXEL, SUBPIXEL_BITS};

/// The diamond's half-diagonal: ½ px.
const HALF: i64 = HALF_PIXEL;

/// `n / d` with `d > 0` and whether the bound is strict.
#[derive(Clone, Copy)]
struct Bound {
    n: i64,
    d: i64,
    strict: bool,
}

impl Bound {
    /// How `self` compares with `other` as numbers (cross-multiplied: both denominators are
    /// positive): in 64 bits where the products fit (the segment measured from its end nearer
    /// the pixel: always, but for segments over 2²⁰ px), else in 128.
    #[inline]
    fn cmp(self, other: Bound) -> core::cmp::Ordering {
        match (self.n.checked_mul(other.d), other.n.checked_mul(self.d)) {
            (Some(l), Some(r)) => l.cmp(&r),
            _ => (i128::from(self.n) * i128::from(other.d))
                .cmp(&(i128::from(other.n) * i128::from(self.d))),
        }
    }

    fn below(self, other: Bound) -> bool {
        self.cmp(other).is_lt()
    }

    fn equals(self, other: Bound) -> bool {
        self.cmp(other).is_eq()
    }
}

/// Whether the segment from `p` to `p + d` (offsets from a pixel centre, sub-pixels) meets that
/// pixel's diamond test area (`y_major`: the right corner included too).
fn meets_diamond(p: (i64, i64), d: (i64, i64), y_major: bool) -> bool {
    // t in [0, 1]: lower bound 0, upper bound 1, both closed.
    let mut lower = Bound {
        n: 0,
        d: 1,
        strict: false,
    };
    let mut upper = Bound {
        n: 1,
        d: 1,
        strict: false,
    };
    // α·u + β·v ≤ 128 (the lower edges, included) or < 128 (the upper ones).
    for (alpha, beta, strict) in [(1, 1, false), (-1, 1, false), (1, -1, true), (-1, -1, true)] {
        let a = alpha * p.0 + beta * p.1 - HALF;
        let b = alpha * d.0 + beta * d.1;
        // a + b·t ≤ 0 (or < 0).
        if b == 0 {
            if a > 0 || (strict && a == 0) {
                return y_major && through_right_corner(p, d);
            }
        } else if b > 0 {
            let bound = Bound {
                n: -a,
                d: b,
                strict,
            };
            if bound.below(upper) || (bound.equals(upper) && strict) {
                upper = bound;
            }
        } else {
            let bound = Bound {
                n: a,
                d: -b,
                strict,
            };
            if lower.below(bound) || (bound.equals(lower) && strict) {
                lower = bound;
            }
        }
    }
    let meets = lower.below(upper) || (lower.equals(upper) && !lower.strict && !upper.strict);
    meets || (y_major && through_right_corner(p, d))
}

/// Whether the segment from `p` to `p + d` passes through the point `(128, 0)` (the diamond's
/// right corner).
fn through_right_corner(p: (i64, i64), d: (i64, i64)) -> bool {
    let (cu, cv) = (HALF - p.0, -p.1);
    let cross = i128::from(cu) * i128::from(d.1) - i128::from(cv) * i128::from(d.0);
    let dot = i128::from(cu) * i128::from(d.0) + i128::from(cv) * i128::from(d.1);
    let length = i128::from(d.0) * i128::from(d.0) + i128::from(d.1) * i128::from(d.1);
    cross == 0 && (0..=length).contains(&dot)
}

/// Whether the point `p` (offset from a pixel centre) is inside that pixel's diamond test area.
fn in_diamond(p: (i64, i64), y_major: bool) -> bool {
    let (u, v) = p;
    let inside = u + v <= HALF && v - u <= HALF && u - v < HALF && -u - v < HALF;
    inside || (y_major && (u, v) == (HALF, 0))
}

/// The exact rule for pixel `(i, j)`: the segment meets its diamond and does not end inside it.
fn draws(p0: (i64, i64), p1: (i64, i64), (i, j): (i64, i64), y_major: bool) -> bool {
    let centre = |k: i64| (k << SUBPIXEL_BITS) + HALF;
    let c = (centre(i), centre(j));
    let start = (p0.0 - c.0, p0.1 - c.1);
    let end = (p1.0 - c.0, p1.1 - c.1);
    if in_diamond(end, y_major) {
        return false;
    }
    // The segment as a set, from its end nearer the pixel (small offsets: 64-bit bounds).
    let d = (p1.0 - p0.0, p1.1 - p0.1);
    let far = |q: (i64, i64)| q.0.unsigned_abs() + q.1.unsigned_abs();
    if far(start) <= far(end) {
        meets_diamond(start, d, y_major)
    } else {
        meets_diamond(end, (-d.0, -d.1), y_major)
    }
}

/// Runs of consecutive pixels along a row, merged before they reach the shader.
struct Runs<'s, S: SpanShader<0>> {
    shader: &'s mut S,
    steps: S::Steps,
    run: Option<Span>,
    clip: (i32, i32, i32, i32),
}

impl<S: SpanShader<0>> Runs<'_, S> {
    /// Pixels `x0 .. x1` of row `y` (clipped; `x0 < x1`), merged with the run before when they
    /// continue it. `false` once the shader has stopped.
    #[inline(always)]
    fn span(&mut self, y: i32, x0: i32, x1: i32) -> bool {
        let (cx0, cy0, cx1, cy1) = self.clip;
        let (x0, x1) = (x0.max(cx0), x1.min(cx1));
        if x0 >= x1 || y < cy0 || y >= cy1 {
            return true;
        }
        if let Some(run) = &mut self.run {
            if run.y == y && run.x_end == x0 {
                run.x_end = x1;
                return true;
            }
        }
        self.flush() && {
            self.run = Some(Span {
                y,
                x_start: x0,
                x_end: x1,
            });
            true
        }
    }

    fn flush(&mut self) -> bool {
        if let Some(run) = self.run.take() {
            self.shader.span(&self.steps, run, []);
            return !self.shader.stopped();
        }
        true
    }
}

/// Hands the pixels inside `clip` of the segment from `p0` to `p1` (raw sub-pixels) to `shader`
/// as runs of one row, from `p0`'s end to `p1`'s.
pub(crate) fn draw_line<S: SpanShader<0>>(
    p0: (i32, i32),
    p1: (i32, i32),
    clip: &Rectangle,
    shader: &mut S,
) {
    let Some(bottom_right) = clip.bottom_right() else {
        return;
    };
    if p0 == p1 {
        return;
    }
    let steps = shader.prepare([]);
    let mut runs = Runs {
        shader,
        steps,
        run: None,
        clip: (
            clip.top_left.x,
            clip.top_left.y,
            bottom_right.x.saturating_add(1),
            bottom_right.y.saturating_add(1),
        ),
    };
    let wide = |p: (i32, i32)| (i64::from(p.0), i64::from(p.1));
    let (a, b) = (wide(p0), wide(p1));
    let y_major = (b.1 - a.1).abs() > (b.0 - a.0).abs();
    // Major and minor coordinates: (x, y) for an x-major segment, (y, x) for a y-major one.
    let swap = |(x, y): (i32, i32)| if y_major { (y, x) } else { (x, y) };
    let (ma, mb) = (swap(p0), swap(p1));
    let (clip_lo, clip_hi) = if y_major {
        (runs.clip.1, runs.clip.3 - 1)
    } else {
        (runs.clip.0, runs.clip.2 - 1)
    };
    // The major-axis indices whose diamonds the segment can reach, inside the clip.
    let (lo, hi) = (ma.0.min(mb.0), ma.0.max(mb.0));
    // Those whose diamond's major extent [256k, 256k + 256] meets [lo, hi].
    let first = (((i64::from(lo) + 255) >> SUBPIXEL_BITS) as i32 - 1).max(clip_lo);
    // At most `clip_hi`, below `i32::MAX`: `last + 1` does not overflow.
    let last = (hi >> SUBPIXEL_BITS).min(clip_hi);
    if first > last {
        return;
    }
    // The inner indices, whose diamonds' major extent lies strictly between the ends
    // (`c − 128 > lo`, `c + 128 < hi`): there the line crosses the diamond's diagonal and goes
    // on, and the crossing decides. Near the ends the exact test does.
    let inner_first = (lo >> SUBPIXEL_BITS) + 1;
    let inner_last = (i64::from(hi) - 257) >> SUBPIXEL_BITS;
    let (inner_first, inner_last) = (inner_first.max(first), (inner_last as i32).min(last));
    let pixel = |k: i32, m: i32| if y_major { (m, k) } else { (k, m) };
    let (d_major, d_minor) = (
        i64::from(mb.0) - i64::from(ma.0),
        i64::from(mb.1) - i64::from(ma.1),
    );
    // The exact test on the pixels of index `k` the segment can reach.
    let near_end = |k: i32, runs: &mut Runs<'_, S>| -> bool {
        let c = (i64::from(k) << SUBPIXEL_BITS) + HALF;
        // The segment's minor coordinate at a major coordinate (clamped to it), within a
        // sub-pixel (truncated).
        // From the end nearer `c`: |major − e| is a few pixels, the product far below 2⁶³.
        let e = if (c - i64::from(ma.0)).abs() <= (c - i64::from(mb.0)).abs() {
            ma
        } else {
            mb
        };
        let along = |major: i64| {
            let major = major.max(i64::from(lo)).min(i64::from(hi));
            let offset = (major - i64::from(e.0))
                .saturating_mul(d_minor)
                .checked_div(d_major)
                .unwrap_or(0);
            i64::from(e.1).saturating_add(offset)
        };
        let (m0, m1) = (along(c - HALF), along(c + HALF));
        // Pixels whose diamond's minor extent [256m, 256m + 256] meets [min − 1, max + 1].
        let from = ((m0.min(m1) - 1 + 255) >> SUBPIXEL_BITS) - 1;
        let to = (m0.max(m1) + 1) >> SUBPIXEL_BITS;
        for m in from..to + 1 {
            let Ok(m) = i32::try_from(m) else { continue };
            let (x, y) = pixel(k, m);
            if draws(a, b, (i64::from(x), i64::from(y)), y_major) && !runs.span(y, x, x + 1) {
                return false;
            }
        }
        true
    };
    if inner_first > inner_last {
        for k in first..last + 1 {
            if !near_end(k, &mut runs) {
                return;
            }
        }
        runs.flush();
        return;
    }
    for k in first..inner_first {
        if !near_end(k, &mut runs) {
            return;
        }
    }
    // The minor index `⌈(minor − 256) / 256⌉` at each major centre: the pixel whose diamond's
    // diagonal the line crosses (bottom or right corner included).
    if let Some(mut crossing) = EdgeCrossing::biased(
        (ma.1, ma.0),
        (mb.1, mb.0),
        inner_first,
        inner_last,
        2 * HALF,
    ) {
        if y_major {
            // One pixel a row; the rows are inside the clip, the column may not be.
            let (left, right) = (runs.clip.0, runs.clip.2);
            for k in inner_first..inner_last + 1 {
                let m = crossing.column();
                crossing.advance();
                if m >= left && m < right && !runs.span(k, m, m + 1) {
                    return;
                }
            }
        } else {
            // Runs of columns on one row.
            let (mut start, mut row) = (inner_first, crossing.column());
            for k in inner_first..inner_last + 1 {
                let m = crossing.column();
                crossing.advance();
                if m != row {
                    if !runs.span(row, start, k) {
                        return;
                    }
                    (start, row) = (k, m);
                }
            }
            if !runs.span(row, start, inner_last + 1) {
                return;
            }
        }
    }
    for k in inner_last + 1..last + 1 {
        if !near_end(k, &mut runs) {
            return;
        }
    }
    runs.flush();
}
