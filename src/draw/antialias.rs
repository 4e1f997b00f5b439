//! Anti-aliased triangles: each pixel the triangle covers in part blended with the area it
//! covers.
//!
//! [`SolidTriangle::anti_aliased`] makes an [`AntiAliased`] triangle. Its wholly covered pixels
//! are the plain fill; every pixel it covers in part is its colour blended over the pixel
//! ([`GouraudColor::blend`]) at the alpha of the exact area of the pixel square inside it
//! (rounded to 8 bits; the area from the exact edge functions, within 2⁻⁹ of a pixel: see
//! `raster::coverage`). Like a [`Translucent`] triangle it needs the pixels it blends over:
//! [`AntiAliased::draw_into`] a [`SliceFramebuffer`] and bands read them,
//! [`AntiAliased::draw_reading`] reads any [`GetPixel`] target, and [`AntiAliased::over`] a
//! known background colour draws into any `DrawTarget`; all give the same pixels.

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::image::GetPixel;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;

use super::framebuffer::SliceFramebuffer;
use super::translucent::OnBackground;
use super::triangle::SolidTriangle;
use crate::color::fill_row;
use crate::color::{BlendSource, GouraudColor};
use crate::raster::coverage::{cover, CoverageSink, FULL};

#[cfg(doc)]
use super::translucent::Translucent;

/// The 8-bit alpha of a coverage (16 fractional bits) at `opacity`, rounded: the one rule from
/// coverage to alpha (a `CoverageMask`'s cells too).
#[inline(always)]
pub(super) fn alpha_of(coverage: u32, opacity: u8) -> u8 {
    ((coverage.min(FULL) * u32::from(opacity) + (1 << 15)) >> 16) as u8
}

/// A triangle with anti-aliased edges ([`SolidTriangle::anti_aliased`]): pixels it covers in part
/// blended with the area it covers.
///
/// Each triangle is blended on its own: where two anti-aliased triangles share an edge, the
/// pixels along it are covered `a + b·(1 − a)` rather than whole (a seam). Triangles of a mesh
/// or fan mark the edges they share ([`with_shared_edges`](Self::with_shared_edges)): those are
/// drawn by the exact aliased rule, seam-free, and only the outline is anti-aliased.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::{SliceFramebuffer, SolidTriangle};
///
/// let mut pixels = [Rgb565::BLACK; 16 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
/// // A half-plane through the pixels' diagonals: (0,0)–(16,16) and beyond.
/// let triangle = SolidTriangle::new([(0.0, 0.0), (16.0, 16.0), (0.0, 16.0)], Rgb565::WHITE);
/// triangle.anti_aliased().draw_into(&mut fb);
/// assert_eq!(fb.get(0, 5), Some(Rgb565::WHITE)); // wholly inside
/// assert_eq!(fb.get(5, 5), Some(Rgb565::new(16, 32, 16))); // half covered
/// assert_eq!(fb.get(6, 5), Some(Rgb565::BLACK)); // outside
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AntiAliased<T> {
    shape: T,
    /// Which edges (edge `i` from vertex `i` to vertex `i + 1`) are anti-aliased.
    edges: [bool; 3],
    /// The opacity of a wholly covered pixel (255: opaque).
    opacity: u8,
}

impl<T> AntiAliased<T> {
    /// The aliased triangle.
    pub fn shape(&self) -> &T {
        &self.shape
    }

    /// The triangle with the edges `shared[i]` (edge `i` from vertex `i` to vertex `i + 1`)
    /// drawn without anti-aliasing, by the exact top-left rule of the aliased triangles: where a
    /// neighbour of a mesh or a fan drawn the same way shares such an edge, every pixel along it
    /// is drawn by exactly one of the two, whole — no seam. Only the outline's edges are then
    /// blended.
    ///
    /// ```
    /// use embedded_graphics::{pixelcolor::Gray8, prelude::*};
    /// use embedded_raster::{SliceFramebuffer, SolidTriangle};
    ///
    /// let mut pixels = [Gray8::BLACK; 16 * 16];
    /// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
    /// // A square of two triangles sharing its diagonal (edge 2 of the first, 0 of the second).
    /// let (a, b, c, d) = ((1.3, 1.3), (14.6, 1.3), (14.6, 14.6), (1.3, 14.6));
    /// let first = SolidTriangle::new([a, b, c], Gray8::WHITE).anti_aliased();
    /// let second = SolidTriangle::new([a, c, d], Gray8::WHITE).anti_aliased();
    /// first.with_shared_edges([false, false, true]).draw_into(&mut fb);
    /// second.with_shared_edges([true, false, false]).draw_into(&mut fb);
    /// // Along the diagonal, every pixel is whole.
    /// assert!((2..14).all(|i| fb.get(i, i) == Some(Gray8::WHITE)));
    /// ```
    pub fn with_shared_edges(self, shared: [bool; 3]) -> Self {
        AntiAliased {
            edges: shared.map(|s| !s),
            ..self
        }
    }

    /// The triangle at opacity `opacity` (0 transparent, 255 opaque, the default): a pixel is
    /// blended at the alpha `coverage × opacity`, rounded (wholly covered pixels as
    /// [`Translucent`]'s).
    pub fn with_opacity(self, opacity: u8) -> Self {
        AntiAliased { opacity, ..self }
    }

    /// This triangle over a background of one colour: a [`Drawable`] for any `DrawTarget`, the
    /// pixels [`draw_into`](AntiAliased::draw_into) gives over a framebuffer of that colour.
    pub fn over<C>(self, background: C) -> OnBackground<Self, C> {
        OnBackground::new(self, background)
    }
}

