//! Splits of the wedges quality refinement leaves above its bound (TetGen's mesh optimization
//! by point insertion, its `-O` scheme 4, `splitsliver`). A wedge is a tetrahedron two of
//! whose facets are input triangles meeting at an input edge at a nearly flat angle (wider
//! than [`WIDE_ANGLE`]): it lies between them, flat, and neither flips take it away nor
//! refinement, which declines its far circumcenter (fandisk with the bound 1.414: triangles
//! 588-683-684 and 683-684-784, ratio 38). Its other diagonal, no input edge, is split by a new
//! interior point, moved to where the worst shape of the diagonal's star is best (an ascent on
//! the worst tetrahedron's shape, TetGen's `smoothpoint`): each input triangle then rests on
//! its own tetrahedron with the point. The new tetrahedra above the bound are refined as
//! refinement does ([`super::refine::refine_these`]).
//!
//! Invariants: the split edge is no input edge, so no input triangle holds it, no protected
//! facet lies around it and its shell lies in one region; the point lies strictly inside that
//! shell (every new tetrahedron is positive, exactly), so it is an interior point of the
//! region and no input triangle is split. A split is kept only where it raises the worst shape
//! of the shell and no new tetrahedron has a radius-edge ratio above the worst of the shell's
//! and the bound; otherwise the point is dropped and nothing changes.

use smallvec::SmallVec;

use super::flips::{Bound, Exempt, Protected};
use super::tetmesh::TetMesh;
use crate::error::Result;
use crate::geometry::{add, cross, dist, dot, midpoint, norm, sub, tet_volume};
use crate::predicates::Point;
use crate::quality::radius_edge;
use crate::triangulation::tets::{FACE, INFINITE};

/// The dihedral angle, degrees, above which the tetrahedron between two input triangles that
/// meet at an input edge is a wedge.
const WIDE_ANGLE: f64 = 150.0;

/// How many times the ratio bound a wedge's radius-edge ratio must exceed to be split: each
/// split's new tetrahedra above the bound are refined, and those points add up. With the bound
/// 1.414 on armadillo (TetGen -pq1.414Y: 18,465 points): 18,370 points with 10, 18,756 with 4,
/// 19,302 with 1 (tetrahedra with a dihedral angle below 5 degrees 751, 671, 628; 800 without
/// splits); fandisk's largest ratio 4.1 with 10 or 4, 3.7 with 1 (38 without).
const EXCESS: f64 = 10.0;

/// The longest shell split.
const SPLIT_SHELL: usize = 16;

/// Steps of the ascent that places the new point.
const ASCENT_STEPS: usize = 64;

/// Halvings of a step before the ascent stops.
const HALVINGS: usize = 16;

/// Splits, in `candidates` order, the wedges among them [`EXCESS`] times above the ratio bound
/// of `bound` where that gives a better star ([`split`]). `made(mesh, old, new)` is told the
/// new tetrahedra of each split and one it replaced. Returns the new tetrahedra still in the
/// mesh.
pub fn split_wedges(
    mesh: &mut TetMesh,
    protected: &Protected,
    bound: Bound,
    candidates: &[u32],
    made: &mut dyn FnMut(&TetMesh, u32, &[u32]),
) -> Result<Vec<u32>> {
    let mut created = Vec::new();
    for &t in candidates {
        if !mesh.tets.is_live(t) {
            continue;
        }
        let quad = mesh.tets.vertices(t);
        let above = bound.ratio * EXCESS;
        if quad.contains(&INFINITE) || radius_edge(quad.map(|v| mesh.point(v))) <= above {
            continue;
        }
        let Some(diagonal) = wedge_diagonal(mesh, protected, quad) else {
            continue;
        };
        if let Some(new) = split(mesh, protected, bound, t, diagonal)? {
            made(mesh, t, &new);
            created.extend(new);
        }
    }
    created.retain(|&t| mesh.tets.is_live(t));
    Ok(created)
}

/// The edge of `quad` opposite the input edge where two of its facets, input triangles, meet
/// at a dihedral angle wider than [`WIDE_ANGLE`]; `None` when `quad` is no such wedge.
fn wedge_diagonal(mesh: &TetMesh, protected: &Protected, quad: [u32; 4]) -> Option<[u32; 2]> {
    let facet = |k: usize| FACE[k].map(|i| quad[i]);
    let input: SmallVec<[usize; 4]> = (0..4).filter(|&k| protected.facet(facet(k))).collect();
    let [k, l] = input[..] else {
        return None;
    };
    // Facet k's normal (opposite vertex k) points into the tetrahedron; facets k and l meet at
    // the edge of the two other vertices.
    let inward = |k: usize| {
        let [a, b, c] = facet(k).map(|v| *mesh.point(v));
        cross(&sub(&b, &a), &sub(&c, &a))
    };
    let (nk, nl) = (inward(k), inward(l));
    let cosine = -dot(&nk, &nl) / (norm(&nk) * norm(&nl));
    (cosine < WIDE_ANGLE.to_radians().cos()).then_some([quad[k], quad[l]])
}

