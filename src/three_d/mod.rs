//! A fixed-point 3D pipeline: meshes transformed, clipped, projected, culled, lit and drawn with
//! a 16-bit z-buffer.
//!
//! * `math` — [`Scalar`] (`I16F16`), [`Vec3`], [`Vec4`], [`Mat4`] and [`Angle`]: integer
//!   arithmetic with wide accumulation, no floats (conversions from floats: [`ToScalar`],
//!   [`Degrees`]).
//! * `camera` — projections ([`Mat4::perspective`], [`Mat4::orthographic`]), views
//!   ([`Mat4::look_at`], [`Mat4::orbit`]), [`Mat4::inverse`] and [`Mat4::normal_matrix`].
//! * `mesh` — [`Mesh`]: positions, triangles and optional normals, colours and texture
//!   coordinates ([`TexCoord`]), borrowed (typically from flash); [`Bounds`] to place it.
//! * `pipeline` — [`Pipeline`] draws a [`Mesh`]: transform, clip in clip space, project, cull.
//! * `light` — [`Light`] (one directional light and the ambient term), [`Lights`] (up to three
//!   more directional and point lights, [`LightSource`]) and [`Specular`].
//! * `shading` — [`Light`], [`Material`] (with an optional Blinn-Phong [`Specular`] highlight),
//!   [`Shading`] and the depth-tested fills (flat, Gouraud, per-pixel lighting of quadratically
//!   interpolated normals).
//! * `texturing` — [`draw_textured`] and [`draw_textured_lit`]: textured, depth-tested fills with perspective-correct texel
//!   coordinates; [`TexturedMaterial`]; [`NoTexture`] and [`FrameTexture`], the texture type
//!   of a band renderer's mesh bin (untextured and textured).
//! * `depth` — [`DepthTarget`]: a colour framebuffer with its z-buffer.
//! * `band` — a band's rows as two clip-space planes: how a band's draw without a bin rejects
//!   the faces outside it before projecting them (band rendering itself is the `band` module,
//!   which builds on this one).
//! * [`meshes`] — meshes in flash (an icosphere and a torus) and, on the host, mesh data to
//!   generate them; [`obj`] reads Wavefront OBJ files (host).
//!
//! The [crate page](crate#3d-a-lit-mesh-with-a-z-buffer) draws a lit mesh from flash with a
//! z-buffer; [`Pipeline`], [`Light`], [`Material`] and [`DepthTarget`] have examples of their
//! own.
//!
//! # Example: from OBJ text to a picture
//!
//! On the host (feature `std`): OBJ text ([`obj::read_file`] reads a file) becomes a mesh,
//! placed to fill a box of half-side 1 around the origin, drawn flat-lit into a 32×16
//! framebuffer — and, here, printed as text (with the `png` feature,
//! `target.framebuffer().save_png("pyramid.png")` writes the picture).
//!
//! ```
//! # #[cfg(feature = "std")]
//! # {
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
//! use embedded_raster::three_d::{obj, Angle, DepthTarget, Light, Mat4, Material, Pipeline};
//! use embedded_raster::three_d::{Shading, Vec3};
//!
//! let text = "\
//! # A square pyramid, apex up
//! v  0  1  0
//! v -1 -1  1
//! v  1 -1  1
//! v  1 -1 -1
//! v -1 -1 -1
//! f 1 2 3
//! f 1 3 4
//! f 1 4 5
//! f 1 5 2
//! f 2 5 4 3
//! ";
//! let mesh = obj::parse(text)?;
//! assert_eq!((mesh.vertices.len(), mesh.indices.len()), (5, 6)); // the base fanned in two
//! let model = Mat4::rotation_y(Angle::from_degrees(30)) * mesh.bounds().unwrap().fit(1);
//!
//! let (mut pixels, mut depth) = ([Rgb565::BLACK; 32 * 16], [0u16; 32 * 16]);
//! let mut target = DepthTarget::new(&mut pixels, &mut depth, 32, 16)?;
//! // Pixels twice as tall as wide, as the characters below are: an aspect of 32 / (2 · 16).
//! let (eye, looked_at) = (Vec3::new(0.0, 1.5, 4.5), Vec3::new(0.0, -0.1, 0.0));
//! let camera = Mat4::perspective(Angle::from_degrees(40), 1, 0.5, 20).unwrap()
//!     * Mat4::look_at(eye, looked_at, Vec3::new(0, 1, 0)).unwrap();
//! let viewport = Rectangle::new(Point::zero(), Size::new(32, 16));
//! let pipeline = Pipeline::new(model, camera, viewport, Light::new(Vec3::new(-1, 1, 1), 0.2));
//! let material = Material::new(Rgb565::WHITE, Shading::Flat);
//! let stats = pipeline.draw_mesh(&mesh.as_mesh(), &material, &mut target);
//! assert_eq!(stats.drawn, 2); // two sides face the camera; the others are culled
//!
//! // One character a pixel, by brightness: the side towards the light (upper left) is `@`.
//! let shades = [' ', '.', ':', '+', '#', '@'];
//! let rows: Vec<String> = target.framebuffer().pixels().chunks(32).map(|row| {
//!     let row: String = row.iter().map(|c| shades[(usize::from(c.g()) * 5 + 31) / 63]).collect();
//!     row.trim_end().to_owned()
//! }).collect();
//! assert_eq!(rows, [
//!     "",
//!     "",
//!     "",
//!     "               @+",
//!     "              @+++",
//!     "            @@@++++",
//!     "           @@@@++++++",
//!     "          @@@@++++++++",
//!     "        @@@@@@+++++++++",
//!     "       @@@@@@@+++++++++++",
//!     "      @@@@@@@+++++++++++++",
//!     "      @@@@@@@++++++++++++++",
//!     "       @@@@@@++++++++++++++++",
//!     "         @@@+++++++++++",
//!     "          @@++++++",
//!     "",
//! ]);
//! # }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod band;
mod camera;
mod clip;
mod depth;
mod light;
mod math;
mod mesh;
mod mesh_target;
pub mod meshes;
#[cfg(feature = "std")]
pub mod obj;
mod pipeline;
mod shading;
mod texturing;
mod vertex;
mod wireframe;

pub use depth::{DepthImage, DepthTarget, ScreenVertex, DEPTH_CLEAR, DEPTH_FAR};
pub use light::{Light, LightSource, Lights, Specular};
pub use math::{
    inv_sqrt, normalize_wide, Angle, Degrees, Mat4, Scalar, ToAngle, ToScalar, Vec3, Vec4,
    SCALAR_BITS,
};
pub use mesh::{Bounds, Mesh, MeshError, TexCoord};
pub(crate) use mesh_target::sealed::Target as MeshTargetParts;
pub use mesh_target::MeshTarget;
pub(crate) use pipeline::{fit_scratch, FaceSink, Frame};
pub use pipeline::{signed_area2, Cull, DrawStats, Pipeline, ScratchTooSmall};
pub(crate) use shading::TargetClip;
pub use shading::{
    draw_flat, draw_gouraud, draw_quadratic, shade, Material, QuadraticNormals, Shading,
};
pub(crate) use texturing::FaceTexture;
pub use texturing::{
    draw_textured, draw_textured_lit, Blended, FrameTexture, NoTexture, Opacity, Opaque,
    TexturedMaterial, TexturedScreenVertex,
};
pub use vertex::ProjectedVertex;
