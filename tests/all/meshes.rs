//! Procedural meshes, the OBJ loader/writer and the Rust-source emitter.
//!
//! The flash meshes in `src/meshes/*.rs` must be what the generators and the emitter produce
//! (compared ignoring whitespace and trailing commas, since the files are rustfmt-formatted). Set
//! `REGENERATE_MESHES=1` to rewrite them after changing either.

use embedded_raster::three_d::meshes::{icosphere, to_f64, torus, torus_knot, MeshData};
use embedded_raster::three_d::obj;
use embedded_raster::three_d::{Mesh, Vec3};

use crate::vec_f64;
use vec_f64::{cross, dot, normalize, sub};

/// The text without whitespace and trailing commas (which rustfmt adds or drops with the
/// layout).
fn squeeze(s: &str) -> String {
    let s: String = s.chars().filter(|c| !c.is_whitespace()).collect();
    s.replace(",]", "]").replace(",)", ")")
}

/// The flash meshes of the crate (`src/three_d/meshes/`).
fn check_generated(mesh: &MeshData, name: &str, file: &str) {
    check_source(mesh, name, "crate", &format!("src/three_d/meshes/{file}"));
}

/// `file` (relative to the package) holds `mesh` as emitted for `crate_path`; with
/// `REGENERATE_MESHES` set it is rewritten first.
fn check_source(mesh: &MeshData, name: &str, crate_path: &str, file: &str) {
    let source = &mesh.to_rust_source(name, crate_path);
    let path = format!("{}/{file}", env!("CARGO_MANIFEST_DIR"));
    if std::env::var_os("REGENERATE_MESHES").is_some() {
        std::fs::write(&path, source).unwrap();
        let _ = std::process::Command::new("rustfmt")
            .args(["--edition", "2021", &path])
            .status();
    }
    let stored = std::fs::read_to_string(&path).unwrap();
    assert!(
        squeeze(&stored) == squeeze(source),
        "{path} is stale: rerun with REGENERATE_MESHES=1"
    );
}

fn same_mesh(a: &Mesh<'_>, b: &MeshData) {
    assert_eq!(a.vertices, &b.vertices[..]);
    assert_eq!(a.normals, &b.normals[..]);
    assert_eq!(a.indices, &b.indices[..]);
}

#[test]
fn flash_meshes_match_generators() {
    let ico = icosphere(1.0, 1);
    let tor = torus(1.0, 0.4, 12, 8);
    check_generated(&ico, "ICOSPHERE", "icosphere.rs");
    check_generated(&tor, "TORUS", "torus.rs");
    // The generated statics compile into the crate (no_std) and hold the same data.
    same_mesh(
        &embedded_raster::three_d::meshes::icosphere::ICOSPHERE,
        &ico,
    );
    same_mesh(&embedded_raster::three_d::meshes::torus::TORUS, &tor);
}

/// The 3D benchmark's knot (`examples/common/scene3d.rs`): 6,144 faces.
fn bench_knot() -> MeshData {
    torus_knot((2, 3), 0.33, 0.13, 192, 16)
}

#[test]
fn bench_knot_matches_its_generator() {
    let knot = bench_knot();
    assert_eq!(knot.indices.len(), 6144);
    check_closed_and_oriented(&knot);
    check_source(
        &knot,
        "KNOT",
        "embedded_raster",
        "examples/common/meshes/knot.rs",
    );
}

/// The 3D benchmark's spot (`examples/common/scene3d.rs`): Keenan Crane's cow, released by its
/// author into the public domain (`examples/common/meshes/spot/README.txt`), 5,856 faces. Its
/// texture coordinates are dropped and the vertices they split welded back (2,930), the normals
/// computed around each position, the box centred and its largest half-side scaled to 1.
fn bench_spot() -> MeshData {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/common/meshes/spot/spot_triangulated.obj"
    );
    let mut spot = obj::read_file(path).unwrap();
    spot.uvs.clear();
    spot.weld();
    spot.scale_to_fit(1.0);
    spot
}

#[test]
fn bench_spot_matches_its_obj() {
    let spot = bench_spot();
    assert_eq!(spot.indices.len(), 5856);
    assert_eq!(spot.vertices.len(), 2930);
    check_closed_and_oriented(&spot);
    check_source(
        &spot,
        "SPOT",
        "embedded_raster",
        "examples/common/meshes/spot.rs",
    );
}

