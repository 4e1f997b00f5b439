//! The vertex stage: each mesh vertex transformed to clip space, classified against the view
//! volume, projected and lit — once per draw when the caller gives the pipeline a scratch slice
//! ([`ProjectedVertex`], 16 bytes a vertex), once per face using it otherwise. Both give the same
//! bits, so the frame does not depend on the choice.
//!
//! * **Transform**: the model-view-projection matrix times `(p, 1)` with `i64` accumulation. When
//!   the matrix and the mesh's largest coordinate (found once per draw) keep every sum below 2⁴⁶
//!   (any real camera and model), the products are summed without checks; otherwise through
//!   [`Mat4::transform_point`]'s saturating sums (the same result whenever nothing saturates).
//! * **Project**: one exact 32-bit reciprocal of `w` ([`reciprocal_63`]: a division on 64-bit
//!   hosts, two Newton steps and a correction on Cortex-M — the same integer everywhere), then
//!   one product per coordinate to sub-pixels (within ½ sub-pixel + 2⁻⁷ of the exact quotient)
//!   and to a 16-bit depth.
//! * **Light** (Gouraud): when the normal matrix is a rotation (`RᵀR = I` within 2⁻¹², checked
//!   once per draw), unit model normals stay unit, so the light is turned into model space once
//!   (`Rᵀl`) and each vertex costs one 3-term dot product of 14-bit components: the diffuse
//!   term is within 2⁻¹² of the exact one. Other normal matrices transform and renormalise each
//!   normal ([`normalize_wide`]).

use super::clip::{ClipVolume, W_MIN};
use super::depth::{ScreenVertex, DEPTH_FAR};
use super::light::{Highlight, Light, Specular};
use super::math::{normalize_wide, sat32, Mat4, Vec3, SCALAR_BITS};
use crate::arch::{self, LevelField, LevelLight, NO_LONG_MULTIPLY};
use crate::fixed_point::Coord;
use crate::raster::arith::{
    leading_zeros_32, leading_zeros_64, mul_i32_wide, mul_u32_wide, reciprocal_63,
};

/// Largest viewport side used for the mapping; larger viewports are treated as this size.
const MAX_VIEWPORT: i64 = 65_535;

/// Set in [`ProjectedVertex`]'s code when the mesh has no normal for the vertex: its light level
/// comes from the face.
pub(crate) const NO_NORMAL: u8 = 1 << 7;

/// A mesh vertex as one draw transformed, projected and lit it: the element of the scratch slice
/// of [`Pipeline::draw_mesh_with`](super::Pipeline::draw_mesh_with) (16 bytes). Its contents are
/// private to the pipeline.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[repr(C)]
pub struct ProjectedVertex {
    /// Sub-pixel screen position and depth (valid when the vertex is inside the view volume):
    /// a [`ScreenVertex`]'s fields at its offsets, which the fills take by reference
    /// ([`screen`](Self::screen)): a face's vertices are drawn from the scratch where they are,
    /// not copied.
    x: Coord,
    y: Coord,
    depth: u16,
    /// In a textured draw lit per vertex, the light level (as `level` elsewhere), in the bytes
    /// a `ScreenVertex` leaves as padding.
    texel_level: u16,
    /// Light level, 8.8 fixed point of the 0–255 scale (Gouraud only); in a textured draw the
    /// high 16 bits of `q`, the reciprocal of `w` ([`q`](Self::q)).
    level: u16,
    /// Outside which clip planes (bit `k` for plane `k`), and [`NO_NORMAL`].
    code: u8,
    /// In a textured draw, `q`'s shift (in the byte the others leave free).
    q_shift: u8,
}

// SAFETY: `ProjectedVertex` is `repr(C)`: 16 bytes, 4-byte aligned, x and y at bytes 0 and 4,
// the depth at 8 and the level at 12, as asserted below (a layout change fails the build).
#[allow(unsafe_code)]
unsafe impl crate::arch::LevelVertex for ProjectedVertex {}

// SAFETY: as above, and every one of its 16 bytes is a field's (their sizes add up to 16: no
// padding), the texel level at 10, `q`'s mantissa (`level`) at 12 and its shift at 15 (asserted
// below).
#[allow(unsafe_code)]
unsafe impl crate::arch::ProjectedPrefix for ProjectedVertex {}

// SAFETY: `Vec3` is `repr(C)`: three `I16F16`s (`repr(transparent)` `i32`s) at bytes 0, 4
// and 8, 12 bytes, 4-byte aligned (asserted below).
#[allow(unsafe_code)]
unsafe impl crate::arch::ModelPosition for Vec3 {}

const _: () = {
    use core::mem::{align_of, offset_of, size_of};
    assert!(size_of::<Vec3>() == 12 && align_of::<Vec3>() == 4);
    assert!(offset_of!(Vec3, x) == 0 && offset_of!(Vec3, y) == 4 && offset_of!(Vec3, z) == 8);
    assert!(size_of::<ProjectedVertex>() == 16 && align_of::<ProjectedVertex>() == 4);
    assert!(offset_of!(ProjectedVertex, texel_level) == 10);
    assert!(offset_of!(ProjectedVertex, code) == 14 && offset_of!(ProjectedVertex, q_shift) == 15);
    assert!(2 * size_of::<Coord>() + 3 * size_of::<u16>() + 2 == 16);
    assert!(offset_of!(ProjectedVertex, x) == 0 && offset_of!(ProjectedVertex, y) == 4);
    assert!(offset_of!(ProjectedVertex, depth) == 8 && offset_of!(ProjectedVertex, level) == 12);
    assert!(offset_of!(ScreenVertex, x) == 0 && offset_of!(ScreenVertex, y) == 4);
    assert!(offset_of!(ScreenVertex, depth) == 8 && size_of::<Coord>() == 4);
    assert!(size_of::<ScreenVertex>() == 12 && align_of::<ScreenVertex>() == 4);
};

