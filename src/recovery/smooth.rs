//! Relocation of the interior points (TetGen's mesh optimization by vertex smoothing, its `-O`
//! scheme 2, `smoothpoint`): each point of a tetrahedron with a dihedral angle below
//! [`SMOOTH_BELOW`] moves to where the worst shape of its ball is best, found by the ascent
//! that places the splits' points ([`super::wedges::place`]). Refinement puts its points at
//! circumcenters, blind to the slivers they make with their neighbours; the vertices a sliver
//! has inside the region can move, those on the surface cannot.
//!
//! Invariants: only points added to the mesh and on no protected edge move (they lie strictly
//! inside a region, no input triangle has them); a point moves only where every tetrahedron
//! of its ball stays positive (exact), so the ball fills the same polyhedron and nothing
//! outside it changes, and where the ball's worst shape rises and its tetrahedra meet the
//! bound ([`Bound::improves_on`]); otherwise it stays where it was, bit for bit.

use super::flips::{shape, worst_ratio, Before, Bound};
use super::tetmesh::TetMesh;
use super::wedges::{opposite_facet, place};
use crate::geometry::dist;
use crate::predicates::Point;
use crate::quality::min_dihedral;

/// The dihedral angle, degrees, below which a tetrahedron's points inside the region move.
/// With the bound 1.414, tetrahedra with a dihedral angle below 5, 10 and 15 degrees (TetGen
/// -pq1.414Y: bunny00 1, 1,390, 6,265; fandisk 0, 204, 874): bunny00 34, 115, 432 without
/// moves, 33, 87, 223 with 15, 32, 86, 219 with 20; fandisk 9, 22, 102 without, 9, 16, 59 with
/// 15 or 20; armadillo 608, 1,634, 2,982 without, 598, 1,592, 2,777 with 15. Moving the points
/// of every tetrahedron shaped worse than half a regular one (on armadillo 15,311 of its
/// 18,316 points) gave bunny00 25, 73, 191 but took 40% more time in all; two more rounds
/// after the flips gained 5 on bunny00 and on armadillo.
pub const SMOOTH_BELOW: f64 = 15.0;

/// Moves, in increasing order, each added point off the surface (`on[v]` false or past its
/// end) of the tetrahedra of `tets` with a dihedral angle below [`SMOOTH_BELOW`], where that
/// raises the worst shape of its ball and the ball meets `bound`. Returns the tetrahedra of
/// the balls of the points moved, sorted, without repeats.
pub fn smooth_points(mesh: &mut TetMesh, on: &[bool], bound: Bound, tets: &[u32]) -> Vec<u32> {
    let movable = |mesh: &TetMesh, v: u32| mesh.is_added(v) && on.get(v as usize) != Some(&true);
    let mut points: Vec<u32> = tets
        .iter()
        .filter(|&&t| mesh.tets.is_live(t))
        .map(|&t| mesh.tets.vertices(t))
        // The shape first, cheaper than the angles: it took a third of the time of this
        // filter on bunny00, and the outputs of bunny00, armadillo, fandisk and knot stayed
        // the same.
        .filter(|&q| shape(mesh, q) < bound.below)
        .filter(|&q| min_dihedral(q.map(|v| *mesh.point(v))) < SMOOTH_BELOW)
        .flatten()
        .filter(|&v| movable(mesh, v))
        .collect();
    points.sort_unstable();
    points.dedup();
    let mut moved = Vec::new();
    for v in points {
        let ball = mesh.ball(v);
        if relocate(mesh, bound, v, &ball) {
            moved.extend(ball);
        }
    }
    moved.sort_unstable();
    moved.dedup();
    moved
}

