//! Planar triangulation (DESIGN.md layer 6, "2D"): Delaunay triangulations of points, and
//! conforming Delaunay triangulations of planar straight-line graphs by Pébay's a-priori
//! subdivision of the constraints (P. Pébay, INRIA RR-3492, 1998, in
//! `papers/pebay-1998-delaunay-admissible-constraint-2d.txt`).
//!
//! What implements which part of the paper:
//! - [`classify`]: §2 — the classification `Θ₂` of an edge (Definition 2.2) and strong
//!   Delaunay-admissibility, membership in the Delaunay *cover* (Definition 2.3, Theorem 2.1),
//!   exact, with no general-position assumption;
//! - [`subdivide`]: §3 — Algorithm 3.2 (`projection`, `nettoyage` at closed nodes, open and
//!   closed nodes of Definition 3.1, edges by decreasing count of points in their small disk,
//!   a bucket grid for the small-disk queries of §3.3), with a better `nettoyage` distance than
//!   the paper's `d_i / 2`; Algorithm 3.1 as an option;
//! - [`cover`]: §2 — the cells of the Delaunay cover (Definition 2.3) of a result: its
//!   triangles grouped across edges whose four points are cocircular;
//! - [`delaunay`]: the Delaunay triangulation itself (§1.2), Bowyer–Watson with a walk, ties
//!   broken by a symbolic perturbation so that the output is a function of the point set;
//! - [`refine`]: quality triangulation of the domain (Ruppert's Delaunay refinement with
//!   Shewchuk's concentric shells and Üngör's off-centers) on top of the conforming one, every
//!   sub-segment kept strongly Delaunay-admissible ([`quality_2d`]);
//! - [`input`]: checks of the points and segments, and [`crossing`]: crossing segments split
//!   at their intersection points, on request;
//! - [`read`]: Triangle `.node` / `.poly` and CGAL `.edg` readers.
//!
//! Invariants of a result (checked by [`validate_mesh`]): every triangle counter-clockwise
//! (exact `orient2d > 0`) with vertex indices in range; input points first, in input order,
//! then the intersection points of split crossing segments, then the other added points;
//! every constraint sub-edge `Mesh::edges` is an edge of a triangle and strongly
//! Delaunay-admissible relative to all vertices (the property tests check it again,
//! independently).

pub mod classify;
pub mod cloud;
pub mod cover;
pub mod crossing;
pub mod delaunay;
pub mod exact;
pub mod input;
pub mod read;
pub mod refine;
pub mod subdivide;

use crate::error::{Error, Result};
use crate::mesh::{Mesh, DIMENSION_UNKNOWN};
use crate::predicates::{orient2d, Sign};
use cloud::Cloud;
use delaunay::{first_duplicates, Delaunay2d};
pub use input::Crossings;
use refine::{QualityOptions, RefinementReport, Refiner};
use subdivide::{Algorithm, Subdivision, SubdivisionReport};

/// Vertex dimension of an input point at a segment end (a corner), and of an intersection
/// point of split crossing segments.
pub const DIMENSION_CORNER: i8 = 0;
/// Vertex dimension of a point added on a segment.
pub const DIMENSION_SEGMENT: i8 = 1;
/// Vertex dimension of an input point on no segment.
pub const DIMENSION_PLANE: i8 = 2;

/// Points added by the subdivision at most, per input point and segment (a guard against
/// runaway subdivision of pathological inputs; never reached by the paper's examples).
const ADDED_POINTS_PER_ITEM: usize = 1 << 12;

/// Pébay's triangle *degradation* `α h / r` (§4: `h` the longest edge, `r` the inradius,
/// `α = √3 / 6` so that the equilateral triangle scores 1) over a triangulation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Degradation {
    pub best: f64,
    pub worst: f64,
    pub mean: f64,
}

/// The outcome of [`conforming_2d`].
#[derive(Clone, Debug)]
pub struct Conforming2d {
    pub mesh: Mesh,
    /// Points added (`mesh` vertices past the input points): the intersection points, then
    /// the points added on the segments.
    pub inserted: usize,
    /// Intersection points of crossing segments (with [`Crossings::Split`]).
    pub intersections: usize,
    pub subdivision: SubdivisionReport,
    pub degradation: Degradation,
}

