//! Linear and radial gradients against the independent f64 reference (`reference::gradient`):
//! random gradients, stops (coincident, out of order, beyond 1, none), colour formats, rows at
//! any position; degenerate and huge inputs; `draw_row` against `paint_row`; ordered dithering.
//!
//! "Within 1 LSB": each channel is the floor or the ceiling of the exact value; the plain
//! gradients round to nearest from within 1/4 LSB (radial; linear: 2⁻⁵), so the check is
//! `|got − exact| ≤ ½ + 1/4`. Dithered: each channel is `⌊v + θ⌋` for a Bayer threshold θ of the
//! pixel, `v` within 1/4 LSB of the exact value: `⌊exact − 1/4⌋ ≤ got ≤ ⌈exact + 1/4⌉`.

use std::fmt::Debug;

use embedded_graphics::pixelcolor::{
    Bgr555, Bgr565, Bgr666, Bgr888, BinaryColor, Gray2, Gray4, Gray8, Rgb555, Rgb565, Rgb666,
    Rgb888,
};
use embedded_graphics::prelude::*;
use embedded_raster::paint::{LinearGradient, Paint, RadialGradient, Stop, STOP_ONE};
use embedded_raster::reference::gradient as reference;
use embedded_raster::{Coord, GouraudColor};

use crate::readable_target::ReadableTarget;
use crate::rng::Rng;

/// Stops a test gradient has at most.
const MAX_STOPS: usize = 5;
/// Tolerance of a rounded channel (see the module).
const ROUNDED: f64 = 0.5 + 1.0 / 4.0;
/// Tolerance of the value a dithered channel is the floor or the ceiling of.
const DITHERED: f64 = 1.0 / 4.0;

type Stops = Vec<(u32, [u8; 3])>;

/// Random stops in format `C`: positions anywhere in 0..=1 (a few beyond 1, coincident, out of
/// order), colours anywhere in the format's range.
fn random_stops<C: GouraudColor>(rng: &mut Rng, n: usize) -> Stops {
    let mut stops = Vec::new();
    let mut last = 0u32;
    for _ in 0..n {
        let position = match rng.below(8) {
            0 => last,                     // coincident with the one before
            1 => rng.below(70_000) as u32, // out of order, or beyond 1
            2 => [0, STOP_ONE, STOP_ONE + 5][rng.below(3) as usize],
            _ => last + rng.below(u64::from(STOP_ONE - last.min(STOP_ONE)) + 1) as u32,
        };
        last = position.min(STOP_ONE);
        let channels = core::array::from_fn(|k| rng.below(u64::from(C::MAX[k]) + 1) as u8);
        stops.push((position, channels));
    }
    stops
}

fn stops_of<C: GouraudColor, const N: usize>(stops: &Stops) -> [Stop<C>; N] {
    core::array::from_fn(|k| {
        let (p, c) = stops[k];
        Stop::new(p, C::from_channels(c))
    })
}

/// How far `got` is from `exact`, worst channel, in LSB.
fn error<C: GouraudColor>(got: C, exact: [f64; 3]) -> f64 {
    let got = got.channels();
    (0..C::CHANNELS)
        .map(|k| (f64::from(got[k]) - exact[k]).abs())
        .fold(0.0, f64::max)
}

/// Whether dithered `got` is the floor or ceiling of a value within [`DITHERED`] of `exact`.
fn dither_ok<C: GouraudColor>(got: C, exact: [f64; 3]) -> bool {
    let got = got.channels();
    (0..C::CHANNELS).all(|k| {
        let g = f64::from(got[k]);
        (exact[k] - DITHERED).floor() <= g && g <= (exact[k] + DITHERED).ceil()
    })
}

enum Kind {
    Linear((i32, i32), (i32, i32)),
    Radial((i32, i32), i32),
}

impl Kind {
    fn exact(&self, stops: &Stops, x: i32, y: i32) -> [f64; 3] {
        match *self {
            Kind::Linear(s, e) => reference::linear(s, e, stops, x, y),
            Kind::Radial(c, r) => reference::radial(c, r, stops, x, y),
        }
    }
}

