//! The fixed-point 3D pipeline against an independent f64 reference.
//!
//! The reference does not project, clip or rasterise anything: for every pixel it casts the ray
//! through the pixel centre in eye space (f64 model-view from the same angles and positions) and
//! intersects it with every triangle. A triangle covers the pixel if the ray passes inside its
//! three edge planes (planes through the eye), hits it in front of the eye, and the hit lies
//! between the near and far planes; its depth there is `(1 + z_ndc)/2 · 65534` with `z_ndc` from
//! the f64 projection. Each of those conditions is an affine function of the screen position, so
//! the reference also knows how far (in pixels) the pixel centre is from the boundary of every
//! triangle.
//!
//! The fixed-point vertices differ from the f64 ones by rounding (measured below: well under
//! 0.01 px), so the comparison leaves out exactly what that rounding can decide:
//!
//! * a triangle whose boundary passes within `MARGIN` px of a pixel centre *may* cover it
//!   (shared edges: either neighbour may own the pixel, but the pipeline must draw one of them —
//!   holes or background there fail);
//! * where two candidate triangles' f64 depths are within their depth tolerances of each other
//!   (`2 LSB` of the 16-bit depth plus what `MARGIN` px of position error moves the depth), either
//!   may win. Everywhere else exactly one triangle is acceptable: the nearest one.
//!
//! Tests also check that those ambiguous pixels are rare, and that the z-buffer holds the drawn
//! triangle's depth within its tolerance.

use embedded_graphics::{pixelcolor::Rgb888, prelude::*, primitives::Rectangle};
use embedded_raster::three_d::meshes::{icosphere, MeshData};
use embedded_raster::three_d::{Angle, Mat4, Scalar, Vec3};
use embedded_raster::three_d::{Cull, DepthTarget, Mesh, Pipeline, DEPTH_CLEAR};
use embedded_raster::three_d::{Light, Material, Shading};

const W: u32 = 128;
const H: u32 = 96;

use crate::raycast;
use raycast::{apply, bits3, cross, dot, fl, flat_grid, fx, sub, View, MARGIN, V};

use crate::rng;
use rng::Rng;

impl Rng {
    fn angle(&mut self) -> Angle {
        Angle(self.next() as u16)
    }
}

/// One camera and object placement, in both arithmetics.
struct Scene {
    pipeline: Pipeline,
    view: View,
}

impl Scene {
    /// The pipeline of `view` (default light), culling `cull`.
    fn new(view: View, cull: Cull) -> Scene {
        let mut pipeline =
            Pipeline::new(view.model, view.projection, view.viewport, Light::default());
        pipeline.cull = cull;
        Scene { pipeline, view }
    }

    /// Screen position and 16-bit depth of a model-space point (f64).
    fn project(&self, p: Vec3) -> (f64, f64, f64) {
        let e = apply(&self.view.model_view, bits3(p));
        let (x, y) = self.view.screen(e);
        let zn = -self.view.a - self.view.b / e[2];
        (x, y, (1.0 + zn) / 2.0 * 65534.0)
    }
}

/// The 60° camera (near plane 0.5, far 20) on the object turned by `yaw`, `pitch` and moved to
/// `position`.
fn view_60(yaw: Angle, pitch: Angle, position: V, viewport: Rectangle) -> View {
    View::new(
        Angle::from_degrees(60),
        0.5,
        20.0,
        yaw,
        pitch,
        position,
        viewport,
    )
}

fn id_color(k: usize) -> Rgb888 {
    let k = k + 1;
    Rgb888::new((k & 0xff) as u8, (k >> 8) as u8, 0x5a)
}

fn id_of(c: Rgb888) -> Option<usize> {
    (c != Rgb888::BLACK).then(|| usize::from(c.r()) + (usize::from(c.g()) << 8) - 1)
}

#[derive(Default, Debug)]
struct Tally {
    pixels: u64,
    exact: u64,
    covered: u64,
    worst_depth: f64,
}

