//! Reading an implementation's texel coordinates to a fraction of a texel through a coordinate
//! texture (tests/all/perspective.rs and tests/all/textured_mesh.rs, each with its `probe`).

#![allow(dead_code)]

/// The texel coordinates at each written pixel, modulo the coordinate texture's size and to
/// within `1/(2·steps)` texel, from `base` (the texel index each pixel took, `None` where
/// nothing was written) and `moved(j)`: the same indices drawn with every texture coordinate
/// moved by `j/steps` texel (both texel axes growing), for `j = 1, 2, …, steps − 1`. The computed
/// coordinates move by exactly that (an offset common to the vertices adds to the base value
/// and leaves the differences, so the steps too, unchanged), so the first `j` at which a pixel's
/// texel changes tells the fraction of its coordinate.
pub fn coordinates(
    base: &[Option<(u32, u32)>],
    steps: u32,
    mut moved: impl FnMut(u32) -> Vec<Option<(u32, u32)>>,
) -> Vec<Option<[f64; 2]>> {
    let mut first = vec![[steps; 2]; base.len()];
    for j in 1..steps {
        let got = moved(j);
        for i in 0..base.len() {
            if let (Some(b), Some(g)) = (base[i], got[i]) {
                for (a, changed) in [g.0 != b.0, g.1 != b.1].into_iter().enumerate() {
                    if changed && first[i][a] == steps {
                        first[i][a] = j;
                    }
                }
            }
        }
    }
    // floor(c + j/steps) > floor(c) first at j: the fraction is in [1 − j/steps, 1 − (j−1)/steps).
    let s = f64::from(steps);
    base.iter()
        .zip(first)
        .map(|(b, f)| {
            b.map(|(x, y)| {
                [
                    f64::from(x) + 1.0 - (f64::from(f[0]) - 0.5) / s,
                    f64::from(y) + 1.0 - (f64::from(f[1]) - 0.5) / s,
                ]
            })
        })
        .collect()
}

/// `v` (known modulo 256) brought within 128 of `near`.
pub fn unwrap_near(v: f64, near: f64) -> f64 {
    v + 256.0 * ((near - v) / 256.0).round()
}
