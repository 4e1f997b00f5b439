//! Names the target facts the drawing code depends on, once, as `cfg`s:
//!
//! * `armv6m`: ARMv6-M (Cortex-M0/M0+) — no 32 × 32 → 64-bit multiply, no `clz`, no divider;
//!   the 5-6-5 span loop is Thumb-1 assembly.
//! * `armv7m`: ARMv7-M/ARMv7E-M (Cortex-M3/M4/M7) — long multiply and `clz`, no 64-bit divider.
//! * `armv8m`: ARMv8-M Mainline (Cortex-M33/M35P/M55/M85, the `thumbv8m.main` targets) — also
//!   `armv7m`: it has ARMv7-M's instructions, and their Thumb-2 loops run there unchanged.
//! * `arm_dsp`: the DSP extension's instructions (`uxtb16`, `uxtab16`, `pkhbt`, `smuad`, `smlad`):
//!   ARMv7E-M (Cortex-M4/M7, the `thumbv7em` targets), which always has them, and ARMv8-M
//!   Mainline with this crate's `dsp` feature. There the extension is optional, so the feature
//!   is the user's promise that the core has it (the Cortex-M33 of the RP2350, nRF5340, STM32U5
//!   and most others do; an instruction of it faults on a core without it); the target's name
//!   cannot say, and rustc does not expose the `dsp` target feature as a `cfg`. The Cortex-M3
//!   lacks it.
//! * `rv32`: RISC-V's 32-bit targets with the M extension (`riscv32imc`, `riscv32imac`, …) —
//!   a multiplier and a divider, 31 registers, no `clz` without Zbb; the rows of a small lit 3D
//!   face are assembly. (Without M, as `riscv32i`, the portable code.)
//! * `sse2_rows`: x86-64, whose baseline SSE2 draws tiny triangles a row of lanes at a time.
//!
//! ARMv6-M is recognised as ARM without 32-bit atomics (there is no `target_feature` for it), and
//! ARMv8-M Baseline (Cortex-M23, `thumbv8m.base`) takes its code: a superset of its instructions
//! without Thumb-2's (no IT blocks, long multiplies or `clz`). `armv7m` is the M-profile Thumb-2
//! targets by name (`thumbv7m`, `thumbv7em`, `thumbv8m.main`); other ARM targets (A- and
//! R-profile) take the portable code.
//!
//! And links the measuring firmware (this package's examples in `firmware/`, for bare-metal
//! targets) for the QEMU board each target runs on (`.cargo/config.toml` has the runners): the
//! runtime's `link.x`, after a board's layout where it is not the MPS2 one of `memory.x` — the
//! micro:bit's for `thumbv6m` (or the MPS2 one with `EMBEDDED_RASTER_FIRMWARE_LAYOUT=mps2`, for
//! the frames its 16 KiB cannot hold), mps2-an505's for `thumbv8m.main`, QEMU `virt`'s for
//! RISC-V. As link arguments of this package's examples they reach neither the library nor any
//! crate that depends on it (a board crate such as `boards/pico-lcd2` links its own), as
//! `.cargo/config.toml`'s rustflags would.
use std::env;

fn main() {
    for name in ["armv6m", "armv7m", "arm_dsp", "armv8m", "rv32", "sse2_rows"] {
        println!("cargo::rustc-check-cfg=cfg({name})");
    }
    let arch = env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let target = env::var("TARGET").unwrap_or_default();
    let atomics = env::var("CARGO_CFG_TARGET_HAS_ATOMIC").unwrap_or_default();
    let features = env::var("CARGO_CFG_TARGET_FEATURE").unwrap_or_default();
    let has_atomic_32 = atomics.split(',').any(|w| w == "32");
    // The M-profile Thumb-2 targets; other ARM targets with 32-bit atomics (A- and R-profile,
    // whose divider is optional) take the portable code.
    let thumb2 = ["thumbv7m", "thumbv7em", "thumbv8m.main"]
        .iter()
        .any(|t| target.starts_with(t));
    match arch.as_str() {
        "arm" if thumb2 => {
            println!("cargo::rustc-cfg=armv7m");
            let dsp = env::var_os("CARGO_FEATURE_DSP").is_some();
            if target.starts_with("thumbv7em") || (dsp && target.starts_with("thumbv8m.main")) {
                println!("cargo::rustc-cfg=arm_dsp");
            }
            if target.starts_with("thumbv8m.main") {
                println!("cargo::rustc-cfg=armv8m");
            }
        }
        "arm" if !has_atomic_32 || target.starts_with("thumbv8m.base") => {
            println!("cargo::rustc-cfg=armv6m")
        }
        "riscv32" if features.split(',').any(|f| f == "m") => println!("cargo::rustc-cfg=rv32"),
        "x86_64" => println!("cargo::rustc-cfg=sse2_rows"),
        _ => {}
    }
    if env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("none") {
        let layout = env::var("EMBEDDED_RASTER_FIRMWARE_LAYOUT").unwrap_or_default();
        let board = if target.starts_with("thumbv6m") && layout != "mps2" {
            Some("microbit")
        } else if target.starts_with("thumbv8m.main") {
            Some("an505")
        } else if arch == "riscv32" {
            Some("riscv")
        } else {
            None
        };
        let dir = env::var("CARGO_MANIFEST_DIR").unwrap_or_default();
        if let Some(board) = board {
            println!("cargo::rustc-link-arg-examples=-T{dir}/firmware/{board}/memory.x");
        }
        println!("cargo::rustc-link-arg-examples=-Tlink.x");
        println!("cargo::rerun-if-env-changed=EMBEDDED_RASTER_FIRMWARE_LAYOUT");
    }
    println!("cargo::rerun-if-changed=build.rs");
}
