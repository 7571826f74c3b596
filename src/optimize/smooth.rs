//! Smoothing by optimal Delaunay triangulation (Chen and Xu, "Optimal Delaunay
//! triangulations", J. Comput. Math. 2004; Alliez et al., "Variational tetrahedral meshing",
//! SIGGRAPH 2005; CGAL Mesh_3's `odt_optimize_mesh_3`): each vertex inside a subdomain moves
//! to the volume-weighted mean of the circumcenters of its star, the position that minimizes
//! the interpolation error of |x|² locally. Off by default, as in CGAL.
//!
//! A move is a relocation (see `relocate`): kept only if the smallest dihedral angle of the
//! changed cells is no worse than that of the old star, the facets between different labels
//! stay, and the radius-edge bound holds. Surface vertices do not move.

use std::time::{Duration, Instant};

use super::relocate::{movable_star, relocate, Gain, Outcome};
use crate::criteria::Criteria;
use crate::error::Result;
use crate::geometry::{circumcenter, tet_volume};
use crate::predicates::Point;
use crate::refine::Labeled;

/// Options of [`smooth`].
#[derive(Clone, Copy, Debug)]
pub struct SmoothOptions {
    /// Passes over all vertices.
    pub sweeps: usize,
    /// Stop after this long (the result then depends on the machine's speed).
    pub time_limit: Option<Duration>,
}

impl Default for SmoothOptions {
    fn default() -> Self {
        SmoothOptions {
            sweeps: 2,
            time_limit: None,
        }
    }
}

/// What a pass did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SmoothReport {
    /// Moves made, over all sweeps.
    pub moved: usize,
    /// Sweeps completed.
    pub sweeps: usize,
    /// Whether the time limit stopped the pass.
    pub timed_out: bool,
}

/// Smooths the vertices inside subdomains of `m` (see the module documentation).
pub fn smooth(
    m: &mut Labeled,
    criteria: &Criteria,
    options: &SmoothOptions,
) -> Result<SmoothReport> {
    let start = Instant::now();
    let mut report = SmoothReport::default();
    for _ in 0..options.sweeps {
        // A tetrahedron of every vertex, kept up to date from the cells each move creates.
        let mut home = vec![u32::MAX; m.tri.vertex_count()];
        for t in m.tri.tets().live() {
            for v in m.tri.tets().vertices(t) {
                if v != u32::MAX {
                    home[v as usize] = t;
                }
            }
        }
        for v in 0..home.len() as u32 {
            if options
                .time_limit
                .is_some_and(|limit| start.elapsed() > limit)
            {
                report.timed_out = true;
                return Ok(report);
            }
            let t = home[v as usize];
            if t == u32::MAX || !m.tri.tets().is_live(t) || !m.tri.tets().vertices(t).contains(&v) {
                continue;
            }
            let Some(star) = movable_star(m, v, t) else {
                continue;
            };
            let target = odt_position(m, &star);
            let outcome = relocate(m, criteria, v, t, &star, &[target], Gain::NoWorse)?;
            if let Outcome::Moved = outcome {
                report.moved += 1;
            }
            if !matches!(outcome, Outcome::Skipped) {
                for &c in m.tri.created() {
                    for x in m.tri.tets().vertices(c) {
                        if (x as usize) < home.len() {
                            home[x as usize] = c;
                        }
                    }
                }
            }
        }
        report.sweeps += 1;
    }
    Ok(report)
}

/// The volume-weighted mean of the circumcenters of `star`.
fn odt_position(m: &Labeled, star: &[u32]) -> Point {
    let mut sum = [0.0; 3];
    let mut total = 0.0;
    for &s in star {
        let p = m.tri.tets().vertices(s).map(|x| m.tri.vertex(x));
        let volume = tet_volume(p);
        let c = circumcenter(p);
        for k in 0..3 {
            sum[k] += volume * c[k];
        }
        total += volume;
    }
    sum.map(|x| x / total)
}
