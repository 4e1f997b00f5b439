//! Textured spans: texel coordinates stepped across a span and the texture sampled at each
//! pixel, by one loop per addressing kind (power-of-two repeat with nearest filtering, the
//! common flash texture, takes masks and shifts alone; every other mode the texture's own
//! [`sample`](Texture::sample)) — the same colours either way.
//!
//! Coordinates come from the raster core's attribute planes ([`PlaneMap`]: a texel coordinate
//! offset and scaled into a plane's 16-bit vertex values) and are stepped in 16.16 texels,
//! restarted from the plane's exact value every [`RUN`] pixels so that stepping adds at most
//! `RUN / 2` units of 2⁻¹⁶ texel.

use super::address::Wrap;
use super::map::{bilinear_sums_by, Blend, Filter, Texture};
use super::source::TexelSource;
use crate::arch::{self, MaskedSpan565};
use crate::color::{scale_channels, GouraudColor};
use crate::raster::arith::leading_zeros_32;

/// Longest run of pixels whose texel coordinates are stepped from one start.
pub(crate) const RUN: u32 = 1024;

/// The largest spread of a triangle's vertex values in a [`PlaneMap`]: 16 bits less the margins.
const SPREAD: u64 = (1 << 16) - 256;

/// A texel coordinate (16.16 texels) as one of the raster core's attributes: vertex values
/// `128 + round((c − origin) / 2^shift)`, read back as `origin + (value − 128·2¹⁶)·2^(shift −
/// 16)` from the planes' 8.24 values (`value = attribute · 2¹⁶`).
///
/// The values span at most [`SPREAD`] units, with 128 units of margin each way, so that the
/// planes' rounding error never wraps them below zero. Across a run of three or more covered
/// pixels the per-pixel change is then under half the range, below 2³¹, so a plane's step read
/// as an `i32` is the true one ([`step`](Self::step)); a shader takes a two-pixel run's second
/// coordinate from its own plane value instead.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct PlaneMap {
    /// The 16.16 coordinate of plane value 0.
    base: i32,
    /// A plane value is shifted right by `down`, then left by `up`, to 16.16 texels: `16 −
    /// shift` and 0 for the vertex values' scale `2^shift` (`shift` 0 to 16), 0 and
    /// `shift − 16` beyond.
    down: u32,
    up: u32,
}

impl PlaneMap {
    /// The map for vertex coordinates `c` (16.16 texels) and their plane values.
    #[inline]
    pub(crate) fn new(c: [i32; 3]) -> (Self, [u16; 3]) {
        let lo = c[0].min(c[1]).min(c[2]);
        let hi = c[0].max(c[1]).max(c[2]);
        // Below 2³² (in 32 bits: the difference modulo 2³² is the true one). The least shift
        // whose rounded spread fits SPREAD steps of 2^shift: from the spread's bit length, one
        // more where rounding needs it; at most 17.
        let spread = hi.wrapping_sub(lo) as u32;
        let mut shift = (32 - leading_zeros_32(spread)).saturating_sub(16);
        // Below 2¹⁶ after the first shift, below 2¹⁵ (within SPREAD) after one more.
        if u64::from(round_shift(spread, shift)) > SPREAD {
            shift += 1;
        }
        // Each value rounded to the nearest step.
        let value = |c: i32| (128 + round_shift(c.wrapping_sub(lo) as u32, shift)) as u16;
        let values = c.map(value);
        let base = (lo as u32).wrapping_sub(128 << shift) as i32;
        let (down, up) = if shift <= 16 {
            (16 - shift, 0)
        } else {
            (0, shift - 16)
        };
        (PlaneMap { base, down, up }, values)
    }

    /// The 16.16 coordinate of plane value `value` (8.24 of the 8.8 attribute), truncated.
    #[inline(always)]
    pub(crate) fn at(&self, value: u32) -> i32 {
        // Modulo 2³², as the coordinates themselves (a spread of 2¹⁷ scale steps reaches past
        // 32 bits only where the coordinates do).
        self.base
            .wrapping_add(((value >> self.down) << self.up) as i32)
    }

