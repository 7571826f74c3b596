//! Delaunay and regular tetrahedralizations of points (API.md).

use super::mesh::DelmeshMesh;
use super::{args, call, DelmeshStatus};
use crate::triangulation;

/// Delaunay tetrahedralization of the `n` points `xyz` (x y z interleaved, 3 * n
/// doubles): every finite tetrahedron of the triangulation of their convex hull, label 1.
///
/// Output vertex `i` is input point `i`. A point equal to an earlier one is merged onto
/// it (see `delmesh_mesh_duplicate_of`): it keeps its slot and no tetrahedron uses it.
/// The result is deterministic: the same points give the same arrays.
///
/// On success `*out` receives a new mesh owned by the caller (free it with
/// `delmesh_mesh_free`); on failure `*out` is left untouched. Errors: NULL `xyz` or `out`
/// -> `DELMESH_ERROR_NULL_ARGUMENT`; `n` so large that 3 * n doubles cannot be addressed ->
/// `DELMESH_ERROR_INVALID_ARGUMENT`; a non-finite coordinate, a coordinate of magnitude
/// above 1e60, or fewer than 4 affinely independent points ->
/// `DELMESH_ERROR_INVALID_INPUT`.
///
/// Thread-safe: calls on different threads run independently; `xyz` is only read.
///
/// # Safety
/// `xyz` is NULL or points to 3 * n readable doubles; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn delmesh_delaunay_tetrahedralize(
    xyz: *const f64,
    n: usize,
    out: *mut *mut DelmeshMesh,
) -> DelmeshStatus {
    call("delmesh_delaunay_tetrahedralize", || {
        let xyz = unsafe { args::array(xyz, n, 3, "xyz", "n") }?;
        let out = unsafe { args::out_param(out, "out") }?;
        *out = DelmeshMesh::into_raw(triangulation::delaunay_tetrahedralize(xyz)?);
        Ok(())
    })
}

/// Regular (weighted Delaunay) tetrahedralization of the `n` points `xyz` (x y z
/// interleaved) with weights `weights` (n doubles, squared radii): every finite
/// tetrahedron, label 1.
///
/// Output vertex `i` is input point `i`. Hidden (redundant) points and exact copies of an
/// earlier point (same coordinates and same weight) keep their slot and are referenced by
/// no tetrahedron; copies are reported by `delmesh_mesh_duplicate_of`. Points at one
/// position with different weights are not copies: the heaviest is kept and the others are
/// hidden, as in the power diagram (CGAL's `Regular_triangulation_3` does the same).
/// Deterministic.
///
/// On success `*out` receives a new mesh owned by the caller (free it with
/// `delmesh_mesh_free`); on failure `*out` is left untouched. Errors: NULL `xyz`,
/// `weights` or `out` -> `DELMESH_ERROR_NULL_ARGUMENT`; `n` too large to address ->
/// `DELMESH_ERROR_INVALID_ARGUMENT`; a non-finite coordinate or weight, a coordinate of
/// magnitude above 1e60, or fewer than 4 affinely independent points ->
/// `DELMESH_ERROR_INVALID_INPUT`.
///
/// Thread-safe: calls on different threads run independently; the inputs are only read.
///
/// # Safety
/// `xyz` is NULL or points to 3 * n readable doubles, `weights` to n; `out` is NULL or
/// writable.
#[no_mangle]
pub unsafe extern "C" fn delmesh_regular_tetrahedralize(
    xyz: *const f64,
    weights: *const f64,
    n: usize,
    out: *mut *mut DelmeshMesh,
) -> DelmeshStatus {
    call("delmesh_regular_tetrahedralize", || {
        let xyz = unsafe { args::array(xyz, n, 3, "xyz", "n") }?;
        let weights = unsafe { args::array(weights, n, 1, "weights", "n") }?;
        let out = unsafe { args::out_param(out, "out") }?;
        *out = DelmeshMesh::into_raw(triangulation::regular_tetrahedralize(xyz, weights)?);
        Ok(())
    })
}
