//! The panic handler of the measuring firmware: it prints the panic and exits with failure, so
//! that CI sees a failed run rather than a hang. (The firmware that proves the drawing code
//! panic-free links `nopanic.rs` instead.)

use crate::board::hprintln;

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    hprintln!("panic: {}", info);
    crate::board::exit(false)
}
