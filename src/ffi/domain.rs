//! Domains given by C callbacks (API.md "Domains").

use std::ffi::c_void;

use super::{args, call, DelmeshStatus, Failure};
use crate::domain::{BBox, FunctionDomain, Oracle};
use crate::predicates::Point;

/// An implicit function: negative inside the domain, positive or zero outside. Returning
/// NaN reports a failure: the run stops with `DELMESH_ERROR_CALLBACK`.
pub type DelmeshImplicitFn =
    Option<unsafe extern "C" fn(p: *const f64, user_data: *mut c_void) -> f64>;

/// A labeling function: 0 outside, > 0 the subdomain containing `p`. A negative value
/// reports a failure: the run stops with `DELMESH_ERROR_CALLBACK`.
pub type DelmeshLabelFn =
    Option<unsafe extern "C" fn(p: *const f64, user_data: *mut c_void) -> i32>;

/// An opaque domain, created by `delmesh_domain_new_implicit` or `delmesh_domain_new_labeled`
/// and released with `delmesh_domain_free`.
///
/// Thread-safety: a domain is only read by `delmesh_mesher_run`; two runs may share it on
/// two threads only if its callbacks are thread-safe. `delmesh_domain_add_surface_points`
/// must not run concurrently with any other use of the same domain.
pub struct DelmeshDomain {
    pub(crate) domain: FunctionDomain,
}

fn new_domain(
    oracle: Oracle,
    bbox: *const f64,
    relative_error: f64,
    out: *mut *mut DelmeshDomain,
) -> Result<(), Failure> {
    // SAFETY: the callers' contract: `bbox` is NULL or 6 readable doubles.
    let b = unsafe { args::array(bbox, 6, 1, "bbox", "6") }?;
    let b: &[f64; 6] = b.try_into().map_err(|_| Failure::null_argument("bbox"))?;
    let bbox = BBox::from_array(b)
        .map_err(|message| Failure::new(DelmeshStatus::DELMESH_ERROR_INVALID_ARGUMENT, message))?;
    // SAFETY: the callers' contract: `out` is NULL or writable.
    let out = unsafe { args::out_param(out, "out") }?;
    let domain = FunctionDomain::new(oracle, bbox, relative_error)?;
    *out = Box::into_raw(Box::new(DelmeshDomain { domain }));
    Ok(())
}

/// A domain given by an implicit function `f` (negative inside: one subdomain, label 1)
/// inside the box `bbox` = {xmin, ymin, zmin, xmax, ymax, zmax}.
///
/// `f` must be positive or zero (outside) everywhere on the boundary of `bbox`; the run
/// checks this on a grid and fails with `DELMESH_ERROR_INVALID_INPUT` otherwise.
/// `relative_error` bounds the distance from surface vertices to the surface `f = 0`,
/// relative to the box diagonal, in (0, 0.1] (1e-6 is a good default). `user_data` is
/// passed to every call of `f`, which is called only during `delmesh_mesher_run`, from
/// the calling thread.
///
/// On success `*out` receives a new domain owned by the caller (free it with
/// `delmesh_domain_free`); on failure `*out` is untouched. Errors: NULL `f`, `bbox` or
/// `out` -> `DELMESH_ERROR_NULL_ARGUMENT`; an empty or non-finite box, or
/// `relative_error` outside (0, 0.1] -> `DELMESH_ERROR_INVALID_ARGUMENT`.
///
/// # Safety
/// `bbox` is NULL or 6 readable doubles; `out` is NULL or writable; `f` may be called with
/// `user_data` until the domain is freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_domain_new_implicit(
    f: DelmeshImplicitFn,
    user_data: *mut c_void,
    bbox: *const f64,
    relative_error: f64,
    out: *mut *mut DelmeshDomain,
) -> DelmeshStatus {
    call("delmesh_domain_new_implicit", || {
        let f = f.ok_or_else(|| Failure::null_argument("f"))?;
        // SAFETY: `f` is the caller's function, called with its `user_data` as documented.
        let oracle = Oracle::Implicit(Box::new(move |p: &Point| unsafe {
            f(p.as_ptr(), user_data)
        }));
        new_domain(oracle, bbox, relative_error, out)
    })
}

/// A domain given by a labeling function `f`: 0 outside, > 0 the subdomain containing the
/// point (any number of subdomains; the surfaces between different labels are meshed as
/// interfaces), inside the box `bbox` = {xmin, ymin, zmin, xmax, ymax, zmax}.
///
/// `f` must return 0 everywhere on the boundary of `bbox` (checked on a grid during the
/// run: `DELMESH_ERROR_INVALID_INPUT`). `relative_error`, `user_data`, ownership and errors
/// as for `delmesh_domain_new_implicit`.
///
/// # Safety
/// As for `delmesh_domain_new_implicit`.
#[no_mangle]
pub unsafe extern "C" fn delmesh_domain_new_labeled(
    f: DelmeshLabelFn,
    user_data: *mut c_void,
    bbox: *const f64,
    relative_error: f64,
    out: *mut *mut DelmeshDomain,
) -> DelmeshStatus {
    call("delmesh_domain_new_labeled", || {
        let f = f.ok_or_else(|| Failure::null_argument("f"))?;
        // SAFETY: `f` is the caller's function, called with its `user_data` as documented.
        let oracle = Oracle::Labels(Box::new(move |p: &Point| unsafe {
            f(p.as_ptr(), user_data)
        }));
        new_domain(oracle, bbox, relative_error, out)
    })
}

/// Adds `n` points (x y z interleaved) on the domain's surface: they become initial surface
/// vertices, so that components too small for the initial search are meshed too.
///
/// Errors: NULL `d` or `xyz` -> `DELMESH_ERROR_NULL_ARGUMENT`; a point not finite or
/// outside the box -> `DELMESH_ERROR_INVALID_INPUT` (nothing is added).
///
/// # Safety
/// `d` is NULL or a live domain; `xyz` is NULL or 3 * n readable doubles.
#[no_mangle]
pub unsafe extern "C" fn delmesh_domain_add_surface_points(
    d: *mut DelmeshDomain,
    xyz: *const f64,
    n: usize,
) -> DelmeshStatus {
    call("delmesh_domain_add_surface_points", || {
        // SAFETY: the caller's contract.
        let d = unsafe { d.as_mut() }.ok_or_else(|| Failure::null_argument("d"))?;
        // SAFETY: the caller's contract.
        let xyz = unsafe { args::array(xyz, n, 3, "xyz", "n") }?;
        d.domain.add_seeds(xyz.as_chunks::<3>().0)?;
        Ok(())
    })
}

/// Releases a domain; NULL is ignored.
///
/// # Safety
/// `d` is NULL or a domain not yet freed, not in use by a running mesher.
#[no_mangle]
pub unsafe extern "C" fn delmesh_domain_free(d: *mut DelmeshDomain) {
    call("delmesh_domain_free", || {
        if !d.is_null() {
            // SAFETY: `d` came from `Box::into_raw` in a constructor and is freed once.
            drop(unsafe { Box::from_raw(d) });
        }
        Ok(())
    });
}
