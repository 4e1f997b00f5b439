//! The 5-6-5 span loop (`Rgb565`, `Bgr565`): two pixels a word.
//!
//! Each channel is rounded to a 16-bit lane with its integer bits on top, two neighbouring
//! pixels' lanes share a 32-bit word, and one addition steps both; one mask and one shift place a
//! channel of both pixels at once. Every [`PACKED_RUN`] pixels the lanes restart from the exact
//! [`STEP_BITS`] values. Cortex-M0 runs the same arithmetic in Thumb-1 assembly
//! ([`arch::thumbv6m`]), x86-64 computes tiny triangles' rows of eight pixels in SSE2, and
//! `SpanColors` (so `Drawable::draw`) steps the same lanes one pixel at a time ([`span_state`],
//! [`state_color`], [`next_state`]): every path gives the same colours.

use embedded_graphics::pixelcolor::raw::{RawData, RawU16};

use super::dither::{bayer_offset, bayer_pair, DITHER_RUN};
use super::{SpanSteps, STEP_BITS};
use crate::arch::{self, LANES};

const F: u32 = STEP_BITS;

/// Pixels stepped from one restart by the 5-6-5 loop. Their channels carry 11, 10 and 11
/// fractional bits, so 128 steps add at most 2⁻⁴ LSB of error.
pub(super) const PACKED_RUN: usize = 128;

/// Spans up to this long skip the packed 5-6-5 loop, whose pair set-up they would not repay, and
/// step the same lanes one pixel at a time (the same pixels). On x86 LLVM vectorises the packed
/// loop and its set-up costs ~150 instructions a span; on Cortex-M the check alone costs more
/// than it saves.
const SHORT_SPAN: Option<usize> = if arch::MCU { None } else { Some(4) };

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
pub(super) fn prepare_565(step: [u32; 3], order: [usize; 3]) -> SpanSteps {
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
pub(super) fn fill_565<C: From<RawU16>>(
    dst: &mut [C],
    start: [u32; 3],
    steps: &SpanSteps,
    order: [usize; 3],
) {
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
    let advance = |value: &mut [u32; 3]| *value = advanced(*value, step, PACKED_RUN as u32);
    // ARMv6-M: the last run (the only one of most spans) outside the loop of runs, in assembly.
    #[cfg(armv6m)]
    {
        let mut rest = dst;
        while rest.len() > PACKED_RUN {
            let (run, tail) = rest.split_at_mut(PACKED_RUN);
            span_565_thumb1(run, value, steps);
            advance(&mut value);
            rest = tail;
        }
        span_565_thumb1(rest, value, steps);
        return;
    }
    #[allow(unreachable_code)]
    for run in dst.chunks_mut(PACKED_RUN) {
        run_565(run, lanes(value), steps);
        advance(&mut value);
    }
}

/// Runs shorter than this take [`dithered_565`]'s definition pixel by pixel (a radial
/// gradient's chords are a few pixels): the packed pairs' set-up costs more than they save.
const SHORT_DITHERED: usize = 4;

/// `[f(a₀, b₀), f(a₁, b₁), f(a₂, b₂)]`: constant indices, so no bounds check is left at any
/// optimisation level (the firmware proves its drawing code panic-free at `s` and `z` too).
#[inline(always)]
fn zip3<A: Copy, B: Copy, R>(a: [A; 3], b: [B; 3], f: impl Fn(A, B) -> R) -> [R; 3] {
    [f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2])]
}

/// The largest value of each lane's channel (raw order: top, middle, bottom).
const LANE_MAX: [i32; 3] = [31, 63, 31];

