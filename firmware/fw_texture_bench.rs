//! Firmware benchmark of textured triangles: instructions per covered pixel on large triangles,
//! counted by SysTick (or `minstret`) under QEMU's `-icount` (see `fw_bench`), for each texturing path.
//!
//! ```text
//! cargo run --release --target thumbv7em-none-eabihf --example fw_texture_bench   # mps2-an386
//! cargo run --release --target thumbv6m-none-eabi    --example fw_texture_bench   # micro:bit
//! ```
//!
//! The texture is 64 × 64 Rgb565 in flash (a power of two, repeating: the masked loop) or the
//! same texels as a 4-bit palette texture; the triangles are `fw_bench`'s large set, each
//! covering the texture a few times. 2D cases draw into a `SliceFramebuffer` (`draw_into`, and
//! `Drawable::draw` through the generic `DrawTarget` path); 3D cases are the perspective-correct,
//! depth-tested fill (`draw_textured`) with the far vertices three times as deep as the near
//! one, every pixel passing the depth test (each pass nearer than the last).
//!
//! After each case, and after untimed drawings of random textured triangles ([`check`],
//! [`check_3d`]), the firmware prints a checksum line of the framebuffer (`texture <w>x<h>
//! <what> fnv1a=…`), and one of random small 3D faces ([`check_faces`]: the ARMv7-M set-up of
//! a small textured face against the portable one); the host build prints the same lines for
//! both sizes, and `.ci/firmware.sh` compares them (the Cortex-M0 has a span loop of its own).
#![cfg_attr(target_os = "none", no_std, no_main)]

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::texture::{Filter, Indexed4, Rgb565Texels, TexelCoord, TexelSource, Texture};
use embedded_raster::three_d::TexturedScreenVertex;
use embedded_raster::three_d::{
    draw_textured, draw_textured_lit, DepthTarget, Scalar, ScreenVertex,
};
use embedded_raster::{Coord, SliceFramebuffer, SolidTriangle, TexturedTriangle, TexturedVertex};

#[allow(dead_code)]
#[path = "../examples/common/scene.rs"]
mod scene;

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/board.rs"]
mod board;

#[cfg(target_os = "none")]
#[path = "common/report_panic.rs"]
mod report_panic;

#[cfg(target_os = "none")]
#[path = "common/clock.rs"]
mod clock;

/// Texture side.
const SIDE: usize = 64;

/// A 64 × 64 Rgb565 pattern of 16 colours (so that the palette form holds the same texels).
const fn palette_index(x: usize, y: usize) -> u8 {
    (((x / 8) ^ (y / 4) ^ (x * y / 64)) & 15) as u8
}

const fn palette_color(i: u8) -> u16 {
    let i = i as u16;
    ((i * 2) << 11) | ((63 - i * 3) << 5) | (31 - i)
}

static TEXELS: [u16; SIDE * SIDE] = {
    let mut t = [0; SIDE * SIDE];
    let mut i = 0;
    while i < SIDE * SIDE {
        t[i] = palette_color(palette_index(i % SIDE, i / SIDE));
        i += 1;
    }
    t
};

static INDICES: [u8; SIDE * SIDE / 2] = {
    let mut t = [0; SIDE * SIDE / 2];
    let mut i = 0;
    while i < SIDE * SIDE / 2 {
        let (x, y) = ((2 * i) % SIDE, (2 * i) / SIDE);
        t[i] = (palette_index(x, y) << 4) | palette_index(x + 1, y);
        i += 1;
    }
    t
};

static PALETTE: [Rgb565; 16] = {
    let mut p = [Rgb565::new(0, 0, 0); 16];
    let mut i = 0;
    while i < 16 {
        let c = palette_color(i as u8);
        p[i] = Rgb565::new((c >> 11) as u8, ((c >> 5) & 63) as u8, (c & 31) as u8);
        i += 1;
    }
    p
};

