//! Footprint firmware: `GouraudTriangle<Rgb565>` through `draw_into_compact` only (see
//! `firmware/common/size.rs`; `.ci/firmware.sh` reports the sizes).
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/board.rs"]
mod board;

#[cfg(target_os = "none")]
#[path = "common/size.rs"]
mod size;

#[cfg(target_os = "none")]
fn main() -> ! {
    use core::hint::black_box;

    use embedded_raster::{GouraudTriangle, Vertex};

    size::run(|fb| {
        let (points, colors) = size::inputs();
        let vertex = |k: usize| Vertex::new(points[k].0, points[k].1, colors[k]);
        let triangle = GouraudTriangle::new([vertex(0), vertex(1), vertex(2)]);
        let _ = black_box(triangle).draw_into_compact(fb);
    })
}

#[cfg(not(target_os = "none"))]
fn main() {
    println!("fw_size_compact is firmware: build it with --target thumbv6m-none-eabi");
}
