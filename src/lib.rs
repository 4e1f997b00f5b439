//! A `no_std` fixed-point triangle rasterizer for [embedded-graphics].
//!
//! * **Exact coverage.** Vertices are sub-pixel fixed point ([`Coord`], 8 fractional bits). Integer
//!   edge functions with the Direct3D top-left rule decide coverage exactly: a pixel on an edge
//!   shared by two triangles is drawn once, and the result matches an exact evaluation on the same
//!   vertices bit for bit.
//! * **Gouraud shading** within 1 LSB of the exact barycentric interpolation, in the target's own
//!   channel depth ([`GouraudColor`]: `Rgb565`, `Rgb888`, `Gray8`, `BinaryColor`, …).
//! * **No floats, no heap, no panics** on the drawing path. Every [`Coord`] is a valid vertex; far
//!   off-screen and huge triangles are clipped exactly, degenerate ones draw nothing.
//! * **Spans, not pixels**: each covered row is one `fill_contiguous`/`fill_solid` call, and
//!   [`SliceFramebuffer`] turns those into slice writes.
//! * **Band rendering** ([`band`]): a 2D scene or a z-buffered 3D mesh drawn a few rows at a
//!   time into RAM for one band, each band sent to any display as it is finished — the same
//!   pixels as the frame drawn whole.
//!
//! # Coordinate range
//!
//! Any `Coord` (±2²³ pixels with 1/256-pixel precision) is accepted for vertices. Triangles whose
//! bounding box is under 2048 × 2048 pixels (anywhere in that range) are set up and walked in
//! 32-bit arithmetic (the raster core's compact set-up, [`raster::COMPACT_LIMIT`]; `GouraudTriangle::draw_into_compact` takes only
//! those, for small firmware); on x86-64 hosts those under 8 × 8 pixels are drawn by
//! `draw_into` a row of eight lanes at a time (the same pixels). For larger ones setup
//! is done in `i64` for vertices within ±2²¹ pixels and
//! in `i128` beyond. Spans are stepped in `i32` (one
//! start and one end edge per row, each read only in the rows of its edge's height) over the
//! triangle's pixel bounding box clipped to the target; regions of a few pixels test each
//! pixel's edge values instead. The target's bounding box may be anywhere in `i32`. Gouraud
//! colours are stepped in 32 bits (24 fractional bits, wrapping, so slivers' steep gradients
//! are exact on their pixels) for regions up to 2¹⁶ pixels (`width + height`) and restarted
//! from exact values every 4096 pixels beyond that, so the 1-LSB bound holds everywhere.
//!
//! # Examples
//!
//! ## 2D: triangles on any `DrawTarget`
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use embedded_raster::{GouraudTriangle, SliceFramebuffer, SolidTriangle, Vertex};
//!
//! let mut pixels = [Rgb565::BLACK; 320 * 240];
//! let mut display = SliceFramebuffer::new(&mut pixels, 320, 240).unwrap();
//!
//! GouraudTriangle::new([
//!     Vertex::new(10.0, 10.0, Rgb565::RED),
//!     Vertex::new(300.5, 40.25, Rgb565::GREEN),
//!     Vertex::new(120.75, 230.0, Rgb565::BLUE),
//! ])
//! .draw(&mut display)?;
//!
//! SolidTriangle::new([(-5000.0, 0.0), (5.0, 0.0), (5.0, 240.0)], Rgb565::WHITE)
//!     .draw(&mut display)?;
//! # Ok::<(), core::convert::Infallible>(())
//! ```
//!
//! ## 3D: a lit mesh with a z-buffer
//!
//! The icosphere stored in flash, turned 30° and lit from the upper left with 15% ambient,
//! Gouraud-shaded into a 64×48 framebuffer with its 16-bit z-buffer:
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
//! use embedded_raster::three_d::meshes::icosphere::ICOSPHERE;
//! use embedded_raster::three_d::DEPTH_CLEAR;
//! use embedded_raster::three_d::Angle;
//! use embedded_raster::{DepthTarget, Light, Mat4, Material, Pipeline, Shading, Vec3};
//!
//! let (mut pixels, mut depth) = ([Rgb565::BLACK; 64 * 48], [0u16; 64 * 48]);
//! let mut target = DepthTarget::new(&mut pixels, &mut depth, 64, 48)?;
//!
//! let projection = Mat4::perspective(Angle::from_degrees(50), 64.0 / 48.0, 0.5, 20).unwrap();
//! let view = Mat4::look_at(Vec3::new(0, 0, 3), Vec3::ZERO, Vec3::new(0, 1, 0)).unwrap();
//! let model = Mat4::rotation_y(Angle::from_degrees(30));
//! let light = Light::new(Vec3::new(-1, 1, 1), 0.15);
//! let viewport = Rectangle::new(Point::zero(), Size::new(64, 48));
//! let pipeline = Pipeline::new(model, projection * view, viewport, light);
//!
//! let material = Material::new(Rgb565::CSS_ORANGE, Shading::Gouraud);
//! let stats = pipeline.draw_mesh(&ICOSPHERE, &material, &mut target);
//! assert_eq!(stats.drawn + stats.culled, 80); // every face drawn, or culled facing away
//!
//! // The sphere covers the middle (in front of the cleared depth), not the corners ...
//! assert!(target.depth_at(32, 24).unwrap() < DEPTH_CLEAR);
//! assert_eq!(target.framebuffer().get(0, 0), Some(Rgb565::BLACK));
//! // ... and is brighter towards the light (upper left) than away from it.
//! let green = |x, y| target.framebuffer().get(x, y).unwrap().g();
//! assert!(green(25, 17) > green(39, 31));
//!
//! target.clear(Rgb565::BLACK); // the next frame: colour and depth
//! # Ok::<(), embedded_raster::FramebufferError>(())
//! ```
//!
//! [`three_d`] describes the pipeline and turns an OBJ file's text into a picture;
//! [`band`] draws the same in bands of a few rows; [`fixed_point`] builds coordinates from
//! floats, pixel indices and embedded-graphics `Point`s.
//!
//! # Converting floats
//!
//! Floats become fixed point only in conversions you call; none is part of drawing. Each has a
//! saturating form, which never fails, and a checked form, which returns `None` where the
//! saturating one would have to make a value up:
//!
//! | conversion | NaN | ±infinity | finite beyond the range | checked form |
//! |---|---|---|---|---|
//! | [`ToCoord::to_coord`] (`f32`, `f64` to [`Coord`]: the 2D vertices) | 0 | [`Coord::MAX`] / [`Coord::MIN`] | saturates to `Coord::MAX` / `MIN` (±2²³ px) | [`ToCoord::try_to_coord`] |
//! | [`ToScalar::to_scalar`] (`f32`, `f64` to [`Scalar`]: the 3D vectors, distances, light and material values) | 0 | `Scalar::MAX` / `MIN` | saturates to ±32768 | [`ToScalar::try_to_scalar`] |
//! | [`Angle::from_degrees`](three_d::Angle::from_degrees) (`f32`, `f64` degrees) | 0° | 0° | none: angles wrap | [`Angle::try_from_degrees`](three_d::Angle::try_from_degrees), [`Degrees::try_to_angle`](three_d::Degrees::try_to_angle) |
//! | [`Angle::from_radians`](three_d::Angle::from_radians) | 0° | 0° | none: angles wrap | [`Angle::try_from_radians`](three_d::Angle::try_from_radians) |
//! | [`ToAngle::to_angle`] of embedded-graphics' `Angle` (through its radians) | 0° | 0° | none: angles wrap | [`ToAngle::try_to_angle`] |
//!
//! Integers convert without floats: to a `Scalar` saturating beyond ±32768 (`try_to_scalar`
//! gives `None` there), to degrees exactly. The saturating forms round to the nearest step
//! (ties to even); the checked ones round the same way and fail only where the table says.
//! [`Mat4::perspective`] takes its aspect and planes through the checked form, so a NaN there
//! is `None`, not a projection of nothing.
//!
//! On the host (feature `std`): `three_d::meshes::scalar` and `vec3`, and so
//! `MeshData::from_f64` and the mesh generators, convert as `to_scalar` does (NaN as 0,
//! infinities and values beyond ±32768 saturate); `three_d::obj::parse` rejects a number that is
//! NaN or infinite (`nan`, `inf` in the file) with an error naming its line, and saturates
//! finite positions beyond the range. The conversions back to floats (`Vec3::to_f32`,
//! `to_f64`, `Angle::to_degrees_f32`, the `fixed` crate's `to_num`) are exact or rounded and
//! never give NaN or an infinity.
//!
//! ```
//! use embedded_raster::three_d::Angle;
//! use embedded_raster::{Coord, Scalar, ToCoord, ToScalar};
//!
//! assert_eq!(f32::NAN.to_coord(), Coord::ZERO); // a NaN vertex lands on 0 ...
//! assert_eq!(f32::NAN.try_to_coord(), None); // ... unless you ask
//! assert_eq!(f64::NEG_INFINITY.to_scalar(), Scalar::MIN);
//! assert_eq!(f64::NEG_INFINITY.try_to_scalar(), None);
//! assert_eq!(40_000.0.try_to_scalar(), None); // beyond ±32768
//! assert_eq!(40_000.try_to_scalar(), None);
//! assert_eq!(Angle::try_from_degrees(f32::NAN), None);
//! assert_eq!(Angle::try_from_degrees(450.0), Some(Angle::QUARTER));
//! ```
//!
//! # Errors
//!
//! Every error type — [`FramebufferError`], [`band::BandError`] and a band render's
//! [`band::RenderError`], [`three_d::MeshError`],
//! [`three_d::ScratchTooSmall`],
//! [`texture::TextureError`], [`raster::TooLarge`], and on the host `three_d::obj`'s and
//! `texture::convert`'s — implements [`core::fmt::Display`], with a message that says what was
//! needed and what was given, and [`core::error::Error`] (`std::error::Error`): `?` takes them
//! into `Box<dyn std::error::Error>` or an error-reporting crate's type.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use embedded_raster::band::{BandLayout, ColorBands};
//! use embedded_raster::texture::{Rgb565Texels, Texture};
//!
//! fn set_up(texels: &[u16], band: &mut [Rgb565]) -> Result<(), Box<dyn std::error::Error>> {
//!     let texture = Texture::new(Rgb565Texels(texels), 8, 8)?;
//!     let layout = BandLayout::new(Size::new(320, 240), 16)?;
//!     let bands = ColorBands::new(layout, band)?;
//!     # let _ = (texture, bands);
//!     Ok(())
//! }
//!
//! let mut band = [Rgb565::BLACK; 320 * 16];
//! assert!(set_up(&[0; 64], &mut band).is_ok());
//! let error = set_up(&[0; 60], &mut band).unwrap_err();
//! assert_eq!(error.to_string(), "the texture's size needs 64 texels, the storage holds 60");
//! let error = set_up(&[0; 64], &mut band[..320 * 15]).unwrap_err();
//! assert_eq!(
//!     error.to_string(),
//!     "a colour band buffer needs 5120 pixels (width · rows), given 4800"
//! );
//! ```
//!
//! # Features
//!
//! | feature | what it adds |
//! |---|---|
//! | `std` | host-only helpers: `three_d::meshes::MeshData` (generators, welding, the flash emitter), `three_d::obj` (OBJ files) |
//! | `png` | `save_png` / `write_png` of a [`SliceFramebuffer`] and a [`DepthTarget`]; `texture::convert`, PNG files to flash textures (implies `std`) |
//! | `reference` | the module `reference`: the f64 reference rasterizer the tests compare against (implies `std`) |
//! | `sdl` | only the interactive `spin` example (needs SDL2) |
//!
//! [embedded-graphics]: https://docs.rs/embedded-graphics
#![no_std]
#![deny(missing_docs)]
#![deny(unsafe_code)]

