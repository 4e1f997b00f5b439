//! Span shaders: what the walks and the scan hand each covered span to (like tiny-skia's
//! `Blitter`), with the attributes at its first pixel. The drawables of `draw` are span
//! shaders: a solid fill, the colour format's span loop into a slice, or `fill_contiguous` of
//! any `DrawTarget`; the 3D pipeline's depth-tested fills too.

use core::ops::ControlFlow;

use super::runs::SmallScan;
use super::walk::Span;
use crate::arch::LANES;

/// What the walk hands each covered span to (like tiny-skia's `Blitter`).
///
/// Attributes are the `N` planes of [`shade`]'s vertex values, as [`STEP_BITS`] fixed point
/// (+½ included, so truncation rounds), wrapping: the value at a span's first pixel comes with the
/// span, the per-pixel steps once per triangle.
///
/// [`STEP_BITS`]: super::plane::STEP_BITS
pub(crate) trait SpanShader<const N: usize> {
    /// What the shader makes of a triangle's per-pixel steps: built once per triangle and handed
    /// back with every span (a local of the walk's frame, so the shader needs no placeholder).
    type Steps;

    /// Once per triangle, before its first span: the attributes' per-pixel steps.
    fn prepare(&mut self, step: [u32; N]) -> Self::Steps;

    /// One covered span; `start` holds the attributes at its first pixel.
    fn span(&mut self, steps: &Self::Steps, span: Span, start: [u32; N]);

    /// Whether the shader takes no more spans (a `DrawTarget` returned an error): asked after
    /// each span of the walk, the scan and the exact planes' chunks, and the triangle then ends
    /// there, however many rows it has left. `false` (the default) for shaders that take every
    /// span: the check then compiles to nothing where the shader is known (behind a vtable, a
    /// test of the answer [`SpanSink::take`] returns). Not asked between the rows of lanes of
    /// [`masked_row`](Self::masked_row) (tiny triangles, under 8 rows, into framebuffers).
    #[inline(always)]
    fn stopped(&self) -> bool {
        false
    }

    /// Whether triangles under [`SMALL`](super::runs::SMALL) pixels are scanned row by row
    /// instead of walked (the same spans, no divisions; see `scan.rs`). `false` (the
    /// default) keeps a firmware that draws only with this shader from linking the scan.
    #[inline(always)]
    fn scans_small(&self) -> bool {
        false
    }

    /// Whether a scanned small triangle takes the compact walk's planes (`Planes::compact`, the
    /// integers a walk of it has: the 2D fills, whose other paths walk it) rather than the small
    /// set-up's own (`false`, the default: the 3D fills, which scan small triangles on every
    /// path, and ARMv7-M's assembly set-ups with them).
    #[inline(always)]
    fn walk_planes(&self) -> bool {
        false
    }

    /// All rows of a scanned small triangle at once (where a dedicated row loop is faster than a
    /// call a span): `true` if done, `false` (the default) to be handed its spans. Asked only
    /// where a division is an instruction.
    #[inline(always)]
    fn small_rows(&mut self, _scan: &SmallScan<'_, N>) -> bool {
        false
    }

    /// The target's width if it takes whole rows of [`LANES`] pixels ([`masked_row`]), the
    /// strategy for tiny triangles on x86-64; `None` (the default): spans only.
    ///
    /// [`masked_row`]: Self::masked_row
    #[cfg_attr(not(sse2_rows), allow(dead_code))]
    #[inline(always)]
    fn row_width(&self) -> Option<u32> {
        None
    }

    /// Pixels `x .. x + LANES` of row `y` (inside the target): those with `covered[i] = −1`
    /// form one run from pixel `first`, which gets the span colours from `start`; the others
    /// keep theirs. Only called when [`row_width`](Self::row_width) is `Some`.
    #[cfg_attr(not(sse2_rows), allow(dead_code))]
    #[inline(always)]
    fn masked_row(
        &mut self,
        _steps: &Self::Steps,
        _y: i32,
        _x: i32,
        _covered: [i16; LANES],
        _first: u32,
        _start: [u32; N],
    ) {
    }
}

/// A [`SpanShader`] as the walks call it: a span and whether the walk goes on after it
/// ([`SpanShader::stopped`]) in one call, which is also one call where the shader is behind a
/// vtable (the Cortex-M0's walk, the general set-up's): for shaders that never stop, the answer
/// is a constant inside it.
pub(crate) trait SpanSink<const N: usize> {
    /// The shader's [`Steps`](SpanShader::Steps).
    type Steps;

    /// [`SpanShader::prepare`].
    fn begin(&mut self, step: [u32; N]) -> Self::Steps;

    /// [`SpanShader::span`], then `Break` if the shader has stopped.
    fn take(&mut self, steps: &Self::Steps, span: Span, start: [u32; N]) -> ControlFlow<()>;
}

impl<S: SpanShader<N>, const N: usize> SpanSink<N> for S {
    type Steps = S::Steps;

    #[inline(always)]
    fn begin(&mut self, step: [u32; N]) -> S::Steps {
        self.prepare(step)
    }

    #[inline(always)]
    fn take(&mut self, steps: &S::Steps, span: Span, start: [u32; N]) -> ControlFlow<()> {
        self.span(steps, span, start);
        if self.stopped() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}
