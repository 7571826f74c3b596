//! Recovery of a missing sub-edge with one point inside the volume instead of points on the
//! surface (TetGen's `add_steinerpt_in_schoenhardtpoly`): where flips leave the segment
//! `se` crossing the shell of an edge `uv` from ring vertex `s` to ring vertex `e`, the
//! tetrahedra of the shell between them (a polyhedron that, like Schönhardt's prism, may
//! have no tetrahedralization containing `se` without an added point) are replaced by
//! - the tetrahedron `(s, e, u, v)`, which holds `se` (it is flat, and left out, when the
//!   segment meets `uv`: both sides of the shell are then replaced together);
//! - the cone from an apex over the rest of the polyhedron's boundary: its outer facets and
//!   the triangles `(s, e, u)`, `(s, e, v)`.
//!
//! The apex is a vertex of the ring between `s` and `e` when one sees all those facets, else
//! a new point, searched where its distance to the nearest facet plane is largest (a pattern
//! search from the segment; the region it must lie in is the intersection of half-spaces, so
//! the distance is concave). Every new tetrahedron is checked positive exactly and the
//! replacement conforms facet for facet: a point that is only close to right is refused.
//!
//! Such a point lies off the surface: its rounding cannot make two pieces of the surface
//! cross, as that of a point on a planar face can. [`super::tetrahedralize_surface`] uses it
//! in a second attempt, where points on the surface alone fail (the corpus's anchor).

use super::edges::{first_crossing, Crossing};
use super::flips::Protected;
use super::tetmesh::TetMesh;
use crate::error::Result;
use crate::geometry::{add, cross, dist, dot, norm, sub};
use crate::predicates::{Point, Sign};
use crate::triangulation::tets::INFINITE;

/// Longest shell looked at.
const SHELL: usize = 64;

/// Recovers sub-edge `(a, b)` by replacing the part of a crossed shell between its ends, as
/// the module documentation says; `Some(added)` when the edge is a mesh edge after it
/// (`added`: whether a new point was needed), `None` when no such replacement is valid or
/// `may_add` is false and a new point would be needed.
pub fn recover_edge(
    mesh: &mut TetMesh,
    protected: &Protected,
    [a, b]: [u32; 2],
    may_add: bool,
) -> Result<Option<bool>> {
    for [s, e] in [[a, b], [b, a]] {
        let (t, edges) = match first_crossing(mesh, s, e)? {
            None => return Ok(Some(false)),
            Some(Crossing::Facet(t, i)) => {
                let [x, y, z] = mesh.facet(t, i);
                (t, vec![[x, y], [y, z], [z, x]])
            }
            Some(Crossing::Edge(uv, t)) => (t, vec![uv]),
            Some(Crossing::Vertex(_)) => continue,
        };
        for uv in edges {
            if let Some(added) = replace_shell(mesh, protected, t, uv, [s, e], may_add)? {
                return Ok(Some(added));
            }
        }
    }
    Ok(None)
}

/// The replacement of the shell of `uv` (an edge of `t`) between `s` and `e`.
fn replace_shell(
    mesh: &mut TetMesh,
    protected: &Protected,
    t: u32,
    [u, v]: [u32; 2],
    [s, e]: [u32; 2],
    may_add: bool,
) -> Result<Option<bool>> {
    let Some((tets, ring)) = mesh.shell(t, u, v, SHELL) else {
        return Ok(None);
    };
    let (Some(i), Some(j)) = (
        ring.iter().position(|&w| w == s),
        ring.iter().position(|&w| w == e),
    ) else {
        return Ok(None);
    };
    if ring.contains(&INFINITE) {
        return Ok(None);
    }
    let parts = [
        Part::new(&ring, &tets, i, j, [s, e]),
        Part::new(&ring, &tets, j, i, [e, s]),
    ];
    // The facets inside a part vanish: none may be protected.
    let usable =
        |p: &Part| !p.middle.is_empty() && !p.middle.iter().any(|&w| protected.facet([u, v, w]));
    let side = mesh.orient([s, e, u, v]);
    if side == Sign::Zero {
        // Both sides go together, and the edge uv with them.
        if protected.edge(u, v) || !parts.iter().all(usable) {
            return Ok(None);
        }
        return fill(
            mesh,
            &parts.iter().collect::<Vec<_>>(),
            [u, v],
            None,
            may_add,
        );
    }
    let lens = if side == Sign::Positive {
        [s, e, u, v]
    } else {
        [e, s, u, v]
    };
    for part in parts.iter().filter(|p| usable(p)) {
        if let Some(added) = fill(mesh, &[part], [u, v], Some(lens), may_add)? {
            return Ok(Some(added));
        }
    }
    Ok(None)
}

/// Replaces the tetrahedra of `parts` by `lens` and, in each part, the cone from an apex
/// over the facets it must see ([`Part::facets`]); `Some(added)` when done.
fn fill(
    mesh: &mut TetMesh,
    parts: &[&Part],
    uv: [u32; 2],
    lens: Option<[u32; 4]>,
    may_add: bool,
) -> Result<Option<bool>> {
    let first_new = mesh.points.len() as u32;
    let mut old = Vec::new();
    let mut new: Vec<[u32; 4]> = lens.into_iter().collect();
    for part in parts {
        old.extend(&part.tets);
        let facets = part.facets(mesh, uv, lens.is_none());
        let apex = match part.middle.iter().find(|&&w| sees(mesh, &facets, w)) {
            Some(&w) => Some(w),
            None if may_add => best_point(mesh, &facets, part.ends).map(|p| mesh.add_point(p)),
            None => None,
        };
        let Some(apex) = apex else {
            break;
        };
        new.extend(
            facets
                .iter()
                .filter(|f| !f.contains(&apex))
                .map(|&[x, y, z]| [x, y, z, apex]),
        );
    }
    let done = new.iter().all(|&q| mesh.positive(q)) && mesh.try_replace(&old, &new)?.is_some();
    let added = mesh.points.len() as u32 > first_new;
    if !done {
        while mesh.points.len() as u32 > first_new {
            mesh.pop_point();
        }
        return Ok(None);
    }
    Ok(Some(added))
}