#[cfg(feature = "std")]
extern crate std;

// Layers, each using only those above it: target code, rectangle arithmetic (`rect`), the raster
// core, colours, textures, drawing into embedded-graphics targets, the 3D pipeline, band rendering.
// `geometry` and `reference` stand apart.
mod arch;
pub mod band;
pub mod color;
pub mod draw;
pub mod fixed_point;
pub mod paint;
pub mod raster;
mod rect;
pub mod texture;
pub mod three_d;

pub mod geometry;
#[cfg(feature = "reference")]
pub mod reference;

pub use color::{GouraudColor, SpanSteps};
pub use draw::{
    AntiAliased, Cap, CoverageMask, DitheredTriangle, FilledPolygon, FramebufferError,
    GouraudTriangle, Join, Line, OnBackground, PaintedTriangle, Polygon, PolygonFull, Polyline,
    ShadedSpans, SliceFramebuffer, SolidTriangle, SpanColors, Stroke, Stroked, TexturedTriangle,
    TexturedVertex, Translucent, Vertex,
};
pub use fixed_point::{Coord, ToCoord};
pub use paint::{LinearGradient, Paint, RadialGradient, Stop};
pub use raster::FillRule;
pub use texture::{Filter, Texture, Wrap};
pub use three_d::{
    Bounds, Cull, DepthTarget, Light, LightSource, Lights, Mat4, Material, Mesh, Pipeline, Scalar,
    Shading, Specular, TexCoord, TexturedMaterial, ToAngle, ToScalar, Vec3,
};

