//! The optimization passes (src/optimize/): perturbation and exudation raise the smallest
//! dihedral angle of refined meshes, keep their boundary and interface facets, surface vertices
//! and subdomain volumes, meet the radius-edge bound, and are deterministic.

use delmesh::criteria::Criteria;
use delmesh::domain::{BBox, FunctionDomain, Oracle};
use delmesh::optimize::{
    exude, optimize, perturb, smooth, ExudeOptions, Optimization, PerturbOptions, SmoothOptions,
};
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

#[derive(Clone, Copy, Debug)]
enum Pass {
    Exude,
    Perturb,
    Smooth,
    Default,
    All,
}

/// The refined mesh, and the same after `pass`.
fn optimized(d: &FunctionDomain, size: f64, pass: Pass) -> (Mesh, Mesh) {
    let cr = criteria(size);
    let c = refine_complex(d, &cr, Limits::default()).unwrap();
    let before = c.to_mesh();
    let mut labeled = c.into_labeled();
    match pass {
        Pass::Exude => drop(exude(&mut labeled, &cr, &ExudeOptions::default()).unwrap()),
        Pass::Perturb => drop(perturb(&mut labeled, &cr, &PerturbOptions::default()).unwrap()),
        Pass::Smooth => drop(smooth(&mut labeled, &cr, &SmoothOptions::default()).unwrap()),
        Pass::Default => optimize(&mut labeled, &cr, &Optimization::default()).unwrap(),
        Pass::All => {
            let all = Optimization {
                smooth: true,
                ..Optimization::default()
            };
            optimize(&mut labeled, &cr, &all).unwrap()
        }
    }
    labeled.tri.validate().unwrap();
    let after = labeled.to_mesh();
    let (qb, qa) = (Quality::of(&before), Quality::of(&after));
    eprintln!(
        "{pass:?}: min dihedral {:.2} -> {:.2}, below 5/10/15: {:?} -> {:?}",
        qb.min_dihedral, qa.min_dihedral, qb.dihedral_below, qa.dihedral_below
    );
    (before, after)
}

/// The coordinates (as bits) of the vertices of dimension 2, sorted.
fn surface_vertices(m: &Mesh) -> Vec<[u64; 3]> {
    let mut out: Vec<[u64; 3]> = (0..m.vertex_count() as u32)
        .filter(|&v| m.vertex_dimensions[v as usize] == 2)
        .map(|v| m.vertex(v).map(f64::to_bits))
        .collect();
    out.sort_unstable();
    out
}

fn check(before: &Mesh, after: &Mesh) {
    after.validate().unwrap();
    assert_eq!(facet_set(before), facet_set(after), "the boundary changed");
    assert_eq!(
        surface_vertices(before),
        surface_vertices(after),
        "a surface vertex moved"
    );
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
    let (before, after) = optimized(&d, 0.1, Pass::Exude);
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
    for pass in [Pass::Exude, Pass::Perturb, Pass::Default] {
        let (before, after) = optimized(&d, 0.1, pass);
        check(&before, &after);
        let (_, again) = optimized(&d, 0.1, pass);
        assert!(after == again, "two runs of {pass:?} differ");
    }
}

#[test]
fn perturbation_and_the_default_passes_remove_slivers_of_a_torus() {
    let torus = |p: &P| {
        let q = (p[0] * p[0] + p[1] * p[1]).sqrt() - 1.0;
        q * q + p[2] * p[2] - 0.35 * 0.35
    };
    let d = domain(Oracle::Implicit(Box::new(torus)));
    for pass in [Pass::Perturb, Pass::Default] {
        let (before, after) = optimized(&d, 0.08, pass);
        check(&before, &after);
    }
}

/// The mean radius ratio (3 inradius / circumradius) of the tetrahedra.
fn mean_radius_ratio(m: &Mesh) -> f64 {
    let sum: f64 = m
        .tetrahedra
        .chunks_exact(4)
        .map(|t| delmesh::quality::tetrahedron([0, 1, 2, 3].map(|k| m.vertex(t[k]))).radius_ratio)
        .sum();
    sum / m.tetrahedron_count() as f64
}

#[test]
fn odt_smoothing_improves_the_mean_shape_and_keeps_the_boundary() {
    let d = domain(Oracle::Implicit(Box::new(|p: &P| norm2(p) - 1.0)));
    let (before, after) = optimized(&d, 0.1, Pass::Smooth);
    after.validate().unwrap();
    assert_eq!(
        facet_set(&before),
        facet_set(&after),
        "the boundary changed"
    );
    assert_eq!(
        surface_vertices(&before),
        surface_vertices(&after),
        "a surface vertex moved"
    );
    let (mb, ma) = (mean_radius_ratio(&before), mean_radius_ratio(&after));
    eprintln!("mean radius ratio {mb:.4} -> {ma:.4}");
    assert!(ma > mb, "mean radius ratio {mb} -> {ma}");
    let (qb, qa) = (Quality::of(&before), Quality::of(&after));
    assert!(
        qa.min_dihedral >= qb.min_dihedral,
        "{} -> {}",
        qb.min_dihedral,
        qa.min_dihedral
    );
    let (all_before, all) = optimized(&d, 0.1, Pass::All);
    check(&all_before, &all);
}
