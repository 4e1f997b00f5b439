//! Triangle geometry in fixed point: areas, side lengths, barycentric coordinates, point-in-triangle
//! tests and triangle centres, in 2D and 3D.
//!
//! Everything here is `no_std`, heap-free and float-free, so it runs on an FPU-less Cortex-M0. All
//! intermediate arithmetic is done in exact wide integers (`i128` and a private 256-bit integer),
//! so results are either **exact** or **rounded once** from the exact value, never accumulated
//! float-style error.
//!
//! # Types
//!
//! | alias      | type     | range, resolution        | used for                                          |
//! |------------|----------|--------------------------|---------------------------------------------------|
//! | [`Scalar`] | `I16F16` | ±2¹⁵, 2⁻¹⁶               | input coordinates ([`Point2`], [`Point3`]), centroid, incentre |
//! | [`Wide`]   | `I32F32` | ±2³¹, 2⁻³²               | lengths, perimeter, radii, barycentric weights, circumcentre |
//! | [`Area`]   | `I64F64` | ±2⁶³, 2⁻⁶⁴               | areas, cross and dot products                     |
//!
//! [`Vec2<T>`] and [`Vec3<T>`] are plain generic containers; the geometry is implemented for the
//! concrete coordinate type [`Scalar`] (`Point2 = Vec2<Scalar>`, `Point3 = Vec3<Scalar>`). Derived
//! vectors use the wider types, e.g. [`Triangle3::normal`] returns `Vec3<Area>`.
//!
//! # Accuracy
//!
//! Every bit pattern of every input is valid, and no input can panic (debug or release) or
//! overflow. Over the **whole** input range:
//!
//! * exact: [`Triangle2::signed_area`], [`Triangle2::area`], [`Triangle3::normal`],
//!   [`Triangle3::vector_area`], [`Vec2::cross`], [`Vec3::cross`], the `dot` products, and the
//!   decisions of `contains` and `is_degenerate`;
//! * correctly rounded to nearest (error ≤ ½ ulp of the output type): [`Triangle3::area`],
//!   `heron_area`, [`heron`], `side_lengths` (≤ 2⁻³³), `circumcenter` and `circumradius`
//!   (≤ 2⁻³³), `centroid` (≤ 2⁻¹⁷);
//! * `perimeter` is the exact sum of the three rounded side lengths (≤ 1.5·2⁻³²);
//! * `barycentric`: each weight is within ⅔ ulp (⅔·2⁻³²) of the exact value and the three
//!   weights sum to exactly 1 (largest-remainder rounding), so a vertex gets exactly `[1, 0, 0]` and a
//!   point on an edge gets exactly 0 for the opposite vertex;
//! * `incenter`: ≤ 2⁻¹⁷ + 2⁻³¹ per component, `inradius`: ≤ 2⁻³² (both single roundings of the
//!   exact formula evaluated with the correctly rounded side lengths).
//!
//! Results that may not fit their output type return `None` instead: barycentric weights of
//! magnitude ≥ 2³¹, and circumcentres/circumradii ≥ 2³¹. Both only happen for nearly collinear
//! triangles (or points very far outside a thin triangle).
//!
//! # Degenerate triangles
//!
//! A triangle is degenerate when its three vertices are collinear (including coincident vertices);
//! this is decided exactly. Quantities that exist only for a proper triangle (`barycentric`,
//! `incenter`, `inradius`, `circumcenter`, `circumradius`) return `None` for it, and `contains`
//! returns `false`. Quantities defined for any three points (areas — which are then exactly 0 —,
//! side lengths, perimeter, centroid, normal) are always returned. Nothing ever yields NaN or
//! panics.
//!
//! # Cost
//!
//! The wide arithmetic is software 128-/256-bit integer maths: fine for per-triangle setup, not
//! meant for per-pixel inner loops (the rasterizer has its own incremental edge functions).
//!
//! # Example
//!
//! ```
//! use embedded_raster::geometry::{Area, Point2, Triangle2, Wide};
//!
//! // The 3-4-5 right triangle.
//! let t = Triangle2::new(Point2::from_int(0, 0), Point2::from_int(4, 0), Point2::from_int(0, 3));
//! assert_eq!(t.signed_area(), Area::from_num(6));
//! assert_eq!(t.heron_area(), Area::from_num(6));
//! assert_eq!(t.side_lengths(), [Wide::from_num(5), Wide::from_num(3), Wide::from_num(4)]);
//! assert_eq!(t.perimeter(), Wide::from_num(12));
//! assert_eq!(t.inradius(), Some(Wide::from_num(1)));
//! assert_eq!(t.incenter(), Some(Point2::from_int(1, 1)));
//! assert_eq!(t.circumradius(), Some(Wide::from_num(5) / 2));
//! let o = t.circumcenter().unwrap();
//! assert_eq!((o.x, o.y), (Wide::from_num(2), Wide::from_num(3) / 2));
//! assert!(t.contains(Point2::from_int(2, 1)));
//!
//! // Collinear points are not a triangle.
//! let flat = Triangle2::new(Point2::from_int(0, 0), Point2::from_int(1, 1), Point2::from_int(3, 3));
//! assert_eq!(flat.area(), Area::ZERO);
//! assert_eq!(flat.circumcenter(), None);
//! assert_eq!(flat.barycentric(Point2::from_int(1, 1)), None);
//! ```

use fixed::types::{I16F16, I32F32, I64F64};

/// Coordinate type of [`Point2`] and [`Point3`]: `I16F16` (±32768, resolution 2⁻¹⁶).
pub type Scalar = I16F16;

/// Wide scalar, `I32F32` (±2³¹, resolution 2⁻³²): lengths, radii, barycentric weights and
/// circumcentres (which may lie outside the coordinate range).
pub type Wide = I32F32;

/// Area and product type, `I64F64`: holds every area, cross product and dot product of
/// [`Scalar`] coordinates exactly.
pub type Area = I64F64;

/// A 2D vector or point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Vec2<T = Scalar> {
    /// The x component.
    pub x: T,
    /// The y component.
    pub y: T,
}

/// A 3D vector or point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Vec3<T = Scalar> {
    /// The x component.
    pub x: T,
    /// The y component.
    pub y: T,
    /// The z component.
    pub z: T,
}

/// A 2D point with [`Scalar`] coordinates.
pub type Point2 = Vec2<Scalar>;

/// A 3D point with [`Scalar`] coordinates.
pub type Point3 = Vec3<Scalar>;

impl<T> Vec2<T> {
    /// Creates a vector from its components.
    pub const fn new(x: T, y: T) -> Self {
        Self { x, y }
    }
}

