//! What the shapes filled by a [`Paint`] (polygons, lines, strokes) share: a shape hands its
//! covered spans to a span shader ([`PaintedShape`]), and the paint fills them — its row fill
//! into a framebuffer or a band's buffer ([`draw_rows`]), its `draw_row` into any `DrawTarget`
//! ([`draw`]), or a closure ([`Calls`]).

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::framebuffer::SliceFramebuffer;
use crate::paint::Paint;
use crate::raster::walk::Span;
use crate::raster::SpanShader;

/// A shape whose covered spans a paint fills.
pub(crate) trait PaintedShape {
    /// What fills it.
    type Paint: Paint;

    /// The paint.
    fn paint(&self) -> &Self::Paint;

    /// Hands its covered spans inside `clip` to `shader`, stopping when the shader has stopped.
    fn spans<S: SpanShader<0>>(&self, clip: &Rectangle, shader: &mut S);
}

/// Draws the rows of `rect` (frame coordinates) of `shape` into `framebuffer`, whose first row
/// is the frame's row `rect`'s top (a band's buffer, or the whole frame for `draw_into`): the
/// frame's pixels there, as the shapes' crossings are exact at any first row.
pub(crate) fn draw_rows<T: PaintedShape>(
    shape: &T,
    framebuffer: &mut SliceFramebuffer<'_, <T::Paint as Paint>::Color>,
    rect: &Rectangle,
) {
    let mut shader = PaintIntoSlice {
        framebuffer,
        paint: shape.paint(),
        top: rect.top_left.y,
    };
    shape.spans(rect, &mut shader);
}

/// `Drawable::draw` of `shape`: one `draw_row` of the paint a span, until the first error.
pub(crate) fn draw<T, D>(shape: &T, target: &mut D) -> Result<(), D::Error>
where
    T: PaintedShape,
    D: DrawTarget<Color = <T::Paint as Paint>::Color>,
{
    let clip = target.bounding_box();
    let mut shader = PaintToTarget {
        target,
        paint: shape.paint(),
        result: Ok(()),
    };
    shape.spans(&clip, &mut shader);
    shader.result
}

/// The paint's row fill of each span, into
/// the framebuffer's row `y − top` (a band's buffer starts at the frame's row `top`).
struct PaintIntoSlice<'f, 'a, 'p, P: Paint> {
    framebuffer: &'f mut SliceFramebuffer<'a, P::Color>,
    paint: &'p P,
    top: i32,
}

impl<P: Paint> SpanShader<0> for PaintIntoSlice<'_, '_, '_, P> {
    type Steps = ();

    scan_small_with_walk_planes!();

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
            match (self.paint.uniform(), row) {
                (Some(color), [pixel]) => *pixel = color,
                (_, row) => self.paint.paint_row(span.y, span.x_start, row),
            }
        }
    }
}

/// The paint's `draw_row` a span,
/// stopping at the first error.
struct PaintToTarget<'t, 'p, D: DrawTarget, P> {
    target: &'t mut D,
    paint: &'p P,
    result: Result<(), D::Error>,
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
