//! The result mesh handle and its accessors (API.md "Result mesh").
//!
//! A `DelmeshMesh` is immutable once returned: its arrays are the flat `Vec`s of
//! [`Mesh`], handed out without copying.

use std::ffi::c_char;
use std::ptr::null;
use std::sync::OnceLock;

use super::{args, call, value, DelmeshStatus};
use crate::mesh::Mesh;

/// An opaque result mesh, produced by a `delmesh_*` call through its `DelmeshMesh **out`
/// parameter. The caller owns it and releases it with `delmesh_mesh_free`.
///
/// Thread-safety: a mesh is never modified after it is returned, so any number of threads
/// may call the `const DelmeshMesh *` accessors on it at once; `delmesh_mesh_free` must
/// not run concurrently with any other use of the same mesh.
pub struct DelmeshMesh {
    mesh: Mesh,
    /// The Delaunay cover cells of the 2D triangles and their count, computed on first use.
    cover: OnceLock<(Vec<u32>, usize)>,
}

impl DelmeshMesh {
    /// Moves `mesh` to the heap as a handle owned by the C caller.
    pub fn into_raw(mesh: Mesh) -> *mut DelmeshMesh {
        Box::into_raw(Box::new(DelmeshMesh {
            mesh,
            cover: OnceLock::new(),
        }))
    }

    /// The mesh behind the handle.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The Delaunay cover cells of the 2D triangles ([`crate::mesh2d::cover::cells`]).
    fn cover(&self) -> &(Vec<u32>, usize) {
        self.cover
            .get_or_init(|| crate::mesh2d::cover::cells(&self.mesh))
    }
}

/// `f` of the mesh behind `m`, or 0 for a NULL handle.
///
/// # Safety
/// `m` is NULL or a live handle.
unsafe fn count(function: &str, m: *const DelmeshMesh, f: impl FnOnce(&Mesh) -> usize) -> usize {
    // SAFETY: the caller's contract.
    value(function, 0, || {
        unsafe { m.as_ref() }.map_or(0, |h| f(&h.mesh))
    })
}

/// The first element of the array `f` picks in the mesh behind `m`; NULL for a NULL
/// handle or an empty array.
///
/// # Safety
/// `m` is NULL or a live handle.
unsafe fn array<T>(
    function: &str,
    m: *const DelmeshMesh,
    f: impl FnOnce(&Mesh) -> &[T],
) -> *const T {
    // SAFETY: the caller's contract.
    let handle = unsafe { m.as_ref() };
    value(function, null(), || match handle.map(|h| f(&h.mesh)) {
        Some(values) if !values.is_empty() => values.as_ptr(),
        _ => null(),
    })
}

/// Number of vertices; 0 for a NULL handle.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_vertex_count(m: *const DelmeshMesh) -> usize {
    unsafe { count("delmesh_mesh_vertex_count", m, Mesh::vertex_count) }
}

/// Vertex coordinates, x y z interleaved: 3 * vertex_count doubles. NULL for a NULL
/// handle or a mesh without vertices. Owned by the mesh, valid until `delmesh_mesh_free`.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_vertices(m: *const DelmeshMesh) -> *const f64 {
    unsafe { array("delmesh_mesh_vertices", m, |mesh| &mesh.vertices) }
}

/// Dimension of the feature each vertex lies on, one per vertex: 0 corner, 1 curve,
/// 2 surface, 3 volume, -1 unknown (triangulations do not classify vertices). NULL for
/// a NULL handle or an empty array. Owned by the mesh, valid until `delmesh_mesh_free`.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_vertex_dimensions(m: *const DelmeshMesh) -> *const i8 {
    unsafe {
        array("delmesh_mesh_vertex_dimensions", m, |mesh| {
            &mesh.vertex_dimensions
        })
    }
}

/// Number of tetrahedra; 0 for a NULL handle.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_tetrahedron_count(m: *const DelmeshMesh) -> usize {
    unsafe { count("delmesh_mesh_tetrahedron_count", m, Mesh::tetrahedron_count) }
}

/// Tetrahedra, 4 vertex indices each (4 * tetrahedron_count), positively oriented:
/// `dot(b-a, cross(c-a, d-a)) > 0`. NULL for a NULL handle or no tetrahedra. Owned by
/// the mesh, valid until `delmesh_mesh_free`.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_tetrahedra(m: *const DelmeshMesh) -> *const u32 {
    unsafe { array("delmesh_mesh_tetrahedra", m, |mesh| &mesh.tetrahedra) }
}

