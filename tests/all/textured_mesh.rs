//! Textured meshes in the fixed-point 3D pipeline (`Pipeline::draw_textured_mesh`, its scratch
//! form and the band renderer's, with and without a `MeshBin`) against an independent f64 reference.
//!
//! The reference is the ray caster of tests/all/pipeline.rs (tests/support/raycast.rs): for every pixel
//! it casts the ray through the pixel centre in eye space (f64 model-view from the same angles and
//! positions) and intersects it with every face. It decides which face a pixel shows — or that
//! rounding may decide it (a boundary within `MARGIN` px, near-equal depths: those pixels are left
//! out) — and the hit point's exact 3D barycentrics in that face give the exact perspective-correct
//! texture coordinate and light level at the pixel centre, independent of the pipeline's
//! perspective planes.
//!
//! Texel coordinates are observed through a *coordinate texture* (256 × 256 Rgb888, texel
//! `(i, j)` = `(i, j, K)`), so that a pixel tells which texel it took; `probe` reads them to
//! 1/512 texel by redrawing with every texture coordinate moved by `j/256` texel (the idea of
//! tests/all/perspective.rs).
//!
//! The tolerance on an interpolated attribute (`tolerance`) is the larger of what the two fills
//! of src/three_d/texturing.rs may make of it:
//!
//! * the perspective fill: its documented accuracy ("Accuracy": `δ·spread + 2⁻¹⁶` at the pixels
//!   where the values are computed, `δ = ρ/32 640 + 2⁻¹⁵`, `ρ` the face's vertex-`w` ratio),
//!   another 2⁻¹⁵ for the vertices' 16-bit `q` mantissa and the `w`s' own error, plus between
//!   those pixels the chord's deviation from the true curve, computed here from the exact plane
//!   of the face over the span the reference gives it (`exact`), and the steps' rounding;
//! * the screen-space fill, which faces whose interpolation departs from the perspective-correct
//!   values by at most 1/16 texel (and a quarter of the target's finest channel step in light
//!   level: 1/4 level into Rgb888, about one into Rgb565) take (`nearly_affine`): that departure,
//!   bounded here from the f64 `w`s (`affine_ratio`), plus the 2D planes' rounding;
//!
//! each plus the vertices' screen-position error (from `CLIP_ERROR`, see
//! `Scene::position_error`) times the attribute's gradient. `vertices_match_f64` checks the
//! input bounds.
//!
//! Run with `cargo test --features reference --test all textured_mesh:: -- --nocapture` to see the
//! statistics.

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::band::{BandLayout, BinEntry, Callback, ColorBands, DepthBands, MeshBin};
use embedded_raster::reference::texture::{nearest_texel, RefTexture, RefWrap};
use embedded_raster::texture::{
    Filter, Rgb565Texels, Rgb888Texels, Solid, TexelSource, Texture, Wrap,
};
use embedded_raster::three_d::meshes::{icosphere, MeshData};
use embedded_raster::three_d::{Angle, Scalar, TexCoord, Vec3};
use embedded_raster::three_d::{Cull, DepthTarget, DrawStats, Mesh, Pipeline, DEPTH_CLEAR};
use embedded_raster::three_d::{
    Light, LightSource, Lights, Material, ProjectedVertex, ScratchTooSmall, Shading, Specular,
    TexturedMaterial,
};

use crate::raycast;
use raycast::{
    apply, bits3, cross, dot, fl, flat_grid, fx, mul, radians, rot_x, rot_y, sub, View, M, MARGIN,
    V,
};

use crate::probe;
use probe::unwrap_near;

use crate::rng;
use rng::Rng;

const W: u32 = 128;
const H: u32 = 96;
const N: usize = (W * H) as usize;
/// Bound on the error of the fixed-point clip-space coordinates (`I16F16` matrices and
/// positions) against the f64 ones, in clip units (checked by `vertices_match_f64`).
const CLIP_ERROR: f64 = 4.0e-4;
/// The guard band, in normalised device coordinates: no drawn vertex lies farther out
/// (src/three_d/clip.rs: about 1000 px from the viewport's centre).
const GUARD: f64 = 24.0;
/// Side of the coordinate texture.
const TEX: u32 = 256;
/// The coordinate texture's blue channel.
const K: u8 = 0x5a;
/// 16.16 units a texel.
const UNIT: f64 = 65_536.0;

impl Rng {
    fn any_angle(&mut self) -> Angle {
        Angle(self.next() as u16)
    }
}

// ---------------------------------------------------------------------------------------------
// f64 geometry (the ray caster of tests/all/pipeline.rs: tests/support/raycast.rs)
// ---------------------------------------------------------------------------------------------

fn normalize(v: V) -> V {
    let l = dot(v, v).sqrt();
    if l > 0.0 {
        v.map(|c| c / l)
    } else {
        v
    }
}
fn rotate(m: &M, v: V) -> V {
    [0, 1, 2].map(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2])
}

/// One camera, object placement and light, in both arithmetics.
struct Scene {
    pipeline: Pipeline,
    /// The f64 view (eye space is world space, the light's).
    view: View,
    /// Unit direction towards the light and the ambient level (f64).
    light: V,
    ambient: f64,
}

/// A pose: field of view, near and far planes, the object's yaw and pitch about its origin and
/// its eye-space position, culling.
#[derive(Clone, Copy, Debug)]
struct Pose {
    fov: i32,
    near: f64,
    far: f64,
    yaw: Angle,
    pitch: Angle,
    position: V,
    cull: Cull,
}

impl Scene {
    /// Camera at the origin looking down −z; the object rotated by `yaw`, `pitch` about its
    /// origin and moved to `position` (eye space); the light from `light` (eye space) with
    /// `ambient`.
    fn new(pose: &Pose, light: V, ambient: f64) -> Scene {
        let viewport = Rectangle::new(Point::zero(), Size::new(W, H));
        let fov = Angle::from_degrees(pose.fov);
        let view = View::new(
            fov,
            pose.near,
            pose.far,
            pose.yaw,
            pose.pitch,
            pose.position,
            viewport,
        );
        let light_bits = Vec3::new(fx(light[0]), fx(light[1]), fx(light[2]));
        let fixed_light = Light::new(light_bits, fx(ambient));
        let mut pipeline = Pipeline::new(view.model, view.projection, viewport, fixed_light);
        pipeline.cull = pose.cull;
        Scene {
            pipeline,
            view,
            light: normalize(bits3(light_bits)),
            ambient: fl(fx(ambient)).clamp(0.0, 1.0),
        }
    }

    /// The f64 light level of a unit world-space normal: `ambient + (1 − ambient)·max(0, n·l)`.
    fn level(&self, n: V) -> f64 {
        self.ambient + (1.0 - self.ambient) * dot(n, self.light).max(0.0)
    }

    /// The f64 clip-space coordinates of an eye-space point.
    fn clip(&self, e: V) -> [f64; 4] {
        [
            self.view.p00 * e[0],
            self.view.p11 * e[1],
            self.view.a * e[2] + self.view.b,
            -e[2],
        ]
    }

    /// A bound on the screen position error of the fixed-point vertices of a face with
    /// eye-space vertices `eye` (drawn parts: `w ≥ near`, within the guard band), pixels: clip
    /// coordinates off by `CLIP_ERROR` move `x/w` by `CLIP_ERROR·(1 + |x/w|)/w`; the projection
    /// itself rounds to ½ sub-pixel (1/512 px) and a little more.
    fn position_error(&self, eye: &[V]) -> f64 {
        let w = eye
            .iter()
            .map(|e| -e[2])
            .fold(f64::MAX, f64::min)
            .max(self.view.near);
        let reach = eye
            .iter()
            .map(|e| (self.view.p00 * e[0].abs()).max(self.view.p11 * e[1].abs()))
            .fold(0.0, f64::max);
        let ndc = (reach / w).min(GUARD);
        let half = f64::from(
            self.view
                .viewport
                .size
                .width
                .max(self.view.viewport.size.height),
        ) / 2.0;
        CLIP_ERROR * (1.0 + ndc) / w * half + 1.0 / 256.0
    }

    /// Where the ray through screen point `(sx, sy)` meets the plane of `tri` (eye space): the
    /// point's barycentrics in the triangle (exact 3D ones: the perspective-correct weights) and
    /// `Q = −1/z_eye` there (affine in the screen position).
    fn plane_point(&self, tri: &[V; 3], sx: f64, sy: f64) -> ([f64; 3], f64) {
        let (d, _, _) = self.view.ray(sx, sy);
        let n = cross(sub(tri[1], tri[0]), sub(tri[2], tri[0]));
        let q = dot(n, d) / dot(n, tri[0]);
        let x = d.map(|c| c / q);
        let nn = dot(n, n);
        let b0 = dot(n, cross(sub(tri[1], x), sub(tri[2], x))) / nn;
        let b1 = dot(n, cross(sub(tri[2], x), sub(tri[0], x))) / nn;
        ([b0, b1, 1.0 - b0 - b1], q)
    }
}

// ---------------------------------------------------------------------------------------------
// The reference's faces and pixels
// ---------------------------------------------------------------------------------------------

/// A face of the mesh in one scene, as the reference sees it (from the mesh's fixed-point bits).
struct RefFace {
    eye: [V; 3],
    /// The vertices' texel coordinates for the texture's size (texels, `y` down).
    texel: [[f64; 2]; 3],
    /// The vertices' Gouraud light levels (from the mesh's normals), `[0, 1]`.
    levels: [f64; 3],
    /// The face's flat light level (from its geometric normal).
    flat: f64,
    /// The smallest and largest vertex `w` (view depth).
    w: (f64, f64),
    /// Whether culling keeps it.
    kept: bool,
    /// Pixel rows and columns it may cover (inclusive), all of the screen if a vertex is near or
    /// behind the eye.
    bbox: (i32, i32, i32, i32),
}

impl RefFace {
    /// The documented error of the perspective barycentrics (`δ`) for this face, with the
    /// inputs' rounding: `ρ/32 640 + 2⁻¹⁵` (src/raster/perspective.rs), another 2⁻¹⁵ for the
    /// vertices' 16-bit `q` mantissa, and twice the relative `w` error. `ρ` is the `w` ratio of what is
    /// drawn: clipping keeps `w` within `[near, far]`.
    fn delta(&self, scene: &Scene) -> f64 {
        let lo = self.w.0.max(scene.view.near);
        let hi = self.w.1.min(scene.view.far);
        (hi / lo) / 32_640.0 + 2.0 / 32_768.0 + 2.0 * CLIP_ERROR / lo
    }

    /// The spread of the vertices' texel coordinates (largest difference on either axis).
    fn spread(&self) -> f64 {
        let axis = |a: usize| spread_of(self.texel.map(|t| t[a]));
        axis(0).max(axis(1))
    }
}

/// The reference's faces of `mesh` in `scene`, for a texture of `size` texels.
fn ref_faces(scene: &Scene, mesh: &MeshData, size: (u32, u32)) -> Vec<RefFace> {
    let world_normal = |n: V| normalize(rotate(&scene.view.model_view, normalize(n)));
    mesh.indices
        .iter()
        .map(|f| {
            let idx = f.map(usize::from);
            let model = idx.map(|i| bits3(mesh.vertices[i]));
            let eye = model.map(|p| apply(&scene.view.model_view, p));
            let texel = idx.map(|i| {
                let t = mesh.uvs.get(i).copied().unwrap_or_default().to_bits();
                [
                    f64::from(t[0]) * f64::from(size.0) / UNIT,
                    (UNIT - f64::from(t[1])) * f64::from(size.1) / UNIT,
                ]
            });
            let geometric = world_normal(cross(sub(model[1], model[0]), sub(model[2], model[0])));
            let flat = scene.level(geometric);
            let levels = match mesh.normals.is_empty() {
                true => [flat; 3],
                false => idx.map(|i| scene.level(world_normal(bits3(mesh.normals[i])))),
            };
            let ws = eye.map(|e| -e[2]);
            let w = (ws[0].min(ws[1]).min(ws[2]), ws[0].max(ws[1]).max(ws[2]));
            // Front faces are counter-clockwise seen by the camera.
            let front = dot(cross(sub(eye[1], eye[0]), sub(eye[2], eye[0])), eye[0]) < 0.0;
            let kept = match scene.pipeline.cull {
                Cull::None => true,
                Cull::Back => front,
                Cull::Front => !front,
            };
            let bbox = if w.0 > scene.view.near * 0.5 {
                let s = eye.map(|e| scene.view.screen(e));
                let lo = |c: fn(&(f64, f64)) -> f64| s.iter().map(c).fold(f64::MAX, f64::min);
                let hi = |c: fn(&(f64, f64)) -> f64| s.iter().map(c).fold(f64::MIN, f64::max);
                (
                    (lo(|p| p.0).floor() as i32 - 1).max(0),
                    (lo(|p| p.1).floor() as i32 - 1).max(0),
                    (hi(|p| p.0).ceil() as i32 + 1).min(W as i32 - 1),
                    (hi(|p| p.1).ceil() as i32 + 1).min(H as i32 - 1),
                )
            } else {
                (0, 0, W as i32 - 1, H as i32 - 1)
            };
            RefFace {
                eye,
                texel,
                levels,
                flat,
                w,
                kept,
                bbox,
            }
        })
        .collect()
}

