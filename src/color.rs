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

use embedded_graphics::pixelcolor::raw::{RawData, RawU16};
use embedded_graphics::pixelcolor::{
    Bgr555, Bgr565, Bgr666, Bgr888, BinaryColor, Gray2, Gray4, Gray8, GrayColor, Rgb555, Rgb565,
    Rgb666, Rgb888, RgbColor,
};
use embedded_graphics::prelude::PixelColor;

use crate::interpolation::AttributePlane;
use crate::tiny::LANES;

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

    /// [`fill_span`](Self::fill_span) with steps from [`prepare_steps`](Self::prepare_steps).
    /// Formats may override both with a faster packed loop that keeps the same accuracy.
    #[inline]
    fn fill_prepared(dst: &mut [Self], start: [u32; 3], steps: &SpanSteps) {
        let (mut v, step) = (start, steps.step);
        for px in dst {
            *px = Self::from_stepped(v);
            v[0] = v[0].wrapping_add(step[0]);
            if Self::CHANNELS > 1 {
                v[1] = v[1].wrapping_add(step[1]);
                v[2] = v[2].wrapping_add(step[2]);
            }
        }
    }

    /// Fills the covered pixels of one row of a tiny triangle's box (see
    /// [`tiny`](crate::tiny)): `covered[i]` is `-1` for covered pixels, which form one run from
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
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C)] // The ARMv6-M span loop reads the fields at fixed offsets.
pub struct SpanSteps {
    /// The steps, [`STEP_BITS`] fractional bits, in channel order.
    step: [u32; 3],
    /// 5-6-5 formats: each channel's step rounded to its lane, in raw order (see [`fill_565`]) …
    lane: [u32; 3],
    /// … and two of them in both halves of a word (see [`run_565`]).
    double: [u32; 3],
}

impl SpanSteps {
    /// The steps, [`STEP_BITS`] fractional bits, in channel order.
    pub fn step(&self) -> [u32; 3] {
        self.step
    }
}

