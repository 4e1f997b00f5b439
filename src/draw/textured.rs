//! Textured triangles: texel coordinates per vertex, interpolated affinely across the triangle
//! (the raster core's attribute planes) and the texture sampled at each pixel centre.

use core::marker::PhantomData;

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::framebuffer::SliceFramebuffer;
use crate::color::GouraudColor;
use crate::fixed_point::{Coord, ToCoord};
use crate::raster::band::RowWindow;
use crate::raster::plane::Attributes;
use crate::raster::{shade, Span, SpanShader};
use crate::texture::span::{fill_affine, PlaneMap, Sampled, SampledLoop, Sampler, RUN};
use crate::texture::{TexelCoord, TexelSource, Texture, ToTexel};

/// A vertex of a [`TexturedTriangle`]: sub-pixel position and texel coordinate.
///
/// Texel coordinates are in texels of the texture (`(0, 0)` its top-left corner, `(w, h)` its
/// bottom-right; beyond, the texture's [`Wrap`](crate::texture::Wrap) modes apply), any
/// [`TexelCoord`] (±2¹⁵ texels, 1/65536 texel).
///
/// ```
/// use embedded_raster::{Coord, TexturedVertex};
/// use embedded_raster::texture::TexelCoord;
///
/// let v = TexturedVertex::new(10.5, 20.0, 0.0, 31.75);
/// assert_eq!((v.x, v.v), (Coord::from_num(10.5), TexelCoord::from_num(31.75)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct TexturedVertex {
    /// Horizontal position (pixel centres are at `i + 0.5`).
    pub x: Coord,
    /// Vertical position, growing downward.
    pub y: Coord,
    /// Horizontal texel coordinate.
    pub u: TexelCoord,
    /// Vertical texel coordinate, growing downward (the image's rows).
    pub v: TexelCoord,
}

impl TexturedVertex {
    /// A vertex at `(x, y)` reading the texture at `(u, v)`: floats or fixed point
    /// ([`ToCoord`], [`ToTexel`]: rounded, saturated, NaN as 0).
    pub fn new(x: impl ToCoord, y: impl ToCoord, u: impl ToTexel, v: impl ToTexel) -> Self {
        TexturedVertex {
            x: x.to_coord(),
            y: y.to_coord(),
            u: u.to_texel(),
            v: v.to_texel(),
        }
    }

    /// The position as a coordinate pair.
    pub fn position(&self) -> (Coord, Coord) {
        (self.x, self.y)
    }
}

/// A triangle filled with a texture: each pixel whose centre is inside (the pixels a
/// [`SolidTriangle`](crate::SolidTriangle) of the same positions covers) gets the texture
/// sampled at the texel coordinate interpolated there (affine in screen space), by the
/// texture's filter and wrap modes, as a colour `C` (the target's: any [`GouraudColor`] the
/// texels convert to).
///
/// The interpolated coordinate is within `s + 1/128` texel of the exact one on each axis, where
/// `s`, the step of the planes' vertex values, is under the triangle's texel-coordinate spread
/// on that axis (its largest difference between vertices) over 32,639, and 2⁻¹⁶ texel for
/// spreads under a texel: under 1/100 texel for spreads under 64 texels.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::{Rgb565, RgbColor}, prelude::*};
/// use embedded_raster::texture::{Rgb565Texels, Texture};
/// use embedded_raster::{SliceFramebuffer, TexturedTriangle, TexturedVertex};
///
/// // 2 × 2 texels: red, green / blue, white.
/// static TEXELS: [u16; 4] = [0xf800, 0x07e0, 0x001f, 0xffff];
/// let texture = Texture::new(Rgb565Texels(&TEXELS), 2, 2).unwrap();
///
/// let mut pixels = [Rgb565::BLACK; 16 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
/// // The texture over the square's upper-left half, 8 pixels a texel.
/// let v = |x: f32, y: f32| TexturedVertex::new(x, y, x / 8.0, y / 8.0);
/// let triangle = TexturedTriangle::new([v(0.0, 0.0), v(16.0, 0.0), v(0.0, 16.0)], &texture);
/// triangle.draw_into(&mut fb);
/// assert_eq!(fb.get(12, 2), Some(Rgb565::GREEN));
/// assert_eq!(fb.get(2, 12), Some(Rgb565::BLUE));
/// // Through any DrawTarget: the same pixels.
/// triangle.draw(&mut fb)?;
/// # Ok::<(), core::convert::Infallible>(())
/// ```
#[derive(Debug)]
pub struct TexturedTriangle<'t, S, C> {
    /// The three vertices, in either winding.
    pub vertices: [TexturedVertex; 3],
    /// The texture.
    pub texture: &'t Texture<S>,
    _color: PhantomData<C>,
}

impl<S, C> Clone for TexturedTriangle<'_, S, C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S, C> Copy for TexturedTriangle<'_, S, C> {}