/// The tetrahedra of a shell from ring vertex `from` to `to`.
struct Part {
    /// The tetrahedra `(u, v, w[k], w[k+1])`, turning the ring's way.
    tets: Vec<u32>,
    /// Their pairs `(w[k], w[k+1])`.
    pairs: Vec<[u32; 2]>,
    /// The ring's vertices strictly between the ends.
    middle: Vec<u32>,
    ends: [u32; 2],
}

impl Part {
    fn new(ring: &[u32], tets: &[u32], from: usize, to: usize, ends: [u32; 2]) -> Part {
        let n = ring.len();
        let steps = (from..from + (to + n - from) % n).map(|k| k % n);
        Part {
            tets: steps.clone().map(|k| tets[k]).collect(),
            pairs: steps
                .clone()
                .map(|k| [ring[k], ring[(k + 1) % n]])
                .collect(),
            middle: steps.skip(1).map(|k| ring[k]).collect(),
            ends,
        }
    }

    /// The facets the apex must see, each `[x, y, z]` with `[x, y, z, apex]` positive for an
    /// apex inside: the outer facets and the two triangles through the segment, turned away
    /// from the tetrahedron `(s, e, u, v)`, or, when it is `flat`, toward this part.
    fn facets(&self, mesh: &TetMesh, [u, v]: [u32; 2], flat: bool) -> Vec<[u32; 3]> {
        let [s, e] = self.ends;
        let mut out = Vec::with_capacity(2 * self.pairs.len() + 2);
        for &[x, y] in &self.pairs {
            // (u, v, x, y) is positive, so are (v, y, x, u) and (u, x, y, v).
            out.push([v, y, x]);
            out.push([u, x, y]);
        }
        for (w, other) in [(u, v), (v, u)] {
            let toward_positive = if flat {
                mesh.orient([s, e, w, self.middle[0]]) == Sign::Positive
            } else {
                mesh.orient([s, e, w, other]) != Sign::Positive
            };
            out.push(if toward_positive {
                [s, e, w]
            } else {
                [e, s, w]
            });
        }
        out
    }
}

/// Whether `w` sees every facet not through it from inside.
fn sees(mesh: &TetMesh, facets: &[[u32; 3]], w: u32) -> bool {
    facets
        .iter()
        .filter(|f| !f.contains(&w))
        .all(|&[x, y, z]| mesh.positive([x, y, z, w]))
}

/// Pattern search steps before giving up.
const SEARCH: usize = 400;

/// The point inside every facet's half-space (`[x, y, z, point]` positive for each facet
/// `[x, y, z]` of `facets`) farthest from the nearest facet plane that a pattern search
/// finds, starting at the best of the segment's points at every hundredth of it with steps
/// of a twentieth of its length; `None` when it finds none inside (in floating point: the
/// caller checks orientations exactly). The distance is the minimum of affine functions, a
/// concave function, which the search climbs.
fn best_point(mesh: &TetMesh, facets: &[[u32; 3]], [s, e]: [u32; 2]) -> Option<Point> {
    let planes: Vec<(Point, Point)> = facets
        .iter()
        .filter_map(|&[x, y, z]| {
            let (a, b, c) = (mesh.point(x), mesh.point(y), mesh.point(z));
            let n = cross(&sub(b, a), &sub(c, a));
            let l = norm(&n);
            (l > 0.0).then(|| (*a, scale(&n, 1.0 / l)))
        })
        .collect();
    let depth = |p: &Point| {
        planes
            .iter()
            .map(|(a, n)| dot(n, &sub(p, a)))
            .fold(f64::INFINITY, f64::min)
    };
    let better = |b: (f64, Point), c: (f64, Point)| if c.0 > b.0 { c } else { b };
    let (ps, pe) = (*mesh.point(s), *mesh.point(e));
    let (along, length) = (sub(&pe, &ps), dist(&ps, &pe));
    let mut best = (1..100)
        .map(|k| add(&ps, &scale(&along, k as f64 / 100.0)))
        .map(|p| (depth(&p), p))
        .fold((f64::NEG_INFINITY, ps), better);
    let directions = directions();
    let mut step = 0.05 * length;
    for _ in 0..SEARCH {
        let next = directions
            .iter()
            .map(|d| add(&best.1, &scale(d, step)))
            .map(|p| (depth(&p), p))
            .fold(best, better);
        if next.0 > best.0 {
            best = next;
        } else {
            step *= 0.5;
            if step < 1e-9 * length {
                break;
            }
        }
    }
    (best.0 > 0.0).then_some(best.1)
}

fn scale(u: &Point, s: f64) -> Point {
    [u[0] * s, u[1] * s, u[2] * s]
}

/// The 26 unit directions toward the neighbours of a cell in a cubic grid.
fn directions() -> Vec<Point> {
    let mut out = Vec::with_capacity(26);
    for i in -1i32..=1 {
        for j in -1i32..=1 {
            for k in -1i32..=1 {
                if (i, j, k) != (0, 0, 0) {
                    let d = [i as f64, j as f64, k as f64];
                    out.push(scale(&d, 1.0 / norm(&d)));
                }
            }
        }
    }
    out
}
