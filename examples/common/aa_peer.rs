//! `bench_report aa`: anti-aliased triangle fills against tiny-skia 0.12 (issue #33, item 4).
//!
//! The workload's triangles (`benches/fill_rate/workload.rs`: ≈16 px², ≈1,000 px² and
//! screen-filling sets on 320×240, vertices in 1/256 px), each in its own colour, filled
//!
//! * by this crate, `SolidTriangle::anti_aliased().draw_into` a `SliceFramebuffer<Rgb888>`;
//! * by tiny-skia, `Pixmap::fill_path` of the triangle's path (the same vertices as `f32`),
//!   `anti_alias = true`, solid opaque paint, source-over, into its 320×240 RGBA8888 pixmap;
//! * by this crate aliased (`SolidTriangle::draw_into`, `Rgb888`), for scale.
//!
//! Rates are covered pixels a second: the pixels whose square the triangle covers at all (exact
//! area > 0, in the frame), the same count for every renderer, so the rate ratio is the time
//! ratio for the same triangles. Cells are timed in interleaved rounds as the main report's.
//!
//! Then the accuracy of both anti-aliased fills against the exact area
//! (`reference::pixel_area`): every triangle of the sets drawn white alone on black (ours: the
//! red channel of `Rgb888`; tiny-skia: the alpha of a transparent pixmap), the error
//! `|value − 255·area|` over the pixels an edge cuts (`0 < area < 1`); and the seam dip of
//! shapes made of triangles drawn one after another, white: `255 −` the least value over the
//! pixels wholly inside the shape.

use std::f64::consts::TAU;
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::{Duration, Instant};

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::{Point, Size};
use embedded_graphics::primitives::Rectangle;
use embedded_raster::{AntiAliased, Coord, CoverageMask, SliceFramebuffer, SolidTriangle};
use tiny_skia::{FillRule, Paint, Path, PathBuilder, Pixmap, PremultipliedColorU8, Transform};

use super::reference::pixel_area;
use super::workload::{triangles, Rng, SizeClass, HEIGHT, WIDTH};
use super::{interleave, median, reps_for};

/// Rounds of interleaved anti-aliasing measurements.
const ROUNDS_AA: usize = 21;
/// Target duration of one timed sample.
const SAMPLE_AA: Duration = Duration::from_millis(15);
/// The goal: ours at least this many times tiny-skia's pixel rate.
const GOAL: f64 = 4.0;

/// Who fills the triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AaMethod {
    /// `SolidTriangle::anti_aliased().draw_into(&mut SliceFramebuffer<Rgb888>)`.
    Ours,
    /// tiny-skia 0.12 `Pixmap::fill_path`, anti-aliased.
    TinySkia,
    /// `SolidTriangle::draw_into(&mut SliceFramebuffer<Rgb888>)`: no anti-aliasing.
    OursAliased,
}

impl AaMethod {
    const ALL: [AaMethod; 3] = [AaMethod::Ours, AaMethod::TinySkia, AaMethod::OursAliased];

    fn id(self) -> &'static str {
        match self {
            AaMethod::Ours => "ours",
            AaMethod::TinySkia => "tiny-skia",
            AaMethod::OursAliased => "ours-aliased",
        }
    }

    fn label(self) -> &'static str {
        match self {
            AaMethod::Ours => "ours: `anti_aliased().draw_into` → SliceFramebuffer<Rgb888>",
            AaMethod::TinySkia => "tiny-skia 0.12 `fill_path`, anti-aliased → Pixmap (RGBA8888)",
            AaMethod::OursAliased => "ours aliased: `SolidTriangle::draw_into` → Rgb888 (scale)",
        }
    }
}

/// The corners of a triangle in 1/256 px.
type Corners = [(Coord, Coord); 3];

fn coord(v: f64) -> Coord {
    Coord::from_bits((v * 256.0).round() as i32)
}

fn raw(points: &Corners) -> [(i32, i32); 3] {
    points.map(|(x, y)| (x.to_bits(), y.to_bits()))
}

/// tiny-skia's path of a triangle: the same vertices, exact in `f32`.
fn path(points: &Corners) -> Path {
    let mut pb = PathBuilder::new();
    let f = |(x, y): (Coord, Coord)| (x.to_num::<f32>(), y.to_num::<f32>());
    let [a, b, c] = points.map(f);
    pb.move_to(a.0, a.1);
    pb.line_to(b.0, b.1);
    pb.line_to(c.0, c.1);
    pb.close();
    pb.finish().expect("a triangle's path")
}

