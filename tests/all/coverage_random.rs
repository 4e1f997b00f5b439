//! Random triangles against the independent f64 reference (`embedded_raster::reference`).
//!
//! For every triangle: the core's spans (`raster::for_each_span`) must cover exactly the
//! reference's pixel set; `SolidTriangle` and `GouraudTriangle` (through both `Drawable::draw` and
//! `draw_into`) must write exactly those pixels; every Gouraud channel must be within 1 LSB of the
//! reference's exact barycentric interpolation. Triangles range from sub-pixel to the full `i32`
//! raw range, with slivers, (near-)collinear, snapped, axis-aligned and extreme-valued vertices.
//!
//! Run with `cargo test --release --features reference --test all coverage_random:: -- --nocapture`
//! to see the statistics.

use std::fmt::Debug;

use embedded_graphics::pixelcolor::{BinaryColor, Gray8, GrayColor, Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::{
    raster, reference, Coord, GouraudColor, GouraudTriangle, SliceFramebuffer, SolidTriangle,
    Vertex,
};

const W: i32 = 64;
const H: i32 = 48;
const N: usize = (W * H) as usize;
/// Allowed deviation from the exact interpolated channel value, in LSB.
const TOLERANCE: f64 = 1.0 + 1e-9;

use crate::rng;
use rng::Rng;

use crate::raw_points;
use raw_points::{sliver, Screen, MAX, MIN};

const RAW: Screen = Screen::new(W as i64, H as i64);

fn clamp(v: (i64, i64)) -> (i32, i32) {
    (v.0.clamp(MIN, MAX) as i32, v.1.clamp(MIN, MAX) as i32)
}

fn extreme(rng: &mut Rng) -> i64 {
    const VALUES: [i64; 10] = [
        MIN,
        MAX,
        MIN + 1,
        MAX - 1,
        0,
        -1,
        128,
        MIN + 128,
        MAX - 127,
        -128,
    ];
    if rng.chance(3) {
        rng.any_scale()
    } else {
        VALUES[rng.below(VALUES.len() as u64) as usize]
    }
}

const KINDS: usize = 13;

/// A random triangle of the given kind, raw sub-pixel coordinates.
fn triangle(rng: &mut Rng, kind: usize) -> [(i32, i32); 3] {
    let v: [(i64, i64); 3] = match kind {
        // Sub-pixel.
        0 => RAW.cluster(rng, 2, (1, 300)),
        // A few pixels.
        1 => RAW.cluster(rng, 4, (256, 256 * 12)),
        // Screen-sized, partly off-screen.
        2 => [(); 3].map(|_| RAW.point(rng, 32)),
        // Ten times the screen.
        3 => [(); 3].map(|_| RAW.point(rng, i64::from(W) * 10)),
        // Any magnitude up to the full raw range.
        4 => [(); 3].map(|_| (rng.any_scale(), rng.any_scale())),
        // One vertex on screen, the others far away.
        5 => {
            let a = RAW.point(rng, 1);
            let mut far = || {
                if rng.chance(2) {
                    (extreme(rng), extreme(rng))
                } else {
                    (rng.any_scale(), rng.any_scale())
                }
            };
            [a, far(), far()]
        }
        // Slivers: c near the line through a and b.
        6 => {
            let a = RAW.point(rng, 8);
            sliver(rng, a, 28)
        }
        // Exactly collinear, or one unit off: a + s·dir, a + t·dir.
        7 => {
            let a = if rng.chance(2) {
                RAW.point(rng, 8)
            } else {
                RAW.snapped_point(rng, 8)
            };
            let m = 1 << rng.below(10);
            let dir = (rng.range(-m, m), rng.range(-m, m));
            let lim = 1 << rng.below(22);
            let (s, t) = (rng.range(-lim, lim), rng.range(-lim, lim));
            let mut c = (a.0 + t * dir.0, a.1 + t * dir.1);
            if rng.chance(2) {
                c.0 += rng.range(-1, 1);
                c.1 += rng.range(-1, 1);
            }
            [a, (a.0 + s * dir.0, a.1 + s * dir.1), c]
        }
        // Snapped to pixel corners/centres: edges through centres.
        8 => {
            let margin = if rng.chance(4) { 40 } else { 4 };
            [(); 3].map(|_| RAW.snapped_point(rng, margin))
        }
        // Axis-aligned edges.
        9 => {
            let (p, q) = if rng.chance(2) {
                (RAW.snapped_point(rng, 6), RAW.snapped_point(rng, 6))
            } else {
                (RAW.point(rng, 6), RAW.point(rng, 6))
            };
            match rng.below(3) {
                0 => [p, (q.0, p.1), (p.0, q.1)],
                1 => [p, (q.0, p.1), q],
                _ => [p, (p.0, q.1), RAW.point(rng, 6)],
            }
        }
        // Extreme values of the raw range.
        10 => [(); 3].map(|_| {
            if rng.chance(4) {
                RAW.snapped_point(rng, 2)
            } else {
                (extreme(rng), extreme(rng))
            }
        }),
        // Repeated vertices.
        11 => {
            let a = RAW.point(rng, 4);
            let b = if rng.chance(2) {
                RAW.point(rng, 4)
            } else {
                (extreme(rng), extreme(rng))
            };
            if rng.chance(4) {
                [a, a, a]
            } else {
                [a, b, a]
            }
        }
        // Long thin slivers across the screen with snapped ends, one raw unit wide.
        _ => {
            let a = RAW.snapped_point(rng, 20);
            let b = if rng.chance(3) {
                (extreme(rng), extreme(rng))
            } else {
                RAW.snapped_point(rng, 20)
            };
            let c = (b.0 + rng.range(-2, 2), b.1 + rng.range(-2, 2));
            [a, b, c]
        }
    };
    // Random winding and vertex order.
    let mut v = v.map(clamp);
    let r = rng.below(3) as usize;
    v.rotate_left(r);
    if rng.chance(2) {
        v.swap(0, 1);
    }
    v
}

/// The colour formats under test, with channel accessors independent of the core.
trait TestColor: GouraudColor + Debug {
    const NAME: &'static str;
    /// Two distinct background colours.
    const A: Self;
    const B: Self;
    /// Number of meaningful channels.
    const USED: usize;
    fn random(rng: &mut Rng) -> Self;
    fn chans(self) -> [f64; 3];
}

/// A channel value in `0..=max`, biased towards the extremes.
fn channel(rng: &mut Rng, max: u8) -> u8 {
    match rng.below(8) {
        0 => 0,
        1 => max,
        _ => (rng.below(u64::from(max) + 1)) as u8,
    }
}

impl TestColor for Rgb888 {
    const NAME: &'static str = "Rgb888";
    const A: Self = Rgb888::BLACK;
    const B: Self = Rgb888::WHITE;
    const USED: usize = 3;
    fn random(rng: &mut Rng) -> Self {
        Rgb888::new(channel(rng, 255), channel(rng, 255), channel(rng, 255))
    }
    fn chans(self) -> [f64; 3] {
        [self.r(), self.g(), self.b()].map(f64::from)
    }
}

impl TestColor for Rgb565 {
    const NAME: &'static str = "Rgb565";
    const A: Self = Rgb565::BLACK;
    const B: Self = Rgb565::WHITE;
    const USED: usize = 3;
    fn random(rng: &mut Rng) -> Self {
        Rgb565::new(channel(rng, 31), channel(rng, 63), channel(rng, 31))
    }
    fn chans(self) -> [f64; 3] {
        [self.r(), self.g(), self.b()].map(f64::from)
    }
}

impl TestColor for Gray8 {
    const NAME: &'static str = "Gray8";
    const A: Self = Gray8::BLACK;
    const B: Self = Gray8::WHITE;
    const USED: usize = 1;
    fn random(rng: &mut Rng) -> Self {
        Gray8::new(channel(rng, 255))
    }
    fn chans(self) -> [f64; 3] {
        [f64::from(self.luma()), 0.0, 0.0]
    }
}

impl TestColor for BinaryColor {
    const NAME: &'static str = "BinaryColor";
    const A: Self = BinaryColor::Off;
    const B: Self = BinaryColor::On;
    const USED: usize = 1;
    fn random(rng: &mut Rng) -> Self {
        BinaryColor::from(rng.chance(2))
    }
    fn chans(self) -> [f64; 3] {
        [f64::from(u8::from(self.is_on())), 0.0, 0.0]
    }
}

#[derive(Default)]
struct Stats {
    triangles: usize,
    degenerate: usize,
    covered_pixels: usize,
    checked_channels: usize,
    /// Max |out − exact| per colour format (Rgb888, Rgb565, Gray8, BinaryColor).
    max_err: [f64; 4],
}

fn coords(v: [(i32, i32); 3]) -> [(Coord, Coord); 3] {
    v.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y)))
}

