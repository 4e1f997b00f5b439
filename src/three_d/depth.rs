//! The depth target: a colour framebuffer with a 16-bit z-buffer, and the projected vertices the
//! depth-tested fills take.

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;

use crate::draw::{fill_row, SliceFramebuffer};
use crate::fixed_point::Coord;
use crate::raster::Span;

/// The z-buffer value of an empty pixel; nothing is ever drawn at this depth.
pub const DEPTH_CLEAR: u16 = u16::MAX;

/// The depth of the far plane (the near plane is at 0).
pub const DEPTH_FAR: u16 = u16::MAX - 1;

/// A colour framebuffer with a 16-bit z-buffer of the same size, both caller-owned.
///
/// It is also a plain [`DrawTarget`] for 2D overlays: drawing ignores and keeps the depth, except
/// `clear`, which resets it as well.
#[derive(Debug)]
pub struct DepthTarget<'a, C> {
    color: SliceFramebuffer<'a, C>,
    depth: &'a mut [u16],
    width: u32,
}

impl<'a, C: PixelColor> DepthTarget<'a, C> {
    /// Wraps row-major `width × height` colour and depth buffers, or `None` if either is too
    /// short. The depth buffer is not cleared: call [`clear`](Self::clear) or
    /// [`clear_depth`](Self::clear_depth) before the first frame.
    pub fn new(color: &'a mut [C], depth: &'a mut [u16], width: u32, height: u32) -> Option<Self> {
        let len = (width as usize).checked_mul(height as usize)?;
        let color = SliceFramebuffer::new(color, width, height)?;
        let depth = depth.get_mut(..len)?;
        Some(DepthTarget {
            color,
            depth,
            width,
        })
    }

    /// The colour buffer.
    pub fn framebuffer(&self) -> &SliceFramebuffer<'a, C> {
        &self.color
    }

    /// The colour buffer, mutably.
    pub fn framebuffer_mut(&mut self) -> &mut SliceFramebuffer<'a, C> {
        &mut self.color
    }

    /// The z-buffer, row-major.
    pub fn depth(&self) -> &[u16] {
        self.depth
    }

    /// The depth at `(x, y)`, or `None` outside the buffer.
    pub fn depth_at(&self, x: i32, y: i32) -> Option<u16> {
        // The colour buffer's index checks both coordinates (a row past the last could wrap the
        // index on 32-bit targets).
        self.color
            .index(x, y)
            .and_then(|i| self.depth.get(i))
            .copied()
    }

    /// Resets every depth to [`DEPTH_CLEAR`].
    pub fn clear_depth(&mut self) {
        fill_row(self.depth, DEPTH_CLEAR);
    }

    /// Fills the colour buffer with `color` and resets the z-buffer.
    pub fn clear(&mut self, color: C) {
        fill_row(self.color.pixels_mut(), color);
        self.clear_depth();
    }

    /// Colour and depth of the pixels of `span`, a span of a walk clipped to this target: the
    /// row and column checks are debug assertions, the slices' own bounds checks remain, so a
    /// wrong span could only ever write other pixels of this target.
    #[inline(always)]
    pub(crate) fn clipped_spans_mut(&mut self, span: Span) -> Option<(&mut [C], &mut [u16])> {
        let (y, a, b) = (span.y as u32, span.x_start as u32, span.x_end as u32);
        debug_assert!(
            a <= b
                && b <= self.width
                && self.depth.len() / (self.width as usize).max(1) > y as usize
        );
        let base = (y as usize).wrapping_mul(self.width as usize);
        let range = base.wrapping_add(a as usize)..base.wrapping_add(b as usize);
        let colors = self.color.pixels_mut().get_mut(range.clone())?;
        let depths = self.depth.get_mut(range)?;
        Some((colors, depths))
    }
}

impl<C: PixelColor> OriginDimensions for DepthTarget<'_, C> {
    fn size(&self) -> Size {
        self.color.size()
    }
}

impl<C: PixelColor> DrawTarget for DepthTarget<'_, C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        self.color.draw_iter(pixels)
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = C>,
    {
        self.color.fill_contiguous(area, colors)
    }

    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Self::Error> {
        self.color.fill_solid(area, color)
    }

    /// Fills the colour buffer and resets the z-buffer, like the inherent
    /// [`DepthTarget::clear`].
    fn clear(&mut self, color: C) -> Result<(), Self::Error> {
        DepthTarget::clear(self, color);
        Ok(())
    }
}

/// A projected vertex: sub-pixel screen position and depth (0 near … [`DEPTH_FAR`] far).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ScreenVertex {
    /// Horizontal position.
    pub x: Coord,
    /// Vertical position (down).
    pub y: Coord,
    /// Depth; smaller is nearer.
    pub depth: u16,
}

impl ScreenVertex {
    /// A vertex at `(x, y)` with `depth`.
    pub const fn new(x: Coord, y: Coord, depth: u16) -> Self {
        ScreenVertex { x, y, depth }
    }

    /// The position as a coordinate pair.
    pub fn position(&self) -> (Coord, Coord) {
        (self.x, self.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::pixelcolor::Gray8;

    /// Rows past the last read nothing. (Before, the row alone was unchecked: on 32-bit targets
    /// `y · width` wrapped, so row 2³⁰ of a 4-pixel-wide target read row 0.)
    #[test]
    fn depth_outside_the_buffer_is_none() {
        let (mut px, mut z) = ([Gray8::BLACK; 16], [7u16; 16]);
        let target = DepthTarget::new(&mut px, &mut z, 4, 4).unwrap();
        assert_eq!(target.depth_at(3, 3), Some(7));
        for (x, y) in [
            (0, 4),
            (4, 0),
            (-1, 0),
            (0, -1),
            (0, 1 << 30),
            (i32::MAX, i32::MAX),
        ] {
            assert_eq!(target.depth_at(x, y), None, "({x}, {y})");
        }
    }
}
