//! Where texels come from: borrowed arrays (flash or RAM) in the storage forms firmware keeps
//! textures in, each read by index as one colour.
//!
//! * [`Rgb565Texels`] — raw 16-bit 5-6-5 words (`RawU16` bits), 2 bytes a texel.
//! * [`Rgb888Texels`] — `r, g, b` bytes, 3 bytes a texel.
//! * [`Gray8Texels`] — one luma byte a texel.
//! * [`Indexed8`] — a byte a texel into a palette of up to 256 colours.
//! * [`Indexed4`] — half a byte a texel (the first texel of a byte in its high nibble, as PNG
//!   packs them) into a palette of up to 16 colours: a quarter of Rgb565's flash.
//! * [`Direct`] — a slice of any colour type (a framebuffer used as a texture, for example).
//!
//! A source is only ever read at indices below `width × height`, which [`Texture::new`]
//! checks against [`TexelSource::texels`] once.
//!
//! [`Texture::new`]: super::Texture::new

use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::{Gray8, Rgb565, Rgb888};
use embedded_graphics::prelude::PixelColor;

/// Texel storage: how many texels it holds and the colour at an index (row-major, row 0 at the
/// top). Sources are small borrowed views (`Copy`), handed to the span loops by value.
pub trait TexelSource: Copy {
    /// The colour a texel reads as.
    type Color: PixelColor;

    /// How many texels the storage holds.
    fn texels(&self) -> usize;

    /// The texel at `index`, for `index < self.texels()`; any colour beyond (never panics).
    fn texel(&self, index: usize) -> Self::Color;

    /// [`texel`](Self::texel) without the bounds check: the masked loops' fetch, whose indices
    /// are below the texture's size by construction. By default `texel` itself.
    ///
    /// # Safety
    ///
    /// `index < self.texels()`.
    #[allow(unsafe_code)]
    #[inline(always)]
    unsafe fn texel_unchecked(&self, index: usize) -> Self::Color {
        self.texel(index)
    }

    /// The same storage cut after texel `last`, if it holds that one: the masked loops of
    /// power-of-two textures read it at indices masked to at most `last`, which the compiler
    /// then needs no bounds check for. `None` (the default): those loops read `self`.
    #[inline(always)]
    fn prefix(&self, last: usize) -> Option<Self>
    where
        Self: Sized,
    {
        let _ = last;
        None
    }

    /// The texels as raw Rgb565 words, if they are stored so (the texel at `index` being
    /// `Rgb565::from(RawU16::new(words[index]))`): for span loops that copy them. Hidden: its
    /// return type cannot be named outside the crate, so only the crate's sources say yes.
    #[doc(hidden)]
    #[inline(always)]
    fn rgb565_words(&self) -> Option<Rgb565Words<'_>> {
        None
    }

    /// The texels as 4-bit palette indices and their palette, if they are stored so (as
    /// [`Indexed4`]: two indices a byte, the even texel in the high nibble): for the row loops
    /// that look them up. Hidden: the crate's own sources say yes.
    #[doc(hidden)]
    #[inline(always)]
    fn palette4(&self) -> Option<(&[u8], &[Self::Color])> {
        None
    }
}

/// Raw Rgb565 texel words ([`TexelSource::rgb565_words`]): public in this private module, so
/// that no source outside the crate can claim to be one.
#[derive(Debug, Clone, Copy)]
pub struct Rgb565Words<'a>(pub(crate) &'a [u16]);

/// Rgb565 texels as raw 16-bit words (embedded-graphics' `RawU16` bits: red in the top five).
///
/// ```
/// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// use embedded_raster::texture::{Rgb565Texels, TexelSource};
///
/// static TEXELS: [u16; 2] = [0xf800, 0x07e0];
/// assert_eq!(Rgb565Texels(&TEXELS).texel(1), Rgb565::GREEN);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rgb565Texels<'a>(pub &'a [u16]);

impl TexelSource for Rgb565Texels<'_> {
    type Color = Rgb565;

    #[inline(always)]
    fn texels(&self) -> usize {
        self.0.len()
    }

    #[inline(always)]
    fn texel(&self, index: usize) -> Rgb565 {
        Rgb565::from(RawU16::new(self.0.get(index).copied().unwrap_or(0)))
    }

    #[allow(unsafe_code)]
    #[inline(always)]
    unsafe fn texel_unchecked(&self, index: usize) -> Rgb565 {
        // SAFETY: `index < self.texels()`, the slice's length (the caller's contract).
        Rgb565::from(RawU16::new(unsafe { *self.0.get_unchecked(index) }))
    }

    #[inline(always)]
    fn prefix(&self, last: usize) -> Option<Self> {
        Some(Rgb565Texels(self.0.get(..=last)?))
    }

    #[inline(always)]
    fn rgb565_words(&self) -> Option<Rgb565Words<'_>> {
        Some(Rgb565Words(self.0))
    }
}

