//! embedded-graphics primitives: Gouraud-shaded and solid triangles.
//!
//! Both implement [`Drawable`] for any [`DrawTarget`] of their colour. They clip to the target's
//! `bounding_box()` before traversal, so no pixel outside it is ever emitted, and they emit whole
//! spans (`fill_contiguous`, `fill_solid`), which [`SliceFramebuffer`]
//! turns into plain slice writes.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use embedded_raster::{Coord, GouraudTriangle, SliceFramebuffer, Vertex};
//!
//! let mut pixels = [Rgb565::BLACK; 64 * 48];
//! let mut display = SliceFramebuffer::new(&mut pixels, 64, 48).unwrap();
//! let v = |x: f32, y: f32, c| Vertex::new(Coord::from_num(x), Coord::from_num(y), c);
//! GouraudTriangle::new([
//!     v(2.0, 2.0, Rgb565::RED),
//!     v(60.5, 10.25, Rgb565::GREEN),
//!     v(20.0, 45.75, Rgb565::BLUE),
//! ])
//! .draw(&mut display)?;
//! assert_eq!(display.get(3, 3).map(|c| c.r()), Some(30));
//! # Ok::<(), core::convert::Infallible>(())
//! ```

use core::marker::PhantomData;

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::framebuffer::{fill_row, SliceFramebuffer};
#[cfg(sse2_rows)]
use super::tiny;
use crate::color::{GouraudColor, SpanSteps, PLANE_TO_STEP};
use crate::fixed_point::{pixel_corner, Coord};
use crate::raster::compact::{CompactColors, CompactTriangle, TooLarge};
use crate::raster::edge::TriangleSetup;
use crate::raster::plane::{
    AttributePlane, InverseArea, SmallPlanes, StepContext, Stepped, MAX_CHUNK,
};
use crate::raster::walk::{Region, Span, Spans};

/// A triangle vertex: sub-pixel position and colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Vertex<C> {
    /// Horizontal position (pixel centres are at `i + 0.5`).
    pub x: Coord,
    /// Vertical position, growing downward.
    pub y: Coord,
    /// Colour at this vertex.
    pub color: C,
}

impl<C> Vertex<C> {
    /// A vertex at `(x, y)` with colour `color`.
    pub const fn new(x: Coord, y: Coord, color: C) -> Self {
        Vertex { x, y, color }
    }

    /// A vertex at the top-left corner of the pixel `p`.
    pub fn from_point(p: Point, color: C) -> Self {
        Vertex::new(pixel_corner(p.x), pixel_corner(p.y), color)
    }

    /// The position as a coordinate pair.
    pub fn position(&self) -> (Coord, Coord) {
        (self.x, self.y)
    }
}

/// A triangle whose vertex colours are interpolated across it (Gouraud shading).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GouraudTriangle<C> {
    /// The three vertices, in either winding.
    pub vertices: [Vertex<C>; 3],
}

impl<C: GouraudColor> GouraudTriangle<C> {
    /// A Gouraud triangle through `vertices` (either winding).
    pub const fn new(vertices: [Vertex<C>; 3]) -> Self {
        GouraudTriangle { vertices }
    }

