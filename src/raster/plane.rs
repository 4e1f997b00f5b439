//! Attribute planes: barycentric interpolation by fixed-point stepping.
//!
//! An attribute with vertex values `c_k` is the plane `c(p) = Σ c_k E_k(p) / (2·area)`, where
//! `E_k` is the exact edge function opposite vertex `k`, evaluated at pixel centres. Vertex
//! values are [`Attributes`]: 8.8 fixed point of an 8-bit scale (colour channels `c << 8`, 16-bit
//! depths and barycentrics as they are) with a rounding offset each.
//!
//! * [`Planes`] — the one stepped form every walk uses: each attribute's value at the walk's
//!   first pixel and its per-pixel and per-row gradients, 24 fractional bits (of the 8-bit scale),
//!   wrapping, so the value at a pixel is the same integer modulo 2³² however it is reached. Built
//!   by the compact set-up (`Planes::compact`: gradients from one 32-bit reciprocal of the area,
//!   within 2⁻¹⁰ of a unit over a compact region) or the general one ([`GeneralPlanes::new`]:
//!   the exact quotients rounded to the nearest 2⁻²⁴, under 2⁻²⁵ a pixel of distance, below
//!   2⁻⁹ over the largest region it takes, 2¹⁶ px across). With the +½ offset every channel is
//!   within ½ LSB plus that error of the exact value.
//! * [`ExactPlanes`] — the general set-up's exact values: at any pixel, the quotient rounded to
//!   the nearest 2⁻²⁴ (one `i128` division, of which only the low 32 bits are kept). The
//!   stepped planes of the general set-up come from it; regions over 2¹⁶ px across start each
//!   span chunk of at most [`MAX_CHUNK`] pixels from it, so stepping adds at most 2⁻¹³ LSB.
//! * `InverseArea` — one reciprocal of the area for the 3D pipeline's normal planes.

use crate::fixed_point::SUBPIXEL_BITS;
use core::num::NonZeroU64;

use crate::raster::arith::{
    div_floor_wide, div_rem_u64, div_rem_wide, div_round_wrapping, leading_zeros_32, mul_i32_wide,
    mul_u32_u33, mul_wide, reciprocal_125, reciprocal_63, wrapping_mul_i32,
};
use crate::raster::compact::CompactSetup;
use crate::raster::edge::{dot2, TriangleSetup};
use crate::raster::walk::Region;

/// Fractional bits of the attribute values the walk hands out (8.24 fixed point: attributes have
/// at most 8 integer bits, so a value fits a `u32`).
pub const STEP_BITS: u32 = 24;

/// Longest run of pixels stepped from one exact restart.
pub const MAX_CHUNK: u32 = 4096;

/// Largest region (`width + height + 2`) the stepped path is used for.
const MAX_STEPPED_EXTENT: i64 = 1 << 16;

/// `round(n / d)` (halves up) for `d > 0`, never panicking.
#[inline(never)]
#[cold]
fn div_round(n: i128, d: i128) -> i128 {
    div_floor_wide(n.saturating_mul(2).saturating_add(d), d.saturating_mul(2))
}

/// `1 / area2` for the quadratic normal planes of the 3D pipeline, normalised so that one
/// division per triangle serves every numerator.
///
/// `recip = ⌊2^shift / area2⌋` with `shift = 61 + bitlen(area2)`, so `2^61 < recip ≤ 2^62` (a
/// `u64`) and `num · 2^k / area2` is `|num| · recip >> (shift − k)` with a relative error below
/// 2⁻⁶¹: one 64 × 64 → 128-bit product. Numerators of 64 bits or more fall back to an exact `i128`
/// division.
#[derive(Debug, Clone, Copy)]
pub(crate) struct InverseArea {
    area2: i128,
    recip: u64,
    shift: u32,
}

impl InverseArea {
    /// The reciprocal of a triangle's doubled area (`area2 > 0`, as in [`TriangleSetup`]).
    pub(crate) fn new(area2: i128) -> Self {
        // |area2| < 2^65 for any Coord vertices, so shift ≤ 126.
        let bits = 128 - area2.leading_zeros();
        let shift = 61 + bits;
        let magnitude = area2.unsigned_abs();
        let recip = if (1..=64).contains(&bits) {
            // floor(2^(61+n) / area2) = floor(2^125 / d) for the normalised d = area2·2^(64−n).
            reciprocal_125((magnitude as u64) << (64 - bits))
        } else {
            // 2^126 / area2 < 2^62 for the 65-bit areas of vertices 2³¹ sub-pixels apart.
            match 1u128.checked_shl(shift) {
                Some(n) if magnitude > 0 => div_rem_wide(n, magnitude).0 as u64,
                _ => 0,
            }
        };
        InverseArea {
            area2,
            recip,
            shift,
        }
    }

    /// `round(num · 2^k / area2)`, for `k ≤ 40`.
    // One copy for every caller (flash on Cortex-M; a call per attribute and triangle).
    #[inline(never)]
    pub(crate) fn scale(&self, num: i128, k: u32) -> i128 {
        let s = self.shift.saturating_sub(k);
        let magnitude = num.unsigned_abs();
        if magnitude < 1 << 64 && s > 0 && s < 128 && self.recip > 0 {
            // < 2^64 · 2^62: no overflow; rounded half away from zero.
            let product = mul_wide(magnitude as u64, self.recip);
            let q = ((product >> (s - 1)) + 1) >> 1;
            // q < 2^126.
            if num < 0 {
                -(q as i128)
            } else {
                q as i128
            }
        } else {
            div_round(num << k, self.area2)
        }
    }
}

