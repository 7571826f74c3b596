//! The writers, checked by reading their files back with an independent reader: meshio
//! (Debian's python3-meshio). Without python3 and meshio the read-back tests say so and
//! skip.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use delmesh::io::{write, Format};
use delmesh::{ErrorKind, Mesh};

/// Prints what meshio read, one `= key: values...` line per cell block or data array
/// (the marker sets them apart from what meshio itself prints).
const DUMP: &str = r#"
import sys, meshio
m = meshio.read(sys.argv[1])
print("= points:", *m.points.ravel().tolist())
for c in m.cells:
    print(f"= cells {c.type}:", *c.data.ravel().tolist())
for k, arrays in m.cell_data.items():
    print(f"= cell_data {k}:", *[x for a in arrays for x in a.ravel().tolist()])
for k, a in m.point_data.items():
    print(f"= point_data {k}:", *a.ravel().tolist())
"#;

/// A python3 that can import meshio: the one on PATH, else the system's.
fn python_with_meshio() -> Option<&'static str> {
    ["python3", "/usr/bin/python3"].into_iter().find(|python| {
        Command::new(python)
            .args(["-c", "import meshio"])
            .output()
            .is_ok_and(|o| o.status.success())
    })
}

/// What meshio reads from `path`: values per key, blocks of the same key concatenated.
/// `None` (with a message) when no python3 with meshio is available.
fn read_back(path: &Path) -> Option<BTreeMap<String, Vec<f64>>> {
    let Some(python) = python_with_meshio() else {
        eprintln!("skipped: no python3 with meshio (apt-get install python3-meshio)");
        return None;
    };
    let output = Command::new(python)
        .args(["-c", DUMP])
        .arg(path)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "meshio cannot read {}: {stderr}",
        path.display()
    );
    let mut values: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    let stdout = String::from_utf8(output.stdout).unwrap();
    for line in stdout.lines().filter_map(|l| l.strip_prefix("= ")) {
        let (key, rest) = line
            .rsplit_once(':')
            .unwrap_or_else(|| panic!("unexpected line {line:?}"));
        let numbers = rest.split_whitespace().map(|x| x.parse::<f64>().unwrap());
        values.entry(key.to_owned()).or_default().extend(numbers);
    }
    Some(values)
}

/// Two positively oriented tetrahedra sharing the face (1, 2, 3), subdomains 1 and 2,
/// with their boundary facets oriented outward, the interface oriented from 1 to 2, and
/// two edges. Patches: (1,0) = 1, (1,2) = 2, (2,0) = 3.
fn two_tetrahedra() -> Mesh {
    let mesh = Mesh {
        vertices: vec![
            0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1., 1., 1., 1.0e-300,
        ],
        vertex_dimensions: vec![0, 1, 2, 3, -1],
        tetrahedra: vec![0, 1, 2, 3, 1, 2, 3, 4],
        tetrahedron_labels: vec![1, 2],
        facets: vec![
            0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 2, 3, 4, 1, 4, 3, 1, 2, 4,
        ],
        facet_labels: vec![1, 0, 1, 0, 1, 0, 1, 2, 2, 0, 2, 0, 2, 0],
        edges: vec![0, 1, 1, 4],
        ..Mesh::default()
    };
    mesh.validate().unwrap();
    mesh
}

/// Three triangles of a 2D result, regions 5 and 7.
fn three_triangles() -> Mesh {
    Mesh {
        vertices: vec![0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0., 2., 0.5, 0.],
        vertex_dimensions: vec![-1; 5],
        triangles: vec![0, 1, 2, 0, 2, 3, 1, 4, 2],
        triangle_labels: vec![7, 5, 7],
        ..Mesh::default()
    }
}

fn temp_path(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("delmesh-io-{}-{name}", std::process::id()))
}

/// Writes `mesh` to a temporary `name` and reads it back.
fn round_trip(mesh: &Mesh, name: &str) -> Option<BTreeMap<String, Vec<f64>>> {
    let path = temp_path(name);
    write(mesh, &path).unwrap();
    let values = read_back(&path);
    std::fs::remove_file(&path).unwrap();
    values
}

fn as_f64<T: Copy + Into<f64>>(values: &[T]) -> Vec<f64> {
    values.iter().map(|&v| v.into()).collect()
}

