//! [`Mesh`]: the indexed triangle mesh the [`Pipeline`](super::Pipeline) draws, a borrowed view of
//! arrays that typically live in flash, with optional per-vertex normals, colours and texture
//! coordinates; [`Bounds`] for placing it.

use embedded_graphics::pixelcolor::Rgb888;

use super::math::{Mat4, Scalar, ToScalar, Vec3};

/// A texture coordinate: `u` to the right, `v` up, `(0, 0)` at the bottom-left corner of the
/// texture image and `(1, 1)` at its top-right (the OBJ and OpenGL convention; values outside
/// `[0, 1]` are for wrapping textures).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
#[repr(C)]
pub struct TexCoord {
    /// Horizontal coordinate.
    pub u: Scalar,
    /// Vertical coordinate, up.
    pub v: Scalar,
}

// SAFETY: `TexCoord` is `repr(C)`: two `I16F16`s (`repr(transparent)` `i32`s), `u` at 0 and
// `v` at 4, 8 bytes, 4-byte aligned, no padding (asserted below).
#[allow(unsafe_code)]
unsafe impl crate::arch::CoordinatePair for TexCoord {}

const _: () = {
    use core::mem::{align_of, offset_of, size_of};
    assert!(size_of::<TexCoord>() == 8 && align_of::<TexCoord>() == 4);
    assert!(offset_of!(TexCoord, u) == 0 && offset_of!(TexCoord, v) == 4);
};

impl TexCoord {
    /// A texture coordinate from floats, integers or [`Scalar`]s (see [`ToScalar`]).
    pub fn new(u: impl ToScalar, v: impl ToScalar) -> Self {
        TexCoord {
            u: u.to_scalar(),
            v: v.to_scalar(),
        }
    }

    /// A texture coordinate from raw `I16F16` bits (`65536` is `1.0`); usable in `const` data.
    pub const fn from_bits(u: i32, v: i32) -> Self {
        TexCoord {
            u: Scalar::from_bits(u),
            v: Scalar::from_bits(v),
        }
    }

    /// The raw components `[u, v]`.
    pub const fn to_bits(self) -> [i32; 2] {
        [self.u.to_bits(), self.v.to_bits()]
    }
}

/// An indexed triangle mesh, typically in flash (`&'static` slices).
///
/// Per vertex `i`: the position `vertices[i]` and, optionally, the unit normal `normals[i]`, the
/// colour `colors[i]` and the texture coordinate `uvs[i]`. Each optional array is either empty
/// or exactly as long as `vertices`, and every index refers to a vertex: [`Mesh::validate`]
/// reports the first violation as a [`MeshError`] (it is a `const fn`, so a `const` mesh can be
/// checked at compile time). Drawing never panics on an inconsistent mesh: a missing normal is
/// taken from the face, a triangle with an index out of range is skipped (and counted in
/// [`DrawStats::invalid`](super::DrawStats::invalid)). Front faces are counter-clockwise seen from
/// outside (right-handed: the face normal `(v1 − v0) × (v2 − v0)` points out).
///
/// Colours are [`Rgb888`] whatever the target's format, so one mesh in flash serves every
/// display; they convert to any embedded-graphics colour with `From`. The pipeline draws with
/// the [`Material`](super::Material)'s colour today; vertex colours and texture coordinates are
/// carried for the shading that will use them.
///
/// # Examples
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb888;
/// use embedded_raster::three_d::{Mesh, TexCoord, Vec3};
///
/// static VERTICES: [Vec3; 3] = [
///     Vec3::from_bits(0, 0, 0),
///     Vec3::from_bits(2 << 16, 0, 0),
///     Vec3::from_bits(0, 2 << 16, 0),
/// ];
/// static INDICES: [[u16; 3]; 1] = [[0, 1, 2]];
/// static COLORS: [Rgb888; 3] = [Rgb888::new(255, 0, 0), Rgb888::new(0, 255, 0), Rgb888::new(0, 0, 255)];
/// static UVS: [TexCoord; 3] =
///     [TexCoord::from_bits(0, 0), TexCoord::from_bits(1 << 16, 0), TexCoord::from_bits(0, 1 << 16)];
/// // No normals: faces give them.
/// static TRIANGLE: Mesh<'static> = Mesh::new(&VERTICES, &[], &INDICES).with_colors(&COLORS).with_uvs(&UVS);
///
/// assert_eq!(TRIANGLE.validate(), Ok(()));
/// // Checked when compiling, for a `const` mesh:
/// const CHECKED: Mesh<'static> = Mesh::new(&[Vec3::ZERO; 3], &[], &[[0, 1, 2]]);
/// const _: () = assert!(CHECKED.validate().is_ok());
/// let bounds = TRIANGLE.bounds().unwrap();
/// assert_eq!(bounds.center(), Vec3::new(1, 1, 0));
/// // A model matrix that centres it on the origin, its largest half-side 1.
/// let fit = bounds.fit(1);
/// assert_eq!(fit.transform_point(Vec3::new(2, 2, 0)).to_bits(), [65536, 65536, 0, 65536]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct Mesh<'a> {
    /// Model-space positions.
    pub vertices: &'a [Vec3],
    /// Model-space unit normals, one per vertex, or none (face normals).
    pub normals: &'a [Vec3],
    /// Triangles as vertex indices.
    pub indices: &'a [[u16; 3]],
    /// Vertex colours, one per vertex, or none.
    pub colors: &'a [Rgb888],
    /// Texture coordinates, one per vertex, or none.
    pub uvs: &'a [TexCoord],
    /// The positions' extent found once ([`with_extent`](Mesh::with_extent)), if it was.
    extent: Option<Extent<'a>>,
}

