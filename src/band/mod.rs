//! Band rendering: a frame drawn in horizontal bands of a few rows, each into a small buffer and
//! sent to the display when finished, so that a 320×240 frame with a z-buffer needs RAM for one
//! band (320 × 16 rows × 4 bytes = 20 KB) instead of 300 KB.
//!
//! Every band has exactly the pixels (and depths) of the frame drawn at once: each triangle is
//! set up over the whole frame's clip as a full-frame draw sets it up, and the walk then starts
//! at the band's first row with the attribute planes advanced there in the same integers (see
//! `raster::band`), so no colour step is rounded anywhere else. The tests check this for every
//! band height from 1 to the frame's height, on random 2D scenes and on 3D meshes.
//!
//! * [`BandLayout`] — the frame's size and the rows of a band.
//! * [`ColorBand`] (2D: [`GouraudTriangle`](crate::GouraudTriangle),
//!   [`SolidTriangle`](crate::SolidTriangle), [`Triangle`]; any embedded-graphics drawable) and
//!   [`DepthBand`] (3D: [`Pipeline`](crate::Pipeline) meshes with z-buffer, culling, clipping and
//!   every shading) — one band of caller's buffers, in frame coordinates.
//! * [`ColorBands`] and [`DepthBands`] — a whole frame: the bands top to bottom, each drawn by
//!   the caller's closure and handed to a [`BandOutput`]: any `DrawTarget` ([`ToDisplay`]: one
//!   `fill_contiguous` of the band's rectangle, which SPI display drivers take as one window
//!   write) or a callback with the band's pixels as a slice ([`Callback`], e.g. for DMA). With
//!   two colour buffers the next band is drawn while the last one is sent. A render's one
//!   error type is [`RenderError`]: the set-up's [`BandError`] (`?` converts it) or the
//!   output's (the display's) error.
//! * A [`DepthBand`] is a target of the pipeline as a [`DepthTarget`](crate::DepthTarget) is:
//!   `pipeline.draw_mesh(mesh, material, band)`, in the same order for the whole frame and for
//!   a band.
//! * Without a bin, each band runs the whole draw again: a mesh's vertices are transformed for
//!   every band (faces wholly above or below the band are rejected from two rows of the
//!   transform, before projection) — no memory but the band's. With a bin ([`TriangleBin`],
//!   [`MeshBin`]: caller's storage of [`BinEntry`], 12 bytes per triangle kept and per band),
//!   the triangles are transformed, culled and sorted into the bands they touch once per frame,
//!   and each band draws only its own; a [`MeshBin`] takes a
//!   [`Material`](crate::three_d::Material) ([`MeshBin::new`]) or a
//!   [`TexturedMaterial`](crate::three_d::TexturedMaterial) ([`MeshBin::new_textured`]).
//!
//! Costs (Cortex-M4, the 3D bench knot at 320×240) are in `docs/benchmarks.md`.
//!
//! Bad input is an error before anything is drawn: a zero band height ([`BandLayout::new`]), a
//! buffer of the wrong length, a bin too small ([`BandError`]).
//!
//! # Examples
//!
//! A 3D mesh and a 2D overlay into any display, 16 rows at a time (here a
//! [`SliceFramebuffer`](crate::SliceFramebuffer) stands in for an SPI display driver's
//! `DrawTarget`):
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
//! use embedded_raster::band::{BandLayout, ColorBands, DepthBands, ToDisplay};
//! use embedded_raster::three_d::meshes::icosphere::ICOSPHERE;
//! use embedded_raster::three_d::{Angle, Light, Mat4, Material, Pipeline, Scalar, Shading, Vec3};
//! use embedded_raster::{Coord, SliceFramebuffer, SolidTriangle};
//!
//! let mut screen = [Rgb565::BLACK; 64 * 48];
//! let mut display = SliceFramebuffer::new(&mut screen, 64, 48).unwrap();
//!
//! let layout = BandLayout::new(Size::new(64, 48), 16)?;
//! let projection = Mat4::perspective(Angle::from_degrees(60), Scalar::from_num(4) / 3,
//!     Scalar::from_num(0.5), Scalar::from_num(20)).unwrap();
//! let view = Mat4::translation(Vec3::from_bits(0, 0, -3 << 16));
//! let viewport = Rectangle::new(Point::zero(), layout.size());
//! let light = Light::new(Vec3::new(0, 0, 1), 0.2);
//! let pipeline = Pipeline::new(Mat4::IDENTITY, projection * view, viewport, light);
//! let material = Material::new(Rgb565::WHITE, Shading::Gouraud);
//! let c = |x: i32, y: i32| (Coord::from_num(x), Coord::from_num(y));
//! let overlay = SolidTriangle::new([c(0, 0), c(12, 0), c(0, 12)], Rgb565::RED);
//!
//! let (mut colors, mut depth) = ([Rgb565::BLACK; 64 * 16], [0u16; 64 * 16]);
//! let mut bands = DepthBands::new(ColorBands::new(layout, &mut colors)?, &mut depth)?;
//! bands.render(&mut ToDisplay(&mut display), |band| {
//!     band.clear(Rgb565::BLUE);
//!     pipeline.draw_mesh(&ICOSPHERE, &material, band); // a band is the pipeline's target
//!     band.colors().draw(&overlay);
//! })?; // a RenderError: the display's error (none for a SliceFramebuffer) or a band's
//! assert_eq!(display.get(1, 1), Some(Rgb565::RED));
//! assert_ne!(display.get(32, 24), Some(Rgb565::BLUE)); // lit
//! # Ok::<(), embedded_raster::band::RenderError<core::convert::Infallible>>(())
//! ```

