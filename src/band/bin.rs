//! Bins: each triangle of a frame recorded once, with the bands it touches, in the caller's
//! storage; each band then draws only its own triangles, in the frame's order.
//!
//! The storage is a slice of [`BinEntry`] (12 bytes): one per band (the head of the list of
//! the triangles whose first band it is) and one per triangle kept (what a band needs to draw
//! it — a mesh face's three vertex indices, so that a band reads its vertices without the
//! mesh's indices; a 2D triangle's number and first band —, its last band, the link to the next
//! of its list). The triangles are recorded in the frame's order, so a list's order is theirs.
//! Drawing the bands top to bottom, the triangles of a band are those still open from the
//! bands above (a list kept in order) merged with those starting there: each band costs the
//! triangles it touches. Drawn in any other order, a band reads every entry and draws those
//! reaching it or a lower band (the same pixels, more work).
//!
//! A [`MeshBin`] uses the storage past the entries it needs, if any: a small Gouraud face
//! reaching the next band leaves its set-up there (5 entries: its region, its rows' run bounds
//! and planes, the integers the set-up computes), and the next band draws its rows from it
//! where it lies instead of setting the face up again — the same pixels, a set-up less for
//! each face crossing a band boundary. The set-ups are kept in a ring in the order the faces
//! are drawn; when it is full (or the storage has no spare entry) a face is set up again.

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::target::{BandDrawable, ColorBand, DepthBand};
use super::{BandError, BandLayout};
use crate::color::GouraudColor;
use crate::raster::band::{AllRows, RowWindow};
use crate::raster::edge::{first_centre_from, last_centre_to};
use crate::raster::scan::{KeptWords, KEPT_WORDS};
use crate::texture::TexelSource;
use crate::three_d::{
    fit_scratch, DrawStats, FaceSink, FaceTexture, Frame, FrameTexture, Material, Mesh, NoTexture,
    Opacity, Pipeline, ProjectedVertex, TargetClip, TexturedMaterial,
};
use crate::Vec3;

/// One entry of a bin's storage, 12 bytes: a band's list head or a triangle kept. A bin needs
/// one per band plus one per triangle kept (for a mesh: the faces inside the view volume, not
/// culled, of non-zero area; for a 2D list: the triangles that reach the frame's rows); the
/// bin reports how many it needs when its storage is too short.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct BinEntry {
    /// What the bin records of the triangle (a mesh face's first two vertex indices, a 2D
    /// triangle's number); for a band's head, the last entry of its list (the head itself
    /// while the list is empty).
    item: u32,
    /// The next entry of the list.
    next: u32,
    /// 16 more bits of the record (a mesh face's third vertex index, a 2D triangle's first
    /// band), the triangle's last band (15 bits) and a flag (a mesh face to clip again).
    bands: u32,
}

impl BinEntry {
    /// An entry for a storage array: `[BinEntry::EMPTY; N]`.
    pub const EMPTY: BinEntry = BinEntry {
        item: NONE,
        next: NONE,
        bands: 0,
    };

    /// The triangle's last band.
    #[inline(always)]
    fn last(&self) -> u32 {
        self.bands >> 16 & MAX_BAND
    }

    /// The triangle as recorded, in entry `slot`.
    #[inline(always)]
    fn record(&self, slot: u32) -> Record {
        Record {
            item: self.item,
            low: self.bands & 0xFFFF,
            flag: self.bands >> 31 != 0,
            slot,
        }
    }
}

/// The largest band number (and one less than the most bands a bin takes).
const MAX_BAND: u32 = (1 << 15) - 1;

/// A triangle as a bin recorded it ([`Lists::push`]), and the entry it is in (unique to it).
#[derive(Clone, Copy)]
struct Record {
    item: u32,
    low: u32,
    flag: bool,
    slot: u32,
}

impl Record {
    /// A mesh face's vertex indices ([`Recorder::record`]).
    #[inline(always)]
    fn face(&self) -> [usize; 3] {
        [self.item & 0xFFFF, self.item >> 16, self.low].map(|i| i as usize)
    }
}

impl Default for BinEntry {
    fn default() -> Self {
        BinEntry::EMPTY
    }
}

/// No entry.
const NONE: u32 = u32::MAX;

/// Triangles a bin numbers at most: `bands + records` fits `u32`.
const MAX_RECORDS: u32 = 1 << 31;

