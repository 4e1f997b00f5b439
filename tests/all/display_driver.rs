//! A real display driver end to end: mipidsi 0.10 (the embedded-graphics driver of ST7789 and
//! ILI9341 panels) over an embedded-hal 1.0 `SpiDevice` that records the bytes, replayed into a
//! model of the controller written from the datasheets' command descriptions
//! (`examples/common/spi_panel.rs`), and compared pixel for pixel with the 3D bench frame drawn
//! whole: blitted from a `SliceFramebuffer`, drawn in bands through `ToDisplay`, and in bands
//! through a `Callback` that sends each band's bytes as one transfer, the way a DMA channel
//! would.
//!
//! The display is landscape, 320 × 240 (mipidsi's `Rotation::Deg90` of the 240 × 320
//! controllers): the scenes' size. The wire's bytes are counted against the datasheets' framing
//! (a window is CASET and RASET, 1 + 4 bytes each, and RAMWR, 1 byte, then 2 bytes a pixel);
//! `cargo test --test all -- display_driver --nocapture` prints them.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::band::{BandLayout, Callback, ColorBands, DepthBand, DepthBands, ToDisplay};
use embedded_raster::three_d::{DepthTarget, ProjectedVertex};
use embedded_raster::SliceFramebuffer;
use mipidsi::dcs::{InterfaceExt, SetColumnAddress, SetPageAddress};
use mipidsi::interface::SpiInterface;
use mipidsi::models::{ILI9341Rgb565, Model, ST7789};
use mipidsi::options::{Orientation, Rotation};
use mipidsi::{Builder, Display, NoResetPin};

use crate::scene3d;

#[allow(dead_code)]
#[path = "../../examples/common/spi_panel.rs"]
mod spi_panel;

use spi_panel::{first_difference, panel_bytes, Byte, NoDelay, Panel, Recorder, RecordingSpi};

/// The landscape frame.
const W: u16 = 320;
const H: u16 = 240;

/// Bytes of a window's commands: CASET and RASET (a command byte and four parameters each),
/// RAMWR (a command byte).
const WINDOW: usize = 5 + 5 + 1;

/// Bytes of a 320 × 240 frame's pixels at 16 bits a pixel.
const FRAME_PIXEL_BYTES: usize = 320 * 240 * 2;

type Driver<'b, M> = Display<SpiInterface<'b, RecordingSpi, spi_panel::DcPin>, M, NoResetPin>;

/// `model` on a recording bus, landscape, initialised; its pixel buffer is `buffer` (mipidsi
/// sends pixels in chunks of its size). The log holds the initialisation.
fn driver<'b, M: Model<ColorFormat = Rgb565>>(
    model: M,
    recorder: &Recorder,
    buffer: &'b mut [u8],
) -> Driver<'b, M> {
    let interface = SpiInterface::new(recorder.spi(), recorder.dc(), buffer);
    let display = Builder::new(model, interface)
        .orientation(Orientation::new().rotate(Rotation::Deg90))
        .init(&mut NoDelay)
        .expect("the recording bus does not fail");
    assert_eq!(display.size(), Size::new(W.into(), H.into()));
    display
}

/// The knot frame of the benchmarks (`scene3d`), drawn whole.
fn whole_frame(model: scene3d::Model) -> Vec<Rgb565> {
    let (w, h) = scene3d::SIZE;
    let mut colors = vec![Rgb565::BLACK; scene3d::PIXELS];
    let mut depth = vec![0; scene3d::PIXELS];
    let mut target = DepthTarget::new(&mut colors, &mut depth, w, h).unwrap();
    let mesh = model.mesh(&scene3d::KNOT);
    let mut scratch = vec![ProjectedVertex::EMPTY; mesh.vertices.len()];
    scene3d::render(model, mesh, &mut target, Some(&mut scratch));
    colors
}

/// Replays `init` then `frame` into `panel`; checks the panel is ready after `init` and that
/// the frame's bytes show `want` with nothing left unwritten, and returns the frame's counts.
fn check(
    panel: &mut Panel,
    init: &[Byte],
    frame: &[Byte],
    want: &[Rgb565],
    what: &str,
) -> spi_panel::Counts {
    panel.replay(init);
    assert!(
        panel.ready(),
        "{what}: the panel is awake, on and 16-bit after init"
    );
    panel.reset_counts();
    panel.replay(frame);
    let got = panel.frame(W, H);
    assert_eq!(
        first_difference(want, &got, W.into()),
        None,
        "{what}: the first pixel that differs"
    );
    // The host's view is not mirrored: the memory holds the frame turned a quarter.
    let turn = panel.rotation(want);
    assert!(turn.is_some(), "{what}: a quarter turn");
    println!(
        "{what}: MADCTL {:#04x}, the frame turned {}° clockwise in the portrait memory",
        panel.madctl(),
        turn.unwrap_or(0)
    );
    panel.counts().clone()
}

