//! The band-rendering showcase: a micro:bit (Cortex-M0, 16 KiB of RAM) renders the 3D bench
//! frame — the 6,144-face knot of `examples/common/scene3d.rs` (in flash), 320×240 Rgb565, lit,
//! z-buffered, Gouraud — band by band without a bin, into a display stand-in that hashes each
//! band as it would be sent; the hashes must equal those of the frame drawn whole on the host.
//!
//! ```text
//! cargo run --release --target thumbv6m-none-eabi --example fw_band_microbit   # QEMU microbit
//! cargo run --release --example fw_band_microbit                               # host: the line
//! ```
//!
//! RAM: one band of [`ROWS`] rows, colours and depths (320 × rows × 4 bytes), and the stack
//! (measured, printed); nothing per vertex or per face. `.ci/firmware.sh` runs it under QEMU and
//! compares its `bands …` line with the host's. Its panic handler is `fw_nopanic`'s: the release
//! build links only if the drawing code it uses (band renderer, 3D pipeline, fills) has no panic
//! path left, so it prints without `core::fmt`.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[allow(dead_code)]
#[path = "../examples/common/scene3d.rs"]
mod scene3d;

#[allow(dead_code)]
#[path = "common/bands.rs"]
mod bands;

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/board.rs"]
mod board;

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/clock.rs"]
mod clock;

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/stack.rs"]
mod stack;

// Release builds link only if nothing reachable can panic (see `fw_nopanic`): the whole band
// renderer and 3D pipeline of this frame are panic-free.
#[cfg(target_os = "none")]
#[path = "common/nopanic.rs"]
mod nopanic;

#[cfg(target_os = "none")]
#[path = "common/plain_print.rs"]
mod plain_print;

/// Rows of a band: 320 × 8 × 4 = 10 KiB of the micro:bit's 16.
const ROWS: u32 = 8;

/// Entries of one band buffer.
const BAND: usize = scene3d::SIZE.0 as usize * ROWS as usize;

#[cfg(target_os = "none")]
mod firmware {
    use core::hint::black_box;

    use crate::board::entry;
    use embedded_graphics::pixelcolor::Rgb565;

    use crate::bands::{self, Buffers, Mode, Seen};
    use crate::plain_print::{decimal, hex, print};
    use crate::scene3d::{self, Model};
    use crate::{board, clock, stack, BAND, ROWS};

    /// The line of `bands::BandLine`, printed piece by piece.
    fn band_line(seen: &Seen) {
        print(b"bands knot 320x240 rows=");
        decimal(u64::from(seen.rows));
        print(b" colors=0x");
        hex(seen.colors.0);
        print(b" depths=0x");
        hex(seen.depths.0);
        print(b"\n");
    }

    static mut COLORS: [Rgb565; BAND] = [Rgb565::new(0, 0, 0); BAND];
    static mut DEPTH: [u16; BAND] = [0; BAND];

    #[entry]
    fn main() -> ! {
        // SAFETY: `main` runs once and never returns: the statics' only references.
        let (colors, depth) = unsafe {
            (
                &mut *core::ptr::addr_of_mut!(COLORS),
                &mut *core::ptr::addr_of_mut!(DEPTH),
            )
        };
        stack::paint_run();

        clock::start();
        let calibration = clock::calibrate();
        let mesh = &scene3d::KNOT;
        let mut frame = |hash| {
            let buffers = Buffers {
                colors: &mut colors[..],
                depth: &mut depth[..],
                scratch: &mut [],
                bin: &mut [],
            };
            bands::render(
                Model::Knot,
                black_box(mesh),
                ROWS,
                Mode::EachFace,
                buffers,
                hash,
            )
        };
        let (seen, stack) = stack::measure(&mut || frame(true));
        let Ok((seen, _)) = seen else {
            print(b"error: the band buffers do not fit\n");
            board::exit(false)
        };
        band_line(&seen);
        let ticks = clock::measure(1, || {
            black_box(frame(false).ok());
        });
        let instructions = clock::instructions(ticks, calibration);
        print(b"\n### The knot frame on the micro:bit (Cortex-M0, thumbv6m-none-eabi), ");
        decimal(u64::from(ROWS));
        print(b"-row bands, no bin\n\n");
        print(b"| instructions a frame | bands | band buffers (bytes) | stack (bytes) |\n");
        print(b"|---:|---:|---:|---:|\n| ");
        decimal(instructions);
        print(b" | ");
        decimal(u64::from(scene3d::SIZE.1.div_ceil(ROWS)));
        print(b" | ");
        decimal(BAND as u64 * 4);
        print(b" | ");
        decimal(u64::from(stack));
        print(b" |\n\n");
        stack::report();
        board::exit(true)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    use bands::{BandLine, Buffers, Mode, Seen};
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_raster::three_d::DepthTarget;
    use scene3d::{Model, PIXELS, SIZE};

    let mesh = &scene3d::KNOT;
    let (mut colors, mut depth) = (vec![Rgb565::new(0, 0, 0); PIXELS], vec![0u16; PIXELS]);
    let mut target = DepthTarget::new(&mut colors, &mut depth, SIZE.0, SIZE.1).expect("buffers");
    scene3d::render(Model::Knot, mesh, &mut target, None);
    let want = Seen::of_frame(target.framebuffer().pixels(), target.depth());
    println!("{}", BandLine(Model::Knot, want));
    let buffers = Buffers {
        colors: &mut colors[..BAND],
        depth: &mut depth[..BAND],
        scratch: &mut [],
        bin: &mut [],
    };
    let (seen, _) =
        bands::render(Model::Knot, mesh, ROWS, Mode::EachFace, buffers, true).expect("buffers fit");
    assert_eq!(seen, want, "the bands differ from the frame drawn whole");
}
