//! Sub-pixel fixed-point coordinates.
//!
//! Vertices are given as [`Coord`], a signed 24.8 fixed-point number: 256 sub-pixel steps per pixel,
//! the same precision as Direct3D 11. Pixel `(i, j)` covers the unit square `[i, i+1) × [j, j+1)` and
//! its centre is at `(i + 0.5, j + 0.5)`; `y` grows downward, as in embedded-graphics.
//!
//! Every bit pattern of `Coord` is a valid vertex coordinate (about ±8.4 million pixels); the
//! rasterizer does its setup in wide integers, so no vertex position can overflow it.
//!
//! # From what you have
//!
//! * **Floats**: the constructors take any [`ToCoord`] (`f32`, `f64` or `Coord`), so
//!   `Vertex::new(10.25, 3.0, color)` works; `x.to_coord()` converts one number. Conversion
//!   rounds to the nearest 1/256 pixel, saturates beyond the range and maps NaN to 0;
//!   [`ToCoord::try_to_coord`] is the checked form (`None` for NaN, infinities and values beyond
//!   the range: [converting floats](crate#converting-floats)). It is a
//!   conversion you call, never part of drawing: on a Cortex-M0 it runs in software floating point
//!   (and is linked only if used).
//! * **Integer pixel positions** need a placement, so integers are not [`ToCoord`]:
//!   [`pixel_centre`]`(i)` is the centre `i + 0.5` of pixel `i`, [`pixel_corner`]`(i)` its top-left
//!   corner `i`. [`Vertex::at_pixel_centre`](crate::Vertex::at_pixel_centre) and
//!   [`at_pixel_corner`](crate::Vertex::at_pixel_corner) do the same for an embedded-graphics
//!   `Point`.
//! * **embedded-graphics `Point`s**: place them at pixel centres
//!   ([`SolidTriangle::at_pixel_centres`](crate::SolidTriangle::at_pixel_centres)): then a
//!   triangle covers the pixels of an embedded-graphics filled `Triangle` of the same points except
//!   along its edges, where embedded-graphics also draws the pixels its outline passes through
//!   and the top-left rule gives a pixel whose centre is on an edge to one side only (measured in
//!   `tests/all/eg_placement.rs`; see [`SolidTriangle::at_pixel_centres`](crate::SolidTriangle::at_pixel_centres)).
//! * **Raw bits**: `Coord::from_bits(raw)` (`256` is one pixel), also in `const` items.
//!
//! `Coord` is the `fixed` crate's `I24F8`, so all of its methods apply: `from_num` (panics on
//! overflow), `saturating_from_num`, `checked_from_num`, `to_num::<f32>()`, `from_bits`,
//! `to_bits`, arithmetic with other `Coord`s and with `i32`.
//!
//! ```
//! use embedded_raster::fixed_point::{pixel_centre, pixel_corner, ToCoord};
//! use embedded_raster::Coord;
//!
//! let x = Coord::from_num(10.25);
//! assert_eq!(x.to_bits(), 10 * 256 + 64);
//! assert_eq!(10.25f32.to_coord(), x);
//! assert_eq!(1e30f64.to_coord(), Coord::MAX);
//! assert_eq!(f32::NAN.to_coord(), Coord::ZERO);
//! assert_eq!(pixel_centre(3), Coord::from_num(3.5));
//! assert_eq!(pixel_corner(3), Coord::from_num(3));
//! ```

/// A sub-pixel coordinate: signed fixed point with [`SUBPIXEL_BITS`] fractional bits (the `fixed`
/// crate's `I24F8`: ±2²³ pixels, 1/256 pixel). See the [module docs](self) for how to make one
/// from floats, pixel indices and embedded-graphics `Point`s.
pub type Coord = fixed::types::I24F8;

/// A number that converts to a [`Coord`]: `f32` and `f64` (rounded to the nearest 1/256 pixel,
/// saturated to the `Coord` range, NaN as 0) and `Coord` itself.
/// [`try_to_coord`](Self::try_to_coord) is the checked form: `None` for NaN, an infinity or a
/// value beyond the range ([converting floats](crate#converting-floats)).
///
/// ```
/// use embedded_raster::{Coord, ToCoord};
///
/// assert_eq!(f32::NAN.to_coord(), Coord::ZERO);
/// assert_eq!(f32::NAN.try_to_coord(), None);
/// assert_eq!(1e30.try_to_coord(), None);
/// assert_eq!(10.25.try_to_coord(), Some(Coord::from_num(10.25)));
/// ```
///
/// Integers are deliberately not `ToCoord`: an integer is a pixel index, and whether it means
/// the pixel's centre or its corner is a choice ([`pixel_centre`], [`pixel_corner`]).
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not a sub-pixel coordinate",
    label = "expected `f32`, `f64` or `Coord`",
    note = "an integer is a pixel index: place it with `fixed_point::pixel_centre(i)` (the embedded-graphics placement) or `pixel_corner(i)`, `Vertex::at_pixel_centre(point, color)`, or write a float (`10.0`)"
)]
pub trait ToCoord: Copy {
    /// The coordinate: rounded to the nearest 1/256 pixel, saturated to the range, NaN as 0.
    fn to_coord(self) -> Coord;

