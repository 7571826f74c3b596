//! Recovery of a missing input triangle whose three edges exist (George and Borouchaki §5.2,
//! second part).
//!
//! With its edges in the mesh and no other vertex on it (the input is free of
//! self-intersections), a triangle is a facet of the mesh exactly when no edge crosses its
//! interior ([`crossing_edges`] finds them all by a search from the stars of its corners).
//! Each crossing edge is removed when a ring triangulation exists whose diagonals do not cross
//! the triangle: the number of crossing edges then drops by one.

use super::flips::{remove_edge_deep, Protected};
use super::tetmesh::TetMesh;
use crate::error::Result;
use crate::predicates::Sign;
use crate::triangulation::tets::INFINITE;

/// Whether the segment `(u, v)` crosses the interior of triangle `f` (exact; a segment with
/// an end at a corner of `f` does not).
pub fn crosses(mesh: &TetMesh, f: [u32; 3], u: u32, v: u32) -> bool {
    if f.contains(&u) || f.contains(&v) || u == INFINITE || v == INFINITE {
        return false;
    }
    let [a, b, c] = f;
    let su = mesh.orient([a, b, c, u]);
    let sv = mesh.orient([a, b, c, v]);
    if su == Sign::Zero || su != sv.negate() {
        return false;
    }
    let s = [
        mesh.orient([u, v, a, b]),
        mesh.orient([u, v, b, c]),
        mesh.orient([u, v, c, a]),
    ];
    s[0] != Sign::Zero && s[0] == s[1] && s[1] == s[2]
}

/// The edges crossing the interior of triangle `f`, each with a tetrahedron holding it,
/// sorted by their vertices.
pub fn crossing_edges(mesh: &mut TetMesh, f: [u32; 3]) -> Vec<([u32; 2], u32)> {
    let mut seen = Vec::new();
    let mut stack = Vec::new();
    for corner in f {
        for t in mesh.ball(corner) {
            if mesh.tets.mark[t as usize] == 0 {
                mesh.tets.mark[t as usize] = 1;
                seen.push(t);
                stack.push(t);
            }
        }
    }
    let mut edges = Vec::new();
    while let Some(t) = stack.pop() {
        let v = mesh.tets.vertices(t);
        let mut hit = false;
        for i in 0..4 {
            for j in i + 1..4 {
                if crosses(mesh, f, v[i], v[j]) {
                    hit = true;
                    edges.push(([v[i].min(v[j]), v[i].max(v[j])], t));
                }
            }
        }
        if !hit {
            continue;
        }
        for i in 0..4 {
            let n = mesh.tets.neighbor(t, i);
            if mesh.tets.mark[n as usize] == 0 {
                mesh.tets.mark[n as usize] = 1;
                seen.push(n);
                stack.push(n);
            }
        }
    }
    for t in seen {
        mesh.tets.mark[t as usize] = 0;
    }
    edges.sort_unstable_by_key(|&(e, _)| e);
    edges.dedup_by_key(|&mut (e, _)| e);
    edges
}

/// Recovers triangle `f` (its edges in the mesh) by edge removals; `false` if it is still
/// missing when no crossing edge can be removed.
pub fn recover_face(mesh: &mut TetMesh, protected: &Protected, f: [u32; 3]) -> Result<bool> {
    if mesh.find_face(f).is_some() {
        return Ok(true);
    }
    let clear = |m: &TetMesh, u: u32, w: u32| !crosses(m, f, u, w);
    loop {
        let edges = crossing_edges(mesh, f);
        if edges.is_empty() {
            return Ok(mesh.find_face(f).is_some());
        }
        let mut removed = false;
        for (e, _) in edges {
            if remove_edge_deep(mesh, protected, e, &clear, 2, &mut 64)? {
                removed = true;
                break;
            }
        }
        if !removed {
            return Ok(false);
        }
    }
}
