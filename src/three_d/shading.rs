//! Lambert lighting and depth-tested triangle fills: flat, Gouraud, and per-pixel lighting with
//! quadratic normal interpolation.
//!
//! All three fills take a triangle already in screen space ([`ScreenVertex`]: sub-pixel position
//! and 16-bit depth), cover exactly the pixels [`SolidTriangle`](crate::SolidTriangle) covers, and
//! test and write a caller-owned z-buffer per pixel ([`DepthTarget`]: smaller is nearer, a pixel is
//! written only if strictly nearer). They are span shaders of the raster core, like the 2D
//! drawables: the same set-up, walk and attribute planes, with the depth as the first plane and
//! the depth test and write in the span loop.
//!
//! * [`draw_flat`]: one colour per face, typically `shade(color, light.level(face_normal))`.
//! * [`draw_gouraud`]: per-vertex colours interpolated like [`GouraudTriangle`](crate::GouraudTriangle),
//!   with its colours where nothing is nearer.
//! * [`draw_quadratic`]: per-pixel Lambert lighting of the normal field
//!
//!   `N(c) = Σ Nᵢ cᵢ(2cᵢ − 1) + Σ 4 N̂ᵢⱼ cᵢ cⱼ`, with `N̂ᵢⱼ = normalize(Nᵢ + Nⱼ)`,
//!
//!   the quadratic (P2) interpolant through the vertex normals and the normalised edge-midpoint
//!   normals ([`QuadraticNormals`]). Along a row the barycentrics are linear in `x`, so `N` is
//!   quadratic in `x`: each span restarts from the barycentrics at its first pixel and then steps
//!   the value by forward differences (two additions per component and pixel, 40 fractional
//!   bits). The lit intensity `max(0, N·L) / |N|` uses the table-and-Newton [`inv_sqrt`]: no
//!   division, no floating point.
//!
//! Unlike linear interpolation, whose normals shrink towards the middle of a face by
//! `1 − cos(θ/2)` for vertex normals `θ` apart, the quadratic field hits the unit sphere at the
//! vertices and edge midpoints and stays within a fraction of that deviation elsewhere; the
//! renormalisation then has much less to correct and the highlight moves smoothly across faces.
//!
//! A [`Material`] with a Blinn-Phong [`Specular`] highlight is drawn by the pipeline's
//! highlighted fills: the colour `base · level + specular · max` per channel (`max` the
//! channel's maximum: white light), rounded once and saturating. Flat: one colour a face from its
//! normal. Gouraud: the specular term at the vertices (16 bits) as a second plane next to the
//! light level, added per pixel. Quadratic: the stepped normal rounded to 16 fractional bits and
//! renormalised once for both `n̂·l` and `n̂·ĥ` (the power magnifies the cosine's error by up to
//! the shininess, so it needs more than the 14 bits of the plain fill). Flat and Gouraud faces
//! whose specular terms are all 0 take the plain fills: the same pixels as without a highlight.
//!
//! With the pipeline's [`Lights`](super::Lights), the quadratic fill lights each pixel by the
//! first light and every source (a point light's direction, half vector and falloff taken at the
//! face's centroid), the 16-bit normal renormalised once a light, the levels and highlights
//! summed and saturating at 1 (`fill_quadratic_lights`, the highlighted fill's loops with the
//! sources added out of line): as the textured per-pixel light sums them. Faces no source
//! reaches take the fills above.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Gray8, prelude::*, primitives::Rectangle};
//! use embedded_raster::three_d::{Scalar, Vec3};
//! use embedded_raster::three_d::{DepthTarget, ScreenVertex};
//! use embedded_raster::three_d::{draw_quadratic, Light, QuadraticNormals};
//! use embedded_raster::Coord;
//!
//! let (mut px, mut z) = ([Gray8::BLACK; 16 * 16], [0u16; 16 * 16]);
//! let mut target = DepthTarget::new(&mut px, &mut z, 16, 16).unwrap();
//! target.clear(Gray8::BLACK);
//! let v = |x: i32, y: i32| ScreenVertex::new(Coord::from_num(x), Coord::from_num(y), 1000);
//! let up = Vec3::from_bits(0, 0, 1 << 16);
//! let normals = QuadraticNormals::new([up; 3]);
//! let light = Light::new(up, Scalar::ZERO);
//! let clip = Rectangle::new(Point::zero(), Size::new(16, 16));
//! draw_quadratic(&mut target, &clip, &[v(0, 0), v(16, 0), v(0, 16)], &normals, &light, Gray8::WHITE);
//! assert_eq!(target.framebuffer().get(2, 2), Some(Gray8::WHITE));
//! assert_eq!(target.depth_at(2, 2), Some(1000));
//! ```

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::depth::{Blend, DepthTarget, ScreenVertex};
use super::light::{Highlight, Light, PixelSource, Specular};
use super::math::{
    inv_sqrt, normalize_wide, sat32, zip3_with, zip_with, Bary, Scalar, Vec3, BARY_ONE,
};
use super::vertex::ProjectedVertex;
use crate::arch::{self, FaceSetup};
use crate::color::{scale_channels, GouraudColor, SpanSteps};
use crate::draw::SpanColors;
use crate::raster::arith::mul_i32_wide;
use crate::raster::band::{AllRows, RowWindow};
use crate::raster::edge::TriangleSetup;
use crate::raster::plane::{Attributes, InverseArea, STEP_BITS as STEP_BITS_PLANES};
use crate::raster::runs::SmallScan;
use crate::raster::scan::{self, KeptWords};
use crate::raster::walk::{last_of, Band};
use crate::raster::{Span, SpanShader};

/// How a mesh is lit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Shading {
    /// The material colour, no lighting.
    Unlit,
    /// One Lambert intensity per face, from its geometric normal.
    #[default]
    Flat,
    /// Lambert intensity per vertex, colours interpolated across the face.
    Gouraud,
    /// Lambert intensity per pixel from the quadratically interpolated normal.
    Quadratic,
}

