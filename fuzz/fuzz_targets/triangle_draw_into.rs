//! `GouraudTriangle`/`SolidTriangle` into a `SliceFramebuffer` of any size up to 96 × 96 (zero
//! included) by every entry point — `draw` (the `DrawTarget` fills), `draw_into` and, for compact
//! triangles, `draw_into_compact` — with vertices near the buffer or anywhere in the `Coord`
//! range: no panic, all entry points write the same pixels, exactly the reference's coverage,
//! Gouraud colours within 1 LSB of the f64 interpolation, and `draw_into_compact` draws nothing
//! when it returns `TooLarge`.
//!
//! A pixel counts as written when two buffers cleared to different colours agree on it.
#![no_main]

use arbitrary::Arbitrary;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_raster::{Coord, GouraudTriangle, SliceFramebuffer, SolidTriangle, Vertex};
use embedded_raster_fuzz::{assert_gouraud_colour, reference_coverage, Color, RawCoord};
use libfuzzer_sys::fuzz_target;

#[derive(Arbitrary, Debug)]
struct Input {
    width: u8,
    height: u8,
    vertices: [(RawCoord, RawCoord); 3],
    colors: [Color; 3],
    solid: bool,
}

/// The two background colours.
const BACKGROUNDS: [Rgb888; 2] = [Rgb888::new(1, 2, 3), Rgb888::new(254, 253, 252)];

/// Draws with `draw` into two buffers of different backgrounds and returns the pixels written
/// (`Some(colour)` where both agree).
fn written(
    width: u32,
    height: u32,
    draw: impl Fn(&mut SliceFramebuffer<'_, Rgb888>),
) -> Vec<Option<Rgb888>> {
    let n = (width * height) as usize;
    let buffers = BACKGROUNDS.map(|bg| {
        let mut px = vec![bg; n];
        draw(&mut SliceFramebuffer::new(&mut px, width, height).unwrap());
        px
    });
    buffers[0]
        .iter()
        .zip(&buffers[1])
        .map(|(a, b)| (a == b).then_some(*a))
        .collect()
}

fuzz_target!(|input: Input| {
    let (width, height) = (u32::from(input.width % 97), u32::from(input.height % 97));
    let raw = input.vertices.map(|(x, y)| (x.get(0), y.get(0)));
    let coords = raw.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y)));
    let colors = input.colors.map(Color::get);

    let results: Vec<Vec<Option<Rgb888>>> = if input.solid {
        let t = SolidTriangle::new(coords, colors[0]);
        vec![
            written(width, height, |fb| t.draw(fb).unwrap()),
            written(width, height, |fb| t.draw_into(fb)),
        ]
    } else {
        let t = GouraudTriangle::new(
            [0, 1, 2].map(|k| Vertex::new(coords[k].0, coords[k].1, colors[k])),
        );
        let mut results = vec![
            written(width, height, |fb| t.draw(fb).unwrap()),
            written(width, height, |fb| t.draw_into(fb)),
        ];
        let too_large = std::cell::Cell::new(false);
        let compact = written(width, height, |fb| {
            too_large.set(t.draw_into_compact(fb).is_err())
        });
        if too_large.get() {
            assert!(
                compact.iter().all(Option::is_none),
                "draw_into_compact drew and said TooLarge"
            );
        } else {
            results.push(compact);
        }
        results
    };
    for (k, r) in results.iter().enumerate().skip(1) {
        assert_eq!(
            r, &results[0],
            "entry point {k} differs from draw for {raw:?} in {width}×{height}"
        );
    }

    let bounds =
        embedded_graphics::primitives::Rectangle::new(Point::zero(), Size::new(width, height));
    let want = reference_coverage(raw, &bounds);
    let got: Vec<(i32, i32)> = {
        let mut got: Vec<(i32, i32)> = results[0]
            .iter()
            .enumerate()
            .filter(|(_, c)| c.is_some())
            .map(|(i, _)| {
                (
                    (i as u32 % width.max(1)) as i32,
                    (i as u32 / width.max(1)) as i32,
                )
            })
            .collect();
        got.sort_unstable();
        got
    };
    assert_eq!(
        got, want,
        "triangle {raw:?} in {width}×{height}: coverage differs from the reference"
    );
    for &(x, y) in &want {
        let c = results[0][(y as u32 * width + x as u32) as usize].unwrap();
        if input.solid {
            assert_eq!(c, colors[0]);
        } else {
            assert_gouraud_colour(raw, colors, x, y, c);
        }
    }
});
