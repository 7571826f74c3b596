//! Readers of planar straight-line graphs (Triangle `.node` / `.poly`, CGAL `.edg`) and
//! `delmesh_triangulate_2d_file`: small files written to a temporary directory, and the shared
//! 2D files when present (`$DELMESH_CORPUS/2d`, by default `../shared/data/2d`).

use std::ffi::CString;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use delmesh::error::ErrorKind;
use delmesh::ffi::mesh::*;
use delmesh::ffi::status::delmesh_last_error_message;
use delmesh::ffi::triangulate2d::{delmesh_triangulate_2d_file, DelmeshMode2d, DelmeshOptions2d};
use delmesh::ffi::DelmeshStatus;
use delmesh::mesh2d::read::{parse_edg, parse_node, parse_poly, read_pslg};
use delmesh::mesh2d::refine::{QualityOptions, RegionSeed};
use delmesh::mesh2d::{conforming_2d, quality_2d};

/// A fresh file `name` with `text` in a directory of its own under the system's temp dir.
fn write_temp(name: &str, text: &str) -> PathBuf {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "delmesh-read2d-{}-{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn error_of(result: delmesh::error::Result<delmesh::mesh2d::read::Pslg>) -> (ErrorKind, String) {
    let e = result.unwrap_err();
    (e.kind, e.message)
}

/// A unit square with a square hole, 1-based, with attributes and markers, a hole and two
/// regions.
const SQUARE_WITH_HOLE: &str = "# square with a hole
8 2 1 1
1 0 0  5.5 1
2 4 0  5.5 1
3 4 4  5.5 1
4 0 4  5.5 1
5 1 1  0 2   # inner square
6 3 1  0 2
7 3 3  0 2
8 1 3  0 2

8 1
1 1 2 1
2 2 3 1
3 3 4 1
4 4 1 1
5 5 6 2
6 6 7 2
7 7 8 2
8 8 5 2
1
1 2 2
2
1 0.5 0.5 7 0.25
2 3.5 3.5 9 -1
";

#[test]
fn poly_with_attributes_markers_holes_and_regions() {
    let p = parse_poly(SQUARE_WITH_HOLE, "sq.poly", None).unwrap();
    assert_eq!(p.n_points(), 8);
    assert_eq!(p.first_index, 1);
    assert_eq!(&p.xy[..4], &[0.0, 0.0, 4.0, 0.0]);
    assert_eq!(p.n_attributes, 1);
    assert_eq!(p.point_attributes[0], 5.5);
    assert_eq!(p.point_markers, vec![1, 1, 1, 1, 2, 2, 2, 2]);
    assert_eq!(&p.segments[..4], &[0, 1, 1, 2]);
    assert_eq!(&p.segments[14..], &[7, 4]);
    assert_eq!(p.segment_markers.len(), 8);
    assert_eq!(p.holes, vec![[2.0, 2.0]]);
    assert_eq!(
        p.regions,
        vec![
            RegionSeed {
                seed: [0.5, 0.5],
                label: 7,
                max_area: 0.25
            },
            RegionSeed {
                seed: [3.5, 3.5],
                label: 9,
                max_area: 0.0
            }
        ]
    );
    let options = QualityOptions {
        min_angle_degrees: 25.0,
        holes: p.holes.clone(),
        regions: p.regions.clone(),
        ..QualityOptions::default()
    };
    let q = quality_2d(&p.xy, &p.segments, &options).unwrap();
    let labels: std::collections::HashSet<i32> = q.mesh.triangle_labels.iter().copied().collect();
    // Both seeds are in the one region around the hole: one label.
    assert_eq!(labels.len(), 1, "{labels:?}");
    assert!(
        labels.is_subset(&[7, 9].into_iter().collect()),
        "{labels:?}"
    );
    // No triangle in the hole.
    for t in q.mesh.triangles.chunks_exact(3) {
        let c = t.iter().fold([0.0, 0.0], |c, &v| {
            let x = q.mesh.vertex(v);
            [c[0] + x[0] / 3.0, c[1] + x[1] / 3.0]
        });
        assert!(!(1.0 < c[0] && c[0] < 3.0 && 1.0 < c[1] && c[1] < 3.0));
    }
}

