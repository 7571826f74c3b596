//! Sliver exudation by vertex pumping (Cheng et al. 2000; thesis §3.6; CGAL's exuder does the
//! same with a time limit).
//!
//! The cells in the complex whose smallest dihedral angle is below the target are taken worst
//! first. For each vertex of such a cell, the weights at which its star changes (its *critical
//! weights*: the power of the vertex with respect to the orthosphere of each tetrahedron just
//! outside its star) are visited in increasing order up to a bound — a fraction of the squared
//! distance to its nearest neighbour, so that its power cell never covers a neighbour — and the
//! weight whose new star has the largest smallest dihedral angle among its cells in the complex
//! is kept, if it beats the current star. Raising a weight only grows the vertex's power cell:
//! the change is the insertion of a heavier copy of the vertex, whose cavity is its star plus
//! the tetrahedra the heavier copy conflicts with (the triangulation changes by flips only).
//!
//! Labels: each new cell takes the label of the old cell on the other side of its cavity
//! boundary facet (so the boundary facets keep both their labels), and the change is refused
//! unless the facets between different labels inside the cavity are the same, with the same
//! labels on the same sides, before and after. So the mesh's boundary and interface facets and
//! the volume of every subdomain do not change. A change is also refused when one of its new
//! cells in the complex would exceed the radius-edge bound that refinement met. The size bound
//! is not kept: it bounds Delaunay circumballs, and a flip that removes a sliver may give a
//! cell a somewhat larger circumball without moving any vertex (as in CGAL).

use std::time::{Duration, Instant};

use super::local::{
    commit_labels, cone_labels, cone_quality, nearest_neighbour2, star_quality, SliverQueue,
};
use crate::criteria::Criteria;
use crate::error::Result;
use crate::geometry::{cross, dot, sub};
use crate::predicates::Point;
use crate::refine::Labeled;
use crate::triangulation::tets::INFINITE;

/// Options of [`exude`].
#[derive(Clone, Copy, Debug)]
pub struct ExudeOptions {
    /// Cells whose smallest dihedral angle is below this (degrees) are treated.
    pub target_dihedral: f64,
    /// Largest weight of a vertex, as a fraction of its squared nearest-neighbour distance
    /// (below 1 the vertex's power cell never covers a neighbour).
    pub max_weight_ratio: f64,
    /// Stop after this long (the result then depends on the machine's speed).
    pub time_limit: Option<Duration>,
}

impl Default for ExudeOptions {
    fn default() -> Self {
        ExudeOptions {
            target_dihedral: 15.0,
            max_weight_ratio: 0.75,
            time_limit: None,
        }
    }
}

/// What a pass did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ExudeReport {
    /// Vertices given a (larger) weight.
    pub pumped: usize,
    /// Slivers examined.
    pub examined: usize,
    /// Whether the time limit stopped the pass.
    pub timed_out: bool,
}

/// Critical weights visited per vertex.
const MAX_PROBES: usize = 24;

/// Exudes the slivers of `m` (see the module documentation).
pub fn exude(m: &mut Labeled, criteria: &Criteria, options: &ExudeOptions) -> Result<ExudeReport> {
    let start = Instant::now();
    m.tri.make_regular();
    let mut report = ExudeReport::default();
    let mut queue = SliverQueue::default();
    let live: Vec<u32> = m.tri.tets().live().collect();
    queue.push_bad(m, &live, options.target_dihedral);
    while let Some(t) = queue.pop(m) {
        if options
            .time_limit
            .is_some_and(|limit| start.elapsed() > limit)
        {
            report.timed_out = true;
            break;
        }
        report.examined += 1;
        let mut best: Option<Pump> = None;
        for v in m.tri.tets().vertices(t) {
            if let Some(p) = best_pump(m, criteria, v, t, options)? {
                if best.is_none_or(|b| p.quality > b.quality) {
                    best = Some(p);
                }
            }
        }
        if let Some(p) = best {
            apply(m, &p)?;
            report.pumped += 1;
            let created = m.tri.created().to_vec();
            queue.push_bad(m, &created, options.target_dihedral);
        }
    }
    Ok(report)
}

