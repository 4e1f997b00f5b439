//! `GouraudTriangle`/`SolidTriangle` `draw` into a recording target whose box is anywhere in
//! `i32` (up to 64 × 64 pixels, reaching past `i32::MAX` too), vertices anywhere in the `Coord`
//! range: no panic, every pixel inside the box and written once, exactly the reference's
//! coverage, one call a covered row, Gouraud colours within 1 LSB of the f64 interpolation, solid
//! colours exact. Then `spans`/`shaded_spans` under an arbitrary clip rectangle: every span
//! inside the clip, rows in order, and each span maximal (its ends covered by the reference, the
//! pixels just past them not covered or outside the clip).
#![no_main]

use arbitrary::Arbitrary;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raster::raster::Span;
use embedded_raster::{reference, Coord, GouraudTriangle, SolidTriangle, Vertex};
use embedded_raster_fuzz::{
    assert_gouraud_colour, inside, reference_coverage, AnyRect, Color, Int, RawCoord, Recorder,
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