/// The gradient `kind` with `stops` (`N` of them) in format `C`, plain or dithered, painted on a
/// row of `len` pixels from `(x, y)`, through `paint_row` and `draw_row`.
fn paint<C: GouraudColor + Debug, const N: usize>(
    kind: &Kind,
    stops: &Stops,
    dithered: bool,
    (x, y, len): (i32, i32, usize),
) -> Vec<C> {
    let bits = |(a, b): (i32, i32)| (Coord::from_bits(a), Coord::from_bits(b));
    let black = C::from_channels([0; 3]);
    let mut row = vec![black; len];
    let mut drawn = ReadableTarget::new(len as u32, 1, vec![black; len]);
    match *kind {
        Kind::Linear(s, e) => {
            let mut g = LinearGradient::new(bits(s), bits(e), stops_of::<C, N>(stops));
            if dithered {
                g = g.dithered();
            }
            g.paint_row(y, x, &mut row);
            if x == 0 && y == 0 {
                g.draw_row(&mut drawn, 0, 0, len as u32).unwrap();
                assert_eq!(drawn.pixels, row, "draw_row differs from paint_row");
            }
        }
        Kind::Radial(c, r) => {
            let mut g = RadialGradient::new(bits(c), Coord::from_bits(r), stops_of::<C, N>(stops));
            if dithered {
                g = g.dithered();
            }
            g.paint_row(y, x, &mut row);
            if x == 0 && y == 0 {
                g.draw_row(&mut drawn, 0, 0, len as u32).unwrap();
                assert_eq!(drawn.pixels, row, "draw_row differs from paint_row");
            }
        }
    }
    row
}

/// Paints `kind` with `stops` on the row and checks every pixel against the reference;
/// returns the worst error (plain) .
fn check<C: GouraudColor + Debug>(
    kind: &Kind,
    stops: &Stops,
    dithered: bool,
    (x, y, len): (i32, i32, usize),
) -> f64 {
    let row: Vec<C> = match stops.len() {
        0 => paint::<C, 0>(kind, stops, dithered, (x, y, len)),
        1 => paint::<C, 1>(kind, stops, dithered, (x, y, len)),
        2 => paint::<C, 2>(kind, stops, dithered, (x, y, len)),
        3 => paint::<C, 3>(kind, stops, dithered, (x, y, len)),
        4 => paint::<C, 4>(kind, stops, dithered, (x, y, len)),
        _ => paint::<C, MAX_STOPS>(kind, stops, dithered, (x, y, len)),
    };
    let mut worst = 0.0f64;
    for (i, &got) in row.iter().enumerate() {
        let px = x.wrapping_add(i as i32);
        let exact = kind.exact(stops, px, y);
        if dithered {
            assert!(
                dither_ok(got, exact),
                "{}: pixel ({px}, {y}) dithered {:?}, exact {exact:?}, stops {stops:?}",
                std::any::type_name::<C>(),
                got.channels()
            );
        } else {
            let e = error(got, exact);
            worst = worst.max(e);
            assert!(
                e <= ROUNDED,
                "{}: pixel ({px}, {y}) got {:?}, exact {exact:?}, stops {stops:?}",
                std::any::type_name::<C>(),
                got.channels()
            );
        }
    }
    worst
}

/// A random point within `range` pixels of the origin, any sub-pixel position.
fn point(rng: &mut Rng, range: i64) -> (i32, i32) {
    let mut c = || rng.range(-range * 256, range * 256) as i32;
    (c(), c())
}

/// Radial stops whose segments are exact edges or at least 1/16 pixel wide (the documented
/// condition for 8-bit channels).
fn radial_stops<C: GouraudColor>(rng: &mut Rng, n: usize, radius: i32) -> Stops {
    let mut stops = random_stops::<C>(rng, n);
    let r = i64::from(radius).abs();
    let mut e = 0i64;
    for s in &mut stops {
        let p = i64::from(s.0.min(STOP_ONE)).max(e);
        if p > e && (p - e) * r < 1 << 20 {
            s.0 = e as u32; // too narrow: make it an edge
        } else {
            e = p;
        }
    }
    stops
}

