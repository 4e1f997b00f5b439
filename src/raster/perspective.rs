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

use super::arith::{div_rem_u32, leading_zeros_64, reciprocal_31};
use super::plane::Attributes;
use crate::arch::{HAS_DIVIDER, NO_LONG_MULTIPLY};
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

/// The pixels a span's corrected values are computed at: every [`CHUNK`] pixels from its first,
/// and at its last; the values between are stepped from them.
pub(crate) const CHUNK: u32 = 16;

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
/// `(b − a) / n`, a shift for whole chunks, a product by [`INVERSE`] (within a unit) else.
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

/// The chunks of a span from the perspective planes' values at its first pixel: [`CHUNK`]
/// pixels each, the last one shorter; one [`lambdas`] a chunk.
#[derive(Debug, Clone)]
pub(crate) struct Chunks {
    /// The planes' values at the current chunk's first pixel.
    values: [u32; 3],
    step: [u32; 3],
    at: (Lambda, Lambda),
    left: u32,
}

impl Chunks {
    /// The chunks of a span of `len` pixels whose perspective planes' values start at `values`
    /// and step by `step` a pixel.
    #[inline(always)]
    pub(crate) fn new(values: [u32; 3], step: [u32; 3], len: u32) -> Self {
        Chunks {
            values,
            step,
            at: lambdas(values),
            left: len,
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
        let (len, over) = if self.left > CHUNK {
            (CHUNK, CHUNK)
        } else {
            (self.left, self.left - 1)
        };
        let values: [u32; 3] =
            core::array::from_fn(|k| self.values[k].wrapping_add(self.step[k].wrapping_mul(over)));
        let end = if over == 0 { start } else { lambdas(values) };
        self.values = values;
        self.at = end;
        self.left -= len;
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
