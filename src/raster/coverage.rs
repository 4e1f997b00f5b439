//! Anti-aliased coverage: the area of each pixel square inside a triangle, from the exact edge
//! functions.
//!
//! A row's pixels fall in three kinds, each found from the edge functions `E` at pixel centres
//! ([`TriangleSetup`]'s, exact integers): over a square `E` ranges over `E_c ± h` with
//! `h = 128·(|a| + |b|)`, so a square is wholly inside an edge where `E_c ≥ h`, wholly outside
//! where `E_c ≤ −h`, and cut by it in between. [`cover`] hands a [`CoverageSink`] the row's
//! run of squares inside all three edges as one span (the plain fill) and every square cut by an
//! edge and outside none with its area:
//!
//! * cut by one edge: the area of a unit square on one side of a line, in closed form — a
//!   trapezoid `½ + c/max(A, B)` where the line crosses two opposite sides, else a corner
//!   triangle `t²/(2AB)` or its complement;
//! * cut by two or three (near vertices, slivers, sub-pixel triangles): the square clipped by
//!   those edges as a polygon, its area by the shoelace formula.
//!
//! Each edge is normalised once a triangle to a line `A·u + B·v + C` with `|A|, |B| < 2¹²` and
//! `C` in 16 fractional bits of a pixel, so the arithmetic a pixel is 32- and 64-bit; the
//! direction's truncation moves the line by under 2⁻¹¹ px across a square, and coverage is
//! rounded to 2⁻¹⁶: every area within 2⁻⁹ of the exact one (`tests/all/antialias.rs` checks it
//! against the `f64` polygon clip of `reference::pixel_area`).
//!
//! Rows and their runs come from the same conditions solved for the column: a square can be cut
//! only where `E_c > −h` for every edge, and is inside where `E_c ≥ h` for all three.

use embedded_graphics::primitives::Rectangle;

use super::arith::{div_floor_wide, leading_zeros_32, leading_zeros_64, mul_u32_u33};
use super::edge::{owns_centres_on, EdgeFunction, TriangleSetup};
use crate::fixed_point::{Coord, SUBPIXEL_BITS};

/// Coverage of a whole pixel, 16 fractional bits.
pub(crate) const FULL: u32 = 1 << 16;

/// Bits of the normalised edge directions.
const DIRECTION_BITS: u32 = 12;

/// Where anti-aliased coverage goes: runs of wholly covered pixels and partly covered pixels
/// with their area.
pub(crate) trait CoverageSink {
    /// Pixels `x0 .. x1` of row `y`, each wholly inside the triangle.
    fn full(&mut self, y: i32, x0: i32, x1: i32);

    /// Pixel `(x, y)`, `coverage / 2¹⁶` of it inside the triangle (`0 < coverage ≤` [`FULL`]).
    fn partial(&mut self, x: i32, y: i32, coverage: u32);
}

/// An edge normalised for coverage: its line through a square is `a·u + b·v + C ≥ 0` for `u`, `v`
/// in 16 fractional bits of a pixel around the square's centre, where `C` is the exact edge value
/// there scaled by [`Self::scale`].
#[derive(Debug, Clone, Copy)]
struct CoverageEdge {
    edge: EdgeFunction,
    /// A square whose centre's edge value is below `lo` lies wholly outside, one at `hi` or above
    /// wholly inside; in between the edge cuts it. Anti-aliased: `1 − half` and `half`, with
    /// `half = 128·(|a| + |b|)` the most the edge value changes from a centre to a corner.
    /// Aliased (an edge shared with a neighbour): both at the top-left rule's threshold, 0 or 1,
    /// so a square is inside or outside by its centre alone and the edge cuts none.
    lo: i128,
    hi: i128,
    /// Normalised direction: `a`, `b` shifted right by `shift` (magnitudes, toward zero).
    a: i64,
    b: i64,
    /// Right shift of the exact edge values to `C` (negative: a left shift).
    shift: i32,
    /// `⌊(2³² − 1) / max(|a|, |b|)⌋`, and of `|a|` and `|b|` (0 for a zero component): within
    /// 2⁻¹⁹ of `2³²/v` for `v < 2¹²`, by one 32-bit division each.
    recip_max: u64,
    recip_a: u64,
    recip_b: u64,
}