#[test]
fn zero_based_files_and_missing_sections() {
    let p = parse_poly(
        "3 2\n0 0 0\n1 1 0\n2 0 1\n3 0\n0 0 1\n1 1 2\n2 2 0\n",
        "t.poly",
        None,
    )
    .unwrap();
    assert_eq!(p.first_index, 0);
    assert_eq!(p.segments, vec![0, 1, 1, 2, 2, 0]);
    assert!(p.holes.is_empty() && p.regions.is_empty());
    let node = parse_node("3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n", "t.node").unwrap();
    assert_eq!(node.xy, vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
    assert!(node.segments.is_empty());
}

#[test]
fn poly_without_points_reads_the_node_file() {
    let node = write_temp("shape.node", "4 2 0 0\n1 0 0\n2 2 0\n3 2 2\n4 0 2\n");
    let poly = node.with_extension("poly");
    std::fs::write(&poly, "0 2 0 0\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n").unwrap();
    let p = read_pslg(&poly).unwrap();
    assert_eq!(p.n_points(), 4);
    assert_eq!(p.segments, vec![0, 1, 1, 2, 2, 3, 3, 0]);
    std::fs::remove_file(&node).unwrap();
    let (kind, message) = error_of(read_pslg(&poly));
    assert_eq!(kind, ErrorKind::Io);
    assert!(message.contains("shape.node"), "{message}");
}

#[test]
fn errors_name_the_line() {
    let cases: &[(&str, &str)] = &[
        ("3 2 0 0\n1 0 0\n2 1 0\n", "t.poly:3: end of file"),
        ("3 3 0 0\n", "t.poly:1: dimension 3"),
        (
            "1 2 0 0\n\n# c\n1 0 zero\n0 0\n",
            "t.poly:4: y \"zero\" is not a number",
        ),
        (
            "2 2 0 0\n1 0 0\n3 1 0\n",
            "t.poly:3: point index 3: expected 2",
        ),
        ("2 2 0 0\n2 0 0\n3 1 0\n", "t.poly:2: first point index 2"),
        (
            "2 2 0 0\n1 0 0\n2 1 0\n1 0\n1 1 3\n",
            "t.poly:5: segment end 3 is not a point index (1 to 2)",
        ),
        (
            "2 2 0 0\n1 0 0\n2 1 0\n1 0\n1 1\n",
            "t.poly:5: expected <index> <end> <end>",
        ),
        (
            "2 2 0 0\n1 0 0\n2 1 0\n0 0\n0\n1\n1 0 0 1.5 0\n",
            "t.poly:7: regional attribute 1.5",
        ),
        (
            "2 2 0 0\n1 0 0\n2 1 0\n0 0\n0\n0\n7\n",
            "t.poly:7: unexpected content",
        ),
        ("-1 2 0 0\n", "t.poly:1: point count -1 is negative"),
    ];
    for (text, expected) in cases {
        let (kind, message) = error_of(parse_poly(text, "t.poly", None));
        assert_eq!(kind, ErrorKind::InvalidInput, "{text}");
        assert!(
            message.contains(expected),
            "{message} (expected {expected})"
        );
    }
    let edg: &[(&str, &str)] = &[
        (
            "2\n0 0 1 0\n",
            "t.edg:2: end of file where coordinate x of segment 2",
        ),
        (
            "1\n0 0 1 q\n",
            "t.edg:2: coordinate y of segment 1 of 1: \"q\"",
        ),
        ("x\n", "t.edg:1: segment count \"x\""),
        ("1\n0 0 1 0\n5\n", "t.edg:3: unexpected \"5\""),
    ];
    for (text, expected) in edg {
        let (kind, message) = error_of(parse_edg(text, "t.edg"));
        assert_eq!(kind, ErrorKind::InvalidInput, "{text}");
        assert!(
            message.contains(expected),
            "{message} (expected {expected})"
        );
    }
    let (kind, _) = error_of(read_pslg(Path::new("a.stl")));
    assert_eq!(kind, ErrorKind::InvalidArgument);
    let (kind, _) = error_of(read_pslg(Path::new("/nonexistent/a.edg")));
    assert_eq!(kind, ErrorKind::Io);
}

#[test]
fn edg_merges_equal_points_and_drops_point_segments() {
    let p = parse_edg(
        "4\n0 0 1 0\n1 0 1 1\n\n1 1 0 0\n0.5 0.25 0.5 0.25\n",
        "t.edg",
    )
    .unwrap();
    assert_eq!(p.n_points(), 4);
    assert_eq!(p.segments, vec![0, 1, 1, 2, 2, 0]);
    let c = conforming_2d(&p.xy, &p.segments).unwrap();
    assert_eq!(c.mesh.vertex_count(), 4);
}

fn options(mode: DelmeshMode2d, angle: f64, holes: &[f64]) -> DelmeshOptions2d {
    DelmeshOptions2d {
        mode,
        min_angle_degrees: angle,
        max_area: 0.0,
        holes: if holes.is_empty() {
            std::ptr::null()
        } else {
            holes.as_ptr()
        },
        n_holes: holes.len() / 2,
        regions: std::ptr::null(),
        n_regions: 0,
        split_crossing_segments: 0,
    }
}

/// `delmesh_triangulate_2d_file` on `path`: the triangle count, or the status and message.
fn triangulate_file(path: &Path, o: &DelmeshOptions2d) -> Result<usize, (DelmeshStatus, String)> {
    let c = CString::new(path.to_str().unwrap()).unwrap();
    let mut mesh = std::ptr::null_mut();
    let status = unsafe { delmesh_triangulate_2d_file(c.as_ptr(), o, &mut mesh) };
    if status != DelmeshStatus::DELMESH_OK {
        let message = unsafe { std::ffi::CStr::from_ptr(delmesh_last_error_message()) };
        return Err((status, message.to_string_lossy().into_owned()));
    }
    let n = unsafe { delmesh_mesh_triangle_count(mesh) };
    unsafe { delmesh_mesh_free(mesh) };
    Ok(n)
}

#[test]
fn c_api_adds_the_file_holes_to_the_options() {
    let path = write_temp("square.poly", SQUARE_WITH_HOLE);
    let quality = options(DelmeshMode2d::DELMESH_MODE2D_QUALITY, 25.0, &[]);
    let with_hole = triangulate_file(&path, &quality).unwrap();
    // The same without the file's hole and regions: the hole is meshed too.
    let plain = SQUARE_WITH_HOLE
        .split("1\n1 2 2\n")
        .next()
        .unwrap()
        .to_string()
        + "0\n";
    let plain_path = write_temp("plain.poly", &plain);
    let filled = triangulate_file(&plain_path, &quality).unwrap();
    assert!(filled > with_hole, "{filled} vs {with_hole}");
    // The hole given by the options instead.
    let by_options = options(DelmeshMode2d::DELMESH_MODE2D_QUALITY, 25.0, &[2.0, 2.0]);
    assert_eq!(
        triangulate_file(&plain_path, &by_options).unwrap(),
        with_hole
    );
    // NULL options: conforming mode, the convex hull triangulated.
    let c = CString::new(path.to_str().unwrap()).unwrap();
    let mut mesh = std::ptr::null_mut();
    let status = unsafe { delmesh_triangulate_2d_file(c.as_ptr(), std::ptr::null(), &mut mesh) };
    assert_eq!(status, DelmeshStatus::DELMESH_OK);
    assert!(unsafe { delmesh_mesh_triangle_count(mesh) } >= 8);
    unsafe { delmesh_mesh_free(mesh) };
    // Errors.
    let bad = write_temp("bad.edg", "1\n0 0 1\n");
    let (status, message) = triangulate_file(&bad, &quality).unwrap_err();
    assert_eq!(status, DelmeshStatus::DELMESH_ERROR_INVALID_INPUT);
    assert!(
        message.starts_with("delmesh_triangulate_2d_file") && message.contains("bad.edg:2"),
        "{message}"
    );
    let (status, _) = triangulate_file(Path::new("/nonexistent/x.poly"), &quality).unwrap_err();
    assert_eq!(status, DelmeshStatus::DELMESH_ERROR_IO);
    let mut mesh = std::ptr::null_mut();
    let status = unsafe { delmesh_triangulate_2d_file(std::ptr::null(), &quality, &mut mesh) };
    assert_eq!(status, DelmeshStatus::DELMESH_ERROR_NULL_ARGUMENT);
}

/// The shared 2D files, when present.
fn corpus_2d() -> Option<PathBuf> {
    let root = std::env::var_os("DELMESH_CORPUS")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data"));
    let dir = root.join("2d");
    dir.is_dir().then_some(dir)
}

#[test]
fn shared_files_read_and_mesh() {
    let Some(dir) = corpus_2d() else {
        eprintln!("skipped: no shared 2D data");
        return;
    };
    let mut names: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            matches!(
                p.extension().and_then(|e| e.to_str()),
                Some("poly" | "edg" | "node")
            )
        })
        .collect();
    names.sort();
    assert!(!names.is_empty());
    for path in names {
        let p = read_pslg(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(p.n_points() >= 3, "{}", path.display());
        assert_eq!(p.segments.len() % 2, 0);
        assert!(p.segments.iter().all(|&i| (i as usize) < p.n_points()));
        // Quality mode meshes what the segments enclose (nothing for an open star of segments).
        let quality = options(DelmeshMode2d::DELMESH_MODE2D_QUALITY, 25.0, &[]);
        let n = triangulate_file(&path, &quality)
            .unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
        let conforming = options(DelmeshMode2d::DELMESH_MODE2D_CONFORMING, 0.0, &[]);
        let n_conforming = triangulate_file(&path, &conforming)
            .unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
        assert!(n_conforming > 0, "{}", path.display());
        eprintln!(
            "{}: {} points, {} segments, {} holes: {n} triangles at 25 degrees",
            path.file_name().unwrap().to_string_lossy(),
            p.n_points(),
            p.segments.len() / 2,
            p.holes.len()
        );
    }
}