/// The Delaunay triangulation of the points `xy` (x y interleaved): all finite triangles of
/// the triangulation of their convex hull, counter-clockwise, label 1. Output vertex `i` is
/// input point `i` (z = 0); duplicates are merged onto their first occurrence.
pub fn delaunay_2d(xy: &[f64]) -> Result<Mesh> {
    let points = input::point_slice(xy)?;
    let dt = Delaunay2d::new(points)?;
    let dims = vec![DIMENSION_UNKNOWN; points.len()];
    Ok(mesh_of(points, &dt, dims, Vec::new()))
}

/// Pébay's conforming Delaunay triangulation of the points `xy` and the segments `segments`
/// (pairs of point indices): the segments are subdivided a priori (Algorithm 3.2) until every
/// sub-segment is strongly Delaunay-admissible, then the augmented point set is triangulated.
/// `Mesh::edges` lists the sub-segments, by input segment and along it.
pub fn conforming_2d(xy: &[f64], segments: &[u32]) -> Result<Conforming2d> {
    conforming_2d_with(xy, segments, &ConformingOptions::default())
}

/// The choices of [`conforming_2d_with`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ConformingOptions {
    /// Pébay's algorithm: 3.2 by default, 3.1 as an option.
    pub algorithm: Algorithm,
    /// Crossing segments: an error by default, or split at their intersection points.
    pub crossings: Crossings,
}

/// [`conforming_2d`] with the choice of Pébay's algorithm and of what crossing segments do.
pub fn conforming_2d_with(
    xy: &[f64],
    segments: &[u32],
    options: &ConformingOptions,
) -> Result<Conforming2d> {
    let points = input::points(xy)?;
    let c = conform(points, segments, options)?;
    let dt = Delaunay2d::new(&c.all)?;
    let edges = ordered_sub_edges(&c.sub, &c.segs, &c.all, dt.duplicate_of());
    let mesh = mesh_of(&c.all, &dt, c.dims, edges);
    validate_mesh(&mesh).map_err(|m| Error::internal(format!("conforming 2D result: {m}")))?;
    Ok(Conforming2d {
        inserted: c.all.len() - c.n_input,
        intersections: c.intersections,
        degradation: degradation(&mesh),
        subdivision: c.sub.report,
        mesh,
    })
}

/// Pébay's subdivision of the segments of checked input points.
struct Conformed {
    n_input: usize,
    intersections: usize,
    /// Input points then added points.
    all: Vec<[f64; 2]>,
    /// Kept segments (duplicates merged), by input segment and along it.
    segs: Vec<[u32; 2]>,
    dims: Vec<i8>,
    sub: Subdivision,
}

fn conform(
    points: Vec<[f64; 2]>,
    segments: &[u32],
    options: &ConformingOptions,
) -> Result<Conformed> {
    let first = first_duplicates(&points);
    let mut cloud = cloud_of(&points, &first, segments.len() / 2);
    let input::Segments {
        segs,
        intersections,
        ..
    } = input::segments(segments, &points, &first, &mut cloud, options.crossings)?;
    let limit = ADDED_POINTS_PER_ITEM.saturating_mul(points.len() + segs.len());
    let mut sub = Subdivision::new(cloud, &segs, limit, options.algorithm);
    sub.run()?;
    let all = sub.cloud.points.clone();
    let mut dims = vec![DIMENSION_PLANE; all.len()];
    dims[points.len() + intersections..].fill(DIMENSION_SEGMENT);
    for s in &segs {
        dims[s[0] as usize] = DIMENSION_CORNER;
        dims[s[1] as usize] = DIMENSION_CORNER;
    }
    Ok(Conformed {
        n_input: points.len(),
        intersections,
        all,
        segs,
        dims,
        sub,
    })
}

/// The outcome of [`quality_2d`].
#[derive(Clone, Debug)]
pub struct Quality2d {
    /// Triangles of the domain only, labeled by region; `edges` the sub-segments.
    pub mesh: Mesh,
    /// Intersection points of crossing segments (with [`Crossings::Split`]).
    pub intersections: usize,
    /// Points added on the segments before refinement (the first phase of [`refine`]).
    pub conforming_points: usize,
    pub refinement: RefinementReport,
}

