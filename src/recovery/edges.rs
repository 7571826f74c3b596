//! Recovery of a missing input edge by flips (George and Borouchaki §5.2, first part).
//!
//! The segment `ab` is followed from `a`: its first crossing is a facet or an edge of the
//! star of `a` ([`first_crossing`]). A 2-3 flip of that facet, or the removal of that edge
//! with the ring fanned from `a`, takes the crossing away: the segment then leaves the star
//! of `a` one tetrahedron further. The same is tried from `b`. When neither end can advance,
//! the edges of the first crossed facets are removed (any valid ring triangulation), which
//! changes the stars without advancing, a bounded number of times.

use super::flips::{flip23, remove_edge, remove_edge_deep, Protected};
use super::tetmesh::TetMesh;
use crate::error::{Error, ErrorKind, Result};
use crate::predicates::Sign;

/// Most flips tried on one edge before it is declared stuck.
const MAX_FLIPS: usize = 256;

/// How deep [`remove_edge_deep`] goes to unblock a star, and how many edge removals each
/// unblocking tries.
const DEPTH: u32 = 3;
const BUDGET: usize = 256;

/// What the segment from a vertex meets first, leaving that vertex's star.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Crossing {
    /// The relative interior of facet `i` of tetrahedron `t` (the facet opposite the start).
    Facet(u32, usize),
    /// The relative interior of the edge `(x, y)`, a side of a facet opposite the start.
    Edge([u32; 2], u32),
    /// The vertex itself: it lies on the segment.
    Vertex(u32),
}

/// The first crossing of the segment from `a` to `b`, or `None` if `(a, b)` is an edge.
pub fn first_crossing(mesh: &mut TetMesh, a: u32, b: u32) -> Result<Option<Crossing>> {
    let found = mesh.search_ball(a, |mesh, t| {
        let v = mesh.tets.vertices(t);
        let i = v.iter().position(|&x| x == a).unwrap_or(0);
        let (_, [x, y, z]) = mesh.with_apex(t, i);
        if [x, y, z].contains(&b) {
            return Some(None);
        }
        if !mesh.positive(v) {
            return None;
        }
        // b in the cone of the star of a at t: on the inner side of the three planes at a.
        let s = [
            mesh.orient([a, x, y, b]),
            mesh.orient([a, y, z, b]),
            mesh.orient([a, z, x, b]),
        ];
        if s.contains(&Sign::Negative) {
            return None;
        }
        Some(Some(match s {
            [Sign::Zero, Sign::Zero, _] => Crossing::Vertex(y),
            [_, Sign::Zero, Sign::Zero] => Crossing::Vertex(z),
            [Sign::Zero, _, Sign::Zero] => Crossing::Vertex(x),
            [Sign::Zero, ..] => Crossing::Edge([x, y], t),
            [_, Sign::Zero, _] => Crossing::Edge([y, z], t),
            [.., Sign::Zero] => Crossing::Edge([z, x], t),
            _ => Crossing::Facet(t, i),
        }))
    });
    found.ok_or_else(|| {
        Error::internal(format!("no tetrahedron around vertex {a} faces vertex {b}"))
    })
}

/// Recovers edge `(a, b)` by flips; `false` if it is still missing when no flip helps.
pub fn recover_edge(mesh: &mut TetMesh, protected: &Protected, a: u32, b: u32) -> Result<bool> {
    for _ in 0..MAX_FLIPS {
        let Some(from_a) = first_crossing(mesh, a, b)? else {
            return Ok(true);
        };
        let Some(from_b) = first_crossing(mesh, b, a)? else {
            return Ok(true);
        };
        for crossing in [from_a, from_b] {
            if let Crossing::Vertex(v) = crossing {
                return Err(vertex_on_edge(mesh, v, [a, b]));
            }
        }
        if advance(mesh, protected, a, from_a)? || advance(mesh, protected, b, from_b)? {
            continue;
        }
        if unblock(mesh, protected, from_a)? {
            continue;
        }
        // A failed unblocking may have kept flips: follow the segment from b again.
        let Some(from_b) = first_crossing(mesh, b, a)? else {
            return Ok(true);
        };
        if unblock(mesh, protected, from_b)? {
            continue;
        }
        return Ok(false);
    }
    Ok(false)
}

/// The error for vertex `v` found on the segment `e`: bad input when all three are input
/// vertices (validation lets no vertex lie on an input edge, so this is a check of last
/// resort), else the rounding of points added on the surface, which stops recovery.
pub fn vertex_on_edge(mesh: &TetMesh, v: u32, e: [u32; 2]) -> Error {
    let message = format!("vertex {v} lies on the edge ({}, {})", e[0], e[1]);
    if [v, e[0], e[1]].iter().all(|&x| !mesh.is_added(x)) {
        Error::invalid_input(message)
    } else {
        Error::new(
            ErrorKind::Limit,
            format!("{message} (rounded points added on the surface)"),
        )
    }
}

/// Takes away the first crossing from `start`: a 2-3 flip of the crossed facet, or the
/// removal of the crossed edge with its ring fanned from `start`.
fn advance(mesh: &mut TetMesh, protected: &Protected, start: u32, c: Crossing) -> Result<bool> {
    match c {
        Crossing::Facet(t, i) => flip23(mesh, protected, t, i, &|_, _, _| true),
        Crossing::Edge(e, _) => {
            let fan = |_: &TetMesh, u: u32, w: u32| u == start || w == start;
            remove_edge(mesh, protected, e, &fan)
        }
        Crossing::Vertex(_) => Ok(false),
    }
}

/// Removes one edge of the first crossed facet, or the crossed edge, whatever the ring
/// triangulation, to change the star that blocks [`advance`].
fn unblock(mesh: &mut TetMesh, protected: &Protected, c: Crossing) -> Result<bool> {
    let any = |_: &TetMesh, _: u32, _: u32| true;
    match c {
        Crossing::Facet(t, i) => {
            let (_, [x, y, z]) = mesh.with_apex(t, i);
            for e in [[x, y], [y, z], [z, x]] {
                if remove_edge_deep(mesh, protected, e, &any, DEPTH, &mut BUDGET.to_owned())? {
                    return Ok(true);
                }
            }
            Ok(false)
        }
        Crossing::Edge(e, _) => {
            remove_edge_deep(mesh, protected, e, &any, DEPTH, &mut BUDGET.to_owned())
        }
        Crossing::Vertex(_) => Ok(false),
    }
}
