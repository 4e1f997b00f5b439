//! Fixed-point 3D maths for the [`Pipeline`](crate::three_d::Pipeline): vectors, 4×4 matrices, binary
//! angles with sine and cosine, and an inverse square root — all integer, for cores without an FPU.
//!
//! * Scalars are [`Scalar`] (`I16F16`: 16 fractional bits, range ±32768). Products are formed in
//!   `i64` and rounded back; results that leave the `I16F16` range saturate instead of panicking
//!   (as do sums of products beyond `i64`, which only extreme inputs reach).
//! * Angles are [`Angle`]s: a `u16` fraction of a full turn (65536 steps), so they wrap for free.
//!   [`Angle::sin`] evaluates a degree-11 odd polynomial in `i64` with 30 fractional bits (error
//!   below 2⁻²³ before the final rounding to `I16F16`).
//! * [`inv_sqrt`] is a 24-entry table plus two Newton steps in `u64`: relative error below 2⁻¹⁸,
//!   no division.
//!
//! Matrices act on column vectors (`p' = M·p`) and are stored row by row, as written on paper.
//!
//! # From what you have
//!
//! Constructors take any [`ToScalar`]: `f32`, `f64` (rounded to the nearest 2⁻¹⁶, saturated to
//! ±32768, NaN as 0: see [converting floats](crate#converting-floats) for the checked
//! forms), integers up to 32 bits (saturated) and `Scalar` itself, so
//! `Vec3::new(1.0, -0.5, 2)` and `Light::new(direction, 0.15)` work. [`Angle::from_degrees`]
//! takes integer or fractional degrees ([`Degrees`]); [`Angle::from_radians`] takes
//! `f32`/`f64`; the rotations and camera matrices take any [`ToAngle`] (an [`Angle`] or
//! embedded-graphics' `Angle`). Float conversions are calls you
//! make (in software floating point on a Cortex-M0, linked only if used), never part of drawing;
//! the integer forms use no floats. `Scalar` is the `fixed` crate's `I16F16`: `from_num`,
//! `saturating_from_num`, `to_num::<f32>()`, `from_bits`, and arithmetic with `Scalar`s and
//! `i32`s (`Scalar::from_num(0.5) * 2`) all apply; convert floats first (`x.to_scalar()`).
//!
//! ```
//! use embedded_raster::three_d::{Angle, Mat4, Scalar, Vec3};
//!
//! let quarter = Angle::from_degrees(90);
//! let r = Mat4::rotation_z(quarter);
//! let p = r.transform_vector(Vec3::new(Scalar::ONE, Scalar::ZERO, Scalar::ZERO));
//! assert_eq!(p, Vec3::new(Scalar::ZERO, Scalar::ONE, Scalar::ZERO));
//! let n = Vec3::from_bits(3 << 16, 0, 4 << 16).normalize();
//! assert!((n.x.to_bits() - 39322).abs() <= 1 && (n.z.to_bits() - 52429).abs() <= 1);
//! ```

use core::ops::{Add, Mul, Neg, Sub};

use fixed::types::I16F16;

/// Barycentric coordinates with 30 fractional bits (clipped vertices in their face, points of
/// the quadratic normal field).
pub(crate) type Bary = [i32; 3];

/// `1.0` in [`Bary`] units.
pub(crate) const BARY_ONE: i32 = 1 << 30;

/// The scalar type of the 3D pipeline: signed fixed point with 16 fractional bits.
pub type Scalar = I16F16;

/// Fractional bits of [`Scalar`].
pub const SCALAR_BITS: u32 = 16;

/// A number that converts to a [`Scalar`]: `f32` and `f64` (rounded to the nearest 2⁻¹⁶,
/// saturated to the `Scalar` range, NaN as 0), `i8`–`i32` and `u8`–`u32` (saturated), and
/// `Scalar` itself. [`try_to_scalar`](Self::try_to_scalar) is the checked form: `None` for
/// NaN, an infinity or a value beyond the range. How every conversion treats NaN and
/// infinities: [converting floats](crate#converting-floats).
///
/// ```
/// use embedded_raster::three_d::{Scalar, ToScalar};
///
/// assert_eq!(0.5f32.to_scalar() * 2, Scalar::ONE);
/// assert_eq!(3.to_scalar(), Scalar::from_num(3));
/// assert_eq!(1e9.to_scalar(), Scalar::MAX);
/// assert_eq!(1e9.try_to_scalar(), None);
/// assert_eq!(f32::NAN.to_scalar(), Scalar::ZERO);
/// assert_eq!(f32::NAN.try_to_scalar(), None);
/// assert_eq!(0.25.try_to_scalar(), Some(Scalar::from_num(0.25)));
/// ```
#[diagnostic::on_unimplemented(
    message = "`{Self}` does not convert to a fixed-point `Scalar`",
    label = "expected a float, an integer or a `Scalar`"
)]
pub trait ToScalar: Copy {
    /// The scalar: rounded to the nearest 2⁻¹⁶, saturated to the range, NaN as 0.
    fn to_scalar(self) -> Scalar;

    /// The scalar, or `None` if the value has none: NaN, an infinity, or beyond the `Scalar`
    /// range (after rounding to the nearest 2⁻¹⁶). The default is `Some(self.to_scalar())`.
    fn try_to_scalar(self) -> Option<Scalar> {
        Some(self.to_scalar())
    }
}

impl ToScalar for Scalar {
    #[inline(always)]
    fn to_scalar(self) -> Scalar {
        self
    }
}

