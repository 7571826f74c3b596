//! Splits of the flat tetrahedra on the surface that quality refinement leaves far above its
//! bound (TetGen's mesh optimization by point insertion, its `-O` scheme 4, `splitsliver`).
//! A wedge is a tetrahedron two of whose facets are input triangles meeting at an input edge
//! at a nearly flat angle (wider than [`WIDE_ANGLE`]): it lies between them, flat, and
//! neither flips take it away nor refinement, which declines its far circumcenter (fandisk
//! with the bound 1.414: triangles 588-683-684 and 683-684-784, ratio 38). Its other
//! diagonal, no input edge, is split first; for it and for the other flat tetrahedra with an
//! input facet or with three or four vertices on the surface (a point refinement put nearly in
//! the plane of three surface vertices: armadillo with the bound 1.414, ratio 354), then the
//! edges where the dihedral angle is that wide, no input edges. The new interior point moves
//! to where the worst shape of the edge's star is best (an ascent on the worst tetrahedron's
//! shape, TetGen's `smoothpoint`): each input triangle then rests on its own tetrahedron with
//! the point. The new tetrahedra above the bound are refined as refinement does
//! ([`super::refine::refine_these`]), and what that makes gets the flips that raise the worst
//! shape ([`super::flips::improve_by_flips`]).
//!
//! Invariants: the split edge is no input edge, so no input triangle holds it, no protected
//! facet lies around it and its shell lies in one region; the point lies strictly inside that
//! shell (every new tetrahedron is positive, exactly), so it is an interior point of the
//! region and no input triangle is split. A split is kept only where it raises the worst shape
//! of the shell and every new tetrahedron's radius-edge ratio is within the bound or [`GAIN`]
//! times lower than the worst of the shell; otherwise the point is dropped and nothing
//! changes.

use smallvec::SmallVec;

use super::flips::{Bound, Exempt, Protected};
use super::tetmesh::TetMesh;
use crate::error::Result;
use crate::geometry::{add, cross, dist, dot, midpoint, norm, sub};
use crate::predicates::Point;
use crate::quality::radius_edge;
use crate::triangulation::tets::{FACE, INFINITE};

/// The dihedral angle, degrees, above which the tetrahedron between two input triangles that
/// meet at an input edge is a wedge.
const WIDE_ANGLE: f64 = 150.0;

/// How many times the ratio bound a tetrahedron's radius-edge ratio must exceed for its edges
/// to be split: each split's new tetrahedra above the bound are refined, and those points add
/// up. With the bound 1.414 on armadillo (TetGen -pq1.414Y: 18,465 points): 18,316 points with
/// 10 (608 tetrahedra with a dihedral angle below 5 degrees, the largest ratio 136), 18,561
/// with 4 (524, the same largest ratio): more points than TetGen; fandisk's largest ratio 4.1
/// with either (38 without splits).
const EXCESS: f64 = 10.0;

/// How many times lower than the worst radius-edge ratio of the shell every new tetrahedron's
/// must be, unless it meets the bound: a split that trades a bad tetrahedron for others nearly
/// as bad only gives refinement more to do around them. With the bound 1.414, Chazelle's
/// polyhedron with three notches a side keeps 15 points (TetGen -pq1.414Y: 16, and 3 on its
/// surface) and 111 tetrahedra below 5 degrees with 2, 21 and 122 with 1 (11 and 110 without
/// splits), the same largest ratio; double-torus-example's largest ratio is 269 with 2, 152
/// with 1; stanfordbunny's 45.7 with 2 and 1, 90 with 4 (448 without splits).
const GAIN: f64 = 2.0;

/// The longest shell split.
const SPLIT_SHELL: usize = 16;

/// Steps of the ascent that places the new point.
const ASCENT_STEPS: usize = 64;

/// The shortest step of the ascent, over the length it starts from.
const SHORTEST_STEP: f64 = 1e-3;

/// How much better than the worst shape a tetrahedron's may be for the ascent to raise it
/// with the worst one's where that alone gains nothing.
const NEAR_WORST: f64 = 1.5;

/// Splits, in `candidates` order, an edge of each of them [`EXCESS`] times above the ratio
/// bound of `bound`, the first of [`edges_to_split`] where that gives a better star
/// ([`split`]). `made(mesh, old, new)` is told the
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
        for e in edges_to_split(mesh, protected, quad) {
            if let Some(new) = split(mesh, protected, bound, t, e)? {
                made(mesh, t, &new);
                created.extend(new);
                break;
            }
        }
    }
    created.retain(|&t| mesh.tets.is_live(t));
    Ok(created)
}

