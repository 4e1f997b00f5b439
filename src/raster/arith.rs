//! Integer arithmetic for the set-up, fast on every core and small on Cortex-M: full products of
//! 32-bit factors from 16-bit limbs where there is no long multiply (Cortex-M0), exact reciprocals
//! by a seed table and Newton steps (32-bit) or one quotient bit an iteration (64-bit) where there
//! is no divider, the rare 64-bit divisions on Cortex-M0 and 128-bit divisions of the general
//! set-up by shifting and subtracting (small routines instead of the library's kilobytes),
//! leading zeros by halving where there
//! is no `clz`. Each form is checked against the native operation on the host.

use core::num::{NonZeroU32, NonZeroU64};

use crate::arch::{FAST_WIDE_DIVISION, HAS_DIVIDER, NO_CLZ, NO_LONG_MULTIPLY};

/// `a · b` in full. Without a long multiply it is formed from 16-bit limbs ([`mul_32_limbs`]):
/// sixteen 32-bit multiplies instead of four 64-bit library calls.
#[inline]
pub(crate) fn mul_wide(a: u64, b: u64) -> u128 {
    if NO_LONG_MULTIPLY {
        mul_wide_limbs(a, b)
    } else {
        u128::from(a) * u128::from(b)
    }
}

/// `a · b` in full; without a long multiply from [`mul_i64_wide_parts`].
#[inline]
pub(crate) fn mul_i64_wide(a: i64, b: i64) -> i128 {
    if NO_LONG_MULTIPLY {
        mul_i64_wide_parts(a, b)
    } else {
        i128::from(a) * i128::from(b)
    }
}

/// [`mul_i64_wide`] from four 32 × 32 → 64-bit products of the magnitudes: library calls on
/// Cortex-M0, where [`mul_wide`]'s limbs are faster but this is smaller, for the general
/// set-up's rare products. One copy on Cortex-M0 (flash).
#[cfg_attr(armv6m, inline(never))]
#[cfg_attr(not(armv6m), inline)]
fn mul_i64_wide_parts(a: i64, b: i64) -> i128 {
    let (m, n) = (a.unsigned_abs(), b.unsigned_abs());
    let (m0, m1, n0, n1) = (m & 0xFFFF_FFFF, m >> 32, n & 0xFFFF_FFFF, n >> 32);
    let middle = u128::from(m0 * n1) + u128::from(m1 * n0);
    let p = ((u128::from(m1 * n1) << 64) + (middle << 32) + u128::from(m0 * n0)) as i128;
    // At most 2¹²⁶ in magnitude: the negation cannot overflow.
    if (a < 0) != (b < 0) {
        p.wrapping_neg()
    } else {
        p
    }
}

/// [`mul_wide`] from four 32 × 32 → 64-bit products of [`mul_32_limbs`].
#[inline]
fn mul_wide_limbs(a: u64, b: u64) -> u128 {
    let (a0, a1, b0, b1) = (a as u32, (a >> 32) as u32, b as u32, (b >> 32) as u32);
    let middle = u128::from(mul_32_limbs(a0, b1)) + u128::from(mul_32_limbs(a1, b0));
    (u128::from(mul_32_limbs(a1, b1)) << 64) + (middle << 32) + u128::from(mul_32_limbs(a0, b0))
}

/// `a · b` in full; without a long multiply from [`mul_32_limbs`] of the magnitudes.
#[inline]
pub(crate) fn mul_i32_wide(a: i32, b: i32) -> i64 {
    if NO_LONG_MULTIPLY {
        mul_i32_wide_limbs(a, b)
    } else {
        i64::from(a) * i64::from(b)
    }
}

/// [`mul_i32_wide`] from signed 16-bit limbs: `a = a₁·2¹⁶ + a₀` with `a₁ = a >> 16` signed and
/// `a₀` the low half unsigned, so `a₁·b₁` (at most 2³⁰ in magnitude), `a₁·b₀` and `a₀·b₁` (below
/// 2³¹) are exact `i32` products and `a₀·b₀` an exact `u32` one: four multiplies, no signs to
/// fix.
#[inline]
fn mul_i32_wide_limbs(a: i32, b: i32) -> i64 {
    let (a0, a1, b0, b1) = (a & 0xFFFF, a >> 16, b & 0xFFFF, b >> 16);
    let low = (a0 as u32) * (b0 as u32);
    let middle = i64::from(a1 * b0) + i64::from(a0 * b1);
    (i64::from(a1 * b1) << 32) + (middle << 16) + i64::from(low)
}

/// `a · b` in full for 32-bit unsigned factors: without a long multiply from
/// [`mul_32_limbs`] instead of a 64 × 64-bit library call.
#[inline]
pub(crate) fn mul_u32_wide(a: u32, b: u32) -> u64 {
    if NO_LONG_MULTIPLY {
        mul_32_limbs(a, b)
    } else {
        u64::from(a) * u64::from(b)
    }
}

/// `a · b` for `b ≤ 2³²` (and a product below 2⁶⁴); without a long multiply from
/// [`mul_32_limbs`] and a shift.
#[inline]
pub(crate) fn mul_u32_u33(a: u32, b: u64) -> u64 {
    if NO_LONG_MULTIPLY {
        mul_u32_u33_limbs(a, b)
    } else {
        u64::from(a).wrapping_mul(b)
    }
}