/// The texturing paths compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Case {
    AffineNearestInto,
    AffineNearestIndexed4Into,
    AffineBilinearInto,
    AffineNearestDraw,
    PerspectiveNearest,
    PerspectiveBilinear,
    PerspectiveNearestLit,
}

const CASES: [Case; 7] = [
    Case::AffineNearestInto,
    Case::AffineNearestIndexed4Into,
    Case::AffineBilinearInto,
    Case::AffineNearestDraw,
    Case::PerspectiveNearest,
    Case::PerspectiveBilinear,
    Case::PerspectiveNearestLit,
];

impl Case {
    fn name(self) -> &'static str {
        match self {
            Case::AffineNearestInto => "TexturedTriangle::draw_into nearest",
            Case::AffineNearestIndexed4Into => "TexturedTriangle::draw_into nearest, 4-bit palette",
            Case::AffineBilinearInto => "TexturedTriangle::draw_into bilinear",
            Case::AffineNearestDraw => "TexturedTriangle::draw nearest",
            Case::PerspectiveNearest => "draw_textured perspective nearest",
            Case::PerspectiveBilinear => "draw_textured perspective bilinear",
            Case::PerspectiveNearestLit => {
                "draw_textured_lit perspective nearest (texture × Gouraud)"
            }
        }
    }
}

/// Texel coordinates of corner `(x, y)` (pixels): the texture about twice across the screen's
/// width, sheared a little.
fn texel_at(x: i32, y: i32) -> (TexelCoord, TexelCoord) {
    (
        TexelCoord::from_bits((x * 3 + y) << 15),
        TexelCoord::from_bits((y * 3 - x / 2) << 15),
    )
}

/// The large set's triangle `k` as a 2D textured triangle's vertices.
fn vertices_2d(corners: &[(i32, i32); 3]) -> [TexturedVertex; 3] {
    corners.map(|(x, y)| {
        let (u, v) = texel_at(x, y);
        TexturedVertex {
            x: Coord::from_bits(x * 256 + 128),
            y: Coord::from_bits(y * 256 + 128),
            u,
            v,
        }
    })
}

/// The same as 3D vertices at `depth`, `w` growing with x (the far side three times as deep).
fn vertices_3d(corners: &[(i32, i32); 3], width: i32, depth: u16) -> [TexturedScreenVertex; 3] {
    corners.map(|(x, y)| {
        let (u, v) = texel_at(x, y);
        TexturedScreenVertex {
            screen: ScreenVertex::new(
                Coord::from_bits(x * 256 + 128),
                Coord::from_bits(y * 256 + 128),
                depth,
            ),
            w: Scalar::from_bits((1 << 16) + ((x << 17) / width.max(1))),
            u,
            v,
        }
    })
}

/// A xorshift32 generator from `seed` (not 0): the checks' random inputs, the same on every
/// board and the host.
fn xorshift(mut state: u32) -> impl FnMut() -> u32 {
    move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state
    }
}

/// Random triangles for [`check`].
const CHECK_TRIANGLES: u32 = 300;