/// The bands' lists in a caller's storage.
#[derive(Debug)]
struct Lists<'b> {
    entries: &'b mut [BinEntry],
    /// Bands (the first entries), and triangles recorded (or counted past the storage's end).
    bands: u32,
    records: u32,
    /// A triangle numbered past [`MAX_RECORDS`] (so far fewer are recorded: `bands + records`
    /// fits `u32`).
    limit: bool,
    /// The list of triangles still open after the band drawn last, and the band expected next.
    active: u32,
    next_band: u32,
    /// The ring of kept set-ups in the storage past the lists: its first and its length.
    kept_start: u32,
    kept_len: u32,
}

impl<'b> Lists<'b> {
    /// Empty lists for the bands of `layout` in `entries`.
    fn new(layout: &BandLayout, entries: &'b mut [BinEntry]) -> Result<Self, BandError> {
        let bands = layout.count();
        if bands > MAX_BAND + 1 {
            return Err(BandError::BinLimit);
        }
        for (band, head) in entries.iter_mut().take(bands as usize).enumerate() {
            *head = BinEntry {
                // Below 2¹⁶ + 1.
                item: band as u32,
                ..BinEntry::EMPTY
            };
        }
        Ok(Lists {
            entries,
            bands,
            records: 0,
            limit: false,
            active: NONE,
            next_band: 0,
            kept_start: 0,
            kept_len: 0,
        })
    }

    /// Records a triangle as `item`, `low` and `flag` (the [`Record`] the walk gives back), in
    /// bands `first ..= last` (below the number of bands); fewer than [`MAX_RECORDS`] times.
    #[inline(always)]
    fn push(&mut self, (item, low, flag): (u32, u16, bool), first: u32, last: u32) {
        // The slots follow the bands' heads: below 2¹⁵ + 2³¹, no overflow.
        let slot = self.bands + self.records;
        self.records += 1;
        let Some(e) = self.entries.get_mut(slot as usize) else {
            // Counted, not stored: `finish` reports the storage too small.
            return;
        };
        // The last band is below 2¹⁵.
        *e = BinEntry {
            item,
            next: NONE,
            bands: u32::from(low) | last << 16 | u32::from(flag) << 31,
        };
        // Appended to its first band's list: linked from the tail the head keeps in `item` (the
        // head itself for an empty list).
        let Some(head) = self.entries.get_mut(first as usize) else {
            return;
        };
        let tail = core::mem::replace(&mut head.item, slot);
        if let Some(t) = self.entries.get_mut(tail as usize) {
            t.next = slot;
        }
    }

    /// Whether everything fitted.
    fn finish(&self) -> Result<(), BandError> {
        if self.limit {
            return Err(BandError::BinLimit);
        }
        let needed = self.bands as usize + self.records as usize;
        if needed > self.entries.len() {
            return Err(BandError::BinTooSmall {
                needed,
                given: self.entries.len(),
            });
        }
        Ok(())
    }

    /// Triangles recorded.
    fn len(&self) -> usize {
        self.records as usize
    }

    /// Calls `f` with every triangle touching `band` (drawn top to bottom; in any other order,
    /// every triangle reaching it or a lower band), in the order they were recorded, whether it
    /// comes from the band above and whether it reaches the next band (both only when the
    /// bands are drawn top to bottom), and the set-ups kept for the triangles reaching this band
    /// from above (in their order).
    fn each(&mut self, band: u32, mut f: impl FnMut(Record, bool, bool, &mut KeptRing<'_>)) {
        if band >= self.bands {
            return;
        }
        let end = (self.bands as usize + self.records as usize).min(self.entries.len());
        let (entries, spare) = self.entries.split_at_mut(end);
        if band != self.next_band {
            // Out of order: every entry, read; nothing kept. (The entries keep no first band.)
            let mut none = KeptRing::new(&mut [], &mut self.kept_start, &mut self.kept_len);
            none.clear();
            let records = entries.iter().zip(0..).skip(self.bands as usize);
            for (e, slot) in records.take(self.records as usize) {
                if band <= e.last() {
                    f(e.record(slot), false, false, &mut none);
                }
            }
            return;
        }
        let mut kept = KeptRing::new(spare, &mut self.kept_start, &mut self.kept_len);
        if band == 0 {
            kept.clear();
        }
        // The open triangles merged with those starting here, by slot (their order); those
        // reaching further down stay open.
        let (mut open, mut starting) = (
            self.active,
            entries.get(band as usize).map_or(NONE, |h| h.next),
        );
        let (mut head, mut tail) = (NONE, NONE);
        loop {
            let slot = open.min(starting);
            let Some(e) = entries.get(slot as usize).copied() else {
                break;
            };
            let above = slot == open;
            if above {
                open = e.next;
            } else {
                starting = e.next;
            }
            let continues = e.last() > band;
            f(e.record(slot), above, continues, &mut kept);
            if continues {
                match entries.get_mut(tail as usize) {
                    Some(t) => t.next = slot,
                    None => head = slot,
                }
                tail = slot;
            }
        }
        if let Some(t) = entries.get_mut(tail as usize) {
            t.next = NONE;
        }
        self.active = head;
        self.next_band = band + 1;
    }
}

/// Entries a kept set-up takes in the storage past the lists: its words, three an entry, and
/// the entry of its triangle (its slot, unique to it) in the last word.
const KEPT_ENTRIES: usize = 5;
const _: () = assert!(KEPT_WORDS == 3 * KEPT_ENTRIES - 1);

/// One set-up's entries in the ring: its words in place.
type Slot = [BinEntry; KEPT_ENTRIES];

impl KeptWords for Slot {
    #[inline(always)]
    fn word(&self, i: usize) -> u32 {
        self.get(i / 3).map_or(0, |e| match i % 3 {
            0 => e.item,
            1 => e.next,
            _ => e.bands,
        })
    }