/// [`mul_u32_u33`] from limbs.
#[inline]
fn mul_u32_u33_limbs(a: u32, b: u64) -> u64 {
    let high = if b >> 32 != 0 { u64::from(a) << 32 } else { 0 };
    mul_32_limbs(a, b as u32).wrapping_add(high)
}

/// `g · d` modulo 2⁶⁴; without a long multiply from [`mul_32_limbs`] and one 32-bit product
/// instead of a 64 × 64-bit library call.
#[inline]
pub(crate) fn wrapping_mul_i32(g: i64, d: i32) -> i64 {
    if NO_LONG_MULTIPLY {
        wrapping_mul_i32_limbs(g, d)
    } else {
        g.wrapping_mul(i64::from(d))
    }
}

/// [`wrapping_mul_i32`] from limbs: `|d|` times the low word in full, times the high word modulo
/// 2³², then the sign.
#[inline]
fn wrapping_mul_i32_limbs(g: i64, d: i32) -> i64 {
    let m = d.unsigned_abs();
    let low = mul_32_limbs(g as u32, m);
    let high = ((g as u64 >> 32) as u32).wrapping_mul(m);
    let p = low.wrapping_add(u64::from(high) << 32) as i64;
    if d < 0 {
        p.wrapping_neg()
    } else {
        p
    }
}

/// `a · b` from four 16 × 16 → 32-bit products (each exact in a `u32`).
#[inline]
fn mul_32_limbs(a: u32, b: u32) -> u64 {
    let (a0, a1, b0, b1) = (a & 0xFFFF, a >> 16, b & 0xFFFF, b >> 16);
    let middle = u64::from(a0 * b1) + u64::from(a1 * b0);
    (u64::from(a1 * b1) << 32) + (middle << 16) + u64::from(a0 * b0)
}

/// First guesses `2^16 / (t + ½) − 256` for the top eight bits `t ∈ [128, 256)` of a
/// normalised 32-bit (or 16-bit) divisor (128 bytes of flash).
const RECIPROCAL_SEED_8: [u8; 128] = {
    let mut table = [0u8; 128];
    let mut i = 0;
    while i < 128 {
        // 2^16 / (t + ½), the interval's midpoint: in (256, 511), within 2⁻⁸ of 2^16 / d.
        let guess = (2u32 << 16) / (2 * (128 + i as u32) + 1);
        table[i] = (guess - 256) as u8;
        i += 1;
    }
    table
};

/// `⌊2^63 / d⌋` for `2^31 ≤ d < 2^32`: a hardware division on 64-bit hosts, two 32-bit
/// hardware divisions where there is a divider ([`reciprocal_63_by_digits`]), and
/// [`reciprocal_63_newton`] elsewhere (a 64-bit library division costs hundreds of instructions
/// on Cortex-M). All give the exact floor.
#[inline]
pub(crate) fn reciprocal_63(d: u32) -> u64 {
    if FAST_WIDE_DIVISION {
        (1u64 << 63) / u64::from(d.max(1))
    } else if HAS_DIVIDER {
        reciprocal_63_by_digits(d)
    } else {
        reciprocal_63_newton(d)
    }
}

/// [`reciprocal_63`] from two 32-bit divisions: schoolbook division of 2⁶³ by `d` in 16-bit
/// digits, each digit estimated from `d`'s top half and corrected by its exact remainder (one
/// 32 × 32 → 64-bit product; a multiply instruction where there is a divider).
#[inline]
fn reciprocal_63_by_digits(d: u32) -> u64 {
    if d <= 1 << 31 {
        // 2³², the one quotient that does not fit 32 bits (and the floor for smaller inputs).
        return 1 << 32;
    }
    // d > 2³¹: the top half is at least 2¹⁵.
    let high = NonZeroU32::new(d >> 16).unwrap_or(NonZeroU32::MIN);
    // The digit ⌊rem·2¹⁶/d⌋ and its remainder, for rem < d. The estimate rem/high exceeds the
    // digit by less than rem·2¹⁶/(high·d) < 2¹⁶/high ≤ 2, so `e`, its product with d (below
    // 2¹⁷·2³²) less rem·2¹⁶, is in (−d, 2d): the digit is the estimate less [e > 0] + [e > d],
    // and the remainder, below d, the low word of c·d − e.
    let digit = |rem: u32| {
        let q = rem / high;
        let e = (u64::from(q) * u64::from(d)).wrapping_sub(u64::from(rem) << 16) as i64;
        let c = u32::from(e > 0) + u32::from(e > i64::from(d));
        (q.wrapping_sub(c), c.wrapping_mul(d).wrapping_sub(e as u32))
    };
    // 2⁶³ = 2³¹·2³² with 2³¹ < d: two digits below 2¹⁶ each; the next digits of the dividend
    // are 0.
    let (q1, rem) = digit(1 << 31);
    let (q0, _) = digit(rem);
    u64::from(q1) << 16 | u64::from(q0)
}

