//! The C boundary seen from Rust: status values, NULL and oversized arguments, the panic
//! boundary, the thread-local error message, versions and the mesh accessors.

use std::ffi::{c_char, CStr, CString};
use std::ptr::{null, null_mut};

use delmesh::ffi::mesh::*;
use delmesh::ffi::status::delmesh_last_error_message;
use delmesh::ffi::triangulate::{delmesh_delaunay_tetrahedralize, delmesh_regular_tetrahedralize};
use delmesh::ffi::version::{delmesh_abi_version, delmesh_version_string, DELMESH_ABI_VERSION};
use delmesh::ffi::{call, DelmeshStatus, DelmeshStatus::*, Failure};
use delmesh::Mesh;

fn last_error() -> String {
    let message = delmesh_last_error_message();
    assert!(!message.is_null());
    unsafe { CStr::from_ptr(message) }
        .to_str()
        .unwrap()
        .to_owned()
}

/// A pointer that no call may write: out-parameters must stay untouched on failure.
fn sentinel() -> *mut DelmeshMesh {
    std::ptr::NonNull::dangling().as_ptr()
}

const STATUS_VALUES: [(DelmeshStatus, &str, u32); 10] = [
    (DELMESH_OK, "DELMESH_OK", 0),
    (
        DELMESH_ERROR_NULL_ARGUMENT,
        "DELMESH_ERROR_NULL_ARGUMENT",
        1,
    ),
    (
        DELMESH_ERROR_INVALID_ARGUMENT,
        "DELMESH_ERROR_INVALID_ARGUMENT",
        2,
    ),
    (
        DELMESH_ERROR_INVALID_INPUT,
        "DELMESH_ERROR_INVALID_INPUT",
        3,
    ),
    (DELMESH_ERROR_CALLBACK, "DELMESH_ERROR_CALLBACK", 4),
    (DELMESH_ERROR_CANCELLED, "DELMESH_ERROR_CANCELLED", 5),
    (DELMESH_ERROR_LIMIT, "DELMESH_ERROR_LIMIT", 6),
    (
        DELMESH_ERROR_OUT_OF_MEMORY,
        "DELMESH_ERROR_OUT_OF_MEMORY",
        7,
    ),
    (DELMESH_ERROR_IO, "DELMESH_ERROR_IO", 8),
    (DELMESH_ERROR_INTERNAL, "DELMESH_ERROR_INTERNAL", 9),
];

fn header() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/include/delmesh.h")).unwrap()
}

#[test]
fn status_values_are_those_of_the_api_in_rust_and_in_the_header() {
    let header = header();
    for (status, name, value) in STATUS_VALUES {
        assert_eq!(status as u32, value, "{name}");
        assert!(
            header.contains(&format!("{name} = {value},")),
            "{name} = {value} missing from the header"
        );
    }
    assert_eq!(size_of::<DelmeshStatus>(), size_of::<std::ffi::c_int>());
}

#[test]
fn versions_agree_and_parse() {
    assert_eq!(delmesh_abi_version(), DELMESH_ABI_VERSION);
    assert_eq!(DELMESH_ABI_VERSION, delmesh::ABI_VERSION);
    assert!(header().contains(&format!(
        "#define DELMESH_ABI_VERSION {DELMESH_ABI_VERSION}\n"
    )));

    let version = unsafe { CStr::from_ptr(delmesh_version_string()) }
        .to_str()
        .unwrap();
    assert_eq!(version, env!("CARGO_PKG_VERSION"));
    let parts: Vec<u32> = version.split('.').map(|p| p.parse().unwrap()).collect();
    assert_eq!(parts.len(), 3, "{version} is not MAJOR.MINOR.PATCH");
}

#[test]
fn null_arguments_are_named_and_outputs_untouched() {
    let xyz = [0.0; 12];
    let weights = [0.0; 4];
    let mut out = sentinel();
    unsafe {
        assert_eq!(
            delmesh_delaunay_tetrahedralize(null(), 4, &mut out),
            DELMESH_ERROR_NULL_ARGUMENT
        );
        assert!(last_error().contains("`xyz`"), "{}", last_error());
        assert!(
            last_error().starts_with("delmesh_delaunay_tetrahedralize:"),
            "{}",
            last_error()
        );
        assert_eq!(
            delmesh_delaunay_tetrahedralize(xyz.as_ptr(), 4, null_mut()),
            DELMESH_ERROR_NULL_ARGUMENT
        );
        assert!(last_error().contains("`out`"), "{}", last_error());

        let status = delmesh_regular_tetrahedralize(xyz.as_ptr(), null(), 4, &mut out);
        assert_eq!(status, DELMESH_ERROR_NULL_ARGUMENT);
        assert!(last_error().contains("`weights`"), "{}", last_error());
        let status = delmesh_regular_tetrahedralize(null(), weights.as_ptr(), 4, &mut out);
        assert_eq!(status, DELMESH_ERROR_NULL_ARGUMENT);
        assert!(last_error().contains("`xyz`"), "{}", last_error());

        let path = CString::new("never-written.vtu").unwrap();
        assert_eq!(
            delmesh_mesh_write(null(), path.as_ptr()),
            DELMESH_ERROR_NULL_ARGUMENT
        );
        assert!(last_error().contains("`m`"), "{}", last_error());
    }
    assert_eq!(out, sentinel());
}

