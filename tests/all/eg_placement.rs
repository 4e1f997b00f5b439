//! How closely `SolidTriangle::at_pixel_centres` matches an embedded-graphics filled `Triangle`
//! of the same points, measured against embedded-graphics itself (the independent reference):
//!
//! * every pixel we draw, embedded-graphics draws too;
//! * the pixels only embedded-graphics draws lie along the outline: their centres are within
//!   half a pixel of the triangle through the centres (the pixels its outline passes through);
//! * placing the points at pixel corners instead differs on more pixels, both ways.

use embedded_graphics::{
    pixelcolor::BinaryColor,
    prelude::*,
    primitives::{PrimitiveStyle, Triangle},
};
use embedded_raster::{SliceFramebuffer, SolidTriangle, Vertex};

use crate::rng;
use rng::Rng;

const W: u32 = 64;
const H: u32 = 64;

fn eg_pixels(points: [Point; 3]) -> Vec<bool> {
    let mut px = vec![BinaryColor::Off; (W * H) as usize];
    let mut fb = SliceFramebuffer::new(&mut px, W, H).unwrap();
    Triangle::new(points[0], points[1], points[2])
        .into_styled(PrimitiveStyle::with_fill(BinaryColor::On))
        .draw(&mut fb)
        .unwrap();
    px.iter().map(|c| c.is_on()).collect()
}

fn our_pixels(triangle: SolidTriangle<BinaryColor>) -> Vec<bool> {
    let mut px = vec![BinaryColor::Off; (W * H) as usize];
    let mut fb = SliceFramebuffer::new(&mut px, W, H).unwrap();
    triangle.draw_into(&mut fb);
    px.iter().map(|c| c.is_on()).collect()
}

/// Distance from `p` to the closed triangle `t` (0 inside), in f64.
fn distance(p: [f64; 2], t: [[f64; 2]; 3]) -> f64 {
    let cross = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let s = [
        cross(t[0], t[1], p),
        cross(t[1], t[2], p),
        cross(t[2], t[0], p),
    ];
    if s.iter().all(|&v| v >= 0.0) || s.iter().all(|&v| v <= 0.0) {
        return 0.0;
    }
    (0..3)
        .map(|k| {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let len2 = d[0] * d[0] + d[1] * d[1];
            let u = if len2 == 0.0 {
                0.0
            } else {
                (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
            };
            let q = [a[0] + u * d[0], a[1] + u * d[1]];
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn pixel_centres_match_embedded_graphics_but_for_the_outline() {
    let mut rng = Rng(0x6567_5f70);
    let (mut both, mut only_eg, mut corner_mismatch) = (0u64, 0u64, 0u64);
    let mut farthest = 0.0f64;
    for case in 0..3000 {
        // Points inside the target (embedded-graphics clips by dropping pixels, as we do) and a
        // few just outside it.
        let size = [4, 16, 70][case % 3];
        let (bx, by) = (rng.range(-3, 64 - size / 2), rng.range(-3, 64 - size / 2));
        let point = |rng: &mut Rng| {
            Point::new(
                (bx + rng.range(0, size)) as i32,
                (by + rng.range(0, size)) as i32,
            )
        };
        let points = [point(&mut rng), point(&mut rng), point(&mut rng)];
        let eg = eg_pixels(points);
        let ours = our_pixels(SolidTriangle::at_pixel_centres(points, BinaryColor::On));
        let corners = our_pixels(SolidTriangle::new(
            points.map(|p| Vertex::at_pixel_corner(p, ()).position()),
            BinaryColor::On,
        ));
        let centres = points.map(|p| [f64::from(p.x) + 0.5, f64::from(p.y) + 0.5]);
        for (i, (&e, &o)) in eg.iter().zip(&ours).enumerate() {
            corner_mismatch += u64::from(e != corners[i]);
            match (e, o) {
                (true, true) => both += 1,
                (false, true) => {
                    panic!(
                        "case {case}: pixel {i} drawn here, not by embedded-graphics: {points:?}"
                    )
                }
                (true, false) => {
                    only_eg += 1;
                    let (x, y) = (i as u32 % W, i as u32 / W);
                    let d = distance([f64::from(x) + 0.5, f64::from(y) + 0.5], centres);
                    farthest = farthest.max(d);
                    assert!(
                        d <= 0.5,
                        "case {case}: pixel ({x}, {y}) {d} px away: {points:?}"
                    );
                }
                (false, false) => {}
            }
        }
    }
    println!(
        "both {both}, only embedded-graphics {only_eg} (centres at most {farthest:.3} px from \
         the triangle), only ours 0; corner placement differs on {corner_mismatch}"
    );
    assert!(both > 100_000, "too few covered pixels: {both}");
    // The corner placement is worse.
    assert!(corner_mismatch > only_eg);
}