/// [`reciprocal_63`] without a division or a long multiply: the reciprocal `y = ⌊2³¹ / h⌋` of
/// `d`'s top half `h ∈ [2¹⁵, 2¹⁶)` ([`reciprocal_31`], 32-bit products), `x₀ = y·2¹⁶`, one
/// Newton step, then an exact correction of the remainder.
///
/// With `d = h·2¹⁶ + l` and `R = 2⁶³ / d`: `2⁴⁷ / (h + 1) < R ≤ 2⁴⁷ / h` and `x₀ ∈ (2⁴⁷ / h −
/// 2¹⁶, 2⁴⁷ / h]`, so `x₀ − R ∈ (−2¹⁶, 2¹⁷]` and the error term `e = 2⁶³ − d·x₀` is within
/// `±2⁴⁹` (exact in the wrapping 64-bit product). The step `x₁ = x₀ + ⌊y·⌊e / 2²⁰⌋ / 2²⁷⌋` (the
/// Newton step's `x₀·e / 2⁶³` from `e`'s top bits, a 32 × 32-bit product) leaves `R − x₁`
/// within `R·(2⁻¹⁴)² + 2` (under 18), a few units for most `d`; the remainder `2⁶³ − d·x₁`
/// then steps `x₁` to the floor. For `d ≤ 2³¹`, `2³²` (the floor for `d = 2³¹`).
fn reciprocal_63_newton(d: u32) -> u64 {
    if d <= 1 << 31 {
        return 1 << 32;
    }
    // d > 2³¹: the top half is at least 2¹⁵, and y at most 2¹⁶.
    let high = NonZeroU32::new(d >> 16).unwrap_or(NonZeroU32::MIN);
    // d·x modulo 2⁶⁴ for x < 2³³ (one 32 × 32-bit product and an addition: no 64 × 64-bit
    // library call).
    let error = |x: u64| (1u64 << 63).wrapping_sub(mul_u32_u33(d, x)) as i64;
    let mut x = reciprocal_63_estimate(d, reciprocal_31(high));
    // A few units off at most: step to the exact floor.
    let mut rem = error(x);
    while rem < 0 {
        x -= 1;
        rem += d as i64;
    }
    while rem >= d as i64 {
        x += 1;
        rem -= d as i64;
    }
    x
}

/// The Newton step of [`reciprocal_63_newton`] from `y = ⌊2³¹ / h⌋` for `d`'s top half `h`:
/// `x₁`, within 18 below or above `⌊2⁶³ / d⌋` for `d > 2³¹` (the test checks the bound).
#[inline(always)]
fn reciprocal_63_estimate(d: u32, y: u32) -> u64 {
    let x0 = u64::from(y) << 16;
    // d·x₀ = (d₁·y)·2³² + (d₀·y)·2¹⁶ for d's halves (y ≤ 2¹⁶: each product fits 32 bits).
    let (high, low) = ((d >> 16) * y, (d & 0xFFFF) * y);
    let product = (u64::from(high) << 32).wrapping_add(u64::from(low) << 16);
    // |e| ≤ 2⁴⁹: e / 2²⁰ fits an i32, and y·(e / 2²⁰) is below 2⁴⁶ in magnitude.
    let e = (1u64 << 63).wrapping_sub(product) as i64;
    x0.wrapping_add((mul_i32_wide(y as i32, (e >> 20) as i32) >> 27) as u64)
}