impl<T> Vec3<T> {
    /// Creates a vector from its components.
    pub const fn new(x: T, y: T, z: T) -> Self {
        Self { x, y, z }
    }
}

impl Vec2<Scalar> {
    /// A point from raw `I16F16` bit patterns (units of 2⁻¹⁶).
    pub const fn from_bits(x: i32, y: i32) -> Self {
        Self::new(Scalar::from_bits(x), Scalar::from_bits(y))
    }

    /// A point with integer coordinates (always representable, never panics).
    pub const fn from_int(x: i16, y: i16) -> Self {
        Self::from_bits((x as i32) << 16, (y as i32) << 16)
    }

    /// The 2D cross product (perp-dot product) `self.x * other.y - self.y * other.x`, exact.
    ///
    /// ```
    /// use embedded_raster::geometry::{Area, Point2};
    /// assert_eq!(Point2::from_int(2, 0).cross(Point2::from_int(0, 3)), Area::from_num(6));
    /// ```
    pub fn cross(self, other: Self) -> Area {
        let [ax, ay] = self.raw();
        let [bx, by] = other.raw();
        // Each product ≤ 2^62 in magnitude (units 2^-32): the difference is < 2^63.
        let p = i128::from(ax) * i128::from(by) - i128::from(ay) * i128::from(bx);
        Area::from_bits(p << 32)
    }

    /// The dot product, exact.
    pub fn dot(self, other: Self) -> Area {
        let [ax, ay] = self.raw();
        let [bx, by] = other.raw();
        let p = i128::from(ax) * i128::from(bx) + i128::from(ay) * i128::from(by);
        Area::from_bits(p << 32)
    }

    fn raw(self) -> [i64; 2] {
        [i64::from(self.x.to_bits()), i64::from(self.y.to_bits())]
    }
}

impl Vec3<Scalar> {
    /// A point from raw `I16F16` bit patterns (units of 2⁻¹⁶).
    pub const fn from_bits(x: i32, y: i32, z: i32) -> Self {
        Self::new(
            Scalar::from_bits(x),
            Scalar::from_bits(y),
            Scalar::from_bits(z),
        )
    }

    /// A point with integer coordinates (always representable, never panics).
    pub const fn from_int(x: i16, y: i16, z: i16) -> Self {
        Self::from_bits((x as i32) << 16, (y as i32) << 16, (z as i32) << 16)
    }

    /// The cross product `self × other`, exact.
    ///
    /// ```
    /// use embedded_raster::geometry::{Area, Point3, Vec3};
    /// let z = Point3::from_int(1, 0, 0).cross(Point3::from_int(0, 1, 0));
    /// assert_eq!(z, Vec3::new(Area::ZERO, Area::ZERO, Area::ONE));
    /// ```
    pub fn cross(self, other: Self) -> Vec3<Area> {
        let c = cross3(widen3(self.raw()), widen3(other.raw()));
        // Each component < 2^63 in magnitude (units 2^-32).
        Vec3::new(
            Area::from_bits(c[0] << 32),
            Area::from_bits(c[1] << 32),
            Area::from_bits(c[2] << 32),
        )
    }

    /// The dot product, exact.
    pub fn dot(self, other: Self) -> Area {
        let a = widen3(self.raw());
        let b = widen3(other.raw());
        // Three products ≤ 2^62 each (units 2^-32).
        let p = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        Area::from_bits(p << 32)
    }

    fn raw(self) -> [i64; 3] {
        [
            i64::from(self.x.to_bits()),
            i64::from(self.y.to_bits()),
            i64::from(self.z.to_bits()),
        ]
    }
}

// ---------------------------------------------------------------------------------------------
// 2D triangles
// ---------------------------------------------------------------------------------------------

/// A triangle in the plane with vertices `a`, `b`, `c`.
///
/// Side `a` is `|BC|` (opposite vertex `a`), side `b` is `|CA|`, side `c` is `|AB|`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Triangle2 {
    /// First vertex.
    pub a: Point2,
    /// Second vertex.
    pub b: Point2,
    /// Third vertex.
    pub c: Point2,
}

impl Triangle2 {
    /// Creates a triangle from its vertices.
    pub const fn new(a: Point2, b: Point2, c: Point2) -> Self {
        Self { a, b, c }
    }

    fn raw(&self) -> [[i64; 2]; 3] {
        [self.a.raw(), self.b.raw(), self.c.raw()]
    }

    /// `(B − A) × (C − A)` in units of 2⁻³²: |·| < 2⁶⁵.
    fn cross_raw(&self) -> i128 {
        let [a, b, c] = self.raw();
        cross2(sub(b, a), sub(c, a))
    }

    /// Squared side lengths `[|BC|², |CA|², |AB|²]` in units of 2⁻³², each < 2⁶⁵.
    fn sq_sides(&self) -> [u128; 3] {
        let [a, b, c] = self.raw();
        [sq_norm(sub(c, b)), sq_norm(sub(a, c)), sq_norm(sub(b, a))]
    }

    /// Whether the vertices are collinear (or coincident), decided exactly.
    pub fn is_degenerate(&self) -> bool {
        self.cross_raw() == 0
    }

    /// Signed area `½ (B − A) × (C − A)`, exact.
    ///
    /// Positive when `a → b → c` turns counter-clockwise in a y-up frame (which is clockwise on a
    /// y-down screen), negative for the other winding, exactly zero for degenerate triangles.
    ///
    /// ```
    /// use embedded_raster::geometry::{Area, Point2, Triangle2};
    /// let (a, b, c) = (Point2::from_int(0, 0), Point2::from_int(4, 0), Point2::from_int(0, 3));
    /// assert_eq!(Triangle2::new(a, b, c).signed_area(), Area::from_num(6));
    /// assert_eq!(Triangle2::new(a, c, b).signed_area(), Area::from_num(-6));
    /// ```
    pub fn signed_area(&self) -> Area {
        // |cross| < 2^65 in units of 2^-32; halving and rescaling to 2^-64 is a shift by 31.
        Area::from_bits(self.cross_raw() << 31)
    }

    /// Unsigned area, exact.
    pub fn area(&self) -> Area {
        Area::from_bits((self.cross_raw() << 31).abs())
    }

    /// Side lengths `[|BC|, |CA|, |AB|]`, each correctly rounded (error ≤ 2⁻³³).
    pub fn side_lengths(&self) -> [Wide; 3] {
        self.sq_sides().map(|l2| Wide::from_bits(length_raw(l2)))
    }

