//! A fixed-point 3D pipeline: meshes transformed, clipped, projected, culled, lit and drawn with
//! a 16-bit z-buffer.
//!
//! A draw runs in two stages:
//!
//! 1. **Vertices** ([`vertex`](super::vertex)): each mesh vertex is transformed by the
//!    model-view-projection matrix into clip space, classified against the view volume (near and
//!    far planes, `w ≥ 2⁻⁸`, a guard band reaching about 1000 px from the viewport's centre),
//!    projected to sub-pixel [`Coord`]s and a 16-bit depth `(1 + z/w)/2 · 65534` (0 at the near
//!    plane), and lit (Gouraud). With a scratch slice ([`Pipeline::draw_mesh_with`], one
//!    [`ProjectedVertex`] of 16 bytes per mesh vertex) this happens once per vertex; without one
//!    ([`Pipeline::draw_mesh`]), once per face using it — the same bits either way.
//! 2. **Faces**: a face with all three vertices inside the volume (almost all of them) is culled by
//!    the sign of its exact doubled screen area and handed to the raster core; its bounding box
//!    is under 2048 px, so the 32-bit set-up takes it. A face outside one plane is dropped; a face
//!    crossing one is clipped in clip space ([`clip`](super::clip), watertight) and drawn as a fan.
//!    Fills: flat, Gouraud (the light level interpolated, the material colour looked up at 256
//!    levels) or per-pixel quadratic normals ([`shading`](super::shading)), each with an
//!    optional Blinn-Phong highlight ([`Material::specular`]: the half vector of the light and
//!    the [`view_direction`](Pipeline::view_direction) found once per draw), the depth test and
//!    write in the span loop (smaller is nearer).
//!
//! Front faces are counter-clockwise in normalised device coordinates (y up), as in OpenGL; on
//! screen (y down) that is a negative area. Normals are transformed by
//! [`Pipeline::normal_matrix`] (the model matrix by default, exact for rotations); the light is
//! given in the same (world) space, and so are the directional and point lights a pipeline may
//! add to it ([`Pipeline::lights`]: point lights placed against the mesh by
//! [`Pipeline::model`]). A [`Material`]'s attributes are interpolated affinely in screen
//! space (no perspective correction: the cheaper choice, good for small faces); a
//! [`TexturedMaterial`] interpolates its texel coordinates, light levels, vertex colours and
//! highlights perspective-correct — of a plain colour with a 1 × 1
//! [`Solid`](crate::texture::Solid) texture. Depth, being `z/w`, is affine in screen space and
//! therefore exact.
//! All state lives on the stack: the clipped polygon holds at most 10 vertices.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
//! use embedded_raster::three_d::{Angle, Mat4, Scalar, Vec3};
//! use embedded_raster::three_d::{DepthTarget, Mesh, Pipeline};
//! use embedded_raster::three_d::{Light, Material, Shading};
//!
//! static VERTICES: [Vec3; 3] = [
//!     Vec3::from_bits(-65536, -65536, 0),
//!     Vec3::from_bits(65536, -65536, 0),
//!     Vec3::from_bits(0, 65536, 0),
//! ];
//! static NORMALS: [Vec3; 3] = [Vec3::from_bits(0, 0, 65536); 3];
//! static INDICES: [[u16; 3]; 1] = [[0, 1, 2]];
//! let mesh = Mesh::new(&VERTICES, &NORMALS, &INDICES);
//!
//! let (mut pixels, mut depth) = ([Rgb565::BLACK; 64 * 48], [0u16; 64 * 48]);
//! let mut target = DepthTarget::new(&mut pixels, &mut depth, 64, 48).unwrap();
//! target.clear(Rgb565::BLACK);
//!
//! let projection = Mat4::perspective(
//!     Angle::from_degrees(60),
//!     Scalar::from_num(4) / 3,
//!     Scalar::from_num(0.5),
//!     Scalar::from_num(20),
//! ).unwrap();
//! let view = Mat4::translation(Vec3::from_bits(0, 0, -3 << 16));
//! let viewport = Rectangle::new(Point::zero(), Size::new(64, 48));
//! let light = Light::new(Vec3::new(0, 0, 1), 0.2);
//! let pipeline = Pipeline::new(Mat4::IDENTITY, projection * view, viewport, light);
//! let stats = pipeline.draw_mesh(&mesh, &Material::new(Rgb565::WHITE, Shading::Flat), &mut target);
//! assert_eq!(stats.drawn, 1);
//! assert_eq!(target.framebuffer().get(32, 24), Some(Rgb565::WHITE));
//! ```

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::primitives::Rectangle;

use super::band::{BandPlanes, SideCache};
use super::clip::{ClipVertex, Polygon};
use super::depth::{Blend, DepthTarget, ScreenVertex};
use super::light::{Highlight, Light, LightRig, Lights, Specular};
use super::math::{normalize_wide, zip3_with, Bary, Mat4, Vec3, Vec4, BARY_ONE};
use super::mesh::Mesh;
use super::mesh_target::MeshTarget;
use super::shading::{self, Material, QuadraticNormals, ShadeTable, Shading, TargetClip};
use super::texturing::{
    FaceTexture, FrameTexture, NoTexture, Opacity, PixelLight, TexelLight, TexturedMaterial,
};
use super::vertex::{Inverse, ProjectedVertex, VertexLight, VertexSpecular, VertexStage};
use crate::arch::{self, LevelField, TexturedDraw, SIZE_OVER_SPEED};
use crate::color::GouraudColor;
use crate::fixed_point::Coord;
use crate::raster::arith::mul_i32_wide;
use crate::raster::band::{AllRows, RowWindow};
use crate::raster::scan::KeptWords;
use crate::raster::walk::Band;
use crate::texture::TexelSource;

/// Which faces are skipped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Cull {
    /// Draw both sides.
    None,
    /// Skip faces that are clockwise in normalised device coordinates (facing away).
    #[default]
    Back,
    /// Skip faces that are counter-clockwise (facing the camera).
    Front,
}

/// What happened to the triangles of a [`Pipeline::draw_mesh`] call: each is counted once, in
/// `drawn`, `rejected`, `culled`, `degenerate` or `invalid` (`clipped` counts again some of
/// those drawn or rejected).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct DrawStats {
    /// Triangles handed to the fill (whether or not any pixel passed the depth test).
    pub drawn: u32,
    /// Triangles that needed clipping (counted in `drawn` if anything was left).
    pub clipped: u32,
    /// Triangles outside the view volume, or left empty by clipping.
    pub rejected: u32,
    /// Back- (or front-) facing triangles skipped.
    pub culled: u32,
    /// Triangles with zero screen area.
    pub degenerate: u32,
    /// Triangles skipped for an index past the mesh's vertices: a mesh that
    /// [`Mesh::validate`] rejects (a corrupt or mis-generated index array, not geometry).
    pub invalid: u32,
}

/// Doubled signed area of a screen triangle in squared sub-pixel units (positive when clockwise
/// on screen, i.e. counter-clockwise with y up).
pub fn signed_area2(v: [(Coord, Coord); 3]) -> i128 {
    let [p0, p1, p2] = v.map(|(x, y)| (i128::from(x.to_bits()), i128::from(y.to_bits())));
    (p1.0 - p0.0) * (p2.1 - p0.1) - (p2.0 - p0.0) * (p1.1 - p0.1)
}

/// Model-view-projection, viewport, light and culling: everything needed to draw meshes.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb888, prelude::*, primitives::Rectangle};
/// use embedded_raster::three_d::meshes::torus::TORUS;
/// use embedded_raster::three_d::{Angle, Cull, DepthTarget, Light, Mat4, Material, Pipeline, Shading, Vec3};
///
/// let (mut pixels, mut depth) = ([Rgb888::BLACK; 64 * 64], [0u16; 64 * 64]);
/// let mut target = DepthTarget::new(&mut pixels, &mut depth, 64, 64).unwrap();
/// let camera = Mat4::perspective(Angle::from_degrees(45), 1, 0.5, 20).unwrap()
///     * Mat4::orbit(Vec3::ZERO, 4, Angle::from_degrees(20), Angle::from_degrees(35.5));
/// let viewport = Rectangle::new(Point::zero(), Size::new(64, 64));
/// let mut pipeline = Pipeline::new(Mat4::IDENTITY, camera, viewport, Light::default());
/// pipeline.cull = Cull::None; // both sides
/// let stats = pipeline.draw_mesh(&TORUS, &Material::new(Rgb888::WHITE, Shading::Gouraud), &mut target);
/// assert_eq!(stats.drawn, 192);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Pipeline {
    /// Model space to clip space.
    pub mvp: Mat4,
    /// Transforms model-space normals into the light's space (only the 3×3 block is used);
    /// the inverse transpose of the model matrix, which for rotations and uniform scaling is the
    /// model matrix itself (any positive multiple will do: normals are renormalised).
    /// [`Pipeline::with_inverse_transpose`] sets it for any invertible model matrix.
    pub normal_matrix: Mat4,
    /// Where normalised device coordinates `[−1, 1]²` land on the target (at most 65535 pixels
    /// a side); also the scissor rectangle. Any `Rectangle` is accepted: only its part inside the
    /// target is drawn (nothing when they do not overlap), computed without overflow.
    pub viewport: Rectangle,
    /// Which faces to skip.
    pub cull: Cull,
    /// The light, in world space: one directional light and the ambient term.
    pub light: Light,
    /// More lights besides [`light`](Self::light), in world space: up to [`Lights::MAX`]
    /// directional and point lights (none by default; [`with_lights`](Self::with_lights)).
    pub lights: Lights,
    /// Model space to world space, where point lights are ([`LightSource::point`]): set by
    /// [`new`](Self::new); keep it in step with [`mvp`](Self::mvp) when setting that by hand
    /// for a draw with point lights (no other draw reads it).
    ///
    /// [`LightSource::point`]: super::LightSource::point
    pub model: Mat4,
}

/// [`Pipeline::draw_mesh_with`]'s scratch slice has fewer entries than the mesh has vertices;
/// nothing was drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ScratchTooSmall {
    /// Entries the mesh needs: one per vertex.
    pub needed: usize,
    /// Entries given.
    pub given: usize,
}

impl core::fmt::Display for ScratchTooSmall {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "a vertex scratch needs {} entries (one per vertex of the mesh), given {}",
            self.needed, self.given
        )
    }
}

impl core::error::Error for ScratchTooSmall {}

impl Pipeline {
    /// A pipeline drawing meshes placed by `model` through the camera `view_projection`
    /// (projection · view) into `viewport`, culling back faces. Normals are transformed by
    /// `model`.
    pub fn new(model: Mat4, view_projection: Mat4, viewport: Rectangle, light: Light) -> Self {
        Pipeline {
            mvp: view_projection * model,
            normal_matrix: model,
            viewport,
            cull: Cull::Back,
            light,
            lights: Lights::new(),
            model,
        }
    }

