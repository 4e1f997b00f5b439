//! Linear and radial gradients: paints whose colour is a function of one parameter `t` of the
//! pixel's centre, through a list of colour stops.
//!
//! # The gradient, exactly
//!
//! A gradient has `N` [`Stop`]s, each a position in `0..=1` ([`STOP_ONE`] = 1) and a colour.
//! Positions are taken in the order given and made non-decreasing the way CSS does it: a stop's
//! effective position is the largest of its own (clamped to `0..=1`) and those before it. At a
//! pixel whose parameter is `t`:
//!
//! * `t` below the first effective position: the first stop's colour (pad);
//! * `t` at or beyond the last: the last stop's colour (pad);
//! * otherwise `t` lies in exactly one segment `e[k] ≤ t < e[k+1]` of two stops with distinct
//!   positions, and each channel is `c[k] + (c[k+1] − c[k])·(t − e[k])/(e[k+1] − e[k])`,
//!   interpolated in the colour format's own channel depth ([`GouraudColor`]).
//!
//! So coincident stops make a hard edge (the later stop's colour from its position on), stops out
//! of order are raised to the position of the stop before them, and a gradient without stops
//! paints black (channels 0). A zero-length gradient (start = end, radius 0) paints the last
//! stop's colour everywhere, as CSS does.
//!
//! Each pixel gets its channels rounded to nearest from within 1/32 LSB (linear) or 1/4 LSB
//! (radial) of that exact value, so within 1 LSB of it (the floor or the ceiling), given the
//! conditions of each gradient's documentation; dithered, the floor or the ceiling of a value
//! that near the exact one (on 5-6-5, within a further 2⁻⁶ LSB: the packed lanes of
//! [`GouraudColor::fill_dithered`]). Which segment a pixel falls in is decided exactly, in integers: a pixel on a
//! stop's line or circle gets the later segment's colour.
//!
//! # Drawing
//!
//! A segment's channels are affine along a row for a linear gradient: each run of pixels in one
//! segment is one Gouraud span ([`GouraudColor::fill_prepared`], the format's own packed loop),
//! found by one exact classification and a multiply by a reciprocal (no division on the drawing
//! path). A radial gradient's distance is approximated along the row by chords between pixels
//! where it is computed exactly (an integer square root), each chord short enough to keep the
//! error under the bound, and each chord is again a Gouraud span.

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::Paint;
use crate::color::{fill_row, restart_value, DitheredColors, GouraudColor, SpanSteps, STEP_BITS};
use crate::fixed_point::{Coord, ToCoord};

/// The position 1 of a [`Stop`]: positions are in 1/65536.
pub const STOP_ONE: u32 = 1 << 16;

/// Pixels painted from one start: the chunks of a row restart from exact values, so stepping
/// errors never add up over more than this many pixels.
const CHUNK: usize = 1 << 15;

/// Bits of the sub-pixel coordinates (`Coord`: 1/256 pixel).
const SUB: u32 = 8;

/// A colour stop of a gradient: a position in `0..=1` ([`STOP_ONE`] is 1) and a colour.
///
/// # Examples
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use embedded_graphics::prelude::*;
/// use embedded_raster::paint::{Stop, STOP_ONE};
///
/// let a = Stop::new(STOP_ONE / 2, Rgb565::RED);
/// assert_eq!(a, Stop::at(0.5, Rgb565::RED));
/// assert_eq!(Stop::at(2.0, Rgb565::RED).position, STOP_ONE); // clamped
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stop<C> {
    /// Position in 1/65536 of the gradient; values beyond [`STOP_ONE`] count as 1.
    pub position: u32,
    /// The colour at that position.
    pub color: C,
}

impl<C> Stop<C> {
    /// A stop at `position` 65536ths (beyond [`STOP_ONE`]: at 1).
    pub const fn new(position: u32, color: C) -> Self {
        Stop { position, color }
    }

    /// A stop at `position` in `0..=1` given as a float (rounded to the nearest 1/65536, clamped
    /// to `0..=1`, NaN as 0): a conversion the caller makes, never part of drawing.
    pub fn at(position: f32, color: C) -> Self {
        let p = if position.is_nan() {
            0.0
        } else {
            position.clamp(0.0, 1.0)
        };
        Stop {
            position: (p * STOP_ONE as f32 + 0.5) as u32,
            color,
        }
    }
}

/// `num / den` with `den` fixed, by a multiply: `den` normalised to `[2³¹, 2³²)` by a shift and
/// its reciprocal kept in 32 bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct Recip {
    /// `den` is shifted right by this much (left if negative) to `[2³¹, 2³²)`.
    shift: i32,
    /// `⌊(2⁶³ − 1) / den'⌋`, in `(2³¹, 2³²)`; 0 for `den = 0`.
    inv: u32,
}

