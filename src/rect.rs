//! Rectangle arithmetic for every clip the crate computes (framebuffer fills, the 3D viewport
//! and fills), in `i64`.
//!
//! embedded-graphics' `Rectangle::intersection` and `bottom_right` compute `top_left + size` in
//! `i32`: for rectangles reaching past `i32::MAX` they panic in debug builds and wrap in release
//! ones, which can put a clip on the wrong side of the target. Here a rectangle's edges are held
//! in `i64`, where `top_left + size` (below 2³³) is exact, so the result is right for **any**
//! `Rectangle`: the pixels that lie in both rectangles and have `i32` coordinates, and empty
//! when there are none.
//!
//! Every clip goes through [`intersection`]: `SliceFramebuffer`'s fills and the 3D fills'
//! `TargetClip` (the pipeline's viewport ∩ target, the public fills' clip ∩ target). (Clipping
//! in clip space is `three_d::clip`'s.)

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

/// The part of `a` inside `b` that has `i32` coordinates, for any two rectangles (sides up to
/// `u32::MAX`, corners anywhere in `i32`); `Rectangle::zero()` when they share no such pixel, as
/// embedded-graphics' `intersection` returns for rectangles that do not overlap.
#[inline]
pub(crate) fn intersection(a: &Rectangle, b: &Rectangle) -> Rectangle {
    let (x0, x1) = overlap(a.top_left.x, a.size.width, b.top_left.x, b.size.width);
    let (y0, y1) = overlap(a.top_left.y, a.size.height, b.top_left.y, b.size.height);
    if x0 >= x1 || y0 >= y1 {
        return Rectangle::zero();
    }
    // Non-empty: the first pixel is one of the corners (an `i32`), and each side is at most the
    // smaller of the two sides it came from (a `u32`).
    Rectangle::new(
        Point::new(x0 as i32, y0 as i32),
        Size::new((x1 - x0) as u32, (y1 - y0) as u32),
    )
}

/// One axis: the first and one-past-the-last coordinate common to `a .. a + a_len` and
/// `b .. b + b_len`, the end limited to `i32::MAX + 1` (the last `i32` coordinate).
#[inline]
fn overlap(a: i32, a_len: u32, b: i32, b_len: u32) -> (i64, i64) {
    let end =
        |start: i32, len: u32| (i64::from(start) + i64::from(len)).min(i64::from(i32::MAX) + 1);
    (i64::from(a.max(b)), end(a, a_len).min(end(b, b_len)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x: i32, y: i32, w: u32, h: u32) -> Rectangle {
        Rectangle::new(Point::new(x, y), Size::new(w, h))
    }

    /// The pixels of a rectangle with `i32` coordinates, counted from its definition in `i128`
    /// (one axis: the first and one-past-last coordinate).
    fn axis(start: i32, len: u32) -> (i128, i128) {
        let end = (i128::from(start) + i128::from(len)).min(i128::from(i32::MAX) + 1);
        (i128::from(start), end)
    }

    /// Against the definition, per axis, on edge values of both rectangles (sizes up to
    /// `u32::MAX`, corners at both ends of `i32`).
    #[test]
    fn intersection_is_the_common_pixels_for_any_rectangles() {
        let starts = [i32::MIN, i32::MIN + 1, -5, 0, 3, 16, i32::MAX - 1, i32::MAX];
        let lens = [
            0,
            1,
            2,
            3,
            20,
            1 << 31,
            3_000_000_000,
            u32::MAX - 1,
            u32::MAX,
        ];
        for &ax in &starts {
            for &aw in &lens {
                for &bx in &starts {
                    for &bw in &lens {
                        let got = intersection(&rect(ax, 0, aw, 1), &rect(bx, 0, bw, 1));
                        let (a0, a1) = axis(ax, aw);
                        let (b0, b1) = axis(bx, bw);
                        let (lo, hi) = (a0.max(b0), a1.min(b1));
                        if lo >= hi {
                            assert_eq!(got, Rectangle::zero(), "{ax} {aw} {bx} {bw}");
                        } else {
                            assert_eq!(i128::from(got.top_left.x), lo, "{ax} {aw} {bx} {bw}");
                            assert_eq!(i128::from(got.size.width), hi - lo, "{ax} {aw} {bx} {bw}");
                            assert_eq!(got.size.height, 1);
                        }
                    }
                }
            }
        }
    }

    /// The case: a clip at x ≥ 16 of width 3·10⁹ on a 32-pixel target keeps columns
    /// 16..32 (embedded-graphics' `intersection` wraps to columns 0..=16 in release).
    #[test]
    fn huge_clip_keeps_its_side() {
        let clip = rect(16, 0, 3_000_000_000, 8);
        assert_eq!(intersection(&clip, &rect(0, 0, 32, 8)), rect(16, 0, 16, 8));
        assert_eq!(
            intersection(&rect(0, 100, 320, 1 << 31), &rect(0, 0, 320, 240)),
            rect(0, 100, 320, 140)
        );
        let edge = rect(i32::MAX - 1, 0, 2, 1);
        assert_eq!(intersection(&edge, &edge), edge);
        let all = rect(i32::MIN, i32::MIN, u32::MAX, u32::MAX);
        assert_eq!(intersection(&all, &all), all);
    }
}
