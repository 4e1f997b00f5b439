//! An independent `f64` reference for texture sampling and textured triangles.
//!
//! Like the rest of [`reference`](super), it is written from the conventions below alone and
//! shares no code with the fixed-point texture mapping, so the test suites can compare that
//! implementation against it. Coverage and screen barycentrics come from the parent module's
//! [`super::covers`], [`super::barycentric`] and [`super::for_each_covered`].
//!
//! # Conventions
//!
//! * A texture ([`RefTexture`]) is `width × height` texels, row-major, row 0 at the top:
//!   `texels[y·width + x]` holds the channel values of texel `(x, y)`, already in the target
//!   colour's channel depth (e.g. `0..=31` for the red channel of `Rgb565`).
//! * Texel coordinates are continuous and measured in texels: texel `(i, j)` is the square
//!   `[i, i+1) × [j, j+1)` with its centre at `(i + 0.5, j + 0.5)`; `x` grows right, `y` down.
//! * Wrap modes ([`RefWrap`], [`wrap`]) map an integer texel index `i` to `0..n`: *Repeat* is
//!   `i mod n`, *MirroredRepeat* is `m` if `m < n` else `2n − 1 − m` with `m = i mod 2n`, *Clamp*
//!   is `clamp(i, 0, n − 1)` (all moduli Euclidean, so never negative).
//! * [`nearest`] samples texel `(wrap(⌊x⌋), wrap(⌊y⌋))`. [`boundary_distance`] says how close a
//!   coordinate is to a texel boundary, where a fixed-point sampler may legitimately pick the
//!   neighbour.
//! * [`bilinear`] follows OpenGL: `x' = x − 0.5`, `i0 = ⌊x'⌋`, `fx = x' − i0` (likewise `y`),
//!   blending texels `(i0, j0)`, `(i0+1, j0)`, `(i0, j0+1)`, `(i0+1, j0+1)`, each index wrapped
//!   separately, with weights `(1−fx)(1−fy)`, `fx(1−fy)`, `(1−fx)fy`, `fx·fy`.
//! * Textured triangles have raw sub-pixel vertices (256 units a pixel, as in the parent module),
//!   per-vertex texel coordinates `uv[k]` and a positive clip-space `w[k]` (the view depth; equal
//!   `w`s mean affine mapping). At a covered pixel centre with screen barycentrics `b_k` the
//!   perspective-correct value of an attribute `a` is `Σ b_k·a_k/w_k / Σ b_k/w_k`
//!   ([`perspective_attributes`], [`perspective_texel_coords`]).
//! * Shading helpers: [`modulate`] (texel × vertex colour of the same depth), [`scale`] (texel ×
//!   light level), [`lambert`] and [`blinn_phong`] (light and specular factors in `[0, 1]`).
//!
//! # Example
//!
//! ```
//! use embedded_raster::reference::texture::{bilinear, nearest, RefTexture, RefWrap};
//!
//! // A 2 × 1 texture, one channel used: 0 on the left, 10 on the right.
//! let t = RefTexture::new(2, 1, vec![[0.0; 3], [10.0, 0.0, 0.0]]);
//! let clamp = [RefWrap::Clamp; 2];
//! assert_eq!(nearest(&t, clamp, 1.2, 0.5)[0], 10.0);
//! // Half-way between the two texel centres (0.5 and 1.5).
//! assert_eq!(bilinear(&t, clamp, 1.0, 0.5)[0], 5.0);
//! ```

use std::vec::Vec;

use super::{barycentric, for_each_covered};

/// A texture for the reference samplers: `width × height` texels, row-major, row 0 at the top.
///
/// `texels[y·width + x]` holds the three channel values of texel `(x, y)`, in the target colour's
/// channel depth.
#[derive(Clone, Debug, PartialEq)]
pub struct RefTexture {
    /// Width in texels (at least 1).
    pub width: u32,
    /// Height in texels (at least 1).
    pub height: u32,
    /// The texels, row-major, `width · height` of them.
    pub texels: Vec<[f64; 3]>,
}

impl RefTexture {
    /// A texture of `width × height` texels given row-major, row 0 at the top.
    ///
    /// Panics if a dimension is 0 or `texels.len() != width · height`.
    pub fn new(width: u32, height: u32, texels: Vec<[f64; 3]>) -> RefTexture {
        assert!(width > 0 && height > 0, "empty texture");
        assert_eq!(
            texels.len() as u64,
            u64::from(width) * u64::from(height),
            "texel count does not match width × height"
        );
        RefTexture {
            width,
            height,
            texels,
        }
    }

