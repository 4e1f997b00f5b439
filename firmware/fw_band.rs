//! Firmware benchmark of band rendering: the 3D bench frame (`examples/common/scene3d.rs`, the
//! knot, 320×240 Rgb565 with z, Gouraud) drawn in bands of 8, 16, 32 and 240 rows, each band
//! handed to a display stand-in that hashes it, in the three modes of
//! `firmware/common/bands.rs` (no bin per face, no bin with the vertex scratch, a `MeshBin`),
//! against the frame drawn whole with the scratch; instructions counted by SysTick (or `minstret`) under QEMU's
//! `-icount` (`firmware/common/clock.rs`), and the RAM each mode takes.
//!
//! ```text
//! cargo run --release --target thumbv7em-none-eabihf --example fw_band   # mps2-an386, M4F
//! cargo run --release --example fw_band                                  # host: checksums
//! ```
//!
//! Each run prints one `bands …` line per band height and mode (the hashes of the colours and
//! the depths the stand-in received), which must all equal the host's line for the frame drawn
//! whole (`.ci/firmware.sh`), then a table. The stack each frame takes is measured by painting
//! the free RAM below the stack before it and finding the lowest word it changed.
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
#[path = "common/report_panic.rs"]
mod report_panic;

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/clock.rs"]
mod clock;

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/stack.rs"]
mod stack;

/// The band heights measured.
const HEIGHTS: [u32; 4] = [8, 16, 32, 240];

#[cfg(target_os = "none")]
mod firmware {
    use core::hint::black_box;

    use crate::board::entry;
    use crate::board::hprintln;
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_raster::band::BinEntry;
    use embedded_raster::three_d::{DepthTarget, ProjectedVertex};

    use crate::bands::{self, BandLine, Buffers, Mode, Seen};
    use crate::scene3d::{self, Model, PIXELS, SIZE};
    use crate::{board, clock, stack, HEIGHTS};

    /// Vertices of the knot: the scratch.
    const VERTICES: usize = 3072;
    /// Bands at one row (the most a layout of the frame has) plus every face.
    const BIN: usize = 240 + 6144;

    static mut COLORS: [Rgb565; PIXELS] = [Rgb565::new(0, 0, 0); PIXELS];
    static mut DEPTH: [u16; PIXELS] = [0; PIXELS];
    static mut SCRATCH: [ProjectedVertex; VERTICES] = [ProjectedVertex::EMPTY; VERTICES];
    static mut BIN_STORAGE: [BinEntry; BIN] = [BinEntry::EMPTY; BIN];

    #[entry]
    fn main() -> ! {
        // SAFETY: `main` runs once and never returns: the statics' only references.
        let (colors, depth, scratch, bin_storage) = unsafe {
            (
                &mut *core::ptr::addr_of_mut!(COLORS),
                &mut *core::ptr::addr_of_mut!(DEPTH),
                &mut *core::ptr::addr_of_mut!(SCRATCH),
                &mut *core::ptr::addr_of_mut!(BIN_STORAGE),
            )
        };

        clock::start();
        let calibration = clock::calibrate();
        let mesh = &scene3d::KNOT;
        let (w, h) = SIZE;

        // The frame drawn whole, with the scratch: the reference and the baseline.
        let whole = |target: &mut DepthTarget<'_, Rgb565>, scratch: &mut [ProjectedVertex]| {
            black_box(scene3d::render(Model::Knot, mesh, target, Some(scratch)))
        };
        if let Some(profile) = option_env!("BAND_PROFILE") {
            // Profiling build: one mode and band height (`<mode>-<rows>[-<frames>]`, mode
            // `each`, `scratch` or `bin`), four frames, or the whole frame (`whole`).
            let mut parts = profile.split('-');
            let mode = parts.next().unwrap_or("whole");
            let rows = parts.next().and_then(|r| r.parse().ok()).unwrap_or(16);
            let frames = parts.next().and_then(|r| r.parse().ok()).unwrap_or(4);
            let mode = match mode {
                "each" => Some(Mode::EachFace),
                "scratch" => Some(Mode::Scratch),
                "bin" => Some(Mode::Bin),
                _ => None,
            };
            for _ in 0..frames {
                match mode {
                    Some(mode) => {
                        let buffers = Buffers {
                            colors: &mut colors[..],
                            depth: &mut depth[..],
                            scratch: &mut scratch[..],
                            bin: &mut bin_storage[..],
                        };
                        // Through `black_box`: every mode and both kinds of run linked, as
                        // in the benchmark (the code LLVM makes of one depends on the others).
                        let (mode, hash) = (black_box(mode), black_box(false));
                        black_box(bands::render(Model::Knot, mesh, rows, mode, buffers, hash).ok());
                    }
                    None => {
                        let mut target = DepthTarget::new(&mut colors[..], &mut depth[..], w, h)
                            .expect("buffers fit");
                        whole(&mut target, scratch);
                    }
                }
            }
            board::exit(true)
        }

