//! Oracle-driven refinement (src/refine): meshes of implicit and labeled domains are valid,
//! meet the criteria, bound closed oriented surfaces of the right topology and volume, and
//! are deterministic; bad callbacks, budgets and cancellation end in the documented errors.

use delmesh::criteria::Criteria;
use delmesh::domain::{BBox, FunctionDomain, Oracle};
use delmesh::refine::{refine, refine_complex, Limits};
use delmesh::{ErrorKind, Mesh};
use std::collections::{BTreeMap, HashMap, HashSet};
use std::f64::consts::PI;

type P = [f64; 3];

fn bbox(h: f64) -> BBox {
    BBox::from_array(&[-h, -h, -h, h, h, h]).unwrap()
}

fn norm2(p: &P) -> f64 {
    p[0] * p[0] + p[1] * p[1] + p[2] * p[2]
}

fn sphere(r: f64) -> FunctionDomain {
    let f = move |p: &P| norm2(p) - r * r;
    FunctionDomain::new(Oracle::Implicit(Box::new(f)), bbox(2.0), 1e-6).unwrap()
}

fn torus(big: f64, small: f64) -> FunctionDomain {
    let f = move |p: &P| {
        let q = (p[0] * p[0] + p[1] * p[1]).sqrt() - big;
        q * q + p[2] * p[2] - small * small
    };
    FunctionDomain::new(Oracle::Implicit(Box::new(f)), bbox(2.0), 1e-6).unwrap()
}

/// Label 1 inside radius 0.5, 2 in the shell up to radius 1.
fn nested_spheres() -> FunctionDomain {
    let f = |p: &P| match norm2(p) {
        r2 if r2 < 0.25 => 1,
        r2 if r2 < 1.0 => 2,
        _ => 0,
    };
    FunctionDomain::new(Oracle::Labels(Box::new(f)), bbox(2.0), 1e-6).unwrap()
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

fn sub(a: &P, b: &P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn tet_volume(m: &Mesh, t: &[u32]) -> f64 {
    let p: Vec<P> = t.iter().map(|&v| m.vertex(v)).collect();
    let (u, v, w) = (sub(&p[1], &p[0]), sub(&p[2], &p[0]), sub(&p[3], &p[0]));
    (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]))
        / 6.0
}

fn volumes(m: &Mesh) -> BTreeMap<i32, f64> {
    let mut v = BTreeMap::new();
    for (t, &l) in m.tetrahedra.chunks_exact(4).zip(&m.tetrahedron_labels) {
        *v.entry(l).or_insert(0.0) += tet_volume(m, t);
    }
    v
}

/// The faces between tetrahedra of different labels (0 outside), each oriented from the
/// tetrahedron's label toward the other, as (sorted vertices) -> (oriented face, from, to).
fn label_changes(m: &Mesh) -> HashMap<[u32; 3], ([u32; 3], i32, i32)> {
    let mut faces: HashMap<[u32; 3], Vec<([u32; 3], i32)>> = HashMap::new();
    for (t, &l) in m.tetrahedra.chunks_exact(4).zip(&m.tetrahedron_labels) {
        // Outward faces of a positively oriented tetrahedron.
        for f in [
            [t[1], t[2], t[3]],
            [t[0], t[3], t[2]],
            [t[0], t[1], t[3]],
            [t[0], t[2], t[1]],
        ] {
            let mut key = f;
            key.sort_unstable();
            faces.entry(key).or_default().push((f, l));
        }
    }
    let mut out = HashMap::new();
    for (key, sides) in faces {
        match sides.as_slice() {
            [(f, l)] => {
                out.insert(key, (*f, *l, 0));
            }
            [(f, a), (_, b)] if a > b => {
                out.insert(key, (*f, *a, *b));
            }
            [(_, a), (f, b)] if b > a => {
                out.insert(key, (*f, *b, *a));
            }
            [_, _] => {}
            _ => panic!("face {key:?} is shared by {} tetrahedra", sides.len()),
        }
    }
    out
}