impl ToScalar for f64 {
    fn to_scalar(self) -> Scalar {
        if self.is_nan() {
            Scalar::ZERO
        } else {
            // `fixed` converts from the float's bits (round to nearest, ties to even).
            Scalar::saturating_from_num(self)
        }
    }

    fn try_to_scalar(self) -> Option<Scalar> {
        // `None` for NaN, infinities and overflow.
        Scalar::checked_from_num(self)
    }
}

impl ToScalar for f32 {
    fn to_scalar(self) -> Scalar {
        f64::from(self).to_scalar()
    }

    fn try_to_scalar(self) -> Option<Scalar> {
        f64::from(self).try_to_scalar()
    }
}

macro_rules! integer_to_scalar {
    ($($t:ty),*) => {$(
        impl ToScalar for $t {
            #[inline]
            fn to_scalar(self) -> Scalar {
                Scalar::saturating_from_num(self)
            }

            #[inline]
            fn try_to_scalar(self) -> Option<Scalar> {
                Scalar::checked_from_num(self)
            }
        }
    )*};
}
integer_to_scalar!(i8, i16, i32, u8, u16, u32);

/// A number of degrees [`Angle::from_degrees`] takes: integers up to 32 bits (exact, no floats),
/// [`Scalar`] (exact rational rounding, no floats), `f32` and `f64` (NaN and infinities as 0°;
/// [`try_to_angle`](Self::try_to_angle) and [`Angle::try_from_degrees`] give `None` for them
/// instead: [converting floats](crate#converting-floats)).
pub trait Degrees: Copy {
    /// The angle, rounded to the nearest 1/65536 turn.
    fn to_angle(self) -> Angle;

    /// The angle, or `None` for NaN and infinities (every other value has one: angles wrap).
    /// The default is `Some(self.to_angle())`.
    fn try_to_angle(self) -> Option<Angle> {
        Some(self.to_angle())
    }
}

/// A value the rotations and camera matrices take as an angle ([`Mat4::rotation_y`],
/// [`Mat4::perspective`](crate::three_d::Mat4::perspective), [`Mat4::orbit`]): an [`Angle`], or
/// embedded-graphics' `Angle` (`30.0.deg()` with `embedded_graphics::prelude::*` in scope;
/// converted through its radians, in floats, when the matrix is built).
///
/// A bare number is not an angle: its unit is a choice, so write
/// [`Angle::from_degrees`]`(30)` (integer or fractional degrees, [`Degrees`]) or
/// [`Angle::from_radians`]`(0.5)`.
///
/// ```
/// use embedded_graphics::prelude::*;
/// use embedded_raster::three_d::{Angle, Mat4};
///
/// let ours = Mat4::rotation_y(embedded_raster::three_d::Angle::from_degrees(90));
/// // embedded-graphics' prelude brings its own `Angle` and the `.deg()` of `AngleUnit`.
/// assert_eq!(Mat4::rotation_y(90.0.deg()), ours);
/// assert_eq!(Mat4::rotation_y(Angle::from_degrees(90.0)), ours);
/// ```
///
/// A number does not compile as an angle (degrees or radians?):
///
/// ```compile_fail
/// use embedded_raster::three_d::Mat4;
///
/// let turned = Mat4::rotation_y(90);
/// ```
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not an angle",
    label = "expected an `Angle`",
    note = "a number has no unit: write `Angle::from_degrees(30)` (integer or fractional degrees) or `Angle::from_radians(0.5)`"
)]
pub trait ToAngle: Copy {
    /// The angle, rounded to the nearest 1/65536 turn (embedded-graphics' `Angle` of NaN or
    /// infinite radians as 0: [converting floats](crate#converting-floats)).
    fn to_angle(self) -> Angle;

    /// The angle, or `None` for embedded-graphics' `Angle` of NaN or infinite radians. The
    /// default is `Some(self.to_angle())`.
    fn try_to_angle(self) -> Option<Angle> {
        Some(self.to_angle())
    }
}

impl ToAngle for Angle {
    #[inline(always)]
    fn to_angle(self) -> Angle {
        self
    }
}

impl ToAngle for embedded_graphics::geometry::Angle {
    fn to_angle(self) -> Angle {
        Angle::from_radians(self.to_radians())
    }

    fn try_to_angle(self) -> Option<Angle> {
        Angle::try_from_radians(self.to_radians())
    }
}

/// `round(n / d)` turns of 65536 steps, wrapped to `u16`; `d > 0`, `|n| < 2⁶²` (64-bit: no
/// 128-bit division on Cortex-M).
fn steps(n: i64, d: i64) -> Angle {
    Angle((2 * n + d).div_euclid(2 * d).rem_euclid(65536) as u16)
}

macro_rules! integer_degrees {
    ($($t:ty),*) => {$(
        impl Degrees for $t {
            #[inline]
            fn to_angle(self) -> Angle {
                steps(i64::from(self) * 65536, 360)
            }
        }
    )*};
}
integer_degrees!(i8, i16, i32, u8, u16, u32);

impl Degrees for Scalar {
    fn to_angle(self) -> Angle {
        steps(i64::from(self.to_bits()), 360)
    }
}

impl Degrees for f64 {
    fn to_angle(self) -> Angle {
        float_turns(self / 360.0)
    }

    fn try_to_angle(self) -> Option<Angle> {
        self.is_finite().then(|| self.to_angle())
    }
}

impl Degrees for f32 {
    fn to_angle(self) -> Angle {
        f64::from(self).to_angle()
    }

    fn try_to_angle(self) -> Option<Angle> {
        f64::from(self).try_to_angle()
    }
}