/// What a pixel must show.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Verdict {
    /// Nothing: no face comes within `MARGIN` of its centre.
    Empty,
    /// Rounding decides (a boundary within `MARGIN`, near-equal depths).
    Either,
    /// This face, at this depth (within the tolerance).
    Face {
        face: usize,
        depth: f64,
        tolerance: f64,
    },
}

/// The verdict on every pixel of the screen (row-major), as tests/all/pipeline.rs decides it, and
/// where each face's spans may lie.
fn verdicts(scene: &Scene, faces: &[RefFace]) -> (Vec<Verdict>, Spans) {
    // (face, margin, depth, depth tolerance) of every face that may cover each pixel.
    let mut hits: Vec<Vec<(usize, f64, f64, f64)>> = vec![Vec::new(); N];
    let mut spans = vec![vec![(i32::MAX, i32::MIN); H as usize]; faces.len()];
    for (k, f) in faces.iter().enumerate().filter(|(_, f)| f.kept) {
        let (x0, y0, x1, y1) = f.bbox;
        for j in y0..=y1 {
            for i in x0..=x1 {
                if let Some((m, d, g)) = scene.view.hit(&f.eye, i, j) {
                    let span = &mut spans[k][j as usize];
                    *span = (span.0.min(i), span.1.max(i));
                    hits[(j as u32 * W + i as u32) as usize].push((
                        k,
                        m,
                        d,
                        2.0 + 2.0 * MARGIN * g,
                    ));
                }
            }
        }
    }
    let verdicts = hits
        .iter()
        .map(|hits| {
            let front = hits
                .iter()
                .filter(|h| h.1 > MARGIN)
                .map(|h| h.2 + h.3)
                .fold(f64::INFINITY, f64::min);
            if hits.is_empty() {
                return Verdict::Empty;
            }
            let mut acceptable = hits.iter().filter(|h| h.2 - h.3 <= front);
            match (front.is_finite(), acceptable.next(), acceptable.next()) {
                (true, Some(h), None) => Verdict::Face {
                    face: h.0,
                    depth: h.2,
                    tolerance: h.3,
                },
                _ => Verdict::Either,
            }
        })
        .collect();
    (verdicts, Spans(spans))
}

/// For each face and row, the first and last pixel the face may cover there: its spans lie
/// inside.
struct Spans(Vec<Vec<(i32, i32)>>);

impl Spans {
    fn of(&self, face: usize, row: i32) -> (i32, i32) {
        self.0[face][row as usize]
    }
}

/// The exact value of a vertex attribute at a pixel centre and what may move the
/// implementation's value from it besides the computed values' own error (`δ·spread`).
#[derive(Clone, Copy, Debug)]
struct Exact {
    value: f64,
    /// Chord deviation + steps' rounding + the vertices' position error times the gradient.
    wiggle: f64,
    /// The vertices' position error times the gradient alone.
    position: f64,
}

/// The attribute with vertex values `a` of face `f` at the centre of pixel `(i, j)`, exactly
/// (perspective-correct: the ray's hit barycentrics), for a face whose span in row `j` lies in
/// `span` (first and last pixel).
///
/// Along a span the perspective fill computes the attribute at every 16th pixel from the span's
/// first and at its last, and steps it linearly between (src/raster/perspective.rs, `Chunks`),
/// so it may be off the exact curve by the chord's deviation: at most `½·max|f''|·(x − a)(b −
/// x)` in a chunk from `a` to `b` (`b − a ≤ 16`, both in the span). Along a row the attribute is
/// `f = P/Q` with `P` and `Q = 1/w` affine in `x`, so `f'' = 2·Q'·K/Q³` with the constant
/// `K = Q'·P − P'·Q`; `|f''|` grows as `Q` falls, so its largest value in the chunk is at the end
/// with the smaller `Q`. The steps round by up to 2⁻¹⁶ (of the attribute's 16.16 unit) a pixel,
/// plus `|b − a|·2⁻¹⁶` for a short chunk.
fn exact(
    scene: &Scene,
    f: &RefFace,
    span: (i32, i32),
    a: [f64; 3],
    (i, j): (i32, i32),
    unit: f64,
) -> Exact {
    let position_error = scene.position_error(&f.eye);
    let at = |x: f64, dy: f64| {
        let (b, q) = scene.plane_point(&f.eye, x + 0.5, f64::from(j) + 0.5 + dy);
        (b[0] * a[0] + b[1] * a[1] + b[2] * a[2], q)
    };
    let x = f64::from(i);
    let (v, q) = at(x, 0.0);
    let (right, q_right) = at(x + 1.0, 0.0);
    let (left, _) = at(x - 1.0, 0.0);
    let (down, _) = at(x, 1.0);
    let (up, _) = at(x, -1.0);
    let gradient = ((right - left).abs() + (down - up).abs()) / 2.0;
    let dq = q_right - q;
    let dp = right * q_right - v * q;
    let k = dq * v * q - dp * q;
    // The chunk [i − p, i + r]: p ≤ i − first, r ≤ last − i, p + r ≤ 16; the largest p·r.
    let (before, after) = (f64::from(i - span.0), f64::from(span.1 - i));
    let p = 8f64.max(16.0 - after).min(before).max(0.0);
    let r = (16.0 - p).min(after).max(0.0);
    let (lo, hi) = (
        (x - p).max(f64::from(span.0)),
        (x + r).min(f64::from(span.1)),
    );
    let q_min = at(lo, 0.0).1.min(at(hi, 0.0).1);
    let chord = (dq * k).abs() / q_min.powi(3) * p * r;
    let slope = k.abs() / (q_min * q_min);
    let steps = p / unit * (1.0 + 16.0 * slope);
    Exact {
        value: v,
        wiggle: chord + steps + position_error * gradient,
        position: position_error * gradient,
    }
}

/// Faces whose screen-space interpolation departs from the perspective-correct values by at
/// most 1/16 texel (and, lit by vertex levels, 1/4 of a level of the 0–255 scale) may be filled
/// in screen space (src/three_d/texturing.rs, `nearly_affine`).
const AFFINE_TEXELS: f64 = 1.0 / 16.0;
const AFFINE_LEVEL: f64 = 0.25 / 255.0;
/// Into Rgb565 the level's bound is a quarter of green's 6-bit step: 8.8 levels
/// `⌊64 · 255 / 63⌋ = 259`, about one level.
const AFFINE_LEVEL_565: f64 = 259.0 / 256.0 / 255.0;

/// How far the fill's value of a vertex attribute of face `f` may lie from the exact one at a
/// pixel where the exact attribute is `e`: the perspective fill's documented error (`δ·spread
/// + 1 unit`, `spread` the documented one: `documented`), the chord and the inputs' rounding
/// (`e.wiggle`); or, if the face may be filled in screen space (`affine`: its departure bound
/// for this attribute), that departure plus the screen-space fill's own rounding (`rounding`).
fn tolerance(
    scene: &Scene,
    f: &RefFace,
    e: &Exact,
    documented: f64,
    affine: Option<f64>,
    rounding: f64,
) -> f64 {
    let perspective = f.delta(scene) * documented + 1.0 / UNIT + e.wiggle;
    match affine {
        Some(departure) => perspective.max(departure + rounding + e.position),
        None => perspective,
    }
}

/// The fill decides from its 16-bit `q` (within a unit of 32 640 or more) and the fixed-point
/// `w`: a limit with 5 % slack.
fn slack(limit: f64) -> f64 {
    limit * 1.05 + 2.0 / 32_640.0
}

/// Whether face `f` may be filled in screen space: `None` if not, else the bound on the
/// departure of screen-space values from perspective-correct ones per unit of spread,
/// `(q_max − q_min)/(4·q_min)`. `spreads` are the attributes' spreads the fill decides by, each
/// with its limit. A face crossing the near or far plane is drawn as a fan of smaller triangles,
/// any of which may qualify: it may (its departure on each attribute at most that attribute's
/// limit, see `departure`).
fn affine_ratio(scene: &Scene, f: &RefFace, spreads: &[(f64, f64)]) -> Option<f64> {
    let lo = f.w.0.max(scene.view.near);
    let hi = f.w.1.min(scene.view.far);
    let ratio = (hi / lo - 1.0) / 4.0;
    let clipped = f.w.0 < scene.view.near || f.w.1 > scene.view.far;
    let qualifies = spreads
        .iter()
        .all(|&(spread, limit)| spread * ratio <= slack(limit));
    // The fixed-point `w`s' own ratio may be a little larger.
    (clipped || qualifies).then_some(ratio + 2.0 * CLIP_ERROR / lo)
}

/// The departure bound of an attribute of spread `own` and limit `limit` on a face of ratio
/// `ratio` filled in screen space (at most the limit: the triangle qualified).
fn departure(ratio: f64, own: f64, limit: f64) -> f64 {
    (ratio * own).min(slack(limit))
}

/// The exact texel coordinate of face `f` at pixel `(i, j)` and its tolerance on each axis, for
/// an unlit or flat-lit draw (the fill decides by the texel spread alone), the face's span in
/// row `j` within `span`.
fn texel_at(
    scene: &Scene,
    f: &RefFace,
    span: (i32, i32),
    (i, j): (i32, i32),
) -> ([f64; 2], [f64; 2]) {
    let spread = f.spread();
    let affine = affine_ratio(scene, f, &[(spread, AFFINE_TEXELS)]);
    let axis = |a: usize| {
        let values = f.texel.map(|t| t[a]);
        let e = exact(scene, f, span, values, (i, j), UNIT);
        let own = spread_of(values);
        // The 2D textured fill's planes: within `s + 1/128` texel, `s` the spread over 32 639
        // (tests/all/textured.rs).
        let rounding = own / 32_639.0 + 1.0 / 128.0;
        let d = affine.map(|r| departure(r, own, AFFINE_TEXELS));
        (e.value, tolerance(scene, f, &e, spread, d, rounding))
    };
    let (x, y) = (axis(0), axis(1));
    ([x.0, y.0], [x.1, y.1])
}

/// The largest difference of three values.
fn spread_of(v: [f64; 3]) -> f64 {
    v[0].max(v[1]).max(v[2]) - v[0].min(v[1]).min(v[2])
}

// ---------------------------------------------------------------------------------------------
// Meshes with texture coordinates
// ---------------------------------------------------------------------------------------------

/// Normalised texture coordinate from floats (rounded to `I16F16`).
fn uv(u: f64, v: f64) -> TexCoord {
    TexCoord::from_bits((u * UNIT).round() as i32, (v * UNIT).round() as i32)
}

/// A floor: the square `[−half, half]²` at `z = 0` in `n × n` cells (two faces each), normal
/// `+z`, the texture `repeat` times across it.
fn floor(half: f64, n: usize, repeat: f64) -> MeshData {
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    for r in 0..=n {
        for c in 0..=n {
            let (s, t) = (c as f64 / n as f64, r as f64 / n as f64);
            positions.push([-half + 2.0 * half * s, -half + 2.0 * half * t, 0.0]);
            uvs.push(uv(s * repeat, t * repeat));
        }
    }
    let mut mesh = flat_grid(&positions, n);
    mesh.uvs = uvs;
    mesh
}

/// A torus around `z` (radii `major`, `minor`) with its seams' vertices duplicated so that the
/// texture coordinates run on across them: `u` from 0.9 to 1.15 around the ring (64 texels of
/// the coordinate texture, across its wrap), `v` from 0 to 1/8 around the tube (32 texels).
fn textured_torus(major: f64, minor: f64, rings: usize, sides: usize) -> MeshData {
    let tau = std::f64::consts::TAU;
    let (mut positions, mut normals, mut uvs) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..=rings {
        for j in 0..=sides {
            let (s, t) = (i as f64 / rings as f64, j as f64 / sides as f64);
            let (st, ct) = (tau * s).sin_cos();
            let (sp, cp) = (tau * t).sin_cos();
            positions.push([
                (major + minor * cp) * ct,
                (major + minor * cp) * st,
                minor * sp,
            ]);
            normals.push([cp * ct, cp * st, sp]);
            uvs.push(uv(0.9 + 0.25 * s, 0.125 * t));
        }
    }
    let at = |i: usize, j: usize| i * (sides + 1) + j;
    let mut faces = Vec::new();
    for i in 0..rings {
        for j in 0..sides {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            faces.push([a, b, c]);
            faces.push([a, c, d]);
        }
    }
    let mut mesh = MeshData::from_f64(&positions, &normals, &faces);
    mesh.uvs = uvs;
    mesh
}

