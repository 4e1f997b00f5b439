//! A framebuffer over a caller-owned slice, with span fast paths.
//!
//! embedded-graphics' own `Framebuffer` only implements `draw_iter`, so every span the rasterizer
//! emits would be drawn pixel by pixel with a bounds check each. [`SliceFramebuffer`] overrides
//! `fill_contiguous` and `fill_solid` with plain slice writes: one bounds check per row.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use embedded_raster::{Coord, SliceFramebuffer, SolidTriangle};
//!
//! let mut pixels = [Rgb565::BLACK; 32 * 24];
//! let mut fb = SliceFramebuffer::new(&mut pixels, 32, 24).unwrap();
//! let c = |x: i32, y: i32| (Coord::from_num(x), Coord::from_num(y));
//! SolidTriangle::new([c(0, 0), c(32, 0), c(0, 24)], Rgb565::RED).draw(&mut fb).unwrap();
//! assert_eq!(fb.get(0, 0), Some(Rgb565::RED));
//! assert_eq!(fb.get(31, 23), Some(Rgb565::BLACK));
//! ```

use core::convert::Infallible;

use embedded_graphics::image::GetPixel;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;

use crate::arch::{LANES, SIZE_OVER_SPEED};
use crate::color::fill_row;
use crate::rect;

/// Drops the next `n` items of `colors`; `false` if it ran out first. In steps of at most
/// `usize::MAX` items (`nth` takes a `usize`; `n` may exceed it on 32-bit targets).
#[inline]
pub(crate) fn skip_colors<I: Iterator>(colors: &mut I, mut n: u64) -> bool {
    while n > 0 {
        let step = usize::try_from(n).unwrap_or(usize::MAX);
        if colors.nth(step - 1).is_none() {
            return false;
        }
        n -= step as u64;
    }
    true
}

/// Why [`SliceFramebuffer::new`] or [`DepthTarget::new`](crate::DepthTarget::new) refused its
/// buffers: what they need and what they were given.
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use embedded_raster::draw::FramebufferError;
/// use embedded_raster::SliceFramebuffer;
///
/// let mut pixels = [Rgb565::new(0, 0, 0); 100];
/// let error = SliceFramebuffer::new(&mut pixels, 320, 240).unwrap_err();
/// assert_eq!(error, FramebufferError::ColorBuffer { needed: 76_800, given: 100 });
/// assert_eq!(error.to_string(), "a colour buffer needs 76800 pixels (width · height), given 100");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FramebufferError {
    /// A side beyond `i32::MAX` pixels (positions are `i32`), or `width · height` beyond
    /// `usize::MAX`.
    TooLarge {
        /// The width given.
        width: u32,
        /// The height given.
        height: u32,
    },
    /// A colour buffer shorter than `width · height` pixels (a longer one is fine: the frame
    /// takes its first `width · height`).
    ColorBuffer {
        /// Pixels the frame needs: `width · height`.
        needed: usize,
        /// Pixels given.
        given: usize,
    },
    /// A depth buffer shorter than `width · height` entries (a longer one is fine).
    DepthBuffer {
        /// Entries the frame needs: `width · height`.
        needed: usize,
        /// Entries given.
        given: usize,
    },
    /// A coverage mask's cells shorter than its area (`width · height` cells).
    MaskBuffer {
        /// Cells the area needs: `width · height`.
        needed: usize,
        /// Cells given.
        given: usize,
    },
}

impl core::fmt::Display for FramebufferError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            FramebufferError::TooLarge { width, height } => write!(
                f,
                "a framebuffer of {width} × {height} pixels: each side must be at most \
                 i32::MAX (2147483647) pixels and width · height at most usize::MAX"
            ),
            FramebufferError::ColorBuffer { needed, given } => write!(
                f,
                "a colour buffer needs {needed} pixels (width · height), given {given}"
            ),
            FramebufferError::DepthBuffer { needed, given } => write!(
                f,
                "a depth buffer needs {needed} entries (width · height), given {given}"
            ),
            FramebufferError::MaskBuffer { needed, given } => write!(
                f,
                "a coverage mask needs {needed} cells (width · height), given {given}"
            ),
        }
    }
}

