//! Translucent triangles: a solid or Gouraud triangle blended source-over what is under it.
//!
//! [`SolidTriangle::with_opacity`] and [`GouraudTriangle::with_alpha`] (an alpha per vertex,
//! interpolated like a colour channel) make a [`Translucent`] triangle. Blending needs the
//! destination, and where it comes from is in the types:
//!
//! * [`Translucent::draw_into`] a [`SliceFramebuffer`] (and bands: `ColorBand::draw`) reads
//!   the pixels it blends over;
//! * [`Translucent::draw_reading`] reads them from any `DrawTarget` that implements
//!   embedded-graphics' [`GetPixel`], 32 pixels at a time;
//! * [`Translucent::over`] a known background colour is a [`Drawable`] for any `DrawTarget`.
//!
//! All give the same pixels. A solid triangle's colour `s` at opacity `a` over `d` is
//! [`GouraudColor::blend`]; with an alpha per vertex, the colours are interpolated premultiplied
//! by their alpha (the colour of a transparent vertex does not show) and the alpha with them, and
//! each channel is `P + d·(1 − α)` for the premultiplied colour `P` and alpha `α` there. Both are
//! within 1 LSB of the exact f64 blend (of the barycentric `P` and `α`, for an alpha per vertex;
//! see `tests/all/alpha.rs`).
//!

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::image::GetPixel;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::framebuffer::SliceFramebuffer;
use super::triangle::{GouraudTriangle, SolidTriangle};
use crate::color::{
    blend_premultiplied, premultiplied_values, BlendSource, GouraudColor, STEP_BITS,
    TRANSPARENCY_HALF,
};
use crate::raster::band::RowWindow;
use crate::raster::plane::Attributes;
use crate::raster::shade;
use crate::raster::walk::Span;
use crate::raster::SpanShader;

/// The rounding offset of a colour plane: ½ of a channel's unit.
const HALF: u32 = 1 << (STEP_BITS - 1);

/// Pixels read from a [`GetPixel`] target, blended and written back at a time.
const READ_CHUNK: usize = 32;

/// A triangle blended source-over its destination: a [`SolidTriangle`] at one opacity
/// ([`SolidTriangle::with_opacity`]) or a [`GouraudTriangle`] with an alpha per vertex
/// ([`GouraudTriangle::with_alpha`]). Alpha 0 is transparent, 255 opaque.
///
/// The destination is read where it can be: [`draw_into`](Self::draw_into) a
/// [`SliceFramebuffer`], bands, [`draw_reading`](Self::draw_reading) any target with
/// [`GetPixel`]; [`over`](Self::over) a known background colour draws into any `DrawTarget`.
/// Every path gives the same pixels, within 1 LSB of the exact f64 blend: [`GouraudColor::blend`]
/// of the colour at an opacity, the premultiplied blend of [`GouraudTriangle::with_alpha`] with
/// an alpha per vertex.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::{GouraudColor, GouraudTriangle, SliceFramebuffer, SolidTriangle, Vertex};
///
/// let mut pixels = [Rgb565::BLUE; 16 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
/// let half_red = SolidTriangle::new([(0.0, 0.0), (16.0, 0.0), (0.0, 16.0)], Rgb565::RED)
///     .with_opacity(128);
/// half_red.draw_into(&mut fb);
/// assert_eq!(fb.get(1, 1), Some(Rgb565::RED.blend(Rgb565::BLUE, 128)));
///
/// // Any display, over a background colour it is known to have:
/// half_red.over(Rgb565::BLUE).draw(&mut fb)?;
///
/// // An alpha per vertex: opaque at the left, transparent at the right.
/// let fade = GouraudTriangle::new([
///     Vertex::new(0.0, 0.0, Rgb565::WHITE),
///     Vertex::new(16.0, 8.0, Rgb565::WHITE),
///     Vertex::new(0.0, 16.0, Rgb565::WHITE),
/// ])
/// .with_alpha([255, 0, 255]);
/// fade.draw_reading(&mut fb)?; // reads the pixels back through `GetPixel`
/// # Ok::<(), core::convert::Infallible>(())
/// ```
///
/// [`GouraudColor::blend`]: crate::GouraudColor::blend
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Translucent<T> {
    shape: T,
    alpha: [u8; 3],
}

impl<T> Translucent<T> {
    /// The opaque triangle.
    pub fn shape(&self) -> &T {
        &self.shape
    }

    /// The alpha at each vertex (all three the same for a solid triangle's opacity).
    pub fn alpha(&self) -> [u8; 3] {
        self.alpha
    }