/// Spot with its texture coordinates, for the textured frames (`examples/common/scene3d.rs`):
/// the same OBJ welded with them kept, so the vertices on the texture's seams stay split (a
/// vertex for each distinct position and texture coordinate), scaled as `bench_spot`.
fn bench_spot_textured() -> MeshData {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/common/meshes/spot/spot_triangulated.obj"
    );
    let mut spot = obj::read_file(path).unwrap();
    spot.weld();
    spot.scale_to_fit(1.0);
    spot
}

#[test]
fn textured_spot_matches_its_obj() {
    let spot = bench_spot_textured();
    let plain = bench_spot();
    assert_eq!(spot.indices.len(), 5856);
    assert_eq!(spot.uvs.len(), spot.vertices.len());
    // The seams split vertices: more than the welded 2,930, each position still one of them.
    assert!(
        spot.vertices.len() > plain.vertices.len(),
        "{}",
        spot.vertices.len()
    );
    for p in &spot.vertices {
        assert!(plain.vertices.contains(p));
    }
    // The unit square, but for a few coordinates of its OBJ a little outside (u to -0.053).
    let near = -(1 << 16) / 16..=(1 << 16) + (1 << 16) / 16;
    for t in &spot.uvs {
        let [u, v] = t.to_bits();
        assert!(near.contains(&u) && near.contains(&v), "{t:?}");
    }
    check_normals_agree(&spot);
    check_source(
        &spot,
        "SPOT_TEXTURED",
        "embedded_raster",
        "examples/common/meshes/spot_textured.rs",
    );
}

/// Every face is counter-clockwise seen from outside: its geometric normal agrees with its
/// vertex normals; every normal is unit length; every edge is shared by exactly two faces in
/// opposite directions (a closed, consistently oriented surface).
fn check_closed_and_oriented(m: &MeshData) {
    for n in &m.normals {
        let n = to_f64(*n);
        assert!((dot(n, n).sqrt() - 1.0).abs() < 1e-4);
    }
    check_normals_agree(m);
    check_closed(m);
}

