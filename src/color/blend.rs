//! Source-over blending in a colour format's own channel depth.
//!
//! An opacity is an 8-bit alpha `a` (0 transparent, 255 opaque), used as the weight
//! `w = a + (a >> 7)` of 256ths ([`weight`]); a channel `s` over a channel `d` is
//!
//! ```text
//! ⌊(s·w + d·(256 − w) + 128) / 256⌋
//! ```
//!
//! in the channel's own depth (5 and 6 bits for Rgb565, 8 for Rgb888 and Gray8, …). The weight
//! is within 127/65280 < 1/514 of `a/255`, so a blended channel is within ½ + MAX/514 < 1 LSB of
//! the exact `s·a/255 + d·(1 − a/255)` for channels of up to 8 bits (`MAX ≤ 255`): opacity 255
//! leaves the source, 0 the destination.
//!
//! One channel is one multiply: with `s` and `d` in the high and low halves of a word and
//! `256 − w` and `w` in those of another, the middle 16 bits of their 32-bit product are
//! `s·w + d·(256 − w)` (`d·w < 2¹⁶` never carries into them; `s·(256 − w)` falls beyond bit 31).
//! A constant colour at a constant opacity ([`BlendSource`]) needs one multiply a channel of the
//! destination only; the 5-6-5 formats blend two pixels' channels in one word.

use embedded_graphics::pixelcolor::raw::{RawData, RawU16};

use super::GouraudColor;

/// The weight of an 8-bit alpha in 256ths: `a + (a >> 7)`, 0 for 0 and 256 for 255.
#[inline(always)]
pub(crate) const fn weight(alpha: u8) -> u32 {
    let a = alpha as u32;
    a + (a >> 7)
}

/// The weights `256 − w` (high half) and `w` (low half) of one blend, for [`blend_channel`].
#[inline(always)]
pub(crate) const fn weights(w: u32) -> u32 {
    ((256 - w) << 16) | w
}

/// Channel `s` over channel `d` (each below 256) with [`weights`] `ww`:
/// `⌊(s·w + d·(256 − w) + 128) / 256⌋` in one multiply.
#[inline(always)]
pub(crate) const fn blend_channel(s: u32, d: u32, ww: u32) -> u32 {
    (((s << 16) | d).wrapping_mul(ww).wrapping_add(128 << 16) >> 24) & 0xFF
}

/// The channels of `src` over those of `dst` at weight `w` ([`weight`]), the definition every
/// blend of a format gives ([`GouraudColor::blend`]).
#[inline(always)]
pub(crate) fn blend_channels(src: [u8; 3], dst: [u8; 3], w: u32) -> [u8; 3] {
    let ww = weights(w);
    core::array::from_fn(|k| blend_channel(u32::from(src[k]), u32::from(dst[k]), ww) as u8)
}

/// A colour at an opacity, prepared once for blending over many pixels
/// ([`GouraudColor::blend_solid`]): `s·w + 128` of each channel and the destination's weight
/// `256 − w`.
///
/// ```
/// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// use embedded_raster::color::BlendSource;
/// use embedded_raster::GouraudColor;
///
/// let mut row = [Rgb565::BLUE; 4];
/// Rgb565::blend_solid(&mut row, &BlendSource::new(Rgb565::RED, 128));
/// assert_eq!(row[0], Rgb565::new(16, 0, 15)); // half red over blue, per channel
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BlendSource {
    /// `s·w + 128` of each channel, in channel order.
    pre: [u32; 3],
    /// `256 − w`.
    keep: u32,
    /// `keep`, then each channel's `pre` in both halves of a word (channel order): the 5-6-5
    /// formats' two-pixel lanes ([`blend_solid_565`]), formed once for all of a triangle's spans.
    lanes: [u32; 4],
}

impl BlendSource {
    /// `color` at opacity `alpha` (0 transparent, 255 opaque).
    #[inline]
    pub fn new<C: GouraudColor>(color: C, alpha: u8) -> Self {
        let w = weight(alpha);
        let pre = color.channels().map(|s| u32::from(s) * w + 128);
        let keep = 256 - w;
        // Each `pre` is at most 255·256 + 128 < 2¹⁶: the halves do not overlap.
        let both = |v: u32| v | (v << 16);
        BlendSource {
            pre,
            keep,
            lanes: [keep, both(pre[0]), both(pre[1]), both(pre[2])],
        }
    }