/// Quality triangulation of the planar straight-line graph `xy`, `segments` (phases in
/// [`refine`]): the segments split until they are Delaunay edges, then Delaunay refinement of
/// the domain: the triangles not reachable from the outside or from a hole seed without
/// crossing a segment. With no segment, the convex hull of the points bounds the domain (its
/// edges become segments). Input points outside the domain are in no triangle and constrain
/// nothing. Every sub-segment is in every Delaunay triangulation of the mesh's vertices.
pub fn quality_2d(xy: &[f64], segments: &[u32], options: &QualityOptions) -> Result<Quality2d> {
    options.check()?;
    let mut points = input::points(xy)?;
    let hull;
    let segments = if segments.is_empty() {
        hull = hull_segments(&points)?;
        &hull[..]
    } else {
        segments
    };
    let n_caller = points.len();
    let mut first = first_duplicates(&points);
    let mut checked = cloud_of(&points, &first, segments.len() / 2);
    let input::Segments {
        segs,
        intersections,
        ..
    } = input::segments(segments, &points, &first, &mut checked, options.crossings)?;
    // The intersection points of split segments count as input points from here on.
    points.extend_from_slice(&checked.points[n_caller..]);
    first.extend(n_caller as u32..points.len() as u32);
    let n_input = points.len();
    // Ruppert's first phase on the segment points only; the other input points are inserted
    // afterwards without crossing a segment, so that points outside the domain split nothing.
    let mut on_any = vec![false; n_input];
    for s in &segs {
        on_any[s[0] as usize] = true;
        on_any[s[1] as usize] = true;
    }
    // The grid of the checks indexes the points that are their own first copy; when those
    // are all on segments, it is the grid this phase needs.
    let mut cloud = if (0..n_input).all(|i| on_any[i] || first[i] as usize != i) {
        checked
    } else {
        grid_of(&points, segs.len(), |i| on_any[i])
    };
    let limit = ADDED_POINTS_PER_ITEM.saturating_mul(n_input + segs.len());
    let acute = refine::acute_apices(&points, &segs);
    let (subs, added_on) = refine::split_segments(&mut cloud, &segs, &acute, limit)?;
    let all = cloud.into_points();
    let n_all = all.len();
    let dt = Delaunay2d::of_subset(&all, |i| i as usize >= n_input || on_any[i as usize]).map_err(
        |e| {
            Error::invalid_input(format!(
                "the segments enclose no region (their points: {})",
                e.message
            ))
        },
    )?;
    let compact = dt.compact();
    drop(dt);
    let mut duplicate_of = first.clone();
    duplicate_of.extend((n_input as u32)..(n_all as u32));
    let mut on_segment = vec![u32::MAX; n_input];
    on_segment.extend(added_on);
    let sub_edges: Vec<[u32; 2]> = subs.iter().map(|s| [s[0], s[1]]).collect();
    let mut dims = vec![DIMENSION_PLANE; n_all];
    for s in &segs {
        dims[s[0] as usize] = DIMENSION_CORNER;
        dims[s[1] as usize] = DIMENSION_CORNER;
    }
    dims[n_input..].fill(DIMENSION_SEGMENT);
    let corners = enclosing_box(&all);
    let mut r = Refiner::new(all, compact, segs, acute, on_segment, &sub_edges)?;
    // Four far corners enclose everything, so that no point added on a segment is ever on the
    // convex hull (rounding would make the hull concave there).
    for corner in corners {
        r.insert_outside(corner)?;
    }
    // The other input points: those outside the domain are left out (in no triangle, they
    // constrain nothing).
    r.assign_regions(options);
    let free: Vec<u32> = (0..n_input as u32)
        .filter(|&i| !on_any[i as usize] && first[i as usize] == i)
        .collect();
    r.insert_if_inside(&free)?;
    r.run(options)?;
    // In the output numbering the box corners (n_all..n_all + 4) are left out.
    let renumber = |v: u32| if v as usize >= n_all { v - 4 } else { v };
    for (i, &d) in duplicate_of.iter().enumerate() {
        if d as usize != i {
            dims[i] = DIMENSION_UNKNOWN;
        }
    }
    let points: Vec<[f64; 2]> = r.points[..n_all]
        .iter()
        .chain(&r.points[n_all + 4..])
        .copied()
        .collect();
    for v in n_all + 4..r.points.len() {
        dims.push(if r.on_segment[v] == u32::MAX {
            DIMENSION_PLANE
        } else {
            DIMENSION_SEGMENT
        });
    }
    let (triangles, triangle_labels) = r.domain_triangles();
    let triangles: Vec<u32> = triangles.into_iter().map(renumber).collect();
    let subs: Vec<(u32, u32, u32)> = r
        .sub_segments()
        .into_iter()
        .map(|(a, b, s)| (renumber(a), renumber(b), s))
        .collect();
    let edges = ordered_segments(&subs, &r.segments, &points);
    let mut full_duplicate_of = duplicate_of;
    full_duplicate_of.extend((n_all as u32)..(points.len() as u32));
    let mesh = Mesh {
        vertices: points.iter().flat_map(|p| [p[0], p[1], 0.0]).collect(),
        vertex_dimensions: dims,
        triangles,
        triangle_labels,
        edges,
        duplicate_of: full_duplicate_of,
        ..Mesh::default()
    };
    validate_triangles(&mesh).map_err(|m| Error::internal(format!("quality 2D result: {m}")))?;
    Ok(Quality2d {
        intersections,
        conforming_points: n_all - n_input,
        refinement: r.report,
        mesh,
    })
}