/// Every edge is used once in each direction.
fn check_closed(m: &MeshData) {
    let mut edges = std::collections::HashMap::new();
    for f in &m.indices {
        for k in 0..3 {
            *edges.entry((f[k], f[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    for (&(a, b), &count) in &edges {
        assert_eq!(count, 1, "edge {a}-{b} used twice in one direction");
        assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a}-{b} has no twin");
    }
}

#[test]
fn procedural_meshes_are_closed_and_outward() {
    for k in 0..4 {
        let m = icosphere(2.0, k);
        assert_eq!(m.vertices.len(), 10 * 4usize.pow(k) + 2);
        assert_eq!(m.indices.len(), 20 * 4usize.pow(k));
        for v in &m.vertices {
            let r = dot(to_f64(*v), to_f64(*v)).sqrt();
            assert!((r - 2.0).abs() < 1e-4);
        }
        check_closed_and_oriented(&m);
    }
    let t = torus(1.5, 0.5, 16, 10);
    assert_eq!((t.vertices.len(), t.indices.len()), (160, 320));
    check_closed_and_oriented(&t);
}

const CUBE_OBJ: &str = "\
# a unit cube with per-face normals, quads, comments and noise
mtllib cube.mtl
o cube
v -0.5 -0.5 -0.5
v 0.5 -0.5 -0.5
v 0.5 0.5 -0.5
v -0.5 0.5 -0.5
v -0.5 -0.5 0.5
v 0.5 -0.5 0.5
v 0.5 0.5 0.5
v -0.5 0.5 0.5
vt 0 0
vn 0 0 -1
vn 0 0 1
vn 0 -1 0
vn 0 1 0
vn -1 0 0
vn 1 0 0
usemtl white
s off
f 1//1 4//1 3//1 2//1
f 5//2 6//2 7//2 8//2
f 1/1/3 2/1/3 6/1/3 5/1/3
f 4//4 8//4 7//4 3//4
f -8//5 -4//5 -1//5 -5//5
f 2//6 3//6 7//6 6//6
";

#[test]
fn obj_parses_and_round_trips() {
    let cube = obj::parse(CUBE_OBJ).unwrap();
    // 6 faces × 4 distinct (position, normal) corners; each quad fanned into 2 triangles.
    assert_eq!(cube.vertices.len(), 24);
    assert_eq!(cube.indices.len(), 12);
    check_normals_agree(&cube);
    // Written out and read back: the same mesh, bit for bit, and again the same text.
    let text = obj::to_obj(&cube);
    let again = obj::parse(&text).unwrap();
    assert_eq!(again, cube);
    assert_eq!(obj::to_obj(&again), text);

    // Without normals: smooth normals from the faces (a tetrahedron's corners point outwards).
    let tet =
        obj::parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
            .unwrap();
    assert_eq!(tet.vertices.len(), 4);
    let centre = [0.25; 3];
    for (v, n) in tet.vertices.iter().zip(&tet.normals) {
        assert!(dot(sub(to_f64(*v), centre), to_f64(*n)) > 0.0);
    }
    check_closed(&tet);
    assert_eq!(obj::parse(&obj::to_obj(&tet)).unwrap(), tet);

    // Errors carry the line number.
    let e = obj::parse("v 0 0 0\nv 1 0\n").unwrap_err();
    assert_eq!(e.line, 2);
    assert_eq!(obj::parse("v 0 0 0\nf 1 2 3\n").unwrap_err().line, 2);
    assert_eq!(obj::parse("v 0 0 0\nf 1 1\n").unwrap_err().line, 2);
}

/// Text without faces is an error about the whole text (line 0), not an empty mesh (issue #32,
/// item 6): empty, blank, comments only, vertices only, every kind of `v` line without `f`.
#[test]
fn obj_without_faces_is_an_error() {
    let cases = [
        ("", "0 lines, 0 `v` and 0 `f` lines"),
        ("\n\n  \n", "3 lines, 0 `v` and 0 `f` lines"),
        (
            "# exported by nothing\n# at all",
            "2 lines, 0 `v` and 0 `f` lines",
        ),
        (
            "o empty\ng group\ns 1\nusemtl m\n",
            "4 lines, 0 `v` and 0 `f` lines",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\n",
            "3 lines, 3 `v` and 0 `f` lines",
        ),
        (
            "v 0 0 0\nvt 0 0\nvn 0 0 1\n# f 1 1 1\n",
            "4 lines, 1 `v` and 0 `f` lines",
        ),
    ];
    for (text, counts) in cases {
        for weld in [true, false] {
            let e = obj::parse_with(text, obj::ParseOptions { weld }).unwrap_err();
            assert_eq!(e.line, 0, "{text:?}");
            assert_eq!(
                e.to_string(),
                format!("no faces: a mesh needs at least one `f` line; the text has {counts}"),
                "{text:?}"
            );
        }
        let read = obj::read(text.as_bytes()).unwrap_err();
        assert!(
            matches!(read, obj::ReadError::Obj { path: None, .. }),
            "{read:?}"
        );
    }
}

/// OBJ text with `n` distinct vertices on `v` lines (a grid in z = 0) and faces naming them in
/// order, three new ones a face, the last face reaching back for vertices it lacks; each
/// vertex's `v` line is repeated `repeat` times in a row (positions that weld).
fn numbered_vertices(n: usize, repeat: usize) -> String {
    let mut text = String::new();
    for i in 0..n {
        for _ in 0..repeat {
            text += &format!("v {} {} 0\n", i % 300, i / 300);
        }
    }
    let line = |i: usize| i * repeat + 1;
    let mut i = 0;
    while i < n {
        let [a, b, c] = [i, i + 1, i + 2].map(|k| if k < n { k } else { k - 3 });
        text += &format!("f {} {} {}\n", line(a), line(b), line(c));
        i += 3;
    }
    text
}

/// More than 65536 distinct vertices: the error names the line of the face that brings the
/// 65537th (issue #32, item 6; it said line 0), welded or not; at 65536 the mesh is read.
#[test]
fn obj_vertex_limit_names_its_line() {
    // 65538 `v` lines, then faces of three new vertices each: the 65537th is the first corner
    // of face 21,846 (vertices 65,536 to 65,538, 0-based 65,535..), on line 65,538 + 21,846.
    let text = numbered_vertices(65538, 1);
    for weld in [true, false] {
        let e = obj::parse_with(&text, obj::ParseOptions { weld }).unwrap_err();
        assert_eq!(e.line, 65538 + 21846, "weld: {weld}");
        assert_eq!(
            e.to_string(),
            "line 87384: more than 65536 distinct vertices (indices are u16): this face's vertex \
             is the 65537th"
        );
    }
    let mesh = obj::parse(&numbered_vertices(65536, 1)).unwrap();
    assert_eq!(mesh.vertices.len(), 65536);

    // 40,000 positions on two `v` lines each: 80,000 references weld into 40,000 vertices.
    assert_eq!(
        obj::parse(&numbered_vertices(40000, 2))
            .unwrap()
            .vertices
            .len(),
        40000
    );
    // Kept apart, a vertex is a distinct `v/vt/vn` reference: 40,000 positions named plainly,
    // then again with a texture coordinate, are 80,000 vertices (welded: 40,000, as the missing
    // texture coordinates are (0, 0) too). The 65,537th is the 25,537th textured reference: the
    // first corner of the 8,513th textured face, after 40,000 `v` lines, 13,334 plain faces and
    // a `vt` line.
    let plain = numbered_vertices(40000, 1);
    let mut textured = plain.clone() + "vt 0 0\n";
    for face in plain.lines().filter(|l| l.starts_with("f ")) {
        let corners: Vec<String> = face[2..].split(' ').map(|i| format!("{i}/1")).collect();
        textured += &format!("f {}\n", corners.join(" "));
    }
    assert_eq!(obj::parse(&textured).unwrap().vertices.len(), 40000);
    let e = obj::parse_with(&textured, obj::ParseOptions { weld: false }).unwrap_err();
    assert_eq!(e.line, 40000 + 13334 + 1 + 8513);
}

/// Reading from any `Read` and from a file (issue #32, item 6): the meshes `parse` gives; the
/// file's errors carry its path.
#[test]
fn obj_reads_readers_and_files() {
    let tet = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    let want = obj::parse(tet).unwrap();
    assert_eq!(obj::read(tet.as_bytes()).unwrap(), want);
    assert_eq!(obj::read(std::io::Cursor::new(tet)).unwrap(), want);
    let apart = obj::ParseOptions { weld: false };
    assert_eq!(
        obj::read_with(tet.as_bytes(), apart).unwrap(),
        obj::parse_with(tet, apart).unwrap()
    );
    // Bytes that are not UTF-8 in a comment.
    let mut latin1 = b"# cr\xe9\xe9 par nobody\n".to_vec();
    latin1.extend_from_slice(tet.as_bytes());
    assert_eq!(obj::read(&latin1[..]).unwrap(), want);

    let dir = std::env::temp_dir().join(format!("embedded-raster-obj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("tet.obj");
    std::fs::write(&file, tet).unwrap();
    assert_eq!(obj::read_file(&file).unwrap(), want);

    let bad = dir.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nf 1 2 3\n").unwrap();
    let e = obj::read_file(&bad).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "{}: line 2: `v` index 2 out of range: 1 `v` line before it (index 1 or -1)",
            bad.display()
        )
    );
    assert!(matches!(&e, obj::ReadError::Obj { error, .. } if error.line == 2));

    let missing = dir.join("missing.obj");
    let e = obj::read_file(&missing).unwrap_err();
    let obj::ReadError::Io { path, error } = &e else {
        panic!("{e:?}");
    };
    assert_eq!(path.as_deref(), Some(missing.as_path()));
    assert_eq!(error.kind(), std::io::ErrorKind::NotFound);
    assert!(
        e.to_string()
            .starts_with(&format!("cannot read the OBJ file {}: ", missing.display())),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

fn check_normals_agree(m: &MeshData) {
    for f in &m.indices {
        let p = f.map(|i| to_f64(m.vertices[usize::from(i)]));
        let g = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        for &i in f {
            assert!(dot(g, to_f64(m.normals[usize::from(i)])) > 0.0);
        }
    }
}

#[test]
fn rust_source_declares_the_arrays() {
    let tri = obj::parse("v 0 0 0\nv 1.5 0 0\nv 0 -2 0.25\nf 1 3 2\n").unwrap();
    let src = tri.to_rust_source("TRI", "embedded_raster");
    assert!(src.contains("use embedded_raster::three_d::{Mesh, Vec3};"));
    assert!(src.contains("pub static TRI_VERTICES: [Vec3; 3] = ["));
    assert!(src.contains("Vec3::from_bits(98304, 0, 0),"));
    assert!(src.contains("Vec3::from_bits(0, -131072, 16384),"));
    assert!(src.contains("pub static TRI_INDICES: [[u16; 3]; 1] = [\n    [0, 2, 1],\n];"));
    assert!(src.contains("pub static TRI: Mesh<'static> ="));
    // The face normal (0, 0.375, 3) normalised.
    let l = (0.375f64 * 0.375 + 9.0).sqrt();
    let want = [0.0, 0.375 / l, 3.0 / l];
    for (got, want) in to_f64(tri.normals[0]).iter().zip(want) {
        assert!((got - want).abs() < 1e-4);
    }
    assert_eq!(tri.normals[0].x, Vec3::ZERO.x);
}

/// A mesh written as a triangle soup: every face with its own `v` lines, no normals.
fn soup_obj(m: &MeshData) -> String {
    let mut s = String::new();
    for f in &m.indices {
        for &i in f {
            let [x, y, z] = to_f64(m.vertices[usize::from(i)]);
            s += &format!("v {x} {y} {z}\n");
        }
    }
    for k in 0..m.indices.len() {
        s += &format!("f {} {} {}\n", 3 * k + 1, 3 * k + 2, 3 * k + 3);
    }
    s
}

#[test]
fn obj_welds_repeated_positions() {
    let ico = icosphere(1.0, 2);
    let soup = soup_obj(&ico);
    let welded = obj::parse(&soup).unwrap();
    // As many vertices as distinct positions (counted independently), the same triangles.
    let distinct: std::collections::HashSet<[i32; 3]> =
        ico.vertices.iter().map(|v| v.to_bits()).collect();
    assert_eq!(welded.vertices.len(), distinct.len());
    assert_eq!(welded.indices.len(), ico.indices.len());
    check_closed_and_oriented(&welded);
    // Smooth normals: close to the sphere's own normals (the generator's exact ones).
    for (v, n) in welded.vertices.iter().zip(&welded.normals) {
        let (v, n) = (to_f64(*v), to_f64(*n));
        let l = dot(v, v).sqrt();
        assert!(dot(v, n) / l > 0.99, "{v:?} {n:?}");
    }
    // Unwelded: a vertex per `v` line and flat normals, so the soup shades faceted.
    let apart = obj::parse_with(&soup, obj::ParseOptions { weld: false }).unwrap();
    assert_eq!(apart.vertices.len(), 3 * ico.indices.len());
    for f in &apart.indices {
        let n = f.map(|i| apart.normals[usize::from(i)]);
        assert!(n[0] == n[1] && n[1] == n[2]);
    }

    // Two patches that repeat their border (as the Utah teapot's do): the border vertices get
    // one normal, the mean of both sides.
    let patches = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 0\nv 0 1 0\nv -1 0 1\nf 1 2 3\nf 4 5 6\n";
    let m = obj::parse(patches).unwrap();
    assert_eq!(m.vertices.len(), 4);
    let border: Vec<_> = m
        .vertices
        .iter()
        .zip(&m.normals)
        .filter(|(v, _)| v.x == Vec3::ZERO.x)
        .map(|(_, n)| to_f64(*n))
        .collect();
    assert_eq!(border.len(), 2);
    // The faces' doubled-area normals (0, 0, 1) and (1, 0, 1), summed and normalised.
    let want = normalize([1.0, 0.0, 2.0]);
    for n in border {
        for k in 0..3 {
            assert!((n[k] - want[k]).abs() < 1e-4, "{n:?} vs {want:?}");
        }
    }
}

/// A coloured, textured triangle pair: OBJ with `v x y z r g b`, `vt`, `f v/vt/vn`.
const COLORED_OBJ: &str = "\
v 0 0 0 1 0 0
v 1 0 0 0 1 0
v 1 1 0 0 0 1
v 0 1 0 0.5 0.5 0.5
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
f 1/1/1 2/2/1 3/3/1
f 1/1/1 3/3/1 4/4/1
";

#[test]
fn obj_carries_colours_and_texture_coordinates() {
    use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
    use embedded_raster::three_d::TexCoord;
    let m = obj::parse(COLORED_OBJ).unwrap();
    assert_eq!(m.vertices.len(), 4);
    assert_eq!(
        m.colors,
        [
            Rgb888::new(255, 0, 0),
            Rgb888::new(0, 255, 0),
            Rgb888::new(0, 0, 255),
            Rgb888::new(128, 128, 128)
        ]
    );
    assert_eq!(m.uvs[2], TexCoord::new(1, 1));
    assert_eq!(m.validate(), Ok(()));
    assert_eq!(obj::parse(&obj::to_obj(&m)).unwrap(), m);
    // A corner with a different texture coordinate is a vertex of its own (a UV seam), with the
    // same normal.
    let seam = COLORED_OBJ.replace("f 1/1/1 3/3/1 4/4/1", "vt 0.5 0.5\nf 1/5/1 3/3/1 4/4/1");
    assert_eq!(obj::parse(&seam).unwrap().vertices.len(), 5);
    // Corners that end up storing the same values weld, however the file gave them: a computed
    // normal equal to an explicit one, a missing texture coordinate and an explicit (0, 0), a
    // missing colour and an explicit white. Written out and read back: unchanged.
    for text in [
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 2 3\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 1 2 3\n",
        "v 0 0 0 1 1 1\nv 1 0 0\nv 0 1 0\nv 0 0 0\nf 1 2 3\nf 4 2 3\n",
    ] {
        let m = obj::parse(text).unwrap();
        assert_eq!(m.vertices.len(), 3, "{text}");
        assert_eq!(obj::parse(&obj::to_obj(&m)).unwrap(), m, "{text}");
    }
    // Files without colours on some lines: white.
    let partial = obj::parse("v 0 0 0 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    assert_eq!(
        partial.colors,
        [Rgb888::new(0, 0, 0), Rgb888::WHITE, Rgb888::WHITE]
    );
}

use crate::colored_quad;

#[test]
fn rust_source_carries_colours_and_texture_coordinates() {
    let m = obj::parse(COLORED_OBJ).unwrap();
    check_source(
        &m,
        "COLORED_QUAD",
        "embedded_raster",
        "tests/support/colored_quad.rs",
    );
    // The generated statics compile and hold the same data.
    let flash = colored_quad::COLORED_QUAD;
    same_mesh(&flash, &m);
    assert_eq!(flash.colors, &m.colors[..]);
    assert_eq!(flash.uvs, &m.uvs[..]);
}

#[test]
fn mesh_checks_bounds_and_placement() {
    use embedded_raster::three_d::{Mat4, MeshError};
    let tor = torus(1.0, 0.4, 12, 8);
    assert_eq!(tor.validate(), Ok(()));
    let b = tor.bounds().unwrap();
    // The torus' box is ±1.4 in x and y (vertices every 30° around the axis, so at 90°) and
    // ±0.4 in z (every 45° around the tube).
    for (got, want) in to_f64(b.max).iter().zip([1.4, 1.4, 0.4]) {
        assert!((got - want).abs() < 1e-4, "{got} vs {want}");
    }
    let mut moved = tor.clone();
    for v in &mut moved.vertices {
        *v = *v + Vec3::new(10, -3, 0.5);
    }
    moved.recenter();
    let c = moved.bounds().unwrap().center();
    assert!(c.to_bits().iter().all(|v| v.abs() <= 1), "{c:?}");
    moved.scale_to_fit(2.0);
    let b = moved.bounds().unwrap();
    assert!((to_f64(b.max)[0] - 2.0).abs() < 1e-4 && (to_f64(b.min)[0] + 2.0).abs() < 1e-4);
    // The same placement as a model matrix.
    let fit: Mat4 = tor.bounds().unwrap().fit(2);
    let p = fit.transform_point(tor.bounds().unwrap().max);
    assert!((p.x.to_num::<f64>() - 2.0).abs() < 1e-3, "{p:?}");

    // Inconsistent arrays and indices are reported.
    let mut bad = tor.clone();
    bad.normals.pop();
    assert_eq!(
        bad.validate(),
        Err(MeshError::Length {
            array: "normals",
            len: 95,
            vertices: 96
        })
    );
    let mut bad = tor.clone();
    bad.indices[7][1] = 96;
    assert_eq!(
        bad.validate(),
        Err(MeshError::Index {
            triangle: 7,
            index: 96
        })
    );
    assert!(bad
        .validate()
        .unwrap_err()
        .to_string()
        .contains("vertex 96"));

    // Welding a mesh whose vertices were duplicated gives the original back.
    let mut doubled = tor.clone();
    let n = doubled.vertices.len() as u16;
    doubled.vertices.extend_from_within(..);
    doubled.normals.extend_from_within(..);
    for f in doubled.indices.iter_mut().step_by(2) {
        *f = f.map(|i| i + n);
    }
    assert_eq!(doubled.weld(), 96);
    assert_eq!(doubled.vertices.len(), 96);
    check_closed_and_oriented(&doubled);
}
