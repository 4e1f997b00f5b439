//! Filled polygons: any number of closed contours in a caller-sized store, drawn by any
//! [`Paint`] under the non-zero or even-odd rule.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use embedded_raster::{FillRule, Polygon, SliceFramebuffer};
//!
//! let mut pixels = [Rgb565::BLACK; 32 * 32];
//! let mut fb = SliceFramebuffer::new(&mut pixels, 32, 32).unwrap();
//! // A square with a square hole: two contours.
//! let mut frame = Polygon::<8>::new();
//! frame.add_contour(&[(2.0, 2.0), (30.0, 2.0), (30.0, 30.0), (2.0, 30.0)])?;
//! frame.add_contour(&[(10.0, 10.0), (22.0, 10.0), (22.0, 22.0), (10.0, 22.0)])?;
//! frame.filled(Rgb565::RED).with_rule(FillRule::EvenOdd).draw_into(&mut fb);
//! assert_eq!(fb.get(5, 5), Some(Rgb565::RED));
//! assert_eq!(fb.get(16, 16), Some(Rgb565::BLACK)); // in the hole
//! # Ok::<(), embedded_raster::PolygonFull>(())
//! ```

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::framebuffer::SliceFramebuffer;
use super::painted::{draw, draw_rows, Calls, PaintedShape};
use crate::fixed_point::{Coord, ToCoord};
use crate::paint::Paint;
use crate::raster::polygon::{fill_polygon, EdgeCrossing};
use crate::raster::{FillRule, SpanShader};

/// A polygon of up to `N` vertices in one or more closed contours, stored inline (no heap).
///
/// Each contour is closed by an edge from its last vertex back to its first. Contours may be
/// convex or not, cross themselves or each other, and nest: [`FillRule`] says which regions
/// are inside. Vertices are [`Coord`]s (1/256 px), any value: far off-screen parts are clipped
/// exactly.
///
/// Drawing it ([`filled`](Self::filled)) keeps one edge crossing (32 bytes) for each vertex on
/// the stack: `32·N` bytes, 2 KiB for `N = 64`.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::{Polygon, SliceFramebuffer};
///
/// let mut pixels = [Rgb565::BLACK; 16 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
/// // An arrow, not convex.
/// let arrow = Polygon::<7>::from_points(&[
///     (1.0, 6.0), (9.0, 6.0), (9.0, 2.0), (15.0, 8.0), (9.0, 14.0), (9.0, 10.0), (1.0, 10.0),
/// ])?;
/// arrow.filled(Rgb565::GREEN).draw(&mut fb).unwrap();
/// assert_eq!(fb.get(2, 8), Some(Rgb565::GREEN));
/// assert_eq!(fb.get(2, 3), Some(Rgb565::BLACK));
/// // Too many vertices for the store: an error, nothing dropped silently.
/// assert!(Polygon::<2>::from_points(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]).is_err());
/// # Ok::<(), embedded_raster::PolygonFull>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Polygon<const N: usize> {
    points: [(Coord, Coord); N],
    /// `ends[i]`: vertex `i` is the last of its contour (the last vertex always is).
    ends: [bool; N],
    len: usize,
}

/// A [`Polygon`]'s store is full: the vertex was not added.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PolygonFull {
    /// The polygon's capacity (`N`).
    pub capacity: usize,
}

impl core::fmt::Display for PolygonFull {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "the polygon holds at most {} vertices", self.capacity)
    }
}

impl core::error::Error for PolygonFull {}

impl<const N: usize> Default for Polygon<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> Polygon<N> {
    /// A polygon with no vertices.
    pub const fn new() -> Self {
        Polygon {
            points: [(Coord::ZERO, Coord::ZERO); N],
            ends: [false; N],
            len: 0,
        }
    }

    /// A polygon of one contour through `points` (`f32`, `f64` or [`Coord`] pairs).
    pub fn from_points<P: ToCoord + Copy>(points: &[(P, P)]) -> Result<Self, PolygonFull> {
        let mut polygon = Self::new();
        polygon.add_contour(points)?;
        Ok(polygon)
    }

    /// Adds `point` to the current contour (the first point after [`close`](Self::close) starts
    /// a new one).
    pub fn push<P: ToCoord>(&mut self, (x, y): (P, P)) -> Result<(), PolygonFull> {
        let capacity = N;
        let (Some(point), Some(end)) = (self.points.get_mut(self.len), self.ends.get_mut(self.len))
        else {
            return Err(PolygonFull { capacity });
        };
        *point = (x.to_coord(), y.to_coord());
        *end = false;
        self.len += 1;
        Ok(())
    }

    /// Ends the current contour: the next vertex starts another.
    pub fn close(&mut self) {
        if let Some(end) = self.len.checked_sub(1).and_then(|i| self.ends.get_mut(i)) {
            *end = true;
        }
    }

