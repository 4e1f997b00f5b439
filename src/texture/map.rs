//! [`Texture`]: texel storage with its size, wrap modes and filter, sampled at 16.16 fixed-point
//! texel coordinates.

use core::marker::PhantomData;

use super::address::{Axis, Wrap};
use super::source::TexelSource;
use crate::color::GouraudColor;
use crate::raster::arith::mul_u32_wide;

/// Largest width or height of a texture, in texels (2¹⁵: texel coordinates are 16.16 fixed
/// point, so a texture's coordinates span a few periods of it either way).
pub const MAX_SIZE: u32 = 1 << 15;

/// How a texture is read between texel centres.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Filter {
    /// The texel the sample point lies in.
    #[default]
    Nearest,
    /// The four texels around the sample point, weighted by its distance to their centres
    /// (weights of one bit more than the target's widest channel, channel by channel in its
    /// depth: within 1 LSB of the exact blend). Lit by one level (a 3D material's flat or
    /// Gouraud light), the blend is scaled by the level before its one rounding.
    Bilinear,
}

/// Why a texture could not be made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TextureError {
    /// Width or height 0 or over [`MAX_SIZE`].
    Size {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
    /// The storage holds fewer texels than `width × height`.
    TooFewTexels {
        /// Texels the size needs.
        needed: usize,
        /// Texels the storage holds.
        held: usize,
    },
}

impl core::fmt::Display for TextureError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            TextureError::Size { width, height } => write!(
                f,
                "a texture of {width} × {height} texels: each side must be 1 to {MAX_SIZE}"
            ),
            TextureError::TooFewTexels { needed, held } => write!(
                f,
                "the texture's size needs {needed} texels, the storage holds {held}"
            ),
        }
    }
}

impl core::error::Error for TextureError {}

/// A texture: borrowed texels ([`TexelSource`]: Rgb565, Rgb888, Gray8, 4- and 8-bit indexed,
/// any colour slice) with their size, a [`Wrap`] mode per axis and a [`Filter`].
///
/// Any size from 1 × 1 to [`MAX_SIZE`] on a side; power-of-two sizes take a mask where others
/// take a multiply or a remainder. Texel coordinates are in texels, `(0, 0)` the top-left
/// corner of texel `(0, 0)` and `(i + ½, j + ½)` the centre of texel `(i, j)`, as 16.16 fixed
/// point (`i32`, 65536 a texel) on the drawing paths.
///
/// # Examples
///
/// ```
/// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// use embedded_raster::texture::{Filter, Rgb565Texels, Texture, Wrap};
///
/// // A 2 × 2 checker: red, green / blue, white (raw 5-6-5 words, as a flash table holds them).
/// static CHECKER: [u16; 4] = [0xf800, 0x07e0, 0x001f, 0xffff];
/// let texture = Texture::new(Rgb565Texels(&CHECKER), 2, 2).unwrap();
/// let texel = |x: f32, y: f32| texture.nearest((x * 65536.0) as i32, (y * 65536.0) as i32);
/// assert_eq!(texel(1.5, 0.5), Rgb565::GREEN);
/// assert_eq!(texel(-0.5, 0.5), Rgb565::GREEN); // repeats
/// let clamped = texture.with_wrap(Wrap::Clamp, Wrap::Clamp);
/// assert_eq!(clamped.nearest(-65536, 3 << 16), Rgb565::BLUE);
/// // Halfway between the red and green centres: half of each, channel by channel.
/// let mixed: Rgb565 = texture.with_filter(Filter::Bilinear).bilinear(1 << 16, 1 << 15);
/// assert_eq!(mixed, Rgb565::new(16, 32, 0));
/// # assert!(Texture::new(Rgb565Texels(&CHECKER), 3, 2).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Texture<S> {
    source: S,
    x: Axis,
    y: Axis,
    filter: Filter,
}

