//! The targets a band is drawn into: [`ColorBand`] (2D) and [`DepthBand`] (3D, with its
//! z-buffer), each a caller's buffer of the band's rows seen in frame coordinates.

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;

use super::{check_buffer, BandError, BandLayout};
use crate::color::GouraudColor;
use crate::draw::{
    draw_shape_rows, skip_colors, AntiAliased, CoverageMask, FilledPolygon, GouraudTriangle, Line,
    Polyline, SliceFramebuffer, SolidTriangle, Stroked, TexturedTriangle, Translucent,
};
use crate::fixed_point::ToCoord;
use crate::paint::Paint;
use crate::raster::walk::Band;
use crate::rect;
use crate::texture::TexelSource;
use crate::three_d::{DepthTarget, MeshTarget, MeshTargetParts, Pipeline, TargetClip};

/// Which band of which layout a band target holds: its rows in the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Placement {
    pub(crate) layout: BandLayout,
    pub(crate) index: u32,
    /// The band's rows, `first ..= last` (not empty).
    pub(crate) rows: Band,
}

impl Placement {
    /// Band `index` of `layout`, if there is one.
    pub(crate) fn new(layout: &BandLayout, index: u32) -> Result<Self, BandError> {
        let area = layout.band(index).ok_or(BandError::NoSuchBand {
            index,
            count: layout.count(),
        })?;
        let first = area.top_left.y;
        // At most `rows` rows (below 2³¹) from a row below 2³¹: no overflow.
        let last = first + area.size.height as i32 - 1;
        Ok(Placement {
            layout: *layout,
            index,
            rows: Band { first, last },
        })
    }

    /// Rows in the band.
    pub(crate) fn height(&self) -> u32 {
        (self.rows.last - self.rows.first) as u32 + 1
    }

    /// The band's rectangle in the frame.
    pub(crate) fn rect(&self) -> Rectangle {
        let width = self.layout.size().width;
        Rectangle::new(
            Point::new(0, self.rows.first),
            Size::new(width, self.height()),
        )
    }
}

/// What draws into a band exactly the pixels it gives those rows of the whole frame: the
/// triangles of this crate (and references to them), through [`ColorBand::draw`] and
/// [`ColorBand::draw_all`].
pub trait BandDrawable<C: PixelColor> {
    /// Draws the band's rows of `self` into `band`: exactly the pixels that drawing `self` into
    /// a [`SliceFramebuffer`] of the frame's size with `draw_into` gives those rows.
    fn draw_band(&self, band: &mut ColorBand<'_, C>);

    /// The first and last frame rows `self` may cover (a superset of those it covers), or `None`
    /// if it covers none: what a bin records.
    fn rows(&self) -> Option<(i32, i32)>;
}

/// The pixel rows whose centres lie between the vertices' heights.
fn rows_of(y: [crate::Coord; 3]) -> Option<(i32, i32)> {
    use crate::raster::edge::{first_centre_from, last_centre_to};
    let y = y.map(|y| y.to_bits());
    let (top, bottom) = (y[0].min(y[1]).min(y[2]), y[0].max(y[1]).max(y[2]));
    let (first, last) = (first_centre_from(top), last_centre_to(bottom));
    (first <= last).then_some((first, last))
}

impl<C: GouraudColor> BandDrawable<C> for GouraudTriangle<C> {
    fn draw_band(&self, band: &mut ColorBand<'_, C>) {
        let clip = band.frame();
        self.draw_rows(&mut band.pixels, &clip, &band.placement.rows);
    }

    fn rows(&self) -> Option<(i32, i32)> {
        rows_of(self.vertices.map(|v| v.y))
    }
}

impl<C: PixelColor> BandDrawable<C> for SolidTriangle<C> {
    fn draw_band(&self, band: &mut ColorBand<'_, C>) {
        let clip = band.frame();
        self.draw_rows(&mut band.pixels, &clip, &band.placement.rows);
    }

    fn rows(&self) -> Option<(i32, i32)> {
        rows_of(self.points.map(|p| p.1))
    }
}

impl<S, C> BandDrawable<C> for TexturedTriangle<'_, S, C>
where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    fn draw_band(&self, band: &mut ColorBand<'_, C>) {
        let clip = band.frame();
        self.draw_rows(&mut band.pixels, &clip, &band.placement.rows);
    }

    fn rows(&self) -> Option<(i32, i32)> {
        rows_of(self.vertices.map(|v| v.y))
    }
}

impl<C: GouraudColor> BandDrawable<C> for AntiAliased<SolidTriangle<C>> {
    fn draw_band(&self, band: &mut ColorBand<'_, C>) {
        let rect = band.rect();
        self.draw_rows(&mut band.pixels, &rect, rect.top_left.y);
    }