/// The vertex values a triangle's planes interpolate: `N` attributes per vertex in 8.8 fixed point
/// of the 8-bit scale the planes hand out (a colour channel `c` is `c << 8`; a 16-bit depth `d` is
/// `d` itself, 1/256 of that scale), and each plane's rounding offset: half of the unit its
/// consumer truncates to (`1 << 23` for a channel read as `value >> 24`, `1 << 15` for a depth
/// read as `value >> 16`), so that truncation rounds to nearest.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Attributes<const N: usize> {
    pub(crate) values: [[u16; N]; 3],
    pub(crate) half: [u32; N],
}

impl<const N: usize> Attributes<N> {
    /// Colour channels (per vertex), each rounded to its own integer unit.
    #[inline(always)]
    pub(crate) fn channels(channels: [[u8; N]; 3]) -> Self {
        Attributes {
            values: channels.map(|c| c.map(|v| u16::from(v) << 8)),
            half: [1 << (STEP_BITS - 1); N],
        }
    }

    /// The values of attribute `k` at the three vertices.
    #[inline(always)]
    pub(crate) fn vertex_values(&self, k: usize) -> [u16; 3] {
        self.values.map(|v| v.get(k).copied().unwrap_or(0))
    }
}

/// Stepped attribute planes: each attribute's value at the walk's first pixel (its region's
/// top-left pixel centre) and its per-pixel and per-row gradients, in
/// [`STEP_BITS`] = 24 fractional bits with the +½ rounding offset,
/// wrapping modulo 2³².
///
/// Wrapping makes the value at `(column, row)` the same integer modulo 2³² however it is
/// reached, and covered pixels have values in `[0, 256)·2²⁴`, so the wrapped value is the true
/// one. The error against the exact plane, before the final truncation, is below 2⁻⁹ LSB
/// everywhere a walk asks (see [`Planes::compact`] and [`GeneralPlanes::new`]), so every attribute
/// is within ½ LSB + 2⁻⁹ of the exact value.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Planes<const N: usize> {
    value: [u32; N],
    dx: [u32; N],
    dy: [u32; N],
}

impl<const N: usize> Planes<N> {
    /// The planes through `values` (per input vertex) of the compact triangle set up as `setup`.
    ///
    /// The barycentric gradients of oriented vertices 1 and 2, `256·a/area2` per pixel, are
    /// found to 32 fractional bits ([`GradientScale`]) within `U` units, where `U·X < 2¹³` for
    /// pixels within `X` pixels of vertex 0; an attribute's gradient is `Σ (cₖ − c₀)·gₖ`, within
    /// `510·U` units of 2⁻³² (`U·2⁻²³` LSB a pixel), and its value at a pixel is `c₀` plus the
    /// gradients times the offset from vertex 0 (at most `X` pixels): the error stays below
    /// 2⁻¹⁰ LSB. Everything wraps modulo
    /// 2⁶⁴ and then 2³²: only the low bits of a huge gradient matter for the (in-range) covered
    /// values.
    #[inline(always)]
    pub(crate) fn compact(setup: &CompactSetup, attributes: &Attributes<N>) -> Self {
        if N == 0 && crate::arch::NO_LONG_MULTIPLY {
            // No attributes (solid fills): no gradients. Where the gradients' reciprocal and
            // products are library calls (Cortex-M0) the compiler cannot drop them unused;
            // elsewhere it does, and the test would only move code.
            return Self::zero();
        }
        let scale = GradientScale::new(setup.area2, setup.reach);
        let gx = setup.a.map(|a| scale.of(a));
        let gy = setup.b.map(|b| scale.of(b));
        let [c0, c1, c2] = setup
            .order
            .map(|k| attributes.values.get(k).copied().unwrap_or([0; N]));
        let (px, py) = (setup.dx, setup.dy);
        let vertices = [c0, c1, c2];
        Self::compact_narrow((gx, gy), (px, py), vertices, &attributes.half)
            .unwrap_or_else(|| Self::compact_wide((gx, gy), (px, py), vertices, &attributes.half))
    }

    /// [`compact`](Self::compact) from the barycentric gradients `(gx, gy)`, the offset
    /// `(px, py)` of the first pixel from vertex 0 and the oriented vertices' values.
    #[inline(always)]
    fn compact_wide(
        (gx, gy): ([i64; 2], [i64; 2]),
        (px, py): (i32, i32),
        [c0, c1, c2]: [[u16; N]; 3],
        half: &[u32; N],
    ) -> Self {
        // Products of 32-bit factors: no 64 × 64-bit library calls on Cortex-M0.
        let mul = wrapping_mul_i32;
        let planes: [[u32; 3]; N] = core::array::from_fn(|k| {
            let base = i32::from(c0[k]);
            let (d1, d2) = (i32::from(c1[k]) - base, i32::from(c2[k]) - base);
            // 2⁻⁴⁰ units (of the 8-bit scale; the values are 8.8) per pixel.
            let sx = mul(gx[0], d1).wrapping_add(mul(gx[1], d2));
            let sy = mul(gy[0], d1).wrapping_add(mul(gy[1], d2));
            // Value at the first centre, 2⁻⁴⁸ units: c₀ + (sx·px + sy·py) / 256 (px, py in
            // sub-pixels).
            let v = (i64::from(base) << 40)
                .wrapping_add(mul(sx, px))
                .wrapping_add(mul(sy, py));
            let to_step = |u: i64, bits: u32| (u.wrapping_add(1 << (bits - 1)) >> bits) as u32;
            [
                to_step(v, 24).wrapping_add(half[k]),
                to_step(sx, 16),
                to_step(sy, 16),
            ]
        });
        Planes {
            value: planes.map(|p| p[0]),
            dx: planes.map(|p| p[1]),
            dy: planes.map(|p| p[2]),
        }
    }

