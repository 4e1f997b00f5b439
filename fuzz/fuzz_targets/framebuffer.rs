//! `SliceFramebuffer`'s `DrawTarget` methods — `fill_solid`, `fill_contiguous`, `draw_iter`,
//! `clear` — on a buffer of any size up to 64 × 64, with arbitrary rectangles (corners anywhere
//! in `i32`, sides up to `u32::MAX`) and pixels, against a naive model that tests every buffer
//! pixel against the definition in `i64`. `fill_contiguous` gets colour streams shorter or longer
//! than the area, must use colour `(y − y0)·width + (x − x0)` for pixel `(x, y)`, and may fetch
//! one by one only the colours it draws (plus one a row for `nth`'s skips).
#![no_main]

use std::cell::Cell;

use arbitrary::Arbitrary;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::Pixel;
use embedded_raster::SliceFramebuffer;
use embedded_raster_fuzz::{inside, AnyRect, Color, Int, Len};
use libfuzzer_sys::fuzz_target;

#[derive(Arbitrary, Debug)]
enum Op {
    FillSolid(AnyRect, Color),
    /// The area, how many colours the stream has (`None`: as many as the area's pixels), and a
    /// seed for the colours.
    FillContiguous(AnyRect, Option<Len>, u32),
    DrawIter(Vec<(Int, Int, Color)>),
    Clear(Color),
}

#[derive(Arbitrary, Debug)]
struct Input {
    width: u8,
    height: u8,
    ops: Vec<Op>,
}

/// Colour `i` of a stream: a hash of the seed and the index.
fn stream_color(seed: u32, i: u64) -> Rgb888 {
    let h = (i ^ u64::from(seed) << 32).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    Rgb888::new((h >> 56) as u8, (h >> 48) as u8, (h >> 40) as u8)
}

/// The colour stream of `fill_contiguous`: counts the colours fetched one by one; `nth` skips in
/// constant time, like a slice iterator.
struct Stream<'c> {
    seed: u32,
    index: u64,
    len: u64,
    fetched: &'c Cell<u64>,
}

impl Iterator for Stream<'_> {
    type Item = Rgb888;

    fn next(&mut self) -> Option<Rgb888> {
        (self.index < self.len).then(|| {
            self.fetched.set(self.fetched.get() + 1);
            self.index += 1;
            stream_color(self.seed, self.index - 1)
        })
    }

    fn nth(&mut self, n: usize) -> Option<Rgb888> {
        self.index = self.index.saturating_add(n as u64).min(self.len);
        self.next()
    }
}

fuzz_target!(|input: Input| {
    let (width, height) = (u32::from(input.width % 65), u32::from(input.height % 65));
    let n = (width * height) as usize;
    let mut pixels = vec![Rgb888::BLACK; n];
    let mut model = vec![Rgb888::BLACK; n];
    let mut fb = SliceFramebuffer::new(&mut pixels, width, height).unwrap();
    let each = |f: &mut dyn FnMut(i32, i32, usize)| {
        for i in 0..n {
            f((i as u32 % width) as i32, (i as u32 / width) as i32, i);
        }
    };
    for op in input.ops.iter().take(16) {
        match op {
            Op::FillSolid(area, color) => {
                let (area, color) = (area.get(), color.get());
                fb.fill_solid(&area, color).unwrap();
                each(&mut |x, y, i| {
                    if inside(&area, x, y) {
                        model[i] = color;
                    }
                });
            }
            Op::FillContiguous(area, len, seed) => {
                let area = area.get();
                let pixels = u64::from(area.size.width) * u64::from(area.size.height);
                let len = len.map_or(pixels, |l| u64::from(l.get()));
                let fetched = Cell::new(0);
                let stream = Stream {
                    seed: *seed,
                    index: 0,
                    len,
                    fetched: &fetched,
                };
                fb.fill_contiguous(&area, stream).unwrap();
                let (mut drawn, mut rows) = (0u64, std::collections::BTreeSet::new());
                each(&mut |x, y, i| {
                    if inside(&area, x, y) {
                        let k = (i64::from(y) - i64::from(area.top_left.y)) as u64
                            * u64::from(area.size.width)
                            + (i64::from(x) - i64::from(area.top_left.x)) as u64;
                        rows.insert(y);
                        if k < len {
                            model[i] = stream_color(*seed, k);
                            drawn += 1;
                        }
                    }
                });
                assert!(
                    fetched.get() <= drawn + rows.len() as u64 + 1,
                    "{area:?}: {} colours fetched one by one for {drawn} drawn",
                    fetched.get()
                );
            }
            Op::DrawIter(list) => {
                let list: Vec<Pixel<Rgb888>> = list
                    .iter()
                    .map(|(x, y, c)| Pixel(Point::new(x.get(), y.get()), c.get()))
                    .collect();
                fb.draw_iter(list.iter().copied()).unwrap();
                for Pixel(p, c) in list {
                    if (0..width as i64).contains(&i64::from(p.x))
                        && (0..height as i64).contains(&i64::from(p.y))
                    {
                        model[(p.y as u32 * width + p.x as u32) as usize] = c;
                    }
                }
            }
            Op::Clear(color) => {
                fb.clear(color.get()).unwrap();
                model.fill(color.get());
            }
        }
        assert_eq!(fb.pixels(), &model[..], "after {op:?} on {width}×{height}");
    }
});