    /// The pipeline with the lights `lights` besides its [`light`](Self::light) ([`Lights`]
    /// has an example).
    ///
    /// Every shading lights with them as with the first light (flat: at the face's centroid
    /// with its normal; Gouraud: per vertex; [`Shading::Quadratic`], a [`Material`] or a
    /// [`TexturedMaterial`]: per pixel), and a material's [`Specular`](super::Specular)
    /// highlight shines for each. Per pixel, directional lights light each pixel's normal as
    /// the first light does, and point lights take their direction, half vector and falloff at
    /// each face's centroid (one out of range there lights none of the face). That is an
    /// approximation on faces large beside their distance to the
    /// light: for a point light of intensity `I` and range `r` at distance `D` from the
    /// centroid of a face reaching `ρ` from it (`ε = ρ/(D − ρ)`), the level is within
    /// `I·(ε + 1.54·ρ/r)` of the light at each pixel's own surface point, and the highlight
    /// within `I·strength·min(1, shininess·ε/|l̂ + v̂| + 1.54·ρ/r)` (`1.54/r` bounds the
    /// falloff's slope, `ε` the direction's turn; away from the light's terminator, where the
    /// highlight is cut). Measured (`tests/all/lights.rs`,
    /// `quadratic_lights_are_lit_per_pixel`, Rgb888): on an icosphere of radius 1 whose faces
    /// reach `ρ ≤ 0.09` from their centroids, lit by two point lights (`ε` up to 0.15) and a
    /// directional one, at most 9.4 LSB off the exact per-pixel light without a highlight and
    /// 24 LSB with one (strength 0.6, shininess 24); with point lights near a coarser sphere
    /// (`ε` up to 2), 46 and 81 LSB; everywhere within 0.37 of the bound. Against the same
    /// centroid approximation in f64 the fills are within 0.55 LSB (a material) and 2.2 LSB
    /// (a texture: its barycentrics stepped along 16-pixel chords). Subdivide meshes lit by
    /// nearby point lights. A set that lights nothing (empty, or every source of intensity 0)
    /// draws as without it, at the same cost.
    pub fn with_lights(self, lights: Lights) -> Self {
        Pipeline { lights, ..self }
    }

    /// A pipeline like [`new`](Self::new) whose normals are transformed by the inverse transpose
    /// of `model` ([`Mat4::normal_matrix`]), so they stay perpendicular to surfaces under
    /// non-uniform scale and shear; `None` if `model` is singular.
    ///
    /// ```
    /// # use embedded_graphics::{prelude::*, primitives::Rectangle};
    /// use embedded_raster::three_d::{Light, Mat4, Pipeline, Vec3};
    ///
    /// let mut model = Mat4::scaling(2);
    /// model.rows[1][1] = embedded_raster::three_d::Scalar::from_num(0.5); // squash y
    /// # let viewport = Rectangle::new(Point::zero(), Size::new(64, 48));
    /// let pipeline =
    ///     Pipeline::with_inverse_transpose(model, Mat4::IDENTITY, viewport, Light::default());
    /// assert_eq!(pipeline.unwrap().normal_matrix, model.normal_matrix().unwrap());
    /// ```
    pub fn with_inverse_transpose(
        model: Mat4,
        view_projection: Mat4,
        viewport: Rectangle,
        light: Light,
    ) -> Option<Self> {
        Some(Pipeline {
            normal_matrix: model.normal_matrix()?,
            ..Pipeline::new(model, view_projection, viewport, light)
        })
    }

    /// The clip-space position of a model-space point.
    pub fn clip_position(&self, p: Vec3) -> Vec4 {
        self.mvp.transform_point(p)
    }

    /// The screen position and depth of a clip-space point inside the view volume (within the
    /// near and far planes and the guard band), or `None` if it is outside.
    pub fn project(&self, clip: Vec4) -> Option<ScreenVertex> {
        let stage = self.stage([0; 3], None);
        let p = clip.to_bits();
        (stage.volume.outcode(&p) == 0).then(|| stage.project(&p))
    }

    /// The vertex stage of one draw, for positions within `bounds` (raw) of the origin on the
    /// `x`, `y` and `z` axes.
    fn stage(&self, bounds: [u32; 3], light: Option<VertexLight>) -> VertexStage {
        let size = self.viewport.size;
        let corner = self.viewport.top_left;
        let viewport = ((corner.x, corner.y), (size.width, size.height));
        VertexStage::new(&self.mvp, bounds, viewport, light)
    }

    /// The unit world-space direction towards the viewer that specular highlights
    /// ([`Material::specular`]) use: the viewer at infinity along the camera's `+z` (view
    /// space), the infinite-viewer approximation.
    ///
    /// It is found once per draw from the view depth's gradient in model space, `mvp`'s `w` row
    /// negated (a perspective projection's `w` is `−z` in view space) or, where that row has no
    /// `x`, `y` or `z` part (an orthographic projection), its `z` row negated, and turned into
    /// world space like a normal, by [`normal_matrix`](Self::normal_matrix): exact (up to
    /// rounding) for `mvp = projection · view · model` with the crate's projections and a normal
    /// matrix that is a positive multiple of the model matrix's inverse transpose. The zero
    /// vector if `mvp` has neither. Rounding: within about 2⁻¹⁴ a component through a
    /// perspective projection; an orthographic one's `z` row is `2/(far − near)` times smaller,
    /// and its rounding costs that factor more.
    ///
    /// ```
    /// # use embedded_graphics::{prelude::*, primitives::Rectangle};
    /// use embedded_raster::three_d::{Angle, Light, Mat4, Pipeline, Vec3};
    ///
    /// let view = Mat4::look_at(Vec3::new(3, 0, 0), Vec3::ZERO, Vec3::new(0, 1, 0)).unwrap();
    /// let camera = Mat4::perspective(Angle::from_degrees(60), 1, 0.5, 20).unwrap() * view;
    /// # let viewport = Rectangle::new(Point::zero(), Size::new(64, 64));
    /// let pipeline = Pipeline::new(Mat4::IDENTITY, camera, viewport, Light::default());
    /// assert_eq!(pipeline.view_direction(), Vec3::new(1, 0, 0)); // towards the eye on +x
    /// ```
    pub fn view_direction(&self) -> Vec3 {
        let m = self.mvp.to_bits();
        let [w, z] = [m[3], m[2]];
        let row = if w[..3].iter().any(|&c| c != 0) { w } else { z };
        let gradient = normalize_wide([row[0], row[1], row[2]].map(|c| -i64::from(c)));
        // The gradient is a normal of the planes of constant view depth.
        let n = self.normal_matrix.to_bits();
        let g = gradient.to_bits().map(i64::from);
        normalize_wide(core::array::from_fn(|r| {
            (0..3)
                .map(|c| i64::from(n[r][c]) * g[c])
                .fold(0i64, i64::saturating_add)
        }))
    }

    /// The draw's lights when [`lights`](Self::lights) light anything, with the highlight
    /// `specular`.
    #[inline(never)]
    fn rig(&self, specular: Option<Specular>) -> Option<LightRig> {
        if !self.lights.lit() {
            return None;
        }
        let (light, lights) = (&self.light, &self.lights);
        let view = self.view_direction();
        LightRig::new(
            light,
            lights,
            &self.model,
            &self.normal_matrix,
            view,
            specular,
        )
    }

    /// The world-space half vector `normalize(l + v)` of the light and the
    /// [`view_direction`](Self::view_direction) (zero if they are opposite).
    fn half_vector(&self) -> Vec3 {
        let (l, v) = (
            self.light.direction.to_bits(),
            self.view_direction().to_bits(),
        );
        normalize_wide(core::array::from_fn(|k| i64::from(l[k]) + i64::from(v[k])))
    }

    /// The unit world-space normal of a model-space normal.
    fn world_normal(&self, n: Vec3) -> Vec3 {
        self.normal_matrix
            .transform_vector(n.normalize())
            .normalize()
    }

    /// Draws every triangle of `mesh` with `material` into `target`, depth-tested, clipped to the
    /// viewport and the target (for any viewport, no pixel outside both is written), transforming
    /// each vertex once per face that uses it (no memory per vertex). [`draw_mesh_with`](Self::draw_mesh_with) transforms each vertex once; both
    /// draw the same pixels.
    pub fn draw_mesh<C: GouraudColor>(
        &self,
        mesh: &Mesh<'_>,
        material: &Material<C>,
        target: &mut impl MeshTarget<C>,
    ) -> DrawStats {
        let clip = target.clip(&self.viewport);
        target.with_depth(|target| {
            let frame = Frame::new(self, mesh, material, clip);
            target.blending(frame.blend(), |target| frame.each_face(mesh, target))
        })
    }

    /// [`draw_mesh`](Self::draw_mesh) with each vertex transformed, projected and lit once, into
    /// `scratch` (at least one entry per mesh vertex: [`ProjectedVertex`] is 16 bytes, so a
    /// 3,000-vertex mesh needs 48 KB). The same pixels as `draw_mesh`; `Err` without drawing
    /// anything if `scratch` is too short.
    pub fn draw_mesh_with<C: GouraudColor>(
        &self,
        mesh: &Mesh<'_>,
        material: &Material<C>,
        target: &mut impl MeshTarget<C>,
        scratch: &mut [ProjectedVertex],
    ) -> Result<DrawStats, ScratchTooSmall> {
        let scratch = fit_scratch(mesh, scratch)?;
        let frame = Frame::new(self, mesh, material, target.clip(&self.viewport));
        frame.project(mesh, scratch);
        Ok(target.with_depth(|target| {
            target.blending(frame.blend(), |target| {
                frame.scratch_faces(mesh, scratch, target)
            })
        }))
    }