impl core::error::Error for FramebufferError {}

/// The number of pixels of a `width × height` frame: an error if a side does not fit an `i32`
/// position or the product a `usize`.
pub(crate) fn frame_len(width: u32, height: u32) -> Result<usize, FramebufferError> {
    let too_large = FramebufferError::TooLarge { width, height };
    if width > i32::MAX as u32 || height > i32::MAX as u32 {
        return Err(too_large);
    }
    (width as usize)
        .checked_mul(height as usize)
        .ok_or(too_large)
}

/// A `width × height` framebuffer stored row-major in a borrowed slice of colours.
///
/// A `DrawTarget` whose span fills are slice writes, the target of the triangles' `draw_into`
/// fast paths, and an `ImageDrawable` to blit elsewhere (see [`Image`](embedded_graphics::image::Image)).
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::{PrimitiveStyle, Rectangle}};
/// use embedded_raster::SliceFramebuffer;
///
/// let mut pixels = [Rgb565::BLACK; 32 * 24];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 32, 24).unwrap();
/// // Any embedded-graphics drawing works on it.
/// Rectangle::new(Point::new(2, 2), Size::new(4, 3))
///     .into_styled(PrimitiveStyle::with_fill(Rgb565::GREEN))
///     .draw(&mut fb)?;
/// assert_eq!(fb.get(5, 4), Some(Rgb565::GREEN));
/// assert_eq!(fb.pixels().len(), 32 * 24);
/// // Too short a slice is an error that says so, not a silent crop.
/// let error = SliceFramebuffer::new(&mut [Rgb565::BLACK; 10], 4, 4).unwrap_err();
/// assert_eq!(error.to_string(), "a colour buffer needs 16 pixels (width · height), given 10");
/// # Ok::<(), core::convert::Infallible>(())
/// ```
///
/// # Areas outside the buffer
///
/// Every `DrawTarget` method takes any input: `fill_solid` and `fill_contiguous` accept any
/// `Rectangle` (corners anywhere in `i32`, sides up to `u32::MAX`, so reaching past `i32::MAX`)
/// and write exactly its pixels that lie inside the buffer, nothing when none do; the clip is
/// exact (no overflow), and only the rows inside are visited. `draw_iter` ignores pixels outside.
///
/// ```
/// use embedded_graphics::{pixelcolor::Gray8, prelude::*, primitives::Rectangle};
/// use embedded_raster::SliceFramebuffer;
///
/// let mut pixels = [Gray8::BLACK; 8 * 4];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 8, 4).unwrap();
/// // Columns 6 to 6 + 3·10⁹ of rows 1 to 2³¹: columns 6 and 7 of rows 1 to 3 are inside.
/// let area = Rectangle::new(Point::new(6, 1), Size::new(3_000_000_000, 1 << 31));
/// fb.fill_solid(&area, Gray8::WHITE).unwrap();
/// let lit = fb.pixels().iter().filter(|&&p| p == Gray8::WHITE).count();
/// assert_eq!(lit, 6);
/// assert_eq!(fb.get(6, 1), Some(Gray8::WHITE));
/// assert_eq!(fb.get(5, 1), Some(Gray8::BLACK));
/// ```
#[derive(Debug)]
pub struct SliceFramebuffer<'a, C> {
    pixels: &'a mut [C],
    width: u32,
    height: u32,
}

impl<'a, C: PixelColor> SliceFramebuffer<'a, C> {
    /// Wraps `pixels` (row-major, at least `width · height` long; a longer slice's first
    /// `width · height` pixels).
    ///
    /// # Errors
    ///
    /// [`FramebufferError::ColorBuffer`] if `pixels` is too short (with the length needed and
    /// given), [`FramebufferError::TooLarge`] if a side does not fit an `i32` coordinate.
    pub fn new(pixels: &'a mut [C], width: u32, height: u32) -> Result<Self, FramebufferError> {
        let len = frame_len(width, height)?;
        let given = pixels.len();
        let pixels = pixels
            .get_mut(..len)
            .ok_or(FramebufferError::ColorBuffer { needed: len, given })?;
        Ok(SliceFramebuffer {
            pixels,
            width,
            height,
        })
    }

