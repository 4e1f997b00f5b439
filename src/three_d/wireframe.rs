//! Wireframes: the edges of the faces a mesh draw keeps, as thin lines tested against the
//! z-buffer.
//!
//! The face stage is the fill's (the same transform, clipping and culling: the edges of exactly
//! the faces [`Pipeline::draw_mesh`] would fill), and each edge is the raster core's thin line
//! (`raster::line`, the diamond-exit rule) between the face's projected vertices, with a span
//! shader that gives each pixel the edge's depth and tests it:
//!
//! * **Each edge as one segment.** An edge is drawn from its vertex of the lower index to the
//!   other, whichever face hands it over: its two faces give the same segment, hence the same
//!   pixels and depths (they differ only in their slack, below: a pixel is drawn where either
//!   face's test passes it), never two lines a pixel apart. A clipped face's edges are the parts
//!   of its polygon on the face's own edges (not those on the clip planes), and clipping
//!   computes a shared edge's points from its inside end, the same for both faces. (Each face
//!   rasterises its three edges, so an edge between two drawn faces is rasterised twice: a mesh
//!   carries no adjacency to tell which face drew it.)
//! * **Depth.** A pixel's depth is the segment's, interpolated linearly along the major axis
//!   (depth is affine in screen space) at the pixel's centre, clamped to the segment's ends and
//!   rounded. The pixel is drawn where that is at most the stored depth plus the face's *slack*:
//!   `⌈|∂z/∂x| + |∂z/∂y|⌉ + 2` depth units (its depth change over a pixel, and rounding) — the
//!   most the segment's depth at a pixel the line draws (at most a pixel from its centre) can
//!   lie behind the face's own depth at that centre. So over the mesh filled first, its visible
//!   edges are drawn whole and the hidden ones hidden: an edge's pixel is covered by one of its
//!   two faces (or by nothing, or by a surface in front of it), and that face's pass over the
//!   edge passes it. Depth is not written: lines never hide lines, and the order of the faces
//!   does not matter.
//!
//! The slack is `polygon offset` in OpenGL's terms, chosen per face: lines within it of a
//! surface in front of them show through, as a line that close to a surface is in any z-buffer.

use embedded_graphics::primitives::Rectangle;

use super::depth::{DepthTarget, ScreenVertex};
use super::math::{Bary, Vec3};
use super::mesh::Mesh;
use super::mesh_target::MeshTarget;
use super::pipeline::{
    fit_scratch, signed_area2, DrawStats, FaceSink, Frame, Pipeline, ScratchTooSmall,
};
use super::shading::{Material, Shading, TargetClip};
use super::texturing::FaceTexture;
use super::vertex::ProjectedVertex;
use crate::color::GouraudColor;
use crate::fixed_point::{HALF_PIXEL, SUBPIXEL_BITS};
use crate::raster::band::RowWindow;
use crate::raster::walk::Span;
use crate::raster::SpanShader;

