//! The C ABI (DESIGN.md layer 8, API.md), kept apart from the engine: this module only
//! checks pointers, converts between C and Rust types and maps engine errors onto
//! `DelmeshStatus`. The header `include/delmesh.h` is generated from it by cbindgen.
//!
//! Every exported function runs its body through [`guard`], the one panic boundary:
//! - a panic becomes `DELMESH_ERROR_INTERNAL` (or the documented neutral value for
//!   functions that return no status) and never unwinds into C;
//! - a failure is recorded as the thread's last error message, prefixed with the name
//!   of the exported function, and returned as a status;
//! - out-parameters are written by the body only once everything has succeeded.
//!
//! # Why no panic hook is installed
//! Rust reports a panic through the process-wide panic hook *before* unwinding starts,
//! and the default hook writes one line to stderr. Replacing the hook (`set_hook`) would
//! silently change process-global state that belongs to the application (which may be
//! written partly in Rust and have its own hook), and a wrapper hook that only filters
//! delmesh's panics would still be one more global installed behind the user's back.
//! So delmesh installs nothing: the engine reports every expected failure as an
//! `Error` value, a panic can only come from a bug, and in that case the process's own
//! hook (by default, a line on stderr) runs once and the panic payload is turned into
//! the `DELMESH_ERROR_INTERNAL` message here. The boundary itself never prints.

pub mod domain;
pub mod mesh;
pub mod mesher;
pub mod quality;
pub mod status;
pub mod surface;
pub mod triangulate;
pub mod triangulate2d;
pub mod version;

mod args;

use std::any::Any;
use std::panic::{catch_unwind, AssertUnwindSafe};

pub use status::{DelmeshStatus, Failure};

/// Runs `body` as the exported function `function`; a panic or a failure is recorded as
/// the calling thread's last error and returned as `Err` with its status.
///
/// `AssertUnwindSafe` is sound here because a body never leaves a caller-visible value
/// half-updated: results are written through out-parameters only after success, and a
/// handle that a panicking body was reading is not modified by it.
pub fn guard<T>(
    function: &str,
    body: impl FnOnce() -> Result<T, Failure>,
) -> Result<T, DelmeshStatus> {
    let outcome = catch_unwind(AssertUnwindSafe(body)).unwrap_or_else(|payload| {
        Err(Failure::new(
            DelmeshStatus::DELMESH_ERROR_INTERNAL,
            format!(
                "internal error (panic): {}",
                panic_message(payload.as_ref())
            ),
        ))
    });
    outcome.map_err(|failure| failure.record(function))
}

/// [`guard`] for functions that return a status.
pub fn call(function: &str, body: impl FnOnce() -> Result<(), Failure>) -> DelmeshStatus {
    match guard(function, body) {
        Ok(()) => DelmeshStatus::DELMESH_OK,
        Err(status) => status,
    }
}

/// [`guard`] for functions that return a value instead of a status: a panic yields
/// `fallback` (and is still recorded as the last error).
pub fn value<T>(function: &str, fallback: T, body: impl FnOnce() -> T) -> T {
    guard(function, || Ok(body())).unwrap_or(fallback)
}

/// The text of a panic payload: `panic!` produces a `&str` or a `String`.
fn panic_message(payload: &(dyn Any + Send)) -> &str {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s
    } else {
        "a panic without a message"
    }
}
