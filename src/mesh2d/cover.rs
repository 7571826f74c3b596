//! The Delaunay *cover* of a planar triangulation (Pébay §2, Definition 2.3): the edges that
//! every Delaunay triangulation of the points contains. They cut the plane into cells, each a
//! triangle or a convex polygon of four or more cocircular points, which any Delaunay
//! triangulation splits into triangles in its own way; Theorem 2.1's strongly admissible
//! edges are cover edges.
//!
//! Here the cells are those of a result's triangles: two triangles sharing an edge are in one
//! cell when their four vertices are cocircular (exact `incircle`); an edge with one triangle
//! separates cells. Invariant: every cell's triangles are connected across cocircular edges,
//! and cells are numbered in the order of their first triangle, so the numbering is a function
//! of the triangles alone.

use rustc_hash::FxHashMap as HashMap;

use crate::mesh::Mesh;
use crate::predicates::{incircle, Sign};
use crate::union_find::UnionFind;

/// The cells of the Delaunay cover of `mesh`'s 2D triangles: for each triangle, the index of
/// its cell (numbered from 0 by first triangle), and the number of cells.
pub fn cells(mesh: &Mesh) -> (Vec<u32>, usize) {
    let tris: Vec<[u32; 3]> = mesh
        .triangles
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    let point = |v: u32| {
        let p = mesh.vertex(v);
        [p[0], p[1]]
    };
    let mut opposite: HashMap<(u32, u32), u32> = HashMap::default();
    for (t, v) in tris.iter().enumerate() {
        for k in 0..3 {
            opposite.insert((v[k], v[(k + 1) % 3]), t as u32);
        }
    }
    let mut sets = UnionFind::new(tris.len());
    for (t, v) in tris.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            let Some(&u) = opposite.get(&(b, a)) else {
                continue;
            };
            if (u as usize) < t {
                continue;
            }
            let apex = tris[u as usize]
                .into_iter()
                .find(|&x| x != a && x != b)
                .expect("a triangle has a vertex off its edge");
            let c = v[(k + 2) % 3];
            if incircle(&point(a), &point(b), &point(c), &point(apex)) == Sign::Zero {
                sets.union(t as u32, u);
            }
        }
    }
    let mut number = vec![u32::MAX; tris.len()];
    let mut cell = Vec::with_capacity(tris.len());
    let mut count = 0usize;
    for t in 0..tris.len() as u32 {
        let r = sets.find(t) as usize;
        if number[r] == u32::MAX {
            number[r] = count as u32;
            count += 1;
        }
        cell.push(number[r]);
    }
    (cell, count)
}
