//! The triangles of the convex hull of the input vertices, for `keep_convex_hull` (TetGen's
//! `-c`): recovered like input triangles, they bound the tetrahedra between the surface and
//! the hull, which then form regions of their own.
//!
//! The hull is read off the Delaunay triangulation of the vertices: the finite facet of every
//! infinite tetrahedron. A planar face of the hull made of several facets is triangulated
//! again, by 2D edge flips, until every input edge between two of its vertices is an edge of
//! its triangulation; the input triangles lying in that face are then triangles of it (no
//! vertex lies inside an input triangle), and are not repeated.
//!
//! Invariants: the triangles cover the hull's boundary once, meet only along shared edges and
//! vertices, and conform to the input edges; decisions are exact (`orient3d`, and `orient2d`
//! in a projection of each planar face that keeps its triangles proper).

use rustc_hash::FxHashSet as HashSet;

use super::tetmesh::{key, Key};
use super::validate::Projection;
use crate::error::{Error, Result};
use crate::predicates::{orient3d, Point, Sign};
use crate::triangulation::tets::{FACE, INFINITE};
use crate::triangulation::Triangulation;
use crate::union_find::UnionFind;

/// The hull triangles of the `vertices` of `points` that are not input `triangles` (as
/// vertex sets), conforming to the input edges.
pub fn triangles(
    points: &[Point],
    triangles: &[[u32; 3]],
    vertices: &[u32],
) -> Result<Vec<[u32; 3]>> {
    let faces = planar_faces(points, vertices)?;
    let edges: HashSet<[u32; 2]> = triangles
        .iter()
        .flat_map(|t| [0, 1, 2].map(|k| sorted_pair(t[k], t[(k + 1) % 3])))
        .collect();
    let input: HashSet<Key> = triangles.iter().map(|&t| key(t)).collect();
    let mut out = Vec::new();
    for face in faces {
        let face = conform(points, face, &edges)?;
        out.extend(face.into_iter().filter(|&t| !input.contains(&key(t))));
    }
    Ok(out)
}

fn sorted_pair(a: u32, b: u32) -> [u32; 2] {
    [a.min(b), a.max(b)]
}

/// The hull facets of the Delaunay triangulation of `vertices`, grouped into the planar faces
/// of the hull (facets joined across an edge when coplanar), in a deterministic order.
fn planar_faces(points: &[Point], vertices: &[u32]) -> Result<Vec<Vec<[u32; 3]>>> {
    let xyz: Vec<f64> = vertices.iter().flat_map(|&v| points[v as usize]).collect();
    let mut triangulation = Triangulation::new(&xyz, None)?;
    triangulation.insert_all()?;
    let tets = triangulation.into_input_numbered();
    let hull: Vec<u32> = tets
        .live()
        .filter(|&t| tets.vertices(t).contains(&INFINITE))
        .collect();
    let facet = |t: u32| {
        let v = tets.vertices(t);
        let i = v.iter().position(|&x| x == INFINITE).unwrap_or(0);
        FACE[i].map(|k| vertices[v[k] as usize])
    };
    let index: rustc_hash::FxHashMap<u32, u32> = hull
        .iter()
        .enumerate()
        .map(|(k, &t)| (t, k as u32))
        .collect();
    let mut sets = UnionFind::new(hull.len());
    for (k, &t) in hull.iter().enumerate() {
        let f = facet(t);
        let [a, b, c] = f.map(|v| &points[v as usize]);
        let inf = tets.vertices(t).iter().position(|&x| x == INFINITE);
        for i in (0..4).filter(|&i| Some(i) != inf) {
            let n = tets.neighbor(t, i);
            let Some(&m) = index.get(&n) else {
                return Err(Error::internal("a hull facet next to a finite tetrahedron"));
            };
            if (m as usize) <= k {
                continue;
            }
            let g = facet(n);
            let apex = g.into_iter().find(|x| !f.contains(x));
            if apex.is_some_and(|x| orient3d(a, b, c, &points[x as usize]) == Sign::Zero) {
                sets.union(k as u32, m);
            }
        }
    }
    let mut faces: Vec<Vec<[u32; 3]>> = Vec::new();
    let mut slot = vec![usize::MAX; hull.len()];
    for k in 0..hull.len() as u32 {
        let root = sets.find(k) as usize;
        if slot[root] == usize::MAX {
            slot[root] = faces.len();
            faces.push(Vec::new());
        }
        faces[slot[root]].push(facet(hull[k as usize]));
    }
    Ok(faces)
}