/// The mesh's facets are exactly the label changes, oriented from `from` toward `to`.
fn check_facets(m: &Mesh) {
    let want = label_changes(m);
    assert_eq!(m.facets.len() / 3, want.len(), "facet count");
    for (f, l) in m.facets.chunks_exact(3).zip(m.facet_labels.chunks_exact(2)) {
        let mut key = [f[0], f[1], f[2]];
        key.sort_unstable();
        let (g, from, to) = want[&key];
        assert_eq!((l[0], l[1]), (from, to), "labels of facet {f:?}");
        let same_cycle = (0..3).any(|r| [f[r], f[(r + 1) % 3], f[(r + 2) % 3]] == g);
        assert!(
            same_cycle,
            "facet {f:?} is not oriented from {from} toward {to}"
        );
    }
}

/// For the facets separating `labels`: every directed edge once, reversed once (closed,
/// oriented, edge-manifold); returns the Euler characteristic per connected component.
fn euler_per_component(m: &Mesh, labels: (i32, i32)) -> Vec<i64> {
    let facets: Vec<&[u32]> = m
        .facets
        .chunks_exact(3)
        .zip(m.facet_labels.chunks_exact(2))
        .filter(|(_, l)| (l[0], l[1]) == labels)
        .map(|(f, _)| f)
        .collect();
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for f in &facets {
        for k in 0..3 {
            *directed.entry((f[k], f[(k + 1) % 3])).or_default() += 1;
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
    // Components through shared vertices (edge-manifold and closed: through edges too).
    let mut parent: HashMap<u32, u32> = HashMap::new();
    fn find(p: &mut HashMap<u32, u32>, x: u32) -> u32 {
        let up = *p.entry(x).or_insert(x);
        if up == x {
            x
        } else {
            let r = find(p, up);
            p.insert(x, r);
            r
        }
    }
    for f in &facets {
        for k in 1..3 {
            let (a, b) = (find(&mut parent, f[0]), find(&mut parent, f[k]));
            parent.insert(a.max(b), a.min(b));
        }
    }
    let mut count: BTreeMap<u32, (HashSet<u32>, usize, usize)> = BTreeMap::new();
    for f in &facets {
        let c = count.entry(find(&mut parent, f[0])).or_default();
        c.0.extend(f.iter());
        c.2 += 1;
    }
    for &(a, _) in directed.keys() {
        count.get_mut(&find(&mut parent, a)).unwrap().1 += 1;
    }
    count
        .values()
        .map(|(v, e2, f)| v.len() as i64 - (*e2 / 2) as i64 + *f as i64)
        .collect()
}

fn relative(v: f64, exact: f64) -> f64 {
    (v - exact).abs() / exact
}

/// Refines, validates the restricted Delaunay triangulation (and that its restricted facets
/// are the output boundary), then the mesh and its facets.
fn checked_mesh(d: &FunctionDomain, cr: &Criteria) -> Mesh {
    let mut c = refine_complex(d, cr, Limits::default()).unwrap();
    c.validate().unwrap();
    assert_eq!(c.boundary_disagreement(), (0, 0));
    let m = c.to_mesh();
    m.validate().unwrap();
    check_facets(&m);
    m
}

#[test]
fn unit_sphere_is_one_closed_ball_of_the_right_volume() {
    let m = checked_mesh(&sphere(1.0), &criteria(0.05));
    assert_eq!(euler_per_component(&m, (1, 0)), vec![2]);
    let smallest = m
        .facets
        .chunks_exact(3)
        .map(|f| min_angle_degrees(&f.iter().map(|&v| m.vertex(v)).collect::<Vec<_>>()))
        .fold(180.0, f64::min);
    assert!(
        smallest >= 30.0 - 1e-9,
        "facet angle {smallest} below the bound 30"
    );
    let v = volumes(&m);
    let error = relative(v[&1], 4.0 / 3.0 * PI);
    eprintln!(
        "sphere: {} vertices, {} cells, volume error {error:.2e}",
        m.vertex_count(),
        m.tetrahedron_count()
    );
    assert!(error < 0.005, "volume error {error}");
}

#[test]
fn surface_vertices_lie_on_the_surface_and_cells_meet_the_ratio() {
    let d = sphere(1.0);
    let m = refine(&d, &criteria(0.1), Limits::default()).unwrap();
    let diagonal = 48f64.sqrt();
    for (v, &dim) in m.vertex_dimensions.iter().enumerate() {
        let r = norm2(&m.vertex(v as u32)).sqrt();
        match dim {
            2 => assert!(
                (r - 1.0).abs() <= 2e-6 * diagonal,
                "vertex {v} at radius {r}"
            ),
            3 => assert!(r < 1.0, "volume vertex {v} at radius {r}"),
            _ => panic!("vertex {v} has dimension {dim}"),
        }
    }
    for t in m.tetrahedra.chunks_exact(4) {
        let p: Vec<P> = t.iter().map(|&v| m.vertex(v)).collect();
        let c = circumcenter(&p);
        let r2 = norm2(&sub(&c, &p[0]));
        let shortest2 = (0..4)
            .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
            .map(|(i, j)| norm2(&sub(&p[i], &p[j])))
            .fold(f64::INFINITY, f64::min);
        assert!(
            r2 / shortest2 <= 4.0 * (1.0 + 1e-9),
            "radius-edge ratio {}",
            (r2 / shortest2).sqrt()
        );
    }
}

fn min_angle_degrees(p: &[P]) -> f64 {
    (0..3)
        .map(|k| {
            let (u, v) = (sub(&p[(k + 1) % 3], &p[k]), sub(&p[(k + 2) % 3], &p[k]));
            let dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
            (dot / (norm2(&u) * norm2(&v)).sqrt())
                .clamp(-1.0, 1.0)
                .acos()
                .to_degrees()
        })
        .fold(180.0, f64::min)
}

fn circumcenter(p: &[P]) -> P {
    let (u, v, w) = (sub(&p[1], &p[0]), sub(&p[2], &p[0]), sub(&p[3], &p[0]));
    let cross = |a: &P, b: &P| -> P {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: &P, b: &P| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (vw, wu, uv) = (cross(&v, &w), cross(&w, &u), cross(&u, &v));
    let d = 2.0 * dot(&u, &vw);
    std::array::from_fn(|k| {
        p[0][k] + (norm2(&u) * vw[k] + norm2(&v) * wu[k] + norm2(&w) * uv[k]) / d
    })
}

#[test]
fn torus_has_genus_one() {
    let d = torus(1.0, 0.35);
    let m = refine(&d, &criteria(0.08), Limits::default()).unwrap();
    m.validate().unwrap();
    check_facets(&m);
    assert_eq!(euler_per_component(&m, (1, 0)), vec![0]);
    // The boundary lies within about the facet distance of the surface: the volume error is
    // at most area * distance / volume.
    let (area, volume) = (4.0 * PI * PI * 0.35, 2.0 * PI * PI * 0.35 * 0.35);
    let error = relative(volumes(&m)[&1], volume);
    eprintln!("torus: volume error {error:.2e}");
    assert!(error < area * 0.016 / volume, "volume error {error}");
}

#[test]
fn nested_spheres_give_two_subdomains_and_an_interface() {
    let m = checked_mesh(&nested_spheres(), &criteria(0.08));
    assert_eq!(euler_per_component(&m, (2, 0)), vec![2]);
    assert_eq!(euler_per_component(&m, (2, 1)), vec![2]);
    let v = volumes(&m);
    let inner = 4.0 / 3.0 * PI * 0.125;
    let shell = 4.0 / 3.0 * PI - inner;
    assert!(relative(v[&1], inner) < 0.02, "inner volume {}", v[&1]);
    assert!(relative(v[&2], shell) < 0.02, "shell volume {}", v[&2]);
}

#[test]
fn two_runs_give_identical_meshes() {
    let d = nested_spheres();
    let a = refine(&d, &criteria(0.15), Limits::default()).unwrap();
    let b = refine(&d, &criteria(0.15), Limits::default()).unwrap();
    assert!(a == b, "two runs differ");
}

#[test]
fn callback_failures_stop_the_run() {
    let nan = |p: &P| if p[2] > 0.5 { f64::NAN } else { norm2(p) - 1.0 };
    let d = FunctionDomain::new(Oracle::Implicit(Box::new(nan)), bbox(2.0), 1e-6).unwrap();
    let e = refine(&d, &criteria(0.2), Limits::default()).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Callback, "{}", e.message);
    assert!(e.message.contains("NaN"), "{}", e.message);

    let negative = |p: &P| {
        if p[0] > 0.9 {
            -3
        } else {
            i32::from(norm2(p) < 1.0)
        }
    };
    let d = FunctionDomain::new(Oracle::Labels(Box::new(negative)), bbox(2.0), 1e-6).unwrap();
    let e = refine(&d, &criteria(0.2), Limits::default()).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Callback, "{}", e.message);
    assert!(e.message.contains("-3"), "{}", e.message);
}

#[test]
fn a_domain_inside_on_its_box_is_invalid_input() {
    let d = FunctionDomain::new(
        Oracle::Implicit(Box::new(|p: &P| norm2(p) - 9.0)),
        bbox(2.0),
        1e-6,
    )
    .unwrap();
    let e = refine(&d, &criteria(0.2), Limits::default()).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidInput, "{}", e.message);
    assert!(e.message.contains("boundary of its bbox"), "{}", e.message);

    let empty =
        FunctionDomain::new(Oracle::Implicit(Box::new(|_: &P| 1.0)), bbox(2.0), 1e-6).unwrap();
    let e = refine(&empty, &criteria(0.2), Limits::default()).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidInput, "{}", e.message);
}

