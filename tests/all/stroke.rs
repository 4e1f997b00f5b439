//! Wide lines against f64 references:
//!
//! * round caps and joins: a pixel is drawn where its centre is within half the width of the
//!   polyline (the stroke's exact shape), but for centres near that boundary — within the
//!   32-gon's shortfall from the circle and the corners' rounding to 1/256 px (counted);
//! * every cap and join: the union of the pieces the docs describe (rectangles, square ends,
//!   bevel triangles, miter quads up to the limit, 32-gons), built in f64 from the points, but
//!   for centres within 1/64 px of a piece's edge (counted);
//! * `draw` and `draw_into` agree.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_raster::{Cap, Join, Polyline, SliceFramebuffer, Stroke};

use crate::rng::Rng;

const W: u32 = 64;
const H: u32 = 48;

type P = (f64, f64);

fn drawn(points: &[P], stroke: Stroke) -> Vec<bool> {
    let mut pixels = vec![Rgb565::BLACK; (W * H) as usize];
    let mut fb = SliceFramebuffer::new(&mut pixels, W, H).unwrap();
    Polyline::new(points, Rgb565::WHITE)
        .stroked(stroke)
        .draw_into(&mut fb);
    pixels.iter().map(|&c| c == Rgb565::WHITE).collect()
}

/// The points as the crate sees them (rounded to 1/256 px).
fn snapped(points: &[P]) -> Vec<P> {
    points
        .iter()
        .map(|&(x, y)| ((x * 256.0).round() / 256.0, (y * 256.0).round() / 256.0))
        .collect()
}

fn distance_to_segment(p: P, a: P, b: P) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((a.0 + t * dx - p.0).powi(2) + (a.1 + t * dy - p.1).powi(2)).sqrt()
}

impl Rng {
    fn stroke_points(&mut self) -> Vec<P> {
        let n = 2 + self.below(5) as usize;
        let mut p = (self.range_f64(4.0, 60.0), self.range_f64(4.0, 44.0));
        let mut points = vec![p];
        for _ in 1..n {
            p = (
                (p.0 + self.range_f64(-25.0, 25.0)).clamp(-5.0, 70.0),
                (p.1 + self.range_f64(-25.0, 25.0)).clamp(-5.0, 55.0),
            );
            points.push(p);
        }
        points
    }
}

#[test]
fn round_strokes_are_the_points_within_half_the_width() {
    let mut rng = Rng(0x57e0_0001);
    let (mut compared, mut near) = (0u64, 0u64);
    for _ in 0..400 {
        let points = snapped(&rng.stroke_points());
        let width = rng.range_f64(1.0, 12.0);
        let stroke = Stroke::new(width)
            .with_cap(Cap::Round)
            .with_join(Join::Round);
        let h = (width * 256.0).round() as i64 / 2;
        let h = h as f64 / 256.0;
        let got = drawn(&points, stroke);
        // The 32-gon reaches the circle at its corners and falls short by h·(1 − cos(π/32))
        // between them; corners are within 1/256 px.
        let tolerance = h * (1.0 - (std::f64::consts::PI / 32.0).cos()) + 1.0 / 64.0;
        for j in 0..H {
            for i in 0..W {
                let c = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                let d = points
                    .windows(2)
                    .map(|w| distance_to_segment(c, w[0], w[1]))
                    .fold(f64::MAX, f64::min);
                if (d - h).abs() < tolerance {
                    near += 1;
                    continue;
                }
                compared += 1;
                assert_eq!(
                    got[(j * W + i) as usize],
                    d < h,
                    "({i}, {j}) {points:?} {width}"
                );
            }
        }
    }
    assert!(near * 20 < compared, "{near} near the edge of {compared}");
}

/// The pieces in f64, as the docs define them.
fn pieces(points: &[P], width: f64, cap: Cap, join: Join) -> Vec<Vec<P>> {
    let h = ((width * 256.0).round() as i64 / 2) as f64 / 256.0;
    let mut distinct: Vec<P> = vec![];
    for &p in points {
        if distinct.last() != Some(&p) {
            distinct.push(p);
        }
    }
    let disk = |p: P| -> Vec<P> {
        (0..32)
            .map(|k| {
                let t = f64::from(k) * std::f64::consts::PI / 16.0;
                (p.0 + h * t.cos(), p.1 + h * t.sin())
            })
            .collect()
    };
    let mut out = vec![];
    let normal = |a: P, b: P| {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = (dx * dx + dy * dy).sqrt();
        (-dy * h / len, dx * h / len)
    };
    let n = distinct.len();
    for k in 0..n.saturating_sub(1) {
        let (a, b) = (distinct[k], distinct[k + 1]);
        let nv = normal(a, b);
        let t = (nv.1, -nv.0);
        let (mut s, mut e) = (a, b);
        if cap == Cap::Square {
            if k == 0 {
                s = (a.0 - t.0, a.1 - t.1);
            }
            if k + 2 == n {
                e = (b.0 + t.0, b.1 + t.1);
            }
        }
        out.push(vec![
            (s.0 + nv.0, s.1 + nv.1),
            (e.0 + nv.0, e.1 + nv.1),
            (e.0 - nv.0, e.1 - nv.1),
            (s.0 - nv.0, s.1 - nv.1),
        ]);
        if k > 0 {
            let n0 = normal(distinct[k - 1], a);
            let d1 = (b.0 - a.0, b.1 - a.1);
            match join {
                Join::Round => out.push(disk(a)),
                _ => {
                    let turn = n0.0 * d1.0 + n0.1 * d1.1;
                    if turn != 0.0 {
                        let s = if turn > 0.0 { -1.0 } else { 1.0 };
                        let (o0, o1) = ((s * n0.0, s * n0.1), (s * nv.0, s * nv.1));
                        let dot = n0.0 * nv.0 + n0.1 * nv.1;
                        let den = h * h + dot;
                        if join == Join::Miter && 8.0 * den >= h * h && den > 0.0 {
                            let tip = ((o0.0 + o1.0) * h * h / den, (o0.1 + o1.1) * h * h / den);
                            out.push(vec![
                                a,
                                (a.0 + o0.0, a.1 + o0.1),
                                (a.0 + tip.0, a.1 + tip.1),
                                (a.0 + o1.0, a.1 + o1.1),
                            ]);
                        } else {
                            out.push(vec![a, (a.0 + o0.0, a.1 + o0.1), (a.0 + o1.0, a.1 + o1.1)]);
                        }
                    }
                }
            }
        }
    }
    if cap == Cap::Round && n >= 2 {
        out.push(disk(distinct[0]));
        out.push(disk(distinct[n - 1]));
    }
    out
}

