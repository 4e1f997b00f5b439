//! Translucent triangles against an f64 reference, and every way of drawing them alike.
//!
//! * An opacity: every covered pixel within 1 LSB of the exact `s·a/255 + d·(1 − a/255)`, every
//!   other pixel untouched (coverage from the reference's exact rule).
//! * An alpha per vertex: within 1 LSB of `P + d·(1 − α)` for the barycentric premultiplied
//!   colour `P = Σ bₖ sₖ aₖ/255` and alpha `α = Σ bₖ aₖ/255` at the pixel centre.
//! * `draw_into`, `draw_reading` (through `GetPixel`), `over` a background colour (into a
//!   framebuffer and into a target with nothing but `draw_iter`) and bands of every height give
//!   the same pixels.
//!
//! Triangles from sub-pixel to far beyond the target, over random backgrounds, in 5-6-5, 6-6-6,
//! 8-8-8 and grey formats.

use std::fmt::Debug;

use embedded_graphics::pixelcolor::{Bgr565, Gray4, Gray8, Rgb565, Rgb666, Rgb888};
use embedded_graphics::prelude::*;
use embedded_raster::band::{BandLayout, ColorBand};
use embedded_raster::reference;
use embedded_raster::{
    Coord, GouraudColor, GouraudTriangle, SliceFramebuffer, SolidTriangle, Vertex,
};

use crate::readable_target;
use readable_target::ReadableTarget;

use crate::rng;
use rng::Rng;

use crate::raw_points;
use raw_points::mixed_triangle;

const W: u32 = 61;
const H: u32 = 37;

fn triangle(rng: &mut Rng) -> [(i32, i32); 3] {
    mixed_triangle(rng, W, H)
}

fn coords(v: [(i32, i32); 3]) -> [(Coord, Coord); 3] {
    v.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y)))
}

fn color<C: GouraudColor>(rng: &mut Rng) -> C {
    C::from_channels(core::array::from_fn(|k| match rng.below(5) {
        0 => 0,
        1 => C::MAX[k],
        _ => rng.below(u64::from(C::MAX[k]) + 1) as u8,
    }))
}

fn alpha(rng: &mut Rng) -> u8 {
    match rng.below(6) {
        0 => 0,
        1 => 255,
        _ => rng.below(256) as u8,
    }
}

fn background<C: GouraudColor>(rng: &mut Rng) -> Vec<C> {
    (0..W * H).map(|_| color(rng)).collect()
}

/// Checks every pixel of `after` (drawn over `before`): covered ones within 1 LSB of `exact`
/// (channels in the format's units), the others unchanged. Returns the largest error.
fn check<C: GouraudColor + Debug>(
    v: [(i32, i32); 3],
    before: &[C],
    after: &[C],
    exact: impl Fn(i32, i32, [u8; 3]) -> [f64; 3],
    what: &str,
) -> f64 {
    let mut worst = 0.0f64;
    for y in 0..H as i32 {
        for x in 0..W as i32 {
            let i = (y as u32 * W + x as u32) as usize;
            if !reference::covers(v, x, y) {
                assert_eq!(
                    after[i], before[i],
                    "{what}: pixel ({x}, {y}) outside {v:?} drawn"
                );
                continue;
            }
            let want = exact(x, y, before[i].channels());
            let got = after[i].channels();
            for k in 0..C::CHANNELS {
                let error = (f64::from(got[k]) - want[k]).abs();
                worst = worst.max(error);
                assert!(
                    error < 1.0,
                    "{what}: pixel ({x}, {y}) of {v:?}, channel {k}: {} against {}, under {:?}",
                    got[k],
                    want[k],
                    before[i]
                );
            }
        }
    }
    worst
}

fn opacity_against_f64<C: GouraudColor + Debug>(seed: u64, count: usize) -> f64 {
    let mut rng = Rng(seed);
    let mut worst = 0.0f64;
    for _ in 0..count {
        let v = triangle(&mut rng);
        let (s, a) = (color::<C>(&mut rng), alpha(&mut rng));
        let before = background::<C>(&mut rng);
        let mut after = before.clone();
        let mut fb = SliceFramebuffer::new(&mut after, W, H).unwrap();
        SolidTriangle::new(coords(v), s)
            .with_opacity(a)
            .draw_into(&mut fb);
        let alpha = f64::from(a) / 255.0;
        let s = s.channels();
        worst = worst.max(check(
            v,
            &before,
            &after,
            |_, _, d| {
                core::array::from_fn(|k| f64::from(s[k]) * alpha + f64::from(d[k]) * (1.0 - alpha))
            },
            std::any::type_name::<C>(),
        ));
    }
    worst
}

