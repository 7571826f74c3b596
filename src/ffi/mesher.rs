//! The mesher: criteria, stops, and the run (API.md "Mesher").

use std::ffi::c_void;

use super::domain::DelmeshDomain;
use super::mesh::DelmeshMesh;
use super::{args, call, DelmeshStatus, Failure};
use crate::criteria::{Criteria, Which};
use crate::optimize::{optimize, Optimization};
use crate::predicates::Point;
use crate::refine::{refine_complex, Limits, Progress};

/// `delmesh_mesher_set_sizing_field`: the field replaces the facet size bound.
pub const DELMESH_SIZING_FACET_SIZE: i32 = 1;
/// `delmesh_mesher_set_sizing_field`: the field replaces the facet distance bound.
pub const DELMESH_SIZING_FACET_DISTANCE: i32 = 2;
/// `delmesh_mesher_set_sizing_field`: the field replaces the cell size bound.
pub const DELMESH_SIZING_CELL_SIZE: i32 = 3;

/// `delmesh_mesher_set_optimization` flag: sliver exudation (vertex weights chosen to flip
/// slivers away; no point added or moved). On by default.
pub const DELMESH_OPTIMIZE_EXUDE: i32 = 1;
/// `delmesh_mesher_set_optimization` flag: sliver perturbation (vertices inside a subdomain
/// move a little where their cells are better; surface vertices never move). On by default;
/// it runs before exudation.
pub const DELMESH_OPTIMIZE_PERTURB: i32 = 2;
/// `delmesh_mesher_set_optimization` flag: optimal Delaunay triangulation smoothing of the
/// vertices inside subdomains (two sweeps; surface vertices never move). Off by default; it
/// runs before perturbation.
pub const DELMESH_OPTIMIZE_ODT: i32 = 4;

/// Progress phase: the initial surface points are inserted.
pub const DELMESH_PHASE_INITIAL: i32 = 0;
/// Progress phase: the surface is being refined.
pub const DELMESH_PHASE_SURFACE: i32 = 1;
/// Progress phase: the volume is being refined.
pub const DELMESH_PHASE_VOLUME: i32 = 2;

/// A sizing field: the bound at `p` for an element of `dimension` (2: a surface facet,
/// `index` = (low label << 16) | high label of the two subdomains it separates; 3: a cell,
/// `index` = its subdomain). Must return a positive finite number; anything else stops the
/// run with `DELMESH_ERROR_CALLBACK`.
pub type DelmeshSizingFn = Option<
    unsafe extern "C" fn(p: *const f64, dimension: i32, index: i32, user_data: *mut c_void) -> f64,
>;

/// A progress report, passed to the progress callback.
#[repr(C)]
pub struct DelmeshProgress {
    /// DELMESH_PHASE_INITIAL, DELMESH_PHASE_SURFACE or DELMESH_PHASE_VOLUME.
    pub phase: i32,
    pub vertices: usize,
    pub tetrahedra: usize,
    /// A rough estimate of the work done, in [0, 1).
    pub fraction: f64,
}

/// Called now and then during a run; returning nonzero cancels it
/// (`DELMESH_ERROR_CANCELLED`).
pub type DelmeshProgressFn =
    Option<unsafe extern "C" fn(p: *const DelmeshProgress, user_data: *mut c_void) -> i32>;

/// An opaque mesher: criteria and options, created by `delmesh_mesher_new`, released with
/// `delmesh_mesher_free`.
///
/// Thread-safety: setters must not run concurrently with any other use of the same
/// mesher; `delmesh_mesher_run` only reads it.
pub struct DelmeshMesher {
    criteria: Criteria,
    optimization: Optimization,
    max_vertices: usize,
    progress: Option<(
        unsafe extern "C" fn(*const DelmeshProgress, *mut c_void) -> i32,
        *mut c_void,
    )>,
}

/// A new mesher with no bound set but the facet topology criterion (every vertex of a
/// surface facet lies on the surface, as in CGAL Mesh_3) and the surface sliver bound (15
/// degrees, `delmesh_mesher_set_surface_sliver_angle`); sliver perturbation and exudation on. Set at least a
/// facet size or distance and a cell bound for a useful mesh.
///
/// Errors: NULL `out` -> `DELMESH_ERROR_NULL_ARGUMENT`.
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_new(out: *mut *mut DelmeshMesher) -> DelmeshStatus {
    call("delmesh_mesher_new", || {
        // SAFETY: the caller's contract.
        let out = unsafe { args::out_param(out, "out") }?;
        let mesher = DelmeshMesher {
            criteria: Criteria::new(),
            optimization: Optimization::default(),
            max_vertices: 0,
            progress: None,
        };
        *out = Box::into_raw(Box::new(mesher));
        Ok(())
    })
}

