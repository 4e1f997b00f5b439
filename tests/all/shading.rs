//! Shading against f64 references: the quadratic normal field (nodes, length, per-pixel
//! stepping), per-pixel and per-vertex Lambert lighting, interpolated depth and the depth test.

use embedded_graphics::{
    pixelcolor::{Gray8, Rgb888},
    prelude::*,
    primitives::Rectangle,
};
use embedded_raster::three_d::{
    draw_flat, draw_gouraud, draw_quadratic, shade, Light, QuadraticNormals,
};
use embedded_raster::three_d::{DepthTarget, ScreenVertex, DEPTH_CLEAR};
use embedded_raster::three_d::{Scalar, Vec3};
use embedded_raster::{Coord, SliceFramebuffer, SolidTriangle};

use crate::rng;
use rng::Rng;

impl Rng {
    fn gauss3(&mut self) -> [f64; 3] {
        // Sum of uniforms: direction only matters, any symmetric distribution will do.
        [0; 3].map(|_| (0..4).map(|_| self.unit() - 0.5).sum::<f64>())
    }
}

type V = [f64; 3];

fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(a: V, s: f64) -> V {
    a.map(|c| c * s)
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn len(a: V) -> f64 {
    dot(a, a).sqrt()
}
fn normalize(a: V) -> V {
    scale(a, 1.0 / len(a))
}
fn fx(v: V) -> Vec3 {
    let c = |x: f64| (x * 65536.0).round() as i32;
    Vec3::from_bits(c(v[0]), c(v[1]), c(v[2]))
}
fn fl(v: Vec3) -> V {
    v.to_bits().map(|c| f64::from(c) / 65536.0)
}

/// Three unit normals within `spread` (tangent offset) of a random axis: like the vertex normals
/// of one face of a smooth mesh.
fn normals(rng: &mut Rng, spread: f64) -> [V; 3] {
    let axis = normalize(rng.gauss3());
    [0; 3].map(|_| {
        let off = normalize(rng.gauss3());
        normalize(add(axis, scale(off, spread * rng.unit())))
    })
}

/// The f64 quadratic field with N̂ᵢⱼ = normalize(Nᵢ + Nⱼ).
fn quadratic_f64(n: &[V; 3], c: [f64; 3]) -> V {
    let mut v = [0.0; 3];
    for i in 0..3 {
        v = add(v, scale(n[i], c[i] * (2.0 * c[i] - 1.0)));
    }
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        v = add(v, scale(normalize(add(n[i], n[j])), 4.0 * c[i] * c[j]));
    }
    v
}

fn linear_f64(n: &[V; 3], c: [f64; 3]) -> V {
    add(add(scale(n[0], c[0]), scale(n[1], c[1])), scale(n[2], c[2]))
}

fn s(v: f64) -> Scalar {
    Scalar::from_bits((v * 65536.0).round() as i32)
}

#[test]
fn quadratic_field_hits_vertices_and_midpoints() {
    let mut rng = Rng(0x5eed_0001);
    let (one, half, zero) = (Scalar::ONE, Scalar::from_bits(1 << 15), Scalar::ZERO);
    for _ in 0..2000 {
        let spread = rng.range_f64(0.0, 1.5);
        let n = normals(&mut rng, spread);
        let input = n.map(fx);
        let q = QuadraticNormals::new(input);
        let exact = input.map(fl).map(normalize);
        let corners = [[one, zero, zero], [zero, one, zero], [zero, zero, one]];
        for (k, c) in corners.iter().enumerate() {
            let got = fl(q.at(*c));
            for i in 0..3 {
                assert!((got[i] - exact[k][i]).abs() <= 1.5 / 65536.0, "vertex {k}");
            }
        }
        let mids = [[half, half, zero], [zero, half, half], [half, zero, half]];
        for (k, c) in mids.iter().enumerate() {
            let (a, b) = [(0, 1), (1, 2), (2, 0)][k];
            let want = normalize(add(exact[a], exact[b]));
            let got = fl(q.at(*c));
            for i in 0..3 {
                assert!((got[i] - want[i]).abs() <= 2.5 / 65536.0, "midpoint {k}");
            }
        }
    }
}