    /// Adds a whole contour through `points` (closed). If the store is full, nothing is added.
    pub fn add_contour<P: ToCoord + Copy>(&mut self, points: &[(P, P)]) -> Result<(), PolygonFull> {
        if points.len() > N - self.len {
            return Err(PolygonFull { capacity: N });
        }
        self.close();
        for &point in points {
            self.push(point)?;
        }
        self.close();
        Ok(())
    }

    /// The vertices, every contour's in order.
    pub fn points(&self) -> &[(Coord, Coord)] {
        self.points.get(..self.len).unwrap_or(&[])
    }

    /// The number of vertices.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether it has no vertices.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Removes every vertex.
    pub fn clear(&mut self) {
        self.len = 0;
    }

    /// The edges, as pairs of raw sub-pixel points: each vertex to the next of its contour, and
    /// each contour's last back to its first.
    pub(crate) fn edges(&self) -> impl Iterator<Item = ((i32, i32), (i32, i32))> + '_ {
        let raw = |(x, y): (Coord, Coord)| (x.to_bits(), y.to_bits());
        let points = self.points();
        let ends = self.ends.get(..self.len).unwrap_or(&[]);
        let mut start = 0;
        points
            .iter()
            .zip(ends)
            .enumerate()
            .map(move |(i, (&p, &end))| {
                let to = if end || i + 1 == points.len() {
                    let first = start;
                    start = i + 1;
                    first
                } else {
                    i + 1
                };
                (raw(p), raw(points.get(to).copied().unwrap_or(p)))
            })
    }

    /// The polygon filled with `paint` (a colour or a gradient) under the non-zero rule
    /// ([`with_rule`](FilledPolygon::with_rule) to change it).
    pub fn filled<P: Paint>(&self, paint: P) -> FilledPolygon<'_, N, P> {
        FilledPolygon {
            polygon: self,
            paint,
            rule: FillRule::NonZero,
        }
    }

    /// Calls `f(y, x_start, x_end)` for each covered span inside `clip` under `rule`, top to
    /// bottom, left to right (`x_end` exclusive).
    pub fn for_each_span(&self, rule: FillRule, clip: &Rectangle, f: impl FnMut(i32, i32, i32)) {
        let mut scratch = [EdgeCrossing::default(); N];
        let mut shader = Calls(f);
        fill_polygon(self.edges(), &mut scratch, rule, clip, &mut shader);
    }
}

/// A [`Polygon`] with its paint and fill rule: drawable into any `DrawTarget` ([`Drawable`]) or
/// a [`SliceFramebuffer`] ([`draw_into`](Self::draw_into)), the same pixels.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::{FillRule, Polygon, SliceFramebuffer};
///
/// let mut pixels = [Rgb565::BLACK; 16 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
/// // A pentagram: its centre has winding number 2.
/// let star = Polygon::<5>::from_points(&[(8.0, 0.5), (12.7, 15.0), (0.4, 6.0), (15.6, 6.0), (3.3, 15.0)])?;
/// star.filled(Rgb565::BLUE).with_rule(FillRule::EvenOdd).draw_into(&mut fb);
/// assert_eq!(fb.get(8, 9), Some(Rgb565::BLACK));
/// star.filled(Rgb565::BLUE).draw_into(&mut fb); // non-zero
/// assert_eq!(fb.get(8, 9), Some(Rgb565::BLUE));
/// # Ok::<(), embedded_raster::PolygonFull>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct FilledPolygon<'p, const N: usize, P> {
    polygon: &'p Polygon<N>,
    paint: P,
    rule: FillRule,
}

impl<const N: usize, P: Paint> FilledPolygon<'_, N, P> {
    /// The same fill under `rule`.
    pub fn with_rule(self, rule: FillRule) -> Self {
        FilledPolygon { rule, ..self }
    }

    /// Draws into a [`SliceFramebuffer`] with the paint's row fills: the same pixels as
    /// [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, P::Color>) {
        let clip = framebuffer.bounding_box();
        draw_rows(self, framebuffer, &clip);
    }

    /// The first and last rows it may cover (a superset), `None` if none: those between its
    /// highest and lowest vertex.
    pub fn rows(&self) -> Option<(i32, i32)> {
        let ys = self.polygon.points().iter().map(|p| p.1.to_bits());
        let (top, bottom) = (ys.clone().min()?, ys.max()?);
        let (first, last) = (
            crate::raster::edge::first_centre_from(top),
            crate::raster::edge::last_centre_before(bottom),
        );
        (first <= last).then_some((first, last))
    }
}

impl<const N: usize, P: Paint> PaintedShape for FilledPolygon<'_, N, P> {
    type Paint = P;

    fn paint(&self) -> &P {
        &self.paint
    }

    fn spans<S: SpanShader<0>>(&self, clip: &Rectangle, shader: &mut S) {
        let mut scratch = [EdgeCrossing::default(); N];
        fill_polygon(self.polygon.edges(), &mut scratch, self.rule, clip, shader);
    }
}

impl<const N: usize, P: Paint> Drawable for FilledPolygon<'_, N, P> {
    type Color = P::Color;
    type Output = ();

    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = P::Color>,
    {
        draw(self, target)
    }
}
