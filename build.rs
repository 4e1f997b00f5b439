//! Names the target facts the drawing code depends on, once, as `cfg`s:
//!
//! * `armv6m`: ARMv6-M (Cortex-M0/M0+) — no 32 × 32 → 64-bit multiply, no `clz`, no divider;
//!   the 5-6-5 span loop is Thumb-1 assembly.
//! * `armv7m`: ARMv7-M/ARMv7E-M (Cortex-M3/M4/M7) — long multiply and `clz`, no 64-bit divider.
//! * `armv8m`: ARMv8-M Mainline (Cortex-M33, the `thumbv8m.main` targets) — also `armv7m`: it
//!   has ARMv7-M's instructions, and their Thumb-2 loops run there unchanged. Its DSP extension
//!   is optional, so not `armv7em` (measured with it, `-C target-cpu=cortex-m33`: no faster).
//! * `armv7em`: ARMv7E-M (Cortex-M4/M7, the `thumbv7em` targets) — also the DSP extension's
//!   16-bit lane instructions (`uxtb16`, `uxtab16`), which the Cortex-M3 lacks.
//! * `sse2_rows`: x86-64, whose baseline SSE2 draws tiny triangles a row of lanes at a time.
//!
//! ARMv6-M is recognised as ARM without 32-bit atomics (there is no `target_feature` for it).
use std::env;

fn main() {
    for name in ["armv6m", "armv7m", "armv7em", "armv8m", "sse2_rows"] {
        println!("cargo::rustc-check-cfg=cfg({name})");
    }
    let arch = env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let atomics = env::var("CARGO_CFG_TARGET_HAS_ATOMIC").unwrap_or_default();
    let has_atomic_32 = atomics.split(',').any(|w| w == "32");
    match arch.as_str() {
        "arm" if has_atomic_32 => {
            println!("cargo::rustc-cfg=armv7m");
            let target = env::var("TARGET").unwrap_or_default();
            if target.starts_with("thumbv7em") {
                println!("cargo::rustc-cfg=armv7em");
            }
            if target.starts_with("thumbv8m.main") {
                println!("cargo::rustc-cfg=armv8m");
            }
        }
        "arm" => println!("cargo::rustc-cfg=armv6m"),
        "x86_64" => println!("cargo::rustc-cfg=sse2_rows"),
        _ => {}
    }
    println!("cargo::rerun-if-changed=build.rs");
}
