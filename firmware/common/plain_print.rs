//! Output to the host's stdout over semihosting without formatting machinery, so that the
//! firmware proving the drawing code panic-free links no panic path of its own.

/// Writes `text` (nothing if the host does not answer).
#[cfg(target_arch = "arm")]
pub fn print(text: &[u8]) {
    if let Ok(mut out) = cortex_m_semihosting::hio::hstdout() {
        let _ = out.write_all(text);
    }
}

/// Writes `text` to the host's console.
#[cfg(target_arch = "riscv32")]
pub fn print(text: &[u8]) {
    crate::board::print(text);
}

/// Writes `n` in decimal.
pub fn decimal(mut n: u64) {
    let mut digits = [0u8; 20];
    let mut first = digits.len();
    while first > 0 {
        first -= 1;
        if let Some(d) = digits.get_mut(first) {
            *d = b'0' + (n % 10) as u8;
        }
        n /= 10;
        if n == 0 {
            break;
        }
    }
    print(digits.get(first..).unwrap_or(&[]));
}

/// Writes `n` as eight hexadecimal digits.
pub fn hex(n: u32) {
    let digits: [u8; 8] =
        core::array::from_fn(|k| b"0123456789abcdef"[((n >> (28 - 4 * k)) & 15) as usize]);
    print(&digits);
}
