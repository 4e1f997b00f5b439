//! Textured triangles (`TexturedTriangle`) and texture sampling (`Texture`) against the
//! independent f64 reference (`embedded_raster::reference` and its `texture` module).
//!
//! * The samplers: `Texture::nearest` picks exactly the reference's texel and
//!   `Texture::bilinear` is within 1 LSB of the reference's exact blend, at random 16.16
//!   coordinates anywhere in the `i32` range, for every texel source, power-of-two and other
//!   sizes and every pair of wrap modes.
//! * Triangles: exactly the reference's pixels are written (each pixel is drawn over two
//!   backgrounds that differ everywhere: a pixel was written exactly when both results agree),
//!   and each holds the texture sampled at the exactly interpolated texel coordinate, to the
//!   documented accuracy: the interpolated coordinate is within `s + 1/128` texel of the exact
//!   one, `s` being the triangle's texel-coordinate spread on that axis over 32,639.
//! * Every drawing path writes the same pixels: `draw_into`, `Drawable::draw` into a
//!   `SliceFramebuffer` and into a target with nothing but `draw_iter`, and band rendering in
//!   bands of several heights.
//! * The same accuracy for texel coordinates spread over up to the whole `I16F16` range, on
//!   triangles about the screen's size and larger.
//! * Robustness: vertices anywhere in the `Coord` range, zero-area triangles, texel
//!   coordinates up to the `I16F16` extremes: no panic (overflow checks are on in the test
//!   profile), no pixel outside the triangle touched.
//!
//! The reference textures are built from the raw texel data by hand (5-6-5 words split into
//! their fields, palette indices looked up), never through the `TexelSource`s under test.
//!
//! Run with `cargo test --release --features reference --test all textured:: -- --nocapture` to see
//! the statistics.

use std::convert::Infallible;
use std::f64::consts::TAU;
use std::fmt::Debug;