    /// This triangle over a background of one colour: a [`Drawable`] for any `DrawTarget`, the
    /// pixels [`draw_into`](Self::draw_into) gives over a framebuffer of that colour.
    pub fn over<C>(self, background: C) -> OnBackground<Self, C> {
        OnBackground::new(self, background)
    }
}

impl<C: GouraudColor> SolidTriangle<C> {
    /// This triangle at opacity `opacity` (0 transparent, 255 opaque), blended over what is
    /// under it ([`Translucent`]).
    pub fn with_opacity(self, opacity: u8) -> Translucent<Self> {
        Translucent {
            shape: self,
            alpha: [opacity; 3],
        }
    }
}

impl<C: GouraudColor> GouraudTriangle<C> {
    /// This triangle with an alpha at each vertex (0 transparent, 255 opaque), blended over what
    /// is under it ([`Translucent`]). The alpha is interpolated like a colour channel and the
    /// colours premultiplied by it: a pixel is `P + d·(1 − α)` for the interpolated `s·α` (`P`)
    /// and `α` there, within 1 LSB of the exact value, so a transparent vertex's colour does not
    /// show.
    pub fn with_alpha(self, alpha: [u8; 3]) -> Translucent<Self> {
        Translucent { shape: self, alpha }
    }
}

/// A shape that blends over what is under it ([`Translucent`], [`AntiAliased`]) over a known
/// background colour (their `over`): a [`Drawable`] for any `DrawTarget`.
///
/// [`AntiAliased`]: crate::AntiAliased
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OnBackground<T, C> {
    shape: T,
    background: C,
}

impl<T, C> OnBackground<T, C> {
    /// `shape` over `background`.
    pub(crate) fn new(shape: T, background: C) -> Self {
        OnBackground { shape, background }
    }

    /// The shape and the background.
    pub(crate) fn parts(&self) -> (&T, &C) {
        (&self.shape, &self.background)
    }
}

/// How a translucent shape's spans are coloured: what the three shaders below share.
trait SpanSource<C: GouraudColor, const N: usize> {
    /// Per-triangle steps.
    type Steps;
    /// What a pixel blends with (its planes' values).
    type Pixel;
    /// The attributes' steps prepared.
    fn prepare(&self, step: [u32; N]) -> Self::Steps;
    /// The pixels of a span of `len` pixels from `start`.
    fn pixels(
        &self,
        steps: &Self::Steps,
        start: [u32; N],
        len: u32,
    ) -> impl Iterator<Item = Self::Pixel>;
    /// `pixel` over the colour `under`.
    fn over(&self, pixel: Self::Pixel, under: C) -> C;
    /// Blends a span into `dst` (its pixels): [`over`](Self::over) each of them.
    #[inline(always)]
    fn blend_into(&self, steps: &Self::Steps, start: [u32; N], dst: &mut [C]) {
        let pixels = self.pixels(steps, start, dst.len() as u32);
        for (px, pixel) in dst.iter_mut().zip(pixels) {
            *px = self.over(pixel, *px);
        }
    }
}

/// A solid colour at one opacity.
struct SolidSource<C> {
    color: C,
    alpha: u8,
    source: BlendSource,
}

impl<C: GouraudColor> SpanSource<C, 0> for SolidSource<C> {
    type Steps = ();
    type Pixel = ();

    #[inline(always)]
    fn prepare(&self, _: [u32; 0]) {}

    #[inline(always)]
    fn pixels(&self, _: &(), _: [u32; 0], len: u32) -> impl Iterator<Item = ()> {
        core::iter::repeat_n((), len as usize)
    }

    #[inline(always)]
    fn over(&self, _: (), under: C) -> C {
        self.color.blend(under, self.alpha)
    }

    #[inline(always)]
    fn blend_into(&self, _: &(), _: [u32; 0], dst: &mut [C]) {
        C::blend_solid(dst, &self.source);
    }
}

/// Colours with an alpha per vertex: the premultiplied colour planes and the transparency plane
/// ([`blend_premultiplied`]).
struct PremultipliedSource<C>(core::marker::PhantomData<C>);

impl<C: GouraudColor> SpanSource<C, 4> for PremultipliedSource<C> {
    type Steps = [u32; 4];
    type Pixel = [u32; 4];

    #[inline(always)]
    fn prepare(&self, step: [u32; 4]) -> [u32; 4] {
        step
    }

    #[inline(always)]
    fn pixels(&self, step: &[u32; 4], start: [u32; 4], len: u32) -> impl Iterator<Item = [u32; 4]> {
        let step = *step;
        let mut value = start;
        (0..len).map(move |_| {
            let here = value;
            for (v, s) in value.iter_mut().zip(step) {
                *v = v.wrapping_add(s);
            }
            here
        })
    }

