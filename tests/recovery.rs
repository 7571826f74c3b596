//! Surface tetrahedralization (`recovery`): every input triangle kept, volume preserved, regions
//! labeled, on generated surfaces and, when present, the shared corpus of closed surfaces.

use std::collections::{HashMap, HashSet};
use std::path::Path;

use delmesh::recovery::{tetrahedralize_surface, SurfaceOptions};
use delmesh::{ErrorKind, Mesh};

/// The vertices and triangles of an OFF file (triangles only; polygons fanned).
fn read_off(path: &Path) -> (Vec<f64>, Vec<u32>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut tokens = text
        .lines()
        .map(|l| l.split('#').next().unwrap_or(""))
        .flat_map(|l| l.split_whitespace())
        .skip(1);
    let mut next = || tokens.next().unwrap();
    let (nv, nf) = (next().parse::<usize>().unwrap(), next().parse::<usize>().unwrap());
    next();
    let xyz = (0..3 * nv).map(|_| next().parse().unwrap()).collect();
    let mut triangles = Vec::new();
    for _ in 0..nf {
        let k: usize = next().parse().unwrap();
        let f: Vec<u32> = (0..k).map(|_| next().parse().unwrap()).collect();
        for i in 1..k - 1 {
            triangles.extend_from_slice(&[f[0], f[i], f[i + 1]]);
        }
    }
    (xyz, triangles)
}

fn point(xyz: &[f64], v: u32) -> [f64; 3] {
    let i = 3 * v as usize;
    [xyz[i], xyz[i + 1], xyz[i + 2]]
}

/// Six times the signed volume of (a, b, c, d).
fn volume6(p: [[f64; 3]; 4]) -> f64 {
    let u = [0, 1, 2].map(|k| p[1][k] - p[0][k]);
    let v = [0, 1, 2].map(|k| p[2][k] - p[0][k]);
    let w = [0, 1, 2].map(|k| p[3][k] - p[0][k]);
    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
}

/// Checks the result against its input; returns the number of Steiner points.
fn check(xyz: &[f64], triangles: &[u32], mesh: &Mesh) -> usize {
    mesh.validate().unwrap();
    let n = xyz.len() / 3;
    assert_eq!(&mesh.vertices[..3 * n], xyz, "input vertices changed");
    assert_eq!(mesh.facets, triangles, "facets are not the input triangles");
    // Facets with one or two tetrahedra; boundary facets exactly the input triangles.
    let mut count: HashMap<[u32; 3], Vec<i32>> = HashMap::new();
    for (tet, &label) in mesh.tetrahedra.chunks_exact(4).zip(&mesh.tetrahedron_labels) {
        for skip in 0..4 {
            let mut f: Vec<u32> = (0..4).filter(|&k| k != skip).map(|k| tet[k]).collect();
            f.sort_unstable();
            count.entry([f[0], f[1], f[2]]).or_default().push(label);
        }
    }
    let input: HashSet<[u32; 3]> = triangles
        .chunks_exact(3)
        .map(|f| {
            let mut k = [f[0], f[1], f[2]];
            k.sort_unstable();
            k
        })
        .collect();
    for (f, labels) in &count {
        assert!(labels.len() <= 2, "facet {f:?} in {} tetrahedra", labels.len());
        let separating = labels.len() == 1 || labels[0] != labels[1];
        if separating {
            assert!(input.contains(f), "facet {f:?} separates regions but is no input triangle");
        }
    }
    for f in &input {
        assert!(count.contains_key(f), "input triangle {f:?} is not a facet");
    }
    // Volume: the tetrahedra's against the divergence theorem over outward-labeled facets.
    let outside_volume: f64 = triangles
        .chunks_exact(3)
        .zip(mesh.facet_labels.chunks_exact(2))
        .map(|(f, l)| {
            let p = [[0.0; 3], point(xyz, f[0]), point(xyz, f[1]), point(xyz, f[2])];
            match (l[0], l[1]) {
                (0, 0) => panic!("facet {f:?} has the outside on both sides"),
                (_, 0) => volume6(p),
                (0, _) => -volume6(p),
                _ => 0.0,
            }
        })
        .sum();
    let total: f64 = mesh
        .tetrahedra
        .chunks_exact(4)
        .map(|t| volume6([0, 1, 2, 3].map(|k| mesh.vertex(t[k]))))
        .sum();
    let rel = (total - outside_volume).abs() / total;
    assert!(rel < 1e-9, "volume {total} vs enclosed {outside_volume} ({rel:e})");
    mesh.vertex_count() - n
}

fn cube() -> (Vec<f64>, Vec<u32>) {
    let mut xyz = Vec::new();
    for v in 0..8 {
        xyz.extend_from_slice(&[(v & 1) as f64, (v >> 1 & 1) as f64, (v >> 2 & 1) as f64]);
    }
    let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    let tris = quads.iter().flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]]).collect();
    (xyz, tris)
}

#[test]
fn cube_is_five_or_six_tetrahedra_without_steiner_points() {
    let (xyz, tris) = cube();
    let mesh = tetrahedralize_surface(&xyz, &tris, &SurfaceOptions::default()).unwrap();
    assert_eq!(check(&xyz, &tris, &mesh), 0);
    assert!(mesh.tetrahedron_labels.iter().all(|&l| l == 1));
}

#[test]
fn corpus_surfaces() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/surfaces");
    let Ok(manifest) = std::fs::read_to_string(dir.join("../MANIFEST.tsv")) else {
        eprintln!("corpus absent: skipped");
        return;
    };
    let mut failures = Vec::new();
    for line in manifest.lines() {
        let file = line.split('\t').next().unwrap_or("");
        if !file.starts_with("surfaces/") || !file.ends_with(".off") || !line.contains("CLOSED 2-manifold") {
            continue;
        }
        let (xyz, tris) = read_off(&dir.join("..").join(file));
        if tris.len() / 3 > 20_000 {
            continue;
        }
        match tetrahedralize_surface(&xyz, &tris, &SurfaceOptions::default()) {
            Ok(mesh) => {
                let steiner = check(&xyz, &tris, &mesh);
                eprintln!("{file}: {} triangles, {} tetrahedra, {steiner} Steiner", tris.len() / 3, mesh.tetrahedron_count());
            }
            Err(e) if e.kind == ErrorKind::InvalidInput => eprintln!("{file}: invalid: {}", e.message),
            Err(e) => {
                eprintln!("{file}: {e}");
                failures.push(file.to_string());
            }
        }
    }
    assert!(failures.is_empty(), "failed: {failures:?}");
}