/// Subdomain label (> 0) of each tetrahedron (tetrahedron_count entries). NULL for a
/// NULL handle or no tetrahedra. Owned by the mesh, valid until `delmesh_mesh_free`.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_tetrahedron_labels(m: *const DelmeshMesh) -> *const i32 {
    unsafe {
        array("delmesh_mesh_tetrahedron_labels", m, |mesh| {
            &mesh.tetrahedron_labels
        })
    }
}

/// Number of boundary and interface facets; 0 for a NULL handle.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_facet_count(m: *const DelmeshMesh) -> usize {
    unsafe { count("delmesh_mesh_facet_count", m, |mesh| mesh.facets.len() / 3) }
}

/// Boundary and interface facets, 3 vertex indices each (3 * facet_count). NULL for a
/// NULL handle or no facets. Owned by the mesh, valid until `delmesh_mesh_free`.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_facets(m: *const DelmeshMesh) -> *const u32 {
    unsafe { array("delmesh_mesh_facets", m, |mesh| &mesh.facets) }
}

/// Two labels per facet (2 * facet_count): (from, to). The facet normal (right-hand
/// rule) points from subdomain `from` toward subdomain `to`; 0 is the outside. NULL for
/// a NULL handle or no facets. Owned by the mesh, valid until `delmesh_mesh_free`.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_facet_labels(m: *const DelmeshMesh) -> *const i32 {
    unsafe { array("delmesh_mesh_facet_labels", m, |mesh| &mesh.facet_labels) }
}

/// Number of feature-curve edges (2D results: constraint sub-segments); 0 for a NULL
/// handle.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_edge_count(m: *const DelmeshMesh) -> usize {
    unsafe { count("delmesh_mesh_edge_count", m, |mesh| mesh.edges.len() / 2) }
}

/// Edges, 2 vertex indices each (2 * edge_count). NULL for a NULL handle or no edges.
/// Owned by the mesh, valid until `delmesh_mesh_free`.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_edges(m: *const DelmeshMesh) -> *const u32 {
    unsafe { array("delmesh_mesh_edges", m, |mesh| &mesh.edges) }
}

/// Number of triangles of a 2D result; 0 for a NULL handle or a 3D result.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_triangle_count(m: *const DelmeshMesh) -> usize {
    unsafe {
        count("delmesh_mesh_triangle_count", m, |mesh| {
            mesh.triangle_labels.len()
        })
    }
}

/// Triangles of a 2D result, 3 vertex indices each (3 * triangle_count),
/// counter-clockwise. NULL for a NULL handle or no triangles. Owned by the mesh, valid
/// until `delmesh_mesh_free`.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_triangles(m: *const DelmeshMesh) -> *const u32 {
    unsafe { array("delmesh_mesh_triangles", m, |mesh| &mesh.triangles) }
}

/// Region label of each triangle of a 2D result (triangle_count entries). NULL for a
/// NULL handle or no triangles. Owned by the mesh, valid until `delmesh_mesh_free`.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_triangle_labels(m: *const DelmeshMesh) -> *const i32 {
    unsafe {
        array("delmesh_mesh_triangle_labels", m, |mesh| {
            &mesh.triangle_labels
        })
    }
}

/// Number of input points merged onto an earlier exact copy (see `delmesh_mesh_duplicate_of`); 0 for
/// a NULL handle or a result not made from input points.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_duplicate_count(m: *const DelmeshMesh) -> usize {
    unsafe { count("delmesh_mesh_duplicate_count", m, Mesh::duplicate_count) }
}

/// For results made from input points: entry `i` is the first input point of which point
/// `i` is an exact copy (same coordinates; for weighted points, same weight too), `i`
/// itself when it is no copy; vertex_count entries. A merged
/// point keeps its vertex slot but no simplex refers to it. NULL for a NULL handle or
/// other results. Owned by the mesh, valid until `delmesh_mesh_free`.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_duplicate_of(m: *const DelmeshMesh) -> *const u32 {
    unsafe { array("delmesh_mesh_duplicate_of", m, |mesh| &mesh.duplicate_of) }
}

