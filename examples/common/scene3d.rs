//! The 3D benchmark scene, shared by the firmware benchmark (`fw_mesh_bench`), the host's
//! checksums and `bench_report` (included with `#[path]`): a mesh rendered into a 320×240 Rgb565
//! framebuffer with a 16-bit z-buffer, back faces culled, Gouraud-lit by one directional light
//! plus ambient, colour and depth cleared first, from a fixed camera and pose.
//!
//! Three meshes:
//!
//! * [`SPOT`]: Keenan Crane's cow, 5,856 faces (2,930 vertices), which its author released into
//!   the public domain (`meshes/spot/README.txt`), stored in flash (`meshes/spot.rs`, converted
//!   on the host from `meshes/spot/spot_triangulated.obj` by `tests/all/meshes.rs`, which checks it).
//! * [`KNOT`]: a tube around the trefoil knot, 6,144 faces (3,072 vertices) whose radius swells
//!   and narrows along it, stored in flash (`meshes/knot.rs`, generated on the host by
//!   `meshes::torus_knot` and checked by `tests/all/meshes.rs`). It overlaps itself, so the depth
//!   test decides many pixels.
//! * the torus of [`torus`]: 10,000 faces (5,000 vertices), generated at start-up in fixed point
//!   (the same bits on every target), into RAM the caller provides.
//!
//! Everything here is integer code, so the host and every Cortex-M render the same pixels.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::three_d::{
    Angle, DepthTarget, DrawStats, Light, Mat4, Material, Mesh, Pipeline, ProjectedVertex, Scalar,
    Shading, Vec3, DEPTH_CLEAR,
};

#[allow(clippy::all)]
#[rustfmt::skip]
#[path = "fnv.rs"]
mod fnv;
pub use fnv::{fnv, FNV_START};

#[path = "meshes/knot.rs"]
mod knot;

pub use knot::KNOT;

#[allow(clippy::all)]
#[rustfmt::skip]
#[path = "meshes/spot.rs"]
mod spot;

// Not every file that includes the scene draws spot (the band tests and firmware draw the knot).
#[allow(unused_imports)]
pub use spot::SPOT;

/// The frame: 320×240, a common SPI display's size.
pub const SIZE: (u32, u32) = (320, 240);

/// Pixels of the frame.
pub const PIXELS: usize = (SIZE.0 * SIZE.1) as usize;

/// Rings around the torus's axis and sides around its tube.
pub const TORUS_RINGS: usize = 100;
/// Sides around the torus's tube.
pub const TORUS_SIDES: usize = 50;
/// Vertices of the torus.
pub const TORUS_VERTICES: usize = TORUS_RINGS * TORUS_SIDES;
/// Faces of the torus.
pub const TORUS_FACES: usize = 2 * TORUS_VERTICES;

/// Vertices of the larger mesh: the scratch the frames need.
pub const MAX_VERTICES: usize = TORUS_VERTICES;

/// The three bench meshes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    /// [`SPOT`].
    Spot,
    /// [`KNOT`].
    Knot,
    /// The torus of [`torus`].
    Torus,
}

impl Model {
    /// All, in report order.
    pub const ALL: [Model; 3] = [Model::Spot, Model::Knot, Model::Torus];

    /// The name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Model::Spot => "spot",
            Model::Knot => "knot",
            Model::Torus => "torus",
        }
    }

    /// The model's mesh: a flash one, or `torus` (generated into RAM by [`torus`]).
    pub fn mesh<'a>(self, torus: &'a Mesh<'a>) -> &'a Mesh<'a> {
        match self {
            Model::Spot => &SPOT,
            Model::Knot => &KNOT,
            Model::Torus => torus,
        }
    }

    /// The model's pose: a rotation that shows the mesh overlapping itself.
    fn pose(self) -> Mat4 {
        match self {
            Model::Spot => spot_pose(Angle::from_degrees(145)),
            Model::Knot => {
                Mat4::rotation_x(Angle::from_degrees(-35))
                    * Mat4::rotation_y(Angle::from_degrees(20))
            }
            Model::Torus => {
                Mat4::rotation_x(Angle::from_degrees(-60))
                    * Mat4::rotation_z(Angle::from_degrees(15))
            }
        }
    }
}

