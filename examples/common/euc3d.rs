//! The 3D bench scene of `scene3d.rs` rendered by euc 0.5 (a float software renderer, host-only),
//! for `bench_report`'s comparison: the same mesh, the same camera (the fixed-point pipeline's
//! matrices converted to `f32`), viewport, back-face culling, depth test and light.
//!
//! The work matches the pipeline's: the vertex shader transforms the position by the
//! model-view-projection matrix and the normal by the normal matrix, renormalises it and lights it
//! (`ambient + (1 − ambient)·max(0, n·l)`); euc culls clockwise faces (in normalised device
//! coordinates, as the pipeline does), interpolates the level and tests and writes its `f32` depth
//! buffer; the fragment shader scales the material colour by the level into Rgb565. Euc 0.5 takes
//! vertices in threes, so the vertex stream is the mesh's index list and every face shades its
//! own three vertices (as the pipeline does today). It does not clip: the bench frames need no
//! clipping (`clipped=0` in their frame lines).

use embedded_graphics::pixelcolor::{raw::RawU16, Rgb565};
use embedded_graphics::prelude::*;
use embedded_raster::three_d::{Mat4, Mesh, Vec3};
use euc::buffer::Buffer2d;
use euc::rasterizer::{BackfaceCullingEnabled, Triangles};
use euc::{Pipeline, Target};

use crate::scene3d::{self, Model, SIZE};

/// Depth of an empty pixel (the far plane in euc's normalised depth).
pub const DEPTH_CLEAR: f32 = 1.0;

/// `I16F16` bits as `f32`.
fn real(bits: i32) -> f32 {
    bits as f32 / 65536.0
}

fn vec3(v: Vec3) -> [f32; 3] {
    v.to_bits().map(real)
}

fn mat4(m: &Mat4) -> [[f32; 4]; 4] {
    m.to_bits().map(|row| row.map(real))
}

/// One bench mesh with its camera and light, in `f32`, as an euc pipeline.
pub struct Scene {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    /// Three indices a face.
    stream: Vec<u16>,
    mvp: [[f32; 4]; 4],
    normal_matrix: [[f32; 4]; 4],
    /// Unit vector towards the light.
    light: [f32; 3],
    ambient: f32,
    /// Material colour in Rgb565 channel units (0..31, 0..63, 0..31).
    color: [f32; 3],
}

impl Scene {
    /// `mesh` posed as `model`, with `scene3d`'s camera, light and material.
    pub fn new(model: Model, mesh: &Mesh<'_>) -> Self {
        let pipeline = scene3d::pipeline(model);
        let c = scene3d::MATERIAL.color;
        Scene {
            positions: mesh.vertices.iter().map(|&v| vec3(v)).collect(),
            normals: mesh.normals.iter().map(|&n| vec3(n)).collect(),
            stream: mesh.indices.iter().flatten().copied().collect(),
            mvp: mat4(&pipeline.mvp),
            normal_matrix: mat4(&pipeline.normal_matrix),
            light: vec3(pipeline.light.direction()),
            ambient: real(pipeline.light.ambient().to_bits()),
            color: [c.r(), c.g(), c.b()].map(f32::from),
        }
    }

    /// One frame: clears colour and depth, draws.
    pub fn render(&self, frame: &mut Frame) {
        frame.color.clear(scene3d::BACKGROUND.into_storage());
        frame.depth.clear(DEPTH_CLEAR);
        self.draw::<Triangles<'_, Buffer2d<f32>, BackfaceCullingEnabled>, _>(
            &self.stream,
            &mut frame.color,
            Some(&mut frame.depth),
        );
    }
}

impl Pipeline for Scene {
    type Vertex = u16;
    /// The light level.
    type VsOut = f32;
    /// Rgb565 bits.
    type Pixel = u16;

    #[inline(always)]
    fn vert(&self, &index: &u16) -> ([f32; 4], f32) {
        let i = usize::from(index);
        let [x, y, z] = self.positions[i];
        let m = &self.mvp;
        let clip = [0, 1, 2, 3].map(|r| m[r][0] * x + m[r][1] * y + m[r][2] * z + m[r][3]);
        let [nx, ny, nz] = self.normals[i];
        let n = &self.normal_matrix;
        let w = [0, 1, 2].map(|r| n[r][0] * nx + n[r][1] * ny + n[r][2] * nz);
        let l = &self.light;
        let dot = (w[0] * l[0] + w[1] * l[1] + w[2] * l[2])
            / (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        (clip, self.ambient + (1.0 - self.ambient) * dot.max(0.0))
    }

    #[inline(always)]
    fn frag(&self, &level: &f32) -> u16 {
        let channel = |k: usize| (self.color[k] * level + 0.5) as u16;
        (channel(0) << 11) | (channel(1) << 5) | channel(2)
    }
}

/// Euc's colour (Rgb565 bits) and depth buffers, [`SIZE`].
pub struct Frame {
    /// Rgb565 bits, row by row.
    pub color: Buffer2d<u16>,
    /// Normalised depth, [`DEPTH_CLEAR`] where nothing was drawn.
    pub depth: Buffer2d<f32>,
}

impl Frame {
    /// Buffers of [`SIZE`].
    pub fn new() -> Self {
        let size = [SIZE.0 as usize, SIZE.1 as usize];
        Frame {
            color: Buffer2d::new(size, 0),
            depth: Buffer2d::new(size, DEPTH_CLEAR),
        }
    }

    /// The colours.
    pub fn pixels(&self) -> impl Iterator<Item = Rgb565> + '_ {
        self.color
            .as_ref()
            .iter()
            .map(|&bits| Rgb565::from(RawU16::new(bits)))
    }

    /// Which pixels were drawn.
    pub fn covered(&self) -> impl Iterator<Item = bool> + '_ {
        self.depth.as_ref().iter().map(|&d| d != DEPTH_CLEAR)
    }
}