    /// The blended channels over the destination channels `d`.
    #[inline(always)]
    fn over(&self, d: [u8; 3]) -> [u8; 3] {
        core::array::from_fn(|k| ((self.pre[k] + u32::from(d[k]) * self.keep) >> 8) as u8)
    }

    /// Whether the source leaves every pixel as it is (opacity 0).
    #[inline(always)]
    pub fn is_transparent(&self) -> bool {
        self.keep == 256
    }
}

/// Rounding offset of the transparency plane of per-vertex alpha ([`premultiplied_attributes`]):
/// 2⁻⁸ of a unit keeps its stepped value above zero (its error is below 2⁻⁹) without carrying.
pub(crate) const TRANSPARENCY_HALF: u32 = 1 << 16;

/// Planes of a triangle with an alpha per vertex: each colour channel premultiplied by its
/// vertex's alpha (`s·a/255`, 8.8 fixed point rounded) and the transparency `255 − a`, which
/// [`blend_premultiplied`] blends with.
#[inline(always)]
pub(crate) fn premultiplied_values(channels: [u8; 3], alpha: u8) -> [u16; 4] {
    let a = u32::from(alpha);
    let p = channels.map(|s| ((u32::from(s) * a * 256 + 127) / 255) as u16);
    [p[0], p[1], p[2], ((255 - a) << 8) as u16]
}

/// A pixel of per-vertex alpha over `d`: `p` the premultiplied channel planes' values there
/// ([`STEP_BITS`] fractional bits, +½ included), `t` the transparency plane's
/// ([`TRANSPARENCY_HALF`] included). Each channel is `⌊p + d·t/255⌋` (the +½ in `p` rounds),
/// `t/255` to 16 fractional bits: within ½ LSB + 2⁻⁷ of the exact blend of the interpolated
/// premultiplied colour.
///
/// [`STEP_BITS`]: super::STEP_BITS
#[inline(always)]
pub(crate) fn blend_premultiplied<C: GouraudColor>(p: [u32; 3], t: u32, d: C) -> C {
    // t < 255·2²⁴ + 2¹⁷: (t >> 9)·257 < 2³¹; the factor is t/255 in 0.16, at most 2¹⁶ + 1.
    let factor = transparency_factor(t);
    let d = d.channels();
    // The sum is the blended channel (at most 255.5) in 8.24; its terms wrap back into it.
    C::from_channels(core::array::from_fn(|k| {
        (p[k].wrapping_add((u32::from(d[k]) * factor) << 8) >> 24) as u8
    }))
}

/// The factor `t/255` (0.16 fixed point, at most 2¹⁶ + 2⁸) of the transparency plane's value `t`
/// that [`blend_premultiplied`] multiplies the destination's channels by.
#[inline(always)]
fn transparency_factor(t: u32) -> u32 {
    // t >> 9 < 2²³: the product is below 2³².
    ((t >> 9) * 257) >> 15
}

/// [`GouraudColor::blend_premultiplied_span`] pixel by pixel: [`blend_premultiplied`] of each
/// pixel of `dst`, the planes (`r`, `g`, `b`, `t`) from `start` stepped by `step`, wrapping. The
/// definition, for every format.
#[inline(always)]
pub(crate) fn blend_premultiplied_by_pixels<C: GouraudColor>(
    dst: &mut [C],
    start: [u32; 4],
    step: [u32; 4],
) {
    let mut value = start;
    let planes = (0..dst.len()).map(move |_| {
        let here = value;
        for (v, s) in value.iter_mut().zip(step) {
            *v = v.wrapping_add(s);
        }
        here
    });
    for (px, [r, g, b, t]) in dst.iter_mut().zip(planes) {
        *px = blend_premultiplied([r, g, b], t, *px);
    }
}

/// One 5-6-5 pixel `d` (its raw value in the low half) under [`blend_premultiplied`] with the
/// factor `f` ([`transparency_factor`]) and the colour planes `p` in raw order (top, middle,
/// bottom field), the top one scaled by 8: the blended pixel in the **high** half, the low half
/// unspecified.
///
/// A channel is bits 24 and up of `p + d·f·2⁸` (modulo 2³²), masked to its field: it depends
/// only on the sum's low 29 bits (30 for the middle field), so the top channel can be computed
/// eight times larger (its plane and step scaled by 8, wrapping), which puts it at bits 27–31,
/// where the high half's top field is, and `d`'s field in place (`d & 0xF800` is `d_top·2¹¹`)
/// is the multiplicand. The other two fields are inserted below it.
// Not used on Cortex-M, whose loops are in assembly.
#[cfg_attr(any(armv6m, armv7m), allow(dead_code))]
#[inline(always)]
fn premultiplied_pixel_565(d: u32, f: u32, p: [u32; 3]) -> u32 {
    let f8 = f << 8;
    let top = (d & 0xF800).wrapping_mul(f).wrapping_add(p[0]);
    let middle = ((d >> 5) & 0x3F).wrapping_mul(f8).wrapping_add(p[1]) >> 24;
    let bottom = (d & 0x1F).wrapping_mul(f8).wrapping_add(p[2]) >> 24;
    (top & 0xF800_FFFF) | ((middle & 0x3F) << 21) | ((bottom & 0x1F) << 16)
}

