//! An independent `f64` reference rasterizer, for tests and tools on the host.
//!
//! Only compiled with the `reference` feature (which implies `std`). It shares no code with the
//! integer core: it is written from the coverage rules alone, so the test suites can compare the
//! core against it.
//!
//! # Conventions
//!
//! * Vertices are **raw sub-pixel coordinates** as `i32` (what [`Coord::to_bits`] returns: 256 units
//!   per pixel). Every `i32`, including `i32::MIN` and `i32::MAX`, is a valid input.
//! * Pixel `(i, j)` (any `i32`s) is sampled at its centre, `(256·i + 128, 256·j + 128)` in
//!   sub-pixel units; `y` grows downward.
//! * Coverage follows the Direct3D top-left rule: a centre strictly inside the triangle is covered;
//!   a centre exactly on an edge is covered only if that edge is a *top* edge (horizontal, third
//!   vertex below it) or a *left* edge (not horizontal, interior to its right, i.e. towards `+x`).
//!   Both windings cover the same pixels; zero-area triangles cover nothing.
//!
//! # Exactness
//!
//! All coordinates and their differences are integers below 2⁵³, so they are exact in `f64`. The
//! edge function `(b−a) × (p−a)` is evaluated with a floating-point filter and, when the filter is
//! inconclusive, exactly as a floating-point *expansion* (Shewchuk's error-free transformations:
//! two-product via [`f64::mul_add`], two-sum, expansion growth). Its sign — and therefore the
//! coverage — is exact for every input. Interpolated values are computed from the exact
//! expansions and rounded only at the final division, so they are accurate to a few ulps.
//!
//! # Example
//!
//! ```
//! use embedded_raster::reference;
//!
//! // Vertices on pixel corners (0, 0), (4, 0), (0, 4), in raw sub-pixel units.
//! let v = [(0, 0), (4 * 256, 0), (0, 4 * 256)];
//! assert!(reference::covers(v, 0, 0));
//! // The centre of pixel (1, 2) is (1.5, 2.5): on the hypotenuse, a right edge.
//! assert!(!reference::covers(v, 1, 2));
//!
//! // Pixel centres with i + j < 3 are strictly inside: 6 of them.
//! let mut n = 0;
//! reference::for_each_covered(v, 0, 0, 8, 8, |_x, _y| n += 1);
//! assert_eq!(n, 6);
//!
//! // A channel that is 0, 4 and 0 at the vertices equals the x coordinate in pixels.
//! let channels = [[0.0; 3], [4.0, 0.0, 0.0], [0.0; 3]];
//! assert_eq!(reference::interpolate(v, channels, 1, 0).unwrap()[0], 1.5);
//! ```
//!
//! [`Coord::to_bits`]: crate::Coord

use core::cmp::Ordering;

mod area;
pub mod gradient;
pub mod lights;
pub mod texture;

pub use area::pixel_area;

/// Sub-pixel units per pixel.
const ONE: i64 = 256;
/// Offset of a pixel centre from its corner, in sub-pixel units.
const HALF: i64 = 128;

// ---------------------------------------------------------------------------------------------
// Error-free transformations and expansions
// ---------------------------------------------------------------------------------------------

/// `a + b = s + e` exactly (Knuth's two-sum; no precondition on magnitudes).
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) + (b - bv))
}

/// `a · b = p + e` exactly (the fused multiply-add computes the rounding error of the product).
#[inline]
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// Room for the largest expansion built here: a 4-term edge function scaled by a double (8 terms),
/// three of them summed (24 terms).
const CAP: usize = 32;

/// A nonoverlapping floating-point expansion: the exact value is the sum of `c[..len]`, stored in
/// increasing order of magnitude without zeros. Its sign is the sign of the last component.
#[derive(Clone, Copy)]
struct Expansion {
    len: usize,
    c: [f64; CAP],
}

impl Expansion {
    const ZERO: Expansion = Expansion {
        len: 0,
        c: [0.0; CAP],
    };

