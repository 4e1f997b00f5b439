//! What the fuzz targets share: inputs biased towards the edges of `i32`, a recording
//! `DrawTarget` that checks every write, and the f64 reference's coverage and colours.
//!
//! Every check here is independent of the code under test: rectangles are evaluated per pixel in
//! `i64`, coverage and colours come from `embedded_raster::reference` (exact edge functions and
//! f64 interpolation).

use std::collections::HashMap;
use std::convert::Infallible;

use arbitrary::Arbitrary;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;
use embedded_raster::reference;

/// An `i32` drawn from a mix of scales, so that both ordinary and extreme values are common.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub enum Int {
    /// Near zero.
    Small(i8),
    /// Up to ±32767.
    Medium(i16),
    /// One of the values where arithmetic breaks: the ends of `i32`, powers of two and their
    /// neighbours.
    Edge(u8),
    /// Anything.
    Any(i32),
}

impl Int {
    /// The value.
    pub fn get(self) -> i32 {
        match self {
            Int::Small(v) => i32::from(v),
            Int::Medium(v) => i32::from(v),
            Int::Edge(k) => {
                let p = 1i64 << (k % 32);
                let v = match k / 32 % 8 {
                    0 => p,
                    1 => p - 1,
                    2 => p + 1,
                    3 => -p,
                    4 => -p - 1,
                    5 => -p + 1,
                    6 => i64::from(i32::MAX) - i64::from(k % 32),
                    _ => i64::from(i32::MIN) + i64::from(k % 32),
                };
                v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
            }
            Int::Any(v) => v,
        }
    }
}

/// A `u32` size, likewise biased.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub enum Len {
    /// Up to 255.
    Small(u8),
    /// Near a power of two (`u32::MAX` included).
    Edge(u8),
    /// Anything.
    Any(u32),
}

impl Len {
    /// The value.
    pub fn get(self) -> u32 {
        match self {
            Len::Small(v) => u32::from(v),
            Len::Edge(k) => {
                let p = 1u64 << (k % 33);
                let v = match k / 33 % 3 {
                    0 => p,
                    1 => p - 1,
                    _ => p + 1,
                };
                v.min(u64::from(u32::MAX)) as u32
            }
            Len::Any(v) => v,
        }
    }
}

/// Any rectangle: corner anywhere in `i32`, sides up to `u32::MAX`.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub struct AnyRect {
    pub x: Int,
    pub y: Int,
    pub width: Len,
    pub height: Len,
}

impl AnyRect {
    /// The rectangle.
    pub fn get(self) -> Rectangle {
        Rectangle::new(
            Point::new(self.x.get(), self.y.get()),
            Size::new(self.width.get(), self.height.get()),
        )
    }
}

/// Whether pixel `(x, y)` lies in `r`, from the definition in `i64`.
pub fn inside(r: &Rectangle, x: i32, y: i32) -> bool {
    let axis = |p: i32, start: i32, len: u32| {
        let (p, start) = (i64::from(p), i64::from(start));
        start <= p && p < start + i64::from(len)
    };
    axis(x, r.top_left.x, r.size.width) && axis(y, r.top_left.y, r.size.height)
}

/// Every pixel of `r` that has `i32` coordinates, row by row; `r` must be small (a span or a
/// target's box). Computed in `i64`, so rectangles reaching past `i32::MAX` are fine.
pub fn pixels(r: &Rectangle) -> impl Iterator<Item = (i32, i32)> {
    let (x0, y0) = (i64::from(r.top_left.x), i64::from(r.top_left.y));
    let x1 = (x0 + i64::from(r.size.width)).min(i64::from(i32::MAX) + 1);
    let y1 = (y0 + i64::from(r.size.height)).min(i64::from(i32::MAX) + 1);
    (y0..y1).flat_map(move |y| (x0..x1).map(move |x| (x as i32, y as i32)))
}

