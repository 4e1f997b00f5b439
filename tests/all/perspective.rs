//! Perspective-correct textured fills (`three_d::draw_textured`) against the independent f64
//! reference (`embedded_raster::reference::texture`).
//!
//! The texel coordinates are observed through *coordinate textures*: every texel has a colour of
//! its own, from which the pixel's texel index is read back. The reference gives the exact
//! perspective-correct texel coordinate of every covered pixel; a pixel agrees with it if its
//! texel is the reference's `nearest_texel`, or, where it differs, if the reference coordinate
//! lies within the tolerance of the texel the implementation picked.
//!
//! The tolerance follows the implementation's documented accuracy (src/three_d/texturing.rs,
//! "Accuracy"): the coordinates it computes (at the ends of chunks of up to 16 pixels of a span,
//! and at its last) are within `ε = δ·spread + 2⁻¹⁶` of the exact ones; between them they follow
//! chords, whose departure from the exact curve is computed here from the reference coordinates
//! themselves (at a grazing angle it reaches texels): the largest of any chunk length (`chords`).
//! So a pixel may be off the exact coordinate by `ε` plus what a chord may depart there. `ε` is
//! the documented bound, not a tighter measured one: probing the coordinates to 1/512 texel
//! (`probe`) shows the bound nearly reached (0.95 of it), though a texel boundary reveals much
//! less of it.
//!
//! `draw_textured_lit` (the same fill, each texel scaled by vertex light levels interpolated
//! perspective-correct) is checked channel by channel against `texel × level` at the reference
//! texel and level (`check_lit`).
//!
//! Run with `cargo test --features reference --test all perspective:: -- --nocapture` to see the
//! statistics.

use std::fmt::Write as _;

use embedded_graphics::pixelcolor::{Gray8, GrayColor, Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::reference::texture::{
    bilinear, boundary_distance, nearest, nearest_texel, perspective_attributes,
    perspective_texel_coords, scale, wrap, RefTexture, RefWrap,
};
use embedded_raster::reference::{covers, for_each_covered, interpolate};
use embedded_raster::texture::{
    Filter, Gray8Texels, Rgb565Texels, Rgb888Texels, TexelCoord, TexelSource, Texture, Wrap,
};
use embedded_raster::three_d::{
    draw_textured, draw_textured_lit, DepthTarget, Scalar, ScreenVertex, TexturedScreenVertex,
    DEPTH_CLEAR,
};
use embedded_raster::{Coord, GouraudColor};

use crate::probe;
use probe::unwrap_near;

use crate::rng;
use rng::Rng;

use crate::raw_points;
use raw_points::{sliver, Screen, MAX, MIN};

const W: i32 = 160;
const H: i32 = 120;
const N: usize = (W * H) as usize;

// ---------------------------------------------------------------------------------------------
// Triangles: the implementation's inputs, and the reference's view of exactly the same values
// ---------------------------------------------------------------------------------------------

/// A textured triangle as raw fixed-point bits: sub-pixel positions (256 a pixel), depths, `w`
/// and texel coordinates (both 16.16). The reference reads the same bits, so both sides see
/// exactly the same triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Tri {
    p: [(i32, i32); 3],
    depth: [u16; 3],
    w: [i32; 3],
    uv: [[i32; 2]; 3],
}

/// `x` in units of `2^-frac`, rounded and saturated to `i32`.
fn bits(x: f64, frac: u32) -> i32 {
    (x * f64::from(1u32 << frac))
        .round()
        .clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as i32
}

impl Tri {
    /// Positions in pixels, `w`, texel coordinates in texels, one depth for all vertices.
    fn new(p: [(f64, f64); 3], w: [f64; 3], uv: [[f64; 2]; 3], depth: u16) -> Tri {
        Tri {
            p: p.map(|(x, y)| (bits(x, 8), bits(y, 8))),
            depth: [depth; 3],
            w: w.map(|w| bits(w, 16)),
            uv: uv.map(|c| c.map(|c| bits(c, 16))),
        }
    }

    fn vertices(&self) -> [TexturedScreenVertex; 3] {
        core::array::from_fn(|k| TexturedScreenVertex {
            screen: ScreenVertex::new(
                Coord::from_bits(self.p[k].0),
                Coord::from_bits(self.p[k].1),
                self.depth[k],
            ),
            w: Scalar::from_bits(self.w[k]),
            u: TexelCoord::from_bits(self.uv[k][0]),
            v: TexelCoord::from_bits(self.uv[k][1]),
        })
    }

    /// The reference's `w`: the fixed-point value, a non-positive one taken as the smallest
    /// positive (as documented for `TexturedScreenVertex::w`).
    fn ref_w(&self) -> [f64; 3] {
        self.w.map(|w| f64::from(w.max(1)) / 65536.0)
    }

    fn ref_uv(&self) -> [[f64; 2]; 3] {
        self.uv.map(|c| c.map(|c| f64::from(c) / 65536.0))
    }

    /// Every covered pixel inside `clip` (already within the screen) with its exact
    /// perspective-correct texel coordinate.
    fn texels(&self, clip: &Clip) -> Vec<(i32, i32, [f64; 2])> {
        perspective_texel_coords(
            self.p,
            self.ref_uv(),
            self.ref_w(),
            clip.x0,
            clip.y0,
            clip.w,
            clip.h,
        )
    }

    /// The same pixels with affine texel coordinates (screen barycentrics: all `w` equal).
    fn affine_texels(&self, clip: &Clip) -> Vec<(i32, i32, [f64; 2])> {
        perspective_texel_coords(
            self.p,
            self.ref_uv(),
            [1.0; 3],
            clip.x0,
            clip.y0,
            clip.w,
            clip.h,
        )
    }

    /// The ratio of the largest vertex `w` to the smallest.
    fn w_ratio(&self) -> f64 {
        let w = self.ref_w();
        w.iter().copied().fold(0.0, f64::max) / w.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// The largest difference of the vertices' texel coordinates (either axis), in texels.
    fn spread(&self) -> f64 {
        let uv = self.ref_uv();
        (0..2)
            .map(|a| {
                let (lo, hi) = uv
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
                        (lo.min(c[a]), hi.max(c[a]))
                    });
                hi - lo
            })
            .fold(0.0, f64::max)
    }

    /// The documented error of the exactly computed texel coordinates (src/three_d/texturing.rs,
    /// "Accuracy"): `δ·spread + 2⁻¹⁶` with `δ = 1/q_min + 2⁻¹⁵`, `q_min = 32 640 / ρ`.
    fn documented_bound(&self) -> f64 {
        let delta = self.w_ratio() / 32_640.0 + 1.0 / 32_768.0;
        delta * self.spread() + 1.0 / 65_536.0
    }
}

/// A clip rectangle (the reference's: already intersected with the screen).
#[derive(Clone, Copy, Debug)]
struct Clip {
    x0: i32,
    y0: i32,
    w: u32,
    h: u32,
}

const SCREEN: Clip = Clip {
    x0: 0,
    y0: 0,
    w: W as u32,
    h: H as u32,
};

impl Clip {
    fn rectangle(&self) -> Rectangle {
        Rectangle::new(Point::new(self.x0, self.y0), Size::new(self.w, self.h))
    }