    /// A framebuffer of no pixels.
    pub(crate) fn empty() -> Self {
        SliceFramebuffer {
            pixels: &mut [],
            width: 0,
            height: 0,
        }
    }

    /// The pixels, row-major, exactly `width · height` of them.
    pub fn pixels(&self) -> &[C] {
        self.pixels
    }

    /// Mutable access to the pixels.
    pub fn pixels_mut(&mut self) -> &mut [C] {
        self.pixels
    }

    /// The pixel at `(x, y)`, or `None` outside the buffer.
    pub fn get(&self, x: i32, y: i32) -> Option<C> {
        self.index(x, y).and_then(|i| self.pixels.get(i)).copied()
    }

    /// The row-major index of `(x, y)`, or `None` outside the buffer.
    pub(crate) fn index(&self, x: i32, y: i32) -> Option<usize> {
        let (x, y) = (u32::try_from(x).ok()?, u32::try_from(y).ok()?);
        (x < self.width && y < self.height).then(|| y as usize * self.width as usize + x as usize)
    }

    /// Columns `x_start..x_end` of row `y`, if they are all inside the buffer (fewer checks than
    /// [`row_mut`](Self::row_mut), for the spans of the rasterizer's own loops).
    #[inline(always)]
    pub fn span_mut(&mut self, y: i32, x_start: i32, x_end: i32) -> Option<&mut [C]> {
        // Negative values become huge and fail the comparisons.
        let (y, a, b) = (y as u32, x_start as u32, x_end as u32);
        if y >= self.height || b > self.width || a > b {
            return None;
        }
        // y < height and b ≤ width: the range lies inside `width · height ≤ len`.
        let base = y as usize * self.width as usize;
        self.pixels.get_mut(base + a as usize..base + b as usize)
    }

    /// [`span_mut`](Self::span_mut) for the spans of a walk clipped to this buffer (the compact
    /// path's): the row and column checks are debug assertions, the slice's own bounds check
    /// remains, so a wrong span could only ever write other pixels of this buffer.
    #[inline(always)]
    pub(crate) fn clipped_span_mut(
        &mut self,
        y: i32,
        x_start: i32,
        x_end: i32,
    ) -> Option<&mut [C]> {
        let (y, a, b) = (y as u32, x_start as u32, x_end as u32);
        debug_assert!(y < self.height && a <= b && b <= self.width);
        let base = (y as usize).wrapping_mul(self.width as usize);
        self.pixels
            .get_mut(base.wrapping_add(a as usize)..base.wrapping_add(b as usize))
    }

    /// Pixels `x .. x + LANES` of row `y`, if they are all inside the buffer: a row of a tiny
    /// triangle's box (x86-64).
    #[cfg_attr(not(sse2_rows), allow(dead_code))]
    #[inline(always)]
    pub(crate) fn lanes_mut(&mut self, y: i32, x: i32) -> Option<&mut [C; LANES]> {
        let end = x.checked_add(LANES as i32)?;
        self.span_mut(y, x, end)
            .and_then(|row| <&mut [C; LANES]>::try_from(row).ok())
    }

    /// The pixels of `area` if it is one row wholly inside the buffer (a rasterizer's span): the
    /// fills' fast path, without a rectangle intersection.
    #[inline(always)]
    fn one_row(&mut self, area: &Rectangle) -> Option<&mut [C]> {
        if area.size.height != 1 {
            return None;
        }
        let (x, y) = (area.top_left.x, area.top_left.y);
        let end = x.checked_add(i32::try_from(area.size.width).ok()?)?;
        self.span_mut(y, x, end)
    }