/// Spot tilted 15° towards the camera and turned by `yaw` about its vertical axis (145°: a
/// three-quarter view of its face).
fn spot_pose(yaw: Angle) -> Mat4 {
    Mat4::rotation_x(Angle::from_degrees(15)) * Mat4::rotation_y(yaw)
}

/// Poses of the spot turntable ([`turntable`]).
pub const TURNTABLE_POSES: i32 = 12;

/// The pipeline of pose `step` (of [`TURNTABLE_POSES`]) of spot turning on a turntable: the
/// frame of [`Model::Spot`] with the yaw `step` × 30°, so a bench sees the whole range of faces
/// drawn (about 2,000 to 2,700 of the 5,856) rather than one pose.
pub fn turntable(step: i32) -> Pipeline {
    posed(spot_pose(Angle::from_turns(step, TURNTABLE_POSES)))
}

/// The pipeline of spot's frame turned by `yaw` on the turntable (the board examples' spin).
pub fn spot_turned(yaw: Angle) -> Pipeline {
    posed(spot_pose(yaw))
}

/// The background colour.
pub const BACKGROUND: Rgb565 = Rgb565::new(3, 6, 4);

/// The surface: a warm colour, Gouraud-lit.
pub const MATERIAL: Material<Rgb565> = Material::new(Rgb565::new(30, 48, 16), Shading::Gouraud);

/// The pipeline of `model`'s frame: a 60° perspective camera 2.5 units from the origin, the
/// light from the upper left and in front, ambient 0.15.
pub fn pipeline(model: Model) -> Pipeline {
    posed(model.pose())
}

/// The frame's camera, light and viewport with the model posed by `pose`.
pub fn posed(pose: Mat4) -> Pipeline {
    let (w, h) = SIZE;
    let projection = projection(Scalar::from_bits(1 << 15), Scalar::from_num(8));
    let view = Mat4::translation(Vec3::from_bits(0, 0, -(5 << 16) / 2));
    let viewport = Rectangle::new(Point::zero(), Size::new(w, h));
    Pipeline::new(pose, projection * view, viewport, light())
}

/// The frames' 60° perspective projection onto [`SIZE`] with the depth range `near` to `far`.
fn projection(near: Scalar, far: Scalar) -> Mat4 {
    let (w, h) = SIZE;
    Mat4::perspective(
        Angle::from_degrees(60),
        Scalar::from_num(w) / Scalar::from_num(h),
        near,
        far,
    )
    // Constants that make a projection: never `None`. A fallback, not a panic path, for the
    // firmware (a zero matrix would draw nothing, which the frame checksums would catch).
    .unwrap_or(Mat4::from_bits([[0; 4]; 4]))
}

/// The light of every frame here (the bench scene's).
fn light() -> Light {
    Light::new(
        Vec3::from_bits(-26214, 39322, 45875),
        Scalar::from_bits(9830),
    )
}

/// The torus into the caller's arrays: major radius 1, tube radius 0.35, [`TORUS_RINGS`] ×
/// [`TORUS_SIDES`], faces counter-clockwise seen from outside; all in fixed point.
pub fn torus<'a>(
    vertices: &'a mut [Vec3; TORUS_VERTICES],
    normals: &'a mut [Vec3; TORUS_VERTICES],
    indices: &'a mut [[u16; 3]; TORUS_FACES],
) -> Mesh<'a> {
    let (major, minor) = (Scalar::ONE, Scalar::from_bits(22938));
    for i in 0..TORUS_RINGS {
        let theta = Angle::from_turns(i as i32, TORUS_RINGS as i32);
        let (st, ct) = (theta.sin(), theta.cos());
        for j in 0..TORUS_SIDES {
            let phi = Angle::from_turns(j as i32, TORUS_SIDES as i32);
            let (sp, cp) = (phi.sin(), phi.cos());
            let ring = major + minor * cp;
            vertices[i * TORUS_SIDES + j] = Vec3::new(ring * ct, ring * st, minor * sp);
            normals[i * TORUS_SIDES + j] = Vec3::new(cp * ct, cp * st, sp).normalize();
        }
    }
    let at = |i: usize, j: usize| ((i % TORUS_RINGS) * TORUS_SIDES + (j % TORUS_SIDES)) as u16;
    for i in 0..TORUS_RINGS {
        for j in 0..TORUS_SIDES {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            let k = 2 * (i * TORUS_SIDES + j);
            indices[k] = [a, b, c];
            indices[k + 1] = [a, c, d];
        }
    }
    Mesh::new(&vertices[..], &normals[..], &indices[..])
}

