//! The light of a scene: one directional light with an ambient term ([`Light`]), and up to
//! [`Lights::MAX`] more directional and point lights ([`Lights`], [`LightSource`]). The vertex
//! stage lights vertices with them and the fills shade pixels with them, so they sit below both.

use super::math::{normalize_wide, sat32, Mat4, Scalar, ToScalar, Vec3};
use crate::raster::arith::{leading_zeros_64, mul_i32_wide, reciprocal_63};

/// A directional light with an ambient term.
///
/// A surface with unit normal `n` receives `level = ambient + (1 − ambient)·max(0, n·l)`. A
/// pipeline takes one ([`Pipeline::light`](super::Pipeline::light)), and up to three more
/// directional and point lights in a [`Lights`] set; `Light::new(Vec3::ZERO, ambient)` is the
/// ambient term alone.
///
/// # Examples
///
/// ```
/// use embedded_raster::three_d::{Light, Scalar, Vec3};
///
/// // From the viewer's side (+z), with 15% ambient: the level is a float, an integer or a
/// // `Scalar` (any `ToScalar`), like `Vec3::new`'s components.
/// let direction = Vec3::new(0, 0, 2);
/// let light = Light::new(direction, 0.15);
/// assert_eq!(light.direction(), Vec3::new(0, 0, 1));
/// assert_eq!(light.ambient(), Scalar::from_num(0.15));
/// // Facing the light: fully lit; edge-on or facing away: the ambient level alone.
/// assert_eq!(light.level(Vec3::new(0, 0, 1)), Scalar::ONE);
/// assert_eq!(light.level(Vec3::new(1, 0, 0)), light.ambient());
/// assert_eq!(light.level(Vec3::new(0, 0, -1)), light.ambient());
/// // Levels are clamped to [0, 1].
/// assert_eq!(Light::new(direction, 2).ambient(), Scalar::ONE);
/// ```
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
    pub fn new(direction: Vec3, ambient: impl ToScalar) -> Self {
        Light {
            direction: direction.normalize(),
            ambient: ambient.to_scalar().clamp(Scalar::ZERO, Scalar::ONE),
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

/// Most light sources a [`Lights`] set holds besides the pipeline's [`Light`] (fixed-function
/// OpenGL's `GL_LIGHT1` … `GL_LIGHT3` next to `GL_LIGHT0`).
const MAX_SOURCES: usize = 3;

/// Largest intensity of a [`LightSource`]: 4.
const MAX_INTENSITY: i32 = 4 << 16;

/// What a [`LightSource`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Kind {
    /// From a direction (unit vector towards the light).
    Directional,
    /// From a position, within a range.
    Point,
}

/// A light besides the pipeline's [`Light`]: a directional light or a point light, white, of
/// some intensity, in world space (the space of [`Light`]'s direction).
///
/// A surface with unit normal `n` at world position `X` receives from it, added to the
/// [`Light`]'s level (the sum saturating at 1):
///
/// * directional (direction `l`): `intensity · max(0, n·l)`;
/// * point (position `P`, range `r`): `intensity · a · max(0, n·l)` with
///   `l = (P − X)/|P − X|` and the windowed falloff
///
///   `a = (1 − d²/r²)²` for `d = |P − X| < r`, 0 beyond,
///
///   smooth (its slope is 0 at `d = r`), 1 at the light, and without a division per vertex:
///   `1/r²` is found once per draw, `l` with the table-and-Newton [`inv_sqrt`](super::inv_sqrt).
///   A surface point at the light's position (`d = 0`) gets nothing from it (no direction).
///
/// With a [`Specular`] material each source adds its own highlight, `intensity · a ·
/// strength · max(0, n·ĥ)^shininess` (`a = 1` for a directional light), its half vector
/// `ĥ = normalize(l + v)` per draw for a directional light and per vertex (or face: flat
/// shading and per-pixel lighting) for a point light, whose `l` varies.
///
/// Ranges: the intensity is clamped to `[0, 4]`, the range to `[0, 32768)` (raw `I16F16`,
/// non-negative); positions and distances are raw `I16F16` (differences saturate at ±32768
/// per axis, beyond which nothing is lit anyway for ranges below it).
///
/// # Examples
///
/// ```
/// use embedded_raster::three_d::{LightSource, Scalar, Vec3};
///
/// let lamp = LightSource::point(Vec3::new(0, 2, 0), 0.8, 4);
/// assert_eq!(lamp.position(), Some(Vec3::new(0, 2, 0)));
/// // Half the range away: (1 − ¼)² = 0.5625 (of the intensity, 0.8).
/// let a = lamp.falloff(Scalar::from_num(2) * Scalar::from_num(2));
/// assert_eq!(a, Scalar::from_num(0.5625));
/// // At and beyond the range: nothing.
/// assert_eq!(lamp.falloff(Scalar::from_num(16)), Scalar::ZERO);
///
/// let sun = LightSource::directional(Vec3::new(0, 0, 3), 0.5);
/// assert_eq!(sun.direction(), Some(Vec3::new(0, 0, 1)));
/// assert_eq!(sun.falloff(Scalar::from_num(100)), Scalar::ONE);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct LightSource {
    kind: Kind,
    /// The unit direction towards a directional light, or a point light's position.
    vector: Vec3,
    /// In `[0, 4]`.
    intensity: Scalar,
    /// A point light's range, in `[0, 32768)`; 0 for a directional light.
    range: Scalar,
}