impl<S: TexelSource> Texture<S> {
    /// A `width × height` texture of `source`'s first texels (row-major), repeating on both
    /// axes, nearest filtering. An error if a side is 0 or over [`MAX_SIZE`], or if the storage
    /// holds fewer than `width × height` texels.
    pub fn new(source: S, width: u32, height: u32) -> Result<Self, TextureError> {
        if !(1..=MAX_SIZE).contains(&width) || !(1..=MAX_SIZE).contains(&height) {
            return Err(TextureError::Size { width, height });
        }
        // Below 2³⁰: no overflow.
        let needed = (width * height) as usize;
        let held = source.texels();
        if held < needed {
            return Err(TextureError::TooFewTexels { needed, held });
        }
        Ok(Texture {
            source,
            x: Axis::new(width, Wrap::Repeat),
            y: Axis::new(height, Wrap::Repeat),
            filter: Filter::Nearest,
        })
    }

    /// The texture with wrap modes `x` (horizontal) and `y` (vertical).
    pub fn with_wrap(self, x: Wrap, y: Wrap) -> Self {
        Texture {
            x: self.x.with_wrap(x),
            y: self.y.with_wrap(y),
            ..self
        }
    }

    /// The texture with filter `filter`.
    pub fn with_filter(self, filter: Filter) -> Self {
        Texture { filter, ..self }
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.x.size()
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.y.size()
    }

    /// The wrap modes, horizontal and vertical.
    pub fn wrap(&self) -> (Wrap, Wrap) {
        (self.x.wrap(), self.y.wrap())
    }

    /// The filter.
    pub fn filter(&self) -> Filter {
        self.filter
    }

    /// The texel storage.
    pub fn source(&self) -> &S {
        &self.source
    }

    /// The axes (crate-internal: the span loops' addressing).
    #[inline(always)]
    pub(crate) fn axes(&self) -> (&Axis, &Axis) {
        (&self.x, &self.y)
    }

    /// Texel `(i, j)` after wrapping both indices (any `i32`s).
    #[inline(always)]
    pub fn texel(&self, i: i32, j: i32) -> S::Color {
        let (x, y) = (self.x.index(i), self.y.index(j));
        self.source.texel(self.linear(x, y))
    }

    /// The storage index of texel `(x, y)` (inside the texture).
    #[inline(always)]
    pub(crate) fn linear(&self, x: u32, y: u32) -> usize {
        match self.x.shift() {
            Some(s) => ((y << s) | x) as usize,
            // Below 2³⁰.
            None => (y * self.x.size() + x) as usize,
        }
    }

    /// The texel at the 16.16 texel coordinate `(x, y)` (nearest filtering): texel
    /// `(⌊x⌋, ⌊y⌋)`, wrapped.
    #[inline(always)]
    pub fn nearest(&self, x: i32, y: i32) -> S::Color {
        self.texel(x >> 16, y >> 16)
    }

    /// The bilinear blend at the 16.16 texel coordinate `(x, y)`, channel by channel in `C`'s
    /// depth: the four texels around `(x − ½, y − ½)` (each index wrapped on its own), weighted
    /// by their fractions rounded to one bit more than `C`'s widest channel, the blend rounded
    /// to nearest.
    #[inline(always)]
    pub fn bilinear<C>(&self, x: i32, y: i32) -> C
    where
        C: GouraudColor + From<S::Color>,
    {
        bilinear_by(x, y, |i, j| C::from(self.texel(i, j)))
    }

    /// [`bilinear`](Self::bilinear)'s blend before its rounding.
    #[inline(always)]
    pub(crate) fn bilinear_sums<C>(&self, x: i32, y: i32) -> Blend<C>
    where
        C: GouraudColor + From<S::Color>,
    {
        bilinear_sums_by(x, y, |i, j| C::from(self.texel(i, j)))
    }

    /// The texel at the 16.16 coordinate `(x, y)` by this texture's filter, as `C`.
    #[inline(always)]
    pub fn sample<C>(&self, x: i32, y: i32) -> C
    where
        C: GouraudColor + From<S::Color>,
    {
        match self.filter {
            Filter::Nearest => C::from(self.nearest(x, y)),
            Filter::Bilinear => self.bilinear(x, y),
        }
    }
}

/// The bilinear blend at the 16.16 texel coordinate `(x, y)` of the texels `fetch(i, j)` gives
/// (wrapped by the caller): [`Texture::bilinear`]'s arithmetic, for every addressing.
#[inline(always)]
pub(crate) fn bilinear_by<C: GouraudColor>(x: i32, y: i32, fetch: impl Fn(i32, i32) -> C) -> C {
    bilinear_sums_by(x, y, fetch).color()
}

