//! Planar triangulation (API.md "2D").

use super::mesh::DelmeshMesh;
use super::{args, call, DelmeshStatus, Failure};
use crate::mesh2d;

/// What `delmesh_triangulate_2d` computes.
#[allow(non_camel_case_types)]
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DelmeshMode2d {
    /// Delaunay triangulation of the points; segments ignored.
    DELMESH_MODE2D_DELAUNAY = 0,
    /// Pébay: subdivide the segments a priori until every sub-segment is strongly
    /// Delaunay-admissible; output = Delaunay triangulation of the convex hull of the
    /// augmented point set.
    DELMESH_MODE2D_CONFORMING = 1,
    /// Conforming + Ruppert/Shewchuk refinement inside the domain. Not yet supported:
    /// `delmesh_triangulate_2d` returns DELMESH_ERROR_INVALID_ARGUMENT for it.
    DELMESH_MODE2D_QUALITY = 2,
}

/// Options of `delmesh_triangulate_2d` (all In). Zero-initialize, then set `mode`.
#[repr(C)]
pub struct DelmeshOptions2d {
    pub mode: DelmeshMode2d,
    /// Quality mode: lower bound on triangle angles, in degrees; 0 = no angle criterion.
    pub min_angle_degrees: f64,
    /// Quality mode: upper bound on triangle areas; 0 = none.
    pub max_area: f64,
    /// Quality mode: `n_holes` (x, y) seeds; the region containing each is removed.
    pub holes: *const f64,
    pub n_holes: usize,
    /// Quality mode: `n_regions` (x, y, label, max_area) seeds; max_area 0 = the global one.
    pub regions: *const f64,
    pub n_regions: usize,
}

/// Triangulates the `n_points` points `xy` (x y interleaved, 2 * n_points doubles) and the
/// `n_segments` constraint segments `segments` (2 * n_segments point indices; NULL allowed
/// when `n_segments` is 0), as `options->mode` says (NULL `options`: conforming mode).
///
/// - DELAUNAY: every triangle of the Delaunay triangulation of the points' convex hull;
///   segments are ignored. Cocircular points are resolved by a deterministic symbolic
///   perturbation.
/// - CONFORMING: Pébay's a-priori subdivision (INRIA RR-3492, Algorithm 3.2): points are
///   added on the segments until every sub-segment is strongly Delaunay-admissible (in every
///   Delaunay triangulation of the points, cocircular ones included); the triangles are the
///   Delaunay triangulation of the convex hull of all points. `delmesh_mesh_edges` lists the
///   sub-segments, input segment after input segment, each from its first point to its
///   second. The number of added points is `delmesh_mesh_vertex_count - n_points`.
/// - QUALITY: not yet supported (DELMESH_ERROR_INVALID_ARGUMENT).
///
/// Output: vertices with z = 0; vertex `i < n_points` is input point `i`, added points
/// follow. A point equal to an earlier one is merged onto it (`delmesh_mesh_duplicate_of`),
/// keeps its slot and is used by nothing; segments through it use the earlier point and a
/// repeated segment is listed once. Triangles are counter-clockwise, label 1. Vertex
/// dimensions: 0 at segment ends, 1 for added points, 2 for other points, -1 for merged
/// copies (and for every point in DELAUNAY mode). Deterministic.
///
/// On success `*out` receives a new mesh owned by the caller (free it with
/// `delmesh_mesh_free`); on failure `*out` is left untouched. Errors: NULL `xy`, `out` or
/// (with `n_segments > 0`) `segments` -> DELMESH_ERROR_NULL_ARGUMENT; an unknown mode, a
/// negative or non-finite option, or the QUALITY mode -> DELMESH_ERROR_INVALID_ARGUMENT; a
/// non-finite coordinate or one of magnitude above 1e60, all points collinear, a segment
/// index out of range, a zero-length segment, a point on a segment, or two crossing segments
/// -> DELMESH_ERROR_INVALID_INPUT, the message naming the culprits.
///
/// Thread-safe: calls on different threads run independently; the inputs are only read.
///
/// # Safety
/// `xy` is NULL or points to 2 * n_points readable doubles, `segments` to 2 * n_segments
/// `uint32_t`; `options` is NULL or points to a readable `DelmeshOptions2d`; `out` is NULL or
/// writable.
#[no_mangle]
pub unsafe extern "C" fn delmesh_triangulate_2d(
    xy: *const f64,
    n_points: usize,
    segments: *const u32,
    n_segments: usize,
    options: *const DelmeshOptions2d,
    out: *mut *mut DelmeshMesh,
) -> DelmeshStatus {
    call("delmesh_triangulate_2d", || {
        let xy = unsafe { args::array(xy, n_points, 2, "xy", "n_points") }?;
        let segments = if n_segments == 0 {
            &[][..]
        } else {
            unsafe { args::array(segments, n_segments, 2, "segments", "n_segments") }?
        };
        let mode = unsafe { mode_of(options) }?;
        let out = unsafe { args::out_param(out, "out") }?;
        let mesh = match mode {
            DelmeshMode2d::DELMESH_MODE2D_DELAUNAY => mesh2d::delaunay_2d(xy)?,
            DelmeshMode2d::DELMESH_MODE2D_CONFORMING => mesh2d::conforming_2d(xy, segments)?.mesh,
            DelmeshMode2d::DELMESH_MODE2D_QUALITY => {
                return Err(invalid(
                    "options->mode: DELMESH_MODE2D_QUALITY is not yet supported",
                ))
            }
        };
        *out = DelmeshMesh::into_raw(mesh);
        Ok(())
    })
}

/// The mode of `options` (conforming when NULL), its numeric options checked. The mode is
/// read as an integer so that a value outside the enum never becomes a Rust enum.
///
/// # Safety
/// `options` is NULL or points to a readable `DelmeshOptions2d`.
unsafe fn mode_of(options: *const DelmeshOptions2d) -> Result<DelmeshMode2d, Failure> {
    if options.is_null() {
        return Ok(DelmeshMode2d::DELMESH_MODE2D_CONFORMING);
    }
    // SAFETY: non-NULL and readable by the caller's contract; a C enum is an `int`.
    let raw = unsafe { std::ptr::addr_of!((*options).mode).cast::<i32>().read() };
    let mode = match raw {
        0 => DelmeshMode2d::DELMESH_MODE2D_DELAUNAY,
        1 => DelmeshMode2d::DELMESH_MODE2D_CONFORMING,
        2 => DelmeshMode2d::DELMESH_MODE2D_QUALITY,
        other => return Err(invalid(&format!("options->mode: unknown mode {other}"))),
    };
    // SAFETY: as above; the remaining fields are plain numbers.
    let (angle, area) = unsafe { ((*options).min_angle_degrees, (*options).max_area) };
    if !(0.0..60.0).contains(&angle) {
        return Err(invalid(&format!(
            "options->min_angle_degrees = {angle}: must be in [0, 60)"
        )));
    }
    if !(area >= 0.0 && area.is_finite()) {
        return Err(invalid(&format!(
            "options->max_area = {area}: must be finite and >= 0"
        )));
    }
    Ok(mode)
}

fn invalid(message: &str) -> Failure {
    Failure::new(DelmeshStatus::DELMESH_ERROR_INVALID_ARGUMENT, message)
}
