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

use crate::color::GouraudColor;
use crate::edge::TriangleSetup;
use crate::fixed_point::{pixel_corner, Coord};
use crate::framebuffer::SliceFramebuffer;
use crate::interpolation::{AttributePlane, InverseArea, MAX_CHUNK};
use crate::traversal::{Region, Span, Spans};

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
    /// loop: the fastest path, with the same pixels as [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, C>) {
        for (span, colors) in self.shaded_spans(&framebuffer.bounding_box()) {
            if let Some(row) = framebuffer.row_mut(span.x_start, span.y, span.len()) {
                colors.fill(row);
            }
        }
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
        for (span, colors) in self.shaded_spans(&target.bounding_box()) {
            let area = Rectangle::new(Point::new(span.x_start, span.y), Size::new(span.len(), 1));
            target.fill_contiguous(&area, colors)?;
        }
        Ok(())
    }
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

    /// Draws into a [`SliceFramebuffer`] with one slice fill per span; the same pixels as
    /// [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, C>) {
        for span in self.spans(&framebuffer.bounding_box()) {
            if let Some(row) = framebuffer.row_mut(span.x_start, span.y, span.len()) {
                row.fill(self.color);
            }
        }
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
        for span in self.spans(&target.bounding_box()) {
            let area = Rectangle::new(Point::new(span.x_start, span.y), Size::new(span.len(), 1));
            target.fill_solid(&area, self.color)?;
        }
        Ok(())
    }
}

/// Iterator over the covered spans of a [`GouraudTriangle`] and their colours.
#[derive(Debug, Clone)]
pub struct ShadedSpans<C> {
    spans: Spans,
    planes: [AttributePlane; 3],
    /// The span being handed out in chunks, and how far into it we are.
    current: Option<(Span, u32)>,
    _color: PhantomData<C>,
}

impl<C: GouraudColor> ShadedSpans<C> {
    fn new(triangle: &GouraudTriangle<C>, clip: &Rectangle) -> Self {
        let positions = triangle.vertices.map(|v| v.position());
        let channels = triangle.vertices.map(|v| v.color.channels());
        let setup = TriangleSetup::new(positions);
        let region = setup.as_ref().and_then(|s| Region::new(s, clip));
        match (setup, region) {
            (Some(setup), Some(region)) => {
                let inverse = InverseArea::new(setup.area2);
                let plane = |k: usize| {
                    if k < C::CHANNELS {
                        let values = channels.map(|c| u16::from(c[k]));
                        AttributePlane::with_inverse(&setup, &inverse, values, &region)
                    } else {
                        AttributePlane::constant(0)
                    }
                };
                ShadedSpans {
                    spans: Spans::new(&setup, region),
                    planes: [plane(0), plane(1), plane(2)],
                    current: None,
                    _color: PhantomData,
                }
            }
            _ => ShadedSpans {
                spans: Spans::empty(),
                planes: [AttributePlane::constant(0); 3],
                current: None,
                _color: PhantomData,
            },
        }
    }
}

impl<C: GouraudColor> Iterator for ShadedSpans<C> {
    type Item = (Span, SpanColors<C>);

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        let (span, offset, start) = match self.current {
            Some((span, offset)) => (span, offset, self.planes.map(|p| p.further(offset))),
            None => {
                let span = self.spans.next()?;
                let start = [0, 1, 2].map(|k| match self.planes.get_mut(k) {
                    Some(p) if k < C::CHANNELS => p.row_start(span.x_start, span.y),
                    _ => 0,
                });
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
        let step = self.planes.map(|p| p.step());
        Some((chunk, SpanColors::new(start, step, len)))
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