impl ProjectedVertex {
    /// An entry for a scratch array: `[ProjectedVertex::EMPTY; N]`.
    pub const EMPTY: ProjectedVertex = ProjectedVertex {
        x: Coord::ZERO,
        y: Coord::ZERO,
        depth: 0,
        texel_level: 0,
        level: 0,
        code: 0,
        q_shift: 0,
    };

    /// The vertex at `screen` (its level and `q` 0, inside the view volume).
    #[inline(always)]
    fn at(screen: ScreenVertex) -> Self {
        let ScreenVertex { x, y, depth } = screen;
        ProjectedVertex {
            x,
            y,
            depth,
            ..ProjectedVertex::EMPTY
        }
    }

    /// A vertex inside the view volume at `screen`, lit at `level` (a clipped face's fan).
    pub(crate) fn lit(screen: ScreenVertex, level: u16) -> Self {
        ProjectedVertex {
            level,
            ..Self::at(screen)
        }
    }

    /// The vertex lit at `level` instead (the pipeline's lights, [`Lights`](super::Lights)).
    #[inline(always)]
    pub(crate) fn with_level(self, level: u16) -> Self {
        ProjectedVertex { level, ..self }
    }

    /// A vertex inside the view volume at `screen` with `q` (a textured face's fan).
    pub(crate) fn with_q(screen: ScreenVertex, q: Inverse) -> Self {
        ProjectedVertex {
            level: q.mantissa,
            q_shift: q.shift,
            ..Self::at(screen)
        }
    }

    /// The vertex of a textured draw lit at `level` (its [`texel_level`](Self::texel_level)).
    #[inline(always)]
    pub(crate) fn with_texel_level(self, level: u16) -> Self {
        ProjectedVertex {
            texel_level: level,
            ..self
        }
    }

    /// The vertex of a textured draw marked as without a normal (its level is the face's).
    #[inline(always)]
    pub(crate) fn without_normal(self) -> Self {
        ProjectedVertex {
            code: self.code | NO_NORMAL,
            ..self
        }
    }

    /// In a textured draw lit per vertex, the vertex's light level (8.8 of the 0–255 scale;
    /// meaningful where it has a normal).
    #[inline(always)]
    pub(crate) fn texel_level(&self) -> u16 {
        self.texel_level
    }

    /// In a textured draw, `q = 2⁶³ / w` within 2⁻¹⁵ of itself (`w` the raw clip-space `w`):
    /// what the perspective planes need, proportional to `1/w`.
    #[inline(always)]
    pub(crate) fn q(&self) -> Inverse {
        Inverse {
            mantissa: self.level,
            shift: self.q_shift,
        }
    }

    /// The clip planes the vertex is outside of (0: inside the view volume).
    #[inline(always)]
    pub(crate) fn outside(&self) -> u8 {
        self.code & !NO_NORMAL
    }

    /// Whether the mesh has a normal for this vertex.
    #[inline(always)]
    pub(crate) fn has_normal(&self) -> bool {
        self.code & NO_NORMAL == 0
    }

    /// Position and depth (meaningful when [`outside`](Self::outside) is 0).
    #[inline(always)]
    #[allow(unsafe_code)]
    pub(crate) fn screen(&self) -> &ScreenVertex {
        // SAFETY: both types are `repr(C)` and 4-byte aligned; a `ScreenVertex` is 12 bytes, its
        // `x`, `y` and `depth` at 0, 4 and 8 — where this vertex has fields of the same types
        // (asserted above) — and bytes 10 and 11 padding, which may hold anything (here
        // `texel_level`). The reference borrows `self`, which outlives it.
        unsafe { &*(self as *const ProjectedVertex).cast::<ScreenVertex>() }
    }

    /// Raw sub-pixel position.
    #[inline(always)]
    pub(crate) fn position_bits(&self) -> (i32, i32) {
        (self.x.to_bits(), self.y.to_bits())
    }

    /// The Gouraud light level (8.8 of the 0–255 scale).
    #[inline(always)]
    pub(crate) fn level(&self) -> u16 {
        self.level
    }
}

/// The reciprocal of a vertex's `w` in 24 bits, `mantissa · 2^(16 + shift)` (the high half of
/// the projection's reciprocal and its normalising shift): the `q` of a textured draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Inverse {
    mantissa: u16,
    shift: u8,
}

/// Shifts of a face's three `q` that may differ for [`Inverse::common_scale`]: beyond, their
/// ratio is at least 2⁷ (a face seen that much in perspective takes the perspective path).
const COMMON_SHIFTS: u8 = 8;

impl Inverse {
    /// The `Inverse` of any positive value proportional to `1/w` (0 is taken as 1): its 16 high
    /// bits and their shift, so that [`value`](Self::value) is `q · 2¹⁶` within 2⁻¹⁵ of itself.
    pub(crate) fn of(q: u64) -> Self {
        let q = q.max(1);
        let shift = (64 - leading_zeros_64(q)).saturating_sub(16);
        Inverse {
            mantissa: (q >> shift) as u16,
            shift: shift as u8,
        }
    }

