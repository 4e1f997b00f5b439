//! Rectangles of any size and position (issue #16): `SliceFramebuffer`'s `DrawTarget` fills, the
//! 3D viewport and the depth-tested fills' clip write exactly the pixels of the rectangle inside
//! the target, even for rectangles reaching past `i32::MAX` (which embedded-graphics'
//! `Rectangle::intersection` cannot take), and `fill_contiguous` takes its colours in
//! embedded-graphics' order while fetching only the visible ones one by one.
//!
//! Each expectation is a naive per-pixel model: a pixel `(x, y)` of the target is in a rectangle
//! when `x0 ≤ x < x0 + width` in `i64`.

use std::cell::Cell;

use embedded_graphics::{
    pixelcolor::{Gray8, Rgb888},
    prelude::*,
    primitives::Rectangle,
};
use embedded_raster::three_d::{draw_flat, DepthTarget, ScreenVertex};
use embedded_raster::three_d::{Light, Mat4, Material, Mesh, Pipeline, Shading, Vec3};
use embedded_raster::{Coord, SliceFramebuffer};

fn rect(x: i32, y: i32, w: u32, h: u32) -> Rectangle {
    Rectangle::new(Point::new(x, y), Size::new(w, h))
}

/// Whether the target pixel `(x, y)` lies in `r`, from the definition in `i64`.
fn inside(r: &Rectangle, x: i32, y: i32) -> bool {
    let axis = |p: i32, start: i32, len: u32| {
        let (p, start) = (i64::from(p), i64::from(start));
        start <= p && p < start + i64::from(len)
    };
    axis(x, r.top_left.x, r.size.width) && axis(y, r.top_left.y, r.size.height)
}

/// Asserts that exactly the pixels `(x, y)` where `lit(x, y)` are white in `fb` (the others
/// black); `case` names the input in the message.
fn assert_lit(fb: &SliceFramebuffer<'_, Gray8>, case: &Rectangle, lit: impl Fn(i32, i32) -> bool) {
    let Size { width, height } = fb.size();
    for y in 0..height as i32 {
        for x in 0..width as i32 {
            let want = if lit(x, y) {
                Gray8::WHITE
            } else {
                Gray8::BLACK
            };
            assert_eq!(fb.get(x, y), Some(want), "{case:?} at ({x}, {y})");
        }
    }
}

/// Runs `draw` on a cleared black `w × h` depth target.
fn with_depth_target(w: u32, h: u32, draw: impl FnOnce(&mut DepthTarget<'_, Gray8>)) {
    let (mut px, mut z) = (
        vec![Gray8::BLACK; (w * h) as usize],
        vec![0; (w * h) as usize],
    );
    let mut target = DepthTarget::new(&mut px, &mut z, w, h).unwrap();
    target.clear(Gray8::BLACK);
    draw(&mut target);
}

/// Rectangles of the issue and around the edges of `i32`, over a `w × h` target.
fn awkward_rectangles(w: u32, h: u32) -> Vec<Rectangle> {
    let (wi, hi) = (w as i32, h as i32);
    vec![
        // A clip at x ≥ 16 of width 3·10⁹ (e-g's intersection wraps to columns 0..=16).
        rect(16, 0, 3_000_000_000, h),
        // 2³¹ rows from row 5 (e-g panics or wraps, and looped 2³¹ rows).
        rect(0, 5, w, 1 << 31),
        // Last column at i32::MAX.
        rect(i32::MAX - 1, 0, 2, 3),
        rect(i32::MAX, i32::MAX, u32::MAX, u32::MAX),
        // Everything.
        rect(i32::MIN, i32::MIN, u32::MAX, u32::MAX),
        rect(i32::MIN, -3, u32::MAX, 5),
        // Partly outside on each side, inside, empty, far outside.
        rect(-1, 0, 4096, 4096),
        rect(-3, -2, 7, 6),
        rect(wi - 2, hi - 1, 9, 9),
        rect(2, 1, 3, 2),
        rect(3, 3, 0, 1 << 31),
        rect(1, 1, 1 << 31, 0),
        rect(wi, 0, 5, 5),
        rect(-(1 << 30), -(1 << 30), 1 << 30, 1 << 30),
    ]
}

#[test]
fn fill_solid_writes_the_rectangle_inside_the_buffer() {
    let (w, h) = (32, 24);
    for area in awkward_rectangles(w, h) {
        let mut px = vec![Gray8::BLACK; (w * h) as usize];
        let mut fb = SliceFramebuffer::new(&mut px, w, h).unwrap();
        fb.fill_solid(&area, Gray8::WHITE).unwrap();
        assert_lit(&fb, &area, |x, y| inside(&area, x, y));
    }
}

/// A colour iterator that counts how many colours it hands out one by one (`next`) and lets
/// `nth` skip without producing the skipped ones (like a slice iterator). Colour `i` encodes
/// `i` (24 bits, enough for 2²⁴ pixels).
struct Counted<'c> {
    index: u64,
    len: u64,
    fetched: &'c Cell<u64>,
}

