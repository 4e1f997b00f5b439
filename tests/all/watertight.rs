//! Watertightness: meshes of triangles sharing edges must draw every pixel of their union
//! exactly once and nothing outside it.
//!
//! Meshes: regular and non-uniform grids with either or random diagonals, fans of many thin
//! triangles around centres on pixel centres, corners or sub-pixel offsets, jittered grids,
//! meshes extending past the screen and up to the ends of the raw `i32` range; windings mixed.
//! A counting `DrawTarget` records how often each pixel is drawn by `SolidTriangle`,
//! `GouraudTriangle` and `raster::for_each_span`; the independent reference
//! (`reference::for_each_covered`) must count each pixel of the union exactly once (and 0
//! elsewhere), and each core count must equal the reference count.

use std::convert::Infallible;
use std::f64::consts::TAU;

use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::{raster, reference, Coord, GouraudTriangle, SolidTriangle, Vertex};

const W: u32 = 64;
const H: u32 = 48;
const MIN: i64 = i32::MIN as i64;
const MAX: i64 = i32::MAX as i64;

type Tri = [(i32, i32); 3];

use crate::rng;
use rng::Rng;

/// A `DrawTarget` that counts how often each pixel is drawn and panics on any pixel outside its
/// bounding box.
struct Counter {
    area: Rectangle,
    counts: Vec<u32>,
}

impl Counter {
    fn new(area: Rectangle) -> Self {
        let n = (area.size.width * area.size.height) as usize;
        Counter {
            area,
            counts: vec![0; n],
        }
    }
}

impl Dimensions for Counter {
    fn bounding_box(&self) -> Rectangle {
        self.area
    }
}

impl DrawTarget for Counter {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        for Pixel(p, _) in pixels {
            assert!(
                self.area.contains(p),
                "pixel {p:?} drawn outside {:?}",
                self.area
            );
            let d = p - self.area.top_left;
            self.counts[(d.y as u32 * self.area.size.width + d.x as u32) as usize] += 1;
        }
        Ok(())
    }
}

struct Mesh {
    name: String,
    triangles: Vec<Tri>,
    /// Known by construction to cover the whole origin-based `W × H` screen.
    covers_screen: bool,
}

/// Exact orientation of a raw triangle: the sign of twice its signed area.
fn orientation(t: [(i64, i64); 3]) -> i32 {
    let [a, b, c] = t.map(|(x, y)| (i128::from(x), i128::from(y)));
    let d = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
    d.signum() as i32
}

fn to_i32(p: (i64, i64)) -> (i32, i32) {
    assert!(
        (MIN..=MAX).contains(&p.0) && (MIN..=MAX).contains(&p.1),
        "{p:?}"
    );
    (p.0 as i32, p.1 as i32)
}

/// Adds `t` (positive orientation) with a random winding.
fn push(out: &mut Vec<Tri>, t: [(i64, i64); 3], rng: &mut Rng) {
    let mut t = t.map(to_i32);
    if rng.chance(2) {
        t.swap(1, 2);
    }
    t.rotate_left(rng.below(3) as usize);
    out.push(t);
}

#[derive(Clone, Copy, Debug)]
enum Diagonal {
    Down,
    Up,
    Random,
}

/// A grid through the given column and row positions (strictly increasing), each cell split
/// along a diagonal. Interior vertices are moved by up to `jitter` raw units (reduced until no
/// triangle flips). Boundary vertices stay put, so the outline is the rectangle
/// `[xs[0], xs[last]] × [ys[0], ys[last]]`.
fn grid(xs: &[i64], ys: &[i64], diagonal: Diagonal, jitter: i64, rng: &mut Rng) -> Vec<Tri> {
    let (nx, ny) = (xs.len(), ys.len());
    let diagonals: Vec<bool> = (0..(nx - 1) * (ny - 1))
        .map(|_| match diagonal {
            Diagonal::Down => true,
            Diagonal::Up => false,
            Diagonal::Random => rng.chance(2),
        })
        .collect();
    let mut jitter = jitter;
    loop {
        let mut pts = vec![(0i64, 0i64); nx * ny];
        for j in 0..ny {
            for i in 0..nx {
                let interior = i > 0 && j > 0 && i + 1 < nx && j + 1 < ny;
                let (dx, dy) = if interior && jitter > 0 {
                    (rng.range(-jitter, jitter), rng.range(-jitter, jitter))
                } else {
                    (0, 0)
                };
                pts[j * nx + i] = (xs[i] + dx, ys[j] + dy);
            }
        }
        let mut cells = Vec::new();
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let a = pts[j * nx + i];
                let b = pts[j * nx + i + 1];
                let c = pts[(j + 1) * nx + i + 1];
                let d = pts[(j + 1) * nx + i];
                // With y downward, a → b → c → d runs clockwise on screen: positive orientation.
                if diagonals[j * (nx - 1) + i] {
                    cells.push([a, b, c]);
                    cells.push([a, c, d]);
                } else {
                    cells.push([a, b, d]);
                    cells.push([b, c, d]);
                }
            }
        }
        if cells.iter().all(|&t| orientation(t) > 0) {
            let mut out = Vec::new();
            for t in cells {
                push(&mut out, t, rng);
            }
            return out;
        }
        jitter /= 2;
    }
}