/// An icosphere whose every face has vertices of its own, each face mapped onto a random
/// triangle of the texture (0.01 to 0.06 of it from its centre, any orientation, some outside
/// `[0, 1]²`: the texture repeats); smooth normals.
fn patched_icosphere(rng: &mut Rng, subdivisions: u32) -> MeshData {
    let sphere = icosphere(1.0, subdivisions);
    let mut mesh = MeshData::default();
    for f in &sphere.indices {
        let (cu, cv) = (rng.range_f64(-0.2, 1.2), rng.range_f64(-0.2, 1.2));
        let size = rng.range_f64(0.01, 0.06);
        let turn = rng.range_f64(0.0, std::f64::consts::TAU);
        let base = mesh.vertices.len() as u16;
        for (k, &i) in f.iter().enumerate() {
            mesh.vertices.push(sphere.vertices[usize::from(i)]);
            mesh.normals.push(sphere.normals[usize::from(i)]);
            let a = turn + k as f64 * std::f64::consts::TAU / 3.0 + rng.range_f64(-0.4, 0.4);
            mesh.uvs.push(uv(cu + size * a.cos(), cv + size * a.sin()));
        }
        mesh.indices.push([base, base + 1, base + 2]);
    }
    mesh
}

// ---------------------------------------------------------------------------------------------
// Drawing
// ---------------------------------------------------------------------------------------------

/// A colour and depth buffer of the screen's size.
#[derive(Clone, PartialEq)]
struct Frame {
    px: Vec<Rgb888>,
    z: Vec<u16>,
}

impl Frame {
    fn new() -> Frame {
        Frame {
            px: vec![Rgb888::BLACK; N],
            z: vec![DEPTH_CLEAR; N],
        }
    }

    fn target(&mut self) -> DepthTarget<'_, Rgb888> {
        let mut t = DepthTarget::new(&mut self.px, &mut self.z, W, H).unwrap();
        t.clear(Rgb888::BLACK);
        t
    }

    fn written(&self, i: usize) -> bool {
        self.z[i] != DEPTH_CLEAR
    }

    fn written_set(&self) -> Vec<bool> {
        (0..N).map(|i| self.written(i)).collect()
    }
}

fn textured<S: TexelSource>(
    pipeline: &Pipeline,
    mesh: &Mesh<'_>,
    texture: &Texture<S>,
    shading: Shading,
) -> (Frame, DrawStats)
where
    Rgb888: From<S::Color>,
{
    let mut frame = Frame::new();
    let material = TexturedMaterial::new(texture, shading);
    let stats = pipeline.draw_textured_mesh(mesh, &material, &mut frame.target());
    (frame, stats)
}

/// [`textured`] into an Rgb565 target: its colours.
fn textured_rgb565<S: TexelSource>(
    pipeline: &Pipeline,
    mesh: &Mesh<'_>,
    texture: &Texture<S>,
    shading: Shading,
) -> Vec<Rgb565>
where
    Rgb565: From<S::Color>,
{
    let (mut px, mut z) = (vec![Rgb565::BLACK; N], vec![DEPTH_CLEAR; N]);
    let mut target = DepthTarget::new(&mut px, &mut z, W, H).unwrap();
    target.clear(Rgb565::BLACK);
    let material = TexturedMaterial::new(texture, shading);
    pipeline.draw_textured_mesh(mesh, &material, &mut target);
    px
}

fn untextured(pipeline: &Pipeline, mesh: &Mesh<'_>, color: Rgb888, shading: Shading) -> Frame {
    let mut frame = Frame::new();
    pipeline.draw_mesh(mesh, &Material::new(color, shading), &mut frame.target());
    frame
}

/// The coordinate texture's texels: `(i, j, K)`.
fn coordinate_texels() -> Vec<u8> {
    (0..TEX)
        .flat_map(|j| (0..TEX).map(move |i| [i as u8, j as u8, K]))
        .flatten()
        .collect()
}

/// The texel index each written pixel of an Unlit draw with the coordinate texture took.
fn decode(frame: &Frame) -> Vec<Option<(u32, u32)>> {
    (0..N)
        .map(|i| {
            frame.written(i).then(|| {
                let c = frame.px[i];
                assert_eq!(c.b(), K, "pixel {i}: not a texel of the coordinate texture");
                (u32::from(c.r()), u32::from(c.g()))
            })
        })
        .collect()
}

/// The implementation's texel coordinates at each written pixel, modulo 256 texels and to
/// within `1/(2·steps)` texel: the mesh drawn with the coordinate texture, then again with
/// every texture coordinate moved by `j/steps` texel (`u` up, `v` down: texel `x` and `y` both
/// grow) for `j = 1, 2, …` (`probe::coordinates`, shared with tests/all/perspective.rs).
fn probe(
    pipeline: &Pipeline,
    mesh: &MeshData,
    texture: &Texture<Rgb888Texels<'_>>,
) -> Vec<Option<[f64; 2]>> {
    const STEPS: u32 = 256;
    // One raw unit of a normalised coordinate is 256/65536 texel of a 256-texel side.
    assert_eq!(TEX, STEPS);
    let base = decode(&textured(pipeline, &mesh.as_mesh(), texture, Shading::Unlit).0);
    let mut moved = mesh.clone();
    probe::coordinates(&base, STEPS, |j| {
        for (m, o) in moved.uvs.iter_mut().zip(&mesh.uvs) {
            let [u, v] = o.to_bits();
            *m = TexCoord::from_bits(u + j as i32, v - j as i32);
        }
        decode(&textured(pipeline, &moved.as_mesh(), texture, Shading::Unlit).0)
    })
}

// ---------------------------------------------------------------------------------------------
// Scenes
// ---------------------------------------------------------------------------------------------

/// A named mesh in a pose.
struct Case {
    name: String,
    mesh: MeshData,
    pose: Pose,
}

/// `degrees` as an angle (any sign).
fn degrees(d: f64) -> Angle {
    Angle((d / 360.0 * 65536.0).round().rem_euclid(65536.0) as u16)
}

/// A floor quad with tilted corner normals (curved light across it), seen at a grazing angle
/// from a random pose just above it.
fn grazing_floor(rng: &mut Rng) -> (MeshData, Pose) {
    let mut mesh = floor(6.0, 1, 1.0);
    let tilt = |x: f64, y: f64| {
        let v = normalize([x, y, 1.0]);
        Vec3::new(v[0], v[1], v[2])
    };
    mesh.normals = vec![
        tilt(-1.2, -0.4),
        tilt(1.0, -1.1),
        tilt(-0.9, 1.3),
        tilt(1.3, 0.8),
    ];
    let pose = Pose {
        fov: 60,
        near: 0.5,
        far: 30.0,
        yaw: degrees(rng.range_f64(-20.0, 20.0)),
        pitch: degrees(-90.0 + rng.range_f64(1.0, 4.0)),
        position: [
            rng.range_f64(-0.5, 0.5),
            rng.range_f64(-0.8, -0.3),
            rng.range_f64(-9.0, -7.0),
        ],
        cull: Cull::None,
    };
    (mesh, pose)
}

/// Floors seen at grazing angles (the camera 0.15 to 0.8 above a floor reaching 17 units
/// away, tilted up to 3° towards it), tessellated finely and coarsely; tori and patched
/// icospheres at random poses, all three cullings.
fn unclipped_cases(rng: &mut Rng) -> Vec<Case> {
    let mut cases = Vec::new();
    for n in 0..12 {
        let (cells, repeat) = [(8, 0.5), (2, 0.25), (1, 0.25)][n % 3];
        let pose = Pose {
            fov: 60,
            near: 0.5,
            far: 30.0,
            yaw: degrees(rng.range_f64(-30.0, 30.0)),
            pitch: degrees(-90.0 + rng.range_f64(0.0, 3.0)),
            position: [
                rng.range_f64(-1.0, 1.0),
                rng.range_f64(-0.8, -0.15),
                rng.range_f64(-11.0, -9.5),
            ],
            cull: Cull::Back,
        };
        cases.push(Case {
            name: format!("floor {cells}×{cells} #{n}"),
            mesh: floor(6.0, cells, repeat),
            pose,
        });
    }
    for n in 0..12 {
        let torus = n % 2 == 0;
        let mesh = if torus {
            textured_torus(1.0, 0.4, 24, 12)
        } else {
            patched_icosphere(rng, 2)
        };
        let pose = Pose {
            fov: 60,
            near: 0.5,
            far: 20.0,
            yaw: rng.any_angle(),
            pitch: rng.any_angle(),
            position: [
                rng.range_f64(-1.0, 1.0),
                rng.range_f64(-0.7, 0.7),
                rng.range_f64(-5.0, -2.6),
            ],
            cull: [Cull::Back, Cull::None, Cull::Front][n % 3],
        };
        let what = if torus { "torus" } else { "patched icosphere" };
        cases.push(Case {
            name: format!("{what} #{n}"),
            mesh,
            pose,
        });
    }
    cases
}

/// Meshes the near plane cuts: a floor running from behind the camera to far ahead, the camera
/// inside a torus's tube, a large patched icosphere brushing the eye, the camera inside an
/// icosphere near its surface.
fn clipped_cases(rng: &mut Rng) -> Vec<Case> {
    let mut cases = Vec::new();
    for n in 0..16 {
        let (yaw, pitch) = (rng.any_angle(), rng.any_angle());
        let (name, mesh, pose) = match n % 4 {
            0 => (
                "floor",
                floor(8.0, 12, 0.5),
                Pose {
                    fov: 70,
                    near: 0.2,
                    far: 40.0,
                    yaw,
                    pitch: degrees(rng.range_f64(-120.0, -60.0)),
                    position: [
                        rng.range_f64(-2.0, 2.0),
                        rng.range_f64(-1.5, -0.3),
                        rng.range_f64(-3.0, -1.0),
                    ],
                    cull: Cull::Back,
                },
            ),
            1 => {
                // The eye near the centre line of the tube: a point of the ring, turned.
                let t = rng.range_f64(0.0, std::f64::consts::TAU);
                let turn = mul(&rot_y(radians(yaw)), &rot_x(radians(pitch)));
                let ring = rotate(&turn, [t.cos(), t.sin(), 0.0]);
                let position = [0, 1, 2].map(|k| -ring[k] + rng.range_f64(-0.12, 0.12));
                (
                    "inside a torus",
                    textured_torus(1.0, 0.4, 24, 12),
                    Pose {
                        fov: 70,
                        near: 0.15,
                        far: 10.0,
                        yaw,
                        pitch,
                        position,
                        cull: Cull::None,
                    },
                )
            }
            2 => (
                "large patched icosphere",
                {
                    let mut m = patched_icosphere(rng, 2);
                    m.scale_to_fit(3.0);
                    m
                },
                Pose {
                    fov: 70,
                    near: 0.3,
                    far: 10.0,
                    yaw,
                    pitch,
                    // Outside the sphere (radius 3), 60° off the view axis, its nearest point
                    // nearer than the near plane: its surface runs from the cut away to the side.
                    position: {
                        let turn = rng.range_f64(0.0, std::f64::consts::TAU);
                        let (d, off) = (3.0 + rng.range_f64(0.1, 0.25), 60f64.to_radians());
                        [
                            d * off.sin() * turn.cos(),
                            d * off.sin() * turn.sin(),
                            -d * off.cos(),
                        ]
                    },
                    cull: Cull::Back,
                },
            ),
            _ => (
                "inside an icosphere",
                patched_icosphere(rng, 2),
                Pose {
                    fov: 70,
                    near: 0.3,
                    far: 10.0,
                    yaw,
                    pitch,
                    position: [
                        rng.range_f64(-0.3, 0.3),
                        rng.range_f64(-0.3, 0.3),
                        -rng.range_f64(0.75, 0.9),
                    ],
                    cull: Cull::None,
                },
            ),
        };
        cases.push(Case {
            name: format!("{name} #{n}"),
            mesh,
            pose,
        });
    }
    cases
}

/// Every case of the suite: the unclipped ones, then the clipped ones.
fn all_cases() -> (Vec<Case>, Vec<Case>) {
    let mut rng = Rng(0x7e47_3d01);
    let unclipped = unclipped_cases(&mut rng);
    let clipped = clipped_cases(&mut rng);
    (unclipped, clipped)
}

/// The light of the texel tests (the lit tests choose their own).
const LIGHT: V = [0.3, 0.5, 1.0];

// ---------------------------------------------------------------------------------------------
// Texel coordinates against the reference
// ---------------------------------------------------------------------------------------------

/// Counts of a nearest-texel comparison.
#[derive(Debug, Default)]
struct Tally {
    pixels: u64,
    /// Pixels the reference gives one face at (and so one exact coordinate).
    faces: u64,
    /// Of those, pixels whose both axes were checked (the coordinate farther than its tolerance
    /// from a texel boundary).
    checked: u64,
    /// Pixels left out on an axis: the coordinate within its tolerance of a texel boundary.
    near_boundary: u64,
    /// Pixels rounding decides (boundaries, near-equal depths).
    ambiguous: u64,
    worst_depth: f64,
    /// The median tolerance (filled in at the end).
    median_tolerance: f64,
    clipped: u32,
    drawn: u32,
}

