//! A small Wavefront OBJ loader and writer for the host (`std` feature).
//!
//! [`parse`] reads `v` (with the common `v x y z r g b` vertex-colour extension), `vt`, `vn`
//! and `f` statements (faces with `v`, `v/vt`, `v//vn` or `v/vt/vn` references, 1-based or
//! negative, polygons fanned into triangles) into a `MeshData`
//! ([`meshes::MeshData`](crate::three_d::meshes::MeshData)) and ignores everything else (`o`,
//! `g`, `s`, materials, comments).
//!
//! **Welding.** Face corners become one vertex when their position, normal, texture coordinate
//! and colour are equal as the mesh stores them (`I16F16`, 8-bit colour; computed normals and
//! the defaults for missing colours and texture coordinates included), whether or not the file
//! repeats them on separate lines; vertices whose faces give no normal get the normalised area-weighted
//! mean of the normals of all faces around their *position*, so models that repeat positions
//! along patch borders (the Utah teapot) shade without seams. [`parse_with`] with
//! `weld: false` keeps a vertex per distinct `v/vt/vn` reference instead. Explicit normals are
//! kept as written (the pipeline normalises what it uses). Vertices come out sorted by their
//! first (`v`, `vt`, `vn`) reference; unused lines are dropped. The mesh has colours if any used
//! `v` line has them (white for those that do not) and texture coordinates if any face corner
//! has one (`(0, 0)` for those that do not).
//!
//! Text without faces (empty, comments only, vertices only) is an error, not an empty mesh, and
//! so are more than 65536 distinct vertices (`u16` indices; the error names the line of the face
//! that brings the 65537th). [`read`] and [`read_file`] read the text from any
//! [`std::io::Read`] or from a file.
//!
//! [`to_obj`] writes a mesh back out exactly (every `I16F16` value prints as a decimal that
//! parses back to it), and
//! [`MeshData::to_rust_source`](crate::three_d::meshes::MeshData::to_rust_source) turns it into
//! `static` arrays for firmware.
//!
//! ```
//! use embedded_raster::three_d::obj;
//!
//! let mesh = obj::parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
//! assert_eq!(mesh.indices, vec![[0, 1, 2]]);
//! assert_eq!(mesh.normals[0].z.to_num::<f64>(), 1.0);
//! assert_eq!(obj::parse(&obj::to_obj(&mesh)).unwrap(), mesh);
//!
//! // Two triangles that repeat their shared positions weld into four vertices.
//! let quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 1 1 0\nv 0 1 0\nv 0 0 0\nf 1 2 3\nf 4 5 6\n";
//! assert_eq!(obj::parse(quad).unwrap().vertices.len(), 4);
//!
//! // No faces: an error, whose line is 0 (the whole text).
//! let empty = obj::parse("# nothing but a comment\n").unwrap_err();
//! assert_eq!(empty.line, 0);
//! assert_eq!(
//!     empty.to_string(),
//!     "no faces: a mesh needs at least one `f` line; the text has 1 line, 0 `v` and 0 `f` lines"
//! );
//!
//! // From any reader (a file: `obj::read_file(path)`).
//! let mesh = obj::read(std::io::Cursor::new("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"))?;
//! assert_eq!(mesh.vertices.len(), 3);
//! # Ok::<(), obj::ReadError>(())
//! ```

use std::collections::HashMap;
use std::fmt;
use std::format;
use std::io::{self, Read};
use std::path::{Path, PathBuf};
use std::string::String;
use std::vec::Vec;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

use crate::three_d::meshes::{to_f64, vec3, MeshData};
use crate::three_d::{TexCoord, Vec3};

/// Why OBJ text is not a mesh.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObjError {
    /// 1-based line number; 0 where the whole text is at fault (it has no faces).
    pub line: usize,
    /// What was wrong.
    pub message: String,
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            0 => write!(f, "{}", self.message),
            line => write!(f, "line {line}: {}", self.message),
        }
    }
}

impl std::error::Error for ObjError {}

/// Why [`read`] or [`read_file`] gave no mesh: the text could not be read, or is not a mesh.
#[derive(Debug)]
#[non_exhaustive]
pub enum ReadError {
    /// Reading failed ([`read_file`]: with the file's path).
    Io {
        /// The file, for [`read_file`].
        path: Option<PathBuf>,
        /// The reader's error.
        error: io::Error,
    },
    /// The text is not a mesh ([`read_file`]: with the file's path).
    Obj {
        /// The file, for [`read_file`].
        path: Option<PathBuf>,
        /// What [`parse`] found.
        error: ObjError,
    },
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReadError::Io { path: None, error } => write!(f, "cannot read the OBJ text: {error}"),
            ReadError::Io {
                path: Some(path),
                error,
            } => write!(f, "cannot read the OBJ file {}: {error}", path.display()),
            ReadError::Obj { path: None, error } => write!(f, "{error}"),
            ReadError::Obj {
                path: Some(path),
                error,
            } => write!(f, "{}: {error}", path.display()),
        }
    }
}