fn paint(color: Rgb888) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color_rgba8(color.r(), color.g(), color.b(), 255);
    paint.anti_alias = true;
    paint
}

/// A size class's triangles in each renderer's form (built outside the timed loops).
pub struct AaSet {
    ours: Vec<AntiAliased<SolidTriangle<Rgb888>>>,
    aliased: Vec<SolidTriangle<Rgb888>>,
    skia: Vec<(Path, Paint<'static>)>,
    corners: Vec<Corners>,
    /// Pixels of the frame each triangle covers at all (exact area > 0), summed over the set.
    covered: u64,
    /// The exact area in the frame, px², summed over the set.
    area: f64,
}

/// The pixels of the frame that the bounding box of `points` meets: `(x0, y0, x1, y1)`,
/// exclusive ends.
fn frame_box(points: &Corners) -> (i32, i32, i32, i32) {
    let xs = points.map(|p| p.0.to_num::<f64>());
    let ys = points.map(|p| p.1.to_num::<f64>());
    let lo = |v: [f64; 3], max: usize| {
        (v.iter().copied().fold(f64::MAX, f64::min).floor() as i32).clamp(0, max as i32)
    };
    let hi = |v: [f64; 3], max: usize| {
        (v.iter().copied().fold(f64::MIN, f64::max).ceil() as i32).clamp(0, max as i32)
    };
    (lo(xs, WIDTH), lo(ys, HEIGHT), hi(xs, WIDTH), hi(ys, HEIGHT))
}

impl AaSet {
    pub fn new(class: SizeClass) -> Self {
        let tris = triangles(class);
        let corners: Vec<Corners> = tris.iter().map(|t| t.positions).collect();
        let colors: Vec<Rgb888> = tris.iter().map(|t| t.colors[0].into()).collect();
        let aliased: Vec<SolidTriangle<Rgb888>> = corners
            .iter()
            .zip(&colors)
            .map(|(&p, &c)| SolidTriangle::new(p, c))
            .collect();
        let (mut covered, mut area) = (0u64, 0.0);
        for p in &corners {
            let (x0, y0, x1, y1) = frame_box(p);
            let v = raw(p);
            for y in y0..y1 {
                for x in x0..x1 {
                    let a = pixel_area(v, x, y);
                    covered += u64::from(a > 0.0);
                    area += a;
                }
            }
        }
        AaSet {
            ours: aliased.iter().map(|t| t.anti_aliased()).collect(),
            skia: corners
                .iter()
                .zip(&colors)
                .map(|(p, &c)| (path(p), paint(c)))
                .collect(),
            aliased,
            corners,
            covered,
            area,
        }
    }
}

/// Both renderers' 320×240 targets.
pub struct AaTargets {
    pixels: Vec<Rgb888>,
    pixmap: Pixmap,
}

impl AaTargets {
    pub fn new() -> Self {
        AaTargets {
            pixels: vec![Rgb888::BLACK; WIDTH * HEIGHT],
            pixmap: Pixmap::new(WIDTH as u32, HEIGHT as u32).expect("a 320×240 pixmap"),
        }
    }

    fn framebuffer(&mut self) -> SliceFramebuffer<'_, Rgb888> {
        SliceFramebuffer::new(&mut self.pixels, WIDTH as u32, HEIGHT as u32).expect("320×240")
    }
}

/// One pass over the set by `method`.
fn draw(method: AaMethod, set: &AaSet, targets: &mut AaTargets) {
    match method {
        AaMethod::Ours => {
            let mut fb = targets.framebuffer();
            for t in black_box(&set.ours) {
                t.draw_into(&mut fb);
            }
        }
        AaMethod::OursAliased => {
            let mut fb = targets.framebuffer();
            for t in black_box(&set.aliased) {
                t.draw_into(&mut fb);
            }
        }
        AaMethod::TinySkia => {
            for (path, paint) in black_box(&set.skia) {
                targets.pixmap.fill_path(
                    path,
                    paint,
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                );
            }
        }
    }
    black_box(targets);
}

/// `passes` passes over the set: the function callgrind's `--toggle-collect` names.
#[inline(never)]
fn aa_passes(method: AaMethod, set: &AaSet, targets: &mut AaTargets, passes: u32) {
    for _ in 0..passes {
        draw(method, set, targets);
    }
}

