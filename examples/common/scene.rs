//! The firmware test scene, shared with `#[path]` by the firmware examples (`fw_scene`,
//! `fw_nopanic`) and by the host test `tests/all/firmware_checksum.rs`.
//!
//! About 220 triangles, generated procedurally with integer arithmetic only (no tables that
//! differ between targets, no floats): a jittered grid that overhangs every border, a 32-spoke fan
//! around a sub-pixel centre that crosses the top and bottom edges, a thin band between vertices
//! at the ends of the `Coord` range, big triangles crossing the borders (one from 50 000
//! pixels above the screen), off-screen and degenerate ones, and sub-pixel slivers. Shapes
//! alternate between `Drawable::draw` and the `draw_into` fast path so both are exercised. Four
//! solid triangles at an opacity are then blended over the finished scene (`draw_into`).
//!
//! Everything here is panic-free for any size: `fw_nopanic` links it with a panic handler that
//! does not exist.

#[path = "fnv.rs"]
mod fnv;
pub use fnv::{fnv, FNV_START};

use embedded_graphics::pixelcolor::{raw::RawU16, Rgb565};
use embedded_graphics::prelude::*;
use embedded_raster::{
    Coord, CoverageMask, GouraudTriangle, SliceFramebuffer, SolidTriangle, Translucent, Vertex,
};

/// Framebuffer size on the MPS2 boards (4 MiB RAM).
pub const MPS2_SIZE: (u32, u32) = (128, 96);
/// Framebuffer size on the micro:bit (16 KiB RAM shared with the stack).
pub const MICROBIT_SIZE: (u32, u32) = (64, 48);
/// Every size the firmware is run with.
pub const SIZES: [(u32, u32); 2] = [MPS2_SIZE, MICROBIT_SIZE];

/// The colour the framebuffer is cleared to.
pub const BACKGROUND: Rgb565 = Rgb565::new(2, 5, 9);

/// One element of the scene.
#[derive(Debug, Clone, Copy)]
pub enum Shape {
    /// A Gouraud-shaded triangle.
    Gouraud(GouraudTriangle<Rgb565>),
    /// A solid triangle.
    Solid(SolidTriangle<Rgb565>),
}

impl Shape {
    /// Corner positions in raw sub-pixel units (256 per pixel).
    pub fn raw_positions(&self) -> [(i32, i32); 3] {
        match self {
            Shape::Gouraud(t) => t.vertices.map(|v| (v.x.to_bits(), v.y.to_bits())),
            Shape::Solid(t) => t.points.map(|(x, y)| (x.to_bits(), y.to_bits())),
        }
    }
}

/// The benchmarks' "large" set on a `w × h` screen (corner pixel centres): the two halves of the
/// screen and two big rotated triangles (`fw_bench`, `fw_profile`).
pub fn large_triangles(w: i32, h: i32) -> [[(i32, i32); 3]; 4] {
    [
        [(0, 0), (w - 1, 0), (w - 1, h - 1)],
        [(0, 0), (w - 1, h - 1), (0, h - 1)],
        [
            (w / 10, h / 20),
            (w * 19 / 20, h * 2 / 5),
            (w * 3 / 10, h * 19 / 20),
        ],
        [
            (w * 9 / 10, h * 9 / 10),
            (w / 20, h * 3 / 5),
            (w * 3 / 5, h / 20),
        ],
    ]
}

/// `sin(2π k / 32)` in units of 1/4096, for any `k`.
fn sin32(k: u32) -> i32 {
    const QUARTER: [i32; 9] = [0, 799, 1567, 2276, 2896, 3406, 3784, 4017, 4096];
    let (quadrant, r) = ((k / 8) % 4, (k % 8) as usize);
    let at = |i: usize| QUARTER.get(i).copied().unwrap_or(0);
    match quadrant {
        0 => at(r),
        1 => at(8 - r),
        2 => -at(r),
        _ => -at(8 - r),
    }
}

/// A well-mixed 32-bit hash of two integers and a seed.
fn hash(a: i32, b: i32, seed: u32) -> u32 {
    let mut h = (a as u32)
        .wrapping_mul(0x9E37_79B1)
        .wrapping_add((b as u32).wrapping_mul(0x85EB_CA77))
        ^ seed.wrapping_mul(0xC2B2_AE3D);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2C1B_3C6D);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297A_2D39);
    h ^ (h >> 15)
}

