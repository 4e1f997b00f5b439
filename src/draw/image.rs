//! Blitting: a [`SliceFramebuffer`] is an embedded-graphics [`ImageDrawable`], so
//! `Image::new(&framebuffer, position).draw(&mut display)` copies it to any [`DrawTarget`] (a
//! display driver, the simulator, another framebuffer) one `fill_contiguous` a row.
//!
//! ```
//! use embedded_graphics::{image::Image, pixelcolor::Rgb565, prelude::*};
//! use embedded_raster::{SliceFramebuffer, SolidTriangle};
//!
//! let mut pixels = [Rgb565::BLACK; 16 * 16];
//! let mut frame = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
//! SolidTriangle::new([(0.0, 0.0), (16.0, 0.0), (0.0, 16.0)], Rgb565::RED).draw_into(&mut frame);
//!
//! let mut screen_pixels = [Rgb565::BLACK; 64 * 64];
//! let mut screen = SliceFramebuffer::new(&mut screen_pixels, 64, 64).unwrap();
//! Image::new(&frame, Point::new(40, 8)).draw(&mut screen)?;
//! assert_eq!(screen.get(40, 8), Some(Rgb565::RED));
//! // Another colour format: convert on the way.
//! let mut gray = [embedded_graphics::pixelcolor::Gray8::BLACK; 16 * 16];
//! let mut gray_fb = SliceFramebuffer::new(&mut gray, 16, 16).unwrap();
//! Image::new(&frame, Point::zero()).draw(&mut gray_fb.color_converted())?;
//! # Ok::<(), core::convert::Infallible>(())
//! ```

use embedded_graphics::image::ImageDrawable;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::framebuffer::SliceFramebuffer;
use crate::rect::intersection;

/// Draws the part `area` (image coordinates) of a `size` image at the target's origin, a row at a
/// time: `row(y, x_start, x_end)` gives the colours of columns `x_start..x_end` of row `y`.
/// Nothing outside the image is read; an `area` reaching outside it is clipped.
pub(crate) fn draw_rows<D, I>(
    target: &mut D,
    size: Size,
    area: &Rectangle,
    mut row: impl FnMut(usize, usize, usize) -> I,
) -> Result<(), D::Error>
where
    D: DrawTarget,
    I: IntoIterator<Item = D::Color>,
{
    // The part of `area` inside the image (for any rectangle: `crate::rect`), and where it
    // lands: its offset in `area`, off every target when beyond `i32`.
    let inside = intersection(area, &Rectangle::new(Point::zero(), size));
    let (Some(dx), Some(dy)) = (
        inside.top_left.x.checked_sub(area.top_left.x),
        inside.top_left.y.checked_sub(area.top_left.y),
    ) else {
        return Ok(());
    };
    // Inside the image: non-negative, below its size.
    let (x0, y0) = (inside.top_left.x as usize, inside.top_left.y as usize);
    let (x1, y1) = (
        x0 + inside.size.width as usize,
        y0 + inside.size.height as usize,
    );
    for (k, y) in (y0..y1).enumerate() {
        // Rows beyond i32 are off every target.
        let Some(ty) = i32::try_from(k).ok().and_then(|k| dy.checked_add(k)) else {
            break;
        };
        let line = Rectangle::new(Point::new(dx, ty), Size::new((x1 - x0) as u32, 1));
        target.fill_contiguous(&line, row(y, x0, x1))?;
    }
    Ok(())
}

impl<C: PixelColor> ImageDrawable for SliceFramebuffer<'_, C> {
    type Color = C;

    /// The whole framebuffer, one `fill_contiguous` call.
    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        target.fill_contiguous(&self.bounding_box(), self.pixels().iter().copied())
    }

    /// The pixels of `area` (framebuffer coordinates, clipped to the framebuffer), drawn at the
    /// target's origin.
    fn draw_sub_image<D>(&self, target: &mut D, area: &Rectangle) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        let width = self.size().width as usize;
        let pixels = self.pixels();
        draw_rows(target, self.size(), area, |y, a, b| {
            pixels[y * width + a..y * width + b].iter().copied()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::image::Image;
    use embedded_graphics::pixelcolor::Gray8;

    /// Sub-images against a per-pixel copy, including areas reaching outside the image, far
    /// away, and at the ends of the `i32` range.
    #[test]
    fn sub_images_copy_the_right_pixels() {
        let src_at = |x: i64, y: i64| Gray8::new((y * 5 + x) as u8 + 1);
        let mut src: [Gray8; 5 * 4] = core::array::from_fn(|i| Gray8::new(i as u8 + 1));
        let image = SliceFramebuffer::new(&mut src, 5, 4).unwrap();
        let mut next = crate::random(3);
        // The whole image through `Image`.
        let mut got = [Gray8::BLACK; 12 * 12];
        let mut fb = SliceFramebuffer::new(&mut got, 12, 12).unwrap();
        Image::new(&image, Point::new(7, 1)).draw(&mut fb).unwrap();
        assert_eq!(fb.get(7, 1), Some(Gray8::new(1)));
        assert_eq!(fb.get(11, 4), Some(Gray8::new(20)));
        for case in 0..2000 {
            let coord = |next: &mut dyn FnMut() -> u64| match next() % 8 {
                0 => i32::MIN,
                1 => i32::MAX - 3,
                _ => (next() % 12) as i32 - 4,
            };
            let area = Rectangle::new(
                Point::new(coord(&mut next), coord(&mut next)),
                Size::new((next() % 9) as u32, (next() % 9) as u32),
            );
            let at = Point::new((next() % 6) as i32 - 2, (next() % 6) as i32 - 2);
            let mut got = [Gray8::BLACK; 12 * 12];
            let mut fb = SliceFramebuffer::new(&mut got, 12, 12).unwrap();
            image.draw_sub_image(&mut fb.translated(at), &area).unwrap();
            // Reference: every image pixel inside the area, moved to `at` (in i64).
            let mut want = [Gray8::BLACK; 12 * 12];
            let (ax, ay) = (i64::from(area.top_left.x), i64::from(area.top_left.y));
            let (aw, ah) = (i64::from(area.size.width), i64::from(area.size.height));
            for y in 0..4i64 {
                for x in 0..5i64 {
                    if x >= ax && x < ax + aw && y >= ay && y < ay + ah {
                        let (qx, qy) = (x - ax + i64::from(at.x), y - ay + i64::from(at.y));
                        if (0..12).contains(&qx) && (0..12).contains(&qy) {
                            want[(qy * 12 + qx) as usize] = src_at(x, y);
                        }
                    }
                }
            }
            assert_eq!(got, want, "case {case}: {area:?} at {at:?}");
        }
    }
}
