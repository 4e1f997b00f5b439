//! embedded-graphics primitives: Gouraud-shaded and solid triangles.
//!
//! Both implement [`Drawable`] for any [`DrawTarget`] of their colour. They clip to the target's
//! `bounding_box()` before traversal, so no pixel outside it is ever emitted, and they emit whole
//! spans (`fill_contiguous`, `fill_solid`), which [`SliceFramebuffer`]
//! turns into plain slice writes.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use embedded_raster::{Coord, GouraudTriangle, SliceFramebuffer, Vertex};
//!
//! let mut pixels = [Rgb565::BLACK; 64 * 48];
//! let mut display = SliceFramebuffer::new(&mut pixels, 64, 48).unwrap();
//! let v = |x: f32, y: f32, c| Vertex::new(Coord::from_num(x), Coord::from_num(y), c);
//! GouraudTriangle::new([
//!     v(2.0, 2.0, Rgb565::RED),
//!     v(60.5, 10.25, Rgb565::GREEN),
//!     v(20.0, 45.75, Rgb565::BLUE),
//! ])
//! .draw(&mut display)?;
//! assert_eq!(display.get(3, 3).map(|c| c.r()), Some(30));
//! # Ok::<(), core::convert::Infallible>(())
//! ```

use core::marker::PhantomData;

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::framebuffer::SliceFramebuffer;
use crate::arch::LANES;
use crate::color::fill_row;
use crate::color::{restart_value, GouraudColor, SpanSteps};
use crate::fixed_point::{pixel_centre, pixel_corner, Coord, ToCoord};
use crate::raster::band::RowWindow;
use crate::raster::compact::{CompactTriangle, TooLarge};
use crate::raster::edge::TriangleSetup;
use crate::raster::plane::{Attributes, ExactPlanes, GeneralPlanes, Planes, MAX_CHUNK};
use crate::raster::walk::Span;
use crate::raster::Spans;
use crate::raster::{shade, shade_compact, SpanShader};

/// A triangle vertex: sub-pixel position and colour.
///
/// Positions are in pixels, `y` down: pixel `(i, j)` is the square `[i, i+1) × [j, j+1)`, its
/// centre at `(i + 0.5, j + 0.5)`. Give them as floats or [`Coord`]s ([`Vertex::new`]), or as
/// integer pixel positions with an explicit placement ([`Vertex::at_pixel_centre`], the
/// embedded-graphics placement, or [`Vertex::at_pixel_corner`]).
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::{Coord, Vertex};
///
/// let a = Vertex::new(10.5, 20.5, Rgb565::RED);
/// assert_eq!(a, Vertex::at_pixel_centre(Point::new(10, 20), Rgb565::RED));
/// assert_eq!(Vertex::at_pixel_corner(Point::new(10, 20), Rgb565::RED).x, Coord::from_num(10));
/// // Fixed point in, fixed point out: no rounding.
/// let b = Vertex::new(Coord::from_bits(2561), Coord::from_num(3), Rgb565::BLUE);
/// assert_eq!(b.position(), (Coord::from_bits(2561), Coord::from_num(3)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Vertex<C> {
    /// Horizontal position (pixel centres are at `i + 0.5`).
    pub x: Coord,
    /// Vertical position, growing downward.
    pub y: Coord,
    /// Colour at this vertex.
    pub color: C,
}

impl<C> Vertex<C> {
    /// A vertex at `(x, y)` with colour `color`; `x` and `y` are `f32`, `f64` or [`Coord`]
    /// ([`ToCoord`]: floats are rounded to the nearest 1/256 pixel and saturated). For a `const`
    /// vertex, write the struct with [`Coord::from_bits`] fields.
    #[inline(always)]
    pub fn new(x: impl ToCoord, y: impl ToCoord, color: C) -> Self {
        Vertex {
            x: x.to_coord(),
            y: y.to_coord(),
            color,
        }
    }

    /// A vertex at the centre of pixel `p` (`p + 0.5`): the placement under which triangles cover
    /// the pixels of an embedded-graphics `Triangle` of the same points, but for its edges (see
    /// [`SolidTriangle::at_pixel_centres`]).
    pub fn at_pixel_centre(p: Point, color: C) -> Self {
        Vertex {
            x: pixel_centre(p.x),
            y: pixel_centre(p.y),
            color,
        }
    }

