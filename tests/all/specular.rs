//! Blinn-Phong specular highlights (`Material::with_specular`) against the f64 reference
//! (`reference::texture::{lambert, blinn_phong}`):
//!
//! * the fixed-point power `strength · x^shininess` over every 16-bit cosine and every
//!   shininess, within its stated bound `shininess · 2⁻¹⁷`;
//! * a lit icosphere, each face drawn alone so that every pixel it covers is checked: Gouraud
//!   (the f64 light and specular levels at the vertices interpolated by the exact screen
//!   barycentrics), per pixel (`Shading::Quadratic`: the f64 light and highlight of the f64
//!   quadratic normal field at the pixel centre) and flat (the face normal's), in `Rgb888` and
//!   `Rgb565`, for a rotation (the model-space vertex path) and a non-uniform scale (normals
//!   transformed per vertex);
//! * `draw_mesh`, `draw_mesh_with` and band rendering (no bin, no scratch; scratch; `MeshBin`)
//!   drawing the same pixels and depths, with clipped faces and meshes without normals;
//! * materials without a highlight (or of strength 0) drawing the frames they drew before.

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::band::BandLayout;
use embedded_raster::reference::{self, texture};
use embedded_raster::three_d::meshes::{self, icosphere::ICOSPHERE, torus::TORUS, MeshData};
use embedded_raster::three_d::{
    Angle, Cull, DepthTarget, Light, Mat4, Material, Mesh, Pipeline, ProjectedVertex, Scalar,
    Shading, Specular, Vec3, DEPTH_CLEAR,
};
use embedded_raster::GouraudColor;

use crate::vec_f64;
use vec_f64::{dot, normalize};

use crate::banded;
use banded::banded;

use crate::rng;
use rng::Rng;

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    a.map(|c| c * s)
}

/// The power alone: `Specular::term` of every cosine `k/2¹⁶` for every shininess, against
/// `strength · x^n` in f64, within the documented `n·2⁻¹⁷`.
#[test]
fn power_is_within_its_bound_for_every_input() {
    for strength in [1.0, 0.75, 0.3] {
        let mut worst = 0.0f64;
        let mut worst_ratio = 0.0f64;
        for n in 0..=255u8 {
            let s = Specular::new(Scalar::from_num(strength), n);
            let strength = s.strength().to_num::<f64>();
            let bound = f64::from(n) / 131072.0;
            for raw in 0..=65536i32 {
                let x = f64::from(raw) / 65536.0;
                let got = s.term(Scalar::from_bits(raw)).to_num::<f64>();
                let want = strength * x.powi(i32::from(n));
                let err = (got - want).abs();
                assert!(
                    err <= bound + 1e-12,
                    "strength {strength}, n {n}, x {x}: {got} vs {want}"
                );
                worst = worst.max(err);
                if n > 0 {
                    worst_ratio = worst_ratio.max(err / bound);
                }
            }
        }
        println!(
            "strength {strength}: worst |error| {:.2e} = {:.3} LSB of 255; at most {:.2} of the bound",
            worst,
            worst * 255.0,
            worst_ratio
        );
    }
    // Outside [0, 1]: clamped.
    let s = Specular::new(Scalar::from_num(2), 7);
    assert_eq!(s.strength(), Scalar::ONE);
    assert_eq!(s.term(Scalar::from_num(-0.5)), Scalar::ZERO);
    assert_eq!(s.term(Scalar::from_num(1.5)), Scalar::ONE);
    assert_eq!(
        Specular::new(Scalar::ONE, 0).term(Scalar::ZERO),
        Scalar::ONE
    );
}

/// A camera, a light and a model for the sphere tests, with their f64 counterparts.
struct Scene {
    pipeline: Pipeline,
    /// The light direction and the direction towards the (infinite) viewer, world space.
    light: [f64; 3],
    eye: [f64; 3],
    ambient: f64,
}

const W: u32 = 160;
const H: u32 = 120;

