//! The 3D bench frame (the knot of `examples/common/scene3d.rs`, 320×240, lit, z-buffered,
//! Gouraud) drawn in 16-row bands into a real display driver — mipidsi 0.10's ST7789, landscape —
//! over an embedded-hal 1.0 `SpiDevice` that records the bytes instead of a panel. The bytes
//! are replayed into a model of the controller (`examples/common/spi_panel.rs`: CASET, RASET,
//! RAMWR, MADCTL, COLMOD as the datasheet describes them), compared with the frame drawn whole,
//! and counted: the bytes a frame and a band take on the wire, and the frames a second an SPI
//! clock of 40 MHz and of 62.5 MHz carries.
//!
//! No hardware: run with `cargo run --release --example display_spi`.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::band::{BandLayout, ColorBands, DepthBand, DepthBands, ToDisplay};
use embedded_raster::three_d::{DepthTarget, ProjectedVertex};
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::{Orientation, Rotation};
use mipidsi::Builder;

#[allow(dead_code)]
#[path = "common/scene3d.rs"]
mod scene3d;

#[allow(dead_code)]
#[path = "common/spi_panel.rs"]
mod spi_panel;

use spi_panel::{first_difference, NoDelay, Panel, Recorder};

/// Rows of a band.
const ROWS: u32 = 16;

/// SPI clocks, Hz.
const CLOCKS: [(&str, f64); 2] = [("40 MHz", 40e6), ("62.5 MHz", 62.5e6)];

fn main() {
    let (w, h) = scene3d::SIZE;

    // The frame drawn whole: what the panel should show.
    let mut want = vec![Rgb565::BLACK; scene3d::PIXELS];
    let mut depth = vec![0u16; scene3d::PIXELS];
    {
        let mut target = DepthTarget::new(&mut want, &mut depth, w, h).expect("a target");
        let mut scratch = vec![ProjectedVertex::EMPTY; scene3d::KNOT.vertices.len()];
        scene3d::render(
            scene3d::Model::Knot,
            &scene3d::KNOT,
            &mut target,
            Some(&mut scratch),
        );
    }

    // The driver on the recording bus, landscape (320 × 240).
    let recorder = Recorder::new();
    let mut buffer = [0u8; 512];
    let interface = SpiInterface::new(recorder.spi(), recorder.dc(), &mut buffer);
    let mut display = Builder::new(ST7789, interface)
        .orientation(Orientation::new().rotate(Rotation::Deg90))
        .init(&mut NoDelay)
        .expect("the recording bus does not fail");
    let mut panel = Panel::st7789();
    let init = recorder.take();
    panel.replay(&init.bytes);
    assert!(panel.ready(), "awake, on and 16 bits a pixel");

    // The frame in bands of 16 rows, one `fill_contiguous` a band.
    let layout = BandLayout::new(Size::new(w, h), ROWS).expect("a layout");
    let n = layout.buffer_len();
    let (mut front, mut back, mut band_depth) = (
        vec![Rgb565::BLACK; n],
        vec![Rgb565::BLACK; n],
        vec![0u16; n],
    );
    let colors = ColorBands::double(layout, &mut front, &mut back).expect("two band buffers");
    let mut bands = DepthBands::new(colors, &mut band_depth).expect("a depth band buffer");
    let pipeline = scene3d::pipeline(scene3d::Model::Knot);
    bands
        .render(
            &mut ToDisplay(&mut display),
            |band: &mut DepthBand<'_, Rgb565>| {
                band.clear(scene3d::BACKGROUND);
                pipeline.draw_mesh(&scene3d::KNOT, &scene3d::MATERIAL, band);
            },
        )
        .expect("the recording bus does not fail");
    let banded = recorder.take();
    panel.reset_counts();
    panel.replay(&banded.bytes);
    let got = panel.frame(w as u16, h as u16);
    assert_eq!(
        first_difference(&want, &got, w as usize),
        None,
        "the panel shows the frame"
    );
    let band_counts = panel.counts().clone();

    // The frame drawn whole, blitted in one window, for comparison.
    display
        .fill_contiguous(
            &Rectangle::new(Point::zero(), Size::new(w, h)),
            want.iter().copied(),
        )
        .expect("the recording bus does not fail");
    let blit = recorder.take();
    panel.reset_counts();
    panel.replay(&blit.bytes);
    assert_eq!(
        first_difference(&want, &panel.frame(w as u16, h as u16), w as usize),
        None
    );
    let blit_counts = panel.counts().clone();

    let count = layout.count() as usize;
    let band_bytes = band_counts.total() / count;
    println!(
        "ST7789 (mipidsi 0.10, landscape, MADCTL {:#04x}) over a recording SPI: the knot frame \
         {w}x{h} Rgb565 decoded from the bytes equals the frame drawn whole.",
        panel.madctl()
    );
    println!("initialisation: {} bytes", init.bytes.len());
    println!();
    println!("| sent | bytes | SPI transactions | 40 MHz | 62.5 MHz |");
    println!("|---|---:|---:|---:|---:|");
    let rows: [(&str, usize, usize, bool); 3] = [
        (
            "frame blitted whole (one window)",
            blit_counts.total(),
            blit.transactions.len(),
            true,
        ),
        (
            "frame in 16-row bands (15 windows)",
            band_counts.total(),
            banded.transactions.len(),
            true,
        ),
        (
            "one 16-row band",
            band_bytes,
            banded.transactions.len() / count,
            false,
        ),
    ];
    for (what, bytes, transactions, frame) in rows {
        let mut line = format!("| {what} | {bytes} | {transactions} |");
        for (_, clock) in CLOCKS {
            let seconds = bytes as f64 * 8.0 / clock;
            if frame {
                line += &format!(" {:.2} ms, {:.1} fps |", seconds * 1e3, 1.0 / seconds);
            } else {
                line += &format!(" {:.3} ms |", seconds * 1e3);
            }
        }
        println!("{line}");
    }
    println!();
    println!(
        "Times and fps are the bits (bytes × 8) at the clock, with no gaps between bytes or \
         transactions (a DMA transfer comes close; a CPU-fed SPI does not), and no D/C or chip \
         select set-up time."
    );
}