impl LightSource {
    /// A directional light shining from `direction` (normalised here; the zero vector lights
    /// nothing) with `intensity` (clamped to `[0, 4]`).
    pub fn directional(direction: Vec3, intensity: impl ToScalar) -> Self {
        LightSource {
            kind: Kind::Directional,
            vector: direction.normalize(),
            intensity: intensity
                .to_scalar()
                .clamp(Scalar::ZERO, Scalar::from_bits(MAX_INTENSITY)),
            range: Scalar::ZERO,
        }
    }

    /// A point light at `position` (world space) with `intensity` (clamped to `[0, 4]`),
    /// reaching surfaces closer than `range` (clamped to `[0, 32768)`) with the falloff
    /// [`falloff`](Self::falloff).
    pub fn point(position: Vec3, intensity: impl ToScalar, range: impl ToScalar) -> Self {
        LightSource {
            kind: Kind::Point,
            vector: position,
            intensity: intensity
                .to_scalar()
                .clamp(Scalar::ZERO, Scalar::from_bits(MAX_INTENSITY)),
            range: range.to_scalar().max(Scalar::ZERO),
        }
    }

    /// The unit direction towards a directional light (`None` for a point light).
    pub fn direction(&self) -> Option<Vec3> {
        (self.kind == Kind::Directional).then_some(self.vector)
    }

    /// A point light's position (`None` for a directional light).
    pub fn position(&self) -> Option<Vec3> {
        (self.kind == Kind::Point).then_some(self.vector)
    }

    /// The intensity, in `[0, 4]`.
    pub const fn intensity(&self) -> Scalar {
        self.intensity
    }

    /// A point light's range (0 for a directional light).
    pub const fn range(&self) -> Scalar {
        self.range
    }

    /// The falloff at squared distance `distance_squared` from a point light:
    /// `(1 − d²/r²)²` below the range `r`, 0 from it on, within 2⁻¹⁶ of the exact value
    /// (1 for a directional light). Computed as the draws compute it: `1/r²` once, then
    /// products only.
    pub fn falloff(&self, distance_squared: Scalar) -> Scalar {
        if self.kind == Kind::Directional {
            return Scalar::ONE;
        }
        // 32 fractional bits.
        let d2 = (distance_squared.to_bits().max(0) as u64) << 16;
        Scalar::from_bits(Range::new(self.range).falloff(d2) as i32)
    }
}

