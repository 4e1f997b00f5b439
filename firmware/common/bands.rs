//! The 3D bench frame (`scene3d.rs`) drawn in bands, shared by the band firmware (`fw_band`,
//! `fw_band_microbit`) and their host runs (included with `#[path]`, next to `scene3d`): the
//! three ways a band can draw the mesh, and the checksums a display stand-in computes from the
//! bands as they arrive, which must equal those of the frame drawn whole.

use core::convert::Infallible;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::band::{
    BandError, BandLayout, BinEntry, Callback, ColorBands, DepthBand, DepthBands, MeshBin,
    RenderError,
};
use embedded_raster::three_d::{Material, Mesh, Pipeline, ProjectedVertex};

use crate::scene3d::{self, Model};

/// How the bands draw the mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// No bin, no memory per vertex: each band runs the pipeline over every face
    /// (`Pipeline::draw_mesh` into a band).
    EachFace,
    /// No bin: each band transforms every vertex once into the scratch
    /// (`Pipeline::draw_mesh_with` into a band).
    Scratch,
    /// A `MeshBin`: vertices and faces once per frame, each band fills its own faces.
    Bin,
}

impl Mode {
    /// Every mode, in report order.
    pub const ALL: [Mode; 3] = [Mode::EachFace, Mode::Scratch, Mode::Bin];

    /// The name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Mode::EachFace => "no bin, per face",
            Mode::Scratch => "no bin, scratch",
            Mode::Bin => "bin",
        }
    }
}

/// FNV-1a over little-endian 16-bit words, fed a band at a time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fnv(pub u32);

impl Fnv {
    /// The empty hash.
    pub const fn new() -> Self {
        Fnv(scene3d::FNV_START)
    }

    /// Hashes `words` on.
    pub fn words(&mut self, words: impl IntoIterator<Item = u16>) {
        self.0 = scene3d::fnv(self.0, words);
    }
}

/// What the display stand-in saw: the hashes of the frame's colours and of its depths
/// (row-major, each on its own), and the rows it received.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Seen {
    /// The colours' hash.
    pub colors: Fnv,
    /// The depths' hash.
    pub depths: Fnv,
    /// Rows received.
    pub rows: u32,
}

impl Seen {
    /// Nothing yet.
    pub const fn new() -> Self {
        Seen {
            colors: Fnv::new(),
            depths: Fnv::new(),
            rows: 0,
        }
    }

    /// The hashes of a frame drawn whole.
    pub fn of_frame(colors: &[Rgb565], depths: &[u16]) -> Self {
        let mut seen = Seen::new();
        seen.colors.words(colors.iter().map(|c| c.into_storage()));
        seen.depths.words(depths.iter().copied());
        seen.rows = scene3d::SIZE.1;
        seen
    }
}

/// The line the host and the firmware print for a frame, compared by `.ci/firmware.sh`.
pub struct BandLine(pub Model, pub Seen);

impl core::fmt::Display for BandLine {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let (w, h) = scene3d::SIZE;
        write!(
            f,
            "bands {} {}x{} rows={} colors={:#010x} depths={:#010x}",
            self.0.name(),
            w,
            h,
            self.1.rows,
            self.1.colors.0,
            self.1.depths.0
        )
    }
}

/// The buffers of a band renderer: colours, depths (one band each), the vertex scratch and the
/// bin's storage (for [`Mode::Scratch`] and [`Mode::Bin`]; may be empty otherwise).
pub struct Buffers<'a> {
    pub colors: &'a mut [Rgb565],
    pub depth: &'a mut [u16],
    pub scratch: &'a mut [ProjectedVertex],
    pub bin: &'a mut [BinEntry],
}

/// The frame of `model` (`mesh`) in bands of `rows`, drawn as `mode` says into `buffers` (their
/// first `320 · rows` colours and depths), each band handed to a display stand-in that hashes
/// its colours (as they would be sent) and its depths — unless `hash` is false (a timed frame:
/// the stand-in then takes the bands without reading them). Also returns the faces the bin kept
/// (0 without one).
pub fn render(
    model: Model,
    mesh: &Mesh<'_>,
    rows: u32,
    mode: Mode,
    buffers: Buffers<'_>,
    hash: bool,
) -> Result<(Seen, usize), RenderError<Infallible>> {
    let (w, h) = scene3d::SIZE;
    let layout = BandLayout::new(Size::new(w, h), rows)?;
    let n = layout.buffer_len();
    let colors = buffers.colors.get_mut(..n).unwrap_or(&mut []);
    let depth = buffers.depth.get_mut(..n).unwrap_or(&mut []);
    let mut bands = DepthBands::new(ColorBands::new(layout, colors)?, depth)?;
    let pipeline = scene3d::pipeline(model);
    let material = scene3d::MATERIAL;
    let (scratch, storage) = (buffers.scratch, buffers.bin);
    let mut bin = None;
    let mut scratch = Some(scratch);
    if mode == Mode::Bin {
        let s = scratch.take().unwrap_or(&mut []);
        bin = Some(MeshBin::new(
            &pipeline, mesh, &material, &layout, s, storage,
        )?);
    }
    let (mut colors, mut rows) = (Fnv::new(), 0);
    let mut depths = Fnv::new();
    {
        let mut output = Callback(|area: &Rectangle, pixels: &[Rgb565]| {
            if hash {
                colors.words(pixels.iter().map(|c| c.into_storage()));
            }
            core::hint::black_box(pixels);
            rows += area.size.height;
            Ok::<(), Infallible>(())
        });
        bands.render(&mut output, |band| {
            band.clear(scene3d::BACKGROUND);
            let drawn = match (mode, &mut bin, &mut scratch) {
                (Mode::EachFace, _, _) => {
                    each_face(band, &pipeline, mesh, &material);
                    Ok(())
                }
                (Mode::Scratch, _, Some(s)) => with_scratch(band, &pipeline, mesh, &material, s),
                (Mode::Bin, Some(bin), _) => binned(bin, band),
                _ => Ok(()),
            };
            if hash {
                depths.words(band.depth().iter().copied());
            }
            drawn
        })?;
    }
    let seen = Seen {
        colors,
        depths,
        rows,
    };
    Ok((seen, bin.map_or(0, |b| b.len())))
}

// Each mode's draw out of line: the stack a mode measures is its own (the micro:bit runs only
// the first, in 16 KiB).

#[inline(never)]
fn each_face(
    band: &mut DepthBand<'_, Rgb565>,
    pipeline: &Pipeline,
    mesh: &Mesh<'_>,
    material: &Material<Rgb565>,
) {
    pipeline.draw_mesh(mesh, material, band);
}

#[inline(never)]
fn with_scratch(
    band: &mut DepthBand<'_, Rgb565>,
    pipeline: &Pipeline,
    mesh: &Mesh<'_>,
    material: &Material<Rgb565>,
    scratch: &mut [ProjectedVertex],
) -> Result<(), BandError> {
    pipeline
        .draw_mesh_with(mesh, material, band, scratch)
        .map(|_| ())
        .map_err(BandError::from)
}

#[inline(never)]
fn binned(
    bin: &mut MeshBin<'_, Rgb565>,
    band: &mut DepthBand<'_, Rgb565>,
) -> Result<(), BandError> {
    bin.draw(band)
}