    /// Planes all zero, to [`set`](Self::set).
    #[inline(always)]
    pub(crate) fn zero() -> Self {
        Planes {
            value: [0; N],
            dx: [0; N],
            dy: [0; N],
        }
    }

    /// Sets attribute `k`'s value at the first pixel and its per-pixel and per-row steps.
    #[inline(always)]
    pub(crate) fn set(&mut self, k: usize, value: u32, dx: u32, dy: u32) {
        if let (Some(v), Some(x), Some(y)) = (
            self.value.get_mut(k),
            self.dx.get_mut(k),
            self.dy.get_mut(k),
        ) {
            (*v, *x, *y) = (value, dx, dy);
        }
    }

    /// [`compact`](Self::compact) for triangles whose barycentric gradients `(gx, gy)` are below
    /// 2³¹ units in magnitude (no slivers): the same integers from 32 × 32-bit products, and the
    /// value at the first pixel (offset `(px, py)` from vertex 0) as `c₀ + Σ dₖ·Lₖ` from the
    /// barycentrics `Lₖ = gxₖ·px + gyₖ·py` (exact, below 2⁵¹), modulo 2⁶⁴ like `compact`'s
    /// `sx·px + sy·py`. `None` for the others. Not on Cortex-M0, where its flash is dearer
    /// than its speed: the result is the same.
    #[inline(always)]
    fn compact_narrow(
        (gx, gy): ([i64; 2], [i64; 2]),
        (px, py): (i32, i32),
        [c0, c1, c2]: [[u16; N]; 3],
        half: &[u32; N],
    ) -> Option<Self> {
        if crate::arch::NO_LONG_MULTIPLY {
            return None;
        }
        let narrow = |g: i64| i32::try_from(g).ok();
        let (Some(gx0), Some(gx1), Some(gy0), Some(gy1)) =
            (narrow(gx[0]), narrow(gx[1]), narrow(gy[0]), narrow(gy[1]))
        else {
            return None;
        };
        // 2⁻⁴⁰ units: gradients (2⁻³² a pixel) times offsets (sub-pixels).
        let l1 = mul_i32_wide(gx0, px) + mul_i32_wide(gy0, py);
        let l2 = mul_i32_wide(gx1, px) + mul_i32_wide(gy1, py);
        let mut planes = Planes {
            value: [0; N],
            dx: [0; N],
            dy: [0; N],
        };
        for k in 0..N {
            let base = i32::from(c0[k]);
            let (d1, d2) = (i32::from(c1[k]) - base, i32::from(c2[k]) - base);
            // |d| ≤ 2¹⁶ and |g| < 2³¹: the sums are below 2⁴⁸, exact, as in `compact`.
            let step = |g1: i32, g2: i32| {
                ((mul_i32_wide(g1, d1) + mul_i32_wide(g2, d2) + (1 << 15)) >> 16) as u32
            };
            // 2⁻⁴⁸ units, modulo 2⁶⁴: d₁·L₁ + d₂·L₂ = sx·px + sy·py.
            let v = (i64::from(base) << 40)
                .wrapping_add(wrapping_mul_i32(l1, d1))
                .wrapping_add(wrapping_mul_i32(l2, d2));
            planes.value[k] = ((v.wrapping_add(1 << 23) >> 24) as u32).wrapping_add(half[k]);
            planes.dx[k] = step(gx0, gx1);
            planes.dy[k] = step(gy0, gy1);
        }
        Some(planes)
    }

    /// The per-pixel steps.
    #[inline(always)]
    pub(crate) fn step(&self) -> [u32; N] {
        self.dx
    }

    /// The per-row steps.
    #[inline(always)]
    pub(crate) fn row_step(&self) -> [u32; N] {
        self.dy
    }

    /// The values at the first pixel.
    #[inline(always)]
    pub(crate) fn first(&self) -> [u32; N] {
        self.value
    }

    /// The planes of the values at the first pixel and the per-pixel and per-row steps (those
    /// [`first`](Self::first), [`step`](Self::step) and [`row_step`](Self::row_step) give).
    #[inline(always)]
    pub(crate) fn from_parts(value: [u32; N], dx: [u32; N], dy: [u32; N]) -> Self {
        Planes { value, dx, dy }
    }

    /// The planes from `rows` rows below the first pixel on: their `at(column, row)` is this
    /// one's `at(column, rows + row)`, the same integers modulo 2³² (a band's walk that starts
    /// lower than the region).
    #[inline(always)]
    pub(crate) fn advanced(&self, rows: u32) -> Self {
        Planes {
            value: self.at(0, rows),
            dx: self.dx,
            dy: self.dy,
        }
    }

    /// The values `column` pixels right of and `row` rows below the first pixel.
    #[inline(always)]
    pub(crate) fn at(&self, column: u32, row: u32) -> [u32; N] {
        core::array::from_fn(|k| {
            self.value[k]
                .wrapping_add(self.dy[k].wrapping_mul(row))
                .wrapping_add(self.dx[k].wrapping_mul(column))
        })
    }
}

