//! Filled polygons against independent references:
//!
//! * the triangles' own fill: a 3-vertex polygon covers exactly the pixels of `SolidTriangle`
//!   (both windings), and a polygon exactly the union of a triangulation of it (fans of convex
//!   and star-shaped polygons), each pixel once;
//! * the exact winding number at every pixel centre, counted edge by edge with `i128` cross
//!   products and the tie rule the module states (no stepping, no division);
//! * the `f64` crossing-number (even-odd) and winding-number tests of point-in-polygon, which
//!   agree with the exact one everywhere but at centres within rounding of an edge (counted);
//! * two polygons sharing edges never both cover a pixel.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::{Coord, FillRule, Polygon, SliceFramebuffer, SolidTriangle};

use crate::rng::Rng;

const W: u32 = 48;
const H: u32 = 40;

fn clip() -> Rectangle {
    Rectangle::new(Point::zero(), Size::new(W, H))
}

/// Coverage of `polygon` in the clip, from its spans (each pixel counted).
fn coverage<const N: usize>(polygon: &Polygon<N>, rule: FillRule, clip: &Rectangle) -> Vec<u8> {
    let mut cells = vec![0u8; (clip.size.width * clip.size.height) as usize];
    let (x0, y0) = (clip.top_left.x, clip.top_left.y);
    let mut last = (i32::MIN, i32::MIN);
    polygon.for_each_span(rule, clip, |y, a, b| {
        assert!(a < b, "empty span {a}..{b} in row {y}");
        assert!(clip.contains(Point::new(a, y)) && clip.contains(Point::new(b - 1, y)));
        // Top to bottom, left to right, disjoint.
        assert!((y, a) > last, "span ({y}, {a}) after {last:?}");
        last = (y, b);
        for x in a..b {
            let cell = &mut cells[((y - y0) as u32 * clip.size.width + (x - x0) as u32) as usize];
            *cell += 1;
        }
    });
    cells
}

/// The exact winding number at the centre of pixel `(i, j)`: each edge crossing the centre's
/// row (`y_top ≤ y_c < y_bottom`) adds its direction if the centre is right of it or on it.
/// An edge as two raw sub-pixel points.
type RawEdge = ((i64, i64), (i64, i64));

fn exact_winding(edges: &[RawEdge], i: i64, j: i64) -> i32 {
    let (px, py) = (i128::from(i) * 256 + 128, i128::from(j) * 256 + 128);
    let mut winding = 0;
    for &(a, b) in edges {
        let (dir, (xa, ya), (xb, yb)) = if a.1 < b.1 {
            (1, a, b)
        } else if a.1 > b.1 {
            (-1, b, a)
        } else {
            continue;
        };
        let (xa, ya, xb, yb) = (xa as i128, ya as i128, xb as i128, yb as i128);
        if ya <= py && py < yb && (px - xa) * (yb - ya) - (py - ya) * (xb - xa) >= 0 {
            winding += dir;
        }
    }
    winding
}

fn raw_edges<const N: usize>(contours: &[Vec<(i32, i32)>]) -> Vec<RawEdge> {
    let mut edges = vec![];
    for c in contours {
        for k in 0..c.len() {
            let (a, b) = (c[k], c[(k + 1) % c.len()]);
            edges.push((
                (i64::from(a.0), i64::from(a.1)),
                (i64::from(b.0), i64::from(b.1)),
            ));
        }
    }
    edges
}

fn polygon_of<const N: usize>(contours: &[Vec<(i32, i32)>]) -> Polygon<N> {
    let mut polygon = Polygon::<N>::new();
    for c in contours {
        let points: Vec<(Coord, Coord)> = c
            .iter()
            .map(|&(x, y)| (Coord::from_bits(x), Coord::from_bits(y)))
            .collect();
        polygon.add_contour(&points).unwrap();
    }
    polygon
}

fn check_exact<const N: usize>(contours: &[Vec<(i32, i32)>], clip: &Rectangle) {
    let polygon = polygon_of::<N>(contours);
    let edges = raw_edges::<N>(contours);
    for rule in [FillRule::NonZero, FillRule::EvenOdd] {
        let cells = coverage(&polygon, rule, clip);
        for j in 0..clip.size.height as i32 {
            for i in 0..clip.size.width as i32 {
                let (x, y) = (clip.top_left.x + i, clip.top_left.y + j);
                let inside = rule.inside(exact_winding(&edges, x.into(), y.into()));
                let got = cells[(j as u32 * clip.size.width + i as u32) as usize];
                assert_eq!(
                    got,
                    u8::from(inside),
                    "{rule:?} pixel ({x}, {y}) of {contours:?}"
                );
            }
        }
    }
}

