//! `Pipeline::draw_mesh` with arbitrary matrices (raw, or cameras built from arbitrary
//! parameters), small arbitrary meshes (indices out of range included), viewports anywhere
//! (huge rectangles too), lights built from their public fields, every `Shading` and `Cull`, in
//! Rgb565 and Rgb888, into a `DepthTarget` of up to 48 × 48: no panic; no colour or depth
//! written outside viewport ∩ target (checked per pixel in `i64` against a cleared buffer);
//! every depth written is at most `DEPTH_FAR`; every face is counted once in the statistics;
//! `draw_mesh_with` (a scratch of any length) draws the same pixels and depths with the same
//! statistics, or nothing and `ScratchTooSmall` when the scratch is shorter than the mesh.
#![no_main]

use arbitrary::Arbitrary;
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_raster::three_d::{
    Angle, Cull, DepthTarget, Light, Mat4, Material, Mesh, Pipeline, ProjectedVertex, Scalar,
    Shading, Vec3, DEPTH_CLEAR, DEPTH_FAR,
};
use embedded_raster::GouraudColor;
use embedded_raster_fuzz::{inside, AnyRect, Int};
use libfuzzer_sys::fuzz_target;

#[derive(Arbitrary, Debug, Clone, Copy)]
enum Matrix {
    Raw([[Int; 4]; 4]),
    /// perspective · translation · rotations · scaling from arbitrary parameters.
    Camera {
        fov: u16,
        aspect: Int,
        near: Int,
        far: Int,
        turn: [u16; 3],
        shift: [Int; 3],
        scale: Int,
    },
    Identity,
}

impl Matrix {
    fn get(self) -> Mat4 {
        match self {
            Matrix::Raw(m) => Mat4::from_bits(m.map(|row| row.map(Int::get))),
            Matrix::Camera {
                fov,
                aspect,
                near,
                far,
                turn,
                shift,
                scale,
            } => {
                let s = |v: Int| Scalar::from_bits(v.get());
                // Parameters that show nothing have no projection (`None`): the identity then.
                Mat4::perspective(Angle(fov), s(aspect), s(near), s(far)).unwrap_or(Mat4::IDENTITY)
                    * Mat4::translation(Vec3::from_bits(
                        shift[0].get(),
                        shift[1].get(),
                        shift[2].get(),
                    ))
                    * Mat4::rotation_x(Angle(turn[0]))
                    * Mat4::rotation_y(Angle(turn[1]))
                    * Mat4::rotation_z(Angle(turn[2]))
                    * Mat4::scaling(s(scale))
            }
            Matrix::Identity => Mat4::IDENTITY,
        }
    }
}

#[derive(Arbitrary, Debug, Clone, Copy)]
enum Viewport {
    /// The whole target.
    Target,
    Any(AnyRect),
}

#[derive(Arbitrary, Debug)]
struct Input {
    width: u8,
    height: u8,
    model: Matrix,
    view_projection: Matrix,
    normal_matrix: Option<Matrix>,
    viewport: Viewport,
    light_direction: [Int; 3],
    light_ambient: Int,
    cull: u8,
    shading: u8,
    rgb565: bool,
    color: (u8, u8, u8),
    vertices: Vec<[Int; 3]>,
    normals: Vec<[Int; 3]>,
    faces: Vec<[u8; 3]>,
    scratch: u8,
}

fn vec3(v: &[Int; 3]) -> Vec3 {
    Vec3::from_bits(v[0].get(), v[1].get(), v[2].get())
}

