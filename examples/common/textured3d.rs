//! The textured 3D benchmark frames (`fw_mesh_bench`, included with `#[path]` next to
//! `scene3d.rs`): Keenan Crane's spot with its own texture (released by its author into the
//! public domain with the mesh, `textures/spot_README.txt`) in the bench scene's frame — the
//! same camera, light, pose and 320×240 Rgb565 target with a 16-bit z-buffer — Gouraud-lit,
//! perspective-correct.
//!
//! * [`SPOT_TEXTURED`]: the mesh with its texture coordinates (3,225 vertices: the texture's
//!   seams split some), stored in flash (`meshes/spot_textured.rs`, converted from the OBJ by
//!   `tests/all/meshes.rs`, which checks it).
//! * [`SPOT_TEXTURE`]: the texture box-filtered to 256 × 256 and reduced to 16 colours, 4 bits a
//!   texel in flash (32 KB; `textures/spot_texture.rs`, generated from `textures/spot_texture.png`
//!   by `texture::convert` and checked by `tests/all/texture_convert.rs`), drawn as it is or expanded
//!   once into 256 × 256 Rgb565 texels in RAM ([`expand`], 128 KB) as TGX's frame draws it.

use core::convert::Infallible;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_raster::band::{
    BandError, BandLayout, BinEntry, Callback, ColorBands, DepthBands, MeshBin,
};
use embedded_raster::texture::{Filter, Rgb565Texels, TexelSource, Texture};
use embedded_raster::three_d::{Angle, Mat4, Mesh, TexCoord, TexturedMaterial, Vec3};
use embedded_raster::three_d::{
    DepthTarget, DrawStats, Pipeline, ProjectedVertex, Scalar, Shading, Specular,
};

use crate::scene3d::{self, fnv, pipeline, Model, BACKGROUND, FNV_START, SIZE};

#[allow(clippy::all)]
#[rustfmt::skip]
#[path = "meshes/spot_textured.rs"]
mod spot_textured;

#[allow(clippy::all)]
#[rustfmt::skip]
#[path = "textures/spot_texture.rs"]
mod spot_texture;

pub use spot_texture::{SPOT_TEXTURE, SPOT_TEXTURE_HEIGHT, SPOT_TEXTURE_WIDTH};
pub use spot_textured::SPOT_TEXTURED;

/// Pixels of the band buffers of [`render_bands`] (bands of up to 16 rows).
pub const BAND_PIXELS: usize = SIZE.0 as usize * 16;

/// Texels of the texture.
pub const TEXELS: usize = (SPOT_TEXTURE_WIDTH * SPOT_TEXTURE_HEIGHT) as usize;

/// The textured frames: the texture's storage and filter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Textured {
    /// Rgb565 texels in RAM, nearest.
    Nearest,
    /// Rgb565 texels in RAM, bilinear.
    Bilinear,
    /// The 4-bit palette texels in flash, nearest.
    Palette,
    /// Rgb565 texels in RAM, nearest, with a Blinn-Phong highlight.
    Specular,
    /// Rgb565 texels in RAM, nearest, lit per pixel (`Shading::Quadratic`).
    Quadratic,
    /// The same with the Blinn-Phong highlight per pixel.
    QuadraticSpecular,
    /// Rgb565 texels in RAM, nearest, unlit (`Shading::Unlit`).
    Unlit,
    /// The [`floor`] mesh, not spot: an 8 × 8 texture, nearest, Gouraud-lit, seen at a grazing
    /// angle ([`render_floor`]; not in [`ALL`](Self::ALL)).
    Floor,
    /// The scatter mesh ([`scene3d::scatter`]) with the floor's texture, some faces handed back
    /// by a face scan ([`render_scatter_textured`]; not in [`ALL`](Self::ALL)).
    Scatter,
}

impl Textured {
    /// All, in report order.
    pub const ALL: [Textured; 7] = [
        Textured::Nearest,
        Textured::Bilinear,
        Textured::Palette,
        Textured::Specular,
        Textured::Quadratic,
        Textured::QuadraticSpecular,
        Textured::Unlit,
    ];