    #[inline(always)]
    fn set_word(&mut self, i: usize, w: u32) {
        if let Some(e) = self.get_mut(i / 3) {
            match i % 3 {
                0 => e.item = w,
                1 => e.next = w,
                _ => e.bands = w,
            }
        }
    }
}

/// The set-ups of the triangles reaching the next band, kept in the storage past the lists: a
/// ring of [`KEPT_ENTRIES`] entries each, in the order the triangles are drawn (the order of the
/// next band's open list), so the next band takes them from the front as it meets them. The
/// raster core writes and reads a set-up where it lies in the ring ([`KeptWords`]).
pub(crate) struct KeptRing<'e> {
    spare: &'e mut [BinEntry],
    start: &'e mut u32,
    len: &'e mut u32,
}

impl<'e> KeptRing<'e> {
    fn new(spare: &'e mut [BinEntry], start: &'e mut u32, len: &'e mut u32) -> Self {
        KeptRing { spare, start, len }
    }

    /// Set-ups the ring holds at most.
    #[inline(always)]
    fn capacity(&self) -> u32 {
        // Fewer entries than 2³² · 5.
        (self.spare.len() / KEPT_ENTRIES) as u32
    }

    /// Empties it.
    fn clear(&mut self) {
        (*self.start, *self.len) = (0, 0);
    }

    /// The entries of set-up `n` of the ring's storage.
    #[inline(always)]
    pub(crate) fn at(&self, n: u32) -> Option<&Slot> {
        let from = n as usize * KEPT_ENTRIES;
        self.spare
            .get(from..from + KEPT_ENTRIES)
            .and_then(|e| e.try_into().ok())
    }

    /// [`at`](Self::at), to write.
    #[inline(always)]
    fn at_mut(&mut self, n: u32) -> Option<&mut Slot> {
        let from = n as usize * KEPT_ENTRIES;
        self.spare
            .get_mut(from..from + KEPT_ENTRIES)
            .and_then(|e| e.try_into().ok())
    }

    /// The position after the last set-up (below the capacity), if the ring is not full.
    #[inline(always)]
    fn end(&self) -> Option<u32> {
        let capacity = self.capacity();
        if *self.len >= capacity {
            return None;
        }
        // Both below the capacity: the sum fits.
        let end = *self.start + *self.len;
        Some(if end >= capacity { end - capacity } else { end })
    }

    /// The position of the set-up of the triangle in entry `slot` if it is the front one (taken
    /// off the ring: valid until the next [`vacant`](Self::vacant)).
    #[inline(always)]
    pub(crate) fn take(&mut self, slot: u32) -> Option<u32> {
        if *self.len == 0 {
            return None;
        }
        let start = *self.start;
        if self.at(start)?.last()?.bands != slot {
            return None;
        }
        let next = start + 1;
        *self.start = if next == self.capacity() { 0 } else { next };
        *self.len -= 1;
        Some(start)
    }

    /// Appends the set-up at position `n` (just taken) again, for the band after the next.
    #[inline(always)]
    pub(crate) fn requeue(&mut self, n: u32) {
        let Some(end) = self.end() else {
            return;
        };
        if end != n {
            let Some(&slot) = self.at(n) else {
                return;
            };
            let Some(to) = self.at_mut(end) else {
                return;
            };
            *to = slot;
        }
        *self.len += 1;
    }

    /// The storage of the next set-up, if the ring is not full: the raster core writes it, and
    /// [`commit`](Self::commit) appends it.
    #[inline(always)]
    pub(crate) fn vacant(&mut self) -> Option<&mut Slot> {
        let end = self.end()?;
        self.at_mut(end)
    }

