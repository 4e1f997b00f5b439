//! Host-side texture conversion (feature `png`): decode a PNG, resize it, reduce it to a palette
//! and write it out as Rust source declaring `static` texel arrays for flash.
//!
//! * [`TextureData`] — an owned RGB image: [`TextureData::from_png`] / [`read_png`] (every PNG
//!   colour type and bit depth; alpha is dropped), [`TextureData::resized`] (area-average
//!   downscale, nearest upscale), [`TextureData::palette`] (exact or median cut).
//! * [`TextureData::to_rust_source`] — the flash emitter, in any [`TexelFormat`]: the arrays a
//!   [`Rgb565Texels`], [`Rgb888Texels`], [`Gray8Texels`], [`Indexed8`] or [`Indexed4`] reads.
//!
//! `examples/texture_tool.rs` runs the whole chain from the command line.
//!
//! ```
//! use embedded_raster::texture::convert::{TexelFormat, TextureData};
//!
//! let image = TextureData {
//!     width: 2,
//!     height: 1,
//!     pixels: vec![[255, 0, 0], [0, 0, 255]],
//! };
//! assert_eq!(image.rgb565(), [0xf800, 0x001f]);
//! let source = image.to_rust_source("FLAG", TexelFormat::Indexed4, "embedded_raster");
//! assert!(source.contains("pub static FLAG_INDICES: [u8; 1] = [0x10];"));
//! ```
//!
//! [`Rgb565Texels`]: super::Rgb565Texels
//! [`Rgb888Texels`]: super::Rgb888Texels
//! [`Gray8Texels`]: super::Gray8Texels
//! [`Indexed8`]: super::Indexed8
//! [`Indexed4`]: super::Indexed4

use std::borrow::ToOwned;
use std::fmt;
use std::format;
use std::io;
use std::path::Path;
use std::string::{String, ToString};
use std::vec;
use std::vec::Vec;

use embedded_graphics::pixelcolor::Rgb565;

/// An owned RGB image on the host: 8 bits a channel, row-major, row 0 at the top.
///
/// `pixels` should hold `width × height` colours; the methods read a missing pixel as black
/// and ignore any extra ones (they never panic on a mismatched length).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct TextureData {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `[r, g, b]` colours, `width` a row, top row first.
    pub pixels: Vec<[u8; 3]>,
}

/// A palette image: colours and one index into them a pixel (from [`TextureData::palette`]).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Palette {
    /// The palette's colours, at most the `max_colors` asked for, in ascending `[r, g, b]`
    /// order, no two equal.
    pub colors: Vec<[u8; 3]>,
    /// One index into `colors` a pixel, row-major.
    pub indices: Vec<u8>,
}

/// How far a palette image is from the image it was made from, in 8-bit channel levels.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct QuantisationError {
    /// Root mean square channel difference: the square root of the mean, over every channel of
    /// every pixel, of the squared difference.
    pub rms: f64,
    /// The largest RGB distance (Euclidean, over the three channels) of any pixel from its
    /// palette colour.
    pub max: f64,
}

/// A storage form for the emitted texels ([`TextureData::to_rust_source`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TexelFormat {
    /// Raw 5-6-5 words (`RawU16` bits), 2 bytes a texel: [`Rgb565Texels`](super::Rgb565Texels).
    Rgb565,
    /// `r, g, b` bytes, 3 bytes a texel: [`Rgb888Texels`](super::Rgb888Texels).
    Rgb888,
    /// A luma byte a texel: [`Gray8Texels`](super::Gray8Texels).
    Gray8,
    /// A byte a texel into a palette of up to 256 Rgb565 colours: [`Indexed8`](super::Indexed8).
    Indexed8,
    /// Half a byte a texel into a palette of up to 16 Rgb565 colours:
    /// [`Indexed4`](super::Indexed4).
    Indexed4,
}

impl TexelFormat {
    /// Every format.
    pub const ALL: [TexelFormat; 5] = [
        TexelFormat::Rgb565,
        TexelFormat::Rgb888,
        TexelFormat::Gray8,
        TexelFormat::Indexed8,
        TexelFormat::Indexed4,
    ];

