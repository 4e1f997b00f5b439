//! Tiny triangles: a bounding box under 8 × 8 pixels, drawn a whole row of the box at a time.
//!
//! A triangle of a dozen pixels has rows of two to five pixels, and on a host the span walk's
//! per-row work (boundary columns stepped by quotient and remainder, span and row loop exits the
//! branch predictor cannot learn) costs more than its pixels. Here every row of the box is
//! [`LANES`] lanes, one per pixel: the three edge values of each lane (16 bits, exact over the
//! box), the mask of covered lanes, their colours and one masked write of the eight pixels. The
//! lanes are plain arrays; on x86-64 LLVM turns each loop over them into a few SSE2
//! instructions, the eight pixels' load and store included. Two parts are SSE2 intrinsics, where
//! LLVM left scalar code: the run's first pixel (one `movemask` of the covered mask) and the
//! colours' per-row arithmetic (the three channels in one register).
//!
//! [`GouraudTriangle::draw_into`](crate::GouraudTriangle::draw_into) and
//! [`SolidTriangle::draw_into`](crate::SolidTriangle::draw_into) take this path on x86-64
//! for triangles whose vertices lie within 8 pixels (less a sub-pixel) of each other on both
//! axes, drawn into a framebuffer at least 8 pixels wide. Other targets walk spans: on Cortex-M,
//! without vector units, eight lanes cost more than the span walk (see the benchmarks in the
//! README), and firmware keeps its flash. `Drawable::draw` and `draw_into_compact` always walk
//! spans.
//!
//! The pixels are exactly those of the span walk (the compact set-up's): the same edge
//! functions and top-left rule decide coverage, and each row's covered run gets the colours
//! [`fill_masked_row`](crate::GouraudColor::fill_masked_row) gives it from the run's first
//! pixel, as the span fill does, so a firmware and its host simulation draw the same picture.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
//! use embedded_raster::{Coord, GouraudTriangle, SliceFramebuffer, Vertex};
//!
//! let v = |x: f32, y: f32, c| Vertex::new(Coord::from_num(x), Coord::from_num(y), c);
//! let tiny = GouraudTriangle::new([
//!     v(2.5, 1.0, Rgb565::RED),
//!     v(7.0, 6.25, Rgb565::GREEN),
//!     v(1.0, 5.5, Rgb565::BLUE),
//! ]);
//! let (mut rows, mut spans) = ([Rgb565::BLACK; 16 * 8], [Rgb565::BLACK; 16 * 8]);
//! tiny.draw_into(&mut SliceFramebuffer::new(&mut rows, 16, 8).unwrap());
//! tiny.draw_into_compact(&mut SliceFramebuffer::new(&mut spans, 16, 8).unwrap()).unwrap();
//! assert_eq!(rows, spans);
//! assert_ne!(rows, [Rgb565::BLACK; 16 * 8]);
//! ```

use super::compact::CompactTriangle;
use super::edge::owns_centres_on;
use super::plane::Planes;
use super::sink::SpanShader;
use crate::arch::x86_64::{first_covered, ChannelRows};
use crate::arch::LANES;
use crate::fixed_point::SUBPIXEL_BITS;

/// Width and height of a tiny triangle's vertex bounding box stay below this many sub-pixels
/// (8 pixels): its box then holds at most 8 × 8 pixel centres, and every edge value there,
/// `|a·Δx + b·Δy| ≤ 2·w·h < 2²³` sub-pixels², divided by 256 fits an `i16`.
const TINY: u32 = (LANES as u32) << SUBPIXEL_BITS;

/// Draws `triangle` (set up over a target `width` pixels wide, its left column 0) with `planes`
/// through `shader`'s masked rows if it is tiny and the target at least [`LANES`] pixels wide;
/// `false` (nothing drawn) otherwise. Each row's run gets the attributes of its first pixel, as
/// the span walk would hand them.
#[inline(always)]
pub(crate) fn shade<const N: usize>(
    triangle: &CompactTriangle,
    planes: &Planes<N>,
    width: u32,
    shader: &mut impl SpanShader<N>,
) -> bool {
    let (w, h) = triangle.extent;
    // The row values are four lanes of one register (`ChannelRows`).
    if N > 4 || w >= TINY || h >= TINY || width < LANES as u32 {
        return false;
    }
    let steps = shader.prepare(planes.step());
    let mut rows = ChannelRows::new(planes.first(), planes.step(), planes.row_step());
    walk(width, triangle, |y, x, covered, first, column| {
        let start = rows.next_row(column);
        shader.masked_row(&steps, y, x, covered, first, start);
    });
    true
}

/// Walks the rows of tiny `triangle` (set up over a target `width ≥ LANES` pixels wide), handing
/// `row` each row's `y`, the first column `x` of its window of [`LANES`] pixels (inside the
/// target), the covered mask, the run's first lane ([`LANES`] if the row is empty) and its column
/// from the walk's first column.
#[inline(always)]
fn walk(
    width: u32,
    triangle: &CompactTriangle,
    mut row: impl FnMut(i32, i32, [i16; LANES], u32, u32),
) {
    // The box's columns x0..=x1 (at most 8) inside the window of eight columns from xw,
    // which ends inside the framebuffer (the walk is clipped to it: 0 ≤ x0, x1 < width).
    // Lanes outside the box may be far enough from the vertices for their edge values to
    // wrap: masked.
    let (x0, x1) = (triangle.x0, triangle.x1);
    let xw = x0.min(width as i32 - LANES as i32);
    let (lo, hi) = ((x0 - xw) as i16, (x1 - xw) as i16);
    let lane: [i16; LANES] = core::array::from_fn(|i| i as i16);
    let in_box = lane.map(|i| -i16::from(lo <= i && i <= hi));

    // Edge values K = ⌊(E − bias)/256⌋ at the window's pixel centres (inside iff K ≥ 0; the
    // bias gives the centres on an edge to left and top edges only), stepped by a per column
    // and b per row: exact modulo 2¹⁶, so exact wherever the true value fits, in the box.
    let setup = &triangle.setup;
    let mut edge = [[0i16; LANES]; 3];
    let mut row_step = [0i16; 3];
    for (k, (&(a, b), &s)) in triangle.coef.iter().zip(&triangle.starts).enumerate() {
        // Within 2¹² of the box's centres: the products fit.
        let offset = (
            setup.dx - (i32::from(lo) << SUBPIXEL_BITS) - s.0,
            setup.dy - s.1,
        );
        let e = a * offset.0 + b * offset.1;
        let bias = i32::from(!owns_centres_on(a.into(), b.into()));
        let first = ((e - bias) >> SUBPIXEL_BITS) as i16;
        if let (Some(values), Some(step)) = (edge.get_mut(k), row_step.get_mut(k)) {
            *values = lane.map(|i| first.wrapping_add((a as i16).wrapping_mul(i)));
            *step = b as i16;
        }
    }

    for y in triangle.y0..=triangle.y1 {
        let mut covered = [0i16; LANES];
        for (i, c) in covered.iter_mut().enumerate() {
            *c = in_box[i] & !((edge[0][i] | edge[1][i] | edge[2][i]) >> 15);
        }
        // The run's first lane (8 if the row is empty) and its column from x0.
        let first = first_covered(covered);
        let column = first.wrapping_sub(lo as u32);
        row(y, xw, covered, first, column);
        for (values, step) in edge.iter_mut().zip(row_step) {
            for v in values.iter_mut() {
                *v = v.wrapping_add(step);
            }
        }
    }
}
