//! The depth target: a colour framebuffer with a 16-bit z-buffer, and the projected vertices the
//! depth-tested fills take; the z-buffer as a grey image ([`DepthImage`]) to blit or save.

use embedded_graphics::image::ImageDrawable;
use embedded_graphics::pixelcolor::Gray8;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;

use crate::draw::{draw_rows, FramebufferError, SliceFramebuffer};
use crate::fixed_point::{Coord, ToCoord};
use crate::raster::Span;

/// The z-buffer value of an empty pixel; nothing is ever drawn at this depth.
pub const DEPTH_CLEAR: u16 = u16::MAX;

/// The depth of the far plane (the near plane is at 0).
pub const DEPTH_FAR: u16 = u16::MAX - 1;

/// A colour framebuffer with a 16-bit z-buffer of the same size, both caller-owned.
///
/// It is also a plain [`DrawTarget`] for 2D overlays: drawing ignores and keeps the depth, except
/// `clear`, which resets it as well.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::three_d::{draw_flat, DepthTarget, ScreenVertex, DEPTH_CLEAR};
///
/// let (mut pixels, mut depth) = ([Rgb565::BLACK; 32 * 32], [0u16; 32 * 32]);
/// // `new` resets the depth buffer: a zeroed one would be all near plane and hide everything.
/// let mut target = DepthTarget::new(&mut pixels, &mut depth, 32, 32).unwrap();
/// assert!(target.depth().iter().all(|&d| d == DEPTH_CLEAR));
///
/// let v = |x: f32, y: f32, z| ScreenVertex::new(x, y, z);
/// let clip = target.bounding_box();
/// draw_flat(&mut target, &clip, &[v(0.0, 0.0, 100), v(32.0, 0.0, 100), v(0.0, 32.0, 100)], Rgb565::RED);
/// // Farther away: hidden where the red triangle is.
/// draw_flat(&mut target, &clip, &[v(0.0, 0.0, 900), v(32.0, 0.0, 900), v(32.0, 32.0, 900)], Rgb565::BLUE);
/// assert_eq!(target.framebuffer().get(4, 1), Some(Rgb565::RED));
/// assert_eq!(target.framebuffer().get(30, 20), Some(Rgb565::BLUE));
/// assert_eq!(target.depth_at(4, 1), Some(100));
///
/// // Next frame: colour and depth together.
/// target.clear(Rgb565::BLACK);
/// ```
#[derive(Debug)]
pub struct DepthTarget<'a, C> {
    color: SliceFramebuffer<'a, C>,
    depth: &'a mut [u16],
    width: u32,
    /// While a translucent material is drawn ([`Material::opacity`]): its opacity and the colour
    /// format's blend. The fills then test depth without writing it and blend.
    ///
    /// [`Material::opacity`]: crate::Material::opacity
    blend: Option<Blend<C>>,
}

/// A translucent draw's opacity and the colour format's [`GouraudColor::blend`] (a function
/// pointer: the depth-tested fills are generic over `PixelColor`).
///
/// [`GouraudColor::blend`]: crate::GouraudColor::blend
#[derive(Debug, Clone, Copy)]
pub(crate) struct Blend<C> {
    pub(crate) opacity: u8,
    pub(crate) over: fn(C, C, u8) -> C,
}

impl<'a, C: PixelColor> DepthTarget<'a, C> {
    /// Wraps row-major `width × height` colour and depth buffers (each at least
    /// `width · height` long) and resets the depth buffer to [`DEPTH_CLEAR`] (the colours are
    /// kept). Each frame after the first starts with [`clear`](Self::clear) (colour and depth)
    /// or [`clear_depth`](Self::clear_depth).
    ///
    /// # Errors
    ///
    /// [`FramebufferError::ColorBuffer`] or [`FramebufferError::DepthBuffer`] if a buffer is too
    /// short (with the length needed and given), [`FramebufferError::TooLarge`] if a side does
    /// not fit an `i32` coordinate.
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::Rgb565;
    /// use embedded_raster::DepthTarget;
    ///
    /// let (mut pixels, mut depth) = ([Rgb565::new(0, 0, 0); 64 * 48], [0u16; 64 * 47]);
    /// let error = DepthTarget::new(&mut pixels, &mut depth, 64, 48).unwrap_err();
    /// assert_eq!(error.to_string(), "a depth buffer needs 3072 entries (width · height), given 3008");
    /// ```
    pub fn new(
        color: &'a mut [C],
        depth: &'a mut [u16],
        width: u32,
        height: u32,
    ) -> Result<Self, FramebufferError> {
        let mut target = Self::new_uncleared(color, depth, width, height)?;
        target.clear_depth();
        Ok(target)
    }