/// Draws `case` Unlit with the coordinate texture and checks every pixel against the
/// reference: empty where it must be, written where a face surely covers it, at its depth, and
/// the texel of the exact coordinate wherever that is farther than its tolerance from a texel
/// boundary. Returns the tolerances met.
fn check_nearest(case: &Case, tally: &mut Tally) -> Vec<f64> {
    let scene = Scene::new(&case.pose, LIGHT, 0.2);
    let texels = coordinate_texels();
    let texture = Texture::new(Rgb888Texels(&texels), TEX, TEX).unwrap();
    let reference = RefTexture::new(TEX, TEX, vec![[0.0; 3]; (TEX * TEX) as usize]);
    let mesh = case.mesh.as_mesh();
    let (frame, stats) = textured(&scene.pipeline, &mesh, &texture, Shading::Unlit);
    tally.clipped += stats.clipped;
    tally.drawn += stats.drawn;
    let got = decode(&frame);
    let faces = ref_faces(&scene, &case.mesh, (TEX, TEX));
    let (verdicts, spans) = verdicts(&scene, &faces);
    let mut tolerances = Vec::new();
    for (p, verdict) in verdicts.into_iter().enumerate() {
        let (i, j) = ((p as u32 % W) as i32, (p as u32 / W) as i32);
        tally.pixels += 1;
        match verdict {
            Verdict::Empty => assert!(!frame.written(p), "{}: pixel {i},{j} written", case.name),
            Verdict::Either => tally.ambiguous += 1,
            Verdict::Face {
                face,
                depth,
                tolerance,
            } => {
                let (x, y) = got[p].unwrap_or_else(|| {
                    panic!("{}: pixel {i},{j} empty, covered by face {face}", case.name)
                });
                let err = (f64::from(frame.z[p]) - depth).abs();
                assert!(
                    err <= tolerance,
                    "{}: pixel {i},{j}: depth {} vs {depth}",
                    case.name,
                    frame.z[p]
                );
                tally.worst_depth = tally.worst_depth.max(err);
                tally.faces += 1;
                let f = &faces[face];
                let (c, tol) = texel_at(&scene, f, spans.of(face, j), (i, j));
                let want = nearest_texel(&reference, [RefWrap::Repeat; 2], c[0], c[1]);
                let mut both = true;
                for (a, (g, w)) in [(x, want.0), (y, want.1)].into_iter().enumerate() {
                    tolerances.push(tol[a]);
                    if (c[a] - c[a].round()).abs() <= tol[a] {
                        both = false;
                        continue;
                    }
                    assert_eq!(
                        g, w,
                        "{}: pixel {i},{j} face {face} axis {a}: texel {g}, exact coordinate {:.4} \
                         (tolerance {:.4}), face texels {:?}, pose {:?}",
                        case.name, c[a], tol[a], f.texel, case.pose
                    );
                }
                if both {
                    tally.checked += 1;
                } else {
                    tally.near_boundary += 1;
                }
            }
        }
    }
    tolerances
}

/// The median of `v`.
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

/// The fixed-point vertices of every scene of the suite against the f64 ones: clip-space
/// coordinates within `CLIP_ERROR`, and so screen positions within `position_error`'s bound —
/// the input error the tolerances allow for.
#[test]
fn vertices_match_f64() {
    let (unclipped, clipped) = all_cases();
    let (mut worst_clip, mut worst_xy, mut worst_ratio) = (0.0f64, 0.0f64, 0.0f64);
    for case in unclipped.iter().chain(&clipped) {
        let scene = Scene::new(&case.pose, LIGHT, 0.0);
        for v in &case.mesh.vertices {
            let clip = scene.pipeline.clip_position(*v);
            let e = apply(&scene.view.model_view, bits3(*v));
            let want = scene.clip(e);
            let got = [clip.x, clip.y, clip.z, clip.w].map(fl);
            for k in 0..4 {
                worst_clip = worst_clip.max((got[k] - want[k]).abs());
            }
            if let Some(got) = scene.pipeline.project(clip) {
                let (x, y) = scene.view.screen(e);
                let d = (got.x.to_num::<f64>() - x)
                    .abs()
                    .max((got.y.to_num::<f64>() - y).abs());
                let bound = scene.position_error(&[e]);
                assert!(d <= bound, "{}: vertex {e:?} off by {d} px", case.name);
                worst_xy = worst_xy.max(d);
                worst_ratio = worst_ratio.max(d / bound);
            }
        }
    }
    println!(
        "worst clip-space error {worst_clip:.2e}, vertex {worst_xy:.4} px ({worst_ratio:.2} of \
         its bound)"
    );
    assert!(worst_clip <= CLIP_ERROR, "{worst_clip}");
}

/// The totals of `check_nearest` over a suite's cases and the tolerances it met: printed (with
/// the median tolerance), then the suite's bounds: over 25 000 pixels checked on both axes, at
/// least 60 % of those the reference gives one face, and rounding deciding at most 10 % of the
/// covered pixels.
fn assert_nearest_totals(mut tally: Tally, tolerances: Vec<f64>) {
    tally.median_tolerance = median(tolerances);
    println!("{tally:?}");
    assert!(tally.checked > 25_000, "{tally:?}");
    assert!(
        tally.checked as f64 >= 0.6 * tally.faces as f64,
        "{tally:?}"
    );
    assert!(tally.ambiguous as f64 <= 0.1 * (tally.faces + tally.ambiguous) as f64);
}

/// Unlit textured floors at grazing angles, tori and patched icospheres at random poses (all
/// three cullings): every pixel the reference gives one face shows the texel of the exact
/// perspective-correct coordinate there, unless that coordinate is within its tolerance
/// (module docs; about 1/16 texel where a face may be filled in screen space, less elsewhere)
/// of a texel boundary on that axis; the coverage and depths are the reference's (depth within
/// 2 LSB plus what `MARGIN` px moves it). With tolerances of about 1/16 texel, about a quarter
/// of the pixels have an axis within one of a boundary: at least 60 % must be checked on both
/// axes, and rounding may decide at most 10 % of the covered pixels.
#[test]
fn unlit_nearest_texels_match_the_ray_cast() {
    let (cases, _) = all_cases();
    let mut tally = Tally::default();
    let mut tolerances = Vec::new();
    for case in &cases {
        tolerances.extend(check_nearest(case, &mut tally));
    }
    assert_nearest_totals(tally, tolerances);
}

/// Faces crossing the near plane (a floor from behind the camera to far ahead, the camera inside
/// a torus's tube, a large icosphere brushing the eye, the camera inside an icosphere): the clipped
/// fans are textured as the whole faces are — the same check and bounds as the unclipped
/// meshes', and every case clips.
#[test]
fn clipped_faces_keep_their_texels() {
    let (_, cases) = all_cases();
    let mut tally = Tally::default();
    let mut tolerances = Vec::new();
    for case in &cases {
        let before = tally.clipped;
        tolerances.extend(check_nearest(case, &mut tally));
        assert!(tally.clipped > before, "{}: nothing clipped", case.name);
    }
    assert_nearest_totals(tally, tolerances);
}

/// The probed coordinates' errors, in texels.
#[derive(Debug, Default)]
struct Probed {
    pixels: u64,
    /// The largest error anywhere, and on faces that must take the perspective fill.
    worst: f64,
    worst_perspective: f64,
    /// The largest error over its tolerance (less the probe's resolution).
    worst_ratio: f64,
}

/// The coordinates themselves, probed to 1/512 texel (`probe`), on every case of the suite
/// (clipped and not): at every pixel the reference gives one face, within the tolerance of the
/// texel tests plus the probe's resolution. Stronger than the nearest-texel tests, which see an
/// error only where it takes a pixel across a texel boundary; the measured errors are printed.
#[test]
fn probed_coordinates_are_within_the_tolerance() {
    let resolution = 0.5 / 256.0;
    let (unclipped, clipped) = all_cases();
    let texels = coordinate_texels();
    let texture = Texture::new(Rgb888Texels(&texels), TEX, TEX).unwrap();
    let mut all = Probed::default();
    let mut lines = String::new();
    for case in unclipped.iter().chain(&clipped) {
        let scene = Scene::new(&case.pose, LIGHT, 0.2);
        let got = probe(&scene.pipeline, &case.mesh, &texture);
        let faces = ref_faces(&scene, &case.mesh, (TEX, TEX));
        let (verdicts, spans) = verdicts(&scene, &faces);
        let mut this = Probed::default();
        for (p, verdict) in verdicts.into_iter().enumerate() {
            let Verdict::Face { face, .. } = verdict else {
                continue;
            };
            let (i, j) = ((p as u32 % W) as i32, (p as u32 / W) as i32);
            let f = &faces[face];
            let (c, tol) = texel_at(&scene, f, spans.of(face, j), (i, j));
            let perspective = affine_ratio(&scene, f, &[(f.spread(), AFFINE_TEXELS)]).is_none();
            let g = got[p].unwrap_or_else(|| panic!("{}: pixel {i},{j} empty", case.name));
            for a in 0..2 {
                let v = unwrap_near(g[a], c[a]);
                let d = (v - c[a]).abs();
                assert!(
                    d <= tol[a] + resolution + 1e-9,
                    "{}: pixel {i},{j} face {face} axis {a}: coordinate {v:.4}, exact {:.4}, \
                     tolerance {:.4}; face texels {:?}, w {:?}, pose {:?}",
                    case.name,
                    c[a],
                    tol[a],
                    f.texel,
                    f.w,
                    case.pose
                );
                this.worst = this.worst.max(d);
                if perspective {
                    this.worst_perspective = this.worst_perspective.max(d);
                }
                this.worst_ratio = this.worst_ratio.max((d - resolution).max(0.0) / tol[a]);
            }
            this.pixels += 1;
        }
        lines += &format!(
            "  {}: {} pixels, error ≤ {:.4} texel ({:.4} on perspective-only faces), ≤ {:.2} of \
             the tolerance\n",
            case.name, this.pixels, this.worst, this.worst_perspective, this.worst_ratio
        );
        all.pixels += this.pixels;
        all.worst = all.worst.max(this.worst);
        all.worst_perspective = all.worst_perspective.max(this.worst_perspective);
        all.worst_ratio = all.worst_ratio.max(this.worst_ratio);
    }
    println!("probed coordinates: {all:?}\n{lines}");
    assert!(all.pixels > 60_000, "{all:?}");
}

// ---------------------------------------------------------------------------------------------
// Lit texels
// ---------------------------------------------------------------------------------------------

/// The constant texel of the lit tests.
const TEXEL: [u8; 3] = [240, 180, 100];

/// `case`'s scene under a random light (from the front half) with a random ambient level.
fn random_lit_scene(case: &Case, rng: &mut Rng) -> Scene {
    let light = normalize([
        rng.range_f64(-1.0, 1.0),
        rng.range_f64(-1.0, 1.0),
        rng.range_f64(0.2, 1.0),
    ]);
    let ambient = rng.range_f64(0.0, 0.4);
    Scene::new(&case.pose, light, ambient)
}

/// The bytes of a 4 × 4 Rgb888 texture of [`TEXEL`] everywhere.
fn constant_texels() -> Vec<u8> {
    (0..16).flat_map(|_| TEXEL).collect()
}

/// The largest channel errors of a lit comparison (LSB).
#[derive(Debug, Default)]
struct Lit {
    pixels: u64,
    flat: f64,
    gouraud: f64,
    /// The Gouraud error less its interpolation allowance.
    gouraud_beyond: f64,
    /// The untextured (screen-space) Gouraud draw against the textured one, and against the
    /// exact perspective-correct level.
    untextured_vs_textured: f64,
    untextured_vs_exact: f64,
    /// Pixels written, and of all pixels those whose depth the untextured draw gives too.
    written: u64,
    same_depth: u64,
    /// The Gouraud draw into Rgb565 (its own 5- and 6-bit LSBs), and less its allowance.
    gouraud_565: f64,
    gouraud_565_beyond: f64,
}