mod bin;
mod render;
mod target;

pub use bin::{BinEntry, MeshBin, TriangleBin};
pub use render::{BandOutput, Callback, ColorBands, DepthBands, ToDisplay};
pub use target::{BandDrawable, ColorBand, DepthBand, Triangle};

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use crate::three_d::ScratchTooSmall;

/// How a frame is cut into bands: the frame's size and the rows of a band (the last band has
/// the rows that are left).
///
/// ```
/// use embedded_graphics::{prelude::*, primitives::Rectangle};
/// use embedded_raster::band::{BandError, BandLayout};
///
/// let layout = BandLayout::new(Size::new(320, 240), 16)?;
/// assert_eq!((layout.count(), layout.buffer_len()), (15, 320 * 16));
/// let last = BandLayout::new(Size::new(320, 100), 32)?.band(3);
/// assert_eq!(last, Some(Rectangle::new(Point::new(0, 96), Size::new(320, 4))));
/// assert_eq!(BandLayout::new(Size::new(320, 240), 0), Err(BandError::ZeroRows));
/// # Ok::<(), BandError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct BandLayout {
    size: Size,
    rows: u32,
}

impl BandLayout {
    /// A frame of `size` in bands of `rows` rows. Errors: `rows` is 0, or a side of the frame
    /// does not fit an `i32` coordinate, or a band buffer (`width · rows`) is beyond `usize`.
    pub fn new(size: Size, rows: u32) -> Result<Self, BandError> {
        if rows == 0 {
            return Err(BandError::ZeroRows);
        }
        let fits = |side: u32| i32::try_from(side).is_ok();
        let buffer = usize::try_from(size.width)
            .ok()
            .and_then(|w| w.checked_mul(usize::try_from(rows).ok()?));
        if !fits(size.width) || !fits(size.height) || !fits(rows) || buffer.is_none() {
            return Err(BandError::FrameTooLarge);
        }
        Ok(BandLayout { size, rows })
    }

    /// The frame's size.
    pub fn size(&self) -> Size {
        self.size
    }

    /// Rows of a band (the last one may have fewer).
    pub fn rows(&self) -> u32 {
        self.rows
    }

    /// Number of bands: the frame's height divided by the rows of a band, rounded up.
    pub fn count(&self) -> u32 {
        self.size.height.div_ceil(self.rows)
    }

    /// Entries of one band buffer: `width · rows` (colours, or depths).
    pub fn buffer_len(&self) -> usize {
        // Checked in `new`.
        (self.size.width as usize).saturating_mul(self.rows as usize)
    }

    /// Band `index`'s rectangle in the frame (from the top), or `None` past the last.
    pub fn band(&self, index: u32) -> Option<Rectangle> {
        let first = index.checked_mul(self.rows)?;
        let rows = self.size.height.checked_sub(first)?.min(self.rows);
        (rows > 0).then(|| {
            Rectangle::new(
                Point::new(0, first as i32),
                Size::new(self.size.width, rows),
            )
        })
    }

    /// The bands' rectangles, top to bottom.
    pub fn bands(&self) -> impl Iterator<Item = Rectangle> + '_ {
        (0..self.count()).filter_map(|k| self.band(k))
    }
}

