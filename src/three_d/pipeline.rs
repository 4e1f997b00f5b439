//! A fixed-point 3D pipeline: transform, clip, project, cull, and depth-tested shading of meshes
//! stored in flash.
//!
//! Per triangle of a [`Mesh`]:
//!
//! 1. **Transform** the three model-space vertices by the model-view-projection matrix
//!    ([`Mat4`], `I16F16` with `i64` accumulation) into homogeneous clip space.
//! 2. **Clip** in clip space, before any division: triangles wholly outside one plane are
//!    dropped; triangles crossing one are clipped (Sutherland–Hodgman into a
//!    `heapless::Vec`) against the near plane `z ≥ −w`, the far plane `z ≤ w`, `w ≥ 2⁻⁸`, and a
//!    guard band `|x|, |y| ≤ 64·w` that keeps every projected vertex well inside [`Coord`]. The
//!    intersection on an edge is always computed from its inside end, so two triangles sharing an
//!    edge get bit-identical clipped vertices and stay watertight.
//! 3. **Project**: one division per vertex (`2^46 / w`), then the viewport mapping to sub-pixel
//!    [`Coord`]s and a 16-bit depth `(1 + z/w)/2 · 65534` (0 at the near plane).
//! 4. **Cull** by the sign of the exact doubled screen-space area of the projected polygon
//!    (`i128` from the `Coord` vertices). Front faces are counter-clockwise in normalised device
//!    coordinates (y up), as in OpenGL; on screen (y down) that is a negative area.
//! 5. **Shade and fill** (see [`shading`](super::shading)): flat, Gouraud or per-pixel quadratic
//!    normals, with the z-buffer tested and written per pixel (smaller is nearer).
//!
//! Each face transforms its own three vertices, so nothing proportional to the mesh is kept in
//! RAM (shared vertices are transformed once per face using them, about twice on closed meshes).
//! All state lives on the stack: the clipped polygon holds at most 10 vertices.
//!
//! Normals are transformed by [`Pipeline::normal_matrix`] (the model matrix by default, exact for
//! rotations with uniform scale) and renormalised; the light is given in the same (world) space.
//! Attributes are interpolated affinely in screen space (no perspective correction); depth,
//! being `z/w`, is affine in screen space and therefore exact.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
//! use embedded_raster::three_d::{Angle, Mat4, Scalar, Vec3};
//! use embedded_raster::three_d::{DepthTarget, Mesh, Pipeline};
//! use embedded_raster::three_d::{Light, Material, Shading};
//!
//! static VERTICES: [Vec3; 3] = [
//!     Vec3::from_bits(-65536, -65536, 0),
//!     Vec3::from_bits(65536, -65536, 0),
//!     Vec3::from_bits(0, 65536, 0),
//! ];
//! static NORMALS: [Vec3; 3] = [Vec3::from_bits(0, 0, 65536); 3];
//! static INDICES: [[u16; 3]; 1] = [[0, 1, 2]];
//! let mesh = Mesh::new(&VERTICES, &NORMALS, &INDICES);
//!
//! let (mut pixels, mut depth) = ([Rgb565::BLACK; 64 * 48], [0u16; 64 * 48]);
//! let mut target = DepthTarget::new(&mut pixels, &mut depth, 64, 48).unwrap();
//! target.clear(Rgb565::BLACK);
//!
//! let projection = Mat4::perspective(
//!     Angle::from_degrees(60),
//!     Scalar::from_num(4) / 3,
//!     Scalar::from_num(0.5),
//!     Scalar::from_num(20),
//! );
//! let view = Mat4::translation(Vec3::from_bits(0, 0, -3 << 16));
//! let viewport = Rectangle::new(Point::zero(), Size::new(64, 48));
//! let light = Light::new(Vec3::from_bits(0, 0, 65536), Scalar::from_num(0.2));
//! let pipeline = Pipeline::new(Mat4::IDENTITY, projection * view, viewport, light);
//! let stats = pipeline.draw_mesh(&mesh, &Material::new(Rgb565::WHITE, Shading::Flat), &mut target);
//! assert_eq!(stats.drawn, 1);
//! assert_eq!(target.framebuffer().get(32, 24), Some(Rgb565::WHITE));
//! ```

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec as HVec;