    fn rows(&self) -> Option<(i32, i32)> {
        // Every row whose squares meet the band between the lowest and highest vertex.
        let y = self.shape().points.map(|p| p.1.to_bits());
        let (top, bottom) = (y[0].min(y[1]).min(y[2]), y[0].max(y[1]).max(y[2]));
        (top < bottom).then(|| (top >> 8, (bottom - 1) >> 8))
    }
}

impl<C: GouraudColor> BandDrawable<C> for Translucent<SolidTriangle<C>> {
    fn draw_band(&self, band: &mut ColorBand<'_, C>) {
        let clip = band.frame();
        self.draw_rows(&mut band.pixels, &clip, &band.placement.rows);
    }

    fn rows(&self) -> Option<(i32, i32)> {
        rows_of(self.shape().points.map(|p| p.1))
    }
}

impl<C: GouraudColor> BandDrawable<C> for Translucent<GouraudTriangle<C>> {
    fn draw_band(&self, band: &mut ColorBand<'_, C>) {
        let clip = band.frame();
        self.draw_rows(&mut band.pixels, &clip, &band.placement.rows);
    }

    fn rows(&self) -> Option<(i32, i32)> {
        rows_of(self.shape().vertices.map(|v| v.y))
    }
}

impl<C: PixelColor, P: Paint<Color = C>, const N: usize> BandDrawable<C>
    for FilledPolygon<'_, N, P>
{
    fn draw_band(&self, band: &mut ColorBand<'_, C>) {
        let rect = band.rect();
        draw_shape_rows(self, &mut band.pixels, &rect);
    }

    fn rows(&self) -> Option<(i32, i32)> {
        FilledPolygon::rows(self)
    }
}

impl<C: PixelColor, P: Paint<Color = C>> BandDrawable<C> for Line<P> {
    fn draw_band(&self, band: &mut ColorBand<'_, C>) {
        let rect = band.rect();
        draw_shape_rows(self, &mut band.pixels, &rect);
    }

    fn rows(&self) -> Option<(i32, i32)> {
        Line::rows(self)
    }
}

impl<C: PixelColor, T: ToCoord + Copy, P: Paint<Color = C>> BandDrawable<C> for Polyline<'_, T, P> {
    fn draw_band(&self, band: &mut ColorBand<'_, C>) {
        let rect = band.rect();
        draw_shape_rows(self, &mut band.pixels, &rect);
    }

    fn rows(&self) -> Option<(i32, i32)> {
        Polyline::rows(self)
    }
}

impl<C: PixelColor, T: ToCoord + Copy, P: Paint<Color = C>> BandDrawable<C> for Stroked<'_, T, P> {
    fn draw_band(&self, band: &mut ColorBand<'_, C>) {
        let rect = band.rect();
        draw_shape_rows(self, &mut band.pixels, &rect);
    }

    fn rows(&self) -> Option<(i32, i32)> {
        Stroked::rows(self)
    }
}

impl<C: PixelColor, T: BandDrawable<C> + ?Sized> BandDrawable<C> for &T {
    fn draw_band(&self, band: &mut ColorBand<'_, C>) {
        (**self).draw_band(band);
    }

    fn rows(&self) -> Option<(i32, i32)> {
        (**self).rows()
    }
}

/// A 2D triangle of a mixed list: Gouraud-shaded or solid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Triangle<C> {
    /// A [`GouraudTriangle`].
    Gouraud(GouraudTriangle<C>),
    /// A [`SolidTriangle`].
    Solid(SolidTriangle<C>),
}

impl<C> From<GouraudTriangle<C>> for Triangle<C> {
    fn from(t: GouraudTriangle<C>) -> Self {
        Triangle::Gouraud(t)
    }
}

impl<C> From<SolidTriangle<C>> for Triangle<C> {
    fn from(t: SolidTriangle<C>) -> Self {
        Triangle::Solid(t)
    }
}

impl<C: GouraudColor> BandDrawable<C> for Triangle<C> {
    fn draw_band(&self, band: &mut ColorBand<'_, C>) {
        match self {
            Triangle::Gouraud(t) => t.draw_band(band),
            Triangle::Solid(t) => t.draw_band(band),
        }
    }

    fn rows(&self) -> Option<(i32, i32)> {
        match self {
            Triangle::Gouraud(t) => BandDrawable::<C>::rows(t),
            Triangle::Solid(t) => BandDrawable::<C>::rows(t),
        }
    }
}