/// Untimed: [`CHECK_TRIANGLES`] random triangles over and around the screen with random texel
/// coordinates (spreads from a fraction of a texel to 2¹⁵ texels, anywhere in the range), nearest
/// and bilinear (every other one), from the texels as textures of several power-of-two shapes, drawn into the framebuffer (which
/// the caller clears). Out of line: its frame is not `main`'s, under [`check_3d`]'s deep draws
/// (a micro:bit's stack is 4 KB).
#[inline(never)]
fn check(fb: &mut SliceFramebuffer<'_, Rgb565>) {
    let (w, h) = (fb.size().width as i32, fb.size().height as i32);
    let mut next = xorshift(0x2545_f491_u32);
    let shapes = [(64, 64), (256, 16), (1, 4096), (8, 2), (16, 256)];
    for k in 0..CHECK_TRIANGLES {
        let (tw, th) = shapes[(k % shapes.len() as u32) as usize];
        let Ok(texture) = Texture::new(Rgb565Texels(&TEXELS), tw, th) else {
            return;
        };
        // Every other one bilinear (ARMv7E-M's span loop blends them).
        let texture = match k % 2 {
            0 => texture,
            _ => texture.with_filter(Filter::Bilinear),
        };
        let (base_u, base_v) = (next() as i32, next() as i32);
        let spread = 8 + next() % 24;
        let mut vertex = || {
            // Sub-pixel positions from half a screen before to half a screen past it.
            let x = (next() % (w as u32 * 512)) as i32 - w * 128;
            let y = (next() % (h as u32 * 512)) as i32 - h * 128;
            let u = base_u.wrapping_add(next() as i32 >> spread);
            let v = base_v.wrapping_add(next() as i32 >> spread);
            TexturedVertex {
                x: Coord::from_bits(x),
                y: Coord::from_bits(y),
                u: TexelCoord::from_bits(u),
                v: TexelCoord::from_bits(v),
            }
        };
        let vertices = [vertex(), vertex(), vertex()];
        TexturedTriangle::new(vertices, &texture).draw_into(fb);
    }
}

/// Three random light levels for the checks, a third of them 0 and a third 255.
fn random_levels(next: &mut impl FnMut() -> u32) -> [u8; 3] {
    let mut level = || match next() % 3 {
        0 => 0,
        1 => 255,
        _ => (next() >> 24) as u8,
    };
    [level(), level(), level()]
}

/// Untimed: [`CHECK_TRIANGLES`] random perspective-correct textured triangles over and around
/// the screen — `w` ratios up to 1:20 within a triangle, random depths, texel coordinates and
/// light levels (often 0 or 255), unlit and lit, nearest and bilinear, from the texels as textures of several power-of-two
/// shapes (and one that is not) — drawn into the depth target (which the caller clears):
/// the spans' chunks of every length, clipped at every edge, levels at the clamp. Out of line:
/// its frame is not added to the firmware's `main` (the micro:bit's 4 KB of stack).
#[inline(never)]
fn check_3d(fb: &mut DepthTarget<'_, Rgb565>) {
    let size = fb.framebuffer().size();
    let clip = Rectangle::new(Point::zero(), size);
    let (w, h) = (size.width as i32, size.height as i32);
    let mut next = xorshift(0x9e37_79b9_u32);
    let shapes = [(64, 64), (256, 16), (1, 4096), (8, 2), (16, 256), (48, 64)];
    for k in 0..CHECK_TRIANGLES {
        let (tw, th) = shapes[(k % shapes.len() as u32) as usize];
        let Ok(texture) = Texture::new(Rgb565Texels(&TEXELS), tw, th) else {
            return;
        };
        // Half of each of the unlit and the lit ones bilinear (ARMv7E-M's span loop blends
        // them, lit by the level before one rounding).
        let texture = match k / 2 % 2 {
            0 => texture,
            _ => texture.with_filter(Filter::Bilinear),
        };
        let (base_u, base_v) = (next() as i32, next() as i32);
        let spread = 10 + next() % 20;
        let mut vertex = || {
            let x = (next() % (w as u32 * 512)) as i32 - w * 128;
            let y = (next() % (h as u32 * 512)) as i32 - h * 128;
            // w from 1/2 to 10 (16.16).
            let depth_w = (1 << 15) + (next() % (19 << 15)) as i32;
            TexturedScreenVertex {
                screen: ScreenVertex::new(
                    Coord::from_bits(x),
                    Coord::from_bits(y),
                    (next() % 60_000) as u16,
                ),
                w: Scalar::from_bits(depth_w),
                u: TexelCoord::from_bits(base_u.wrapping_add(next() as i32 >> spread)),
                v: TexelCoord::from_bits(base_v.wrapping_add(next() as i32 >> spread)),
            }
        };
        let v = [vertex(), vertex(), vertex()];
        if k % 2 == 0 {
            draw_3d(fb, &clip, &v, &texture, None);
        } else {
            // Levels at the ends of the range too: a level stepped down to 0 or up to 255
            // passes them between two chunk ends (the loops' clamp).
            draw_3d(fb, &clip, &v, &texture, Some(random_levels(&mut next)));
        }
    }
}

