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

use crate::criteria::{circumcenter, Criteria};
use crate::error::Result;
use crate::predicates::Point;
use crate::quality::min_dihedral as dihedral;
use crate::refine::Labeled;
use crate::triangulation::tets::{FACE, INFINITE};

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

/// The cells in the complex below the target, worst first; stale entries (dead slots, or slots
/// holding other vertices) are skipped on `pop`.
#[derive(Default)]
struct SliverQueue {
    heap: std::collections::BinaryHeap<(std::cmp::Reverse<u64>, u32, [u32; 4])>,
}

impl SliverQueue {
    fn push_bad(&mut self, m: &Labeled, cells: &[u32], target: f64) {
        for &t in cells {
            if m.label[t as usize] > 0 {
                let angle = min_dihedral(m, m.tri.tets().vertices(t));
                if angle < target {
                    // Non-negative floats order as their bits.
                    let key = std::cmp::Reverse(angle.max(0.0).to_bits());
                    self.heap.push((key, t, m.tri.tets().vertices(t)));
                }
            }
        }
    }

    fn pop(&mut self, m: &Labeled) -> Option<u32> {
        while let Some((_, t, v)) = self.heap.pop() {
            let tets = m.tri.tets();
            if tets.is_live(t) && tets.vertices(t) == v {
                return Some(t);
            }
        }
        None
    }
}

fn min_dihedral(m: &Labeled, v: [u32; 4]) -> f64 {
    dihedral(v.map(|x| *m.tri.vertex(x)))
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

/// The smallest dihedral angle of the cells in the complex among `cells`.
fn star_quality(m: &Labeled, cells: &[u32]) -> f64 {
    cells
        .iter()
        .filter(|&&s| m.label[s as usize] > 0)
        .map(|&s| min_dihedral(m, m.tri.tets().vertices(s)))
        .fold(180.0, f64::min)
}

/// For the pending re-weighting of `v`: the smallest dihedral angle of the new cells in the
/// complex, or `None` if the change would not keep the facets between different labels or a
/// new cell in the complex would exceed the radius-edge bound.
fn cone_quality(m: &Labeled, criteria: &Criteria, v: u32) -> Option<f64> {
    let labels = cone_labels(m);
    if !keeps_interfaces(m, v, &labels) {
        return None;
    }
    let q = m.tri.vertex_count() as u32 - 1;
    let mut quality = 180.0f64;
    for ((verts, _, _), &l) in m.tri.cavity_cone().iter().zip(&labels) {
        if l <= 0 {
            continue;
        }
        let p = verts.map(|x| m.tri.vertex(if x == q { v } else { x }));
        if !criteria.cell_shape_holds(p, &circumcenter(p)) {
            return None;
        }
        quality = quality.min(dihedral(p.map(|x| *x)));
    }
    Some(quality)
}

/// The label of each cell of the pending cone: that of the old cell inside its base facet.
fn cone_labels(m: &Labeled) -> Vec<i32> {
    m.tri
        .cavity_cone()
        .iter()
        .map(|&(_, outer, _)| {
            let inner = m.tri.tets().glued(outer >> 2, (outer & 3) as usize) >> 2;
            m.label[inner as usize]
        })
        .collect()
}

/// Whether the facets between different labels inside the cavity are the same before and
/// after the pending change (the new vertex read as `v`).
fn keeps_interfaces(m: &Labeled, v: u32, labels: &[i32]) -> bool {
    let tets = m.tri.tets();
    let cavity = m.tri.cavity();
    // Inside one subdomain (or outside) nothing separates labels, before or after.
    let first = m.label[cavity[0] as usize];
    if cavity.iter().all(|&t| m.label[t as usize] == first) && labels.iter().all(|&l| l == first) {
        return true;
    }
    let mut before = Vec::new();
    for &a in cavity {
        for i in 0..4 {
            if m.tri.in_cavity(tets.neighbor(a, i)) {
                before.push(side(facet_of(tets.vertices(a), i), m.label[a as usize]));
            }
        }
    }
    let q = m.tri.vertex_count() as u32 - 1;
    let mut after = Vec::new();
    for (&(verts, _, at), &l) in m.tri.cavity_cone().iter().zip(labels) {
        let verts = verts.map(|x| if x == q { v } else { x });
        for i in (0..4).filter(|&i| i != at as usize) {
            after.push(side(facet_of(verts, i), l));
        }
    }
    label_changes(before) == label_changes(after)
}

/// Facet `i` of a tetrahedron, counter-clockwise seen from inside it.
fn facet_of(v: [u32; 4], i: usize) -> [u32; 3] {
    FACE[i].map(|k| v[k])
}

/// A facet seen from one side: its sorted vertices, whether the side is the positive one of
/// the sorted order, and the label on that side.
fn side(f: [u32; 3], label: i32) -> ([u32; 3], bool, i32) {
    let mut sorted = f;
    sorted.sort_unstable();
    // Counter-clockwise from inside: the inside is positive iff the sort is an even permutation.
    let even = (0..3).any(|r| [f[r], f[(r + 1) % 3], f[(r + 2) % 3]] == sorted);
    (sorted, even, label)
}

/// The facets seen from both sides whose two labels differ, as (facet, positive-side label,
/// negative-side label), sorted.
fn label_changes(mut sides: Vec<([u32; 3], bool, i32)>) -> Vec<([u32; 3], i32, i32)> {
    sides.sort_unstable();
    let mut out: Vec<_> = sides
        .chunks(2)
        .filter_map(|pair| match pair {
            [(f, false, neg), (g, true, pos)] if f == g && pos != neg => Some((*f, *pos, *neg)),
            _ => None,
        })
        .collect();
    out.sort_unstable();
    out
}

/// Squared distance from `v` to its nearest neighbour in its star.
fn nearest_neighbour2(m: &Labeled, v: u32, star: &[u32]) -> f64 {
    let p = *m.tri.vertex(v);
    star.iter()
        .flat_map(|&s| m.tri.tets().vertices(s))
        .filter(|&u| u != v && u != INFINITE)
        .map(|u| {
            let d = sub(m.tri.vertex(u), &p);
            dot(&d, &d)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Applies a pump: the heavier copy replaces the vertex, the new cells get their labels and
/// the vertex's dimension.
fn apply(m: &mut Labeled, p: &Pump) -> Result<()> {
    m.tri.find_reweight_conflicts(p.vertex, p.tet, p.weight)?;
    let labels = cone_labels(m);
    m.tri.commit_reweight(p.vertex)?;
    m.label.resize(m.tri.tets().slots(), 0);
    let created = m.tri.created().to_vec();
    for (&t, &l) in created.iter().zip(&labels) {
        m.label[t as usize] = l;
    }
    let dimension = m.dimension[p.vertex as usize];
    m.dimension.push(dimension);
    Ok(())
}

fn sub(a: &Point, b: &Point) -> Point {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(u: &Point, v: &Point) -> Point {
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

fn dot(u: &Point, v: &Point) -> f64 {
    u[0] * v[0] + u[1] * v[1] + u[2] * v[2]
}
