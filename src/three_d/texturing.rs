//! Textured, depth-tested fills with perspective-correct texel coordinates.
//!
//! The raster core interpolates the depth and the three perspective planes
//! ([`perspective`](crate::raster::perspective): `q ∝ 1/w` and the barycentrics times `q`);
//! along each span the texel coordinates are computed exactly at the ends of chunks of up to
//! 16 pixels and at the span's last pixel (one reciprocal each) and stepped in 16.16 texels
//! between. The depth test and the texture's sampling are in the span loop.
//!
//! # Accuracy
//!
//! At the pixels where they are computed, the texel coordinates are within
//! `δ·(spread) + 2⁻¹⁶` texel of the exact perspective-correct ones, where `spread` is the largest
//! difference of the vertices' texel coordinates and `δ`, the error of the perspective
//! barycentrics, is about `1/q_min + 2⁻¹⁵` (see [`perspective`](crate::raster::perspective):
//! `6·10⁻⁴` for vertex depths in a ratio of 1:20). Between them the coordinates follow the chord,
//! off the true curve by at most `L²/4 · |X′| · |q′|/q` for chunks of `L ≤ 16` pixels (`X′` the
//! coordinate's rate and `q′/q` the relative change of `1/w` a pixel): with `L = 16`, below
//! 1/16 texel where `|X′|·|q′/q|` is under 1/1024 (a texel a pixel where `w` changes by under a
//! thousandth of itself a pixel); more on a floor seen at a grazing angle (measured: 0.4 texel
//! at most on the tests' grazing floors, several texels where a face reaches the near plane,
//! whose chords are long in texels).
//!
//! Light levels (and tints, highlights) are computed and stepped the same way, and the chunks
//! are short enough for their chords to stay within a quarter of the target's finest channel
//! step of the exact levels: each chunk is the longest power of two up to 16 pixels for which
//! the chord bound `L²·|K|·|dq| / (4·q_min³)` (`K = ℓ′·q²`, constant along a span) holds
//! ([`chunk_shift`](crate::raster::perspective), sixteenth-logarithms, no division; on ARMv6-M
//! the same lengths from thresholds found once a span), and lies
//! inside an aligned chunk of 16 (so the coordinates' chords are never longer than with chunks
//! of 16). So every colour is within 1 LSB of the texel times the exact perspective-correct
//! level (tested in `tests/all/perspective.rs` on random faces whose `w` changes by 1:20 across a
//! few pixels, where chords of 16 pixels would be up to 58 LSB off, and on grazing floors:
//! within 0.65 LSB). Steep faces pay for it with shorter chunks (`fw_texture_bench`'s lit
//! triangles, `w` 1:3 across 128 pixels: chords of 16 would be 2.1 levels off, chunks of 8).
//!
//! A face whose `1/w` varies so little across it that screen-space interpolation departs from
//! the perspective-correct values by at most 1/16 texel and a quarter of the target's finest
//! channel step in light level (its spread times `(q_max − q_min) / 4q_min`; a quarter of a
//! level of 255 for 8-bit channels, one level for Rgb565's 6-bit green: most faces of a mesh)
//! takes the 2D textured fill's planes
//! instead, with their own rounding (`s + 1/128` texel, see
//! [`TexturedTriangle`](crate::TexturedTriangle)) on top: no division in its spans.
//!
//! # Per-pixel light (quadratic shading)
//!
//! A [`TexturedMaterial`] with [`Shading::Quadratic`](super::Shading) is lit per pixel, as
//! [`draw_quadratic`](super::draw_quadratic) lights an untextured face, but perspective-correct:
//! the quadratic normal field `N(c) = Σ Nᵢcᵢ(2cᵢ − 1) + Σ 4N̂ᵢⱼcᵢcⱼ` is written once a face as a
//! polynomial in its perspective barycentrics `λ₁`, `λ₂` (`PixelLight`: six coefficients a
//! component, 16 fractional bits) and is evaluated at the barycentrics the perspective fill
//! computes at each chunk's ends (every 16 pixels and the span's last, the same `Chunks` as the
//! texel coordinates). Between them the barycentrics follow their chord (stepped linearly, as
//! the texel coordinates are) and the field, quadratic along that chord, is stepped by forward
//! differences (28 fractional bits, 32-bit operands with 64-bit products once a chunk; two
//! additions a component and pixel): exactly the field at the chord's barycentrics, up to the
//! differences' rounding (below 2⁻¹⁹ after 16 pixels). Each pixel's normal, rounded to 16
//! fractional bits, is renormalised with [`inv_sqrt`](super::inv_sqrt) (no division, no float)
//! for Lambert's `n̂·l` and, with a [`Specular`](super::Specular), Blinn-Phong's `n̂·ĥ` (each
//! within about 2⁻¹⁵, as the untextured quadratic highlight); the colour is `texel · level +
//! specular · max`, rounded once and saturating. Such a draw takes the perspective fill for
//! every face (no screen-space planes: the field is not linear in the barycentrics).
//!
//! So the normal departs from the exact field at the exact barycentrics only by the
//! barycentrics' own error: `δ` (above) at the chunk ends, plus the chord's departure between
//! them (`L²/4 · |λ′| · |q′|/q`, the texel coordinates' bound with a barycentric as the
//! attribute). Measured against the f64 per-pixel evaluation (`tests/all/textured_mesh.rs`,
//! `quadratic_texels_are_lit_per_pixel`, Rgb888, each pixel's tolerance from those bounds): on
//! grazing floors with curved normals at most 0.98 LSB (per vertex: up to 115 LSB, beyond the
//! tolerance at 98 % of the pixels); on faces whose highlight lies inside them (shininess 24 to
//! 40) at most 2.2 LSB (per vertex: up to 211 LSB); on the suite's meshes under random lights
//! and highlights (shininess 1 to 48; clipped faces drawn as fans, the field restricted to each
//! triangle) 1.1 LSB where the tolerance is at most 2 LSB and 1.5 % of the channels more than
//! 1 LSB off, but up to 9.2 LSB where the barycentrics' bound is wide (long chords of faces
//! whose `w` changes fast, sharp highlights: other random draws gave 12.5 LSB, and 109 LSB
//! against a tolerance of 110). Evaluating the field at
//! the chunk ends alone and stepping it linearly between (cheaper: no second difference)
//! measured twice the error (1.9 LSB on the floors, 6.0 inside the faces).
//!
//! Per-pixel light takes the pipeline's [`Light`](super::Light) and its
//! [`Lights`](super::Lights) (with the material's highlight for each, about its half vector):
//! directional lights per pixel, as the first; a point light with its direction, half vector
//! and falloff taken once a face at the face's centroid (an approximation where a face is large
//! beside its distance to the light), applied per pixel with the pixel's normal. The levels
//! and the highlights add up, each saturating at 1, as per vertex. Measured with two more
//! directional lights on the domed floors: at most 1.4 LSB off the f64 per-pixel reference. A
//! material taking the mesh's vertex colours (where the mesh has them) is lit per vertex as
//! [`Shading::Gouraud`](super::Shading) instead. A [`Solid`](crate::texture::Solid) texture
//! gives untextured meshes the same per-pixel light.

use embedded_graphics::primitives::Rectangle;

use super::depth::{DepthTarget, ScreenVertex};
use super::light::{Highlight, Light, Lights, PixelSource, Specular};
use super::math::Vec3;
use super::math::{zip3_with, Scalar};
use super::mesh::TexCoord;
use super::shading::{
    highlighted_channels, pixel_terms, with_depth, QuadraticNormals, TargetClip, DEPTH_SHIFT,
};
use super::vertex::{Inverse, ProjectedVertex};
use crate::arch::{self, TexturedDraw, SIZE_OVER_SPEED};
use crate::color::GouraudColor;
use crate::raster::arith::mul_i32_wide;
use crate::raster::band::RowWindow;
use crate::raster::perspective::{self, step_over, Chunks, Corrected, Lambda};
use crate::raster::runs::SmallScan;
use crate::raster::{Span, SpanShader};
use crate::texture::span::{PlaneMap, Sampled, SampledLoop, Sampler};
use crate::texture::{TexelCoord, TexelSource, Texture};

/// A vertex of a perspective-correct textured fill: its screen position and depth, its
/// clip-space `w` (the view depth of a perspective projection: positive) and its texel
/// coordinate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct TexturedScreenVertex {
    /// Sub-pixel position and 16-bit depth.
    pub screen: ScreenVertex,
    /// Clip-space `w`; values of 0 or below are taken as the smallest positive one.
    pub w: Scalar,
    /// Horizontal texel coordinate (texels; `0` the texture's left edge).
    pub u: TexelCoord,
    /// Vertical texel coordinate (texels, down; `0` the texture's top row).
    pub v: TexelCoord,
}

/// Fills the triangle with `texture`, perspective-correct, depth-tested (a pixel is written
/// only where it is strictly nearer than the z-buffer), inside `clip` (any `Rectangle`) and the
/// target: the pixels [`draw_flat`](super::draw_flat) covers, each the texture sampled by its
/// filter and wrap modes at the texel coordinate there.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::{Rgb565, RgbColor}, prelude::*, primitives::Rectangle};
/// use embedded_raster::texture::{Rgb565Texels, TexelCoord, Texture};
/// use embedded_raster::three_d::{draw_textured, DepthTarget, Scalar, ScreenVertex, TexturedScreenVertex};
/// use embedded_raster::Coord;
///
/// static TEXELS: [u16; 4] = [0xf800, 0x07e0, 0x001f, 0xffff];
/// let texture = Texture::new(Rgb565Texels(&TEXELS), 2, 2).unwrap();
/// let (mut px, mut z) = ([Rgb565::BLACK; 16 * 16], [0u16; 16 * 16]);
/// let mut target = DepthTarget::new(&mut px, &mut z, 16, 16).unwrap();
/// // A square's upper-left half leaning away: its right vertex three times as far.
/// let v = |x: i32, y: i32, w: i32, u: i32, t: i32| TexturedScreenVertex {
///     screen: ScreenVertex::new(Coord::from_num(x), Coord::from_num(y), 100),
///     w: Scalar::from_num(w),
///     u: TexelCoord::from_num(u),
///     v: TexelCoord::from_num(t),
/// };
/// let clip = Rectangle::new(Point::zero(), Size::new(16, 16));
/// draw_textured(&mut target, &clip, &[v(0, 0, 1, 0, 0), v(16, 0, 3, 2, 0), v(0, 16, 1, 0, 2)], &texture);
/// // Halfway across on screen is a quarter of the way across the texture: still red.
/// assert_eq!(target.framebuffer().get(8, 0), Some(Rgb565::RED));
/// assert_eq!(target.framebuffer().get(14, 0), Some(Rgb565::GREEN));
/// ```
// Inlined: a thin wrapper whose frame would add to the fill's (stack on a micro:bit).
#[inline(always)]
pub fn draw_textured<S, C>(
    target: &mut DepthTarget<'_, C>,
    clip: &Rectangle,
    vertices: &[TexturedScreenVertex; 3],
    texture: &Texture<S>,
) where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    let clip = TargetClip::new(clip, target);
    let q = vertices.map(|v| Inverse::of(inverse_w(v.w)));
    let texels = vertices.map(|v| [v.u.to_bits(), v.v.to_bits()]);
    let screen = vertices.each_ref().map(|v| &v.screen);
    let palette = palette_565::<S, C>(texture);
    fill_textured(
        target,
        &clip,
        screen,
        q,
        texels,
        Sampler::new(texture),
        palette.as_ref(),
        Opaque,
        TexelLight::Full,
        None,
    );
}

