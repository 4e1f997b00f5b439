//! Property tests against the independent f64 reference (`embedded_raster::reference`).
//!
//! * coverage of `raster::for_each_span` equals the reference for arbitrary `i32` vertices in
//!   several ranges and arbitrary clip rectangles;
//! * drawing never touches a pixel outside the target (a `DrawTarget` that asserts), with targets
//!   anywhere, and draws exactly the reference's pixels;
//! * the vertex order (winding) does not change the covered set;
//! * translating a triangle (and the clip) by whole pixels translates its coverage;
//! * Gouraud colours are within 1 LSB of the exact interpolation.

use std::collections::BTreeSet;
use std::convert::Infallible;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::{
    raster, reference, Coord, GouraudTriangle, SliceFramebuffer, SolidTriangle, Vertex,
};
use proptest::prelude::*;

type Tri = [(i32, i32); 3];
type PixelSet = BTreeSet<(i32, i32)>;

const MIN: i32 = i32::MIN;
const MAX: i32 = i32::MAX;
/// Allowed deviation from the exact interpolated channel value, in LSB.
const TOLERANCE: f64 = 1.0 + 1e-9;

fn coords(v: Tri) -> [(Coord, Coord); 3] {
    v.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y)))
}

fn rect(x: i32, y: i32, w: u32, h: u32) -> Rectangle {
    Rectangle::new(Point::new(x, y), Size::new(w, h))
}

/// The core's covered set inside `clip`; asserts spans are inside it and not repeated.
fn core_set(v: Tri, clip: Rectangle) -> PixelSet {
    let mut set = PixelSet::new();
    raster::for_each_span(coords(v), clip, |y, x0, x1| {
        for x in x0..x1 {
            assert!(
                clip.contains(Point::new(x, y)),
                "({x}, {y}) outside {clip:?}"
            );
            assert!(set.insert((x, y)), "({x}, {y}) emitted twice");
        }
    });
    set
}

fn reference_set(v: Tri, clip: Rectangle) -> PixelSet {
    let mut set = PixelSet::new();
    if clip.size.width == 0 || clip.size.height == 0 {
        return set;
    }
    let (x0, y0) = (clip.top_left.x, clip.top_left.y);
    let br = clip.bottom_right().unwrap();
    reference::for_each_covered(v, x0, y0, br.x + 1, br.y + 1, |x, y| {
        set.insert((x, y));
    });
    set
}

// ----------------------------------------------------------------------------------------------
// Strategies
// ----------------------------------------------------------------------------------------------

/// Raw coordinates around a 64 × 48 screen, any sub-pixel position.
fn near_screen() -> BoxedStrategy<(i32, i32)> {
    (-16 * 256..80 * 256, -16 * 256..64 * 256).boxed()
}

/// Raw coordinates on pixel corners, centres and quarters near the screen (edges through centres).
fn snapped() -> BoxedStrategy<(i32, i32)> {
    let c = || {
        (
            -8i32..72,
            prop::sample::select(vec![0, 128, 64, 192, 1, 255]),
        )
    };
    (c(), c())
        .prop_map(|((x, fx), (y, fy))| (256 * x + fx, 256 * y + fy))
        .boxed()
}

fn medium() -> BoxedStrategy<(i32, i32)> {
    (-(1 << 20)..1 << 20, -(1 << 20)..1 << 20).boxed()
}

fn extreme() -> BoxedStrategy<i32> {
    prop_oneof![
        prop::sample::select(vec![MIN, MAX, MIN + 1, MAX - 1, 0, -1, 128, MIN + 128]),
        any::<i32>(),
    ]
    .boxed()
}

fn full_range() -> BoxedStrategy<(i32, i32)> {
    (extreme(), extreme()).boxed()
}

fn mixed() -> BoxedStrategy<(i32, i32)> {
    prop_oneof![
        3 => near_screen(),
        3 => snapped(),
        2 => medium(),
        2 => full_range(),
    ]
    .boxed()
}

fn tri(s: BoxedStrategy<(i32, i32)>) -> impl Strategy<Value = Tri> {
    prop::array::uniform3(s)
}

/// The 64 × 48 screen, or a small rectangle near it, or anywhere in the pixel range.
fn clip() -> impl Strategy<Value = Rectangle> {
    prop_oneof![
        2 => Just(rect(0, 0, 64, 48)),
        2 => (-70i32..70, -70i32..70, 0u32..80, 0u32..80)
            .prop_map(|(x, y, w, h)| rect(x, y, w, h)),
        1 => (-(1i32 << 24)..1 << 24, -(1i32 << 24)..1 << 24, 0u32..64, 0u32..64)
            .prop_map(|(x, y, w, h)| rect(x, y, w, h)),
    ]
}

