//! Input checks of a triangulated surface, before any meshing.
//!
//! Boundary recovery (George and Borouchaki, §5) needs a surface that bounds regions: vertices
//! at distinct positions, proper triangles given once, no edge with a single triangle, and
//! triangles that meet only at their shared vertices and edges. [`check_surface`] checks these
//! in that order and reports the first failing check, naming the culprit with the smallest
//! triangle (or vertex) numbers. The recovery runs the last check, [`check_intersections`],
//! only when it needs it, and then often on a few suspect triangles
//! ([`check_intersections_of`]): see `IntersectionCheck` in the module above.
//!
//! Every geometric decision is an exact predicate on input coordinates. Self-intersections are
//! found by testing the pairs of triangles whose bounding boxes overlap (a bounding-volume
//! hierarchy) with an exact test of the contact the two triangles are allowed:
//! - no shared vertex: the closed triangles are disjoint;
//! - one shared vertex `v`: they meet at `v` only;
//! - a shared edge: they meet along it only, i.e. they are not coplanar with their third
//!   vertices on the same side of it.
//!
//! Vertices not used by any triangle are not checked: [`isolated_vertices`] picks those that
//! can be meshed and leaves the others out.

use super::bvh::{Aabb, Bvh};
use super::by_vertex::{vertex_count, ByVertex};
use crate::error::{Error, Result};
use crate::predicates::{lex_cmp, orient2d, orient3d, BoxFilter, Point, Sign};
use crate::triangulation::MAX_COORDINATE;