    /// A vertex at the top-left corner of pixel `p` (the point `p` itself): meshes of pixel
    /// squares, such as a rectangle split into two triangles, cover whole pixels.
    pub fn at_pixel_corner(p: Point, color: C) -> Self {
        Vertex {
            x: pixel_corner(p.x),
            y: pixel_corner(p.y),
            color,
        }
    }

    /// The position as a coordinate pair.
    pub fn position(&self) -> (Coord, Coord) {
        (self.x, self.y)
    }
}

/// A triangle whose vertex colours are interpolated across it (Gouraud shading).
///
/// Each pixel whose centre is inside (top-left rule on edges) gets the vertex colours
/// interpolated at its centre, within 1 LSB, in the colour format's own channel depth.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb888, prelude::*};
/// use embedded_raster::{GouraudTriangle, SliceFramebuffer, Vertex};
///
/// let mut pixels = [Rgb888::BLACK; 16 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
/// let triangle = GouraudTriangle::new([
///     Vertex::new(0.0, 0.0, Rgb888::new(0, 0, 0)),
///     Vertex::new(32.0, 0.0, Rgb888::new(255, 0, 0)),
///     Vertex::new(0.0, 32.0, Rgb888::new(0, 0, 0)),
/// ]);
/// // Through any DrawTarget, or straight into a SliceFramebuffer: the same pixels.
/// triangle.draw(&mut fb)?;
/// triangle.draw_into(&mut fb);
/// // Red grows with x: 255 · 8.5 / 32 = 67.7 at the centre of pixel (8, 0), within 1 LSB.
/// let red = fb.get(8, 0).unwrap().r();
/// assert!((67..=68).contains(&red));
/// # Ok::<(), core::convert::Infallible>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GouraudTriangle<C> {
    /// The three vertices, in either winding.
    pub vertices: [Vertex<C>; 3],
}

impl<C: GouraudColor> GouraudTriangle<C> {
    /// A Gouraud triangle through `vertices` (either winding).
    pub const fn new(vertices: [Vertex<C>; 3]) -> Self {
        GouraudTriangle { vertices }
    }

    /// Draws into a [`SliceFramebuffer`] with slice writes and the colour format's packed span
    /// loop (tiny triangles on x86-64: one masked write per row of eight pixels): the fastest
    /// path, with the same pixels as [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, C>) {
        let clip = framebuffer.bounding_box();
        let mut shader = IntoSlice::new(framebuffer, true);
        shade(self.positions(), &self.channels(), &clip, &mut shader);
    }

    /// Draws into a [`SliceFramebuffer`] like [`draw_into`](Self::draw_into) if the triangle is
    /// compact (bounding box under 2048 × 2048 pixels, see [`COMPACT_LIMIT`](crate::raster::COMPACT_LIMIT)),
    /// else draws nothing and returns [`TooLarge`]. A firmware that draws only through this
    /// method links only the compact rasterizer: a fraction of `draw_into`'s code. It always
    /// walks spans (no rows of lanes): the same pixels.
    pub fn draw_into_compact(
        &self,
        framebuffer: &mut SliceFramebuffer<'_, C>,
    ) -> Result<(), TooLarge> {
        let clip = framebuffer.bounding_box();
        let mut shader = IntoSlice::new(framebuffer, false);
        shade_compact(self.positions(), &self.channels(), &clip, &mut shader)
    }

    /// Draws the rows of `window` into `framebuffer` (a band's buffer) as
    /// [`draw_into`](Self::draw_into) draws them into a framebuffer whose bounds are `clip`.
    #[inline]
    pub(crate) fn draw_rows(
        &self,
        framebuffer: &mut SliceFramebuffer<'_, C>,
        clip: &Rectangle,
        window: &impl RowWindow,
    ) {
        let shader = IntoSlice::new(framebuffer, false);
        window.shade(self.positions(), &self.channels(), clip, shader);
    }

    /// The covered spans inside `clip` with their colours, each at most
    /// [`MAX_CHUNK`] pixels long.
    pub fn shaded_spans(&self, clip: &Rectangle) -> ShadedSpans<C> {
        ShadedSpans::new(self, clip)
    }

    /// The vertices' positions.
    #[inline(always)]
    fn positions(&self) -> [(Coord, Coord); 3] {
        self.vertices.map(|v| v.position())
    }

    /// The vertices' colour channels, the planes' attributes.
    #[inline(always)]
    fn channels(&self) -> Attributes<3> {
        Attributes::channels(self.vertices.map(|v| v.color.channels()))
    }
}