    /// The mantissa and the shift.
    #[inline(always)]
    pub(crate) fn parts(self) -> (u16, u8) {
        (self.mantissa, self.shift)
    }

    /// `mantissa · 2^(16 + shift)`: about 2⁶³ / w.
    #[inline(always)]
    pub(crate) fn value(self) -> u64 {
        u64::from(self.mantissa) << (16 + u32::from(self.shift))
    }

    /// Three values in a common 32-bit scale (`mantissa · 2^(shift − the least shift)`, below
    /// 2²⁴: exactly proportional to their [`value`](Self::value)s) and the largest of those
    /// shift differences, or `None` where they differ by more than [`COMMON_SHIFTS`].
    #[inline(always)]
    pub(crate) fn common_scale(q: [Inverse; 3]) -> Option<([u32; 3], u32)> {
        let least = q[0].shift.min(q[1].shift).min(q[2].shift);
        let d = q.map(|q| q.shift - least);
        let most = d[0].max(d[1]).max(d[2]);
        if most > COMMON_SHIFTS {
            return None;
        }
        // Without indices: no bounds checks where the compiler does not inline (`opt-level`
        // "s", "z").
        let ([q0, q1, q2], [d0, d1, d2]) = (q, d);
        let scaled = [
            u32::from(q0.mantissa) << d0,
            u32::from(q1.mantissa) << d1,
            u32::from(q2.mantissa) << d2,
        ];
        Some((scaled, u32::from(most)))
    }
}

/// The light of one draw, ready for per-vertex levels.
#[derive(Debug, Clone, Copy)]
pub(crate) struct VertexLight {
    /// The light direction in the space the normals are dotted in (model space when
    /// `rotation`, world space otherwise), 14 fractional bits, components within ±2¹⁴.
    direction: [i32; 3],
    /// The normal matrix's 3×3 block (raw), for normal matrices that are not rotations.
    normal_matrix: Option<[[i32; 3]; 3]>,
    /// The ambient level, 16 fractional bits, in `[0, 2¹⁶]`.
    ambient: u32,
}

/// A draw's specular highlight, ready for per-vertex (and per-face) specular terms
/// ([`VertexLight::terms`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct VertexSpecular {
    /// The half vector `ĥ = normalize(l + v)` in the space the normals are dotted in (as
    /// [`VertexLight`]'s direction), raw `I16F16`, unit or zero.
    half: [i32; 3],
    specular: Specular,
    /// The specular's [`threshold`](Specular::threshold).
    threshold: u32,
}

impl VertexLight {
    /// The light `light` for normals transformed by `normal_matrix`.
    pub(crate) fn new(light: &Light, normal_matrix: &Mat4) -> Self {
        let m = normal_matrix.to_bits();
        let block: [[i32; 3]; 3] = core::array::from_fn(|r| core::array::from_fn(|c| m[r][c]));
        let rotation = is_rotation(&block);
        let l = light.direction.to_bits().map(i64::from);
        let direction = if rotation {
            // Rᵀl: the light in model space.
            core::array::from_fn(|c| {
                let acc = (0..3)
                    .map(|r| i64::from(block[r][c]) * l[r])
                    .fold(0i64, i64::saturating_add);
                sat32(acc >> SCALAR_BITS)
            })
        } else {
            light.direction.to_bits()
        };
        VertexLight {
            direction: direction.map(to_14_bits),
            normal_matrix: (!rotation).then_some(block),
            ambient: light.ambient.to_bits().clamp(0, 1 << 16) as u32,
        }
    }

    /// The highlight `h` (its half vector in world space) for this light (of
    /// `normal_matrix`): the half vector turned into model space like the light when the normal
    /// matrix is a rotation (`Rᵀĥ`, renormalised), as it is otherwise.
    pub(crate) fn specular(&self, normal_matrix: &Mat4, h: &Highlight) -> VertexSpecular {
        let half = h.half;
        let half = match self.normal_matrix {
            Some(_) => half,
            None => {
                let m = normal_matrix.to_bits();
                let h = half.to_bits().map(i64::from);
                normalize_wide(core::array::from_fn(|c| {
                    (0..3)
                        .map(|r| i64::from(m[r][c]) * h[r])
                        .fold(0i64, i64::saturating_add)
                }))
            }
        };
        VertexSpecular {
            half: half.to_bits(),
            specular: h.specular,
            threshold: h.threshold,
        }
    }

    /// A model-space normal in the light's space, of unit length: itself when the normal
    /// matrix is a rotation (unit normals stay unit), transformed and renormalised otherwise.
    #[inline]
    fn in_light_space(&self, n: Vec3) -> Vec3 {
        match &self.normal_matrix {
            None => n,
            Some(m) => {
                let v = n.to_bits().map(i64::from);
                normalize_wide(m.map(|row| {
                    (0..3)
                        .map(|c| i64::from(row[c]) * v[c])
                        .fold(0i64, i64::saturating_add)
                }))
            }
        }
    }