/// The edges of `quad` to split, in order: where two of its facets are input triangles
/// meeting at an input edge at a dihedral angle wider than [`WIDE_ANGLE`] (a wedge), the other
/// diagonal; then the edges where its dihedral angle is that wide, no input edges, widest
/// first (TetGen splits a sliver at its widest dihedral angle).
fn edges_to_split(
    mesh: &TetMesh,
    protected: &Protected,
    quad: [u32; 4],
) -> SmallVec<[[u32; 2]; 6]> {
    let facet = |k: usize| FACE[k].map(|i| quad[i]);
    // Facet k's normal (opposite vertex k) points into the tetrahedron; facets k and l meet at
    // the edge of the two other vertices, at the angle whose cosine is minus the normals'.
    let normals: [Point; 4] = std::array::from_fn(|k| {
        let [a, b, c] = facet(k).map(|v| *mesh.point(v));
        cross(&sub(&b, &a), &sub(&c, &a))
    });
    let mut edges = SmallVec::new();
    let mut wide: SmallVec<[(f64, [u32; 2]); 6]> = SmallVec::new();
    for k in 0..4 {
        for l in k + 1..4 {
            let (nk, nl) = (normals[k], normals[l]);
            let cosine = -dot(&nk, &nl) / (norm(&nk) * norm(&nl));
            if cosine >= WIDE_ANGLE.to_radians().cos() {
                continue;
            }
            if protected.facet(facet(k)) && protected.facet(facet(l)) {
                edges.push([quad[k], quad[l]]);
            }
            let mut rest = (0..4).filter(|&i| i != k && i != l).map(|i| quad[i]);
            let (Some(x), Some(y)) = (rest.next(), rest.next()) else {
                continue;
            };
            if !protected.edge(x, y) {
                wide.push((cosine, [x, y]));
            }
        }
    }
    wide.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (_, e) in wide {
        if !edges.contains(&e) {
            edges.push(e);
        }
    }
    edges
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
    let ratio = |q: &[u32; 4]| radius_edge(q.map(|v| mesh.point(v)));
    let worst = old.iter().map(ratio).fold(0.0, f64::max);
    let gain = Bound {
        ratio: bound.ratio.max(worst / GAIN),
        exempt: Exempt::None,
        ..bound
    };
    if !new.iter().all(|&q| mesh.positive(q)) || !gain.improved(mesh, &old, &new) {
        mesh.pop_point();
        return Ok(None);
    }
    mesh.replace(&shell, &new).map(Some)
}

/// The facet of the positive tetrahedron `q` opposite its vertex `x`, ordered so that it and
/// `x` (or any point on `x`'s side) are positive.
pub(super) fn opposite_facet(q: &[u32; 4], x: u32) -> [u32; 3] {
    let k = q.iter().position(|&v| v == x).unwrap_or(0);
    FACE[k].map(|i| q[i])
}

/// A facet of a star with what the shape of its tetrahedron with a free point `p` needs, the
/// corners taken from an origin near `p` (the ascent's start) so that the sums below lose
/// nothing to large coordinates.
struct Facet {
    /// `(b - a) x (c - a)`: six times the volume is `normal . (p - a)`.
    normal: Point,
    /// `normal . a`.
    offset: f64,
    /// `a + b + c`.
    corners: Point,
    /// `|a|^2 + |b|^2 + |c|^2` and the squared lengths of the facet's edges: the sum of the
    /// tetrahedron's squared edge lengths is this plus `3 |p|^2 - 2 p . corners`.
    squares: f64,
}

impl Facet {
    fn new(f: &[Point; 3], origin: &Point) -> Facet {
        let [a, b, c] = f.map(|x| sub(&x, origin));
        let normal = cross(&sub(&b, &a), &sub(&c, &a));
        let square = |x: &Point| dot(x, x);
        let edges = square(&sub(&b, &a)) + square(&sub(&c, &b)) + square(&sub(&a, &c));
        Facet {
            normal,
            offset: dot(&normal, &a),
            corners: add(&add(&a, &b), &c),
            squares: square(&a) + square(&b) + square(&c) + edges,
        }
    }

    /// The signed volume of the tetrahedron with `p` and the sum of its squared edge lengths.
    fn volume_and_edges(&self, p: &Point) -> (f64, f64) {
        let volume = (dot(&self.normal, p) - self.offset) / 6.0;
        (
            volume,
            3.0 * dot(p, p) - 2.0 * dot(p, &self.corners) + self.squares,
        )
    }

    /// The shape of `flips::shape`, signed by the tetrahedron's orientation.
    fn shape(&self, p: &Point) -> f64 {
        let (volume, sum) = self.volume_and_edges(p);
        volume / (sum * sum.sqrt())
    }

    /// The gradient of [`Facet::shape`] in `p`: the volume grows along the normal, the sum
    /// of squared edges along `p`'s offset from the corners.
    fn gradient(&self, p: &Point) -> Point {
        let (volume, sum) = self.volume_and_edges(p);
        let (s15, s25) = (sum * sum.sqrt(), sum * sum * sum.sqrt());
        std::array::from_fn(|k| {
            let offset = 2.0 * (3.0 * p[k] - self.corners[k]);
            self.normal[k] / 6.0 / s15 - 1.5 * volume * offset / s25
        })
    }
}