    /// Perimeter: the exact sum of the three rounded side lengths (error ≤ 1.5·2⁻³²).
    pub fn perimeter(&self) -> Wide {
        Wide::from_bits(self.sq_sides().iter().map(|&l2| length_raw(l2)).sum())
    }

    /// Area by Heron's formula from the (exact, squared) side lengths,
    /// `16K² = 4a²b² − (a² + b² − c²)²`, correctly rounded (error ≤ 2⁻⁶⁵).
    ///
    /// Evaluated in exact integer arithmetic, so it does not suffer the cancellation of the
    /// textbook float formula on needle-shaped triangles; it equals [`area`](Self::area).
    pub fn heron_area(&self) -> Area {
        heron_from_sq(self.sq_sides())
    }

    /// Barycentric coordinates `[λa, λb, λc]` of `p`, so that `p = λa·a + λb·b + λc·c` and
    /// `λa + λb + λc = 1`.
    ///
    /// Each weight is within ⅔·2⁻³² of the exact value and the sum is exactly 1. Returns `None` for
    /// a degenerate triangle, or if a weight's magnitude is ≥ 2³¹ (a point very far outside a very
    /// thin triangle).
    ///
    /// ```
    /// use embedded_raster::geometry::{Point2, Triangle2, Wide};
    /// let t = Triangle2::new(Point2::from_int(0, 0), Point2::from_int(4, 0), Point2::from_int(0, 4));
    /// let w = t.barycentric(Point2::from_int(1, 2)).unwrap();
    /// assert_eq!(w, [Wide::from_num(1) / 4, Wide::from_num(1) / 4, Wide::from_num(1) / 2]);
    /// // Outside points get negative weights.
    /// let w = t.barycentric(Point2::from_int(-4, 0)).unwrap();
    /// assert_eq!(w, [Wide::from_num(2), Wide::from_num(-1), Wide::ZERO]);
    /// ```
    pub fn barycentric(&self, p: Point2) -> Option<[Wide; 3]> {
        let mut n = self.sub_crosses(p);
        // Σ n = (B − A) × (C − A) exactly; |n_i| < 2^65, |d| < 2^67.
        let mut d = n[0] + n[1] + n[2];
        if d == 0 {
            return None;
        }
        if d < 0 {
            d = -d;
            n = n.map(|x| -x);
        }
        let mut q = [0i128; 3];
        let mut r = [0i128; 3];
        for ((q, r), n) in q.iter_mut().zip(r.iter_mut()).zip(n) {
            // |n << 32| < 2^97: exact; d > 0, so neither division can fail.
            let s = n << 32;
            *q = s.checked_div_euclid(d)?;
            *r = s.checked_rem_euclid(d)?;
        }
        round_weights(q, r)
    }

    /// Twice the signed areas of the sub-triangles `(p, b, c)`, `(p, c, a)`, `(p, a, b)`.
    fn sub_crosses(&self, p: Point2) -> [i128; 3] {
        let [a, b, c] = self.raw();
        let p = p.raw();
        let (pa, pb, pc) = (sub(a, p), sub(b, p), sub(c, p));
        [cross2(pb, pc), cross2(pc, pa), cross2(pa, pb)]
    }

    /// Whether `p` lies in the triangle, **boundary inclusive** (points on an edge or at a vertex
    /// are contained), decided exactly from the signs of the three edge cross products. Both
    /// windings behave the same; a degenerate triangle contains nothing.
    ///
    /// (The rasterizer's coverage uses the top-left rule instead, so that shared edges are drawn
    /// once; this is the plain geometric test.)
    ///
    /// ```
    /// use embedded_raster::geometry::{Point2, Triangle2};
    /// let t = Triangle2::new(Point2::from_int(0, 0), Point2::from_int(4, 0), Point2::from_int(0, 4));
    /// assert!(t.contains(Point2::from_int(1, 1)));
    /// assert!(t.contains(Point2::from_int(2, 2))); // on the hypotenuse
    /// assert!(t.contains(Point2::from_int(4, 0))); // a vertex
    /// assert!(!t.contains(Point2::from_int(3, 2)));
    /// ```
    pub fn contains(&self, p: Point2) -> bool {
        let n = self.sub_crosses(p);
        let d = n[0] + n[1] + n[2];
        (d > 0 && n.iter().all(|&x| x >= 0)) || (d < 0 && n.iter().all(|&x| x <= 0))
    }

    /// Centroid `(a + b + c) / 3`, correctly rounded (error ≤ 2⁻¹⁷); defined for any three points.
    pub fn centroid(&self) -> Point2 {
        let [a, b, c] = self.raw();
        Vec2::new(centroid1(a[0], b[0], c[0]), centroid1(a[1], b[1], c[1]))
    }

    /// Incentre `(|BC|·a + |CA|·b + |AB|·c) / perimeter`, rounded to the nearest point
    /// (error ≤ 2⁻¹⁷ + 2⁻³¹ per component). `None` for a degenerate triangle.
    pub fn incenter(&self) -> Option<Point2> {
        if self.is_degenerate() {
            return None;
        }
        let [a, b, c] = self.raw();
        let [_, lb, lc] = self.sq_sides().map(length_raw);
        let per = i128::from(self.perimeter().to_bits());
        let (u, v) = (sub(b, a), sub(c, a));
        let coord = |k: usize| -> Option<Scalar> {
            // Lengths < 2^49 (units 2^-32), differences < 2^32 (units 2^-16): sum < 2^82.
            let num = i128::from(lb) * i128::from(u[k]) + i128::from(lc) * i128::from(v[k]);
            let off = div_round(num, per)?; // units 2^-16
            let raw = i128::from(a[k]) + off;
            Some(Scalar::from_bits(i32::try_from(raw).ok()?))
        };
        Some(Vec2::new(coord(0)?, coord(1)?))
    }

    /// Inradius `2·area / perimeter`, rounded to nearest (error ≤ 2⁻³²). `None` for a degenerate
    /// triangle.
    pub fn inradius(&self) -> Option<Wide> {
        let cross = self.cross_raw();
        if cross == 0 {
            return None;
        }
        let per = i128::from(self.perimeter().to_bits());
        // |cross| < 2^65 (units 2^-32) → shifted < 2^97; result in units 2^-32.
        let r = div_round(cross.abs() << 32, per)?;
        Some(Wide::from_bits(i64::try_from(r).ok()?))
    }

