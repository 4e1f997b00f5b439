//! Camera and transform helpers for [`Mat4`]: projections, look-at and orbit views, the inverse
//! and the normal matrix — all in integer arithmetic.
//!
//! Conventions are OpenGL's: right-handed world, the camera looks down its −z axis with +y up,
//! and projections map the visible volume to `−w ≤ x, y, z ≤ w`. Angles take any [`ToAngle`]:
//! an [`Angle`] (`Angle::from_degrees(52.5)` for fractional degrees) or embedded-graphics'
//! `Angle`; distances and planes take any [`ToScalar`] (`f32`, `f64`, integers, [`Scalar`]).
//!
//! ```
//! use embedded_raster::three_d::{Angle, Mat4, Vec3};
//!
//! let projection = Mat4::perspective(Angle::from_degrees(52.5), 4.0 / 3.0, 0.5, 50.0).unwrap();
//! let view = Mat4::look_at(Vec3::new(0, 2, 6), Vec3::ZERO, Vec3::new(0, 1, 0)).unwrap();
//! let camera = projection * view;
//! // The point looked at lands in the middle of the screen (normalised device coordinates).
//! let centre = camera.transform_point(Vec3::ZERO);
//! assert!((centre.x / centre.w).abs() < 0.001 && (centre.y / centre.w).abs() < 0.001);
//!
//! let model = Mat4::scaling(2) * Mat4::rotation_y(Angle::from_degrees(30));
//! let back = model.inverse().unwrap() * model;
//! assert!(back.to_bits().iter().flatten().zip(Mat4::IDENTITY.to_bits().iter().flatten())
//!     .all(|(a, b)| (a - b).abs() <= 2));
//! ```

use super::math::{
    div_raw, div_round, normalize_wide, sat32, Angle, Mat4, Scalar, ToAngle, ToScalar, Vec3,
};

impl Mat4 {
    /// An OpenGL-style perspective projection: the camera looks down −z, `fov_y` is the full
    /// vertical field of view (`Angle::from_degrees(52.5)` for fractional degrees), `aspect` is
    /// width / height, and `near < far` are positive distances. Visible points end up with
    /// `−w ≤ x, y, z ≤ w`; `z = −w` on the near plane. Entries are rounded once from exact
    /// quotients of the fixed-point inputs and saturate.
    ///
    /// `None` if the projection would show nothing: a field of view of 0 or of 180° or more (an
    /// [`Angle`] wraps, so −30° is 330°), an aspect that is not positive, a `near` that is not
    /// positive or a `far` not beyond `near`, or a number a [`Scalar`] cannot hold (NaN, an
    /// infinity or beyond ±32768: [`ToScalar::try_to_scalar`]; see
    /// [converting floats](crate#converting-floats)).
    ///
    /// ```
    /// use embedded_raster::three_d::{Angle, Mat4};
    ///
    /// let projection = Mat4::perspective(Angle::from_degrees(60), 4.0 / 3.0, 0.5, 50.0);
    /// assert!(projection.is_some());
    /// // Nothing would be visible: no field of view, a flat screen, a depth range of zero.
    /// assert_eq!(Mat4::perspective(Angle::ZERO, 4.0 / 3.0, 0.5, 50.0), None);
    /// assert_eq!(Mat4::perspective(Angle::from_degrees(60), 0.0, 0.5, 50.0), None);
    /// assert_eq!(Mat4::perspective(Angle::from_degrees(60), 4.0 / 3.0, 0.5, 0.5), None);
    /// assert_eq!(Mat4::perspective(Angle::from_degrees(60), f32::NAN, 0.5, 50.0), None);
    /// ```
    pub fn perspective(
        fov_y: impl ToAngle,
        aspect: impl ToScalar,
        near: impl ToScalar,
        far: impl ToScalar,
    ) -> Option<Self> {
        let fov_y = fov_y.try_to_angle()?;
        let aspect = aspect.try_to_scalar()?;
        let (near, far) = (near.try_to_scalar()?, far.try_to_scalar()?);
        // 0 < fov < 180° (half a turn is 32768 steps), 0 < aspect, 0 < near < far.
        if fov_y.0 == 0
            || fov_y.0 >= 1 << 15
            || aspect <= Scalar::ZERO
            || near <= Scalar::ZERO
            || far <= near
        {
            return None;
        }
        // cot(θ/2) = (1 + cos θ) / sin θ: no rounding of the half angle.
        let f = div_raw((Scalar::ONE + fov_y.cos()).to_bits(), fov_y.sin().to_bits());
        let (n, fa) = (i64::from(near.to_bits()), i64::from(far.to_bits()));
        let d = n - fa;
        let mut m = Mat4::from_bits([[0; 4]; 4]);
        m.rows[0][0] = Scalar::from_bits(div_raw(f, aspect.to_bits()));
        m.rows[1][1] = Scalar::from_bits(f);
        m.rows[2][2] = Scalar::from_bits(div_round((n + fa) << 16, d));
        // 2·n·f / (n − f): the product has 32 fractional bits, the quotient 16.
        m.rows[2][3] = Scalar::from_bits(div_round((n * fa).saturating_mul(2), d));
        m.rows[3][2] = -Scalar::ONE;
        Some(m)
    }

