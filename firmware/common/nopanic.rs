//! The panic handler of the firmware that proves the drawing code panic-free.
//!
//! In release builds it calls a function that does not exist, so any panic path the optimiser
//! leaves in the drawing code makes the link fail with
//! `undefined symbol: embedded_raster_drawing_code_can_panic`. Debug builds keep their panics and
//! exit with failure.

#[cfg(not(debug_assertions))]
extern "C" {
    /// Deliberately undefined: a panic path in the drawing code fails the (release) link.
    fn embedded_raster_drawing_code_can_panic() -> !;
}

#[cfg(not(debug_assertions))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    unsafe { embedded_raster_drawing_code_can_panic() }
}

#[cfg(debug_assertions)]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    crate::board::exit(false)
}