fn random_case<C: GouraudColor + Debug>(rng: &mut Rng, radial: bool, dithered: bool) -> f64 {
    let n = rng.below(MAX_STOPS as u64 + 1) as usize;
    let (range, span) = if rng.chance(4) { (30, 40) } else { (400, 300) };
    let kind = if radial {
        Kind::Radial(
            point(rng, range),
            rng.range(-range * 256, range * 256) as i32,
        )
    } else if rng.chance(10) {
        // Axis-aligned, or a zero-length gradient.
        let s = point(rng, range);
        let e = match rng.below(3) {
            0 => (s.0, point(rng, range).1),
            1 => (point(rng, range).0, s.1),
            _ => s,
        };
        Kind::Linear(s, e)
    } else {
        Kind::Linear(point(rng, range), point(rng, range))
    };
    let stops = match kind {
        Kind::Radial(_, r) => radial_stops::<C>(rng, n, r),
        Kind::Linear(..) => random_stops::<C>(rng, n),
    };
    let (x, y) = if rng.chance(4) {
        (0, 0)
    } else {
        let p = point(rng, range * 3 / 2);
        (p.0 >> 8, p.1 >> 8)
    };
    let len = 1 + rng.below(span) as usize;
    check::<C>(&kind, &stops, dithered, (x, y, len))
}

fn random_cases(radial: bool, dithered: bool, seed: u64, cases: u32) {
    let mut rng = Rng(seed);
    let mut worst = 0.0f64;
    for _ in 0..cases {
        let e = match rng.below(12) {
            0 => random_case::<Rgb565>(&mut rng, radial, dithered),
            1 => random_case::<Bgr565>(&mut rng, radial, dithered),
            2 => random_case::<Rgb888>(&mut rng, radial, dithered),
            3 => random_case::<Bgr888>(&mut rng, radial, dithered),
            4 => random_case::<Rgb555>(&mut rng, radial, dithered),
            5 => random_case::<Bgr555>(&mut rng, radial, dithered),
            6 => random_case::<Rgb666>(&mut rng, radial, dithered),
            7 => random_case::<Bgr666>(&mut rng, radial, dithered),
            8 => random_case::<Gray8>(&mut rng, radial, dithered),
            9 => random_case::<Gray4>(&mut rng, radial, dithered),
            10 => random_case::<Gray2>(&mut rng, radial, dithered),
            _ => random_case::<BinaryColor>(&mut rng, radial, dithered),
        };
        worst = worst.max(e);
    }
    println!("worst error {worst:.4} LSB");
}

#[test]
fn linear_within_one_lsb() {
    random_cases(false, false, 1, 30_000);
}

#[test]
fn radial_within_one_lsb() {
    random_cases(true, false, 2, 30_000);
}

#[test]
fn linear_dithered_is_floor_or_ceiling() {
    random_cases(false, true, 3, 10_000);
}

#[test]
fn radial_dithered_is_floor_or_ceiling() {
    random_cases(true, true, 4, 10_000);
}

/// Dithering a flat colour between two levels: each 4×4 block averages it to 1/16 LSB.
#[test]
fn dithering_averages_the_exact_colour() {
    for sixteenths in 0..16u32 {
        // A gradient so long that the 4×4 block at its start is flat to 2⁻¹² LSB: red
        // 10 + sixteenths/16 + 1/32 (a threshold's midpoint away from any ambiguity).
        let red = 10.0 + f64::from(sixteenths) / 16.0 + 1.0 / 32.0;
        // Channel value v at t: 8·t (0 → 0, 1 → 8 ... ) scaled so that red = stop colour: use two
        // stops of the same colour but a fraction between: 10 to 11 with the pixel at fraction
        // red − 10.
        let f = red - 10.0;
        let length = 1 << 20; // sub-pixel units: 4096 pixels
        let start = -((f * f64::from(length)) as i32) + 128;
        let g = LinearGradient::new(
            (Coord::from_bits(start), Coord::ZERO),
            (Coord::from_bits(start + length), Coord::ZERO),
            [
                Stop::new(0, Rgb565::new(10, 0, 0)),
                Stop::new(STOP_ONE, Rgb565::new(11, 0, 0)),
            ],
        )
        .dithered();
        let mut sum = 0u32;
        for y in 0..4 {
            let mut row = [Rgb565::BLACK; 4];
            g.paint_row(y, 0, &mut row);
            sum += row.iter().map(|c| u32::from(c.r())).sum::<u32>();
        }
        let mean = f64::from(sum) / 16.0;
        assert!(
            (mean - red).abs() <= 1.0 / 16.0,
            "{sixteenths}: {mean} vs {red}"
        );
    }
}