/// The half sizes of the box around the origin that holds the positions `of` (the largest
/// magnitude of each raw coordinate), kept with those positions: a mesh whose `vertices` are
/// no longer them finds its extent again.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct Extent<'a> {
    of: &'a [Vec3],
    half: [u32; 3],
}

/// The largest magnitudes of the raw `x`, `y` and `z` of `positions`.
const fn half_sizes(positions: &[Vec3]) -> [u32; 3] {
    let (mut hx, mut hy, mut hz) = (0u32, 0u32, 0u32);
    let mut rest = positions;
    while let [p, tail @ ..] = rest {
        let [x, y, z] = p.to_bits();
        let (x, y, z) = (x.unsigned_abs(), y.unsigned_abs(), z.unsigned_abs());
        hx = if x > hx { x } else { hx };
        hy = if y > hy { y } else { hy };
        hz = if z > hz { z } else { hz };
        rest = tail;
    }
    [hx, hy, hz]
}

/// What [`Mesh::validate`] found wrong.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MeshError {
    /// An optional per-vertex array is neither empty nor as long as `vertices`.
    Length {
        /// `"normals"`, `"colors"` or `"uvs"`.
        array: &'static str,
        /// Its length.
        len: usize,
        /// The number of vertices.
        vertices: usize,
    },
    /// A triangle refers to a vertex that does not exist (the pipeline skips it).
    Index {
        /// The triangle's position in `indices`.
        triangle: usize,
        /// The index out of range.
        index: u16,
    },
}

impl core::fmt::Display for MeshError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            MeshError::Length {
                array,
                len,
                vertices,
            } => write!(
                f,
                "a mesh of {vertices} vertices needs 0 or {vertices} {array}, given {len}"
            ),
            MeshError::Index { triangle, index } => write!(
                f,
                "triangle {triangle} refers to vertex {index}: indices must be below the number \
                 of vertices"
            ),
        }
    }
}

impl core::error::Error for MeshError {}

/// Whether an optional per-vertex array of `len` suits `vertices` vertices.
const fn fits(len: usize, vertices: usize) -> bool {
    len == 0 || len == vertices
}

impl<'a> Mesh<'a> {
    /// A mesh from its positions, normals (or `&[]` for face normals) and triangles, without
    /// colours or texture coordinates.
    pub const fn new(vertices: &'a [Vec3], normals: &'a [Vec3], indices: &'a [[u16; 3]]) -> Self {
        Mesh {
            vertices,
            normals,
            indices,
            colors: &[],
            uvs: &[],
            extent: None,
        }
    }

