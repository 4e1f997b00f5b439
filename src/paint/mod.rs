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

use crate::color::{fill_row, BlendSource, GouraudColor};

pub mod gradient;

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

    /// The one colour of every pixel, for a paint that has one (a plain colour): the shapes
    /// then store it into one-pixel runs (a steep line's) without a row fill. `None` (the
    /// default) for paints that vary or read the pixels under them.
    #[inline(always)]
    fn uniform(&self) -> Option<Self::Color> {
        None
    }

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
    fn uniform(&self) -> Option<C> {
        Some(*self)
    }

    #[inline(always)]
    fn draw_row<D>(&self, target: &mut D, y: i32, x: i32, len: u32) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        target.fill_solid(&Rectangle::new(Point::new(x, y), Size::new(len, 1)), *self)
    }
}

/// A colour at an opacity, blended source-over what is under it, in the target's own channel
/// depth (the colours of [`GouraudColor::blend`], as a translucent triangle's).
///
/// Into a [`SliceFramebuffer`](crate::SliceFramebuffer) or a band it blends over the pixels
/// there; `Drawable::draw` into another `DrawTarget`, which cannot be read, blends over the
/// `background` colour given — the same pixels where the target holds that colour.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::paint::Translucent;
/// use embedded_raster::{Polygon, SliceFramebuffer};
///
/// let mut pixels = [Rgb565::BLUE; 16 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
/// let square = Polygon::<4>::from_points(&[(0.0, 0.0), (16.0, 0.0), (16.0, 16.0), (0.0, 16.0)])?;
/// square.filled(Translucent::new(Rgb565::RED, 128, Rgb565::BLUE)).draw_into(&mut fb);
/// assert_eq!(fb.get(3, 3), Some(Rgb565::RED.blend(Rgb565::BLUE, 128)));
/// # use embedded_raster::GouraudColor;
/// # Ok::<(), embedded_raster::PolygonFull>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Translucent<C> {
    color: C,
    opacity: u8,
    /// `color` over the background: what `draw_row` fills with.
    over_background: C,
    source: BlendSource,
}

impl<C: GouraudColor> Translucent<C> {
    /// `color` at `opacity` (0 transparent, 255 opaque), over `background` where the target
    /// cannot be read.
    pub fn new(color: C, opacity: u8, background: C) -> Self {
        Translucent {
            color,
            opacity,
            over_background: color.blend(background, opacity),
            source: BlendSource::new(color, opacity),
        }
    }

    /// The colour.
    pub fn color(&self) -> C {
        self.color
    }

    /// The opacity.
    pub fn opacity(&self) -> u8 {
        self.opacity
    }
}

impl<C: GouraudColor> Paint for Translucent<C> {
    type Color = C;

    #[inline]
    fn paint_row(&self, _y: i32, _x: i32, row: &mut [C]) {
        C::blend_solid(row, &self.source);
    }

    #[inline]
    fn draw_row<D>(&self, target: &mut D, y: i32, x: i32, len: u32) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        self.over_background.draw_row(target, y, x, len)
    }
}