/// Moves `v`, whose ball is `ball`, where the worst shape of the ball is best; whether it
/// moved (the move raises the worst shape, keeps every tetrahedron positive and meets
/// `bound`).
fn relocate(mesh: &mut TetMesh, bound: Bound, v: u32, ball: &[u32]) -> bool {
    let quads: Vec<[u32; 4]> = ball.iter().map(|&t| mesh.tets.vertices(t)).collect();
    let from = *mesh.point(v);
    let faces: Vec<[Point; 3]> = quads
        .iter()
        .map(|q| opposite_facet(q, v).map(|w| *mesh.point(w)))
        .collect();
    // The ascent's first step is a tenth of the mean distance to the ball's other corners.
    let reach: f64 = faces.iter().flatten().map(|p| dist(p, &from)).sum();
    let to = place(&faces, from, reach / (3 * faces.len()) as f64);
    // The ascent returns its start where no step raised the worst shape: nothing to try.
    if to == from {
        return false;
    }
    let before = Before::of(&bound, mesh, &quads);
    let old_ratio = worst_ratio(mesh, &quads);
    mesh.move_point(v, to);
    let positive = quads.iter().all(|&q| mesh.positive(q));
    if positive && bound.improves_on(mesh, before, &|| old_ratio, &quads) {
        return true;
    }
    mesh.move_point(v, from);
    false
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::recovery::flips::{worst_shape, Exempt, IMPROVED_BELOW};
    use crate::triangulation::tets::{FACE, INFINITE};

    /// A cube's Delaunay tetrahedralization with one of its tetrahedra split at a point put
    /// near one of that tetrahedron's facets (the tetrahedron over that facet is a sliver);
    /// the mesh and the point.
    fn cube_with_point_near_a_facet() -> (TetMesh, u32) {
        let corners: Vec<Point> = (0..8)
            .map(|c| [0, 1, 2].map(|k| f64::from((c >> k) & 1) * 2.0 - 1.0))
            .collect();
        let used: Vec<u32> = (0..8).collect();
        let mut mesh = TetMesh::delaunay(corners, &used).unwrap();
        let t = mesh
            .tets
            .live()
            .find(|&t| mesh.positive(mesh.tets.vertices(t)))
            .unwrap();
        let q = mesh.tets.vertices(t);
        // 0.99 of the way from q[3] to the centroid of its opposite facet.
        let p = q.map(|v| *mesh.point(v));
        let at = std::array::from_fn(|k| {
            let facet = (p[0][k] + p[1][k] + p[2][k]) / 3.0;
            p[3][k] + 0.99 * (facet - p[3][k])
        });
        let s = mesh.add_point(at);
        let new: Vec<[u32; 4]> = (0..4)
            .map(|k| {
                let [a, b, c] = FACE[k].map(|i| q[i]);
                [a, b, c, s]
            })
            .collect();
        mesh.replace(&[t], &new).unwrap();
        (mesh, s)
    }

    fn bound(on: &[bool]) -> Bound<'_> {
        Bound {
            below: IMPROVED_BELOW,
            ratio: 1.414,
            exempt: Exempt::OnSurface(on),
            no_larger: false,
        }
    }

    /// The finite tetrahedra (the kept regions' are).
    fn finite(mesh: &TetMesh) -> Vec<u32> {
        let finite = |&t: &u32| !mesh.tets.vertices(t).contains(&INFINITE);
        mesh.tets.live().filter(finite).collect()
    }

    fn ball_quads(mesh: &mut TetMesh, v: u32) -> Vec<[u32; 4]> {
        let ball = mesh.ball(v);
        ball.iter().map(|&t| mesh.tets.vertices(t)).collect()
    }

    /// The point moves off the facet: its ball's worst shape rises, every tetrahedron stays
    /// positive and the mesh is valid.
    #[test]
    fn a_point_near_a_facet_moves_away_from_it() {
        let (mut mesh, s) = cube_with_point_near_a_facet();
        let on = vec![true; 8];
        let quads = ball_quads(&mut mesh, s);
        let before = worst_shape(&mesh, &quads);
        let from = *mesh.point(s);
        let all = finite(&mesh);
        let moved = smooth_points(&mut mesh, &on, bound(&on), &all);
        assert_eq!(moved.len(), 4, "the point's ball is not told");
        assert_ne!(*mesh.point(s), from, "the point did not move");
        assert!(worst_shape(&mesh, &quads) > 2.0 * before);
        assert!(finite(&mesh)
            .iter()
            .all(|&t| mesh.positive(mesh.tets.vertices(t))));
        mesh.validate().unwrap();
    }

    /// A point on the surface stays where it is, bit for bit.
    #[test]
    fn a_point_on_the_surface_stays() {
        let (mut mesh, s) = cube_with_point_near_a_facet();
        let on = vec![true; 9];
        let from = *mesh.point(s);
        let all = finite(&mesh);
        assert!(smooth_points(&mut mesh, &on, bound(&on), &all).is_empty());
        assert_eq!(mesh.point(s).map(f64::to_bits), from.map(f64::to_bits));
    }
}