fn vertex_alpha_against_f64<C: GouraudColor + Debug>(seed: u64, count: usize) -> f64 {
    let mut rng = Rng(seed);
    let mut worst = 0.0f64;
    for _ in 0..count {
        let v = triangle(&mut rng);
        let colors: [C; 3] = core::array::from_fn(|_| color(&mut rng));
        let alphas: [u8; 3] = core::array::from_fn(|_| alpha(&mut rng));
        let before = background::<C>(&mut rng);
        let mut after = before.clone();
        let mut fb = SliceFramebuffer::new(&mut after, W, H).unwrap();
        let c = coords(v);
        let vertices = core::array::from_fn(|k| Vertex::new(c[k].0, c[k].1, colors[k]));
        GouraudTriangle::new(vertices)
            .with_alpha(alphas)
            .draw_into(&mut fb);
        // Premultiplied channels, and the alpha, per vertex.
        let premultiplied: [[f64; 3]; 3] = core::array::from_fn(|k| {
            let a = f64::from(alphas[k]) / 255.0;
            colors[k].channels().map(|s| f64::from(s) * a)
        });
        let a = alphas.map(|a| [f64::from(a) / 255.0; 3]);
        worst = worst.max(check(
            v,
            &before,
            &after,
            |x, y, d| {
                let p = reference::interpolate(v, premultiplied, x, y).unwrap();
                let alpha = reference::interpolate(v, a, x, y).unwrap()[0];
                core::array::from_fn(|k| p[k] + f64::from(d[k]) * (1.0 - alpha))
            },
            std::any::type_name::<C>(),
        ));
    }
    worst
}

#[test]
fn opacity_is_within_one_lsb_of_the_f64_blend() {
    let worst = [
        opacity_against_f64::<Rgb565>(1, 400),
        opacity_against_f64::<Bgr565>(2, 200),
        opacity_against_f64::<Rgb666>(3, 200),
        opacity_against_f64::<Rgb888>(4, 400),
        opacity_against_f64::<Gray8>(5, 200),
        opacity_against_f64::<Gray4>(6, 200),
    ];
    println!("largest error (LSB): {worst:?}");
}

#[test]
fn vertex_alpha_is_within_one_lsb_of_the_f64_blend() {
    let worst = [
        vertex_alpha_against_f64::<Rgb565>(11, 400),
        vertex_alpha_against_f64::<Bgr565>(12, 200),
        vertex_alpha_against_f64::<Rgb666>(13, 200),
        vertex_alpha_against_f64::<Rgb888>(14, 400),
        vertex_alpha_against_f64::<Gray8>(15, 200),
        vertex_alpha_against_f64::<Gray4>(16, 200),
    ];
    println!("largest error (LSB): {worst:?}");
}

