//! Band rendering of a list of meshes, shared by the lighting suites (tests/all/specular.rs,
//! tests/all/lights.rs): the frame put together from its bands.
#![allow(dead_code)]

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_raster::band::{BandLayout, BinEntry, DepthBand, MeshBin};
use embedded_raster::three_d::{Material, Mesh, Pipeline, ProjectedVertex};

/// The frame of `meshes` in the bands of `layout`: mode 0 `Pipeline::draw_mesh` into a band, 1
/// `draw_mesh_with`, 2 a `MeshBin`.
pub fn banded(
    layout: &BandLayout,
    pipeline: &Pipeline,
    meshes: &[(Mesh<'_>, Material<Rgb888>)],
    mode: u32,
) -> (Vec<Rgb888>, Vec<u16>) {
    let n = layout.buffer_len();
    let (mut colors, mut depth) = (vec![Rgb888::BLACK; n], vec![0u16; n]);
    let (mut all_colors, mut all_depth) = (Vec::new(), Vec::new());
    let mut scratch: Vec<Vec<ProjectedVertex>> = meshes
        .iter()
        .map(|m| vec![ProjectedVertex::EMPTY; m.0.vertices.len()])
        .collect();
    let mut band_scratch = vec![ProjectedVertex::EMPTY; 4096];
    let mut storage: Vec<Vec<BinEntry>> = meshes
        .iter()
        .map(|m| vec![BinEntry::EMPTY; layout.count() as usize + 2 * m.0.indices.len() + 64])
        .collect();
    let mut bins = Vec::new();
    if mode == 2 {
        for ((mesh, material), (scratch, storage)) in meshes
            .iter()
            .zip(scratch.iter_mut().zip(storage.iter_mut()))
        {
            bins.push(MeshBin::new(pipeline, mesh, material, layout, scratch, storage).unwrap());
        }
    }
    for index in 0..layout.count() {
        let mut band = DepthBand::new(&mut colors, &mut depth, layout, index).unwrap();
        band.clear(Rgb888::new(3, 60, 90));
        match mode {
            0 => meshes.iter().for_each(|(mesh, material)| {
                pipeline.draw_mesh(mesh, material, &mut band);
            }),
            1 => meshes.iter().for_each(|(mesh, material)| {
                pipeline
                    .draw_mesh_with(mesh, material, &mut band, &mut band_scratch)
                    .unwrap();
            }),
            _ => bins.iter_mut().for_each(|bin| bin.draw(&mut band).unwrap()),
        }
        all_colors.extend_from_slice(band.pixels());
        all_depth.extend_from_slice(band.depth());
    }
    (all_colors, all_depth)
}
