//! Band walks: the rows of a band of a frame, as the walk over the whole frame's clip gives them.
//!
//! A frame drawn in bands must be the frame drawn at once, bit for bit. Coverage is exact
//! however a walk is clipped, but the attribute planes are not: every set-up starts its planes
//! at the first pixel of the triangle's region over the clip (rounded there) and steps them
//! from it, so a walk clipped to a band's rows would round at another pixel and could differ by
//! an LSB. [`shade_rows`] therefore sets the triangle up over the frame's clip — the same size
//! class (small, compact, general), the same region and the same planes as [`shade`] — and
//! only then restricts the walk to the band's rows: the walk starts at the band's first row (its
//! boundaries computed there exactly, not stepped from the top) and the planes are advanced to
//! that row in the wrapping integers every walk uses, `value + dy·rows` modulo 2³², so each
//! pixel gets the integer the whole walk gives it.
//!
//! The band's buffer holds only its rows: the spans reach the shader with their rows counted
//! from the band's first ([`Band::local`]).
//!
//! [`shade`]: super::shade

use embedded_graphics::prelude::{Point, Size};
use embedded_graphics::primitives::Rectangle;

use super::compact::{CompactTriangle, TooLarge};
use super::edge::{first_centre_from, last_centre_to};
use super::line::draw_line;
use super::plane::{Attributes, Planes};
use super::runs::SmallScan;
use super::scan::{Kept, KeptWords};
use super::shade::{fold_planes, shade, shade_general};
use super::sink::SpanShader;
use super::walk::{Band, Span};
use crate::arch::LANES;
use crate::fixed_point::{Coord, SUBPIXEL_BITS};
use crate::rect::intersection;

/// Which rows of a frame a draw hands out, and where they go: all of them in place
/// ([`AllRows`]) or a band's, into the band's buffer ([`Band`]). The full-frame draws are
/// generic over it so that they cost nothing for it.
pub(crate) trait RowWindow: Copy {
    /// Draws the rows of the window of the triangle `v` with `attributes` over `clip` (the
    /// frame's clip) through `shader`: the spans and values [`shade`] gives those rows. The
    /// shader is taken and given back by value: a local of the draw, which the compiler keeps
    /// in registers.
    fn shade<const N: usize, S: SpanShader<N>>(
        &self,
        v: [(Coord, Coord); 3],
        attributes: &Attributes<N>,
        clip: &Rectangle,
        shader: S,
    ) -> S;

    /// Whether a triangle whose vertices are at the sub-pixel heights `y` may cover a pixel of
    /// the window (`false` only if it covers none).
    fn touches(&self, y: [i32; 3]) -> bool;

    /// The band, if the window is one.
    fn band(&self) -> Option<Band>;

    /// The window with a row more on each side (a band's; every row is every row): where a
    /// face's edges may draw, as thin lines, when the face covers no pixel centre of the window
    /// (a line draws a row its segment reaches within half a pixel of the centre of).
    fn widened(&self) -> Self;

    /// Draws the window's rows of the thin line from `p0` to `p1` (raw sub-pixels) over `clip`
    /// through `shader`: the pixels `raster::line` gives those rows.
    fn line<S: SpanShader<0>>(
        &self,
        p0: (i32, i32),
        p1: (i32, i32),
        clip: &Rectangle,
        shader: S,
    ) -> S;
}

/// Every row, in place: [`shade`] itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AllRows;

impl RowWindow for AllRows {
    #[inline(always)]
    fn shade<const N: usize, S: SpanShader<N>>(
        &self,
        v: [(Coord, Coord); 3],
        attributes: &Attributes<N>,
        clip: &Rectangle,
        mut shader: S,
    ) -> S {
        shade(v, attributes, clip, &mut shader);
        shader
    }

    #[inline(always)]
    fn touches(&self, _: [i32; 3]) -> bool {
        true
    }

    #[inline(always)]
    fn band(&self) -> Option<Band> {
        None
    }

    #[inline(always)]
    fn widened(&self) -> Self {
        AllRows
    }

