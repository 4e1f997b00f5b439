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
//! without vector units, eight lanes cost more than the span walk (measured under QEMU: a
//! 16 px² Gouraud triangle takes 1.8 times the instructions on a Cortex-M4, 1.4 times on a
//! Cortex-M0), and firmware keeps its flash. `Drawable::draw` and `draw_into_compact` always
//! walk spans.
//!
//! The pixels are exactly those of the span walk ([`compact`](crate::compact)): the same edge
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

/// Pixels of a row of the box: one lane each.
pub const LANES: usize = 8;

// x86-64 only, where it is measured (on AArch64 LLVM vectorises the lanes but loads and stores
// the eight pixels one by one: unmeasured, so other hosts walk spans).
#[cfg(target_arch = "x86_64")]
pub(crate) use rows::{draw, fill};

#[cfg(target_arch = "x86_64")]
mod rows {
    use embedded_graphics::geometry::OriginDimensions;
    use embedded_graphics::pixelcolor::PixelColor;

    use super::LANES;
    use crate::color::{GouraudColor, SpanSteps};
    use crate::compact::{CompactColors, CompactTriangle};
    use crate::fixed_point::SUBPIXEL_BITS;
    use crate::SliceFramebuffer;

    /// Width and height of a tiny triangle's vertex bounding box stay below this many sub-pixels
    /// (8 pixels): its box then holds at most 8 × 8 pixel centres, and every edge value there,
    /// `|a·Δx + b·Δy| ≤ 2·w·h < 2²³` sub-pixels², divided by 256 fits an `i16`.
    const TINY: u32 = (LANES as u32) << SUBPIXEL_BITS;

    /// Walks the rows of `triangle` (set up over `framebuffer`'s bounding box) if it is tiny and
    /// the framebuffer is at least [`LANES`] pixels wide, handing `fill` each row's eight pixels,
    /// the covered mask, the run's first pixel (8 if the row is empty) and its column from the
    /// walk's first column; `false` (nothing walked) otherwise.
    #[inline(always)]
    fn walk<C: PixelColor>(
        framebuffer: &mut SliceFramebuffer<'_, C>,
        triangle: &CompactTriangle,
        mut fill: impl FnMut(&mut [C; LANES], [i16; LANES], u32, u32),
    ) -> bool {
        let (w, h) = triangle.extent;
        let width = framebuffer.size().width;
        if w >= TINY || h >= TINY || width < LANES as u32 {
            return false;
        }
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
            let bias = i32::from(!(a > 0 || (a == 0 && b > 0)));
            let first = ((e - bias) >> SUBPIXEL_BITS) as i16;
            if let (Some(values), Some(step)) = (edge.get_mut(k), row_step.get_mut(k)) {
                *values = lane.map(|i| first.wrapping_add((a as i16).wrapping_mul(i)));
                *step = b as i16;
            }
        }

        let pixels = framebuffer.pixels_mut();
        let rows = (triangle.y1 - triangle.y0) as u32 + 1;
        let mut base = triangle.y0 as usize * width as usize + xw as usize;
        for _ in 0..rows {
            let mut covered = [0i16; LANES];
            for (i, c) in covered.iter_mut().enumerate() {
                *c = in_box[i] & !((edge[0][i] | edge[1][i] | edge[2][i]) >> 15);
            }
            // The run's first lane (8 if the row is empty) and its column from x0.
            let first = first_covered(covered);
            let column = first.wrapping_sub(lo as u32);
            if let Some(row) = pixels
                .get_mut(base..base + LANES)
                .and_then(|row| <&mut [C; LANES]>::try_from(row).ok())
            {
                fill(row, covered, first, column);
            }
            for (values, step) in edge.iter_mut().zip(row_step) {
                for v in values.iter_mut() {
                    *v = v.wrapping_add(step);
                }
            }
            base += width as usize;
        }
        true
    }

    /// The first covered lane (8 if none): the lanes' sign bits in one SSE2 `movemask`.
    #[inline(always)]
    fn first_covered(covered: [i16; LANES]) -> u32 {
        use core::arch::x86_64::{_mm_movemask_epi8, _mm_packs_epi16, _mm_set_epi16};
        let c = covered;
        // SAFETY: SSE2 is part of the x86-64 baseline; no memory is accessed.
        let bits = unsafe {
            let v = _mm_set_epi16(c[7], c[6], c[5], c[4], c[3], c[2], c[1], c[0]);
            _mm_movemask_epi8(_mm_packs_epi16(v, v)) as u32 & 0xFF
        };
        (bits | 1 << LANES).trailing_zeros()
    }

    /// Draws `triangle` with `colors` (see [`walk`]).
    #[inline(always)]
    pub(crate) fn draw<C: GouraudColor>(
        framebuffer: &mut SliceFramebuffer<'_, C>,
        triangle: &CompactTriangle,
        colors: &CompactColors,
        steps: &SpanSteps,
    ) -> bool {
        use core::arch::x86_64::*;
        // The channels in one SSE2 register (the fourth lane unused): the row's values stepped
        // by dy, and the first pixel's offset from a table of dx·column (column 0..=8).
        let vector = |v: [u32; 3]| {
            // SAFETY: SSE2 is part of the x86-64 baseline.
            unsafe { _mm_setr_epi32(v[0] as i32, v[1] as i32, v[2] as i32, 0) }
        };
        let (dx, dy, zero) = (vector(colors.dx), vector(colors.dy), vector([0; 3]));
        let mut next = zero;
        let by_column: [__m128i; LANES + 1] = core::array::from_fn(|_| {
            let this = next;
            // SAFETY: as above.
            next = unsafe { _mm_add_epi32(next, dx) };
            this
        });
        let mut row_value = vector(colors.value);
        walk(framebuffer, triangle, |row, covered, first, column| {
            let offset = by_column.get(column as usize).copied().unwrap_or(zero);
            let mut start = [0u32; 4];
            // SAFETY: as above; the store writes the 16 bytes of `start`.
            unsafe {
                _mm_storeu_si128(start.as_mut_ptr().cast(), _mm_add_epi32(row_value, offset));
                row_value = _mm_add_epi32(row_value, dy);
            }
            C::fill_masked_row(row, covered, first, [start[0], start[1], start[2]], steps);
        })
    }

    /// Fills the covered pixels of `triangle` with `color` (see [`walk`]).
    #[inline(always)]
    pub(crate) fn fill<C: PixelColor>(
        framebuffer: &mut SliceFramebuffer<'_, C>,
        triangle: &CompactTriangle,
        color: C,
    ) -> bool {
        walk(framebuffer, triangle, |row, covered, _, _| {
            // The whole row read, then written: a select of values, which LLVM vectorises (a
            // select of a load per pixel becomes a branch per pixel).
            let old = *row;
            *row = core::array::from_fn(|i| if covered[i] != 0 { color } else { old[i] });
        })
    }
}

