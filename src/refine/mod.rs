//! Oracle-driven Delaunay refinement of volumes bounded by smooth surfaces (Rineau's thesis
//! ch. 3, in the level architecture of ch. 5; DESIGN.md layers 5–6).
//!
//! From surface points on every component ([`crate::domain::initial_points`]), the Delaunay
//! triangulation restricted to the domain ([`complex`]) is refined by a chain of levels
//! ([`levels`]): the facet level (R1, R2) above the cell level (R3, with R3.2 decided by the
//! facet level's check of the cell's circumcenter). [`refine`] always serves the highest
//! level with work: a lower level proposes a point only when every higher queue is empty.
//!
//! The result holds the cells in the complex with their subdomain labels, the facets between
//! different labels (oriented from the first label toward the second), and the used
//! vertices only, numbered in insertion order.
//!
//! Deterministic: the initial points, the triangulation, the queues' order and every
//! construction depend only on the input.

mod complex;
mod levels;
mod output;
mod queue;

pub use complex::Complex;
pub use output::Labeled;

use crate::criteria::Criteria;
use crate::domain::{initial_points, Domain};
use crate::error::{Error, ErrorKind, Result};
use crate::mesh::Mesh;
use crate::triangulation::Conflicts;
use levels::{CellLevel, FacetLevel, Level, Verdict};

/// Which stage a progress report comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// The initial points are inserted.
    Initial = 0,
    /// The surface is being refined (facets queued).
    Surface = 1,
    /// The volume is being refined.
    Volume = 2,
}

/// A progress report.
#[derive(Clone, Copy, Debug)]
pub struct Progress {
    pub phase: Phase,
    pub vertices: usize,
    pub tetrahedra: usize,
    /// A rough estimate in `[0, 1)`: inserted points over inserted plus queued elements.
    pub fraction: f64,
}

/// Stops of a run: a vertex budget, and a progress callback that may cancel (`true`).
#[derive(Default)]
pub struct Limits<'a> {
    /// 0: no limit.
    pub max_vertices: usize,
    pub progress: Option<&'a mut dyn FnMut(&Progress) -> bool>,
}

/// Insertions between two progress reports.
const REPORT_EVERY: usize = 4096;

/// Meshes `domain` until every criterion holds.
/// Errors: a callback failed (`Callback`), the vertex budget was reached (`Limit`), the
/// progress callback cancelled (`Cancelled`), the domain is unusable (`InvalidInput`).
pub fn refine(domain: &dyn Domain, criteria: &Criteria, limits: Limits) -> Result<Mesh> {
    refine_complex(domain, criteria, limits).map(|c| c.to_mesh())
}

/// [`refine`], returning the restricted Delaunay triangulation itself (for
/// [`Complex::validate`] and [`Complex::to_mesh`]).
pub fn refine_complex<'a>(
    domain: &'a dyn Domain,
    criteria: &'a Criteria,
    limits: Limits,
) -> Result<Complex<'a>> {
    let mut run = Run {
        limits,
        inserted: 0,
    };
    let initial = initial_points(domain)?;
    let mut c = Complex::new(domain, criteria, initial)?;
    let mut facets = FacetLevel::default();
    let mut cells = CellLevel::default();
    let mut chain: [&mut dyn Level; 2] = [&mut facets, &mut cells];
    for level in chain.iter_mut() {
        level.after_insertion(&c, criteria)?;
    }
    run.report(&c, &chain, Phase::Initial)?;
    'refine: loop {
        for k in 0..chain.len() {
            let Some(e) = chain[k].next(&c, criteria)? else {
                continue;
            };
            let proposal = chain[k].refinement_point(&c, &e);
            let pending = c.find_conflicts(proposal.point, proposal.near)? == Conflicts::Cavity;
            let (higher, _) = chain.split_at_mut(k);
            let verdict = if pending {
                higher
                    .iter_mut()
                    .map(|h| h.check_refinement_point(&c, &proposal.point))
                    .find(|&v| v != Verdict::Accepted)
                    .unwrap_or(Verdict::Accepted)
            } else {
                // A vertex is already there: the element cannot be refined.
                Verdict::RejectedForever
            };
            match verdict {
                Verdict::Accepted => {
                    c.commit(proposal.dimension)?;
                    for level in chain.iter_mut() {
                        level.after_insertion(&c, criteria)?;
                    }
                    run.inserted(&c, &chain, k)?;
                }
                Verdict::Rejected => {
                    c.abandon();
                    chain[k].requeue(e);
                }
                Verdict::RejectedForever if pending => c.abandon(),
                Verdict::RejectedForever => {}
            }
            continue 'refine;
        }
        break;
    }
    Ok(c)
}

struct Run<'a> {
    limits: Limits<'a>,
    inserted: usize,
}

impl Run<'_> {
    /// Counts an insertion by level `k`; applies the budget and reports progress.
    fn inserted(&mut self, c: &Complex, chain: &[&mut dyn Level], k: usize) -> Result<()> {
        self.inserted += 1;
        let max = self.limits.max_vertices;
        if max > 0 && c.vertex_count() > max {
            let queued: usize = chain.iter().map(|l| l.queued()).sum();
            return Err(Error::new(
                ErrorKind::Limit,
                format!(
                    "reached the maximum of {max} vertices before the criteria held \
                     ({queued} elements still queued)"
                ),
            ));
        }
        if self.inserted.is_multiple_of(REPORT_EVERY) {
            let phase = if k == 0 {
                Phase::Surface
            } else {
                Phase::Volume
            };
            self.report(c, chain, phase)?;
        }
        Ok(())
    }

    fn report(&mut self, c: &Complex, chain: &[&mut dyn Level], phase: Phase) -> Result<()> {
        let Some(progress) = self.limits.progress.as_mut() else {
            return Ok(());
        };
        let queued: usize = chain.iter().map(|l| l.queued()).sum();
        let report = Progress {
            phase,
            vertices: c.vertex_count(),
            tetrahedra: c.tri.tets().slots() - c.tri.tets().free.len(),
            fraction: self.inserted as f64 / (self.inserted + queued + 1) as f64,
        };
        if progress(&report) {
            return Err(Error::new(
                ErrorKind::Cancelled,
                format!(
                    "the progress callback cancelled the run at {} vertices",
                    report.vertices
                ),
            ));
        }
        Ok(())
    }
}