    /// Draws into a [`SliceFramebuffer`] with slice writes and the colour format's packed span
    /// loop (tiny triangles on x86-64: one masked write per row, see the tiny rows): the
    /// fastest path, with the same pixels as [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, C>) {
        let clip = framebuffer.bounding_box();
        let walked = match CompactTriangle::new(self.positions(), &clip) {
            Ok(None) => return,
            Ok(Some(triangle)) => {
                #[cfg(sse2_rows)]
                let colors = {
                    let (colors, steps) = self.compact_colors(&triangle);
                    if tiny::draw(framebuffer, &triangle, &colors, &steps) {
                        return;
                    }
                    move || (colors, steps)
                };
                #[cfg(not(sse2_rows))]
                let colors = || self.compact_colors(&triangle);
                fold_compact_spans(&triangle, colors, (), |(), span, start, steps| {
                    fill_into(framebuffer, span, start, steps)
                })
            }
            Err(TooLarge) => Err(()),
        };
        let walked = walked.or_else(|()| {
            self.fold_wide(&clip, (), |(), span, start, steps| {
                fill_into(framebuffer, span, start, steps)
            })
        });
        if walked.is_err() {
            let Ok(()) = self.draw_exact(framebuffer);
        }
    }

    /// Folds `f` over the covered spans inside `clip`, handing it each span's channel values at
    /// its first pixel and the per-pixel steps ([`STEP_BITS`](crate::color::STEP_BITS) fractional
    /// bits); `Err(init)` untouched if the colours need the exact planes (extreme slivers, huge
    /// regions).
    ///
    /// One walk with the accumulators in registers, no chunking: the 24-bit per-pixel steps stay
    /// within 2⁻⁹ LSB over the longest span this path takes (2¹⁶ pixels). Set-up and walker are
    /// built here, in place.
    #[inline(always)]
    fn fold_stepped<B>(
        &self,
        clip: &Rectangle,
        init: B,
        mut f: impl FnMut(B, Span, [u32; 3], &SpanSteps) -> B,
    ) -> Result<B, B> {
        match self.fold_compact(clip, init, &mut f) {
            Err(init) => self.fold_wide(clip, init, f),
            done => done,
        }
    }

    /// [`fold_stepped`](Self::fold_stepped) for compact triangles (see
    /// [`compact`](crate::raster::compact)): `Err(init)` untouched for the others.
    #[inline(always)]
    fn fold_compact<B>(
        &self,
        clip: &Rectangle,
        init: B,
        f: impl FnMut(B, Span, [u32; 3], &SpanSteps) -> B,
    ) -> Result<B, B> {
        match CompactTriangle::new(self.positions(), clip) {
            Ok(Some(triangle)) => {
                fold_compact_spans(&triangle, || self.compact_colors(&triangle), init, f)
            }
            Ok(None) => Ok(init),
            Err(TooLarge) => Err(init),
        }
    }

    /// The vertices' positions.
    #[inline(always)]
    fn positions(&self) -> [(Coord, Coord); 3] {
        self.vertices.map(|v| v.position())
    }

    /// The colour planes of the compact triangle `triangle` (these vertices) and their span
    /// steps.
    #[inline(always)]
    fn compact_colors(&self, triangle: &CompactTriangle) -> (CompactColors, SpanSteps) {
        let channels = self.vertices.map(|v| v.color.channels());
        let colors = CompactColors::new(&triangle.setup, channels);
        let steps = C::prepare_steps(colors.dx);
        (colors, steps)
    }

    /// [`fold_stepped`](Self::fold_stepped) for any triangle, with `i64`/`i128` set-up.
    #[inline(always)]
    fn fold_wide<B>(
        &self,
        clip: &Rectangle,
        init: B,
        mut f: impl FnMut(B, Span, [u32; 3], &SpanSteps) -> B,
    ) -> Result<B, B> {
        let positions = self.positions();
        // By reference: moving the setup out of the `Option` would copy it.
        let setup = TriangleSetup::new(positions);
        let Some(setup) = setup.as_ref() else {
            return Ok(init);
        };
        let Some(region) = Region::new(setup, clip) else {
            return Ok(init);
        };
        let Some(mut rows) = RowColors::of_triangle(self, setup, &region) else {
            return Err(init);
        };
        let steps = C::prepare_steps(rows.dx);
        Ok(Spans::new(setup, region).fold(init, |acc, span| {
            let start = rows.at(span.x_start, span.y, C::CHANNELS);
            f(acc, span, start, &steps)
        }))
    }

    /// Draws into a [`SliceFramebuffer`] like [`draw_into`](Self::draw_into) if the triangle is
    /// compact (bounding box under 2048 × 2048 pixels, see [`compact`](crate::raster::compact)), else
    /// draws nothing and returns [`TooLarge`]. A firmware that draws only through this method
    /// links only the compact rasterizer: about an eighth of `draw_into`'s code. It always walks
    /// spans (no the tiny rows rows): the same pixels.
    pub fn draw_into_compact(
        &self,
        framebuffer: &mut SliceFramebuffer<'_, C>,
    ) -> Result<(), TooLarge> {
        self.fold_compact(&framebuffer.bounding_box(), (), |(), span, start, steps| {
            fill_into(framebuffer, span, start, steps)
        })
        .map_err(|()| TooLarge)
    }

    /// The covered spans inside `clip` with their colours, each at most
    /// [`MAX_CHUNK`] pixels long.
    pub fn shaded_spans(&self, clip: &Rectangle) -> ShadedSpans<C> {
        ShadedSpans::new(self, clip)
    }
}

