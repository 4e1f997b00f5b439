//! The textured drawing of `fw_nopanic_textures` (included with `#[path]`): 2D textured triangles through
//! `draw_into` and `Drawable::draw` with every wrap mode on each axis and both filters, and a
//! textured floor through the 3D pipeline (`Pipeline::draw_textured_mesh_with`, and
//! `draw_textured_mesh` in a frame of its own; every shading, reaching the perspective-correct
//! path; vertex colours and highlights on some draws) and `three_d::draw_textured`, with two textures of Rgb565 texels (8 × 8, a power of
//! two: the masked loops; 5 × 3: the loops that wrap by compares and remainders).
//!
//! Every input goes through `core::hint::black_box`, so that the firmware links only if these
//! paths have no panic left for any input, and the same code runs on the host, whose
//! `textures` lines (checksums) `.ci/firmware.sh` compares with the firmware's.

use core::hint::black_box;

use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::texture::{Filter, Rgb565Texels, TexelCoord, Wrap};
use embedded_raster::three_d::{
    draw_textured, Angle, Cull, DepthTarget, Light, Mat4, Mesh, Pipeline, ProjectedVertex, Scalar,
    ScreenVertex, Shading, Specular, TexCoord, TexturedMaterial, TexturedScreenVertex, Vec3,
};
use embedded_raster::{Coord, SliceFramebuffer, Texture, TexturedTriangle, TexturedVertex};

/// The 2D frame's size (pixels).
pub const SIZE_2D: (u32, u32) = (64, 48);
/// The 3D frame's size (pixels).
pub const SIZE_3D: (u32, u32) = (24, 16);

/// Every wrap mode.
const WRAPS: [Wrap; 3] = [Wrap::Repeat, Wrap::MirroredRepeat, Wrap::Clamp];
/// Both filters.
const FILTERS: [Filter; 2] = [Filter::Nearest, Filter::Bilinear];

/// 8 × 8 Rgb565 texels (raw words).
static RGB565: [u16; 64] = {
    let mut t = [0; 64];
    let mut i = 0;
    while i < 64 {
        let (x, y) = ((i % 8) as u16, (i / 8) as u16);
        t[i] = ((x * 4) << 11) | ((y * 9) << 5) | ((x ^ y) * 4);
        i += 1;
    }
    t
};

/// 5 × 3 Rgb565 texels (raw words): a size that is not a power of two.
static ODD: [u16; 15] = {
    let mut t = [0; 15];
    let mut i = 0;
    while i < 15 {
        t[i] = (((i * 2) << 11) | ((63 - i * 4) << 5) | ((i * 7) % 32)) as u16;
        i += 1;
    }
    t
};

/// A floor of 3 × 3 vertices from behind the camera far into the scene: 8 faces, up.
static FLOOR_VERTICES: [Vec3; 9] = {
    let mut v = [Vec3::from_bits(0, 0, 0); 9];
    let mut i = 0;
    while i < 9 {
        let (r, c) = ((i / 3) as i32, (i % 3) as i32);
        v[i] = Vec3::from_bits((-2 + 2 * c) << 16, -1 << 16, (1 - 5 * r) << 16);
        i += 1;
    }
    v
};

/// Unit normals leaning left, up and right (so that Gouraud levels vary).
static FLOOR_NORMALS: [Vec3; 9] = {
    let lean = [
        Vec3::from_bits(-19_661, 62_521, 0),
        Vec3::from_bits(0, 65_536, 0),
        Vec3::from_bits(19_661, 62_521, 0),
    ];
    [
        lean[0], lean[1], lean[2], lean[0], lean[1], lean[2], lean[0], lean[1], lean[2],
    ]
};

