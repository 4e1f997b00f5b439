//! PNG files of framebuffers (feature `png`, host): the `png` crate's encoder, which
//! embedded-graphics-simulator uses too.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;
use std::vec::Vec;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;

use super::framebuffer::SliceFramebuffer;

/// Writes a `width × height` PNG of `color_type` samples, 8 or 16 bits each (`bits`), from
/// row-major `data` (16-bit samples big-endian).
pub(crate) fn write_png(
    out: impl Write,
    width: u32,
    height: u32,
    color_type: ::png::ColorType,
    bits: ::png::BitDepth,
    data: &[u8],
) -> io::Result<()> {
    let mut encoder = ::png::Encoder::new(out, width, height);
    encoder.set_color(color_type);
    encoder.set_depth(bits);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(data)?;
    writer.finish()?;
    Ok(())
}

impl<C: PixelColor + Into<Rgb888>> SliceFramebuffer<'_, C> {
    /// Writes the pixels as an 8-bit RGB PNG (feature `png`; every embedded-graphics colour
    /// converts to `Rgb888`: 5-6-5 channels are scaled to 8 bits, grey and binary colours become
    /// grey levels).
    pub fn write_png(&self, out: impl Write) -> io::Result<()> {
        let data: Vec<u8> = self
            .pixels()
            .iter()
            .flat_map(|&c| {
                let c: Rgb888 = c.into();
                [c.r(), c.g(), c.b()]
            })
            .collect();
        let Size { width, height } = self.size();
        write_png(
            out,
            width,
            height,
            ::png::ColorType::Rgb,
            ::png::BitDepth::Eight,
            &data,
        )
    }

    /// Saves the pixels as an 8-bit RGB PNG file at `path` (feature `png`), replacing it.
    ///
    /// ```no_run
    /// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
    /// use embedded_raster::SliceFramebuffer;
    ///
    /// let mut pixels = vec![Rgb565::BLUE; 320 * 240];
    /// let frame = SliceFramebuffer::new(&mut pixels, 320, 240).unwrap();
    /// frame.save_png("frame.png")?;
    /// # Ok::<(), std::io::Error>(())
    /// ```
    pub fn save_png(&self, path: impl AsRef<Path>) -> io::Result<()> {
        let mut file = BufWriter::new(File::create(path)?);
        self.write_png(&mut file)?;
        file.flush()
    }
}