    /// The coordinate at the first pixel of a run of `len` pixels whose plane values start at
    /// `value` and step by `step` a pixel, and its per-pixel step (`texel_step`, the
    /// [`step`](Self::step) of `step`): a two-pixel run takes its second pixel's own
    /// coordinate, as a step read as an `i32` is the true one only across three or more.
    #[inline(always)]
    pub(crate) fn run(&self, value: u32, step: u32, texel_step: i32, len: u32) -> (i32, i32) {
        let at = self.at(value);
        if len != 2 {
            return (at, texel_step);
        }
        (at, self.at(value.wrapping_add(step)).wrapping_sub(at))
    }

    /// The per-pixel step in 16.16 texels of a plane step (rounded to nearest, halves up;
    /// modulo 2³² where a scale of 2¹⁷ takes it past 32 bits): `step · 2^(up − down)`.
    #[inline(always)]
    pub(crate) fn step(&self, step: u32) -> i32 {
        let step = step as i32;
        match self.down {
            0 => step.wrapping_shl(self.up),
            down => (step >> down) + ((step >> (down - 1)) & 1),
        }
    }
}

/// `⌊v / 2^shift + ½⌋` without leaving 32 bits: the bit below the shift rounds.
#[inline(always)]
fn round_shift(v: u32, shift: u32) -> u32 {
    match shift {
        0 => v,
        _ => (v >> shift) + ((v >> (shift - 1)) & 1),
    }
}

/// What a sampling function gives at a point: the texel (nearest filtering), or a blend not yet
/// rounded (bilinear), so that a light scales the blend before its one rounding.
pub(crate) trait Sampled<C>: Copy {
    /// The texture's colour.
    fn color(self) -> C;
    /// The colour lit at a level given as a fraction of 16 bits (`f16`, below 2¹⁷) and of 18
    /// (`f18`, below `2¹⁸·257/256`): a texel's channels `(c·f16 + 2¹⁵) >> 16`, a blend's
    /// [`Blend::lit`] by `f18`.
    fn lit(self, f16: u32, f18: u32) -> C;
}

impl<C: GouraudColor> Sampled<C> for C {
    #[inline(always)]
    fn color(self) -> C {
        self
    }

    #[inline(always)]
    fn lit(self, f16: u32, _: u32) -> C {
        scale_channels(self.channels(), f16)
    }
}

impl<C: GouraudColor> Sampled<C> for Blend<C> {
    #[inline(always)]
    fn color(self) -> C {
        Blend::color(self)
    }

    #[inline(always)]
    fn lit(self, _: u32, f18: u32) -> C {
        Blend::lit(self, f18)
    }
}

/// A loop over pixels that samples a texture: [`Sampler::run`] hands it the sampling function
/// of the texture's filter and addressing, so that each kind gets a loop of its own.
pub(crate) trait SampledLoop<C> {
    /// What the loop returns.
    type Output;

    /// Runs the loop with `sample`, the texture's colour (or blend) at a 16.16 texel coordinate
    /// `(x, y)` given as `(x, y << y_shift)` (wrapping: the loop steps the shifted `y` by the
    /// shifted step).
    fn run<T: Sampled<C>>(self, sample: impl Fn(i32, i32) -> T, y_shift: u32) -> Self::Output;

    /// Runs the loop with bilinear texels of raw Rgb565 `words` addressed by `masks` by the
    /// target's own loop, if it has one for this loop (ARMv7E-M's dual products), or gives the
    /// loop back (the default), nothing drawn.
    #[inline(always)]
    fn run_bilinear_565(self, masks: PowerOfTwoRepeat, words: &[u16]) -> Result<Self::Output, Self>
    where
        Self: Sized,
    {
        let _ = (masks, words);
        Err(self)
    }
}

