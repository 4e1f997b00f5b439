//! Several lights (`Pipeline::with_lights`: directional and point lights with the windowed
//! falloff) against the f64 light model (`reference::lights`):
//!
//! * the falloff `(1 − d²/r²)²` of `LightSource::falloff` over distances and ranges, and the
//!   point light's direction `normalize(P − X)` (`normalize_wide`: the table-and-Newton inverse
//!   square root) over random and extreme vectors;
//! * a lit icosphere, each face drawn alone and every pixel it covers checked: Gouraud (the f64
//!   levels and highlights at the vertices interpolated by the exact screen barycentrics) and
//!   flat (the face's at its centroid), with and without a highlight, for a rotation and a
//!   non-uniform scale;
//! * `draw_mesh`, `draw_mesh_with` and band rendering drawing the same pixels and depths;
//! * extreme inputs: a light at a vertex, huge ranges and positions, intensity 0 (the frame
//!   without it), full sets.

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::band::BandLayout;
use embedded_raster::reference::{self, lights as model};
use embedded_raster::texture::{Solid, Texture};
use embedded_raster::three_d::meshes::{self, icosphere::ICOSPHERE, torus::TORUS, MeshData};
use embedded_raster::three_d::{
    normalize_wide, Angle, Cull, DepthTarget, Light, LightSource, Lights, Mat4, Material, Mesh,
    Pipeline, ProjectedVertex, Scalar, Shading, Specular, TexturedMaterial, Vec3, DEPTH_CLEAR,
};
use embedded_raster::GouraudColor;

use crate::vec_f64;
use vec_f64::{dot, normalize};

use crate::banded;
use banded::banded;

use crate::rng;
use rng::Rng;

/// `LightSource::falloff` against `(1 − d²/r²)²` in f64 for ranges from 1/16 to 30000 and
/// squared distances across them: within its stated 2⁻¹⁶.
#[test]
fn falloff_is_within_its_bound() {
    let mut rng = Rng(0x11_9470);
    let mut worst = 0.0f64;
    for _ in 0..20000 {
        let r = 2f64.powf(rng.range_f64(-4.0, 14.87));
        let light = LightSource::point(Vec3::ZERO, Scalar::ONE, Scalar::from_num(r));
        let r = light.range().to_num::<f64>();
        let d2 = Scalar::from_num((r * r * rng.range_f64(0.0, 1.2)).min(32767.0));
        let got = light.falloff(d2).to_num::<f64>();
        let d2 = d2.to_num::<f64>();
        let want = model::falloff(d2.sqrt(), r);
        let err = (got - want).abs();
        worst = worst.max(err);
        assert!(err <= 1.0 / 65536.0, "r {r}, d² {d2}: {got} vs {want}");
    }
    println!(
        "falloff: worst |error| {worst:.2e} (bound {:.2e})",
        1.0 / 65536.0
    );
    let light = LightSource::point(Vec3::ZERO, Scalar::ONE, Scalar::from_num(2));
    assert_eq!(light.falloff(Scalar::ZERO), Scalar::ONE);
    assert_eq!(light.falloff(Scalar::from_num(4)), Scalar::ZERO);
    assert_eq!(light.falloff(Scalar::from_num(-3)), Scalar::ONE);
    assert_eq!(light.falloff(Scalar::MAX), Scalar::ZERO);
    let none = LightSource::point(Vec3::ZERO, Scalar::ONE, Scalar::ZERO);
    assert_eq!(none.falloff(Scalar::ZERO), Scalar::ZERO);
    let huge = LightSource::point(Vec3::ZERO, Scalar::ONE, Scalar::MAX);
    assert_eq!(huge.falloff(Scalar::from_num(100)), Scalar::ONE);
}

/// The direction towards a point light, `normalize(P − X)` of raw `I16F16` differences up to
/// ±2³¹ (the saturated range), without floats: within 2⁻¹⁶·1.5 a component of the f64 unit
/// vector, for random vectors of every magnitude and the extreme ones.
#[test]
fn point_directions_are_unit_within_bound() {
    let mut rng = Rng(0x11_9471);
    let mut worst = 0.0f64;
    let mut check = |d: [i64; 3]| {
        let got = meshes::to_f64(normalize_wide(d));
        let want = normalize(d.map(|c| c as f64));
        for k in 0..3 {
            let err = (got[k] - want[k]).abs();
            worst = worst.max(err);
            assert!(err <= 1.5 / 65536.0, "{d:?}: {got:?} vs {want:?}");
        }
    };
    for _ in 0..200000 {
        let bits = rng.below(32) as u32;
        let c = |r: &mut Rng| r.range(-(1i64 << bits), 1i64 << bits);
        let d = [c(&mut rng), c(&mut rng), c(&mut rng)];
        if d != [0; 3] {
            check(d);
        }
    }
    let m = i64::from(i32::MAX);
    for d in [
        [1, 0, 0],
        [0, -1, 0],
        [m, m, m],
        [-m - 1, -m - 1, -m - 1],
        [m, 1, 0],
        [1, 1, 1],
        [-m - 1, m, 3],
    ] {
        check(d);
    }
    assert_eq!(normalize_wide([0; 3]), Vec3::ZERO);
    println!("direction: worst component error {:.2e}", worst);
}

const W: u32 = 160;
const H: u32 = 120;

/// The fixed-point scene and its f64 model.
struct Scene {
    pipeline: Pipeline,
    model: model::Scene,
}