/// Draws `case` with a constant texture lit Flat and Gouraud by a random light, and the
/// untextured Gouraud material of the same colour; checks the lit colours against the f64
/// Lambert levels at every pixel the reference gives one face.
fn check_lit(case: &Case, rng: &mut Rng, lit: &mut Lit) {
    let scene = random_lit_scene(case, rng);
    let bytes = constant_texels();
    let texture = Texture::new(Rgb888Texels(&bytes), 4, 4).unwrap();
    let mesh = case.mesh.as_mesh();
    let (flat, _) = textured(&scene.pipeline, &mesh, &texture, Shading::Flat);
    let (gouraud, _) = textured(&scene.pipeline, &mesh, &texture, Shading::Gouraud);
    let gouraud_565 = textured_rgb565(&scene.pipeline, &mesh, &texture, Shading::Gouraud);
    let color = Rgb888::new(TEXEL[0], TEXEL[1], TEXEL[2]);
    let texel_565 = Rgb565::from(color);
    let texel_565 = [texel_565.r(), texel_565.g(), texel_565.b()].map(f64::from);
    let plain = untextured(&scene.pipeline, &mesh, color, Shading::Gouraud);
    // The textured draws cover the untextured draw's pixels (documented); the depths are
    // counted.
    let coverage = plain.written_set();
    assert!(
        flat.written_set() == coverage && gouraud.written_set() == coverage,
        "{}: coverage differs",
        case.name
    );
    lit.same_depth += (0..N).filter(|&i| plain.z[i] == gouraud.z[i]).count() as u64;
    lit.written += coverage.iter().filter(|&&c| c).count() as u64;
    let faces = ref_faces(&scene, &case.mesh, (4, 4));
    let (verdicts, spans) = verdicts(&scene, &faces);
    let channels = |c: Rgb888| [c.r(), c.g(), c.b()].map(f64::from);
    for (p, verdict) in verdicts.into_iter().enumerate() {
        let Verdict::Face { face, .. } = verdict else {
            continue;
        };
        let (i, j) = ((p as u32 % W) as i32, (p as u32 / W) as i32);
        let f = &faces[face];
        let texel = TEXEL.map(f64::from);
        // Flat: the face's level, within 1 LSB (½ for the rounding, the level's 2⁻¹² and its
        // 8.8 and 16-bit fractions).
        for (k, g) in channels(flat.px[p]).into_iter().enumerate() {
            let d = (g - texel[k] * f.flat).abs();
            assert!(
                d <= 1.0,
                "{}: pixel {i},{j} face {face} channel {k}: flat {g}, exact {:.3} (level {:.5}), \
                 pose {:?}",
                case.name,
                texel[k] * f.flat,
                f.flat,
                case.pose
            );
            lit.flat = lit.flat.max(d);
        }
        // Gouraud: the vertex levels interpolated perspective-correct, within 1 LSB plus the
        // interpolation's tolerance (as the texel coordinates', with the level's spread; the
        // fill may take screen space if both the texels and the levels allow).
        let e = exact(&scene, f, spans.of(face, j), f.levels, (i, j), UNIT);
        let spread = spread_of(f.levels);
        let affine = affine_ratio(
            &scene,
            f,
            &[(f.spread(), AFFINE_TEXELS), (spread, AFFINE_LEVEL)],
        )
        .map(|r| departure(r, spread, AFFINE_LEVEL));
        // The screen-space fill's level plane: 8.8 vertex values, truncated, and its 16-bit
        // fraction.
        let rounding = 2.0 / (256.0 * 255.0);
        let tol = tolerance(&scene, f, &e, spread, affine, rounding);
        for (k, g) in channels(gouraud.px[p]).into_iter().enumerate() {
            let want = texel[k] * e.value.clamp(0.0, 1.0);
            let d = (g - want).abs();
            assert!(
                d <= 1.0 + texel[k] * tol,
                "{}: pixel {i},{j} face {face} channel {k}: Gouraud {g}, exact {want:.3} (levels \
                 {:?}, tolerance {:.5}), pose {:?}",
                case.name,
                f.levels,
                tol,
                case.pose
            );
            lit.gouraud = lit.gouraud.max(d);
            lit.gouraud_beyond = lit.gouraud_beyond.max(d - texel[k] * tol);
            let u = channels(plain.px[p])[k];
            lit.untextured_vs_textured = lit.untextured_vs_textured.max((u - g).abs());
            lit.untextured_vs_exact = lit.untextured_vs_exact.max((u - want).abs());
        }
        // The same into Rgb565, whose fill may take screen space with about one level of
        // departure (a quarter of green's step): within 1 LSB of each channel plus the
        // allowance, in that channel's own steps.
        let affine = affine_ratio(
            &scene,
            f,
            &[(f.spread(), AFFINE_TEXELS), (spread, AFFINE_LEVEL_565)],
        )
        .map(|r| departure(r, spread, AFFINE_LEVEL_565));
        let tol = tolerance(&scene, f, &e, spread, affine, rounding);
        let c = gouraud_565[p];
        for (k, g) in [c.r(), c.g(), c.b()].map(f64::from).into_iter().enumerate() {
            let want = texel_565[k] * e.value.clamp(0.0, 1.0);
            let d = (g - want).abs();
            assert!(
                d <= 1.0 + texel_565[k] * tol,
                "{}: pixel {i},{j} face {face} channel {k}: Gouraud into Rgb565 {g}, exact \
                 {want:.3} (levels {:?}, tolerance {:.5}), pose {:?}",
                case.name,
                f.levels,
                tol,
                case.pose
            );
            lit.gouraud_565 = lit.gouraud_565.max(d);
            lit.gouraud_565_beyond = lit.gouraud_565_beyond.max(d - texel_565[k] * tol);
        }
        lit.pixels += 1;
    }
}

/// The largest errors of the vertex-colour comparison (LSB): pixels checked, the largest
/// error, and the largest beyond its allowance.
#[derive(Debug, Default)]
struct Tinted {
    pixels: u64,
    worst: f64,
    beyond: f64,
}

/// Draws `case` with random vertex colours tinting a constant texture
/// (`TexturedMaterial::with_vertex_colors`), Gouraud-lit by a random light, and checks every
/// pixel the reference gives one face against the texel times the f64 colour-times-level of
/// the vertices, interpolated perspective-correct at the ray's hit: within 1 LSB plus the
/// interpolation's tolerance (as the levels', with each channel's spread) and the tint's 8.8
/// quantisation.
fn check_tinted(case: &Case, rng: &mut Rng, tinted: &mut Tinted) {
    let scene = random_lit_scene(case, rng);
    let bytes = constant_texels();
    let texture = Texture::new(Rgb888Texels(&bytes), 4, 4).unwrap();
    let mut data = case.mesh.clone();
    data.colors = (0..data.vertices.len())
        .map(|_| {
            Rgb888::new(
                rng.below(256) as u8,
                rng.below(256) as u8,
                rng.below(256) as u8,
            )
        })
        .collect();
    let mesh = data.as_mesh();
    let mut frame = Frame::new();
    let material = TexturedMaterial::new(&texture, Shading::Gouraud).with_vertex_colors();
    scene
        .pipeline
        .draw_textured_mesh(&mesh, &material, &mut frame.target());
    let faces = ref_faces(&scene, &data, (4, 4));
    let (verdicts, spans) = verdicts(&scene, &faces);
    for (p, verdict) in verdicts.into_iter().enumerate() {
        let Verdict::Face { face, .. } = verdict else {
            continue;
        };
        let (i, j) = ((p as u32 % W) as i32, (p as u32 / W) as i32);
        let f = &faces[face];
        let colors = data.indices[face].map(|v| data.colors[usize::from(v)]);
        let tint = |k: usize| {
            let c = colors.map(|c| f64::from([c.r(), c.g(), c.b()][k]) / 255.0);
            [0, 1, 2].map(|v| c[v] * f.levels[v])
        };
        let spreads = [0, 1, 2].map(|k| spread_of(tint(k)));
        let widest = spreads[0].max(spreads[1]).max(spreads[2]);
        let ratio = affine_ratio(
            &scene,
            f,
            &[(f.spread(), AFFINE_TEXELS), (widest, AFFINE_LEVEL)],
        );
        let got = frame.px[p];
        for (k, g) in [got.r(), got.g(), got.b()]
            .map(f64::from)
            .into_iter()
            .enumerate()
        {
            let e = exact(&scene, f, spans.of(face, j), tint(k), (i, j), UNIT);
            let affine = ratio.map(|r| departure(r, spreads[k], AFFINE_LEVEL));
            // The screen-space planes' rounding as the levels'; the tint's own 8.8 rounding.
            let rounding = 2.0 / (256.0 * 255.0);
            let tol = tolerance(&scene, f, &e, spreads[k], affine, rounding) + 1.0 / 65_280.0;
            let texel = f64::from(TEXEL[k]);
            let want = texel * e.value.clamp(0.0, 1.0);
            let d = (g - want).abs();
            assert!(
                d <= 1.0 + texel * tol,
                "{}: pixel {i},{j} face {face} channel {k}: {g}, exact {want:.3} (colours \
                 {colors:?}, levels {:?}, tolerance {tol:.5}), pose {:?}",
                case.name,
                f.levels,
                case.pose
            );
            tinted.worst = tinted.worst.max(d);
            tinted.beyond = tinted.beyond.max(d - texel * tol);
        }
        tinted.pixels += 1;
    }
}

/// Draws `case` with a constant texture, Gouraud-lit with a Blinn-Phong highlight
/// (`TexturedMaterial::with_specular`) by a random light, and checks every pixel the reference
/// gives one face against `min(255, texel · L + 255 · S)`, `L` and `S` the vertices' f64
/// Lambert level and `strength · max(0, n·ĥ)^shininess` (none facing away from the light;
/// `ĥ` between the light and the viewer at infinity along +z) interpolated
/// perspective-correct at the ray's hit: within 1 LSB plus each term's interpolation
/// tolerance, the power's `shininess · 2⁻¹⁷` and the terms' 8.8 quantisation.
fn check_shiny(case: &Case, rng: &mut Rng, shiny: &mut Tinted) {
    let scene = random_lit_scene(case, rng);
    let specular = Specular::new(fx(rng.range_f64(0.2, 1.0)), rng.below(48) as u8 + 1);
    let (strength, shininess) = (fl(specular.strength()), specular.shininess());
    let bytes = constant_texels();
    let texture = Texture::new(Rgb888Texels(&bytes), 4, 4).unwrap();
    let mesh = case.mesh.as_mesh();
    let mut frame = Frame::new();
    let material = TexturedMaterial::new(&texture, Shading::Gouraud).with_specular(specular);
    scene
        .pipeline
        .draw_textured_mesh(&mesh, &material, &mut frame.target());
    let half = normalize([scene.light[0], scene.light[1], scene.light[2] + 1.0]);
    let world_normal = |n: Vec3| normalize(rotate(&scene.view.model_view, normalize(bits3(n))));
    let faces = ref_faces(&scene, &case.mesh, (4, 4));
    let (verdicts, spans) = verdicts(&scene, &faces);
    for (p, verdict) in verdicts.into_iter().enumerate() {
        let Verdict::Face { face, .. } = verdict else {
            continue;
        };
        if case.mesh.normals.is_empty() {
            continue;
        }
        let (i, j) = ((p as u32 % W) as i32, (p as u32 / W) as i32);
        let f = &faces[face];
        let normals =
            case.mesh.indices[face].map(|v| world_normal(case.mesh.normals[usize::from(v)]));
        let speculars = normals.map(|n| match dot(n, scene.light) > 0.0 {
            true => strength * dot(n, half).max(0.0).powi(i32::from(shininess)),
            false => 0.0,
        });
        let (level_spread, specular_spread) = (spread_of(f.levels), spread_of(speculars));
        let ratio = affine_ratio(
            &scene,
            f,
            &[
                (f.spread(), AFFINE_TEXELS),
                (level_spread.max(specular_spread), AFFINE_LEVEL),
            ],
        );
        let rounding = 2.0 / (256.0 * 255.0);
        let term = |values: [f64; 3], spread: f64| {
            let e = exact(&scene, f, spans.of(face, j), values, (i, j), UNIT);
            let affine = ratio.map(|r| departure(r, spread, AFFINE_LEVEL));
            let tol = tolerance(&scene, f, &e, spread, affine, rounding) + 1.0 / 65_280.0;
            (e.value.clamp(0.0, 1.0), tol)
        };
        let (level, level_tol) = term(f.levels, level_spread);
        let (spec, spec_tol) = term(speculars, specular_spread);
        let spec_tol = spec_tol + f64::from(shininess) / 131_072.0;
        let got = frame.px[p];
        for (k, g) in [got.r(), got.g(), got.b()]
            .map(f64::from)
            .into_iter()
            .enumerate()
        {
            let texel = f64::from(TEXEL[k]);
            let want = (texel * level + 255.0 * spec).min(255.0);
            let allowance = texel * level_tol + 255.0 * spec_tol;
            let d = (g - want).abs();
            assert!(
                d <= 1.0 + allowance,
                "{}: pixel {i},{j} face {face} channel {k}: {g}, exact {want:.3} (levels {:?}, \
                 speculars {speculars:?}, allowance {allowance:.4}), pose {:?}",
                case.name,
                f.levels,
                case.pose
            );
            shiny.worst = shiny.worst.max(d);
            shiny.beyond = shiny.beyond.max(d - allowance);
        }
        shiny.pixels += 1;
    }
}

/// Highlights on textured meshes: every pixel within 1 LSB (plus the interpolation's
/// tolerance and the power's bound) of the texel times the f64 Lambert level plus the f64
/// Blinn-Phong term, both perspective-correct, on clipped and unclipped cases.
#[test]
fn highlights_light_texels() {
    let (unclipped, clipped) = all_cases();
    let mut rng = Rng(0x7e47_3d09);
    let mut shiny = Tinted::default();
    for case in unclipped.iter().chain(&clipped) {
        check_shiny(case, &mut rng, &mut shiny);
    }
    println!("{shiny:?}");
    assert!(shiny.pixels > 30_000, "{shiny:?}");
}