/// One band of a frame for 2D drawing: a caller's buffer of the band's rows (row-major, the
/// frame's width), drawn in frame coordinates.
///
/// [`draw`](Self::draw) gives exactly the pixels the frame drawn at once has in these rows
/// (`draw_into` a [`SliceFramebuffer`] of the frame's size). It is also an embedded-graphics
/// [`DrawTarget`] whose bounding box is the band's rectangle in the frame, for other drawables
/// (text, lines): any pixel outside the band is ignored. (This crate's triangles drawn through
/// `Drawable::draw` clip to that box and start their colour steps at the band's first row, so
/// they may differ from the whole frame's by an LSB; [`draw`](Self::draw) does not.)
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::band::{BandLayout, ColorBand};
/// use embedded_raster::{Coord, SliceFramebuffer, SolidTriangle};
///
/// let c = |x: i32, y: i32| (Coord::from_num(x), Coord::from_num(y));
/// let triangle = SolidTriangle::new([c(2, 1), c(30, 6), c(9, 22)], Rgb565::RED);
/// let layout = BandLayout::new(Size::new(32, 24), 8)?;
/// let mut whole = [Rgb565::BLACK; 32 * 24];
/// triangle.draw_into(&mut SliceFramebuffer::new(&mut whole, 32, 24).unwrap());
///
/// let mut rows = [Rgb565::BLACK; 32 * 8];
/// for index in 0..layout.count() {
///     let mut band = ColorBand::new(&mut rows, &layout, index)?;
///     band.clear(Rgb565::BLACK);
///     band.draw(&triangle);
///     let start = band.rect().top_left.y as usize * 32;
///     assert_eq!(band.pixels(), &whole[start..start + band.pixels().len()]);
/// }
/// # Ok::<(), embedded_raster::band::BandError>(())
/// ```
#[derive(Debug)]
pub struct ColorBand<'a, C> {
    pixels: SliceFramebuffer<'a, C>,
    placement: Placement,
}

impl<'a, C: PixelColor> ColorBand<'a, C> {
    /// Band `index` of `layout` in `pixels`, which must hold exactly one band buffer
    /// ([`BandLayout::buffer_len`] pixels; the last band may use fewer rows of it).
    pub fn new(pixels: &'a mut [C], layout: &BandLayout, index: u32) -> Result<Self, BandError> {
        let placement = Placement::new(layout, index)?;
        ColorBand::placed(pixels, placement)
    }

    /// The band `placement` in `pixels` (exactly one band buffer).
    pub(crate) fn placed(pixels: &'a mut [C], placement: Placement) -> Result<Self, BandError> {
        let layout = &placement.layout;
        check_buffer(layout, pixels.len(), false)?;
        let width = layout.size().width;
        let pixels = SliceFramebuffer::new(pixels, width, placement.height())
            .map_err(|_| BandError::FrameTooLarge)?;
        Ok(ColorBand { pixels, placement })
    }

    /// The band's rectangle in the frame.
    pub fn rect(&self) -> Rectangle {
        self.placement.rect()
    }

    /// The band's index in its layout, from 0 at the top.
    pub fn index(&self) -> u32 {
        self.placement.index
    }

    /// The layout the band belongs to.
    pub fn layout(&self) -> &BandLayout {
        &self.placement.layout
    }

    /// The band's pixels, row-major: its rectangle's width × height.
    pub fn pixels(&self) -> &[C] {
        self.pixels.pixels()
    }

    /// Sets every pixel of the band to `color`.
    pub fn clear(&mut self, color: C) {
        crate::color::fill_all(self.pixels.pixels_mut(), color);
    }

    /// Blends `color` with the summed coverage of `mask` into the band (see [`CoverageMask`];
    /// its area is usually the band's [`rect`](Self::rect)) and clears the mask: the pixels
    /// [`CoverageMask::fill_into`] gives these rows of the frame.
    pub fn fill_mask(&mut self, mask: &mut CoverageMask<'_>, color: C)
    where
        C: GouraudColor,
    {
        let top = self.rect().top_left.y;
        mask.fill_rows(color, 255, &mut self.pixels, top);
    }

    /// [`fill_mask`](Self::fill_mask) at `opacity`: the band's rows of
    /// [`CoverageMask::fill_translucent_into`].
    pub fn fill_mask_translucent(&mut self, mask: &mut CoverageMask<'_>, color: C, opacity: u8)
    where
        C: GouraudColor,
    {
        let top = self.rect().top_left.y;
        mask.fill_rows(color, opacity, &mut self.pixels, top);
    }

    /// Draws the band's rows of `item`: the pixels the whole frame has there.
    pub fn draw(&mut self, item: &impl BandDrawable<C>) {
        item.draw_band(self);
    }

    /// Draws the band's rows of every item in order (painter's order: later items over earlier
    /// ones), skipping those outside the band.
    pub fn draw_all<T: BandDrawable<C>>(&mut self, items: &[T]) {
        let band = self.placement.rows;
        for item in items {
            if item
                .rows()
                .is_some_and(|(top, bottom)| band.meets(top, bottom))
            {
                item.draw_band(self);
            }
        }
    }

    /// The frame's rectangle: the clip the whole frame's draws have.
    fn frame(&self) -> Rectangle {
        Rectangle::new(Point::zero(), self.placement.layout.size())
    }
}

impl<C: PixelColor> Dimensions for ColorBand<'_, C> {
    fn bounding_box(&self) -> Rectangle {
        self.rect()
    }
}

impl<C: PixelColor> DrawTarget for ColorBand<'_, C> {
    type Color = C;
    type Error = core::convert::Infallible;