/// How a texture is sampled, decided once per triangle: by masks alone into storage cut to the
/// texture's size (power-of-two sides repeating on both axes), or through the texture's
/// wrapping; by its filter.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Sampler<'t, S> {
    /// Nearest, masked.
    MaskedNearest(PowerOfTwoRepeat, S),
    /// Bilinear, masked.
    MaskedBilinear(PowerOfTwoRepeat, S),
    /// Any other nearest texture.
    Nearest(&'t Texture<S>),
    /// Any other bilinear texture.
    Bilinear(&'t Texture<S>),
}

impl<'t, S: TexelSource> Sampler<'t, S> {
    /// The sampler of `texture`.
    #[inline(always)]
    pub(crate) fn new(texture: &'t Texture<S>) -> Self {
        let masked = PowerOfTwoRepeat::of(texture)
            .and_then(|masks| Some((masks, texture.source().prefix(masks.last())?)));
        match (texture.filter(), masked) {
            (Filter::Nearest, Some((masks, texels))) => Sampler::MaskedNearest(masks, texels),
            (Filter::Bilinear, Some((masks, texels))) => Sampler::MaskedBilinear(masks, texels),
            (Filter::Nearest, None) => Sampler::Nearest(texture),
            (Filter::Bilinear, None) => Sampler::Bilinear(texture),
        }
    }

    /// Runs `body` with this sampling function: [`Texture::sample`]'s colours.
    // The masked samplers' fetch skips the bounds check their masks make redundant.
    #[allow(unsafe_code)]
    #[inline(always)]
    pub(crate) fn run<C, L>(&self, body: L) -> L::Output
    where
        C: GouraudColor + From<S::Color>,
        L: SampledLoop<C>,
    {
        match self {
            // Indices masked to the texture's texels, read from storage cut to exactly those
            // (`prefix`): inside by construction, fetched without a bounds check.
            // Textures of up to 2¹⁶ texels take `y` scaled by their width: its whole texels
            // are then the row's storage offset, and a mask alone finds it.
            // The closures take copies: values the loop keeps in registers, not loads through a
            // reference (which the compiler cannot tell from the pixels being written).
            &Sampler::MaskedNearest(masks, texels) if masks.rows.is_some() => {
                let rows = masks.rows.unwrap_or(0);
                let sample = move |x: i32, y_scaled: i32| {
                    let row = (y_scaled >> 16) as u32 & rows;
                    let column = (x >> 16) as u32 & masks.x_mask;
                    // SAFETY: at most `rows | x_mask`, the index of the texture's last texel,
                    // and `texels` holds exactly its texels (`prefix`).
                    C::from(unsafe { texels.texel_unchecked((row | column) as usize) })
                };
                body.run(sample, masks.row_shift)
            }
            &Sampler::MaskedNearest(masks, texels) => {
                let sample = move |x, y| {
                    // SAFETY: as above.
                    C::from(unsafe { texels.texel_unchecked(masks.index(x, y)) })
                };
                body.run(sample, 0)
            }
            &Sampler::MaskedBilinear(masks, texels) => {
                // The target's loop for raw Rgb565 texels, if the body has one.
                let body = match texels.rgb565_words() {
                    Some(words) if arch::BILINEAR_ROWS => {
                        match body.run_bilinear_565(masks, words.0) {
                            Ok(output) => return output,
                            Err(body) => body,
                        }
                    }
                    _ => body,
                };
                // SAFETY: `texels` holds exactly the texels `masks` address (above).
                body.run(
                    move |x, y| unsafe { masked_bilinear(x, y, masks, &texels) },
                    0,
                )
            }
            Sampler::Nearest(texture) => body.run(|x, y| C::from(texture.nearest(x, y)), 0),
            Sampler::Bilinear(texture) => body.run(|x, y| texture.bilinear_sums(x, y), 0),
        }
    }
}

/// The bilinear blend at `(x, y)` of `texels` addressed by `masks` (the masked sampler's). Out
/// of line on ARMv6-M: the many loops that take it would each hold a copy (the micro:bit's
/// flash).
///
/// # Safety
///
/// `texels` holds at least the texels of the texture `masks` address (every index they give).
#[allow(unsafe_code)]
#[cfg_attr(armv6m, inline(never))]
#[cfg_attr(not(armv6m), inline(always))]
unsafe fn masked_bilinear<C, S>(x: i32, y: i32, masks: PowerOfTwoRepeat, texels: &S) -> Blend<C>
where
    C: GouraudColor + From<S::Color>,
    S: TexelSource,
{
    bilinear_sums_by(x, y, |i, j| {
        // SAFETY: an index the masks give, inside `texels` (the caller's promise).
        C::from(unsafe { texels.texel_unchecked(masks.texel_index(i, j)) })
    })
}

/// Fills `dst` with the texture sampled at `(x, y) + i·(dx, dy)` (16.16 texels, wrapping) for
/// pixel `i`: [`Texture::sample`] at each.
#[inline(always)]
pub(crate) fn fill_affine<S, C>(
    dst: &mut [C],
    sampler: &Sampler<'_, S>,
    at: (i32, i32),
    step: (i32, i32),
) where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    // Raw Rgb565 texels into Rgb565 pixels: the target's loop, if it has one (the same texels
    // as the masked loop below).
    if arch::MASKED_NEAREST_565 {
        if let Sampler::MaskedNearest(masks, texels) = sampler {
            if let Some(words) = texels.rgb565_words() {
                if let Some(span) = masks.span_565(words.0, at, step) {
                    if C::fill_masked_565(dst, &span) {
                        return;
                    }
                }
            }
        }
    }
    sampler.run(Affine { dst, at, step });
}