/// The angle of `turns` full turns (a float), rounded to the nearest step; not finite → 0.
fn float_turns(turns: f64) -> Angle {
    if !turns.is_finite() {
        return Angle::ZERO;
    }
    // Only the fraction of a turn matters: keep 16 integer bits of turns (exact, as the steps
    // are a power of two) and round to the nearest step with `fixed`'s bit-level conversion.
    let steps = fixed::types::I48F16::saturating_from_num(turns).to_bits();
    Angle((steps & 0xffff) as u16)
}

/// `[f(a₀, b₀), f(a₁, b₁), …]`, without indexing: no bounds check is left to panic where the
/// optimiser does not inline the closure (the drawing code links without panic paths at
/// `opt-level` `"s"` and `"z"` too).
#[inline(always)]
pub(crate) fn zip_with<T: Copy + Default, R, const N: usize>(
    a: [T; N],
    b: [T; N],
    mut f: impl FnMut(T, T) -> R,
) -> [R; N] {
    let mut b = b.into_iter();
    a.map(|a| f(a, b.next().unwrap_or_default()))
}

/// [`zip_with`] of three vectors' components.
#[inline(always)]
pub(crate) fn zip3_with<A, B, T, R>(
    [a0, a1, a2]: [A; 3],
    [b0, b1, b2]: [B; 3],
    [c0, c1, c2]: [T; 3],
    mut f: impl FnMut(A, B, T) -> R,
) -> [R; 3] {
    [f(a0, b0, c0), f(a1, b1, c1), f(a2, b2, c2)]
}