    #[inline(always)]
    fn over(&self, [r, g, b, t]: [u32; 4], under: C) -> C {
        blend_premultiplied([r, g, b], t, under)
    }

    #[inline(always)]
    fn blend_into(&self, step: &[u32; 4], start: [u32; 4], dst: &mut [C]) {
        C::blend_premultiplied_span(dst, start, *step);
    }
}

/// Blends into a [`SliceFramebuffer`] (or a band's rows), reading its pixels.
struct BlendIntoSlice<'f, 'a, C, S> {
    framebuffer: &'f mut SliceFramebuffer<'a, C>,
    source: S,
}

impl<C: GouraudColor, S: SpanSource<C, N>, const N: usize> SpanShader<N>
    for BlendIntoSlice<'_, '_, C, S>
{
    type Steps = S::Steps;

    scan_small_with_walk_planes!();

    #[inline(always)]
    fn prepare(&mut self, step: [u32; N]) -> S::Steps {
        self.source.prepare(step)
    }

    #[inline(always)]
    fn span(&mut self, steps: &S::Steps, span: Span, start: [u32; N]) {
        if let Some(row) = self
            .framebuffer
            .clipped_span_mut(span.y, span.x_start, span.x_end)
        {
            self.source.blend_into(steps, start, row);
        }
    }
}

/// Blends over one background colour into any target: one `fill_contiguous` a span.
struct BlendOver<'t, D: DrawTarget, S> {
    target: &'t mut D,
    background: D::Color,
    source: S,
    result: Result<(), D::Error>,
}

impl<C, D, S, const N: usize> SpanShader<N> for BlendOver<'_, D, S>
where
    C: GouraudColor,
    D: DrawTarget<Color = C>,
    S: SpanSource<C, N>,
{
    type Steps = S::Steps;

    #[inline(always)]
    fn prepare(&mut self, step: [u32; N]) -> S::Steps {
        self.source.prepare(step)
    }

    #[inline(always)]
    fn span(&mut self, steps: &S::Steps, span: Span, start: [u32; N]) {
        if self.result.is_ok() {
            let area = Rectangle::new(Point::new(span.x_start, span.y), Size::new(span.len(), 1));
            let background = self.background;
            let source = &self.source;
            let colors = source
                .pixels(steps, start, span.len())
                .map(|pixel| source.over(pixel, background));
            self.result = self.target.fill_contiguous(&area, colors);
        }
    }

    #[inline(always)]
    fn stopped(&self) -> bool {
        self.result.is_err()
    }
}

/// Blends into a target it reads through [`GetPixel`], [`READ_CHUNK`] pixels at a time.
struct BlendReading<'t, D: DrawTarget, S> {
    target: &'t mut D,
    source: S,
    result: Result<(), D::Error>,
}

impl<C, D, S, const N: usize> SpanShader<N> for BlendReading<'_, D, S>
where
    C: GouraudColor,
    D: DrawTarget<Color = C> + GetPixel<Color = C>,
    S: SpanSource<C, N>,
{
    type Steps = S::Steps;

    #[inline(always)]
    fn prepare(&mut self, step: [u32; N]) -> S::Steps {
        self.source.prepare(step)
    }

    fn span(&mut self, steps: &S::Steps, span: Span, start: [u32; N]) {
        let mut pixels = self.source.pixels(steps, start, span.len());
        let mut x = span.x_start;
        while self.result.is_ok() && x < span.x_end {
            let mut buffer = [(C::from_channels([0; 3]), false); READ_CHUNK];
            let mut n = 0;
            for (slot, pixel) in buffer.iter_mut().zip(pixels.by_ref()) {
                // A pixel the target cannot read (outside it) is not drawn.
                let at = Point::new(x + n as i32, span.y);
                if let Some(under) = self.target.pixel(at) {
                    *slot = (self.source.over(pixel, under), true);
                }
                n += 1;
            }
            if n == 0 {
                break;
            }
            let area = Rectangle::new(Point::new(x, span.y), Size::new(n as u32, 1));
            let buffer = buffer.get(..n).unwrap_or(&[]);
            if buffer.iter().all(|&(_, read)| read) {
                let colors = buffer.iter().map(|&(color, _)| color);
                self.result = self.target.fill_contiguous(&area, colors);
            } else {
                let points = area.points();
                let drawn = buffer.iter().zip(points).filter(|((_, read), _)| *read);
                let pixels = drawn.map(|(&(color, _), p)| Pixel(p, color));
                self.result = self.target.draw_iter(pixels);
            }
            x += n as i32;
        }
    }

    #[inline(always)]
    fn stopped(&self) -> bool {
        self.result.is_err()
    }
}

