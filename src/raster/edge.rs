//! Exact edge-function setup with the Direct3D top-left fill rule.
//!
//! For the edge from vertex `a` to vertex `b` the edge function at a point `p` (sub-pixel units) is
//!
//! `E(p) = (x_b − x_a)(p_y − y_a) − (y_b − y_a)(p_x − x_a)`.
//!
//! Vertices are reordered so that the doubled signed area `E_01(v2)` is positive; then the interior
//! is where all three edge functions are positive (on screen, with y down, that is clockwise order).
//!
//! At the centre of pixel `(i, j)`, `p = (256 i + 128, 256 j + 128)` and
//! `E = 256 (A i + B j) + C` with `A = y_a − y_b`, `B = x_b − x_a`. Writing `C = 256 q + r`
//! (`0 ≤ r < 256`), the test "`E > 0`, or `E = 0` on a top or left edge" becomes exactly
//! `K(i, j) = A i + B j + q − t ≥ 0`, where `t = 1` only when `r = 0` and the edge is neither top
//! nor left. `K` is what the traversal steps: it changes by `A` per pixel and `B` per row, and its
//! sign is the exact coverage decision — no rounding anywhere.
//!

use crate::fixed_point::{Coord, HALF_PIXEL, SUBPIXEL_BITS};
use crate::raster::arith::mul_i64_wide;

/// Vertices with every raw coordinate below this magnitude (2²⁹ sub-pixels, about two million
/// pixels) are set up in `i64`: differences stay below 2³⁰, so every `a·x + b·y` formed during
/// set-up and at the pixel centres of the bounding box stays below 2⁶¹. Larger ones use
/// `i128`, which on a 32-bit core costs several times more.
const NARROW_LIMIT: i64 = 1 << 29;

/// `a·x + b·y`, in `i64` when `narrow` (all operands below 2³¹ in magnitude), else in `i128`.
#[inline]
pub(crate) fn dot2(a: i64, x: i64, b: i64, y: i64, narrow: bool) -> i128 {
    if narrow {
        // Cannot overflow under the caller's bound (debug builds check it).
        i128::from(a * x + b * y)
    } else {
        dot2_wide(a, x, b, y)
    }
}

/// The `i128` case of [`dot2`], kept out of line: it is rare and large on 32-bit cores.
#[inline(never)]
#[cold]
fn dot2_wide(a: i64, x: i64, b: i64, y: i64) -> i128 {
    mul_i64_wide(a, x) + mul_i64_wide(b, y)
}

/// The fill rule (Direct3D's top-left rule): whether an edge with coefficients `a = y_a − y_b`,
/// `b = x_b − x_a` of a positively oriented triangle owns the pixel centres that lie exactly on
/// it. Left edges (`a > 0`) and top edges (`a = 0`, `b > 0`) do; right and bottom ones do not, so
/// a centre on an edge shared by two triangles is drawn once.
#[inline(always)]
pub(crate) const fn owns_centres_on(a: i64, b: i64) -> bool {
    a > 0 || (a == 0 && b > 0)
}

/// The first pixel whose centre is at or after `m` (sub-pixels) on its axis.
#[inline(always)]
pub(crate) fn first_centre_from(m: i32) -> i32 {
    (m >> SUBPIXEL_BITS) + i32::from(m & 0xFF > 0x80)
}

/// The last pixel whose centre is at or before `m` (sub-pixels) on its axis.
#[inline(always)]
pub(crate) fn last_centre_to(m: i32) -> i32 {
    (m >> SUBPIXEL_BITS) - i32::from(m & 0xFF < 0x80)
}

/// The last pixel whose centre is strictly before `m` (sub-pixels) on its axis.
#[inline(always)]
pub(crate) fn last_centre_before(m: i32) -> i32 {
    (m >> SUBPIXEL_BITS) - i32::from(m & 0xFF <= 0x80)
}

/// The last pixel row a triangle with vertex heights `ys` (sub-pixels) can cover: the last
/// whose centre is at or above its lowest vertex, or strictly above it if two vertices share
/// that height. A horizontal edge only limits the rows, and only a bottom one needs this: it does
/// not own the centres on it, while a top one does (its row is the first whose centre is at or
/// below the top vertex, where every walk starts anyway).
#[inline(always)]
pub(crate) fn last_row(ys: [i32; 3]) -> i32 {
    let [a, b, c] = ys;
    let lowest = a.max(b).max(c);
    let shared = u32::from(a == lowest) + u32::from(b == lowest) + u32::from(c == lowest);
    if shared > 1 {
        last_centre_before(lowest)
    } else {
        last_centre_to(lowest)
    }
}

/// One edge function: its coefficients and the vertex it starts from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct EdgeFunction {
    /// Change of the edge function per pixel step in x (`y_a − y_b`, sub-pixel units).
    pub(crate) a: i64,
    /// Change of the edge function per pixel step in y (`x_b − x_a`, sub-pixel units).
    pub(crate) b: i64,
    /// The start vertex `a` (raw sub-pixels), where the edge function is 0.
    start: (i64, i64),
}