/// A fan around `centre` through the closed rim polygon `rim` (in clockwise-on-screen order).
/// Returns `None` if a triangle would be degenerate or flipped (the rim is not strictly
/// star-shaped around the centre).
fn fan(centre: (i64, i64), rim: &[(i64, i64)], rng: &mut Rng) -> Option<Vec<Tri>> {
    let mut tris = Vec::new();
    for k in 0..rim.len() {
        let t = [centre, rim[k], rim[(k + 1) % rim.len()]];
        if orientation(t) <= 0 {
            return None;
        }
        tris.push(t);
    }
    let mut out = Vec::new();
    for t in tris {
        push(&mut out, t, rng);
    }
    Some(out)
}

/// `n` points on a circle of radius `r` around `centre`, clockwise on screen, rounded to raw units.
fn circle(centre: (i64, i64), r: f64, n: usize, phase: f64) -> Vec<(i64, i64)> {
    (0..n)
        .map(|k| {
            let a = phase + TAU * k as f64 / n as f64;
            (
                centre.0 + (r * a.cos()).round() as i64,
                centre.1 + (r * a.sin()).round() as i64,
            )
        })
        .collect()
}

/// Strictly increasing positions from `lo` to `hi` with `n` steps of random lengths.
fn positions(lo: i64, hi: i64, n: usize, rng: &mut Rng) -> Vec<i64> {
    let mut cuts: Vec<i64> = (0..n - 1).map(|_| rng.range(lo + 1, hi - 1)).collect();
    cuts.push(lo);
    cuts.push(hi);
    cuts.sort_unstable();
    cuts.dedup();
    cuts
}

fn uniform(start: i64, step: i64, n: usize) -> Vec<i64> {
    (0..=n as i64).map(|i| start + i * step).collect()
}

/// A raw sub-pixel offset: pixel corner, centre, or random.
fn offset(rng: &mut Rng) -> i64 {
    match rng.below(4) {
        0 => 0,
        1 => 128,
        _ => rng.range(0, 255),
    }
}

fn screen_covering(xs: &[i64], ys: &[i64]) -> bool {
    let last_x = (i64::from(W) - 1) * 256 + 128;
    let last_y = (i64::from(H) - 1) * 256 + 128;
    xs[0] <= 128 && *xs.last().unwrap() > last_x && ys[0] <= 128 && *ys.last().unwrap() > last_y
}

