//! 3D Delaunay and regular triangulations (DESIGN.md layer 2).

use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// Delaunay tetrahedralization of `xyz` (3 coordinates per point). Output vertex `i` is
/// input point `i`; duplicates are merged onto their first occurrence (`Mesh::duplicate_of`).
pub fn delaunay_tetrahedralize(xyz: &[f64]) -> Result<Mesh> {
    let _ = xyz;
    Err(Error::internal("not yet available"))
}

/// Regular (weighted Delaunay) tetrahedralization; hidden points are referenced by no tetrahedron.
pub fn regular_tetrahedralize(xyz: &[f64], weights: &[f64]) -> Result<Mesh> {
    let _ = (xyz, weights);
    Err(Error::internal("not yet available"))
}