/// Zero-length gradients, zero radius, no stops, one stop: defined colours everywhere.
#[test]
fn degenerate_gradients() {
    let stops = [Stop::new(100, Rgb888::RED), Stop::new(50_000, Rgb888::BLUE)];
    let mut row = [Rgb888::BLACK; 8];
    LinearGradient::new((3.0, 4.0), (3.0, 4.0), stops).paint_row(0, 0, &mut row);
    assert_eq!(row, [Rgb888::BLUE; 8]);
    RadialGradient::new((3.0, 4.0), 0.0, stops).paint_row(5, -3, &mut row);
    assert_eq!(row, [Rgb888::BLUE; 8]);
    let none: [Stop<Rgb888>; 0] = [];
    row = [Rgb888::WHITE; 8];
    LinearGradient::new((0.0, 0.0), (8.0, 0.0), none).paint_row(0, 0, &mut row);
    assert_eq!(row, [Rgb888::BLACK; 8]);
    row = [Rgb888::WHITE; 8];
    RadialGradient::new((0.0, 0.0), 8.0, none).paint_row(0, 0, &mut row);
    assert_eq!(row, [Rgb888::BLACK; 8]);
    let one = [Stop::new(STOP_ONE / 2, Rgb888::GREEN)];
    LinearGradient::new((0.0, 0.0), (8.0, 0.0), one).paint_row(0, -4, &mut row);
    assert_eq!(row, [Rgb888::GREEN; 8]);
    // Coincident stops: a hard edge at x = 4, the later colour from it on.
    let edge = [
        Stop::new(0, Rgb888::RED),
        Stop::new(STOP_ONE / 2, Rgb888::RED),
        Stop::new(STOP_ONE / 2, Rgb888::BLUE),
        Stop::new(STOP_ONE, Rgb888::BLUE),
    ];
    LinearGradient::new((0.5, 0.0), (8.5, 0.0), edge).paint_row(0, 0, &mut row);
    assert_eq!(row[..4], [Rgb888::RED; 4]);
    assert_eq!(row[4..], [Rgb888::BLUE; 4]);
    // Out of order: the stop at 0.25 after one at 0.5 is raised to 0.5 (an edge there).
    let disorder = [
        Stop::new(0, Rgb888::RED),
        Stop::new(STOP_ONE / 2, Rgb888::RED),
        Stop::new(STOP_ONE / 4, Rgb888::BLUE),
    ];
    LinearGradient::new((0.5, 0.0), (8.5, 0.0), disorder).paint_row(0, 0, &mut row);
    assert_eq!(row[..4], [Rgb888::RED; 4]);
    assert_eq!(row[4..], [Rgb888::BLUE; 4]);
}

/// Points anywhere in the `Coord` range and rows anywhere in `i32`: no panic, and where the
/// documented conditions hold (gradients up to 16,384 pixels a side), within 1 LSB.
#[test]
fn huge_inputs() {
    let mut rng = Rng(5);
    let extremes = [i32::MIN, i32::MIN + 1, -1, 0, 1, i32::MAX - 1, i32::MAX];
    for case in 0..3000 {
        let mut any = || {
            if rng.chance(3) {
                extremes[rng.below(extremes.len() as u64) as usize]
            } else {
                rng.next() as i32
            }
        };
        let (s, e, r) = ((any(), any()), (any(), any()), any());
        let (x, y) = (any(), any());
        let len = 1 + (case % 50) as usize;
        let stops = random_stops::<Rgb565>(&mut rng, 3);
        let st = stops_of::<Rgb565, 3>(&stops);
        let mut row = vec![Rgb565::BLACK; len];
        let bits = |(a, b): (i32, i32)| (Coord::from_bits(a), Coord::from_bits(b));
        LinearGradient::new(bits(s), bits(e), st).paint_row(y, x, &mut row);
        RadialGradient::new(bits(s), Coord::from_bits(r), st).paint_row(y, x, &mut row);
        LinearGradient::new(bits(s), bits(e), st)
            .dithered()
            .paint_row(y, x, &mut row);
        RadialGradient::new(bits(s), Coord::from_bits(r), st)
            .dithered()
            .paint_row(y, x, &mut row);
    }
    // Far from the origin, within the exact domain: a gradient 10,000 pixels long at 8 million
    // pixels, and pixels there.
    let mut rng = Rng(6);
    for _ in 0..300 {
        let base = (
            rng.range(-8_000_000, 8_000_000) as i32,
            rng.range(-8_000_000, 8_000_000) as i32,
        );
        let s = (
            base.0 * 256 + rng.range(0, 255) as i32,
            base.1 * 256 + rng.range(0, 255) as i32,
        );
        let e = (
            s.0 + rng.range(-16384 * 256, 16384 * 256) as i32,
            s.1 + rng.range(-16384 * 256, 16384 * 256) as i32,
        );
        let stops = random_stops::<Rgb888>(&mut rng, 3);
        let x = base.0 + rng.range(-20_000, 20_000) as i32;
        let y = base.1 + rng.range(-20_000, 20_000) as i32;
        check::<Rgb888>(&Kind::Linear(s, e), &stops, false, (x, y, 200));
    }
}