/// Faces [`check_faces`] draws (each into a cell of its own, a batch of cells a frame): enough
/// that a texel step one unit of 2⁻¹⁶ texel off shows (fewer faces missed it).
const CHECK_FACES: u32 = 50_000;

/// A cell's side in pixels: more than a small face's box (16 px) and a pixel.
const CELL: i32 = 20;

/// `i` hashed by two multiply-xorshift rounds with the odd multipliers `m` and the shifts `s`.
const fn mix(i: usize, m: [u32; 2], s: [u32; 2]) -> u32 {
    let mut x = (i as u32).wrapping_mul(m[0]);
    x ^= x >> s[0];
    x = x.wrapping_mul(m[1]);
    x ^ (x >> s[1])
}

/// 64 × 64 hashed 4-bit palette indices for [`check_faces`], two a byte.
#[cfg(not(armv6m))]
static NOISE_INDICES: [u8; SIDE * SIDE / 2] = {
    let mut indices = [0; SIDE * SIDE / 2];
    let mut i = 0;
    while i < indices.len() {
        indices[i] = mix(i, [0x2c1b_3c6d, 0x297a_2d39], [12, 15]) as u8;
        i += 1;
    }
    indices
};

/// 64 × 64 texels of hashed colours for [`check_faces`]: neighbours differ (a coordinate a unit
/// off at a texel's edge shows).
static NOISE: [u16; SIDE * SIDE] = {
    let mut texels = [0; SIDE * SIDE];
    let mut i = 0;
    while i < texels.len() {
        texels[i] = mix(i, [0x9e37_79b1, 0x85eb_ca6b], [15, 13]) as u16;
        i += 1;
    }
    texels
};

/// A random spread of texel coordinates (16.16) for [`check_faces`]: anywhere in the range, at
/// the texel maps' limits (`0xff00 · 2ᵏ` and `2¹⁶ · 2ᵏ`, give or take a few units), or below
/// a texel.
fn spread(next: &mut impl FnMut() -> u32) -> i32 {
    match next() % 5 {
        0 | 1 => (next() >> (next() % 32)) as i32,
        2 => (0xff00_i32 << (next() % 15)).wrapping_add((next() % 7) as i32 - 3),
        3 => (1_i32 << (16 + next() % 15)).wrapping_add((next() % 7) as i32 - 3),
        _ => (next() % 0x1_0000) as i32,
    }
}

