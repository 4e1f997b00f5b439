//! Wide lines: a line or polyline stroked with a width, caps and joins, drawn as polygons.
//!
//! Each segment is the rectangle of the stroke's width around it; each point between two
//! segments gets its join (a miter, a bevel or a disk) and the two ends their caps (none, a
//! half-width extension or a disk). Every piece is a polygon filled under the exact rule, so a
//! piece's edges are exact; the pieces' corners are rounded to 1/256 px and the disks are
//! 32-gons (within `r·(1 − cos(π/32))`, 0.5 % of the half-width, of the circle). Pieces overlap
//! where they meet: an opaque paint draws the union, a translucent one
//! ([`paint::Translucent`](crate::paint::Translucent)) blends the overlaps twice.

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::framebuffer::SliceFramebuffer;
use super::painted::{draw, draw_rows, PaintedShape};
use super::polygon::Polygon;
use crate::fixed_point::{Coord, ToCoord};
use crate::paint::Paint;
use crate::raster::polygon::{fill_polygon, EdgeCrossing};
use crate::raster::{FillRule, SpanShader};

/// How a stroke ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Cap {
    /// At the end point.
    #[default]
    Butt,
    /// Half the width past the end point.
    Square,
    /// A half disk around the end point.
    Round,
}

/// How a stroke turns at a point between two segments.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Join {
    /// The outer edges extended to where they meet, or a bevel where that tip would be more
    /// than twice the width from the point (SVG's default miter limit: segments meeting at
    /// less than about 29°).
    #[default]
    Miter,
    /// The outer corners joined by a straight edge.
    Bevel,
    /// A disk around the point.
    Round,
}

/// A width, caps and joins for [`Line::stroked`](crate::Line::stroked) and
/// [`Polyline::stroked`](crate::Polyline::stroked).
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::{Cap, Join, Polyline, SliceFramebuffer, Stroke};
///
/// let mut pixels = [Rgb565::BLACK; 48 * 32];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 48, 32).unwrap();
/// let stroke = Stroke::new(4.0).with_cap(Cap::Round).with_join(Join::Round);
/// let points = [(4.0, 26.0), (20.0, 6.0), (30.0, 20.0), (44.0, 8.0)];
/// Polyline::new(&points, Rgb565::CSS_GOLD).stroked(stroke).draw_into(&mut fb);
/// assert_eq!(fb.get(20, 7), Some(Rgb565::CSS_GOLD));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stroke {
    /// The width (negative widths draw nothing).
    pub width: Coord,
    /// The ends.
    pub cap: Cap,
    /// The turns.
    pub join: Join,
}

impl Stroke {
    /// A stroke `width` wide (`f32`, `f64` or [`Coord`]), butt caps, miter joins.
    pub fn new(width: impl ToCoord) -> Self {
        Stroke {
            width: width.to_coord(),
            cap: Cap::Butt,
            join: Join::Miter,
        }
    }

    /// The same stroke with `cap` at both ends.
    pub fn with_cap(self, cap: Cap) -> Self {
        Stroke { cap, ..self }
    }

    /// The same stroke with `join` at every turn.
    pub fn with_join(self, join: Join) -> Self {
        Stroke { join, ..self }
    }
}

/// Vertices of a piece: a disk's 32.
const PIECE: usize = 32;

/// `cos` and `sin` of `k·π/16`, `k` in `0..32`, in 16 fractional bits.
const CIRCLE: [(i64, i64); 32] = {
    // Octant values, rounded: cos(k·π/16) for k = 0..=8.
    const C: [i64; 9] = [65536, 64277, 60547, 54491, 46341, 36410, 25080, 12785, 0];
    let mut t = [(0, 0); 32];
    let mut k = 0;
    while k < 32 {
        let c = match k % 32 {
            k @ 0..=8 => C[k],
            k @ 9..=16 => -C[16 - k],
            k @ 17..=24 => -C[k - 16],
            k => C[32 - k],
        };
        let s = match (k + 24) % 32 {
            k @ 0..=8 => C[k],
            k @ 9..=16 => -C[16 - k],
            k @ 17..=24 => -C[k - 16],
            k => C[32 - k],
        };
        t[k] = (c, s);
        k += 1;
    }
    t
};

/// `n / d` rounded to nearest (`d > 0`).
fn div_round(n: i128, d: i128) -> i64 {
    let q = if n >= 0 {
        (n + d / 2) / d
    } else {
        -((-n + d / 2) / d)
    };
    q.clamp(i128::from(i32::MIN), i128::from(i32::MAX)) as i64
}

/// A point offset by `v`, saturated to the `Coord` range.
fn at(p: (i64, i64), v: (i64, i64)) -> (Coord, Coord) {
    let c = |x: i64| Coord::from_bits(x.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32);
    (c(p.0 + v.0), c(p.1 + v.1))
}