    /// This mesh with the extent of its positions found now — at compile time for a `const` or
    /// `static` mesh — rather than by every draw (a pass over the positions: on a Cortex-M4
    /// about 23 instructions a vertex, 3 % of a 3D frame of spot). The pipeline uses it while
    /// `vertices` are the positions it was found for (the same slice), and finds the extent
    /// again otherwise; the frames are the same either way. The mesh emitter writes it.
    ///
    /// # Examples
    ///
    /// ```
    /// use embedded_raster::three_d::{Mesh, Vec3};
    ///
    /// static VERTICES: [Vec3; 3] = [
    ///     Vec3::from_bits(0, 0, 0),
    ///     Vec3::from_bits(2 << 16, 0, 0),
    ///     Vec3::from_bits(0, -3 << 16, 0),
    /// ];
    /// static TRIANGLE: Mesh<'static> = Mesh::new(&VERTICES, &[], &[[0, 1, 2]]).with_extent();
    /// assert_eq!(TRIANGLE.validate(), Ok(()));
    /// ```
    pub const fn with_extent(mut self) -> Self {
        self.extent = Some(Extent {
            of: self.vertices,
            half: half_sizes(self.vertices),
        });
        self
    }

    /// The largest magnitudes of the raw `x`, `y` and `z` of the positions: the half sizes of
    /// the box around the origin that holds them (whose corners the vertex stage tests against
    /// the view volume). Kept by [`with_extent`](Self::with_extent) for these positions, else
    /// found now.
    pub(crate) fn half_sizes(&self) -> [u32; 3] {
        match self.extent {
            Some(e) if core::ptr::eq(e.of, self.vertices) => e.half,
            _ => half_sizes(self.vertices),
        }
    }

    /// This mesh with `normals`, one per vertex (or none).
    pub const fn with_normals(mut self, normals: &'a [Vec3]) -> Self {
        self.normals = normals;
        self
    }

    /// This mesh with vertex colours, one per vertex (or none).
    pub const fn with_colors(mut self, colors: &'a [Rgb888]) -> Self {
        self.colors = colors;
        self
    }

    /// This mesh with texture coordinates, one per vertex (or none).
    pub const fn with_uvs(mut self, uvs: &'a [TexCoord]) -> Self {
        self.uvs = uvs;
        self
    }

    /// Checks that every optional array is empty or one per vertex and that every index refers
    /// to a vertex; the first problem found, else `Ok`. (Drawing never fails on these: triangles
    /// with a bad index are skipped, missing normals come from the face.)
    pub const fn validate(&self) -> Result<(), MeshError> {
        let vertices = self.vertices.len();
        let arrays = [
            ("normals", self.normals.len()),
            ("colors", self.colors.len()),
            ("uvs", self.uvs.len()),
        ];
        let mut k = 0;
        while k < arrays.len() {
            let (array, len) = arrays[k];
            if !fits(len, vertices) {
                return Err(MeshError::Length {
                    array,
                    len,
                    vertices,
                });
            }
            k += 1;
        }
        let mut triangle = 0;
        while triangle < self.indices.len() {
            let face = self.indices[triangle];
            let mut c = 0;
            while c < 3 {
                if face[c] as usize >= vertices {
                    return Err(MeshError::Index {
                        triangle,
                        index: face[c],
                    });
                }
                c += 1;
            }
            triangle += 1;
        }
        Ok(())
    }

    /// The axis-aligned box around all vertices, or `None` for a mesh without vertices.
    pub fn bounds(&self) -> Option<Bounds> {
        let (first, rest) = self.vertices.split_first()?;
        let mut b = Bounds {
            min: *first,
            max: *first,
        };
        for v in rest {
            b.min = Vec3::new(b.min.x.min(v.x), b.min.y.min(v.y), b.min.z.min(v.z));
            b.max = Vec3::new(b.max.x.max(v.x), b.max.y.max(v.y), b.max.z.max(v.z));
        }
        Some(b)
    }
}

