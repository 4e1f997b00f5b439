//! The integration tests, one binary: each file in this directory is a module (`alpha.rs` is
//! `alpha::`), the helpers they share (`tests/support/`) modules at the root. One binary builds
//! and links the crate's generic drawing code once at the test profile's opt-level 3, where a
//! binary per file did it 25 times (CI's host-test step took 10 minutes, most of it that).
//! `tests/mesh_limits.rs` stays a binary of its own: its global allocator counts the bytes each
//! thread asks for.
//!
//! A module whose tests need a feature is compiled only with it (`reference`: the f64 reference
//! rasterizer; `std`; `png`); `cargo test` without features runs the others. CI runs
//! `cargo test --all-features`. One file's tests: `cargo test --all-features --test all alpha::`.

// Helpers shared by the modules (each has `#![allow(dead_code)]`: a module uses some of them).
#[path = "../support/banded.rs"]
mod banded;
#[cfg(feature = "std")] // for `meshes`
#[path = "../support/colored_quad.rs"]
mod colored_quad;
#[path = "../support/probe.rs"]
mod probe;
#[path = "../support/raw_points.rs"]
mod raw_points;
#[cfg(feature = "std")] // `MeshData` (for `pipeline` and `textured_mesh`)
#[path = "../support/raycast.rs"]
mod raycast;
#[path = "../support/readable_target.rs"]
mod readable_target;
#[path = "../support/rng.rs"]
mod rng;
#[path = "../support/vec_f64.rs"]
mod vec_f64;

// The 3D bench scenes of the firmware (`textured3d` uses `crate::scene3d`), for `bands`.
#[allow(dead_code)]
#[path = "../../examples/common/scene3d.rs"]
mod scene3d;
#[allow(dead_code)]
#[path = "../../examples/common/textured3d.rs"]
mod textured3d;

#[cfg(feature = "reference")]
mod alpha;
#[cfg(feature = "reference")]
mod antialias;
mod any_rectangle;
mod bands;
mod camera;
#[cfg(feature = "reference")]
mod coverage_random;
mod display_driver;
mod draw_errors;
mod eg_placement;
mod errors;
mod firmware_checksum;
mod geometry;
#[cfg(feature = "reference")]
mod gradient;
mod imports;
#[cfg(feature = "reference")]
mod lights;
mod line;
#[cfg(feature = "std")]
mod meshes;
#[cfg(feature = "reference")]
mod perspective;
#[cfg(feature = "std")]
mod pipeline;
#[cfg(feature = "png")]
mod png_files;
mod polygon;
#[cfg(feature = "reference")]
mod proptest_raster;
mod same_pixels;
mod shading;
#[cfg(feature = "reference")]
mod specular;
mod stroke;
#[cfg(feature = "png")]
mod texture_convert;
#[cfg(feature = "reference")]
mod textured;
#[cfg(feature = "reference")]
mod textured_mesh;
#[cfg(feature = "reference")]
mod watertight;
#[cfg(feature = "std")] // `raycast`
mod wireframe;
