//! `bench_report polygons`: filled polygons against tiny-skia 0.12's aliased `fill_path`
//! (issue #30, item 4).
//!
//! Three sets on 320×240, vertices in 1/256 px, each polygon in its own colour:
//!
//! * `stars_16px2` — 2,048 five-pointed stars (pentagrams, self-intersecting: ten edges
//!   each), about 16 px² of covered area;
//! * `polygons_1000px2` — 256 star-shaped polygons of 6–14 vertices at random radii, about
//!   1,000 px²;
//! * `frames_screen` — 16 screen-sized polygons with a hole (two contours of 8 vertices).
//!
//! Filled by this crate (`Polygon::filled(color).with_rule(rule).draw_into` a
//! `SliceFramebuffer<Rgb888>`) and by tiny-skia (`Pixmap::fill_path` of the same contours as
//! `f32`, `anti_alias = false`, opaque solid paint, into its RGBA8888 pixmap), under the
//! non-zero rule and the even-odd rule. Rates are this crate's covered pixels a second for both
//! (the same polygons), from interleaved rounds as the main report's.
//!
//! Correctness side by side: each polygon drawn alone, both renderers' pixels against the exact
//! winding number at each pixel centre (`i128` cross products, the module's tie rule): pixels
//! that differ from it, and how many of those lie within 1/64 px of an edge.

use std::fmt::Write as _;
use std::hint::black_box;
use std::time::{Duration, Instant};

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_raster::{Coord, FillRule, Polygon, SliceFramebuffer};
use tiny_skia::{Paint, Path, PathBuilder, Pixmap, Transform};

use super::workload::{Rng, HEIGHT, WIDTH};
use super::{interleave, median, reps_for};

const ROUNDS: usize = 21;
const SAMPLE: Duration = Duration::from_millis(15);
/// Vertices a polygon can hold.
const CAPACITY: usize = 16;

/// Contours in 1/256 px.
type Contours = Vec<Vec<(i32, i32)>>;