/// Untimed: [`CHECK_FACES`] random small depth-tested textured faces, nearest, bilinear and
/// from 4-bit palette indices, unlit and lit,
/// from hashed texels ([`NOISE`]) as textures of several shapes (power-of-two ones and one that is not), each
/// into a cell of its own, clipped by the cell or less of it and by the screen's edges (the
/// cells overhang them). Their boxes reach and pass the small set-up's 4096 sub-pixels, some
/// are slivers; their `w` are equal, nearly equal or up to 2¹⁰ apart, and their texel
/// coordinates spread from below a texel to the whole range, many at the texel maps' limits:
/// faces on both sides of the screen-space bound and of each limit of the target's own
/// small-face set-up (`arch::textured_face` on ARMv7-M), whose pixels and depths must be the
/// portable code's. Returns the FNV-1a of each batch's colour and depth checksums.
#[inline(never)]
fn check_faces(fb: &mut DepthTarget<'_, Rgb565>) -> u32 {
    let size = fb.framebuffer().size();
    let (w, h) = (size.width as i32, size.height as i32);
    // Cells from half a cell before the screen to past its end.
    let (columns, rows) = ((w + CELL) / CELL + 1, (h + CELL) / CELL + 1);
    let mut next = xorshift(0x3c6e_f372_u32);
    let shapes = [(64, 64), (256, 16), (1, 4096), (8, 2), (16, 256), (48, 64)];
    let mut sum = scene::FNV_START;
    let mut drawn = 0;
    while drawn < CHECK_FACES {
        fb.clear(Rgb565::new(0, 0, 0));
        for cell in 0..(columns * rows) as u32 {
            if drawn == CHECK_FACES {
                break;
            }
            drawn += 1;
            let (tw, th) = shapes[(next() % shapes.len() as u32) as usize];
            // A quarter bilinear (ARMv7E-M's row loop blends them), a quarter 4-bit palette
            // indices (ARMv7-M's looks them up; a palette of 11 colours in a quarter of those;
            // raw Rgb565 words on the micro:bit's 64 × 48, whose flash has no room for a fill
            // of another texel source), the rest raw Rgb565 words.
            let (kind, short) = (next() % 4, next() % 4 == 0);
            let Ok(texture) = Texture::new(Rgb565Texels(&NOISE), tw, th) else {
                return 0;
            };
            let texture = match kind {
                0 => texture.with_filter(Filter::Bilinear),
                _ => texture,
            };
            let (cx, cy) = (
                (cell as i32 % columns) * CELL - CELL / 2,
                (cell as i32 / columns) * CELL - CELL / 2,
            );
            // The box: up to 4200 sub-pixels a side, many at the small set-up's limit (4096).
            let mut side = || match next() % 8 {
                0 | 1 => 4094 + (next() % 4) as i32,
                2 => (next() % 256) as i32,
                _ => 1024 + (next() % 3176) as i32,
            };
            let (sx, sy) = (side(), side());
            let mut room = |s: i32| (next() % ((CELL << 8) - s) as u32) as i32;
            let (ox, oy) = ((cx << 8) + room(sx), (cy << 8) + room(sy));
            // Which vertex is at each end of the box, on each axis.
            let (ax, ay) = ((next() % 3) as usize, (next() % 3) as usize);
            let mut xs = [ox, ox + sx, ox + (next() % (sx as u32 + 1)) as i32];
            let mut ys = [oy, oy + sy, oy + (next() % (sy as u32 + 1)) as i32];
            xs.rotate_left(ax);
            ys.rotate_left(ay);
            if next() % 8 == 0 {
                // A sliver: the third vertex on the line through the others, give or take.
                xs[2] = (xs[0] + xs[1]) / 2 + (next() % 3) as i32 - 1;
                ys[2] = (ys[0] + ys[1]) / 2 + (next() % 3) as i32 - 1;
            }
            let base_w = (1 << 15) + (next() % (19 << 15)) as i32;
            let w_mode = next() % 4;
            let (base_u, base_v) = (next() as i32, next() as i32);
            let (spread_u, spread_v) = (spread(&mut next), spread(&mut next));
            let base_z = 1000 + next() % 59_000;
            let z_spread = 1 + next() % 4000;
            let vertex = |i: usize, next: &mut dyn FnMut() -> u32| {
                let w = match w_mode {
                    0 | 1 => base_w,
                    2 => base_w + (next() % (base_w as u32 >> 8).max(1)) as i32,
                    // Up to 2¹⁰ apart: past the common scale's 2⁸.
                    _ => ((1 << 14) + (next() % (1 << 16)) as i32) << (next() % 11),
                };
                // u and v: the base, one spread from it, or between.
                let part = |spread: i32, next: &mut dyn FnMut() -> u32| match i {
                    0 => 0,
                    1 => spread,
                    _ => ((i64::from(spread) * i64::from(next() % 257)) >> 8) as i32,
                };
                let z = base_z + next() % z_spread;
                TexturedScreenVertex {
                    screen: ScreenVertex::new(
                        Coord::from_bits(xs[i]),
                        Coord::from_bits(ys[i]),
                        z.min(65_000) as u16,
                    ),
                    w: Scalar::from_bits(w),
                    u: TexelCoord::from_bits(base_u.wrapping_add(part(spread_u, next))),
                    v: TexelCoord::from_bits(base_v.wrapping_add(part(spread_v, next))),
                }
            };
            let v = [
                vertex(0, &mut next),
                vertex(1, &mut next),
                vertex(2, &mut next),
            ];
            // The cell, or less of it.
            let (mut x0, mut y0, mut x1, mut y1) = (cx, cy, cx + CELL, cy + CELL);
            if next() % 3 == 0 {
                x0 += (next() % 9) as i32;
                y0 += (next() % 9) as i32;
                x1 -= (next() % 9) as i32;
                y1 -= (next() % 9) as i32;
            }
            let clip = Rectangle::with_corners(Point::new(x0, y0), Point::new(x1 - 1, y1 - 1));
            let levels = (next() % 2 == 1).then(|| random_levels(&mut next));
            #[cfg(not(armv6m))]
            if kind == 1 && w > 64 {
                let palette: &[Rgb565] = if short { &PALETTE[..11] } else { &PALETTE };
                let indices = Indexed4 {
                    indices: &NOISE_INDICES,
                    palette,
                };
                if let Ok(indexed) = Texture::new(indices, tw, th) {
                    draw_3d(fb, &clip, &v, &indexed, levels);
                }
                continue;
            }
            #[cfg(armv6m)]
            let _ = short;
            draw_3d(fb, &clip, &v, &texture, levels);
        }
        // The batch's colour and depth hashes, their bytes low first.
        let colors = scene::checksum(fb.framebuffer().pixels());
        let depths = scene::fnv(scene::FNV_START, fb.depth().iter().copied());
        let words = [colors, depths].map(|h| [h as u16, (h >> 16) as u16]);
        sum = scene::fnv(sum, words.into_iter().flatten());
    }
    sum
}

