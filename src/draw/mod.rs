//! Drawing into embedded-graphics targets: the triangle primitives and a slice framebuffer.
//!
//! [`GouraudTriangle`] and [`SolidTriangle`] implement `Drawable` for any `DrawTarget` (one
//! `fill_contiguous` or `fill_solid` a span) and draw into a [`SliceFramebuffer`] directly with
//! `draw_into` (slice writes and the colour format's packed span loop).

mod framebuffer;
mod triangle;

pub(crate) use framebuffer::skip_colors;
pub use framebuffer::{fill_row, SliceFramebuffer};
pub use triangle::{GouraudTriangle, ShadedSpans, SolidTriangle, SpanColors, Vertex};