/// A 64-bit LCG (Knuth's MMIX constants) from `seed`: each call the top `bits` of its next state.
fn random_bits(seed: u64) -> impl FnMut(u32) -> i32 {
    let mut state = seed;
    move |bits: u32| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> (64 - bits)) as i32
    }
}

/// Faces of the [`scatter`] mesh.
pub const SCATTER_FACES: usize = 1600;

/// Vertices of the [`scatter`] mesh: three a face.
pub const SCATTER_VERTICES: usize = 3 * SCATTER_FACES;

/// Small faces scattered over the screen and past its edges, into the caller's arrays: each face
/// its own three vertices, from 16 px across down to 2, a sliver in eight, one in 64 with an index
/// past the vertices, at random depths and orientations (about half face away), with random
/// normals. Through [`scatter_pipeline`]'s orthographic camera the positions land on quarter pixels, so pixel
/// centres lie exactly on many edges (the fill rule's cases). The frame that tests the set-up
/// of small faces where a core has its own (`arch::level_face`) against the host's.
pub fn scatter<'a>(
    vertices: &'a mut [Vec3; SCATTER_VERTICES],
    normals: &'a mut [Vec3; SCATTER_VERTICES],
    indices: &'a mut [[u16; 3]; SCATTER_FACES],
) -> Mesh<'a> {
    let mut next = random_bits(0x5ca7_7e2e_d000_0001);
    // A quarter pixel of the camera's 256-px viewport: 1/512 of the unit.
    const QUARTER: i32 = 1 << 7;
    for (k, face) in indices.iter_mut().enumerate() {
        // The centre in ±1.25 (the viewport's ±1 and past it), ±1 in depth; the face within
        // 64·2⁻ʲ quarter pixels of it (16 px) for j in 0..4.
        let centre = [
            (next(11) - (1 << 10)) * 5 / 4 * QUARTER,
            (next(11) - (1 << 10)) * 5 / 4 * QUARTER,
            (next(16) - (1 << 15)) * 2,
        ];
        let size = 64 >> next(2);
        let mut corner = |_| {
            let d = [(); 3].map(|_| (next(8) * size) >> 7);
            [
                centre[0] + (d[0] - size) * QUARTER,
                centre[1] + (d[1] - size) * QUARTER,
                centre[2] + (d[2] - size) * 64,
            ]
        };
        let (a, b) = (corner(0), corner(1));
        let c = if k % 8 == 0 {
            // On the line through the first two, or a quarter pixel off it.
            core::array::from_fn(|i| 2 * b[i] - a[i] + (next(2) - 2) * QUARTER)
        } else {
            corner(2)
        };
        let mut corners = [a, b, c];
        // One face in 400 large, each way round in turn: 220 × 220 px near the middle, at the
        // back, a doubled area between 2³¹ and 2³² sub-pixels² (its low word's top bit set).
        if k % 400 == 100 {
            const HALF: i32 = 440 * QUARTER;
            let (x, y, z) = (centre[0] / 8, centre[1] / 8, 63 << 10);
            corners = [
                [x - HALF, y - HALF, z],
                [x + HALF, y - HALF, z],
                [x, y + HALF, z],
            ];
            if k % 800 == 100 {
                corners.swap(1, 2);
            }
        }
        // Past the guard band, right, left, down and up in turn (30,000 units: 3.8 M px): one
        // corner of one face in 64 (clipped), all three of another (rejected).
        let far = [(0, 1), (0, -1), (1, 1), (1, -1)][k / 64 % 4];
        for (j, p) in corners.iter_mut().enumerate() {
            if k % 64 == 45 || (k % 64 == 29 && j == 2) {
                p[far.0] = far.1 * (30_000 << 16);
            }
        }
        for (j, p) in corners.into_iter().enumerate() {
            let v = 3 * k + j;
            vertices[v] = Vec3::from_bits(p[0], p[1], p[2]);
            let n = [(); 3].map(|_| next(16) - (1 << 15));
            let n = Vec3::from_bits(n[0], n[1], n[2] | 1).normalize();
            // One normal in eight half as long again (a mesh's normals need not be unit): lit
            // as it is by a rotation-free draw, its level reaches the clamp at full diffuse.
            let [x, y, z] = n.to_bits();
            normals[v] = if v % 8 == 5 {
                Vec3::from_bits(x + x / 2, y + y / 2, z + z / 2)
            } else {
                n
            };
        }
        *face = [0, 1, 2].map(|j| (3 * k + j) as u16);
        // One face in 64 with an index past the vertices (each corner in turn): never drawn,
        // counted as invalid.
        if k % 64 == 13 {
            face[k / 64 % 3] = u16::MAX;
        }
    }
    Mesh::new(&vertices[..], &normals[..], &indices[..])
}