impl std::error::Error for ReadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ReadError::Io { error, .. } => Some(error),
            ReadError::Obj { error, .. } => Some(error),
        }
    }
}

impl From<io::Error> for ReadError {
    fn from(error: io::Error) -> Self {
        ReadError::Io { path: None, error }
    }
}

impl From<ObjError> for ReadError {
    fn from(error: ObjError) -> Self {
        ReadError::Obj { path: None, error }
    }
}

fn err(line: usize, message: impl Into<String>) -> ObjError {
    ObjError {
        line,
        message: message.into(),
    }
}

fn floats(line: usize, words: &[&str], n: usize) -> Result<[f64; 3], ObjError> {
    if words.len() < n {
        let found = words.len();
        return Err(err(line, format!("expected {n} numbers, found {found}")));
    }
    let mut v = [0.0; 3];
    for (slot, w) in v.iter_mut().zip(words) {
        *slot = w
            .parse::<f64>()
            .map_err(|_| err(line, format!("expected a number, found `{w}`")))?;
        if !slot.is_finite() {
            return Err(err(line, format!("expected a finite number, found `{w}`")));
        }
    }
    Ok(v)
}

/// Resolves a 1-based or negative (relative) OBJ index against the `count` items of `kind`
/// (`"v"`, `"vt"` or `"vn"`) read so far.
fn index(line: usize, word: &str, count: usize, kind: &str) -> Result<usize, ObjError> {
    let i: i64 = word.parse().map_err(|_| {
        err(
            line,
            format!("expected a `{kind}` index (a non-zero integer), found `{word}`"),
        )
    })?;
    let resolved = if i > 0 { i - 1 } else { count as i64 + i };
    if i == 0 || resolved < 0 || resolved >= count as i64 {
        let before = match count {
            0 => format!("no `{kind}` line before it"),
            1 => format!("1 `{kind}` line before it (index 1 or -1)"),
            n => format!("{n} `{kind}` lines before it (indices 1 to {n} or -1 to -{n})"),
        };
        return Err(err(
            line,
            format!("`{kind}` index {word} out of range: {before}"),
        ));
    }
    Ok(resolved as usize)
}

/// How [`parse_with`] builds vertices.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ParseOptions {
    /// Merge face corners whose stored position, normal, texture coordinate and colour are
    /// equal, and compute missing normals around each position (see the module docs). When
    /// `false`: a vertex per distinct `v/vt/vn` reference, missing normals per `v` line.
    pub weld: bool,
}

impl Default for ParseOptions {
    /// Welding on.
    fn default() -> Self {
        ParseOptions { weld: true }
    }
}

/// Parses OBJ text into a triangle mesh, welding vertices ([`ParseOptions::default`]).
///
/// # Errors
///
/// The first line that is not valid OBJ (a number or index that is not one, an index out of
/// range, a face of fewer than 3 vertices), more than 65536 distinct vertices (the line of the
/// face that brings the 65537th), or no faces at all (line 0).
///
/// # Examples
///
/// ```
/// use embedded_raster::three_d::{obj, Vec3};
///
/// // A unit square in the xy plane as one polygon (fanned into two triangles), with a normal
/// // for all four corners and 1-based and negative (from the end) references.
/// let text = "\
/// v 0 0 0
/// v 1 0 0
/// v 1 1 0
/// v 0 1 0
/// vn 0 0 1
/// f 1//1 2//1 -2//1 -1//1
/// ";
/// let square = obj::parse(text)?;
/// assert_eq!(square.indices, vec![[0, 1, 2], [0, 2, 3]]);
/// assert_eq!(square.vertices[2], Vec3::new(1, 1, 0));
/// assert_eq!(square.normals, vec![Vec3::new(0, 0, 1); 4]);
///
/// // Errors name the line and what is wrong with it.
/// let error = obj::parse("v 0 0 0\nv 1 0 zero\n").unwrap_err();
/// assert_eq!(error.line, 2);
/// assert!(error.to_string().starts_with("line 2: "), "{error}");
/// # Ok::<(), obj::ObjError>(())
/// ```
pub fn parse(src: &str) -> Result<MeshData, ObjError> {
    parse_with(src, ParseOptions::default())
}

