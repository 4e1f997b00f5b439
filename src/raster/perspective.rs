//! Perspective-correct interpolation: three more attribute planes — `q ∝ 1/w` and the
//! barycentrics of vertices 1 and 2 times `q` — from which a span shader recovers the
//! perspective-correct barycentrics `λₖ = (bₖ·q) / q` at chosen pixels (one reciprocal, two
//! products) and from them any attribute (texel coordinates, light levels) as
//! `a₀ + λ₁(a₁ − a₀) + λ₂(a₂ − a₀)`, exact to the planes' precision. Between those pixels
//! a shader steps the attribute affinely.
//!
//! Screen-space linear functions are exactly what the planes interpolate: `q = 1/w` is one (the
//! projection of a plane), and so is `bₖ·q`, so the corrected values need no new walker.
//!
//! # Precision
//!
//! `q` is normalised per triangle by a common shift (its largest vertex value in
//! `[32 640, 65 279]`, a division-free choice), so a triangle whose vertices' `w` differ by a
//! ratio `ρ` has every `q` at least `32 640 / ρ`. The planes carry each value within half a unit
//! of its 16-bit scale, so `λ` is within about `1/q` of the exact ratio: `3·10⁻⁵` for `ρ = 1`,
//! `6·10⁻⁴` for `ρ = 20`, plus the 2⁻¹⁵ of its fixed-point reciprocal.

use super::arith::{
    div_rem_u32, leading_zeros_32, leading_zeros_64, mul_i32_wide, mul_u32_u33, reciprocal_31,
};
use super::plane::Attributes;
use crate::arch::{CHUNKS_BY_THRESHOLDS, HAS_DIVIDER, NO_LONG_MULTIPLY};
use core::num::{NonZeroU16, NonZeroU32};

/// Margin added to every vertex value, so that the planes' rounding error (under one unit)
/// never takes a value below zero, where it would wrap.
const MARGIN: u16 = 128;

/// The largest normalised `q` (the margin below the 16-bit limit).
const Q_MAX: u32 = 65_535 - 2 * MARGIN as u32;

/// A perspective barycentric with 16 fractional bits (`65536` is 1).
pub(crate) type Lambda = u32;

/// The three perspective planes' vertex values (`q`, `b₁·q`, `b₂·q`, each + [`MARGIN`]) for
/// vertices whose `q` (any positive values proportional to `1/w`, such as 2³² / w) are `q`,
/// with the planes' rounding offset (none: the values are read back whole).
pub(crate) fn attributes(q: [u64; 3]) -> Attributes<3> {
    // A q of 0 (w beyond any range) is taken as the smallest positive one.
    let q = q.map(|q| q.max(1));
    let top = q[0].max(q[1]).max(q[2]);
    // The common shift that brings the largest into (Q_MAX/2, Q_MAX]: from its bit length
    // (17 bits down to 16), one step more if that is still above Q_MAX.
    let bits = 64 - leading_zeros_64(top);
    let (mut shift, mut up) = if bits > 16 {
        (bits - 16, 0)
    } else {
        (0, 16 - bits)
    };
    if top >> shift > u64::from(Q_MAX) {
        shift += 1;
    }
    if up > 0 && top << up > u64::from(Q_MAX) {
        up -= 1;
    }
    let n = q.map(|q| {
        let v = if shift > 0 { q >> shift } else { q << up };
        // At least 1: a vertex at (practically) infinite w still has a positive q.
        v.clamp(1, u64::from(Q_MAX)) as u16
    });
    // Vertex by vertex without indices: no bounds checks where the compiler does not inline
    // (`opt-level` "s", "z").
    let [n0, n1, n2] = n;
    let values = [
        [n0 + MARGIN, MARGIN, MARGIN],
        [n1 + MARGIN, n1 + MARGIN, MARGIN],
        [n2 + MARGIN, MARGIN, n2 + MARGIN],
    ];
    Attributes {
        values,
        half: [0; 3],
    }
}