    /// Draws every triangle of `mesh` with the textured `material` into `target`, as
    /// [`draw_mesh`](Self::draw_mesh) draws a material: the mesh's texture coordinates
    /// ([`Mesh::uvs`], normalised, `v` up) read the texture perspective-correct, the texel lit
    /// by the material's shading. A mesh without texture coordinates reads texel `(0, 0)`.
    ///
    /// # Examples
    ///
    /// ```
    /// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
    /// use embedded_raster::texture::{Rgb565Texels, Texture};
    /// use embedded_raster::three_d::{Angle, DepthTarget, Light, Mat4, Mesh, Pipeline, Shading};
    /// use embedded_raster::three_d::{TexCoord, TexturedMaterial, Vec3};
    ///
    /// // A square of two triangles, a 2 × 2 texture over it.
    /// static POSITIONS: [Vec3; 4] = [
    ///     Vec3::from_bits(-65536, -65536, 0),
    ///     Vec3::from_bits(65536, -65536, 0),
    ///     Vec3::from_bits(65536, 65536, 0),
    ///     Vec3::from_bits(-65536, 65536, 0),
    /// ];
    /// static UVS: [TexCoord; 4] = [
    ///     TexCoord::from_bits(0, 0),
    ///     TexCoord::from_bits(65536, 0),
    ///     TexCoord::from_bits(65536, 65536),
    ///     TexCoord::from_bits(0, 65536),
    /// ];
    /// static INDICES: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];
    /// static TEXELS: [u16; 4] = [0xf800, 0x07e0, 0x001f, 0xffff];
    /// let mesh = Mesh::new(&POSITIONS, &[], &INDICES).with_uvs(&UVS);
    /// let texture = Texture::new(Rgb565Texels(&TEXELS), 2, 2).unwrap();
    ///
    /// let (mut px, mut z) = ([Rgb565::BLACK; 64 * 64], [0u16; 64 * 64]);
    /// let mut target = DepthTarget::new(&mut px, &mut z, 64, 64).unwrap();
    /// let camera = Mat4::perspective(Angle::from_degrees(60), 1, 0.5, 10).unwrap()
    ///     * Mat4::look_at(Vec3::new(0, 0, 3), Vec3::ZERO, Vec3::new(0, 1, 0)).unwrap();
    /// let viewport = Rectangle::new(Point::zero(), Size::new(64, 64));
    /// let pipeline = Pipeline::new(Mat4::IDENTITY, camera, viewport, Light::default());
    /// let material = TexturedMaterial::new(&texture, Shading::Unlit);
    /// let stats = pipeline.draw_textured_mesh(&mesh, &material, &mut target);
    /// assert_eq!(stats.drawn, 2);
    /// // The top-left quarter of the screen's square is the texture's top-left texel.
    /// assert_eq!(target.framebuffer().get(26, 26), Some(Rgb565::RED));
    /// assert_eq!(target.framebuffer().get(38, 38), Some(Rgb565::WHITE));
    /// ```
    pub fn draw_textured_mesh<S, C, W>(
        &self,
        mesh: &Mesh<'_>,
        material: &TexturedMaterial<'_, S, W>,
        target: &mut impl MeshTarget<C>,
    ) -> DrawStats
    where
        S: TexelSource,
        C: GouraudColor + From<S::Color>,
        W: Opacity,
    {
        let clip = target.clip(&self.viewport);
        target.with_depth(|target| {
            Frame::textured(self, mesh, material, clip).each_face(mesh, target)
        })
    }

    /// [`draw_textured_mesh`](Self::draw_textured_mesh) with each vertex transformed and
    /// projected once into `scratch`, as [`draw_mesh_with`](Self::draw_mesh_with): the same
    /// pixels; `Err` without drawing if `scratch` is too short.
    pub fn draw_textured_mesh_with<S, C, W>(
        &self,
        mesh: &Mesh<'_>,
        material: &TexturedMaterial<'_, S, W>,
        target: &mut impl MeshTarget<C>,
        scratch: &mut [ProjectedVertex],
    ) -> Result<DrawStats, ScratchTooSmall>
    where
        S: TexelSource,
        C: GouraudColor + From<S::Color>,
        W: Opacity,
    {
        let scratch = fit_scratch(mesh, scratch)?;
        let clip = target.clip(&self.viewport);
        let frame = Frame::textured(self, mesh, material, clip);
        frame.project(mesh, scratch);
        Ok(target.with_depth(|target| frame.scratch_faces(mesh, scratch, target)))
    }
}

/// The scratch entries of a face's vertices `idx`, or `None` if an index is past them. Each
/// vertex by name (the array form, `at_face`'s, costs the frame instructions).
#[inline(always)]
fn face_vertices(scratch: &[ProjectedVertex], idx: [usize; 3]) -> Option<[&ProjectedVertex; 3]> {
    Some([
        scratch.get(idx[0])?,
        scratch.get(idx[1])?,
        scratch.get(idx[2])?,
    ])
}

/// The first entry of `scratch` for each vertex of `mesh`, or the error if it is too short.
pub(crate) fn fit_scratch<'s>(
    mesh: &Mesh<'_>,
    scratch: &'s mut [ProjectedVertex],
) -> Result<&'s mut [ProjectedVertex], ScratchTooSmall> {
    let needed = mesh.vertices.len();
    let given = scratch.len();
    scratch
        .get_mut(..needed)
        .ok_or(ScratchTooSmall { needed, given })
}

/// How a draw colours its faces. Copied as a whole (a band's draw copies it, its 256 colours
/// included: a word copy, where a field-by-field clone copies the colours as halves).
enum Fill<C> {
    /// The material colour.
    Unlit(C),
    /// One level per face.
    Flat(ShadeTable<C>),
    /// Levels per vertex, interpolated.
    Gouraud(ShadeTable<C>),
    /// Per-pixel lighting of the quadratic normal field.
    Quadratic(C),
    /// Per-pixel lighting of the quadratic normal field by the first light and the pipeline's
    /// [`Lights`] (the frame's `rig`), highlighted per pixel if there is a highlight.
    QuadraticLights(C, Option<Highlight>),
    /// The frame's texture, lit by one level a face (`Flat`), the vertex levels (`Gouraud`)
    /// or not at all (`Unlit`); tinted by the mesh's vertex colours, and highlighted.
    Textured(Texturing),
    /// The frame's texture lit per pixel by the quadratic normal field (`Quadratic`,
    /// untinted), and highlighted per pixel.
    TexturedPixel(Texturing),
    /// A material with a highlight, lit with `Flat`, `Gouraud` or `Quadratic` shading.
    Specular(Shiny<C>),
}

/// How a draw fills a material with a highlight.
struct Shiny<C> {
    color: C,
    shading: Shading,
    /// The highlight per pixel, its half vector in world space (quadratic shading).
    pixel: Highlight,
    /// The highlight per vertex or face, its half vector in the normals' space.
    vertex: VertexSpecular,
    /// The material colour's levels (flat and Gouraud shading): the faces that the highlight
    /// does not reach (a specular term of 0 at every vertex) are filled as without it.
    table: Option<ShadeTable<C>>,
}

impl<C: Copy> Clone for Fill<C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<C: Copy> Copy for Fill<C> {}

impl<C: Copy> Clone for Shiny<C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<C: Copy> Copy for Shiny<C> {}

/// How a textured draw lights its texels.
#[derive(Debug, Clone, Copy)]
struct Texturing {
    shading: Shading,
    /// Whether the mesh's vertex colours tint them.
    tinted: bool,
    /// The highlight per vertex or face, its half vector in the normals' space.
    highlight: Option<VertexSpecular>,
    /// The highlight per pixel (quadratic shading), its half vector in world space.
    pixel: Option<Highlight>,
}

/// Where the face stage hands the faces it keeps: a target to fill them into now (a frame's, or a
/// band's through a [`RowWindow`]), or a record of them (a band renderer's bin).
pub(crate) trait FaceSink<C> {
    /// Face `k` of the mesh (vertices `idx` at `model`, projected `v`): inside the view volume,
    /// not culled, of non-zero area; `tried` is what a face scan's textured set-up did with it,
    /// if it tried (then not again: `TexturedDraw::Perspective`, to draw perspective-correct).
    #[allow(clippy::too_many_arguments)]
    fn face<R: RowWindow, T: FaceTexture<C>>(
        &mut self,
        frame: &Frame<'_, C, R, T>,
        mesh: &Mesh<'_>,
        k: usize,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3] + Copy,
        v: [&ProjectedVertex; 3],
        tried: Option<TexturedDraw>,
    );

    /// Where the kept faces of `frame` may be drawn by the face scan itself
    /// ([`arch::FaceScan::next_batch`]): the draw's level faces, for the scan's next batch
    /// (none: every kept face is handed to [`face`](Self::face)). Only where that draws what
    /// `face` would.
    #[inline(always)]
    fn level_faces<R: RowWindow, T: FaceTexture<C>>(
        &mut self,
        frame: &Frame<'_, C, R, T>,
    ) -> Option<arch::LevelFace<'static>> {
        let _ = frame;
        None
    }

    /// Where the kept faces of `frame` (a textured draw of `mesh`) may be drawn by the face
    /// scan itself: the draw's textured faces, for the scan's next batch (none: every kept face
    /// is handed to [`face`](Self::face)). Only where that draws what `face` would.
    #[inline(always)]
    fn textured_faces<'f, R: RowWindow, T: FaceTexture<C>>(
        &mut self,
        frame: &'f Frame<'_, C, R, T>,
        mesh: &'f Mesh<'_>,
    ) -> Option<arch::TexturedFaces<'f>> {
        let _ = (frame, mesh);
        None
    }

    /// Face `k`, crossing the view volume's boundary (to be clipped; it may still be dropped:
    /// `stats` counts it).
    #[allow(clippy::too_many_arguments)]
    fn clipped<R: RowWindow, T: FaceTexture<C>>(
        &mut self,
        frame: &Frame<'_, C, R, T>,
        mesh: &Mesh<'_>,
        k: usize,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3] + Copy,
        v: [ProjectedVertex; 3],
        stats: &mut DrawStats,
    );
}

impl<C: GouraudColor> FaceSink<C> for DepthTarget<'_, C> {
    #[inline(always)]
    fn face<R: RowWindow, T: FaceTexture<C>>(
        &mut self,
        frame: &Frame<'_, C, R, T>,
        mesh: &Mesh<'_>,
        _: usize,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3] + Copy,
        v: [&ProjectedVertex; 3],
        tried: Option<TexturedDraw>,
    ) {
        frame.fill(mesh, idx, model, v, None, tried, self);
    }

    #[inline(always)]
    fn level_faces<R: RowWindow, T: FaceTexture<C>>(
        &mut self,
        frame: &Frame<'_, C, R, T>,
    ) -> Option<arch::LevelFace<'static>> {
        frame.level_faces(self)
    }

    #[inline(always)]
    fn textured_faces<'f, R: RowWindow, T: FaceTexture<C>>(
        &mut self,
        frame: &'f Frame<'_, C, R, T>,
        mesh: &'f Mesh<'_>,
    ) -> Option<arch::TexturedFaces<'f>> {
        frame.textured_faces(self, mesh)
    }

    #[inline(always)]
    fn clipped<R: RowWindow, T: FaceTexture<C>>(
        &mut self,
        frame: &Frame<'_, C, R, T>,
        mesh: &Mesh<'_>,
        _: usize,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3] + Copy,
        v: [ProjectedVertex; 3],
        stats: &mut DrawStats,
    ) {
        frame.clipped_face(mesh, idx, model, v, self, stats);
    }
}

/// What the face stage does with a face.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Verdict {
    /// Nothing (outside the view volume or a band's rows, culled, or of no area; counted).
    Dropped,
    /// Clip it: it crosses the view volume's boundary.
    Clipped,
    /// Fill it.
    Drawn,
    /// Fill it perspective-correct: the textured set-up found it not within its screen-space
    /// bound (a face scan's textured faces).
    Perspective,
}