/// Runs `f` on the mesher behind `m`, named `function` in error messages.
///
/// # Safety
/// `m` is NULL or a live mesher not used concurrently.
unsafe fn with_mesher(
    function: &str,
    m: *mut DelmeshMesher,
    f: impl FnOnce(&mut DelmeshMesher) -> Result<(), Failure>,
) -> DelmeshStatus {
    call(function, || {
        // SAFETY: the caller's contract.
        let m = unsafe { m.as_mut() }.ok_or_else(|| Failure::null_argument("m"))?;
        f(m)
    })
}

/// Lower bound on the angles of surface facets, in degrees, in (0, 30].
/// Errors: NULL `m`; a value outside (0, 30] or NaN -> `DELMESH_ERROR_INVALID_ARGUMENT`.
///
/// # Safety
/// `m` is NULL or a live mesher.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_set_facet_angle(
    m: *mut DelmeshMesher,
    degrees: f64,
) -> DelmeshStatus {
    unsafe {
        with_mesher("delmesh_mesher_set_facet_angle", m, |m| {
            Ok(m.criteria.set_facet_angle(degrees)?)
        })
    }
}

/// Upper bound on the radius of the surface Delaunay balls of surface facets (positive,
/// finite). Errors: NULL `m`; zero, negative, infinite or NaN ->
/// `DELMESH_ERROR_INVALID_ARGUMENT`.
///
/// # Safety
/// `m` is NULL or a live mesher.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_set_facet_size(
    m: *mut DelmeshMesher,
    size: f64,
) -> DelmeshStatus {
    unsafe {
        with_mesher("delmesh_mesher_set_facet_size", m, |m| {
            Ok(m.criteria.set_facet_size(size)?)
        })
    }
}

/// Upper bound on the distance from a surface facet's circumcenter to the center of its
/// surface Delaunay ball (positive, finite). Errors as for `delmesh_mesher_set_facet_size`.
///
/// # Safety
/// `m` is NULL or a live mesher.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_set_facet_distance(
    m: *mut DelmeshMesher,
    distance: f64,
) -> DelmeshStatus {
    unsafe {
        with_mesher("delmesh_mesher_set_facet_distance", m, |m| {
            Ok(m.criteria.set_facet_distance(distance)?)
        })
    }
}

/// Whether every vertex of a surface facet must lie on the surface (nonzero, the default)
/// or not (0). Errors: NULL `m`.
///
/// # Safety
/// `m` is NULL or a live mesher.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_set_facet_topology(
    m: *mut DelmeshMesher,
    vertices_on_surface: i32,
) -> DelmeshStatus {
    unsafe {
        with_mesher("delmesh_mesher_set_facet_topology", m, |m| {
            m.criteria.set_facet_topology(vertices_on_surface != 0);
            Ok(())
        })
    }
}

/// Lower bound, in degrees, on the smallest dihedral angle of the cells with at least three
/// vertices on the surface ("surface slivers"), in [0, 20]; 0 turns it off. Default 15.
/// Such cells can have a good radius-edge ratio, and exudation (which keeps the boundary)
/// often cannot remove them, so refinement treats them as bad cells. Not a CGAL Mesh_3
/// criterion: set 0 to compare with CGAL at equal criteria. Errors: NULL `m`; a value
/// outside [0, 20] or NaN -> `DELMESH_ERROR_INVALID_ARGUMENT`.
///
/// # Safety
/// `m` is NULL or a live mesher.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_set_surface_sliver_angle(
    m: *mut DelmeshMesher,
    degrees: f64,
) -> DelmeshStatus {
    unsafe {
        with_mesher("delmesh_mesher_set_surface_sliver_angle", m, |m| {
            Ok(m.criteria.set_surface_sliver_angle(degrees)?)
        })
    }
}

/// Upper bound on circumradius / shortest edge of the cells, finite and at least 2 (below
/// 2, refinement is not guaranteed to terminate). Errors: NULL `m`; a value below 2,
/// infinite or NaN -> `DELMESH_ERROR_INVALID_ARGUMENT`.
///
/// # Safety
/// `m` is NULL or a live mesher.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_set_cell_radius_edge_ratio(
    m: *mut DelmeshMesher,
    ratio: f64,
) -> DelmeshStatus {
    unsafe {
        with_mesher("delmesh_mesher_set_cell_radius_edge_ratio", m, |m| {
            Ok(m.criteria.set_cell_radius_edge_ratio(ratio)?)
        })
    }
}

/// Upper bound on the circumradius of the cells (positive, finite). Errors as for
/// `delmesh_mesher_set_facet_size`.
///
/// # Safety
/// `m` is NULL or a live mesher.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_set_cell_size(
    m: *mut DelmeshMesher,
    size: f64,
) -> DelmeshStatus {
    unsafe {
        with_mesher("delmesh_mesher_set_cell_size", m, |m| {
            Ok(m.criteria.set_cell_size(size)?)
        })
    }
}

