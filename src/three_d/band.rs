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
use crate::raster::arith::mul_i32_wide;
use crate::raster::walk::Band;

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
    top: i32,
    bottom: i32,
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
            q.clamp(-MAX_T, MAX_T) as i32
        };
        let (top, bottom) = (ndc(top_y, true), ndc(bottom_y, false));
        let margin = |t: i32| CLIP_ERROR * ((1 << 16) + i64::from(t.unsigned_abs()));
        BandPlanes {
            top,
            bottom,
            top_margin: margin(top),
            bottom_margin: margin(bottom),
        }
    }

    /// Which side of the band the point `p` lands on for certain: [`ABOVE`] the top plane,
    /// [`BELOW`] the bottom one (both in front of the camera, `w ≥ 2⁻⁸`), or neither. Out of
    /// line: called on a [`SideCache`] miss only, it keeps the transform's set-up out of the
    /// face loop.
    #[inline(never)]
    fn side(&self, stage: &VertexStage, p: Vec3) -> u8 {
        let (y, w) = stage.clip_height(p);
        if i64::from(w) < W_MIN {
            return NEITHER;
        }
        // |y| < 2³¹, so y·2¹⁶ < 2⁴⁷; |t| ≤ 2²³ and w < 2³¹: one 32 × 32-bit product each.
        let y = i64::from(y) << 16;
        if y - mul_i32_wide(self.top, w) > self.top_margin {
            ABOVE
        } else if mul_i32_wide(self.bottom, w) - y > self.bottom_margin {
            BELOW
        } else {
            NEITHER
        }
    }
}

/// Sides of the band (see [`BandPlanes::side`]).
const NEITHER: u8 = 0;
const ABOVE: u8 = 1;
const BELOW: u8 = 2;

/// Entries of a [`SideCache`].
const CACHE: usize = 256;

/// The sides of the vertices a band's draw met last: each vertex is shared by several faces,
/// mostly close in the mesh's order, so a small direct-mapped cache (512 bytes of stack, whatever
/// the mesh) spares most of their transforms.
pub(crate) struct SideCache {
    /// `index / CACHE + 1` (0: empty) in the high bits, the side in the low two, by
    /// `index % CACHE`.
    entries: [u16; CACHE],
}

impl SideCache {
    /// An empty cache.
    pub(crate) fn new() -> Self {
        SideCache {
            entries: [0; CACHE],
        }
    }

    /// Whether the face of the vertices `idx` at `model` covers no pixel of the band of
    /// `planes` for certain: all three vertices above it or all below.
    #[inline(always)]
    pub(crate) fn misses(
        &mut self,
        planes: &BandPlanes,
        stage: &VertexStage,
        idx: &[usize; 3],
        model: &[Vec3; 3],
    ) -> bool {
        let mut all = ABOVE | BELOW;
        for (&i, &p) in idx.iter().zip(model) {
            // Vertex indices come from `u16`s: the tag fits.
            let tag = ((i / CACHE + 1) as u16) << 2;
            let side = match self.entries.get_mut(i % CACHE) {
                Some(e) if *e & !3 == tag => *e as u8 & 3,
                Some(e) => {
                    let side = planes.side(stage, p);
                    *e = tag | u16::from(side);
                    side
                }
                None => planes.side(stage, p),
            };
            all &= side;
            if all == NEITHER {
                return false;
            }
        }
        true
    }
}