/// Splits the edge `(a, b)` of `t` by a new point placed by [`place`]; the new tetrahedra,
/// or `None` (nothing changed) where the edge is an input edge, its shell is infinite or
/// longer than [`SPLIT_SHELL`], or the split does not raise the worst shape with no new
/// tetrahedron above both the bound and the worst ratio of the shell.
fn split(
    mesh: &mut TetMesh,
    protected: &Protected,
    bound: Bound,
    t: u32,
    [a, b]: [u32; 2],
) -> Result<Option<Vec<u32>>> {
    if protected.edge(a, b) {
        return Ok(None);
    }
    let Some((shell, ring)) = mesh.shell(t, a, b, SPLIT_SHELL) else {
        return Ok(None);
    };
    if ring.contains(&INFINITE) {
        return Ok(None);
    }
    let old: SmallVec<[[u32; 4]; 16]> = shell.iter().map(|&u| mesh.tets.vertices(u)).collect();
    // Each old tetrahedron gives two, with a or b replaced by the point: the facet opposite
    // that end, oriented so that the point completes it positively.
    let faces: Vec<[u32; 3]> = old
        .iter()
        .flat_map(|q| [a, b].map(|x| opposite_facet(q, x)))
        .collect();
    let corners: Vec<[Point; 3]> = faces.iter().map(|f| f.map(|v| *mesh.point(v))).collect();
    let (pa, pb) = (*mesh.point(a), *mesh.point(b));
    let at = place(&corners, midpoint(&pa, &pb), dist(&pa, &pb));
    let s = mesh.add_point(at);
    let new: Vec<[u32; 4]> = faces.iter().map(|&[x, y, z]| [x, y, z, s]).collect();
    // Refinement then takes the new tetrahedra above the bound.
    let no_worse = Bound {
        exempt: Exempt::All,
        ..bound
    };
    if !new.iter().all(|&q| mesh.positive(q)) || !no_worse.improved(mesh, &old, &new) {
        mesh.pop_point();
        return Ok(None);
    }
    mesh.replace(&shell, &new).map(Some)
}

/// The facet of the positive tetrahedron `q` opposite its vertex `x`, ordered so that it and
/// `x` (or any point on `x`'s side) are positive.
fn opposite_facet(q: &[u32; 4], x: u32) -> [u32; 3] {
    let k = q.iter().position(|&v| v == x).unwrap_or(0);
    FACE[k].map(|i| q[i])
}

/// The worst shape of the tetrahedra of `faces` completed by `p`, and which one it is
/// (negative where one is inverted).
fn worst(faces: &[[Point; 3]], p: &Point) -> (f64, usize) {
    faces
        .iter()
        .enumerate()
        .map(|(k, f)| (signed_shape(f, p), k))
        .fold((f64::INFINITY, 0), |w, x| if x.0 < w.0 { x } else { w })
}

/// The shape of `flips::shape`, signed by the tetrahedron `(f, p)`'s orientation.
fn signed_shape(f: &[Point; 3], p: &Point) -> f64 {
    let (volume, sum) = volume_and_edges(f, p);
    volume / (sum * sum.sqrt())
}

/// The volume of `(f, p)`, signed, and the sum of its squared edge lengths.
fn volume_and_edges(f: &[Point; 3], p: &Point) -> (f64, f64) {
    let volume = tet_volume([&f[0], &f[1], &f[2], p]);
    let mut sum = 0.0;
    for i in 0..3 {
        sum += dot(&sub(&f[(i + 1) % 3], &f[i]), &sub(&f[(i + 1) % 3], &f[i]));
        sum += dot(&sub(p, &f[i]), &sub(p, &f[i]));
    }
    (volume, sum)
}