use embedded_graphics::pixelcolor::{Gray8, Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;
use embedded_raster::band::{BandLayout, Callback, ColorBands};
use embedded_raster::reference;
use embedded_raster::reference::texture::{self as rt, RefTexture, RefWrap};
use embedded_raster::texture::{
    Filter, Gray8Texels, Indexed4, Indexed8, Rgb565Texels, Rgb888Texels, TexelCoord, TexelSource,
    Texture, Wrap,
};
use embedded_raster::{Coord, GouraudColor, SliceFramebuffer, TexturedTriangle, TexturedVertex};

use crate::rng;
use rng::Rng;

use crate::raw_points;
use raw_points::{extreme, sliver, Screen, MAX, MIN};

/// The screen: wider than tall, small enough for thousands of triangles a second.
const W: u32 = 64;
const H: u32 = 48;
const PIXELS: usize = (W * H) as usize;
const RAW: Screen = Screen::new(W as i64, H as i64);
/// 16.16 units a texel.
const UNIT: f64 = 65_536.0;
/// The documented interpolation accuracy: a coordinate is within `s + 1/128` texel of the exact
/// one, `s` (the step of the planes' vertex values) under `spread / STEPS` and at least 2⁻¹⁶.
const STEPS: f64 = 32_639.0;
/// The `1/128` texel of span stepping in that bound.
const STEPPING: f64 = 1.0 / 128.0;
/// Slack for the reference's own rounding: its coordinates (below 2¹⁵ texels) and blends
/// (below 2⁸) are a few ulps off, far below this.
const MARGIN: f64 = 1e-9;
/// Largest texel-coordinate spread of a triangle in the accuracy tests, in texels: the bound
/// is then under 1/128 + 512/32,639 ≈ 0.0235 texel, so that nearest filtering is checked at
/// all but a few percent of the pixels.
const MAX_SPREAD: f64 = 512.0;
/// Triangles per texture and pair of wrap modes in the triangle tests (6 textures × 9 pairs).
const TRIANGLES_PER_WRAP: usize = 60;

const WRAPS: [(Wrap, RefWrap); 3] = [
    (Wrap::Repeat, RefWrap::Repeat),
    (Wrap::MirroredRepeat, RefWrap::MirroredRepeat),
    (Wrap::Clamp, RefWrap::Clamp),
];

impl Rng {
    /// A colour with random channels.
    fn uniform_color<C: GouraudColor>(&mut self) -> C {
        C::from_channels(core::array::from_fn(|k| {
            self.below(u64::from(C::MAX[k]) + 1) as u8
        }))
    }
}

// ---------------------------------------------------------------------------------------------
// Textures
// ---------------------------------------------------------------------------------------------

/// A check run on every texture of [`each_texture`]: the texture (repeating, nearest) and its
/// reference, whose channels are those of the target colour `C`.
trait Visit {
    fn visit<S, C>(&mut self, name: &str, texture: Texture<S>, reference: &RefTexture)
    where
        S: TexelSource + Copy + Debug,
        C: GouraudColor + From<S::Color> + Debug;
}

/// Channel values `0..=max` for `w × h` texels, row-major: random, or (`smooth`) a periodic
/// field whose neighbours (across the wrap too) differ by at most [`SMOOTH_STEP`] + 1.
fn field(rng: &mut Rng, w: u32, h: u32, max: u8, smooth: bool) -> Vec<u8> {
    if !smooth {
        return (0..w * h)
            .map(|_| rng.below(u64::from(max) + 1) as u8)
            .collect();
    }
    let mid = f64::from(max) / 2.0;
    // `a·sin(τ·i/n)` changes by at most `a·τ/n` from one texel to the next.
    let amplitude = |n: u32| (mid / 2.0).min(SMOOTH_STEP * f64::from(n) / TAU);
    let (ax, ay) = (amplitude(w), amplitude(h));
    let (px, py) = (rng.unit() * TAU, rng.unit() * TAU);
    let mut out = Vec::with_capacity((w * h) as usize);
    for j in 0..h {
        for i in 0..w {
            let x = ax * (TAU * f64::from(i) / f64::from(w) + px).sin();
            let y = ay * (TAU * f64::from(j) / f64::from(h) + py).sin();
            out.push((mid + x + y).round().clamp(0.0, f64::from(max)) as u8);
        }
    }
    out
}

/// Largest change of a smooth field's value between neighbouring texels, before rounding.
const SMOOTH_STEP: f64 = 2.0;

/// The reference channels of a 5-6-5 word (red in the top five bits, then six of green).
fn rgb565_channels(word: u16) -> [f64; 3] {
    [
        f64::from(word >> 11),
        f64::from((word >> 5) & 0x3f),
        f64::from(word & 0x1f),
    ]
}

/// A palette of `n` Rgb565 colours and their channels: random, or (`smooth`) a gradient whose
/// neighbours differ by at most one step per channel.
fn palette(rng: &mut Rng, n: usize, smooth: bool) -> (Vec<Rgb565>, Vec<[u8; 3]>) {
    let max = [31u8, 63, 31];
    let start: [u8; 3] = core::array::from_fn(|k| rng.below(u64::from(max[k]) + 1) as u8);
    let channels: Vec<[u8; 3]> = (0..n)
        .map(|i| {
            core::array::from_fn(|k| {
                if smooth {
                    // Up and down across the range: a triangle wave from `start`.
                    let m = usize::from(max[k]);
                    let t = (usize::from(start[k]) + i) % (2 * m);
                    (if t <= m { t } else { 2 * m - t }) as u8
                } else {
                    rng.below(u64::from(max[k]) + 1) as u8
                }
            })
        })
        .collect();
    let colors = channels
        .iter()
        .map(|c| Rgb565::new(c[0], c[1], c[2]))
        .collect();
    (colors, channels)
}

/// The reference channels of palette index `i`: past the palette's end, its first colour.
fn palette_channels(channels: &[[u8; 3]], i: u8) -> [f64; 3] {
    let c = channels.get(usize::from(i)).unwrap_or(&channels[0]);
    c.map(f64::from)
}

/// Runs `v` on each texture: every texel source, power-of-two sizes (both sides, or one) and
/// others, 1-texel rows and columns. Random texels, or smooth ones (`smooth`).
fn each_texture(rng: &mut Rng, smooth: bool, v: &mut impl Visit) {
    // Rgb565 words into Rgb565: power-of-two, then not.
    for (w, h) in [(64, 32), (24, 16)] {
        let [r, g, b] = [31, 63, 31].map(|max| field(rng, w, h, max, smooth));
        let words: Vec<u16> = (0..r.len())
            .map(|i| u16::from(r[i]) << 11 | u16::from(g[i]) << 5 | u16::from(b[i]))
            .collect();
        let reference = RefTexture::new(w, h, words.iter().map(|&t| rgb565_channels(t)).collect());
        let texture = Texture::new(Rgb565Texels(&words), w, h).unwrap();
        v.visit::<_, Rgb565>(&format!("Rgb565Texels {w}×{h}"), texture, &reference);
    }

    // 4-bit indices into 12 colours (indices 12 to 15 read the first), 13 × 13: an odd number
    // of texels, the last byte's low nibble unused.
    let (w, h) = (13, 13);
    let (colors, channels) = palette(rng, 12, smooth);
    // Smooth: indices inside the palette only (the jump to the first colour is not smooth).
    let indices = field(rng, w, h, if smooth { 11 } else { 15 }, smooth);
    let packed: Vec<u8> = indices
        .chunks(2)
        .map(|p| p[0] << 4 | p.get(1).copied().unwrap_or(0))
        .collect();
    let texels = (0..(w * h) as usize)
        .map(|t| {
            let byte = packed[t / 2];
            let i = if t % 2 == 0 { byte >> 4 } else { byte & 0xf };
            palette_channels(&channels, i)
        })
        .collect();
    let reference = RefTexture::new(w, h, texels);
    let source = Indexed4 {
        indices: &packed,
        palette: &colors,
    };
    let texture = Texture::new(source, w, h).unwrap();
    v.visit::<_, Rgb565>("Indexed4<Rgb565> 13×13", texture, &reference);

    // Byte indices into 200 colours (a fifth of the indices past the end), one column of 7.
    let (w, h) = (1, 7);
    let (colors, channels) = palette(rng, 200, smooth);
    let indices = if smooth {
        field(rng, w, h, 199, true)
    } else {
        field(rng, w, h, 255, false)
    };
    let texels = indices
        .iter()
        .map(|&i| palette_channels(&channels, i))
        .collect();
    let reference = RefTexture::new(w, h, texels);
    let source = Indexed8 {
        indices: &indices,
        palette: &colors,
    };
    let texture = Texture::new(source, w, h).unwrap();
    v.visit::<_, Rgb565>("Indexed8<Rgb565> 1×7", texture, &reference);

    // Gray8 into Gray8, 7 × 64: a power of two on one axis only.
    let (w, h) = (7, 64);
    let luma = field(rng, w, h, 255, smooth);
    let texels = luma.iter().map(|&l| [f64::from(l), 0.0, 0.0]).collect();
    let reference = RefTexture::new(w, h, texels);
    let texture = Texture::new(Gray8Texels(&luma), w, h).unwrap();
    v.visit::<_, Gray8>("Gray8Texels 7×64", texture, &reference);

    // Rgb888 bytes into Rgb888, 5 × 3, with a stray byte past the last texel.
    let (w, h) = (5, 3);
    let [r, g, b] = [0; 3].map(|_| field(rng, w, h, 255, smooth));
    let mut bytes: Vec<u8> = (0..r.len()).flat_map(|i| [r[i], g[i], b[i]]).collect();
    bytes.push(rng.below(256) as u8);
    let texels = bytes
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]].map(f64::from))
        .collect();
    let reference = RefTexture::new(w, h, texels);
    let texture = Texture::new(Rgb888Texels(&bytes), w, h).unwrap();
    v.visit::<_, Rgb888>("Rgb888Texels 5×3", texture, &reference);
}

/// Per channel, the largest difference between horizontal and between vertical neighbours.
type Differences = ([f64; 3], [f64; 3]);

/// The largest difference of each channel between neighbouring texels, horizontally and
/// vertically, the wrap-around neighbours included (so it bounds every wrap mode's): how fast
/// the bilinear blend can change per texel of coordinate.
fn neighbour_difference(t: &RefTexture) -> Differences {
    let (mut dx, mut dy) = ([0.0f64; 3], [0.0f64; 3]);
    for j in 0..t.height {
        for i in 0..t.width {
            let c = t.texel(i, j);
            let right = t.texel((i + 1) % t.width, j);
            let below = t.texel(i, (j + 1) % t.height);
            for k in 0..3 {
                dx[k] = dx[k].max((c[k] - right[k]).abs());
                dy[k] = dy[k].max((c[k] - below[k]).abs());
            }
        }
    }
    (dx, dy)
}