/// `⌊2³¹ / q⌋` for `0 < q < 2¹⁶` without a division (the perspective chunks' reciprocal on
/// ARMv6-M, `raster::perspective::lambdas`, where [`div_rem_u32`] takes a loop iteration a
/// quotient bit: 17 to 18 of them, about 400 instructions, for the usual `q ∈ [2¹⁴, 2¹⁶)`): a
/// seed from [`RECIPROCAL_SEED_8`], one Newton step, the quotient of its remainder from the
/// same reciprocal, and one exact correction. All in 32-bit integers (five `muls`, no long
/// product): on Cortex-M0 38 instructions with the call for `q ≥ 2¹⁵` (one more when the
/// correction adds), about 4 more a halving below. Exact for every `q < 2¹⁶` (the test checks
/// them all); a larger `q` gives some value (no panic, no division).
///
/// Let `R = 2³¹ / q` (real) and `d = q·2ˢ ∈ [2¹⁵, 2¹⁶)` (`s ≤ 15`), so `R = 2³¹⁺ˢ / d`.
///
/// 1. Seed: `d`'s top byte `t ∈ [128, 256)` gives `g = ⌊2¹⁷ / (2t + 1)⌋ ≈ 2²⁴ / d` within a
///    relative `ε < 2⁻⁷` (half the byte's interval, `2⁻⁸`, plus the floor's, under `2⁻⁸`): the
///    error term `e = 2²⁴ − g·d` has `|e| < 2¹⁷` (at most 93 696), and `x₀ = g·2⁷⁺ˢ ≈ R`.
/// 2. Newton: `x₁ = ⌊x₀ + x₀·(2³¹ − q·x₀) / 2³¹⌋ = ⌊g·(2²⁴ + e) / 2¹⁷⁻ˢ⌋`, as `q·x₀ = 2⁷·g·d`.
///    It is formed at a fixed scale as `f = g·2²² + ⌊g·e / 4⌋` (`|g·e| < 2²⁶`), so `x₁ = ⌊f /
///    2¹⁵⁻ˢ⌋` (nested floors by powers of two are one floor). With `x₀ = R(1 − ε)` the step gives
///    `R(1 − ε²)` before the floor: `x₁ ≤ R` (so `f ≤ 2⁴⁶ / d ≤ 2³¹`, no overflow) and `R − x₁ <
///    R·ε² + 1`. The remainder `e₁ = 2³¹ − q·x₁ = q·(R − x₁)` is then in `[0, 2¹⁷ + 2¹⁶)` (at
///    most 127 508), exact in the wrapping 32-bit product.
/// 3. Remainder: `⌊R⌋ = x₁ + ⌊e₁ / q⌋`, and `e₁ / q = e₁·2ˢ / d` with `2³⁰ / d ≈ z = ⌊f / 2¹⁶⌋
///    ≤ 2¹⁵` (`x₁`'s top bits, within a relative `2⁻¹⁴`): `c = ⌊⌊e₁ / 2⌋·z / 2²⁹⁻ˢ⌋`, the product
///    under `2¹⁷·2¹⁵`. Every truncation rounds down, so `c ≤ e₁ / q`: `x₁ + c ≤ ⌊R⌋`, and the
///    remainder `2³¹ − q·(x₁ + c) = e₁ − q·c ≥ 0`. `c` (the shortfall `R − x₁`, at most 32 767) is
///    short by under `c·2⁻¹⁴` from `z` and under 1 from each floor: a few units at most, and by the
///    exhaustive test never more than one.
/// 4. Correction: one more if that remainder is still `q` or more.
#[cfg_attr(armv6m, inline(never))]
pub(crate) fn reciprocal_31(q: NonZeroU32) -> u32 {
    let q = q.get();
    let (x, remainder) = reciprocal_31_estimate(q);
    x.wrapping_add(u32::from(remainder >= q))
}

/// Steps 1 to 3 of [`reciprocal_31`] for `0 < q < 2¹⁶`: `(x, 2³¹ − q·x)` with `x ≤ ⌊2³¹ /
/// q⌋ ≤ x + 1`.
#[inline(always)]
fn reciprocal_31_estimate(q: u32) -> (u32, u32) {
    // d = q·2ˢ in [2¹⁵, 2¹⁶) and k = 15 − s, a bit a step (no `clz` on ARMv6-M): no step for
    // the usual q ≥ 2¹⁵ (a triangle's largest q is in [32 640, 65 279], the others below it by
    // its w ratio), fifteen for q = 1. The loop ends for any q > 0; the mask tells the compiler that the
    // shifts below are in range.
    let (mut d, mut k) = (q, 15);
    while d >> 15 == 0 {
        d <<= 1;
        k -= 1;
    }
    let k = k & 15;
    // Index t − 128 by a mask: in range for any d, no bounds check.
    let g = RECIPROCAL_SEED_8
        .get((d >> 8) as usize & 127)
        .map_or(256, |&seed| 256 + u32::from(seed));
    let e = (1u32 << 24).wrapping_sub(d.wrapping_mul(g)) as i32;
    // 2¹⁵⁻ˢ·x₁ before its floor (step 2).
    let f = (g << 22).wrapping_add(((g as i32).wrapping_mul(e) >> 2) as u32);
    let x = f >> k;
    let e1 = (1u32 << 31).wrapping_sub(q.wrapping_mul(x));
    // ⌊e₁ / q⌋ by the reciprocal's top bits, never over (step 3).
    let c = ((e1 >> 1).wrapping_mul(f >> 16)) >> (14 + k);
    (x.wrapping_add(c), e1.wrapping_sub(q.wrapping_mul(c)))
}

/// Whether a rare loop has steps left, counting `left` down to 0: the count is hidden from the
/// optimiser at every step, so the loop keeps one body instead of several unrolled copies
/// (flash on Cortex-M; these loops run only in rare set-ups).
#[inline(always)]
fn rare_step(left: &mut u32) -> bool {
    let more = core::hint::black_box(*left) != 0;
    *left = left.wrapping_sub(1);
    more
}

/// `⌊2^125 / d⌋` for `2^63 ≤ d < 2^64`: the library division on 64-bit hosts; elsewhere one
/// quotient bit an iteration in 64-bit arithmetic (a 128-bit library division costs thousands
/// of instructions and several kilobytes of flash on Cortex-M0).
pub(crate) fn reciprocal_125(d: u64) -> u64 {
    if FAST_WIDE_DIVISION {
        return ((1u128 << 125) / u128::from(d.max(1))) as u64;
    }
    // 2^125 = 2^63 · 2^62: the first partial remainder is 2^63, then 62 zero bits follow.
    let (mut q, mut r) = (0u64, 1u64 << 63);
    if r >= d {
        (q, r) = (1, r.wrapping_sub(d));
    }
    let mut left = 62;
    while rare_step(&mut left) {
        // r < d < 2^64, so 2r < 2^65: with the carry out, 2r ≥ d and 2r − d < d wraps exactly.
        let carry = r >> 63 != 0;
        r <<= 1;
        q <<= 1;
        if carry || r >= d {
            r = r.wrapping_sub(d);
            q |= 1;
        }
    }
    q
}