/// Checks `points` and `triangles` (0-based vertex indices); the error names the offending
/// triangles and vertices.
pub fn check_surface(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> Result<()> {
    check_surface_but_intersections(points, triangles)?;
    check_intersections(points, triangles)
}

/// [`check_surface`] without its last check, [`check_intersections`].
pub fn check_surface_but_intersections(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> Result<()> {
    if triangles.is_empty() {
        return Err(Error::invalid_input("the surface has no triangles"));
    }
    check_indices(points.len(), triangles)?;
    check_coordinates(points, triangles)?;
    check_coincident(points, triangles)?;
    check_degenerate(points, triangles)?;
    check_duplicates(triangles)?;
    check_closed(triangles)
}

/// "triangle k (vertices a, b, c)".
fn describe(k: usize, t: &[u32; 3]) -> String {
    format!("triangle {k} (vertices {}, {}, {})", t[0], t[1], t[2])
}

/// "k (vertices a, b, c)", the second of two triangles named together.
fn describe_short(k: usize, t: &[u32; 3]) -> String {
    format!("{k} (vertices {}, {}, {})", t[0], t[1], t[2])
}

/// Fails on the first triangle with a vertex index not below `n_points`.
fn check_indices(n_points: usize, triangles: &[[u32; 3]]) -> Result<()> {
    for (k, t) in triangles.iter().enumerate() {
        if let Some(&v) = t.iter().find(|&&v| v as usize >= n_points) {
            return Err(Error::invalid_input(format!(
                "{} references vertex {v}, out of range (n_points = {n_points})",
                describe(k, t)
            )));
        }
    }
    Ok(())
}

/// Fails on the first triangle with a vertex whose coordinates are not finite or exceed
/// [`MAX_COORDINATE`] in magnitude.
fn check_coordinates(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> Result<()> {
    let bad = |v: u32| {
        points[v as usize]
            .iter()
            .any(|x| !x.is_finite() || x.abs() > MAX_COORDINATE)
    };
    for (k, t) in triangles.iter().enumerate() {
        if let Some(&v) = t.iter().find(|&&v| bad(v)) {
            return Err(Error::invalid_input(format!(
                "vertex {v} of {} has a non-finite coordinate or one of magnitude above \
                 {MAX_COORDINATE:e}: {:?}",
                describe(k, t),
                points[v as usize]
            )));
        }
    }
    Ok(())
}

/// Fails when two distinct vertices used by triangles have the same coordinates (the pair with
/// the smallest indices is named).
fn check_coincident(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> Result<()> {
    let mut used = vec![false; points.len()];
    for &v in triangles.iter().flatten() {
        used[v as usize] = true;
    }
    // The positions are copied next to their index: the sort reads no other array.
    let mut sorted: Vec<(Point, u32)> = (0..points.len() as u32)
        .filter(|&v| used[v as usize])
        .map(|v| (points[v as usize], v))
        .collect();
    sorted.sort_unstable_by(|(p, i), (q, j)| lex_cmp(p, q).then(i.cmp(j)));
    let pair = sorted
        .windows(2)
        .filter(|w| lex_cmp(&w[0].0, &w[1].0).is_eq())
        .map(|w| (w[0].1, w[1].1))
        .min();
    match pair {
        Some((i, j)) => Err(Error::invalid_input(format!(
            "vertices {i} and {j} are at the same position {:?}",
            points[i as usize]
        ))),
        None => Ok(()),
    }
}

/// The vertices no triangle uses that can be vertices of the mesh (TetGen meshes every node
/// of a `.node` file): finite and within [`MAX_COORDINATE`], at a position no used vertex or
/// smaller such vertex has, and off every closed input triangle (exact tests). The others
/// are left out of the mesh, as junk vertices of a file are. Call after
/// [`check_surface_but_intersections`].
pub fn isolated_vertices(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> Vec<u32> {
    let mut used = vec![false; points.len()];
    for &v in triangles.iter().flatten() {
        used[v as usize] = true;
    }
    let finite = |p: &Point| p.iter().all(|x| x.is_finite() && x.abs() <= MAX_COORDINATE);
    let mut candidates: Vec<u32> = (0..points.len() as u32)
        .filter(|&v| used[v as usize] || finite(&points[v as usize]))
        .collect();
    if candidates.iter().all(|&v| used[v as usize]) {
        return Vec::new();
    }
    // At each position, the used vertex or else the smallest index stays.
    candidates.sort_unstable_by(|&i, &j| {
        lex_cmp(&points[i as usize], &points[j as usize])
            .then(used[j as usize].cmp(&used[i as usize]))
            .then(i.cmp(&j))
    });
    let mut isolated: Vec<u32> = candidates
        .iter()
        .enumerate()
        .filter(|&(k, &v)| {
            !used[v as usize]
                && (k == 0
                    || lex_cmp(&points[candidates[k - 1] as usize], &points[v as usize]).is_ne())
        })
        .map(|(_, &v)| v)
        .collect();
    isolated.sort_unstable();
    let bvh = triangle_hierarchy(points, triangles);
    isolated.retain(|&v| {
        let p = &points[v as usize];
        let mut on_surface = false;
        bvh.for_each_containing(p, |k| {
            let t = corners(points, &triangles[k]);
            on_surface = on_surface
                || orient3d(t[0], t[1], t[2], p) == Sign::Zero
                    && coplanar_segment_meets_triangle(p, p, &t);
        });
        !on_surface
    });
    isolated
}

/// Fails on the first triangle with a repeated vertex or three collinear vertices.
fn check_degenerate(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> Result<()> {
    match triangles
        .iter()
        .position(|t| has_repeated_index(t) || is_degenerate(&corners(points, t)))
    {
        Some(k) => Err(Error::invalid_input(format!(
            "{} is degenerate (zero area)",
            describe(k, &triangles[k])
        ))),
        None => Ok(()),
    }
}

/// Whether a vertex index appears twice in `t`.
fn has_repeated_index(t: &[u32; 3]) -> bool {
    t[0] == t[1] || t[1] == t[2] || t[2] == t[0]
}

/// Whether the three points are collinear: their projections onto the three coordinate planes
/// are all collinear.
pub(super) fn is_degenerate(c: &[&Point; 3]) -> bool {
    (0..3).all(|t| Projection::dropping(t).orient(c[0], c[1], c[2]) == Sign::Zero)
}

/// The coordinates of the vertices of `t`.
fn corners<'a>(points: &'a [[f64; 3]], t: &[u32; 3]) -> [&'a Point; 3] {
    t.map(|v| &points[v as usize])
}

/// Fails when two triangles have the same three vertices, in any order (the pair with the
/// smallest numbers is named).
fn check_duplicates(triangles: &[[u32; 3]]) -> Result<()> {
    // Triangles grouped by smallest vertex, each group sorted by the other two, then number.
    let by_vertex = ByVertex::new(
        vertex_count(triangles),
        triangles.iter().enumerate().map(|(k, t)| {
            let mut key = *t;
            key.sort_unstable();
            (key[0], ((key[1], key[2]), k as u32))
        }),
    );
    let mut pair: Option<(u32, u32)> = None;
    let mut group = Vec::new();
    for a in 0..by_vertex.vertices() {
        group.clear();
        group.extend_from_slice(by_vertex.of(a as u32));
        group.sort_unstable();
        for w in group.windows(2).filter(|w| w[0].0 == w[1].0) {
            let found = (w[0].1, w[1].1);
            pair = Some(pair.map_or(found, |p| p.min(found)));
        }
    }
    match pair {
        Some((i, j)) => {
            let (i, j) = (i as usize, j as usize);
            Err(Error::invalid_input(format!(
                "{} and triangle {} have the same vertices",
                describe(i, &triangles[i]),
                describe_short(j, &triangles[j])
            )))
        }
        None => Ok(()),
    }
}

/// Fails when an edge belongs to a single triangle (the one with the smallest number is named,
/// then the smallest edge).
fn check_closed(triangles: &[[u32; 3]]) -> Result<()> {
    // Edges grouped by smaller end, each group sorted by the other end, then triangle.
    let by_vertex = ByVertex::new(
        vertex_count(triangles),
        triangles.iter().enumerate().flat_map(|(k, t)| {
            [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]
                .map(|(a, b)| (a.min(b), (a.max(b), k as u32)))
        }),
    );
    let mut open: Option<(u32, u32, u32)> = None;
    let mut group = Vec::new();
    for a in 0..by_vertex.vertices() {
        group.clear();
        group.extend_from_slice(by_vertex.of(a as u32));
        group.sort_unstable();
        for (i, &(b, k)) in group.iter().enumerate() {
            let alone =
                (i == 0 || group[i - 1].0 != b) && (i + 1 == group.len() || group[i + 1].0 != b);
            if alone {
                let found = (k, a as u32, b);
                open = Some(open.map_or(found, |o| o.min(found)));
            }
        }
    }
    match open {
        Some((k, a, b)) => Err(Error::invalid_input(format!(
            "edge ({a}, {b}) belongs to {} only: the surface is not closed",
            describe(k as usize, &triangles[k as usize])
        ))),
        None => Ok(()),
    }
}

/// Fails when two triangles meet other than at their shared vertices and edge (the pair with
/// the smallest numbers is named). Only the pairs whose bounding boxes overlap are tested.
pub fn check_intersections(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> Result<()> {
    let mut first: Option<(usize, usize)> = None;
    let o = bounding_filter(points);
    triangle_hierarchy(points, triangles).for_each_overlapping_pair(|i, j| {
        if first.is_none_or(|f| (i, j) < f)
            && improper_contact(&o, points, &triangles[i], &triangles[j])
        {
            first = Some((i, j));
        }
    });
    intersection_error(first, triangles)
}

/// [`check_intersections`] when every pair of triangles that may meet improperly has one
/// among `suspects` (distinct triangle numbers): only those pairs are tested, and the same
/// pair is named. The triangles that are facets of one tetrahedralization, for instance,
/// meet properly: the others are the suspects.
pub fn check_intersections_of(
    points: &[[f64; 3]],
    triangles: &[[u32; 3]],
    suspects: &[usize],
) -> Result<()> {
    let mut suspect = vec![false; triangles.len()];
    for &s in suspects {
        suspect[s] = true;
    }
    let o = bounding_filter(points);
    let bounds = |t: usize| Aabb::of_points(&triangles[t].map(|v| points[v as usize]));
    // Few suspects: their hierarchy is small, and every triangle looks them up in it.
    let hierarchy = Bvh::new(suspects.iter().map(|&s| bounds(s)).collect());
    let mut first: Option<(usize, usize)> = None;
    for (t, &is_suspect) in suspect.iter().enumerate() {
        hierarchy.for_each_overlapping(&bounds(t), |k| {
            let s = suspects[k];
            // Each pair once: a pair of suspects from its larger one.
            let (i, j) = (s.min(t), s.max(t));
            if t == s || is_suspect && t < s || first.is_some_and(|f| f < (i, j)) {
                return;
            }
            if improper_contact(&o, points, &triangles[i], &triangles[j]) {
                first = Some((i, j));
            }
        });
    }
    intersection_error(first, triangles)
}

/// The error naming the intersecting triangles `first`, if any.
fn intersection_error(first: Option<(usize, usize)>, triangles: &[[u32; 3]]) -> Result<()> {
    match first {
        Some((i, j)) => Err(Error::invalid_input(format!(
            "triangles {} and {} intersect",
            describe_short(i, &triangles[i]),
            describe_short(j, &triangles[j])
        ))),
        None => Ok(()),
    }
}

/// The orientation filter of the box of `points` (all finite).
fn bounding_filter(points: &[[f64; 3]]) -> BoxFilter {
    let (lo, hi) = crate::triangulation::bounding_box(points);
    BoxFilter::new(&lo, &hi)
}

/// The bounding-volume hierarchy of the triangles' boxes (item `k` is triangle `k`).
fn triangle_hierarchy(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> Bvh {
    Bvh::new(
        triangles
            .iter()
            .map(|t| Aabb::of_points(&t.map(|v| points[v as usize])))
            .collect(),
    )
}

/// Whether triangles `s` and `t` (proper, distinct, with vertices at distinct positions when
/// their indices differ) meet other than at their shared vertices and edge.
fn improper_contact(o: &BoxFilter, points: &[[f64; 3]], s: &[u32; 3], t: &[u32; 3]) -> bool {
    match s.iter().filter(|v| t.contains(v)).count() {
        0 => closed_triangles_meet(o, &corners(points, s), &corners(points, t)),
        1 => {
            // Rotate both so that the shared vertex comes first.
            let s = rotate_to_front(s, |v| t.contains(&v));
            let t = rotate_to_front(t, |v| v == s[0]);
            let (s, t) = (corners(points, &s), corners(points, &t));
            meet_beyond_vertex(o, s[0], [s[1], s[2]], [t[1], t[2]])
        }
        2 => {
            // Rotate both so that the vertex off the shared edge comes first.
            let s = rotate_to_front(s, |v| !t.contains(&v));
            let t = rotate_to_front(t, |v| !s.contains(&v));
            let (s, t) = (corners(points, &s), corners(points, &t));
            overlap_across_edge(o, [s[1], s[2]], s[0], t[0])
        }
        _ => false,
    }
}

/// `t` rotated (orientation kept) so that its first vertex satisfying `first` comes first.
fn rotate_to_front(t: &[u32; 3], first: impl Fn(u32) -> bool) -> [u32; 3] {
    let i = t.iter().position(|&v| first(v)).unwrap_or(0);
    [t[i], t[(i + 1) % 3], t[(i + 2) % 3]]
}

/// Whether the sides (strict signs) are all positive or all negative.
fn strictly_one_side(sides: &[Sign]) -> bool {
    sides.iter().all(|&s| s == Sign::Positive) || sides.iter().all(|&s| s == Sign::Negative)
}

/// Whether the closed triangles `s` and `t` (proper) share a point.
///
/// When they are not coplanar, `s ∩ t` lies on the line where their planes meet, on which each
/// triangle is a segment whose ends are on its edges; two such segments that overlap do so at
/// an end of one of them, so the triangles meet exactly when an edge of one meets the other.
fn closed_triangles_meet(o: &BoxFilter, s: &[&Point; 3], t: &[&Point; 3]) -> bool {
    let t_sides = t.map(|p| o.orient3d(s[0], s[1], s[2], p));
    if strictly_one_side(&t_sides) {
        return false;
    }
    if t_sides.iter().all(|&side| side == Sign::Zero) {
        return coplanar_triangles_meet(s, t);
    }
    let s_sides = s.map(|p| o.orient3d(t[0], t[1], t[2], p));
    if strictly_one_side(&s_sides) {
        return false;
    }
    let edge_meets = |a: &[&Point; 3], sides: &[Sign; 3], b: &[&Point; 3]| {
        (0..3).any(|i| {
            let j = (i + 1) % 3;
            segment_meets_triangle(o, [a[i], a[j]], [sides[i], sides[j]], b)
        })
    };
    edge_meets(t, &t_sides, s) || edge_meets(s, &s_sides, t)
}

/// Whether the closed segment `seg` meets the closed triangle `t` (proper), given the sides
/// of the segment's ends relative to the plane of `t`.
fn segment_meets_triangle(
    o: &BoxFilter,
    seg: [&Point; 2],
    sides: [Sign; 2],
    t: &[&Point; 3],
) -> bool {
    let [d, e] = seg;
    if sides[0] == sides[1] {
        return sides[0] == Sign::Zero && coplanar_segment_meets_triangle(d, e, t);
    }
    // The segment meets the plane at one point, in `t` exactly when the line through `d` and
    // `e` passes on the same side of the three (cyclically oriented) edges, or on one of them.
    // It cannot be on all three lines, which have no common point.
    let turns = [(0, 1), (1, 2), (2, 0)].map(|(i, j)| o.orient3d(d, e, t[i], t[j]));
    !(turns.contains(&Sign::Positive) && turns.contains(&Sign::Negative))
}

/// Whether the closed triangles `s` and `t`, in one plane, share a point: they do unless the
/// line of an edge of one leaves the other strictly on its outer side (two disjoint convex
/// polygons are separated by the line of one of their edges).
fn coplanar_triangles_meet(s: &[&Point; 3], t: &[&Point; 3]) -> bool {
    let plane = Projection::of(s);
    !(plane.edge_separates(s, t) || plane.edge_separates(t, s))
}

/// Whether the closed segment `d e` and the closed triangle `t`, in one plane, share a point:
/// they do unless the line of an edge of `t` leaves both ends strictly outside, or the line of
/// the segment leaves `t` strictly on one side.
fn coplanar_segment_meets_triangle(d: &Point, e: &Point, t: &[&Point; 3]) -> bool {
    let plane = Projection::of(t);
    let sides = t.map(|p| plane.orient(d, e, p));
    !(plane.edge_separates(t, &[d, e]) || strictly_one_side(&sides))
}

/// Whether triangles `v a b` and `v p q` (proper, sharing only the vertex `v`) meet anywhere
/// else.
///
/// When they are not coplanar, `s ∩ t` is a segment from `v` on the line where the planes
/// meet, longer than a point exactly when the edge opposite `v` of one triangle meets the other.
/// When they are coplanar, they meet beyond `v` exactly when their angles at `v` overlap.
fn meet_beyond_vertex(o: &BoxFilter, v: &Point, [a, b]: [&Point; 2], [p, q]: [&Point; 2]) -> bool {
    let pq_sides = [o.orient3d(v, a, b, p), o.orient3d(v, a, b, q)];
    if strictly_one_side(&pq_sides) {
        return false;
    }
    if pq_sides == [Sign::Zero; 2] {
        return angles_overlap(v, [a, b], [p, q]);
    }
    let ab_sides = [o.orient3d(v, p, q, a), o.orient3d(v, p, q, b)];
    if strictly_one_side(&ab_sides) {
        return false;
    }
    segment_meets_triangle(o, [a, b], ab_sides, &[v, p, q])
        || segment_meets_triangle(o, [p, q], pq_sides, &[v, a, b])
}

/// Whether the angles `a v b` and `p v q`, in one plane, share more than their apex `v`.
///
/// Two angles below 180° that share only their apex are separated by a line through `v`;
/// turning that line about `v` until it meets a side of either angle gives a separating line
/// along a side of one of them. The other angle then lies strictly beyond that line, except
/// for a side of it that may lie along the opposite ray.
fn angles_overlap(v: &Point, [a, b]: [&Point; 2], [p, q]: [&Point; 2]) -> bool {
    let plane = Projection::of(&[v, a, b]);
    let side_separates = |r: &Point, own: &Point, others: [&Point; 2]| {
        let inner = plane.orient(v, r, own);
        others.iter().all(|x| match plane.orient(v, r, x) {
            Sign::Zero => on_opposite_rays(v, r, x),
            side => side == inner.negate(),
        })
    };
    !(side_separates(a, b, [p, q])
        || side_separates(b, a, [p, q])
        || side_separates(p, q, [a, b])
        || side_separates(q, p, [a, b]))
}

/// For `r` and `x` on a line through `v` and distinct from it: whether `v` lies between them.
/// Decided by comparing coordinates along an axis where `r` and `v` differ.
fn on_opposite_rays(v: &Point, r: &Point, x: &Point) -> bool {
    (0..3)
        .find(|&k| r[k] != v[k])
        .is_some_and(|k| (r[k] > v[k]) != (x[k] > v[k]))
}

/// Whether triangles `u w a` and `u w p` (proper, sharing the edge `u w`) overlap: they are
/// coplanar with `a` and `p` on the same side of the edge.
fn overlap_across_edge(o: &BoxFilter, [u, w]: [&Point; 2], a: &Point, p: &Point) -> bool {
    if o.orient3d(u, w, a, p) != Sign::Zero {
        return false;
    }
    let plane = Projection::of(&[u, w, a]);
    plane.orient(u, w, a) == plane.orient(u, w, p)
}

/// A coordinate plane onto which a plane projects one to one: the two kept axes.
#[derive(Clone, Copy, Debug)]
pub(super) struct Projection {
    axes: [usize; 2],
}

impl Projection {
    /// The projection along axis `t` (`t` in `0..3`).
    fn dropping(t: usize) -> Projection {
        Projection {
            axes: [(t + 1) % 3, (t + 2) % 3],
        }
    }

    /// A projection onto which the triangle `c` (proper) projects to a proper triangle,
    /// preferring to drop the axis along which its (floating-point) normal is largest; the
    /// choice is checked exactly.
    pub(super) fn of(c: &[&Point; 3]) -> Projection {
        let ab = [0, 1, 2].map(|k| c[1][k] - c[0][k]);
        let ac = [0, 1, 2].map(|k| c[2][k] - c[0][k]);
        let normal = [0, 1, 2].map(|t| {
            let (u, v) = ((t + 1) % 3, (t + 2) % 3);
            (ab[u] * ac[v] - ab[v] * ac[u]).abs()
        });
        let mut order = [0, 1, 2];
        order.sort_by(|&i, &j| normal[j].total_cmp(&normal[i]).then(i.cmp(&j)));
        let candidates = order.map(Projection::dropping);
        candidates
            .into_iter()
            .find(|plane| plane.orient(c[0], c[1], c[2]) != Sign::Zero)
            .unwrap_or(candidates[0])
    }

    /// The exact orientation of the projections of `a, b, c`.
    pub(super) fn orient(&self, a: &Point, b: &Point, c: &Point) -> Sign {
        let [u, v] = self.axes;
        orient2d(&[a[u], a[v]], &[b[u], b[v]], &[c[u], c[v]])
    }

    /// Whether the line of an edge of the triangle `t` (proper in this projection) leaves all
    /// of `others` strictly on the side away from `t`.
    fn edge_separates(&self, t: &[&Point; 3], others: &[&Point]) -> bool {
        (0..3).any(|i| {
            let (a, b, c) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
            let outer = self.orient(a, b, c).negate();
            others.iter().all(|x| self.orient(a, b, x) == outer)
        })
    }
}