    /// The name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Textured::Nearest => "spot-textured-nearest",
            Textured::Bilinear => "spot-textured-bilinear",
            Textured::Palette => "spot-textured-palette",
            Textured::Specular => "spot-textured-specular",
            Textured::Quadratic => "spot-textured-quadratic",
            Textured::QuadraticSpecular => "spot-textured-quadratic-specular",
            Textured::Unlit => "spot-textured-unlit",
            Textured::Floor => "floor-textured",
            Textured::Scatter => "scatter-textured",
        }
    }

    /// How the frame lights the texels.
    fn shading(self) -> Shading {
        match self {
            Textured::Quadratic | Textured::QuadraticSpecular => Shading::Quadratic,
            Textured::Unlit => Shading::Unlit,
            _ => Shading::Gouraud,
        }
    }
}

/// [`SPOT_TEXTURE`]'s texels as raw Rgb565 words into `out`.
pub fn expand(out: &mut [u16]) {
    for (k, texel) in out.iter_mut().enumerate().take(TEXELS) {
        *texel = embedded_graphics::prelude::IntoStorage::into_storage(SPOT_TEXTURE.texel(k));
    }
}

/// One textured frame of spot (`texels`: [`expand`]ed, for the Rgb565 frames): clears colour
/// and depth, draws — each vertex transformed once into `scratch` if given (it must hold a
/// vertex per mesh vertex), or once per face without.
pub fn render(
    frame: Textured,
    texels: &[u16],
    target: &mut DepthTarget<'_, Rgb565>,
    scratch: Option<&mut [ProjectedVertex]>,
) -> DrawStats {
    let (w, h) = (SPOT_TEXTURE_WIDTH, SPOT_TEXTURE_HEIGHT);
    target.clear(BACKGROUND);
    match frame {
        Textured::Palette => match Texture::new(SPOT_TEXTURE, w, h) {
            Ok(texture) => draw(&texture, frame.shading(), None, target, scratch),
            Err(_) => DrawStats::default(),
        },
        _ => {
            let filter = match frame {
                Textured::Bilinear => Filter::Bilinear,
                _ => Filter::Nearest,
            };
            // Strength ½, shininess 24.
            let shiny = matches!(frame, Textured::Specular | Textured::QuadraticSpecular);
            let specular = shiny.then(|| Specular::new(Scalar::from_bits(1 << 15), 24));
            match Texture::new(Rgb565Texels(texels), w, h) {
                Ok(texture) => {
                    let texture = texture.with_filter(filter);
                    draw(&texture, frame.shading(), specular, target, scratch)
                }
                Err(_) => DrawStats::default(),
            }
        }
    }
}

/// Quads a side of the [`floor`] grid.
pub const FLOOR_SIDE: usize = 24;

/// Vertices of the [`floor`] mesh.
pub const FLOOR_VERTICES: usize = (FLOOR_SIDE + 1) * (FLOOR_SIDE + 1);

/// Faces of the [`floor`] mesh.
pub const FLOOR_FACES: usize = 2 * FLOOR_SIDE * FLOOR_SIDE;

/// A floor into the caller's arrays: a grid of [`FLOOR_SIDE`]² quads 0.6 below the camera's
/// eye, 4 units wide, reaching from just past the near plane to near the far one (seen in the
/// bench frame's camera, without the pose: faces in depth ratios from about 1.4 near to 1.04
/// far), with a bumpy normal field (the light varies across each face) and texture coordinates
/// repeating every four quads. The frame that decides, face by face, between screen-space and
/// perspective-correct textured fills, on both sides of the bound.
pub fn floor<'a>(
    vertices: &'a mut [Vec3; FLOOR_VERTICES],
    normals: &'a mut [Vec3; FLOOR_VERTICES],
    uvs: &'a mut [TexCoord; FLOOR_VERTICES],
    indices: &'a mut [[u16; 3]; FLOOR_FACES],
) -> Mesh<'a> {
    let n = FLOOR_SIDE as i32;
    for j in 0..=FLOOR_SIDE {
        for i in 0..=FLOOR_SIDE {
            let k = j * (FLOOR_SIDE + 1) + i;
            let (i, j) = (i as i32, j as i32);
            // x from −2 to 2, z from 1.8 to −5 (the view's −0.7 to −7.5).
            let x = -(2 << 16) + (4 << 16) / n * i;
            let z = (118_000) - (445_645 / n) * j;
            vertices[k] = Vec3::from_bits(x, -39_322, z);
            let (bx, bz) = (Angle::from_turns(3 * i, n), Angle::from_turns(2 * j, n));
            let half = Scalar::from_bits(1 << 15);
            normals[k] = Vec3::new(bx.sin() * half, Scalar::ONE, bz.cos() * half).normalize();
            uvs[k] = TexCoord::from_bits(i << 14, j << 14);
        }
    }
    let at = |i: usize, j: usize| (j * (FLOOR_SIDE + 1) + i) as u16;
    for j in 0..FLOOR_SIDE {
        for i in 0..FLOOR_SIDE {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            let k = 2 * (j * FLOOR_SIDE + i);
            indices[k] = [a, b, c];
            indices[k + 1] = [a, c, d];
        }
    }
    Mesh::new(&vertices[..], &normals[..], &indices[..]).with_uvs(&uvs[..])
}

