//! `Pipeline::draw_wireframe`: the edges of the drawn faces, depth-tested.
//!
//! * Against an f64 reference on the knot bench frame drawn as hidden lines: each kept face's
//!   edges (the faces found again from the public projection and the cull rule), their pixels
//!   from the 2D `Line` (the diamond-exit rule, tested on its own in `line.rs`), each pixel's
//!   depth interpolated in f64 along the segment and tested against the z-buffer plus the face's
//!   slope over a pixel: every pixel clearly visible by that rule drawn, every pixel clearly
//!   hidden not, and the pixels within 2 depth units of the threshold (rounding) counted.
//! * With and without the vertex scratch, and the faces in reverse order: the same pixels (each
//!   edge is drawn from its lower vertex index, whichever face hands it over).
//! * A floor through the near plane: the clipped faces' edges lie on the f64 projection of the
//!   grid's lines clipped to the view volume (within a pixel), never on the clip planes.

use embedded_graphics::pixelcolor::{BinaryColor, Rgb888};
use embedded_graphics::{prelude::*, primitives::Rectangle};
use embedded_raster::three_d::{
    signed_area2, Angle, Cull, DepthTarget, Material, Mesh, Pipeline, ProjectedVertex,
    ScreenVertex, Shading, DEPTH_CLEAR,
};
use embedded_raster::{Line, SliceFramebuffer};

use crate::raycast::{apply, bits3, flat_grid, View};
use crate::rng::Rng;
use crate::scene3d;

const EDGE: Rgb888 = Rgb888::WHITE;

/// The hidden-line frame of `mesh`: its faces in black filling the z-buffer, then its edges.
fn hidden_lines(pipeline: &Pipeline, mesh: &Mesh<'_>, w: u32, h: u32) -> (Vec<Rgb888>, Vec<u16>) {
    let (mut px, mut z) = (
        vec![Rgb888::BLACK; (w * h) as usize],
        vec![0; (w * h) as usize],
    );
    let mut target = DepthTarget::new(&mut px, &mut z, w, h).unwrap();
    target.clear(Rgb888::BLACK);
    let faces = Material::new(Rgb888::BLACK, Shading::Unlit);
    let filled = pipeline.draw_mesh(mesh, &faces, &mut target);
    let edges = pipeline.draw_wireframe(mesh, EDGE, &mut target);
    assert_eq!(filled, edges, "the wireframe keeps the fill's faces");
    (px, z)
}

/// The pixels the 2D line from `a` to `b` draws in a `w × h` frame.
fn line_pixels(a: &ScreenVertex, b: &ScreenVertex, w: u32, h: u32) -> Vec<(i32, i32)> {
    let mut buf = vec![BinaryColor::Off; (w * h) as usize];
    let mut fb = SliceFramebuffer::new(&mut buf, w, h).unwrap();
    let line = Line {
        start: (a.x, a.y),
        end: (b.x, b.y),
        paint: BinaryColor::On,
    };
    line.draw_into(&mut fb);
    let mut out = Vec::new();
    for y in 0..h as i32 {
        for x in 0..w as i32 {
            if fb.get(x, y) == Some(BinaryColor::On) {
                out.push((x, y));
            }
        }
    }
    out
}

/// A kept face's projected vertices and its edges as pairs of its vertices.
type KeptFace = ([ScreenVertex; 3], [(usize, usize); 3]);

/// The faces `pipeline` keeps of `mesh` (front-facing: anticlockwise on screen, non-degenerate;
/// the frames here need no clipping), found from the public projection: their projected vertices
/// and their edges as vertex pairs `(a, b)` of the face, `a` the vertex of the lower index.
fn kept_edges(pipeline: &Pipeline, mesh: &Mesh<'_>) -> Vec<KeptFace> {
    let mut kept = Vec::new();
    for face in mesh.indices {
        let s = face.map(|i| {
            let p = mesh.vertices[usize::from(i)];
            let screen = pipeline.project(pipeline.clip_position(p));
            screen.expect("the frame needs no clipping")
        });
        if signed_area2(s.map(|v| (v.x, v.y))) >= 0 {
            continue; // culled (back-facing: clockwise on screen) or degenerate
        }
        let edges = [0, 1, 2].map(|a| {
            let b = (a + 1) % 3;
            if face[a] <= face[b] {
                (a, b)
            } else {
                (b, a)
            }
        });
        kept.push((s, edges));
    }
    kept
}

