//! A coverage mask: the exact coverage of many triangles summed per pixel, blended once.
//!
//! Anti-aliasing triangles one by one leaves a seam where two share an edge: each covers part
//! of the pixels along it, and two partial blends do not make a whole pixel. A [`CoverageMask`]
//! adds every triangle's coverage (the area of each pixel square inside it, as
//! [`AntiAliased`](crate::AntiAliased) finds it) into caller's cells first; where triangles
//! share an edge their parts of a pixel sum to the whole pixel, so a shape made of triangles
//! (a polygon, an icon, a glyph, a mesh's silhouette) is blended once with the area it covers of
//! every pixel: seam-free and anti-aliased along its whole outline, turns included.

use embedded_graphics::primitives::Rectangle;

use super::antialias::alpha_of;
use super::framebuffer::{frame_len, FramebufferError, SliceFramebuffer};
use super::triangle::SolidTriangle;
use crate::color::GouraudColor;
use crate::fixed_point::{Coord, ToCoord};
use crate::raster::coverage::{cover, CoverageSink, FULL};

/// A whole pixel in a cell: coverage in 15 fractional bits, so that a cell holds up to two whole
/// pixels (overlapping triangles) before it saturates.
const CELL_FULL: u32 = 1 << 15;

/// The summed coverage of triangles over a rectangle of pixels (the frame, or a band's rows), in
/// caller's cells: one `u16` a pixel. Add triangles ([`add`](Self::add)), then blend one colour
/// with it into a framebuffer ([`fill_into`](Self::fill_into)), which also clears it for the next
/// shape.
///
/// Coverage adds up: where triangles share an edge, the pixels along it are whole (within 2⁻⁹
/// of a pixel per triangle); where they overlap it saturates at whole. Each pixel's alpha is
/// `255 ×` its summed coverage, rounded.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Gray8, prelude::*, primitives::Rectangle};
/// use embedded_raster::{CoverageMask, SliceFramebuffer};
///
/// let mut pixels = [Gray8::BLACK; 16 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
/// let mut cells = [0u16; 16 * 16];
/// let mut mask = CoverageMask::new(&mut cells, Rectangle::new(Point::zero(), Size::new(16, 16)))?;
/// // A square of two triangles sharing its diagonal.
/// let (a, b, c, d) = ((1.25, 1.25), (14.6, 1.25), (14.6, 14.6), (1.25, 14.6));
/// mask.add([a, b, c]);
/// mask.add([a, c, d]);
/// mask.fill_into(Gray8::WHITE, &mut fb);
/// assert!((2..14).all(|i| fb.get(i, i) == Some(Gray8::WHITE))); // no seam
/// assert_eq!(fb.get(1, 5), Some(Gray8::new(191))); // 0.75 of the pixel: 191.25
/// # Ok::<(), embedded_raster::FramebufferError>(())
/// ```
#[derive(Debug)]
pub struct CoverageMask<'a> {
    cells: &'a mut [u16],
    area: Rectangle,
    /// The columns and rows `(x0, y0, x1, y1)` (inclusive) any triangle added since the last
    /// fill reached.
    touched: Option<(i32, i32, i32, i32)>,
}

impl<'a> CoverageMask<'a> {
    /// A mask over `area` (any rectangle of frame pixels: the frame's, a band's) in `cells`,
    /// `width × height` of them row by row, all 0 (clear). Errors: `cells` is shorter than the
    /// area ([`FramebufferError::MaskBuffer`]), or a side of the area does not fit an `i32`
    /// ([`FramebufferError::TooLarge`]).
    pub fn new(cells: &'a mut [u16], area: Rectangle) -> Result<Self, FramebufferError> {
        let needed = frame_len(area.size.width, area.size.height)?;
        if cells.len() < needed {
            return Err(FramebufferError::MaskBuffer {
                needed,
                given: cells.len(),
            });
        }
        Ok(CoverageMask {
            cells,
            area,
            touched: None,
        })
    }

    /// The rectangle of frame pixels the mask covers.
    pub fn area(&self) -> Rectangle {
        self.area
    }

    /// Adds the coverage of the triangle with corners `points` (either winding; floats or
    /// [`Coord`]s, any position: clipped to the mask's area).
    pub fn add<P: ToCoord>(&mut self, points: [(P, P); 3]) {
        self.add_points(points.map(|(x, y)| (x.to_coord(), y.to_coord())));
    }

    /// Adds the coverage of `triangle` (its colour is not used: the mask's colour is given to
    /// [`fill_into`](Self::fill_into)).
    pub fn add_triangle<C>(&mut self, triangle: &SolidTriangle<C>) {
        self.add_points(triangle.points);
    }

    fn add_points(&mut self, points: [(Coord, Coord); 3]) {
        let area = self.area;
        cover(points, [true; 3], &area, self);
    }

    /// Blends `color` with the summed coverage into `framebuffer` (the frame's pixels) and
    /// clears the mask for the next shape.
    pub fn fill_into<C: GouraudColor>(
        &mut self,
        color: C,
        framebuffer: &mut SliceFramebuffer<'_, C>,
    ) {
        self.resolve(color, 255, framebuffer, 0);
    }