/// Draws `mesh` one triangle at a time (each in its own ID colour, one shared z-buffer) and
/// checks every pixel of the target against the reference.
fn check_scene(scene: &Scene, mesh: &MeshData, tally: &mut Tally) {
    let mut px = vec![Rgb888::BLACK; (W * H) as usize];
    let mut z = vec![0u16; (W * H) as usize];
    let mut target = DepthTarget::new(&mut px, &mut z, W, H).unwrap();
    target.clear(Rgb888::BLACK);
    for k in 0..mesh.indices.len() {
        let one = Mesh::new(&mesh.vertices, &mesh.normals, &mesh.indices[k..k + 1]);
        let material = Material::new(id_color(k), Shading::Unlit);
        scene.pipeline.draw_mesh(&one, &material, &mut target);
    }
    let eye: Vec<[V; 3]> = mesh
        .indices
        .iter()
        .map(|f| f.map(|i| apply(&scene.view.model_view, bits3(mesh.vertices[usize::from(i)]))))
        .collect();
    // Front faces are counter-clockwise seen by the camera: (v1 − v0) × (v2 − v0) points at it.
    let facing = |t: &[V; 3]| dot(cross(sub(t[1], t[0]), sub(t[2], t[0])), t[0]) < 0.0;
    for j in 0..H as i32 {
        for i in 0..W as i32 {
            tally.pixels += 1;
            let got = id_of(target.framebuffer().get(i, j).unwrap());
            let depth = target.depth_at(i, j).unwrap();
            assert_eq!(got.is_some(), depth != DEPTH_CLEAR);
            if !scene.view.viewport.contains(Point::new(i, j)) {
                assert_eq!(got, None, "drawn outside the viewport at {i},{j}");
                tally.exact += 1;
                continue;
            }
            // (triangle, margin, depth, depth tolerance)
            let hits: Vec<(usize, f64, f64, f64)> = eye
                .iter()
                .enumerate()
                .filter(|(_, t)| match scene.pipeline.cull {
                    Cull::None => true,
                    Cull::Back => facing(t),
                    Cull::Front => !facing(t),
                })
                .filter_map(|(k, t)| {
                    scene
                        .view
                        .hit(t, i, j)
                        .map(|(m, d, g)| (k, m, d, 2.0 + 2.0 * MARGIN * g))
                })
                .collect();
            let sure = hits.iter().filter(|h| h.1 > MARGIN);
            let front = sure.map(|h| h.2 + h.3).fold(f64::INFINITY, f64::min);
            let acceptable: Vec<&(usize, f64, f64, f64)> =
                hits.iter().filter(|h| h.2 - h.3 <= front).collect();
            let background_ok = front.is_infinite();
            match got {
                None => assert!(
                    background_ok,
                    "pixel {i},{j} empty but covered by {:?}",
                    hits.iter().filter(|h| h.1 > MARGIN).collect::<Vec<_>>()
                ),
                Some(k) => {
                    let h = acceptable.iter().find(|h| h.0 == k).unwrap_or_else(|| {
                        panic!("pixel {i},{j}: drew {k}, acceptable {acceptable:?}")
                    });
                    let err = (f64::from(depth) - h.2).abs();
                    assert!(err <= h.3, "pixel {i},{j}: depth {depth} vs {}", h.2);
                    tally.worst_depth = tally.worst_depth.max(err);
                    tally.covered += 1;
                }
            }
            if acceptable.len() == 1 && !background_ok || acceptable.is_empty() {
                tally.exact += 1;
            }
        }
    }
}

