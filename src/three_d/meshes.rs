//! Meshes: ready-made ones in flash, and (with the `std` feature) procedural generators.
//!
//! * [`icosphere::ICOSPHERE`] (42 vertices, 80 faces) and [`torus::TORUS`] (96 vertices, 192
//!   faces) are `static` arrays, generated on the host by `icosphere()` / `torus()` and
//!   `MeshData::to_rust_source` (feature `std`); firmware draws them straight from flash.
//! * `MeshData` is an owned mesh for the host: generate one, load one from an OBJ file (module
//!   `obj`, feature `std`), weld, re-centre or scale it, and write it out as Rust source for
//!   firmware (with its vertex colours and texture coordinates, if it has them).
//!
//! ```
//! use embedded_raster::three_d::meshes::icosphere::ICOSPHERE;
//!
//! assert_eq!(ICOSPHERE.vertices.len(), 42);
//! assert_eq!(ICOSPHERE.indices.len(), 80);
//! ```

pub mod icosphere;
pub mod torus;

#[cfg(feature = "std")]
pub use host::*;

#[cfg(feature = "std")]
mod host {
    use std::collections::HashMap;
    use std::format;
    use std::string::String;
    use std::vec;
    use std::vec::Vec;

    use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

    use crate::three_d::math::{Scalar, Vec3};
    use crate::three_d::{Bounds, Mesh, MeshError, TexCoord};

    /// An owned mesh on the host: the arrays of a [`Mesh`], in `Vec`s.
    ///
    /// `normals`, `colors` and `uvs` are each empty or one per vertex, as in [`Mesh`].
    ///
    /// # Examples
    ///
    /// Generated ([`icosphere`], [`torus`], [`torus_knot`]), read from OBJ text (the `obj`
    /// module's `parse`) or written field by field; drawn through
    /// [`as_mesh`](Self::as_mesh), or turned into `static` arrays for firmware:
    ///
    /// ```
    /// use embedded_raster::three_d::meshes::{icosphere, MeshData};
    /// use embedded_raster::three_d::Vec3;
    ///
    /// let sphere = icosphere(1.0, 1);
    /// assert_eq!((sphere.vertices.len(), sphere.indices.len()), (42, 80));
    ///
    /// // A 2 × 2 square off the origin, two triangles, no normals (the pipeline uses the
    /// // faces' own).
    /// let mut square = MeshData {
    ///     vertices: vec![Vec3::new(1, 1, 0), Vec3::new(3, 1, 0), Vec3::new(3, 3, 0), Vec3::new(1, 3, 0)],
    ///     indices: vec![[0, 1, 2], [0, 2, 3]],
    ///     ..MeshData::default()
    /// };
    /// square.validate()?;
    /// square.recenter();
    /// assert_eq!(square.vertices[0], Vec3::new(-1, -1, 0));
    /// assert_eq!(square.as_mesh().indices.len(), 2);
    ///
    /// let source = square.to_rust_source("SQUARE", "embedded_raster");
    /// assert!(source.contains("pub static SQUARE: Mesh<'static> ="));
    /// assert!(source.contains("pub static SQUARE_INDICES: [[u16; 3]; 2] = ["));
    /// # Ok::<(), embedded_raster::three_d::MeshError>(())
    /// ```
    #[derive(Debug, Clone, PartialEq, Eq, Default)]
    pub struct MeshData {
        /// Positions.
        pub vertices: Vec<Vec3>,
        /// Unit normals, one per vertex (or none).
        pub normals: Vec<Vec3>,
        /// Triangles, counter-clockwise seen from outside.
        pub indices: Vec<[u16; 3]>,
        /// Vertex colours, one per vertex (or none).
        pub colors: Vec<Rgb888>,
        /// Texture coordinates, one per vertex (or none).
        pub uvs: Vec<TexCoord>,
    }

    /// The nearest `I16F16` to `v` (saturating; NaN as 0, as
    /// [`ToScalar::to_scalar`](crate::three_d::ToScalar::to_scalar) does:
    /// [converting floats](crate#converting-floats)).
    ///
    /// ```
    /// use embedded_raster::three_d::{meshes::scalar, Scalar};
    ///
    /// assert_eq!(scalar(0.5), Scalar::from_num(0.5));
    /// assert_eq!(scalar(f64::NAN), Scalar::ZERO);
    /// assert_eq!(scalar(f64::INFINITY), Scalar::MAX);
    /// assert_eq!(scalar(-1e9), Scalar::MIN);
    /// ```
    pub fn scalar(v: f64) -> Scalar {
        let raw = (v * 65536.0).round();
        Scalar::from_bits(raw.clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as i32)
    }