/// The corners of a square 64 times as wide as the bounding box of `points`, around it.
fn enclosing_box(points: &[[f64; 2]]) -> [[f64; 2]; 4] {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let c = [(lo[0] + hi[0]) * 0.5, (lo[1] + hi[1]) * 0.5];
    let side = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let r = 32.0 * if side > 0.0 { side } else { 1.0 };
    [
        [c[0] - r, c[1] - r],
        [c[0] + r, c[1] - r],
        [c[0] + r, c[1] + r],
        [c[0] - r, c[1] + r],
    ]
}

/// The edges of the convex hull of `points`, as segments (index pairs).
fn hull_segments(points: &[[f64; 2]]) -> Result<Vec<u32>> {
    let dt = Delaunay2d::new(points)?;
    let (tri, _) = dt.compact();
    let mut out = Vec::new();
    for v in tri {
        if let Some(k) = v.iter().position(|&x| x == delaunay::INFINITE) {
            out.extend([v[(k + 1) % 3], v[(k + 2) % 3]]);
        }
    }
    Ok(out)
}

/// Sub-segments `(a, b, segment)` ordered by input segment and along it from its first end,
/// oriented that way (the segments `segs` of one input segment are consecutive, in order
/// along it, so that the order of the input segments is that of `segs`: the sub-segments are
/// grouped by segment with a counting sort, then sorted along it within a group).
fn ordered_segments(subs: &[(u32, u32, u32)], segs: &[[u32; 2]], points: &[[f64; 2]]) -> Vec<u32> {
    let mut start = vec![0usize; segs.len() + 1];
    for &(_, _, s) in subs {
        start[s as usize + 1] += 1;
    }
    for k in 1..start.len() {
        start[k] += start[k - 1];
    }
    let mut keyed = vec![(0.0, 0u32, 0u32); subs.len()];
    let mut next = start.clone();
    for &(a, b, s) in subs {
        let [p, q] = segs[s as usize].map(|i| points[i as usize]);
        let along = |i: u32| {
            let x = points[i as usize];
            (x[0] - p[0]) * (q[0] - p[0]) + (x[1] - p[1]) * (q[1] - p[1])
        };
        let (a, b) = if along(a) <= along(b) { (a, b) } else { (b, a) };
        keyed[next[s as usize]] = (along(a), a, b);
        next[s as usize] += 1;
    }
    for k in 0..segs.len() {
        keyed[start[k]..start[k + 1]].sort_by(|x, y| x.0.total_cmp(&y.0));
    }
    keyed.into_iter().flat_map(|(_, a, b)| [a, b]).collect()
}

/// The grid of the input points, copies of an earlier point left out of the buckets.
fn cloud_of(points: &[[f64; 2]], first: &[u32], n_segments: usize) -> Cloud {
    grid_of(points, n_segments, |i| first[i] as usize == i)
}