/// [`bilinear_by`]'s blend before its rounding.
#[inline(always)]
pub(crate) fn bilinear_sums_by<C: GouraudColor>(
    x: i32,
    y: i32,
    fetch: impl Fn(i32, i32) -> C,
) -> Blend<C> {
    // The texels around (x − ½, y − ½): ⌊x − ½⌋ is ⌊x⌋ − 1 in a texel's left half (with no
    // overflow at the ends of i32, where x − ½ would wrap).
    let below = |x: i32| (x >> 16) - i32::from((x as u32 & 0xffff) < 1 << 15);
    let (i, j) = (below(x), below(y));
    // Weights of (x − ½, y − ½)'s fractions, rounded to `k` bits (`1 << k` is a whole texel).
    let k = weight_bits::<C>();
    let fraction =
        |x: i32| (((x as u32).wrapping_sub(1 << 15) & 0xffff) + (1 << (15 - k))) >> (16 - k);
    let (fx, fy) = (fraction(x), fraction(y));
    let (i1, j1) = (i.wrapping_add(1), j.wrapping_add(1));
    let c = |i, j| fetch(i, j).channels().map(u32::from);
    let (t00, t10, t01, t11) = (c(i, j), c(i1, j), c(i, j1), c(i1, j1));
    let blend = |n: usize| {
        // Each row's blend below 2¹⁷, the sum below 2²⁶ (channels of at most 8 bits, `k` at
        // most 9). One product a blend, `a·(2ᵏ − f) + b·f = a·2ᵏ + (b − a)·f`, modulo 2³² (the
        // same integer: the true value is below 2³²).
        let lerp =
            |a: u32, b: u32, f: u32| (a << k).wrapping_add(b.wrapping_sub(a).wrapping_mul(f));
        let top = lerp(t00[n], t10[n], fx);
        let bottom = lerp(t01[n], t11[n], fx);
        lerp(top, bottom, fy)
    };
    let sums = if C::CHANNELS == 1 {
        [blend(0), 0, 0]
    } else {
        [blend(0), blend(1), blend(2)]
    };
    Blend {
        sums,
        color: PhantomData,
    }
}

/// A bilinear blend before its rounding: each channel's four texels weighted by weights of
/// `2k` bits in all (`k` = [`weight_bits`]), the sum below `2^(8 + 2k)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Blend<C> {
    sums: [u32; 3],
    color: PhantomData<C>,
}

impl<C: GouraudColor> Blend<C> {
    /// The blend rounded to nearest: the bilinear texel.
    #[inline(always)]
    pub(crate) fn color(self) -> C {
        let k = weight_bits::<C>();
        let round = |s: u32| (s.wrapping_add(1 << (2 * k - 1)) >> (2 * k)) as u8;
        let [a, b, c] = self.sums;
        C::from_channels([round(a), round(b), round(c)])
    }

    /// The blend scaled by the light level `f` (18 fractional bits, below `2¹⁸·257/256`) and
    /// rounded once: `(s·f + 2^(2k + 17)) >> (2k + 18)` each channel (at most its maximum; for
    /// 5-6-5 colours `(s·f + 2³¹) >> 32`, one `smmulr` on ARMv7E-M). One rounding where the
    /// rounded blend scaled and rounded again would take two. (Out of line on ARMv6-M, where
    /// each loop that lights a blend would hold a copy.)
    #[cfg_attr(armv6m, inline(never))]
    #[cfg_attr(not(armv6m), inline(always))]
    pub(crate) fn lit(self, f: u32) -> C {
        let k = weight_bits::<C>();
        let shift = 2 * k + 18;
        let scaled = |s: u32| -> u32 {
            if k <= 7 {
                // Channels of at most 6 bits: `s < 2³ᵏ⁻¹`, and with `f = h·2¹⁰ + l` both
                // `s·l + 2^(shift − 1)` and `s·h` plus the first's top bits stay below 2³²:
                // the same integer in 32-bit products (no long multiply on Cortex-M0).
                let low = (s * (f & 1023) + (1 << (shift - 1))) >> 10;
                (s * (f >> 10) + low) >> (shift - 10)
            } else {
                ((mul_u32_wide(s, f) + (1 << (shift - 1))) >> shift) as u32
            }
        };
        let [a, b, c] = self.sums;
        let [ma, mb, mc] = C::MAX;
        let (ma, mb, mc) = (u32::from(ma), u32::from(mb), u32::from(mc));
        // 5-6-5 channels stay within theirs (`63·257/256 + ½ < 64`); a level above 1 takes a
        // channel of 128 or more past its maximum, so wider ones are clamped.
        let clamp = |v: u32, max: u32| if k > 7 { v.min(max) } else { v } as u8;
        C::from_channels([
            clamp(scaled(a), ma),
            clamp(scaled(b), mb),
            clamp(scaled(c), mc),
        ])
    }
}

