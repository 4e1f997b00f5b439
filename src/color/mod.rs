//! Colour channels the rasterizer interpolates.
//!
//! [`GouraudColor`] splits a colour into up to three integer channels in its own depth
//! (`Rgb565`: 5, 6 and 5 bits) and builds it back. Interpolating in the target's own depth is what
//! makes the "within 1 LSB" guarantee meaningful for every format. The colours of a span are
//! defined once per format, by its span state ([`GouraudColor::span_state`] and the items after
//! it); the slice loops ([`GouraudColor::fill_prepared`]) and the per-pixel iterator
//! ([`SpanColors`](crate::SpanColors)) both give them. The 5-6-5 formats have a packed span loop
//! of their own (`packed565`).
//!
//! ```
//! use embedded_graphics::pixelcolor::{Rgb565, Gray8};
//! use embedded_raster::GouraudColor;
//!
//! assert_eq!(Rgb565::new(31, 40, 2).channels(), [31, 40, 2]);
//! assert_eq!(Gray8::from_channels([77, 0, 0]), Gray8::new(77));
//! ```

use core::num::NonZeroU32;

use embedded_graphics::pixelcolor::{
    Bgr555, Bgr565, Bgr666, Bgr888, BinaryColor, Gray2, Gray4, Gray8, GrayColor, Rgb555, Rgb565,
    Rgb666, Rgb888, RgbColor,
};
use embedded_graphics::prelude::PixelColor;

use crate::arch::MaskedSpan565;
pub use crate::arch::LANES;

mod blend;
mod dither;
mod packed565;

pub use blend::BlendSource;
pub(crate) use blend::{
    blend_channels, blend_premultiplied, premultiplied_values, weight, TRANSPARENCY_HALF,
};
pub(crate) use dither::DitheredColors;
use packed565::{dithered_565, fill_565, masked_row_565, prepare_565, PACKED_RUN};

/// Fractional bits of the stepped channel values handed to [`GouraudColor::fill_span`] and
/// [`GouraudColor::from_stepped`]: channels have at most 8 integer bits, so a value fits a `u32`.
pub use crate::raster::plane::STEP_BITS;