impl<'t, S, C> TexturedTriangle<'t, S, C>
where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    /// A triangle through `vertices` (either winding) filled with `texture`.
    pub fn new(vertices: [TexturedVertex; 3], texture: &'t Texture<S>) -> Self {
        TexturedTriangle {
            vertices,
            texture,
            _color: PhantomData,
        }
    }

    /// Draws into a [`SliceFramebuffer`] with slice writes: the same pixels as
    /// [`Drawable::draw`].
    pub fn draw_into(&self, framebuffer: &mut SliceFramebuffer<'_, C>) {
        let clip = framebuffer.bounding_box();
        let (texels, attributes) = Texels::new(self.texture, &self.vertices);
        let mut shader = IntoSlice {
            framebuffer,
            texels,
        };
        shade(self.positions(), &attributes, &clip, &mut shader);
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
        let (texels, attributes) = Texels::new(self.texture, &self.vertices);
        let shader = IntoSlice {
            framebuffer,
            texels,
        };
        window.shade(self.positions(), &attributes, clip, shader);
    }

    /// The vertices' positions.
    #[inline(always)]
    fn positions(&self) -> [(Coord, Coord); 3] {
        self.vertices.map(|v| v.position())
    }
}

impl<S, C> Drawable for TexturedTriangle<'_, S, C>
where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    type Color = C;
    type Output = ();

    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        let clip = target.bounding_box();
        let (texels, attributes) = Texels::new(self.texture, &self.vertices);
        let mut shader = ToTarget {
            target,
            texels,
            result: Ok(()),
        };
        shade(self.positions(), &attributes, &clip, &mut shader);
        shader.result
    }
}

/// What both span shaders share: the texture's sampler and how the two planes map to texel
/// coordinates.
struct Texels<'t, S> {
    sampler: Sampler<'t, S>,
    maps: [PlaneMap; 2],
}

/// A triangle's per-pixel steps: the planes' own (for restarts) and in 16.16 texels.
struct Steps {
    plane: [u32; 2],
    texel: (i32, i32),
}

impl<'t, S: TexelSource> Texels<'t, S> {
    /// The maps of the vertices' texel coordinates and the planes' attributes.
    #[inline(always)]
    fn new(texture: &'t Texture<S>, vertices: &[TexturedVertex; 3]) -> (Self, Attributes<2>) {
        let (mu, u) = PlaneMap::new(vertices.map(|v| v.u.to_bits()));
        let (mv, v) = PlaneMap::new(vertices.map(|v| v.v.to_bits()));
        // Vertex by vertex without indices: a `map` over indices keeps their bounds checks
        // (panic paths) where `opt-level` "s" or "z" does not inline it.
        let ([u0, u1, u2], [v0, v1, v2]) = (u, v);
        let attributes = Attributes {
            values: [[u0, v0], [u1, v1], [u2, v2]],
            // The maps truncate: no rounding offset.
            half: [0; 2],
        };
        let texels = Texels {
            sampler: Sampler::new(texture),
            maps: [mu, mv],
        };
        (texels, attributes)
    }

    #[inline(always)]
    fn prepare(&self, step: [u32; 2]) -> Steps {
        Steps {
            plane: step,
            texel: (self.maps[0].step(step[0]), self.maps[1].step(step[1])),
        }
    }

    /// The first texel coordinate and the per-pixel step of the run of `len` pixels `offset`
    /// pixels into a span whose plane values start at `start` ([`PlaneMap::run`]).
    #[inline(always)]
    fn run(
        &self,
        steps: &Steps,
        start: [u32; 2],
        offset: u32,
        len: u32,
    ) -> ((i32, i32), (i32, i32)) {
        let value = |k: usize| start[k].wrapping_add(steps.plane[k].wrapping_mul(offset));
        let (maps, plane) = (&self.maps, &steps.plane);
        let (x, dx) = maps[0].run(value(0), plane[0], steps.texel.0, len);
        let (y, dy) = maps[1].run(value(1), plane[1], steps.texel.1, len);
        ((x, y), (dx, dy))
    }
}

/// The span shader of [`TexturedTriangle::draw_into`]: the textured span loop into the slice,
/// restarted from the planes every [`RUN`] pixels.
struct IntoSlice<'f, 'a, 't, S, C> {
    framebuffer: &'f mut SliceFramebuffer<'a, C>,
    texels: Texels<'t, S>,
}

impl<S, C> SpanShader<2> for IntoSlice<'_, '_, '_, S, C>
where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    type Steps = Steps;

    scan_small_with_walk_planes!();

    #[inline(always)]
    fn prepare(&mut self, step: [u32; 2]) -> Steps {
        self.texels.prepare(step)
    }

    #[inline(always)]
    fn span(&mut self, steps: &Steps, span: Span, start: [u32; 2]) {
        let Some(row) = self
            .framebuffer
            .clipped_span_mut(span.y, span.x_start, span.x_end)
        else {
            return;
        };
        if span.len() <= RUN {
            let (at, step) = self.texels.run(steps, start, 0, span.len());
            fill_affine(row, &self.texels.sampler, at, step);
            return;
        }
        let mut offset = 0;
        for run in row.chunks_mut(RUN as usize) {
            let (at, step) = self.texels.run(steps, start, offset, run.len() as u32);
            fill_affine(run, &self.texels.sampler, at, step);
            offset += RUN;
        }
    }
}