// ----------------------------------------------------------------------------------------------
// A target that asserts every pixel is inside its bounding box
// ----------------------------------------------------------------------------------------------

struct Asserting<C> {
    area: Rectangle,
    drawn: Vec<(i32, i32, C)>,
}

impl<C> Dimensions for Asserting<C> {
    fn bounding_box(&self) -> Rectangle {
        self.area
    }
}

impl<C: PixelColor> DrawTarget for Asserting<C> {
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        for Pixel(p, c) in pixels {
            assert!(self.area.contains(p), "{p:?} outside {:?}", self.area);
            self.drawn.push((p.x, p.y, c));
        }
        Ok(())
    }
}

fn drawn_set<C>(drawn: &[(i32, i32, C)]) -> PixelSet {
    let set: PixelSet = drawn.iter().map(|&(x, y, _)| (x, y)).collect();
    assert_eq!(set.len(), drawn.len(), "a pixel was drawn twice");
    set
}

fn rgb888(c: u32) -> Rgb888 {
    Rgb888::new(c as u8, (c >> 8) as u8, (c >> 16) as u8)
}

fn channels888(c: Rgb888) -> [f64; 3] {
    [c.r(), c.g(), c.b()].map(f64::from)
}

fn channels565(c: Rgb565) -> [f64; 3] {
    [c.r(), c.g(), c.b()].map(f64::from)
}