const F: u32 = STEP_BITS;

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
    /// ([`STEP_BITS`] fractional bits, +½ rounding offset included, at most 2¹⁶ pixels).
    #[inline]
    fn fill_span(dst: &mut [Self], start: [u32; 3], step: [u32; 3]) {
        Self::fill_prepared(dst, start, &Self::prepare_steps(step));
    }

    /// The per-pixel steps `step` in the form this format's span loop uses, computed once per
    /// triangle for [`fill_prepared`](Self::fill_prepared).
    #[inline]
    fn prepare_steps(step: [u32; 3]) -> SpanSteps {
        SpanSteps {
            step,
            lane: [0; 3],
            double: [0; 3],
        }
    }

    /// [`fill_span`](Self::fill_span) with steps from [`prepare_steps`](Self::prepare_steps):
    /// the span's colours as [`span_state`](Self::span_state),
    /// [`state_color`](Self::state_color), [`next_state`](Self::next_state) and
    /// [`SPAN_RUN`](Self::SPAN_RUN) define them ([`SpanColors`](crate::SpanColors) hands out the
    /// same ones). Formats may override both with a faster loop that gives those colours (the
    /// 5-6-5 formats do).
    #[inline]
    fn fill_prepared(dst: &mut [Self], start: [u32; 3], steps: &SpanSteps) {
        fill_by_state(dst, start, steps);
    }

    /// Fills `dst`, pixels `x ..` of row `y`, with the span from `start` by `steps` (as for
    /// [`fill_prepared`](Self::fill_prepared)) ordered-dithered with a 4×4 Bayer matrix: each
    /// channel the floor or the ceiling of its value (within 2⁻⁶ LSB), a flat colour between
    /// two levels averaging to it over each 4×4 block. By default from the [`STEP_BITS`]
    /// values channel by channel; the 5-6-5 formats override it with their packed lanes,
    /// restarted every 32 pixels. Every dithered fill of this crate gives these colours (`draw`
    /// fills a span 32 pixels at a time from the values there: an override must give a span
    /// filled in such pieces the colours it gives it whole).
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
    /// use embedded_raster::{color::STEP_BITS, GouraudColor};
    ///
    /// // Red 10.25 (+½ included) on a whole 4×4 block: a quarter of the pixels 11, the rest 10.
    /// let one = 1u32 << STEP_BITS;
    /// let steps = Rgb565::prepare_steps([0; 3]);
    /// let mut elevens = 0;
    /// for y in 0..4 {
    ///     let mut row = [Rgb565::BLACK; 4];
    ///     Rgb565::fill_dithered(&mut row, 0, y, [10 * one + one / 4 + one / 2, one / 2, one / 2], &steps);
    ///     elevens += row.iter().filter(|c| c.r() == 11).count();
    ///     assert!(row.iter().all(|c| (10..=11).contains(&c.r()) && c.g() == 0 && c.b() == 0));
    /// }
    /// assert_eq!(elevens, 4);
    /// ```
    #[inline]
    fn fill_dithered(dst: &mut [Self], x: i32, y: i32, start: [u32; 3], steps: &SpanSteps) {
        dither::fill_dithered_by_channels(dst, x, y, start, steps);
    }

    /// Pixels of a span stepped from one start: every `SPAN_RUN` pixels the span loop restarts
    /// from the exact channel values there (the start plus that many steps, modulo 2³²), so its
    /// stepping error never grows beyond that many steps. `None` (the default): the whole span
    /// is stepped from its start.
    const SPAN_RUN: Option<NonZeroU32> = None;

    /// The span loop's per-pixel state at a (re)start whose channel values are `value`
    /// ([`STEP_BITS`] fractional bits, +½ included); by default the values themselves.
    #[inline(always)]
    fn span_state(value: [u32; 3]) -> [u32; 3] {
        value
    }

    /// The colour of the span loop's state `state`; by default
    /// [`from_stepped`](Self::from_stepped).
    #[inline(always)]
    fn state_color(state: [u32; 3]) -> Self {
        Self::from_stepped(state)
    }

    /// Draws the rows of a small textured face into `colors` and `depths` by a loop of the
    /// target's own, if this format has one there (Rgb565 on ARMv7-M, whose raw values the
    /// texels are); `false` without writing anything where it has none (the default). Hidden:
    /// its argument's type cannot be named outside the crate.
    #[doc(hidden)]
    #[inline(always)]
    fn textured_rows_565(
        colors: &mut [Self],
        depths: &mut [u16],
        rows: &crate::arch::TexturedRows<'_>,
    ) -> bool {
        let _ = (colors, depths, rows);
        false
    }

    /// Sets up and draws a small textured face into the buffers `(colors, depths, width)` by
    /// the target's own code, if this format has it there (Rgb565 on ARMv7-M, whose raw values
    /// the texels are): what it did; declined, without writing anything, where it has none
    /// (the default). Hidden: its argument's type cannot be named outside the crate.
    #[doc(hidden)]
    #[inline(always)]
    fn textured_face_565(
        buffers: (&mut [Self], &mut [u16], usize),
        face: crate::arch::TexturedFace<'_>,
    ) -> crate::arch::TexturedDraw {
        let _ = (buffers, face);
        crate::arch::TexturedDraw::Declined
    }

    /// The textured faces `faces` of a draw into `buffers` for the target's face scan (its
    /// faces' set-up as [`textured_face_565`](Self::textured_face_565)'s), if this format has
    /// that set-up there; none where it has none (the default). Hidden: its argument's type
    /// cannot be named outside the crate.
    #[doc(hidden)]
    #[inline(always)]
    fn textured_faces_565<'w>(
        buffers: (&mut [Self], &mut [u16], usize),
        faces: crate::arch::TexturedFaces<'w>,
    ) -> Option<crate::arch::TexturedFaces<'w>> {
        let _ = (buffers, faces);
        None
    }

    /// Draws a span of the perspective-correct textured fill into `colors` and `depths` by a
    /// loop of the target's own, if this format has one there (Rgb565 on ARMv7-M, whose raw
    /// values the texels are); `false` without writing anything where it has none (the
    /// default). Hidden: its argument's type cannot be named outside the crate.
    #[doc(hidden)]
    #[inline(always)]
    fn perspective_span_565(
        colors: &mut [Self],
        depths: &mut [u16],
        span: &crate::arch::PerspectiveSpan565<'_>,
    ) -> bool {
        let _ = (colors, depths, span);
        false
    }

    /// The state one pixel to the right of `state`; by default the values plus the steps,
    /// wrapping.
    #[inline(always)]
    fn next_state(state: [u32; 3], steps: &SpanSteps) -> [u32; 3] {
        let (mut v, step) = (state, steps.step);
        v[0] = v[0].wrapping_add(step[0]);
        if Self::CHANNELS > 1 {
            v[1] = v[1].wrapping_add(step[1]);
            v[2] = v[2].wrapping_add(step[2]);
        }
        v
    }

    /// Fills the covered pixels of one row of a tiny triangle's box (drawn a row of [`LANES`]
    /// pixels at a time on x86-64): `covered[i]` is `-1` for covered pixels, which form one run from
    /// pixel `first` on, and `0` for the others, which keep their colour. The run gets the
    /// colours [`fill_prepared`](Self::fill_prepared) gives it from `start`. Formats may
    /// override it with a loop over all eight pixels that masks the write (the 5-6-5 formats
    /// do).
    ///
    /// ```
    /// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
    /// use embedded_raster::{color::STEP_BITS, GouraudColor};
    ///
    /// let one = 1u32 << STEP_BITS;
    /// let (start, step) = ([one / 2, 81 * one / 2, 61 * one / 2], [one, 0, 0]);
    /// let steps = Rgb565::prepare_steps(step);
    /// let mut row = [Rgb565::WHITE; 8];
    /// // Pixels 2, 3 and 4 covered: red 0, 1, 2 there.
    /// Rgb565::fill_masked_row(&mut row, [0, 0, -1, -1, -1, 0, 0, 0], 2, start, &steps);
    /// let mut span = [Rgb565::WHITE; 3];
    /// Rgb565::fill_prepared(&mut span, start, &steps);
    /// assert_eq!(row[..2], [Rgb565::WHITE; 2]);
    /// assert_eq!(row[2..5], span);
    /// assert_eq!(span[2], Rgb565::new(2, 40, 30));
    /// assert_eq!(row[5..], [Rgb565::WHITE; 3]);
    /// ```
    #[inline]
    fn fill_masked_row(
        row: &mut [Self; LANES],
        covered: [i16; LANES],
        first: u32,
        start: [u32; 3],
        steps: &SpanSteps,
    ) {
        let len = covered.iter().filter(|&&c| c != 0).count();
        if let Some(run) = row.get_mut(first as usize..first as usize + len) {
            Self::fill_prepared(run, start, steps);
        }
    }

    /// `self` at opacity `alpha` (0 transparent, 255 opaque) over `dst`, source-over in this
    /// format's channel depth: each channel `⌊(s·w + d·(256 − w) + 128) / 256⌋` with the weight
    /// `w = alpha + (alpha >> 7)` of 256ths, within 1 LSB of the exact
    /// `s·alpha/255 + d·(1 − alpha/255)` (see `color::blend`). Every blend of this crate gives
    /// these colours.
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
    /// use embedded_raster::GouraudColor;
    ///
    /// assert_eq!(Rgb888::RED.blend(Rgb888::BLUE, 255), Rgb888::RED);
    /// assert_eq!(Rgb888::RED.blend(Rgb888::BLUE, 0), Rgb888::BLUE);
    /// assert_eq!(Rgb888::RED.blend(Rgb888::BLUE, 128), Rgb888::new(128, 0, 127));
    /// ```
    #[inline(always)]
    fn blend(self, dst: Self, alpha: u8) -> Self {
        Self::from_channels(blend_channels(
            self.channels(),
            dst.channels(),
            weight(alpha),
        ))
    }

    /// Blends one colour at one opacity ([`BlendSource`]) over every pixel of `dst`: the colours
    /// of [`blend`](Self::blend). Formats may override it with a faster loop that gives them
    /// (the 5-6-5 formats do, two pixels a word).
    #[inline]
    fn blend_solid(dst: &mut [Self], source: &BlendSource) {
        blend::blend_solid_by_channels(dst, source);
    }

    /// Blends a span of a triangle with an alpha per vertex over `dst`: pixel `i` is
    /// `blend_premultiplied` of the planes (premultiplied `r`, `g`, `b`, transparency `t`) at
    /// `start + i·step` (wrapping) over it. By default pixel by pixel; the 5-6-5 formats override
    /// it with a loop on raw values that gives the same pixels. Hidden: the planes' form is the
    /// crate's own.
    #[doc(hidden)]
    #[inline]
    fn blend_premultiplied_span(dst: &mut [Self], start: [u32; 4], step: [u32; 4]) {
        blend::blend_premultiplied_by_pixels(dst, start, step);
    }

    /// Fills `dst` with an affine span of nearest Rgb565 texels by a loop of the target's own,
    /// if this format has one there (Rgb565 on Cortex-M0); `false` without writing anything
    /// where it has none (the default). Hidden: its argument's type cannot be named outside the
    /// crate.
    #[doc(hidden)]
    #[inline(always)]
    fn fill_masked_565(dst: &mut [Self], span: &MaskedSpan565<'_>) -> bool {
        let _ = (dst, span);
        false
    }

    /// Fills `dst` with an affine span of bilinear Rgb565 texels (`span` as for
    /// [`fill_masked_565`](Self::fill_masked_565)) by a loop of the target's own, if this
    /// format has one there (Rgb565 on ARMv7E-M); `false` without writing anything where it
    /// has none (the default). Hidden: its argument's type cannot be named outside the crate.
    #[doc(hidden)]
    #[inline(always)]
    fn fill_bilinear_565(dst: &mut [Self], span: &MaskedSpan565<'_>) -> bool {
        let _ = (dst, span);
        false
    }

    /// Draws the depth-tested pixels of a perspective-correct chunk of nearest Rgb565 texels
    /// into `colors` and `depths`, the depth plane's value and step a pixel `depth`, by a loop of
    /// the target's own, if this format has one there (Rgb565 on Cortex-M0); `false` without
    /// writing anything where it has none (the default). Hidden: its argument's type cannot be
    /// named outside the crate.
    #[doc(hidden)]
    #[inline(always)]
    fn fill_depth_masked_565(
        colors: &mut [Self],
        depths: &mut [u16],
        span: &MaskedSpan565<'_>,
        depth: (u32, u32),
    ) -> bool {
        let _ = (colors, depths, span, depth);
        false
    }
}