/// Rows longer than the chunks the gradients restart at (2¹⁵ pixels), long gradients.
#[test]
fn long_rows() {
    let mut rng = Rng(7);
    for _ in 0..6 {
        let s = point(&mut rng, 30_000);
        let e = point(&mut rng, 30_000);
        let e = (s.0 / 2 + e.0 / 2, s.1 / 2 + e.1 / 2);
        let stops = random_stops::<Rgb888>(&mut rng, 4);
        check::<Rgb888>(&Kind::Linear(s, e), &stops, false, (-20_000, 100, 70_000));
        let r = rng.range(1, 40_000 * 256) as i32;
        let stops = radial_stops::<Rgb888>(&mut rng, 4, r);
        check::<Rgb888>(&Kind::Radial(s, r), &stops, false, (-20_000, 100, 70_000));
    }
}

/// Gradient-filled triangles: `draw_into` and `draw` (into a framebuffer and into a target with
/// only `draw_iter`) give the same pixels, on exactly a `SolidTriangle`'s, each within 1 LSB of
/// the gradient.
#[test]
fn painted_triangles() {
    use embedded_raster::{PaintedTriangle, SliceFramebuffer, SolidTriangle};
    let (w, h) = (48u32, 40u32);
    let mut rng = Rng(8);
    for case in 0..400 {
        let mut corner = || {
            let range = if case % 5 == 0 { 3000 } else { 60 };
            (
                Coord::from_bits(rng.range(-range * 256, range * 256) as i32),
                Coord::from_bits(rng.range(-range * 256, range * 256) as i32),
            )
        };
        let points = [corner(), corner(), corner()];
        let (s, e) = (point(&mut rng, 60), point(&mut rng, 60));
        let radius = rng.range(256, 60 * 256) as i32;
        let stops = radial_stops::<Rgb565>(&mut rng, 3, radius);
        let st = stops_of::<Rgb565, 3>(&stops);
        let bits = |(a, b): (i32, i32)| (Coord::from_bits(a), Coord::from_bits(b));
        let dithered = rng.chance(3);
        let (kind, a, b, c) = if rng.chance(2) {
            let mut g = LinearGradient::new(bits(s), bits(e), st);
            if dithered {
                g = g.dithered();
            }
            let t = PaintedTriangle { points, paint: g };
            let (a, b, c) = draw_three(&t, w, h);
            (Kind::Linear(s, e), a, b, c)
        } else {
            let mut g = RadialGradient::new(bits(s), Coord::from_bits(radius), st);
            if dithered {
                g = g.dithered();
            }
            let t = PaintedTriangle { points, paint: g };
            let (a, b, c) = draw_three(&t, w, h);
            (Kind::Radial(s, radius), a, b, c)
        };
        assert_eq!(a, b, "draw_into and draw differ");
        assert_eq!(a, c, "draw into a framebuffer and into draw_iter differ");
        // Coverage: a solid triangle's, in a colour no gradient pixel can be… checked by a mask.
        let mut solid = vec![BinaryColor::Off; (w * h) as usize];
        let mut fb = SliceFramebuffer::new(&mut solid, w, h).unwrap();
        SolidTriangle {
            points,
            color: BinaryColor::On,
        }
        .draw_into(&mut fb);
        let background = Rgb565::new(1, 2, 3);
        for (i, (&got, &covered)) in a.iter().zip(&solid).enumerate() {
            let (x, y) = ((i as u32 % w) as i32, (i as u32 / w) as i32);
            if covered == BinaryColor::Off {
                assert_eq!(
                    got, background,
                    "pixel ({x}, {y}) drawn outside the triangle"
                );
                continue;
            }
            let exact = kind.exact(&stops, x, y);
            if dithered {
                assert!(dither_ok(got, exact), "({x}, {y}): {got:?} vs {exact:?}");
            } else {
                assert!(
                    error(got, exact) <= ROUNDED,
                    "({x}, {y}): {got:?} vs {exact:?}"
                );
            }
        }
    }
}

