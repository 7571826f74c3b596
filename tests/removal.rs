//! Vertex removal and re-weighting on a growing triangulation (src/triangulation/remove.rs,
//! incremental.rs): after removing vertices (and raising weights), the triangulation is the
//! one the remaining points have from scratch, tetrahedron for tetrahedron, and `validate`
//! holds.

use delmesh::triangulation::{delaunay_tetrahedralize, regular_tetrahedralize, Triangulation};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

type P = [f64; 3];

/// The finite tetrahedra of `t` as sorted quadruples of coordinates' bits.
fn by_coordinates(t: &Triangulation, quads: impl Iterator<Item = [P; 4]>) -> Vec<[[u64; 3]; 4]> {
    let _ = t;
    let mut out: Vec<[[u64; 3]; 4]> = quads
        .map(|q| {
            let mut k = q.map(|p| p.map(f64::to_bits));
            k.sort_unstable();
            k
        })
        .collect();
    out.sort_unstable();
    out
}

fn live_finite(t: &Triangulation) -> Vec<[P; 4]> {
    let tets = t.tets();
    tets.live()
        .map(|s| tets.vertices(s))
        .filter(|v| !v.contains(&u32::MAX))
        .map(|v| v.map(|x| *t.vertex(x)))
        .collect()
}

fn mesh_quads(m: &delmesh::Mesh) -> Vec<[P; 4]> {
    m.tetrahedra
        .chunks_exact(4)
        .map(|q| [0, 1, 2, 3].map(|k| m.vertex(q[k])))
        .collect()
}

/// A live tetrahedron holding vertex `v`.
fn tet_of(t: &Triangulation, v: u32) -> u32 {
    t.tets()
        .live()
        .find(|&s| t.tets().vertices(s).contains(&v))
        .unwrap()
}

fn random_points(n: usize, seed: u64) -> Vec<P> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n).map(|_| [rng.gen(), rng.gen(), rng.gen()]).collect()
}

#[test]
fn removing_vertices_gives_the_delaunay_triangulation_of_the_rest() {
    let points = random_points(1500, 7);
    let mut t = Triangulation::growable(points, &[0.0; 3], &[1.0; 3]).unwrap();
    let mut rng = StdRng::seed_from_u64(11);
    let mut removed = 0;
    while removed < 300 {
        let v = rng.gen_range(0..t.vertex_count() as u32);
        if t.tets().live().all(|s| !t.tets().vertices(s).contains(&v)) {
            continue; // already removed
        }
        if t.remove(v, tet_of(&t, v)).unwrap() {
            removed += 1;
        }
    }
    t.validate().unwrap();
    let rest: Vec<f64> = (0..t.vertex_count() as u32)
        .filter(|&v| t.tets().live().any(|s| t.tets().vertices(s).contains(&v)))
        .flat_map(|v| *t.vertex(v))
        .collect();
    let fresh = delaunay_tetrahedralize(&rest).unwrap();
    assert_eq!(
        by_coordinates(&t, live_finite(&t).into_iter()),
        by_coordinates(&t, mesh_quads(&fresh).into_iter())
    );
}

#[test]
fn removing_weighted_vertices_gives_the_regular_triangulation_of_the_rest() {
    let points = random_points(1200, 3);
    let mut t = Triangulation::growable(points, &[0.0; 3], &[1.0; 3]).unwrap();
    t.make_regular();
    let mut rng = StdRng::seed_from_u64(5);
    // Raise some weights (a small fraction of the squared spacing), then remove others.
    for _ in 0..200 {
        let v = rng.gen_range(0..t.vertex_count() as u32);
        let Some(s) = t.tets().live().find(|&s| t.tets().vertices(s).contains(&v)) else {
            continue;
        };
        let w = t.weight(v) + rng.gen_range(0.0..2e-4);
        if w > t.weight(v) {
            t.find_reweight_conflicts(v, s, w).unwrap();
            t.commit_reweight(v).unwrap();
        }
    }
    let mut removed = 0;
    while removed < 200 {
        let v = rng.gen_range(0..t.vertex_count() as u32);
        let Some(s) = t.tets().live().find(|&s| t.tets().vertices(s).contains(&v)) else {
            continue;
        };
        if t.remove(v, s).unwrap() {
            removed += 1;
        }
    }
    t.validate().unwrap();
    let alive: Vec<u32> = (0..t.vertex_count() as u32)
        .filter(|&v| t.tets().live().any(|s| t.tets().vertices(s).contains(&v)))
        .collect();
    let xyz: Vec<f64> = alive.iter().flat_map(|&v| *t.vertex(v)).collect();
    let w: Vec<f64> = alive.iter().map(|&v| t.weight(v)).collect();
    let fresh = regular_tetrahedralize(&xyz, &w).unwrap();
    assert_eq!(
        by_coordinates(&t, live_finite(&t).into_iter()),
        by_coordinates(&t, mesh_quads(&fresh).into_iter())
    );
}