/// A sub-pixel vertex coordinate (raw `Coord` bits, 8 fractional bits): near the target, or
/// anywhere in the `Coord` range.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub enum RawCoord {
    /// Within ±128 pixels of the origin (sub-pixel positions).
    Near(i16),
    /// A pixel anywhere in `i32`'s range of pixels representable as `Coord` (±2²³), plus a
    /// sub-pixel offset.
    Far(i32, u8),
    /// Any raw value.
    Any(i32),
}

impl RawCoord {
    /// The raw `Coord` bits.
    pub fn get(self, origin: i32) -> i32 {
        match self {
            RawCoord::Near(v) => {
                (origin.clamp(-(1 << 23), (1 << 23) - 1) << 8).saturating_add(i32::from(v))
            }
            RawCoord::Far(p, s) => (p % (1 << 23)) * 256 + i32::from(s),
            RawCoord::Any(v) => v,
        }
    }
}

/// A recording `DrawTarget` with any bounding box (a stand-in for a translated or cropped
/// display): panics on any pixel outside the box, any pixel written twice, and `fill_contiguous`
/// colours that do not match the area's size.
pub struct Recorder {
    pub bounds: Rectangle,
    pub written: HashMap<(i32, i32), Rgb888>,
    /// Calls of `fill_contiguous`, `fill_solid` and `draw_iter`.
    pub calls: usize,
}

impl Recorder {
    /// A recorder over `bounds`, which must hold at most a few thousand pixels.
    pub fn new(bounds: Rectangle) -> Self {
        Recorder {
            bounds,
            written: HashMap::new(),
            calls: 0,
        }
    }

    fn write(&mut self, x: i32, y: i32, color: Rgb888) {
        assert!(
            inside(&self.bounds, x, y),
            "pixel ({x}, {y}) outside the target's box {:?}",
            self.bounds
        );
        let previous = self.written.insert((x, y), color);
        assert!(previous.is_none(), "pixel ({x}, {y}) written twice");
    }

    /// Checks that `area` lies inside the box (the rasterizer clips before it emits).
    fn check_area(&self, area: &Rectangle) {
        if area.size.width == 0 || area.size.height == 0 {
            return;
        }
        let last = |start: i32, len: u32| i64::from(start) + i64::from(len) - 1;
        let (x1, y1) = (
            last(area.top_left.x, area.size.width),
            last(area.top_left.y, area.size.height),
        );
        assert!(
            x1 <= i64::from(i32::MAX) && y1 <= i64::from(i32::MAX),
            "area {area:?} reaches past i32::MAX"
        );
        assert!(
            inside(&self.bounds, area.top_left.x, area.top_left.y)
                && inside(&self.bounds, x1 as i32, y1 as i32),
            "area {area:?} outside the target's box {:?}",
            self.bounds
        );
    }
}

/// The box is anywhere, so `Dimensions` directly (not `OriginDimensions`).
impl Dimensions for Recorder {
    fn bounding_box(&self) -> Rectangle {
        self.bounds
    }
}

