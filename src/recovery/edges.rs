//! Recovery of a missing input edge by flips (George and Borouchaki §5.2, first part).
//!
//! The segment `ab` is followed from `a`: its first crossing is a facet or an edge of the
//! star of `a` ([`first_crossing`]). A 2-3 flip of that facet, or the removal of that edge,
//! takes the crossing away: the segment then leaves the star of `a` one tetrahedron further.
//! A crossed edge is coplanar with the segment; its ring is triangulated without any
//! diagonal across that plane, which generalizes the fan from `a` and, when `b` is in the
//! ring, is the 2-2 flip in the plane that coplanar input (grids, planar CAD faces) needs;
//! where the ring cannot be so triangulated, the shell may first be shrunk (2-3 flips of its
//! facets, a few levels deep, none across the plane), when the caller asks for it.
//! The same is tried from `b`. When neither end can advance, the edges of the first crossed
//! facets are removed (any valid ring triangulation, shrinking rings some levels deep as
//! TetGen's `flipnm` does; a facet's edges where its 2-3 flip fails first, as TetGen's
//! `removefacebyflips` picks them), which changes the stars without advancing, until the
//! first crossings repeat or a bounded number of times. The caller tries the edges still
//! missing again, deeper (down to [`DEEPEST`]) or with guarded unblocking: no flip may
//! create a facet whose interior the segment crosses ([`Clear`], TetGen's
//! `checkflipeligibility` with a segment).

use super::faces::crosses;
use super::flips::{blocking_sides, flip23, remove_edge, remove_edge_deep, Any, Protected, Rule};
use super::partition::pair;
use super::tetmesh::{key, TetMesh};
use crate::error::{Error, ErrorKind, Result};
use crate::predicates::Sign;
use crate::triangulation::tets::INFINITE;

/// Most flips tried on one edge before it is declared stuck.
const MAX_FLIPS: usize = 256;

/// How deep [`remove_edge_deep`] goes to unblock a star at the first attempt on an edge, and
/// how many edge removals each unblocking tries then; each level deeper doubles them.
pub const DEPTH: u32 = 3;
const BUDGET: usize = 256;

/// The deepest level at which the main recovery tries again the edges still missing, before
/// it adds points (TetGen raises its flip level the same way, while missing segments remain;
/// the passes are the recovery's schedules).
pub const DEEPEST: u32 = 5;

/// How deep, and with how many edge removals, [`advance`] shrinks the shell of an edge the
/// segment crosses in its plane, when asked to.
const SHRINK_DEPTH: u32 = 2;
const SHRINK_BUDGET: usize = 64;

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

/// What the unblocking flips of a segment may create ([`recover_edge`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Guard {
    /// Anything.
    Open,
    /// No facet whose interior the segment crosses ([`Clear`]).
    Clear,
    /// Neither such a facet nor an edge whose interior the segment crosses, nor a facet in
    /// the segment's plane whose sides it crosses ([`Eligible`]: TetGen's
    /// `checkflipeligibility` with a segment).
    Eligible,
}

/// Recovers edge `(a, b)` by flips; `false` if it is still missing when no flip helps.
/// Crossings are looked up again after every attempt that may have changed the mesh.
/// Unblocking ([`unblock`]) removes edges `depth` levels deep (at least [`DEPTH`], from which
/// its budget doubles with each level), and stops when it meets the first crossings from
/// both ends it met before (its flips went round in a circle); `guard` says what its flips
/// may create. With `shrink`, an edge crossed in the segment's plane whose ring cannot be
/// triangulated at once has its shell shrunk first ([`SHRINK_DEPTH`]).
pub fn recover_edge(
    mesh: &mut TetMesh,
    protected: &Protected,
    [a, b]: [u32; 2],
    depth: u32,
    guard: Guard,
    shrink: bool,
) -> Result<bool> {
    debug_assert!(depth >= DEPTH, "recovery of an edge {depth} levels deep");
    let (clear, eligible) = (Clear([a, b]), Eligible([a, b]));
    let rule: &dyn Rule = match guard {
        Guard::Open => &Any,
        Guard::Clear => &clear,
        Guard::Eligible => &eligible,
    };
    let mut seen = rustc_hash::FxHashSet::default();
    'flips: for _ in 0..MAX_FLIPS {
        // A failed advance changes nothing unless it shrinks: its crossings still hold after
        // both failed, and are looked up again otherwise.
        let mut crossings = [Crossing::Vertex(a); 2];
        for (k, [s, e]) in [[a, b], [b, a]].into_iter().enumerate() {
            let Some(c) = crossing_off_vertices(mesh, s, e)? else {
                return Ok(true);
            };
            if advance(mesh, protected, [s, e], c, shrink)? {
                continue 'flips;
            }
            crossings[k] = c;
        }
        if shrink {
            for (k, [s, e]) in [[a, b], [b, a]].into_iter().enumerate() {
                let Some(c) = crossing_off_vertices(mesh, s, e)? else {
                    return Ok(true);
                };
                crossings[k] = c;
            }
        }
        if !seen.insert(crossings.map(|c| crossed(mesh, c))) {
            // The unblocking flips went round in a circle.
            return Ok(false);
        }
        if unblock(mesh, protected, crossings[0], depth, rule)? {
            continue;
        }
        // A failed unblocking may keep flips: the crossing from b is looked up again.
        let Some(c) = crossing_off_vertices(mesh, b, a)? else {
            return Ok(true);
        };
        if !unblock(mesh, protected, c, depth, rule)? {
            return Ok(false);
        }
    }
    Ok(false)
}