/// An axis-aligned box, `min ≤ max` componentwise: a mesh's [`bounds`](Mesh::bounds).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Bounds {
    /// The smallest coordinates.
    pub min: Vec3,
    /// The largest coordinates.
    pub max: Vec3,
}

impl Bounds {
    /// The centre, rounded to the nearest 2⁻¹⁶ (ties up).
    pub fn center(&self) -> Vec3 {
        let mid = |a: Scalar, b: Scalar| {
            Scalar::from_bits(((i64::from(a.to_bits()) + i64::from(b.to_bits()) + 1) >> 1) as i32)
        };
        Vec3::new(
            mid(self.min.x, self.max.x),
            mid(self.min.y, self.max.y),
            mid(self.min.z, self.max.z),
        )
    }

    /// The side lengths `max − min` (saturating beyond 32768).
    pub fn size(&self) -> Vec3 {
        self.max - self.min
    }

    /// The translation that moves the centre to the origin: a model matrix that re-centres the
    /// mesh.
    pub fn centering(&self) -> Mat4 {
        Mat4::translation(-self.center())
    }

    /// A model matrix that centres the box on the origin and scales it uniformly so that its
    /// largest half-side is `half_extent` (a float, an integer or a [`Scalar`]); a box of zero
    /// size is only centred.
    pub fn fit(&self, half_extent: impl ToScalar) -> Mat4 {
        let size = self.size().to_bits().map(i64::from);
        let largest = size.into_iter().max().unwrap_or(0);
        if largest <= 0 {
            return self.centering();
        }
        // Scale = half_extent / (largest / 2), rounded once.
        let target = i64::from(half_extent.to_scalar().to_bits());
        let q = ((target << 18) + largest).div_euclid(2 * largest);
        let scale = Scalar::from_bits(q.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32);
        Mat4::scaling(scale) * self.centering()
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use std::string::ToString;

    use super::*;

    /// The extent kept by `with_extent` (computed in a `const`) is the largest magnitude of each
    /// raw coordinate, as a fold over the positions finds it, including `i32::MIN`'s; a mesh
    /// whose positions were replaced finds the extent of its new ones.
    #[test]
    fn extents_are_the_positions_largest_magnitudes() {
        const A: [Vec3; 4] = [
            Vec3::from_bits(3, -7, 0),
            Vec3::from_bits(-9, 2, 5),
            Vec3::from_bits(1, 1, i32::MIN),
            Vec3::from_bits(i32::MAX, -1, -4),
        ];
        static B: [Vec3; 2] = [Vec3::from_bits(-1, 20, 6), Vec3::from_bits(0, -30, 1)];
        const MESH: Mesh<'static> = Mesh::new(&A, &[], &[]).with_extent();
        let fold = |p: &[Vec3]| {
            p.iter().fold([0u32; 3], |m, v| {
                let b = v.to_bits();
                [0, 1, 2].map(|k| m[k].max(b[k].unsigned_abs()))
            })
        };
        assert_eq!(MESH.half_sizes(), fold(&A));
        assert_eq!(MESH.half_sizes(), [i32::MAX as u32, 7, 1 << 31]);
        assert_eq!(Mesh::new(&A, &[], &[]).half_sizes(), fold(&A));
        let mut moved = MESH;
        moved.vertices = &B;
        assert_eq!(moved.half_sizes(), [1, 30, 6]);
        assert_eq!(Mesh::new(&[], &[], &[]).with_extent().half_sizes(), [0; 3]);
    }

    /// The errors' messages: what was needed and what was given (issue #32, item 2).
    #[test]
    fn mesh_error_messages() {
        let length = MeshError::Length {
            array: "normals",
            len: 11,
            vertices: 12,
        };
        assert_eq!(
            length.to_string(),
            "a mesh of 12 vertices needs 0 or 12 normals, given 11"
        );
        let index = MeshError::Index {
            triangle: 3,
            index: 12,
        };
        assert_eq!(
            index.to_string(),
            "triangle 3 refers to vertex 12: indices must be below the number of vertices"
        );
    }
}
