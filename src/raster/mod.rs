//! The raster core: from three sub-pixel vertices to covered spans and interpolated attributes.
//!
//! The stages run one way, each in its own file, and each uses only those listed before it:
//!
//! * `arith` — the integer helpers the set-up needs on cores without a long multiply, a divider
//!   or `clz` (and its rare 128-bit divisions, in a few hundred bytes of flash).
//! * `edge` — the fill rule, stated once: integer edge functions of the oriented triangle with
//!   the Direct3D top-left rule, reduced so that a pixel is covered exactly when three integers
//!   are non-negative. Set-up arithmetic is chosen here: `i64` for vertices within about two
//!   million pixels, `i128` beyond.
//! * `coverage` — anti-aliasing: the area of each pixel square inside a triangle, from the exact
//!   edge functions.
//! * `walk` — the covered spans of a triangle clipped to a rectangle, top to bottom, by
//!   stepping one start and one end boundary column a row (exact quotient and remainder, no
//!   rounding, in 32 bits for any triangle), set up exactly in `i64`/`i128`; the pixel region,
//!   a band's rows and the choice of edges for each side of the rows.
//! * `compact` — the same walk set up in 32-bit arithmetic for triangles under 2048 px.
//! * `spans` — the public span iterator over either set-up's walk.
//! * `plane` — attributes (colour channels now) interpolated barycentrically by fixed-point
//!   stepping, with a documented error bound.
//! * `perspective` — perspective-correct barycentrics from three more planes (`q ∝ 1/w` and
//!   `bₖ·q`), recovered every few pixels of a span by one reciprocal: what textures and light
//!   levels in 3D are corrected with.
//! * `runs` — a small triangle's rows as runs between its edges' bounds, as a shader that
//!   draws them all at once sees them.
//! * `sink` — the span shaders (`SpanShader`, like tiny-skia's `Blitter`): what every walk
//!   hands its covered spans to (solid fill, a colour format's span loop, `fill_contiguous`, …).
//! * `polygon` — polygons of any number of contours under the non-zero or even-odd rule: each
//!   edge's crossing of the rows stepped exactly, the runs between them handed to a span shader
//!   (the triangles' fill rule, for any orientation).
//! * `line` — thin lines under the diamond-exit rule: the crossing stepped along the major
//!   axis, the exact test near the ends.
//! * `scan` — small triangles (under 16 px) for shaders that opt in: each row's run found by
//!   testing its pixels' edge values, the same spans without the walk's divisions.
//! * `tiny` (x86-64) — triangles under 8 px drawn a row of lanes at a time.
//! * `shade` — the one entry: `shade` sets a triangle up in the width it needs (scan, compact
//!   or general), walks it and hands each covered span with its attributes to a shader.
//! * `band` — a band's rows of a triangle (`shade_rows`): set up over the frame's clip, the walk
//!   started at the band's first row, the same spans and values as the whole walk's there.

pub(crate) mod arith;
pub(crate) mod band;
pub(crate) mod compact;
pub(crate) mod coverage;
pub(crate) mod edge;
pub(crate) mod line;
pub(crate) mod perspective;
pub(crate) mod plane;
pub(crate) mod polygon;
pub(crate) mod runs;
pub(crate) mod scan;
mod shade;
pub(crate) mod sink;
mod spans;
#[cfg(sse2_rows)]
mod tiny;
pub(crate) mod walk;

pub use compact::{TooLarge, LIMIT as COMPACT_LIMIT};
pub use plane::{MAX_CHUNK, STEP_BITS};
pub use polygon::FillRule;
#[cfg(test)]
pub(crate) use shade::Counting;
pub(crate) use shade::{shade, shade_compact};
pub(crate) use sink::SpanShader;
pub use spans::{for_each_span, Spans};
pub use walk::Span;