/// The light sources a [`Pipeline`](super::Pipeline) adds to its [`Light`]: up to
/// [`MAX`](Self::MAX) directional and point lights, stored inline (no heap).
///
/// The pipeline's [`Light`] stays the first light with the ambient term; these add to it. An
/// empty set (the default) draws exactly as before, at the same cost; sources of intensity 0 (or
/// point lights of range 0) are left out of the draws, so they cost nothing either.
///
/// Flat shading lights a face at its centroid, Gouraud shading each vertex, and per-pixel
/// lighting ([`Shading::Quadratic`](super::Shading), a [`Material`](super::Material) or a
/// [`TexturedMaterial`](super::TexturedMaterial)) each pixel's normal, with a point light's
/// direction and falloff taken at the face's centroid: within the bound
/// [`Pipeline::with_lights`](super::Pipeline::with_lights) states of the light at each pixel's
/// own surface point (a few LSB on finely subdivided meshes, tens of LSB on faces as large as
/// their distance to the light).
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
/// use embedded_raster::three_d::meshes::icosphere::ICOSPHERE;
/// use embedded_raster::three_d::{Angle, DepthTarget, Light, LightSource, Lights, Mat4};
/// use embedded_raster::three_d::{Material, Pipeline, Shading, Specular, Vec3};
///
/// let lights = Lights::new()
///     .with(LightSource::point(Vec3::new(2, 1, 2), 1, 5))
///     .with(LightSource::directional(Vec3::new(-1, 0, 0), 0.3));
/// assert_eq!(lights.sources().len(), 2);
///
/// let camera = Mat4::perspective(Angle::from_degrees(50), 1, 0.5, 20).unwrap()
///     * Mat4::look_at(Vec3::new(0, 0, 4), Vec3::ZERO, Vec3::new(0, 1, 0)).unwrap();
/// let viewport = Rectangle::new(Point::zero(), Size::new(48, 48));
/// // Only the ambient term from the first light: its direction is zero.
/// let light = Light::new(Vec3::ZERO, 0.1);
/// let pipeline = Pipeline::new(Mat4::IDENTITY, camera, viewport, light).with_lights(lights);
///
/// let (mut px, mut z) = ([Rgb565::BLACK; 48 * 48], [0u16; 48 * 48]);
/// let mut target = DepthTarget::new(&mut px, &mut z, 48, 48).unwrap();
/// target.clear(Rgb565::BLACK);
/// let shiny = Material::new(Rgb565::new(20, 40, 20), Shading::Gouraud)
///     .with_specular(Specular::new(0.6, 16));
/// let stats = pipeline.draw_mesh(&ICOSPHERE, &shiny, &mut target);
/// assert!(stats.drawn > 0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Lights {
    /// The first `len` are the set's.
    sources: [LightSource; MAX_SOURCES],
    len: u8,
}

impl Default for Lights {
    fn default() -> Self {
        Lights::new()
    }
}

impl Lights {
    /// Most sources a set holds: 3 (with the pipeline's [`Light`], four lights).
    pub const MAX: usize = MAX_SOURCES;

    /// The empty set.
    pub const fn new() -> Self {
        const NONE: LightSource = LightSource {
            kind: Kind::Directional,
            vector: Vec3::ZERO,
            intensity: Scalar::ZERO,
            range: Scalar::ZERO,
        };
        Lights {
            sources: [NONE; MAX_SOURCES],
            len: 0,
        }
    }

    /// Adds `source`: `Err(source)` if the set is full.
    pub fn push(&mut self, source: LightSource) -> Result<(), LightSource> {
        match self.sources.get_mut(usize::from(self.len)) {
            Some(slot) => {
                *slot = source;
                self.len += 1;
                Ok(())
            }
            None => Err(source),
        }
    }

    /// The set with `source` added (left out if the set is full: see [`push`](Self::push)).
    pub fn with(mut self, source: LightSource) -> Self {
        let _ = self.push(source);
        self
    }