impl<C: GouraudColor> Drawable for GouraudTriangle<C> {
    type Color = C;
    type Output = ();

    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        let clip = target.bounding_box();
        let mut shader = ToTarget {
            target,
            result: Ok(()),
        };
        shade(self.positions(), &self.channels(), &clip, &mut shader);
        shader.result
    }
}

/// The span shader of [`GouraudTriangle::draw_into`]: the colour format's span loop into the
/// slice, and its masked rows of eight pixels for tiny triangles (x86-64) when `rows`.
struct IntoSlice<'f, 'a, C> {
    framebuffer: &'f mut SliceFramebuffer<'a, C>,
    /// Read by `row_width` only, which the walks ask on x86-64 alone (Rust 1.85 sees the field
    /// as never read elsewhere).
    #[cfg_attr(not(sse2_rows), allow(dead_code))]
    rows: bool,
}

impl<'f, 'a, C: GouraudColor> IntoSlice<'f, 'a, C> {
    #[inline(always)]
    fn new(framebuffer: &'f mut SliceFramebuffer<'a, C>, rows: bool) -> Self {
        IntoSlice { framebuffer, rows }
    }
}

impl<C: GouraudColor> SpanShader<3> for IntoSlice<'_, '_, C> {
    type Steps = SpanSteps;

    #[inline(always)]
    fn prepare(&mut self, step: [u32; 3]) -> SpanSteps {
        C::prepare_steps(step)
    }

    scan_small_with_walk_planes!();

    #[inline(always)]
    fn span(&mut self, steps: &SpanSteps, span: Span, start: [u32; 3]) {
        // The spans of the walk are clipped to the framebuffer.
        if let Some(row) = self
            .framebuffer
            .clipped_span_mut(span.y, span.x_start, span.x_end)
        {
            C::fill_prepared(row, start, steps);
        }
    }

    #[inline(always)]
    fn row_width(&self) -> Option<u32> {
        self.rows.then(|| self.framebuffer.size().width)
    }

    #[inline(always)]
    fn masked_row(
        &mut self,
        steps: &SpanSteps,
        y: i32,
        x: i32,
        covered: [i16; LANES],
        first: u32,
        start: [u32; 3],
    ) {
        if let Some(row) = self.framebuffer.lanes_mut(y, x) {
            C::fill_masked_row(row, covered, first, start, steps);
        }
    }
}

/// The span shader of [`GouraudTriangle`]'s [`Drawable::draw`]: one `fill_contiguous` a span.
/// After an error it has [stopped](SpanShader::stopped): the walk ends there.
struct ToTarget<'t, D: DrawTarget> {
    target: &'t mut D,
    result: Result<(), D::Error>,
}

impl<C: GouraudColor, D: DrawTarget<Color = C>> SpanShader<3> for ToTarget<'_, D> {
    type Steps = SpanSteps;

    scan_small_with_walk_planes!();

    #[inline(always)]
    fn prepare(&mut self, step: [u32; 3]) -> SpanSteps {
        C::prepare_steps(step)
    }

    #[inline(always)]
    fn span(&mut self, steps: &SpanSteps, span: Span, start: [u32; 3]) {
        if self.result.is_ok() {
            let area = Rectangle::new(Point::new(span.x_start, span.y), Size::new(span.len(), 1));
            let colors = SpanColors::<C>::new(start, steps, span.len());
            self.result = self.target.fill_contiguous(&area, colors);
        }
    }

    #[inline(always)]
    fn stopped(&self) -> bool {
        self.result.is_err()
    }
}

/// A triangle filled with one colour; covers exactly the pixels a [`GouraudTriangle`] with the
/// same positions covers.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::{SliceFramebuffer, SolidTriangle};
///
/// let mut pixels = [Rgb565::BLACK; 16 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
/// // Sub-pixel corners as floats; far off-screen vertices are clipped exactly.
/// SolidTriangle::new([(0.0, 0.0), (1000.0, 0.0), (0.0, 16.0)], Rgb565::RED).draw_into(&mut fb);
/// assert_eq!(fb.get(0, 0), Some(Rgb565::RED));
/// // Points as embedded-graphics gives them: at pixel centres.
/// let points = [Point::new(2, 2), Point::new(12, 2), Point::new(2, 12)];
/// SolidTriangle::at_pixel_centres(points, Rgb565::GREEN).draw(&mut fb)?;
/// assert_eq!(fb.get(3, 3), Some(Rgb565::GREEN));
/// # Ok::<(), core::convert::Infallible>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SolidTriangle<C> {
    /// The three corner positions, in either winding.
    pub points: [(Coord, Coord); 3],
    /// The fill colour.
    pub color: C,
}

