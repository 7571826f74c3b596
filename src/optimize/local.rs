//! What the optimization passes share: the queue of slivers, the quality of a star, and the
//! check and labelling of a pending local change (an insertion whose cavity is marked in the
//! triangulation).
//!
//! Labels of a change: each new cell takes the label of the old cell on the other side of its
//! cavity boundary facet, so boundary facets keep both their labels; the change is acceptable
//! only if the facets between different labels inside the cavity are the same, with the same
//! labels on the same sides, before and after ([`keeps_interfaces`]).

use crate::criteria::Criteria;
use crate::geometry::circumcenter;
use crate::geometry::{dot, sub};
use crate::quality::min_dihedral as dihedral;
use crate::refine::Labeled;
use crate::triangulation::tets::{FACE, INFINITE};

/// The cells in the complex below the target, worst first; stale entries (dead slots, or slots
/// holding other vertices) are skipped on `pop`.
#[derive(Default)]
pub struct SliverQueue {
    heap: std::collections::BinaryHeap<(std::cmp::Reverse<u64>, u32, [u32; 4])>,
}

impl SliverQueue {
    pub fn push_bad(&mut self, m: &Labeled, cells: &[u32], target: f64) {
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

    pub fn pop(&mut self, m: &Labeled) -> Option<u32> {
        while let Some((_, t, v)) = self.heap.pop() {
            let tets = m.tri.tets();
            if tets.is_live(t) && tets.vertices(t) == v {
                return Some(t);
            }
        }
        None
    }
}

/// The smallest dihedral angle of the tetrahedron `v`.
pub fn min_dihedral(m: &Labeled, v: [u32; 4]) -> f64 {
    dihedral(v.map(|x| *m.tri.vertex(x)))
}

/// The smallest dihedral angle of the cells in the complex among `cells`.
pub fn star_quality(m: &Labeled, cells: &[u32]) -> f64 {
    cells
        .iter()
        .filter(|&&s| m.label[s as usize] > 0)
        .map(|&s| min_dihedral(m, m.tri.tets().vertices(s)))
        .fold(180.0, f64::min)
}

/// For the pending insertion (the new vertex standing for `v`, the vertex it replaces): the
/// smallest dihedral angle of the new cells in the complex, or `None` if the change would not
/// keep the facets between different labels or a new cell in the complex would exceed the
/// radius-edge bound.
pub fn cone_quality(m: &Labeled, criteria: &Criteria, v: u32) -> Option<f64> {
    let labels = cone_labels(m);
    if !keeps_interfaces(m, v, &labels) {
        return None;
    }
    let mut quality = 180.0f64;
    for ((verts, _, _), &l) in m.tri.cavity_cone().iter().zip(&labels) {
        if l <= 0 {
            continue;
        }
        let p = verts.map(|x| m.tri.vertex(x));
        if !criteria.cell_shape_holds(p, &circumcenter(p)) {
            return None;
        }
        quality = quality.min(dihedral(p.map(|x| *x)));
    }
    Some(quality)
}

/// The label of each cell of the pending cone: that of the old cell inside its base facet.
pub fn cone_labels(m: &Labeled) -> Vec<i32> {
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
pub fn keeps_interfaces(m: &Labeled, v: u32, labels: &[i32]) -> bool {
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
pub fn nearest_neighbour2(m: &Labeled, v: u32, star: &[u32]) -> f64 {
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

/// Labels the tetrahedra the last commit created (`labels` in cone order) and gives the new
/// vertex `dimension`.
pub fn commit_labels(m: &mut Labeled, labels: &[i32], dimension: i8) {
    m.label.resize(m.tri.tets().slots(), 0);
    for (&t, &l) in m.tri.created().iter().zip(labels) {
        m.label[t as usize] = l;
    }
    m.dimension.push(dimension);
}