/// A full-frame blit of a `SliceFramebuffer`: one window, every pixel once, and the bytes on
/// the wire are the frame's pixels and one window's commands — for an ST7789 and an ILI9341.
#[test]
fn a_framebuffer_blit_arrives_whole() {
    for scene in [scene3d::Model::Knot, scene3d::Model::Spot] {
        let mut colors = whole_frame(scene);
        let framebuffer = SliceFramebuffer::new(&mut colors, W.into(), H.into()).unwrap();
        blit(ST7789, Panel::st7789(), &framebuffer, "ST7789");
        blit(ILI9341Rgb565, Panel::ili9341(), &framebuffer, "ILI9341");
    }
}

/// `framebuffer` blitted whole (one `fill_contiguous`) to `model`, replayed into `panel`.
fn blit<M: Model<ColorFormat = Rgb565>>(
    model: M,
    mut panel: Panel,
    framebuffer: &SliceFramebuffer<'_, Rgb565>,
    name: &str,
) {
    let recorder = Recorder::new();
    let mut buffer = [0u8; 512];
    let mut display = driver(model, &recorder, &mut buffer);
    let init = recorder.take().bytes;
    let area = Rectangle::new(Point::zero(), framebuffer.size());
    display
        .fill_contiguous(&area, framebuffer.pixels().iter().copied())
        .unwrap();
    let frame = recorder.take();
    let counts = check(&mut panel, &init, &frame.bytes, framebuffer.pixels(), name);
    check_blit(&counts, &frame.transactions, name);
}

/// One window, the frame's pixel bytes, in transactions of at most the driver's buffer.
fn check_blit(counts: &spi_panel::Counts, transactions: &[usize], name: &str) {
    assert_eq!(counts.count(0x2C), 1, "{name}: one RAMWR");
    assert_eq!(counts.count(0x2A), 1, "{name}: one CASET");
    assert_eq!(counts.count(0x2B), 1, "{name}: one RASET");
    assert_eq!(counts.commands.len(), 3, "{name}: no other command");
    assert_eq!(counts.pixel_bytes, FRAME_PIXEL_BYTES);
    assert_eq!(counts.total(), FRAME_PIXEL_BYTES + WINDOW);
    assert_eq!(transactions.iter().sum::<usize>(), counts.total());
    assert!(transactions.iter().all(|&n| n <= 512));
    println!(
        "{name} blit of a 320x240 Rgb565 framebuffer: {} bytes ({} pixel bytes + {} of commands), {} SPI transactions with a 512-byte driver buffer",
        counts.total(),
        counts.pixel_bytes,
        counts.total() - counts.pixel_bytes,
        transactions.len()
    );
}

/// Bands of the knot frame of `rows` rows, drawn into `output`.
fn render_bands<O: embedded_raster::band::BandOutput<Rgb565>>(
    rows: u32,
    output: &mut O,
) -> Result<(), embedded_raster::band::RenderError<O::Error>> {
    let layout = BandLayout::new(Size::new(W.into(), H.into()), rows).unwrap();
    let n = layout.buffer_len();
    let (mut front, mut back, mut depth) = (
        vec![Rgb565::BLACK; n],
        vec![Rgb565::BLACK; n],
        vec![0u16; n],
    );
    let colors = ColorBands::double(layout, &mut front, &mut back).unwrap();
    let mut bands = DepthBands::new(colors, &mut depth).unwrap();
    let pipeline = scene3d::pipeline(scene3d::Model::Knot);
    bands.render(output, |band: &mut DepthBand<'_, Rgb565>| {
        band.clear(scene3d::BACKGROUND);
        pipeline.draw_mesh(&scene3d::KNOT, &scene3d::MATERIAL, band);
    })
}

/// Band heights: a few that divide 240, the whole frame, and one that leaves a short last
/// band (240 = 6 × 36 + 24).
const ROWS: [u32; 5] = [8, 16, 30, 240, 36];