/// The lights of the sphere tests: the first light, a directional light and two point lights
/// near the sphere (one reaching only part of it).
fn lights() -> (Light, Lights, Vec<model::Source>) {
    let light = Light::new(Vec3::new(-0.6, 0.9, 0.7), Scalar::from_num(0.1));
    let sources = [
        LightSource::point(
            Vec3::new(1.3, 0.6, 1.4),
            Scalar::from_num(0.9),
            Scalar::from_num(3.2),
        ),
        LightSource::point(
            Vec3::new(-1.2, -0.9, 0.8),
            Scalar::from_num(1.3),
            Scalar::from_num(1.9),
        ),
        LightSource::directional(Vec3::new(0.3, -1.0, 0.2), Scalar::from_num(0.35)),
    ];
    let mut set = Lights::new();
    let mut f64_sources = Vec::new();
    for s in sources {
        set.push(s).unwrap();
        f64_sources.push(to_model(&s));
    }
    (light, set, f64_sources)
}

/// The f64 source of a source (its stored, rounded values).
fn to_model(s: &LightSource) -> model::Source {
    let intensity = s.intensity().to_num::<f64>();
    match (s.direction(), s.position()) {
        (Some(d), _) => model::Source::Directional {
            direction: meshes::to_f64(d),
            intensity,
        },
        (_, Some(p)) => model::Source::Point {
            position: meshes::to_f64(p),
            intensity,
            range: s.range().to_num::<f64>(),
        },
        _ => unreachable!(),
    }
}

fn scene(model_matrix: Mat4, inverse_transpose: bool, specular: Option<Specular>) -> Scene {
    let eye = [0.7, 0.9, 2.6];
    let view = Mat4::look_at(Vec3::from(eye), Vec3::ZERO, Vec3::new(0, 1, 0)).unwrap();
    let projection =
        Mat4::perspective(Angle::from_degrees(50), W as f64 / H as f64, 0.5, 20.0).unwrap();
    let (light, set, sources) = lights();
    let viewport = Rectangle::new(Point::zero(), Size::new(W, H));
    let pipeline = if inverse_transpose {
        Pipeline::with_inverse_transpose(model_matrix, projection * view, viewport, light).unwrap()
    } else {
        Pipeline::new(model_matrix, projection * view, viewport, light)
    }
    .with_lights(set);
    Scene {
        pipeline,
        model: model::Scene {
            direction: Some(meshes::to_f64(light.direction())),
            ambient: light.ambient().to_num::<f64>(),
            sources,
            eye: normalize(eye),
            specular: specular.map(|s| (s.strength().to_num::<f64>(), f64::from(s.shininess()))),
        },
    }
}

/// A matrix's 3×4 block applied in f64.
fn apply(m: &Mat4, p: [f64; 3], translate: bool) -> [f64; 3] {
    let m = m.to_bits();
    core::array::from_fn(|r| {
        let t = if translate {
            f64::from(m[r][3]) / 65536.0
        } else {
            0.0
        };
        (0..3)
            .map(|c| f64::from(m[r][c]) / 65536.0 * p[c])
            .sum::<f64>()
            + t
    })
}

/// Errors of one sphere drawing against f64.
#[derive(Default, Debug)]
struct Tally {
    pixels: u64,
    /// Faces with a vertex next to a terminator (`|n̂·l̂|` below 10⁻³ for a light reaching
    /// it): not checked.
    skipped: u64,
    /// The largest error on faces a highlight reaches, and on the others.
    worst: f64,
    worst_plain: f64,
    highlighted: u64,
}

