//! Readers of triangulated surfaces.

use std::path::Path;

use crate::error::{Error, Result};
use crate::recovery::Surface;

/// Reads the surface of the file `path`, in the format its extension names.
pub fn read_surface(path: &Path) -> Result<Surface> {
    Err(Error::invalid_argument(format!(
        "{}: no surface reader yet",
        path.display()
    )))
}