/// [`draw_textured`] with each texel lit: scaled channel by channel by a light level that
/// `levels` gives at the vertices (0 black, 255 the texel as it is), interpolated
/// perspective-correct like the texel coordinates (texture × Gouraud light, as the 3D
/// pipeline lights a [`TexturedMaterial`] with [`Shading::Gouraud`](super::Shading::Gouraud)).
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::{Rgb565, RgbColor}, prelude::*, primitives::Rectangle};
/// use embedded_raster::texture::{Rgb565Texels, TexelCoord, Texture};
/// use embedded_raster::three_d::{draw_textured_lit, DepthTarget, Scalar, ScreenVertex, TexturedScreenVertex};
/// use embedded_raster::Coord;
///
/// static WHITE: [u16; 1] = [0xffff];
/// let texture = Texture::new(Rgb565Texels(&WHITE), 1, 1).unwrap();
/// let (mut px, mut z) = ([Rgb565::BLACK; 16 * 16], [u16::MAX; 16 * 16]);
/// let mut target = DepthTarget::new(&mut px, &mut z, 16, 16).unwrap();
/// let v = |x: i32, y: i32| TexturedScreenVertex {
///     screen: ScreenVertex::new(Coord::from_num(x), Coord::from_num(y), 100),
///     w: Scalar::from_num(1),
///     u: TexelCoord::from_num(0),
///     v: TexelCoord::from_num(0),
/// };
/// let clip = Rectangle::new(Point::zero(), Size::new(16, 16));
/// // Full light along the left edge, none at the right vertex.
/// draw_textured_lit(&mut target, &clip, &[v(0, 0), v(16, 0), v(0, 16)], &texture, [255, 0, 255]);
/// let green = |x: i32| target.framebuffer().get(x, 1).unwrap().g();
/// assert!(green(1) > 55 && green(12) < 20);
/// ```
// Inlined: a thin wrapper whose frame would add to the fill's (stack on a micro:bit).
#[inline(always)]
pub fn draw_textured_lit<S, C>(
    target: &mut DepthTarget<'_, C>,
    clip: &Rectangle,
    vertices: &[TexturedScreenVertex; 3],
    texture: &Texture<S>,
    levels: [u8; 3],
) where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    let clip = TargetClip::new(clip, target);
    let q = vertices.map(|v| Inverse::of(inverse_w(v.w)));
    let texels = vertices.map(|v| [v.u.to_bits(), v.v.to_bits()]);
    let screen = vertices.each_ref().map(|v| &v.screen);
    // 8.8 levels: 255 is 255 · 256, the full fraction.
    let levels = levels.map(|l| u16::from(l) << 8);
    let palette = palette_565::<S, C>(texture);
    fill_textured(
        target,
        &clip,
        screen,
        q,
        texels,
        Sampler::new(texture),
        palette.as_ref(),
        Opaque,
        TexelLight::Levels(levels),
        None,
    );
}

/// The raw Rgb565 words of the 16 colours a 4-bit palette texture's indices name (its
/// palette's, the first's for an index past its end, as [`Indexed4`](crate::texture::Indexed4)
/// reads them) as `C` has them, where `C` is a 5-6-5 colour and the target's row loop looks
/// indices up (ARMv7-M); `None` elsewhere.
#[inline(always)]
fn palette_565<S, C>(texture: &Texture<S>) -> Option<[u16; 16]>
where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    if !arch::TEXTURED_FACE || C::MAX != [31, 63, 31] {
        return None;
    }
    let (_, palette) = texture.source().palette4()?;
    let first = *palette.first()?;
    Some(core::array::from_fn(|i| {
        let [r, g, b] = C::from(*palette.get(i).unwrap_or(&first)).channels();
        u16::from(r) << 11 | u16::from(g) << 5 | u16::from(b)
    }))
}

/// `2⁴⁷ / w` (of the raw `I16F16` bits, at least 1): a `q` for the perspective planes.
fn inverse_w(w: Scalar) -> u64 {
    let w = u64::try_from(w.to_bits()).unwrap_or(0).max(1);
    (1u64 << 47) / w
}

/// How the light modulates a textured face's texels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum TexelLight<'p> {
    /// Not at all: the texels as they are.
    Full,
    /// By one level for the face (8.8 of the 0–255 scale).
    Level(u16),
    /// By the vertices' levels (8.8 of the 0–255 scale), interpolated perspective-correct.
    Levels([u16; 3]),
    /// Channel by channel by the vertices' tints (each channel 8.8 of the 0–255 scale: a
    /// vertex colour times its light level), interpolated perspective-correct.
    Tints([[u16; 3]; 3]),
    /// By the vertices' tints, plus their specular terms (8.8 of the 0–255 scale) as white
    /// light, saturating; both interpolated perspective-correct.
    Shiny {
        /// Each vertex's tints.
        tints: [[u16; 3]; 3],
        /// Each vertex's specular term.
        speculars: [u16; 3],
    },
    /// Per pixel: the face's quadratic normal field, evaluated at the perspective-correct
    /// barycentrics, lit by one light (and a highlight); always interpolated perspective-correct.
    Quadratic(&'p PixelLight),
}

/// A texture a frame draws its faces with: none (a material's colour), or a texture of some
/// texel source (a textured material's).
pub(crate) trait FaceTexture<C>: Copy {
    /// Whether there is a texture: its draws' vertices keep their reciprocal `w`.
    const TEXTURED: bool = true;

    /// The texture's width and height (a mesh's normalised texture coordinates are scaled by
    /// them).
    fn size(&self) -> (u32, u32);

    /// Fills the face of `vertices` with their `q ∝ 1/w` and 16.16 texel coordinates, lit by
    /// `light`; `set_up` is what [`fill_small`](Self::fill_small) did with it if it was offered
    /// there (then not again).
    #[allow(clippy::too_many_arguments)]
    fn fill<R: RowWindow>(
        &self,
        target: &mut DepthTarget<'_, C>,
        clip: &TargetClip<R>,
        vertices: [&ScreenVertex; 3],
        q: [Inverse; 3],
        texels: [[i32; 2]; 3],
        light: TexelLight<'_>,
        set_up: Option<TexturedDraw>,
    );

    /// Whether [`fill_small`](Self::fill_small) may draw a face (the target has a set-up for
    /// this texture and colour); none where there is no such set-up (the default).
    #[inline(always)]
    fn sets_up_small(&self) -> bool {
        false
    }

    /// The same texture for a draw inside `clip` (a band's rows of the draw).
    #[inline(always)]
    fn clipped<R: RowWindow>(&self, clip: &TargetClip<R>) -> Self {
        let _ = clip;
        *self
    }

    /// Sets up and draws the face of `vertices` (their levels if `lit`, else unlit) with 16.16
    /// texel coordinates `texels` by the target's own code with the draw's template, if the
    /// target has it and the face is small: what [`fill`](Self::fill)'s first step does, without
    /// building the face's light. Declined where there is none (the default).
    #[inline(always)]
    fn fill_small(
        &self,
        target: &mut DepthTarget<'_, C>,
        vertices: [&ProjectedVertex; 3],
        texels: [[i32; 2]; 3],
        lit: bool,
    ) -> TexturedDraw {
        let _ = (target, vertices, texels, lit);
        TexturedDraw::Declined
    }

    /// The draw's textured faces into `target` for the target's face scan: faces of a mesh with
    /// the texture coordinates `uvs`, each offered to the set-up as
    /// [`fill_small`](Self::fill_small) offers it (lit if `lit`), if the target has one for this
    /// texture; none where it has none (the default).
    #[inline(always)]
    fn scan_faces<'s>(
        &'s self,
        target: &mut DepthTarget<'_, C>,
        uvs: &'s [TexCoord],
        lit: bool,
    ) -> Option<arch::TexturedFaces<'s>> {
        let _ = (target, uvs, lit);
        None
    }
}

/// No texture: the draws of a [`Material`](super::Material) (the default texture type of a
/// `band::MeshBin`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct NoTexture;

impl<C> FaceTexture<C> for NoTexture {
    const TEXTURED: bool = false;

    fn size(&self) -> (u32, u32) {
        (0, 0)
    }

    fn fill<R: RowWindow>(
        &self,
        _: &mut DepthTarget<'_, C>,
        _: &TargetClip<R>,
        _: [&ScreenVertex; 3],
        _: [Inverse; 3],
        _: [[i32; 2]; 3],
        _: TexelLight<'_>,
        _: Option<TexturedDraw>,
    ) {
    }
}

/// A textured draw's texture and its sampler, decided once a draw: the texture type of a
/// `band::MeshBin` of a [`TexturedMaterial`] reading texels of `S` (`MeshBin::new_textured`).
#[derive(Debug, Clone, Copy)]
pub struct FrameTexture<'t, S, W = Opaque> {
    size: (u32, u32),
    sampler: Sampler<'t, S>,
    /// A 4-bit palette texture's colours as the target's row loop looks them up, if it does.
    palette: Option<[u16; 16]>,
    /// What the draw's faces have in common for the target's face set-up, if it has one for
    /// this texture and `C` ([`FaceTexture::fill_small`]).
    face: Option<arch::TemplateSlot>,
    write: W,
}

impl<'t, S: TexelSource, W: Opacity> FrameTexture<'t, S, W> {
    /// The texture of a draw into `C` inside `clip`, its texels written as `write` says.
    pub(crate) fn new<C, R: RowWindow>(
        texture: &'t Texture<S>,
        write: W,
        clip: &TargetClip<R>,
    ) -> Self
    where
        C: GouraudColor + From<S::Color>,
    {
        let sampler = Sampler::new(texture);
        let palette = palette_565::<S, C>(texture);
        // Opaque draws of texels the set-up reads (the words, or indices with their palette).
        let words = face_words(&sampler, palette.as_ref()).is_some();
        let face = face_masks(&sampler)
            .filter(|_| arch::TEXTURED_FACE && !W::BLENDS && words)
            .and_then(|masks| {
                arch::template_slot(clip.textured_template(masks, affine_level::<C>() as u32))
            });
        FrameTexture {
            size: (texture.width(), texture.height()),
            sampler,
            palette,
            face,
            write,
        }
    }
}

impl<S, C, W> FaceTexture<C> for FrameTexture<'_, S, W>
where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
    W: Opacity,
{
    #[inline(always)]
    fn size(&self) -> (u32, u32) {
        self.size
    }

    #[inline(always)]
    fn fill<R: RowWindow>(
        &self,
        target: &mut DepthTarget<'_, C>,
        clip: &TargetClip<R>,
        vertices: [&ScreenVertex; 3],
        q: [Inverse; 3],
        texels: [[i32; 2]; 3],
        light: TexelLight<'_>,
        set_up: Option<TexturedDraw>,
    ) {
        fill_textured(
            target,
            clip,
            vertices,
            q,
            texels,
            self.sampler,
            self.palette.as_ref(),
            self.write,
            light,
            set_up,
        );
    }

    #[inline(always)]
    fn sets_up_small(&self) -> bool {
        self.face.is_some()
    }

    #[inline(always)]
    fn clipped<R: RowWindow>(&self, clip: &TargetClip<R>) -> Self {
        FrameTexture {
            face: self.face.as_ref().and_then(|slot| {
                arch::template_slot(clip.textured_reclipped(arch::slot_template(slot)))
            }),
            ..*self
        }
    }

    #[inline(always)]
    fn fill_small(
        &self,
        target: &mut DepthTarget<'_, C>,
        vertices: [&ProjectedVertex; 3],
        texels: [[i32; 2]; 3],
        lit: bool,
    ) -> TexturedDraw {
        let words = face_words(&self.sampler, self.palette.as_ref());
        let (Some(slot), Some(words)) = (&self.face, words) else {
            return TexturedDraw::Declined;
        };
        let template = arch::slot_template(slot);
        let face = template.face(vertices, &texels, words, lit);
        C::textured_face_565(target.buffers_mut(), face)
    }

    #[inline(always)]
    fn scan_faces<'s>(
        &'s self,
        target: &mut DepthTarget<'_, C>,
        uvs: &'s [TexCoord],
        lit: bool,
    ) -> Option<arch::TexturedFaces<'s>> {
        let words = face_words(&self.sampler, self.palette.as_ref())?;
        let template = arch::slot_template(self.face.as_ref()?);
        let faces = arch::TexturedFaces::new(template.faces(words, lit), uvs, self.size, lit)?;
        C::textured_faces_565(target.buffers_mut(), faces)
    }
}

mod sealed {
    /// Only this crate's opacities.
    pub trait Sealed {}
}

/// How a [`TexturedMaterial`] writes its texels, by its type: [`Opaque`] (colour and depth, the
/// default) or [`Blended`] ([`TexturedMaterial::with_opacity`]: the lit texel blended over the
/// pixel, depth tested and not written). A draw of an opaque material has no code for blending.
pub trait Opacity: Copy + core::fmt::Debug + sealed::Sealed {
    /// Whether the texels are blended.
    #[doc(hidden)]
    const BLENDS: bool;

    /// The opacity the texels are blended at (255 for [`Opaque`]).
    fn opacity(self) -> u8;
}

/// Opaque texels: a [`TexturedMaterial`]'s default [`Opacity`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Opaque;

impl sealed::Sealed for Opaque {}