    /// The format's name as [`str::parse`] takes it: `rgb565`, `rgb888`, `gray8`, `indexed8`,
    /// `indexed4`.
    pub fn name(self) -> &'static str {
        match self {
            TexelFormat::Rgb565 => "rgb565",
            TexelFormat::Rgb888 => "rgb888",
            TexelFormat::Gray8 => "gray8",
            TexelFormat::Indexed8 => "indexed8",
            TexelFormat::Indexed4 => "indexed4",
        }
    }

    /// The most palette colours the format holds (`None` for the direct formats).
    pub fn palette_size(self) -> Option<usize> {
        match self {
            TexelFormat::Indexed8 => Some(256),
            TexelFormat::Indexed4 => Some(16),
            _ => None,
        }
    }

    /// Flash bytes of `texels` texels in this format, without the palette (2 bytes a colour).
    pub fn texel_bytes(self, texels: usize) -> usize {
        match self {
            TexelFormat::Rgb565 => texels.saturating_mul(2),
            TexelFormat::Rgb888 => texels.saturating_mul(3),
            TexelFormat::Gray8 | TexelFormat::Indexed8 => texels,
            TexelFormat::Indexed4 => texels.div_ceil(2),
        }
    }
}

impl fmt::Display for TexelFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl core::str::FromStr for TexelFormat {
    type Err = ConvertError;

    /// A format by its [`name`](TexelFormat::name), ignoring ASCII case.
    fn from_str(s: &str) -> Result<Self, ConvertError> {
        TexelFormat::ALL
            .into_iter()
            .find(|f| f.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| ConvertError::UnknownFormat(s.to_owned()))
    }
}

/// Why an image could not be read.
#[derive(Debug)]
pub enum ConvertError {
    /// The file could not be read.
    Io(io::Error),
    /// The bytes are not a PNG the `png` crate decodes (its message).
    Decode(String),
    /// The decoder produced a colour type and bit depth this module does not handle (it asks
    /// for 8- or 16-bit grey, grey + alpha, RGB or RGBA, which every PNG expands to).
    Unsupported(String),
    /// A [`TexelFormat`] name that is none of them.
    UnknownFormat(String),
}

impl fmt::Display for ConvertError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ConvertError::Io(e) => write!(f, "cannot read the image: {e}"),
            ConvertError::Decode(e) => write!(f, "not a PNG image this decoder reads: {e}"),
            ConvertError::Unsupported(what) => write!(f, "unsupported PNG output: {what}"),
            ConvertError::UnknownFormat(name) => write!(
                f,
                "unknown texel format `{name}`: expected rgb565, rgb888, gray8, indexed8 or indexed4"
            ),
        }
    }
}

impl std::error::Error for ConvertError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ConvertError::Io(e) => Some(e),
            _ => None,
        }
    }
}

impl From<io::Error> for ConvertError {
    fn from(e: io::Error) -> Self {
        ConvertError::Io(e)
    }
}

/// Reads and decodes the PNG file at `path` ([`TextureData::from_png`]).
pub fn read_png(path: impl AsRef<Path>) -> Result<TextureData, ConvertError> {
    TextureData::from_png(&std::fs::read(path)?)
}

/// The raw 5-6-5 word (`RawU16` bits: red in the top five) of an 8-bit colour, each channel
/// rounded to the nearest level: `r5 = (r · 31 + 127) / 255`, `g6 = (g · 63 + 127) / 255`,
/// `b5 = (b · 31 + 127) / 255` in integer division (`c · 31 / 255` is never halfway between
/// two levels, 255 being odd, so there are no ties to break).
pub fn rgb565_bits(c: [u8; 3]) -> u16 {
    let [r, g, b] = rgb565_channels(c);
    (u16::from(r) << 11) | (u16::from(g) << 5) | u16::from(b)
}

/// The 5-, 6- and 5-bit channels of [`rgb565_bits`].
pub fn rgb565_channels([r, g, b]: [u8; 3]) -> [u8; 3] {
    let level = |c: u8, max: u32| ((u32::from(c) * max + 127) / 255) as u8;
    [level(r, 31), level(g, 63), level(b, 31)]
}

/// The luma of an 8-bit colour: `round(0.299 R + 0.587 G + 0.114 B)`, computed exactly as
/// `(299 R + 587 G + 114 B + 500) / 1000` (halves round up).
pub fn luma(c: [u8; 3]) -> u8 {
    let [r, g, b] = c.map(u32::from);
    ((299 * r + 587 * g + 114 * b + 500) / 1000) as u8
}

