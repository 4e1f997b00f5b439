//! Band rendering draws exactly the frame drawn at once.
//!
//! For every band height from 1 to the frame's height, the bands' pixels (and depths) put
//! together must equal the frame drawn whole into a full-size target, bit for bit:
//!
//! * 2D: random lists of Gouraud and solid triangles (painter's order, every size class from
//!   sub-pixel to far beyond the `i32` pixel range, slivers, edges through pixel centres) drawn
//!   with `draw_into`, against `ColorBand::draw_all` and the `TriangleBin`, in several colour
//!   formats, on frames whose height is not a multiple of most band heights;
//! * 3D: the bench scene's knot (6,144 faces) at 320×240, and meshes with every shading, culling
//!   mode and near-plane clipping on viewports that are not the frame (offset, partly outside
//!   it), drawn with `Pipeline::draw_mesh_with`, against `Pipeline::draw_mesh` into a band (no bin, no
//!   scratch), `draw_mesh_with` (no bin) and the `MeshBin`, colours and depths;
//! * textured meshes (spot with its texture, in the bench frame and clipped by the near plane,
//!   every shading and sampler, vertex colours, highlights, `Lights`) drawn with
//!   `Pipeline::draw_textured_mesh_with`, against a `MeshBin::new_textured` (tests/all/textured_mesh.rs
//!   has the bin beside the bin-less band draws over its own suite of poses).
//!
//! And the renderers' contracts: one `fill_contiguous` of the band's rectangle per band, the
//! double buffer's protocol (no buffer drawn into while it is being sent), errors before
//! anything is drawn.

