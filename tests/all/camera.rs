//! Camera and transform helpers against f64 references written from the textbook formulas
//! (gluLookAt, glOrtho, gluPerspective, Gauss–Jordan inverse), evaluated on the same
//! fixed-point inputs.

use embedded_raster::three_d::{Angle, Mat4, Scalar, Vec3};

use crate::rng;
use rng::Rng;

use crate::vec_f64;
use vec_f64::{cross, dot, normalize};

type M = [[f64; 4]; 4];

fn to_f64(m: &Mat4) -> M {
    m.to_bits().map(|r| r.map(|v| f64::from(v) / 65536.0))
}

/// Largest difference in raw units (2⁻¹⁶) between `got` and the reference.
fn raw_error(got: &Mat4, want: &M) -> f64 {
    let g = to_f64(got);
    (0..16)
        .map(|i| ((g[i / 4][i % 4] - want[i / 4][i % 4]) * 65536.0).abs())
        .fold(0.0, f64::max)
}

/// Gauss–Jordan with partial pivoting.
fn inverse_f64(m: &M) -> Option<M> {
    let mut a = *m;
    let mut inv = [[0.0; 4]; 4];
    for (i, row) in inv.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for col in 0..4 {
        let pivot = (col..4).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col] == 0.0 {
            return None;
        }
        a.swap(col, pivot);
        inv.swap(col, pivot);
        let p = a[col][col];
        for k in 0..4 {
            a[col][k] /= p;
            inv[col][k] /= p;
        }
        for r in 0..4 {
            if r != col {
                let f = a[r][col];
                for k in 0..4 {
                    a[r][k] -= f * a[col][k];
                    inv[r][k] -= f * inv[col][k];
                }
            }
        }
    }
    Some(inv)
}

fn random_matrix(rng: &mut Rng, case: usize) -> Mat4 {
    match case % 3 {
        // Entries of every size.
        0 => {
            let scale = [1u32 << 16, 1 << 18, 1 << 22][case % 9 / 3];
            Mat4::from_bits(core::array::from_fn(|_| {
                core::array::from_fn(|_| rng.range(-i64::from(scale), i64::from(scale)) as i32)
            }))
        }
        // Model matrices: rotation, non-uniform scale, translation.
        1 => {
            let s = |rng: &mut Rng| Scalar::from_num(rng.range_f64(0.05, 8.0));
            let mut scale = Mat4::IDENTITY;
            scale.rows[0][0] = s(rng);
            scale.rows[1][1] = s(rng);
            scale.rows[2][2] = s(rng);
            let a = |rng: &mut Rng| Angle(rng.next() as u16);
            let t = Vec3::new(
                rng.range_f64(-100.0, 100.0),
                rng.range_f64(-100.0, 100.0),
                rng.range_f64(-100.0, 100.0),
            );
            Mat4::translation(t)
                * Mat4::rotation_y(a(rng))
                * Mat4::rotation_x(a(rng))
                * Mat4::rotation_z(a(rng))
                * scale
        }
        // Projection · view.
        _ => {
            let fov = Angle::from_degrees(rng.range_f64(20.0, 120.0));
            let p = Mat4::perspective(fov, rng.range_f64(0.5, 2.5), rng.range_f64(0.1, 2.0), 90)
                .unwrap();
            let v = Mat4::orbit(
                Vec3::ZERO,
                rng.range_f64(1.0, 20.0),
                Angle(rng.next() as u16),
                Angle::from_degrees(rng.range_f64(-80.0, 80.0)),
            );
            p * v
        }
    }
}

#[test]
fn inverse_is_the_rounded_exact_inverse() {
    let mut rng = Rng(0x696e_7665);
    let (mut checked, mut none) = (0, 0);
    for case in 0..20_000 {
        let m = random_matrix(&mut rng, case);
        let want = inverse_f64(&to_f64(&m));
        match (m.inverse(), want) {
            (Some(got), Some(want)) => {
                // f64 Gauss–Jordan is itself within a few ulps on these (condition numbers
                // below 10⁸): 0.5 LSB of rounding plus a margin of 0.01.
                let e = raw_error(&got, &want);
                assert!(e <= 0.51, "case {case}: {e} LSB\n{m:?}\n{got:?}\n{want:?}");
                checked += 1;
            }
            (None, Some(want)) => {
                // Only inverses with an entry out of range are refused.
                let largest = want.iter().flatten().map(|v| v.abs()).fold(0.0, f64::max);
                assert!(
                    largest >= 32767.99,
                    "case {case}: refused, largest {largest}"
                );
                none += 1;
            }
            (Some(_), None) => panic!("case {case}: inverted a singular matrix {m:?}"),
            (None, None) => none += 1,
        }
    }
    assert!(checked > 15_000, "{checked} checked, {none} refused");

    // Singular and out-of-range matrices.
    let mut flat = Mat4::IDENTITY;
    flat.rows[2] = flat.rows[1];
    assert_eq!(flat.inverse(), None);
    assert_eq!(Mat4::scaling(Scalar::from_bits(1)).inverse(), None);
    assert_eq!(Mat4::from_bits([[i32::MAX; 4]; 4]).inverse(), None);
    assert_eq!(Mat4::IDENTITY.inverse(), Some(Mat4::IDENTITY));
    let s = Mat4::scaling(Scalar::from_num(0.25));
    assert_eq!(s.inverse(), Some(Mat4::scaling(Scalar::from_num(4))));
}

