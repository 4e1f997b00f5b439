//! Every way of drawing a triangle writes the same colour to the same pixel.
//!
//! For random Gouraud triangles over a random background, in every colour format that implements
//! `GouraudColor`, five framebuffers must come out equal pixel for pixel:
//!
//! * `Drawable::draw` into a [`SliceFramebuffer`] (its `fill_contiguous` writes slices),
//! * `Drawable::draw` into a target that only implements `draw_iter` (embedded-graphics' own
//!   `fill_contiguous`, one `Pixel` at a time),
//! * `GouraudTriangle::draw_into` (the colour format's packed span loop, tiny rows on x86-64),
//! * `GouraudTriangle::draw_into_compact` when it takes the triangle (else nothing drawn),
//! * the public `shaded_spans` iterator written out here, pixel by pixel; each span's
//!   `SpanColors::fill` must also give the colours of its iteration, from any point of it.
//!
//! Likewise `SolidTriangle::draw` into both targets, `draw_into` and its `spans` written out.
//!
//! Triangles range from sub-pixel to many times the target, far off-screen and up to the whole
//! `Coord` range, slivers and snapped vertices; targets from one pixel to rows over 2¹⁶ pixels,
//! whose huge regions take the exact per-row path. The accuracy of the colours is checked against
//! the f64 reference by `coverage_random`, `proptest_raster` and `watertight`; this suite checks
//! that the paths agree bit for bit.

use std::fmt::Debug;

use embedded_graphics::pixelcolor::{
    Bgr555, Bgr565, Bgr666, Bgr888, BinaryColor, Gray2, Gray4, Gray8, Rgb555, Rgb565, Rgb666,
    Rgb888,
};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;
use embedded_raster::{
    Coord, GouraudColor, GouraudTriangle, SliceFramebuffer, SolidTriangle, SpanColors, Vertex,
};

use crate::rng;
use rng::Rng;

use crate::raw_points;
use raw_points::{extreme, sliver, Screen, MAX, MIN};

/// The targets (width, height) and how many triangles each gets per colour format. The 320-pixel
/// rows hold spans beyond the 5-6-5 loop's restart period (128 pixels); the last target's rows
/// are wider than 2¹⁶ pixels, so triangles across it take the exact path in chunks.
const TARGETS: [(u32, u32, usize); 5] = [
    (1, 1, 300),
    (7, 5, 1200),
    (64, 48, 2000),
    (320, 40, 600),
    (65_600, 2, 120),
];

/// A random triangle for a `w × h` target, raw sub-pixel coordinates.
fn triangle(rng: &mut Rng, w: u32, h: u32) -> [(Coord, Coord); 3] {
    let (wi, hi) = (i64::from(w), i64::from(h));
    let screen = Screen::new(wi, hi);
    let v: [(i64, i64); 3] = match rng.below(11) {
        // Sub-pixel.
        0 => screen.cluster(rng, 2, (1, 300)),
        // Up to a dozen pixels (the tiny rows on x86-64 take those under 8 × 8).
        1 | 2 => screen.cluster(rng, 4, (128, 256 * 12)),
        // About the target's size, partly off it.
        3 => [(); 3].map(|_| screen.point_xy(rng, (wi / 2 + 2, hi / 2 + 2))),
        // Ten times the target.
        4 => [(); 3].map(|_| screen.point_xy(rng, (10 * wi, 10 * hi))),
        // Any magnitude, far off-screen and huge.
        5 => [(); 3].map(|_| (rng.any_scale(), rng.any_scale())),
        // One vertex on the target, the others anywhere up to the ends of the range.
        6 => {
            let a = screen.point(rng, 1);
            [
                a,
                (extreme(rng), extreme(rng)),
                (extreme(rng), extreme(rng)),
            ]
        }
        // Slivers: the third vertex near the line through the first two.
        7 => {
            let a = screen.point(rng, 8);
            sliver(rng, a, 28)
        }
        // Long slivers a raw unit or two wide, across the target or out to the range's ends.
        8 => {
            let a = screen.snapped_per_axis(rng, 20);
            let b = if rng.chance(3) {
                (extreme(rng), extreme(rng))
            } else {
                screen.snapped_per_axis(rng, 20)
            };
            [a, b, (b.0 + rng.range(-2, 2), b.1 + rng.range(-2, 2))]
        }
        // Across the target: from left of it to right of it (on the widest target the region
        // then exceeds 2¹⁶ pixels).
        9 => {
            let near = |rng: &mut Rng, y: i64| y + rng.range(-4 * hi * 256, 4 * hi * 256);
            let a = (rng.range(-wi * 64, 0), near(rng, hi * 128));
            let b = (rng.range(wi * 256, wi * 320), near(rng, hi * 128));
            [a, b, screen.point_xy(rng, (wi / 4, 2 * hi))]
        }
        // Snapped to corners and centres: edges through pixel centres.
        _ => [(); 3].map(|_| screen.snapped_per_axis(rng, 6)),
    };
    v.map(|(x, y)| {
        (
            Coord::from_bits(x.clamp(MIN, MAX) as i32),
            Coord::from_bits(y.clamp(MIN, MAX) as i32),
        )
    })
}

