//! [`Mesh`]: the indexed triangle mesh the [`Pipeline`](super::Pipeline) draws, a borrowed view of
//! arrays that typically live in flash.

use super::math::Vec3;

/// An indexed triangle mesh, typically in flash (`&'static` slices).
///
/// `normals[i]` is the unit normal of `vertices[i]`; when `normals` is shorter, the missing ones
/// are taken from the face. Triangles with an index out of range are skipped. Front faces are
/// counter-clockwise seen from outside (right-handed: the face normal `(v1 − v0) × (v2 − v0)`
/// points out).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Mesh<'a> {
    /// Model-space positions.
    pub vertices: &'a [Vec3],
    /// Model-space unit normals, one per vertex.
    pub normals: &'a [Vec3],
    /// Triangles as vertex indices.
    pub indices: &'a [[u16; 3]],
}

impl<'a> Mesh<'a> {
    /// A mesh from its arrays.
    pub const fn new(vertices: &'a [Vec3], normals: &'a [Vec3], indices: &'a [[u16; 3]]) -> Self {
        Mesh {
            vertices,
            normals,
            indices,
        }
    }
}