/// A set of polygons in each renderer's form.
pub struct PolygonSet {
    ours: Vec<(Polygon<CAPACITY>, Rgb888)>,
    skia: Vec<(Path, Paint<'static>)>,
    contours: Vec<Contours>,
}

fn star(rng: &mut Rng, radius: f64) -> Vec<(f64, f64)> {
    let (cx, cy) = (
        rng.uniform(0.0, WIDTH as f64),
        rng.uniform(0.0, HEIGHT as f64),
    );
    let phase = rng.uniform(0.0, std::f64::consts::TAU);
    (0..5)
        .map(|k| {
            // Every second point of five: a pentagram.
            let t = phase + (k * 2) as f64 * std::f64::consts::TAU / 5.0;
            (cx + radius * t.cos(), cy + radius * t.sin())
        })
        .collect()
}

fn star_shaped(rng: &mut Rng, n: usize, radius: f64, (cx, cy): (f64, f64)) -> Vec<(f64, f64)> {
    let phase = rng.uniform(0.0, std::f64::consts::TAU);
    (0..n)
        .map(|k| {
            let t = phase + k as f64 * std::f64::consts::TAU / n as f64;
            let r = radius * rng.uniform(0.6, 1.0);
            (cx + r * t.cos(), cy + r * t.sin())
        })
        .collect()
}

fn raw(points: &[(f64, f64)]) -> Vec<(i32, i32)> {
    points
        .iter()
        .map(|&(x, y)| ((x * 256.0).round() as i32, (y * 256.0).round() as i32))
        .collect()
}

fn color(rng: &mut Rng) -> Rgb888 {
    let c = rng.next_u64();
    Rgb888::new(c as u8 | 1, (c >> 8) as u8, (c >> 16) as u8)
}

impl PolygonSet {
    fn new(name: &'static str) -> Self {
        let mut rng = Rng::new(0x9017_6047);
        let shapes: Vec<Contours> = match name {
            "stars_16px2" => (0..2048).map(|_| vec![raw(&star(&mut rng, 3.6))]).collect(),
            "polygons_1000px2" => (0..256)
                .map(|_| {
                    let n = 6 + rng.below(9) as usize;
                    let centre = (
                        rng.uniform(0.0, WIDTH as f64),
                        rng.uniform(0.0, HEIGHT as f64),
                    );
                    vec![raw(&star_shaped(&mut rng, n, 20.0, centre))]
                })
                .collect(),
            _ => (0..16)
                .map(|_| {
                    let centre = (
                        WIDTH as f64 / 2.0 + rng.uniform(-20.0, 20.0),
                        HEIGHT as f64 / 2.0 + rng.uniform(-20.0, 20.0),
                    );
                    let outer = star_shaped(&mut rng, 8, 190.0, centre);
                    let mut inner = star_shaped(&mut rng, 8, 60.0, centre);
                    inner.reverse();
                    vec![raw(&outer), raw(&inner)]
                })
                .collect(),
        };
        let mut ours = vec![];
        let mut skia = vec![];
        for contours in &shapes {
            let c = color(&mut rng);
            let mut polygon = Polygon::new();
            let mut pb = PathBuilder::new();
            for contour in contours {
                let points: Vec<(Coord, Coord)> = contour
                    .iter()
                    .map(|&(x, y)| (Coord::from_bits(x), Coord::from_bits(y)))
                    .collect();
                polygon.add_contour(&points).expect("capacity");
                for (k, p) in points.iter().enumerate() {
                    let (x, y) = (p.0.to_num::<f32>(), p.1.to_num::<f32>());
                    if k == 0 {
                        pb.move_to(x, y);
                    } else {
                        pb.line_to(x, y);
                    }
                }
                pb.close();
            }
            ours.push((polygon, c));
            let mut paint = Paint::default();
            paint.set_color_rgba8(c.r(), c.g(), c.b(), 255);
            paint.anti_alias = false;
            skia.push((pb.finish().expect("a path"), paint));
        }
        PolygonSet {
            ours,
            skia,
            contours: shapes,
        }
    }
}

const SETS: [&str; 3] = ["stars_16px2", "polygons_1000px2", "frames_screen"];

fn skia_rule(rule: FillRule) -> tiny_skia::FillRule {
    match rule {
        FillRule::NonZero => tiny_skia::FillRule::Winding,
        FillRule::EvenOdd => tiny_skia::FillRule::EvenOdd,
    }
}

struct Targets {
    pixels: Vec<Rgb888>,
    pixmap: Pixmap,
}

impl Targets {
    fn new() -> Self {
        Targets {
            pixels: vec![Rgb888::BLACK; WIDTH * HEIGHT],
            pixmap: Pixmap::new(WIDTH as u32, HEIGHT as u32).expect("a pixmap"),
        }
    }
}

/// One pass: ours (`skia == false`) or tiny-skia's.
fn draw(skia: bool, set: &PolygonSet, rule: FillRule, targets: &mut Targets) {
    if skia {
        for (path, paint) in black_box(&set.skia) {
            targets
                .pixmap
                .fill_path(path, paint, skia_rule(rule), Transform::identity(), None);
        }
    } else {
        let mut fb = SliceFramebuffer::new(&mut targets.pixels, WIDTH as u32, HEIGHT as u32)
            .expect("320×240");
        for (polygon, color) in black_box(&set.ours) {
            polygon.filled(*color).with_rule(rule).draw_into(&mut fb);
        }
    }
    black_box(targets);
}

/// `passes` passes (callgrind: `--toggle-collect='*polygon_passes*'`).
#[inline(never)]
fn polygon_passes(skia: bool, set: &PolygonSet, rule: FillRule, t: &mut Targets, passes: u32) {
    for _ in 0..passes {
        draw(skia, set, rule, t);
    }
}

fn time(skia: bool, set: &PolygonSet, rule: FillRule, t: &mut Targets, reps: u32) -> Duration {
    let start = Instant::now();
    polygon_passes(skia, set, rule, t, reps);
    start.elapsed()
}

/// The exact winding number at the centre of pixel `(i, j)`.
fn winding(contours: &Contours, i: i32, j: i32) -> i32 {
    let (px, py) = (i128::from(i) * 256 + 128, i128::from(j) * 256 + 128);
    let mut w = 0;
    for c in contours {
        for k in 0..c.len() {
            let (a, b) = (c[k], c[(k + 1) % c.len()]);
            let (dir, (xa, ya), (xb, yb)) = match a.1.cmp(&b.1) {
                std::cmp::Ordering::Less => (1, a, b),
                std::cmp::Ordering::Greater => (-1, b, a),
                std::cmp::Ordering::Equal => continue,
            };
            let (xa, ya, xb, yb) = (xa as i128, ya as i128, xb as i128, yb as i128);
            if ya <= py && py < yb && (px - xa) * (yb - ya) - (py - ya) * (xb - xa) >= 0 {
                w += dir;
            }
        }
    }
    w
}

/// Whether the centre of `(i, j)` lies within 1/64 px of an edge of `contours`.
fn near_edge(contours: &Contours, i: i32, j: i32) -> bool {
    let (px, py) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
    contours.iter().any(|c| {
        (0..c.len()).any(|k| {
            let f = |(x, y): (i32, i32)| (f64::from(x) / 256.0, f64::from(y) / 256.0);
            let ((x0, y0), (x1, y1)) = (f(c[k]), f(c[(k + 1) % c.len()]));
            let (dx, dy) = (x1 - x0, y1 - y0);
            let len2 = dx * dx + dy * dy;
            let t = if len2 > 0.0 {
                (((px - x0) * dx + (py - y0) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (qx, qy) = (x0 + t * dx - px, y0 + t * dy - py);
            (qx * qx + qy * qy).sqrt() <= 1.0 / 64.0
        })
    })
}

/// Pixels of each polygon drawn alone that differ from the exact winding rule: (ours, ours near
/// an edge, tiny-skia's, tiny-skia's near an edge, pixels inside).
fn correctness(set: &PolygonSet, rule: FillRule) -> [u64; 5] {
    let mut t = Targets::new();
    let mut counts = [0u64; 5];
    for (k, contours) in set.contours.iter().enumerate() {
        t.pixels.fill(Rgb888::BLACK);
        t.pixmap.fill(tiny_skia::Color::TRANSPARENT);
        let (polygon, _) = &set.ours[k];
        polygon.filled(Rgb888::WHITE).with_rule(rule).draw_into(
            &mut SliceFramebuffer::new(&mut t.pixels, WIDTH as u32, HEIGHT as u32).unwrap(),
        );
        let (path, paint) = &set.skia[k];
        t.pixmap
            .fill_path(path, paint, skia_rule(rule), Transform::identity(), None);
        let skia = t.pixmap.pixels();
        // The polygon's box and a pixel around it (everything else is blank for both).
        let all = contours.iter().flatten();
        let x0 = (all.clone().map(|p| p.0 >> 8).min().unwrap_or(0) - 1).max(0);
        let x1 = (all.clone().map(|p| p.0 >> 8).max().unwrap_or(0) + 2).min(WIDTH as i32);
        let y0 = (all.clone().map(|p| p.1 >> 8).min().unwrap_or(0) - 1).max(0);
        let y1 = (all.map(|p| p.1 >> 8).max().unwrap_or(0) + 2).min(HEIGHT as i32);
        for j in y0..y1 {
            for i in x0..x1 {
                let n = j as usize * WIDTH + i as usize;
                let exact = rule.inside(winding(contours, i, j));
                counts[4] += u64::from(exact);
                let ours = t.pixels[n] == Rgb888::WHITE;
                let theirs = skia[n].alpha() > 0;
                if ours != exact {
                    counts[0] += 1;
                    counts[1] += u64::from(near_edge(contours, i, j));
                }
                if theirs != exact {
                    counts[2] += 1;
                    counts[3] += u64::from(near_edge(contours, i, j));
                }
            }
        }
    }
    counts
}

/// Covered pixels of one pass of ours.
fn covered(set: &PolygonSet, rule: FillRule) -> u64 {
    let clip = embedded_graphics::primitives::Rectangle::new(
        embedded_graphics::prelude::Point::zero(),
        embedded_graphics::prelude::Size::new(WIDTH as u32, HEIGHT as u32),
    );
    let mut n = 0u64;
    for (polygon, _) in &set.ours {
        polygon.for_each_span(rule, &clip, |_, a, b| n += (b - a) as u64);
    }
    n
}

/// Profiling mode: `bench_report polygons <ours|tiny-skia> <set> <nonzero|evenodd> [passes]`.
pub fn profile_polygons(who: &str, set: &str, rule: &str, passes: u32) {
    let rule = if rule == "evenodd" {
        FillRule::EvenOdd
    } else {
        FillRule::NonZero
    };
    let name = SETS
        .into_iter()
        .find(|s| *s == set)
        .unwrap_or_else(|| panic!("sets: {SETS:?}"));
    let set = PolygonSet::new(name);
    let mut t = Targets::new();
    let elapsed = time(who == "tiny-skia", &set, rule, &mut t, passes);
    let px = covered(&set, rule) * u64::from(passes);
    println!(
        "{who} on {name} ({rule:?}): {passes} passes, {px} px, {:.1} Mpx/s",
        px as f64 / elapsed.as_secs_f64() / 1e6
    );
}

/// The table: rates, the ratio, and correctness against the exact winding numbers.
pub fn report_polygons() -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "\n### Filled polygons against tiny-skia 0.12 (aliased `fill_path`)\n\n\
         | set | rule | covered px a pass | ours Mpx/s | tiny-skia Mpx/s | ours / tiny-skia | \
         ours wrong (near an edge) | tiny-skia wrong (near an edge) |\n\
         |---|---|---:|---:|---:|---:|---:|---:|"
    );
    for name in SETS {
        for rule in [FillRule::NonZero, FillRule::EvenOdd] {
            let set = PolygonSet::new(name);
            let px = covered(&set, rule);
            let mut t = Targets::new();
            let reps =
                [false, true].map(|skia| reps_for(SAMPLE, |r| time(skia, &set, rule, &mut t, r)));
            // cells: (skia, rates)
            let mut cells = [(false, vec![]), (true, vec![])];
            let mut ratios = vec![];
            for _ in 0..ROUNDS {
                let mut round = [0.0; 2];
                interleave(&mut cells, 1, 1, |(skia, rates): &mut (bool, Vec<f64>)| {
                    let r = reps[usize::from(*skia)];
                    let d = time(*skia, &set, rule, &mut t, r);
                    let rate = (px * u64::from(r)) as f64 / d.as_secs_f64() / 1e6;
                    rates.push(rate);
                    round[usize::from(*skia)] = rate;
                });
                ratios.push(round[0] / round[1]);
            }
            let [ours, theirs] = cells.map(|(_, mut rates)| median(&mut rates));
            let c = correctness(&set, rule);
            let _ = writeln!(
                md,
                "| {name} | {rule:?} | {px} | {ours:.0} | {theirs:.0} | {:.2}× | {} ({}) | {} ({}) |",
                median(&mut ratios),
                c[0],
                c[1],
                c[2],
                c[3]
            );
        }
    }
    md
}