impl<C: GouraudColor> Drawable for GouraudTriangle<C> {
    type Color = C;
    type Output = ();

    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        // After an error the remaining spans are skipped, not drawn.
        let walked = self.fold_stepped(
            &target.bounding_box(),
            Ok(()),
            |drawn, span, start, steps| {
                drawn.and_then(|()| {
                    let area =
                        Rectangle::new(Point::new(span.x_start, span.y), Size::new(span.len(), 1));
                    target.fill_contiguous(&area, SpanColors::new(start, steps.step(), span.len()))
                })
            },
        );
        match walked {
            Ok(drawn) => drawn,
            Err(_) => self.draw_exact(target),
        }
    }
}

impl<C: GouraudColor> GouraudTriangle<C> {
    /// [`Drawable::draw`] (and [`draw_into`](Self::draw_into)) for triangles whose colours need
    /// the exact planes (extreme slivers, huge regions): spans in chunks, each restarted exactly.
    #[cold]
    #[inline(never)]
    fn draw_exact<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        for (span, colors) in self.shaded_spans(&target.bounding_box()) {
            let area = Rectangle::new(Point::new(span.x_start, span.y), Size::new(span.len(), 1));
            target.fill_contiguous(&area, colors)?;
        }
        Ok(())
    }
}

/// Fills `span` of `framebuffer` with colours from `start` stepped by `steps` (the spans of the
/// rasterizer's own walks, clipped to the framebuffer).
#[inline(always)]
fn fill_into<C: GouraudColor>(
    framebuffer: &mut SliceFramebuffer<'_, C>,
    span: Span,
    start: [u32; 3],
    steps: &SpanSteps,
) {
    if let Some(row) = framebuffer.clipped_span_mut(span.y, span.x_start, span.x_end) {
        C::fill_prepared(row, start, steps);
    }
}

/// Folds `f` over the covered spans of the compact triangle `triangle` with their colours from
/// `colors` (see [`GouraudTriangle::fold_stepped`]), called after the walk's set-up (on
/// Cortex-M0 fewer values then live across it); `Err(init)` untouched if its walk does not fit
/// 32 bits.
#[inline(always)]
fn fold_compact_spans<B>(
    triangle: &CompactTriangle,
    colors: impl FnOnce() -> (CompactColors, SpanSteps),
    init: B,
    mut f: impl FnMut(B, Span, [u32; 3], &SpanSteps) -> B,
) -> Result<B, B> {
    let Ok(spans) = triangle.walk() else {
        return Err(init);
    };
    let (colors, steps) = colors();
    let steps = &steps;
    Ok(spans.fold(init, |acc, span, column, row| {
        let start = core::array::from_fn(|k| {
            colors.value[k]
                .wrapping_add(colors.dy[k].wrapping_mul(row))
                .wrapping_add(colors.dx[k].wrapping_mul(column))
        });
        f(acc, span, start, steps)
    }))
}

/// A triangle filled with one colour; covers exactly the pixels a [`GouraudTriangle`] with the
/// same positions covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SolidTriangle<C> {
    /// The three corner positions, in either winding.
    pub points: [(Coord, Coord); 3],
    /// The fill colour.
    pub color: C,
}

impl<C: PixelColor> SolidTriangle<C> {
    /// A triangle with corners `points` filled with `color`.
    pub const fn new(points: [(Coord, Coord); 3], color: C) -> Self {
        SolidTriangle { points, color }
    }

    /// Draws into a [`SliceFramebuffer`] with one slice fill per span (tiny triangles on x86-64:
    /// one masked write per row, see the tiny rows); the same pixels as
    /// [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, C>) {
        let color = self.color;
        // The framebuffer travels in the fold's accumulator.
        self.fold_spans(
            &framebuffer.bounding_box(),
            framebuffer,
            |_triangle, fb| {
                #[cfg(sse2_rows)]
                if tiny::fill(fb, _triangle, color) {
                    return Ok(fb);
                }
                Err(fb)
            },
            |fb, span| {
                if let Some(row) = fb.clipped_span_mut(span.y, span.x_start, span.x_end) {
                    fill_row(row, color);
                }
                fb
            },
        );
    }

    /// Folds `f` over the covered spans inside `clip`: the compact walk for triangles under
    /// 2048 px (see [`compact`](crate::raster::compact)), [`Spans`] for the rest. A compact triangle is
    /// first offered to `whole`, which may draw it in one piece (`Ok`) or hand the accumulator
    /// back (`Err`).
    #[inline(always)]
    fn fold_spans<B>(
        &self,
        clip: &Rectangle,
        init: B,
        whole: impl FnOnce(&CompactTriangle, B) -> Result<B, B>,
        mut f: impl FnMut(B, Span) -> B,
    ) -> B {
        let init = match CompactTriangle::new(self.points, clip) {
            Ok(Some(triangle)) => {
                let init = match whole(&triangle, init) {
                    Ok(done) => return done,
                    Err(init) => init,
                };
                match triangle.walk() {
                    Ok(spans) => return spans.fold(init, |acc, span, _, _| f(acc, span)),
                    Err(TooLarge) => init,
                }
            }
            Ok(None) => return init,
            Err(TooLarge) => init,
        };
        // One call of the general walk for both ways here (flash on Cortex-M).
        self.spans(clip).fold(init, f)
    }

    /// The covered spans inside `clip`.
    pub fn spans(&self, clip: &Rectangle) -> Spans {
        Spans::of_triangle(self.points, clip)
    }
}

