//! Triangulations of random and degenerate point sets, checked exactly by `validate`.

use delmesh::triangulation::{
    delaunay_tetrahedralize, regular_tetrahedralize, PointState, Triangulation,
};
use delmesh::ErrorKind;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn random_points(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..3 * n).map(|_| rng.gen::<f64>()).collect()
}

fn grid(k: usize) -> Vec<f64> {
    let mut v = Vec::new();
    for x in 0..k {
        for y in 0..k {
            for z in 0..k {
                v.extend([x as f64, y as f64, z as f64]);
            }
        }
    }
    v
}

/// Builds, validates, and returns the triangulation's finite tetrahedron count.
fn check(xyz: &[f64], weights: Option<&[f64]>) -> usize {
    let mut t = Triangulation::new(xyz, weights).unwrap();
    t.insert_all().unwrap();
    t.validate().unwrap();
    let count = t.finite_tetrahedra().count();
    let mesh = t.into_mesh();
    mesh.validate().unwrap();
    assert_eq!(mesh.tetrahedron_count(), count);
    count
}

fn volume(mesh: &delmesh::Mesh) -> f64 {
    mesh.tetrahedra
        .chunks_exact(4)
        .map(|t| {
            let [a, b, c, d] = [0, 1, 2, 3].map(|k| mesh.vertex(t[k]));
            let u = [0, 1, 2].map(|i| b[i] - a[i]);
            let v = [0, 1, 2].map(|i| c[i] - a[i]);
            let w = [0, 1, 2].map(|i| d[i] - a[i]);
            (u[0] * (v[1] * w[2] - v[2] * w[1])
                + u[1] * (v[2] * w[0] - v[0] * w[2])
                + u[2] * (v[0] * w[1] - v[1] * w[0]))
                / 6.0
        })
        .sum()
}

#[test]
fn random_points_are_delaunay() {
    for (n, seed) in [(4, 1), (5, 2), (50, 3), (2000, 4)] {
        check(&random_points(n, seed), None);
    }
}

#[test]
fn cubic_grid_is_triangulated_with_the_cube_volume() {
    let xyz = grid(6);
    check(&xyz, None);
    let mesh = delaunay_tetrahedralize(&xyz).unwrap();
    assert!((volume(&mesh) - 125.0).abs() < 1e-9);
}

#[test]
fn cospherical_points() {
    // All integer points with x^2 + y^2 + z^2 = 25 (exactly cospherical).
    let mut xyz = Vec::new();
    for x in -5i32..=5 {
        for y in -5i32..=5 {
            for z in -5i32..=5 {
                if x * x + y * y + z * z == 25 {
                    xyz.extend([x as f64, y as f64, z as f64]);
                }
            }
        }
    }
    check(&xyz, None);
}

#[test]
fn coplanar_layers_and_duplicates() {
    let mut rng = StdRng::seed_from_u64(7);
    let mut xyz = Vec::new();
    for layer in 0..4 {
        for _ in 0..100 {
            xyz.extend([
                rng.gen_range(0..20) as f64,
                rng.gen_range(0..20) as f64,
                layer as f64,
            ]);
        }
    }
    assert!(check(&xyz, None) > 0);
    let mesh = delaunay_tetrahedralize(&xyz).unwrap();
    assert!(mesh.duplicate_count() > 0);
    for (i, &d) in mesh.duplicate_of.iter().enumerate() {
        assert!(d as usize <= i);
        assert_eq!(mesh.vertex(d), mesh.vertex(i as u32));
    }
}

fn canonical(m: &delmesh::Mesh, map: &dyn Fn(u32) -> u32) -> Vec<[u32; 4]> {
    let mut v: Vec<[u32; 4]> = m
        .tetrahedra
        .chunks_exact(4)
        .map(|t| {
            let mut q = [map(t[0]), map(t[1]), map(t[2]), map(t[3])];
            q.sort_unstable();
            q
        })
        .collect();
    v.sort_unstable();
    v
}

#[test]
fn triangulation_does_not_depend_on_input_order() {
    let xyz = grid(5);
    let a = delaunay_tetrahedralize(&xyz).unwrap();
    let n = xyz.len() / 3;
    let perm: Vec<usize> = (0..n).rev().collect();
    let rev: Vec<f64> = perm
        .iter()
        .flat_map(|&i| xyz[3 * i..3 * i + 3].to_vec())
        .collect();
    let b = delaunay_tetrahedralize(&rev).unwrap();
    assert_eq!(
        canonical(&a, &|i| i),
        canonical(&b, &|i| perm[i as usize] as u32)
    );
}

#[test]
fn regular_random_weights_hide_points() {
    let xyz = random_points(1500, 11);
    let mut rng = StdRng::seed_from_u64(12);
    let w: Vec<f64> = (0..1500).map(|_| rng.gen::<f64>() * 0.01).collect();
    check(&xyz, Some(&w));
    let mut t = Triangulation::new(&xyz, Some(&w)).unwrap();
    t.insert_all().unwrap();
    let hidden = t
        .states()
        .iter()
        .filter(|&&s| s == PointState::Hidden)
        .count();
    assert!(hidden > 0, "no point hidden");
}