    /// The light level and specular term of a model-space unit normal `n`, 16 fractional bits
    /// each (in `[0, 2¹⁶]`): `ambient + (1 − ambient)·max(0, n·l)` as [`level`](Self::level)
    /// (within 2⁻¹⁶ of its level before the 0–255 scale) and
    /// `strength · max(0, n·ĥ)^shininess` of the highlight `s`, 0 where `n·l` rounds to 0 (no
    /// highlight facing away from the light).
    ///
    /// `n·ĥ` is a dot product of raw `I16F16` components (within `2⁻¹⁶` of the exact one for
    /// normals of unit length to 2⁻¹⁷ a component) and the power is
    /// [`Specular::term`]'s.
    #[inline]
    pub(crate) fn terms(&self, n: Vec3, s: &VertexSpecular) -> (u32, u32) {
        let n = self.in_light_space(n);
        let bits = n.to_bits().map(i64::from);
        let l = self.direction.map(i64::from);
        let dot = bits[0] * l[0] + bits[1] * l[1] + bits[2] * l[2];
        // As in `level_of_unit`: the diffuse term rounds to 0 below half a unit of 2⁻¹⁶.
        if dot < 1 << 13 {
            return (self.ambient, 0);
        }
        let diffuse = ((dot + (1 << 13)).min((1 << 30) - 1) as u32) >> 14;
        let lit = (((1 << 16) - self.ambient) * diffuse + (1 << 15)) >> 16;
        let level = (self.ambient + lit).min(1 << 16);
        let h = s.half.map(i64::from);
        // Raw components below 2³¹ times unit ones: below 2⁴⁹.
        let dot = bits[0] * h[0] + bits[1] * h[1] + bits[2] * h[2];
        let x = ((dot + (1 << 15)) >> 16).clamp(0, 1 << 16) as u32;
        (level, s.specular.term_above(x, s.threshold))
    }

    /// The light level of a vertex with model-space unit normal `n`: 8.8 fixed point of the
    /// 0–255 scale, `255·(ambient + (1 − ambient)·max(0, n·l))`.
    #[inline]
    pub(crate) fn level(&self, n: Vec3) -> u16 {
        let n = match &self.normal_matrix {
            None => n,
            Some(m) => {
                let v = n.to_bits().map(i64::from);
                normalize_wide(m.map(|row| {
                    (0..3)
                        .map(|c| i64::from(row[c]) * v[c])
                        .fold(0i64, i64::saturating_add)
                }))
            }
        };
        self.level_of_unit(n)
    }

    /// Lights each vertex of `out` by `set` with the level of the normal of `normals` at its
    /// index (as many as both have): [`level`](Self::level)'s levels, the normal matrix's case
    /// decided once for them all.
    #[inline(always)]
    pub(crate) fn light_all(
        &self,
        normals: &[Vec3],
        out: &mut [ProjectedVertex],
        field: LevelField,
    ) {
        let set = |v: &mut ProjectedVertex, level: u16| match field {
            LevelField::Level => v.level = level,
            LevelField::TexelLevel => v.texel_level = level,
        };
        if self.normal_matrix.is_none() {
            // ARMv7-M: one assembly loop.
            let light = LevelLight::new(self.direction, self.ambient);
            if light.is_some_and(|l| arch::light_levels(normals, out, field, &l)) {
                return;
            }
            for (v, n) in out.iter_mut().zip(normals) {
                set(v, self.level_of_unit(*n));
            }
        } else {
            for (v, n) in out.iter_mut().zip(normals) {
                set(v, self.level(*n));
            }
        }
    }

    /// [`level`](Self::level) for a normal already in the light's space and of unit length.
    #[inline]
    pub(crate) fn level_of_unit(&self, n: Vec3) -> u16 {
        let n = n.to_bits();
        let l = self.direction;
        // Raw components (below 2³¹) times the light's (within ±2¹⁴): below 2⁴⁷, 30 fractional
        // bits.
        let dot = mul_i32_wide(n[0], l[0]) + mul_i32_wide(n[1], l[1]) + mul_i32_wide(n[2], l[2]);
        // ⌊(dot + 2¹³)/2¹⁴⌋ clamped to [0, 2¹⁶ − 1]: the clamp before the shift, where the
        // upper bound is a 32-bit one.
        let rounded = dot + (1 << 13);
        let diffuse = if rounded < 0 {
            0
        } else {
            (rounded.min((1 << 30) - 1) as u32) >> 14
        };
        // Below 2³²: (2¹⁶ − a)·d with d < 2¹⁶.
        let lit = (((1 << 16) - self.ambient) * diffuse + (1 << 15)) >> 16;
        let level = (self.ambient + lit).min(1 << 16);
        ((level * 255) >> 8) as u16
    }
}

/// `⌊32767·r / 2¹⁶⌋` without a long multiply, from `r`'s halves `h`, `l`: `32767·h` plus
/// `⌊32767·l / 2¹⁶⌋` (both 32-bit products; the first term is a whole multiple of 2¹⁶ of the
/// dividend, so the floor is the second's).
#[inline(always)]
fn depth_scale_halves(r: u32) -> u32 {
    32767 * (r >> 16) + ((32767 * (r & 0xFFFF)) >> 16)
}

/// A raw `I16F16` component as 14 fractional bits, clamped to `±1`.
#[inline(always)]
fn to_14_bits(c: i32) -> i32 {
    (c >> 2).clamp(-(1 << 14), 1 << 14)
}

/// `RᵀR = I` within 2⁻¹² per entry.
fn is_rotation(r: &[[i32; 3]; 3]) -> bool {
    (0..3).all(|i| {
        (0..3).all(|j| {
            let dot: i64 = (0..3)
                .map(|k| i64::from(r[k][i]) * i64::from(r[k][j]))
                .fold(0, i64::saturating_add);
            let want = if i == j { 1i64 << 32 } else { 0 };
            (dot - want).unsigned_abs() <= 1 << 20
        })
    })
}