impl Recip {
    fn new(den: u64) -> Self {
        if den == 0 {
            return Recip::default();
        }
        let shift = 32 - den.leading_zeros() as i32;
        let normal = shift_right(den, shift);
        Recip {
            shift,
            inv: ((u64::MAX >> 1) / normal.max(1)) as u32,
        }
    }

    /// `num / den` in 32 fractional bits for `0 ≤ num ≤ den` (at most 2³²), within a few units
    /// of 2⁻³¹ below the exact quotient.
    #[inline(always)]
    fn fraction(&self, num: u64) -> u64 {
        let n = shift_right(num, self.shift).min(u64::from(u32::MAX));
        (n * u64::from(self.inv)) >> 31
    }

    /// `⌊num / den⌋` or one less, for `num < 2⁴⁷·den` (larger: at least `2¹⁵`).
    #[inline(always)]
    fn quotient(&self, num: u64) -> u64 {
        let n = shift_right(num, self.shift);
        if n >> 32 == 0 {
            (n * u64::from(self.inv)) >> 63
        } else if n >> 47 == 0 {
            ((n >> 15) * u64::from(self.inv)) >> 48
        } else {
            CHUNK as u64
        }
    }
}

/// `v >> s` for `s` in `-63..=63` (left for negative `s`, saturating).
#[inline(always)]
fn shift_right(v: u64, s: i32) -> u64 {
    if s >= 0 {
        v.checked_shr(s as u32).unwrap_or(0)
    } else {
        let l = s.unsigned_abs();
        if v.leading_zeros() >= l {
            v << l
        } else {
            u64::MAX
        }
    }
}

/// A segment's interpolation: the colours at its ends as channels.
#[inline(always)]
fn channels_of<C: GouraudColor>(c: C) -> [i64; 3] {
    c.channels().map(i64::from)
}

/// The stepped channel values ([`STEP_BITS`], +½) at fraction `w` (32 fractional bits, in
/// `0..=1`) of the way from `a` to `b`.
#[inline(always)]
fn value_at(a: [i64; 3], b: [i64; 3], w: u64) -> [u32; 3] {
    let w = w.min(1 << 32) as i64;
    core::array::from_fn(|k| {
        let d = b[k] - a[k];
        ((a[k] << STEP_BITS) + (1 << (STEP_BITS - 1)) + ((d * w) >> (32 - STEP_BITS))) as u32
    })
}

/// The per-pixel channel steps ([`STEP_BITS`], two's complement) of fraction step `ws` (32
/// fractional bits, signed) from `a` to `b`.
#[inline(always)]
fn step_of(a: [i64; 3], b: [i64; 3], ws: i64) -> [u32; 3] {
    core::array::from_fn(|k| (((b[k] - a[k]) * ws) >> (32 - STEP_BITS)) as u32)
}

/// Where a parameter value lies among the stops: before the first (`0`), after the last (`N`),
/// or in the segment that ends at stop `k` (`1..N`).
#[inline(always)]
fn effective<C, const N: usize>(stops: &[Stop<C>; N]) -> [u32; N] {
    let mut e = 0;
    core::array::from_fn(|k| {
        e = stops.get(k).map_or(e, |s| e.max(s.position.min(STOP_ONE)));
        e
    })
}

/// The colour to pad with below the first stop (`first`) or from the last on.
#[inline(always)]
fn pad_color<C: GouraudColor, const N: usize>(stops: &[Stop<C>; N], first: bool) -> C {
    let stop = if first { stops.first() } else { stops.last() };
    stop.map_or(C::from_channels([0; 3]), |s| s.color)
}

/// Where a gradient's pieces of a row go: a framebuffer's row, or a `DrawTarget`.
trait Out<C> {
    /// Pixels in the row.
    fn len(&self) -> usize;
    /// Pixels `from .. from + len` are `color`.
    fn solid(&mut self, from: usize, len: usize, color: C);
    /// Pixels `from .. from + len` are the span loop's colours from `start` by `steps`
    /// ([`GouraudColor::fill_prepared`]), or dithered ([`GouraudColor::fill_dithered`]) at pixel `at` on.
    fn span(
        &mut self,
        from: usize,
        len: usize,
        at: (i32, i32),
        start: [u32; 3],
        steps: &SpanSteps,
        dithered: bool,
    );
}

/// Pieces written into a framebuffer's row.
struct IntoRow<'r, C>(&'r mut [C]);

