//! Sliver perturbation: moving a vertex of a sliver a little (the perturbation step of CGAL
//! Mesh_3, after Tournois, Srinivasan and Alliez, "Perturbing slivers in 3D Delaunay meshes",
//! IMR 2009), for the slivers exudation leaves.
//!
//! The cells in the complex below the target dihedral angle are taken worst first. For each
//! vertex of such a cell that lies inside a subdomain (dimension 3) and whose star lies in one
//! subdomain, the vertex is removed and candidate positions are tried in the hole: steps of a
//! tenth to a half of the distance to its nearest neighbour, along the gradient of the cell's
//! smallest dihedral angle with respect to the vertex and along the six axis directions. A
//! candidate is kept when the cells it changes (its new star and what is left of the hole)
//! have a larger smallest dihedral angle than the old star, keep the facets between different
//! labels (see `local`) and meet the radius-edge bound; otherwise the vertex goes back where it
//! was, which restores the same triangulation (it is unique). Surface vertices are not moved:
//! the passes keep the boundary facets as they are.

use std::collections::HashSet;
use std::time::{Duration, Instant};

use super::local::{nearest_neighbour2, SliverQueue};
use super::relocate::{movable_star, relocate, Gain, Outcome};
use crate::criteria::Criteria;
use crate::error::Result;
use crate::geometry::{dot, sub};
use crate::predicates::Point;
use crate::quality;
use crate::refine::Labeled;

/// Steps tried, as fractions of the distance to the nearest neighbour.
const STEPS: [f64; 3] = [0.1, 0.25, 0.5];

/// Options of [`perturb`].
#[derive(Clone, Copy, Debug)]
pub struct PerturbOptions {
    /// Cells whose smallest dihedral angle is below this (degrees) are treated.
    pub target_dihedral: f64,
    /// Stop after this long (the result then depends on the machine's speed).
    pub time_limit: Option<Duration>,
}

impl Default for PerturbOptions {
    fn default() -> Self {
        PerturbOptions {
            target_dihedral: 15.0,
            time_limit: None,
        }
    }
}

/// What a pass did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PerturbReport {
    /// Vertices moved.
    pub moved: usize,
    /// Slivers examined.
    pub examined: usize,
    /// Whether the time limit stopped the pass.
    pub timed_out: bool,
}

/// Perturbs the slivers of `m` (see the module documentation).
pub fn perturb(
    m: &mut Labeled,
    criteria: &Criteria,
    options: &PerturbOptions,
) -> Result<PerturbReport> {
    let start = Instant::now();
    let mut report = PerturbReport::default();
    let mut queue = SliverQueue::default();
    let live: Vec<u32> = m.tri.tets().live().collect();
    queue.push_bad(m, &live, options.target_dihedral);
    // Slivers no move improved, by their corners: a restored vertex gets a new id, so its
    // cells come back to the queue, and must not be tried again.
    let mut given_up: HashSet<[[u64; 3]; 4]> = HashSet::new();
    while let Some(t) = queue.pop(m) {
        if options
            .time_limit
            .is_some_and(|limit| start.elapsed() > limit)
        {
            report.timed_out = true;
            break;
        }
        let key = corners(m, t);
        if given_up.contains(&key) {
            continue;
        }
        report.examined += 1;
        let (mut sliver, mut moved) = (t, false);
        for k in 0..4 {
            let v = m.tri.tets().vertices(sliver)[k];
            match try_vertex(m, criteria, v, sliver)? {
                Outcome::Skipped => continue,
                Outcome::Moved => moved = true,
                Outcome::Restored => {}
            }
            let created = m.tri.created().to_vec();
            queue.push_bad(m, &created, options.target_dihedral);
            if moved {
                report.moved += 1;
                break;
            }
            // The same sliver, rebuilt around the restored vertex.
            match created.iter().find(|&&c| corners(m, c) == key) {
                Some(&c) => sliver = c,
                None => break,
            }
        }
        if !moved {
            given_up.insert(key);
        }
    }
    Ok(report)
}

/// The corners of tetrahedron `t`, sorted, as bits.
fn corners(m: &Labeled, t: u32) -> [[u64; 3]; 4] {
    let mut c = m
        .tri
        .tets()
        .vertices(t)
        .map(|x| m.tri.vertex(x).map(f64::to_bits));
    c.sort_unstable();
    c
}

/// Tries to move vertex `v` of the sliver `t` along the directions of [`directions`].
fn try_vertex(m: &mut Labeled, criteria: &Criteria, v: u32, t: u32) -> Result<Outcome> {
    let Some(star) = movable_star(m, v, t) else {
        return Ok(Outcome::Skipped);
    };
    let origin = *m.tri.vertex(v);
    let spacing = nearest_neighbour2(m, v, &star).sqrt();
    let candidates: Vec<Point> = directions(m, v, t)
        .iter()
        .flat_map(|d| STEPS.map(|step| std::array::from_fn(|k| origin[k] + step * spacing * d[k])))
        .collect();
    relocate(m, criteria, v, t, &star, &candidates, Gain::Strict)
}

/// Unit directions to try for `v` in the sliver `t`: the gradient of the sliver's smallest
/// dihedral angle with respect to `v` (central differences), then the six axis directions.
fn directions(m: &Labeled, v: u32, t: u32) -> Vec<Point> {
    let verts = m.tri.tets().vertices(t);
    let points = verts.map(|x| *m.tri.vertex(x));
    let at = verts.iter().position(|&x| x == v).unwrap_or(0);
    let scale = (0..4)
        .map(|k| sub(&points[k], &points[at]))
        .map(|d| dot(&d, &d).sqrt())
        .fold(0.0, f64::max);
    let h = 1e-4 * scale;
    let angle_at = |k: usize, s: f64| {
        let mut p = points;
        p[at][k] += s;
        quality::min_dihedral(p)
    };
    let g: Point = std::array::from_fn(|k| angle_at(k, h) - angle_at(k, -h));
    let mut out = Vec::with_capacity(7);
    let norm = dot(&g, &g).sqrt();
    if norm > 0.0 && norm.is_finite() {
        out.push(g.map(|x| x / norm));
    }
    for k in 0..3 {
        for s in [1.0, -1.0] {
            let mut d = [0.0; 3];
            d[k] = s;
            out.push(d);
        }
    }
    out
}
