//! Shared workload of the fill-rate benchmarks (`benches/fill_rate.rs`, criterion) and the
//! one-process interleaved report (`examples/bench_report.rs`).
//!
//! Host-only: floats are used freely here (triangle generation and the textbook rasterizer).
//!
//! * Deterministic triangle sets per size class: own xorshift PRNG, fixed seeds, random rotation
//!   and winding, sub-pixel (1/256) vertices.
//! * The methods being compared, each drawing a whole set into a 320×240 `Rgb565` target.
//! * Each method's own covered-pixel count per set, for `Mpx/s`.
#![allow(dead_code)]

use std::f64::consts::TAU;

use embedded_graphics::{
    framebuffer::{buffer_size, Framebuffer},
    pixelcolor::{
        raw::{LittleEndian, RawU16},
        Rgb565,
    },
    prelude::*,
    primitives::{PrimitiveStyle, Rectangle, Styled, Triangle},
    Pixel,
};
use embedded_raster::{
    raster::for_each_span, Coord, GouraudTriangle, SliceFramebuffer, SolidTriangle, Vertex,
};

pub const WIDTH: usize = 320;
pub const HEIGHT: usize = 240;

/// embedded-graphics' own framebuffer: 320×240 Rgb565, little-endian bytes.
pub type EgFramebuffer = Framebuffer<
    Rgb565,
    RawU16,
    LittleEndian,
    WIDTH,
    HEIGHT,
    { buffer_size::<Rgb565>(WIDTH, HEIGHT) },
>;

/// xorshift64*: small, fast, deterministic.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed | 1)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * unit
    }

    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
}

/// Triangle size mixes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SizeClass {
    /// About 16 px² each, fully on screen.
    Small,
    /// About 1,000 px² each, fully on screen.
    Medium,
    /// Covering most of the 320×240 screen, many crossing its edges.
    Screen,
}

impl SizeClass {
    pub const ALL: [SizeClass; 3] = [SizeClass::Small, SizeClass::Medium, SizeClass::Screen];

    /// Short id (criterion benchmark names).
    pub fn id(self) -> &'static str {
        match self {
            SizeClass::Small => "small_16px2",
            SizeClass::Medium => "medium_1000px2",
            SizeClass::Screen => "screen_filling",
        }
    }

    /// Table heading.
    pub fn label(self) -> &'static str {
        match self {
            SizeClass::Small => "≈16 px²",
            SizeClass::Medium => "≈1,000 px²",
            SizeClass::Screen => "screen-filling",
        }
    }

    fn count(self) -> usize {
        match self {
            SizeClass::Small => 4096,
            SizeClass::Medium => 256,
            SizeClass::Screen => 16,
        }
    }

    fn seed(self) -> u64 {
        match self {
            SizeClass::Small => 0x5EED_0016,
            SizeClass::Medium => 0x5EED_1000,
            SizeClass::Screen => 0x5EED_F111,
        }
    }
}

/// One benchmark triangle in every form the methods need (built outside the timed loops).
#[derive(Debug, Clone)]
pub struct Tri {
    pub positions: [(Coord, Coord); 3],
    pub colors: [Rgb565; 3],
    pub solid: SolidTriangle<Rgb565>,
    pub gouraud: GouraudTriangle<Rgb565>,
    /// embedded-graphics' triangle on integer points, filled with `colors[0]`.
    pub eg: Styled<Triangle, PrimitiveStyle<Rgb565>>,
    /// The same vertices as `f32` pixel coordinates, for the textbook rasterizer.
    pub float: [(f32, f32); 3],
}

fn to_coord(v: f64) -> Coord {
    Coord::from_bits((v * 256.0).round() as i32)
}

/// embedded-graphics treats a `Point` as a pixel, i.e. as the pixel centre `(p + 0.5)` in our
/// convention: rounding `x − 0.5` (= flooring the 1/256 value) lines the two coverages up.
fn to_point((x, y): (Coord, Coord)) -> Point {
    Point::new(x.to_bits() >> 8, y.to_bits() >> 8)
}

