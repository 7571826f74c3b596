//! Tetrahedralization of a triangulated surface that keeps every input triangle as a facet
//! (George and Borouchaki, INRIA RR-4397, 2002, §5).
//!
//! Pipeline:
//! 1. [`validate`]: the input is checked before anything else (finite coordinates, indices,
//!    degenerate and duplicate triangles, edges with a single triangle, self-intersections).
//! 2. The Delaunay triangulation of the surface vertices and of the corners of an enlarged
//!    bounding box (§5.1), so that no input triangle lies on the convex hull.
//! 3. Missing edges, then missing triangles, are recovered (§5.2).
//! 4. Regions are found by flood fill from the box across non-input facets; the box region
//!    is dropped (§5.3, last remark).
//!
//! Invariants of the result: every input triangle is a facet of the output with the same
//! vertex indices; no vertex is added on the input surface; output vertices are the input
//! vertices in input order followed by the Steiner points, all strictly inside a region.

mod bvh;
pub mod validate;

use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// A region seed (TetGen `.poly` semantics): the region containing `point` gets `label`
/// and, when `max_volume > 0`, that bound on its tetrahedra's volumes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegionSeed {
    pub point: [f64; 3],
    pub label: i32,
    pub max_volume: f64,
}

/// A triangulated surface with its region and hole seeds, as the readers return it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Surface {
    /// x y z interleaved.
    pub xyz: Vec<f64>,
    /// Three vertex indices (0-based) per triangle.
    pub triangles: Vec<u32>,
    pub regions: Vec<RegionSeed>,
    /// The region containing each hole seed is removed.
    pub holes: Vec<[f64; 3]>,
}

/// What [`tetrahedralize_surface`] does besides recovering the surface.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceOptions {
    /// 0 = no quality refinement; else cells whose radius-edge ratio is above it are refined
    /// with interior points, never splitting an input triangle.
    pub max_radius_edge_ratio: f64,
    /// 0 = none; else an upper bound on every tetrahedron's volume.
    pub max_volume: f64,
    /// Keep the tetrahedra of the convex hull outside the surface (label 0 is never given:
    /// they get their own region label).
    pub keep_convex_hull: bool,
    pub regions: Vec<RegionSeed>,
    pub holes: Vec<[f64; 3]>,
}

/// Tetrahedralizes the regions that `triangles` (3 indices per triangle into `xyz`, 3
/// coordinates per vertex) enclose, keeping every triangle as a facet.
pub fn tetrahedralize_surface(
    xyz: &[f64],
    triangles: &[u32],
    options: &SurfaceOptions,
) -> Result<Mesh> {
    let (points, rest) = xyz.as_chunks::<3>();
    let (tris, trest) = triangles.as_chunks::<3>();
    if !rest.is_empty() || !trest.is_empty() {
        return Err(Error::invalid_input(
            "coordinates or triangle indices are not a multiple of 3",
        ));
    }
    validate::check_surface(points, tris)?;
    let _ = options;
    Err(Error::internal("surface recovery is not implemented yet"))
}
