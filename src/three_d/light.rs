//! The light of a scene: one directional light with an ambient term. The vertex stage lights
//! vertices with it and the fills shade pixels with it, so it sits below both.

use super::math::{Scalar, Vec3};

/// A directional light with an ambient term.
///
/// A surface with unit normal `n` receives `level = ambient + (1 − ambient)·max(0, n·l)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Light {
    /// Unit vector from the surface towards the light (same space as the normals).
    pub(crate) direction: Vec3,
    /// Light level of surfaces facing away, in `[0, 1]`.
    pub(crate) ambient: Scalar,
}

impl Default for Light {
    fn default() -> Self {
        Light::new(Vec3::from_bits(0, 0, 1 << 16), Scalar::ZERO)
    }
}

impl Light {
    /// A light shining from `direction` (normalised here) with the given ambient level (clamped
    /// to `[0, 1]`).
    pub fn new(direction: Vec3, ambient: Scalar) -> Self {
        Light {
            direction: direction.normalize(),
            ambient: ambient.clamp(Scalar::ZERO, Scalar::ONE),
        }
    }

    /// The unit vector towards the light (the zero vector for a light built from one).
    pub const fn direction(&self) -> Vec3 {
        self.direction
    }

    /// The ambient level, in `[0, 1]`.
    pub const fn ambient(&self) -> Scalar {
        self.ambient
    }

    /// Lambert's `max(0, n·l)` for a unit normal `n`, in `[0, 1]`.
    pub fn diffuse(&self, normal: Vec3) -> Scalar {
        self.direction.dot(normal).clamp(Scalar::ZERO, Scalar::ONE)
    }

    /// The light level `ambient + (1 − ambient)·max(0, n·l)` for a unit normal `n`.
    pub fn level(&self, normal: Vec3) -> Scalar {
        Scalar::from_bits(self.level_of_diffuse(self.diffuse(normal).to_bits() as u32) as i32)
    }

    /// `ambient + (1 − ambient)·d` with 16 fractional bits, for `d` in `[0, 2^16]`.
    #[inline(always)]
    pub(crate) fn level_of_diffuse(&self, d: u32) -> u32 {
        let a = self.ambient.to_bits().clamp(0, 1 << 16) as u32;
        let lit = (u64::from((1 << 16) - a) * u64::from(d.min(1 << 16)) + (1 << 15)) >> 16;
        a + lit as u32
    }
}

/// A material's specular highlight: Blinn-Phong's `strength · max(0, n̂·ĥ)^shininess`, added to
/// every channel of the lit colour as white light (saturating at the channel's maximum).
///
/// `ĥ = normalize(l + v)` is the half vector between the light direction `l` and the direction
/// `v` towards the viewer. The pipeline takes the viewer at infinity along the camera's `+z`
/// (view space), the infinite-viewer approximation of fixed-function OpenGL's default
/// (`GL_LIGHT_MODEL_LOCAL_VIEWER` false): `v`, and so `ĥ`, is the same for every vertex and pixel
/// of a draw ([`Pipeline::view_direction`](super::Pipeline::view_direction)). Surfaces facing
/// away from the light (`n·l ≤ 0`) get no highlight.
///
/// The power is computed in 16-bit fixed point by repeated squaring, no floats and no division
/// ([`term`](Self::term)): within `shininess · 2⁻¹⁷` of the exact
/// `strength · cosine^shininess` for a cosine given to 2⁻¹⁶.
///
/// # Examples
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use embedded_raster::three_d::{Material, Scalar, Shading, Specular};
///
/// let shiny = Specular::new(Scalar::from_num(0.5), 32);
/// let material = Material::new(Rgb565::new(20, 10, 4), Shading::Quadratic).with_specular(shiny);
/// assert_eq!(material.specular, Some(shiny));
///
/// // Head-on, the whole strength; 30° off the half vector, cos³²(30°) = 0.01 of it.
/// assert_eq!(shiny.term(Scalar::ONE), Scalar::from_num(0.5));
/// assert!(shiny.term(Scalar::from_num(0.866)) < Scalar::from_num(0.006));
/// // cos 10° = 0.985: 0.985³² = 0.61.
/// let ten = shiny.term(Scalar::from_num(0.98481)).to_num::<f64>();
/// assert!((ten - 0.5 * 0.98481f64.powi(32)).abs() < 0.001);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Specular {
    /// The highlight's peak, in `[0, 1]`.
    pub(crate) strength: Scalar,
    /// The exponent: larger is a smaller, sharper highlight.
    pub(crate) shininess: u8,
}

impl Specular {
    /// A highlight of `strength` (clamped to `[0, 1]`) and exponent `shininess` (typically 8 to
    /// 128; 0 lights every surface facing the light by `strength`).
    pub fn new(strength: Scalar, shininess: u8) -> Self {
        Specular {
            strength: strength.clamp(Scalar::ZERO, Scalar::ONE),
            shininess,
        }
    }

    /// The highlight's peak, in `[0, 1]`.
    pub const fn strength(&self) -> Scalar {
        self.strength
    }

    /// The exponent.
    pub const fn shininess(&self) -> u8 {
        self.shininess
    }