/// The offset `h` long perpendicular to `d` (to its right on screen, y down), rounded; `None`
/// for a zero `d`.
fn normal(d: (i64, i64), h: i64) -> Option<(i64, i64)> {
    // The direction alone matters: shifted below 2³⁰ so that its square fits.
    let bits = 64 - (d.0.unsigned_abs() | d.1.unsigned_abs()).leading_zeros();
    let s = bits.saturating_sub(30);
    let (x, y) = (d.0 >> s, d.1 >> s);
    let len = ((x * x + y * y) as u64).isqrt();
    if len == 0 {
        return None;
    }
    let len = i128::from(len);
    let h = i128::from(h);
    Some((
        div_round(-i128::from(y) * h, len),
        div_round(i128::from(x) * h, len),
    ))
}

/// The pieces of a stroke through `points` (raw sub-pixels), each handed to `piece`.
fn pieces(
    points: impl Iterator<Item = (i64, i64)> + Clone,
    stroke: &Stroke,
    mut piece: impl FnMut(&Polygon<PIECE>),
) {
    let h = i64::from(stroke.width.to_bits()) / 2;
    if h <= 0 {
        return;
    }
    let mut polygon = Polygon::<PIECE>::new();
    let mut emit = |corners: &mut dyn Iterator<Item = (Coord, Coord)>| {
        polygon.clear();
        for c in corners {
            let _ = polygon.push(c);
        }
        piece(&polygon);
    };
    let disk = |p: (i64, i64)| {
        CIRCLE.iter().map(move |&(c, s)| {
            at(
                p,
                (
                    div_round(i128::from(h * c), 1 << 16),
                    div_round(i128::from(h * s), 1 << 16),
                ),
            )
        })
    };
    // Distinct consecutive points only: a zero-length segment has no direction.
    let mut distinct = points.clone().peekable();
    let mut previous: Option<((i64, i64), (i64, i64))> = None; // (point, normal of the last segment)
    let first_point = distinct.peek().copied();
    let mut last_point = first_point;
    let mut first_normal = None;
    let mut segments = 0;
    while let Some(a) = distinct.next() {
        // The next point that differs from `a`.
        let b = loop {
            match distinct.peek() {
                Some(&b) if b == a => {
                    distinct.next();
                }
                other => break other.copied(),
            }
        };
        let Some(b) = b else { break };
        let d = (b.0 - a.0, b.1 - a.1);
        let Some(n) = normal(d, h) else { continue };
        segments += 1;
        last_point = Some(b);
        if first_normal.is_none() {
            first_normal = Some((a, n, d));
        }
        // The join at `a` with the segment before.
        if let Some((_, n0)) = previous {
            join(a, (n0, n, d), h, stroke.join, &mut emit, &disk);
        }
        // The segment's rectangle; square caps extend the first and last by `h`.
        let t = (n.1, -n.0); // along d, h long
        let (mut s, mut e) = (a, b);
        if stroke.cap == Cap::Square {
            if segments == 1 {
                s = (a.0 - t.0, a.1 - t.1);
            }
            // The last segment: every point after `b` is `b` again.
            let mut rest = distinct.clone();
            rest.next();
            if rest.all(|q| q == b) {
                e = (b.0 + t.0, b.1 + t.1);
            }
        }
        emit(&mut [at(s, n), at(e, n), at(e, (-n.0, -n.1)), at(s, (-n.0, -n.1))].into_iter());
        previous = Some((b, n));
    }
    if stroke.cap == Cap::Round && segments > 0 {
        if let Some(p) = first_point {
            emit(&mut disk(p));
        }
        if let Some(p) = last_point {
            emit(&mut disk(p));
        }
    }
}

/// The join at `p` between a segment with normal `n0` and the next, with normal `n1` and
/// direction `d1` (`h` long normals).
fn join<D: Iterator<Item = (Coord, Coord)>>(
    p: (i64, i64),
    (n0, n1, d1): ((i64, i64), (i64, i64), (i64, i64)),
    h: i64,
    kind: Join,
    emit: &mut impl FnMut(&mut dyn Iterator<Item = (Coord, Coord)>),
    disk: &impl Fn((i64, i64)) -> D,
) {
    if kind == Join::Round {
        emit(&mut disk(p));
        return;
    }
    // The turn: toward the normals' side (clockwise on screen) when n0 · d1 > 0; the join fills
    // the outer side.
    let turn = i128::from(n0.0) * i128::from(d1.0) + i128::from(n0.1) * i128::from(d1.1);
    if turn == 0 {
        return;
    }
    let s = if turn > 0 { -1 } else { 1 };
    let (o0, o1) = ((s * n0.0, s * n0.1), (s * n1.0, s * n1.1));
    // The miter's tip: (n0 + n1)·h² / (h² + n0·n1), within 4h of p (else a bevel).
    let h2 = i128::from(h) * i128::from(h);
    let dot = i128::from(n0.0) * i128::from(n1.0) + i128::from(n0.1) * i128::from(n1.1);
    let denominator = h2 + dot;
    // |tip| = h·√(2 / (1 + cos θ)) ≤ 4h ⇔ 1 + cos θ ≥ ⅛ ⇔ 8·(h² + n0·n1) ≥ h².
    if kind == Join::Miter && 8 * denominator >= h2 && denominator > 0 {
        let tip = (
            div_round(i128::from(o0.0 + o1.0) * h2, denominator),
            div_round(i128::from(o0.1 + o1.1) * h2, denominator),
        );
        emit(&mut [at(p, (0, 0)), at(p, o0), at(p, tip), at(p, o1)].into_iter());
    } else {
        emit(&mut [at(p, (0, 0)), at(p, o0), at(p, o1)].into_iter());
    }
}

