//! Tetrahedralization of a triangulated surface (API.md "Surface tetrahedralization").

use std::ffi::c_char;

use super::mesh::DelmeshMesh;
use super::{args, call, DelmeshStatus, Failure};
use crate::recovery::{self, RegionSeed, SurfaceOptions};

/// Options of `delmesh_tetrahedralize_surface` (all In). Zero-initialized = defaults.
#[repr(C)]
pub struct DelmeshSurfaceOptions {
    /// 0 = no quality refinement; else tetrahedra whose circumradius-to-shortest-edge ratio is
    /// above it are refined with interior points (TetGen `-q`), never splitting an input
    /// triangle: a circumcenter beyond the surface, encroaching an input triangle or edge, or
    /// within an input vertex's local feature size is declined (TetGen `-Y`'s rules), so
    /// tetrahedra the surface forces stay above the bound. At least 1.2 when not 0.
    pub max_radius_edge_ratio: f64,
    /// 0 = none; else an upper bound on every tetrahedron's volume (TetGen `-a`), met by
    /// circumcenters, or centroids where those are declined.
    pub max_volume: f64,
    /// 1 = keep the tetrahedra between the surface and the convex hull of the meshed vertices
    /// too (TetGen `-c`): the hull's triangles are recovered like input triangles, and the
    /// regions between the surface and the hull get labels after the surface's regions.
    /// Points may be left on the hull's triangles (vertex dimension 2), never on the input
    /// surface. 0 = drop them.
    pub keep_convex_hull: i32,
}

/// Tetrahedralizes the regions enclosed by the `n_triangles` triangles `triangles` (3 vertex
/// indices each, into the `n_vertices` vertices `xyz`, 3 doubles each), keeping every input
/// triangle as a facet of the output.
///
/// The triangles may bound several regions: an edge shared by more than two triangles (an
/// interface, two solids touching along an edge) is fine. Orientation of the input triangles
/// does not matter. Regions are found by flood fill from outside; the region left after the
/// outside is removed, region after region, gets labels 1, 2, ... in the order of their
/// smallest input triangle index.
///
/// Output: vertex `i < n_vertices` is input vertex `i` (bit for bit); Steiner points follow,
/// all strictly inside a region (none on the surface; with keep_convex_hull, some may lie on
/// the hull's boundary, dimension 2). Tetrahedra are positively oriented.
/// Facet `k` is input triangle `k` with the same vertex order; its labels (from, to) say which
/// region lies on each side (the right-hand normal points from `from` to `to`, 0 = outside).
/// Input vertices no triangle uses are meshed as TetGen meshes the nodes of a `.node` file:
/// one strictly inside a kept region becomes a vertex of the mesh; one outside, in a hole, on
/// an input triangle, at another vertex's position or with a non-finite coordinate is left
/// out. Vertex dimension 2 for surface vertices and Steiner points on a kept hull's boundary,
/// 3 for the other Steiner points and meshed unused
/// vertices, -1 for the vertices left out. Deterministic.
///
/// Errors: NULL `xyz`, `triangles` or `out` -> DELMESH_ERROR_NULL_ARGUMENT; a negative or
/// non-finite option, a ratio in (0, 1.2), keep_convex_hull other than 0 or 1 ->
/// DELMESH_ERROR_INVALID_ARGUMENT; a non-finite
/// coordinate, an index out of range, a degenerate (zero-area) or repeated triangle, an edge
/// with a single triangle, two input vertices at one position, or two triangles that
/// intersect other than along their shared vertices and edge -> DELMESH_ERROR_INVALID_INPUT,
/// the message naming the indices; recovery or refinement that cannot finish within its
/// bounds -> DELMESH_ERROR_LIMIT.
///
/// # Safety
/// `xyz` is NULL or points to 3 * n_vertices readable doubles, `triangles` to 3 * n_triangles
/// `uint32_t`; `options` is NULL or readable; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn delmesh_tetrahedralize_surface(
    xyz: *const f64,
    n_vertices: usize,
    triangles: *const u32,
    n_triangles: usize,
    options: *const DelmeshSurfaceOptions,
    out: *mut *mut DelmeshMesh,
) -> DelmeshStatus {
    call("delmesh_tetrahedralize_surface", || {
        let xyz = unsafe { args::array(xyz, n_vertices, 3, "xyz", "n_vertices") }?;
        let triangles =
            unsafe { args::array(triangles, n_triangles, 3, "triangles", "n_triangles") }?;
        let options = unsafe { options_of(options) }?;
        let out = unsafe { args::out_param(out, "out") }?;
        let mesh = recovery::tetrahedralize_surface(xyz, triangles, &options)?;
        *out = DelmeshMesh::into_raw(mesh);
        Ok(())
    })
}