    /// Circumcentre (the point equidistant from the three vertices), correctly rounded
    /// (error ≤ 2⁻³³ per component). `None` for a degenerate triangle or if a coordinate does not
    /// fit [`Wide`] (|·| ≥ 2³¹, nearly collinear vertices).
    pub fn circumcenter(&self) -> Option<Vec2<Wide>> {
        let [a, b, c] = self.raw();
        let (u, v) = (sub(b, a), sub(c, a));
        let (uu, vv) = (sq_norm(u) as i128, sq_norm(v) as i128); // < 2^65
        let mut d = 2 * cross2(u, v); // < 2^66, units 2^-32
        if d == 0 {
            return None;
        }
        // Numerators < 2^98, units 2^-48.
        let mut nx = i128::from(v[1]) * uu - i128::from(u[1]) * vv;
        let mut ny = i128::from(u[0]) * vv - i128::from(v[0]) * uu;
        if d < 0 {
            (d, nx, ny) = (-d, -nx, -ny);
        }
        let coord = |n: i128, a: i64| -> Option<Wide> {
            // (n << 16) / d is the offset from `a` in units of 2^-32; n << 16 < 2^114.
            let off = div_round(n << 16, d)?;
            let raw = (i128::from(a) << 16) + off;
            Some(Wide::from_bits(i64::try_from(raw).ok()?))
        };
        Some(Vec2::new(coord(nx, a[0])?, coord(ny, a[1])?))
    }

    /// Circumradius `|AB|·|BC|·|CA| / (4·area)`, correctly rounded (error ≤ 2⁻³³). `None` for a
    /// degenerate triangle or if it is ≥ 2³¹.
    pub fn circumradius(&self) -> Option<Wide> {
        let cross = self.cross_raw().unsigned_abs();
        circumradius_from(self.sq_sides(), U256::mul_u128(cross, cross))
    }
}

// ---------------------------------------------------------------------------------------------
// 3D triangles
// ---------------------------------------------------------------------------------------------

/// A triangle in space with vertices `a`, `b`, `c`.
///
/// Side `a` is `|BC|` (opposite vertex `a`), side `b` is `|CA|`, side `c` is `|AB|`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Triangle3 {
    /// First vertex.
    pub a: Point3,
    /// Second vertex.
    pub b: Point3,
    /// Third vertex.
    pub c: Point3,
}

impl Triangle3 {
    /// Creates a triangle from its vertices.
    pub const fn new(a: Point3, b: Point3, c: Point3) -> Self {
        Self { a, b, c }
    }

    fn raw(&self) -> [[i64; 3]; 3] {
        [self.a.raw(), self.b.raw(), self.c.raw()]
    }

    /// `(B − A) × (C − A)` in units of 2⁻³²: each component < 2⁶⁵.
    fn normal_raw(&self) -> [i128; 3] {
        let [a, b, c] = self.raw();
        cross3(widen3(sub(b, a)), widen3(sub(c, a)))
    }

    /// `|n|²` in units of 2⁻⁶⁴: < 3·2¹³⁰.
    fn normal_sq(n: [i128; 3]) -> U256 {
        n.iter().fold(U256::ZERO, |acc, &x| {
            acc.add(U256::mul_u128(x.unsigned_abs(), x.unsigned_abs()))
        })
    }

    /// Squared side lengths `[|BC|², |CA|², |AB|²]` in units of 2⁻³², each < 3·2⁶⁴.
    fn sq_sides(&self) -> [u128; 3] {
        let [a, b, c] = self.raw();
        [sq_norm(sub(c, b)), sq_norm(sub(a, c)), sq_norm(sub(b, a))]
    }

    /// Whether the vertices are collinear (or coincident), decided exactly.
    pub fn is_degenerate(&self) -> bool {
        self.normal_raw() == [0; 3]
    }

    /// The (unnormalised) normal `(B − A) × (C − A)`, exact. Its length is twice the area; it
    /// points to the side from which `a → b → c` appears counter-clockwise (right-hand rule).
    ///
    /// ```
    /// use embedded_raster::geometry::{Area, Point3, Triangle3, Vec3};
    /// let t = Triangle3::new(Point3::from_int(0, 0, 0), Point3::from_int(2, 0, 0), Point3::from_int(0, 2, 0));
    /// assert_eq!(t.normal(), Vec3::new(Area::ZERO, Area::ZERO, Area::from_num(4)));
    /// assert_eq!(t.area(), Area::from_num(2));
    /// ```
    pub fn normal(&self) -> Vec3<Area> {
        // Components < 2^65 in units of 2^-32 → < 2^97 in units of 2^-64.
        let n = self.normal_raw();
        Vec3::new(
            Area::from_bits(n[0] << 32),
            Area::from_bits(n[1] << 32),
            Area::from_bits(n[2] << 32),
        )
    }

    /// The vector area `½ (B − A) × (C − A)`, exact: its components are the signed areas of the
    /// triangle's projections onto the yz, zx and xy planes.
    pub fn vector_area(&self) -> Vec3<Area> {
        let n = self.normal_raw();
        Vec3::new(
            Area::from_bits(n[0] << 31),
            Area::from_bits(n[1] << 31),
            Area::from_bits(n[2] << 31),
        )
    }

    /// Area `½ |(B − A) × (C − A)|`, correctly rounded (error ≤ 2⁻⁶⁵).
    pub fn area(&self) -> Area {
        let nn = Self::normal_sq(self.normal_raw());
        // area (units 2^-64) = sqrt(nn · 2^-64) / 2 · 2^64 = sqrt(nn · 2^62); nn · 2^62 < 2^194.
        Area::from_bits(sqrt_round_u256(nn.shl(62)) as i128)
    }

    /// Side lengths `[|BC|, |CA|, |AB|]`, each correctly rounded (error ≤ 2⁻³³).
    pub fn side_lengths(&self) -> [Wide; 3] {
        self.sq_sides().map(|l2| Wide::from_bits(length_raw(l2)))
    }

    /// Perimeter: the exact sum of the three rounded side lengths (error ≤ 1.5·2⁻³²).
    pub fn perimeter(&self) -> Wide {
        Wide::from_bits(self.sq_sides().iter().map(|&l2| length_raw(l2)).sum())
    }

    /// Area by Heron's formula from the (exact, squared) side lengths, correctly rounded
    /// (error ≤ 2⁻⁶⁵); equal to [`area`](Self::area).
    pub fn heron_area(&self) -> Area {
        heron_from_sq(self.sq_sides())
    }