/// Texture coordinates past the texture's edges (wrapped by its modes).
static FLOOR_UVS: [TexCoord; 9] = {
    let mut t = [TexCoord::from_bits(0, 0); 9];
    let mut i = 0;
    while i < 9 {
        let (r, c) = ((i / 3) as i32, (i % 3) as i32);
        t[i] = TexCoord::from_bits(c * 98_304 - 49_152, r * 131_072 - 65_536);
        i += 1;
    }
    t
};

/// Two faces a square of the grid, counter-clockwise seen from above.
static FLOOR_INDICES: [[u16; 3]; 8] = [
    [0, 1, 3],
    [1, 4, 3],
    [1, 2, 4],
    [2, 5, 4],
    [3, 4, 6],
    [4, 7, 6],
    [4, 5, 7],
    [5, 8, 7],
];

/// The floor: positions, normals and texture coordinates.
/// Vertex colours of the floor (the draws that tint their texels by them).
static FLOOR_COLORS: [Rgb888; 9] = {
    let mut c = [Rgb888::new(0, 0, 0); 9];
    let mut k = 0;
    while k < 9 {
        c[k] = Rgb888::new((k * 29) as u8, (255 - k * 17) as u8, (90 + k * 13) as u8);
        k += 1;
    }
    c
};

static FLOOR: Mesh<'static> = Mesh::new(&FLOOR_VERTICES, &FLOOR_NORMALS, &FLOOR_INDICES)
    .with_uvs(&FLOOR_UVS)
    .with_colors(&FLOOR_COLORS);

/// FNV-1a of `bytes`, continuing from `h`.
fn fnv(mut h: u32, bytes: &[u8]) -> u32 {
    for &byte in bytes {
        h = (h ^ u32::from(byte)).wrapping_mul(0x0100_0193);
    }
    h
}

/// FNV-1a of colours (little-endian words), continuing from `h`.
fn hash_colors(h: u32, colors: &[Rgb565]) -> u32 {
    colors.iter().fold(h, |h, &c| {
        fnv(h, &RawU16::from(c).into_inner().to_le_bytes())
    })
}

/// FNV-1a of depths (little-endian), continuing from `h`.
fn hash_depths(h: u32, depths: &[u16]) -> u32 {
    depths.iter().fold(h, |h, &d| fnv(h, &d.to_le_bytes()))
}

/// A small generator of opaque, varied inputs.
struct Random(u32);

impl Random {
    fn next(&mut self) -> u32 {
        self.0 = self.0.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        self.0
    }

    /// An integer in `lo..lo + span` (`span` at most 2¹⁶).
    fn range(&mut self, lo: i32, span: u32) -> i32 {
        lo.wrapping_add((((self.next() >> 16) * span) >> 16) as i32)
    }
}

/// The texture type drawn.
type Tex = Texture<Rgb565Texels<'static>>;

/// The texture of `texels`, `size` texels (both opaque): repeating, with nearest filtering.
fn texture(texels: &'static [u16], size: (u32, u32)) -> Option<Tex> {
    let (w, h) = black_box(size);
    Texture::new(Rgb565Texels(black_box(texels)), w, h).ok()
}

/// The textures drawn: 8 × 8 (the masked loops of power-of-two sizes) and 5 × 3 (the loops
/// that wrap by compares and remainders). One texel source (each source's `texel` is a
/// checked read; one keeps the firmware within the micro:bit's flash at `opt-level` 3).
fn textures() -> [Option<Tex>; 2] {
    [texture(&RGB565, (8, 8)), texture(&ODD, (5, 3))]
}