/// [`GouraudColor::fill_dithered`] for 5-6-5 layouts whose raw value holds channels `order`:
/// pixel `i` of `dst` (pixel `x + i` of row `y`) is its lanes ([`fill_565`]'s, restarted every
/// [`DITHER_RUN`] pixels, so within 2⁻⁶ LSB of the values) plus its Bayer offset, truncated to
/// the channel's range.
///
/// Where the span's values stay within 1/64 LSB of the channels' ranges (a Gouraud triangle's
/// covered pixels always: its values are within 2⁻⁹ LSB of ones inside them), the dithered
/// lanes stay inside their 16 bits, `[0, (max + 1)·2^f)`, and two pixels are packed and
/// stepped as a word, the offsets folded into the steps ([`dithered_run_565`]); otherwise the
/// same definition pixel by pixel with the clamp.
///
/// [`GouraudColor::fill_dithered`]: super::GouraudColor::fill_dithered
#[inline(always)]
pub(super) fn dithered_565<C: From<RawU16>>(
    dst: &mut [C],
    (x, y): (i32, i32),
    start: [u32; 3],
    steps: &SpanSteps,
    order: [usize; 3],
) {
    let pick = |v: [u32; 3]| order.map(|k| v.get(k).copied().unwrap_or(0));
    // The ARMv7-M loop's runs are this long; it takes a whole span whose values at both ends
    // are inside the ranges of `run_stays_inside` (exactly, in 64 bits).
    const { assert!(DITHER_RUN == 32) };
    if dst.len() >= SHORT_DITHERED {
        // The values and steps where they are when the raw order is the channel order (Rgb565).
        let (value, reordered);
        let (value, words) = if matches!(order, [0, 1, 2]) {
            (&start, steps.words())
        } else {
            value = pick(start);
            let [l0, l1, l2] = steps.lane;
            let [d0, d1, d2] = steps.double;
            let [s0, s1, s2] = pick(steps.step);
            reordered = [l0, l1, l2, d0, d1, d2, s0, s1, s2];
            (&value, &reordered)
        };
        #[cfg(armv6m)]
        return dithered_span_thumb1(dst, (x, y), *value, words, steps);
        #[cfg(not(armv6m))]
        {
            let span = arch::DitheredSpan565 {
                value,
                steps: words,
                first: bayer_pair(x, y),
                second: bayer_pair(x.wrapping_add(2), y),
            };
            if arch::dithered_565(dst, &span) {
                return;
            }
        }
    }
    dithered_runs_565(dst, (x, y), pick(start), steps, pick(steps.step));
}

/// [`dithered_565`] on ARMv6-M: the span's runs by the Thumb-1 loop ([`arch::thumbv6m`]'s
/// `dithered_span_565`, [`run_stays_inside`]'s test of each run in it) up to the first run
/// whose values leave the channels' ranges, that run by the clamped definition
/// ([`dithered_pixels_565`]), and the rest by the loop again. `value` and `words` (the
/// `SpanSteps` words) in raw order; a span at an address of 2 mod 4 has the first pixel of
/// each run drawn alone (ARMv6-M stores words at 4-byte aligned addresses only; runs are 32
/// pixels, so every run starts at the same address mod 4).
#[cfg(armv6m)]
#[inline(always)]
#[allow(unsafe_code)]
fn dithered_span_thumb1<C: From<RawU16>>(
    dst: &mut [C],
    (x, y): (i32, i32),
    value: [u32; 3],
    words: &[u32; 9],
    steps: &SpanSteps,
) {
    // 5-6-5 colours are one `u16` (embedded-graphics' `Rgb565(u16)`, `Bgr565(u16)`).
    const { assert!(core::mem::size_of::<C>() == 2 && core::mem::align_of::<C>() == 2) };
    let [.., s0, s1, s2] = *words;
    let aligned = x.wrapping_add(i32::from((dst.as_ptr() as usize) % 4 != 0));
    let mut span = arch::thumbv6m::DitheredSpan565 {
        value,
        steps: words,
        head: bayer_pair(x, y),
        first: bayer_pair(aligned, y),
        second: bayer_pair(aligned.wrapping_add(2), y),
    };
    let (mut rest, mut at) = (dst, x);
    loop {
        // SAFETY: `rest` is `rest.len()` (at least one: the span has at least SHORT_DITHERED
        // pixels, and the loop goes on only with some left) consecutive 16-bit pixels
        // (asserted above).
        let done = unsafe {
            arch::thumbv6m::dithered_span_565(rest.as_mut_ptr().cast(), rest.len(), &mut span)
        };
        at = at.wrapping_add(done as i32);
        // The run after those (if any) leaves the channels' ranges.
        let Some((_, after)) = rest.split_at_mut_checked(done) else {
            return;
        };
        let n = after.len().min(DITHER_RUN);
        let Some((run @ [_, ..], tail)) = after.split_at_mut_checked(n) else {
            return;
        };
        dithered_pixels_565(run, span.value, steps, (at, y));
        span.value = advanced(span.value, [s0, s1, s2], DITHER_RUN as u32);
        if tail.is_empty() {
            return;
        }
        (rest, at) = (tail, at.wrapping_add(DITHER_RUN as i32));
    }
}

