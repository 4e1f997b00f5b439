//! The f64 ray-casting reference of the 3D pipeline tests (tests/all/pipeline.rs, where it is
//! described, and tests/all/textured_mesh.rs): f64 matrices, one camera and object placement in both
//! arithmetics (`View`) and the ray through a pixel centre against a face (`View::hit`); and the
//! flat grid meshes both draw (`flat_grid`).

#![allow(dead_code)]

use embedded_graphics::primitives::Rectangle;
use embedded_raster::three_d::meshes::MeshData;
use embedded_raster::three_d::{Angle, Mat4, Scalar, Vec3};

pub use crate::vec_f64::{cross, dot, sub};

/// Pixel centres closer than this to a face's boundary may go either way.
pub const MARGIN: f64 = 0.02;

pub type V = [f64; 3];
pub type M = [[f64; 4]; 4];

pub fn fl(s: Scalar) -> f64 {
    s.to_num::<f64>()
}
pub fn fx(v: f64) -> Scalar {
    Scalar::from_bits((v * 65536.0).round() as i32)
}
pub fn radians(a: Angle) -> f64 {
    f64::from(a.0) / 65536.0 * std::f64::consts::TAU
}
/// The f64 value of fixed-point vector bits.
pub fn bits3(v: Vec3) -> V {
    v.to_bits().map(|c| f64::from(c) / 65536.0)
}

pub fn mul(a: &M, b: &M) -> M {
    let mut m = [[0.0; 4]; 4];
    for (r, row) in m.iter_mut().enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            *v = (0..4).map(|k| a[r][k] * b[k][c]).sum();
        }
    }
    m
}
pub fn identity() -> M {
    let mut m = [[0.0; 4]; 4];
    for (k, row) in m.iter_mut().enumerate() {
        row[k] = 1.0;
    }
    m
}
pub fn translate(t: V) -> M {
    let mut m = identity();
    for k in 0..3 {
        m[k][3] = t[k];
    }
    m
}
pub fn rot_x(a: f64) -> M {
    let (s, c) = a.sin_cos();
    let mut m = identity();
    m[1][1] = c;
    m[1][2] = -s;
    m[2][1] = s;
    m[2][2] = c;
    m
}
pub fn rot_y(a: f64) -> M {
    let (s, c) = a.sin_cos();
    let mut m = identity();
    m[0][0] = c;
    m[0][2] = s;
    m[2][0] = -s;
    m[2][2] = c;
    m
}
pub fn apply(m: &M, p: V) -> V {
    [0, 1, 2].map(|r| m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] + m[r][3])
}

/// One camera and object placement, in both arithmetics.
pub struct View {
    /// The fixed-point model and projection matrices, for the `Pipeline`.
    pub model: Mat4,
    pub projection: Mat4,
    /// f64 model-view (the view is the identity: eye space is world space).
    pub model_view: M,
    /// `f / aspect`, `f` of the f64 projection.
    pub p00: f64,
    pub p11: f64,
    /// `z_ndc = −a − b / z_eye`.
    pub a: f64,
    pub b: f64,
    /// The near and far planes as the fixed-point projection has them.
    pub near: f64,
    pub far: f64,
    pub viewport: Rectangle,
}

impl View {
    /// Camera at the origin looking down −z; the object rotated by `yaw`, `pitch` about its
    /// origin and moved to `position` (eye space).
    pub fn new(
        fov: Angle,
        near: f64,
        far: f64,
        yaw: Angle,
        pitch: Angle,
        position: V,
        viewport: Rectangle,
    ) -> View {
        let aspect = f64::from(viewport.size.width) / f64::from(viewport.size.height);
        let (n, f) = (fl(fx(near)), fl(fx(far)));
        let projection = Mat4::perspective(fov, fx(aspect), fx(near), fx(far)).unwrap();
        let model = Mat4::translation(Vec3::new(fx(position[0]), fx(position[1]), fx(position[2])))
            * Mat4::rotation_y(yaw)
            * Mat4::rotation_x(pitch);
        let pos = [0, 1, 2].map(|k| fl(fx(position[k])));
        let model_view = mul(
            &mul(&translate(pos), &rot_y(radians(yaw))),
            &rot_x(radians(pitch)),
        );
        let focal = 1.0 / (radians(fov) / 2.0).tan();
        View {
            model,
            projection,
            model_view,
            p00: focal / aspect,
            p11: focal,
            a: (f + n) / (n - f),
            b: 2.0 * f * n / (n - f),
            near: n,
            far: f,
            viewport,
        }
    }