impl<C: GouraudColor> Out<C> for IntoRow<'_, C> {
    #[inline(always)]
    fn len(&self) -> usize {
        self.0.len()
    }

    #[inline(always)]
    fn solid(&mut self, from: usize, len: usize, color: C) {
        if let Some(part) = self.0.get_mut(from..from + len) {
            fill_row(part, color);
        }
    }

    #[inline(always)]
    fn span(
        &mut self,
        from: usize,
        len: usize,
        (x, y): (i32, i32),
        start: [u32; 3],
        steps: &SpanSteps,
        dithered: bool,
    ) {
        if let Some(part) = self.0.get_mut(from..from + len) {
            if dithered {
                C::fill_dithered(part, x, y, start, steps);
            } else {
                C::fill_prepared(part, start, steps);
            }
        }
    }
}

/// Pieces drawn into a `DrawTarget`, one `fill_solid` or `fill_contiguous` each, with the
/// colours [`IntoRow`] writes; nothing after an error.
struct ToTarget<'t, D: DrawTarget> {
    target: &'t mut D,
    at: (i32, i32),
    len: u32,
    result: Result<(), D::Error>,
}

impl<'t, D: DrawTarget> ToTarget<'t, D> {
    fn new(target: &'t mut D, at: (i32, i32), len: u32) -> Self {
        ToTarget {
            target,
            at,
            len,
            result: Ok(()),
        }
    }

    fn area(&self, from: usize, len: usize) -> Rectangle {
        let x = self.at.0.wrapping_add(from as i32);
        Rectangle::new(Point::new(x, self.at.1), Size::new(len as u32, 1))
    }
}

impl<C: GouraudColor, D: DrawTarget<Color = C>> Out<C> for ToTarget<'_, D> {
    fn len(&self) -> usize {
        self.len as usize
    }

    fn solid(&mut self, from: usize, len: usize, color: C) {
        if self.result.is_ok() {
            self.result = self.target.fill_solid(&self.area(from, len), color);
        }
    }

    fn span(
        &mut self,
        from: usize,
        len: usize,
        (x, y): (i32, i32),
        start: [u32; 3],
        steps: &SpanSteps,
        dithered: bool,
    ) {
        if self.result.is_err() {
            return;
        }
        let area = self.area(from, len);
        self.result = if dithered {
            let colors = DitheredColors::<C>::new(start, steps, (x, y), len);
            self.target.fill_contiguous(&area, colors)
        } else {
            self.target
                .fill_contiguous(&area, StateColors::<C>::new(start, steps, len))
        };
    }
}

/// The colours [`GouraudColor::fill_prepared`] gives a span, one at a time: its state stepped
/// by [`GouraudColor::next_state`], restarted every [`GouraudColor::SPAN_RUN`] pixels.
struct StateColors<C> {
    value: [u32; 3],
    state: [u32; 3],
    steps: SpanSteps,
    taken: u32,
    left: usize,
    _color: core::marker::PhantomData<C>,
}

impl<C: GouraudColor> StateColors<C> {
    fn new(value: [u32; 3], steps: &SpanSteps, len: usize) -> Self {
        StateColors {
            value,
            state: C::span_state(value),
            steps: *steps,
            taken: 0,
            left: len,
            _color: core::marker::PhantomData,
        }
    }
}

impl<C: GouraudColor> Iterator for StateColors<C> {
    type Item = C;

    #[inline]
    fn next(&mut self) -> Option<C> {
        self.left = self.left.checked_sub(1)?;
        let color = C::state_color(self.state);
        self.taken = self.taken.wrapping_add(1);
        match C::SPAN_RUN {
            Some(run) if self.taken == run.get() => {
                self.value = restart_value(self.value, &self.steps, run.get());
                self.state = C::span_state(self.value);
                self.taken = 0;
            }
            _ => self.state = C::next_state(self.state, &self.steps),
        }
        Some(color)
    }
}

// ---- linear -----------------------------------------------------------------------------------

/// A segment of a linear gradient, precomputed when it is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct LinearSegment {
    /// `e·L`: the stop's threshold on the scaled parameter `u` (see [`LinearGradient`]).
    threshold: i64,
    /// The segment ending at this stop: `(threshold − previous threshold)` as a reciprocal.
    width: Recip,
    /// Its channels' per-pixel steps along a row, prepared for the span loop.
    steps: SpanSteps,
}