    fn push(&mut self, x: f64) {
        if x != 0.0 {
            assert!(self.len < CAP, "expansion capacity exceeded");
            self.c[self.len] = x;
            self.len += 1;
        }
    }

    /// Adds `b` exactly (Shewchuk's GROW-EXPANSION with zero elimination).
    fn grow(&mut self, b: f64) {
        let mut q = b;
        let mut k = 0;
        for i in 0..self.len {
            let (s, h) = two_sum(q, self.c[i]);
            q = s;
            if h != 0.0 {
                self.c[k] = h;
                k += 1;
            }
        }
        self.len = k;
        self.push(q);
    }

    /// Adds another expansion exactly.
    fn add(&mut self, other: &Expansion) {
        for &x in &other.c[..other.len] {
            self.grow(x);
        }
    }

    /// `self · b` exactly (Shewchuk's SCALE-EXPANSION with zero elimination).
    fn scale(&self, b: f64) -> Expansion {
        let mut out = Expansion::ZERO;
        if self.len == 0 || b == 0.0 {
            return out;
        }
        let (mut q, h) = two_product(self.c[0], b);
        out.push(h);
        for &e in &self.c[1..self.len] {
            let (p1, p0) = two_product(e, b);
            let (sum, h) = two_sum(q, p0);
            out.push(h);
            let (s, h) = two_sum(p1, sum);
            out.push(h);
            q = s;
        }
        out.push(q);
        out
    }

    /// The exact sign.
    fn sign(&self) -> Ordering {
        match self.len {
            0 => Ordering::Equal,
            n => self.c[n - 1].partial_cmp(&0.0).unwrap_or(Ordering::Equal),
        }
    }

    /// The value rounded to `f64` (summed from the smallest component up: a few ulps at most).
    fn estimate(&self) -> f64 {
        self.c[..self.len].iter().sum()
    }
}

// ---------------------------------------------------------------------------------------------
// Edge functions
// ---------------------------------------------------------------------------------------------

/// A point with integer coordinates held exactly in `f64`.
type P = (f64, f64);

/// `ε = 2⁻⁵³`, the unit roundoff of `f64`.
const EPS: f64 = f64::EPSILON / 2.0;
/// Error bound of the filtered edge function relative to `|l| + |r|` (Shewchuk's `ccwerrboundA`,
/// which even allows for rounded differences; ours are exact).
const FILTER: f64 = (3.0 + 16.0 * EPS) * EPS;

/// The edge function `(b − a) × (p − a) = (bx−ax)(py−ay) − (by−ay)(px−ax)` as an exact expansion.
/// All coordinates must be integers whose pairwise differences are below 2⁵³ in magnitude.
fn edge_exact(a: P, b: P, p: P) -> Expansion {
    let (l, le) = two_product(b.0 - a.0, p.1 - a.1);
    let (r, re) = two_product(b.1 - a.1, p.0 - a.0);
    let mut e = Expansion::ZERO;
    e.grow(le);
    e.grow(l);
    e.grow(-re);
    e.grow(-r);
    e
}

/// The exact sign of [`edge_exact`]: a floating-point filter first, the exact expansion when the
/// filter cannot decide.
///
/// With `y` downward, `Greater` means `p` lies clockwise of `a → b` on screen.
fn orient(a: P, b: P, p: P) -> Ordering {
    let l = (b.0 - a.0) * (p.1 - a.1);
    let r = (b.1 - a.1) * (p.0 - a.0);
    let det = l - r;
    let bound = FILTER * (l.abs() + r.abs());
    if det > bound {
        Ordering::Greater
    } else if -det > bound {
        Ordering::Less
    } else {
        edge_exact(a, b, p).sign()
    }
}

fn vertex(v: (i32, i32)) -> P {
    (f64::from(v.0), f64::from(v.1))
}