/// A surface colour and how it is lit.
///
/// # Examples
///
/// One triangle facing the camera, drawn in three materials under a light from the side
/// (edge-on to the triangle: lit materials get the ambient level alone, a quarter):
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
/// use embedded_raster::three_d::{Angle, DepthTarget, Light, Mat4, Material, Mesh, Pipeline};
/// use embedded_raster::three_d::{Shading, Specular, Vec3};
///
/// static VERTICES: [Vec3; 3] = [
///     Vec3::from_bits(-65536, -65536, 0),
///     Vec3::from_bits(65536, -65536, 0),
///     Vec3::from_bits(0, 65536, 0),
/// ];
/// static NORMALS: [Vec3; 3] = [Vec3::from_bits(0, 0, 65536); 3];
/// let triangle = Mesh::new(&VERTICES, &NORMALS, &[[0, 1, 2]]);
///
/// let camera = Mat4::perspective(Angle::from_degrees(60), 1, 0.5, 20).unwrap()
///     * Mat4::translation(Vec3::new(0, 0, -3));
/// let viewport = Rectangle::new(Point::zero(), Size::new(16, 16));
/// let light = Light::new(Vec3::new(1, 0, 0), 0.25);
/// let pipeline = Pipeline::new(Mat4::IDENTITY, camera, viewport, light);
/// let centre = |material: Material<Rgb565>| {
///     let (mut pixels, mut depth) = ([Rgb565::BLACK; 16 * 16], [0u16; 16 * 16]);
///     let mut target = DepthTarget::new(&mut pixels, &mut depth, 16, 16).unwrap();
///     pipeline.draw_mesh(&triangle, &material, &mut target);
///     target.framebuffer().get(8, 8).unwrap()
/// };
///
/// // Unlit: the colour itself. Lit: a quarter of it, each channel rounded.
/// assert_eq!(centre(Material::new(Rgb565::WHITE, Shading::Unlit)), Rgb565::WHITE);
/// assert_eq!(centre(Material::new(Rgb565::WHITE, Shading::Flat)), Rgb565::new(8, 16, 8));
/// assert_eq!(centre(Material::new(Rgb565::WHITE, Shading::Gouraud)), Rgb565::new(8, 16, 8));
///
/// // `new` is a `const fn`: materials can live in flash. `with_specular` adds a highlight
/// // ([`Specular`] has an example).
/// const PAINT: Material<Rgb565> = Material::new(Rgb565::CSS_ORANGE, Shading::Quadratic);
/// let shiny = PAINT.with_specular(Specular::new(0.5, 32));
/// assert_eq!(shiny.specular.map(|s| s.shininess()), Some(32));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Material<C> {
    /// Colour of a fully lit surface.
    pub color: C,
    /// Lighting model.
    pub shading: Shading,
    /// A Blinn-Phong highlight added to the lit colour (flat: per face, Gouraud: per vertex and
    /// interpolated, quadratic: per pixel; none unlit), or none.
    ///
    /// The colour is `base · (ambient + (1 − ambient)·diffuse) + specular` in every channel,
    /// the specular term as white light (each channel's maximum times it), saturating.
    pub specular: Option<Specular>,
    /// Opacity, 0 (transparent) to 255 (opaque, the default). A translucent material (below
    /// 255) is drawn depth-tested without writing depth, its lit colour blended over each pixel
    /// at this opacity ([`GouraudColor::blend`]) — by every draw of an untextured mesh: the
    /// pipeline's, with and without a vertex scratch, a depth band's and a mesh bin's. Draw the
    /// opaque meshes first, then the translucent ones from the farthest to the nearest; a mesh
    /// whose faces overlap on screen (not convex, or without culling) blends them in the order
    /// of its faces — the order is the caller's to choose.
    pub opacity: u8,
}

impl<C> Material<C> {
    /// A material of `color` lit with `shading`, opaque, without a highlight.
    pub const fn new(color: C, shading: Shading) -> Self {
        Material {
            color,
            shading,
            specular: None,
            opacity: 255,
        }
    }

    /// The material at `opacity` ([`opacity`](Self::opacity) says how it draws).
    ///
    /// ```
    /// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
    /// use embedded_raster::three_d::meshes::icosphere::ICOSPHERE;
    /// use embedded_raster::three_d::Angle;
    /// use embedded_raster::{DepthTarget, GouraudColor, Light, Mat4, Material, Pipeline};
    /// use embedded_raster::{Shading, Vec3};
    ///
    /// let (mut pixels, mut depth) = ([Rgb565::BLUE; 32 * 32], [0u16; 32 * 32]);
    /// let mut target = DepthTarget::new(&mut pixels, &mut depth, 32, 32).unwrap();
    /// let camera = Mat4::perspective(Angle::from_degrees(60), 1, 0.5, 20).unwrap()
    ///     * Mat4::translation(Vec3::new(0, 0, -3));
    /// let viewport = Rectangle::new(Point::zero(), Size::new(32, 32));
    /// let pipeline = Pipeline::new(Mat4::IDENTITY, camera, viewport, Light::default());
    /// let glass = Material::new(Rgb565::WHITE, Shading::Unlit).with_opacity(128);
    /// pipeline.draw_mesh(&ICOSPHERE, &glass, &mut target);
    /// assert_eq!(target.framebuffer().get(16, 16), Some(Rgb565::WHITE.blend(Rgb565::BLUE, 128)));
    /// assert_eq!(target.depth_at(16, 16), Some(u16::MAX)); // not written
    /// ```
    ///
    /// [`GouraudColor::blend`]: crate::GouraudColor::blend
    pub const fn with_opacity(self, opacity: u8) -> Self
    where
        C: Copy,
    {
        Material { opacity, ..self }
    }

    /// The material with the highlight `specular` ([`Specular`] has an example).
    pub fn with_specular(self, specular: Specular) -> Self {
        Material {
            specular: Some(specular),
            ..self
        }
    }
}

/// `color` with every channel multiplied by `level` (in `[0, 1]`), rounded to nearest.
pub fn shade<C: GouraudColor>(color: C, level: Scalar) -> C {
    let l = level.to_bits().clamp(0, 1 << 16) as u32;
    scale_channels::<C>(color.channels(), l)
}

/// The colour of a lit, highlighted surface: `base · level + specular · max` in every channel
/// (`max` the channel's maximum: a white highlight), rounded once and saturating at `max`;
/// `level` and `specular` with 16 fractional bits (up to a little above 2¹⁶).
#[inline(always)]
pub(super) fn highlighted_channels<C: GouraudColor>(base: [u8; 3], level: u32, specular: u32) -> C {
    let (level, specular) = (level.min(1 << 17), specular.min(1 << 17));
    // Below 2²⁶: 255 · 2¹⁷ twice.
    let s = |c: u8, max: u8| {
        let v = (u32::from(c) * level + u32::from(max) * specular + (1 << 15)) >> 16;
        v.min(u32::from(max)) as u8
    };
    let [m0, m1, m2] = C::MAX;
    C::from_channels([s(base[0], m0), s(base[1], m1), s(base[2], m2)])
}

/// The quadratic normal field of a triangle: its values at the three vertices and the three edge
/// midpoints (the nodes of the P2 interpolant).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct QuadraticNormals {
    /// `Nᵢ`, the normals at the vertices.
    pub(crate) vertices: [Vec3; 3],
    /// The normals at the midpoints of edges 0–1, 1–2 and 2–0.
    pub(crate) midpoints: [Vec3; 3],
}

impl QuadraticNormals {
    /// The field through unit vertex normals `n` (normalised here) with
    /// `N̂ᵢⱼ = normalize(Nᵢ + Nⱼ)` at the edge midpoints. Opposite normals give a zero midpoint.
    pub fn new(n: [Vec3; 3]) -> Self {
        Self::of_unit(n.map(Vec3::normalize))
    }

    /// [`new`](Self::new) of normals already of unit length (not normalised again).
    pub(crate) fn of_unit(n: [Vec3; 3]) -> Self {
        let mid = |a: Vec3, b: Vec3| {
            let (a, b) = (a.to_bits(), b.to_bits());
            normalize_wide(zip_with(a, b, |a, b| i64::from(a) + i64::from(b)))
        };
        QuadraticNormals {
            vertices: n,
            midpoints: [mid(n[0], n[1]), mid(n[1], n[2]), mid(n[2], n[0])],
        }
    }

    /// The field through the given nodes, each normalised (a zero node stays zero): vertex
    /// normals and the normals at the midpoints of edges 0–1, 1–2 and 2–0.
    pub fn from_nodes(vertices: [Vec3; 3], midpoints: [Vec3; 3]) -> Self {
        QuadraticNormals {
            vertices: vertices.map(Vec3::normalize),
            midpoints: midpoints.map(Vec3::normalize),
        }
    }