/// A colour with random channels, often at their ends (where rounding meets the range's
/// limits).
fn color<C: GouraudColor>(rng: &mut Rng) -> C {
    C::from_channels(core::array::from_fn(|k| {
        let max = C::MAX[k];
        match rng.below(6) {
            0 => 0,
            1 => max,
            _ => rng.below(u64::from(max) + 1) as u8,
        }
    }))
}

/// A target with nothing but `draw_iter`: embedded-graphics' default `fill_contiguous` and
/// `fill_solid` hand it one `Pixel` at a time.
struct PixelTarget<C> {
    width: u32,
    height: u32,
    pixels: Vec<C>,
}

impl<C: PixelColor> OriginDimensions for PixelTarget<C> {
    fn size(&self) -> Size {
        Size::new(self.width, self.height)
    }
}

impl<C: PixelColor> DrawTarget for PixelTarget<C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            assert!(
                (0..self.width as i32).contains(&p.x) && (0..self.height as i32).contains(&p.y),
                "pixel {p:?} outside the {} × {} target",
                self.width,
                self.height
            );
            self.pixels[p.y as usize * self.width as usize + p.x as usize] = c;
        }
        Ok(())
    }
}

/// How often the cases that decide which path draws came up, over all formats.
#[derive(Debug, Default)]
struct Counts {
    triangles: usize,
    /// Triangles that covered at least one pixel.
    drawn: usize,
    pixels: usize,
    /// Drawn triangles whose bounding box is under 8 × 8 pixels (tiny rows on x86-64).
    tiny: usize,
    /// Drawn triangles whose bounding box is 2048 pixels or more (the general set-up).
    wide: usize,
    /// Drawn triangles whose bounding box clipped to the target exceeds 2¹⁶ pixels
    /// (`width + height`): the exact path.
    exact: usize,
    /// Spans longer than the 5-6-5 loop's restart period (128 pixels).
    long_spans: usize,
    /// Spans `shaded_spans` handed out in more than one chunk (over 4096 pixels).
    chunked_spans: usize,
    /// `draw_into_compact` calls that drew (`Ok`) and that declined (`TooLarge`).
    compact: usize,
    too_large: usize,
}

/// The triangle's pixel bounding box `(x0, y0, x1, y1)`, half-open.
fn bounding_box(points: &[(Coord, Coord); 3]) -> (i64, i64, i64, i64) {
    let xs = points.map(|p| i64::from(p.0.to_bits()));
    let ys = points.map(|p| i64::from(p.1.to_bits()));
    let lo = |v: [i64; 3]| v.into_iter().min().unwrap_or(0).div_euclid(256);
    let hi = |v: [i64; 3]| (v.into_iter().max().unwrap_or(0) + 255).div_euclid(256);
    (lo(xs), lo(ys), hi(xs), hi(ys))
}

/// The first pixel where `got` differs from `want`, if any.
fn first_difference<C: PartialEq + Copy>(want: &[C], got: &[C], width: u32) -> Option<(u32, u32)> {
    let i = want.iter().zip(got).position(|(a, b)| a != b)?;
    Some((i as u32 % width, i as u32 / width))
}

/// Failures seen, reported together at the end (a failing run shows how widespread a mismatch
/// is).
#[derive(Default)]
struct Failures {
    /// (format, path) → cases (triangles or spans) with differing pixels, differing pixels, the
    /// first example.
    seen: Vec<(String, usize, usize, String)>,
}

