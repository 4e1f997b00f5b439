//! Firmware: renders the shared test scene (`examples/common/scene.rs`) into a RAM framebuffer
//! and prints its checksum over semihosting, then exits with success (a panic or HardFault exits
//! with failure).
//!
//! ```text
//! cargo run --release --target thumbv7em-none-eabihf --example fw_scene   # mps2-an386, 128×96
//! cargo run --release --target thumbv7m-none-eabi    --example fw_scene   # mps2-an385, 128×96
//! cargo run --release --target thumbv6m-none-eabi    --example fw_scene   # micro:bit,  64×48
//! cargo run --release --example fw_scene                                  # host: both sizes
//! ```
//!
//! Then it draws random dithered spans over the scene (`scene::dithered_spans`: the targets'
//! packed loops against the portable definition) and prints their checksum.
//!
//! `.ci/firmware.sh` compares the firmware's lines with the host's; `tests/all/firmware_checksum.rs`
//! checks the host rendering of the same scene against an independent reference.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[allow(dead_code)]
#[path = "../examples/common/scene.rs"]
mod scene;

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/board.rs"]
mod board;

#[cfg(target_os = "none")]
#[path = "common/report_panic.rs"]
mod report_panic;

#[cfg(target_os = "none")]
#[path = "common/stack.rs"]
mod stack;

#[cfg(target_os = "none")]
mod firmware {
    use crate::board::entry;
    use crate::board::hprintln;
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_raster::SliceFramebuffer;

    use crate::{board, scene};

    // The host prints the checksums of scene::SIZES; the boards must use one of them.
    const _: () = assert!(
        (board::SIZE.0 == scene::MPS2_SIZE.0 && board::SIZE.1 == scene::MPS2_SIZE.1)
            || (board::SIZE.0 == scene::MICROBIT_SIZE.0 && board::SIZE.1 == scene::MICROBIT_SIZE.1)
    );

    static mut PIXELS: [Rgb565; board::PIXELS] = [Rgb565::new(0, 0, 0); board::PIXELS];

    #[entry]
    fn main() -> ! {
        // SAFETY: `main` runs once and never returns: the static's only reference.
        let pixels = unsafe { &mut *core::ptr::addr_of_mut!(PIXELS) };
        crate::stack::paint_run();
        let (width, height) = board::SIZE;
        let mut fb = SliceFramebuffer::new(pixels, width, height).expect("framebuffer size");
        scene::render(&mut fb);
        let checksum = scene::checksum(fb.pixels());
        let line = scene::ChecksumLine {
            width,
            height,
            checksum,
        };
        hprintln!("{}", line);
        let spans = scene::dithered_spans(&mut fb);
        hprintln!("spans {}x{} fnv1a={:#010x}", width, height, spans);
        crate::stack::report();
        board::exit(true)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_raster::SliceFramebuffer;

    for (width, height) in scene::SIZES {
        let mut pixels = vec![Rgb565::new(0, 0, 0); (width * height) as usize];
        let mut fb = SliceFramebuffer::new(&mut pixels, width, height).expect("framebuffer size");
        scene::render(&mut fb);
        let checksum = scene::checksum(fb.pixels());
        let line = scene::ChecksumLine {
            width,
            height,
            checksum,
        };
        println!("{line}");
        let spans = scene::dithered_spans(&mut fb);
        println!("spans {width}x{height} fnv1a={spans:#010x}");
    }
}