/// `n·2⁴⁰ / area2` for `|n| < 2¹⁹` and `0 < area2 < 2³⁸` (a barycentric gradient per pixel,
/// 2⁻³² units), from one 32-bit reciprocal of the area per triangle, within `2¹²/X + 1` units
/// for a triangle whose pixels lie within `X` pixels (x plus y) of its vertex 0 — so that over
/// those pixels the gradient's error adds up to at most `2¹² + X` units-pixels, below 2¹³.
///
/// The area is normalised to `d ∈ [2³¹, 2³²)` and `r = ⌊2⁶³/d⌋` is exact ([`reciprocal_63`]);
/// `|n|·r` (below 2⁵¹) shifted back gives the quotient. Areas of 2³² or more are shifted right
/// by at most 6 bits (a relative change below 2⁻³¹) and their quotients are below 2²⁷, so the
/// result is within `2⁻³⁰·2²⁷ + ½`. Smaller areas are shifted left by `t` bits, exactly, and
/// the floor of `r` costs at most `|n|·2^(t−23)` units: within the bound while
/// `|n|·X ≤ 2^(35−t)`, which small triangles meet whatever their shape. Larger numerators (long
/// thin triangles of small area) are refined: the remainder of that estimate, below 2³⁰, times
/// `r` gives the rest of the quotient, and one correction makes it the exactly rounded
/// `⌊(|n|·2⁴⁰ + ⌊area2/2⌋) / area2⌋` — no division. Only areas below 2⁹ (1/128 px²), where
/// `t > 23`, divide.
#[derive(Debug, Clone, Copy)]
struct GradientScale {
    area2: NonZeroU64,
    r: u64,
    shift: u32,
    /// The plain estimate serves numerators `m` with `m·reach ≤ limit`.
    limit: u32,
    reach: u32,
    /// Half of `2^shift`: rounds the plain estimate.
    half: u64,
}

impl GradientScale {
    /// The scale of `area2`, for pixels within `reach` (below 2¹³) of vertex 0.
    #[inline]
    fn new(area2: NonZeroU64, reach: u32) -> Self {
        let (area, area2) = (area2, area2.get());
        let (d, shift, limit) = if area2 >> 32 == 0 {
            let t = leading_zeros_32(area2 as u32);
            if t > 23 {
                // Below 2⁹: every numerator but 0 divides.
                return GradientScale {
                    area2: area,
                    r: 0,
                    shift: 0,
                    limit: 0,
                    reach,
                    half: 0,
                };
            }
            // 2^(35−t), and every m·reach < 2³² for t < 4.
            let limit = u32::try_from((1u64 << 35) >> t).unwrap_or(u32::MAX);
            ((area2 << t) as u32, 23 - t, limit)
        } else {
            // area2 < 2³⁸: at most 6 bits to drop.
            let mut s = 1;
            while area2 >> (32 + s) != 0 {
                s += 1;
            }
            ((area2 >> s) as u32, 23 + s, u32::MAX)
        };
        GradientScale {
            area2: area,
            r: reciprocal_63(d),
            shift,
            limit,
            reach,
            half: (1u64 << shift) >> 1,
        }
    }

    // One copy for the four gradients on Cortex-M0 (flash); inlined elsewhere.
    #[cfg_attr(armv6m, inline(never))]
    #[cfg_attr(not(armv6m), inline(always))]
    fn of(&self, n: i32) -> i64 {
        let m = n.unsigned_abs();
        // m < 2¹⁹ and reach < 2¹³: the product fits.
        let q = if m * self.reach <= self.limit {
            // m < 2¹⁹ and r ≤ 2³²: the product fits.
            (mul_u32_u33(m, self.r) + self.half) >> self.shift
        } else {
            self.exact(m)
        };
        let q = q as i64;
        if crate::arch::MCU {
            if n < 0 {
                q.wrapping_neg()
            } else {
                q
            }
        } else {
            // Without a branch on hosts: the signs of a triangle's gradients are random.
            let sign = i64::from(n >> 31);
            (q ^ sign).wrapping_sub(sign)
        }
    }

    /// `⌊(m·2⁴⁰ + ⌊area2/2⌋) / area2⌋` for the numerators the plain estimate does not serve
    /// (long thin triangles of small area): out of line, so that it costs the common case
    /// nothing.
    #[cold]
    #[inline(never)]
    fn exact(&self, m: u32) -> u64 {
        let area2 = self.area2.get();
        // The same quotient by division for the tiniest areas, and on Cortex-M0, where the
        // refinement's 64-bit products cost flash the compact path does not have.
        if self.r == 0 || crate::arch::NO_LONG_MULTIPLY {
            return div_rem_u64((u64::from(m) << 40) + area2 / 2, self.area2).0;
        }
        // Here 4 ≤ t ≤ 23 (the limit admits every m < 2¹⁹ for smaller t) and area2 < 2^(32−t).
        // q0 is at most the exact quotient and below it by under m·2^(t−23) + 1, so the
        // remainder is below (m·2^(t−23) + 3)·area2 < 2³⁰, and rem·r < 2⁶².
        let q0 = mul_u32_u33(m, self.r) >> self.shift;
        let rem = (u64::from(m) << 40) + (area2 >> 1) - q0.wrapping_mul(area2);
        // r·2^(t−63) is 1/area2 rounded down: c is the quotient or one below it.
        let c = rem.wrapping_mul(self.r) >> (40 + self.shift);
        let left = rem - c.wrapping_mul(area2);
        q0 + c + u64::from(left >= area2)
    }
}