/// `⌊n / d⌋` for `d > 0`, exactly (any `i128`; the quotient wraps only for `i128::MIN / 1`'s
/// magnitude, whose wrapped value is the true one).
pub(crate) fn div_floor_wide(n: i128, d: i128) -> i128 {
    let (q, r) = div_rem_wide(n.unsigned_abs(), d.unsigned_abs());
    let q = q as i128;
    if n >= 0 {
        q
    } else if r == 0 {
        q.wrapping_neg()
    } else {
        q.wrapping_neg().wrapping_sub(1)
    }
}

/// `(⌊n / d⌋, n mod d)` for `d > 0`: the library division on 64-bit hosts, [`div_rem_shifting`]
/// elsewhere (on Cortex-M the library's 128-bit division is several kilobytes of flash, and
/// the set-up divides in 128 bits only for rare triangles).
#[inline]
pub(crate) fn div_rem_wide(n: u128, d: u128) -> (u128, u128) {
    if FAST_WIDE_DIVISION {
        let d = d.max(1);
        (n / d, n % d)
    } else {
        div_rem_shifting(n, d)
    }
}

/// [`div_rem_wide`] by shifting and subtracting: one bit of `n` an iteration (leading zero words
/// skipped).
#[inline(never)]
fn div_rem_shifting(n: u128, d: u128) -> (u128, u128) {
    // `q` holds the bits of `n` still to come at the top and the quotient's bits below them.
    let (mut q, mut r) = (n, 0u128);
    let mut bits = 128;
    while bits > 0 && q >> 96 == 0 {
        q <<= 32;
        bits -= 32;
    }
    while rare_step(&mut bits) {
        // r < d: with the carry out, 2r + 1 ≥ d and the wrapping difference is exact.
        let carry = r >> 127 != 0;
        r = (r << 1) | (q >> 127);
        q <<= 1;
        if carry || r >= d {
            r = r.wrapping_sub(d);
            q |= 1;
        }
    }
    (q, r)
}

/// `round(n / d)` (halves up) modulo 2³², for `d > 0`: what wrapping 32-bit attribute planes
/// keep of a quotient. Exact for any `n` and `d`; on 32-bit cores, divisors below 2⁶⁴ (every
/// triangle's doubled area but those of vertices 2²³ pixels apart) take
/// [`div_rem_low32`], which carries only a 64-bit remainder and the quotient's low 32 bits:
/// about a third of the full 128-bit division's instructions on a Cortex-M0.
pub(crate) fn div_round_wrapping(n: i128, d: i128) -> u32 {
    round_wrapping(n, d, !FAST_WIDE_DIVISION)
}

/// [`div_round_wrapping`], by [`div_rem_low32`] for divisors below 2⁶⁴ if `low32`.
#[inline(always)]
fn round_wrapping(n: i128, d: i128, low32: bool) -> u32 {
    let d = d.max(1);
    let magnitude = n.unsigned_abs();
    // ⌊|n| / d⌋ modulo 2³² and |n| mod d.
    let (q, r) = match u64::try_from(d) {
        Ok(d64) if low32 => {
            let (q, r) = div_rem_low32(magnitude, d64);
            (q, u128::from(r))
        }
        _ => {
            let (q, r) = div_rem_wide(magnitude, d.unsigned_abs());
            (q as u32, r)
        }
    };
    let d = d.unsigned_abs();
    // ⌊n / d⌋ and its remainder in [0, d).
    let (floor, r) = if n >= 0 || r == 0 {
        (if n >= 0 { q } else { q.wrapping_neg() }, r)
    } else {
        (q.wrapping_neg().wrapping_sub(1), d - r)
    };
    // Halves up: one more where 2r ≥ d (r < d < 2¹²⁷: no overflow).
    floor.wrapping_add(u32::from(2 * r >= d))
}

/// `(⌊n / d⌋ mod 2³², n mod d)` for `d > 0`, by shifting and subtracting: one bit of `n` an
/// iteration, taken from its 32-bit words (leading zero words skipped), a 64-bit remainder, the
/// quotient's bits above the low 32 dropped as they are shifted out.
#[inline(never)]
fn div_rem_low32(n: u128, d: u64) -> (u32, u64) {
    let (mut q, mut r) = (0u32, 0u64);
    let words = [
        (n >> 96) as u32,
        (n >> 64) as u32,
        (n >> 32) as u32,
        n as u32,
    ];
    let mut started = false;
    for word in words {
        started |= word != 0;
        if !started {
            continue;
        }
        let (mut w, mut bits) = (word, 32);
        while rare_step(&mut bits) {
            // r < d: with the carry out, 2r + 1 ≥ d and the wrapping difference is exact.
            let carry = r >> 63 != 0;
            r = (r << 1) | u64::from(w >> 31);
            w <<= 1;
            q <<= 1;
            if carry || r >= d {
                r = r.wrapping_sub(d);
                q |= 1;
            }
        }
    }
    (q, r)
}