/// Why the face stage drops a face it does not reject outright.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Dropped {
    /// Nothing of it is left inside the view volume.
    Rejected,
    /// Zero area.
    Degenerate,
    /// Facing the culled way.
    Culled,
}

impl Dropped {
    /// Counts it in `stats`.
    pub(crate) fn count(self, stats: &mut DrawStats) {
        match self {
            Dropped::Rejected => stats.rejected += 1,
            Dropped::Degenerate => stats.degenerate += 1,
            Dropped::Culled => stats.culled += 1,
        }
    }
}

/// A face clipped to the view volume and projected: the fan's vertices with their barycentric
/// coordinates in the face, and the face's vertex light levels.
pub(crate) struct ClippedFace {
    screen: heapless::Vec<(ScreenVertex, Bary, Inverse), 12>,
    levels: [u16; 3],
}

impl ClippedFace {
    /// The polygon's vertices in order, each with its barycentric coordinates in the face (a
    /// vertex on the face's edge `j`, from vertex `j` to `j + 1`, has coordinate `(j + 2) % 3`
    /// zero).
    pub(crate) fn outline(&self) -> impl Iterator<Item = (&ScreenVertex, &Bary)> + '_ {
        self.screen.iter().map(|(s, bary, _)| (s, bary))
    }

    /// The sub-pixel heights of the fan's highest and lowest vertices.
    pub(crate) fn heights(&self) -> (i32, i32) {
        let y = self.screen.iter().map(|s| s.0.y.to_bits());
        let top = y.clone().min().unwrap_or(0);
        (top, y.max().unwrap_or(top))
    }
}

/// The state of one draw: the vertex stage, the clip rectangle and its rows, the fill and its
/// texture (none for a material).
pub(crate) struct Frame<'p, C, R = AllRows, T = NoTexture> {
    pipeline: &'p Pipeline,
    stage: VertexStage,
    light: VertexLight,
    clip: TargetClip<R>,
    /// The band's rows as planes in clip space, for a band's draw.
    band: Option<BandPlanes>,
    fill: Fill<C>,
    texture: T,
    /// Whether the vertices take their levels from `rig` (Gouraud shading with it): the frame
    /// lights them after the stage, which then has no light.
    vertex_rig: bool,
    /// Whether a textured draw lights its vertices where it projects them (shading through the
    /// vertices' levels): each one's `texel_level`, found once, not once a face using it.
    lit_texels: bool,
    /// Whether a textured draw's faces go to the target's set-up from their vertices as they
    /// are ([`FaceTexture::fill_small`]): lit by their levels (`Some(true)`: `lit_texels`) or
    /// unlit, untinted and without a highlight.
    small: Option<bool>,
    /// The pipeline's lights ([`Lights`]) when they light anything: then every level and
    /// specular term comes from them instead of `light`.
    rig: Option<LightRig>,
    /// A translucent material's blend, which the draw sets on its target while it draws.
    blend: Option<Blend<C>>,
}

impl<'p, 't, C, R, S, W> Frame<'p, C, R, FrameTexture<'t, S, W>>
where
    C: GouraudColor + From<S::Color>,
    R: RowWindow,
    S: TexelSource,
    W: Opacity,
{
    /// The draw of `mesh` with the textured `material` by `pipeline` inside `clip`.
    pub(crate) fn textured(
        pipeline: &'p Pipeline,
        mesh: &Mesh<'_>,
        material: &TexturedMaterial<'t, S, W>,
        clip: TargetClip<R>,
    ) -> Self {
        let light = VertexLight::new(&pipeline.light, &pipeline.normal_matrix);
        let stage = pipeline.stage(mesh.half_sizes(), None);
        // A highlight of strength 0 is none: the same frame as without it.
        let specular = material
            .specular
            .filter(|s| material.shading != Shading::Unlit && s.strength().to_bits() > 0);
        let pixel = specular.map(|specular| Highlight::new(pipeline.half_vector(), specular));
        let highlight = pixel.map(|h| light.specular(&pipeline.normal_matrix, &h));
        let rig = pipeline.rig(specular);
        let texturing = Texturing {
            shading: material.shading,
            tinted: material.vertex_colors,
            highlight,
            pixel,
        };
        // Per-pixel light is untinted: with the mesh's vertex colours, the vertices' levels (as
        // `Gouraud`).
        let tinted = material.vertex_colors && !mesh.colors.is_empty();
        let fill = match material.shading {
            Shading::Quadratic if !tinted => Fill::TexturedPixel(texturing),
            _ => Fill::Textured(texturing),
        };
        let lit_texels = matches!(
            (&fill, material.shading),
            (Fill::Textured(_), Shading::Gouraud | Shading::Quadratic)
        );
        let texture = FrameTexture::new::<C, R>(material.texture, material.opacity, &clip);
        let plain = !tinted && highlight.is_none() && FaceTexture::<C>::sets_up_small(&texture);
        let small = match material.shading {
            Shading::Unlit if plain && !SIZE_OVER_SPEED => Some(false),
            Shading::Gouraud | Shading::Quadratic if plain && lit_texels => Some(true),
            _ => None,
        };
        Frame {
            pipeline,
            band: clip.rows().band().map(|b| BandPlanes::new(&stage, &b)),
            stage,
            light,
            rig,
            vertex_rig: false,
            lit_texels,
            small,
            clip,
            fill,
            texture,
            // A translucent textured material blends by its type (`FrameTexture`'s `W`).
            blend: None,
        }
    }
}

impl<'p, C: GouraudColor, R: RowWindow> Frame<'p, C, R> {
    /// The draw of `mesh` with `material` by `pipeline` inside `clip`.
    pub(crate) fn new(
        pipeline: &'p Pipeline,
        mesh: &Mesh<'_>,
        material: &Material<C>,
        clip: TargetClip<R>,
    ) -> Self {
        let color = material.color;
        let blend = (material.opacity < 255).then_some(Blend {
            opacity: material.opacity,
            over: C::blend,
        });
        // A highlight of strength 0 is none: the same frame as without it.
        let specular = material
            .specular
            .filter(|s| material.shading != Shading::Unlit && s.strength().to_bits() > 0);
        let rig = pipeline.rig(specular);
        let light = VertexLight::new(&pipeline.light, &pipeline.normal_matrix);
        let highlight = specular.map(|specular| Highlight::new(pipeline.half_vector(), specular));
        let (fill, vertex_light) = match highlight {
            // Per-pixel lighting with the pipeline's lights: its own fill (the others' stay as
            // they are).
            _ if rig.is_some() && material.shading == Shading::Quadratic => {
                (Fill::QuadraticLights(color, highlight), None)
            }
            None => Self::plain_fill(material, light),
            Some(h) => {
                let shading = material.shading;
                let shiny = Shiny {
                    color,
                    shading,
                    pixel: h,
                    vertex: light.specular(&pipeline.normal_matrix, &h),
                    table: (shading != Shading::Quadratic).then(|| ShadeTable::new(color)),
                };
                let vertex_light = (shading == Shading::Gouraud).then_some(light);
                (Fill::Specular(shiny), vertex_light)
            }
        };
        // With the pipeline's lights, the frame lights the vertices (`vertex_rig`), not the
        // stage.
        let vertex_rig = rig.is_some() && vertex_light.is_some();
        let vertex_light = vertex_light.filter(|_| rig.is_none());
        let stage = pipeline.stage(mesh.half_sizes(), vertex_light);
        Frame {
            pipeline,
            band: clip.rows().band().map(|b| BandPlanes::new(&stage, &b)),
            stage,
            light,
            rig,
            vertex_rig,
            lit_texels: false,
            small: None,
            clip,
            fill,
            texture: NoTexture,
            blend,
        }
    }

    /// The fill of a `material` without a highlight, and the light of its vertex stage.
    fn plain_fill(material: &Material<C>, light: VertexLight) -> (Fill<C>, Option<VertexLight>) {
        let color = material.color;
        match material.shading {
            Shading::Unlit => (Fill::Unlit(color), None),
            Shading::Flat => (Fill::Flat(ShadeTable::new(color)), None),
            Shading::Gouraud => (Fill::Gouraud(ShadeTable::new(color)), Some(light)),
            Shading::Quadratic => (Fill::Quadratic(color), None),
        }
    }
}

