//! Fill rate of every method in ONE process, interleaved, as a Markdown table for the README.
//!
//! Same workload as `benches/fill_rate.rs` (320×240 `Rgb565`; ≈16 px², ≈1,000 px² and
//! screen-filling triangle mixes). Each round times every (size class, method) cell once, in
//! rotating order, for about [`SAMPLE`] each; the table shows the median over [`ROUNDS`] rounds.
//! Ratios are the median of the per-round ratios (both methods timed in the same round), so slow
//! drift of a noisy machine cancels out. Pixel rates use each method's own pixel count.
//!
//! ```text
//! cargo run --release --example bench_report
//! ```
//!
//! Then the 3D bench frame (`examples/common/scene3d.rs`: 320×240 Rgb565, 16-bit z, back faces
//! culled, Gouraud, one directional light plus ambient) of each bench mesh, rendered by this crate
//! and by euc 0.5 (`examples/common/euc3d.rs`: the same mesh, camera, viewport, culling, depth test
//! and light, in `f32`), in interleaved rounds: frames/s medians and the median per-round ratio.
//!
//! Prints the tables and writes them to `target/bench-report.md`; `bench_report 3d` prints only
//! the 3D table.
//!
//! For profilers, `bench_report <method id> <size class id> [passes]` only draws that set
//! `passes` times (default 200), e.g.
//! `valgrind --tool=callgrind target/release/examples/bench_report ours_solid_draw_into_slice small_16px2 20`;
//! `bench_report 3d <knot|torus> [frames]` (this crate) and `bench_report 3d-euc <knot|torus>
//! [frames]` (euc) only render that frame `frames` times (default 200), inside `frames_3d`, so
//! that callgrind counts the frames alone:
//!
//! ```text
//! valgrind --tool=callgrind --toggle-collect='*frames_3d*' target/release/examples/bench_report 3d knot 20
//! ```
//!
//! prints `Collected : <instructions of 20 frames>`. `bench_report pictures <dir>` writes both
//! renderers' frames as PPM files and prints where their coverage differs.
//!
//! Then filled polygons against tiny-skia 0.12's aliased fill (`examples/common/polygon_peer.rs`):
//! pixel rates and pixels off the exact winding rule; `bench_report polygons` prints only that
//! part, `bench_report polygons <ours|tiny-skia> <set> <nonzero|evenodd> [passes]` fills one set
//! inside `polygon_passes` for callgrind. Then thin lines against embedded-graphics' `Line` and
//! `Polyline` (`examples/common/line_peer.rs`; `bench_report lines`, and `bench_report lines
//! <ours|eg> <set> [passes]` inside `line_passes`).
//!
//! Last, anti-aliased fills against tiny-skia 0.12 (`examples/common/aa_peer.rs`): pixel rates,
//! coverage error against the exact area and seam dips; `bench_report aa` prints only that part.
//! `bench_report aa <ours|tiny-skia|ours-aliased> <size class id> [passes]` only fills that set
//! `passes` times (default 200) inside `aa_passes`, for callgrind:
//!
//! ```text
//! valgrind --tool=callgrind --toggle-collect='*aa_passes*' target/release/examples/bench_report aa tiny-skia small_16px2 20
//! ```

use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::{Duration, Instant};

#[path = "../benches/fill_rate/workload.rs"]
mod workload;

#[allow(dead_code)]
#[path = "common/scene3d.rs"]
mod scene3d;

#[path = "common/euc3d.rs"]
mod euc3d;

#[path = "common/aa_peer.rs"]
mod aa_peer;

#[path = "common/polygon_peer.rs"]
mod polygon_peer;

#[path = "common/line_peer.rs"]
mod line_peer;

// The f64 reference (exact pixel areas for the anti-aliasing report), compiled in directly so
// that the example needs no cargo feature (it is `embedded_raster::reference` with `reference`).
#[allow(dead_code, unused_imports)]
#[path = "../src/reference/mod.rs"]
mod reference;