/// Rgb888 texels as `r, g, b` bytes, three a texel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rgb888Texels<'a>(pub &'a [u8]);

impl TexelSource for Rgb888Texels<'_> {
    type Color = Rgb888;

    #[inline(always)]
    fn texels(&self) -> usize {
        self.0.len() / 3
    }

    #[inline(always)]
    fn texel(&self, index: usize) -> Rgb888 {
        let bytes = index.checked_mul(3).and_then(|i| self.0.get(i..)?.get(..3));
        match bytes {
            Some(&[r, g, b]) => Rgb888::new(r, g, b),
            _ => Rgb888::new(0, 0, 0),
        }
    }

    #[inline(always)]
    fn prefix(&self, last: usize) -> Option<Self> {
        Some(Rgb888Texels(
            self.0.get(..=last.checked_mul(3)?.checked_add(2)?)?,
        ))
    }
}

/// Gray8 texels, a luma byte each.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Gray8Texels<'a>(pub &'a [u8]);

impl TexelSource for Gray8Texels<'_> {
    type Color = Gray8;

    #[inline(always)]
    fn texels(&self) -> usize {
        self.0.len()
    }

    #[inline(always)]
    fn texel(&self, index: usize) -> Gray8 {
        Gray8::new(self.0.get(index).copied().unwrap_or(0))
    }

    #[allow(unsafe_code)]
    #[inline(always)]
    unsafe fn texel_unchecked(&self, index: usize) -> Gray8 {
        // SAFETY: `index < self.texels()`, the slice's length (the caller's contract).
        Gray8::new(unsafe { *self.0.get_unchecked(index) })
    }

    #[inline(always)]
    fn prefix(&self, last: usize) -> Option<Self> {
        Some(Gray8Texels(self.0.get(..=last)?))
    }
}

/// Texels as byte indices into a palette of colours. An index past the palette's end reads as
/// its first colour (or the default colour of an empty palette).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Indexed8<'a, C> {
    /// One palette index a texel.
    pub indices: &'a [u8],
    /// The colours the indices name.
    pub palette: &'a [C],
}

impl<C: PixelColor + Default> TexelSource for Indexed8<'_, C> {
    type Color = C;

    #[inline(always)]
    fn texels(&self) -> usize {
        self.indices.len()
    }

    #[inline(always)]
    fn texel(&self, index: usize) -> C {
        let i = self.indices.get(index).copied().unwrap_or(0);
        palette_color(self.palette, usize::from(i))
    }

    #[inline(always)]
    fn prefix(&self, last: usize) -> Option<Self> {
        Some(Indexed8 {
            indices: self.indices.get(..=last)?,
            palette: self.palette,
        })
    }
}

/// Texels as 4-bit indices into a palette of up to 16 colours, two a byte: the texel at an even
/// index in the high nibble, the next in the low one (PNG's packing).
///
/// ```
/// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// use embedded_raster::texture::{Indexed4, TexelSource};
///
/// static PALETTE: [Rgb565; 3] = [Rgb565::BLACK, Rgb565::RED, Rgb565::BLUE];
/// static INDICES: [u8; 1] = [0x12];
/// let texels = Indexed4 { indices: &INDICES, palette: &PALETTE };
/// assert_eq!((texels.texel(0), texels.texel(1)), (Rgb565::RED, Rgb565::BLUE));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Indexed4<'a, C> {
    /// Two palette indices a byte.
    pub indices: &'a [u8],
    /// The colours the indices name.
    pub palette: &'a [C],
}