/// The triangle drawn by `draw_into`, by `draw` into a framebuffer and by `draw` into a target
/// with only `draw_iter`, over the same background.
fn draw_three<P: Paint<Color = Rgb565>>(
    t: &embedded_raster::PaintedTriangle<P>,
    w: u32,
    h: u32,
) -> (Vec<Rgb565>, Vec<Rgb565>, Vec<Rgb565>) {
    use embedded_raster::SliceFramebuffer;
    let background = Rgb565::new(1, 2, 3);
    let mut a = vec![background; (w * h) as usize];
    t.draw_into(&mut SliceFramebuffer::new(&mut a, w, h).unwrap());
    let mut b = vec![background; (w * h) as usize];
    t.draw(&mut SliceFramebuffer::new(&mut b, w, h).unwrap())
        .unwrap();
    let mut c = ReadableTarget::new(w, h, vec![background; (w * h) as usize]);
    t.draw(&mut c).unwrap();
    (a, b, c.pixels)
}

/// Dithered Gouraud triangles: the plain triangle's pixels, `draw_into` and `draw` equal, each
/// channel the floor or the ceiling of the exact interpolation (within 1/32 LSB: the planes'
/// error is under 2⁻⁹, the 5-6-5 lanes' under 2⁻⁶).
#[test]
fn dithered_gouraud_triangles() {
    use embedded_raster::reference;
    use embedded_raster::{GouraudTriangle, SliceFramebuffer, Vertex};
    fn case<C: GouraudColor + Debug>(rng: &mut Rng, w: u32, h: u32) {
        let range = if rng.chance(5) { 2000 } else { 50 };
        let vertices: [Vertex<C>; 3] = core::array::from_fn(|_| {
            let c = core::array::from_fn(|k| rng.below(u64::from(C::MAX[k]) + 1) as u8);
            Vertex::new(
                Coord::from_bits(rng.range(-range * 256, range * 256) as i32),
                Coord::from_bits(rng.range(-range * 256, range * 256) as i32),
                C::from_channels(c),
            )
        });
        let t = GouraudTriangle::new(vertices);
        let background = C::from_channels([1, 1, 1]);
        let n = (w * h) as usize;
        let (mut a, mut b) = (vec![background; n], vec![background; n]);
        t.dithered()
            .draw_into(&mut SliceFramebuffer::new(&mut a, w, h).unwrap());
        t.dithered()
            .draw(&mut SliceFramebuffer::new(&mut b, w, h).unwrap())
            .unwrap();
        let mut c = ReadableTarget::new(w, h, vec![background; n]);
        t.dithered().draw(&mut c).unwrap();
        assert_eq!(a, b);
        assert_eq!(a, c.pixels);
        let raw = vertices.map(|v| (v.x.to_bits(), v.y.to_bits()));
        let channels = vertices.map(|v| v.color.channels().map(f64::from));
        let mut covers = vec![false; n];
        reference::for_each_covered(raw, 0, 0, w as i32, h as i32, |x, y| {
            covers[(y as u32 * w + x as u32) as usize] = true;
        });
        for (i, (&got, &covered)) in a.iter().zip(&covers).enumerate() {
            let (x, y) = ((i as u32 % w) as i32, (i as u32 / w) as i32);
            if !covered {
                assert_eq!(got, background, "({x}, {y}) drawn outside");
                continue;
            }
            let exact = reference::interpolate(raw, channels, x, y).unwrap();
            let g = got.channels();
            for k in 0..C::CHANNELS {
                let g = f64::from(g[k]);
                assert!(
                    (exact[k] - 1.0 / 32.0).floor() <= g && g <= (exact[k] + 1.0 / 32.0).ceil(),
                    "{}: ({x}, {y}) channel {k}: {g} vs {}",
                    std::any::type_name::<C>(),
                    exact[k]
                );
            }
        }
    }
    let mut rng = Rng(9);
    for _ in 0..300 {
        match rng.below(4) {
            0 => case::<Rgb565>(&mut rng, 40, 32),
            1 => case::<Bgr565>(&mut rng, 40, 32),
            2 => case::<Rgb888>(&mut rng, 40, 32),
            _ => case::<Gray4>(&mut rng, 40, 32),
        }
    }
}