fn color_of(i: u64) -> Rgb888 {
    Rgb888::new((i >> 16) as u8, (i >> 8) as u8, i as u8)
}

impl Iterator for Counted<'_> {
    type Item = Rgb888;

    fn next(&mut self) -> Option<Rgb888> {
        (self.index < self.len).then(|| {
            self.fetched.set(self.fetched.get() + 1);
            self.index += 1;
            color_of(self.index - 1)
        })
    }

    fn nth(&mut self, n: usize) -> Option<Rgb888> {
        self.index = self.index.saturating_add(n as u64).min(self.len);
        self.next()
    }
}

/// Colours in embedded-graphics' order (row by row over the whole area, index
/// `(y − y0)·width + (x − x0)`), each visible pixel's colour fetched once and nothing fetched
/// one by one for the pixels outside: a 4096 × 4096 area at (−1, 0) fetches 32 × 24 colours, not
/// 2²⁴. Areas reaching 2³¹ rows below stop after the last visible row.
#[test]
fn fill_contiguous_takes_colours_in_order_and_fetches_only_visible_ones() {
    let (w, h) = (32, 24);
    let mut areas = awkward_rectangles(w, h);
    areas.push(rect(-(i32::MAX), 3, i32::MAX as u32 + 5, 1));
    for area in areas {
        // All colours, and fewer than the area needs (cut in the middle of the visible part).
        let total = u64::from(area.size.width) * u64::from(area.size.height);
        for len in [total, total / 2] {
            let mut px = vec![Rgb888::BLACK; (w * h) as usize];
            let mut fb = SliceFramebuffer::new(&mut px, w, h).unwrap();
            let fetched = Cell::new(0);
            let colors = Counted {
                index: 0,
                len,
                fetched: &fetched,
            };
            fb.fill_contiguous(&area, colors).unwrap();
            let mut visible = 0;
            for y in 0..h as i32 {
                for x in 0..w as i32 {
                    // Meaningful (non-negative) only inside the area.
                    let i = (i128::from(y) - i128::from(area.top_left.y))
                        * i128::from(area.size.width)
                        + (i128::from(x) - i128::from(area.top_left.x));
                    let want = if inside(&area, x, y) && i < i128::from(len) {
                        visible += 1;
                        color_of(i as u64)
                    } else {
                        Rgb888::BLACK
                    };
                    assert_eq!(fb.get(x, y), Some(want), "{area:?} ({len}) at ({x}, {y})");
                }
            }
            assert!(
                fetched.get() <= visible + u64::from(h),
                "{area:?}: {} colours fetched one by one for {visible} visible pixels",
                fetched.get()
            );
        }
    }
}

