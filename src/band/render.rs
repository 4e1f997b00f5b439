//! A whole frame in bands: each band drawn by the caller into one of one or two colour buffers
//! (and a depth buffer for 3D), then handed to a [`BandOutput`].

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::target::{ColorBand, DepthBand, Placement};
use super::{check_buffer, BandDrawn, BandError, BandLayout, RenderError};
use crate::color::GouraudColor;

/// Where finished bands go: a display, a DMA channel, a checksum.
///
/// The renderer calls [`send`](Self::send) once per band, top to bottom, with the band's
/// rectangle in the frame and its pixels (row-major, exactly its width × height of them), and
/// [`wait`](Self::wait) before it writes into that band's buffer again and once after the
/// last band. A synchronous output does all its work in `send`; an asynchronous one (DMA) may
/// start a transfer of the pixels in `send` and return at once — with two colour buffers
/// ([`ColorBands::double`]) the next band is then drawn into the other buffer while the
/// transfer runs, and `wait` returns when it has finished. The pixels stay untouched from `send`
/// until `wait` returns (the output may keep their address for a transfer for that long).
pub trait BandOutput<C> {
    /// The output's error; the frame stops at the first.
    type Error;

    /// Takes the finished band `area` with its `pixels`.
    fn send(&mut self, area: &Rectangle, pixels: &[C]) -> Result<(), Self::Error>;

    /// Returns when the band sent last no longer needs its pixels. By default at once: `send`
    /// was synchronous.
    fn wait(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
}

/// Any embedded-graphics [`DrawTarget`] as a band output: each band is one `fill_contiguous`
/// of its rectangle, which display drivers turn into one window and one pixel stream (SPI
/// drivers of the ILI9341, ST7789 and their kin do).
///
/// # Examples
///
/// A frame of 16 × 12 pixels in bands of 4 rows into a display (here a
/// [`SliceFramebuffer`](crate::SliceFramebuffer); a display driver's error would come back
/// from `render`):
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::band::{BandLayout, ColorBands, ToDisplay};
/// use embedded_raster::{SliceFramebuffer, SolidTriangle};
///
/// let mut screen = [Rgb565::BLACK; 16 * 12];
/// let mut display = SliceFramebuffer::new(&mut screen, 16, 12)?;
///
/// let layout = BandLayout::new(Size::new(16, 12), 4)?;
/// let mut band_pixels = [Rgb565::BLACK; 16 * 4];
/// let mut bands = ColorBands::new(layout, &mut band_pixels)?;
/// let triangle = SolidTriangle::new([(0.0, 0.0), (16.0, 0.0), (0.0, 12.0)], Rgb565::GREEN);
/// bands
///     .render(&mut ToDisplay(&mut display), |band| {
///         band.clear(Rgb565::BLUE);
///         band.draw(&triangle);
///     })
///     .unwrap(); // a SliceFramebuffer's error: `Infallible`
///
/// assert_eq!(display.get(1, 1), Some(Rgb565::GREEN));
/// assert_eq!(display.get(15, 11), Some(Rgb565::BLUE));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct ToDisplay<'d, D>(pub &'d mut D);

impl<D: DrawTarget> BandOutput<D::Color> for ToDisplay<'_, D> {
    type Error = D::Error;

    fn send(&mut self, area: &Rectangle, pixels: &[D::Color]) -> Result<(), D::Error> {
        self.0.fill_contiguous(area, pixels.iter().copied())
    }
}

/// A closure as a band output, called with each band's rectangle and pixels (for DMA, or a
/// checksum); `wait` returns at once.
///
/// # Examples
///
/// The bands of a 16 × 10 frame in bands of 4 rows (the last one 2 rows), as a transfer
/// would take them; an `Err` from the closure stops the frame and comes back from `render`:
///
/// ```
/// use embedded_graphics::{pixelcolor::Gray8, prelude::*, primitives::Rectangle};
/// use embedded_raster::band::{BandLayout, Callback, ColorBands, RenderError};
///
/// let layout = BandLayout::new(Size::new(16, 10), 4)?;
/// let mut band_pixels = [Gray8::BLACK; 16 * 4];
/// let mut bands = ColorBands::new(layout, &mut band_pixels)?;
///
/// let mut sent = Vec::new();
/// let mut output = Callback(|area: &Rectangle, pixels: &[Gray8]| {
///     sent.push((area.top_left.y, area.size.height, pixels.len()));
///     Ok::<(), ()>(())
/// });
/// bands.render(&mut output, |band| band.clear(Gray8::WHITE)).unwrap();
/// assert_eq!(sent, [(0, 4, 64), (4, 4, 64), (8, 2, 32)]);
///
/// // The output's error ends the frame: nothing more is drawn or sent.
/// let mut calls = 0;
/// let mut failing = Callback(|_: &Rectangle, _: &[Gray8]| {
///     calls += 1;
///     Err("the display went away")
/// });
/// let result = bands.render(&mut failing, |band| band.clear(Gray8::WHITE));
/// assert_eq!(result, Err(RenderError::Display("the display went away")));
/// assert_eq!(calls, 1);
/// # Ok::<(), embedded_raster::band::BandError>(())
/// ```
#[derive(Debug)]
pub struct Callback<F>(pub F);

