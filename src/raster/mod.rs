//! The raster core: from three sub-pixel vertices to covered spans and interpolated attributes.
//!
//! The stages run one way, each in its own file:
//!
//! * `edge` — the fill rule, stated once: integer edge functions of the oriented triangle with
//!   the Direct3D top-left rule, reduced so that a pixel is covered exactly when three integers
//!   are non-negative. Set-up arithmetic is chosen here: `i64` for vertices within about two
//!   million pixels, `i128` beyond.
//! * `walk` — the covered spans of a triangle clipped to a rectangle, top to bottom, by
//!   stepping one start and one end boundary column a row (exact quotient and remainder, no
//!   rounding, in 32 bits for any triangle). `compact` sets the same walk up in 32-bit
//!   arithmetic for triangles under 2048 px, `walk` itself exactly in `i64`/`i128` for the
//!   others; both share the pixel region and the choice of edges for each side of the rows.
//!   `tiny` (x86-64) draws triangles under 8 px a row of lanes at a time.
//! * `scan` — small triangles (under 16 px) for shaders that opt in: each row's run found by
//!   testing its pixels' edge values, the same spans without the walk's divisions.
//! * `plane` — attributes (colour channels now) interpolated barycentrically by fixed-point
//!   stepping, with a documented error bound.
//! * `perspective` — perspective-correct barycentrics from three more planes (`q ∝ 1/w` and
//!   `bₖ·q`), recovered every few pixels of a span by one reciprocal: what textures and light
//!   levels in 3D are corrected with.
//! * `shade` — the one entry: `shade` sets a triangle up in the width it needs, walks it and
//!   hands each covered span with its attributes to a `SpanShader` (solid fill, a colour
//!   format's span loop, `fill_contiguous`, …).
//! * `band` — a band's rows of a triangle (`shade_rows`): set up over the frame's clip, the walk
//!   started at the band's first row, the same spans and values as the whole walk's there.
//! * `arith` — the integer helpers the set-up needs on cores without a long multiply, a divider
//!   or `clz` (and its rare 128-bit divisions, in a few hundred bytes of flash).

pub(crate) mod arith;
pub(crate) mod band;
pub(crate) mod compact;
pub(crate) mod coverage;
pub(crate) mod edge;
pub(crate) mod perspective;
pub(crate) mod plane;
pub(crate) mod scan;
mod shade;
#[cfg(sse2_rows)]
mod tiny;
pub(crate) mod walk;

pub use compact::{TooLarge, LIMIT as COMPACT_LIMIT};
pub use plane::{MAX_CHUNK, STEP_BITS};
#[cfg(test)]
pub(crate) use shade::Counting;
pub(crate) use shade::{shade, shade_compact, SpanShader};
pub use walk::{for_each_span, Span, Spans};