/// The pipeline of the [`scatter`] frame: an orthographic camera (the identity) onto a 256 × 256
/// viewport centred on the screen, the bench frame's light.
pub fn scatter_pipeline() -> Pipeline {
    let viewport = Rectangle::new(Point::new(32, -8), Size::new(256, 256));
    Pipeline::new(Mat4::IDENTITY, Mat4::IDENTITY, viewport, light())
}

/// The line of the [`scatter`] frame (rendered with the scratch): its counts, covered pixels
/// and checksum, compared like the frame lines.
pub struct ScatterLine {
    /// The pipeline's counts.
    pub stats: DrawStats,
    /// [`covered`] pixels.
    pub covered: u32,
    /// [`checksum`] of colours and depths.
    pub checksum: u32,
}

impl core::fmt::Display for ScatterLine {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write_frame_line(f, "scatter", &self.stats, self.covered, self.checksum)
    }
}

/// Adds the counts of `more` to `total`'s.
fn add_stats(total: &mut DrawStats, more: &DrawStats) {
    total.drawn += more.drawn;
    total.clipped += more.clipped;
    total.rejected += more.rejected;
    total.culled += more.culled;
    total.degenerate += more.degenerate;
    total.invalid += more.invalid;
}

/// The [`scatter`] frame of `mesh` (with `scratch`): its line. The mesh is drawn three times:
/// through [`scatter_pipeline`], then through the same camera onto viewports over the screen's
/// left and right edges (the counts summed).
pub fn render_scatter(
    mesh: &Mesh<'_>,
    target: &mut DepthTarget<'_, Rgb565>,
    scratch: &mut [ProjectedVertex],
) -> ScatterLine {
    let mut stats = render_with(&scatter_pipeline(), mesh, target, Some(scratch));
    // Then over each side edge of the screen (the viewport past it): faces inside the view
    // volume whose columns the screen cuts (each way: the set-ups' runs clamped to the clip).
    for x in [-192, 200] {
        let viewport = Rectangle::new(Point::new(x, -8), Size::new(256, 256));
        let pipeline = Pipeline::new(Mat4::IDENTITY, Mat4::IDENTITY, viewport, light());
        let more = pipeline
            .draw_mesh_with(mesh, &MATERIAL, target, &mut *scratch)
            .unwrap_or_default();
        add_stats(&mut stats, &more);
    }
    ScatterLine {
        stats,
        covered: covered(target.depth()),
        checksum: checksum(target.framebuffer().pixels(), target.depth()),
    }
}

/// Faces of the [`depths`] cluster mesh (it fits the [`scatter`] arrays).
pub const DEPTHS_FACES: usize = 400;