    /// Appends the set-up written into [`vacant`](Self::vacant) as that of the triangle in entry
    /// `slot`.
    #[inline(always)]
    pub(crate) fn commit(&mut self, slot: u32) {
        let Some(end) = self.end() else {
            return;
        };
        let Some(last) = self.at_mut(end).and_then(|s| s.last_mut()) else {
            return;
        };
        last.bands = slot;
        *self.len += 1;
    }
}

/// The frame rows a bin's triangles are drawn in (its clip's), and the rows of a band.
#[derive(Debug, Clone, Copy)]
struct Rows {
    first: i32,
    last: i32,
    band: u32,
}

impl Rows {
    /// The rows of `clip` (inside the frame of `layout`; `None` if empty).
    fn new(layout: &BandLayout, clip: &Rectangle) -> Option<Rows> {
        let first = clip.top_left.y;
        // Inside the frame: below 2³¹.
        let last = first.checked_add(clip.size.height as i32)?.checked_sub(1)?;
        (!clip.is_zero_sized() && first >= 0).then_some(Rows {
            first,
            last,
            band: layout.rows(),
        })
    }

    /// The first and last band of rows `top ..= bottom`, if they meet these rows.
    #[inline(always)]
    fn bands(&self, top: i32, bottom: i32) -> Option<(u32, u32)> {
        let (top, bottom) = (top.max(self.first), bottom.min(self.last));
        // Both in `first ..= last`, non-negative.
        (top <= bottom).then(|| (top as u32 / self.band, bottom as u32 / self.band))
    }
}

/// A 2D list's triangles sorted into the bands of a frame once, drawn band by band.
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Gray8, prelude::*};
/// use embedded_raster::band::{BandError, BandLayout, BinEntry, ColorBand, TriangleBin};
/// use embedded_raster::{Coord, SolidTriangle};
///
/// let c = |x: i32, y: i32| (Coord::from_num(x), Coord::from_num(y));
/// let scene = [
///     SolidTriangle::new([c(0, 0), c(30, 2), c(4, 9)], Gray8::WHITE),
///     SolidTriangle::new([c(0, 20), c(30, 22), c(4, 31)], Gray8::new(128)),
/// ];
/// let layout = BandLayout::new(Size::new(32, 32), 8)?;
/// // Four bands and two triangles.
/// let mut too_small = [BinEntry::EMPTY; 5];
/// let error = TriangleBin::new(&layout, &scene, &mut too_small).unwrap_err();
/// assert_eq!(error, BandError::BinTooSmall { needed: 6, given: 5 });
///
/// let mut storage = [BinEntry::EMPTY; 6];
/// let mut bin = TriangleBin::new(&layout, &scene, &mut storage)?;
/// let mut rows = [Gray8::BLACK; 32 * 8];
/// for index in 0..layout.count() {
///     let mut band = ColorBand::new(&mut rows, &layout, index)?;
///     band.clear(Gray8::BLACK);
///     bin.draw(&mut band)?;
/// }
/// # Ok::<(), BandError>(())
/// ```
#[derive(Debug)]
pub struct TriangleBin<'b, 't, T> {
    lists: Lists<'b>,
    items: &'t [T],
    layout: BandLayout,
}

impl<'b, 't, T> TriangleBin<'b, 't, T> {
    /// The triangles of `items` that reach the rows of `layout`'s frame, recorded in `storage`
    /// (one entry per band and per such triangle). `Err(BinTooSmall)` (with the number
    /// needed) if it is too short.
    pub fn new<C: PixelColor>(
        layout: &BandLayout,
        items: &'t [T],
        storage: &'b mut [BinEntry],
    ) -> Result<Self, BandError>
    where
        T: BandDrawable<C>,
    {
        let mut lists = Lists::new(layout, storage)?;
        let frame = Rectangle::new(Point::zero(), layout.size());
        let rows = Rows::new(layout, &frame);
        for (k, item) in items.iter().enumerate() {
            let Some((top, bottom)) = item.rows() else {
                continue;
            };
            let Some((first, last)) = rows.and_then(|r| r.bands(top, bottom)) else {
                continue;
            };
            // The first band in the record's low half: the out-of-order walk skips the
            // triangles below the band.
            match u32::try_from(k) {
                Ok(k) if k < MAX_RECORDS => lists.push((k, first as u16, false), first, last),
                _ => return Err(BandError::BinLimit),
            }
        }
        lists.finish()?;
        Ok(TriangleBin {
            lists,
            items,
            layout: *layout,
        })
    }

