//! Span shaders: what the walk hands its covered spans to, and the one entry that sets a triangle
//! up, walks it and interpolates its attributes.
//!
//! [`shade`] picks the arithmetic a triangle needs — the 32-bit compact set-up for bounding boxes
//! under 2048 px, the `i64`/`i128` one beyond — builds the [`Walk`](super::walk) and the
//! attribute planes ([`Planes`]) and calls the [`SpanShader`] once per covered span with the
//! attributes at the span's first pixel. The drawables of `draw` are span shaders: a solid fill,
//! the colour format's span loop into a slice, or `fill_contiguous` of any `DrawTarget`.

use core::ops::ControlFlow;

use embedded_graphics::primitives::Rectangle;

use super::compact::{CompactTriangle, TooLarge};
use super::edge::TriangleSetup;
use super::plane::{Attributes, ExactPlanes, GeneralPlanes, Planes, MAX_CHUNK};
pub(crate) use super::sink::{SpanShader, SpanSink};
use super::walk::{general_walk, Band, Region, Span, Walk};
use crate::arch::MCU;
use crate::fixed_point::Coord;

/// Walks the triangle `v` inside `clip` and hands `shader` its covered spans with the planes
/// of `attributes`. Degenerate triangles draw nothing.
#[inline(always)]
pub(crate) fn shade<const N: usize>(
    v: [(Coord, Coord); 3],
    attributes: &Attributes<N>,
    clip: &Rectangle,
    shader: &mut impl SpanShader<N>,
) {
    if shader.scans_small() {
        if !super::scan::shade(v, attributes, clip, shader) {
            shade_not_small(v, *attributes, clip, shader);
        }
        return;
    }
    shade_walked(v, attributes, clip, shader);
}

/// [`shade_walked`] out of line, for shaders that scan small triangles: their triangles are
/// mostly small, and the walk's set-up kept out of the scan's frame leaves it its registers (the
/// attributes by value: a copy made here, not one the scan's frame keeps in memory for it).
#[inline(never)]
fn shade_not_small<const N: usize>(
    v: [(Coord, Coord); 3],
    attributes: Attributes<N>,
    clip: &Rectangle,
    shader: &mut impl SpanShader<N>,
) {
    shade_walked(v, &attributes, clip, shader);
}

/// [`shade`] for the triangles that are not scanned: the compact set-up and walk, or the
/// general ones.
#[inline(always)]
fn shade_walked<const N: usize>(
    v: [(Coord, Coord); 3],
    attributes: &Attributes<N>,
    clip: &Rectangle,
    shader: &mut impl SpanShader<N>,
) {
    #[cfg(armv6m)]
    {
        shade_dyn(v, attributes, clip, shader);
    }
    #[cfg(not(armv6m))]
    {
        // The compact walk (on x86-64 tiny triangles a row of lanes at a time), else the
        // general one.
        let compact =
            |triangle: &CompactTriangle| shade_compact_triangle(triangle, attributes, shader);
        let classified = CompactTriangle::classify(v, clip);
        if let Err(Some(region)) = classified.compact_or_region(compact) {
            shade_general(v, attributes, &region, None, shader);
        }
    }
}

/// [`shade_walked`] on Cortex-M0, where flash is scarcest: every triangle, compact or not, goes
/// through one set-up and one walk per kind of span steps, the shader called through a vtable
/// (a call a span: a few per cent more instructions a pixel, see `docs/benchmarks.md`). A
/// firmware drawing through `draw` and `draw_into` then links the walk once, not once per shader
/// and set-up.
#[cfg(armv6m)]
#[inline(never)]
fn shade_dyn<T, const N: usize>(
    v: [(Coord, Coord); 3],
    attributes: &Attributes<N>,
    clip: &Rectangle,
    shader: &mut dyn SpanSink<N, Steps = T>,
) {
    let exact;
    let (walk, planes) = match CompactTriangle::classify(v, clip).walk() {
        Ok((triangle, walk)) => {
            let planes = Planes::compact(&triangle.setup, attributes);
            (walk, GeneralPlanes::Stepped(planes))
        }
        Err(None) => return,
        Err(Some(region)) => {
            let Some((walk, planes)) = general_set_up(v, attributes, &region, None) else {
                return;
            };
            exact = planes;
            (walk, GeneralPlanes::new(&exact, &region))
        }
    };
    fold_general(walk, &planes, shader);
}

