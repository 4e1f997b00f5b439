//! Thin lines against independent references:
//!
//! * the diamond-exit rule evaluated pixel by pixel, exactly, by membership of points: a segment
//!   meets a diamond (a convex set cut by four lines) if and only if one of its ends, one of the
//!   points where it crosses those lines, or a point between two such crossings is in it —
//!   every point tested with integers, no interval arithmetic shared with the crate;
//! * Bresenham's line without its last pixel for ends on pixel centres (the rule's reduction);
//! * a segment split at a point on it draws exactly its pixels, none twice;
//! * `draw` and `draw_into` agree.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::{Coord, Line, Polyline, SliceFramebuffer};
use std::collections::BTreeSet;

use crate::rng::Rng;

const W: u32 = 40;
const H: u32 = 32;

fn clip() -> Rectangle {
    Rectangle::new(Point::zero(), Size::new(W, H))
}

fn pixels(a: (i32, i32), b: (i32, i32), clip: &Rectangle) -> BTreeSet<(i32, i32)> {
    let line = Line::new(
        (Coord::from_bits(a.0), Coord::from_bits(a.1)),
        (Coord::from_bits(b.0), Coord::from_bits(b.1)),
        Rgb565::WHITE,
    );
    let mut set = BTreeSet::new();
    line.for_each_span(clip, |y, x0, x1| {
        assert!(x0 < x1);
        for x in x0..x1 {
            assert!(set.insert((x, y)), "({x}, {y}) twice");
        }
    });
    set
}

/// Whether the rational point `(x / d, y / d)` (sub-pixels, `d > 0`) is in the diamond test area
/// of the pixel centred at `(cx, cy)`.
fn in_diamond(x: i128, y: i128, d: i128, (cx, cy): (i128, i128), y_major: bool) -> bool {
    let (u, v) = (x - cx * d, y - cy * d);
    let h = 128 * d;
    let inside = u + v <= h && v - u <= h && u - v < h && -u - v < h;
    inside || (y_major && u == h && v == 0)
}

/// The diamond-exit rule for pixel `(i, j)`, by membership of the critical points.
fn reference(a: (i64, i64), b: (i64, i64), (i, j): (i64, i64)) -> bool {
    let y_major = (b.1 - a.1).abs() > (b.0 - a.0).abs();
    let c = (i128::from(i) * 256 + 128, i128::from(j) * 256 + 128);
    let (ax, ay) = (i128::from(a.0), i128::from(a.1));
    let (dx, dy) = (i128::from(b.0 - a.0), i128::from(b.1 - a.1));
    // Where the segment crosses each of the diamond's four lines (α·u + β·v = 128): t = n/d.
    let mut ts: Vec<(i128, i128)> = vec![(0, 1), (1, 1)];
    for (alpha, beta) in [(1, 1), (-1, 1), (1, -1), (-1, -1)] {
        let num = 128 - (alpha * (ax - c.0) + beta * (ay - c.1));
        let den = alpha * dx + beta * dy;
        if den != 0 {
            let (num, den) = if den < 0 { (-num, -den) } else { (num, den) };
            if num >= 0 && num <= den {
                ts.push((num, den));
            }
        }
    }
    // The right corner, for y-major segments: a point, not a line.
    ts.sort_by(|p, q| (p.0 * q.1).cmp(&(q.0 * p.1)));
    let mut points = ts.clone();
    for w in ts.windows(2) {
        let ((n0, d0), (n1, d1)) = (w[0], w[1]);
        points.push((n0 * d1 + n1 * d0, 2 * d0 * d1));
    }
    let at = |(n, d): (i128, i128)| (ax * d + dx * n, ay * d + dy * n, d);
    let meets = points.iter().any(|&t| {
        let (x, y, d) = at(t);
        in_diamond(x, y, d, c, y_major)
    }) || (y_major && {
        // The segment through the right corner (128, 0).
        let (cu, cv) = (c.0 + 128 - ax, c.1 - ay);
        cu * dy - cv * dx == 0 && {
            let dot = cu * dx + cv * dy;
            (0..=dx * dx + dy * dy).contains(&dot)
        }
    });
    meets && !in_diamond(i128::from(b.0), i128::from(b.1), 1, c, y_major)
}