use embedded_raster::three_d::{DepthTarget, Mesh, ProjectedVertex, Vec3};
use scene3d::{Model, PIXELS, SIZE, TORUS_FACES, TORUS_VERTICES};
use workload::{draw_set, pixel_count, triangles, Method, SizeClass, Targets, Tri};

/// Rounds of interleaved measurements.
const ROUNDS: usize = 41;
/// Target duration of one timed sample.
const SAMPLE: Duration = Duration::from_millis(15);

struct Cell {
    class: usize,
    method: Method,
    pixels: u64,
    reps: u32,
    /// Mpx/s of each round.
    rates: Vec<f64>,
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Repetitions of a sample that take about `sample`, from `time(reps)` (after one warm-up pass).
fn reps_for(sample: Duration, mut time: impl FnMut(u32) -> Duration) -> u32 {
    time(1);
    let once = time(3) / 3;
    ((sample.as_secs_f64() / once.as_secs_f64().max(1e-9)).ceil() as u32).max(1)
}

/// Interleaved rounds: `measure` every cell once per round, starting `stride` cells further on
/// each round, so that slow drift of the machine spreads over all cells.
fn interleave<T>(cells: &mut [T], rounds: usize, stride: usize, mut measure: impl FnMut(&mut T)) {
    let n = cells.len();
    for round in 0..rounds {
        for i in 0..n {
            measure(&mut cells[(i + round * stride) % n]);
        }
    }
}

fn time(method: Method, tris: &[Tri], targets: &mut Targets, reps: u32) -> Duration {
    let start = Instant::now();
    for _ in 0..reps {
        draw_set(method, black_box(tris), targets);
        black_box(&mut *targets);
    }
    start.elapsed()
}

/// Profiling mode: draw one set with one method `passes` times.
fn profile(method: &str, class: &str, passes: u32) {
    let method = Method::ALL
        .into_iter()
        .find(|m| m.id() == method)
        .unwrap_or_else(|| panic!("methods: {:?}", Method::ALL.map(Method::id)));
    let class = SizeClass::ALL
        .into_iter()
        .find(|c| c.id() == class)
        .unwrap_or_else(|| panic!("size classes: {:?}", SizeClass::ALL.map(SizeClass::id)));
    let tris = triangles(class);
    let mut targets = Targets::new();
    let elapsed = time(method, &tris, &mut targets, passes);
    let pixels = pixel_count(method, &tris) * u64::from(passes);
    println!(
        "{} on {}: {passes} passes, {pixels} px, {:.1} Mpx/s",
        method.id(),
        class.id(),
        pixels as f64 / elapsed.as_secs_f64() / 1e6
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args
        .iter()
        .map(String::as_str)
        .collect::<Vec<_>>()
        .as_slice()
    {
        ["3d"] => {
            let md = report_3d();
            print!("{md}");
            return;
        }
        [mode @ ("3d" | "3d-euc"), mesh, rest @ ..] => {
            let renderer = if *mode == "3d" {
                Renderer::Ours
            } else {
                Renderer::Euc
            };
            let frames = rest.first().map_or(200, |n| n.parse().expect("frames"));
            return profile_3d(renderer, parse_model(mesh), frames);
        }
        ["pictures", dir] => return pictures(dir),
        ["aa"] => {
            print!("{}", aa_peer::report_aa());
            return;
        }
        ["polygons"] => {
            print!("{}", polygon_peer::report_polygons());
            return;
        }
        ["lines"] => {
            print!("{}", line_peer::report_lines());
            return;
        }
        ["lines", who, set, rest @ ..] => {
            let passes = rest.first().map_or(200, |p| p.parse().expect("passes"));
            return line_peer::profile_lines(who, set, passes);
        }
        ["polygons", who, set, rule, rest @ ..] => {
            let passes = rest.first().map_or(200, |p| p.parse().expect("passes"));
            return polygon_peer::profile_polygons(who, set, rule, passes);
        }
        ["aa", method, class, rest @ ..] => {
            let passes = rest.first().map_or(200, |p| p.parse().expect("passes"));
            return aa_peer::profile_aa(method, class, passes);
        }
        _ => {}
    }
    if let [method, class, rest @ ..] = args.as_slice() {
        let passes = rest.first().map_or(200, |p| p.parse().expect("passes"));
        return profile(method, class, passes);
    }
    let started = Instant::now();
    let sets: Vec<Vec<Tri>> = SizeClass::ALL.iter().map(|&c| triangles(c)).collect();
    let mut targets = Targets::new();
    // The block traversal is only a fair comparison if it draws exactly our pixels.
    for tris in &sets {
        let render = |method: Method, targets: &mut Targets| {
            targets.slice.fill(Rgb565::BLACK);
            draw_set(method, tris, targets);
            targets.slice.clone()
        };
        assert!(
            render(Method::Block8Solid, &mut targets)
                == render(Method::OursSolidInto, &mut targets),
            "8×8 block traversal and spans cover different pixels"
        );
    }

    // Pixel counts (outside any timing) and a repetition count per cell for ~SAMPLE per sample.
    let mut cells = Vec::new();
    for (class, tris) in sets.iter().enumerate() {
        for method in Method::ALL {
            let pixels = pixel_count(method, tris);
            cells.push(Cell {
                class,
                method,
                pixels,
                reps: reps_for(SAMPLE, |reps| time(method, tris, &mut targets, reps)),
                rates: Vec::with_capacity(ROUNDS),
            });
        }
    }

    interleave(&mut cells, ROUNDS, 7, |cell| {
        let elapsed = time(cell.method, &sets[cell.class], &mut targets, cell.reps);
        let mpx = (cell.pixels * u64::from(cell.reps)) as f64 / elapsed.as_secs_f64() / 1e6;
        cell.rates.push(mpx);
    });

    let find = |class: usize, method: Method| {
        cells
            .iter()
            .find(|c| c.class == class && c.method == method)
            .expect("cell")
    };
    let rate = |class: usize, method: Method| median(&mut find(class, method).rates.clone());
    let ratio = |class: usize, method: Method, base: Method| {
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
        md.push('\n');
        md.push_str("|---|");
        for _ in classes {
            md.push_str("---:|");
        }
        md.push('\n');
    };

    writeln!(
        md,
        "### Fill rate, 320×240 Rgb565 (Mpx/s, median of {ROUNDS} interleaved rounds)\n"
    )
    .unwrap();
    header(&mut md, "method");
    for method in Method::ALL {
        write!(md, "| {} |", method.label()).unwrap();
        for k in 0..classes.len() {
            write!(md, " {:.0} |", rate(k, method)).unwrap();
        }
        md.push('\n');
    }

    for (base, name) in [
        (
            Method::EgTriangleSlice,
            "e-g `Triangle` on SliceFramebuffer",
        ),
        (Method::EgTriangleEgFb, "e-g `Triangle` on e-g Framebuffer"),
    ] {
        writeln!(
            md,
            "\n### Speed-up vs {name}: pixel rate (time for the same triangles)\n"
        )
        .unwrap();
        header(&mut md, "method");
        for method in Method::ALL {
            if method == base {
                continue;
            }
            write!(md, "| {} |", method.label()).unwrap();
            for k in 0..classes.len() {
                let r = ratio(k, method, base);
                let same_work = r * find(k, base).pixels as f64 / find(k, method).pixels as f64;
                write!(md, " {r:.1}× ({same_work:.1}×) |").unwrap();
            }
            md.push('\n');
        }
    }

    writeln!(
        md,
        "\n### Workload (pixels written per pass over the set)\n"
    )
    .unwrap();
    write!(md, "| |").unwrap();
    for (k, c) in classes.iter().enumerate() {
        write!(md, " {} ({} triangles) |", c.label(), sets[k].len()).unwrap();
    }
    md.push_str("\n|---|");
    for _ in classes {
        md.push_str("---:|");
    }
    md.push('\n');
    for (name, method) in [
        ("ours (exact top-left rule)", Method::OursSolidInto),
        ("e-g `Triangle` (integer vertices)", Method::EgTriangleSlice),
        ("naive f32", Method::NaiveFloat),
        ("8×8 blocks (exact edges)", Method::Block8Solid),
    ] {
        write!(md, "| {name} |").unwrap();
        for k in 0..classes.len() {
            write!(md, " {} |", find(k, method).pixels).unwrap();
        }
        md.push('\n');
    }

    writeln!(
        md,
        "\n### Goals (pixel-rate ratio; same-work time ratio in brackets)\n"
    )
    .unwrap();
    let base = Method::EgTriangleSlice;
    let same_work = |k: usize, method: Method| {
        ratio(k, method, base) * find(k, base).pixels as f64 / find(k, method).pixels as f64
    };
    let mut check = |what: String, k: usize, method: Method, goal: f64| {
        let got = ratio(k, method, base);
        let verdict = if got >= goal { "met" } else { "MISSED" };
        writeln!(
            md,
            "- {what}, {}: {got:.1}× ({:.1}×), goal ≥ {goal}× — {verdict}",
            classes[k].label(),
            same_work(k, method)
        )
        .unwrap();
    };
    let (small, screen) = (0, 2);
    for (method, name) in [
        (Method::OursSolidInto, "`draw_into`"),
        (Method::OursSolidDraw, "`Drawable::draw`"),
    ] {
        let what = format!("solid {name} vs e-g `Triangle` (both on SliceFramebuffer)");
        check(what.clone(), screen, method, 10.0);
        check(what, small, method, 3.0);
    }
    for k in 0..classes.len() {
        let what = "Gouraud `draw_into` vs e-g solid `Triangle` on SliceFramebuffer".to_string();
        check(what, k, Method::OursGouraudInto, 5.0);
    }

    writeln!(
        md,
        "\n{} on {} logical CPUs, {ROUNDS} rounds × {} cells × ~{} ms, {:.1} s in all. Rates use \
         each method's own pixel count; e-g's integer-vertex triangles cover slightly different \
         pixels.",
        std::env::consts::ARCH,
        std::thread::available_parallelism().map_or(1, |n| n.get()),
        cells.len(),
        SAMPLE.as_millis(),
        started.elapsed().as_secs_f64()
    )
    .unwrap();

    md.push('\n');
    md.push_str(&report_3d());
    md.push('\n');
    md.push_str(&polygon_peer::report_polygons());
    md.push('\n');
    md.push_str(&line_peer::report_lines());
    md.push('\n');
    md.push_str(&aa_peer::report_aa());

    print!("{md}");
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/target/bench-report.md");
    match std::fs::write(path, &md) {
        Ok(()) => println!("\nwrote {path}"),
        Err(e) => eprintln!("could not write {path}: {e}"),
    }
}

// ---- 3D frame ---------------------------------------------------------------------------------

/// Rounds of interleaved 3D frame measurements.
const ROUNDS_3D: usize = 31;
/// Target duration of one timed 3D sample.
const SAMPLE_3D: Duration = Duration::from_millis(40);

/// Who renders the 3D frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Renderer {
    /// This crate's fixed-point pipeline (`scene3d::render`).
    Ours,
    /// Euc 0.5 (`euc3d`).
    Euc,
}

impl Renderer {
    const ALL: [Renderer; 2] = [Renderer::Ours, Renderer::Euc];
}

fn parse_model(name: &str) -> Model {
    Model::ALL
        .into_iter()
        .find(|m| m.name() == name)
        .unwrap_or_else(|| panic!("meshes: {:?}", Model::ALL.map(Model::name)))
}

/// The bench mesh of `model` (the torus generated once, kept for the process).
fn mesh(model: Model) -> &'static Mesh<'static> {
    static TORUS: std::sync::OnceLock<Mesh<'static>> = std::sync::OnceLock::new();
    match model {
        Model::Spot => &scene3d::SPOT,
        Model::Knot => &scene3d::KNOT,
        Model::Torus => TORUS.get_or_init(|| {
            scene3d::torus(
                Box::leak(Box::new([Vec3::ZERO; TORUS_VERTICES])),
                Box::leak(Box::new([Vec3::ZERO; TORUS_VERTICES])),
                Box::leak(Box::new([[0; 3]; TORUS_FACES])),
            )
        }),
    }
}

/// Both renderers' buffers and euc's scenes.
struct Frames3d {
    colors: Vec<embedded_graphics::pixelcolor::Rgb565>,
    depth: Vec<u16>,
    euc_scenes: Vec<(Model, euc3d::Scene)>,
    euc: euc3d::Frame,
    /// The vertex scratch of our pipeline (one entry per vertex of the larger mesh).
    scratch: Vec<ProjectedVertex>,
}

impl Frames3d {
    /// Buffers for both renderers; euc's `f32` copies of the meshes of `models`.
    fn new(models: &[Model]) -> Self {
        Frames3d {
            colors: vec![Rgb565::BLACK; PIXELS],
            depth: vec![0; PIXELS],
            euc_scenes: models
                .iter()
                .map(|&m| (m, euc3d::Scene::new(m, mesh(m))))
                .collect(),
            euc: euc3d::Frame::new(),
            scratch: vec![ProjectedVertex::EMPTY; scene3d::MAX_VERTICES],
        }
    }