fn color(h: u32) -> Rgb565 {
    Rgb565::new(
        (h & 31) as u8,
        ((h >> 5) & 63) as u8,
        ((h >> 11) & 31) as u8,
    )
}

fn c(raw: i32) -> Coord {
    Coord::from_bits(raw)
}

fn v(x: i32, y: i32, color: Rgb565) -> Vertex<Rgb565> {
    Vertex::new(c(x), c(y), color)
}

// (Constant indices: no bounds-check panic path in the firmware that proves there is none.)
fn gouraud_triangle(p: [(i32, i32); 3], colors: [Rgb565; 3]) -> GouraudTriangle<Rgb565> {
    GouraudTriangle::new([
        v(p[0].0, p[0].1, colors[0]),
        v(p[1].0, p[1].1, colors[1]),
        v(p[2].0, p[2].1, colors[2]),
    ])
}

fn gouraud(p: [(i32, i32); 3], colors: [Rgb565; 3]) -> Shape {
    Shape::Gouraud(gouraud_triangle(p, colors))
}

fn solid(p: [(i32, i32); 3], color: Rgb565) -> Shape {
    Shape::Solid(SolidTriangle::new(p.map(|(x, y)| (c(x), c(y))), color))
}

/// Calls `f` with every shape of the scene for a `width × height` screen (each clamped to
/// 4096), in drawing order.
pub fn for_each_shape(width: u32, height: u32, mut f: impl FnMut(Shape)) {
    // Screen size in sub-pixel units; `fx(n)` is n/100 of the width, `fy(n)` of the height.
    let w = (width.min(4096) as i32) * 256;
    let h = (height.min(4096) as i32) * 256;
    let fx = |n: i32| w / 100 * n;
    let fy = |n: i32| h / 100 * n;

    // 1. A 10 × 8 grid of jittered cells, one cell beyond every border; diagonals alternate.
    //    Shared corners keep their position and colour, so neighbouring triangles share edges.
    let (cols, rows) = (8, 6);
    let (cw, ch) = (w / cols, h / rows);
    let corner = |i: i32, j: i32| {
        let r = hash(i, j, 1);
        let jx = (r % 256) as i32 * cw / 512 - cw / 4;
        let jy = ((r >> 8) % 256) as i32 * ch / 512 - ch / 4;
        // Half-pixel multiples: many edges pass exactly through pixel centres (fill-rule ties).
        let snap = |v: i32| v & !127;
        (snap((i - 1) * cw + jx), snap((j - 1) * ch + jy))
    };
    for j in 0..rows + 2 {
        for i in 0..cols + 2 {
            let [a, b, cc, d] = [
                corner(i, j),
                corner(i + 1, j),
                corner(i + 1, j + 1),
                corner(i, j + 1),
            ];
            let (t1, t2) = if (i + j) % 2 == 0 {
                ([a, b, cc], [a, cc, d])
            } else {
                ([a, b, d], [b, cc, d])
            };
            // Every triangle has its own colours, so whoever owns a shared edge is visible.
            let colors = |t: i32| [0, 1, 2].map(|k| color(hash(i * 2 + t, j, k + 10)));
            f(gouraud(t1, colors(0)));
            f(gouraud(t2, colors(1)));
        }
    }

    // 2. A 32-spoke elliptic fan around a sub-pixel centre, crossing the top and bottom.
    let (cx, cy) = (fx(60) + 77, fy(45) + 179);
    let (rx, ry) = (h / 256 * 102, h / 256 * 154); // 0.4 h and 0.6 h in sub-pixel units
    let rim = |k: u32| {
        let along = |r: i32, s: i32| (i64::from(r) * i64::from(s) / 4096) as i32;
        (cx + along(rx, sin32(k + 8)), cy + along(ry, sin32(k)))
    };
    for k in 0..32u32 {
        f(gouraud(
            [(cx, cy), rim(k), rim(k + 1)],
            [
                Rgb565::WHITE,
                color(hash(k as i32, 0, 3)),
                color(hash(k as i32 + 1, 0, 3)),
            ],
        ));
    }

    // 3. A thin band across the screen whose vertices sit at the ends of the Coord range.
    f(gouraud(
        [(i32::MIN, fy(75)), (i32::MAX, fy(80)), (i32::MIN, fy(85))],
        [
            Rgb565::new(31, 0, 0),
            Rgb565::new(0, 63, 0),
            Rgb565::new(0, 0, 31),
        ],
    ));

    // 4. Big triangles crossing the borders, off-screen and degenerate ones.
    f(gouraud(
        [
            (fx(-200), fy(90)),
            (fx(45), fy(190)),
            (fx(30) + 13, fy(70) + 201),
        ],
        [Rgb565::CYAN, Rgb565::MAGENTA, Rgb565::YELLOW],
    ));
    f(gouraud(
        [
            (fx(85) + 99, -50_000 * 256),
            (fx(160), fy(50)),
            (fx(90), fy(55) + 31),
        ],
        [
            Rgb565::new(31, 63, 0),
            Rgb565::new(0, 20, 31),
            Rgb565::new(10, 0, 5),
        ],
    ));
    f(gouraud(
        [
            (fx(-20), fy(-30)),
            (fx(35) + 5, fy(-10)),
            (fx(5), fy(40) + 250),
        ],
        [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE],
    ));
    f(solid(
        [
            (fx(60) + 77, fy(70)),
            (fx(130), fy(120)),
            (fx(70), fy(150) + 3),
        ],
        Rgb565::new(25, 50, 3),
    ));
    f(solid(
        [(fx(-300), fy(10)), (fx(-100), fy(20)), (fx(-200), fy(90))],
        Rgb565::WHITE,
    ));
    f(gouraud(
        [(fx(10), fy(10)), (fx(50), fy(50)), (fx(90), fy(90))],
        [Rgb565::WHITE; 3],
    ));

    // 5. Rectangles with corners on pixel centres, split along either diagonal: horizontal and
    //    vertical edges through centres (top-left rule ties), and shared diagonals.
    for k in 0..4 {
        let (x0, y0) = ((10 + 7 * k) * 256 + 128, fy(60) / 256 * 256 + 128);
        let (x1, y1) = (x0 + (3 + k) * 256, y0 + (6 - k) * 256);
        let (c1, c2) = (color(hash(k, 11, 1)), color(hash(k, 11, 2)));
        if k % 2 == 0 {
            f(solid([(x0, y0), (x1, y0), (x1, y1)], c1));
            f(solid([(x0, y0), (x1, y1), (x0, y1)], c2));
        } else {
            f(solid([(x0, y1), (x0, y0), (x1, y0)], c1));
            f(solid([(x1, y0), (x1, y1), (x0, y1)], c2));
        }
    }

    // 6. Sub-pixel slivers and tiny triangles along the top and left.
    for k in 0..16 {
        let x = fx(4) + k * w / 17 + (hash(k, 9, 4) % 256) as i32;
        let y = fy(3) + (hash(k, 9, 5) % 512) as i32;
        let size = 64 + k * 48; // 0.25 to 3 pixels
        f(gouraud(
            [(x, y), (x + size, y + size / 3), (x + size / 4, y + size)],
            [
                color(hash(k, 9, 6)),
                color(hash(k, 9, 7)),
                color(hash(k, 9, 8)),
            ],
        ));
        let (x, y) = (
            fx(2) + (hash(k, 10, 4) % 200) as i32,
            y + fy(5) + k * h / 20,
        );
        f(solid(
            [(x, y), (x + size / 2, y + 11), (x + 29, y + size)],
            color(hash(k, 10, 6)),
        ));
    }

    // 7. Small triangles (boxes up to 16 px), most across a border, at sub-pixel positions: thin
    //    slivers, pixel-centre corners (fill-rule ties), sizes from a fraction of a pixel up,
    //    and a few whose coordinates are near the ends of the range.
    for k in 0..96 {
        let r = |s: u32| hash(k, 12, s);
        // Most across a border: the first or last 12 px of an axis, or 12 px beyond it.
        let near = |n: i32, s: u32| {
            let along = (r(s) % (24 * 256)) as i32 - 12 * 256;
            match r(s + 20) % 3 {
                0 => along,
                1 => n + along,
                _ => r(s + 40).checked_rem(n as u32).unwrap_or(0) as i32,
            }
        };
        let (mut x, mut y) = (near(w, 1), near(h, 2));
        if k % 8 == 7 {
            (x, y) = (i32::MAX - 5000 - (r(1) % 4096) as i32, y);
        } else if k % 8 == 6 {
            (x, y) = (x, i32::MIN + 5000 + (r(2) % 4096) as i32);
        }
        let size = (((r(3) % 4095) as i32 + 1) >> (r(4) % 4)).max(1);
        let corner = |s: u32| {
            // (`checked_rem`: no division-by-zero panic path in the firmware that proves there
            // is none.)
            let within = |v: u32| v.checked_rem(size as u32).unwrap_or(0) as i32;
            let (dx, dy) = (within(r(s)), within(r(s + 1)));
            if k % 5 == 1 {
                ((x + dx) & !255 | 128, (y + dy) & !255 | 128)
            } else {
                (x + dx, y + dy)
            }
        };
        let (a, b) = (corner(5), corner(7));
        let c = if k % 6 == 2 {
            // Nearly on the line through the other two.
            (
                b.0 + (b.0 - a.0) / 2 + (r(9) % 3) as i32 - 1,
                b.1 + (b.1 - a.1) / 2,
            )
        } else {
            corner(9)
        };
        // Twice, so that each is drawn by both `draw` and `draw_into` (`render_opaque`
        // alternates them), the same pixels.
        for _ in 0..2 {
            f(gouraud(
                [a, b, c],
                [color(r(11)), color(r(12)), color(r(13))],
            ));
        }
    }
}