fn time(method: AaMethod, set: &AaSet, targets: &mut AaTargets, reps: u32) -> Duration {
    let start = Instant::now();
    aa_passes(method, set, targets, reps);
    start.elapsed()
}

fn parse_method(id: &str) -> AaMethod {
    AaMethod::ALL
        .into_iter()
        .find(|m| m.id() == id)
        .unwrap_or_else(|| panic!("methods: {:?}", AaMethod::ALL.map(AaMethod::id)))
}

fn parse_class(id: &str) -> SizeClass {
    SizeClass::ALL
        .into_iter()
        .find(|c| c.id() == id)
        .unwrap_or_else(|| panic!("size classes: {:?}", SizeClass::ALL.map(SizeClass::id)))
}

/// Profiling mode (`bench_report aa <method> <class> [passes]`): `passes` passes of one set by
/// one renderer inside `aa_passes`; prints the covered pixels of one pass and of all.
pub fn profile_aa(method: &str, class: &str, passes: u32) {
    let (method, class) = (parse_method(method), parse_class(class));
    let set = AaSet::new(class);
    let mut targets = AaTargets::new();
    let elapsed = time(method, &set, &mut targets, passes);
    println!(
        "{} on {}: {} triangles, {} covered px a pass ({:.0} px² of area), {passes} passes, {} \
         px, {:.1} Mpx/s",
        method.id(),
        class.id(),
        set.corners.len(),
        set.covered,
        set.area,
        set.covered * u64::from(passes),
        (set.covered * u64::from(passes)) as f64 / elapsed.as_secs_f64() / 1e6
    );
}

// ---- accuracy -----------------------------------------------------------------------------------

/// Error statistics in 1/255 over the pixels an edge cuts.
#[derive(Default, Clone, Copy)]
struct Errors {
    sum: f64,
    max: f64,
    pixels: u64,
    /// Pixels wholly inside not 255, or wholly outside not 0 (within the triangle's box).
    wrong_elsewhere: u64,
}

impl Errors {
    fn add(&mut self, value: u8, area: f64) {
        if area > 0.0 && area < 1.0 {
            let e = (f64::from(value) - 255.0 * area).abs();
            self.sum += e;
            self.max = self.max.max(e);
            self.pixels += 1;
        } else if (area >= 1.0 && value != 255) || (area <= 0.0 && value != 0) {
            self.wrong_elsewhere += 1;
        }
    }

    fn mean(&self) -> f64 {
        self.sum / self.pixels.max(1) as f64
    }
}

/// Each triangle of `set` white alone on black by ours and by tiny-skia, against the exact area.
fn accuracy(set: &AaSet, targets: &mut AaTargets) -> [Errors; 2] {
    let mut errors = [Errors::default(); 2];
    targets.pixels.fill(Rgb888::BLACK);
    targets.pixmap.fill(tiny_skia::Color::TRANSPARENT);
    let white = paint(Rgb888::WHITE);
    for p in &set.corners {
        SolidTriangle::new(*p, Rgb888::WHITE)
            .anti_aliased()
            .draw_into(&mut targets.framebuffer());
        targets.pixmap.fill_path(
            &path(p),
            &white,
            FillRule::Winding,
            Transform::identity(),
            None,
        );
        // One pixel around the box too: tiny-skia snaps x to ¼ px.
        let (x0, y0, x1, y1) = frame_box(p);
        let (x0, y0) = ((x0 - 1).max(0), (y0 - 1).max(0));
        let (x1, y1) = ((x1 + 1).min(WIDTH as i32), (y1 + 1).min(HEIGHT as i32));
        let v = raw(p);
        let skia = targets.pixmap.pixels_mut();
        for y in y0..y1 {
            for x in x0..x1 {
                let i = y as usize * WIDTH + x as usize;
                let area = pixel_area(v, x, y);
                errors[0].add(targets.pixels[i].r(), area);
                errors[1].add(skia[i].alpha(), area);
                targets.pixels[i] = Rgb888::BLACK;
                skia[i] = PremultipliedColorU8::TRANSPARENT;
            }
        }
    }
    errors
}

// ---- seams --------------------------------------------------------------------------------------

/// How a shape made of triangles is drawn, white.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SeamWay {
    TinySkia,
    OursPerTriangle,
    OursShared,
    OursMask,
}