impl<C: PixelColor> SolidTriangle<C> {
    /// A triangle with corners `points` (`f32`, `f64` or [`Coord`] pairs, see [`ToCoord`])
    /// filled with `color`.
    #[inline(always)]
    pub fn new<P: ToCoord>(points: [(P, P); 3], color: C) -> Self {
        SolidTriangle {
            points: points.map(|(x, y)| (x.to_coord(), y.to_coord())),
            color,
        }
    }

    /// The triangle through the centres of pixels `points`: the embedded-graphics-compatible
    /// placement. It covers the pixels of an embedded-graphics filled `Triangle` of the same
    /// points except some along the edges: embedded-graphics draws every pixel its outline
    /// passes through (a shared edge is drawn by both neighbours), while here a pixel is drawn
    /// when its centre is inside, and one whose centre lies exactly on an edge goes to one
    /// neighbour only (the top-left rule). Measured against embedded-graphics over 3,000 random
    /// triangles of 4 to 70 pixels (`tests/all/eg_placement.rs`): 282,390 pixels drawn by both, none
    /// drawn only here, 46,562 only by embedded-graphics, all with centres within ½ pixel of the
    /// triangle (its outline). Placing the points at pixel corners instead
    /// ([`Vertex::at_pixel_corner`]) shifts the triangle by half a pixel up and left and differs
    /// on 53,119 pixels, both ways.
    pub fn at_pixel_centres(points: [Point; 3], color: C) -> Self {
        SolidTriangle {
            points: points.map(|p| (pixel_centre(p.x), pixel_centre(p.y))),
            color,
        }
    }

    /// Draws into a [`SliceFramebuffer`] with one slice fill per span (tiny triangles on x86-64:
    /// one masked write per row of eight pixels); the same pixels as [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, C>) {
        let clip = framebuffer.bounding_box();
        let mut shader = SolidIntoSlice {
            framebuffer,
            color: self.color,
        };
        shade(
            self.points,
            &Attributes::channels([[]; 3]),
            &clip,
            &mut shader,
        );
    }

    /// Draws the rows of `window` into `framebuffer` (a band's buffer) as
    /// [`draw_into`](Self::draw_into) draws them into a framebuffer whose bounds are `clip`.
    #[inline]
    pub(crate) fn draw_rows(
        &self,
        framebuffer: &mut SliceFramebuffer<'_, C>,
        clip: &Rectangle,
        window: &impl RowWindow,
    ) {
        let shader = SolidIntoSlice {
            framebuffer,
            color: self.color,
        };
        let attributes = Attributes::channels([[]; 3]);
        window.shade(self.points, &attributes, clip, shader);
    }

    /// The covered spans inside `clip`.
    pub fn spans(&self, clip: &Rectangle) -> Spans {
        Spans::of_triangle(self.points, clip)
    }
}

impl<C: PixelColor> Drawable for SolidTriangle<C> {
    type Color = C;
    type Output = ();

    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        let clip = target.bounding_box();
        let mut shader = SolidToTarget {
            target,
            color: self.color,
            result: Ok(()),
        };
        shade(
            self.points,
            &Attributes::channels([[]; 3]),
            &clip,
            &mut shader,
        );
        shader.result
    }
}

/// The span shader of [`SolidTriangle::draw_into`]: slice fills, and masked rows of eight
/// pixels for tiny triangles (x86-64).
struct SolidIntoSlice<'f, 'a, C> {
    framebuffer: &'f mut SliceFramebuffer<'a, C>,
    color: C,
}

impl<C: PixelColor> SpanShader<0> for SolidIntoSlice<'_, '_, C> {
    type Steps = ();

    scan_small_with_walk_planes!();

    #[inline(always)]
    fn prepare(&mut self, _: [u32; 0]) {}

    #[inline(always)]
    fn span(&mut self, _: &(), span: Span, _: [u32; 0]) {
        // The spans of the walk are clipped to the framebuffer.
        if let Some(row) = self
            .framebuffer
            .clipped_span_mut(span.y, span.x_start, span.x_end)
        {
            fill_row(row, self.color);
        }
    }

    #[inline(always)]
    fn row_width(&self) -> Option<u32> {
        Some(self.framebuffer.size().width)
    }

