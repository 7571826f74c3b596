//! Planar triangulation (API.md "2D").

use std::ffi::c_char;

use super::mesh::DelmeshMesh;
use super::{args, call, DelmeshStatus, Failure};
use crate::mesh::Mesh;
use crate::mesh2d;
use crate::mesh2d::refine::{QualityOptions, RegionSeed};

/// What `delmesh_triangulate_2d` computes.
#[allow(non_camel_case_types)]
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DelmeshMode2d {
    /// Delaunay triangulation of the points; segments ignored.
    DELMESH_MODE2D_DELAUNAY = 0,
    /// Pébay: subdivide the segments a priori until every sub-segment is strongly
    /// Delaunay-admissible; output = Delaunay triangulation of the convex hull of the
    /// augmented point set.
    DELMESH_MODE2D_CONFORMING = 1,
    /// Conforming + Ruppert/Shewchuk Delaunay refinement (off-centers, concentric shells)
    /// inside the domain; output = the triangles of the domain only, holes removed.
    DELMESH_MODE2D_QUALITY = 2,
}

/// Options of `delmesh_triangulate_2d` (all In). Zero-initialize, then set `mode`: zero is
/// the default of every other field.
#[repr(C)]
pub struct DelmeshOptions2d {
    pub mode: DelmeshMode2d,
    /// Quality mode: lower bound on triangle angles, in degrees, at most 34; 0 = no angle
    /// criterion. Triangles skinny because of an input angle below 60 degrees may stay below
    /// it. Other modes: ignored, but must be in [0, 60).
    pub min_angle_degrees: f64,
    /// Quality mode: upper bound on triangle areas; 0 = none.
    pub max_area: f64,
    /// Quality mode: `n_holes` (x, y) seeds; the region containing each is removed.
    pub holes: *const f64,
    pub n_holes: usize,
    /// Quality mode: `n_regions` (x, y, label, max_area) seeds; the triangles reachable from
    /// a seed without crossing a segment get `label` (an integer) and `max_area` as their area
    /// bound (0 = the global one). Triangles in no seeded region have label 1.
    pub regions: *const f64,
    pub n_regions: usize,
    /// Conforming and quality modes: 1 = segments that cross are split at their intersection
    /// points (new vertices, see `delmesh_triangulate_2d`); 0 (default) = crossing segments
    /// are an error. Other values: DELMESH_ERROR_INVALID_ARGUMENT.
    pub split_crossing_segments: i32,
}

