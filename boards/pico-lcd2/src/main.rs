//! The lit spot turning on a Raspberry Pi Pico (RP2040, one Cortex-M0+ at 125 MHz) with a
//! Waveshare Pico-LCD-2 (ST7789, 320×240, SPI at 62.5 MHz), drawn by embedded-raster in 16-row
//! bands: a frame is never whole in RAM. The 3D frame is the crate's bench scene (spot, 5,856
//! faces, Gouraud-lit, 16-bit z), one 2° turn a frame; the band buffers take 20 KiB, the vertex
//! scratch and the bin that sorts the faces into bands 125 KiB.
//!
//! Build (from this folder): `cargo build --release`; flash: `cargo run --release` with the
//! Pico in BOOTSEL mode (see the README for the wiring and the tools).
#![no_std]
#![no_main]

use core::ptr::addr_of_mut;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_hal::digital::OutputPin;
use embedded_hal_bus::spi::ExclusiveDevice;
use embedded_raster::band::{BandLayout, BinEntry, ColorBands, DepthBands, MeshBin, ToDisplay};
use embedded_raster::three_d::{Angle, ProjectedVertex};
use hal::clocks::Clock;
use hal::fugit::RateExtU32;
use hal::gpio::{FunctionSpi, PinState};
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::{ColorInversion, Orientation, Rotation};
use panic_halt as _;
use rp2040_hal as hal;

#[allow(dead_code)]
#[path = "../../../examples/common/scene3d.rs"]
mod scene3d;

/// The second-stage boot loader for the Pico's W25Q080 flash.
#[link_section = ".boot2"]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The Pico's crystal.
const XTAL_FREQ_HZ: u32 = 12_000_000;

/// Rows of a band, and pixels of its buffers.
const ROWS: u32 = 16;
const BAND: usize = 320 * ROWS as usize;

/// Spot's vertices (the scratch holds each transformed once a frame) and the bin's entries (a
/// band's list heads and the faces drawn, 2,000 to 2,700 a pose of the 5,856).
const VERTICES: usize = 2930;
const BIN: usize = 15 + 5856;

/// Poses a turn.
const POSES: i32 = 180;

static mut COLORS: [Rgb565; BAND] = [Rgb565::BLACK; BAND];
static mut DEPTH: [u16; BAND] = [0; BAND];
static mut SCRATCH: [ProjectedVertex; VERTICES] = [ProjectedVertex::EMPTY; VERTICES];
static mut BIN_STORAGE: [BinEntry; BIN] = [BinEntry::EMPTY; BIN];

#[hal::entry]
fn main() -> ! {
    // SAFETY: `main` runs once and never returns: the statics' only references.
    let (colors, depth, scratch, bin_storage) = unsafe {
        (
            &mut *addr_of_mut!(COLORS),
            &mut *addr_of_mut!(DEPTH),
            &mut *addr_of_mut!(SCRATCH),
            &mut *addr_of_mut!(BIN_STORAGE),
        )
    };
    let mut pac = hal::pac::Peripherals::take().unwrap();
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    let Ok(clocks) = hal::clocks::init_clocks_and_plls(
        XTAL_FREQ_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    ) else {
        panic!("the clocks do not start");
    };
    let sio = hal::Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let timer = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);

    // The Pico-LCD-2's pins: SPI1 clock GP10 and data GP11, chip select GP9, data/command GP8,
    // reset GP12, backlight GP13. SPI at half the 125 MHz peripheral clock, the ST7789's
    // fastest serial clock.
    let sclk = pins.gpio10.into_function::<FunctionSpi>();
    let mosi = pins.gpio11.into_function::<FunctionSpi>();
    let spi = hal::spi::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, sclk)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        embedded_hal::spi::MODE_0,
    );
    let cs = pins.gpio9.into_push_pull_output_in_state(PinState::High);
    let dc = pins.gpio8.into_push_pull_output();
    let reset = pins.gpio12.into_push_pull_output();
    let mut backlight = pins.gpio13.into_push_pull_output();
    // Its errors are the pins' and the delay's: none.
    let Ok(spi) = ExclusiveDevice::new(spi, cs, timer);
    let mut buffer = [0u8; 512];
    let interface = SpiInterface::new(spi, dc, &mut buffer);
    let mut delay = timer;
    let Ok(mut display) = mipidsi::Builder::new(ST7789, interface)
        .display_size(240, 320)
        .orientation(Orientation::new().rotate(Rotation::Deg90))
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(reset)
        .init(&mut delay)
    else {
        panic!("the display does not start");
    };
    let _ = backlight.set_high();

    let Ok(layout) = BandLayout::new(Size::new(320, 240), ROWS) else {
        panic!("band layout");
    };
    let Ok(bands) = ColorBands::new(layout, colors) else {
        panic!("band buffer");
    };
    let Ok(mut bands) = DepthBands::new(bands, depth) else {
        panic!("depth band buffer");
    };
    let mut pose = 0;
    loop {
        let pipeline = scene3d::spot_turned(Angle::from_turns(pose, POSES));
        pose = (pose + 1) % POSES;
        // The faces sorted into the bands they cross, each vertex transformed once a frame.
        let Ok(mut bin) = MeshBin::new(
            &pipeline,
            &scene3d::SPOT,
            &scene3d::MATERIAL,
            &layout,
            &mut scratch[..],
            &mut bin_storage[..],
        ) else {
            panic!("the scratch or the bin is too small for the mesh");
        };
        // Each band drawn, then sent while the next waits: `ToDisplay` hands it to the driver.
        let _ = bands.render(&mut ToDisplay(&mut display), |band| {
            band.clear(scene3d::BACKGROUND);
            bin.draw(band)
        });
    }
}