/// `(⌊n / d⌋, n mod d)`: the library division where there is a 32-bit divider (ARMv7-M builds
/// the 64-bit one from it; hosts have the instruction), [`div_rem_u64_shifting`] on ARMv6-M,
/// where the library's 64-bit division is nearly a kilobyte of flash and only rare set-ups divide
/// in 64 bits (the general walk's boundaries, the gradients of compact slivers).
#[inline]
pub(crate) fn div_rem_u64(n: u64, d: NonZeroU64) -> (u64, u64) {
    if HAS_DIVIDER {
        (n / d, n % d)
    } else {
        div_rem_u64_shifting(n, d.get())
    }
}

/// [`div_rem_u64`] by shifting and subtracting: one bit of `n` an iteration, from the top.
#[inline(never)]
fn div_rem_u64_shifting(n: u64, d: u64) -> (u64, u64) {
    // `q` holds the bits of `n` still to come at the top and the quotient's bits below them.
    let (mut q, mut r) = (n, 0u64);
    let mut left = 64;
    while rare_step(&mut left) {
        // r < d: with the carry out, 2r + 1 ≥ d and the wrapping difference is exact.
        let carry = r >> 63 != 0;
        r = (r << 1) | (q >> 63);
        q <<= 1;
        if carry || r >= d {
            r = r.wrapping_sub(d);
            q |= 1;
        }
    }
    (q, r)
}

/// `(⌊n / d⌋, n mod d)` in 32 bits: the instruction where there is a divider,
/// [`div_rem_u32_aligned`] on ARMv6-M (the library's routine is 400 bytes of flash).
#[inline]
pub(crate) fn div_rem_u32(n: u32, d: NonZeroU32) -> (u32, u32) {
    if HAS_DIVIDER {
        (n / d, n % d)
    } else {
        div_rem_u32_aligned(n, d)
    }
}

/// [`div_rem_u32`] by shifting and subtracting, one quotient bit an iteration: the divisor is
/// first doubled up to the dividend's magnitude, so a quotient of `q` bits takes `q` steps (the
/// walk's set-up divides for columns and slopes, mostly of a few bits).
#[cfg_attr(not(armv6m), allow(dead_code))]
#[inline(never)]
fn div_rem_u32_aligned(n: u32, d: NonZeroU32) -> (u32, u32) {
    let (mut shifted, mut bits) = (d.get(), 0);
    // shifted ≤ n / 2 before each doubling: no overflow, and at most 31 doublings of d ≥ 1.
    while shifted <= n >> 1 {
        shifted <<= 1;
        bits += 1;
    }
    let (mut q, mut r) = (0u32, n);
    loop {
        q <<= 1;
        if r >= shifted {
            r -= shifted;
            q |= 1;
        }
        if bits == 0 {
            break;
        }
        shifted >>= 1;
        bits -= 1;
    }
    (q, r)
}

/// Leading zero bits of `v > 0`: by halving steps on ARMv6-M (Cortex-M0 has no `clz`
/// instruction; the library routine is a call of about the same length), the instruction
/// elsewhere.
#[inline]
pub(crate) fn leading_zeros_32(v: u32) -> u32 {
    if NO_CLZ {
        leading_zeros_by_halving(v)
    } else {
        v.leading_zeros()
    }
}

/// The leading zeros of a 64-bit value, from [`leading_zeros_32`] of its halves (no library
/// call where there is no `clz`).
#[inline]
pub(crate) fn leading_zeros_64(v: u64) -> u32 {
    let high = (v >> 32) as u32;
    if high != 0 {
        leading_zeros_32(high)
    } else {
        32 + leading_zeros_32(v as u32)
    }
}