fn scene(model: Mat4, inverse_transpose: bool) -> Scene {
    let eye = [0.7, 0.9, 2.6];
    let view = Mat4::look_at(Vec3::from(eye), Vec3::ZERO, Vec3::new(0, 1, 0)).unwrap();
    let projection =
        Mat4::perspective(Angle::from_degrees(50), W as f64 / H as f64, 0.5, 20.0).unwrap();
    let light = [-0.6, 0.9, 0.7];
    let ambient = 0.12;
    let l = Light::new(Vec3::from(light), Scalar::from_num(ambient));
    let viewport = Rectangle::new(Point::zero(), Size::new(W, H));
    let pipeline = if inverse_transpose {
        Pipeline::with_inverse_transpose(model, projection * view, viewport, l).unwrap()
    } else {
        Pipeline::new(model, projection * view, viewport, l)
    };
    Scene {
        pipeline,
        light: normalize(light),
        eye: normalize(eye),
        ambient: l.ambient().to_num::<f64>(),
    }
}

/// The world-space unit normal of a model-space normal, through the pipeline's normal matrix
/// (in f64).
fn world_normal(pipeline: &Pipeline, n: Vec3) -> [f64; 3] {
    let m = pipeline.normal_matrix.to_bits();
    let n = meshes::to_f64(n);
    normalize(core::array::from_fn(|r| {
        (0..3).map(|c| f64::from(m[r][c]) / 65536.0 * n[c]).sum()
    }))
}

/// The f64 quadratic normal field of unit vertex normals `n` at barycentrics `c`.
fn quadratic(n: &[[f64; 3]; 3], c: [f64; 3]) -> [f64; 3] {
    let mut v = [0.0; 3];
    for i in 0..3 {
        v = add(v, scale(n[i], c[i] * (2.0 * c[i] - 1.0)));
    }
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        v = add(v, scale(normalize(add(n[i], n[j])), 4.0 * c[i] * c[j]));
    }
    v
}

/// The f64 light level and specular term of a surface normal (not necessarily unit).
fn lit_f64(scene: &Scene, specular: &Specular, n: [f64; 3]) -> (f64, f64) {
    let diffuse = texture::lambert(n, scene.light);
    let shininess = f64::from(specular.shininess());
    let s = texture::blinn_phong(n, scene.light, scene.eye, shininess);
    (
        scene.ambient + (1.0 - scene.ambient) * diffuse,
        specular.strength().to_num::<f64>() * s,
    )
}

/// Errors of one sphere drawing against f64.
#[derive(Default, Debug)]
struct Tally {
    pixels: u64,
    /// Pixels next to the terminator (`|n̂·l|` below 10⁻³), where the highlight starts: not
    /// checked (the fixed-point and f64 signs of `n·l` may differ there).
    skipped: u64,
    /// The largest error on the faces the highlight reaches, and on the others (flat and
    /// Gouraud faces without highlight are filled as without one).
    worst: f64,
    worst_plain: f64,
    highlighted: u64,
}