/// Replaces the constant bound `which` (DELMESH_SIZING_FACET_SIZE,
/// DELMESH_SIZING_FACET_DISTANCE or DELMESH_SIZING_CELL_SIZE) by the field `f`, called with
/// `user_data` during `delmesh_mesher_run` from the calling thread. Errors: NULL `m` or `f`
/// -> `DELMESH_ERROR_NULL_ARGUMENT`; an unknown `which` -> `DELMESH_ERROR_INVALID_ARGUMENT`.
///
/// # Safety
/// `m` is NULL or a live mesher; `f` may be called with `user_data` until the mesher is
/// freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_set_sizing_field(
    m: *mut DelmeshMesher,
    which: i32,
    f: DelmeshSizingFn,
    user_data: *mut c_void,
) -> DelmeshStatus {
    let set = |m: &mut DelmeshMesher| {
        let f = f.ok_or_else(|| Failure::null_argument("f"))?;
        let which = match which {
            DELMESH_SIZING_FACET_SIZE => Which::FacetSize,
            DELMESH_SIZING_FACET_DISTANCE => Which::FacetDistance,
            DELMESH_SIZING_CELL_SIZE => Which::CellSize,
            _ => {
                return Err(Failure::new(
                    DelmeshStatus::DELMESH_ERROR_INVALID_ARGUMENT,
                    format!("`which` = {which} names no sizing criterion (1, 2 or 3)"),
                ))
            }
        };
        // SAFETY: `f` is the caller's function, called with its `user_data` as documented.
        let field = move |p: &Point, dimension: i32, index: i32| unsafe {
            f(p.as_ptr(), dimension, index, user_data)
        };
        m.criteria.set_sizing_field(which, Box::new(field));
        Ok(())
    };
    unsafe { with_mesher("delmesh_mesher_set_sizing_field", m, set) }
}

/// Selects the optimization passes run after refinement: `flags` is 0 (none) or a union of
/// DELMESH_OPTIMIZE_ODT, DELMESH_OPTIMIZE_PERTURB and DELMESH_OPTIMIZE_EXUDE (perturbation and
/// exudation: the default, as in CGAL Mesh_3; they run in that order); `time_limit_seconds` bounds each pass (0: no limit; a pass
/// stopped by it gives a result that depends on the machine's speed). Passes keep the boundary
/// and interface facets (the same vertices, bit for bit) and every subdomain's volume.
///
/// Errors: NULL `m`; an unknown flag, a negative or NaN time limit ->
/// `DELMESH_ERROR_INVALID_ARGUMENT`.
///
/// # Safety
/// `m` is NULL or a live mesher.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_set_optimization(
    m: *mut DelmeshMesher,
    flags: i32,
    time_limit_seconds: f64,
) -> DelmeshStatus {
    let set = |m: &mut DelmeshMesher| {
        let invalid =
            |message: String| Failure::new(DelmeshStatus::DELMESH_ERROR_INVALID_ARGUMENT, message);
        let known = DELMESH_OPTIMIZE_ODT | DELMESH_OPTIMIZE_PERTURB | DELMESH_OPTIMIZE_EXUDE;
        if flags & !known != 0 {
            return Err(invalid(format!("flags = {flags:#x} has unknown bits")));
        }
        if !(time_limit_seconds >= 0.0 && time_limit_seconds.is_finite()) {
            return Err(invalid(format!(
                "time limit {time_limit_seconds} must be finite and non-negative (0: none)"
            )));
        }
        let limit = (time_limit_seconds > 0.0)
            .then(|| std::time::Duration::from_secs_f64(time_limit_seconds));
        m.optimization.exude = flags & DELMESH_OPTIMIZE_EXUDE != 0;
        m.optimization.exude_options.time_limit = limit;
        m.optimization.perturb = flags & DELMESH_OPTIMIZE_PERTURB != 0;
        m.optimization.perturb_options.time_limit = limit;
        m.optimization.smooth = flags & DELMESH_OPTIMIZE_ODT != 0;
        m.optimization.smooth_options.time_limit = limit;
        Ok(())
    };
    unsafe { with_mesher("delmesh_mesher_set_optimization", m, set) }
}