/// The texture issue's motivating scene: a large floor quad seen at a grazing angle, its
/// corners' normals tilted apart so that their Gouraud levels differ widely, drawn into Rgb565.
/// A `Material` interpolates the levels in screen space and misses the f64 perspective-correct
/// colour by more than 1 LSB on many pixels (asserted: the scene is one where affine
/// interpolation fails); a `TexturedMaterial` of a `Solid` texture of the same colour is within
/// 1 LSB (plus the interpolation's tolerance) at every pixel the reference gives one face.
#[test]
fn solid_textures_make_gouraud_perspective_correct() {
    let mut rng = Rng(0x7e47_3d0b);
    let (mut pixels, mut affine_off, mut worst, mut affine_worst) = (0u64, 0u64, 0f64, 0f64);
    let white = Rgb565::WHITE;
    let base = [white.r(), white.g(), white.b()].map(f64::from);
    let texture = Texture::new(Solid(white), 1, 1).unwrap();
    for n in 0..6 {
        let (mesh, pose) = grazing_floor(&mut rng);
        let scene = Scene::new(&pose, normalize([0.3, 1.0, 0.4]), 0.1);
        let case = Case {
            name: format!("grazing floor #{n}"),
            mesh,
            pose,
        };
        let solid = textured_rgb565(
            &scene.pipeline,
            &case.mesh.as_mesh(),
            &texture,
            Shading::Gouraud,
        );
        let (mut px, mut z) = (vec![Rgb565::BLACK; N], vec![DEPTH_CLEAR; N]);
        let mut target = DepthTarget::new(&mut px, &mut z, W, H).unwrap();
        target.clear(Rgb565::BLACK);
        let material = Material::new(white, Shading::Gouraud);
        scene
            .pipeline
            .draw_mesh(&case.mesh.as_mesh(), &material, &mut target);
        let faces = ref_faces(&scene, &case.mesh, (1, 1));
        let (verdicts, spans) = verdicts(&scene, &faces);
        for (p, verdict) in verdicts.into_iter().enumerate() {
            let Verdict::Face { face, .. } = verdict else {
                continue;
            };
            let (i, j) = ((p as u32 % W) as i32, (p as u32 / W) as i32);
            let f = &faces[face];
            let e = exact(&scene, f, spans.of(face, j), f.levels, (i, j), UNIT);
            let spread = spread_of(f.levels);
            let affine = affine_ratio(
                &scene,
                f,
                &[(f.spread(), AFFINE_TEXELS), (spread, AFFINE_LEVEL_565)],
            )
            .map(|r| departure(r, spread, AFFINE_LEVEL_565));
            let tol = tolerance(&scene, f, &e, spread, affine, 2.0 / (256.0 * 255.0));
            let (got, plain) = (solid[p], px[p]);
            let mut off = false;
            for k in 0..3 {
                let want = base[k] * e.value.clamp(0.0, 1.0);
                let g = f64::from([got.r(), got.g(), got.b()][k]);
                let d = (g - want).abs();
                assert!(
                    d <= 1.0 + base[k] * tol,
                    "{}: pixel {i},{j} channel {k}: {g}, exact {want:.3} (levels {:?}, \
                     tolerance {tol:.5})",
                    case.name,
                    f.levels
                );
                worst = worst.max(d);
                let a = (f64::from([plain.r(), plain.g(), plain.b()][k]) - want).abs();
                affine_worst = affine_worst.max(a);
                off |= a > 1.0;
            }
            pixels += 1;
            affine_off += u64::from(off);
        }
    }
    println!(
        "{pixels} px: solid texture within {worst:.3} LSB; Material (screen space) up to \
         {affine_worst:.3} LSB, beyond 1 LSB at {affine_off} px"
    );
    assert!(pixels > 20_000, "{pixels}");
    assert!(affine_off * 5 > pixels, "{affine_off} of {pixels}");
}

/// Vertex colours tint textured meshes: every pixel within 1 LSB (plus the interpolation's
/// tolerance) of the texel times the vertices' colour-times-level, perspective-correct, on
/// clipped and unclipped cases.
#[test]
fn vertex_colors_tint_texels() {
    let (unclipped, clipped) = all_cases();
    let mut rng = Rng(0x7e47_3d07);
    let mut tinted = Tinted::default();
    for case in unclipped.iter().chain(&clipped) {
        check_tinted(case, &mut rng, &mut tinted);
    }
    println!("{tinted:?}");
    assert!(tinted.pixels > 60_000, "{tinted:?}");
}

/// Flat and Gouraud lighting of textured meshes (a constant texture, so the colour is the
/// light's alone) under random lights, clipped and not: Flat texels are the texel times the
/// face's f64 Lambert level (geometric normal) within 1 LSB; Gouraud texels the texel times the
/// vertex levels (from the mesh's normals) interpolated at the ray's hit barycentrics, within
/// 1 LSB plus the texel's share of the interpolation tolerance. The textured draws cover the
/// pixels of the untextured Gouraud draw of the same mesh; its depths and colours (screen-space
/// levels, 256-entry table) are only reported.
#[test]
fn lit_texels_follow_lambert() {
    let (unclipped, clipped) = all_cases();
    let mut rng = Rng(0x7e47_3d02);
    let mut lit = Lit::default();
    for case in unclipped.iter().chain(&clipped) {
        check_lit(case, &mut rng, &mut lit);
    }
    println!("{lit:?}");
    assert!(lit.pixels > 60_000, "{lit:?}");
}

// ---------------------------------------------------------------------------------------------
// Per-pixel (quadratic) light on textured meshes
// ---------------------------------------------------------------------------------------------

/// The f64 light of the quadratic normal field of a face with unit world normals `normals` at
/// barycentrics `b`: `N(b) = Σ Nᵢbᵢ(2bᵢ − 1) + Σ 4N̂ᵢⱼbᵢbⱼ`, `N̂ᵢⱼ = normalize(Nᵢ + Nⱼ)`,
/// renormalised; its Lambert level `ambient + (1 − ambient)·max(0, n̂·l)` and Blinn-Phong term
/// `strength · max(0, n̂·ĥ)^shininess` (0 where `n̂·l ≤ 0`).
fn quadratic_terms(
    scene: &Scene,
    normals: &[V; 3],
    b: [f64; 3],
    half: V,
    specular: (f64, i32),
    extra: &[(V, f64)],
) -> (f64, f64) {
    let mid = |i: usize, j: usize| normalize([0, 1, 2].map(|c| normals[i][c] + normals[j][c]));
    let nodes = [
        normals[0],
        normals[1],
        normals[2],
        mid(0, 1),
        mid(1, 2),
        mid(2, 0),
    ];
    let w = [
        b[0] * (2.0 * b[0] - 1.0),
        b[1] * (2.0 * b[1] - 1.0),
        b[2] * (2.0 * b[2] - 1.0),
        4.0 * b[0] * b[1],
        4.0 * b[1] * b[2],
        4.0 * b[2] * b[0],
    ];
    let n = normalize([0, 1, 2].map(|c| (0..6).map(|k| w[k] * nodes[k][c]).sum::<f64>()));
    let d = dot(n, scene.light);
    let level = scene.ambient + (1.0 - scene.ambient) * d.max(0.0);
    let mut spec = match d > 0.0 {
        true => specular.0 * dot(n, half).max(0.0).powi(specular.1),
        false => 0.0,
    };
    // The pipeline's other lights (directional: unit direction and intensity), saturating.
    let mut level = level;
    for &(l, w) in extra {
        let d = dot(n, l);
        if d > 0.0 {
            let h = normalize([l[0], l[1], l[2] + 1.0]);
            level += w * d;
            spec += w * specular.0 * dot(n, h).max(0.0).powi(specular.1);
        }
    }
    (level.min(1.0), spec.min(1.0))
}

/// What a quadratic comparison found: pixels checked, the largest error and tolerance (LSB),
/// the largest error beyond the tolerance, and how the per-vertex (Gouraud) draw of the same
/// scene fares against the same reference and tolerance: its largest error, and the pixels
/// where it exceeds the tolerance.
#[derive(Debug, Default)]
struct Quadratic {
    pixels: u64,
    worst: f64,
    widest: f64,
    beyond: f64,
    /// The largest error at pixels whose tolerance is at most 2 LSB.
    worst_tight: f64,
    /// Channels more than 1 and 2 LSB off.
    over_one: u64,
    over_two: u64,
    gouraud_worst: f64,
    gouraud_off: u64,
}

/// The fixed-point evaluation's own error on a cosine (nodes rounded to `I16F16`, the field's
/// coefficients and differences, the 16-bit normal and `inv_sqrt`): 2⁻¹³.
const COSINE_ERROR: f64 = 1.0 / 8192.0;

/// Draws `mesh` in `scene` textured with a constant texture, `Shading::Quadratic` with the
/// highlight `specular` (per pixel), and `Shading::Gouraud` (the old fallback: per vertex), and
/// checks every pixel the reference gives one face against `min(255, texel · L + 255 · S)`, `L`
/// and `S` the f64 per-pixel level and highlight of the quadratic normal field at the ray's hit
/// barycentrics (`quadratic_terms`).
///
/// Tolerance: the implementation's perspective barycentrics `λ₁`, `λ₂` are off the exact ones
/// by at most `εₖ = δ + chord + steps + position` (`RefFace::delta` and `exact` with the
/// barycentric as the attribute: the same bounds as the texel coordinates'); the colour may then
/// be anything the f64 colour takes with `λ` moved by up to `±εₖ` (evaluated at the corners
/// and the edges' midpoints of that box), plus 1 LSB (rounding) and the cosines' own error
/// (`COSINE_ERROR`: `texel · η` on the level, `255 · strength · shininess · η` and the power's
/// `shininess · 2⁻¹⁷` on the highlight).
fn check_quadratic(
    name: &str,
    scene: &Scene,
    mesh: &MeshData,
    specular: Specular,
    extra: &[(V, f64)],
    q: &mut Quadratic,
) -> Frame {
    let bytes = constant_texels();
    let texture = Texture::new(Rgb888Texels(&bytes), 4, 4).unwrap();
    let (strength, shininess) = (fl(specular.strength()), i32::from(specular.shininess()));
    let draw = |shading: Shading| {
        let mut frame = Frame::new();
        let material = TexturedMaterial::new(&texture, shading).with_specular(specular);
        scene
            .pipeline
            .draw_textured_mesh(&mesh.as_mesh(), &material, &mut frame.target());
        frame
    };
    let (quadratic, gouraud) = (draw(Shading::Quadratic), draw(Shading::Gouraud));
    let half = normalize([scene.light[0], scene.light[1], scene.light[2] + 1.0]);
    let world_normal = |n: Vec3| normalize(rotate(&scene.view.model_view, normalize(bits3(n))));
    let faces = ref_faces(scene, mesh, (4, 4));
    let (verdicts, spans) = verdicts(scene, &faces);
    let texel = TEXEL.map(f64::from);
    let color = |b: [f64; 3], normals: &[V; 3]| {
        let (l, s) = quadratic_terms(scene, normals, b, half, (strength, shininess), extra);
        texel.map(|t| (t * l + 255.0 * s).min(255.0))
    };
    for (p, verdict) in verdicts.into_iter().enumerate() {
        let Verdict::Face { face, .. } = verdict else {
            continue;
        };
        let (i, j) = ((p as u32 % W) as i32, (p as u32 / W) as i32);
        let f = &faces[face];
        let idx = mesh.indices[face].map(usize::from);
        let normals = match mesh.normals.is_empty() {
            false => idx.map(|v| world_normal(mesh.normals[v])),
            true => {
                let p = idx.map(|v| bits3(mesh.vertices[v]));
                let n = normalize(cross(sub(p[1], p[0]), sub(p[2], p[0])));
                [normalize(rotate(&scene.view.model_view, n)); 3]
            }
        };
        let basis = |k: usize| {
            let mut a = [0.0; 3];
            a[k] = 1.0;
            exact(scene, f, spans.of(face, j), a, (i, j), UNIT)
        };
        let (e1, e2) = (basis(1), basis(2));
        let delta = f.delta(scene);
        let (eps1, eps2) = (delta + e1.wiggle, delta + e2.wiggle);
        let b = [1.0 - e1.value - e2.value, e1.value, e2.value];
        let want = color(b, &normals);
        let mut spread = [0.0f64; 3];
        for s1 in [-1.0, -0.5, 0.0, 0.5, 1.0] {
            for s2 in [-1.0, -0.5, 0.0, 0.5, 1.0] {
                let (l1, l2) = (b[1] + s1 * eps1, b[2] + s2 * eps2);
                let moved = color([1.0 - l1 - l2, l1, l2], &normals);
                for k in 0..3 {
                    spread[k] = spread[k].max((moved[k] - want[k]).abs());
                }
            }
        }
        let n = f64::from(shininess);
        let highlight = 255.0 * (strength * n * COSINE_ERROR + n / 131_072.0);
        let channels = |c: Rgb888| [c.r(), c.g(), c.b()].map(f64::from);
        let (got, old) = (channels(quadratic.px[p]), channels(gouraud.px[p]));
        for k in 0..3 {
            let tol = 1.0 + spread[k] + texel[k] * COSINE_ERROR + highlight;
            let d = (got[k] - want[k]).abs();
            assert!(
                d <= tol,
                "{name}: pixel {i},{j} face {face} channel {k}: {}, exact {:.3} (tolerance \
                 {tol:.3}, ε {eps1:.2e} {eps2:.2e})",
                got[k],
                want[k]
            );
            q.worst = q.worst.max(d);
            q.widest = q.widest.max(tol);
            q.beyond = q.beyond.max(d - tol);
            if tol <= 2.0 {
                q.worst_tight = q.worst_tight.max(d);
            }
            q.over_one += u64::from(d > 1.0);
            q.over_two += u64::from(d > 2.0);
            let g = (old[k] - want[k]).abs();
            q.gouraud_worst = q.gouraud_worst.max(g);
            if g > tol && k == 1 {
                q.gouraud_off += 1;
            }
        }
        q.pixels += 1;
    }
    quadratic
}