    /// The unit normals at the vertices.
    pub const fn vertices(&self) -> [Vec3; 3] {
        self.vertices
    }

    /// The unit normals at the midpoints of edges 0–1, 1–2 and 2–0.
    pub const fn midpoints(&self) -> [Vec3; 3] {
        self.midpoints
    }

    /// The (unnormalised) normal at barycentric coordinates `c` (`c₀ + c₁ + c₂ = 1`).
    pub fn at(&self, c: [Scalar; 3]) -> Vec3 {
        self.at_bary(c.map(|v| v.to_bits().saturating_mul(1 << 14)))
    }

    /// [`at`](Self::at) with 30 fractional bits.
    pub(crate) fn at_bary(&self, c: Bary) -> Vec3 {
        let c = c.map(i64::from);
        let one = i64::from(BARY_ONE);
        let sq = |a: i64| a.saturating_mul(2 * a - one) >> 30;
        let pr = |a: i64, b: i64| (4 * a).saturating_mul(b) >> 30;
        let w = [
            sq(c[0]),
            sq(c[1]),
            sq(c[2]),
            pr(c[0], c[1]),
            pr(c[1], c[2]),
            pr(c[2], c[0]),
        ];
        let nodes = [
            self.vertices[0],
            self.vertices[1],
            self.vertices[2],
            self.midpoints[0],
            self.midpoints[1],
            self.midpoints[2],
        ];
        let comp = |k: usize| {
            let acc: i64 = w
                .iter()
                .zip(nodes.iter())
                .map(|(w, n)| {
                    let n = n.to_bits().get(k).copied().unwrap_or(0);
                    w.saturating_mul(i64::from(n))
                })
                .fold(0, i64::saturating_add);
            sat32(acc.saturating_add(1 << 29) >> 30)
        };
        Vec3::from_bits(comp(0), comp(1), comp(2))
    }

    /// The same field on a sub-triangle whose vertices have barycentric coordinates `b[k]` (30
    /// fractional bits) in this triangle: a quadratic restricted to a sub-triangle is again the
    /// quadratic through its values at the sub-triangle's vertices and edge midpoints.
    pub(crate) fn restricted(&self, b: [Bary; 3]) -> Self {
        let mid =
            |p: Bary, q: Bary| zip_with(p, q, |p, q| ((i64::from(p) + i64::from(q)) >> 1) as i32);
        QuadraticNormals {
            vertices: b.map(|c| self.at_bary(c)),
            midpoints: [
                self.at_bary(mid(b[0], b[1])),
                self.at_bary(mid(b[1], b[2])),
                self.at_bary(mid(b[2], b[0])),
            ],
        }
    }
}

/// Fractional bits of the stepped normal components.
const STEP_BITS: u32 = 40;

/// The quadratic normal field of one screen triangle, ready to be stepped along spans.
///
/// With `u = c₀`, `v = c₁` and `c₂ = 1 − u − v`, `N = K₀ + K₁u + K₂v + K₃u² + K₄uv + K₅v²`.
/// Along a row `u = u₀ + g_u·t`, `v = v₀ + g_v·t`, so `N(t) = N₀ + B·t + C·t²` with
/// `C = K₃g_u² + K₄g_u g_v + K₅g_v²` the same for the whole triangle; the forward differences are
/// `Δ₁ = B + C` and `Δ₂ = 2C`.
#[derive(Debug, Clone, Copy)]
struct NormalPlane {
    /// `K₀ … K₅` per component, 16 fractional bits.
    k: [[i64; 3]; 6],
    /// `K₁g_u + K₂g_v`, [`STEP_BITS`] fractional bits.
    b0: [i64; 3],
    /// `C`, [`STEP_BITS`] fractional bits.
    c: [i64; 3],
    /// `g_u`, `g_v` per pixel with 32 fractional bits.
    g32: [i64; 2],
}

impl NormalPlane {
    fn new(n: &QuadraticNormals, setup: &TriangleSetup, inverse: &InverseArea) -> Self {
        let v = n.vertices.map(|v| v.to_bits().map(i64::from));
        let m = n.midpoints.map(|v| v.to_bits().map(i64::from));
        let (n0, n1, n2) = (v[0], v[1], v[2]);
        let (m01, m12, m20) = (m[0], m[1], m[2]);
        let m20_m12 = zip_with(m20, m12, |a, b| a + b);
        let k = [
            n2,
            zip3_with(n0, n2, m20, |n0, n2, m20| -n0 - 3 * n2 + 4 * m20),
            zip3_with(n1, n2, m12, |n1, n2, m12| -n1 - 3 * n2 + 4 * m12),
            zip3_with(n0, n2, m20, |n0, n2, m20| 2 * n0 + 2 * n2 - 4 * m20),
            zip3_with(n2, m01, m20_m12, |n2, m01, m| 4 * n2 + 4 * m01 - 4 * m),
            zip3_with(n1, n2, m12, |n1, n2, m12| 2 * n1 + 2 * n2 - 4 * m12),
        ];
        // dc_k/dx per pixel: the edge opposite input vertex k changes by 256·a per pixel.
        let gradient = |vertex: usize| {
            let j = setup.order.iter().position(|&o| o == vertex).unwrap_or(0);
            let a = setup.edge(j).a;
            inverse.scale(i128::from(a) << 8, STEP_BITS)
        };
        let (gu, gv) = (gradient(0), gradient(1));
        let limit = (1i128 << STEP_BITS) + 2;
        // Covered pixel centres have every cₖ in [0, 1], so two adjacent covered pixels imply
        // |g| ≤ 1 for all three gradients. Larger gradients mean one-pixel spans: no stepping.
        let (gu, gv) = if gu.abs() > limit || gv.abs() > limit || (gu + gv).abs() > limit {
            (0, 0)
        } else {
            (gu as i64, gv as i64)
        };
        let shift = 16 + 2 * STEP_BITS - STEP_BITS;
        let (gu2, guv, gv2) = (
            i128::from(gu) * i128::from(gu),
            i128::from(gu) * i128::from(gv),
            i128::from(gv) * i128::from(gv),
        );
        let c = zip3_with(k[3], k[4], k[5], |k3, k4, k5| {
            let sum = i128::from(k3) * gu2 + i128::from(k4) * guv + i128::from(k5) * gv2;
            (sum >> shift) as i64
        });
        let b0 = zip_with(k[1], k[2], |k1, k2| {
            (k1.wrapping_mul(gu)).wrapping_add(k2.wrapping_mul(gv)) >> 16
        });
        NormalPlane {
            k,
            b0,
            c,
            g32: [gu >> 8, gv >> 8],
        }
    }

    /// Value and first difference at a span start with `u`, `v` in 30 fractional bits.
    #[inline]
    fn start(&self, u: i64, v: i64) -> ([i64; 3], [i64; 3]) {
        let k = &self.k;
        let (uu, uv, vv) = ((u * u) >> 30, (u * v) >> 30, (v * v) >> 30);
        let su = (u.wrapping_mul(self.g32[0])) >> 32;
        let suv = (u.wrapping_mul(self.g32[1]) >> 32) + (v.wrapping_mul(self.g32[0]) >> 32);
        let sv = (v.wrapping_mul(self.g32[1])) >> 32;
        let mut value = [0i64; 3];
        let mut d1 = [0i64; 3];
        for i in 0..3 {
            let lin = k[1][i]
                .wrapping_mul(u)
                .wrapping_add(k[2][i].wrapping_mul(v))
                .wrapping_add(k[3][i].wrapping_mul(uu))
                .wrapping_add(k[4][i].wrapping_mul(uv))
                .wrapping_add(k[5][i].wrapping_mul(vv));
            value[i] = (k[0][i] << (STEP_BITS - 16)).wrapping_add(lin >> (46 - STEP_BITS));
            let b = (2 * k[3][i])
                .wrapping_mul(su)
                .wrapping_add(k[4][i].wrapping_mul(suv))
                .wrapping_add((2 * k[5][i]).wrapping_mul(sv));
            d1[i] = self.b0[i]
                .wrapping_add(b >> (46 - STEP_BITS))
                .wrapping_add(self.c[i]);
        }
        (value, d1)
    }
}