/// The [`depths`] frame's clusters: the distance of each from the camera (units, near to far)
/// and the direction of its centre (view-space `x/−z` and `y/−z`, hundredths): a 4 × 3 grid over
/// the screen. Distances from 0.5 to 1024: `w` from 2¹⁵ to past 2²⁶ (the vertex stage's far
/// points, `w ≥ 2²⁵`, from 512 on), exact powers of two among them (a normalised `w` of 2³¹).
const DEPTHS_CLUSTERS: [(f32, [i32; 2]); 12] = [
    (0.5, [-45, 30]),
    (0.9, [-15, 30]),
    (1.0, [15, 30]),
    (3.7, [45, 30]),
    (8.0, [-45, 0]),
    (13.0, [-15, 0]),
    (64.0, [15, 0]),
    (100.0, [45, 0]),
    (300.0, [-45, -30]),
    (512.0, [-15, -30]),
    (700.0, [15, -30]),
    (1024.0, [45, -30]),
];

/// The cluster of small faces that the [`depths`] frame draws at each distance, into the first
/// entries of the caller's arrays: [`DEPTHS_FACES`] faces in the box ±0.15 (2 to 12 px across
/// where the frame scales the cluster by its distance), random orientations and normals, every
/// fourth face's first vertex at `z` = 0 (its `w` the cluster's distance exactly).
pub fn depths<'a>(
    vertices: &'a mut [Vec3],
    normals: &'a mut [Vec3],
    indices: &'a mut [[u16; 3]],
) -> Mesh<'a> {
    let mut next = random_bits(0xde97_4500_1234_5679);
    let (vertices, normals) = (
        &mut vertices[..3 * DEPTHS_FACES],
        &mut normals[..3 * DEPTHS_FACES],
    );
    let indices = &mut indices[..DEPTHS_FACES];
    for (k, face) in indices.iter_mut().enumerate() {
        // The centre within ±0.12 (raw ±7864), the corners within 983·2⁻ʲ of it (0.015).
        let centre = [(); 3].map(|_| next(14) - (1 << 13));
        let size = 1966 >> next(2);
        for j in 0..3 {
            let mut p = centre.map(|c| c + ((next(12) * size) >> 11) - size);
            if j == 0 && k % 4 == 0 {
                p[2] = 0;
            }
            let v = 3 * k + j;
            vertices[v] = Vec3::from_bits(p[0], p[1], p[2]);
            let n = [(); 3].map(|_| next(16) - (1 << 15));
            let n = Vec3::from_bits(n[0], n[1], n[2] | 1).normalize();
            // One normal in eight half as long again (a mesh's normals need not be unit): lit
            // as it is by a rotation-free draw, its level reaches the clamp at full diffuse.
            let [x, y, z] = n.to_bits();
            normals[v] = if v % 8 == 5 {
                Vec3::from_bits(x + x / 2, y + y / 2, z + z / 2)
            } else {
                n
            };
        }
        *face = [0, 1, 2].map(|j| (3 * k + j) as u16);
        // One face in 64 with an index past the vertices (each corner in turn): never drawn,
        // counted as invalid.
        if k % 64 == 13 {
            face[k / 64 % 3] = u16::MAX;
        }
    }
    Mesh::new(&vertices[..], &normals[..], &indices[..])
}

/// The line of the [`depths`] frame (each cluster drawn with the scratch): the counts summed,
/// covered pixels and checksum, compared like the frame lines.
pub struct DepthsLine {
    /// The pipeline's counts, summed over the clusters.
    pub stats: DrawStats,
    /// [`covered`] pixels.
    pub covered: u32,
    /// [`checksum`] of colours and depths.
    pub checksum: u32,
    /// FNV-1a of every cluster's projected vertices (the scratch's entries, each as `Hash`
    /// writes it): the vertex stage's integers, which the pixels show only in part.
    pub vertices: u32,
}

impl core::fmt::Display for DepthsLine {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write_frame_line(f, "depths", &self.stats, self.covered, self.checksum)?;
        write!(f, " vertices={:#010x}", self.vertices)
    }
}

/// FNV-1a over the bytes a value's `Hash` writes (the same on every target for the fixed-width
/// integers a `ProjectedVertex` holds).
struct FnvHasher(u32);

impl core::hash::Hasher for FnvHasher {
    fn finish(&self) -> u64 {
        u64::from(self.0)
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u32::from(b)).wrapping_mul(0x0100_0193);
        }
    }
}