/// Triangulates the `n_points` points `xy` (x y interleaved, 2 * n_points doubles) and the
/// `n_segments` constraint segments `segments` (2 * n_segments point indices; NULL allowed
/// when `n_segments` is 0), as `options->mode` says (NULL `options`: conforming mode).
///
/// - DELAUNAY: every triangle of the Delaunay triangulation of the points' convex hull;
///   segments are ignored. Cocircular points are resolved by a deterministic symbolic
///   perturbation.
/// - CONFORMING: Pébay's a-priori subdivision (INRIA RR-3492, Algorithm 3.2): points are
///   added on the segments until every sub-segment is strongly Delaunay-admissible (in every
///   Delaunay triangulation of the points, cocircular ones included); the triangles are the
///   Delaunay triangulation of the convex hull of all points. `delmesh_mesh_edges` lists the
///   sub-segments, input segment after input segment, each from its first point to its
///   second. The number of added points is `delmesh_mesh_vertex_count - n_points`.
/// - QUALITY: the segments are split (at midpoints, or at concentric shells around acute
///   angles) until they are Delaunay edges, then the domain is refined (Ruppert's Delaunay
///   refinement, Shewchuk's concentric shells at small input angles, Üngör's off-centers): points
///   are added until no triangle has an angle below `min_angle_degrees` or an area above its
///   bound, except triangles that are skinny because of an input angle below 60 degrees. The
///   domain is what is enclosed by segments: triangles reachable from the convex hull's
///   outside or from a hole seed without crossing a segment are removed; with no segment the
///   convex hull is the domain (its edges become segments). Input points outside the domain
///   are in no triangle and constrain nothing. Every sub-segment is strongly
///   Delaunay-admissible (in every Delaunay triangulation of the vertices that triangles and
///   sub-segments use), and every triangle has an empty circumcircle.
///
/// Crossing segments: with `options->split_crossing_segments` = 1 (conforming and quality
/// modes), segments that cross (at a point interior to both) are first split there. The
/// crossings are found with exact orientation tests and each intersection point is computed
/// exactly, then rounded once to the nearest doubles; crossings at the same exact point (three
/// or more segments through it) give one vertex. These vertices come right after the input
/// points (`n_points`, `n_points + 1`, ..., in the order of the first pair of crossing
/// segments, by segment index, through each), before the other added points, with dimension
/// 0: each input segment is then the chain of its pieces, and `delmesh_mesh_edges` still
/// lists the sub-segments input segment after input segment along it, through the
/// intersection points. Should rounding make two pieces cross, put a point on a piece or
/// two points on the same coordinates -> DELMESH_ERROR_LIMIT, the message naming them. A
/// segment end on another segment (T-junction) and collinear overlapping segments are not
/// crossings and stay DELMESH_ERROR_INVALID_INPUT ("a point on a segment").
///
/// Output: vertices with z = 0; vertex `i < n_points` is input point `i`, added points
/// follow. A point equal to an earlier one is merged onto it (`delmesh_mesh_duplicate_of`),
/// keeps its slot and is used by nothing; segments through it use the earlier point and a
/// repeated segment is listed once. Triangles are counter-clockwise, label 1 (QUALITY: the
/// region labels). Vertex dimensions: 0 at segment ends and at intersection points of split
/// segments, 1 for points added on segments, 2 for other points, -1 for merged copies (and
/// for every point in DELAUNAY mode). Deterministic.
///
/// On success `*out` receives a new mesh owned by the caller (free it with
/// `delmesh_mesh_free`); on failure `*out` is left untouched. Errors: NULL `xy`, `out`,
/// (with `n_segments > 0`) `segments`, or in QUALITY mode (with a count > 0) `holes` or
/// `regions` -> DELMESH_ERROR_NULL_ARGUMENT; an unknown mode, a negative or non-finite
/// option, a QUALITY angle bound above 34 degrees, a non-integer region label, a
/// `split_crossing_segments` other than 0 or 1 -> DELMESH_ERROR_INVALID_ARGUMENT; refinement
/// that does not finish within 2^24 added points, split segments invalid after rounding ->
/// DELMESH_ERROR_LIMIT; a non-finite coordinate or one of magnitude above 1e60, all points
/// collinear, a segment index out of range, a zero-length segment, a point on a segment, or
/// (unless split) two crossing segments -> DELMESH_ERROR_INVALID_INPUT, the message naming
/// the culprits.
///
/// Thread-safe: calls on different threads run independently; the inputs are only read.
///
/// # Safety
/// `xy` is NULL or points to 2 * n_points readable doubles, `segments` to 2 * n_segments
/// `uint32_t`; `options` is NULL or points to a readable `DelmeshOptions2d`; `out` is NULL or
/// writable.
#[no_mangle]
pub unsafe extern "C" fn delmesh_triangulate_2d(
    xy: *const f64,
    n_points: usize,
    segments: *const u32,
    n_segments: usize,
    options: *const DelmeshOptions2d,
    out: *mut *mut DelmeshMesh,
) -> DelmeshStatus {
    call("delmesh_triangulate_2d", || {
        let xy = unsafe { args::array(xy, n_points, 2, "xy", "n_points") }?;
        let segments = if n_segments == 0 {
            &[][..]
        } else {
            unsafe { args::array(segments, n_segments, 2, "segments", "n_segments") }?
        };
        let mode = unsafe { mode_of(options) }?;
        let out = unsafe { args::out_param(out, "out") }?;
        let mesh = unsafe { triangulate(xy, segments, mode, options, &[], &[]) }?;
        *out = DelmeshMesh::into_raw(mesh);
        Ok(())
    })
}