/// The arithmetic of ARMv6-M's Thumb-1 loop (`arch::thumbv6m::premultiplied_565`) for one
/// 5-6-5 pixel `d` under the transparency plane's value `t` and the colour planes `p` (raw
/// order, unscaled): the raw blended pixel in the low half (bits above: anything). The factor is
/// taken times 2¹⁰ and the planes scaled by 4, 4 and 8 (the bottom field doubled), which puts
/// the top channel at bits 26-30, the middle at 26-31 and the bottom at 27-31 of their sums, as
/// [`premultiplied_pixel_565`] scales its top one.
#[cfg(test)]
fn premultiplied_pixel_v6m(d: u32, t: u32, p: [u32; 3]) -> u32 {
    let f = transparency_factor(t) << 10;
    let top = (d >> 11).wrapping_mul(f).wrapping_add(p[0] << 2);
    let middle = ((d << 21) >> 26).wrapping_mul(f).wrapping_add(p[1] << 2);
    let bottom = ((d << 27) >> 26).wrapping_mul(f).wrapping_add(p[2] << 3);
    // Bit 31 of `top` (not the channel's) lands at bit 16, beyond the pixel.
    ((((top >> 26) << 6) | (middle >> 26)) << 5) | (bottom >> 27)
}

/// [`GouraudColor::blend_premultiplied_span`] for the 5-6-5 formats whose raw value holds
/// channels `order` (top, middle, bottom field): on raw values, two pixels a word
/// ([`premultiplied_pixel_565`]), the pixels of [`blend_premultiplied_by_pixels`].
#[inline(always)]
pub(crate) fn blend_premultiplied_565<C: Copy + From<RawU16> + Into<RawU16>>(
    dst: &mut [C],
    start: [u32; 4],
    step: [u32; 4],
    order: [usize; 3],
) {
    // Raw order (top, middle, bottom field, transparency).
    let raw = |v: [u32; 4]| {
        let [top, middle, bottom] = order.map(|k| v.get(k).copied().unwrap_or(0));
        [top, middle, bottom, v[3]]
    };
    // Cortex-M: in assembly (ARMv7-M: `premultiplied_pixel_565`'s arithmetic, two pixels a
    // word; ARMv6-M: `premultiplied_pixel_v6m`'s, one pixel at a time).
    #[cfg(any(armv6m, armv7m))]
    {
        crate::arch::premultiplied_565(dst, raw(start), raw(step));
        return;
    }
    // The top field's plane scaled by 8 (see `premultiplied_pixel_565`).
    #[allow(unreachable_code)]
    let planes = |v: [u32; 4]| {
        let [top, middle, bottom, t] = raw(v);
        [top << 3, middle, bottom, t]
    };
    let (mut value, step) = (planes(start), planes(step));
    let advance =
        |v: [u32; 4]| -> [u32; 4] { core::array::from_fn(|k| v[k].wrapping_add(step[k])) };
    let pixel = |d: C, v: [u32; 4]| {
        let d = u32::from(d.into().into_inner());
        premultiplied_pixel_565(d, transparency_factor(v[3]), [v[0], v[1], v[2]])
    };
    let mut rest = dst;
    while let [a, b, tail @ ..] = rest {
        let next = advance(value);
        let (left, right) = (pixel(*a, value), pixel(*b, next));
        let both = (right & 0xFFFF_0000) | (left >> 16);
        *a = C::from(RawU16::new(both as u16));
        *b = C::from(RawU16::new((both >> 16) as u16));
        value = advance(next);
        rest = tail;
    }
    if let [last] = rest {
        *last = C::from(RawU16::new((pixel(*last, value) >> 16) as u16));
    }
}

/// [`GouraudColor::blend_solid`] by channels: the definition, for every format.
#[inline(always)]
pub(crate) fn blend_solid_by_channels<C: GouraudColor>(dst: &mut [C], source: &BlendSource) {
    for px in dst {
        *px = C::from_channels(source.over(px.channels()));
    }
}