impl EdgeFunction {
    #[inline(always)]
    fn new(va: (i32, i32), vb: (i32, i32)) -> Self {
        let (va, vb) = (
            (i64::from(va.0), i64::from(va.1)),
            (i64::from(vb.0), i64::from(vb.1)),
        );
        EdgeFunction {
            a: va.1 - vb.1,
            b: vb.0 - va.0,
            start: va,
        }
    }

    /// The exact edge function `E` at the centre of pixel `(i, j)` (squared sub-pixel units):
    /// in `i64` when `narrow` (the centre and the vertices within 2³⁰ sub-pixels of each other,
    /// so both products stay below 2⁶⁰), else in `i128`.
    #[inline]
    pub(crate) fn exact_at(&self, i: i64, j: i64, narrow: bool) -> i128 {
        let centre = |p: i64, start: i64| (p << SUBPIXEL_BITS) + HALF_PIXEL - start;
        let (x, y) = (centre(i, self.start.0), centre(j, self.start.1));
        dot2(self.a, x, self.b, y, narrow)
    }

    /// The reduced coverage value `K = ⌊E/256⌋ − t` of the exact value `e` at a pixel centre:
    /// the pixel is inside this edge iff it is `≥ 0` (`t = 1` for centres on an edge that does
    /// not own them; `E` changes by multiples of 256 from centre to centre, so whether one lies
    /// on the edge's lattice is the same at every centre).
    #[inline]
    pub(crate) fn reduced(&self, e: i128) -> i128 {
        let on_lattice = e & ((1 << SUBPIXEL_BITS) - 1) == 0;
        (e >> SUBPIXEL_BITS) - i128::from(on_lattice && !owns_centres_on(self.a, self.b))
    }

    #[cfg(test)]
    /// The reduced coverage value `K` at pixel `(i, j)` (any `i64` pixel within ±2⁵⁵).
    pub(crate) fn value_at(&self, i: i64, j: i64) -> i128 {
        self.reduced(self.exact_at(i, j, false))
    }
}

/// A non-degenerate triangle in positive orientation: its vertices, doubled area and edge
/// functions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct TriangleSetup {
    /// Raw sub-pixel positions (the `Coord` bits) of the oriented vertices.
    pub(crate) oriented: [(i32, i32); 3],
    /// Twice the triangle's area in squared sub-pixel units; always positive.
    pub(crate) area2: i128,
    /// Which input vertex each of the oriented vertices is (`[0, 1, 2]` or `[0, 2, 1]`).
    pub(crate) order: [usize; 3],
    /// All raw coordinates are below 2²⁹ in magnitude, so the edge functions at pixel centres
    /// within the bounding box fit `i64`.
    pub(crate) narrow: bool,
}

impl TriangleSetup {
    /// Sets up the edge functions of a triangle, or `None` if its vertices are collinear.
    ///
    /// Every `Coord` value is accepted; the area is formed in `i64` for vertices within about
    /// two million pixels of the origin and in `i128` beyond.
    pub(crate) fn new(v: [(Coord, Coord); 3]) -> Option<Self> {
        let vertices = v.map(|(x, y)| (x.to_bits(), y.to_bits()));
        let narrow = vertices.iter().all(|&(x, y)| {
            let inside = |c: i32| c.unsigned_abs() < NARROW_LIMIT as u32;
            inside(x) && inside(y)
        });
        let [p0, p1, p2] = vertices.map(|(x, y)| (i64::from(x), i64::from(y)));
        let area2 = dot2(p1.0 - p0.0, p2.1 - p0.1, p0.0 - p2.0, p1.1 - p0.1, narrow);
        let [v0, v1, v2] = vertices;
        let (order, area2, oriented) = match area2 {
            0 => return None,
            a if a > 0 => ([0, 1, 2], a, [v0, v1, v2]),
            a => ([0, 2, 1], -a, [v0, v2, v1]),
        };
        Some(TriangleSetup {
            oriented,
            area2,
            order,
            narrow,
        })
    }

    /// The edge opposite oriented vertex `k` (0, 1 or 2): from the next vertex to the one after;
    /// it evaluates to `area2` at vertex `k`.
    #[inline(always)]
    pub(crate) fn edge(&self, k: usize) -> EdgeFunction {
        let [o0, o1, o2] = self.oriented;
        match k {
            0 => EdgeFunction::new(o1, o2),
            1 => EdgeFunction::new(o2, o0),
            _ => EdgeFunction::new(o0, o1),
        }
    }

    #[cfg(test)]
    /// The three edges, opposite oriented vertices 0, 1 and 2.
    pub(crate) fn edges(&self) -> [EdgeFunction; 3] {
        [self.edge(0), self.edge(1), self.edge(2)]
    }

    #[cfg(test)]
    /// Whether the centre of pixel `(i, j)` is covered under the top-left rule.
    pub(crate) fn covers(&self, i: i32, j: i32) -> bool {
        self.edges()
            .iter()
            .all(|e| e.value_at(i64::from(i), i64::from(j)) >= 0)
    }