    #[inline(always)]
    fn masked_row(&mut self, _: &(), y: i32, x: i32, covered: [i16; LANES], _: u32, _: [u32; 0]) {
        if let Some(row) = self.framebuffer.lanes_mut(y, x) {
            // The whole row read, then written: a select of values, which LLVM vectorises (a
            // select of a load per pixel becomes a branch per pixel).
            let (old, color) = (*row, self.color);
            *row = core::array::from_fn(|i| if covered[i] != 0 { color } else { old[i] });
        }
    }
}

/// The span shader of [`SolidTriangle`]'s [`Drawable::draw`]: one `fill_solid` a span. After an
/// error it has [stopped](SpanShader::stopped): the walk ends there.
struct SolidToTarget<'t, D: DrawTarget> {
    target: &'t mut D,
    color: D::Color,
    result: Result<(), D::Error>,
}

impl<D: DrawTarget> SpanShader<0> for SolidToTarget<'_, D> {
    type Steps = ();

    scan_small_with_walk_planes!();

    #[inline(always)]
    fn prepare(&mut self, _: [u32; 0]) {}

    #[inline(always)]
    fn span(&mut self, _: &(), span: Span, _: [u32; 0]) {
        if self.result.is_ok() {
            let area = Rectangle::new(Point::new(span.x_start, span.y), Size::new(span.len(), 1));
            self.result = self.target.fill_solid(&area, self.color);
        }
    }

    #[inline(always)]
    fn stopped(&self) -> bool {
        self.result.is_err()
    }
}

/// Iterator over the covered spans of a [`GouraudTriangle`] and their colours: the same walk,
/// planes and colours as [`Drawable::draw`], spans cut into chunks of at most [`MAX_CHUNK`]
/// pixels.
#[derive(Debug, Clone)]
pub struct ShadedSpans<C> {
    spans: Spans,
    shading: Shading,
    /// Per-pixel steps of the channels, prepared for the colour format's span loop.
    steps: SpanSteps,
    /// The span being handed out in chunks, how far into it we are, and its first pixel's values.
    current: Option<(Span, u32, [u32; 3])>,
    _color: PhantomData<C>,
}

/// How the channel values at span starts are found.
// No heap to box the rare large variant in.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
enum Shading {
    /// The stepped planes (the common case), from the pixel `origin`.
    Stepped {
        planes: Planes<3>,
        origin: (i32, i32),
    },
    /// Exact planes (regions over 2¹⁶ pixels across).
    Exact(ExactPlanes<3>),
}

impl<C: GouraudColor> ShadedSpans<C> {
    fn new(triangle: &GouraudTriangle<C>, clip: &Rectangle) -> Self {
        let (positions, channels) = (triangle.positions(), triangle.channels());
        let region = match CompactTriangle::classify(positions, clip).walk() {
            Ok((compact, walk)) => {
                let planes = Planes::compact(&compact.setup, &channels);
                let origin = (compact.x0, compact.y0);
                return Self::stepped(Spans::compact(walk), planes, origin);
            }
            Err(None) => return Self::empty(),
            Err(Some(region)) => region,
        };
        let setup = TriangleSetup::new(positions);
        // By reference: moving the setup out of the `Option` would copy it.
        let Some(setup) = setup.as_ref() else {
            return Self::empty();
        };
        let spans = Spans::new(setup, region);
        let planes = ExactPlanes::new(setup, &region, &channels);
        if let GeneralPlanes::Stepped(stepped) = GeneralPlanes::new(&planes, &region) {
            return Self::stepped(spans, stepped, (region.x0, region.y0));
        }
        ShadedSpans {
            spans,
            steps: C::prepare_steps(planes.step()),
            shading: Shading::Exact(planes),
            current: None,
            _color: PhantomData,
        }
    }

    fn stepped(spans: Spans, planes: Planes<3>, origin: (i32, i32)) -> Self {
        ShadedSpans {
            spans,
            steps: C::prepare_steps(planes.step()),
            shading: Shading::Stepped { planes, origin },
            current: None,
            _color: PhantomData,
        }
    }

    /// An iterator with no spans.
    fn empty() -> Self {
        ShadedSpans {
            spans: Spans::empty(),
            shading: Shading::Exact(ExactPlanes::empty()),
            steps: SpanSteps::default(),
            current: None,
            _color: PhantomData,
        }
    }

    /// Channel values at the start of `span`.
    #[inline]
    fn row_start(&self, span: &Span) -> [u32; 3] {
        match &self.shading {
            Shading::Stepped { planes, origin } => {
                // Inside the walk's region, which starts at `origin`.
                let column = span.x_start.wrapping_sub(origin.0) as u32;
                planes.at(column, span.y.wrapping_sub(origin.1) as u32)
            }
            Shading::Exact(planes) => planes.at(span.x_start, span.y),
        }
    }