/// A [`Line`](crate::Line) or [`Polyline`](crate::Polyline) with a [`Stroke`]: drawable into any
/// `DrawTarget` ([`Drawable`]) or a [`SliceFramebuffer`] ([`draw_into`](Self::draw_into)).
#[derive(Debug, Clone, Copy)]
pub struct Stroked<'a, T, P> {
    pub(crate) points: StrokedPoints<'a, T>,
    pub(crate) paint: P,
    pub(crate) stroke: Stroke,
}

/// A stroke's points: a line's two or a polyline's slice.
#[derive(Debug, Clone, Copy)]
pub(crate) enum StrokedPoints<'a, T> {
    Line([(Coord, Coord); 2]),
    Slice(&'a [(T, T)]),
}

impl<T: ToCoord + Copy, P: Paint> Stroked<'_, T, P> {
    fn each_piece(&self, piece: impl FnMut(&Polygon<PIECE>)) {
        let raw = |(x, y): (Coord, Coord)| (i64::from(x.to_bits()), i64::from(y.to_bits()));
        match self.points {
            StrokedPoints::Line(points) => pieces(points.into_iter().map(raw), &self.stroke, piece),
            StrokedPoints::Slice(points) => pieces(
                points
                    .iter()
                    .map(|&(x, y)| raw((x.to_coord(), y.to_coord()))),
                &self.stroke,
                piece,
            ),
        }
    }

    /// Draws into a [`SliceFramebuffer`]: the same pixels as [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, P::Color>) {
        let clip = framebuffer.bounding_box();
        draw_rows(self, framebuffer, &clip);
    }

    /// The first and last rows it may draw (a superset): its points' and the width's.
    pub fn rows(&self) -> Option<(i32, i32)> {
        let (mut top, mut bottom) = (i64::MAX, i64::MIN);
        self.each_point(|y| {
            top = top.min(y);
            bottom = bottom.max(y);
        });
        let reach = i64::from(self.stroke.width.to_bits().max(0)) + 512;
        let row = |y: i64| (y >> 8).clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
        (top <= bottom).then(|| (row(top - reach), row(bottom + reach)))
    }

    fn each_point(&self, mut f: impl FnMut(i64)) {
        match self.points {
            StrokedPoints::Line(points) => points.iter().for_each(|p| f(p.1.to_bits().into())),
            StrokedPoints::Slice(points) => points
                .iter()
                .for_each(|p| f(p.1.to_coord().to_bits().into())),
        }
    }
}

impl<T: ToCoord + Copy, P: Paint> PaintedShape for Stroked<'_, T, P> {
    type Paint = P;

    fn paint(&self) -> &P {
        &self.paint
    }

    fn spans<S: SpanShader<0>>(&self, clip: &Rectangle, shader: &mut S) {
        let mut scratch = [EdgeCrossing::default(); PIECE];
        self.each_piece(|polygon| {
            if !shader.stopped() {
                fill_polygon(
                    polygon.edges(),
                    &mut scratch,
                    FillRule::NonZero,
                    clip,
                    shader,
                );
            }
        });
    }
}

impl<T: ToCoord + Copy, P: Paint> Drawable for Stroked<'_, T, P> {
    type Color = P::Color;
    type Output = ();

    fn draw<D: DrawTarget<Color = P::Color>>(&self, target: &mut D) -> Result<(), D::Error> {
        draw(self, target)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_circle_table_is_cos_and_sin() {
        for (k, &(c, s)) in CIRCLE.iter().enumerate() {
            let t = k as f64 * core::f64::consts::PI / 16.0;
            assert!((c as f64 / 65536.0 - libm_cos(t)).abs() < 1e-5, "cos {k}");
            assert!(
                (s as f64 / 65536.0 - libm_cos(t - core::f64::consts::FRAC_PI_2)).abs() < 1e-5,
                "sin {k}"
            );
        }
    }

    fn libm_cos(t: f64) -> f64 {
        // Taylor series to many terms: no std in the crate's unit tests.
        let t = t.rem_euclid(2.0 * core::f64::consts::PI);
        let (mut term, mut sum) = (1.0, 1.0);
        for i in 1..40 {
            term *= -t * t / ((2 * i - 1) * (2 * i)) as f64;
            sum += term;
        }
        sum
    }
}