fn target() -> Rectangle {
    Rectangle::new(Point::zero(), Size::new(W as u32, H as u32))
}

/// The reference's covered set over the target.
fn reference_set(v: [(i32, i32); 3]) -> Vec<bool> {
    let mut set = vec![false; N];
    reference::for_each_covered(v, 0, 0, W, H, |x, y| {
        assert!((0..W).contains(&x) && (0..H).contains(&y));
        let i = (y * W + x) as usize;
        assert!(!set[i], "reference visited ({x}, {y}) twice");
        set[i] = true;
    });
    set
}

fn fail(v: [(i32, i32); 3], what: &str, x: i32, y: i32, want: bool, got: impl Debug) -> ! {
    panic!(
        "{what}: triangle (raw sub-pixel) {v:?}, pixel ({x}, {y}): reference covered = {want}, \
         got {got:?}"
    );
}

fn check_spans(v: [(i32, i32); 3], want: &[bool]) {
    let mut got = vec![0u8; N];
    raster::for_each_span(coords(v), target(), |y, x0, x1| {
        assert!(
            (0..H).contains(&y) && 0 <= x0 && x0 <= x1 && x1 <= W,
            "span outside the clip: y {y}, x {x0}..{x1}, triangle {v:?}"
        );
        for x in x0..x1 {
            got[(y * W + x) as usize] += 1;
        }
    });
    for (i, (&w, &g)) in want.iter().zip(&got).enumerate() {
        if u8::from(w) != g {
            let (x, y) = (i as i32 % W, i as i32 / W);
            fail(v, "for_each_span", x, y, w, format_args!("{g} span hits"));
        }
    }
}