/// The gradient, in `p`, of the signed shape of `(f, p)`: the volume grows along the facet's
/// normal, the sum of squared edges along `p`'s offset from the facet's corners.
fn gradient(f: &[Point; 3], p: &Point) -> Point {
    let (volume, sum) = volume_and_edges(f, p);
    let normal = cross(&sub(&f[1], &f[0]), &sub(&f[2], &f[0]));
    let offset: Point = std::array::from_fn(|k| 2.0 * (3.0 * p[k] - f[0][k] - f[1][k] - f[2][k]));
    let (s15, s25) = (sum * sum.sqrt(), sum * sum * sum.sqrt());
    std::array::from_fn(|k| normal[k] / 6.0 / s15 - 1.5 * volume * offset[k] / s25)
}

/// Where the point completing every facet of `faces` gives the best worst shape, from
/// `start`: steps along the gradient of the worst tetrahedron's shape, kept where they raise
/// the worst shape, a step halved until one does (at most [`HALVINGS`] times) and doubled
/// after one did; `length` (the split edge's) sets the first step.
fn place(faces: &[[Point; 3]], start: Point, length: f64) -> Point {
    let mut p = start;
    let (mut best, mut k) = worst(faces, &p);
    let mut step = 0.1 * length;
    for _ in 0..ASCENT_STEPS {
        let g = gradient(&faces[k], &p);
        let n = norm(&g);
        if n == 0.0 || !n.is_finite() {
            break;
        }
        let direction = g.map(|x| x / n);
        let mut moved = false;
        for _ in 0..HALVINGS {
            let q = add(&p, &direction.map(|x| x * step));
            let (w, wk) = worst(faces, &q);
            if w > best {
                (p, best, k, moved) = (q, w, wk, true);
                break;
            }
            step *= 0.5;
        }
        if !moved {
            break;
        }
        step *= 2.0;
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The worst shape (volume over the cube of the root of the summed squared edges) of the
    /// finite tetrahedra.
    fn worst_shape(mesh: &TetMesh) -> f64 {
        let faces: Vec<([Point; 3], Point)> = mesh
            .tets
            .live()
            .map(|t| mesh.tets.vertices(t))
            .filter(|q| !q.contains(&INFINITE))
            .map(|q| (FACE[3].map(|i| *mesh.point(q[i])), *mesh.point(q[3])))
            .collect();
        faces
            .iter()
            .map(|(f, p)| signed_shape(f, p))
            .fold(f64::INFINITY, f64::min)
    }

    /// A roof of two input triangles over a ridge `ab`, their far corners `c` and `d` 0.02
    /// lower: the Delaunay tetrahedron of the four corners (its circumcenter some 75 above)
    /// lies flat between them, radius-edge ratio 37.5. Its diagonal `cd` is split by a point
    /// below the roof: the wedge goes, the triangles stay, every tetrahedron is positive and
    /// the worst shape rises.
    #[test]
    fn a_wedge_under_a_ridge_is_split_below_it() {
        let points = vec![
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [2.0, -1.0, -0.02],
            [2.0, 1.0, -0.02],
            [2.0, 0.0, -2.0],
            [0.5, -1.5, -2.5],
            [3.5, 1.5, -2.5],
        ];
        let n = points.len();
        let used: Vec<u32> = (0..n as u32).collect();
        let mut mesh = TetMesh::delaunay(points, &used).unwrap();
        let wedge = |mesh: &TetMesh| {
            mesh.tets.live().any(|t| {
                let mut q = mesh.tets.vertices(t);
                q.sort_unstable();
                q == [0, 1, 2, 3]
            })
        };
        assert!(wedge(&mesh), "the Delaunay tetrahedralization has no wedge");
        let mut protected = Protected::default();
        protected.insert_facet([0, 1, 2]);
        protected.insert_facet([0, 1, 3]);
        let on = protected.vertices_on_edges(n);
        let bound = Bound {
            below: 0.0,
            ratio: 1.414,
            exempt: Exempt::OnSurface(&on),
            no_larger: false,
        };
        let before = worst_shape(&mesh);
        let kept: Vec<u32> = mesh.tets.live().collect();
        let mut told = 0;
        let new = split_wedges(&mut mesh, &protected, bound, &kept, &mut |_, _, new| {
            told += new.len()
        })
        .unwrap();
        assert!(!new.is_empty() && told >= new.len());
        assert!(!wedge(&mesh), "the wedge is still there");
        mesh.validate().unwrap();
        assert!(mesh.find_face([0, 1, 2]).is_some() && mesh.find_face([0, 1, 3]).is_some());
        assert_eq!(mesh.points.len(), n + 1);
        assert!(
            mesh.point(n as u32)[2] < -0.02,
            "the point is not below the roof"
        );
        assert!(worst_shape(&mesh) > before);
    }
}