    #[inline(always)]
    fn line<S: SpanShader<0>>(
        &self,
        p0: (i32, i32),
        p1: (i32, i32),
        clip: &Rectangle,
        mut shader: S,
    ) -> S {
        draw_line(p0, p1, clip, &mut shader);
        shader
    }
}

impl RowWindow for Band {
    #[inline(always)]
    fn shade<const N: usize, S: SpanShader<N>>(
        &self,
        v: [(Coord, Coord); 3],
        attributes: &Attributes<N>,
        clip: &Rectangle,
        shader: S,
    ) -> S {
        let mut local = Local {
            shader,
            band: *self,
        };
        shade_rows(v, attributes, clip, *self, &mut local, None::<&mut Kept>);
        local.shader
    }

    #[inline(always)]
    fn touches(&self, y: [i32; 3]) -> bool {
        let (top, bottom) = (y[0].min(y[1]).min(y[2]), y[0].max(y[1]).max(y[2]));
        // Rows whose centres lie between the vertices' heights: a superset of the covered ones.
        self.meets(first_centre_from(top), last_centre_to(bottom))
    }

    #[inline(always)]
    fn band(&self) -> Option<Band> {
        Some(*self)
    }

    fn widened(&self) -> Self {
        Band {
            first: self.first.saturating_sub(1),
            last: self.last.saturating_add(1),
        }
    }

    fn line<S: SpanShader<0>>(
        &self,
        p0: (i32, i32),
        p1: (i32, i32),
        clip: &Rectangle,
        shader: S,
    ) -> S {
        let mut local = Local {
            shader,
            band: *self,
        };
        // The band's rows of the clip: the line's pixels there are the whole line's (its rule
        // decides each pixel on its own).
        let rows = Rectangle::new(
            Point::new(clip.top_left.x, self.first),
            Size::new(
                clip.size.width,
                self.last.abs_diff(self.first).saturating_add(1),
            ),
        );
        draw_line(p0, p1, &intersection(clip, &rows), &mut local);
        local.shader
    }
}

/// Walks the triangle `v` with `attributes` over `clip` like [`shade`], but only the rows of
/// `band` (in frame rows; the spans reach `shader` as they are): the same spans and values as
/// `shade` gives those rows. Nothing for a band outside `clip`. With `keep`, whether a small
/// triangle's set-up went there (see [`scan::shade_rows`](super::scan::shade_rows)).
#[inline(always)]
pub(crate) fn shade_rows<const N: usize>(
    v: [(Coord, Coord); 3],
    attributes: &Attributes<N>,
    clip: &Rectangle,
    band: Band,
    shader: &mut impl SpanShader<N>,
    keep: Option<&mut impl KeptWords>,
) -> bool {
    if shader.scans_small() {
        return match super::scan::shade_rows(v, attributes, clip, &band, shader, keep) {
            Some(kept) => kept,
            None => {
                walked_rows_not_small(v, *attributes, clip, band, shader);
                false
            }
        };
    }
    walked_rows(v, attributes, clip, band, shader);
    false
}

/// [`walked_rows`] out of line, for shaders that scan small triangles (as `shade` keeps the
/// walk's set-up out of the scan's frame).
#[inline(never)]
fn walked_rows_not_small<const N: usize>(
    v: [(Coord, Coord); 3],
    attributes: Attributes<N>,
    clip: &Rectangle,
    band: Band,
    shader: &mut impl SpanShader<N>,
) {
    walked_rows(v, &attributes, clip, band, shader);
}

/// [`shade_rows`] for the triangles that are not scanned.
#[inline(always)]
fn walked_rows<const N: usize>(
    v: [(Coord, Coord); 3],
    attributes: &Attributes<N>,
    clip: &Rectangle,
    band: Band,
    shader: &mut impl SpanShader<N>,
) {
    let compact = |triangle: &CompactTriangle| compact_rows(triangle, attributes, &band, shader);
    if let Err(Some(region)) = CompactTriangle::classify(v, clip).compact_or_region(compact) {
        shade_general(v, attributes, &region, Some(band), shader);
    }
}