/// Projected vertices agree with f64 to well under the comparison margin.
#[test]
fn vertices_project_like_f64() {
    let mut rng = Rng(0xfeed_0001);
    let viewport = Rectangle::new(Point::zero(), Size::new(W, H));
    let sphere = icosphere(1.0, 2);
    let (mut worst_xy, mut worst_z) = (0.0f64, 0.0f64);
    for _ in 0..200 {
        let pos = [
            rng.range_f64(-1.0, 1.0),
            rng.range_f64(-1.0, 1.0),
            rng.range_f64(-6.0, -2.5),
        ];
        let scene = Scene::new(view_60(rng.angle(), rng.angle(), pos, viewport), Cull::None);
        for v in &sphere.vertices {
            let got = scene
                .pipeline
                .project(scene.pipeline.clip_position(*v))
                .unwrap();
            let (x, y, z) = scene.project(*v);
            worst_xy = worst_xy
                .max((got.x.to_num::<f64>() - x).abs())
                .max((got.y.to_num::<f64>() - y).abs());
            worst_z = worst_z.max((f64::from(got.depth) - z).abs());
        }
    }
    println!("worst vertex error {worst_xy:.4} px, depth {worst_z:.3} LSB");
    assert!(worst_xy < MARGIN / 2.0);
    // ½ LSB rounding plus the I16F16 rounding of the matrices.
    assert!(worst_z < 1.5);
}

/// An icosphere at random rotations and positions, culled and not: every pixel shows the nearest
/// triangle.
#[test]
fn icosphere_matches_f64_reference() {
    let mut rng = Rng(0xfeed_0013);
    let sphere = icosphere(1.0, 2);
    let mut tally = Tally::default();
    for round in 0..24 {
        let viewport = if round % 3 == 2 {
            Rectangle::new(Point::new(9, 5), Size::new(100, 80))
        } else {
            Rectangle::new(Point::zero(), Size::new(W, H))
        };
        let pos = [
            rng.range_f64(-1.5, 1.5),
            rng.range_f64(-1.0, 1.0),
            rng.range_f64(-5.0, -2.0),
        ];
        let cull = [Cull::None, Cull::Back, Cull::Front][round % 3];
        let scene = Scene::new(view_60(rng.angle(), rng.angle(), pos, viewport), cull);
        check_scene(&scene, &sphere, &mut tally);
    }
    println!("{tally:?}");
    assert!(tally.covered > 50_000);
    assert!(tally.exact as f64 > 0.9 * tally.pixels as f64);
}

/// Random triangles in separated, slightly tilted layers (they overlap on screen but never
/// intersect), both windings, no culling; some scenes put the camera among the layers so the
/// near plane cuts through them.
#[test]
fn layered_triangles_match_f64_reference() {
    let mut rng = Rng(0xfeed_0012);
    let mut tally = Tally::default();
    let viewport = Rectangle::new(Point::zero(), Size::new(W, H));
    for round in 0..30 {
        let mut positions = Vec::new();
        let mut faces = Vec::new();
        for layer in 0..6 {
            let z0 = layer as f64 * 0.35 - 0.9;
            let (tx, ty) = (rng.range_f64(-0.1, 0.1), rng.range_f64(-0.1, 0.1));
            for _ in 0..8 {
                let (cx, cy) = (rng.range_f64(-1.5, 1.5), rng.range_f64(-1.5, 1.5));
                let base = positions.len();
                for _ in 0..3 {
                    let (x, y) = (cx + rng.range_f64(-1.0, 1.0), cy + rng.range_f64(-1.0, 1.0));
                    positions.push([x, y, z0 + tx * x + ty * y]);
                }
                faces.push([base, base + 1, base + 2]);
            }
        }
        let normals = vec![[0.0, 0.0, 1.0]; positions.len()];
        let mut mesh = MeshData::from_f64(&positions, &normals, &faces);
        // Random windings.
        for f in &mut mesh.indices {
            if rng.unit() < 0.5 {
                f.swap(1, 2);
            }
        }
        let close = round % 3 == 0;
        let pos = if close {
            [
                rng.range_f64(-0.5, 0.5),
                rng.range_f64(-0.5, 0.5),
                rng.range_f64(-1.2, -0.6),
            ]
        } else {
            [
                rng.range_f64(-0.5, 0.5),
                rng.range_f64(-0.5, 0.5),
                rng.range_f64(-6.0, -3.5),
            ]
        };
        let scene = Scene::new(
            View::new(
                Angle::from_degrees(70),
                0.25,
                12.0,
                Angle((rng.next() as u16) / 6),
                Angle((rng.next() as u16) / 6),
                pos,
                viewport,
            ),
            Cull::None,
        );
        check_scene(&scene, &mesh, &mut tally);
    }
    println!("{tally:?}");
    assert!(tally.covered > 100_000);
    assert!(tally.exact as f64 > 0.9 * tally.pixels as f64);
}