/// The planes of the general set-up: stepped where their error bound holds, else exact.
#[derive(Debug, Clone, Copy)]
pub(crate) enum GeneralPlanes<'a, const N: usize> {
    /// The stepped planes (every walk's form), from the region's first pixel.
    Stepped(Planes<N>),
    /// The exact planes, for regions more than 2¹⁶ pixels across (borrowed: moved, they
    /// would be copied).
    Exact(&'a ExactPlanes<N>),
}

impl<'a, const N: usize> GeneralPlanes<'a, N> {
    /// The planes of `exact` (the exact planes of a triangle over `region`) a walk uses.
    ///
    /// The value at the region's first pixel and the gradients are the exact quotients rounded
    /// to the nearest 2⁻²⁴ ([`ExactPlanes`]), wrapping: the value `(x, y)` pixels away is off
    /// by under 2⁻²⁵·(1 + x + y), below 2⁻⁹ LSB over regions up to 2¹⁶ pixels across (width
    /// plus height). Larger regions take the exact planes. Steep gradients need nothing else:
    /// the covered pixels' values are in range, and wrapping keeps them exact there.
    #[inline]
    pub(crate) fn new(exact: &'a ExactPlanes<N>, region: &Region) -> Self {
        if N == 0 {
            // No attributes (solid fills): nothing to step, whatever the region.
            GeneralPlanes::Stepped(Planes::zero())
        } else if region.width() + region.height() <= MAX_STEPPED_EXTENT {
            GeneralPlanes::Stepped(Planes {
                value: exact.at(region.x0, region.y0),
                dx: exact.step,
                dy: exact.row_step(),
            })
        } else {
            GeneralPlanes::Exact(exact)
        }
    }
}

/// The exact planes of [`Attributes`] over a region, in the units of [`Planes`]: the value at
/// any pixel is the exact quotient `Σ cₖ·Eₖ / area2` rounded to the nearest 2⁻²⁴ (one `i128`
/// division), the gradients likewise. Regions over 2¹⁶ pixels across start every span chunk
/// of at most [`MAX_CHUNK`] pixels from [`at`](Self::at), so stepping adds at most 2⁻¹³ LSB;
/// the stepped planes of smaller ones come from it ([`GeneralPlanes::new`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ExactPlanes<const N: usize> {
    /// `Σ cₖ·Eₖ` at the region's first pixel centre and its gradients per sub-pixel
    /// ([`gradient`]), per attribute.
    n: [i128; N],
    nx: [i64; N],
    ny: [i64; N],
    /// The per-pixel steps.
    step: [u32; N],
    half: [u32; N],
    area2: i128,
    /// The region's first pixel.
    x0: i32,
    y0: i32,
}

impl<const N: usize> ExactPlanes<N> {
    /// The planes of `attributes` on the triangle `setup` over `region`.
    #[inline(always)]
    pub(crate) fn new(setup: &TriangleSetup, region: &Region, attributes: &Attributes<N>) -> Self {
        let mut planes = Self::empty();
        planes.set_up(setup, region, attributes);
        planes
    }

    /// Sets these planes up for `attributes` on the triangle `setup` over `region`, in place
    /// (built elsewhere and moved, they would be copied).
    #[inline(always)]
    fn set_up(&mut self, setup: &TriangleSetup, region: &Region, attributes: &Attributes<N>) {
        let planes = self;
        (planes.half, planes.area2) = (attributes.half, setup.area2);
        (planes.x0, planes.y0) = (region.x0, region.y0);
        // The region's first pixel centre from oriented vertex 0, sub-pixels: both within
        // 2³¹, so below 2³³.
        let (vx, vy) = setup.oriented[0];
        let centre = |p: i32, v: i32| (i64::from(p) << SUBPIXEL_BITS) + (1 << 7) - i64::from(v);
        let (px, py) = (centre(region.x0, vx), centre(region.y0, vy));
        for k in 0..N {
            let (n, nx, ny) = exact_numerators(setup, (px, py), attributes.vertex_values(k));
            let step = planes.quotient(per_pixel(nx));
            if let (Some(slot), Some(x), Some(y), Some(s)) = (
                planes.n.get_mut(k),
                planes.nx.get_mut(k),
                planes.ny.get_mut(k),
                planes.step.get_mut(k),
            ) {
                (*slot, *x, *y, *s) = (n, nx, ny, step);
            }
        }
    }

    /// Attribute planes of no triangle.
    pub(crate) fn empty() -> Self {
        ExactPlanes {
            n: [0; N],
            nx: [0; N],
            ny: [0; N],
            step: [0; N],
            half: [0; N],
            area2: 1,
            x0: 0,
            y0: 0,
        }
    }

    /// `numerator / area2` rounded to the nearest integer, modulo 2³².
    // One copy for all attributes: a division of up to 2¹⁰² by up to 2⁶⁵, of which only the
    // low 32 bits are kept.
    #[inline(never)]
    fn quotient(&self, numerator: i128) -> u32 {
        div_round_wrapping(numerator, self.area2)
    }

    /// The per-pixel steps.
    pub(crate) fn step(&self) -> [u32; N] {
        self.step
    }

