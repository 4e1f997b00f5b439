//! The span shaders of the shapes filled by a [`Paint`] (polygons, lines): the paint's row fill
//! into a framebuffer, its `draw_row` into any `DrawTarget`, or a closure.

use embedded_graphics::prelude::*;

use super::framebuffer::SliceFramebuffer;
use crate::paint::Paint;
use crate::raster::walk::Span;
use crate::raster::SpanShader;

/// The paint's row fill of each span, into
/// the framebuffer's row `y − top` (a band's buffer starts at the frame's row `top`).
pub(crate) struct PaintIntoSlice<'f, 'a, 'p, P: Paint> {
    pub(crate) framebuffer: &'f mut SliceFramebuffer<'a, P::Color>,
    pub(crate) paint: &'p P,
    pub(crate) top: i32,
}

impl<P: Paint> SpanShader<0> for PaintIntoSlice<'_, '_, '_, P> {
    type Steps = ();

    #[inline(always)]
    fn prepare(&mut self, _: [u32; 0]) {}

    #[inline(always)]
    fn span(&mut self, _: &(), span: Span, _: [u32; 0]) {
        // The spans are clipped to the framebuffer's rows in the frame.
        if let Some(row) = self.framebuffer.clipped_span_mut(
            span.y.wrapping_sub(self.top),
            span.x_start,
            span.x_end,
        ) {
            self.paint.paint_row(span.y, span.x_start, row);
        }
    }
}

/// The paint's `draw_row` a span,
/// stopping at the first error.
pub(crate) struct PaintToTarget<'t, 'p, D: DrawTarget, P> {
    pub(crate) target: &'t mut D,
    pub(crate) paint: &'p P,
    pub(crate) result: Result<(), D::Error>,
}

impl<D: DrawTarget, P: Paint<Color = D::Color>> SpanShader<0> for PaintToTarget<'_, '_, D, P> {
    type Steps = ();

    #[inline(always)]
    fn prepare(&mut self, _: [u32; 0]) {}

    #[inline(always)]
    fn span(&mut self, _: &(), span: Span, _: [u32; 0]) {
        if self.result.is_ok() {
            self.result = self
                .paint
                .draw_row(self.target, span.y, span.x_start, span.len());
        }
    }

    #[inline(always)]
    fn stopped(&self) -> bool {
        self.result.is_err()
    }
}

/// A closure as a span shader (the shapes' `for_each_span`).
pub(crate) struct Calls<F>(pub(crate) F);

impl<F: FnMut(i32, i32, i32)> SpanShader<0> for Calls<F> {
    type Steps = ();

    #[inline(always)]
    fn prepare(&mut self, _: [u32; 0]) {}

    #[inline(always)]
    fn span(&mut self, _: &(), span: Span, _: [u32; 0]) {
        (self.0)(span.y, span.x_start, span.x_end);
    }
}
