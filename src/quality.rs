//! Quality figures of a mesh, as METRICS.md "Quality" defines them (the ones the C tests, the
//! demo and `delmesh_mesh_quality` report).
//!
//! Per tetrahedron: the six dihedral angles, the radius-edge ratio (circumradius / shortest
//! edge) and the radius ratio `3 r_in / r_circ` (1 for the regular tetrahedron, 0 for a flat
//! one). Per boundary facet: its smallest angle. Computed in floating point: these are
//! measurements, not decisions.

use crate::geometry::{cross, dist2, dot, norm, sub, tet_volume};
use crate::mesh::Mesh;

type P = [f64; 3];

/// Dihedral angle thresholds of [`Quality::dihedral_below`], in degrees.
pub const DIHEDRAL_THRESHOLDS: [f64; 3] = [5.0, 10.0, 15.0];

/// Bins of the radius-ratio histogram: bin `k` counts `[k/10, (k+1)/10)`, the last includes 1.
pub const RADIUS_RATIO_BINS: usize = 10;

/// The quality report of a mesh's tetrahedra and boundary facets.
#[derive(Clone, Debug, PartialEq)]
pub struct Quality {
    pub tetrahedra: usize,
    /// Degrees; NaN without tetrahedra.
    pub min_dihedral: f64,
    pub max_dihedral: f64,
    pub max_radius_edge: f64,
    pub min_radius_ratio: f64,
    /// Tetrahedra with a dihedral angle below each of [`DIHEDRAL_THRESHOLDS`].
    pub dihedral_below: [usize; 3],
    pub radius_ratio_histogram: [usize; RADIUS_RATIO_BINS],
    /// Smallest angle of the boundary and interface facets, degrees; NaN without facets.
    pub min_facet_angle: f64,
}

/// The figures of one tetrahedron.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TetQuality {
    pub min_dihedral: f64,
    pub max_dihedral: f64,
    pub radius_edge: f64,
    pub radius_ratio: f64,
}

impl Quality {
    pub fn of(mesh: &Mesh) -> Quality {
        let mut q = Quality {
            tetrahedra: mesh.tetrahedron_count(),
            min_dihedral: f64::NAN,
            max_dihedral: f64::NAN,
            max_radius_edge: f64::NAN,
            min_radius_ratio: f64::NAN,
            dihedral_below: [0; 3],
            radius_ratio_histogram: [0; RADIUS_RATIO_BINS],
            min_facet_angle: f64::NAN,
        };
        for t in mesh.tetrahedra.as_chunks::<4>().0 {
            let tq = tetrahedron(t.map(|v| mesh.vertex(v)));
            q.min_dihedral = q.min_dihedral.min(tq.min_dihedral);
            q.max_dihedral = q.max_dihedral.max(tq.max_dihedral);
            q.max_radius_edge = q.max_radius_edge.max(tq.radius_edge);
            q.min_radius_ratio = q.min_radius_ratio.min(tq.radius_ratio);
            for (k, &bound) in DIHEDRAL_THRESHOLDS.iter().enumerate() {
                q.dihedral_below[k] += usize::from(tq.min_dihedral < bound);
            }
            let bin = (tq.radius_ratio * RADIUS_RATIO_BINS as f64) as usize;
            q.radius_ratio_histogram[bin.min(RADIUS_RATIO_BINS - 1)] += 1;
        }
        for f in mesh.facets.as_chunks::<3>().0 {
            q.min_facet_angle = q
                .min_facet_angle
                .min(triangle_min_angle(f.map(|v| mesh.vertex(v))));
        }
        q
    }
}

/// The outward normals of the four faces of `p` (face `i` opposite vertex `i`), either
/// orientation of `p`.
fn outward_normals(p: &[P; 4]) -> [P; 4] {
    std::array::from_fn(|i| {
        let [a, b, c] = [(i + 1) % 4, (i + 2) % 4, (i + 3) % 4].map(|k| p[k]);
        let v = cross(&sub(&b, &a), &sub(&c, &a));
        if dot(&v, &sub(&p[i], &a)) > 0.0 {
            v.map(|x| -x)
        } else {
            v
        }
    })
}

/// The smallest and largest cosine of the angle between two outward face normals: faces `i`
/// and `j` meet at the edge opposite them, where the dihedral angle is `acos(-cos)` (so the
/// smallest cosine gives the smallest dihedral angle).
fn normal_cosines(n: &[P; 4]) -> (f64, f64) {
    let (mut lo, mut hi) = (1.0f64, -1.0f64);
    for i in 0..4 {
        for j in i + 1..4 {
            let c = dot(&n[i], &n[j]) / (norm(&n[i]) * norm(&n[j]));
            // A flat tetrahedron (NaN) has a zero dihedral angle.
            let c = if c.is_nan() { -1.0 } else { c.clamp(-1.0, 1.0) };
            lo = lo.min(c);
            hi = hi.max(c);
        }
    }
    (lo, hi)
}

