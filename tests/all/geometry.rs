//! `embedded_raster::geometry` against closed forms evaluated independently in `f64`.
//!
//! # Tolerances
//!
//! Every comparison is `|got − ref| ≤ fixed_tol + ref_err + conv`, where
//!
//! * `fixed_tol` is the accuracy the module documents for that quantity, derived from the
//!   fixed-point resolution of its output type:
//!   - exact results (2D areas, normals): 0;
//!   - correctly rounded results: half an ulp — 2⁻⁶⁵ for `I64F64` areas, 2⁻³³ for `I32F32`
//!     lengths, circumcentres and circumradii, 2⁻¹⁷ for the `I16F16` centroid;
//!   - the perimeter, a sum of three rounded lengths: 3·2⁻³³;
//!   - barycentric weights (largest-remainder rounding, proof at `round_weights`): ⅔·2⁻³²;
//!   - the incentre: 2⁻¹⁷ for its final rounding plus 2.6·2⁻³³ for the rounded side lengths
//!     that weight it (|δ(b/P)| ≤ 2.5·2⁻³³/P and |B − A| ≤ P/2), i.e. 2⁻¹⁷ + 2⁻³¹;
//!   - the inradius: 2⁻³³ rounding + r·3·2⁻³³/P ≤ 2⁻³²;
//! * `ref_err` is a rigorous bound on the error of the `f64` reference itself, carried along by
//!   running error analysis ([`R`]): each operation propagates its operands' bounds exactly
//!   (including second-order terms) and adds `u·|result|` (u = 2⁻⁵³). The inputs (`I16F16`
//!   coordinates) are exact in `f64`, so ill-conditioned references (thin triangles) get a
//!   wider, still honest, tolerance instead of spurious failures;
//! * `conv` = u·|got| covers converting the fixed-point result to `f64`.
//!
//! The reference formulas are deliberately different from the module's: shoelace over absolute
//! coordinates, Heron (Kahan's stable form) on float side lengths, the determinant form of the
//! circumcentre, Gram-matrix solves for 3D barycentrics and circumcentres, sub-area ratios for 2D
//! barycentrics. Exact quantities are additionally compared with plain `i128` computations here.
//!
//! No-panic properties are checked with proptest; run this file also without `--release`
//! (`cargo test --test all geometry::`: the test profile keeps overflow checks) so that an arithmetic
//! overflow would panic instead of wrapping.

use std::collections::BTreeMap;
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

use embedded_raster::geometry::{
    heron, Area, Point2, Point3, Scalar, Triangle2, Triangle3, Vec2, Vec3, Wide,
};
use proptest::prelude::*;

// ------------------------------------------------------------------------------------------------
// f64 with a running (rigorous, first-order-exact) absolute error bound
// ------------------------------------------------------------------------------------------------

const U: f64 = f64::EPSILON / 2.0;

#[derive(Clone, Copy, Debug)]
struct R {
    v: f64,
    e: f64,
}

impl R {
    fn exact(v: f64) -> R {
        R { v, e: 0.0 }
    }
    fn rounded(v: f64) -> R {
        R { v, e: v.abs() * U }
    }
    fn abs(self) -> R {
        R {
            v: self.v.abs(),
            e: self.e,
        }
    }
    fn sqrt(self) -> R {
        let v = self.v.max(0.0).sqrt();
        let lo = (self.v - self.e).max(0.0).sqrt();
        let hi = (self.v + self.e).max(0.0).sqrt();
        R {
            v,
            e: (hi - v).max(v - lo) + 4.0 * U * hi,
        }
    }
}

impl Add for R {
    type Output = R;
    fn add(self, o: R) -> R {
        let v = self.v + o.v;
        R {
            v,
            e: self.e + o.e + U * v.abs(),
        }
    }
}
impl Sub for R {
    type Output = R;
    fn sub(self, o: R) -> R {
        let v = self.v - o.v;
        R {
            v,
            e: self.e + o.e + U * v.abs(),
        }
    }
}
impl Neg for R {
    type Output = R;
    fn neg(self) -> R {
        R {
            v: -self.v,
            e: self.e,
        }
    }
}
impl Mul for R {
    type Output = R;
    fn mul(self, o: R) -> R {
        let v = self.v * o.v;
        // 0 · ∞ = 0 here: an exactly zero factor makes the product exact whatever the other's
        // (finite but unknown) error.
        let m = |x: f64, y: f64| if x == 0.0 || y == 0.0 { 0.0 } else { x * y };
        R {
            v,
            e: m(self.v.abs(), o.e) + m(o.v.abs(), self.e) + m(self.e, o.e) + U * v.abs(),
        }
    }
}
impl Mul<f64> for R {
    type Output = R;
    /// Multiplication by an exact power of two (0.5, 2, 4, ...): exact.
    fn mul(self, k: f64) -> R {
        R {
            v: self.v * k,
            e: self.e * k.abs(),
        }
    }
}
impl Div for R {
    type Output = R;
    fn div(self, o: R) -> R {
        let v = self.v / o.v;
        let den = o.v.abs() - o.e;
        if den.is_nan() || den <= 0.0 || !v.is_finite() {
            return R {
                v: if v.is_finite() { v } else { 0.0 },
                e: f64::INFINITY,
            };
        }
        R {
            v,
            e: (self.e + v.abs() * o.e) / den + U * v.abs(),
        }
    }
}

const P16: f64 = 1.0 / 65536.0; // 2^-16
const P32: f64 = P16 * P16; // 2^-32
const P64: f64 = P32 * P32; // 2^-64

fn s(x: Scalar) -> R {
    R::exact(x.to_num::<f64>())
}
fn p2(p: Point2) -> [R; 2] {
    [s(p.x), s(p.y)]
}
fn p3(p: Point3) -> [R; 3] {
    [s(p.x), s(p.y), s(p.z)]
}
fn wf(x: Wide) -> f64 {
    x.to_num::<f64>()
}
fn af(x: Area) -> f64 {
    x.to_num::<f64>()
}

// ------------------------------------------------------------------------------------------------
// Comparison and statistics
// ------------------------------------------------------------------------------------------------