    /// The pixels of the `len` from `start` (one row) inside the buffer, and how many of them
    /// lie left of it; `None` if none is inside.
    #[inline(always)]
    fn row_part(&mut self, start: Point, len: u32) -> Option<(&mut [C], u32)> {
        let y = u32::try_from(start.y).ok().filter(|&y| y < self.height)?;
        // In 32 bits: the first column inside, a ≥ start.x, is `skip` (below 2³²) to its right.
        let a = start.x.max(0) as u32;
        let skip = a.wrapping_sub(start.x as u32);
        let b = a.saturating_add(len.checked_sub(skip)?).min(self.width);
        if a >= b {
            return None;
        }
        // a < b ≤ width and y < height: the range lies inside `width · height ≤ len`.
        let base = y as usize * self.width as usize;
        let row = self.pixels.get_mut(base + a as usize..base + b as usize)?;
        Some((row, skip))
    }

    /// [`fill_contiguous`](DrawTarget::fill_contiguous) of the `len` pixels from `start` (one
    /// row, such as a span of the rasterizer's `draw`), with one copy of the colours' loop: the
    /// form for [`SIZE_OVER_SPEED`] (elsewhere spans wholly inside take a loop of their own,
    /// which keeps the colours' state in registers).
    #[inline(always)]
    fn fill_row_part<I: IntoIterator<Item = C>>(&mut self, start: Point, len: u32, colors: I) {
        if let Some((row, skip)) = self.row_part(start, len) {
            let mut colors = colors.into_iter();
            if skip_colors(&mut colors, skip.into()) {
                for (dst, c) in row.iter_mut().zip(colors) {
                    *dst = c;
                }
            }
        }
    }

    /// The `len` pixels of row `y` starting at column `x`, if they are all inside the buffer.
    #[inline]
    pub fn row_mut(&mut self, x: i32, y: i32, len: u32) -> Option<&mut [C]> {
        let start = self.index(x, y)?;
        if (x as u32).checked_add(len)? > self.width {
            return None;
        }
        self.pixels.get_mut(start..start + len as usize)
    }
}

/// Reads a pixel (`None` outside): what [`Translucent::draw_reading`](crate::Translucent) and
/// other readers of a display need.
impl<C: PixelColor> GetPixel for SliceFramebuffer<'_, C> {
    type Color = C;

    fn pixel(&self, p: Point) -> Option<C> {
        self.get(p.x, p.y)
    }
}

impl<C: PixelColor> OriginDimensions for SliceFramebuffer<'_, C> {
    fn size(&self) -> Size {
        Size::new(self.width, self.height)
    }
}