use embedded_graphics::pixelcolor::{Gray8, Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::band::{
    BandError, BandLayout, BandOutput, BinEntry, Callback, ColorBand, ColorBands, DepthBand,
    DepthBands, MeshBin, RenderError, ToDisplay, Triangle, TriangleBin,
};
use embedded_raster::texture::{Filter, Rgb565Texels, TexelSource, Texture};
use embedded_raster::three_d::meshes::{icosphere::ICOSPHERE, torus::TORUS};
use embedded_raster::three_d::{
    Angle, Cull, DepthTarget, DrawStats, Light, LightSource, Lights, Mat4, Material, Mesh,
    Pipeline, ProjectedVertex, Scalar, Shading, Specular, TexturedMaterial, Vec3,
};
use embedded_raster::{
    Coord, GouraudColor, GouraudTriangle, SliceFramebuffer, SolidTriangle, Vertex,
};

use crate::scene3d;

use crate::textured3d;

use crate::rng;
use rng::Rng;

const MIN: i64 = i32::MIN as i64;
const MAX: i64 = i32::MAX as i64;

impl Rng {
    /// A raw point over a `w × h` frame extended by `m` pixels on every side.
    fn point(&mut self, w: u32, h: u32, m: i64) -> (i64, i64) {
        (
            self.range(-m * 256, (i64::from(w) + m) * 256),
            self.range(-m * 256, (i64::from(h) + m) * 256),
        )
    }

    /// A raw coordinate on a pixel corner or centre, or a unit off one.
    fn snapped(&mut self, n: u32) -> i64 {
        const OFFSETS: [i64; 5] = [0, 128, 1, 255, 127];
        256 * self.range(-4, i64::from(n) + 4) + OFFSETS[self.below(5) as usize]
    }

    /// A random triangle's raw vertices for a `w × h` frame.
    fn vertices(&mut self, w: u32, h: u32) -> [(Coord, Coord); 3] {
        let (wi, hi) = (i64::from(w), i64::from(h));
        let v: [(i64, i64); 3] = match self.below(9) {
            // Sub-pixel to a dozen pixels (small, and tiny on x86-64).
            0..=2 => {
                let c = self.point(w, h, 3);
                let r = self.range(1, 256 * 14);
                [(); 3].map(|_| (c.0 + self.range(-r, r), c.1 + self.range(-r, r)))
            }
            // About the frame, partly off it.
            3 => [(); 3].map(|_| self.point(w, h, wi.max(hi) / 2 + 2)),
            // Far beyond it: general set-up.
            4 => [(); 3].map(|_| self.point(w, h, 3000)),
            // Any magnitude, up to the ends of the range.
            5 => {
                let a = self.point(w, h, 1);
                let mut any = || i64::from((self.next() as i32) >> self.below(32));
                [a, (any(), any()), (any(), any())]
            }
            // Slivers.
            6 => {
                let a = self.point(w, h, 6);
                let s = self.below(24) as u32;
                let d = (self.range(-(1 << s), 1 << s), self.range(-(1 << s), 1 << s));
                let t = self.range(-64, 128);
                let c = (
                    a.0 + d.0 * t / 64 + self.range(-2, 2),
                    a.1 + d.1 * t / 64 + self.range(-2, 2),
                );
                [a, (a.0 + d.0, a.1 + d.1), c]
            }
            // Across the frame, from left of it to right of it.
            7 => {
                let y = |r: &mut Rng| r.range(-hi * 256, 2 * hi * 256);
                let a = (self.range(-wi * 256, 0), y(self));
                let b = (self.range(wi * 256, 2 * wi * 256), y(self));
                [a, b, self.point(w, h, hi)]
            }
            // Edges through pixel centres.
            _ => [(); 3].map(|_| (self.snapped(w), self.snapped(h))),
        };
        v.map(|(x, y)| {
            (
                Coord::from_bits(x.clamp(MIN, MAX) as i32),
                Coord::from_bits(y.clamp(MIN, MAX) as i32),
            )
        })
    }

    fn color<C: GouraudColor>(&mut self) -> C {
        C::from_channels(core::array::from_fn(|k| {
            let max = C::MAX[k];
            match self.below(4) {
                0 => 0,
                1 => max,
                _ => (self.below(u64::from(max) + 1)) as u8,
            }
        }))
    }

    /// A list of `n` triangles, Gouraud and solid mixed.
    fn scene<C: GouraudColor>(&mut self, n: usize, w: u32, h: u32) -> Vec<Triangle<C>> {
        (0..n)
            .map(|_| {
                let v = self.vertices(w, h);
                if self.below(3) == 0 {
                    SolidTriangle::new(v, self.color()).into()
                } else {
                    let c = [(); 3].map(|_| self.color::<C>());
                    GouraudTriangle::new(core::array::from_fn(|k| {
                        Vertex::new(v[k].0, v[k].1, c[k])
                    }))
                    .into()
                }
            })
            .collect()
    }
}

/// The frame drawn whole: `draw_into` a framebuffer of its size, in order.
fn whole_2d<C: GouraudColor>(scene: &[Triangle<C>], w: u32, h: u32, background: C) -> Vec<C> {
    let mut pixels = vec![background; (w * h) as usize];
    let mut fb = SliceFramebuffer::new(&mut pixels, w, h).unwrap();
    for t in scene {
        match t {
            Triangle::Gouraud(t) => t.draw_into(&mut fb),
            Triangle::Solid(t) => t.draw_into(&mut fb),
        }
    }
    pixels
}

/// The first pixel where `got` differs from `want`, as (x, y).
fn first_difference<T: PartialEq>(want: &[T], got: &[T], width: u32) -> Option<(usize, usize)> {
    let k = want.iter().zip(got).position(|(a, b)| a != b)?;
    Some((k % width as usize, k / width as usize))
}

/// Every band height: the bands of `draw_all` and of a bin, put together, are the whole frame.
fn check_2d<C: GouraudColor + core::fmt::Debug>(seed: u64, w: u32, h: u32, scenes: usize) {
    let mut rng = Rng(seed);
    for scene_index in 0..scenes {
        let n = 1 + rng.below(40) as usize;
        let scene: Vec<Triangle<C>> = rng.scene(n, w, h);
        let background = rng.color::<C>();
        let want = whole_2d(&scene, w, h, background);
        for rows in 1..=h {
            let layout = BandLayout::new(Size::new(w, h), rows).unwrap();
            let mut buffer = vec![background; layout.buffer_len()];
            let mut storage = vec![BinEntry::EMPTY; layout.count() as usize + scene.len()];
            let mut bin = TriangleBin::new(&layout, &scene, &mut storage).unwrap();
            let (mut listed, mut binned) = (Vec::new(), Vec::new());
            for index in 0..layout.count() {
                let mut band = ColorBand::new(&mut buffer, &layout, index).unwrap();
                band.clear(background);
                band.draw_all(&scene);
                listed.extend_from_slice(band.pixels());
                band.clear(background);
                bin.draw(&mut band).unwrap();
                binned.extend_from_slice(band.pixels());
            }
            let what = format!("{w}×{h}, scene {scene_index}, {rows}-row bands");
            assert_eq!(
                first_difference(&want, &listed, w),
                None,
                "draw_all, {what}"
            );
            assert_eq!(first_difference(&want, &binned, w), None, "bin, {what}");
            assert_eq!(want.len(), listed.len());
        }
    }
}

#[test]
fn two_d_bands_are_the_whole_frame_rgb565() {
    check_2d::<Rgb565>(0xba4d_2d00_0000_0001, 61, 47, 12);
    check_2d::<Rgb565>(0xba4d_2d00_0000_0002, 320, 24, 3);
}

#[test]
fn two_d_bands_are_the_whole_frame_other_formats() {
    check_2d::<Rgb888>(0xba4d_2d00_0000_0003, 37, 29, 10);
    check_2d::<Gray8>(0xba4d_2d00_0000_0004, 16, 53, 10);
}

/// A bin drawn in another order than top to bottom (and twice) still gives each band its rows.
#[test]
fn bins_draw_bands_in_any_order() {
    let (w, h) = (50, 40);
    let mut rng = Rng(0xba4d_0de5_0000_0001);
    let scene: Vec<Triangle<Rgb565>> = rng.scene(30, w, h);
    let want = whole_2d(&scene, w, h, Rgb565::BLACK);
    let layout = BandLayout::new(Size::new(w, h), 6).unwrap();
    let mut storage = vec![BinEntry::EMPTY; 100];
    let mut bin = TriangleBin::new(&layout, &scene, &mut storage).unwrap();
    let mut buffer = vec![Rgb565::BLACK; layout.buffer_len()];
    let order = [3, 0, 1, 6, 2, 4, 5, 5, 0];
    for index in order {
        let mut band = ColorBand::new(&mut buffer, &layout, index).unwrap();
        band.clear(Rgb565::BLACK);
        bin.draw(&mut band).unwrap();
        let start = band.rect().top_left.y as usize * w as usize;
        assert_eq!(
            band.pixels(),
            &want[start..start + band.pixels().len()],
            "band {index}"
        );
    }
}

/// The 3D bench frame: `scene3d::render`'s pipeline and material, drawn whole with the scratch.
fn knot_frame() -> (Vec<Rgb565>, Vec<u16>) {
    let (w, h) = scene3d::SIZE;
    let (mut colors, mut depth) = (
        vec![Rgb565::BLACK; (w * h) as usize],
        vec![0; (w * h) as usize],
    );
    let mut target = DepthTarget::new(&mut colors, &mut depth, w, h).unwrap();
    let mut scratch = vec![ProjectedVertex::EMPTY; scene3d::KNOT.vertices.len()];
    scene3d::render(
        scene3d::Model::Knot,
        &scene3d::KNOT,
        &mut target,
        Some(&mut scratch),
    );
    (colors, depth)
}

/// How a band draws a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// `Pipeline::draw_mesh` into a band: no bin, no scratch.
    EachFace,
    /// `Pipeline::draw_mesh_with` into a band: no bin, the vertices again per band.
    Scratch,
    /// `MeshBin`.
    Bin,
}

