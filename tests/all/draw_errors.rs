//! `Drawable::draw` into a `DrawTarget` that fails (issue #32, item 11): the first error is
//! returned and nothing more is asked of the target — also on a target whose bounding box is
//! over a billion pixels on each side, where a walk that went on after the error took 10–12 s
//! for a Gouraud triangle (a fuzz find). Calls are counted, not timed; the unit tests
//! `raster::shade::tests` count the spans the walk hands its shader after it has stopped.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;
use embedded_raster::texture::{Rgb565Texels, Texture};
use embedded_raster::{
    Coord, GouraudTriangle, SolidTriangle, TexturedTriangle, TexturedVertex, Vertex,
};

/// A target with any bounding box that fails its `fail_at`-th call (of any drawing method) and
/// every one after it, counting them all.
struct Failing {
    area: Rectangle,
    fail_at: u32,
    calls: u32,
}

impl Failing {
    fn new(area: Rectangle, fail_at: u32) -> Self {
        Failing {
            area,
            fail_at,
            calls: 0,
        }
    }

    /// Counts a call: `Err(n)` from the `fail_at`-th on, `n` the call's number.
    fn call(&mut self) -> Result<(), u32> {
        self.calls += 1;
        if self.calls >= self.fail_at {
            Err(self.calls)
        } else {
            Ok(())
        }
    }
}

impl Dimensions for Failing {
    fn bounding_box(&self) -> Rectangle {
        self.area
    }
}

impl DrawTarget for Failing {
    type Color = Rgb565;
    type Error = u32;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, _: I) -> Result<(), u32> {
        self.call()
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        _: &Rectangle,
        _: I,
    ) -> Result<(), u32> {
        self.call()
    }

    fn fill_solid(&mut self, _: &Rectangle, _: Rgb565) -> Result<(), u32> {
        self.call()
    }

    fn clear(&mut self, _: Rgb565) -> Result<(), u32> {
        self.call()
    }
}

/// The fuzz find's target: about 1.2·10⁹ × 1.4·10⁹ pixels around the origin.
fn huge() -> Rectangle {
    Rectangle::new(
        Point::new(-600_000_000, -700_000_000),
        Size::new(1_200_000_000, 1_400_000_000),
    )
}

/// 2²³ − 1 pixels: the ends of the `Coord` range.
const FAR: i32 = (1 << 23) - 1;

fn c(x: i32, y: i32) -> (Coord, Coord) {
    (Coord::from_num(x), Coord::from_num(y))
}

/// Triangles as far apart as `Coord`s go, and one of a few hundred pixels: compact and general
/// set-ups, stepped and exact planes (regions over 2¹⁶ pixels across).
fn triangles() -> [[(Coord, Coord); 3]; 3] {
    [
        [c(-FAR, -FAR), c(FAR, -FAR / 2), c(-FAR / 3, FAR)],
        [c(-30_000, -20_000), c(30_000, -10_000), c(0, 25_000)],
        [c(3, 2), c(400, 50), c(90, 350)],
    ]
}

static TEXELS: [u16; 4] = [0xf800, 0x07e0, 0x001f, 0xffff];

/// Every 2D drawable's `draw` into `target`.
fn draw_all(
    points: [(Coord, Coord); 3],
    make: impl Fn() -> Failing,
) -> [(Result<(), u32>, u32); 3] {
    let colors = [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE];
    let texture = Texture::new(Rgb565Texels(&TEXELS), 2, 2).unwrap();
    let mut results = [(Ok(()), 0); 3];

    let mut target = make();
    let result = SolidTriangle::new(points, Rgb565::RED).draw(&mut target);
    results[0] = (result, target.calls);

    let mut target = make();
    let vertices = [0, 1, 2].map(|k| Vertex::new(points[k].0, points[k].1, colors[k]));
    let result = GouraudTriangle::new(vertices).draw(&mut target);
    results[1] = (result, target.calls);

    let mut target = make();
    // A texel every 1000 pixels, wrapping.
    let vertices = points.map(|(x, y)| {
        TexturedVertex::new(x, y, x.to_num::<f32>() / 1000.0, y.to_num::<f32>() / 1000.0)
    });
    let triangle: TexturedTriangle<'_, _, Rgb565> = TexturedTriangle::new(vertices, &texture);
    let result = triangle.draw(&mut target);
    results[2] = (result, target.calls);
    results
}

/// A target that fails its first call: the draw returns that error and calls nothing more.
#[test]
fn the_first_error_ends_the_draw() {
    for points in triangles() {
        for area in [
            huge(),
            Rectangle::new(Point::new(-20, -10), Size::new(640, 480)),
        ] {
            for (k, (result, calls)) in draw_all(points, || Failing::new(area, 1))
                .iter()
                .enumerate()
            {
                assert_eq!(*result, Err(1), "drawable {k}, {points:?} into {area:?}");
                assert_eq!(*calls, 1, "drawable {k}, {points:?} into {area:?}");
            }
        }
    }
}

/// A target that fails its `n`-th call: the draw made exactly `n` calls and returns that error.
#[test]
fn an_error_mid_draw_ends_it() {
    let area = Rectangle::new(Point::new(-20, -10), Size::new(640, 480));
    let points = triangles()[2];
    let all = draw_all(points, || Failing::new(area, u32::MAX));
    for (k, (result, calls)) in all.iter().enumerate() {
        assert_eq!(*result, Ok(()));
        assert!(*calls > 300, "drawable {k}: only {calls} calls");
        for n in [2, 17, calls / 2, *calls] {
            let (result, made) = draw_all(points, || Failing::new(area, n))[k];
            assert_eq!(
                (result, made),
                (Err(n), n),
                "drawable {k}, failing call {n}"
            );
        }
    }
}