/// Draws `draw_into`'s pixels every other way and compares.
fn same_pixels<C, T>(
    triangle: &T,
    under: &[C],
    into: impl Fn(&T, &mut SliceFramebuffer<'_, C>),
    reading: impl Fn(&T, &mut ReadableTarget<C>),
    over: impl Fn(&T, C, &mut ReadableTarget<C>),
    uniform: C,
) where
    C: GouraudColor + Debug,
    T: embedded_raster::band::BandDrawable<C>,
{
    let mut want = under.to_vec();
    into(
        triangle,
        &mut SliceFramebuffer::new(&mut want, W, H).unwrap(),
    );

    let mut target = ReadableTarget::new(W, H, under.to_vec());
    reading(triangle, &mut target);
    assert_eq!(target.pixels, want, "draw_reading");

    for rows in [1, 2, 3, 7, 16, H] {
        let layout = BandLayout::new(Size::new(W, H), rows).unwrap();
        let mut buffer = vec![uniform; layout.buffer_len()];
        for index in 0..layout.count() {
            let start = (layout.band(index).unwrap().top_left.y as u32 * W) as usize;
            let len = (layout.band(index).unwrap().size.height * W) as usize;
            buffer[..len].copy_from_slice(&under[start..start + len]);
            let mut band = ColorBand::new(&mut buffer, &layout, index).unwrap();
            band.draw(triangle);
            assert_eq!(
                band.pixels(),
                &want[start..start + len],
                "band of {rows} rows, {index}"
            );
        }
    }

    // Over a uniform background: `over` into a framebuffer and a `draw_iter` target.
    let plain = vec![uniform; (W * H) as usize];
    let mut want = plain.clone();
    into(
        triangle,
        &mut SliceFramebuffer::new(&mut want, W, H).unwrap(),
    );
    let mut target = ReadableTarget::new(W, H, plain.clone());
    over(triangle, uniform, &mut target);
    assert_eq!(target.pixels, want, "over a background colour");
}

fn paths_agree<C: GouraudColor + Debug>(seed: u64, count: usize) {
    let mut rng = Rng(seed);
    for _ in 0..count {
        let v = coords(triangle(&mut rng));
        let under = background::<C>(&mut rng);
        let uniform = color::<C>(&mut rng);
        let solid = SolidTriangle::new(v, color::<C>(&mut rng)).with_opacity(alpha(&mut rng));
        same_pixels(
            &solid,
            &under,
            |t, fb| t.draw_into(fb),
            |t, target| t.draw_reading(target).unwrap(),
            |t, bg, target| t.over(bg).draw(target).unwrap(),
            uniform,
        );
        let vertices = core::array::from_fn(|k| Vertex::new(v[k].0, v[k].1, color::<C>(&mut rng)));
        let alphas = core::array::from_fn(|_| alpha(&mut rng));
        let faded = GouraudTriangle::new(vertices).with_alpha(alphas);
        same_pixels(
            &faded,
            &under,
            |t, fb| t.draw_into(fb),
            |t, target| t.draw_reading(target).unwrap(),
            |t, bg, target| t.over(bg).draw(target).unwrap(),
            uniform,
        );
    }
}

#[test]
fn every_path_gives_the_same_pixels() {
    paths_agree::<Rgb565>(21, 300);
    paths_agree::<Rgb888>(22, 200);
    paths_agree::<Gray8>(23, 100);
}

/// Opacity 255 is the opaque triangle, opacity 0 and alpha 0 everywhere draw nothing.
#[test]
fn opaque_and_transparent_ends() {
    let mut rng = Rng(31);
    for _ in 0..300 {
        let v = coords(triangle(&mut rng));
        let s: Rgb565 = color(&mut rng);
        let under = background::<Rgb565>(&mut rng);
        let (mut opaque, mut full) = (under.clone(), under.clone());
        SolidTriangle::new(v, s).draw_into(&mut SliceFramebuffer::new(&mut opaque, W, H).unwrap());
        let solid = SolidTriangle::new(v, s);
        solid
            .with_opacity(255)
            .draw_into(&mut SliceFramebuffer::new(&mut full, W, H).unwrap());
        assert_eq!(full, opaque);
        let mut none = under.clone();
        solid
            .with_opacity(0)
            .draw_into(&mut SliceFramebuffer::new(&mut none, W, H).unwrap());
        let vertices = core::array::from_fn(|k| Vertex::new(v[k].0, v[k].1, s));
        let faded = GouraudTriangle::new(vertices).with_alpha([0; 3]);
        faded.draw_into(&mut SliceFramebuffer::new(&mut none, W, H).unwrap());
        assert_eq!(none, under);
    }
}

/// The frame the translucent-mesh tests draw over: 96 × 72, a torus lit Gouraud, and the
/// camera and light of the translucent meshes in front of it.
mod over_torus {
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::prelude::*;
    use embedded_graphics::primitives::Rectangle;
    use embedded_raster::band::MeshBin;
    use embedded_raster::band::{
        BandLayout, BinEntry, Callback, ColorBands, DepthBand, DepthBands,
    };
    use embedded_raster::three_d::meshes::torus::TORUS;
    use embedded_raster::three_d::{Angle, MeshTarget, ProjectedVertex};
    use embedded_raster::Vec3;
    use embedded_raster::{DepthTarget, GouraudColor, Light, Mat4, Material, Pipeline, Shading};

    pub const W: u32 = 96;
    pub const H: u32 = 72;
    const N: usize = (W * H) as usize;

    /// The camera and light of the scene; `model` places a mesh.
    pub fn pipeline(model: Mat4) -> Pipeline {
        let camera = Mat4::perspective(Angle::from_degrees(55), 4.0 / 3.0, 0.5, 20).unwrap()
            * Mat4::look_at(Vec3::new(0.3, 0.8, 3.2), Vec3::ZERO, Vec3::new(0, 1, 0)).unwrap();
        let viewport = Rectangle::new(Point::zero(), Size::new(W, H));
        Pipeline::new(
            model,
            camera,
            viewport,
            Light::new(Vec3::new(-0.4, 1.0, 0.8), 0.2),
        )
    }

    /// A band's draw of a bin.
    pub type BinDraw<'a> = Box<dyn FnMut(&mut DepthBand<'_, Rgb565>) + 'a>;

    /// A translucent mesh, drawn opaque or at its opacity by every path.
    pub trait Glass {
        /// Vertices of the mesh (a scratch's length).
        fn vertices(&self) -> usize;
        /// Draws the mesh opaque (`opaque`) or translucent into `target`.
        fn draw(&self, opaque: bool, target: &mut impl MeshTarget<Rgb565>);
        /// [`draw`](Self::draw) of the translucent mesh with a vertex scratch.
        fn draw_with(&self, target: &mut impl MeshTarget<Rgb565>, scratch: &mut [ProjectedVertex]);
        /// The translucent mesh's bin for `layout` (its vertices in `scratch`, its faces in
        /// `storage`), as a band's draw.
        fn bin<'a>(
            &'a self,
            layout: &BandLayout,
            scratch: &'a mut [ProjectedVertex],
            storage: &'a mut [BinEntry],
        ) -> BinDraw<'a>;
    }

    /// Copies each band into `out`, the frame's pixels.
    pub fn into_frame(
        out: &mut [Rgb565],
    ) -> impl FnMut(&Rectangle, &[Rgb565]) -> Result<(), ()> + '_ {
        move |rect: &Rectangle, px: &[Rgb565]| {
            let start = (rect.top_left.y as u32 * W) as usize;
            out[start..start + px.len()].copy_from_slice(px);
            Ok(())
        }
    }

    /// The torus behind, opaque.
    pub fn behind() -> (Pipeline, Material<Rgb565>) {
        (
            pipeline(Mat4::rotation_x(Angle::from_degrees(70))),
            Material::new(Rgb565::new(25, 30, 4), Shading::Gouraud),
        )
    }

    /// Draws the torus behind into a band.
    pub fn draw_behind(band: &mut DepthBand<'_, Rgb565>) {
        let (pipeline, base) = behind();
        band.clear(Rgb565::BLACK);
        pipeline.draw_mesh(&TORUS, &base, band);
    }

    /// `glass` at `opacity` over the torus: where it drawn opaque would write a pixel, the pixel
    /// is that colour blended over the one there; elsewhere, and the whole depth buffer,
    /// untouched. The same pixels with a vertex scratch, in bands of several heights (with and
    /// without a scratch) and from mesh bins.
    pub fn check(glass: &impl Glass, opacity: u8, case: &str) {
        let (behind, base) = behind();
        let (mut colors, mut depth) = (vec![Rgb565::BLACK; N], vec![0u16; N]);
        let mut target = DepthTarget::new(&mut colors, &mut depth, W, H).unwrap();
        behind.draw_mesh(&TORUS, &base, &mut target);
        let (before, before_depth) = (
            target.framebuffer().pixels().to_vec(),
            target.depth().to_vec(),
        );
        // The mesh drawn opaque over a copy: where and what it would draw.
        let (mut oc, mut od) = (before.clone(), before_depth.clone());
        let mut opaque = DepthTarget::new_uncleared(&mut oc, &mut od, W, H).unwrap();
        glass.draw(true, &mut opaque);
        let (drawn, drawn_depth) = (
            opaque.framebuffer().pixels().to_vec(),
            opaque.depth().to_vec(),
        );
        glass.draw(false, &mut target);
        assert!(target.depth() == &before_depth[..], "depth written, {case}");
        let mut blended = 0;
        for i in 0..N {
            let want = if drawn_depth[i] != before_depth[i] {
                blended += 1;
                drawn[i].blend(before[i], opacity)
            } else {
                before[i]
            };
            assert_eq!(target.framebuffer().pixels()[i], want, "pixel {i}, {case}");
        }
        assert!(blended > N / 20, "{blended}");
        let whole = target.framebuffer().pixels().to_vec();

        let mut scratch = vec![ProjectedVertex::EMPTY; glass.vertices()];
        let mut with = (before.clone(), before_depth.clone());
        let mut t = DepthTarget::new_uncleared(&mut with.0, &mut with.1, W, H).unwrap();
        glass.draw_with(&mut t, &mut scratch);
        assert!(t.framebuffer().pixels() == &whole[..], "scratch, {case}");
        assert!(
            t.depth() == &before_depth[..],
            "depth written with a scratch, {case}"
        );

        for rows in [5, 16, 72] {
            let layout = BandLayout::new(Size::new(W, H), rows).unwrap();
            let (mut cb, mut db) = (
                vec![Rgb565::BLACK; layout.buffer_len()],
                vec![0; layout.buffer_len()],
            );
            let mut bands =
                DepthBands::new(ColorBands::new(layout, &mut cb).unwrap(), &mut db).unwrap();
            let mut out = vec![Rgb565::BLACK; N];
            bands
                .render(&mut Callback(into_frame(&mut out)), |band| {
                    draw_behind(band);
                    if rows == 16 {
                        glass.draw_with(band, &mut scratch);
                    } else {
                        glass.draw(false, band);
                    }
                })
                .unwrap();
            assert!(out == whole, "{rows}-row bands, {case}");
            // From bins: the torus's, then the mesh's.
            let (mut s0, mut s1) = (
                vec![ProjectedVertex::EMPTY; TORUS.vertices.len()],
                vec![ProjectedVertex::EMPTY; glass.vertices()],
            );
            let (mut e0, mut e1) = (vec![BinEntry::EMPTY; 40_000], vec![BinEntry::EMPTY; 40_000]);
            let mut under =
                MeshBin::new(&behind, &TORUS, &base, &layout, &mut s0, &mut e0).unwrap();
            let mut over = glass.bin(&layout, &mut s1, &mut e1);
            let mut binned = vec![Rgb565::BLACK; N];
            bands
                .render(&mut Callback(into_frame(&mut binned)), |band| {
                    band.clear(Rgb565::BLACK);
                    under.draw(band).unwrap();
                    over(band);
                })
                .unwrap();
            assert!(binned == whole, "{rows}-row bins, {case}");
        }
    }
}

