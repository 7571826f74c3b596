//! Sliver exudation (src/optimize/exude.rs): it raises the smallest dihedral angle of refined
//! meshes, keeps their boundary and interface facets and subdomain volumes, and is deterministic.

use delmesh::criteria::Criteria;
use delmesh::domain::{BBox, FunctionDomain, Oracle};
use delmesh::optimize::{exude, ExudeOptions};
use delmesh::quality::Quality;
use delmesh::refine::{refine_complex, Limits};
use delmesh::Mesh;
use std::collections::BTreeMap;

type P = [f64; 3];

fn norm2(p: &P) -> f64 {
    p[0] * p[0] + p[1] * p[1] + p[2] * p[2]
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

fn domain(oracle: Oracle) -> FunctionDomain {
    let bbox = BBox::from_array(&[-2.0, -2.0, -2.0, 2.0, 2.0, 2.0]).unwrap();
    FunctionDomain::new(oracle, bbox, 1e-6).unwrap()
}

/// Facets by coordinates with their labels (vertex numbers change with exudation).
fn facet_set(m: &Mesh) -> Vec<([[u64; 3]; 3], i32, i32)> {
    let mut out: Vec<_> = m
        .facets
        .chunks_exact(3)
        .zip(m.facet_labels.chunks_exact(2))
        .map(|(f, l)| {
            let p: Vec<[u64; 3]> = f.iter().map(|&v| m.vertex(v).map(f64::to_bits)).collect();
            // Rotate so the smallest vertex comes first: keeps the orientation.
            let r = (0..3).min_by_key(|&k| p[k]).unwrap();
            ([p[r], p[(r + 1) % 3], p[(r + 2) % 3]], l[0], l[1])
        })
        .collect();
    out.sort_unstable();
    out
}

fn volumes(m: &Mesh) -> BTreeMap<i32, f64> {
    let mut v = BTreeMap::new();
    for (t, &l) in m.tetrahedra.chunks_exact(4).zip(&m.tetrahedron_labels) {
        let p: Vec<P> = t.iter().map(|&x| m.vertex(x)).collect();
        let d = |a: &P, b: &P| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let (u, w, z) = (d(&p[1], &p[0]), d(&p[2], &p[0]), d(&p[3], &p[0]));
        let vol = (u[0] * (w[1] * z[2] - w[2] * z[1]) - u[1] * (w[0] * z[2] - w[2] * z[0])
            + u[2] * (w[0] * z[1] - w[1] * z[0]))
            / 6.0;
        *v.entry(l).or_insert(0.0) += vol;
    }
    v
}

fn exuded(d: &FunctionDomain, size: f64) -> (Mesh, Mesh) {
    let cr = criteria(size);
    let c = refine_complex(d, &cr, Limits::default()).unwrap();
    let before = c.to_mesh();
    let mut labeled = c.into_labeled();
    let report = exude(&mut labeled, &cr, &ExudeOptions::default()).unwrap();
    labeled.tri.validate().unwrap();
    let after = labeled.to_mesh();
    let (qb, qa) = (Quality::of(&before), Quality::of(&after));
    eprintln!(
        "{report:?}: min dihedral {:.2} -> {:.2}, below 5/10/15: {:?} -> {:?}",
        qb.min_dihedral, qa.min_dihedral, qb.dihedral_below, qa.dihedral_below
    );
    (before, after)
}

fn check(before: &Mesh, after: &Mesh) {
    after.validate().unwrap();
    assert_eq!(facet_set(before), facet_set(after), "the boundary changed");
    let (vb, va) = (volumes(before), volumes(after));
    for (l, v) in &vb {
        assert!(
            (va[l] - v).abs() <= 1e-12 * v,
            "volume of {l}: {v} -> {}",
            va[l]
        );
    }
    let (qb, qa) = (Quality::of(before), Quality::of(after));
    // The bar for the sphere (CGAL's perturb + exude reaches about 10 degrees there).
    assert!(
        qa.min_dihedral >= 12.0,
        "{} -> {}",
        qb.min_dihedral,
        qa.min_dihedral
    );
    assert!(qb.dihedral_below[1] > 0 && qa.dihedral_below[1] == 0);
    assert!(
        qa.max_radius_edge <= 2.0 * (1.0 + 1e-9),
        "radius-edge {}",
        qa.max_radius_edge
    );
}

#[test]
fn exudation_removes_slivers_of_a_sphere_and_keeps_its_boundary() {
    let d = domain(Oracle::Implicit(Box::new(|p: &P| norm2(p) - 1.0)));
    let (before, after) = exuded(&d, 0.1);
    check(&before, &after);
}

#[test]
fn exudation_keeps_interfaces_between_subdomains() {
    let f = |p: &P| match norm2(p) {
        r2 if r2 < 0.25 => 1,
        r2 if r2 < 1.0 => 2,
        _ => 0,
    };
    let d = domain(Oracle::Labels(Box::new(f)));
    let (before, after) = exuded(&d, 0.1);
    check(&before, &after);
    let (_, again) = exuded(&d, 0.1);
    assert!(after == again, "two runs differ");
}