/// Solid triangles at an opacity, drawn over the finished opaque scene ([`render`]): one
/// crossing the left and bottom borders, a big one over most of the screen, a thin sliver and a
/// small one at the highest opacity short of opaque, so that spans of every length start and
/// end at both pixel parities of the 5-6-5 blend loops' words.
pub fn translucent_shapes(width: u32, height: u32) -> [(SolidTriangle<Rgb565>, u8); 4] {
    let w = (width.min(4096) as i32) * 256;
    let h = (height.min(4096) as i32) * 256;
    let fx = |n: i32| w / 100 * n;
    let fy = |n: i32| h / 100 * n;
    let tri = |p: [(i32, i32); 3], color: Rgb565, alpha: u8| {
        (
            SolidTriangle::new(p.map(|(x, y)| (c(x), c(y))), color),
            alpha,
        )
    };
    [
        tri(
            [(fx(-20), fy(30)), (fx(55) + 41, fy(70)), (fx(10), fy(130))],
            Rgb565::new(31, 10, 3),
            77,
        ),
        tri(
            [(fx(8) + 3, fy(6)), (fx(93), fy(20) + 101), (fx(40), fy(95))],
            Rgb565::new(4, 60, 25),
            200,
        ),
        tri(
            [
                (fx(20), fy(50)),
                (fx(90) + 17, fy(52)),
                (fx(20) + 60, fy(56)),
            ],
            Rgb565::WHITE,
            1,
        ),
        tri(
            [
                (fx(70), fy(10) + 33),
                (fx(85) + 9, fy(25)),
                (fx(66), fy(40)),
            ],
            Rgb565::new(0, 0, 31),
            254,
        ),
    ]
}