/// Draws each face of `mesh` alone with `material` (shading `shading`, highlight `specular`)
/// and checks every pixel it covers against the f64 lit colour there, channel by channel.
///
/// On the faces the highlight reaches (an f64 specular term above 2⁻¹⁴ at a vertex, or the
/// face's when flat; every face when quadratic): within ½ LSB of rounding, 0.1 LSB for the
/// light level and the planes, and `k · shininess · strength · 2⁻¹⁷ · max` for the highlight
/// (`max` the channel's maximum): the power's `shininess · 2⁻¹⁷` and the cosine's error
/// amplified by up to the shininess, `k = 3` per vertex or face (a cosine within 2⁻¹⁶) and
/// `k = 5` per pixel (within 2⁻¹⁵). On the others, flat and Gouraud faces are filled as
/// without a highlight: ½ LSB, the 256 levels' `½·base/255` and 0.01 of interpolation.
fn check_sphere<C: GouraudColor>(
    scene: &Scene,
    mesh: &MeshData,
    base: C,
    shading: Shading,
    specular: Specular,
) -> Tally {
    let material = Material::new(base, shading).with_specular(specular);
    let pipeline = &scene.pipeline;
    let max = C::MAX.map(f64::from);
    let base_c = base.channels().map(f64::from);
    let n = (W * H) as usize;
    let (mut px, mut z) = (vec![base; n], vec![0u16; n]);
    let mut tally = Tally::default();
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
        let normals = idx.map(|i| world_normal(pipeline, mesh.normals[i]));
        let vertex = normals.map(|n| lit_f64(scene, &specular, n));
        let face_n = {
            let p = idx.map(|i| meshes::to_f64(mesh.vertices[i]));
            let (e1, e2) = (vec_f64::sub(p[1], p[0]), vec_f64::sub(p[2], p[0]));
            let m = pipeline.normal_matrix.to_bits();
            let nm = vec_f64::cross(e1, e2);
            // A face normal transforms like a vertex normal.
            normalize(core::array::from_fn(|r| {
                (0..3).map(|c| f64::from(m[r][c]) / 65536.0 * nm[c]).sum()
            }))
        };
        // Gouraud: a vertex at the terminator may or may not have its highlight.
        let near_terminator = |n: [f64; 3]| dot(normalize(n), scene.light).abs() < 1e-3;
        if shading == Shading::Gouraud && normals.iter().any(|&n| near_terminator(n)) {
            tally.skipped += covered as u64;
            continue;
        }
        if shading == Shading::Flat && near_terminator(face_n) {
            tally.skipped += covered as u64;
            continue;
        }
        let reached = match shading {
            Shading::Gouraud => vertex.iter().any(|v| v.1 > 1.0 / 16384.0),
            Shading::Flat => lit_f64(scene, &specular, face_n).1 > 1.0 / 16384.0,
            _ => true,
        };
        let k = if shading == Shading::Quadratic {
            5.0
        } else {
            3.0
        };
        let highlight =
            k * f64::from(specular.shininess()) * specular.strength().to_num::<f64>() / 131072.0;
        let tolerance = |ch: usize| match reached {
            true => 0.6 + highlight * max[ch],
            false => 0.51 + 0.5 * base_c[ch] / 255.0,
        };
        reference::for_each_covered(raw, 0, 0, W as i32, H as i32, |i, j| {
            let c = reference::barycentric(raw, i, j).unwrap();
            let (level, spec) = match shading {
                Shading::Gouraud => (
                    (0..3).map(|m| c[m] * vertex[m].0).sum::<f64>(),
                    (0..3).map(|m| c[m] * vertex[m].1).sum::<f64>(),
                ),
                Shading::Quadratic => {
                    let nq = quadratic(&normals, c);
                    if near_terminator(nq) {
                        tally.skipped += 1;
                        return;
                    }
                    lit_f64(scene, &specular, nq)
                }
                _ => lit_f64(scene, &specular, face_n),
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

/// The model poses: a rotation (normals dotted in model space) and a non-uniform scale
/// (normals transformed and renormalised per vertex).
fn poses() -> [(Mat4, bool, &'static str); 2] {
    let rotation =
        Mat4::rotation_y(Angle::from_degrees(25)) * Mat4::rotation_x(Angle::from_degrees(-15));
    let mut stretch = Mat4::IDENTITY;
    stretch.rows[0][0] = Scalar::from_num(1.15);
    stretch.rows[1][1] = Scalar::from_num(0.85);
    [
        (rotation, false, "rotation"),
        (rotation * stretch, true, "scaled"),
    ]
}

/// Gouraud, in `Rgb888` and `Rgb565`, within the tolerances of [`check_sphere`].
#[test]
fn gouraud_sphere_matches_f64() {
    let mesh = sphere();
    for (model, it, name) in poses() {
        let scene = scene(model, it);
        for (specular, base) in [
            (
                Specular::new(Scalar::from_num(0.8), 24),
                Rgb888::new(200, 90, 40),
            ),
            (
                Specular::new(Scalar::from_num(0.5), 64),
                Rgb888::new(40, 120, 230),
            ),
            (Specular::new(Scalar::ONE, 6), Rgb888::new(250, 250, 250)),
        ] {
            let t = check_sphere(&scene, &mesh, base, Shading::Gouraud, specular);
            println!("Gouraud {name} {specular:?} Rgb888: {t:?}");
            assert!(t.pixels > 3000 && t.highlighted > 100, "{t:?}");
            let base = Rgb565::new(base.r() >> 3, base.g() >> 2, base.b() >> 3);
            let t = check_sphere(&scene, &mesh, base, Shading::Gouraud, specular);
            println!("Gouraud {name} {specular:?} Rgb565: {t:?}");
        }
    }
}

/// Per pixel (`Shading::Quadratic`), in `Rgb888` and `Rgb565`, within the tolerances of
/// [`check_sphere`]: the cosine from the stepped normal rounded to 16 bits and renormalised.
#[test]
fn quadratic_sphere_matches_f64() {
    let mesh = sphere();
    for (model, it, name) in poses() {
        let scene = scene(model, it);
        for (specular, base) in [
            (
                Specular::new(Scalar::from_num(0.8), 24),
                Rgb888::new(200, 90, 40),
            ),
            (
                Specular::new(Scalar::from_num(0.6), 96),
                Rgb888::new(40, 120, 230),
            ),
            (Specular::new(Scalar::ONE, 6), Rgb888::new(250, 250, 250)),
        ] {
            let t = check_sphere(&scene, &mesh, base, Shading::Quadratic, specular);
            println!("Quadratic {name} {specular:?} Rgb888: {t:?}");
            assert!(t.pixels > 3000 && t.highlighted > 100, "{t:?}");
            let base = Rgb565::new(base.r() >> 3, base.g() >> 2, base.b() >> 3);
            let t = check_sphere(&scene, &mesh, base, Shading::Quadratic, specular);
            println!("Quadratic {name} {specular:?} Rgb565: {t:?}");
        }
    }
}

/// Flat: one colour a face, within the tolerances of [`check_sphere`].
#[test]
fn flat_sphere_matches_f64() {
    let mesh = sphere();
    for (model, it, name) in poses() {
        let scene = scene(model, it);
        let specular = Specular::new(Scalar::from_num(0.7), 12);
        let t = check_sphere(
            &scene,
            &mesh,
            Rgb888::new(30, 200, 90),
            Shading::Flat,
            specular,
        );
        println!("Flat {name} Rgb888: {t:?}");
        assert!(t.pixels > 3000 && t.highlighted > 100, "{t:?}");
    }
}

/// The sharpest highlight, shininess 255: the cosine's error is amplified the most (the
/// tolerance on the highlight is 1.5 LSB of an 8-bit channel per vertex, 2.5 per pixel).
#[test]
fn sharpest_highlight_matches_f64() {
    let mesh = sphere();
    let specular = Specular::new(Scalar::ONE, 255);
    for (model, it, name) in poses() {
        let scene = scene(model, it);
        for shading in [Shading::Gouraud, Shading::Quadratic] {
            let base = Rgb888::new(20, 20, 20);
            let t = check_sphere(&scene, &mesh, base, shading, specular);
            println!("{shading:?} {name} shininess 255 Rgb888: {t:?}");
            assert!(t.highlighted > 20, "{t:?}");
        }
    }
}

/// The viewer direction: towards the eye of a `look_at` camera, through perspective and
/// orthographic projections, in world space whatever the model matrix.
#[test]
fn view_direction_points_at_the_camera() {
    let viewport = Rectangle::new(Point::zero(), Size::new(64, 48));
    let mut worst = [0.0f64; 2];
    let mut error = |a: Vec3, b: [f64; 3], k: usize| {
        let a = meshes::to_f64(a);
        let e = (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max);
        worst[k] = worst[k].max(e);
        e
    };
    let mut rng = Rng(0x59ec_0001);
    for _ in 0..200 {
        let eye = [0; 3].map(|_| rng.range_f64(-5.0, 5.0));
        if dot(eye, eye) < 0.5 {
            continue;
        }
        let view = Mat4::look_at(Vec3::from(eye), Vec3::ZERO, Vec3::new(0, 1, 0.01)).unwrap();
        let model = Mat4::rotation_x(Angle(rng.next() as u16))
            * Mat4::rotation_z(Angle(rng.next() as u16))
            * Mat4::scaling(Scalar::from_num(rng.range_f64(0.5, 2.0)));
        for (k, projection) in [
            Mat4::perspective(Angle::from_degrees(60), 1.3, 0.5, 30.0).unwrap(),
            Mat4::orthographic(-3.0, 3.0, -2.0, 2.0, 0.5, 30.0),
        ]
        .into_iter()
        .enumerate()
        {
            let pipeline = Pipeline::new(model, projection * view, viewport, Light::default());
            let v = pipeline.view_direction();
            // The matrices' roundings: the orthographic `z` row's entries are small
            // (2/(far − near)), so rounding them to 2⁻¹⁶ costs it more.
            let e = error(v, normalize(eye), k);
            assert!(e < [1e-4, 1e-3][k], "{k}: {v:?} vs {:?}", normalize(eye));
        }
    }
    println!(
        "worst component error: perspective {:.2e}, orthographic {:.2e}",
        worst[0], worst[1]
    );
}

/// Every path draws the same pixels and depths: `draw_mesh`, `draw_mesh_with` and the bands
/// (no bin, no scratch; scratch; bin) at every band height, for each shading with a
/// highlight, with faces clipped at the near plane and a mesh without normals.
#[test]
fn every_path_draws_the_same_highlights() {
    let mut rng = Rng(0x59ec_0002);
    let mut bare = meshes::icosphere(0.8, 1);
    bare.normals.clear();
    let (size, viewport) = (
        Size::new(61, 47),
        Rectangle::new(Point::new(-4, 3), Size::new(70, 50)),
    );
    let mut clipped = 0;
    for round in 0..9 {
        let shading = [Shading::Flat, Shading::Gouraud, Shading::Quadratic][round % 3];
        let projection = Mat4::perspective(Angle::from_degrees(70), 1.4, 0.5, 12.0).unwrap();
        let distance = 1 + rng.below(3) as i32;
        let view = Mat4::translation(Vec3::from_bits(0, 0, -(distance << 16) - (1 << 15)));
        let model =
            Mat4::rotation_x(Angle(rng.next() as u16)) * Mat4::rotation_y(Angle(rng.next() as u16));
        let light = Light::new(Vec3::new(-0.4, 0.6, 0.9), Scalar::from_num(0.15));
        let mut pipeline = Pipeline::new(model, projection * view, viewport, light);
        pipeline.cull = [Cull::Back, Cull::None, Cull::Front][round / 3];
        let specular = Specular::new(
            Scalar::from_num(rng.range_f64(0.3, 1.0)),
            rng.below(80) as u8 + 1,
        );
        let color = |r: &mut Rng| Rgb888::new(r.next() as u8, r.next() as u8, r.next() as u8);
        let meshes = [
            (
                TORUS,
                Material::new(color(&mut rng), shading).with_specular(specular),
            ),
            (
                ICOSPHERE,
                Material::new(color(&mut rng), shading).with_specular(specular),
            ),
            (
                bare.as_mesh(),
                Material::new(color(&mut rng), shading).with_specular(specular),
            ),
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
        // Highlights there: brighter than the same materials without.
        for rows in [1, 2, 5, 16, 47] {
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

/// Without a highlight, or with one of strength 0, a material draws what it drew before the
/// highlight existed; with one it draws brighter, never darker.
#[test]
fn no_highlight_is_the_plain_frame() {
    let mesh = sphere();
    let scene = scene(Mat4::rotation_y(Angle::from_degrees(40)), false);
    let draw = |material: &Material<Rgb565>| {
        let n = (W * H) as usize;
        let (mut colors, mut depth) = (vec![Rgb565::BLACK; n], vec![0u16; n]);
        let mut target = DepthTarget::new(&mut colors, &mut depth, W, H).unwrap();
        target.clear(Rgb565::BLACK);
        scene
            .pipeline
            .draw_mesh(&mesh.as_mesh(), material, &mut target);
        (colors, depth)
    };
    for shading in [
        Shading::Unlit,
        Shading::Flat,
        Shading::Gouraud,
        Shading::Quadratic,
    ] {
        let plain = Material::new(Rgb565::new(20, 40, 10), shading);
        assert_eq!(plain.specular, None);
        let off = plain.with_specular(Specular::new(Scalar::ZERO, 32));
        let (colors, depth) = draw(&plain);
        assert!(draw(&off) == (colors.clone(), depth.clone()), "{shading:?}");
        let (shiny, shiny_depth) = draw(&plain.with_specular(Specular::new(Scalar::ONE, 16)));
        assert_eq!(shiny_depth, depth);
        let brighter = shiny.iter().zip(&colors).filter(|(s, c)| s != c).count();
        let darker = shiny.iter().zip(&colors).any(|(s, c)| {
            let (s, c) = (s.channels(), c.channels());
            // Rounding in a different order may take one LSB off a pixel without highlight.
            (0..3).any(|k| s[k] + 1 < c[k])
        });
        assert!(!darker, "{shading:?}");
        if shading == Shading::Unlit {
            assert_eq!(brighter, 0);
        } else {
            assert!(brighter > 200, "{shading:?}: {brighter}");
        }
    }
}
