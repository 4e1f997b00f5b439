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
//! Prints the table and writes it to `target/bench-report.md`.
//!
//! For profilers, `bench_report <method id> <size class id> [passes]` only draws that set
//! `passes` times (default 200), e.g.
//! `valgrind --tool=callgrind target/release/examples/bench_report ours_solid_draw_into_slice small_16px2 20`.

use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::{Duration, Instant};

#[path = "../benches/fill_rate/workload.rs"]
mod workload;

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
            time(method, tris, &mut targets, 1); // warm-up
            let once = time(method, tris, &mut targets, 3) / 3;
            let reps = (SAMPLE.as_secs_f64() / once.as_secs_f64().max(1e-9)).ceil() as u32;
            cells.push(Cell {
                class,
                method,
                pixels,
                reps: reps.max(1),
                rates: Vec::with_capacity(ROUNDS),
            });
        }
    }

    // Interleaved rounds: every cell once per round, starting at a different cell each round.
    for round in 0..ROUNDS {
        let n = cells.len();
        for i in 0..n {
            let cell = &mut cells[(i + round * 7) % n];
            let elapsed = time(cell.method, &sets[cell.class], &mut targets, cell.reps);
            let mpx = (cell.pixels * u64::from(cell.reps)) as f64 / elapsed.as_secs_f64() / 1e6;
            cell.rates.push(mpx);
        }
    }

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

    print!("{md}");
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/target/bench-report.md");
    match std::fs::write(path, &md) {
        Ok(()) => println!("\nwrote {path}"),
        Err(e) => eprintln!("could not write {path}: {e}"),
    }
}