/// Clears `fb` and draws the scene: the opaque shapes ([`render_opaque`]), then the translucent
/// ones ([`render_translucent`]).
pub fn render(fb: &mut SliceFramebuffer<'_, Rgb565>) {
    render_opaque(fb);
    render_translucent(fb);
    render_antialiased(fb);
    render_dithered(fb);
}

/// Gouraud triangles ordered-dithered ([`render_dithered`]): one over most of the screen, one
/// across the left and bottom borders, a sliver, a small one and one whose channels run from 0
/// to their maximum (the lanes' margins), at sub-pixel positions, so that spans of every length
/// start at every column of the Bayer matrix and both pixel parities.
pub fn dithered_shapes(width: u32, height: u32) -> [GouraudTriangle<Rgb565>; 5] {
    let w = (width.min(4096) as i32) * 256;
    let h = (height.min(4096) as i32) * 256;
    let tri = gouraud_triangle;
    [
        tri(
            [
                (w / 20 + 7, h / 12),
                (w - w / 15, h / 3 + 51),
                (w / 4 + 3, h - h / 10),
            ],
            [
                Rgb565::new(31, 5, 0),
                Rgb565::new(3, 63, 12),
                Rgb565::new(12, 0, 31),
            ],
        ),
        tri(
            [
                (-w / 5, h / 2 + 19),
                (w / 2 + 101, h - h / 6),
                (w / 8, h + h / 4),
            ],
            [
                Rgb565::new(0, 0, 0),
                Rgb565::new(31, 63, 31),
                Rgb565::new(16, 32, 16),
            ],
        ),
        tri(
            [
                (w / 10 + 33, h / 2),
                (w - w / 10, h / 2 + 200),
                (w / 10, h / 2 + 420),
            ],
            [
                Rgb565::new(7, 20, 30),
                Rgb565::new(29, 41, 2),
                Rgb565::new(15, 60, 9),
            ],
        ),
        tri(
            [
                (w / 2 + 60, h / 5 + 90),
                (w / 2 + 2100, h / 5 + 700),
                (w / 2 + 500, h / 5 + 2600),
            ],
            [
                Rgb565::new(31, 63, 31),
                Rgb565::new(30, 62, 30),
                Rgb565::new(31, 63, 0),
            ],
        ),
        tri(
            [
                (w / 3 + 5, h / 20),
                (w - 3, h / 20 + 77),
                (w - w / 4, h / 2 + 9),
            ],
            [
                Rgb565::new(0, 63, 0),
                Rgb565::new(31, 0, 31),
                Rgb565::new(0, 0, 0),
            ],
        ),
    ]
}