impl Opacity for Opaque {
    const BLENDS: bool = false;

    fn opacity(self) -> u8 {
        255
    }
}

/// Texels blended at an opacity: the [`Opacity`] of [`TexturedMaterial::with_opacity`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Blended(u8);

impl sealed::Sealed for Blended {}

impl Opacity for Blended {
    const BLENDS: bool = true;

    fn opacity(self) -> u8 {
        self.0
    }
}

/// A textured material: the texture a mesh's texture coordinates read and how the light
/// modulates its texels ([`Shading::Unlit`](super::Shading): not at all; `Flat`: one level a
/// face; `Gouraud`: the vertex levels interpolated perspective-correct; `Quadratic`: per pixel,
/// the quadratic normal field at the perspective-correct barycentrics with Lambert and
/// Blinn-Phong per pixel, for the pipeline's light and [`Lights`](super::Lights) — per vertex,
/// as `Gouraud`, with vertex colours), and whether the mesh's vertex colours tint them
/// ([`with_vertex_colors`](Self::with_vertex_colors)).
///
/// A pixel's colour is `texel · light`, or with vertex colours `texel · colour · light`
/// channel by channel (the colour and the light level both interpolated perspective-correct,
/// as one tint a channel); a mesh without colours draws as without them.
#[derive(Debug)]
pub struct TexturedMaterial<'t, S, W = Opaque> {
    /// The texture.
    pub texture: &'t Texture<S>,
    /// How the texels are lit.
    pub shading: super::Shading,
    /// Whether the mesh's vertex colours ([`Mesh::colors`](super::Mesh)) tint the texels.
    pub vertex_colors: bool,
    /// A Blinn-Phong highlight added to the lit texel as white light (flat: per face; Gouraud:
    /// per vertex, interpolated perspective-correct; quadratic: per pixel, or per vertex where
    /// quadratic shading is; none unlit), or none.
    pub specular: Option<super::Specular>,
    /// How the texels are written: [`Opaque`], or [`Blended`] at an opacity
    /// ([`with_opacity`](Self::with_opacity)).
    pub opacity: W,
}

impl<S, W: Copy> Clone for TexturedMaterial<'_, S, W> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S, W: Copy> Copy for TexturedMaterial<'_, S, W> {}

impl<'t, S> TexturedMaterial<'t, S> {
    /// The material of `texture` lit with `shading`, without vertex colours.
    pub const fn new(texture: &'t Texture<S>, shading: super::Shading) -> Self {
        TexturedMaterial {
            texture,
            shading,
            vertex_colors: false,
            specular: None,
            opacity: Opaque,
        }
    }
}

impl<'t, S, W: Opacity> TexturedMaterial<'t, S, W> {
    /// The same material translucent: its lit texels blended over the pixels at `opacity` (0
    /// transparent … 255), depth-tested without writing depth, as a
    /// [`Material`](super::Material)'s [`opacity`](super::Material::opacity) below 255 (here
    /// at 255 too: the type decides, so that opaque draws carry no blending code). Draw it after
    /// the opaque meshes, the farthest first.
    ///
    /// ```
    /// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
    /// use embedded_raster::texture::{Rgb565Texels, Texture};
    /// use embedded_raster::three_d::meshes::icosphere::ICOSPHERE;
    /// use embedded_raster::three_d::{Angle, DepthTarget, Light, Mat4, Pipeline, Shading};
    /// use embedded_raster::three_d::{TexturedMaterial, Vec3};
    /// use embedded_raster::GouraudColor;
    ///
    /// static WHITE: [u16; 1] = [0xffff];
    /// let texture = Texture::new(Rgb565Texels(&WHITE), 1, 1).unwrap();
    /// let (mut pixels, mut depth) = ([Rgb565::BLUE; 32 * 32], [0u16; 32 * 32]);
    /// let mut target = DepthTarget::new(&mut pixels, &mut depth, 32, 32).unwrap();
    /// let camera = Mat4::perspective(Angle::from_degrees(60), 1, 0.5, 20).unwrap()
    ///     * Mat4::translation(Vec3::new(0, 0, -3));
    /// let viewport = Rectangle::new(Point::zero(), Size::new(32, 32));
    /// let pipeline = Pipeline::new(Mat4::IDENTITY, camera, viewport, Light::default());
    /// let glass = TexturedMaterial::new(&texture, Shading::Unlit).with_opacity(128);
    /// pipeline.draw_textured_mesh(&ICOSPHERE, &glass, &mut target);
    /// assert_eq!(target.framebuffer().get(16, 16), Some(Rgb565::WHITE.blend(Rgb565::BLUE, 128)));
    /// assert_eq!(target.depth_at(16, 16), Some(u16::MAX)); // not written
    /// ```
    pub const fn with_opacity(self, opacity: u8) -> TexturedMaterial<'t, S, Blended> {
        TexturedMaterial {
            texture: self.texture,
            shading: self.shading,
            vertex_colors: self.vertex_colors,
            specular: self.specular,
            opacity: Blended(opacity),
        }
    }

    /// The same material with a highlight: `texel · light + specular · max` in every channel
    /// (the highlight white, saturating), as a [`Material`](super::Material)'s.
    pub const fn with_specular(self, specular: super::Specular) -> Self {
        TexturedMaterial {
            specular: Some(specular),
            ..self
        }
    }

    /// The same material with its texels tinted by the mesh's vertex colours: a pixel is
    /// `texel · colour · light`, channel by channel (white where the mesh has no colours).
    ///
    /// # Examples
    ///
    /// ```
    /// use embedded_graphics::{pixelcolor::{Rgb565, Rgb888, RgbColor}, prelude::*, primitives::Rectangle};
    /// use embedded_raster::texture::{Rgb565Texels, Texture};
    /// use embedded_raster::three_d::{DepthTarget, Light, Mat4, Mesh, Pipeline, Shading};
    /// use embedded_raster::three_d::{TexCoord, TexturedMaterial, Vec3};
    ///
    /// // A white texture on a square facing the camera, its vertices red and blue.
    /// static TEXELS: [u16; 1] = [0xffff];
    /// let texture = Texture::new(Rgb565Texels(&TEXELS), 1, 1).unwrap();
    /// let v = |x: f32, y: f32| Vec3::new(x, y, 0.0);
    /// let vertices = [v(-1.0, -1.0), v(1.0, -1.0), v(1.0, 1.0), v(-1.0, 1.0)];
    /// let colors = [Rgb888::RED, Rgb888::RED, Rgb888::BLUE, Rgb888::BLUE];
    /// let uvs = [TexCoord::new(0.0, 0.0); 4];
    /// let indices = [[0, 1, 2], [0, 2, 3]];
    /// let mesh = Mesh::new(&vertices, &[], &indices).with_colors(&colors).with_uvs(&uvs);
    /// let viewport = Rectangle::new(Point::zero(), Size::new(16, 16));
    /// let pipeline = Pipeline::new(Mat4::IDENTITY, Mat4::IDENTITY, viewport, Light::default());
    /// let material = TexturedMaterial::new(&texture, Shading::Unlit).with_vertex_colors();
    /// let (mut px, mut z) = ([Rgb565::BLACK; 16 * 16], [0u16; 16 * 16]);
    /// let mut target = DepthTarget::new(&mut px, &mut z, 16, 16).unwrap();
    /// target.clear(Rgb565::BLACK);
    /// pipeline.draw_textured_mesh(&mesh, &material, &mut target);
    /// // Red at the bottom (y is up in clip space), blue at the top, blended between.
    /// let (bottom, top) = (target.framebuffer().get(8, 15).unwrap(), target.framebuffer().get(8, 0).unwrap());
    /// assert!(bottom.r() >= 29 && bottom.b() <= 2 && top.b() >= 29 && top.r() <= 2);
    /// let middle = target.framebuffer().get(8, 8).unwrap();
    /// assert!((13..=17).contains(&middle.r()) && (13..=17).contains(&middle.b()));
    /// ```
    pub const fn with_vertex_colors(self) -> Self {
        TexturedMaterial {
            vertex_colors: true,
            ..self
        }
    }
}

/// [`draw_textured`] inside a clip already within the target, with the vertices' `q ∝ 1/w`
/// and 16.16 texel coordinates, lit by `light`.
#[allow(clippy::too_many_arguments)]
#[cfg_attr(not(armv6m), inline(always))]
pub(crate) fn fill_textured<S, C, R: RowWindow, W: Opacity>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    screen: [&ScreenVertex; 3],
    q: [Inverse; 3],
    texels: [[i32; 2]; 3],
    sampler: Sampler<'_, S>,
    palette: Option<&[u16; 16]>,
    write: W,
    light: TexelLight<'_>,
    set_up: Option<TexturedDraw>,
) where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    // A small face of an opaque draw: set up and drawn by the target's own code if it has it
    // (which tests the screen-space bound first, as `fill_portable`), unless it was offered
    // there already.
    let levels = match light {
        TexelLight::Full if !SIZE_OVER_SPEED => Some(None),
        TexelLight::Levels(l) => Some(Some(l)),
        _ => None,
    };
    // Only a target with the set-up has offered a face to it (a constant elsewhere).
    let set_up = set_up.filter(|_| arch::TEXTURED_FACE);
    let mut perspective = set_up == Some(TexturedDraw::Perspective);
    let offer = arch::TEXTURED_FACE && !W::BLENDS && set_up.is_none();
    if let Some(levels) = levels.filter(|_| offer) {
        match textured_face(target, clip, screen, &q, &texels, levels, &sampler, palette) {
            TexturedDraw::Done => return,
            TexturedDraw::Perspective => perspective = true,
            TexturedDraw::Declined => {}
        }
    }
    fill_portable(
        target,
        clip,
        screen,
        q,
        texels,
        sampler,
        write,
        light,
        perspective,
    );
}

/// [`fill_textured`]'s portable fills (out of line where there is the target's own set-up, so
/// that the frame of these is not set up for the faces that one draws): perspective-correct if
/// `perspective` (the bound is known not to hold), else as the bound says.
#[allow(clippy::too_many_arguments)]
#[cfg_attr(armv7m, inline(never))]
#[cfg_attr(not(armv7m), inline(always))]
fn fill_portable<S, C, R: RowWindow, W: Opacity>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    screen: [&ScreenVertex; 3],
    q: [Inverse; 3],
    texels: [[i32; 2]; 3],
    sampler: Sampler<'_, S>,
    write: W,
    light: TexelLight<'_>,
    perspective: bool,
) where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    let quadratic = matches!(light, TexelLight::Quadratic(_));
    if !perspective && !quadratic && nearly_affine(q, texels, &light, affine_level::<C>()) {
        fill_screen_space(target, clip, screen, texels, sampler, write, light);
    } else {
        fill_perspective(target, clip, screen, q, texels, sampler, write, light);
    }
}