/// The texture and reference wrap modes of each of the 9 pairs (horizontal, vertical).
fn wrap_pairs() -> impl Iterator<Item = ([Wrap; 2], [RefWrap; 2])> {
    WRAPS
        .into_iter()
        .flat_map(|(x, rx)| WRAPS.map(|(y, ry)| ([x, y], [rx, ry])))
}

fn channels<C: GouraudColor>(c: C) -> [f64; 3] {
    c.channels().map(f64::from)
}

/// Failures seen, reported together at the end (a failing run shows how widespread a mismatch
/// is): per kind (texture, wrap modes, filter, check), how many and the first example.
#[derive(Default)]
struct Failures {
    seen: Vec<(String, usize, String)>,
}

impl Failures {
    fn record(&mut self, key: impl FnOnce() -> String, what: impl FnOnce() -> String) {
        let key = key();
        match self.seen.iter_mut().find(|(k, ..)| *k == key) {
            Some((_, count, _)) => *count += 1,
            None => self.seen.push((key, 1, what())),
        }
    }

    fn assert_none(&self) {
        let report: Vec<String> = self
            .seen
            .iter()
            .map(|(key, count, example)| format!("{key}: {count} failures; first: {example}"))
            .collect();
        assert!(report.is_empty(), "{}", report.join("\n"));
    }
}

// ---------------------------------------------------------------------------------------------
// Samplers
// ---------------------------------------------------------------------------------------------

/// A 16.16 texel coordinate for a texture axis of `n` texels: near the texture (a few periods
/// either way), on a texel centre or boundary, of any magnitude, or at the ends of `i32`.
fn sample_coordinate(rng: &mut Rng, n: u32) -> i32 {
    let n = i64::from(n);
    let v = match rng.below(5) {
        0 | 1 => rng.range(-3 * n * 65_536, 3 * n * 65_536),
        // Texel boundaries and centres: where nearest changes texel and bilinear is one texel.
        2 => rng.range(-3 * n, 3 * n) * 65_536 + [0, 32_768, 1, -1][rng.below(4) as usize],
        3 => rng.any_scale(),
        _ => extreme(rng),
    };
    v.clamp(MIN, MAX) as i32
}

/// Coordinates per texture and pair of wrap modes.
const SAMPLES: usize = 6_000;

struct Samplers<'r> {
    rng: &'r mut Rng,
    failures: Failures,
    /// Samples taken, and the largest bilinear error (LSB) above the bottom half texel.
    samples: usize,
    worst: f64,
}

impl Visit for Samplers<'_> {
    fn visit<S, C>(&mut self, name: &str, texture: Texture<S>, reference: &RefTexture)
    where
        S: TexelSource + Copy + Debug,
        C: GouraudColor + From<S::Color> + Debug,
    {
        for (wrap, ref_wrap) in wrap_pairs() {
            let texture = texture.with_wrap(wrap[0], wrap[1]);
            let bilinear = texture.with_filter(Filter::Bilinear);
            for _ in 0..SAMPLES {
                let x = sample_coordinate(self.rng, texture.width());
                let y = sample_coordinate(self.rng, texture.height());
                let (fx, fy) = (f64::from(x) / UNIT, f64::from(y) / UNIT);
                let what = || format!("{name} {wrap:?} at ({x}, {y}) = ({fx}, {fy}) texels");
                // Failures are reported apart for the half texel at the bottom of the range,
                // whose blend reads the texels left of (above) −32,768.
                let bottom = x < i32::MIN + (1 << 15) || y < i32::MIN + (1 << 15);
                let region = if bottom {
                    " (below −32,767.5 texels)"
                } else {
                    ""
                };

                let want = rt::nearest(reference, ref_wrap, fx, fy);
                let got = channels(C::from(texture.nearest(x, y)));
                if got != want {
                    self.failures.record(
                        || format!("{name} {wrap:?}: nearest{region}"),
                        || format!("{}: nearest {got:?} instead of {want:?}", what()),
                    );
                }
                let sampled = channels(texture.sample::<C>(x, y));
                if sampled != got {
                    self.failures.record(
                        || format!("{name} {wrap:?}: sample (nearest){region}"),
                        || {
                            format!(
                                "{}: sample (nearest) {sampled:?} but nearest {got:?}",
                                what()
                            )
                        },
                    );
                }

                let want = rt::bilinear(reference, ref_wrap, fx, fy);
                let got = channels(bilinear.bilinear::<C>(x, y));
                for k in 0..3 {
                    let error = (got[k] - want[k]).abs();
                    if !bottom {
                        self.worst = self.worst.max(error);
                    }
                    if error > 1.0 + MARGIN {
                        self.failures.record(
                            || format!("{name} {wrap:?}: bilinear{region}"),
                            || format!("{}: bilinear {got:?} instead of {want:?}", what()),
                        );
                        break;
                    }
                }
                let sampled = channels(bilinear.sample::<C>(x, y));
                if sampled != got {
                    self.failures.record(
                        || format!("{name} {wrap:?}: sample (bilinear){region}"),
                        || {
                            format!(
                                "{}: sample (bilinear) {sampled:?} but bilinear {got:?}",
                                what()
                            )
                        },
                    );
                }
                self.samples += 1;
            }
        }
    }
}

/// `Texture::nearest` (and `sample` with nearest filtering) reads exactly the reference's
/// texel, and `Texture::bilinear` (and `sample` with bilinear filtering) is within 1 LSB per
/// channel of the reference's exact blend, at 16.16 coordinates anywhere in the `i32` range
/// (several periods either way, texel centres and boundaries, the ends of the range), for
/// every source, random and smooth texels, and every pair of wrap modes.
#[test]
fn samplers_match_the_reference() {
    let mut coordinates = Rng(0x7e47_5a01);
    let mut check = Samplers {
        rng: &mut coordinates,
        failures: Failures::default(),
        samples: 0,
        worst: 0.0,
    };
    let mut textures = Rng(0x7e47_5a02);
    each_texture(&mut textures, false, &mut check);
    each_texture(&mut textures, true, &mut check);
    println!(
        "{} samples, worst bilinear error {:.4} LSB (above −32,767.5 texels)",
        check.samples, check.worst
    );
    check.failures.assert_none();
    // 2 × 6 textures × 9 wrap pairs.
    assert_eq!(check.samples, 2 * 6 * 9 * SAMPLES);
}