/// [`leading_zeros_32`] by halving steps.
#[inline]
fn leading_zeros_by_halving(mut v: u32) -> u32 {
    let mut zeros = 0;
    for bits in [16, 8, 4, 2, 1] {
        if v >> (32 - bits) == 0 {
            v <<= bits;
            zeros += bits;
        }
    }
    zeros
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The aligned 32-bit division against the instruction, at the ends of the range and at
    /// random.
    #[test]
    fn aligned_division_matches_the_instruction() {
        let mut next = crate::random(0x5eed_d1f1_u64);
        let edges = [0, 1, 2, 3, 255, 256, 1 << 31, u32::MAX - 1, u32::MAX];
        let check = |n: u32, d: u32| {
            if let Some(nz) = NonZeroU32::new(d) {
                assert_eq!(div_rem_u32_aligned(n, nz), (n / d, n % d), "{n} / {d}");
            }
        };
        for n in edges {
            for d in edges {
                check(n, d);
            }
        }
        for i in 0..200_000 {
            let n = next() as u32;
            let d = (next() as u32) >> (i % 32);
            check(n, d);
        }
    }

    /// The full products by parts against the native ones, at the ends of the range and at
    /// random.
    #[test]
    fn products_by_parts_are_exact() {
        let mut next = crate::random(0x9a27_5c0d_e000_0001);
        let edges = [
            0,
            1,
            -1,
            2,
            i64::MAX,
            i64::MIN,
            i64::MIN + 1,
            1 << 32,
            -(1 << 32) - 1,
        ];
        let check = |a: i64, b: i64| {
            assert_eq!(
                mul_i64_wide_parts(a, b),
                i128::from(a) * i128::from(b),
                "{a} {b}"
            );
        };
        for a in edges {
            for b in edges {
                check(a, b);
            }
        }
        for i in 0..200_000 {
            check(next() as i64 >> (i % 64), (next() as i64) >> (i / 64 % 64));
        }
    }

    #[test]
    fn halving_counts_leading_zeros() {
        for v in (0..32).flat_map(|k| [1u32 << k, (1u32 << k) | 1, u32::MAX >> k]) {
            assert_eq!(leading_zeros_by_halving(v), v.leading_zeros(), "{v}");
        }
    }

    #[test]
    fn reciprocal_is_exact() {
        let mut rng = crate::rng::Rng(0x9e37_79b9_7f4a_7c15_u64);
        let check = |d: u64| {
            let d = d | 1 << 63;
            assert_eq!(
                u128::from(reciprocal_125(d)),
                (1u128 << 125) / u128::from(d),
                "{d:#x}"
            );
        };
        for d in [0, 1, u64::MAX, u64::MAX >> 1, 1 << 62, (1 << 62) + 1] {
            check(d);
        }
        for _ in 0..100_000 {
            let seed = rng.next();
            check(seed);
            check(seed >> 40);
            check(seed | (u64::MAX >> 30));
        }
    }

    /// The wrapping rounded quotient (both the 64-bit-remainder routine and the full division)
    /// against `i128` arithmetic: `⌊(2n + d) / 2d⌋` modulo 2³².
    #[test]
    fn wrapping_rounded_quotients_are_exact() {
        let mut rng = crate::rng::Rng(0x2545_f491_4f6c_dd1d);
        for i in 0..100_000 {
            let n = (((u128::from(rng.next()) << 64) | u128::from(rng.next()))
                >> (rng.below(40) + 26)) as i128;
            let n = if i % 2 == 0 { n } else { -n };
            let d = (u128::from(rng.next()) << 2 | 3) >> rng.below(64);
            let d = d.max(1) as i128;
            let want = (2 * n + d).div_euclid(2 * d) as u32;
            assert_eq!(round_wrapping(n, d, true), want, "{n} / {d}");
            assert_eq!(round_wrapping(n, d, false), want, "{n} / {d}");
            let d64 = d as u64;
            assert_eq!(
                div_rem_low32(n.unsigned_abs(), d64),
                (
                    (n.unsigned_abs() / u128::from(d64)) as u32,
                    (n.unsigned_abs() % u128::from(d64)) as u64
                ),
                "{n} / {d64}"
            );
        }
        // Divisors of 2⁶⁴ and more take the full division.
        let d = (1i128 << 64) + 12_345;
        for n in [
            d * 7 + d / 2,
            -(d * 7 + d / 2),
            -(d * 7 + d / 2) - 1,
            1 << 100,
        ] {
            for low32 in [true, false] {
                assert_eq!(
                    round_wrapping(n, d, low32),
                    (2 * n + d).div_euclid(2 * d) as u32
                );
            }
        }
    }

    #[test]
    fn wide_division_by_shifting_is_exact() {
        let mut rng = crate::rng::Rng(0x9e37_79b9_7f4a_7c15_u64);
        let wide = |rng: &mut crate::rng::Rng| {
            let v = (u128::from(rng.next()) << 64) | u128::from(rng.next());
            v >> rng.below(128)
        };
        for _ in 0..100_000 {
            let (n, d) = (wide(&mut rng), wide(&mut rng).max(1));
            assert_eq!(div_rem_shifting(n, d), (n / d, n % d), "{n} / {d}");
            let n = n as i128;
            let d = (d >> 1).max(1) as i128;
            assert_eq!(div_floor_wide(n, d), n.div_euclid(d), "{n} / {d}");
        }
        for (n, d) in [
            (0, 1),
            (u128::MAX, 1),
            (u128::MAX, u128::MAX),
            (1 << 125, 3),
            (5, 7),
        ] {
            assert_eq!(div_rem_shifting(n, d), (n / d, n % d), "{n} / {d}");
        }
        assert_eq!(div_floor_wide(i128::MIN, 1), i128::MIN);
        assert_eq!(div_floor_wide(-7, 2), -4);
    }

    #[test]
    fn division_of_64_bits_by_shifting_is_exact() {
        let mut rng = crate::rng::Rng(0xbb67_ae85_84ca_a73b_u64);
        let check = |n: u64, d: u64| {
            assert_eq!(div_rem_u64_shifting(n, d), (n / d, n % d), "{n} / {d}");
            let nonzero = NonZeroU64::new(d).unwrap();
            assert_eq!(div_rem_u64(n, nonzero), (n / d, n % d), "{n} / {d}");
        };
        for _ in 0..200_000 {
            let n = rng.next() >> rng.below(64);
            let d = (rng.next() >> rng.below(64)).max(1);
            check(n, d);
            check(n, (d >> 32).max(1));
        }
        for (n, d) in [
            (0, 1),
            (u64::MAX, 1),
            (u64::MAX, u64::MAX),
            (u64::MAX - 1, u64::MAX),
            (u64::MAX, 1 << 63),
            ((1 << 63) - 1, 1 << 63),
            (1 << 59, 3),
            (u64::from(u32::MAX), u64::from(u32::MAX) + 1),
            (5, 7),
        ] {
            check(n, d);
        }
    }

    #[test]
    fn limb_products_are_exact() {
        let mut rng = crate::rng::Rng(0x3c6e_f372_fe94_f82b_u64);
        for _ in 0..100_000 {
            let (a, b) = (rng.next() >> rng.below(64), rng.next() >> rng.below(64));
            assert_eq!(
                mul_wide_limbs(a, b),
                u128::from(a) * u128::from(b),
                "{a} {b}"
            );
            assert_eq!(mul_wide(a, b), u128::from(a) * u128::from(b));
        }
        for (a, b) in [(u64::MAX, u64::MAX), (0, u64::MAX), (1 << 63, 3)] {
            assert_eq!(mul_wide_limbs(a, b), u128::from(a) * u128::from(b));
        }
    }

    #[test]
    fn narrow_full_products_match_native() {
        let mut rng = crate::rng::Rng(0xa54f_f53a_5f1d_36f1_u64);
        for _ in 0..200_000 {
            let (a, b) = (
                (rng.next() as i32) >> rng.below(32),
                (rng.next() as i32) >> rng.below(32),
            );
            assert_eq!(
                mul_i32_wide_limbs(a, b),
                i64::from(a) * i64::from(b),
                "{a} {b}"
            );
            let c = rng.next() % ((1 << 32) + 1);
            assert_eq!(
                mul_u32_u33_limbs(a as u32, c),
                u64::from(a as u32) * c,
                "{a} {c}"
            );
        }
        assert_eq!(mul_i32_wide_limbs(i32::MIN, i32::MIN), 1 << 62);
        assert_eq!(
            mul_u32_u33_limbs(u32::MAX, 1 << 32),
            u64::from(u32::MAX) << 32
        );
    }

    #[test]
    fn narrow_wrapping_products_match_native() {
        let mut rng = crate::rng::Rng(0x3c6e_f372_fe94_f82b_u64);
        for _ in 0..200_000 {
            let g = rng.next() as i64;
            let d = (rng.next() as i32) >> rng.below(32);
            assert_eq!(
                wrapping_mul_i32_limbs(g, d),
                g.wrapping_mul(i64::from(d)),
                "{g} {d}"
            );
        }
        for (g, d) in [
            (i64::MIN, -1),
            (i64::MAX, i32::MIN),
            (-1, i32::MIN),
            (0, -5),
        ] {
            assert_eq!(wrapping_mul_i32_limbs(g, d), g.wrapping_mul(i64::from(d)));
        }
    }

    /// The division-free `⌊2³¹ / q⌋` of every 16-bit `q`: exact, its estimate never above the
    /// quotient and at most one below (the one correction step suffices).
    #[test]
    fn reciprocal_31_is_the_exact_floor_for_every_q() {
        for q in 1..=u16::MAX {
            let exact = (1u32 << 31) / u32::from(q);
            let (x, remainder) = reciprocal_31_estimate(q.into());
            assert!(x <= exact && exact - x <= 1, "{q}: {x}");
            assert_eq!(remainder, (1u32 << 31) - u32::from(q) * x, "{q}");
            if let Some(q) = NonZeroU32::new(q.into()) {
                assert_eq!(reciprocal_31(q), exact, "{q}");
            }
        }
    }

    #[test]
    fn reciprocal_63_is_the_exact_floor() {
        let mut rng = crate::rng::Rng(0x6a09_e667_f3bc_c908_u64);
        let check = |d: u32| {
            let exact = (1u64 << 63) / u64::from(d);
            assert_eq!(reciprocal_63_newton(d), exact, "{d}");
            assert_eq!(reciprocal_63_by_digits(d), exact, "{d}");
        };
        for d in [1 << 31, (1 << 31) + 1, 3 << 30, u32::MAX - 1, u32::MAX] {
            check(d);
        }
        for t in 256..512u32 {
            check(t << 23);
            check((t << 23) - 1 + (1 << 23));
        }
        for _ in 0..200_000 {
            check((rng.next() as u32) | 1 << 31);
        }
    }

    /// The Newton step before the correction is within its documented 18 of the floor: at the
    /// ends of every top half's range and at random (the correction's loops stay short).
    #[test]
    fn reciprocal_63_estimate_is_close() {
        let mut rng = crate::rng::Rng(0xbb67_ae85_84ca_a73b_u64);
        let mut worst = 0;
        let mut check = |d: u32| {
            let exact = (1u64 << 63) / u64::from(d);
            let y = (1u32 << 31) / (d >> 16);
            let off = reciprocal_63_estimate(d, y).abs_diff(exact);
            assert!(off < 18, "{d}: {off}");
            worst = worst.max(off);
        };
        for h in (1u32 << 15)..(1 << 16) {
            check(h << 16 | 1);
            check(h << 16 | 0xFFFF);
        }
        for _ in 0..200_000 {
            check((rng.next() as u32) | 1 << 31);
        }
        assert!(worst > 0);
    }
}