/// The perspective barycentrics `(λ₁, λ₂)` at a pixel from the three planes' values there
/// (8.24 of the 8-bit scale: the 16-bit value times 2¹⁶): `(bₖ·q) / q`, from one reciprocal
/// `⌊2³¹ / q⌋` (a division: one instruction where there is a divider; on ARMv6-M a seed and
/// Newton steps, [`reciprocal_31`], a tenth of the shift-subtract division's instructions).
#[inline(always)]
pub(crate) fn lambdas(values: [u32; 3]) -> (Lambda, Lambda) {
    let whole = |v: u32| (v >> 16).saturating_sub(u32::from(MARGIN));
    // q: the whole part, at least 1 (and below 2¹⁶); r = 2³¹ / q ≤ 2³¹, the exact quotient.
    let (q, r) = if HAS_DIVIDER {
        let q = whole(values[0]).max(1);
        (
            q,
            div_rem_u32(1 << 31, NonZeroU32::MIN.saturating_add(q - 1)).0,
        )
    } else {
        // As a 16-bit value (the same q), which the Cortex-M0 code around takes in less flash.
        let q = NonZeroU16::new(whole(values[0]) as u16).unwrap_or(NonZeroU16::MIN);
        (u32::from(q.get()), reciprocal_31(q.into()))
    };
    // p ≤ q (at covered pixels up to the planes' rounding, clamped): p·r ≤ 2³¹.
    let lambda = |v: u32| (whole(v).min(q) * r) >> 15;
    (lambda(values[1]), lambda(values[2]))
}

/// An attribute corrected for perspective: its value at vertex 0 and the differences to
/// vertices 1 and 2, in any 32-bit fixed point (16.16 texels, 8.24 levels), wrapping.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Corrected {
    base: i32,
    /// `(a₁ − a₀)` and `(a₂ − a₀)` split into their high halves (signed) and low halves: the
    /// products with a 17-bit `λ` in 32 bits, the same on every core.
    high: [i32; 2],
    low: [u32; 2],
}

impl Corrected {
    /// The attribute with values `a` at the vertices (in their input order).
    pub(crate) fn new(a: [i32; 3]) -> Self {
        let d = [a[1].wrapping_sub(a[0]), a[2].wrapping_sub(a[0])];
        Corrected {
            base: a[0],
            high: d.map(|d| d >> 16),
            low: d.map(|d| d as u32 & 0xffff),
        }
    }

    /// `(a₀, d₁, d₂)`: the value at vertex 0 and the differences (wrapping).
    #[inline(always)]
    pub(crate) fn parts(&self) -> [i32; 3] {
        let d = |k: usize| (self.high[k] << 16) | self.low[k] as i32;
        [self.base, d(0), d(1)]
    }

    /// A bound on `|a′·q²|` along a span (constant along it: `a·q` and `q` are linear), from
    /// `kₖ = (dpₖ·q − pₖ·dq) / 2¹⁶` for its perspective planes' values `pₖ`, `q` (whole) and
    /// steps `dpₖ`, `dq` (raw), each within `eₖ` of the exact value: `a·q = a₀·q + d₁·p₁ +
    /// d₂·p₂`, so `a′·q² = d₁·(dp₁·q − p₁·dq) + d₂·(dp₂·q − p₂·dq)`, here over 2¹⁶, and
    /// `|d₁|·e₁ + |d₂|·e₂` more.
    #[inline(always)]
    pub(crate) fn slope(&self, (k1, e1): (i32, u32), (k2, e2): (i32, u32)) -> u64 {
        let [_, d1, d2] = self.parts();
        let off = |d: i32, e: u32| mul_u32_u33(d.unsigned_abs(), u64::from(e));
        mul_i32_wide(d1, k1)
            .saturating_add(mul_i32_wide(d2, k2))
            .unsigned_abs()
            .saturating_add(off(d1, e1) + off(d2, e2))
    }

