//! Textures: borrowed texels sampled at fixed-point texel coordinates, and the textured spans
//! the raster core's span shaders fill with them.
//!
//! * `source` — [`TexelSource`]: texel storage in flash or RAM ([`Rgb565Texels`],
//!   [`Rgb888Texels`], [`Gray8Texels`], the palette forms [`Indexed8`] and [`Indexed4`], and
//!   [`Direct`] colour slices).
//! * `address` — [`Wrap`]: repeat, mirrored repeat and clamp, a mask for power-of-two sizes.
//! * `map` — [`Texture`]: a source with its size, wrap modes and [`Filter`] (nearest or
//!   bilinear), sampled at 16.16 texel coordinates.
//! * `span` — the span loops: texel coordinates stepped along a span from the attribute planes.
//! * `convert` (feature `png`, host) — PNG decoding, resizing, palette reduction and the
//!   flash emitter: a PNG as Rust source of `static` texel arrays.
//!
//! Texel coordinates are in texels: `(0, 0)` is the top-left corner of texel `(0, 0)`, `(i + ½,
//! j + ½)` the centre of texel `(i, j)`, `y` down (the image's rows), as [`TexelCoord`]s
//! (`I16F16`) on the way in and 16.16 `i32`s on the drawing paths.

mod address;
#[cfg(feature = "png")]
pub mod convert;
mod map;
mod source;
pub(crate) mod span;

pub use address::Wrap;
pub use map::{Filter, Texture, TextureError, MAX_SIZE};
pub use source::{
    Direct, Gray8Texels, Indexed4, Indexed8, Rgb565Texels, Rgb888Texels, Solid, TexelSource,
};

/// A texel coordinate: signed 16.16 fixed point in texels (the `fixed` crate's `I16F16`).
pub type TexelCoord = fixed::types::I16F16;

/// A number that converts to a [`TexelCoord`]: `f32` and `f64` (rounded to the nearest 2⁻¹⁶
/// texel, saturated to ±2¹⁵ texels, NaN as 0) and `TexelCoord` itself.
pub trait ToTexel: Copy {
    /// The texel coordinate.
    fn to_texel(self) -> TexelCoord;
}

impl ToTexel for TexelCoord {
    #[inline(always)]
    fn to_texel(self) -> TexelCoord {
        self
    }
}

impl ToTexel for f32 {
    fn to_texel(self) -> TexelCoord {
        f64::from(self).to_texel()
    }
}

impl ToTexel for f64 {
    fn to_texel(self) -> TexelCoord {
        if self.is_nan() {
            TexelCoord::ZERO
        } else {
            TexelCoord::saturating_from_num(self)
        }
    }
}
