//! Skeleton of the footprint firmware (`fw_size_base`, `fw_size_solid`, `fw_size_gouraud`):
//! identical except for the drawing, so the difference of their sizes is the drawing code's
//! flash and RAM (`.ci/firmware.sh` reports it).
//!
//! The panic handler calls an undefined function, so like `fw_nopanic` these only link (in
//! release builds) if the drawing code has no panic path; with no formatting in the skeleton,
//! nothing but the drawing differs. Inputs go through `black_box`, so nothing is specialised to
//! constants.

use core::hint::black_box;

use cortex_m_rt::entry;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_raster::{Coord, SliceFramebuffer};

use crate::board;

#[path = "nopanic.rs"]
mod nopanic;

/// Three opaque vertex positions and colours.
pub fn inputs() -> ([(Coord, Coord); 3], [Rgb565; 3]) {
    let c = |v: i32| Coord::from_bits(black_box(v));
    (
        [(c(300), c(520)), (c(9000), c(1800)), (c(2500), c(11000))],
        [
            black_box(Rgb565::RED),
            black_box(Rgb565::GREEN),
            black_box(Rgb565::BLUE),
        ],
    )
}

/// Clears a framebuffer, calls `draw` on it and exits QEMU.
pub fn run(draw: fn(&mut SliceFramebuffer<'_, Rgb565>)) -> ! {
    static mut PIXELS: [Rgb565; board::PIXELS] = [Rgb565::new(0, 0, 0); board::PIXELS];
    // SAFETY: the only reference to PIXELS, taken once.
    let pixels = unsafe { &mut *core::ptr::addr_of_mut!(PIXELS) };
    let (width, height) = black_box(board::SIZE);
    if let Some(mut fb) = SliceFramebuffer::new(pixels, width, height) {
        let _ = fb.clear(black_box(Rgb565::BLACK));
        draw(&mut fb);
        black_box(fb.pixels());
    }
    board::exit(true)
}

#[entry]
fn main() -> ! {
    crate::main()
}
