//! Points added on the input surface where flips cannot recover it (George and Borouchaki
//! §5.2): at the intersection of a missing sub-edge with the first facet or edge it crosses,
//! or of a mesh edge with a missing subface. The tetrahedra around the crossed facet (two)
//! or edge (its shell) are replaced by the cone from the new point over their boundary.
//!
//! The crossing is computed in floating point; the point added is the combination of the
//! corners of the input edge or triangle it is in nearest to it
//! ([`crate::predicates::combination`]), exactly on the surface for the orientation tests
//! ([`TetMesh::add_point_on`]), while its coordinates are rounded. Which input edge or
//! triangle it belongs to is recorded combinatorially ([`super::partition`]). The cone is
//! accepted only if every new tetrahedron is positive: a tetrahedron with its four vertices on
//! one input triangle is not (it is flat, exactly), and the point could not have left the
//! surface through it later ([`super::suppress`] moves a point into each piece of its star).
//! Where no set around the crossing is star-shaped from the point, the tetrahedra whose
//! closure holds it are split instead ([`holding`]); where no point near the crossing goes
//! in, the sub-edge's midpoint is added. A crossing closer to an end of the sub-edge than
//! [`NEAR_COPY`] of its length stops the attempt, except where a crossed edge passes the
//! sub-edge's start within rounding (flips made it again past a point added on it): no point
//! is added, the edge's shell joins the start's star, coned again from the start
//! ([`absorb`]).
//!
//! Measured when the points became exact (rounded before, with flat tetrahedra refused by
//! their vertices' input triangles): every corpus output the same but anchor's (10 interior
//! points, and 24 instead of 25 with the bound 1.414); Chazelle's polyhedra with two to seven
//! notches a side 5, 11, 16, 21, 29, 34 interior points (5, 11, 15, 21, 32, 38 before), and
//! with the relocation of stuck points that came next ([`super::suppress`]) 5, 11, 17, 21, 27,
//! 31, and 46 with eight (the relocation alone: 5, 11, 15, 21, 30, 36, 51). The exact tests
//! cost time (one driver run each, with the relocation either way): anchor 2.0 -> 2.6 s,
//! Chazelle's polyhedron with four notches 4.8 -> 8.6 s, with eight 38 -> 69 s.

use super::edges::Crossing;
use super::partition::{Host, Partition};
use super::tetmesh::{key, TetMesh};
use crate::error::{Error, ErrorKind, Result};
use crate::geometry::{add, cross, dist, dot, midpoint, sub};
use crate::predicates::combination::Combination;
use crate::predicates::{Point, Sign};
use crate::triangulation::tets::INFINITE;

fn scale(u: &Point, s: f64) -> Point {
    [u[0] * s, u[1] * s, u[2] * s]
}

/// The point of segment `(u, v)` on the plane of `(a, b, c)`.
fn segment_plane(u: &Point, v: &Point, [a, b, c]: [&Point; 3]) -> Point {
    let n = cross(&sub(b, a), &sub(c, a));
    let (du, dv) = (dot(&n, &sub(u, a)), dot(&n, &sub(v, a)));
    let t = du / (du - dv);
    add(u, &scale(&sub(v, u), t))
}

/// The point of line `(p, q)` closest to line `(x, y)`.
fn line_line(p: &Point, q: &Point, x: &Point, y: &Point) -> Point {
    let (d1, d2) = (sub(q, p), sub(y, x));
    let n = cross(&d1, &d2);
    let s = dot(&cross(&sub(x, p), &d2), &n) / dot(&n, &n);
    add(p, &scale(&d1, s))
}

fn failure(what: String) -> Error {
    Error::new(ErrorKind::Limit, what)
}

