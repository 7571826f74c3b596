//! The writers, checked by reading their files back with an independent reader: meshio
//! (Debian's python3-meshio), on hand-made meshes and on a mesh of an oracle domain. Without
//! python3 and meshio the read-back tests say so and skip.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use delmesh::criteria::Criteria;
use delmesh::domain::{BBox, FunctionDomain, Oracle};
use delmesh::io::{write, Format};
use delmesh::refine::{refine, Limits};
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
for k, a in m.field_data.items():
    print(f"= field_data {k}:", *a.ravel().tolist())
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

/// A refined mesh of two nested spheres given by a labeling function: label 1 inside
/// radius 0.5, 2 in the shell out to radius 1, 0 outside.
fn nested_spheres() -> Mesh {
    let label = |p: &[f64; 3]| match p[0] * p[0] + p[1] * p[1] + p[2] * p[2] {
        r2 if r2 < 0.25 => 1,
        r2 if r2 < 1.0 => 2,
        _ => 0,
    };
    let bbox = BBox::from_array(&[-1.5, -1.5, -1.5, 1.5, 1.5, 1.5]).unwrap();
    let domain = FunctionDomain::new(Oracle::Labels(Box::new(label)), bbox, 1e-6).unwrap();
    let mut criteria = Criteria::new();
    criteria.set_facet_angle(30.0).unwrap();
    criteria.set_facet_size(0.15).unwrap();
    criteria.set_facet_distance(0.03).unwrap();
    criteria.set_cell_radius_edge_ratio(2.0).unwrap();
    criteria.set_cell_size(0.15).unwrap();
    let mesh = refine(&domain, &criteria, Limits::default()).unwrap();
    mesh.validate().unwrap();
    mesh
}

/// How many times each value occurs.
fn multiset(values: &[f64]) -> BTreeMap<i64, usize> {
    let mut counts = BTreeMap::new();
    for &v in values {
        assert_eq!(v, v.trunc(), "not an integer: {v}");
        *counts.entry(v as i64).or_default() += 1;
    }
    counts
}

/// The elements (`per` indices each) reordered by increasing key, stably: the order of the
/// Gmsh blocks. Returns the indices and the matching keys.
fn grouped_by(elements: &[u32], per: usize, keys: &[i32]) -> (Vec<f64>, Vec<f64>) {
    let mut order: Vec<usize> = (0..keys.len()).collect();
    order.sort_by_key(|&e| keys[e]);
    let indices = order
        .iter()
        .flat_map(|&e| as_f64(&elements[per * e..per * (e + 1)]))
        .collect();
    (indices, order.iter().map(|&e| keys[e].into()).collect())
}