/// Draws the [`dithered_shapes`] over `fb`, alternating `Drawable::draw` and `draw_into`.
pub fn render_dithered(fb: &mut SliceFramebuffer<'_, Rgb565>) {
    let size = fb.size();
    for (k, t) in dithered_shapes(size.width, size.height)
        .into_iter()
        .enumerate()
    {
        let t = core::hint::black_box(t).dithered();
        if k % 2 == 0 {
            let _ = t.draw(fb);
        } else {
            t.draw_into(fb);
        }
    }
}

/// Anti-aliased triangles drawn last ([`render_antialiased`]), with their opacities: one crossing
/// the right border, a sub-pixel one, a sliver at half opacity and one far beyond the screen
/// (the `i64` and `i128` paths, rows stepped and scanned).
pub fn antialiased_shapes(width: u32, height: u32) -> [(SolidTriangle<Rgb565>, u8); 4] {
    let w = (width.min(4096) as i32) * 256;
    let h = (height.min(4096) as i32) * 256;
    let tri = |p: [(i32, i32); 3], color: Rgb565, opacity: u8| {
        (
            SolidTriangle::new(p.map(|(x, y)| (c(x), c(y))), color),
            opacity,
        )
    };
    [
        tri(
            [
                (w / 2 + 77, h / 9),
                (w + w / 5, h / 2 + 13),
                (w / 3 + 5, h - h / 8),
            ],
            Rgb565::new(30, 58, 6),
            255,
        ),
        tri(
            [
                (w / 5 + 21, h / 3 + 40),
                (w / 5 + 190, h / 3 + 77),
                (w / 5 + 60, h / 3 + 230),
            ],
            Rgb565::WHITE,
            255,
        ),
        tri(
            [
                (w / 10, h / 2),
                (w - w / 10, h / 2 + 300),
                (w / 10 + 40, h / 2 + 700),
            ],
            Rgb565::new(0, 20, 31),
            128,
        ),
        tri(
            [
                (-2_000_000_000, h / 4),
                (w / 2, -1_900_000_000),
                (w / 3, h / 5 + 3),
            ],
            Rgb565::new(31, 0, 20),
            200,
        ),
    ]
}