/// Everything a 2D or 3D drawing needs, in one import: `use embedded_raster::prelude::*;`
/// (next to `embedded_graphics::prelude::*`, which brings `Drawable`, `Point`, `Size` and the
/// colour traits).
///
/// 2D: the triangles, their [`Vertex`] and [`TexturedVertex`], [`SliceFramebuffer`],
/// [`Coord`] with [`ToCoord`] and the pixel placements, [`Texture`] with its [`Wrap`] and
/// [`Filter`], and the [`GouraudColor`] bound. 3D: the pipeline, its mesh, target, light and
/// material types (textured too), the maths types with [`ToScalar`], [`ToAngle`] and
/// [`Degrees`](three_d::Degrees).
///
/// No `Angle` is in it, nor at the crate's root: embedded-graphics' prelude has an `Angle` of
/// its own, and two globs bringing one each would make the name ambiguous. So either glob
/// (`embedded_raster::prelude::*` or `embedded_raster::*`) goes next to embedded-graphics'
/// prelude, whose `Angle` and `.deg()` the matrices take ([`ToAngle`]); this crate's exact
/// binary angle (integer degrees without floats) is [`three_d::Angle`].
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
/// use embedded_raster::prelude::*;
/// use embedded_raster::three_d;
///
/// let mut pixels = [Rgb565::BLACK; 8 * 8];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 8, 8).unwrap();
/// SolidTriangle::new([(0.0, 0.0), (8.0, 0.0), (0.0, 8.0)], Rgb565::RED).draw_into(&mut fb);
/// let view = Mat4::look_at(Vec3::new(0, 0, 5), Vec3::ZERO, Vec3::new(0, 1, 0)).unwrap();
/// let camera = Mat4::perspective(52.5.deg(), 1, 0.5, 20).unwrap() * view;
/// // embedded-graphics' `Angle` (through its radians, in floats) or this crate's, exact:
/// assert_eq!(Mat4::rotation_y(90.0.deg()), Mat4::rotation_y(three_d::Angle::from_degrees(90)));
/// # let _ = camera;
/// ```
pub mod prelude {
    pub use crate::color::GouraudColor;
    pub use crate::draw::{
        GouraudTriangle, Polygon, SliceFramebuffer, SolidTriangle, TexturedTriangle,
        TexturedVertex, Vertex,
    };
    pub use crate::fixed_point::{pixel_centre, pixel_corner, Coord, ToCoord};
    pub use crate::raster::FillRule;
    pub use crate::texture::{Filter, Texture, Wrap};
    pub use crate::three_d::{
        Bounds, Cull, Degrees, DepthTarget, DrawStats, Light, LightSource, Lights, Mat4, Material,
        Mesh, Pipeline, Scalar, ScreenVertex, Shading, Specular, TexCoord, TexturedMaterial,
        ToAngle, ToScalar, Vec3, Vec4,
    };
}

/// The unit tests' random numbers: the generator the integration tests share.
#[cfg(test)]
#[path = "../tests/support/rng.rs"]
pub(crate) mod rng;

/// The unit tests' random numbers as a closure: each call returns the next number of
/// [`rng::Rng`] from `seed`.
#[cfg(test)]
pub(crate) fn random(seed: u64) -> impl FnMut() -> u64 {
    let mut rng = rng::Rng(seed);
    move || rng.next()
}

/// The README's code examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