/// Squared RGB distance.
fn distance2(a: [u8; 3], b: [u8; 3]) -> u32 {
    (0..3)
        .map(|i| {
            let d = i32::from(a[i]) - i32::from(b[i]);
            (d * d) as u32
        })
        .sum()
}

/// The most bytes [`TextureData::from_png`] decodes an image into (1 GiB: a 16384 × 16384
/// RGBA image at 16 bits a sample is 2 GiB; 8 bits, 1 GiB).
const MAX_DECODED_BYTES: usize = 1 << 30;

/// A 16-bit sample scaled to 8 bits, to the nearest level (`v · 255 / 65535` is never halfway).
fn sample16(hi: u8, lo: u8) -> u8 {
    let v = u32::from(u16::from_be_bytes([hi, lo]));
    ((v * 255 + 32767) / 65535) as u8
}

impl TextureData {
    /// Decodes a PNG: any colour type (grey, grey + alpha, RGB, RGBA, indexed) and bit depth
    /// (1, 2, 4, 8, 16) the `png` crate reads, interlaced or not (an animated PNG's default
    /// image).
    ///
    /// Grey becomes `[l, l, l]`; palette images their palette colours; grey below 8 bits is
    /// scaled to 8 bits exactly (1 → 255, 2 bits × 85, 4 bits × 17); 16-bit samples are rounded
    /// to the nearest 8-bit level, `(v · 255 + 32767) / 65535`. **Alpha is dropped**: an alpha
    /// channel or a `tRNS` transparency is ignored, each pixel keeping its stored colour (even
    /// a fully transparent one; nothing is blended over a background). Gamma, colour profiles
    /// and the like are ignored too: the samples are taken as they are.
    ///
    /// Errors: [`ConvertError::Decode`] for anything the decoder refuses (not a PNG, corrupt,
    /// over the decoder's memory limits) and for images over 1 GiB decoded.
    pub fn from_png(bytes: &[u8]) -> Result<TextureData, ConvertError> {
        let decode = |e: ::png::DecodingError| ConvertError::Decode(e.to_string());
        let mut decoder = ::png::Decoder::new(io::Cursor::new(bytes));
        // Palette → RGB(A), grey below 8 bits → 8 bits, tRNS → an alpha channel; 16 bits kept.
        decoder.set_transformations(::png::Transformations::EXPAND);
        let mut reader = decoder.read_info().map_err(decode)?;
        let size = reader
            .output_buffer_size()
            .filter(|&size| size <= MAX_DECODED_BYTES)
            .ok_or_else(|| {
                let info = reader.info();
                ConvertError::Decode(format!(
                    "a {} × {} image is too large to decode here",
                    info.width, info.height
                ))
            })?;
        let mut buf = vec![0; size];
        let frame = reader.next_frame(&mut buf).map_err(decode)?;
        let channels = match frame.color_type {
            ::png::ColorType::Grayscale => 1,
            ::png::ColorType::GrayscaleAlpha => 2,
            ::png::ColorType::Rgb => 3,
            ::png::ColorType::Rgba => 4,
            ::png::ColorType::Indexed => 0,
        };
        let bytes_per_sample = match frame.bit_depth {
            ::png::BitDepth::Eight => 1,
            ::png::BitDepth::Sixteen => 2,
            _ => 0,
        };
        if channels == 0 || bytes_per_sample == 0 {
            return Err(ConvertError::Unsupported(format!(
                "{:?} at {:?} bits",
                frame.color_type, frame.bit_depth
            )));
        }
        let (width, height) = (frame.width, frame.height);
        let pixel_bytes = channels * bytes_per_sample;
        let mut pixels = Vec::new();
        for y in 0..height as usize {
            let row = y
                .checked_mul(frame.line_size)
                .and_then(|start| buf.get(start..)?.get(..frame.line_size))
                .ok_or_else(|| ConvertError::Decode("short image data".to_owned()))?;
            let samples = row.chunks_exact(pixel_bytes).take(width as usize);
            for px in samples {
                let s = |i: usize| {
                    let at = i * bytes_per_sample;
                    if bytes_per_sample == 2 {
                        sample16(px[at], px[at + 1])
                    } else {
                        px[at]
                    }
                };
                pixels.push(if channels < 3 {
                    [s(0); 3]
                } else {
                    [s(0), s(1), s(2)]
                });
            }
        }
        if pixels.len() != width as usize * height as usize {
            return Err(ConvertError::Decode("short image data".to_owned()));
        }
        Ok(TextureData {
            width,
            height,
            pixels,
        })
    }