/// [`fill_textured`] of a face whose screen-space interpolation is within the bound: the 2D
/// textured fill's planes, with the light's after the texel coordinates'. Out of line on
/// ARMv6-M, as [`fill_perspective`]: each has a large frame, and only one is on the stack at a
/// time (a micro:bit has 4 KB of it beside a 64×48 frame and its z-buffer).
#[cfg_attr(armv6m, inline(never))]
#[cfg_attr(not(armv6m), inline(always))]
fn fill_screen_space<S, C, R: RowWindow, W: Opacity>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    screen: [&ScreenVertex; 3],
    texels: [[i32; 2]; 3],
    sampler: Sampler<'_, S>,
    write: W,
    light: TexelLight<'_>,
) where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    let rect = clip.rect();
    let position = screen.map(|v| v.position());
    // Where flash counts more than speed, fewer kinds of light with the same pixels (the arms
    // `if !SIZE_OVER_SPEED` below): no light is a full level (`(c·65535 + 2¹⁵) >> 16 = c`),
    // tints are tints with a highlight of 0.
    let full = level_fraction(255 << 8);
    let (mu, u) = PlaneMap::new(texels.map(|t| t[0]));
    let (mv, v) = PlaneMap::new(texels.map(|t| t[1]));
    let maps = [mu, mv];
    let rows = clip.rows();
    match light {
        TexelLight::Full if !SIZE_OVER_SPEED => {
            let more = zip3_with(u, v, [(); 3], |u, v, ()| [u, v]);
            let a = with_depth::<2, 3>(screen, more, [0; 2]);
            rows.shade(
                position,
                &a,
                &rect,
                AffineFill::new(target, sampler, write, maps, Unlit),
            );
        }
        TexelLight::Full | TexelLight::Level(_) => {
            let more = zip3_with(u, v, [(); 3], |u, v, ()| [u, v]);
            let light = match light {
                TexelLight::Level(level) => Constant(level_fraction(level)),
                _ => Constant(full),
            };
            let a = with_depth::<2, 3>(screen, more, [0; 2]);
            rows.shade(
                position,
                &a,
                &rect,
                AffineFill::new(target, sampler, write, maps, light),
            );
        }
        TexelLight::Levels(l) => {
            let more = zip3_with(u, v, l, |u, v, l| [u, v, l]);
            let a = with_depth::<3, 4>(screen, more, [0; 3]);
            let fill = AffineFill::new(target, sampler, write, maps, PlaneLevel);
            rows.shade(position, &a, &rect, fill);
        }
        TexelLight::Tints(t) if !SIZE_OVER_SPEED => {
            let more = zip3_with(u, v, t, |u, v, [r, g, b]| [u, v, r, g, b]);
            let a = with_depth::<5, 6>(screen, more, [0; 5]);
            let fill = AffineFill::new(target, sampler, write, maps, PlaneChannels::<3>);
            rows.shade(position, &a, &rect, fill);
        }
        TexelLight::Tints(t) | TexelLight::Shiny { tints: t, .. } => {
            let speculars = match light {
                TexelLight::Shiny { speculars, .. } => speculars,
                _ => [0; 3],
            };
            let light = zip3_with(t, speculars, [(); 3], |t, s, ()| (t, s));
            let more = zip3_with(u, v, light, |u, v, ([r, g, b], s)| [u, v, r, g, b, s]);
            let a = with_depth::<6, 7>(screen, more, [0; 6]);
            let fill = AffineFill::new(target, sampler, write, maps, PlaneChannels::<4>);
            rows.shade(position, &a, &rect, fill);
        }
        // Per-pixel light is always perspective-correct (`fill_textured` never brings it here).
        TexelLight::Quadratic(_) => {}
    }
}

/// Sets up and draws the face `screen` (with `q ∝ 1/w`, 16.16 texel coordinates `texels`, lit
/// by the levels `levels` if any) by the target's own code ([`arch::textured_face`]) if the
/// target and `C` have it: drawn (done), not within the screen-space bound of
/// [`nearly_affine`] (perspective), or declined (and then as elsewhere), nothing drawn in
/// either. The same pixels as the portable screen-space fill.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn textured_face<S, C, R: RowWindow>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    screen: [&ScreenVertex; 3],
    q: &[Inverse; 3],
    texels: &[[i32; 2]; 3],
    levels: Option<[u16; 3]>,
    sampler: &Sampler<'_, S>,
    palette: Option<&[u16; 16]>,
) -> TexturedDraw
where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    let (Some(words), Some(masks)) = (face_words(sampler, palette), face_masks(sampler)) else {
        return TexturedDraw::Declined;
    };
    let l = levels.unwrap_or([0; 3]);
    let vertex = |k: usize| {
        let position = (screen[k].x.to_bits(), screen[k].y.to_bits());
        arch::VertexPrefix::new(position, screen[k].depth, l[k], q[k].parts())
    };
    let vertices = [vertex(0), vertex(1), vertex(2)];
    let template = clip.textured_template(masks, affine_level::<C>() as u32);
    let face = template.face(vertices.each_ref(), texels, words, levels.is_some());
    C::textured_face_565(target.buffers_mut(), face)
}

/// The texels of a face for the target's set-up ([`arch::FaceTexels`]): raw Rgb565 words of a
/// masked sampler (read nearest, or bilinear where the target's row loop has that), or the
/// 4-bit indices of a masked nearest sampler with the raw words of their `palette` if there are
/// those. Their masks are [`face_masks`]'.
#[inline(always)]
fn face_words<'w, S: TexelSource>(
    sampler: &'w Sampler<'_, S>,
    palette: Option<&'w [u16; 16]>,
) -> Option<arch::FaceTexels<'w>> {
    match sampler {
        Sampler::MaskedNearest(_, texels) => match texels.rgb565_words() {
            Some(words) => Some(arch::FaceTexels::words(words.0, false)),
            None => Some(arch::FaceTexels::palette4(texels.palette4()?.0, palette?)),
        },
        Sampler::MaskedBilinear(_, texels) if arch::BILINEAR_ROWS => {
            Some(arch::FaceTexels::words(texels.rgb565_words()?.0, true))
        }
        _ => None,
    }
}

/// The column and row masks (in texels, up to 2¹⁶ of them) and `y`'s shift of
/// [`face_words`]' texels.
#[inline(always)]
fn face_masks<S: TexelSource>(sampler: &Sampler<'_, S>) -> Option<(u32, u32, u32)> {
    let (Sampler::MaskedNearest(masks, _) | Sampler::MaskedBilinear(masks, _)) = sampler else {
        return None;
    };
    let (x_mask, rows_mask) = masks.masks_565()?;
    Some((x_mask, rows_mask, 32 - x_mask.leading_zeros()))
}

/// [`fill_textured`] of a face interpolated perspective-correct.
#[allow(clippy::too_many_arguments)]
#[cfg_attr(armv6m, inline(never))]
#[cfg_attr(not(armv6m), inline(always))]
fn fill_perspective<S, C, R: RowWindow, W: Opacity>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    screen: [&ScreenVertex; 3],
    q: [Inverse; 3],
    texels: [[i32; 2]; 3],
    sampler: Sampler<'_, S>,
    write: W,
    light: TexelLight<'_>,
) where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
{
    let rect = clip.rect();
    let position = screen.map(|v| v.position());
    // Fewer kinds of light where flash counts more than speed, as in `fill_screen_space`.
    let full = level_fraction(255 << 8);
    let perspective = perspective::attributes(q.map(Inverse::value));
    let attributes = with_depth(screen, perspective.values, perspective.half);
    let coordinates = (
        Corrected::new(texels.map(|t| t[0])),
        Corrected::new(texels.map(|t| t[1])),
    );
    // One span loop for each kind of light.
    match light {
        TexelLight::Full if !SIZE_OVER_SPEED => {
            let fill = TexturedFill::new(target, sampler, write, coordinates, Unlit);
            shade_textured(clip, position, &attributes, &rect, fill);
        }
        TexelLight::Full | TexelLight::Level(_) => {
            let level = match light {
                TexelLight::Level(level) => level_fraction(level),
                _ => full,
            };
            let fill = TexturedFill::new(target, sampler, write, coordinates, Constant(level));
            shade_textured(clip, position, &attributes, &rect, fill);
        }
        TexelLight::Levels(levels) => {
            let fill = TexturedFill::new(
                target,
                sampler,
                write,
                coordinates,
                Varying(Corrected::new(levels.map(|l| level_fraction(l) as i32))),
            );
            shade_textured(clip, position, &attributes, &rect, fill);
        }
        TexelLight::Tints(tints) if !SIZE_OVER_SPEED => {
            let [r, g, b] = transpose(tints).map(corrected_levels);
            let fill = TexturedFill::new(
                target,
                sampler,
                write,
                coordinates,
                CorrectedChannels([r, g, b]),
            );
            shade_textured(clip, position, &attributes, &rect, fill);
        }
        TexelLight::Tints(tints) | TexelLight::Shiny { tints, .. } => {
            let speculars = match light {
                TexelLight::Shiny { speculars, .. } => speculars,
                _ => [0; 3],
            };
            let [r, g, b] = transpose(tints).map(corrected_levels);
            let fill = TexturedFill::new(
                target,
                sampler,
                write,
                coordinates,
                CorrectedChannels([r, g, b, corrected_levels(speculars)]),
            );
            shade_textured(clip, position, &attributes, &rect, fill);
        }
        TexelLight::Quadratic(pixel) => {
            let fill = TexturedFill {
                target,
                sampler,
                write,
                coordinates,
                light: PerPixel(pixel),
            };
            shade_textured(clip, position, &attributes, &rect, fill);
        }
    }
}

/// The rows of a face drawn perspective-correct with the light `L`. Out of line on ARMv6-M:
/// each kind of light's span loop has a frame of its own, not all of them in
/// [`fill_perspective`]'s (a micro:bit's stack is 4 KB beside its buffers).
#[cfg_attr(armv6m, inline(never))]
#[cfg_attr(not(armv6m), inline(always))]
fn shade_textured<S, C, L, R: RowWindow, W: Opacity>(
    clip: &TargetClip<R>,
    position: [(crate::Coord, crate::Coord); 3],
    attributes: &crate::raster::plane::Attributes<4>,
    rect: &Rectangle,
    fill: TexturedFill<'_, '_, '_, C, S, L, W>,
) where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
    L: SpanLight,
{
    clip.rows().shade(position, attributes, rect, fill);
}

/// Levels (8.8 of the 0–255 scale) at the vertices as 16-bit fractions corrected for
/// perspective.
#[inline(always)]
fn corrected_levels(levels: [u16; 3]) -> Corrected {
    Corrected::new(levels.map(|l| level_fraction(l) as i32))
}

/// The vertices' channels as the channels' vertex values (and back).
#[inline(always)]
fn transpose<T>([[a0, a1, a2], [b0, b1, b2], [c0, c1, c2]]: [[T; 3]; 3]) -> [[T; 3]; 3] {
    [[a0, b0, c0], [a1, b1, c1], [a2, b2, c2]]
}

/// The largest departure from the perspective-correct texel coordinates that screen-space
/// interpolation may make where a face takes it: 1/16 texel (16.16).
const AFFINE_TEXELS: u64 = 1 << 12;

/// The largest departure from the perspective-correct light level (8.8 of the 0–255 scale) that
/// screen-space interpolation may make in a face drawn into `C`: a quarter of its finest
/// channel's step (¼ level for 8-bit channels, one level for Rgb565's 6-bit green, two for
/// 5-bit channels), so that the colour moves by at most a quarter of a step of that channel.
/// A texel times a level is `texel · level / 255`: a level off by `δ` moves a channel by at
/// most `δ` levels of 255.
const fn affine_level<C: GouraudColor>() -> u64 {
    let mut finest = 1;
    let mut k = 0;
    while k < 3 {
        if C::MAX[k] > finest {
            finest = C::MAX[k];
        }
        k += 1;
    }
    // 8.8 levels: a quarter step is 256 · 255 / (4 · max), at least a quarter level.
    64 * 255 / finest as u64
}

/// Whether a face whose vertices have `q ∝ 1/w`, texel coordinates (16.16) and light may be
/// interpolated in screen space (the levels within `affine_level`, 8.8): an attribute of
/// spread `s` (its largest difference between vertices) departs from its perspective-correct
/// value by at most `s·(q_max − q_min) / (4·q_min)`. At screen barycentrics `bₖ` the
/// perspective-correct value weighs the vertex values by `bₖ·qₖ / Q` (`Q = Σ bⱼ·qⱼ`), so it
/// departs from the screen-space one by `Σ bₖ·(aₖ − c)·(qₖ − Q) / Q` for any `c`: with `c`
/// the middle of the values' range, at most `s/2` times the mean absolute deviation of the
/// `qₖ` (weights `bₖ`, mean `Q`) over `Q`, and that deviation is at most `(q_max − q_min)/2`.
/// The bound is reached along an edge whose ends hold `q_min` and `q_max` as `q_max/q_min → 1`
/// (a unit test checks both). Small faces (most of a mesh's) take the cheaper screen-space
/// fill.
#[inline(always)]
fn nearly_affine(
    q: [Inverse; 3],
    texels: [[i32; 2]; 3],
    light: &TexelLight<'_>,
    affine_level: u64,
) -> bool {
    let Some((q, most)) = Inverse::common_scale(q) else {
        return false;
    };
    let (lo, hi) = (q[0].min(q[1]).min(q[2]), q[0].max(q[1]).max(q[2]));
    let spread = |a: [i32; 3]| {
        a[0].max(a[1])
            .max(a[2])
            .wrapping_sub(a[0].min(a[1]).min(a[2]))
    };
    let texel_spread =
        (spread(texels.map(|t| t[0])) as u32).max(spread(texels.map(|t| t[1])) as u32);
    // The common scale's values are below 2²⁴; a truncated mantissa is within one unit, so the
    // difference is widened by two units of the largest shift: a larger ratio, never a smaller
    // one. Below 2³² · 2²⁵ and 2¹⁴ · 2²⁶: no overflow.
    let (ratio, four) = (u64::from(hi - lo + (2 << most)), u64::from(4 * lo));
    if u64::from(texel_spread) * ratio > AFFINE_TEXELS * four {
        return false;
    }
    let levels = match light {
        TexelLight::Levels(l) => spread(l.map(i32::from)) as u32,
        TexelLight::Tints(t) => {
            let [r, g, b] = transpose(*t).map(|c| spread(c.map(i32::from)) as u32);
            r.max(g).max(b)
        }
        TexelLight::Shiny {
            tints: t,
            speculars,
        } => {
            let [r, g, b] = transpose(*t).map(|c| spread(c.map(i32::from)) as u32);
            let specular = spread(speculars.map(i32::from)) as u32;
            r.max(g).max(b).max(specular)
        }
        TexelLight::Full | TexelLight::Level(_) => return true,
        TexelLight::Quadratic(_) => return false,
    };
    u64::from(levels) * ratio <= affine_level * four
}

