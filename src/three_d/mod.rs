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

mod band;
mod camera;
mod clip;
mod depth;
mod light;
mod math;
mod mesh;
pub mod meshes;
#[cfg(feature = "std")]
pub mod obj;
mod pipeline;
mod shading;
mod texturing;
mod vertex;

pub use depth::{DepthImage, DepthTarget, ScreenVertex, DEPTH_CLEAR, DEPTH_FAR};
pub use light::{Light, LightSource, Lights, Specular};
pub use math::{
    inv_sqrt, normalize_wide, Angle, Degrees, Mat4, Scalar, ToAngle, ToScalar, Vec3, Vec4,
    SCALAR_BITS,
};
pub use mesh::{Bounds, Mesh, MeshError, TexCoord};
pub(crate) use pipeline::{fit_scratch, FaceSink, Frame};
pub use pipeline::{signed_area2, Cull, DrawStats, Pipeline, ScratchTooSmall};
pub(crate) use shading::TargetClip;
pub use shading::{
    draw_flat, draw_gouraud, draw_quadratic, shade, Material, QuadraticNormals, Shading,
};
pub(crate) use texturing::FaceTexture;
pub use texturing::{
    draw_textured, draw_textured_lit, FrameTexture, NoTexture, TexturedMaterial,
    TexturedScreenVertex,
};
pub use vertex::ProjectedVertex;
