//! Ordered dithering (4×4 Bayer) of stepped channel values: each channel is the floor or the
//! ceiling of its exact value, and a flat colour between two levels averages to it over each
//! 4×4 block.
//!
//! A format's dithered span is [`GouraudColor::fill_dithered`]: by default channel by channel
//! from the [`STEP_BITS`] values ([`fill_dithered_by_channels`]); the 5-6-5 formats dither their
//! packed lanes instead (`packed565::dithered_565`, two pixels a word), and every path that
//! hands out a dithered span's colours ([`DitheredColors`] for a `DrawTarget`) takes them from
//! that one function.

use super::{restart_value, GouraudColor, SpanSteps, STEP_BITS};

/// The 4×4 Bayer matrix, rows by `y & 3`, columns by `x & 3`: pixel `(x, y)`'s threshold is
/// `(2·b + 1) / 32` LSB.
const BAYER: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

/// Pixels of a dithered span stepped from one restart by a format's own loop, and so the chunk
/// [`DitheredColors`] fills at a time (a multiple of every such restart).
pub(super) const DITHER_RUN: usize = 32;

/// The offset of Bayer entry `b` with `fraction` fractional bits (5 to 24), to add to a value
/// that has the +½ rounding offset in it: `(2b + 1)/32 − ½` LSB, so that truncation gives the
/// floor or the ceiling of the value without the +½.
const fn threshold_offset(b: u8, fraction: u32) -> i32 {
    ((b as i32 * 2 + 1) << (fraction - 5)) - (1 << (fraction - 1))
}

/// The fractional bits of [`bayer_pair`]'s offsets (the 5-6-5 top and bottom lanes').
const PAIR_FRACTION: u32 = 11;

/// [`bayer_pair`]'s table: rows by `y & 3`, columns by `x & 3`.
const BAYER_PAIRS: [[u32; 4]; 4] = {
    let mut pairs = [[0; 4]; 4];
    let mut y = 0;
    while y < 4 {
        let mut x = 0;
        while x < 4 {
            let low = threshold_offset(BAYER[y][x], PAIR_FRACTION);
            let high = threshold_offset(BAYER[y][(x + 1) % 4], PAIR_FRACTION);
            pairs[y][x] = (high * 65536 + low) as u32;
            x += 1;
        }
        y += 1;
    }
    pairs
};

/// The Bayer offsets of pixels `(x, y)` and `(x + 1, y)` with 11 fractional bits (those of
/// [`bayer_offset`]), as the integer `o₁·2¹⁶ + o₀` modulo 2³²: added to a word that holds two
/// 16-bit lanes, it adds `o₀` to the low one and `o₁` to the high one wherever both sums stay in
/// `[0, 2¹⁶)`. The offsets are even, so half of it (an arithmetic shift) is the pair with 10.
#[inline(always)]
pub(super) fn bayer_pair(x: i32, y: i32) -> u32 {
    BAYER_PAIRS
        .get((y & 3) as usize)
        .and_then(|r| r.get((x & 3) as usize))
        .copied()
        .unwrap_or(0)
}

/// The Bayer offset of pixel `(x, y)` with `fraction` fractional bits (5 to 24)
/// ([`threshold_offset`]).
#[inline(always)]
pub(super) fn bayer_offset(x: i32, y: i32, fraction: u32) -> i32 {
    let b = BAYER
        .get((y & 3) as usize)
        .and_then(|r| r.get((x & 3) as usize))
        .copied()
        .unwrap_or(0);
    threshold_offset(b, fraction)
}

/// [`GouraudColor::fill_dithered`]'s default: pixel `i` of `dst` (pixel `x + i` of row `y`) has
/// channel values `start + i·step` ([`STEP_BITS`] fractional bits, +½ included, wrapping) and
/// is `⌊v − ½ + (2b + 1)/32⌋` for its Bayer entry `b`, within the channel's range.
#[inline]
pub(crate) fn fill_dithered_by_channels<C: GouraudColor>(
    dst: &mut [C],
    x: i32,
    y: i32,
    start: [u32; 3],
    steps: &SpanSteps,
) {
    let step = steps.step();
    let mut v = start;
    let mut at = x;
    for px in dst {
        let o = i64::from(bayer_offset(at, y, STEP_BITS));
        // The offset may take a value at 0 below it, or one at the maximum above it.
        let channel = |v: u32, max: u8| ((i64::from(v) + o).max(0) >> STEP_BITS).min(max.into());
        let [a, b, c] = v;
        let [ma, mb, mc] = C::MAX;
        *px = C::from_channels([
            channel(a, ma) as u8,
            channel(b, mb) as u8,
            channel(c, mc) as u8,
        ]);
        for (v, s) in v.iter_mut().zip(step) {
            *v = v.wrapping_add(s);
        }
        at = at.wrapping_add(1);
    }
}

/// The colours [`GouraudColor::fill_dithered`] gives a span, one at a time (for
/// `fill_contiguous`): [`DITHER_RUN`] pixels at a time from the values there, so the same
/// colours however the span is drawn.
pub(crate) struct DitheredColors<C> {
    chunk: [C; DITHER_RUN],
    /// The next colour's index in `chunk`, and how many it holds.
    at: usize,
    filled: usize,
    /// The values and column of the next chunk's first pixel, the row, the pixels left after
    /// the chunk.
    value: [u32; 3],
    x: i32,
    y: i32,
    left: usize,
    steps: SpanSteps,
}

impl<C: GouraudColor> DitheredColors<C> {
    /// The `len` pixels from `(x, y)` on of the dithered span from `start` by `steps`.
    #[inline]
    pub(crate) fn new(start: [u32; 3], steps: &SpanSteps, (x, y): (i32, i32), len: usize) -> Self {
        DitheredColors {
            chunk: [C::from_channels([0; 3]); DITHER_RUN],
            at: 0,
            filled: 0,
            value: start,
            x,
            y,
            left: len,
            steps: *steps,
        }
    }
}

impl<C: GouraudColor> Iterator for DitheredColors<C> {
    type Item = C;

    #[inline]
    fn next(&mut self) -> Option<C> {
        if self.at == self.filled {
            let n = self.left.min(DITHER_RUN);
            let chunk = self.chunk.get_mut(..n).filter(|c| !c.is_empty())?;
            C::fill_dithered(chunk, self.x, self.y, self.value, &self.steps);
            self.value = restart_value(self.value, &self.steps, n as u32);
            self.x = self.x.wrapping_add(n as i32);
            self.left -= n;
            (self.at, self.filled) = (0, n);
        }
        let color = self.chunk.get(self.at).copied();
        self.at += 1;
        color
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.filled - self.at + self.left;
        (n, Some(n))
    }
}