/// Triangulates the planar straight-line graph of the file `path` as `delmesh_triangulate_2d`
/// does with its points and segments: Triangle `.node` (points only) or `.poly` (points,
/// segments, holes, regional attributes; with no point in the `.poly`, the points of the
/// `.node` file of the same name), or CGAL `.edg` (one segment `x1 y1 x2 y2` a line after the
/// count; equal coordinates are one point, in order of first appearance; a segment from a
/// point to itself adds the point only). The extension (ASCII case ignored) names the format.
///
/// Triangle files are numbered from 0 or 1 as their first point's index says; vertex `i` of
/// the output is the file's point `i` counted from 0. Attributes and boundary markers are
/// read and ignored. In QUALITY mode the file's holes are added to `options->holes`, and its
/// regions to `options->regions` (the regional attribute, which must be an integer, is the
/// label; a negative or absent maximum area means the global bound); other modes ignore them.
///
/// Errors: those of `delmesh_triangulate_2d`; NULL `path` -> DELMESH_ERROR_NULL_ARGUMENT; an
/// unknown extension -> DELMESH_ERROR_INVALID_ARGUMENT; a file that cannot be read ->
/// DELMESH_ERROR_IO; a syntax error -> DELMESH_ERROR_INVALID_INPUT, the message naming the
/// file and the line.
///
/// Thread-safe.
///
/// # Safety
/// `path` is NULL or a NUL-terminated string; `options` is NULL or points to a readable
/// `DelmeshOptions2d`; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn delmesh_triangulate_2d_file(
    path: *const c_char,
    options: *const DelmeshOptions2d,
    out: *mut *mut DelmeshMesh,
) -> DelmeshStatus {
    call("delmesh_triangulate_2d_file", || {
        let path = unsafe { args::path(path, "path") }?;
        let mode = unsafe { mode_of(options) }?;
        let out = unsafe { args::out_param(out, "out") }?;
        let pslg = mesh2d::read::read_pslg(&path)?;
        let mesh = unsafe {
            triangulate(
                &pslg.xy,
                &pslg.segments,
                mode,
                options,
                &pslg.holes,
                &pslg.regions,
            )
        }?;
        *out = DelmeshMesh::into_raw(mesh);
        Ok(())
    })
}

/// The triangulation of `xy`, `segments` in `mode`; in QUALITY mode `holes` and `regions` are
/// added to those of `options`.
///
/// # Safety
/// As `quality_options` when `mode` is QUALITY (then `options` is not NULL).
unsafe fn triangulate(
    xy: &[f64],
    segments: &[u32],
    mode: DelmeshMode2d,
    options: *const DelmeshOptions2d,
    holes: &[[f64; 2]],
    regions: &[RegionSeed],
) -> Result<Mesh, Failure> {
    Ok(match mode {
        DelmeshMode2d::DELMESH_MODE2D_DELAUNAY => mesh2d::delaunay_2d(xy)?,
        DelmeshMode2d::DELMESH_MODE2D_CONFORMING => {
            let conforming = mesh2d::ConformingOptions {
                crossings: unsafe { crossings_of(options) },
                ..Default::default()
            };
            mesh2d::conforming_2d_with(xy, segments, &conforming)?.mesh
        }
        DelmeshMode2d::DELMESH_MODE2D_QUALITY => {
            let mut quality = unsafe { quality_options(options) }?;
            quality.holes.extend_from_slice(holes);
            quality.regions.extend_from_slice(regions);
            mesh2d::quality_2d(xy, segments, &quality)?.mesh
        }
    })
}

