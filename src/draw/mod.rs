//! Drawing into embedded-graphics targets: the triangle primitives and a slice framebuffer.
//!
//! [`GouraudTriangle`] and [`SolidTriangle`] implement `Drawable` for any `DrawTarget` (one
//! `fill_contiguous` or `fill_solid` a span) and draw into a [`SliceFramebuffer`] directly with
//! `draw_into` (slice writes and the colour format's packed span loop). A `SliceFramebuffer` is
//! an `ImageDrawable` (blit it to any `DrawTarget` with `Image`) and, with the `png` feature,
//! saves itself as a PNG file.

/// A 2D fill's span shader scans small triangles where a division is an instruction, with the
/// compact walk's planes ([`SpanShader::walk_planes`](crate::raster::SpanShader)): the same
/// spans and values as `draw`'s and the bands' walks of them.
macro_rules! scan_small_with_walk_planes {
    () => {
        #[inline(always)]
        fn scans_small(&self) -> bool {
            crate::arch::MCU && crate::arch::HAS_DIVIDER
        }

        #[inline(always)]
        fn walk_planes(&self) -> bool {
            true
        }
    };
}

mod antialias;
mod dithered;
mod framebuffer;
mod image;
mod line;
mod mask;
mod painted;
mod painted_triangle;
pub(crate) use painted::draw_rows as draw_shape_rows;
#[cfg(feature = "png")]
mod png_file;
mod polygon;
mod stroke;
mod textured;
mod translucent;
mod triangle;

pub use crate::color::fill_row;
pub use antialias::AntiAliased;
pub use dithered::DitheredTriangle;
pub(crate) use framebuffer::skip_colors;
pub use framebuffer::{FramebufferError, SliceFramebuffer};
pub(crate) use image::draw_rows;
pub use line::{Line, Polyline};
pub use mask::CoverageMask;
pub use painted_triangle::PaintedTriangle;
#[cfg(feature = "png")]
pub(crate) use png_file::write_png;
pub use polygon::{FilledPolygon, Polygon, PolygonFull};
pub use stroke::{Cap, Join, Stroke, Stroked};
pub use textured::{TexturedTriangle, TexturedVertex};
pub use translucent::{OnBackground, Translucent};
pub use triangle::{GouraudTriangle, ShadedSpans, SolidTriangle, SpanColors, Vertex};