/// The [`floor`] frame of `mesh` with `scratch`: clears colour and depth and draws it with an
/// 8 × 8 texture of distinct colours, nearest, Gouraud-lit, in the bench frame's camera.
pub fn render_floor(
    mesh: &Mesh<'_>,
    target: &mut DepthTarget<'_, Rgb565>,
    scratch: &mut [ProjectedVertex],
) -> DrawStats {
    draw_floor_textured(&scene3d::posed(Mat4::IDENTITY), mesh, target, scratch)
}

/// Clears colour and depth and draws `mesh` through `pipeline` with the [`floor`]'s 8 × 8
/// texture of distinct colours, nearest, Gouraud-lit.
fn draw_floor_textured(
    pipeline: &Pipeline,
    mesh: &Mesh<'_>,
    target: &mut DepthTarget<'_, Rgb565>,
    scratch: &mut [ProjectedVertex],
) -> DrawStats {
    let texels: [u16; 64] = core::array::from_fn(|k| {
        let c = Rgb565::new((k * 5 % 32) as u8, (k * 11 % 64) as u8, (k * 7 % 32) as u8);
        c.into_storage()
    });
    target.clear(BACKGROUND);
    let Ok(texture) = Texture::new(Rgb565Texels(&texels[..]), 8, 8) else {
        return DrawStats::default();
    };
    let material = TexturedMaterial::new(&texture, Shading::Gouraud);
    pipeline
        .draw_textured_mesh_with(mesh, &material, target, scratch)
        .unwrap_or_default()
}

/// The scatter frame textured: the [`scene3d::scatter`] mesh `mesh` with normals for its first
/// sixteenth of vertices only and the texture coordinates `uvs` (fewer than its vertices, more
/// than those normals; every corner of the first 100 faces and one vertex in 16 set to `u` =
/// 30,000, whose products with the texture's size pass `i32`), drawn as the [`floor`]
/// is through the scatter's camera. The frame whose faces a face scan's textured faces hand
/// back untried: a vertex without a normal in a lit draw, an index past the coordinates, a
/// texel coordinate that saturates.
pub fn render_scatter_textured(
    mesh: &Mesh<'_>,
    uvs: &mut [TexCoord],
    target: &mut DepthTarget<'_, Rgb565>,
    scratch: &mut [ProjectedVertex],
) -> DrawStats {
    for (k, uv) in uvs.iter_mut().enumerate() {
        // Every corner of the first 100 faces (lit), one vertex in 16 past them.
        if k < 300 || k % 16 == 5 {
            *uv = TexCoord::from_bits(30_000 << 16, uv.v.to_bits());
        }
    }
    let normals = &mesh.normals[..mesh.normals.len() / 16];
    let mesh = Mesh::new(mesh.vertices, normals, mesh.indices).with_uvs(uvs);
    draw_floor_textured(&scene3d::scatter_pipeline(), &mesh, target, scratch)
}

/// The [`fnv`] hashes of a frame's colours (raw) and of its depths.
pub fn hashes(colors: &[Rgb565], depth: &[u16]) -> (u32, u32) {
    let colors = fnv(FNV_START, colors.iter().map(|c| c.into_storage()));
    (colors, fnv(FNV_START, depth.iter().copied()))
}

