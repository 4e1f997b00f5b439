//! The f64 light model of the pipeline's lights ([`Light`](crate::three_d::Light) and
//! [`Lights`](crate::three_d::Lights)), written from their documentation: several directional
//! and point lights with the windowed falloff `(1 − d²/r²)²`, Lambert diffuse and Blinn-Phong
//! highlights with an infinite viewer.

use std::vec::Vec;

use super::texture::{blinn_phong, lambert};

/// A light source of the f64 model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Source {
    /// From `direction` (towards the light, any length but zero).
    Directional {
        /// Towards the light.
        direction: [f64; 3],
        /// Its intensity.
        intensity: f64,
    },
    /// From `position`, reaching distances below `range`.
    Point {
        /// World position.
        position: [f64; 3],
        /// Its intensity.
        intensity: f64,
        /// Distance where the falloff reaches 0.
        range: f64,
    },
}

/// The windowed falloff `(1 − (d/r)²)²` for `d < r`, 0 from `r` on.
pub fn falloff(distance: f64, range: f64) -> f64 {
    if distance >= range {
        return 0.0;
    }
    let t = distance / range;
    (1.0 - t * t).powi(2)
}

/// A scene's lights: the first light (a direction, `None` for ambient only, and the ambient
/// level), the other sources, the direction towards the viewer and the material's highlight
/// (strength and shininess, if any).
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The first light's direction towards it.
    pub direction: Option<[f64; 3]>,
    /// The ambient level.
    pub ambient: f64,
    /// The other sources.
    pub sources: Vec<Source>,
    /// Towards the (infinite) viewer.
    pub eye: [f64; 3],
    /// Strength and shininess of the highlight.
    pub specular: Option<(f64, f64)>,
}

impl Scene {
    /// The light level and the specular term (the highlights' sum), each saturating at 1, of a
    /// surface at world position `x` with normal `normal` (any length but zero):
    ///
    /// `level = ambient + (1 − ambient)·max(0, n̂·l̂₀) + Σ intensityᵢ·aᵢ·max(0, n̂·l̂ᵢ)`,
    /// `specular = strength·(max(0, n̂·ĥ₀)^s + Σ intensityᵢ·aᵢ·max(0, n̂·ĥᵢ)^s)` (each highlight
    /// only where its light faces the surface), `aᵢ` the falloff of a point light (1 for a
    /// directional one), `l̂ᵢ` towards it. A point light at `x` itself lights nothing.
    pub fn terms(&self, x: [f64; 3], normal: [f64; 3]) -> (f64, f64) {
        let (strength, shininess) = self.specular.unwrap_or((0.0, 1.0));
        let mut level = self.ambient;
        let mut specular = 0.0;
        if let Some(l) = self.direction {
            level += (1.0 - self.ambient) * lambert(normal, l);
            specular += strength * blinn_phong(normal, l, self.eye, shininess);
        }
        for source in &self.sources {
            let (l, w) = match *source {
                Source::Directional {
                    direction,
                    intensity,
                } => (direction, intensity),
                Source::Point {
                    position,
                    intensity,
                    range,
                } => {
                    let d = [0, 1, 2].map(|k| position[k] - x[k]);
                    let distance = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                    if distance == 0.0 {
                        continue;
                    }
                    (d, intensity * falloff(distance, range))
                }
            };
            level += w * lambert(normal, l);
            specular += w * strength * blinn_phong(normal, l, self.eye, shininess);
        }
        (level.min(1.0), specular.min(1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec;

    #[test]
    fn falloff_is_one_at_the_light_and_zero_at_the_range() {
        assert_eq!(falloff(0.0, 2.0), 1.0);
        assert_eq!(falloff(1.0, 2.0), 0.5625);
        assert_eq!(falloff(2.0, 2.0), 0.0);
        assert_eq!(falloff(3.0, 2.0), 0.0);
    }

    #[test]
    fn lights_add_up_and_saturate() {
        let scene = Scene {
            direction: Some([0.0, 0.0, 1.0]),
            ambient: 0.2,
            sources: vec![Source::Point {
                position: [0.0, 0.0, 1.0],
                intensity: 0.5,
                range: 2.0,
            }],
            eye: [0.0, 0.0, 1.0],
            specular: None,
        };
        assert_eq!(scene.terms([0.0; 3], [0.0, 0.0, 1.0]).0, 1.0);
        let (level, _) = scene.terms([0.0; 3], [1.0, 0.0, 0.0]);
        assert!((level - 0.2).abs() < 1e-12);
    }
}