impl Pipeline {
    /// Draws the edges of `mesh`'s faces in `color` into `target`, each a thin line (the
    /// diamond-exit rule of [`Line`](crate::Line)) tested against the z-buffer: the faces
    /// [`draw_mesh`](Self::draw_mesh) would fill (culled, clipped and counted the same: the
    /// returned stats are the fill's), each edge one segment whichever face hands it over, a
    /// pixel drawn where the edge's depth
    /// there is at most the stored depth plus the face's slope over a pixel (depth is not
    /// written). Drawn over the same mesh filled first (in any material, or the background
    /// colour for a hidden-line drawing), the edges behind its faces are hidden.
    ///
    /// # Examples
    ///
    /// ```
    /// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
    /// use embedded_raster::three_d::meshes::torus::TORUS;
    /// use embedded_raster::three_d::{Angle, DepthTarget, Light, Mat4, Material, Pipeline};
    /// use embedded_raster::three_d::{Shading, Vec3};
    ///
    /// let (mut pixels, mut depth) = ([Rgb565::BLACK; 64 * 64], [0u16; 64 * 64]);
    /// let mut target = DepthTarget::new(&mut pixels, &mut depth, 64, 64).unwrap();
    /// let camera = Mat4::perspective(Angle::from_degrees(45), 1, 0.5, 20).unwrap()
    ///     * Mat4::orbit(Vec3::ZERO, 4, Angle::from_degrees(20), Angle::from_degrees(35.5));
    /// let viewport = Rectangle::new(Point::zero(), Size::new(64, 64));
    /// let pipeline = Pipeline::new(Mat4::IDENTITY, camera, viewport, Light::default());
    /// // Hidden lines: the faces in the background colour, then their edges.
    /// pipeline.draw_mesh(&TORUS, &Material::new(Rgb565::BLACK, Shading::Unlit), &mut target);
    /// let stats = pipeline.draw_wireframe(&TORUS, Rgb565::GREEN, &mut target);
    /// assert!(stats.drawn > 0);
    /// ```
    pub fn draw_wireframe<C: GouraudColor>(
        &self,
        mesh: &Mesh<'_>,
        color: C,
        target: &mut impl MeshTarget<C>,
    ) -> DrawStats {
        let clip = target.clip(&self.viewport);
        let rows = *clip.rows();
        target.with_depth(|target| {
            let frame = wire_frame(self, mesh, color, &clip);
            frame.each_face(
                mesh,
                &mut Edges {
                    target,
                    color,
                    rows,
                },
            )
        })
    }

    /// [`draw_wireframe`](Self::draw_wireframe) with each vertex transformed and projected once
    /// into `scratch` (one entry per mesh vertex), as [`draw_mesh_with`](Self::draw_mesh_with):
    /// the same pixels; `Err` without drawing if `scratch` is too short.
    pub fn draw_wireframe_with<C: GouraudColor>(
        &self,
        mesh: &Mesh<'_>,
        color: C,
        target: &mut impl MeshTarget<C>,
        scratch: &mut [ProjectedVertex],
    ) -> Result<DrawStats, ScratchTooSmall> {
        let scratch = fit_scratch(mesh, scratch)?;
        let clip = target.clip(&self.viewport);
        let rows = *clip.rows();
        let frame = wire_frame(self, mesh, color, &clip);
        frame.project(mesh, scratch);
        Ok(target.with_depth(|target| {
            frame.scratch_faces(
                mesh,
                scratch,
                &mut Edges {
                    target,
                    color,
                    rows,
                },
            )
        }))
    }
}

/// The face stage of a wireframe of `mesh` in `color` through `clip`: the fill's, unlit, over a
/// row more on each side of a band (an edge draws rows its face's pixel centres do not reach).
fn wire_frame<'p, C: GouraudColor, R: RowWindow>(
    pipeline: &'p Pipeline,
    mesh: &Mesh<'_>,
    color: C,
    clip: &TargetClip<R>,
) -> Frame<'p, C, R> {
    let material = Material::new(color, Shading::Unlit);
    Frame::new(pipeline, mesh, &material, clip.widened())
}

/// The face stage's sink of a wireframe: each kept face's edges drawn into `target`, the rows
/// `rows` of the frame.
struct Edges<'a, 't, C, R> {
    target: &'a mut DepthTarget<'t, C>,
    color: C,
    rows: R,
}

impl<C: GouraudColor, W: RowWindow> Edges<'_, '_, C, W> {
    /// The edge between the face's vertices `a` and `b` (mesh indices `ia`, `ib`), from the one
    /// of the lower index.
    fn edge(
        &mut self,
        clip: &Rectangle,
        (ia, a): (usize, &ScreenVertex),
        (ib, b): (usize, &ScreenVertex),
        slack: u32,
    ) {
        let (from, to) = if ia <= ib { (a, b) } else { (b, a) };
        let (p0, p1) = (
            (from.x.to_bits(), from.y.to_bits()),
            (to.x.to_bits(), to.y.to_bits()),
        );
        let line = DepthLine {
            target: self.target,
            color: self.color,
            along: Along::new((p0, from.depth), (p1, to.depth)),
            slack,
            first_row: self.rows.band().map_or(0, |band| band.first),
        };
        self.rows.line(p0, p1, clip, line);
    }
}