/// A translucent mesh (`Material::with_opacity`) over an opaque one (`over_torus::check`):
/// every shading, with and without a highlight, with the first light alone and with more
/// (`Lights`: a point light and a directional one).
#[test]
fn translucent_meshes_blend_where_nearer_and_keep_depth() {
    use embedded_raster::band::{BandLayout, BinEntry, MeshBin};
    use embedded_raster::three_d::meshes::icosphere::ICOSPHERE;
    use embedded_raster::three_d::{LightSource, Lights, MeshTarget, ProjectedVertex};
    use embedded_raster::{Mat4, Material, Pipeline, Shading, Specular, Vec3};
    use over_torus::Glass;

    struct Untextured(Pipeline, Material<Rgb565>);

    impl Glass for Untextured {
        fn vertices(&self) -> usize {
            ICOSPHERE.vertices.len()
        }

        fn draw(&self, opaque: bool, target: &mut impl MeshTarget<Rgb565>) {
            let material = if opaque {
                self.1.with_opacity(255)
            } else {
                self.1
            };
            self.0.draw_mesh(&ICOSPHERE, &material, target);
        }

        fn draw_with(&self, target: &mut impl MeshTarget<Rgb565>, scratch: &mut [ProjectedVertex]) {
            self.0
                .draw_mesh_with(&ICOSPHERE, &self.1, target, scratch)
                .unwrap();
        }

        fn bin<'a>(
            &'a self,
            layout: &BandLayout,
            scratch: &'a mut [ProjectedVertex],
            storage: &'a mut [BinEntry],
        ) -> over_torus::BinDraw<'a> {
            let mut bin =
                MeshBin::new(&self.0, &ICOSPHERE, &self.1, layout, scratch, storage).unwrap();
            Box::new(move |band| bin.draw(band).unwrap())
        }
    }

    let first =
        over_torus::pipeline(Mat4::translation(Vec3::new(0.2, 0.1, 0.6)) * Mat4::scaling(0.7));
    let lights = Lights::new()
        .with(LightSource::point(Vec3::new(0.9, 0.7, 1.5), 0.9, 2.5))
        .with(LightSource::directional(Vec3::new(1, -0.5, 0.3), 0.3));
    for front in [first, first.with_lights(lights)] {
        for shading in [
            Shading::Unlit,
            Shading::Flat,
            Shading::Gouraud,
            Shading::Quadratic,
        ] {
            for specular in [None, Some(Specular::new(0.6, 24))] {
                let mut glass = Material::new(Rgb565::new(6, 50, 31), shading);
                glass.specular = specular;
                for opacity in [0u8, 77, 200, 254] {
                    let case = format!("{shading:?}, {specular:?}, opacity {opacity}");
                    over_torus::check(
                        &Untextured(front, glass.with_opacity(opacity)),
                        opacity,
                        &case,
                    );
                }
            }
        }
    }
}