impl Failures {
    fn record<C: PartialEq + Copy + Debug>(
        &mut self,
        format: &str,
        path: &str,
        want: &[C],
        got: &[C],
        width: u32,
        what: impl FnOnce() -> String,
    ) {
        let Some((x, y)) = first_difference(want, got, width) else {
            return;
        };
        let pixels = want.iter().zip(got).filter(|(a, b)| a != b).count();
        let key = format!("{format}: {path}");
        let i = (y * width + x) as usize;
        match self.seen.iter_mut().find(|(k, ..)| *k == key) {
            Some((_, cases, total, _)) => {
                *cases += 1;
                *total += pixels;
            }
            None => self.seen.push((
                key,
                1,
                pixels,
                format!(
                    "{}: pixel ({x}, {y}) {:?} instead of {:?}",
                    what(),
                    got[i],
                    want[i]
                ),
            )),
        }
    }
}

/// Writes `colors` by hand from column `x` of row `y` and checks `SpanColors::fill` against the
/// iteration, whole and after `skip` colours.
#[allow(clippy::too_many_arguments)]
fn write_span<C: GouraudColor + Debug>(
    pixels: &mut [C],
    width: u32,
    (x, y, len): (i32, i32, u32),
    colors: SpanColors<C>,
    skip: usize,
    failures: &mut Failures,
    name: &str,
    what: impl Fn() -> String,
) {
    assert_eq!(colors.len(), len as usize);
    let all: Vec<C> = colors.clone().collect();
    assert_eq!(all.len(), len as usize);
    let n = all.len();
    let span = || format!("{}, span at ({x}, {y})", what());
    // Into a slice one longer than the span, prefilled with either end of the channel range:
    // the pixel past the span keeps its colour.
    for sentinel in [C::from_channels([0; 3]), C::from_channels(C::MAX)] {
        let mut want = all.clone();
        want.push(sentinel);
        let mut filled = vec![sentinel; n + 1];
        colors.clone().fill(&mut filled);
        failures.record(name, "SpanColors::fill", &want, &filled, n as u32 + 1, span);
    }
    let skip = skip.min(n);
    let mut rest = colors.clone();
    for _ in 0..skip {
        rest.next();
    }
    assert_eq!(rest.len(), n - skip);
    let mut tail = vec![C::from_channels([0; 3]); n - skip];
    rest.fill(&mut tail);
    failures.record(
        name,
        "SpanColors::fill after next()",
        &all[skip..],
        &tail,
        (n - skip).max(1) as u32,
        span,
    );

    let start = y as usize * width as usize + x as usize;
    for (px, c) in pixels[start..start + len as usize].iter_mut().zip(colors) {
        *px = c;
    }
}

