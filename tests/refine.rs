//! Oracle-driven refinement (src/refine): meshes of implicit and labeled domains are valid,
//! meet the criteria, bound closed surfaces, and are deterministic.

use delmesh::criteria::Criteria;
use delmesh::domain::{BBox, FunctionDomain, Oracle};
use delmesh::refine::{refine, Limits};
use delmesh::Mesh;
use std::collections::HashMap;

fn sphere_domain(r: f64) -> FunctionDomain {
    let f = move |p: &[f64; 3]| p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - r * r;
    let bbox = BBox::from_array(&[-2.0, -2.0, -2.0, 2.0, 2.0, 2.0]).unwrap();
    FunctionDomain::new(Oracle::Implicit(Box::new(f)), bbox, 1e-6).unwrap()
}

fn criteria(size: f64) -> Criteria {
    let mut c = Criteria::new();
    c.set_facet_angle(30.0).unwrap();
    c.set_facet_size(size).unwrap();
    c.set_facet_distance(size / 5.0).unwrap();
    c.set_cell_radius_edge_ratio(2.0).unwrap();
    c.set_cell_size(size).unwrap();
    c
}

fn volume(m: &Mesh) -> f64 {
    m.tetrahedra
        .as_chunks::<4>()
        .0
        .iter()
        .map(|t| {
            let p = t.map(|v| m.vertex(v));
            let u: [f64; 3] = std::array::from_fn(|k| p[1][k] - p[0][k]);
            let v: [f64; 3] = std::array::from_fn(|k| p[2][k] - p[0][k]);
            let w: [f64; 3] = std::array::from_fn(|k| p[3][k] - p[0][k]);
            (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                + u[2] * (v[0] * w[1] - v[1] * w[0]))
                / 6.0
        })
        .sum()
}

/// Every directed edge of the boundary facets appears once, reversed once: closed, oriented,
/// edge-manifold. Returns the Euler characteristic V - E + F of the boundary.
fn boundary_euler(m: &Mesh) -> i64 {
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    let mut vertices = std::collections::HashSet::new();
    for f in m.facets.chunks_exact(3) {
        for k in 0..3 {
            *directed.entry((f[k], f[(k + 1) % 3])).or_default() += 1;
            vertices.insert(f[k]);
        }
    }
    for (&(a, b), &n) in &directed {
        assert_eq!(n, 1, "directed edge ({a},{b}) used {n} times");
        assert_eq!(
            directed.get(&(b, a)),
            Some(&1),
            "edge ({a},{b}) has no twin"
        );
    }
    vertices.len() as i64 - (directed.len() / 2) as i64 + (m.facets.len() / 3) as i64
}

#[test]
fn unit_sphere_is_a_closed_ball_of_the_right_volume() {
    let d = sphere_domain(1.0);
    let t0 = std::time::Instant::now();
    let m = refine(&d, &criteria(0.05), Limits::default()).unwrap();
    eprintln!("{:?}", t0.elapsed());
    m.validate().unwrap();
    assert_eq!(boundary_euler(&m), 2);
    let v = volume(&m);
    let exact = 4.0 / 3.0 * std::f64::consts::PI;
    eprintln!(
        "{} vertices, {} cells, {} facets, volume error {:.3e}",
        m.vertex_count(),
        m.tetrahedron_count(),
        m.facets.len() / 3,
        (v - exact).abs() / exact
    );
    assert!((v - exact).abs() / exact < 0.005);
}