/// The corners of a small quadrilateral anti-aliased as one shape ([`render_antialiased`]'s coverage mask,
/// over the 24 × 16 pixels from (4, 4)).
pub const MASK_FAN: [(i32, i32); 4] = [(1100, 1090), (1500, 1900), (5700, 2300), (2000, 4900)];

/// Blends the [`antialiased_shapes`] into `fb` (`anti_aliased().with_opacity(..).draw_into`),
/// then the quadrilateral [`MASK_FAN`] (two triangles around its first corner) through a
/// coverage mask.
pub fn render_antialiased(fb: &mut SliceFramebuffer<'_, Rgb565>) {
    let size = fb.size();
    for (t, opacity) in antialiased_shapes(size.width, size.height) {
        let (t, opacity) = core::hint::black_box((t, opacity));
        t.anti_aliased().with_opacity(opacity).draw_into(fb);
    }
    render_antialiased_mask(fb);
}

/// The colour of the [`MASK_FAN`] quadrilateral.
pub const MASK_COLOR: Rgb565 = Rgb565::new(31, 40, 0);

/// The [`MASK_FAN`] quadrilateral through a coverage mask (the end of [`render_antialiased`]).
pub fn render_antialiased_mask(fb: &mut SliceFramebuffer<'_, Rgb565>) {
    let mut cells = [0u16; 24 * 16];
    let area = embedded_graphics::primitives::Rectangle::new(Point::new(4, 4), Size::new(24, 16));
    if let Ok(mut mask) = CoverageMask::new(&mut cells, area) {
        for k in 1..MASK_FAN.len() - 1 {
            let p = [MASK_FAN[0], MASK_FAN[k], MASK_FAN[k + 1]];
            mask.add(core::hint::black_box(p.map(|(x, y)| (c(x), c(y)))));
        }
        mask.fill_into(MASK_COLOR, fb);
    }
}

/// Blends the [`translucent_shapes`] into `fb` (`draw_into`).
pub fn render_translucent(fb: &mut SliceFramebuffer<'_, Rgb565>) {
    let size = fb.size();
    for (t, alpha) in translucent_shapes(size.width, size.height) {
        let (t, alpha) = core::hint::black_box((t, alpha));
        t.with_opacity(alpha).draw_into(fb);
    }
}

/// Clears `fb` and draws the opaque shapes, alternating `Drawable::draw` and `draw_into`, then
/// blends the triangle with an alpha per vertex ([`translucent`]) over them.
pub fn render_opaque(fb: &mut SliceFramebuffer<'_, Rgb565>) {
    let size = fb.size();
    let _ = fb.clear(BACKGROUND);
    let mut n = 0u32;
    for_each_shape(size.width, size.height, |shape| {
        // Opaque to the optimiser: the firmware runs the general drawing code, not a version
        // specialised to these constants (and fw_nopanic proves that code panic-free).
        match (core::hint::black_box(shape), n % 2) {
            (Shape::Gouraud(t), 0) => {
                let _ = t.draw(fb);
            }
            (Shape::Gouraud(t), _) => t.draw_into(fb),
            (Shape::Solid(t), 0) => {
                let _ = t.draw(fb);
            }
            (Shape::Solid(t), _) => t.draw_into(fb),
        }
        n = n.wrapping_add(1);
    });
    core::hint::black_box(translucent(size.width, size.height)).draw_into(fb);
}

/// The triangle [`render_opaque`] blends over its shapes: an alpha per vertex, opaque to
/// transparent.
pub fn translucent(width: u32, height: u32) -> Translucent<GouraudTriangle<Rgb565>> {
    let (w, h) = (width.min(4096) as i32 * 256, height.min(4096) as i32 * 256);
    GouraudTriangle::new([
        v(w / 9 + 37, h / 7, Rgb565::new(31, 10, 3)),
        v(w / 9 * 8, h / 3 + 101, Rgb565::new(2, 60, 9)),
        v(w / 3, h / 7 * 6 + 13, Rgb565::new(20, 5, 30)),
    ])
    .with_alpha([255, 128, 0])
}

/// How many random spans [`dithered_spans`] draws.
pub const DITHERED_SPANS: u32 = 3000;