    /// An OpenGL-style orthographic projection (`glOrtho`) of the box `left..right`,
    /// `bottom..top` and depths `near..far` in front of the camera (−z), onto
    /// `−1 ≤ x, y, z ≤ 1` with `w = 1`; `z = −1` on the near plane. Entries are rounded once from
    /// exact quotients and saturate; a side of zero length gives a zero row (nothing visible).
    ///
    /// ```
    /// use embedded_raster::three_d::{Mat4, Vec3};
    ///
    /// let ortho = Mat4::orthographic(-4.0, 4.0, -2.0, 2.0, 0.5, 8.5);
    /// let corner = ortho.transform_point(Vec3::new(4.0, 2.0, -0.5));
    /// assert_eq!(corner.to_bits(), [65536, 65536, -65536, 65536]);
    /// ```
    pub fn orthographic(
        left: impl ToScalar,
        right: impl ToScalar,
        bottom: impl ToScalar,
        top: impl ToScalar,
        near: impl ToScalar,
        far: impl ToScalar,
    ) -> Self {
        let raw = |v: Scalar| i64::from(v.to_bits());
        let [l, r, b, t, n, f] = [
            left.to_scalar(),
            right.to_scalar(),
            bottom.to_scalar(),
            top.to_scalar(),
            near.to_scalar(),
            far.to_scalar(),
        ]
        .map(raw);
        // Scale 2 / (hi − lo) and offset −(hi + lo) / (hi − lo), in raw I16F16.
        let axis = |lo: i64, hi: i64| {
            let d = hi - lo;
            if d == 0 {
                (0, 0)
            } else {
                (div_round(2 << 32, d), div_round(-(hi + lo) << 16, d))
            }
        };
        let (sx, ox) = axis(l, r);
        let (sy, oy) = axis(b, t);
        // Depth runs along −z: z_ndc = −2z / (f − n) − (f + n) / (f − n).
        let (sz, oz) = axis(n, f);
        Mat4::from_bits([
            [sx, 0, 0, ox],
            [0, sy, 0, oy],
            [0, 0, sat32(-i64::from(sz)), oz],
            [0, 0, 0, 1 << 16],
        ])
    }

    /// A view matrix for a camera at `eye` looking at `target`, with `up` giving the upward
    /// direction on screen (`gluLookAt`): world space to a camera space in which the camera
    /// looks down −z with +y up. `None` if `eye` and `target` coincide or `up` is parallel to
    /// the view direction.
    ///
    /// The axes are normalised from exact wide cross products (each within about 2⁻¹⁶ of unit
    /// length); the translation is rounded once from exact dot products and saturates beyond
    /// ±32768.
    pub fn look_at(eye: Vec3, target: Vec3, up: Vec3) -> Option<Self> {
        let wide = |v: Vec3| v.to_bits().map(i64::from);
        let (e, t) = (wide(eye), wide(target));
        let forward = normalize_wide([t[0] - e[0], t[1] - e[1], t[2] - e[2]]);
        let side = normalize_wide(forward.cross_wide(up));
        if forward == Vec3::ZERO || side == Vec3::ZERO {
            return None;
        }
        let up = normalize_wide(side.cross_wide(forward));
        let back = -forward;
        // −axis · eye, exact (units 2⁻³²), rounded to raw I16F16.
        let offset = |axis: Vec3| sat32_i128((-dot_i128(axis, eye) + (1 << 15)) >> 16);
        let row = |a: Vec3| {
            let [x, y, z] = a.to_bits();
            [x, y, z, offset(a)]
        };
        Some(Mat4::from_bits([
            row(side),
            row(up),
            row(back),
            [0, 0, 0, 1 << 16],
        ]))
    }

