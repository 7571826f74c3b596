//! Mesh optimization after refinement (DESIGN.md layer 6; Rineau's thesis §3.6): sliver
//! removal that adds no point and moves no point.
//!
//! - [`perturb`]: sliver perturbation (as in CGAL Mesh_3): a vertex inside a subdomain of a
//!   sliver moves a little, by removal and insertion, where its cells are better;
//! - [`exude`]: sliver exudation (Cheng, Dey, Edelsbrunner, Facello, Teng, "Sliver exudation",
//!   J. ACM 2000, the *pumping* of the thesis): small vertex weights turn the Delaunay
//!   triangulation into a regular one, changed by flips only, chosen to raise the smallest
//!   dihedral angle around the worst slivers.
//!
//! - [`smooth`]: optimal Delaunay triangulation smoothing of the vertices inside subdomains,
//!   off by default.
//!
//! They run in CGAL's order: smoothing, perturbation, then exudation.
//!
//! Every pass keeps the boundary and interface facets and the subdomain of every point of the
//! domain exactly: a change whose cells would not keep the facets between different labels is
//! refused. The passes are deterministic, unless their time limit stops them.

pub mod exude;
mod local;
pub mod perturb;
mod relocate;
pub mod smooth;

pub use exude::{exude, ExudeOptions, ExudeReport};
pub use perturb::{perturb, PerturbOptions, PerturbReport};
pub use smooth::{smooth, SmoothOptions, SmoothReport};

use crate::criteria::Criteria;
use crate::error::Result;
use crate::refine::Labeled;

/// Which passes run after refinement, and for how long at most.
#[derive(Clone, Copy, Debug)]
pub struct Optimization {
    pub smooth: bool,
    pub smooth_options: SmoothOptions,
    pub perturb: bool,
    pub perturb_options: PerturbOptions,
    pub exude: bool,
    pub exude_options: ExudeOptions,
}

impl Default for Optimization {
    /// Perturbation and exudation, as CGAL Mesh_3's defaults; no smoothing.
    fn default() -> Self {
        Optimization {
            smooth: false,
            smooth_options: SmoothOptions::default(),
            perturb: true,
            perturb_options: PerturbOptions::default(),
            exude: true,
            exude_options: ExudeOptions::default(),
        }
    }
}

/// Runs the selected passes on `m`, refined to meet `criteria` (which the passes keep).
pub fn optimize(m: &mut Labeled, criteria: &Criteria, o: &Optimization) -> Result<()> {
    if o.smooth {
        smooth(m, criteria, &o.smooth_options)?;
    }
    if o.perturb {
        perturb(m, criteria, &o.perturb_options)?;
    }
    if o.exude {
        exude(m, criteria, &o.exude_options)?;
    }
    Ok(())
}