impl SeamWay {
    const ALL: [SeamWay; 4] = [
        SeamWay::TinySkia,
        SeamWay::OursPerTriangle,
        SeamWay::OursShared,
        SeamWay::OursMask,
    ];

    fn label(self) -> &'static str {
        match self {
            SeamWay::TinySkia => "tiny-skia, each triangle filled on its own (source-over)",
            SeamWay::OursPerTriangle => "ours, `anti_aliased()` triangle by triangle",
            SeamWay::OursShared => "ours, `anti_aliased().with_shared_edges(..)`",
            SeamWay::OursMask => "ours, one `CoverageMask` (`add` each, `fill_into` once)",
        }
    }
}

/// A shape: its triangles, each with the edges it shares with another.
struct Shape {
    triangles: Vec<(Corners, [bool; 3])>,
    /// The frame indices of the pixels wholly inside the shape (the triangles' exact areas of
    /// the pixel sum to 1).
    inside: Vec<usize>,
}

impl Shape {
    fn new(triangles: Vec<(Corners, [bool; 3])>) -> Shape {
        let boxes: Vec<_> = triangles.iter().map(|(p, _)| frame_box(p)).collect();
        let (x0, y0, x1, y1) = boxes.iter().fold((i32::MAX, i32::MAX, 0, 0), |a, b| {
            (a.0.min(b.0), a.1.min(b.1), a.2.max(b.2), a.3.max(b.3))
        });
        let mut inside = Vec::new();
        for y in y0..y1 {
            for x in x0..x1 {
                let union: f64 = triangles
                    .iter()
                    .zip(&boxes)
                    .filter(|(_, b)| (b.0..b.2).contains(&x) && (b.1..b.3).contains(&y))
                    .map(|((p, _), _)| pixel_area(raw(p), x, y))
                    .sum();
                if union >= 1.0 - 1e-9 {
                    inside.push(y as usize * WIDTH + x as usize);
                }
            }
        }
        Shape { triangles, inside }
    }

    /// A square of side `side` turned by `angle` around `centre`, cut along a diagonal.
    fn square(centre: (f64, f64), side: f64, angle: f64) -> Shape {
        let h = side / 2.0;
        let (s, c) = angle.sin_cos();
        let corner = |u: f64, v: f64| {
            (
                coord(centre.0 + c * u - s * v),
                coord(centre.1 + s * u + c * v),
            )
        };
        let (a, b, cc, d) = (corner(-h, -h), corner(h, -h), corner(h, h), corner(-h, h));
        Shape::new(vec![
            ([a, b, cc], [false, false, true]),
            ([a, cc, d], [true, false, false]),
        ])
    }

    /// `n` triangles around `centre` out to `radius`, the first corner at `phase`.
    fn fan(centre: (f64, f64), radius: f64, n: usize, phase: f64) -> Shape {
        let c = (coord(centre.0), coord(centre.1));
        let rim = |k: usize| {
            let a = phase + TAU * k as f64 / n as f64;
            (
                coord(centre.0 + radius * a.cos()),
                coord(centre.1 + radius * a.sin()),
            )
        };
        Shape::new(
            (0..n)
                .map(|k| ([c, rim(k), rim(k + 1)], [true, false, true]))
                .collect(),
        )
    }

    /// `255 −` the least value `way` gives a pixel wholly inside the shape.
    fn dip(&self, way: SeamWay, targets: &mut AaTargets, cells: &mut [u16]) -> u8 {
        targets.pixels.fill(Rgb888::BLACK);
        targets.pixmap.fill(tiny_skia::Color::TRANSPARENT);
        let white = paint(Rgb888::WHITE);
        let frame = Rectangle::new(Point::zero(), Size::new(WIDTH as u32, HEIGHT as u32));
        let mut mask = CoverageMask::new(cells, frame).expect("cells of the frame");
        for (p, shared) in &self.triangles {
            let t = SolidTriangle::new(*p, Rgb888::WHITE).anti_aliased();
            match way {
                SeamWay::TinySkia => targets.pixmap.fill_path(
                    &path(p),
                    &white,
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                ),
                SeamWay::OursPerTriangle => t.draw_into(&mut targets.framebuffer()),
                SeamWay::OursShared => t
                    .with_shared_edges(*shared)
                    .draw_into(&mut targets.framebuffer()),
                SeamWay::OursMask => mask.add(*p),
            }
        }
        if way == SeamWay::OursMask {
            let mut fb =
                SliceFramebuffer::new(&mut targets.pixels, WIDTH as u32, HEIGHT as u32).unwrap();
            mask.fill_into(Rgb888::WHITE, &mut fb);
        }
        let least = self.inside.iter().map(|&i| match way {
            SeamWay::TinySkia => targets.pixmap.pixels()[i].alpha(),
            _ => targets.pixels[i].r(),
        });
        let least = least.min().unwrap_or(255);
        255 - least
    }
}