/// Replaces the tetrahedra `set`, or failing that `set` grown by its neighbours across
/// unprotected facets (at most [`GROWTH`] times: the new point, on the surface but only
/// near the computed crossing, may fall just outside `set`), by the cone from the new point
/// `p` over their boundary. Last, the tetrahedra around the point itself ([`holding`]) are
/// split: the crossing can lie beyond a plane through the segment's start by less than its
/// rounding, and no set around the crossing is star-shaped from the point.
fn cone(mesh: &mut TetMesh, part: &Partition, set: &[u32], p: NewPoint) -> Result<Option<u32>> {
    let start = set[0];
    let mut set = set.to_vec();
    for _ in 0..=GROWTH {
        if let Some(s) = cone_over(mesh, part, &set, p)? {
            return Ok(Some(s));
        }
        set = grown(mesh, part, &set);
    }
    match holding(mesh, part, start, &p.at) {
        Some(set) => cone_over(mesh, part, &set, p),
        None => Ok(None),
    }
}

/// Longest walk [`holding`] takes (from the crossing to the sub-edge's midpoint, it can go
/// far).
const WALK: usize = 4096;

/// The tetrahedra whose closure holds `p`, found by a visibility walk from `t`: the one
/// holding it inside, or those around the facet or edge holding it. The walk may cross the
/// surface, which `p` is on only up to rounding. `None` when that facet or edge is
/// protected, `p` is at a vertex, or the walk stops.
fn holding(mesh: &TetMesh, part: &Partition, t: u32, p: &Point) -> Option<Vec<u32>> {
    let protected = |f: [u32; 3]| part.protected.facet(f);
    let at = mesh.walk(t, p, WALK, |m, _, _, n| {
        !m.tets.vertices(n).contains(&INFINITE)
    })?;
    let on: Vec<usize> = (0..4)
        .filter(|&i| mesh.orient_point(mesh.facet(at, i), p) == Sign::Zero)
        .collect();
    match on[..] {
        [] => Some(vec![at]),
        [i] if !protected(mesh.facet(at, i)) => Some(vec![at, mesh.tets.neighbor(at, i)]),
        [i, j] => {
            let [x, y] = mesh.others(at, mesh.tets.vertices(at)[i], mesh.tets.vertices(at)[j]);
            if part.protected.edge(x, y) {
                return None;
            }
            mesh.shell(at, x, y, usize::MAX)
                .map(|(shell, _)| shell.to_vec())
        }
        _ => None,
    }
}

/// How many times [`cone`] grows its set.
const GROWTH: usize = 2;

/// `set` and its neighbours across facets that are not protected.
fn grown(mesh: &mut TetMesh, part: &Partition, set: &[u32]) -> Vec<u32> {
    let mut out = set.to_vec();
    for &t in set {
        mesh.tets.mark[t as usize] = 3;
    }
    for &t in set {
        for k in 0..4 {
            let n = mesh.tets.neighbor(t, k);
            let f = mesh.facet(t, k);
            if mesh.tets.mark[n as usize] != 3 && !part.protected.facet(f) {
                mesh.tets.mark[n as usize] = 3;
                out.push(n);
            }
        }
    }
    for &t in &out {
        mesh.tets.mark[t as usize] = 0;
    }
    out
}

/// A point to add on the surface: near where, and the input edge or triangle it is in.
#[derive(Clone, Copy)]
struct NewPoint {
    at: Point,
    host: Host,
}

/// The cone from the new point `p` over the boundary of `set`, if every tetrahedron is
/// positive and every vertex of `set` stays. The point is the combination of its host's
/// corners nearest to `p.at` ([`Combination::nearest`]): exactly on the surface.
fn cone_over(
    mesh: &mut TetMesh,
    part: &Partition,
    set: &[u32],
    p: NewPoint,
) -> Result<Option<u32>> {
    let Some(new) = cone_boundary(mesh, set, mesh.points.len() as u32) else {
        // A vertex inside the set would vanish.
        return Ok(None);
    };
    let corners = part.corners(p.host);
    let s = match Combination::nearest(corners.map(|v| *mesh.point(v)), &p.at) {
        Some(exact) => mesh.add_point_on(exact, corners),
        None => mesh.add_point(p.at),
    };
    if !new.iter().all(|&q| mesh.positive(q)) || mesh.try_replace(set, &new)?.is_none() {
        mesh.pop_point();
        return Ok(None);
    }
    Ok(Some(s))
}