    /// `a₀ + ⌊λ₁·d₁ / 2¹⁶⌋ + ⌊λ₂·d₂ / 2¹⁶⌋` modulo 2³² (`λ` at most 2¹⁷).
    #[inline(always)]
    pub(crate) fn at(&self, (l1, l2): (Lambda, Lambda)) -> i32 {
        let part = |l: u32, k: usize| {
            if NO_LONG_MULTIPLY {
                // λ·d / 2¹⁶ = λ·high + λ·low / 2¹⁶, floored exactly; λ·low < 2³³ is split once
                // more (λ's high part is at most 2), so every product fits 32 bits.
                let low = self.low[k];
                let low = (l >> 16) * low + (((l & 0xffff) * low) >> 16);
                (l as i32)
                    .wrapping_mul(self.high[k])
                    .wrapping_add(low as i32)
            } else {
                // The same integer from one long product: d = high·2¹⁶ + low.
                let d = (i64::from(self.high[k]) << 16) | i64::from(self.low[k]);
                ((i64::from(l) * d) >> 16) as i32
            }
        };
        self.base
            .wrapping_add(part(l1, 0))
            .wrapping_add(part(l2, 1))
    }
}

/// The longest chunk: a span's corrected values are computed every [`chunk_shift`]-chosen
/// power of two of pixels up to this from its first, and at its last; the values between are
/// stepped from them.
pub(crate) const CHUNK: u32 = 1 << CHUNK_SHIFT;

/// `CHUNK`'s bits.
const CHUNK_SHIFT: u32 = 4;

/// `16·log₂ v` rounded down (`v ≥ 1`): the bit length less one and the four bits after the
/// leading one (`log₂(1 + f) ≥ f`). No division, no table.
#[inline(always)]
fn log16_down(v: u32) -> i32 {
    let n = 32 - leading_zeros_32(v.max(1));
    let fraction = if n > 5 { v >> (n - 5) } else { v << (5 - n) } & 15;
    16 * (n as i32 - 1) + fraction as i32
}

/// `16·log₂ v` rounded up: [`log16_down`] plus one for the fraction's truncated bits and two
/// for `log₂(1 + f) − f ≤ 0.087`.
#[inline(always)]
fn log16_up(v: u32) -> i32 {
    log16_down(v) + 3
}

/// [`log16_up`] of a 64-bit value.
#[inline(always)]
fn log16_up_64(v: u64) -> i32 {
    let high = (v >> 32) as u32;
    if high == 0 {
        log16_up(v as u32)
    } else {
        // The 32 bits from the leading one: the value over 2^shift, rounded down, so one more.
        let shift = 32 - leading_zeros_32(high);
        log16_up((v >> shift) as u32 + 1) + 16 * shift as i32
    }
}

/// What [`Chunks`] needs to pick each chunk's length along a span whose perspective planes
/// start at `values` and step by `step` a pixel, for an attribute that chords must keep within
/// `tolerance` of its exact values and whose [`slope`](Corrected::slope) `slope` gives for the
/// span's `(k₁, k₂)` (the largest over several attributes; 0 for none that varies): the chunk's
/// length is the largest power of two `L` up to [`CHUNK`] with `32·log₂ L ≤ room + 48·log₂
/// q_min` (`q_min` the smaller raw `q` at the chunk's first pixel and [`CHUNK`] pixels on, or the
/// span's last), every chunk [`CHUNK`] long for a room of [`NO_LIMIT`] or more.
///
/// Along a chunk of `L` pixels from `q₀` to `q₁`, the perspective-correct value departs from
/// the chord between its exact ends by `Δa·s(1 − s)(q₁ − q₀)/q(s)` at the fraction `s` of the
/// way, at most `|Δa|·|Δq| / (4·q_min)` (q is linear along it). Its change a pixel is `a′ =
/// K/q²` with `K` constant along the span (`slope` is `K/2¹⁶` with `q` whole and the steps raw),
/// so the departure is at most `L²·|K|·|dq| / (4·q_min³)`: in raw units, within the tolerance
/// when `2·log₂ L ≤ 2 + log₂ tolerance + 3·log₂ q_min − log₂ slope − log₂|dq| − 32` (`q_min`
/// raw). The logarithms are taken to a sixteenth and rounded the safe way (no division). A span
/// along which `q` is constant has exact chords: chunks of [`CHUNK`].
// Out of line on ARMv6-M: its 64-bit arithmetic's frame is not the span loop's.
#[cfg_attr(armv6m, inline(never))]
#[cfg_attr(not(armv6m), inline(always))]
pub(crate) fn chunk_room(
    values: [u32; 3],
    step: [u32; 3],
    tolerance: u32,
    slope: impl FnOnce((i32, u32), (i32, u32)) -> u64,
) -> i32 {
    let dq = step[0] as i32;
    if dq == 0 {
        return NO_LIMIT;
    }
    // Whole parts below 2¹⁶: 32-bit factors (products of 16-bit limbs where a 64-bit one would
    // be a library call).
    let whole = |v: u32| (v >> 16).saturating_sub(u32::from(MARGIN)) as i32;
    let q = whole(values[0]);
    let k = |k: usize| {
        let dp = step[k] as i32;
        let d = mul_i32_wide(dp, q) - mul_i32_wide(whole(values[k]), dq);
        // Below 2³² · 2¹⁶ + 2¹⁶ · 2³²: within i32 over 2¹⁶, clamped (never reached). The whole
        // parts are each within one unit: the product within |dp| + |dq|, over 2¹⁶ (and the
        // floor) within this error.
        let error = (dp.unsigned_abs().saturating_add(dq.unsigned_abs()) >> 16) + 2;
        (
            (d >> 16).clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32,
            error,
        )
    };
    let slope = slope(k(1), k(2));
    if slope == 0 {
        return NO_LIMIT;
    }
    32 + log16_down(tolerance) - log16_up_64(slope) - log16_up(dq.unsigned_abs()) - 512
}