impl Rng {
    /// A raw sub-pixel coordinate, mostly in and around `0..extent` px, sometimes on the
    /// lattice of centres or corners (ties), sometimes anywhere in the `Coord` range.
    fn coordinate(&mut self, extent: u32) -> i32 {
        let e = i64::from(extent) * 256;
        match self.below(10) {
            0 => self.range(i64::from(i32::MIN), i64::from(i32::MAX)) as i32,
            1 => (self.range(-4, i64::from(extent) + 4) * 256 + 128) as i32,
            2 => (self.range(-4, i64::from(extent) + 4) * 256) as i32,
            3 => self.range(-20 * e, 20 * e) as i32,
            _ => self.range(-e / 4, e + e / 4) as i32,
        }
    }

    fn contour(&mut self, len: usize, extent: u32) -> Vec<(i32, i32)> {
        let mut c: Vec<(i32, i32)> = (0..len)
            .map(|_| (self.coordinate(extent), self.coordinate(extent)))
            .collect();
        // Adversarial pieces: repeated vertices, collinear runs, zero-area spikes.
        match self.below(6) {
            0 if len > 1 => c[1] = c[0],
            1 if len > 2 => {
                let (a, b) = (c[0], c[2]);
                c[1] = (
                    ((i64::from(a.0) + i64::from(b.0)) / 2) as i32,
                    ((i64::from(a.1) + i64::from(b.1)) / 2) as i32,
                );
            }
            2 if len > 3 => c[2] = c[0],
            _ => {}
        }
        c
    }
}

#[test]
fn random_polygons_match_the_exact_winding_numbers() {
    let mut rng = Rng(0x5eed_0001);
    for case in 0..1500 {
        let contours: Vec<Vec<(i32, i32)>> = (0..1 + rng.below(3))
            .map(|_| {
                let len = 1 + rng.below(9) as usize;
                rng.contour(len, W.max(H))
            })
            .collect();
        // A clip inside the frame, or one off to the side (negative, far) now and then.
        let clip = if case % 5 == 0 {
            Rectangle::new(
                Point::new(rng.range(-60, 60) as i32, rng.range(-60, 60) as i32),
                Size::new(1 + rng.below(40) as u32, 1 + rng.below(40) as u32),
            )
        } else {
            clip()
        };
        check_exact::<32>(&contours, &clip);
    }
}

#[test]
fn huge_coordinates_match_the_exact_winding_numbers() {
    let mut rng = Rng(0x5eed_0002);
    for _ in 0..300 {
        let contours: Vec<Vec<(i32, i32)>> = (0..1 + rng.below(2))
            .map(|_| {
                (0..3 + rng.below(5))
                    .map(|_| match rng.below(3) {
                        0 => (
                            rng.range(i32::MIN.into(), i32::MAX.into()) as i32,
                            rng.range(i32::MIN.into(), i32::MAX.into()) as i32,
                        ),
                        1 => (
                            [i32::MIN, i32::MAX][rng.below(2) as usize],
                            [i32::MIN, i32::MAX][rng.below(2) as usize],
                        ),
                        _ => (rng.coordinate(W), rng.coordinate(H)),
                    })
                    .collect()
            })
            .collect();
        let clip = Rectangle::new(
            Point::new(rng.range(-40, 40) as i32, rng.range(-40, 40) as i32),
            Size::new(32, 24),
        );
        check_exact::<16>(&contours, &clip);
    }
}