impl<C, E, F: FnMut(&Rectangle, &[C]) -> Result<(), E>> BandOutput<C> for Callback<F> {
    type Error = E;

    fn send(&mut self, area: &Rectangle, pixels: &[C]) -> Result<(), E> {
        (self.0)(area, pixels)
    }
}

/// A frame drawn in bands for 2D: the layout and one or two colour buffers of one band each.
///
/// # Examples
///
/// A 2D scene (painter's order) into a display, 8 rows at a time with two buffers:
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::band::{BandLayout, ColorBands, ToDisplay, Triangle};
/// use embedded_raster::{Coord, GouraudTriangle, SliceFramebuffer, SolidTriangle, Vertex};
///
/// let v = |x: i32, y: i32, c| Vertex::new(Coord::from_num(x), Coord::from_num(y), c);
/// let p = |x: i32, y: i32| (Coord::from_num(x), Coord::from_num(y));
/// let scene: [Triangle<Rgb565>; 2] = [
///     GouraudTriangle::new([v(0, 0, Rgb565::RED), v(40, 2, Rgb565::GREEN), v(5, 30, Rgb565::BLUE)]).into(),
///     SolidTriangle::new([p(10, 10), p(40, 12), p(20, 30)], Rgb565::WHITE).into(),
/// ];
///
/// let mut screen = [Rgb565::BLACK; 40 * 30];
/// let mut display = SliceFramebuffer::new(&mut screen, 40, 30).unwrap();
/// let layout = BandLayout::new(Size::new(40, 30), 8)?;
/// let (mut front, mut back) = ([Rgb565::BLACK; 40 * 8], [Rgb565::BLACK; 40 * 8]);
/// let mut bands = ColorBands::double(layout, &mut front, &mut back)?;
/// bands
///     .render(&mut ToDisplay(&mut display), |band| {
///         band.clear(Rgb565::BLACK);
///         band.draw_all(&scene);
///     })
///     .unwrap();
/// assert_eq!(display.get(20, 15), Some(Rgb565::WHITE));
/// # Ok::<(), embedded_raster::band::BandError>(())
/// ```
#[derive(Debug)]
pub struct ColorBands<'a, C> {
    layout: BandLayout,
    front: &'a mut [C],
    back: Option<&'a mut [C]>,
}

impl<'a, C: PixelColor> ColorBands<'a, C> {
    /// Bands of `layout` drawn into `color` (exactly one band buffer,
    /// [`BandLayout::buffer_len`] pixels), each sent before the next is drawn.
    pub fn new(layout: BandLayout, color: &'a mut [C]) -> Result<Self, BandError> {
        check_buffer(&layout, color.len(), false)?;
        Ok(ColorBands {
            layout,
            front: color,
            back: None,
        })
    }

    /// Bands of `layout` drawn alternately into `front` and `back` (one band buffer each), so
    /// that one band is drawn while the other is being sent.
    pub fn double(
        layout: BandLayout,
        front: &'a mut [C],
        back: &'a mut [C],
    ) -> Result<Self, BandError> {
        check_buffer(&layout, front.len(), false)?;
        check_buffer(&layout, back.len(), false)?;
        Ok(ColorBands {
            layout,
            front,
            back: Some(back),
        })
    }

    /// The layout.
    pub fn layout(&self) -> &BandLayout {
        &self.layout
    }