/// A barycentric coordinate read from a plane with vertex values `{65535, 0, 0}` (8.8: 1/256 of
/// the planes' 8-bit scale), as 30 fractional bits: `raw = c·65535·2^16 + 2^15`.
#[inline(always)]
fn bary_from_plane(raw: u32) -> i64 {
    let r = i64::from(raw) - (1 << 15);
    // ·65536/65535 = ·(1 + 2^-16 + …): c with 32 fractional bits, then 30.
    (r + (r >> 16)) >> 2
}

/// Fractional bits of a depth read from a plane: 16-bit depths are 8.8 values of the planes'
/// 8-bit scale, which carries 24 fractional bits.
pub(super) const DEPTH_SHIFT: u32 = STEP_BITS_PLANES - 8;

/// Half a depth unit, the depth plane's rounding offset.
pub(super) const DEPTH_HALF: u32 = 1 << (DEPTH_SHIFT - 1);

/// The rounding term of the Gouraud fill's light-level plane: ½ of its 8.8 level's unit (the
/// pixel takes the nearest of the 256 levels).
const LEVEL_HALF: u32 = 1 << (STEP_BITS_PLANES - 1);

/// The planes' attributes: the depths first, then `M` more per vertex with their rounding
/// offsets.
#[inline(always)]
pub(super) fn with_depth<const M: usize, const N: usize>(
    vertices: [&ScreenVertex; 3],
    more: [[u16; M]; 3],
    half: [u32; M],
) -> Attributes<N> {
    debug_assert!(N == M + 1);
    Attributes {
        values: core::array::from_fn(|v| {
            core::array::from_fn(|k| match k {
                0 => vertices[v].depth,
                k => more[v].get(k - 1).copied().unwrap_or(0),
            })
        }),
        half: core::array::from_fn(|k| match k {
            0 => DEPTH_HALF,
            k => half.get(k - 1).copied().unwrap_or(0),
        }),
    }
}

/// A depth-tested fill: the raster core hands it the spans of a triangle with the depth first
/// among the attributes; the depth test and write are in the span loop, and `pixel` gives the
/// colour of a pixel that passes from the other attributes (stepped per pixel).
struct DepthFill<'t, 'a, C, P, const N: usize> {
    target: &'t mut DepthTarget<'a, C>,
    step: [u32; N],
    pixel: P,
}

/// What a [`DepthFill`] writes at a pixel that passes the depth test.
trait DepthPixel<C, const N: usize> {
    /// Whether small triangles may take the scan with its own planes ([`Planes::small`]): not
    /// where the colours must be [`GouraudTriangle`](crate::GouraudTriangle)'s.
    ///
    /// [`Planes::small`]: crate::raster::plane::Planes
    const SCANS_SMALL: bool = true;
    /// Once per triangle: the attributes' per-pixel steps.
    fn prepare(&mut self, _step: &[u32; N]) {}
    /// Once per span: its attributes at the first pixel and its length.
    fn start(&mut self, _values: &[u32; N], _len: u32) {}
    /// The colour of the current pixel, from the attributes `values`.
    fn color(&mut self, values: &[u32; N]) -> C;
    /// Moves to the next pixel.
    fn advance(&mut self) {}
    /// All rows of a small triangle at once into `target` (a target's row loop): `true` if
    /// drawn, `false` (the default) to be handed its spans.
    fn rows(&mut self, _target: &mut DepthTarget<'_, C>, _scan: &SmallScan<'_, N>) -> bool {
        false
    }
}

impl<C: PixelColor, P: DepthPixel<C, N>, const N: usize> SpanShader<N>
    for DepthFill<'_, '_, C, P, N>
{
    type Steps = ();

    #[inline(always)]
    fn scans_small(&self) -> bool {
        P::SCANS_SMALL
    }

    #[inline(always)]
    fn prepare(&mut self, step: [u32; N]) {
        self.step = step;
        self.pixel.prepare(&step);
    }

    #[inline(always)]
    fn small_rows(&mut self, scan: &SmallScan<'_, N>) -> bool {
        // A translucent draw takes its spans: the row loops write depth.
        self.target.blend().is_none() && self.pixel.rows(self.target, scan)
    }

    #[inline(always)]
    fn span(&mut self, _: &(), span: Span, start: [u32; N]) {
        // A translucent draw in progress (a test a span: about 0.7 % of the Gouraud spot frame).
        let blend = self.target.blend();
        let Some((colors, depths)) = self.target.clipped_spans_mut(span) else {
            return;
        };
        let mut v = start;
        self.pixel.start(&v, span.len());
        if let Some(blend) = blend {
            blended_span(colors, depths, v, self.step, &mut self.pixel, blend);
            return;
        }
        for (px, d) in colors.iter_mut().zip(depths.iter_mut()) {
            let z = v.first().map_or(0, |z| (z >> DEPTH_SHIFT) as u16);
            if z < *d {
                *d = z;
                *px = self.pixel.color(&v);
            }
            for (value, step) in v.iter_mut().zip(self.step) {
                *value = value.wrapping_add(step);
            }
            self.pixel.advance();
        }
    }
}

/// A span of a translucent draw: depth-tested without writing depth, each passing pixel's
/// colour blended over the one there. Out of line: opaque draws keep their loop as it was.
#[inline(never)]
fn blended_span<C: Copy, P: DepthPixel<C, N>, const N: usize>(
    colors: &mut [C],
    depths: &mut [u16],
    start: [u32; N],
    step: [u32; N],
    pixel: &mut P,
    blend: Blend<C>,
) {
    let mut v = start;
    for (px, d) in colors.iter_mut().zip(depths.iter()) {
        let z = v.first().map_or(0, |z| (z >> DEPTH_SHIFT) as u16);
        if z < *d {
            *px = (blend.over)(pixel.color(&v), *px, blend.opacity);
        }
        for (value, step) in v.iter_mut().zip(step) {
            *value = value.wrapping_add(step);
        }
        pixel.advance();
    }
}

/// A clip rectangle inside a frame's bounds, and which of its rows the fills draw where
/// ([`RowWindow`]: all of them into a target of the frame's size, or a band's into the band's
/// buffer). The pipeline makes one per draw; the public fills one per call.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TargetClip<R = AllRows> {
    rect: Rectangle,
    /// The rectangle's first column and row and its last column and row, for the face set-up
    /// where there is one (nothing elsewhere).
    bounds: arch::ClipBounds,
    rows: R,
}

impl TargetClip {
    /// The part of `clip` inside `target`, for any `clip` (reaching past `i32::MAX` too): computed
    /// in `i64`, empty when they do not overlap.
    pub(crate) fn new<C: PixelColor>(clip: &Rectangle, target: &DepthTarget<'_, C>) -> Self {
        TargetClip::of_frame(clip, &target.bounding_box(), AllRows)
    }
}