/// Two 5-6-5 pixels (the right one in the high half of `d`) under the channels' `pre` values of
/// [`BlendSource`] in raw order (top, middle, bottom field), each in both halves of its word.
/// Every lane of a product stays below 2¹⁶ (`63·256 + 128`), so the halves never carry into
/// each other and each is [`BlendSource::over`]'s integer.
#[inline(always)]
fn blend_pair_565(d: u32, pre: [u32; 3], keep: u32) -> u32 {
    let top = ((d >> 11) & 0x001F_001F) * keep + pre[0];
    let middle = ((d >> 5) & 0x003F_003F) * keep + pre[1];
    let bottom = (d & 0x001F_001F) * keep + pre[2];
    (((top >> 8) & 0x001F_001F) << 11)
        | (((middle >> 8) & 0x003F_003F) << 5)
        | ((bottom >> 8) & 0x001F_001F)
}

/// [`GouraudColor::blend_solid`] for the 5-6-5 formats whose raw value holds channels `order`
/// (top, middle, bottom field): two pixels a word ([`blend_pair_565`]), the same integers as
/// [`blend_solid_by_channels`].
#[inline(always)]
pub(crate) fn blend_solid_565<C: Copy + From<RawU16> + Into<RawU16>>(
    dst: &mut [C],
    source: &BlendSource,
    order: [usize; 3],
) {
    let permuted;
    let lanes = if matches!(order, [0, 1, 2]) {
        &source.lanes
    } else {
        let lane = |k: usize| source.lanes.get(k + 1).copied().unwrap_or(0);
        permuted = [source.keep, lane(order[0]), lane(order[1]), lane(order[2])];
        &permuted
    };
    if crate::arch::blend_solid_565(dst, lanes) {
        return;
    }
    let [keep, pre @ ..] = *lanes;
    let raw_of = |c: C| u32::from(c.into().into_inner());
    let mut rest = dst;
    while let [a, b, tail @ ..] = rest {
        let blended = blend_pair_565(raw_of(*a) | (raw_of(*b) << 16), pre, keep);
        *a = C::from(RawU16::new(blended as u16));
        *b = C::from(RawU16::new((blended >> 16) as u16));
        rest = tail;
    }
    if let [last] = rest {
        *last = C::from(RawU16::new(blend_pair_565(raw_of(*last), pre, keep) as u16));
    }
}

#[cfg(test)]
mod tests {
    use embedded_graphics::pixelcolor::{Bgr565, Gray8, Rgb565, Rgb888};

    use super::*;

    /// Every channel value, destination and alpha against the exact blend, and the one-multiply
    /// form against the plain one.
    #[test]
    fn channel_blend_is_within_one_lsb_of_the_exact_blend() {
        for max in [1u32, 3, 15, 31, 63, 255] {
            let mut worst = 0.0f64;
            for a in 0..=255u8 {
                let (w, alpha) = (weight(a), f64::from(a) / 255.0);
                for s in 0..=max {
                    for d in 0..=max {
                        let got = blend_channel(s, d, weights(w));
                        assert_eq!(got, (s * w + d * (256 - w) + 128) >> 8);
                        let exact = f64::from(s) * alpha + f64::from(d) * (1.0 - alpha);
                        worst = worst.max((f64::from(got) - exact).abs());
                    }
                }
                assert_eq!(blend_channel(max, 0, weights(weight(255))), max);
                assert_eq!(blend_channel(max, 0, weights(weight(0))), 0);
            }
            assert!(worst < 1.0, "{max}: {worst}");
        }
    }

    #[test]
    fn source_over_is_the_channel_blend() {
        for a in [0u8, 1, 77, 127, 128, 200, 254, 255] {
            for (s, d) in [(0u8, 255u8), (255, 0), (17, 240), (128, 128)] {
                let source = BlendSource::new(Rgb888::new(s, d, s / 2), a);
                let mut px = [Rgb888::new(d, s, d / 3)];
                blend_solid_by_channels(&mut px, &source);
                let want = blend_channels([s, d, s / 2], [d, s, d / 3], weight(a));
                assert_eq!(px[0].channels(), want);
            }
            let mut gray = [Gray8::new(10)];
            blend_solid_by_channels(&mut gray, &BlendSource::new(Gray8::new(250), a));
            assert_eq!(
                gray[0].channels(),
                blend_channels([250, 0, 0], [10, 0, 0], weight(a))
            );
        }
    }