/// Per-pixel channel steps of a triangle, prepared for a colour format's span loop
/// ([`GouraudColor::prepare_steps`]).
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use embedded_raster::{color::STEP_BITS, GouraudColor};
///
/// // Red from 2.5 stepping by 0.25 a pixel, green 40.5, blue 30.5 stepping by −1 (+½ included).
/// let one = 1u32 << STEP_BITS;
/// let (start, step) = ([5 * one / 2, 81 * one / 2, 61 * one / 2], [one / 4, 0, one.wrapping_neg()]);
/// let steps = Rgb565::prepare_steps(step); // once per triangle
/// let mut row = [Rgb565::new(0, 0, 0); 8];
/// Rgb565::fill_prepared(&mut row, start, &steps); // once per span
/// assert_eq!(row[0], Rgb565::new(2, 40, 30));
/// assert_eq!(row[7], Rgb565::new(4, 40, 23));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[repr(C)] // The ARMv6-M span loop reads `lane` and `double` at fixed offsets.
pub struct SpanSteps {
    /// 5-6-5 formats: each channel's step rounded to its lane, in raw order (see [`fill_565`]) …
    lane: [u32; 3],
    /// … and two of them in both halves of a word (see [`run_565`]).
    double: [u32; 3],
    /// The steps, [`STEP_BITS`] fractional bits, in channel order.
    step: [u32; 3],
}