/// A floor quad (two faces) whose corner normals lean outwards by `lean` (a dome: the normal
/// field is near the floor's own normal in the middle of the faces, far from it at the corners).
fn dome_floor(half: f64, lean: f64) -> MeshData {
    let mut mesh = floor(half, 1, 1.0);
    mesh.normals = mesh
        .vertices
        .iter()
        .map(|p| {
            let v = bits3(*p);
            let n = normalize([v[0] * lean / half, v[1] * lean / half, 1.0]);
            Vec3::new(fx(n[0]), fx(n[1]), fx(n[2]))
        })
        .collect();
    mesh
}

/// Textured meshes with `Shading::Quadratic` are lit per pixel, perspective-correct: on large
/// faces at grazing angles with curved normals (the normal field's barycentrics corrected for
/// perspective) and on faces whose highlight lies inside them (missed by per-vertex specular),
/// every pixel within the tolerance of `check_quadratic` of the f64 per-pixel reference, and
/// the per-vertex (Gouraud) draw of the same scenes — what `Quadratic` drew before — beyond it on
/// many pixels.
#[test]
fn quadratic_texels_are_lit_per_pixel() {
    let mut rng = Rng(0x7e47_3d11);
    let mut grazing = Quadratic::default();
    for n in 0..6 {
        let (mesh, pose) = grazing_floor(&mut rng);
        let scene = Scene::new(&pose, normalize([0.3, 1.0, 0.4]), 0.1);
        let specular = Specular::new(fx(0.5), 8);
        check_quadratic(
            &format!("grazing floor #{n}"),
            &scene,
            &mesh,
            specular,
            &[],
            &mut grazing,
        );
    }
    println!("grazing floors: {grazing:?}");
    assert!(grazing.pixels > 20_000, "{grazing:?}");
    assert!(grazing.gouraud_off * 5 > grazing.pixels, "{grazing:?}");

    // A domed floor tilted towards the camera, the light placed so that the half vector is the
    // floor's own normal: the highlight peaks inside the faces, where no vertex sees it.
    let mut inside = Quadratic::default();
    for n in 0..6 {
        let pitch = rng.range_f64(-70.0, -45.0);
        let pose = Pose {
            fov: 60,
            near: 0.5,
            far: 30.0,
            yaw: degrees(rng.range_f64(-15.0, 15.0)),
            pitch: degrees(pitch),
            position: [
                rng.range_f64(-0.3, 0.3),
                rng.range_f64(-0.5, 0.0),
                rng.range_f64(-6.0, -4.5),
            ],
            cull: Cull::None,
        };
        // The floor's normal in eye space, and the light reflecting the viewer (+z) about it.
        let probe = Scene::new(&pose, [0.0, 0.0, 1.0], 0.0);
        let up = normalize(rotate(&probe.view.model_view, [0.0, 0.0, 1.0]));
        let k = 2.0 * up[2];
        let light = normalize([k * up[0], k * up[1], k * up[2] - 1.0]);
        let scene = Scene::new(&pose, light, 0.15);
        let mesh = dome_floor(3.0, rng.range_f64(0.5, 0.9));
        let specular = Specular::new(fx(0.8), 24 + 8 * (n as u8 % 3));
        let name = format!("domed floor #{n}");
        let frame = check_quadratic(&name, &scene, &mesh, specular, &[], &mut inside);
        // An untextured mesh through a `Solid` texture of the same colour: the same pixels
        // (its per-pixel light and highlight those checked here).
        let solid = Texture::new(Solid(Rgb888::new(TEXEL[0], TEXEL[1], TEXEL[2])), 1, 1).unwrap();
        let material = TexturedMaterial::new(&solid, Shading::Quadratic).with_specular(specular);
        let mut plain = Frame::new();
        scene
            .pipeline
            .draw_textured_mesh(&mesh.as_mesh(), &material, &mut plain.target());
        assert!(plain == frame, "{name}: the Solid texture's pixels differ");
    }
    println!("highlights inside faces: {inside:?}");
    assert!(inside.pixels > 20_000, "{inside:?}");
    assert!(inside.gouraud_off * 5 > inside.pixels, "{inside:?}");
    assert!(inside.gouraud_worst > 60.0, "{inside:?}");

    // The same domes with two more directional lights (`Lights`), each lit and highlighted per
    // pixel too.
    let mut lights = Quadratic::default();
    let mut rng = Rng(0x7e47_3d13);
    for n in 0..4 {
        let pose = Pose {
            fov: 60,
            near: 0.5,
            far: 30.0,
            yaw: degrees(rng.range_f64(-15.0, 15.0)),
            pitch: degrees(rng.range_f64(-70.0, -45.0)),
            position: [0.0, rng.range_f64(-0.5, 0.0), rng.range_f64(-6.0, -4.5)],
            cull: Cull::None,
        };
        let mut scene = Scene::new(&pose, normalize([0.2, 0.6, 1.0]), 0.1);
        let mut set = Lights::new();
        let mut extra = Vec::new();
        for _ in 0..2 {
            let d = [
                rng.range_f64(-1.0, 1.0),
                rng.range_f64(-1.0, 1.0),
                rng.range_f64(0.2, 1.0),
            ];
            let bits = Vec3::new(fx(d[0]), fx(d[1]), fx(d[2]));
            let w = fx(rng.range_f64(0.2, 0.8));
            set = set.with(LightSource::directional(bits, w));
            extra.push((normalize(bits3(bits)), fl(w)));
        }
        scene.pipeline = scene.pipeline.with_lights(set);
        let mesh = dome_floor(3.0, rng.range_f64(0.5, 0.9));
        let specular = Specular::new(fx(0.6), 16);
        let name = format!("domed floor with lights #{n}");
        check_quadratic(&name, &scene, &mesh, specular, &extra, &mut lights);
    }
    println!("with two more directional lights: {lights:?}");
    assert!(lights.pixels > 10_000, "{lights:?}");

    // The suite's meshes (floors, tori, patched icospheres; clipped faces drawn as fans, the
    // field restricted to each triangle) under random lights and highlights.
    let mut rng = Rng(0x7e47_3d12);
    let (unclipped, clipped) = all_cases();
    let mut suite = Quadratic::default();
    for case in unclipped.iter().chain(&clipped) {
        let scene = random_lit_scene(case, &mut rng);
        let specular = Specular::new(fx(rng.range_f64(0.2, 1.0)), rng.below(48) as u8 + 1);
        check_quadratic(&case.name, &scene, &case.mesh, specular, &[], &mut suite);
    }
    println!("the suite's cases: {suite:?}");
    assert!(suite.pixels > 60_000, "{suite:?}");
}

// ---------------------------------------------------------------------------------------------
// Every path the same pixels
// ---------------------------------------------------------------------------------------------

/// How a band draws a textured mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// `DepthBand::draw_textured_mesh`: no bin, no scratch.
    EachFace,
    /// `DepthBand::draw_textured_mesh_with`: no bin, the vertices again per band.
    Scratch,
    /// `MeshBin::new_textured`: the faces binned once, each band drawing its own.
    Bin,
}

/// `mesh` drawn with `material` in bands of `rows` rows (`mode`: with a vertex scratch or
/// not, or through a bin whose counts must be `stats`), the bands' colours and depths put
/// together into one frame.
fn banded<S: TexelSource>(
    pipeline: &Pipeline,
    mesh: &Mesh<'_>,
    material: &TexturedMaterial<'_, S>,
    rows: u32,
    mode: Mode,
    scratch: &mut [ProjectedVertex],
    stats: DrawStats,
) -> Frame
where
    Rgb888: From<S::Color>,
{
    let layout = BandLayout::new(Size::new(W, H), rows).unwrap();
    let mut storage = vec![BinEntry::EMPTY; layout.count() as usize + mesh.indices.len()];
    let mut bin_scratch = vec![ProjectedVertex::EMPTY; mesh.vertices.len()];
    let mut bin = (mode == Mode::Bin).then(|| {
        let bin = MeshBin::new_textured(
            pipeline,
            mesh,
            material,
            &layout,
            &mut bin_scratch,
            &mut storage,
        )
        .unwrap();
        assert_eq!(bin.stats(), stats, "the bin's counts");
        bin
    });
    let mut colors = vec![Rgb888::BLACK; layout.buffer_len()];
    let mut depth = vec![0u16; layout.buffer_len()];
    let mut frame = Frame::new();
    let mut depths = vec![DEPTH_CLEAR; N];
    let mut bands =
        DepthBands::new(ColorBands::new(layout, &mut colors).unwrap(), &mut depth).unwrap();
    let mut sent = Callback(|area: &Rectangle, pixels: &[Rgb888]| {
        let start = (area.top_left.y as u32 * W) as usize;
        frame.px[start..start + pixels.len()].copy_from_slice(pixels);
        Ok::<(), ()>(())
    });
    bands
        .render(&mut sent, |band| {
            band.clear(Rgb888::BLACK);
            match (mode, bin.as_mut()) {
                (Mode::Bin, Some(bin)) => bin.draw(band).unwrap(),
                (Mode::Scratch, _) => {
                    pipeline
                        .draw_textured_mesh_with(mesh, material, band, scratch)
                        .unwrap();
                }
                _ => {
                    pipeline.draw_textured_mesh(mesh, material, band);
                }
            }
            let start = (band.rect().top_left.y as u32 * W) as usize;
            depths[start..start + band.depth().len()].copy_from_slice(band.depth());
        })
        .unwrap();
    frame.z = depths;
    frame
}

/// One draw of the paths test: a pose, a texture and a shading.
fn paths_round<S: TexelSource>(
    case: &Case,
    scene: &Scene,
    texture: &Texture<S>,
    shading: Shading,
    round: usize,
) -> DrawStats
where
    Rgb888: From<S::Color>,
{
    // Every other round's faces tinted by vertex colours.
    let mut data = case.mesh.clone();
    let mut material = TexturedMaterial::new(texture, shading);
    if round % 2 == 1 {
        data.colors = (0..data.vertices.len() as u32)
            .map(|k| Rgb888::new((k * 97) as u8, (k * 31 + 80) as u8, (k * 57 + 160) as u8))
            .collect();
        material = material.with_vertex_colors();
    }
    // Two rounds in three highlighted.
    if round % 3 != 0 {
        material = material.with_specular(Specular::new(Scalar::from_num(0.6), 12));
    }
    let mesh = data.as_mesh();
    let mut whole = Frame::new();
    let stats = scene
        .pipeline
        .draw_textured_mesh(&mesh, &material, &mut whole.target());
    let mut once = Frame::new();
    let mut scratch = vec![ProjectedVertex::EMPTY; case.mesh.vertices.len()];
    let with = scene
        .pipeline
        .draw_textured_mesh_with(&mesh, &material, &mut once.target(), &mut scratch)
        .unwrap();
    assert_eq!(stats, with, "{} round {round}: stats", case.name);
    assert!(
        whole == once,
        "{} round {round} ({shading:?}): the scratch draw differs",
        case.name
    );
    for rows in [1, 8, 16, 240] {
        for mode in [Mode::EachFace, Mode::Scratch, Mode::Bin] {
            let bands = banded(
                &scene.pipeline,
                &mesh,
                &material,
                rows,
                mode,
                &mut scratch,
                stats,
            );
            let at = (0..N).find(|&i| bands.px[i] != whole.px[i] || bands.z[i] != whole.z[i]);
            assert!(
                at.is_none(),
                "{} round {round} ({shading:?}): {rows}-row bands ({mode:?}) differ at pixel {:?}",
                case.name,
                at.map(|i| (i as u32 % W, i as u32 / W))
            );
        }
    }
    stats
}