    /// Like [`new`](Self::new), but keeps whatever the depth buffer holds: for continuing a frame
    /// over buffers that another `DepthTarget` drew into (a second pass, a band of a larger
    /// frame), without the cost of a reset. A zeroed buffer holds the near plane everywhere, so
    /// nothing would be drawn into it.
    pub fn new_uncleared(
        color: &'a mut [C],
        depth: &'a mut [u16],
        width: u32,
        height: u32,
    ) -> Result<Self, FramebufferError> {
        let color = SliceFramebuffer::new(color, width, height)?;
        // The frame's pixels, which the colour buffer was cut to.
        let len = color.pixels().len();
        let given = depth.len();
        let depth = depth
            .get_mut(..len)
            .ok_or(FramebufferError::DepthBuffer { needed: len, given })?;
        Ok(DepthTarget {
            color,
            depth,
            width,
            blend: None,
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

    /// The z-buffer as a grey image: blit it to any `DrawTarget` with embedded-graphics'
    /// `Image` (convert with `color_converted()` for a colour display).
    ///
    /// ```
    /// use embedded_graphics::{image::Image, pixelcolor::{Gray8, Rgb565}, prelude::*};
    /// use embedded_raster::{three_d::DepthTarget, SliceFramebuffer};
    ///
    /// let (mut pixels, mut depth) = ([Rgb565::BLACK; 8 * 8], [0u16; 8 * 8]);
    /// let target = DepthTarget::new(&mut pixels, &mut depth, 8, 8).unwrap();
    /// let mut view = [Rgb565::WHITE; 8 * 8];
    /// let mut screen = SliceFramebuffer::new(&mut view, 8, 8).unwrap();
    /// Image::new(&target.depth_image(), Point::zero()).draw(&mut screen.color_converted())?;
    /// assert_eq!(screen.get(3, 3), Some(Rgb565::BLACK)); // empty
    /// # Ok::<(), core::convert::Infallible>(())
    /// ```
    pub fn depth_image(&self) -> DepthImage<'_> {
        DepthImage {
            depth: self.depth,
            size: self.color.size(),
        }
    }

    /// Resets every depth to [`DEPTH_CLEAR`].
    pub fn clear_depth(&mut self) {
        crate::arch::fill_u16(self.depth, DEPTH_CLEAR);
    }

    /// Fills the colour buffer with `color` and resets the z-buffer.
    pub fn clear(&mut self, color: C) {
        crate::color::fill_all(self.color.pixels_mut(), color);
        self.clear_depth();
    }

    /// The blend of a translucent draw in progress, if any.
    #[inline(always)]
    pub(crate) fn blend(&self) -> Option<Blend<C>> {
        self.blend
    }

    /// Runs `draw` with `blend` as the draw's blend (none: opaque), then ends it.
    #[inline(always)]
    pub(crate) fn blending<T>(
        &mut self,
        blend: Option<Blend<C>>,
        draw: impl FnOnce(&mut Self) -> T,
    ) -> T {
        self.blend = blend;
        let result = draw(self);
        self.blend = None;
        result
    }

    /// The colour and depth buffers (row-major, of the same length) and the row length.
    #[inline(always)]
    pub(crate) fn buffers_mut(&mut self) -> (&mut [C], &mut [u16], usize) {
        (self.color.pixels_mut(), self.depth, self.width as usize)
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

#[cfg(feature = "png")]
impl<C: PixelColor + Into<embedded_graphics::pixelcolor::Rgb888>> DepthTarget<'_, C> {
    /// Saves the colour buffer as an 8-bit RGB PNG file (feature `png`), like
    /// [`SliceFramebuffer::save_png`].
    pub fn save_png(&self, path: impl AsRef<std::path::Path>) -> std::io::Result<()> {
        self.color.save_png(path)
    }

    /// Saves the z-buffer as a 16-bit greyscale PNG file (feature `png`), losslessly: each
    /// sample is `65535 − depth`, so near is bright, the far plane is 1 and empty pixels are 0.
    /// (The 8 high bits of the same values are [`depth_image`](Self::depth_image)'s grey.)
    pub fn save_depth_png(&self, path: impl AsRef<std::path::Path>) -> std::io::Result<()> {
        use std::io::Write;
        let data: std::vec::Vec<u8> = self
            .depth
            .iter()
            .flat_map(|&d| (u16::MAX - d).to_be_bytes())
            .collect();
        let Size { width, height } = self.color.size();
        let mut file = std::io::BufWriter::new(std::fs::File::create(path)?);
        crate::draw::write_png(
            &mut file,
            width,
            height,
            ::png::ColorType::Grayscale,
            ::png::BitDepth::Sixteen,
            &data,
        )?;
        file.flush()
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

/// The z-buffer of a [`DepthTarget`] as a [`Gray8`] image ([`DepthTarget::depth_image`]): grey
/// `(65535 − depth) >> 8`, so near is white and the far plane and empty pixels are black.
#[derive(Debug, Clone, Copy)]
pub struct DepthImage<'a> {
    depth: &'a [u16],
    size: Size,
}

/// The grey of a depth.
fn depth_gray(d: u16) -> Gray8 {
    Gray8::new(((u16::MAX - d) >> 8) as u8)
}

impl OriginDimensions for DepthImage<'_> {
    fn size(&self) -> Size {
        self.size
    }
}

impl ImageDrawable for DepthImage<'_> {
    type Color = Gray8;

    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = Gray8>,
    {
        target.fill_contiguous(
            &self.bounding_box(),
            self.depth.iter().map(|&d| depth_gray(d)),
        )
    }

    fn draw_sub_image<D>(&self, target: &mut D, area: &Rectangle) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = Gray8>,
    {
        let width = self.size.width as usize;
        draw_rows(target, self.size, area, |y, a, b| {
            self.depth[y * width + a..y * width + b]
                .iter()
                .map(|&d| depth_gray(d))
        })
    }
}

/// A projected vertex: sub-pixel screen position and depth (0 near … [`DEPTH_FAR`] far).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[repr(C)]
pub struct ScreenVertex {
    /// Horizontal position.
    pub x: Coord,
    /// Vertical position (down).
    pub y: Coord,
    /// Depth; smaller is nearer.
    pub depth: u16,
}

impl ScreenVertex {
    /// A vertex at `(x, y)` with `depth`: floats or [`Coord`]s ([`ToCoord`]), e.g.
    /// `ScreenVertex::new(10.5, 3.0, 1000)`. For `const` data write the fields (all public).
    #[inline(always)]
    pub fn new(x: impl ToCoord, y: impl ToCoord, depth: u16) -> Self {
        ScreenVertex {
            x: x.to_coord(),
            y: y.to_coord(),
            depth,
        }
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

    /// A short buffer is an error naming which buffer and the lengths needed and given
    /// (issue #32, item 3); the colour buffer is checked first.
    #[test]
    fn short_buffers_are_errors() {
        let (mut px, mut z) = ([Gray8::BLACK; 12], [7u16; 12]);
        assert_eq!(
            DepthTarget::new(&mut px, &mut z[..11], 4, 3).err(),
            Some(FramebufferError::DepthBuffer {
                needed: 12,
                given: 11
            })
        );
        assert_eq!(
            DepthTarget::new_uncleared(&mut px[..5], &mut z[..11], 4, 3).err(),
            Some(FramebufferError::ColorBuffer {
                needed: 12,
                given: 5
            })
        );
        assert_eq!(
            DepthTarget::new(&mut px, &mut z, 4, 1 << 31).err(),
            Some(FramebufferError::TooLarge {
                width: 4,
                height: 1 << 31
            })
        );
        // A refused target leaves the depth buffer as it was.
        assert!(z.iter().all(|&d| d == 7));
        assert!(DepthTarget::new(&mut px, &mut z, 4, 3).is_ok());
        assert!(z.iter().all(|&d| d == DEPTH_CLEAR));
    }

    /// Rows past the last read nothing. (Before, the row alone was unchecked: on 32-bit targets
    /// `y · width` wrapped, so row 2³⁰ of a 4-pixel-wide target read row 0.)
    #[test]
    fn depth_outside_the_buffer_is_none() {
        let (mut px, mut z) = ([Gray8::BLACK; 16], [7u16; 16]);
        // Uncleared: the depths as given.
        let target = DepthTarget::new_uncleared(&mut px, &mut z, 4, 4).unwrap();
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