    /// How many pixels `width × height` is.
    pub fn len(&self) -> usize {
        (self.width as usize).saturating_mul(self.height as usize)
    }

    /// Whether the image has no pixels (a width or height of 0).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The pixel at `(x, y)`: black outside the image or past the end of `pixels`.
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        if x >= self.width || y >= self.height {
            return [0; 3];
        }
        self.at(y as usize * self.width as usize + x as usize)
    }

    /// Pixel `i` in row-major order, black past the end of `pixels`.
    fn at(&self, i: usize) -> [u8; 3] {
        self.pixels.get(i).copied().unwrap_or([0; 3])
    }

    /// The `width × height` pixels in order (missing ones black).
    fn colors(&self) -> impl Iterator<Item = [u8; 3]> + '_ {
        (0..self.len()).map(|i| self.at(i))
    }

    /// The image resized to `width × height`, axis by axis: an axis that shrinks (or keeps its
    /// size) is box-filtered — each new pixel the area-weighted average of the old pixels its
    /// footprint covers, fractions of pixels included, rounded to the nearest level (halves up);
    /// an axis that grows takes the nearest old pixel (the one under the new pixel's centre).
    ///
    /// A 1024 × 1024 image made 256 × 256 averages each 4 × 4 block. The same size returns the
    /// same pixels; a width or height of 0 an empty image; an empty image resized to a
    /// non-empty size is black.
    pub fn resized(&self, width: u32, height: u32) -> TextureData {
        let (xs, wx) = axis_weights(self.width, width);
        let (ys, wy) = axis_weights(self.height, height);
        let total = wx * wy;
        let mut pixels = Vec::with_capacity((width as usize).saturating_mul(height as usize));
        for row in &ys {
            for col in &xs {
                let mut sum = [0u64; 3];
                for &(y, ky) in row {
                    for &(x, kx) in col {
                        let c = self.pixel(x, y);
                        for (s, c) in sum.iter_mut().zip(c) {
                            *s += ky * kx * u64::from(c);
                        }
                    }
                }
                pixels.push(if total == 0 {
                    [0; 3]
                } else {
                    sum.map(|s| ((s + total / 2) / total) as u8)
                });
            }
        }
        TextureData {
            width,
            height,
            pixels,
        }
    }

    /// The distinct colours and how many pixels have each, in ascending `[r, g, b]` order.
    pub fn histogram(&self) -> Vec<([u8; 3], u64)> {
        let mut keys: Vec<u32> = self.colors().map(pack).collect();
        keys.sort_unstable();
        let mut out: Vec<([u8; 3], u64)> = Vec::new();
        for k in keys {
            match out.last_mut() {
                Some((c, n)) if pack(*c) == k => *n += 1,
                _ => out.push((unpack(k), 1)),
            }
        }
        out
    }

    /// The image as palette indices into at most `max_colors` colours (clamped to 2..=256).
    ///
    /// If the image has at most `max_colors` distinct colours the palette is exactly those, in
    /// ascending `[r, g, b]` order, and every pixel reads back as its own colour. Otherwise it
    /// is a median cut of the colours weighted by their pixel counts — the box whose colours
    /// are the most spread (largest summed squared deviation from their mean) is split at the
    /// weighted median of its widest channel, until there are `max_colors` boxes, each giving
    /// its weighted mean colour — and each pixel then takes the nearest palette colour (least
    /// squared RGB distance; the first of equals). Deterministic: no randomness, every tie
    /// broken by order.
    pub fn palette(&self, max_colors: usize) -> Palette {
        let max_colors = max_colors.clamp(2, 256);
        let hist = self.histogram();
        let mut colors = if hist.len() <= max_colors {
            hist.iter().map(|&(c, _)| c).collect()
        } else {
            median_cut(hist.clone(), max_colors)
        };
        colors.sort_unstable();
        colors.dedup();
        // The nearest palette colour of each distinct colour, then of each pixel.
        let nearest: Vec<u8> = hist
            .iter()
            .map(|&(c, _)| {
                let mut best = (u32::MAX, 0);
                for (i, &p) in colors.iter().enumerate() {
                    let d = distance2(c, p);
                    if d < best.0 {
                        best = (d, i);
                    }
                }
                best.1 as u8
            })
            .collect();
        let indices = self
            .colors()
            .map(|c| {
                let k = pack(c);
                hist.binary_search_by_key(&k, |&(h, _)| pack(h))
                    .map_or(0, |i| nearest[i])
            })
            .collect();
        Palette { colors, indices }
    }

    /// The texels as raw 5-6-5 words, rounded by [`rgb565_bits`].
    pub fn rgb565(&self) -> Vec<u16> {
        self.colors().map(rgb565_bits).collect()
    }

    /// The texels as `r, g, b` bytes.
    pub fn rgb888(&self) -> Vec<u8> {
        self.colors().flatten().collect()
    }

    /// The texels as luma bytes ([`luma`]).
    pub fn gray8(&self) -> Vec<u8> {
        self.colors().map(luma).collect()
    }

    /// Rust source declaring the image as `static` texel arrays for firmware, in `format`:
    ///
    /// * `{NAME}_WIDTH` and `{NAME}_HEIGHT`: `pub const` `u32`s.
    /// * Rgb565: `{NAME}_TEXELS: [u16; N]`, raw 5-6-5 words ([`rgb565_bits`]). Rgb888:
    ///   `{NAME}_TEXELS: [u8; 3N]`, `r, g, b` bytes. Gray8: `{NAME}_TEXELS: [u8; N]`, luma
    ///   bytes ([`luma`]).
    /// * Indexed8 and Indexed4: the image reduced by [`palette`](Self::palette) to 256 or 16
    ///   colours, `{NAME}_PALETTE: [Rgb565; K]` (`Rgb565::new(r5, g6, b5)`, channels rounded as
    ///   [`rgb565_channels`]) and `{NAME}_INDICES`: a byte a texel, or for Indexed4 two a byte,
    ///   the even texel in the high nibble, packed across rows (texel `i` of the row-major image
    ///   in byte `i / 2`, as [`Indexed4`](super::Indexed4) reads it: no padding at the rows'
    ///   ends, only the last byte's low nibble 0 when `N` is odd).
    /// * `{NAME}`: the texel source reading them (a [`Rgb565Texels`](super::Rgb565Texels),
    ///   [`Rgb888Texels`](super::Rgb888Texels), [`Gray8Texels`](super::Gray8Texels), or
    ///   [`Indexed8`](super::Indexed8) / [`Indexed4`](super::Indexed4) of `Rgb565`), for
    ///   `Texture::new({NAME}, {NAME}_WIDTH, {NAME}_HEIGHT)`.
    ///
    /// Statics are stored once, in flash (`.rodata`). `crate_path` is how the file names this
    /// crate: `embedded_raster` from another crate, `crate` inside it; palettes name
    /// `embedded_graphics::pixelcolor::Rgb565`. The text is laid out as rustfmt lays it out
    /// (hex values, 16 bytes or 12 words a line).
    pub fn to_rust_source(&self, name: &str, format: TexelFormat, crate_path: &str) -> String {
        self.to_rust_source_from(name, format, crate_path, "")
    }

    /// [`to_rust_source`](Self::to_rust_source) with `origin` (where the image comes from, for
    /// example ``From `logo.png`.``) added to the doc comment of `{NAME}`, a `///` line for each
    /// of its lines.
    pub fn to_rust_source_from(
        &self,
        name: &str,
        format: TexelFormat,
        crate_path: &str,
        origin: &str,
    ) -> String {
        let n = self.len();
        let (w, h) = (self.width, self.height);
        let mut s = String::new();
        s += "//! Generated by `embedded_raster::texture::convert::TextureData::to_rust_source`; do not edit.\n\n";
        let source = match format {
            TexelFormat::Rgb565 => "Rgb565Texels",
            TexelFormat::Rgb888 => "Rgb888Texels",
            TexelFormat::Gray8 => "Gray8Texels",
            TexelFormat::Indexed8 => "Indexed8",
            TexelFormat::Indexed4 => "Indexed4",
        };
        let palette = format.palette_size().map(|k| self.palette(k));
        if palette.is_some() {
            s += "use embedded_graphics::pixelcolor::Rgb565;\n";
        }
        s += &format!("use {crate_path}::texture::{source};\n\n");

        let k = palette.as_ref().map_or(0, |p| p.colors.len());
        let what = match format {
            TexelFormat::Rgb565 => "raw Rgb565 words (`RawU16` bits)".to_owned(),
            TexelFormat::Rgb888 => "Rgb888 `r, g, b` bytes".to_owned(),
            TexelFormat::Gray8 => "Gray8 luma bytes".to_owned(),
            TexelFormat::Indexed8 => format!("8-bit indices into a {k}-colour Rgb565 palette"),
            TexelFormat::Indexed4 => {
                format!("4-bit indices into a {k}-colour Rgb565 palette, two a byte")
            }
        };
        s += &format!("/// `{name}`: {w} × {h} texels in format `{format}`:\n/// {what}.\n");
        for line in origin.lines() {
            s += &format!("/// {line}\n");
        }
        s += "///\n";
        s += &format!(
            "/// `Texture::new({name}, {name}_WIDTH, {name}_HEIGHT)` makes the texture.\n"
        );
        match &palette {
            None => {
                let ty = format!("pub static {name}: {source}<'static> = ");
                let value = format!("{source}(&{name}_TEXELS);");
                if ty.len() + value.len() <= 100 {
                    s += &format!("{ty}{value}\n\n");
                } else {
                    s += &format!("{}\n    {value}\n\n", ty.trim_end());
                }
            }
            Some(_) => {
                s += &format!("pub static {name}: {source}<'static, Rgb565> = {source} {{\n");
                s += &format!("    indices: &{name}_INDICES,\n");
                s += &format!("    palette: &{name}_PALETTE,\n");
                s += "};\n\n";
            }
        }
        s += &format!("/// Width of `{name}` in texels.\n");
        s += &format!("pub const {name}_WIDTH: u32 = {w};\n");
        s += &format!("/// Height of `{name}` in texels.\n");
        s += &format!("pub const {name}_HEIGHT: u32 = {h};\n\n");

        let bytes = |v: &[u8]| -> Vec<String> { v.iter().map(|b| format!("0x{b:02x}")).collect() };
        match (format, palette) {
            (TexelFormat::Rgb565, _) => {
                let words: Vec<String> =
                    self.rgb565().iter().map(|w| format!("0x{w:04x}")).collect();
                s += &format!("/// Texels of `{name}`: raw 5-6-5 words, row-major.\n");
                push_array(
                    &mut s,
                    &format!("pub static {name}_TEXELS: [u16; {n}] = "),
                    &words,
                );
            }
            (TexelFormat::Rgb888, _) => {
                s += &format!("/// Texels of `{name}`: `r, g, b` bytes, row-major.\n");
                let decl = format!("pub static {name}_TEXELS: [u8; {}] = ", n.saturating_mul(3));
                push_array(&mut s, &decl, &bytes(&self.rgb888()));
            }
            (TexelFormat::Gray8, _) => {
                s += &format!("/// Texels of `{name}`: luma bytes, row-major.\n");
                push_array(
                    &mut s,
                    &format!("pub static {name}_TEXELS: [u8; {n}] = "),
                    &bytes(&self.gray8()),
                );
            }
            (_, None) => {}
            (format, Some(p)) => {
                let k = p.colors.len();
                s += &format!("/// Palette of `{name}`.\n");
                let colors: Vec<String> = p
                    .colors
                    .iter()
                    .map(|&c| {
                        let [r, g, b] = rgb565_channels(c);
                        format!("Rgb565::new({r}, {g}, {b})")
                    })
                    .collect();
                push_array(
                    &mut s,
                    &format!("pub static {name}_PALETTE: [Rgb565; {k}] = "),
                    &colors,
                );
                s += "\n";
                let indices = if format == TexelFormat::Indexed4 {
                    s += &format!(
                        "/// Texel indices of `{name}`, row-major, two a byte: the even texel in \
                         the high nibble.\n"
                    );
                    p.packed4()
                } else {
                    s += &format!("/// Texel indices of `{name}`, row-major.\n");
                    p.indices.clone()
                };
                let decl = format!("pub static {name}_INDICES: [u8; {}] = ", indices.len());
                push_array(&mut s, &decl, &bytes(&indices));
            }
        }
        s
    }
}