impl<R: RowWindow> TargetClip<R> {
    /// The part of `clip` inside `frame`, drawn through `rows`.
    pub(crate) fn of_frame(clip: &Rectangle, frame: &Rectangle, rows: R) -> Self {
        let rect = crate::rect::intersection(clip, frame);
        let (x, y, size) = (rect.top_left.x, rect.top_left.y, rect.size);
        let last = [last_of(x, size.width), last_of(y, size.height)];
        TargetClip {
            rect,
            bounds: arch::ClipBounds::new([x, y, last[0], last[1]]),
            rows,
        }
    }

    /// The rows drawn.
    #[inline(always)]
    pub(crate) fn rows(&self) -> &R {
        &self.rows
    }

    /// The face of `v` for the assembly's set-up of the Gouraud fill ([`arch::level_face`]):
    /// this clip's bounds and rows (a band's, or every row of a frame from row 0), the depth
    /// and level planes' rounding.
    #[inline(always)]
    fn level_face<'v>(&self, v: [&'v ProjectedVertex; 3]) -> arch::LevelFace<'v> {
        arch::LevelFace::new(v, self.bounds, [DEPTH_HALF, LEVEL_HALF], self.face_rows())
    }

    /// [`level_face`](Self::level_face) without its vertices, for a face scan to set.
    fn level_faces(&self) -> arch::LevelFace<'static> {
        arch::LevelFace::without_vertices(self.bounds, [DEPTH_HALF, LEVEL_HALF], self.face_rows())
    }

    /// What the faces of a draw have in common for the assembly's set-up of the textured fill
    /// ([`arch::textured_face`]; each face's vertices, texels and light are set by
    /// [`arch::TexturedTemplate::face`]): this clip's bounds and rows, the depth plane's
    /// rounding (the other planes' is 0), the texels' `masks` and the levels' bound
    /// `affine_level`.
    #[inline(always)]
    pub(super) fn textured_template(
        &self,
        masks: (u32, u32, u32),
        affine_level: u32,
    ) -> arch::TexturedTemplate {
        let (bounds, rows, half) = (self.bounds, self.face_rows(), [DEPTH_HALF, 0, 0, 0]);
        arch::TexturedTemplate::new(bounds, half, rows, masks, affine_level)
    }

    /// `template` (a [`textured_template`](Self::textured_template)) inside this clip instead.
    #[inline(always)]
    pub(super) fn textured_reclipped(
        &self,
        template: &arch::TexturedTemplate,
    ) -> arch::TexturedTemplate {
        template.with_clip(self.bounds, self.face_rows())
    }

    /// The rows the assembly's set-ups draw, first and last: a band's, or every row of a frame
    /// from row 0.
    #[inline(always)]
    fn face_rows(&self) -> [i32; 2] {
        // Every row: the clip of a frame from (0, 0) (rows above 0 would be skipped).
        debug_assert!(self.rows.band().is_some() || self.rect.top_left.y >= 0);
        self.rows
            .band()
            .map_or([0, i32::MAX], |b| [b.first, b.last])
    }

    /// The clip with a row more on each side of its window ([`RowWindow::widened`]).
    pub(crate) fn widened(&self) -> Self {
        TargetClip {
            rows: self.rows.widened(),
            ..*self
        }
    }

    /// The rectangle drawn in.
    pub(crate) fn rect(&self) -> Rectangle {
        self.rect
    }
}

/// Draws the depth-tested triangle `vertices` with `attributes` (the depth first) and `pixel`,
/// inside `clip`.
#[inline(always)]
fn depth_fill<C: PixelColor, P: DepthPixel<C, N>, R: RowWindow, const N: usize>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    vertices: [&ScreenVertex; 3],
    attributes: &Attributes<N>,
    pixel: P,
) {
    let fill = DepthFill {
        target,
        step: [0; N],
        pixel,
    };
    clip.rows
        .shade(vertices.map(|v| v.position()), attributes, &clip.rect, fill);
}

/// One colour.
struct Flat<C>(C);

impl<C: Copy> DepthPixel<C, 1> for Flat<C> {
    #[inline(always)]
    fn color(&mut self, _: &[u32; 1]) -> C {
        self.0
    }
}

/// The interpolated colour channels (attributes 1 to 3), pixel by pixel as the colour format's
/// span loop gives them ([`SpanColors`]): the colours of [`GouraudTriangle`](crate::GouraudTriangle)
/// where nothing is nearer.
struct Smooth<C> {
    steps: SpanSteps,
    colors: SpanColors<C>,
    current: C,
}

impl<C: GouraudColor> DepthPixel<C, 4> for Smooth<C> {
    const SCANS_SMALL: bool = false;

    #[inline(always)]
    fn prepare(&mut self, step: &[u32; 4]) {
        self.steps = C::prepare_steps([step[1], step[2], step[3]]);
    }

    #[inline(always)]
    fn start(&mut self, values: &[u32; 4], len: u32) {
        self.colors = SpanColors::new([values[1], values[2], values[3]], &self.steps, len);
        self.advance();
    }

    #[inline(always)]
    fn color(&mut self, _: &[u32; 4]) -> C {
        self.current
    }

    #[inline(always)]
    fn advance(&mut self) {
        if let Some(color) = self.colors.next() {
            self.current = color;
        }
    }
}

/// Lambert lighting of the quadratic normal field at the barycentrics of attributes 1 and 2.
struct Lit<'l> {
    field: NormalPlane,
    /// Second difference of the normal along a row.
    d2: [i64; 3],
    /// The normal at the current pixel and its first difference.
    n: [i64; 3],
    d1: [i64; 3],
    /// Light direction with 14 fractional bits.
    l: [i32; 3],
    light: &'l Light,
    base: [u8; 3],
}

impl<C: GouraudColor> DepthPixel<C, 3> for Lit<'_> {
    #[inline(always)]
    fn start(&mut self, values: &[u32; 3], _: u32) {
        let (u, v) = (bary_from_plane(values[1]), bary_from_plane(values[2]));
        (self.n, self.d1) = self.field.start(u, v);
    }

    #[inline(always)]
    fn color(&mut self, _: &[u32; 3]) -> C {
        let q = self.n.map(|v| {
            (v.wrapping_add(1 << (STEP_BITS - 15)) >> (STEP_BITS - 14))
                .clamp(-(1 << 15) + 1, (1 << 15) - 1) as i32
        });
        let l = self.l;
        let dot = q[0] * l[0] + q[1] * l[1] + q[2] * l[2];
        let diffuse = if dot <= 0 {
            0
        } else {
            let nn = q.iter().map(|v| v.unsigned_abs().pow(2)).sum::<u32>();
            let (r, sh) = inv_sqrt(u64::from(nn));
            ((dot as u64 * u64::from(r)) >> sh.saturating_sub(2)).min(1 << 16) as u32
        };
        scale_channels::<C>(self.base, self.light.level_of_diffuse(diffuse))
    }

    #[inline(always)]
    fn advance(&mut self) {
        wrapping_add_each(&mut self.n, &self.d1);
        wrapping_add_each(&mut self.d1, &self.d2);
    }
}

