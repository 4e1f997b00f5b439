//! `three_d::obj::parse` on arbitrary text: no panic; a mesh it returns is consistent (at least
//! one face, one normal per vertex, every index in range) and survives `to_obj` → `parse`
//! unchanged; it is then drawn by the pipeline (unit cube camera) without panic. `obj::read` of
//! the same bytes gives the same result.
#![no_main]

use embedded_graphics::pixelcolor::Gray8;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::three_d::{obj, DepthTarget, Light, Mat4, Material, Pipeline, Shading};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let parsed = obj::parse(text);
    match (obj::read(text.as_bytes()), &parsed) {
        (Ok(read), Ok(parsed)) => assert_eq!(&read, parsed, "read and parse differ"),
        (Err(obj::ReadError::Obj { error, .. }), Err(parsed)) => assert_eq!(&error, parsed),
        (read, parsed) => panic!("read: {read:?}, parse: {parsed:?}"),
    }
    let Ok(mesh) = parsed else {
        return;
    };
    assert!(!mesh.indices.is_empty(), "a mesh without faces");
    assert_eq!(
        mesh.normals.len(),
        mesh.vertices.len(),
        "one normal per vertex"
    );
    for face in &mesh.indices {
        assert!(
            face.iter().all(|&i| usize::from(i) < mesh.vertices.len()),
            "index out of range in {face:?}"
        );
    }
    let again = obj::parse(&obj::to_obj(&mesh)).expect("to_obj output parses");
    assert_eq!(again, mesh, "to_obj → parse changed the mesh");

    let (mut px, mut z) = ([Gray8::BLACK; 16 * 16], [0u16; 16 * 16]);
    let mut target = DepthTarget::new(&mut px, &mut z, 16, 16).unwrap();
    target.clear(Gray8::BLACK);
    let viewport = Rectangle::new(Point::zero(), Size::new(16, 16));
    let pipeline = Pipeline::new(Mat4::IDENTITY, Mat4::IDENTITY, viewport, Light::default());
    let stats = pipeline.draw_mesh(
        &mesh.as_mesh(),
        &Material::new(Gray8::WHITE, Shading::Quadratic),
        &mut target,
    );
    assert_eq!(
        (stats.drawn + stats.rejected + stats.culled + stats.degenerate + stats.invalid) as usize,
        mesh.indices.len()
    );
});