impl<C: PixelColor> Drawable for SolidTriangle<C> {
    type Color = C;
    type Output = ();

    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        // `fold` walks with the walker's state in registers (see `Spans`; `try_fold` would step
        // through `next`); after an error the remaining spans are skipped, not drawn.
        let span_by_span = |_: &CompactTriangle, drawn| Err(drawn);
        self.fold_spans(
            &target.bounding_box(),
            Ok(()),
            span_by_span,
            |drawn, span| {
                drawn.and_then(|()| {
                    let area =
                        Rectangle::new(Point::new(span.x_start, span.y), Size::new(span.len(), 1));
                    target.fill_solid(&area, self.color)
                })
            },
        )
    }
}

/// Iterator over the covered spans of a [`GouraudTriangle`] and their colours.
#[derive(Debug, Clone)]
pub struct ShadedSpans<C> {
    spans: Spans,
    shading: Shading,
    /// Per-pixel steps of the channels.
    step: [u32; 3],
    /// The span being handed out in chunks, and how far into it we are.
    current: Option<(Span, u32)>,
    _color: PhantomData<C>,
}

/// How the channel values at span starts are found.
// No heap to box the rare large variant in; the iterator was this size before (three planes).
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
enum Shading {
    /// All channels stepped from one shared position (the common case): [`STEP_BITS`]
    /// fractional bits at pixel `(x, y)`, moved by exact multiples of `dx` and `dy` modulo 2³².
    Stepped(RowColors),
    /// Some channel needs the general plane (huge regions or gradients).
    Planes([AttributePlane; 3]),
}

/// The channel values at one pixel and their gradients, [`STEP_BITS`] fractional bits (+½
/// included), wrapping.
///
/// Wrapping arithmetic makes the value at `(x, y)` the same integer modulo 2³² whichever way it
/// was reached, so its error is that of the start value plus `|Δx|` and `|Δy|` times that of the
/// gradients (each within ½ + 2⁻⁸ units of 2⁻²⁴): below 2⁻⁹ LSB over the largest region stepped
/// (`width + height ≤ 2¹⁶`). Covered pixels have values in `[0, 256)·2²⁴`, so the wrapped value
/// is the true one.
#[derive(Debug, Clone, Copy)]
struct RowColors {
    value: [u32; 3],
    dx: [u32; 3],
    dy: [u32; 3],
    x: i32,
    y: i32,
}

/// The values of channel `k` at the vertices of `triangle`.
#[inline]
fn channel_values<C: GouraudColor>(triangle: &GouraudTriangle<C>, k: usize) -> [u8; 3] {
    triangle
        .vertices
        .map(|v| v.color.channels().get(k).copied().unwrap_or(0))
}

impl RowColors {
    /// The accumulators of the colours of `triangle` over `region`, or `None` if a channel needs
    /// the exact plane (extreme slivers, huge regions).
    #[inline]
    fn of_triangle<C: GouraudColor>(
        triangle: &GouraudTriangle<C>,
        setup: &TriangleSetup,
        region: &Region,
    ) -> Option<Self> {
        if let Some(small) = SmallPlanes::new(setup, region) {
            let plane = |k: usize| {
                if k < C::CHANNELS {
                    small.plane(channel_values(triangle, k))
                } else {
                    Some(Stepped::ZERO)
                }
            };
            if let (Some(r), Some(g), Some(b)) = (plane(0), plane(1), plane(2)) {
                return Some(RowColors::new([r, g, b], region));
            }
        }
        let inverse = InverseArea::new(setup.area2);
        let ctx = StepContext::new(setup, region)?;
        // Each channel: gradients and corner value, three products by the shared reciprocal.
        let stepped = |k: usize| {
            if k < C::CHANNELS {
                let values = channel_values(triangle, k).map(u16::from);
                Stepped::new(&inverse, &ctx, AttributePlane::gradient(setup, values))
            } else {
                Some(Stepped::ZERO)
            }
        };
        Some(RowColors::new(
            [stepped(0)?, stepped(1)?, stepped(2)?],
            region,
        ))
    }