/// A linear gradient: `t` grows from 0 at `start` to 1 at `end`, constant across lines
/// perpendicular to `end − start`; colours by [`Stop`]s (see the [module](crate::paint::gradient) for the exact
/// gradient, padding, coincident and out-of-order stops).
///
/// `N` stops live in the gradient (a caller-sized array), each with its segment's set-up,
/// computed once by [`new`](Self::new): the drawing path has no division.
///
/// # Accuracy
///
/// Within 1 LSB (rounded to nearest from within 1/32 LSB of the exact channel value, segments
/// decided exactly) at every pixel centre when `end − start` is at most 16,384 pixels on each
/// axis. Longer gradients are scaled down to that (their direction rounded to 1/256 pixel in
/// 16,384): `t` then has a relative error under 2⁻²¹ of the pixel's distance from `start` over
/// the gradient's length. A pixel at any `i32` position and any `Coord` points are valid.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb888, prelude::*};
/// use embedded_raster::paint::{LinearGradient, Paint, Stop, STOP_ONE};
///
/// // Black at x = 0 to red at x = 256 (pixel centres at x + 0.5), along a row.
/// let gradient = LinearGradient::new(
///     (0.0, 0.0),
///     (256.0, 0.0),
///     [Stop::new(0, Rgb888::BLACK), Stop::new(STOP_ONE, Rgb888::RED)],
/// );
/// let mut row = [Rgb888::BLACK; 4];
/// gradient.paint_row(7, 100, &mut row);
/// // 255 · 100.5 / 256 = 100.1
/// assert_eq!(row[0], Rgb888::new(100, 0, 0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LinearGradient<C, const N: usize> {
    stops: [Stop<C>; N],
    start: (Coord, Coord),
    end: (Coord, Coord),
    /// Set-up of the exact parameter `u = 2¹⁶·(p − start)·d` (sub-pixel units, `d` the scaled
    /// direction), with `t = u / (2¹⁶·|d|²)`; `None` for a zero-length gradient.
    plane: Option<LinearPlane>,
    segments: [LinearSegment; N],
    dithered: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct LinearPlane {
    /// `start` in sub-pixel units.
    s: (i64, i64),
    /// The direction `end − start` in sub-pixel units, scaled to at most 2²² on each axis.
    d: (i64, i64),
    /// `u`'s step a pixel to the right: `2¹⁶·256·dx`.
    du: i64,
    /// `|du|` as a reciprocal, for the pixels to a threshold.
    du_recip: Recip,
}

impl LinearPlane {
    /// `u` at the centre of pixel `(x, y)`, saturating (a saturated `u` is beyond every stop).
    #[inline(always)]
    fn at(&self, x: i32, y: i32) -> i64 {
        let px = (i64::from(x) << SUB) + 128 - self.s.0;
        let py = (i64::from(y) << SUB) + 128 - self.s.1;
        // |p − s| < 2⁴¹, |d| ≤ 2²²: each product fits.
        let dot = (px * self.d.0).saturating_add(py * self.d.1);
        // Saturated by a test and a shift, not a checked multiply (a library call on ARMv6-M).
        if dot.unsigned_abs() >> 47 == 0 {
            dot << 16
        } else if dot < 0 {
            i64::MIN
        } else {
            i64::MAX
        }
    }
}

impl<C: GouraudColor, const N: usize> LinearGradient<C, N> {
    /// A gradient from `start` (`t = 0`) to `end` (`t = 1`), `f32`, `f64` or [`Coord`] pairs
    /// ([`ToCoord`]), with `stops`.
    pub fn new<P: ToCoord>(start: (P, P), end: (P, P), stops: [Stop<C>; N]) -> Self {
        let start = (start.0.to_coord(), start.1.to_coord());
        let end = (end.0.to_coord(), end.1.to_coord());
        let s = (i64::from(start.0.to_bits()), i64::from(start.1.to_bits()));
        let mut d = (
            i64::from(end.0.to_bits()) - s.0,
            i64::from(end.1.to_bits()) - s.1,
        );
        // Scale the direction to at most 2²² sub-pixel units on each axis: `t` does not depend on
        // its length, and `2¹⁶·|d|²` then fits 62 bits.
        let big = d.0.unsigned_abs().max(d.1.unsigned_abs());
        let shift = (64 - big.leading_zeros()).saturating_sub(22);
        if shift > 0 {
            let half = 1i64 << (shift - 1);
            d = ((d.0 + half) >> shift, (d.1 + half) >> shift);
        }
        let length = d.0 * d.0 + d.1 * d.1;
        let mut segments = [LinearSegment::default(); N];
        let plane = (length != 0).then(|| {
            let du = (d.0 << SUB) << 16;
            LinearPlane {
                s,
                d,
                du,
                du_recip: Recip::new(du.unsigned_abs()),
            }
        });
        if let Some(plane) = plane {
            let e = effective(&stops);
            let mut previous: Option<(i64, [i64; 3])> = None;
            for ((segment, &e), stop) in segments.iter_mut().zip(&e).zip(&stops) {
                let threshold = i64::from(e) * length;
                let color = channels_of(stop.color);
                segment.threshold = threshold;
                if let Some((before, from)) = previous {
                    let width = (threshold - before) as u64;
                    segment.width = Recip::new(width);
                    // The fraction's step a pixel, 32 fractional bits; beyond ±1 a run in this
                    // segment has one pixel, and the step is never used.
                    let ws = if width == 0 {
                        0
                    } else {
                        let q = (i128::from(plane.du) << 32) / i128::from(width);
                        q.clamp(-(1 << 32), 1 << 32) as i64
                    };
                    segment.steps = C::prepare_steps(step_of(from, color, ws));
                }
                previous = Some((threshold, color));
            }
        }
        LinearGradient {
            stops,
            start,
            end,
            plane,
            segments,
            dithered: false,
        }
    }