/// `len` against one band buffer of `layout`, of depths if `depth` (else colours).
fn check_buffer(layout: &BandLayout, len: usize, depth: bool) -> Result<(), BandError> {
    let (needed, given) = (layout.buffer_len(), len);
    match (needed == given, depth) {
        (true, _) => Ok(()),
        (false, false) => Err(BandError::ColorBuffer { needed, given }),
        (false, true) => Err(BandError::DepthBuffer { needed, given }),
    }
}

/// What is wrong with a band renderer's input; reported before anything is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BandError {
    /// A band of zero rows.
    ZeroRows,
    /// A side of the frame beyond `i32::MAX`, or a band buffer beyond `usize`.
    FrameTooLarge,
    /// A band index past the last band.
    NoSuchBand {
        /// The index given.
        index: u32,
        /// The layout's number of bands.
        count: u32,
    },
    /// A colour buffer of the wrong length: it must hold one band (`width · rows` entries).
    ColorBuffer {
        /// Entries a band buffer has.
        needed: usize,
        /// Entries given.
        given: usize,
    },
    /// A depth buffer of the wrong length: it must hold one band (`width · rows` entries).
    DepthBuffer {
        /// Entries a band buffer has.
        needed: usize,
        /// Entries given.
        given: usize,
    },
    /// A bin's storage holds fewer entries than its triangles and bands need (see
    /// [`BinEntry`]); nothing was drawn.
    BinTooSmall {
        /// Entries needed: one per band and one per triangle kept.
        needed: usize,
        /// Entries given.
        given: usize,
    },
    /// More triangles than a bin numbers (2³¹), or more bands (32,768).
    BinLimit,
    /// The vertex scratch of a [`MeshBin`] is too short.
    Scratch(ScratchTooSmall),
    /// A band of another layout than the bin's, or of another frame size.
    OtherLayout,
}

impl From<ScratchTooSmall> for BandError {
    fn from(e: ScratchTooSmall) -> Self {
        BandError::Scratch(e)
    }
}

impl core::fmt::Display for BandError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            BandError::ZeroRows => write!(f, "a band of 0 rows: a band needs at least 1 row"),
            BandError::FrameTooLarge => write!(
                f,
                "a frame side or band height beyond i32::MAX pixels, or a band buffer \
                 (width · rows) beyond usize::MAX entries"
            ),
            BandError::NoSuchBand { index, count } => write!(
                f,
                "band {index} asked for, but the layout has {count} bands (indices below {count})"
            ),
            BandError::ColorBuffer { needed, given } => write!(
                f,
                "a colour band buffer needs {needed} pixels (width · rows), given {given}"
            ),
            BandError::DepthBuffer { needed, given } => write!(
                f,
                "a depth band buffer needs {needed} entries (width · rows), given {given}"
            ),
            BandError::BinTooSmall { needed, given } => write!(
                f,
                "a bin needs {needed} entries (one per band and per triangle kept), given {given}"
            ),
            BandError::BinLimit => write!(
                f,
                "a bin numbers at most 2^31 triangles and 32768 bands, given more"
            ),
            BandError::Scratch(e) => e.fmt(f),
            BandError::OtherLayout => write!(
                f,
                "a band of another layout (frame size or band height) than the bin's"
            ),
        }
    }
}

impl core::error::Error for BandError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            BandError::Scratch(e) => Some(e),
            _ => None,
        }
    }
}

/// What went wrong in a frame drawn in bands: the one error type of a render, so that `?` takes
/// both the set-up's errors ([`BandError`], through `From`) and [`render`](DepthBands::render)'s
/// into a function's result.
///
/// `E` is the band output's error: a display driver's `DrawTarget::Error` through
/// [`ToDisplay`], or a [`Callback`]'s. The message and [`core::error::Error`] need only
/// `E: Debug` (every `DrawTarget::Error` is), so a render's error goes into
/// `Box<dyn std::error::Error>` whatever the display.
///
/// ```
/// use embedded_graphics::{pixelcolor::Gray8, prelude::*, primitives::Rectangle};
/// use embedded_raster::band::{BandError, BandLayout, Callback, ColorBands, RenderError};
///
/// fn frame(rows: u32, fail: bool) -> Result<u32, RenderError<&'static str>> {
///     let layout = BandLayout::new(Size::new(16, 8), rows)?; // a BandError
///     let mut pixels = [Gray8::BLACK; 16 * 4];
///     let mut bands = ColorBands::new(layout, &mut pixels)?; // a BandError
///     let mut sent = 0;
///     let mut output = Callback(|_: &Rectangle, _: &[Gray8]| {
///         sent += 1;
///         if fail { Err("the display went away") } else { Ok(()) }
///     });
///     bands.render(&mut output, |band| band.clear(Gray8::WHITE))?; // the display's error
///     Ok(sent)
/// }
///
/// assert_eq!(frame(4, false), Ok(2));
/// assert_eq!(frame(0, false), Err(RenderError::Band(BandError::ZeroRows)));
/// assert_eq!(frame(2, false), Err(RenderError::Band(BandError::ColorBuffer { needed: 32, given: 64 })));
/// assert_eq!(frame(4, true), Err(RenderError::Display("the display went away")));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RenderError<E> {
    /// The renderer's input (a layout, a buffer, a bin): reported before the band it concerns
    /// is drawn.
    Band(BandError),
    /// The band output's (the display's) error; the frame stopped there.
    Display(E),
}

