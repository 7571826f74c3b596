//! The quality report of a mesh (`delmesh_mesh_quality`).

use super::mesh::DelmeshMesh;
use super::{args, call};
use crate::quality::{Quality, RADIUS_RATIO_BINS};

/// Bins of `DelmeshQuality::radius_ratio_histogram`.
pub const DELMESH_QUALITY_HISTOGRAM_BINS: usize = 10;
const _: () = assert!(DELMESH_QUALITY_HISTOGRAM_BINS == RADIUS_RATIO_BINS);

/// Quality figures of a mesh (definitions of the project's METRICS.md "Quality"); angles in
/// degrees. Extremes are NaN when the mesh has no tetrahedra (or no facets).
#[repr(C)]
pub struct DelmeshQuality {
    pub tetrahedra: usize,
    pub min_dihedral_angle: f64,
    pub max_dihedral_angle: f64,
    /// Largest circumradius / shortest edge.
    pub max_radius_edge_ratio: f64,
    /// Smallest 3 * inradius / circumradius (1 for the regular tetrahedron).
    pub min_radius_ratio: f64,
    /// Tetrahedra with a dihedral angle below 5, 10 and 15 degrees.
    pub dihedral_below: [usize; 3],
    /// Bin k counts the radius ratios in [k/10, (k+1)/10); the last bin includes 1.
    pub radius_ratio_histogram: [usize; DELMESH_QUALITY_HISTOGRAM_BINS],
    /// Smallest angle of the boundary and interface facets.
    pub min_facet_angle: f64,
}

/// Computes the quality report of `m` into `*out`.
///
/// Errors: NULL `m` or `out` -> `DELMESH_ERROR_NULL_ARGUMENT` (`*out` untouched).
///
/// # Safety
/// `m` is NULL or a live mesh; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_quality(
    m: *const DelmeshMesh,
    out: *mut DelmeshQuality,
) -> super::DelmeshStatus {
    call("delmesh_mesh_quality", || {
        // SAFETY: the caller's contract.
        let m = unsafe { args::required(m, "m") }?;
        // SAFETY: the caller's contract.
        let out = unsafe { out.as_mut() }.ok_or_else(|| super::Failure::null_argument("out"))?;
        let q = Quality::of(m.mesh());
        *out = DelmeshQuality {
            tetrahedra: q.tetrahedra,
            min_dihedral_angle: q.min_dihedral,
            max_dihedral_angle: q.max_dihedral,
            max_radius_edge_ratio: q.max_radius_edge,
            min_radius_ratio: q.min_radius_ratio,
            dihedral_below: q.dihedral_below,
            radius_ratio_histogram: q.radius_ratio_histogram,
            min_facet_angle: q.min_facet_angle,
        };
        Ok(())
    })
}