/// The seam shapes: `count` squares cut along a diagonal (random sub-pixel centre, side 12–40 px,
/// turn; the first axis-aligned), and `count` 60-triangle fans (random sub-pixel centre, radius
/// 20–60 px, phase).
fn seam_shapes(count: usize) -> (Vec<Shape>, Vec<Shape>) {
    let mut rng = Rng::new(0x5EA3_D1B5);
    let centre = |rng: &mut Rng| (rng.uniform(100.0, 220.0), rng.uniform(70.0, 170.0));
    let squares = (0..count)
        .map(|k| {
            let c = centre(&mut rng);
            let side = rng.uniform(12.0, 40.0);
            let angle = if k == 0 {
                0.0
            } else {
                rng.uniform(0.0, TAU / 4.0)
            };
            Shape::square(c, side, angle)
        })
        .collect();
    let fans = (0..count)
        .map(|_| {
            let c = centre(&mut rng);
            Shape::fan(c, rng.uniform(20.0, 60.0), 60, rng.uniform(0.0, TAU))
        })
        .collect();
    (squares, fans)
}

// ---- the report ---------------------------------------------------------------------------------

struct AaCell {
    class: usize,
    method: AaMethod,
    reps: u32,
    /// Mpx/s of each round.
    rates: Vec<f64>,
}