impl Palette {
    /// The indices packed two a byte, the even index in the high nibble (only the low four bits
    /// of each are kept), a last low nibble of 0 for an odd count: [`Indexed4`](super::Indexed4)'s
    /// layout.
    pub fn packed4(&self) -> Vec<u8> {
        self.indices
            .chunks(2)
            .map(|pair| {
                let lo = pair.get(1).copied().unwrap_or(0) & 0xf;
                ((pair[0] & 0xf) << 4) | lo
            })
            .collect()
    }

    /// The colours in Rgb565, rounded as [`rgb565_channels`].
    pub fn rgb565(&self) -> Vec<Rgb565> {
        self.colors
            .iter()
            .map(|&c| {
                let [r, g, b] = rgb565_channels(c);
                Rgb565::new(r, g, b)
            })
            .collect()
    }

    /// How far the palette image is from `image` (the image it was made from): each pixel's
    /// colour against its palette colour (an index past the palette reads as black, a pixel
    /// without an index is skipped).
    pub fn error(&self, image: &TextureData) -> QuantisationError {
        let (mut sum, mut max, mut count) = (0u64, 0u32, 0u64);
        for (c, &i) in image.colors().zip(&self.indices) {
            let p = self.colors.get(usize::from(i)).copied().unwrap_or([0; 3]);
            let d = distance2(c, p);
            sum += u64::from(d);
            max = max.max(d);
            count += 1;
        }
        if count == 0 {
            return QuantisationError::default();
        }
        QuantisationError {
            rms: (sum as f64 / (3 * count) as f64).sqrt(),
            max: f64::from(max).sqrt(),
        }
    }
}