/// The sorted vertices of the facet or edge (then with [`INFINITE`] last) a crossing names.
fn crossed(mesh: &TetMesh, c: Crossing) -> [u32; 3] {
    key(match c {
        Crossing::Facet(t, i) => mesh.facet(t, i),
        Crossing::Edge([x, y], _) => [x, y, INFINITE],
        Crossing::Vertex(v) => [v, INFINITE, INFINITE],
    })
}

/// [`first_crossing`] from `s` toward `e`, an error when it is a vertex.
fn crossing_off_vertices(mesh: &mut TetMesh, s: u32, e: u32) -> Result<Option<Crossing>> {
    match first_crossing(mesh, s, e)? {
        Some(Crossing::Vertex(v)) => Err(vertex_on_edge(mesh, v, [s, e])),
        c => Ok(c),
    }
}

/// The error for vertex `v` found on the segment `e`: bad input when all three are input
/// vertices (validation lets no vertex lie on an input edge, so this is a check of last
/// resort), else a point added on the surface found on a segment it is not on in the
/// partition (a near copy, or a point where flips met it exactly), which stops recovery.
pub fn vertex_on_edge(mesh: &TetMesh, v: u32, e: [u32; 2]) -> Error {
    let message = format!("vertex {v} lies on the edge ({}, {})", e[0], e[1]);
    if [v, e[0], e[1]].iter().all(|&x| !mesh.is_added(x)) {
        Error::invalid_input(message)
    } else {
        Error::new(
            ErrorKind::Limit,
            format!("{message} (points added on the surface)"),
        )
    }
}

/// Takes away the first crossing of the segment from `start` to `end`: a 2-3 flip of the
/// crossed facet, or the removal of the crossed edge. The segment meets that edge, so the
/// four points are coplanar: any ring triangulation without a diagonal across their plane
/// leaves the segment one tetrahedron further into the star of `start` (and recovers it, by
/// a 2-2 flip in that plane, when `end` is in the ring). With `shrink`, where the ring has no
/// such triangulation, the edge is removed after shrinking its shell; flips made on the way
/// stay when that fails.
fn advance(
    mesh: &mut TetMesh,
    protected: &Protected,
    [start, end]: [u32; 2],
    c: Crossing,
    shrink: bool,
) -> Result<bool> {
    match c {
        Crossing::Facet(t, i) => flip23(mesh, protected, t, i, &Any),
        Crossing::Edge([x, y], _) => {
            debug_assert_eq!(mesh.orient([x, y, start, end]), Sign::Zero);
            let rule = not_across(x, y, start);
            if !shrink {
                return remove_edge(mesh, protected, [x, y], &rule);
            }
            // The plain removal first, then with the shell shrunk.
            let mut budget = SHRINK_BUDGET;
            remove_edge_deep(mesh, protected, [x, y], &rule, SHRINK_DEPTH, &mut budget)
        }
        Crossing::Vertex(_) => Ok(false),
    }
}

/// Accepts a diagonal unless its ends lie strictly on opposite sides of the plane through
/// `x`, `y` and `start`.
fn not_across(x: u32, y: u32, start: u32) -> impl Fn(&TetMesh, u32, u32) -> bool {
    move |m: &TetMesh, u: u32, w: u32| {
        let su = m.orient([x, y, start, u]);
        su == Sign::Zero || su != m.orient([x, y, start, w]).negate()
    }
}

/// Removes one edge of the first crossed facet, or the crossed edge, `depth` levels deep, by
/// flips that `rule` allows, to change the star that blocks [`advance`]. A facet's edges
/// are tried first where its 2-3 flip fails (TetGen's `removefacebyflips`): the edges whose
/// new tetrahedron would not be positive.
fn unblock(
    mesh: &mut TetMesh,
    protected: &Protected,
    c: Crossing,
    depth: u32,
    rule: &dyn Rule,
) -> Result<bool> {
    let budget = BUDGET << (depth - DEPTH);
    match c {
        Crossing::Facet(t, i) => {
            let (d, [x, y, z]) = mesh.with_apex(t, i);
            let mut edges = [[x, y], [y, z], [z, x]];
            if d != INFINITE && mesh.across(t, i) != INFINITE {
                let blocking = blocking_sides(mesh, t, i);
                edges.sort_by_key(|&[u, w]| !blocking.contains(&pair(u, w)));
            }
            for e in edges {
                if remove_edge_deep(mesh, protected, e, rule, depth, &mut budget.to_owned())? {
                    return Ok(true);
                }
            }
            Ok(false)
        }
        Crossing::Edge(e, _) => {
            remove_edge_deep(mesh, protected, e, rule, depth, &mut budget.to_owned())
        }
        Crossing::Vertex(_) => Ok(false),
    }
}