    /// [`fill_into`](Self::fill_into) at `opacity` (0 transparent … 255 opaque): each pixel's
    /// alpha is `opacity ×` its summed coverage (at most whole), rounded, as an
    /// [`AntiAliased::with_opacity`](crate::AntiAliased::with_opacity) triangle's. The shape is
    /// blended once, so where its triangles share an edge or overlap the pixels are not
    /// blended twice (no darker seams or overlaps, as drawing each translucent triangle would
    /// leave).
    ///
    /// ```
    /// use embedded_graphics::{pixelcolor::Gray8, prelude::*, primitives::Rectangle};
    /// use embedded_raster::{CoverageMask, SliceFramebuffer};
    ///
    /// let mut pixels = [Gray8::BLACK; 16 * 16];
    /// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
    /// let mut cells = [0u16; 16 * 16];
    /// let mut mask = CoverageMask::new(&mut cells, Rectangle::new(Point::zero(), Size::new(16, 16)))?;
    /// // Two overlapping triangles, blended once at half opacity.
    /// mask.add([(2.0, 2.0), (14.0, 2.0), (2.0, 14.0)]);
    /// mask.add([(2.0, 2.0), (14.0, 2.0), (14.0, 14.0)]);
    /// mask.fill_translucent_into(Gray8::WHITE, 128, &mut fb);
    /// assert_eq!(fb.get(5, 3), Some(Gray8::new(128)));
    /// # Ok::<(), embedded_raster::FramebufferError>(())
    /// ```
    pub fn fill_translucent_into<C: GouraudColor>(
        &mut self,
        color: C,
        opacity: u8,
        framebuffer: &mut SliceFramebuffer<'_, C>,
    ) {
        self.resolve(color, opacity, framebuffer, 0);
    }

    /// [`fill_translucent_into`](Self::fill_translucent_into) a band's buffer, whose first row
    /// is frame row `top`.
    pub(crate) fn fill_rows<C: GouraudColor>(
        &mut self,
        color: C,
        opacity: u8,
        framebuffer: &mut SliceFramebuffer<'_, C>,
        top: i32,
    ) {
        self.resolve(color, opacity, framebuffer, top);
    }

    /// Blends `color` at `opacity` into `framebuffer` (whose row 0 is frame row `top`) with
    /// each cell's coverage, and clears the cells the triangles reached.
    fn resolve<C: GouraudColor>(
        &mut self,
        color: C,
        opacity: u8,
        framebuffer: &mut SliceFramebuffer<'_, C>,
        top: i32,
    ) {
        let Some((x0, y0, x1, y1)) = self.touched.take() else {
            return;
        };
        let len = x1.abs_diff(x0) as usize + 1;
        for y in y0..=y1 {
            let Some(first) = self.index(x0, y) else {
                continue;
            };
            let Some(cells) = self.cells.get_mut(first..first + len) else {
                continue;
            };
            // The framebuffer's part of the row: columns left of 0 skipped.
            if let Some(row) = framebuffer.clipped_span_mut(y - top, x0, x1 + 1) {
                let skip = x0.min(0).unsigned_abs() as usize;
                blend_cells(cells.get(skip..).unwrap_or(&[]), row, color, opacity);
            }
            cells.fill(0);
        }
    }

    /// The index of frame pixel `(x, y)`'s cell, if it is in the area.
    fn index(&self, x: i32, y: i32) -> Option<usize> {
        let dx = u32::try_from(i64::from(x) - i64::from(self.area.top_left.x)).ok()?;
        let dy = u32::try_from(i64::from(y) - i64::from(self.area.top_left.y)).ok()?;
        if dx >= self.area.size.width || dy >= self.area.size.height {
            return None;
        }
        Some(dy as usize * self.area.size.width as usize + dx as usize)
    }

    /// Adds `coverage` (16 fractional bits) to the cells of pixels `x .. x + len` of row `y`.
    fn accumulate(&mut self, x: i32, y: i32, len: u32, coverage: u32) {
        let Some(i) = self.index(x, y) else {
            return;
        };
        let add = ((coverage + 1) >> 1).min(CELL_FULL) as u16;
        if let Some(cells) = self.cells.get_mut(i..i + len as usize) {
            for cell in cells {
                *cell = cell.saturating_add(add);
            }
        }
        let last = x + (len as i32 - 1);
        self.touched = Some(match self.touched {
            None => (x, y, last, y),
            Some((x0, y0, x1, y1)) => (x0.min(x), y0.min(y), x1.max(last), y1.max(y)),
        });
    }
}

impl CoverageSink for CoverageMask<'_> {
    fn full(&mut self, y: i32, x0: i32, x1: i32) {
        self.accumulate(x0, y, x1.abs_diff(x0), FULL);
    }

    fn partial(&mut self, x: i32, y: i32, coverage: u32) {
        self.accumulate(x, y, 1, coverage);
    }
}

/// Blends `color` at `opacity` over `row` with the coverage in `cells` (one a pixel, 15
/// fractional bits), each pixel's alpha by [`alpha_of`]: at 255 the colour itself, at 0
/// untouched.
fn blend_cells<C: GouraudColor>(cells: &[u16], row: &mut [C], color: C, opacity: u8) {
    for (&cell, px) in cells.iter().zip(row.iter_mut()) {
        // A cell's 15 fractional bits as the 16 of a coverage.
        match alpha_of(u32::from(cell) << 1, opacity) {
            0 => {}
            255 => *px = color,
            alpha => *px = color.blend(*px, alpha),
        }
    }
}