    /// The per-row steps.
    fn row_step(&self) -> [u32; N] {
        core::array::from_fn(|k| self.quotient(per_pixel(self.ny.get(k).copied().unwrap_or(0))))
    }

    /// The values at pixel `(x, y)` of the region.
    pub(crate) fn at(&self, x: i32, y: i32) -> [u32; N] {
        // Offsets within the region: below 2²⁵, so the numerator stays below 2⁸⁵ before the
        // 16-bit shift to the planes' 2⁻²⁴ units (8.8 values).
        let column = i64::from(x) - i64::from(self.x0);
        let row = i64::from(y) - i64::from(self.y0);
        core::array::from_fn(|k| {
            let (n, nx, ny) = (
                self.n.get(k).copied().unwrap_or(0),
                self.nx.get(k).copied().unwrap_or(0),
                self.ny.get(k).copied().unwrap_or(0),
            );
            let n = n + (dot2(nx, column, ny, row, false) << SUBPIXEL_BITS);
            // The attributes' rounding offsets added.
            self.quotient(n << (STEP_BITS - 8))
                .wrapping_add(self.half.get(k).copied().unwrap_or(0))
        })
    }
}

/// `Σ cₖ·Eₖ` at the pixel centre `(px, py)` from oriented vertex 0 and the numerator gradients
/// (see [`gradient`]) of the plane through `values`.
// One copy for every attribute on Cortex-M0 (flash: its `i128` products are long there).
#[cfg_attr(armv6m, inline(never))]
#[cfg_attr(not(armv6m), inline(always))]
fn exact_numerators(
    setup: &TriangleSetup,
    (px, py): (i64, i64),
    values: [u16; 3],
) -> (i128, i64, i64) {
    let (c0, nx, ny) = gradient(setup, values);
    // c₀·area2 + nx·px + ny·py < 2⁸¹ + 2⁸²: Σ cₖ·Eₖ at the first pixel centre (the edges
    // through vertex 0 vanish at it).
    (
        i128::from(c0) * setup.area2 + dot2(nx, px, ny, py, false),
        nx,
        ny,
    )
}

/// The numerator of a gradient per pixel in the planes' units from its numerator gradient per
/// sub-pixel of the 8.8 values (see [`gradient`]): 2⁸ sub-pixels a pixel, 2¹⁶ more fractional
/// bits. Below 2⁷⁴.
#[inline(always)]
fn per_pixel(n: i64) -> i128 {
    i128::from(n) << (SUBPIXEL_BITS + STEP_BITS - 8)
}

/// `(c₀, nx, ny)`: the value at oriented vertex 0 and the numerator gradients `Σ c_k·a_k`,
/// `Σ c_k·b_k` of the plane through `values` (in input vertex order).
#[inline]
pub(crate) fn gradient(setup: &TriangleSetup, values: [u16; 3]) -> (i64, i64, i64) {
    // Oriented vertex values; Σ a_k = Σ b_k = 0, so Σ c_k·a_k = (c₁−c₀)·a₁ + (c₂−c₀)·a₂,
    // below 2⁵⁰ in magnitude for 16-bit values: exact in i64.
    let c = setup
        .order
        .map(|v| i64::from(values.get(v).copied().unwrap_or(0)));
    let (e1, e2) = (setup.edge(1), setup.edge(2));
    let (d1, d2) = (c[1] - c[0], c[2] - c[0]);
    (c[0], d1 * e1.a + d2 * e2.a, d1 * e1.b + d2 * e2.b)
}