/// The span shader of [`TexturedTriangle`]'s [`Drawable::draw`]: one `fill_contiguous` a run
/// of at most [`RUN`] pixels. After an error it has [stopped](SpanShader::stopped): the walk
/// ends there.
struct ToTarget<'d, 't, D: DrawTarget, S> {
    target: &'d mut D,
    texels: Texels<'t, S>,
    result: Result<(), D::Error>,
}

impl<D, S> SpanShader<2> for ToTarget<'_, '_, D, S>
where
    S: TexelSource,
    D: DrawTarget,
    D::Color: GouraudColor + From<S::Color>,
{
    type Steps = Steps;

    #[inline(always)]
    fn prepare(&mut self, step: [u32; 2]) -> Steps {
        self.texels.prepare(step)
    }

    #[inline(always)]
    fn span(&mut self, steps: &Steps, span: Span, start: [u32; 2]) {
        let mut offset = 0;
        while offset < span.len() && self.result.is_ok() {
            let len = (span.len() - offset).min(RUN);
            // Inside the span: no overflow.
            let x = span.x_start.wrapping_add(offset as i32);
            let (at, step) = self.texels.run(steps, start, offset, len);
            let run = Contiguous {
                target: &mut *self.target,
                area: Rectangle::new(Point::new(x, span.y), Size::new(len, 1)),
                at,
                step,
            };
            self.result = self.texels.sampler.run(run);
            offset += len;
        }
    }

    #[inline(always)]
    fn stopped(&self) -> bool {
        self.result.is_err()
    }
}

/// One `fill_contiguous` of a run's sampled texels.
struct Contiguous<'d, D> {
    target: &'d mut D,
    area: Rectangle,
    at: (i32, i32),
    step: (i32, i32),
}

impl<D: DrawTarget> SampledLoop<D::Color> for Contiguous<'_, D> {
    type Output = Result<(), D::Error>;

    #[inline(always)]
    fn run<T: Sampled<D::Color>>(
        self,
        sample: impl Fn(i32, i32) -> T,
        y_shift: u32,
    ) -> Self::Output {
        let (mut x, dx) = (self.at.0, self.step.0);
        let (mut y, dy) = (self.at.1 << y_shift, self.step.1 << y_shift);
        let colors = (0..self.area.size.width).map(|_| {
            let color = sample(x, y).color();
            x = x.wrapping_add(dx);
            y = y.wrapping_add(dy);
            color
        });
        self.target.fill_contiguous(&self.area, colors)
    }
}

#[cfg(test)]
mod tests {
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::Pixel;

    use super::*;
    use crate::raster::Counting;
    use crate::texture::Rgb565Texels;

    /// A target over 10⁹ pixels a side that fails every call, counting them.
    struct Failing {
        calls: u32,
    }

    impl Dimensions for Failing {
        fn bounding_box(&self) -> Rectangle {
            Rectangle::new(
                Point::new(-600_000_000, -700_000_000),
                Size::new(1_200_000_000, 1_400_000_000),
            )
        }
    }

    impl DrawTarget for Failing {
        type Color = Rgb565;
        type Error = u32;

        fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, _: I) -> Result<(), u32> {
            self.calls += 1;
            Err(self.calls)
        }
    }

    /// After the target's first error `draw`'s shader has stopped and the walk hands it no
    /// further span (issue #32, item 11): a triangle across the whole `Coord` range (its first
    /// span alone is 4,096 runs) and a small one; the spans counted as the walk hands them over.
    #[test]
    fn a_failed_draw_walks_no_further() {
        const FAR: i32 = (1 << 23) - 1;
        static TEXELS: [u16; 4] = [0xf800, 0x07e0, 0x001f, 0xffff];
        let texture = Texture::new(Rgb565Texels(&TEXELS), 2, 2).unwrap();
        let v = |x: i32, y: i32| {
            let (x, y) = (x as f32, y as f32);
            TexturedVertex::new(x, y, x / 1000.0, y / 1000.0)
        };
        for vertices in [
            [v(-FAR, -FAR), v(FAR, -FAR), v(0, FAR)],
            [v(1, 1), v(60, 5), v(10, 50)],
        ] {
            let triangle: TexturedTriangle<'_, _, Rgb565> =
                TexturedTriangle::new(vertices, &texture);
            let mut target = Failing { calls: 0 };
            let clip = target.bounding_box();
            let (texels, attributes) = Texels::new(&texture, &vertices);
            let shader = ToTarget {
                target: &mut target,
                texels,
                result: Ok(()),
            };
            let mut counting = Counting::new(shader);
            shade(triangle.positions(), &attributes, &clip, &mut counting);
            assert_eq!(counting.shader.result, Err(1));
            assert_eq!(counting.handed, 1);
            assert_eq!(target.calls, 1);
        }
    }
}