/// A [`chunk_room`] for which every chunk is [`CHUNK`] pixels long (`q_min ≥ 2¹⁶`: its
/// sixteenth-logarithm times three is at least 768).
pub(crate) const NO_LIMIT: i32 = 128 - 768;

/// The bits of the length of a chunk of a span with [`chunk_room`] `room` whose `q` plane is
/// `q` at the chunk's first pixel and steps by `dq`, `left` pixels (at least one) from there to
/// the span's end and `offset` from the span's first: at most the bits of the largest power of
/// two dividing `offset`, so that every chunk lies inside the chunk of 16 from a multiple of 16
/// (a chord over part of another is closer to the curve: the coordinates' chords are never
/// further off than those of chunks of 16).
#[inline(always)]
pub(crate) fn chunk_shift(room: i32, q: u32, dq: u32, left: u32, offset: u32) -> u32 {
    chunk_shift_from(room, q, dq, left, offset, |q_min| {
        ((room + 3 * log16_down(q_min)) >> 5).clamp(0, CHUNK_SHIFT as i32) as u32
    })
}

/// The chunk's length's bits as [`chunk_shift`] bounds them, with `bits` giving the longest the
/// light's chords allow from the chunk's `q_min` (asked only for a room below [`NO_LIMIT`]).
#[inline(always)]
fn chunk_shift_from(
    room: i32,
    q: u32,
    dq: u32,
    left: u32,
    offset: u32,
    bits: impl FnOnce(u32) -> u32,
) -> u32 {
    let aligned = aligned_shift(offset);
    if room >= NO_LIMIT {
        return aligned;
    }
    bits(chunk_q_min(q, dq, left)).min(aligned)
}

/// The bits of the largest power of two dividing `offset`, at most [`CHUNK_SHIFT`] (all of
/// them for the span's first chunk): where a trailing-zero count is a software loop (ARMv6-M),
/// a byte of [`ALIGNED`].
#[inline(always)]
fn aligned_shift(offset: u32) -> u32 {
    if CHUNKS_BY_THRESHOLDS {
        u32::from(ALIGNED[(offset % CHUNK) as usize])
    } else if offset == 0 {
        CHUNK_SHIFT
    } else {
        offset.trailing_zeros().min(CHUNK_SHIFT)
    }
}

/// [`aligned_shift`] of each residue modulo [`CHUNK`].
const ALIGNED: [u8; CHUNK as usize] = {
    let mut t = [CHUNK_SHIFT as u8; CHUNK as usize];
    let mut n = 1;
    while n < CHUNK as usize {
        t[n] = n.trailing_zeros() as u8;
        n += 1;
    }
    t
};