/// The quadratic field stays much closer to unit length than linear interpolation of the same
/// vertex normals. Both are measured against f64; the fixed-point field itself is checked
/// against the f64 quadratic at every sample.
#[test]
fn quadratic_normals_keep_their_length() {
    let mut rng = Rng(0x5eed_0002);
    for &spread in &[0.2, 0.5, 0.8] {
        let (mut worst_quad, mut worst_lin) = (0.0f64, 0.0f64);
        let (mut sum_quad, mut sum_lin, mut samples) = (0.0, 0.0, 0);
        for _ in 0..300 {
            let n = normals(&mut rng, spread);
            let input = n.map(fx);
            let exact = input.map(fl).map(normalize);
            let q = QuadraticNormals::new(input);
            let (mut tri_quad, mut tri_lin) = (0.0f64, 0.0f64);
            for _ in 0..40 {
                let (a, b) = (rng.unit(), rng.unit());
                let (a, b) = if a + b > 1.0 {
                    (1.0 - a, 1.0 - b)
                } else {
                    (a, b)
                };
                let c = [a, b, 1.0 - a - b];
                let cs = [s(c[0]), s(c[1]), Scalar::ONE - s(c[0]) - s(c[1])];
                let cf = cs.map(|v| v.to_num::<f64>());
                let fixed = fl(q.at(cs));
                let want = quadratic_f64(&exact, cf);
                for i in 0..3 {
                    assert!((fixed[i] - want[i]).abs() < 2e-4, "{fixed:?} vs {want:?}");
                }
                let dq = (len(fixed) - 1.0).abs();
                let dl = (len(linear_f64(&exact, cf)) - 1.0).abs();
                tri_quad = tri_quad.max(dq);
                tri_lin = tri_lin.max(dl);
                sum_quad += dq;
                sum_lin += dl;
                samples += 1;
            }
            // Per face: the quadratic's worst deviation is a small fraction of the linear one's.
            assert!(
                tri_quad <= 0.15 * tri_lin + 1e-4,
                "spread {spread}: {tri_quad} vs {tri_lin}"
            );
            worst_quad = worst_quad.max(tri_quad);
            worst_lin = worst_lin.max(tri_lin);
        }
        let (mean_quad, mean_lin) = (sum_quad / samples as f64, sum_lin / samples as f64);
        println!(
            "spread {spread}: max |len−1| quadratic {worst_quad:.2e} linear {worst_lin:.2e}; \
             mean {mean_quad:.2e} vs {mean_lin:.2e}"
        );
        assert!(mean_quad < 0.1 * mean_lin);
    }
}

/// Exact barycentrics of the centre of pixel (i, j) in the triangle with raw vertices `p`.
fn barycentrics(p: &[(f64, f64); 3], i: i32, j: i32) -> [f64; 3] {
    let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
    let e = |a: (f64, f64), b: (f64, f64)| (b.0 - a.0) * (y - a.1) - (b.1 - a.1) * (x - a.0);
    let area = e(p[0], p[1]) + e(p[1], p[2]) + e(p[2], p[0]);
    [
        e(p[1], p[2]) / area,
        e(p[2], p[0]) / area,
        e(p[0], p[1]) / area,
    ]
}

fn random_triangle(rng: &mut Rng, w: f64, h: f64) -> [ScreenVertex; 3] {
    let big = rng.unit() < 0.5;
    let (cx, cy) = (rng.range_f64(0.0, w), rng.range_f64(0.0, h));
    [0; 3].map(|_| {
        let (x, y) = if big {
            (
                rng.range_f64(-0.3 * w, 1.3 * w),
                rng.range_f64(-0.3 * h, 1.3 * h),
            )
        } else {
            (
                cx + rng.range_f64(-12.0, 12.0),
                cy + rng.range_f64(-12.0, 12.0),
            )
        };
        ScreenVertex::new(
            Coord::from_num(x),
            Coord::from_num(y),
            rng.range_f64(0.0, 65534.0) as u16,
        )
    })
}

fn positions(t: &[ScreenVertex; 3]) -> [(f64, f64); 3] {
    t.map(|v| (v.x.to_num::<f64>(), v.y.to_num::<f64>()))
}

/// Pixels covered by a `SolidTriangle` with the same vertices.
fn coverage(t: &[ScreenVertex; 3], w: u32, h: u32) -> Vec<bool> {
    let mut px = vec![Gray8::BLACK; (w * h) as usize];
    let mut fb = SliceFramebuffer::new(&mut px, w, h).unwrap();
    SolidTriangle::new(t.map(|v| v.position()), Gray8::WHITE)
        .draw(&mut fb)
        .unwrap();
    px.iter().map(|p| p.luma() == 255).collect()
}