fn check_format<C: GouraudColor + Debug>(
    name: &str,
    seed: u64,
    counts: &mut Counts,
    failures: &mut Failures,
) {
    let mut rng = Rng(seed);
    for (width, height, n) in TARGETS {
        let len = (width * height) as usize;
        let bounds = Rectangle::new(Point::zero(), Size::new(width, height));
        let mut background = vec![C::from_channels([0; 3]); len];
        let mut want = background.clone();
        let mut slice = background.clone();
        let mut plain = PixelTarget {
            width,
            height,
            pixels: background.clone(),
        };
        let mut into = background.clone();
        let mut compact = background.clone();
        for _ in 0..n {
            for px in &mut background {
                *px = color(&mut rng);
            }
            let points = triangle(&mut rng, width, height);
            let colors = [(); 3].map(|_| color::<C>(&mut rng));
            let gouraud = GouraudTriangle::new(
                [0, 1, 2].map(|k| Vertex::new(points[k].0, points[k].1, colors[k])),
            );
            let what = || format!("{width} × {height} target, triangle {gouraud:?}");

            // The public iterator, written out by hand: the expected image.
            want.copy_from_slice(&background);
            let mut spans = 0;
            let mut pixels = 0;
            let mut previous: Option<(i32, i32)> = None;
            for (span, span_colors) in gouraud.shaded_spans(&bounds) {
                assert!(
                    0 <= span.x_start
                        && span.x_start <= span.x_end
                        && span.x_end <= width as i32
                        && (0..height as i32).contains(&span.y),
                    "span {span:?} outside the target: {}",
                    what()
                );
                if previous == Some((span.y, span.x_start)) {
                    counts.chunked_spans += 1;
                }
                previous = Some((span.y, span.x_end));
                if span.len() > 128 {
                    counts.long_spans += 1;
                }
                spans += 1;
                pixels += span.len() as usize;
                let skip = rng.below(u64::from(span.len().min(300)) + 1) as usize;
                write_span(
                    &mut want,
                    width,
                    (span.x_start, span.y, span.len()),
                    span_colors,
                    skip,
                    failures,
                    name,
                    what,
                );
            }
            counts.triangles += 1;
            counts.pixels += pixels;
            if spans > 0 {
                counts.drawn += 1;
                let (x0, y0, x1, y1) = bounding_box(&points);
                if x1 - x0 < 8 && y1 - y0 < 8 {
                    counts.tiny += 1;
                }
                if x1 - x0 >= 2048 || y1 - y0 >= 2048 {
                    counts.wide += 1;
                }
                let clipped = (x1.min(i64::from(width)) - x0.max(0))
                    + (y1.min(i64::from(height)) - y0.max(0));
                if clipped > 1 << 16 {
                    counts.exact += 1;
                }
            }

            slice.copy_from_slice(&background);
            let mut fb = SliceFramebuffer::new(&mut slice, width, height).unwrap();
            let Ok(()) = gouraud.draw(&mut fb);
            failures.record(
                name,
                "Gouraud draw (SliceFramebuffer)",
                &want,
                &slice,
                width,
                what,
            );

            plain.pixels.copy_from_slice(&background);
            let Ok(()) = gouraud.draw(&mut plain);
            failures.record(
                name,
                "Gouraud draw (draw_iter)",
                &want,
                &plain.pixels,
                width,
                what,
            );

            into.copy_from_slice(&background);
            gouraud.draw_into(&mut SliceFramebuffer::new(&mut into, width, height).unwrap());
            failures.record(name, "Gouraud draw_into", &want, &into, width, what);

            compact.copy_from_slice(&background);
            let mut fb = SliceFramebuffer::new(&mut compact, width, height).unwrap();
            match gouraud.draw_into_compact(&mut fb) {
                Ok(()) => {
                    counts.compact += 1;
                    failures.record(
                        name,
                        "Gouraud draw_into_compact",
                        &want,
                        &compact,
                        width,
                        what,
                    );
                }
                Err(_) => {
                    counts.too_large += 1;
                    failures.record(
                        name,
                        "Gouraud draw_into_compact (TooLarge: nothing drawn)",
                        &background,
                        &compact,
                        width,
                        what,
                    );
                }
            }

            // Solid: one colour, the same pixels every way.
            let solid = SolidTriangle::new(points, colors[0]);
            let what = || format!("{width} × {height} target, triangle {solid:?}");
            want.copy_from_slice(&background);
            for span in solid.spans(&bounds) {
                let start = span.y as usize * width as usize;
                want[start + span.x_start as usize..start + span.x_end as usize].fill(solid.color);
            }
            slice.copy_from_slice(&background);
            let Ok(()) = solid.draw(&mut SliceFramebuffer::new(&mut slice, width, height).unwrap());
            failures.record(
                name,
                "Solid draw (SliceFramebuffer)",
                &want,
                &slice,
                width,
                what,
            );
            plain.pixels.copy_from_slice(&background);
            let Ok(()) = solid.draw(&mut plain);
            failures.record(
                name,
                "Solid draw (draw_iter)",
                &want,
                &plain.pixels,
                width,
                what,
            );
            into.copy_from_slice(&background);
            solid.draw_into(&mut SliceFramebuffer::new(&mut into, width, height).unwrap());
            failures.record(name, "Solid draw_into", &want, &into, width, what);
        }
    }
}