    /// Writes each pixel inside the band; the others are ignored.
    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        let first = self.placement.rows.first;
        let local = pixels
            .into_iter()
            .filter_map(|Pixel(p, c)| Some(Pixel(Point::new(p.x, p.y.checked_sub(first)?), c)));
        self.pixels.draw_iter(local)
    }

    /// Writes the colours of the pixels of `area` inside the band, for any `area`, taking the
    /// colours in embedded-graphics' order (see [`SliceFramebuffer`]).
    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = C>,
    {
        let visible = rect::intersection(area, &self.rect());
        if visible.is_zero_sized() {
            return Ok(());
        }
        // The colours of the rows above the band, then the band's rows of `area` in the
        // buffer's rows (inside the band: no overflow).
        let above = (i64::from(visible.top_left.y) - i64::from(area.top_left.y)) as u64;
        let mut colors = colors.into_iter();
        if !skip_colors(&mut colors, above * u64::from(area.size.width)) {
            return Ok(());
        }
        let rows = Rectangle::new(
            Point::new(
                area.top_left.x,
                visible.top_left.y - self.placement.rows.first,
            ),
            Size::new(area.size.width, visible.size.height),
        );
        self.pixels.fill_contiguous(&rows, colors)
    }

    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Self::Error> {
        let visible = rect::intersection(area, &self.rect());
        let local = Rectangle::new(
            visible.top_left - Point::new(0, self.placement.rows.first),
            visible.size,
        );
        if visible.is_zero_sized() {
            return Ok(());
        }
        self.pixels.fill_solid(&local, color)
    }

    fn clear(&mut self, color: C) -> Result<(), Self::Error> {
        ColorBand::clear(self, color);
        Ok(())
    }
}

/// One band of a frame for the 3D pipeline: caller's colour and depth buffers of the band's rows
/// (row-major, the frame's width), drawn in frame coordinates.
///
/// It is a target of the pipeline ([`MeshTarget`]), as a [`DepthTarget`] of the whole frame is:
/// `pipeline.draw_mesh(mesh, material, &mut band)` (and `draw_mesh_with`,
/// `draw_textured_mesh`, `draw_textured_mesh_with`) runs the pipeline
/// for the band: every vertex and face again (faces outside the band's rows are rejected before
/// they are projected), the fills only for the band's rows — exactly the pixels and depths the
/// whole frame has there; the counts are the band's. With a [`MeshBin`](super::MeshBin), each
/// face is transformed and culled once per frame instead.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
/// use embedded_raster::band::{BandLayout, DepthBand};
/// use embedded_raster::three_d::meshes::icosphere::ICOSPHERE;
/// use embedded_raster::three_d::{Angle, Light, Mat4, Material, Pipeline, Scalar, Shading, Vec3};
///
/// let layout = BandLayout::new(Size::new(64, 48), 16)?;
/// let projection = Mat4::perspective(Angle::from_degrees(60), Scalar::from_num(4) / 3,
///     Scalar::from_num(0.5), Scalar::from_num(20)).unwrap();
/// let view = Mat4::translation(Vec3::from_bits(0, 0, -3 << 16));
/// let viewport = Rectangle::new(Point::zero(), layout.size());
/// let light = Light::new(Vec3::new(0, 0, 1), 0.2);
/// let pipeline = Pipeline::new(Mat4::rotation_y(Angle::from_degrees(30)), projection * view, viewport, light);
/// let material = Material::new(Rgb565::WHITE, Shading::Gouraud);
///
/// let (mut colors, mut depth) = ([Rgb565::BLACK; 64 * 16], [0u16; 64 * 16]);
/// let mut lit = 0;
/// for index in 0..layout.count() {
///     let mut band = DepthBand::new(&mut colors, &mut depth, &layout, index)?;
///     band.clear(Rgb565::BLACK);
///     pipeline.draw_mesh(&ICOSPHERE, &material, &mut band);
///     lit += band.pixels().iter().filter(|&&c| c != Rgb565::BLACK).count();
/// }
/// assert!(lit > 500);
/// # Ok::<(), embedded_raster::band::BandError>(())
/// ```
#[derive(Debug)]
pub struct DepthBand<'a, C> {
    target: DepthTarget<'a, C>,
    placement: Placement,
}