/// Two triangles for each wrap pair and filter, one through `draw_into` and one through
/// `draw`, into `fb`.
fn draw_2d(fb: &mut SliceFramebuffer<'_, Rgb565>, texture: &Tex, random: &mut Random) {
    let (w, h) = SIZE_2D;
    for wrap_x in WRAPS {
        for wrap_y in WRAPS {
            for filter in FILTERS {
                let texture = texture
                    .with_wrap(black_box(wrap_x), black_box(wrap_y))
                    .with_filter(black_box(filter));
                let mut vertex = |_| {
                    // Positions a little past the frame, texel coordinates past the texture.
                    let x = random.range(-8 << 8, (w + 16) << 8);
                    let y = random.range(-8 << 8, (h + 16) << 8);
                    let mut texel =
                        || (random.range(-12 << 8, 36 << 8) << 8) | (random.next() >> 24) as i32;
                    let (u, v) = (texel(), texel());
                    black_box(TexturedVertex {
                        x: Coord::from_bits(x),
                        y: Coord::from_bits(y),
                        u: TexelCoord::from_bits(u),
                        v: TexelCoord::from_bits(v),
                    })
                };
                let first = core::array::from_fn(&mut vertex);
                let second = core::array::from_fn(&mut vertex);
                black_box(TexturedTriangle::new(first, &texture)).draw_into(fb);
                let _ = black_box(TexturedTriangle::new(second, &texture)).draw(fb);
            }
        }
    }
}

/// The 2D frame: [`draw_2d`] with both textures into `pixels` (at least [`SIZE_2D`]), and its
/// FNV-1a.
pub fn render_2d(pixels: &mut [Rgb565]) -> u32 {
    let (w, h) = black_box(SIZE_2D);
    let Ok(mut fb) = SliceFramebuffer::new(pixels, w, h) else {
        return 0;
    };
    let _ = fb.clear(black_box(Rgb565::new(3, 7, 3)));
    let mut random = Random(black_box(0x7e47_0028));
    for texture in textures().iter().flatten() {
        draw_2d(&mut fb, texture, &mut random);
    }
    hash_colors(0x811C_9DC5, fb.pixels())
}

/// The floor's camera and light (opaque), `FLOOR` leaning away to the horizon.
#[inline(never)]
fn floor_pipeline() -> Option<Pipeline> {
    let projection = black_box(Mat4::perspective(
        Angle::from_degrees(60),
        Scalar::from_bits(98_304),
        Scalar::from_bits(1 << 15),
        Scalar::from_bits(20 << 16),
    ))?;
    let model = black_box(Mat4::rotation_y(Angle::from_degrees(20)));
    let view = black_box(Mat4::rotation_x(Angle::from_degrees(10)));
    let viewport = black_box(Rectangle::new(Point::new(-1, 0), Size::new(26, 15)));
    let light = Light::new(
        black_box(Vec3::from_bits(1 << 15, 1 << 16, 1 << 16)),
        black_box(Scalar::from_bits(1 << 13)),
    );
    Some(Pipeline::new(model, projection * view, viewport, light))
}

/// One draw of a 3D frame into `target` (the floor with a pipeline and material, or a screen
/// triangle with the material's texture), with a vertex scratch.
type Draw = fn(
    &mut DepthTarget<'_, Rgb565>,
    &Pipeline,
    &TexturedMaterial<'_, Rgb565Texels<'_>>,
    &mut [ProjectedVertex],
);

// The draws are out of line, so that one draw's stack is taken at a time: the micro:bit has 16
// KiB of RAM.

/// `Pipeline::draw_textured_mesh_with`.
#[inline(never)]
fn mesh_with(
    target: &mut DepthTarget<'_, Rgb565>,
    pipeline: &Pipeline,
    material: &TexturedMaterial<'_, Rgb565Texels<'_>>,
    scratch: &mut [ProjectedVertex],
) {
    let mesh = black_box(&FLOOR);
    let _ = black_box(pipeline.draw_textured_mesh_with(mesh, material, target, scratch));
}

/// `Pipeline::draw_textured_mesh` (no scratch).
#[inline(never)]
fn mesh(
    target: &mut DepthTarget<'_, Rgb565>,
    pipeline: &Pipeline,
    material: &TexturedMaterial<'_, Rgb565Texels<'_>>,
    _: &mut [ProjectedVertex],
) {
    black_box(pipeline.draw_textured_mesh(black_box(&FLOOR), material, target));
}