/// One row of the model-view-projection matrix (raw) times `(p, 1)` for a draw whose sums stay
/// below 2⁴⁶ (the bound of [`VertexStage::new`]): the result fits, nothing saturates.
/// (32 × 32-bit products: on Cortex-M0, from limbs rather than 64 × 64-bit library calls.)
#[inline(always)]
fn direct_row(row: &[i32; 4], p: &[i32; 3]) -> i32 {
    if NO_LONG_MULTIPLY {
        return direct_row_limbs(row, p);
    }
    let acc = mul_i32_wide(row[0], p[0])
        + mul_i32_wide(row[1], p[1])
        + mul_i32_wide(row[2], p[2])
        + (i64::from(row[3]) << SCALAR_BITS);
    ((acc + (1 << 15)) >> SCALAR_BITS) as i32
}

/// [`direct_row`] in 32-bit arithmetic from 16-bit limbs (Cortex-M0: no long multiply): the
/// result `⌊(Σ mₖ·pₖ + t·2¹⁶ + 2¹⁵) / 2¹⁶⌋` fits an `i32`, so it is found modulo 2³² from the
/// limbs' products — `mₖ = hₖ·2¹⁶ + lₖ` (`hₖ` signed, `lₖ` unsigned), likewise `pₖ` — as
/// `Σ hₖ·h'ₖ·2¹⁶ + Σ (hₖ·l'ₖ + lₖ·h'ₖ) + t` plus the exact floor of the low products' part,
/// `Σ ⌊lₖ·l'ₖ / 2¹⁶⌋ + ⌊(Σ (lₖ·l'ₖ mod 2¹⁶) + 2¹⁵) / 2¹⁶⌋`: twelve 32-bit multiplies, no
/// 64-bit sums.
#[inline(always)]
fn direct_row_limbs(row: &[i32; 4], p: &[i32; 3]) -> i32 {
    let (mut whole, mut fraction) = (row[3], 1u32 << 15);
    for k in 0..3 {
        let (m, v) = (row[k], p[k]);
        let (ml, mh, vl, vh) = (m & 0xFFFF, m >> 16, v & 0xFFFF, v >> 16);
        let low = (ml as u32) * (vl as u32);
        whole = whole
            .wrapping_add(mh.wrapping_mul(vh) << 16)
            .wrapping_add(mh * vl)
            .wrapping_add(ml * vh)
            .wrapping_add((low >> 16) as i32);
        fraction += low & 0xFFFF;
    }
    whole.wrapping_add((fraction >> 16) as i32)
}

/// What one draw needs to transform, project and light its vertices.
#[derive(Debug, Clone, Copy)]
pub(crate) struct VertexStage {
    mvp: [[i32; 4]; 4],
    /// No sum of the transform can leave ±2⁴⁶ for the mesh's positions: no saturation needed.
    direct: bool,
    /// Every position within the bound is inside the view volume once transformed: the
    /// vertices' outcodes are 0 without testing them.
    inside: bool,
    pub(crate) volume: ClipVolume,
    /// The viewport's centre, sub-pixels (clamped to ±(2³¹ − 2²⁵): beyond, nothing is on a
    /// target anyway), and its half sizes times 2ᵉ (in `[2²², 2²³)` for the larger).
    centre: (i32, i32),
    half: (u32, u32),
    /// `e`, and the rounding of a product shifted right by `32 + e`.
    exponent: u32,
    round: i64,
    /// The light, when vertex levels are wanted.
    light: Option<VertexLight>,
}

impl VertexStage {
    /// The stage of `mvp` into the viewport at `(x, y)` of `width × height` pixels, for
    /// positions whose raw components are at most `bounds` in magnitude (`x`, `y`, `z`),
    /// lighting vertices with `light` when given.
    pub(crate) fn new(
        mvp: &Mat4,
        bounds: [u32; 3],
        ((x, y), (width, height)): ((i32, i32), (u32, u32)),
        light: Option<VertexLight>,
    ) -> Self {
        let mvp = mvp.to_bits();
        let bound = bounds[0].max(bounds[1]).max(bounds[2]);
        let direct = mvp.iter().all(|row| {
            let linear: u64 = row[..3].iter().map(|m| u64::from(m.unsigned_abs())).sum();
            let translation = u64::from(row[3].unsigned_abs()) << SCALAR_BITS;
            linear
                .saturating_mul(u64::from(bound))
                .saturating_add(translation)
                < 1 << 46
        });
        let width = i64::from(width).min(MAX_VIEWPORT);
        let height = i64::from(height).min(MAX_VIEWPORT);
        let half = (width * 128, height * 128);
        // The larger half size to [2²², 2²³) (it is below 2²³: viewports up to 65535 px).
        let exponent = (half.0.max(half.1).max(1) as u32)
            .leading_zeros()
            .saturating_sub(9);
        let limit = i64::from(i32::MAX) - (1 << 25);
        // `max` and `min`, not `clamp`: its bounds check is a panic path where the closure is
        // not inlined (`opt-level` `"z"`).
        let centre =
            |corner: i32, half: i64| (i64::from(corner) * 256 + half).max(-limit).min(limit);
        let volume = ClipVolume::new(width, height);
        // The box of the positions, `±bounds`, inside the view volume: no vertex of the draw
        // needs its outcode (eight corners transformed once a draw).
        let inside = direct && i32::try_from(bound).is_ok() && {
            let corners: [[i32; 4]; 8] = core::array::from_fn(|k| {
                let p: [i32; 3] = core::array::from_fn(|axis| {
                    let b = bounds[axis] as i32;
                    if k >> axis & 1 == 0 {
                        -b
                    } else {
                        b
                    }
                });
                mvp.map(|row| direct_row(&row, &p))
            });
            volume.holds(&corners)
        };
        VertexStage {
            mvp,
            direct,
            inside,
            volume,
            centre: (centre(x, half.0) as i32, centre(y, half.1) as i32),
            half: ((half.0 as u32) << exponent, (half.1 as u32) << exponent),
            exponent,
            round: 1 << (31 + exponent),
            light,
        }
    }