fn run<C: GouraudColor>(
    input: &Input,
    pipeline: &Pipeline,
    mesh: &Mesh<'_>,
    color: C,
    background: C,
) {
    let (width, height) = (u32::from(input.width % 49), u32::from(input.height % 49));
    let n = (width * height) as usize;
    let (mut pixels, mut depth) = (vec![background; n], vec![DEPTH_CLEAR; n]);
    let mut target = DepthTarget::new(&mut pixels, &mut depth, width, height).unwrap();
    let shading = [
        Shading::Unlit,
        Shading::Flat,
        Shading::Gouraud,
        Shading::Quadratic,
    ][usize::from(input.shading % 4)];
    let stats = pipeline.draw_mesh(mesh, &Material::new(color, shading), &mut target);
    assert_eq!(
        stats.drawn + stats.rejected + stats.culled + stats.degenerate + stats.invalid,
        mesh.indices.len() as u32,
        "faces not counted once: {stats:?}"
    );
    for y in 0..height as i32 {
        for x in 0..width as i32 {
            let z = target.depth_at(x, y).unwrap();
            let c = target.framebuffer().get(x, y).unwrap();
            if z == DEPTH_CLEAR && c == background {
                continue;
            }
            assert!(
                inside(&pipeline.viewport, x, y),
                "pixel ({x}, {y}) written outside the viewport {:?}",
                pipeline.viewport
            );
            assert!(z <= DEPTH_FAR, "depth {z} at ({x}, {y})");
        }
    }

    let (mut pixels_with, mut depth_with) = (vec![background; n], vec![DEPTH_CLEAR; n]);
    let mut target_with =
        DepthTarget::new(&mut pixels_with, &mut depth_with, width, height).unwrap();
    let mut scratch = vec![ProjectedVertex::default(); usize::from(input.scratch % 10)];
    let material = Material::new(color, shading);
    match pipeline.draw_mesh_with(mesh, &material, &mut target_with, &mut scratch) {
        Ok(stats_with) => {
            assert!(
                scratch.len() >= mesh.vertices.len(),
                "drew with a short scratch"
            );
            assert_eq!(stats_with, stats, "draw_mesh_with counted differently");
            assert!(pixels_with == pixels, "draw_mesh_with drew other colours");
            assert!(depth_with == depth, "draw_mesh_with drew other depths");
        }
        Err(e) => {
            assert!(
                scratch.len() < mesh.vertices.len(),
                "ScratchTooSmall with enough: {e:?}"
            );
            assert!(
                pixels_with.iter().all(|&c| c == background),
                "drew and said ScratchTooSmall"
            );
            assert!(
                depth_with.iter().all(|&z| z == DEPTH_CLEAR),
                "drew and said ScratchTooSmall"
            );
        }
    }
}

fuzz_target!(|input: Input| {
    let (width, height) = (u32::from(input.width % 49), u32::from(input.height % 49));
    let viewport = match input.viewport {
        Viewport::Target => {
            embedded_graphics::primitives::Rectangle::new(Point::zero(), Size::new(width, height))
        }
        Viewport::Any(r) => r.get(),
    };
    let direction = vec3(&input.light_direction);
    let ambient = Scalar::from_bits(input.light_ambient.get());
    // Light's fields are private: every light comes from the constructor.
    let light = Light::new(direction, ambient);
    let mut pipeline = Pipeline::new(
        input.model.get(),
        input.view_projection.get(),
        viewport,
        light,
    );
    if let Some(m) = input.normal_matrix {
        pipeline.normal_matrix = m.get();
    }
    pipeline.cull = [Cull::None, Cull::Back, Cull::Front][usize::from(input.cull % 3)];
    let vertices: Vec<Vec3> = input.vertices.iter().take(8).map(vec3).collect();
    let normals: Vec<Vec3> = input.normals.iter().take(8).map(vec3).collect();
    // Indices up to 9: some out of range of the (at most 8) vertices.
    let indices: Vec<[u16; 3]> = input
        .faces
        .iter()
        .take(8)
        .map(|f| f.map(|i| u16::from(i % 10)))
        .collect();
    let mesh = Mesh::new(&vertices, &normals, &indices);
    let (r, g, b) = input.color;
    if input.rgb565 {
        let background = Rgb565::new(1, 2, 3);
        run(
            &input,
            &pipeline,
            &mesh,
            Rgb565::new(r >> 3, g >> 2, b >> 3),
            background,
        );
    } else {
        run(
            &input,
            &pipeline,
            &mesh,
            Rgb888::new(r, g, b),
            Rgb888::new(1, 2, 3),
        );
    }
});