#[test]
fn a_mesh_of_two_labels_reads_back_in_every_format() {
    let mesh = nested_spheres();
    let (tet_count, facet_count) = (mesh.tetrahedron_count(), mesh.facets.len() / 3);
    let labels = as_f64(&mesh.tetrahedron_labels);
    let label_counts = multiset(&labels);
    assert_eq!(
        label_counts.keys().copied().collect::<Vec<_>>(),
        vec![1, 2],
        "subdomains"
    );

    // Patches, numbered here independently of src/io: the distinct (from, to) pairs in
    // increasing order, from 1. The facets lie on the outer sphere (between 2 and 0) and on
    // the interface (between 1 and 2), each pair in some orientation.
    let pairs: Vec<[i32; 2]> = mesh
        .facet_labels
        .chunks_exact(2)
        .map(|p| [p[0], p[1]])
        .collect();
    let mut distinct = pairs.clone();
    distinct.sort_unstable();
    distinct.dedup();
    let mut unordered: Vec<[i32; 2]> = distinct
        .iter()
        .map(|&[a, b]| [a.min(b), a.max(b)])
        .collect();
    unordered.sort_unstable();
    unordered.dedup();
    assert_eq!(
        unordered,
        vec![[0, 2], [1, 2]],
        "facet label pairs {distinct:?}"
    );
    let patch_of: Vec<i32> = pairs
        .iter()
        .map(|p| 1 + distinct.iter().position(|d| d == p).unwrap() as i32)
        .collect();
    let patch_counts = multiset(&as_f64(&patch_of));
    eprintln!(
        "{} vertices, {tet_count} tetrahedra {label_counts:?}, {facet_count} facets in patches \
         {distinct:?} {patch_counts:?}",
        mesh.vertex_count()
    );

    // Medit: every array in order; references = labels, then patch numbers.
    let Some(read) = round_trip(&mesh, "spheres.mesh") else {
        return;
    };
    assert_eq!(read["points"].len(), 3 * mesh.vertex_count());
    assert_eq!(read["points"], mesh.vertices);
    assert_eq!(read["cells tetra"].len(), 4 * tet_count);
    assert_eq!(read["cells tetra"], as_f64(&mesh.tetrahedra));
    assert_eq!(read["cells triangle"].len(), 3 * facet_count);
    assert_eq!(read["cells triangle"], as_f64(&mesh.facets));
    let refs = &read["cell_data medit:ref"];
    assert_eq!(refs.len(), tet_count + facet_count);
    assert_eq!(refs[..tet_count], labels[..]);
    assert_eq!(multiset(&refs[..tet_count]), label_counts);
    assert_eq!(refs[tet_count..], as_f64(&patch_of)[..]);
    assert_eq!(multiset(&refs[tet_count..]), patch_counts);
    assert!(!read.contains_key("cells line"));

    // Gmsh: one block per patch, then one per subdomain, each in increasing order; the
    // physical names give each patch its (from, to) pair.
    let Some(read) = round_trip(&mesh, "spheres.msh") else {
        return;
    };
    assert_eq!(read["points"], mesh.vertices);
    let (tets, tet_physical) = grouped_by(&mesh.tetrahedra, 4, &mesh.tetrahedron_labels);
    let (facets, facet_physical) = grouped_by(&mesh.facets, 3, &patch_of);
    assert_eq!(read["cells tetra"].len(), 4 * tet_count);
    assert_eq!(read["cells tetra"], tets);
    assert_eq!(read["cells triangle"].len(), 3 * facet_count);
    assert_eq!(read["cells triangle"], facets);
    let physical = &read["cell_data gmsh:physical"];
    assert_eq!(physical.len(), facet_count + tet_count);
    assert_eq!(physical[..facet_count], facet_physical[..]);
    assert_eq!(multiset(&physical[..facet_count]), patch_counts);
    assert_eq!(physical[facet_count..], tet_physical[..]);
    assert_eq!(multiset(&physical[facet_count..]), label_counts);
    for (k, [from, to]) in distinct.iter().enumerate() {
        let name = format!("field_data facets {from} {to}");
        assert_eq!(read.get(&name), Some(&vec![k as f64 + 1.0, 2.0]), "{name}");
    }
    for label in [1, 2] {
        let name = format!("field_data subdomain {label}");
        assert_eq!(read.get(&name), Some(&vec![label as f64, 3.0]), "{name}");
    }

    // VTU: the tetrahedra with their labels, the vertex dimensions; no facets.
    let Some(read) = round_trip(&mesh, "spheres.vtu") else {
        return;
    };
    assert_eq!(read["points"], mesh.vertices);
    assert_eq!(read["cells tetra"], as_f64(&mesh.tetrahedra));
    assert!(!read.contains_key("cells triangle"));
    assert_eq!(read["cell_data label"], labels);
    assert_eq!(multiset(&read["cell_data label"]), label_counts);
    let dimensions = &read["point_data dimension"];
    assert_eq!(*dimensions, as_f64(&mesh.vertex_dimensions));
    // Surface vertices are exactly the vertices of the facets; all others are volume ones.
    let mut on_facets: Vec<u32> = mesh.facets.clone();
    on_facets.sort_unstable();
    on_facets.dedup();
    let mut expected = vec![3.0; mesh.vertex_count()];
    for &v in &on_facets {
        expected[v as usize] = 2.0;
    }
    assert_eq!(*dimensions, expected);
}