/// A finely tessellated plane far larger than the view, crossing the near plane and the guard
/// band: drawn triangle by triangle without depth test interference (a fresh z-buffer per
/// triangle), every pixel inside its visible outline (by more than `MARGIN`) is covered exactly
/// once, every pixel outside it never, and no pixel twice.
/// Shared edges, including the ones produced by clipping, leave no gaps and no double hits.
#[test]
fn clipped_grid_is_watertight() {
    let mut rng = Rng(0xfeed_0004);
    let viewport = Rectangle::new(Point::zero(), Size::new(W, H));
    let n = 24;
    let half = 60.0;
    let mut positions = Vec::new();
    for r in 0..=n {
        for c in 0..=n {
            let x = -half + 2.0 * half * c as f64 / n as f64;
            let y = -half + 2.0 * half * r as f64 / n as f64;
            // Interior vertices jittered; the outline stays the exact square.
            let interior = r > 0 && r < n && c > 0 && c < n;
            let j = if interior { 0.5 } else { 0.0 };
            positions.push([x + rng.range_f64(-j, j), y + rng.range_f64(-j, j), 0.0]);
        }
    }
    let grid = flat_grid(&positions, n);
    let at = |r: usize, c: usize| r * (n + 1) + c;
    let corners = [
        positions[at(0, 0)],
        positions[at(0, n)],
        positions[at(n, n)],
        positions[at(n, 0)],
    ];
    let mut px = vec![Rgb888::BLACK; (W * H) as usize];
    let mut z = vec![0u16; (W * H) as usize];
    let (mut inside, mut clipped) = (0u64, 0u32);
    for _ in 0..12 {
        // A floor below the camera (the xy plane tipped by about −90° about x), turned about
        // the vertical: it runs from behind the camera to beyond the far plane.
        let pitch = Angle::from_degrees(rng.range_f64(-120.0, -60.0) as i32);
        let pos = [
            rng.range_f64(-2.0, 2.0),
            rng.range_f64(-1.5, -0.3),
            rng.range_f64(-3.0, -1.0),
        ];
        let scene = Scene::new(
            View::new(
                Angle::from_degrees(70),
                0.2,
                40.0,
                rng.angle(),
                pitch,
                pos,
                viewport,
            ),
            Cull::None,
        );
        let behind = grid
            .vertices
            .iter()
            .filter(|v| {
                let e = apply(&scene.view.model_view, bits3(**v));
                e[2] > -0.2
            })
            .count();
        assert!(behind > 0, "the near plane must cut the grid");
        let mut count = vec![0u8; (W * H) as usize];
        for k in 0..grid.indices.len() {
            let mut target = DepthTarget::new(&mut px, &mut z, W, H).unwrap();
            target.clear(Rgb888::BLACK);
            let one = Mesh::new(&grid.vertices, &grid.normals, &grid.indices[k..k + 1]);
            let s = scene.pipeline.draw_mesh(
                &one,
                &Material::new(Rgb888::WHITE, Shading::Unlit),
                &mut target,
            );
            clipped += s.clipped;
            for (c, d) in count.iter_mut().zip(target.depth()) {
                *c += u8::from(*d != DEPTH_CLEAR);
            }
        }
        // The outline: the square through the grid's corners, cut by the near and far planes.
        let outline = corners.map(|p| {
            let v = [0, 1, 2].map(|k| fl(fx(p[k])));
            apply(&scene.view.model_view, v)
        });
        for j in 0..H as i32 {
            for i in 0..W as i32 {
                let c = count[(j as u32 * W + i as u32) as usize];
                assert!(c <= 1, "pixel {i},{j} drawn {c} times");
                match scene.view.hit(&outline, i, j) {
                    Some((m, _, _)) if m > MARGIN => {
                        assert_eq!(c, 1, "hole at {i},{j}");
                        inside += 1;
                    }
                    Some(_) => {}
                    None => assert_eq!(c, 0, "stray pixel at {i},{j}"),
                }
            }
        }
    }
    println!("{inside} interior pixels checked, {clipped} clipped triangles");
    assert!(inside > 50_000 && clipped > 100);
}