fn grid_meshes(rng: &mut Rng, out: &mut Vec<Mesh>) {
    let diagonals = [Diagonal::Down, Diagonal::Up, Diagonal::Random];
    for n in 0..720 {
        let diagonal = diagonals[n % 3];
        let (xs, ys, jitter) = match n / 3 % 6 {
            // Whole-pixel spacing from a pixel corner or centre: edges through rows of centres.
            0 => {
                let s = 256 * rng.range(1, 12);
                let o = (
                    rng.range(-6, 2) * 256 + offset(rng),
                    rng.range(-6, 2) * 256 + 128,
                );
                (uniform(o.0, s, 8), uniform(o.1, s, 6), 0)
            }
            // Random sub-pixel spacing and origin, square or not.
            1 => {
                let sx = rng.range(40, 3000);
                let sy = if rng.chance(2) {
                    sx
                } else {
                    rng.range(40, 3000)
                };
                let o = (rng.range(-4000, 2000), rng.range(-4000, 2000));
                (uniform(o.0, sx, 20), uniform(o.1, sy, 20), 0)
            }
            // Jittered (random triangulation of perturbed grid points).
            2 => {
                let s = rng.range(200, 2500);
                let o = (rng.range(-3000, 0), rng.range(-3000, 0));
                let nx = (W as i64 * 256 + 6000) / s + 2;
                let ny = (H as i64 * 256 + 6000) / s + 2;
                (
                    uniform(o.0, s, nx as usize),
                    uniform(o.1, s, ny as usize),
                    s / 3,
                )
            }
            // Non-uniform columns and rows around the screen.
            3 => (
                positions(-3000, i64::from(W) * 256 + 3000, 25, rng),
                positions(-3000, i64::from(H) * 256 + 3000, 20, rng),
                0,
            ),
            // Far beyond the screen: large cells.
            4 => {
                let s = 1 << rng.range(16, 26);
                let o = (
                    -rng.range(1, 4) * s + offset(rng),
                    -rng.range(1, 4) * s + 128,
                );
                (uniform(o.0, s, 8), uniform(o.1, s, 8), s / 4)
            }
            // The full raw range: columns from i32::MIN to i32::MAX with cuts near the screen.
            _ => {
                let mut xs = positions(MIN, MAX, 6, rng);
                xs.extend(positions(-2000, i64::from(W) * 256 + 2000, 10, rng));
                xs.sort_unstable();
                xs.dedup();
                let mut ys = positions(MIN, MAX, 6, rng);
                ys.extend(positions(-2000, i64::from(H) * 256 + 2000, 8, rng));
                ys.sort_unstable();
                ys.dedup();
                (xs, ys, 0)
            }
        };
        let covers_screen = screen_covering(&xs, &ys);
        out.push(Mesh {
            name: format!(
                "grid #{n} {diagonal:?} {}x{} cells, jitter {jitter}",
                xs.len() - 1,
                ys.len() - 1
            ),
            triangles: grid(&xs, &ys, diagonal, jitter, rng),
            covers_screen,
        });
    }
}

fn fan_meshes(rng: &mut Rng, out: &mut Vec<Mesh>) {
    let mut n = 0;
    while n < 960 {
        // Centre on a pixel centre, a pixel corner, or a random sub-pixel position on screen.
        let px = (
            rng.range(0, i64::from(W) - 1),
            rng.range(0, i64::from(H) - 1),
        );
        let centre = match n % 3 {
            0 => (px.0 * 256 + 128, px.1 * 256 + 128),
            1 => (px.0 * 256, px.1 * 256),
            _ => (
                px.0 * 256 + rng.range(0, 255),
                px.1 * 256 + rng.range(0, 255),
            ),
        };
        let (name, rim, covers_screen) = match n / 3 % 4 {
            // Many thin triangles on a circle inside or around the screen.
            0 => {
                let r = rng.range(2 * 256, 60 * 256) as f64;
                let k = rng.range(3, 360) as usize;
                (
                    format!("circle fan r={r} n={k}"),
                    circle(centre, r, k, rng.unit() * TAU),
                    false,
                )
            }
            // A rim of pixel-lattice points on a square around the centre: every edge passes
            // through a row of pixel centres when the centre is on one.
            1 => {
                let r = rng.range(1, 40);
                let mut rim = Vec::new();
                for i in -r..r {
                    rim.push((i, -r));
                }
                for i in -r..r {
                    rim.push((r, i));
                }
                for i in -r..r {
                    rim.push((-i, r));
                }
                for i in -r..r {
                    rim.push((-r, -i));
                }
                let rim = rim
                    .into_iter()
                    .map(|(x, y)| (centre.0 + 256 * x, centre.1 + 256 * y))
                    .collect();
                (format!("lattice square fan r={r}px"), rim, false)
            }
            // Huge fans covering the whole screen.
            2 => {
                let r = (1u64 << rng.range(17, 30)) as f64;
                let k = rng.range(3, 400) as usize;
                (
                    format!("huge fan r={r} n={k}"),
                    circle(centre, r, k, rng.unit() * TAU),
                    true,
                )
            }
            // Extremely thin triangles: 1000+ rim points, a radius of a few hundred pixels.
            _ => {
                let r = rng.range(100 * 256, 3000 * 256) as f64;
                let k = rng.range(1000, 3000) as usize;
                (
                    format!("dense fan r={r} n={k}"),
                    circle(centre, r, k, rng.unit() * TAU),
                    true,
                )
            }
        };
        if let Some(triangles) = fan(centre, &rim, rng) {
            out.push(Mesh {
                name: format!("fan #{n} centre {centre:?}: {name}"),
                triangles,
                covers_screen,
            });
            n += 1;
        }
    }
}