// ---------------------------------------------------------------------------------------------
// Triangles
// ---------------------------------------------------------------------------------------------

/// Kinds of random triangle positions ([`positions`]): every kind, those of nonzero area
/// (almost always: the last two kinds are zero-area), and those at least about the screen's
/// size (so that a texel coordinate changes by a small part of its spread from one pixel to
/// the next).
const ALL_KINDS: &[u64] = &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12];
const AREA_KINDS: &[u64] = &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10];
const LARGE_KINDS: &[u64] = &[4, 5, 6, 7];

/// Raw (sub-pixel) vertex positions of kind `kind`.
fn positions(rng: &mut Rng, kind: u64) -> [(i32, i32); 3] {
    let v: [(i64, i64); 3] = match kind {
        // Sub-pixel.
        0 => RAW.cluster(rng, 2, (1, 300)),
        // Up to a dozen pixels.
        1 | 2 => RAW.cluster(rng, 4, (128, 256 * 12)),
        // Narrow: 1 to 2 pixels wide, up to a dozen tall (spans of one or two pixels).
        3 => {
            let a = RAW.point(rng, 2);
            let w = rng.range(256, 512);
            let mut y = || a.1 + rng.range(-256 * 12, 256 * 12);
            let (y1, y2) = (y(), y());
            let x = a.0 + rng.range(0, w);
            [a, (a.0 + w, y1), (x, y2)]
        }
        // About the screen's size, partly off it.
        4 | 5 => [(); 3].map(|_| RAW.point(rng, i64::from(W) / 2)),
        // Ten times the screen.
        6 => [(); 3].map(|_| RAW.point(rng, 10 * i64::from(W))),
        // Up to ±2²² pixels (raw ±2³⁰) around the screen.
        7 => [(); 3].map(|_| {
            let r = 1i64 << rng.range(8, 30);
            (rng.range(-r, r), rng.range(-r, r))
        }),
        // One vertex on the screen, the others anywhere up to the ends of the range.
        8 => [
            RAW.point(rng, 1),
            (extreme(rng), extreme(rng)),
            (extreme(rng), extreme(rng)),
        ],
        // Slivers: the third vertex near the line through the first two.
        9 => {
            let a = RAW.point(rng, 8);
            sliver(rng, a, 28)
        }
        // Edges through pixel centres and corners.
        10 => [(); 3].map(|_| RAW.snapped_per_axis(rng, 6)),
        // Exactly collinear: a + s·d and a + t·d (any of them may coincide).
        11 => {
            let a = RAW.point(rng, 8);
            let m = 1i64 << rng.range(0, 20);
            let d = (rng.range(-m, m), rng.range(-m, m));
            let (s, t) = (rng.range(-40, 40), rng.range(-40, 40));
            [
                a,
                (a.0 + s * d.0, a.1 + s * d.1),
                (a.0 + t * d.0, a.1 + t * d.1),
            ]
        }
        // Two vertices the same, the third anywhere.
        _ => {
            let a = RAW.point(rng, 8);
            [a, a, (rng.any_scale(), rng.any_scale())]
        }
    };
    v.map(|(x, y)| (x.clamp(MIN, MAX) as i32, y.clamp(MIN, MAX) as i32))
}

/// Whether the raw triangle has zero area (exactly, in `i128`).
fn zero_area(v: [(i32, i32); 3]) -> bool {
    let d = |a: (i32, i32), b: (i32, i32)| {
        (
            i128::from(b.0) - i128::from(a.0),
            i128::from(b.1) - i128::from(a.1),
        )
    };
    let (e, f) = (d(v[0], v[1]), d(v[0], v[2]));
    e.0 * f.1 - e.1 * f.0 == 0
}

/// A texel coordinate in texels as 16.16 bits, rounded and kept inside `i32`.
fn texel_bits(t: f64) -> i32 {
    (t * UNIT).round().clamp(MIN as f64, MAX as f64) as i32
}

/// Texel coordinates (16.16 bits, `[u, v]` per vertex) for vertices `p` whose spread on each
/// axis is at most [`MAX_SPREAD`] texels: an affine map of the position (magnifying or
/// minifying, sheared, offset by several periods), or coordinates near a random centre.
fn moderate_texels(rng: &mut Rng, p: [(i32, i32); 3]) -> [[i32; 2]; 3] {
    let spread = |c: [i32; 2], d: [i32; 2], e: [i32; 2], k: usize| {
        let v = [c[k], d[k], e[k]].map(f64::from);
        (v.iter().fold(f64::MIN, |a, &b| a.max(b)) - v.iter().fold(f64::MAX, |a, &b| a.min(b)))
            / UNIT
    };
    if rng.chance(2) {
        // Texels per pixel from 1/32 to 4, either sign, with a shear of up to as much.
        let scale = |rng: &mut Rng| {
            let s = 2f64.powf(rng.range_f64(-5.0, 2.0));
            if rng.chance(2) {
                -s
            } else {
                s
            }
        };
        let (a, b) = (scale(rng), scale(rng) * rng.unit());
        let (c, d) = (scale(rng) * rng.unit(), scale(rng));
        let (ou, ov) = (rng.range_f64(-300.0, 300.0), rng.range_f64(-300.0, 300.0));
        let t = p.map(|(x, y)| {
            let (x, y) = (f64::from(x) / 256.0, f64::from(y) / 256.0);
            [
                texel_bits(a * x + b * y + ou),
                texel_bits(c * x + d * y + ov),
            ]
        });
        if (0..2).all(|k| spread(t[0], t[1], t[2], k) <= MAX_SPREAD) {
            return t;
        }
    }
    // Near a centre a few periods of the largest texture (64 texels) away, spread 2⁻⁶ to 2⁹
    // texels on each axis.
    let centre = [0; 2].map(|_| rng.range_f64(-700.0, 700.0));
    let half = [0; 2].map(|_| 2f64.powf(rng.range_f64(-6.0, 9.0)) / 2.0);
    [(); 3]
        .map(|_| core::array::from_fn(|k| texel_bits(centre[k] + rng.range_f64(-half[k], half[k]))))
}