    /// The sources, in the order they were added.
    pub fn sources(&self) -> &[LightSource] {
        self.sources
            .get(..usize::from(self.len))
            .unwrap_or(&self.sources)
    }

    /// Whether a draw lights anything with them: some source of non-zero intensity (and
    /// range, for a point light; direction, for a directional one).
    pub(crate) fn lit(&self) -> bool {
        self.sources().iter().any(LightSource::lights)
    }
}

impl LightSource {
    /// Whether it can light anything.
    fn lights(&self) -> bool {
        self.intensity.to_bits() > 0
            && match self.kind {
                Kind::Directional => self.vector != Vec3::ZERO,
                Kind::Point => self.range.to_bits() > 0,
            }
    }
}

/// A point light's range ready for [`falloff`](Self::falloff): `r²` (32 fractional bits)
/// normalised to `[2³¹, 2³²)` by a shift, and `⌊2⁶³ / r²⌋` of it, found once per draw. (In
/// 32-bit words: a draw's state keeps the alignment of 4 its hot fields are laid out for.)
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Range {
    /// `r²`, 32 fractional bits (below 2⁶²): high and low words.
    r2: [u32; 2],
    /// Left shift (`≥ 0`) or right shift (`< 0`) taking `r²` to `[2³¹, 2³²)`.
    shift: i32,
    /// `⌊2⁶³ / (r² shifted)⌋`, in `(2³¹, 2³²)` (`2³² − 1` for `2³²`, 2⁻³² of it).
    inverse: u32,
}

impl Range {
    pub(crate) fn new(range: Scalar) -> Self {
        let r = range.to_bits().max(0) as u64;
        let r2 = r * r;
        if r2 == 0 {
            return Range {
                r2: [0; 2],
                shift: 0,
                inverse: 0,
            };
        }
        let shift = leading_zeros_64(r2) as i32 - 32;
        let n = shifted(r2, shift);
        Range {
            r2: [(r2 >> 32) as u32, r2 as u32],
            shift,
            inverse: reciprocal_63(n as u32).min(u64::from(u32::MAX)) as u32,
        }
    }

    /// `(1 − d²/r²)²` with 16 fractional bits (in `[0, 2¹⁶]`) for `d²` with 32 fractional bits:
    /// 0 from `d² ≥ r²` on. `t = d²/r²` is `(d² shifted)·⌊2⁶³/(r² shifted)⌋ / 2³²` (31
    /// fractional bits, within about 2⁻²⁹ of `t`: the shifted `d²` is truncated to 32 bits
    /// below the shifted `r²`, the reciprocal floored), then `u = 1 − t` to 24 bits and `u²`
    /// rounded to 16: within 2⁻¹⁶ in all (measured: 2⁻¹⁷ and a little).
    #[inline]
    pub(crate) fn falloff(&self, d2: u64) -> u32 {
        let r2 = (u64::from(self.r2[0]) << 32) | u64::from(self.r2[1]);
        if d2 >= r2 {
            return 0;
        }
        let n = shifted(d2, self.shift);
        // Below 2³²·2³² = 2⁶⁴.
        let t = ((n * u64::from(self.inverse)) >> 32).min(1 << 31);
        // 1 − t with 24 fractional bits, squared: 48, rounded to 16.
        let u = ((1u64 << 31) - t) >> 7;
        ((u * u + (1 << 31)) >> 32) as u32
    }
}

/// `v` shifted left by `shift` (right by `−shift` if negative), for `v < 2⁶⁴` whose result the
/// caller knows to fit.
#[inline(always)]
fn shifted(v: u64, shift: i32) -> u64 {
    if shift >= 0 {
        v << (shift as u32).min(63)
    } else {
        v >> (shift.unsigned_abs()).min(63)
    }
}