    /// Triangles recorded.
    pub fn len(&self) -> usize {
        self.lists.len()
    }

    /// Whether no triangle reaches the frame.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Draws `band`'s triangles into it, in the list's order: the pixels of
    /// [`ColorBand::draw_all`] with the whole list. Fastest when the bands are drawn top to
    /// bottom once; `Err(OtherLayout)` (nothing drawn) for a band of another layout.
    pub fn draw<C: PixelColor>(&mut self, band: &mut ColorBand<'_, C>) -> Result<(), BandError>
    where
        T: BandDrawable<C>,
    {
        if band.layout() != &self.layout {
            return Err(BandError::OtherLayout);
        }
        let items = self.items;
        let index = band.index();
        self.lists.each(index, |r, _, _, _| {
            if r.low > index {
                return;
            }
            if let Some(item) = items.get(r.item as usize) {
                item.draw_band(band);
            }
        });
        Ok(())
    }
}

/// A mesh transformed, culled and sorted into the bands of a frame once, drawn band by band.
///
/// [`new`](Self::new) runs the vertex stage into the caller's scratch (16 bytes a vertex, as
/// [`Pipeline::draw_mesh_with`]) and the face stage (rejection, culling by area, clipping
/// decisions) once, recording each face it keeps with the bands it touches; each band then fills
/// only its faces. The pixels and depths are those of `draw_mesh_with` on the whole frame, and
/// [`stats`](Self::stats) its counts.
///
/// A textured mesh takes [`new_textured`](MeshBin::new_textured) (a [`TexturedMaterial`], any
/// sampler, shading, vertex colours or highlight, and the pipeline's [`Lights`](crate::three_d::Lights)):
/// the pixels and depths of [`Pipeline::draw_textured_mesh_with`], `T` being then the
/// [`FrameTexture`] of the material's texels. Its faces crossing a band boundary are set up
/// again in each band (the spare storage keeps set-ups of untextured Gouraud faces only).
///
/// # Examples
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
/// use embedded_raster::band::{BandLayout, BinEntry, ColorBands, DepthBands, MeshBin, ToDisplay};
/// use embedded_raster::three_d::meshes::icosphere::ICOSPHERE;
/// use embedded_raster::three_d::{Angle, Light, Mat4, Material, Pipeline, ProjectedVertex, Scalar, Shading, Vec3};
/// use embedded_raster::SliceFramebuffer;
///
/// let layout = BandLayout::new(Size::new(64, 48), 8)?;
/// let projection = Mat4::perspective(Angle::from_degrees(60), Scalar::from_num(4) / 3,
///     Scalar::from_num(0.5), Scalar::from_num(20)).unwrap();
/// let view = Mat4::translation(Vec3::from_bits(0, 0, -3 << 16));
/// let viewport = Rectangle::new(Point::zero(), layout.size());
/// let pipeline = Pipeline::new(Mat4::IDENTITY, projection * view, viewport, Light::default());
/// let material = Material::new(Rgb565::CYAN, Shading::Gouraud);
///
/// let mut scratch = [ProjectedVertex::EMPTY; 42];
/// let mut storage = [BinEntry::EMPTY; 6 + 80];
/// let mut bin = MeshBin::new(&pipeline, &ICOSPHERE, &material, &layout, &mut scratch, &mut storage)?;
/// assert_eq!(bin.stats().drawn + bin.stats().culled, 80);
///
/// let mut screen = [Rgb565::BLACK; 64 * 48];
/// let mut display = SliceFramebuffer::new(&mut screen, 64, 48).unwrap();
/// let (mut colors, mut depth) = ([Rgb565::BLACK; 64 * 8], [0u16; 64 * 8]);
/// let mut bands = DepthBands::new(ColorBands::new(layout, &mut colors)?, &mut depth)?;
/// bands
///     .render(&mut ToDisplay(&mut display), |band| {
///         band.clear(Rgb565::BLACK);
///         bin.draw(band).unwrap(); // the band is of the bin's layout
///     })
///     .unwrap();
/// assert_ne!(display.get(32, 24), Some(Rgb565::BLACK));
/// # Ok::<(), embedded_raster::band::BandError>(())
/// ```
pub struct MeshBin<'a, C, T = NoTexture> {
    lists: Lists<'a>,
    pipeline: &'a Pipeline,
    frame: Frame<'a, C, AllRows, T>,
    mesh: Mesh<'a>,
    scratch: &'a [ProjectedVertex],
    layout: BandLayout,
    stats: DrawStats,
}

impl<C, T> core::fmt::Debug for MeshBin<'_, C, T> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("MeshBin")
            .field("layout", &self.layout)
            .field("faces", &self.lists.len())
            .field("stats", &self.stats)
            .finish_non_exhaustive()
    }
}

