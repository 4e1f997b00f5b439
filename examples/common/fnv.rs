//! 32-bit FNV-1a, the hash every checksum line of the examples and the firmware prints (included
//! with `#[path]` by `scene.rs` and `scene3d.rs`).

/// The FNV-1a hash of nothing, where [`fnv`] starts.
pub const FNV_START: u32 = 0x811c_9dc5;

/// FNV-1a over little-endian 16-bit words, from the hash `h` on ([`FNV_START`] to start).
pub fn fnv(mut h: u32, words: impl IntoIterator<Item = u16>) -> u32 {
    for w in words {
        for b in w.to_le_bytes() {
            h = (h ^ u32::from(b)).wrapping_mul(0x0100_0193);
        }
    }
    h
}
