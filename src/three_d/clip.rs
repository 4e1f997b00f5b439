//! Clipping in homogeneous clip space, before any division.
//!
//! A triangle is tested against seven planes: near `z ≥ −w`, far `z ≤ w`, `w ≥ 2⁻⁸`, and a guard
//! band `|x| ≤ g_x·w`, `|y| ≤ g_y·w` around the viewport. The guard band is chosen per draw so
//! that every projected vertex inside it lies within about 1000 px of the viewport's centre:
//! triangles inside it are drawn without clipping and are compact for the raster core (bounding
//! boxes under 2048 px). Triangles wholly outside one plane are dropped; the rare ones crossing a
//! plane are clipped (Sutherland–Hodgman into a `heapless::Vec`). The intersection on an edge is
//! always computed from its inside end, so two triangles sharing an edge get bit-identical
//! clipped vertices and stay watertight.

use heapless::Vec as HVec;

use super::math::{sat32, zip_with, Bary};

/// Smallest `w` kept by clipping (raw `I16F16`, 2⁻⁸).
pub(crate) const W_MIN: i64 = 256;

/// Number of clip planes.
const PLANES: usize = 7;

/// Largest guard band factor (8 fractional bits): 64.
const MAX_GUARD: i64 = 64 << 8;

/// Projected vertices inside the guard band lie within this many pixels of the viewport's
/// centre on each axis, so the triangles between them are under 2048 px across.
pub(crate) const GUARD_PIXELS: i64 = 1000;

/// A clip-space vertex with its barycentric coordinates in the original triangle.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ClipVertex {
    /// Raw `I16F16` `[x, y, z, w]`.
    pub(crate) p: [i32; 4],
    pub(crate) bary: Bary,
}

/// Up to 3 + [`PLANES`] vertices.
pub(crate) type Polygon = HVec<ClipVertex, 12>;

/// The view volume of one draw: the fixed planes and the guard band.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ClipVolume {
    /// Guard band factors `g_x`, `g_y` with 8 fractional bits, in `[1, 64]`.
    guard: [i32; 2],
}

impl ClipVolume {
    /// The volume for a viewport of `width × height` pixels: a guard band reaching
    /// [`GUARD_PIXELS`] from its centre (at least the viewport itself, at most 64 times it).
    pub(crate) fn new(width: i64, height: i64) -> Self {
        let factor = |side: i64| {
            let half = (side / 2).max(1);
            (GUARD_PIXELS * 256 / half).clamp(256, MAX_GUARD)
        };
        ClipVolume {
            guard: [factor(width), factor(height)].map(|g| g as i32),
        }
    }

    /// Signed distance of `p` to plane `k` (inside where `≥ 0`), in raw units (the guard planes'
    /// scaled by 256).
    #[inline(always)]
    fn distance(&self, k: usize, p: &[i32; 4]) -> i64 {
        let [x, y, z, w] = p.map(i64::from);
        let [gx, gy] = self.guard.map(i64::from);
        match k {
            0 => z + w,
            1 => w - z,
            2 => w - W_MIN,
            3 => gx * w - (x << 8),
            4 => gx * w + (x << 8),
            5 => gy * w - (y << 8),
            _ => gy * w + (y << 8),
        }
    }

    /// Whether every point of the convex hull of `corners` (clip-space points, each the rounded
    /// transform of a model-space point) is inside every plane once transformed and rounded the
    /// same way: then no vertex of a mesh inside the corners' model-space box needs its
    /// outcode.
    ///
    /// A plane's distance is a linear form `f` whose coefficients sum to `m` in magnitude (2
    /// for near and far, 1 for `w`, `g + 256` for the guard planes), and rounding each
    /// coordinate to the nearest integer moves `f` by at most `m/2`. The exact transform is
    /// affine, so at a point of the hull it is the convex combination of the corners' exact
    /// transforms: each corner's rounded distance at least `m` puts every exact one at least
    /// `m/2`, the point's exact distance at least `m/2`, and its rounded one at least 0.
    pub(crate) fn holds(&self, corners: &[[i32; 4]]) -> bool {
        let [gx, gy] = self.guard.map(i64::from);
        let margin = [2, 2, 1, gx + 256, gx + 256, gy + 256, gy + 256];
        corners
            .iter()
            .all(|p| (0..PLANES).all(|k| self.distance(k, p) >= margin[k]))
    }

    /// Bit `k` is set when `p` is outside plane `k`.
    #[inline(always)]
    pub(crate) fn outcode(&self, p: &[i32; 4]) -> u8 {
        if self.inside(p) {
            0
        } else {
            self.outcode_outside(p)
        }
    }

    /// Whether `p` is inside every plane: the common case, tested first.
    #[inline(always)]
    fn inside(&self, p: &[i32; 4]) -> bool {
        let [x, y, z, w] = p.map(i64::from);
        // 32 × 32-bit products: the factors are below 2¹⁵.
        let [gx, gy] = self.guard.map(i64::from);
        // `|v| ≤ l` as one unsigned comparison, `v + l ≤ 2l`, for `l ≥ 0` (below 2⁴⁸ here).
        let within = |v: i64, l: i64| (v + l) as u64 <= (2 * l) as u64;
        w >= W_MIN && within(z, w) && within(x << 8, gx * w) && within(y << 8, gy * w)
    }