fn pack([r, g, b]: [u8; 3]) -> u32 {
    (u32::from(r) << 16) | (u32::from(g) << 8) | u32::from(b)
}

fn unpack(k: u32) -> [u8; 3] {
    [(k >> 16) as u8, (k >> 8) as u8, k as u8]
}

/// For each of `to` new pixels along an axis of `from` old ones: the old pixels it reads with
/// their integer weights, and the weights' sum (the same for every new pixel; 0 if `from` is 0).
fn axis_weights(from: u32, to: u32) -> (Vec<Vec<(u32, u64)>>, u64) {
    if from == 0 {
        return ((0..to).map(|_| Vec::new()).collect(), 0);
    }
    let (from64, to64) = (u64::from(from), u64::from(to));
    if to > from {
        // Nearest: the old pixel under the new centre, (i + ½) · from / to.
        let pick = |i: u64| ((2 * i + 1) * from64 / (2 * to64)) as u32;
        return ((0..to64).map(|i| vec![(pick(i), 1)]).collect(), 1);
    }
    // Box: in units of 1 / to of an old pixel, new pixel i spans [i · from, (i + 1) · from) and
    // old pixel j spans [j · to, (j + 1) · to); the weight is their overlap (summing to `from`).
    let weights = (0..to64)
        .map(|i| {
            let (start, end) = (i * from64, (i + 1) * from64);
            (start / to64..end.div_ceil(to64))
                .filter_map(|j| {
                    let overlap = end.min((j + 1) * to64).saturating_sub(start.max(j * to64));
                    (overlap > 0).then_some((j as u32, overlap))
                })
                .collect()
        })
        .collect();
    (weights, from64)
}