impl<'a, C: GouraudColor> MeshBin<'a, C> {
    /// Runs the vertex and face stages of `mesh` with `material` through `pipeline` for the frame
    /// of `layout`, its vertices into `scratch` (one [`ProjectedVertex`] per mesh vertex), its
    /// faces into `storage` (one entry per band and per face kept; entries beyond those keep the
    /// set-ups of faces crossing into the next band, 5 each, saving their set-up there). Errors,
    /// before anything is drawn: the scratch too short, the storage too short (`BinTooSmall`
    /// with the number needed), more than 2³¹ faces.
    // Out of line: the frame's work once, and the same code whatever the caller.
    #[inline(never)]
    pub fn new(
        pipeline: &'a Pipeline,
        mesh: &Mesh<'a>,
        material: &Material<C>,
        layout: &BandLayout,
        scratch: &'a mut [ProjectedVertex],
        storage: &'a mut [BinEntry],
    ) -> Result<Self, BandError> {
        build(pipeline, mesh, layout, scratch, storage, |clip| {
            Frame::new(pipeline, mesh, material, clip)
        })
    }

    /// Fills `band`'s faces into it, in the mesh's order: the pixels and depths the whole frame
    /// has there. Fastest when the bands are drawn top to bottom once; `Err(OtherLayout)`
    /// (nothing drawn) for a band of another layout.
    pub fn draw(&mut self, band: &mut DepthBand<'_, C>) -> Result<(), BandError> {
        if band.layout() != &self.layout {
            return Err(BandError::OtherLayout);
        }
        let frame = self.frame.with_clip(band.clip(self.pipeline));
        if frame.levels().is_none() {
            // Nothing kept set up.
            return set_up_each(self, band);
        }
        let (target, placement) = band.parts();
        let (mesh, scratch) = (&self.mesh, self.scratch);
        let Some(table) = frame.levels() else {
            return Ok(());
        };
        // The refill inlined in the list's walk: a call per face otherwise.
        let lists = &mut self.lists;
        target.blending(frame.blend(), |target| {
            lists.each(
                placement.index,
                #[inline(always)]
                |r, above, continues, kept| {
                    let (idx, clipped) = (r.face(), r.flag);
                    if let Some(n) = above.then(|| kept.take(r.slot)).flatten() {
                        // Set up in a band above: its rows here from the same integers.
                        if let Some(set_up) = kept.at(n) {
                            frame.resume_levels(table, target, set_up);
                            if continues {
                                kept.requeue(n);
                            }
                            return;
                        }
                    }
                    if continues {
                        if let Some(slot) = kept.vacant() {
                            if frame.refill_levels_keeping(
                                table, mesh, scratch, &idx, clipped, target, slot,
                            ) {
                                kept.commit(r.slot);
                            }
                            return;
                        }
                    }
                    frame.refill_levels(table, mesh, scratch, &idx, clipped, target);
                },
            )
        });
        Ok(())
    }
}

impl<C, T> MeshBin<'_, C, T> {
    /// The frame's counts, as [`Pipeline::draw_mesh_with`] (or
    /// [`Pipeline::draw_textured_mesh_with`]) gives them.
    pub fn stats(&self) -> DrawStats {
        self.stats
    }

    /// Faces recorded.
    pub fn len(&self) -> usize {
        self.lists.len()
    }

    /// Whether no face is drawn.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl<'a, C, S, W> MeshBin<'a, C, FrameTexture<'a, S, W>>
