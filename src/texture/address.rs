//! Texel addressing: an integer texel index anywhere in `i32` to a texel of the texture, by the
//! axis's wrap mode. Power-of-two sizes take a mask (repeat), a mask and an exclusive or
//! (mirrored repeat); other sizes a remainder, skipped when the index is already inside.

/// How texel indices outside `0..size` are brought inside, per axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Wrap {
    /// The texture tiles the plane: index `i` reads texel `i mod size`.
    #[default]
    Repeat,
    /// Tiles alternate with their mirror images: `0 1 … n−1 n−1 … 1 0 0 1 …`.
    MirroredRepeat,
    /// Indices outside are the nearest edge texel's (OpenGL's clamp to edge).
    Clamp,
}

/// One axis of a texture: its size (1 to [`MAX_SIZE`](super::MAX_SIZE)) and wrap mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Axis {
    size: u32,
    /// `log2(size)` for power-of-two sizes.
    shift: Option<u32>,
    wrap: Wrap,
}

impl Axis {
    /// An axis of `size` texels (1 to 2¹⁵, checked by the texture).
    pub(crate) fn new(size: u32, wrap: Wrap) -> Self {
        Axis {
            size,
            shift: size.is_power_of_two().then(|| size.trailing_zeros()),
            wrap,
        }
    }

    /// The axis with wrap mode `wrap`.
    pub(crate) fn with_wrap(self, wrap: Wrap) -> Self {
        Axis { wrap, ..self }
    }

    /// The number of texels.
    #[inline(always)]
    pub(crate) fn size(&self) -> u32 {
        self.size
    }

    /// `log2(size)` for a power-of-two size.
    #[inline(always)]
    pub(crate) fn shift(&self) -> Option<u32> {
        self.shift
    }

    /// The wrap mode.
    #[inline(always)]
    pub(crate) fn wrap(&self) -> Wrap {
        self.wrap
    }

    /// The texel (in `0..size`) that index `i` reads.
    #[inline(always)]
    pub(crate) fn index(&self, i: i32) -> u32 {
        let n = self.size;
        match (self.wrap, self.shift) {
            (Wrap::Repeat, Some(_)) => i as u32 & (n - 1),
            (Wrap::MirroredRepeat, Some(s)) => {
                // Bit `s` tells an odd tile, whose indices run backwards: !i = −1 − i there.
                let odd = ((i >> s) & 1).wrapping_neg();
                (i ^ odd) as u32 & (n - 1)
            }
            // `max` and `min`, not `clamp`: its bounds check would be a panic path.
            (Wrap::Clamp, _) => i.max(0).min(n as i32 - 1) as u32,
            (Wrap::Repeat, None) if (i as u32) < n => i as u32,
            (Wrap::Repeat, None) => rem_euclid(i, n),
            (Wrap::MirroredRepeat, None) => {
                let m = if (i as u32) < n {
                    i as u32
                } else {
                    rem_euclid(i, 2 * n)
                };
                if m < n {
                    m
                } else {
                    2 * n - 1 - m
                }
            }
        }
    }
}

/// `i mod n` in `0..n` for `1 ≤ n ≤ 2¹⁶` (a division: the slow path of sizes that are not powers
/// of two).
#[cold]
#[inline(never)]
fn rem_euclid(i: i32, n: u32) -> u32 {
    // i + 2³¹ is in 0..2³², and 2³¹ mod n is added back as (n − 2³¹ mod n) to stay positive.
    let shifted = (i as u32) ^ (1 << 31);
    let offset = (1u32 << 31).checked_rem(n).unwrap_or(0);
    let r = shifted.checked_rem(n).unwrap_or(0);
    // (i + 2³¹) mod n − 2³¹ mod n, brought into 0..n.
    if r >= offset {
        r - offset
    } else {
        r + n - offset
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every mode and size against the definitions, stated with `i64` Euclidean remainders.
    #[test]
    fn indices_wrap_as_defined() {
        let mut next = crate::random(0x7e47_0001);
        for size in (1..=70).chain([127, 128, 256, 1000, 1024, 1 << 15]) {
            for wrap in [Wrap::Repeat, Wrap::MirroredRepeat, Wrap::Clamp] {
                let axis = Axis::new(size, wrap);
                let n = i64::from(size);
                let edges = [i32::MIN, i32::MIN + 1, -1, 0, 1, i32::MAX - 1, i32::MAX];
                let near = (-3 * size as i32..3 * size as i32).step_by(1 + size as usize / 64);
                let random = (0..200).map(|_| next() as i32);
                for i in edges.into_iter().chain(near).chain(random) {
                    let want = match wrap {
                        Wrap::Repeat => i64::from(i).rem_euclid(n),
                        Wrap::MirroredRepeat => {
                            let m = i64::from(i).rem_euclid(2 * n);
                            if m < n {
                                m
                            } else {
                                2 * n - 1 - m
                            }
                        }
                        Wrap::Clamp => i64::from(i).clamp(0, n - 1),
                    };
                    assert_eq!(i64::from(axis.index(i)), want, "{wrap:?} {size} {i}");
                }
            }
        }
    }
}