impl CoverageEdge {
    fn new(edge: EdgeFunction, anti_aliased: bool) -> Self {
        let m = edge.a.unsigned_abs().max(edge.b.unsigned_abs());
        let bits = 64 - leading_zeros_64(m.max(1));
        let s = bits.saturating_sub(DIRECTION_BITS);
        let norm = |v: i64| (v.unsigned_abs() >> s) as i64 * v.signum();
        let (a, b) = (norm(edge.a), norm(edge.b));
        let recip = |v: i64| u64::from(u32::MAX.checked_div(v.unsigned_abs() as u32).unwrap_or(0));
        let half = 128 * (i128::from(edge.a.unsigned_abs()) + i128::from(edge.b.unsigned_abs()));
        let centre = i128::from(!owns_centres_on(edge.a, edge.b));
        let (recip_a, recip_b) = (recip(a), recip(b));
        CoverageEdge {
            edge,
            lo: if anti_aliased { 1 - half } else { centre },
            hi: if anti_aliased { half } else { centre },
            a,
            b,
            // E / (256·2^s) in 16 fractional bits: E·2^(8 − s).
            shift: s as i32 - 8,
            // The larger component's: the smaller reciprocal (0 only for a zero component).
            recip_max: match (recip_a, recip_b) {
                (0, r) | (r, 0) => r,
                (ra, rb) => ra.min(rb),
            },
            recip_a,
            recip_b,
        }
    }

    /// `C` of the exact edge value `e` at a centre of a square it cuts (`|e| < half < 2⁴¹`).
    #[inline]
    fn line_offset(&self, e: i64) -> i64 {
        if self.shift >= 0 {
            e >> self.shift
        } else {
            e << -self.shift
        }
    }

    /// The area (16 fractional bits) of the unit square on the inside of this edge alone, its
    /// line at offset `c` from the centre.
    fn area(&self, c: i64) -> u32 {
        let (a, b) = (self.a.abs(), self.b.abs());
        let h = (a + b) << 15;
        if c >= h {
            return FULL;
        }
        if c <= -h {
            return 0;
        }
        let (m, n) = (a.max(b), a.min(b));
        if c.abs() <= (m - n) << 15 {
            // Crosses two opposite sides: ½ + c/m.
            // |c| ≤ m·2¹⁵ < 2²⁷: the product is below 2⁴⁸.
            let part = (mul_u32_u33(c.unsigned_abs() as u32, self.recip_max) >> 32) as u32;
            return if c >= 0 {
                (FULL / 2 + part).min(FULL)
            } else {
                (FULL / 2).saturating_sub(part)
            };
        }
        // Cuts a corner: legs t/a and t/b (0 < t ≤ n·2¹⁶, so both below 2¹⁶ + 1).
        let t = (h - c.abs()) as u32;
        let leg = |recip: u64| (mul_u32_u33(t, recip) >> 32) as u32;
        let legs = mul_u32_u33(leg(self.recip_a), u64::from(leg(self.recip_b)));
        let corner = (legs >> 17).min(u64::from(FULL)) as u32;
        if c >= 0 {
            FULL - corner
        } else {
            corner
        }
    }

    /// This edge's line, `a·u + b·v + c`, at `(u, v)` within the square: `|a|, |b| < 2¹²`,
    /// `|u|, |v| ≤ 2¹⁵` and `|c| < 2²⁸` for an edge that cuts it, so every term fits 32 bits
    /// and the sum is below 2³⁰.
    #[inline]
    fn at(&self, c: i64, (u, v): (i32, i32)) -> i32 {
        (self.a as i32) * u + (self.b as i32) * v + c as i32
    }
}

/// A pixel square as a polygon clipped by up to three lines: at most seven corners.
#[derive(Clone, Copy)]
struct Polygon {
    points: [(i32, i32); 8],
    len: usize,
}

impl Polygon {
    const HALF: i32 = 1 << 15;

    const EMPTY: Polygon = Polygon {
        points: [(0, 0); 8],
        len: 0,
    };

    fn square() -> Self {
        let h = Self::HALF;
        let mut square = Self::EMPTY;
        square.points[..4].copy_from_slice(&[(-h, -h), (h, -h), (h, h), (-h, h)]);
        square.len = 4;
        square
    }