    /// The channel values of texel `(x, y)` (`x` right, `y` down). Panics if it lies outside.
    pub fn texel(&self, x: u32, y: u32) -> [f64; 3] {
        // Without the check an x past the width would silently read the next row.
        assert!(
            x < self.width && y < self.height,
            "texel ({x}, {y}) outside a {}×{} texture",
            self.width,
            self.height
        );
        self.texels[y as usize * self.width as usize + x as usize]
    }
}

/// How an integer texel index outside `0..n` is mapped back into the texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RefWrap {
    /// `i mod n` (Euclidean): the texture tiles.
    Repeat,
    /// With `m = i mod 2n` (Euclidean): `m` if `m < n`, else `2n − 1 − m`: every other tile is
    /// mirrored, the edge texel repeated at each seam.
    MirroredRepeat,
    /// `clamp(i, 0, n − 1)`: the edge texels extend outward.
    Clamp,
}

/// Maps the integer texel index `i` into `0..n` with the wrap mode `wrap` (see [`RefWrap`]).
/// Panics if `n` is 0.
pub fn wrap(i: i64, n: u32, wrap: RefWrap) -> u32 {
    assert!(n > 0, "wrap into an empty range");
    let n = i64::from(n);
    let r = match wrap {
        RefWrap::Repeat => i.rem_euclid(n),
        RefWrap::MirroredRepeat => {
            let m = i.rem_euclid(2 * n);
            if m < n {
                m
            } else {
                2 * n - 1 - m
            }
        }
        RefWrap::Clamp => i.clamp(0, n - 1),
    };
    // In 0..n, and n came from a u32.
    r as u32
}

/// `⌊x⌋` as an integer texel index (saturating for coordinates beyond `i64`; `x` must not be NaN).
fn index(x: f64) -> i64 {
    debug_assert!(!x.is_nan(), "NaN texel coordinate");
    x.floor() as i64
}

/// The texel that nearest sampling picks at texel coordinates `(x, y)`:
/// `(wrap(⌊x⌋), wrap(⌊y⌋))`, with `wrap[0]` for `x` and `wrap[1]` for `y`.
pub fn nearest_texel(t: &RefTexture, wrap: [RefWrap; 2], x: f64, y: f64) -> (u32, u32) {
    (
        self::wrap(index(x), t.width, wrap[0]),
        self::wrap(index(y), t.height, wrap[1]),
    )
}

/// Nearest sampling at texel coordinates `(x, y)`: the channels of [`nearest_texel`].
pub fn nearest(t: &RefTexture, wrap: [RefWrap; 2], x: f64, y: f64) -> [f64; 3] {
    let (i, j) = nearest_texel(t, wrap, x, y);
    t.texel(i, j)
}

/// The distance, in texels, from `(x, y)` to the nearest texel boundary line in either axis:
/// `min(|x − round(x)|, |y − round(y)|)`. Nearest sampling is ambiguous only near 0.
pub fn boundary_distance(x: f64, y: f64) -> f64 {
    (x - x.round()).abs().min((y - y.round()).abs())
}

/// Bilinear sampling at texel coordinates `(x, y)` (OpenGL convention: texel centres at
/// half-integers, each of the four indices wrapped separately; `wrap[0]` for `x`, `wrap[1]` for
/// `y`). At a texel centre the result is that texel exactly.
pub fn bilinear(t: &RefTexture, wrap: [RefWrap; 2], x: f64, y: f64) -> [f64; 3] {
    // Shift so that texel centres fall on integers; the fraction is then the weight of the
    // texel to the right (below).
    let (xs, ys) = (x - 0.5, y - 0.5);
    let (i0, j0) = (index(xs), index(ys));
    let (fx, fy) = (xs - i0 as f64, ys - j0 as f64);
    let wi = |i: i64| self::wrap(i, t.width, wrap[0]);
    let wj = |j: i64| self::wrap(j, t.height, wrap[1]);
    let (i0w, i1w) = (wi(i0), wi(i0.saturating_add(1)));
    let (j0w, j1w) = (wj(j0), wj(j0.saturating_add(1)));
    let (t00, t10) = (t.texel(i0w, j0w), t.texel(i1w, j0w));
    let (t01, t11) = (t.texel(i0w, j1w), t.texel(i1w, j1w));
    core::array::from_fn(|c| {
        (1.0 - fx) * (1.0 - fy) * t00[c]
            + fx * (1.0 - fy) * t10[c]
            + (1.0 - fx) * fy * t01[c]
            + fx * fy * t11[c]
    })
}