/// `GouraudColor` for RGB formats; `order = [top, 1, bottom]` selects the 5-6-5 span loop with
/// that channel order in the raw value.
macro_rules! rgb_color {
    ($t:ty $(, order = $order:expr)?) => {
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
                fn prepare_steps(step: [u32; 3]) -> SpanSteps {
                    prepare_565(step, $order)
                }
                // Out of line on Cortex-M3/M4/M7: the loop then has the registers to itself.
                // Inlined on ARMv6-M (the loop is an assembly function and this wrapper is
                // small) and on hosts (x86: 1,000 px² Gouraud 7.9× → 10.3× e-g in one run).
                #[cfg_attr(not(all(target_arch = "arm", target_has_atomic = "32")), inline(always))]
                #[cfg_attr(all(target_arch = "arm", target_has_atomic = "32"), inline(never))]
                fn fill_prepared(dst: &mut [Self], start: [u32; 3], steps: &SpanSteps) {
                    fill_565(dst, start, steps, $order)
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

/// Pixels stepped from one restart by the 5-6-5 loop. Their channels carry 11, 10 and 11
/// fractional bits, so 128 steps add at most 2⁻⁴ LSB of error.
const PACKED_RUN: usize = 128;

/// Spans up to this long skip the packed 5-6-5 loop, whose pair set-up they would not repay, and
/// step the same lanes one pixel at a time (the same pixels). On x86 LLVM vectorises the packed
/// loop and its set-up costs ~150 instructions a span; on Cortex-M the check alone costs more
/// than it saves.
const SHORT_SPAN: Option<usize> = if cfg!(target_arch = "arm") {
    None
} else {
    Some(4)
};

/// Fractional bits of the 5-6-5 loop's channels in raw order (top, middle, bottom): each channel
/// fills a 16-bit lane with its integer bits on top.
const LANE_FRACTION: [u32; 3] = [11, 10, 11];

/// `v >> k`, rounded to nearest, for a signed step.
#[inline(always)]
fn round_shift(v: u32, k: u32) -> u32 {
    ((v as i32).wrapping_add(1 << (k - 1)) >> k) as u32
}

/// The steps of a 5-6-5 format whose raw value holds channels `order` (top, middle, bottom).
#[inline]
fn prepare_565(step: [u32; 3], order: [usize; 3]) -> SpanSteps {
    let lane: [u32; 3] = core::array::from_fn(|i| {
        let s = order
            .get(i)
            .and_then(|&k| step.get(k))
            .copied()
            .unwrap_or(0);
        round_shift(s, F - LANE_FRACTION[i])
    });
    SpanSteps {
        step,
        lane,
        double: lane.map(|s| s.wrapping_mul(2).wrapping_mul(0x1_0001)),
    }
}

/// Gouraud loop for 5-6-5 layouts whose raw value holds channels `order`: the first in bits
/// 11..16, the second in bits 5..11, the third in bits 0..5.
///
/// Every [`PACKED_RUN`] pixels each channel restarts from its [`STEP_BITS`] value rounded to a
/// 16-bit lane ([`LANE_FRACTION`]) and is stepped by its step rounded once to the lane. At covered
/// pixels a lane value lies in `[0, 2¹⁶)` (the channel's range plus the +½ offset and an error of
/// at most 2⁻⁴), so lanes packed side by side ([`run_565`]) never carry into each other.
#[inline(always)]
fn fill_565<C: From<RawU16>>(dst: &mut [C], start: [u32; 3], steps: &SpanSteps, order: [usize; 3]) {
    let pick = |v: [u32; 3]| order.map(|k| v.get(k).copied().unwrap_or(0));
    let (mut value, step) = (pick(start), pick(steps.step));

    if SHORT_SPAN.is_some_and(|short| dst.len() <= short) {
        // The packed loop's lanes one pixel at a time (the same pixels): its set-up of the
        // pair words costs more than a few pixels.
        let mut lane = lanes(value);
        for px in dst {
            *px = raw_565(pack_565(lane));
            for (l, s) in lane.iter_mut().zip(steps.lane) {
                *l = l.wrapping_add(s);
            }
        }
        return;
    }
    let advance = |value: &mut [u32; 3]| {
        for (v, s) in value.iter_mut().zip(step) {
            *v = v.wrapping_add(s.wrapping_mul(PACKED_RUN as u32));
        }
    };
    // ARMv6-M: the last run (the only one of most spans) outside the loop of runs, in assembly.
    #[cfg(all(target_arch = "arm", not(target_has_atomic = "32")))]
    {
        let mut rest = dst;
        while rest.len() > PACKED_RUN {
            let (run, tail) = rest.split_at_mut(PACKED_RUN);
            thumb1::span_565(run, value, steps);
            advance(&mut value);
            rest = tail;
        }
        thumb1::span_565(rest, value, steps);
        return;
    }
    #[allow(unreachable_code)]
    for run in dst.chunks_mut(PACKED_RUN) {
        run_565(run, lanes(value), steps);
        advance(&mut value);
    }
}

/// Channel values (raw order, [`STEP_BITS`] fractional bits) rounded to their 5-6-5 lanes.
#[inline(always)]
fn lanes(value: [u32; 3]) -> [u32; 3] {
    // Values are below 2³⁰ (at most 6 integer bits): the unsigned rounding cannot overflow.
    core::array::from_fn(|i| {
        let k = F - LANE_FRACTION[i];
        value[i].wrapping_add(1 << (k - 1)) >> k
    })
}

/// [`GouraudColor::fill_masked_row`] for 5-6-5 layouts whose raw value holds channels `order`:
/// every pixel's lanes are those of [`fill_565`] for the run from `first` (the run's first lanes
/// stepped by the lane steps, modulo 2¹⁶ as in its pair words), and the write keeps the pixels
/// outside the run.
#[inline(always)]
fn masked_row_565<C: Copy + From<RawU16> + Into<RawU16>>(
    row: &mut [C; LANES],
    covered: [i16; LANES],
    first: u32,
    start: [u32; 3],
    steps: &SpanSteps,
    order: [usize; 3],
) {
    let raw = row_565(
        order.map(|k| start.get(k).copied().unwrap_or(0)),
        first,
        &steps.lane,
    );
    for ((px, &mask), new) in row.iter_mut().zip(&covered).zip(raw) {
        let old = (*px).into().into_inner();
        let mask = mask as u16;
        *px = C::from(RawU16::new((new & mask) | (old & !mask)));
    }
}

/// The raw 5-6-5 values of a row's eight pixels for the run from `first` (see
/// [`masked_row_565`]); `start` and `lane` in raw order. SSE2 on x86-64.
#[inline(always)]
fn row_565(start: [u32; 3], first: u32, lane: &[u32; 3]) -> [u16; LANES] {
    #[cfg(target_arch = "x86_64")]
    return row_565_sse2(start, first, lane);
    #[cfg(not(target_arch = "x86_64"))]
    return row_565_portable(start, first, lane);
}

/// [`row_565`] in portable code.
#[cfg_attr(all(target_arch = "x86_64", not(test)), allow(dead_code))]
#[inline(always)]
fn row_565_portable(start: [u32; 3], first: u32, lane: &[u32; 3]) -> [u16; LANES] {
    let first_lanes = lanes(start);
    // Lane values at pixel 0 of the row: pixel i adds i steps.
    let at_zero: [u16; 3] =
        core::array::from_fn(|c| first_lanes[c].wrapping_sub(lane[c].wrapping_mul(first)) as u16);
    core::array::from_fn(|i| {
        let l: [u16; 3] = core::array::from_fn(|c| {
            at_zero[c].wrapping_add((lane[c] as u16).wrapping_mul(i as u16))
        });
        pack_565(l.map(u32::from)) as u16
    })
}

/// [`row_565`] in SSE2: the three channels' rounding and first-pixel offset in one register (the
/// lanes only matter modulo 2¹⁶), then each channel's eight lanes.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn row_565_sse2(start: [u32; 3], first: u32, lane: &[u32; 3]) -> [u16; LANES] {
    use core::arch::x86_64::*;
    let mut raw = [0u16; LANES];
    // SAFETY: SSE2 is part of the x86-64 baseline; the one store writes the 16 bytes of `raw`.
    unsafe {
        let i32s = |v: [u32; 3]| _mm_setr_epi32(v[0] as i32, v[1] as i32, v[2] as i32, 0);
        // Lanes: (v + 2^12) >> 13 for the top and bottom channels, (v + 2^13) >> 14 for the
        // middle one (see `lanes`).
        let t = _mm_add_epi32(i32s(start), _mm_setr_epi32(1 << 12, 1 << 13, 1 << 12, 0));
        let (t13, t14) = (_mm_srli_epi32::<13>(t), _mm_srli_epi32::<14>(t));
        let middle = _mm_setr_epi32(0, -1, 0, 0);
        let lanes = _mm_or_si128(_mm_andnot_si128(middle, t13), _mm_and_si128(middle, t14));
        // Minus `first` steps, in the low 16 bits of each 32-bit lane.
        let steps = i32s(*lane);
        let at_zero = _mm_sub_epi16(lanes, _mm_mullo_epi16(steps, _mm_set1_epi16(first as i16)));
        // Each channel's value at pixel 0 in all eight lanes, plus i steps at pixel i.
        let index = _mm_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7);
        let top = _mm_unpacklo_epi64(
            _mm_shufflelo_epi16::<0x00>(at_zero),
            _mm_shufflelo_epi16::<0x00>(at_zero),
        );
        let mid = _mm_shufflelo_epi16::<0xAA>(at_zero);
        let mid = _mm_unpacklo_epi64(mid, mid);
        let bot = _mm_shufflehi_epi16::<0x00>(at_zero);
        let bot = _mm_unpackhi_epi64(bot, bot);
        let step = |k: usize| _mm_mullo_epi16(index, _mm_set1_epi16(lane[k] as i16));
        let top = _mm_add_epi16(top, step(0));
        let mid = _mm_add_epi16(mid, step(1));
        let bot = _mm_add_epi16(bot, step(2));
        let packed = _mm_or_si128(
            _mm_or_si128(
                _mm_and_si128(top, _mm_set1_epi16(0xF800u16 as i16)),
                _mm_and_si128(_mm_srli_epi16::<5>(mid), _mm_set1_epi16(0x07E0)),
            ),
            _mm_srli_epi16::<11>(bot),
        );
        _mm_storeu_si128(raw.as_mut_ptr().cast(), packed);
    }
    raw
}

/// The raw 5-6-5 values of the lanes `w` (top, middle, bottom channel): two pixels when each word
/// holds two lanes ([`run_565`]), one in the low half when it holds one.
#[inline(always)]
fn pack_565(w: [u32; 3]) -> u32 {
    (w[0] & 0xF800_F800) | ((w[1] >> 5) & 0x07E0_07E0) | ((w[2] >> 11) & 0x001F_001F)
}

/// The 5-6-5 colour of a raw value.
#[inline(always)]
fn raw_565<C: From<RawU16>>(raw: u32) -> C {
    C::from(RawU16::new(raw as u16))
}

/// One run of [`fill_565`], two pixels per word: each channel is one 32-bit word holding the
/// lanes of two neighbouring pixels (the right one in the upper half), stepped two pixels at a
/// time by one addition. With the integer bits on top of each lane, one mask (and one shift)
/// places a channel of both pixels at once: two pixels cost three masks, two ORs, three additions
/// and their stores.
#[inline(always)]
fn run_565<C: From<RawU16>>(run: &mut [C], lane: [u32; 3], steps: &SpanSteps) {
    // Lanes (left pixel, right pixel) of each channel; `double` steps both by two pixels.
    let mut word: [u32; 3] =
        core::array::from_fn(|i| (lane[i].wrapping_add(steps.lane[i]) << 16).wrapping_add(lane[i]));
    let double = steps.double;
    // Slice patterns rather than `chunks_exact_mut`: LLVM then does not unroll the loop on
    // Cortex-M, which would cost more set-up per span than it saves on spans of a few dozen pixels.
    // (On x86 it still vectorizes it.)
    let mut rest = run;
    while let [a, b, tail @ ..] = rest {
        let both = pack_565(word);
        *a = raw_565(both);
        *b = raw_565(both >> 16);
        for (w, d) in word.iter_mut().zip(double) {
            *w = w.wrapping_add(d);
        }
        rest = tail;
    }
    if let [last] = rest {
        *last = raw_565(pack_565(word));
    }
}

/// One run of [`fill_565`] (lanes, pair words, the pair loop of [`run_565`] and a last odd
/// pixel) in Thumb-1 assembly for ARMv6-M (Cortex-M0/M0+), where LLVM keeps masks, steps and
/// words in memory (26 instructions a pair, ~70 a span around them): here the three channel
/// words, two masks, the pointer and two temporaries stay in the low registers and the steps, the
/// end pointer and the odd-pixel flag in high ones: 19 instructions a pair and ~60 a span. The
/// host checks the same arithmetic through the portable loop; CI checks that the Cortex-M0
/// firmware's scene has the host's checksum.
#[cfg(all(target_arch = "arm", not(target_has_atomic = "32")))]
mod thumb1 {
    use embedded_graphics::pixelcolor::raw::RawU16;

    use super::SpanSteps;

    /// r4 = two pixels from the channel words r1 (top), r3 (middle), r2 (bottom) with the masks
    /// r6 = 0xF800F800 and r7 = 0xFC00FC00: top & r6 | (middle & r7) >> 5 | (bottom & r6) >> 11
    /// (r5 is clobbered). Used by the pair loop and for the odd last pixel.
    macro_rules! pack_565 {
        () => {
            "mov r4, r1\nands r4, r6\nmov r5, r2\nands r5, r6\nlsrs r5, r5, #11\norrs r4, r5\n\
             mov r5, r3\nands r5, r7\nlsrs r5, r5, #5\norrs r4, r5"
        };
    }

    core::arch::global_asm!(
        ".section .text.embedded_raster_565_span_v6m,\"ax\",%progbits",
        ".syntax unified",
        ".thumb",
        ".p2align 2",
        ".global embedded_raster_565_span_v6m",
        ".hidden embedded_raster_565_span_v6m",
        ".type embedded_raster_565_span_v6m,%function",
        ".thumb_func",
        // r0 = pixels (2-byte aligned), r1 = pixel count, r2 = channel values (raw order,
        // STEP_BITS fractional bits), r3 = SpanSteps (step +0, lane +12, double +24).
        "embedded_raster_565_span_v6m:",
        "push {{r4-r7, lr}}",
        "mov r4, r8",
        "mov r5, r9",
        "mov r6, r10",
        "push {{r4-r6}}",
        // lr = odd pixel count (the return address is on the stack), r12 = end of the pairs.
        "movs r4, #1",
        "ands r4, r1",
        "mov lr, r4",
        "lsrs r1, r1, #1",
        "lsls r1, r1, #2",
        "adds r1, r0, r1",
        "mov r12, r1",
        // r8..r10 = steps of two pixels; r4..r6 = steps of one (lanes).
        "ldr r4, [r3, #24]",
        "mov r8, r4",
        "ldr r4, [r3, #28]",
        "mov r9, r4",
        "ldr r4, [r3, #32]",
        "mov r10, r4",
        "ldr r4, [r3, #12]",
        "ldr r5, [r3, #16]",
        "ldr r6, [r3, #20]",
        // Lanes: top and bottom (v + 2^12) >> 13, middle (v + 2^13) >> 14, in r1, r3, r2.
        "ldr r1, [r2]",
        "ldr r3, [r2, #4]",
        "ldr r2, [r2, #8]",
        "movs r7, #1",
        "lsls r7, r7, #12",
        "adds r1, r1, r7",
        "lsrs r1, r1, #13",
        "adds r2, r2, r7",
        "lsrs r2, r2, #13",
        "lsls r7, r7, #1",
        "adds r3, r3, r7",
        "lsrs r3, r3, #14",
        // Words: (lane + step) << 16 | lane.
        "adds r4, r4, r1",
        "lsls r4, r4, #16",
        "adds r1, r1, r4",
        "adds r5, r5, r3",
        "lsls r5, r5, #16",
        "adds r3, r3, r5",
        "adds r6, r6, r2",
        "lsls r6, r6, #16",
        "adds r2, r2, r6",
        "ldr r6, 4f",
        "ldr r7, 5f",
        "cmp r0, r12",
        "beq 3f",
        // One pair.
        "2:",
        pack_565!(),
        "strh r4, [r0]",
        "lsrs r4, r4, #16",
        "strh r4, [r0, #2]",
        "add r1, r8",
        "add r3, r9",
        "add r2, r10",
        "adds r0, #4",
        "cmp r0, r12",
        "bne 2b",
        // The odd last pixel: the left lanes.
        "3:",
        "mov r4, lr",
        "cmp r4, #0",
        "beq 6f",
        pack_565!(),
        "strh r4, [r0]",
        "6:",
        "pop {{r4-r6}}",
        "mov r8, r4",
        "mov r9, r5",
        "mov r10, r6",
        "pop {{r4-r7, pc}}",
        ".p2align 2",
        "4: .word 0xF800F800",
        "5: .word 0xFC00FC00",
        ".size embedded_raster_565_span_v6m, . - embedded_raster_565_span_v6m",
    );

    extern "C" {
        fn embedded_raster_565_span_v6m(
            pixels: *mut u16,
            len: usize,
            values: *const [u32; 3],
            steps: *const SpanSteps,
        );
    }

    /// [`run_565`](super::run_565) of `run` (at most `PACKED_RUN` pixels) from the channel
    /// values `value` (raw order, [`STEP_BITS`](super::STEP_BITS) fractional bits).
    #[inline(always)]
    pub(super) fn span_565<C: From<RawU16>>(run: &mut [C], value: [u32; 3], steps: &SpanSteps) {
        // 5-6-5 colours are one `u16` (embedded-graphics' `Rgb565(u16)`, `Bgr565(u16)`).
        const { assert!(core::mem::size_of::<C>() == 2 && core::mem::align_of::<C>() == 2) };
        // SAFETY: the function writes exactly `run.len()` consecutive 16-bit pixels from `run`'s
        // start (2-byte aligned), reads three words at `value` and `SpanSteps` (`repr(C)`, nine
        // words), and saves and restores every register the AAPCS asks it to.
        unsafe {
            embedded_raster_565_span_v6m(run.as_mut_ptr().cast(), run.len(), &value, steps);
        }
    }
}

rgb_color!(Rgb565, order = [0, 1, 2]);
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

    /// The 5-6-5 loop stays within 2⁻⁴ LSB of plain [`STEP_BITS`]-fractional-bit stepping.
    #[test]
    fn packed_565_matches_plain_stepping() {
        let mut next = crate::xorshift(0x2545_f491_4f6c_dd1d_u64);
        let mut rnd = move |n: u64| next() % n;
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
            // The span is runs of the packed loop, each restarted from the exactly stepped
            // values every PACKED_RUN pixels.
            let mut other = [Rgb565::BLACK; 700];
            let steps = Rgb565::prepare_steps(step);
            let mut value = start;
            for run in other[..n].chunks_mut(PACKED_RUN) {
                run_565(run, lanes(value), &steps);
                for (v, s) in value.iter_mut().zip(step) {
                    *v = v.wrapping_add(s.wrapping_mul(PACKED_RUN as u32));
                }
            }
            assert_eq!(other[..n], out[..n]);
            // Short spans step the packed loop's lanes one pixel at a time: the same pixels.
            let short = n.min(6);
            run_565(&mut other[..short], lanes(start), &steps);
            fill_565(&mut out[..short], start, &steps, [0, 1, 2]);
            assert_eq!(other[..short], out[..short]);
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

    /// The SSE2 row of eight 5-6-5 pixels is the portable one (and so the span loop's lanes,
    /// which the tiny tests check), over values, steps and first pixels of every range.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn sse2_rows_are_the_portable_rows() {
        let mut next = crate::xorshift(0x0005_5e20_0001_0001);
        for _ in 0..100_000 {
            let (v, s) = (next(), next());
            let start = [
                v as u32 >> (v >> 59),
                (v >> 20) as u32,
                (v >> 36) as u32 >> 2,
            ];
            let lane = [
                s as u32 >> (s >> 60),
                (s >> 16) as u32,
                (s >> 32) as u32 >> (s >> 59),
            ];
            let first = (next() % 9) as u32;
            assert_eq!(
                row_565_sse2(start, first, &lane),
                row_565_portable(start, first, &lane),
                "{start:?} {lane:?} {first}"
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