/// The centre of pixel `(px, py)` in sub-pixel units (exact: below 2⁴⁰ in magnitude).
fn centre(px: i32, py: i32) -> P {
    (
        (ONE * i64::from(px) + HALF) as f64,
        (ONE * i64::from(py) + HALF) as f64,
    )
}

/// A non-degenerate triangle prepared for coverage tests.
#[derive(Clone, Copy)]
struct Setup {
    /// The vertices, reordered if needed so that every edge `v[k] → v[k+1]` has the third vertex
    /// on its `Greater` side.
    v: [P; 3],
    /// Whether a centre exactly on edge `v[k] → v[k+1]` is covered (top or left edge).
    inclusive: [bool; 3],
}

impl Setup {
    fn new(raw: [(i32, i32); 3]) -> Option<Setup> {
        let mut v = raw.map(vertex);
        match orient(v[0], v[1], v[2]) {
            Ordering::Equal => return None,
            Ordering::Less => v.swap(1, 2),
            Ordering::Greater => {}
        }
        let inclusive = core::array::from_fn(|k| {
            let (a, b, c) = (v[k], v[(k + 1) % 3], v[(k + 2) % 3]);
            if a.1 == b.1 {
                // Horizontal: a top edge if the third vertex is below it (larger y).
                c.1 > a.1
            } else {
                // A left edge if the interior (the third vertex) is towards +x of the edge line.
                // Take the edge downward (u above w): for w.y > u.y,
                //   c.x − x_line(c.y) = −(w − u) × (c − u) / (w.y − u.y),
                // so c is to the right exactly when the edge function is negative.
                let (u, w) = if a.1 < b.1 { (a, b) } else { (b, a) };
                orient(u, w, c) == Ordering::Less
            }
        });
        Some(Setup { v, inclusive })
    }

    fn covers_point(&self, p: P) -> bool {
        (0..3).all(|k| match orient(self.v[k], self.v[(k + 1) % 3], p) {
            Ordering::Greater => true,
            Ordering::Equal => self.inclusive[k],
            Ordering::Less => false,
        })
    }
}

// ---------------------------------------------------------------------------------------------
// Public API
// ---------------------------------------------------------------------------------------------

/// Whether the centre of pixel `(px, py)` is covered by the triangle `v` (raw sub-pixel vertex
/// coordinates, either winding) under the top-left rule. Exact for every input; `false` for
/// zero-area triangles.
pub fn covers(v: [(i32, i32); 3], px: i32, py: i32) -> bool {
    Setup::new(v).is_some_and(|s| s.covers_point(centre(px, py)))
}

/// Exact edge-function expansions of the centre of pixel `(px, py)` against the edges opposite
/// each vertex, and twice the signed area, or `None` for a zero-area triangle.
fn weights_exact(v: [(i32, i32); 3], px: i32, py: i32) -> Option<([Expansion; 3], Expansion)> {
    let q = v.map(vertex);
    let area = edge_exact(q[0], q[1], q[2]);
    if area.sign() == Ordering::Equal {
        return None;
    }
    let p = centre(px, py);
    let e = core::array::from_fn(|k| edge_exact(q[(k + 1) % 3], q[(k + 2) % 3], p));
    Some((e, area))
}

/// The barycentric weights of the centre of pixel `(px, py)` with respect to the vertices of `v`
/// (weight `k` belongs to vertex `k`), or `None` for a zero-area triangle.
///
/// The weights sum to 1 up to rounding and are each within a few ulps of the exact value. They
/// are defined for every pixel: outside the triangle some are negative.
pub fn barycentric(v: [(i32, i32); 3], px: i32, py: i32) -> Option<[f64; 3]> {
    let (e, area) = weights_exact(v, px, py)?;
    let a = area.estimate();
    Some(e.map(|e| e.estimate() / a))
}