    /// Barycentric coordinates `[λa, λb, λc]` of the orthogonal projection of `p` onto the
    /// triangle's plane, from the signed sub-areas measured along the normal `n`:
    /// `λa = n·((b − p) × (c − p)) / |n|²`, and cyclically.
    ///
    /// For `p` in the plane this is the usual `p = λa·a + λb·b + λc·c`. Each weight is within
    /// ⅔·2⁻³² of the exact value and the sum is exactly 1. `None` for a degenerate triangle or if a
    /// weight's magnitude is ≥ 2³¹.
    ///
    /// ```
    /// use embedded_raster::geometry::{Point3, Triangle3, Wide};
    /// let t = Triangle3::new(Point3::from_int(0, 0, 0), Point3::from_int(4, 0, 0), Point3::from_int(0, 4, 0));
    /// // (1, 2, 7) projects onto (1, 2, 0).
    /// let w = t.barycentric(Point3::from_int(1, 2, 7)).unwrap();
    /// assert_eq!(w, [Wide::from_num(1) / 4, Wide::from_num(1) / 4, Wide::from_num(1) / 2]);
    /// ```
    pub fn barycentric(&self, p: Point3) -> Option<[Wide; 3]> {
        let num = self.sub_areas(p)?;
        // Σ num = |n|² > 0 exactly.
        let d = num[0].add(num[1]).add(num[2]);
        if d.is_negative() || d == U256::ZERO {
            return None;
        }
        let mut q = [0i128; 3];
        let mut r = [U256::ZERO; 3];
        for ((q, r), n) in q.iter_mut().zip(r.iter_mut()).zip(num) {
            // |n| < 2^132 → n << 32 < 2^164.
            (*q, *r) = floor_div_i256(n.shl(32), d)?;
        }
        round_weights(q, r)
    }

    /// `n · ((v₁ − p) × (v₂ − p))` for the three sub-triangles, in units of 2⁻⁶⁴ (|·| < 2¹³²);
    /// `None` if degenerate.
    fn sub_areas(&self, p: Point3) -> Option<[U256; 3]> {
        let n = self.normal_raw();
        if n == [0; 3] {
            return None;
        }
        let [a, b, c] = self.raw();
        let p = p.raw();
        let (pa, pb, pc) = (widen3(sub(a, p)), widen3(sub(b, p)), widen3(sub(c, p)));
        // Sub-cross components < 2^65; each dot product < 3·2^130.
        Some([cross3(pb, pc), cross3(pc, pa), cross3(pa, pb)].map(|s| dot_i256(n, s)))
    }

    /// Whether the orthogonal projection of `p` onto the triangle's plane lies in the triangle,
    /// **boundary inclusive**, decided exactly (signs of the sub-areas along the normal). A
    /// degenerate triangle contains nothing. Check the distance to the plane separately if `p`
    /// must also lie on it.
    ///
    /// ```
    /// use embedded_raster::geometry::{Point3, Triangle3};
    /// let t = Triangle3::new(Point3::from_int(0, 0, 0), Point3::from_int(0, 4, 0), Point3::from_int(0, 0, 4));
    /// assert!(t.contains(Point3::from_int(9, 2, 2))); // projects onto the hypotenuse
    /// assert!(!t.contains(Point3::from_int(0, 3, 3)));
    /// ```
    pub fn contains(&self, p: Point3) -> bool {
        match self.sub_areas(p) {
            Some(n) => n.iter().all(|x| !x.is_negative()),
            None => false,
        }
    }

    /// Centroid `(a + b + c) / 3`, correctly rounded (error ≤ 2⁻¹⁷); defined for any three points.
    pub fn centroid(&self) -> Point3 {
        let [a, b, c] = self.raw();
        Vec3::new(
            centroid1(a[0], b[0], c[0]),
            centroid1(a[1], b[1], c[1]),
            centroid1(a[2], b[2], c[2]),
        )
    }

    /// Incentre `(|BC|·a + |CA|·b + |AB|·c) / perimeter`, rounded to the nearest point
    /// (error ≤ 2⁻¹⁷ + 2⁻³¹ per component). `None` for a degenerate triangle.
    pub fn incenter(&self) -> Option<Point3> {
        if self.is_degenerate() {
            return None;
        }
        let [a, b, c] = self.raw();
        let [_, lb, lc] = self.sq_sides().map(length_raw);
        let per = i128::from(self.perimeter().to_bits());
        let (u, v) = (sub(b, a), sub(c, a));
        let coord = |k: usize| -> Option<Scalar> {
            // Lengths < 2^49 (units 2^-32), differences < 2^32 (units 2^-16): sum < 2^82.
            let num = i128::from(lb) * i128::from(u[k]) + i128::from(lc) * i128::from(v[k]);
            let off = div_round(num, per)?;
            let raw = i128::from(a[k]) + off;
            Some(Scalar::from_bits(i32::try_from(raw).ok()?))
        };
        Some(Vec3::new(coord(0)?, coord(1)?, coord(2)?))
    }

    /// Inradius `2·area / perimeter`, rounded to nearest (error ≤ 2⁻³²). `None` for a degenerate
    /// triangle.
    pub fn inradius(&self) -> Option<Wide> {
        let n = self.normal_raw();
        if n == [0; 3] {
            return None;
        }
        let nn = Self::normal_sq(n);
        // per < 2^51. r (units 2^-32) = sqrt(nn) · 2^32 / per = sqrt(nn · 2^64 / per²), and
        // round(√x) = (⌊√⌊4x⌋⌋ + 1) / 2 with 4x = nn · 2^66 / per² (nn · 2^66 < 2^198).
        let per = self.perimeter().to_bits().unsigned_abs() as u128;
        let (q4, _) = nn.shl(66).div_rem(U256::from_u128(per * per))?;
        let s = i128::try_from(q4.isqrt()).ok()?;
        Some(Wide::from_bits(i64::try_from((s + 1) >> 1).ok()?))
    }

    /// Circumcentre (the point of the triangle's plane equidistant from the three vertices),
    /// correctly rounded (error ≤ 2⁻³³ per component). `None` for a degenerate triangle or if a
    /// coordinate does not fit [`Wide`] (|·| ≥ 2³¹).
    ///
    /// Computed as `a + (|v|²·(n × u) + |u|²·(v × n)) / (2|n|²)` with `u = b − a`, `v = c − a`,
    /// `n = u × v`, in exact 256-bit arithmetic.
    pub fn circumcenter(&self) -> Option<Vec3<Wide>> {
        let [a, b, c] = self.raw();
        let (u, v) = (widen3(sub(b, a)), widen3(sub(c, a))); // < 2^32, units 2^-16
        let n = cross3(u, v); // < 2^65, units 2^-32
        if n == [0; 3] {
            return None;
        }
        let den = Self::normal_sq(n).shl(1); // 2|n|² < 2^133, units 2^-64
        let (uu, vv) = (
            sq_norm(sub(b, a)) as i128, // < 2^66, units 2^-32
            sq_norm(sub(c, a)) as i128,
        );
        let nxu = cross3(n, u); // < 2^98, units 2^-48
        let vxn = cross3(v, n);
        let coord = |k: usize| -> Option<Wide> {
            // Numerator < 2^165 (units 2^-80); shifted by 16 so the quotient is in 2^-32 units.
            let num = U256::mul_i128(vv, nxu[k]).add(U256::mul_i128(uu, vxn[k]));
            let off = div_round_i256(num.shl(16), den)?;
            let raw = (i128::from(a[k]) << 16).checked_add(off)?;
            Some(Wide::from_bits(i64::try_from(raw).ok()?))
        };
        Some(Vec3::new(coord(0)?, coord(1)?, coord(2)?))
    }