/// `delmesh_tetrahedralize_surface` with region and hole seeds (TetGen `.poly` semantics):
/// `regions` holds `n_regions` records (x, y, z, label, max_volume): the region containing
/// the point gets `label` (an integer other than 0) and, when `max_volume > 0`, that bound on
/// its tetrahedra's volumes; `holes` holds `n_holes` points (x, y, z): the region containing
/// each is removed. Regions with no seed are labeled as `delmesh_tetrahedralize_surface` says,
/// after the largest seed label. A seed on the surface or outside every region is
/// DELMESH_ERROR_INVALID_ARGUMENT.
///
/// # Safety
/// As `delmesh_tetrahedralize_surface`; `regions` and `holes` are NULL (with a count of 0) or
/// point to 5 * n_regions and 3 * n_holes readable doubles.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn delmesh_tetrahedralize_surface_regions(
    xyz: *const f64,
    n_vertices: usize,
    triangles: *const u32,
    n_triangles: usize,
    regions: *const f64,
    n_regions: usize,
    holes: *const f64,
    n_holes: usize,
    options: *const DelmeshSurfaceOptions,
    out: *mut *mut DelmeshMesh,
) -> DelmeshStatus {
    call("delmesh_tetrahedralize_surface_regions", || {
        let xyz = unsafe { args::array(xyz, n_vertices, 3, "xyz", "n_vertices") }?;
        let triangles =
            unsafe { args::array(triangles, n_triangles, 3, "triangles", "n_triangles") }?;
        let regions = unsafe { optional_array(regions, n_regions, 5, "regions", "n_regions") }?;
        let holes = unsafe { optional_array(holes, n_holes, 3, "holes", "n_holes") }?;
        let mut options = unsafe { options_of(options) }?;
        options.regions = region_seeds(regions)?;
        options.holes = holes.chunks_exact(3).map(|h| [h[0], h[1], h[2]]).collect();
        let out = unsafe { args::out_param(out, "out") }?;
        let mesh = recovery::tetrahedralize_surface(xyz, triangles, &options)?;
        *out = DelmeshMesh::into_raw(mesh);
        Ok(())
    })
}

/// Tetrahedralizes the surface of the file `path` as `delmesh_tetrahedralize_surface_regions`
/// does. Formats, by extension (ASCII case ignored): `.off`, `.stl` (ASCII or binary; equal
/// coordinates are one vertex), `.obj`, `.ply` (ASCII or binary), TetGen `.poly` and
/// `.smesh` (the file's region and hole seeds are used). Polygons, with their holes in
/// `.poly` facets, are triangulated first in their plane with their own corners (ear
/// clipping); the output facets are those triangles.
///
/// Errors: those of `delmesh_tetrahedralize_surface`; NULL `path` ->
/// DELMESH_ERROR_NULL_ARGUMENT; an unknown extension -> DELMESH_ERROR_INVALID_ARGUMENT; an
/// unreadable file -> DELMESH_ERROR_IO; a syntax error -> DELMESH_ERROR_INVALID_INPUT naming
/// the file and the line.
///
/// # Safety
/// `path` is NULL or a NUL-terminated string; `options` is NULL or readable; `out` is NULL or
/// writable.
#[no_mangle]
pub unsafe extern "C" fn delmesh_tetrahedralize_surface_file(
    path: *const c_char,
    options: *const DelmeshSurfaceOptions,
    out: *mut *mut DelmeshMesh,
) -> DelmeshStatus {
    call("delmesh_tetrahedralize_surface_file", || {
        let path = unsafe { args::path(path, "path") }?;
        let mut options = unsafe { options_of(options) }?;
        let out = unsafe { args::out_param(out, "out") }?;
        let surface = crate::io::surface::read_surface(&path)?;
        options.regions = surface.regions;
        options.holes = surface.holes;
        let mesh = recovery::tetrahedralize_surface(&surface.xyz, &surface.triangles, &options)?;
        *out = DelmeshMesh::into_raw(mesh);
        Ok(())
    })
}