/// Texel coordinates of any size, up to the ends of `I16F16`.
fn extreme_texels(rng: &mut Rng, p: [(i32, i32); 3]) -> [[i32; 2]; 3] {
    match rng.below(3) {
        0 => moderate_texels(rng, p),
        1 => [(); 3].map(|_| [0; 2].map(|_| extreme(rng).clamp(MIN, MAX) as i32)),
        _ => {
            // Spread over the whole range on one axis, moderate on the other.
            let mut t = moderate_texels(rng, p);
            let k = rng.below(2) as usize;
            for c in &mut t {
                c[k] = rng.next() as i32;
            }
            t
        }
    }
}

fn vertices(p: [(i32, i32); 3], t: [[i32; 2]; 3]) -> [TexturedVertex; 3] {
    core::array::from_fn(|k| TexturedVertex {
        x: Coord::from_bits(p[k].0),
        y: Coord::from_bits(p[k].1),
        u: TexelCoord::from_bits(t[k][0]),
        v: TexelCoord::from_bits(t[k][1]),
    })
}

/// A target with nothing but `draw_iter`: embedded-graphics' default `fill_contiguous` hands
/// it one `Pixel` at a time.
struct PixelTarget<C> {
    pixels: Vec<C>,
}

impl<C: PixelColor> OriginDimensions for PixelTarget<C> {
    fn size(&self) -> Size {
        Size::new(W, H)
    }
}

impl<C: PixelColor> DrawTarget for PixelTarget<C> {
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        for Pixel(p, c) in pixels {
            assert!(
                (0..W as i32).contains(&p.x) && (0..H as i32).contains(&p.y),
                "pixel {p:?} outside the screen"
            );
            self.pixels[(p.y as u32 * W + p.x as u32) as usize] = c;
        }
        Ok(())
    }
}

/// What the triangle checks saw, summed over triangles.
#[derive(Debug, Default)]
struct Stats {
    triangles: usize,
    /// Zero-area triangles (the reference covers nothing of them).
    zero_area: usize,
    /// Triangles that covered a pixel of the screen.
    drawn: usize,
    /// Pixels covered (by the reference).
    covered: usize,
    /// Covered pixels whose colour was compared with the reference.
    checked: usize,
    /// Covered pixels of nearest filtering not compared: the reference coordinate within the
    /// accuracy bound of a texel boundary, where either texel is right.
    excluded: usize,
    /// Largest deviation of a bilinear channel from the reference at the exact coordinate
    /// (LSB), and the largest tolerance that allowed (from the neighbour differences).
    worst_bilinear: f64,
    widest_tolerance: f64,
}

/// The reference bilinear blend's range of channel values over the box `[x ± bx] × [y ± by]`.
/// The blend is bilinear between texel centres (half-integer coordinates), so its extremes over
/// the box lie at the box's corners and where the centre lines cross its sides.
fn bilinear_range(
    t: &RefTexture,
    wrap: [RefWrap; 2],
    (x, y): (f64, f64),
    (bx, by): (f64, f64),
) -> ([f64; 3], [f64; 3]) {
    let stops = |c: f64, b: f64| {
        let (lo, hi) = (c - b, c + b);
        let mut s = vec![lo, hi];
        let mut k = (lo - 0.5).ceil();
        while k + 0.5 < hi {
            s.push(k + 0.5);
            k += 1.0;
        }
        s
    };
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for &sx in &stops(x, bx) {
        for &sy in &stops(y, by) {
            let c = rt::bilinear(t, wrap, sx, sy);
            for k in 0..3 {
                lo[k] = lo[k].min(c[k]);
                hi[k] = hi[k].max(c[k]);
            }
        }
    }
    (lo, hi)
}

