//! Tiny triangles on x86-64: the Gouraud and solid fills of the raster core's rows of
//! [`LANES`](crate::color::LANES) pixels (see `raster::tiny`).

use embedded_graphics::pixelcolor::PixelColor;
use embedded_graphics::prelude::*;

use super::framebuffer::SliceFramebuffer;
use crate::arch::x86_64::ChannelRows;
use crate::color::{GouraudColor, SpanSteps};
use crate::raster::compact::{CompactColors, CompactTriangle};
use crate::raster::tiny::walk;

/// Draws `triangle` with `colors` if it is tiny (see [`walk`]); `false` (nothing drawn)
/// otherwise. Each row's run gets the colours of the span fill from its first pixel.
#[inline(always)]
pub(super) fn draw<C: GouraudColor>(
    framebuffer: &mut SliceFramebuffer<'_, C>,
    triangle: &CompactTriangle,
    colors: &CompactColors,
    steps: &SpanSteps,
) -> bool {
    let mut rows = ChannelRows::new(colors.value, colors.dx, colors.dy);
    let width = framebuffer.size().width;
    walk(
        framebuffer.pixels_mut(),
        width,
        triangle,
        |row, covered, first, column| {
            let start = rows.next_row(column);
            C::fill_masked_row(row, covered, first, start, steps);
        },
    )
}

/// Fills the covered pixels of `triangle` with `color` if it is tiny (see [`walk`]).
#[inline(always)]
pub(super) fn fill<C: PixelColor>(
    framebuffer: &mut SliceFramebuffer<'_, C>,
    triangle: &CompactTriangle,
    color: C,
) -> bool {
    let width = framebuffer.size().width;
    walk(
        framebuffer.pixels_mut(),
        width,
        triangle,
        |row, covered, _, _| {
            // The whole row read, then written: a select of values, which LLVM vectorises (a
            // select of a load per pixel becomes a branch per pixel).
            let old = *row;
            *row = core::array::from_fn(|i| if covered[i] != 0 { color } else { old[i] });
        },
    )
}

#[cfg(test)]
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