    /// The nearest fixed-point vector (as [`scalar`]: NaN as 0, saturating).
    pub fn vec3(v: [f64; 3]) -> Vec3 {
        Vec3::new(scalar(v[0]), scalar(v[1]), scalar(v[2]))
    }

    /// A fixed-point vector as `f64`s.
    pub fn to_f64(v: Vec3) -> [f64; 3] {
        v.to_bits().map(|c| f64::from(c) / 65536.0)
    }

    fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }

    fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    fn normalize(v: [f64; 3]) -> [f64; 3] {
        let l = dot(v, v).sqrt();
        if l > 0.0 {
            v.map(|c| c / l)
        } else {
            v
        }
    }

    impl MeshData {
        /// A borrowed [`Mesh`] view, for drawing (check it with [`validate`](Self::validate)).
        pub fn as_mesh(&self) -> Mesh<'_> {
            Mesh::new(&self.vertices, &self.normals, &self.indices)
                .with_colors(&self.colors)
                .with_uvs(&self.uvs)
        }

        /// [`Mesh::validate`] of this mesh: array lengths and indices.
        pub fn validate(&self) -> Result<(), MeshError> {
            self.as_mesh().validate()
        }

        /// The box around all vertices ([`Mesh::bounds`]).
        pub fn bounds(&self) -> Option<Bounds> {
            self.as_mesh().bounds()
        }

        /// Moves the vertices so that the centre of their box is the origin.
        pub fn recenter(&mut self) {
            if let Some(b) = self.bounds() {
                let c = b.center();
                for v in &mut self.vertices {
                    *v = *v - c;
                }
            }
        }

        /// Centres the vertices on the origin and scales them uniformly so that the largest
        /// half-side of their box is `half_extent` (computed in `f64`, each coordinate rounded
        /// once); a mesh of zero size is only centred. Normals keep their directions.
        pub fn scale_to_fit(&mut self, half_extent: f64) {
            let Some(b) = self.bounds() else {
                return;
            };
            let (lo, hi) = (to_f64(b.min), to_f64(b.max));
            let centre = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
            let largest = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max) / 2.0;
            let scale = if largest > 0.0 {
                half_extent / largest
            } else {
                1.0
            };
            for v in &mut self.vertices {
                let p = to_f64(*v);
                *v = vec3([0, 1, 2].map(|k| (p[k] - centre[k]) * scale));
            }
        }

        /// Merges vertices that agree in everything they carry (position, normal, colour,
        /// texture coordinate): the triangles refer to the first of each group, unused vertices
        /// are dropped, the order of first use is kept. Returns how many vertices were removed.
        pub fn weld(&mut self) -> usize {
            type Key = ([i32; 3], Option<[i32; 3]>, Option<Rgb888>, Option<[i32; 2]>);
            let key = |i: usize| -> Key {
                (
                    self.vertices[i].to_bits(),
                    self.normals.get(i).map(|n| n.to_bits()),
                    self.colors.get(i).copied(),
                    self.uvs.get(i).map(|t| t.to_bits()),
                )
            };
            let before = self.vertices.len();
            let mut first: HashMap<Key, u16> = HashMap::new();
            let mut kept: Vec<usize> = Vec::new();
            let mut indices = self.indices.clone();
            for face in &mut indices {
                for i in face.iter_mut() {
                    let k = key(usize::from(*i));
                    *i = *first.entry(k).or_insert_with(|| {
                        kept.push(usize::from(*i));
                        (kept.len() - 1) as u16
                    });
                }
            }
            let pick = |v: &[Vec3]| -> Vec<Vec3> {
                if v.is_empty() {
                    Vec::new()
                } else {
                    kept.iter().map(|&i| v[i]).collect()
                }
            };
            let vertices = pick(&self.vertices);
            let normals = pick(&self.normals);
            let colors = if self.colors.is_empty() {
                Vec::new()
            } else {
                kept.iter().map(|&i| self.colors[i]).collect()
            };
            let uvs = if self.uvs.is_empty() {
                Vec::new()
            } else {
                kept.iter().map(|&i| self.uvs[i]).collect()
            };
            *self = MeshData {
                vertices,
                normals,
                indices,
                colors,
                uvs,
            };
            before - self.vertices.len()
        }

        /// Builds a mesh from `f64` positions and normals, orienting every face so that its
        /// geometric normal agrees with the mean of its vertex normals.
        ///
        /// # Panics
        ///
        /// If there are more than 65536 vertices or an index is out of range (host-only code).
        pub fn from_f64(
            positions: &[[f64; 3]],
            normals: &[[f64; 3]],
            faces: &[[usize; 3]],
        ) -> Self {
            assert!(
                positions.len() <= 65536,
                "too many vertices for u16 indices"
            );
            let indices = faces
                .iter()
                .map(|&[a, b, c]| {
                    let n = cross(
                        sub(positions[b], positions[a]),
                        sub(positions[c], positions[a]),
                    );
                    let mean = [0, 1, 2].map(|k| normals[a][k] + normals[b][k] + normals[c][k]);
                    let f = if dot(n, mean) < 0.0 {
                        [a, c, b]
                    } else {
                        [a, b, c]
                    };
                    f.map(|i| i as u16)
                })
                .collect();
            MeshData {
                vertices: positions.iter().map(|p| vec3(*p)).collect(),
                normals: normals.iter().map(|n| vec3(normalize(*n))).collect(),
                indices,
                ..MeshData::default()
            }
        }

        /// Rust source declaring this mesh as `static` arrays for firmware: `{NAME}_VERTICES`,
        /// `{NAME}_NORMALS`, `{NAME}_INDICES`, `{NAME}_COLORS` and `{NAME}_UVS` (the last two
        /// only if the mesh has colours or texture coordinates) and a `Mesh<'static>` called
        /// `{NAME}`. Statics are stored once, in flash (`.rodata`). `crate_path` is how the
        /// generated file names this crate: `embedded_raster` from another crate, `crate` inside
        /// it; colours name `embedded_graphics::pixelcolor::Rgb888`.
        pub fn to_rust_source(&self, name: &str, crate_path: &str) -> String {
            let mut s = String::new();
            let n = self.vertices.len();
            let (colors, uvs) = (!self.colors.is_empty(), !self.uvs.is_empty());
            s += "//! Generated by `embedded_raster::three_d::meshes::MeshData::to_rust_source`; do not edit.\n\n";
            if colors {
                s += "use embedded_graphics::pixelcolor::Rgb888;\n";
            }
            let tex = if uvs { ", TexCoord" } else { "" };
            s += &format!("use {crate_path}::three_d::{{Mesh{tex}, Vec3}};\n\n");
            let what = match (colors, uvs) {
                (false, false) => "its normals and indices",
                (true, false) => "its normals, indices and vertex colours",
                (false, true) => "its normals, indices and texture coordinates",
                (true, true) => "its normals, indices, vertex colours and texture coordinates",
            };
            s += &format!("/// `{name}` with {what}.\n");
            let mut mesh = format!("Mesh::new(&{name}_VERTICES, &{name}_NORMALS, &{name}_INDICES)");
            if colors {
                mesh += &format!(".with_colors(&{name}_COLORS)");
            }
            if uvs {
                mesh += &format!(".with_uvs(&{name}_UVS)");
            }
            // The positions' extent found when compiling, not by every draw.
            mesh += ".with_extent()";
            s += &format!("pub static {name}: Mesh<'static> = {mesh};\n\n");
            let vecs = |s: &mut String, what: &str, suffix: &str, v: &[Vec3]| {
                *s += &format!("/// {what} of `{name}` (`I16F16` bits).\n");
                *s += &format!("pub static {name}_{suffix}: [Vec3; {}] = [\n", v.len());
                for p in v {
                    let [x, y, z] = p.to_bits();
                    *s += &format!("    Vec3::from_bits({x}, {y}, {z}),\n");
                }
                *s += "];\n\n";
            };
            vecs(&mut s, "Vertex positions", "VERTICES", &self.vertices);
            vecs(&mut s, "Unit vertex normals", "NORMALS", &self.normals);
            s += &format!("/// Triangles of `{name}`, counter-clockwise seen from outside.\n");
            s += &format!(
                "pub static {name}_INDICES: [[u16; 3]; {}] = [\n",
                self.indices.len()
            );
            for [a, b, c] in &self.indices {
                s += &format!("    [{a}, {b}, {c}],\n");
            }
            s += "];\n";
            if colors {
                s += &format!("\n/// Vertex colours of `{name}`.\n");
                s += &format!("pub static {name}_COLORS: [Rgb888; {n}] = [\n");
                for c in &self.colors {
                    s += &format!("    Rgb888::new({}, {}, {}),\n", c.r(), c.g(), c.b());
                }
                s += "];\n";
            }
            if uvs {
                s += &format!("\n/// Texture coordinates of `{name}` (`I16F16` bits).\n");
                s += &format!("pub static {name}_UVS: [TexCoord; {n}] = [\n");
                for t in &self.uvs {
                    let [u, v] = t.to_bits();
                    s += &format!("    TexCoord::from_bits({u}, {v}),\n");
                }
                s += "];\n";
            }
            s
        }
    }

    /// A sphere of `radius` made by subdividing an icosahedron `subdivisions` times (each step
    /// splits every triangle into four): `10·4^k + 2` vertices, `20·4^k` faces.
    ///
    /// # Panics
    ///
    /// If the result has more than 65536 vertices (`subdivisions > 6`), before building anything.
    pub fn icosphere(radius: f64, subdivisions: u32) -> MeshData {
        assert!(
            subdivisions <= 6,
            "an icosphere of at most 65536 vertices has at most 6 subdivisions, not {subdivisions}"
        );
        let t = (1.0 + 5f64.sqrt()) / 2.0;
        let mut points: Vec<[f64; 3]> = [
            [-1.0, t, 0.0],
            [1.0, t, 0.0],
            [-1.0, -t, 0.0],
            [1.0, -t, 0.0],
            [0.0, -1.0, t],
            [0.0, 1.0, t],
            [0.0, -1.0, -t],
            [0.0, 1.0, -t],
            [t, 0.0, -1.0],
            [t, 0.0, 1.0],
            [-t, 0.0, -1.0],
            [-t, 0.0, 1.0],
        ]
        .iter()
        .map(|p| normalize(*p))
        .collect();
        let mut faces: Vec<[usize; 3]> = [
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ]
        .to_vec();
        for _ in 0..subdivisions {
            let mut midpoints: HashMap<(usize, usize), usize> = HashMap::new();
            let mut mid = |a: usize, b: usize, points: &mut Vec<[f64; 3]>| {
                *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    let (p, q) = (points[a], points[b]);
                    points.push(normalize([0, 1, 2].map(|k| p[k] + q[k])));
                    points.len() - 1
                })
            };
            faces = faces
                .iter()
                .flat_map(|&[a, b, c]| {
                    let ab = mid(a, b, &mut points);
                    let bc = mid(b, c, &mut points);
                    let ca = mid(c, a, &mut points);
                    [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
                })
                .collect();
        }
        let positions: Vec<[f64; 3]> = points.iter().map(|p| p.map(|c| c * radius)).collect();
        MeshData::from_f64(&positions, &points, &faces)
    }

    /// A tube around the `(p, q)` torus knot — the curve that winds `p` times around the z axis
    /// and `q` times through the torus of radii 2 and 1 — scaled by `scale`, with a radius that
    /// swells and narrows five times along it (between `0.65·tube` and `1.35·tube`, so that its
    /// triangles differ in size and slant as a scanned model's do): `rings` segments along the
    /// curve, `sides` around the tube, `2·rings·sides` faces. Normals are the area-weighted means
    /// of the faces around each vertex. `(2, 3)` is the trefoil.
    ///
    /// # Panics
    ///
    /// If `rings` or `sides` is below 3 or `rings · sides > 65536`, before building anything.
    pub fn torus_knot(
        (p, q): (u32, u32),
        scale: f64,
        tube: f64,
        rings: usize,
        sides: usize,
    ) -> MeshData {
        check_segments("a torus knot", rings, sides);
        let tau = core::f64::consts::TAU;
        let (p, q) = (f64::from(p), f64::from(q));
        let curve = |t: f64| {
            let r = 2.0 + (q * t).cos();
            [r * (p * t).cos(), r * (p * t).sin(), -(q * t).sin()].map(|c| c * scale)
        };
        // Frenet frame from central differences (a torus knot's curvature never vanishes).
        let h = 1e-4;
        let mut positions = Vec::with_capacity(rings * sides);
        let mut radial = Vec::with_capacity(rings * sides);
        for i in 0..rings {
            let t = tau * i as f64 / rings as f64;
            let (c, prev, next) = (curve(t), curve(t - h), curve(t + h));
            let tangent = normalize(sub(next, prev));
            let second = [0, 1, 2].map(|k| next[k] - 2.0 * c[k] + prev[k]);
            let along = dot(second, tangent);
            let normal = normalize([0, 1, 2].map(|k| second[k] - along * tangent[k]));
            let binormal = cross(tangent, normal);
            let radius = tube * (1.0 + 0.35 * (5.0 * t).sin());
            for j in 0..sides {
                let (s, co) = (tau * j as f64 / sides as f64).sin_cos();
                let d = [0, 1, 2].map(|k| co * normal[k] + s * binormal[k]);
                positions.push([0, 1, 2].map(|k| c[k] + radius * d[k]));
                radial.push(d);
            }
        }
        let at = |i: usize, j: usize| (i % rings) * sides + (j % sides);
        let faces: Vec<[usize; 3]> = (0..rings)
            .flat_map(|i| {
                (0..sides).flat_map(move |j| {
                    let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                    [[a, b, c], [a, c, d]]
                })
            })
            .collect();
        // Orient by the radial directions, then take the faces' mean normals.
        let oriented = MeshData::from_f64(&positions, &radial, &faces);
        let mut normals = vec![[0.0; 3]; positions.len()];
        for face in &oriented.indices {
            let [a, b, c] = face.map(usize::from);
            let n = cross(
                sub(positions[b], positions[a]),
                sub(positions[c], positions[a]),
            );
            for v in [a, b, c] {
                normals[v] = [0, 1, 2].map(|k| normals[v][k] + n[k]);
            }
        }
        let faces: Vec<[usize; 3]> = oriented
            .indices
            .iter()
            .map(|f| f.map(usize::from))
            .collect();
        MeshData::from_f64(&positions, &normals, &faces)
    }

    /// A torus around the z axis: tube centre at distance `major` from the axis, tube radius
    /// `minor`, `rings` segments around the axis and `sides` around the tube.
    ///
    /// # Panics
    ///
    /// If `rings` or `sides` is below 3 or `rings · sides > 65536`, before building anything.
    pub fn torus(major: f64, minor: f64, rings: usize, sides: usize) -> MeshData {
        check_segments("a torus", rings, sides);
        let tau = core::f64::consts::TAU;
        let mut positions = Vec::with_capacity(rings * sides);
        let mut normals = Vec::with_capacity(rings * sides);
        for i in 0..rings {
            let theta = tau * i as f64 / rings as f64;
            for j in 0..sides {
                let phi = tau * j as f64 / sides as f64;
                let (st, ct) = theta.sin_cos();
                let (sp, cp) = phi.sin_cos();
                positions.push([
                    (major + minor * cp) * ct,
                    (major + minor * cp) * st,
                    minor * sp,
                ]);
                normals.push([cp * ct, cp * st, sp]);
            }
        }
        let at = |i: usize, j: usize| (i % rings) * sides + (j % sides);
        let faces: Vec<[usize; 3]> = (0..rings)
            .flat_map(|i| {
                (0..sides).flat_map(move |j| {
                    let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                    [[a, b, c], [a, c, d]]
                })
            })
            .collect();
        MeshData::from_f64(&positions, &normals, &faces)
    }

    /// Panics unless a mesh of `rings × sides` vertices (`what`) has 3 × 3 to 65536 of them
    /// (`u16` indices): before anything is built, the product checked (it may not fit `usize`).
    fn check_segments(what: &str, rings: usize, sides: usize) {
        let vertices = rings.checked_mul(sides);
        assert!(
            rings >= 3 && sides >= 3 && vertices.is_some_and(|n| n <= 65536),
            "{what} needs at least 3 rings and 3 sides and at most 65536 vertices (rings · sides, \
             for u16 indices), not {rings} × {sides} = {}",
            vertices.map_or_else(|| String::from("more than usize::MAX"), |n| format!("{n}"))
        );
    }
}
