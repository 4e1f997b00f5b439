//! Band rendering of a list of meshes, shared by the lighting suites (tests/all/specular.rs,
//! tests/all/lights.rs): the frame put together from its bands.
#![allow(dead_code)]

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
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

/// Checks that `items` drawn into bands of every height from 1 to `size`'s, each band directly
/// (`ColorBand::draw_all`) and through a `TriangleBin`, give the rows of `whole` (the frame
/// drawn at once).
pub fn check_bands_2d<T: embedded_raster::band::BandDrawable<Rgb565>>(
    items: &[T],
    whole: &[Rgb565],
    size: Size,
) {
    use embedded_raster::band::{ColorBand, TriangleBin};
    for height in 1..=size.height {
        let layout = BandLayout::new(size, height).unwrap();
        let mut rows = vec![Rgb565::BLACK; (size.width * height) as usize];
        let mut binned = rows.clone();
        let mut storage = vec![BinEntry::EMPTY; (items.len() + 1) * layout.count() as usize];
        let mut bin = TriangleBin::new(&layout, items, &mut storage).unwrap();
        for index in 0..layout.count() {
            for (buffer, through_bin) in [(&mut rows, false), (&mut binned, true)] {
                let mut band = ColorBand::new(buffer, &layout, index).unwrap();
                band.clear(Rgb565::BLACK);
                if through_bin {
                    bin.draw(&mut band).unwrap();
                } else {
                    band.draw_all(items);
                }
                let start = (band.rect().top_left.y as u32 * size.width) as usize;
                let len = band.pixels().len();
                assert_eq!(
                    band.pixels(),
                    &whole[start..start + len],
                    "band {index} of {height} rows (bin: {through_bin})"
                );
            }
        }
    }
}