/// [`Lit`] with a Blinn-Phong highlight: the normal renormalised once, with 16 fractional bits,
/// for both the diffuse term and `n̂·ĥ` (the power amplifies the cosine's error by up to the
/// shininess, so it needs more than the 14 bits that serve the diffuse term).
///
/// With `q` the stepped normal rounded to 16 fractional bits (`|q| ≈ 2¹⁶`, each component
/// within 2⁻¹⁷), `1/|q|` from [`inv_sqrt`] (relative error below 2⁻¹⁸) and `l`, `ĥ` in raw
/// `I16F16`, each cosine is within about 2⁻¹⁵ of the exact one of the stepped normal.
///
/// With the pipeline's other lights (`sources`), each lights the same normal and
/// adds its highlight ([`add_sources`]; a draw without a highlight has one of strength 0): the
/// fill of a face they reach shares this one's loops.
struct Shiny<'l> {
    lit: Lit<'l>,
    /// Light direction and half vector, raw `I16F16`.
    l: [i32; 3],
    h: [i32; 3],
    specular: Specular,
    threshold: u32,
    sources: &'l [PixelSource],
}

impl<C: GouraudColor> DepthPixel<C, 3> for Shiny<'_> {
    #[inline(always)]
    fn start(&mut self, values: &[u32; 3], len: u32) {
        DepthPixel::<C, 3>::start(&mut self.lit, values, len);
    }

    #[inline(always)]
    fn color(&mut self, _: &[u32; 3]) -> C {
        // 16 fractional bits, within ±2¹⁷ (the field stays near unit length).
        let q = self.lit.n.map(|v| {
            (v.wrapping_add(1 << (STEP_BITS - 17)) >> (STEP_BITS - 16))
                .clamp(-(1 << 17) + 1, (1 << 17) - 1) as i32
        });
        let highlight = Some((&self.h, &self.specular, self.threshold));
        let (diffuse, specular) = pixel_terms(q, &self.l, highlight);
        let mut terms = (self.lit.light.level_of_diffuse(diffuse), specular);
        if !self.sources.is_empty() {
            terms = add_sources(q, terms, self.sources, (&self.specular, self.threshold));
        }
        highlighted_channels::<C>(self.lit.base, terms.0, terms.1)
    }

    #[inline(always)]
    fn advance(&mut self) {
        DepthPixel::<C, 3>::advance(&mut self.lit);
    }
}

/// The pipeline's other lights ([`Lights`](super::Lights)) added to a pixel's light level and
/// highlight (16 fractional bits each) of the normal `q` (as [`pixel_terms`] takes it): each
/// source's `weight · max(0, n̂·lᵢ)` and `weight · strength · max(0, n̂·ĥᵢ)^shininess` (a point
/// light's direction and weight taken at the face's centroid,
/// [`LightRig::pixel_sources`](super::light::LightRig)), each sum saturating at 1, as the
/// textured per-pixel light sums them. Out of line: the single-light fill's loop only tests
/// whether there are any, and the firmware has one copy of it.
#[inline(never)]
fn add_sources(
    q: [i32; 3],
    (mut level, mut specular): (u32, u32),
    sources: &[PixelSource],
    (highlight, threshold): (&Specular, u32),
) -> (u32, u32) {
    for s in sources {
        let (d, sp) = pixel_terms(q, &s.l, Some((&s.h, highlight, threshold)));
        // Below 2¹⁸·2¹⁶ each.
        let weigh = |v: u32| ((u64::from(s.weight) * u64::from(v) + (1 << 15)) >> 16) as u32;
        level = level.saturating_add(weigh(d)).min(1 << 16);
        specular = specular.saturating_add(weigh(sp)).min(1 << 16);
    }
    (level, specular)
}

/// The diffuse cosine `max(0, n̂·l)` and the Blinn-Phong term `strength · max(0, n̂·ĥ)^shininess`
/// (0 without a highlight, or where `n̂·l ≤ 0`), 16 fractional bits each, of the normal `q`
/// (16 fractional bits, components within ±2¹⁷, any length but zero: renormalised here once by
/// [`inv_sqrt`], no division) for the unit light direction `l` and, if any, the highlight's unit
/// half vector `h` (raw `I16F16`, components within ±2¹⁶), its specular and threshold. Each
/// cosine is within about 2⁻¹⁵ of the exact one of `q` (see [`Shiny`]).
#[inline(always)]
pub(super) fn pixel_terms(
    q: [i32; 3],
    l: &[i32; 3],
    highlight: Option<(&[i32; 3], &Specular, u32)>,
) -> (u32, u32) {
    // Below 3·2³³ in magnitude: 32 fractional bits.
    let dot = |a: &[i32; 3]| {
        mul_i32_wide(q[0], a[0]) + mul_i32_wide(q[1], a[1]) + mul_i32_wide(q[2], a[2])
    };
    let towards = dot(l);
    if towards <= 0 {
        return (0, 0);
    }
    let nn: u64 = q.iter().map(|v| u64::from(v.unsigned_abs()).pow(2)).sum();
    let (r, sh) = inv_sqrt(nn);
    // d/|q| with 16 fractional bits: (d/2⁴)·r/2^(sh−4), below 2³¹·2³¹.
    let unit = |d: i64| {
        if d <= 0 {
            return 0;
        }
        let shift = sh.saturating_sub(4);
        let p = ((d >> 4) as u64) * u64::from(r) + (1 << shift.saturating_sub(1));
        (p >> shift).min(1 << 16) as u32
    };
    let specular = match highlight {
        Some((h, specular, threshold)) => specular.term_above(unit(dot(h)), threshold),
        None => 0,
    };
    (unit(towards), specular)
}

/// `a += b` component by component, wrapping (no index, so no bounds check is left to panic
/// where the loop is not unrolled).
#[inline(always)]
fn wrapping_add_each(a: &mut [i64; 3], b: &[i64; 3]) {
    let ([a0, a1, a2], [b0, b1, b2]) = (a, b);
    *a0 = a0.wrapping_add(*b0);
    *a1 = a1.wrapping_add(*b1);
    *a2 = a2.wrapping_add(*b2);
}

/// A material colour at the 256 light levels of a Gouraud-lit mesh: `table[i]` is
/// `shade(color, i/255)`. Built once per draw.
// Word-aligned, and copied as a whole (not an array clone of 2-byte elements): a band's draw
// copies it (`Frame::with_clip`), and the library copy of words is several times as fast as its
// copy of halves on the Cortex-M.
#[repr(align(4))]
pub(crate) struct ShadeTable<C> {
    colors: [C; 256],
}

impl<C: Copy> Clone for ShadeTable<C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<C: Copy> Copy for ShadeTable<C> {}

impl<C: GouraudColor> ShadeTable<C> {
    /// The levels of `color`.
    pub(crate) fn new(color: C) -> Self {
        let base = color.channels();
        ShadeTable {
            colors: core::array::from_fn(|i| {
                // i/255 with 16 fractional bits, rounded.
                let level = ((i as u32) * 65536 + 127) / 255;
                scale_channels::<C>(base, level)
            }),
        }
    }

    /// The colour at `level` (8.8 fixed point of the 0–255 scale), rounded to the nearest of the
    /// 256.
    #[inline(always)]
    pub(crate) fn at(&self, level: u16) -> C {
        let index = ((u32::from(level) + 128) >> 8).min(255);
        self.colors[index as usize]
    }
}

/// The colour at the interpolated light level (attribute 1).
struct Leveled<'t, C>(&'t [C; 256]);