/// Reads OBJ text from `reader` to its end and parses it ([`parse`]). Bytes that are not UTF-8
/// (in a comment, say) read as U+FFFD.
pub fn read(reader: impl Read) -> Result<MeshData, ReadError> {
    read_with(reader, ParseOptions::default())
}

/// [`read`] with `options` ([`parse_with`]).
pub fn read_with(mut reader: impl Read, options: ParseOptions) -> Result<MeshData, ReadError> {
    let mut bytes = Vec::new();
    reader.read_to_end(&mut bytes)?;
    Ok(parse_with(&String::from_utf8_lossy(&bytes), options)?)
}

/// Reads and parses the OBJ file at `path` ([`read`]); its errors carry the path.
pub fn read_file(path: impl AsRef<Path>) -> Result<MeshData, ReadError> {
    let path = path.as_ref();
    let with_path = |e: ReadError| match e {
        ReadError::Io { error, .. } => ReadError::Io {
            path: Some(path.to_path_buf()),
            error,
        },
        ReadError::Obj { error, .. } => ReadError::Obj {
            path: Some(path.to_path_buf()),
            error,
        },
    };
    let file = std::fs::File::open(path).map_err(|e| with_path(e.into()))?;
    read(io::BufReader::new(file)).map_err(with_path)
}

/// A face corner's references: position, texture coordinate, normal (0-based).
type Reference = (usize, Option<usize>, Option<usize>);

