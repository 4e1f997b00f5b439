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

use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::{
    Bgr555, Bgr565, Bgr666, Bgr888, BinaryColor, Gray2, Gray4, Gray8, GrayColor, Rgb555, Rgb565,
    Rgb666, Rgb888, RgbColor,
};
use embedded_graphics::prelude::PixelColor;

use crate::interpolation::AttributePlane;

/// Fractional bits of the stepped channel values handed to [`GouraudColor::fill_span`] and
/// [`GouraudColor::from_stepped`]: channels have at most 8 integer bits, so a value fits a `u32`.
pub const STEP_BITS: u32 = 24;

const F: u32 = STEP_BITS;

/// Shift from [`AttributePlane::FRACTION_BITS`] to [`STEP_BITS`] fractional bits.
pub(crate) const PLANE_TO_STEP: u32 = STEP_BITS - AttributePlane::FRACTION_BITS;

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

    /// The colour of stepped channel values ([`STEP_BITS`] fractional bits, rounding offset
    /// included).
    #[inline(always)]
    fn from_stepped(v: [u32; 3]) -> Self {
        Self::from_channels([(v[0] >> F) as u8, (v[1] >> F) as u8, (v[2] >> F) as u8])
    }

    /// Fills `dst` with colours whose channels start at `start` and advance by `step` per pixel
    /// ([`STEP_BITS`] fractional bits, +½ rounding offset included, at most 2¹⁶ pixels). Formats
    /// may override it with a faster packed loop that keeps the same accuracy.
    #[inline]
    fn fill_span(dst: &mut [Self], start: [u32; 3], step: [u32; 3]) {
        let mut v = start;
        for px in dst {
            *px = Self::from_stepped(v);
            v[0] = v[0].wrapping_add(step[0]);
            if Self::CHANNELS > 1 {
                v[1] = v[1].wrapping_add(step[1]);
                v[2] = v[2].wrapping_add(step[2]);
            }
        }
    }
}

/// `GouraudColor` for RGB formats; `fill = |dst, start, step| …` overrides the span loop.
macro_rules! rgb_color {
    ($t:ty $(, fill = $fill:expr)?) => {
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
            $(
                #[inline]
                fn fill_span(dst: &mut [Self], start: [u32; 3], step: [u32; 3]) {
                    ($fill)(dst, start, step)
                }
            )?
        }
    };
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

rgb_color!(Rgb555);
rgb_color!(Bgr555);
rgb_color!(Rgb666);
rgb_color!(Bgr666);
rgb_color!(Rgb888);
rgb_color!(Bgr888);

/// Pixels stepped from one restart by the packed 5-6-5 loop. Its lanes carry 11 and 10 fractional
/// bits, so 128 steps add at most 2⁻⁴ LSB of error.
const PACKED_RUN: usize = 128;

/// `v >> k`, rounded to nearest, for a signed step.
#[inline(always)]
fn round_shift(v: u32, k: u32) -> u32 {
    ((v as i32).wrapping_add(1 << (k - 1)) >> k) as u32
}

/// Packed Gouraud loop for 5-6-5 layouts: channel `top` goes to raw bits 11..16, channel 1 to
/// bits 5..11, channel `bottom` to bits 0..5.
///
/// `top` (11 fractional bits) and the 6-bit channel (10 fractional bits) share one 32-bit word as
/// two 16-bit lanes; one addition steps both, because every lane value stays inside its lane at
/// covered pixels. `bottom` is stepped alone with 27 fractional bits. A pixel is then 2 additions
/// and 4 shift/mask/or operations.
#[inline(always)]
fn fill_565<C: From<RawU16>>(
    dst: &mut [C],
    start: [u32; 3],
    step: [u32; 3],
    top: usize,
    bottom: usize,
) {
    let (st, sg, sb) = (step[top], step[1], step[bottom]);
    let s1 = (round_shift(st, F - 11) << 16).wrapping_add(round_shift(sg, F - 10));
    let s2 = sb << (27 - F);
    let (mut vt, mut vg, mut vb) = (start[top], start[1], start[bottom]);
    for run in dst.chunks_mut(PACKED_RUN) {
        let w1 = ((vt >> (F - 11)) << 16) | (vg >> (F - 10));
        let w2 = vb << (27 - F);
        packed_run(run, w1, w2, s1, s2);
        let n = PACKED_RUN as u32;
        vt = vt.wrapping_add(st.wrapping_mul(n));
        vg = vg.wrapping_add(sg.wrapping_mul(n));
        vb = vb.wrapping_add(sb.wrapping_mul(n));
    }
}

