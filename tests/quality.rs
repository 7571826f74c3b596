//! The quality report (src/quality.rs) on tetrahedra whose figures are known in closed form.

use delmesh::quality::{tetrahedron, triangle_min_angle, Quality};
use delmesh::Mesh;

const REGULAR: [[f64; 3]; 4] = [
    [1.0, 1.0, 1.0],
    [1.0, -1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
];

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

#[test]
fn regular_tetrahedron_has_the_textbook_figures() {
    let q = tetrahedron(REGULAR);
    let dihedral = (1.0f64 / 3.0).acos().to_degrees(); // 70.5288 degrees
    assert!(
        close(q.min_dihedral, dihedral) && close(q.max_dihedral, dihedral),
        "{q:?}"
    );
    assert!(close(q.radius_ratio, 1.0), "{q:?}");
    assert!(close(q.radius_edge, 6f64.sqrt() / 4.0), "{q:?}");
    let mut swapped = REGULAR;
    swapped.swap(0, 1);
    assert_eq!(
        tetrahedron(swapped).min_dihedral.to_bits(),
        q.min_dihedral.to_bits()
    );
}

#[test]
fn corner_tetrahedron_and_sliver() {
    // The corner of the unit cube: three right dihedral angles, three of acos(1/sqrt(3)).
    let q = tetrahedron([
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ]);
    assert!(close(q.max_dihedral, 90.0), "{q:?}");
    assert!(
        close(q.min_dihedral, (1.0 / 3f64.sqrt()).acos().to_degrees()),
        "{q:?}"
    );
    // Four points near a circle: two dihedral angles near 180, four near 0.
    let e = 1e-3;
    let q = tetrahedron([
        [1.0, 0.0, e],
        [0.0, 1.0, -e],
        [-1.0, 0.0, e],
        [0.0, -1.0, -e],
    ]);
    assert!(q.min_dihedral < 0.5 && q.max_dihedral > 179.5, "{q:?}");
    assert!(q.radius_ratio < 0.01, "{q:?}");
}

#[test]
fn report_counts_and_histogram() {
    let e = 1e-3;
    let mut m = Mesh::default();
    for p in REGULAR.iter().chain(&[
        [1.0, 0.0, e],
        [0.0, 1.0, -e],
        [-1.0, 0.0, e],
        [0.0, -1.0, -e],
    ]) {
        m.vertices.extend_from_slice(p);
    }
    m.vertex_dimensions = vec![3; 8];
    m.tetrahedra = vec![0, 1, 2, 3, 4, 5, 6, 7];
    m.tetrahedron_labels = vec![1, 1];
    m.facets = vec![0, 1, 2];
    m.facet_labels = vec![1, 0];
    let q = Quality::of(&m);
    assert_eq!(q.tetrahedra, 2);
    assert_eq!(q.dihedral_below, [1, 1, 1]);
    assert_eq!(q.radius_ratio_histogram[0], 1);
    assert_eq!(q.radius_ratio_histogram[9], 1);
    assert!(close(q.min_facet_angle, 60.0), "{}", q.min_facet_angle);
    assert!(close(
        triangle_min_angle([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
        45.0
    ));
}