impl Tri {
    fn new(vertices: [(f64, f64); 3], colors: [Rgb565; 3]) -> Tri {
        let positions = vertices.map(|(x, y)| (to_coord(x), to_coord(y)));
        let points = positions.map(to_point);
        Tri {
            positions,
            colors,
            solid: SolidTriangle::new(positions, colors[0]),
            gouraud: GouraudTriangle::new(
                [0, 1, 2].map(|k| Vertex::new(positions[k].0, positions[k].1, colors[k])),
            ),
            eg: Triangle::new(points[0], points[1], points[2])
                .into_styled(PrimitiveStyle::with_fill(colors[0])),
            float: positions.map(|(x, y)| (x.to_num::<f32>(), y.to_num::<f32>())),
        }
    }
}

fn random_color(rng: &mut Rng) -> Rgb565 {
    Rgb565::new(
        rng.below(32) as u8,
        rng.below(64) as u8,
        rng.below(32) as u8,
    )
}

/// Three points roughly 120° apart around the origin, rotated at random, radii `r·[0.6, 1]`;
/// random winding.
fn random_shape(rng: &mut Rng, jitter: f64, r_lo: f64) -> [(f64, f64); 3] {
    let theta = rng.uniform(0.0, TAU);
    let mut v = [0, 1, 2].map(|k| {
        let a = theta + k as f64 * TAU / 3.0 + rng.uniform(-jitter, jitter);
        let r = rng.uniform(r_lo, 1.0);
        (r * a.cos(), r * a.sin())
    });
    if rng.below(2) == 1 {
        v.swap(1, 2);
    }
    v
}

fn area(v: &[(f64, f64); 3]) -> f64 {
    0.5 * ((v[1].0 - v[0].0) * (v[2].1 - v[0].1) - (v[2].0 - v[0].0) * (v[1].1 - v[0].1)).abs()
}

/// The deterministic triangle set of a size class.
pub fn triangles(class: SizeClass) -> Vec<Tri> {
    let mut rng = Rng::new(class.seed());
    (0..class.count())
        .map(|_| {
            let shape = random_shape(&mut rng, 0.5, 0.6);
            let (cx, cy, scale) = match class {
                SizeClass::Small | SizeClass::Medium => {
                    let target = if class == SizeClass::Small {
                        16.0
                    } else {
                        1000.0
                    };
                    let target = target * rng.uniform(0.8, 1.2);
                    let scale = (target / area(&shape)).sqrt();
                    // Fully on screen: the shape lies within `scale` of its centre.
                    let cx = rng.uniform(scale, WIDTH as f64 - scale);
                    let cy = rng.uniform(scale, HEIGHT as f64 - scale);
                    (cx, cy, scale)
                }
                SizeClass::Screen => {
                    // Circumradius 190..420 px around a point near the centre: from about 60 % of
                    // the screen to all of it, edges and corners crossing the borders.
                    let cx = WIDTH as f64 / 2.0 + rng.uniform(-40.0, 40.0);
                    let cy = HEIGHT as f64 / 2.0 + rng.uniform(-30.0, 30.0);
                    (cx, cy, rng.uniform(190.0, 420.0))
                }
            };
            let vertices = shape.map(|(x, y)| (cx + scale * x, cy + scale * y));
            let colors = [(); 3].map(|_| random_color(&mut rng));
            Tri::new(vertices, colors)
        })
        .collect()
}

/// The compared methods.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// `SolidTriangle::draw_into(&mut SliceFramebuffer)`: slice fill per span.
    OursSolidInto,
    /// `SolidTriangle` through `Drawable::draw` on a `SliceFramebuffer` (`fill_solid` per span).
    OursSolidDraw,
    /// `SolidTriangle` through `Drawable::draw` on embedded-graphics' `Framebuffer`.
    OursSolidEgFb,
    /// `GouraudTriangle::draw_into(&mut SliceFramebuffer)`: packed 5-6-5 span loop.
    OursGouraudInto,
    /// `GouraudTriangle` through `Drawable::draw` on a `SliceFramebuffer` (`fill_contiguous`).
    OursGouraudDraw,
    /// `GouraudTriangle` through `Drawable::draw` on embedded-graphics' `Framebuffer`.
    OursGouraudEgFb,
    /// embedded-graphics' filled `Triangle` on a `SliceFramebuffer`.
    EgTriangleSlice,
    /// embedded-graphics' filled `Triangle` on its own `Framebuffer`.
    EgTriangleEgFb,
    /// Textbook per-pixel `f32` barycentric rasterizer over the bounding box (Gouraud).
    NaiveFloat,
    /// 8×8 block traversal with trivial accept/reject over the same exact edge functions
    /// (solid; the technique weighed against our per-row spans).
    Block8Solid,
}