    /// The packed loop against the per-channel definition for every alpha, many colours and
    /// every destination pair position (odd and even lengths).
    #[test]
    fn packed_565_blend_is_the_channel_blend() {
        fn check<C: GouraudColor + Copy + From<RawU16> + Into<RawU16> + core::fmt::Debug>(
            order: [usize; 3],
        ) {
            let mut seed = 0x1234_5678u32;
            let mut next = || {
                seed ^= seed << 13;
                seed ^= seed >> 17;
                seed ^= seed << 5;
                seed
            };
            for a in 0..=255u8 {
                let color = C::from(RawU16::new(next() as u16));
                let mut packed: [C; 7] =
                    core::array::from_fn(|_| C::from(RawU16::new(next() as u16)));
                let mut plain = packed;
                let source = BlendSource::new(color, a);
                blend_solid_565(&mut packed, &source, order);
                blend_solid_by_channels(&mut plain, &source);
                assert_eq!(packed, plain, "alpha {a}");
                let mut odd = [plain[0]; 1];
                blend_solid_565(&mut odd, &source, order);
                assert_eq!(
                    odd[0],
                    C::from_channels(blend_channels(
                        color.channels(),
                        plain[0].channels(),
                        weight(a)
                    ))
                );
            }
        }
        check::<Rgb565>([0, 1, 2]);
        check::<Bgr565>([2, 1, 0]);
    }

    /// The raw 5-6-5 loop of per-vertex alpha against the per-pixel definition: random pixels,
    /// planes and steps (in range and anywhere in `u32`, wrapping), every length up to 9 and
    /// both pair positions.
    #[test]
    fn premultiplied_565_span_is_the_pixel_blend() {
        fn check<C: GouraudColor + Copy + From<RawU16> + Into<RawU16> + core::fmt::Debug>(
            order: [usize; 3],
        ) {
            let mut seed = 0x9E37_79B9u32;
            let mut next = || {
                seed ^= seed << 13;
                seed ^= seed >> 17;
                seed ^= seed << 5;
                seed
            };
            for round in 0..20_000 {
                let (start, step) = if round % 2 == 0 {
                    // Anywhere: huge and wrapping values.
                    ([(); 4].map(|_| next()), [(); 4].map(|_| next()))
                } else {
                    // In range: premultiplied channels with their +½, transparency up to 255.
                    let mut v = [(); 4].map(|_| next());
                    v[3] = next() % (255 << 24) + TRANSPARENCY_HALF;
                    let s = [(); 4].map(|_| (next() as i32 >> (6 + next() % 20)) as u32);
                    (v, s)
                };
                let len = (round / 2) % 10;
                let mut fast: [C; 9] =
                    core::array::from_fn(|_| C::from(RawU16::new(next() as u16)));
                let (mut plain, under) = (fast, fast);
                let fast = &mut fast[..len];
                let plain = &mut plain[..len];
                blend_premultiplied_565(fast, start, step, order);
                blend_premultiplied_by_pixels(plain, start, step);
                assert_eq!(fast, plain, "{start:x?} {step:x?} {len}");
                // The Thumb-1 loop's arithmetic, pixel by pixel from the same planes.
                let mut value = start;
                for (&d, &want) in under.iter().zip(plain.iter()) {
                    let d = u32::from(d.into().into_inner());
                    let got = premultiplied_pixel_v6m(d, value[3], order.map(|k| value[k]));
                    assert_eq!(C::from(RawU16::new(got as u16)), want, "{value:x?}");
                    value = core::array::from_fn(|k| value[k].wrapping_add(step[k]));
                }
            }
            // Every factor's extremes: opaque, transparent and the largest plane values.
            for t in [
                0,
                TRANSPARENCY_HALF,
                255 << 24,
                u32::MAX,
                (255 << 24) + TRANSPARENCY_HALF,
            ] {
                for p in [0, u32::MAX, 1 << 31, 0x00FF_FFFF] {
                    let mut fast = [C::from(RawU16::new(0xFFFF)), C::from(RawU16::new(0x1234))];
                    let mut plain = fast;
                    blend_premultiplied_565(&mut fast, [p, p, p, t], [0; 4], order);
                    blend_premultiplied_by_pixels(&mut plain, [p, p, p, t], [0; 4]);
                    assert_eq!(fast, plain, "{p:x} {t:x}");
                }
            }
        }
        check::<Rgb565>([0, 1, 2]);
        check::<Bgr565>([2, 1, 0]);
    }
}