/// Parses OBJ text into a triangle mesh with `options`.
pub fn parse_with(src: &str, options: ParseOptions) -> Result<MeshData, ObjError> {
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut colors: Vec<Option<[f64; 3]>> = Vec::new();
    let mut texcoords: Vec<[f64; 2]> = Vec::new();
    let mut normals: Vec<[f64; 3]> = Vec::new();
    // Distinct corner references, and the triangles as indices into them.
    let mut refs: Vec<Reference> = Vec::new();
    // The line of each reference's first corner.
    let mut ref_lines: Vec<usize> = Vec::new();
    let mut ref_ids: HashMap<Reference, usize> = HashMap::new();
    let mut faces: Vec<[usize; 3]> = Vec::new();
    let (mut lines, mut face_lines) = (0, 0);
    for (n, raw) in src.lines().enumerate() {
        let line = n + 1;
        lines = line;
        let text = raw.split('#').next().unwrap_or("");
        let words: Vec<&str> = text.split_whitespace().collect();
        let Some((&head, rest)) = words.split_first() else {
            continue;
        };
        match head {
            "v" => {
                positions.push(floats(line, rest, 3)?);
                colors.push(if rest.len() >= 6 {
                    Some(floats(line, &rest[3..], 3)?)
                } else {
                    None
                });
            }
            "vt" => {
                let [u, v, _] = floats(line, rest, 1)?;
                texcoords.push([u, v]);
            }
            "vn" => normals.push(floats(line, rest, 3)?),
            "f" => {
                if rest.len() < 3 {
                    let given = rest.len();
                    return Err(err(
                        line,
                        format!("a face needs at least 3 vertices, given {given}"),
                    ));
                }
                let mut corner = Vec::with_capacity(rest.len());
                for w in rest {
                    let mut parts = w.split('/');
                    let p = index(line, parts.next().unwrap_or(""), positions.len(), "v")?;
                    let mut optional = |count: usize, kind: &str| match parts.next() {
                        Some(s) if !s.is_empty() => index(line, s, count, kind).map(Some),
                        _ => Ok(None),
                    };
                    let t = optional(texcoords.len(), "vt")?;
                    let nrm = optional(normals.len(), "vn")?;
                    let key = (p, t, nrm);
                    let id = *ref_ids.entry(key).or_insert_with(|| {
                        refs.push(key);
                        ref_lines.push(line);
                        refs.len() - 1
                    });
                    corner.push(id);
                }
                for k in 1..corner.len() - 1 {
                    faces.push([corner[0], corner[k], corner[k + 1]]);
                }
                face_lines += 1;
            }
            _ => {}
        }
    }
    if faces.is_empty() {
        let plural = |n: usize, what: &str| match n {
            1 => format!("1 {what}"),
            n => format!("{n} {what}s"),
        };
        let v = positions.len();
        return Err(err(
            0,
            format!(
                "no faces: a mesh needs at least one `f` line; the text has {}, {v} `v` and \
                 {face_lines} `f` lines",
                plural(lines, "line")
            ),
        ));
    }

    let has_colors = refs.iter().any(|r| colors[r.0].is_some());
    let has_uvs = refs.iter().any(|r| r.1.is_some());
    // Smooth normals around each position (welded: by stored value; else by `v` line).
    let around = |p: usize| -> [i64; 3] {
        if options.weld {
            vec3(positions[p]).to_bits().map(i64::from)
        } else {
            [p as i64, 0, 0]
        }
    };
    let mut smooth: HashMap<[i64; 3], [f64; 3]> = HashMap::new();
    for f in &faces {
        let p = f.map(|i| positions[refs[i].0]);
        let e1 = [0, 1, 2].map(|k| p[1][k] - p[0][k]);
        let e2 = [0, 1, 2].map(|k| p[2][k] - p[0][k]);
        let c = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        // Each position of the face once (a welded face may repeat one).
        let mut seen: Vec<[i64; 3]> = Vec::with_capacity(3);
        for &i in f {
            let key = around(refs[i].0);
            if !seen.contains(&key) {
                seen.push(key);
                let sum = smooth.entry(key).or_insert([0.0; 3]);
                for k in 0..3 {
                    sum[k] += c[k];
                }
            }
        }
    }
    // What the vertex of a reference stores, exactly as the mesh will hold it.
    let vertex_of = |r: &Reference| -> StoredVertex {
        let (p, t, nrm) = *r;
        let normal = match nrm {
            // Explicit normals are kept as written (the pipeline normalises what it uses).
            Some(i) => normals[i],
            None => {
                let n = smooth.get(&around(p)).copied().unwrap_or([0.0; 3]);
                let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                if l > 0.0 {
                    n.map(|c| c / l)
                } else {
                    n
                }
            }
        };
        StoredVertex {
            position: vec3(positions[p]),
            normal: vec3(normal),
            color: has_colors.then(|| colors[p].map_or(Rgb888::WHITE, rgb888)),
            uv: has_uvs.then(|| t.map_or(TexCoord::default(), |t| uv(texcoords[t]))),
        }
    };
    // Welding groups: vertices that store the same values, or distinct references.
    let group = |r: &Reference| -> (StoredVertex, Option<Reference>) {
        (vertex_of(r), (!options.weld).then_some(*r))
    };

    // One output vertex per group, ordered by its first reference.
    // References come in the order of the lines that first name them, so the group that
    // exceeds the limit is the first line's that has more distinct vertices before it.
    let mut groups: HashMap<(StoredVertex, Option<Reference>), usize> = HashMap::new();
    let mut first: Vec<Reference> = Vec::new();
    let mut ref_group: Vec<usize> = Vec::with_capacity(refs.len());
    for (r, &line) in refs.iter().zip(&ref_lines) {
        let id = *groups.entry(group(r)).or_insert_with(|| {
            first.push(*r);
            first.len() - 1
        });
        if first.len() > 65536 {
            return Err(err(
                line,
                "more than 65536 distinct vertices (indices are u16): this face's vertex is the \
                 65537th",
            ));
        }
        if *r < first[id] {
            first[id] = *r;
        }
        ref_group.push(id);
    }
    let mut order: Vec<usize> = (0..first.len()).collect();
    order.sort_by_key(|&g| first[g]);
    let mut remap = std::vec![0u16; first.len()];
    let mut mesh = MeshData::default();
    for (new, &g) in order.iter().enumerate() {
        remap[g] = new as u16;
        let v = vertex_of(&first[g]);
        mesh.vertices.push(v.position);
        mesh.normals.push(v.normal);
        mesh.colors.extend(v.color);
        mesh.uvs.extend(v.uv);
    }
    mesh.indices = faces
        .iter()
        .map(|f| f.map(|i| remap[ref_group[i]]))
        .collect();
    Ok(mesh)
}

/// An output vertex, as stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct StoredVertex {
    position: Vec3,
    normal: Vec3,
    color: Option<Rgb888>,
    uv: Option<TexCoord>,
}

/// A colour with channels in `[0, 1]` as 8-bit channels (rounded, clamped).
fn rgb888(c: [f64; 3]) -> Rgb888 {
    let q = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    Rgb888::new(q(c[0]), q(c[1]), q(c[2]))
}

fn uv(t: [f64; 2]) -> TexCoord {
    TexCoord::new(t[0], t[1])
}