/// The f64 point-in-polygon tests (crossing number for even-odd, winding number for non-zero)
/// agree with the polygon everywhere but at centres within 10⁻⁶ px of an edge's line.
#[test]
fn polygons_agree_with_the_f64_point_in_polygon_tests() {
    let mut rng = Rng(0x5eed_0003);
    let (mut compared, mut near) = (0u64, 0u64);
    for _ in 0..800 {
        let contours: Vec<Vec<(i32, i32)>> = (0..1 + rng.below(3))
            .map(|_| {
                (0..3 + rng.below(8))
                    .map(|_| {
                        (
                            rng.range(-2560, i64::from(W) * 256 + 2560) as i32,
                            rng.range(-2560, i64::from(H) * 256 + 2560) as i32,
                        )
                    })
                    .collect()
            })
            .collect();
        let polygon = polygon_of::<32>(&contours);
        let edges: Vec<((f64, f64), (f64, f64))> = raw_edges::<32>(&contours)
            .into_iter()
            .map(|(a, b)| {
                let f = |(x, y): (i64, i64)| (x as f64 / 256.0, y as f64 / 256.0);
                (f(a), f(b))
            })
            .collect();
        for rule in [FillRule::NonZero, FillRule::EvenOdd] {
            let cells = coverage(&polygon, rule, &clip());
            for j in 0..H {
                for i in 0..W {
                    let (px, py) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                    // Crossing number (ray to +x) and winding number, the textbook tests.
                    let (mut crossings, mut winding) = (0, 0);
                    let mut on_edge = false;
                    for &((x0, y0), (x1, y1)) in &edges {
                        let len = ((x1 - x0).powi(2) + (y1 - y0).powi(2)).sqrt();
                        let distance = ((x1 - x0) * (py - y0) - (y1 - y0) * (px - x0)).abs() / len;
                        let within = px >= x0.min(x1) - 1e-6
                            && px <= x0.max(x1) + 1e-6
                            && py >= y0.min(y1) - 1e-6
                            && py <= y0.max(y1) + 1e-6;
                        if len > 0.0 && distance < 1e-6 && within || (y0 == py || y1 == py) {
                            on_edge = true;
                        }
                        if (y0 > py) != (y1 > py) {
                            let x = x0 + (py - y0) * (x1 - x0) / (y1 - y0);
                            if px < x {
                                crossings += 1;
                                winding += if y1 > y0 { -1 } else { 1 };
                            }
                        }
                    }
                    if on_edge {
                        near += 1;
                        continue;
                    }
                    compared += 1;
                    let inside = match rule {
                        FillRule::NonZero => winding != 0,
                        FillRule::EvenOdd => crossings % 2 == 1,
                    };
                    let got = cells[(j * W + i) as usize] == 1;
                    assert_eq!(got, inside, "{rule:?} ({i}, {j}) of {contours:?}");
                }
            }
        }
    }
    // Centres on an edge are the exception, not the rule.
    assert!(near * 1000 < compared, "{near} near edges of {compared}");
}

#[test]
fn a_three_vertex_polygon_is_the_triangle() {
    let mut rng = Rng(0x5eed_0004);
    for _ in 0..20_000 {
        let points: [(i32, i32); 3] =
            core::array::from_fn(|_| (rng.coordinate(W), rng.coordinate(H)));
        let coords = points.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y)));
        let triangle: Vec<(i32, i32, i32)> = SolidTriangle::new(coords, Rgb565::RED)
            .spans(&clip())
            .map(|s| (s.y, s.x_start, s.x_end))
            .collect();
        for (order, rule) in [
            ([0, 1, 2], FillRule::NonZero),
            ([2, 1, 0], FillRule::EvenOdd),
        ] {
            let polygon = Polygon::<3>::from_points(&order.map(|k| coords[k])).unwrap();
            let mut spans = vec![];
            polygon.for_each_span(rule, &clip(), |y, a, b| spans.push((y, a, b)));
            assert_eq!(spans, triangle, "{points:?}");
        }
    }
}

/// A star-shaped polygon (vertices at random radii around a centre, in angle order) is the
/// union of the fan of triangles from its centre: every pixel of the polygon in exactly one.
#[test]
fn a_polygon_is_the_union_of_its_triangulation() {
    let mut rng = Rng(0x5eed_0005);
    let mut checked = 0;
    for case in 0..2000 {
        let n = 3 + rng.below(13) as usize;
        let centre = (
            rng.range(0, i64::from(W) * 256),
            rng.range(0, i64::from(H) * 256),
        );
        let convex = case % 2 == 0;
        let r0 = rng.range_f64(2.0, 40.0);
        let mut angles: Vec<f64> = (0..n)
            .map(|_| rng.range_f64(0.0, core::f64::consts::TAU))
            .collect();
        angles.sort_by(|a, b| a.partial_cmp(b).unwrap());
        let mut points: Vec<(i32, i32)> = angles
            .iter()
            .map(|&t| {
                let r = if convex { r0 } else { rng.range_f64(0.5, r0) } * 256.0;
                (
                    (centre.0 as f64 + r * t.cos()).round() as i32,
                    (centre.1 as f64 + r * t.sin()).round() as i32,
                )
            })
            .collect();
        if case % 4 < 2 {
            points.reverse();
        }
        // A convex polygon of points on a circle is still only star-shaped after rounding:
        // fan from the centre, which every edge sees from the same side.
        let c = (centre.0 as i32, centre.1 as i32);
        let side = |a: (i32, i32), b: (i32, i32)| {
            let (a, b, c) = (
                (i64::from(a.0), i64::from(a.1)),
                (i64::from(b.0), i64::from(b.1)),
                (i64::from(c.0), i64::from(c.1)),
            );
            ((b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)).signum()
        };
        let sides: Vec<i64> = (0..n)
            .map(|k| side(points[k], points[(k + 1) % n]))
            .collect();
        if sides.iter().any(|&s| s != sides[0] || s == 0) {
            continue;
        }
        let polygon = polygon_of::<16>(&[points.clone()]);
        let cells = coverage(&polygon, FillRule::NonZero, &clip());
        let mut union = vec![0u8; (W * H) as usize];
        for k in 0..n {
            let t = [c, points[k], points[(k + 1) % n]]
                .map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y)));
            for s in SolidTriangle::new(t, Rgb565::RED).spans(&clip()) {
                for x in s.x_start..s.x_end {
                    union[(s.y as u32 * W + x as u32) as usize] += 1;
                }
            }
        }
        assert_eq!(cells, union, "{points:?} around {c:?}");
        checked += 1;
    }
    assert!(
        checked > 1500,
        "{checked} of 2000 polygons star-shaped around their centre"
    );
}