/// Garbage in, nothing out of bounds and no panic (run in the debug test profile too, where
/// overflow checks are on): extreme vertices, normals and matrices, out-of-range indices,
/// degenerate and huge triangles, every shading mode.
#[test]
fn extreme_inputs_do_not_panic() {
    use embedded_raster::three_d::ScreenVertex;
    use embedded_raster::three_d::{draw_quadratic, QuadraticNormals};
    use embedded_raster::Coord;
    let mut rng = Rng(0xfeed_0005);
    let pick = |rng: &mut Rng| -> i32 {
        match rng.next() % 6 {
            0 => i32::MIN,
            1 => i32::MAX,
            2 => 0,
            3 => (rng.next() as i32) >> (rng.next() % 31),
            4 => ((rng.next() % 200_000) as i32) - 100_000,
            _ => rng.next() as i32,
        }
    };
    let mut px = vec![Rgb888::BLACK; (W * H) as usize];
    let mut z = vec![0u16; (W * H) as usize];
    let (mut drawn, mut clipped, mut filled) = (0, 0, 0);
    for round in 0..3000 {
        let vertices: Vec<Vec3> = (0..6)
            .map(|_| Vec3::from_bits(pick(&mut rng), pick(&mut rng), pick(&mut rng)))
            .collect();
        let normals: Vec<Vec3> = (0..5)
            .map(|_| Vec3::from_bits(pick(&mut rng), pick(&mut rng), pick(&mut rng)))
            .collect();
        let indices: Vec<[u16; 3]> = (0..4)
            .map(|_| [0; 3].map(|_| (rng.next() % 7) as u16))
            .collect();
        let matrix = |rng: &mut Rng| {
            if rng.next() % 2 == 0 {
                Mat4::from_bits([[0; 4]; 4].map(|r| r.map(|_: i32| pick(rng))))
            } else {
                Mat4::perspective(
                    rng.angle(),
                    fx(rng.range_f64(-2.0, 4.0)),
                    fx(rng.range_f64(-1.0, 1.0)),
                    fx(rng.range_f64(-5.0, 50.0)),
                )
                // Parameters that show nothing have no projection: a raw matrix instead.
                .unwrap_or_else(|| Mat4::from_bits([[0; 4]; 4].map(|r| r.map(|_: i32| pick(rng)))))
                    * Mat4::translation(Vec3::from_bits(pick(rng), pick(rng), pick(rng)))
                    * Mat4::rotation_x(rng.angle())
            }
        };
        let viewport = Rectangle::new(
            Point::new(pick(&mut rng) % 200, pick(&mut rng) % 200),
            Size::new((rng.next() % 70_000) as u32, (rng.next() % 300) as u32),
        );
        let light = Light::new(
            Vec3::from_bits(pick(&mut rng), pick(&mut rng), pick(&mut rng)),
            Scalar::from_bits(pick(&mut rng)),
        );
        let mut pipeline = Pipeline::new(matrix(&mut rng), matrix(&mut rng), viewport, light);
        pipeline.cull = [Cull::None, Cull::Back, Cull::Front][round % 3];
        let mesh = Mesh::new(&vertices, &normals, &indices);
        let mut target = DepthTarget::new(&mut px, &mut z, W, H).unwrap();
        target.clear(Rgb888::BLACK);
        for shading in [
            Shading::Unlit,
            Shading::Flat,
            Shading::Gouraud,
            Shading::Quadratic,
        ] {
            let stats =
                pipeline.draw_mesh(&mesh, &Material::new(Rgb888::WHITE, shading), &mut target);
            drawn += stats.drawn;
            clipped += stats.clipped;
        }
        filled += target.depth().iter().filter(|d| **d != DEPTH_CLEAR).count();
        // Screen-space fills with arbitrary vertices and non-unit normal fields.
        let sv = |rng: &mut Rng| {
            ScreenVertex::new(
                Coord::from_bits(pick(rng) >> (rng.next() % 20)),
                Coord::from_bits(pick(rng) >> (rng.next() % 20)),
                rng.next() as u16,
            )
        };
        let tri = [sv(&mut rng), sv(&mut rng), sv(&mut rng)];
        let field = QuadraticNormals::from_nodes(
            [0; 3].map(|_| Vec3::from_bits(pick(&mut rng), pick(&mut rng), pick(&mut rng))),
            [0; 3].map(|_| Vec3::from_bits(pick(&mut rng), pick(&mut rng), pick(&mut rng))),
        );
        let clip = Rectangle::new(Point::zero(), Size::new(W, H));
        draw_quadratic(&mut target, &clip, &tri, &field, &light, Rgb888::WHITE);
        let _ = field.at([0; 3].map(|_| Scalar::from_bits(pick(&mut rng))));
    }
    println!("{drawn} triangles drawn, {clipped} clipped, {filled} pixels");
    assert!(drawn > 100 && clipped > 100 && filled > 10_000);
}