/// Writes a mesh as OBJ text, whatever its fields hold: `v` lines (with `r g b` in `[0, 1]` for
/// vertices that have a colour), `vt` and `vn` lines for the texture coordinates and normals it
/// has, and `f` lines referring to the same index in each.
///
/// For a mesh [`parse`] could have produced — normals, and colours and texture coordinates if
/// any, one per vertex; every index in range; every vertex used by a face; no two vertices
/// that would weld — parsing the result gives back the same mesh, bit for bit. Otherwise
/// `parse` rejects the text (a face naming a missing vertex) or drops the unused vertices and
/// welds the equal ones.
pub fn to_obj(mesh: &MeshData) -> String {
    let mut s = String::from("# written by embedded_raster::three_d::obj\n");
    for (i, v) in mesh.vertices.iter().enumerate() {
        let [x, y, z] = to_f64(*v);
        s += &format!("v {x} {y} {z}");
        if let Some(c) = mesh.colors.get(i) {
            let [r, g, b] = [c.r(), c.g(), c.b()].map(|c| f64::from(c) / 255.0);
            s += &format!(" {r} {g} {b}");
        }
        s += "\n";
    }
    for t in &mesh.uvs {
        let [u, v] = [t.u, t.v].map(|c| c.to_num::<f64>());
        s += &format!("vt {u} {v}\n");
    }
    for n in &mesh.normals {
        let [x, y, z] = to_f64(*n);
        s += &format!("vn {x} {y} {z}\n");
    }
    let has = |len: usize, i: u32| len > i as usize - 1;
    for f in &mesh.indices {
        s += "f";
        for i in f.map(|i| u32::from(i) + 1) {
            let t = if has(mesh.uvs.len(), i) {
                format!("{i}")
            } else {
                String::new()
            };
            s += &match (t.is_empty(), has(mesh.normals.len(), i)) {
                (true, false) => format!(" {i}"),
                (false, false) => format!(" {i}/{t}"),
                (_, true) => format!(" {i}/{t}/{i}"),
            };
        }
        s += "\n";
    }
    s
}

#[cfg(test)]
mod tests {
    use std::string::ToString;

    use super::*;

    /// The error's message: the line and what was wrong there (issue #32, item 2).
    #[test]
    fn obj_error_message() {
        let cases = [
            (
                "v 0 0 0\nv 1 0 0\nf 1 2 3\n",
                "line 3: `v` index 3 out of range: 2 `v` lines before it (indices 1 to 2 or -1 to -2)",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n",
                "line 5: `vt` index 2 out of range: 1 `vt` line before it (index 1 or -1)",
            ),
            (
                "v 0 0 0\nf 1 1 x\n",
                "line 2: expected a `v` index (a non-zero integer), found `x`",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n",
                "line 4: `vn` index 1 out of range: no `vn` line before it",
            ),
            ("v 0 0\n", "line 1: expected 3 numbers, found 2"),
            ("# a comment\nv 0 zero 0\n", "line 2: expected a number, found `zero`"),
            ("v 0 inf 0\n", "line 1: expected a finite number, found `inf`"),
            (
                "v 0 0 0\nv 1 0 0\nf 1 2\n",
                "line 3: a face needs at least 3 vertices, given 2",
            ),
        ];
        for (text, message) in cases {
            assert_eq!(parse(text).unwrap_err().to_string(), message, "{text:?}");
        }
    }

    /// Errors about the whole text (line 0) and [`ReadError`]'s messages: where, and what.
    #[test]
    fn whole_text_and_read_error_messages() {
        let whole = err(0, "no faces");
        assert_eq!(whole.to_string(), "no faces");
        let at = err(7, "expected 3 numbers, found 1");
        assert_eq!(at.to_string(), "line 7: expected 3 numbers, found 1");

        let io = || io::Error::new(io::ErrorKind::NotFound, "no such file");
        let path = Some(PathBuf::from("models/cow.obj"));
        let cases = [
            (
                ReadError::Io {
                    path: None,
                    error: io(),
                },
                "cannot read the OBJ text: no such file",
            ),
            (
                ReadError::Io {
                    path: path.clone(),
                    error: io(),
                },
                "cannot read the OBJ file models/cow.obj: no such file",
            ),
            (
                ReadError::Obj {
                    path: None,
                    error: at.clone(),
                },
                "line 7: expected 3 numbers, found 1",
            ),
            (
                ReadError::Obj {
                    path,
                    error: at.clone(),
                },
                "models/cow.obj: line 7: expected 3 numbers, found 1",
            ),
        ];
        for (error, message) in cases {
            assert_eq!(error.to_string(), message);
            assert!(std::error::Error::source(&error).is_some());
        }
    }
}