        let mut target =
            DepthTarget::new(&mut colors[..], &mut depth[..], w, h).expect("buffers fit");
        whole(&mut target, scratch);
        let want = Seen::of_frame(target.framebuffer().pixels(), target.depth());
        let full = clock::instructions(
            clock::measure(1, || {
                whole(&mut target, scratch);
            }),
            calibration,
        );
        drop(target);

        let mut same = true;
        let mut table = [[(0u64, 0u32); 3]; HEIGHTS.len()];
        let mut kept = 0;
        for (i, rows) in HEIGHTS.into_iter().enumerate() {
            for (j, mode) in Mode::ALL.into_iter().enumerate() {
                let mut run = |hash| {
                    let buffers = Buffers {
                        colors: &mut colors[..],
                        depth: &mut depth[..],
                        scratch: &mut scratch[..],
                        bin: &mut bin_storage[..],
                    };
                    bands::render(Model::Knot, black_box(mesh), rows, mode, buffers, hash)
                };
                let (seen, stack) = stack::measure(&mut || run(true));
                let (seen, faces) = seen.expect("the buffers fit");
                kept = kept.max(faces);
                same &= seen == want;
                hprintln!("{}", BandLine(Model::Knot, seen));
                let ticks = clock::measure(1, || {
                    black_box(run(false).ok());
                });
                table[i][j] = (clock::instructions(ticks, calibration), stack);
            }
        }

        hprintln!("\n### Band rendering, {}\n", board::name());
        hprintln!(
            "The knot frame drawn whole (with the vertex scratch): {} instructions.\n",
            full
        );
        hprintln!("| band rows | bands | no bin, per face | no bin, scratch | bin | bin over the whole frame |");
        hprintln!("|---:|---:|---:|---:|---:|---:|");
        for (i, rows) in HEIGHTS.into_iter().enumerate() {
            let [each, scratch, bin] = table[i].map(|(n, _)| n);
            let over = (bin as i64 - full as i64) * 1000 / full as i64;
            hprintln!(
                "| {} | {} | {} | {} | {} | {}{}.{} % |",
                rows,
                h.div_ceil(rows),
                each,
                scratch,
                bin,
                if over < 0 { "-" } else { "+" },
                over.unsigned_abs() / 10,
                over.unsigned_abs() % 10
            );
        }
        hprintln!(
            "\nRAM (bytes): band buffers (colour and depth, 320 × rows × 4), the vertex scratch"
        );
        hprintln!(
            "({} × 16), the bin ((bands + faces kept) × 12), stack (measured):\n",
            VERTICES
        );
        hprintln!("| band rows | band buffers | per face: stack | scratch: stack | bin: stack | bin storage |");
        hprintln!("|---:|---:|---:|---:|---:|---:|");
        for (i, rows) in HEIGHTS.into_iter().enumerate() {
            let [each, scratch, bin] = table[i].map(|(_, s)| s);
            let bands = h.div_ceil(rows) as usize;
            hprintln!(
                "| {} | {} | {} | {} | {} | {} |",
                rows,
                w as usize * rows as usize * 4,
                each,
                scratch,
                bin,
                (bands + kept) * 12
            );
        }
        hprintln!();
        if !same {
            hprintln!("error: a band rendering differs from the frame drawn whole");
        }
        board::exit(same)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    use bands::{BandLine, Buffers, Mode, Seen};
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_raster::band::BinEntry;
    use embedded_raster::three_d::{DepthTarget, ProjectedVertex};
    use scene3d::{Model, PIXELS, SIZE};

    let mesh = &scene3d::KNOT;
    let (mut colors, mut depth) = (vec![Rgb565::new(0, 0, 0); PIXELS], vec![0u16; PIXELS]);
    let mut scratch = vec![ProjectedVertex::EMPTY; mesh.vertices.len()];
    let mut target = DepthTarget::new(&mut colors, &mut depth, SIZE.0, SIZE.1).expect("buffers");
    scene3d::render(Model::Knot, mesh, &mut target, Some(&mut scratch));
    let want = Seen::of_frame(target.framebuffer().pixels(), target.depth());
    println!("{}", BandLine(Model::Knot, want));
    // The host draws the bands too: they must give the same frame.
    let mut bin = vec![BinEntry::EMPTY; 240 + mesh.indices.len()];
    for rows in HEIGHTS {
        for mode in Mode::ALL {
            let buffers = Buffers {
                colors: &mut colors,
                depth: &mut depth,
                scratch: &mut scratch,
                bin: &mut bin,
            };
            let (seen, _) =
                bands::render(Model::Knot, mesh, rows, mode, buffers, true).expect("buffers fit");
            assert_eq!(seen, want, "{rows}-row bands, {}", mode.name());
        }
    }
}