/// The options of `options` (defaults when NULL), checked.
///
/// # Safety
/// `options` is NULL or points to a readable `DelmeshSurfaceOptions`.
unsafe fn options_of(options: *const DelmeshSurfaceOptions) -> Result<SurfaceOptions, Failure> {
    if options.is_null() {
        return Ok(SurfaceOptions::default());
    }
    // SAFETY: non-NULL and readable by the caller's contract.
    let o = unsafe { &*options };
    let ratio = o.max_radius_edge_ratio;
    if !(ratio == 0.0 || (ratio >= 1.2 && ratio.is_finite())) {
        return Err(invalid(&format!(
            "options->max_radius_edge_ratio = {ratio}: must be 0 (none) or finite and >= 1.2"
        )));
    }
    let volume = o.max_volume;
    if !(volume >= 0.0 && volume.is_finite()) {
        return Err(invalid(&format!(
            "options->max_volume = {volume}: must be finite and >= 0"
        )));
    }
    if !matches!(o.keep_convex_hull, 0 | 1) {
        return Err(invalid(&format!(
            "options->keep_convex_hull = {}: must be 0 or 1",
            o.keep_convex_hull
        )));
    }
    Ok(SurfaceOptions {
        max_radius_edge_ratio: ratio,
        max_volume: volume,
        keep_convex_hull: o.keep_convex_hull == 1,
        ..SurfaceOptions::default()
    })
}

/// `n` records of `width` doubles at `p`; NULL is allowed when `n` is 0.
///
/// # Safety
/// As `args::array`.
unsafe fn optional_array<'a>(
    p: *const f64,
    n: usize,
    width: usize,
    name: &str,
    count: &str,
) -> Result<&'a [f64], Failure> {
    if n == 0 {
        return Ok(&[]);
    }
    unsafe { args::array(p, n, width, name, count) }
}

/// Region records (x, y, z, label, max_volume) as seeds; the label must be a nonzero 32-bit
/// integer and the volume bound finite and >= 0.
fn region_seeds(records: &[f64]) -> Result<Vec<RegionSeed>, Failure> {
    let mut seeds = Vec::with_capacity(records.len() / 5);
    for (k, r) in records.chunks_exact(5).enumerate() {
        let (label, max_volume) = (r[3], r[4]);
        if !(label.fract() == 0.0 && label.abs() <= i32::MAX as f64 && label != 0.0) {
            return Err(invalid(&format!(
                "regions[{k}]: label {label} is not a nonzero 32-bit integer"
            )));
        }
        if !(max_volume >= 0.0 && max_volume.is_finite()) {
            return Err(invalid(&format!(
                "regions[{k}]: max_volume {max_volume} must be finite and >= 0"
            )));
        }
        seeds.push(RegionSeed {
            point: [r[0], r[1], r[2]],
            label: label as i32,
            max_volume,
        });
    }
    Ok(seeds)
}

fn invalid(message: &str) -> Failure {
    Failure::new(DelmeshStatus::DELMESH_ERROR_INVALID_ARGUMENT, message)
}
