//! The error type shared by the whole engine.
//!
//! Every fallible engine call returns [`Result<T>`]; the C boundary (`ffi`) maps
//! [`ErrorKind`] one-to-one onto `DelmeshStatus` and keeps the message for
//! `delmesh_last_error_message()`. Messages name the culprit (which point, which
//! parameter) so that a user can fix the input without a debugger.

use std::fmt;

/// What went wrong, at the granularity of the C status codes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    /// A parameter value is out of range (negative size, NaN, ...).
    InvalidArgument,
    /// The geometry is unusable (NaN coordinate, too few points, all coplanar, ...).
    InvalidInput,
    /// A user callback reported failure.
    Callback,
    /// The progress callback asked to stop.
    Cancelled,
    /// A vertex or time budget was reached before the criteria held.
    Limit,
    /// An allocation failed.
    OutOfMemory,
    /// A file could not be read or written.
    Io,
    /// A bug: an invariant did not hold.
    Internal,
}

/// An error with a message that names what is wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Error {
    pub kind: ErrorKind,
    pub message: String,
}

impl Error {
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Error {
            kind,
            message: message.into(),
        }
    }

    pub fn invalid_input(message: impl Into<String>) -> Self {
        Error::new(ErrorKind::InvalidInput, message)
    }

    pub fn invalid_argument(message: impl Into<String>) -> Self {
        Error::new(ErrorKind::InvalidArgument, message)
    }

    pub fn internal(message: impl Into<String>) -> Self {
        Error::new(ErrorKind::Internal, message)
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}: {}", self.kind, self.message)
    }
}

impl std::error::Error for Error {}

pub type Result<T> = std::result::Result<T, Error>;