/// A weight for a vertex and the smallest dihedral angle of its star with it.
#[derive(Clone, Copy, Debug)]
struct Pump {
    vertex: u32,
    tet: u32,
    weight: f64,
    quality: f64,
}

/// The best weight for vertex `v` (a vertex of `t`) if it improves on its current star.
fn best_pump(
    m: &mut Labeled,
    criteria: &Criteria,
    v: u32,
    t: u32,
    options: &ExudeOptions,
) -> Result<Option<Pump>> {
    if v == INFINITE {
        return Ok(None);
    }
    let star = m.tri.star(v, t);
    if star
        .iter()
        .any(|&s| m.tri.tets().vertices(s).contains(&INFINITE))
    {
        return Ok(None); // a hull vertex: its star is not closed
    }
    let current = star_quality(m, &star);
    let limit = options.max_weight_ratio * nearest_neighbour2(m, v, &star);
    // The star at the current weight, probed just above it, gives the first critical weight.
    let mut weight = m.tri.weight(v).next_up();
    let mut best: Option<Pump> = None;
    for probe in 0..=MAX_PROBES {
        m.tri.find_reweight_conflicts(v, t, weight)?;
        let quality = if probe == 0 {
            None
        } else {
            cone_quality(m, criteria, v)
        };
        let next = next_critical_weight(m, v, weight);
        m.tri.abandon();
        if let Some(q) = quality.filter(|&q| q > current && best.is_none_or(|b| q > b.quality)) {
            best = Some(Pump {
                vertex: v,
                tet: t,
                weight,
                quality: q,
            });
        }
        // Just past the next critical weight, the tetrahedron behind it joins the star.
        match next {
            Some(w) if w + w * 1e-9 < limit => weight = w + w * 1e-9,
            _ => break,
        }
    }
    Ok(best)
}

/// For the pending re-weighting of `v` to `weight`: the smallest critical weight above
/// `weight` among the tetrahedra just outside the cavity (the next one to join the star).
fn next_critical_weight(m: &Labeled, v: u32, weight: f64) -> Option<f64> {
    let p = *m.tri.vertex(v);
    m.tri
        .cavity_boundary()
        .map(|outer| m.tri.tets().vertices(outer >> 2))
        .filter(|verts| !verts.contains(&INFINITE))
        .map(|verts| power_of(m, &p, verts))
        .filter(|&w| w > weight)
        .min_by(f64::total_cmp)
}

/// The power of `p` with respect to the orthosphere of the weighted tetrahedron `v`: the
/// weight at which a point at `p` starts to conflict with it.
fn power_of(m: &Labeled, p: &Point, v: [u32; 4]) -> f64 {
    let x = v.map(|k| *m.tri.vertex(k));
    let w = v.map(|k| m.tri.weight(k));
    let u: [Point; 3] = std::array::from_fn(|i| sub(&x[i + 1], &x[0]));
    let b: [f64; 3] = std::array::from_fn(|i| dot(&u[i], &u[i]) - (w[i + 1] - w[0]));
    let (c12, c20, c01) = (
        cross(&u[1], &u[2]),
        cross(&u[2], &u[0]),
        cross(&u[0], &u[1]),
    );
    let det2 = 2.0 * dot(&u[0], &c12);
    let c: Point = std::array::from_fn(|k| (b[0] * c12[k] + b[1] * c20[k] + b[2] * c01[k]) / det2);
    let radius2 = dot(&c, &c) - w[0];
    let d = sub(&sub(p, &x[0]), &c);
    dot(&d, &d) - radius2
}

/// Applies a pump: the heavier copy replaces the vertex.
fn apply(m: &mut Labeled, p: &Pump) -> Result<()> {
    m.tri.find_reweight_conflicts(p.vertex, p.tet, p.weight)?;
    let labels = cone_labels(m);
    m.tri.commit_reweight(p.vertex)?;
    commit_labels(m, &labels, m.dimension[p.vertex as usize]);
    Ok(())
}