    /// The clip-space position of a model-space point (raw `I16F16` `[x, y, z, w]`): the same
    /// as [`Mat4::transform_point`].
    #[inline(always)]
    pub(crate) fn clip_position(&self, p: Vec3) -> [i32; 4] {
        if !self.direct {
            return Mat4::from_bits(self.mvp).transform_point(p).to_bits();
        }
        let p = p.to_bits();
        self.mvp.map(|row| direct_row(&row, &p))
    }

    /// The `y` and `w` of [`clip_position`](Self::clip_position), the same integers (a band's
    /// test of a face against its rows, before the rest of the vertex).
    #[inline(always)]
    pub(crate) fn clip_height(&self, p: Vec3) -> (i32, i32) {
        if !self.direct {
            let [_, y, _, w] = Mat4::from_bits(self.mvp).transform_point(p).to_bits();
            return (y, w);
        }
        let p = p.to_bits();
        (direct_row(&self.mvp[1], &p), direct_row(&self.mvp[3], &p))
    }

    /// The viewport's vertical centre (sub-pixels) and its half height (sub-pixels from the
    /// centre to the edge, where `y/w = ±1`) as [`project`](Self::project) maps them.
    pub(crate) fn vertical(&self) -> (i32, u32) {
        (self.centre.1, self.half.1 >> self.exponent)
    }

    /// Perspective divide and viewport mapping of a clip-space point inside the view volume
    /// (`w ≥ 2⁻⁸`, `|x|, |y|` within the guard band, `|z| ≤ w`).
    ///
    /// With `w` normalised to `w·2ˢ ∈ [2³¹, 2³²)` and `r = ⌊2⁶³/(w·2ˢ)⌋`, `c/w = c·2ˢ·r/2⁶³`.
    /// Inside the guard band `|x|, |y| ≤ 64·w < 2^(38−s)`, so `c·2^(s−7)` fits 32 bits; the half
    /// size `h` is normalised once per draw to `h·2ᵉ ∈ [2²², 2²³)`, so `k = h·2ᵉ·r/2²⁴` is
    /// below 2³¹ and the offset `c·2^(s−7)·k / 2^(32+e)` is one 32 × 32-bit product and fixed
    /// shifts (rounded; the truncations of `k` and of `c` for far points, `s < 7`, cost under
    /// 2⁻²¹ of the offset, below 0.2 sub-pixels a thousand pixels out). The depth likewise with
    /// `z·2^(s−1)` and `32767·r/2¹⁶`.
    #[inline(always)]
    pub(crate) fn project(&self, p: &[i32; 4]) -> ScreenVertex {
        self.project_inverse(p).0
    }

    /// [`project`](Self::project), and the reciprocal of `w` it used (a textured draw's `q`).
    #[inline(always)]
    pub(crate) fn project_inverse(&self, p: &[i32; 4]) -> (ScreenVertex, Inverse) {
        let w = p[3].max(W_MIN as i32) as u32;
        // w in [2⁸, 2³¹): s in [1, 23].
        let s = leading_zeros_32(w);
        // r ≤ 2³², and 2³² only for w·2ˢ = 2³¹: clamping it changes c/w by 2⁻³².
        let r = reciprocal_63(w << s).min(u64::from(u32::MAX)) as u32;
        let scale = |c: i32| {
            if s >= 7 {
                c << (s - 7)
            } else {
                c >> (7 - s)
            }
        };
        let (e, round) = (self.exponent, self.round);
        // 32 × 32-bit products throughout: h·2ᵉ < 2²³ and r < 2³², so k < 2³¹.
        let offset = |c: i32, half: u32| {
            let k = (mul_u32_wide(half, r) >> 24) as i32;
            (((mul_i32_wide(scale(c), k) + round) >> 32) as i32) >> e
        };
        let x = self.centre.0.wrapping_add(offset(p[0], self.half.0));
        let y = self.centre.1.wrapping_sub(offset(p[1], self.half.1));
        // 32767·z/w: |z| ≤ w < 2^(32−s), so z·2^(s−1) fits and the depth is in [0, 65534].
        let kz = if NO_LONG_MULTIPLY {
            depth_scale_halves(r)
        } else {
            ((32767 * u64::from(r)) >> 16) as u32
        } as i32;
        let dz = ((mul_i32_wide(p[2] << (s - 1), kz) + (1 << 45)) >> 32) as i32 >> 14;
        let screen = ScreenVertex {
            x: Coord::from_bits(x),
            y: Coord::from_bits(y),
            depth: (32767 + dz).clamp(0, i32::from(DEPTH_FAR)) as u16,
        };
        // r·2ˢ = 2⁶³ / w; r ≥ 2³¹, so its high half keeps 15 bits below its first.
        let inverse = Inverse {
            mantissa: (r >> 16) as u16,
            shift: s as u8,
        };
        (screen, inverse)
    }