use super::depth::{DepthTarget, ScreenVertex, DEPTH_FAR};
use super::math::{normalize_wide, sat32, Mat4, Scalar, Vec3, Vec4};
use super::mesh::Mesh;
use super::shading::{self, shade, Bary, Light, Material, QuadraticNormals, Shading, BARY_ONE};
use crate::color::GouraudColor;
use crate::fixed_point::Coord;

/// Guard-band factor: clip space is clipped to `|x|, |y| ≤ GUARD_BAND·w`.
pub const GUARD_BAND: i64 = 64;

/// Smallest `w` kept by clipping (raw `I16F16`, 2⁻⁸).
const W_MIN: i64 = 256;

/// Number of clip planes.
const PLANES: usize = 7;

/// Largest viewport side used for the mapping; larger viewports are treated as this size.
const MAX_VIEWPORT: i64 = 65_535;

/// Which faces are skipped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Cull {
    /// Draw both sides.
    None,
    /// Skip faces that are clockwise in normalised device coordinates (facing away).
    #[default]
    Back,
    /// Skip faces that are counter-clockwise (facing the camera).
    Front,
}

/// What happened to the triangles of a [`Pipeline::draw_mesh`] call.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct DrawStats {
    /// Triangles handed to the fill (whether or not any pixel passed the depth test).
    pub drawn: u32,
    /// Triangles that needed clipping (counted in `drawn` if anything was left).
    pub clipped: u32,
    /// Triangles outside the view volume, or left empty by clipping.
    pub rejected: u32,
    /// Back- (or front-) facing triangles skipped.
    pub culled: u32,
    /// Triangles with zero screen area or an index out of range.
    pub degenerate: u32,
}

/// A clip-space vertex with its barycentric coordinates in the original triangle.
#[derive(Debug, Clone, Copy)]
struct ClipVertex {
    /// Raw `I16F16` `[x, y, z, w]`.
    p: [i32; 4],
    bary: Bary,
}

/// Up to 3 + [`PLANES`] vertices.
type Polygon = HVec<ClipVertex, 12>;

/// Signed distance of `p` to clip plane `k` (inside where `≥ 0`), in raw units.
#[inline]
fn plane_distance(k: usize, p: &[i32; 4]) -> i64 {
    let [x, y, z, w] = p.map(i64::from);
    match k {
        0 => z + w,
        1 => w - z,
        2 => w - W_MIN,
        3 => GUARD_BAND * w - x,
        4 => GUARD_BAND * w + x,
        5 => GUARD_BAND * w - y,
        _ => GUARD_BAND * w + y,
    }
}

/// Bit `k` is set when `p` is outside plane `k`.
#[inline]
fn outcode(p: &[i32; 4]) -> u8 {
    (0..PLANES).fold(0, |code, k| {
        code | (u8::from(plane_distance(k, p) < 0) << k)
    })
}

/// The point where the edge from `inside` (distance `di ≥ 0`) to `outside` (`d_o < 0`) crosses
/// the plane. Always evaluated from the inside end, so both triangles sharing the edge agree.
fn intersect(inside: &ClipVertex, di: i64, outside: &ClipVertex, d_o: i64) -> ClipVertex {
    let den = di - d_o;
    // t = di / den with 30 fractional bits; shift both down so that di·2^30 fits.
    let s = (64 - den.leading_zeros()).saturating_sub(32);
    let (n, d) = (di >> s, (den >> s).max(1));
    let t = ((n << 30) / d).clamp(0, 1 << 30);
    let lerp = |a: i32, b: i32| {
        let (a, b) = (i64::from(a), i64::from(b));
        sat32(a + (((b - a) * t + (1 << 29)) >> 30))
    };
    ClipVertex {
        p: [0, 1, 2, 3].map(|k| lerp(inside.p[k], outside.p[k])),
        bary: [0, 1, 2].map(|k| lerp(inside.bary[k], outside.bary[k])),
    }
}