#[test]
fn a_point_count_whose_size_overflows_is_an_invalid_argument() {
    let xyz = [0.0; 12];
    let mut out = sentinel();
    for n in [usize::MAX, usize::MAX / 3 + 1, isize::MAX as usize / 8] {
        let status = unsafe { delmesh_delaunay_tetrahedralize(xyz.as_ptr(), n, &mut out) };
        assert_eq!(status, DELMESH_ERROR_INVALID_ARGUMENT, "n = {n}");
        assert!(last_error().contains("`n`"), "{}", last_error());
    }
    assert_eq!(out, sentinel());
}

#[test]
fn a_panic_inside_the_boundary_becomes_internal_with_its_message() {
    let status = call("delmesh_test_function", || {
        panic!("invariant {} broken", 42)
    });
    assert_eq!(status, DELMESH_ERROR_INTERNAL);
    let message = last_error();
    assert!(message.starts_with("delmesh_test_function:"), "{message}");
    assert!(message.contains("invariant 42 broken"), "{message}");

    let status = call("delmesh_test_function", || std::panic::panic_any(7_u8));
    assert_eq!(status, DELMESH_ERROR_INTERNAL);
}

#[test]
fn failures_keep_their_status_and_success_keeps_the_last_message() {
    let status = call("delmesh_test_function", || {
        Err(Failure::new(DELMESH_ERROR_LIMIT, "budget"))
    });
    assert_eq!(status, DELMESH_ERROR_LIMIT);
    assert_eq!(last_error(), "delmesh_test_function: budget");
    assert_eq!(call("delmesh_test_function", || Ok(())), DELMESH_OK);
    assert_eq!(last_error(), "delmesh_test_function: budget");
}

#[test]
fn engine_error_kinds_map_one_to_one_onto_statuses() {
    use delmesh::ErrorKind::*;
    let kinds = [
        InvalidArgument,
        InvalidInput,
        Callback,
        Cancelled,
        Limit,
        OutOfMemory,
        Io,
        Internal,
    ];
    let statuses: Vec<u32> = kinds
        .iter()
        .map(|&k| DelmeshStatus::from(k) as u32)
        .collect();
    assert_eq!(statuses, (2..=9).collect::<Vec<u32>>());
}

#[test]
fn the_last_error_message_is_per_thread_and_never_null() {
    let _ = call("delmesh_test_function", || {
        Err(Failure::null_argument("here"))
    });
    let other = std::thread::spawn(last_error).join().unwrap();
    assert_eq!(other, "");
    assert!(last_error().contains("`here`"));
}

#[test]
fn free_accepts_null_and_accessors_of_null_are_empty() {
    unsafe {
        delmesh_mesh_free(null_mut());
        assert_eq!(delmesh_mesh_vertex_count(null()), 0);
        assert_eq!(delmesh_mesh_tetrahedron_count(null()), 0);
        assert_eq!(delmesh_mesh_facet_count(null()), 0);
        assert_eq!(delmesh_mesh_edge_count(null()), 0);
        assert_eq!(delmesh_mesh_triangle_count(null()), 0);
        assert_eq!(delmesh_mesh_duplicate_count(null()), 0);
        assert!(delmesh_mesh_vertices(null()).is_null());
        assert!(delmesh_mesh_vertex_dimensions(null()).is_null());
        assert!(delmesh_mesh_tetrahedra(null()).is_null());
        assert!(delmesh_mesh_tetrahedron_labels(null()).is_null());
        assert!(delmesh_mesh_facets(null()).is_null());
        assert!(delmesh_mesh_facet_labels(null()).is_null());
        assert!(delmesh_mesh_edges(null()).is_null());
        assert!(delmesh_mesh_triangles(null()).is_null());
        assert!(delmesh_mesh_triangle_labels(null()).is_null());
        assert!(delmesh_mesh_duplicate_of(null()).is_null());
    }
}

/// One positively oriented tetrahedron, with a duplicate of its first corner.
fn one_tetrahedron() -> Mesh {
    Mesh {
        vertices: vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0.],
        vertex_dimensions: vec![-1; 5],
        tetrahedra: vec![0, 1, 2, 3],
        tetrahedron_labels: vec![1],
        duplicate_of: vec![0, 1, 2, 3, 0],
        ..Mesh::default()
    }
}

unsafe fn slice<'a, T>(p: *const T, len: usize) -> &'a [T] {
    assert!(!p.is_null());
    unsafe { std::slice::from_raw_parts(p, len) }
}