impl<C: PixelColor> DepthPixel<C, 2> for Leveled<'_, C> {
    #[inline(always)]
    fn color(&mut self, values: &[u32; 2]) -> C {
        // 8.24 of the 0–255 scale, +½: the nearest level.
        self.0[(values[1] >> STEP_BITS_PLANES) as u8 as usize]
    }

    /// The row loop of [`arch::level_rows`] where there is one (ARMv7-M): the same depths and
    /// colours as the spans through [`color`](Self::color).
    #[inline(always)]
    fn rows(&mut self, target: &mut DepthTarget<'_, C>, scan: &SmallScan<'_, 2>) -> bool {
        if !arch::LEVEL_ROWS {
            return false;
        }
        let (colors, depths, width) = target.buffers_mut();
        let runs = scan.runs();
        // The region is inside the clip, inside the target: its origin is a pixel of the
        // buffers (and `level_rows` checks that the region is inside them).
        let (x0, y0) = scan.origin();
        debug_assert!(x0 >= 0 && y0 >= 0 && x0 as usize + runs.columns as usize <= width);
        let first = (y0 as usize).wrapping_mul(width).wrapping_add(x0 as usize);
        let planes = scan.planes();
        let (v, dx, dy) = (planes.first(), planes.step(), planes.row_step());
        let rows = arch::LevelRows {
            first,
            width,
            columns: runs.columns,
            rows: scan.rows(),
            bounds: runs.bounds.map(|b| (b.numerator, b.divisor, b.step)),
            middle_starts: runs.middle_starts,
            depth: [v[0], dx[0], dy[0]],
            level: [v[1], dx[1], dy[1]],
        };
        arch::level_rows(colors, depths, &rows, self.0)
    }
}

/// Fills the triangle of the vertices `v` with the material colour of `table` at their light
/// levels (8.8 fixed point of the 0–255 scale) interpolated across it, depth-tested: the
/// pipeline's Gouraud fill. The vertices are read where they are (a draw's scratch).
#[inline(never)]
pub(crate) fn draw_levels<C: PixelColor, R: RowWindow>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    v: [&ProjectedVertex; 3],
    table: &ShadeTable<C>,
) {
    // A small face of an opaque draw: set up and drawn by the assembly.
    if arch::LEVEL_FACE && target.blend().is_none() {
        let face = clip.level_face(v);
        if arch::level_face(target.buffers_mut(), face, &table.colors) {
            return;
        }
    }
    let vertices = v.map(|v| v.screen());
    let levels = v.map(|v| [v.level()]);
    let attributes = with_depth(vertices, levels, [LEVEL_HALF]);
    depth_fill(target, clip, vertices, &attributes, Leveled(&table.colors));
}

/// The level faces of an opaque [`draw_levels`] draw into `target` inside `clip` with `table`'s
/// colours ([`arch::level_faces`]): a face given its vertices there is drawn as
/// [`draw_levels`] draws it, where the set-up does not decline it. None for a translucent draw.
#[inline(always)]
pub(crate) fn level_faces<C: PixelColor, R: RowWindow>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    table: &ShadeTable<C>,
) -> Option<arch::LevelFace<'static>> {
    if target.blend().is_some() {
        return None;
    }
    arch::level_faces(target.buffers_mut(), clip.level_faces(), &table.colors)
}

/// The material colour at the interpolated light level (attribute 1) plus the white highlight
/// of the interpolated specular level (attribute 2), both 8.24 of the 0–255 scale: the
/// Gouraud fill of a material with a highlight.
struct Highlighted([u8; 3]);

impl<C: GouraudColor> DepthPixel<C, 3> for Highlighted {
    #[inline(always)]
    fn color(&mut self, values: &[u32; 3]) -> C {
        // 8.8 of the 0–255 scale (the planes' +½ of that unit rounds) to 16 fractional bits of
        // 1: ·2⁸/255 = ·257/2⁸ (within 2⁻¹⁶ of it).
        let unit = |v: u32| ((v >> 16) * 257 + (1 << 7)) >> 8;
        highlighted_channels::<C>(self.0, unit(values[1]), unit(values[2]))
    }
}

/// Fills the triangle of the vertices `v` with `color` lit at their light levels and
/// highlighted by their specular levels `speculars` (8.8 of the 0–255 scale, as the levels),
/// both interpolated across it, depth-tested: the pipeline's Gouraud fill of a material with a
/// highlight.
#[inline(never)]
pub(crate) fn draw_levels_specular<C: GouraudColor, R: RowWindow>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    v: [&ProjectedVertex; 3],
    speculars: [u16; 3],
    color: C,
) {
    let vertices = v.map(|v| v.screen());
    let ([a, b, c], [sa, sb, sc]) = (v, speculars);
    let levels = [[a.level(), sa], [b.level(), sb], [c.level(), sc]];
    // +½ of the 8.8 unit the pixel truncates to (and above the planes' error: no wrapping
    // below 0).
    let attributes = with_depth(vertices, levels, [1 << (STEP_BITS_PLANES - 9); 2]);
    let pixel = Highlighted(color.channels());
    depth_fill(target, clip, vertices, &attributes, pixel);
}

/// [`draw_levels`] into a band (`clip`'s rows), writing a small triangle's set-up into `keep`
/// (for [`resume_levels`]): whether it did.
#[inline(never)]
pub(crate) fn draw_levels_keeping<C: PixelColor>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<Band>,
    v: [&ProjectedVertex; 3],
    table: &ShadeTable<C>,
    keep: &mut impl KeptWords,
) -> bool {
    // A small face of an opaque draw: set up and drawn by the assembly, which writes its set-up
    // out to keep.
    if arch::LEVEL_FACE && target.blend().is_none() {
        let face = clip.level_face(v);
        let mut setup = core::mem::MaybeUninit::uninit();
        match arch::level_face_keeping(target.buffers_mut(), face, &table.colors, &mut setup) {
            FaceSetup::Done => return false,
            FaceSetup::Ready(setup) => return scan::keep_setup(setup, keep),
            FaceSetup::Declined => {}
        }
    }
    let vertices = v.map(|v| v.screen());
    let levels = v.map(|v| [v.level()]);
    let attributes = with_depth(vertices, levels, [LEVEL_HALF]);
    let fill = DepthFill {
        target,
        step: [0; 2],
        pixel: Leveled(&table.colors),
    };
    let v = vertices.map(|v| v.position());
    clip.rows
        .shade_keeping(v, &attributes, &clip.rect, fill, keep)
}

/// The rows of `band` of the triangle [`draw_levels_keeping`] kept in `kept` (with `table`):
/// the pixels `draw_levels` gives them.
#[inline(never)]
pub(crate) fn resume_levels<C: PixelColor>(
    target: &mut DepthTarget<'_, C>,
    band: &Band,
    table: &ShadeTable<C>,
    kept: &impl KeptWords,
) {
    let fill = DepthFill {
        target,
        step: [0; 2],
        pixel: Leveled(&table.colors),
    };
    band.resume(kept, fill);
}

/// Fills the triangle with `color` where it is nearer than the z-buffer, inside `clip` and the
/// target. Depth is interpolated from the vertex depths.
///
/// `clip` may be any `Rectangle` (reaching past `i32::MAX` too): only pixels inside both it and
/// the target are written, nothing when they do not overlap. The same holds for every fill here.
pub fn draw_flat<C: PixelColor>(
    target: &mut DepthTarget<'_, C>,
    clip: &Rectangle,
    vertices: &[ScreenVertex; 3],
    color: C,
) {
    let clip = TargetClip::new(clip, target);
    fill_flat(target, &clip, vertices.each_ref(), color);
}