where
    S: TexelSource,
    C: GouraudColor + From<S::Color>,
    W: Opacity,
{
    /// [`new`](MeshBin::new) for a textured material: the vertex and face stages of `mesh`
    /// with `material` through `pipeline` for the frame of `layout`, as
    /// [`Pipeline::draw_textured_mesh_with`] runs them (its vertices into `scratch`, one
    /// [`ProjectedVertex`] per mesh vertex), its faces into `storage` (one entry per band and
    /// per face kept; a textured face crossing into the next band is set up again there, so
    /// entries beyond those are not used). The same errors as `new`, before anything is drawn.
    ///
    /// # Examples
    ///
    /// ```
    /// use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
    /// use embedded_raster::band::{BandError, BandLayout, BinEntry, ColorBands, DepthBands, MeshBin, ToDisplay};
    /// use embedded_raster::texture::{Rgb565Texels, Texture};
    /// use embedded_raster::three_d::{Angle, Light, Mat4, Mesh, Pipeline, ProjectedVertex, Shading};
    /// use embedded_raster::three_d::{TexCoord, TexturedMaterial, Vec3};
    ///
    /// // A square of two triangles, a 2 × 2 texture over it, seen at an angle.
    /// let v = |x: f32, y: f32| Vec3::new(x, y, 0.0);
    /// let positions = [v(-1.0, -1.0), v(1.0, -1.0), v(1.0, 1.0), v(-1.0, 1.0)];
    /// let uvs = [TexCoord::new(0.0, 0.0), TexCoord::new(1.0, 0.0), TexCoord::new(1.0, 1.0),
    ///     TexCoord::new(0.0, 1.0)];
    /// let indices = [[0, 1, 2], [0, 2, 3]];
    /// let mesh = Mesh::new(&positions, &[], &indices).with_uvs(&uvs);
    /// static TEXELS: [u16; 4] = [0xf800, 0x07e0, 0x001f, 0xffff];
    /// let texture = Texture::new(Rgb565Texels(&TEXELS), 2, 2).unwrap();
    /// let material = TexturedMaterial::new(&texture, Shading::Gouraud);
    ///
    /// let layout = BandLayout::new(Size::new(64, 48), 8)?;
    /// let camera = Mat4::perspective(Angle::from_degrees(60), 4.0 / 3.0, 0.5, 10).unwrap()
    ///     * Mat4::look_at(Vec3::new(0, -1, 3), Vec3::ZERO, Vec3::new(0, 1, 0)).unwrap();
    /// let viewport = Rectangle::new(Point::zero(), layout.size());
    /// let pipeline = Pipeline::new(Mat4::IDENTITY, camera, viewport, Light::default());
    ///
    /// // Six bands and two faces. (The target's colour type is the bands' the bin draws
    /// // into, named here as it draws none.)
    /// let mut scratch = [ProjectedVertex::EMPTY; 4];
    /// let mut too_small = [BinEntry::EMPTY; 7];
    /// let error = MeshBin::<Rgb565, _>::new_textured(&pipeline, &mesh, &material, &layout,
    ///     &mut scratch, &mut too_small).unwrap_err();
    /// assert_eq!(error, BandError::BinTooSmall { needed: 8, given: 7 });
    ///
    /// let mut storage = [BinEntry::EMPTY; 6 + 2];
    /// let mut bin = MeshBin::new_textured(&pipeline, &mesh, &material, &layout, &mut scratch,
    ///     &mut storage)?;
    /// assert_eq!(bin.stats().drawn, 2);
    ///
    /// let mut screen = [Rgb565::BLACK; 64 * 48];
    /// let mut display = embedded_raster::SliceFramebuffer::new(&mut screen, 64, 48).unwrap();
    /// let (mut colors, mut depth) = ([Rgb565::BLACK; 64 * 8], [0u16; 64 * 8]);
    /// let mut bands = DepthBands::new(ColorBands::new(layout, &mut colors)?, &mut depth)?;
    /// bands
    ///     .render(&mut ToDisplay(&mut display), |band| {
    ///         band.clear(Rgb565::BLACK);
    ///         bin.draw(band).unwrap(); // the band is of the bin's layout
    ///     })
    ///     .unwrap();
    /// assert_ne!(display.get(32, 24), Some(Rgb565::BLACK));
    /// # Ok::<(), BandError>(())
    /// ```
    // Out of line: the frame's work once, and the same code whatever the caller.
    #[inline(never)]
    pub fn new_textured(
        pipeline: &'a Pipeline,
        mesh: &Mesh<'a>,
        material: &TexturedMaterial<'a, S, W>,
        layout: &BandLayout,
        scratch: &'a mut [ProjectedVertex],
        storage: &'a mut [BinEntry],
    ) -> Result<Self, BandError> {
        build(pipeline, mesh, layout, scratch, storage, |clip| {
            Frame::textured(pipeline, mesh, material, clip)
        })
    }

    /// Fills `band`'s faces into it, in the mesh's order: the pixels and depths the whole frame
    /// drawn with [`Pipeline::draw_textured_mesh_with`] has there (each face crossing bands set
    /// up again in each). Fastest when the bands are drawn top to bottom once;
    /// `Err(OtherLayout)` (nothing drawn) for a band of another layout.
    pub fn draw(&mut self, band: &mut DepthBand<'_, C>) -> Result<(), BandError> {
        set_up_each(self, band)
    }
}

