//! `GouraudTriangle`/`SolidTriangle` `draw` into a recording target whose box is anywhere in
//! `i32` (up to 64 × 64 pixels, reaching past `i32::MAX` too), vertices anywhere in the `Coord`
//! range: no panic, every pixel inside the box and written once, exactly the reference's
//! coverage, one call a covered row, Gouraud colours within 1 LSB of the f64 interpolation, solid
//! colours exact. Then `spans`/`shaded_spans` under an arbitrary clip rectangle: every span
//! inside the clip, rows in order, and each span maximal (its ends covered by the reference, the
//! pixels just past them not covered or outside the clip).
//!
//! Then the same triangle (solid or Gouraud, and textured) into a target that fails: its `n`-th
//! call, the draw returning that error exactly when the recording target had `n` calls or more,
//! or the first call of a target whose box is any rectangle (over 10⁹ pixels a side: a draw that
//! walked on after the error ran into the 5 s timeout, issue #32 item 11). No call after the
//! error.
#![no_main]

use arbitrary::Arbitrary;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::raster::Span;
use embedded_raster::texture::{Rgb565Texels, TexelCoord, Texture};
use embedded_raster::{
    reference, Coord, GouraudTriangle, SolidTriangle, TexturedTriangle, TexturedVertex, Vertex,
};
use embedded_raster_fuzz::{
    assert_gouraud_colour, inside, reference_coverage, AnyRect, Color, Failing, Int, RawCoord,
    Recorder,
};
use libfuzzer_sys::fuzz_target;

#[derive(Arbitrary, Debug)]
struct Input {
    box_x: Int,
    box_y: Int,
    box_width: u8,
    box_height: u8,
    vertices: [(RawCoord, RawCoord); 3],
    colors: [Color; 3],
    solid: bool,
    clip: AnyRect,
    fail: Fail,
}

/// Which call of the failing target fails.
#[derive(Arbitrary, Debug)]
enum Fail {
    /// The `n`-th (1-based, `n % 80 + 1`) of the same box as the recording target's.
    At(u8),
    /// The first, of a target whose box is this rectangle.
    First(AnyRect),
}

/// The 2 × 2 texture of the textured draw.
static TEXELS: [u16; 4] = [0xf800, 0x07e0, 0x001f, 0xffff];

/// `draw` of the triangle (solid or Gouraud as `solid`, or textured) into `target`.
fn draw_failing(
    coords: [(Coord, Coord); 3],
    colors: [Rgb888; 3],
    solid: bool,
    textured: bool,
    target: &mut Failing,
) -> Result<(), usize> {
    if textured {
        let texture = Texture::new(Rgb565Texels(&TEXELS), 2, 2).unwrap();
        // Texel coordinates from the positions: a texel every 64 pixels, wrapping.
        let vertices = coords.map(|(x, y)| {
            let texel = |c: Coord| TexelCoord::from_bits(c.to_bits().wrapping_mul(4));
            TexturedVertex::new(x, y, texel(x), texel(y))
        });
        TexturedTriangle::new(vertices, &texture).draw(target)
    } else if solid {
        SolidTriangle::new(coords, colors[0]).draw(target)
    } else {
        let vertices = [0, 1, 2].map(|k| Vertex::new(coords[k].0, coords[k].1, colors[k]));
        GouraudTriangle::new(vertices).draw(target)
    }
}

/// Spans at most checked under the arbitrary clip (huge triangles have billions of rows).
const MAX_SPANS: usize = 512;

fn check_spans(raw: [(i32, i32); 3], clip: &Rectangle, spans: impl Iterator<Item = Span>) {
    // Shaded spans come in chunks of at most MAX_CHUNK pixels: joined again here.
    let mut joined: Vec<Span> = Vec::new();
    let mut taken = 0;
    for span in spans.take(MAX_SPANS) {
        taken += 1;
        assert!(span.x_start < span.x_end, "empty span {span:?}");
        match joined.last_mut() {
            Some(last) if last.y == span.y && last.x_end == span.x_start => last.x_end = span.x_end,
            _ => joined.push(span),
        }
    }
    if taken == MAX_SPANS {
        // The last one may continue.
        joined.pop();
    }
    for pair in joined.windows(2) {
        assert!(
            pair[0].y < pair[1].y,
            "rows out of order or split: {pair:?}"
        );
    }
    for span in joined {
        let last = span.x_end - 1;
        for x in [span.x_start, last] {
            assert!(
                inside(clip, x, span.y),
                "{span:?} outside the clip {clip:?}"
            );
            assert!(
                reference::covers(raw, x, span.y),
                "{raw:?}: {span:?} end ({x}) not covered"
            );
        }
        for x in [span.x_start.checked_sub(1), Some(span.x_end)]
            .into_iter()
            .flatten()
        {
            assert!(
                !inside(clip, x, span.y) || !reference::covers(raw, x, span.y),
                "{raw:?}: {span:?} not maximal in {clip:?} (column {x} covered)"
            );
        }
    }
}

fuzz_target!(|input: Input| {
    let (bx, by) = (input.box_x.get(), input.box_y.get());
    let bounds = Rectangle::new(
        Point::new(bx, by),
        Size::new(
            u32::from(input.box_width % 65),
            u32::from(input.box_height % 65),
        ),
    );
    let raw = input.vertices.map(|(x, y)| (x.get(bx), y.get(by)));
    let coords = raw.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y)));
    let colors = input.colors.map(Color::get);

    let mut target = Recorder::new(bounds);
    if input.solid {
        SolidTriangle::new(coords, colors[0])
            .draw(&mut target)
            .unwrap();
        assert!(
            target.written.values().all(|&c| c == colors[0]),
            "solid colour changed"
        );
    } else {
        let vertices = [0, 1, 2].map(|k| Vertex::new(coords[k].0, coords[k].1, colors[k]));
        GouraudTriangle::new(vertices).draw(&mut target).unwrap();
        for (&(x, y), &c) in &target.written {
            assert_gouraud_colour(raw, colors, x, y, c);
        }
    }
    let want = reference_coverage(raw, &bounds);
    let mut got: Vec<(i32, i32)> = target.written.keys().copied().collect();
    got.sort_unstable();
    assert_eq!(
        got, want,
        "triangle {raw:?} in {bounds:?}: coverage differs from the reference"
    );
    let rows: std::collections::BTreeSet<i32> = want.iter().map(|&(_, y)| y).collect();
    assert_eq!(target.calls, rows.len(), "not one call a covered row");

    // Into a failing target: stops at the error.
    for textured in [false, true] {
        let (bounds, fail_at) = match input.fail {
            Fail::At(n) => (bounds, usize::from(n % 80) + 1),
            Fail::First(rect) => (rect.get(), 1),
        };
        let mut failing = Failing::new(bounds, fail_at);
        let result = draw_failing(coords, colors, input.solid, textured, &mut failing);
        assert_eq!(result.is_err(), failing.calls == fail_at, "{result:?}");
        if let (Fail::At(_), false) = (&input.fail, textured) {
            // As many calls as the recording target had, up to the failing one.
            assert_eq!(failing.calls, target.calls.min(fail_at), "{result:?}");
        }
    }

    let clip = input.clip.get();
    if input.solid {
        check_spans(
            raw,
            &clip,
            SolidTriangle::new(coords, colors[0]).spans(&clip),
        );
    } else {
        let vertices = [0, 1, 2].map(|k| Vertex::new(coords[k].0, coords[k].1, colors[k]));
        let spans = GouraudTriangle::new(vertices)
            .shaded_spans(&clip)
            .map(|(span, _)| span);
        check_spans(raw, &clip, spans);
    }
});