/// Each vertex transformed once into a scratch slice (`draw_mesh_with`) or once per face
/// (`draw_mesh`): the same frame, bit for bit, over random poses (some crossing the near plane
/// and the guard band), every shading and culling mode, meshes with and without normals and
/// with and without their extent kept; and a scratch too short is an error that draws nothing.
#[test]
fn vertex_scratch_gives_the_same_frame() {
    use embedded_raster::three_d::{ProjectedVertex, ScratchTooSmall};
    let mut rng = Rng(0xfeed_0006);
    let sphere = icosphere(1.0, 2);
    let viewport = Rectangle::new(Point::new(-7, 3), Size::new(W + 20, H - 10));
    let (mut px_a, mut z_a) = (
        vec![Rgb888::BLACK; (W * H) as usize],
        vec![0u16; (W * H) as usize],
    );
    let (mut px_b, mut z_b) = (px_a.clone(), z_a.clone());
    let mut scratch = vec![ProjectedVertex::EMPTY; sphere.vertices.len()];
    let (mut clipped, mut drawn) = (0, 0);
    for round in 0..400 {
        let pos = [
            rng.range_f64(-2.0, 2.0),
            rng.range_f64(-2.0, 2.0),
            rng.range_f64(-5.0, 0.5),
        ];
        let cull = [Cull::None, Cull::Back, Cull::Front][round % 3];
        let scene = Scene::new(
            View::new(
                Angle::from_degrees(70),
                0.3,
                9.0,
                rng.angle(),
                rng.angle(),
                pos,
                viewport,
            ),
            cull,
        );
        let shading = [
            Shading::Unlit,
            Shading::Flat,
            Shading::Gouraud,
            Shading::Quadratic,
        ][round % 4];
        let material = Material::new(Rgb888::new(200, 150, 90), shading);
        // Every other round without normals: levels from the faces.
        let normals: &[Vec3] = if round % 8 < 4 { &sphere.normals } else { &[] };
        let mesh = Mesh::new(&sphere.vertices, normals, &sphere.indices);
        let mut a = DepthTarget::new(&mut px_a, &mut z_a, W, H).unwrap();
        a.clear(Rgb888::BLACK);
        let per_face = scene.pipeline.draw_mesh(&mesh, &material, &mut a);
        let mut b = DepthTarget::new(&mut px_b, &mut z_b, W, H).unwrap();
        b.clear(Rgb888::BLACK);
        // Every other round with the extent found once (`with_extent`): the same frame.
        let kept = if round % 2 == 1 {
            mesh.with_extent()
        } else {
            mesh
        };
        let once = scene
            .pipeline
            .draw_mesh_with(&kept, &material, &mut b, &mut scratch)
            .unwrap();
        assert_eq!(per_face, once, "round {round}");
        assert!(
            px_a == px_b && z_a == z_b,
            "round {round}: the frames differ"
        );
        clipped += once.clipped;
        drawn += once.drawn;
    }
    assert!(
        clipped > 200 && drawn > 20_000,
        "{clipped} clipped, {drawn} drawn"
    );

    let mesh = sphere.as_mesh();
    let mut b = DepthTarget::new(&mut px_b, &mut z_b, W, H).unwrap();
    b.clear(Rgb888::BLACK);
    let pipeline = Scene::new(
        view_60(Angle::ZERO, Angle::ZERO, [0.0, 0.0, -3.0], viewport),
        Cull::Back,
    )
    .pipeline;
    let short = &mut scratch[..sphere.vertices.len() - 1];
    let material = Material::new(Rgb888::WHITE, Shading::Gouraud);
    assert_eq!(
        pipeline.draw_mesh_with(&mesh, &material, &mut b, short),
        Err(ScratchTooSmall {
            needed: sphere.vertices.len(),
            given: sphere.vertices.len() - 1
        })
    );
    assert!(z_b.iter().all(|&d| d == DEPTH_CLEAR), "nothing drawn");
}