/// The grid of the input points, those with `!indexed(i)` left out of the buckets.
fn grid_of(points: &[[f64; 2]], n_segments: usize, indexed: impl Fn(usize) -> bool) -> Cloud {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if points.is_empty() {
        (lo, hi) = ([0.0; 2], [1.0; 2]);
    }
    let mut cloud = Cloud::new(lo, hi, points.len() + n_segments);
    for (i, p) in points.iter().enumerate() {
        if indexed(i) {
            cloud.push(*p);
        } else {
            cloud.push_unindexed(*p);
        }
    }
    cloud
}

/// The live sub-edges, ordered by input segment and along it from its first end, oriented
/// that way; ends mapped through `duplicate_of`.
fn ordered_sub_edges(
    sub: &Subdivision,
    segs: &[[u32; 2]],
    points: &[[f64; 2]],
    duplicate_of: &[u32],
) -> Vec<u32> {
    let subs: Vec<(u32, u32, u32)> = sub.sub_edges().collect();
    let mut edges = ordered_segments(&subs, segs, points);
    for v in &mut edges {
        *v = duplicate_of[*v as usize];
    }
    edges
}

/// The mesh of a 2D triangulation: z = 0, label 1.
fn mesh_of(points: &[[f64; 2]], dt: &Delaunay2d, mut dims: Vec<i8>, edges: Vec<u32>) -> Mesh {
    let duplicate_of = dt.duplicate_of().to_vec();
    for (i, &d) in duplicate_of.iter().enumerate() {
        if d as usize != i {
            dims[i] = DIMENSION_UNKNOWN;
        }
    }
    let triangles = dt.triangles().into_flattened();
    let vertices: Vec<[f64; 3]> = points.iter().map(|p| [p[0], p[1], 0.0]).collect();
    Mesh {
        vertices: vertices.into_flattened(),
        vertex_dimensions: dims,
        triangle_labels: vec![1; triangles.len() / 3],
        triangles,
        edges,
        duplicate_of,
        ..Mesh::default()
    }
}

/// Checks the invariants of a 2D result listed in the module documentation (but
/// admissibility, which the tests check): the error names the first culprit.
pub fn validate_mesh(mesh: &Mesh) -> std::result::Result<(), String> {
    validate_triangles(mesh)?;
    let mut sides = std::collections::HashSet::new();
    for tri in mesh.triangles.chunks_exact(3) {
        for k in 0..3 {
            sides.insert((tri[k].min(tri[(k + 1) % 3]), tri[k].max(tri[(k + 1) % 3])));
        }
    }
    for (e, edge) in mesh.edges.chunks_exact(2).enumerate() {
        if !sides.contains(&(edge[0].min(edge[1]), edge[0].max(edge[1]))) {
            return Err(format!(
                "constraint edge {e} {edge:?} is not a triangle edge"
            ));
        }
    }
    Ok(())
}

/// [`validate_mesh`] but the constraint edges (in quality mode, segments outside the domain
/// are in no triangle).
pub fn validate_triangles(mesh: &Mesh) -> std::result::Result<(), String> {
    mesh.validate()?;
    let p = |i: u32| {
        let v = mesh.vertex(i);
        [v[0], v[1]]
    };
    for (t, tri) in mesh.triangles.chunks_exact(3).enumerate() {
        if orient2d(&p(tri[0]), &p(tri[1]), &p(tri[2])) != Sign::Positive {
            return Err(format!("triangle {t} {tri:?} is not counter-clockwise"));
        }
    }
    Ok(())
}

/// Pébay's degradation `α h / r` of every triangle of `mesh` (see [`Degradation`]).
pub fn degradation(mesh: &Mesh) -> Degradation {
    let alpha = 3f64.sqrt() / 6.0;
    let mut out = Degradation {
        best: f64::INFINITY,
        worst: 0.0,
        mean: 0.0,
    };
    let mut count = 0usize;
    for tri in mesh.triangles.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| mesh.vertex(tri[k]));
        let len = |p: [f64; 3], q: [f64; 3]| (p[0] - q[0]).hypot(p[1] - q[1]);
        let (x, y, z) = (len(a, b), len(b, c), len(c, a));
        let area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs();
        let inradius = 2.0 * area / (x + y + z);
        let d = alpha * x.max(y).max(z) / inradius;
        out.best = out.best.min(d);
        out.worst = out.worst.max(d);
        out.mean += d;
        count += 1;
    }
    if count == 0 {
        return Degradation::default();
    }
    out.mean /= count as f64;
    out
}