impl<C: GouraudColor, W: RowWindow> FaceSink<C> for Edges<'_, '_, C, W> {
    fn face<R: RowWindow, T: FaceTexture<C>>(
        &mut self,
        frame: &Frame<'_, C, R, T>,
        _: &Mesh<'_>,
        _: usize,
        idx: &[usize; 3],
        _: impl Fn() -> [Vec3; 3] + Copy,
        v: [&ProjectedVertex; 3],
        _: Option<crate::arch::TexturedDraw>,
    ) {
        let clip = frame.clip_rect();
        let s = v.map(|v| v.screen());
        let slack = slack([s[0], s[1], s[2]]);
        for j in 0..3 {
            let k = (j + 1) % 3;
            self.edge(&clip, (idx[j], s[j]), (idx[k], s[k]), slack);
        }
    }

    fn clipped<R: RowWindow, T: FaceTexture<C>>(
        &mut self,
        frame: &Frame<'_, C, R, T>,
        _: &Mesh<'_>,
        _: usize,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3] + Copy,
        v: [ProjectedVertex; 3],
        stats: &mut DrawStats,
    ) {
        stats.clipped += 1;
        let face = match frame.clip_face(model, &v) {
            Ok(face) => face,
            Err(dropped) => return dropped.count(stats),
        };
        stats.drawn += 1;
        // (Pushed, not collected: `collect` into a `heapless::Vec` panics past its capacity,
        // which the clipper's polygon shares.)
        let mut outline: heapless::Vec<(&ScreenVertex, &Bary), 12> = heapless::Vec::new();
        for vertex in face.outline() {
            let _ = outline.push(vertex);
        }
        // The face's slope from the fan's largest triangle (every one lies in its plane).
        let fan = (1..outline.len().saturating_sub(1)).filter_map(|k| {
            let (a, b, c) = (outline.first()?, outline.get(k)?, outline.get(k + 1)?);
            Some([a.0, b.0, c.0])
        });
        let largest = fan.max_by_key(|s| signed_area2(s.map(|v| (v.x, v.y))).unsigned_abs());
        let Some(slack) = largest.map(slack) else {
            return;
        };
        let clip = frame.clip_rect();
        for (i, &(p, p_bary)) in outline.iter().enumerate() {
            // The next vertex, the first after the last (no `%`: a division's zero test).
            let Some(&(q, q_bary)) = outline.get(i + 1).or(outline.first()) else {
                continue;
            };
            // The face's edge `j` (vertex `j` to `j + 1`) holds both ends where their coordinate
            // for the vertex opposite it is zero; the polygon runs along it from `j` to `j + 1`.
            let on = (0..3).find(|&j| p_bary[(j + 2) % 3] == 0 && q_bary[(j + 2) % 3] == 0);
            if let Some(j) = on {
                self.edge(&clip, (idx[j], p), (idx[(j + 1) % 3], q), slack);
            }
        }
    }
}

/// The depth slack of the face in the plane of the screen triangle `s`: `⌈|∂z/∂x| + |∂z/∂y|⌉ +
/// 2` depth units, its depth change across a pixel (at most `u16::MAX`; that for a triangle of
/// zero area).
fn slack(s: [&ScreenVertex; 3]) -> u32 {
    let p = s.map(|v| {
        (
            i64::from(v.x.to_bits()),
            i64::from(v.y.to_bits()),
            i64::from(v.depth),
        )
    });
    // The guard band keeps the coordinates within 2²⁰ sub-pixels of each other: every product
    // fits `i64`.
    let d = |k: usize| (p[k].0 - p[0].0, p[k].1 - p[0].1, p[k].2 - p[0].2);
    let (d1, d2) = (d(1), d(2));
    let area = (d1.0 * d2.1 - d2.0 * d1.1).unsigned_abs();
    if area == 0 {
        return u32::from(u16::MAX);
    }
    // Depth over sub-pixels times the doubled area: below 2¹⁶·2²¹ each.
    let gx = d1.2 * d2.1 - d2.2 * d1.1;
    let gy = d1.0 * d2.2 - d2.0 * d1.2;
    let per_pixel = (gx.unsigned_abs() + gy.unsigned_abs()) << 8;
    let slope = per_pixel.div_ceil(area).saturating_add(2);
    slope.min(u64::from(u16::MAX)) as u32
}