/// The face's depth change across a pixel, `|∂z/∂x| + |∂z/∂y|`, in f64.
fn slope(s: &[ScreenVertex; 3]) -> f64 {
    let p = s.map(|v| (v.x.to_num::<f64>(), v.y.to_num::<f64>(), f64::from(v.depth)));
    let (d1, d2) = (
        (p[1].0 - p[0].0, p[1].1 - p[0].1, p[1].2 - p[0].2),
        (p[2].0 - p[0].0, p[2].1 - p[0].1, p[2].2 - p[0].2),
    );
    let area = d1.0 * d2.1 - d2.0 * d1.1;
    let gx = d1.2 * d2.1 - d2.2 * d1.1;
    let gy = d1.0 * d2.2 - d2.0 * d1.2;
    (gx.abs() + gy.abs()) / area.abs()
}

/// The segment's depth at the centre of pixel `(x, y)`: linear along its major axis, clamped to
/// its ends.
fn depth_along(a: &ScreenVertex, b: &ScreenVertex, (x, y): (i32, i32)) -> f64 {
    let (ax, ay, bx, by) = (
        a.x.to_num::<f64>(),
        a.y.to_num::<f64>(),
        b.x.to_num::<f64>(),
        b.y.to_num::<f64>(),
    );
    let (m0, m1, c) = if (by - ay).abs() > (bx - ax).abs() {
        (ay, by, f64::from(y) + 0.5)
    } else {
        (ax, bx, f64::from(x) + 0.5)
    };
    let t = ((c - m0) / (m1 - m0)).clamp(0.0, 1.0);
    f64::from(a.depth) + t * (f64::from(b.depth) - f64::from(a.depth))
}

#[test]
fn hidden_lines_match_f64_reference() {
    let (w, h) = scene3d::SIZE;
    let mut checked = 0;
    for model in [scene3d::Model::Knot, scene3d::Model::Spot] {
        let pipeline = scene3d::pipeline(model);
        let mesh = model.mesh(&scene3d::KNOT);
        let (px, z) = hidden_lines(&pipeline, mesh, w, h);
        // Per pixel: whether some edge clearly passes there, whether every edge that reaches it
        // clearly fails, and whether any edge reaches it at all.
        let n = (w * h) as usize;
        let (mut visible, mut reached, mut passes_somewhere) =
            (vec![false; n], vec![false; n], vec![false; n]);
        let mut ambiguous = 0;
        for (s, edges) in kept_edges(&pipeline, mesh) {
            let slack = slope(&s) + 2.0;
            for (a, b) in edges {
                for p in line_pixels(&s[a], &s[b], w, h) {
                    let i = (p.1 as u32 * w + p.0 as u32) as usize;
                    let margin = f64::from(z[i]) + slack - depth_along(&s[a], &s[b], p);
                    reached[i] = true;
                    if margin > 2.0 {
                        visible[i] = true;
                    }
                    if margin >= -2.0 {
                        passes_somewhere[i] = true;
                    }
                }
            }
        }
        for i in 0..n {
            let drawn = px[i] == EDGE;
            let (x, y) = (i as u32 % w, i as u32 / w);
            assert!(!drawn || reached[i], "{model:?}: {x},{y} is on no edge");
            if visible[i] {
                assert!(drawn, "{model:?}: visible edge pixel {x},{y} not drawn");
                checked += 1;
            } else if !passes_somewhere[i] {
                assert!(!drawn, "{model:?}: hidden edge pixel {x},{y} drawn");
                checked += 1;
            } else if reached[i] {
                ambiguous += 1;
            }
        }
        let hidden = (0..n)
            .filter(|&i| reached[i] && !passes_somewhere[i])
            .count();
        let shown = (0..n).filter(|&i| visible[i]).count();
        println!("{model:?}: {shown} visible and {hidden} hidden edge pixels, {ambiguous} within rounding");
        assert!(shown > 5_000 && hidden > 200);
        assert!(
            ambiguous * 100 < shown,
            "{ambiguous} pixels within rounding of the threshold"
        );
    }
    assert!(checked > 20_000);
}