/// How close to an end of a sub-edge, relative to its length, a crossing stops the attempt
/// ([`split_subedge`]): a point there would be a near copy of the end, and the sub-edges around
/// such pairs cross one another a little later. Stopping at once left every output of the
/// C test as it was and made the failing attempts shorter: anchor 1.61 -> 1.01 s, Chazelle's
/// polyhedron with four notches a side 11.1 -> 7.7 s, and with five 17.3 -> 10.1 s to fail.
const NEAR_COPY: f64 = 1e-6;

/// Whether the crossing `point` of sub-edge `(p, q)` is so close to `p` (a billionth of the
/// sub-edge) that a point there would be a near copy of `p`: the crossed edge passes `p`
/// within rounding, and [`absorb`] is tried first. (Tried on crossed facets too, it cost
/// Chazelle's polyhedron with three notches a side a point more, 17 against 16.)
fn at_start(point: &Point, p: &Point, q: &Point) -> bool {
    dist(point, p) <= 1e-9 * dist(p, q)
}

/// Takes away the edge that a sub-edge from `p` crosses within rounding of `p` (its shell is
/// `crossed`): `p` was added where a sub-edge crossed that edge, rounded a little off its
/// line, and flips made the edge again past `p`. A point added at the crossing would be a
/// near copy of `p`. Instead the shell joins the star of `p`, and the union is replaced by
/// the cone from `p` over its boundary, which joins `p` to the edge's ends.
/// `false` (nothing changed) where a tetrahedron of the cone is not positive or a vertex
/// would vanish, or where a protected facet or edge of the union would: those not through
/// `p` must be on its boundary, and those through `p` must have their other vertices on it.
fn absorb(mesh: &mut TetMesh, part: &Partition, p: u32, crossed: &[u32]) -> Result<bool> {
    let mut region = mesh.ball(p);
    for &t in crossed {
        if !region.contains(&t) {
            region.push(t);
        }
    }
    if region
        .iter()
        .any(|&t| mesh.tets.vertices(t).contains(&INFINITE))
    {
        return Ok(false);
    }
    let Some(new) = cone_boundary(mesh, &region, p) else {
        return Ok(false);
    };
    let on_boundary_edge = |a: u32, b: u32| {
        new.iter()
            .any(|q| q[..3].contains(&a) && q[..3].contains(&b))
    };
    let on_boundary_facet = |f: [u32; 3]| {
        let k = key(f);
        new.iter().any(|q| key([q[0], q[1], q[2]]) == k)
    };
    for &t in &region {
        let v = mesh.tets.vertices(t);
        for i in 0..4 {
            let f = mesh.facet(t, i);
            if part.protected.facet(f) {
                let kept = match f.iter().position(|&w| w == p) {
                    Some(k) => on_boundary_edge(f[(k + 1) % 3], f[(k + 2) % 3]),
                    None => on_boundary_facet(f),
                };
                if !kept {
                    return Ok(false);
                }
            }
            for j in i + 1..4 {
                let (a, b) = (v[i], v[j]);
                if a != p && b != p && part.protected.edge(a, b) && !on_boundary_edge(a, b) {
                    return Ok(false);
                }
            }
        }
    }
    if !new.iter().all(|&q| mesh.positive(q)) {
        return Ok(false);
    }
    Ok(mesh.try_replace(&region, &new)?.is_some())
}

/// The tetrahedra joining `s` to the boundary facets of `set`, or `None` where a vertex of
/// `set` other than `s` is on no boundary facet (it would vanish). `s` is a new point, or a
/// vertex whose whole star is in `set` (so on no boundary facet).
fn cone_boundary(mesh: &mut TetMesh, set: &[u32], s: u32) -> Option<Vec<[u32; 4]>> {
    for &t in set {
        mesh.tets.mark[t as usize] = 3;
    }
    let mut new = Vec::new();
    for &t in set {
        for k in 0..4 {
            if mesh.tets.mark[mesh.tets.neighbor(t, k) as usize] != 3 {
                let [a, b, c] = mesh.facet(t, k);
                new.push([a, b, c, s]);
            }
        }
    }
    for &t in set {
        mesh.tets.mark[t as usize] = 0;
    }
    let kept = |v: &u32| *v == s || new.iter().any(|q| q[..3].contains(v));
    let whole = set.iter().all(|&t| mesh.tets.vertices(t).iter().all(kept));
    whole.then_some(new)
}

