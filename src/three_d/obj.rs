//! A small Wavefront OBJ loader and writer for the host (`std` feature).
//!
//! [`parse`] reads `v`, `vn` and `f` statements (faces with `v`, `v/vt`, `v//vn` or `v/vt/vn`
//! references, 1-based or negative, polygons fanned into triangles) into a
//! `MeshData` ([`meshes::MeshData`](crate::three_d::meshes::MeshData)) and ignores everything else (`vt`, `o`, `g`, `s`,
//! materials, comments). A vertex is emitted per distinct position/normal pair; vertices whose
//! faces give no normal get the normalised area-weighted mean of their faces' normals; explicit
//! normals are kept as written. Vertices come out sorted by (position, normal) index, unused
//! positions are dropped. [`to_obj`] writes a
//! mesh back out exactly (every `I16F16` value prints as a decimal that parses back to it), and
//! [`MeshData::to_rust_source`](crate::three_d::meshes::MeshData::to_rust_source) turns it into `static`
//! arrays for firmware.
//!
//! ```
//! use embedded_raster::three_d::obj;
//!
//! let mesh = obj::parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
//! assert_eq!(mesh.indices, vec![[0, 1, 2]]);
//! assert_eq!(mesh.normals[0].z.to_num::<f64>(), 1.0);
//! assert_eq!(obj::parse(&obj::to_obj(&mesh)).unwrap(), mesh);
//! ```

use std::collections::HashMap;
use std::fmt;
use std::format;
use std::string::String;
use std::vec::Vec;

use crate::three_d::meshes::{to_f64, vec3, MeshData};

/// Why an OBJ file could not be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObjError {
    /// 1-based line number.
    pub line: usize,
    /// What was wrong.
    pub message: String,
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

impl std::error::Error for ObjError {}

fn err(line: usize, message: impl Into<String>) -> ObjError {
    ObjError {
        line,
        message: message.into(),
    }
}

fn floats(line: usize, words: &[&str], n: usize) -> Result<[f64; 3], ObjError> {
    if words.len() < n {
        return Err(err(line, format!("expected {n} numbers")));
    }
    let mut v = [0.0; 3];
    for (slot, w) in v.iter_mut().zip(words) {
        *slot = w
            .parse::<f64>()
            .map_err(|_| err(line, format!("not a number: {w}")))?;
        if !slot.is_finite() {
            return Err(err(line, format!("not finite: {w}")));
        }
    }
    Ok(v)
}

/// Resolves a 1-based or negative (relative) OBJ index against `count` items.
fn index(line: usize, word: &str, count: usize) -> Result<usize, ObjError> {
    let i: i64 = word
        .parse()
        .map_err(|_| err(line, format!("bad index: {word}")))?;
    let resolved = if i > 0 { i - 1 } else { count as i64 + i };
    if i == 0 || resolved < 0 || resolved >= count as i64 {
        return Err(err(line, format!("index out of range: {word}")));
    }
    Ok(resolved as usize)
}

/// Parses OBJ text into a triangle mesh.
pub fn parse(src: &str) -> Result<MeshData, ObjError> {
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut normals: Vec<[f64; 3]> = Vec::new();
    // Output vertices: (position index, normal index or None).
    let mut keys: Vec<(usize, Option<usize>)> = Vec::new();
    let mut lookup: HashMap<(usize, Option<usize>), usize> = HashMap::new();
    let mut faces: Vec<[usize; 3]> = Vec::new();
    for (n, raw) in src.lines().enumerate() {
        let line = n + 1;
        let text = raw.split('#').next().unwrap_or("");
        let words: Vec<&str> = text.split_whitespace().collect();
        let Some((&head, rest)) = words.split_first() else {
            continue;
        };
        match head {
            "v" => positions.push(floats(line, rest, 3)?),
            "vn" => normals.push(floats(line, rest, 3)?),
            "f" => {
                if rest.len() < 3 {
                    return Err(err(line, "a face needs at least 3 vertices"));
                }
                let mut corner = Vec::with_capacity(rest.len());
                for w in rest {
                    let mut parts = w.split('/');
                    let p = index(line, parts.next().unwrap_or(""), positions.len())?;
                    let _texture = parts.next();
                    let nrm = match parts.next() {
                        Some(s) if !s.is_empty() => Some(index(line, s, normals.len())?),
                        _ => None,
                    };
                    let key = (p, nrm);
                    let id = *lookup.entry(key).or_insert_with(|| {
                        keys.push(key);
                        keys.len() - 1
                    });
                    corner.push(id);
                }
                for k in 1..corner.len() - 1 {
                    faces.push([corner[0], corner[k], corner[k + 1]]);
                }
            }
            _ => {}
        }
    }
    if keys.len() > 65536 {
        return Err(err(0, "more than 65536 distinct vertices"));
    }
    // Area-weighted face normals per position, for vertices without an explicit normal.
    let mut smooth = vec_zero(positions.len());
    for f in &faces {
        let p = f.map(|i| positions[keys[i].0]);
        let e1 = [0, 1, 2].map(|k| p[1][k] - p[0][k]);
        let e2 = [0, 1, 2].map(|k| p[2][k] - p[0][k]);
        let c = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        for &i in f {
            for k in 0..3 {
                smooth[keys[i].0][k] += c[k];
            }
        }
    }
    // Output vertices in (position, normal) order: files written by `to_obj` come back unchanged.
    let mut order: Vec<usize> = (0..keys.len()).collect();
    order.sort_by_key(|&i| keys[i]);
    let mut remap = std::vec![0u16; keys.len()];
    let mut mesh = MeshData::default();
    for (new, &old) in order.iter().enumerate() {
        remap[old] = new as u16;
        let (p, nrm) = keys[old];
        let normal = match nrm {
            // Explicit normals are kept as written (the pipeline normalises what it uses).
            Some(i) => normals[i],
            None => {
                let n = smooth[p];
                let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                if l > 0.0 {
                    n.map(|c| c / l)
                } else {
                    n
                }
            }
        };
        mesh.vertices.push(vec3(positions[p]));
        mesh.normals.push(vec3(normal));
    }
    mesh.indices = faces.iter().map(|f| f.map(|i| remap[i])).collect();
    Ok(mesh)
}

fn vec_zero(n: usize) -> Vec<[f64; 3]> {
    std::vec![[0.0; 3]; n]
}

/// Writes a mesh as OBJ text (`v`, `vn`, and `f v//vn` lines), whatever its fields hold.
///
/// For a mesh [`parse`] could have produced — one normal per vertex, every index in range, every
/// vertex used by a face — parsing the result gives back the same mesh, bit for bit. Otherwise
/// `parse` rejects the text (a face naming a missing vertex or normal) or drops the unused
/// vertices.
pub fn to_obj(mesh: &MeshData) -> String {
    let mut s = String::from("# written by embedded_raster::three_d::obj\n");
    for v in &mesh.vertices {
        let [x, y, z] = to_f64(*v);
        s += &format!("v {x} {y} {z}\n");
    }
    for n in &mesh.normals {
        let [x, y, z] = to_f64(*n);
        s += &format!("vn {x} {y} {z}\n");
    }
    for f in &mesh.indices {
        let [a, b, c] = f.map(|i| u32::from(i) + 1);
        s += &format!("f {a}//{a} {b}//{b} {c}//{c}\n");
    }
    s
}