    /// One frame of `model` by `renderer`.
    fn render(&mut self, renderer: Renderer, model: Model) {
        match renderer {
            Renderer::Ours => {
                let mut target =
                    DepthTarget::new(&mut self.colors, &mut self.depth, SIZE.0, SIZE.1)
                        .expect("buffers of the frame's size");
                let scratch = Some(&mut self.scratch[..]);
                black_box(scene3d::render(
                    model,
                    black_box(mesh(model)),
                    &mut target,
                    scratch,
                ));
            }
            Renderer::Euc => {
                let (_, scene) = self
                    .euc_scenes
                    .iter()
                    .find(|(m, _)| *m == model)
                    .expect("an euc scene for the mesh");
                scene.render(&mut self.euc);
                black_box(&mut self.euc);
            }
        }
    }

    /// Which pixels `renderer`'s last frame drew.
    fn covered(&self, renderer: Renderer) -> Vec<bool> {
        match renderer {
            Renderer::Ours => self
                .depth
                .iter()
                .map(|&d| d != embedded_raster::three_d::DEPTH_CLEAR)
                .collect(),
            Renderer::Euc => self.euc.covered().collect(),
        }
    }

    /// `renderer`'s last frame as a binary PPM.
    fn ppm(&self, renderer: Renderer) -> Vec<u8> {
        let mut ppm = format!("P6 {} {} 255\n", SIZE.0, SIZE.1).into_bytes();
        let rgb = |c: Rgb565| [c.r() << 3, c.g() << 2, c.b() << 3];
        match renderer {
            Renderer::Ours => self.colors.iter().for_each(|&c| ppm.extend(rgb(c))),
            Renderer::Euc => self.euc.pixels().for_each(|c| ppm.extend(rgb(c))),
        }
        ppm
    }
}

/// `frames` frames of `model` by `renderer`: the function callgrind's `--toggle-collect` names.
#[inline(never)]
fn frames_3d(frames3d: &mut Frames3d, renderer: Renderer, model: Model, frames: u32) {
    for _ in 0..frames {
        frames3d.render(renderer, model);
    }
}

/// Profiling mode: `frames` frames of one mesh by one renderer.
fn profile_3d(renderer: Renderer, model: Model, frames: u32) {
    let euc_models: &[Model] = if renderer == Renderer::Euc {
        &[model]
    } else {
        &[]
    };
    let mut frames3d = Frames3d::new(euc_models);
    let start = Instant::now();
    frames_3d(&mut frames3d, renderer, model, frames);
    let elapsed = start.elapsed();
    let covered = frames3d.covered(renderer).iter().filter(|&&c| c).count();
    println!(
        "{renderer:?} {}: {frames} frames, {covered} px covered, {:.0} frames/s",
        model.name(),
        f64::from(frames) / elapsed.as_secs_f64()
    );
}

/// Writes `<dir>/<mesh>-ours.ppm` and `<dir>/<mesh>-euc.ppm`; prints where coverage differs.
fn pictures(dir: &str) {
    let mut frames3d = Frames3d::new(&Model::ALL);
    for model in Model::ALL {
        let mut covered = Vec::new();
        for renderer in Renderer::ALL {
            frames3d.render(renderer, model);
            covered.push(frames3d.covered(renderer));
            let name = format!("{}-{renderer:?}", model.name()).to_lowercase();
            let path = format!("{dir}/{name}.ppm");
            std::fs::write(&path, frames3d.ppm(renderer)).expect("write the picture");
            println!("wrote {path}");
        }
        let count = |v: &[bool]| v.iter().filter(|&&c| c).count();
        let differ = covered[0].iter().zip(&covered[1]).filter(|(a, b)| a != b);
        println!(
            "{}: ours covers {} px, euc {} px, {} px covered by only one",
            model.name(),
            count(&covered[0]),
            count(&covered[1]),
            differ.count()
        );
    }
}

/// The 3D table: frames/s of both renderers on both meshes, interleaved rounds.
fn report_3d() -> String {
    let started = Instant::now();
    let mut frames3d = Frames3d::new(&Model::ALL);
    struct Cell3d {
        model: Model,
        renderer: Renderer,
        covered: usize,
        reps: u32,
        /// Frames/s of each round.
        rates: Vec<f64>,
    }
    let time = |frames3d: &mut Frames3d, renderer: Renderer, model: Model, reps: u32| {
        let start = Instant::now();
        frames_3d(frames3d, renderer, model, reps);
        start.elapsed()
    };
    let mut cells = Vec::new();
    for model in Model::ALL {
        for renderer in Renderer::ALL {
            let reps = reps_for(SAMPLE_3D, |reps| time(&mut frames3d, renderer, model, reps));
            cells.push(Cell3d {
                model,
                renderer,
                covered: frames3d.covered(renderer).iter().filter(|&&c| c).count(),
                reps,
                rates: Vec::with_capacity(ROUNDS_3D),
            });
        }
    }
    interleave(&mut cells, ROUNDS_3D, 1, |cell| {
        let elapsed = time(&mut frames3d, cell.renderer, cell.model, cell.reps);
        cell.rates
            .push(f64::from(cell.reps) / elapsed.as_secs_f64());
    });

    let find = |model: Model, renderer: Renderer| {
        cells
            .iter()
            .find(|c| c.model == model && c.renderer == renderer)
            .expect("cell")
    };
    let mut md = String::new();
    writeln!(
        md,
        "### 3D frame, 320×240 Rgb565, z-buffer, culled, Gouraud (frames/s, median of \
         {ROUNDS_3D} interleaved rounds)\n"
    )
    .unwrap();
    md.push_str(
        "| mesh | faces | ours frames/s | euc frames/s | ours / euc | covered px, ours / euc |\n",
    );
    md.push_str("|---|---:|---:|---:|---:|---:|\n");
    for model in Model::ALL {
        let (ours, euc) = (find(model, Renderer::Ours), find(model, Renderer::Euc));
        let mut ratios: Vec<f64> = ours
            .rates
            .iter()
            .zip(&euc.rates)
            .map(|(a, b)| a / b)
            .collect();
        writeln!(
            md,
            "| {} | {} | {:.0} | {:.0} | {:.2}× | {} / {} |",
            model.name(),
            mesh(model).indices.len(),
            median(&mut ours.rates.clone()),
            median(&mut euc.rates.clone()),
            median(&mut ratios),
            ours.covered,
            euc.covered
        )
        .unwrap();
    }
    writeln!(
        md,
        "\n{ROUNDS_3D} rounds × {} cells × ~{} ms, {:.1} s. Ours: fixed point, 16-bit z; euc 0.5: \
         `f32`, `f32` z, its own coverage rule.",
        cells.len(),
        SAMPLE_3D.as_millis(),
        started.elapsed().as_secs_f64()
    )
    .unwrap();
    md
}