/// Random ordered-dithered spans drawn straight through `GouraudColor::fill_dithered`: into the
/// rows of `fb` (Rgb565) and into a row of Bgr565 (the other channel order), every Bayer phase,
/// positions anywhere in `i32`. Their channels start and end near the limits a target's packed
/// loop takes a span within (31/64 LSB and the maximum plus 33/64, give or take 1/64 to 1), across
/// them, anywhere inside, or anywhere at all, with flat, steep and wrapping steps: the spans a
/// packed loop must hand to the clamped definition and those it must draw itself. Returns the
/// FNV-1a of the framebuffer's pixels after them and of each Bgr565 row: a board's must be the
/// host's (the portable definition, which the crate's tests check against an independent one).
pub fn dithered_spans(fb: &mut SliceFramebuffer<'_, Rgb565>) -> u32 {
    use embedded_graphics::pixelcolor::Bgr565;
    use embedded_raster::color::STEP_BITS;
    use embedded_raster::GouraudColor;

    let size = fb.size();
    let (width, height) = (
        size.width.clamp(1, 64) as usize,
        size.height.max(1) as usize,
    );
    let one = 1i64 << STEP_BITS;
    let mut sum = FNV_START;
    let mut row = [Bgr565::new(0, 0, 0); 64];
    for i in 0..DITHERED_SPANS {
        let h = |k: u32| hash(i as i32, k as i32, 0x7f4a_7c15);
        let len = 1 + (h(0) as usize % width);
        // A channel's value near a limit, inside, or anything; `max` in its own depth.
        let value = |k: u32, max: i64| -> i64 {
            // Within 1, 1/4, 1/16 or 1/64 LSB of the limit.
            let reach = one >> (2 * (h(k) % 4));
            let near = i64::from(h(k) >> 1) % (2 * reach) - reach;
            match h(k + 1) % 6 {
                0 | 1 => one * 31 / 64 + near,
                2 | 3 => (max * 64 + 33) * one / 64 + near,
                4 => i64::from(h(k + 2)) % ((max + 1) * one),
                _ => i64::from(h(k + 2) as i32),
            }
        };
        let max = [31, 63, 31];
        let mut start = [0u32; 3];
        let mut step = [0u32; 3];
        for c in 0..3 {
            let first = value(8 * c as u32 + 1, max[c]);
            start[c] = first as u32;
            step[c] = match h(8 * c as u32 + 4) % 5 {
                0 => 0,
                1 => h(8 * c as u32 + 5),
                // Towards a chosen end at the span's last pixel.
                _ => {
                    let last = value(8 * c as u32 + 5, max[c]);
                    ((last - first) / (len as i64 - 1).max(1)) as u32
                }
            };
        }
        let (x, y) = (h(30) as i32 >> (h(31) % 32), h(32) as i32 >> (h(33) % 32));
        if i % 4 == 3 {
            let steps = Bgr565::prepare_steps(step);
            Bgr565::fill_dithered(&mut row[..len], x, y, start, &steps);
            sum = fnv(
                sum,
                row[..len].iter().map(|&p| RawU16::from(p).into_inner()),
            );
        } else {
            let steps = Rgb565::prepare_steps(step);
            let at = (i as usize % height) * size.width as usize;
            if let Some(pixels) = fb.pixels_mut().get_mut(at..at + len) {
                Rgb565::fill_dithered(pixels, x, y, start, &steps);
            }
        }
    }
    fnv(
        sum,
        fb.pixels().iter().map(|&p| RawU16::from(p).into_inner()),
    )
}

/// 32-bit FNV-1a over the raw pixels, each as two little-endian bytes.
pub fn checksum(pixels: &[Rgb565]) -> u32 {
    fnv(
        FNV_START,
        pixels.iter().map(|&p| RawU16::from(p).into_inner()),
    )
}

/// The line the firmware prints and the host build of `fw_scene` reproduces.
pub struct ChecksumLine {
    /// Framebuffer width.
    pub width: u32,
    /// Framebuffer height.
    pub height: u32,
    /// [`checksum`] of the rendered pixels.
    pub checksum: u32,
}

impl core::fmt::Display for ChecksumLine {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "scene {}x{} fnv1a={:#010x}",
            self.width, self.height, self.checksum
        )
    }
}