fn check_draws<C: TestColor>(v: [(i32, i32); 3], want: &[bool], rng: &mut Rng, stats: &mut Stats) {
    let colors: [C; 3] = if rng.chance(8) {
        [C::random(rng); 3]
    } else {
        [(); 3].map(|_| C::random(rng))
    };
    let c = coords(v);
    let gouraud = GouraudTriangle::new([0, 1, 2].map(|k| Vertex::new(c[k].0, c[k].1, colors[k])));
    let solid = SolidTriangle::new(c, C::B);

    // Each method draws once over background A and once over B: a pixel was written iff the two
    // results agree, and then that is the written colour.
    let mut bufs: [Vec<C>; 4] = [vec![C::A; N], vec![C::B; N], vec![C::A; N], vec![C::B; N]];
    for (k, buf) in bufs.iter_mut().enumerate() {
        let mut fb = SliceFramebuffer::new(buf, W as u32, H as u32).unwrap();
        if k < 2 {
            gouraud.draw(&mut fb).unwrap();
        } else {
            gouraud.draw_into(&mut fb);
        }
    }
    let mut solids: [Vec<C>; 2] = [vec![C::A; N], vec![C::A; N]];
    {
        let mut fb = SliceFramebuffer::new(&mut solids[0], W as u32, H as u32).unwrap();
        solid.draw(&mut fb).unwrap();
        let mut fb = SliceFramebuffer::new(&mut solids[1], W as u32, H as u32).unwrap();
        solid.draw_into(&mut fb);
    }

    let channels = colors.map(C::chans);
    let slot = match C::NAME {
        "Rgb888" => 0,
        "Rgb565" => 1,
        "Gray8" => 2,
        _ => 3,
    };
    for i in 0..N {
        let (x, y) = (i as i32 % W, i as i32 / W);
        for (m, s) in solids.iter().enumerate() {
            let written = s[i] == C::B;
            if written != want[i] || !(written || s[i] == C::A) {
                let name = ["SolidTriangle::draw", "SolidTriangle::draw_into"][m];
                fail(v, name, x, y, want[i], s[i]);
            }
        }
        let exact = want[i].then(|| {
            reference::interpolate(v, channels, x, y)
                .expect("a covered pixel implies a non-degenerate triangle")
        });
        for m in 0..2 {
            let (a, b) = (bufs[2 * m][i], bufs[2 * m + 1][i]);
            let name = ["GouraudTriangle::draw", "GouraudTriangle::draw_into"][m];
            let written = a == b;
            if written != want[i] || !(written || (a == C::A && b == C::B)) {
                fail(v, name, x, y, want[i], (C::NAME, a, b));
            }
            if let Some(exact) = exact {
                let got = a.chans();
                for k in 0..C::USED {
                    let err = (got[k] - exact[k]).abs();
                    stats.max_err[slot] = stats.max_err[slot].max(err);
                    stats.checked_channels += 1;
                    assert!(
                        err <= TOLERANCE,
                        "{name}: triangle {v:?}, colours {colors:?}, pixel ({x}, {y}): channel \
                         {k} = {}, exact {} (error {err} LSB > 1)",
                        got[k],
                        exact[k]
                    );
                }
            }
        }
    }
}