/// The frame of `pipeline` drawing `meshes` (in order) in bands of `rows`, put together.
fn banded(
    layout: &BandLayout,
    pipeline: &Pipeline,
    meshes: &[(Mesh<'_>, Material<Rgb888>)],
    mode: Mode,
) -> (Vec<Rgb888>, Vec<u16>) {
    let background = Rgb888::new(3, 60, 90);
    let n = layout.buffer_len();
    let (mut colors, mut depth) = (vec![Rgb888::BLACK; n], vec![0u16; n]);
    let (mut all_colors, mut all_depth) = (Vec::new(), Vec::new());
    let vertices = meshes.iter().map(|m| m.0.vertices.len()).max().unwrap_or(0);
    let mut scratch = vec![vec![ProjectedVertex::EMPTY; vertices]; meshes.len()];
    let mut band_scratch = vec![ProjectedVertex::EMPTY; vertices];
    let mut storage: Vec<Vec<BinEntry>> = meshes
        .iter()
        .map(|m| vec![BinEntry::EMPTY; layout.count() as usize + m.0.indices.len()])
        .collect();
    let mut bins: Vec<MeshBin<'_, Rgb888>> = Vec::new();
    if mode == Mode::Bin {
        for ((mesh, material), (scratch, storage)) in meshes
            .iter()
            .zip(scratch.iter_mut().zip(storage.iter_mut()))
        {
            bins.push(MeshBin::new(pipeline, mesh, material, layout, scratch, storage).unwrap());
        }
    }
    for index in 0..layout.count() {
        let mut band = DepthBand::new(&mut colors, &mut depth, layout, index).unwrap();
        band.clear(background);
        match mode {
            Mode::EachFace => {
                for (mesh, material) in meshes {
                    pipeline.draw_mesh(mesh, material, &mut band);
                }
            }
            Mode::Scratch => {
                for (mesh, material) in meshes {
                    pipeline
                        .draw_mesh_with(mesh, material, &mut band, &mut band_scratch)
                        .unwrap();
                }
            }
            Mode::Bin => {
                for bin in &mut bins {
                    bin.draw(&mut band).unwrap();
                }
            }
        }
        all_colors.extend_from_slice(band.pixels());
        all_depth.extend_from_slice(band.depth());
    }
    (all_colors, all_depth)
}

/// The same frame drawn whole with `draw_mesh_with`.
fn whole_3d(
    size: Size,
    pipeline: &Pipeline,
    meshes: &[(Mesh<'_>, Material<Rgb888>)],
) -> (Vec<Rgb888>, Vec<u16>) {
    let (w, h) = (size.width, size.height);
    let (mut colors, mut depth) = (
        vec![Rgb888::BLACK; (w * h) as usize],
        vec![0; (w * h) as usize],
    );
    let mut target = DepthTarget::new(&mut colors, &mut depth, w, h).unwrap();
    target.clear(Rgb888::new(3, 60, 90));
    for (mesh, material) in meshes {
        let mut scratch = vec![ProjectedVertex::EMPTY; mesh.vertices.len()];
        pipeline
            .draw_mesh_with(mesh, material, &mut target, &mut scratch)
            .unwrap();
    }
    (colors, depth)
}

/// The knot at 320×240 in bands of every height from 1 to 240, in each mode: the bench frame's
/// colours and depths.
#[test]
fn knot_bands_are_the_whole_frame_at_every_height() {
    let (want_colors, want_depth) = knot_frame();
    let (w, h) = scene3d::SIZE;
    let pipeline = scene3d::pipeline(scene3d::Model::Knot);
    let material = scene3d::MATERIAL;
    let mut scratch = vec![ProjectedVertex::EMPTY; scene3d::KNOT.vertices.len()];
    let n_faces = scene3d::KNOT.indices.len();
    for rows in 1..=h {
        let layout = BandLayout::new(Size::new(w, h), rows).unwrap();
        let n = layout.buffer_len();
        let (mut colors, mut depth) = (vec![Rgb565::BLACK; n], vec![0u16; n]);
        let mut bin_scratch = vec![ProjectedVertex::EMPTY; scene3d::KNOT.vertices.len()];
        let mut storage = vec![BinEntry::EMPTY; layout.count() as usize + n_faces];
        let mut bin = MeshBin::new(
            &pipeline,
            &scene3d::KNOT,
            &material,
            &layout,
            &mut bin_scratch,
            &mut storage,
        )
        .unwrap();
        // The faces drawn (2,968), less those too small to reach a pixel centre's row.
        assert!(
            bin.len() <= 2968 && bin.len() > 2900,
            "{} faces kept",
            bin.len()
        );
        let modes = [Mode::EachFace, Mode::Scratch, Mode::Bin];
        // Every height in the bin; the bin-less modes at every height up to 40 and every
        // seventh beyond (they run the whole mesh per band).
        for mode in modes {
            if mode != Mode::Bin && rows > 40 && rows % 7 != 0 && rows != h {
                continue;
            }
            let (mut got_colors, mut got_depth) = (Vec::new(), Vec::new());
            for index in 0..layout.count() {
                let mut band = DepthBand::new(&mut colors, &mut depth, &layout, index).unwrap();
                band.clear(scene3d::BACKGROUND);
                match mode {
                    Mode::EachFace => {
                        pipeline.draw_mesh(&scene3d::KNOT, &material, &mut band);
                    }
                    Mode::Scratch => {
                        pipeline
                            .draw_mesh_with(&scene3d::KNOT, &material, &mut band, &mut scratch)
                            .unwrap();
                    }
                    Mode::Bin => bin.draw(&mut band).unwrap(),
                }
                got_colors.extend_from_slice(band.pixels());
                got_depth.extend_from_slice(band.depth());
            }
            let what = format!("{mode:?}, {rows}-row bands");
            assert_eq!(
                first_difference(&want_colors, &got_colors, w),
                None,
                "colours, {what}"
            );
            assert_eq!(
                first_difference(&want_depth, &got_depth, w),
                None,
                "depths, {what}"
            );
        }
    }
}

/// A mesh bin whose storage keeps no set-up of the faces crossing bands (exactly the entries
/// it needs), a few (a ring that fills up) or many, its bands drawn top to bottom, out of order
/// and again: every band the whole frame's rows.
#[test]
fn mesh_bins_keep_set_ups_in_any_storage_and_order() {
    let (want_colors, want_depth) = knot_frame();
    let (w, h) = scene3d::SIZE;
    let pipeline = scene3d::pipeline(scene3d::Model::Knot);
    let material = scene3d::MATERIAL;
    for rows in [3, 16, 37] {
        let layout = BandLayout::new(Size::new(w, h), rows).unwrap();
        let n = layout.buffer_len();
        let (mut colors, mut depth) = (vec![Rgb565::BLACK; n], vec![0u16; n]);
        let mut scratch = vec![ProjectedVertex::EMPTY; scene3d::KNOT.vertices.len()];
        let mut storage = vec![BinEntry::EMPTY; 240 + 6144];
        let kept = MeshBin::new(
            &pipeline,
            &scene3d::KNOT,
            &material,
            &layout,
            &mut scratch,
            &mut storage,
        )
        .unwrap()
        .len();
        let needed = layout.count() as usize + kept;
        let count = layout.count();
        let mut order: Vec<u32> = (0..count).collect();
        order.extend([count - 1, 0, 2, 1, 2, 3, 4, 3]);
        for spare in [0, 1, 7, 7 * 5 + 3, 2000] {
            let mut storage = vec![BinEntry::EMPTY; needed + spare];
            let mut bin = MeshBin::new(
                &pipeline,
                &scene3d::KNOT,
                &material,
                &layout,
                &mut scratch,
                &mut storage,
            )
            .unwrap();
            for &index in &order {
                let mut band = DepthBand::new(&mut colors, &mut depth, &layout, index).unwrap();
                band.clear(scene3d::BACKGROUND);
                bin.draw(&mut band).unwrap();
                let from = (index * rows * w) as usize;
                let len = band.pixels().len();
                let what = format!("{rows}-row band {index}, {spare} spare entries");
                assert!(
                    band.pixels() == &want_colors[from..from + len],
                    "colours, {what}"
                );
                assert!(
                    band.depth() == &want_depth[from..from + len],
                    "depths, {what}"
                );
            }
        }
    }
}

/// Meshes with every shading and culling, the camera close enough to clip some faces at the
/// near plane, on viewports that are not the frame, in bands of every height.
#[test]
fn meshes_with_every_shading_and_clipping_are_the_whole_frame() {
    let mut rng = Rng(0xba4d_3d00_0000_0001);
    let frames = [
        (
            Size::new(53, 41),
            Rectangle::new(Point::new(3, -5), Size::new(47, 39)),
        ),
        (
            Size::new(64, 48),
            Rectangle::new(Point::new(-20, 7), Size::new(90, 70)),
        ),
        (
            Size::new(31, 67),
            Rectangle::new(Point::new(0, 0), Size::new(31, 67)),
        ),
    ];
    let shadings = [
        Shading::Unlit,
        Shading::Flat,
        Shading::Gouraud,
        Shading::Quadratic,
    ];
    let culls = [Cull::Back, Cull::None, Cull::Front];
    let mut clipped = 0;
    for (case, (size, viewport)) in frames.iter().enumerate() {
        for (s, shading) in shadings.iter().enumerate() {
            let aspect =
                Scalar::from_num(viewport.size.width) / Scalar::from_num(viewport.size.height);
            let projection = Mat4::perspective(
                Angle::from_degrees(70),
                aspect,
                Scalar::from_num(0.5),
                Scalar::from_num(12),
            )
            .unwrap();
            // Near enough that the torus crosses the near plane in some poses.
            let distance = 1 + rng.below(3) as i32;
            let view = Mat4::translation(Vec3::from_bits(0, 0, -(distance << 16) - (1 << 15)));
            let model = Mat4::rotation_x(Angle(rng.next() as u16))
                * Mat4::rotation_y(Angle(rng.next() as u16));
            let light = Light::new(Vec3::from_bits(-20000, 30000, 50000), Scalar::from_num(0.2));
            let mut pipeline = Pipeline::new(model, projection * view, *viewport, light);
            pipeline.cull = culls[(case + s) % 3];
            let color = |r: &mut Rng| Rgb888::new(r.next() as u8, r.next() as u8, r.next() as u8);
            let meshes = [
                (TORUS, Material::new(color(&mut rng), *shading)),
                (
                    ICOSPHERE,
                    Material::new(color(&mut rng), shadings[(s + 1) % 4]),
                ),
            ];
            let (want_colors, want_depth) = whole_3d(*size, &pipeline, &meshes);
            let mut target_colors = want_colors.clone();
            let mut target_depth = want_depth.clone();
            let stats = pipeline.draw_mesh(
                &meshes[0].0,
                &meshes[0].1,
                &mut DepthTarget::new(
                    &mut target_colors,
                    &mut target_depth,
                    size.width,
                    size.height,
                )
                .unwrap(),
            );
            clipped += stats.clipped;
            for rows in 1..=size.height {
                let layout = BandLayout::new(*size, rows).unwrap();
                for mode in [Mode::EachFace, Mode::Scratch, Mode::Bin] {
                    let (colors, depth) = banded(&layout, &pipeline, &meshes, mode);
                    let what = format!("case {case}, {shading:?}, {mode:?}, {rows}-row bands");
                    assert_eq!(
                        first_difference(&want_colors, &colors, size.width),
                        None,
                        "{what}"
                    );
                    assert_eq!(
                        first_difference(&want_depth, &depth, size.width),
                        None,
                        "{what}"
                    );
                }
            }
        }
    }
    assert!(clipped > 20, "{clipped} faces clipped");
}

/// `mesh` with the textured `material` through `pipeline` into a frame of `size` in `C`: drawn
/// whole with `draw_textured_mesh_with`, then through a `MeshBin::new_textured` in bands of each
/// of `heights` rows, top to bottom and then some again out of order: each band the whole
/// frame's colours and depths there, the bin's counts the frame's. The frame's counts.
fn check_textured_bin<S, C>(
    what: &str,
    size: Size,
    pipeline: &Pipeline,
    mesh: &Mesh<'_>,
    material: &TexturedMaterial<'_, S>,
    heights: &[u32],
) -> DrawStats
where
    S: TexelSource,
    C: GouraudColor + From<S::Color> + From<Rgb888> + core::fmt::Debug,
{
    let (w, h) = (size.width, size.height);
    let background = C::from(Rgb888::new(3, 60, 90));
    let n = (w * h) as usize;
    let (mut want_colors, mut want_depth) = (vec![background; n], vec![0u16; n]);
    let mut scratch = vec![ProjectedVertex::EMPTY; mesh.vertices.len()];
    let mut target = DepthTarget::new(&mut want_colors, &mut want_depth, w, h).unwrap();
    target.clear(background);
    let stats = pipeline
        .draw_textured_mesh_with(mesh, material, &mut target, &mut scratch)
        .unwrap();
    for &rows in heights {
        let layout = BandLayout::new(size, rows).unwrap();
        let count = layout.count();
        let mut storage = vec![BinEntry::EMPTY; count as usize + mesh.indices.len()];
        let mut bin = MeshBin::new_textured(
            pipeline,
            mesh,
            material,
            &layout,
            &mut scratch,
            &mut storage,
        )
        .unwrap();
        assert_eq!(bin.stats(), stats, "{what}, {rows}-row bands: the counts");
        assert!(bin.len() <= stats.drawn as usize, "{what}: {}", bin.len());
        let mut order: Vec<u32> = (0..count).collect();
        order.extend((0..count).rev().step_by(3));
        order.push(count / 2);
        let (mut colors, mut depth) = (
            vec![background; layout.buffer_len()],
            vec![0u16; layout.buffer_len()],
        );
        for (k, &index) in order.iter().enumerate() {
            let mut band = DepthBand::new(&mut colors, &mut depth, &layout, index).unwrap();
            band.clear(background);
            bin.draw(&mut band).unwrap();
            let from = (index * rows * w) as usize;
            let len = band.pixels().len();
            let again = if k < count as usize { "" } else { ", again" };
            let what = format!("{what}: {rows}-row band {index}{again}");
            assert_eq!(
                first_difference(&want_colors[from..from + len], band.pixels(), w),
                None,
                "colours, {what}"
            );
            assert_eq!(
                first_difference(&want_depth[from..from + len], band.depth(), w),
                None,
                "depths, {what}"
            );
        }
    }
    stats
}

/// Textured meshes through a `MeshBin` (issue #28): spot with its texture in the bench frame
/// (320×240) and close enough that the near plane clips it, every shading, nearest and bilinear
/// Rgb565 texels and the 4-bit palette in flash, vertex colours, highlights and the pipeline's
/// `Lights`, into Rgb565 and Rgb888, in bands of several heights: each band the frame drawn
/// whole with `draw_textured_mesh_with`, pixels and depths; and its errors: a storage too
/// short (the number needed), a band of another layout.
#[test]
fn textured_mesh_bins_are_the_whole_frame() {
    let mut texels = vec![0u16; textured3d::TEXELS];
    textured3d::expand(&mut texels);
    let (tw, th) = (
        textured3d::SPOT_TEXTURE_WIDTH,
        textured3d::SPOT_TEXTURE_HEIGHT,
    );
    let nearest = Texture::new(Rgb565Texels(&texels), tw, th).unwrap();
    let bilinear = nearest.with_filter(Filter::Bilinear);
    let palette = Texture::new(textured3d::SPOT_TEXTURE, tw, th).unwrap();
    let size = Size::new(scene3d::SIZE.0, scene3d::SIZE.1);
    let spot: Mesh<'_> = textured3d::SPOT_TEXTURED;
    let colors: Vec<Rgb888> = (0..spot.vertices.len() as u32)
        .map(|k| Rgb888::new((k * 97) as u8, (k * 31 + 80) as u8, (k * 57 + 160) as u8))
        .collect();
    let tinted = spot.with_colors(&colors);
    let frame = scene3d::pipeline(scene3d::Model::Spot);
    // The camera 0.8 from spot's centre, the near plane at 0.5: its front is clipped.
    let projection = Mat4::perspective(
        Angle::from_degrees(70),
        Scalar::from_num(4) / 3,
        Scalar::from_num(0.5),
        Scalar::from_num(8),
    )
    .unwrap();
    let view = Mat4::translation(Vec3::from_bits(0, 0, -52429));
    let close = Pipeline::new(
        Mat4::rotation_y(Angle::from_degrees(200)),
        projection * view,
        Rectangle::new(Point::new(-9, 5), Size::new(330, 220)),
        frame.light,
    );
    let lights = Lights::new()
        .with(LightSource::point(
            Vec3::new(-0.8, 0.6, 1.2),
            Scalar::from_num(1.2),
            Scalar::from_num(2.5),
        ))
        .with(LightSource::directional(
            Vec3::new(0.3, -1.0, 0.2),
            Scalar::from_num(0.4),
        ));
    let shiny = Specular::new(Scalar::from_num(0.6), 16);

    let gouraud = TexturedMaterial::new(&nearest, Shading::Gouraud);
    let stats = check_textured_bin::<_, Rgb565>(
        "nearest, Gouraud",
        size,
        &frame,
        &spot,
        &gouraud,
        &[1, 5, 16, 240],
    );
    let flat = TexturedMaterial::new(&bilinear, Shading::Flat);
    check_textured_bin::<_, Rgb888>("bilinear, flat", size, &frame, &spot, &flat, &[8, 33]);
    let unlit = TexturedMaterial::new(&palette, Shading::Unlit);
    let clipped = check_textured_bin::<_, Rgb565>(
        "palette, unlit, clipped",
        size,
        &close,
        &spot,
        &unlit,
        &[3, 16],
    );
    assert!(clipped.clipped > 10, "{clipped:?}");
    let lit = frame.with_lights(lights);
    let all = TexturedMaterial::new(&nearest, Shading::Gouraud)
        .with_vertex_colors()
        .with_specular(shiny);
    check_textured_bin::<_, Rgb565>(
        "Gouraud, colours, highlight, lights",
        size,
        &lit,
        &tinted,
        &all,
        &[7, 16],
    );
    let close_lit = close.with_lights(lights);
    let quadratic = TexturedMaterial::new(&bilinear, Shading::Quadratic).with_specular(shiny);
    check_textured_bin::<_, Rgb888>(
        "bilinear, quadratic, highlight, lights, clipped",
        size,
        &close_lit,
        &spot,
        &quadratic,
        &[1, 12],
    );
    let flat_shiny = TexturedMaterial::new(&palette, Shading::Flat)
        .with_vertex_colors()
        .with_specular(shiny);
    check_textured_bin::<_, Rgb565>(
        "palette, flat, colours, highlight",
        size,
        &close,
        &tinted,
        &flat_shiny,
        &[10],
    );

    // Errors before anything is drawn: a storage too short (the number needed), a scratch too
    // short, a band of another layout.
    let layout = BandLayout::new(size, 16).unwrap();
    let mut scratch = vec![ProjectedVertex::EMPTY; spot.vertices.len()];
    let mut storage = vec![BinEntry::EMPTY; 15 + spot.indices.len()];
    let faces = MeshBin::<Rgb565, _>::new_textured(
        &frame,
        &spot,
        &gouraud,
        &layout,
        &mut scratch,
        &mut storage,
    )
    .unwrap()
    .len();
    assert!(
        faces > 2000 && faces <= stats.drawn as usize,
        "{faces} faces kept"
    );
    let mut short = vec![BinEntry::EMPTY; 15 + faces - 1];
    let error = MeshBin::<Rgb565, _>::new_textured(
        &frame,
        &spot,
        &gouraud,
        &layout,
        &mut scratch,
        &mut short,
    )
    .unwrap_err();
    assert_eq!(
        error,
        BandError::BinTooSmall {
            needed: 15 + faces,
            given: 15 + faces - 1
        }
    );
    let mut storage = vec![BinEntry::EMPTY; 15 + faces];
    let error = MeshBin::<Rgb565, _>::new_textured(
        &frame,
        &spot,
        &gouraud,
        &layout,
        &mut scratch[..100],
        &mut storage,
    )
    .unwrap_err();
    assert!(matches!(error, BandError::Scratch(_)), "{error:?}");
    let mut bin =
        MeshBin::new_textured(&frame, &spot, &gouraud, &layout, &mut scratch, &mut storage)
            .unwrap();
    let other = BandLayout::new(size, 15).unwrap();
    let (mut c, mut d) = (vec![Rgb565::BLACK; 320 * 15], vec![0; 320 * 15]);
    let mut band = DepthBand::new(&mut c, &mut d, &other, 7).unwrap();
    band.clear(Rgb565::BLACK);
    assert_eq!(bin.draw(&mut band), Err(BandError::OtherLayout));
    assert!(band.pixels().iter().all(|&p| p == Rgb565::BLACK));
    assert!(band
        .depth()
        .iter()
        .all(|&z| z == embedded_raster::three_d::DEPTH_CLEAR));
}

/// The bench scene's knot binned for the bands of `layout`.
fn knot_bin<'a>(
    pipeline: &'a Pipeline,
    layout: &BandLayout,
    scratch: &'a mut [ProjectedVertex],
    storage: &'a mut [BinEntry],
) -> Result<MeshBin<'a, Rgb565>, BandError> {
    MeshBin::new(
        pipeline,
        &scene3d::KNOT,
        &scene3d::MATERIAL,
        layout,
        scratch,
        storage,
    )
}

/// A bin's counts are the whole frame's.
#[test]
fn mesh_bin_counts_are_the_frames() {
    let pipeline = scene3d::pipeline(scene3d::Model::Knot);
    let (w, h) = scene3d::SIZE;
    let (mut colors, mut depth) = (
        vec![Rgb565::BLACK; (w * h) as usize],
        vec![0; (w * h) as usize],
    );
    let mut target = DepthTarget::new(&mut colors, &mut depth, w, h).unwrap();
    let want = scene3d::render(scene3d::Model::Knot, &scene3d::KNOT, &mut target, None);
    let layout = BandLayout::new(Size::new(w, h), 16).unwrap();
    let mut scratch = vec![ProjectedVertex::EMPTY; scene3d::KNOT.vertices.len()];
    let mut storage = vec![BinEntry::EMPTY; 15 + 6144];
    let bin = knot_bin(&pipeline, &layout, &mut scratch, &mut storage).unwrap();
    assert_eq!(bin.stats(), want);
}

/// Errors before anything is drawn: a zero band height, buffers of the wrong size, a bin too
/// small (with the number it needs), a scratch too short, a band of another layout.
#[test]
fn bad_input_is_an_error_before_drawing() {
    let size = Size::new(32, 20);
    assert_eq!(BandLayout::new(size, 0), Err(BandError::ZeroRows));
    assert_eq!(
        BandLayout::new(Size::new(1 << 31, 2), 1),
        Err(BandError::FrameTooLarge)
    );
    let layout = BandLayout::new(size, 8).unwrap();
    assert_eq!(layout.count(), 3);
    let mut short = [Rgb565::BLACK; 32 * 8 - 1];
    let mut long = [Rgb565::BLACK; 32 * 8 + 1];
    let mut right = [Rgb565::BLACK; 32 * 8];
    let mut depth = [0u16; 32 * 7];
    let wrong = |needed, given| BandError::ColorBuffer { needed, given };
    assert_eq!(
        ColorBand::new(&mut short, &layout, 0).unwrap_err(),
        wrong(256, 255)
    );
    assert_eq!(
        ColorBand::new(&mut long, &layout, 0).unwrap_err(),
        wrong(256, 257)
    );
    assert_eq!(
        ColorBand::new(&mut right, &layout, 3).unwrap_err(),
        BandError::NoSuchBand { index: 3, count: 3 }
    );
    assert_eq!(
        ColorBands::new(layout, &mut short).unwrap_err(),
        wrong(256, 255)
    );
    assert_eq!(
        DepthBand::new(&mut right, &mut depth, &layout, 0).unwrap_err(),
        BandError::DepthBuffer {
            needed: 256,
            given: 224
        }
    );
    let mut back = [Rgb565::BLACK; 32 * 8];
    assert_eq!(
        ColorBands::double(layout, &mut right, &mut short).unwrap_err(),
        wrong(256, 255)
    );
    let colors = ColorBands::double(layout, &mut right, &mut back).unwrap();
    assert_eq!(
        DepthBands::new(colors, &mut depth).unwrap_err(),
        BandError::DepthBuffer {
            needed: 256,
            given: 224
        }
    );

    // A bin too small: the number needed, and nothing drawn since nothing can be.
    let pipeline = scene3d::pipeline(scene3d::Model::Knot);
    let layout = BandLayout::new(Size::new(320, 240), 16).unwrap();
    let mut scratch = vec![ProjectedVertex::EMPTY; scene3d::KNOT.vertices.len()];
    let mut storage = vec![BinEntry::EMPTY; 15 + 6144];
    let faces = knot_bin(&pipeline, &layout, &mut scratch, &mut storage)
        .unwrap()
        .len();
    let mut storage = vec![BinEntry::EMPTY; 15 + faces - 1];
    let error = knot_bin(&pipeline, &layout, &mut scratch, &mut storage).unwrap_err();
    assert_eq!(
        error,
        BandError::BinTooSmall {
            needed: 15 + faces,
            given: 15 + faces - 1
        }
    );
    let mut few = vec![BinEntry::EMPTY; 3];
    let error = knot_bin(&pipeline, &layout, &mut scratch, &mut few).unwrap_err();
    assert_eq!(
        error,
        BandError::BinTooSmall {
            needed: 15 + faces,
            given: 3
        }
    );
    let mut storage = vec![BinEntry::EMPTY; 15 + faces];
    let error = knot_bin(&pipeline, &layout, &mut scratch[..100], &mut storage).unwrap_err();
    assert!(matches!(error, BandError::Scratch(_)), "{error:?}");

    // A band of another layout.
    let mut bin = knot_bin(&pipeline, &layout, &mut scratch, &mut storage).unwrap();
    let other = BandLayout::new(Size::new(320, 240), 15).unwrap();
    let (mut c, mut d) = (vec![Rgb565::BLACK; 320 * 15], vec![0; 320 * 15]);
    let mut band = DepthBand::new(&mut c, &mut d, &other, 0).unwrap();
    band.clear(Rgb565::BLACK);
    assert_eq!(bin.draw(&mut band), Err(BandError::OtherLayout));
    assert!(band.pixels().iter().all(|&p| p == Rgb565::BLACK));

    // 2D: the triangles and bands a bin needs.
    let c = |x: i32, y: i32| (Coord::from_num(x), Coord::from_num(y));
    let scene = [
        SolidTriangle::new([c(0, 0), c(10, 0), c(0, 10)], Gray8::WHITE),
        // Above the frame: not recorded.
        SolidTriangle::new([c(0, -30), c(10, -30), c(0, -20)], Gray8::WHITE),
        SolidTriangle::new([c(0, 10), c(10, 10), c(0, 19)], Gray8::WHITE),
    ];
    let layout = BandLayout::new(size, 8).unwrap();
    let mut storage = [BinEntry::EMPTY; 4];
    assert_eq!(
        TriangleBin::new(&layout, &scene, &mut storage).unwrap_err(),
        BandError::BinTooSmall {
            needed: 5,
            given: 4
        }
    );
    let mut storage = [BinEntry::EMPTY; 5];
    assert_eq!(
        TriangleBin::new(&layout, &scene, &mut storage)
            .unwrap()
            .len(),
        2
    );
}

/// A display that records its calls.
struct Recording {
    size: Size,
    pixels: Vec<Rgb565>,
    calls: Vec<Rectangle>,
}

impl OriginDimensions for Recording {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Recording {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        _: I,
    ) -> Result<(), Self::Error> {
        panic!("bands are sent as rectangles");
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        self.calls.push(*area);
        let mut colors = colors.into_iter();
        for p in area.points() {
            let c = colors.next().expect("a colour per pixel");
            self.pixels[(p.y as u32 * self.size.width + p.x as u32) as usize] = c;
        }
        assert!(colors.next().is_none(), "no colour left");
        Ok(())
    }
}

/// Each band reaches a `DrawTarget` as one `fill_contiguous` of its rectangle, top to bottom,
/// and the display ends up with the frame (the knot, 320×240, in 16-row bands and in bands of
/// 7 rows, the last one shorter).
#[test]
fn bands_reach_a_display_as_one_fill_each() {
    let (want, _) = knot_frame();
    let (w, h) = scene3d::SIZE;
    let pipeline = scene3d::pipeline(scene3d::Model::Knot);
    for rows in [16, 7] {
        let layout = BandLayout::new(Size::new(w, h), rows).unwrap();
        let mut display = Recording {
            size: Size::new(w, h),
            pixels: vec![Rgb565::BLACK; (w * h) as usize],
            calls: Vec::new(),
        };
        let n = layout.buffer_len();
        let (mut front, mut back, mut depth) = (
            vec![Rgb565::BLACK; n],
            vec![Rgb565::BLACK; n],
            vec![0u16; n],
        );
        let mut bands = DepthBands::new(
            ColorBands::double(layout, &mut front, &mut back).unwrap(),
            &mut depth,
        )
        .unwrap();
        bands
            .render(&mut ToDisplay(&mut display), |band| {
                band.clear(scene3d::BACKGROUND);
                pipeline.draw_mesh(&scene3d::KNOT, &scene3d::MATERIAL, band);
            })
            .unwrap();
        assert_eq!(display.calls, layout.bands().collect::<Vec<_>>());
        assert_eq!(
            first_difference(&want, &display.pixels, w),
            None,
            "{rows}-row bands"
        );
    }
}

/// An asynchronous output (DMA): `send` only notes the buffer as busy, `wait` frees it. No band
/// may be drawn into a busy buffer, and with two buffers they alternate.
#[test]
fn double_buffers_are_never_drawn_while_sent() {
    struct Dma {
        busy: Option<*const Rgb565>,
        sent: Vec<(*const Rgb565, Rectangle, u32)>,
        waits: u32,
    }
    impl BandOutput<Rgb565> for Dma {
        type Error = ();
        fn send(&mut self, area: &Rectangle, pixels: &[Rgb565]) -> Result<(), ()> {
            assert!(
                self.busy.is_none(),
                "a transfer started before the last one ended"
            );
            assert_eq!(pixels.len() as u32, area.size.width * area.size.height);
            let sum = pixels.iter().map(|p| u32::from(p.into_storage())).sum();
            self.busy = Some(pixels.as_ptr());
            self.sent.push((pixels.as_ptr(), *area, sum));
            Ok(())
        }
        fn wait(&mut self) -> Result<(), ()> {
            self.busy = None;
            self.waits += 1;
            Ok(())
        }
    }
    let layout = BandLayout::new(Size::new(10, 25), 4).unwrap();
    for double in [false, true] {
        let (mut front, mut back) = ([Rgb565::BLACK; 40], [Rgb565::BLACK; 40]);
        let mut bands = if double {
            ColorBands::double(layout, &mut front, &mut back).unwrap()
        } else {
            ColorBands::new(layout, &mut front).unwrap()
        };
        let mut dma = Dma {
            busy: None,
            sent: Vec::new(),
            waits: 0,
        };
        let busy: *const Option<*const Rgb565> = &dma.busy;
        let mut drawn = 0;
        bands
            .render(&mut dma, |band| {
                // Safety: read only, between the output's calls.
                let busy = unsafe { *busy };
                assert_ne!(
                    busy,
                    Some(band.pixels().as_ptr()),
                    "drawing into a buffer being sent"
                );
                band.clear(Rgb565::new(drawn, 0, 0));
                drawn += 1;
            })
            .unwrap();
        assert_eq!(dma.sent.len(), 7);
        assert_eq!(dma.waits, 7);
        assert!(dma.busy.is_none());
        for (k, (ptr, area, sum)) in dma.sent.iter().enumerate() {
            assert_eq!(Some(*area), layout.band(k as u32));
            assert_eq!(
                *sum,
                area.size.width
                    * area.size.height
                    * u32::from(Rgb565::new(k as u8, 0, 0).into_storage())
            );
            if double && k > 0 {
                assert_ne!(*ptr, dma.sent[k - 1].0, "the buffers alternate");
            }
        }
    }
}

/// `Callback` hands the pixels over; its error stops the frame.
#[test]
fn a_callbacks_error_stops_the_frame() {
    let layout = BandLayout::new(Size::new(8, 8), 2).unwrap();
    let mut buffer = [Gray8::BLACK; 16];
    let mut bands = ColorBands::new(layout, &mut buffer).unwrap();
    let mut calls = 0;
    let result = bands.render(
        &mut Callback(|area: &Rectangle, _: &[Gray8]| {
            calls += 1;
            if area.top_left.y == 4 {
                Err("display gone")
            } else {
                Ok(())
            }
        }),
        |band| band.clear(Gray8::WHITE),
    );
    assert_eq!(result, Err(RenderError::Display("display gone")));
    assert_eq!(calls, 3);
}

/// A band's draw that fails (a bin of another layout) stops the frame with `RenderError::Band`:
/// that band is not sent, the output is waited for, and no later band is drawn.
#[test]
fn a_draws_error_stops_the_frame() {
    let layout = BandLayout::new(Size::new(8, 8), 2).unwrap();
    let other = BandLayout::new(Size::new(8, 8), 4).unwrap();
    let scene = [SolidTriangle::new(
        [(0.0, 0.0), (8.0, 0.0), (0.0, 8.0)],
        Gray8::WHITE,
    )];
    let mut storage = [BinEntry::EMPTY; 8];
    let mut wrong = TriangleBin::new(&other, &scene, &mut storage).unwrap();
    let mut buffer = [Gray8::BLACK; 16];
    let mut bands = ColorBands::new(layout, &mut buffer).unwrap();
    let (mut sent, mut drawn) = (0, 0);
    let result = bands.render(
        &mut Callback(|_: &Rectangle, _: &[Gray8]| {
            sent += 1;
            Ok::<(), &str>(())
        }),
        |band| {
            drawn += 1;
            band.clear(Gray8::WHITE);
            // The first band draws; the second one's bin is of another layout.
            if band.index() == 0 {
                Ok(())
            } else {
                wrong.draw(band)
            }
        },
    );
    assert_eq!(result, Err(RenderError::Band(BandError::OtherLayout)));
    assert_eq!((drawn, sent), (2, 1));
}

/// `RenderError`'s messages: the band error's own, or the display's error (by its `Debug`, which
/// every `DrawTarget::Error` has); and `?` takes a render's error and the set-up's into
/// `Box<dyn Error>` (issue #32, item 4).
#[test]
fn render_errors_say_what_failed_and_box() {
    #[derive(Debug)]
    #[allow(dead_code)] // read through `Debug`
    struct SpiError(u8);

    let band: RenderError<SpiError> = BandError::ZeroRows.into();
    assert_eq!(
        band.to_string(),
        "a band of 0 rows: a band needs at least 1 row"
    );
    let display = RenderError::Display(SpiError(3));
    assert_eq!(
        display.to_string(),
        "the display (band output) failed: SpiError(3)"
    );
    let scratch: RenderError<SpiError> = embedded_raster::three_d::ScratchTooSmall {
        needed: 42,
        given: 12,
    }
    .into();
    assert!(matches!(scratch, RenderError::Band(BandError::Scratch(_))));
    // The band error's source is the wrapped one's (the message is the band error's).
    assert!(std::error::Error::source(&scratch).is_some());
    assert!(std::error::Error::source(&display).is_none());

    fn frame(rows: u32, fail: bool) -> Result<(), Box<dyn std::error::Error>> {
        let layout = BandLayout::new(Size::new(8, 8), rows)?;
        let mut buffer = [Gray8::BLACK; 16];
        let mut bands = ColorBands::new(layout, &mut buffer)?;
        bands.render(
            &mut Callback(
                |_: &Rectangle, _: &[Gray8]| {
                    if fail {
                        Err(SpiError(7))
                    } else {
                        Ok(())
                    }
                },
            ),
            |band| band.clear(Gray8::WHITE),
        )?;
        Ok(())
    }
    assert!(frame(2, false).is_ok());
    assert_eq!(
        frame(0, false).unwrap_err().to_string(),
        "a band of 0 rows: a band needs at least 1 row"
    );
    assert_eq!(
        frame(4, false).unwrap_err().to_string(),
        "a colour band buffer needs 32 pixels (width · rows), given 16"
    );
    assert_eq!(
        frame(2, true).unwrap_err().to_string(),
        "the display (band output) failed: SpiError(7)"
    );
}

/// A `ColorBand` as an embedded-graphics target: other drawables land in frame coordinates,
/// clipped to the band, as on a whole frame.
#[test]
fn color_band_is_a_draw_target_in_frame_coordinates() {
    use embedded_graphics::primitives::{Circle, PrimitiveStyle};
    let (w, h) = (40u32, 30u32);
    let mut whole = vec![Gray8::BLACK; (w * h) as usize];
    let mut fb = SliceFramebuffer::new(&mut whole, w, h).unwrap();
    let circle =
        Circle::new(Point::new(5, 3), 24).into_styled(PrimitiveStyle::with_fill(Gray8::WHITE));
    let rect = Rectangle::new(Point::new(-3, 20), Size::new(60, 7))
        .into_styled(PrimitiveStyle::with_fill(Gray8::new(99)));
    circle.draw(&mut fb).unwrap();
    rect.draw(&mut fb).unwrap();
    fb.fill_contiguous(
        &Rectangle::new(Point::new(30, -2), Size::new(5, 9)),
        (0..45).map(|v| Gray8::new(v as u8)),
    )
    .unwrap();
    let layout = BandLayout::new(Size::new(w, h), 4).unwrap();
    let mut buffer = vec![Gray8::BLACK; layout.buffer_len()];
    let mut got = Vec::new();
    for index in 0..layout.count() {
        let mut band = ColorBand::new(&mut buffer, &layout, index).unwrap();
        band.clear(Gray8::BLACK);
        circle.draw(&mut band).unwrap();
        rect.draw(&mut band).unwrap();
        band.fill_contiguous(
            &Rectangle::new(Point::new(30, -2), Size::new(5, 9)),
            (0..45).map(|v| Gray8::new(v as u8)),
        )
        .unwrap();
        got.extend_from_slice(band.pixels());
    }
    assert_eq!(first_difference(&whole, &got, w), None);
}

/// A bin takes frames of up to 32,768 bands and refuses more before anything is drawn
/// (`BinLimit`), a 2D bin and a mesh bin alike.
#[test]
fn bins_refuse_more_bands_than_they_number() {
    let c = |x: i32, y: i32| (Coord::from_num(x), Coord::from_num(y));
    let scene = [SolidTriangle::new(
        [c(0, 0), c(3, 0), c(0, 40_000)],
        Gray8::WHITE,
    )];
    let pipeline = scene3d::pipeline(scene3d::Model::Knot);
    let material = Material::new(Rgb888::WHITE, Shading::Gouraud);
    let mut scratch = vec![ProjectedVertex::EMPTY; ICOSPHERE.vertices.len()];
    for (height, fits) in [(32_768, true), (32_769, false), (40_000, false)] {
        let layout = BandLayout::new(Size::new(4, height), 1).unwrap();
        let mut storage = vec![BinEntry::EMPTY; height as usize + 1];
        let bin = TriangleBin::new(&layout, &scene, &mut storage);
        assert_eq!(bin.is_ok(), fits, "2D, {height} bands");
        if !fits {
            assert_eq!(bin.unwrap_err(), BandError::BinLimit);
        }
        let mut storage = vec![BinEntry::EMPTY; height as usize + 1000];
        let bin = MeshBin::new(
            &pipeline,
            &ICOSPHERE,
            &material,
            &layout,
            &mut scratch,
            &mut storage,
        );
        match bin {
            Ok(_) => assert!(fits, "mesh, {height} bands"),
            Err(e) => assert!(
                !fits && e == BandError::BinLimit,
                "mesh, {height} bands: {e:?}"
            ),
        }
    }
}
