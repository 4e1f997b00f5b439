//! Triangles filled by any [`Paint`]: a gradient, or a plain colour.

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::framebuffer::SliceFramebuffer;
use super::painted::{draw, draw_rows, PaintedShape};
use crate::fixed_point::{pixel_centre, Coord, ToCoord};
use crate::paint::Paint;
use crate::raster::plane::Attributes;
use crate::raster::{shade, SpanShader};

/// A triangle filled by a [`Paint`] (a [`LinearGradient`](crate::LinearGradient), a
/// [`RadialGradient`](crate::RadialGradient), a plain colour): it covers exactly the pixels a
/// [`SolidTriangle`](crate::SolidTriangle) with the same corners covers, and each gets the
/// paint's colour at its position. [`draw_into`](Self::draw_into) and [`Drawable::draw`] give
/// the same pixels.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::paint::{LinearGradient, Stop, STOP_ONE};
/// use embedded_raster::{PaintedTriangle, SliceFramebuffer};
///
/// let mut pixels = [Rgb565::BLACK; 32 * 32];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 32, 32).unwrap();
/// // Red at the left edge to blue at the right, across the triangle.
/// let gradient = LinearGradient::new(
///     (0.0, 0.0),
///     (32.0, 0.0),
///     [Stop::new(0, Rgb565::RED), Stop::new(STOP_ONE, Rgb565::BLUE)],
/// )
/// .dithered();
/// let triangle = PaintedTriangle::new([(0.0, 0.0), (32.0, 0.0), (0.0, 32.0)], gradient);
/// triangle.draw_into(&mut fb);
/// // Red 31 − 31 · 0.5/32 = 30.5 at the centre of pixel (0, 0): dithered to 30 or 31.
/// assert!(fb.get(0, 0).unwrap().r() >= 30);
/// triangle.draw(&mut fb)?; // the same pixels through any DrawTarget
/// assert_eq!(fb.get(31, 31), Some(Rgb565::BLACK)); // outside
/// # Ok::<(), core::convert::Infallible>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PaintedTriangle<P> {
    /// The three corner positions, in either winding.
    pub points: [(Coord, Coord); 3],
    /// What fills it.
    pub paint: P,
}

impl<P: Paint> PaintedTriangle<P> {
    /// A triangle with corners `points` (`f32`, `f64` or [`Coord`] pairs, see [`ToCoord`])
    /// filled by `paint`.
    #[inline(always)]
    pub fn new<T: ToCoord>(points: [(T, T); 3], paint: P) -> Self {
        PaintedTriangle {
            points: points.map(|(x, y)| (x.to_coord(), y.to_coord())),
            paint,
        }
    }

    /// The triangle through the centres of pixels `points` (the embedded-graphics placement,
    /// see [`SolidTriangle::at_pixel_centres`](crate::SolidTriangle::at_pixel_centres)).
    pub fn at_pixel_centres(points: [Point; 3], paint: P) -> Self {
        PaintedTriangle {
            points: points.map(|p| (pixel_centre(p.x), pixel_centre(p.y))),
            paint,
        }
    }

    /// Draws into a [`SliceFramebuffer`]: the paint writes each covered span's slice
    /// ([`Paint::paint_row`]); the same pixels as [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, P::Color>) {
        let clip = framebuffer.bounding_box();
        draw_rows(self, framebuffer, &clip);
    }
}

impl<P: Paint> PaintedShape for PaintedTriangle<P> {
    type Paint = P;

    fn paint(&self) -> &P {
        &self.paint
    }

    fn spans<S: SpanShader<0>>(&self, clip: &Rectangle, shader: &mut S) {
        shade(self.points, &Attributes::channels([[]; 3]), clip, shader);
    }
}

impl<P: Paint> Drawable for PaintedTriangle<P> {
    type Color = P::Color;
    type Output = ();

    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = P::Color>,
    {
        draw(self, target)
    }
}