impl Method {
    pub const ALL: [Method; 10] = [
        Method::OursSolidInto,
        Method::OursSolidDraw,
        Method::OursSolidEgFb,
        Method::OursGouraudInto,
        Method::OursGouraudDraw,
        Method::OursGouraudEgFb,
        Method::EgTriangleSlice,
        Method::EgTriangleEgFb,
        Method::NaiveFloat,
        Method::Block8Solid,
    ];

    pub fn id(self) -> &'static str {
        match self {
            Method::OursSolidInto => "ours_solid_draw_into_slice",
            Method::OursSolidDraw => "ours_solid_draw_slice",
            Method::OursSolidEgFb => "ours_solid_draw_eg_fb",
            Method::OursGouraudInto => "ours_gouraud_draw_into_slice",
            Method::OursGouraudDraw => "ours_gouraud_draw_slice",
            Method::OursGouraudEgFb => "ours_gouraud_draw_eg_fb",
            Method::EgTriangleSlice => "eg_triangle_slice",
            Method::EgTriangleEgFb => "eg_triangle_eg_fb",
            Method::NaiveFloat => "naive_f32_barycentric_slice",
            Method::Block8Solid => "block8_solid_slice",
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            Method::OursSolidInto => "ours: `SolidTriangle::draw_into` → SliceFramebuffer",
            Method::OursSolidDraw => "ours: `SolidTriangle.draw` → SliceFramebuffer",
            Method::OursSolidEgFb => "ours: `SolidTriangle.draw` → e-g Framebuffer",
            Method::OursGouraudInto => "ours: `GouraudTriangle::draw_into` → SliceFramebuffer",
            Method::OursGouraudDraw => "ours: `GouraudTriangle.draw` → SliceFramebuffer",
            Method::OursGouraudEgFb => "ours: `GouraudTriangle.draw` → e-g Framebuffer",
            Method::EgTriangleSlice => "e-g `Triangle` (solid) → SliceFramebuffer",
            Method::EgTriangleEgFb => "e-g `Triangle` (solid) → e-g Framebuffer",
            Method::NaiveFloat => "naive f32 barycentric (Gouraud) → slice",
            Method::Block8Solid => "8×8 blocks, exact edges (solid) → slice",
        }
    }
}

/// Draw targets, allocated once.
pub struct Targets {
    pub slice: Vec<Rgb565>,
    pub eg_fb: Box<EgFramebuffer>,
}

impl Targets {
    pub fn new() -> Self {
        Targets {
            slice: vec![Rgb565::BLACK; WIDTH * HEIGHT],
            eg_fb: Box::new(EgFramebuffer::new()),
        }
    }
}

impl Default for Targets {
    fn default() -> Self {
        Self::new()
    }
}

fn slice_fb(pixels: &mut [Rgb565]) -> SliceFramebuffer<'_, Rgb565> {
    SliceFramebuffer::new(pixels, WIDTH as u32, HEIGHT as u32).expect("320×240 slice")
}

/// Draws the whole set with one method.
///
/// Each method's loop is its own function ([`each`]): compiled apart, so that LLVM's inlining
/// decisions for one method do not depend on how much code the others add to one big function.
pub fn draw_set(method: Method, tris: &[Tri], targets: &mut Targets) {
    match method {
        Method::OursSolidInto => {
            let mut fb = slice_fb(&mut targets.slice);
            each(tris, |t| t.solid.draw_into(&mut fb));
        }
        Method::OursSolidDraw => {
            let mut fb = slice_fb(&mut targets.slice);
            each(tris, |t| {
                let Ok(()) = t.solid.draw(&mut fb);
            });
        }
        Method::OursSolidEgFb => each(tris, |t| {
            let Ok(()) = t.solid.draw(&mut *targets.eg_fb);
        }),
        Method::OursGouraudInto => {
            let mut fb = slice_fb(&mut targets.slice);
            each(tris, |t| t.gouraud.draw_into(&mut fb));
        }
        Method::OursGouraudDraw => {
            let mut fb = slice_fb(&mut targets.slice);
            each(tris, |t| {
                let Ok(()) = t.gouraud.draw(&mut fb);
            });
        }
        Method::OursGouraudEgFb => each(tris, |t| {
            let Ok(()) = t.gouraud.draw(&mut *targets.eg_fb);
        }),
        Method::EgTriangleSlice => {
            let mut fb = slice_fb(&mut targets.slice);
            each(tris, |t| {
                let Ok(()) = t.eg.draw(&mut fb);
            });
        }
        Method::EgTriangleEgFb => each(tris, |t| {
            let Ok(()) = t.eg.draw(&mut *targets.eg_fb);
        }),
        Method::NaiveFloat => {
            let pixels = &mut targets.slice[..];
            each(tris, |t| {
                naive_barycentric(t, |index, color| pixels[index] = color)
            });
        }
        Method::Block8Solid => {
            let pixels = &mut targets.slice[..];
            each(tris, |t| {
                block8(t, |row, x0, x1| {
                    pixels[row + x0..row + x1].fill(t.colors[0])
                })
            });
        }
    }
}