/// The checksum line of `what` drawn into `pixels` (`w × h`).
struct CheckLine<'a> {
    size: (u32, u32),
    what: &'a str,
    pixels: &'a [Rgb565],
}

impl core::fmt::Display for CheckLine<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let (w, h, sum) = (self.size.0, self.size.1, scene::checksum(self.pixels));
        write!(f, "texture {w}x{h} {} fnv1a={sum:#010x}", self.what)
    }
}

/// Covered pixels of one pass over the large set on a `w × h` screen (untimed).
fn count_pixels(w: u32, h: u32) -> u32 {
    let mut pixels = 0;
    for corners in scene::large_triangles(w as i32, h as i32) {
        let c = |i: i32| Coord::from_bits(i * 256 + 128);
        let t = SolidTriangle::new(corners.map(|(x, y)| (c(x), c(y))), Rgb565::BLACK);
        for span in t.spans(&Rectangle::new(Point::zero(), Size::new(w, h))) {
            pixels += span.len();
        }
    }
    pixels
}

/// One pass of `case` over the large set (`pass` counts down the depth, so each pass is nearer).
fn run<S: TexelSource>(
    case: Case,
    texture: &Texture<S>,
    fb: &mut DepthTarget<'_, Rgb565>,
    pass: u16,
) where
    Rgb565: From<S::Color>,
{
    let size = fb.framebuffer().size();
    let clip = Rectangle::new(Point::zero(), size);
    for corners in scene::large_triangles(size.width as i32, size.height as i32) {
        match case {
            Case::PerspectiveNearest | Case::PerspectiveBilinear => {
                let v = vertices_3d(&corners, size.width as i32, 60_000 - pass);
                draw_3d(fb, &clip, &v, texture, None);
            }
            Case::PerspectiveNearestLit => {
                let v = vertices_3d(&corners, size.width as i32, 60_000 - pass);
                // Light from 64 to 255 across the screen, and down it.
                let levels = corners.map(|(x, y)| {
                    let (w, h) = (size.width as i32, size.height as i32);
                    (64 + (x * 127 / w.max(1) + y * 64 / h.max(1)).clamp(0, 191)) as u8
                });
                draw_3d(fb, &clip, &v, texture, Some(levels));
            }
            Case::AffineNearestDraw => draw_2d(fb, &vertices_2d(&corners), texture, false),
            _ => draw_2d(fb, &vertices_2d(&corners), texture, true),
        }
    }
}

