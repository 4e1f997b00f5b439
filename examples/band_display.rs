//! The 3D bench frame (the knot of `examples/common/scene3d.rs`, 320×240, lit, z-buffered,
//! Gouraud) drawn in 16-row bands into an embedded-graphics display — here the simulator's,
//! standing in for an SPI display driver — with two band buffers and 30 KB of RAM, and saved
//! as `docs/bands.png`: the frame, and beside it the bands as they were sent, one
//! `fill_contiguous` each, drawn apart.
//!
//! Run with `cargo run --release --example band_display`.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Rectangle};
use embedded_graphics::transform::Transform;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use embedded_raster::band::{BandLayout, Callback, ColorBands, DepthBands, ToDisplay};

#[allow(dead_code)]
#[path = "common/scene3d.rs"]
mod scene3d;

/// Rows of a band.
const ROWS: u32 = 16;

/// Pixels between the bands in the picture's exploded view.
const GAP: u32 = 3;

fn main() {
    let (w, h) = scene3d::SIZE;
    let layout = BandLayout::new(Size::new(w, h), ROWS).expect("a layout");
    let n = layout.buffer_len();
    let (mut front, mut back, mut depth) = (
        vec![Rgb565::BLACK; n],
        vec![Rgb565::BLACK; n],
        vec![0u16; n],
    );
    let colors = ColorBands::double(layout, &mut front, &mut back).expect("two band buffers");
    let mut bands = DepthBands::new(colors, &mut depth).expect("a depth band buffer");
    let pipeline = scene3d::pipeline(scene3d::Model::Knot);
    let draw = |band: &mut embedded_raster::band::DepthBand<'_, Rgb565>| {
        band.clear(scene3d::BACKGROUND);
        pipeline.draw_mesh(&scene3d::KNOT, &scene3d::MATERIAL, band);
    };

    // The display: the frame on the left, the bands drawn apart on the right.
    let gaps = (layout.count() - 1) * GAP;
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(2 * w + 16, h + gaps));
    display.clear(Rgb565::WHITE).expect("the simulator draws");
    {
        let mut frame = display.cropped(&Rectangle::new(Point::zero(), Size::new(w, h)));
        bands
            .render(&mut ToDisplay(&mut frame), draw)
            .expect("the simulator draws");
    }
    let mut index = 0;
    let mut exploded = Callback(|area: &Rectangle, pixels: &[Rgb565]| {
        let shift = Point::new(w as i32 + 16, (index * GAP) as i32);
        index += 1;
        display.fill_contiguous(&area.translate(shift), pixels.iter().copied())
    });
    bands
        .render(&mut exploded, draw)
        .expect("the simulator draws");
    let outline = Rectangle::new(Point::zero(), Size::new(w, h))
        .into_styled(PrimitiveStyle::with_stroke(Rgb565::CSS_GRAY, 1));
    outline.draw(&mut display).expect("the simulator draws");

    let path = "docs/bands.png";
    let settings = OutputSettingsBuilder::new().scale(2).build();
    display
        .to_rgb_output_image(&settings)
        .save_png(path)
        .expect("write PNG");
    println!("wrote {path}");
}