    /// The part where `line ≥ 0`, into `out`. Corners stay within the square (±2¹⁵) and line
    /// values below 2³⁰ in magnitude.
    fn clip_into(&self, out: &mut Polygon, line: impl Fn((i32, i32)) -> i32) {
        out.len = 0;
        let points = self.points.get(..self.len).unwrap_or(&[]);
        let Some(&last) = points.last() else {
            return;
        };
        let (mut p, mut lp) = (last, line(last));
        for &q in points {
            let lq = line(q);
            if (lp >= 0) != (lq >= 0) {
                // lp and lq differ in sign: |lp| < |lp − lq| < 2³¹, the ratio in [0, 1), found to
                // 16 bits from both shifted below 2¹⁵ (one 32-bit division).
                let d = (i64::from(lp) - i64::from(lq)).unsigned_abs() as u32;
                let t = lp.unsigned_abs();
                // 14 bits, so that `(q − p)·ratio` (|q − p| ≤ 2¹⁶) fits 31 bits.
                let shift = (32 - leading_zeros_32(d)).saturating_sub(15);
                let ratio = ((t >> shift) << 14) / (d >> shift).max(1);
                let cut = |p: i32, q: i32| p + (((q - p) * ratio as i32) >> 14);
                out.push((cut(p.0, q.0), cut(p.1, q.1)));
            }
            if lq >= 0 {
                out.push(q);
            }
            (p, lp) = (q, lq);
        }
    }

    #[inline(always)]
    fn push(&mut self, p: (i32, i32)) {
        if let Some(slot) = self.points.get_mut(self.len) {
            *slot = p;
            self.len += 1;
        }
    }

    /// The area in 16 fractional bits of a pixel.
    fn area(&self) -> u32 {
        let points = self.points.get(..self.len).unwrap_or(&[]);
        let Some(&last) = points.last() else {
            return 0;
        };
        let (mut twice, mut p) = (0i64, last);
        for &q in points {
            // Corners within ±2¹⁵: each product fits 31 bits.
            twice += i64::from(p.0 * q.1) - i64::from(q.0 * p.1);
            p = q;
        }
        ((twice.unsigned_abs() + (1 << 16)) >> 17).min(u64::from(FULL)) as u32
    }
}

/// The area inside a triangle of the square of a pixel whose exact edge values at the centre are
/// `e` (`lo` and `hi` each edge's [`CoverageEdge`] thresholds).
#[inline]
fn square_area<T: Wide>(edges: &[CoverageEdge; 3], e: [T; 3], (lo, hi): ([T; 3], [T; 3])) -> u32 {
    let mut cut = [false; 3];
    let mut offsets = [0i64; 3];
    for k in 0..3 {
        if e[k] < lo[k] {
            return 0;
        }
        if e[k] < hi[k] {
            // |e| < half < 2⁴¹: the narrow value is exact.
            cut[k] = true;
            offsets[k] = edges[k].line_offset(e[k].wide() as i64);
        }
    }
    match cut {
        [false, false, false] => FULL,
        [true, false, false] => edges[0].area(offsets[0]),
        [false, true, false] => edges[1].area(offsets[1]),
        [false, false, true] => edges[2].area(offsets[2]),
        _ => {
            // Clipped back and forth between two polygons.
            let mut polygons = [Polygon::square(), Polygon::EMPTY];
            let mut current = false;
            for ((edge, &offset), _) in edges.iter().zip(&offsets).zip(cut).filter(|(_, c)| *c) {
                let [a, b] = &mut polygons;
                let (from, to) = if current { (b, a) } else { (a, b) };
                from.clip_into(to, |p| edge.at(offset, p));
                current = !current;
            }
            let [a, b] = &polygons;
            if current {
                b.area()
            } else {
                a.area()
            }
        }
    }
}

/// The integers edge values are stepped in: `i64` for triangles set up narrow (every value at a
/// pixel centre of the box within 2⁶²), `i128` beyond.
trait Wide:
    Copy
    + Ord
    + core::ops::Add<Output = Self>
    + core::ops::Sub<Output = Self>
    + core::ops::Mul<Output = Self>
    + core::ops::Neg<Output = Self>
{
    const ZERO: Self;
    const ONE: Self;
    /// Whether this is the narrow triangles' type (their exact edge values in `i64`).
    const NARROW: bool;
    /// `v`, which the caller knows to fit.
    fn of(v: i128) -> Self;
    fn wide(self) -> i128;
    /// `(⌊n / d⌋, n mod d)` for `d > 0`.
    fn div_floor(n: Self, d: Self) -> (Self, Self);
}