    /// Screen position of an eye-space point (in front of the eye).
    pub fn screen(&self, e: V) -> (f64, f64) {
        let (xn, yn) = (self.p00 * e[0] / -e[2], self.p11 * e[1] / -e[2]);
        let (w, h) = (
            f64::from(self.viewport.size.width),
            f64::from(self.viewport.size.height),
        );
        (
            f64::from(self.viewport.top_left.x) + w / 2.0 * (1.0 + xn),
            f64::from(self.viewport.top_left.y) + h / 2.0 * (1.0 - yn),
        )
    }

    /// Eye-space direction through screen point `(sx, sy)` and its derivatives per pixel.
    pub fn ray(&self, sx: f64, sy: f64) -> (V, f64, f64) {
        let (w, h) = (
            f64::from(self.viewport.size.width),
            f64::from(self.viewport.size.height),
        );
        let xn = 2.0 * (sx - f64::from(self.viewport.top_left.x)) / w - 1.0;
        let yn = 1.0 - 2.0 * (sy - f64::from(self.viewport.top_left.y)) / h;
        let dx = 2.0 / (w * self.p00);
        let dy = -2.0 / (h * self.p11);
        ([xn / self.p00, yn / self.p11, -1.0], dx, dy)
    }

    /// The reference's verdict on the convex planar polygon `poly` (eye space; a triangle, say) at
    /// the centre of pixel `(i, j)`: `None` if it surely does not cover it, else the signed
    /// distance of the centre to the polygon's visible boundary (positive inside, pixels), its
    /// depth there and the depth change per pixel (16-bit units).
    pub fn hit(&self, poly: &[V], i: i32, j: i32) -> Option<(f64, f64, f64)> {
        let (d, dx, dy) = self.ray(f64::from(i) + 0.5, f64::from(j) + 0.5);
        let det = dot(poly[0], cross(poly[1], poly[2]));
        if det == 0.0 {
            return None;
        }
        let mut margin = f64::INFINITY;
        for a in 0..poly.len() {
            // The plane through the eye and the edge: affine in the screen position.
            let c = cross(poly[a], poly[(a + 1) % poly.len()]);
            let g = (c[0] * dx).hypot(c[1] * dy);
            margin = margin.min(det.signum() * dot(c, d) / g);
        }
        if margin < -MARGIN {
            return None;
        }
        // 1/z_eye of the hit is affine in the screen position too; it must be negative.
        let n = cross(sub(poly[1], poly[0]), sub(poly[2], poly[0]));
        let nv = dot(n, poly[0]);
        let inv_z = -dot(n, d) / nv;
        if inv_z >= 0.0 {
            return None;
        }
        let depth = (1.0 - self.a - self.b * inv_z) / 2.0;
        let grad = (self.b / 2.0 * n[0] * dx / nv).hypot(self.b / 2.0 * n[1] * dy / nv);
        margin = margin.min(depth / grad).min((1.0 - depth) / grad);
        (margin >= -MARGIN).then_some((margin, depth * 65534.0, grad * 65534.0))
    }
}

/// A flat mesh over the `(n + 1) × (n + 1)` vertices `positions` (row by row): two faces a cell,
/// counter-clockwise seen from `+z`, every normal `+z`.
pub fn flat_grid(positions: &[V], n: usize) -> MeshData {
    let at = |r: usize, c: usize| r * (n + 1) + c;
    let mut faces = Vec::new();
    for r in 0..n {
        for c in 0..n {
            faces.push([at(r, c), at(r, c + 1), at(r + 1, c + 1)]);
            faces.push([at(r, c), at(r + 1, c + 1), at(r + 1, c)]);
        }
    }
    let normals = vec![[0.0, 0.0, 1.0]; positions.len()];
    MeshData::from_f64(positions, &normals, &faces)
}