fn draw_counts(mesh: &Mesh, area: Rectangle, rng: &mut Rng) -> [Vec<u32>; 3] {
    let mut solid = Counter::new(area);
    let mut gouraud = Counter::new(area);
    let mut spans = Counter::new(area);
    for t in &mesh.triangles {
        let c = t.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y)));
        SolidTriangle::new(c, Rgb565::WHITE)
            .draw(&mut solid)
            .unwrap();
        let colour = |rng: &mut Rng| {
            let v = rng.next();
            Rgb565::new(v as u8 & 31, (v >> 8) as u8 & 63, (v >> 16) as u8 & 31)
        };
        GouraudTriangle::new([0, 1, 2].map(|k| Vertex::new(c[k].0, c[k].1, colour(rng))))
            .draw(&mut gouraud)
            .unwrap();
        raster::for_each_span(c, area, |y, x0, x1| {
            spans
                .draw_iter((x0..x1).map(|x| Pixel(Point::new(x, y), Rgb565::WHITE)))
                .unwrap();
        });
    }
    [solid.counts, gouraud.counts, spans.counts]
}

fn reference_counts(mesh: &Mesh, area: Rectangle) -> Vec<u32> {
    let (x0, y0) = (area.top_left.x, area.top_left.y);
    let (w, h) = (area.size.width as i32, area.size.height as i32);
    let mut counts = vec![0u32; (w * h) as usize];
    for &t in &mesh.triangles {
        reference::for_each_covered(t, x0, y0, x0 + w, y0 + h, |x, y| {
            counts[((y - y0) * w + (x - x0)) as usize] += 1;
        });
    }
    counts
}

/// Checks one mesh against one target area; returns (pixels in the union, pixels outside).
fn check(mesh: &Mesh, area: Rectangle, rng: &mut Rng) -> (usize, usize) {
    let want = reference_counts(mesh, area);
    let w = area.size.width as usize;
    let at = |i: usize| area.top_left + Point::new((i % w) as i32, (i / w) as i32);
    for (i, &n) in want.iter().enumerate() {
        assert!(
            n <= 1,
            "{}: the reference covers pixel {:?} {n} times: not a valid mesh",
            mesh.name,
            at(i)
        );
    }
    if mesh.covers_screen && area.top_left == Point::zero() {
        if let Some(i) = want.iter().position(|&n| n != 1) {
            panic!(
                "{}: the mesh covers the screen but the reference misses pixel {:?}",
                mesh.name,
                at(i)
            );
        }
    }
    let got = draw_counts(mesh, area, rng);
    for (which, counts) in ["SolidTriangle", "GouraudTriangle", "for_each_span"]
        .iter()
        .zip(&got)
    {
        if let Some(i) = (0..want.len()).find(|&i| counts[i] != want[i]) {
            let p = at(i);
            let (px, py) = (p.x, p.y);
            let owners: Vec<Tri> = mesh
                .triangles
                .iter()
                .copied()
                .filter(|&t| {
                    reference::covers(t, px, py)
                        || reference::barycentric(t, px, py)
                            .is_some_and(|b| b.iter().all(|&w| w >= -1e-9))
                })
                .collect();
            panic!(
                "{}: {which} drew pixel {p:?} {} times, the reference covers it {} times; \
                 triangles at that pixel (raw): {owners:?}",
                mesh.name, counts[i], want[i]
            );
        }
    }
    let inside = want.iter().filter(|&&n| n == 1).count();
    (inside, want.len() - inside)
}

fn screen() -> Rectangle {
    Rectangle::new(Point::zero(), Size::new(W, H))
}

#[test]
fn grids_are_watertight() {
    let mut rng = Rng(0x6772_6964);
    let mut meshes = Vec::new();
    grid_meshes(&mut rng, &mut meshes);
    let (mut inside, mut outside, mut triangles, mut full) = (0, 0, 0, 0);
    for mesh in &meshes {
        let (i, o) = check(mesh, screen(), &mut rng);
        inside += i;
        outside += o;
        triangles += mesh.triangles.len();
        full += usize::from(mesh.covers_screen);
    }
    println!(
        "grids: {} meshes ({full} covering the screen), {triangles} triangles, {inside} pixels \
         inside the union, {outside} outside",
        meshes.len()
    );
}

