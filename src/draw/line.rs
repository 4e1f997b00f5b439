//! Thin lines and polylines between sub-pixel points, under the diamond-exit rule.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use embedded_raster::{Line, Polyline, SliceFramebuffer};
//!
//! let mut pixels = [Rgb565::BLACK; 32 * 16];
//! let mut fb = SliceFramebuffer::new(&mut pixels, 32, 16).unwrap();
//! Line::new((0.5, 0.5), (20.5, 5.5), Rgb565::WHITE).draw_into(&mut fb);
//! assert_eq!(fb.get(0, 0), Some(Rgb565::WHITE)); // the start's pixel
//! assert_eq!(fb.get(20, 5), Some(Rgb565::BLACK)); // the end's is the next segment's
//! // A polyline: each vertex's pixel drawn once.
//! let points = [(1.0, 14.0), (10.25, 8.5), (18.0, 14.0), (30.5, 2.0)];
//! Polyline::new(&points, Rgb565::GREEN).draw(&mut fb).unwrap();
//! ```

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::framebuffer::SliceFramebuffer;
use super::painted::{draw, draw_rows, Calls, PaintedShape};
use super::stroke::{Stroke, Stroked, StrokedPoints};
use crate::fixed_point::{Coord, ToCoord};
use crate::paint::Paint;
use crate::raster::line::draw_line;
use crate::raster::SpanShader;

/// A thin line from `start` to `end` (sub-pixel points, any [`Coord`]), one pixel wide.
///
/// It draws the pixels whose diamond (`|dx| + |dy| < ½` around the centre, with its lower edges
/// included) the segment leaves — Direct3D's and OpenGL's diamond-exit rule: a pixel the segment
/// only enters, such as the one its end lies in, is left to the next segment of a polyline, so
/// connected lines draw each shared point once. Points on pixel centres give Bresenham's line
/// without its last pixel.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Gray8, prelude::*};
/// use embedded_raster::{Line, SliceFramebuffer};
///
/// let mut pixels = [Gray8::BLACK; 8 * 4];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 8, 4).unwrap();
/// Line::new((0.5, 1.5), (7.5, 1.5), Gray8::WHITE).draw_into(&mut fb);
/// let row: Vec<u8> = (0..8).map(|x| fb.get(x, 1).unwrap().luma()).collect();
/// assert_eq!(row, [255, 255, 255, 255, 255, 255, 255, 0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Line<P> {
    /// Where it starts (its pixel drawn when the line leaves it).
    pub start: (Coord, Coord),
    /// Where it ends (its pixel not drawn).
    pub end: (Coord, Coord),
    /// The paint: a colour, or a gradient.
    pub paint: P,
}

impl<P: Paint> Line<P> {
    /// The line from `start` to `end` (`f32`, `f64` or [`Coord`] pairs) in `paint`.
    pub fn new<T: ToCoord>(start: (T, T), end: (T, T), paint: P) -> Self {
        Line {
            start: (start.0.to_coord(), start.1.to_coord()),
            end: (end.0.to_coord(), end.1.to_coord()),
            paint,
        }
    }

    /// Draws into a [`SliceFramebuffer`]: the same pixels as [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, P::Color>) {
        let clip = framebuffer.bounding_box();
        draw_rows(self, framebuffer, &clip);
    }

    /// The first and last rows it may draw (a superset).
    pub fn rows(&self) -> Option<(i32, i32)> {
        let (a, b) = (self.start.1.to_bits(), self.end.1.to_bits());
        Some(((a.min(b) >> 8) - 1, (a.max(b) >> 8) + 1))
    }

    /// The line drawn `stroke.width` wide with its caps: a polygon.
    pub fn stroked(self, stroke: Stroke) -> Stroked<'static, Coord, P> {
        Stroked {
            points: StrokedPoints::Line([self.start, self.end]),
            paint: self.paint,
            stroke,
        }
    }

    /// Calls `f(y, x_start, x_end)` for each run of the line's pixels inside `clip` that lie on
    /// one row (`x_end` exclusive).
    pub fn for_each_span(&self, clip: &Rectangle, f: impl FnMut(i32, i32, i32)) {
        draw_line(raw(self.start), raw(self.end), clip, &mut Calls(f));
    }
}

