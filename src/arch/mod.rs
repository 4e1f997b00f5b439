//! Target-specific code, and the target facts the portable code branches on.
//!
//! Every `target_arch` decision of the crate is here or in `build.rs`, which names the targets
//! as `cfg`s (`armv6m`, `armv7m`, `sse2_rows`). The portable code asks the constants below; the
//! instruction-level code (SSE2 intrinsics, Thumb-1 assembly) lives in one file per target, each
//! computing exactly what a portable function computes (tested on the host, and by the firmware
//! checksums in CI).

#[cfg(armv6m)]
pub(crate) mod thumbv6m;
#[cfg(sse2_rows)]
pub(crate) mod x86_64;

/// Pixels of a row of a tiny triangle's box, drawn at once on x86-64: one 16-bit lane each, one
/// SSE2 register.
pub const LANES: usize = 8;

/// ARMv6-M: no 32 × 32 → 64-bit multiply (every 64-bit product is a library call): products of
/// 32-bit factors are formed from 16-bit limbs.
pub(crate) const NO_LONG_MULTIPLY: bool = cfg!(armv6m);

/// ARMv6-M: no `clz` instruction (the library routine is a call of about the same length as a
/// few halving steps).
pub(crate) const NO_CLZ: bool = cfg!(armv6m);

/// A Cortex-M core: branches are cheap and predictable, loops are not vectorised, and code size
/// matters more than a host's branch predictor.
pub(crate) const CORTEX_M: bool = cfg!(any(armv6m, armv7m));

/// A 32-bit hardware divider (ARMv7-M, and every host): a 32-bit division is one instruction
/// (on Cortex-M0 it is a library loop).
pub(crate) const HAS_DIVIDER: bool = !cfg!(armv6m);

/// A 64-bit host: a 64-bit division is one instruction (on Cortex-M it is a long library call).
pub(crate) const FAST_WIDE_DIVISION: bool = cfg!(target_pointer_width = "64");