    /// Circumradius `|AB|·|BC|·|CA| / (4·area)`, correctly rounded (error ≤ 2⁻³³). `None` for a
    /// degenerate triangle or if it is ≥ 2³¹.
    pub fn circumradius(&self) -> Option<Wide> {
        circumradius_from(self.sq_sides(), Self::normal_sq(self.normal_raw()))
    }
}

/// Area of a triangle with the given side lengths by Heron's formula, correctly rounded
/// (error ≤ 2⁻⁶⁵ against the exact area for these exact side lengths).
///
/// Uses Kahan's ordering `¼√((a+(b+c))(c−(a−b))(c+(a−b))(a+(b−c)))` with `a ≥ b ≥ c`, evaluated in
/// exact 256-bit integer arithmetic. Returns `Some(0)` for a flat triangle (`a = b + c`) and
/// `None` if the lengths violate the triangle inequality or one is negative. Every input is
/// accepted (the area of any valid triangle with sides < 2³¹ fits [`Area`]).
///
/// ```
/// use embedded_raster::geometry::{heron, Area, Wide};
/// let w = |x: i32| Wide::from_num(x);
/// assert_eq!(heron(w(3), w(4), w(5)), Some(Area::from_num(6)));
/// assert_eq!(heron(w(1), w(2), w(3)), Some(Area::ZERO));
/// assert_eq!(heron(w(1), w(2), w(4)), None);
/// ```
pub fn heron(a: Wide, b: Wide, c: Wide) -> Option<Area> {
    let [mut a, mut b, mut c] = [a.to_bits(), b.to_bits(), c.to_bits()].map(i128::from);
    if a < 0 || b < 0 || c < 0 {
        return None;
    }
    // Sort so that a ≥ b ≥ c.
    if a < b {
        core::mem::swap(&mut a, &mut b);
    }
    if b < c {
        core::mem::swap(&mut b, &mut c);
    }
    if a < b {
        core::mem::swap(&mut a, &mut b);
    }
    let f2 = c - (a - b);
    if f2 < 0 {
        return None;
    }
    let f1 = a + (b + c); // ≤ 3a < 3·2^63
    let f3 = c + (a - b); // ≤ a
    let f4 = a + (b - c); // ≤ 2a

    // f1·f4 ≤ 6a² < 2^129; f2·f3 = c² − (a−b)² < 2^126; product ≤ 6a⁴ < 2^255.
    let x = U256::mul_u128(f1 as u128, f4 as u128).mul_small((f2 * f3) as u128);
    // x = 16K² in units of 2^-128; K in units of 2^-64 is √x / 4, rounded as ⌊(⌊√x⌋ + 2) / 4⌋.
    let s = x.isqrt(); // < 2^128
    Some(Area::from_bits(((s >> 2) + ((s & 3) >> 1)) as i128))
}

// ---------------------------------------------------------------------------------------------
// Exact integer helpers (all arguments are raw bit patterns; bounds are noted at the call sites)
// ---------------------------------------------------------------------------------------------

fn sub<const N: usize>(a: [i64; N], b: [i64; N]) -> [i64; N] {
    // Raw I16F16 values: |a − b| < 2^32.
    core::array::from_fn(|i| a[i] - b[i])
}

fn widen3(a: [i64; 3]) -> [i128; 3] {
    a.map(i128::from)
}

/// Σ dᵢ², for differences < 2^32 and N ≤ 3: < 3·2^64.
fn sq_norm<const N: usize>(d: [i64; N]) -> u128 {
    d.iter()
        .map(|&x| {
            let m = u128::from(x.unsigned_abs());
            m * m
        })
        .sum()
}

fn cross2(u: [i64; 2], v: [i64; 2]) -> i128 {
    i128::from(u[0]) * i128::from(v[1]) - i128::from(u[1]) * i128::from(v[0])
}