impl SpanSteps {
    /// The steps, [`STEP_BITS`] fractional bits, in channel order.
    pub fn step(&self) -> [u32; 3] {
        self.step
    }

    /// The nine words as the assembly loops read them: `lane`, `double`, `step`.
    #[cfg_attr(not(any(armv7m, armv6m)), allow(dead_code))]
    #[inline(always)]
    #[allow(unsafe_code)]
    pub(crate) fn words(&self) -> &[u32; 9] {
        const { assert!(core::mem::size_of::<SpanSteps>() == 36) };
        // SAFETY: `SpanSteps` is `repr(C)`: three `[u32; 3]` one after the other, no padding
        // (36 bytes, asserted), with the alignment of `u32`.
        unsafe { &*core::ptr::from_ref(self).cast::<[u32; 9]>() }
    }
}

/// The channel values `pixels` pixels after `value` (`steps`' plain steps, wrapping): where the
/// span loop restarts ([`GouraudColor::SPAN_RUN`]), or a dithered span's next chunk.
#[inline(always)]
pub(crate) fn restart_value(value: [u32; 3], steps: &SpanSteps, pixels: u32) -> [u32; 3] {
    core::array::from_fn(|k| value[k].wrapping_add(steps.step[k].wrapping_mul(pixels)))
}