/// Per-pixel quadratic lighting and depth, on random triangles (small ones, and ones larger
/// than the 320-pixel-wide target, for long spans), against f64 evaluated at each pixel centre:
/// within 1 LSB of Gray8 (and of the interpolated depth), on exactly the covered pixels.
#[test]
fn per_pixel_lighting_matches_f64() {
    let (w, h) = (320u32, 60u32);
    let mut rng = Rng(0x5eed_0003);
    let mut px = vec![Gray8::BLACK; (w * h) as usize];
    let mut z = vec![0u16; (w * h) as usize];
    let clip = Rectangle::new(Point::zero(), Size::new(w, h));
    let (mut pixels, mut worst, mut worst_z) = (0u64, 0.0f64, 0.0f64);
    for _ in 0..400 {
        let tri = random_triangle(&mut rng, f64::from(w), f64::from(h));
        let spread = rng.range_f64(0.0, 0.9);
        let n = normals(&mut rng, spread);
        let input = n.map(fx);
        let light_dir = rng.gauss3();
        let ambient = if rng.unit() < 0.3 {
            0.0
        } else {
            rng.range_f64(0.0, 0.5)
        };
        let light = Light::new(fx(scale(normalize(light_dir), 3.0)), s(ambient));
        let q = QuadraticNormals::new(input);
        let mut target = DepthTarget::new(&mut px, &mut z, w, h).unwrap();
        target.clear(Gray8::BLACK);
        draw_quadratic(&mut target, &clip, &tri, &q, &light, Gray8::WHITE);

        let covered = coverage(&tri, w, h);
        let p = positions(&tri);
        let exact_n = input.map(fl).map(normalize);
        let l = normalize(light_dir);
        let amb = light.ambient().to_num::<f64>();
        for j in 0..h as i32 {
            for i in 0..w as i32 {
                let k = (j as u32 * w + i as u32) as usize;
                let depth = target.depth()[k];
                assert_eq!(depth != DEPTH_CLEAR, covered[k], "coverage at {i},{j}");
                if !covered[k] {
                    continue;
                }
                let c = barycentrics(&p, i, j);
                let nq = quadratic_f64(&exact_n, c);
                let diffuse = (dot(nq, l) / len(nq)).max(0.0);
                let want = 255.0 * (amb + (1.0 - amb) * diffuse);
                let got = f64::from(target.framebuffer().get(i, j).unwrap().luma());
                worst = worst.max((got - want).abs());
                assert!((got - want).abs() <= 1.0, "pixel {i},{j}: {got} vs {want}");
                let dz: f64 = (0..3).map(|m| c[m] * f64::from(tri[m].depth)).sum();
                worst_z = worst_z.max((f64::from(depth) - dz).abs());
                assert!(
                    (f64::from(depth) - dz).abs() <= 1.0,
                    "depth {depth} vs {dz}"
                );
                pixels += 1;
            }
        }
    }
    println!("{pixels} pixels; worst error {worst:.3} LSB, depth {worst_z:.3} LSB");
    assert!(pixels > 500_000);
    // ½ LSB of final rounding; normal stepping, quantisation and inv_sqrt add well under 0.1.
    assert!(worst < 0.6 && worst_z < 0.6);
}

/// Gouraud fills (per-vertex lit colours) and flat fills against f64.
#[test]
fn gouraud_and_flat_fills_match_f64() {
    let (w, h) = (96u32, 80u32);
    let mut rng = Rng(0x5eed_0004);
    let mut px = vec![Rgb888::BLACK; (w * h) as usize];
    let mut z = vec![0u16; (w * h) as usize];
    let clip = Rectangle::new(Point::zero(), Size::new(w, h));
    for round in 0..600 {
        let tri = random_triangle(&mut rng, f64::from(w), f64::from(h));
        let base = Rgb888::new(
            rng.range_f64(0.0, 256.0) as u8,
            rng.range_f64(0.0, 256.0) as u8,
            rng.range_f64(0.0, 256.0) as u8,
        );
        let light = Light::new(fx(normalize(rng.gauss3())), s(rng.range_f64(0.0, 0.4)));
        let n = normals(&mut rng, 1.0).map(fx);
        let levels = n.map(|n| light.level(n.normalize()));
        let colors = levels.map(|l| shade(base, l));
        let mut target = DepthTarget::new(&mut px, &mut z, w, h).unwrap();
        target.clear(Rgb888::BLACK);
        let flat = round % 2 == 1;
        if flat {
            draw_flat(&mut target, &clip, &tri, colors[0]);
        } else {
            draw_gouraud(&mut target, &clip, &tri, colors);
        }
        let covered = coverage(&tri, w, h);
        let p = positions(&tri);
        // Independent f64 levels from the same inputs.
        let l = normalize(fl(light.direction()));
        let amb = light.ambient().to_num::<f64>();
        let lvl = n.map(|n| amb + (1.0 - amb) * dot(normalize(fl(n)), l).max(0.0));
        let chan = |c: Rgb888| [c.r(), c.g(), c.b()].map(f64::from);
        let base_c = chan(base);
        for j in 0..h as i32 {
            for i in 0..w as i32 {
                let k = (j as u32 * w + i as u32) as usize;
                assert_eq!(target.depth()[k] != DEPTH_CLEAR, covered[k]);
                if !covered[k] {
                    continue;
                }
                let got = chan(target.framebuffer().get(i, j).unwrap());
                let c = barycentrics(&p, i, j);
                for ch in 0..3 {
                    let want = if flat {
                        base_c[ch] * lvl[0]
                    } else {
                        (0..3).map(|m| c[m] * base_c[ch] * lvl[m]).sum::<f64>()
                    };
                    // Rounding the vertex colours (½) plus interpolation (½ + ε).
                    let tol = if flat { 0.51 } else { 1.01 };
                    assert!(
                        (got[ch] - want).abs() <= tol,
                        "{i},{j} ch {ch}: {} vs {want}",
                        got[ch]
                    );
                }
            }
        }
    }
}