/// Test support: attribute values against the exact barycentric interpolation.
#[cfg(test)]
pub(crate) mod exact {
    /// Checks the values `at(column, row)` of the channel planes of the triangle `v` (raw
    /// sub-pixel vertices) with channel values `channels` over the pixels `x0 ..= x0 + last`,
    /// `y0 ..= y0 + rows` against the exact rationals (`i128`), modulo 2³² (the covered pixels'
    /// values are in range, so wrapping is exact there): within 2⁻¹⁰ LSB of the exact value
    /// before the final truncation. Returns the values checked.
    pub(crate) fn check_channel_planes<const K: usize>(
        v: [(i32, i32); 3],
        channels: &[[u8; K]; 3],
        (x0, y0, last, rows): (i32, i32, u32, u32),
        at: impl Fn(u32, u32) -> [u32; K],
    ) -> u64 {
        let p = v.map(|(x, y)| (i128::from(x), i128::from(y)));
        let cross = |o: (i128, i128), a: (i128, i128), b: (i128, i128)| {
            (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
        };
        let area2 = cross(p[0], p[1], p[2]);
        let modulus = area2.abs() << 32;
        let mut checked = 0;
        for row in 0..=rows {
            for column in 0..=last {
                let q = (
                    i128::from(x0 + column as i32) * 256 + 128,
                    i128::from(y0 + row as i32) * 256 + 128,
                );
                // λₖ·area2 = the edge function of the opposite edge at q.
                let lambda = [
                    cross(q, p[1], p[2]),
                    cross(q, p[2], p[0]),
                    cross(q, p[0], p[1]),
                ];
                let got = at(column, row);
                for k in 0..K {
                    let exact: i128 = (0..3).map(|m| i128::from(channels[m][k]) * lambda[m]).sum();
                    // (got − ½ − exact) · area2, in 2⁻²⁴ units, reduced modulo 2³²·area2.
                    let mut err = ((i128::from(got[k]) - (1 << 23)) * area2 - (exact << 24))
                        .rem_euclid(modulus);
                    if err > modulus / 2 {
                        err -= modulus;
                    }
                    // Within 2⁻¹⁰ LSB: |err| ≤ 2¹⁴ · |area2|.
                    assert!(
                        err.abs() <= area2.abs() << 14,
                        "{v:?} {channels:?} ({column}, {row}) channel {k}: error {} units",
                        err as f64 / area2.abs() as f64
                    );
                    checked += 1;
                }
            }
        }
        checked
    }
}

#[cfg(test)]
mod tests {
    /// The narrow planes are the wide ones, bit for bit, wherever they apply.
    #[test]
    fn narrow_planes_equal_wide_ones() {
        let mut next = crate::random(0x1f83_d9ab_fb41_bd6b);
        let mut narrow = 0;
        for _ in 0..200_000 {
            let area2 = NonZeroU64::new((next() >> (26 + next() % 38)).max(1)).unwrap();
            let reach = 2 + (next() % 4097) as u32;
            let scale = GradientScale::new(area2, reach);
            let mut n = || {
                let m = (next() >> (45 + next() % 19)) as i32;
                if next() & 1 == 0 {
                    m
                } else {
                    -m
                }
            };
            let a = [n(), n()];
            let b = [n(), n()];
            let (gx, gy) = (a.map(|a| scale.of(a)), b.map(|b| scale.of(b)));
            let px = (next() % (1 << 20)) as i32 - (1 << 19);
            let py = (next() % (1 << 20)) as i32 - (1 << 19);
            let values: [[u16; 3]; 3] =
                core::array::from_fn(|_| core::array::from_fn(|_| next() as u16));
            let half = [1 << 23, 1 << 15, 7];
            let wide = Planes::compact_wide((gx, gy), (px, py), values, &half);
            if let Some(p) = Planes::compact_narrow((gx, gy), (px, py), values, &half) {
                assert_eq!((p.value, p.dx, p.dy), (wide.value, wide.dx, wide.dy));
                narrow += 1;
            }
        }
        assert!(narrow > 20_000, "{narrow}");
    }

    use super::*;
    use crate::Coord;
    use embedded_graphics::{prelude::*, primitives::Rectangle};