#[test]
fn scratch_and_face_order_give_the_same_wireframe() {
    let (w, h) = scene3d::SIZE;
    let pipeline = scene3d::pipeline(scene3d::Model::Knot);
    let mesh = &scene3d::KNOT;
    let (whole, _) = hidden_lines(&pipeline, mesh, w, h);
    // Reversed faces: each shared edge handed over by the other face first.
    let reversed: Vec<[u16; 3]> = mesh.indices.iter().rev().copied().collect();
    let flipped = Mesh::new(mesh.vertices, mesh.normals, &reversed);
    let (other, _) = hidden_lines(&pipeline, &flipped, w, h);
    assert!(whole == other, "face order changed the wireframe");
    // With the scratch.
    let (mut px, mut z) = (
        vec![Rgb888::BLACK; (w * h) as usize],
        vec![0; (w * h) as usize],
    );
    let mut target = DepthTarget::new(&mut px, &mut z, w, h).unwrap();
    target.clear(Rgb888::BLACK);
    let mut scratch = vec![ProjectedVertex::EMPTY; mesh.vertices.len()];
    let faces = Material::new(Rgb888::BLACK, Shading::Unlit);
    pipeline
        .draw_mesh_with(mesh, &faces, &mut target, &mut scratch)
        .unwrap();
    pipeline
        .draw_wireframe_with(mesh, EDGE, &mut target, &mut scratch)
        .unwrap();
    assert!(whole == px, "the scratch changed the wireframe");
    // Too short a scratch: nothing drawn.
    let before = px.clone();
    let mut target = DepthTarget::new(&mut px, &mut z, w, h).unwrap();
    let short = &mut scratch[..10];
    assert!(pipeline
        .draw_wireframe_with(mesh, Rgb888::RED, &mut target, short)
        .is_err());
    assert!(before == px);
}

/// Without faces in the z-buffer every edge of every drawn face is visible: the pixels are
/// exactly the union of the faces' edges as 2D lines.
#[test]
fn on_an_empty_z_buffer_every_edge_is_drawn_whole() {
    let (w, h) = scene3d::SIZE;
    let pipeline = scene3d::pipeline(scene3d::Model::Spot);
    let mesh = &scene3d::SPOT;
    let (mut px, mut z) = (
        vec![Rgb888::BLACK; (w * h) as usize],
        vec![0; (w * h) as usize],
    );
    let mut target = DepthTarget::new(&mut px, &mut z, w, h).unwrap();
    target.clear(Rgb888::BLACK);
    pipeline.draw_wireframe(mesh, EDGE, &mut target);
    assert!(z.iter().all(|&d| d == DEPTH_CLEAR), "depth is not written");
    let mut want = vec![false; (w * h) as usize];
    for (s, edges) in kept_edges(&pipeline, mesh) {
        for (a, b) in edges {
            for (x, y) in line_pixels(&s[a], &s[b], w, h) {
                want[(y as u32 * w + x as u32) as usize] = true;
            }
        }
    }
    let got: Vec<bool> = px.iter().map(|&c| c == EDGE).collect();
    assert!(got == want, "the edges' pixels differ from the 2D lines'");
}