    /// The same gradient ordered-dithered (4×4 Bayer): each channel is the floor or the ceiling
    /// of its exact value (where the plain gradient rounds to nearest), chosen by the pixel's
    /// position so that areas average the exact colour: smooth 5-6-5 ramps without bands.
    pub fn dithered(mut self) -> Self {
        self.dithered = true;
        self
    }

    /// The start and end points.
    pub fn points(&self) -> ((Coord, Coord), (Coord, Coord)) {
        (self.start, self.end)
    }

    /// The stops.
    pub fn stops(&self) -> &[Stop<C>; N] {
        &self.stops
    }

    /// Paints pixels `x ..` of row `y` (at most [`CHUNK`]) into `out`.
    #[inline]
    fn paint_chunk(&self, y: i32, x: i32, out: &mut impl Out<C>) {
        let n = out.len();
        let Some(plane) = &self.plane else {
            out.solid(0, n, pad_color(&self.stops, false));
            return;
        };
        let mut i = 0;
        while i < n {
            let at = x.wrapping_add(i as i32);
            let u = plane.at(at, y);
            // The segment: the number of stops at or below `u`.
            let k = self
                .segments
                .iter()
                .take_while(|s| s.threshold <= u)
                .count();
            let below = k.checked_sub(1).and_then(|j| self.segments.get(j));
            let above = self.segments.get(k);
            // Pixels before `u` leaves the segment (at least 1: this one is in it).
            let left = n - i;
            let run = if plane.du > 0 {
                above.map_or(left, |a| {
                    let gap = a.threshold.saturating_sub(u) as u64; // > 0
                    run_to(plane, gap, left, |m| {
                        u.saturating_add(plane.du * (m as i64 - 1)) < a.threshold
                    })
                })
            } else if plane.du < 0 {
                below.map_or(left, |b| {
                    let gap = u.saturating_sub(b.threshold) as u64 + 1; // > 0
                    run_to(plane, gap, left, |m| {
                        u.saturating_add(plane.du * (m as i64 - 1)) >= b.threshold
                    })
                })
            } else {
                left
            };
            match (below, above) {
                (Some(b), Some(a)) => {
                    let from = self.stops.get(k - 1).map(|s| channels_of(s.color));
                    let to = self.stops.get(k).map(|s| channels_of(s.color));
                    if let (Some(from), Some(to)) = (from, to) {
                        let w = a.width.fraction((u - b.threshold) as u64);
                        let start = value_at(from, to, w);
                        out.span(i, run, (at, y), start, &a.steps, self.dithered);
                    }
                }
                _ => out.solid(i, run, pad_color(&self.stops, above.is_some())),
            }
            i += run;
        }
    }
}

/// The pixels from one whose parameter is `gap` (> 0) short of a threshold (in the direction
/// the row goes) to the first at or past it, at most `left`: the quotient by the reciprocal, then
/// corrected with `inside(m)` (whether the `m`-th pixel is still short of it). `m ≤ 2¹⁵` and
/// `|du| ≤ 2⁴⁶`: `du·(m − 1)` fits an `i64`.
#[inline(always)]
fn run_to(plane: &LinearPlane, gap: u64, left: usize, inside: impl Fn(usize) -> bool) -> usize {
    // ⌈gap / |du|⌉ pixels, give or take one.
    let q = plane.du_recip.quotient(gap.saturating_sub(1)) as usize + 1;
    let mut m = q.min(left).max(1);
    while m > 1 && !inside(m) {
        m -= 1;
    }
    while m < left && inside(m + 1) {
        m += 1;
    }
    m
}