/// A draw's lights besides the plain path's: the pipeline's [`Light`] and its [`Lights`] in
/// world space, evaluated at world positions and normals (the model matrix and the normal
/// matrix once per vertex), with the material's highlight if it has one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct LightRig {
    /// The model matrix's first three rows (raw): model space to world space.
    model: [[i32; 4]; 3],
    /// The normal matrix's 3×3 block (raw).
    normals: [[i32; 3]; 3],
    /// The first light's direction (raw `I16F16`, unit or zero), its ambient level (16
    /// fractional bits) and its half vector.
    direction: [i32; 3],
    ambient: u32,
    half: [i32; 3],
    /// The unit direction towards the (infinite) viewer.
    view: [i32; 3],
    /// The sources that light anything, `count` of them.
    sources: [Prepared; MAX_SOURCES],
    count: usize,
    /// The material's highlight and its threshold.
    specular: Option<(Specular, u32)>,
}

/// A [`LightSource`] ready for a draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Prepared {
    point: bool,
    /// A directional light's unit direction or a point light's position (raw).
    vector: [i32; 3],
    /// A directional light's half vector (raw, unit or zero).
    half: [i32; 3],
    /// 16 fractional bits, in `[0, 2¹⁸]`.
    intensity: u32,
    range: Range,
}

impl Prepared {
    /// A point light seen from `x` (raw world position): the unit direction towards it (raw)
    /// and its falloff there, or `None` beyond its range.
    #[inline(always)]
    fn towards(&self, x: &[i32; 3]) -> Option<([i32; 3], u32)> {
        let d: [i32; 3] =
            core::array::from_fn(|k| sat32(i64::from(self.vector[k]) - i64::from(x[k])));
        // Below 3·2⁶²: 32 fractional bits.
        let d2: u64 = d
            .iter()
            .map(|c| u64::from(c.unsigned_abs()).pow(2))
            .fold(0, u64::saturating_add);
        let falloff = self.range.falloff(d2);
        (falloff != 0).then(|| (normalize_wide(d.map(i64::from)).to_bits(), falloff))
    }
}

impl LightRig {
    /// The lights of a draw: `None` if `lights` light nothing (the plain path draws it).
    /// `view` is the unit world-space direction towards the viewer, `specular` the
    /// material's highlight (of non-zero strength) if any.
    pub(crate) fn new(
        light: &Light,
        lights: &Lights,
        model: &Mat4,
        normal_matrix: &Mat4,
        view: Vec3,
        specular: Option<Specular>,
    ) -> Option<Self> {
        if !lights.lit() {
            return None;
        }
        let view = view.to_bits();
        let half_of = |l: [i32; 3]| {
            normalize_wide(core::array::from_fn(|k| {
                i64::from(l[k]) + i64::from(view[k])
            }))
            .to_bits()
        };
        let direction = light.direction.to_bits();
        let empty = Prepared {
            point: false,
            vector: [0; 3],
            half: [0; 3],
            intensity: 0,
            range: Range::new(Scalar::ZERO),
        };
        let mut sources = [empty; MAX_SOURCES];
        let mut count = 0;
        for (slot, s) in sources
            .iter_mut()
            .zip(lights.sources().iter().filter(|s| s.lights()))
        {
            let vector = s.vector.to_bits();
            *slot = Prepared {
                point: s.kind == Kind::Point,
                vector,
                half: half_of(vector),
                intensity: s.intensity.to_bits().clamp(0, MAX_INTENSITY) as u32,
                range: Range::new(s.range),
            };
            count += 1;
        }
        let (m, n) = (model.to_bits(), normal_matrix.to_bits());
        Some(LightRig {
            model: [m[0], m[1], m[2]],
            normals: core::array::from_fn(|r| core::array::from_fn(|c| n[r][c])),
            direction,
            ambient: light.ambient.to_bits().clamp(0, 1 << 16) as u32,
            half: half_of(direction),
            view,
            sources,
            count,
            specular: specular.map(|s| (s, s.threshold())),
        })
    }

