//! Skeleton of the footprint firmware (`fw_size_base`, `fw_size_solid`, `fw_size_gouraud`, …;
//! `run_depth` adds a z-buffer for the 3D one, `fw_size_textured3d`): identical except for the
//! drawing, so the difference of their sizes is the drawing code's flash and RAM
//! (`.ci/firmware.sh` reports it).
//!
//! The panic handler calls an undefined function, so like `fw_nopanic` these only link (in
//! release builds) if the drawing code has no panic path; with no formatting in the skeleton,
//! nothing but the drawing differs. Inputs go through `black_box`, so nothing is specialised to
//! constants.

use core::hint::black_box;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_raster::three_d::DepthTarget;
use embedded_raster::{Coord, SliceFramebuffer};

use crate::board::{self, entry};

#[path = "nopanic.rs"]
mod nopanic;

/// Three opaque vertex positions and colours.
#[allow(dead_code)] // not by the 3D firmware
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
#[allow(dead_code)] // not by the 3D firmware
pub fn run(draw: fn(&mut SliceFramebuffer<'_, Rgb565>)) -> ! {
    static mut PIXELS: [Rgb565; board::PIXELS] = [Rgb565::new(0, 0, 0); board::PIXELS];
    // SAFETY: the only reference to PIXELS, taken once.
    let pixels = unsafe { &mut *core::ptr::addr_of_mut!(PIXELS) };
    let (width, height) = black_box(board::SIZE);
    if let Ok(mut fb) = SliceFramebuffer::new(pixels, width, height) {
        let _ = fb.clear(black_box(Rgb565::BLACK));
        draw(&mut fb);
        black_box(fb.pixels());
    }
    board::exit(true)
}

/// [`run`] for a 3D draw: the same framebuffer with its z-buffer (2 bytes a pixel more RAM),
/// cleared, handed to `draw` as a depth target.
#[allow(dead_code)] // only by the 3D firmware
pub fn run_depth(draw: fn(&mut DepthTarget<'_, Rgb565>)) -> ! {
    static mut PIXELS: [Rgb565; board::PIXELS] = [Rgb565::new(0, 0, 0); board::PIXELS];
    static mut DEPTH: [u16; board::PIXELS] = [0; board::PIXELS];
    // SAFETY: the only references to PIXELS and DEPTH, taken once.
    let (pixels, depth) = unsafe {
        (
            &mut *core::ptr::addr_of_mut!(PIXELS),
            &mut *core::ptr::addr_of_mut!(DEPTH),
        )
    };
    let (width, height) = black_box(board::SIZE);
    if let Ok(mut target) = DepthTarget::new(pixels, depth, width, height) {
        target.clear(black_box(Rgb565::BLACK));
        draw(&mut target);
        black_box(target.framebuffer().pixels());
        black_box(target.depth());
    }
    board::exit(true)
}

#[entry]
fn main() -> ! {
    crate::main()
}