/// A gradient's `paint_row`: `chunk(x, out)` paints [`CHUNK`] pixels at most from column `x`.
fn paint_row_in_chunks<C>(mut chunk: impl FnMut(i32, &mut IntoRow<'_, C>), x: i32, row: &mut [C]) {
    let mut at = x;
    for part in row.chunks_mut(CHUNK) {
        chunk(at, &mut IntoRow(part));
        at = at.wrapping_add(CHUNK as i32);
    }
}

/// A gradient's `draw_row`: the same chunks drawn into `target`, until the first error.
fn draw_row_in_chunks<D: DrawTarget>(
    mut chunk: impl FnMut(i32, &mut ToTarget<'_, D>),
    target: &mut D,
    (x, y): (i32, i32),
    len: u32,
) -> Result<(), D::Error> {
    let mut done = 0;
    while done < len {
        let n = (len - done).min(CHUNK as u32);
        let at = x.wrapping_add(done as i32);
        let mut out = ToTarget::new(target, (at, y), n);
        chunk(at, &mut out);
        out.result?;
        done += n;
    }
    Ok(())
}

impl<C: GouraudColor, const N: usize> Paint for LinearGradient<C, N> {
    type Color = C;

    fn paint_row(&self, y: i32, x: i32, row: &mut [C]) {
        paint_row_in_chunks(|at, out| self.paint_chunk(y, at, out), x, row);
    }

    fn draw_row<D>(&self, target: &mut D, y: i32, x: i32, len: u32) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        draw_row_in_chunks(|at, out| self.paint_chunk(y, at, out), target, (x, y), len)
    }
}

// ---- radial -----------------------------------------------------------------------------------

/// A segment of a radial gradient, precomputed when it is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct RadialSegment {
    /// `(e·r)²` (`r` in sub-pixel units): the stop's threshold on `2³²·|p − c|²`.
    threshold: u128,
    /// `e·r`: the stop's threshold on `256·d` (`d` the distance in 2⁻¹⁶ pixel).
    at: i64,
    /// The segment ending at this stop: `(at − previous at)` as a reciprocal.
    width: Recip,
    /// `log₂` budget of its chords (see [`RadialGradient::chord_bits`]).
    flatness: i32,
}

/// The largest chord, `2^MAX_CHORD` pixels.
const MAX_CHORD: i32 = 14;

/// A radial gradient: `t` is the distance from `centre` over `radius` (0 at the centre, 1 on the
/// circle); colours by [`Stop`]s (see the [module](crate::paint::gradient) for the exact gradient, padding,
/// coincident and out-of-order stops).
///
/// # Accuracy
///
/// Which segment a pixel is in is decided exactly (squared distances in 128 bits). Along a row
/// the distance is computed by an integer square root, to 2⁻¹⁶ pixel, at the ends of chords and
/// linearly between them; each chord is short enough that the distance's curvature moves a
/// colour at most 1/4 LSB off the exact one (a chord of `w` pixels on a row `h` from the centre,
/// at distances of at least `d`, is off by at most `w²·h²/(8·d³)` pixels). So pixels are within 1 LSB of the exact gradient
/// (the floor or the ceiling of the exact value) where the pixel is within 46,000 pixels of the
/// centre on each axis and the colour changes by at most 4,096 LSB per pixel of distance (for
/// 8-bit channels: segments at least 1/16 pixel wide; coincident stops are exact edges).
/// Further away the distance is computed to 1/256 pixel.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Gray8, prelude::*};
/// use embedded_raster::paint::{Paint, RadialGradient, Stop, STOP_ONE};
///
/// let gradient = RadialGradient::new(
///     (0.5, 0.5),
///     100.0,
///     [Stop::new(0, Gray8::WHITE), Stop::new(STOP_ONE, Gray8::BLACK)],
/// );
/// let mut row = [Gray8::BLACK; 3];
/// gradient.paint_row(0, 0, &mut row);
/// assert_eq!(row[0], Gray8::WHITE); // the centre
/// // 255 · (1 − 2/100) = 249.9
/// assert_eq!(row[2], Gray8::new(250));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RadialGradient<C, const N: usize> {
    stops: [Stop<C>; N],
    centre: (Coord, Coord),
    radius: Coord,
    segments: [RadialSegment; N],
    dithered: bool,
}

/// A lower bound of `16·log₂ v` (within 1.5; for `v ≥ 1`): the bit length and the next four
/// bits as the mantissa (`log₂(1 + f) ≥ f`).
#[inline(always)]
fn log16_below(v: u64) -> i32 {
    let v = v.max(1);
    let lz = v.leading_zeros();
    let mantissa = ((v << lz) >> 59) & 15;
    16 * (63 - lz as i32) + mantissa as i32
}

/// An upper bound of `16·log₂ v` (within 3; `log₂(1 + f) ≤ f + 0.09`).
#[inline(always)]
fn log16_above(v: u64) -> i32 {
    log16_below(v) + 3
}

/// `⌊log₂ v⌋` (−1 for 0).
#[inline(always)]
fn log2_floor(v: u64) -> i32 {
    63 - v.leading_zeros() as i32
}

/// `|v|` capped at 2³¹: a squared distance of two such fits a `u64`.
#[inline(always)]
fn capped(v: i64) -> u64 {
    v.unsigned_abs().min(1 << 31)
}

/// The distance in 2⁻¹⁶ pixel (floor) of a squared distance in sub-pixel units: to 1/256 pixel
/// beyond 2⁴⁸ (46,000 pixels).
#[inline(always)]
fn distance(d2: u64) -> u64 {
    if d2 >> 48 == 0 {
        (d2 << 16).isqrt()
    } else {
        d2.isqrt() << 8
    }
}