/// The rule of guarded unblocking: no new facet whose interior the segment crosses.
pub struct Clear(pub [u32; 2]);

impl Rule for Clear {
    fn edge(&self, _: &TetMesh, _: u32, _: u32) -> bool {
        true
    }

    fn facet(&self, mesh: &TetMesh, f: [u32; 3]) -> bool {
        !crosses(mesh, f, self.0[0], self.0[1])
    }

    /// The segment's ends, the lower first (the rule does not depend on their order).
    fn memo_key(&self) -> Option<[u32; 2]> {
        let [a, b] = self.0;
        Some([a.min(b), a.max(b)])
    }
}

/// TetGen's rule for the flips that recover a segment (`checkflipeligibility`): no new
/// facet whose interior the segment crosses, no new edge whose interior it crosses, and no
/// new facet in the segment's plane whose sides it crosses.
pub struct Eligible(pub [u32; 2]);

impl Rule for Eligible {
    fn edge(&self, mesh: &TetMesh, u: u32, w: u32) -> bool {
        let [a, b] = self.0;
        if [u, w].iter().any(|x| [a, b, INFINITE].contains(x))
            || mesh.orient([a, b, u, w]) != Sign::Zero
        {
            return true;
        }
        // The four points are in a plane; a vertex off it tells the sides of a line in it.
        match mesh.off_plane([u, a, b]) {
            Some(x) => !crosses_in_plane(mesh, [a, b], [u, w], x),
            // No such vertex at hand: refused, as a crossing may not be ruled out.
            None => false,
        }
    }

    fn facet(&self, mesh: &TetMesh, f: [u32; 3]) -> bool {
        let [a, b] = self.0;
        let in_plane = |e: u32| mesh.orient([f[0], f[1], f[2], e]) == Sign::Zero;
        // Off the plane, only a crossing of the interior counts; with one end in it and the
        // other off it, the segment cannot cross the facet.
        if f.contains(&INFINITE) || !in_plane(a) {
            return !crosses(mesh, f, a, b);
        }
        if !in_plane(b) {
            return true;
        }
        // In the facet's plane: its sides must not cross the segment; a vertex off the plane
        // tells the sides of a line in it.
        let Some(x) = mesh.off_plane(f) else {
            return false;
        };
        (0..3).all(|k| !crosses_in_plane(mesh, [a, b], [f[k], f[(k + 1) % 3]], x))
    }

    /// The segment's ends, the higher first: not [`Clear`]'s name.
    fn memo_key(&self) -> Option<[u32; 2]> {
        let [a, b] = self.0;
        Some([a.max(b), a.min(b)])
    }
}

/// Whether the coplanar segments `(a, b)` and `(u, w)` cross at one point inside both: each
/// separates the other's ends in their plane, where the side of a point `p` of the line
/// `(s, t)` is the sign of `orient(s, t, x, p)`, `x` a vertex off the plane.
fn crosses_in_plane(mesh: &TetMesh, [a, b]: [u32; 2], [u, w]: [u32; 2], x: u32) -> bool {
    let separates = |[s, t]: [u32; 2], [p, q]: [u32; 2]| {
        let (sp, sq) = (mesh.orient([s, t, x, p]), mesh.orient([s, t, x, q]));
        sp != Sign::Zero && sp == sq.negate()
    };
    separates([a, b], [u, w]) && separates([u, w], [a, b])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square in the plane z = 0 with apexes above and below its centre: its diagonal
    /// (0, 2) crosses the other diagonal (1, 3) and the apexes' edge (4, 5) at its middle,
    /// and the sides of the triangle (1, 2, 3) of its plane.
    #[test]
    fn tetgens_rule_refuses_what_the_segment_crosses_in_its_plane() {
        let points = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
            [1.0, 1.0, 1.0],
            [1.0, 1.0, -1.0],
        ];
        let mesh = TetMesh::delaunay(points, &[0, 1, 2, 3, 4, 5]).unwrap();
        let rule = Eligible([0, 2]);
        assert!(!rule.edge(&mesh, 1, 3) && !rule.edge(&mesh, 4, 5));
        assert!(rule.edge(&mesh, 1, 4) && rule.edge(&mesh, 0, 4) && rule.edge(&mesh, 2, 5));
        assert!(!rule.facet(&mesh, [1, 2, 3]) && !rule.facet(&mesh, [3, 0, 1]));
        assert!(rule.facet(&mesh, [0, 1, 2]) && rule.facet(&mesh, [1, 3, 4]));
        // The guarded rule refuses only facets whose interior the segment crosses.
        assert!(Clear([0, 2]).facet(&mesh, [1, 2, 3]));
    }
}