impl<'p, C: GouraudColor, R: RowWindow, T: FaceTexture<C>> Frame<'p, C, R, T> {
    /// The same draw inside `clip`: a band's rows of it.
    pub(crate) fn with_clip<Q: RowWindow>(&self, clip: TargetClip<Q>) -> Frame<'p, C, Q, T> {
        Frame {
            pipeline: self.pipeline,
            stage: self.stage,
            light: self.light,
            rig: self.rig,
            vertex_rig: self.vertex_rig,
            lit_texels: self.lit_texels,
            small: self.small,
            band: clip.rows().band().map(|b| BandPlanes::new(&self.stage, &b)),
            texture: self.texture.clipped(&clip),
            clip,
            fill: self.fill,
            blend: self.blend,
        }
    }

    /// The blend the draw sets on its target while it draws (none: opaque).
    #[inline(always)]
    pub(crate) fn blend(&self) -> Option<Blend<C>> {
        self.blend
    }

    /// Vertex `k` of `mesh`, at `p`.
    #[inline(always)]
    fn vertex(&self, mesh: &Mesh<'_>, k: usize, p: Vec3) -> ProjectedVertex {
        if T::TEXTURED {
            return self.textured_vertex(mesh, k, p);
        }
        let n = mesh.normals.get(k);
        let vertex = self.stage.vertex(p, n);
        match (self.vertex_rig, n) {
            (true, Some(n)) => self.rig_vertex(vertex, p, n),
            _ => vertex,
        }
    }

    /// Vertex `k` of `mesh` at `p` in a textured draw: projected, and lit if the frame's
    /// levels are the vertices' ([`lit_texels`](Self::lit_texels); those inside the view volume,
    /// whose faces take them from there).
    #[inline(always)]
    fn textured_vertex(&self, mesh: &Mesh<'_>, k: usize, p: Vec3) -> ProjectedVertex {
        let vertex = self.stage.textured_vertex(p);
        if !self.lit_texels || vertex.outside() != 0 {
            return vertex;
        }
        match mesh.normals.get(k) {
            Some(n) => vertex.with_texel_level(match &self.rig {
                None => self.light.level(*n),
                Some(rig) => rig.level(p, *n),
            }),
            None => vertex.without_normal(),
        }
    }

    /// `vertex` (at `p`, with normal `n`) lit by the pipeline's lights. Out of line: the plain
    /// draws' face loop keeps its registers.
    #[inline(never)]
    fn rig_vertex(&self, vertex: ProjectedVertex, p: Vec3, n: &Vec3) -> ProjectedVertex {
        match &self.rig {
            Some(rig) => vertex.with_level(rig.level(p, *n)),
            None => vertex,
        }
    }

    /// Hands every face of `mesh` to `sink`, transforming each vertex once per face using it:
    /// [`Pipeline::draw_mesh`]. A band's draw rejects the faces wholly above or below its rows
    /// from their vertices' clip-space heights (kept for the vertices met last), before
    /// projecting them.
    #[inline(always)]
    pub(crate) fn each_face<S: FaceSink<C>>(&self, mesh: &Mesh<'_>, sink: &mut S) -> DrawStats {
        let mut stats = DrawStats::default();
        let mut sides = SideCache::new();
        for (k, face) in mesh.indices.iter().enumerate() {
            let idx = face.map(usize::from);
            let Some([a, b, c]) = at_face(mesh.vertices, &idx) else {
                stats.invalid += 1;
                continue;
            };
            let model = [*a, *b, *c];
            if let Some(planes) = self.band_planes() {
                if sides.misses(planes, &self.stage, &idx, &model) {
                    stats.rejected += 1;
                    continue;
                }
            }
            // Each vertex by name: no index to check.
            let (a, b, c) = (
                self.vertex(mesh, idx[0], model[0]),
                self.vertex(mesh, idx[1], model[1]),
                self.vertex(mesh, idx[2], model[2]),
            );
            let verdict = self.verdict([&a, &b, &c], &mut stats);
            self.kept_face(
                verdict,
                mesh,
                k,
                &idx,
                || model,
                [&a, &b, &c],
                sink,
                &mut stats,
            );
        }
        stats
    }

    /// The band's planes, for a band's draw (never for a frame's: no code at all).
    #[inline(always)]
    fn band_planes(&self) -> Option<&BandPlanes> {
        self.clip.rows().band().and(self.band.as_ref())
    }

    /// Every vertex of `mesh` transformed, projected and lit into `scratch` (one entry each).
    #[inline(never)]
    pub(crate) fn project(&self, mesh: &Mesh<'_>, scratch: &mut [ProjectedVertex]) {
        if T::TEXTURED {
            let (vertices, normals) = (mesh.vertices, mesh.normals);
            if !self.lit_texels {
                // Unlit and per-pixel draws: a loop of their own, without the general loop's
                // tests for each vertex (kept: without it they measured slower).
                if !self.stage.project_inside(vertices, scratch, true) {
                    for (out, p) in scratch.iter_mut().zip(vertices) {
                        *out = self.stage.textured_vertex(*p);
                    }
                }
            } else if self.rig.is_none() && normals.len() >= vertices.len() {
                // The common case with its tests hoisted: every vertex has a normal, and the
                // light is the pipeline's own (the same levels as `textured_vertex`'s).
                if self.stage.project_inside(vertices, scratch, true) {
                    // Every vertex inside the view volume.
                    let count = vertices.len().min(scratch.len());
                    let out = &mut scratch[..count];
                    self.light.light_all(normals, out, LevelField::TexelLevel);
                    return;
                }
                for ((out, p), n) in scratch.iter_mut().zip(vertices).zip(normals) {
                    let vertex = self.stage.textured_vertex(*p);
                    *out = match vertex.outside() {
                        0 => vertex.with_texel_level(self.light.level(*n)),
                        _ => vertex,
                    };
                }
            } else {
                for (k, (out, p)) in scratch.iter_mut().zip(vertices).enumerate() {
                    *out = self.textured_vertex(mesh, k, *p);
                }
            }
            return;
        }
        self.stage.vertices(mesh.vertices, mesh.normals, scratch);
        if self.vertex_rig {
            self.rig_vertices(mesh, scratch);
        }
    }

    /// The levels of the vertices in `scratch` from the pipeline's lights (a second pass: the
    /// stage's loops stay as they are).
    #[inline(never)]
    fn rig_vertices(&self, mesh: &Mesh<'_>, scratch: &mut [ProjectedVertex]) {
        let Some(rig) = &self.rig else {
            return;
        };
        for ((out, p), n) in scratch.iter_mut().zip(mesh.vertices).zip(mesh.normals) {
            *out = out.with_level(rig.level(*p, *n));
        }
    }

    /// Hands every face of `mesh` to `sink`, its vertices read from `scratch` (one entry per
    /// vertex, filled by [`project`](Self::project)): [`Pipeline::draw_mesh_with`].
    #[inline]
    pub(crate) fn scratch_faces<S: FaceSink<C>>(
        &self,
        mesh: &Mesh<'_>,
        scratch: &[ProjectedVertex],
        sink: &mut S,
    ) -> DrawStats {
        // A draw of every row, one side culled: the target's face scan, where there is one.
        if arch::FACE_SCAN && self.clip.rows().band().is_none() {
            let keep_front = match self.pipeline.cull {
                Cull::Back => Some(true),
                Cull::Front => Some(false),
                Cull::None => None,
            };
            let scan = keep_front.and_then(|f| arch::FaceScan::new(mesh.indices, scratch, f));
            if let Some(scan) = scan {
                return self.scanned_faces(mesh, scratch, scan, sink);
            }
        }
        let mut stats = DrawStats::default();
        for (k, face) in mesh.indices.iter().enumerate() {
            let idx = face.map(usize::from);
            let Some([a, b, c]) = face_vertices(scratch, idx) else {
                stats.invalid += 1;
                continue;
            };
            // Most faces end here: nothing else of them is read before.
            let verdict = self.verdict([a, b, c], &mut stats);
            if verdict == Verdict::Dropped {
                continue;
            }
            self.scratch_face(verdict, mesh, k, (face, idx), [a, b, c], sink, &mut stats);
        }
        stats
    }

    /// [`scratch_faces`](Self::scratch_faces) through the face scan `scan` of the mesh's faces
    /// (`arch::FACE_SCAN`): the faces it hands on clipped or filled, in order, the same counts.
    #[inline(always)]
    fn scanned_faces<S: FaceSink<C>>(
        &self,
        mesh: &Mesh<'_>,
        scratch: &[ProjectedVertex],
        mut scan: arch::FaceScan<'_>,
        sink: &mut S,
    ) -> DrawStats {
        let mut stats = DrawStats::default();
        let mut batch = [0; arch::FACE_BATCH];
        let mut handed = 0u32;
        loop {
            let mut level = sink.level_faces(self);
            let mut textured = sink.textured_faces(self, mesh);
            let entries = scan.next_batch(&mut batch, level.as_mut(), textured.as_mut());
            if entries.is_empty() {
                break;
            }
            handed += entries.len() as u32;
            for &entry in entries {
                let k = (entry >> 2) as usize;
                let Some(face) = mesh.indices.get(k) else {
                    continue;
                };
                let idx = face.map(usize::from);
                let Some([a, b, c]) = face_vertices(scratch, idx) else {
                    // `SCANNED_INVALID`.
                    stats.invalid += 1;
                    continue;
                };
                let verdict = match entry & 3 {
                    arch::SCANNED_CLIPPED => Verdict::Clipped,
                    arch::SCANNED_PERSPECTIVE => Verdict::Perspective,
                    _ => Verdict::Drawn,
                };
                if verdict != Verdict::Clipped {
                    stats.drawn += 1;
                }
                self.scratch_face(verdict, mesh, k, (face, idx), [a, b, c], sink, &mut stats);
            }
        }
        // The faces not handed on: drawn by the scan, rejected, degenerate or culled.
        let (rejected, degenerate, drawn) = scan.counts();
        stats.rejected += rejected;
        stats.degenerate += degenerate;
        stats.drawn += drawn;
        stats.culled += (mesh.indices.len() as u32)
            .wrapping_sub(handed)
            .wrapping_sub(rejected)
            .wrapping_sub(degenerate)
            .wrapping_sub(drawn);
        stats
    }

    /// Hands the face `k` (`face`, its vertices `v` in the scratch) that `verdict` keeps to
    /// `sink`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn scratch_face<S: FaceSink<C>>(
        &self,
        verdict: Verdict,
        mesh: &Mesh<'_>,
        k: usize,
        (face, idx): (&[u16; 3], [usize; 3]),
        v: [&ProjectedVertex; 3],
        sink: &mut S,
        stats: &mut DrawStats,
    ) {
        // Only flat shading, faces without normals and clipping need the positions again:
        // in range, as the scratch has one entry per vertex.
        let vertices = mesh.vertices;
        if arch::MCU {
            // By value: a closure holding the address of `idx` would keep it in memory
            // every face, for the clipped ones.
            let model = move || idx.map(|i| vertices.get(i).copied().unwrap_or_default());
            self.kept_face(verdict, mesh, k, &idx, model, v, sink, stats);
        } else {
            // The mesh's own indices: the copy of `idx` above is stored every face, and a
            // host reading the three stored words back as one stalls its store forwarding.
            let model =
                move || face.map(|i| vertices.get(usize::from(i)).copied().unwrap_or_default());
            self.kept_face(verdict, mesh, k, &idx, model, v, sink, stats);
        }
    }

    /// Fills the face of `mesh` of the vertices `idx` (a face
    /// [`scratch_faces`](Self::scratch_faces) handed a sink, `clipped` if through
    /// [`FaceSink::clipped`]) into `target`, its vertices read from `scratch`: the same pixels
    /// as then. Nothing for indices past the scratch.
    #[inline(always)]
    pub(crate) fn refill(
        &self,
        mesh: &Mesh<'_>,
        scratch: &[ProjectedVertex],
        idx: &[usize; 3],
        clipped: bool,
        target: &mut DepthTarget<'_, C>,
    ) {
        let idx = *idx;
        let Some([a, b, c]) = at_face(scratch, &idx) else {
            return;
        };
        let model = || idx.map(|i| mesh.vertices.get(i).copied().unwrap_or_default());
        if clipped {
            self.refill_clipped(mesh, &idx, &[*a, *b, *c], target);
        } else {
            self.fill(mesh, &idx, model, [a, b, c], None, None, target);
        }
    }

    /// The light levels of a face's vertices `v` (at `model`): their own, or the face's for
    /// those without a normal.
    #[inline(always)]
    fn vertex_levels(&self, model: impl Fn() -> [Vec3; 3], v: [&ProjectedVertex; 3]) -> [u16; 3] {
        let face = v.iter().all(|v| v.has_normal()).then_some(0);
        let face = face.unwrap_or_else(|| self.face_level(&model()));
        v.map(|v| if v.has_normal() { v.level() } else { face })
    }

    /// The vertices `v` (at `model`) as a Gouraud fill reads them, with the levels
    /// [`vertex_levels`](Self::vertex_levels) gives: `v` itself when every vertex has a normal,
    /// else relit copies ([`relit`](Self::relit)), kept in `lit` (the caller's, so that the fill
    /// reads them in place).
    #[inline(always)]
    fn lit_vertices<'v>(
        &self,
        model: impl Fn() -> [Vec3; 3],
        v: [&'v ProjectedVertex; 3],
        lit: &'v mut Option<[ProjectedVertex; 3]>,
    ) -> [&'v ProjectedVertex; 3] {
        if v.iter().all(|v| v.has_normal()) {
            return v;
        }
        lit.insert(self.relit(model, v)).each_ref()
    }

    /// Copies of the vertices `v` (at `model`), some without a normal, lit as
    /// [`vertex_levels`](Self::vertex_levels) lights them. Out of line: rare, and the face loop
    /// keeps its registers.
    #[cold]
    #[inline(never)]
    fn relit(
        &self,
        model: impl Fn() -> [Vec3; 3],
        v: [&ProjectedVertex; 3],
    ) -> [ProjectedVertex; 3] {
        let ([a, b, c], [la, lb, lc]) = (v, self.vertex_levels(model, v));
        let lit = |v: &ProjectedVertex, level| ProjectedVertex::lit(*v.screen(), level);
        [lit(a, la), lit(b, lb), lit(c, lc)]
    }

    /// [`refill`](Self::refill) of a clipped face (out of line: rare, and its polygon is large).
    #[inline(never)]
    fn refill_clipped(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        v: &[ProjectedVertex; 3],
        target: &mut DepthTarget<'_, C>,
    ) {
        let model = || idx.map(|i| mesh.vertices.get(i).copied().unwrap_or_default());
        if let Ok(face) = self.clip_face(model, v) {
            self.fill_fan(mesh, idx, model, &face, target);
        }
    }
}