/// The nearest frame ([`Textured::Nearest`], `texels` [`expand`]ed) drawn with `scratch` in
/// bands of `rows` rows into the band buffers `colors` and `depth` (their first `320 · rows`
/// entries) — each band drawing the mesh, or, with `bin` storage, a `MeshBin`'s faces of it —
/// each band's colours and depths hashed as a display would receive them: the frame's
/// [`hashes`] if the bands draw the frame drawn whole; zeros if the buffers are too short.
pub fn render_bands(
    texels: &[u16],
    rows: u32,
    colors: &mut [Rgb565],
    depth: &mut [u16],
    scratch: &mut [ProjectedVertex],
    bin: Option<&mut [BinEntry]>,
) -> (u32, u32) {
    let (w, h) = (SPOT_TEXTURE_WIDTH, SPOT_TEXTURE_HEIGHT);
    let Ok(texture) = Texture::new(Rgb565Texels(texels), w, h) else {
        return (0, 0);
    };
    let material = TexturedMaterial::new(&texture, Textured::Nearest.shading());
    let pipeline = pipeline(Model::Spot);
    let Ok(layout) = BandLayout::new(Size::new(SIZE.0, SIZE.1), rows) else {
        return (0, 0);
    };
    let n = layout.buffer_len();
    let (Some(colors), Some(depth)) = (colors.get_mut(..n), depth.get_mut(..n)) else {
        return (0, 0);
    };
    let Ok(colors) = ColorBands::new(layout, colors) else {
        return (0, 0);
    };
    let Ok(mut bands) = DepthBands::new(colors, depth) else {
        return (0, 0);
    };
    let mesh: &Mesh<'_> = &SPOT_TEXTURED;
    let mut bin = match bin {
        Some(storage) => {
            match MeshBin::new_textured(&pipeline, mesh, &material, &layout, scratch, storage) {
                Ok(bin) => Ok(bin),
                Err(_) => return (0, 0),
            }
        }
        None => Err(scratch),
    };
    let (mut color_hash, mut depth_hash) = (FNV_START, FNV_START);
    let mut output = Callback(|_: &_, pixels: &[Rgb565]| {
        color_hash = fnv(color_hash, pixels.iter().map(|c| c.into_storage()));
        Ok::<(), Infallible>(())
    });
    let drawn = bands.render(&mut output, |band| {
        band.clear(BACKGROUND);
        let _ = match &mut bin {
            Ok(bin) => bin.draw(band),
            Err(scratch) => pipeline
                .draw_textured_mesh_with(mesh, &material, band, scratch)
                .map(|_| ())
                .map_err(BandError::from),
        };
        depth_hash = fnv(depth_hash, band.depth().iter().copied());
    });
    match drawn {
        Ok(()) => (color_hash, depth_hash),
        Err(_) => (0, 0),
    }
}

/// Spot in the bench frame with `texture`, lit with `shading`, highlighted by `specular` if
/// given.
fn draw<S>(
    texture: &Texture<S>,
    shading: Shading,
    specular: Option<Specular>,
    target: &mut DepthTarget<'_, Rgb565>,
    scratch: Option<&mut [ProjectedVertex]>,
) -> DrawStats
where
    S: TexelSource,
    Rgb565: From<S::Color>,
{
    let pipeline = pipeline(Model::Spot);
    let mut material = TexturedMaterial::new(texture, shading);
    if let Some(specular) = specular {
        material = material.with_specular(specular);
    }
    let mesh: &Mesh<'_> = &SPOT_TEXTURED;
    match scratch {
        Some(scratch) => pipeline
            .draw_textured_mesh_with(mesh, &material, target, scratch)
            .unwrap_or_default(),
        None => pipeline.draw_textured_mesh(mesh, &material, target),
    }
}

/// The line the host and the firmware print for a textured frame, compared by
/// `.ci/firmware.sh` like the other frame lines.
pub struct TexturedLine {
    /// The frame.
    pub frame: Textured,
    /// The pipeline's counts.
    pub stats: DrawStats,
    /// Pixels covered.
    pub covered: u32,
    /// FNV-1a of colours and depths.
    pub checksum: u32,
}

impl TexturedLine {
    /// The line of `frame` drawn into `target` with the counts `stats`.
    pub fn of(frame: Textured, stats: DrawStats, target: &DepthTarget<'_, Rgb565>) -> Self {
        TexturedLine {
            frame,
            stats,
            covered: scene3d::covered(target.depth()),
            checksum: scene3d::checksum(target.framebuffer().pixels(), target.depth()),
        }
    }
}

impl core::fmt::Display for TexturedLine {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let s = &self.stats;
        write!(
            f,
            "frame {} {}x{} drawn={} culled={} clipped={} covered={} fnv1a={:#010x}",
            self.frame.name(),
            SIZE.0,
            SIZE.1,
            s.drawn,
            s.culled,
            s.clipped,
            self.covered,
            self.checksum
        )
    }
}