/// Whether `p` is inside the convex polygon `q` (either orientation), and its distance to the
/// nearest edge.
fn inside_convex(p: P, q: &[P]) -> (bool, f64) {
    let (mut pos, mut neg, mut nearest) = (false, false, f64::MAX);
    for k in 0..q.len() {
        let (a, b) = (q[k], q[(k + 1) % q.len()]);
        let cross = (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
        pos |= cross > 0.0;
        neg |= cross < 0.0;
        nearest = nearest.min(distance_to_segment(p, a, b));
    }
    (!(pos && neg), nearest)
}

#[test]
fn every_cap_and_join_is_the_union_of_its_pieces() {
    let mut rng = Rng(0x57e0_0002);
    let (mut compared, mut near) = (0u64, 0u64);
    for case in 0..900 {
        let points = snapped(&rng.stroke_points());
        let width = rng.range_f64(1.0, 10.0);
        let cap = [Cap::Butt, Cap::Square, Cap::Round][case % 3];
        let join = [Join::Miter, Join::Bevel, Join::Round][(case / 3) % 3];
        let stroke = Stroke::new(width).with_cap(cap).with_join(join);
        let got = drawn(&points, stroke);
        let reference = pieces(&points, width, cap, join);
        for j in 0..H {
            for i in 0..W {
                let c = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                let (mut inside, mut edge) = (false, f64::MAX);
                for q in &reference {
                    let (hit, d) = inside_convex(c, q);
                    inside |= hit;
                    edge = edge.min(d);
                }
                if edge < 1.0 / 64.0 {
                    near += 1;
                    continue;
                }
                compared += 1;
                assert_eq!(
                    got[(j * W + i) as usize],
                    inside,
                    "({i}, {j}) {points:?} {width} {cap:?} {join:?}"
                );
            }
        }
    }
    assert!(near * 50 < compared, "{near} near an edge of {compared}");
}

#[test]
fn draw_and_draw_into_agree() {
    let mut rng = Rng(0x57e0_0003);
    for case in 0..200 {
        let points = rng.stroke_points();
        let stroke = Stroke::new(rng.range_f64(0.5, 9.0))
            .with_cap([Cap::Butt, Cap::Square, Cap::Round][case % 3])
            .with_join([Join::Miter, Join::Bevel, Join::Round][case % 3]);
        let line = Polyline::new(&points, Rgb565::GREEN).stroked(stroke);
        let mut a = vec![Rgb565::BLACK; (W * H) as usize];
        let mut b = a.clone();
        line.draw(&mut SliceFramebuffer::new(&mut a, W, H).unwrap())
            .unwrap();
        line.draw_into(&mut SliceFramebuffer::new(&mut b, W, H).unwrap());
        assert_eq!(a, b);
    }
    // Degenerate input draws nothing and does not panic.
    let mut pixels = vec![Rgb565::BLACK; (W * H) as usize];
    let mut fb = SliceFramebuffer::new(&mut pixels, W, H).unwrap();
    for (points, width) in [
        (vec![(3.0, 3.0)], 4.0),
        (vec![(3.0, 3.0), (3.0, 3.0)], 4.0),
        (vec![(3.0, 3.0), (9.0, 3.0)], 0.0),
        (vec![(3.0, 3.0), (9.0, 3.0)], -2.0),
        (vec![(-8e6, -8e6), (8e6, 8e6), (-8e6, 8e6)], 1e6),
    ] {
        Polyline::new(&points, Rgb565::RED)
            .stroked(Stroke::new(width).with_cap(Cap::Round))
            .draw_into(&mut fb);
    }
    assert!(pixels
        .iter()
        .take(1)
        .all(|&c| c == Rgb565::BLACK || c == Rgb565::RED));
}

/// Bands of every height, directly and through a bin, give the frame's pixels.
#[test]
fn bands_equal_the_whole_frame() {
    let mut rng = Rng(0x57e0_0004);
    for case in 0..30 {
        let points = rng.stroke_points();
        let stroke = Stroke::new(rng.range_f64(0.5, 9.0))
            .with_cap([Cap::Butt, Cap::Square, Cap::Round][case % 3])
            .with_join([Join::Miter, Join::Bevel, Join::Round][(case / 3) % 3]);
        let line = Polyline::new(&points, Rgb565::GREEN).stroked(stroke);
        let mut whole = vec![Rgb565::BLACK; (W * H) as usize];
        line.draw_into(&mut SliceFramebuffer::new(&mut whole, W, H).unwrap());
        crate::banded::check_bands_2d(&[line], &whole, Size::new(W, H));
    }
}
