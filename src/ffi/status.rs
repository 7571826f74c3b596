//! Status codes and the per-thread last error message.
//!
//! The thread-local message is the one piece of state delmesh keeps outside a handle;
//! the API requires it so that a status can be explained without an extra out-parameter.

use std::cell::RefCell;
use std::ffi::{c_char, CStr, CString};

use crate::error::{Error, ErrorKind};

/// The outcome of a fallible call. Values are explicit and never reused: a new status
/// is added at the end with a new number.
#[allow(non_camel_case_types)]
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DelmeshStatus {
    /// Success; the out-parameters were written.
    DELMESH_OK = 0,
    /// A required pointer was NULL; the message names the parameter.
    DELMESH_ERROR_NULL_ARGUMENT = 1,
    /// A parameter value is out of range (negative size, NaN, unknown file extension...).
    DELMESH_ERROR_INVALID_ARGUMENT = 2,
    /// The geometry is unusable (NaN coordinate, too few points, all coplanar...).
    DELMESH_ERROR_INVALID_INPUT = 3,
    /// A user callback reported failure.
    DELMESH_ERROR_CALLBACK = 4,
    /// The progress callback asked to stop.
    DELMESH_ERROR_CANCELLED = 5,
    /// A vertex or time budget was reached before the criteria held.
    DELMESH_ERROR_LIMIT = 6,
    /// An allocation failed.
    DELMESH_ERROR_OUT_OF_MEMORY = 7,
    /// A file could not be written (or read); the message names the path and the
    /// operating system's reason.
    DELMESH_ERROR_IO = 8,
    /// A bug in delmesh, including a caught panic; please report it with the message.
    DELMESH_ERROR_INTERNAL = 9,
}

impl From<ErrorKind> for DelmeshStatus {
    fn from(kind: ErrorKind) -> Self {
        use DelmeshStatus::*;
        match kind {
            ErrorKind::InvalidArgument => DELMESH_ERROR_INVALID_ARGUMENT,
            ErrorKind::InvalidInput => DELMESH_ERROR_INVALID_INPUT,
            ErrorKind::Callback => DELMESH_ERROR_CALLBACK,
            ErrorKind::Cancelled => DELMESH_ERROR_CANCELLED,
            ErrorKind::Limit => DELMESH_ERROR_LIMIT,
            ErrorKind::OutOfMemory => DELMESH_ERROR_OUT_OF_MEMORY,
            ErrorKind::Io => DELMESH_ERROR_IO,
            ErrorKind::Internal => DELMESH_ERROR_INTERNAL,
        }
    }
}

/// A failed call as the boundary reports it: a status and a message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Failure {
    pub status: DelmeshStatus,
    pub message: String,
}

impl Failure {
    pub fn new(status: DelmeshStatus, message: impl Into<String>) -> Self {
        Failure {
            status,
            message: message.into(),
        }
    }

    /// The required pointer parameter `parameter` was NULL.
    pub fn null_argument(parameter: &str) -> Self {
        Failure::new(
            DelmeshStatus::DELMESH_ERROR_NULL_ARGUMENT,
            format!("argument `{parameter}` is NULL"),
        )
    }

    /// Stores the message, prefixed with `function`, as the thread's last error.
    pub(crate) fn record(self, function: &str) -> DelmeshStatus {
        set_last_error(&format!("{function}: {}", self.message));
        self.status
    }
}

impl From<Error> for Failure {
    fn from(error: Error) -> Self {
        Failure::new(error.kind.into(), error.message)
    }
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

/// Replaces the calling thread's last error message (NUL bytes inside are dropped).
/// Does nothing while the thread is being torn down (its thread-locals are gone).
fn set_last_error(message: &str) {
    let text = CString::new(message.replace('\0', "")).unwrap_or_default();
    let _ = LAST_ERROR.try_with(|last| *last.borrow_mut() = text);
}

/// The message of the last failed call on the calling thread, or "" if none failed yet.
///
/// Never NULL; NUL-terminated UTF-8. The message starts with the name of the function
/// that failed and names the culprit (parameter, point, path). Owned by delmesh: do not
/// free it. It stays valid until the next failing delmesh call on the same thread (a
/// successful call leaves it in place) or until the thread exits. Thread-safe: each
/// thread has its own message.
#[no_mangle]
pub extern "C" fn delmesh_last_error_message() -> *const c_char {
    // The one export outside `guard` (which reports into it); it cannot panic: the
    // thread-local is reached with `try_with` and is never borrowed mutably across calls.
    LAST_ERROR
        .try_with(|last| last.borrow().as_ptr())
        .unwrap_or(<&CStr>::default().as_ptr())
}
