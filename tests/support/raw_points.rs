//! Random raw (sub-pixel: 256 a pixel) vertex positions for the 2D fill tests
//! (tests/all/coverage_random.rs, tests/all/perspective.rs, tests/all/same_pixels.rs, tests/all/textured.rs,
//! tests/all/alpha.rs, tests/all/antialias.rs).
//! Needs the suite's `mod rng`.

#![allow(dead_code)]

use crate::rng::Rng;

/// The ends of the `i32` range (the raw coordinates'), as `i64`.
pub const MIN: i64 = i32::MIN as i64;
pub const MAX: i64 = i32::MAX as i64;

impl Rng {
    /// An `i32` of random magnitude (2⁰ … 2³¹), either sign.
    pub fn any_scale(&mut self) -> i64 {
        i64::from((self.next() as i32) >> self.below(32))
    }
}

/// A raw value at or near the ends of the `i32` range, or (half the time) of any magnitude.
pub fn extreme(rng: &mut Rng) -> i64 {
    const VALUES: [i64; 6] = [MIN, MAX, MIN + 1, MAX - 1, 0, -1];
    if rng.chance(2) {
        rng.any_scale()
    } else {
        VALUES[rng.below(VALUES.len() as u64) as usize]
    }
}

/// A raw coordinate on pixel `i`'s corner, centre, a quarter, or one unit off the corner (the
/// centre twice as often).
pub fn snap(rng: &mut Rng, i: i64) -> i64 {
    const OFFSETS: [i64; 7] = [0, 128, 128, 64, 192, 1, 255];
    256 * i + OFFSETS[rng.below(OFFSETS.len() as u64) as usize]
}

/// A sliver: `a`, `a + d` (`d` up to 2^s raw units on each axis, `s` below `shifts`) and a
/// third vertex near the line through them.
pub fn sliver(rng: &mut Rng, a: (i64, i64), shifts: u64) -> [(i64, i64); 3] {
    let s = rng.below(shifts) as u32;
    let d = (rng.range(-(1 << s), 1 << s), rng.range(-(1 << s), 1 << s));
    let (num, e) = (rng.range(-64, 128), rng.range(0, 3));
    let c = (
        a.0 + d.0 * num / 64 + rng.range(-e, e),
        a.1 + d.1 * num / 64 + rng.range(-e, e),
    );
    [a, (a.0 + d.0, a.1 + d.1), c]
}

/// A screen (or target) of `w × h` pixels, for raw points over it.
#[derive(Clone, Copy, Debug)]
pub struct Screen {
    pub w: i64,
    pub h: i64,
}

impl Screen {
    pub const fn new(w: i64, h: i64) -> Screen {
        Screen { w, h }
    }

    /// A raw point over the screen extended by `margin` pixels on every side.
    pub fn point(self, rng: &mut Rng, margin: i64) -> (i64, i64) {
        self.point_xy(rng, (margin, margin))
    }

    /// Three raw points within `r` raw units (on each axis; `r` from `lo` to `hi`) of a raw
    /// point over the screen extended by `margin` pixels.
    pub fn cluster(self, rng: &mut Rng, margin: i64, (lo, hi): (i64, i64)) -> [(i64, i64); 3] {
        let c = self.point(rng, margin);
        let r = rng.range(lo, hi);
        [(); 3].map(|_| (c.0 + rng.range(-r, r), c.1 + rng.range(-r, r)))
    }

    /// A raw point over the screen extended by `mx` pixels left and right, `my` above and
    /// below.
    pub fn point_xy(self, rng: &mut Rng, (mx, my): (i64, i64)) -> (i64, i64) {
        (
            rng.range(-mx * 256, (self.w + mx) * 256),
            rng.range(-my * 256, (self.h + my) * 256),
        )
    }

    /// A raw point over the screen extended by `margin` pixels, each coordinate `snap`ped (both
    /// pixels drawn first, then both offsets).
    pub fn snapped_point(self, rng: &mut Rng, margin: i64) -> (i64, i64) {
        let x = rng.range(-margin, self.w + margin);
        let y = rng.range(-margin, self.h + margin);
        (snap(rng, x), snap(rng, y))
    }

    /// A raw point on a pixel corner, centre or quarter, or one unit off a corner, over the
    /// screen extended by `margin` pixels (each axis' pixel and offset drawn in turn, every
    /// offset equally often).
    pub fn snapped_per_axis(self, rng: &mut Rng, margin: i64) -> (i64, i64) {
        const OFFSETS: [i64; 6] = [0, 128, 64, 192, 1, 255];
        let mut snap = |n: i64| {
            256 * rng.range(-margin, n + margin) + OFFSETS[rng.below(OFFSETS.len() as u64) as usize]
        };
        (snap(self.w), snap(self.h))
    }
}

/// A triangle for a `w × h` target from a mix of kinds, raw `i32` coordinates: sub-pixel, up to
/// a dozen pixels, about the target's size and ten times it, one vertex on the target and the
/// others out to the range's ends, snapped to corners and centres, slivers (the translucent and
/// anti-aliased suites).
pub fn mixed_triangle(rng: &mut Rng, w: u32, h: u32) -> [(i32, i32); 3] {
    let (wi, hi) = (i64::from(w), i64::from(h));
    let screen = Screen::new(wi, hi);
    let v: [(i64, i64); 3] = match rng.below(8) {
        0 => screen.cluster(rng, 2, (1, 300)),
        1 | 2 => screen.cluster(rng, 4, (128, 256 * 12)),
        3 => [(); 3].map(|_| screen.point_xy(rng, (wi / 2 + 2, hi / 2 + 2))),
        4 => [(); 3].map(|_| screen.point_xy(rng, (10 * wi, 10 * hi))),
        5 => {
            let a = screen.point(rng, 1);
            [
                a,
                (extreme(rng), extreme(rng)),
                (extreme(rng), extreme(rng)),
            ]
        }
        6 => [(); 3].map(|_| screen.snapped_per_axis(rng, 6)),
        _ => {
            let a = screen.point(rng, 8);
            sliver(rng, a, 28)
        }
    };
    v.map(|(x, y)| (x.clamp(MIN, MAX) as i32, y.clamp(MIN, MAX) as i32))
}