    #[cfg(test)]
    /// The inclusive pixel bounding box `(i_min, j_min, i_max, j_max)` of all pixel centres that lie
    /// within the triangle's bounding box (possibly empty: `i_min > i_max`).
    pub(crate) fn pixel_bounds(&self) -> (i64, i64, i64, i64) {
        let xs = self.oriented.map(|v| i64::from(v.0));
        let ys = self.oriented.map(|v| i64::from(v.1));
        let lo = |v: [i64; 3]| {
            (v[0].min(v[1]).min(v[2]) - HALF_PIXEL + (1 << SUBPIXEL_BITS) - 1) >> SUBPIXEL_BITS
        };
        let hi = |v: [i64; 3]| (v[0].max(v[1]).max(v[2]) - HALF_PIXEL) >> SUBPIXEL_BITS;
        (lo(xs), lo(ys), hi(xs), hi(ys))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup(v: [(i32, i32); 3]) -> Option<TriangleSetup> {
        TriangleSetup::new(v.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y))))
    }

    #[test]
    fn top_left_rule_on_axis_aligned_square_halves() {
        // A 2×2-pixel square split along its diagonal, corners on pixel corners (0,0)-(512,512):
        // every centre of the four pixels is strictly inside one half except (0,0) and (1,1),
        // which lie exactly on the diagonal and must go to exactly one of the halves.
        let upper = setup([(0, 0), (512, 0), (512, 512)]).unwrap();
        let lower = setup([(0, 0), (512, 512), (0, 512)]).unwrap();
        for (i, j) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            assert_eq!(
                u8::from(upper.covers(i, j)) + u8::from(lower.covers(i, j)),
                1,
                "pixel ({i},{j})"
            );
        }
        // The upper half's interior lies to the right of the diagonal: it is that half's left edge,
        // so the upper half owns both centres on it.
        assert!(upper.covers(0, 0) && upper.covers(1, 1));
    }

    #[test]
    fn top_edge_includes_bottom_edge_excludes() {
        // Horizontal edge through pixel centres y = 128: rectangle rows.
        // Triangle with top edge on y=128 (third vertex below) covers centres on that edge.
        let t = setup([(0, 128), (2048, 128), (0, 2048)]).unwrap();
        assert!(t.covers(1, 0));
        // Triangle with its bottom edge on y = 128 + 256 (third vertex above) excludes them.
        let b = setup([(0, 0), (2048, 384), (0, 384)]).unwrap();
        assert!(!b.covers(0, 1));
        assert!(b.covers(0, 0));
    }

    #[test]
    fn winding_does_not_matter_and_degenerate_is_none() {
        let a = setup([(10, 20), (3000, 700), (900, 2500)]).unwrap();
        let b = setup([(10, 20), (900, 2500), (3000, 700)]).unwrap();
        for j in -2..12 {
            for i in -2..14 {
                assert_eq!(a.covers(i, j), b.covers(i, j));
            }
        }
        assert!(setup([(0, 0), (256, 256), (-512, -512)]).is_none());
        assert!(setup([(5, 5), (5, 5), (9, 1)]).is_none());
    }

    #[test]
    fn narrow_and_wide_setups_agree_at_the_limit() {
        // Just inside the i64 limit, queried at the corners of the bounding box (where the walk
        // evaluates); debug builds (overflow checks on) would panic if the i64 bound were wrong.
        let l = (NARROW_LIMIT - 1) as i32;
        for v in [[(-l, -l), (l, -l), (-l, l)], [(l, l), (-l, 3), (5, -l)]] {
            let narrow = setup(v).unwrap();
            assert!(narrow.narrow);
            // The i64 setup equals the i128 formula.
            let area2 = |p: [(i32, i32); 3]| {
                let d =
                    |k: usize, m: usize| (i128::from(p[k].0 - p[m].0), i128::from(p[k].1 - p[m].1));
                let ((x1, y1), (x2, y2)) = (d(1, 0), d(2, 0));
                (x1 * y2 - x2 * y1).abs()
            };
            assert_eq!(narrow.area2, area2(v));
            let (i0, j0, i1, j1) = narrow.pixel_bounds();
            for (i, j) in [(i0, j0), (i1, j0), (i0, j1), (i1, j1), (0, 0)] {
                for e in &narrow.edges() {
                    assert_eq!(e.exact_at(i, j, true), e.exact_at(i, j, false));
                }
            }
        }
        assert!(!setup([(1 << 29, 0), (0, 5), (7, 7)]).unwrap().narrow);
    }

    #[test]
    fn extreme_coordinates_do_not_overflow() {
        let m = i32::MIN;
        let x = i32::MAX;
        // Hypotenuse x + y = -1 (sub-pixel units): pixel (-1, 0) (centre sum 0) is outside, (-2, 0) inside.
        let t = setup([(m, m), (x, m), (m, x)]).unwrap();
        assert!(!t.covers(-1, 0));
        assert!(t.covers(-2, 0));
        assert!(t.covers(-8_000_000, 8_000_000 - 1000));
        let (i0, j0, i1, j1) = t.pixel_bounds();
        assert!(i0 <= -8_388_607 && i1 >= 8_388_606 && j0 <= -8_388_607 && j1 >= 8_388_606);
    }
}