    /// A view matrix for a camera orbiting `target` at `distance`, looking at it: at zero
    /// angles the camera sits on the target's +z side; `yaw` turns it about the +y axis (from +z
    /// towards +x), `pitch` raises it towards +y (looking down). Unlike
    /// [`look_at`](Self::look_at) it has no singular pose: at a pitch of ±90° the camera looks
    /// straight down (up) with screen-up along the yaw direction.
    ///
    /// ```
    /// use embedded_raster::three_d::{Angle, Mat4, Vec3};
    ///
    /// let view = Mat4::orbit(Vec3::ZERO, 5.0, Angle::from_degrees(90), Angle::ZERO);
    /// // Yawed a quarter turn: the camera sits on +x, so the origin is 5 units in front of it
    /// // and +x points back at the camera.
    /// assert_eq!(view.transform_point(Vec3::ZERO).to_bits(), [0, 0, -5 << 16, 1 << 16]);
    /// assert_eq!(view.transform_vector(Vec3::new(1, 0, 0)), Vec3::new(0, 0, 1));
    /// ```
    pub fn orbit(
        target: Vec3,
        distance: impl ToScalar,
        yaw: impl ToAngle,
        pitch: impl ToAngle,
    ) -> Self {
        let (yaw, pitch) = (yaw.to_angle(), pitch.to_angle());
        // View = T(0, 0, −distance) · Rx(pitch) · Ry(−yaw) · T(−target): the inverse of placing
        // the camera at target + Ry(yaw)·Rx(−pitch)·(0, 0, distance).
        let turn = Mat4::rotation_x(pitch) * Mat4::rotation_y(Angle(yaw.0.wrapping_neg()));
        let mut view = turn;
        let shift = turn.transform_vector(-target);
        view.rows[0][3] = shift.x;
        view.rows[1][3] = shift.y;
        view.rows[2][3] = shift.z.saturating_sub(distance.to_scalar());
        view
    }