/// The perspective-correct interpolation of `N` attributes at the centre of pixel `(px, py)`:
/// `values[k]` holds the attributes at vertex `k` (raw sub-pixel position `v[k]`), `w[k]` its
/// clip-space `w`; the result is `Σ b_k·values_k/w_k / Σ b_k/w_k` for the screen barycentrics
/// `b_k` of [`super::barycentric`].
///
/// `None` if the triangle is not valid: zero area, or a `w` that is not positive and finite. Outside
/// the triangle the value is extrapolated, and `None` where `Σ b_k/w_k ≤ 0` (behind the eye).
pub fn perspective_attributes<const N: usize>(
    v: [(i32, i32); 3],
    values: [[f64; N]; 3],
    w: [f64; 3],
    px: i32,
    py: i32,
) -> Option<[f64; N]> {
    if !w.iter().all(|&w| w.is_finite() && w > 0.0) {
        return None;
    }
    let b = barycentric(v, px, py)?;
    // Screen barycentrics divided by w are proportional to the barycentrics on the 3D triangle.
    let q: [f64; 3] = core::array::from_fn(|k| b[k] / w[k]);
    let den = q[0] + q[1] + q[2];
    if den.partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater) {
        return None;
    }
    Some(core::array::from_fn(|c| {
        (q[0] * values[0][c] + q[1] * values[1][c] + q[2] * values[2][c]) / den
    }))
}

/// Every pixel covered by the triangle `v` (raw sub-pixel vertices, top-left rule) inside the
/// clip rectangle `[x0, x0 + width) × [y0, y0 + height)`, with its perspective-correct texel
/// coordinates `[x, y]` interpolated from `uv` with the clip-space `w`s (see
/// [`perspective_attributes`]); row by row, top to bottom, left to right.
///
/// Empty for a zero-area triangle. Panics if a `w` is not positive and finite.
pub fn perspective_texel_coords(
    v: [(i32, i32); 3],
    uv: [[f64; 2]; 3],
    w: [f64; 3],
    x0: i32,
    y0: i32,
    width: u32,
    height: u32,
) -> Vec<(i32, i32, [f64; 2])> {
    assert!(
        w.iter().all(|&w| w.is_finite() && w > 0.0),
        "w must be positive and finite: {w:?}"
    );
    // Saturating the exclusive bound loses only pixel i32::MAX, whose centre (≈ 2³⁹ sub-pixel
    // units) no triangle with i32 vertices can cover.
    let end = |start: i32, len: u32| (i64::from(start) + i64::from(len)).min(i64::from(i32::MAX));
    let (x1, y1) = (end(x0, width) as i32, end(y0, height) as i32);
    let mut out = Vec::new();
    for_each_covered(v, x0, y0, x1, y1, |x, y| {
        // A covered pixel has barycentrics ≥ 0 (to rounding) summing to 1, so the denominator
        // is positive and the value exists.
        let c = perspective_attributes(v, uv, w, x, y)
            .expect("covered pixel of a valid triangle has perspective coordinates");
        out.push((x, y, c));
    });
    out
}

/// A texel modulated by a vertex colour of the same channel depth: `texel_k · factor_k / max_k`
/// per channel, where `max` holds the channel maxima (e.g. `[31, 63, 31]` for `Rgb565`), so a
/// factor at the maximum leaves the texel unchanged.
pub fn modulate(texel: [f64; 3], factor: [f64; 3], max: [f64; 3]) -> [f64; 3] {
    core::array::from_fn(|k| texel[k] * factor[k] / max[k])
}

