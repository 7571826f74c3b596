//! Moving a vertex inside a subdomain: removal, then insertion at a candidate position, kept
//! only if the changed cells (the new star and what is left of the hole) are better than the
//! old star, keep the facets between different labels (see `local`) and meet the radius-edge
//! bound; otherwise the vertex goes back where it was, which restores the same triangulation
//! (it is unique). Used by perturbation and smoothing. Surface vertices never move, and a
//! vertex whose star touches another subdomain does not either: the passes keep the boundary.

use super::local::{commit_labels, cone_labels, keeps_interfaces, min_dihedral, star_quality};
use crate::criteria::Criteria;
use crate::error::{Error, Result};
use crate::geometry::circumcenter;
use crate::predicates::Point;
use crate::quality;
use crate::refine::Labeled;
use crate::triangulation::Conflicts;

/// Vertex dimension of points inside a subdomain (the only ones moved).
const VOLUME: i8 = 3;

/// What [`relocate`] did.
pub enum Outcome {
    /// The vertex cannot be moved (on the surface, next to another subdomain, on the hull).
    Skipped,
    /// The vertex moved; the created tetrahedra are its new star and the rest of the hole.
    Moved,
    /// No position improved: the vertex is back where it was, under a new id.
    Restored,
}

/// The star of `v` (a vertex of `t`) if `v` may move: inside a subdomain (dimension 3), its
/// star in one subdomain.
pub fn movable_star(m: &Labeled, v: u32, t: u32) -> Option<Vec<u32>> {
    if v == u32::MAX || m.dimension[v as usize] != VOLUME {
        return None;
    }
    let star = m.tri.star(v, t);
    let label = m.label[star[0] as usize];
    (label > 0 && star.iter().all(|&s| m.label[s as usize] == label)).then_some(star)
}

/// How much better the changed cells must be than the old star for a move.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Gain {
    /// Strictly larger smallest dihedral angle.
    Strict,
    /// No smaller smallest dihedral angle.
    NoWorse,
}

/// Moves vertex `v` (of `t`, with its [`movable_star`]) to the best of `candidates` if it
/// gains, by removal and insertion; otherwise puts it back (the same triangulation).
pub fn relocate(
    m: &mut Labeled,
    criteria: &Criteria,
    v: u32,
    t: u32,
    star: &[u32],
    candidates: &[Point],
    gain: Gain,
) -> Result<Outcome> {
    let label = m.label[star[0] as usize];
    let current = star_quality(m, star);
    let origin = *m.tri.vertex(v);
    let weight = m.tri.weight(v);
    if !m.tri.remove(v, t)? {
        return Ok(Outcome::Skipped);
    }
    let hole = m.tri.created().to_vec();
    for &h in &hole {
        relabel(m, h, label);
    }
    let mut best: Option<(Point, f64)> = None;
    for p in candidates {
        if !m.tri.in_bounds(p) {
            continue;
        }
        if let Some(q) = evaluate(m, criteria, v, p, &hole)? {
            let gains = match gain {
                Gain::Strict => q > current,
                Gain::NoWorse => q >= current,
            };
            if gains && best.is_none_or(|(_, b)| q > b) {
                best = Some((*p, q));
            }
        }
    }
    match best {
        Some((p, _)) => {
            insert(m, v, p, 0.0, hole[0])?;
            Ok(Outcome::Moved)
        }
        None => {
            insert(m, v, origin, weight, hole[0])?;
            Ok(Outcome::Restored)
        }
    }
}

/// The cells changed by inserting `p` into the hole left by `v`: their smallest dihedral
/// angle, or `None` when the insertion is refused.
fn evaluate(
    m: &mut Labeled,
    criteria: &Criteria,
    v: u32,
    p: &Point,
    hole: &[u32],
) -> Result<Option<f64>> {
    if m.tri.find_conflicts_weighted(*p, 0.0, hole[0])? != Conflicts::Cavity {
        return Ok(None);
    }
    let labels = cone_labels(m);
    let mut quality = None;
    if keeps_interfaces(m, v, &labels) {
        let mut q = 180.0f64;
        let mut shape_ok = true;
        for ((verts, _, _), &l) in m.tri.cavity_cone().iter().zip(&labels) {
            if l > 0 {
                let pts = verts.map(|x| m.tri.vertex(x));
                shape_ok &= criteria.cell_shape_holds(pts, &circumcenter(pts));
                q = q.min(quality::min_dihedral(pts.map(|x| *x)));
            }
        }
        // What is left of the hole stays.
        for &h in hole {
            if !m.tri.in_cavity(h) && m.label[h as usize] > 0 {
                q = q.min(min_dihedral(m, m.tri.tets().vertices(h)));
            }
        }
        quality = shape_ok.then_some(q);
    }
    m.tri.abandon();
    Ok(quality)
}

/// Inserts the moved (or restored) vertex with weight `w` and labels its cells; `v` is the
/// vertex it stands for.
fn insert(m: &mut Labeled, v: u32, p: Point, w: f64, near: u32) -> Result<()> {
    if m.tri.find_conflicts_weighted(p, w, near)? != Conflicts::Cavity {
        return Err(Error::internal(format!(
            "vertex {v} cannot be inserted back at {p:?}"
        )));
    }
    let labels = cone_labels(m);
    m.tri.commit()?;
    commit_labels(m, &labels, m.dimension[v as usize]);
    Ok(())
}

fn relabel(m: &mut Labeled, t: u32, label: i32) {
    if m.label.len() <= t as usize {
        m.label.resize(m.tri.tets().slots(), 0);
    }
    m.label[t as usize] = label;
}