fn concat<T: Copy + Into<f64>>(parts: &[&[T]]) -> Vec<f64> {
    parts.iter().flat_map(|p| as_f64(p)).collect()
}

#[test]
fn medit_reads_back() {
    let mesh = two_tetrahedra();
    let Some(read) = round_trip(&mesh, "two.mesh") else {
        return;
    };
    assert_eq!(read["points"], mesh.vertices);
    assert_eq!(read["cells tetra"], as_f64(&mesh.tetrahedra));
    assert_eq!(read["cells triangle"], as_f64(&mesh.facets));
    assert_eq!(read["cells line"], as_f64(&mesh.edges));
    let refs = concat(&[&[1, 2][..], &[1, 1, 1, 2, 3, 3, 3], &[0, 0]]);
    assert_eq!(read["cell_data medit:ref"], refs);
    assert_eq!(read["point_data medit:ref"], vec![0.0; 5]);
}

#[test]
fn gmsh_reads_back() {
    let mesh = two_tetrahedra();
    let Some(read) = round_trip(&mesh, "two.msh") else {
        return;
    };
    assert_eq!(read["points"], mesh.vertices);
    assert_eq!(read["cells tetra"], as_f64(&mesh.tetrahedra));
    assert_eq!(read["cells triangle"], as_f64(&mesh.facets));
    assert_eq!(read["cells line"], as_f64(&mesh.edges));
    // Blocks: the edges, the three patches, then the two subdomains.
    let physical = concat(&[&[1, 1][..], &[1, 1, 1], &[2], &[3, 3, 3], &[1], &[2]]);
    assert_eq!(read["cell_data gmsh:physical"], physical);
}

#[test]
fn vtu_reads_back() {
    let mesh = two_tetrahedra();
    let Some(read) = round_trip(&mesh, "two.vtu") else {
        return;
    };
    assert_eq!(read["points"], mesh.vertices);
    assert_eq!(read["cells tetra"], as_f64(&mesh.tetrahedra));
    assert!(
        !read.contains_key("cells triangle"),
        "facets are not written to .vtu"
    );
    assert_eq!(read["cell_data label"], vec![1.0, 2.0]);
    assert_eq!(
        read["point_data dimension"],
        as_f64(&mesh.vertex_dimensions)
    );
}

#[test]
fn two_dimensional_results_read_back_in_every_format() {
    let mesh = three_triangles();
    for (name, key) in [
        ("tri.mesh", "cell_data medit:ref"),
        ("tri.vtu", "cell_data label"),
    ] {
        let Some(read) = round_trip(&mesh, name) else {
            return;
        };
        assert_eq!(read["cells triangle"], as_f64(&mesh.triangles), "{name}");
        assert_eq!(read[key], vec![7.0, 5.0, 7.0], "{name}");
    }
    let Some(read) = round_trip(&mesh, "tri.msh") else {
        return;
    };
    // One block per region label, in increasing label order.
    assert_eq!(
        read["cells triangle"],
        vec![0., 2., 3., 0., 1., 2., 1., 4., 2.]
    );
    assert_eq!(read["cell_data gmsh:physical"], vec![5.0, 7.0, 7.0]);
}

#[test]
fn writing_is_deterministic() {
    let mesh = two_tetrahedra();
    for format in [Format::Medit, Format::Gmsh, Format::Vtu] {
        let (mut first, mut second) = (Vec::new(), Vec::new());
        format.write(&mesh, &mut first).unwrap();
        format.write(&mesh, &mut second).unwrap();
        assert_eq!(first, second, "{format:?}");
    }
}

#[test]
fn unknown_extensions_and_unwritable_paths_are_reported() {
    let mesh = two_tetrahedra();
    let error = write(&mesh, Path::new("mesh.off")).unwrap_err();
    assert_eq!(error.kind, ErrorKind::InvalidArgument);
    assert!(error.message.contains("\"off\""), "{}", error.message);
    let error = write(&mesh, Path::new("no-extension")).unwrap_err();
    assert_eq!(error.kind, ErrorKind::InvalidArgument);

    let path = temp_path("missing-directory").join("mesh.msh");
    let error = write(&mesh, &path).unwrap_err();
    assert_eq!(error.kind, ErrorKind::Io);
    assert!(
        error.message.contains(&*path.to_string_lossy()),
        "{}",
        error.message
    );
    assert!(
        error.message.contains("No such file or directory"),
        "{}",
        error.message
    );
}
