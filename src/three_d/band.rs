//! A band's rows in clip space: two planes `y = t·w` above and below them, so that a band's draw
//! without a bin rejects the faces wholly above or below its rows from two rows of the
//! transform (`y` and `w`), before projecting or lighting their vertices.
//!
//! A point in front of the camera (`w > 0`) lands on screen at `centre − half·y/w` (sub-pixels,
//! y down). A face whose three vertices all have `y/w` above the band's top plane covers no
//! pixel of the band, clipped or not: the clipped polygon lies in the triangle (in clip space),
//! and for `w > 0` the projection of a triangle is the triangle of the projected vertices. The
//! planes sit two pixels outside the band's rows, which covers the projection's rounding (under a
//! sub-pixel) and the planes' own (`t` has 16 fractional bits: `half·2⁻¹⁶` sub-pixels, below half
//! a pixel for the largest viewports); an absolute margin in clip space covers the clip's
//! rounding of the polygon's vertices (a few raw units each).

use super::clip::W_MIN;
use super::math::Vec3;
use super::vertex::VertexStage;
use crate::raster::band::Band;

/// Sub-pixels between the band's rows and its planes.
const MARGIN: i64 = 2 << 8;

/// A bound (raw clip-space units) on how far the clip moves a polygon vertex off the triangle.
const CLIP_ERROR: i64 = 128;

/// Largest `|t|` (16 fractional bits): beyond 64 (the guard band), a face wholly past a plane
/// is wholly outside the view volume and rejected anyway, so clamping changes nothing drawn.
const MAX_T: i64 = 128 << 16;

/// The planes of one band of one draw.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BandPlanes {
    /// `y/w` (16 fractional bits) above which a point lands above the band's first row less
    /// the margin, and below which it lands below its last row plus the margin.
    top: i64,
    bottom: i64,
    /// The clip-space margins of the two tests: `CLIP_ERROR·(2¹⁶ + |t|)`.
    top_margin: i64,
    bottom_margin: i64,
}

impl BandPlanes {
    /// The planes of `band` for the vertex stage `stage`.
    pub(crate) fn new(stage: &VertexStage, band: &Band) -> Self {
        let (centre, half) = stage.vertical();
        let (centre, half) = (i64::from(centre), i64::from(half.max(1)));
        // Rows first ..= last have their centres at 256·r + 128.
        let top_y = (i64::from(band.first) << 8) + 128 - MARGIN;
        let bottom_y = (i64::from(band.last) << 8) + 128 + MARGIN;
        // (centre − y)/half with 16 fractional bits (below 2⁵⁷ before the division), rounded
        // outwards (up for the top plane, down for the bottom one): less is rejected.
        let ndc = |y: i64, up: bool| {
            let n = (centre - y) << 16;
            let (q, r) = (n.checked_div_euclid(half), n.checked_rem_euclid(half));
            let q = q.unwrap_or(0) + i64::from(up && r.unwrap_or(0) != 0);
            q.clamp(-MAX_T, MAX_T)
        };
        let (top, bottom) = (ndc(top_y, true), ndc(bottom_y, false));
        BandPlanes {
            top,
            bottom,
            top_margin: CLIP_ERROR * ((1 << 16) + top.abs()),
            bottom_margin: CLIP_ERROR * ((1 << 16) + bottom.abs()),
        }
    }

    /// Whether the face at `model` covers no pixel of the band for certain: every vertex in
    /// front of the camera (`w ≥ 2⁻⁸`) and above the top plane, or every one below the bottom
    /// plane.
    #[inline(always)]
    pub(crate) fn misses(&self, stage: &VertexStage, model: &[Vec3; 3]) -> bool {
        let (mut above, mut below) = (true, true);
        for p in model {
            let (y, w) = stage.clip_height(*p);
            if i64::from(w) < W_MIN {
                return false;
            }
            // |y| < 2³¹ and |t| ≤ 2²³, w < 2³¹: below 2⁵⁵.
            let (y, w) = (i64::from(y) << 16, i64::from(w));
            above &= y - self.top * w > self.top_margin;
            below &= self.bottom * w - y > self.bottom_margin;
        }
        above || below
    }
}