    /// `strength · max(0, cosine)^shininess` (`cosine` = `n̂·ĥ`, clamped to `[0, 1]`), in
    /// `[0, strength]`: within `shininess · 2⁻¹⁷` of the exact value for this `cosine` (the
    /// squarings' and products' roundings, each at most 2⁻¹⁷, add up to at most that: every
    /// factor is at most 1). A cosine off by `ε` moves the exact value by up to
    /// `strength · shininess · ε`.
    pub fn term(&self, cosine: Scalar) -> Scalar {
        let x = cosine.to_bits().clamp(0, 1 << 16) as u32;
        Scalar::from_bits(self.term_bits(x) as i32)
    }

    /// The strength with 16 fractional bits, in `[0, 2¹⁶]`.
    #[inline(always)]
    pub(crate) fn strength_bits(&self) -> u32 {
        self.strength.to_bits().clamp(0, 1 << 16) as u32
    }

    /// [`term`](Self::term) of `x` with 16 fractional bits (in `[0, 2¹⁶]`), 16 fractional bits.
    #[inline]
    pub(crate) fn term_bits(&self, x: u32) -> u32 {
        specular_power(self.strength_bits(), x, self.shininess)
    }

    /// The smallest `x` (16 fractional bits) whose [`term_bits`](Self::term_bits) is not 0
    /// (`2¹⁶ + 1` if none): the term is non-decreasing in `x` (every rounded product is), so
    /// a draw skips the power below it. A binary search, once per draw.
    pub(crate) fn threshold(&self) -> u32 {
        // term(lo − 1) = 0 (or lo = 0) and term(hi) > 0 (or hi = 2¹⁶ + 1).
        let (mut lo, mut hi) = (0u32, (1 << 16) + 1);
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if self.term_bits(mid) > 0 {
                hi = mid;
            } else {
                lo = mid + 1;
            }
        }
        lo
    }

    /// [`term_bits`](Self::term_bits), 0 below `threshold` (this highlight's
    /// [`threshold`](Self::threshold)) without the power.
    #[inline(always)]
    pub(crate) fn term_above(&self, x: u32, threshold: u32) -> u32 {
        if x < threshold {
            0
        } else {
            self.term_bits(x)
        }
    }
}

/// `s · xⁿ` with 16 fractional bits for `s` and `x` in `[0, 2¹⁶]` (`0⁰` is 1): the strength
/// times the power by repeated squaring, each product rounded to nearest. Every operand stays
/// within `[0, 2¹⁶]` (`x < 2¹⁶` once past the exact `x = 1`), so the products fit 32 bits:
/// `2¹⁶·(2¹⁶ − 1) + 2¹⁵ < 2³²`. Error: each rounding is at most 2⁻¹⁷ and products of factors
/// at most 1 add their factors' errors (`|ãb̃ − ab| ≤ |ã − a| + |b̃ − b|` plus the rounding), so
/// the result, a product of `n + 1` factors by `n` roundings, is within `n·2⁻¹⁷` of `s·xⁿ`.
#[inline]
pub(crate) fn specular_power(s: u32, x: u32, n: u8) -> u32 {
    let s = s.min(1 << 16);
    if x >= 1 << 16 {
        return s;
    }
    let (mut result, mut base, mut e) = (s, x, n);
    while e != 0 {
        if e & 1 != 0 {
            result = (result * base + (1 << 15)) >> 16;
        }
        e >>= 1;
        if e != 0 {
            base = (base * base + (1 << 15)) >> 16;
        }
    }
    result
}

/// A draw's highlight for per-pixel lighting: the material's [`Specular`] and the half vector
/// in the light's (world) space.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Highlight {
    /// `ĥ = normalize(l + v)`, raw `I16F16`, unit or zero.
    pub(crate) half: Vec3,
    pub(crate) specular: Specular,
    /// The specular's [`threshold`](Specular::threshold).
    pub(crate) threshold: u32,
}

impl Highlight {
    /// The highlight `specular` about the half vector `half`.
    pub(crate) fn new(half: Vec3, specular: Specular) -> Self {
        Highlight {
            half,
            specular,
            threshold: specular.threshold(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The power is non-decreasing in the cosine, and the threshold is where it leaves 0.
    #[test]
    fn specular_thresholds() {
        for strength in [0, 1, 300, 40000, 65535, 65536] {
            for n in 0..=255u8 {
                let s = Specular::new(Scalar::from_bits(strength), n);
                let t = s.threshold();
                let mut last = 0;
                for x in 0..=1 << 16 {
                    let v = s.term_bits(x);
                    assert!(v >= last, "{strength} {n} {x}");
                    assert_eq!(v > 0, x >= t, "{strength} {n} {x}: threshold {t}");
                    assert_eq!(s.term_above(x, t), v);
                    last = v;
                }
            }
        }
    }

    #[test]
    fn light_levels() {
        let l = Light::new(Vec3::from_bits(0, 0, 3 << 16), Scalar::from_num(0.25));
        assert_eq!(l.direction, Vec3::from_bits(0, 0, 1 << 16));
        assert_eq!(l.level(Vec3::from_bits(0, 0, 1 << 16)), Scalar::ONE);
        assert_eq!(
            l.level(Vec3::from_bits(0, 0, -1 << 16)),
            Scalar::from_num(0.25)
        );
        assert_eq!(
            l.level(Vec3::from_bits(1 << 16, 0, 0)),
            Scalar::from_num(0.25)
        );
    }
}