    /// The coordinate, or `None` if the value has none: NaN, an infinity, or beyond the `Coord`
    /// range (after rounding to the nearest 1/256 pixel). The default is
    /// `Some(self.to_coord())`.
    fn try_to_coord(self) -> Option<Coord> {
        Some(self.to_coord())
    }
}

impl ToCoord for Coord {
    #[inline(always)]
    fn to_coord(self) -> Coord {
        self
    }
}

impl ToCoord for f32 {
    fn to_coord(self) -> Coord {
        f64::from(self).to_coord()
    }

    fn try_to_coord(self) -> Option<Coord> {
        f64::from(self).try_to_coord()
    }
}

impl ToCoord for f64 {
    fn to_coord(self) -> Coord {
        if self.is_nan() {
            Coord::ZERO
        } else {
            // `fixed` converts from the float's bits (round to nearest, ties to even): no float
            // arithmetic.
            Coord::saturating_from_num(self)
        }
    }

    fn try_to_coord(self) -> Option<Coord> {
        // `None` for NaN, infinities and overflow.
        Coord::checked_from_num(self)
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    /// The checked form: `None` for NaN, infinities and values beyond the range (after rounding),
    /// otherwise exactly the saturating form's value.
    #[test]
    fn checked_floats() {
        extern crate std;
        let max = f64::from(i32::MAX) / 256.0;
        let min = f64::from(i32::MIN) / 256.0;
        for v in [
            f64::NAN,
            -f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e30,
            -1e300,
            8_388_608.0,       // 2²³: one beyond the largest
            max + 1.0 / 512.0, // rounds up past the largest (a tie, to even: 2²³)
            min - 1.0,         // below the smallest
            f64::from(f32::MAX),
        ] {
            assert_eq!(v.try_to_coord(), None, "{v}");
            assert_eq!((v as f32).try_to_coord(), None, "{v} as f32");
        }
        for (v, bits) in [
            (0.0, 0),
            (-0.0, 0),
            (10.25, 10 * 256 + 64),
            (-10.25, -(10 * 256 + 64)),
            (1.0 / 512.0, 0), // a tie: to even, as the saturating form
            (3.0 / 512.0, 2),
            (max, i32::MAX),
            (min, i32::MIN),
            (f64::MIN_POSITIVE, 0),
        ] {
            assert_eq!(v.try_to_coord().map(Coord::to_bits), Some(bits), "{v}");
            assert_eq!(v.try_to_coord(), Some(v.to_coord()), "{v}");
        }
        assert_eq!(0.75f32.try_to_coord().map(Coord::to_bits), Some(192));
        assert_eq!(Coord::MAX.try_to_coord(), Some(Coord::MAX));
        // In range, the checked form is the saturating one.
        let mut next = crate::random(11);
        for _ in 0..10_000 {
            let v = ((next() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * 8_388_000.0;
            assert_eq!(v.try_to_coord(), Some(v.to_coord()), "{v}");
            let f = v as f32;
            assert_eq!(f.try_to_coord(), Some(f.to_coord()), "{f}");
        }
    }

    #[test]
    fn floats_round_and_saturate() {
        extern crate std;
        for (v, bits) in [
            (0.0, 0),
            (1.0 / 512.0, 0),        // a tie: to even
            (3.0 / 512.0, 2),        // a tie: to even
            (1.0 / 512.0 + 1e-9, 1), // just above the tie
            (-10.25, -(10 * 256 + 64)),
            (8_388_607.996, i32::MAX), // rounds to the largest value
            (8_388_608.0, i32::MAX),   // beyond the range: saturates
            (-1e300, i32::MIN),
            (f64::INFINITY, i32::MAX),
            (f64::NEG_INFINITY, i32::MIN),
        ] {
            assert_eq!(v.to_coord().to_bits(), bits, "{v}");
        }
        assert_eq!(f64::NAN.to_coord(), Coord::ZERO);
        assert_eq!(0.75f32.to_coord().to_bits(), 192);
        // Against an independent reference: round(v · 256) for exactly representable
        // non-tie values.
        let mut next = crate::random(7);
        for _ in 0..10_000 {
            let raw = (next() >> 40) as i64 - (1 << 23);
            let v = raw as f64 / 1000.0;
            let want = (v * 256.0).round() as i32;
            let got = v.to_coord().to_bits();
            let tie = (v * 256.0).fract().abs() == 0.5;
            assert!(got == want || tie, "{v}: {got} vs {want}");
        }
    }

    #[test]
    fn centre_and_corner() {
        assert_eq!(pixel_centre(0).to_bits(), 128);
        assert_eq!(pixel_centre(-1).to_bits(), -128);
        assert_eq!(pixel_corner(-2).to_bits(), -512);
        assert_eq!(pixel_centre(i32::MAX).to_bits(), i32::MAX);
        assert_eq!(pixel_corner(i32::MIN).to_bits(), i32::MIN);
    }
}