// Only where the path is taken: elsewhere `draw_into` walks spans, and these tests would compare
// the walk with itself.
#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use embedded_graphics::pixelcolor::{Bgr565, Gray8, Rgb565, Rgb888};

    use embedded_graphics::Drawable;

    use crate::{Coord, GouraudColor, GouraudTriangle, SolidTriangle, Vertex};

    /// Tiny and small triangles drawn by `draw_into` (this path, for the tiny ones) and by the
    /// span walk (`draw_into_compact`; `Drawable::draw` for solid ones) give the same
    /// framebuffer, pixel for pixel: over random backgrounds, near and across every border of
    /// framebuffers 8 to 21 pixels wide.
    fn same_as_the_span_walk<C: GouraudColor + core::fmt::Debug>(
        seed: u64,
        color: impl Fn(u64) -> C,
    ) {
        let mut next = crate::xorshift(seed);
        let mut tiny = 0;
        for n in 0..40_000 {
            let (width, height) = (8 + (next() % 14) as u32, 1 + (next() % 14) as u32);
            let len = (width * height) as usize;
            let mut background = [color(0); 21 * 14];
            for px in &mut background[..len] {
                *px = color(next());
            }
            // Boxes up to 9 pixels (some just past the tiny limit), anywhere over the buffer; a
            // quarter near the limit with vertices on the box's corners, across the right border
            // (the eight lanes then reach furthest from the vertices: edge values wrap there).
            let extreme = n % 4 == 1;
            let size = if extreme {
                1792 + (next() % 256) as i32
            } else {
                1 + (next() % (9 * 256)) as i32
            };
            let origin = (
                if extreme {
                    (width as i32 - 7) * 256 + (next() % 1536) as i32
                } else {
                    (next() % u64::from(width + 8) * 256) as i32 - 6 * 256
                },
                (next() % u64::from(height + 8) * 256) as i32 - 6 * 256,
            );
            // A third on a 1/2-pixel lattice: edges through pixel centres (the fill rule's ties).
            let lattice = if n % 3 == 0 { !127 } else { !0 };
            let v: [Vertex<C>; 3] = core::array::from_fn(|_| {
                let mut at = |o: i32| {
                    let d = if extreme {
                        (next() % 2) as i32 * (size - 1)
                    } else {
                        (next() % size as u64) as i32
                    };
                    (o + d) & lattice
                };
                let (x, y) = (at(origin.0), at(origin.1));
                Vertex::new(Coord::from_bits(x), Coord::from_bits(y), color(next()))
            });
            let triangle = GouraudTriangle::new(v);
            let (mut got, mut want) = (background, background);
            let mut fb = crate::SliceFramebuffer::new(&mut got[..len], width, height).unwrap();
            triangle.draw_into(&mut fb);
            let mut fb = crate::SliceFramebuffer::new(&mut want[..len], width, height).unwrap();
            assert_eq!(triangle.draw_into_compact(&mut fb), Ok(()));
            assert!(got == want, "case {n}: {width}×{height}, {v:?}");
            // Solid: `draw_into` (this path) against `Drawable::draw` (the span walk).
            let solid = SolidTriangle::new(v.map(|v| v.position()), v[0].color);
            let (mut got, mut want) = (background, background);
            let mut fb = crate::SliceFramebuffer::new(&mut got[..len], width, height).unwrap();
            solid.draw_into(&mut fb);
            let mut fb = crate::SliceFramebuffer::new(&mut want[..len], width, height).unwrap();
            let Ok(()) = solid.draw(&mut fb);
            assert!(got == want, "solid case {n}: {width}×{height}, {v:?}");
            tiny += usize::from(size < 2048);
        }
        assert!(tiny > 20_000);
    }

    #[test]
    fn rgb565_rows_are_the_span_walks_pixels() {
        same_as_the_span_walk(0x7157_0001, |r| {
            Rgb565::from(embedded_graphics::pixelcolor::raw::RawU16::new(r as u16))
        });
    }

    #[test]
    fn bgr565_rows_are_the_span_walks_pixels() {
        same_as_the_span_walk(0x7157_0002, |r| {
            Bgr565::from(embedded_graphics::pixelcolor::raw::RawU16::new(r as u16))
        });
    }

    #[test]
    fn default_rows_are_the_span_walks_pixels() {
        same_as_the_span_walk(0x7157_0003, |r| {
            Rgb888::new(r as u8, (r >> 8) as u8, (r >> 16) as u8)
        });
        same_as_the_span_walk(0x7157_0004, |r| Gray8::new(r as u8));
    }
}