/// Saturates a wide value to `i32`.
#[inline]
pub(crate) fn sat32(v: i64) -> i32 {
    v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// `round(a·b / 2^16)` of raw `I16F16` values, saturating.
#[inline]
fn mul_raw(a: i32, b: i32) -> i32 {
    sat32((i64::from(a) * i64::from(b) + (1 << 15)) >> SCALAR_BITS)
}

/// `round(n / d)`, saturated to `i32`; `0` if `d = 0`.
pub(super) fn div_round(n: i64, d: i64) -> i32 {
    if d == 0 {
        return 0;
    }
    let (n, d) = (i128::from(n), i128::from(d));
    let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
    let q = (2 * n + d).div_euclid(2 * d);
    q.clamp(i128::from(i32::MIN), i128::from(i32::MAX)) as i32
}

/// `round(a / b)` of raw `I16F16` values (the quotient in `I16F16`), saturating; `0` if `b = 0`.
#[inline]
pub(super) fn div_raw(a: i32, b: i32) -> i32 {
    div_round(i64::from(a) << SCALAR_BITS, i64::from(b))
}

/// A binary angle: `turns / 65536` of a full turn. Arithmetic on it wraps around the circle.
///
/// The field is public because it carries no invariant: every `u16` is a valid angle
/// (`Angle(16384)` is a quarter turn). Build one from degrees ([`Angle::from_degrees`], integer
/// or fractional), radians ([`Angle::from_radians`]) or a fraction of a turn
/// ([`Angle::from_turns`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Angle(pub u16);

/// Odd Taylor coefficients of `sin(π/2 · t)` (t in [0, 1]), 30 fractional bits, highest first.
const SIN_COEFFICIENTS: [i64; 6] = [
    -3864,
    172_272,
    -5_026_995,
    85_569_306,
    -693_598_668,
    1_686_629_713,
];

impl Angle {
    /// No rotation.
    pub const ZERO: Angle = Angle(0);
    /// A quarter turn (90°).
    pub const QUARTER: Angle = Angle(1 << 14);
    /// A half turn (180°).
    pub const HALF: Angle = Angle(1 << 15);

    /// The angle of `degrees`: an integer (`Angle::from_degrees(90)`, exact arithmetic),
    /// fractional degrees as a float (`Angle::from_degrees(22.5)`) or a [`Scalar`]; rounded to
    /// the nearest 1/65536 turn and wrapped around the circle. Floats that are not finite give
    /// `Angle::ZERO` ([`try_from_degrees`](Self::try_from_degrees) gives `None`:
    /// [converting floats](crate#converting-floats)); `f64` degrees keep their precision to about ±10¹¹ degrees.
    ///
    /// ```
    /// use embedded_raster::three_d::{Angle, Scalar};
    ///
    /// assert_eq!(Angle::from_degrees(90), Angle::QUARTER);
    /// assert_eq!(Angle::from_degrees(-270), Angle::QUARTER);
    /// assert_eq!(Angle::from_degrees(22.5), Angle(4096));
    /// assert_eq!(Angle::from_degrees(Scalar::from_num(22.5)), Angle(4096));
    /// ```
    pub fn from_degrees(degrees: impl Degrees) -> Angle {
        degrees.to_angle()
    }

    /// The angle of `radians` (`f32` or `f64`), rounded to the nearest 1/65536 turn; not finite
    /// gives `Angle::ZERO` ([`try_from_radians`](Self::try_from_radians) gives `None`:
    /// [converting floats](crate#converting-floats)).
    pub fn from_radians(radians: impl Into<f64>) -> Angle {
        float_turns(radians.into() / core::f64::consts::TAU)
    }

    /// The angle of `radians`, or `None` if it is NaN or infinite.
    ///
    /// ```
    /// use embedded_raster::three_d::Angle;
    ///
    /// assert_eq!(Angle::try_from_radians(core::f64::consts::PI), Some(Angle::HALF));
    /// assert_eq!(Angle::try_from_radians(f32::NAN), None);
    /// assert_eq!(Angle::from_radians(f32::NAN), Angle::ZERO);
    /// ```
    pub fn try_from_radians(radians: impl Into<f64>) -> Option<Angle> {
        let radians = radians.into();
        radians.is_finite().then(|| Angle::from_radians(radians))
    }

    /// The angle of `degrees`, or `None` for a float that is NaN or infinite (integers and
    /// [`Scalar`]s always have one).
    ///
    /// ```
    /// use embedded_raster::three_d::Angle;
    ///
    /// assert_eq!(Angle::try_from_degrees(90.0), Some(Angle::from_degrees(90)));
    /// assert_eq!(Angle::try_from_degrees(f64::INFINITY), None);
    /// ```
    pub fn try_from_degrees(degrees: impl Degrees) -> Option<Angle> {
        degrees.try_to_angle()
    }

    /// This angle in degrees, in `[0, 360)`.
    pub fn to_degrees_f32(self) -> f32 {
        f32::from(self.0) * (360.0 / 65536.0)
    }

    /// The angle of `numerator / denominator` turns (`Angle::ZERO` if the denominator is 0).
    pub fn from_turns(numerator: i32, denominator: i32) -> Angle {
        if denominator == 0 {
            return Angle::ZERO;
        }
        let (n, d) = (i64::from(numerator) * 65536, i64::from(denominator));
        let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
        Angle((2 * n + d).div_euclid(2 * d).rem_euclid(65536) as u16)
    }

    /// This angle plus `other`, wrapping around the circle.
    pub const fn wrapping_add(self, other: Angle) -> Angle {
        Angle(self.0.wrapping_add(other.0))
    }

    /// Half of this angle, in `[0°, 180°)`.
    pub const fn half(self) -> Angle {
        Angle(self.0 >> 1)
    }

    /// The sine, within 1 LSB of `I16F16`.
    pub fn sin(self) -> Scalar {
        Scalar::from_bits(sin_raw(self.0))
    }

    /// The cosine, within 1 LSB of `I16F16`.
    pub fn cos(self) -> Scalar {
        Scalar::from_bits(sin_raw(self.0.wrapping_add(1 << 14)))
    }
}

/// `sin(2π · a / 65536)` as raw `I16F16`, rounded to nearest.
fn sin_raw(a: u16) -> i32 {
    let quadrant = a >> 14;
    let mut t = i64::from(a & 0x3fff);
    if quadrant & 1 == 1 {
        t = (1 << 14) - t;
    }
    // t in [0, 1] with 30 fractional bits.
    let x = t << 16;
    let x2 = (x * x) >> 30;
    let mut p = 0i64;
    for c in SIN_COEFFICIENTS {
        p = c + ((p * x2) >> 30);
    }
    let s = (p * x) >> 30;
    let r = ((s + (1 << 13)) >> 14).clamp(0, 1 << 16) as i32;
    if quadrant >= 2 {
        -r
    } else {
        r
    }
}

/// Initial guesses of `1/√M` for `M` in `[(i + 8)/32, (i + 9)/32)`, at the middle of each bucket,
/// with 30 fractional bits: `⌊√(2^66 / (2i + 17))⌋`.
const INV_SQRT_TABLE: [u32; 24] = {
    let mut t = [0u32; 24];
    let mut i = 0;
    while i < 24 {
        t[i] = ((1u128 << 66) / (2 * i as u128 + 17)).isqrt() as u32;
        i += 1;
    }
    t
};

/// The inverse square root of `x > 0` as `(r, s)` with `1/√x ≈ r / 2^s`; `r` lies in `(2^30, 2^31]`
/// and `s` in `[30, 62]`. Relative error below 2⁻¹⁸. `x = 0` gives `(0, 0)`.
///
/// Normalises `x` by an even shift to `M·2^k` with `M` in `[1/4, 1)`, looks up a first guess of
/// `1/√M` and refines it with two Newton steps `r ← r·(3 − M·r²)/2` in `u64`.
pub fn inv_sqrt(x: u64) -> (u32, u32) {
    if x == 0 {
        return (0, 0);
    }
    let e = x.leading_zeros() & !1;
    let m = x << e;
    // M with 32 fractional bits, in [2^30, 2^32).
    let m32 = m >> 32;
    let index = ((m32 >> 27) as usize).saturating_sub(8);
    let mut r = u64::from(INV_SQRT_TABLE.get(index).copied().unwrap_or(1 << 30));
    for _ in 0..2 {
        let r2 = (r * r) >> 30;
        let mr2 = (m32 * r2) >> 32;
        r = (r * ((3u64 << 30).saturating_sub(mr2))) >> 31;
    }
    // x = M·2^(64−e): 1/√x = r·2^-30 · 2^(e/2 − 32).
    (r.min(1 << 31) as u32, 62 - e / 2)
}

/// A 3D vector of [`Scalar`]s.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
#[repr(C)]
pub struct Vec3 {
    /// x component.
    pub x: Scalar,
    /// y component.
    pub y: Scalar,
    /// z component.
    pub z: Scalar,
}

impl Vec3 {
    /// The zero vector.
    pub const ZERO: Vec3 = Vec3::from_bits(0, 0, 0);

    /// A vector from its components: floats, integers or [`Scalar`]s ([`ToScalar`]), e.g.
    /// `Vec3::new(1.0, -0.5, 2)`. For `const` data use [`from_bits`](Self::from_bits).
    #[inline(always)]
    pub fn new(x: impl ToScalar, y: impl ToScalar, z: impl ToScalar) -> Self {
        Vec3 {
            x: x.to_scalar(),
            y: y.to_scalar(),
            z: z.to_scalar(),
        }
    }

    /// The components as `f32`s (rounded to nearest where a value needs more than the 24
    /// significant bits of an `f32`, i.e. at magnitudes of 256 and above).
    pub fn to_f32(self) -> [f32; 3] {
        [self.x, self.y, self.z].map(|c| c.to_num::<f32>())
    }

    /// The components as `f64`s (exact).
    pub fn to_f64(self) -> [f64; 3] {
        [self.x, self.y, self.z].map(|c| c.to_num::<f64>())
    }

    /// A vector from raw `I16F16` bits (`65536` is `1.0`); usable in `const` mesh data.
    pub const fn from_bits(x: i32, y: i32, z: i32) -> Self {
        Vec3 {
            x: Scalar::from_bits(x),
            y: Scalar::from_bits(y),
            z: Scalar::from_bits(z),
        }
    }

    /// The raw components.
    pub const fn to_bits(self) -> [i32; 3] {
        [self.x.to_bits(), self.y.to_bits(), self.z.to_bits()]
    }

    /// The dot product with 32 fractional bits: exact unless it exceeds the `i64` range, where it
    /// saturates.
    #[inline]
    pub fn dot_wide(self, o: Vec3) -> i64 {
        let (a, b) = (self.to_bits(), o.to_bits());
        (i64::from(a[0]) * i64::from(b[0]))
            .saturating_add(i64::from(a[1]) * i64::from(b[1]))
            .saturating_add(i64::from(a[2]) * i64::from(b[2]))
    }

    /// The dot product, rounded and saturated to a [`Scalar`].
    pub fn dot(self, o: Vec3) -> Scalar {
        Scalar::from_bits(sat32(
            self.dot_wide(o).saturating_add(1 << 15) >> SCALAR_BITS,
        ))
    }

    /// The exact cross product with 32 fractional bits.
    pub fn cross_wide(self, o: Vec3) -> [i64; 3] {
        let (a, b) = (self.to_bits().map(i64::from), o.to_bits().map(i64::from));
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    /// The cross product, rounded and saturated.
    pub fn cross(self, o: Vec3) -> Vec3 {
        let c = self
            .cross_wide(o)
            .map(|v| sat32((v + (1 << 15)) >> SCALAR_BITS));
        Vec3::from_bits(c[0], c[1], c[2])
    }

    /// Each component multiplied by `s`, rounded and saturated.
    pub fn scale(self, s: Scalar) -> Vec3 {
        let [x, y, z] = self.to_bits().map(|c| mul_raw(c, s.to_bits()));
        Vec3::from_bits(x, y, z)
    }

    /// The squared length with 32 fractional bits (saturating, like
    /// [`dot_wide`](Self::dot_wide)).
    pub fn length_squared_wide(self) -> i64 {
        self.dot_wide(self)
    }

    /// The unit vector in this direction (the zero vector stays zero).
    pub fn normalize(self) -> Vec3 {
        normalize_wide(self.to_bits().map(i64::from))
    }

    /// The component-wise sum, saturating.
    pub fn saturating_add(self, o: Vec3) -> Vec3 {
        Vec3::new(
            self.x.saturating_add(o.x),
            self.y.saturating_add(o.y),
            self.z.saturating_add(o.z),
        )
    }
}

/// The unit vector in the direction of a vector with components of any fixed-point format (all
/// three in the same one), as `I16F16`. The zero vector gives the zero vector.
pub fn normalize_wide(v: [i64; 3]) -> Vec3 {
    let m = v.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
    if m == 0 {
        return Vec3::ZERO;
    }
    // Bring the largest component to [2^28, 2^29): squares then sum below 2^60.
    let top = 63 - m.leading_zeros() as i32;
    let shift = 28 - top;
    let c = v.map(|x| if shift >= 0 { x << shift } else { x >> -shift });
    let ss = c.iter().map(|x| x * x).sum::<i64>() as u64;
    let (r, s) = inv_sqrt(ss);
    let [x, y, z] = c.map(|x| {
        let p = x * i64::from(r);
        sat32((p + (1 << (s - 17))) >> (s - SCALAR_BITS))
    });
    Vec3::from_bits(x, y, z)
}

impl From<[f32; 3]> for Vec3 {
    /// Rounds each component to the nearest `I16F16` (saturating; NaN as 0).
    fn from(v: [f32; 3]) -> Vec3 {
        Vec3::new(v[0], v[1], v[2])
    }
}

impl From<[f64; 3]> for Vec3 {
    /// Rounds each component to the nearest `I16F16` (saturating; NaN as 0).
    fn from(v: [f64; 3]) -> Vec3 {
        Vec3::new(v[0], v[1], v[2])
    }
}

impl Add for Vec3 {
    type Output = Vec3;
    fn add(self, o: Vec3) -> Vec3 {
        self.saturating_add(o)
    }
}

impl Sub for Vec3 {
    type Output = Vec3;
    fn sub(self, o: Vec3) -> Vec3 {
        Vec3::new(
            self.x.saturating_sub(o.x),
            self.y.saturating_sub(o.y),
            self.z.saturating_sub(o.z),
        )
    }
}

impl Neg for Vec3 {
    type Output = Vec3;
    fn neg(self) -> Vec3 {
        Vec3::new(
            self.x.saturating_neg(),
            self.y.saturating_neg(),
            self.z.saturating_neg(),
        )
    }
}

/// A homogeneous 4D vector of [`Scalar`]s (clip-space positions).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Vec4 {
    /// x component.
    pub x: Scalar,
    /// y component.
    pub y: Scalar,
    /// z component.
    pub z: Scalar,
    /// w component.
    pub w: Scalar,
}

impl Vec4 {
    /// A vector from its components: floats, integers or [`Scalar`]s ([`ToScalar`]), e.g.
    /// `Vec4::new(1.0, -0.5, 2, 1)`. For `const` data use [`from_bits`](Self::from_bits).
    #[inline(always)]
    pub fn new(x: impl ToScalar, y: impl ToScalar, z: impl ToScalar, w: impl ToScalar) -> Self {
        Vec4 {
            x: x.to_scalar(),
            y: y.to_scalar(),
            z: z.to_scalar(),
            w: w.to_scalar(),
        }
    }

    /// The point `p` with `w = 1`.
    pub const fn from_point(p: Vec3) -> Self {
        Vec4 {
            x: p.x,
            y: p.y,
            z: p.z,
            w: Scalar::ONE,
        }
    }

    /// The raw components `[x, y, z, w]`.
    pub const fn to_bits(self) -> [i32; 4] {
        [
            self.x.to_bits(),
            self.y.to_bits(),
            self.z.to_bits(),
            self.w.to_bits(),
        ]
    }

    /// A vector from raw `I16F16` components `[x, y, z, w]`.
    pub const fn from_bits(v: [i32; 4]) -> Self {
        Vec4 {
            x: Scalar::from_bits(v[0]),
            y: Scalar::from_bits(v[1]),
            z: Scalar::from_bits(v[2]),
            w: Scalar::from_bits(v[3]),
        }
    }
}

/// A 4×4 matrix of [`Scalar`]s acting on column vectors, stored row by row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Mat4 {
    /// `rows[r][c]` is the entry in row `r`, column `c`.
    pub rows: [[Scalar; 4]; 4],
}