/// `draw` for every triangle of the set, in a function of its own for each method.
#[inline(never)]
fn each(tris: &[Tri], mut draw: impl FnMut(&Tri)) {
    for t in tris {
        draw(t);
    }
}

/// The bench's own edge set-up for [`block8`] (on-screen triangles, `i64`): the oriented edges'
/// `(a, b, k)` with pixel `(i, j)` inside an edge iff `a·i + b·j + k ≥ 0` (the top-left rule:
/// centres on left and top edges are inside), and the pixel bounding box clipped to the screen.
#[allow(clippy::type_complexity)]
fn block_setup(t: &Tri) -> Option<([(i64, i64, i64); 3], (i64, i64, i64, i64))> {
    let p = t
        .positions
        .map(|(x, y)| (i64::from(x.to_bits()), i64::from(y.to_bits())));
    let area2 = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
    let o = match area2.signum() {
        0 => return None,
        1 => p,
        _ => [p[0], p[2], p[1]],
    };
    let edge = |(xa, ya): (i64, i64), (xb, yb): (i64, i64)| {
        let (a, b) = (ya - yb, xb - xa);
        // The edge function at the centre of pixel (0, 0), 256² units.
        let c = a * (128 - xa) + b * (128 - ya);
        let top_left = a > 0 || (a == 0 && b > 0);
        (a, b, (c >> 8) - i64::from(c & 255 == 0 && !top_left))
    };
    let edges = [edge(o[1], o[2]), edge(o[2], o[0]), edge(o[0], o[1])];
    let lo = |v: [i64; 3]| (v.iter().min().copied().unwrap_or(0) - 128 + 255) >> 8;
    let hi = |v: [i64; 3]| (v.iter().max().copied().unwrap_or(0) - 128) >> 8;
    let (xs, ys) = (p.map(|v| v.0), p.map(|v| v.1));
    let (x0, y0) = (lo(xs).max(0), lo(ys).max(0));
    let (x1, y1) = (hi(xs).min(WIDTH as i64 - 1), hi(ys).min(HEIGHT as i64 - 1));
    (x0 <= x1 && y0 <= y1).then_some((edges, (x0, y0, x1, y1)))
}

/// 8×8 block traversal (solid): each block of the clipped bounding box is tested against the
/// three exact edge functions at its extreme corners — skipped if outside one edge, filled row by
/// row if inside all three — and the blocks an edge crosses are tested pixel by pixel with the
/// edge values stepped by `a` per pixel. `put(row_offset, x0, x1)` fills columns `x0..x1` of the
/// row starting at `row_offset`; the coverage is ours (same edge functions and tie rule).
#[inline(always)]
pub fn block8(t: &Tri, mut put: impl FnMut(usize, usize, usize)) {
    const B: i64 = 8;
    let Some((edges, (x0, y0, x1, y1))) = block_setup(t) else {
        return;
    };
    let mut by = y0;
    while by <= y1 {
        let bh = (y1 - by + 1).min(B);
        let mut bx = x0;
        while bx <= x1 {
            let bw = (x1 - bx + 1).min(B);
            let (mut inside, mut outside) = (true, false);
            for &(a, b, k) in &edges {
                let v = a * bx + b * by + k;
                let (da, db) = (a * (bw - 1), b * (bh - 1));
                inside &= v + da.min(0) + db.min(0) >= 0;
                outside |= v + da.max(0) + db.max(0) < 0;
            }
            if !outside {
                for j in by..by + bh {
                    let row = j as usize * WIDTH;
                    if inside {
                        put(row, bx as usize, (bx + bw) as usize);
                        continue;
                    }
                    let mut v = edges.map(|(a, b, k)| a * bx + b * j + k);
                    for i in bx..bx + bw {
                        if v.iter().all(|&e| e >= 0) {
                            put(row, i as usize, i as usize + 1);
                        }
                        for (e, &(a, _, _)) in v.iter_mut().zip(&edges) {
                            *e += a;
                        }
                    }
                }
            }
            bx += B;
        }
        by += B;
    }
}