#[test]
fn a_small_component_is_reached_through_seed_points() {
    // Two spheres: one of radius 1, one of radius 0.04 (between grid lines at spacing 1/6).
    let small = [1.5, 1.45, 1.45];
    let f = move |p: &P| (norm2(p) - 1.0).min(norm2(&sub(p, &small)) - 0.0016);
    let mut d = FunctionDomain::new(Oracle::Implicit(Box::new(f)), bbox(2.0), 1e-6).unwrap();
    let without = refine(&d, &criteria(0.3), Limits::default()).unwrap();
    assert_eq!(euler_per_component(&without, (1, 0)), vec![2]);
    let seeds: Vec<P> = [
        [0.04, 0.0, 0.0],
        [-0.04, 0.0, 0.0],
        [0.0, 0.04, 0.0],
        [0.0, 0.0, 0.04],
        [0.0, 0.0, -0.04],
    ]
    .iter()
    .map(|o| [small[0] + o[0], small[1] + o[1], small[2] + o[2]])
    .collect();
    d.add_seeds(&seeds).unwrap();
    let with = refine(&d, &criteria(0.3), Limits::default()).unwrap();
    let mut euler = euler_per_component(&with, (1, 0));
    euler.sort_unstable();
    assert_eq!(euler, vec![2, 2]);
}