impl Band {
    /// [`RowWindow::shade`], writing a small triangle's set-up into `keep` for
    /// [`resume`](Self::resume) (if the shader scans small triangles): whether it did.
    #[inline(always)]
    pub(crate) fn shade_keeping<const N: usize, S: SpanShader<N>>(
        &self,
        v: [(Coord, Coord); 3],
        attributes: &Attributes<N>,
        clip: &Rectangle,
        shader: S,
        keep: &mut impl KeptWords,
    ) -> bool {
        let mut local = Local {
            shader,
            band: *self,
        };
        shade_rows(v, attributes, clip, *self, &mut local, Some(keep))
    }

    /// Draws this band's rows of the triangle whose set-up [`shade_keeping`](Self::shade_keeping)
    /// kept in `kept` through `shader` (of the type it drew with): the pixels and values
    /// `RowWindow::shade` gives them.
    #[inline(always)]
    pub(crate) fn resume<const N: usize, S: SpanShader<N>>(
        &self,
        kept: &impl KeptWords,
        shader: S,
    ) {
        let mut local = Local {
            shader,
            band: *self,
        };
        super::scan::resume_rows(kept, self, &mut local);
    }
}

/// The band's rows of a compact triangle: the walk of a copy set up from the band's first row,
/// the planes of the whole region advanced to it.
#[inline(always)]
fn compact_rows<const N: usize, S: SpanShader<N>>(
    triangle: &CompactTriangle,
    attributes: &Attributes<N>,
    band: &Band,
    shader: &mut S,
) -> Result<(), TooLarge> {
    if triangle.y0 >= band.first && triangle.y1 <= band.last {
        // Wholly inside the band: the whole walk.
        let walk = triangle.walk()?;
        let planes = Planes::compact(&triangle.setup, attributes);
        fold_planes(walk, &planes, shader);
        return Ok(());
    }
    let Some((y0, y1, skip)) = band.restrict(triangle.y0, triangle.y1) else {
        return Ok(());
    };
    let mut rows = *triangle;
    rows.y0 = y0;
    rows.y1 = y1;
    // The walk starts from the first pixel centre's offset from vertex 0: `skip` rows lower
    // (inside the bounding box, below 2¹⁹ sub-pixels).
    rows.setup.dy = triangle
        .setup
        .dy
        .wrapping_add((skip << SUBPIXEL_BITS) as i32);
    let walk = rows.walk()?;
    let planes = Planes::compact(&triangle.setup, attributes).advanced(skip);
    fold_planes(walk, &planes, shader);
    Ok(())
}

/// A shader seen through a band: each span's row counted from the band's first row.
struct Local<S> {
    shader: S,
    band: Band,
}

impl<S: SpanShader<N>, const N: usize> SpanShader<N> for Local<S> {
    type Steps = S::Steps;

    #[inline(always)]
    fn prepare(&mut self, step: [u32; N]) -> S::Steps {
        self.shader.prepare(step)
    }

    #[inline(always)]
    fn span(&mut self, steps: &S::Steps, span: Span, start: [u32; N]) {
        let span = Span {
            y: self.band.local(span.y),
            ..span
        };
        self.shader.span(steps, span, start);
    }

    #[inline(always)]
    fn stopped(&self) -> bool {
        self.shader.stopped()
    }

    #[inline(always)]
    fn scans_small(&self) -> bool {
        self.shader.scans_small()
    }

    #[inline(always)]
    fn small_rows(&mut self, scan: &SmallScan<'_, N>) -> bool {
        self.shader.small_rows(&scan.in_band(&self.band))
    }

    // No rows of lanes (x86-64's tiny triangles): they cover a triangle's whole box. The spans
    // give the same pixels.
    #[inline(always)]
    fn row_width(&self) -> Option<u32> {
        None
    }

    #[inline(always)]
    fn masked_row(&mut self, _: &S::Steps, _: i32, _: i32, _: [i16; LANES], _: u32, _: [u32; N]) {}
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::vec::Vec;

    use embedded_graphics::prelude::*;

    use super::*;

    /// Records the spans with their values at the first pixel, and the per-pixel steps.
    struct Record {
        spans: Vec<(Span, [u32; 2])>,
        steps: Option<[u32; 2]>,
        small: bool,
    }