/// Every way of drawing a textured mesh (every other round tinted by vertex colours, two in
/// three highlighted) gives the same frame, bit for bit: `draw_textured_mesh` and
/// `draw_textured_mesh_with` (a vertex scratch: the same stats too), and band rendering
/// (`DepthBands` of 1, 8, 16 and 240 rows, each band drawn with and without a scratch, and
/// through a `MeshBin::new_textured` with the frame's stats) against
/// the frame drawn whole — colours and depths, over the suite's poses (clipped and not), every
/// shading, power-of-two and other textures, nearest and bilinear, a viewport partly off the
/// target; and a scratch too short is an error that draws nothing.
#[test]
fn every_path_draws_the_same_pixels() {
    let (unclipped, clipped) = all_cases();
    let coordinates = coordinate_texels();
    let pow2 = Texture::new(Rgb888Texels(&coordinates), TEX, TEX).unwrap();
    let odd_bytes: Vec<u8> = (0..3 * 5 * 3).map(|k| (k * 37 % 251) as u8).collect();
    let odd = Texture::new(Rgb888Texels(&odd_bytes), 3, 5)
        .unwrap()
        .with_wrap(Wrap::MirroredRepeat, Wrap::Clamp);
    let words: Vec<u16> = (0..64 * 32)
        .map(|k| (k as u16).wrapping_mul(40_503))
        .collect();
    let rgb565 = Texture::new(Rgb565Texels(&words), 64, 32)
        .unwrap()
        .with_filter(Filter::Bilinear);
    let shadings = [
        Shading::Unlit,
        Shading::Flat,
        Shading::Gouraud,
        Shading::Quadratic,
    ];
    let (mut drawn, mut clipped_faces) = (0, 0);
    for (round, case) in unclipped.iter().chain(&clipped).enumerate() {
        let mut scene = Scene::new(&case.pose, LIGHT, 0.15);
        if round % 4 == 3 {
            scene.pipeline.viewport = Rectangle::new(Point::new(-7, 3), Size::new(W + 20, H - 10));
        }
        let shading = shadings[round % 4];
        let stats = match round % 3 {
            0 => paths_round(case, &scene, &pow2, shading, round),
            1 => paths_round(case, &scene, &odd, shading, round),
            _ => paths_round(case, &scene, &rgb565, shading, round),
        };
        drawn += stats.drawn;
        clipped_faces += stats.clipped;
    }
    println!("{drawn} faces drawn, {clipped_faces} clipped");
    assert!(
        drawn > 5_000 && clipped_faces > 300,
        "{drawn} {clipped_faces}"
    );

    let case = &unclipped[12];
    let scene = Scene::new(&case.pose, LIGHT, 0.15);
    let mut frame = Frame::new();
    let mut short = vec![ProjectedVertex::EMPTY; case.mesh.vertices.len() - 1];
    let material = TexturedMaterial::new(&pow2, Shading::Gouraud);
    let got = scene.pipeline.draw_textured_mesh_with(
        &case.mesh.as_mesh(),
        &material,
        &mut frame.target(),
        &mut short,
    );
    assert_eq!(
        got,
        Err(ScratchTooSmall {
            needed: case.mesh.vertices.len(),
            given: case.mesh.vertices.len() - 1
        })
    );
    assert!(frame.z.iter().all(|&d| d == DEPTH_CLEAR), "nothing drawn");
}

/// Every way of drawing a textured mesh lit per pixel (`Shading::Quadratic`, untinted: lit by
/// the quadratic normal field; two rounds in three highlighted per pixel) gives the same frame,
/// bit for bit: `draw_textured_mesh`, `draw_textured_mesh_with` and band rendering (1, 8, 16
/// and 240 rows, with and without a scratch), over the suite's poses (clipped faces drawn as
/// fans), three textures and a viewport partly off the target.
#[test]
fn per_pixel_paths_draw_the_same_pixels() {
    let (unclipped, clipped) = all_cases();
    let coordinates = coordinate_texels();
    let pow2 = Texture::new(Rgb888Texels(&coordinates), TEX, TEX).unwrap();
    let solid = Texture::new(Solid(Rgb888::new(200, 150, 90)), 1, 1).unwrap();
    let words: Vec<u16> = (0..64 * 32)
        .map(|k| (k as u16).wrapping_mul(40_503))
        .collect();
    let rgb565 = Texture::new(Rgb565Texels(&words), 64, 32)
        .unwrap()
        .with_filter(Filter::Bilinear);
    let (mut drawn, mut clipped_faces) = (0, 0);
    for (k, case) in unclipped.iter().chain(&clipped).enumerate() {
        let mut scene = Scene::new(&case.pose, LIGHT, 0.15);
        // Every third case with more lights: a directional one and a point light near the
        // mesh (its direction and falloff per face).
        if k % 3 == 2 {
            let set = Lights::new()
                .with(LightSource::directional(
                    Vec3::new(fx(-0.5), fx(0.3), fx(0.8)),
                    fx(0.4),
                ))
                .with(LightSource::point(
                    Vec3::new(fx(0.5), fx(1.0), fx(-3.0)),
                    fx(0.8),
                    fx(6.0),
                ));
            scene.pipeline = scene.pipeline.with_lights(set);
        }
        if k % 4 == 3 {
            scene.pipeline.viewport = Rectangle::new(Point::new(-7, 3), Size::new(W + 20, H - 10));
        }
        // Even rounds: untinted; highlighted unless a multiple of 3.
        let round = 2 * k;
        let stats = match k % 3 {
            0 => paths_round(case, &scene, &pow2, Shading::Quadratic, round),
            1 => paths_round(case, &scene, &solid, Shading::Quadratic, round),
            _ => paths_round(case, &scene, &rgb565, Shading::Quadratic, round),
        };
        drawn += stats.drawn;
        clipped_faces += stats.clipped;
    }
    println!("{drawn} faces drawn, {clipped_faces} clipped");
    assert!(
        drawn > 5_000 && clipped_faces > 300,
        "{drawn} {clipped_faces}"
    );
}

// ---------------------------------------------------------------------------------------------
// Robustness
// ---------------------------------------------------------------------------------------------

/// A raw coordinate: the `I16F16` extremes, zero, small and random values.
fn pick(rng: &mut Rng) -> i32 {
    match rng.next() % 7 {
        0 => i32::MIN,
        1 => i32::MAX,
        2 => 0,
        3 => (rng.next() as i32) >> (rng.next() % 31),
        4 => ((rng.next() % 200_000) as i32) - 100_000,
        5 => 65_536 * ((rng.next() % 5) as i32 - 2),
        _ => rng.next() as i32,
    }
}

/// A texture whose every texel has its own colour (`(a, b, c)` from the index), `width ×
/// height`.
fn distinct_texels(width: u32, height: u32) -> Vec<u8> {
    (0..width * height)
        .flat_map(|k| {
            [
                (k % 251) as u8,
                (k / 251 % 251) as u8,
                (k / 63_001 % 251) as u8 | 1,
            ]
        })
        .collect()
}

/// Odd inputs (run in the test profile, whose overflow checks are on): meshes without texture
/// coordinates, with degenerate faces (repeated and collinear vertices, indices out of range),
/// texture coordinates at the `I16F16` extremes, garbage normals; textures of 1 × 1, 1 × n,
/// n × 1 and other sizes that are not powers of two, every wrap mode and filter; poses around
/// and inside the meshes, extreme vertices: no panic, and the textured draw writes exactly the
/// pixels the untextured draw of the same mesh writes (`draw_mesh`, unlit), each — unlit and
/// nearest — a texel of the texture, and texel `(0, 0)` for a mesh without texture
/// coordinates (documented).
#[test]
fn odd_inputs_stay_inside_the_untextured_coverage() {
    let mut rng = Rng(0x7e47_3d03);
    let sizes = [
        (1, 1),
        (1, 9),
        (7, 1),
        (3, 5),
        (33, 17),
        (256, 256),
        (1000, 2),
    ];
    let wraps = [Wrap::Repeat, Wrap::MirroredRepeat, Wrap::Clamp];
    let textures: Vec<(u32, u32, Vec<u8>)> = sizes
        .iter()
        .map(|&(w, h)| (w, h, distinct_texels(w, h)))
        .collect();
    let sphere = icosphere(1.0, 1);
    let (mut written, mut rounds_drawn, mut no_uv_pixels) = (0u64, 0u32, 0u64);
    for round in 0..600 {
        // The mesh: a small icosphere or random garbage.
        let mut mesh = if round % 2 == 0 {
            let mut m = sphere.clone();
            // Degenerate faces: a repeated vertex, a collinear triple, indices out of range.
            let n = m.vertices.len() as u16;
            m.indices.push([0, 0, 1]);
            m.indices.push([n, 1, 2]);
            m.indices.push([3, u16::MAX, 4]);
            let (a, b) = (m.vertices[5], m.vertices[6]);
            m.vertices.push(Vec3::from_bits(
                a.to_bits()[0] / 2 + b.to_bits()[0] / 2,
                a.to_bits()[1] / 2 + b.to_bits()[1] / 2,
                a.to_bits()[2] / 2 + b.to_bits()[2] / 2,
            ));
            m.normals.push(Vec3::ZERO);
            m.indices.push([5, n, 6]);
            m
        } else {
            let count = 3 + rng.below(8) as usize;
            let mut m = MeshData {
                vertices: (0..count)
                    .map(|_| match rng.below(3) {
                        0 => Vec3::from_bits(pick(&mut rng), pick(&mut rng), pick(&mut rng)),
                        _ => Vec3::new(
                            fx(rng.range_f64(-2.0, 2.0)),
                            fx(rng.range_f64(-2.0, 2.0)),
                            fx(rng.range_f64(-2.0, 2.0)),
                        ),
                    })
                    .collect(),
                ..MeshData::default()
            };
            m.indices = (0..6)
                .map(|_| [0; 3].map(|_| rng.below(count as u64 + 2) as u16))
                .collect();
            if rng.chance(2) {
                m.normals = (0..count)
                    .map(|_| Vec3::from_bits(pick(&mut rng), pick(&mut rng), pick(&mut rng)))
                    .collect();
            }
            m
        };
        // Texture coordinates: none, ordinary, or anything at all.
        let uv_kind = round / 2 % 3;
        mesh.uvs = match uv_kind {
            0 => Vec::new(),
            1 => (0..mesh.vertices.len())
                .map(|_| uv(rng.range_f64(-3.0, 3.0), rng.range_f64(-3.0, 3.0)))
                .collect(),
            _ => (0..mesh.vertices.len())
                .map(|_| TexCoord::from_bits(pick(&mut rng), pick(&mut rng)))
                .collect(),
        };
        let pose = Pose {
            fov: [40, 70, 100][round % 3],
            near: [0.1, 0.3, 1.0][round / 3 % 3],
            far: 20.0,
            yaw: rng.any_angle(),
            pitch: rng.any_angle(),
            position: [
                rng.range_f64(-2.0, 2.0),
                rng.range_f64(-2.0, 2.0),
                rng.range_f64(-5.0, 1.0),
            ],
            cull: [Cull::None, Cull::Back, Cull::Front][round / 9 % 3],
        };
        let light = [
            rng.range_f64(-1.0, 1.0),
            rng.range_f64(-1.0, 1.0),
            rng.range_f64(-1.0, 1.0),
        ];
        let mut scene = Scene::new(&pose, light, rng.range_f64(-0.5, 1.5));
        if round % 5 == 4 {
            scene.pipeline.viewport = Rectangle::new(
                Point::new(rng.range(-100, 100) as i32, rng.range(-100, 100) as i32),
                Size::new(rng.below(300) as u32, rng.below(300) as u32),
            );
        }
        let (w, h, bytes) = &textures[round % textures.len()];
        let filter = if round % 4 == 1 {
            Filter::Bilinear
        } else {
            Filter::Nearest
        };
        let texture = Texture::new(Rgb888Texels(bytes), *w, *h)
            .unwrap()
            .with_wrap(wraps[round % 3], wraps[round / 3 % 3])
            .with_filter(filter);
        let texel_set: std::collections::HashSet<[u8; 3]> =
            bytes.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
        let first = Rgb888::new(bytes[0], bytes[1], bytes[2]);
        let m = mesh.as_mesh();
        let coverage = untextured(&scene.pipeline, &m, Rgb888::WHITE, Shading::Unlit).written_set();
        for shading in [
            Shading::Unlit,
            Shading::Flat,
            Shading::Gouraud,
            Shading::Quadratic,
        ] {
            let (frame, stats) = textured(&scene.pipeline, &m, &texture, shading);
            let mut scratch = vec![ProjectedVertex::EMPTY; mesh.vertices.len()];
            let mut again = Frame::new();
            let material = TexturedMaterial::new(&texture, shading);
            let with = scene
                .pipeline
                .draw_textured_mesh_with(&m, &material, &mut again.target(), &mut scratch)
                .unwrap();
            assert!(
                stats == with && frame == again,
                "round {round}: scratch draw differs"
            );
            let at = (0..N).find(|&i| frame.written(i) != coverage[i]);
            assert!(
                at.is_none(),
                "round {round} ({shading:?}): pixel {:?} written {} by the textured draw, {} by \
                 the untextured one; mesh {mesh:?}, pose {pose:?}",
                at.map(|i| (i as u32 % W, i as u32 / W)),
                at.is_some_and(|i| frame.written(i)),
                at.is_some_and(|i| coverage[i]),
            );
            if shading == Shading::Unlit && filter == Filter::Nearest {
                for i in (0..N).filter(|&i| frame.written(i)) {
                    let c = frame.px[i];
                    assert!(
                        texel_set.contains(&[c.r(), c.g(), c.b()]),
                        "round {round}: {c:?}"
                    );
                    if mesh.uvs.is_empty() {
                        assert_eq!(c, first, "round {round}: no texture coordinates");
                        no_uv_pixels += 1;
                    }
                }
            }
            written += coverage.iter().filter(|&&c| c).count() as u64;
            rounds_drawn += u32::from(stats.drawn > 0);
        }
    }
    println!("{rounds_drawn} draws with faces, {written} pixels, {no_uv_pixels} without uvs");
    assert!(rounds_drawn > 800 && written > 1_000_000 && no_uv_pixels > 20_000);
}