/// The smallest dihedral angle, in degrees, that sliver perturbation and exudation aim at: the
/// cells below it are treated, worst first (default 15). In (0, 45]. Errors: NULL `m`; a value
/// outside (0, 45] or NaN -> `DELMESH_ERROR_INVALID_ARGUMENT`.
///
/// # Safety
/// `m` is NULL or a live mesher.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_set_sliver_bound(
    m: *mut DelmeshMesher,
    degrees: f64,
) -> DelmeshStatus {
    let set = |m: &mut DelmeshMesher| {
        if !(degrees > 0.0 && degrees <= 45.0) {
            return Err(Failure::new(
                DelmeshStatus::DELMESH_ERROR_INVALID_ARGUMENT,
                format!("sliver bound {degrees} must lie in (0, 45] degrees"),
            ));
        }
        m.optimization.perturb_options.target_dihedral = degrees;
        m.optimization.exude_options.target_dihedral = degrees;
        Ok(())
    };
    unsafe { with_mesher("delmesh_mesher_set_sliver_bound", m, set) }
}

/// Largest number of vertices a run may create; past it the run stops with
/// `DELMESH_ERROR_LIMIT`. 0 (the default) means no limit. Errors: NULL `m`.
///
/// # Safety
/// `m` is NULL or a live mesher.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_set_max_vertices(
    m: *mut DelmeshMesher,
    max_vertices: usize,
) -> DelmeshStatus {
    unsafe {
        with_mesher("delmesh_mesher_set_max_vertices", m, |m| {
            m.max_vertices = max_vertices;
            Ok(())
        })
    }
}

/// Sets (or, with a NULL `f`, removes) the progress callback, called with `user_data` from
/// the thread running `delmesh_mesher_run` every few thousand insertions; a nonzero return
/// stops the run with `DELMESH_ERROR_CANCELLED`. Errors: NULL `m`.
///
/// # Safety
/// `m` is NULL or a live mesher; `f` may be called with `user_data` until the mesher is
/// freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_set_progress(
    m: *mut DelmeshMesher,
    f: DelmeshProgressFn,
    user_data: *mut c_void,
) -> DelmeshStatus {
    unsafe {
        with_mesher("delmesh_mesher_set_progress", m, |m| {
            m.progress = f.map(|f| (f, user_data));
            Ok(())
        })
    }
}

/// Meshes domain `d` with the criteria of `m`, then runs the optimization passes
/// (`delmesh_mesher_set_optimization`; by default sliver perturbation and exudation): a tetrahedral mesh of every subdomain
/// (labels > 0), the surface and interface facets with their label pairs, vertex
/// dimensions 2 (surface) and 3 (volume); only used vertices, numbered compactly. The same
/// mesher and domain give bit-identical arrays.
///
/// On success `*out` receives a new mesh owned by the caller; on failure it is untouched
/// and nothing leaks. Errors: NULL `m`, `d` or `out` -> `DELMESH_ERROR_NULL_ARGUMENT`; the
/// domain inside on the boundary of its box, or no surface found ->
/// `DELMESH_ERROR_INVALID_INPUT`; a callback reported failure -> `DELMESH_ERROR_CALLBACK`;
/// the progress callback cancelled -> `DELMESH_ERROR_CANCELLED`; the vertex budget ran
/// out -> `DELMESH_ERROR_LIMIT`.
///
/// # Safety
/// `m` and `d` are NULL or live handles; `out` is NULL or writable. Callbacks must not
/// unwind (C++ exceptions) into delmesh.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_run(
    m: *const DelmeshMesher,
    d: *const DelmeshDomain,
    out: *mut *mut DelmeshMesh,
) -> DelmeshStatus {
    call("delmesh_mesher_run", || {
        // SAFETY: the caller's contract.
        let m = unsafe { args::required(m, "m") }?;
        // SAFETY: the caller's contract.
        let d = unsafe { args::required(d, "d") }?;
        // SAFETY: the caller's contract.
        let out = unsafe { args::out_param(out, "out") }?;
        let mut report = |p: &Progress| {
            let Some((f, user_data)) = m.progress else {
                return false;
            };
            let c = DelmeshProgress {
                phase: p.phase as i32,
                vertices: p.vertices,
                tetrahedra: p.tetrahedra,
                fraction: p.fraction,
            };
            // SAFETY: the caller's function and data, as documented.
            unsafe { f(&c, user_data) != 0 }
        };
        let limits = Limits {
            max_vertices: m.max_vertices,
            progress: Some(&mut report),
        };
        let mut labeled = refine_complex(&d.domain, &m.criteria, limits)?.into_labeled();
        optimize(&mut labeled, &m.criteria, &m.optimization)?;
        *out = DelmeshMesh::into_raw(labeled.to_mesh());
        Ok(())
    })
}

/// Releases a mesher; NULL is ignored.
///
/// # Safety
/// `m` is NULL or a mesher not yet freed and not running.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesher_free(m: *mut DelmeshMesher) {
    call("delmesh_mesher_free", || {
        if !m.is_null() {
            // SAFETY: `m` came from `Box::into_raw` in `delmesh_mesher_new`, freed once.
            drop(unsafe { Box::from_raw(m) });
        }
        Ok(())
    });
}