/// [`shade`] for compact triangles only (bounding box under 2048 × 2048 px); `Err(TooLarge)`
/// without drawing for the others. A firmware drawing only through this links only the 32-bit
/// set-up and walk.
#[inline(always)]
pub(crate) fn shade_compact<const N: usize>(
    v: [(Coord, Coord); 3],
    attributes: &Attributes<N>,
    clip: &Rectangle,
    shader: &mut impl SpanShader<N>,
) -> Result<(), TooLarge> {
    match CompactTriangle::new(v, clip)? {
        Some(triangle) => shade_compact_triangle(&triangle, attributes, shader),
        None => Ok(()),
    }
}

/// The compact set-up's walk and planes (the planes after the walk's set-up: on Cortex-M0 fewer
/// values then live across it).
#[inline(always)]
fn shade_compact_triangle<const N: usize, S: SpanShader<N>>(
    triangle: &CompactTriangle,
    attributes: &Attributes<N>,
    shader: &mut S,
) -> Result<(), TooLarge> {
    #[cfg(sse2_rows)]
    if let Some(width) = shader.row_width() {
        let planes = Planes::compact(&triangle.setup, attributes);
        if super::tiny::shade(triangle, &planes, width, shader) {
            return Ok(());
        }
        let walk = triangle.walk()?;
        fold_planes(walk, &planes, shader);
        return Ok(());
    }
    let walk = triangle.walk()?;
    let planes = Planes::compact(&triangle.setup, attributes);
    fold_planes(walk, &planes, shader);
    Ok(())
}

/// Prepares `shader` for the planes' steps and hands it the spans of `walk` with the stepped
/// planes' values at their first pixels.
#[inline(always)]
pub(super) fn fold_planes<const N: usize, S: SpanSink<N> + ?Sized>(
    walk: Walk,
    planes: &Planes<N>,
    shader: &mut S,
) {
    let steps = shader.begin(planes.step());
    // The closures are inlined: each has a call site for every walk of this width, and LLVM
    // would rather call it than copy it, at a call's cost every span. Steps without data (solid
    // fills) are moved in: a reference to them would still be a pointer kept live across the
    // walk. Others stay in this frame and go by reference: the span loops read them from memory.
    if core::mem::size_of_val(&steps) == 0 {
        let _ = walk.try_fold(
            (),
            #[inline(always)]
            move |(), span, column, row| shader.take(&steps, span, planes.at(column, row)),
        );
    } else {
        let steps = &steps;
        let _ = walk.try_fold(
            (),
            #[inline(always)]
            move |(), span, column, row| shader.take(steps, span, planes.at(column, row)),
        );
    }
}

/// The general set-up (any [`Coord`]): `i64`/`i128` edge functions, stepped planes where their
/// error bound holds (regions up to 2¹⁶ px across), exact ones (a division per span chunk)
/// beyond.
///
/// Only triangles 2048 px or more across come here, whose spans are long: the shader is called
/// through a vtable, so one copy of this path serves every shader (flash on Cortex-M).
///
/// With a `band`, only its rows are walked (see `band.rs`): the planes (stepped or
/// exact) are still those of the whole region over `clip`, and the walk counts its rows from
/// that region's first.
#[inline(never)]
pub(super) fn shade_general<T, const N: usize>(
    v: [(Coord, Coord); 3],
    attributes: &Attributes<N>,
    region: &Region,
    band: Option<Band>,
    shader: &mut dyn SpanSink<N, Steps = T>,
) {
    if let Some((walk, exact)) = general_set_up(v, attributes, region, band) {
        fold_general(walk, &GeneralPlanes::new(&exact, region), shader);
    }
}