/// Bits of the depth's fraction along a line.
const DEPTH_FRACTION: u32 = 24;

/// A segment's depth along its major axis.
#[derive(Clone, Copy)]
struct Along {
    /// Whether the segment is y-major (the raster line's choice: `|dy| > |dx|`).
    y_major: bool,
    /// The start's major coordinate (sub-pixels) and depth ([`DEPTH_FRACTION`] bits).
    start: i64,
    depth: i64,
    /// Depth a sub-pixel along the major axis, and the ends' depths (the bounds).
    slope: i64,
    bounds: (i64, i64),
}

impl Along {
    /// The segment from `p0` to `p1` (sub-pixels) with the depths `z0` and `z1` at its ends.
    fn new((p0, z0): ((i32, i32), u16), (p1, z1): ((i32, i32), u16)) -> Self {
        let wide = |p: (i32, i32)| (i64::from(p.0), i64::from(p.1));
        let (a, b) = (wide(p0), wide(p1));
        let y_major = (b.1 - a.1).abs() > (b.0 - a.0).abs();
        let (start, run) = if y_major {
            (a.1, b.1 - a.1)
        } else {
            (a.0, b.0 - a.0)
        };
        let (z0, z1) = (i64::from(z0), i64::from(z1));
        // |z1 − z0| < 2¹⁶: the shifted difference fits 40 bits.
        let slope = if run == 0 {
            0
        } else {
            ((z1 - z0) << DEPTH_FRACTION) / run
        };
        Along {
            y_major,
            start,
            depth: z0 << DEPTH_FRACTION,
            slope,
            bounds: (z0.min(z1) << DEPTH_FRACTION, z0.max(z1) << DEPTH_FRACTION),
        }
    }

    /// The depth at the centre of the pixel `(x, y)`, rounded.
    #[inline(always)]
    fn depth_at(&self, x: i32, y: i32) -> u32 {
        let k = if self.y_major { y } else { x };
        let centre = (i64::from(k) << SUBPIXEL_BITS) + HALF_PIXEL;
        // The line's pixels lie within a pixel of its ends along the major axis: the offset is
        // below the run plus a pixel, its product with the slope below 2⁴⁹ (saturating anyway).
        let along = (centre - self.start).saturating_mul(self.slope);
        let z = self.depth.saturating_add(along);
        // Not `clamp`, which asserts its bounds are in order.
        let z = z.max(self.bounds.0).min(self.bounds.1);
        ((z + (1 << (DEPTH_FRACTION - 1))) >> DEPTH_FRACTION) as u32
    }
}

/// The span shader of an edge: each pixel's depth from the segment, tested against the z-buffer.
struct DepthLine<'a, 't, C> {
    target: &'a mut DepthTarget<'t, C>,
    color: C,
    along: Along,
    /// How far behind the stored depth a pixel may be and still be drawn.
    slack: u32,
    /// The frame row of the target's first (a band's spans come counted from it).
    first_row: i32,
}

impl<C: GouraudColor> SpanShader<0> for DepthLine<'_, '_, C> {
    type Steps = ();

    fn prepare(&mut self, _: [u32; 0]) {}

    fn span(&mut self, _: &(), span: Span, _: [u32; 0]) {
        let (along, slack, color) = (self.along, self.slack, self.color);
        let y = span.y.wrapping_add(self.first_row);
        let Some((colors, stored)) = self.target.clipped_spans_mut(span) else {
            return;
        };
        for ((c, d), x) in colors.iter_mut().zip(stored.iter()).zip(span.x_start..) {
            if along.depth_at(x, y) <= u32::from(*d) + slack {
                *c = color;
            }
        }
    }
}