/// The bands of a frame, drawn through `ToDisplay` straight into the driver: a window per band,
/// the same pixels as the frame drawn whole.
#[test]
fn bands_through_to_display_arrive_whole() {
    let want = whole_frame(scene3d::Model::Knot);
    for rows in ROWS {
        let recorder = Recorder::new();
        let mut buffer = [0u8; 512];
        let mut display = driver(ST7789, &recorder, &mut buffer);
        let init = recorder.take().bytes;
        render_bands(rows, &mut ToDisplay(&mut display)).unwrap();
        let frame = recorder.take();
        let what = format!("{rows}-row bands through ToDisplay");
        let counts = check(&mut Panel::st7789(), &init, &frame.bytes, &want, &what);
        let bands = 240_usize.div_ceil(rows as usize);
        assert_eq!(counts.count(0x2C), bands, "{what}: a RAMWR a band");
        assert_eq!(counts.count(0x2A), bands);
        assert_eq!(counts.count(0x2B), bands);
        assert_eq!(counts.commands.len(), 3);
        assert_eq!(counts.pixel_bytes, FRAME_PIXEL_BYTES);
        assert_eq!(counts.total(), FRAME_PIXEL_BYTES + bands * WINDOW);
        println!(
            "{what}: {bands} bands, {} bytes a frame, {} bytes a full band ({} pixel bytes + {WINDOW})",
            counts.total(),
            320 * 2 * rows as usize + WINDOW,
            320 * 2 * rows as usize,
        );
    }
}

/// The bands through a `Callback` as a DMA transfer takes them: the window set through the
/// driver's command interface, then RAMWR and the band's bytes, converted here to the panel's
/// big-endian 5-6-5, in one SPI write.
#[test]
fn bands_through_a_dma_style_callback_arrive_whole() {
    let want = whole_frame(scene3d::Model::Knot);
    for rows in ROWS {
        let recorder = Recorder::new();
        let mut buffer = [0u8; 512];
        let mut display = driver(ST7789, &recorder, &mut buffer);
        let init = recorder.take().bytes;
        let mut bytes = Vec::new();
        let mut sent = 0;
        let mut dma = Callback(|area: &Rectangle, pixels: &[Rgb565]| {
            panel_bytes(pixels, &mut bytes);
            let end = area.bottom_right().expect("a band is not empty");
            // SAFETY (of the state, not memory): the window and RAMWR are all this sends; the
            // orientation mipidsi set stays.
            let dcs = unsafe { display.dcs() };
            dcs.write_command(SetColumnAddress::new(area.top_left.x as u16, end.x as u16))?;
            dcs.write_command(SetPageAddress::new(area.top_left.y as u16, end.y as u16))?;
            sent += 1;
            dcs.write_raw(0x2C, &bytes)
        });
        render_bands(rows, &mut dma).unwrap();
        let frame = recorder.take();
        let what = format!("{rows}-row bands through a DMA-style callback");
        let counts = check(&mut Panel::st7789(), &init, &frame.bytes, &want, &what);
        let bands = 240_usize.div_ceil(rows as usize);
        assert_eq!(sent, bands);
        assert_eq!(counts.count(0x2C), bands, "{what}: a RAMWR a band");
        assert_eq!(counts.total(), FRAME_PIXEL_BYTES + bands * WINDOW);
        // Each band's pixels went out in one transaction: the largest is a full band.
        let full = 320 * 2 * rows as usize;
        assert_eq!(frame.transactions.iter().max(), Some(&full), "{what}");
        assert_eq!(
            frame.transactions.iter().filter(|&&n| n >= 2 * 320).count(),
            bands,
            "{what}: one pixel transfer a band"
        );
    }
}

/// The comparison sees one wrong bit, and bytes in the wrong order: the frame's log replayed
/// with the first byte of pixel (5, 7) changed, or with every pixel's two bytes swapped, is not
/// the frame.
#[test]
fn the_comparison_sees_one_wrong_pixel() {
    let want = whole_frame(scene3d::Model::Knot);
    let recorder = Recorder::new();
    let mut buffer = [0u8; 512];
    let mut display = driver(ST7789, &recorder, &mut buffer);
    let init = recorder.take().bytes;
    display
        .fill_contiguous(
            &Rectangle::new(Point::zero(), Size::new(W.into(), H.into())),
            want.iter().copied(),
        )
        .unwrap();
    let frame = recorder.take().bytes;
    // The pixel data starts after the last command byte (RAMWR).
    let start = frame.iter().rposition(|b| !b.data).unwrap() + 1;
    assert_eq!(frame.len() - start, FRAME_PIXEL_BYTES);

    let mut flipped = frame.clone();
    flipped[start + 2 * (7 * 320 + 5)].value ^= 0x08;
    let mut panel = Panel::st7789();
    panel.replay(&init);
    panel.replay(&flipped);
    assert_eq!(
        first_difference(&want, &panel.frame(W, H), W.into()),
        Some((5, 7))
    );

    let mut swapped = frame.clone();
    for pair in swapped[start..].chunks_exact_mut(2) {
        pair.swap(0, 1);
    }
    let mut panel = Panel::st7789();
    panel.replay(&init);
    panel.replay(&swapped);
    assert_ne!(first_difference(&want, &panel.frame(W, H), W.into()), None);
}