/// A box of colours in the median cut: a range of the entries.
struct ColorBox {
    start: usize,
    end: usize,
    /// Pixel count.
    count: u64,
    /// Per channel `count · Σ n c² − (Σ n c)²`: `count²` times the variance.
    spread: [u128; 3],
    /// Per channel `Σ n c`.
    sum: [u64; 3],
}

impl ColorBox {
    fn new(entries: &[([u8; 3], u64)], start: usize, end: usize) -> ColorBox {
        let (mut count, mut sum, mut sum2) = (0u64, [0u64; 3], [0u128; 3]);
        for &(c, n) in &entries[start..end] {
            count += n;
            for i in 0..3 {
                sum[i] += n * u64::from(c[i]);
                sum2[i] += u128::from(n) * u128::from(c[i]) * u128::from(c[i]);
            }
        }
        let spread = core::array::from_fn(|i| {
            (u128::from(count) * sum2[i]).saturating_sub(u128::from(sum[i]) * u128::from(sum[i]))
        });
        ColorBox {
            start,
            end,
            count,
            spread,
            sum,
        }
    }

    /// The summed squared deviation from the mean over the channels (`Σ spread / count`).
    fn error(&self) -> u128 {
        self.spread.iter().sum::<u128>() / u128::from(self.count.max(1))
    }

