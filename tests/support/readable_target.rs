//! A `W × H` target with nothing but `draw_iter` (embedded-graphics' default `fill_contiguous`
//! and `fill_solid` hand it one `Pixel` at a time), readable through `GetPixel`: what the
//! translucent and anti-aliased suites draw into besides a `SliceFramebuffer`.
#![allow(dead_code)]

use embedded_graphics::image::GetPixel;
use embedded_graphics::prelude::*;
use embedded_graphics::Pixel;

pub struct ReadableTarget<C> {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<C>,
}

impl<C: PixelColor> ReadableTarget<C> {
    pub fn new(width: u32, height: u32, pixels: Vec<C>) -> Self {
        ReadableTarget {
            width,
            height,
            pixels,
        }
    }

    fn index(&self, p: Point) -> Option<usize> {
        let inside =
            p.x >= 0 && p.y >= 0 && (p.x as u32) < self.width && (p.y as u32) < self.height;
        inside.then(|| (p.y as u32 * self.width + p.x as u32) as usize)
    }
}

impl<C: PixelColor> OriginDimensions for ReadableTarget<C> {
    fn size(&self) -> Size {
        Size::new(self.width, self.height)
    }
}

impl<C: PixelColor> DrawTarget for ReadableTarget<C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            if let Some(i) = self.index(p) {
                self.pixels[i] = c;
            }
        }
        Ok(())
    }
}

impl<C: PixelColor> GetPixel for ReadableTarget<C> {
    type Color = C;

    fn pixel(&self, p: Point) -> Option<C> {
        self.index(p).map(|i| self.pixels[i])
    }
}