impl<C: GouraudColor> SolidTriangle<C> {
    /// This triangle with anti-aliased edges ([`AntiAliased`]).
    pub fn anti_aliased(self) -> AntiAliased<Self> {
        AntiAliased {
            shape: self,
            edges: [true; 3],
            opacity: 255,
        }
    }
}

/// Anti-aliased coverage into a framebuffer (or a band's rows, `top` its first frame row).
struct IntoSlice<'f, 'a, C> {
    framebuffer: &'f mut SliceFramebuffer<'a, C>,
    color: C,
    opacity: u8,
    /// The colour at the opacity, for wholly covered runs.
    source: BlendSource,
    top: i32,
}

impl<C: GouraudColor> CoverageSink for IntoSlice<'_, '_, C> {
    #[inline]
    fn full(&mut self, y: i32, x0: i32, x1: i32) {
        if let Some(row) = self.framebuffer.clipped_span_mut(y - self.top, x0, x1) {
            if self.opacity == 255 {
                fill_row(row, self.color);
            } else {
                C::blend_solid(row, &self.source);
            }
        }
    }

    #[inline]
    fn partial(&mut self, x: i32, y: i32, coverage: u32) {
        if let Some([px]) = self.framebuffer.clipped_span_mut(y - self.top, x, x + 1) {
            *px = self.color.blend(*px, alpha_of(coverage, self.opacity));
        }
    }
}

/// Anti-aliased coverage over a background colour, into any target.
struct Over<'t, D: DrawTarget> {
    target: &'t mut D,
    color: D::Color,
    /// The colour of a wholly covered pixel over the background.
    whole: D::Color,
    opacity: u8,
    background: D::Color,
    result: Result<(), D::Error>,
}

impl<C: GouraudColor, D: DrawTarget<Color = C>> CoverageSink for Over<'_, D> {
    fn full(&mut self, y: i32, x0: i32, x1: i32) {
        if self.result.is_ok() {
            let area = Rectangle::new(Point::new(x0, y), Size::new(x1.abs_diff(x0), 1));
            self.result = self.target.fill_solid(&area, self.whole);
        }
    }

    fn partial(&mut self, x: i32, y: i32, coverage: u32) {
        if self.result.is_ok() {
            let color = self
                .color
                .blend(self.background, alpha_of(coverage, self.opacity));
            self.result = self
                .target
                .draw_iter(core::iter::once(Pixel(Point::new(x, y), color)));
        }
    }
}

/// Anti-aliased coverage into a target it reads through [`GetPixel`].
struct Reading<'t, D: DrawTarget> {
    target: &'t mut D,
    color: D::Color,
    opacity: u8,
    result: Result<(), D::Error>,
}

impl<C, D> CoverageSink for Reading<'_, D>
where
    C: GouraudColor,
    D: DrawTarget<Color = C> + GetPixel<Color = C>,
{
    fn full(&mut self, y: i32, x0: i32, x1: i32) {
        if self.opacity < 255 {
            for x in x0..x1 {
                self.partial(x, y, FULL);
            }
        } else if self.result.is_ok() {
            let area = Rectangle::new(Point::new(x0, y), Size::new(x1.abs_diff(x0), 1));
            self.result = self.target.fill_solid(&area, self.color);
        }
    }

    fn partial(&mut self, x: i32, y: i32, coverage: u32) {
        let p = Point::new(x, y);
        if let (true, Some(under)) = (self.result.is_ok(), self.target.pixel(p)) {
            let color = self.color.blend(under, alpha_of(coverage, self.opacity));
            self.result = self.target.draw_iter(core::iter::once(Pixel(p, color)));
        }
    }
}

impl<C: GouraudColor> AntiAliased<SolidTriangle<C>> {
    /// Draws the triangle into a [`SliceFramebuffer`], blending the pixels it covers in part
    /// over the framebuffer's: the pixels of every other path.
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, C>) {
        let clip = framebuffer.bounding_box();
        self.draw_rows(framebuffer, &clip, 0);
    }

    /// Draws the triangle into `target`, reading the pixels it blends over through
    /// [`GetPixel`] (a pixel it cannot read is left alone): the pixels
    /// [`draw_into`](Self::draw_into) gives.
    pub fn draw_reading<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C> + GetPixel<Color = C>,
    {
        let clip = target.bounding_box();
        let mut sink = Reading {
            target,
            color: self.shape.color,
            opacity: self.opacity,
            result: Ok(()),
        };
        cover(self.shape.points, self.edges, &clip, &mut sink);
        sink.result
    }

    /// Draws the frame rows `clip` covers into `framebuffer`, whose first row is frame row
    /// `top` (a band's buffer): the pixels [`draw_into`](Self::draw_into) gives those rows.
    pub(crate) fn draw_rows(
        &self,
        framebuffer: &mut SliceFramebuffer<'_, C>,
        clip: &Rectangle,
        top: i32,
    ) {
        let mut sink = IntoSlice {
            framebuffer,
            color: self.shape.color,
            opacity: self.opacity,
            source: BlendSource::new(self.shape.color, self.opacity),
            top,
        };
        cover(self.shape.points, self.edges, clip, &mut sink);
    }
}

impl<C: GouraudColor> Drawable for OnBackground<AntiAliased<SolidTriangle<C>>, C> {
    type Color = C;
    type Output = ();

    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        let clip = target.bounding_box();
        let (shape, background) = self.parts();
        let color = shape.shape.color;
        let mut sink = Over {
            target,
            color,
            whole: color.blend(*background, shape.opacity),
            opacity: shape.opacity,
            background: *background,
            result: Ok(()),
        };
        cover(shape.shape.points, shape.edges, &clip, &mut sink);
        sink.result
    }
}