    fn mean(&self) -> [u8; 3] {
        let n = self.count.max(1);
        self.sum.map(|s| ((s + n / 2) / n) as u8)
    }
}

/// Median cut of the weighted colours `entries` (distinct, more than `k`) into `k` colours.
fn median_cut(mut entries: Vec<([u8; 3], u64)>, k: usize) -> Vec<[u8; 3]> {
    let mut boxes = vec![ColorBox::new(&entries, 0, entries.len())];
    while boxes.len() < k {
        // The most spread box that can be split (the first of equals).
        let mut pick: Option<(usize, u128)> = None;
        for (i, b) in boxes.iter().enumerate() {
            if b.end - b.start >= 2 && pick.is_none_or(|(_, e)| b.error() > e) {
                pick = Some((i, b.error()));
            }
        }
        let Some((i, _)) = pick else { break };
        let b = boxes.remove(i);
        // Its widest channel (the first of equals), then its colours in that channel's order.
        let mut channel = 0;
        for c in 1..3 {
            if b.spread[c] > b.spread[channel] {
                channel = c;
            }
        }
        let slice = &mut entries[b.start..b.end];
        slice.sort_unstable_by_key(|&(c, _)| (c[channel], c));
        // The weighted median: the first entry at which half the pixels are counted, leaving at
        // least one entry on either side.
        let mut seen = 0;
        let mut cut = slice.len() - 1;
        for (j, &(_, n)) in slice.iter().enumerate() {
            seen += n;
            if 2 * seen >= b.count {
                cut = j + 1;
                break;
            }
        }
        let mid = b.start + cut.clamp(1, slice.len() - 1);
        let (left, right) = (
            ColorBox::new(&entries, b.start, mid),
            ColorBox::new(&entries, mid, b.end),
        );
        boxes.insert(i, right);
        boxes.insert(i, left);
    }
    boxes.iter().map(ColorBox::mean).collect()
}

/// Appends `{decl}[items];` as rustfmt lays an array out: on one line if it fits (the array in
/// 60 columns, the line in 100), else short items (up to 10 characters) packed into lines of up
/// to 100 columns, else one item a line.
fn push_array(s: &mut String, decl: &str, items: &[String]) {
    let one_line = format!("[{}]", items.join(", "));
    if one_line.len() <= 60 && decl.len() + one_line.len() < 100 {
        *s += &format!("{decl}{one_line};\n");
        return;
    }
    *s += decl;
    *s += "[\n";
    if items.iter().all(|i| i.len() <= 10) {
        let mut line = String::new();
        for item in items {
            if !line.is_empty() && line.len() + 1 + item.len() + 1 > 100 {
                *s += &line;
                *s += "\n";
                line.clear();
            }
            if line.is_empty() {
                line += "    ";
            } else {
                line += " ";
            }
            line += item;
            line += ",";
        }
        if !line.is_empty() {
            *s += &line;
            *s += "\n";
        }
    } else {
        for item in items {
            *s += &format!("    {item},\n");
        }
    }
    *s += "];\n";
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The errors' messages: what was wrong with what was given (issue #32, item 2).
    #[test]
    fn convert_error_messages() {
        let io = ConvertError::Io(io::Error::new(io::ErrorKind::NotFound, "no such file"));
        assert_eq!(io.to_string(), "cannot read the image: no such file");
        assert!(std::error::Error::source(&io).is_some());
        let decode = ConvertError::Decode("bad signature".to_owned());
        assert_eq!(
            decode.to_string(),
            "not a PNG image this decoder reads: bad signature"
        );
        let unsupported = ConvertError::Unsupported("4-bit grey".to_owned());
        assert_eq!(
            unsupported.to_string(),
            "unsupported PNG output: 4-bit grey"
        );
        let unknown = ConvertError::UnknownFormat("rgb332".to_owned());
        assert_eq!(
            unknown.to_string(),
            "unknown texel format `rgb332`: expected rgb565, rgb888, gray8, indexed8 or indexed4"
        );
    }
}