fn check(a: (i32, i32), b: (i32, i32), clip: &Rectangle) {
    let got = pixels(a, b, clip);
    let wide = |p: (i32, i32)| (i64::from(p.0), i64::from(p.1));
    // The box of the segment and two pixels around it, inside the clip.
    let (x0, x1) = (a.0.min(b.0) >> 8, a.0.max(b.0) >> 8);
    let (y0, y1) = (a.1.min(b.1) >> 8, a.1.max(b.1) >> 8);
    let c = clip;
    let xs = (x0.saturating_sub(2)).max(c.top_left.x)
        ..=(x1.saturating_add(2)).min(c.top_left.x + c.size.width as i32 - 1);
    let ys = (y0.saturating_sub(2)).max(c.top_left.y)
        ..=(y1.saturating_add(2)).min(c.top_left.y + c.size.height as i32 - 1);
    let mut expected = BTreeSet::new();
    for y in ys.clone() {
        for x in xs.clone() {
            if reference(wide(a), wide(b), (x.into(), y.into())) {
                expected.insert((x, y));
            }
        }
    }
    assert_eq!(got, expected, "{a:?} → {b:?}");
}

impl Rng {
    /// A raw sub-pixel coordinate in and around `0..extent` px, often on the lattice of
    /// centres, corners or diamond corners (ties).
    fn line_coordinate(&mut self, extent: u32) -> i32 {
        let e = i64::from(extent);
        match self.below(6) {
            0 => (self.range(-2, e + 2) * 256 + 128) as i32,
            1 => (self.range(-2, e + 2) * 256) as i32,
            2 => (self.range(-2, e + 2) * 256 + [0, 128, 255, 1][self.below(4) as usize]) as i32,
            _ => self.range(-512, e * 256 + 512) as i32,
        }
    }
}

#[test]
fn random_lines_follow_the_diamond_exit_rule() {
    let mut rng = Rng(0x11e5_0001);
    for case in 0..20_000 {
        let a = (rng.line_coordinate(W), rng.line_coordinate(H));
        let b = match case % 4 {
            // Short segments: both ends in a few pixels.
            0 => (
                a.0 + rng.range(-600, 600) as i32,
                a.1 + rng.range(-600, 600) as i32,
            ),
            // Slope ±1 exactly (the x-major boundary) and axis-aligned.
            1 => {
                let d = rng.range(-3000, 3000) as i32;
                match rng.below(3) {
                    0 => (a.0 + d, a.1 + d),
                    1 => (a.0 + d, a.1 - d),
                    _ => (a.0 + d, a.1),
                }
            }
            _ => (rng.line_coordinate(W), rng.line_coordinate(H)),
        };
        check(a, b, &clip());
    }
}

#[test]
fn clipped_and_huge_lines_follow_the_rule() {
    let mut rng = Rng(0x11e5_0002);
    for _ in 0..2000 {
        let far = |rng: &mut Rng| rng.range(-2_000_000, 2_000_000) as i32;
        let a = (far(&mut rng), far(&mut rng));
        // Through the clip's neighbourhood: the other end mirrored about a point inside.
        let m = (rng.line_coordinate(W), rng.line_coordinate(H));
        let b = (
            (2 * i64::from(m.0) - i64::from(a.0)) as i32,
            (2 * i64::from(m.1) - i64::from(a.1)) as i32,
        );
        let clip = Rectangle::new(
            Point::new(rng.range(-8, 8) as i32, rng.range(-8, 8) as i32),
            Size::new(
                1 + rng.below(W as u64) as u32,
                1 + rng.below(H as u64) as u32,
            ),
        );
        check(a, b, &clip);
    }
    // The ends of the coordinate range draw without overflow.
    for (a, b) in [
        ((i32::MIN, i32::MIN), (i32::MAX, i32::MAX)),
        ((i32::MAX, 300), (i32::MIN, 500)),
        ((100, i32::MIN), (900, i32::MAX)),
    ] {
        let _ = pixels(a, b, &clip());
    }
}

/// Ends on pixel centres: Bresenham's line from the first pixel, without the last one. At a
/// column whose crossing is halfway between two rows, the upper pixel (its diamond's bottom
/// corner is included); y-major, halfway between two columns, the left pixel (right corner).
#[test]
fn lines_between_centres_are_bresenham_without_the_last_pixel() {
    let mut rng = Rng(0x11e5_0003);
    for _ in 0..5000 {
        let p = |rng: &mut Rng| (rng.range(0, 39), rng.range(0, 31));
        let (a, b) = (p(&mut rng), p(&mut rng));
        if a == b {
            continue;
        }
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let mut expected = BTreeSet::new();
        if dy.abs() <= dx.abs() {
            let s = dx.signum();
            let mut x = a.0;
            while x != b.0 {
                // y = a.1 + (x − a.0)·dy/dx; the pixel j with j − ½ < y ≤ j + ½.
                let (n, d) = ((x - a.0) * dy * s, dx * s); // y − a.1 = n / d, d > 0
                let j = a.1 + (2 * n - d).div_euclid(2 * d) + 1;
                let j = if (2 * n - d).rem_euclid(2 * d) == 0 {
                    j - 1
                } else {
                    j
                };
                expected.insert((x as i32, j as i32));
                x += s;
            }
        } else {
            let s = dy.signum();
            let mut y = a.1;
            while y != b.1 {
                let (n, d) = ((y - a.1) * dx * s, dy * s);
                let i = a.0 + (2 * n - d).div_euclid(2 * d) + 1;
                let i = if (2 * n - d).rem_euclid(2 * d) == 0 {
                    i - 1
                } else {
                    i
                };
                expected.insert((i as i32, y as i32));
                y += s;
            }
        }
        let centre = |(x, y): (i64, i64)| ((x * 256 + 128) as i32, (y * 256 + 128) as i32);
        assert_eq!(
            pixels(centre(a), centre(b), &clip()),
            expected,
            "{a:?} → {b:?}"
        );
    }
}