/// One packed pixel from the two lane words of [`fill_565`].
#[inline(always)]
fn packed_pixel<C: From<RawU16>>(w1: u32, w2: u32) -> C {
    let raw = ((w1 >> 16) & 0xF800) | ((w1 >> 5) & 0x07E0) | (w2 >> 27);
    C::from(RawU16::new(raw as u16))
}

/// The packed loop of [`fill_565`] over one run (at most [`PACKED_RUN`] pixels), two pixels an
/// iteration; written with slice patterns so that it is neither vectorized nor unrolled further
/// (either costs more set-up per span than it saves on spans of a few dozen pixels).
#[inline(always)]
fn packed_run<C: From<RawU16>>(mut run: &mut [C], mut w1: u32, mut w2: u32, s1: u32, s2: u32) {
    while let [a, b, rest @ ..] = run {
        *a = packed_pixel(w1, w2);
        *b = packed_pixel(w1.wrapping_add(s1), w2.wrapping_add(s2));
        w1 = w1.wrapping_add(s1).wrapping_add(s1);
        w2 = w2.wrapping_add(s2).wrapping_add(s2);
        run = rest;
    }
    if let [a] = run {
        *a = packed_pixel(w1, w2);
    }
}

rgb_color!(
    Rgb565,
    fill = |d: &mut [Rgb565], s, t| fill_565(d, s, t, 0, 2)
);
rgb_color!(
    Bgr565,
    fill = |d: &mut [Bgr565], s, t| fill_565(d, s, t, 2, 0)
);
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

    /// The packed 5-6-5 loop stays within 2⁻⁴ LSB of plain [`STEP_BITS`]-fractional-bit stepping.
    #[test]
    fn packed_565_matches_plain_stepping() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut rnd = move |n: u64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed % n
        };
        let mut out = [Rgb565::BLACK; 700];
        let mut bgr = [Bgr565::BLACK; 700];
        for _ in 0..2000 {
            let n = 1 + rnd(700) as usize;
            let mut start = [0u32; 3];
            let mut step = [0u32; 3];
            for k in 0..3 {
                let max = f64::from(Rgb565::MAX[k]);
                let (c0, c1) = (
                    rnd(1 << 20) as f64 / f64::from(1 << 20) * max,
                    rnd(1 << 20) as f64 / f64::from(1 << 20) * max,
                );
                let s = if n > 1 {
                    (c1 - c0) / (n - 1) as f64
                } else {
                    0.0
                };
                let one = f64::from(1u32 << STEP_BITS);
                start[k] = ((c0 + 0.5) * one) as u32;
                step[k] = ((s * one).round() as i32) as u32;
            }
            Rgb565::fill_span(&mut out[..n], start, step);
            Bgr565::fill_span(&mut bgr[..n], start, step);
            for (i, (px, b)) in out[..n].iter().zip(&bgr[..n]).enumerate() {
                for (got, k) in [px.channels(), b.channels()]
                    .into_iter()
                    .flat_map(|c| (0..3).map(move |k| (c, k)))
                {
                    let plain = (f64::from(start[k]) + f64::from(step[k] as i32) * i as f64)
                        / f64::from(1u32 << STEP_BITS);
                    let lo = (plain - 1.0 / 16.0).floor().max(0.0);
                    let hi = (plain + 1.0 / 16.0).floor().min(f64::from(Rgb565::MAX[k]));
                    let g = f64::from(got[k]);
                    assert!(lo <= g && g <= hi, "pixel {i} channel {k}: {g} vs {plain}");
                }
            }
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
