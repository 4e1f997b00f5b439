//! `bench_report lines`: thin lines against embedded-graphics' `Line` and `Polyline`
//! (issue #30, item 4).
//!
//! Lines between pixel centres on a 320×240 `Rgb565` `SliceFramebuffer` (so that
//! embedded-graphics, whose points are integers, draws the same segments): 4,096 short ones
//! (≈8 px), 1,024 of ≈60 px and 128 of ≈300 px, and polylines of 64 points (≈20 px a segment,
//! a plot). Ours: `Line::draw_into` and `Polyline::draw_into`; embedded-graphics 0.8:
//! `Line::into_styled(PrimitiveStyle::with_stroke(c, 1)).draw` and the same for `Polyline`,
//! into the same framebuffer (its `draw_iter`). Rates are ours's pixels a second for both.
//!
//! Side by side, the pixels each draws differently from the diamond-exit rule (ours is tested to
//! follow it exactly), apart from the end point that rule leaves to the next segment.

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::{Duration, Instant};

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Line as EgLine, Polyline as EgPolyline, PrimitiveStyle};
use embedded_raster::{Coord, Line, Polyline, SliceFramebuffer};

use super::workload::{Rng, HEIGHT, WIDTH};
use super::{interleave, median, reps_for};

const ROUNDS: usize = 21;
const SAMPLE: Duration = Duration::from_millis(15);

struct LineSet {
    name: &'static str,
    /// Each a polyline (two points: a line).
    paths: Vec<Vec<Point>>,
}

fn centre(p: Point) -> (Coord, Coord) {
    (
        Coord::from_bits(p.x * 256 + 128),
        Coord::from_bits(p.y * 256 + 128),
    )
}

impl LineSet {
    fn new(name: &'static str) -> Self {
        let mut rng = Rng::new(0x11e5_7e57);
        let point = |rng: &mut Rng| {
            Point::new(
                rng.below(WIDTH as u64) as i32,
                rng.below(HEIGHT as u64) as i32,
            )
        };
        let near = |rng: &mut Rng, p: Point, r: f64| {
            let t = rng.uniform(0.0, std::f64::consts::TAU);
            Point::new(
                (f64::from(p.x) + r * t.cos())
                    .round()
                    .clamp(0.0, WIDTH as f64 - 1.0) as i32,
                (f64::from(p.y) + r * t.sin())
                    .round()
                    .clamp(0.0, HEIGHT as f64 - 1.0) as i32,
            )
        };
        let paths = match name {
            "short_8px" => (0..4096)
                .map(|_| {
                    let p = point(&mut rng);
                    vec![p, near(&mut rng, p, 8.0)]
                })
                .collect(),
            "medium_60px" => (0..1024)
                .map(|_| {
                    let p = point(&mut rng);
                    vec![p, near(&mut rng, p, 60.0)]
                })
                .collect(),
            "long_300px" => (0..128)
                .map(|_| {
                    let p = point(&mut rng);
                    vec![p, near(&mut rng, p, 300.0)]
                })
                .collect(),
            _ => (0..64)
                .map(|_| {
                    let mut p = point(&mut rng);
                    let mut path = vec![p];
                    for _ in 0..63 {
                        p = near(&mut rng, p, 20.0);
                        path.push(p);
                    }
                    path
                })
                .collect(),
        };
        LineSet { name, paths }
    }
}

const SETS: [&str; 4] = ["short_8px", "medium_60px", "long_300px", "polylines_64"];

fn draw(eg: bool, set: &LineSet, pixels: &mut [Rgb565]) {
    let mut fb = SliceFramebuffer::new(pixels, WIDTH as u32, HEIGHT as u32).expect("320×240");
    let color = Rgb565::CSS_ORANGE;
    for path in black_box(&set.paths) {
        match (eg, path.as_slice()) {
            (false, [a, b]) => Line::new(centre(*a), centre(*b), color).draw_into(&mut fb),
            (false, points) => {
                let points: Vec<(Coord, Coord)> = points.iter().map(|&p| centre(p)).collect();
                Polyline::new(&points, color).draw_into(&mut fb);
            }
            (true, [a, b]) => {
                let _ = EgLine::new(*a, *b)
                    .into_styled(PrimitiveStyle::with_stroke(color, 1))
                    .draw(&mut fb);
            }
            (true, points) => {
                let _ = EgPolyline::new(points)
                    .into_styled(PrimitiveStyle::with_stroke(color, 1))
                    .draw(&mut fb);
            }
        }
    }
    black_box(&fb);
}

