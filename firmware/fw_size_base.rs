//! Footprint firmware: the skeleton alone: the baseline the other two are measured against (see
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

    size::run(|fb| {
        black_box(size::inputs());
        black_box(fb);
    })
}

#[cfg(not(target_os = "none"))]
fn main() {
    println!("fw_size_base is firmware: build it with --target thumbv6m-none-eabi");
}