/// What a translucent triangle draws with: its positions, attributes and span source.
trait Blendable<C: GouraudColor, const N: usize> {
    type Source: SpanSource<C, N>;
    fn parts(
        &self,
    ) -> (
        [(crate::Coord, crate::Coord); 3],
        Attributes<N>,
        Self::Source,
    );
}

impl<C: GouraudColor> Blendable<C, 0> for Translucent<SolidTriangle<C>> {
    type Source = SolidSource<C>;

    #[inline(always)]
    fn parts(
        &self,
    ) -> (
        [(crate::Coord, crate::Coord); 3],
        Attributes<0>,
        SolidSource<C>,
    ) {
        let (color, alpha) = (self.shape.color, self.alpha[0]);
        let source = SolidSource {
            color,
            alpha,
            source: BlendSource::new(color, alpha),
        };
        (self.shape.points, Attributes::channels([[]; 3]), source)
    }
}

impl<C: GouraudColor> Blendable<C, 4> for Translucent<GouraudTriangle<C>> {
    type Source = PremultipliedSource<C>;

    #[inline(always)]
    fn parts(
        &self,
    ) -> (
        [(crate::Coord, crate::Coord); 3],
        Attributes<4>,
        PremultipliedSource<C>,
    ) {
        let v = self.shape.vertices;
        let attributes = Attributes {
            values: core::array::from_fn(|k| {
                premultiplied_values(v[k].color.channels(), self.alpha[k])
            }),
            half: [HALF, HALF, HALF, TRANSPARENCY_HALF],
        };
        let source = PremultipliedSource(core::marker::PhantomData);
        (v.map(|v| v.position()), attributes, source)
    }
}

/// The drawing methods of both kinds of [`Translucent`] triangle.
macro_rules! translucent_draws {
    ($shape:ident, $n:literal) => {
        impl<C: GouraudColor> Translucent<$shape<C>> {
            /// Blends the triangle into a [`SliceFramebuffer`], reading its pixels: the fastest
            /// path, the pixels of every other.
            pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, C>) {
                let clip = framebuffer.bounding_box();
                let (positions, attributes, source) = Blendable::<C, $n>::parts(self);
                let mut shader = BlendIntoSlice {
                    framebuffer,
                    source,
                };
                shade(positions, &attributes, &clip, &mut shader);
            }

            /// Blends the triangle into `target`, reading the pixels under it through
            /// [`GetPixel`] (a pixel it cannot read is left alone): the pixels
            /// [`draw_into`](Self::draw_into) gives.
            pub fn draw_reading<D>(&self, target: &mut D) -> Result<(), D::Error>
            where
                D: DrawTarget<Color = C> + GetPixel<Color = C>,
            {
                let clip = target.bounding_box();
                let (positions, attributes, source) = Blendable::<C, $n>::parts(self);
                let mut shader = BlendReading {
                    target,
                    source,
                    result: Ok(()),
                };
                shade(positions, &attributes, &clip, &mut shader);
                shader.result
            }

            /// Draws the rows of `window` into `framebuffer` (a band's buffer) as
            /// [`draw_into`](Self::draw_into) draws them into a framebuffer whose bounds are
            /// `clip`.
            #[inline]
            pub(crate) fn draw_rows(
                &self,
                framebuffer: &mut SliceFramebuffer<'_, C>,
                clip: &Rectangle,
                window: &impl RowWindow,
            ) {
                let (positions, attributes, source) = Blendable::<C, $n>::parts(self);
                let shader = BlendIntoSlice {
                    framebuffer,
                    source,
                };
                window.shade(positions, &attributes, clip, shader);
            }
        }

        impl<C: GouraudColor> Drawable for OnBackground<Translucent<$shape<C>>, C> {
            type Color = C;
            type Output = ();

            fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
            where
                D: DrawTarget<Color = C>,
            {
                let clip = target.bounding_box();
                let (positions, attributes, source) = Blendable::<C, $n>::parts(&self.shape);
                let mut shader = BlendOver {
                    target,
                    background: self.background,
                    source,
                    result: Ok(()),
                };
                shade(positions, &attributes, &clip, &mut shader);
                shader.result
            }
        }
    };
}

translucent_draws!(SolidTriangle, 0);
translucent_draws!(GouraudTriangle, 4);
