//! Paints: what fills the covered spans of a shape.
//!
//! A shape's scan conversion (a polygon's rows, a triangle's walk) finds which pixels it covers;
//! a [`Paint`] decides their colours from their positions alone. A plain colour is a paint (every
//! [`PixelColor`] is one); so are the gradients that fill shapes by position rather than by vertex.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use embedded_raster::paint::Paint;
//!
//! let mut row = [Rgb565::BLACK; 4];
//! Rgb565::RED.paint_row(0, 0, &mut row);
//! assert_eq!(row, [Rgb565::RED; 4]);
//! ```

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use crate::color::fill_row;

mod gradient;

pub(crate) use gradient::{dithered_color, fill_dithered};
pub use gradient::{LinearGradient, RadialGradient, Stop, STOP_ONE};

/// The colours of a shape's pixels, by position: a plain colour, or a gradient.
///
/// The shapes that take a paint ([`Polygon`](crate::Polygon)'s fills) hand it each covered span
/// once, left to right, as a slice of a framebuffer's row ([`paint_row`](Self::paint_row)) or
/// as a run of a `DrawTarget` ([`draw_row`](Self::draw_row)); both must give the same colours.
pub trait Paint {
    /// The colour format it paints.
    type Color: PixelColor;

    /// Sets `row` to the colours of pixels `x .. x + row.len()` of row `y`.
    fn paint_row(&self, y: i32, x: i32, row: &mut [Self::Color]);

    /// Draws pixels `x .. x + len` of row `y` into `target` (inside its bounds) with the colours
    /// [`paint_row`](Self::paint_row) gives them.
    fn draw_row<D>(&self, target: &mut D, y: i32, x: i32, len: u32) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = Self::Color>;
}

/// A plain colour paints every pixel with itself.
impl<C: PixelColor> Paint for C {
    type Color = C;

    #[inline(always)]
    fn paint_row(&self, _y: i32, _x: i32, row: &mut [C]) {
        fill_row(row, *self);
    }

    #[inline(always)]
    fn draw_row<D>(&self, target: &mut D, y: i32, x: i32, len: u32) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        target.fill_solid(&Rectangle::new(Point::new(x, y), Size::new(len, 1)), *self)
    }
}
