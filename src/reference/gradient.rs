//! Linear and radial gradients in `f64`, from their definition (`paint::gradient`'s module
//! documentation): which segment a pixel centre falls in decided exactly in `i128`, the
//! channels interpolated in `f64`.
//!
//! Stops are `(position, channels)`: the position in 65536ths (clamped to `0..=65536`, made
//! non-decreasing as CSS does), the channels in the colour format's depth. Points are raw
//! sub-pixel coordinates (256 a pixel); pixel `(x, y)` is sampled at its centre.
//!
//! ```
//! use embedded_raster::reference::gradient::{linear, radial};
//!
//! let stops = [(0, [0, 0, 0]), (65536, [255, 0, 0])];
//! // From x = 0 to x = 256 pixels: the centre of pixel 100 is at t = 100.5 / 256.
//! let c = linear((0, 0), (256 * 256, 0), &stops, 100, 7);
//! assert!((c[0] - 255.0 * 100.5 / 256.0).abs() < 1e-9);
//! // Around (0.5, 0.5) with radius 100: pixel (3, 4) is 5 pixels away.
//! let c = radial((128, 128), 100 * 256, &stops, 3, 4);
//! assert!((c[0] - 255.0 * 0.05).abs() < 1e-9);
//! ```

use std::vec::Vec;

/// The stops' effective positions: each clamped to `0..=65536`, then at least the one before.
fn effective(stops: &[(u32, [u8; 3])]) -> Vec<i128> {
    let mut e = 0i128;
    stops
        .iter()
        .map(|&(p, _)| {
            e = e.max(i128::from(p.min(65536)));
            e
        })
        .collect()
}

/// The channels at a pixel whose parameter `t` is such that `at_or_beyond(e)` tells whether
/// `t ≥ e/65536` exactly, and `fraction(a, b)` is `(t − a/65536)/((b − a)/65536)`.
fn channels(
    stops: &[(u32, [u8; 3])],
    at_or_beyond: impl Fn(i128) -> bool,
    fraction: impl Fn(i128, i128) -> f64,
) -> [f64; 3] {
    let e = effective(stops);
    let k = e.iter().take_while(|&&e| at_or_beyond(e)).count();
    let of = |c: [u8; 3]| c.map(f64::from);
    match (k.checked_sub(1), stops.get(k)) {
        (None, Some(first)) => of(first.1),
        (Some(_), None) | (None, None) => stops.last().map_or([0.0; 3], |s| of(s.1)),
        (Some(a), Some(b)) => {
            let f = fraction(e[a], e[k]);
            let (ca, cb) = (of(stops[a].1), of(b.1));
            core::array::from_fn(|i| ca[i] + (cb[i] - ca[i]) * f)
        }
    }
}

/// The linear gradient from `start` to `end` at the centre of pixel `(x, y)`.
pub fn linear(
    start: (i32, i32),
    end: (i32, i32),
    stops: &[(u32, [u8; 3])],
    x: i32,
    y: i32,
) -> [f64; 3] {
    let d = (
        i128::from(end.0) - i128::from(start.0),
        i128::from(end.1) - i128::from(start.1),
    );
    let p = (
        256 * i128::from(x) + 128 - i128::from(start.0),
        256 * i128::from(y) + 128 - i128::from(start.1),
    );
    let den = d.0 * d.0 + d.1 * d.1;
    if den == 0 {
        return stops.last().map_or([0.0; 3], |s| s.1.map(f64::from));
    }
    let num = p.0 * d.0 + p.1 * d.1;
    channels(
        stops,
        |e| 65536 * num >= e * den,
        |a, b| (65536 * num - a * den) as f64 / ((b - a) * den) as f64,
    )
}

/// The radial gradient around `centre` with radius `radius` (its absolute value) at the centre
/// of pixel `(x, y)`.
pub fn radial(
    centre: (i32, i32),
    radius: i32,
    stops: &[(u32, [u8; 3])],
    x: i32,
    y: i32,
) -> [f64; 3] {
    let r = i128::from(radius).abs();
    if r == 0 {
        return stops.last().map_or([0.0; 3], |s| s.1.map(f64::from));
    }
    let p = (
        256 * i128::from(x) + 128 - i128::from(centre.0),
        256 * i128::from(y) + 128 - i128::from(centre.1),
    );
    let d2 = p.0 * p.0 + p.1 * p.1;
    let d = (d2 as f64).sqrt();
    channels(
        stops,
        |e| (d2 << 32) >= (e * r) * (e * r),
        |a, b| (65536.0 * d / r as f64 - a as f64) / (b - a) as f64,
    )
}