impl Default for Mat4 {
    fn default() -> Self {
        Mat4::IDENTITY
    }
}

impl Mat4 {
    /// The identity.
    pub const IDENTITY: Mat4 = Mat4::from_bits([
        [1 << 16, 0, 0, 0],
        [0, 1 << 16, 0, 0],
        [0, 0, 1 << 16, 0],
        [0, 0, 0, 1 << 16],
    ]);

    /// A matrix from raw `I16F16` entries, row by row.
    pub const fn from_bits(m: [[i32; 4]; 4]) -> Self {
        let mut rows = [[Scalar::ZERO; 4]; 4];
        let mut r = 0;
        while r < 4 {
            let mut c = 0;
            while c < 4 {
                rows[r][c] = Scalar::from_bits(m[r][c]);
                c += 1;
            }
            r += 1;
        }
        Mat4 { rows }
    }

    /// The raw entries, row by row.
    pub fn to_bits(&self) -> [[i32; 4]; 4] {
        self.rows.map(|r| r.map(|v| v.to_bits()))
    }

    /// A translation by `t`.
    pub fn translation(t: Vec3) -> Self {
        let mut m = Mat4::IDENTITY;
        m.rows[0][3] = t.x;
        m.rows[1][3] = t.y;
        m.rows[2][3] = t.z;
        m
    }