/// The general set-up of the triangle `v` over `region`, the pixels of its bounding box inside
/// the clip rectangle (not empty): its walk over the rows of `band` (all rows without one) and
/// its exact planes over the whole region, whatever the band (the walk counts its rows from the
/// region's first, so each pixel gets the whole walk's values). `None` if the vertices are
/// collinear or the band has no rows of the region.
#[inline(always)]
fn general_set_up<const N: usize>(
    v: [(Coord, Coord); 3],
    attributes: &Attributes<N>,
    region: &Region,
    band: Option<Band>,
) -> Option<(Walk, ExactPlanes<N>)> {
    // By reference: moving the setup out of the `Option` would copy it.
    let setup = TriangleSetup::new(v);
    let setup = setup.as_ref()?;
    let rows = match band {
        None => *region,
        Some(band) => {
            let (y0, y1, _) = band.restrict(region.y0, region.y1)?;
            Region { y0, y1, ..*region }
        }
    };
    let exact = ExactPlanes::new(setup, region, attributes);
    Some((general_walk(setup, region, &rows), exact))
}

/// [`fold_planes`] for the general planes: spans of stepped planes as there, those of exact
/// ones in chunks ([`shade_exact`]). Hosts get a walk for each kind of planes; on Cortex-M one
/// walk serves both, the span's planes chosen a span (flash).
#[inline(always)]
fn fold_general<T, const N: usize>(
    walk: Walk,
    planes: &GeneralPlanes<N>,
    shader: &mut dyn SpanSink<N, Steps = T>,
) {
    if MCU {
        let steps = shader.begin(match planes {
            GeneralPlanes::Stepped(p) => p.step(),
            GeneralPlanes::Exact(p) => p.step(),
        });
        let steps = &steps;
        let _ = walk.try_fold((), |(), span, column, row| match planes {
            GeneralPlanes::Stepped(p) => shader.take(steps, span, p.at(column, row)),
            GeneralPlanes::Exact(p) => shade_exact(p, steps, span, shader),
        });
    } else {
        match planes {
            GeneralPlanes::Stepped(p) => fold_planes(walk, p, shader),
            GeneralPlanes::Exact(p) => {
                let steps = shader.begin(p.step());
                let steps = &steps;
                let _ = walk.try_fold((), |(), span, _, _| shade_exact(p, steps, span, shader));
            }
        }
    }
}

/// A span of exact planes (regions over 2¹⁶ pixels across): in chunks of at most
/// [`MAX_CHUNK`] pixels, every chunk started from the exact value, so the per-pixel steps add at
/// most 2⁻¹³ LSB. `Break` once the shader has stopped, the rest of the span not handed over.
#[cold]
#[inline(never)]
fn shade_exact<T, const N: usize>(
    planes: &ExactPlanes<N>,
    steps: &T,
    span: Span,
    shader: &mut dyn SpanSink<N, Steps = T>,
) -> ControlFlow<()> {
    let mut offset = 0;
    while offset < span.len() {
        let len = (span.len() - offset).min(MAX_CHUNK);
        // Inside the span, which lies inside the region: no overflow.
        let x_start = span.x_start.wrapping_add(offset as i32);
        let chunk = Span {
            y: span.y,
            x_start,
            x_end: x_start.wrapping_add(len as i32),
        };
        shader.take(steps, chunk, planes.at(x_start, span.y))?;
        offset += len;
    }
    ControlFlow::Continue(())
}

/// A shader as the walk sees it, counting the spans it is handed (the drawables' tests: after a
/// target's error, none). The walk is cut after [`CAP`](Counting::CAP) spans whether `shader`
/// stops or not: a shader that does not stop is then seen to take them, in no time.
#[cfg(test)]
pub(crate) struct Counting<S> {
    pub(crate) shader: S,
    pub(crate) handed: u32,
}

#[cfg(test)]
impl<S> Counting<S> {
    /// Spans after which the walk is cut.
    pub(crate) const CAP: u32 = 10;