/// A convex polygon cut by a chord into two polygons: they share the chord, cover the whole
/// one's pixels between them, and no pixel twice.
#[test]
fn polygons_sharing_an_edge_never_both_cover_a_pixel() {
    let mut rng = Rng(0x5eed_0006);
    for _ in 0..2000 {
        let n = 4 + rng.below(8) as usize;
        let centre = (
            rng.range(0, i64::from(W) * 256) as f64,
            rng.range(0, i64::from(H) * 256) as f64,
        );
        let r = rng.range_f64(3.0, 30.0) * 256.0;
        let phase = rng.range_f64(0.0, 1.0);
        let points: Vec<(i32, i32)> = (0..n)
            .map(|k| {
                let t = (k as f64 + phase) / n as f64 * core::f64::consts::TAU;
                (
                    (centre.0 + r * t.cos()).round() as i32,
                    (centre.1 + r * t.sin()).round() as i32,
                )
            })
            .collect();
        let cut = 2 + rng.below(n as u64 - 3) as usize;
        let first: Vec<(i32, i32)> = points[..=cut].to_vec();
        let mut second: Vec<(i32, i32)> = points[cut..].to_vec();
        second.push(points[0]);
        let rule = [FillRule::NonZero, FillRule::EvenOdd][rng.below(2) as usize];
        let whole = coverage(
            &polygon_of::<16>(std::slice::from_ref(&points)),
            rule,
            &clip(),
        );
        let a = coverage(&polygon_of::<16>(&[first]), rule, &clip());
        let b = coverage(&polygon_of::<16>(&[second]), rule, &clip());
        let sum: Vec<u8> = a.iter().zip(&b).map(|(a, b)| a + b).collect();
        assert_eq!(sum, whole, "{points:?} cut at {cut}");
    }
}

/// `draw` (any DrawTarget), `draw_into` and the spans give the same pixels; the paint's colour
/// only where the spans say.
#[test]
fn draw_and_draw_into_agree() {
    let mut rng = Rng(0x5eed_0007);
    for _ in 0..300 {
        let contours: Vec<Vec<(i32, i32)>> = (0..1 + rng.below(3))
            .map(|_| {
                let len = 3 + rng.below(6) as usize;
                rng.contour(len, W)
            })
            .collect();
        let polygon = polygon_of::<32>(&contours);
        let rule = [FillRule::NonZero, FillRule::EvenOdd][rng.below(2) as usize];
        let fill = polygon.filled(Rgb565::GREEN).with_rule(rule);
        let mut a = vec![Rgb565::BLACK; (W * H) as usize];
        let mut b = a.clone();
        fill.draw(&mut SliceFramebuffer::new(&mut a, W, H).unwrap())
            .unwrap();
        fill.draw_into(&mut SliceFramebuffer::new(&mut b, W, H).unwrap());
        assert_eq!(a, b);
        let cells = coverage(&polygon, rule, &clip());
        for (c, p) in cells.iter().zip(&a) {
            assert_eq!(*c == 1, *p == Rgb565::GREEN);
        }
    }
}