    /// The part of the rectangle on the screen (what the target clips to).
    fn on_screen(&self) -> Clip {
        let (x0, y0) = (self.x0.max(0), self.y0.max(0));
        let x1 = (i64::from(self.x0) + i64::from(self.w)).min(i64::from(W));
        let y1 = (i64::from(self.y0) + i64::from(self.h)).min(i64::from(H));
        Clip {
            x0,
            y0,
            w: (x1 - i64::from(x0)).max(0) as u32,
            h: (y1 - i64::from(y0)).max(0) as u32,
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Frames and coordinate textures
// ---------------------------------------------------------------------------------------------

/// A colour and depth buffer of the screen's size, depth cleared to empty.
struct Frame<C> {
    px: Vec<C>,
    z: Vec<u16>,
}

impl<C: GouraudColor> Frame<C> {
    fn new() -> Self {
        Frame {
            px: vec![C::from_channels([0; 3]); N],
            z: vec![DEPTH_CLEAR; N],
        }
    }

    fn draw<S: TexelSource>(&mut self, tri: &Tri, clip: &Rectangle, texture: &Texture<S>)
    where
        C: From<S::Color>,
    {
        let mut target = DepthTarget::new_uncleared(&mut self.px, &mut self.z, W as u32, H as u32)
            .expect("buffers of the screen's size");
        draw_textured(&mut target, clip, &tri.vertices(), texture);
    }

    fn written(&self, x: i32, y: i32) -> bool {
        self.z[(y * W + x) as usize] != DEPTH_CLEAR
    }

    fn at(&self, x: i32, y: i32) -> C {
        self.px[(y * W + x) as usize]
    }
}

/// A texture whose every texel has its own colour, so that a pixel tells which texel it took.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum CoordKind {
    /// Rgb888 texels `(i, j, 0)`: up to 256 × 256.
    Rgb888,
    /// Rgb565 texels: green `i` (6 bits), red `j mod 32`, blue `j / 32`: up to 64 × 64.
    Rgb565,
    /// Gray8 texels `i + 16·j`: up to 16 × 16.
    Gray8,
}

struct CoordTexture {
    kind: CoordKind,
    width: u32,
    height: u32,
    bytes: Vec<u8>,
    words: Vec<u16>,
    /// The same size for the reference samplers (its texels unused).
    reference: RefTexture,
}

impl CoordTexture {
    fn new(kind: CoordKind, width: u32, height: u32) -> Self {
        let ij = || (0..height).flat_map(move |j| (0..width).map(move |i| (i, j)));
        let (mut bytes, mut words) = (Vec::new(), Vec::new());
        match kind {
            CoordKind::Rgb888 => {
                assert!(width <= 256 && height <= 256);
                bytes = ij().flat_map(|(i, j)| [i as u8, j as u8, 0]).collect();
            }
            CoordKind::Rgb565 => {
                assert!(width <= 64 && height <= 64);
                words = ij()
                    .map(|(i, j)| ((j as u16 & 31) << 11) | ((i as u16) << 5) | (j as u16 >> 5))
                    .collect();
            }
            CoordKind::Gray8 => {
                assert!(width <= 16 && height <= 16);
                bytes = ij().map(|(i, j)| (i + 16 * j) as u8).collect();
            }
        }
        let reference = RefTexture::new(width, height, vec![[0.0; 3]; (width * height) as usize]);
        CoordTexture {
            kind,
            width,
            height,
            bytes,
            words,
            reference,
        }
    }

    /// Draws `tris` (in order, into one frame) with this texture, nearest filtering and wrap
    /// modes `wraps`; the texel index each written pixel took, row-major (`None`: not written).
    fn render(
        &self,
        tris: &[Tri],
        clip: &Rectangle,
        wraps: [RefWrap; 2],
    ) -> Vec<Option<(u32, u32)>> {
        let wraps = wraps.map(to_wrap);
        match self.kind {
            CoordKind::Rgb888 => {
                let t = Texture::new(Rgb888Texels(&self.bytes), self.width, self.height)
                    .unwrap()
                    .with_wrap(wraps[0], wraps[1]);
                decode(&render::<_, Rgb888>(tris, clip, &t), |c| {
                    (c.r().into(), c.g().into())
                })
            }
            CoordKind::Rgb565 => {
                let t = Texture::new(Rgb565Texels(&self.words), self.width, self.height)
                    .unwrap()
                    .with_wrap(wraps[0], wraps[1]);
                decode(&render::<_, Rgb565>(tris, clip, &t), |c| {
                    (c.g().into(), u32::from(c.r()) + 32 * u32::from(c.b()))
                })
            }
            CoordKind::Gray8 => {
                let t = Texture::new(Gray8Texels(&self.bytes), self.width, self.height)
                    .unwrap()
                    .with_wrap(wraps[0], wraps[1]);
                decode(&render::<_, Gray8>(tris, clip, &t), |c| {
                    (u32::from(c.luma() % 16), u32::from(c.luma() / 16))
                })
            }
        }
    }
}

fn to_wrap(w: RefWrap) -> Wrap {
    match w {
        RefWrap::Repeat => Wrap::Repeat,
        RefWrap::MirroredRepeat => Wrap::MirroredRepeat,
        RefWrap::Clamp => Wrap::Clamp,
    }
}

const WRAPS: [RefWrap; 3] = [RefWrap::Repeat, RefWrap::MirroredRepeat, RefWrap::Clamp];

fn render<S: TexelSource, C: GouraudColor + From<S::Color>>(
    tris: &[Tri],
    clip: &Rectangle,
    texture: &Texture<S>,
) -> Frame<C> {
    let mut frame = Frame::new();
    for tri in tris {
        frame.draw(tri, clip, texture);
    }
    frame
}

fn decode<C: GouraudColor>(
    frame: &Frame<C>,
    texel: impl Fn(C) -> (u32, u32),
) -> Vec<Option<(u32, u32)>> {
    (0..N)
        .map(|i| (frame.z[i] != DEPTH_CLEAR).then(|| texel(frame.px[i])))
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Comparing texel indices with the reference coordinates
// ---------------------------------------------------------------------------------------------

/// How far (in texels) the coordinate `c` lies from the nearest texel `[i, i + 1)` within
/// `window` texels of it that wraps to index `got` on an axis of `n` texels: 0 if `c` is in such a
/// texel, infinite if there is none.
fn axis_distance(c: f64, got: u32, n: u32, mode: RefWrap, window: f64) -> f64 {
    let (lo, hi) = ((c - window).floor() as i64, (c + window).floor() as i64);
    (lo..=hi)
        .filter(|&i| wrap(i, n, mode) == got)
        .map(|i| {
            let (a, b) = (i as f64, (i + 1) as f64);
            if c < a {
                a - c
            } else if c >= b {
                c - b
            } else {
                0.0
            }
        })
        .fold(f64::INFINITY, f64::min)
}

/// What the chords the implementation's attributes follow along a span may add to their error:
/// it computes them exactly at the ends of chunks of `L` pixels from a span's first (and at its
/// last; src/raster/perspective.rs, `Chunks`), `L` a power of two up to 16 chosen per span (so
/// that a light level's chords stay within a quarter of the target's finest channel step of the
/// exact curve), and steps linearly between. `texels` is a reference list (rows top to bottom,
/// each left to right, one span a row); the result holds, per pixel in the same order and on
/// each axis, the most a chord may depart from the exact value there — the largest departure
/// of the chords of any `L` (each through the reference values at its chunk's ends) — and what
/// stepping along it may add (`step_over`'s rounding: a
/// whole chunk's step is floored, up to 2⁻¹⁶ texel a pixel; a short last chunk's taken with a
/// rounded-up inverse, up to `|b − a|·2⁻¹⁶` a pixel more), the largest for any `L`.
fn chords(texels: &[(i32, i32, [f64; 2])]) -> Vec<([f64; 2], [f64; 2])> {
    let mut out = Vec::with_capacity(texels.len());
    let mut start = 0;
    while start < texels.len() {
        let y = texels[start].1;
        let mut end = start;
        while end + 1 < texels.len() && texels[end + 1].1 == y {
            end += 1;
        }
        for i in start..=end {
            let (mut off, mut steps) = ([0.0f64; 2], [0.0f64; 2]);
            for len in [1, 2, 4, 8, 16] {
                let a = start + (i - start) / len * len;
                let b = (a + len).min(end);
                let t = if b == a {
                    0.0
                } else {
                    (i - a) as f64 / (b - a) as f64
                };
                let (ca, cb, c) = (texels[a].2, texels[b].2, texels[i].2);
                let rounding = (i - a) as f64 / 65_536.0;
                for k in 0..2 {
                    off[k] = off[k].max((ca[k] + (cb[k] - ca[k]) * t - c[k]).abs());
                    steps[k] = steps[k].max(rounding * (1.0 + (cb[k] - ca[k]).abs()));
                }
            }
            out.push((off, steps));
        }
        start = end + 1;
    }
    out
}

/// A covered pixel of a scene: position, exact texel coordinate, how far the implementation's
/// coordinate may lie from the exact one besides the computed coordinates' own error (the
/// chord's departure and the steps' rounding, see [`chords`]), and the index of the triangle
/// that covers it.
#[derive(Clone, Copy, Debug)]
struct RefPixel {
    x: i32,
    y: i32,
    c: [f64; 2],
    chord: [f64; 2],
    /// The steps' rounding alone.
    steps: [f64; 2],
    tri: usize,
}

/// The reference pixels of `tris` (none covering a pixel another covers) inside `clip`.
fn reference_scene(tris: &[Tri], clip: &Clip) -> Vec<RefPixel> {
    let mut out = Vec::new();
    for (tri, t) in tris.iter().enumerate() {
        let texels = t.texels(clip);
        let chords = chords(&texels);
        out.extend(
            texels
                .into_iter()
                .zip(chords)
                .map(|((x, y, c), (off, steps))| RefPixel {
                    x,
                    y,
                    c,
                    chord: core::array::from_fn(|k| off[k] + steps[k]),
                    steps,
                    tri,
                }),
        );
    }
    out
}

/// Agreement of rendered texel indices with the reference coordinates over a scene.
#[derive(Debug, Default)]
struct Accuracy {
    /// Covered pixels compared.
    pixels: usize,
    /// Pixels whose texel is the reference's `nearest_texel`.
    same: usize,
    /// Pixels whose reference coordinate lies within `ε` of a texel boundary: those where either
    /// neighbour is acceptable.
    near_boundary: usize,
    /// Pixels where the chord is more than 1/16 texel off the exact coordinate (a wider
    /// tolerance).
    off_chord: usize,
    /// The largest distance from a reference coordinate to the texel taken, in texels.
    max_error: f64,
    /// The same where the chord is within 2⁻¹⁰ texel of the exact coordinates.
    max_error_on_chord: f64,
    /// The largest of that distance beyond the chord's deviation from the exact coordinate.
    max_excess: f64,
    /// The largest chord deviation seen.
    max_chord: f64,
    /// Pixels beyond the tolerance (the first few described in `report`).
    failures: usize,
    report: String,
}

impl Accuracy {
    /// One pixel: texel `got` against the reference pixel `r` on a texture of `texture`'s size
    /// with `wraps`; accepted if, on each axis, the exact coordinate lies within `eps` plus the
    /// chord's deviation of the texel taken.
    fn pixel(
        &mut self,
        r: &RefPixel,
        got: (u32, u32),
        texture: &RefTexture,
        wraps: [RefWrap; 2],
        eps: f64,
        context: &dyn Fn() -> String,
    ) {
        self.pixels += 1;
        let c = r.c;
        let want = nearest_texel(texture, wraps, c[0], c[1]);
        if got == want {
            self.same += 1;
        }
        let tol = r.chord.map(|d| d + eps);
        if boundary_distance(c[0], c[1]) < eps {
            self.near_boundary += 1;
        }
        if r.chord[0].max(r.chord[1]) > 1.0 / 16.0 {
            self.off_chord += 1;
        }
        let window = tol[0].max(tol[1]) + 2.0;
        let err = [
            axis_distance(c[0], got.0, texture.width, wraps[0], window),
            axis_distance(c[1], got.1, texture.height, wraps[1], window),
        ];
        let worst = err[0].max(err[1]);
        self.max_error = self.max_error.max(worst);
        if r.chord[0].max(r.chord[1]) < 1.0 / 1024.0 {
            self.max_error_on_chord = self.max_error_on_chord.max(worst);
        }
        self.max_chord = self.max_chord.max(r.chord[0]).max(r.chord[1]);
        let excess = (err[0] - r.chord[0]).max(err[1] - r.chord[1]).max(0.0);
        self.max_excess = self.max_excess.max(excess);
        if excess > eps {
            self.failures += 1;
            if self.failures <= 5 {
                let _ = writeln!(
                    self.report,
                    "  pixel ({}, {}): texel {got:?}, reference coordinate {c:?} → texel {want:?}, \
                     chord off by {:?}; {}",
                    r.x,
                    r.y,
                    r.chord,
                    context()
                );
            }
        }
    }

    fn add(&mut self, other: &Accuracy) {
        self.pixels += other.pixels;
        self.same += other.same;
        self.near_boundary += other.near_boundary;
        self.off_chord += other.off_chord;
        self.max_error = self.max_error.max(other.max_error);
        self.max_error_on_chord = self.max_error_on_chord.max(other.max_error_on_chord);
        self.max_excess = self.max_excess.max(other.max_excess);
        self.max_chord = self.max_chord.max(other.max_chord);
        self.failures += other.failures;
        if self.report.lines().count() < 5 {
            self.report.push_str(&other.report);
        }
    }

    fn summary(&self, name: &str) -> String {
        format!(
            "{name}: {} pixels, {} on the reference's texel, {} within ε of a boundary, {} \
             where the chord is over 1/16 texel off; coordinate error max {:.5} texel ({:.5} \
             where the chord is exact), {:.5} beyond the chord (chord deviation up to {:.3})",
            self.pixels,
            self.same,
            self.near_boundary,
            self.off_chord,
            self.max_error,
            self.max_error_on_chord,
            self.max_excess,
            self.max_chord
        )
    }

    /// Asserts every pixel within the tolerance, at least `min_pixels` compared, and at most
    /// `max_near` of them near a boundary.
    fn assert_within(&self, name: &str, min_pixels: usize, max_near: f64) {
        assert_eq!(
            self.failures,
            0,
            "{}\n{} pixels off the reference:\n{}",
            self.summary(name),
            self.failures,
            self.report
        );
        assert!(self.pixels >= min_pixels, "{}", self.summary(name));
        assert!(
            (self.near_boundary as f64) <= max_near * self.pixels as f64,
            "{}",
            self.summary(name)
        );
    }
}

/// Draws `tris` (not overlapping) into one frame with `texture` (nearest, `wraps`) clipped to
/// `clip`; asserts that exactly the reference's covered pixels are written, and compares each
/// with its reference coordinate.
fn check_nearest(
    tris: &[Tri],
    clip: &Clip,
    texture: &CoordTexture,
    wraps: [RefWrap; 2],
    eps: f64,
) -> Accuracy {
    let got = texture.render(tris, &clip.rectangle(), wraps);
    let want = reference_scene(tris, &clip.on_screen());
    let context = |r: &RefPixel| {
        format!(
            "{:?} {}×{} {wraps:?}, clip {clip:?}, {:?}",
            texture.kind, texture.width, texture.height, tris[r.tri]
        )
    };
    let mut expected = vec![false; N];
    let mut acc = Accuracy::default();
    for r in &want {
        let i = (r.y * W + r.x) as usize;
        assert!(!expected[i], "pixel ({}, {}) covered twice", r.x, r.y);
        expected[i] = true;
        let got = got[i].unwrap_or_else(|| {
            panic!(
                "covered pixel ({}, {}) not written: {}",
                r.x,
                r.y,
                context(r)
            )
        });
        acc.pixel(r, got, &texture.reference, wraps, eps, &|| context(r));
    }
    for (i, g) in got.iter().enumerate() {
        assert!(
            g.is_none() || expected[i],
            "pixel ({}, {}) written, not covered: {tris:?}, clip {clip:?}",
            i as i32 % W,
            i as i32 / W
        );
    }
    acc
}

// ---------------------------------------------------------------------------------------------
// Scene (a): a floor seen at a grazing angle
// ---------------------------------------------------------------------------------------------

/// A pinhole camera: its position and axes, the focal length in pixels; the screen centre is the
/// principal point.
struct Camera {
    eye: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    forward: [f64; 3],
    focal: f64,
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn axpy(a: f64, x: [f64; 3], b: f64, y: [f64; 3]) -> [f64; 3] {
    core::array::from_fn(|k| a * x[k] + b * y[k])
}

impl Camera {
    /// A camera at `eye` looking along `+z`, pitched down by `pitch` degrees, then rolled by
    /// `roll` degrees about its view direction.
    fn new(eye: [f64; 3], pitch: f64, roll: f64, focal: f64) -> Camera {
        let (ps, pc) = pitch.to_radians().sin_cos();
        let (rs, rc) = roll.to_radians().sin_cos();
        let (forward, right, up) = ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let (forward, up) = (axpy(pc, forward, -ps, up), axpy(pc, up, ps, forward));
        let (right, up) = (axpy(rc, right, rs, up), axpy(rc, up, -rs, right));
        Camera {
            eye,
            right,
            up,
            forward,
            focal,
        }
    }

    /// Screen position (pixels, y down) and `w` (view depth) of a world point.
    fn project(&self, p: [f64; 3]) -> ((f64, f64), f64) {
        let d = axpy(1.0, p, -1.0, self.eye);
        let (x, y, z) = (dot(d, self.right), dot(d, self.up), dot(d, self.forward));
        assert!(z > 0.1, "behind the camera");
        let (cx, cy) = (f64::from(W) / 2.0, f64::from(H) / 2.0);
        ((cx + self.focal * x / z, cy - self.focal * y / z), z)
    }
}

/// A floor: the quad `[-x1, x1] × [z0, z1]` of the plane `y = 0` seen by `camera`.
struct Floor {
    camera: Camera,
    x1: f64,
    z0: f64,
    z1: f64,
    /// Texels a unit.
    scale: f64,
    /// The texture's axes turned by this many degrees from the world's.
    turn: f64,
}

impl Floor {
    /// The quad as two triangles sharing the edge from corner 0 to corner 2.
    fn triangles(&self) -> [Tri; 2] {
        let corners = [
            [-self.x1, self.z0],
            [self.x1, self.z0],
            [self.x1, self.z1],
            [-self.x1, self.z1],
        ];
        let (s, c) = self.turn.to_radians().sin_cos();
        let v = corners.map(|[x, z]| {
            let (p, w) = self.camera.project([x, 0.0, z]);
            let (a, b) = (x + self.x1, z - self.z0);
            let uv = [(a * c + b * s) * self.scale, (b * c - a * s) * self.scale];
            (p, w, uv)
        });
        let tri = |a: usize, b: usize, c: usize| {
            Tri::new(
                [v[a].0, v[b].0, v[c].0],
                [v[a].1, v[b].1, v[c].1],
                [v[a].2, v[b].2, v[c].2],
                1000,
            )
        };
        [tri(0, 1, 2), tri(0, 2, 3)]
    }
}

/// The floors of scene (a): eye 1 above the plane, 110 px focal length (72° across 160 px).
/// Rolled: `w` changes along the rows, so the spans' chords are exercised; level: `w` is
/// constant along each row, the chords exact and the computed coordinates alone are seen.
fn floors() -> [(&'static str, Floor); 2] {
    [
        (
            "rolled floor",
            Floor {
                camera: Camera::new([0.0, 1.0, 0.0], 12.0, 20.0, 110.0),
                x1: 10.0,
                z0: 0.6,
                z1: 12.0,
                scale: 6.4,
                turn: 30.0,
            },
        ),
        (
            "level floor",
            Floor {
                camera: Camera::new([0.0, 1.0, 0.0], 6.0, 0.0, 110.0),
                x1: 12.0,
                z0: 0.8,
                z1: 14.0,
                scale: 6.0,
                turn: 20.0,
            },
        ),
    ]
}

/// Nearest filtering on a floor quad seen at a grazing angle, `w` in a ratio of about 1:15
/// across each triangle and texel coordinates over 2–3 repeats of a 64 × 64 Rgb565 texture (and
/// of a 256 × 256 Rgb888 one): exactly the reference's pixels are written, each within `ε`
/// (the documented `δ·spread + 2⁻¹⁶`: 0.072 and 0.083 texel) plus the chord's deviation of
/// the reference coordinate; a pixel within `ε` of a texel boundary is ambiguous (at most 40 %
/// of them at this `ε`).
///
/// The same comparison of affine texel coordinates (the reference with equal `w`) with the
/// perspective-correct ones fails at most pixels: the scene tells the two apart.
#[test]
fn floor_nearest_matches_the_reference() {
    let mut total = Accuracy::default();
    for (name, floor) in floors() {
        let tris = floor.triangles();
        let bound = tris[0].documented_bound().max(tris[1].documented_bound());
        let eps = bound;
        let wraps = [RefWrap::Repeat; 2];
        for texture in [
            CoordTexture::new(CoordKind::Rgb565, 64, 64),
            CoordTexture::new(CoordKind::Rgb888, 256, 256),
        ] {
            let acc = check_nearest(&tris, &SCREEN, &texture, wraps, eps);
            println!(
                "{} (documented {bound:.4})",
                acc.summary(&format!("{name}, {:?}", texture.kind))
            );
            acc.assert_within(name, 8_000, 0.4);
            total.add(&acc);

            // Affine coordinates, the same tolerance: most pixels fail.
            let mut affine = Accuracy::default();
            for (k, tri) in tris.iter().enumerate() {
                let exact = reference_scene(&[*tri], &SCREEN);
                let flat = tri.affine_texels(&SCREEN);
                assert_eq!(exact.len(), flat.len());
                for (r, (_, _, a)) in exact.iter().zip(flat) {
                    let got = nearest_texel(&texture.reference, wraps, a[0], a[1]);
                    affine.pixel(r, got, &texture.reference, wraps, eps, &|| {
                        format!("tri {k}")
                    });
                }
            }
            println!(
                "  affine coordinates: {} of {} pixels off",
                affine.failures, affine.pixels
            );
            assert!(
                affine.failures * 4 > affine.pixels * 3,
                "{name}: affine mapping too close to perspective: {}",
                affine.summary("affine")
            );
        }
    }
    println!("{}", total.summary("floors"));
}

// ---------------------------------------------------------------------------------------------
// Scene (b): random triangles
// ---------------------------------------------------------------------------------------------

impl Rng {
    /// Log-uniform in `[lo, hi)`.
    fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.unit()).exp()
    }

    /// A textured triangle around the screen: 2 to ~180 pixels across, `w` from 0.5 to 10 (one
    /// in three with the extremes 0.5 and 10 both), texel coordinates spanning up to 64 texels
    /// anywhere in ±300.
    fn textured(&mut self) -> Tri {
        let c = (
            self.range_f64(-20.0, f64::from(W) + 20.0),
            self.range_f64(-20.0, f64::from(H) + 20.0),
        );
        let r = 2f64.powf(self.range_f64(1.0, 7.5));
        let p = [(); 3].map(|_| (c.0 + self.range_f64(-r, r), c.1 + self.range_f64(-r, r)));
        let mut w = [(); 3].map(|_| self.log_uniform(0.5, 10.0));
        if self.chance(3) {
            let k = self.below(3) as usize;
            w[k] = 0.5;
            w[(k + 1 + self.below(2) as usize) % 3] = 10.0;
        }
        let spread = self.range_f64(1.0, 64.0);
        let o = (self.range_f64(-300.0, 300.0), self.range_f64(-300.0, 300.0));
        let uv = [(); 3].map(|_| {
            [
                o.0 + self.range_f64(0.0, spread),
                o.1 + self.range_f64(0.0, spread),
            ]
        });
        let mut t = Tri::new(p, w, uv, 0);
        t.depth = [(); 3].map(|_| self.range(0, 60_000) as u16);
        t
    }

    /// The screen, or one time in four a random rectangle (partly off-screen, maybe empty).
    fn clip(&mut self) -> Clip {
        if self.chance(4) {
            Clip {
                x0: self.range(-40, i64::from(W)) as i32,
                y0: self.range(-40, i64::from(H)) as i32,
                w: self.range(0, 200) as u32,
                h: self.range(0, 160) as u32,
            }
        } else {
            SCREEN
        }
    }
}

/// The coordinate textures of the random scenes: power-of-two and other sizes, each source.
fn coordinate_textures() -> Vec<CoordTexture> {
    vec![
        CoordTexture::new(CoordKind::Rgb888, 256, 256),
        CoordTexture::new(CoordKind::Rgb565, 64, 32),
        CoordTexture::new(CoordKind::Rgb888, 24, 17),
        CoordTexture::new(CoordKind::Gray8, 16, 16),
        CoordTexture::new(CoordKind::Gray8, 12, 16),
    ]
}

/// Nearest filtering of random triangles whose vertex `w` differ up to 1:20, on textures of
/// power-of-two and other sizes with every wrap mode on each axis: exactly the reference's
/// pixels are written, each within the documented error of the computed coordinates
/// (`δ·spread + 2⁻¹⁶`, at most 0.041 texel here) plus the chord's deviation; at most a fifth
/// of them within `ε` of a texel boundary.
#[test]
fn random_triangles_nearest_match_the_reference() {
    let mut rng = Rng(0x9e47_5e01);
    let mut total = Accuracy::default();
    let mut worst_ratio = 0.0f64;
    let mut triangles = 0;
    for texture in coordinate_textures() {
        for wx in WRAPS {
            for wy in WRAPS {
                let wraps = [wx, wy];
                for _ in 0..40 {
                    let tri = rng.textured();
                    let clip = rng.clip();
                    let eps = tri.documented_bound();
                    let acc = check_nearest(&[tri], &clip, &texture, wraps, eps);
                    if acc.max_excess / tri.documented_bound() > 0.9 {
                        println!("RATIO {} doc {} excess {} ratio {} spread {} {:?} {:?} {wraps:?} {tri:?}", acc.max_excess / tri.documented_bound(), tri.documented_bound(), acc.max_excess, tri.w_ratio(), tri.spread(), texture.kind, (texture.width, texture.height));
                    }
                    worst_ratio = worst_ratio.max(acc.max_excess / eps);
                    total.add(&acc);
                    triangles += 1;
                }
            }
        }
    }
    println!(
        "{} triangles; {}; worst excess / documented {worst_ratio:.3}",
        triangles,
        total.summary("random")
    );
    total.assert_within("random", 300_000, 0.2);
}

// ---------------------------------------------------------------------------------------------
// Coverage
// ---------------------------------------------------------------------------------------------

const RAW: Screen = Screen::new(W as i64, H as i64);

const KINDS: u64 = 10;

/// Raw vertex positions of a random kind: sub-pixel, small, screen-sized, ten screens, any
/// magnitude, far off-screen, slivers, collinear, snapped, axis-aligned.
fn positions(rng: &mut Rng, kind: u64) -> [(i32, i32); 3] {
    let v: [(i64, i64); 3] = match kind {
        0 => RAW.cluster(rng, 2, (1, 300)),
        1 => RAW.cluster(rng, 4, (256, 256 * 24)),
        2 => [(); 3].map(|_| RAW.point(rng, 40)),
        3 => [(); 3].map(|_| RAW.point(rng, i64::from(W) * 10)),
        4 => [(); 3].map(|_| (rng.any_scale(), rng.any_scale())),
        // Far off-screen: a triangle of any size a million pixels away, either direction.
        5 => {
            let d = (rng.range(-1, 1) << 28, rng.range(-1, 1) << 28);
            [(); 3].map(|_| {
                let p = RAW.point(rng, 100);
                (p.0 + d.0, p.1 + d.1)
            })
        }
        // Slivers: c near the line through a and b.
        6 => {
            let a = RAW.point(rng, 8);
            sliver(rng, a, 24)
        }
        // Exactly collinear, or repeated vertices.
        7 => {
            let a = RAW.point(rng, 8);
            let dir = (rng.range(-64, 64), rng.range(-64, 64));
            let (s, t) = (rng.range(-4096, 4096), rng.range(-4096, 4096));
            if rng.chance(3) {
                [a, a, (a.0 + s * dir.0, a.1 + s * dir.1)]
            } else {
                [
                    a,
                    (a.0 + s * dir.0, a.1 + s * dir.1),
                    (a.0 + t * dir.0, a.1 + t * dir.1),
                ]
            }
        }
        8 => [(); 3].map(|_| RAW.snapped_point(rng, 6)),
        _ => {
            let (p, q) = (RAW.snapped_point(rng, 6), RAW.snapped_point(rng, 6));
            [p, (q.0, p.1), (p.0, q.1)]
        }
    };
    v.map(|(x, y)| (x.clamp(MIN, MAX) as i32, y.clamp(MIN, MAX) as i32))
}

/// The reference's covered pixels of `p` inside `clip` (on the screen), as a row-major mask.
fn coverage_mask(p: [(i32, i32); 3], clip: &Clip) -> Vec<bool> {
    let mut mask = vec![false; N];
    let (x1, y1) = (clip.x0 + clip.w as i32, clip.y0 + clip.h as i32);
    for_each_covered(p, clip.x0, clip.y0, x1, y1, |x, y| {
        mask[(y * W + x) as usize] = true
    });
    mask
}

/// Coverage: triangles of every kind (sub-pixel to the full raw range, slivers, collinear,
/// snapped, far off-screen), random `w` and texel coordinates, all depths equal, into a cleared
/// z-buffer: exactly the reference's covered pixels inside the clip are written (depth and
/// colour both; the frame starts in a colour no texel has).
#[test]
fn coverage_is_the_reference_coverage() {
    let mut rng = Rng(0x9e47_5e02);
    let bytes: Vec<u8> = (0..256 * 256)
        .flat_map(|k| [k as u8, (k >> 8) as u8, 0])
        .collect();
    let texture = Texture::new(Rgb888Texels(&bytes), 256, 256).unwrap();
    let sentinel = Rgb888::new(1, 2, 3);
    let (mut triangles, mut pixels, mut empty) = (0, 0, 0);
    for n in 0..3_000 {
        let p = positions(&mut rng, n % KINDS);
        let mut tri = rng.textured();
        tri.p = p;
        tri.depth = [500; 3];
        let clip = rng.clip();
        let mut frame = Frame::<Rgb888>::new();
        frame.px.fill(sentinel);
        frame.draw(&tri, &clip.rectangle(), &texture);
        let mask = coverage_mask(p, &clip.on_screen());
        for (i, &covered) in mask.iter().enumerate() {
            let (x, y) = (i as i32 % W, i as i32 / W);
            let written = frame.written(x, y);
            assert_eq!(
                written, covered,
                "pixel ({x}, {y}): written {written}, covered {covered}: {tri:?}, clip {clip:?}"
            );
            assert_eq!(frame.at(x, y) != sentinel, written, "({x}, {y}): {tri:?}");
            pixels += usize::from(covered);
        }
        triangles += 1;
        empty += usize::from(!mask.contains(&true));
    }
    println!("coverage: {triangles} triangles ({empty} empty), {pixels} covered pixels");
    assert!(pixels > 1_000_000 && empty < triangles * 4 / 5);
}

// ---------------------------------------------------------------------------------------------
// Bilinear filtering
// ---------------------------------------------------------------------------------------------

/// A smooth texture (neighbouring texels differ by a few LSB, across the repeat seams too):
/// periodic sums of sines, Rgb888 or Gray8.
struct SmoothTexture {
    gray: bool,
    width: u32,
    height: u32,
    bytes: Vec<u8>,
    reference: RefTexture,
}

impl SmoothTexture {
    fn new(gray: bool, width: u32, height: u32) -> Self {
        let tau = std::f64::consts::TAU;
        let (fw, fh) = (f64::from(width), f64::from(height));
        let mut channels = Vec::new();
        for j in 0..height {
            for i in 0..width {
                let (a, b) = (tau * f64::from(i) / fw, tau * f64::from(j) / fh);
                // Amplitudes in proportion to the size: about the same steps for any size.
                let (x, y) = (fw / 64.0, fh / 64.0);
                let c = [
                    128.0 + 30.0 * x * a.sin() + 20.0 * y * b.cos(),
                    120.0 + 15.0 * x * a.sin() + 15.0 * y * b.sin(),
                    100.0 + 20.0 * y * b.sin() - 15.0 * x * a.cos(),
                ];
                channels.push(c.map(f64::round));
            }
        }
        let bytes = if gray {
            channels.iter().map(|c| c[0] as u8).collect()
        } else {
            channels.iter().flat_map(|c| c.map(|v| v as u8)).collect()
        };
        let texels = if gray {
            channels.iter().map(|c| [c[0], 0.0, 0.0]).collect()
        } else {
            channels
        };
        SmoothTexture {
            gray,
            width,
            height,
            bytes,
            reference: RefTexture::new(width, height, texels),
        }
    }

    /// The largest difference of neighbouring texels (any channel, either axis, the neighbours
    /// across the edges as `wraps` make them).
    fn max_step(&self, wraps: [RefWrap; 2]) -> f64 {
        let t = &self.reference;
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        let mut d = 0.0f64;
        for j in -1..=h {
            for i in -1..=w {
                let at = |i: i64, j: i64| {
                    t.texel(wrap(i, t.width, wraps[0]), wrap(j, t.height, wraps[1]))
                };
                let (c, r, b) = (at(i, j), at(i + 1, j), at(i, j + 1));
                for k in 0..3 {
                    d = d.max((c[k] - r[k]).abs()).max((c[k] - b[k]).abs());
                }
            }
        }
        d
    }

    /// Draws `tris` with bilinear filtering and `wraps`: each written pixel's channels.
    fn render(&self, tris: &[Tri], clip: &Rectangle, wraps: [RefWrap; 2]) -> Vec<Option<[u8; 3]>> {
        let wraps = wraps.map(to_wrap);
        fn channels<C: GouraudColor>(frame: &Frame<C>) -> Vec<Option<[u8; 3]>> {
            (0..N)
                .map(|i| (frame.z[i] != DEPTH_CLEAR).then(|| frame.px[i].channels()))
                .collect()
        }
        if self.gray {
            let t = Texture::new(Gray8Texels(&self.bytes), self.width, self.height)
                .unwrap()
                .with_wrap(wraps[0], wraps[1])
                .with_filter(Filter::Bilinear);
            channels(&render::<_, Gray8>(tris, clip, &t))
        } else {
            let t = Texture::new(Rgb888Texels(&self.bytes), self.width, self.height)
                .unwrap()
                .with_wrap(wraps[0], wraps[1])
                .with_filter(Filter::Bilinear);
            channels(&render::<_, Rgb888>(tris, clip, &t))
        }
    }
}

/// Bilinear agreement over a scene.
#[derive(Debug, Default)]
struct Blend {
    pixels: usize,
    /// The largest channel difference from the reference blend, in LSB.
    max_diff: f64,
    /// The same where the chord is within 1/16 texel of the exact coordinates.
    max_diff_on_chord: f64,
    /// The largest difference beyond the tolerance's 1 LSB, relative to its coordinate part.
    max_relative: f64,
    failures: usize,
    report: String,
}

/// Draws `tris` (not overlapping) with bilinear filtering and compares every pixel with the
/// reference blend at the reference coordinate: within 1 LSB (the weights' rounding, under
/// half an LSB with a bit more than the channel's, and the blend's) plus `D·(tol_x + tol_y)`,
/// `D` the largest neighbour difference and `tol` the
/// coordinate tolerance of nearest filtering (`eps` plus the chord's deviation) — the blend
/// changes by at most `D` a texel along either axis.
fn check_bilinear(
    tris: &[Tri],
    clip: &Clip,
    texture: &SmoothTexture,
    wraps: [RefWrap; 2],
    eps: f64,
    blend: &mut Blend,
) {
    let got = texture.render(tris, &clip.rectangle(), wraps);
    let d = texture.max_step(wraps);
    let channels = if texture.gray { 1 } else { 3 };
    let mut written = got.iter().filter(|g| g.is_some()).count();
    for r in reference_scene(tris, &clip.on_screen()) {
        let g = got[(r.y * W + r.x) as usize].expect("covered pixel written");
        written -= 1;
        let want = bilinear(&texture.reference, wraps, r.c[0], r.c[1]);
        let coordinate = d * (2.0 * eps + r.chord[0] + r.chord[1]);
        blend.pixels += 1;
        for k in 0..channels {
            let diff = (f64::from(g[k]) - want[k]).abs();
            blend.max_diff = blend.max_diff.max(diff);
            if r.chord[0].max(r.chord[1]) < 1.0 / 16.0 {
                blend.max_diff_on_chord = blend.max_diff_on_chord.max(diff);
            }
            blend.max_relative = blend.max_relative.max((diff - 1.0).max(0.0) / coordinate);
            if diff > 1.0 + coordinate + 1e-9 {
                blend.failures += 1;
                if blend.failures <= 5 {
                    let _ = writeln!(
                        blend.report,
                        "  pixel ({}, {}) channel {k}: {} vs reference {:.3} at {:?} (chord off \
                         by {:?}, D = {d}); {:?}",
                        r.x, r.y, g[k], want[k], r.c, r.chord, tris[r.tri]
                    );
                }
            }
        }
    }
    assert_eq!(written, 0, "pixels written outside the coverage: {tris:?}");
}

/// Bilinear filtering of a smooth texture (neighbours at most 5 LSB apart) on the floors and on
/// random triangles (ratios up to 1:20, every wrap mode, 64 × 64 Rgb888 and 24 × 17 Gray8):
/// every channel within 1 LSB + `D·(tol_x + tol_y)` of the reference blend at the reference
/// coordinate (see `check_bilinear`).
#[test]
fn bilinear_matches_the_reference_blend() {
    let mut blend = Blend::default();
    let rgb = SmoothTexture::new(false, 64, 64);
    let gray = SmoothTexture::new(true, 24, 17);
    for t in [&rgb, &gray] {
        for wx in WRAPS {
            for wy in WRAPS {
                let d = t.max_step([wx, wy]);
                assert!((2.0..=5.0).contains(&d), "{d}");
            }
        }
    }
    for (_, floor) in floors() {
        let tris = floor.triangles();
        let eps = tris[0].documented_bound().max(tris[1].documented_bound());
        check_bilinear(&tris, &SCREEN, &rgb, [RefWrap::Repeat; 2], eps, &mut blend);
    }
    let mut rng = Rng(0x9e47_5e03);
    for n in 0..400 {
        let tri = rng.textured();
        let clip = rng.clip();
        let wraps = [WRAPS[n % 3], WRAPS[n / 3 % 3]];
        let texture = if n % 2 == 0 { &rgb } else { &gray };
        let eps = tri.documented_bound();
        check_bilinear(&[tri], &clip, texture, wraps, eps, &mut blend);
    }
    println!(
        "bilinear: {} pixels, channel difference max {:.3} LSB ({:.3} where the chord is within \
         1/16 texel), beyond 1 LSB at most {:.3} of the coordinate allowance",
        blend.pixels, blend.max_diff, blend.max_diff_on_chord, blend.max_relative
    );
    assert_eq!(
        blend.failures, 0,
        "{} pixels off:\n{}",
        blend.failures, blend.report
    );
    assert!(blend.pixels > 150_000);
}

// ---------------------------------------------------------------------------------------------
// Lit texels: texture × Gouraud light levels (`draw_textured_lit`)
// ---------------------------------------------------------------------------------------------

/// A triangle of `draw_textured_lit`: a textured triangle and its vertices' light levels.
#[derive(Clone, Copy, Debug)]
struct LitTri {
    tri: Tri,
    levels: [u8; 3],
}

impl LitTri {
    /// The light level (the vertex levels over 255, so in `[0, 1]`) at the centre of pixel
    /// `(x, y)`, perspective-correct with the vertices' `w` or, `affine`, screen-linear.
    fn level(&self, x: i32, y: i32, affine: bool) -> f64 {
        let l = self.levels.map(|l| [f64::from(l) / 255.0]);
        let w = if affine { [1.0; 3] } else { self.tri.ref_w() };
        perspective_attributes(self.tri.p, l, w, x, y).expect("a covered pixel has a level")[0]
    }
}

impl<C: GouraudColor> Frame<C> {
    fn draw_lit<S: TexelSource>(&mut self, t: &LitTri, clip: &Rectangle, texture: &Texture<S>)
    where
        C: From<S::Color>,
    {
        let mut target = DepthTarget::new_uncleared(&mut self.px, &mut self.z, W as u32, H as u32)
            .expect("buffers of the screen's size");
        draw_textured_lit(&mut target, clip, &t.tri.vertices(), texture, t.levels);
    }
}

/// A texture of random texels (each channel uniform over its range), Rgb565 or Rgb888 texels,
/// with its wrap modes; the reference's copies of its texels as an Rgb565 and an Rgb888 target
/// read them (embedded-graphics' conversions: "the texel as it is" in the target's channels).
struct LitTexture {
    rgb565: bool,
    width: u32,
    height: u32,
    wraps: [RefWrap; 2],
    words: Vec<u16>,
    bytes: Vec<u8>,
    as_rgb565: RefTexture,
    as_rgb888: RefTexture,
}

fn rgb<C: RgbColor>(c: C) -> [f64; 3] {
    [c.r(), c.g(), c.b()].map(f64::from)
}

impl LitTexture {
    fn new(rng: &mut Rng, rgb565: bool, width: u32, height: u32, wraps: [RefWrap; 2]) -> Self {
        let (mut words, mut bytes) = (Vec::new(), Vec::new());
        let (mut as_rgb565, mut as_rgb888) = (Vec::new(), Vec::new());
        for _ in 0..width * height {
            let mut channel = |max: u64| rng.below(max + 1) as u8;
            let (c565, c888) = if rgb565 {
                let (r, g, b) = (channel(31), channel(63), channel(31));
                words.push((u16::from(r) << 11) | (u16::from(g) << 5) | u16::from(b));
                let c = Rgb565::new(r, g, b);
                (c, Rgb888::from(c))
            } else {
                let c = Rgb888::new(channel(255), channel(255), channel(255));
                bytes.extend([c.r(), c.g(), c.b()]);
                (Rgb565::from(c), c)
            };
            as_rgb565.push(rgb(c565));
            as_rgb888.push(rgb(c888));
        }
        LitTexture {
            rgb565,
            width,
            height,
            wraps,
            words,
            bytes,
            as_rgb565: RefTexture::new(width, height, as_rgb565),
            as_rgb888: RefTexture::new(width, height, as_rgb888),
        }
    }

    fn describe(&self) -> String {
        let kind = if self.rgb565 { "Rgb565" } else { "Rgb888" };
        format!("{kind} {}×{} {:?}", self.width, self.height, self.wraps)
    }

    /// Draws `tris` (in order, into one frame) with `draw_textured_lit`, nearest filtering.
    fn render<C: LitColor>(&self, tris: &[LitTri], clip: &Rectangle) -> Frame<C> {
        let [wx, wy] = self.wraps.map(to_wrap);
        let mut frame = Frame::new();
        if self.rgb565 {
            let t = Texture::new(Rgb565Texels(&self.words), self.width, self.height)
                .unwrap()
                .with_wrap(wx, wy);
            for lit in tris {
                frame.draw_lit(lit, clip, &t);
            }
        } else {
            let t = Texture::new(Rgb888Texels(&self.bytes), self.width, self.height)
                .unwrap()
                .with_wrap(wx, wy);
            for lit in tris {
                frame.draw_lit(lit, clip, &t);
            }
        }
        frame
    }
}

/// A target colour of the lit tests, and the reference's texels as it reads them.
trait LitColor: GouraudColor + RgbColor + From<Rgb565> + From<Rgb888> {
    const NAME: &'static str;
    fn texels(texture: &LitTexture) -> &RefTexture;
}

impl LitColor for Rgb565 {
    const NAME: &'static str = "Rgb565";
    fn texels(texture: &LitTexture) -> &RefTexture {
        &texture.as_rgb565
    }
}

impl LitColor for Rgb888 {
    const NAME: &'static str = "Rgb888";
    fn texels(texture: &LitTexture) -> &RefTexture {
        &texture.as_rgb888
    }
}

/// The texels nearest sampling may take at the coordinate `c` given a tolerance `tol` on each
/// axis: every texel whose square lies within `tol` of `c` on both axes, wrapped (one texel
/// unless `c` lies within `tol` of a texel boundary that separates different texels).
fn candidate_texels(
    t: &RefTexture,
    wraps: [RefWrap; 2],
    c: [f64; 2],
    tol: [f64; 2],
) -> Vec<[f64; 3]> {
    let axis = |a: usize, n: u32| {
        let (lo, hi) = (
            (c[a] - tol[a]).floor() as i64,
            (c[a] + tol[a]).floor() as i64,
        );
        let mut v: Vec<u32> = (lo..=hi).map(|i| wrap(i, n, wraps[a])).collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let (xs, ys) = (axis(0, t.width), axis(1, t.height));
    ys.iter()
        .flat_map(|&j| xs.iter().map(move |&i| t.texel(i, j)))
        .collect()
}

/// The coordinate tolerance at a pixel, on each axis, as in the nearest tests: the documented
/// error of the computed coordinates (`δ·spread + 2⁻¹⁶`) plus the chord's deviation and the
/// steps' rounding. A face close enough to affine to take the 2D fill (src/three_d/texturing.rs,
/// "Accuracy": its perspective departure `spread·(ratio − 1)/4` within 1/16 texel; with 5 %
/// slack for the fill's 16-bit `q`) gets that departure and the 2D fill's rounding
/// (`s/32 639 + 1/128`) on top.
fn coordinate_tolerance(tri: &Tri, r: &RefPixel) -> [f64; 2] {
    let mut eps = tri.documented_bound();
    if tri.spread() * (tri.w_ratio() - 1.0) / 4.0 <= 1.05 / 16.0 {
        eps += 1.0 / 16.0 + tri.spread() / 32_639.0 + 1.0 / 128.0;
    }
    r.chord.map(|d| d + eps)
}

/// Agreement of lit pixels with `texel × level` over scenes (channel differences in LSB of the
/// target's channels).
#[derive(Debug, Default)]
struct LitAccuracy {
    pixels: usize,
    /// Pixels whose reference coordinate lies within the coordinate tolerance of a texel boundary
    /// (between different texels): compared with the closest of those texels' lit colours.
    near_boundary: usize,
    /// The largest difference from `texel × level` with the exact perspective-correct level
    /// (the checked one: within 1 LSB plus the steps' rounding), where the texel is certain.
    max_error: f64,
    /// The same at the near-boundary pixels (the closest candidate texel).
    max_error_near: f64,
    /// The same as `max_error` where a chord over 16 pixels would be more than half an LSB off
    /// the exact level (the chunks there are shorter).
    max_exact_steep: f64,
    /// The most a chord over up to 16 pixels would be off the exact level, `texel × |chord −
    /// exact|`.
    max_chord: f64,
    /// Pixels (the texel certain) where the affine (screen-linear) level, rounded, would be
    /// beyond the bound in some channel: an implementation without perspective correction of
    /// the level would fail there.
    affine_off: usize,
    /// The largest difference of the affine level's channels from the chord's.
    max_affine: f64,
    /// Pixels beyond the bound (the first few described in `report`).
    failures: usize,
    report: String,
}

impl LitAccuracy {
    fn add(&mut self, o: &LitAccuracy) {
        self.pixels += o.pixels;
        self.near_boundary += o.near_boundary;
        self.max_error = self.max_error.max(o.max_error);
        self.max_error_near = self.max_error_near.max(o.max_error_near);
        self.max_exact_steep = self.max_exact_steep.max(o.max_exact_steep);
        self.max_chord = self.max_chord.max(o.max_chord);
        self.affine_off += o.affine_off;
        self.max_affine = self.max_affine.max(o.max_affine);
        self.failures += o.failures;
        if self.report.lines().count() < 5 {
            self.report.push_str(&o.report);
        }
    }

    fn summary(&self, name: &str) -> String {
        format!(
            "{name}: {} pixels, {} near a texel boundary; channel error against the exact level \
             max {:.3} LSB ({:.3} near a boundary; {:.3} where a 16-pixel chord would be up to \
             {:.3} LSB off it); affine levels beyond the bound at {} pixels (up to {:.1} LSB off)",
            self.pixels,
            self.near_boundary,
            self.max_error,
            self.max_error_near,
            self.max_exact_steep,
            self.max_chord,
            self.affine_off,
            self.max_affine
        )
    }

    /// Asserts every pixel within the bound, at least `min_pixels` compared and at most
    /// `max_near` of them near a boundary.
    fn assert_within(&self, name: &str, min_pixels: usize, max_near: f64) {
        assert_eq!(
            self.failures,
            0,
            "{}\n{} pixels beyond 1 LSB of texel × level:\n{}",
            self.summary(name),
            self.failures,
            self.report
        );
        assert!(self.pixels >= min_pixels, "{}", self.summary(name));
        assert!(
            (self.near_boundary as f64) <= max_near * self.pixels as f64,
            "{}",
            self.summary(name)
        );
    }
}

/// The largest channel difference of `got` from `texel × level`.
fn lit_error(got: [f64; 3], texel: [f64; 3], level: f64) -> f64 {
    let want = scale(texel, level);
    (0..3).map(|k| (got[k] - want[k]).abs()).fold(0.0, f64::max)
}

/// Draws `tris` (not overlapping) with `draw_textured_lit` into a `C` frame; asserts that exactly
/// the reference's covered pixels are written, and compares every channel of each with
/// `texel × level` in the target's channels: the texel the reference coordinate's (any texel
/// within the coordinate tolerance where it lies near a boundary: the closest of them), the level
/// the vertex levels over 255 interpolated perspective-correct.
///
/// The bound is 1 LSB (the crate's for interpolated colours) plus the steps' rounding, around
/// `texel × level` with the exact perspective-correct level: like the texel coordinates, the
/// level is computed exactly at the ends of chunks of up to 16 pixels and stepped linearly
/// between (see [`chords`]), the chunks short enough for the chords to stay within a quarter of
/// the target's finest channel step of the exact level (a chord over 16 pixels would be off by
/// up to tens of LSB on the steepest random triangles, a 1:20 ratio of `w` across a few pixels;
/// the statistics report it). A face close enough to affine to take the 2D fill has its level
/// screen-linear, within the same quarter step of the exact one.
fn check_lit<C: LitColor>(tris: &[LitTri], clip: &Clip, texture: &LitTexture) -> LitAccuracy {
    let frame = texture.render::<C>(tris, &clip.rectangle());
    let texels = C::texels(texture);
    let on_screen = clip.on_screen();
    let plain: Vec<Tri> = tris.iter().map(|t| t.tri).collect();
    let scene = reference_scene(&plain, &on_screen);
    // The levels of the same pixels, in the same order, with their chords.
    let mut levels = Vec::with_capacity(scene.len());
    for t in tris {
        let exact: Vec<(i32, i32, [f64; 2])> = t
            .tri
            .texels(&on_screen)
            .iter()
            .map(|&(x, y, _)| (x, y, [t.level(x, y, false), 0.0]))
            .collect();
        levels.extend(
            exact
                .iter()
                .zip(chords(&exact))
                .map(|(&(x, y, [l, _]), (off, steps))| (x, y, l, off[0], steps[0])),
        );
    }
    assert_eq!(levels.len(), scene.len());
    let mut acc = LitAccuracy::default();
    let mut covered = vec![false; N];
    for (r, &(x, y, level, chord_off, steps)) in scene.iter().zip(&levels) {
        assert_eq!((r.x, r.y), (x, y));
        let i = (y * W + x) as usize;
        assert!(!covered[i], "pixel ({x}, {y}) covered twice");
        covered[i] = true;
        let lit = &tris[r.tri];
        let context = || {
            format!(
                "{} into {}, clip {clip:?}, {lit:?}",
                texture.describe(),
                C::NAME
            )
        };
        assert!(
            frame.written(x, y),
            "covered pixel ({x}, {y}) not written: {}",
            context()
        );
        let got = rgb(frame.at(x, y));
        let tol = coordinate_tolerance(&lit.tri, r);
        let candidates = candidate_texels(texels, texture.wraps, r.c, tol);
        if let [only] = candidates[..] {
            assert_eq!(only, nearest(texels, texture.wraps, r.c[0], r.c[1]));
        }
        // The bound: 1 LSB, plus the steps' rounding of the level (up to 2⁻¹⁶ a pixel).
        let bound = |t: &[f64; 3]| 1.0 + t.iter().fold(0.0f64, |m, &c| m.max(c * steps));
        // The candidate texel closest to the bound: its error, and by how much it exceeds the
        // bound (if positive).
        let (texel, err, excess) = candidates
            .iter()
            .map(|t| {
                let err = lit_error(got, *t, level);
                (t, err, err - bound(t))
            })
            .min_by(|a, b| a.2.total_cmp(&b.2))
            .expect("at least one texel");
        acc.pixels += 1;
        if candidates.len() > 1 {
            acc.near_boundary += 1;
            acc.max_error_near = acc.max_error_near.max(err);
        } else {
            acc.max_error = acc.max_error.max(err);
            // How far a 16-pixel chord could be off the exact level here: where that is large,
            // the chunk length chosen per span is what keeps the error within the bound.
            let deviation = texel.iter().fold(0.0f64, |m, t| m.max(t * chord_off));
            if deviation > 0.5 {
                acc.max_exact_steep = acc.max_exact_steep.max(err);
            }
            acc.max_chord = acc.max_chord.max(deviation);
            let affine = scale(*texel, lit.level(x, y, true)).map(f64::round);
            let affine_error = lit_error(affine, *texel, level);
            acc.max_affine = acc.max_affine.max(affine_error);
            if affine_error > bound(texel) + 1e-9 {
                acc.affine_off += 1;
            }
        }
        if excess > 1e-9 {
            acc.failures += 1;
            if acc.failures <= 5 {
                let _ = writeln!(
                    acc.report,
                    "  pixel ({x}, {y}): {got:?}, texel {texel:?} × level {level:.5} (×255 = \
                     {:.2}; a chord could be off by {chord_off:.5}) = {:?}, {} candidate texels, \
                     coordinate {:?}; {}",
                    level * 255.0,
                    scale(*texel, level),
                    candidates.len(),
                    r.c,
                    context()
                );
            }
        }
    }
    for (i, &c) in covered.iter().enumerate() {
        assert!(
            c || frame.z[i] == DEPTH_CLEAR,
            "pixel ({}, {}) written, not covered: {tris:?}, clip {clip:?}",
            i as i32 % W,
            i as i32 / W
        );
    }
    acc
}

impl Rng {
    /// Vertex light levels: uniform, or one time in four each 0 or 255.
    fn levels(&mut self) -> [u8; 3] {
        if self.chance(4) {
            [(); 3].map(|_| if self.chance(2) { 0 } else { 255 })
        } else {
            [(); 3].map(|_| self.below(256) as u8)
        }
    }

    /// A lit triangle: a random textured one (`textured`) with random levels; one time in four
    /// with its texel coordinates within half a texel of each other, its `w` within 1:3 and
    /// levels of 0 and 255 among its vertices: a face whose texel coordinates alone would allow
    /// screen-space interpolation (src/three_d/texturing.rs, "Accuracy") but whose levels do not.
    fn lit(&mut self) -> LitTri {
        let mut tri = self.textured();
        let mut levels = self.levels();
        if self.chance(4) {
            let spread = self.range_f64(0.02, 0.5);
            let base = tri.ref_uv()[0];
            let uv: [[f64; 2]; 3] = [(); 3].map(|_| base.map(|c| c + self.range_f64(0.0, spread)));
            tri.uv = uv.map(|c| c.map(|c| bits(c, 16)));
            tri.w = [(); 3].map(|_| bits(self.range_f64(1.0, 3.0), 16));
            let k = self.below(3) as usize;
            levels[k] = 0;
            levels[(k + 1) % 3] = 255;
        }
        LitTri { tri, levels }
    }
}

/// `draw_textured_lit` on random triangles (`w` in ratios up to 1:20, sub-pixel vertices,
/// random clips) with random vertex levels (one triangle in four with levels of 0 and 255 only,
/// one in four with texel coordinates close enough for screen-space interpolation but not its
/// levels: `Rng::lit`), textures of random texels — 64 × 64 and 32 × 8 repeating Rgb565 (the
/// power-of-two fast path), 24 × 17 Rgb565 (mirrored × clamped), 64 × 32 and 20 × 12 Rgb888 —
/// each into Rgb565 and Rgb888 targets: exactly the reference's pixels written, every channel
/// within 1 LSB (and the steps' rounding) of the texel's times the exact perspective-correct
/// level (see `check_lit`; the texel the reference coordinate's, or near a texel boundary,
/// within the nearest tests' tolerance, the closest of the texels there); at most 30 % of the
/// pixels near a boundary. A chord over 16 pixels would be up to 58 LSB off the exact level
/// here (Rgb888 targets): with fixed 16-pixel chunks the test fails.
#[test]
fn random_lit_triangles_match_texel_times_level() {
    let mut rng = Rng(0x9e47_5e07);
    let textures = [
        (true, 64, 64, [RefWrap::Repeat; 2]),
        (true, 32, 8, [RefWrap::Repeat; 2]),
        (true, 24, 17, [RefWrap::MirroredRepeat, RefWrap::Clamp]),
        (false, 64, 32, [RefWrap::Repeat, RefWrap::MirroredRepeat]),
        (false, 20, 12, [RefWrap::Clamp, RefWrap::Repeat]),
    ]
    .map(|(rgb565, w, h, wraps)| LitTexture::new(&mut rng, rgb565, w, h, wraps));
    let mut total = LitAccuracy::default();
    for texture in &textures {
        for target in 0..2 {
            let mut acc = LitAccuracy::default();
            for _ in 0..100 {
                let lit = rng.lit();
                let clip = rng.clip();
                acc.add(&if target == 0 {
                    check_lit::<Rgb565>(&[lit], &clip, texture)
                } else {
                    check_lit::<Rgb888>(&[lit], &clip, texture)
                });
            }
            let name = format!(
                "{} into {}",
                texture.describe(),
                ["Rgb565", "Rgb888"][target]
            );
            println!("{}", acc.summary(&name));
            total.add(&acc);
        }
    }
    println!("{}", total.summary("lit random"));
    total.assert_within("lit random", 250_000, 0.3);
}

/// `draw_textured_lit` on the floors seen at a grazing angle (`w` about 1:15 across each
/// triangle), the light differing strongly between the near edge and the far one (rolled: 255
/// near, 16 far; level: 40 near, 255 far), 64 × 64 repeating Rgb565 and Rgb888 textures into
/// Rgb565 and Rgb888 targets: every channel within 1 LSB of texel × exact perspective-correct
/// level (see `check_lit`: on the level floor the chords are exact, on the rolled one a chord
/// over 16 pixels would depart from the exact level by up to 1.5 LSB). The affine (screen-linear) level, rounded,
/// would be beyond that bound at most of the pixels whose texel is certain (measured: over 99 %
/// of them, by up to 141 LSB): the scene tells perspective-correct light from affine.
#[test]
fn floor_lit_matches_texel_times_level() {
    let mut rng = Rng(0x9e47_5e08);
    let textures =
        [true, false].map(|rgb565| LitTexture::new(&mut rng, rgb565, 64, 64, [RefWrap::Repeat; 2]));
    let mut total = LitAccuracy::default();
    for ((name, floor), (near, far)) in floors().into_iter().zip([(255, 16), (40, 255)]) {
        let [a, b] = floor.triangles();
        // Corners 0 and 1 are on the near edge, 2 and 3 on the far one.
        let tris = [
            LitTri {
                tri: a,
                levels: [near, near, far],
            },
            LitTri {
                tri: b,
                levels: [near, far, far],
            },
        ];
        for texture in &textures {
            for target in 0..2 {
                let acc = if target == 0 {
                    check_lit::<Rgb565>(&tris, &SCREEN, texture)
                } else {
                    check_lit::<Rgb888>(&tris, &SCREEN, texture)
                };
                let scene = format!(
                    "{name} ({near} near, {far} far), {} into {}",
                    texture.describe(),
                    ["Rgb565", "Rgb888"][target]
                );
                println!("{}", acc.summary(&scene));
                acc.assert_within(&scene, 8_000, 0.6);
                let certain = acc.pixels - acc.near_boundary;
                assert!(
                    acc.affine_off * 4 > certain * 3,
                    "{scene}: affine levels too close to perspective-correct ones: {}",
                    acc.summary("affine")
                );
                total.add(&acc);
            }
        }
    }
    println!("{}", total.summary("lit floors"));
}

// ---------------------------------------------------------------------------------------------
// Depth
// ---------------------------------------------------------------------------------------------

/// Overlapping textured triangles at different depths, drawn in either order: where both cover
/// a pixel and their reference depths (screen-linear) differ by more than 2 units, the nearer
/// one's texel is there (each triangle's texture tags its texels); where one covers it, its
/// texel; the z-buffer holds the winner's depth within 1 unit. The texels are checked against
/// the winner's reference coordinates as in the nearest tests.
#[test]
fn nearer_textured_triangles_win() {
    let mut rng = Rng(0x9e47_5e04);
    let tags = [40u8, 200];
    let bytes: Vec<Vec<u8>> = tags
        .iter()
        .map(|&tag| {
            (0..256 * 256)
                .flat_map(|k| [k as u8, (k >> 8) as u8, tag])
                .collect()
        })
        .collect();
    let textures: Vec<_> = bytes
        .iter()
        .map(|b| Texture::new(Rgb888Texels(b), 256, 256).unwrap())
        .collect();
    let size = CoordTexture::new(CoordKind::Rgb888, 256, 256).reference;
    let wraps = [RefWrap::Repeat; 2];
    let (mut contested, mut decided, mut acc) = (0, 0, Accuracy::default());
    for n in 0..300 {
        let a = rng.textured();
        let mut b = rng.textured();
        // Overlapping: b moved onto a's centroid.
        let centre = |t: &Tri| {
            let s = t.p.iter().fold((0i64, 0i64), |s, p| {
                (s.0 + i64::from(p.0), s.1 + i64::from(p.1))
            });
            (s.0 / 3, s.1 / 3)
        };
        let (ca, cb) = (centre(&a), centre(&b));
        b.p = b.p.map(|p| {
            (
                (i64::from(p.0) + ca.0 - cb.0) as i32,
                (i64::from(p.1) + ca.1 - cb.1) as i32,
            )
        });
        if n % 3 == 0 {
            // Constant depths.
            b.depth = [rng.range(0, 60_000) as u16; 3];
        }
        let tris = [a, b];
        let order: [usize; 2] = if n % 2 == 0 { [0, 1] } else { [1, 0] };
        let mut frame = Frame::<Rgb888>::new();
        for k in order {
            frame.draw(&tris[k], &SCREEN.rectangle(), &textures[k]);
        }
        let refs: Vec<Vec<Option<RefPixel>>> = tris
            .iter()
            .map(|t| {
                let mut m = vec![None; N];
                for r in reference_scene(&[*t], &SCREEN) {
                    m[(r.y * W + r.x) as usize] = Some(r);
                }
                m
            })
            .collect();
        let depth = |t: &Tri, x, y| {
            let d = t.depth.map(|d| [f64::from(d), 0.0, 0.0]);
            interpolate(t.p, d, x, y).map_or(f64::NAN, |v| v[0])
        };
        for (i, (&ra, &rb)) in refs[0].iter().zip(&refs[1]).enumerate() {
            let (x, y) = (i as i32 % W, i as i32 / W);
            let cover = [ra, rb];
            let winner = match cover {
                [None, None] => {
                    assert!(!frame.written(x, y), "({x}, {y}) written: {tris:?}");
                    continue;
                }
                [Some(_), None] => 0,
                [None, Some(_)] => 1,
                [Some(_), Some(_)] => {
                    contested += 1;
                    let (da, db) = (depth(&a, x, y), depth(&b, x, y));
                    if (da - db).abs() <= 2.0 {
                        continue;
                    }
                    decided += 1;
                    usize::from(db < da)
                }
            };
            assert!(frame.written(x, y), "({x}, {y}) not written: {tris:?}");
            let px = frame.at(x, y);
            assert_eq!(
                px.b(),
                tags[winner],
                "({x}, {y}): triangle {winner} should be in front (depths {:.2}, {:.2}); {tris:?}",
                depth(&a, x, y),
                depth(&b, x, y)
            );
            let z = f64::from(frame.z[i]);
            let want = depth(&tris[winner], x, y);
            assert!(
                (z - want).abs() <= 1.0,
                "({x}, {y}): depth {z} vs {want:.3}; {tris:?}"
            );
            let r = cover[winner].unwrap();
            let eps = tris[winner].documented_bound();
            acc.pixel(
                &r,
                (px.r().into(), px.g().into()),
                &size,
                wraps,
                eps,
                &|| format!("{:?}", tris[winner]),
            );
        }
    }
    println!(
        "depth: {contested} pixels covered by both, {decided} decided; {}",
        acc.summary("winners")
    );
    assert!(decided > 10_000, "{decided}");
    acc.assert_within("depth", 200_000, 0.2);
}

// ---------------------------------------------------------------------------------------------
// Robustness
// ---------------------------------------------------------------------------------------------

/// Robustness: positions of every kind (including the full raw range, far off-screen, huge and
/// degenerate triangles), `w` of 0, negative, the smallest and largest `I16F16`, texel
/// coordinates at the `I16F16` extremes, every texture kind, wrap mode and filter: no panic
/// (overflow checks are on), and, all depths equal, exactly the reference's covered pixels
/// written inside the clip (coverage does not depend on `w` or the texels).
#[test]
fn extreme_inputs_write_only_the_coverage() {
    let mut rng = Rng(0x9e47_5e05);
    let coords = coordinate_textures();
    let smooth = [
        SmoothTexture::new(false, 64, 64),
        SmoothTexture::new(true, 24, 17),
    ];
    let mut pixels = 0;
    for n in 0..2_000u64 {
        let mut tri = rng.textured();
        tri.p = positions(&mut rng, n % KINDS);
        tri.depth = [500; 3];
        for k in 0..3 {
            if rng.chance(2) {
                tri.w[k] = match rng.below(6) {
                    0 => 0,
                    1 => -1,
                    2 => i32::MIN,
                    3 => 1,
                    4 => i32::MAX,
                    _ => -(rng.below(1 << 20) as i32),
                };
            }
            for a in 0..2 {
                if rng.chance(2) {
                    tri.uv[k][a] = match rng.below(4) {
                        0 => i32::MIN,
                        1 => i32::MAX,
                        2 => rng.next() as i32,
                        _ => (rng.next() as i32) >> 12,
                    };
                }
            }
        }
        let clip = rng.clip();
        let wraps = [WRAPS[rng.below(3) as usize], WRAPS[rng.below(3) as usize]];
        let written: Vec<bool> = if rng.chance(3) {
            let t = &smooth[rng.below(2) as usize];
            t.render(&[tri], &clip.rectangle(), wraps)
                .iter()
                .map(Option::is_some)
                .collect()
        } else {
            let t = &coords[rng.below(coords.len() as u64) as usize];
            t.render(&[tri], &clip.rectangle(), wraps)
                .iter()
                .map(Option::is_some)
                .collect()
        };
        let mask = coverage_mask(tri.p, &clip.on_screen());
        for i in 0..N {
            assert_eq!(
                written[i],
                mask[i],
                "pixel ({}, {}): written {}, covered {}: {tri:?}, clip {clip:?}",
                i as i32 % W,
                i as i32 / W,
                written[i],
                mask[i]
            );
        }
        pixels += mask.iter().filter(|&&m| m).count();
        // The reference agrees that a covered pixel has a centre inside.
        if let Some(i) = mask.iter().position(|&m| m) {
            assert!(covers(tri.p, i as i32 % W, i as i32 / W));
        }
    }
    println!("robustness: 2000 triangles, {pixels} covered pixels");
    assert!(pixels > 500_000);
}

// ---------------------------------------------------------------------------------------------
// The coordinates themselves
// ---------------------------------------------------------------------------------------------

/// The implementation's texel coordinates at each written pixel, modulo 256 texels and to within
/// `1/(2·steps)` texel: the scene drawn with the 256 × 256 coordinate texture, then again with
/// every vertex's texel coordinates moved by `j/steps` texel for `j = 1, 2, …`
/// (`probe::coordinates`).
fn probe(tris: &[Tri], clip: &Clip, steps: u32) -> Vec<Option<[f64; 2]>> {
    let texture = CoordTexture::new(CoordKind::Rgb888, 256, 256);
    let wraps = [RefWrap::Repeat; 2];
    let rect = clip.rectangle();
    let base = texture.render(tris, &rect, wraps);
    probe::coordinates(&base, steps, |j| {
        let o = (65_536 / steps * j) as i32;
        let moved: Vec<Tri> = tris
            .iter()
            .map(|t| Tri {
                uv: t.uv.map(|c| c.map(|c| c.wrapping_add(o))),
                ..*t
            })
            .collect();
        texture.render(&moved, &rect, wraps)
    })
}

/// The coordinates themselves (probed to 1/512 texel, see `probe`) on the floors and on random
/// triangles (ratios up to 1:20): at every pixel within the documented error of the computed
/// coordinates (`δ·spread + 2⁻¹⁶`) of the exact coordinate, plus what the chords may depart
/// there (`chords`), the steps' rounding and the probe's resolution. Stronger than the nearest tests, which see an
/// error only where it takes a pixel across a texel boundary.
#[test]
fn probed_coordinates_are_within_the_documented_bound() {
    const STEPS: u32 = 256;
    let resolution = 0.5 / f64::from(STEPS);
    let mut rng = Rng(0x9e47_5e06);
    let mut scenes: Vec<(String, Vec<Tri>, Clip)> = floors()
        .into_iter()
        .map(|(name, f)| (name.to_string(), f.triangles().to_vec(), SCREEN))
        .collect();
    for n in 0..48 {
        scenes.push((format!("random {n}"), vec![rng.textured()], rng.clip()));
    }
    let (mut pixels, mut worst_ratio) = (0, 0.0f64);
    let (mut random_off_chord, mut random_ratio) = (0.0f64, 0.0f64);
    let mut lines = String::new();
    for (name, tris, clip) in &scenes {
        let got = probe(tris, clip, STEPS);
        let (mut off_chord, mut off_exact, mut off_where_exact) = (0.0f64, 0.0f64, 0.0f64);
        let mut scene_ratio = 0.0f64;
        for r in reference_scene(tris, &clip.on_screen()) {
            let g = got[(r.y * W + r.x) as usize].expect("covered pixel written");
            let bound = tris[r.tri].documented_bound();
            for (a, &ga) in g.iter().enumerate() {
                let v = unwrap_near(ga, r.c[a]);
                let d = (v - r.c[a]).abs();
                assert!(
                    d <= bound + r.chord[a] + resolution + 1e-9,
                    "{name}, pixel ({}, {}) axis {a}: coordinate {v:.4}, exact {:.4}, chords \
                     allowed {:.4}, bound {bound:.4}: {:?}",
                    r.x,
                    r.y,
                    r.c[a],
                    r.chord[a],
                    tris[r.tri]
                );
                scene_ratio = scene_ratio.max((d - r.chord[a] - resolution).max(0.0) / bound);
                off_chord = off_chord.max(r.chord[a] - r.steps[a]);
                off_exact = off_exact.max(d);
                if r.chord[a] - r.steps[a] < 1.0 / 1024.0 {
                    off_where_exact = off_where_exact.max(d);
                }
            }
            pixels += 1;
        }
        worst_ratio = worst_ratio.max(scene_ratio);
        let documented = tris.iter().map(Tri::documented_bound).fold(0.0, f64::max);
        if name.starts_with("random") {
            random_off_chord = random_off_chord.max(off_chord);
            random_ratio = random_ratio.max(scene_ratio);
        } else {
            let _ = writeln!(
                lines,
                "  {name}: ratio {:.1}, spread {:.0}, documented {documented:.4}: chords may be \
                 off by ≤ {off_chord:.4}, off the exact coordinate ≤ {off_exact:.4} \
                 ({off_where_exact:.4} where every chord is exact)",
                tris.iter().map(Tri::w_ratio).fold(0.0, f64::max),
                tris.iter().map(Tri::spread).fold(0.0, f64::max),
            );
        }
    }
    println!(
        "probed coordinates: {pixels} pixels, error (less the steps' rounding and the probe's \
         resolution) at most {worst_ratio:.3} of the documented bound\n{lines}  48 random \
         triangles: chords allowed ≤ {random_off_chord:.4} texel, at most {random_ratio:.3} of \
         their documented bound"
    );
    assert!(pixels > 40_000);
}