/// A texel scaled by a light level in `[0, 1]`: `texel_k · level` per channel.
pub fn scale(texel: [f64; 3], level: f64) -> [f64; 3] {
    texel.map(|t| t * level)
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a / |a|`, or `None` for the zero vector.
fn normalize(a: [f64; 3]) -> Option<[f64; 3]> {
    let len = dot(a, a).sqrt();
    (len > 0.0).then(|| a.map(|x| x / len))
}

/// The Lambert diffuse factor `max(0, n̂·l̂)` for a surface normal and the direction to the light
/// (neither needs to be unit length). Panics if either is the zero vector.
pub fn lambert(normal: [f64; 3], to_light: [f64; 3]) -> f64 {
    let n = normalize(normal).expect("zero normal");
    let l = normalize(to_light).expect("zero light direction");
    dot(n, l).max(0.0)
}

/// The Blinn-Phong specular factor `max(0, n̂·ĥ)^shininess` with the half vector
/// `ĥ = normalize(l̂ + ê)` (all three inputs are normalised here); 0 when the light is behind the
/// surface (`n̂·l̂ ≤ 0`) or exactly opposite the eye (`l̂ + ê = 0`). Panics on a zero vector.
pub fn blinn_phong(normal: [f64; 3], to_light: [f64; 3], to_eye: [f64; 3], shininess: f64) -> f64 {
    let n = normalize(normal).expect("zero normal");
    let l = normalize(to_light).expect("zero light direction");
    let e = normalize(to_eye).expect("zero eye direction");
    if dot(n, l) <= 0.0 {
        return 0.0;
    }
    match normalize([l[0] + e[0], l[1] + e[1], l[2] + e[2]]) {
        Some(h) => dot(n, h).max(0.0).powf(shininess),
        // Light and eye exactly opposite: no half vector, no highlight.
        None => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::super::{covers, interpolate};
    use super::*;
    use std::vec;

    const ALL: [RefWrap; 3] = [RefWrap::Repeat, RefWrap::MirroredRepeat, RefWrap::Clamp];

    /// A 2 × 2 texture with distinct dyadic channel values (sums of products stay exact).
    fn two_by_two() -> RefTexture {
        RefTexture::new(
            2,
            2,
            vec![
                [0.0, 1.0, 2.0],
                [4.0, 5.0, 6.0],
                [8.0, 9.0, 10.0],
                [16.0, 17.0, 18.0],
            ],
        )
    }

    /// A 4 × 4 texture whose channels are linear in the texel index: `[i, j, i + 4j]`.
    fn linear_4x4() -> RefTexture {
        let texels = (0..16)
            .map(|k| {
                let (i, j) = (f64::from(k % 4), f64::from(k / 4));
                [i, j, i + 4.0 * j]
            })
            .collect();
        RefTexture::new(4, 4, texels)
    }

    /// A 3 × 1 texture: 0, 10, 20 in the first channel.
    fn three_by_one() -> RefTexture {
        RefTexture::new(3, 1, vec![[0.0; 3], [10.0, 0.0, 0.0], [20.0, 0.0, 0.0]])
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs().max(1.0)
    }

    #[test]
    fn texel_is_row_major_top_first() {
        let t = two_by_two();
        assert_eq!(t.texel(0, 0), [0.0, 1.0, 2.0]);
        assert_eq!(t.texel(1, 0), [4.0, 5.0, 6.0]);
        assert_eq!(t.texel(0, 1), [8.0, 9.0, 10.0]);
        assert_eq!(t.texel(1, 1), [16.0, 17.0, 18.0]);
    }

    #[test]
    #[should_panic]
    fn texel_outside_panics() {
        // (2, 0) would otherwise alias (0, 1).
        two_by_two().texel(2, 0);
    }

    #[test]
    #[should_panic]
    fn texel_count_must_match() {
        RefTexture::new(2, 2, vec![[0.0; 3]; 3]);
    }

    #[test]
    fn wrap_modes_by_hand() {
        // n = 3, i = -6..6.
        let repeat = [0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2];
        let mirrored = [0, 1, 2, 2, 1, 0, 0, 1, 2, 2, 1, 0];
        let clamp = [0, 0, 0, 0, 0, 0, 0, 1, 2, 2, 2, 2];
        for (k, i) in (-6..6).enumerate() {
            assert_eq!(wrap(i, 3, RefWrap::Repeat), repeat[k], "repeat {i}");
            assert_eq!(
                wrap(i, 3, RefWrap::MirroredRepeat),
                mirrored[k],
                "mirrored {i}"
            );
            assert_eq!(wrap(i, 3, RefWrap::Clamp), clamp[k], "clamp {i}");
        }
        // A 1-texel axis always maps to 0; extreme indices stay in range.
        for mode in ALL {
            for i in [i64::MIN, -7, -1, 0, 1, 8, i64::MAX] {
                assert_eq!(wrap(i, 1, mode), 0);
                assert!(wrap(i, 5, mode) < 5);
            }
        }
        assert_eq!(wrap(i64::MIN, 4, RefWrap::Repeat), 0);
        assert_eq!(wrap(i64::MAX, 4, RefWrap::Repeat), 3);
        assert_eq!(wrap(i64::MAX, 4, RefWrap::Clamp), 3);
        // Mirrored with n = 2: period 4 reading 0, 1, 1, 0; i64::MAX ≡ 3 (mod 4).
        assert_eq!(wrap(i64::MAX, 2, RefWrap::MirroredRepeat), 0);
    }

    #[test]
    fn nearest_by_hand() {
        let t = two_by_two();
        for mode in ALL {
            let m = [mode; 2];
            // Inside the texture every mode agrees: the texel containing the point.
            assert_eq!(nearest_texel(&t, m, 0.5, 0.5), (0, 0));
            assert_eq!(nearest_texel(&t, m, 1.99, 0.0), (1, 0));
            assert_eq!(nearest_texel(&t, m, 1.0, 1.0), (1, 1));
            assert_eq!(nearest_texel(&t, m, 0.999, 1.001), (0, 1));
            assert_eq!(nearest(&t, m, 1.25, 1.75), [16.0, 17.0, 18.0]);
        }
        // Just left of the texture (column -1) and just right (column 2).
        let at = |mode, x| nearest_texel(&t, [mode, RefWrap::Clamp], x, 1.5);
        assert_eq!(at(RefWrap::Repeat, -0.01), (1, 1));
        assert_eq!(at(RefWrap::MirroredRepeat, -0.01), (0, 1));
        assert_eq!(at(RefWrap::Clamp, -0.01), (0, 1));
        assert_eq!(at(RefWrap::Repeat, 2.0), (0, 1));
        assert_eq!(at(RefWrap::MirroredRepeat, 2.0), (1, 1));
        assert_eq!(at(RefWrap::Clamp, 2.0), (1, 1));
        // Column 3: repeat 1, mirrored 0 (period 0, 1, 1, 0), clamp 1.
        assert_eq!(at(RefWrap::Repeat, 3.5), (1, 1));
        assert_eq!(at(RefWrap::MirroredRepeat, 3.5), (0, 1));
        // Separate modes per axis: x repeats, y clamps.
        let m = [RefWrap::Repeat, RefWrap::Clamp];
        assert_eq!(nearest_texel(&t, m, -1.5, -5.0), (0, 0));
        assert_eq!(nearest_texel(&t, m, 5.5, 9.0), (1, 1));
    }

    #[test]
    fn nearest_on_linear_texture() {
        let t = linear_4x4();
        for k in -40..40 {
            for l in -40..40 {
                let (x, y) = (f64::from(k) * 0.3 + 0.01, f64::from(l) * 0.3 + 0.02);
                let s = nearest(&t, [RefWrap::Repeat; 2], x, y);
                let want = [
                    x.floor().rem_euclid(4.0),
                    y.floor().rem_euclid(4.0),
                    x.floor().rem_euclid(4.0) + 4.0 * y.floor().rem_euclid(4.0),
                ];
                assert_eq!(s, want, "({x}, {y})");
            }
        }
    }

    #[test]
    fn boundary_distance_by_hand() {
        assert_eq!(boundary_distance(0.5, 0.5), 0.5);
        assert_eq!(boundary_distance(3.0, 0.5), 0.0);
        assert_eq!(boundary_distance(-0.25, 3.5), 0.25);
        assert_eq!(boundary_distance(1.5, 2.875), 0.125);
        assert_eq!(boundary_distance(-7.5, -7.5), 0.5);
        assert!(close(boundary_distance(1.1, 2.45), 0.1));
    }

    #[test]
    fn bilinear_at_texel_centres_is_the_texel() {
        let t = two_by_two();
        for mode in ALL {
            for j in 0..2 {
                for i in 0..2 {
                    let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                    assert_eq!(bilinear(&t, [mode; 2], x, y), t.texel(i, j));
                }
            }
        }
    }

    #[test]
    fn bilinear_2x2_by_hand() {
        let t = two_by_two();
        for mode in ALL {
            let m = [mode; 2];
            // The shared corner of the four texels: their mean.
            assert_eq!(bilinear(&t, m, 1.0, 1.0), [7.0, 8.0, 9.0]);
            // (0.75, 1.25): fx = 0.25, fy = 0.75; weights 0.1875, 0.0625, 0.5625, 0.1875:
            // 0·0.1875 + 4·0.0625 + 8·0.5625 + 16·0.1875 = 7.75 (+1, +2 for the other channels).
            assert_eq!(bilinear(&t, m, 0.75, 1.25), [7.75, 8.75, 9.75]);
            // Half-way between the two top centres.
            assert_eq!(bilinear(&t, m, 1.0, 0.5), [2.0, 3.0, 4.0]);
        }
    }

    #[test]
    fn bilinear_3x1_wraps_each_index() {
        let t = three_by_one();
        let s = |mode, x: f64, y: f64| bilinear(&t, [mode, RefWrap::Repeat], x, y)[0];
        for mode in ALL {
            // Interior: between centres 0.5 / 1.5 and 1.5 / 2.5.
            assert_eq!(s(mode, 1.0, 0.5), 5.0);
            assert_eq!(s(mode, 2.25, 0.5), 17.5);
            // A 1-texel column: every y gives the same row.
            assert_eq!(s(mode, 2.25, 0.9), 17.5);
            assert_eq!(s(mode, 2.25, -3.3), 17.5);
        }
        // x = 0: x' = -0.5, indices -1 and 0 with fx = 0.5.
        assert_eq!(s(RefWrap::Repeat, 0.0, 0.5), 10.0); // (20 + 0) / 2
        assert_eq!(s(RefWrap::MirroredRepeat, 0.0, 0.5), 0.0); // -1 → 0
        assert_eq!(s(RefWrap::Clamp, 0.0, 0.5), 0.0);
        // x = 3: indices 2 and 3 with fx = 0.5.
        assert_eq!(s(RefWrap::Repeat, 3.0, 0.5), 10.0); // (20 + 0) / 2
        assert_eq!(s(RefWrap::MirroredRepeat, 3.0, 0.5), 20.0); // 3 → 2
        assert_eq!(s(RefWrap::Clamp, 3.0, 0.5), 20.0);
        // x = 3.25 (Repeat): indices 2, 3 → 2, 0 with fx = 0.75: 20·0.25 = 5.
        assert_eq!(s(RefWrap::Repeat, 3.25, 0.5), 5.0);
        // Repeat tiles: shifting by the width changes nothing.
        for k in 0..30 {
            let x = f64::from(k) * 0.125 - 1.0;
            assert_eq!(s(RefWrap::Repeat, x, 0.5), s(RefWrap::Repeat, x + 3.0, 0.5));
        }
    }

    #[test]
    fn bilinear_reproduces_a_linear_texture() {
        // Inside [0.5, 3.5]² (between the outermost centres) wrapping never contributes a weight,
        // and a texture linear in the texel index is reproduced exactly: channel 0 = x − 0.5.
        let t = linear_4x4();
        for mode in ALL {
            for k in 0..=24 {
                for l in 0..=24 {
                    let (x, y) = (0.5 + f64::from(k) * 0.125, 0.5 + f64::from(l) * 0.125);
                    let s = bilinear(&t, [mode; 2], x, y);
                    let want = [x - 0.5, y - 0.5, (x - 0.5) + 4.0 * (y - 0.5)];
                    for c in 0..3 {
                        assert!(close(s[c], want[c]), "({x}, {y}): {s:?} vs {want:?}");
                    }
                }
            }
        }
        // Clamp outside: the edge value continues (channel 0 is 0 left, 3 right).
        let c = [RefWrap::Clamp; 2];
        assert_eq!(bilinear(&t, c, -5.0, 2.0)[0], 0.0);
        assert_eq!(bilinear(&t, c, 9.0, 2.0)[0], 3.0);
        // Repeat at x = 0: texels 3 and 0 blended half-half.
        assert_eq!(bilinear(&t, [RefWrap::Repeat; 2], 0.0, 2.0)[0], 1.5);
    }

    /// The corner triangle with legs of 4 px from pixel corner (0, 0), raw sub-pixel units.
    const CORNER: [(i32, i32); 3] = [(0, 0), (1024, 0), (0, 1024)];

    #[test]
    fn equal_w_is_affine() {
        // uv = the vertex positions in pixels: the texel coordinate is the pixel centre.
        let uv = [[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]];
        for w in [[1.0; 3], [7.5; 3]] {
            let got = perspective_texel_coords(CORNER, uv, w, -2, -2, 10, 10);
            assert_eq!(got.len(), 6);
            for (x, y, c) in got {
                assert!(covers(CORNER, x, y));
                assert!(close(c[0], f64::from(x) + 0.5), "{c:?}");
                assert!(close(c[1], f64::from(y) + 0.5), "{c:?}");
            }
        }
        // Arbitrary uv with equal w: the same as the parent module's affine interpolation.
        let uv = [[3.0, -1.0], [0.25, 9.0], [12.0, 5.5]];
        for (x, y, c) in perspective_texel_coords(CORNER, uv, [2.0; 3], 0, 0, 4, 4) {
            let ch = uv.map(|p| [p[0], p[1], 0.0]);
            let want = interpolate(CORNER, ch, x, y).unwrap();
            assert!(close(c[0], want[0]) && close(c[1], want[1]), "({x}, {y})");
        }
    }

    #[test]
    fn perspective_by_hand() {
        // At the centre of pixel (1, 2) the screen barycentrics are (0, 0.375, 0.625). With
        // w = (1, 2, 4): Σ b/w = 0.1875 + 0.15625 = 0.34375 = 11/32; u = 0.375·4/2 / (11/32)
        // = 24/11, v = 0.625·4/4 / (11/32) = 20/11.
        let uv = [[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]];
        let w = [1.0, 2.0, 4.0];
        let c = perspective_attributes(CORNER, uv, w, 1, 2).unwrap();
        assert!(
            close(c[0], 24.0 / 11.0) && close(c[1], 20.0 / 11.0),
            "{c:?}"
        );
        // Scaling every w by the same factor changes nothing.
        let c2 = perspective_attributes(CORNER, uv, w.map(|w| w * 3.0), 1, 2).unwrap();
        assert!(close(c2[0], c[0]) && close(c2[1], c[1]));
        // At a vertex the attribute is that vertex's own value (pixel corner (0,0) isn't a
        // centre, so use a triangle with a vertex on the centre of pixel (0, 0)).
        let v = [(128, 128), (128 + 1024, 128), (128, 128 + 1024)];
        let c = perspective_attributes(v, [[5.0], [-1.0], [2.0]], w, 0, 0).unwrap();
        assert!(close(c[0], 5.0));
    }

    #[test]
    fn perspective_matches_a_projected_3d_triangle() {
        // 3D points (0,0,1), (8,0,2), (0,16,4) seen by a pinhole camera at the origin, screen =
        // (X/Z, Y/Z) in pixels: (0,0), (4,0), (0,4), w = Z. The plane through them is
        // −2X − 3Y + 16Z = 16, so the ray through screen point (sx, sy) meets it at
        // Z = 16 / (16 − 2sx − 3sy), X = sx·Z, Y = sy·Z. The perspective-correct interpolation
        // of the vertices' (X, Y, Z) must land exactly there.
        let values = [[0.0, 0.0, 1.0], [8.0, 0.0, 2.0], [0.0, 16.0, 4.0]];
        let w = [1.0, 2.0, 4.0];
        let mut n = 0;
        for_each_covered(CORNER, -1, -1, 6, 6, |px, py| {
            let (sx, sy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
            let z = 16.0 / (16.0 - 2.0 * sx - 3.0 * sy);
            let got = perspective_attributes(CORNER, values, w, px, py).unwrap();
            let want = [sx * z, sy * z, z];
            for c in 0..3 {
                assert!(close(got[c], want[c]), "({px}, {py}): {got:?} vs {want:?}");
            }
            n += 1;
        });
        assert_eq!(n, 6);
    }

    #[test]
    fn texel_coords_follow_coverage_and_clip() {
        let uv = [[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]];
        let w = [1.0; 3];
        let pixels = |x0, y0, wd, ht| -> Vec<(i32, i32)> {
            perspective_texel_coords(CORNER, uv, w, x0, y0, wd, ht)
                .into_iter()
                .map(|(x, y, _)| (x, y))
                .collect()
        };
        // The 6 covered pixels (i + j < 3), rows top to bottom, left to right.
        let all = [(0, 0), (1, 0), (2, 0), (0, 1), (1, 1), (0, 2)];
        assert_eq!(pixels(-5, -5, 20, 20), all);
        assert_eq!(pixels(0, 0, 3, 3), all);
        // Clipped to the rectangle [1, 9) × [0, 1).
        assert_eq!(pixels(1, 0, 8, 1), [(1, 0), (2, 0)]);
        assert_eq!(pixels(0, 1, 1, 1), [(0, 1)]);
        assert!(pixels(0, 0, 0, 5).is_empty());
        assert!(pixels(3, 0, 5, 5).is_empty());
        // A clip reaching the end of the i32 range is fine.
        assert!(pixels(i32::MAX - 1, 0, u32::MAX, 4).is_empty());
        assert_eq!(pixels(i32::MIN, i32::MIN, u32::MAX, u32::MAX), all);
        // Either winding gives the same pixels and coordinates.
        let flipped = [CORNER[0], CORNER[2], CORNER[1]];
        let fuv = [uv[0], uv[2], uv[1]];
        let a = perspective_texel_coords(flipped, fuv, [1.0, 4.0, 2.0], 0, 0, 8, 8);
        let b = perspective_texel_coords(CORNER, uv, [1.0, 2.0, 4.0], 0, 0, 8, 8);
        assert_eq!(a.len(), b.len());
        for ((xa, ya, ca), (xb, yb, cb)) in a.into_iter().zip(b) {
            // The sums run in another order: equal to rounding.
            assert_eq!((xa, ya), (xb, yb));
            assert!(close(ca[0], cb[0]) && close(ca[1], cb[1]));
        }
    }

    #[test]
    fn invalid_triangles() {
        let degenerate = [(0, 0), (512, 512), (1024, 1024)];
        let uv = [[0.0; 2]; 3];
        assert!(perspective_texel_coords(degenerate, uv, [1.0; 3], -4, -4, 16, 16).is_empty());
        assert!(perspective_attributes(degenerate, uv, [1.0; 3], 0, 0).is_none());
        for w in [[0.0, 1.0, 1.0], [1.0, -2.0, 1.0], [1.0, 1.0, f64::NAN]] {
            assert!(perspective_attributes(CORNER, uv, w, 0, 0).is_none());
        }
        // Far outside, with very unequal w, the extrapolated Σ b/w turns negative: no value.
        // At pixel (-20, 0) b = (5.75, -4.875, 0.125): with w = (4, 1, 1), Σ b/w = -3.3125.
        assert!(perspective_attributes(CORNER, uv, [4.0, 1.0, 1.0], -20, 0).is_none());
    }

    #[test]
    #[should_panic]
    fn texel_coords_reject_non_positive_w() {
        perspective_texel_coords(CORNER, [[0.0; 2]; 3], [1.0, 0.0, 1.0], 0, 0, 4, 4);
    }

    #[test]
    fn modulate_and_scale_by_hand() {
        let max = [31.0, 63.0, 31.0];
        // A white vertex colour leaves the texel unchanged; black gives black.
        assert_eq!(modulate([16.0, 32.0, 8.0], max, max), [16.0, 32.0, 8.0]);
        assert_eq!(modulate([16.0, 32.0, 8.0], [0.0; 3], max), [0.0; 3]);
        // Per channel: red full, green off, blue full.
        assert_eq!(
            modulate([31.0, 63.0, 0.0], [31.0, 0.0, 31.0], max),
            [31.0, 0.0, 0.0]
        );
        // Red 31 · 15.5 / 31 = 15.5; green 63 · 21 / 63 = 21; blue 10 · 3.1 / 31 = 1.
        let got = modulate([31.0, 63.0, 10.0], [15.5, 21.0, 3.1], max);
        assert!(close(got[0], 15.5) && close(got[1], 21.0) && close(got[2], 1.0));
        assert_eq!(scale([31.0, 63.0, 8.0], 0.5), [15.5, 31.5, 4.0]);
        assert_eq!(scale([31.0, 63.0, 8.0], 0.0), [0.0; 3]);
        assert_eq!(scale([31.0, 63.0, 8.0], 1.0), [31.0, 63.0, 8.0]);
    }

    #[test]
    fn lambert_by_hand() {
        let n = [0.0, 0.0, 2.0];
        assert!(close(lambert(n, [0.0, 0.0, 5.0]), 1.0));
        assert!(close(lambert(n, [1.0, 0.0, 1.0]), 0.5f64.sqrt()));
        // 60° from the normal: cos = 0.5.
        assert!(close(lambert(n, [3.0f64.sqrt(), 0.0, 1.0]), 0.5));
        assert_eq!(lambert(n, [1.0, 0.0, 0.0]), 0.0);
        assert_eq!(lambert(n, [0.0, 1.0, -1.0]), 0.0);
    }

    #[test]
    fn blinn_phong_by_hand() {
        let n = [0.0, 0.0, 3.0];
        // Mirror configuration: the half vector is the normal, full highlight for any exponent.
        for s in [1.0, 8.0, 64.0] {
            assert!(close(
                blinn_phong(n, [1.0, 0.0, 1.0], [-2.0, 0.0, 2.0], s),
                1.0
            ));
        }
        // Light along the normal, eye grazing along +x: ĥ = (1, 0, 1)/√2, n̂·ĥ = 1/√2; squared 0.5.
        assert!(close(
            blinn_phong(n, [0.0, 0.0, 1.0], [4.0, 0.0, 0.0], 2.0),
            0.5
        ));
        assert!(close(
            blinn_phong(n, [0.0, 0.0, 1.0], [4.0, 0.0, 0.0], 4.0),
            0.25
        ));
        // Light and eye both at 60° on the same side: ĥ is their bisector at 60°, cos = 0.5.
        let d = [3.0f64.sqrt(), 0.0, 1.0];
        assert!(close(blinn_phong(n, d, d, 3.0), 0.125));
        // Light behind the surface, or exactly opposite the eye: no highlight.
        assert_eq!(blinn_phong(n, [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], 8.0), 0.0);
        assert_eq!(blinn_phong(n, [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 8.0), 0.0);
        assert_eq!(blinn_phong(n, [1.0, 0.0, 1.0], [-1.0, 0.0, -1.0], 8.0), 0.0);
    }
}