impl<C: GouraudColor> Frame<'_, C, Band> {
    /// The light levels' colours of a Gouraud draw, whose small faces a band's draw can keep
    /// set up for the next band ([`refill_levels`](Self::refill_levels)); `None` for the
    /// other shadings.
    #[inline(always)]
    pub(crate) fn levels(&self) -> Option<&ShadeTable<C>> {
        match &self.fill {
            Fill::Gouraud(table) => Some(table),
            _ => None,
        }
    }

    /// [`refill`](Self::refill) of a Gouraud draw (`table` from [`levels`](Self::levels)).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn refill_levels(
        &self,
        table: &ShadeTable<C>,
        mesh: &Mesh<'_>,
        scratch: &[ProjectedVertex],
        idx: &[usize; 3],
        clipped: bool,
        target: &mut DepthTarget<'_, C>,
    ) {
        if clipped {
            self.refill(mesh, scratch, idx, clipped, target);
        } else if let Some((model, v)) = self.face_vertices(mesh, scratch, idx) {
            let mut lit = None;
            let v = self.lit_vertices(model, v, &mut lit);
            shading::draw_levels(target, &self.clip, v, table);
        }
    }

    /// [`refill_levels`](Self::refill_levels), writing the set-up of a small face (not
    /// clipped) into `keep` (for [`resume_levels`](Self::resume_levels)): whether it did.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn refill_levels_keeping(
        &self,
        table: &ShadeTable<C>,
        mesh: &Mesh<'_>,
        scratch: &[ProjectedVertex],
        idx: &[usize; 3],
        clipped: bool,
        target: &mut DepthTarget<'_, C>,
        keep: &mut impl KeptWords,
    ) -> bool {
        if clipped {
            self.refill(mesh, scratch, idx, clipped, target);
            return false;
        }
        let Some((model, v)) = self.face_vertices(mesh, scratch, idx) else {
            return false;
        };
        let mut lit = None;
        let v = self.lit_vertices(model, v, &mut lit);
        shading::draw_levels_keeping(target, &self.clip, v, table, keep)
    }

    /// The model positions (on demand) and the vertices in `scratch` of the face of `mesh` of
    /// the vertices `idx`.
    #[inline(always)]
    fn face_vertices<'s, 'm>(
        &self,
        mesh: &Mesh<'m>,
        scratch: &'s [ProjectedVertex],
        idx: &[usize; 3],
    ) -> Option<(impl Fn() -> [Vec3; 3] + Copy + 'm, [&'s ProjectedVertex; 3])> {
        let idx = *idx;
        let v = at_face(scratch, &idx)?;
        // By value: the indices stay in registers.
        let vertices = mesh.vertices;
        let model = move || idx.map(|i| vertices.get(i).copied().unwrap_or_default());
        Some((model, v))
    }

    /// Draws the band's rows of the face whose set-up [`refill_levels`](Self::refill_levels)
    /// kept in `kept` (in a band of the same frame, `table` from [`levels`](Self::levels)):
    /// the pixels `refill` gives them.
    #[inline(always)]
    pub(crate) fn resume_levels(
        &self,
        table: &ShadeTable<C>,
        target: &mut DepthTarget<'_, C>,
        kept: &impl KeptWords,
    ) {
        shading::resume_levels(target, self.clip.rows(), table, kept);
    }
}

