//! The public span iterator: a triangle's covered spans inside a clip, top to bottom, from the
//! compact set-up's walk (bounding boxes under 2048 px) or the general one's.

use embedded_graphics::primitives::Rectangle;

use super::compact::CompactTriangle;
use super::edge::TriangleSetup;
use super::walk::{general_walk, Region, Span, Walk};
use crate::fixed_point::Coord;

/// Iterator over the covered spans of a triangle inside a clip rectangle, top to bottom: the
/// walk of the compact set-up (bounding boxes under 2048 px) or of the general one.
#[derive(Debug, Clone)]
pub struct Spans {
    walk: Walk,
}

impl Spans {
    /// Spans of `setup` inside `region` (the general walk).
    #[inline(always)]
    pub(crate) fn new(setup: &TriangleSetup, region: Region) -> Spans {
        Spans {
            walk: general_walk(setup, &region, &region),
        }
    }

    /// The spans of a walk (a compact triangle's).
    #[inline(always)]
    pub(crate) fn compact(walk: Walk) -> Spans {
        Spans { walk }
    }

    /// Spans of the triangle `v` inside `clip` (empty for degenerate triangles).
    #[inline(always)]
    pub fn of_triangle(v: [(Coord, Coord); 3], clip: &Rectangle) -> Spans {
        match CompactTriangle::classify(v, clip).walk() {
            Ok((_, walk)) => Spans::compact(walk),
            Err(None) => Spans::empty(),
            Err(Some(region)) => Spans::general(v, &region),
        }
    }

    /// [`of_triangle`](Self::of_triangle) through the general set-up over `region` (the
    /// triangle's pixels inside the clip), out of line: the compact set-up's spans then start
    /// in fewer instructions.
    #[inline(never)]
    fn general(v: [(Coord, Coord); 3], region: &Region) -> Spans {
        // By reference: moving the setup out of the `Option` would copy it.
        let setup = TriangleSetup::new(v);
        setup
            .as_ref()
            .map_or_else(Spans::empty, |s| Spans::new(s, *region))
    }

    /// An iterator with no spans.
    pub fn empty() -> Spans {
        Spans {
            walk: Walk::empty(),
        }
    }
}

impl Iterator for Spans {
    type Item = Span;

    #[inline]
    fn next(&mut self) -> Option<Span> {
        self.walk.next_span().map(|(span, _, _)| span)
    }

    /// The walk's state then lives in registers.
    #[inline]
    fn fold<B, F: FnMut(B, Span) -> B>(self, init: B, mut f: F) -> B {
        self.walk.fold(init, |acc, span, _, _| f(acc, span))
    }
}

/// Calls `f(y, x_start, x_end)` for every covered span of the triangle `v` inside `clip`
/// (`x_end` exclusive), top to bottom. Degenerate triangles produce no spans.
pub fn for_each_span(v: [(Coord, Coord); 3], clip: Rectangle, mut f: impl FnMut(i32, i32, i32)) {
    for s in Spans::of_triangle(v, &clip) {
        f(s.y, s.x_start, s.x_end);
    }
}