/// The smaller raw `q` of a chunk's first pixel (`q`) and [`CHUNK`] pixels on (or the span's
/// last, `left − 1` on), the margin off, at least 2¹⁶ (and below `u32::MAX`).
#[inline(always)]
fn chunk_q_min(q: u32, dq: u32, left: u32) -> u32 {
    let end = q.wrapping_add(dq.wrapping_mul(left.saturating_sub(1).min(CHUNK)));
    let margin = u32::from(MARGIN) << 16;
    q.min(end).saturating_sub(margin).max(1 << 16)
}

/// [`chunk_shift`]'s test as thresholds on the chunk's `q_min`, found once a span from its
/// [`chunk_room`] `room` (below [`NO_LIMIT`]): threshold `s` is the least `q_min` at which a
/// chunk of `2^(s + 1)` pixels is short enough — the least `v` with `room + 3·16·log₂ v ≥ 32·(s
/// + 1)` in [`log16_down`]'s sixteenths — or `u32::MAX` where none is (`q_min` never reaches it).
/// Where a sixteenth-logarithm needs a software leading-zero count (ARMv6-M), a chunk's length is
/// then four comparisons: [`chunk_shift_by`].
#[inline(always)]
pub(crate) fn chunk_thresholds(room: i32) -> [u32; CHUNK_SHIFT as usize] {
    core::array::from_fn(|s| {
        // Positive below NO_LIMIT: the least sixteenth-logarithm m = ⌈need / 3⌉.
        let need = 32 * (s as i32 + 1) - room;
        let m = (need.max(0) + 2) / 3;
        if m > 16 * 31 + 15 {
            // Beyond every 32-bit value's.
            u32::MAX
        } else if m <= 16 * 16 {
            // Every q_min (at least 2¹⁶) has at least this one.
            0
        } else {
            // The least value with bit length n = m / 16 + 1 and the four bits after its leading
            // one m mod 16 (bit lengths of 17 and more here).
            (16 + (m % 16) as u32) << (m / 16 - 4)
        }
    })
}

/// [`chunk_shift`] from the span's [`chunk_thresholds`] `thresholds` (and its `room`): the same
/// length.
#[inline(always)]
pub(crate) fn chunk_shift_by(
    thresholds: &[u32; CHUNK_SHIFT as usize],
    room: i32,
    q: u32,
    dq: u32,
    left: u32,
    offset: u32,
) -> u32 {
    // The thresholds increase: the count of those reached is the longest length's bits.
    chunk_shift_from(room, q, dq, left, offset, |q_min| {
        thresholds.iter().map(|&t| u32::from(q_min >= t)).sum()
    })
}

/// `⌈2¹⁶ / n⌉` for the short last chunk of a span (`n` pixels between its computed ends).
const INVERSE: [u32; CHUNK as usize] = {
    let mut t = [0; CHUNK as usize];
    let mut n = 1;
    while n < CHUNK as usize {
        t[n] = 65_536_u32.div_ceil(n as u32);
        n += 1;
    }
    t
};

/// The per-pixel step of a value going from `a` to `b` over `n` pixels (1 to [`CHUNK`]):
/// `(b − a) / n`, a shift for whole chunks, a product by [`INVERSE`] (within a unit) else —
/// for a power of two the same floored quotient as the shift.
#[inline(always)]
pub(crate) fn step_over(a: i32, b: i32, n: u32) -> i32 {
    let d = b.wrapping_sub(a);
    if n >= CHUNK {
        return d >> CHUNK.trailing_zeros();
    }
    let inverse = INVERSE.get(n as usize).copied().unwrap_or(0);
    // ⌊d·inverse / 2¹⁶⌋ by halves, as in `Corrected::at` (the low product below 2³²: the
    // inverse is at most 2¹⁶).
    let low = ((d as u32 & 0xffff) * inverse) >> 16;
    (d >> 16)
        .wrapping_mul(inverse as i32)
        .wrapping_add(low as i32)
}