/// [`draw_flat`] inside a clip already within the target.
pub(crate) fn fill_flat<C: PixelColor, R: RowWindow>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    vertices: [&ScreenVertex; 3],
    color: C,
) {
    let attributes = with_depth(vertices, [[]; 3], []);
    depth_fill(target, clip, vertices, &attributes, Flat(color));
}

/// Fills the triangle with the vertex colours interpolated barycentrically (as
/// [`GouraudTriangle`](crate::GouraudTriangle) does), depth-tested, inside `clip` (any
/// `Rectangle`, as for [`draw_flat`]) and the target.
pub fn draw_gouraud<C: GouraudColor>(
    target: &mut DepthTarget<'_, C>,
    clip: &Rectangle,
    vertices: &[ScreenVertex; 3],
    colors: [C; 3],
) {
    let vertices = vertices.each_ref();
    let channels = Attributes::channels(colors.map(|c| c.channels()));
    let attributes = with_depth(vertices, channels.values, channels.half);
    let steps = SpanSteps::default();
    let smooth = Smooth {
        colors: SpanColors::new([0; 3], &steps, 0),
        steps,
        current: colors[0],
    };
    let clip = TargetClip::new(clip, target);
    depth_fill(target, &clip, vertices, &attributes, smooth);
}

/// Fills the triangle with per-pixel Lambert lighting of the quadratic normal field `normals`
/// (vertex `k` of `normals` belongs to `vertices[k]`), depth-tested, inside `clip` (any
/// `Rectangle`, as for [`draw_flat`]) and the target. The colour is `shade(color, light level)`.
pub fn draw_quadratic<C: GouraudColor>(
    target: &mut DepthTarget<'_, C>,
    clip: &Rectangle,
    vertices: &[ScreenVertex; 3],
    normals: &QuadraticNormals,
    light: &Light,
    color: C,
) {
    let clip = TargetClip::new(clip, target);
    fill_quadratic(target, &clip, vertices.each_ref(), normals, light, color);
}

/// [`draw_quadratic`] inside a clip already within the target.
pub(crate) fn fill_quadratic<C: GouraudColor, R: RowWindow>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    vertices: [&ScreenVertex; 3],
    normals: &QuadraticNormals,
    light: &Light,
    color: C,
) {
    // The field's per-pixel gradients need more precision than the planes': 40 fractional bits
    // from the exact set-up.
    let Some(setup) = TriangleSetup::new(vertices.map(|v| v.position())) else {
        return;
    };
    let field = NormalPlane::new(normals, &setup, &InverseArea::new(setup.area2));
    let lit = Lit {
        d2: field.c.map(|c| c.wrapping_mul(2)),
        field,
        n: [0; 3],
        d1: [0; 3],
        l: light
            .direction
            .to_bits()
            .map(|c| c.saturating_add(2) >> 2)
            .map(|c| c.clamp(-(1 << 14), 1 << 14)),
        light,
        base: color.channels(),
    };
    // The barycentrics of vertices 0 and 1: 65535 there, 0 at the others.
    let bary = [[u16::MAX, 0], [0, u16::MAX], [0, 0]];
    let attributes = with_depth(vertices, bary, [DEPTH_HALF; 2]);
    depth_fill(target, clip, vertices, &attributes, lit);
}

/// [`fill_quadratic`] with the Blinn-Phong highlight `highlight` (its half vector in the space
/// of `normals` and `light`) added per pixel: [`fill_quadratic_lights`] without other lights
/// (one copy of the loops for both).
#[inline(always)]
pub(crate) fn fill_quadratic_specular<C: GouraudColor, R: RowWindow>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    vertices: [&ScreenVertex; 3],
    normals: &QuadraticNormals,
    light: &Light,
    highlight: &Highlight,
    color: C,
) {
    fill_quadratic_lights(
        target,
        clip,
        vertices,
        normals,
        light,
        Some(highlight),
        &[],
        color,
    );
}

/// [`fill_quadratic`] lit by `light` and the pipeline's other lights `sources` (as
/// [`LightRig::pixel_sources`](super::light::LightRig) gives them for the face),
/// with the Blinn-Phong highlight `highlight` if any (its half vector, like the sources', in
/// the space of `normals` and `light`), per pixel: [`fill_quadratic_specular`]'s loops
/// ([`Shiny`], a highlight of strength 0 without one).
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fill_quadratic_lights<C: GouraudColor, R: RowWindow>(
    target: &mut DepthTarget<'_, C>,
    clip: &TargetClip<R>,
    vertices: [&ScreenVertex; 3],
    normals: &QuadraticNormals,
    light: &Light,
    highlight: Option<&Highlight>,
    sources: &[PixelSource],
    color: C,
) {
    let Some(setup) = TriangleSetup::new(vertices.map(|v| v.position())) else {
        return;
    };
    let field = NormalPlane::new(normals, &setup, &InverseArea::new(setup.area2));
    let lit = Lit {
        d2: field.c.map(|c| c.wrapping_mul(2)),
        field,
        n: [0; 3],
        d1: [0; 3],
        l: [0; 3],
        light,
        base: color.channels(),
    };
    // Unit vectors: within ±2¹⁶ a component.
    let unit = |v: Vec3| v.to_bits().map(|c| c.clamp(-(1 << 16), 1 << 16));
    // Without a highlight, one of strength 0 whose threshold no cosine reaches: no power.
    let (h, specular, threshold) = match highlight {
        Some(h) => (unit(h.half), h.specular, h.threshold),
        None => ([0; 3], Specular::new(Scalar::ZERO, 0), (1 << 16) + 1),
    };
    let shiny = Shiny {
        lit,
        l: unit(light.direction),
        h,
        specular,
        threshold,
        sources,
    };
    let bary = [[u16::MAX, 0], [0, u16::MAX], [0, 0]];
    let attributes = with_depth(vertices, bary, [DEPTH_HALF; 2]);
    depth_fill(target, clip, vertices, &attributes, shiny);
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    fn unit(x: f64, y: f64, z: f64) -> Vec3 {
        let l = (x * x + y * y + z * z).sqrt();
        let c = |v: f64| (v / l * 65536.0).round() as i32;
        Vec3::from_bits(c(x), c(y), c(z))
    }

    #[test]
    fn quadratic_nodes_are_exact() {
        let q = QuadraticNormals::new([
            unit(1.0, 0.2, 0.3),
            unit(-0.2, 1.0, 0.4),
            unit(0.1, 0.3, 1.0),
        ]);
        let one = Scalar::ONE;
        let half = Scalar::from_bits(1 << 15);
        let zero = Scalar::ZERO;
        for (k, c) in [[one, zero, zero], [zero, one, zero], [zero, zero, one]]
            .iter()
            .enumerate()
        {
            assert_eq!(q.at(*c), q.vertices[k]);
        }
        for (k, c) in [[half, half, zero], [zero, half, half], [half, zero, half]]
            .iter()
            .enumerate()
        {
            let got = q.at(*c).to_bits();
            let want = q.midpoints[k].to_bits();
            for i in 0..3 {
                assert!((got[i] - want[i]).abs() <= 1, "{got:?} {want:?}");
            }
        }
    }
}