/// The span shader of a textured face interpolated in screen space: the depth, the texel
/// coordinates (16-bit planes as [`PlaneMap`] maps them) and the light's planes after them, if
/// any (`L` reads them).
struct AffineFill<'t, 'a, 'x, C, S, L, W> {
    target: &'t mut DepthTarget<'a, C>,
    sampler: Sampler<'x, S>,
    write: W,
    maps: [PlaneMap; 2],
    light: L,
}

impl<'t, 'a, 'x, C, S, L, W> AffineFill<'t, 'a, 'x, C, S, L, W> {
    /// The fill of `target` sampling with `sampler` at the coordinates `maps` map, lit by
    /// `light`.
    #[inline(always)]
    fn new(
        target: &'t mut DepthTarget<'a, C>,
        sampler: Sampler<'x, S>,
        write: W,
        maps: [PlaneMap; 2],
        light: L,
    ) -> Self {
        AffineFill {
            target,
            sampler,
            write,
            maps,
            light,
        }
    }
}

impl<C, S, L, W, const N: usize> SpanShader<N> for AffineFill<'_, '_, '_, C, S, L, W>
where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
    L: PlaneLight<N>,
    W: Opacity,
{
    type Steps = ([u32; N], (i32, i32));

    /// Small faces (most of a mesh's) are scanned: the same spans without the walk's
    /// divisions.
    #[inline(always)]
    fn scans_small(&self) -> bool {
        true
    }

    #[inline(always)]
    fn prepare(&mut self, step: [u32; N]) -> Self::Steps {
        (
            step,
            (self.maps[0].step(step[1]), self.maps[1].step(step[2])),
        )
    }

    /// All rows of a small face in one loop (where there is a divider for the rows' runs): the
    /// sampler chosen once a face rather than once a span, the buffers indexed directly. The
    /// same spans, values and pixels as [`span`](Self::span) gives them.
    #[inline(always)]
    fn small_rows(&mut self, scan: &SmallScan<'_, N>) -> bool {
        // A translucent draw's spans blend (`span`).
        if W::BLENDS {
            return false;
        }
        let steps = self.prepare(scan.planes().step());
        let (colors, depths, width) = self.target.buffers_mut();
        // The target's row loop where it draws these texels and light (the same pixels).
        if arch::TEXTURED_ROWS {
            let texel = steps.1;
            if let Some(rows) = texel_rows(scan, width, texel, self.maps, &self.sampler, L::ROWS) {
                if C::textured_rows_565(colors, depths, &rows) {
                    return true;
                }
            }
        }
        let rows = SmallRows {
            colors,
            depths,
            width,
            scan,
            steps,
            maps: self.maps,
            light: self.light,
        };
        self.sampler.run(rows);
        true
    }

    #[inline(always)]
    fn span(&mut self, (step, texel): &Self::Steps, span: Span, start: [u32; N]) {
        let Some((colors, depths)) = self.target.clipped_spans_mut(span) else {
            return;
        };
        let len = span.len();
        let (x, dx) = self.maps[0].run(start[1], step[1], texel.0, len);
        let (y, dy) = self.maps[1].run(start[2], step[2], texel.1, len);
        let run = AffineSpan {
            colors,
            depths,
            depth: (start[0], step[0]),
            at: (x, y),
            step: (dx, dy),
            level: self.light.of_planes(&start, step),
            light: self.light,
            write: self.write,
        };
        self.sampler.run(run);
    }
}

/// One span of [`AffineFill`], its pixels written as `W` writes them.
struct AffineSpan<'p, C, L: SpanLight, W> {
    colors: &'p mut [C],
    depths: &'p mut [u16],
    depth: (u32, u32),
    at: (i32, i32),
    step: (i32, i32),
    /// The light's state at the first pixel, and its step.
    level: (L::Level, L::Level),
    light: L,
    write: W,
}

impl<C: GouraudColor, L: SpanLight, W: Opacity> SampledLoop<C> for AffineSpan<'_, C, L, W> {
    type Output = ();

    #[inline(always)]
    fn run<T: Sampled<C>>(self, texel: impl Fn(i32, i32) -> T, y_shift: u32) {
        let (y, dy) = (self.at.1 << y_shift, self.step.1 << y_shift);
        let (z, dz) = self.depth;
        let (x, dx) = (self.at.0, self.step.0);
        let (l, dl) = self.level;
        let (values, steps) = ((z, x, y, l), (dz, dx, dy, dl));
        let (colors, depths, light) = (self.colors, self.depths, self.light);
        if W::BLENDS {
            let opacity = self.write.opacity();
            blended_pixels(colors, depths, values, steps, &texel, light, opacity);
        } else {
            pixels(colors, depths, values, steps, &texel, light);
        }
    }
}

/// The rows of a small face of [`AffineFill`] (its `small_rows`), in one loop.
struct SmallRows<'p, 's, C, L, const N: usize> {
    colors: &'p mut [C],
    depths: &'p mut [u16],
    /// Pixels a row of both buffers.
    width: usize,
    scan: &'p SmallScan<'s, N>,
    steps: ([u32; N], (i32, i32)),
    maps: [PlaneMap; 2],
    light: L,
}

impl<C: GouraudColor, L: PlaneLight<N>, const N: usize> SampledLoop<C>
    for SmallRows<'_, '_, C, L, N>
{
    type Output = ();

    /// Each row's run (as the walk gives them) and its pixels: what [`AffineFill::span`] draws
    /// for it.
    #[inline(always)]
    fn run<T: Sampled<C>>(self, texel: impl Fn(i32, i32) -> T, y_shift: u32) {
        let (step, texel_step) = self.steps;
        let planes = self.scan.planes();
        let mut row_values = planes.first();
        let row_step = planes.row_step();
        let mut runs = *self.scan.runs();
        let (x0, y0) = self.scan.origin();
        // The region is inside the clip, inside the buffers: its first pixel's index (the
        // slices' own checks below stand guard all the same).
        let mut row_start = (y0 as usize)
            .wrapping_mul(self.width)
            .wrapping_add(x0 as usize);
        let [m_u, m_v] = self.maps;
        for _ in 0..self.scan.rows() {
            let (start, end) = runs.run();
            runs.advance();
            if end > start {
                let range =
                    row_start.wrapping_add(start as usize)..row_start.wrapping_add(end as usize);
                let len = end - start;
                let mut at = row_values;
                for (value, step) in at.iter_mut().zip(step) {
                    *value = value.wrapping_add(step.wrapping_mul(start));
                }
                if let (Some(colors), Some(depths)) = (
                    self.colors.get_mut(range.clone()),
                    self.depths.get_mut(range),
                ) {
                    let (x, dx) = m_u.run(at[1], step[1], texel_step.0, len);
                    let (y, dy) = m_v.run(at[2], step[2], texel_step.1, len);
                    let (l, dl) = self.light.of_planes(&at, &step);
                    let values = (at[0], x, y << y_shift, l);
                    let steps = (step[0], dx, dy << y_shift, dl);
                    pixels(colors, depths, values, steps, &texel, self.light);
                }
            }
            for (value, step) in row_values.iter_mut().zip(row_step) {
                *value = value.wrapping_add(step);
            }
            row_start = row_start.wrapping_add(self.width);
        }
    }
}

/// The lights the target's textured row loop ([`arch::textured_rows`]) draws.
#[derive(Clone, Copy, PartialEq, Eq)]
enum RowLight {
    /// [`Unlit`].
    Unlit,
    /// [`PlaneLevel`].
    Level,
}

/// The rows of a small face for the target's textured row loop, if it draws them: nearest
/// texels of a power-of-two repeating texture of up to 2¹⁶ raw Rgb565 words (the masked loop
/// of [`Sampler::run`]), unlit or lit by the level plane, the coordinates' planes mapped by
/// right shifts; `None` for the portable loop.
#[inline(always)]
fn texel_rows<'w, S: TexelSource, const N: usize>(
    scan: &SmallScan<'_, N>,
    width: usize,
    texel_steps: (i32, i32),
    maps: [PlaneMap; 2],
    sampler: &'w Sampler<'_, S>,
    light: Option<RowLight>,
) -> Option<arch::TexturedRows<'w>> {
    let light = light?;
    let ((texels, x_mask, rows_mask, y_shift), bilinear) = masked_565_texels(sampler)?;
    let maps = [shift_map(&maps[0])?, shift_map(&maps[1])?];
    let planes = scan.planes();
    let (first, step, row_step) = (planes.first(), planes.step(), planes.row_step());
    let plane = |k: usize| Some([*first.get(k)?, *step.get(k)?, *row_step.get(k)?]);
    let runs = scan.runs();
    let (x0, y0) = scan.origin();
    let region = arch::LevelRows {
        first: (y0 as usize).wrapping_mul(width).wrapping_add(x0 as usize),
        width,
        columns: runs.columns,
        rows: scan.rows(),
        bounds: runs.bounds.map(|b| (b.numerator, b.divisor, b.step)),
        middle_starts: runs.middle_starts,
        depth: plane(0)?,
        level: [0; 3],
    };
    let level = match light {
        RowLight::Unlit => None,
        RowLight::Level => Some(plane(3)?),
    };
    Some(arch::TexturedRows {
        region,
        u: plane(1)?,
        v: plane(2)?,
        level,
        maps,
        texel_steps,
        y_shift,
        texels,
        x_mask,
        rows_mask,
        bilinear,
    })
}

/// The raw Rgb565 texels of a masked nearest sampler of a texture of up to 2¹⁶ texels, its
/// column mask, its row mask (in storage units) and `y`'s shift in [`Sampler::run`] (the bits
/// of a row: the width less one is the column mask).
#[inline(always)]
fn masked_565<'w, S: TexelSource>(sampler: &'w Sampler<'_, S>) -> Option<Masked565<'w>> {
    masked_565_texels(sampler).and_then(|(texels, bilinear)| (!bilinear).then_some(texels))
}

/// The texels, the column and row masks and `y`'s shift of [`masked_565`].
type Masked565<'w> = (&'w [u16], u32, u32, u32);

/// [`masked_565`]'s texels, masks and shift of a masked sampler of either filter, and whether
/// it is bilinear (where the target's row loop draws bilinear texels, else nearest only).
#[inline(always)]
fn masked_565_texels<'w, S: TexelSource>(
    sampler: &'w Sampler<'_, S>,
) -> Option<(Masked565<'w>, bool)> {
    let (masks, texels, bilinear) = match sampler {
        Sampler::MaskedNearest(masks, texels) => (masks, texels, false),
        Sampler::MaskedBilinear(masks, texels) if arch::BILINEAR_ROWS => (masks, texels, true),
        _ => return None,
    };
    let texels = texels.rgb565_words()?.0;
    let (x_mask, rows_mask) = masks.masks_565()?;
    Some((
        (texels, x_mask, rows_mask, 32 - x_mask.leading_zeros()),
        bilinear,
    ))
}

/// `map` as `(base, down)`, a plane value `p` mapping to `base + (p >> down)`, if it maps so
/// (not for coordinates spread over more than 2³² units of 2⁻¹⁶ texel, whose values shift left).
#[inline(always)]
fn shift_map(map: &PlaneMap) -> Option<(i32, u32)> {
    let base = map.at(0);
    let all = map.at(u32::MAX).wrapping_sub(base) as u32;
    let down = all.leading_zeros();
    (u32::MAX.checked_shr(down)? == all).then_some((base, down))
}