/// The chunks of one span: their lengths and the perspective barycentrics at their ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Chunk {
    /// Pixels in the chunk.
    pub(crate) len: u32,
    /// `λ` at its first pixel.
    pub(crate) start: (Lambda, Lambda),
    /// `λ` at the pixel `over` pixels on (the next chunk's first, or this one's last).
    pub(crate) end: (Lambda, Lambda),
    /// Pixels from the first to the pixel of `end` (0 for a one-pixel chunk).
    pub(crate) over: u32,
}

/// The chunks of a span from the perspective planes' values at its first pixel: each of the
/// length [`chunk_shift`] picks, the last one shorter; one [`lambdas`] a chunk.
#[derive(Debug, Clone)]
pub(crate) struct Chunks {
    /// The planes' values at the current chunk's first pixel.
    values: [u32; 3],
    step: [u32; 3],
    at: (Lambda, Lambda),
    left: u32,
    /// The span's [`chunk_room`].
    room: i32,
    /// Its [`chunk_thresholds`] where a chunk's length is found from them
    /// ([`CHUNKS_BY_THRESHOLDS`]).
    thresholds: [u32; CHUNK_SHIFT as usize],
    /// Pixels from the span's first to the current chunk's.
    offset: u32,
}

impl Chunks {
    /// The chunks of a span of `len` pixels whose perspective planes' values start at `values`
    /// and step by `step` a pixel, with [`chunk_room`] `room`.
    #[inline(always)]
    pub(crate) fn new(values: [u32; 3], step: [u32; 3], len: u32, room: i32) -> Self {
        Chunks {
            values,
            step,
            at: lambdas(values),
            left: len,
            room,
            thresholds: if CHUNKS_BY_THRESHOLDS && room < NO_LIMIT {
                chunk_thresholds(room)
            } else {
                [0; CHUNK_SHIFT as usize]
            },
            offset: 0,
        }
    }
}

impl Iterator for Chunks {
    type Item = Chunk;