    /// The world position of a model-space point (raw, saturating).
    #[inline]
    fn world(&self, p: Vec3) -> [i32; 3] {
        let p = p.to_bits();
        self.model.map(|row| {
            let acc = (0..3)
                .map(|c| mul_i32_wide(row[c], p[c]))
                .fold(i64::from(row[3]) << 16, i64::saturating_add);
            sat32(acc.saturating_add(1 << 15) >> 16)
        })
    }

    /// The unit world normal of a model-space normal (raw; zero for a zero normal).
    #[inline]
    fn world_normal(&self, n: Vec3) -> [i32; 3] {
        let n = n.to_bits();
        normalize_wide(self.normals.map(|row| {
            (0..3)
                .map(|c| mul_i32_wide(row[c], n[c]))
                .fold(0i64, i64::saturating_add)
        }))
        .to_bits()
    }

    /// The light level and the specular term at the model-space point `p` with normal `n`,
    /// 16 fractional bits each, in `[0, 2¹⁶]` (the specular term 0 without a highlight): both
    /// saturate at 1, as fixed-function OpenGL clamps a vertex's colour.
    #[inline(never)]
    pub(crate) fn terms(&self, p: Vec3, n: Vec3) -> (u32, u32) {
        self.terms_world(self.world(p), self.world_normal(n))
    }

    /// [`terms`](Self::terms) of the face `model` (model space): at its centroid, with its
    /// geometric normal.
    #[inline(never)]
    pub(crate) fn face_terms(&self, model: &[Vec3; 3]) -> (u32, u32) {
        let (e1, e2) = (model[1] - model[0], model[2] - model[0]);
        let normal = normalize_wide(e1.cross_wide(e2));
        let [a, b, c] = model.map(|p| p.to_bits().map(i64::from));
        // sum/3 within a unit: sum·⌈2³²/3⌉/2³² (no division).
        let third = |k: usize| {
            let sum = i128::from(a[k] + b[k] + c[k]);
            sat32(((sum * 0x5555_5556) >> 32) as i64)
        };
        let centroid = Vec3::from_bits(third(0), third(1), third(2));
        self.terms(centroid, normal)
    }

    /// The sources as per-pixel light reads them on the face `model` (model space), the first
    /// `count` of the array: a directional light's direction, half vector and intensity; a
    /// point light's direction, half vector and intensity × falloff at the face's centroid
    /// (per face, not per pixel: an approximation on faces large beside their distance to the
    /// light). Point lights out of range there are left out.
    #[inline(never)]
    pub(crate) fn pixel_sources(&self, model: &[Vec3; 3]) -> ([PixelSource; MAX_SOURCES], usize) {
        let [a, b, c] = model.map(|p| p.to_bits().map(i64::from));
        // sum/3 within a unit, as `face_terms`.
        let third = |k: usize| {
            let sum = i128::from(a[k] + b[k] + c[k]);
            sat32(((sum * 0x5555_5556) >> 32) as i64)
        };
        let x = self.world(Vec3::from_bits(third(0), third(1), third(2)));
        let mut out = [PixelSource::default(); MAX_SOURCES];
        let mut count = 0;
        for s in self.sources.iter().take(self.count) {
            let source = if s.point {
                let Some((l, falloff)) = s.towards(&x) else {
                    continue;
                };
                let h = normalize_wide(core::array::from_fn(|k| {
                    i64::from(l[k]) + i64::from(self.view[k])
                }))
                .to_bits();
                let w = (u64::from(s.intensity) * u64::from(falloff) + (1 << 15)) >> 16;
                PixelSource {
                    l,
                    h,
                    weight: w as u32,
                }
            } else {
                PixelSource {
                    l: s.vector,
                    h: s.half,
                    weight: s.intensity,
                }
            };
            if let Some(slot) = out.get_mut(count) {
                *slot = source;
                count += 1;
            }
        }
        (out, count)
    }