    /// The accumulators of `planes` (32 fractional bits) at the region's top-left pixel.
    fn new(planes: [Stepped; 3], region: &Region) -> Self {
        // Round 32 to 24 fractional bits; wrapping keeps the value modulo 2³².
        let round = |v: i64| (v.wrapping_add(1 << 7) >> 8) as u32;
        RowColors {
            value: planes.map(|p| round(p.value)),
            dx: planes.map(|p| round(p.dx)),
            dy: planes.map(|p| round(p.dy)),
            x: region.x0,
            y: region.y0,
        }
    }

    /// Moves to pixel `(x, y)` and returns the values there.
    #[inline(always)]
    fn at(&mut self, x: i32, y: i32, channels: usize) -> [u32; 3] {
        let (mx, my) = (x.wrapping_sub(self.x) as u32, y.wrapping_sub(self.y) as u32);
        (self.x, self.y) = (x, y);
        for ((v, dx), dy) in self
            .value
            .iter_mut()
            .zip(&self.dx)
            .zip(&self.dy)
            .take(channels)
        {
            *v = v
                .wrapping_add(dy.wrapping_mul(my))
                .wrapping_add(dx.wrapping_mul(mx));
        }
        self.value
    }
}

impl<C: GouraudColor> ShadedSpans<C> {
    fn new(triangle: &GouraudTriangle<C>, clip: &Rectangle) -> Self {
        let positions = triangle.vertices.map(|v| v.position());
        let setup = TriangleSetup::new(positions);
        // By reference: moving the setup out of the `Option` would copy it.
        let Some(setup) = setup.as_ref() else {
            return Self::empty();
        };
        let Some(region) = Region::new(setup, clip) else {
            return Self::empty();
        };

        let shading = match RowColors::of_triangle(triangle, setup, &region) {
            Some(rows) => Shading::Stepped(rows),
            None => {
                let inverse = InverseArea::new(setup.area2);
                Shading::Planes(core::array::from_fn(|k| {
                    if k < C::CHANNELS {
                        let values = channel_values(triangle, k).map(u16::from);
                        AttributePlane::with_inverse(setup, &inverse, values, &region)
                    } else {
                        AttributePlane::constant(0)
                    }
                }))
            }
        };
        let step = match &shading {
            Shading::Stepped(rows) => rows.dx,
            Shading::Planes(planes) => planes.map(|p| p.step() << PLANE_TO_STEP),
        };
        ShadedSpans {
            spans: Spans::new(setup, region),
            shading,
            step,
            current: None,
            _color: PhantomData,
        }
    }

    /// An iterator with no spans.
    fn empty() -> Self {
        ShadedSpans {
            spans: Spans::empty(),
            shading: Shading::Planes([AttributePlane::constant(0); 3]),
            step: [0; 3],
            current: None,
            _color: PhantomData,
        }
    }

    /// Channel values at the start of `span`, which becomes the reference for [`Self::further`].
    #[inline]
    fn row_start(&mut self, span: &Span) -> [u32; 3] {
        match &mut self.shading {
            Shading::Stepped(rows) => rows.at(span.x_start, span.y, C::CHANNELS),
            Shading::Planes(planes) => {
                let mut start = [0; 3];
                for (s, p) in start.iter_mut().zip(planes.iter_mut()).take(C::CHANNELS) {
                    *s = p.row_start(span.x_start, span.y) << PLANE_TO_STEP;
                }
                start
            }
        }
    }

    /// Channel values `offset` pixels right of the last [`Self::row_start`].
    fn further(&self, offset: u32) -> [u32; 3] {
        match &self.shading {
            Shading::Stepped(rows) => {
                let mut start = rows.value;
                for (s, dx) in start.iter_mut().zip(&rows.dx) {
                    *s = s.wrapping_add(dx.wrapping_mul(offset));
                }
                start
            }
            Shading::Planes(planes) => planes.map(|p| p.further(offset) << PLANE_TO_STEP),
        }
    }
}