    /// The general set-up's exact planes of one attribute with vertex values `values` (+½ LSB)
    /// over `clip`.
    fn plane(
        v: [(i32, i32); 3],
        values: [u16; 3],
        clip: Rectangle,
    ) -> Option<(ExactPlanes<1>, TriangleSetup, Region)> {
        let setup = TriangleSetup::new(v.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y))))?;
        let region = Region::new(&setup, &clip)?;
        let attributes = Attributes {
            values: values.map(|v| [v]),
            half: [1 << (STEP_BITS - 1)],
        };
        let planes = ExactPlanes::new(&setup, &region, &attributes);
        Some((planes, setup, region))
    }

    /// The exact planes' values are the exact rational value (`i128` cross products of the
    /// vertices at each pixel centre) rounded to the nearest 2⁻²⁴, for triangles of any size
    /// and pixels anywhere in the region.
    #[test]
    fn exact_values_are_the_rounded_plane() {
        let mut next = crate::random(0x2545_f491_4f6c_dd1d);
        let clip = Rectangle::new(Point::new(-20, -10), Size::new(40, 30));
        let mut checked = 0;
        for i in 0..6_000 {
            let range = 1i64 << (8 + i % 24);
            let mut r = || ((next() % (2 * range as u64 + 1)) as i64 - range) as i32;
            let v = [(); 3].map(|_| (r(), r()));
            let values = [(); 3].map(|_| next() as u16);
            let Some((p, _, region)) = plane(v, values, clip) else {
                continue;
            };
            let q = v.map(|(x, y)| (i128::from(x), i128::from(y)));
            let cross = |o: (i128, i128), a: (i128, i128), b: (i128, i128)| {
                (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
            };
            let area2 = cross(q[0], q[1], q[2]);
            let corners = [
                (region.x0, region.y0),
                (region.x1, region.y1),
                (region.x0, region.y1),
            ];
            for (x, y) in corners {
                let c = (i128::from(x) * 256 + 128, i128::from(y) * 256 + 128);
                let lambda = [
                    cross(c, q[1], q[2]),
                    cross(c, q[2], q[0]),
                    cross(c, q[0], q[1]),
                ];
                let n: i128 = (0..3).map(|k| i128::from(values[k]) * lambda[k]).sum();
                // n / area2 (8.8) in 2⁻²⁴ units of the 8-bit scale, rounded half up, +½ LSB.
                let (n, d) = if area2 < 0 { (-n, -area2) } else { (n, area2) };
                let want = ((n << 17) + d).div_euclid(2 * d) as u32;
                assert_eq!(
                    p.at(x, y)[0],
                    want.wrapping_add(1 << 23),
                    "{v:?} {values:?} ({x}, {y})"
                );
                checked += 1;
            }
        }
        assert!(checked > 10_000, "{checked}");
    }

    /// The general set-up's stepped planes against the exact rationals at every pixel of the
    /// region, for triangles from a pixel to the whole `Coord` range over a small clip,
    /// slivers whose gradients wrap many times included.
    #[test]
    fn general_planes_are_within_the_documented_error() {
        let mut next = crate::random(0x9e37_79b9_7f4a_7c15_u64);
        let clip = Rectangle::new(Point::new(-7, 5), Size::new(24, 18));
        let (mut checked, mut slivers) = (0, 0);
        for i in 0..4_000 {
            let range = 1i64 << (8 + i % 24);
            let mut r = || ((next() % (2 * range as u64 + 1)) as i64 - range) as i32;
            let mut v = [(); 3].map(|_| (r(), r()));
            if i % 3 == 0 {
                // A sliver: the third vertex a sub-pixel off the line through the others.
                let (a, b) = (v[0], v[1]);
                v[2] = ((a.0 / 2 + b.0 / 2) + 1, (a.1 / 2 + b.1 / 2));
            }
            let channels: [[u8; 3]; 3] =
                core::array::from_fn(|_| next().to_le_bytes()[..3].try_into().unwrap());
            let Some(setup) =
                TriangleSetup::new(v.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y))))
            else {
                continue;
            };
            let Some(region) = Region::new(&setup, &clip) else {
                continue;
            };
            let exact = ExactPlanes::new(&setup, &region, &Attributes::channels(channels));
            let GeneralPlanes::Stepped(p) = GeneralPlanes::new(&exact, &region) else {
                panic!("a small region takes the stepped planes: {v:?}");
            };
            if setup.area2 < 1 << 16 && region.width() > 1 {
                slivers += 1;
            }
            let (last, rows) = ((region.width() - 1) as u32, (region.height() - 1) as u32);
            checked += exact::check_channel_planes(
                v,
                &channels,
                (region.x0, region.y0, last, rows),
                |column, row| p.at(column, row),
            );
        }
        assert!(
            checked > 100_000 && slivers > 100,
            "{checked} values, {slivers} slivers"
        );
    }

    /// Regions more than 2¹⁶ pixels across take the exact planes, whose steps start each chunk.
    #[test]
    fn huge_regions_take_the_exact_planes() {
        let clip = Rectangle::new(Point::new(-70_000, -10), Size::new(140_000, 20));
        let v = [(-80_000 * 256, 0), (80_000 * 256, 256), (0, 9 * 256)];
        let setup =
            TriangleSetup::new(v.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y)))).unwrap();
        let region = Region::new(&setup, &clip).unwrap();
        let attributes = Attributes::channels([[0, 9, 200], [255, 3, 7], [40, 40, 40]]);
        let exact = ExactPlanes::new(&setup, &region, &attributes);
        let GeneralPlanes::Exact(p) = GeneralPlanes::new(&exact, &region) else {
            panic!("a region {} pixels wide", region.width());
        };
        // Stepping MAX_CHUNK pixels from an exact value stays within 2⁻¹³ LSB of the next.
        for x in [-70_000, -3, 60_000] {
            let (start, end) = (p.at(x, 2), p.at(x + MAX_CHUNK as i32, 2));
            for k in 0..3 {
                let stepped = start[k].wrapping_add(p.step()[k].wrapping_mul(MAX_CHUNK));
                assert!(stepped.abs_diff(end[k]) <= 1 << 11, "{x} channel {k}");
            }
        }
    }

    #[test]
    fn reciprocal_scaling_matches_division() {
        let mut rnd = crate::random(0x0123_4567_89ab_cdef_u64);
        for _ in 0..20_000 {
            let area2 = (i128::from(rnd()) << (rnd() % 2)) >> (rnd() % 64) | 1;
            let num = (i128::from(rnd() as i64) << (rnd() % 20)) >> (rnd() % 60);
            let k = (rnd() % 41) as u32;
            let inv = InverseArea::new(area2);
            let exact = div_round(num << k, area2);
            let got = inv.scale(num, k);
            assert!(
                (got - exact).abs() <= 1 + (exact.abs() >> 60),
                "{num} {k} {area2}"
            );
        }
    }

    /// The reciprocal gradients are within their bound of the exact quotient, over areas,
    /// numerators and reaches of every magnitude (both sides of the refinement threshold), and
    /// exactly rounded where refined.
    #[test]
    fn gradient_scale_is_within_a_unit() {
        let mut next = crate::random(0x6a09_e667_f3bc_c908);
        let mut refined = 0;
        for _ in 0..200_000 {
            let area2 = (next() >> (26 + next() % 38)).max(1);
            let n = (next() >> (45 + next() % 19)) as i32 * if next() & 1 == 0 { 1 } else { -1 };
            let reach = 2 + (next() >> (next() % 64)) as u32 % 4097;
            let area = NonZeroU64::new(area2).unwrap();
            let scale = GradientScale::new(area, reach);
            let got = scale.of(n);
            let exact_times_area = i128::from(n) << 40;
            // Within 2¹²/reach + 1 units.
            let err = (i128::from(got) * i128::from(area2) - exact_times_area).abs();
            let bound = i128::from(area2) * ((1 << 12) + i128::from(reach)) / i128::from(reach);
            assert!(
                err <= bound,
                "n {n}, area2 {area2}, reach {reach}: got {got}"
            );
            if n.unsigned_abs() * reach > scale.limit {
                // Refined (or divided): exactly rounded, halves away from zero.
                let d = i128::from(area2);
                let rounded = ((i128::from(n.unsigned_abs()) << 40) + d / 2) / d;
                let want = if n < 0 { -rounded } else { rounded };
                assert_eq!(i128::from(got), want, "n {n}, area2 {area2}");
                refined += 1;
            }
        }
        assert!(refined > 20_000, "{refined}");
    }
}