/// [`Wide`] for the narrow types, whose division is the hardware's (a library call on
/// Cortex-M0 for `i64`).
macro_rules! narrow_wide {
    ($($t:ty),*) => {$(
        impl Wide for $t {
            const ZERO: Self = 0;
            const ONE: Self = 1;
            const NARROW: bool = true;
            #[inline(always)]
            fn of(v: i128) -> Self {
                v as $t
            }
            #[inline(always)]
            fn wide(self) -> i128 {
                i128::from(self)
            }
            #[inline]
            fn div_floor(n: Self, d: Self) -> (Self, Self) {
                let q = n.div_euclid(d.max(1));
                (q, n - q * d)
            }
        }
    )*};
}

narrow_wide!(i32, i64);

impl Wide for i128 {
    const ZERO: Self = 0;
    const ONE: Self = 1;
    const NARROW: bool = false;
    #[inline(always)]
    fn of(v: i128) -> Self {
        v
    }
    #[inline(always)]
    fn wide(self) -> i128 {
        self
    }
    #[inline]
    fn div_floor(n: Self, d: Self) -> (Self, Self) {
        let q = div_floor_wide(n, d.max(1));
        (q, n.wrapping_sub(q.wrapping_mul(d)))
    }
}

/// `⌊N_j / d⌋` of a value stepped by a constant a row (`N_{j+1} = N_j + δ`), exactly: quotient
/// and remainder (`0 ≤ r < d`) carried from row to row, one division at the start.
#[derive(Clone, Copy)]
struct Floor<T> {
    q: T,
    r: T,
    d: T,
    dq: T,
    dr: T,
}

impl<T: Wide> Floor<T> {
    fn new(n: T, delta: T, d: T) -> Self {
        let (q, r) = T::div_floor(n, d);
        let (dq, dr) = T::div_floor(delta, d);
        Floor { q, r, d, dq, dr }
    }

    #[inline(always)]
    fn step(&mut self) {
        self.q = self.q + self.dq;
        self.r = self.r + self.dr;
        if self.r >= self.d {
            self.r = self.r - self.d;
            self.q = self.q + T::ONE;
        }
    }
}

/// One edge's bounds on the columns of a row: where its squares are not wholly outside
/// ("touched": `E ≥ lo`, that is `E > lo − 1`) and where they are wholly inside (`E ≥ hi`), from
/// `Nt = lo − 1 − K` and `Ni = K − hi` for the edge value `K` at column 0 of the row
/// (`E = s·i + K`).
#[derive(Clone, Copy)]
enum Bounds<T> {
    /// `s > 0`: lower bounds `⌊Nt/s⌋ + 1` and `−⌊Ni/s⌋`.
    Left { touched: Floor<T>, inside: Floor<T> },
    /// `s < 0`: upper bounds `−⌊Nt/|s|⌋ − 1` and `⌊Ni/|s|⌋`.
    Right { touched: Floor<T>, inside: Floor<T> },
    /// `s = 0` (a horizontal edge): the whole row, or none of it, by the signs of `Nt` and `Ni`.
    Level { nt: T, ni: T, t: T },
}

impl<T: Wide> Bounds<T> {
    fn new(s: T, t: T, k: T, (lo, hi): (T, T)) -> Self {
        let (nt, ni) = (lo - T::ONE - k, k - hi);
        if s > T::ZERO {
            Bounds::Left {
                touched: Floor::new(nt, -t, s),
                inside: Floor::new(ni, t, s),
            }
        } else if s < T::ZERO {
            Bounds::Right {
                touched: Floor::new(nt, -t, -s),
                inside: Floor::new(ni, t, -s),
            }
        } else {
            Bounds::Level { nt, ni, t }
        }
    }

    /// Narrows `touched` and `inside` (inclusive column ranges) to this edge's on the row.
    #[inline(always)]
    fn narrow(&self, touched: &mut (T, T), inside: &mut (T, T)) {
        match self {
            Bounds::Left {
                touched: t,
                inside: i,
            } => {
                touched.0 = touched.0.max(t.q + T::ONE);
                inside.0 = inside.0.max(-i.q);
            }
            Bounds::Right {
                touched: t,
                inside: i,
            } => {
                touched.1 = touched.1.min(-t.q - T::ONE);
                inside.1 = inside.1.min(i.q);
            }
            Bounds::Level { nt, ni, .. } => {
                if *nt >= T::ZERO {
                    *touched = (T::ONE, T::ZERO);
                }
                if *ni < T::ZERO {
                    *inside = (T::ONE, T::ZERO);
                }
            }
        }
    }