/// Cross-checks the reference against itself: `covers` pixel by pixel equals `for_each_covered`.
fn check_reference_consistency(v: [(i32, i32); 3], want: &[bool]) {
    for (i, &w) in want.iter().enumerate() {
        let (x, y) = (i as i32 % W, i as i32 / W);
        assert_eq!(reference::covers(v, x, y), w, "{v:?} ({x}, {y})");
    }
}

fn run(seed: u64, count: usize) -> Stats {
    let mut rng = Rng(seed);
    let mut stats = Stats::default();
    for n in 0..count {
        let v = triangle(&mut rng, n % KINDS);
        let want = reference_set(v);
        if reference::barycentric(v, 0, 0).is_none() {
            stats.degenerate += 1;
            assert!(!want.contains(&true));
        }
        if n % 16 == 0 {
            check_reference_consistency(v, &want);
        }
        check_spans(v, &want);
        match n % 4 {
            0 => check_draws::<Rgb888>(v, &want, &mut rng, &mut stats),
            1 => check_draws::<Rgb565>(v, &want, &mut rng, &mut stats),
            2 => check_draws::<Gray8>(v, &want, &mut rng, &mut stats),
            _ => check_draws::<BinaryColor>(v, &want, &mut rng, &mut stats),
        }
        stats.triangles += 1;
        stats.covered_pixels += want.iter().filter(|&&w| w).count();
    }
    println!(
        "seed {seed:#x}: {} triangles ({} degenerate), {} covered pixels, {} channel values; \
         max |error| in LSB: Rgb888 {:.4}, Rgb565 {:.4}, Gray8 {:.4}, BinaryColor {:.4}",
        stats.triangles,
        stats.degenerate,
        stats.covered_pixels,
        stats.checked_channels,
        stats.max_err[0],
        stats.max_err[1],
        stats.max_err[2],
        stats.max_err[3]
    );
    stats
}

// 4 × 26,000 = 104,000 triangles, split so the test harness can run them in parallel.

#[test]
fn random_triangles_seed_a() {
    run(0x0123_4567_89ab_cdef, 26_000);
}

#[test]
fn random_triangles_seed_b() {
    run(0xfedc_ba98_7654_3210, 26_000);
}

#[test]
fn random_triangles_seed_c() {
    run(0x5eed_0000_0000_0003, 26_000);
}

#[test]
fn random_triangles_seed_d() {
    run(0x5eed_0000_0000_0004, 26_000);
}

/// The generator really produces every kind of case it claims (sanity check of the test itself).
#[test]
fn generator_covers_all_kinds() {
    let mut rng = Rng(7);
    let mut degenerate = 0;
    let mut full_range = 0;
    let mut tiny = 0;
    for n in 0..20_000 {
        let v = triangle(&mut rng, n % KINDS);
        if reference::barycentric(v, 0, 0).is_none() {
            degenerate += 1;
        }
        if v.iter().any(|p| p.0 == i32::MIN || p.1 == i32::MAX) {
            full_range += 1;
        }
        let xs = v.map(|p| i64::from(p.0));
        if xs.iter().max().unwrap() - xs.iter().min().unwrap() < 256 {
            tiny += 1;
        }
    }
    assert!(degenerate > 500, "{degenerate}");
    assert!(full_range > 500, "{full_range}");
    assert!(tiny > 1000, "{tiny}");
}