    pub(crate) fn new(shader: S) -> Self {
        Counting { shader, handed: 0 }
    }
}

#[cfg(test)]
impl<S: SpanShader<N>, const N: usize> SpanShader<N> for Counting<S> {
    type Steps = S::Steps;

    fn prepare(&mut self, step: [u32; N]) -> S::Steps {
        self.shader.prepare(step)
    }

    fn span(&mut self, steps: &S::Steps, span: Span, start: [u32; N]) {
        self.handed += 1;
        self.shader.span(steps, span, start);
    }

    fn scans_small(&self) -> bool {
        self.shader.scans_small()
    }

    fn stopped(&self) -> bool {
        self.shader.stopped() || self.handed >= Self::CAP
    }
}

#[cfg(test)]
mod tests {
    use embedded_graphics::prelude::{Point, Size};

    use super::*;

    /// A shader that has [stopped](SpanShader::stopped) once it has taken `limit` spans, and
    /// counts every span it is handed.
    struct Stopping {
        limit: u32,
        handed: u32,
        scans: bool,
    }

    impl SpanShader<1> for Stopping {
        type Steps = ();

        fn prepare(&mut self, _: [u32; 1]) {}

        fn span(&mut self, _: &(), _: Span, _: [u32; 1]) {
            self.handed += 1;
        }

        fn scans_small(&self) -> bool {
            self.scans
        }

        fn stopped(&self) -> bool {
            self.handed >= self.limit
        }
    }

    /// Spans handed to a shader that stops after `limit`.
    fn handed(v: [(i32, i32); 3], clip: &Rectangle, limit: u32, scans: bool) -> u32 {
        let v = v.map(|(x, y)| (Coord::from_num(x), Coord::from_num(y)));
        let attributes = Attributes::channels([[0], [128], [255]]);
        let mut shader = Stopping {
            limit,
            handed: 0,
            scans,
        };
        shade(v, &attributes, clip, &mut shader);
        shader.handed
    }

    /// 2²³ − 1 pixels: the ends of the `Coord` range.
    const FAR: i32 = (1 << 23) - 1;

    /// Once the shader has stopped, the walk hands it nothing more: small (scanned) triangles,
    /// compact ones, general ones with stepped planes and with exact ones (spans cut into
    /// chunks), into a clip of a few hundred pixels and one of over 10⁹ pixels a side — where
    /// the whole walk would hand out billions of chunks (issue #32, item 11).
    #[test]
    fn a_stopped_shader_ends_the_walk() {
        let screen = Rectangle::new(Point::new(-20, -10), Size::new(640, 480));
        let huge = Rectangle::new(
            Point::new(-600_000_000, -700_000_000),
            Size::new(1_200_000_000, 1_400_000_000),
        );
        let triangles = [
            // Small: scanned where the shader asks for it.
            [(2, 1), (11, 4), (5, 12)],
            // Compact.
            [(3, 2), (400, 50), (90, 350)],
            // General, stepped planes.
            [(-3_000, -2_000), (3_000, -1_000), (0, 2_500)],
            // General, exact planes over the huge clip (a region over 2¹⁶ pixels across); the
            // second with a flat top, its first span cut into 4,096 chunks.
            [(-FAR, -FAR), (FAR, -FAR / 2), (-FAR / 3, FAR)],
            [(-FAR, -FAR), (FAR, -FAR), (0, FAR)],
        ];
        for (k, v) in triangles.into_iter().enumerate() {
            for clip in [screen, huge] {
                for scans in [false, true] {
                    if k < 3 {
                        // Without stopping: more spans than are taken below.
                        assert!(handed(v, &clip, u32::MAX, scans) > 3, "{v:?}");
                    }
                    for limit in [1, 2, 3] {
                        assert_eq!(
                            handed(v, &clip, limit, scans),
                            limit,
                            "{v:?} in {clip:?}, scanned: {scans}"
                        );
                    }
                }
            }
        }
    }
}