    /// [`terms`](Self::terms)' level as 8.8 of the 0–255 scale (the plain path's
    /// [`level`](Light::level) form).
    #[inline(never)]
    pub(crate) fn level(&self, p: Vec3, n: Vec3) -> u16 {
        to_255(self.terms(p, n).0)
    }

    /// [`face_terms`](Self::face_terms)' level as 8.8 of the 0–255 scale.
    #[inline(never)]
    pub(crate) fn face_level(&self, model: &[Vec3; 3]) -> u16 {
        to_255(self.face_terms(model).0)
    }

    /// The light at world position `x` (raw) with unit world normal `n` (raw): the first
    /// light's `ambient + (1 − ambient)·max(0, n·l)` plus each source's
    /// `intensity · falloff · max(0, n·lᵢ)`, saturating at 1, and the highlights' sum,
    /// saturating at 1.
    fn terms_world(&self, x: [i32; 3], n: [i32; 3]) -> (u32, u32) {
        // Unit vectors: the products' sum within about ±2³², 32 fractional bits.
        let dot = |a: &[i32; 3]| {
            mul_i32_wide(n[0], a[0]) + mul_i32_wide(n[1], a[1]) + mul_i32_wide(n[2], a[2])
        };
        // A cosine with 16 fractional bits, in [0, 2¹⁶].
        let cosine = |a: &[i32; 3]| (dot(a).saturating_add(1 << 15) >> 16).clamp(0, 1 << 16) as u32;
        let highlight = |h: &[i32; 3]| match &self.specular {
            Some((s, threshold)) => s.term_above(cosine(h), *threshold),
            None => 0,
        };
        let d = cosine(&self.direction);
        let a = self.ambient;
        let mut level = a + ((u64::from((1 << 16) - a) * u64::from(d) + (1 << 15)) >> 16) as u32;
        let mut specular = if d > 0 { highlight(&self.half) } else { 0 };
        for s in self.sources.iter().take(self.count) {
            let (l, h, weight) = if s.point {
                let Some((l, falloff)) = s.towards(&x) else {
                    continue;
                };
                let h = match self.specular {
                    Some(_) => normalize_wide(core::array::from_fn(|k| {
                        i64::from(l[k]) + i64::from(self.view[k])
                    }))
                    .to_bits(),
                    None => [0; 3],
                };
                let w = (u64::from(s.intensity) * u64::from(falloff) + (1 << 15)) >> 16;
                (l, h, w as u32)
            } else {
                (s.vector, s.half, s.intensity)
            };
            let d = cosine(&l);
            if d == 0 {
                continue;
            }
            // Below 2¹⁸·2¹⁶ each.
            let weigh = |v: u32| ((u64::from(weight) * u64::from(v) + (1 << 15)) >> 16) as u32;
            level = level.saturating_add(weigh(d)).min(1 << 16);
            specular = specular.saturating_add(weigh(highlight(&h))).min(1 << 16);
        }
        (level.min(1 << 16), specular)
    }
}

/// A source of [`Lights`] as per-pixel light reads it ([`LightRig::pixel_sources`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct PixelSource {
    /// The unit direction towards the light and the half vector (raw `I16F16`).
    pub(crate) l: [i32; 3],
    pub(crate) h: [i32; 3],
    /// Intensity (times the falloff), 16 fractional bits, in `[0, 2¹⁸]`.
    pub(crate) weight: u32,
}

/// A level with 16 fractional bits (in `[0, 2¹⁶]`) as 8.8 of the 0–255 scale, as
/// [`Light::level`]'s vertex form.
#[inline(always)]
fn to_255(level: u32) -> u16 {
    ((level.min(1 << 16) * 255) >> 8) as u16
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
/// let shiny = Specular::new(0.5, 32);
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
    pub fn new(strength: impl ToScalar, shininess: u8) -> Self {
        Specular {
            strength: strength.to_scalar().clamp(Scalar::ZERO, Scalar::ONE),
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