/// Draws each face of `mesh` alone and checks every pixel it covers against the f64 model:
/// Gouraud, the f64 level and highlight at the vertices interpolated; flat, at the centroid
/// with the face normal. Tolerance: `plain + highlight·max` per channel, with
/// `highlight = 3·shininess·strength·2⁻¹⁷·(1 + Σ intensities)` (the power's error and the
/// cosines' within 2⁻¹⁶, amplified by the shininess, for each light) on faces a highlight
/// reaches, and `plain = ½ LSB + the 256 levels' ½·base/255 + 0.02` (Gouraud) or `½ LSB + 0.1`
/// (flat) and the levels' fixed-point error.
fn check_sphere<C: GouraudColor>(
    scene: &Scene,
    mesh: &MeshData,
    base: C,
    shading: Shading,
    specular: Option<Specular>,
) -> Tally {
    let mut material = Material::new(base, shading);
    if let Some(s) = specular {
        material = material.with_specular(s);
    }
    let pipeline = &scene.pipeline;
    let max = C::MAX.map(f64::from);
    let base_c = base.channels().map(f64::from);
    let n = (W * H) as usize;
    let (mut px, mut z) = (vec![base; n], vec![0u16; n]);
    let mut tally = Tally::default();
    let intensities: f64 = 1.0
        + pipeline
            .lights
            .sources()
            .iter()
            .map(|s| s.intensity().to_num::<f64>())
            .sum::<f64>();
    let highlight = specular.map_or(0.0, |s| {
        3.0 * f64::from(s.shininess()) * s.strength().to_num::<f64>() * intensities / 131072.0
    });
    // Whether a light reaching `x` grazes the surface there.
    let grazing = |x: [f64; 3], n: [f64; 3]| {
        let n = normalize(n);
        let mut ls: Vec<[f64; 3]> = scene.model.direction.into_iter().collect();
        for s in &scene.model.sources {
            match *s {
                model::Source::Directional { direction, .. } => ls.push(direction),
                model::Source::Point {
                    position, range, ..
                } => {
                    let d = vec_f64::sub(position, x);
                    if dot(d, d).sqrt() < range && dot(d, d) > 0.0 {
                        ls.push(d)
                    }
                }
            }
        }
        ls.iter().any(|&l| dot(n, normalize(l)).abs() < 1e-3)
    };
    for face in &mesh.indices {
        let one = [*face];
        let single = Mesh::new(&mesh.vertices, &mesh.normals, &one);
        let idx = face.map(usize::from);
        let screen = idx.map(|i| pipeline.project(pipeline.clip_position(mesh.vertices[i])));
        let Some(screen) = screen.iter().copied().collect::<Option<Vec<_>>>() else {
            continue;
        };
        let raw = [0, 1, 2].map(|k| (screen[k].x.to_bits(), screen[k].y.to_bits()));
        let mut target = DepthTarget::new(&mut px, &mut z, W, H).unwrap();
        target.clear(C::from_channels([0; 3]));
        let stats = pipeline.draw_mesh(&single, &material, &mut target);
        let mut covered = 0;
        reference::for_each_covered(raw, 0, 0, W as i32, H as i32, |_, _| covered += 1);
        let drawn = target.depth().iter().filter(|&&d| d != DEPTH_CLEAR).count();
        if stats.drawn == 0 {
            assert_eq!(drawn, 0);
            continue;
        }
        assert_eq!(drawn, covered, "face {face:?}: coverage");
        let positions = idx.map(|i| apply(&pipeline.model, meshes::to_f64(mesh.vertices[i]), true));
        let normals = idx.map(|i| {
            normalize(apply(
                &pipeline.normal_matrix,
                meshes::to_f64(mesh.normals[i]),
                false,
            ))
        });
        let model_p = idx.map(|i| meshes::to_f64(mesh.vertices[i]));
        let centroid_model =
            core::array::from_fn(|k| (model_p[0][k] + model_p[1][k] + model_p[2][k]) / 3.0);
        let centroid = apply(&pipeline.model, centroid_model, true);
        let face_n = {
            let (e1, e2) = (
                vec_f64::sub(model_p[1], model_p[0]),
                vec_f64::sub(model_p[2], model_p[0]),
            );
            normalize(apply(
                &pipeline.normal_matrix,
                vec_f64::cross(e1, e2),
                false,
            ))
        };
        let vertex = [0, 1, 2].map(|k| scene.model.terms(positions[k], normals[k]));
        let flat = scene.model.terms(centroid, face_n);
        let grazes = match shading {
            Shading::Flat => grazing(centroid, face_n),
            _ => (0..3).any(|k| grazing(positions[k], normals[k])),
        };
        if grazes {
            tally.skipped += covered as u64;
            continue;
        }
        let reached = match shading {
            Shading::Flat => flat.1 > 1.0 / 16384.0,
            _ => vertex.iter().any(|v| v.1 > 1.0 / 16384.0),
        };
        let tolerance = |ch: usize| match (reached, shading) {
            (true, _) => 0.6 + highlight * max[ch],
            (false, Shading::Flat) => 0.6 + 0.5 * base_c[ch] / 255.0,
            (false, _) => 0.53 + 0.5 * base_c[ch] / 255.0,
        };
        reference::for_each_covered(raw, 0, 0, W as i32, H as i32, |i, j| {
            let c = reference::barycentric(raw, i, j).unwrap();
            let (level, spec) = match shading {
                Shading::Flat => flat,
                _ => (
                    (0..3).map(|m| c[m] * vertex[m].0).sum::<f64>(),
                    (0..3).map(|m| c[m] * vertex[m].1).sum::<f64>(),
                ),
            };
            let got = target.framebuffer().get(i, j).unwrap().channels();
            for ch in 0..C::CHANNELS {
                let want = (base_c[ch] * level + max[ch] * spec).min(max[ch]);
                let err = (f64::from(got[ch]) - want).abs();
                if reached {
                    tally.worst = tally.worst.max(err);
                } else {
                    tally.worst_plain = tally.worst_plain.max(err);
                }
                assert!(
                    err <= tolerance(ch),
                    "{shading:?} face {face:?} pixel {i},{j} channel {ch}: {} vs {want} \
                     (level {level}, specular {spec})",
                    got[ch]
                );
            }
            tally.pixels += 1;
            tally.highlighted += u64::from(spec * max[0] > 1.0);
        });
    }
    tally
}

fn sphere() -> MeshData {
    meshes::icosphere(1.0, 3)
}