impl<C: GouraudColor, R: RowWindow, T: FaceTexture<C>> Frame<'_, C, R, T> {
    /// The rectangle the draw may write, in frame pixels: the viewport inside the frame.
    pub(crate) fn clip_rect(&self) -> Rectangle {
        self.clip.rect()
    }

    /// The light level of the face `model` (8.8 of the 0–255 scale), from its geometric normal.
    fn face_level(&self, model: &[Vec3; 3]) -> u16 {
        match &self.rig {
            None => self.light.level(face_normal(model)),
            Some(rig) => rig.face_level(model),
        }
    }

    /// The quadratic normal field (`field` of the face's world normals: normalised again, or
    /// taken as unit vectors) on the triangle drawn: the face, or a fan's triangle `bary` of it.
    fn normal_field(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: &[Vec3; 3],
        bary: Option<[Bary; 3]>,
        field: fn([Vec3; 3]) -> QuadraticNormals,
    ) -> QuadraticNormals {
        let normals = field(self.world_normals(mesh, idx, model));
        match bary {
            None => normals,
            Some(bary) => normals.restricted(bary),
        }
    }

    /// The face's unit world-space normals at its vertices, for the quadratic field.
    fn world_normals(&self, mesh: &Mesh<'_>, idx: &[usize; 3], model: &[Vec3; 3]) -> [Vec3; 3] {
        let pipeline = self.pipeline;
        let face = || {
            let (e1, e2) = (model[1] - model[0], model[2] - model[0]);
            pipeline.world_normal(normalize_wide(e1.cross_wide(e2)))
        };
        idx.map(|i| {
            mesh.normals
                .get(i)
                .map_or_else(face, |n| pipeline.world_normal(*n))
        })
    }

    /// Hands face `k` (vertices `idx` at `model`, projected `v`) to `sink` as its
    /// [`verdict`](Self::verdict) says: to clip or to fill (nothing if dropped).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn kept_face<S: FaceSink<C>>(
        &self,
        verdict: Verdict,
        mesh: &Mesh<'_>,
        k: usize,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3] + Copy,
        v: [&ProjectedVertex; 3],
        sink: &mut S,
        stats: &mut DrawStats,
    ) {
        match verdict {
            Verdict::Dropped => {}
            Verdict::Clipped => {
                // A copy for the call: the caller's indices need not be in memory otherwise.
                let idx = *idx;
                sink.clipped(self, mesh, k, &idx, model, v.map(|v| *v), stats);
            }
            Verdict::Drawn => sink.face(self, mesh, k, idx, model, v, None),
            Verdict::Perspective => {
                let tried = Some(TexturedDraw::Perspective);
                sink.face(self, mesh, k, idx, model, v, tried);
            }
        }
    }

    /// What the face stage does with the face of the projected vertices `v` (counted in
    /// `stats`, unless it is to be clipped: the clipping counts it), decided from them alone,
    /// before anything else of the face is read: most faces of a mesh end here.
    #[inline(always)]
    fn verdict(&self, v: [&ProjectedVertex; 3], stats: &mut DrawStats) -> Verdict {
        let codes = v.map(|v| v.outside());
        if codes[0] & codes[1] & codes[2] != 0 {
            stats.rejected += 1;
            return Verdict::Dropped;
        }
        if codes[0] | codes[1] | codes[2] != 0 {
            return Verdict::Clipped;
        }
        let [p0, p1, p2] = v.map(|v| v.position_bits());
        // A band's draw: nothing of a face outside its rows.
        if !self.clip.rows().touches([p0.1, p1.1, p2.1]) {
            stats.rejected += 1;
            return Verdict::Dropped;
        }
        // Inside the guard band every coordinate is within 2²⁵ sub-pixels of the viewport's
        // centre (itself clamped inside i32): the differences fit i32, their products i64.
        // (On Cortex-M0 32 × 32-bit products from limbs: no 64 × 64-bit library calls.)
        let d = |a: i32, b: i32| a.wrapping_sub(b);
        let area =
            mul_i32_wide(d(p1.0, p0.0), d(p2.1, p0.1)) - mul_i32_wide(d(p2.0, p0.0), d(p1.1, p0.1));
        if area == 0 {
            stats.degenerate += 1;
            return Verdict::Dropped;
        }
        if !self.keeps(area < 0) {
            stats.culled += 1;
            return Verdict::Dropped;
        }
        stats.drawn += 1;
        Verdict::Drawn
    }

    /// Whether a face that is `front`-facing is drawn.
    #[inline(always)]
    fn keeps(&self, front: bool) -> bool {
        match self.pipeline.cull {
            Cull::None => true,
            Cull::Back => front,
            Cull::Front => !front,
        }
    }

    /// The draw's level faces into `target` ([`FaceSink::level_faces`]): where a kept face is
    /// filled by [`shading::draw_levels`] as it is (an untextured Gouraud draw, opaque; the
    /// scan takes only faces whose vertices all have normals, which [`fill`](Self::fill) draws
    /// with their own levels) and the target has the small faces' set-up.
    #[inline(always)]
    fn level_faces(&self, target: &mut DepthTarget<'_, C>) -> Option<arch::LevelFace<'static>> {
        match &self.fill {
            Fill::Gouraud(table) if !T::TEXTURED && arch::LEVEL_FACE => {
                shading::level_faces(target, &self.clip, table)
            }
            _ => None,
        }
    }

    /// The draw's textured faces into `target` ([`FaceSink::textured_faces`]): where a kept
    /// face is offered to the target's set-up as [`fill`](Self::fill) offers it (a textured draw
    /// lit per vertex or not at all, whose frame offers its small faces: `small`) and the
    /// target has that set-up for the draw's texture and colours.
    #[inline(always)]
    fn textured_faces<'f>(
        &'f self,
        target: &mut DepthTarget<'_, C>,
        mesh: &'f Mesh<'_>,
    ) -> Option<arch::TexturedFaces<'f>> {
        match &self.fill {
            Fill::Textured(_) if T::TEXTURED && arch::TEXTURED_FACE => {
                let lit = self.small?;
                self.texture.scan_faces(target, mesh.uvs, lit)
            }
            _ => None,
        }
    }

    /// Fills one screen triangle of the face; `bary` places its vertices in the face (clipped
    /// faces' fans); `tried` is what a face scan's set-up did with it, if it tried.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn fill(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3] + Copy,
        v: [&ProjectedVertex; 3],
        bary: Option<[Bary; 3]>,
        tried: Option<TexturedDraw>,
        target: &mut DepthTarget<'_, C>,
    ) {
        // A textured frame's fill is `Textured`: the material fills are not compiled into its
        // draws (a const test: an untextured frame's code is as without it).
        if T::TEXTURED {
            match &self.fill {
                Fill::Textured(texturing) => {
                    // Most faces: the target's set-up from the vertices as they are (where
                    // there is one: a constant test), unless a face scan tried it (`tried`).
                    let set_up = match bary {
                        _ if tried.is_some() => tried,
                        None if arch::TEXTURED_FACE && self.small.is_some() => {
                            self.fill_small(mesh, idx, v, target)
                        }
                        _ => None,
                    };
                    if set_up != Some(TexturedDraw::Done) {
                        self.fill_textured(mesh, idx, model, v, bary, texturing, set_up, target)
                    }
                }
                Fill::TexturedPixel(texturing) => {
                    self.fill_textured_pixel(mesh, idx, model, v, bary, texturing, target)
                }
                _ => {}
            }
            return;
        }
        let clip = &self.clip;
        let tri = v.map(|v| v.screen());
        match &self.fill {
            Fill::Unlit(color) => shading::fill_flat(target, clip, tri, *color),
            Fill::Flat(table) => {
                let level = self.face_level(&model());
                shading::fill_flat(target, clip, tri, table.at(level));
            }
            // A fan's vertices carry the levels interpolated at them (`fill_fan`).
            Fill::Gouraud(table) => {
                let mut lit = None;
                let v = self.lit_vertices(model, v, &mut lit);
                shading::draw_levels(target, clip, v, table);
            }
            Fill::Quadratic(color) => {
                let normals = self.normal_field(mesh, idx, &model(), bary, QuadraticNormals::new);
                let light = &self.pipeline.light;
                shading::fill_quadratic(target, clip, tri, &normals, light, *color);
            }
            Fill::QuadraticLights(color, highlight) => {
                let highlight = highlight.as_ref();
                self.fill_quadratic_lights(mesh, idx, model, v, bary, *color, highlight, target)
            }
            Fill::Textured(texturing) => {
                self.fill_textured(mesh, idx, model, v, bary, texturing, None, target)
            }
            Fill::TexturedPixel(texturing) => {
                self.fill_textured_pixel(mesh, idx, model, v, bary, texturing, target)
            }
            Fill::Specular(shiny) => self.fill_specular(mesh, idx, model, v, bary, shiny, target),
        }
    }

    /// [`fill`](Self::fill) of a material with a highlight (out of line, as the textured
    /// fill).
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn fill_specular(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3] + Copy,
        v: [&ProjectedVertex; 3],
        bary: Option<[Bary; 3]>,
        shiny: &Shiny<C>,
        target: &mut DepthTarget<'_, C>,
    ) {
        let (clip, color, vertex) = (&self.clip, shiny.color, &shiny.vertex);
        match shiny.shading {
            // The vertices' levels as without a highlight (a fan's: interpolated at them), and
            // their specular terms, found here for both paths (the vertex stage has no room for
            // them, and its loops stay as they are).
            Shading::Gouraud => {
                let mut lit = None;
                let v = self.lit_vertices(model, v, &mut lit);
                let speculars = self.vertex_speculars(mesh, idx, model, vertex);
                let speculars = at_bary(bary, speculars.map(|s| [i64::from(s)]));
                // 8.8 of the 0–255 scale, as the levels.
                let speculars =
                    speculars.map(|[s]| ((s.clamp(0, 1 << 16) * 255 + (1 << 7)) >> 8) as u16);
                match &shiny.table {
                    Some(table) if speculars == [0; 3] => {
                        shading::draw_levels(target, clip, v, table);
                    }
                    _ => shading::draw_levels_specular(target, clip, v, speculars, color),
                }
            }
            Shading::Quadratic => {
                let normals = self.normal_field(mesh, idx, &model(), bary, QuadraticNormals::new);
                let (light, tri) = (&self.pipeline.light, v.map(|v| v.screen()));
                let highlight = &shiny.pixel;
                shading::fill_quadratic_specular(
                    target, clip, tri, &normals, light, highlight, color,
                );
            }
            // Flat (a material without light has no highlight).
            _ => {
                let model = model();
                let (level, specular) = match &self.rig {
                    None => self.light.terms(face_normal(&model), vertex),
                    Some(rig) => rig.face_terms(&model),
                };
                let color = match &shiny.table {
                    // The level of `face_level`.
                    Some(table) if specular == 0 => table.at(((level * 255) >> 8) as u16),
                    _ => shading::highlighted_channels(color.channels(), level, specular),
                };
                shading::fill_flat(target, clip, v.map(|v| v.screen()), color);
            }
        }
    }

    /// [`fill`](Self::fill) of an untextured material lit per pixel with the pipeline's lights
    /// (out of line): the face's quadratic normal field (restricted to a fan's triangle) lit by
    /// the first light and the sources that reach the face ([`LightRig::pixel_sources`]: a
    /// point light's direction and falloff at its centroid), with the highlight if any. A face
    /// no source reaches is filled as without the lights.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn fill_quadratic_lights(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3],
        v: [&ProjectedVertex; 3],
        bary: Option<[Bary; 3]>,
        color: C,
        highlight: Option<&Highlight>,
        target: &mut DepthTarget<'_, C>,
    ) {
        let model = model();
        let normals = self.normal_field(mesh, idx, &model, bary, QuadraticNormals::new);
        let (clip, light, tri) = (&self.clip, &self.pipeline.light, v.map(|v| v.screen()));
        let sources = match &self.rig {
            Some(rig) => rig.pixel_sources(&model),
            None => Default::default(),
        };
        // Without a source here: the first light's fills (with `count` 0, the highlighted one).
        let sources = sources.0.get(..sources.1).unwrap_or(&[]);
        match (sources, highlight) {
            ([], None) => shading::fill_quadratic(target, clip, tri, &normals, light, color),
            _ => shading::fill_quadratic_lights(
                target, clip, tri, &normals, light, highlight, sources, color,
            ),
        }
    }

    /// The specular terms (16 fractional bits) of the face's vertices `idx` (at `model`) for
    /// the highlight `s`: from the mesh's normals, the face's normal for vertices without one
    /// (as their light levels).
    fn vertex_speculars(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3],
        s: &VertexSpecular,
    ) -> [u32; 3] {
        let Some(rig) = &self.rig else {
            let face = || self.light.terms(face_normal(&model()), s).1;
            return idx.map(|i| {
                mesh.normals
                    .get(i)
                    .map_or_else(&face, |n| self.light.terms(*n, s).1)
            });
        };
        // The pipeline's lights: at the vertices' positions.
        let model = model();
        let face = || rig.face_terms(&model).1;
        let at = |k: usize| {
            let p = model.get(k).copied().unwrap_or_default();
            idx.get(k)
                .and_then(|&i| mesh.normals.get(i))
                .map_or_else(&face, |n| rig.terms(p, *n).1)
        };
        [at(0), at(1), at(2)]
    }

    /// The target's set-up of a textured face from its vertices as they are, where the draw
    /// allows it ([`FaceTexture::fill_small`]; a fan's triangles and vertices without a normal
    /// in a lit draw take the fill's light): what it did, if it was offered the face. Out of
    /// line, apart from [`fill_textured`](Self::fill_textured) and its large frame, which the
    /// faces it draws then never set up.
    #[inline(never)]
    fn fill_small(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        v: [&ProjectedVertex; 3],
        target: &mut DepthTarget<'_, C>,
    ) -> Option<TexturedDraw> {
        let lit = self.small?;
        if lit && !v.iter().all(|v| v.has_normal()) {
            return None;
        }
        let texels = self.texels(mesh, idx);
        Some(self.texture.fill_small(target, v, texels, lit))
    }

    /// [`fill`](Self::fill) of a textured draw (out of line: the untextured fills keep their
    /// registers); `set_up` is what [`fill_small`](Self::fill_small) did with it, if anything.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn fill_textured(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3],
        v: [&ProjectedVertex; 3],
        bary: Option<[Bary; 3]>,
        texturing: &Texturing,
        set_up: Option<TexturedDraw>,
        target: &mut DepthTarget<'_, C>,
    ) {
        let Texturing {
            shading, tinted, ..
        } = *texturing;
        let colors = if tinted {
            at_face(mesh.colors, idx)
        } else {
            None
        };
        let speculars = texturing
            .highlight
            .map(|h| self.texel_speculars(mesh, idx, &model, bary, shading, &h))
            .filter(|s| *s != [0; 3]);
        let light = match (shading, colors, speculars) {
            (Shading::Unlit, None, _) => TexelLight::Full,
            (Shading::Flat, None, None) => TexelLight::Level(self.face_level(&model())),
            (Shading::Gouraud | Shading::Quadratic, None, None) => {
                let levels = self.face_texel_levels(mesh, idx, &model, v, bary);
                let levels = at_bary(bary, levels.map(|l| [i64::from(l)]));
                TexelLight::Levels(levels.map(|[l]| l.clamp(0, u16::MAX.into()) as u16))
            }
            (shading, colors, speculars) => {
                let levels = match shading {
                    Shading::Unlit => [u16::MAX; 3],
                    Shading::Flat => [self.face_level(&model()); 3],
                    Shading::Gouraud | Shading::Quadratic => {
                        self.face_texel_levels(mesh, idx, &model, v, bary)
                    }
                };
                let white = [&Rgb888::WHITE; 3];
                let colors = colors.unwrap_or(white);
                let tints = zip3_with(levels, colors, [(); 3], |level, color, ()| {
                    tint(color, i64::from(level.min(255 << 8)))
                });
                let tints = at_bary(bary, tints);
                let tints = tints.map(|t| t.map(|c| c.clamp(0, i64::from(255 << 8)) as u16));
                match speculars {
                    None => TexelLight::Tints(tints),
                    Some(speculars) => TexelLight::Shiny { tints, speculars },
                }
            }
        };
        self.fill_texels(mesh, idx, v, bary, light, set_up, target);
    }

    /// [`fill`](Self::fill) of a textured draw lit per pixel (out of line, as
    /// [`fill_textured`](Self::fill_textured)): the face's quadratic normal field (restricted
    /// to a fan's triangle), lit by the pipeline's light and highlight.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn fill_textured_pixel(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3],
        v: [&ProjectedVertex; 3],
        bary: Option<[Bary; 3]>,
        texturing: &Texturing,
        target: &mut DepthTarget<'_, C>,
    ) {
        // World normals are unit vectors already.
        let normals = self.normal_field(mesh, idx, &model(), bary, QuadraticNormals::of_unit);
        let sources = match &self.rig {
            Some(rig) => rig.pixel_sources(&model()),
            None => Default::default(),
        };
        let h = texturing.pixel.as_ref();
        let pixel = PixelLight::new(&normals, &self.pipeline.light, h, sources);
        let light = TexelLight::Quadratic(&pixel);
        self.fill_texels(mesh, idx, v, bary, light, None, target);
    }

    /// The textured face's triangle `v` (a fan's at `bary`) filled with its texels lit by
    /// `light` (`set_up`: what the target's set-up did with it, if it was offered there).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn fill_texels(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        v: [&ProjectedVertex; 3],
        bary: Option<[Bary; 3]>,
        light: TexelLight<'_>,
        set_up: Option<TexturedDraw>,
        target: &mut DepthTarget<'_, C>,
    ) {
        let texels = self.texels(mesh, idx);
        let texels = at_bary(bary, texels.map(|t| t.map(i64::from)));
        let texels = texels.map(|t| t.map(|c| c as i32));
        let q = v.map(|v| v.q());
        let tri = v.map(|v| v.screen());
        self.texture
            .fill(target, &self.clip, tri, q, texels, light, set_up);
    }

    /// The specular terms of a textured face's vertices `idx` (at `model`; a fan's at `bary`)
    /// for the highlight `h`, 8.8 of the 0–255 scale as its levels: per vertex (Gouraud and
    /// quadratic shading) or the face's (flat).
    fn texel_speculars(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: &impl Fn() -> [Vec3; 3],
        bary: Option<[Bary; 3]>,
        shading: Shading,
        h: &VertexSpecular,
    ) -> [u16; 3] {
        let eight = |s: i64| ((s.clamp(0, 1 << 16) * 255 + (1 << 7)) >> 8) as u16;
        match shading {
            Shading::Unlit => [0; 3],
            Shading::Flat => {
                let model = model();
                let (_, specular) = match &self.rig {
                    None => self.light.terms(face_normal(&model), h),
                    Some(rig) => rig.face_terms(&model),
                };
                [eight(i64::from(specular)); 3]
            }
            Shading::Gouraud | Shading::Quadratic => {
                let speculars = self.vertex_speculars(mesh, idx, model, h);
                at_bary(bary, speculars.map(|s| [i64::from(s)])).map(|[s]| eight(s))
            }
        }
    }

    /// The 16.16 texel coordinates of the face's vertices `idx` from the mesh's normalised
    /// texture coordinates (`v` up: the texture's row 0 is at `v = 1`); 0 without them.
    #[inline(always)]
    fn texels(&self, mesh: &Mesh<'_>, idx: &[usize; 3]) -> [[i32; 2]; 3] {
        let (w, h) = self.texture.size();
        // Sides up to 2¹⁵: 32-bit products, saturated (the exact products clamped to i32).
        let (w, h) = (w as i32, h as i32);
        match at_face(mesh.uvs, idx) {
            Some(t) => t.map(|t| {
                let [u, v] = t.to_bits();
                [
                    u.saturating_mul(w),
                    (1i32 << 16).saturating_sub(v).saturating_mul(h),
                ]
            }),
            None => [[0; 2]; 3],
        }
    }

    /// The light levels of the face's vertices `idx` (at `model`, projected `v`; a fan's
    /// triangle if `bary`) in a textured draw: the vertices' own where the frame lit them, else
    /// [`texel_levels`](Self::texel_levels) (a fan's vertices are new, and a vertex without a
    /// normal takes the face's level) — the same levels.
    #[inline(always)]
    fn face_texel_levels(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: &impl Fn() -> [Vec3; 3],
        v: [&ProjectedVertex; 3],
        bary: Option<[Bary; 3]>,
    ) -> [u16; 3] {
        let [a, b, c] = v;
        let own = a.has_normal() && b.has_normal() && c.has_normal();
        if self.lit_texels && bary.is_none() && own {
            [a.texel_level(), b.texel_level(), c.texel_level()]
        } else {
            self.texel_levels(mesh, idx, model)
        }
    }

    /// The light levels of the face's vertices `idx` (at `model`) in a textured draw, from the
    /// mesh's normals (the face's normal for a mesh without them). Out of line: most faces take
    /// their vertices' levels, and the textured fill keeps its registers.
    #[inline(never)]
    fn texel_levels(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: &impl Fn() -> [Vec3; 3],
    ) -> [u16; 3] {
        // The positions only where the levels need them (the pipeline's lights, or the face's
        // normal): a directional light's levels are the normals' alone.
        match at_face(mesh.normals, idx) {
            Some([a, b, c]) => match &self.rig {
                None => [a, b, c].map(|n| self.light.level(*n)),
                Some(rig) => {
                    let model = model();
                    [
                        rig.level(model[0], *a),
                        rig.level(model[1], *b),
                        rig.level(model[2], *c),
                    ]
                }
            },
            None => [self.face_level(&model()); 3],
        }
    }

    /// A face crossing the view volume's boundary: clipped in clip space and drawn as a fan.
    #[inline(never)]
    fn clipped_face(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3] + Copy,
        v: [ProjectedVertex; 3],
        target: &mut DepthTarget<'_, C>,
        stats: &mut DrawStats,
    ) {
        stats.clipped += 1;
        match self.clip_face(model, &v) {
            Ok(face) => {
                stats.drawn += 1;
                self.fill_fan(mesh, idx, model, &face, target);
            }
            Err(dropped) => dropped.count(stats),
        }
    }

    /// The face at `model` (projected `v`), clipped in clip space and projected, or why it is
    /// dropped: nothing left, zero area or culled (the orientation of the whole polygon).
    pub(crate) fn clip_face(
        &self,
        model: impl Fn() -> [Vec3; 3],
        v: &[ProjectedVertex; 3],
    ) -> Result<ClippedFace, Dropped> {
        let mut poly = Polygon::new();
        for (k, p) in model().iter().enumerate() {
            let mut bary = [0; 3];
            bary[k] = BARY_ONE;
            let _ = poly.push(ClipVertex {
                p: self.stage.clip_position(*p),
                bary,
            });
        }
        if !self.stage.volume.clip(&mut poly) {
            return Err(Dropped::Rejected);
        }
        let mut screen: heapless::Vec<(ScreenVertex, Bary, Inverse), 12> = heapless::Vec::new();
        for c in &poly {
            let (vertex, q) = self.stage.project_inverse(&c.p);
            let _ = screen.push((vertex, c.bary, q));
        }
        // Orientation of the whole (convex) polygon: the sum of its fan's areas.
        let area: i128 = (1..screen.len().saturating_sub(1))
            .filter_map(|k| {
                let (s0, s1, s2) = (screen.first()?, screen.get(k)?, screen.get(k + 1)?);
                Some(signed_area2([
                    s0.0.position(),
                    s1.0.position(),
                    s2.0.position(),
                ]))
            })
            .sum();
        if area == 0 {
            return Err(Dropped::Degenerate);
        }
        if !self.keeps(area < 0) {
            return Err(Dropped::Culled);
        }
        let levels = self.vertex_levels(model, v.each_ref());
        Ok(ClippedFace { screen, levels })
    }

    /// Fills the fan of the clipped face `face` (vertices `idx` at `model`).
    pub(crate) fn fill_fan(
        &self,
        mesh: &Mesh<'_>,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3] + Copy,
        face: &ClippedFace,
        target: &mut DepthTarget<'_, C>,
    ) {
        let screen = &face.screen;
        for k in 1..screen.len().saturating_sub(1) {
            let (Some(s0), Some(s1), Some(s2)) = (screen.first(), screen.get(k), screen.get(k + 1))
            else {
                continue;
            };
            let bary = [s0.1, s1.1, s2.1];
            // The face's levels at the fan's vertices.
            let level = |b: &Bary| {
                let l: i64 = (0..3)
                    .map(|k| i64::from(b[k]) * i64::from(face.levels[k]))
                    .sum();
                ((l + (1 << 29)) >> 30).clamp(0, i64::from(u16::MAX)) as u16
            };
            let textured =
                T::TEXTURED || matches!(self.fill, Fill::Textured(..) | Fill::TexturedPixel(..));
            let v = [s0, s1, s2].map(|s| match textured {
                true => ProjectedVertex::with_q(s.0, s.2),
                false => ProjectedVertex::lit(s.0, level(&s.1)),
            });
            self.fill(mesh, idx, model, v.each_ref(), Some(bary), None, target);
        }
    }
}