    /// [`outcode`](Self::outcode) of a point outside some plane.
    #[inline(never)]
    fn outcode_outside(&self, p: &[i32; 4]) -> u8 {
        (0..PLANES).fold(0, |code, k| code | (u8::from(self.distance(k, p) < 0) << k))
    }

    /// Clips `poly` against every plane. Returns `false` if nothing is left.
    pub(crate) fn clip(&self, poly: &mut Polygon) -> bool {
        let mut out = Polygon::new();
        for k in 0..PLANES {
            out.clear();
            let n = poly.len();
            for i in 0..n {
                let (Some(a), Some(b)) = (poly.get(i), poly.get((i + 1) % n)) else {
                    continue;
                };
                let (da, db) = (self.distance(k, &a.p), self.distance(k, &b.p));
                if da >= 0 {
                    let _ = out.push(*a);
                }
                if (da >= 0) != (db >= 0) {
                    let v = if da >= 0 {
                        intersect(a, da, b, db)
                    } else {
                        intersect(b, db, a, da)
                    };
                    let _ = out.push(v);
                }
            }
            core::mem::swap(poly, &mut out);
            if poly.len() < 3 {
                return false;
            }
        }
        true
    }
}

/// The point where the edge from `inside` (distance `di ≥ 0`) to `outside` (`d_o < 0`) crosses
/// the plane. Always evaluated from the inside end, so both triangles sharing the edge agree.
fn intersect(inside: &ClipVertex, di: i64, outside: &ClipVertex, d_o: i64) -> ClipVertex {
    let den = di - d_o;
    // t = di / den with 30 fractional bits; shift both down so that di·2^30 fits.
    let s = (64 - den.leading_zeros()).saturating_sub(32);
    let (n, d) = (di >> s, (den >> s).max(1));
    let t = ((n << 30) / d).clamp(0, 1 << 30);
    let lerp = |a: i32, b: i32| {
        let (a, b) = (i64::from(a), i64::from(b));
        sat32(a + (((b - a) * t + (1 << 29)) >> 30))
    };
    ClipVertex {
        p: zip_with(inside.p, outside.p, lerp),
        bary: zip_with(inside.bary, outside.bary, lerp),
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    fn cv(p: [i32; 4]) -> ClipVertex {
        ClipVertex { p, bary: [0; 3] }
    }

    #[test]
    fn clipping_is_symmetric_in_edge_direction() {
        let volume = ClipVolume::new(320, 240);
        let a = cv([1 << 16, 2 << 16, -5 << 16, 3 << 16]);
        let b = cv([-3 << 16, 1 << 16, 2 << 16, 1 << 15]);
        let mut p1 = Polygon::new();
        let mut p2 = Polygon::new();
        for v in [a, b, cv([0, 0, 0, 2 << 16])] {
            let _ = p1.push(v);
        }
        for v in [b, a, cv([1 << 16, -(1 << 16), 0, 2 << 16])] {
            let _ = p2.push(v);
        }
        assert!(volume.clip(&mut p1) && volume.clip(&mut p2));
        let on_near = |p: &Polygon| {
            let mut v: std::vec::Vec<[i32; 4]> = p
                .iter()
                .map(|v| v.p)
                .filter(|p| volume.distance(0, p).abs() <= 2)
                .collect();
            v.sort();
            v
        };
        assert!(!on_near(&p1).is_empty());
        let shared: std::vec::Vec<_> = on_near(&p1)
            .into_iter()
            .filter(|p| on_near(&p2).contains(p))
            .collect();
        assert_eq!(shared.len(), 1);
    }

    #[test]
    fn outcodes_and_guard_band() {
        // 320 px wide: the guard band reaches 1000 px from the centre, 6.25 half-widths.
        let volume = ClipVolume::new(320, 240);
        assert_eq!(volume.guard, [1600, 2133]);
        assert_eq!(volume.outcode(&[0, 0, 0, 1 << 16]), 0);
        assert_eq!(volume.outcode(&[0, 0, -(2 << 16), 1 << 16]), 1);
        assert_eq!(volume.outcode(&[0, 0, 2 << 16, 1 << 16]), 2);
        assert_eq!(volume.outcode(&[(25 << 16) / 4, 0, 0, 1 << 16]), 0);
        assert_eq!(volume.outcode(&[(25 << 16) / 4 + 1, 0, 0, 1 << 16]), 1 << 3);
        assert_eq!(volume.outcode(&[0, -(9 << 16), 0, 1 << 16]), 1 << 6);
        // A huge viewport keeps at least the viewport itself; a tiny one at most 64 times it.
        assert_eq!(ClipVolume::new(60_000, 2).guard, [256, MAX_GUARD as i32]);
    }
}