/// A command byte and its parameters, as the bus carries them.
fn command(code: u8, parameters: &[u8]) -> Vec<Byte> {
    let mut bytes = vec![Byte {
        data: false,
        value: code,
    }];
    bytes.extend(parameters.iter().map(|&value| Byte { data: true, value }));
    bytes
}

/// The model by hand, from the datasheets' descriptions: a 3 × 2 window written with 7 pixels
/// fills it row by row and wraps to its first pixel; the high byte comes first; BGR swaps the
/// colour's ends; INVON complements; the exchanged address space is 320 columns wide.
#[test]
fn the_panel_model_follows_the_datasheets() {
    let setup = [
        command(0x01, &[]),
        command(0x11, &[]),
        command(0x3A, &[0x55]),
        command(0x29, &[]),
        command(0x2A, &[0, 2, 0, 4]),
        command(0x2B, &[0, 1, 0, 2]),
    ]
    .concat();
    let words: [u16; 7] = [0xF800, 0x07E0, 0x001F, 0x0001, 0x0020, 0x0800, 0xFFFF];
    let pixels: Vec<u8> = words.iter().flat_map(|w| w.to_be_bytes()).collect();
    let write = command(0x2C, &pixels);

    let mut panel = Panel::st7789();
    panel.replay(&setup);
    assert!(panel.ready());
    panel.replay(&write);
    let frame = panel.frame(240, 320);
    let at = |x: usize, y: usize| frame[y * 240 + x];
    // The seventh pixel wrapped onto the first.
    assert_eq!(at(2, 1), Some(Rgb565::WHITE));
    assert_eq!(at(3, 1), Some(Rgb565::GREEN));
    assert_eq!(at(4, 1), Some(Rgb565::BLUE));
    assert_eq!(at(2, 2), Some(Rgb565::new(0, 0, 1)));
    assert_eq!(at(3, 2), Some(Rgb565::new(0, 1, 0)));
    assert_eq!(at(4, 2), Some(Rgb565::new(1, 0, 0)));
    assert_eq!(frame.iter().filter(|p| p.is_some()).count(), 6);

    // BGR: the first five bits are blue.
    let mut bgr = Panel::st7789();
    bgr.replay(&[setup.clone(), command(0x36, &[0x08]), write.clone()].concat());
    assert_eq!(bgr.frame(240, 320)[240 + 3], Some(Rgb565::GREEN));
    assert_eq!(bgr.frame(240, 320)[240 + 4], Some(Rgb565::RED));
    // INVON: complemented.
    let mut inverted = Panel::st7789();
    inverted.replay(&[setup.clone(), command(0x21, &[]), write.clone()].concat());
    assert_eq!(inverted.frame(240, 320)[240 + 2], Some(Rgb565::BLACK));

    // MV: columns up to 319, pages up to 239; the host's column 319 is the memory's last row.
    let mut exchanged = Panel::st7789();
    let last = [
        setup.clone(),
        command(0x36, &[0x20]),
        command(0x2A, &[1, 0x3F, 1, 0x3F]),
        command(0x2B, &[0, 0, 0, 0]),
        command(0x2C, &[0xF8, 0x00]),
    ]
    .concat();
    exchanged.replay(&last);
    assert_eq!(exchanged.frame(320, 240)[319], Some(Rgb565::RED));
    assert_eq!(exchanged.portrait()[319 * 240], Some(Rgb565::RED));
}

/// Column 319 is outside the address space without MADCTL's exchange.
#[test]
#[should_panic(expected = "outside the 240 × 320 address space")]
fn the_panel_model_rejects_a_window_outside_memory() {
    let mut panel = Panel::st7789();
    panel.replay(
        &[
            command(0x3A, &[0x55]),
            command(0x2A, &[1, 0x3F, 1, 0x3F]),
            command(0x2C, &[0, 0]),
        ]
        .concat(),
    );
}
