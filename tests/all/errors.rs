//! Every public error type through `?` into `Box<dyn std::error::Error>` (and `+ Send + Sync`),
//! as a caller meets them: made by the crate's own functions, the message read back through the
//! box (issue #32, item 2). Each type's messages are unit-tested in its module.

use std::error::Error;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::band::{BandLayout, BinEntry, ColorBand, MeshBin};
use embedded_raster::texture::{Rgb565Texels, Texture};
use embedded_raster::three_d::ProjectedVertex;
use embedded_raster::{
    DepthTarget, GouraudTriangle, Light, Mat4, Material, Mesh, Pipeline, Shading, SliceFramebuffer,
    Vec3, Vertex,
};

type Boxed = Box<dyn Error + Send + Sync>;

/// `result`'s error through `?`: its message, and its source's.
fn through_box<T, E: Error + Send + Sync + 'static>(
    result: Result<T, E>,
) -> (String, Option<String>) {
    let boxed = || -> Result<T, Boxed> { Ok(result?) };
    let error = boxed().err().expect("an error");
    let source = error.source().map(|s| s.to_string());
    (error.to_string(), source)
}

static VERTICES: [Vec3; 3] = [
    Vec3::from_bits(0, 0, 0),
    Vec3::from_bits(1 << 16, 0, 0),
    Vec3::from_bits(0, 1 << 16, 0),
];

fn pipeline() -> Pipeline {
    let viewport = Rectangle::new(Point::zero(), Size::new(8, 8));
    Pipeline::new(Mat4::IDENTITY, Mat4::IDENTITY, viewport, Light::default())
}

#[test]
fn texture_error() {
    let texels = [0u16; 10];
    let (message, _) = through_box(Texture::new(Rgb565Texels(&texels), 4, 4));
    assert_eq!(
        message,
        "the texture's size needs 16 texels, the storage holds 10"
    );
    let (message, _) = through_box(Texture::new(Rgb565Texels(&texels), 0, 4));
    assert_eq!(
        message,
        "a texture of 0 × 4 texels: each side must be 1 to 32768"
    );
}

#[test]
fn framebuffer_error() {
    let mut pixels = [Rgb565::BLACK; 100];
    let (message, _) = through_box(SliceFramebuffer::new(&mut pixels, 320, 16));
    assert_eq!(
        message,
        "a colour buffer needs 5120 pixels (width · height), given 100"
    );
    let mut depth = [0u16; 99];
    let (message, _) = through_box(DepthTarget::new(&mut pixels, &mut depth, 10, 10));
    assert_eq!(
        message,
        "a depth buffer needs 100 entries (width · height), given 99"
    );
    let (message, _) = through_box(SliceFramebuffer::new(&mut pixels, 1, 1 << 31));
    assert!(message.starts_with("a framebuffer of 1 × 2147483648 pixels: each side must be"));
}

#[test]
fn band_error() {
    let (message, _) = through_box(BandLayout::new(Size::new(320, 240), 0));
    assert_eq!(message, "a band of 0 rows: a band needs at least 1 row");
    let layout = BandLayout::new(Size::new(32, 24), 8).unwrap();
    let mut short = [Rgb565::BLACK; 32 * 8 - 1];
    let (message, _) = through_box(ColorBand::new(&mut short, &layout, 0));
    assert_eq!(
        message,
        "a colour band buffer needs 256 pixels (width · rows), given 255"
    );
    let mut right = [Rgb565::BLACK; 32 * 8];
    let (message, _) = through_box(ColorBand::new(&mut right, &layout, 3));
    assert_eq!(
        message,
        "band 3 asked for, but the layout has 3 bands (indices below 3)"
    );
}

#[test]
fn scratch_too_small_and_as_a_band_errors_source() {
    let mesh = Mesh::new(&VERTICES, &[], &[[0, 1, 2]]);
    let (mut pixels, mut depth) = ([Rgb565::BLACK; 64], [0u16; 64]);
    let mut target = DepthTarget::new(&mut pixels, &mut depth, 8, 8).unwrap();
    let material = Material::new(Rgb565::RED, Shading::Gouraud);
    let mut scratch = [ProjectedVertex::default(); 2];
    let drawn = pipeline().draw_mesh_with(&mesh, &material, &mut target, &mut scratch);
    let (message, _) = through_box(drawn);
    assert_eq!(
        message,
        "a vertex scratch needs 3 entries (one per vertex of the mesh), given 2"
    );

    // The same, wrapped by the band renderer's bin: the scratch's error is its source.
    let layout = BandLayout::new(Size::new(8, 8), 4).unwrap();
    let mut storage = [BinEntry::EMPTY; 64];
    let pipeline = pipeline();
    let bin = MeshBin::new(
        &pipeline,
        &mesh,
        &material,
        &layout,
        &mut scratch,
        &mut storage,
    );
    let (message, source) = through_box(bin.map(|_| ()));
    assert_eq!(
        message,
        "a vertex scratch needs 3 entries (one per vertex of the mesh), given 2"
    );
    assert_eq!(source.as_deref(), Some(message.as_str()));
}

#[test]
fn mesh_error() {
    let mesh = Mesh::new(&VERTICES, &VERTICES[..2], &[[0, 1, 2]]);
    let (message, _) = through_box(mesh.validate());
    assert_eq!(
        message,
        "a mesh of 3 vertices needs 0 or 3 normals, given 2"
    );
}

#[test]
fn too_large() {
    let mut pixels = [Rgb565::BLACK; 64];
    let mut fb = SliceFramebuffer::new(&mut pixels, 8, 8).unwrap();
    let triangle = GouraudTriangle::new([
        Vertex::new(0.0, 0.0, Rgb565::RED),
        Vertex::new(3000.0, 0.0, Rgb565::GREEN),
        Vertex::new(0.0, 8.0, Rgb565::BLUE),
    ]);
    let (message, _) = through_box(triangle.draw_into_compact(&mut fb));
    assert!(message.starts_with("the compact path takes triangles under 2048 × 2048 pixels"));
}

#[cfg(feature = "std")]
#[test]
fn obj_error() {
    use embedded_raster::three_d::obj;

    let (message, _) = through_box(obj::parse("v 0 0 0\nv 1 0 0\nf 1 2 3\n"));
    assert_eq!(
        message,
        "line 3: `v` index 3 out of range: 2 `v` lines before it (indices 1 to 2 or -1 to -2)"
    );
}

#[cfg(feature = "png")]
#[test]
fn convert_error() {
    use embedded_raster::texture::convert::TextureData;

    let (message, _) = through_box(TextureData::from_png(b"not a png"));
    assert!(
        message.starts_with("not a PNG image this decoder reads: "),
        "{message}"
    );
}
