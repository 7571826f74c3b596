//! Library and ABI versions.

use std::ffi::{c_char, CStr};

use super::value;

/// Version of the C ABI described by this header. A program checks at start-up that
/// `delmesh_abi_version() == DELMESH_ABI_VERSION`; see the versioning notes at the top.
pub const DELMESH_ABI_VERSION: u32 = 1;

const _: () = assert!(DELMESH_ABI_VERSION == crate::ABI_VERSION);

const VERSION: &CStr =
    match CStr::from_bytes_with_nul(concat!(env!("CARGO_PKG_VERSION"), "\0").as_bytes()) {
        Ok(version) => version,
        Err(_) => panic!("the package version contains a NUL byte"),
    };

/// The library version, "MAJOR.MINOR.PATCH" (NUL-terminated).
///
/// Static storage owned by delmesh: never NULL, never freed, valid for the life of the
/// process. Thread-safe.
#[no_mangle]
pub extern "C" fn delmesh_version_string() -> *const c_char {
    value(
        "delmesh_version_string",
        <&CStr>::default().as_ptr(),
        || VERSION.as_ptr(),
    )
}

/// The ABI version of the loaded library; equals `DELMESH_ABI_VERSION` of the header it
/// was built with. Thread-safe.
#[no_mangle]
pub extern "C" fn delmesh_abi_version() -> u32 {
    value("delmesh_abi_version", 0, || DELMESH_ABI_VERSION)
}