/// Per quantity: number of checks, and the largest error seen, in units of the documented
/// tolerance, over the checks whose reference is much tighter than that tolerance.
#[derive(Default)]
struct Stats(BTreeMap<&'static str, (u64, f64)>);

impl Stats {
    fn report(&self, title: &str) {
        eprintln!("{title}: max |err| / documented tolerance (samples)");
        for (k, (n, m)) in &self.0 {
            eprintln!("  {k:<22} {m:>8.4}  ({n})");
        }
    }
}

fn close(st: &mut Stats, what: &'static str, got: f64, r: R, fixed_tol: f64, ctx: &dyn Debug) {
    let err = (got - r.v).abs();
    let tol = (fixed_tol + r.e + U * got.abs()) * (1.0 + 1e-9) + f64::MIN_POSITIVE;
    assert!(
        err <= tol,
        "{what}: got {got:e}, reference {:e} ± {:e}, |err| = {err:e} > tol {tol:e} (fixed {fixed_tol:e})\n{ctx:?}",
        r.v,
        r.e
    );
    let ent = st.0.entry(what).or_default();
    ent.0 += 1;
    if fixed_tol > 0.0 && r.e + U * got.abs() <= fixed_tol / 64.0 {
        ent.1 = ent.1.max(err / fixed_tol);
    }
}

// ------------------------------------------------------------------------------------------------
// Reference closed forms
// ------------------------------------------------------------------------------------------------

/// Shoelace over absolute coordinates: signed area.
fn area2_ref(a: [R; 2], b: [R; 2], c: [R; 2]) -> R {
    (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1])) * 0.5
}

fn dist<const N: usize>(p: [R; N], q: [R; N]) -> R {
    let mut acc = R::exact(0.0);
    for i in 0..N {
        let d = p[i] - q[i];
        acc = acc + d * d;
    }
    acc.sqrt()
}

/// Heron, Kahan's numerically stable ordering (sorted by value; the sort uses nominal values, the
/// error bound stays valid for the formula as evaluated).
fn heron_ref(mut l: [R; 3]) -> R {
    l.sort_by(|x, y| y.v.total_cmp(&x.v));
    let [a, b, c] = l;
    let p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
    p.sqrt() * 0.25
}

fn cross3r(u: [R; 3], v: [R; 3]) -> [R; 3] {
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}
fn dot3r(u: [R; 3], v: [R; 3]) -> R {
    u[0] * v[0] + u[1] * v[1] + u[2] * v[2]
}
fn sub3r(u: [R; 3], v: [R; 3]) -> [R; 3] {
    [u[0] - v[0], u[1] - v[1], u[2] - v[2]]
}

/// 2D circumcentre, determinant form over absolute coordinates.
fn circumcenter2_ref(a: [R; 2], b: [R; 2], c: [R; 2]) -> [R; 2] {
    let (aa, bb, cc) = (
        a[0] * a[0] + a[1] * a[1],
        b[0] * b[0] + b[1] * b[1],
        c[0] * c[0] + c[1] * c[1],
    );
    let d = (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1])) * 2.0;
    let ux = aa * (b[1] - c[1]) + bb * (c[1] - a[1]) + cc * (a[1] - b[1]);
    let uy = aa * (c[0] - b[0]) + bb * (a[0] - c[0]) + cc * (b[0] - a[0]);
    [ux / d, uy / d]
}

/// 3D circumcentre via the Gram system (O − A)·u = |u|²/2, (O − A)·v = |v|²/2, O − A = s·u + t·v.
fn circumcenter3_ref(a: [R; 3], b: [R; 3], c: [R; 3]) -> [R; 3] {
    let (u, v) = (sub3r(b, a), sub3r(c, a));
    let (uu, vv, uv) = (dot3r(u, u), dot3r(v, v), dot3r(u, v));
    let det = uu * vv - uv * uv;
    let s_ = vv * (uu - uv) * 0.5 / det;
    let t_ = uu * (vv - uv) * 0.5 / det;
    [0, 1, 2].map(|k| a[k] + s_ * u[k] + t_ * v[k])
}

/// 3D barycentrics of the orthogonal projection of p, via the Gram system.
fn bary3_ref(a: [R; 3], b: [R; 3], c: [R; 3], p: [R; 3]) -> [R; 3] {
    let (u, v, w) = (sub3r(b, a), sub3r(c, a), sub3r(p, a));
    let (uu, vv, uv, uw, vw) = (
        dot3r(u, u),
        dot3r(v, v),
        dot3r(u, v),
        dot3r(u, w),
        dot3r(v, w),
    );
    let det = uu * vv - uv * uv;
    let beta = (vv * uw - uv * vw) / det;
    let gamma = (uu * vw - uv * uw) / det;
    [R::exact(1.0) - beta - gamma, beta, gamma]
}

fn incenter_ref<const N: usize>(v: [[R; N]; 3]) -> [R; N] {
    let l = [dist(v[1], v[2]), dist(v[2], v[0]), dist(v[0], v[1])];
    let per = l[0] + l[1] + l[2];
    std::array::from_fn(|k| (l[0] * v[0][k] + l[1] * v[1][k] + l[2] * v[2][k]) / per)
}

// ------------------------------------------------------------------------------------------------
// Exact integer references for the exact quantities
// ------------------------------------------------------------------------------------------------

fn raw2(p: Point2) -> [i128; 2] {
    [p.x.to_bits().into(), p.y.to_bits().into()]
}
fn raw3(p: Point3) -> [i128; 3] {
    [
        p.x.to_bits().into(),
        p.y.to_bits().into(),
        p.z.to_bits().into(),
    ]
}

/// Twice the signed area by the shoelace formula, units 2^-32.
fn shoelace_i(t: &Triangle2) -> i128 {
    let v = [raw2(t.a), raw2(t.b), raw2(t.c)];
    (0..3)
        .map(|i| v[i][0] * v[(i + 1) % 3][1] - v[(i + 1) % 3][0] * v[i][1])
        .sum()
}