    /// The light level of a model-space normal (0 without a light).
    #[inline(always)]
    pub(crate) fn level(&self, n: Vec3) -> u16 {
        self.light.as_ref().map_or(0, |l| l.level(n))
    }

    /// The vertices of `positions` into `out` (as many as both have) by the target's assembly
    /// loop ([`arch::project_positions`]) where it has one and the draw's box is inside the view
    /// volume: [`placed`](Self::placed)'s vertices, or if `textured`
    /// [`textured_vertex`](Self::textured_vertex)'s, unlit. `false`, with nothing written,
    /// elsewhere.
    #[inline(always)]
    pub(crate) fn project_inside(
        &self,
        positions: &[Vec3],
        out: &mut [ProjectedVertex],
        textured: bool,
    ) -> bool {
        if !arch::PROJECT_POSITIONS || !self.inside {
            return false;
        }
        let viewport = (self.centre, self.half, self.exponent, self.round);
        let block = arch::ProjectionBlock::new(&self.mvp, viewport, textured);
        arch::project_positions(&block, positions, out)
    }

    /// Transforms, classifies, projects (if inside) and lights the vertex at `p` with normal `n`.
    #[inline(always)]
    pub(crate) fn vertex(&self, p: Vec3, n: Option<&Vec3>) -> ProjectedVertex {
        let mut vertex = self.placed(p);
        self.light_vertex(&mut vertex, n);
        vertex
    }

    /// Lights `vertex` by its normal `n`, or marks it as without one.
    #[inline(always)]
    fn light_vertex(&self, vertex: &mut ProjectedVertex, n: Option<&Vec3>) {
        match n {
            Some(n) => vertex.level = self.level(*n),
            None => vertex.code |= NO_NORMAL,
        }
    }

    /// [`vertex`](Self::vertex) for every position of `positions` (with `normals[k]` for
    /// position `k`) into `out`, which is as long: the same vertices, with the light's cases
    /// decided once for the mesh.
    #[inline(always)]
    pub(crate) fn vertices(
        &self,
        positions: &[Vec3],
        normals: &[Vec3],
        out: &mut [ProjectedVertex],
    ) {
        if self.project_inside(positions, out, false) {
            let count = positions.len().min(out.len());
            let out = &mut out[..count];
            match self.light {
                Some(light) if normals.len() >= out.len() => {
                    light.light_all(normals, out, LevelField::Level);
                }
                _ => {
                    for (k, out) in out.iter_mut().enumerate() {
                        self.light_vertex(out, normals.get(k));
                    }
                }
            }
            return;
        }
        match self.light {
            Some(light) if light.normal_matrix.is_none() && normals.len() >= positions.len() => {
                for ((out, p), n) in out.iter_mut().zip(positions).zip(normals) {
                    *out = self.placed(*p);
                    out.level = light.level_of_unit(*n);
                }
            }
            _ => {
                for (k, (out, p)) in out.iter_mut().zip(positions).enumerate() {
                    *out = self.vertex(*p, normals.get(k));
                }
            }
        }
    }

    /// The outcode of the clip-space position of a vertex of the draw (0 without a test where
    /// the draw's box is inside the view volume).
    #[inline(always)]
    fn outcode(&self, clip: &[i32; 4]) -> u8 {
        if self.inside {
            0
        } else {
            self.volume.outcode(clip)
        }
    }

    /// The vertex at `p` transformed, classified and projected (if inside), unlit.
    #[inline(always)]
    fn placed(&self, p: Vec3) -> ProjectedVertex {
        let clip = self.clip_position(p);
        let code = self.outcode(&clip);
        let screen = if code == 0 {
            self.project(&clip)
        } else {
            ScreenVertex::new(Coord::ZERO, Coord::ZERO, 0)
        };
        ProjectedVertex {
            code,
            ..ProjectedVertex::at(screen)
        }
    }