impl DrawTarget for Recorder {
    type Color = Rgb888;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Infallible> {
        self.calls += 1;
        for Pixel(p, c) in pixels {
            self.write(p.x, p.y, c);
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb888>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Infallible> {
        self.calls += 1;
        self.check_area(area);
        let mut colors = colors.into_iter();
        for (x, y) in pixels(area) {
            let c = colors.next().expect("fewer colours than the area's pixels");
            self.write(x, y, c);
        }
        assert!(
            colors.next().is_none(),
            "more colours than the area's pixels"
        );
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Rgb888) -> Result<(), Infallible> {
        self.calls += 1;
        self.check_area(area);
        for (x, y) in pixels(area) {
            self.write(x, y, color);
        }
        Ok(())
    }
}

/// A `DrawTarget` with any bounding box (of any size: it writes nothing) whose `fail_at`-th call
/// (1-based) returns an error, the call's number: panics on any call after that one (a draw
/// must stop at its target's first error) and counts the calls.
pub struct Failing {
    pub bounds: Rectangle,
    pub fail_at: usize,
    pub calls: usize,
}

impl Failing {
    /// A target over `bounds` that fails its `fail_at`-th call.
    pub fn new(bounds: Rectangle, fail_at: usize) -> Self {
        Failing {
            bounds,
            fail_at,
            calls: 0,
        }
    }

    fn call(&mut self) -> Result<(), usize> {
        assert!(
            self.calls < self.fail_at,
            "called again after the target's error (call {})",
            self.fail_at
        );
        self.calls += 1;
        if self.calls == self.fail_at {
            Err(self.calls)
        } else {
            Ok(())
        }
    }
}

impl Dimensions for Failing {
    fn bounding_box(&self) -> Rectangle {
        self.bounds
    }
}

impl DrawTarget for Failing {
    type Color = Rgb888;
    type Error = usize;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(&mut self, _: I) -> Result<(), usize> {
        self.call()
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb888>>(
        &mut self,
        _: &Rectangle,
        _: I,
    ) -> Result<(), usize> {
        self.call()
    }

    fn fill_solid(&mut self, _: &Rectangle, _: Rgb888) -> Result<(), usize> {
        self.call()
    }
}

/// The pixels of `bounds` whose centres the triangle `v` (raw sub-pixel coordinates) covers,
/// by the reference's exact rule.
pub fn reference_coverage(v: [(i32, i32); 3], bounds: &Rectangle) -> Vec<(i32, i32)> {
    let mut covered = Vec::new();
    if bounds.size.width == 0 || bounds.size.height == 0 {
        return covered;
    }
    let end =
        |start: i32, len: u32| (i64::from(start) + i64::from(len)).min(i64::from(i32::MAX)) as i32;
    let (x0, y0) = (bounds.top_left.x, bounds.top_left.y);
    let (x1, y1) = (end(x0, bounds.size.width), end(y0, bounds.size.height));
    reference::for_each_covered(v, x0, y0, x1, y1, |x, y| covered.push((x, y)));
    // `for_each_covered` takes exclusive `i32` bounds: the last column and row of `i32`, if in
    // the box, are tested one by one.
    let reaches = |start: i32, len: u32| i64::from(start) + i64::from(len) > i64::from(i32::MAX);
    if reaches(x0, bounds.size.width) {
        for y in y0..y1 {
            if reference::covers(v, i32::MAX, y) {
                covered.push((i32::MAX, y));
            }
        }
    }
    if reaches(y0, bounds.size.height) {
        for (x, _) in pixels(bounds).filter(|&(_, y)| y == i32::MAX) {
            if reference::covers(v, x, i32::MAX) {
                covered.push((x, i32::MAX));
            }
        }
    }
    covered.sort_unstable();
    covered
}

/// Asserts that `got` is within 1 LSB (per channel) of the reference's interpolation of the
/// vertex colours at pixel `(x, y)`.
pub fn assert_gouraud_colour(v: [(i32, i32); 3], colors: [Rgb888; 3], x: i32, y: i32, got: Rgb888) {
    let channels = colors.map(|c| [c.r(), c.g(), c.b()].map(f64::from));
    let exact = reference::interpolate(v, channels, x, y).expect("a covered pixel");
    let got_channels = [got.r(), got.g(), got.b()].map(f64::from);
    for k in 0..3 {
        let err = (got_channels[k] - exact[k]).abs();
        assert!(
            err <= 1.0 + 1e-9,
            "triangle {v:?}, colours {colors:?}, pixel ({x}, {y}): channel {k} = {}, exact {} \
             (error {err} LSB > 1)",
            got_channels[k],
            exact[k]
        );
    }
}

/// An `Rgb888` colour.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub struct Color(pub u8, pub u8, pub u8);

impl Color {
    /// The colour.
    pub fn get(self) -> Rgb888 {
        Rgb888::new(self.0, self.1, self.2)
    }
}