impl<C: GouraudColor, const N: usize> RadialGradient<C, N> {
    /// A gradient around `centre` (`t = 0`) out to `radius` (`t = 1`; a negative radius counts
    /// as its absolute value), `f32`, `f64` or [`Coord`] ([`ToCoord`]), with `stops`.
    pub fn new<P: ToCoord>(centre: (P, P), radius: P, stops: [Stop<C>; N]) -> Self {
        let centre = (centre.0.to_coord(), centre.1.to_coord());
        let radius = radius.to_coord();
        let r = u64::from(radius.to_bits().unsigned_abs());
        let e = effective(&stops);
        let mut segments = [RadialSegment::default(); N];
        let mut previous: Option<(u32, [i64; 3])> = None;
        for ((segment, &e), stop) in segments.iter_mut().zip(&e).zip(&stops) {
            let er = u64::from(e) * r; // < 2⁴⁸
            let color = channels_of(stop.color);
            segment.threshold = u128::from(er) * u128::from(er);
            segment.at = er as i64;
            if let Some((before, from)) = previous {
                let de = u64::from(e - before);
                segment.width = Recip::new(de * r);
                // A chord of 2^j pixels is within 1/4 LSB where
                // 2^(2j) · h² · Δ · 2³¹ ≤ dmin³ · Δe · r (h the row's offset from the centre,
                // dmin the chord's least distance, r in sub-pixel units, Δe in 65536ths, Δ the
                // largest channel change): the part that depends on the segment alone.
                let delta = from
                    .iter()
                    .zip(&color)
                    .map(|(a, b)| (b - a).unsigned_abs())
                    .max()
                    .unwrap_or(0);
                segment.flatness = if delta == 0 {
                    i32::MAX / 4
                } else {
                    log16_below(de) + log16_below(r) - log16_above(delta) - 31 * 16
                };
            }
            previous = Some((e, color));
        }
        RadialGradient {
            stops,
            centre,
            radius,
            segments,
            dithered: false,
        }
    }

    /// The same gradient ordered-dithered (4×4 Bayer): each channel is the floor or the ceiling
    /// of its exact value (where the plain gradient rounds to nearest), chosen by the pixel's
    /// position so that areas average the exact colour: smooth 5-6-5 ramps without bands.
    pub fn dithered(mut self) -> Self {
        self.dithered = true;
        self
    }

    /// The centre and the radius.
    pub fn circle(&self) -> ((Coord, Coord), Coord) {
        (self.centre, self.radius)
    }

    /// The stops.
    pub fn stops(&self) -> &[Stop<C>; N] {
        &self.stops
    }

    /// The segment of squared distance `d2`: the number of stops at or below it.
    #[inline(always)]
    fn segment_of(&self, d2: u64) -> usize {
        let v = u128::from(d2) << 32;
        self.segments
            .iter()
            .take_while(|s| s.threshold <= v)
            .count()
    }

    /// Paints pixels `x ..` of row `y` (at most [`CHUNK`]).
    fn paint_chunk(&self, y: i32, x: i32, out: &mut impl Out<C>) {
        let n = out.len();
        if self.radius == Coord::ZERO {
            out.solid(0, n, pad_color(&self.stops, false));
            return;
        }
        let (cx, cy) = (
            i64::from(self.centre.0.to_bits()),
            i64::from(self.centre.1.to_bits()),
        );
        let py = (i64::from(y) << SUB) + 128 - cy;
        let px = (i64::from(x) << SUB) + 128 - cx;
        // Pixels left of the centre (or on it), whose distance falls along the row, then the
        // others, whose distance grows.
        let left = if px > 0 {
            0
        } else {
            (((-px) >> SUB) as u64 + 1).min(n as u64) as usize
        };
        self.paint_monotone(out, (0, left), (px, py), true);
        let px = px + ((left as i64) << SUB);
        self.paint_monotone(out, (left, n), (px, py), false);
    }

