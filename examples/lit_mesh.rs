//! Renders a lit icosphere and torus three ways side by side into `docs/lit_mesh.png`:
//! flat (one Lambert intensity per face), Gouraud (per vertex, interpolated) and per-pixel
//! lighting of quadratically interpolated normals. The meshes are the coarse ones stored in
//! flash for firmware (`meshes::icosphere::ICOSPHERE`, 80 faces; `meshes::torus::TORUS`,
//! 192 faces), drawn by the fixed-point pipeline into an `Rgb888` framebuffer with a 16-bit
//! z-buffer.
//!
//! And `docs/wireframe.png`: wireframes of the 3D bench meshes (`examples/common/scene3d.rs`,
//! 320×240, 16-bit z) — the knot as a hidden-line drawing (its faces filled in the background
//! colour, then their edges: the edges behind faces hidden), and spot Gouraud-lit with its edges
//! over it (`Pipeline::draw_wireframe`).
//!
//! Run with `cargo run --release --features std --example lit_mesh`.
//!
//! The rotating, interactive view is `examples/spin.rs` (feature `sdl`, needs SDL2).

use embedded_graphics::{
    mono_font::{ascii::FONT_6X10, MonoTextStyle},
    pixelcolor::Rgb888,
    prelude::*,
    primitives::Rectangle,
    text::Text,
};
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use embedded_raster::three_d::meshes::{icosphere::ICOSPHERE, torus::TORUS};
use embedded_raster::three_d::{Angle, Mat4, Scalar, Vec3};
use embedded_raster::three_d::{DepthTarget, Mesh, Pipeline};
use embedded_raster::three_d::{Light, Material, Shading};

#[allow(dead_code)]
#[path = "common/scene3d.rs"]
mod scene3d;

const PANEL_W: u32 = 220;
const PANEL_H: u32 = 200;
const LABEL_H: u32 = 14;

fn s(v: f64) -> Scalar {
    Scalar::from_num(v)
}

/// Draws `mesh` rotated by `yaw`/`pitch`/`roll` into the panel at `(column, row)`.
#[allow(clippy::too_many_arguments)]
fn draw_panel(
    target: &mut DepthTarget<'_, Rgb888>,
    mesh: &Mesh<'_>,
    shading: Shading,
    color: Rgb888,
    column: u32,
    row: u32,
    rotation: Mat4,
    distance: f64,
) {
    let viewport = Rectangle::new(
        Point::new(
            (column * PANEL_W) as i32,
            (row * (PANEL_H + LABEL_H) + LABEL_H) as i32,
        ),
        Size::new(PANEL_W, PANEL_H),
    );
    let aspect = Scalar::from_num(PANEL_W) / Scalar::from_num(PANEL_H);
    let projection = Mat4::perspective(Angle::from_degrees(40), aspect, s(0.5), s(20.0)).unwrap();
    let view = Mat4::translation(Vec3::new(s(0.0), s(0.0), s(-distance)));
    // World-space light from the upper left, slightly in front.
    let light = Light::new(Vec3::new(s(-0.5), s(0.7), s(0.6)), s(0.12));
    let pipeline = Pipeline::new(rotation, projection * view, viewport, light);
    pipeline.draw_mesh(mesh, &Material::new(color, shading), target);
}

fn render() -> SimulatorDisplay<Rgb888> {
    let (w, h) = (3 * PANEL_W, 2 * (PANEL_H + LABEL_H));
    let mut pixels = vec![Rgb888::new(24, 26, 32); (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    let mut target = DepthTarget::new(&mut pixels, &mut depth, w, h).expect("buffers fit");
    target.clear(Rgb888::new(24, 26, 32));

    let sphere_rotation =
        Mat4::rotation_y(Angle::from_degrees(20)) * Mat4::rotation_x(Angle::from_degrees(-15));
    let torus_rotation =
        Mat4::rotation_x(Angle::from_degrees(-60)) * Mat4::rotation_z(Angle::from_degrees(10));
    let modes = [
        (Shading::Flat, "flat"),
        (Shading::Gouraud, "Gouraud"),
        (Shading::Quadratic, "quadratic normals"),
    ];
    let style = MonoTextStyle::new(&FONT_6X10, Rgb888::new(220, 220, 220));
    for (column, (shading, name)) in modes.iter().enumerate() {
        let column = column as u32;
        draw_panel(
            &mut target,
            &ICOSPHERE,
            *shading,
            Rgb888::new(250, 190, 110),
            column,
            0,
            sphere_rotation,
            3.6,
        );
        draw_panel(
            &mut target,
            &TORUS,
            *shading,
            Rgb888::new(120, 190, 250),
            column,
            1,
            torus_rotation,
            4.4,
        );
        for row in 0..2 {
            let faces = [ICOSPHERE.indices.len(), TORUS.indices.len()][row];
            let label = format!("{name}, {faces} faces");
            let at = Point::new(
                (column * PANEL_W + 6) as i32,
                (row as u32 * (PANEL_H + LABEL_H) + 10) as i32,
            );
            Text::new(&label, at, style)
                .draw(&mut target)
                .expect("infallible");
        }
    }

    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(w, h));
    display
        .fill_contiguous(&Rectangle::new(Point::zero(), Size::new(w, h)), pixels)
        .expect("infallible");
    display
}

fn main() {
    let display = render();
    let settings = OutputSettingsBuilder::new().scale(2).build();
    let path = "docs/lit_mesh.png";
    std::fs::create_dir_all("docs").expect("create docs/");
    display
        .to_rgb_output_image(&settings)
        .save_png(path)
        .expect("write PNG");
    println!("wrote {path}");
    wireframes();
}

/// `docs/wireframe.png`.
fn wireframes() {
    use embedded_graphics::pixelcolor::Rgb565;
    let (w, h) = scene3d::SIZE;
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(2 * w + 8, h));
    display.clear(Rgb565::WHITE).expect("the simulator draws");
    let (mut colors, mut depth) = (
        vec![Rgb565::BLACK; scene3d::PIXELS],
        vec![0u16; scene3d::PIXELS],
    );
    for (k, model) in [scene3d::Model::Knot, scene3d::Model::Spot]
        .into_iter()
        .enumerate()
    {
        let mut target = DepthTarget::new(&mut colors, &mut depth, w, h).expect("buffers fit");
        let mesh = model.mesh(&scene3d::KNOT);
        if model == scene3d::Model::Knot {
            // Hidden lines: the faces in the background colour fill the z-buffer.
            scene3d::render_wireframe(model, mesh, &mut target, None);
        } else {
            // The lit frame with its edges over it.
            scene3d::render(model, mesh, &mut target, None);
            let edges = Rgb565::new(4, 10, 6);
            scene3d::pipeline(model).draw_wireframe(mesh, edges, &mut target);
        }
        let at = Rectangle::new(Point::new(k as i32 * (w as i32 + 8), 0), Size::new(w, h));
        display
            .fill_contiguous(&at, colors.iter().copied())
            .expect("the simulator draws");
    }
    let path = "docs/wireframe.png";
    let settings = OutputSettingsBuilder::new().scale(1).build();
    display
        .to_rgb_output_image(&settings)
        .save_png(path)
        .expect("write PNG");
    println!("wrote {path}");
}