/// Draws the textured triangle `vertices` every way and checks it against the reference:
///
/// * `draw_into` over two backgrounds that differ at every pixel: the pixels where the two
///   results agree (those written) must be exactly those the reference covers;
/// * `Drawable::draw` into a `SliceFramebuffer` and into a `draw_iter` target: the same frame;
/// * at each covered pixel, the texture sampled at the exact texel coordinate, to the
///   documented accuracy `b = s + 1/128` per axis: with nearest filtering the reference texel
///   exactly unless the coordinate is within `b` of a texel boundary; with bilinear filtering
///   within 1 LSB of the reference's range over the box `±b` around the coordinate, and within
///   `1 + D·b` (summed over the axes, `D` the largest neighbour difference) of its value there.
fn check_triangle<S, C>(
    rng: &mut Rng,
    name: &str,
    (texture, reference, wrap, difference): (&Texture<S>, &RefTexture, [RefWrap; 2], Differences),
    vertices: [TexturedVertex; 3],
    accuracy: bool,
    stats: &mut Stats,
    failures: &mut Failures,
) where
    S: TexelSource + Copy + Debug,
    C: GouraudColor + From<S::Color> + Debug,
{
    let triangle = TexturedTriangle::<S, C>::new(vertices, texture);
    let what = || {
        format!(
            "{name} {:?} {:?}, triangle {vertices:?}",
            texture.wrap(),
            texture.filter()
        )
    };
    let raw = vertices.map(|v| (v.x.to_bits(), v.y.to_bits()));
    let uv = vertices.map(|v| {
        [
            f64::from(v.u.to_bits()) / UNIT,
            f64::from(v.v.to_bits()) / UNIT,
        ]
    });
    let spread = |k: usize| {
        let c = uv.map(|c| c[k]);
        c.iter().fold(f64::MIN, |a, &b| a.max(b)) - c.iter().fold(f64::MAX, |a, &b| a.min(b))
    };
    // Failures are reported apart for triangles whose texel coordinates change by half their
    // spread or more from one pixel to the next along a row (from the reference's exact
    // planes).
    let steep = {
        let channels = uv.map(|c| [c[0], c[1], 0.0]);
        let at = |x| reference::interpolate(raw, channels, x, 0);
        match (at(0), at(1)) {
            (Some(a), Some(b)) => (0..2).any(|k| (b[k] - a[k]).abs() >= spread(k) / 2.0),
            _ => false,
        }
    };
    let key = |check: &str| {
        let steep = if steep {
            " (a step of half the spread or more a pixel)"
        } else {
            ""
        };
        format!(
            "{name} {:?} {:?}: {check}{steep}",
            texture.wrap(),
            texture.filter()
        )
    };
    let background: Vec<C> = (0..PIXELS).map(|_| rng.uniform_color()).collect();
    // Channel 0 changed at every pixel (every format here has at least 5 bits of it).
    let other: Vec<C> = background
        .iter()
        .map(|&c| {
            let mut ch = c.channels();
            let n = u64::from(C::MAX[0]) + 1;
            ch[0] = ((u64::from(ch[0]) + 1 + rng.below(n - 1)) % n) as u8;
            C::from_channels(ch)
        })
        .collect();

    let mut first = background.clone();
    triangle.draw_into(&mut SliceFramebuffer::new(&mut first, W, H).unwrap());
    let mut second = other;
    triangle.draw_into(&mut SliceFramebuffer::new(&mut second, W, H).unwrap());

    let mut drawn = background.clone();
    let Ok(()) = triangle.draw(&mut SliceFramebuffer::new(&mut drawn, W, H).unwrap());
    let mut plain = PixelTarget {
        pixels: background.clone(),
    };
    let Ok(()) = triangle.draw(&mut plain);
    for (path, pixels) in [
        ("draw (SliceFramebuffer)", &drawn),
        ("draw (draw_iter)", &plain.pixels),
    ] {
        if let Some(i) = (0..PIXELS).find(|&i| pixels[i] != first[i]) {
            let (x, y) = (i as u32 % W, i as u32 / W);
            failures.record(
                || key(path),
                || {
                    format!(
                        "{}: {path} gives pixel ({x}, {y}) {:?}, draw_into {:?}",
                        what(),
                        pixels[i],
                        first[i]
                    )
                },
            );
        }
    }

    let exact = rt::perspective_texel_coords(raw, uv, [1.0; 3], 0, 0, W, H);
    stats.triangles += 1;
    stats.zero_area += usize::from(zero_area(raw));
    stats.drawn += usize::from(!exact.is_empty());
    stats.covered += exact.len();

    let mut covered = vec![false; PIXELS];
    for &(x, y, _) in &exact {
        covered[(y as u32 * W + x as u32) as usize] = true;
    }
    for i in 0..PIXELS {
        let written = first[i] == second[i];
        if written != covered[i] {
            let (x, y) = (i as u32 % W, i as u32 / W);
            let covers = reference::covers(raw, x as i32, y as i32);
            failures.record(
                || key("coverage"),
                || {
                    format!(
                        "{}: pixel ({x}, {y}) written {written}, covered by the reference {covers}",
                        what()
                    )
                },
            );
        }
    }

    // The accuracy bound per axis.
    let bound = |k: usize| (spread(k) / STEPS).max(1.0 / UNIT) + STEPPING + MARGIN;
    let (bu, bv) = (bound(0), bound(1));
    if !accuracy {
        return;
    }
    for &(x, y, [u, v]) in &exact {
        let got = channels(first[(y as u32 * W + x as u32) as usize]);
        let at = || {
            format!(
                "{}: pixel ({x}, {y}) at ({u}, {v}) texels ±({bu}, {bv})",
                what()
            )
        };
        match texture.filter() {
            Filter::Nearest => {
                if rt::boundary_distance(u, v) <= bu.max(bv) {
                    stats.excluded += 1;
                    continue;
                }
                let want = rt::nearest(reference, wrap, u, v);
                if got != want {
                    let texel = rt::nearest_texel(reference, wrap, u, v);
                    failures.record(
                        || key("texel"),
                        || format!("{}: {got:?} instead of texel {texel:?} {want:?}", at()),
                    );
                }
            }
            Filter::Bilinear => {
                let want = rt::bilinear(reference, wrap, u, v);
                let (lo, hi) = bilinear_range(reference, wrap, (u, v), (bu, bv));
                let (dx, dy) = difference;
                for k in 0..3 {
                    let tolerance = 1.0 + dx[k] * bu + dy[k] * bv + MARGIN;
                    let error = (got[k] - want[k]).abs();
                    stats.worst_bilinear = stats.worst_bilinear.max(error);
                    stats.widest_tolerance = stats.widest_tolerance.max(tolerance);
                    let outside = got[k] < lo[k] - 1.0 - MARGIN || got[k] > hi[k] + 1.0 + MARGIN;
                    if error > tolerance || outside {
                        failures.record(
                            || key("blend"),
                            || {
                                format!(
                                    "{}: {got:?}, the reference {want:?} (±{tolerance} LSB), over \
                                 the box {lo:?} to {hi:?}",
                                    at()
                                )
                            },
                        );
                        break;
                    }
                }
            }
        }
        stats.checked += 1;
    }
}

/// Texel coordinates (16.16 bits, `[u, v]` per vertex) for raw vertex positions.
type TexelsFor = fn(&mut Rng, [(i32, i32); 3]) -> [[i32; 2]; 3];

/// A run of random triangles over every texture and wrap pair.
#[derive(Clone, Copy)]
struct Run {
    seed: u64,
    /// Smooth textures (else random texels).
    smooth: bool,
    filter: Filter,
    /// The kinds of positions ([`positions`]) drawn from.
    kinds: &'static [u64],
    /// The vertices' texel coordinates for their positions.
    texels: TexelsFor,
    /// Whether the colours are checked (else only which pixels are written).
    accuracy: bool,
}

struct Triangles<'r> {
    rng: &'r mut Rng,
    run: Run,
    stats: Stats,
    failures: Failures,
    /// The largest neighbour difference of the textures seen (LSB).
    roughest: f64,
}

impl Visit for Triangles<'_> {
    fn visit<S, C>(&mut self, name: &str, texture: Texture<S>, reference: &RefTexture)
    where
        S: TexelSource + Copy + Debug,
        C: GouraudColor + From<S::Color> + Debug,
    {
        let difference = neighbour_difference(reference);
        let (dx, dy) = difference;
        self.roughest = dx.into_iter().chain(dy).fold(self.roughest, f64::max);
        let run = self.run;
        for (wrap, ref_wrap) in wrap_pairs() {
            let texture = texture.with_wrap(wrap[0], wrap[1]).with_filter(run.filter);
            for _ in 0..TRIANGLES_PER_WRAP {
                let kind = run.kinds[self.rng.below(run.kinds.len() as u64) as usize];
                let p = positions(self.rng, kind);
                let t = (run.texels)(self.rng, p);
                check_triangle::<S, C>(
                    self.rng,
                    name,
                    (&texture, reference, ref_wrap, difference),
                    vertices(p, t),
                    run.accuracy,
                    &mut self.stats,
                    &mut self.failures,
                );
            }
        }
    }
}