/// Clips `poly` against every plane (Sutherland–Hodgman). Returns `false` if nothing is left.
fn clip_polygon(poly: &mut Polygon) -> bool {
    let mut out = Polygon::new();
    for k in 0..PLANES {
        out.clear();
        let n = poly.len();
        for i in 0..n {
            let (Some(a), Some(b)) = (poly.get(i), poly.get((i + 1) % n)) else {
                continue;
            };
            let (da, db) = (plane_distance(k, &a.p), plane_distance(k, &b.p));
            if da >= 0 {
                let _ = out.push(*a);
            }
            if (da >= 0) != (db >= 0) {
                let v = if da >= 0 {
                    intersect(a, da, b, db)
                } else {
                    intersect(b, db, a, da)
                };
                let _ = out.push(v);
            }
        }
        core::mem::swap(poly, &mut out);
        if poly.len() < 3 {
            return false;
        }
    }
    true
}

/// Doubled signed area of a screen triangle in squared sub-pixel units (positive when clockwise
/// on screen, i.e. counter-clockwise with y up).
pub fn signed_area2(v: [(Coord, Coord); 3]) -> i128 {
    let [p0, p1, p2] = v.map(|(x, y)| (i128::from(x.to_bits()), i128::from(y.to_bits())));
    (p1.0 - p0.0) * (p2.1 - p0.1) - (p2.0 - p0.0) * (p1.1 - p0.1)
}

/// Model-view-projection, viewport, light and culling: everything needed to draw meshes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Pipeline {
    /// Model space to clip space.
    pub mvp: Mat4,
    /// Transforms model-space normals into the light's space (only the 3×3 block is used);
    /// the inverse transpose of the model matrix, which for rotations and uniform scaling is the
    /// model matrix itself.
    pub normal_matrix: Mat4,
    /// Where normalised device coordinates `[−1, 1]²` land on the target (at most 65535 pixels
    /// a side); also the scissor rectangle.
    pub viewport: Rectangle,
    /// Which faces to skip.
    pub cull: Cull,
    /// The light, in world space.
    pub light: Light,
}

impl Pipeline {
    /// A pipeline drawing meshes placed by `model` through the camera `view_projection`
    /// (projection · view) into `viewport`, culling back faces. Normals are transformed by
    /// `model`.
    pub fn new(model: Mat4, view_projection: Mat4, viewport: Rectangle, light: Light) -> Self {
        Pipeline {
            mvp: view_projection * model,
            normal_matrix: model,
            viewport,
            cull: Cull::Back,
            light,
        }
    }

    /// The clip-space position of a model-space point.
    pub fn clip_position(&self, p: Vec3) -> Vec4 {
        self.mvp.transform_point(p)
    }

    /// The screen position and depth of a clip-space point inside the view volume (within the
    /// near and far planes and the guard band), or `None` if it is outside.
    pub fn project(&self, clip: Vec4) -> Option<ScreenVertex> {
        (outcode(&clip.to_bits()) == 0).then(|| self.project_raw(&clip.to_bits()))
    }