impl<C: PixelColor> DrawTarget for SliceFramebuffer<'_, C> {
    type Color = C;
    type Error = Infallible;

    /// Writes each pixel inside the buffer; pixels outside it are ignored.
    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        for Pixel(p, c) in pixels {
            if let Some(px) = self.index(p.x, p.y).and_then(|i| self.pixels.get_mut(i)) {
                *px = c;
            }
        }
        Ok(())
    }

    /// Writes the colours of the pixels of `area` inside the buffer, for any `area` (see
    /// [`SliceFramebuffer`]). The colours are taken in embedded-graphics' order, row by row over
    /// the whole `area`: those of pixels outside the buffer are skipped with `Iterator::nth`
    /// (free for slice iterators), and none is taken after the last pixel inside, as
    /// embedded-graphics' own clipped targets do. The cost is the pixels inside plus what the
    /// iterator's `nth` costs for those skipped up to the last row inside. Fewer colours than
    /// pixels fill the area as far as they go.
    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = C>,
    {
        if SIZE_OVER_SPEED && area.size.height == 1 {
            self.fill_row_part(area.top_left, area.size.width, colors);
            return Ok(());
        }
        if let Some(row) = self.one_row(area) {
            for (dst, c) in row.iter_mut().zip(colors) {
                *dst = c;
            }
            return Ok(());
        }
        let visible = rect::intersection(area, &self.bounding_box());
        if visible.is_zero_sized() {
            return Ok(());
        }
        let (Point { x, y }, Size { width, height }) = (visible.top_left, visible.size);
        // Colours before the first pixel inside (the rows above it, then the columns to its
        // left), and between two rows inside: below (2³² − 1)² + 2³², so exact in u64.
        let area_width = u64::from(area.size.width);
        let above = (i64::from(y) - i64::from(area.top_left.y)) as u64;
        let left = (i64::from(x) - i64::from(area.top_left.x)) as u64;
        let mut skip = above * area_width + left;
        let gap = area_width - u64::from(width);
        let mut colors = colors.into_iter();
        // Inside the buffer: y + dy < height ≤ i32::MAX.
        for dy in 0..height {
            if !skip_colors(&mut colors, skip) {
                break;
            }
            let Some(row) = self.row_mut(x, y + dy as i32, width) else {
                break;
            };
            for (dst, c) in row.iter_mut().zip(&mut colors) {
                *dst = c;
            }
            skip = gap;
        }
        Ok(())
    }

    /// Fills the pixels of `area` inside the buffer, for any `area` (see [`SliceFramebuffer`]):
    /// only the rows inside are visited.
    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Infallible> {
        if SIZE_OVER_SPEED && area.size.height == 1 {
            if let Some((row, _)) = self.row_part(area.top_left, area.size.width) {
                fill_row(row, color);
            }
            return Ok(());
        }
        if let Some(row) = self.one_row(area) {
            fill_row(row, color);
            return Ok(());
        }
        let visible = rect::intersection(area, &self.bounding_box());
        let (Point { x, y }, Size { width, height }) = (visible.top_left, visible.size);
        // Inside the buffer (or empty): y + dy < height ≤ i32::MAX.
        for dy in 0..height {
            if let Some(row) = self.row_mut(x, y + dy as i32, width) {
                fill_row(row, color);
            }
        }
        Ok(())
    }

    fn clear(&mut self, color: C) -> Result<(), Infallible> {
        crate::color::fill_all(self.pixels, color);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::pixelcolor::Gray8;

    #[test]
    fn clipped_fills_stay_inside() {
        let mut px = [Gray8::BLACK; 12];
        let mut fb = SliceFramebuffer::new(&mut px, 4, 3).unwrap();
        let area = Rectangle::new(Point::new(-2, 1), Size::new(4, 3));
        fb.fill_contiguous(&area, (0..12).map(|v| Gray8::new(v + 1)))
            .unwrap();
        fb.fill_solid(
            &Rectangle::new(Point::new(3, -5), Size::new(9, 6)),
            Gray8::WHITE,
        )
        .unwrap();
        let luma: [u8; 12] = core::array::from_fn(|i| px[i].luma());
        assert_eq!(luma, [0, 0, 0, 255, 3, 4, 0, 0, 7, 8, 0, 0]);
        assert_eq!(
            SliceFramebuffer::new(&mut [Gray8::BLACK; 5], 2, 3).err(),
            Some(FramebufferError::ColorBuffer {
                needed: 6,
                given: 5
            })
        );
    }

    /// Each error's message says what was needed and what was given (issue #32, item 3), and
    /// `new` returns the error that applies.
    #[test]
    fn error_messages() {
        extern crate std;
        use std::string::ToString;

        let cases = [
            (
                FramebufferError::ColorBuffer {
                    needed: 5120,
                    given: 100,
                },
                "a colour buffer needs 5120 pixels (width · height), given 100",
            ),
            (
                FramebufferError::DepthBuffer {
                    needed: 5120,
                    given: 4800,
                },
                "a depth buffer needs 5120 entries (width · height), given 4800",
            ),
            (
                FramebufferError::TooLarge {
                    width: 1 << 31,
                    height: 1,
                },
                "a framebuffer of 2147483648 × 1 pixels: each side must be at most i32::MAX \
                 (2147483647) pixels and width · height at most usize::MAX",
            ),
        ];
        for (error, message) in cases {
            assert_eq!(error.to_string(), message);
            let _: &dyn core::error::Error = &error;
        }

        let mut px = [Gray8::BLACK; 12];
        // Too large, whatever the buffer: a side beyond i32::MAX.
        assert_eq!(
            SliceFramebuffer::new(&mut px, 1 << 31, 0).err(),
            Some(FramebufferError::TooLarge {
                width: 1 << 31,
                height: 0
            })
        );
        assert_eq!(
            SliceFramebuffer::new(&mut px, 0, u32::MAX).err(),
            Some(FramebufferError::TooLarge {
                width: 0,
                height: u32::MAX
            })
        );
        // A longer buffer is fine: the frame is its first width · height pixels.
        let fb = SliceFramebuffer::new(&mut px, 2, 5).unwrap();
        assert_eq!(fb.pixels().len(), 10);
        assert!(SliceFramebuffer::new(&mut px, 0, 0).is_ok());
    }

    /// The one-row fills of `SIZE_OVER_SPEED` targets (one clipped row) write what the other
    /// targets' fills write, for rows anywhere in `i32` and lengths up to `u32::MAX`.
    #[test]
    fn clipped_row_fills_match_the_fills() {
        let mut next = crate::random(0x0f11_0e00_0000_0001);
        let (width, height) = (7, 3);
        let starts = [
            i32::MIN,
            -9,
            -7,
            -1,
            0,
            1,
            5,
            6,
            7,
            8,
            i32::MAX - 1,
            i32::MAX,
        ];
        let lens = [0, 1, 2, 6, 7, 8, 16, 1 << 31, u32::MAX];
        let check = |x: i32, y: i32, len: u32| {
            let (mut want, mut got) = ([Gray8::BLACK; 21], [Gray8::BLACK; 21]);
            let area = Rectangle::new(Point::new(x, y), Size::new(len, 1));
            let colors = || (1..=255).map(Gray8::new);
            let mut fb = SliceFramebuffer::new(&mut want, width, height).unwrap();
            fb.fill_contiguous(&area, colors()).unwrap();
            let below = Point::new(x, y.wrapping_add(1));
            fb.fill_solid(&Rectangle::new(below, area.size), Gray8::WHITE)
                .unwrap();
            let mut fb = SliceFramebuffer::new(&mut got, width, height).unwrap();
            fb.fill_row_part(area.top_left, len, colors());
            if let Some((row, _)) = fb.row_part(below, len) {
                fill_row(row, Gray8::WHITE);
            }
            assert_eq!(got, want, "({x}, {y}) + {len}");
        };
        for x in starts {
            for len in lens {
                check(x, (next() % 5) as i32 - 1, len);
            }
        }
        for _ in 0..2_000 {
            let (x, y, len) = (next() % 24, next() % 5, next() % 24);
            check(x as i32 - 12, y as i32 - 1, len as u32);
        }
    }

    /// One-row areas (the fast path): inside, partly outside on either side, empty, past the
    /// last row, and far outside.
    #[test]
    fn one_row_fills_stay_inside() {
        let mut px = [Gray8::BLACK; 12];
        let mut fb = SliceFramebuffer::new(&mut px, 4, 3).unwrap();
        let row = |x: i32, y: i32, w: u32| Rectangle::new(Point::new(x, y), Size::new(w, 1));
        fb.fill_contiguous(&row(-1, 0, 3), (1..=3).map(Gray8::new))
            .unwrap();
        fb.fill_contiguous(&row(2, 1, 5), (4..=8).map(Gray8::new))
            .unwrap();
        fb.fill_solid(&row(1, 2, 2), Gray8::new(9)).unwrap();
        fb.fill_solid(&row(0, 2, 0), Gray8::WHITE).unwrap();
        fb.fill_solid(&row(0, 3, 4), Gray8::WHITE).unwrap();
        fb.fill_solid(&row(i32::MAX - 3, 1, 3), Gray8::WHITE)
            .unwrap();
        fb.fill_contiguous(&row(i32::MIN, 2, 2), [Gray8::WHITE; 2])
            .unwrap();
        let luma: [u8; 12] = core::array::from_fn(|i| px[i].luma());
        assert_eq!(luma, [2, 3, 0, 0, 0, 0, 4, 5, 0, 9, 9, 0]);
    }
}