    /// Paints pixels `from .. to` of `out`, the first's centre at `(px, py)` from the centre
    /// (sub-pixel units), along which the distance falls (`falling`) or grows: segments are
    /// runs.
    fn paint_monotone(
        &self,
        out: &mut impl Out<C>,
        (from, to): (usize, usize),
        (px, py): (i64, i64),
        falling: bool,
    ) {
        let d2_at = |i: usize| {
            let (a, b) = (capped(px + ((i as i64) << SUB)), capped(py));
            a * a + b * b
        };
        let n = to.saturating_sub(from);
        let mut i = 0;
        while i < n {
            let k = self.segment_of(d2_at(i));
            // The run of pixels in segment k: gallop, then halve.
            let inside = |m: usize| self.segment_of(d2_at(i + m - 1)) == k;
            let left = n - i;
            let mut m = 1;
            while m < left && inside((2 * m).min(left)) {
                m = (2 * m).min(left);
            }
            let mut beyond = (2 * m).min(left + 1);
            while beyond - m > 1 {
                let mid = m + (beyond - m) / 2;
                if inside(mid) {
                    m = mid;
                } else {
                    beyond = mid;
                }
            }
            let run = (from + i, m);
            let segment = k
                .checked_sub(1)
                .and_then(|a| Some((self.segments.get(a)?, self.segments.get(k)?)));
            match segment {
                Some((a, b)) => {
                    let from = self.stops.get(k - 1).map(|s| channels_of(s.color));
                    let to = self.stops.get(k).map(|s| channels_of(s.color));
                    if let (Some(from), Some(to)) = (from, to) {
                        let x0 = px + ((i as i64) << SUB);
                        self.chords(out, run, (x0, py), falling, (a, b), (from, to));
                    }
                }
                None => out.solid(run.0, run.1, pad_color(&self.stops, k == 0)),
            }
            i += m;
        }
    }

    /// Fills `run` (pixels of one segment from `a` to `b`, the first's centre at `p` from the
    /// centre) by chords of the distance.
    fn chords(
        &self,
        out: &mut impl Out<C>,
        (first, n): (usize, usize),
        p: (i64, i64),
        falling: bool,
        (a, b): (&RadialSegment, &RadialSegment),
        (from, to): ([i64; 3], [i64; 3]),
    ) {
        let value = |i: usize| {
            let (dx, dy) = (capped(p.0 + ((i as i64) << SUB)), capped(p.1));
            let d = distance(dx * dx + dy * dy);
            let num = ((d << 8) as i64).saturating_sub(a.at).max(0);
            value_at(from, to, b.width.fraction(num as u64))
        };
        let h = capped(p.1);
        let mut i = 0;
        let mut start = value(0);
        let (x, y) = self.pixel_of(p);
        while i < n {
            let left = n - i - 1;
            if left == 0 {
                let steps = C::prepare_steps([0; 3]);
                let at = (x.wrapping_add(i as i32), y);
                out.span(first + i, 1, at, start, &steps, self.dithered);
                break;
            }
            let near = capped(p.0 + ((i as i64) << SUB));
            let j = self
                .chord_bits(near, h, falling, b.flatness)
                .min(log2_floor(left as u64));
            let w = 1usize << j;
            let end = value(i + w);
            let step: [u32; 3] =
                core::array::from_fn(|k| ((i64::from(end[k]) - i64::from(start[k])) >> j) as u32);
            let steps = C::prepare_steps(step);
            let at = (x.wrapping_add(i as i32), y);
            out.span(first + i, w, at, start, &steps, self.dithered);
            start = end;
            i += w;
        }
    }

    /// The pixel whose centre is at `p` from the centre (sub-pixel units).
    #[inline(always)]
    fn pixel_of(&self, p: (i64, i64)) -> (i32, i32) {
        let at = |d: i64, c: Coord| ((d + i64::from(c.to_bits()) - 128) >> SUB) as i32;
        (at(p.0, self.centre.0), at(p.1, self.centre.1))
    }

    /// `j` such that a chord of `2^j` pixels from the pixel `near` from the centre horizontally
    /// (`h` vertically; sub-pixel units) keeps the segment's colours within 1/4 LSB:
    /// `2j + 2·log₂ h ≤ 3·log₂ dmin + flatness` with `dmin` the chord's least distance.
    #[inline(always)]
    fn chord_bits(&self, near: u64, h: u64, falling: bool, flatness: i32) -> i32 {
        if h == 0 || flatness >= i32::MAX / 8 {
            // The distance is linear along the row (or the colour constant).
            return MAX_CHORD;
        }
        // In sixteenths of a bit: 32·j ≤ 3·log₂ dmin − 2·log₂ h + flatness.
        let budget = |d: u64| 3 * log16_below(d.max(h)) - 2 * log16_above(h) + flatness;
        // dmin where the chord starts: the least on a growing distance, the most on a falling
        // one, which then is checked at the chord's far end.
        let mut j = (budget(near) / 32).clamp(0, MAX_CHORD);
        while falling && j > 0 && 32 * j > budget(near.saturating_sub(1 << (8 + j))) {
            j -= 1;
        }
        j
    }
}

impl<C: GouraudColor, const N: usize> Paint for RadialGradient<C, N> {
    type Color = C;

    fn paint_row(&self, y: i32, x: i32, row: &mut [C]) {
        paint_row_in_chunks(|at, out| self.paint_chunk(y, at, out), x, row);
    }

    fn draw_row<D>(&self, target: &mut D, y: i32, x: i32, len: u32) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        draw_row_in_chunks(|at, out| self.paint_chunk(y, at, out), target, (x, y), len)
    }
}