/// The mode of `options` (conforming when NULL), its numeric options checked. The mode is
/// read as an integer so that a value outside the enum never becomes a Rust enum.
///
/// # Safety
/// `options` is NULL or points to a readable `DelmeshOptions2d`.
unsafe fn mode_of(options: *const DelmeshOptions2d) -> Result<DelmeshMode2d, Failure> {
    if options.is_null() {
        return Ok(DelmeshMode2d::DELMESH_MODE2D_CONFORMING);
    }
    // SAFETY: non-NULL and readable by the caller's contract; a C enum is an `int`.
    let raw = unsafe { std::ptr::addr_of!((*options).mode).cast::<i32>().read() };
    let mode = match raw {
        0 => DelmeshMode2d::DELMESH_MODE2D_DELAUNAY,
        1 => DelmeshMode2d::DELMESH_MODE2D_CONFORMING,
        2 => DelmeshMode2d::DELMESH_MODE2D_QUALITY,
        other => return Err(invalid(&format!("options->mode: unknown mode {other}"))),
    };
    // SAFETY: as above; the remaining fields are plain numbers.
    let (angle, area) = unsafe { ((*options).min_angle_degrees, (*options).max_area) };
    if !(0.0..60.0).contains(&angle) {
        return Err(invalid(&format!(
            "options->min_angle_degrees = {angle}: must be in [0, 60)"
        )));
    }
    if !(area >= 0.0 && area.is_finite()) {
        return Err(invalid(&format!(
            "options->max_area = {area}: must be finite and >= 0"
        )));
    }
    // SAFETY: as above.
    let split = unsafe { (*options).split_crossing_segments };
    if split != 0 && split != 1 {
        return Err(invalid(&format!(
            "options->split_crossing_segments = {split}: must be 0 or 1"
        )));
    }
    Ok(mode)
}

/// What crossing segments do under `options` (checked by [`mode_of`]; NULL: an error).
///
/// # Safety
/// `options` is NULL or points to a readable `DelmeshOptions2d`.
unsafe fn crossings_of(options: *const DelmeshOptions2d) -> mesh2d::Crossings {
    // SAFETY: non-NULL and readable by the caller's contract.
    if options.is_null() || unsafe { (*options).split_crossing_segments } == 0 {
        mesh2d::Crossings::Reject
    } else {
        mesh2d::Crossings::Split
    }
}

/// The quality criteria and seeds of the non-NULL `options`.
///
/// # Safety
/// `options` points to a readable `DelmeshOptions2d` whose `holes` and `regions` are NULL or
/// point to `2 * n_holes` and `4 * n_regions` readable doubles.
unsafe fn quality_options(options: *const DelmeshOptions2d) -> Result<QualityOptions, Failure> {
    // SAFETY: non-NULL (the QUALITY mode was read from it) and readable by contract.
    let o = unsafe { &*options };
    let holes = if o.n_holes == 0 {
        &[][..]
    } else {
        unsafe { args::array(o.holes, o.n_holes, 2, "options->holes", "options->n_holes") }?
    };
    let regions = if o.n_regions == 0 {
        &[][..]
    } else {
        unsafe {
            args::array(
                o.regions,
                o.n_regions,
                4,
                "options->regions",
                "options->n_regions",
            )
        }?
    };
    let mut seeds = Vec::with_capacity(o.n_regions);
    for (k, r) in regions.chunks_exact(4).enumerate() {
        let label = r[2];
        if !(label.fract() == 0.0 && label.abs() <= i32::MAX as f64) {
            return Err(invalid(&format!(
                "options->regions[{k}]: label {label} is not a 32-bit integer"
            )));
        }
        seeds.push(RegionSeed {
            seed: [r[0], r[1]],
            label: label as i32,
            max_area: r[3],
        });
    }
    Ok(QualityOptions {
        min_angle_degrees: o.min_angle_degrees,
        max_area: o.max_area,
        holes: holes.chunks_exact(2).map(|h| [h[0], h[1]]).collect(),
        regions: seeds,
        off_centers: true,
        crossings: unsafe { crossings_of(options) },
    })
}

fn invalid(message: &str) -> Failure {
    Failure::new(DelmeshStatus::DELMESH_ERROR_INVALID_ARGUMENT, message)
}