/// The planar face `face` triangulated again by 2D flips until every input edge between two
/// of its vertices is one of its edges.
fn conform(
    points: &[Point],
    mut face: Vec<[u32; 3]>,
    edges: &HashSet<[u32; 2]>,
) -> Result<Vec<[u32; 3]>> {
    if face.len() < 2 {
        return Ok(face);
    }
    let p = |v: u32| &points[v as usize];
    let plane = {
        let [a, b, c] = face[0].map(p);
        Projection::of(&[a, b, c])
    };
    for t in &mut face {
        if plane.orient(p(t[0]), p(t[1]), p(t[2])) == Sign::Negative {
            t.swap(1, 2);
        }
    }
    let mut vertices: Vec<u32> = face.iter().flatten().copied().collect();
    vertices.sort_unstable();
    vertices.dedup();
    let mut wanted: Vec<[u32; 2]> = edges
        .iter()
        .copied()
        .filter(|e| vertices.binary_search(&e[0]).is_ok() && vertices.binary_search(&e[1]).is_ok())
        .collect();
    wanted.sort_unstable();
    for [a, b] in wanted {
        // A guard: flips of convex quadrilaterals crossed by the segment end (Sloan 1993).
        let mut flips = 0;
        while let Some(crossing) = crossing_edges(points, &plane, &face, [a, b])
            .into_iter()
            .find_map(|(t, k)| flippable(points, &plane, &face, t, k))
        {
            flip(&mut face, crossing);
            flips += 1;
            if flips > face.len() * face.len() + 16 {
                return Err(Error::internal(format!(
                    "input edge ({a}, {b}) on a face of the convex hull: no flip recovers it"
                )));
            }
        }
        if !crossing_edges(points, &plane, &face, [a, b]).is_empty() {
            return Err(Error::internal(format!(
                "input edge ({a}, {b}) on a face of the convex hull: no convex quadrilateral to flip"
            )));
        }
    }
    Ok(face)
}

/// The edges `(triangle, k)` (the edge from corner `k` to corner `k + 1`) that cross the
/// segment `[a b]` in their relative interiors.
fn crossing_edges(
    points: &[Point],
    plane: &Projection,
    face: &[[u32; 3]],
    [a, b]: [u32; 2],
) -> Vec<(usize, usize)> {
    let p = |v: u32| &points[v as usize];
    let mut out = Vec::new();
    for (t, tri) in face.iter().enumerate() {
        for k in 0..3 {
            let (u, v) = (tri[k], tri[(k + 1) % 3]);
            if [u, v].iter().any(|x| *x == a || *x == b) || u > v {
                continue;
            }
            let opposite = |s: Sign, r: Sign| s != Sign::Zero && s == r.negate();
            if opposite(
                plane.orient(p(a), p(b), p(u)),
                plane.orient(p(a), p(b), p(v)),
            ) && opposite(
                plane.orient(p(u), p(v), p(a)),
                plane.orient(p(u), p(v), p(b)),
            ) {
                out.push((t, k));
            }
        }
    }
    out
}

/// The two triangles on edge `k` of triangle `t` and the corners to flip them, when the
/// quadrilateral they form is strictly convex.
fn flippable(
    points: &[Point],
    plane: &Projection,
    face: &[[u32; 3]],
    t: usize,
    k: usize,
) -> Option<(usize, usize, usize, usize)> {
    let (u, v) = (face[t][k], face[t][(k + 1) % 3]);
    let (s, j) = face.iter().enumerate().find_map(|(s, tri)| {
        (0..3)
            .find(|&j| tri[j] == v && tri[(j + 1) % 3] == u)
            .map(|j| (s, j))
    })?;
    let (w, x) = (face[t][(k + 2) % 3], face[s][(j + 2) % 3]);
    let p = |v: u32| &points[v as usize];
    let convex = plane.orient(p(w), p(u), p(x)) == Sign::Positive
        && plane.orient(p(x), p(v), p(w)) == Sign::Positive;
    convex.then_some((t, k, s, j))
}

/// Replaces triangles `(u, v, w)` and `(v, u, x)` (edge `k` of `t`, edge `j` of `s`) by
/// `(w, u, x)` and `(x, v, w)`.
fn flip(face: &mut [[u32; 3]], (t, k, s, j): (usize, usize, usize, usize)) {
    let (u, v, w) = (face[t][k], face[t][(k + 1) % 3], face[t][(k + 2) % 3]);
    let x = face[s][(j + 2) % 3];
    face[t] = [w, u, x];
    face[s] = [x, v, w];
}