/// The [`depths`] frame: the cluster `mesh` drawn (with `scratch`) at each of twelve distances
/// from 0.5 to 1024, scaled by its distance, then once at distance 2 unscaled, through a 60°
/// camera whose depth range is 0.25 to 2048. Each cluster's box is inside the view volume, so its vertices take a core's own vertex
/// stage where it has one (`arch::project_positions`): the frame tests it against the host's
/// over the range of `w`.
pub fn render_depths(
    mesh: &Mesh<'_>,
    target: &mut DepthTarget<'_, Rgb565>,
    scratch: &mut [ProjectedVertex],
) -> DepthsLine {
    let (w, h) = SIZE;
    let camera = projection(Scalar::from_bits(1 << 14), Scalar::from_num(2048));
    let viewport = Rectangle::new(Point::zero(), Size::new(w, h));
    target.clear(BACKGROUND);
    let mut stats = DrawStats::default();
    let mut vertices = FnvHasher(0x811c_9dc5);
    let scaled = DEPTHS_CLUSTERS.into_iter().map(|(distance, [x, y])| {
        let d = Scalar::from_num(distance);
        // d/100 first: d·c itself overflows the scalar at the farthest cluster (1024 · 45).
        let slope = |c: i32| d / Scalar::from_num(100) * Scalar::from_num(c);
        let place = Mat4::translation(Vec3::new(slope(x), slope(y), -d));
        place * Mat4::scaling(d)
    });
    // Last, once more without the scaling: a rotation-free model, whose vertex stage lights the
    // normals as they are (the unit-normal levels, `arch::light_levels` on ARMv7-M).
    let unscaled = Mat4::translation(Vec3::new(Scalar::ZERO, Scalar::ZERO, -Scalar::from_num(2)));
    for model in scaled.chain(core::iter::once(unscaled)) {
        let pipeline = Pipeline::new(model, camera, viewport, light());
        let s = pipeline
            .draw_mesh_with(mesh, &MATERIAL, target, scratch)
            .unwrap_or_default();
        add_stats(&mut stats, &s);
        for v in scratch.iter().take(3 * DEPTHS_FACES) {
            core::hash::Hash::hash(v, &mut vertices);
        }
    }
    DepthsLine {
        stats,
        covered: covered(target.depth()),
        checksum: checksum(target.framebuffer().pixels(), target.depth()),
        vertices: vertices.0,
    }
}

/// One frame of `mesh` posed as `model`: clears colour and depth, draws — each vertex
/// transformed once into `scratch` if given (it must hold a vertex per mesh vertex), or once per
/// face without.
pub fn render(
    model: Model,
    mesh: &Mesh<'_>,
    target: &mut DepthTarget<'_, Rgb565>,
    scratch: Option<&mut [ProjectedVertex]>,
) -> DrawStats {
    render_with(&pipeline(model), mesh, target, scratch)
}

/// [`render`] through `pipeline` (a [`turntable`] pose, say).
pub fn render_with(
    pipeline: &Pipeline,
    mesh: &Mesh<'_>,
    target: &mut DepthTarget<'_, Rgb565>,
    scratch: Option<&mut [ProjectedVertex]>,
) -> DrawStats {
    target.clear(BACKGROUND);
    match scratch {
        Some(scratch) => pipeline
            .draw_mesh_with(mesh, &MATERIAL, target, scratch)
            .unwrap_or_default(),
        None => pipeline.draw_mesh(mesh, &MATERIAL, target),
    }
}

/// The edges of the wireframe frames ([`render_wireframe`]).
pub const EDGES: Rgb565 = Rgb565::new(8, 52, 20);

/// The hidden-line frame of `mesh` posed as `model`: clears colour and depth, fills its faces in
/// the background colour (the z-buffer), then draws their edges depth-tested — each vertex
/// transformed once into `scratch` for each pass if given, or once per face without. The
/// wireframe's counts.
pub fn render_wireframe(
    model: Model,
    mesh: &Mesh<'_>,
    target: &mut DepthTarget<'_, Rgb565>,
    scratch: Option<&mut [ProjectedVertex]>,
) -> DrawStats {
    let pipeline = pipeline(model);
    let faces = Material::new(BACKGROUND, Shading::Unlit);
    target.clear(BACKGROUND);
    match scratch {
        Some(scratch) => {
            let _ = pipeline.draw_mesh_with(mesh, &faces, target, scratch);
            pipeline
                .draw_wireframe_with(mesh, EDGES, target, scratch)
                .unwrap_or_default()
        }
        None => {
            pipeline.draw_mesh(mesh, &faces, target);
            pipeline.draw_wireframe(mesh, EDGES, target)
        }
    }
}