/// Boundary-inclusive point-in-triangle, by orientation tests.
fn contains_i(t: &Triangle2, p: Point2) -> bool {
    let orient = |a: [i128; 2], b: [i128; 2], c: [i128; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let (a, b, c, p) = (raw2(t.a), raw2(t.b), raw2(t.c), raw2(p));
    let d = orient(a, b, c);
    let e = [orient(a, b, p), orient(b, c, p), orient(c, a, p)];
    if d > 0 {
        e.iter().all(|&x| x >= 0)
    } else if d < 0 {
        e.iter().all(|&x| x <= 0)
    } else {
        false
    }
}

fn normal_i(t: &Triangle3) -> [i128; 3] {
    let (a, b, c) = (raw3(t.a), raw3(t.b), raw3(t.c));
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

// ------------------------------------------------------------------------------------------------
// Checks of a whole triangle
// ------------------------------------------------------------------------------------------------

const TOL_AREA: f64 = P64 / 2.0; // ½ ulp of I64F64
const TOL_LEN: f64 = P32 / 2.0; // ½ ulp of I32F32
const TOL_PER: f64 = 3.0 * P32 / 2.0;
const TOL_BARY: f64 = P32 * 2.0 / 3.0; // largest-remainder rounding: ⅔ ulp
const TOL_CENTROID: f64 = P16 / 2.0;
const TOL_INCENTER: f64 = P16 / 2.0 + 2.0 * P32; // 2^-17 + 2^-31
const TOL_INRADIUS: f64 = P32;
const LIMIT: f64 = 2147483648.0; // 2^31: range of Wide

/// A `None` for an out-of-range result is legitimate only if the reference may reach 2³¹.
fn may_overflow(r: &[R], tol: f64) -> bool {
    r.iter().any(|x| x.v.abs() + x.e + tol >= LIMIT)
}

fn check2(t: Triangle2, st: &mut Stats) {
    let v = [p2(t.a), p2(t.b), p2(t.c)];
    let twice = shoelace_i(&t);
    let degenerate = twice == 0;
    assert_eq!(t.is_degenerate(), degenerate, "{t:?}");

    // Areas: exact, against the integer shoelace and the f64 shoelace.
    assert_eq!(t.signed_area().to_bits(), twice << 31, "{t:?}");
    assert_eq!(t.area().to_bits(), (twice << 31).abs(), "{t:?}");
    let area = area2_ref(v[0], v[1], v[2]);
    close(st, "area2", af(t.signed_area()), area, 0.0, &t);
    // Via the cross product in 3D: embed at z = 0.
    let z = Scalar::ZERO;
    let t3 = Triangle3::new(
        Vec3::new(t.a.x, t.a.y, z),
        Vec3::new(t.b.x, t.b.y, z),
        Vec3::new(t.c.x, t.c.y, z),
    );
    let n = t3.normal();
    assert_eq!((n.x, n.y), (Area::ZERO, Area::ZERO));
    assert_eq!(n.z.to_bits(), 2 * t.signed_area().to_bits());
    assert_eq!(t3.vector_area().z, t.signed_area());

    let lens = [dist(v[1], v[2]), dist(v[2], v[0]), dist(v[0], v[1])];
    for (got, r) in t.side_lengths().into_iter().zip(lens) {
        close(st, "side_length2", wf(got), r, TOL_LEN, &t);
    }
    close(
        st,
        "perimeter2",
        wf(t.perimeter()),
        lens[0] + lens[1] + lens[2],
        TOL_PER,
        &t,
    );
    close(
        st,
        "heron2 vs shoelace",
        af(t.heron_area()),
        area.abs(),
        TOL_AREA,
        &t,
    );
    close(
        st,
        "heron2 vs f64 heron",
        af(t.heron_area()),
        heron_ref(lens),
        TOL_AREA,
        &t,
    );

    let c = t.centroid();
    for (got, k) in [(c.x, 0), (c.y, 1)] {
        let r = (v[0][k] + v[1][k] + v[2][k]) / R::exact(3.0);
        close(st, "centroid2", got.to_num(), r, TOL_CENTROID, &t);
    }

    if degenerate {
        assert_eq!(t.incenter(), None);
        assert_eq!(t.inradius(), None);
        assert_eq!(t.circumcenter(), None);
        assert_eq!(t.circumradius(), None);
        assert_eq!(t.barycentric(t.a), None);
        assert!(!t.contains(t.a) && !t.contains(t.b) && !t.contains(t.c));
        assert!(!t.contains(t.centroid()));
        return;
    }

    let ic = t.incenter().expect("incenter");
    let icr = incenter_ref(v);
    close(st, "incenter2", ic.x.to_num(), icr[0], TOL_INCENTER, &t);
    close(st, "incenter2", ic.y.to_num(), icr[1], TOL_INCENTER, &t);

    let k = area.abs();
    let semi = (lens[0] + lens[1] + lens[2]) * 0.5;
    close(
        st,
        "inradius2",
        wf(t.inradius().expect("inradius")),
        k / semi,
        TOL_INRADIUS,
        &t,
    );

    let ocr = circumcenter2_ref(v[0], v[1], v[2]);
    match t.circumcenter() {
        Some(o) => {
            close(st, "circumcenter2", wf(o.x), ocr[0], TOL_LEN, &t);
            close(st, "circumcenter2", wf(o.y), ocr[1], TOL_LEN, &t);
        }
        None => assert!(
            may_overflow(&ocr, TOL_LEN),
            "circumcenter None: {t:?} {ocr:?}"
        ),
    }
    let rr = lens[0] * lens[1] * lens[2] / (k * 4.0);
    match t.circumradius() {
        Some(r) => close(st, "circumradius2", wf(r), rr, TOL_LEN, &t),
        None => assert!(
            may_overflow(&[rr], TOL_LEN),
            "circumradius None: {t:?} {rr:?}"
        ),
    }

    // Barycentrics of the vertices are exact.
    let (one, zero) = (Wide::ONE, Wide::ZERO);
    assert_eq!(t.barycentric(t.a), Some([one, zero, zero]));
    assert_eq!(t.barycentric(t.b), Some([zero, one, zero]));
    assert_eq!(t.barycentric(t.c), Some([zero, zero, one]));
    assert!(t.contains(t.a) && t.contains(t.b) && t.contains(t.c));
    check_bary2(&t, t.centroid(), st);
    check_bary2(&t, ic, st);
}

fn check_bary2(t: &Triangle2, p: Point2, st: &mut Stats) {
    let inside = contains_i(t, p);
    assert_eq!(t.contains(p), inside, "{t:?} {p:?}");
    let (a, b, c, q) = (p2(t.a), p2(t.b), p2(t.c), p2(p));
    let d = area2_ref(a, b, c);
    let r = [
        area2_ref(q, b, c) / d,
        area2_ref(a, q, c) / d,
        area2_ref(a, b, q) / d,
    ];
    match t.barycentric(p) {
        Some(w) => {
            let sum: i128 = w.iter().map(|x| i128::from(x.to_bits())).sum();
            assert_eq!(
                sum,
                1 << 32,
                "weights must sum to exactly 1: {t:?} {p:?} {w:?}"
            );
            for (got, r) in w.into_iter().zip(r) {
                close(st, "barycentric2", wf(got), r, TOL_BARY, &(t, p));
            }
            if inside {
                assert!(w.iter().all(|x| *x >= 0 && *x <= 1), "{t:?} {p:?} {w:?}");
            }
        }
        None => assert!(
            t.is_degenerate() || may_overflow(&r, TOL_BARY),
            "barycentric None: {t:?} {p:?} {r:?}"
        ),
    }
}

fn check3(t: Triangle3, st: &mut Stats) {
    let v = [p3(t.a), p3(t.b), p3(t.c)];
    let ni = normal_i(&t);
    let degenerate = ni == [0; 3];
    assert_eq!(t.is_degenerate(), degenerate, "{t:?}");
    let n = t.normal();
    assert_eq!(
        [n.x, n.y, n.z].map(|x| x.to_bits()),
        ni.map(|x| x << 32),
        "{t:?}"
    );
    let va = t.vector_area();
    assert_eq!(
        [va.x, va.y, va.z].map(|x| x.to_bits()),
        ni.map(|x| x << 31),
        "{t:?}"
    );

    let nr = cross3r(sub3r(v[1], v[0]), sub3r(v[2], v[0]));
    let area = dot3r(nr, nr).sqrt() * 0.5;
    close(st, "area3", af(t.area()), area, TOL_AREA, &t);
    assert_eq!(t.heron_area(), t.area(), "{t:?}");
    let lens = [dist(v[1], v[2]), dist(v[2], v[0]), dist(v[0], v[1])];
    close(
        st,
        "heron3 vs f64 heron",
        af(t.heron_area()),
        heron_ref(lens),
        TOL_AREA,
        &t,
    );
    for (got, r) in t.side_lengths().into_iter().zip(lens) {
        close(st, "side_length3", wf(got), r, TOL_LEN, &t);
    }
    close(
        st,
        "perimeter3",
        wf(t.perimeter()),
        lens[0] + lens[1] + lens[2],
        TOL_PER,
        &t,
    );

    let c = t.centroid();
    for (got, k) in [(c.x, 0), (c.y, 1), (c.z, 2)] {
        let r = (v[0][k] + v[1][k] + v[2][k]) / R::exact(3.0);
        close(st, "centroid3", got.to_num(), r, TOL_CENTROID, &t);
    }

    if degenerate {
        assert_eq!(t.area(), Area::ZERO);
        assert_eq!(t.incenter(), None);
        assert_eq!(t.inradius(), None);
        assert_eq!(t.circumcenter(), None);
        assert_eq!(t.circumradius(), None);
        assert_eq!(t.barycentric(t.a), None);
        assert!(!t.contains(t.a) && !t.contains(t.centroid()));
        return;
    }

    let ic = t.incenter().expect("incenter");
    let icr = incenter_ref(v);
    for (got, r) in [ic.x, ic.y, ic.z].into_iter().zip(icr) {
        close(st, "incenter3", got.to_num(), r, TOL_INCENTER, &t);
    }
    let semi = (lens[0] + lens[1] + lens[2]) * 0.5;
    close(
        st,
        "inradius3",
        wf(t.inradius().expect("inradius")),
        area / semi,
        TOL_INRADIUS,
        &t,
    );

    let ocr = circumcenter3_ref(v[0], v[1], v[2]);
    match t.circumcenter() {
        Some(o) => {
            for (got, r) in [o.x, o.y, o.z].into_iter().zip(ocr) {
                close(st, "circumcenter3", wf(got), r, TOL_LEN, &t);
            }
        }
        None => assert!(
            may_overflow(&ocr, TOL_LEN),
            "circumcenter None: {t:?} {ocr:?}"
        ),
    }
    let rr = lens[0] * lens[1] * lens[2] / (area * 4.0);
    match t.circumradius() {
        Some(r) => close(st, "circumradius3", wf(r), rr, TOL_LEN, &t),
        None => assert!(
            may_overflow(&[rr], TOL_LEN),
            "circumradius None: {t:?} {rr:?}"
        ),
    }

    let (one, zero) = (Wide::ONE, Wide::ZERO);
    assert_eq!(t.barycentric(t.a), Some([one, zero, zero]));
    assert_eq!(t.barycentric(t.b), Some([zero, one, zero]));
    assert_eq!(t.barycentric(t.c), Some([zero, zero, one]));
    assert!(t.contains(t.a) && t.contains(t.b) && t.contains(t.c));
    check_bary3(&t, t.centroid(), st);
    check_bary3(&t, ic, st);
}

fn check_bary3(t: &Triangle3, p: Point3, st: &mut Stats) {
    let r = bary3_ref(p3(t.a), p3(t.b), p3(t.c), p3(p));
    let got = t.barycentric(p);
    match got {
        Some(w) => {
            let sum: i128 = w.iter().map(|x| i128::from(x.to_bits())).sum();
            assert_eq!(
                sum,
                1 << 32,
                "weights must sum to exactly 1: {t:?} {p:?} {w:?}"
            );
            for (got, r) in w.into_iter().zip(r) {
                close(st, "barycentric3", wf(got), r, TOL_BARY, &(t, p));
            }
        }
        None => assert!(
            may_overflow(&r, TOL_BARY),
            "barycentric None: {t:?} {p:?} {r:?}"
        ),
    }
    // contains() is exact; check it wherever the reference's signs are certain.
    if r.iter().all(|x| x.v - x.e > 0.0) {
        assert!(t.contains(p), "{t:?} {p:?} {r:?}");
    }
    if r.iter().any(|x| x.v + x.e < 0.0) {
        assert!(!t.contains(p), "{t:?} {p:?} {r:?}");
    }
}

// ------------------------------------------------------------------------------------------------
// Random inputs (deterministic)
// ------------------------------------------------------------------------------------------------

use crate::rng;
use rng::Rng;

impl Rng {
    /// Uniform in [-2^bits, 2^bits].
    fn spread(&mut self, bits: u32) -> i64 {
        let m = 1i64 << bits;
        (self.next() % (2 * m as u64 + 1)) as i64 - m
    }
}

fn clamp32(x: i64) -> i32 {
    x.clamp(i32::MIN.into(), i32::MAX.into()) as i32
}

/// Raw coordinates around a random centre with a random scale (2^0 .. 2^32 raw units), and with
/// probability 1/4 a thin triangle (third vertex near the line through the first two).
fn rand_raw<const N: usize>(rng: &mut Rng) -> [[i32; N]; 3] {
    let bits = rng.below(33) as u32;
    let centre: [i64; N] = std::array::from_fn(|_| rng.next() as i32 as i64);
    let mut v: [[i64; N]; 3] =
        std::array::from_fn(|_| std::array::from_fn(|k| centre[k] + rng.spread(bits)));
    if rng.below(4) == 0 {
        let t = rng.unit() * 3.0 - 1.0;
        let off = rng.below(20) as u32;
        let [p0, p1, _] = v;
        v[2] = std::array::from_fn(|k| {
            let x = p0[k] as f64 + t * (p1[k] - p0[k]) as f64;
            x.round() as i64 + rng.spread(off.min(bits))
        });
    }
    v.map(|p| p.map(clamp32))
}

fn rand_tri2(rng: &mut Rng) -> Triangle2 {
    let v = rand_raw::<2>(rng);
    let p = |i: usize| Point2::from_bits(v[i][0], v[i][1]);
    Triangle2::new(p(0), p(1), p(2))
}

fn rand_tri3(rng: &mut Rng) -> Triangle3 {
    let v = rand_raw::<3>(rng);
    let p = |i: usize| Point3::from_bits(v[i][0], v[i][1], v[i][2]);
    Triangle3::new(p(0), p(1), p(2))
}

/// The point Σ λᵢ·vᵢ for random λ (some outside [0, 1]), rounded to the coordinate grid.
fn rand_affine<const N: usize>(rng: &mut Rng, v: [[i64; N]; 3], spread: f64) -> [i32; N] {
    let l1 = rng.unit() * (1.0 + 2.0 * spread) - spread;
    let l2 = rng.unit() * (1.0 + 2.0 * spread) - spread;
    let l0 = 1.0 - l1 - l2;
    std::array::from_fn(|k| {
        clamp32((l0 * v[0][k] as f64 + l1 * v[1][k] as f64 + l2 * v[2][k] as f64).round() as i64)
    })
}

// ------------------------------------------------------------------------------------------------
// Tests
// ------------------------------------------------------------------------------------------------

fn pt(x: f64, y: f64) -> Point2 {
    Point2::new(Scalar::from_num(x), Scalar::from_num(y))
}

#[test]
fn right_triangle_exact_values() {
    let t = Triangle2::new(pt(0.0, 0.0), pt(4.0, 0.0), pt(0.0, 3.0));
    let w = |x: f64| Wide::from_num(x);
    assert_eq!(t.signed_area(), Area::from_num(6));
    assert_eq!(t.area(), Area::from_num(6));
    assert_eq!(t.heron_area(), Area::from_num(6));
    assert_eq!(t.side_lengths(), [w(5.0), w(3.0), w(4.0)]);
    assert_eq!(t.perimeter(), w(12.0));
    assert_eq!(t.centroid(), pt(4.0 / 3.0, 1.0));
    assert_eq!(t.incenter(), Some(pt(1.0, 1.0)));
    assert_eq!(t.inradius(), Some(w(1.0)));
    assert_eq!(t.circumcenter(), Some(Vec2::new(w(2.0), w(1.5))));
    assert_eq!(t.circumradius(), Some(w(2.5)));
    assert_eq!(
        t.barycentric(pt(1.0, 1.5)),
        Some([w(0.25), w(0.25), w(0.5)])
    );
    assert_eq!(heron(w(3.0), w(4.0), w(5.0)), Some(Area::from_num(6)));
    // Reversed winding.
    let r = Triangle2::new(t.a, t.c, t.b);
    assert_eq!(r.signed_area(), Area::from_num(-6));
    assert_eq!(r.circumcenter(), t.circumcenter());
    assert_eq!(
        r.barycentric(pt(1.0, 1.5)),
        Some([w(0.25), w(0.5), w(0.25)])
    );
    // Boundary-inclusive containment.
    for p in [
        pt(2.0, 0.0),
        pt(0.0, 1.5),
        pt(2.0, 1.5),
        pt(4.0, 0.0),
        pt(1.0, 1.0),
    ] {
        assert!(t.contains(p) && r.contains(p), "{p:?}");
    }
    let eps = Scalar::DELTA;
    for p in [
        Point2::new(Scalar::from_num(2), -eps),
        Point2::new(-eps, Scalar::from_num(1)),
        Point2::new(Scalar::from_num(2) + eps, Scalar::from_num(1.5)),
    ] {
        assert!(!t.contains(p) && !r.contains(p), "{p:?}");
    }

    // The same triangle in 3D, in the plane y = 0: A = (0,0,0), B = (0,0,4), C = (3,0,0).
    let q = |x: f64, y: f64, z: f64| {
        Point3::new(
            Scalar::from_num(x),
            Scalar::from_num(y),
            Scalar::from_num(z),
        )
    };
    let t3 = Triangle3::new(q(0.0, 0.0, 0.0), q(0.0, 0.0, 4.0), q(3.0, 0.0, 0.0));
    assert_eq!(t3.area(), Area::from_num(6));
    assert_eq!(
        t3.normal(),
        Vec3::new(Area::ZERO, Area::from_num(12), Area::ZERO)
    );
    assert_eq!(t3.side_lengths(), [w(5.0), w(3.0), w(4.0)]);
    assert_eq!(t3.inradius(), Some(w(1.0)));
    assert_eq!(t3.incenter(), Some(q(1.0, 0.0, 1.0)));
    assert_eq!(t3.circumradius(), Some(w(2.5)));
    assert_eq!(t3.circumcenter(), Some(Vec3::new(w(1.5), w(0.0), w(2.0))));
    assert_eq!(
        t3.barycentric(q(1.5, -7.0, 1.0)),
        Some([w(0.25), w(0.25), w(0.5)])
    );
}

#[test]
fn equilateral_triangle() {
    // Side 2 (x from -1 to 1), apex at √3 rounded to the grid.
    let h = Scalar::from_num(3f64.sqrt());
    let t = Triangle2::new(pt(-1.0, 0.0), pt(1.0, 0.0), Point2::new(Scalar::ZERO, h));
    let mut st = Stats::default();
    check2(t, &mut st);
    let hr = h.to_num::<f64>();
    // Closed forms for the isosceles triangle with base 2 and height h.
    let side = (1.0 + hr * hr).sqrt();
    assert!((wf(t.side_lengths()[0]) - side).abs() <= TOL_LEN * 2.0);
    let r_circ = (1.0 + hr * hr) / (2.0 * hr);
    assert!((wf(t.circumradius().unwrap()) - r_circ).abs() <= TOL_LEN * 2.0);
    let o = t.circumcenter().unwrap();
    assert_eq!(o.x, Wide::ZERO);
    assert!((wf(o.y) - (hr - r_circ)).abs() <= TOL_LEN * 2.0);
}

#[test]
fn hand_picked_triangles() {
    let mut st = Stats::default();
    let tris2 = [
        // right, obtuse, very obtuse, acute
        [(0.0, 0.0), (4.0, 0.0), (0.0, 3.0)],
        [(0.0, 0.0), (10.0, 0.0), (1.0, 1.0)],
        [(0.0, 0.0), (1000.0, 0.0), (500.0, 0.001)],
        [(1.25, -3.5), (7.0, 2.0), (-2.75, 6.125)],
        // tiny: a few raw units
        [(0.0, 0.0), (P16, 0.0), (0.0, P16)],
        [(0.0, 0.0), (3.0 * P16, P16), (P16, 2.0 * P16)],
        // large, near the ends of the range
        [
            (-32768.0, -32768.0),
            (32767.0, -32768.0),
            (-32768.0, 32767.0),
        ],
        [
            (-32768.0, -32768.0),
            (32767.99998, 32767.99998),
            (-32768.0, 32767.99998),
        ],
        [(-32768.0, 0.0), (32767.0, 1.0), (0.0, -32768.0)],
        // sliver across the whole range (circumcentre far away)
        [(-32768.0, -32768.0), (32767.99998, 32767.99998), (0.0, P16)],
    ];
    for t in tris2 {
        let t = Triangle2::new(pt(t[0].0, t[0].1), pt(t[1].0, t[1].1), pt(t[2].0, t[2].1));
        check2(t, &mut st);
        check2(Triangle2::new(t.c, t.b, t.a), &mut st);
    }
    let q = |x: f64, y: f64, z: f64| {
        Point3::new(
            Scalar::from_num(x),
            Scalar::from_num(y),
            Scalar::from_num(z),
        )
    };
    let tris3 = [
        [q(0.0, 0.0, 0.0), q(1.0, 0.0, 0.0), q(0.0, 1.0, 0.0)],
        [q(1.0, 2.0, 3.0), q(-4.0, 5.5, 0.25), q(7.0, -8.0, 9.0)],
        [q(0.0, 0.0, 0.0), q(P16, 0.0, 0.0), q(0.0, 0.0, P16)],
        [
            q(-32768.0, -32768.0, -32768.0),
            q(32767.0, 32767.0, -32768.0),
            q(0.0, -32768.0, 32767.0),
        ],
        [
            q(-32768.0, -32768.0, -32768.0),
            q(32767.9, 32767.9, 32767.9),
            q(0.0, 0.0, P16),
        ],
    ];
    for t in tris3 {
        check3(Triangle3::new(t[0], t[1], t[2]), &mut st);
        check3(Triangle3::new(t[2], t[0], t[1]), &mut st);
    }
    st.report("hand-picked");
}

#[test]
fn random_triangles_2d() {
    let mut rng = Rng(0x5EED_2D2D);
    let mut st = Stats::default();
    for _ in 0..4000 {
        let t = rand_tri2(&mut rng);
        check2(t, &mut st);
        let v = [raw2(t.a), raw2(t.b), raw2(t.c)].map(|p| p.map(|x| x as i64));
        for spread in [0.0, 0.2, 3.0] {
            let p = rand_affine(&mut rng, v, spread);
            check_bary2(&t, Point2::from_bits(p[0], p[1]), &mut st);
        }
        // Points on and right next to an edge (exercise the inclusive boundary).
        let (e0, e1) = (v[0], v[1]);
        if (e0[0] + e1[0]) % 2 == 0 && (e0[1] + e1[1]) % 2 == 0 {
            let m = [((e0[0] + e1[0]) / 2) as i32, ((e0[1] + e1[1]) / 2) as i32];
            let mid = Point2::from_bits(m[0], m[1]);
            assert_eq!(t.contains(mid), !t.is_degenerate(), "{t:?}");
            check_bary2(&t, mid, &mut st);
            for d in [[1, 0], [-1, 0], [0, 1], [0, -1]] {
                let p = Point2::from_bits(m[0].saturating_add(d[0]), m[1].saturating_add(d[1]));
                check_bary2(&t, p, &mut st);
            }
        }
        let far = Point2::from_bits(rng.next() as i32, rng.next() as i32);
        check_bary2(&t, far, &mut st);
    }
    st.report("random 2D");
}

#[test]
fn random_triangles_3d() {
    let mut rng = Rng(0x5EED_3D3D);
    let mut st = Stats::default();
    for _ in 0..4000 {
        let t = rand_tri3(&mut rng);
        check3(t, &mut st);
        let v = [raw3(t.a), raw3(t.b), raw3(t.c)].map(|p| p.map(|x| x as i64));
        for spread in [0.0, 0.2, 3.0] {
            // On the plane up to grid rounding, then pushed off it along a random direction:
            // the weights are those of the orthogonal projection either way.
            let p = rand_affine(&mut rng, v, spread);
            check_bary3(&t, Point3::from_bits(p[0], p[1], p[2]), &mut st);
            let off = rng.below(24) as u32;
            let q = p.map(|x| clamp32(x as i64 + rng.spread(off)));
            check_bary3(&t, Point3::from_bits(q[0], q[1], q[2]), &mut st);
        }
    }
    st.report("random 3D");
}

#[test]
fn random_planes_barycentric_3d() {
    // Well-conditioned triangles in random planes through the origin region: the weights must come
    // back within one ulp of the λ used to build the point (up to the grid rounding of the point,
    // which the f64 reference accounts for since it starts from the rounded point).
    let mut rng = Rng(0xB4B4);
    let mut st = Stats::default();
    let mut checked = 0;
    while checked < 3000 {
        // Vertices within 0.75·scale of the origin, scale = 2^-10 .. 2^15: raw < 2^31.
        let scale = (rng.below(26) as f64 - 10.0).exp2();
        let dir = |rng: &mut Rng| -> [f64; 3] { std::array::from_fn(|_| rng.unit() * 2.0 - 1.0) };
        let (o, e1, e2) = (dir(&mut rng), dir(&mut rng), dir(&mut rng));
        let v: [[i64; 3]; 3] = [[0.0; 3], e1, e2].map(|d| {
            std::array::from_fn(|k| ((o[k] * 0.25 + d[k] * 0.5) * scale * 65536.0).round() as i64)
        });
        let t = Triangle3::new(
            Point3::from_bits(v[0][0] as i32, v[0][1] as i32, v[0][2] as i32),
            Point3::from_bits(v[1][0] as i32, v[1][1] as i32, v[1][2] as i32),
            Point3::from_bits(v[2][0] as i32, v[2][1] as i32, v[2][2] as i32),
        );
        if t.is_degenerate() {
            continue;
        }
        for _ in 0..4 {
            let p = rand_affine(&mut rng, v, 0.5);
            let p = Point3::from_bits(p[0], p[1], p[2]);
            check_bary3(&t, p, &mut st);
            assert!(t.barycentric(p).is_some());
        }
        checked += 1;
    }
    st.report("random planes");
}

#[test]
fn embedding_and_permutation_consistency() {
    let mut rng = Rng(0xE3B);
    for _ in 0..2000 {
        let t = rand_tri2(&mut rng);
        let z = Scalar::from_bits(rng.next() as i32);
        let lift = |p: Point2| Vec3::new(p.x, p.y, z);
        let t3 = Triangle3::new(lift(t.a), lift(t.b), lift(t.c));
        assert_eq!(t3.area(), t.area());
        assert_eq!(t3.heron_area(), t.heron_area());
        assert_eq!(t3.side_lengths(), t.side_lengths());
        assert_eq!(t3.perimeter(), t.perimeter());
        assert_eq!(t3.inradius(), t.inradius());
        assert_eq!(t3.circumradius(), t.circumradius());
        assert_eq!(
            t3.incenter().map(|p| (p.x, p.y)),
            t.incenter().map(|p| (p.x, p.y))
        );
        assert_eq!(
            t3.circumcenter().map(|p| (p.x, p.y)),
            t.circumcenter().map(|p| (p.x, p.y))
        );
        let p = Point2::from_bits(rng.next() as i32 >> rng.below(16), rng.next() as i32);
        let pz = Vec3::new(p.x, p.y, Scalar::from_bits(rng.next() as i32));
        assert_eq!(t3.barycentric(pz), t.barycentric(p));
        assert_eq!(t3.contains(pz), t.contains(p));

        // Cyclic permutation of the axes permutes the results.
        let t3 = rand_tri3(&mut rng);
        let rot = |p: Point3| Vec3::new(p.y, p.z, p.x);
        let r3 = Triangle3::new(rot(t3.a), rot(t3.b), rot(t3.c));
        assert_eq!(r3.area(), t3.area());
        assert_eq!(r3.side_lengths(), t3.side_lengths());
        assert_eq!(r3.circumradius(), t3.circumradius());
        assert_eq!(r3.inradius(), t3.inradius());
        assert_eq!(
            r3.circumcenter(),
            t3.circumcenter().map(|p| Vec3::new(p.y, p.z, p.x))
        );
        let p = Point3::from_bits(rng.next() as i32, rng.next() as i32, rng.next() as i32);
        assert_eq!(r3.barycentric(rot(p)), t3.barycentric(p));
        assert_eq!(r3.contains(rot(p)), t3.contains(p));
    }
}

#[test]
fn degenerate_triangles_give_none() {
    let mut st = Stats::default();
    let mut rng = Rng(0xDE6);
    let mut cases2 = vec![
        Triangle2::new(pt(0.0, 0.0), pt(1.0, 1.0), pt(2.0, 2.0)),
        Triangle2::new(pt(0.0, 0.0), pt(2.0, 2.0), pt(1.0, 1.0)),
        Triangle2::new(pt(5.0, 5.0), pt(5.0, 5.0), pt(5.0, 5.0)),
        Triangle2::new(pt(5.0, 5.0), pt(5.0, 5.0), pt(-3.0, 7.0)),
        Triangle2::new(pt(-32768.0, -32768.0), pt(0.0, 0.0), pt(32767.0, 32767.0)),
        Triangle2::new(
            Point2::from_bits(i32::MIN, i32::MIN),
            Point2::from_bits(i32::MAX, i32::MAX),
            Point2::from_bits(1, 1),
        ),
        Triangle2::new(
            pt(0.0, 0.0),
            Point2::from_bits(1, 3),
            Point2::from_bits(-5, -15),
        ),
    ];
    // Random exactly collinear triples: A, A + j·d, A + k·d.
    for _ in 0..2000 {
        let bits = rng.below(16) as u32;
        let d = [rng.spread(bits), rng.spread(bits)];
        let a = [
            rng.next() as i32 as i64 >> rng.below(8),
            rng.next() as i32 as i64 >> 1,
        ];
        let (j, k) = (rng.spread(8), rng.spread(8));
        let p = |m: i64| Point2::from_bits(clamp32(a[0] + m * d[0]), clamp32(a[1] + m * d[1]));
        let t = Triangle2::new(p(0), p(j), p(k));
        // Clamping could break collinearity; keep only truly collinear ones.
        if shoelace_i(&t) == 0 {
            cases2.push(t);
        }
    }
    assert!(cases2.len() > 1000);
    for t in cases2 {
        assert!(t.is_degenerate());
        check2(t, &mut st); // asserts every Option is None, areas zero, contains false
        assert_eq!(t.signed_area(), Area::ZERO);
        assert_eq!(t.heron_area(), Area::ZERO);
        assert!(!t.contains(t.b));
    }

    let q = |x: f64, y: f64, z: f64| {
        Point3::new(
            Scalar::from_num(x),
            Scalar::from_num(y),
            Scalar::from_num(z),
        )
    };
    let mut cases3 = vec![
        Triangle3::new(q(0.0, 0.0, 0.0), q(1.0, 2.0, 3.0), q(2.0, 4.0, 6.0)),
        Triangle3::new(q(1.0, 1.0, 1.0), q(1.0, 1.0, 1.0), q(1.0, 1.0, 1.0)),
        Triangle3::new(q(1.0, 1.0, 1.0), q(1.0, 1.0, 1.0), q(-9.0, 2.0, 0.5)),
        Triangle3::new(
            Point3::from_bits(i32::MIN, i32::MIN, i32::MIN),
            Point3::from_bits(i32::MAX, i32::MAX, i32::MAX),
            Point3::from_bits(0, 0, 0),
        ),
    ];
    for _ in 0..2000 {
        let bits = rng.below(16) as u32;
        let d = [rng.spread(bits), rng.spread(bits), rng.spread(bits)];
        let a = [0, 1, 2].map(|_| rng.next() as i32 as i64 >> 1);
        let (j, k) = (rng.spread(8), rng.spread(8));
        let p = |m: i64| {
            Point3::from_bits(
                clamp32(a[0] + m * d[0]),
                clamp32(a[1] + m * d[1]),
                clamp32(a[2] + m * d[2]),
            )
        };
        let t = Triangle3::new(p(0), p(j), p(k));
        if normal_i(&t) == [0; 3] {
            cases3.push(t);
        }
    }
    assert!(cases3.len() > 1000);
    for t in cases3 {
        assert!(t.is_degenerate());
        check3(t, &mut st);
        assert_eq!(
            t.vector_area(),
            Vec3::new(Area::ZERO, Area::ZERO, Area::ZERO)
        );
    }
}

#[test]
fn heron_from_lengths() {
    let mut st = Stats::default();
    let mut rng = Rng(0x4E40);
    let w = |x: f64| Wide::from_num(x);
    let eq = heron(w(1.0), w(1.0), w(1.0)).unwrap();
    close(
        &mut st,
        "heron(a,b,c)",
        af(eq),
        R::rounded(3f64.sqrt()) * 0.25,
        TOL_AREA,
        &"1,1,1",
    );
    assert_eq!(heron(w(2.0), w(1.0), w(1.0)), Some(Area::ZERO));
    assert_eq!(heron(w(1.0), w(2.0), w(1.0)), Some(Area::ZERO));
    assert_eq!(heron(w(2.0), w(1.0), w(0.99)), None);
    assert_eq!(heron(w(-1.0), w(1.0), w(1.0)), None);
    assert_eq!(heron(Wide::ZERO, Wide::ZERO, Wide::ZERO), Some(Area::ZERO));
    assert_eq!(heron(Wide::MIN, Wide::MIN, Wide::MIN), None);
    let m = heron(Wide::MAX, Wide::MAX, Wide::MAX).unwrap();
    let mv = wf(Wide::MAX);
    assert!((af(m) / (3f64.sqrt() / 4.0 * mv * mv) - 1.0).abs() < 1e-12);
    let m = heron(Wide::MAX, Wide::MAX, Wide::DELTA).unwrap();
    assert!(m > 0);

    for _ in 0..20000 {
        // Random I32F32 lengths with ≤ 53 significant bits (exact in f64), scale 2^-32 .. 2^31.
        let bits = 1 + rng.below(62) as u32;
        let mut len = || {
            let raw = (rng.next() >> (64 - bits)) as i64;
            let keep = if bits > 53 {
                !((1i64 << (bits - 53)) - 1)
            } else {
                -1
            };
            Wide::from_bits(raw & keep)
        };
        let (a, b, c) = (len(), len(), len());
        let r = heron_ref([a, b, c].map(|x| R::exact(wf(x))));
        let mut l = [a, b, c].map(|x| x.to_bits() as i128);
        l.sort();
        let valid = l[0] + l[1] >= l[2];
        match heron(a, b, c) {
            Some(k) => {
                assert!(valid, "{a:?} {b:?} {c:?}");
                close(&mut st, "heron(a,b,c)", af(k), r, TOL_AREA, &(a, b, c));
            }
            None => assert!(!valid, "{a:?} {b:?} {c:?}"),
        }
    }
    // Valid triangles from real side lengths.
    for _ in 0..5000 {
        let t = rand_tri2(&mut rng);
        let [a, b, c] = t.side_lengths();
        let k = heron(a, b, c);
        let r = heron_ref([a, b, c].map(|x| R::exact(wf(x))));
        match k {
            Some(k) => close(&mut st, "heron(sides)", af(k), r, TOL_AREA, &t),
            // Rounded side lengths of a flat triangle may violate the triangle inequality.
            None => assert!(r.v - r.e <= 0.0 || t.is_degenerate(), "{t:?}"),
        }
    }
    st.report("heron");
}

#[test]
fn extreme_coordinates_exhaustive_2d() {
    // Every triangle with coordinates drawn from the ends of the range and around zero.
    let vals = [
        i32::MIN,
        i32::MIN + 1,
        -65536,
        -1,
        0,
        1,
        65536,
        i32::MAX - 1,
        i32::MAX,
    ];
    let mut st = Stats::default();
    let n = vals.len();
    let mut count = 0;
    for i in 0..n.pow(6) {
        let mut k = i;
        let mut c = [0i32; 6];
        for x in &mut c {
            *x = vals[k % n];
            k /= n;
        }
        // Subsample to keep this quick (every 7th), always covering each coordinate value.
        if i % 7 != 0 {
            continue;
        }
        let t = Triangle2::new(
            Point2::from_bits(c[0], c[1]),
            Point2::from_bits(c[2], c[3]),
            Point2::from_bits(c[4], c[5]),
        );
        check2(t, &mut st);
        check_bary2(&t, Point2::from_bits(c[1], c[4]), &mut st);
        count += 1;
    }
    assert!(count > 70_000);
    st.report("extreme 2D");
}

#[test]
fn extreme_coordinates_3d() {
    let vals = [i32::MIN, i32::MIN + 1, -1, 0, 1, i32::MAX - 1, i32::MAX];
    let mut rng = Rng(0xE7);
    let mut st = Stats::default();
    for _ in 0..30_000 {
        let mut c = [0i32; 12];
        for x in &mut c {
            *x = vals[rng.below(vals.len() as u64) as usize];
        }
        let t = Triangle3::new(
            Point3::from_bits(c[0], c[1], c[2]),
            Point3::from_bits(c[3], c[4], c[5]),
            Point3::from_bits(c[6], c[7], c[8]),
        );
        check3(t, &mut st);
        check_bary3(&t, Point3::from_bits(c[9], c[10], c[11]), &mut st);
    }
    st.report("extreme 3D");
}

// ------------------------------------------------------------------------------------------------
// No panics, for arbitrary raw inputs
// ------------------------------------------------------------------------------------------------

fn raw_coord() -> impl Strategy<Value = i32> {
    prop_oneof![
        any::<i32>(),
        prop::sample::select(vec![
            i32::MIN,
            i32::MIN + 1,
            -1,
            0,
            1,
            i32::MAX - 1,
            i32::MAX
        ]),
        -8i32..8,
    ]
}

fn exercise2(t: Triangle2, p: Point2) {
    let _ = (
        t.signed_area(),
        t.area(),
        t.side_lengths(),
        t.perimeter(),
        t.heron_area(),
    );
    let _ = (
        t.centroid(),
        t.incenter(),
        t.inradius(),
        t.circumcenter(),
        t.circumradius(),
    );
    let w = t.barycentric(p);
    let inside = t.contains(p);
    if let Some(w) = w {
        assert_eq!(
            w.iter().map(|x| i128::from(x.to_bits())).sum::<i128>(),
            1 << 32
        );
    }
    if inside {
        assert!(w.is_some());
    }
    let _ = (p.cross(t.a), p.dot(t.b), t.is_degenerate());
}

fn exercise3(t: Triangle3, p: Point3) {
    let _ = (
        t.normal(),
        t.vector_area(),
        t.area(),
        t.side_lengths(),
        t.perimeter(),
    );
    let _ = (t.heron_area(), t.centroid(), t.incenter(), t.inradius());
    let _ = (t.circumcenter(), t.circumradius(), t.is_degenerate());
    let w = t.barycentric(p);
    let inside = t.contains(p);
    if let Some(w) = w {
        assert_eq!(
            w.iter().map(|x| i128::from(x.to_bits())).sum::<i128>(),
            1 << 32
        );
    }
    if inside {
        assert!(w.is_some());
    }
    let _ = (p.cross(t.a), p.dot(t.b));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn no_panic_2d(c in prop::array::uniform8(raw_coord())) {
        let p = |i: usize| Point2::from_bits(c[2 * i], c[2 * i + 1]);
        exercise2(Triangle2::new(p(0), p(1), p(2)), p(3));
    }

    #[test]
    fn no_panic_3d(c in prop::array::uniform12(raw_coord())) {
        let p = |i: usize| Point3::from_bits(c[3 * i], c[3 * i + 1], c[3 * i + 2]);
        exercise3(Triangle3::new(p(0), p(1), p(2)), p(3));
    }

    #[test]
    fn no_panic_near_degenerate_3d(
        a in prop::array::uniform3(any::<i32>()),
        d in prop::array::uniform3(any::<i32>()),
        k in -3i64..4,
        e in prop::array::uniform3(-2i32..3),
        p in prop::array::uniform3(any::<i32>()),
    ) {
        // C = A + k·d + tiny offset: nearly collinear, huge circumcentres and weights.
        let f = |i: usize| clamp32(a[i] as i64 + k * (d[i] as i64 >> 2) + e[i] as i64);
        let g = |i: usize| clamp32(a[i] as i64 + (d[i] as i64 >> 2));
        let t = Triangle3::new(
            Point3::from_bits(a[0], a[1], a[2]),
            Point3::from_bits(g(0), g(1), g(2)),
            Point3::from_bits(f(0), f(1), f(2)),
        );
        exercise3(t, Point3::from_bits(p[0], p[1], p[2]));
    }

    #[test]
    fn no_panic_heron(a in any::<i64>(), b in any::<i64>(), c in any::<i64>()) {
        let r = heron(Wide::from_bits(a), Wide::from_bits(b), Wide::from_bits(c));
        if let Some(k) = r {
            prop_assert!(k >= 0);
        }
    }
}
