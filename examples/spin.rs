//! The interactive view of the 3D pipeline: a lit torus and icosphere rotating in an SDL window
//! of embedded-graphics-simulator, rendered every frame by the fixed-point pipeline.
//!
//! Needs SDL2 (`apt-get install libsdl2-dev`) and the `sdl` feature:
//! `cargo run --release --features sdl --example spin`. Space cycles flat → Gouraud →
//! quadratic normals; closing the window quits. `--frames N` renders N frames and exits.

use embedded_graphics::{pixelcolor::Rgb888, prelude::*, primitives::Rectangle};
use embedded_graphics_simulator::{
    sdl2::Keycode, OutputSettingsBuilder, SimulatorDisplay, SimulatorEvent, Window,
};
use embedded_raster::three_d::meshes::{icosphere::ICOSPHERE, torus::TORUS};
use embedded_raster::three_d::{Angle, Mat4, Scalar, Vec3};
use embedded_raster::three_d::{DepthTarget, Mesh, Pipeline};
use embedded_raster::three_d::{Light, Material, Shading};

const W: u32 = 320;
const H: u32 = 160;
const BACKGROUND: Rgb888 = Rgb888::new(24, 26, 32);

fn s(v: f64) -> Scalar {
    Scalar::from_num(v)
}

/// Draws `mesh` turned by `frame` into the half of the screen at `column`.
fn draw(
    target: &mut DepthTarget<'_, Rgb888>,
    mesh: &Mesh<'_>,
    column: u32,
    frame: i32,
    shading: Shading,
    color: Rgb888,
) {
    let viewport = Rectangle::new(Point::new((column * W / 2) as i32, 0), Size::new(W / 2, H));
    let projection = Mat4::perspective(Angle::from_degrees(40), s(1.0), s(0.5), s(20.0)).unwrap();
    let view = Mat4::translation(Vec3::new(s(0.0), s(0.0), s(-4.2)));
    let model = Mat4::rotation_y(Angle::from_degrees(frame * 2))
        * Mat4::rotation_x(Angle::from_degrees(frame * 3 - 60));
    let light = Light::new(Vec3::new(s(-0.5), s(0.7), s(0.6)), s(0.12));
    let pipeline = Pipeline::new(model, projection * view, viewport, light);
    pipeline.draw_mesh(mesh, &Material::new(color, shading), target);
}

fn main() {
    let frames: Option<u32> = std::env::args()
        .skip_while(|a| a != "--frames")
        .nth(1)
        .and_then(|n| n.parse().ok());
    let modes = [Shading::Flat, Shading::Gouraud, Shading::Quadratic];
    let mut mode = 2;
    let mut pixels = vec![BACKGROUND; (W * H) as usize];
    let mut depth = vec![0u16; (W * H) as usize];
    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(W, H));
    let mut window = Window::new(
        "embedded-raster",
        &OutputSettingsBuilder::new().scale(3).build(),
    );
    window.set_max_fps(30);
    for frame in 0.. {
        if frames.is_some_and(|n| frame >= n as i32) {
            break;
        }
        let mut target = DepthTarget::new(&mut pixels, &mut depth, W, H).expect("buffers fit");
        target.clear(BACKGROUND);
        draw(
            &mut target,
            &TORUS,
            0,
            frame,
            modes[mode],
            Rgb888::new(120, 190, 250),
        );
        draw(
            &mut target,
            &ICOSPHERE,
            1,
            frame,
            modes[mode],
            Rgb888::new(250, 190, 110),
        );
        display
            .fill_contiguous(
                &Rectangle::new(Point::zero(), Size::new(W, H)),
                pixels.iter().copied(),
            )
            .expect("infallible");
        window.update(&display);
        for event in window.events() {
            match event {
                SimulatorEvent::Quit => return,
                SimulatorEvent::KeyDown {
                    keycode: Keycode::Space,
                    ..
                } => mode = (mode + 1) % modes.len(),
                _ => {}
            }
        }
    }
}