/// A 2D textured triangle by `draw_into` or `Drawable::draw`. Out of line, as [`draw_3d`]: the
/// micro:bit's 4 KB of stack holds one fill's frame at a time, not all of them.
#[inline(never)]
fn draw_2d<S: TexelSource>(
    fb: &mut DepthTarget<'_, Rgb565>,
    vertices: &[TexturedVertex; 3],
    texture: &Texture<S>,
    into: bool,
) where
    Rgb565: From<S::Color>,
{
    let t = TexturedTriangle::new(*vertices, texture);
    if into {
        t.draw_into(fb.framebuffer_mut());
    } else {
        let _ = t.draw(fb.framebuffer_mut());
    }
}

/// `draw_textured`, or `draw_textured_lit` with `levels`. Out of line (see [`draw_2d`]).
#[inline(never)]
fn draw_3d<S: TexelSource>(
    fb: &mut DepthTarget<'_, Rgb565>,
    clip: &Rectangle,
    v: &[TexturedScreenVertex; 3],
    texture: &Texture<S>,
    levels: Option<[u8; 3]>,
) where
    Rgb565: From<S::Color>,
{
    match levels {
        Some(levels) => draw_textured_lit(fb, clip, v, texture, levels),
        None => draw_textured(fb, clip, v, texture),
    }
}

/// Runs `case` once with its texture.
fn run_case(case: Case, fb: &mut DepthTarget<'_, Rgb565>, pass: u16) {
    let Ok(rgb) = Texture::new(Rgb565Texels(&TEXELS), SIDE as u32, SIDE as u32) else {
        return;
    };
    match case {
        Case::AffineNearestIndexed4Into => {
            let texels = Indexed4 {
                indices: &INDICES,
                palette: &PALETTE,
            };
            if let Ok(t) = Texture::new(texels, SIDE as u32, SIDE as u32) {
                run(case, &t, fb, pass);
            }
        }
        Case::AffineBilinearInto | Case::PerspectiveBilinear => {
            run(case, &rgb.with_filter(Filter::Bilinear), fb, pass)
        }
        _ => run(case, &rgb, fb, pass),
    }
}

#[cfg(target_os = "none")]
#[path = "common/stack.rs"]
mod stack;

#[cfg(target_os = "none")]
mod firmware {
    use core::hint::black_box;

    use crate::board::entry;
    use crate::board::hprintln;

    use super::*;
    use crate::clock::{calibrate, measure, Ratio};
    use crate::{board, clock};

    /// Passes per measurement.
    const REPS: u32 = 4;

    static mut PIXELS: [Rgb565; board::PIXELS] = [Rgb565::new(0, 0, 0); board::PIXELS];
    static mut DEPTH: [u16; board::PIXELS] = [0; board::PIXELS];