/// Per-vertex values of a face at the vertices of its clipped fan, whose barycentric coordinates
/// in the face are `bary` (30 fractional bits); the values themselves for a whole face.
#[inline(always)]
fn at_bary<const N: usize>(bary: Option<[Bary; 3]>, values: [[i64; N]; 3]) -> [[i64; N]; 3] {
    let Some(bary) = bary else {
        return values;
    };
    bary.map(|b| {
        core::array::from_fn(|k| {
            let sum: i64 = (0..3).map(|v| i64::from(b[v]) * values[v][k]).sum();
            (sum + (1 << 29)) >> 30
        })
    })
}

/// A vertex colour times a light level (8.8 of the 0–255 scale, at most 255): each channel's
/// tint, 8.8 of the 0–255 scale (`c · level / 255`, by `257 / 2¹⁶` for the division, within
/// 2⁻⁸ of a level).
#[inline(always)]
fn tint(color: &Rgb888, level: i64) -> [i64; 3] {
    [color.r(), color.g(), color.b()].map(|c| (i64::from(c) * level * 257 + (1 << 15)) >> 16)
}

/// The unit geometric normal of the face `model` (model space).
fn face_normal(model: &[Vec3; 3]) -> Vec3 {
    let (e1, e2) = (model[1] - model[0], model[2] - model[0]);
    normalize_wide(e1.cross_wide(e2))
}

/// The entries of `items` at a face's three indices, if all are there.
#[inline(always)]
fn at_face<'i, T>(items: &'i [T], idx: &[usize; 3]) -> Option<[&'i T; 3]> {
    Some([items.get(idx[0])?, items.get(idx[1])?, items.get(idx[2])?])
}

#[cfg(test)]
mod tests {
    extern crate std;

    use std::string::ToString;

    use super::*;

    /// The error's message: what was needed and what was given (issue #32, item 2).
    #[test]
    fn scratch_too_small_message() {
        let e = ScratchTooSmall {
            needed: 2191,
            given: 2190,
        };
        assert_eq!(
            e.to_string(),
            "a vertex scratch needs 2191 entries (one per vertex of the mesh), given 2190"
        );
    }
}