    #[inline(always)]
    fn next(&mut self) -> Option<Chunk> {
        if self.left == 0 {
            return None;
        }
        let start = self.at;
        let (room, q, dq, left, offset) = (
            self.room,
            self.values[0],
            self.step[0],
            self.left,
            self.offset,
        );
        let full = 1
            << if CHUNKS_BY_THRESHOLDS {
                chunk_shift_by(&self.thresholds, room, q, dq, left, offset)
            } else {
                chunk_shift(room, q, dq, left, offset)
            };
        let (len, over) = if self.left > full {
            (full, full)
        } else {
            (self.left, self.left - 1)
        };
        let values: [u32; 3] =
            core::array::from_fn(|k| self.values[k].wrapping_add(self.step[k].wrapping_mul(over)));
        let end = if over == 0 { start } else { lambdas(values) };
        self.values = values;
        self.at = end;
        self.left -= len;
        self.offset = self.offset.wrapping_add(len);
        Some(Chunk {
            len,
            start,
            end,
            over,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The split products are the exact floored ones, and λ the exact ratio within its bound.
    #[test]
    fn corrected_values_are_the_exact_products() {
        let mut next = crate::random(0x9e47_0001);
        for _ in 0..100_000 {
            let a = [next() as i32, next() as i32, next() as i32];
            let l = ((next() % (1 << 17)) as u32, (next() % (1 << 17)) as u32);
            let c = Corrected::new(a);
            let d = |k: usize| i64::from(a[k].wrapping_sub(a[0]));
            let want =
                i64::from(a[0]) + ((i64::from(l.0) * d(1)) >> 16) + ((i64::from(l.1) * d(2)) >> 16);
            assert_eq!(c.at(l), want as i32, "{a:?} {l:?}");
            let n = 1 + (next() % u64::from(CHUNK)) as u32;
            let (x, y) = (next() as i32, next() as i32);
            let exact = i64::from(y.wrapping_sub(x)) as f64 / f64::from(n);
            let got = f64::from(step_over(x, y, n));
            // The rounded-up inverse adds under |d|/2¹⁶.
            let d = f64::from(y.wrapping_sub(x));
            assert!(
                (got - exact).abs() <= 1.0 + d.abs() / 65536.0,
                "{x} {y} {n}"
            );
        }
        for k in 0..=CHUNK_SHIFT {
            for _ in 0..10_000 {
                let (x, y) = (next() as i32, next() as i32);
                assert_eq!(
                    step_over(x, y, 1 << k),
                    y.wrapping_sub(x) >> k,
                    "{x} {y} {k}"
                );
            }
        }
        for q in [1u32, 2, 3, 1000, 32_640, Q_MAX] {
            for p in [0, 1, q / 3, q / 2, q - 1, q] {
                let v = |x: u32| (x + u32::from(MARGIN)) << 16;
                let (l, _) = lambdas([v(q), v(p), v(0)]);
                let exact = f64::from(p) / f64::from(q) * 65536.0;
                assert!(
                    (f64::from(l) - exact).abs() <= 2.0 + exact / 32768.0,
                    "{p}/{q}: {l}"
                );
            }
        }
    }

    /// The thresholds found once a span give every chunk the length `chunk_shift` gives it
    /// (rooms across `chunk_room`'s range, any `q` and step, first and later chunks).
    #[test]
    fn chunk_thresholds_give_the_same_lengths() {
        let mut next = crate::random(0x9e47_0007);
        let mut lengths = [0usize; CHUNK_SHIFT as usize + 1];
        for n in 0..200_000 {
            // Rooms as `chunk_room` gives them (about −2,100 up), and beyond NO_LIMIT.
            let room = NO_LIMIT + 64 - (next() % 2_200) as i32;
            let q = if n % 3 == 0 {
                next() as u32
            } else {
                (next() as u32) >> (next() % 16)
            };
            let dq = (next() as u32) >> (next() % 32);
            let (left, offset) = (1 + (next() % 40) as u32, (next() % 64) as u32);
            let want = chunk_shift(room, q, dq, left, offset);
            let thresholds = chunk_thresholds(room);
            assert!(thresholds.windows(2).all(|t| t[0] <= t[1]), "{room}");
            assert_eq!(
                chunk_shift_by(&thresholds, room, q, dq, left, offset),
                want,
                "{room} {q} {dq} {left} {offset}"
            );
            lengths[want as usize] += 1;
        }
        // Every length taken, so that the comparison covers each threshold.
        assert!(lengths.iter().all(|&n| n > 1_000), "{lengths:?}");
        // The alignment: the largest power of two dividing the offset, at most CHUNK.
        for offset in (0..5_000).chain((0..5_000).map(|_| next() as u32)) {
            let want = if offset == 0 {
                CHUNK_SHIFT
            } else {
                offset.trailing_zeros().min(CHUNK_SHIFT)
            };
            assert_eq!(aligned_shift(offset), want, "{offset}");
            assert_eq!(
                u32::from(ALIGNED[(offset % CHUNK) as usize]),
                want,
                "{offset}"
            );
        }
    }

    /// The chunk length `chunk_shift` picks keeps every attribute's chord (between exact
    /// values at the chunk's ends) within the attribute's tolerance of the exact
    /// perspective-correct values, on random spans whose `q` changes by up to 1:40 along them;
    /// and it is not needlessly short: spans with steep `q` take short chunks, those with
    /// constant `q` the longest.
    #[test]
    fn chunk_shift_keeps_chords_within_the_tolerance() {
        let mut next = crate::random(0x9e47_0002);
        let margin = f64::from(MARGIN);
        let mut shifts = [0usize; CHUNK_SHIFT as usize + 1];
        let mut worst: f64 = 0.0;
        for n in 0..20_000 {
            let len = 2 + (next() % 300) as u32;
            let q_start = 1.0 + (next() % u64::from(Q_MAX)) as f64;
            let ratio = (next() % 4000) as f64 / 100.0 + 1.0;
            let q_end = if next() % 2 == 0 {
                (q_start / ratio).max(1.0)
            } else {
                (q_start * ratio).min(f64::from(Q_MAX))
            };
            let q_end = if n % 10 == 0 { q_start } else { q_end };
            let mut lambda = |_: ()| {
                let a = (next() % 65_537) as f64 / 65_536.0;
                let b = (next() % 65_537) as f64 / 65_536.0 * (1.0 - a);
                [a, b]
            };
            let (ls, le) = (lambda(()), lambda(()));
            // Plane values (8.24 of the 16-bit scale) at the first pixel and their steps.
            let raw = |v: f64| ((v + margin) * 65_536.0).round() as u32;
            let start = [raw(q_start), raw(ls[0] * q_start), raw(ls[1] * q_start)];
            let end = [raw(q_end), raw(le[0] * q_end), raw(le[1] * q_end)];
            let step: [u32; 3] = core::array::from_fn(|k| {
                ((f64::from(end[k]) - f64::from(start[k])) / f64::from(len - 1)).round() as i64
                    as u32
            });
            let attribute =
                [next() as i32, next() as i32, next() as i32].map(|a| a >> (next() % 31));
            let c = Corrected::new(attribute);
            let tolerance = 1 + (next() % (1 << (next() % 16))) as u32;
            let room = chunk_room(start, step, tolerance, |k1, k2| c.slope(k1, k2));
            if step[0] == 0 || attribute[1] == attribute[0] && attribute[2] == attribute[0] {
                assert!(room >= NO_LIMIT);
            }
            // The exact attribute at pixel x of the span, from the planes as the fill has them.
            let [_, d1, d2] = c.parts().map(f64::from);
            let exact = |x: u32| {
                let v: [f64; 3] = core::array::from_fn(|k| {
                    f64::from(start[k].wrapping_add(step[k].wrapping_mul(x))) / 65_536.0 - margin
                });
                (v[1] / v[0] * d1 + v[2] / v[0] * d2, v[0])
            };
            if exact(0).1 < 1.0 || exact(len - 1).1 < 1.0 {
                continue;
            }
            let mut a = 0;
            while a + 1 < len {
                let q = start[0].wrapping_add(step[0].wrapping_mul(a));
                let shift = chunk_shift(room, q, step[0], len - a, a);
                shifts[shift as usize] += 1;
                let b = (a + (1 << shift)).min(len - 1);
                let (ea, eb) = (exact(a).0, exact(b).0);
                for x in a..=b {
                    let t = f64::from(x - a) / f64::from(b - a);
                    let off = (ea + (eb - ea) * t - exact(x).0).abs() / f64::from(tolerance);
                    worst = worst.max(off);
                    assert!(
                        off <= 1.0 + 1e-6,
                        "span {start:?} {step:?} len {len}, attribute {attribute:?} tolerance {tolerance}: room {room}, shift {shift}, pixel {x} off by {off} tolerances"
                    );
                }
                a = b;
            }
        }
        // Every length taken somewhere; the bound is used, not vacuous.
        assert!(shifts.iter().all(|&n| n > 100), "{shifts:?}");
        assert!(worst > 0.25, "{worst}");
        let mut v = 1u32;
        while v < u32::MAX / 3 {
            let exact = 16.0 * f64::from(v).log2();
            assert!(
                f64::from(log16_down(v)) <= exact && exact <= f64::from(log16_up(v)),
                "{v}"
            );
            let wide = u64::from(v) << (v % 33) | u64::from(v % 7);
            let exact = 16.0 * (wide as f64).log2();
            assert!(exact <= f64::from(log16_up_64(wide)), "{wide}");
            v = v * 3 / 2 + 1;
        }
    }

    /// Vertex values: each vertex's own barycentric plane is its q, the others 0; the largest q
    /// normalised into the top half of the range.
    #[test]
    fn attributes_normalise_q() {
        for q in [
            [1u64, 1, 1],
            [7, 70, 700],
            [u64::MAX, 1, 1 << 20],
            [0, 0, 0],
        ] {
            let a = attributes(q);
            let top = a.values.iter().map(|v| v[0] - MARGIN).max().unwrap();
            assert!((Q_MAX / 2..=Q_MAX).contains(&u32::from(top)), "{q:?}");
            for k in 0..3 {
                assert_eq!(a.values[k][1], if k == 1 { a.values[1][0] } else { MARGIN });
                assert_eq!(a.values[k][2], if k == 2 { a.values[2][0] } else { MARGIN });
            }
        }
    }
}