/// A floor through the camera's near plane, both sides drawn: every edge pixel lies within a
/// pixel of a grid line (f64, clipped to the near and far planes) and the lines' visible
/// lengths are drawn.
#[test]
fn clipped_faces_draw_only_their_own_edges() {
    const W: u32 = 160;
    const H: u32 = 120;
    let mut rng = Rng(0xfeed_0005);
    let viewport = Rectangle::new(Point::zero(), Size::new(W, H));
    let n = 12;
    let half = 30.0;
    let mut positions = Vec::new();
    for r in 0..=n {
        for c in 0..=n {
            let x = -half + 2.0 * half * c as f64 / n as f64;
            let y = -half + 2.0 * half * r as f64 / n as f64;
            positions.push([x, y, 0.0]);
        }
    }
    let grid = flat_grid(&positions, n);
    let mut clipped = 0;
    for _ in 0..6 {
        let pitch = Angle::from_degrees(rng.range_f64(-120.0, -60.0) as i32);
        let pos = [
            rng.range_f64(-2.0, 2.0),
            rng.range_f64(-1.5, -0.3),
            rng.range_f64(-3.0, -1.0),
        ];
        let view = View::new(
            Angle::from_degrees(70),
            0.2,
            40.0,
            Angle(rng.next() as u16),
            pitch,
            pos,
            viewport,
        );
        let mut pipeline = Pipeline::new(view.model, view.projection, viewport, Default::default());
        pipeline.cull = Cull::None;
        let mesh = Mesh::new(&grid.vertices, &grid.normals, &grid.indices);
        let (mut px, mut z) = (
            vec![Rgb888::BLACK; (W * H) as usize],
            vec![0; (W * H) as usize],
        );
        let mut target = DepthTarget::new(&mut px, &mut z, W, H).unwrap();
        target.clear(Rgb888::BLACK);
        let stats = pipeline.draw_wireframe(&mesh, EDGE, &mut target);
        clipped += stats.clipped;
        // The grid's edges in eye space, clipped to the near and far planes, on screen.
        let eye: Vec<[f64; 3]> = grid
            .vertices
            .iter()
            .map(|&v| apply(&view.model_view, bits3(v)))
            .collect();
        let (near, far) = (view.near, view.far);
        let mut segments = Vec::new();
        for face in &grid.indices {
            for j in 0..3 {
                let (mut a, mut b) = (
                    eye[usize::from(face[j])],
                    eye[usize::from(face[(j + 1) % 3])],
                );
                // Keep −far ≤ z ≤ −near.
                let mut keep = true;
                for (plane, sign) in [(-near, 1.0), (-far, -1.0)] {
                    let (da, db) = (sign * (plane - a[2]), sign * (plane - b[2]));
                    if da < 0.0 && db < 0.0 {
                        keep = false;
                        break;
                    }
                    if da < 0.0 || db < 0.0 {
                        let t = da / (da - db);
                        let p = [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]));
                        if da < 0.0 {
                            a = p;
                        } else {
                            b = p;
                        }
                    }
                }
                if keep {
                    segments.push((view.screen(a), view.screen(b)));
                }
            }
        }
        let distance = |(px, py): (f64, f64), ((ax, ay), (bx, by)): &((f64, f64), (f64, f64))| {
            let (dx, dy) = (bx - ax, by - ay);
            let len2 = dx * dx + dy * dy;
            let t = if len2 == 0.0 {
                0.0
            } else {
                (((px - ax) * dx + (py - ay) * dy) / len2).clamp(0.0, 1.0)
            };
            (px - ax - t * dx).hypot(py - ay - t * dy)
        };
        let mut drawn = 0;
        for y in 0..H {
            for x in 0..W {
                if px[(y * W + x) as usize] != EDGE {
                    continue;
                }
                drawn += 1;
                let c = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                let nearest = segments
                    .iter()
                    .map(|s| distance(c, s))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    nearest <= 1.0,
                    "pixel {x},{y} is {nearest} px from every grid line"
                );
            }
        }
        assert!(drawn > 200, "{drawn} pixels drawn");
    }
    assert!(clipped > 20, "{clipped} clipped faces");
}

/// The hidden-line knot drawn band by band (each band's rows of the faces, then of their edges,
/// with and without the scratch) at several heights: every band the whole frame's rows.
#[test]
fn bands_are_the_whole_wireframe() {
    use embedded_raster::band::{BandLayout, DepthBand};
    let (w, h) = scene3d::SIZE;
    let pipeline = scene3d::pipeline(scene3d::Model::Knot);
    let mesh = &scene3d::KNOT;
    let (want, want_depth) = hidden_lines(&pipeline, mesh, w, h);
    let faces = Material::new(Rgb888::BLACK, Shading::Unlit);
    let mut scratch = vec![ProjectedVertex::EMPTY; mesh.vertices.len()];
    for rows in [1, 7, 16, 33, 240] {
        let layout = BandLayout::new(Size::new(w, h), rows).unwrap();
        let n = layout.buffer_len();
        for with_scratch in [false, true] {
            let (mut colors, mut depth) = (vec![Rgb888::BLACK; n], vec![0u16; n]);
            let (mut got, mut got_depth) = (Vec::new(), Vec::new());
            for index in 0..layout.count() {
                let mut band = DepthBand::new(&mut colors, &mut depth, &layout, index).unwrap();
                band.clear(Rgb888::BLACK);
                if with_scratch {
                    pipeline
                        .draw_mesh_with(mesh, &faces, &mut band, &mut scratch)
                        .unwrap();
                    pipeline
                        .draw_wireframe_with(mesh, EDGE, &mut band, &mut scratch)
                        .unwrap();
                } else {
                    pipeline.draw_mesh(mesh, &faces, &mut band);
                    pipeline.draw_wireframe(mesh, EDGE, &mut band);
                }
                got.extend_from_slice(band.pixels());
                got_depth.extend_from_slice(band.depth());
            }
            assert!(
                got == want,
                "{rows}-row bands (scratch: {with_scratch}): colours differ"
            );
            assert!(got_depth == want_depth, "{rows}-row bands: depths differ");
        }
    }
}