/// The smallest dihedral angle of `p`, degrees (one `acos`).
pub fn min_dihedral(p: [P; 4]) -> f64 {
    let (lo, _) = normal_cosines(&outward_normals(&p));
    (-lo).acos().to_degrees()
}

/// Circumradius over shortest edge of the tetrahedron `p`; infinite when it is flat. Squared
/// lengths throughout and one square root (refinement measures every tetrahedron it makes).
pub fn radius_edge(p: [&P; 4]) -> f64 {
    let (u, v, w) = edges_from_first(p);
    ratio_from(circumradius2(u, v, w), u, v, w)
}

/// The radius-edge ratio from the squared circumradius and the edges from the first vertex.
fn ratio_from(circumradius2: f64, u: P, v: P, w: P) -> f64 {
    let shortest2 = [
        dot(&u, &u),
        dot(&v, &v),
        dot(&w, &w),
        dist2(&u, &v),
        dist2(&u, &w),
        dist2(&v, &w),
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min);
    ratio_or_infinite((circumradius2 / shortest2).sqrt())
}

/// The length of the shortest edge of the tetrahedron `p`.
pub fn shortest_edge(p: &[P; 4]) -> f64 {
    (0..4)
        .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
        .map(|(i, j)| norm(&sub(&p[i], &p[j])))
        .fold(f64::INFINITY, f64::min)
}

/// The edges `u`, `v`, `w` from `p[0]` to the other vertices.
fn edges_from_first(p: [&P; 4]) -> (P, P, P) {
    (sub(p[1], p[0]), sub(p[2], p[0]), sub(p[3], p[0]))
}

/// The squared circumradius of the tetrahedron with edges `u`, `v`, `w` from a vertex: the
/// circumcenter's offset from that vertex times `2 det` is `|u|² (v × w) + |v|² (w × u) +
/// |w|² (u × v)` (infinite or NaN when it is flat).
fn circumradius2(u: P, v: P, w: P) -> f64 {
    let (nu, nv, nw) = (dot(&u, &u), dot(&v, &v), dot(&w, &w));
    let (vw, wu, uv) = (cross(&v, &w), cross(&w, &u), cross(&u, &v));
    let det2 = 2.0 * dot(&u, &vw);
    let offset: P = std::array::from_fn(|k| nu * vw[k] + nv * wu[k] + nw * uv[k]);
    dot(&offset, &offset) / (det2 * det2)
}

/// A ratio of lengths, infinite where a flat tetrahedron makes it undefined.
fn ratio_or_infinite(ratio: f64) -> f64 {
    if ratio.is_nan() {
        f64::INFINITY
    } else {
        ratio
    }
}

/// Dihedral angles, radius-edge and radius ratios of the tetrahedron `p` (either orientation).
pub fn tetrahedron(p: [P; 4]) -> TetQuality {
    let n = outward_normals(&p);
    let (lo, hi) = normal_cosines(&n);
    let (min_dihedral, max_dihedral) = ((-lo).acos().to_degrees(), (-hi).acos().to_degrees());
    let corners = [&p[0], &p[1], &p[2], &p[3]];
    let volume = tet_volume(corners).abs();
    let area: f64 = n.iter().map(|v| 0.5 * norm(v)).sum();
    let (u, v, w) = edges_from_first(p.each_ref());
    let circumradius2 = circumradius2(u, v, w);
    let circumradius = circumradius2.sqrt();
    let inradius = 3.0 * volume / area;
    let ratio = 3.0 * inradius / circumradius;
    TetQuality {
        min_dihedral,
        max_dihedral,
        radius_edge: ratio_from(circumradius2, u, v, w),
        radius_ratio: if ratio.is_finite() {
            ratio.clamp(0.0, 1.0)
        } else {
            0.0
        },
    }
}

/// Smallest angle of a triangle, degrees.
pub fn triangle_min_angle(p: [P; 3]) -> f64 {
    (0..3)
        .map(|k| {
            let (u, v) = (sub(&p[(k + 1) % 3], &p[k]), sub(&p[(k + 2) % 3], &p[k]));
            norm(&cross(&u, &v)).atan2(dot(&u, &v)).to_degrees()
        })
        .fold(180.0, f64::min)
}