    /// Draws the frame: for each band, top to bottom, `draw` and then `output`. `draw` returns
    /// nothing, or a `Result` whose error is a [`BandError`] (a bin's draw: `bin.draw(band)`).
    /// Stops at the first error, the output's ([`RenderError::Display`]) or `draw`'s
    /// ([`RenderError::Band`]; that band is not sent).
    pub fn render<O: BandOutput<C>, R: BandDrawn>(
        &mut self,
        output: &mut O,
        mut draw: impl FnMut(&mut ColorBand<'_, C>) -> R,
    ) -> Result<(), RenderError<O::Error>> {
        self.each(output, |pixels, placement| {
            let mut band = ColorBand::placed(pixels, placement)?;
            draw(&mut band).into_band_result()?;
            Ok(band.pixels().len())
        })
    }

    /// The bands top to bottom, alternating buffers: `draw` fills one (and says how many of its
    /// pixels the band has), `output` takes it; before a buffer is drawn into again, and at the
    /// end, `output` waits.
    fn each<O: BandOutput<C>>(
        &mut self,
        output: &mut O,
        mut draw: impl FnMut(&mut [C], Placement) -> Result<usize, BandError>,
    ) -> Result<(), RenderError<O::Error>> {
        let mut sent = false;
        let double = self.back.is_some();
        for index in 0..self.layout.count() {
            let placement = Placement::new(&self.layout, index)?;
            let buffer = match &mut self.back {
                Some(back) if index % 2 == 1 => &mut **back,
                _ => &mut *self.front,
            };
            // One buffer: the last band's transfer must end before it is drawn over.
            if sent && !double {
                output.wait().map_err(RenderError::Display)?;
            }
            let len = match draw(buffer, placement) {
                Ok(len) => len,
                Err(e) => {
                    // The bands sent are finished with before the error comes back.
                    if sent {
                        output.wait().map_err(RenderError::Display)?;
                    }
                    return Err(RenderError::Band(e));
                }
            };
            // With two, the other buffer's transfer ends before this one starts.
            if sent && double {
                output.wait().map_err(RenderError::Display)?;
            }
            let buffer = match &self.back {
                Some(back) if index % 2 == 1 => &**back,
                _ => &*self.front,
            };
            output
                .send(&placement.rect(), buffer.get(..len).unwrap_or(buffer))
                .map_err(RenderError::Display)?;
            sent = true;
        }
        if sent {
            output.wait().map_err(RenderError::Display)?;
        }
        Ok(())
    }
}

/// A frame drawn in bands for 3D: [`ColorBands`] and a depth buffer of one band (the depths are
/// not sent).
///
/// # Examples
///
/// See [the module](super) for a mesh into a display; here the bands go to a callback that
/// checksums them, as a DMA transfer would take them.
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
/// use embedded_raster::band::{BandLayout, Callback, ColorBands, DepthBands};
/// use embedded_raster::three_d::meshes::torus::TORUS;
/// use embedded_raster::three_d::{Angle, Light, Mat4, Material, Pipeline, Scalar, Shading, Vec3};
///
/// let layout = BandLayout::new(Size::new(48, 32), 4)?;
/// let projection = Mat4::perspective(Angle::from_degrees(60), Scalar::from_num(1.5),
///     Scalar::from_num(0.5), Scalar::from_num(20)).unwrap();
/// let view = Mat4::translation(Vec3::from_bits(0, 0, -3 << 16));
/// let viewport = Rectangle::new(Point::zero(), layout.size());
/// let pipeline = Pipeline::new(Mat4::rotation_x(Angle::from_degrees(50)), projection * view,
///     viewport, Light::default());
/// let material = Material::new(Rgb565::YELLOW, Shading::Flat);
///
/// let (mut front, mut back, mut depth) = ([Rgb565::BLACK; 48 * 4], [Rgb565::BLACK; 48 * 4], [0; 48 * 4]);
/// let mut bands = DepthBands::new(ColorBands::double(layout, &mut front, &mut back)?, &mut depth)?;
/// let mut rows = 0;
/// let mut checksum = 0u32;
/// bands
///     .render(
///         &mut Callback(|area: &Rectangle, pixels: &[Rgb565]| {
///             rows += area.size.height;
///             for p in pixels {
///                 checksum = checksum.rotate_left(5) ^ u32::from(p.into_storage());
///             }
///             Ok::<(), ()>(())
///         }),
///         |band| {
///             band.clear(Rgb565::BLACK);
///             pipeline.draw_mesh(&TORUS, &material, band);
///         },
///     )
///     .unwrap();
/// assert_eq!(rows, 32);
/// assert_ne!(checksum, 0);
/// # Ok::<(), embedded_raster::band::BandError>(())
/// ```
#[derive(Debug)]
pub struct DepthBands<'a, C> {
    colors: ColorBands<'a, C>,
    depth: &'a mut [u16],
}

impl<'a, C: GouraudColor> DepthBands<'a, C> {
    /// `colors` with the z-buffer `depth` (exactly one band buffer, [`BandLayout::buffer_len`]
    /// entries).
    pub fn new(colors: ColorBands<'a, C>, depth: &'a mut [u16]) -> Result<Self, BandError> {
        check_buffer(&colors.layout, depth.len(), true)?;
        Ok(DepthBands { colors, depth })
    }

    /// The layout.
    pub fn layout(&self) -> &BandLayout {
        &self.colors.layout
    }

    /// Draws the frame: for each band, top to bottom, `draw` and then `output` (the colours).
    /// `draw` returns nothing, or a `Result` whose error is a [`BandError`] (a bin's draw:
    /// `bin.draw(band)`). Stops at the first error, the output's ([`RenderError::Display`]) or
    /// `draw`'s ([`RenderError::Band`]; that band is not sent).
    pub fn render<O: BandOutput<C>, R: BandDrawn>(
        &mut self,
        output: &mut O,
        mut draw: impl FnMut(&mut DepthBand<'_, C>) -> R,
    ) -> Result<(), RenderError<O::Error>> {
        let depth = &mut *self.depth;
        self.colors.each(output, |pixels, placement| {
            let mut band = DepthBand::placed(pixels, depth, placement)?;
            draw(&mut band).into_band_result()?;
            Ok(band.pixels().len())
        })
    }
}
