//! Colour channels the rasterizer interpolates.
//!
//! [`GouraudColor`] splits a colour into up to three integer channels in its own depth
//! (`Rgb565`: 5, 6 and 5 bits) and builds it back. Interpolating in the target's own depth is what
//! makes the "within 1 LSB" guarantee meaningful for every format.
//!
//! ```
//! use embedded_graphics::pixelcolor::{Rgb565, Gray8};
//! use embedded_raster::GouraudColor;
//!
//! assert_eq!(Rgb565::new(31, 40, 2).channels(), [31, 40, 2]);
//! assert_eq!(Gray8::from_channels([77, 0, 0]), Gray8::new(77));
//! ```

use embedded_graphics::pixelcolor::{
    Bgr555, Bgr565, Bgr666, Bgr888, BinaryColor, Gray2, Gray4, Gray8, GrayColor, Rgb555, Rgb565,
    Rgb666, Rgb888, RgbColor,
};
use embedded_graphics::prelude::PixelColor;

/// A colour that can be Gouraud-interpolated channel by channel.
pub trait GouraudColor: PixelColor {
    /// Number of meaningful channels (1 for grey and binary colours, 3 for RGB).
    const CHANNELS: usize;
    /// Largest value of each channel (unused channels are 0).
    const MAX: [u8; 3];
    /// The channel values, each in `0..=MAX[k]`.
    fn channels(self) -> [u8; 3];
    /// The colour with these channel values (each in `0..=MAX[k]`).
    fn from_channels(channels: [u8; 3]) -> Self;
}

macro_rules! rgb_color {
    ($($t:ty),*) => {$(
        impl GouraudColor for $t {
            const CHANNELS: usize = 3;
            const MAX: [u8; 3] = [<$t>::MAX_R, <$t>::MAX_G, <$t>::MAX_B];
            #[inline]
            fn channels(self) -> [u8; 3] {
                [self.r(), self.g(), self.b()]
            }
            #[inline]
            fn from_channels(c: [u8; 3]) -> Self {
                <$t>::new(c[0], c[1], c[2])
            }
        }
    )*};
}

macro_rules! gray_color {
    ($($t:ty = $max:expr),*) => {$(
        impl GouraudColor for $t {
            const CHANNELS: usize = 1;
            const MAX: [u8; 3] = [$max, 0, 0];
            #[inline]
            fn channels(self) -> [u8; 3] {
                [self.luma(), 0, 0]
            }
            #[inline]
            fn from_channels(c: [u8; 3]) -> Self {
                <$t>::new(c[0])
            }
        }
    )*};
}

rgb_color!(Rgb555, Bgr555, Rgb565, Bgr565, Rgb666, Bgr666, Rgb888, Bgr888);
gray_color!(Gray2 = 3, Gray4 = 15, Gray8 = 255);

impl GouraudColor for BinaryColor {
    const CHANNELS: usize = 1;
    const MAX: [u8; 3] = [1, 0, 0];
    #[inline]
    fn channels(self) -> [u8; 3] {
        [u8::from(self.is_on()), 0, 0]
    }
    #[inline]
    fn from_channels(c: [u8; 3]) -> Self {
        BinaryColor::from(c[0] != 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip<C: GouraudColor + core::fmt::Debug>() {
        for v in 0..=255u8 {
            let c = [v.min(C::MAX[0]), v.min(C::MAX[1]), v.min(C::MAX[2])];
            assert_eq!(
                C::from_channels(c).channels(),
                c,
                "{}",
                core::any::type_name::<C>()
            );
        }
    }

    #[test]
    fn channels_round_trip() {
        round_trip::<Rgb565>();
        round_trip::<Bgr565>();
        round_trip::<Rgb555>();
        round_trip::<Bgr555>();
        round_trip::<Rgb666>();
        round_trip::<Bgr666>();
        round_trip::<Rgb888>();
        round_trip::<Bgr888>();
        round_trip::<Gray2>();
        round_trip::<Gray4>();
        round_trip::<Gray8>();
        round_trip::<BinaryColor>();
        assert_eq!(Rgb565::MAX, [31, 63, 31]);
    }
}