/// The worst shape of the tetrahedra of `facets` completed by `p`, and which one it is
/// (negative where one is inverted).
fn worst(facets: &[Facet], p: &Point) -> (f64, usize) {
    facets
        .iter()
        .enumerate()
        .map(|(k, f)| (f.shape(p), k))
        .fold((f64::INFINITY, 0), |w, x| if x.0 < w.0 { x } else { w })
}

/// Where the point completing every facet of `faces` gives the best worst shape, from
/// `start`: steps along the gradient of the worst tetrahedron's shape, or where that gains
/// nothing (another tetrahedron gets worse at once) along the sum of the unit gradients of
/// the tetrahedra within [`NEAR_WORST`] of the worst; a step is kept where it raises the worst
/// shape, halved until one does (down to [`SHORTEST_STEP`] of `length`, the first step's
/// tenfold) and doubled after one did.
pub(super) fn place(faces: &[[Point; 3]], start: Point, length: f64) -> Point {
    let facets: Vec<Facet> = faces.iter().map(|f| Facet::new(f, &start)).collect();
    let mut p = [0.0; 3];
    let (mut best, mut k) = worst(&facets, &p);
    let mut step = 0.1 * length;
    // The worst tetrahedron's gradient, or the sum of the nearly worst ones' unit gradients.
    let along = |nearly: bool, p: &Point, best: f64, k: usize| {
        if !nearly {
            return facets[k].gradient(p);
        }
        let near = facets.iter().filter(|f| f.shape(p) <= best * NEAR_WORST);
        near.filter_map(|f| unit(&f.gradient(p)))
            .fold([0.0; 3], |sum, g| add(&sum, &g))
    };
    for _ in 0..ASCENT_STEPS {
        let mut moved = false;
        for nearly in [false, true] {
            let Some(direction) = unit(&along(nearly, &p, best, k)) else {
                continue;
            };
            while step >= SHORTEST_STEP * length {
                let q = add(&p, &direction.map(|x| x * step));
                let (w, wk) = worst(&facets, &q);
                if w > best {
                    (p, best, k, moved) = (q, w, wk, true);
                    break;
                }
                step *= 0.5;
            }
            if moved {
                break;
            }
            step = 0.1 * length;
        }
        if !moved {
            break;
        }
        step *= 2.0;
    }
    add(&start, &p)
}

/// `v` over its length, where that is finite and not zero.
fn unit(v: &Point) -> Option<Point> {
    let n = norm(v);
    (n > 0.0 && n.is_finite()).then(|| v.map(|x| x / n))
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
            .map(|(f, p)| Facet::new(f, p).shape(&[0.0; 3]))
            .fold(f64::INFINITY, f64::min)
    }

    /// A roof over a ridge `ab` (vertices 0 and 1), its far corners `c` and `d` (2 and 3)
    /// 0.02 lower, over three points: the Delaunay tetrahedron of the four corners (its
    /// circumcenter some 75 above) lies flat under the roof, radius-edge ratio 37.5. With the
    /// input triangles `protect`, [`split_wedges`] of every tetrahedron splits it by a point
    /// below the roof: the flat tetrahedron goes, the triangles stay, every tetrahedron is
    /// positive and the worst shape rises.
    fn split_under_roof(protect: &[[u32; 3]]) {
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
        let flat = |mesh: &TetMesh| {
            mesh.tets.live().any(|t| {
                let mut q = mesh.tets.vertices(t);
                q.sort_unstable();
                q == [0, 1, 2, 3]
            })
        };
        assert!(
            flat(&mesh),
            "the Delaunay tetrahedralization has no flat tetrahedron"
        );
        let mut protected = Protected::default();
        for &f in protect {
            protected.insert_facet(f);
        }
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
        assert!(!flat(&mesh), "the flat tetrahedron is still there");
        mesh.validate().unwrap();
        assert!(protect.iter().all(|&f| mesh.find_face(f).is_some()));
        assert_eq!(mesh.points.len(), n + 1);
        assert!(
            mesh.point(n as u32)[2] < -0.02,
            "the point is not below the roof"
        );
        assert!(worst_shape(&mesh) > before);
    }

    /// Both roof triangles are input triangles: the flat tetrahedron is a wedge, split at its
    /// other diagonal `cd` (this fails with [`EXCESS`] at 100).
    #[test]
    fn a_wedge_under_a_ridge_is_split_below_it() {
        split_under_roof(&[[0, 1, 2], [0, 1, 3]]);
    }

    /// One roof triangle is an input triangle: the flat tetrahedron is split at its widest
    /// edge that is no input edge, `cd`.
    #[test]
    fn a_sliver_on_an_input_triangle_is_split_below_it() {
        split_under_roof(&[[0, 1, 2]]);
    }
}