/// [`dithered_565`] run by run in Rust (where no assembly loop took the span): `value` and
/// `step` in raw order.
///
/// Out of line on ARMv7-M, where it is the rare case (a span leaving the channels' ranges or
/// under 4 pixels): the common one then calls the assembly loop with a small frame.
#[cfg_attr(not(armv7m), inline(always))]
#[cfg_attr(armv7m, inline(never))]
fn dithered_runs_565<C: From<RawU16>>(
    dst: &mut [C],
    (x, y): (i32, i32),
    mut value: [u32; 3],
    steps: &SpanSteps,
    step: [u32; 3],
) {
    if dst.len() < SHORT_DITHERED {
        // One run.
        dithered_pixels_565(dst, value, steps, (x, y));
        return;
    }
    // A run's pixels are a multiple of 4 (the Bayer matrix's width): every run has the same
    // offsets.
    const { assert!(DITHER_RUN % 4 == 0) };
    let offsets = (bayer_lanes(x, y), bayer_lanes(x.wrapping_add(2), y));
    let mut at = x;
    for run in dst.chunks_mut(DITHER_RUN) {
        if run.len() >= SHORT_DITHERED && run_stays_inside(value, step, run.len()) {
            dithered_run_565(run, lanes(value), steps, offsets);
        } else {
            dithered_pixels_565(run, value, steps, (at, y));
        }
        value = advanced(value, step, DITHER_RUN as u32);
        at = at.wrapping_add(DITHER_RUN as i32);
    }
}

/// The values `value` (raw order) `pixels` pixels on by `step` a pixel, wrapping: where a run
/// restarts.
#[inline(always)]
fn advanced(value: [u32; 3], step: [u32; 3], pixels: u32) -> [u32; 3] {
    zip3(value, step, |v, s| v.wrapping_add(s.wrapping_mul(pixels)))
}

/// Whether the values `value + i·step` (raw order, [`STEP_BITS`] fractional bits, +½ included)
/// of a run's pixels (`i < len`, at most [`DITHER_RUN`]) all lie in `[31/64, max + 33/64)` LSB:
/// checked at both ends (the values are linear in `i`). Then each pixel's lanes, within 2⁻⁶
/// LSB of its values, plus its Bayer offset (within ±15/32) lie in `[0, max + 1)`. In 32-bit
/// arithmetic (no long multiply): steps below 2²⁶ (4 LSB a pixel) so that the last pixel's
/// value is exact modulo 2³² (an end beyond `i32` wraps to a value the unsigned test
/// rejects); a run with a steeper step is not taken as inside (the clamped definition draws
/// it: the same pixels).
#[inline(always)]
fn run_stays_inside(value: [u32; 3], step: [u32; 3], len: usize) -> bool {
    let last = len.saturating_sub(1).min(DITHER_RUN) as i32;
    let low: i32 = 31 << (F - 6);
    let inside = zip3(zip3(value, step, |v, s| (v, s)), LANE_MAX, |(v, s), max| {
        let range = (((i64::from(max) * 64 + 33) << (F - 6)) - i64::from(low)) as u32;
        let (s, first) = (s as i32, v as i32);
        let end = first.wrapping_add(s.wrapping_mul(last));
        (s.wrapping_add(1 << 26) as u32) < 1 << 27
            && (first.wrapping_sub(low) as u32) < range
            && (end.wrapping_sub(low) as u32) < range
    });
    inside[0] && inside[1] && inside[2]
}