#[test]
fn the_store_reports_its_capacity() {
    let mut p = Polygon::<4>::new();
    assert!(p.add_contour(&[(0.0, 0.0), (4.0, 0.0), (0.0, 4.0)]).is_ok());
    let err = p.add_contour(&[(0.0, 0.0), (4.0, 0.0)]).unwrap_err();
    assert_eq!(err.capacity, 4);
    assert_eq!(p.len(), 3, "a contour that does not fit adds nothing");
    assert!(p.push((1.0, 1.0)).is_ok());
    assert!(p.push((2.0, 1.0)).is_err());
    assert_eq!(err.to_string(), "the polygon holds at most 4 vertices");
    // An empty or one-point polygon draws nothing.
    let mut spans = 0;
    Polygon::<4>::new().for_each_span(FillRule::NonZero, &clip(), |_, _, _| spans += 1);
    Polygon::<4>::from_points(&[(3.0, 3.0)])
        .unwrap()
        .for_each_span(FillRule::NonZero, &clip(), |_, _, _| spans += 1);
    assert_eq!(spans, 0);
}

/// Bands of every height, drawn directly and through a bin, give the frame's pixels.
#[test]
fn bands_and_bins_equal_the_whole_frame() {
    let mut rng = Rng(0x5eed_0008);
    for case in 0..60 {
        let polygons: Vec<Polygon<24>> = (0..1 + rng.below(4))
            .map(|_| {
                let contours: Vec<Vec<(i32, i32)>> = (0..1 + rng.below(3))
                    .map(|_| {
                        let len = 3 + rng.below(6) as usize;
                        rng.contour(len, W)
                    })
                    .collect();
                polygon_of::<24>(&contours)
            })
            .collect();
        let colors = [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE, Rgb565::YELLOW];
        let rule = [FillRule::NonZero, FillRule::EvenOdd][case % 2];
        let fills: Vec<_> = polygons
            .iter()
            .zip(colors)
            .map(|(p, c)| p.filled(c).with_rule(rule))
            .collect();
        let mut whole = vec![Rgb565::BLACK; (W * H) as usize];
        let mut fb = SliceFramebuffer::new(&mut whole, W, H).unwrap();
        for f in &fills {
            f.draw_into(&mut fb);
        }
        crate::banded::check_bands_2d(&fills, &whole, Size::new(W, H));
    }
}

/// A translucent paint blends each covered pixel once, within 1 LSB of the exact source-over
/// blend of its channels; `draw` over the background colour gives `draw_into`'s pixels on a
/// frame of that colour.
#[test]
fn translucent_polygons_blend_each_pixel_once() {
    use embedded_raster::paint::Translucent;
    use embedded_raster::GouraudColor;
    let mut rng = Rng(0x5eed_0009);
    for case in 0..300 {
        let contours: Vec<Vec<(i32, i32)>> = (0..1 + rng.below(3))
            .map(|_| {
                let len = 3 + rng.below(6) as usize;
                rng.contour(len, W)
            })
            .collect();
        let polygon = polygon_of::<32>(&contours);
        let rule = [FillRule::NonZero, FillRule::EvenOdd][case % 2];
        let opacity = rng.below(256) as u8;
        let color = Rgb565::new(
            rng.below(32) as u8,
            rng.below(64) as u8,
            rng.below(32) as u8,
        );
        let background = Rgb565::new(
            rng.below(32) as u8,
            rng.below(64) as u8,
            rng.below(32) as u8,
        );
        // A frame with a pattern under the polygon: each pixel its own destination.
        let under: Vec<Rgb565> = (0..W * H)
            .map(|i| Rgb565::new((i % 32) as u8, (i * 7 % 64) as u8, (i / 40 % 32) as u8))
            .collect();
        let mut pixels = under.clone();
        let fill = polygon
            .filled(Translucent::new(color, opacity, background))
            .with_rule(rule);
        fill.draw_into(&mut SliceFramebuffer::new(&mut pixels, W, H).unwrap());
        let cells = coverage(&polygon, rule, &clip());
        let a = f64::from(opacity) / 255.0;
        for ((&cell, &got), &d) in cells.iter().zip(&pixels).zip(&under) {
            if cell == 0 {
                assert_eq!(got, d);
                continue;
            }
            let (s, d, g) = (color.channels(), d.channels(), got.channels());
            for k in 0..3 {
                let exact = f64::from(s[k]) * a + f64::from(d[k]) * (1.0 - a);
                assert!(
                    (f64::from(g[k]) - exact).abs() <= 1.0,
                    "{exact} {g:?} opacity {opacity}"
                );
            }
        }
        // Over a known background: draw (any DrawTarget) and draw_into agree.
        let mut a_px = vec![background; (W * H) as usize];
        let mut b_px = a_px.clone();
        fill.draw(&mut SliceFramebuffer::new(&mut a_px, W, H).unwrap())
            .unwrap();
        fill.draw_into(&mut SliceFramebuffer::new(&mut b_px, W, H).unwrap());
        assert_eq!(a_px, b_px);
    }
}