fn raw((x, y): (Coord, Coord)) -> (i32, i32) {
    (x.to_bits(), y.to_bits())
}

impl<P: Paint> PaintedShape for Line<P> {
    type Paint = P;

    fn paint(&self) -> &P {
        &self.paint
    }

    fn spans<S: SpanShader<0>>(&self, clip: &Rectangle, shader: &mut S) {
        draw_line(raw(self.start), raw(self.end), clip, shader);
    }
}

impl<P: Paint> Drawable for Line<P> {
    type Color = P::Color;
    type Output = ();

    fn draw<D: DrawTarget<Color = P::Color>>(&self, target: &mut D) -> Result<(), D::Error> {
        draw(self, target)
    }
}

/// Connected thin lines through `points` (borrowed), each segment a [`Line`]: every point
/// between two segments is drawn once, the last point not at all.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::{Polyline, SliceFramebuffer};
///
/// let mut pixels = [Rgb565::BLACK; 16 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
/// let plot = [(0.5, 12.5), (4.5, 3.5), (8.5, 9.5), (15.5, 1.5)];
/// Polyline::new(&plot, Rgb565::CYAN).draw_into(&mut fb);
/// assert_eq!(fb.get(4, 3), Some(Rgb565::CYAN));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Polyline<'a, T, P> {
    points: &'a [(T, T)],
    paint: P,
}

impl<'a, T: ToCoord + Copy, P: Paint> Polyline<'a, T, P> {
    /// The polyline through `points` (`f32`, `f64` or [`Coord`] pairs) in `paint`.
    pub fn new(points: &'a [(T, T)], paint: P) -> Self {
        Polyline { points, paint }
    }

    /// The polyline drawn `stroke.width` wide with its caps and joins: polygons.
    pub fn stroked(self, stroke: Stroke) -> Stroked<'a, T, P> {
        Stroked {
            points: StrokedPoints::Slice(self.points),
            paint: self.paint,
            stroke,
        }
    }

    fn lines(&self) -> impl Iterator<Item = ((i32, i32), (i32, i32))> + '_ {
        let raw = |&(x, y): &(T, T)| (x.to_coord().to_bits(), y.to_coord().to_bits());
        self.points
            .windows(2)
            .filter_map(move |w| Some((raw(w.first()?), raw(w.get(1)?))))
    }

    /// Draws into a [`SliceFramebuffer`]: the same pixels as [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, P::Color>) {
        let clip = framebuffer.bounding_box();
        draw_rows(self, framebuffer, &clip);
    }

    /// The first and last rows it may draw (a superset), `None` for fewer than two points.
    pub fn rows(&self) -> Option<(i32, i32)> {
        let ys = self.points.iter().map(|p| p.1.to_coord().to_bits());
        (self.points.len() >= 2).then_some(())?;
        Some(((ys.clone().min()? >> 8) - 1, (ys.max()? >> 8) + 1))
    }
}

impl<T: ToCoord + Copy, P: Paint> PaintedShape for Polyline<'_, T, P> {
    type Paint = P;

    fn paint(&self) -> &P {
        &self.paint
    }

    fn spans<S: SpanShader<0>>(&self, clip: &Rectangle, shader: &mut S) {
        for (a, b) in self.lines() {
            if shader.stopped() {
                break;
            }
            draw_line(a, b, clip, shader);
        }
    }
}

impl<T: ToCoord + Copy, P: Paint> Drawable for Polyline<'_, T, P> {
    type Color = P::Color;
    type Output = ();

    fn draw<D: DrawTarget<Color = P::Color>>(&self, target: &mut D) -> Result<(), D::Error> {
        draw(self, target)
    }
}