    /// Channel values `offset` pixels into `span`, whose first pixel's are `start`.
    fn further(&self, span: &Span, start: [u32; 3], offset: u32) -> [u32; 3] {
        match &self.shading {
            Shading::Stepped { .. } => {
                let step = self.steps.step();
                core::array::from_fn(|k| start[k].wrapping_add(step[k].wrapping_mul(offset)))
            }
            // Inside the span: no overflow.
            Shading::Exact(planes) => planes.at(span.x_start.wrapping_add(offset as i32), span.y),
        }
    }
}

impl<C: GouraudColor> Iterator for ShadedSpans<C> {
    type Item = (Span, SpanColors<C>);

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        let (span, offset, first) = match self.current {
            Some(current) => current,
            None => {
                let span = self.spans.next()?;
                let start = self.row_start(&span);
                if span.len() <= MAX_CHUNK {
                    return Some((span, SpanColors::new(start, &self.steps, span.len())));
                }
                (span, 0, start)
            }
        };
        let start = if offset == 0 {
            first
        } else {
            self.further(&span, first, offset)
        };
        let len = (span.len() - offset).min(MAX_CHUNK);
        let done = offset + len;
        self.current = (done < span.len()).then_some((span, done, first));
        let chunk = Span {
            y: span.y,
            x_start: span.x_start.wrapping_add(offset as i32),
            x_end: span.x_start.wrapping_add(done as i32),
        };
        Some((chunk, SpanColors::new(start, &self.steps, len)))
    }
}

/// The colours of one span, left to right: the colour format's span loop
/// ([`GouraudColor::fill_prepared`]) one pixel at a time, so a target drawing them gets the
/// colours [`GouraudTriangle::draw_into`] writes.
#[derive(Debug, Clone)]
pub struct SpanColors<C> {
    /// The channel values at the start of the current run (see [`GouraudColor::SPAN_RUN`]).
    value: [u32; 3],
    /// The span loop's state at the next pixel.
    state: [u32; 3],
    steps: SpanSteps,
    /// Pixels handed out since the current run's start.
    taken: u32,
    left: u32,
    /// Whether the span reaches a restart of the span loop.
    restarts: bool,
    _color: PhantomData<C>,
}

impl<C: GouraudColor> SpanColors<C> {
    /// The `len` colours of a span whose channels start at `value`, stepped by `steps`.
    #[inline(always)]
    pub(crate) fn new(value: [u32; 3], steps: &SpanSteps, len: u32) -> Self {
        SpanColors {
            value,
            state: C::span_state(value),
            steps: *steps,
            taken: 0,
            left: len,
            restarts: C::SPAN_RUN.is_some_and(|run| len > run.get()),
            _color: PhantomData,
        }
    }
}

impl<C: GouraudColor> Iterator for SpanColors<C> {
    type Item = C;

    #[inline(always)]
    fn next(&mut self) -> Option<C> {
        if self.left == 0 {
            return None;
        }
        self.left -= 1;
        let color = C::state_color(self.state);
        self.taken = self.taken.wrapping_add(1);
        match C::SPAN_RUN {
            // Only spans that reach a restart test for it: the others' loop is plain stepping,
            // which compilers vectorise.
            Some(run) if self.restarts && self.taken == run.get() => {
                self.value = restart_value(self.value, &self.steps, run.get());
                self.state = C::span_state(self.value);
                self.taken = 0;
            }
            _ => self.state = C::next_state(self.state, &self.steps),
        }
        Some(color)
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left as usize, Some(self.left as usize))
    }
}

impl<C: GouraudColor> ExactSizeIterator for SpanColors<C> {}