/// Barycentric interpolation of up to three channels at the centre of pixel `(px, py)`:
/// `channels[k]` holds the channel values at vertex `k`; the result holds the interpolated value
/// of each channel. `None` for a zero-area triangle.
///
/// The weighted sum is formed exactly and rounded once, then divided by the (rounded) area: the
/// result is within a few ulps of the exact value, for any vertex coordinates (channel values
/// must be finite and not so large or small that their products with ~2⁷³ overflow or
/// underflow). Pixels outside the triangle are extrapolated.
pub fn interpolate(
    v: [(i32, i32); 3],
    channels: [[f64; 3]; 3],
    px: i32,
    py: i32,
) -> Option<[f64; 3]> {
    let (e, area) = weights_exact(v, px, py)?;
    let a = area.estimate();
    Some(core::array::from_fn(|ch| {
        let mut sum = Expansion::ZERO;
        for (k, ek) in e.iter().enumerate() {
            sum.add(&ek.scale(channels[k][ch]));
        }
        sum.estimate() / a
    }))
}

/// The range of pixel indices whose centres lie in `[lo, hi]` (raw sub-pixel units), clamped to
/// `[c0, c1)`. Computed in `i64`; may be empty (`start > end`).
fn centre_range(lo: i64, hi: i64, c0: i32, c1: i32) -> (i64, i64) {
    // Smallest i with 256 i + 128 >= lo, largest i with 256 i + 128 <= hi.
    let first = -(-(lo - HALF)).div_euclid(ONE);
    let last = (hi - HALF).div_euclid(ONE);
    (first.max(i64::from(c0)), last.min(i64::from(c1) - 1))
}