/// The anti-aliasing section of the report.
pub fn report_aa() -> String {
    let started = Instant::now();
    let sets: Vec<AaSet> = SizeClass::ALL.iter().map(|&c| AaSet::new(c)).collect();
    let mut targets = AaTargets::new();

    let mut cells = Vec::new();
    for (class, set) in sets.iter().enumerate() {
        for method in AaMethod::ALL {
            cells.push(AaCell {
                class,
                method,
                reps: reps_for(SAMPLE_AA, |reps| time(method, set, &mut targets, reps)),
                rates: Vec::with_capacity(ROUNDS_AA),
            });
        }
    }
    interleave(&mut cells, ROUNDS_AA, 4, |cell| {
        let set = &sets[cell.class];
        let elapsed = time(cell.method, set, &mut targets, cell.reps);
        let mpx = (set.covered * u64::from(cell.reps)) as f64 / elapsed.as_secs_f64() / 1e6;
        cell.rates.push(mpx);
    });
    let timing = started.elapsed();

    let find = |class: usize, method: AaMethod| {
        cells
            .iter()
            .find(|c| c.class == class && c.method == method)
            .expect("cell")
    };
    let ratio = |class: usize, method: AaMethod, base: AaMethod| {
        let (a, b) = (find(class, method), find(class, base));
        let mut r: Vec<f64> = a.rates.iter().zip(&b.rates).map(|(x, y)| x / y).collect();
        median(&mut r)
    };
    let classes = SizeClass::ALL;
    let mut md = String::new();
    let header = |md: &mut String, first: &str| {
        write!(md, "| {first} |").unwrap();
        for c in classes {
            write!(md, " {} |", c.label()).unwrap();
        }
        md.push_str("\n|---|");
        for _ in classes {
            md.push_str("---:|");
        }
        md.push('\n');
    };

    writeln!(
        md,
        "### Anti-aliased fill rate against tiny-skia 0.12, 320×240 (million covered px/s, median \
         of {ROUNDS_AA} interleaved rounds)\n"
    )
    .unwrap();
    header(&mut md, "method");
    for method in AaMethod::ALL {
        write!(md, "| {} |", method.label()).unwrap();
        for k in 0..classes.len() {
            write!(md, " {:.0} |", median(&mut find(k, method).rates.clone())).unwrap();
        }
        md.push('\n');
    }
    write!(
        md,
        "| **ours AA / tiny-skia AA** (median per-round ratio) |"
    )
    .unwrap();
    for k in 0..classes.len() {
        write!(
            md,
            " **{:.2}×** |",
            ratio(k, AaMethod::Ours, AaMethod::TinySkia)
        )
        .unwrap();
    }
    write!(md, "\n| ours AA / ours aliased |").unwrap();
    for k in 0..classes.len() {
        write!(
            md,
            " {:.2}× |",
            ratio(k, AaMethod::Ours, AaMethod::OursAliased)
        )
        .unwrap();
    }
    write!(
        md,
        "\n| triangles; covered px a pass (exact area > 0); exact area, px² |"
    )
    .unwrap();
    for set in &sets {
        let n = set.corners.len();
        write!(md, " {n}; {}; {:.0} |", set.covered, set.area).unwrap();
    }
    md.push_str("\n\n");
    for (k, class) in classes.iter().enumerate() {
        let got = ratio(k, AaMethod::Ours, AaMethod::TinySkia);
        let verdict = if got >= GOAL { "met" } else { "MISSED" };
        writeln!(
            md,
            "- ours AA vs tiny-skia AA, {}: {got:.2}×, goal ≥ {GOAL}× — {verdict}",
            class.label()
        )
        .unwrap();
    }

    let accuracy_started = Instant::now();
    writeln!(
        md,
        "\n### Coverage error against the exact area (white on black, /255, over the pixels an \
         edge cuts)\n"
    )
    .unwrap();
    md.push_str(
        "| set | edge pixels | ours mean | ours max | tiny-skia mean | tiny-skia max | other \
         pixels off, ours / tiny-skia |\n|---|---:|---:|---:|---:|---:|---:|\n",
    );
    let mut all = [Errors::default(); 2];
    for (k, set) in sets.iter().enumerate() {
        let e = accuracy(set, &mut targets);
        for (total, e) in all.iter_mut().zip(&e) {
            total.sum += e.sum;
            total.max = total.max.max(e.max);
            total.pixels += e.pixels;
            total.wrong_elsewhere += e.wrong_elsewhere;
        }
        let row = |md: &mut String, name: &str, e: &[Errors; 2]| {
            writeln!(
                md,
                "| {name} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {} / {} |",
                e[0].pixels,
                e[0].mean(),
                e[0].max,
                e[1].mean(),
                e[1].max,
                e[0].wrong_elsewhere,
                e[1].wrong_elsewhere
            )
            .unwrap();
        };
        row(&mut md, classes[k].label(), &e);
        if k + 1 == sets.len() {
            row(&mut md, "all", &all);
        }
    }

    const SHAPES: usize = 16;
    let (squares, fans) = seam_shapes(SHAPES);
    let mut cells16 = vec![0u16; WIDTH * HEIGHT];
    writeln!(
        md,
        "\n### Seam dip (255 − least value over the pixels wholly inside the shape, white on \
         black; worst / mean over {SHAPES} shapes)\n"
    )
    .unwrap();
    md.push_str(
        "| drawn by | square cut along a diagonal | 60-triangle fan around a sub-pixel centre \
         |\n|---|---:|---:|\n",
    );
    for way in SeamWay::ALL {
        let mut stats = |shapes: &[Shape]| {
            let dips: Vec<u8> = shapes
                .iter()
                .map(|s| s.dip(way, &mut targets, &mut cells16))
                .collect();
            let worst = dips.iter().copied().max().unwrap_or(0);
            let mean = dips.iter().map(|&d| f64::from(d)).sum::<f64>() / dips.len() as f64;
            format!("{worst} / {mean:.1}")
        };
        let (s, f) = (stats(&squares), stats(&fans));
        writeln!(md, "| {} | {s} | {f} |", way.label()).unwrap();
    }

    writeln!(
        md,
        "\n{} on {} logical CPUs: timing {ROUNDS_AA} rounds × {} cells × ~{} ms, {:.1} s; accuracy \
         and seams {:.1} s. Ours in `Rgb888` (3 bytes a pixel), tiny-skia in premultiplied \
         RGBA8888 (4 bytes); every triangle opaque, its own colour, source-over.",
        std::env::consts::ARCH,
        std::thread::available_parallelism().map_or(1, |n| n.get()),
        cells.len(),
        SAMPLE_AA.as_millis(),
        timing.as_secs_f64(),
        accuracy_started.elapsed().as_secs_f64()
    )
    .unwrap();
    md
}