impl<C: GouraudColor> SpanColors<C> {
    /// Writes the remaining colours to the start of `dst` (as many as fit), the same colours as
    /// iterating: from the span loop's next restart on with the colour format's fastest loop
    /// ([`GouraudColor::fill_prepared`]), before it one at a time.
    #[inline]
    pub fn fill(self, dst: &mut [C]) {
        let n = dst.len().min(self.left as usize);
        let Some(dst) = dst.get_mut(..n) else {
            return;
        };
        let mut colors = self;
        let mut filled = 0;
        while colors.taken != 0 {
            match (dst.get_mut(filled), colors.next()) {
                (Some(px), Some(color)) => *px = color,
                _ => return,
            }
            filled += 1;
        }
        if let Some(rest) = dst.get_mut(filled..) {
            C::fill_prepared(rest, colors.value, &colors.steps);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::Counting;
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::Pixel;

    /// A target that fails on its `fail_at`-th span and counts the spans it is handed.
    struct Failing {
        spans: u32,
        fail_at: u32,
        area: Rectangle,
    }

    impl Failing {
        /// 64 × 64 pixels.
        fn new(fail_at: u32) -> Self {
            let area = Rectangle::new(Point::zero(), Size::new(64, 64));
            Failing {
                spans: 0,
                fail_at,
                area,
            }
        }
    }

    impl Dimensions for Failing {
        fn bounding_box(&self) -> Rectangle {
            self.area
        }
    }

    impl DrawTarget for Failing {
        type Color = Rgb565;
        type Error = u32;

        fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, _: I) -> Result<(), u32> {
            self.spans += 1;
            if self.spans == self.fail_at {
                Err(self.spans)
            } else {
                Ok(())
            }
        }
    }

    /// The first error is returned and nothing is drawn after it.
    #[test]
    fn draw_stops_at_the_first_error() {
        let c = |x: i32, y: i32| (Coord::from_num(x), Coord::from_num(y));
        let points = [c(1, 1), c(60, 5), c(10, 50)];
        let solid = SolidTriangle::new(points, Rgb565::RED);
        let colors = [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE];
        let gouraud = GouraudTriangle::new(
            [0, 1, 2].map(|k| Vertex::new(points[k].0, points[k].1, colors[k])),
        );
        let mut all = Failing::new(0);
        solid.draw(&mut all).unwrap();
        assert!(all.spans > 40);
        for fail_at in [1, 7, all.spans] {
            let mut target = Failing::new(fail_at);
            assert_eq!(solid.draw(&mut target), Err(fail_at));
            assert_eq!(target.spans, fail_at);
            let mut target = Failing::new(fail_at);
            assert_eq!(gouraud.draw(&mut target), Err(fail_at));
            assert_eq!(target.spans, fail_at);
        }
    }

    /// After the target's first error `draw`'s shaders have stopped, and the walk hands them no
    /// further span: into a target over 10⁹ pixels a side that fails its first call, with
    /// triangles across the whole `Coord` range (exact planes; the Gouraud walk went on through
    /// billions of chunks for 10 s and more, issue #32 item 11) and a small one. The spans are
    /// counted as the walk hands them over (`tests/all/draw_errors.rs` has the user's view).
    #[test]
    fn a_failed_draw_walks_no_further() {
        const FAR: i32 = (1 << 23) - 1;
        let c = |x: i32, y: i32| (Coord::from_num(x), Coord::from_num(y));
        let huge = Rectangle::new(
            Point::new(-600_000_000, -700_000_000),
            Size::new(1_200_000_000, 1_400_000_000),
        );
        let triangles = [
            [c(-FAR, -FAR), c(FAR, -FAR), c(0, FAR)],
            [c(-FAR, -FAR), c(FAR, -FAR / 2), c(-FAR / 3, FAR)],
            [c(1, 1), c(60, 5), c(10, 50)],
        ];
        let colors = [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE];
        for points in triangles {
            let mut target = Failing {
                area: huge,
                ..Failing::new(1)
            };
            let shader = SolidToTarget {
                target: &mut target,
                color: Rgb565::RED,
                result: Ok(()),
            };
            let mut counting = Counting::new(shader);
            let attributes = Attributes::channels([[]; 3]);
            shade(points, &attributes, &huge, &mut counting);
            assert_eq!(counting.shader.result, Err(1), "solid {points:?}");
            assert_eq!(counting.handed, 1, "solid {points:?}");
            assert_eq!(target.spans, 1);

            let gouraud = GouraudTriangle::new(
                [0, 1, 2].map(|k| Vertex::new(points[k].0, points[k].1, colors[k])),
            );
            let mut target = Failing {
                area: huge,
                ..Failing::new(1)
            };
            let shader = ToTarget {
                target: &mut target,
                result: Ok(()),
            };
            let mut counting = Counting::new(shader);
            shade(
                gouraud.positions(),
                &gouraud.channels(),
                &huge,
                &mut counting,
            );
            assert_eq!(counting.shader.result, Err(1), "Gouraud {points:?}");
            assert_eq!(counting.handed, 1, "Gouraud {points:?}");
            assert_eq!(target.spans, 1);
        }
    }
}

/// Tiny triangles (x86-64) drawn a row of lanes at a time by `draw_into`: the same pixels as
/// the span walk.
#[cfg(all(test, sse2_rows))]
mod tiny_tests {
    use embedded_graphics::pixelcolor::{Bgr565, Gray8, Rgb565, Rgb888};