    /// Perspective divide and viewport mapping of a point (assumed inside the view volume).
    fn project_raw(&self, p: &[i32; 4]) -> ScreenVertex {
        let [x, y, z, w] = p.map(i64::from);
        let r = (1i64 << 46) / w.max(1);
        // Normalised device coordinates with 30 fractional bits.
        let ndc = |c: i64| c.saturating_mul(r) >> 16;
        let width = i64::from(self.viewport.size.width).min(MAX_VIEWPORT);
        let height = i64::from(self.viewport.size.height).min(MAX_VIEWPORT);
        let half_w = width * 128;
        let half_h = height * 128;
        let x0 = i64::from(self.viewport.top_left.x) * 256 + half_w;
        let y0 = i64::from(self.viewport.top_left.y) * 256 + half_h;
        let map = |centre: i64, half: i64, n: i64| {
            let off = (half.saturating_mul(n).saturating_add(1 << 29)) >> 30;
            Coord::from_bits(sat32(centre.saturating_add(off)))
        };
        let depth = 32767 + ((32767 * ndc(z).clamp(-(1 << 31), 1 << 31) + (1 << 29)) >> 30);
        ScreenVertex {
            x: map(x0, half_w, ndc(x)),
            y: map(y0, half_h, -ndc(y)),
            depth: depth.clamp(0, i64::from(DEPTH_FAR)) as u16,
        }
    }

    /// The unit world-space normal of a model-space normal.
    fn world_normal(&self, n: Vec3) -> Vec3 {
        self.normal_matrix
            .transform_vector(n.normalize())
            .normalize()
    }

    /// Draws every triangle of `mesh` with `material` into `target`, depth-tested, clipped to the
    /// viewport and the target.
    pub fn draw_mesh<C: GouraudColor>(
        &self,
        mesh: &Mesh<'_>,
        material: &Material<C>,
        target: &mut DepthTarget<'_, C>,
    ) -> DrawStats {
        let mut stats = DrawStats::default();
        let clip = self.viewport.intersection(&target.bounding_box());
        for face in mesh.indices {
            let idx = face.map(usize::from);
            let (Some(a), Some(b), Some(c)) = (
                mesh.vertices.get(idx[0]),
                mesh.vertices.get(idx[1]),
                mesh.vertices.get(idx[2]),
            ) else {
                stats.degenerate += 1;
                continue;
            };
            let model = [*a, *b, *c];
            self.draw_face(mesh, &idx, &model, material, &clip, target, &mut stats);
        }
        stats
    }