/// A light level (8.8 of the 0–255 scale) as a fraction with 16 bits (`65535` for 255).
#[inline(always)]
fn level_fraction(level: u16) -> u32 {
    (u32::from(level) * 257 + 128) >> 8
}

/// How the span loop lights a texel: a state a pixel (the level's 16-bit fraction, or one for
/// each channel), stepped from pixel to pixel.
trait SpanLight: Copy {
    /// The state at a pixel, and its step to the next.
    type Level: Copy;
    /// The light's exact values at a chunk's end: found once, for the chunk that ends there
    /// and the one that starts there.
    type End: Copy;
    /// The exact values at the perspective barycentrics `at`.
    fn end(&self, at: (Lambda, Lambda)) -> Self::End;
    /// The state at the first pixel of a chunk from the values `start` to `end` (its ends'
    /// [`end`](Self::end)s) over `over` pixels, and its step.
    fn chunk(&self, start: Self::End, end: Self::End, over: u32) -> (Self::Level, Self::Level);
    /// The sample (a texel, or a bilinear blend before its rounding) lit at `level`: a
    /// one-level light scales a blend before its one rounding ([`Sampled::lit`]), the others
    /// light the rounded texel.
    fn apply<C: GouraudColor, T: Sampled<C>>(&self, sample: T, level: Self::Level) -> C;
    /// `level` a pixel on.
    fn step(level: Self::Level, by: Self::Level) -> Self::Level;

    /// This light in the target's perspective span loop ([`arch::perspective_span`]), if it
    /// draws it: `Some(None)` unlit, `Some(Some(level))` for a 16-bit fraction `level` as
    /// `(base, d₁, d₂)` that the loop clamps to `0..=2¹⁶` and scales each channel by.
    #[inline(always)]
    fn span_level(&self) -> Option<Option<[i32; 3]>> {
        None
    }

    /// The largest [`slope`](Corrected::slope) of the light's 16-bit fractions along a span
    /// with `(k₁, k₂)` (0 for a light that does not vary across a face).
    #[inline(always)]
    fn slope(&self, _: (i32, u32), _: (i32, u32)) -> u64 {
        0
    }

    /// Whether a lit texel is the texel itself at every pixel (no light, or a full level).
    #[inline(always)]
    fn plain(&self) -> bool {
        false
    }
}

/// A light of the screen-space fill, its state read from the planes after the texel
/// coordinates' (attributes 3 onwards of `N`).
trait PlaneLight<const N: usize>: SpanLight {
    /// The target's textured row loop's form of this light, if it has one.
    const ROWS: Option<RowLight> = None;

    /// The state at a pixel whose planes' values are `at`, and its step for the planes' `step`.
    fn of_planes(&self, at: &[u32; N], step: &[u32; N]) -> (Self::Level, Self::Level);
}

/// No light.
#[derive(Clone, Copy)]
struct Unlit;

impl SpanLight for Unlit {
    type Level = ();

    type End = ();

    #[inline(always)]
    fn end(&self, _: (Lambda, Lambda)) {}

    #[inline(always)]
    fn chunk(&self, _: (), _: (), _: u32) -> ((), ()) {
        ((), ())
    }

    #[inline(always)]
    fn apply<C: GouraudColor, T: Sampled<C>>(&self, sample: T, _: ()) -> C {
        sample.color()
    }

    #[inline(always)]
    fn step(_: (), _: ()) {}

    #[inline(always)]
    fn span_level(&self) -> Option<Option<[i32; 3]>> {
        Some(None)
    }

    #[inline(always)]
    fn plain(&self) -> bool {
        true
    }
}

impl<const N: usize> PlaneLight<N> for Unlit {
    const ROWS: Option<RowLight> = Some(RowLight::Unlit);

    #[inline(always)]
    fn of_planes(&self, _: &[u32; N], _: &[u32; N]) -> ((), ()) {
        ((), ())
    }
}

/// One level for the face (a 16-bit fraction).
#[derive(Clone, Copy)]
struct Constant(u32);

impl SpanLight for Constant {
    type Level = ();

    type End = ();

    #[inline(always)]
    fn end(&self, _: (Lambda, Lambda)) {}

    #[inline(always)]
    fn chunk(&self, _: (), _: (), _: u32) -> ((), ()) {
        ((), ())
    }

    /// A full level leaves the sample as it is (a blend rounded once, as unlit: scaled by
    /// `2¹⁸ − 4` it could round a step lower), so that a full light is no light on every
    /// target (where flash counts, no light is drawn as a full level).
    #[inline(always)]
    fn apply<C: GouraudColor, T: Sampled<C>>(&self, sample: T, _: ()) -> C {
        if self.plain() {
            return sample.color();
        }
        sample.lit(self.0, self.0 << 2)
    }

    #[inline(always)]
    fn step(_: (), _: ()) {}

    /// The same level everywhere: at most 65 535, which the loop's clamp leaves as it is; none
    /// where it is full (as [`apply`](Self::apply) draws it).
    #[inline(always)]
    fn span_level(&self) -> Option<Option<[i32; 3]>> {
        Some((!self.plain()).then_some([self.0 as i32, 0, 0]))
    }

    /// A full level: `(c·f + 2¹⁵) >> 16` is `c` for every 8-bit `c` at `f` = 2¹⁶ − 1 or 2¹⁶.
    #[inline(always)]
    fn plain(&self) -> bool {
        matches!(self.0, 0xffff | 0x1_0000)
    }
}

impl<const N: usize> PlaneLight<N> for Constant {
    #[inline(always)]
    fn of_planes(&self, _: &[u32; N], _: &[u32; N]) -> ((), ()) {
        ((), ())
    }
}

/// A plane's value (8.24 of the 0–255 scale) as a 16-bit fraction (255 is 65535).
#[inline(always)]
fn plane_fraction(value: i32) -> u32 {
    ((value as u32 >> 12) * 257) >> 12
}

/// The same with 18 fractional bits (below `2¹⁸·257/256`), as a bilinear blend is lit.
#[inline(always)]
fn plane_fraction_18(value: i32) -> u32 {
    ((value as u32 >> 12) * 257) >> 10
}

/// The screen-space fill's level plane (8.24 of the 0–255 scale, stepped as it is): attribute
/// 3 of 4.
#[derive(Clone, Copy)]
struct PlaneLevel;

impl SpanLight for PlaneLevel {
    type Level = i32;

    type End = ();

    #[inline(always)]
    fn end(&self, _: (Lambda, Lambda)) {}

    #[inline(always)]
    fn chunk(&self, _: (), _: (), _: u32) -> (i32, i32) {
        (0, 0)
    }

    #[inline(always)]
    fn apply<C: GouraudColor, T: Sampled<C>>(&self, sample: T, level: i32) -> C {
        sample.lit(plane_fraction(level), plane_fraction_18(level))
    }

    #[inline(always)]
    fn step(level: i32, by: i32) -> i32 {
        level.wrapping_add(by)
    }
}

impl PlaneLight<4> for PlaneLevel {
    const ROWS: Option<RowLight> = Some(RowLight::Level);

    #[inline(always)]
    fn of_planes(&self, at: &[u32; 4], step: &[u32; 4]) -> (i32, i32) {
        (at[3] as i32, step[3] as i32)
    }
}

/// The screen-space fill's `K` channel planes after the texel coordinates' (8.24 of the 0–255
/// scale, stepped as they are): three tints (attributes 3 to 5 of 6), and a specular term
/// (attribute 6 of 7) with a fourth.
#[derive(Clone, Copy)]
struct PlaneChannels<const K: usize>;

impl<const K: usize> SpanLight for PlaneChannels<K> {
    type Level = [i32; K];

    type End = ();

    #[inline(always)]
    fn end(&self, _: (Lambda, Lambda)) {}

    #[inline(always)]
    fn chunk(&self, _: (), _: (), _: u32) -> ([i32; K], [i32; K]) {
        ([0; K], [0; K])
    }

    #[inline(always)]
    fn apply<C: GouraudColor, T: Sampled<C>>(&self, sample: T, light: [i32; K]) -> C {
        lit_channels::<C, K>(sample.color().channels(), light.map(plane_fraction))
    }

    #[inline(always)]
    fn step(light: [i32; K], by: [i32; K]) -> [i32; K] {
        add_each(light, by)
    }
}

impl PlaneLight<6> for PlaneChannels<3> {
    #[inline(always)]
    fn of_planes(&self, at: &[u32; 6], step: &[u32; 6]) -> ([i32; 3], [i32; 3]) {
        after_texels(at, step)
    }
}

impl PlaneLight<7> for PlaneChannels<4> {
    #[inline(always)]
    fn of_planes(&self, at: &[u32; 7], step: &[u32; 7]) -> ([i32; 4], [i32; 4]) {
        after_texels(at, step)
    }
}

/// Each of `values` plus its `steps` (wrapping).
#[inline(always)]
fn add_each<const K: usize>(mut values: [i32; K], steps: [i32; K]) -> [i32; K] {
    for (value, step) in values.iter_mut().zip(steps) {
        *value = value.wrapping_add(step);
    }
    values
}

/// The `K` planes' values and steps after the depth and the texel coordinates (attributes
/// `3 .. 3 + K` of `N`).
#[inline(always)]
fn after_texels<const N: usize, const K: usize>(
    at: &[u32; N],
    step: &[u32; N],
) -> ([i32; K], [i32; K]) {
    let of = |v: &[u32; N], c: usize| v.get(3 + c).copied().unwrap_or(0) as i32;
    (
        core::array::from_fn(|c| of(at, c)),
        core::array::from_fn(|c| of(step, c)),
    )
}

/// The vertices' levels, perspective-correct at the chunks' ends and stepped between.
#[derive(Clone, Copy)]
struct Varying(Corrected);

impl SpanLight for Varying {
    type Level = i32;

    type End = i32;

    #[inline(always)]
    fn end(&self, at: (Lambda, Lambda)) -> i32 {
        self.0.at(at)
    }

    #[inline(always)]
    fn chunk(&self, a: i32, b: i32, over: u32) -> (i32, i32) {
        (a, step_over(a, b, over))
    }

    #[inline(always)]
    fn apply<C: GouraudColor, T: Sampled<C>>(&self, sample: T, level: i32) -> C {
        let f = level.clamp(0, 1 << 16) as u32;
        sample.lit(f, f << 2)
    }

    #[inline(always)]
    fn step(level: i32, by: i32) -> i32 {
        level.wrapping_add(by)
    }

    #[inline(always)]
    fn span_level(&self) -> Option<Option<[i32; 3]>> {
        Some(Some(self.0.parts()))
    }

    #[inline(always)]
    fn slope(&self, k1: (i32, u32), k2: (i32, u32)) -> u64 {
        self.0.slope(k1, k2)
    }
}

/// The vertices' `K` channels (16-bit fractions: three tints, and a specular term with a
/// fourth), perspective-correct at the chunks' ends and stepped between.
#[derive(Clone, Copy)]
struct CorrectedChannels<const K: usize>([Corrected; K]);

impl<const K: usize> SpanLight for CorrectedChannels<K> {
    type Level = [i32; K];

    /// The barycentrics: the channels' values are found again at each end (kept from one
    /// chunk to the next, three or four of them cost the loop more registers than the
    /// products they save; the textured frames' perspective spans are short).
    type End = (Lambda, Lambda);

    #[inline(always)]
    fn end(&self, at: (Lambda, Lambda)) -> (Lambda, Lambda) {
        at
    }

    #[inline(always)]
    fn chunk(
        &self,
        start: (Lambda, Lambda),
        end: (Lambda, Lambda),
        over: u32,
    ) -> ([i32; K], [i32; K]) {
        let a = self.0.map(|c| c.at(start));
        let mut steps = self.0.map(|c| c.at(end));
        for (step, a) in steps.iter_mut().zip(a) {
            *step = step_over(a, *step, over);
        }
        (a, steps)
    }

    #[inline(always)]
    fn apply<C: GouraudColor, T: Sampled<C>>(&self, sample: T, light: [i32; K]) -> C {
        let light = light.map(|t| t.clamp(0, 1 << 16) as u32);
        lit_channels::<C, K>(sample.color().channels(), light)
    }

    #[inline(always)]
    fn step(light: [i32; K], by: [i32; K]) -> [i32; K] {
        add_each(light, by)
    }

    #[inline(always)]
    fn slope(&self, k1: (i32, u32), k2: (i32, u32)) -> u64 {
        self.0.iter().map(|c| c.slope(k1, k2)).fold(0, u64::max)
    }
}

