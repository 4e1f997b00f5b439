//! Sub-pixel fixed-point coordinates.
//!
//! Vertices are given as [`Coord`], a signed 24.8 fixed-point number: 256 sub-pixel steps per pixel,
//! the same precision as Direct3D 11. Pixel `(i, j)` covers the unit square `[i, i+1) × [j, j+1)` and
//! its centre is at `(i + 0.5, j + 0.5)`; `y` grows downward, as in embedded-graphics.
//!
//! Every bit pattern of `Coord` is a valid vertex coordinate (about ±8.4 million pixels); the
//! rasterizer does its setup in wide integers, so no vertex position can overflow it.
//!
//! ```
//! use embedded_raster::{Coord, fixed_point};
//!
//! let x = Coord::from_num(10.25);
//! assert_eq!(x.to_bits(), 10 * 256 + 64);
//! assert_eq!(fixed_point::pixel_centre(3), Coord::from_num(3.5));
//! ```

/// A sub-pixel coordinate: signed fixed point with [`SUBPIXEL_BITS`] fractional bits.
pub type Coord = fixed::types::I24F8;

/// Number of fractional (sub-pixel) bits of [`Coord`].
pub const SUBPIXEL_BITS: u32 = 8;

/// Sub-pixel steps per pixel (`1 << SUBPIXEL_BITS`).
pub const SUBPIXEL_ONE: i64 = 1 << SUBPIXEL_BITS;

/// Offset of a pixel centre from the pixel's corner, in sub-pixel units.
pub(crate) const HALF_PIXEL: i64 = SUBPIXEL_ONE / 2;

/// The coordinate of the centre of pixel column/row `i`, saturating at the ends of the `Coord` range.
pub fn pixel_centre(i: i32) -> Coord {
    let raw = (i64::from(i) << SUBPIXEL_BITS) + HALF_PIXEL;
    Coord::from_bits(raw.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32)
}

/// The coordinate of the top-left corner of pixel column/row `i`, saturating at the ends of the
/// `Coord` range. An embedded-graphics `Point` maps to the corner of its pixel.
pub fn pixel_corner(i: i32) -> Coord {
    let raw = i64::from(i) << SUBPIXEL_BITS;
    Coord::from_bits(raw.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32)
}

/// Raw sub-pixel value of a coordinate, widened.
#[inline]
pub(crate) fn raw(c: Coord) -> i64 {
    i64::from(c.to_bits())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_and_corner() {
        assert_eq!(pixel_centre(0).to_bits(), 128);
        assert_eq!(pixel_centre(-1).to_bits(), -128);
        assert_eq!(pixel_corner(-2).to_bits(), -512);
        assert_eq!(pixel_centre(i32::MAX).to_bits(), i32::MAX);
        assert_eq!(pixel_corner(i32::MIN).to_bits(), i32::MIN);
    }
}