    use embedded_graphics::Drawable;

    use crate::{Coord, GouraudColor, GouraudTriangle, SolidTriangle, Vertex};

    /// Tiny and small triangles drawn by `draw_into` (this path, for the tiny ones) and by the
    /// span walk (`draw_into_compact`; `Drawable::draw` for solid ones) give the same
    /// framebuffer, pixel for pixel: over random backgrounds, near and across every border of
    /// framebuffers 8 to 21 pixels wide.
    fn same_as_the_span_walk<C: GouraudColor + core::fmt::Debug>(
        seed: u64,
        color: impl Fn(u64) -> C,
    ) {
        let mut next = crate::random(seed);
        let mut tiny = 0;
        for n in 0..40_000 {
            let (width, height) = (8 + (next() % 14) as u32, 1 + (next() % 14) as u32);
            let len = (width * height) as usize;
            let mut background = [color(0); 21 * 14];
            for px in &mut background[..len] {
                *px = color(next());
            }
            // Boxes up to 9 pixels (some just past the tiny limit), anywhere over the buffer; a
            // quarter near the limit with vertices on the box's corners, across the right border
            // (the eight lanes then reach furthest from the vertices: edge values wrap there).
            let extreme = n % 4 == 1;
            let size = if extreme {
                1792 + (next() % 256) as i32
            } else {
                1 + (next() % (9 * 256)) as i32
            };
            let origin = (
                if extreme {
                    (width as i32 - 7) * 256 + (next() % 1536) as i32
                } else {
                    (next() % u64::from(width + 8) * 256) as i32 - 6 * 256
                },
                (next() % u64::from(height + 8) * 256) as i32 - 6 * 256,
            );
            // A third on a 1/2-pixel lattice: edges through pixel centres (the fill rule's ties).
            let lattice = if n % 3 == 0 { !127 } else { !0 };
            let v: [Vertex<C>; 3] = core::array::from_fn(|_| {
                let mut at = |o: i32| {
                    let d = if extreme {
                        (next() % 2) as i32 * (size - 1)
                    } else {
                        (next() % size as u64) as i32
                    };
                    (o + d) & lattice
                };
                let (x, y) = (at(origin.0), at(origin.1));
                Vertex::new(Coord::from_bits(x), Coord::from_bits(y), color(next()))
            });
            let triangle = GouraudTriangle::new(v);
            let (mut got, mut want) = (background, background);
            let mut fb = crate::SliceFramebuffer::new(&mut got[..len], width, height).unwrap();
            triangle.draw_into(&mut fb);
            let mut fb = crate::SliceFramebuffer::new(&mut want[..len], width, height).unwrap();
            assert_eq!(triangle.draw_into_compact(&mut fb), Ok(()));
            assert!(got == want, "case {n}: {width}×{height}, {v:?}");
            // Solid: `draw_into` (this path) against `Drawable::draw` (the span walk).
            let solid = SolidTriangle::new(v.map(|v| v.position()), v[0].color);
            let (mut got, mut want) = (background, background);
            let mut fb = crate::SliceFramebuffer::new(&mut got[..len], width, height).unwrap();
            solid.draw_into(&mut fb);
            let mut fb = crate::SliceFramebuffer::new(&mut want[..len], width, height).unwrap();
            let Ok(()) = solid.draw(&mut fb);
            assert!(got == want, "solid case {n}: {width}×{height}, {v:?}");
            tiny += usize::from(size < 2048);
        }
        assert!(tiny > 20_000);
    }

    #[test]
    fn rgb565_rows_are_the_span_walks_pixels() {
        same_as_the_span_walk(0x7157_0001, |r| {
            Rgb565::from(embedded_graphics::pixelcolor::raw::RawU16::new(r as u16))
        });
    }

    #[test]
    fn bgr565_rows_are_the_span_walks_pixels() {
        same_as_the_span_walk(0x7157_0002, |r| {
            Bgr565::from(embedded_graphics::pixelcolor::raw::RawU16::new(r as u16))
        });
    }

    #[test]
    fn default_rows_are_the_span_walks_pixels() {
        same_as_the_span_walk(0x7157_0003, |r| {
            Rgb888::new(r as u8, (r >> 8) as u8, (r >> 16) as u8)
        });
        same_as_the_span_walk(0x7157_0004, |r| Gray8::new(r as u8));
    }
}