    impl Record {
        fn new(small: bool) -> Self {
            Record {
                spans: Vec::new(),
                steps: None,
                small,
            }
        }
    }

    impl SpanShader<2> for Record {
        type Steps = ();
        fn prepare(&mut self, step: [u32; 2]) {
            self.steps = Some(step);
        }
        fn span(&mut self, _: &(), span: Span, start: [u32; 2]) {
            self.spans.push((span, start));
        }
        fn scans_small(&self) -> bool {
            self.small
        }
    }

    /// Random triangles of every size class (small, compact, general: up to 2²² px across and
    /// anywhere in the `Coord` range), slivers included, over random clips (some wider than the
    /// stepped planes take: exact planes); every band of random height over the clip's rows
    /// (and a little outside) gives exactly the spans, values and steps of the whole walk in
    /// its rows, with their rows counted from the band's first.
    #[test]
    fn bands_give_the_rows_of_the_whole_walk() {
        let mut next = crate::random(0xba4d_0000_0000_0001);
        let (mut spans, mut banded) = (0usize, 0usize);
        for i in 0..20_000 {
            let scale = [4, 10, 12, 14, 17, 20, 25, 30][i % 8];
            let origin = (next() % 4096) as i32 - 2048;
            let mut coord = || {
                let c = origin.wrapping_mul(256) + (next() % (1u64 << scale)) as i32
                    - (1 << (scale - 1));
                Coord::from_bits(c)
            };
            let mut v = [(coord(), coord()), (coord(), coord()), (coord(), coord())];
            if i % 5 == 0 {
                // A sliver: the third vertex near the line through the other two.
                let (a, b) = (v[0], v[1]);
                let t = (next() % 1025) as i64;
                let mut lerp = |p: Coord, q: Coord| {
                    let (p, q) = (i64::from(p.to_bits()), i64::from(q.to_bits()));
                    Coord::from_bits((p + (q - p) * t / 1024) as i32 + (next() % 3) as i32 - 1)
                };
                v[2] = (lerp(a.0, b.0), lerp(a.1, b.1));
            }
            let wide = i % 40 == 7;
            let size = if wide {
                // Over 2¹⁶ px across (width plus height) or a little under.
                Size::new(65_440 + (next() % 100) as u32, 1 + (next() % 100) as u32)
            } else {
                Size::new(1 + (next() % 80) as u32, 1 + (next() % 80) as u32)
            };
            let corner = |n: u64| origin - 40 + (n % 60) as i32;
            let x = if wide {
                origin - 32_000
            } else {
                corner(next())
            };
            let clip = Rectangle::new(Point::new(x, corner(next())), size);
            let attributes = Attributes {
                values: [(); 3].map(|_| [next() as u16, next() as u16]),
                half: [1 << 23, 1 << 15],
            };
            let small = i % 2 == 0;
            let mut whole = Record::new(small);
            shade(v, &attributes, &clip, &mut whole);
            spans += whole.spans.len();
            let height = 1 + (next() % 24) as i32;
            let mut first = clip.top_left.y - (next() % 3) as i32;
            let end = clip.top_left.y + clip.size.height as i32 + 2;
            while first < end {
                let band = Band {
                    first,
                    last: first + height - 1,
                };
                let rows = band.shade(v, &attributes, &clip, Record::new(small));
                let want: Vec<_> = whole
                    .spans
                    .iter()
                    .filter(|(s, _)| band.meets(s.y, s.y))
                    .map(|&(s, values)| {
                        (
                            Span {
                                y: s.y - first,
                                ..s
                            },
                            values,
                        )
                    })
                    .collect();
                assert_eq!(rows.spans, want, "{v:?} over {clip:?}, band {band:?}");
                if !want.is_empty() {
                    assert_eq!(rows.steps, whole.steps, "{v:?} over {clip:?}, {band:?}");
                    assert!(band.touches(v.map(|p| p.1.to_bits())));
                }
                banded += want.len();
                first += height;
            }
        }
        assert!(spans > 100_000 && banded == spans, "{spans} {banded}");
    }
}