impl<C: PixelColor + Default> TexelSource for Indexed4<'_, C> {
    type Color = C;

    #[inline(always)]
    fn texels(&self) -> usize {
        self.indices.len().saturating_mul(2)
    }

    #[inline(always)]
    fn texel(&self, index: usize) -> C {
        let byte = self.indices.get(index / 2).copied().unwrap_or(0);
        // The even texel in the high nibble: shift by 4 for it, 0 for the odd one.
        let i = (byte >> (4 - 4 * (index as u32 & 1))) & 0xf;
        palette_color(self.palette, usize::from(i))
    }

    #[inline(always)]
    fn prefix(&self, last: usize) -> Option<Self> {
        Some(Indexed4 {
            indices: self.indices.get(..=last / 2)?,
            palette: self.palette,
        })
    }

    #[inline(always)]
    fn palette4(&self) -> Option<(&[u8], &[C])> {
        Some((self.indices, self.palette))
    }
}

/// Texels stored as colours of any type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Direct<'a, C>(pub &'a [C]);

impl<C: PixelColor + Default> TexelSource for Direct<'_, C> {
    type Color = C;

    #[inline(always)]
    fn texels(&self) -> usize {
        self.0.len()
    }

    #[inline(always)]
    fn texel(&self, index: usize) -> C {
        self.0.get(index).copied().unwrap_or_default()
    }

    #[allow(unsafe_code)]
    #[inline(always)]
    unsafe fn texel_unchecked(&self, index: usize) -> C {
        // SAFETY: `index < self.texels()`, the slice's length (the caller's contract).
        unsafe { *self.0.get_unchecked(index) }
    }

    #[inline(always)]
    fn prefix(&self, last: usize) -> Option<Self> {
        Some(Direct(self.0.get(..=last)?))
    }
}

/// One colour as a texture's only texel: with a 1 × 1 [`Texture`](super::Texture) it makes a
/// `three_d::TexturedMaterial` of a plain colour — the textured pipeline's perspective-correct
/// light levels, vertex colours and highlights for an untextured mesh (a `three_d::Material`'s
/// levels are interpolated in screen space).
///
/// ```
/// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// use embedded_raster::texture::{Solid, Texture};
/// use embedded_raster::three_d::{Shading, TexturedMaterial};
///
/// let texture = Texture::new(Solid(Rgb565::YELLOW), 1, 1).unwrap();
/// let material = TexturedMaterial::new(&texture, Shading::Gouraud);
/// # let _ = material;
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Solid<C>(pub C);

impl<C: PixelColor> TexelSource for Solid<C> {
    type Color = C;

    #[inline(always)]
    fn texels(&self) -> usize {
        1
    }

    #[inline(always)]
    fn texel(&self, _: usize) -> C {
        self.0
    }

    #[inline(always)]
    fn prefix(&self, last: usize) -> Option<Self> {
        (last == 0).then_some(*self)
    }
}

/// Palette entry `i`, or the first entry for an index past the end.
#[inline(always)]
fn palette_color<C: Copy + Default>(palette: &[C], i: usize) -> C {
    match palette.get(i) {
        Some(&c) => c,
        None => palette.first().copied().unwrap_or_default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::pixelcolor::RgbColor;

    #[test]
    fn every_source_reads_its_texels_and_nothing_past_them() {
        let rgb = [1u8, 2, 3, 4, 5, 6, 7];
        let s = Rgb888Texels(&rgb);
        assert_eq!(s.texels(), 2);
        assert_eq!(s.texel(1), Rgb888::new(4, 5, 6));
        assert_eq!(s.texel(2), Rgb888::new(0, 0, 0));
        assert_eq!(s.texel(usize::MAX), Rgb888::new(0, 0, 0));

        let palette = [Rgb565::RED, Rgb565::GREEN];
        let s = Indexed8 {
            indices: &[1, 0, 9],
            palette: &palette,
        };
        assert_eq!(
            [s.texel(0), s.texel(1), s.texel(2), s.texel(3)],
            [Rgb565::GREEN, Rgb565::RED, Rgb565::RED, Rgb565::RED]
        );
        let s = Indexed4 {
            indices: &[0x10, 0x01],
            palette: &palette,
        };
        assert_eq!(s.texels(), 4);
        assert_eq!(
            [s.texel(0), s.texel(1), s.texel(2), s.texel(3)],
            [Rgb565::GREEN, Rgb565::RED, Rgb565::RED, Rgb565::GREEN]
        );
        assert_eq!(s.texel(usize::MAX), Rgb565::RED);
        assert_eq!(Gray8Texels(&[9]).texel(0), Gray8::new(9));
        assert_eq!(Rgb565Texels(&[0x001f]).texel(0), Rgb565::BLUE);
        assert_eq!(Direct::<Rgb565>(&[]).texel(0), Rgb565::default());
    }
}
