//! Checked conversions of C arguments: NULL pointers become `DELMESH_ERROR_NULL_ARGUMENT`
//! naming the parameter, sizes whose byte length overflows become
//! `DELMESH_ERROR_INVALID_ARGUMENT` naming the count.

use std::ffi::{c_char, CStr};
use std::path::PathBuf;

use super::status::{DelmeshStatus, Failure};

/// `p` as a reference, or a NULL-argument failure naming `parameter`.
///
/// # Safety
/// A non-NULL `p` must point to a valid `T` that outlives `'a`.
pub unsafe fn required<'a, T>(p: *const T, parameter: &str) -> Result<&'a T, Failure> {
    // SAFETY: validity is the caller's contract; NULL is handled by `as_ref`.
    unsafe { p.as_ref() }.ok_or_else(|| Failure::null_argument(parameter))
}

/// The out-parameter `out`, checked for NULL; written by the caller only on success.
///
/// # Safety
/// A non-NULL `out` must be valid for writes for `'a`.
pub unsafe fn out_param<'a, T>(
    out: *mut *mut T,
    parameter: &str,
) -> Result<&'a mut *mut T, Failure> {
    // SAFETY: validity is the caller's contract; NULL is handled by `as_mut`.
    unsafe { out.as_mut() }.ok_or_else(|| Failure::null_argument(parameter))
}

/// The array of `count * per_item` values at `p`, named `parameter` (`count` is named
/// `count_name` when its byte length does not fit in an address).
///
/// # Safety
/// A non-NULL `p` must point to `count * per_item` initialized values that outlive `'a`.
pub unsafe fn array<'a, T>(
    p: *const T,
    count: usize,
    per_item: usize,
    parameter: &str,
    count_name: &str,
) -> Result<&'a [T], Failure> {
    if p.is_null() {
        return Err(Failure::null_argument(parameter));
    }
    let len = count
        .checked_mul(per_item)
        .filter(|&len| {
            len.checked_mul(size_of::<T>())
                .is_some_and(|b| b <= isize::MAX as usize)
        })
        .ok_or_else(|| {
            Failure::new(
                DelmeshStatus::DELMESH_ERROR_INVALID_ARGUMENT,
                format!(
                    "`{count_name}` = {count} is too large: `{parameter}` would not fit in memory"
                ),
            )
        })?;
    // SAFETY: `p` is non-NULL, the byte length fits in `isize`, the rest is the caller's contract.
    Ok(unsafe { std::slice::from_raw_parts(p, len) })
}

/// The NUL-terminated path `path` as a file system path.
///
/// # Safety
/// A non-NULL `path` must point to a NUL-terminated string.
pub unsafe fn path(path: *const c_char, parameter: &str) -> Result<PathBuf, Failure> {
    if path.is_null() {
        return Err(Failure::null_argument(parameter));
    }
    // SAFETY: non-NULL and NUL-terminated by the caller's contract.
    let bytes = unsafe { CStr::from_ptr(path) }.to_bytes();
    os_path(bytes).ok_or_else(|| {
        Failure::new(
            DelmeshStatus::DELMESH_ERROR_INVALID_ARGUMENT,
            format!("`{parameter}` is not valid UTF-8"),
        )
    })
}

/// Paths are byte strings on Unix and taken as they are.
#[cfg(unix)]
fn os_path(bytes: &[u8]) -> Option<PathBuf> {
    use std::os::unix::ffi::OsStrExt;
    Some(std::ffi::OsStr::from_bytes(bytes).into())
}

/// Elsewhere paths are given in UTF-8.
#[cfg(not(unix))]
fn os_path(bytes: &[u8]) -> Option<PathBuf> {
    std::str::from_utf8(bytes).ok().map(PathBuf::from)
}