/// [`fill_affine`]'s loop.
struct Affine<'d, C> {
    dst: &'d mut [C],
    at: (i32, i32),
    step: (i32, i32),
}

impl<C: GouraudColor> SampledLoop<C> for Affine<'_, C> {
    type Output = ();

    // Out of line: the walk's values stay out of the loop's registers (a call a span).
    #[inline(never)]
    fn run<T: Sampled<C>>(self, sample: impl Fn(i32, i32) -> T, y_shift: u32) {
        let (mut x, dx) = (self.at.0, self.step.0);
        let (mut y, dy) = (self.at.1 << y_shift, self.step.1 << y_shift);
        for px in self.dst {
            *px = sample(x, y).color();
            x = x.wrapping_add(dx);
            y = y.wrapping_add(dy);
        }
    }

    #[inline(always)]
    fn run_bilinear_565(self, masks: PowerOfTwoRepeat, words: &[u16]) -> Result<(), Self> {
        match masks.span_565(words, self.at, self.step) {
            Some(span) if C::fill_bilinear_565(self.dst, &span) => Ok(()),
            _ => Err(self),
        }
    }
}

/// Nearest filtering of a texture repeating on both axes with power-of-two sides: the storage
/// index of the texel at a 16.16 coordinate from two masks and a shift.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct PowerOfTwoRepeat {
    x_mask: u32,
    y_mask: u32,
    row_shift: u32,
    /// The row mask in storage units, `y_mask << row_shift`, for textures of up to 2¹⁶ texels
    /// (whose storage index fits 16 bits).
    rows: Option<u32>,
}

impl PowerOfTwoRepeat {
    /// The masks of `texture`, if it is of that kind.
    #[inline(always)]
    pub(crate) fn of<S: TexelSource>(texture: &Texture<S>) -> Option<Self> {
        let (x, y) = texture.axes();
        match (x.wrap(), y.wrap(), x.shift(), y.shift()) {
            (Wrap::Repeat, Wrap::Repeat, Some(row_shift), Some(_)) => {
                let y_mask = y.size() - 1;
                // At most 16 index bits (`row_shift` plus the bit length of `y_mask`), found
                // by shifts: a bit length is a library call on Cortex-M0.
                let fits = row_shift <= 16 && y_mask >> (16 - row_shift) == 0;
                Some(PowerOfTwoRepeat {
                    x_mask: x.size() - 1,
                    y_mask,
                    row_shift,
                    rows: fits.then(|| y_mask << row_shift),
                })
            }
            _ => None,
        }
    }