#[test]
fn fans_are_watertight() {
    let mut rng = Rng(0x6661_6e73);
    let mut meshes = Vec::new();
    fan_meshes(&mut rng, &mut meshes);
    let (mut inside, mut outside, mut triangles) = (0, 0, 0);
    for mesh in &meshes {
        let (i, o) = check(mesh, screen(), &mut rng);
        inside += i;
        outside += o;
        triangles += mesh.triangles.len();
    }
    println!(
        "fans: {} meshes, {triangles} triangles, {inside} pixels inside the union, {outside} \
         outside",
        meshes.len()
    );
}

/// Meshes spanning the whole raw range cover every pixel whose centre is inside it: check them
/// on targets placed anywhere in that range (clipping with non-zero origins), including the
/// extreme ends.
#[test]
fn full_range_meshes_on_offset_targets() {
    let mut rng = Rng(0x6675_6c6c);
    let limit = (1i64 << 23) - 1; // pixel centres 256 i + 128 within the raw i32 range
    for n in 0..60 {
        let mut xs = positions(MIN, MAX, 10, &mut rng);
        let mut ys = positions(MIN, MAX, 10, &mut rng);
        // Target anywhere, with extra grid lines through it.
        let (tx, ty) = match n % 4 {
            0 => (-limit - 1, -limit - 1),
            1 => (limit + 1 - i64::from(W), limit + 1 - i64::from(H)),
            _ => (
                rng.range(-limit, limit - i64::from(W)),
                rng.range(-limit, limit - i64::from(H)),
            ),
        };
        xs.extend(positions(
            tx * 256 - 500,
            (tx + i64::from(W)) * 256 + 500,
            8,
            &mut rng,
        ));
        ys.extend(positions(
            ty * 256 - 500,
            (ty + i64::from(H)) * 256 + 500,
            8,
            &mut rng,
        ));
        for v in [&mut xs, &mut ys] {
            v.retain(|&p| (MIN..=MAX).contains(&p));
            v.sort_unstable();
            v.dedup();
        }
        let diagonal = [Diagonal::Down, Diagonal::Up, Diagonal::Random][n % 3];
        let mesh = Mesh {
            name: format!("full-range grid #{n} at target ({tx}, {ty})"),
            triangles: grid(&xs, &ys, diagonal, 0, &mut rng),
            covers_screen: false,
        };
        let area = Rectangle::new(Point::new(tx as i32, ty as i32), Size::new(W, H));
        let (inside, _) = check(&mesh, area, &mut rng);
        // The grid spans the whole raw range [MIN, MAX]², and every centre of these targets lies
        // strictly inside it (from MIN + 128 to MAX - 127).
        assert_eq!(inside, (W * H) as usize, "{}", mesh.name);
    }
}

/// Two meshes mirrored around a shared boundary through pixel centres: their union tiles the
/// screen and each side's pixels are drawn once.
#[test]
fn adjacent_meshes_share_their_boundary() {
    let mut rng = Rng(0x7368_6172);
    for n in 0..100 {
        // A vertical or horizontal split line through pixel centres, at a corner, or anywhere.
        let split = rng.range(4, 40) * 256 + [128, 0, rng.range(0, 255)][n % 3];
        let full_x = uniform(-512, 256 * 17, 5);
        let full_y = uniform(-512, 256 * 13, 5);
        let (left_x, right_x) = {
            let l = positions(-512, split, 6, &mut rng);
            let r = positions(split, full_x[5], 6, &mut rng);
            (l, r)
        };
        let mut triangles = grid(&left_x, &full_y, Diagonal::Random, 0, &mut rng);
        triangles.extend(grid(&right_x, &full_y, Diagonal::Random, 0, &mut rng));
        let mesh = Mesh {
            name: format!("split at x = {split}"),
            triangles,
            covers_screen: true,
        };
        check(&mesh, screen(), &mut rng);
        // The same split in y.
        let top_y = positions(-512, split.min(H as i64 * 256 - 1), 4, &mut rng);
        let bottom_y = positions(*top_y.last().unwrap(), full_y[5], 4, &mut rng);
        let mut triangles = grid(&full_x, &top_y, Diagonal::Random, 0, &mut rng);
        triangles.extend(grid(&full_x, &bottom_y, Diagonal::Random, 0, &mut rng));
        let mesh = Mesh {
            name: format!("split at y = {}", top_y.last().unwrap()),
            triangles,
            covers_screen: true,
        };
        check(&mesh, screen(), &mut rng);
    }
}