/// Fills `band`'s faces of `bin` into it, each set up again in each band it reaches.
fn set_up_each<C: GouraudColor, T: FaceTexture<C>>(
    bin: &mut MeshBin<'_, C, T>,
    band: &mut DepthBand<'_, C>,
) -> Result<(), BandError> {
    if band.layout() != &bin.layout {
        return Err(BandError::OtherLayout);
    }
    let frame = bin.frame.with_clip(band.clip(bin.pipeline));
    let (target, placement) = band.parts();
    let (mesh, scratch) = (&bin.mesh, bin.scratch);
    target.blending(frame.blend(), |target| {
        bin.lists.each(placement.index, |r, _, _, _| {
            frame.refill(mesh, scratch, &r.face(), r.flag, target);
        })
    });
    Ok(())
}

/// A [`MeshBin`] of the frame `make` gives for the rows of `layout` (the frame's clip): its
/// vertices projected into `scratch`, its faces recorded in `storage`.
#[inline(always)]
fn build<'a, C, T>(
    pipeline: &'a Pipeline,
    mesh: &Mesh<'a>,
    layout: &BandLayout,
    scratch: &'a mut [ProjectedVertex],
    storage: &'a mut [BinEntry],
    make: impl FnOnce(TargetClip<AllRows>) -> Frame<'a, C, AllRows, T>,
) -> Result<MeshBin<'a, C, T>, BandError>
where
    C: GouraudColor,
    T: FaceTexture<C>,
{
    let scratch = fit_scratch(mesh, scratch)?;
    let lists = Lists::new(layout, storage)?;
    let frame_rect = Rectangle::new(Point::zero(), layout.size());
    let clip = TargetClip::of_frame(&pipeline.viewport, &frame_rect, AllRows);
    let rows = clip.rect();
    let frame = make(clip);
    frame.project(mesh, scratch);
    let scratch = &*scratch;
    let mut sink = Recorder {
        lists,
        rows: Rows::new(layout, &rows),
    };
    let stats = frame.scratch_faces(mesh, scratch, &mut sink);
    sink.lists.finish()?;
    Ok(MeshBin {
        lists: sink.lists,
        pipeline,
        frame,
        mesh: *mesh,
        scratch,
        layout: *layout,
        stats,
    })
}

/// The face stage's sink of a [`MeshBin`]: each face kept recorded with its bands.
struct Recorder<'b> {
    lists: Lists<'b>,
    /// The rows of the frame's clip (no face is drawn outside them), if any.
    rows: Option<Rows>,
}

impl Recorder<'_> {
    /// Records face `k` (vertices `idx`; to be clipped again if `clipped`) reaching the
    /// sub-pixel heights `top ..= bottom`: its vertex indices, so that a band reads its
    /// vertices without the mesh's indices.
    #[inline(always)]
    fn record(&mut self, k: usize, idx: &[usize; 3], clipped: bool, (top, bottom): (i32, i32)) {
        let (top, bottom) = (first_centre_from(top), last_centre_to(bottom));
        let Some((first, last)) = self.rows.and_then(|r| r.bands(top, bottom)) else {
            return;
        };
        if k >= MAX_RECORDS as usize {
            self.lists.limit = true;
            return;
        }
        // A mesh's indices are `u16`s.
        let [a, b, c] = idx.map(|i| i as u16);
        let item = u32::from(a) | u32::from(b) << 16;
        self.lists.push((item, c, clipped), first, last);
    }
}

impl<C: GouraudColor> FaceSink<C> for Recorder<'_> {
    #[inline(always)]
    fn face<R: RowWindow, T: FaceTexture<C>>(
        &mut self,
        _: &Frame<'_, C, R, T>,
        _: &Mesh<'_>,
        k: usize,
        idx: &[usize; 3],
        _: impl Fn() -> [Vec3; 3] + Copy,
        v: [&ProjectedVertex; 3],
        _: Option<crate::arch::TexturedDraw>,
    ) {
        let y = v.map(|v| v.position_bits().1);
        let heights = (y[0].min(y[1]).min(y[2]), y[0].max(y[1]).max(y[2]));
        self.record(k, idx, false, heights);
    }

    fn clipped<R: RowWindow, T: FaceTexture<C>>(
        &mut self,
        frame: &Frame<'_, C, R, T>,
        _: &Mesh<'_>,
        k: usize,
        idx: &[usize; 3],
        model: impl Fn() -> [Vec3; 3] + Copy,
        v: [ProjectedVertex; 3],
        stats: &mut DrawStats,
    ) {
        // Counted as the whole frame's draw counts it.
        stats.clipped += 1;
        match frame.clip_face(model, &v) {
            Ok(face) => {
                stats.drawn += 1;
                self.record(k, idx, true, face.heights());
            }
            Err(dropped) => dropped.count(stats),
        }
    }
}