/// Adds a point on sub-edge `(p, q)` where it first crosses the mesh from `p`; returns it.
/// `None` when the crossing is an edge passing `p` within rounding, which [`absorb`] took
/// away without a point; a `Limit` error when the crossing is nearer an end than
/// [`NEAR_COPY`].
pub fn split_subedge(
    mesh: &mut TetMesh,
    part: &mut Partition,
    p: u32,
    q: u32,
    crossing: Crossing,
) -> Result<Option<u32>> {
    let (pp, pq) = (*mesh.point(p), *mesh.point(q));
    let (set, point) = match crossing {
        Crossing::Facet(t, i) => {
            let (_, f) = mesh.with_apex(t, i);
            if part.protected.facet(f) {
                return Err(failure(format!(
                    "sub-edge ({p}, {q}) crosses the surface piece {f:?}: rounding"
                )));
            }
            let n = mesh.tets.neighbor(t, i);
            let corners = f.map(|v| mesh.point(v));
            (vec![t, n], segment_plane(&pp, &pq, corners))
        }
        Crossing::Edge([x, y], t) => {
            if part.protected.edge(x, y) {
                return Err(failure(format!(
                    "sub-edge ({p}, {q}) crosses the surface edge ({x}, {y}): rounding"
                )));
            }
            let Some((shell, _)) = mesh.shell(t, x, y, usize::MAX) else {
                return Err(Error::internal("open shell"));
            };
            let point = line_line(&pp, &pq, mesh.point(x), mesh.point(y));
            if at_start(&point, &pp, &pq) && absorb(mesh, part, p, &shell)? {
                return Ok(None);
            }
            (shell.to_vec(), point)
        }
        Crossing::Vertex(v) => return Err(super::edges::vertex_on_edge(mesh, v, [p, q])),
    };
    if dist(&point, &pp).min(dist(&point, &pq)) <= NEAR_COPY * dist(&pp, &pq) {
        return Err(failure(format!(
            "sub-edge ({p}, {q}) is crossed too near an end, at {point:?}"
        )));
    }
    let host = part.host_of_subedge(p, q);
    let at = |at| NewPoint { at, host };
    let added = match cone(mesh, part, &set, at(point))? {
        Some(s) => Some(s),
        // No point near the crossing went in: the sub-edge's midpoint, wherever the
        // tetrahedra hold it.
        None => {
            let m = midpoint(&pp, &pq);
            match holding(mesh, part, set[0], &m) {
                Some(around) => cone_over(mesh, part, &around, at(m))?,
                None => None,
            }
        }
    };
    match added {
        Some(s) => {
            part.split_edge(p, q, s);
            Ok(Some(s))
        }
        None => Err(failure(format!(
            "no valid point found on the sub-edge ({p}, {q}) near {point:?}"
        ))),
    }
}

/// Adds a point where edge `(u, v)` crosses subface `t` of input triangle `f`; returns it.
pub fn split_subface(
    mesh: &mut TetMesh,
    part: &mut Partition,
    f: usize,
    t: [u32; 3],
    [u, v]: [u32; 2],
) -> Result<u32> {
    if part.protected.edge(u, v) {
        return Err(failure(format!(
            "the surface edge ({u}, {v}) crosses the surface piece {t:?}: rounding"
        )));
    }
    let Some(tet) = mesh.find_edge(u, v) else {
        return Err(Error::internal(format!("edge ({u}, {v}) vanished")));
    };
    let Some((shell, _)) = mesh.shell(tet, u, v, usize::MAX) else {
        return Err(Error::internal("open shell"));
    };
    let corners = t.map(|w| mesh.point(w));
    let point = segment_plane(mesh.point(u), mesh.point(v), corners);
    let new = NewPoint {
        at: point,
        host: Host::Face(f),
    };
    match cone(mesh, part, &shell, new)? {
        Some(s) => {
            part.split_face(f, t, s);
            Ok(s)
        }
        None => Err(failure(format!(
            "no valid point found on triangle {f} where edge ({u}, {v}) crosses it"
        ))),
    }
}