#[test]
fn normal_matrix_is_the_scaled_inverse_transpose() {
    let mut rng = Rng(0x6e6f_726d);
    for case in 0..20_000 {
        let m = random_matrix(&mut rng, case);
        let f = to_f64(&m);
        let block: M = core::array::from_fn(|i| {
            core::array::from_fn(|j| {
                if i < 3 && j < 3 {
                    f[i][j]
                } else {
                    f64::from(u8::from(i == j))
                }
            })
        });
        let Some(inv) = inverse_f64(&block) else {
            assert_eq!(m.normal_matrix(), None);
            continue;
        };
        let got = m.normal_matrix().unwrap();
        // The inverse transpose's 3×3 block scaled to a largest entry of `got`'s size.
        let it: [[f64; 3]; 3] = core::array::from_fn(|i| core::array::from_fn(|j| inv[j][i]));
        let largest = it.iter().flatten().map(|v| v.abs()).fold(0.0, f64::max);
        let g = to_f64(&got);
        let g_largest = (0..9).map(|k| g[k / 3][k % 3].abs()).fold(0.0, f64::max);
        assert!((0.5..=1.0).contains(&g_largest), "case {case}: {g_largest}");
        for k in 0..9 {
            let (i, j) = (k / 3, k % 3);
            let want = it[i][j] / largest * g_largest;
            // One rounding to 2⁻¹⁶ of the largest entry, plus the scale's own rounding.
            let e = ((g[i][j] - want) * 65536.0).abs();
            assert!(e <= 1.01, "case {case} ({i}, {j}): {e} LSB");
        }
        // The last row and column are the identity's.
        assert_eq!(got.to_bits()[3], [0, 0, 0, 65536]);
    }
    assert_eq!(Mat4::scaling(Scalar::ZERO).normal_matrix(), None);
}