impl<C: GouraudColor> Iterator for ShadedSpans<C> {
    type Item = (Span, SpanColors<C>);

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        let (span, offset, start) = match self.current {
            Some((span, offset)) => (span, offset, self.further(offset)),
            None => {
                let span = self.spans.next()?;
                let start = self.row_start(&span);
                if span.len() <= MAX_CHUNK {
                    return Some((span, SpanColors::new(start, self.step, span.len())));
                }
                (span, 0, start)
            }
        };
        let len = (span.len() - offset).min(MAX_CHUNK);
        let done = offset + len;
        self.current = (done < span.len()).then_some((span, done));
        let chunk = Span {
            y: span.y,
            x_start: span.x_start.wrapping_add(offset as i32),
            x_end: span.x_start.wrapping_add(done as i32),
        };
        Some((chunk, SpanColors::new(start, self.step, len)))
    }
}

/// The colours of one span, left to right: one fixed-point addition per channel and pixel.
#[derive(Debug, Clone)]
pub struct SpanColors<C> {
    value: [u32; 3],
    step: [u32; 3],
    left: u32,
    _color: PhantomData<C>,
}

impl<C: GouraudColor> SpanColors<C> {
    fn new(value: [u32; 3], step: [u32; 3], len: u32) -> Self {
        SpanColors {
            value,
            step,
            left: len,
            _color: PhantomData,
        }
    }
}

impl<C: GouraudColor> Iterator for SpanColors<C> {
    type Item = C;

    #[inline(always)]
    fn next(&mut self) -> Option<C> {
        if self.left == 0 {
            return None;
        }
        self.left -= 1;
        let color = C::from_stepped(self.value);
        self.value[0] = self.value[0].wrapping_add(self.step[0]);
        if C::CHANNELS > 1 {
            self.value[1] = self.value[1].wrapping_add(self.step[1]);
            self.value[2] = self.value[2].wrapping_add(self.step[2]);
        }
        Some(color)
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left as usize, Some(self.left as usize))
    }
}

impl<C: GouraudColor> ExactSizeIterator for SpanColors<C> {}

impl<C: GouraudColor> SpanColors<C> {
    /// Writes the remaining colours to the start of `dst` (as many as fit) with the colour
    /// format's fastest loop ([`GouraudColor::fill_span`]).
    #[inline]
    pub fn fill(self, dst: &mut [C]) {
        let n = dst.len().min(self.left as usize);
        if let Some(dst) = dst.get_mut(..n) {
            C::fill_span(dst, self.value, self.step);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::Pixel;

    /// A target that fails on its `fail_at`-th span and counts the spans it is handed.
    struct Failing {
        spans: u32,
        fail_at: u32,
    }

    impl OriginDimensions for Failing {
        fn size(&self) -> Size {
            Size::new(64, 64)
        }
    }

    impl DrawTarget for Failing {
        type Color = Rgb565;
        type Error = u32;

        fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, _: I) -> Result<(), u32> {
            self.spans += 1;
            if self.spans == self.fail_at {
                Err(self.spans)
            } else {
                Ok(())
            }
        }
    }

    /// The first error is returned and nothing is drawn after it.
    #[test]
    fn draw_stops_at_the_first_error() {
        let c = |x: i32, y: i32| (Coord::from_num(x), Coord::from_num(y));
        let points = [c(1, 1), c(60, 5), c(10, 50)];
        let solid = SolidTriangle::new(points, Rgb565::RED);
        let colors = [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE];
        let gouraud = GouraudTriangle::new(
            [0, 1, 2].map(|k| Vertex::new(points[k].0, points[k].1, colors[k])),
        );
        let mut all = Failing {
            spans: 0,
            fail_at: 0,
        };
        solid.draw(&mut all).unwrap();
        assert!(all.spans > 40);
        for fail_at in [1, 7, all.spans] {
            let mut target = Failing { spans: 0, fail_at };
            assert_eq!(solid.draw(&mut target), Err(fail_at));
            assert_eq!(target.spans, fail_at);
            let mut target = Failing { spans: 0, fail_at };
            assert_eq!(gouraud.draw(&mut target), Err(fail_at));
            assert_eq!(target.spans, fail_at);
        }
    }
}