    /// The vertex at `p` of a textured draw: transformed, classified and projected (if inside),
    /// with its reciprocal `w` in the level's place (its level is found when it is drawn).
    #[inline(always)]
    pub(crate) fn textured_vertex(&self, p: Vec3) -> ProjectedVertex {
        let clip = self.clip_position(p);
        let code = self.outcode(&clip);
        if code != 0 {
            return ProjectedVertex {
                code,
                ..ProjectedVertex::EMPTY
            };
        }
        let (screen, q) = self.project_inverse(&clip);
        ProjectedVertex::with_q(screen, q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::three_d::{Angle, Scalar, Vec3};

    #[test]
    fn rotations_are_recognised() {
        let r = Mat4::rotation_x(Angle::from_degrees(-35))
            * Mat4::rotation_y(Angle::from_degrees(20))
            * Mat4::rotation_z(Angle::from_degrees(71));
        let block = |m: Mat4| {
            let m = m.to_bits();
            core::array::from_fn(|r| core::array::from_fn(|c| m[r][c]))
        };
        assert!(is_rotation(&block(r)));
        assert!(!is_rotation(&block(
            r * Mat4::scaling(Scalar::from_num(1.01))
        )));
        assert!(!is_rotation(&block(Mat4::from_bits([[0; 4]; 4]))));
    }

    /// A draw whose box of positions (`±bound` on each axis) is inside the view volume skips
    /// the vertices' outcodes: every point of the box, transformed and rounded as a vertex is,
    /// must then be inside. Random cameras, each box grown by bisection to the largest the
    /// stage takes (its corners at the margins' edge of some plane), points at and near its
    /// corners, on its edges and inside.
    #[test]
    fn a_box_inside_the_volume_needs_no_outcodes() {
        let mut rng = crate::rng::Rng(0x6f75_7463_6f64_6573);
        let viewport = ((0, 0), (320, 240));
        let (mut boxes, mut points) = (0, 0);
        for _ in 0..400 {
            let degrees =
                |rng: &mut crate::rng::Rng, lo, hi| Angle::from_degrees(rng.range(lo, hi) as i32);
            let fov = degrees(&mut rng, 20, 120);
            let near = rng.range_f64(0.05, 1.0);
            let Some(projection) = Mat4::perspective(fov, 4.0 / 3.0, near, near * 40.0) else {
                continue;
            };
            let scalar = |v: f64| Scalar::from_num(v);
            let offset = Vec3::new(
                scalar(rng.range_f64(-1.0, 1.0)),
                scalar(rng.range_f64(-1.0, 1.0)),
                scalar(-rng.range_f64(0.5, 8.0)),
            );
            let model = Mat4::translation(offset)
                * Mat4::rotation_y(degrees(&mut rng, 0, 359))
                * Mat4::rotation_x(degrees(&mut rng, -90, 90))
                * Mat4::scaling(scalar(rng.range_f64(0.25, 4.0)));
            let mvp = projection * model;
            // The box's shape at random, its size by bisection.
            let shape = [0; 3].map(|_| 1 + rng.below(4) as u32);
            let sized = |size: u32| shape.map(|s| size * s / 4);
            let holds = |size: u32| VertexStage::new(&mvp, sized(size), viewport, None).inside;
            if !holds(0) {
                continue;
            }
            let (mut lo, mut hi) = (0u32, 1 << 22);
            while hi - lo > 1 {
                let mid = (lo + hi) / 2;
                if holds(mid) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let bounds = sized(lo);
            let stage = VertexStage::new(&mvp, bounds, viewport, None);
            assert!(stage.inside);
            boxes += 1;
            let coordinate = |rng: &mut crate::rng::Rng, b: u32, kind: u64| {
                let b = i64::from(b);
                let sign = if rng.chance(2) { 1 } else { -1 };
                match kind {
                    // A corner's, one a little inside it, or anywhere along the axis.
                    0 => b * sign,
                    1 => (b - rng.range(0, 3)).max(0) * sign,
                    _ => rng.range(-b, b),
                }
            };
            for _ in 0..64 {
                let [x, y, z] = core::array::from_fn(|axis| {
                    let kind = rng.below(3);
                    coordinate(&mut rng, bounds[axis], kind) as i32
                });
                let clip = stage.clip_position(Vec3::from_bits(x, y, z));
                assert_eq!(
                    stage.volume.outcode(&clip),
                    0,
                    "{mvp:?} bounds {bounds:?} at {x} {y} {z}"
                );
                points += 1;
            }
        }
        assert!(boxes > 200, "{boxes} boxes");
        assert!(points > 10_000);
    }

    /// The transform's row in 32-bit limbs is the 64-bit sum's rounded quotient: for rows and
    /// points at random (any `i32`s: the quotient modulo 2³², the wrapping `i32` of the exact
    /// value) and at the ends of the range.
    #[test]
    fn direct_row_limbs_is_the_rounded_sum() {
        let exact = |row: &[i32; 4], p: &[i32; 3]| {
            let sum: i128 = (0..3)
                .map(|k| i128::from(row[k]) * i128::from(p[k]))
                .sum::<i128>()
                + (i128::from(row[3]) << 16)
                + (1 << 15);
            (sum >> 16) as i32
        };
        let mut rng = crate::rng::Rng(0x6d76_7072_6f77);
        let value = |rng: &mut crate::rng::Rng| match rng.below(4) {
            0 => [i32::MIN, i32::MAX, -1, 0, 1, 0xFFFF, -0x10000][rng.below(7) as usize],
            _ => (rng.next() as i32) >> rng.below(32),
        };
        for _ in 0..300_000 {
            let row = [0; 4].map(|_| value(&mut rng));
            let p = [0; 3].map(|_| value(&mut rng));
            assert_eq!(direct_row_limbs(&row, &p), exact(&row, &p), "{row:?} {p:?}");
        }
    }

    /// The depth scale's halves form is the 64-bit product's floor, at the ends and at random.
    #[test]
    fn depth_scale_halves_is_the_floor() {
        let check = |r: u32| {
            assert_eq!(
                u64::from(depth_scale_halves(r)),
                (32767 * u64::from(r)) >> 16,
                "{r}"
            )
        };
        for r in [0, 1, 0xFFFF, 0x1_0000, 0x8000_0000, u32::MAX - 1, u32::MAX] {
            check(r);
        }
        let mut rng = crate::rng::Rng(0x6b7a_0001);
        for _ in 0..100_000 {
            check(rng.next() as u32);
        }
    }

    #[test]
    fn scratch_entries_are_16_bytes() {
        assert_eq!(core::mem::size_of::<ProjectedVertex>(), 16);
    }
}