/// A rotation and translation (normals as they are, positions moved) and a non-uniform scale
/// (normals through the inverse transpose).
fn poses() -> [(Mat4, bool, &'static str); 2] {
    let rotation = Mat4::translation(Vec3::new(0.1, -0.05, 0.2))
        * Mat4::rotation_y(Angle::from_degrees(25))
        * Mat4::rotation_x(Angle::from_degrees(-15));
    let mut stretch = Mat4::IDENTITY;
    stretch.rows[0][0] = Scalar::from_num(1.15);
    stretch.rows[1][1] = Scalar::from_num(0.85);
    [
        (rotation, false, "rotation"),
        (rotation * stretch, true, "scaled"),
    ]
}

/// Gouraud with several lights, without and with highlights, in Rgb888 and Rgb565.
#[test]
fn gouraud_lights_match_f64() {
    let mesh = sphere();
    for (model_matrix, it, name) in poses() {
        for (specular, base) in [
            (None, Rgb888::new(200, 90, 40)),
            (
                Some(Specular::new(Scalar::from_num(0.7), 24)),
                Rgb888::new(40, 120, 230),
            ),
            (
                Some(Specular::new(Scalar::ONE, 64)),
                Rgb888::new(90, 90, 90),
            ),
        ] {
            let scene = scene(model_matrix, it, specular);
            let t = check_sphere(&scene, &mesh, base, Shading::Gouraud, specular);
            println!("Gouraud {name} {specular:?} Rgb888: {t:?}");
            assert!(t.pixels > 3000, "{t:?}");
            if specular.is_some() {
                assert!(t.highlighted > 100, "{t:?}");
            }
            let base = Rgb565::new(base.r() >> 3, base.g() >> 2, base.b() >> 3);
            let t = check_sphere(&scene, &mesh, base, Shading::Gouraud, specular);
            println!("Gouraud {name} {specular:?} Rgb565: {t:?}");
        }
    }
}

/// Flat with several lights (at each face's centroid), without and with a highlight.
#[test]
fn flat_lights_match_f64() {
    let mesh = sphere();
    for (model_matrix, it, name) in poses() {
        for specular in [None, Some(Specular::new(Scalar::from_num(0.7), 12))] {
            let scene = scene(model_matrix, it, specular);
            let base = Rgb888::new(30, 200, 90);
            let t = check_sphere(&scene, &mesh, base, Shading::Flat, specular);
            println!("Flat {name} {specular:?} Rgb888: {t:?}");
            assert!(t.pixels > 3000, "{t:?}");
        }
    }
}

/// What a per-pixel comparison found: pixels checked and skipped (next to a terminator of a
/// point light, where the centroid's direction and the pixel's light different sides), the
/// largest error (LSB) against the f64 reference with the implementation's centroid
/// approximation (`centroid`) and against the true per-pixel one (`pixel`), the largest
/// difference between the two references, the largest `(error − tight tolerance) / bound` and
/// the largest bound (LSB).
#[derive(Default, Debug)]
struct PixelTally {
    pixels: u64,
    skipped: u64,
    centroid: f64,
    pixel: f64,
    approximation: f64,
    ratio: f64,
    bound: f64,
    /// The largest `ρ/(D − ρ)` (face radius over distance to a point light) of a checked face.
    reach: f64,
}

/// The fixed-point per-pixel cosine's own error (nodes rounded to `I16F16`, the stepped field,
/// the 16-bit normal and `inv_sqrt`): 2⁻¹³, as `tests/all/textured_mesh.rs` bounds it.
const COSINE_ERROR: f64 = 1.0 / 8192.0;

/// The quadratic normal field `Σ Nᵢbᵢ(2bᵢ − 1) + Σ 4N̂ᵢⱼbᵢbⱼ` of unit normals `n` at
/// barycentrics `b`, normalised.
fn quadratic_normal(n: &[[f64; 3]; 3], b: [f64; 3]) -> [f64; 3] {
    let mid = |i: usize, j: usize| normalize([0, 1, 2].map(|c| n[i][c] + n[j][c]));
    let nodes = [n[0], n[1], n[2], mid(0, 1), mid(1, 2), mid(2, 0)];
    let w = [
        b[0] * (2.0 * b[0] - 1.0),
        b[1] * (2.0 * b[1] - 1.0),
        b[2] * (2.0 * b[2] - 1.0),
        4.0 * b[0] * b[1],
        4.0 * b[1] * b[2],
        4.0 * b[2] * b[0],
    ];
    normalize([0, 1, 2].map(|c| (0..6).map(|k| w[k] * nodes[k][c]).sum::<f64>()))
}

/// Draws each face of `mesh` alone with `Shading::Quadratic` (a `Material`, or a
/// `TexturedMaterial` of a `Solid` texture of the same colour when `textured`) and checks every
/// pixel it covers against two f64 per-pixel references, both the quadratic normal field at the
/// pixel centre's barycentrics (screen-space for a material, perspective-correct for a texture,
/// as the fills interpolate), renormalised, with Lambert and Blinn-Phong per light:
///
/// * with each point light's direction and falloff at the face's centroid (the
///   implementation's approximation): within
///   `1 LSB + Σ wᵢ·(base + max·strength·shininess)·2⁻¹³ + max·shininess·2⁻¹⁷·Σ wᵢ`
///   (rounding, the cosines' and the power's own errors; `wᵢ` the
///   lights' weights, the first light's 1), plus `max·2⁻⁷` for a texture (its perspective
///   barycentrics stepped along 16-pixel chords);
/// * with each point light's direction and falloff at the pixel's own surface point (the exact
///   per-pixel light): within that plus the documented bound of the approximation, per point
///   light of intensity `I`, range `r`, at distance `D` from the centroid of a face reaching
///   `ρ` from it (`ε = ρ/(D − ρ)`): `I·(ε + 1.54·ρ/r)` on the level and
///   `I·strength·min(1, shininess·ε/|l̂ + v̂| + 1.54·ρ/r)` on the highlight (`|l̂ + v̂|` at the
///   centroid, less `ε`), times the channel's base and maximum.
///
/// Pixels where a point light's direction at the pixel and at the centroid light different
/// sides of the normal (or graze it) are skipped: the highlight is cut there.
fn check_pixel_lights(
    scene: &Scene,
    mesh: &MeshData,
    base: Rgb888,
    specular: Option<Specular>,
    textured: bool,
) -> PixelTally {
    let pipeline = &scene.pipeline;
    let solid = Texture::new(Solid(base), 1, 1).unwrap();
    let mut material = Material::new(base, Shading::Quadratic);
    let mut texture = TexturedMaterial::new(&solid, Shading::Quadratic);
    if let Some(s) = specular {
        material = material.with_specular(s);
        texture = texture.with_specular(s);
    }
    let (strength, shininess) = specular.map_or((0.0, 0.0), |s| {
        (s.strength().to_num::<f64>(), f64::from(s.shininess()))
    });
    let base_c = base.channels().map(f64::from);
    let max = 255.0;
    let weights: f64 = 1.0
        + scene
            .model
            .sources
            .iter()
            .map(|s| match *s {
                model::Source::Directional { intensity, .. }
                | model::Source::Point { intensity, .. } => intensity,
            })
            .sum::<f64>();
    let tight = |ch: usize| {
        1.0 + weights * (base_c[ch] + max * strength * shininess) * COSINE_ERROR
            + max * shininess * weights / 131072.0
            + if textured { max / 128.0 } else { 0.0 }
    };
    let n = (W * H) as usize;
    let (mut px, mut z) = (vec![base; n], vec![0u16; n]);
    let mut tally = PixelTally::default();
    for face in &mesh.indices {
        let one = [*face];
        let single = Mesh::new(&mesh.vertices, &mesh.normals, &one);
        let idx = face.map(usize::from);
        let clip = idx.map(|i| pipeline.clip_position(mesh.vertices[i]));
        let Some(screen) = clip
            .iter()
            .map(|&c| pipeline.project(c))
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let w = clip.map(|c| c.w.to_num::<f64>());
        let raw = [0, 1, 2].map(|k| (screen[k].x.to_bits(), screen[k].y.to_bits()));
        let mut target = DepthTarget::new(&mut px, &mut z, W, H).unwrap();
        target.clear(Rgb888::BLACK);
        let stats = match textured {
            true => pipeline.draw_textured_mesh(&single, &texture, &mut target),
            false => pipeline.draw_mesh(&single, &material, &mut target),
        };
        if stats.drawn == 0 {
            continue;
        }
        let positions = idx.map(|i| apply(&pipeline.model, meshes::to_f64(mesh.vertices[i]), true));
        let normals = idx.map(|i| {
            normalize(apply(
                &pipeline.normal_matrix,
                meshes::to_f64(mesh.normals[i]),
                false,
            ))
        });
        let model_p = idx.map(|i| meshes::to_f64(mesh.vertices[i]));
        let centroid_model =
            core::array::from_fn(|k| (model_p[0][k] + model_p[1][k] + model_p[2][k]) / 3.0);
        let centroid = apply(&pipeline.model, centroid_model, true);
        let radius = positions
            .iter()
            .map(|&p| dot(vec_f64::sub(p, centroid), vec_f64::sub(p, centroid)).sqrt())
            .fold(0.0, f64::max);
        // The implementation's approximation: each point light as a directional one from the
        // centroid, weighted by its falloff there; and the bound per point light.
        let mut at_centroid = scene.model.clone();
        let mut points = Vec::new();
        let mut level_bound = 0.0;
        let mut highlight_bound = 0.0;
        for s in &mut at_centroid.sources {
            if let model::Source::Point {
                position,
                intensity,
                range,
            } = *s
            {
                let d = vec_f64::sub(position, centroid);
                let distance = dot(d, d).sqrt();
                let a = model::falloff(distance, range);
                *s = model::Source::Directional {
                    direction: if distance > 0.0 { d } else { [0.0, 0.0, 1.0] },
                    intensity: if distance > 0.0 { intensity * a } else { 0.0 },
                };
                if distance <= radius || distance - radius >= range {
                    // Out of reach of the face (or inside it): a bound of its own below.
                    if distance - radius < range {
                        level_bound += intensity;
                        highlight_bound += intensity * strength;
                    }
                    points.push((position, d, f64::INFINITY));
                    continue;
                }
                let eps = radius / (distance - radius);
                let lv = normalize(d);
                let sum = [0, 1, 2].map(|k| lv[k] + scene.model.eye[k]);
                let lv_norm = (dot(sum, sum).sqrt() - eps).max(1e-9);
                let slope = 1.54 * radius / range;
                level_bound += intensity * (eps + slope);
                // A highlight is at most `I·strength` wherever it is.
                highlight_bound +=
                    intensity * strength * (shininess * eps / lv_norm + slope).min(1.0);
                tally.reach = tally.reach.max(eps);
                points.push((position, d, eps));
            }
        }
        let bound = |ch: usize| base_c[ch] * level_bound + max * highlight_bound;
        reference::for_each_covered(raw, 0, 0, W as i32, H as i32, |i, j| {
            let c = reference::barycentric(raw, i, j).unwrap();
            let q = [0, 1, 2].map(|k| c[k] / w[k]);
            let sum = q[0] + q[1] + q[2];
            let lambda = q.map(|v| v / sum);
            let b = if textured { lambda } else { c };
            let normal = quadratic_normal(&normals, b);
            let x = [0, 1, 2].map(|k| (0..3).map(|m| lambda[m] * positions[m][k]).sum::<f64>());
            // A point light's terminator between the pixel and the centroid: skipped.
            let cut = points.iter().any(|&(p, d, _)| {
                let (at_x, at_c) = (dot(normal, vec_f64::sub(p, x)), dot(normal, d));
                at_x * at_c <= 0.0
                    || at_c.abs() < 1e-3 * dot(d, d).sqrt()
                    || at_x.abs() < 1e-3 * dot(vec_f64::sub(p, x), vec_f64::sub(p, x)).sqrt()
            });
            if cut {
                tally.skipped += 1;
                return;
            }
            let color =
                |(level, spec): (f64, f64)| base_c.map(|b| (b * level + max * spec).min(max));
            let want_centroid = color(at_centroid.terms(centroid, normal));
            let want_pixel = color(scene.model.terms(x, normal));
            let got = target
                .framebuffer()
                .get(i, j)
                .unwrap()
                .channels()
                .map(f64::from);
            for ch in 0..3 {
                let e_c = (got[ch] - want_centroid[ch]).abs();
                let e_p = (got[ch] - want_pixel[ch]).abs();
                tally.centroid = tally.centroid.max(e_c);
                tally.pixel = tally.pixel.max(e_p);
                tally.approximation = tally
                    .approximation
                    .max((want_pixel[ch] - want_centroid[ch]).abs());
                tally.bound = tally.bound.max(bound(ch));
                if bound(ch) > 0.0 {
                    tally.ratio = tally.ratio.max((e_p - tight(ch)) / bound(ch));
                }
                assert!(
                    e_c <= tight(ch),
                    "face {face:?} pixel {i},{j} channel {ch}: {} vs {} with the centroid's \
                     lights (tolerance {})",
                    got[ch],
                    want_centroid[ch],
                    tight(ch)
                );
                assert!(
                    e_p <= tight(ch) + bound(ch),
                    "face {face:?} pixel {i},{j} channel {ch}: {} vs {} per pixel \
                     (tolerance {} + bound {})",
                    got[ch],
                    want_pixel[ch],
                    tight(ch),
                    bound(ch)
                );
            }
            tally.pixels += 1;
        });
    }
    tally
}

/// Per-pixel shading with the lights (`Shading::Quadratic`, a `Material` and a
/// `TexturedMaterial`): lit per pixel by every light, point lights with their direction and
/// falloff at each face's centroid. Checked against the f64 per-pixel references of
/// `check_pixel_lights` (the same centroid approximation: within the arithmetic's tolerance;
/// the exact per-pixel light: within the approximation's documented bound), on the sphere
/// tests' lights and on point lights close to the surface of a coarser sphere (faces large
/// beside their distance to the light), with and without a highlight.
#[test]
fn quadratic_lights_are_lit_per_pixel() {
    let near = [
        LightSource::point(
            Vec3::new(0.9, 0.5, 1.0),
            Scalar::from_num(0.8),
            Scalar::from_num(1.6),
        ),
        LightSource::point(
            Vec3::new(-1.0, -0.2, 0.7),
            Scalar::from_num(1.2),
            Scalar::from_num(1.2),
        ),
        LightSource::directional(Vec3::new(0.3, -1.0, 0.2), Scalar::from_num(0.35)),
    ];
    let cases = [
        ("sphere lights", sphere(), None),
        ("near lights", meshes::icosphere(1.0, 2), Some(near)),
    ];
    for (name, mesh, sources) in &cases {
        for (model_matrix, it, pose) in poses() {
            for specular in [None, Some(Specular::new(Scalar::from_num(0.6), 24))] {
                let mut scene = scene(model_matrix, it, specular);
                if let Some(sources) = sources {
                    scene.pipeline.lights = Lights::new();
                    scene.model.sources.clear();
                    for s in sources {
                        scene.pipeline.lights.push(*s).unwrap();
                        scene.model.sources.push(to_model(s));
                    }
                }
                for textured in [false, true] {
                    let base = Rgb888::new(200, 120, 60);
                    let t = check_pixel_lights(&scene, mesh, base, specular, textured);
                    println!("quadratic {name} {pose} {specular:?} textured {textured}: {t:?}");
                    assert!(t.pixels > 3000, "{t:?}");
                    // The approximation shows (the two references differ), well within its
                    // bound.
                    assert!(t.approximation > 5.0 && t.ratio < 0.5, "{t:?}");
                }
            }
        }
    }
}

/// The per-pixel fill with the lights is not the Gouraud frame it used to fall back to, nor
/// the frame without them.
#[test]
fn quadratic_with_lights_is_lit_per_pixel() {
    let mesh = sphere();
    let specular = Specular::new(Scalar::from_num(0.5), 20);
    let scene = scene(poses()[0].0, false, Some(specular));
    let draw = |pipeline: &Pipeline, shading| {
        let n = (W * H) as usize;
        let (mut colors, mut depth) = (vec![Rgb565::BLACK; n], vec![0u16; n]);
        let mut target = DepthTarget::new(&mut colors, &mut depth, W, H).unwrap();
        target.clear(Rgb565::BLACK);
        let material = Material::new(Rgb565::new(20, 40, 10), shading).with_specular(specular);
        pipeline.draw_mesh(&mesh.as_mesh(), &material, &mut target);
        (colors, depth)
    };
    let lit = draw(&scene.pipeline, Shading::Quadratic);
    assert!(lit != draw(&scene.pipeline, Shading::Gouraud));
    let mut plain = scene.pipeline;
    plain.lights = Lights::new();
    let unlit = draw(&plain, Shading::Quadratic);
    assert!(lit != unlit);
    // A point light that reaches no face's centroid: each face filled as without it.
    let mut far = plain;
    far.lights = Lights::new().with(LightSource::point(
        Vec3::new(0, 0, 3),
        Scalar::ONE,
        Scalar::from_num(1.5),
    ));
    assert!(draw(&far, Shading::Quadratic) == unlit);
}

/// Every path draws the same pixels and depths with the lights: `draw_mesh`,
/// `draw_mesh_with` and the bands (no bin, no scratch; scratch; bin) at several band heights,
/// for each shading with and without a highlight, with faces clipped at the near plane, a mesh
/// without normals and point lights moving through the meshes.
#[test]
fn every_path_draws_the_same_lights() {
    let mut rng = Rng(0x11_9472);
    let mut bare = meshes::icosphere(0.8, 1);
    bare.normals.clear();
    let (size, viewport) = (
        Size::new(61, 47),
        Rectangle::new(Point::new(-4, 3), Size::new(70, 50)),
    );
    let mut clipped = 0;
    for round in 0..12 {
        let shading = [Shading::Flat, Shading::Gouraud, Shading::Quadratic][round % 3];
        let projection = Mat4::perspective(Angle::from_degrees(70), 1.4, 0.5, 12.0).unwrap();
        let distance = 1 + rng.below(3) as i32;
        let view = Mat4::translation(Vec3::from_bits(0, 0, -(distance << 16) - (1 << 15)));
        let model =
            Mat4::rotation_x(Angle(rng.next() as u16)) * Mat4::rotation_y(Angle(rng.next() as u16));
        let light = Light::new(Vec3::new(-0.4, 0.6, 0.9), Scalar::from_num(0.15));
        let mut point = || {
            let p = [0; 3].map(|_| rng.range_f64(-1.5, 1.5));
            LightSource::point(
                Vec3::from(p),
                Scalar::from_num(rng.range_f64(0.2, 2.0)),
                Scalar::from_num(rng.range_f64(0.5, 4.0)),
            )
        };
        let lights = Lights::new()
            .with(point())
            .with(point())
            .with(LightSource::directional(
                Vec3::new(1, -1, 0.5),
                Scalar::from_num(0.3),
            ));
        let mut pipeline =
            Pipeline::new(model, projection * view, viewport, light).with_lights(lights);
        pipeline.cull = [Cull::Back, Cull::None, Cull::Front][round / 4 % 3];
        let specular = Specular::new(
            Scalar::from_num(rng.range_f64(0.3, 1.0)),
            rng.below(80) as u8 + 1,
        );
        let color = |r: &mut Rng| Rgb888::new(r.next() as u8, r.next() as u8, r.next() as u8);
        let shiny = round % 2 == 0;
        let material = |r: &mut Rng| {
            let m = Material::new(color(r), shading);
            if shiny {
                m.with_specular(specular)
            } else {
                m
            }
        };
        let meshes = [
            (TORUS, material(&mut rng)),
            (ICOSPHERE, material(&mut rng)),
            (bare.as_mesh(), material(&mut rng)),
        ];
        let whole = |with_scratch: bool| {
            let n = (size.width * size.height) as usize;
            let (mut colors, mut depth) = (vec![Rgb888::BLACK; n], vec![0u16; n]);
            let mut target =
                DepthTarget::new(&mut colors, &mut depth, size.width, size.height).unwrap();
            target.clear(Rgb888::new(3, 60, 90));
            let mut clipped = 0;
            for (mesh, material) in &meshes {
                let stats = if with_scratch {
                    let mut scratch = vec![ProjectedVertex::EMPTY; mesh.vertices.len()];
                    pipeline
                        .draw_mesh_with(mesh, material, &mut target, &mut scratch)
                        .unwrap()
                } else {
                    pipeline.draw_mesh(mesh, material, &mut target)
                };
                clipped += stats.clipped;
            }
            (colors, depth, clipped)
        };
        let (want_colors, want_depth, c) = whole(true);
        clipped += c;
        let (colors, depth, _) = whole(false);
        assert!(
            colors == want_colors && depth == want_depth,
            "round {round}: draw_mesh"
        );
        // The lights are there: not the frame without them.
        let mut plain = pipeline;
        plain.lights = Lights::new();
        {
            let n = (size.width * size.height) as usize;
            let (mut colors, mut depth) = (vec![Rgb888::BLACK; n], vec![0u16; n]);
            let mut target =
                DepthTarget::new(&mut colors, &mut depth, size.width, size.height).unwrap();
            target.clear(Rgb888::new(3, 60, 90));
            for (mesh, material) in &meshes {
                plain.draw_mesh(mesh, material, &mut target);
            }
            assert!(colors != want_colors, "round {round}: no light");
        }
        for rows in [1, 5, 16, 47] {
            let layout = BandLayout::new(size, rows).unwrap();
            for mode in 0..3 {
                let (colors, depth) = banded(&layout, &pipeline, &meshes, mode);
                assert!(
                    colors == want_colors && depth == want_depth,
                    "round {round}, {shading:?}, mode {mode}, {rows}-row bands"
                );
            }
        }
    }
    assert!(clipped > 10, "{clipped} faces clipped");
}

/// Draws `mesh` with `material` through `pipeline` into a fresh `W × H` target.
fn frame(pipeline: &Pipeline, mesh: &Mesh<'_>, material: &Material<Rgb888>) -> Vec<Rgb888> {
    let n = (W * H) as usize;
    let (mut colors, mut depth) = (vec![Rgb888::BLACK; n], vec![0u16; n]);
    let mut target = DepthTarget::new(&mut colors, &mut depth, W, H).unwrap();
    target.clear(Rgb888::BLACK);
    let mut scratch = vec![ProjectedVertex::EMPTY; mesh.vertices.len()];
    pipeline
        .draw_mesh_with(mesh, material, &mut target, &mut scratch)
        .unwrap();
    colors
}

/// Extreme inputs: sources of intensity 0 or range 0 (the frame without them, bit for bit), a
/// full set, a point light exactly at a vertex (that vertex gets nothing from it, as in the
/// f64 model, checked by the sphere test's machinery), huge ranges and positions at the ends
/// of `I16F16` (no panic, the same frame twice, a huge range lighting like a directional
/// light without falloff to within the f64 model's tolerance).
#[test]
fn extreme_lights() {
    let mesh = sphere();
    let specular = Specular::new(Scalar::from_num(0.8), 30);
    let base = scene(poses()[0].0, false, Some(specular));
    let plain = {
        let mut p = base.pipeline;
        p.lights = Lights::new();
        p
    };
    for shading in [Shading::Flat, Shading::Gouraud, Shading::Quadratic] {
        let material = Material::new(Rgb888::new(200, 100, 50), shading).with_specular(specular);
        let want = frame(&plain, &mesh.as_mesh(), &material);
        let off = Lights::new()
            .with(LightSource::point(
                Vec3::new(0, 0, 1.2),
                Scalar::ZERO,
                Scalar::from_num(9),
            ))
            .with(LightSource::point(
                Vec3::new(0, 0, 1.2),
                Scalar::ONE,
                Scalar::ZERO,
            ))
            .with(LightSource::directional(Vec3::ZERO, Scalar::ONE));
        assert!(
            frame(&plain.with_lights(off), &mesh.as_mesh(), &material) == want,
            "{shading:?}"
        );
    }
    // A full set.
    let mut full = Lights::new();
    for _ in 0..Lights::MAX {
        full.push(LightSource::directional(Vec3::new(0, 1, 0), Scalar::ONE))
            .unwrap();
    }
    let extra = LightSource::directional(Vec3::new(1, 0, 0), Scalar::ONE);
    assert_eq!(full.push(extra), Err(extra));
    assert_eq!(full.with(extra), full);
    assert_eq!(full.sources().len(), Lights::MAX);
    assert_eq!(Lights::default().sources().len(), 0);
    // Clamped inputs.
    let s = LightSource::point(Vec3::ZERO, Scalar::from_num(100), Scalar::from_num(-3));
    assert_eq!(
        (s.intensity(), s.range()),
        (Scalar::from_num(4), Scalar::ZERO)
    );

    // A point light exactly at a vertex (of a torus's inner side, which it lights; identity
    // model: world = model space), and lights at the ends of the range.
    let torus = meshes::torus(0.8, 0.35, 24, 12);
    let inner = torus
        .vertices
        .iter()
        .min_by_key(|v| {
            let [x, y, z] = v.to_bits().map(|c| i64::from(c).pow(2));
            (x + y + z, v.to_bits())
        })
        .copied()
        .unwrap();
    let huge = Scalar::MAX;
    let far = Vec3::from_bits(i32::MAX, i32::MIN, i32::MAX);
    let cases = [
        (
            "at a vertex",
            &torus,
            LightSource::point(inner, Scalar::ONE, Scalar::from_num(1.5)),
        ),
        (
            "huge range",
            &mesh,
            LightSource::point(Vec3::new(0.5, 2, 2), Scalar::ONE, huge),
        ),
        (
            "far away, huge range",
            &mesh,
            LightSource::point(Vec3::new(0.5, 2, 20000), Scalar::from_num(4), huge),
        ),
        (
            "at the corner, huge range",
            &mesh,
            LightSource::point(far, Scalar::from_num(4), huge),
        ),
        (
            "at the corner",
            &mesh,
            LightSource::point(far, Scalar::from_num(4), Scalar::from_num(3)),
        ),
    ];
    for (name, mesh, source) in cases {
        let mut s = scene(Mat4::IDENTITY, false, Some(specular));
        s.pipeline.lights = Lights::new().with(source);
        s.model.sources = vec![to_model(&source)];
        s.model.direction = Some([0.0, 0.0, 0.0]).filter(|_| false);
        s.pipeline.light = Light::new(Vec3::ZERO, Scalar::from_num(0.1));
        for shading in [Shading::Gouraud, Shading::Flat] {
            let t = check_sphere(&s, mesh, Rgb888::new(120, 140, 60), shading, Some(specular));
            println!("{name} {shading:?}: {t:?}");
            assert!(t.pixels > 1000, "{t:?}");
        }
        let material = Material::new(Rgb888::new(120, 140, 60), Shading::Quadratic);
        let a = frame(&s.pipeline, &mesh.as_mesh(), &material);
        assert!(
            a == frame(&s.pipeline, &mesh.as_mesh(), &material),
            "{name}"
        );
        // Lit by it (the corner is out of reach: only the ambient term).
        let mut dark = s.pipeline;
        dark.lights = Lights::new();
        let lit = a != frame(&dark, &mesh.as_mesh(), &material);
        assert_eq!(lit, !name.starts_with("at the corner"), "{name}");
    }
    // The model matrix at the ends of the range too: saturating, no panic.
    let mut s = scene(Mat4::IDENTITY, false, None);
    s.pipeline.model = Mat4::from_bits([[i32::MAX; 4], [i32::MIN; 4], [i32::MAX; 4], [0; 4]]);
    s.pipeline.lights = Lights::new().with(LightSource::point(far, Scalar::ONE, huge));
    let material = Material::new(Rgb888::new(120, 140, 60), Shading::Gouraud);
    let _ = frame(&s.pipeline, &mesh.as_mesh(), &material);
}