impl<E> From<BandError> for RenderError<E> {
    fn from(e: BandError) -> Self {
        RenderError::Band(e)
    }
}

impl<E> From<ScratchTooSmall> for RenderError<E> {
    fn from(e: ScratchTooSmall) -> Self {
        RenderError::Band(BandError::Scratch(e))
    }
}

impl<E: core::fmt::Debug> core::fmt::Display for RenderError<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RenderError::Band(e) => e.fmt(f),
            RenderError::Display(e) => write!(f, "the display (band output) failed: {e:?}"),
        }
    }
}

impl<E: core::fmt::Debug> core::error::Error for RenderError<E> {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            // The message is the band error's own: its source is the band error's source.
            RenderError::Band(e) => e.source(),
            RenderError::Display(_) => None,
        }
    }
}

/// What a band's draw closure of [`ColorBands::render`] and [`DepthBands::render`] may return:
/// nothing (`()`), or a `Result` whose error converts into a [`BandError`] (a bin's
/// `bin.draw(band)`, a scratch draw's [`ScratchTooSmall`]), which stops the frame.
pub trait BandDrawn {
    /// `Ok(())`, or the error that stops the frame.
    fn into_band_result(self) -> Result<(), BandError>;
}

impl BandDrawn for () {
    #[inline(always)]
    fn into_band_result(self) -> Result<(), BandError> {
        Ok(())
    }
}

impl<T, E: Into<BandError>> BandDrawn for Result<T, E> {
    #[inline(always)]
    fn into_band_result(self) -> Result<(), BandError> {
        self.map(|_| ()).map_err(Into::into)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use std::string::ToString;

    use super::*;

    /// Each error's message: what was needed and what was given (issue #32, item 2).
    #[test]
    fn messages() {
        let cases = [
            (
                BandError::ZeroRows,
                "a band of 0 rows: a band needs at least 1 row",
            ),
            (
                BandError::FrameTooLarge,
                "a frame side or band height beyond i32::MAX pixels, or a band buffer \
                 (width · rows) beyond usize::MAX entries",
            ),
            (
                BandError::NoSuchBand {
                    index: 15,
                    count: 15,
                },
                "band 15 asked for, but the layout has 15 bands (indices below 15)",
            ),
            (
                BandError::ColorBuffer {
                    needed: 5120,
                    given: 5119,
                },
                "a colour band buffer needs 5120 pixels (width · rows), given 5119",
            ),
            (
                BandError::DepthBuffer {
                    needed: 5120,
                    given: 0,
                },
                "a depth band buffer needs 5120 entries (width · rows), given 0",
            ),
            (
                BandError::BinTooSmall {
                    needed: 300,
                    given: 20,
                },
                "a bin needs 300 entries (one per band and per triangle kept), given 20",
            ),
            (
                BandError::BinLimit,
                "a bin numbers at most 2^31 triangles and 32768 bands, given more",
            ),
            (
                BandError::Scratch(ScratchTooSmall {
                    needed: 42,
                    given: 12,
                }),
                "a vertex scratch needs 42 entries (one per vertex of the mesh), given 12",
            ),
            (
                BandError::OtherLayout,
                "a band of another layout (frame size or band height) than the bin's",
            ),
        ];
        for (error, message) in cases {
            assert_eq!(error.to_string(), message);
        }
        // The scratch's error is the source of the band error that wraps it.
        let scratch = ScratchTooSmall {
            needed: 42,
            given: 12,
        };
        let wrapped = BandError::Scratch(scratch);
        let source = core::error::Error::source(&wrapped);
        assert_eq!(source.map(|e| e.to_string()), Some(scratch.to_string()));
        assert!(core::error::Error::source(&BandError::ZeroRows).is_none());
    }
}