/// The bits of the bilinear weights for `C`: one more than its widest channel's. A weight then
/// moves the sample point by at most 2⁻⁽ᵏ⁺¹⁾ texel an axis, which moves the blend by at most
/// `D·2⁻⁽ᵏ⁺¹⁾` for neighbours `D` apart: below half an LSB for both axes together, so the
/// rounded blend is within 1 LSB of the exact one. (7 bits for 5-6-5 colours: the four weights
/// `(2⁷ − fx)·(2⁷ − fy)` … fit signed 16-bit lanes, which the targets' dual products take.)
#[inline(always)]
pub(crate) const fn weight_bits<C: GouraudColor>() -> u32 {
    let [a, b, c] = C::MAX;
    let widest = if a > b { a } else { b };
    let widest = if widest > c { widest } else { c };
    // At least 1: a blend of 1-bit channels still needs its halves.
    let bits = 8 - widest.leading_zeros();
    if bits == 0 {
        1
    } else {
        bits + 1
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use std::string::ToString;

    use super::*;

    /// The blend is within 1 LSB of the exact bilinear value at the 16.16 coordinate (f64), for
    /// every channel depth, at the largest contrasts (neighbours 0 and the channel's maximum):
    /// the weights' bits (`weight_bits`) keep their rounding below half an LSB. Lit, within 1
    /// LSB of the exact value times the level, and the blend itself at a full level.
    #[test]
    fn bilinear_blends_are_within_an_lsb_of_the_exact_value() {
        use embedded_graphics::pixelcolor::{BinaryColor, Gray4, Gray8, Rgb555, Rgb565, Rgb888};

        fn check<C: GouraudColor>(seed: u32) -> f64 {
            let mut state = seed;
            let mut next = move || {
                state ^= state << 13;
                state ^= state >> 17;
                state ^= state << 5;
                state
            };
            let hash = |i: i32, j: i32| {
                let h = (i as u32).wrapping_mul(0x9e37_79b9) ^ (j as u32).wrapping_mul(0x85eb_ca6b);
                h ^ (h >> 15)
            };
            let mut worst = 0f64;
            for round in 0..20_000 {
                let salt = next();
                // Channels at the extremes (the largest neighbour differences) or anywhere.
                let texel = |i: i32, j: i32| {
                    let h = hash(i, j) ^ salt;
                    let channel = |k: usize| {
                        let max = u32::from(C::MAX[k]);
                        match (h >> (8 * k)) & 3 {
                            0 | 1 => ((h >> (8 * k + 2)) & 1) * max,
                            _ => (h >> (8 * k + 2)) % (max + 1),
                        }
                    };
                    [channel(0) as u8, channel(1) as u8, channel(2) as u8]
                };
                let (x, y) = if round % 4 == 0 {
                    // Fractions next to the weights' rounding edges.
                    let edge = |r: u32| {
                        let k = weight_bits::<C>();
                        let f = ((r % (1 << k)) << (16 - k)) + (1 << (15 - k));
                        ((r >> 8) as i32 & 0xff) << 16
                            | (f as i32 + (r >> 20) as i32 % 3 - 1 + 0x8000) & 0xffff
                    };
                    (edge(next()), edge(next()))
                } else {
                    (next() as i32, next() as i32)
                };
                let blend = bilinear_sums_by(x, y, |i, j| C::from_channels(texel(i, j)));
                let got = blend.color().channels();
                // Lit: at a level of 18 bits up to a little above 1 (the planes' most), the
                // blend scaled before its one rounding; at exactly 1, the blend itself.
                let f = match round % 8 {
                    0 => 1 << 18,
                    1 => (((1 << 20) - 1) * 257) >> 10,
                    _ => next() % (1 << 18),
                };
                let lit = blend.lit(f).channels();
                if f == 1 << 18 {
                    assert_eq!(lit, got);
                }
                // The exact blend at (x − ½, y − ½).
                let (fx, fy) = (f64::from(x) / 65536.0 - 0.5, f64::from(y) / 65536.0 - 0.5);
                let (i, j) = (fx.floor(), fy.floor());
                let (ax, ay) = (fx - i, fy - j);
                let (i, j) = (i as i32, j as i32);
                for (k, &got) in got.iter().enumerate().take(C::CHANNELS) {
                    let t = |i: i32, j: i32| f64::from(texel(i, j)[k]);
                    let top = t(i, j) * (1.0 - ax) + t(i + 1, j) * ax;
                    let bottom = t(i, j + 1) * (1.0 - ax) + t(i + 1, j + 1) * ax;
                    let exact = top * (1.0 - ay) + bottom * ay;
                    worst = worst.max((f64::from(got) - exact).abs());
                    let exact_lit =
                        (exact * f64::from(f) / f64::from(1 << 18)).min(f64::from(C::MAX[k]));
                    worst = worst.max((f64::from(lit[k]) - exact_lit).abs());
                }
            }
            worst
        }
        for (name, worst) in [
            ("BinaryColor", check::<BinaryColor>(1)),
            ("Gray4", check::<Gray4>(2)),
            ("Gray8", check::<Gray8>(3)),
            ("Rgb555", check::<Rgb555>(4)),
            ("Rgb565", check::<Rgb565>(5)),
            ("Rgb888", check::<Rgb888>(6)),
        ] {
            assert!(worst < 1.0, "{name}: {worst}");
        }
    }

    /// [`Blend::lit`]'s 32-bit products are the exact `(s·f + 2^(2k + 17)) >> (2k + 18)` for
    /// channels of up to 6 bits, at the ends of its ranges (`s` up to the channel's maximum
    /// times 2²ᵏ, `f` up to the planes' largest) and between.
    #[test]
    fn lit_blends_round_the_exact_product() {
        use embedded_graphics::pixelcolor::{Gray4, Rgb555, Rgb565};

        fn check<C: GouraudColor>() {
            let k = weight_bits::<C>();
            let max = C::MAX;
            let f_max = (((1u32 << 20) - 1) * 257) >> 10;
            let mut state = 0x1234_5678u32;
            for round in 0..200_000u32 {
                state ^= state << 13;
                state ^= state >> 17;
                state ^= state << 5;
                let f = match round % 4 {
                    0 => f_max - round % 7,
                    1 => 1 << 18,
                    _ => state % (f_max + 1),
                };
                let sums = [0, 1, 2].map(|n| {
                    let top = u32::from(max[n]) << (2 * k);
                    match (round / 4 + n as u32) % 3 {
                        0 => top.saturating_sub((state >> 8) % 3),
                        _ => (state >> (n * 5)) % (top + 1),
                    }
                });
                let got = Blend::<C> {
                    sums,
                    color: PhantomData,
                }
                .lit(f)
                .channels();
                for n in 0..C::CHANNELS {
                    let shift = 2 * k + 18;
                    let exact = (u64::from(sums[n]) * u64::from(f) + (1 << (shift - 1))) >> shift;
                    assert_eq!(u64::from(got[n]), exact, "{sums:?} {f}");
                }
            }
        }
        check::<Rgb565>();
        check::<Rgb555>();
        check::<Gray4>();
    }

    /// The errors' messages: what was needed and what was given (issue #32, item 2).
    #[test]
    fn texture_error_messages() {
        let size = TextureError::Size {
            width: 0,
            height: 40_000,
        };
        assert_eq!(
            size.to_string(),
            "a texture of 0 × 40000 texels: each side must be 1 to 32768"
        );
        let few = TextureError::TooFewTexels {
            needed: 64,
            held: 63,
        };
        assert_eq!(
            few.to_string(),
            "the texture's size needs 64 texels, the storage holds 63"
        );
    }
}
