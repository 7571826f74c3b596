//! Feeds closed triangulated surfaces to `tetrahedralize_surface` and checks every result.
//!
//! The bytes build a star-shaped surface: the boundary of the cube [-k, k]^3 cut into unit
//! squares, each split along a diagonal the bytes choose, every vertex pushed along its ray
//! from the centre by a small integer factor. Planar patches of many triangles, spikes, dents,
//! coplanar and cospherical vertices are frequent, and the surface never intersects itself
//! (each triangle projects from the centre onto its square's projection). The first byte
//! picks the ratio bound, whether the convex hull is kept, whether triangles are turned
//! inward, and whether one triangle is left out (an open surface). Every valid surface must
//! mesh, with its triangles as the facets, the input vertices unchanged and the enclosed
//! volume; the open one must be refused as invalid input.

#![no_main]

use std::collections::HashMap;

use delmesh::geometry::tet_volume;
use delmesh::recovery::{tetrahedralize_surface, SurfaceOptions};
use delmesh::triangulation::tets::FACE;
use delmesh::ErrorKind;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&head, body)) = data.split_first() else {
        return;
    };
    let k = i32::from(head & 3) + 1;
    let (xyz, mut triangles) = star_surface(k, body);
    let inward = |f: usize| head & 4 != 0 && f % 3 == 0;
    for (f, t) in triangles.chunks_exact_mut(3).enumerate() {
        if inward(f) {
            t.swap(1, 2);
        }
    }
    let options = SurfaceOptions {
        max_radius_edge_ratio: if head & 8 != 0 { 1.414 } else { 0.0 },
        keep_convex_hull: head & 16 != 0,
        ..Default::default()
    };
    if head & 32 != 0 {
        let open = &triangles[..triangles.len() - 3];
        let e = tetrahedralize_surface(&xyz, open, &options).unwrap_err();
        assert_eq!(e.kind, ErrorKind::InvalidInput, "{e}");
        return;
    }
    let mesh = tetrahedralize_surface(&xyz, &triangles, &options)
        .unwrap_or_else(|e| panic!("k {k}, options {options:?}: {e}"));
    mesh.validate().unwrap();
    let n = xyz.len() / 3;
    assert_eq!(&mesh.vertices[..3 * n], &xyz[..], "input vertices changed");
    assert_eq!(
        mesh.facets, triangles,
        "the facets are not the input triangles"
    );
    check_facets(&triangles, &mesh, &inward);
    check_volume(&xyz, &triangles, &mesh, options.keep_convex_hull);
});

/// The star-shaped surface of half-size `k`: vertex factors and diagonals from `bytes`
/// (cycled; all factors 1 when empty).
fn star_surface(k: i32, bytes: &[u8]) -> (Vec<f64>, Vec<u32>) {
    let mut byte = bytes.iter().copied().cycle();
    let mut next = || byte.next().unwrap_or(0);
    let mut index: HashMap<[i32; 3], u32> = HashMap::new();
    let mut xyz = Vec::new();
    let mut triangles = Vec::new();
    for axis in 0..3 {
        for side in [-k, k] {
            let (u, w) = ((axis + 1) % 3, (axis + 2) % 3);
            let corner = |i: i32, j: i32| {
                let mut d = [0; 3];
                d[axis] = side;
                d[u] = i;
                d[w] = j;
                d
            };
            for i in -k..k {
                for j in -k..k {
                    let q = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)].map(|(a, b)| {
                        let d = corner(a, b);
                        *index.entry(d).or_insert_with(|| {
                            let r = i32::from(next() % 6) + 1;
                            xyz.extend(d.map(|x| f64::from(x * r)));
                            (xyz.len() / 3 - 1) as u32
                        })
                    });
                    let split = if next() & 1 == 0 {
                        [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
                    } else {
                        [[q[0], q[1], q[3]], [q[1], q[2], q[3]]]
                    };
                    for mut t in split {
                        if side < 0 {
                            t.swap(1, 2);
                        }
                        triangles.extend(t);
                    }
                }
            }
        }
    }
    (xyz, triangles)
}

/// Every input triangle is a facet of the tetrahedra, with the region on its inner side
/// (`inward(f)`: triangle `f` is turned inward) and nothing, or the hull's region, outside.
fn check_facets(triangles: &[u32], mesh: &delmesh::Mesh, inward: &dyn Fn(usize) -> bool) {
    let sorted = |mut f: [u32; 3]| {
        f.sort_unstable();
        f
    };
    let facets: std::collections::HashSet<[u32; 3]> = (mesh.tetrahedra.chunks_exact(4))
        .flat_map(|t| FACE.map(|f| sorted(f.map(|i| t[i]))))
        .collect();
    let labels: std::collections::HashSet<i32> = mesh.tetrahedron_labels.iter().copied().collect();
    for (f, (t, l)) in triangles
        .chunks_exact(3)
        .zip(mesh.facet_labels.chunks_exact(2))
        .enumerate()
    {
        assert!(
            facets.contains(&sorted([t[0], t[1], t[2]])),
            "triangle {f} is no facet"
        );
        let (inner, outer) = if inward(f) {
            (l[1], l[0])
        } else {
            (l[0], l[1])
        };
        assert!(inner > 0 && inner != outer, "triangle {f}: labels {l:?}");
        assert!(
            labels.contains(&inner),
            "triangle {f}: label {inner} has no tetrahedron"
        );
    }
}

/// The tetrahedra's volume equals the surface's (the hull's, when it is kept), to 1e-12.
fn check_volume(xyz: &[f64], triangles: &[u32], mesh: &delmesh::Mesh, hull: bool) {
    let total: f64 = (mesh.tetrahedra.chunks_exact(4))
        .map(|t| {
            let p = [0, 1, 2, 3].map(|k| mesh.vertex(t[k]));
            tet_volume([&p[0], &p[1], &p[2], &p[3]])
        })
        .sum();
    assert!(total > 0.0, "no volume");
    if hull {
        return;
    }
    // The surface is star-shaped from the origin: its volume is the sum of the cones from
    // there over its triangles, whatever their orientation.
    let enclosed: f64 = (triangles.chunks_exact(3))
        .map(|f| {
            let p = |v: u32| [0, 1, 2].map(|k| xyz[3 * v as usize + k]);
            tet_volume([&[0.0; 3], &p(f[0]), &p(f[1]), &p(f[2])]).abs()
        })
        .sum();
    let rel = (total - enclosed).abs() / enclosed;
    assert!(rel < 1e-12, "volume {total} against {enclosed} ({rel:e})");
}