    #[inline(always)]
    fn step(&mut self) {
        match self {
            Bounds::Left { touched, inside } | Bounds::Right { touched, inside } => {
                touched.step();
                inside.step();
            }
            Bounds::Level { nt, ni, t } => {
                *nt = *nt - *t;
                *ni = *ni + *t;
            }
        }
    }
}

/// `[f(a₀, b₀), f(a₁, b₁), f(a₂, b₂)]`: no index a closure would have to check where it is not
/// inlined (size-optimised builds).
#[inline(always)]
fn zip3<A, B, U>(a: [A; 3], b: [B; 3], mut f: impl FnMut(A, B) -> U) -> [U; 3] {
    let ([a0, a1, a2], [b0, b1, b2]) = (a, b);
    [f(a0, b0), f(a1, b1), f(a2, b2)]
}

/// Triangles whose edges are shorter than this on both axes (sub-pixels: 64 px) in a box of at
/// most [`SMALL_BOX`] pixels a side are stepped in `i32`: every edge value at a centre of the box
/// is below `2·2¹⁴·(65·256) < 2³⁰`, a step `256·2¹⁴ = 2²²`, `half` below 2²².
const SMALL_EDGE: u32 = 1 << 14;

/// See [`SMALL_EDGE`].
const SMALL_BOX: i64 = 64;

/// Boxes of at most this many pixels are scanned pixel by pixel (no divisions); larger ones take
/// each row's runs from the edges' [`Bounds`].
const SCAN_LIMIT: i64 = 256;

/// Hands `sink` every pixel of `clip` that the triangle `v` covers in part or whole, row by row
/// top to bottom: the wholly covered run of a row as one span, the others one by one with their
/// area. Edge `i` (from `v[i]` to `v[i + 1]`) is anti-aliased if `anti_aliased[i]`, else it
/// takes or leaves whole squares by their centres under the top-left rule (the aliased fill's
/// pixels along it). Degenerate triangles cover nothing.
pub(crate) fn cover(
    v: [(Coord, Coord); 3],
    anti_aliased: [bool; 3],
    clip: &Rectangle,
    sink: &mut impl CoverageSink,
) {
    let Some(setup) = TriangleSetup::new(v) else {
        return;
    };
    let Some(bottom_right) = clip.bottom_right() else {
        return;
    };
    // The pixels whose squares meet the triangle's bounding box (open), inside the clip.
    let span = |c: [i32; 3], lo: i32, hi: i32| {
        let (min, max) = (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2]));
        (
            (min >> SUBPIXEL_BITS).max(lo),
            ((max - 1) >> SUBPIXEL_BITS).min(hi),
        )
    };
    let (x0, x1) = span(setup.oriented.map(|p| p.0), clip.top_left.x, bottom_right.x);
    let (y0, y1) = span(setup.oriented.map(|p| p.1), clip.top_left.y, bottom_right.y);
    if x0 > x1 || y0 > y1 {
        return;
    }
    // Setup edge k joins oriented vertices k + 1 and k + 2: input vertices `order[..]`, input
    // edge `i` joins input vertices i and i + 1.
    let edges = [0, 1, 2].map(|k| {
        let (i, j) = (setup.order[(k + 1) % 3], setup.order[(k + 2) % 3]);
        let input_edge = if (i + 1) % 3 == j { i } else { j };
        let anti_aliased = anti_aliased.get(input_edge).copied().unwrap_or(true);
        CoverageEdge::new(setup.edge(k), anti_aliased)
    });
    let (w, h) = (
        i64::from(x1) - i64::from(x0) + 1,
        i64::from(y1) - i64::from(y0) + 1,
    );
    let scan = w * h <= SCAN_LIMIT;
    let steepest = setup
        .oriented
        .iter()
        .zip(setup.oriented.iter().cycle().skip(1))
        .map(|(p, q)| (p.0.abs_diff(q.0)).max(p.1.abs_diff(q.1)))
        .max()
        .unwrap_or(u32::MAX);
    if setup.narrow && steepest < SMALL_EDGE && w.max(h) <= SMALL_BOX {
        cover_box::<i32>(&edges, (x0, y0, x1, y1), scan, sink);
    } else if setup.narrow {
        cover_box::<i64>(&edges, (x0, y0, x1, y1), scan, sink);
    } else {
        cover_box::<i128>(&edges, (x0, y0, x1, y1), scan, sink);
    }
}