/// A segment split at a point exactly on it: the two halves draw the whole segment's pixels,
/// and no pixel twice.
#[test]
fn split_segments_neither_double_nor_skip() {
    let mut rng = Rng(0x11e5_0004);
    for _ in 0..10_000 {
        let a = (rng.line_coordinate(W), rng.line_coordinate(H));
        let n = 2 + rng.below(6) as i32;
        let step = (rng.range(-900, 900) as i32, rng.range(-900, 900) as i32);
        let b = (a.0 + n * step.0, a.1 + n * step.1);
        let k = 1 + rng.below(n as u64 - 1) as i32;
        let m = (a.0 + k * step.0, a.1 + k * step.1);
        let whole = pixels(a, b, &clip());
        let first = pixels(a, m, &clip());
        let second = pixels(m, b, &clip());
        assert!(first.is_disjoint(&second), "{a:?} {m:?} {b:?}");
        let union: BTreeSet<_> = first.union(&second).copied().collect();
        assert_eq!(union, whole, "{a:?} {m:?} {b:?}");
    }
}

#[test]
fn draw_and_draw_into_agree() {
    let mut rng = Rng(0x11e5_0005);
    for _ in 0..500 {
        let points: Vec<(Coord, Coord)> = (0..2 + rng.below(6))
            .map(|_| {
                (
                    Coord::from_bits(rng.line_coordinate(W)),
                    Coord::from_bits(rng.line_coordinate(H)),
                )
            })
            .collect();
        let mut a = vec![Rgb565::BLACK; (W * H) as usize];
        let mut b = a.clone();
        let line = Polyline::new(&points, Rgb565::GREEN);
        line.draw(&mut SliceFramebuffer::new(&mut a, W, H).unwrap())
            .unwrap();
        line.draw_into(&mut SliceFramebuffer::new(&mut b, W, H).unwrap());
        assert_eq!(a, b);
        // Each segment's pixels are the polyline's (they may overlap where it crosses itself).
        let mut covered = BTreeSet::new();
        for w in points.windows(2) {
            let raw = |p: (Coord, Coord)| (p.0.to_bits(), p.1.to_bits());
            covered.extend(pixels(raw(w[0]), raw(w[1]), &clip()));
        }
        for y in 0..H as i32 {
            for x in 0..W as i32 {
                let drawn = a[(y as u32 * W + x as u32) as usize] == Rgb565::GREEN;
                assert_eq!(drawn, covered.contains(&(x, y)));
            }
        }
    }
}

/// Bands of every height, directly and through a bin, give the frame's pixels.
#[test]
fn bands_and_bins_equal_the_whole_frame() {
    let mut rng = Rng(0x11e5_0006);
    for _ in 0..40 {
        let points: Vec<(Coord, Coord)> = (0..2 + rng.below(6))
            .map(|_| {
                (
                    Coord::from_bits(rng.line_coordinate(W)),
                    Coord::from_bits(rng.line_coordinate(H)),
                )
            })
            .collect();
        let lines: Vec<Line<Rgb565>> = points
            .windows(2)
            .map(|w| Line {
                start: w[0],
                end: w[1],
                paint: Rgb565::YELLOW,
            })
            .collect();
        let polyline = Polyline::new(&points, Rgb565::RED);
        let mut whole = vec![Rgb565::BLACK; (W * H) as usize];
        polyline.draw_into(&mut SliceFramebuffer::new(&mut whole, W, H).unwrap());
        let mut only_lines = vec![Rgb565::BLACK; (W * H) as usize];
        let mut fb = SliceFramebuffer::new(&mut only_lines, W, H).unwrap();
        for l in &lines {
            l.draw_into(&mut fb);
        }
        crate::banded::check_bands_2d(&lines, &only_lines, Size::new(W, H));
        crate::banded::check_bands_2d(&[polyline], &whole, Size::new(W, H));
    }
}