/// The channels `base` each times its own 16-bit fraction (the first three of `light`, at
/// most 2¹⁶), plus a fourth fraction, if any, of the channel's maximum (a white highlight),
/// rounded once and saturating at the maximum.
#[inline(always)]
fn lit_channels<C: GouraudColor, const K: usize>(base: [u8; 3], light: [u32; K]) -> C {
    let fraction = |c: usize| light.get(c).copied().unwrap_or(0).min(1 << 16);
    let specular = fraction(3);
    let s = |c: u8, max: u8, fraction: u32| {
        let max = u32::from(max);
        let v = (u32::from(c) * fraction + max * specular + (1 << 15)) >> 16;
        v.min(max) as u8
    };
    let ([c0, c1, c2], [m0, m1, m2]) = (base, C::MAX);
    C::from_channels([
        s(c0, m0, fraction(0)),
        s(c1, m1, fraction(1)),
        s(c2, m2, fraction(2)),
    ])
}

/// The per-pixel light of a textured face with [`Shading::Quadratic`](super::Shading): its
/// quadratic normal field as a polynomial in the face's perspective-correct barycentrics
/// `λ₁`, `λ₂` (those of its vertices 1 and 2, `λ₀ = 1 − λ₁ − λ₂`),
///
/// `N = K₀ + K₁λ₁ + K₂λ₂ + K₃λ₁² + K₄λ₁λ₂ + K₅λ₂²`,
///
/// and the light (one directional light with its ambient term) and highlight it is lit by.
/// Built once a face (a fan's triangle: the field restricted to it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct PixelLight {
    /// `K₀ … K₅` of each component, 16 fractional bits (at most 2²⁰ in magnitude: unit
    /// nodes).
    k: [[i32; 6]; 3],
    /// The unit light direction and half vector, raw `I16F16` (within ±2¹⁶).
    l: [i32; 3],
    h: [i32; 3],
    /// The light (its ambient term).
    light: Light,
    /// The highlight and its threshold, if any.
    specular: Option<(Specular, u32)>,
    /// The pipeline's other lights ([`Lights`](super::Lights)), the first `count`.
    sources: [PixelSource; Lights::MAX],
    count: usize,
}

impl PixelLight {
    /// The light of the face whose normal field is `normals` (vertex `k` of the field the
    /// face's vertex `k`), lit by `light` and `highlight` (its half vector in the normals'
    /// space).
    pub(crate) fn new(
        normals: &QuadraticNormals,
        light: &Light,
        highlight: Option<&Highlight>,
        (sources, count): ([PixelSource; Lights::MAX], usize),
    ) -> Self {
        let [n0, n1, n2] = normals.vertices().map(|v| v.to_bits());
        let [m01, m12, m20] = normals.midpoints().map(|v| v.to_bits());
        // With c₀ = 1 − λ₁ − λ₂, c₁ = λ₁, c₂ = λ₂ in Σ Nᵢcᵢ(2cᵢ − 1) + Σ 4N̂ᵢⱼcᵢcⱼ. Unit nodes
        // (|component| ≤ 2¹⁶): every sum below 12·2¹⁶.
        let unit = |v: [i32; 3]| v.map(|c| c.clamp(-(1 << 16), 1 << 16));
        let [n0, n1, n2, m01, m12, m20] = [n0, n1, n2, m01, m12, m20].map(unit);
        let k = |c: usize| -> [i32; 6] {
            let at = |v: [i32; 3]| v.get(c).copied().unwrap_or(0);
            let (n0, n1, n2) = (at(n0), at(n1), at(n2));
            let (m01, m12, m20) = (at(m01), at(m12), at(m20));
            [
                n0,
                -3 * n0 - n1 + 4 * m01,
                -3 * n0 - n2 + 4 * m20,
                2 * n0 + 2 * n1 - 4 * m01,
                4 * n0 - 4 * m01 + 4 * m12 - 4 * m20,
                2 * n0 + 2 * n2 - 4 * m20,
            ]
        };
        let unit = |v: Vec3| unit(v.to_bits());
        PixelLight {
            k: [k(0), k(1), k(2)],
            l: unit(light.direction()),
            h: highlight.map_or([0; 3], |h| unit(h.half)),
            light: *light,
            specular: highlight.map(|h| (h.specular, h.threshold)),
            sources,
            count,
        }
    }

    /// The normal (28 fractional bits, wrapping: its components are below 8 in magnitude
    /// inside the face) at `a = (λ₁, λ₂)` (16 fractional bits, at most 2¹⁶ each, as
    /// [`lambdas`](perspective) gives them), and its first and second forward differences
    /// along a run on which the barycentrics step by `d` (28 fractional bits, within ±2²⁸) a
    /// pixel: the field is quadratic in the pixel along such a run, so that stepping the
    /// value by the first difference and that by the second gives it exactly, up to the
    /// differences' rounding (the first within 2⁻²⁴, the second 2⁻²⁶: below 2⁻¹⁹ after 16
    /// pixels). 32-bit operands, their products 64 bits (one instruction on ARMv7-M).
    #[inline(always)]
    fn differences(&self, a: (Lambda, Lambda), d: (i32, i32)) -> ([i32; 3], [i32; 3], [i32; 3]) {
        // 29 fractional bits: |a|, |d| ≤ 2²⁹.
        let (a1, a2) = (
            (a.0.min(1 << 16) << 13) as i32,
            (a.1.min(1 << 16) << 13) as i32,
        );
        let (d1, d2) = (
            d.0.clamp(-(1 << 28), 1 << 28) << 1,
            d.1.clamp(-(1 << 28), 1 << 28) << 1,
        );
        let m = mul_i32_wide;
        // Products back to 29 fractional bits: each below 3·2²⁹.
        let w = |p: i64| (p >> 29) as i32;
        let (a11, a12, a22) = (w(m(a1, a1)), w(m(a1, a2)), w(m(a2, a2)));
        // N(a + d) − N(a), the quadratic part: (2a₁d₁ + d₁²), (a₁d₂ + a₂d₁ + d₁d₂), (2a₂d₂ + d₂²).
        let s11 = w(2 * m(a1, d1) + m(d1, d1));
        let s12 = w(m(a1, d2) + m(a2, d1) + m(d1, d2));
        let s22 = w(2 * m(a2, d2) + m(d2, d2));
        // The second difference's squares with 35 fractional bits (below 2³⁶).
        let (q11, q12, q22) = (m(d1, d1) >> 23, m(d1, d2) >> 23, m(d2, d2) >> 23);
        let round = |x: i64, shift: u32| (x.wrapping_add(1 << (shift - 1)) >> shift) as i32;
        let component = |k: &[i32; 6]| {
            let [k0, k1, k2, k3, k4, k5] = *k;
            // 45 fractional bits (K: 16): each product below 2⁵¹.
            let v = (i64::from(k0) << 29)
                + m(k1, a1)
                + m(k2, a2)
                + m(k3, a11)
                + m(k4, a12)
                + m(k5, a22);
            let f = m(k1, d1) + m(k2, d2) + m(k3, s11) + m(k4, s12) + m(k5, s22);
            // 51 fractional bits: twice the quadratic form of d (each product below 2⁵⁷).
            let g = 2 * (i64::from(k3) * q11 + i64::from(k4) * q12 + i64::from(k5) * q22);
            (round(v, 17), round(f, 17), round(g, 23))
        };
        let [kx, ky, kz] = &self.k;
        let (x, y, z) = (component(kx), component(ky), component(kz));
        ([x.0, y.0, z.0], [x.1, y.1, z.1], [x.2, y.2, z.2])
    }
}

/// Per-pixel light of the quadratic normal field ([`PixelLight`]): the normal and its first
/// difference stepped along each chunk (28 fractional bits, wrapping), restarted from the
/// perspective-correct barycentrics at each chunk's first pixel and the barycentrics' chord to
/// its end; each pixel lit by its normal, renormalised.
#[derive(Clone, Copy)]
struct PerPixel<'p>(&'p PixelLight);

impl SpanLight for PerPixel<'_> {
    /// The normal and its first difference (a step: unused, and the second difference).
    type Level = ([i32; 3], [i32; 3]);
    /// The barycentrics themselves (the field is set up from them at each chunk's start).
    type End = (Lambda, Lambda);

    #[inline(always)]
    fn end(&self, at: (Lambda, Lambda)) -> (Lambda, Lambda) {
        at
    }

    #[inline(always)]
    fn chunk(
        &self,
        start: (Lambda, Lambda),
        end: (Lambda, Lambda),
        over: u32,
    ) -> (Self::Level, Self::Level) {
        // The barycentrics' steps with 28 fractional bits (λ ≤ 2¹⁶: no overflow).
        let d = |s: Lambda, e: Lambda| step_over((s << 12) as i32, (e << 12) as i32, over);
        let d = (d(start.0, end.0), d(start.1, end.1));
        let (value, first, second) = self.0.differences(start, d);
        ((value, first), ([0; 3], second))
    }

    #[inline(always)]
    fn apply<C: GouraudColor, T: Sampled<C>>(&self, sample: T, (n, _): Self::Level) -> C {
        // 16 fractional bits, within ±2¹⁷ (the field stays near unit length).
        let q = n.map(|v| (v.wrapping_add(1 << 11) >> 12).clamp(-(1 << 17) + 1, (1 << 17) - 1));
        let light = self.0;
        let highlight = light.specular.as_ref().map(|(s, t)| (&light.h, s, *t));
        let (diffuse, mut specular) = pixel_terms(q, &light.l, highlight);
        let mut level = light.light.level_of_diffuse(diffuse);
        // The other lights, each `weight · max(0, n̂·l)` and its highlight, saturating at 1.
        for s in light.sources.iter().take(light.count) {
            let highlight = light.specular.as_ref().map(|(sp, t)| (&s.h, sp, *t));
            let (d, sp) = pixel_terms(q, &s.l, highlight);
            // Below 2¹⁸·2¹⁶ each.
            let weigh = |v: u32| ((u64::from(s.weight) * u64::from(v) + (1 << 15)) >> 16) as u32;
            level = level.saturating_add(weigh(d)).min(1 << 16);
            specular = specular.saturating_add(weigh(sp)).min(1 << 16);
        }
        highlighted_channels::<C>(sample.color().channels(), level, specular)
    }

    #[inline(always)]
    fn step((n, d1): Self::Level, (_, d2): Self::Level) -> Self::Level {
        (add_each(n, d1), add_each(d1, d2))
    }
}

/// The span shader of the textured fills: depth test, texel coordinates (and light level) from
/// the perspective planes at the ends of chunks of up to [`CHUNK`](perspective::CHUNK) pixels
/// (short enough for the light's chords to stay within a quarter of the target's finest
/// channel step), the texture sampled between.
struct TexturedFill<'t, 'a, 'x, C, S, L, W> {
    target: &'t mut DepthTarget<'a, C>,
    sampler: Sampler<'x, S>,
    write: W,
    coordinates: (Corrected, Corrected),
    light: L,
}

impl<'t, 'a, 'x, C: GouraudColor, S, L: SpanLight, W> TexturedFill<'t, 'a, 'x, C, S, L, W> {
    /// The fill of `target` sampling with `sampler` at `coordinates`, lit by `light`.
    #[inline(always)]
    fn new(
        target: &'t mut DepthTarget<'a, C>,
        sampler: Sampler<'x, S>,
        write: W,
        coordinates: (Corrected, Corrected),
        light: L,
    ) -> Self {
        TexturedFill {
            target,
            sampler,
            write,
            coordinates,
            light,
        }
    }
}

