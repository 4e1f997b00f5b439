//! Wireframes of the 3D bench meshes (`examples/common/scene3d.rs`, 320×240, 16-bit z) saved as
//! `docs/wireframe.png`: the knot as a hidden-line drawing (its faces filled in the background
//! colour, then their edges: the edges behind faces hidden), and spot Gouraud-lit with its
//! edges over it.
//!
//! Run with `cargo run --release --example wireframe`.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use embedded_raster::three_d::{DepthTarget, Material, Shading};

#[allow(dead_code)]
#[path = "common/scene3d.rs"]
mod scene3d;

fn main() {
    let (w, h) = scene3d::SIZE;
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(2 * w + 8, h));
    display.clear(Rgb565::WHITE).expect("the simulator draws");
    let (mut colors, mut depth) = (
        vec![Rgb565::BLACK; scene3d::PIXELS],
        vec![0u16; scene3d::PIXELS],
    );
    let panels = [
        (scene3d::Model::Knot, None, Rgb565::new(8, 52, 20)),
        (
            scene3d::Model::Spot,
            Some(scene3d::MATERIAL),
            Rgb565::new(4, 10, 6),
        ),
    ];
    for (k, (model, material, edges)) in panels.into_iter().enumerate() {
        let mut target = DepthTarget::new(&mut colors, &mut depth, w, h).expect("buffers fit");
        target.clear(scene3d::BACKGROUND);
        let pipeline = scene3d::pipeline(model);
        let mesh = model.mesh(&scene3d::KNOT);
        // Hidden lines: the faces in the background colour fill the z-buffer.
        let faces = material.unwrap_or(Material::new(scene3d::BACKGROUND, Shading::Unlit));
        pipeline.draw_mesh(mesh, &faces, &mut target);
        pipeline.draw_wireframe(mesh, edges, &mut target);
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