/// A translucent textured mesh (`TexturedMaterial::with_opacity`) over an opaque one
/// (`over_torus::check`): nearest and bilinear textures, power-of-two and not, every shading
/// with and without a highlight.
#[test]
fn translucent_textured_meshes_blend_where_nearer_and_keep_depth() {
    use embedded_raster::band::{BandLayout, BinEntry, MeshBin};
    use embedded_raster::texture::{Filter, Rgb565Texels, Texture};
    use embedded_raster::three_d::meshes::icosphere;
    use embedded_raster::three_d::TexturedMaterial;
    use embedded_raster::three_d::{Blended, Mesh, MeshTarget, ProjectedVertex, TexCoord};
    use embedded_raster::{Mat4, Pipeline, Shading, Specular, Vec3};
    use over_torus::Glass;

    struct Textured<'a>(
        Pipeline,
        &'a Mesh<'a>,
        TexturedMaterial<'a, Rgb565Texels<'a>, Blended>,
    );

    impl Glass for Textured<'_> {
        fn vertices(&self) -> usize {
            self.1.vertices.len()
        }

        fn draw(&self, opaque: bool, target: &mut impl MeshTarget<Rgb565>) {
            if opaque {
                let m = self.2;
                let mut material = TexturedMaterial::new(m.texture, m.shading);
                material.specular = m.specular;
                self.0.draw_textured_mesh(self.1, &material, target);
            } else {
                self.0.draw_textured_mesh(self.1, &self.2, target);
            }
        }

        fn draw_with(&self, target: &mut impl MeshTarget<Rgb565>, scratch: &mut [ProjectedVertex]) {
            self.0
                .draw_textured_mesh_with(self.1, &self.2, target, scratch)
                .unwrap();
        }

        fn bin<'a>(
            &'a self,
            layout: &BandLayout,
            scratch: &'a mut [ProjectedVertex],
            storage: &'a mut [BinEntry],
        ) -> over_torus::BinDraw<'a> {
            let mut bin =
                MeshBin::new_textured(&self.0, self.1, &self.2, layout, scratch, storage).unwrap();
            Box::new(move |band| bin.draw(band).unwrap())
        }
    }

    let front =
        over_torus::pipeline(Mat4::translation(Vec3::new(0.2, 0.1, 0.6)) * Mat4::scaling(0.7));
    // A sphere with texture coordinates from its positions (two turns around).
    let mut sphere = icosphere(1.0, 2);
    sphere.uvs = sphere
        .vertices
        .iter()
        .map(|p| {
            let [x, y, z] = embedded_raster::three_d::meshes::to_f64(*p);
            TexCoord::new(
                (z.atan2(x) / std::f64::consts::PI + 1.0) as f32,
                (y * 0.5 + 0.5) as f32,
            )
        })
        .collect();
    let sphere = sphere.as_mesh();
    let mut rng = Rng(0x7e47);
    let texels: Vec<u16> = (0..16 * 16).map(|_| rng.below(1 << 16) as u16).collect();
    let square = Texture::new(Rgb565Texels(&texels), 16, 16).unwrap();
    let odd = Texture::new(Rgb565Texels(&texels), 12, 16).unwrap();
    for (kind, texture) in [
        ("nearest", square),
        ("bilinear", square.with_filter(Filter::Bilinear)),
        ("12 wide", odd),
    ] {
        for shading in [
            Shading::Unlit,
            Shading::Flat,
            Shading::Gouraud,
            Shading::Quadratic,
        ] {
            for specular in [None, Some(Specular::new(0.6, 24))] {
                let mut glass = TexturedMaterial::new(&texture, shading);
                glass.specular = specular;
                let opacity = rng.below(255) as u8;
                let case = format!("{kind}, {shading:?}, {specular:?}, opacity {opacity}");
                let glass = Textured(front, &sphere, glass.with_opacity(opacity));
                over_torus::check(&glass, opacity, &case);
            }
        }
    }
}
