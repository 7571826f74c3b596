//! Readers of surfaces (`delmesh::io::surface::read_surface`): small files of every format
//! written to a temporary directory, their malformed variants, and the shared surfaces and
//! piecewise linear complexes when present (`../shared/data`).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use delmesh::error::{ErrorKind, Result};
use delmesh::io::surface::read_surface;
use delmesh::recovery::{RegionSeed, Surface};

/// A directory of its own under the system's temporary directory, removed when dropped.
struct TempDir(PathBuf);

impl TempDir {
    fn new() -> TempDir {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "delmesh-surface-read-{}-{}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    /// Writes `bytes` to the file `name` of the directory; returns its path.
    fn write(&self, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
        let path = self.0.join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Reads `text` written to a fresh file `name`.
fn read(name: &str, text: impl AsRef<[u8]>) -> Result<Surface> {
    let dir = TempDir::new();
    read_surface(&dir.write(name, text))
}

/// The error kind and message of reading `text` as the file `name`.
fn failure(name: &str, text: impl AsRef<[u8]>) -> (ErrorKind, String) {
    let error = read(name, text).unwrap_err();
    (error.kind, error.message)
}

/// Asserts that reading `text` as `name` is `InvalidInput` with a message that contains
/// `located` (`name:line:` or `byte offset`) and `words`.
fn assert_syntax_error(name: &str, text: impl AsRef<[u8]>, located: &str, words: &str) {
    let (kind, message) = failure(name, text);
    assert_eq!(kind, ErrorKind::InvalidInput, "{message}");
    assert!(message.contains(located), "{message}: no \"{located}\"");
    assert!(message.contains(words), "{message}: no \"{words}\"");
}

fn point(s: &Surface, v: u32) -> [f64; 3] {
    let k = 3 * v as usize;
    [s.xyz[k], s.xyz[k + 1], s.xyz[k + 2]]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(u: [f64; 3], v: [f64; 3]) -> [f64; 3] {
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// Twice the vector area of each triangle.
fn normals(s: &Surface) -> Vec<[f64; 3]> {
    s.triangles
        .chunks_exact(3)
        .map(|t| {
            let [a, b, c] = [0, 1, 2].map(|k| point(s, t[k]));
            cross(sub(b, a), sub(c, a))
        })
        .collect()
}

/// The total area of the triangles.
fn area(s: &Surface) -> f64 {
    normals(s).into_iter().map(|n| 0.5 * norm(n)).sum()
}

fn n_vertices(s: &Surface) -> usize {
    s.xyz.len() / 3
}

fn n_triangles(s: &Surface) -> usize {
    s.triangles.len() / 3
}

/// Asserts that every triangle has a positive area and a normal along `direction`.
fn assert_facing(s: &Surface, direction: [f64; 3]) {
    for n in normals(s) {
        let along = n[0] * direction[0] + n[1] * direction[1] + n[2] * direction[2];
        assert!(along > 0.0, "normal {n:?} not along {direction:?}");
    }
}

// ---------------------------------------------------------------------------------------
// OFF

const PYRAMID_OFF: &str = "# a square pyramid, its base a quad
OFF   # keyword

5 5 0  # counts
0 0 0
1 0 0 # a comment after a vertex
1 1 0
0 1 0

0.5 0.5 1
4 0 3 2 1   # the base, seen from below
3 0 1 4
3 1 2 4
3 2 3 4
3 3 0 4
";

#[test]
fn off_with_comments_and_a_quad() {
    let s = read("pyramid.off", PYRAMID_OFF).unwrap();
    assert_eq!(n_vertices(&s), 5);
    assert_eq!(&s.xyz[12..], &[0.5, 0.5, 1.0]);
    assert_eq!(n_triangles(&s), 6);
    assert_eq!(&s.triangles[6..], &[0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4]);
    let base = Surface {
        triangles: s.triangles[..6].to_vec(),
        ..s.clone()
    };
    assert_eq!(area(&base), 1.0);
    assert_facing(&base, [0.0, 0.0, -1.0]);
    assert!(s.regions.is_empty() && s.holes.is_empty());
}

#[test]
fn off_variants_skip_colours_and_normals() {
    let coff = "COFF 4 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n\
                0 1 0 9 9 9 9\n3 0 1 2 1 0 0\n3 0 2 3 0.5 0.5 0.5 1\n";
    let s = read("c.OFF", coff).unwrap();
    assert_eq!(s.xyz, vec![0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.]);
    assert_eq!(s.triangles, vec![0, 1, 2, 0, 2, 3]);
    let noff = "NOFF\n3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
    assert_eq!(read("n.off", noff).unwrap().triangles, vec![0, 1, 2]);
    let cnoff = "CNOFF\n3 1 0\n0 0 0 0 0 1 1 1 1 1\n1 0 0 0 0 1 1 1 1 1\n\
                 0 1 0 0 0 1 1 1 1 1\n3 0 1 2\n";
    let s = read("cn.off", cnoff).unwrap();
    assert_eq!(s.xyz, vec![0., 0., 0., 1., 0., 0., 0., 1., 0.]);
}

#[test]
fn polygon_with_collinear_corners_gets_no_flat_triangle() {
    // A rectangle with a T-vertex on its bottom side and a repeated corner.
    let off = "OFF\n5 1 0\n0 0 0\n1 0 0\n2 0 0\n2 1 0\n0 1 0\n6 0 1 2 3 3 4\n";
    let s = read("t.off", off).unwrap();
    assert_eq!(n_triangles(&s), 3);
    assert_eq!(area(&s), 2.0);
    assert_facing(&s, [0.0, 0.0, 1.0]);
    // A triangle with a point on each side.
    let off = "OFF\n6 1 0\n0 0 0\n1 0 0\n2 0 0\n1 1 0\n0 2 0\n0 1 0\n6 0 1 2 3 4 5\n";
    let s = read("t.off", off).unwrap();
    assert_eq!(n_triangles(&s), 4);
    assert_eq!(area(&s), 2.0);
    assert_facing(&s, [0.0, 0.0, 1.0]);
}

#[test]
fn ears_avoid_slivers() {
    // A regular hexagon: the fan from one corner has 30-degree angles, the best
    // triangulation (a central triangle and three ears) too, but never worse.
    let mut off = String::from("OFF\n6 1 0\n");
    for k in 0..6 {
        let angle = std::f64::consts::PI / 3.0 * k as f64;
        off += &format!("{} {} 0\n", angle.cos(), angle.sin());
    }
    off += "6 0 1 2 3 4 5\n";
    let s = read("hexagon.off", &off).unwrap();
    assert_eq!(n_triangles(&s), 4);
    for t in s.triangles.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| point(&s, t[k]));
        for (p, q, r) in [(a, b, c), (b, c, a), (c, a, b)] {
            let (u, v) = (sub(q, p), sub(r, p));
            let sine = norm(cross(u, v)) / (norm(u) * norm(v));
            assert!(sine > 0.49, "angle with sine {sine}");
        }
    }
    // The same file, the same triangles.
    assert_eq!(read("hexagon.off", &off).unwrap(), s);
}

#[test]
fn off_errors_name_the_line() {
    let truncated = "OFF\n3 1 0\n0 0 0\n1 0 0\n";
    assert_syntax_error("a.off", truncated, "a.off:4:", "vertex 3 of 3");
    assert_syntax_error(
        "a.off",
        "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n",
        "a.off:4:",
        "\"x\"",
    );
    assert_syntax_error(
        "a.off",
        "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
        "a.off:6:",
        "out of range",
    );
    assert_syntax_error(
        "a.off",
        "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n",
        "a.off:6:",
        "missing",
    );
    assert_syntax_error(
        "a.off",
        "OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n",
        "a.off:4:",
        "finite",
    );
    assert_syntax_error(
        "a.off",
        "OFF\n2 1 0\n0 0 0\n1 0 0\n2 0 1\n",
        "a.off:5:",
        "at least 3",
    );
    assert_syntax_error("a.off", "PLY\n", "a.off:1:", "OFF");
    assert_syntax_error("a.off", "# nothing\n", "a.off:1:", "end of file");
    // A bow tie cannot be triangulated; the error names the face.
    let bow_tie = "OFF\n4 1 0\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n4 0 1 2 3\n";
    assert_syntax_error("a.off", bow_tie, "a.off:7:", "face 1");
    // Collinear corners only.
    let flat = "OFF\n4 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n4 0 1 2 3\n";
    assert_syntax_error("a.off", flat, "a.off:7:", "no area");
}

// ---------------------------------------------------------------------------------------
// STL

const SQUARE_STL: &str = "solid square
  facet normal 0 0 1
    outer loop
      vertex 0 0 0
      vertex 1 0 0
      vertex 1 1 0
    endloop
  endfacet
  facet normal 0 0 1
    outer loop
      vertex -0 0 0
      vertex 1 1 0
      vertex 0 1 0
    endloop
  endfacet
endsolid square
SOLID second
  FACET NORMAL 0 0 -1 OUTER LOOP VERTEX 0 0 0 VERTEX 0 1 0 VERTEX 0 0 -1 ENDLOOP ENDFACET
ENDSOLID
";

#[test]
fn ascii_stl_shares_vertices() {
    let s = read("square.stl", SQUARE_STL).unwrap();
    assert_eq!(n_vertices(&s), 5);
    assert_eq!(s.triangles, vec![0, 1, 2, 0, 2, 3, 0, 3, 4]);
    assert_eq!(&s.xyz[9..], &[0.0, 1.0, 0.0, 0.0, 0.0, -1.0]);
}

/// A binary STL file with the 80-byte header `header` and the triangles `triangles`.
fn binary_stl(header: &[u8], triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut bytes = header.to_vec();
    bytes.resize(80, b' ');
    bytes.extend((triangles.len() as u32).to_le_bytes());
    for t in triangles {
        bytes.extend([0f32; 3].iter().flat_map(|x| x.to_le_bytes()));
        for p in t {
            bytes.extend(p.iter().flat_map(|x| x.to_le_bytes()));
        }
        bytes.extend([0u8; 2]);
    }
    bytes
}

const SQUARE: [[[f32; 3]; 3]; 2] = [
    [[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.1, 0.1, 0.0]],
    [[0.0, 0.0, 0.0], [0.1, 0.1, 0.0], [0.0, 0.1, 0.0]],
];

#[test]
fn binary_stl_shares_vertices() {
    for header in [&b"binary square"[..], b"solid square, but binary"] {
        let s = read("square.stl", binary_stl(header, &SQUARE)).unwrap();
        assert_eq!(n_vertices(&s), 4);
        assert_eq!(s.triangles, vec![0, 1, 2, 0, 2, 3]);
        assert_eq!(s.xyz[3], f64::from(0.1f32));
        assert_eq!(&s.xyz[9..], &[0.0, f64::from(0.1f32), 0.0]);
    }
}

#[test]
fn stl_errors_name_the_line_or_byte() {
    // A binary file without its last 10 bytes is neither binary nor ASCII.
    let mut bytes = binary_stl(b"square", &SQUARE);
    bytes.truncate(bytes.len() - 10);
    assert_syntax_error("a.stl", &bytes, "a.stl:1:", "neither a binary");
    let mut bytes = binary_stl(b"square", &SQUARE);
    bytes[84 + 50 + 12 + 4..84 + 50 + 12 + 8].copy_from_slice(&f32::INFINITY.to_le_bytes());
    assert_syntax_error("a.stl", &bytes, "a.stl: byte 146:", "triangle 2");
    let truncated = &SQUARE_STL[..SQUARE_STL.find("endloop").unwrap()];
    assert_syntax_error("a.stl", truncated, "a.stl:7:", "end of file");
    let bad = SQUARE_STL.replacen("vertex 1 0 0", "vertex 1 0 zero", 1);
    assert_syntax_error("a.stl", bad, "a.stl:5:", "\"zero\"");
    let bad = SQUARE_STL.replacen("endfacet", "endfacets", 1);
    assert_syntax_error("a.stl", bad, "a.stl:8:", "\"endfacet\"");
}

// ---------------------------------------------------------------------------------------
// OBJ

/// An L-shaped hexagon (area 3) and a triangle, with every corner form.
const L_OBJ: &str = "# an L
mtllib l.mtl
o L
v 0 0 0
v 2 0 0
v 2 1 0 1.0
v 1 1 0
v 1 2 0
v 0 2 0
vt 0 0
vn 0 0 1
g shape
usemtl steel
s off
f 1 2/1 3//1 4/1/1 -2 -1
v 5 5 5
f -1 1/1 2//1
l 1 2
";

#[test]
fn obj_corner_forms_negative_indices_and_a_non_convex_polygon() {
    let s = read("l.obj", L_OBJ).unwrap();
    assert_eq!(n_vertices(&s), 7);
    assert_eq!(n_triangles(&s), 5);
    let l = Surface {
        triangles: s.triangles[..12].to_vec(),
        ..s.clone()
    };
    assert_eq!(area(&l), 3.0);
    assert_facing(&l, [0.0, 0.0, 1.0]);
    assert_eq!(&s.triangles[12..], &[6, 0, 1]);
}

#[test]
fn obj_errors_name_the_line() {
    assert_syntax_error(
        "a.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
        "a.obj:4:",
        "out of range",
    );
    assert_syntax_error(
        "a.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
        "a.obj:4:",
        "out of range",
    );
    assert_syntax_error(
        "a.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n",
        "a.obj:4:",
        "out of range",
    );
    assert_syntax_error("a.obj", "v 0 0 0\nv 1 0\n", "a.obj:2:", "missing z");
    assert_syntax_error(
        "a.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf a/1 2 3\n",
        "a.obj:4:",
        "\"a/1\"",
    );
}

// ---------------------------------------------------------------------------------------
// PLY

/// A square pyramid with its base as a quad, with extra vertex and face properties, an
/// element before the vertices and one after the faces.
const PYRAMID_PLY: &str = "ply
format ascii 1.0
comment made by hand
obj_info nothing
element camera 1
property float32 view
property list uchar float32 rays
element vertex 5
property uchar red
property double x
property float y
property list uint8 int tags
property int z
property float nx
element face 5
property uchar flags
property list uchar int vertex_indices
property float quality
element edge 1
property int vertex1
property int vertex2
end_header
1.5 2 0.5 0.5
255 0 0 0 0 0.1
255 1 0 1 7 0 0.1
255 1 1 2 7 8 0 0.1
255 0 1 0 0 0.1
255 0.5 0.5 0 1 0.1
0 4 0 3 2 1 1
0 3 0 1 4 1
0 3 1 2 4 1
0 3 2 3 4 1 0 3 3 0 4 1
0 1
";

#[test]
fn ascii_ply_with_extra_properties_and_elements() {
    let s = read("pyramid.ply", PYRAMID_PLY).unwrap();
    assert_eq!(n_vertices(&s), 5);
    assert_eq!(&s.xyz[12..], &[0.5, 0.5, 1.0]);
    assert_eq!(n_triangles(&s), 6);
    assert_eq!(&s.triangles[6..], &[0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4]);
    let base = Surface {
        triangles: s.triangles[..6].to_vec(),
        ..s.clone()
    };
    assert_eq!(area(&base), 1.0);
    assert_facing(&base, [0.0, 0.0, -1.0]);
}

/// The pyramid of [`PYRAMID_PLY`] in binary, big-endian or not.
fn binary_pyramid(big_endian: bool) -> Vec<u8> {
    let format = if big_endian {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let header = PYRAMID_PLY[..PYRAMID_PLY.find("end_header").unwrap()]
        .replace("format ascii", &format!("format {format}"))
        .replace("property int z", "property int16 z")
        + "end_header\n";
    let mut bytes = header.into_bytes();
    macro_rules! put {
        ($($x:expr),*) => {
            $(bytes.extend(if big_endian { $x.to_be_bytes() } else { $x.to_le_bytes() });)*
        };
    }
    put!(1.5f32, 2u8, 0.5f32, 0.5f32);
    let vertices = [
        (0.0f64, 0.0f32, 0i16),
        (1.0, 0.0, 0),
        (1.0, 1.0, 0),
        (0.0, 1.0, 0),
        (0.5, 0.5, 1),
    ];
    for (k, v) in vertices.iter().enumerate() {
        put!(255u8, v.0, v.1);
        put!(k as u8 % 3);
        for t in 0..k % 3 {
            put!(t as i32);
        }
        put!(v.2, 0.1f32);
    }
    let faces: [&[i32]; 5] = [
        &[0, 3, 2, 1],
        &[0, 1, 4],
        &[1, 2, 4],
        &[2, 3, 4],
        &[3, 0, 4],
    ];
    for f in faces {
        put!(0u8, f.len() as u8);
        for &i in f {
            put!(i);
        }
        put!(1.0f32);
    }
    put!(0i32, 1i32);
    bytes
}

#[test]
fn binary_ply_both_endiannesses() {
    let ascii = read("pyramid.ply", PYRAMID_PLY).unwrap();
    for big_endian in [false, true] {
        let s = read("pyramid.PLY", binary_pyramid(big_endian)).unwrap();
        assert_eq!(s, ascii, "big endian: {big_endian}");
    }
}

#[test]
fn ply_errors_name_the_line_or_byte() {
    let bytes = binary_pyramid(false);
    let truncated = &bytes[..bytes.len() - 12];
    assert_syntax_error("a.ply", truncated, "a.ply: byte", "end of file");
    let mut wrong = binary_pyramid(true);
    let at = wrong.len() - 8 - 4 - 4;
    wrong[at..at + 4].copy_from_slice(&9i32.to_be_bytes());
    assert_syntax_error(
        "a.ply",
        wrong,
        &format!("a.ply: byte {at}:"),
        "vertex index 9",
    );
    let bad = PYRAMID_PLY.replacen("255 1 0 1 7 0 0.1", "255 1 zero 1 7 0 0.1", 1);
    assert_syntax_error("a.ply", bad, "a.ply:25:", "\"zero\"");
    let bad = PYRAMID_PLY.replacen("0 3 1 2 4 1", "0 3 1 2 5 1", 1);
    assert_syntax_error("a.ply", bad, "a.ply:31:", "vertex index 5");
    let truncated = &PYRAMID_PLY[..PYRAMID_PLY.find("0 3 1 2 4").unwrap()];
    assert_syntax_error("a.ply", truncated, "a.ply:30:", "end of file");
    let bad = PYRAMID_PLY.replacen("property float y", "property real y", 1);
    assert_syntax_error("a.ply", bad, "a.ply:11:", "\"real\"");
    let bad = PYRAMID_PLY.replacen("property float y\n", "", 1);
    assert_syntax_error("a.ply", bad, "a.ply:", "no property \"y\"");
    assert_syntax_error("a.ply", "ply\nformat ascii 1.0\n", "a.ply:3:", "end_header");
    assert_syntax_error("a.ply", "solid\n", "a.ply:1:", "not a PLY file");
}

// ---------------------------------------------------------------------------------------
// TetGen

/// A cube [0,2]^3 of 6 quads, 1-based, with attributes and markers, a hole and 3 regions.
const CUBE_SMESH: &str = "# part 1: nodes
8 3 1 1
1 0 0 0  0.5 1
2 2 0 0  0.5 1
3 2 2 0  0.5 1
4 0 2 0  0.5 1
5 0 0 2  0.5 1
6 2 0 2  0.5 1
7 2 2 2  0.5 1
8 0 2 2  0.5 1
# part 2: facets
6 1
4 1 4 3 2 5
4 5 6 7 8 6
4 1 2 6 5 1
4 2 3 7 6 2
4 3 4 8 7 3
4 4 1 5 8 4
# part 3: holes
1
1 1 1 1.5
# part 4: regions
3
1 1 1 0.5 7 0.25
2 1 0.5 1 -3 -1
3 0.5 1 1 4.0
";

#[test]
fn smesh_with_holes_and_regions() {
    let s = read("cube.smesh", CUBE_SMESH).unwrap();
    assert_eq!(n_vertices(&s), 8);
    assert_eq!(&s.xyz[21..], &[0.0, 2.0, 2.0]);
    assert_eq!(n_triangles(&s), 12);
    assert_eq!(area(&s), 24.0);
    assert!(s.triangles.iter().all(|&v| v < 8));
    assert_eq!(s.holes, vec![[1.0, 1.0, 1.5]]);
    let seed = |point, label, max_volume| RegionSeed {
        point,
        label,
        max_volume,
    };
    assert_eq!(
        s.regions,
        vec![
            seed([1.0, 1.0, 0.5], 7, 0.25),
            seed([1.0, 0.5, 1.0], -3, 0.0),
            seed([0.5, 1.0, 1.0], 4, 0.0),
        ]
    );
    // Outward quads give outward triangles: the bottom faces -z, the top +z.
    let normals = normals(&s);
    assert!(normals[..2].iter().all(|n| n[2] < 0.0));
    assert!(normals[2..4].iter().all(|n| n[2] > 0.0));
}

#[test]
fn smesh_points_from_the_node_file() {
    let dir = TempDir::new();
    let (nodes, rest) = CUBE_SMESH.split_at(CUBE_SMESH.find("# part 2").unwrap());
    dir.write("cube.node", nodes);
    let path = dir.write("cube.smesh", format!("0 3 0 0\n{rest}"));
    assert_eq!(
        read_surface(&path).unwrap(),
        read("cube.smesh", CUBE_SMESH).unwrap()
    );
    std::fs::remove_file(dir.0.join("cube.node")).unwrap();
    let error = read_surface(&path).unwrap_err();
    assert_eq!(error.kind, ErrorKind::Io);
    assert!(error.message.contains("cube.node"), "{}", error.message);
}

/// A 4 x 4 square with a 2 x 2 square hole in its middle, in the plane z = x + 1, 0-based;
/// a second facet is a square made of two polygons sharing an edge.
const FRAME_POLY: &str = "14 3 0 0
0 0 0 1
1 4 0 5
2 4 4 5
3 0 4 1
4 1 1 2
5 3 1 4
6 3 3 4
7 1 3 2
8 0 0 -1
9 1 0 -1
10 2 0 -1
11 2 1 -1
12 1 1 -1
13 0 1 -1
2 1
2 1 5    # the frame: 2 polygons, 1 hole, marker 5
4 0 1 2 3
4 4 5 6 7
0 2 2 3
2 0   # two rectangles side by side
4 8 9 12 13
4 9 10 11 12
0
";

#[test]
fn poly_facet_with_a_hole() {
    let s = read("frame.poly", FRAME_POLY).unwrap();
    assert_eq!(n_vertices(&s), 14);
    // The frame: 8 corners and a hole, 8 triangles; then 2 + 2 triangles.
    assert_eq!(n_triangles(&s), 12);
    let frame = Surface {
        triangles: s.triangles[..24].to_vec(),
        ..s.clone()
    };
    let slope = 2f64.sqrt();
    assert!(
        (area(&frame) - 12.0 * slope).abs() < 1e-12,
        "{}",
        area(&frame)
    );
    assert_facing(&frame, [-1.0, 0.0, 1.0]);
    assert!(frame.triangles.iter().all(|&v| v < 8));
    let rectangles = Surface {
        triangles: s.triangles[24..].to_vec(),
        ..s.clone()
    };
    assert_eq!(area(&rectangles), 2.0);
    assert!(s.holes.is_empty() && s.regions.is_empty());
    // Without the hole point, the inner square is triangulated too.
    let filled = FRAME_POLY
        .replace("2 1 5    #", "2 0 5    #")
        .replace("0 2 2 3\n", "");
    let s = read("frame.poly", filled).unwrap();
    assert_eq!(n_triangles(&s), 2 + 2 + 4);
}

#[test]
fn poly_facet_polygons_nested_twice() {
    // A square with a square hole with a square island: hole points in the hole only.
    let poly = "12 3 0 0
1 0 0 0
2 6 0 0
3 6 6 0
4 0 6 0
5 1 1 0
6 5 1 0
7 5 5 0
8 1 5 0
9 2 2 0
10 4 2 0
11 4 4 0
12 2 4 0
1 0
3 1
4 1 2 3 4
4 8 7 6 5
4 9 10 11 12
1 1.5 3 0
";
    let s = read("island.poly", poly).unwrap();
    assert_eq!(area(&s), 36.0 - 16.0 + 4.0);
    assert_eq!(n_triangles(&s), 8 + 2);
    assert_facing(&s, [0.0, 0.0, 1.0]);
}

/// A star-shaped polygon of `n` corners around `center`, radii in `radius` (`random` gives
/// numbers in [0, 1)), counter-clockwise; every fourth corner is put on the segment of its
/// neighbours when `collinear` and there are at least 8 corners (the polygon stays
/// star-shaped: two corners apart are less than half a turn apart).
fn star(
    random: &mut impl FnMut() -> f64,
    n: usize,
    center: [f64; 2],
    radius: [f64; 2],
    collinear: bool,
) -> Vec<[f64; 2]> {
    let mut corners: Vec<[f64; 2]> = (0..n)
        .map(|k| {
            let angle = std::f64::consts::TAU * (k as f64 + 0.8 * random()) / n as f64;
            let r = radius[0] + (radius[1] - radius[0]) * random();
            [center[0] + r * angle.cos(), center[1] + r * angle.sin()]
        })
        .collect();
    if collinear && n >= 8 {
        for k in (1..n - 1).step_by(4) {
            // The midpoint of two points whose coordinates are multiples of 2^-20 is exact.
            let snap = |x: f64| (x * 1048576.0).round() / 1048576.0;
            corners[k - 1] = corners[k - 1].map(snap);
            corners[k + 1] = corners[k + 1].map(snap);
            corners[k] = [0, 1].map(|c| (corners[k - 1][c] + corners[k + 1][c]) / 2.0);
        }
    }
    corners
}

/// Twice the signed area of a polygon.
fn shoelace(corners: &[[f64; 2]]) -> f64 {
    (0..corners.len())
        .map(|k| {
            let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum()
}

#[test]
fn random_polygons_with_holes() {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut random = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for round in 0..200 {
        // Enough corners for the outer polygon to hold the disk of radius 1.5 where the
        // holes are: its corners two apart are at most 3.6 / 16 turn apart, so that its
        // sides are at least 2 cos(40.5 degrees) from the centre.
        let n = 16 + round % 40;
        let outer = star(&mut random, n, [0.0, 0.0], [2.0, 3.0], round % 2 == 0);
        let centers = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0], [0.0, 0.0]];
        let holes: Vec<Vec<[f64; 2]>> = centers[..round % 6]
            .iter()
            .enumerate()
            .map(|(h, &c)| {
                let mut hole = star(&mut random, 4 + (round + h) % 9, c, [0.2, 0.45], h % 2 == 1);
                if h % 2 == 0 {
                    hole.reverse();
                }
                hole
            })
            .collect();
        let loops: Vec<&Vec<[f64; 2]>> = std::iter::once(&outer).chain(&holes).collect();
        let n_points: usize = loops.iter().map(|l| l.len()).sum();
        let mut poly = format!("{n_points} 3 0 0\n");
        let mut index = 0;
        for l in &loops {
            for p in l.iter() {
                poly += &format!("{index} {:?} {:?} 7.5\n", p[0], p[1]);
                index += 1;
            }
        }
        poly += &format!("1 0\n{} {}\n", loops.len(), holes.len());
        let mut first = 0;
        for l in &loops {
            poly += &format!("{}", l.len());
            for k in 0..l.len() {
                poly += &format!(" {}", first + k);
            }
            poly += "\n";
            first += l.len();
        }
        for (h, c) in centers[..holes.len()].iter().enumerate() {
            poly += &format!("{h} {:?} {:?} 7.5\n", c[0], c[1]);
        }
        let s = read("random.poly", &poly).unwrap_or_else(|e| panic!("round {round}: {e}"));
        assert_eq!(
            n_triangles(&s),
            n_points + 2 * holes.len() - 2,
            "round {round}"
        );
        let expected =
            0.5 * (shoelace(&outer) - holes.iter().map(|h| shoelace(h).abs()).sum::<f64>());
        assert!(
            (area(&s) - expected).abs() < 1e-12 * expected,
            "round {round}"
        );
        assert_facing(&s, [0.0, 0.0, 1.0]);
    }
}

#[test]
fn tetgen_errors_name_the_line() {
    let bad = CUBE_SMESH.replacen("4 3 4 8 7 3", "4 3 4 9 7 3", 1);
    assert_syntax_error("a.smesh", bad, "a.smesh:17:", "out of range");
    let bad = CUBE_SMESH.replacen("2 2 0 0  0.5 1", "2 2 0 O  0.5 1", 1);
    assert_syntax_error("a.smesh", bad, "a.smesh:4:", "\"O\"");
    let bad = CUBE_SMESH.replacen("3 2 2 0  0.5 1", "4 2 2 0  0.5 1", 1);
    assert_syntax_error("a.smesh", bad, "a.smesh:5:", "consecutively");
    let bad = CUBE_SMESH.replacen("3 0.5 1 1 4.0", "3 0.5 1 1 4.5", 1);
    assert_syntax_error("a.smesh", bad, "a.smesh:26:", "not a 32-bit integer");
    let truncated = &CUBE_SMESH[..CUBE_SMESH.find("4 3 4 8 7").unwrap()];
    assert_syntax_error("a.smesh", truncated, "a.smesh:16:", "facet 5 of 6");
    let segment = CUBE_SMESH.replacen("4 1 4 3 2 5", "2 1 4", 1);
    assert_syntax_error("a.smesh", segment, "a.smesh:13:", "not supported");
    let bad = FRAME_POLY.replacen("0 2 2 3", "0 2 2", 1);
    assert_syntax_error("a.poly", bad, "a.poly:20:", "missing z");
    let on_edge = FRAME_POLY.replacen("0 2 2 3", "0 1 2 2", 1);
    assert_syntax_error("a.poly", on_edge, "a.poly:17:", "boundary");
    let segment = FRAME_POLY.replacen("4 4 5 6 7", "2 4 5", 1);
    assert_syntax_error("a.poly", segment, "a.poly:17:", "not supported");
    let extra = format!("{CUBE_SMESH}5\n");
    assert_syntax_error("a.smesh", extra, "a.smesh:27:", "after the regions");
}

// ---------------------------------------------------------------------------------------
// Files

#[test]
fn unknown_extension_and_missing_file() {
    let error = read("a.vtk", PYRAMID_OFF).unwrap_err();
    assert_eq!(error.kind, ErrorKind::InvalidArgument);
    assert!(error.message.contains("\"vtk\""), "{}", error.message);
    let error = read_surface(Path::new("/nonexistent/delmesh/a.off")).unwrap_err();
    assert_eq!(error.kind, ErrorKind::Io);
    assert!(
        error.message.contains("/nonexistent/delmesh/a.off"),
        "{}",
        error.message
    );
}

// ---------------------------------------------------------------------------------------
// The shared data

/// The expected vertex and triangle counts of the MANIFEST.tsv descriptions
/// (`V=.. F=.. tri`, `V=.. F=.. poly(4:23,...)`, `TetGen PLC: .. nodes, .. (.. sizes {3: 2,
/// 4: 11})`), by file.
fn manifest(data: &Path) -> HashMap<String, (usize, usize)> {
    let text = std::fs::read_to_string(data.join("MANIFEST.tsv")).unwrap_or_default();
    let number = |s: &str| s.trim().parse::<usize>().unwrap();
    // Triangles of polygons of `k` corners, `count` of them, listed as "k:count" pairs.
    let triangles = |pairs: &str, separator: char| -> usize {
        pairs
            .split(',')
            .map(|pair| {
                let (k, count) = pair.split_once(separator).unwrap();
                (number(k) - 2) * number(count)
            })
            .sum()
    };
    let mut counts = HashMap::new();
    for line in text.lines().skip(1) {
        let fields: Vec<&str> = line.split('\t').collect();
        let Some(description) = fields.last().and_then(|d| d.split(" | ").nth(1)) else {
            continue;
        };
        let expected = if let Some(rest) = description.strip_prefix("V=") {
            let (v, rest) = rest.split_once(" F=").unwrap();
            let (f, rest) = rest.split_once(' ').unwrap();
            let t = match rest.strip_prefix("poly(") {
                Some(pairs) => triangles(&pairs[..pairs.find(')').unwrap()], ':'),
                None => number(f),
            };
            (number(v), t)
        } else if let Some(rest) = description.strip_prefix("TetGen PLC: ") {
            let (v, rest) = rest.split_once(" nodes").unwrap();
            let sizes = &rest[rest.find("sizes {").unwrap() + 7..rest.find('}').unwrap()];
            (number(v), triangles(sizes, ':'))
        } else {
            continue;
        };
        counts.insert(fields[0].to_string(), expected);
    }
    counts
}

/// The files under `dir` (recursively), sorted.
fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let path = entry.path();
        if path.is_dir() {
            files.extend(files_under(&path));
        } else {
            files.push(path);
        }
    }
    files.sort();
    files
}

/// The vertex count and the triangles of the faces (`n - 2` per face of `n` corners) in the
/// header and the face lines of an OFF file.
fn off_counts(path: &Path) -> (usize, usize) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut numbers = text
        .lines()
        .map(|l| l.split('#').next().unwrap())
        .filter(|l| !l.trim().is_empty())
        .skip(1);
    let header: Vec<usize> = text
        .lines()
        .find(|l| l.contains("OFF"))
        .unwrap()
        .split_whitespace()
        .skip(1)
        .map(|f| f.parse().unwrap())
        .collect();
    let counts: Vec<usize> = if header.len() >= 2 {
        header
    } else {
        let line = numbers.next().unwrap();
        line.split_whitespace()
            .map(|f| f.parse().unwrap())
            .collect()
    };
    let (v, f) = (counts[0], counts[1]);
    let triangles = numbers
        .skip(v)
        .take(f)
        .map(|l| {
            l.split_whitespace()
                .next()
                .unwrap()
                .parse::<usize>()
                .unwrap()
                - 2
        })
        .sum();
    (v, triangles)
}

#[test]
fn shared_surfaces_and_complexes() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data");
    if !data.is_dir() {
        eprintln!("skipped: no {}", data.display());
        return;
    }
    let expected = manifest(&data);
    let mut failures = Vec::new();
    let mut n_read = 0;
    for (folder, extensions) in [
        ("surfaces", &["off", "ply", "obj", "stl"][..]),
        ("plc", &["smesh", "off"][..]),
    ] {
        for path in files_under(&data.join(folder)) {
            let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
            if !extensions.contains(&extension) {
                continue;
            }
            let name = path
                .strip_prefix(&data)
                .unwrap()
                .to_string_lossy()
                .into_owned();
            let s = match read_surface(&path) {
                Ok(s) => s,
                Err(e) => {
                    failures.push(format!("{name}: {e}"));
                    continue;
                }
            };
            n_read += 1;
            let counts = (n_vertices(&s), n_triangles(&s));
            if extension == "off" {
                assert_eq!(counts, off_counts(&path), "{name}: against its header");
            }
            if let Some(&manifest_counts) = expected.get(&name) {
                assert_eq!(counts, manifest_counts, "{name}: against MANIFEST.tsv");
            }
            assert!(
                s.triangles.iter().all(|&v| (v as usize) < counts.0),
                "{name}"
            );
            assert!(
                normals(&s).iter().all(|&n| norm(n) > 0.0),
                "{name}: a flat triangle"
            );
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(n_read > 0);
    eprintln!("read {n_read} shared files");
}