    #[entry]
    fn main() -> ! {
        // SAFETY: `main` runs once and never returns: the statics' only references.
        let (pixels, depth) = unsafe {
            (
                &mut *core::ptr::addr_of_mut!(PIXELS),
                &mut *core::ptr::addr_of_mut!(DEPTH),
            )
        };
        crate::stack::paint_run();
        let (width, height) = board::SIZE;
        let Ok(mut fb) = DepthTarget::new(pixels, depth, width, height) else {
            board::exit(false)
        };
        clock::start();
        let cal = calibrate();
        let pixels = u64::from(count_pixels(width, height));

        hprintln!("### {}\n", board::name());
        hprintln!(
            "Textured large triangles ({} px a pass) into {}×{} Rgb565; 64×64 texture; QEMU \
             `-icount shift=0`.\n",
            pixels,
            width,
            height
        );
        hprintln!("| texturing | instr/pixel, large |");
        hprintln!("|---|---:|");
        let mut pass = 0u16;
        let mut checksums = [0u32; CASES.len()];
        // TEXTURE_CASE=<index> at build time measures that case alone (for a profile).
        let only = option_env!("TEXTURE_CASE").and_then(|c| c.parse::<usize>().ok());
        for (index, case) in CASES.into_iter().enumerate() {
            if only.is_some_and(|only| only != index) {
                continue;
            }
            fb.clear(Rgb565::new(0, 0, 0));
            run_case(case, &mut fb, pass); // warm-up, untimed
            pass += 1;
            let ticks = measure(REPS, || {
                run_case(black_box(case), &mut fb, pass);
                pass += 1;
            });
            let instructions = clock::instructions(ticks, cal);
            hprintln!(
                "| {} | {} |",
                case.name(),
                Ratio(instructions, pixels * u64::from(REPS))
            );
            checksums[index] = scene::checksum(fb.framebuffer().pixels());
        }
        // The checksums after the table (whose lines CI reads as they are); not for a profile.
        if only.is_some() {
            board::exit(true)
        }
        for (index, &sum) in checksums.iter().enumerate() {
            hprintln!(
                "texture {}x{} case{} fnv1a={:#010x}",
                width,
                height,
                index,
                sum
            );
        }
        fb.clear(Rgb565::new(0, 0, 0));
        check(fb.framebuffer_mut());
        let line = CheckLine {
            size: (width, height),
            what: "check",
            pixels: fb.framebuffer().pixels(),
        };
        hprintln!("{}", line);
        fb.clear(Rgb565::new(0, 0, 0));
        check_3d(&mut fb);
        let line = CheckLine {
            size: (width, height),
            what: "check3d",
            pixels: fb.framebuffer().pixels(),
        };
        hprintln!("{}", line);
        let faces = check_faces(&mut fb);
        hprintln!("texture {}x{} faces fnv1a={:#010x}", width, height, faces);
        crate::stack::report();
        board::exit(true)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    for (width, height) in scene::SIZES {
        println!(
            "{width}×{height}: {} pixels a pass",
            count_pixels(width, height)
        );
        let (mut px, mut z) = (
            vec![Rgb565::BLACK; (width * height) as usize],
            vec![0u16; (width * height) as usize],
        );
        let mut fb = DepthTarget::new(&mut px, &mut z, width, height).expect("buffers");
        for (index, case) in CASES.into_iter().enumerate() {
            fb.clear(Rgb565::BLACK);
            run_case(case, &mut fb, 0);
            println!("  {}", case.name());
            let what = format!("case{index}");
            let pixels = fb.framebuffer().pixels();
            println!(
                "{}",
                CheckLine {
                    size: (width, height),
                    what: &what,
                    pixels
                }
            );
        }
        fb.clear(Rgb565::BLACK);
        check(fb.framebuffer_mut());
        let pixels = fb.framebuffer().pixels();
        let what = "check";
        println!(
            "{}",
            CheckLine {
                size: (width, height),
                what,
                pixels
            }
        );
        fb.clear(Rgb565::BLACK);
        check_3d(&mut fb);
        let pixels = fb.framebuffer().pixels();
        println!(
            "{}",
            CheckLine {
                size: (width, height),
                what: "check3d",
                pixels
            }
        );
        let faces = check_faces(&mut fb);
        println!("texture {width}x{height} faces fnv1a={faces:#010x}");
    }
}