/// `three_d::draw_textured`: a screen triangle leaning away, its far vertices eight times as
/// deep as the near one (perspective-correct), and one facing the camera in front of it.
#[inline(never)]
fn screen(
    target: &mut DepthTarget<'_, Rgb565>,
    _: &Pipeline,
    material: &TexturedMaterial<'_, Rgb565Texels<'_>>,
    _: &mut [ProjectedVertex],
) {
    // At (x, y) px, depth z, w, texel (u, v).
    let vertex = |x: i32, y: i32, z: u16, w: i32, u: i32, v: i32| TexturedScreenVertex {
        screen: ScreenVertex::new(Coord::from_bits(x << 8), Coord::from_bits(y << 8), z),
        w: Scalar::from_bits(w << 16),
        u: TexelCoord::from_bits(u << 16),
        v: TexelCoord::from_bits(v << 16),
    };
    let clip = black_box(Rectangle::new(Point::new(1, 1), Size::new(40, 13)));
    let leaning = black_box([
        vertex(-2, 15, 900, 1, -3, 11),
        vertex(25, 13, 900, 8, 13, 9),
        vertex(4, -1, 900, 8, -1, -6),
    ]);
    draw_textured(target, &clip, &leaning, material.texture);
    // One facing the camera (the same w at each vertex: interpolated in screen space), nearer.
    let facing = black_box([
        vertex(3, 2, 600, 2, 0, 0),
        vertex(20, 4, 600, 2, 9, -2),
        vertex(9, 14, 600, 2, 3, 7),
    ]);
    draw_textured(target, &clip, &facing, material.texture);
}

/// `draws` with each texture under each wrap mode (horizontally; the next one vertically),
/// filter and shading (culling back faces or none) into `colors` and `depths` (at least
/// [`SIZE_3D`]): the target cleared before each draw, and the FNV-1a of the colours and depths
/// after each.
fn render(
    colors: &mut [Rgb565],
    depths: &mut [u16],
    scratch: &mut [ProjectedVertex],
    draws: &[Draw],
) -> u32 {
    let (w, h) = black_box(SIZE_3D);
    let Ok(mut target) = DepthTarget::new(colors, depths, w, h) else {
        return 0;
    };
    let Some(mut pipeline) = floor_pipeline() else {
        return 0;
    };
    let shadings = [
        Shading::Unlit,
        Shading::Flat,
        Shading::Gouraud,
        Shading::Quadratic,
    ];
    let mut hash = 0x811C_9DC5;
    for texture in textures().iter().flatten() {
        let mut k = 0;
        for wrap in WRAPS {
            for filter in FILTERS {
                let texture = texture
                    .with_wrap(black_box(wrap), black_box(WRAPS[(k + 1) % 3]))
                    .with_filter(black_box(filter));
                let mut material = TexturedMaterial::new(&texture, black_box(shadings[k % 4]));
                // Vertex colours every other draw, a highlight every third.
                if black_box(k % 2 == 1) {
                    material = material.with_vertex_colors();
                }
                if black_box(k % 3 == 2) {
                    let shininess = black_box(k as u8 * 7);
                    material =
                        material.with_specular(Specular::new(black_box(Scalar::ONE), shininess));
                }
                pipeline.cull = black_box([Cull::Back, Cull::None][k % 2]);
                for draw in black_box(draws) {
                    target.clear(black_box(Rgb565::new(2, 4, 8)));
                    draw(&mut target, &pipeline, &material, scratch);
                    hash = hash_colors(hash, target.framebuffer().pixels());
                    hash = hash_depths(hash, target.depth());
                }
                k += 1;
            }
        }
    }
    hash
}

/// The 3D frames of `Pipeline::draw_textured_mesh_with` (the floor) and
/// `three_d::draw_textured` (a screen triangle), and their FNV-1a.
pub fn render_3d(
    colors: &mut [Rgb565],
    depths: &mut [u16],
    scratch: &mut [ProjectedVertex],
) -> u32 {
    render(colors, depths, scratch, &[mesh_with, screen])
}