/// [`dithered_565`]'s definition pixel by pixel, with the clamp: the lanes of the values
/// `value` (raw order) stepped by the lane steps, as signed integers, plus the Bayer offset,
/// truncated and clamped to each channel's range.
#[inline(never)]
fn dithered_pixels_565<C: From<RawU16>>(
    run: &mut [C],
    value: [u32; 3],
    steps: &SpanSteps,
    (x, y): (i32, i32),
) {
    // Within a run of at most DITHER_RUN pixels the lanes stay below 2²⁴ in magnitude (a lane
    // and its step are below 2¹⁹, from 32-bit values and steps).
    let mut lane = zip3(value, LANE_FRACTION, |v, f| {
        let k = F - f;
        (v as i32).wrapping_add(1 << (k - 1)) >> k
    });
    let limits = zip3(LANE_FRACTION, LANE_MAX, |f, max| (f, ((max + 1) << f) - 1));
    let mut at = x;
    for px in run {
        // The offset with 11 fractional bits; the middle lane's (10) is half of it.
        let offset = bayer_offset(at, y, LANE_FRACTION[0]);
        let field = zip3(lane, limits, |l, (f, top)| {
            let v = l.wrapping_add(offset >> (LANE_FRACTION[0] - f));
            (v.max(0).min(top) >> f) as u32
        });
        *px = raw_565(field[0] << 11 | field[1] << 5 | field[2]);
        for (l, s) in lane.iter_mut().zip(steps.lane) {
            *l = l.wrapping_add(s as i32);
        }
        at = at.wrapping_add(1);
    }
}

/// The Bayer offsets of pixels `(x, y)` and `(x + 1, y)` ([`bayer_pair`]) for each lane (raw
/// order): the top and bottom lanes have 11 fractional bits, the middle one 10 (half the
/// offsets).
#[inline(always)]
fn bayer_lanes(x: i32, y: i32) -> [u32; 3] {
    let pair = bayer_pair(x, y);
    [pair, ((pair as i32) >> 1) as u32, pair]
}

/// A run of [`dithered_565`] (at most [`DITHER_RUN`] pixels) from its first pixel's lanes
/// `lane` (raw order) and the Bayer offsets of its pixels 0-1 and 2-3 ([`bayer_lanes`]),
/// where every dithered lane stays inside its 16 bits. Two
/// streams of words: one holds pixels `4k` and `4k + 1`, the other `4k + 2` and `4k + 3`, each
/// word their lanes plus their Bayer offsets ([`bayer_pair`]: the integer `o₁·2¹⁶ + o₀`, so a
/// negative low offset borrows from the high lane as the sum needs). A stream's offsets are the
/// same at every word, so both step by four pixels' lane steps alone.
#[inline(always)]
fn dithered_run_565<C: From<RawU16>>(
    run: &mut [C],
    lane: [u32; 3],
    steps: &SpanSteps,
    (first, second): ([u32; 3], [u32; 3]),
) {
    let word = zip3(lane, steps.lane, |l, s| {
        (l.wrapping_add(s) << 16).wrapping_add(l)
    });
    let mut low = zip3(word, first, u32::wrapping_add);
    let mut high = zip3(
        zip3(word, steps.double, u32::wrapping_add),
        second,
        u32::wrapping_add,
    );
    let quad = steps.double.map(|d| d.wrapping_mul(2));
    let mut rest = run;
    while let [a, b, c, d, tail @ ..] = rest {
        let (one, two) = (pack_565(low), pack_565(high));
        *a = raw_565(one);
        *b = raw_565(one >> 16);
        *c = raw_565(two);
        *d = raw_565(two >> 16);
        low = zip3(low, quad, u32::wrapping_add);
        high = zip3(high, quad, u32::wrapping_add);
        rest = tail;
    }
    match rest {
        [a, b, c] => {
            let one = pack_565(low);
            *a = raw_565(one);
            *b = raw_565(one >> 16);
            *c = raw_565(pack_565(high));
        }
        [a, b] => {
            let one = pack_565(low);
            *a = raw_565(one);
            *b = raw_565(one >> 16);
        }
        [a] => *a = raw_565(pack_565(low)),
        _ => {}
    }
}