/// `fill_contiguous` with a plain (non-skipping) iterator of exactly `width · height` colours
/// agrees with embedded-graphics' own default implementation on small areas.
#[test]
fn fill_contiguous_agrees_with_the_default_implementation() {
    struct Plain<'a>(SliceFramebuffer<'a, Gray8>);
    impl OriginDimensions for Plain<'_> {
        fn size(&self) -> Size {
            self.0.size()
        }
    }
    impl DrawTarget for Plain<'_> {
        type Color = Gray8;
        type Error = core::convert::Infallible;
        fn draw_iter<I: IntoIterator<Item = Pixel<Gray8>>>(
            &mut self,
            p: I,
        ) -> Result<(), Self::Error> {
            self.0.draw_iter(p)
        }
    }
    let (w, h) = (7, 5);
    for x in -9..9 {
        for y in -7..7 {
            for (aw, ah) in [(1, 1), (3, 2), (9, 1), (1, 8), (12, 9), (0, 3)] {
                let area = rect(x, y, aw, ah);
                let colors = (0..aw * ah).map(|i| Gray8::new(i as u8 + 1));
                let (mut a, mut b) = (vec![Gray8::BLACK; 35], vec![Gray8::BLACK; 35]);
                SliceFramebuffer::new(&mut a, w, h)
                    .unwrap()
                    .fill_contiguous(&area, colors.clone())
                    .unwrap();
                Plain(SliceFramebuffer::new(&mut b, w, h).unwrap())
                    .fill_contiguous(&area, colors)
                    .unwrap();
                assert_eq!(a, b, "{area:?}");
            }
        }
    }
}

/// `draw_flat` clipped by each awkward rectangle covers the target pixels inside it, and only
/// those (the triangle covers the whole target).
#[test]
fn depth_fill_clip_takes_any_rectangle() {
    let (w, h) = (32, 24);
    let v = |x: i32, y: i32| ScreenVertex::new(Coord::from_num(x), Coord::from_num(y), 100);
    let cover = [v(-100, -100), v(300, -100), v(-100, 300)];
    for clip in awkward_rectangles(w, h) {
        with_depth_target(w, h, |target| {
            draw_flat(target, &clip, &cover, Gray8::WHITE);
            assert_lit(target.framebuffer(), &clip, |x, y| inside(&clip, x, y));
        });
    }
}

/// A pipeline whose viewport reaches past `i32::MAX` draws only inside viewport ∩ target: a
/// quad over normalised device coordinates `[−1, 1]²` covers exactly the part of the viewport's
/// mapped rectangle (its corner, sides limited to 65535 px) inside the target.
#[test]
fn pipeline_viewport_takes_any_rectangle() {
    static VERTICES: [Vec3; 4] = [
        Vec3::from_bits(-1 << 16, -1 << 16, 0),
        Vec3::from_bits(1 << 16, -1 << 16, 0),
        Vec3::from_bits(1 << 16, 1 << 16, 0),
        Vec3::from_bits(-1 << 16, 1 << 16, 0),
    ];
    static NORMALS: [Vec3; 4] = [Vec3::from_bits(0, 0, 1 << 16); 4];
    static INDICES: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];
    let mesh = Mesh::new(&VERTICES, &NORMALS, &INDICES);
    let (w, h) = (32, 24);
    for viewport in awkward_rectangles(w, h) {
        let pipeline = Pipeline::new(Mat4::IDENTITY, Mat4::IDENTITY, viewport, Light::default());
        let material = Material::new(Gray8::WHITE, Shading::Unlit);
        // The mapped rectangle: the viewport's corner and sides limited to 65535.
        let mapped = Rectangle::new(
            viewport.top_left,
            Size::new(
                viewport.size.width.min(65_535),
                viewport.size.height.min(65_535),
            ),
        );
        with_depth_target(w, h, |target| {
            pipeline.draw_mesh(&mesh, &material, target);
            assert_lit(target.framebuffer(), &viewport, |x, y| {
                inside(&viewport, x, y) && inside(&mapped, x, y)
            });
        });
    }
}