#[inline(never)]
fn line_passes(eg: bool, set: &LineSet, pixels: &mut [Rgb565], passes: u32) {
    for _ in 0..passes {
        draw(eg, set, pixels);
    }
}

fn time(eg: bool, set: &LineSet, pixels: &mut [Rgb565], reps: u32) -> Duration {
    let start = Instant::now();
    line_passes(eg, set, pixels, reps);
    start.elapsed()
}

/// The pixels one path draws: ours, or embedded-graphics'.
fn pixel_set(eg: bool, path: &[Point]) -> BTreeSet<(i32, i32)> {
    let mut pixels = vec![Rgb565::BLACK; WIDTH * HEIGHT];
    let mut set = BTreeSet::new();
    draw(
        eg,
        &LineSet {
            name: "",
            paths: vec![path.to_vec()],
        },
        &mut pixels,
    );
    for (i, p) in pixels.iter().enumerate() {
        if *p != Rgb565::BLACK {
            set.insert(((i % WIDTH) as i32, (i / WIDTH) as i32));
        }
    }
    set
}

/// Pixels of ours a pass, and the pixels embedded-graphics draws apart from ours (its extra,
/// its missing), the final end point not counted.
fn compare(set: &LineSet) -> (u64, u64, u64) {
    let (mut total, mut extra, mut missing) = (0, 0, 0);
    for path in &set.paths {
        let ours = pixel_set(false, path);
        let mut theirs = pixel_set(true, path);
        if let Some(last) = path.last() {
            theirs.remove(&(last.x, last.y));
        }
        total += ours.len() as u64;
        extra += theirs.difference(&ours).count() as u64;
        missing += ours.difference(&theirs).count() as u64;
    }
    (total, extra, missing)
}

/// `bench_report lines <ours|eg> <set> [passes]`, for callgrind (`--toggle-collect='*line_passes*'`).
pub fn profile_lines(who: &str, name: &str, passes: u32) {
    let name = SETS
        .into_iter()
        .find(|s| *s == name)
        .unwrap_or_else(|| panic!("sets: {SETS:?}"));
    let set = LineSet::new(name);
    let mut pixels = vec![Rgb565::BLACK; WIDTH * HEIGHT];
    let elapsed = time(who == "eg", &set, &mut pixels, passes);
    let (px, _, _) = compare(&set);
    println!(
        "{who} on {name}: {passes} passes, {} px, {:.1} Mpx/s",
        px * u64::from(passes),
        (px * u64::from(passes)) as f64 / elapsed.as_secs_f64() / 1e6
    );
}

pub fn report_lines() -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "\n### Thin lines against embedded-graphics 0.8 (`Line`, `Polyline`, 1 px stroke)\n\n\
         | set | px a pass | ours Mpx/s | e-g Mpx/s | ours / e-g | e-g pixels not on the diamond-exit rule (extra, missing) |\n\
         |---|---:|---:|---:|---:|---:|"
    );
    for name in SETS {
        let set = LineSet::new(name);
        let (px, extra, missing) = compare(&set);
        let mut pixels = vec![Rgb565::BLACK; WIDTH * HEIGHT];
        let reps = [false, true].map(|eg| reps_for(SAMPLE, |r| time(eg, &set, &mut pixels, r)));
        let mut cells = [(false, vec![]), (true, vec![])];
        let mut ratios = vec![];
        for _ in 0..ROUNDS {
            let mut round = [0.0; 2];
            interleave(&mut cells, 1, 1, |(eg, rates): &mut (bool, Vec<f64>)| {
                let r = reps[usize::from(*eg)];
                let d = time(*eg, &set, &mut pixels, r);
                let rate = (px * u64::from(r)) as f64 / d.as_secs_f64() / 1e6;
                rates.push(rate);
                round[usize::from(*eg)] = rate;
            });
            ratios.push(round[0] / round[1]);
        }
        let [ours, theirs] = cells.map(|(_, mut rates)| median(&mut rates));
        let _ = writeln!(
            md,
            "| {} | {px} | {ours:.0} | {theirs:.0} | {:.2}× | {extra}, {missing} |",
            set.name,
            median(&mut ratios)
        );
    }
    md
}