/// The span state of a 5-6-5 layout whose raw value holds channels `order` ([`GouraudColor`]'s
/// `span_state`): the channel values `value` (channel order) rounded to their lanes, raw order,
/// as [`fill_565`] restarts from them.
///
/// [`GouraudColor`]: super::GouraudColor
#[inline(always)]
pub(super) fn span_state(value: [u32; 3], order: [usize; 3]) -> [u32; 3] {
    lanes(order.map(|k| value.get(k).copied().unwrap_or(0)))
}

/// The colour of the lanes `lane` (raw order): the low 16 bits of each, as in the pair words of
/// [`run_565`].
#[inline(always)]
pub(super) fn state_color<C: From<RawU16>>(lane: [u32; 3]) -> C {
    raw_565(pack_565(lane))
}

/// The lanes one pixel to the right: each plus its lane step, wrapping (modulo 2¹⁶ in the bits
/// [`state_color`] reads, as in the pair words).
#[inline(always)]
pub(super) fn next_state(lane: [u32; 3], steps: &SpanSteps) -> [u32; 3] {
    core::array::from_fn(|i| lane[i].wrapping_add(steps.lane[i]))
}

/// Channel values (raw order, [`STEP_BITS`] fractional bits) rounded to their 5-6-5 lanes.
#[inline(always)]
fn lanes(value: [u32; 3]) -> [u32; 3] {
    // Values are below 2³⁰ (at most 6 integer bits): the unsigned rounding cannot overflow.
    let mut fraction = LANE_FRACTION.into_iter();
    value.map(|v| {
        let k = F - fraction.next().unwrap_or(0);
        v.wrapping_add(1 << (k - 1)) >> k
    })
}

/// [`GouraudColor::fill_masked_row`] for 5-6-5 layouts whose raw value holds channels `order`:
/// every pixel's lanes are those of [`fill_565`] for the run from `first` (the run's first lanes
/// stepped by the lane steps, modulo 2¹⁶ as in its pair words), and the write keeps the pixels
/// outside the run.
#[inline(always)]
pub(super) fn masked_row_565<C: Copy + From<RawU16> + Into<RawU16>>(
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
    #[cfg(sse2_rows)]
    return arch::x86_64::row_565(start, first, lane);
    #[cfg(not(sse2_rows))]
    return row_565_portable(start, first, lane);
}

/// [`row_565`] in portable code.
#[cfg_attr(all(sse2_rows, not(test)), allow(dead_code))]
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

/// [`run_565`] of `run` (at most [`PACKED_RUN`] pixels) from the channel values `value` (raw
/// order, [`STEP_BITS`] fractional bits), in Thumb-1 assembly ([`arch::thumbv6m`]).
#[cfg(armv6m)]
#[inline(always)]
#[allow(unsafe_code)]
fn span_565_thumb1<C: From<RawU16>>(run: &mut [C], value: [u32; 3], steps: &SpanSteps) {
    // 5-6-5 colours are one `u16` (embedded-graphics' `Rgb565(u16)`, `Bgr565(u16)`).
    const { assert!(core::mem::size_of::<C>() == 2 && core::mem::align_of::<C>() == 2) };
    // SAFETY: `run` is `run.len()` consecutive, 2-byte aligned 16-bit pixels; `SpanSteps` is
    // `repr(C)`, nine `u32`s starting with the six of the lane and double steps.
    unsafe {
        arch::thumbv6m::span_565(
            run.as_mut_ptr().cast(),
            run.len(),
            &value,
            core::ptr::from_ref(steps).cast(),
        );
    }
}