#[test]
fn regular_grid_with_equal_and_duplicate_weights() {
    let xyz = grid(4);
    let w = vec![0.5; xyz.len() / 3];
    check(&xyz, Some(&w));
    // The same position twice: the heavier one wins wherever it comes.
    let mut xyz2 = random_points(200, 5);
    xyz2.extend_from_within(0..3);
    xyz2.extend_from_within(3..6);
    let mut w2 = vec![0.0; 202];
    w2[200] = 1e-4; // heavier copy of point 0
    w2[1] = 1e-4; // point 1 heavier than its later copy 201
    check(&xyz2, Some(&w2));
    let mesh = regular_tetrahedralize(&xyz2, &w2).unwrap();
    let used = |v: u32| mesh.tetrahedra.contains(&v);
    assert!(!used(0) && used(200) && used(1) && !used(201));
}

#[test]
fn bad_inputs_are_reported() {
    let err = |xyz: &[f64]| delaunay_tetrahedralize(xyz).unwrap_err();
    assert_eq!(err(&[0.0; 9]).kind, ErrorKind::InvalidInput);
    let mut xyz = random_points(10, 1);
    xyz[7] = f64::NAN;
    assert!(err(&xyz).message.contains("point 2"));
    let flat: Vec<f64> = (0..20)
        .flat_map(|i| [i as f64, (i * i) as f64, 0.0])
        .collect();
    assert!(err(&flat).message.contains("coplanar"));
    let line: Vec<f64> = (0..20)
        .flat_map(|i| [i as f64, 2.0 * i as f64, 3.0 * i as f64])
        .collect();
    assert!(err(&line).message.contains("collinear"));
    assert!(err(&[1.0; 30]).message.contains("coincide"));
    let w = [1.0, f64::INFINITY, 0.0, 0.0, 0.0];
    let e = regular_tetrahedralize(&random_points(5, 3), &w).unwrap_err();
    assert!(e.message.contains("point 1"));
}

#[test]
fn copies_of_hidden_points_are_duplicates() {
    // Unit-cube corners of weight 1 hide interior points of weight 0; each interior point is
    // given twice, so some copy is always inserted after its original is hidden.
    let mut xyz = Vec::new();
    for c in 0..8 {
        xyz.extend([(c & 1) as f64, ((c >> 1) & 1) as f64, ((c >> 2) & 1) as f64]);
    }
    let interior = [[0.3, 0.5, 0.5], [0.4, 0.5, 0.5], [0.6, 0.45, 0.5]];
    for _ in 0..2 {
        for p in interior {
            xyz.extend(p);
        }
    }
    let mut w = vec![1.0; 8];
    w.extend([0.0; 6]);
    check(&xyz, Some(&w));
    let mesh = regular_tetrahedralize(&xyz, &w).unwrap();
    assert_eq!(&mesh.duplicate_of[11..], &[8, 9, 10]);
    assert_eq!(mesh.duplicate_count(), 3);
    assert!((8..14).all(|v| !mesh.tetrahedra.contains(&v)));
}

#[test]
fn output_is_bit_identical_across_runs() {
    let xyz = random_points(3000, 21);
    assert_eq!(
        delaunay_tetrahedralize(&xyz).unwrap(),
        delaunay_tetrahedralize(&xyz).unwrap()
    );
    let w: Vec<f64> = (0..3000).map(|i| f64::from(i % 7) * 1e-4).collect();
    assert_eq!(
        regular_tetrahedralize(&xyz, &w).unwrap(),
        regular_tetrahedralize(&xyz, &w).unwrap()
    );
    let g = grid(7);
    let threads: Vec<_> = (0..2)
        .map(|_| {
            let g = g.clone();
            std::thread::spawn(move || delaunay_tetrahedralize(&g).unwrap())
        })
        .collect();
    let mut results = threads.into_iter().map(|t| t.join().unwrap());
    let (a, b) = (results.next().unwrap(), results.next().unwrap());
    assert_eq!(a, b);
    assert_eq!(a, delaunay_tetrahedralize(&g).unwrap());
}

#[test]
fn quadratic_output_grows_past_the_reservation() {
    // Points on the moment curve (t, t^2, t^3) have a Delaunay triangulation with a number of
    // tetrahedra quadratic in n, far beyond the 7 per point reserved up front.
    let n = 120;
    let xyz: Vec<f64> = (0..n)
        .flat_map(|i| {
            let t = f64::from(i);
            [t, t * t, t * t * t]
        })
        .collect();
    let count = check(&xyz, None);
    assert!(count > 7 * n as usize, "{count} tetrahedra");
}