/// The textbook rasterizer: for every pixel of the bounding box (clipped to the screen), three
/// `f32` cross products give the barycentric weights of the pixel centre; a pixel is drawn when
/// all three are non-negative, with the colour interpolated from the weights.
#[inline(always)]
pub fn naive_barycentric(t: &Tri, mut put: impl FnMut(usize, Rgb565)) {
    fn edge(a: (f32, f32), b: (f32, f32), p: (f32, f32)) -> f32 {
        (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)
    }
    let [v0, v1, v2] = t.float;
    let area = edge(v0, v1, v2);
    if area == 0.0 {
        return;
    }
    let inv_area = 1.0 / area;
    let channels = |k: usize| {
        let c = t.colors[k];
        [f32::from(c.r()), f32::from(c.g()), f32::from(c.b())]
    };
    let (c0, c1, c2) = (channels(0), channels(1), channels(2));
    // Casts from f32 saturate; clamp to the screen.
    let x0 = (v0.0.min(v1.0).min(v2.0).floor() as i32).clamp(0, WIDTH as i32);
    let x1 = (v0.0.max(v1.0).max(v2.0).ceil() as i32).clamp(0, WIDTH as i32);
    let y0 = (v0.1.min(v1.1).min(v2.1).floor() as i32).clamp(0, HEIGHT as i32);
    let y1 = (v0.1.max(v1.1).max(v2.1).ceil() as i32).clamp(0, HEIGHT as i32);
    for y in y0..y1 {
        for x in x0..x1 {
            let p = (x as f32 + 0.5, y as f32 + 0.5);
            let w0 = edge(v1, v2, p) * inv_area;
            let w1 = edge(v2, v0, p) * inv_area;
            let w2 = edge(v0, v1, p) * inv_area;
            if w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0 {
                let ch = |k: usize| (w0 * c0[k] + w1 * c1[k] + w2 * c2[k] + 0.5) as u8;
                put(
                    y as usize * WIDTH + x as usize,
                    Rgb565::new(ch(0), ch(1), ch(2)),
                );
            }
        }
    }
}

/// A draw target that counts the pixels drawn inside 320×240 (what embedded-graphics' triangle
/// actually writes once the target clips it).
struct CountingTarget(u64);

impl OriginDimensions for CountingTarget {
    fn size(&self) -> Size {
        Size::new(WIDTH as u32, HEIGHT as u32)
    }
}

impl DrawTarget for CountingTarget {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Rgb565>>,
    {
        let bounds = self.bounding_box();
        self.0 += pixels
            .into_iter()
            .filter(|Pixel(p, _)| bounds.contains(*p))
            .count() as u64;
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, _color: Rgb565) -> Result<(), Self::Error> {
        let inside = area.intersection(&self.bounding_box());
        self.0 += u64::from(inside.size.width) * u64::from(inside.size.height);
        Ok(())
    }
}

/// Pixels one pass over the set writes with `method` (each method's own coverage; computed
/// outside any timed loop).
pub fn pixel_count(method: Method, tris: &[Tri]) -> u64 {
    match method {
        Method::EgTriangleSlice | Method::EgTriangleEgFb => {
            let mut counter = CountingTarget(0);
            for t in tris {
                let Ok(()) = t.eg.draw(&mut counter);
            }
            counter.0
        }
        Method::NaiveFloat => {
            let mut n = 0;
            for t in tris {
                naive_barycentric(t, |_, _| n += 1);
            }
            n
        }
        Method::Block8Solid => {
            let mut n = 0;
            for t in tris {
                block8(t, |_, x0, x1| n += (x1 - x0) as u64);
            }
            n
        }
        _ => {
            let clip = Rectangle::new(Point::zero(), Size::new(WIDTH as u32, HEIGHT as u32));
            let mut n = 0u64;
            for t in tris {
                for_each_span(t.positions, clip, |_, x0, x1| n += (x1 - x0) as u64);
            }
            n
        }
    }
}