fn check_colour(
    v: Tri,
    exact: [f64; 3],
    got: [f64; 3],
    x: i32,
    y: i32,
) -> Result<(), TestCaseError> {
    for k in 0..3 {
        let err = (got[k] - exact[k]).abs();
        prop_assert!(
            err <= TOLERANCE,
            "triangle {v:?} pixel ({x}, {y}) channel {k}: got {}, exact {}",
            got[k],
            exact[k]
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 10_000, ..ProptestConfig::default() })]

    #[test]
    fn coverage_matches_reference_near_screen(v in tri(near_screen()), clip in clip()) {
        prop_assert_eq!(core_set(v, clip), reference_set(v, clip), "triangle {:?}", v);
    }

    #[test]
    fn coverage_matches_reference_snapped(v in tri(snapped()), clip in clip()) {
        prop_assert_eq!(core_set(v, clip), reference_set(v, clip), "triangle {:?}", v);
    }

    #[test]
    fn coverage_matches_reference_medium(v in tri(medium()), clip in clip()) {
        prop_assert_eq!(core_set(v, clip), reference_set(v, clip), "triangle {:?}", v);
    }

    #[test]
    fn coverage_matches_reference_full_range(v in tri(full_range()), clip in clip()) {
        prop_assert_eq!(core_set(v, clip), reference_set(v, clip), "triangle {:?}", v);
    }

    #[test]
    fn coverage_matches_reference_mixed(v in tri(mixed()), clip in clip()) {
        prop_assert_eq!(core_set(v, clip), reference_set(v, clip), "triangle {:?}", v);
    }

    /// Near-collinear triangles: c = a + t (b − a) + a tiny offset.
    #[test]
    fn coverage_matches_reference_slivers(
        a in mixed(),
        d in (-(1i64 << 20)..1 << 20, -(1i64 << 20)..1 << 20),
        t in -3i64..4,
        e in (-2i64..3, -2i64..3),
        clip in clip(),
    ) {
        let p = |x: i64, y: i64| (x.clamp(MIN.into(), MAX.into()) as i32,
                                   y.clamp(MIN.into(), MAX.into()) as i32);
        let (ax, ay) = (i64::from(a.0), i64::from(a.1));
        let v = [a, p(ax + d.0, ay + d.1), p(ax + t * d.0 + e.0, ay + t * d.1 + e.1)];
        prop_assert_eq!(core_set(v, clip), reference_set(v, clip), "triangle {:?}", v);
    }

    #[test]
    fn draw_stays_inside_the_target(
        v in tri(mixed()),
        area in clip(),
        colors in prop::array::uniform3(any::<u32>()),
    ) {
        let want = reference_set(v, area);
        let mut solid = Asserting { area, drawn: Vec::new() };
        SolidTriangle::new(coords(v), Rgb888::WHITE).draw(&mut solid).unwrap();
        prop_assert_eq!(drawn_set(&solid.drawn), want.clone(), "solid {:?}", v);

        let c = coords(v);
        let g = GouraudTriangle::new([0, 1, 2].map(|k| Vertex::new(c[k].0, c[k].1, rgb888(colors[k]))));
        let mut gouraud = Asserting { area, drawn: Vec::new() };
        g.draw(&mut gouraud).unwrap();
        prop_assert_eq!(drawn_set(&gouraud.drawn), want, "gouraud {:?}", v);
    }

    /// `SliceFramebuffer` of any size: drawing must not panic and only covered pixels change.
    #[test]
    fn slice_framebuffer_any_size(
        v in tri(mixed()),
        w in 1u32..40,
        h in 1u32..40,
        color in any::<u32>(),
    ) {
        let want = reference_set(v, rect(0, 0, w, h));
        for fast in [false, true] {
            let mut px = vec![Rgb565::BLACK; (w * h) as usize];
            let mut fb = SliceFramebuffer::new(&mut px, w, h).unwrap();
            let t = SolidTriangle::new(coords(v), Rgb565::new((color as u8 & 31) | 1, 0, 0));
            if fast {
                t.draw_into(&mut fb);
            } else {
                t.draw(&mut fb).unwrap();
            }
            for y in 0..h as i32 {
                for x in 0..w as i32 {
                    let written = fb.get(x, y).unwrap() != Rgb565::BLACK;
                    prop_assert_eq!(written, want.contains(&(x, y)), "{:?} ({}, {})", v, x, y);
                }
            }
        }
    }

    #[test]
    fn winding_does_not_change_coverage(v in tri(mixed()), clip in clip()) {
        let [a, b, c] = v;
        let first = core_set(v, clip);
        for w in [[b, c, a], [c, a, b], [a, c, b], [c, b, a], [b, a, c]] {
            prop_assert_eq!(&core_set(w, clip), &first, "{:?} vs {:?}", v, w);
            let mut t = Asserting { area: clip, drawn: Vec::new() };
            SolidTriangle::new(coords(w), Rgb565::WHITE).draw(&mut t).unwrap();
            prop_assert_eq!(&drawn_set(&t.drawn), &first);
        }
    }

    #[test]
    fn translation_by_whole_pixels_translates_coverage(
        v in tri(prop_oneof![near_screen(), snapped(), medium()].boxed()),
        d in (-(1i32 << 21)..1 << 21, -(1i32 << 21)..1 << 21),
        size in (1u32..80, 1u32..60),
        offset in (-40i32..40, -40i32..40),
    ) {
        // A clip near the first vertex so that coverage is usually non-empty.
        let (cx, cy) = ((v[0].0 >> 8) + offset.0, (v[0].1 >> 8) + offset.1);
        let clip = rect(cx, cy, size.0, size.1);
        let moved = v.map(|(x, y)| (x + 256 * d.0, y + 256 * d.1));
        let moved_clip = rect(cx + d.0, cy + d.1, size.0, size.1);
        let base = core_set(v, clip);
        let shifted: PixelSet = core_set(moved, moved_clip)
            .into_iter()
            .map(|(x, y)| (x - d.0, y - d.1))
            .collect();
        prop_assert_eq!(shifted, base);
    }

    #[test]
    fn gouraud_within_one_lsb(
        v in tri(mixed()),
        colors in prop::array::uniform3(any::<u32>()),
        fast in any::<bool>(),
    ) {
        let (w, h) = (64u32, 48u32);
        let want = reference_set(v, rect(0, 0, w, h));
        let c = coords(v);

        // Rgb888
        let cols = colors.map(rgb888);
        let mut px = vec![Rgb888::BLACK; (w * h) as usize];
        let mut fb = SliceFramebuffer::new(&mut px, w, h).unwrap();
        let g = GouraudTriangle::new([0, 1, 2].map(|k| Vertex::new(c[k].0, c[k].1, cols[k])));
        if fast { g.draw_into(&mut fb) } else { g.draw(&mut fb).unwrap() }
        let ch = cols.map(channels888);
        for &(x, y) in &want {
            let exact = reference::interpolate(v, ch, x, y).unwrap();
            check_colour(v, exact, channels888(fb.get(x, y).unwrap()), x, y)?;
        }

        // Rgb565 (5-6-5 bit channels)
        let cols = colors.map(|c| Rgb565::new(c as u8 & 31, (c >> 8) as u8 & 63, (c >> 16) as u8 & 31));
        let mut px = vec![Rgb565::BLACK; (w * h) as usize];
        let mut fb = SliceFramebuffer::new(&mut px, w, h).unwrap();
        let g = GouraudTriangle::new([0, 1, 2].map(|k| Vertex::new(c[k].0, c[k].1, cols[k])));
        if fast { g.draw_into(&mut fb) } else { g.draw(&mut fb).unwrap() }
        let ch = cols.map(channels565);
        for &(x, y) in &want {
            let exact = reference::interpolate(v, ch, x, y).unwrap();
            check_colour(v, exact, channels565(fb.get(x, y).unwrap()), x, y)?;
        }
    }
}
