//! The exact area of a pixel square inside a triangle, in `f64`: what anti-aliased edges are
//! tested against.
//!
//! The square `[i, i+1) × [j, j+1)` is clipped by the triangle's three edges as a polygon
//! (Sutherland–Hodgman) and its area taken by the shoelace formula. Each edge is the line
//! `A·u + B·v + C = 0` in pixel units around the square's centre, with `C` formed exactly in
//! integers at the centre and rounded once, so that vertices anywhere in the `i32` range give the
//! area to about 10⁻¹² of a pixel.

use std::vec;
use std::vec::Vec;

/// The area (in `[0, 1]`) of the square of pixel `(px, py)` inside the triangle `v` (raw
/// sub-pixel coordinates, either winding); 0 for a zero-area triangle.
pub fn pixel_area(v: [(i32, i32); 3], px: i32, py: i32) -> f64 {
    let p = v.map(|(x, y)| (i128::from(x), i128::from(y)));
    let area2 = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[1].1 - p[0].1) * (p[2].0 - p[0].0);
    if area2 == 0 {
        return 0.0;
    }
    let centre = (i128::from(px) * 256 + 128, i128::from(py) * 256 + 128);
    let mut polygon = vec![(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)];
    for k in 0..3 {
        let (a, b) = (p[k], p[(k + 1) % 3]);
        // The inside of edge a → b is where the cross product has area2's sign.
        let sign = area2.signum();
        let cross = |x: i128, y: i128| (b.0 - a.0) * (y - a.1) - (b.1 - a.1) * (x - a.0);
        // In pixel units around the centre: L(u, v) = (cross at the centre + 256·(A u + B v)) / 256².
        let c = (sign * cross(centre.0, centre.1)) as f64 / 65536.0;
        let gu = (sign * -(b.1 - a.1)) as f64 / 256.0;
        let gv = (sign * (b.0 - a.0)) as f64 / 256.0;
        let line = |(u, v): (f64, f64)| c + gu * u + gv * v;
        polygon = clip(&polygon, line);
        if polygon.is_empty() {
            return 0.0;
        }
    }
    let n = polygon.len();
    let twice: f64 = (0..n)
        .map(|i| {
            let (a, b) = (polygon[i], polygon[(i + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum();
    (twice / 2.0).abs().min(1.0)
}

/// The part of `polygon` where `line ≥ 0`.
fn clip(polygon: &[(f64, f64)], line: impl Fn((f64, f64)) -> f64) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(polygon.len() + 2);
    for i in 0..polygon.len() {
        let (p, q) = (polygon[i], polygon[(i + 1) % polygon.len()]);
        let (lp, lq) = (line(p), line(q));
        if lp >= 0.0 {
            out.push(p);
        }
        if (lp >= 0.0) != (lq >= 0.0) {
            let t = lp / (lp - lq);
            out.push((p.0 + (q.0 - p.0) * t, p.1 + (q.1 - p.1) * t));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simple_areas() {
        // The triangle (0,0), (2,0), (0,2) in pixels: pixel (0,0) whole, (1,0) half, (1,1) none.
        let v = [(0, 0), (512, 0), (0, 512)];
        assert!((pixel_area(v, 0, 0) - 1.0).abs() < 1e-12);
        assert!((pixel_area(v, 1, 0) - 0.5).abs() < 1e-12);
        assert!((pixel_area(v, 0, 1) - 0.5).abs() < 1e-12);
        assert!(pixel_area(v, 1, 1).abs() < 1e-12);
        // Either winding.
        assert!((pixel_area([(0, 0), (0, 512), (512, 0)], 1, 0) - 0.5).abs() < 1e-12);
        // A triangle inside one pixel: its own area.
        let small = [(10, 10), (200, 30), (50, 240)];
        let area = ((190.0 * 230.0) - (20.0 * 40.0)) / 2.0 / 65536.0;
        assert!((pixel_area(small, 0, 0) - area).abs() < 1e-12);
        // Huge: a half-plane through the pixel's diagonal.
        let huge = [
            (i32::MIN, i32::MIN),
            (i32::MAX, i32::MAX),
            (i32::MIN, i32::MAX),
        ];
        let a = pixel_area(huge, 3, 3);
        assert!((a - 0.5).abs() < 1e-6, "{a}");
    }
}