    /// A uniform scaling by `s` (a float, an integer or a [`Scalar`]).
    pub fn scaling(s: impl ToScalar) -> Self {
        let s = s.to_scalar();
        let mut m = Mat4::IDENTITY;
        m.rows[0][0] = s;
        m.rows[1][1] = s;
        m.rows[2][2] = s;
        m
    }

    /// A rotation by `a` about the x axis (y towards z).
    pub fn rotation_x(a: impl ToAngle) -> Self {
        let a = a.to_angle();
        let (s, c) = (a.sin(), a.cos());
        let mut m = Mat4::IDENTITY;
        m.rows[1][1] = c;
        m.rows[1][2] = -s;
        m.rows[2][1] = s;
        m.rows[2][2] = c;
        m
    }

    /// A rotation by `a` about the y axis (z towards x).
    pub fn rotation_y(a: impl ToAngle) -> Self {
        let a = a.to_angle();
        let (s, c) = (a.sin(), a.cos());
        let mut m = Mat4::IDENTITY;
        m.rows[0][0] = c;
        m.rows[0][2] = s;
        m.rows[2][0] = -s;
        m.rows[2][2] = c;
        m
    }

    /// A rotation by `a` about the z axis (x towards y).
    pub fn rotation_z(a: impl ToAngle) -> Self {
        let a = a.to_angle();
        let (s, c) = (a.sin(), a.cos());
        let mut m = Mat4::IDENTITY;
        m.rows[0][0] = c;
        m.rows[0][1] = -s;
        m.rows[1][0] = s;
        m.rows[1][1] = c;
        m
    }

    /// The transpose.
    pub fn transpose(&self) -> Self {
        let mut t = *self;
        for (r, row) in self.rows.iter().enumerate() {
            for (c, v) in row.iter().enumerate() {
                t.rows[c][r] = *v;
            }
        }
        t
    }

    /// `self · v`, with `i64` accumulation, rounded and saturated.
    pub fn transform(&self, v: Vec4) -> Vec4 {
        let v = v.to_bits().map(i64::from);
        let out = self.rows.map(|row| {
            let acc: i64 = row
                .iter()
                .zip(v.iter())
                .map(|(m, x)| i64::from(m.to_bits()) * x)
                .fold(0, i64::saturating_add);
            sat32(acc.saturating_add(1 << 15) >> SCALAR_BITS)
        });
        Vec4::from_bits(out)
    }

    /// `self · (p, 1)`.
    pub fn transform_point(&self, p: Vec3) -> Vec4 {
        self.transform(Vec4::from_point(p))
    }

    /// The upper-left 3×3 block times `v` (a direction: no translation).
    pub fn transform_vector(&self, v: Vec3) -> Vec3 {
        let r = self.transform(Vec4::new(v.x, v.y, v.z, Scalar::ZERO));
        Vec3::new(r.x, r.y, r.z)
    }
}