#[test]
fn accessors_hand_out_the_mesh_arrays_and_null_for_absent_ones() {
    let mesh = one_tetrahedron();
    let m = DelmeshMesh::into_raw(mesh.clone());
    unsafe {
        assert_eq!(delmesh_mesh_vertex_count(m), 5);
        assert_eq!(slice(delmesh_mesh_vertices(m), 15), &mesh.vertices[..]);
        assert_eq!(
            slice(delmesh_mesh_vertex_dimensions(m), 5),
            &mesh.vertex_dimensions[..]
        );
        assert_eq!(delmesh_mesh_tetrahedron_count(m), 1);
        assert_eq!(slice(delmesh_mesh_tetrahedra(m), 4), &[0, 1, 2, 3]);
        assert_eq!(slice(delmesh_mesh_tetrahedron_labels(m), 1), &[1]);
        assert_eq!(delmesh_mesh_duplicate_count(m), 1);
        assert_eq!(slice(delmesh_mesh_duplicate_of(m), 5), &[0, 1, 2, 3, 0]);
        assert_eq!(delmesh_mesh_facet_count(m), 0);
        assert!(delmesh_mesh_facets(m).is_null() && delmesh_mesh_facet_labels(m).is_null());
        assert_eq!(delmesh_mesh_edge_count(m), 0);
        assert!(delmesh_mesh_edges(m).is_null());
        assert_eq!(delmesh_mesh_triangle_count(m), 0);
        assert!(delmesh_mesh_triangles(m).is_null() && delmesh_mesh_triangle_labels(m).is_null());
        delmesh_mesh_free(m);
    }
}

#[test]
fn write_reports_null_path_unknown_extension_and_io_failure() {
    let m = DelmeshMesh::into_raw(one_tetrahedron());
    let write = |path: *const c_char| unsafe { delmesh_mesh_write(m, path) };
    assert_eq!(write(null()), DELMESH_ERROR_NULL_ARGUMENT);
    assert!(last_error().contains("`path`"), "{}", last_error());

    let stl = CString::new("mesh.stl").unwrap();
    assert_eq!(write(stl.as_ptr()), DELMESH_ERROR_INVALID_ARGUMENT);
    assert!(last_error().contains("\"stl\""), "{}", last_error());

    let missing = std::env::temp_dir()
        .join("delmesh-no-such-directory")
        .join("mesh.vtu");
    let missing = CString::new(missing.to_str().unwrap()).unwrap();
    assert_eq!(write(missing.as_ptr()), DELMESH_ERROR_IO);
    assert!(
        last_error().contains("delmesh-no-such-directory"),
        "{}",
        last_error()
    );

    let written = std::env::temp_dir().join(format!("delmesh-ffi-{}.mesh", std::process::id()));
    let path = CString::new(written.to_str().unwrap()).unwrap();
    assert_eq!(write(path.as_ptr()), DELMESH_OK);
    assert!(std::fs::read_to_string(&written)
        .unwrap()
        .starts_with("MeshVersionFormatted 2"));
    std::fs::remove_file(written).unwrap();
    unsafe { delmesh_mesh_free(m) };
}

/// Orientation of tetrahedron `t`, `dot(b-a, cross(c-a, d-a))`, from the C arrays.
fn orientation(xyz: &[f64], tet: &[u32]) -> f64 {
    let p = |k: usize| {
        let i = tet[k] as usize * 3;
        [xyz[i], xyz[i + 1], xyz[i + 2]]
    };
    let (a, b, c, d) = (p(0), p(1), p(2), p(3));
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
}

/// Checks the result of a tetrahedralization of the 5 points of [`one_tetrahedron`] plus
/// an interior point.
fn check_tetrahedralization(status: DelmeshStatus, out: *mut DelmeshMesh, xyz: &[f64]) {
    assert_eq!(status, DELMESH_OK, "{}", last_error());
    assert_ne!(out, sentinel());
    unsafe {
        assert_eq!(delmesh_mesh_vertex_count(out), xyz.len() / 3);
        assert_eq!(slice(delmesh_mesh_vertices(out), xyz.len()), xyz);
        let count = delmesh_mesh_tetrahedron_count(out);
        assert!(count >= 1);
        let tets = slice(delmesh_mesh_tetrahedra(out), 4 * count);
        assert!(tets.chunks_exact(4).all(|t| orientation(xyz, t) > 0.0));
        assert!(slice(delmesh_mesh_tetrahedron_labels(out), count)
            .iter()
            .all(|&l| l == 1));
        assert!(tets.iter().all(|&v| v != 4), "the duplicate point is used");
        delmesh_mesh_free(out);
    }
}

#[test]
fn delaunay_through_the_boundary() {
    let mut xyz = one_tetrahedron().vertices;
    xyz.extend([0.1, 0.1, 0.1]);
    let mut out = sentinel();
    let status = unsafe { delmesh_delaunay_tetrahedralize(xyz.as_ptr(), 6, &mut out) };
    check_tetrahedralization(status, out, &xyz);
}

#[test]
fn regular_through_the_boundary() {
    let mut xyz = one_tetrahedron().vertices;
    xyz.extend([0.1, 0.1, 0.1]);
    let weights = [0.0; 6];
    let mut out = sentinel();
    let status =
        unsafe { delmesh_regular_tetrahedralize(xyz.as_ptr(), weights.as_ptr(), 6, &mut out) };
    check_tetrahedralization(status, out, &xyz);
}