/// [`cover`] inside the pixel box `(x0, y0, x1, y1)` (inclusive), each pixel tested (`scan`) or
/// each row's runs from the edges' bounds.
fn cover_box<T: Wide>(
    edges: &[CoverageEdge; 3],
    (x0, y0, x1, y1): (i32, i32, i32, i32),
    scan: bool,
    sink: &mut impl CoverageSink,
) {
    let s: [T; 3] = edges.map(|e| T::of(i128::from(e.edge.a) << SUBPIXEL_BITS));
    let t: [T; 3] = edges.map(|e| T::of(i128::from(e.edge.b) << SUBPIXEL_BITS));
    let thresholds: ([T; 3], [T; 3]) = (edges.map(|e| T::of(e.lo)), edges.map(|e| T::of(e.hi)));
    // Columns are counted from the box's first, `x0`: each edge's value there on the first row.
    let mut k: [T; 3] =
        edges.map(|e| T::of(e.edge.exact_at(i64::from(x0), i64::from(y0), T::NARROW)));
    let mut bounds = if scan {
        None
    } else {
        let steps = zip3(s, t, |s, t| (s, t));
        let values = zip3(
            k,
            zip3(thresholds.0, thresholds.1, |lo, hi| (lo, hi)),
            |k, l| (k, l),
        );
        Some(zip3(steps, values, |(s, t), (k, l)| {
            Bounds::new(s, t, k, l)
        }))
    };
    let (lo, hi) = (T::ZERO, T::of(i128::from(x1) - i128::from(x0)));
    for y in y0..=y1 {
        // Scanned rows test every pixel: no run is known inside.
        let (mut touched, mut inside) = ((lo, hi), (T::ONE, T::ZERO));
        if let Some(bounds) = &bounds {
            inside = (lo, hi);
            for b in bounds {
                b.narrow(&mut touched, &mut inside);
            }
        }
        if touched.0 <= touched.1 {
            // Back to frame columns (within the box: no overflow).
            let column = |c: T| x0.wrapping_add(c.wide() as i32);
            let mut e: [T; 3] = zip3(k, s, |k, s| k + s * touched.0);
            let (from, to) = (column(touched.0), column(touched.1));
            let inside = (inside.0 <= inside.1).then(|| (column(inside.0), column(inside.1)));
            cover_row(edges, y, (from, to), inside, &mut e, s, thresholds, sink);
        }
        for n in 0..3 {
            k[n] = k[n] + t[n];
        }
        if let Some(bounds) = &mut bounds {
            for b in bounds {
                b.step();
            }
        }
    }
}

/// The pixels `from ..= to` of row `y`: the run `inside` (if known) as one span, every other
/// pixel tested: wholly inside ones gathered into runs, cut ones with their area. `e` holds the
/// edge values at `from`'s centre and is stepped by `s` a pixel.
#[allow(clippy::too_many_arguments)]
#[inline]
fn cover_row<T: Wide>(
    edges: &[CoverageEdge; 3],
    y: i32,
    (from, to): (i32, i32),
    inside: Option<(i32, i32)>,
    e: &mut [T; 3],
    s: [T; 3],
    thresholds: ([T; 3], [T; 3]),
    sink: &mut impl CoverageSink,
) {
    let mut run: Option<i32> = None;
    let mut x = from;
    while x <= to {
        if let Some((a, b)) = inside.filter(|&(a, _)| a == x) {
            // The known run: skip its pixels' tests.
            let start = run.take().unwrap_or(a);
            sink.full(y, start, b + 1);
            let n = T::of(i128::from(b) - i128::from(x) + 1);
            for k in 0..3 {
                e[k] = e[k] + s[k] * n;
            }
            x = b + 1;
            continue;
        }
        let whole = e[0] >= thresholds.1[0] && e[1] >= thresholds.1[1] && e[2] >= thresholds.1[2];
        if whole {
            run.get_or_insert(x);
        } else {
            if let Some(start) = run.take() {
                sink.full(y, start, x);
            }
            let area = square_area(edges, *e, thresholds);
            if area > 0 {
                sink.partial(x, y, area);
            }
        }
        for k in 0..3 {
            e[k] = e[k] + s[k];
        }
        x += 1;
    }
    if let Some(start) = run {
        sink.full(y, start, to + 1);
    }
}