/// Smaller depth wins; equal depth keeps what was drawn first.
#[test]
fn depth_test_keeps_the_nearest() {
    let (w, h) = (32u32, 32u32);
    let mut px = vec![Gray8::BLACK; 1024];
    let mut z = vec![0u16; 1024];
    let mut target = DepthTarget::new(&mut px, &mut z, w, h).unwrap();
    target.clear(Gray8::BLACK);
    let clip = Rectangle::new(Point::zero(), Size::new(w, h));
    let tri = |d: [u16; 3]| {
        let c =
            |x: i32, y: i32, d: u16| ScreenVertex::new(Coord::from_num(x), Coord::from_num(y), d);
        [c(0, 0, d[0]), c(32, 0, d[1]), c(0, 32, d[2])]
    };
    draw_flat(&mut target, &clip, &tri([100; 3]), Gray8::new(1));
    draw_flat(&mut target, &clip, &tri([200; 3]), Gray8::new(2));
    draw_flat(&mut target, &clip, &tri([100; 3]), Gray8::new(3));
    assert_eq!(target.framebuffer().get(3, 3), Some(Gray8::new(1)));
    draw_flat(&mut target, &clip, &tri([99; 3]), Gray8::new(4));
    assert_eq!(target.framebuffer().get(3, 3), Some(Gray8::new(4)));
    assert_eq!(target.depth_at(3, 3), Some(99));
    // A sloped triangle crossing depth 99: wins where its depth is below, loses elsewhere.
    draw_flat(&mut target, &clip, &tri([0, 198, 0]), Gray8::new(5));
    for i in 0..16 {
        let want = if (2 * i + 1) as f64 * 198.0 / 64.0 < 99.0 {
            5
        } else {
            4
        };
        assert_eq!(
            target.framebuffer().get(i, 0),
            Some(Gray8::new(want)),
            "{i}"
        );
    }
    // Nothing outside the clip rectangle is touched.
    let small = Rectangle::new(Point::new(4, 4), Size::new(4, 4));
    target.clear(Gray8::BLACK);
    draw_flat(&mut target, &small, &tri([7; 3]), Gray8::WHITE);
    let drawn: Vec<_> = (0..32 * 32)
        .filter(|k| target.depth()[*k] != DEPTH_CLEAR)
        .map(|k| (k % 32, k / 32))
        .collect();
    assert_eq!(drawn.len(), 16);
    assert!(drawn
        .iter()
        .all(|&(x, y)| (4..8).contains(&x) && (4..8).contains(&y)));
}

/// A light built from its public fields with a direction of any magnitude (here `i32::MAX` on x)
/// still lights a surface facing it fully; it used to overflow (a panic in debug builds, a black
/// pixel in release).
#[test]
fn quadratic_fill_takes_any_light_direction() {
    let (mut px, mut z) = ([Gray8::BLACK; 16 * 16], [0u16; 16 * 16]);
    let mut target = DepthTarget::new(&mut px, &mut z, 16, 16).unwrap();
    target.clear(Gray8::BLACK);
    // Its fields are private now: the constructor normalises any direction.
    let light = Light::new(Vec3::from_bits(i32::MAX, 0, 0), Scalar::ZERO);
    assert_eq!(light.direction(), Vec3::from_bits(1 << 16, 0, 0));
    let normals = QuadraticNormals::new([Vec3::from_bits(1 << 16, 0, 0); 3]);
    let v = |x: i32, y: i32| ScreenVertex::new(Coord::from_num(x), Coord::from_num(y), 1000);
    let clip = Rectangle::new(Point::zero(), Size::new(16, 16));
    let triangle = [v(0, 0), v(16, 0), v(0, 16)];
    draw_quadratic(
        &mut target,
        &clip,
        &triangle,
        &normals,
        &light,
        Gray8::WHITE,
    );
    assert_eq!(target.framebuffer().get(2, 2), Some(Gray8::WHITE));
}