impl Mul for Mat4 {
    type Output = Mat4;

    /// The matrix product with `i64` accumulation, rounded and saturated.
    fn mul(self, rhs: Mat4) -> Mat4 {
        let (a, b) = (self.to_bits(), rhs.to_bits());
        let mut out = [[0i32; 4]; 4];
        for (row, a_row) in out.iter_mut().zip(a) {
            for (c, v) in row.iter_mut().enumerate() {
                let acc: i64 = a_row
                    .iter()
                    .zip(b)
                    .map(|(&x, b_row)| i64::from(x) * i64::from(b_row.get(c).copied().unwrap_or(0)))
                    .fold(0, i64::saturating_add);
                *v = sat32(acc.saturating_add(1 << 15) >> SCALAR_BITS);
            }
        }
        Mat4::from_bits(out)
    }
}

impl Mul<Vec4> for Mat4 {
    type Output = Vec4;
    fn mul(self, v: Vec4) -> Vec4 {
        self.transform(v)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// The checked conversions: `None` for NaN, infinities and (for scalars) values beyond the
    /// range after rounding; otherwise the saturating conversion's value.
    #[test]
    fn checked_conversions() {
        let max = f64::from(i32::MAX) / 65536.0;
        let min = f64::from(i32::MIN) / 65536.0;
        for v in [
            f64::NAN,
            -f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            32768.0,
            max + 1.0 / 131_072.0, // a tie above the largest: rounds (to even) to 2¹⁵
            min - 1.0,
            -1e300,
            f64::from(f32::MAX),
        ] {
            assert_eq!(v.try_to_scalar(), None, "{v}");
            assert_eq!((v as f32).try_to_scalar(), None, "{v} as f32");
        }
        assert_eq!(f64::NAN.to_scalar(), Scalar::ZERO);
        assert_eq!(f64::INFINITY.to_scalar(), Scalar::MAX);
        assert_eq!(f64::NEG_INFINITY.to_scalar(), Scalar::MIN);
        for (v, bits) in [
            (0.0, 0),
            (-0.0, 0),
            (0.5, 32768),
            (-2.25, -(2 * 65536 + 16384)),
            (max, i32::MAX),
            (min, i32::MIN),
            (1.0 / 131_072.0, 0), // a tie: to even
        ] {
            assert_eq!(v.try_to_scalar().map(Scalar::to_bits), Some(bits), "{v}");
            assert_eq!(v.try_to_scalar(), Some(v.to_scalar()), "{v}");
        }
        let mut next = crate::random(5);
        for _ in 0..10_000 {
            let v = ((next() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * 32767.0;
            assert_eq!(v.try_to_scalar(), Some(v.to_scalar()), "{v}");
            let f = v as f32;
            assert_eq!(f.try_to_scalar(), Some(f.to_scalar()), "{f}");
        }
        // Integers: exact in range, `None` beyond.
        assert_eq!(32767i32.try_to_scalar(), Some(Scalar::from_num(32767)));
        assert_eq!((-32768i32).try_to_scalar(), Some(Scalar::MIN));
        assert_eq!(32768i32.try_to_scalar(), None);
        assert_eq!((-32769i32).try_to_scalar(), None);
        assert_eq!(32768u32.try_to_scalar(), None);
        assert_eq!(u16::MAX.try_to_scalar(), None);
        assert_eq!(i16::MIN.try_to_scalar(), Some(Scalar::MIN));
        assert_eq!(255u8.try_to_scalar(), Some(Scalar::from_num(255)));
        assert_eq!(Scalar::MAX.try_to_scalar(), Some(Scalar::MAX));

        // Angles: `None` only for floats that are not finite.
        for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(Angle::try_from_degrees(v), None, "{v}");
            assert_eq!(Angle::try_from_degrees(v as f32), None, "{v}");
            assert_eq!(Angle::try_from_radians(v), None, "{v}");
            assert_eq!(Angle::try_from_radians(v as f32), None, "{v}");
            assert_eq!(Angle::from_degrees(v), Angle::ZERO);
            assert_eq!(Angle::from_radians(v), Angle::ZERO);
            let eg = embedded_graphics::geometry::Angle::from_radians(v as f32);
            assert_eq!(eg.try_to_angle(), None, "{v}");
            assert_eq!(eg.to_angle(), Angle::ZERO);
        }
        for v in [0.0, 90.0, -270.0, 22.5, 1e9, -1e12, f64::MAX] {
            assert_eq!(
                Angle::try_from_degrees(v),
                Some(Angle::from_degrees(v)),
                "{v}"
            );
            assert_eq!(
                Angle::try_from_radians(v),
                Some(Angle::from_radians(v)),
                "{v}"
            );
            if (v as f32).is_finite() {
                let eg = embedded_graphics::geometry::Angle::from_radians(v as f32);
                assert_eq!(eg.try_to_angle(), Some(eg.to_angle()), "{v}");
            }
        }
        assert_eq!(Angle::try_from_degrees(-270.0), Some(Angle::QUARTER));
        assert_eq!(
            Angle::try_from_degrees(i32::MIN),
            Some(Angle::from_degrees(i32::MIN))
        );
        let degrees = Scalar::from_num(120);
        assert_eq!(
            Angle::try_from_degrees(degrees),
            Some(Angle::from_degrees(120))
        );
        assert_eq!(Angle::HALF.try_to_angle(), Some(Angle::HALF));
    }

    #[test]
    fn sine_and_cosine_within_one_lsb() {
        for a in 0..=u16::MAX {
            let t = f64::from(a) / 65536.0 * core::f64::consts::TAU;
            let s = f64::from(Angle(a).sin().to_bits()) / 65536.0;
            let c = f64::from(Angle(a).cos().to_bits()) / 65536.0;
            assert!((s - t.sin()).abs() <= 1.0 / 65536.0, "sin {a}");
            assert!((c - t.cos()).abs() <= 1.0 / 65536.0, "cos {a}");
        }
        assert_eq!(Angle::from_degrees(90), Angle::QUARTER);
        assert_eq!(Angle::from_degrees(-90), Angle(49152));
        assert_eq!(Angle::from_turns(1, 3), Angle(21845));
    }

    /// Degrees and radians in every form against `round(turns · 65536) mod 65536` in f64.
    #[test]
    fn angles_from_degrees_and_radians() {
        let want = |turns: f64| ((turns * 65536.0).round().rem_euclid(65536.0)) as u16;
        let mut rng = crate::rng::Rng(0x616e_676c);
        for _ in 0..100_000 {
            let d = (rng.next() % 2_000_001) as i32 - 1_000_000;
            assert_eq!(Angle::from_degrees(d).0, want(f64::from(d) / 360.0), "{d}");
            let f = d as f64 / 1024.0;
            assert_eq!(Angle::from_degrees(f).0, want(f / 360.0), "{f}");
            // Scalar degrees can be ties (half a step): rounded up.
            let s = Scalar::from_bits(d);
            let up = (f64::from(d) / 360.0 + 0.5).floor().rem_euclid(65536.0) as u16;
            assert_eq!(Angle::from_degrees(s).0, up, "{s}");
            let r = f / 100.0;
            let got = Angle::from_radians(r).0;
            let exact = want(r / core::f64::consts::TAU);
            assert!(
                got == exact || got.abs_diff(exact) == 1,
                "{r} rad: {got} vs {exact}"
            );
        }
        assert_eq!(
            Angle::from_degrees(i32::MIN).0,
            want(f64::from(i32::MIN) / 360.0)
        );
        assert_eq!(Angle::from_degrees(f32::NAN), Angle::ZERO);
        assert_eq!(Angle::from_degrees(f64::INFINITY), Angle::ZERO);
        assert_eq!(Angle::from_degrees(22.5f32), Angle(4096));
        assert_eq!(Angle::from_radians(core::f32::consts::PI), Angle::HALF);
        assert_eq!(Angle::QUARTER.to_degrees_f32(), 90.0);
    }

    #[test]
    fn scalars_from_numbers() {
        assert_eq!(
            Vec3::new(1.0, -0.5, 2),
            Vec3::from_bits(65536, -32768, 2 << 16)
        );
        assert_eq!(
            Vec3::from([0.25f32, 1e9, f32::NAN]).to_bits(),
            [16384, i32::MAX, 0]
        );
        assert_eq!(40_000u32.to_scalar(), Scalar::MAX);
        assert_eq!((-40_000i32).to_scalar(), Scalar::MIN);
        assert_eq!(Vec3::new(1.5, 2.25, -3).to_f64(), [1.5, 2.25, -3.0]);
        let mut rng = crate::rng::Rng(5);
        for _ in 0..10_000 {
            let v = (rng.next() as i64 >> 20) as f64 / 1e6;
            let want = (v * 65536.0).round().clamp(-2147483648.0, 2147483647.0) as i32;
            let tie = (v * 65536.0).fract().abs() == 0.5;
            assert!(v.to_scalar().to_bits() == want || tie, "{v}");
        }
    }

    #[test]
    fn inverse_square_root_is_accurate() {
        let mut rng = crate::rng::Rng(0x9e37_79b9_7f4a_7c15_u64);
        for k in 0..200_000u64 {
            let x = (rng.next() >> (k % 64)).max(1);
            let (r, s) = inv_sqrt(x);
            let got = f64::from(r) / (s as f64).exp2();
            let want = 1.0 / (x as f64).sqrt();
            assert!(
                ((got - want) / want).abs() < 1.0 / 262_144.0,
                "{x}: {got} vs {want}"
            );
        }
        assert_eq!(inv_sqrt(0), (0, 0));
    }

    #[test]
    fn normalize_any_magnitude() {
        for v in [
            [1i64, 0, 0],
            [3, 4, 0],
            [-7, 1 << 40, 12345],
            [i64::MAX / 2, -(i64::MAX / 2), 1],
            [0, 0, -1],
        ] {
            let n = normalize_wide(v);
            let f = v.map(|c| c as f64);
            let l = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
            for (got, want) in n.to_bits().iter().zip(f.iter()) {
                assert!((f64::from(*got) - want / l * 65536.0).abs() <= 1.5, "{v:?}");
            }
        }
        assert_eq!(normalize_wide([0; 3]), Vec3::ZERO);
    }

    #[test]
    fn matrices_compose() {
        let a = Angle::from_degrees(45);
        let r = Mat4::rotation_x(a) * Mat4::rotation_x(a);
        let q = Mat4::rotation_x(Angle::QUARTER);
        for (x, y) in r
            .to_bits()
            .iter()
            .flatten()
            .zip(q.to_bits().iter().flatten())
        {
            assert!((x - y).abs() <= 2);
        }
        let t = Mat4::translation(Vec3::from_bits(1 << 16, 2 << 16, 3 << 16));
        let p = t.transform_point(Vec3::ZERO);
        assert_eq!(p.to_bits(), [1 << 16, 2 << 16, 3 << 16, 1 << 16]);
        assert_eq!(t.transpose().transpose(), t);
    }
}