/// The colours of a span from its start `start`, one pixel at a time, as the format's
/// [`span_state`](GouraudColor::span_state), [`state_color`](GouraudColor::state_color),
/// [`next_state`](GouraudColor::next_state) and [`SPAN_RUN`](GouraudColor::SPAN_RUN) define
/// them: the default [`GouraudColor::fill_prepared`], and what faster loops must equal.
#[inline(always)]
pub(crate) fn fill_by_state<C: GouraudColor>(dst: &mut [C], start: [u32; 3], steps: &SpanSteps) {
    let run_of = |dst: &mut [C], value: [u32; 3]| {
        let mut state = C::span_state(value);
        for px in dst {
            *px = C::state_color(state);
            state = C::next_state(state, steps);
        }
    };
    match C::SPAN_RUN {
        None => run_of(dst, start),
        Some(run) => {
            let mut value = start;
            for part in dst.chunks_mut(run.get() as usize) {
                run_of(part, value);
                value = restart_value(value, steps, run.get());
            }
        }
    }
}

/// `GouraudColor` for RGB formats; `order = [top, 1, bottom]` selects the 5-6-5 span loop with
/// that channel order in the raw value; `masked_565` is the target's masked nearest texel loop
/// (for the format whose raw bits are Rgb565 texels' own).
macro_rules! rgb_color {
    ($t:ty $(, order = $order:expr)? $(, masked_565 = $masked:path)?) => {
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
                // Rgb565 (the raw order of Rgb565 texels) only.
                #[inline(always)]
                fn textured_rows_565(
                    colors: &mut [Self],
                    depths: &mut [u16],
                    rows: &crate::arch::TexturedRows<'_>,
                ) -> bool {
                    $order == [0, 1, 2] && crate::arch::textured_rows(colors, depths, rows)
                }
                #[inline(always)]
                fn textured_face_565(
                    buffers: (&mut [Self], &mut [u16], usize),
                    face: crate::arch::TexturedFace<'_>,
                ) -> crate::arch::TexturedDraw {
                    if $order != [0, 1, 2] {
                        return crate::arch::TexturedDraw::Declined;
                    }
                    crate::arch::textured_face(buffers, face)
                }
                #[inline(always)]
                fn textured_faces_565<'w>(
                    buffers: (&mut [Self], &mut [u16], usize),
                    faces: crate::arch::TexturedFaces<'w>,
                ) -> Option<crate::arch::TexturedFaces<'w>> {
                    if $order != [0, 1, 2] {
                        return None;
                    }
                    crate::arch::textured_faces(buffers, faces)
                }
                #[inline(always)]
                fn perspective_span_565(
                    colors: &mut [Self],
                    depths: &mut [u16],
                    span: &crate::arch::PerspectiveSpan565<'_>,
                ) -> bool {
                    $order == [0, 1, 2] && crate::arch::perspective_span(colors, depths, span)
                }
                #[inline(always)]
                fn fill_bilinear_565(dst: &mut [Self], span: &MaskedSpan565<'_>) -> bool {
                    $order == [0, 1, 2] && crate::arch::bilinear_span_565(dst, span)
                }
                #[inline]
                fn prepare_steps(step: [u32; 3]) -> SpanSteps {
                    prepare_565(step, $order)
                }
                #[inline(always)]
                fn blend_solid(dst: &mut [Self], source: &BlendSource) {
                    blend::blend_solid_565(dst, source, $order)
                }
                #[inline(always)]
                fn blend_premultiplied_span(dst: &mut [Self], start: [u32; 4], step: [u32; 4]) {
                    blend::blend_premultiplied_565(dst, start, step, $order)
                }
                // Out of line on Cortex-M3/M4/M7: the loop then has the registers to itself.
                // Inlined on ARMv6-M (the loop is an assembly function and this wrapper is
                // small) and on hosts (where the vectorised loop gains from the span's context).
                #[cfg_attr(not(armv7m), inline(always))]
                #[cfg_attr(armv7m, inline(never))]
                fn fill_prepared(dst: &mut [Self], start: [u32; 3], steps: &SpanSteps) {
                    fill_565(dst, start, steps, $order)
                }
                #[cfg_attr(not(armv7m), inline(always))]
                #[cfg_attr(armv7m, inline(never))]
                fn fill_dithered(
                    dst: &mut [Self],
                    x: i32,
                    y: i32,
                    start: [u32; 3],
                    steps: &SpanSteps,
                ) {
                    dithered_565(dst, (x, y), start, steps, $order)
                }
                const SPAN_RUN: Option<NonZeroU32> = NonZeroU32::new(PACKED_RUN as u32);
                #[inline(always)]
                fn span_state(value: [u32; 3]) -> [u32; 3] {
                    packed565::span_state(value, $order)
                }
                #[inline(always)]
                fn state_color(state: [u32; 3]) -> Self {
                    packed565::state_color(state)
                }
                #[inline(always)]
                fn next_state(state: [u32; 3], steps: &SpanSteps) -> [u32; 3] {
                    packed565::next_state(state, steps)
                }
                #[inline(always)]
                fn fill_masked_row(
                    row: &mut [Self; LANES],
                    covered: [i16; LANES],
                    first: u32,
                    start: [u32; 3],
                    steps: &SpanSteps,
                ) {
                    masked_row_565(row, covered, first, start, steps, $order)
                }
            )?
            $(
                #[inline(always)]
                fn fill_masked_565(dst: &mut [Self], span: &MaskedSpan565<'_>) -> bool {
                    $masked(dst, span)
                }
                #[inline(always)]
                fn fill_depth_masked_565(
                    colors: &mut [Self],
                    depths: &mut [u16],
                    span: &MaskedSpan565<'_>,
                    depth: (u32, u32),
                ) -> bool {
                    crate::arch::depth_masked_nearest_565(colors, depths, span, depth)
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

rgb_color!(
    Rgb565,
    order = [0, 1, 2],
    masked_565 = crate::arch::masked_nearest_565
);
rgb_color!(Bgr565, order = [2, 1, 0]);
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

/// `base`'s channels each scaled by `level` (16 fractional bits) and rounded to nearest: `(c·level
/// + 2¹⁵) >> 16` (the light's scaling of a colour, and of a texel).
#[inline(always)]
pub(crate) fn scale_channels<C: GouraudColor>(base: [u8; 3], level: u32) -> C {
    let s = |c: u8| ((u32::from(c) * level + (1 << 15)) >> 16) as u8;
    C::from_channels([s(base[0]), s(base[1]), s(base[2])])
}

/// Sets every pixel of `pixels` (a whole buffer: a clear) to `color`: as [`fill_row`], and where
/// `C` is a 16-bit colour and the target has a loop of eight words a pass (RV32, ARMv7-M) the
/// 4-byte aligned middle by it, 16 pixels for 4 instructions on the Cortex-M4 (against 10).
pub(crate) fn fill_all<C: Copy>(pixels: &mut [C], color: C) {
    let head = (pixels.as_ptr() as usize >> 1) & 1;
    let whole = pixels.len().saturating_sub(head) & !15;
    // Checked splits (both always succeed): no panic path.
    if let Some((start, rest)) = pixels.split_at_mut_checked(head) {
        if let Some((middle, tail)) = rest.split_at_mut_checked(whole) {
            if let [a, b, ..] = middle {
                (*a, *b) = (color, color);
            }
            if !crate::arch::repeat_first_pair(middle) {
                fill_row(middle, color);
            }
            fill_row(start, color);
            fill_row(tail, color);
            return;
        }
    }
    fill_row(pixels, color);
}

/// Sets every pixel of `row` to `color`, four stores per loop iteration: 1.5 instructions a
/// pixel on Cortex-M4 against 3 for `slice::fill`, which LLVM leaves as one store per iteration
/// for 16-bit colours on Thumb.
// One copy for every fill on Cortex-M0 (flash; a call a span).
#[cfg_attr(armv6m, inline(never))]
#[cfg_attr(not(armv6m), inline)]
pub fn fill_row<C: Copy>(row: &mut [C], color: C) {
    let mut row = row;
    if cfg!(rv32) {
        let mut sixteens = row.chunks_exact_mut(16);
        for sixteen in &mut sixteens {
            sixteen.fill(color);
        }
        row = sixteens.into_remainder();
    }
    let mut quads = row.chunks_exact_mut(4);
    for quad in &mut quads {
        quad.fill(color);
    }
    for px in quads.into_remainder() {
        *px = color;
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