/// A face with an index past the vertices is skipped and counted as `invalid`, apart from the
/// zero-area faces counted as `degenerate` (issue #32, item 7): with and without a vertex
/// scratch, and binned for bands.
#[test]
fn out_of_range_faces_are_invalid_not_degenerate() {
    use embedded_raster::band::{BandLayout, BinEntry, MeshBin};
    use embedded_raster::three_d::ProjectedVertex;

    let vertices = [
        Vec3::new(-1, -1, 0),
        Vec3::new(1, -1, 0),
        Vec3::new(0, 1, 0),
    ];
    // One face drawn, one of zero area, two with an index out of range (3, u16::MAX).
    let indices = [[0, 1, 2], [0, 0, 1], [0, 1, 3], [u16::MAX, 1, 2]];
    let mesh = Mesh::new(&vertices, &[], &indices);
    assert!(mesh.validate().is_err());

    let (w, h) = (32, 24);
    let viewport = Rectangle::new(Point::zero(), Size::new(w, h));
    let camera = Mat4::perspective(Angle::from_degrees(60), 4.0 / 3.0, 0.5, 20).unwrap()
        * Mat4::translation(Vec3::new(0, 0, -3));
    let pipeline = Pipeline::new(Mat4::IDENTITY, camera, viewport, Light::default());
    let material = Material::new(Rgb888::WHITE, Shading::Gouraud);
    let want = |stats: embedded_raster::three_d::DrawStats| {
        assert_eq!(
            (stats.drawn, stats.degenerate, stats.invalid),
            (1, 1, 2),
            "{stats:?}"
        );
    };

    let (mut pixels, mut depth) = (vec![Rgb888::BLACK; 32 * 24], vec![0u16; 32 * 24]);
    let mut target = DepthTarget::new(&mut pixels, &mut depth, w, h).unwrap();
    want(pipeline.draw_mesh(&mesh, &material, &mut target));
    let mut scratch = [ProjectedVertex::default(); 3];
    want(
        pipeline
            .draw_mesh_with(&mesh, &material, &mut target, &mut scratch)
            .unwrap(),
    );

    let layout = BandLayout::new(Size::new(w, h), 8).unwrap();
    let mut storage = [BinEntry::EMPTY; 64];
    let bin = MeshBin::new(
        &pipeline,
        &mesh,
        &material,
        &layout,
        &mut scratch,
        &mut storage,
    )
    .unwrap();
    want(bin.stats());
}