/// Cross product; callers keep every |uᵢ·vⱼ| < 2^126.
fn cross3(u: [i128; 3], v: [i128; 3]) -> [i128; 3] {
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

/// Exact dot product of two `i128` vectors as a two's-complement 256-bit integer; callers keep
/// the sum below 2^254.
fn dot_i256(a: [i128; 3], b: [i128; 3]) -> U256 {
    U256::mul_i128(a[0], b[0])
        .add(U256::mul_i128(a[1], b[1]))
        .add(U256::mul_i128(a[2], b[2]))
}

/// Length in units of 2^-32 from a squared length in units of 2^-32 (< 2^66), rounded to nearest:
/// √(l2 · 2^32) < 2^49.
fn length_raw(l2: u128) -> i64 {
    sqrt_round_u128(l2 << 32) as i64
}

/// Round-to-nearest `(a + b + c) / 3` of raw I16F16 values; the result lies between the smallest
/// and largest of them, so it always fits. (Ties cannot occur.)
fn centroid1(a: i64, b: i64, c: i64) -> Scalar {
    let s = a + b + c;
    Scalar::from_bits((2 * s + 3).div_euclid(6) as i32)
}

/// `n / d` rounded to nearest (ties up), `d > 0`; `None` only on misuse (`d ≤ 0`, overflow).
fn div_round(n: i128, d: i128) -> Option<i128> {
    if d <= 0 {
        return None;
    }
    n.checked_mul(2)?
        .checked_add(d)?
        .checked_div_euclid(d.checked_mul(2)?)
}

/// `⌊√x⌉` (round to nearest; ties are impossible for integer `x`).
fn sqrt_round_u128(x: u128) -> u128 {
    let s = x.isqrt();
    if x - s * s > s {
        s + 1
    } else {
        s
    }
}

/// `⌊√x⌉` for a 256-bit `x` (< 2^254 at every call site).
fn sqrt_round_u256(x: U256) -> u128 {
    let s = x.isqrt();
    if x.sub(U256::mul_u128(s, s)) > U256::from_u128(s) {
        s.saturating_add(1)
    } else {
        s
    }
}

/// Floor division of a two's-complement 256-bit `n` by a positive `d`: `(q, r)` with
/// `n = q·d + r`, `0 ≤ r < d`. `None` if `d` is zero or `|q| ≥ 2^126`.
fn floor_div_i256(n: U256, d: U256) -> Option<(i128, U256)> {
    const LIMIT: u128 = 1 << 126;
    let neg = n.is_negative();
    let (q, r) = if neg { n.neg() } else { n }.div_rem(d)?;
    if q.hi != 0 || q.lo >= LIMIT {
        return None;
    }
    let q = q.lo as i128;
    Some(match (neg, r == U256::ZERO) {
        (false, _) => (q, r),
        (true, true) => (-q, r),
        (true, false) => (-q - 1, d.sub(r)),
    })
}

/// Signed 256-bit `n / d` rounded to nearest (ties up), `d > 0`, |n| < 2^253.
fn div_round_i256(n: U256, d: U256) -> Option<i128> {
    floor_div_i256(n.shl(1).add(d), d.shl(1)).map(|(q, _)| q)
}

/// Rounds exact weights `nᵢ / d` (with `Σ nᵢ = d`), given as floor quotients `q` (units 2^-32)
/// and remainders `r`, so that they sum to exactly 1: the `k` weights with the largest
/// remainders are rounded up, where `k = 1 − Σ q` (0, 1 or 2).
///
/// Error ≤ ⅔ ulp: with fractional parts `fᵢ` (Σ fᵢ = k), for k = 1 the one rounded up has
/// f ≥ ⅓ (error ≤ ⅔) and each other f ≤ 1 − f_max ≤ ⅔; for k = 2 the one rounded down has
/// f ≤ ⅔ and the two rounded up have f ≥ max(f_min, 1 − f_min) ≥ ½.
fn round_weights<T: Ord + Copy>(q: [i128; 3], r: [T; 3]) -> Option<[Wide; 3]> {
    const ONE: i128 = 1 << 32;
    let k = ONE.checked_sub(q[0].checked_add(q[1])?.checked_add(q[2])?)?;
    if !(0..=2).contains(&k) {
        return None;
    }
    // Indices by descending remainder; a stable sort keeps the lower index first on ties.
    let mut idx = [0usize, 1, 2];
    for i in 1..3 {
        let mut j = i;
        while j > 0 && r[idx[j - 1]] < r[idx[j]] {
            idx.swap(j - 1, j);
            j -= 1;
        }
    }
    let mut q = q;
    for &i in idx.iter().take(k as usize) {
        q[i] += 1;
    }
    let w = |q: i128| i64::try_from(q).ok().map(Wide::from_bits);
    Some([w(q[0])?, w(q[1])?, w(q[2])?])
}

/// Shared by [`heron_area`](Triangle2::heron_area) in 2D and 3D: squared side lengths (units
/// 2^-32, < 3·2^64) → area (units 2^-64).
fn heron_from_sq(l2: [u128; 3]) -> Area {
    let [a2, b2, c2] = l2.map(|x| x as i128);
    // |t| < 2^67; 16K² = 4a²b² − (a² + b² − c²)² ≥ 0, < 2^134 (units 2^-64).
    let t = a2 + b2 - c2;
    let x = U256::mul_i128(a2, b2).shl(2).sub(U256::mul_i128(t, t));
    if x.is_negative() {
        return Area::ZERO; // unreachable: x = 4|n|² exactly
    }
    // K (units 2^-64) = √(x · 2^-64) / 4 · 2^64 = √(x · 2^60); x · 2^60 < 2^194.
    Area::from_bits(sqrt_round_u256(x.shl(60)) as i128)
}

/// Circumradius from squared side lengths (units 2^-32, < 3·2^64) and `c2 = (2·area)²`
/// (units 2^-64), rounded to nearest.
fn circumradius_from(l2: [u128; 3], c2: U256) -> Option<Wide> {
    if c2 == U256::ZERO {
        return None;
    }
    // R = abc / (2√c2); in units of 2^-32, R² = a²b²c² · 2^32 / (4·c2), so with
    // round(√x) = (⌊√⌊4x⌋⌋ + 1) / 2 we need ⌊a²b²c² · 2^32 / c2⌋ (a²b²c² < 2^197).
    let prod = U256::mul_u128(l2[0], l2[1]).mul_small(l2[2]);
    let (q4, _) = prod.shl(32).div_rem(c2)?;
    let s = i128::try_from(q4.isqrt()).ok()?;
    Some(Wide::from_bits(i64::try_from((s + 1) >> 1).ok()?))
}

/// A minimal 256-bit integer, unsigned or two's-complement signed depending on the operation.
/// All arithmetic wraps modulo 2^256 (callers stay in range), so nothing here can panic.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct U256 {
    // Field order matters: the derived `Ord` compares `hi` first (unsigned comparison).
    hi: u128,
    lo: u128,
}

impl U256 {
    const ZERO: Self = Self { hi: 0, lo: 0 };

    const fn from_u128(x: u128) -> Self {
        Self { hi: 0, lo: x }
    }

    /// Full 128 × 128 → 256-bit product.
    fn mul_u128(a: u128, b: u128) -> Self {
        const M: u128 = u64::MAX as u128;
        let (a0, a1) = (a & M, a >> 64);
        let (b0, b1) = (b & M, b >> 64);
        let (p00, p01, p10, p11) = (a0 * b0, a0 * b1, a1 * b0, a1 * b1);
        let mid = (p00 >> 64) + (p01 & M) + (p10 & M); // < 3·2^64
        Self {
            lo: (p00 & M) | (mid << 64),
            hi: p11 + (p01 >> 64) + (p10 >> 64) + (mid >> 64),
        }
    }

    /// Exact signed product (two's complement).
    fn mul_i128(a: i128, b: i128) -> Self {
        let m = Self::mul_u128(a.unsigned_abs(), b.unsigned_abs());
        if (a < 0) != (b < 0) {
            m.neg()
        } else {
            m
        }
    }

    /// `self · m` modulo 2^256.
    fn mul_small(self, m: u128) -> Self {
        let lo = Self::mul_u128(self.lo, m);
        Self {
            lo: lo.lo,
            hi: lo.hi.wrapping_add(self.hi.wrapping_mul(m)),
        }
    }

    fn add(self, o: Self) -> Self {
        let (lo, carry) = self.lo.overflowing_add(o.lo);
        Self {
            lo,
            hi: self.hi.wrapping_add(o.hi).wrapping_add(u128::from(carry)),
        }
    }