#[test]
fn every_path_draws_the_same_pixels() {
    let mut counts = Counts::default();
    let mut failures = Failures::default();
    let (c, f) = (&mut counts, &mut failures);
    check_format::<Rgb565>("Rgb565", 0x5a3e_0001, c, f);
    check_format::<Bgr565>("Bgr565", 0x5a3e_0002, c, f);
    check_format::<Rgb555>("Rgb555", 0x5a3e_0003, c, f);
    check_format::<Bgr555>("Bgr555", 0x5a3e_0004, c, f);
    check_format::<Rgb666>("Rgb666", 0x5a3e_0005, c, f);
    check_format::<Bgr666>("Bgr666", 0x5a3e_0006, c, f);
    check_format::<Rgb888>("Rgb888", 0x5a3e_0007, c, f);
    check_format::<Bgr888>("Bgr888", 0x5a3e_0008, c, f);
    check_format::<Gray2>("Gray2", 0x5a3e_0009, c, f);
    check_format::<Gray4>("Gray4", 0x5a3e_000a, c, f);
    check_format::<Gray8>("Gray8", 0x5a3e_000b, c, f);
    check_format::<BinaryColor>("BinaryColor", 0x5a3e_000c, c, f);
    println!("{counts:#?}");

    let report: Vec<String> = failures
        .seen
        .iter()
        .map(|(key, cases, pixels, example)| {
            format!("{key}: {cases} cases, {pixels} pixels differ; first: {example}")
        })
        .collect();
    assert!(report.is_empty(), "paths disagree:\n{}", report.join("\n"));

    // The cases that decide the path all came up.
    let formats = 12;
    let per_format = TARGETS.iter().map(|t| t.2).sum::<usize>();
    assert_eq!(counts.triangles, formats * per_format);
    assert!(counts.drawn > counts.triangles / 3, "{counts:?}");
    assert!(counts.tiny > 1_500, "{counts:?}");
    assert!(counts.wide > 3_000, "{counts:?}");
    assert!(counts.exact > 120, "{counts:?}");
    assert!(counts.long_spans > 20_000, "{counts:?}");
    assert!(counts.chunked_spans > 2_000, "{counts:?}");
    assert!(
        counts.compact > 25_000 && counts.too_large > 6_000,
        "{counts:?}"
    );
}

/// The 3D pipeline's depth-tested Gouraud fill draws what `GouraudTriangle::draw_into` draws
/// where nothing is nearer: the same walk, planes and span colours (depth is one more plane).
fn depth_fill_matches<C: GouraudColor + Debug>(name: &str, seed: u64) -> usize {
    use embedded_raster::three_d::{draw_gouraud, ScreenVertex};
    use embedded_raster::DepthTarget;
    let mut rng = Rng(seed);
    let mut drawn = 0;
    for &(width, height, cases) in &TARGETS[..4] {
        let len = (width * height) as usize;
        let clip = Rectangle::new(Point::zero(), Size::new(width, height));
        for case in 0..cases {
            let points = triangle(&mut rng, width, height);
            let colors: [C; 3] = core::array::from_fn(|_| color(&mut rng));
            let background: Vec<C> = (0..len).map(|_| color(&mut rng)).collect();
            let (mut want, mut got) = (background.clone(), background);
            let vertices =
                core::array::from_fn(|k| Vertex::new(points[k].0, points[k].1, colors[k]));
            GouraudTriangle::new(vertices)
                .draw_into(&mut SliceFramebuffer::new(&mut want, width, height).unwrap());
            let mut depth = vec![0u16; len];
            let mut target = DepthTarget::new(&mut got, &mut depth, width, height).unwrap();
            target.clear_depth();
            let screen: [ScreenVertex; 3] = core::array::from_fn(|k| {
                let depth = (rng.below(65_000) as u16).max(1);
                ScreenVertex::new(points[k].0, points[k].1, depth)
            });
            draw_gouraud(&mut target, &clip, &screen, colors);
            drawn += usize::from(target.depth().iter().any(|&d| d != u16::MAX));
            if let Some((x, y)) = first_difference(&want, target.framebuffer().pixels(), width) {
                panic!(
                    "{name} case {case} on {width}×{height}: pixel ({x}, {y}) differs, {points:?}"
                );
            }
        }
    }
    drawn
}

#[test]
fn depth_tested_gouraud_draws_the_2d_pixels() {
    let drawn = depth_fill_matches::<Rgb565>("Rgb565", 0x5a3e_3d01)
        + depth_fill_matches::<Rgb888>("Rgb888", 0x5a3e_3d02)
        + depth_fill_matches::<Gray8>("Gray8", 0x5a3e_3d03);
    assert!(drawn > 3_000, "{drawn}");
}