impl<C, S, L, W> SpanShader<4> for TexturedFill<'_, '_, '_, C, S, L, W>
where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
    L: SpanLight,
    W: Opacity,
{
    type Steps = [u32; 4];

    /// Small faces (most of a mesh's) are scanned: the same spans without the walk's
    /// divisions.
    #[inline(always)]
    fn scans_small(&self) -> bool {
        true
    }

    #[inline(always)]
    fn prepare(&mut self, step: [u32; 4]) -> [u32; 4] {
        step
    }

    #[inline(always)]
    fn span(&mut self, &steps: &[u32; 4], span: Span, start: [u32; 4]) {
        let Some((colors, depths)) = self.target.clipped_spans_mut(span) else {
            return;
        };
        // The light's chords kept within a quarter of the finest channel step of the exact
        // levels (the coordinates' within the bound of chunks of 16: "Accuracy" above).
        let light = self.light;
        let ([_, dq, dp1, dp2], [_, q, p1, p2]) = (steps, start);
        let room = perspective::chunk_room(
            [q, p1, p2],
            [dq, dp1, dp2],
            affine_level::<C>() as u32,
            |k1, k2| light.slope(k1, k2),
        );
        // The target's span loop where it draws these texels and light (the same pixels).
        if arch::PERSPECTIVE_SPAN && !W::BLENDS {
            // The sampler first: a face's spans the loop does not sample stop at its kind.
            if let Some(((texels, x_mask, rows_mask, y_shift), bilinear)) =
                masked_565_texels(&self.sampler)
            {
                if let Some(level) = self.light.span_level() {
                    let ([dz, dq, dp1, dp2], [z, q, p1, p2]) = (steps, start);
                    let span = arch::PerspectiveSpan565 {
                        depth: (z, dz),
                        planes: [q, p1, p2],
                        steps: [dq, dp1, dp2],
                        u: self.coordinates.0.parts(),
                        v: self.coordinates.1.parts(),
                        level,
                        texels,
                        x_mask,
                        rows_mask,
                        y_shift,
                        chunk_room: room,
                        bilinear,
                    };
                    if C::perspective_span_565(colors, depths, &span) {
                        return;
                    }
                }
            }
        }
        // The target's chunk loop where it draws these texels unlit (the same pixels).
        let masked = if arch::DEPTH_MASKED_565 && self.light.plain() && !W::BLENDS {
            masked_565(&self.sampler)
        } else {
            None
        };
        let run = PerspectiveSpan {
            colors,
            depths,
            steps,
            start,
            coordinates: self.coordinates,
            light: self.light,
            room,
            masked,
            write: self.write,
        };
        self.sampler.run(run);
    }
}

/// One span of [`TexturedFill`]: its pixels and depths, the planes' steps and first values; its
/// pixels written as `W` writes them.
struct PerspectiveSpan<'p, C, L, W> {
    colors: &'p mut [C],
    depths: &'p mut [u16],
    steps: [u32; 4],
    start: [u32; 4],
    coordinates: (Corrected, Corrected),
    light: L,
    /// The span's [`perspective::chunk_room`].
    room: i32,
    /// The texels, masks and row shift of [`masked_565`], where the target's chunk loop draws
    /// the chunks' pixels.
    masked: Option<(&'p [u16], u32, u32, u32)>,
    write: W,
}

impl<C: GouraudColor, L: SpanLight, W: Opacity> SampledLoop<C> for PerspectiveSpan<'_, C, L, W> {
    type Output = ();

    /// The span's pixels with `texel` giving the colour at a 16.16 texel coordinate.
    #[inline(always)]
    fn run<T: Sampled<C>>(self, texel: impl Fn(i32, i32) -> T, y_shift: u32) {
        let (mut colors, mut depths, light) = (self.colors, self.depths, self.light);
        let [dz, dq, dp1, dp2] = self.steps;
        let [mut z, q, p1, p2] = self.start;
        let (u, v) = self.coordinates;
        let masked = self.masked.filter(|m| m.3 == y_shift);
        let len = colors.len().min(depths.len()) as u32;
        let mut at = None;
        for chunk in Chunks::new([q, p1, p2], [dq, dp1, dp2], len, self.room) {
            let (x, mut y, first) = at.unwrap_or_else(|| {
                let start = chunk.start;
                (u.at(start), v.at(start), light.end(start))
            });
            let end = (u.at(chunk.end), v.at(chunk.end), light.end(chunk.end));
            let (dx, dy) = (
                step_over(x, end.0, chunk.over),
                step_over(y, end.1, chunk.over) << y_shift,
            );
            y <<= y_shift;
            let (level, dl) = light.chunk(first, end.2, chunk.over);
            // The chunk's pixels as slices of their own: one counter for the loop.
            let n = chunk.len as usize;
            let (Some((c, rest_c)), Some((d, rest_d))) = (split(colors, n), split(depths, n))
            else {
                return;
            };
            let steps = (dz, dx, dy, dl);
            z = match masked {
                Some((texels, x_mask, rows, _))
                    if C::fill_depth_masked_565(
                        c,
                        d,
                        &arch::MaskedSpan565 {
                            texels,
                            x: (x, dx),
                            y: (y, dy),
                            x_mask,
                            rows,
                        },
                        (z, dz),
                    ) =>
                {
                    z.wrapping_add(dz.wrapping_mul(chunk.len))
                }
                _ if W::BLENDS => {
                    let opacity = self.write.opacity();
                    blended_pixels(c, d, (z, x, y, level), steps, &texel, light, opacity)
                }
                _ => chunk_pixels(c, d, (z, x, y, level), steps, &texel, light),
            };
            (colors, depths) = (rest_c, rest_d);
            at = Some(end);
        }
    }
}

/// The pixels of one chunk of a perspective span: [`pixels`] out of line, so that the loop has
/// the registers to itself (a call a chunk).
#[inline(never)]
fn chunk_pixels<C: GouraudColor, T: Sampled<C>, L: SpanLight>(
    colors: &mut [C],
    depths: &mut [u16],
    values: (u32, i32, i32, L::Level),
    steps: (u32, i32, i32, L::Level),
    texel: &impl Fn(i32, i32) -> T,
    light: L,
) -> u32 {
    pixels(colors, depths, values, steps, texel, light)
}

/// Depth-tested pixels, each the texel at its coordinate lit at its level, from the values
/// `(z, x, y, level)` at the first stepped by `steps`: the span loop of both textured fills.
/// The depth plane's value after the last.
#[inline(always)]
fn pixels<C: GouraudColor, T: Sampled<C>, L: SpanLight>(
    colors: &mut [C],
    depths: &mut [u16],
    (mut z, mut x, mut y, mut level): (u32, i32, i32, L::Level),
    (dz, dx, dy, dl): (u32, i32, i32, L::Level),
    texel: &impl Fn(i32, i32) -> T,
    light: L,
) -> u32 {
    for (px, depth) in colors.iter_mut().zip(depths.iter_mut()) {
        let z16 = (z >> DEPTH_SHIFT) as u16;
        if z16 < *depth {
            *depth = z16;
            *px = light.apply(texel(x, y), level);
        }
        z = z.wrapping_add(dz);
        x = x.wrapping_add(dx);
        y = y.wrapping_add(dy);
        level = L::step(level, dl);
    }
    z
}

/// [`pixels`] of a translucent draw: each pixel nearer than the depth there blended over the
/// colour there, the depth kept.
#[inline(never)]
fn blended_pixels<C: GouraudColor, T: Sampled<C>, L: SpanLight>(
    colors: &mut [C],
    depths: &mut [u16],
    (mut z, mut x, mut y, mut level): (u32, i32, i32, L::Level),
    (dz, dx, dy, dl): (u32, i32, i32, L::Level),
    texel: &impl Fn(i32, i32) -> T,
    light: L,
    opacity: u8,
) -> u32 {
    for (px, depth) in colors.iter_mut().zip(depths.iter()) {
        if ((z >> DEPTH_SHIFT) as u16) < *depth {
            *px = light.apply(texel(x, y), level).blend(*px, opacity);
        }
        z = z.wrapping_add(dz);
        x = x.wrapping_add(dx);
        y = y.wrapping_add(dy);
        level = L::step(level, dl);
    }
    z
}

/// The first `n` items of `items` and the rest, if it has `n`.
#[inline(always)]
fn split<T>(items: &mut [T], n: usize) -> Option<(&mut [T], &mut [T])> {
    // Not `then` and `split_at_mut`: where `then` is not inlined (`opt-level` "s", "z"), the
    // split's own length check is a panic path.
    items.split_at_mut_checked(n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::Rgb565Texels;
    use embedded_graphics::pixelcolor::raw::RawU16;
    use embedded_graphics::pixelcolor::Rgb565;

    /// The textured row loop's texels, masks and shift read the sampled texels.
    #[test]
    fn masked_565_reads_the_nearest_texels() {
        let mut next = crate::random(0x7e47_0006);
        let texels: [u16; 1 << 16] = core::array::from_fn(|_| next() as u16);
        let shapes = [
            (256, 256),
            (64, 32),
            (1, 4096),
            (4096, 1),
            (8, 2),
            (1, 1),
            (16, 256),
        ];
        for n in 0..4_000 {
            let (w, h) = shapes[n % shapes.len()];
            let texture = Texture::new(Rgb565Texels(&texels), w, h).unwrap();
            let sampler = Sampler::new(&texture);
            let (words, x_mask, rows_mask, y_shift) = masked_565(&sampler).unwrap();
            assert!(((rows_mask | x_mask) as usize) < words.len());
            let (x, y) = (next() as i32, next() as i32);
            let index = (((y << y_shift) >> 16) as u32 & rows_mask) | ((x >> 16) as u32 & x_mask);
            let got = Rgb565::from(RawU16::new(words[index as usize]));
            assert_eq!(got, texture.nearest(x, y), "{w}×{h}");
        }
        // Other filters: the portable loop.
        let texture = Texture::new(Rgb565Texels(&texels), 64, 64).unwrap();
        let bilinear = texture.with_filter(crate::texture::Filter::Bilinear);
        assert!(masked_565(&Sampler::new(&bilinear)).is_none());
    }

    /// The textured row loop's form of the coordinate maps reads the plane values as
    /// `PlaneMap::at` does, for coordinates of any spread (or declines).
    #[test]
    fn shift_maps_are_the_plane_maps() {
        let mut next = crate::random(0x7e47_0005);
        let mut declined = 0;
        for n in 0..20_000 {
            let spread = 1u64 << (n % 33);
            let lo = next() as i32;
            let c = [(); 3].map(|_| (i64::from(lo) + (next() % spread) as i64) as i32);
            let (map, _) = PlaneMap::new(c);
            let Some((base, down)) = shift_map(&map) else {
                declined += 1;
                continue;
            };
            for _ in 0..8 {
                let value = next() as u32;
                assert_eq!(base.wrapping_add((value >> down) as i32), map.at(value));
            }
        }
        // Only coordinates spread over nearly 2³² units shift left.
        assert!(declined < 20_000 / 33 * 2, "{declined}");
    }

    /// `nearly_affine`'s bound, in f64: screen-space interpolation departs from the
    /// perspective-correct value by at most `s·(q_max − q_min) / (4·q_min)` anywhere in a
    /// triangle, and by nearly that much along an edge from `q_min` to `q_max` when the ratio is
    /// near 1 (so a bound half as large would be wrong).
    #[test]
    fn screen_space_departure_is_within_a_quarter() {
        let mut next = crate::random(0x7e47_0007);
        let mut unit = move || (next() >> 40) as f64 / (1u64 << 24) as f64;
        let mut closest = 0.0f64;
        for n in 0..4_000 {
            let ratio = 1.0 + [0.001, 0.05, 1.0, 19.0][n % 4] * unit();
            let q = [(); 3].map(|_| 1.0 + (ratio - 1.0) * unit());
            let a = [(); 3].map(|_| 100.0 * unit() - 50.0);
            let (lo, hi) = (q[0].min(q[1]).min(q[2]), q[0].max(q[1]).max(q[2]));
            let s = a[0].max(a[1]).max(a[2]) - a[0].min(a[1]).min(a[2]);
            let bound = s * (hi - lo) / (4.0 * lo);
            let mut worst = 0.0f64;
            for i in 0..=32 {
                for j in 0..=32 - i {
                    let b = [i, j, 32 - i - j].map(|k| f64::from(k) / 32.0);
                    let big_q: f64 = (0..3).map(|k| b[k] * q[k]).sum();
                    let exact: f64 = (0..3).map(|k| b[k] * q[k] * a[k]).sum::<f64>() / big_q;
                    let screen: f64 = (0..3).map(|k| b[k] * a[k]).sum();
                    worst = worst.max((exact - screen).abs());
                }
            }
            assert!(worst <= bound * (1.0 + 1e-9) + 1e-12, "{worst} > {bound}");
            // Two vertices at the extremes of both: the edge between them comes close.
            let edge = |t: f64| {
                let big_q = (1.0 - t) + t * ratio;
                (t * ratio * s / big_q - t * s).abs()
            };
            let peak = (1..100)
                .map(|k| edge(f64::from(k) / 100.0))
                .fold(0.0, f64::max);
            closest = closest.max(peak / (s * (ratio - 1.0) / 4.0));
        }
        assert!(closest > 0.99, "{closest}");
    }
}