/// Number of cells of the Delaunay cover of a 2D result's triangles (Pébay, Definition
/// 2.3): two triangles sharing an edge belong to one cell when their four vertices are
/// cocircular (exact test), so a cell is a triangle or a convex polygon of four or more
/// cocircular vertices that another Delaunay triangulation of the same points may split
/// differently. Equal to `delmesh_mesh_triangle_count` when no four vertices of adjacent
/// triangles are cocircular. 0 for a NULL handle or a 3D result. Computed on the first call
/// to this function or `delmesh_mesh_triangle_cover_cells`, then kept; thread-safe.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_cover_cell_count(m: *const DelmeshMesh) -> usize {
    // SAFETY: the caller's contract.
    let handle = unsafe { m.as_ref() };
    value("delmesh_mesh_cover_cell_count", 0, || {
        handle.map_or(0, |h| h.cover().1)
    })
}

/// The Delaunay cover cell of each triangle of a 2D result (triangle_count entries, see
/// `delmesh_mesh_cover_cell_count`), cells numbered from 0 in the order of their first
/// triangle. NULL for a NULL handle or no triangles. Owned by the mesh, valid until
/// `delmesh_mesh_free`; thread-safe.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_triangle_cover_cells(m: *const DelmeshMesh) -> *const u32 {
    // SAFETY: the caller's contract.
    let handle = unsafe { m.as_ref() };
    value(
        "delmesh_mesh_triangle_cover_cells",
        null(),
        || match handle.map(|h| &h.cover().0) {
            Some(cells) if !cells.is_empty() => cells.as_ptr(),
            _ => null(),
        },
    )
}

/// Pébay's triangle degradation `α h / r` over the 2D triangles of `m` (`h` the longest
/// edge, `r` the inradius, `α = √3 / 6`: 1 for the equilateral triangle, larger is worse):
/// its best, worst and mean values are written to `*best`, `*worst` and `*mean`, each
/// pointer NULL to skip it. A mesh without 2D triangles gives 0, 0, 0. Errors: NULL `m` ->
/// `DELMESH_ERROR_NULL_ARGUMENT`. Thread-safe.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed; each of `best`, `worst`, `mean` is NULL or points
/// to a writable double.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_triangle_degradation(
    m: *const DelmeshMesh,
    best: *mut f64,
    worst: *mut f64,
    mean: *mut f64,
) -> DelmeshStatus {
    call("delmesh_mesh_triangle_degradation", || {
        let handle = unsafe { args::required(m, "m") }?;
        let d = crate::mesh2d::degradation(&handle.mesh);
        for (out, value) in [(best, d.best), (worst, d.worst), (mean, d.mean)] {
            // SAFETY: NULL or writable (the caller's contract).
            if let Some(out) = unsafe { out.as_mut() } {
                *out = value;
            }
        }
        Ok(())
    })
}

/// Writes the mesh to the file `path` (UTF-8 or the platform's byte path,
/// NUL-terminated), in the format its extension names:
/// - `.mesh`: Medit ASCII (vertices, tetrahedra with their label, facets as triangles
///   whose reference numbers the (from, to) label pair, 2D triangles with their label,
///   edges);
/// - `.msh`: Gmsh 4.1 ASCII (one entity and physical group per label; facets as
///   triangles, one surface entity per (from, to) pair);
/// - `.vtu`: VTK XML UnstructuredGrid ASCII (tetrahedra and 2D triangles, cell data
///   `label`, point data `dimension`).
///
/// An existing file is replaced. Errors: NULL `m` or `path` ->
/// `DELMESH_ERROR_NULL_ARGUMENT`; another extension -> `DELMESH_ERROR_INVALID_ARGUMENT`;
/// the file cannot be written -> `DELMESH_ERROR_IO` (the message names the path and the
/// system's reason; a partial file may be left). Thread-safe for distinct paths.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed; `path` is NULL or a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_write(
    m: *const DelmeshMesh,
    path: *const c_char,
) -> DelmeshStatus {
    call("delmesh_mesh_write", || {
        let handle = unsafe { args::required(m, "m") }?;
        let path = unsafe { args::path(path, "path") }?;
        Ok(crate::io::write(&handle.mesh, &path)?)
    })
}

/// Releases a mesh and every array its accessors returned. NULL is accepted and ignored.
///
/// # Safety
/// `m` is NULL or a mesh not yet freed, not in use by another thread; it must not be
/// used afterwards.
#[no_mangle]
pub unsafe extern "C" fn delmesh_mesh_free(m: *mut DelmeshMesh) {
    value("delmesh_mesh_free", (), || {
        if !m.is_null() {
            // SAFETY: `m` came from `DelmeshMesh::into_raw` and is freed once (caller's contract).
            drop(unsafe { Box::from_raw(m) });
        }
    })
}
