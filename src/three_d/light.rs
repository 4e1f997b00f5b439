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

#[cfg(test)]
mod tests {
    use super::*;

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