/// Runs `run`: checks its triangles, fails on any failure, and returns the statistics and the
/// largest neighbour difference of the textures.
fn run_triangles(run: Run) -> (Stats, f64) {
    let mut rng = Rng(run.seed);
    let mut check = Triangles {
        rng: &mut rng,
        run,
        stats: Stats::default(),
        failures: Failures::default(),
        roughest: 0.0,
    };
    let mut textures = Rng(run.seed ^ 0x7e47);
    each_texture(&mut textures, run.smooth, &mut check);
    println!("{:?}: {:#?}", run.filter, check.stats);
    check.failures.assert_none();
    // 6 textures × 9 wrap pairs.
    assert_eq!(check.stats.triangles, 6 * 9 * TRIANGLES_PER_WRAP);
    (check.stats, check.roughest)
}

/// Nearest filtering: random triangles of every size (sub-pixel, one or two pixels wide, to
/// ±2²² pixels, slivers, snapped), texel spreads up to 512 texels at up to 11 periods from the
/// origin, over every texture and wrap pair, write exactly the reference's pixels, each the
/// reference's texel at the exact coordinate wherever that is farther than the documented
/// bound from a texel boundary; and every drawing path gives the same frame.
#[test]
fn nearest_triangles_match_the_reference() {
    let (stats, _) = run_triangles(Run {
        seed: 0x7e47_0e01,
        smooth: false,
        filter: Filter::Nearest,
        kinds: AREA_KINDS,
        texels: moderate_texels,
        accuracy: true,
    });
    // Well below what this seed gives (over 60 % of the triangles reach the screen, about a
    // million pixels compared), so that the checks cannot pass on nearly nothing.
    assert!(stats.drawn > stats.triangles / 3, "{stats:?}");
    assert!(stats.checked > 500_000, "{stats:?}");
    // The bound is at most 0.0235 texel here (4.7 % of uniformly placed coordinates within it of
    // a boundary on an axis), and far less for most triangles' narrower spreads.
    assert!(stats.excluded * 20 < stats.covered, "{stats:?}");
}

/// Bilinear filtering on random and on smooth textures (neighbours at most a few LSB apart):
/// random triangles write exactly the reference's pixels, each within 1 LSB of the reference
/// blend's range over the accuracy box around the exact coordinate and within 1 LSB plus the
/// neighbour difference times the bound of the blend at the exact coordinate.
#[test]
fn bilinear_triangles_match_the_reference() {
    let run = Run {
        seed: 0x7e47_b101,
        smooth: true,
        filter: Filter::Bilinear,
        kinds: AREA_KINDS,
        texels: moderate_texels,
        accuracy: true,
    };
    let (smooth, roughest) = run_triangles(run);
    // The smooth fields' neighbours differ by at most `SMOOTH_STEP` + 1 (rounding), and a
    // palette gradient's colours by one step per index: the tolerance stays near 1 LSB
    // (1 + 3 · 2 · 0.0235).
    assert!(roughest <= SMOOTH_STEP + 1.0, "{roughest}");
    assert!(smooth.widest_tolerance < 1.1, "{smooth:?}");
    let (random, _) = run_triangles(Run {
        seed: 0x7e47_b102,
        smooth: false,
        ..run
    });
    for stats in [smooth, random] {
        // As for nearest filtering: well below what the seeds give.
        assert!(stats.drawn > stats.triangles / 3, "{stats:?}");
        assert!(stats.checked > 500_000, "{stats:?}");
    }
}

/// Texel coordinates spread over 2⁹ to 2¹⁶ texels on each axis (the planes' vertex values then
/// step by 2⁻⁷ to 1 texel), an affine map of the position, on triangles about the screen's size
/// or larger.
fn wide_texels(rng: &mut Rng, p: [(i32, i32); 3]) -> [[i32; 2]; 3] {
    let p = p.map(|(x, y)| (f64::from(x) / 256.0, f64::from(y) / 256.0));
    let axis = |rng: &mut Rng| {
        let (a, b) = (rng.range_f64(-1.0, 1.0), rng.range_f64(-1.0, 1.0));
        let raw = p.map(|(x, y)| a * x + b * y);
        let lo = raw.iter().fold(f64::MAX, |m, &c| m.min(c));
        let hi = raw.iter().fold(f64::MIN, |m, &c| m.max(c));
        // Just inside the `I16F16` range.
        let spread = 2f64.powf(rng.range_f64(9.0, 16.0)).min(65_535.0);
        let scale = if hi > lo { spread / (hi - lo) } else { 0.0 };
        let offset = rng.range_f64(-32_767.0, 32_767.0 - spread);
        raw.map(|c| offset + (c - lo) * scale)
    };
    let (u, v) = (axis(rng), axis(rng));
    core::array::from_fn(|k| [texel_bits(u[k]), texel_bits(v[k])])
}

/// The documented accuracy holds for wide texel spreads too: nearest filtering on triangles
/// about the screen's size and larger whose texel coordinates spread over 2⁹ to 2¹⁶ texels (so
/// that a coordinate changes by a small part of its spread from pixel to pixel) gives the
/// reference's texel wherever the exact coordinate is farther than `s + 1/128` from a texel
/// boundary.
#[test]
fn wide_texel_spreads_keep_the_documented_accuracy() {
    let (stats, _) = run_triangles(Run {
        seed: 0x7e47_1d01,
        smooth: false,
        filter: Filter::Nearest,
        kinds: LARGE_KINDS,
        texels: wide_texels,
        accuracy: true,
    });
    // The bound is 0.0235 to 2 texels: many pixels are excluded, but still far more than
    // this many compared (well below what the seed gives).
    assert!(stats.drawn > stats.triangles / 3, "{stats:?}");
    assert!(stats.checked > 300_000, "{stats:?}");
}