    #[allow(clippy::too_many_arguments)]
    fn draw_face<C: GouraudColor>(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: &[Vec3; 3],
        material: &Material<C>,
        clip: &Rectangle,
        target: &mut DepthTarget<'_, C>,
        stats: &mut DrawStats,
    ) {
        let corners = [0, 1, 2].map(|k| {
            let mut bary = [0; 3];
            bary[k] = BARY_ONE;
            ClipVertex {
                p: self.clip_position(model[k]).to_bits(),
                bary,
            }
        });
        let codes = corners.map(|v| outcode(&v.p));
        if codes[0] & codes[1] & codes[2] != 0 {
            stats.rejected += 1;
            return;
        }
        let mut poly = Polygon::new();
        for v in corners {
            let _ = poly.push(v);
        }
        let clipped = codes[0] | codes[1] | codes[2] != 0;
        if clipped {
            stats.clipped += 1;
            if !clip_polygon(&mut poly) {
                stats.rejected += 1;
                return;
            }
        }
        let mut screen: HVec<(ScreenVertex, Bary), 12> = HVec::new();
        for v in &poly {
            let _ = screen.push((self.project_raw(&v.p), v.bary));
        }
        // Orientation of the whole (convex) polygon: the sum of its fan's areas.
        let area: i128 = (1..screen.len().saturating_sub(1))
            .filter_map(|k| {
                let (s0, s1, s2) = (screen.first()?, screen.get(k)?, screen.get(k + 1)?);
                Some(signed_area2([
                    s0.0.position(),
                    s1.0.position(),
                    s2.0.position(),
                ]))
            })
            .sum();
        if area == 0 {
            stats.degenerate += 1;
            return;
        }
        let front = area < 0;
        if (self.cull == Cull::Back && !front) || (self.cull == Cull::Front && front) {
            stats.culled += 1;
            return;
        }
        stats.drawn += 1;

        // Shading inputs of the original triangle.
        let face_normal = || {
            let e1 = model[1] - model[0];
            let e2 = model[2] - model[0];
            self.world_normal(normalize_wide(e1.cross_wide(e2)))
        };
        let vertex_normals = || {
            let face = face_normal();
            idx.map(|i| mesh.normals.get(i).map_or(face, |n| self.world_normal(*n)))
        };
        enum Fill<C> {
            Solid(C),
            Levels([Scalar; 3]),
            Normals(QuadraticNormals),
        }
        let fill = match material.shading {
            Shading::Unlit => Fill::Solid(material.color),
            Shading::Flat => Fill::Solid(shade(material.color, self.light.level(face_normal()))),
            Shading::Gouraud => Fill::Levels(vertex_normals().map(|n| self.light.level(n))),
            Shading::Quadratic => Fill::Normals(QuadraticNormals::new(vertex_normals())),
        };

        for k in 1..screen.len().saturating_sub(1) {
            let (Some(s0), Some(s1), Some(s2)) = (screen.first(), screen.get(k), screen.get(k + 1))
            else {
                continue;
            };
            let tri = [s0.0, s1.0, s2.0];
            let bary = [s0.1, s1.1, s2.1];
            match &fill {
                Fill::Solid(color) => shading::draw_flat(target, clip, &tri, *color),
                Fill::Levels(levels) => {
                    let colors = bary.map(|b| {
                        let l: i64 = b
                            .iter()
                            .zip(levels.iter())
                            .map(|(b, l)| i64::from(*b) * i64::from(l.to_bits()))
                            .sum();
                        shade(
                            material.color,
                            Scalar::from_bits(sat32((l + (1 << 29)) >> 30)),
                        )
                    });
                    shading::draw_gouraud(target, clip, &tri, colors);
                }
                Fill::Normals(normals) => {
                    let normals = if clipped {
                        normals.restricted(bary)
                    } else {
                        *normals
                    };
                    shading::draw_quadratic(
                        target,
                        clip,
                        &tri,
                        &normals,
                        &self.light,
                        material.color,
                    );
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cv(p: [i32; 4]) -> ClipVertex {
        ClipVertex { p, bary: [0; 3] }
    }

    #[test]
    fn clipping_is_symmetric_in_edge_direction() {
        let a = cv([1 << 16, 2 << 16, -5 << 16, 3 << 16]);
        let b = cv([-3 << 16, 1 << 16, 2 << 16, 1 << 15]);
        let mut p1 = Polygon::new();
        let mut p2 = Polygon::new();
        for v in [a, b, cv([0, 0, 0, 2 << 16])] {
            let _ = p1.push(v);
        }
        for v in [b, a, cv([1 << 16, -(1 << 16), 0, 2 << 16])] {
            let _ = p2.push(v);
        }
        assert!(clip_polygon(&mut p1) && clip_polygon(&mut p2));
        let on_near = |p: &Polygon| {
            let mut v: std::vec::Vec<[i32; 4]> = p
                .iter()
                .map(|v| v.p)
                .filter(|p| plane_distance(0, p).abs() <= 2)
                .collect();
            v.sort();
            v
        };
        extern crate std;
        assert!(!on_near(&p1).is_empty());
        let shared: std::vec::Vec<_> = on_near(&p1)
            .into_iter()
            .filter(|p| on_near(&p2).contains(p))
            .collect();
        assert_eq!(shared.len(), 1);
    }

    #[test]
    fn outcodes() {
        assert_eq!(outcode(&[0, 0, 0, 1 << 16]), 0);
        assert_eq!(outcode(&[0, 0, -(2 << 16), 1 << 16]), 1);
        assert_eq!(outcode(&[0, 0, 2 << 16, 1 << 16]), 2);
        assert_eq!(outcode(&[65 << 16, 0, 0, 1 << 16]), 1 << 3);
    }
}