/// The 3D frames of `Pipeline::draw_textured_mesh` (the floor), and their FNV-1a: the MPS2
/// boards' firmware and the host (with the other draws, a micro:bit's firmware would not fit
/// its flash at `opt-level` 3).
#[allow(dead_code)]
pub fn render_3d_mesh(colors: &mut [Rgb565], depths: &mut [u16]) -> u32 {
    render(colors, depths, &mut [], &[mesh])
}

// ---- 2D shapes -----------------------------------------------------------------------------
// Polygons, thin lines and strokes share this firmware (fw_nopanic is at the micro:bit's flash
// limit): the same opaque inputs, the same checksum comparison with the host.

/// The shapes frame's size (pixels).
pub const SIZE_SHAPES: (u32, u32) = (48, 40);

/// Random polygons (up to three contours, sometimes far outside or at the ends of the `Coord`
/// range) under both rules, polylines thin and stroked with every cap and join, through both
/// `draw_into` and `Drawable::draw`, into `pixels` (at least [`SIZE_SHAPES`]); its FNV-1a.
pub fn render_shapes(pixels: &mut [Rgb565]) -> u32 {
    use embedded_raster::{Cap, FillRule, Join, Line, Polygon, Polyline, Stroke};
    let (w, h) = black_box(SIZE_SHAPES);
    let Ok(mut fb) = SliceFramebuffer::new(pixels, w, h) else {
        return 0;
    };
    let _ = fb.clear(black_box(Rgb565::new(2, 5, 9)));
    let mut random = Random(black_box(0x5a4e_0030));
    let coordinate = |random: &mut Random| match random.next() % 8 {
        0 => Coord::from_bits(random.next() as i32),
        1 => Coord::from_bits(random.range(-40 * 256, 4000) << 4),
        _ => Coord::from_bits(random.range(-1024, 60 * 256 / 2) * 2),
    };
    for k in 0..24u32 {
        let color = Rgb565::new((k * 7 % 32) as u8, (k * 13 % 64) as u8, (k * 5 % 32) as u8);
        let mut polygon = Polygon::<12>::new();
        for _ in 0..1 + random.next() % 3 {
            for _ in 0..1 + random.next() % 4 {
                let _ = polygon.push((coordinate(&mut random), coordinate(&mut random)));
            }
            polygon.close();
        }
        let rule = black_box([FillRule::NonZero, FillRule::EvenOdd][k as usize % 2]);
        let fill = polygon.filled(color).with_rule(rule);
        if k % 3 == 0 {
            let _ = fill.draw(&mut fb);
        } else {
            fill.draw_into(&mut fb);
        }
        let points: [(Coord, Coord); 4] =
            core::array::from_fn(|_| (coordinate(&mut random), coordinate(&mut random)));
        let line = Polyline::new(&points, black_box(Rgb565::WHITE));
        let single = Line::new(points[0], points[1], black_box(Rgb565::YELLOW));
        let stroke = Stroke::new(black_box(Coord::from_bits(random.range(0, 1400))))
            .with_cap(black_box(
                [Cap::Butt, Cap::Square, Cap::Round][k as usize % 3],
            ))
            .with_join(black_box(
                [Join::Miter, Join::Bevel, Join::Round][k as usize / 3 % 3],
            ));
        if k % 2 == 0 {
            line.stroked(stroke).draw_into(&mut fb);
            line.draw_into(&mut fb);
            single.draw_into(&mut fb);
        } else {
            let _ = line.stroked(stroke).draw(&mut fb);
            let _ = line.draw(&mut fb);
            let _ = single.stroked(stroke).draw(&mut fb);
        }
    }
    hash_colors(0x811c_9dc5, fb.pixels())
}
