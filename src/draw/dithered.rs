//! Gouraud triangles with ordered dithering: the 5-6-5 formats' banding removed.

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::framebuffer::SliceFramebuffer;
use super::triangle::GouraudTriangle;
use crate::color::{DitheredColors, GouraudColor, SpanSteps};
use crate::raster::plane::Attributes;
use crate::raster::walk::Span;
use crate::raster::{shade, SpanShader};

/// A [`GouraudTriangle`] drawn with ordered dithering (4×4 Bayer): each channel of each pixel is
/// the floor or the ceiling of its interpolated value (on 5-6-5, of a value within 2⁻⁶ LSB of
/// it: [`GouraudColor::fill_dithered`]; where the plain triangle rounds to nearest), chosen by
/// the pixel's position so that areas average the exact colour. On 5-6-5
/// formats it removes the visible bands of a slow shade. The same pixels as the plain triangle
/// covers; [`draw_into`](Self::draw_into) and [`Drawable::draw`] give the same colours. Made by
/// [`GouraudTriangle::dithered`].
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::{GouraudTriangle, SliceFramebuffer, Vertex};
///
/// let mut pixels = [Rgb565::BLACK; 64 * 8];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 64, 8).unwrap();
/// // Red from 0 to 4 over 64 pixels: 16 pixels a level, smoothly dithered between levels.
/// let dark = Rgb565::new(0, 0, 0);
/// let triangle = GouraudTriangle::new([
///     Vertex::new(0.0, 0.0, dark),
///     Vertex::new(128.0, 0.0, Rgb565::new(8, 0, 0)),
///     Vertex::new(0.0, 128.0, dark),
/// ]);
/// triangle.dithered().draw_into(&mut fb);
/// // Red 8 · 40.5/128 = 2.53 at the centre of pixel (40, 0): 2 or 3.
/// assert!((2..=3).contains(&fb.get(40, 0).unwrap().r()));
/// triangle.dithered().draw(&mut fb)?; // the same pixels through any DrawTarget
/// # Ok::<(), core::convert::Infallible>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DitheredTriangle<C> {
    /// The triangle.
    pub triangle: GouraudTriangle<C>,
}

impl<C: GouraudColor> GouraudTriangle<C> {
    /// This triangle drawn with ordered dithering ([`DitheredTriangle`]).
    pub fn dithered(self) -> DitheredTriangle<C> {
        DitheredTriangle { triangle: self }
    }
}

impl<C: GouraudColor> DitheredTriangle<C> {
    /// Draws into a [`SliceFramebuffer`] with slice writes: the same pixels as
    /// [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, C>) {
        let clip = framebuffer.bounding_box();
        let mut shader = DitherIntoSlice { framebuffer };
        shade(self.positions(), &self.channels(), &clip, &mut shader);
    }

    fn positions(&self) -> [(crate::Coord, crate::Coord); 3] {
        self.triangle.vertices.map(|v| v.position())
    }

    fn channels(&self) -> Attributes<3> {
        Attributes::channels(self.triangle.vertices.map(|v| v.color.channels()))
    }
}

impl<C: GouraudColor> Drawable for DitheredTriangle<C> {
    type Color = C;
    type Output = ();

    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        let clip = target.bounding_box();
        let mut shader = DitherToTarget {
            target,
            result: Ok(()),
        };
        shade(self.positions(), &self.channels(), &clip, &mut shader);
        shader.result
    }
}

/// The span shader of [`DitheredTriangle::draw_into`].
struct DitherIntoSlice<'f, 'a, C> {
    framebuffer: &'f mut SliceFramebuffer<'a, C>,
}

impl<C: GouraudColor> SpanShader<3> for DitherIntoSlice<'_, '_, C> {
    type Steps = SpanSteps;

    scan_small_with_walk_planes!();

    #[inline(always)]
    fn prepare(&mut self, step: [u32; 3]) -> SpanSteps {
        C::prepare_steps(step)
    }

    #[inline(always)]
    fn span(&mut self, steps: &SpanSteps, span: Span, start: [u32; 3]) {
        // The spans of the walk are clipped to the framebuffer.
        if let Some(row) = self
            .framebuffer
            .clipped_span_mut(span.y, span.x_start, span.x_end)
        {
            C::fill_dithered(row, span.x_start, span.y, start, steps);
        }
    }
}

/// The span shader of [`DitheredTriangle`]'s [`Drawable::draw`]: one `fill_contiguous` a span.
struct DitherToTarget<'t, D: DrawTarget> {
    target: &'t mut D,
    result: Result<(), D::Error>,
}

impl<C: GouraudColor, D: DrawTarget<Color = C>> SpanShader<3> for DitherToTarget<'_, D> {
    type Steps = SpanSteps;

    #[inline(always)]
    fn prepare(&mut self, step: [u32; 3]) -> SpanSteps {
        C::prepare_steps(step)
    }

    #[inline(always)]
    fn span(&mut self, steps: &SpanSteps, span: Span, start: [u32; 3]) {
        if self.result.is_err() {
            return;
        }
        let area = Rectangle::new(Point::new(span.x_start, span.y), Size::new(span.len(), 1));
        let colors =
            DitheredColors::<C>::new(start, steps, (span.x_start, span.y), span.len() as usize);
        self.result = self.target.fill_contiguous(&area, colors);
    }

    #[inline(always)]
    fn stopped(&self) -> bool {
        self.result.is_err()
    }
}