    /// The inverse, or `None` if the matrix is singular or an entry of its inverse is beyond the
    /// `Scalar` range (±32768; also for matrices whose determinant exceeds about 2⁶³, which needs
    /// entries near ±32768 throughout).
    ///
    /// The adjugate and the determinant are computed exactly (`i128`), so each entry is the
    /// exact inverse of this fixed-point matrix rounded to the nearest 2⁻¹⁶ (within ½ LSB plus
    /// 2⁻⁶⁰). How close that is to the inverse of the matrix you meant depends on its
    /// conditioning: the entries of this one are already rounded (a rotation's sines and
    /// cosines to 2⁻¹⁶), and an ill-conditioned matrix magnifies that.
    pub fn inverse(&self) -> Option<Self> {
        let a = self.to_bits().map(|r| r.map(i128::from));
        let m2 = |r0: usize, r1: usize, c0: usize, c1: usize| {
            a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]
        };
        // 2×2 minors of the top and bottom row pairs (< 2⁶³ each), columns in this order.
        const COLUMNS: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
        let s = COLUMNS.map(|(c0, c1)| m2(0, 1, c0, c1));
        let c = COLUMNS.map(|(c0, c1)| m2(2, 3, c0, c1));
        // Laplace expansion by complementary minors: six products < 2¹²⁶ each.
        let det = [
            s[0].checked_mul(c[5])?,
            -s[1].checked_mul(c[4])?,
            s[2].checked_mul(c[3])?,
            s[3].checked_mul(c[2])?,
            -s[4].checked_mul(c[1])?,
            s[5].checked_mul(c[0])?,
        ]
        .into_iter()
        .try_fold(0i128, i128::checked_add)?;
        if det == 0 {
            return None;
        }
        // The adjugate (inverse · det): three products < 2⁹⁴ a sum.
        let t = |x: i128, m: i128, y: i128, n: i128, z: i128, o: i128| x * m - y * n + z * o;
        let adj = [
            [
                t(a[1][1], c[5], a[1][2], c[4], a[1][3], c[3]),
                -t(a[0][1], c[5], a[0][2], c[4], a[0][3], c[3]),
                t(a[3][1], s[5], a[3][2], s[4], a[3][3], s[3]),
                -t(a[2][1], s[5], a[2][2], s[4], a[2][3], s[3]),
            ],
            [
                -t(a[1][0], c[5], a[1][2], c[2], a[1][3], c[1]),
                t(a[0][0], c[5], a[0][2], c[2], a[0][3], c[1]),
                -t(a[3][0], s[5], a[3][2], s[2], a[3][3], s[1]),
                t(a[2][0], s[5], a[2][2], s[2], a[2][3], s[1]),
            ],
            [
                t(a[1][0], c[4], a[1][1], c[2], a[1][3], c[0]),
                -t(a[0][0], c[4], a[0][1], c[2], a[0][3], c[0]),
                t(a[3][0], s[4], a[3][1], s[2], a[3][3], s[0]),
                -t(a[2][0], s[4], a[2][1], s[2], a[2][3], s[0]),
            ],
            [
                -t(a[1][0], c[3], a[1][1], c[1], a[1][2], c[0]),
                t(a[0][0], c[3], a[0][1], c[1], a[0][2], c[0]),
                -t(a[3][0], s[3], a[3][1], s[1], a[3][2], s[0]),
                t(a[2][0], s[3], a[2][1], s[1], a[2][2], s[0]),
            ],
        ];
        let mut out = [[0i32; 4]; 4];
        for (o, row) in out.iter_mut().zip(adj) {
            for (o, n) in o.iter_mut().zip(row) {
                // Raw entries: adj (units 2⁻⁴⁸) · 2³² / det (units 2⁻⁶⁴).
                *o = quotient_i32(n, det)?;
            }
        }
        Some(Mat4::from_bits(out))
    }

    /// The matrix that transforms normals for this model matrix: the inverse transpose of its
    /// upper-left 3×3 block, up to a positive factor — scaled so that its largest entry has a
    /// magnitude in `[½, 1]`, which keeps it in range for any invertible block (a model scaled
    /// by 0.001 has an inverse transpose of 1000s). Normals are renormalised after it, so the
    /// factor does not matter. `None` if the block is singular.
    ///
    /// Computed from the exact cofactors (`i128`) and the sign of the exact determinant; each
    /// entry is rounded once, to 2⁻¹⁶ of the largest. For rotations with uniform scale this is
    /// the rotation itself (up to rounding); use it for non-uniform scale and shear, where the
    /// model matrix would tilt normals (see
    /// [`Pipeline::with_inverse_transpose`](super::Pipeline::with_inverse_transpose)).
    ///
    /// ```
    /// use embedded_raster::three_d::{Mat4, Vec3};
    ///
    /// use embedded_raster::three_d::Scalar;
    ///
    /// // Squash y by 4: a 45° slope's normal (1, 1, 0) becomes (1, 4, 0), not (1, ¼, 0).
    /// let mut model = Mat4::IDENTITY;
    /// model.rows[1][1] = Scalar::from_num(0.25);
    /// let n = model.normal_matrix().unwrap().transform_vector(Vec3::new(1, 1, 0));
    /// assert_eq!((n.y / n.x).round(), Scalar::from_num(4));
    /// ```
    pub fn normal_matrix(&self) -> Option<Self> {
        let a = self.to_bits().map(|r| r.map(i128::from));
        // cof[i][j]: the cofactor of entry (i, j) of the 3×3 block (< 2⁶³; units 2⁻³²).
        let cof: [[i128; 3]; 3] = core::array::from_fn(|i| {
            core::array::from_fn(|j| {
                let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
                let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
                a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]
            })
        });
        let det: i128 = (0..3).map(|j| a[0][j] * cof[0][j]).sum();
        if det == 0 {
            return None;
        }
        // inverse transpose = cof / det: keep cof · sign(det), scaled to 16 significant bits.
        let largest = cof.iter().flatten().map(|v| v.unsigned_abs()).max()?;
        let shift = (128 - largest.leading_zeros()) as i32 - 16;
        let sign = det.signum();
        let scale = |v: i128| -> i32 {
            let v = v * sign;
            let r = if shift > 0 {
                (v + (1 << (shift - 1))) >> shift
            } else {
                v << -shift
            };
            // |r| ≤ 2¹⁶ (rounding may reach it): fits.
            r as i32
        };
        let mut out = Mat4::IDENTITY.to_bits();
        for (i, row) in cof.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                out[i][j] = scale(*v);
            }
        }
        Some(Mat4::from_bits(out))
    }
}

/// `round(n · 2³² / d)` as `i32`, or `None` beyond it; `d ≠ 0`, `|n| < 2⁹⁶`.
fn quotient_i32(n: i128, d: i128) -> Option<i32> {
    let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
    // Drop low bits of both until n · 2³² fits: a result in range needs d > |n| / 2³¹, so
    // after a shift of k bits d keeps over 60 significant bits (relative error under 2⁻⁶⁰).
    let k = (128 - n.unsigned_abs().leading_zeros()).saturating_sub(93);
    let (n, d) = (n >> k, d >> k);
    if d == 0 {
        return None;
    }
    // Round to nearest: ⌊(n·2³² + ⌊d/2⌋) / d⌋ (< 2¹²⁶ + 2¹²⁶).
    let q = ((n << 32) + d / 2).div_euclid(d);
    i32::try_from(q).ok()
}

fn dot_i128(a: Vec3, b: Vec3) -> i128 {
    let (a, b) = (a.to_bits(), b.to_bits());
    (0..3).map(|k| i128::from(a[k]) * i128::from(b[k])).sum()
}

fn sat32_i128(v: i128) -> i32 {
    v.clamp(i128::from(i32::MIN), i128::from(i32::MAX)) as i32
}