/// Pixels the frame covers: those whose depth was written.
pub fn covered(depth: &[u16]) -> u32 {
    depth.iter().filter(|&&d| d != DEPTH_CLEAR).count() as u32
}

/// FNV-1a over the colours and the depths.
pub fn checksum(colors: &[Rgb565], depth: &[u16]) -> u32 {
    let words = colors
        .iter()
        .map(|c| c.into_storage())
        .chain(depth.iter().copied());
    fnv(FNV_START, words)
}

/// [`checksum`] of every [`turntable`] frame (rendered with `scratch`), folded into one FNV-1a
/// hash; `measure` runs each frame's rendering (the firmware times it there).
pub fn turntable_checksum(
    mesh: &Mesh<'_>,
    target: &mut DepthTarget<'_, Rgb565>,
    scratch: &mut [ProjectedVertex],
    mut measure: impl FnMut(&mut dyn FnMut()),
) -> u32 {
    let mut h = FNV_START;
    for step in 0..TURNTABLE_POSES {
        let pipeline = turntable(step);
        measure(&mut || {
            core::hint::black_box(render_with(
                &pipeline,
                core::hint::black_box(mesh),
                target,
                Some(&mut *scratch),
            ));
        });
        let frame = checksum(target.framebuffer().pixels(), target.depth());
        // Its four bytes, low first.
        h = fnv(h, [frame as u16, (frame >> 16) as u16]);
    }
    h
}

/// The line the host and the firmware print for a frame, compared by `.ci/firmware.sh`.
pub struct FrameLine {
    /// The mesh.
    pub model: Model,
    /// Whether the frame is its hidden-line wireframe ([`render_wireframe`]).
    pub wireframe: bool,
    /// The pipeline's counts.
    pub stats: DrawStats,
    /// [`covered`] pixels.
    pub covered: u32,
    /// [`checksum`] of colours and depths.
    pub checksum: u32,
}

impl FrameLine {
    /// The line of the frame `target` holds: `model`'s (its hidden-line `wireframe`), drawn
    /// with the counts `stats`.
    pub fn of(
        model: Model,
        wireframe: bool,
        stats: DrawStats,
        target: &DepthTarget<'_, Rgb565>,
    ) -> Self {
        FrameLine {
            model,
            wireframe,
            stats,
            covered: covered(target.depth()),
            checksum: checksum(target.framebuffer().pixels(), target.depth()),
        }
    }
}

impl core::fmt::Display for FrameLine {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let wireframe = if self.wireframe { "-wireframe" } else { "" };
        let name = format_args!("{}{wireframe}", self.model.name());
        write_frame_line(f, name, &self.stats, self.covered, self.checksum)
    }
}

/// A frame line: `frame <name> WxH`, the pipeline's counts, the covered pixels and the checksum.
fn write_frame_line(
    f: &mut core::fmt::Formatter<'_>,
    name: impl core::fmt::Display,
    s: &DrawStats,
    covered: u32,
    checksum: u32,
) -> core::fmt::Result {
    write!(
        f,
        "frame {name} {}x{} drawn={} culled={} clipped={} rejected={} degenerate={} ",
        SIZE.0, SIZE.1, s.drawn, s.culled, s.clipped, s.rejected, s.degenerate
    )?;
    if s.invalid != 0 {
        write!(f, "invalid={} ", s.invalid)?;
    }
    write!(f, "covered={covered} fnv1a={checksum:#010x}")
}

/// The line of the [`turntable`]'s frames ([`turntable_checksum`]), compared like the frame
/// lines.
pub struct TurntableLine(pub u32);

impl core::fmt::Display for TurntableLine {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "frame spot-turntable {}x{} poses={} fnv1a={:#010x}",
            SIZE.0, SIZE.1, TURNTABLE_POSES, self.0
        )
    }
}