impl<'a, C: GouraudColor> DepthBand<'a, C> {
    /// Band `index` of `layout` in `color` and `depth`, which must each hold exactly one band
    /// buffer ([`BandLayout::buffer_len`] entries; the last band may use fewer rows of them).
    /// The buffers are not cleared: call [`clear`](Self::clear) first.
    pub fn new(
        color: &'a mut [C],
        depth: &'a mut [u16],
        layout: &BandLayout,
        index: u32,
    ) -> Result<Self, BandError> {
        let placement = Placement::new(layout, index)?;
        DepthBand::placed(color, depth, placement)
    }

    /// The band `placement` in `color` and `depth` (exactly one band buffer each).
    pub(crate) fn placed(
        color: &'a mut [C],
        depth: &'a mut [u16],
        placement: Placement,
    ) -> Result<Self, BandError> {
        let layout = &placement.layout;
        check_buffer(layout, color.len(), false)?;
        check_buffer(layout, depth.len(), true)?;
        let width = layout.size().width;
        let target = DepthTarget::new(color, depth, width, placement.height())
            .map_err(|_| BandError::FrameTooLarge)?;
        Ok(DepthBand { target, placement })
    }

    /// The band's rectangle in the frame.
    pub fn rect(&self) -> Rectangle {
        self.placement.rect()
    }

    /// The band's index in its layout, from 0 at the top.
    pub fn index(&self) -> u32 {
        self.placement.index
    }

    /// The layout the band belongs to.
    pub fn layout(&self) -> &BandLayout {
        &self.placement.layout
    }

    /// The band's colours, row-major: its rectangle's width × height.
    pub fn pixels(&self) -> &[C] {
        self.target.framebuffer().pixels()
    }

    /// The band's depths, row-major like [`pixels`](Self::pixels).
    pub fn depth(&self) -> &[u16] {
        self.target.depth()
    }

    /// Fills the band's colours with `color` and resets its depths.
    pub fn clear(&mut self, color: C) {
        self.target.clear(color);
    }

    /// The band's colour buffer for 2D drawing (overlays: depth is neither tested nor written).
    pub fn colors(&mut self) -> ColorBand<'_, C> {
        ColorBand {
            pixels: SliceFramebuffer::new(
                self.target.framebuffer_mut().pixels_mut(),
                self.placement.layout.size().width,
                self.placement.height(),
            )
            // The target's own buffer, of its size: never empty.
            .unwrap_or_else(|_| SliceFramebuffer::empty()),
            placement: self.placement,
        }
    }

    /// The clip of `pipeline`'s draws into this band: its viewport inside the frame, the band's
    /// rows.
    pub(crate) fn clip(&self, pipeline: &Pipeline) -> TargetClip<Band> {
        MeshTargetParts::clip(self, &pipeline.viewport)
    }

    /// The band's depth target (its own rows, from 0) and placement.
    pub(crate) fn parts(&mut self) -> (&mut DepthTarget<'a, C>, &Placement) {
        (&mut self.target, &self.placement)
    }
}

/// The band as the target of [`Pipeline::draw_mesh`] and its kin (`_with`, `_translucent`,
/// `draw_textured_mesh`, `draw_textured_mesh_with`): the band's rows of the frame, exactly the
/// pixels and depths the whole frame has there. The counts are the band's: faces outside its
/// rows are `rejected`.
impl<C: GouraudColor> MeshTarget<C> for DepthBand<'_, C> {}

#[allow(private_bounds, private_interfaces)]
impl<C: GouraudColor> MeshTargetParts<C> for DepthBand<'_, C> {
    type Rows = Band;

    #[inline(always)]
    fn clip(&self, viewport: &Rectangle) -> TargetClip<Band> {
        let frame = Rectangle::new(Point::zero(), self.placement.layout.size());
        TargetClip::of_frame(viewport, &frame, self.placement.rows)
    }

    #[inline(always)]
    fn with_depth<R>(&mut self, draw: impl FnOnce(&mut DepthTarget<'_, C>) -> R) -> R {
        draw(&mut self.target)
    }
}