/// Robustness: vertices anywhere in the `Coord` range, exactly collinear and coincident ones,
/// texel coordinates up to the ends of `I16F16` (spreads of the whole range), both filters:
/// nothing panics (overflow checks are on), exactly the reference's pixels are written (none
/// for zero-area triangles) and every path gives the same frame.
#[test]
fn extreme_triangles_draw_only_their_pixels() {
    for (seed, filter) in [
        (0x7e47_e001, Filter::Nearest),
        (0x7e47_e002, Filter::Bilinear),
    ] {
        let (stats, _) = run_triangles(Run {
            seed,
            smooth: false,
            filter,
            kinds: ALL_KINDS,
            texels: extreme_texels,
            accuracy: false,
        });
        // Two kinds in 13 are zero-area (15 % of the triangles); and enough triangles drawn
        // and pixels covered (well below what the seeds give: half the triangles, 850 000
        // pixels).
        assert!(stats.zero_area > stats.triangles / 10, "{stats:?}");
        assert!(stats.drawn > stats.triangles / 4, "{stats:?}");
        assert!(stats.covered > 300_000, "{stats:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// Every path
// ---------------------------------------------------------------------------------------------

/// Scenes per texture, and triangles per scene (painter's order: later ones over earlier).
const SCENES: usize = 12;
const SCENE_TRIANGLES: usize = 6;
/// Band heights: a row, dividing the screen's 48 rows or not (a short last band), the whole.
const BAND_ROWS: [u32; 5] = [1, 3, 7, 8, 48];

struct Paths<'r> {
    rng: &'r mut Rng,
    failures: Failures,
    scenes: usize,
    /// Pixels the scenes changed from their backgrounds.
    changed: usize,
}

impl Visit for Paths<'_> {
    fn visit<S, C>(&mut self, name: &str, texture: Texture<S>, _reference: &RefTexture)
    where
        S: TexelSource + Copy + Debug,
        C: GouraudColor + From<S::Color> + Debug,
    {
        let rng = &mut *self.rng;
        let variants: Vec<Texture<S>> = wrap_pairs()
            .flat_map(|(w, _)| {
                [Filter::Nearest, Filter::Bilinear]
                    .map(|f| texture.with_wrap(w[0], w[1]).with_filter(f))
            })
            .collect();
        for _ in 0..SCENES {
            let scene: Vec<TexturedTriangle<'_, S, C>> = (0..SCENE_TRIANGLES)
                .map(|_| {
                    let kind = ALL_KINDS[rng.below(ALL_KINDS.len() as u64) as usize];
                    let p = positions(rng, kind);
                    let t = if rng.chance(4) {
                        extreme_texels(rng, p)
                    } else {
                        moderate_texels(rng, p)
                    };
                    let texture = &variants[rng.below(variants.len() as u64) as usize];
                    TexturedTriangle::new(vertices(p, t), texture)
                })
                .collect();
            let what = || format!("{name}, scene {scene:?}");
            let background: Vec<C> = (0..PIXELS).map(|_| rng.uniform_color()).collect();

            let mut want = background.clone();
            let mut fb = SliceFramebuffer::new(&mut want, W, H).unwrap();
            for t in &scene {
                t.draw_into(&mut fb);
            }
            self.changed += (0..PIXELS).filter(|&i| want[i] != background[i]).count();
            self.scenes += 1;

            let mut frames: Vec<(String, Vec<C>)> = Vec::new();
            let mut drawn = background.clone();
            let mut fb = SliceFramebuffer::new(&mut drawn, W, H).unwrap();
            for t in &scene {
                let Ok(()) = t.draw(&mut fb);
            }
            frames.push(("draw (SliceFramebuffer)".into(), drawn));
            let mut plain = PixelTarget {
                pixels: background.clone(),
            };
            for t in &scene {
                let Ok(()) = t.draw(&mut plain);
            }
            frames.push(("draw (draw_iter)".into(), plain.pixels));

            for rows in BAND_ROWS {
                for double in [false, true] {
                    let layout = BandLayout::new(Size::new(W, H), rows).unwrap();
                    let mut front = vec![C::from_channels([0; 3]); layout.buffer_len()];
                    let mut back = front.clone();
                    let mut bands = if double {
                        ColorBands::double(layout, &mut front, &mut back).unwrap()
                    } else {
                        ColorBands::new(layout, &mut front).unwrap()
                    };
                    let mut frame = vec![C::from_channels([0; 3]); PIXELS];
                    let mut output = Callback(|area: &Rectangle, pixels: &[C]| {
                        let start = (area.top_left.y as u32 * W) as usize;
                        frame[start..start + pixels.len()].copy_from_slice(pixels);
                        Ok::<(), Infallible>(())
                    });
                    bands
                        .render(&mut output, |band| {
                            let area = band.rect();
                            let start = (area.top_left.y as u32 * W) as usize;
                            let len = (area.size.width * area.size.height) as usize;
                            let Ok(()) = band.fill_contiguous(
                                &area,
                                background[start..start + len].iter().copied(),
                            );
                            band.draw_all(&scene);
                        })
                        .unwrap();
                    let kind = if double { "double" } else { "single" };
                    frames.push((format!("bands of {rows} rows ({kind} buffer)"), frame));
                }
            }

            for (path, frame) in &frames {
                if let Some(i) = (0..PIXELS).find(|&i| frame[i] != want[i]) {
                    let (x, y) = (i as u32 % W, i as u32 / W);
                    self.failures.record(
                        || format!("{name}: {path}"),
                        || {
                            format!(
                                "{}: {path} gives pixel ({x}, {y}) {:?}, draw_into {:?}",
                                what(),
                                frame[i],
                                want[i]
                            )
                        },
                    );
                }
            }
        }
    }
}

/// Every path draws the same pixels: scenes of textured triangles (every wrap pair and both
/// filters, every size class, moderate and extreme texel coordinates) over random backgrounds,
/// drawn with `draw_into`, with `Drawable::draw` into a `SliceFramebuffer` and into a
/// `draw_iter` target, and in bands of 1, 3, 7, 8 and 48 rows (one buffer and two) gathered by
/// a `Callback` output, give the same frame.
#[test]
fn every_path_draws_the_same_pixels() {
    let mut rng = Rng(0x7e47_9a01);
    let mut check = Paths {
        rng: &mut rng,
        failures: Failures::default(),
        scenes: 0,
        changed: 0,
    };
    let mut textures = Rng(0x7e47_9a02);
    each_texture(&mut textures, false, &mut check);
    println!("{} scenes, {} pixels changed", check.scenes, check.changed);
    check.failures.assert_none();
    assert_eq!(check.scenes, 6 * SCENES);
    // About a third of each frame, far more than this, so that the comparisons compare drawn
    // pixels.
    assert!(
        check.changed > check.scenes * PIXELS / 10,
        "{}",
        check.changed
    );
}