#[test]
fn the_vertex_budget_and_cancellation_stop_the_run() {
    let d = sphere(1.0);
    let limits = Limits {
        max_vertices: 500,
        progress: None,
    };
    let e = refine(&d, &criteria(0.05), limits).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Limit, "{}", e.message);

    let mut calls = 0;
    let mut cancel = |_: &delmesh::refine::Progress| {
        calls += 1;
        calls == 2
    };
    let limits = Limits {
        max_vertices: 0,
        progress: Some(&mut cancel),
    };
    let e = refine(&d, &criteria(0.05), limits).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Cancelled, "{}", e.message);
    assert_eq!(calls, 2);
}

#[test]
fn criteria_setters_reject_values_that_cannot_terminate() {
    let mut c = Criteria::new();
    for bad in [f64::NAN, 0.0, -1.0, 31.0] {
        assert!(c.set_facet_angle(bad).is_err(), "angle {bad}");
    }
    for bad in [f64::NAN, 1.9, f64::INFINITY] {
        assert!(c.set_cell_radius_edge_ratio(bad).is_err(), "ratio {bad}");
    }
    for bad in [f64::NAN, 0.0, -0.1, f64::INFINITY] {
        assert!(c.set_facet_size(bad).is_err(), "size {bad}");
        assert!(c.set_facet_distance(bad).is_err(), "distance {bad}");
        assert!(c.set_cell_size(bad).is_err(), "cell size {bad}");
    }
    let e = c.set_cell_radius_edge_ratio(1.5).unwrap_err();
    assert!(e.message.contains("terminate"), "{}", e.message);
}