    fn sub(self, o: Self) -> Self {
        let (lo, borrow) = self.lo.overflowing_sub(o.lo);
        Self {
            lo,
            hi: self.hi.wrapping_sub(o.hi).wrapping_sub(u128::from(borrow)),
        }
    }

    fn neg(self) -> Self {
        Self::ZERO.sub(self)
    }

    fn is_negative(self) -> bool {
        self.hi >> 127 != 0
    }

    /// Left shift (bits shifted out are lost); `n ≥ 256` gives zero.
    fn shl(self, n: u32) -> Self {
        match n {
            0 => self,
            1..=127 => Self {
                hi: (self.hi << n) | (self.lo >> (128 - n)),
                lo: self.lo << n,
            },
            128..=255 => Self {
                hi: self.lo << (n - 128),
                lo: 0,
            },
            _ => Self::ZERO,
        }
    }

    /// Logical right shift; `n ≥ 256` gives zero.
    fn shr(self, n: u32) -> Self {
        match n {
            0 => self,
            1..=127 => Self {
                hi: self.hi >> n,
                lo: (self.lo >> n) | (self.hi << (128 - n)),
            },
            128..=255 => Self {
                hi: 0,
                lo: self.hi >> (n - 128),
            },
            _ => Self::ZERO,
        }
    }

    /// Number of significant bits.
    fn bits(self) -> u32 {
        if self.hi != 0 {
            256 - self.hi.leading_zeros()
        } else {
            128 - self.lo.leading_zeros()
        }
    }

    /// `1 << i` for `i < 256`.
    fn pow2(i: u32) -> Self {
        Self::from_u128(1).shl(i)
    }

    fn bit(self, i: u32) -> bool {
        self.shr(i).lo & 1 != 0
    }

    /// Unsigned quotient and remainder (restoring long division); `None` if `d` is zero.
    fn div_rem(self, d: Self) -> Option<(Self, Self)> {
        if d == Self::ZERO {
            return None;
        }
        let mut q = Self::ZERO;
        let mut r = Self::ZERO;
        let mut i = self.bits();
        while i > 0 {
            i -= 1;
            // The bit shifted out of `r` matters only if d ≥ 2^255; keep it for full generality.
            let carry = r.is_negative();
            r = r.shl(1);
            r.lo |= u128::from(self.bit(i));
            if carry || r >= d {
                r = r.sub(d);
                q = q.add(Self::pow2(i));
            }
        }
        Some((q, r))
    }

    /// `⌊√self⌋` (bit-by-bit).
    fn isqrt(self) -> u128 {
        if self.hi == 0 {
            return self.lo.isqrt();
        }
        let mut x = self;
        let mut res = Self::ZERO;
        // Highest power of four ≤ self.
        let mut bit = Self::pow2((self.bits() - 1) & !1);
        while bit != Self::ZERO {
            let t = res.add(bit);
            if x >= t {
                x = x.sub(t);
                res = res.shr(1).add(bit);
            } else {
                res = res.shr(1);
            }
            bit = bit.shr(2);
        }
        res.lo
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn u256_basics() {
        let a = u128::MAX;
        let p = U256::mul_u128(a, a); // (2^128 − 1)² = 2^256 − 2^129 + 1
        assert_eq!(p.lo, 1);
        assert_eq!(p.hi, u128::MAX - 1);
        assert_eq!(p.isqrt(), u128::MAX);
        let (q, r) = p.div_rem(U256::from_u128(a)).unwrap();
        assert_eq!((q, r), (U256::from_u128(a), U256::ZERO));
        let m = U256::mul_i128(-3, 5);
        assert!(m.is_negative());
        assert_eq!(m.neg(), U256::from_u128(15));
        assert_eq!(
            floor_div_i256(m, U256::from_u128(4)),
            Some((-4, U256::from_u128(1)))
        );
        assert_eq!(div_round_i256(m, U256::from_u128(4)), Some(-4));
        assert_eq!(div_round_i256(m, U256::from_u128(2)), Some(-7)); // −7.5 → −7 (ties up)
        let big = U256::pow2(200).add(U256::from_u128(12345));
        let (q, r) = big
            .div_rem(U256::pow2(100).add(U256::from_u128(7)))
            .unwrap();
        // q·d + r == big
        let back = U256::mul_u128(q.lo, 1u128 << 100)
            .add(U256::mul_u128(q.lo, 7))
            .add(r);
        assert_eq!(back, big);
        for x in [0u128, 1, 2, 3, 4, 15, 16, 17, u64::MAX as u128, u128::MAX] {
            assert_eq!(U256::from_u128(x).isqrt(), x.isqrt());
            // √(x² · 2^128) = x · 2^64 exactly.
            let y = x >> 64;
            assert_eq!(U256::mul_u128(y, y).shl(128).isqrt(), y << 64);
        }
    }

    /// A small LCG for the randomized checks below.
    fn lcg(s: &mut u64) -> u64 {
        *s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        *s ^ (*s >> 29)
    }

    fn rand_u256(s: &mut u64) -> U256 {
        let w = |s: &mut u64| u128::from(lcg(s)) << 64 | u128::from(lcg(s));
        let x = U256 { hi: w(s), lo: w(s) };
        x.shr((lcg(s) % 256) as u32)
    }

    #[test]
    fn u256_isqrt_bounds() {
        let mut s = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..5000 {
            let x = rand_u256(&mut s);
            let r = x.isqrt();
            assert!(U256::mul_u128(r, r) <= x);
            // (r + 1)² > x; (2^128)² exceeds every U256.
            if r < u128::MAX {
                assert!(U256::mul_u128(r + 1, r + 1) > x);
            }
            let n = sqrt_round_u256(x);
            assert!(n == r || n == r + 1);
        }
    }

    #[test]
    fn u256_division() {
        let mut s = 0x1234_5678;
        for _ in 0..5000 {
            let n = rand_u256(&mut s);
            // Divisors below 2^126 so that q·d can be formed with `mul_small`/`mul_i128`.
            let d = rand_u256(&mut s).shr(130).add(U256::from_u128(1));
            let (q, r) = n.div_rem(d).unwrap();
            assert!(r < d);
            assert_eq!(q.mul_small(d.lo).add(r), n);
            // Signed floor division of a negative numerator.
            let m = n.shr(2).neg();
            if let Some((q, r)) = floor_div_i256(m, d) {
                assert!(q <= 0 && r < d);
                assert_eq!(U256::mul_i128(q, d.lo as i128).add(r), m);
            }
        }
        assert_eq!(U256::from_u128(5).div_rem(U256::ZERO), None);
    }
}