/// gluLookAt.
fn look_at_f64(eye: [f64; 3], target: [f64; 3], up: [f64; 3]) -> M {
    let f = normalize([0, 1, 2].map(|k| target[k] - eye[k]));
    let s = normalize(cross(f, up));
    let u = cross(s, f);
    [
        [s[0], s[1], s[2], -dot(s, eye)],
        [u[0], u[1], u[2], -dot(u, eye)],
        [-f[0], -f[1], -f[2], dot(f, eye)],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// Error allowed in a view matrix: the axes within a few LSB (more when `up` is nearly along
/// the view direction: `sine` is the sine of their angle), the translation within that times the
/// eye's distance from the origin.
fn view_error_ok(got: &Mat4, want: &M, reach: f64, sine: f64) -> Result<(), String> {
    let g = to_f64(got);
    for r in 0..4 {
        for c in 0..4 {
            let e = ((g[r][c] - want[r][c]) * 65536.0).abs();
            let axes = 2.0 + 1.5 / sine;
            let allowed = if c == 3 {
                2.0 + 2.0 * axes * reach
            } else {
                axes
            };
            if e > allowed {
                return Err(format!("({r}, {c}): {e} LSB > {allowed}"));
            }
        }
    }
    Ok(())
}

#[test]
fn look_at_matches_glu() {
    let mut rng = Rng(0x6c6f_6f6b);
    let v = |rng: &mut Rng, r: f64| {
        Vec3::new(
            rng.range_f64(-r, r),
            rng.range_f64(-r, r),
            rng.range_f64(-r, r),
        )
    };
    for case in 0..20_000 {
        let reach = [2.0, 50.0, 1000.0][case % 3];
        let (eye, target, up) = (v(&mut rng, reach), v(&mut rng, reach), v(&mut rng, 1.0));
        let (e, t, u) = (eye.to_f64(), target.to_f64(), up.to_f64());
        let want = look_at_f64(e, t, u);
        // Skip nearly degenerate poses, where the f64 axes themselves are ill-defined.
        let f = normalize([0, 1, 2].map(|k| t[k] - e[k]));
        let sine = dot(cross(f, u), cross(f, u)).sqrt() / dot(u, u).sqrt();
        let distance = dot(
            [0, 1, 2].map(|k| t[k] - e[k]),
            [0, 1, 2].map(|k| t[k] - e[k]),
        )
        .sqrt();
        if sine < 0.05 || distance < 0.05 {
            continue;
        }
        let got = Mat4::look_at(eye, target, up).unwrap();
        let r = dot(e, e).sqrt();
        if let Err(msg) = view_error_ok(&got, &want, r, sine) {
            panic!("case {case}: {msg}\neye {e:?} target {t:?} up {u:?}");
        }
    }
    let p = Vec3::new(1, 2, 3);
    assert_eq!(Mat4::look_at(p, p, Vec3::new(0, 1, 0)), None);
    assert_eq!(
        Mat4::look_at(Vec3::ZERO, Vec3::new(0, 5, 0), Vec3::new(0, 1, 0)),
        None
    );
}

#[test]
fn orbit_matches_look_at_from_its_eye() {
    let mut rng = Rng(0x6f72_6269);
    for case in 0..20_000 {
        let target = Vec3::new(
            rng.range_f64(-50.0, 50.0),
            rng.range_f64(-50.0, 50.0),
            rng.range_f64(-50.0, 50.0),
        );
        let distance = Scalar::from_num(rng.range_f64(0.5, 100.0));
        let (yaw, pitch) = (
            Angle(rng.next() as u16),
            Angle::from_degrees(rng.range_f64(-85.0, 85.0)),
        );
        let got = Mat4::orbit(target, distance, yaw, pitch);
        let [y, p] = [yaw, pitch].map(|a| f64::from(a.0) / 65536.0 * std::f64::consts::TAU);
        let d = distance.to_num::<f64>();
        let t = target.to_f64();
        let eye = [
            t[0] + d * p.cos() * y.sin(),
            t[1] + d * p.sin(),
            t[2] + d * p.cos() * y.cos(),
        ];
        let want = look_at_f64(eye, t, [0.0, 1.0, 0.0]);
        let reach = dot(t, t).sqrt() + d;
        if let Err(msg) = view_error_ok(&got, &want, reach, p.cos()) {
            panic!("case {case}: {msg}\ntarget {t:?} distance {d} yaw {y} pitch {p}");
        }
    }
}

#[test]
fn projections_match_gl() {
    let mut rng = Rng(0x7072_6f6a);
    for case in 0..20_000 {
        // gluPerspective on the fixed-point inputs (the angle as the binary angle it is).
        let fov = Angle::from_degrees(rng.range_f64(10.0, 150.0));
        let aspect = Scalar::from_num(rng.range_f64(0.25, 4.0));
        let near = Scalar::from_num(rng.range_f64(0.05, 5.0));
        let far = near + Scalar::from_num(rng.range_f64(1.0, 500.0));
        let got = Mat4::perspective(fov, aspect, near, far).unwrap();
        let theta = f64::from(fov.0) / 65536.0 * std::f64::consts::TAU;
        let f = 1.0 / (theta / 2.0).tan();
        let (a, n, fa) = (
            aspect.to_num::<f64>(),
            near.to_num::<f64>(),
            far.to_num::<f64>(),
        );
        let want = [
            [f / a, 0.0, 0.0, 0.0],
            [0.0, f, 0.0, 0.0],
            [0.0, 0.0, (fa + n) / (n - fa), 2.0 * fa * n / (n - fa)],
            [0.0, 0.0, -1.0, 0.0],
        ];
        // cot(θ/2) = (1 + cos θ) / sin θ from the sine and cosine, each within 1 LSB: within
        // (1 + f) / sin θ LSB, then divided by the aspect; each entry rounded once more.
        let e = raw_error(&got, &want);
        let allowed = 1.0 + (1.0 + f) * (1.0 + 1.0 / a) / theta.sin().abs();
        assert!(e <= allowed, "case {case}: perspective {e} LSB > {allowed}");

        // glOrtho.
        let s = |rng: &mut Rng| Scalar::from_num(rng.range_f64(-200.0, 200.0));
        let (l, b, n) = (s(&mut rng), s(&mut rng), s(&mut rng));
        let w = |rng: &mut Rng| Scalar::from_num(rng.range_f64(0.1, 300.0));
        let (r, t, fa) = (l + w(&mut rng), b + w(&mut rng), n + w(&mut rng));
        let got = Mat4::orthographic(l, r, b, t, n, fa);
        let [l, r, b, t, n, fa] = [l, r, b, t, n, fa].map(|v| v.to_num::<f64>());
        let want = [
            [2.0 / (r - l), 0.0, 0.0, -(r + l) / (r - l)],
            [0.0, 2.0 / (t - b), 0.0, -(t + b) / (t - b)],
            [0.0, 0.0, -2.0 / (fa - n), -(fa + n) / (fa - n)],
            [0.0, 0.0, 0.0, 1.0],
        ];
        // Each entry rounded once (0.5 LSB), saturated where beyond the range.
        let g = to_f64(&got);
        for i in 0..16 {
            let want = want[i / 4][i % 4].clamp(-32768.0, 32767.99998);
            let e = ((g[i / 4][i % 4] - want) * 65536.0).abs();
            assert!(
                e <= 0.5 + 1e-6,
                "case {case}: orthographic ({}, {}) {e} LSB",
                i / 4,
                i % 4
            );
        }
    }
}

/// Any inputs give a matrix or `None` without overflowing (a fuzzed near and far of 2¹⁵ each
/// used to overflow the product `2·n·f` in debug builds); `Some` exactly for a field of view in
/// (0, 180°), a positive aspect and `0 < near < far`.
#[test]
fn perspective_takes_extreme_distances() {
    use embedded_raster::three_d::{Angle, Mat4, Scalar};
    let extremes = [
        Scalar::MAX,
        Scalar::MIN,
        Scalar::ZERO,
        Scalar::DELTA,
        -Scalar::DELTA,
    ];
    for near in extremes {
        for far in extremes {
            for fov in [
                Angle::ZERO,
                Angle(1),
                Angle::HALF,
                Angle(32767),
                Angle::from_degrees(60),
            ] {
                for aspect in extremes {
                    let valid = fov.0 > 0
                        && fov.0 < 32768
                        && aspect > Scalar::ZERO
                        && near > Scalar::ZERO
                        && far > near;
                    let got = Mat4::perspective(fov, aspect, near, far);
                    assert_eq!(got.is_some(), valid, "{fov:?} {aspect} {near} {far}");
                    if let Some(m) = got {
                        // w = −z whatever the distances.
                        assert_eq!(m.to_bits()[3], [0, 0, -(1 << 16), 0]);
                    }
                }
            }
        }
    }
}

/// A projection that would show nothing is `None` (issue #32, item 7): no field of view, one of
/// 180° or more (a negative one wraps to more than 180°), an aspect, near plane or depth range
/// that is not positive, or a number a `Scalar` cannot hold.
#[test]
fn perspective_rejects_what_shows_nothing() {
    use embedded_raster::three_d::{Angle, Mat4};
    let fov = Angle::from_degrees(60);
    let valid = Mat4::perspective(fov, 4.0 / 3.0, 0.5, 20.0);
    assert!(valid.is_some());
    let bad_fovs = [
        Angle::ZERO,
        Angle::from_degrees(180),
        Angle::from_degrees(270),
        Angle::from_degrees(-30),
        Angle(u16::MAX),
    ];
    for bad in bad_fovs {
        assert_eq!(
            Mat4::perspective(bad, 4.0 / 3.0, 0.5, 20.0),
            None,
            "{bad:?}"
        );
    }
    assert!(Mat4::perspective(Angle::from_degrees(179.99), 4.0 / 3.0, 0.5, 20.0).is_some());
    assert!(Mat4::perspective(Angle(1), 4.0 / 3.0, 0.5, 20.0).is_some());
    // embedded-graphics' angle of NaN radians.
    let nan = embedded_graphics::geometry::Angle::from_radians(f32::NAN);
    assert_eq!(Mat4::perspective(nan, 1.0, 0.5, 20.0), None);
    for aspect in [0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e9] {
        assert_eq!(
            Mat4::perspective(fov, aspect, 0.5, 20.0),
            None,
            "aspect {aspect}"
        );
    }
    for (near, far) in [
        (0.5, 0.5),
        (2.0, 1.0),
        (0.0, 20.0),
        (-0.5, 20.0),
        (-2.0, -1.0),
        (f64::NAN, 20.0),
        (0.5, f64::NAN),
        (0.5, f64::INFINITY),
        (f64::NEG_INFINITY, 20.0),
        (0.5, 1e6),
    ] {
        assert_eq!(
            Mat4::perspective(fov, 1.0, near, far),
            None,
            "near {near} far {far}"
        );
    }
    assert_eq!(Mat4::perspective(fov, 1, 0, 20), None);
    assert_eq!(Mat4::perspective(fov, 1, 1, 40_000), None);
    // Valid limits: the smallest positive near, far just beyond it, the largest far and aspect.
    use embedded_raster::three_d::Scalar;
    assert!(Mat4::perspective(fov, Scalar::DELTA, Scalar::DELTA, Scalar::DELTA * 2).is_some());
    assert!(Mat4::perspective(fov, Scalar::MAX, 0.5, Scalar::MAX).is_some());
    assert!(Mat4::perspective(fov, 1.0f32, 0.5f32, 32767.0f32).is_some());
}