#[cfg(test)]
mod tests {
    use embedded_graphics::pixelcolor::{Bgr565, Rgb565, RgbColor};

    use super::*;
    use crate::color::fill_by_state;
    use crate::GouraudColor;

    /// The 5-6-5 loop stays within 2⁻⁴ LSB of plain [`STEP_BITS`]-fractional-bit stepping.
    #[test]
    fn packed_565_matches_plain_stepping() {
        let mut rng = crate::rng::Rng(0x2545_f491_4f6c_dd1d_u64);
        let mut out = [Rgb565::BLACK; 700];
        let mut bgr = [Bgr565::BLACK; 700];
        for _ in 0..2000 {
            let n = 1 + rng.below(700) as usize;
            let mut start = [0u32; 3];
            let mut step = [0u32; 3];
            for k in 0..3 {
                let max = f64::from(Rgb565::MAX[k]);
                let (c0, c1) = (
                    rng.below(1 << 20) as f64 / f64::from(1 << 20) * max,
                    rng.below(1 << 20) as f64 / f64::from(1 << 20) * max,
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
            // And they are the colours the format's span state defines (which `SpanColors`
            // hands out one by one).
            let mut by_state = [Rgb565::BLACK; 700];
            fill_by_state(&mut by_state[..n], start, &steps);
            assert_eq!(by_state[..n], out[..n]);
            let mut by_state = [Bgr565::BLACK; 700];
            fill_by_state(&mut by_state[..n], start, &Bgr565::prepare_steps(step));
            assert_eq!(by_state[..n], bgr[..n]);
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

    /// The words the assembly loops read from `SpanSteps` are its lane steps, double steps and
    /// steps, in that order.
    #[test]
    fn span_steps_words_are_its_fields() {
        for order in [[0, 1, 2], [2, 1, 0]] {
            let steps = prepare_565([0x0123_4567, 0xFEDC_BA98, 0x0F0F_0F0F], order);
            let mut want = [0; 9];
            want[..3].copy_from_slice(&steps.lane);
            want[3..6].copy_from_slice(&steps.double);
            want[6..].copy_from_slice(&steps.step);
            assert_eq!(steps.words(), &want);
        }
    }

    /// The dithered 5-6-5 loop: its packed pairs are the per-pixel definition with the clamp
    /// (`dithered_pixels_565`) wherever the span stays inside the channels' ranges, in both
    /// channel orders, at every alignment of the Bayer columns and rows; and each channel is
    /// the floor or the ceiling of the exact stepped value within 2⁻⁶ LSB (Bayer threshold
    /// `(2b + 1)/32` computed here, independently). Values outside the ranges take the clamped
    /// definition: inside the channels' ranges, no panic.
    #[test]
    fn dithered_565_is_its_definition() {
        const BAYER: [[u32; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
        let mut rng = crate::rng::Rng(0x9e37_79b9_7f4a_7c15_u64);
        let one = f64::from(1u32 << STEP_BITS);
        for case in 0..20_000 {
            let n = 1 + rng.below(if case % 4 == 0 { 300 } else { 40 }) as usize;
            let (x, y) = (rng.next() as i32, rng.next() as i32);
            let mut start = [0u32; 3];
            let mut step = [0u32; 3];
            for k in 0..3 {
                let max = f64::from(Rgb565::MAX[k]);
                let mut end = || match rng.below(6) {
                    0 => 0.0,
                    1 => max,
                    _ => rng.below(1 << 20) as f64 / f64::from(1 << 20) * max,
                };
                let (c0, c1) = (end(), end());
                let s = if n > 1 {
                    (c1 - c0) / (n - 1) as f64
                } else {
                    0.0
                };
                start[k] = ((c0 + 0.5) * one) as u32;
                // Steps rounded towards the start's value: the last pixel stays in range.
                step[k] = ((s * one).trunc() as i32) as u32;
            }
            let steps = Rgb565::prepare_steps(step);
            let mut packed = [Rgb565::BLACK; 300];
            let mut bgr = [Bgr565::BLACK; 300];
            Rgb565::fill_dithered(&mut packed[..n], x, y, start, &steps);
            Bgr565::fill_dithered(&mut bgr[..n], x, y, start, &Bgr565::prepare_steps(step));
            let mut pixels = [Rgb565::BLACK; 300];
            let mut value = start;
            let mut at = x;
            for run in pixels[..n].chunks_mut(DITHER_RUN) {
                dithered_pixels_565(run, value, &steps, (at, y));
                for (v, s) in value.iter_mut().zip(step) {
                    *v = v.wrapping_add(s.wrapping_mul(DITHER_RUN as u32));
                }
                at = at.wrapping_add(DITHER_RUN as i32);
            }
            assert_eq!(
                packed[..n],
                pixels[..n],
                "case {case}: {start:?} {step:?} at ({x}, {y})"
            );
            for (i, (px, b)) in packed[..n].iter().zip(&bgr[..n]).enumerate() {
                let threshold = f64::from(
                    2 * BAYER[(y & 3) as usize][(x.wrapping_add(i as i32) & 3) as usize] + 1,
                ) / 32.0;
                let (b, bc) = (b.channels(), [b.b(), b.g(), b.r()]);
                assert_eq!(bc, [b[2], b[1], b[0]]);
                for (k, got) in px.channels().into_iter().enumerate() {
                    let exact =
                        (f64::from(start[k]) + f64::from(step[k] as i32) * i as f64) / one - 0.5;
                    let lo = (exact + threshold - 1.0 / 64.0).floor();
                    let hi = (exact + threshold + 1.0 / 64.0).floor();
                    let g = f64::from(got);
                    assert!(
                        lo <= g && g <= hi,
                        "case {case} pixel {i} channel {k}: {g} vs {exact}"
                    );
                    assert_eq!(got, b[k], "case {case} pixel {i}: orders differ");
                }
            }
        }
        // Values anywhere (nearly never inside the ranges): the clamped definition, which the
        // packed pairs equal where they are.
        for _ in 0..5_000 {
            let n = 1 + rng.below(80) as usize;
            let start = [rng.next() as u32, rng.next() as u32, rng.next() as u32];
            let step = [rng.next() as u32, rng.next() as u32, rng.next() as u32];
            let steps = Rgb565::prepare_steps(step);
            let mut packed = [Rgb565::BLACK; 80];
            Rgb565::fill_dithered(&mut packed[..n], 3, 5, start, &steps);
            let mut pixels = [Rgb565::BLACK; 80];
            let mut value = start;
            for (k, run) in pixels[..n].chunks_mut(DITHER_RUN).enumerate() {
                dithered_pixels_565(run, value, &steps, (3 + (k * DITHER_RUN) as i32, 5));
                for (v, s) in value.iter_mut().zip(step) {
                    *v = v.wrapping_add(s.wrapping_mul(DITHER_RUN as u32));
                }
            }
            assert_eq!(packed[..n], pixels[..n]);
        }
    }

    /// The SSE2 row of eight 5-6-5 pixels is the portable one (and so the span loop's lanes,
    /// which the tiny tests check), over values, steps and first pixels of every range.
    #[cfg(sse2_rows)]
    #[test]
    fn sse2_rows_are_the_portable_rows() {
        let mut rng = crate::rng::Rng(0x0005_5e20_0001_0001);
        for _ in 0..100_000 {
            let (v, s) = (rng.next(), rng.next());
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
            let first = rng.below(9) as u32;
            assert_eq!(
                arch::x86_64::row_565(start, first, &lane),
                row_565_portable(start, first, &lane),
                "{start:?} {lane:?} {first}"
            );
        }
    }
}