    /// The span of `texels` from `at` stepping by `step` (16.16) for a target's own masked
    /// nearest loop, if the texture's storage index fits 16 bits.
    #[inline(always)]
    fn span_565<'w>(
        &self,
        texels: &'w [u16],
        at: (i32, i32),
        step: (i32, i32),
    ) -> Option<MaskedSpan565<'w>> {
        Some(MaskedSpan565 {
            texels,
            x: (at.0, step.0),
            y: (at.1 << self.row_shift, step.1 << self.row_shift),
            x_mask: self.x_mask,
            rows: self.rows?,
        })
    }

    /// The column mask and the row mask in storage units (the last column's index and the last
    /// row's first), if the texture has at most 2¹⁶ texels: the target's row loops' masks.
    #[inline(always)]
    pub(crate) fn masks_565(&self) -> Option<(u32, u32)> {
        let (x_mask, rows_mask) = (self.texel_index(-1, 0), self.texel_index(0, -1));
        let (x_mask, rows_mask) = (x_mask as u32, rows_mask as u32);
        (x_mask | rows_mask <= 0xffff).then_some((x_mask, rows_mask))
    }

    /// The index of the texture's last texel (its texels less one: a power of two less one).
    #[inline(always)]
    fn last(&self) -> usize {
        ((self.y_mask << self.row_shift) | self.x_mask) as usize
    }

    /// The storage index of texel `(i, j)` after wrapping (at most [`last`](Self::last)).
    #[inline(always)]
    pub(crate) fn texel_index(&self, i: i32, j: i32) -> usize {
        let column = i as u32 & self.x_mask;
        let row = j as u32 & self.y_mask;
        ((row << self.row_shift) | column) as usize
    }

    /// The storage index of the texel at `(x, y)`: [`Texture::nearest`]'s.
    #[inline(always)]
    pub(crate) fn index(&self, x: i32, y: i32) -> usize {
        self.texel_index(x >> 16, y >> 16)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::{Indexed4, Rgb565Texels};
    use embedded_graphics::pixelcolor::raw::RawU16;
    use embedded_graphics::pixelcolor::{Gray8, Rgb565};

    /// The 32-bit roundings are the exact ones (of 64-bit arithmetic).
    #[test]
    fn roundings_in_32_bits_are_exact() {
        let mut next = crate::random(0x7e47_0003);
        for n in 0..200_000 {
            let v = match n % 4 {
                0 => next() as u32,
                1 => u32::MAX - (next() % 1024) as u32,
                2 => (next() % 1024) as u32,
                _ => (next() as u32) >> (next() % 32),
            };
            let shift = (n / 4 % 18) as u32;
            let exact = (u64::from(v) + (1u64 << shift >> 1)) >> shift;
            assert_eq!(u64::from(round_shift(v, shift)), exact, "{v} {shift}");
            let (down, up) = if shift <= 16 {
                (16 - shift, 0)
            } else {
                (0, shift - 16)
            };
            let map = PlaneMap { base: 0, down, up };
            let want = (((i64::from(v as i32) << (up + 16 - down)) + (1 << 15)) >> 16) as i32;
            assert_eq!(map.step(v), want, "{v} {down} {up}");
        }
    }

    /// The mapped plane values read back as the coordinates, and the margin holds.
    #[test]
    fn plane_maps_cover_any_coordinates() {
        let mut next = crate::random(0x7e47_0002);
        for n in 0..20_000 {
            let spread = 1u64 << (n % 33);
            let lo = next() as i32;
            let c = [(); 3].map(|_| {
                (i64::from(lo) + (next() % spread) as i64).clamp(i32::MIN.into(), i32::MAX.into())
                    as i32
            });
            let (map, values) = PlaneMap::new(c);
            let shift = map.up + 16 - map.down;
            for k in 0..3 {
                assert!(
                    (128..=65_535 - 128).contains(&values[k]),
                    "{c:?} {values:?}"
                );
                let back = map.at(u32::from(values[k]) << 16);
                // Within half a step of the values' scale, modulo 2³².
                let err = i64::from(c[k].wrapping_sub(back));
                assert!(err.abs() <= 1 << shift >> 1, "{c:?} {k}: {back}");
            }
        }
    }

    /// The Cortex-M0 masked nearest loop's arithmetic (`arch::thumbv6m`), modelled here: each
    /// texel's byte offset from the coordinates shifted by 15 and the masks doubled, the
    /// coordinates stepped by wrapping adds. Its spans are `Texture::sample`'s.
    #[test]
    fn doubled_mask_offsets_read_the_sampled_texels() {
        let mut next = crate::random(0x7e47_0004);
        let texels: [u16; 4096] = core::array::from_fn(|_| next() as u16);
        let shapes = [
            (64, 64),
            (256, 16),
            (1, 4096),
            (4096, 1),
            (8, 2),
            (1, 1),
            (16, 256),
        ];
        for n in 0..4_000 {
            let (w, h) = shapes[n % shapes.len()];
            let texture = Texture::new(Rgb565Texels(&texels), w, h).unwrap();
            let Sampler::MaskedNearest(masks, source) = Sampler::new(&texture) else {
                panic!("{w}×{h} is masked");
            };
            let at = (next() as i32, next() as i32);
            let step = (
                (next() as i32) >> (next() % 32),
                (next() as i32) >> (next() % 32),
            );
            let span = masks.span_565(source.0, at, step).unwrap();
            assert!(((span.rows | span.x_mask) as usize) < span.texels.len());
            let (mut x, mut y) = (span.x.0, span.y.0);
            for i in 0..40 {
                let offset =
                    ((y >> 15) as u32 & (span.rows << 1)) | ((x >> 15) as u32 & (span.x_mask << 1));
                assert_eq!(offset % 2, 0);
                let got = Rgb565::from(RawU16::new(span.texels[offset as usize / 2]));
                let want = texture.sample::<Rgb565>(
                    at.0.wrapping_add(step.0.wrapping_mul(i)),
                    at.1.wrapping_add(step.1.wrapping_mul(i)),
                );
                assert_eq!(got, want, "{w}×{h} {at:?} {step:?} {i}");
                x = x.wrapping_add(span.x.1);
                y = y.wrapping_add(span.y.1);
            }
        }
    }

    /// The masked loops give what `Texture::sample` gives, with either filter.
    #[test]
    fn masked_spans_are_the_sampled_ones() {
        let mut next = crate::random(0x7e47_0003);
        let texels: [u16; 64 * 32] = core::array::from_fn(|_| next() as u16);
        let indices: [u8; 24 * 8] = core::array::from_fn(|_| next() as u8);
        let palette: [Gray8; 16] = core::array::from_fn(|i| Gray8::new(i as u8 * 16));
        for _ in 0..2_000 {
            let at = (next() as i32, next() as i32);
            let step = (
                (next() as i32) >> (next() % 32),
                (next() as i32) >> (next() % 32),
            );
            let len = (next() % 40) as usize;
            let texture = Texture::new(Rgb565Texels(&texels), 64, 32).unwrap();
            for filter in [Filter::Nearest, Filter::Bilinear] {
                let texture = texture.with_filter(filter);
                let mut got = [Rgb565::from(RawU16::new(0)); 40];
                fill_affine(&mut got[..len], &Sampler::new(&texture), at, step);
                for (i, &px) in got[..len].iter().enumerate() {
                    let (x, y) = (
                        at.0.wrapping_add(step.0.wrapping_mul(i as i32)),
                        at.1.wrapping_add(step.1.wrapping_mul(i as i32)),
                    );
                    assert_eq!(px, texture.sample::<Rgb565>(x, y), "{filter:?}");
                }
            }
            // Not a power of two: the general loop.
            let texture = Texture::new(
                Indexed4 {
                    indices: &indices,
                    palette: &palette,
                },
                24,
                16,
            )
            .unwrap()
            .with_wrap(Wrap::MirroredRepeat, Wrap::Clamp);
            let mut got = [Gray8::new(0); 40];
            fill_affine(&mut got[..len], &Sampler::new(&texture), at, step);
            for (i, &px) in got[..len].iter().enumerate() {
                let x = at.0.wrapping_add(step.0.wrapping_mul(i as i32));
                let y = at.1.wrapping_add(step.1.wrapping_mul(i as i32));
                assert_eq!(px, texture.nearest(x, y));
            }
        }
    }
}