/// Calls `f(x, y)` for every pixel covered by the triangle `v` inside the clip rectangle
/// `[clip_x0, clip_x1) × [clip_y0, clip_y1)` (exclusive upper bounds), row by row, top to bottom
/// and left to right.
///
/// Only the intersection of the clip with the triangle's pixel bounding box is visited, so huge
/// triangles cost no more than the clip area; each visited pixel is tested with [`covers`]'s
/// exact rule.
pub fn for_each_covered(
    v: [(i32, i32); 3],
    clip_x0: i32,
    clip_y0: i32,
    clip_x1: i32,
    clip_y1: i32,
    mut f: impl FnMut(i32, i32),
) {
    let Some(setup) = Setup::new(v) else {
        return;
    };
    let xs = v.map(|p| i64::from(p.0));
    let ys = v.map(|p| i64::from(p.1));
    let (x0, x1) = centre_range(
        xs.iter().copied().min().unwrap_or(0),
        xs.iter().copied().max().unwrap_or(0),
        clip_x0,
        clip_x1,
    );
    let (y0, y1) = centre_range(
        ys.iter().copied().min().unwrap_or(0),
        ys.iter().copied().max().unwrap_or(0),
        clip_y0,
        clip_y1,
    );
    for y in y0..=y1 {
        for x in x0..=x1 {
            // Both lie inside the clip, so they fit an i32.
            let (x, y) = (x as i32, y as i32);
            if setup.covers_point(centre(x, y)) {
                f(x, y);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    const MIN: i32 = i32::MIN;
    const MAX: i32 = i32::MAX;

    /// Pixel-centre coordinates of pixel `i`, raw.
    fn c(i: i32) -> i32 {
        256 * i + 128
    }

    fn covered(v: [(i32, i32); 3], x0: i32, y0: i32, x1: i32, y1: i32) -> Vec<(i32, i32)> {
        let mut out = Vec::new();
        for_each_covered(v, x0, y0, x1, y1, |x, y| out.push((x, y)));
        out
    }

    fn brute(v: [(i32, i32); 3], x0: i32, y0: i32, x1: i32, y1: i32) -> Vec<(i32, i32)> {
        let mut out = Vec::new();
        for y in y0..y1 {
            for x in x0..x1 {
                if covers(v, x, y) {
                    out.push((x, y));
                }
            }
        }
        out
    }

    fn all_windings(v: [(i32, i32); 3]) -> [[(i32, i32); 3]; 6] {
        let [a, b, c] = v;
        [
            [a, b, c],
            [b, c, a],
            [c, a, b],
            [a, c, b],
            [c, b, a],
            [b, a, c],
        ]
    }

    #[test]
    fn two_product_and_two_sum_are_exact() {
        // (2^32 + 1)^2 = 2^64 + 2^33 + 1: the rounded product drops the final 1.
        let x = 4_294_967_297.0;
        assert_eq!(two_product(x, x), (18_446_744_082_299_486_208.0, 1.0));
        // 2^53 + 1 is not representable: the error term carries the 1.
        assert_eq!(
            two_sum(9_007_199_254_740_992.0, 1.0),
            (9_007_199_254_740_992.0, 1.0)
        );
    }

    #[test]
    fn predicate_exact_where_naive_f64_fails() {
        // a = 0, b = (2^32 - 1, 2^32), p = (2^32, 2^32 + 1):
        // edge = (2^32 - 1)(2^32 + 1) - 2^32 · 2^32 = (2^64 - 1) - 2^64 = -1.
        let a = (0.0, 0.0);
        let b = (4_294_967_295.0, 4_294_967_296.0);
        let p = (4_294_967_296.0, 4_294_967_297.0);
        // The plain f64 evaluation rounds 2^64 - 1 to 2^64 and sees 0.
        assert_eq!((b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0), 0.0);
        assert_eq!(orient(a, b, p), Ordering::Less);
        assert_eq!(orient(b, a, p), Ordering::Greater);
        assert_eq!(orient(a, p, b), Ordering::Greater);
        assert_eq!(edge_exact(a, b, p).estimate(), -1.0);
        // Collinear: (k, k) for k = 2^32 - 1, 2^33 + 1 — products 2^64-ish, exact zero.
        let q = (4_294_967_295.0, 4_294_967_295.0);
        let r = (8_589_934_593.0, 8_589_934_593.0);
        assert_eq!(orient(a, q, r), Ordering::Equal);
        assert_eq!(orient(q, r, a), Ordering::Equal);
    }

    #[test]
    fn expansion_scale_and_sum() {
        // (2^64 - 1) represented as [-1, 2^64]; times 3 = 3·2^64 - 3; minus 3·2^64 = -3.
        let mut e = Expansion::ZERO;
        e.grow(-1.0);
        e.grow(18_446_744_073_709_551_616.0);
        let mut s = e.scale(3.0);
        s.grow(-55_340_232_221_128_654_848.0);
        assert_eq!(s.estimate(), -3.0);
        assert_eq!(s.sign(), Ordering::Less);
    }

    #[test]
    fn corner_triangle_hypotenuse_is_a_right_edge() {
        // Corners (0,0), (4,0), (0,4): centres (i+.5, j+.5) strictly inside iff i + j < 3;
        // those with i + j = 3 lie on the hypotenuse (interior to its left: a right edge).
        let v = [(0, 0), (1024, 0), (0, 1024)];
        let expected: Vec<(i32, i32)> = (0..3)
            .flat_map(|y| (0..3 - y).map(move |x| (x, y)))
            .collect();
        assert_eq!(expected.len(), 6);
        for w in all_windings(v) {
            assert_eq!(covered(w, -2, -2, 8, 8), expected);
            assert_eq!(brute(w, -2, -2, 8, 8), expected);
        }
    }

    #[test]
    fn top_and_left_edges_through_centres_are_covered() {
        // Vertices on the centres of pixels (0,0), (4,0), (0,4). The top edge (row 0) and the left
        // edge (column 0) are inclusive; the hypotenuse i + j = 4 is a right edge.
        let v = [(c(0), c(0)), (c(4), c(0)), (c(0), c(4))];
        let expected: Vec<(i32, i32)> = (0..4)
            .flat_map(|y| (0..4 - y).map(move |x| (x, y)))
            .collect();
        assert_eq!(expected.len(), 10);
        for w in all_windings(v) {
            assert_eq!(covered(w, -3, -3, 9, 9), expected);
        }
    }

    #[test]
    fn bottom_and_right_edges_are_excluded_sloped_left_edge_included() {
        // Vertices on the centres of (0,4), (4,4), (4,0): the bottom edge (row 4) and right edge
        // (column 4) are excluded; the hypotenuse i + j = 4 has the interior to its right (+x):
        // a left edge, included. Covered: i, j ≤ 3 and i + j ≥ 4.
        let v = [(c(0), c(4)), (c(4), c(4)), (c(4), c(0))];
        let expected = [(3, 1), (2, 2), (3, 2), (1, 3), (2, 3), (3, 3)];
        for w in all_windings(v) {
            assert_eq!(covered(w, -3, -3, 9, 9), expected);
        }
        // Together with the previous triangle this tiles the square of centres (0,0)–(4,4): the
        // shared hypotenuse is drawn once, and the square covers i, j in 0..4.
        let other = [(c(0), c(0)), (c(4), c(0)), (c(0), c(4))];
        for y in -2..7 {
            for x in -2..7 {
                let n = usize::from(covers(v, x, y)) + usize::from(covers(other, x, y));
                let inside = (0..4).contains(&x) && (0..4).contains(&y);
                assert_eq!(n, usize::from(inside), "pixel ({x}, {y})");
            }
        }
    }

    #[test]
    fn vertex_on_a_centre() {
        // A triangle pointing down with its apex exactly on the centre of pixel (2, 2):
        // (0,0)..(4,0) corners on top, apex at (2.5, 2.5). The apex lies on a left edge
        // (from the apex up to (0,0)) and a right edge (up to (4,0)): not covered.
        let v = [(0, 0), (1024, 0), (c(2), c(2))];
        for w in all_windings(v) {
            assert!(!covers(w, 2, 2));
            // (2.5, 1.5) is inside: below the top edge, between the two slanted edges.
            assert!(covers(w, 2, 1));
        }
        // Apex pointing up instead, at the centre of (2, 0), base on the corner line y = 3: the apex
        // lies on a left edge (from the apex down-left) and a right edge: not covered.
        let v = [(c(2), c(0)), (1024 + 256, 768), (0, 768)];
        for w in all_windings(v) {
            assert!(!covers(w, 2, 0));
            assert!(covers(w, 2, 1));
        }
        // A vertex on a centre where a top edge meets a left edge is covered.
        let v = [(c(1), c(1)), (c(5), c(1)), (c(1), c(3))];
        for w in all_windings(v) {
            assert!(covers(w, 1, 1));
            assert!(!covers(w, 0, 1));
            assert!(!covers(w, 1, 0));
        }
    }

    #[test]
    fn vertical_edges_left_and_right() {
        // The rectangle of centres x in [c(1), c(3)], y in [c(0), c(2)] split along a diagonal.
        // Left column x = 1 is a left edge, right column x = 3 a right edge.
        let upper = [(c(1), c(0)), (c(3), c(0)), (c(3), c(2))];
        let lower = [(c(1), c(0)), (c(3), c(2)), (c(1), c(2))];
        for (u, l) in all_windings(upper).into_iter().zip(all_windings(lower)) {
            for y in -1..4 {
                for x in -1..5 {
                    let n = usize::from(covers(u, x, y)) + usize::from(covers(l, x, y));
                    let inside = (1..3).contains(&x) && (0..2).contains(&y);
                    assert_eq!(n, usize::from(inside), "pixel ({x}, {y})");
                }
            }
            // The diagonal from (1,0) to (3,2) passes through the centres (1,0), (2,1), (3,2):
            // for the upper triangle the interior lies to its right (+x): a left edge, so (2,1)
            // belongs to the upper triangle.
            assert!(covers(u, 2, 1));
            assert!(!covers(l, 2, 1));
        }
    }

    #[test]
    fn degenerate_triangles_cover_nothing() {
        let cases = [
            [(0, 0), (512, 512), (1024, 1024)],
            [(100, 100), (100, 100), (100, 100)],
            [(0, 0), (0, 0), (1024, 5)],
            [(MIN, MIN), (0, 0), (MAX, MAX)],
            [(MIN, 7), (MAX, 7), (0, 7)],
            [(MIN, MIN), (MAX, MIN), (MAX, MIN)],
            // On the line y = 2x + 1 with huge coordinates.
            [
                (-1_000_000_000, -1_999_999_999),
                (3, 7),
                (1_000_000_000, 2_000_000_001),
            ],
        ];
        for v in cases {
            for w in all_windings(v) {
                assert!(covered(w, -5, -5, 10, 10).is_empty());
                assert!(barycentric(w, 0, 0).is_none());
                assert!(interpolate(w, [[1.0; 3]; 3], 0, 0).is_none());
                assert!(!covers(w, 0, 0));
            }
        }
    }

    #[test]
    fn extreme_diagonal_edge() {
        // Edge from (MIN, MIN) to (MAX, MAX): the line y = x, through every centre (i, i) with
        // |256 i + 128| < 2^31.
        // Third vertex (MIN, MAX): interior where x < y, to the left of the edge: a right edge.
        let left_of = [(MIN, MIN), (MAX, MAX), (MIN, MAX)];
        // Third vertex (MAX, MIN): interior where x > y, to the right: a left edge.
        let right_of = [(MIN, MIN), (MAX, MAX), (MAX, MIN)];
        for i in [-8_000_000, -3, 0, 1, 5, 8_000_000] {
            for (a, b) in all_windings(left_of)
                .into_iter()
                .zip(all_windings(right_of))
            {
                assert!(!covers(a, i, i));
                assert!(covers(a, i - 1, i));
                assert!(!covers(a, i + 1, i));
                assert!(covers(b, i, i));
                assert!(covers(b, i + 1, i));
                assert!(!covers(b, i - 1, i));
            }
        }
        // Centres beyond the vertex range are outside both.
        assert!(!covers(left_of, MIN, MIN));
        assert!(!covers(right_of, MAX, MAX));
    }

    #[test]
    fn huge_triangle_clips_to_small_region() {
        // Base on y = MIN from x = MIN to MAX, apex (0, MAX): near the origin its slanted edges
        // are about 2^30 sub-pixels away, so it covers the whole 20 × 20 clip.
        let v = [(MIN, MIN), (MAX, MIN), (0, MAX)];
        assert_eq!(covered(v, -10, -10, 10, 10).len(), 400);
        // The corner triangle x >= MIN, y >= MIN, x + y < -1 (hypotenuse from (MAX, MIN) to
        // (MIN, MAX)). Clips at the ends of the i32 pixel range are fine.
        let v = [(MIN, MIN), (MAX, MIN), (MIN, MAX)];
        assert!(
            covered(v, MIN, MIN, MIN + 3, MIN + 2).is_empty(),
            "centres at -2^39"
        );
        // Pixel -2^23 has its centre at MIN + 128: inside, as are its neighbours: 3 × 2 pixels.
        let got = covered(v, -8_388_608, -8_388_608, -8_388_605, -8_388_606);
        assert_eq!(got.len(), 6);
        // Pixel -2^23 - 1 has its centre at MIN - 128: outside.
        assert!(!covers(v, -8_388_609, -8_388_608));
        assert!(!covers(v, -8_388_608, -8_388_609));
    }

    #[test]
    fn barycentric_and_interpolation() {
        // Right triangle with legs of 4 px from corner (0,0): at the centre of (1, 2) = (1.5, 2.5)
        // the weights are (1 - 1.5/4 - 2.5/4, 1.5/4, 2.5/4) = (0, 0.375, 0.625).
        let v = [(0, 0), (1024, 0), (0, 1024)];
        assert_eq!(barycentric(v, 1, 2), Some([0.0, 0.375, 0.625]));
        let w = [v[2], v[0], v[1]];
        assert_eq!(barycentric(w, 1, 2), Some([0.625, 0.0, 0.375]));
        let ch = [[10.0, 0.0, 255.0], [20.0, 8.0, 255.0], [50.0, 16.0, 0.0]];
        // 10·0 + 20·0.375 + 50·0.625 = 38.75; 8·0.375 + 16·0.625 = 13; 255·0.375 = 95.625.
        assert_eq!(interpolate(v, ch, 1, 2), Some([38.75, 13.0, 95.625]));
        // Extrapolation outside: at (5.5, 0.5) the weights are (-0.5, 1.375, 0.125).
        assert_eq!(barycentric(v, 5, 0), Some([-0.5, 1.375, 0.125]));
    }

    #[test]
    fn huge_triangle_interpolation_is_accurate() {
        // Vertices at the ends of the range, channel = x in pixels (a linear function is
        // reproduced exactly by barycentric interpolation).
        let v = [(MIN, MIN), (MAX, 5), (-12_345, MAX)];
        let ch = v.map(|(x, _)| [f64::from(x) / 256.0, 1.0, 0.0]);
        for (px, py) in [(0, 0), (3, -7), (1000, 200), (-4_000_000, -2_000_000)] {
            let got = interpolate(v, ch, px, py).unwrap();
            let exact = f64::from(px) + 0.5;
            assert!(
                (got[0] - exact).abs() <= 1e-9 * exact.abs().max(1.0),
                "{got:?}"
            );
            assert!((got[1] - 1.0).abs() <= 1e-15);
            assert_eq!(got[2], 0.0);
        }
    }

    /// Exact i128 evaluation of the edge function, an oracle independent of the expansions.
    fn edge_i128(a: (i64, i64), b: (i64, i64), p: (i64, i64)) -> i128 {
        i128::from(b.0 - a.0) * i128::from(p.1 - a.1)
            - i128::from(b.1 - a.1) * i128::from(p.0 - a.0)
    }

    #[test]
    fn predicate_matches_integer_oracle() {
        let mut s = 0x1234_5678_9abc_def1_u64;
        let mut rnd = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        for i in 0..200_000 {
            // Mix huge values with small offsets so that near-collinear cases occur.
            let base = (rnd() as i32, rnd() as i32);
            let d = |r: u64, shift: u32| ((r as i64) >> shift) as i32;
            let shift = 32 + (i % 32) as u32;
            let a = base;
            let b = (
                base.0.wrapping_add(d(rnd(), shift)),
                base.1.wrapping_add(d(rnd(), shift)),
            );
            let (px, py) = (rnd() as i32 >> (i % 24), rnd() as i32 >> (i % 24));
            let p = (ONE * i64::from(px) + HALF, ONE * i64::from(py) + HALF);
            let a64 = (i64::from(a.0), i64::from(a.1));
            let b64 = (i64::from(b.0), i64::from(b.1));
            let want = edge_i128(a64, b64, p).cmp(&0);
            assert_eq!(orient(vertex(a), vertex(b), centre(px, py)), want);
            // Exactly collinear third points: p = a + k (b - a).
            let k = (rnd() % 5) as i64 - 2;
            let q = (a64.0 + k * (b64.0 - a64.0), a64.1 + k * (b64.1 - a64.1));
            let qf = (q.0 as f64, q.1 as f64);
            assert_eq!(orient(vertex(a), vertex(b), qf), Ordering::Equal);
            assert_eq!(edge_exact(vertex(a), vertex(b), qf).sign(), Ordering::Equal);
            // One sub-pixel unit off the line: the filter cannot decide, the expansion must.
            let r = (q.0 + (rnd() % 3) as i64 - 1, q.1 + (rnd() % 3) as i64 - 1);
            let rf = (r.0 as f64, r.1 as f64);
            assert_eq!(
                orient(vertex(a), vertex(b), rf),
                edge_i128(a64, b64, r).cmp(&0)
            );
        }
    }
}
