//! Planar triangulations: the 2D Delaunay triangulation, Pébay's classification `Θ₂` and
//! strong Delaunay-admissibility (Theorem 2.1), and the conforming subdivision (Algorithm 3.2)
//! on the paper's situations. Admissibility of the output is checked independently, in exact
//! rational arithmetic.

use std::collections::{HashMap, HashSet};

use delmesh::error::ErrorKind;
use delmesh::mesh2d::classify::{classify, Theta2};
use delmesh::mesh2d::cloud::Cloud;
use delmesh::mesh2d::cover;
use delmesh::mesh2d::delaunay::Delaunay2d;
use delmesh::mesh2d::exact::incircle_sos;
use delmesh::mesh2d::refine::{QualityOptions, RegionSeed};
use delmesh::mesh2d::subdivide::Algorithm;
use delmesh::mesh2d::{
    conforming_2d, conforming_2d_with, delaunay_2d, quality_2d, validate_mesh, Conforming2d,
    ConformingOptions, Crossings, Quality2d, DIMENSION_CORNER,
};
use delmesh::predicates::{incircle_coplanar_sos, orient2d, Sign};
use delmesh::Mesh;
use num_rational::BigRational;
use rand::{Rng, SeedableRng};

// ---------------------------------------------------------------- helpers

fn cloud_of(points: &[[f64; 2]]) -> Cloud {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let mut cloud = Cloud::new(lo, hi, points.len());
    for p in points {
        cloud.push(*p);
    }
    cloud
}

fn flat(points: &[[f64; 2]]) -> Vec<f64> {
    points.iter().flat_map(|p| [p[0], p[1]]).collect()
}

fn vertex2(mesh: &Mesh, i: u32) -> [f64; 2] {
    let v = mesh.vertex(i);
    [v[0], v[1]]
}

fn rational(x: f64) -> BigRational {
    BigRational::from_float(x).expect("finite coordinate")
}

/// Exact `(a - q) . (b - q) <= 0`: `q` in the closed small disk of `[a b]`, in rationals.
fn in_closed_small_disk(a: [f64; 2], b: [f64; 2], q: [f64; 2]) -> bool {
    let d = |k: usize| (rational(a[k]) - rational(q[k])) * (rational(b[k]) - rational(q[k]));
    let dot = d(0) + d(1);
    dot <= BigRational::from_integer(0.into())
}

/// Every constraint sub-edge of `mesh` is strongly Delaunay-admissible relative to all its
/// vertices (those a triangle or an edge uses; in quality mode, input points outside the
/// domain are used by nothing): its closed small disk holds no other vertex (checked in rationals, by brute
/// force), or else it is in the Delaunay cover of the vertices (an edge of the triangulation
/// whose two triangles are not cocircular, or a hull edge).
fn assert_admissible(mesh: &Mesh, case: &str) {
    let n = mesh.vertex_count() as u32;
    let referenced: HashSet<u32> = mesh.triangles.iter().chain(&mesh.edges).copied().collect();
    let used: Vec<u32> = (0..n).filter(|i| referenced.contains(i)).collect();
    let points: Vec<[f64; 2]> = (0..n).map(|i| vertex2(mesh, i)).collect();
    let dt = Delaunay2d::of_subset(&points, |i| referenced.contains(&i))
        .expect("triangulation of the output vertices");
    let edges = dt.directed_edges();
    for (e, edge) in mesh.edges.chunks_exact(2).enumerate() {
        let (a, b) = (points[edge[0] as usize], points[edge[1] as usize]);
        let empty = used
            .iter()
            .filter(|&&q| q != edge[0] && q != edge[1])
            .all(|&q| !in_closed_small_disk(a, b, points[q as usize]));
        assert!(
            empty || dt.in_delaunay_cover(edge[0], edge[1], &edges),
            "{case}: sub-edge {e} {edge:?} is not strongly Delaunay-admissible"
        );
    }
}

/// Every input segment is the union of sub-edges: a chain from its first end to its second,
/// through added points lying on the segment up to rounding, in order along it.
fn assert_union(mesh: &Mesh, xy: &[[f64; 2]], segments: &[[u32; 2]], case: &str) {
    let n_input = xy.len() as u32;
    let mut next: HashMap<u32, Vec<u32>> = HashMap::new();
    for e in mesh.edges.chunks_exact(2) {
        next.entry(e[0]).or_default().push(e[1]);
        next.entry(e[1]).or_default().push(e[0]);
    }
    let mut covered = HashSet::new();
    for (k, s) in segments.iter().enumerate() {
        let (a, b) = (xy[s[0] as usize], xy[s[1] as usize]);
        let len2 = (b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2);
        let (mut prev, mut cur, mut last_t) = (u32::MAX, s[0], 0.0);
        let mut steps = 0;
        while cur != s[1] {
            let step = next
                .get(&cur)
                .and_then(|list| {
                    list.iter().copied().find(|&v| {
                        v != prev && (v == s[1] || v >= n_input) && {
                            let p = vertex2(mesh, v);
                            let t = ((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1]))
                                / len2;
                            let h = ((p[0] - a[0]) * (b[1] - a[1]) - (p[1] - a[1]) * (b[0] - a[0]))
                                .abs()
                                / len2;
                            t > last_t && t <= 1.0 + 1e-12 && h < 1e-12
                        }
                    })
                })
                .unwrap_or_else(|| {
                    panic!("{case}: segment {k} {s:?} is not a chain of sub-edges (stuck at {cur})")
                });
            covered.insert((cur.min(step), cur.max(step)));
            let p = vertex2(mesh, step);
            last_t = ((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1])) / len2;
            prev = cur;
            cur = step;
            steps += 1;
            assert!(steps <= mesh.edges.len(), "{case}: segment {k} loops");
        }
    }
    assert_eq!(
        covered.len() * 2,
        mesh.edges.len(),
        "{case}: sub-edges outside every segment"
    );
}

fn conform(xy: &[[f64; 2]], segments: &[[u32; 2]], case: &str) -> Conforming2d {
    conform_with(xy, segments, case, Algorithm::ClosedNodes)
}

fn conform_with(
    xy: &[[f64; 2]],
    segments: &[[u32; 2]],
    case: &str,
    algorithm: Algorithm,
) -> Conforming2d {
    let options = ConformingOptions {
        algorithm,
        ..Default::default()
    };
    conform_checked(xy, segments, case, &options)
}

fn conform_checked(
    xy: &[[f64; 2]],
    segments: &[[u32; 2]],
    case: &str,
    options: &ConformingOptions,
) -> Conforming2d {
    let flat_segments: Vec<u32> = segments.iter().flatten().copied().collect();
    let out = conforming_2d_with(&flat(xy), &flat_segments, options)
        .unwrap_or_else(|e| panic!("{case}: {e}"));
    validate_mesh(&out.mesh).unwrap_or_else(|e| panic!("{case}: {e}"));
    assert_admissible(&out.mesh, case);
    assert_union(&out.mesh, xy, segments, case);
    assert_no_cell_across_constraints(&out.mesh, case);
    let again = conforming_2d_with(&flat(xy), &flat_segments, options).expect("second run");
    assert_eq!(out.mesh, again.mesh, "{case}: not deterministic");
    eprintln!(
        "{case} ({options:?}): {} points, {} segments -> {} inserted ({} intersections, {} projections, {} cleanings, {} nodes), degradation worst {:.1} mean {:.2}",
        xy.len(),
        segments.len(),
        out.inserted,
        out.intersections,
        out.subdivision.projections,
        out.subdivision.cleanings,
        out.subdivision.nodes_cleaned,
        out.degradation.worst,
        out.degradation.mean
    );
    out
}

fn polyline(n: usize, closed: bool) -> Vec<[u32; 2]> {
    let mut s: Vec<[u32; 2]> = (0..n as u32 - 1).map(|i| [i, i + 1]).collect();
    if closed {
        s.push([n as u32 - 1, 0]);
    }
    s
}

/// Theorem 2.1: a strongly admissible sub-edge is a Delaunay cover edge, so its two
/// triangles are in different cover cells.
fn assert_no_cell_across_constraints(mesh: &Mesh, case: &str) {
    let (cells, _) = cover::cells(mesh);
    let mut triangle_of: HashMap<(u32, u32), usize> = HashMap::new();
    for (t, v) in mesh.triangles.chunks_exact(3).enumerate() {
        for k in 0..3 {
            triangle_of.insert((v[k], v[(k + 1) % 3]), t);
        }
    }
    for e in mesh.edges.chunks_exact(2) {
        if let (Some(&t), Some(&u)) = (
            triangle_of.get(&(e[0], e[1])),
            triangle_of.get(&(e[1], e[0])),
        ) {
            assert_ne!(
                cells[t], cells[u],
                "{case}: a cover cell spans sub-edge {e:?}"
            );
        }
    }
}

fn grid(nx: usize, ny: usize) -> Vec<[f64; 2]> {
    (0..ny)
        .flat_map(|y| (0..nx).map(move |x| [x as f64, y as f64]))
        .collect()
}

/// `n` points uniform in the unit square, from `seed`.
fn random_points(n: usize, seed: u64) -> Vec<[f64; 2]> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    (0..n)
        .map(|_| [rng.gen::<f64>(), rng.gen::<f64>()])
        .collect()
}

/// The points of `points` at positions no earlier point has.
fn distinct(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let first = delmesh::mesh2d::delaunay::first_duplicates(points);
    (0..points.len())
        .filter(|&i| first[i] as usize == i)
        .map(|i| points[i])
        .collect()
}

fn sorted_triangles(mesh: &Mesh) -> HashSet<[u32; 3]> {
    mesh.triangles
        .chunks_exact(3)
        .map(|t| {
            let mut t = [t[0], t[1], t[2]];
            t.sort_unstable();
            t
        })
        .collect()
}

// ---------------------------------------------------------------- Delaunay

#[test]
fn delaunay_of_random_points_is_valid_and_order_independent() {
    let points = random_points(2000, 7);
    let dt = Delaunay2d::new(&points).expect("triangulation");
    dt.validate().expect("valid");
    let mesh = delaunay_2d(&flat(&points)).expect("mesh");
    validate_mesh(&mesh).expect("valid mesh");
    let reversed: Vec<[f64; 2]> = points.iter().rev().copied().collect();
    let mesh2 = delaunay_2d(&flat(&reversed)).expect("mesh");
    let n = points.len() as u32;
    let renamed: HashSet<[u32; 3]> = sorted_triangles(&mesh2)
        .into_iter()
        .map(|t| {
            let mut t = t.map(|i| n - 1 - i);
            t.sort_unstable();
            t
        })
        .collect();
    assert_eq!(sorted_triangles(&mesh), renamed);
}

#[test]
fn delaunay_cover_cells() {
    // A grid: every unit square is a cell of two triangles.
    let mesh = delaunay_2d(&flat(&grid(9, 6))).expect("grid");
    let (cells, count) = cover::cells(&mesh);
    assert_eq!(count, 8 * 5);
    let mut sizes = vec![0; count];
    for &c in &cells {
        sizes[c as usize] += 1;
    }
    assert!(sizes.iter().all(|&s| s == 2), "{sizes:?}");
    // The 12 integer points on the circle of radius 5 and the centre: the centre is inside
    // the circle, so no four points of adjacent triangles are cocircular.
    let mut ring: Vec<[f64; 2]> = [[5.0, 0.0], [4.0, 3.0], [3.0, 4.0]]
        .into_iter()
        .flat_map(|[x, y]| [[x, y], [-y, x], [-x, -y], [y, -x]])
        .collect();
    let mesh = delaunay_2d(&flat(&ring)).expect("ring");
    assert_eq!(cover::cells(&mesh).1, 1, "12 cocircular points: one cell");
    ring.push([0.0, 0.0]);
    let mesh = delaunay_2d(&flat(&ring)).expect("ring and centre");
    assert_eq!(cover::cells(&mesh).1, mesh.triangles.len() / 3);
    // Random points, and grids: cells agree with the triangulation's own cover test.
    let random = random_points(500, 11);
    for points in [random, grid(12, 9)] {
        let mesh = delaunay_2d(&flat(&points)).expect("mesh");
        let (cells, _) = cover::cells(&mesh);
        let dt = Delaunay2d::new(&points).expect("triangulation");
        let edges = dt.directed_edges();
        let mut triangle_of = HashMap::new();
        for (t, v) in mesh.triangles.chunks_exact(3).enumerate() {
            for k in 0..3 {
                triangle_of.insert((v[k], v[(k + 1) % 3]), t);
            }
        }
        for (&(a, b), &t) in &triangle_of {
            if let Some(&u) = triangle_of.get(&(b, a)) {
                assert_eq!(
                    cells[t] != cells[u],
                    dt.in_delaunay_cover(a, b, &edges),
                    "edge ({a}, {b})"
                );
            }
        }
    }
}

#[test]
fn delaunay_of_cocircular_grids_is_valid_and_deterministic() {
    for (nx, ny) in [(2, 2), (3, 3), (10, 7), (40, 40)] {
        let points = grid(nx, ny);
        let dt = Delaunay2d::new(&points).expect("triangulation");
        dt.validate().expect("valid");
        let mesh = delaunay_2d(&flat(&points)).expect("mesh");
        assert_eq!(
            mesh.triangles.len() / 3,
            2 * (nx - 1) * (ny - 1),
            "{nx}x{ny}"
        );
        let mut shuffled = points.clone();
        shuffled.reverse();
        let mesh2 = delaunay_2d(&flat(&shuffled)).expect("mesh");
        let n = points.len() as u32;
        let renamed: HashSet<[u32; 3]> = sorted_triangles(&mesh2)
            .into_iter()
            .map(|t| {
                let mut t = t.map(|i| n - 1 - i);
                t.sort_unstable();
                t
            })
            .collect();
        assert_eq!(sorted_triangles(&mesh), renamed, "{nx}x{ny}");
    }
    // Points on one circle, and duplicates.
    let mut circle: Vec<[f64; 2]> = [
        [5.0, 0.0],
        [3.0, 4.0],
        [0.0, 5.0],
        [-3.0, 4.0],
        [-4.0, 3.0],
        [-5.0, 0.0],
        [0.0, -5.0],
        [4.0, -3.0],
    ]
    .to_vec();
    circle.push([3.0, 4.0]);
    let mesh = delaunay_2d(&flat(&circle)).expect("mesh");
    validate_mesh(&mesh).expect("valid");
    assert_eq!(mesh.triangles.len() / 3, 6);
    assert_eq!(mesh.duplicate_of[8], 1);
}

#[test]
fn perturbed_incircle_matches_the_coplanar_predicate() {
    let points = grid(4, 4);
    let lift = |p: &[f64; 2]| [p[0], p[1], 0.0];
    for a in &points {
        for b in &points {
            for c in &points {
                if orient2d(a, b, c) != Sign::Positive {
                    continue;
                }
                for d in &points {
                    if d == a || d == b || d == c {
                        continue;
                    }
                    assert_eq!(
                        incircle_sos(a, b, c, d),
                        incircle_coplanar_sos(&lift(a), &lift(b), &lift(c), &lift(d)),
                        "{a:?} {b:?} {c:?} {d:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn two_dimensional_degenerate_inputs_are_rejected() {
    let collinear = [0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0];
    assert_eq!(
        delaunay_2d(&collinear).unwrap_err().kind,
        ErrorKind::InvalidInput
    );
    assert_eq!(
        delaunay_2d(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
            .unwrap_err()
            .kind,
        ErrorKind::InvalidInput
    );
    let nan = [0.0, 0.0, 1.0, f64::NAN, 2.0, 0.0];
    let err = delaunay_2d(&nan).unwrap_err();
    assert_eq!(err.kind, ErrorKind::InvalidInput);
    assert!(err.message.contains("point 1"), "{}", err.message);
}

// ---------------------------------------------------------------- classification

/// The edge [P0 P1] = [(0,0) (2,0)] among `others`: its type, checked against the Delaunay
/// cover of the points (Theorem 2.1).
fn type_of_edge(others: &[[f64; 2]]) -> Theta2 {
    let mut points = vec![[0.0, 0.0], [2.0, 0.0]];
    points.extend_from_slice(others);
    let theta = classify(&cloud_of(&points), 0, 1);
    if theta != Theta2::Through {
        let dt = Delaunay2d::new(&points).expect("triangulation");
        assert_eq!(
            theta.strongly_admissible(),
            dt.in_delaunay_cover(0, 1, &dt.directed_edges()),
            "Theorem 2.1 for type {}",
            theta.name()
        );
    }
    theta
}

#[test]
fn classification_of_hand_made_edges() {
    // Circle of t = (0,0) (2,0) (1,0.5): centre (1,-0.75), radius 1.25.
    assert_eq!(
        type_of_edge(&[[1.0, 5.0], [-1.0, -1.0], [3.0, 0.5]]),
        Theta2::T0
    );
    assert_eq!(type_of_edge(&[[1.0, 1.0], [1.0, -3.0]]), Theta2::T1_0); // Q* on the small circle
    assert_eq!(type_of_edge(&[[1.0, 0.5], [1.0, -3.0]]), Theta2::T1_0); // Δt ∩ S = {Pi, Pj, Q*}
    assert_eq!(type_of_edge(&[[1.0, 0.5], [1.0, -1.5]]), Theta2::T1_1);
    assert_eq!(
        type_of_edge(&[[1.0, 0.5], [1.75, 0.25], [0.25, 0.25]]),
        Theta2::T1_2_0
    );
    assert_eq!(type_of_edge(&[[1.0, 0.5], [1.0, -2.0]]), Theta2::T1_2_1);
    assert_eq!(type_of_edge(&[[1.0, 0.5], [1.0, -0.5]]), Theta2::T2);
    assert_eq!(type_of_edge(&[[1.0, 1.0], [1.0, -1.0]]), Theta2::T2); // both on the small circle
    assert_eq!(type_of_edge(&[[1.0, 0.0]]), Theta2::Through);
    // Q* is the widest angle, not the first point found.
    assert_eq!(
        type_of_edge(&[[0.5, 0.6], [1.0, 0.5], [1.0, -3.0]]),
        Theta2::T1_0
    );
}

#[test]
fn classification_agrees_with_the_delaunay_cover_on_cocircular_sets() {
    // Theorem 2.1 on every pair of points of sets full of cocircular quadruples.
    let mut rng = rand::rngs::StdRng::seed_from_u64(3);
    for round in 0..6 {
        let mut points = grid(5, 4);
        points.retain(|_| rng.gen_bool(0.75));
        for _ in 0..round {
            points.push([
                rng.gen_range(0..8) as f64 * 0.5,
                rng.gen_range(0..6) as f64 * 0.5,
            ]);
        }
        let points = distinct(&points);
        let cloud = cloud_of(&points);
        let dt = Delaunay2d::new(&points).expect("triangulation");
        let edges = dt.directed_edges();
        let mut seen = HashSet::new();
        for i in 0..points.len() as u32 {
            for j in 0..points.len() as u32 {
                if i == j {
                    continue;
                }
                let theta = classify(&cloud, i, j);
                seen.insert(theta);
                assert_eq!(
                    theta.strongly_admissible(),
                    dt.in_delaunay_cover(i, j, &edges),
                    "round {round}: edge ({i}, {j}) {:?} {:?} of type {}",
                    points[i as usize],
                    points[j as usize],
                    theta.name()
                );
            }
        }
        assert!(seen.contains(&Theta2::T0) && seen.contains(&Theta2::T2));
    }
}

/// Sign of a rational.
fn sign_of(x: &BigRational) -> Sign {
    match x.cmp(&BigRational::from_integer(0.into())) {
        std::cmp::Ordering::Greater => Sign::Positive,
        std::cmp::Ordering::Less => Sign::Negative,
        std::cmp::Ordering::Equal => Sign::Zero,
    }
}

/// Whether `q` is strictly inside (`Positive`), on or outside the circle through the
/// non-collinear `a, b, c`, in rationals.
fn in_circle_exact(a: [f64; 2], b: [f64; 2], c: [f64; 2], q: [f64; 2]) -> Sign {
    let row = |p: [f64; 2]| {
        let (x, y) = (
            rational(p[0]) - rational(q[0]),
            rational(p[1]) - rational(q[1]),
        );
        let lift = &x * &x + &y * &y;
        (x, y, lift)
    };
    let [(ax, ay, al), (bx, by, bl), (cx, cy, cl)] = [a, b, c].map(row);
    let det =
        al * (&bx * &cy - &by * &cx) - bl * (&ax * &cy - &ay * &cx) + cl * (ax * by - ay * bx);
    sign_of(&det) * orient2d(&a, &b, &c)
}

/// `Θ₂([Pi Pj])` by Definition 2.2 read literally, by brute force over all points: small
/// disks and circles in rationals, sides by the exact `orient2d`.
fn type_by_definition(points: &[[f64; 2]], i: usize, j: usize) -> Theta2 {
    let (pi, pj) = (points[i], points[j]);
    let n = points.len();
    let others = |skip: [usize; 3]| (0..n).filter(move |k| !skip.contains(k));
    let e: Vec<usize> = others([i, j, j])
        .filter(|&k| in_closed_small_disk(pi, pj, points[k]))
        .collect();
    if e.is_empty() {
        return Theta2::T0;
    }
    let sides: HashSet<Sign> = e.iter().map(|&k| orient2d(&pi, &pj, &points[k])).collect();
    if sides.contains(&Sign::Zero) {
        return Theta2::Through;
    }
    if sides.len() == 2 {
        return Theta2::T2;
    }
    let q = *e
        .iter()
        .find(|&&q| {
            e.iter()
                .all(|&r| in_circle_exact(pi, pj, points[q], points[r]) != Sign::Positive)
        })
        .expect("a widest angle");
    let dot = |k: usize| {
        (rational(pi[k]) - rational(points[q][k])) * (rational(pj[k]) - rational(points[q][k]))
    };
    if sign_of(&(dot(0) + dot(1))) == Sign::Zero {
        return Theta2::T1_0;
    }
    let position = |k: usize| in_circle_exact(pi, pj, points[q], points[k]);
    if others([i, j, q]).any(|k| position(k) == Sign::Positive) {
        return Theta2::T1_1;
    }
    let f: Vec<usize> = others([i, j, q])
        .filter(|&k| position(k) == Sign::Zero)
        .collect();
    let side = orient2d(&pi, &pj, &points[q]);
    if f.is_empty() {
        Theta2::T1_0
    } else if f.iter().all(|&k| orient2d(&pi, &pj, &points[k]) == side) {
        Theta2::T1_2_0
    } else {
        Theta2::T1_2_1
    }
}

#[test]
fn classification_agrees_with_definition_2_2() {
    // Every pair of: random points, points on a rotated grid (cocircular quadruples on
    // slanted lines), and points on circles, on both sides of many edges.
    let random = random_points(40, 11);
    let rotated: Vec<[f64; 2]> = (0..36)
        .map(|k| {
            let (x, y) = ((k % 6) as f64, (k / 6) as f64);
            [3.0 * x - 4.0 * y, 4.0 * x + 3.0 * y]
        })
        .collect();
    let mut circles = Vec::new();
    for r in [5.0f64, 10.0] {
        // Pythagorean points of the circles of radius 5 and 10 about the origin.
        for (x, y) in [(3.0, 4.0), (4.0, 3.0), (0.0, 5.0), (5.0, 0.0)] {
            for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
                circles.push([sx * x * r / 5.0, sy * y * r / 5.0]);
            }
        }
    }
    circles.push([0.5, 0.25]);
    let circles = distinct(&circles);
    // Three points on one arc over [(0,0) (2,0)], its circle through no other point.
    let arc = vec![
        [0.0, 0.0],
        [2.0, 0.0],
        [1.0, 0.5],
        [1.75, 0.25],
        [0.25, 0.25],
        [1.0, -3.0],
    ];
    let mut seen = HashSet::new();
    let sets = [
        ("random", random),
        ("rotated grid", rotated),
        ("circles", circles),
        ("arc", arc),
    ];
    for (name, points) in sets {
        let cloud = cloud_of(&points);
        for i in 0..points.len() {
            for j in 0..points.len() {
                if i != j {
                    let theta = classify(&cloud, i as u32, j as u32);
                    seen.insert(theta);
                    assert_eq!(
                        theta,
                        type_by_definition(&points, i, j),
                        "{name}: edge ({i}, {j}) {:?} {:?}",
                        points[i],
                        points[j]
                    );
                }
            }
        }
    }
    for theta in [
        Theta2::T0,
        Theta2::T1_0,
        Theta2::T1_1,
        Theta2::T1_2_0,
        Theta2::T1_2_1,
        Theta2::T2,
    ] {
        assert!(seen.contains(&theta), "type {} never met", theta.name());
    }
}

// ---------------------------------------------------------------- conforming subdivision

#[test]
fn simple_polygon_with_a_point_near_an_edge() {
    // (2, 0.3) alone in the small disk of the bottom edge leaves it of type 1.0: admissible.
    let xy = [
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 3.0],
        [0.0, 3.0],
        [2.0, 0.3],
        [1.0, 2.9],
    ];
    let out = conform(&xy, &polyline(4, true), "square with a near point");
    assert_eq!(out.inserted, 0);
    // With points on both sides (type 2), the edges are split.
    let xy = [
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 3.0],
        [0.0, 3.0],
        [2.0, 0.3],
        [2.0, -0.3],
        [1.0, 2.9],
        [1.2, 3.1],
    ];
    let out = conform(
        &xy,
        &polyline(4, true),
        "square with near points on both sides",
    );
    assert!(out.inserted >= 2);
    // Already admissible: nothing to insert.
    let out = conform(&xy[..4], &polyline(4, true), "square");
    assert_eq!(out.inserted, 0);
}

/// A fan of `k` edges at the origin over `spread` degrees, lengths varying.
fn fan(k: usize, spread: f64) -> (Vec<[f64; 2]>, Vec<[u32; 2]>) {
    let mut xy = vec![[0.0, 0.0]];
    let mut segments = Vec::new();
    for i in 0..k {
        let angle = (spread * i as f64 / k as f64).to_radians();
        let length = 1.0 + 0.37 * ((i * 7) % 5) as f64;
        xy.push([length * angle.cos(), length * angle.sin()]);
        segments.push([0, i as u32 + 1]);
    }
    (xy, segments)
}

#[test]
fn fans_of_acute_edges_at_one_point() {
    for (k, spread) in [
        (2, 20.0),
        (3, 60.0),
        (6, 80.0),
        (8, 360.0),
        (12, 360.0),
        (24, 360.0),
        (5, 10.0),
    ] {
        let (xy, segments) = fan(k, spread);
        let out = conform(
            &xy,
            &segments,
            &format!("fan of {k} edges over {spread} degrees"),
        );
        if spread >= 360.0 {
            assert!(out.subdivision.nodes_cleaned >= 1);
        }
    }
}

#[test]
fn chains_of_acute_angles() {
    // A zigzag: every angle acute (Pébay Figure 23).
    // A zigzag whose every second point falls in the small disk of the edge before.
    let xy: Vec<[f64; 2]> = (0..12)
        .map(|i| {
            let k = (i / 2) as f64;
            if i % 2 == 0 {
                [0.0, 0.3 * k]
            } else {
                [3.0, 0.3 * k + 1.0]
            }
        })
        .collect();
    let out = conform(&xy, &polyline(xy.len(), false), "zigzag");
    assert!(out.inserted > 0);
    // A spiral of sharp turns.
    let xy: Vec<[f64; 2]> = (0..30)
        .map(|i| {
            let a = 1.2 * i as f64;
            let r = 1.0 + 0.15 * i as f64;
            [r * a.cos(), r * a.sin()]
        })
        .collect();
    conform(&xy, &polyline(xy.len(), false), "spiral");
}

#[test]
fn closed_nodes() {
    // Two stars (closed nodes) side by side, with their rays' ends joined to a frame.
    let mut xy = vec![[0.0, 0.0], [3.0, 0.2]];
    let mut segments = Vec::new();
    for (c, centre) in [[0.0, 0.0], [3.0, 0.2]].iter().enumerate() {
        for i in 0..9 {
            let a = (i as f64 * 40.0 + 10.0 * c as f64).to_radians();
            let r = if i % 2 == 0 { 1.0 } else { 0.6 };
            xy.push([centre[0] + r * a.cos(), centre[1] + r * a.sin()]);
            segments.push([c as u32, xy.len() as u32 - 1]);
        }
    }
    let out = conform(&xy, &segments, "two closed nodes");
    assert_eq!(out.subdivision.nodes_cleaned, 2);
}

#[test]
fn discretized_arc_splitting_a_box() {
    // Cocircular points of an arc from (0,0) to (4,0) through (2,2), joined, in a box.
    let mut xy = vec![[-1.0, -1.0], [5.0, -1.0], [5.0, 4.0], [-1.0, 4.0]];
    let mut segments = polyline(4, true);
    let first = xy.len() as u32;
    for i in 0..=16 {
        let a = std::f64::consts::PI * (1.0 - i as f64 / 16.0);
        xy.push([2.0 + 2.0 * a.cos(), 2.0 * a.sin()]);
    }
    for i in 0..16 {
        segments.push([first + i, first + i + 1]);
    }
    segments.push([0, first]);
    segments.push([1, first + 16]);
    // Concentric arcs just inside and outside, their points shifted by half a step.
    for radius in [1.9, 2.1] {
        let start = xy.len() as u32;
        for i in 0..16 {
            let a = std::f64::consts::PI * (1.0 - (i as f64 + 0.5) / 16.0);
            xy.push([2.0 + radius * a.cos(), radius * a.sin()]);
        }
        for i in 0..15 {
            segments.push([start + i, start + i + 1]);
        }
    }
    let out = conform(&xy, &segments, "discretized arcs");
    assert!(out.inserted > 0);
}

#[test]
fn cocircular_grid_with_constraints() {
    let xy = grid(8, 8);
    let id = |x: u32, y: u32| y * 8 + x;
    let mut segments = Vec::new();
    for x in 0..7 {
        segments.push([id(x, 0), id(x + 1, 0)]);
        segments.push([id(x, 7), id(x + 1, 7)]);
        segments.push([id(0, x), id(0, x + 1)]);
        segments.push([id(7, x), id(7, x + 1)]);
    }
    segments.push([id(1, 1), id(6, 3)]);
    segments.push([id(1, 6), id(6, 5)]);
    segments.push([id(2, 2), id(3, 5)]);
    conform(&xy, &segments, "cocircular grid");
}

#[test]
fn tiny_angles() {
    for degrees in [1.0f64, 2.0, 5.0, 10.0] {
        let a = degrees.to_radians();
        let xy = [
            [0.0, 0.0],
            [1.0, 0.0],
            [0.8 * a.cos(), 0.8 * a.sin()],
            [0.5, -0.5],
        ];
        conform(
            &xy,
            &[[0, 1], [0, 2], [0, 3]],
            &format!("{degrees} degree angle"),
        );
    }
}

#[test]
fn random_star_polygons_with_interior_points() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    for round in 0..4 {
        let k = 20 + 20 * round;
        let mut angles: Vec<f64> = (0..k)
            .map(|_| rng.gen::<f64>() * std::f64::consts::TAU)
            .collect();
        angles.sort_by(f64::total_cmp);
        let mut xy: Vec<[f64; 2]> = angles
            .iter()
            .map(|a| {
                let r = rng.gen_range(0.3..1.0);
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        let segments = polyline(k, true);
        for _ in 0..k {
            xy.push([rng.gen_range(-0.2..0.2), rng.gen_range(-0.2..0.2)]);
        }
        conform(&xy, &segments, &format!("random star polygon {round}"));
    }
}

#[test]
fn bad_constraints_are_rejected_with_their_culprits() {
    let xy = flat(&[
        [0.0, 0.0],
        [2.0, 0.0],
        [2.0, 2.0],
        [0.0, 2.0],
        [1.0, 0.0],
        [1.0, 1.0],
    ]);
    let expect = |segments: &[u32], words: &[&str]| {
        let err = conforming_2d(&xy, segments).unwrap_err();
        assert_eq!(err.kind, ErrorKind::InvalidInput, "{}", err.message);
        for w in words {
            assert!(err.message.contains(w), "{:?} lacks {w:?}", err.message);
        }
    };
    expect(&[4, 2, 1, 5], &["segments 0 and 1 cross"]);
    expect(&[0, 1], &["point 4 lies on segment 0"]);
    expect(&[2, 2], &["segment 0", "zero length"]);
    expect(&[0, 9], &["segment 0", "out of range"]);
    expect(
        &[0, 2, 3, 1, 2, 3],
        &["point 5 lies on segment 0", "point 5 lies on segment 1"],
    );
    let mut nan = xy.clone();
    nan[5] = f64::NAN;
    let err = conforming_2d(&nan, &[0, 1]).unwrap_err();
    assert!(err.message.contains("point 2"), "{}", err.message);
    // Copies merge: a segment between two copies of one point has zero length.
    let copies = flat(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]);
    expect_copy(&copies);
}

fn expect_copy(copies: &[f64]) {
    let err = conforming_2d(copies, &[0, 3]).unwrap_err();
    assert!(err.message.contains("zero length"), "{}", err.message);
    let out = conforming_2d(copies, &[3, 1, 0, 2]).expect("copies merged");
    assert_eq!(out.mesh.edges[..2], [0, 1]);
}

#[test]
fn algorithm_3_1_on_the_paper_situations() {
    for (k, spread) in [(3, 60.0), (6, 80.0), (12, 360.0), (5, 10.0)] {
        let (xy, segments) = fan(k, spread);
        let out = conform_with(
            &xy,
            &segments,
            &format!("fan {k}/{spread}"),
            Algorithm::Brutal,
        );
        // Every edge of these fans is already admissible, or a cut at the centre is made.
        assert!(
            out.inserted == 0 || out.subdivision.nodes_cleaned >= 1,
            "fan {k}/{spread}"
        );
    }
    let xy: Vec<[f64; 2]> = (0..12)
        .map(|i| {
            let k = (i / 2) as f64;
            if i % 2 == 0 {
                [0.0, 0.3 * k]
            } else {
                [3.0, 0.3 * k + 1.0]
            }
        })
        .collect();
    let out = conform_with(&xy, &polyline(xy.len(), false), "zigzag", Algorithm::Brutal);
    assert!(out.subdivision.nodes_cleaned >= 1);
}

// ---------------------------------------------------------------- crossing segments

fn split() -> ConformingOptions {
    ConformingOptions {
        crossings: Crossings::Split,
        ..Default::default()
    }
}

/// The input pairs of `segments` that cross at a point interior to both (exact signs).
fn crossing_count(xy: &[[f64; 2]], segments: &[[u32; 2]]) -> usize {
    let p = |i: u32| &xy[i as usize];
    let mut count = 0;
    for (k, s) in segments.iter().enumerate() {
        for t in &segments[k + 1..] {
            let o1 = orient2d(p(s[0]), p(s[1]), p(t[0])) * orient2d(p(s[0]), p(s[1]), p(t[1]));
            let o2 = orient2d(p(t[0]), p(t[1]), p(s[0])) * orient2d(p(t[0]), p(t[1]), p(s[1]));
            if o1 == Sign::Negative && o2 == Sign::Negative {
                count += 1;
            }
        }
    }
    count
}

/// Checks of a split result: the intersection points follow the input points with dimension
/// 0, each at least on two segments' chains.
fn assert_intersections(out: &Conforming2d, n_input: usize, expected: usize, case: &str) {
    assert_eq!(out.intersections, expected, "{case}: intersection points");
    let dims = &out.mesh.vertex_dimensions[n_input..n_input + expected];
    for (v, &dim) in (n_input..).zip(dims) {
        assert_eq!(dim, DIMENSION_CORNER, "{case}: dimension of vertex {v}");
        let degree = out.mesh.edges.iter().filter(|&&e| e as usize == v).count();
        assert!(
            degree >= 4,
            "{case}: intersection {v} ends {degree} sub-edges"
        );
    }
}

#[test]
fn crossing_segments_are_an_error_unless_split() {
    let xy = [
        [0.0, 1.0],
        [3.0, 1.0],
        [0.0, 2.0],
        [3.0, 2.0],
        [1.0, 0.0],
        [1.0, 3.0],
        [2.0, 0.0],
        [2.0, 3.0],
    ];
    let hash = [[0, 1], [2, 3], [4, 5], [6, 7]];
    let flat_segments: Vec<u32> = hash.iter().flatten().copied().collect();
    let err = conforming_2d(&flat(&xy), &flat_segments).unwrap_err();
    assert_eq!(err.kind, ErrorKind::InvalidInput);
    assert!(
        err.message.contains("segments 0 and 2 cross"),
        "{}",
        err.message
    );
    let out = conform_checked(&xy, &hash, "#", &split());
    assert_intersections(&out, xy.len(), 4, "#");
    // In the order of the first crossing pair through each: (0, 2), (0, 3), (1, 2), (1, 3).
    let expected = [[1.0, 1.0], [2.0, 1.0], [1.0, 2.0], [2.0, 2.0]];
    for (k, p) in expected.iter().enumerate() {
        assert_eq!(vertex2(&out.mesh, (xy.len() + k) as u32), *p);
    }
    // Every segment is three pieces at least, listed first to second end.
    assert_eq!(&out.mesh.edges[..2], &[0, 8]);
    let quality = quality_2d(
        &flat(&xy),
        &flat_segments,
        &QualityOptions {
            crossings: Crossings::Split,
            ..angle_only(25.0)
        },
    )
    .expect("quality mode splits too");
    assert_eq!(quality.intersections, 4);
    assert_admissible(&quality.mesh, "# (quality)");
    assert_union(&quality.mesh, &xy, &hash, "# (quality)");
}

#[test]
fn segments_through_one_point_share_one_intersection() {
    // Four segments through (1/3, 1/3), which no double represents: the six crossings are one
    // point, found equal exactly.
    let xy = [
        [0.0, 0.0],
        [1.0, 1.0],
        [0.0, 1.0],
        [1.0, -1.0],
        [1.0, 0.0],
        [-1.0, 1.0],
        [-1.0, 0.0],
        [3.0, 1.0],
    ];
    let star = [[0, 1], [2, 3], [4, 5], [6, 7]];
    let out = conform_checked(&xy, &star, "star through (1/3, 1/3)", &split());
    assert_intersections(&out, xy.len(), 1, "star");
    let centre = vertex2(&out.mesh, xy.len() as u32);
    assert_eq!(centre, [1.0 / 3.0, 1.0 / 3.0]);
    // A symmetric star through the origin with a crossing segment elsewhere.
    let mut xy: Vec<[f64; 2]> = Vec::new();
    let mut segments = Vec::new();
    for k in 0..7 {
        let a = 0.3 + k as f64 * std::f64::consts::PI / 7.0;
        let (c, s) = (a.cos(), a.sin());
        segments.push([xy.len() as u32, xy.len() as u32 + 1]);
        xy.extend([[c, s], [-c, -s]]);
    }
    segments.push([xy.len() as u32, xy.len() as u32 + 1]);
    xy.extend([[-1.2, 0.55], [1.2, 0.62]]);
    let crossing_the_last = segments[..7]
        .iter()
        .filter(|s| crossing_count(&xy, &[**s, segments[7]]) == 1)
        .count();
    let out = conform_checked(&xy, &segments, "star through the origin", &split());
    assert_intersections(&out, xy.len(), 1 + crossing_the_last, "star");
    assert_eq!(vertex2(&out.mesh, xy.len() as u32), [0.0, 0.0]);
}

#[test]
fn random_crossing_segments_are_split() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(2024);
    for (count, case) in [(12, "12 random segments"), (60, "60 random segments")] {
        let xy: Vec<[f64; 2]> = (0..2 * count)
            .map(|_| [rng.gen::<f64>(), rng.gen::<f64>()])
            .collect();
        let segments: Vec<[u32; 2]> = (0..count as u32).map(|k| [2 * k, 2 * k + 1]).collect();
        // Random segments cross in general position: every crossing is its own point.
        let crossings = crossing_count(&xy, &segments);
        assert!(crossings >= count, "{case}: {crossings} crossings");
        let out = conform_checked(&xy, &segments, case, &split());
        assert_intersections(&out, xy.len(), crossings, case);
    }
}

#[test]
fn split_segments_keep_t_junctions_and_rounding_failures_errors() {
    let split_flat = |xy: &[[f64; 2]], segments: &[u32]| {
        conforming_2d_with(&flat(xy), segments, &split()).unwrap_err()
    };
    // A segment ending on another is no crossing.
    let t = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
    let err = split_flat(&t, &[0, 1, 2, 3]);
    assert_eq!(err.kind, ErrorKind::InvalidInput);
    assert!(
        err.message.contains("point 2 lies on segment 0"),
        "{}",
        err.message
    );
    // The intersection (9/5, 3/5) rounds onto the input point (1.8, 0.6), on neither segment.
    let xy = [[0.0, 0.0], [3.0, 1.0], [2.0, 0.0], [1.0, 3.0], [1.8, 0.6]];
    let err = split_flat(&xy, &[0, 1, 2, 3]);
    assert_eq!(err.kind, ErrorKind::Limit, "{}", err.message);
    assert!(
        err.message
            .contains("intersection point 5 rounds onto point 4"),
        "{}",
        err.message
    );
}

// ---------------------------------------------------------------- quality refinement

/// The smallest angle of each triangle of `mesh`, in degrees, with its shortest edge.
fn smallest_angles(mesh: &Mesh) -> Vec<(f64, [u32; 2])> {
    mesh.triangles
        .chunks_exact(3)
        .map(|t| {
            let p = [0, 1, 2].map(|k| vertex2(mesh, t[k]));
            let sq = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2);
            let len = [sq(p[1], p[2]), sq(p[2], p[0]), sq(p[0], p[1])];
            let k = (0..3).min_by(|&i, &j| len[i].total_cmp(&len[j])).unwrap();
            let (x, y) = (len[(k + 1) % 3], len[(k + 2) % 3]);
            let cos = ((x + y - len[k]) / (2.0 * (x * y).sqrt())).clamp(-1.0, 1.0);
            (cos.acos().to_degrees(), [t[(k + 1) % 3], t[(k + 2) % 3]])
        })
        .collect()
}

fn triangle_area(mesh: &Mesh, t: &[u32]) -> f64 {
    let [a, b, c] = [0, 1, 2].map(|k| vertex2(mesh, t[k]));
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

/// Whether `p` lies on the segment `[a b]` (up to rounding).
fn on_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> bool {
    let len2 = (b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2);
    let t = ((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1])) / len2;
    let h = ((p[0] - a[0]) * (b[1] - a[1]) - (p[1] - a[1]) * (b[0] - a[0])).abs() / len2;
    (-1e-12..=1.0 + 1e-12).contains(&t) && h < 1e-9
}

/// Whether the edge `(p, q)` joins two points on two segments that meet at an input point at
/// an angle below 60 degrees: a triangle with that shortest edge is skinny because of a small
/// input angle.
fn at_small_input_angle(p: [f64; 2], q: [f64; 2], xy: &[[f64; 2]], segments: &[[u32; 2]]) -> bool {
    for (i, s) in segments.iter().enumerate() {
        for r in &segments[i + 1..] {
            let Some(z) = s.iter().find(|&&z| r.contains(&z)).copied() else {
                continue;
            };
            let far = |g: &[u32; 2]| if g[0] == z { g[1] } else { g[0] };
            let (pz, ps, pr) = (xy[z as usize], xy[far(s) as usize], xy[far(r) as usize]);
            let (u, v) = (
                [ps[0] - pz[0], ps[1] - pz[1]],
                [pr[0] - pz[0], pr[1] - pz[1]],
            );
            let cos = (u[0] * v[0] + u[1] * v[1]) / (u[0].hypot(u[1]) * v[0].hypot(v[1]));
            if cos <= 0.5 {
                continue;
            }
            let on = |x: [f64; 2], g: [f64; 2]| x == pz || on_segment(x, pz, g);
            if (on(p, ps) && on(q, pr)) || (on(p, pr) && on(q, ps)) {
                return true;
            }
        }
    }
    false
}

struct QualityCase<'a> {
    name: &'a str,
    xy: Vec<[f64; 2]>,
    segments: Vec<[u32; 2]>,
    options: QualityOptions,
}

/// Refines `case` and checks: validity, strong admissibility of every sub-segment, every
/// segment the union of its sub-segments, every angle at least the bound but at small input
/// angles (counted), every area within its region's bound, determinism. Returns the result
/// and the count of triangles below the bound.
fn refine_checked(case: &QualityCase) -> (Quality2d, usize) {
    let name = case.name;
    let flat_segments: Vec<u32> = case.segments.iter().flatten().copied().collect();
    let out = quality_2d(&flat(&case.xy), &flat_segments, &case.options)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let mesh = &out.mesh;
    validate_mesh(mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(!mesh.triangles.is_empty(), "{name}: no triangle");
    assert_admissible(mesh, name);
    if !case.segments.is_empty() {
        assert_union(mesh, &case.xy, &case.segments, name);
    }
    let bound = case.options.min_angle_degrees;
    let (mut excused, mut worst) = (0, 180.0f64);
    for (angle, [p, q]) in smallest_angles(mesh) {
        worst = worst.min(angle);
        if angle >= bound {
            continue;
        }
        let near =
            at_small_input_angle(vertex2(mesh, p), vertex2(mesh, q), &case.xy, &case.segments);
        assert!(near, "{name}: a triangle of smallest angle {angle:.2} (bound {bound}) away from small input angles");
        excused += 1;
    }
    for (t, tri) in mesh.triangles.chunks_exact(3).enumerate() {
        let label = mesh.triangle_labels[t];
        let bound = case
            .options
            .regions
            .iter()
            .find(|r| r.label == label && r.max_area > 0.0)
            .map_or(case.options.max_area, |r| r.max_area);
        if bound > 0.0 {
            let area = triangle_area(mesh, tri);
            assert!(
                area <= bound,
                "{name}: triangle {t} of area {area} above {bound}"
            );
        }
    }
    let again = quality_2d(&flat(&case.xy), &flat_segments, &case.options).expect("second run");
    assert_eq!(out.mesh, again.mesh, "{name}: not deterministic");
    eprintln!(
        "{name}: {} triangles, {} vertices ({} by subdivision, {} on segments, {} inside, {} off-centers), smallest angle {worst:.2}, {excused} below {bound} at small input angles ({} rejected)",
        mesh.triangles.len() / 3,
        mesh.vertex_count(),
        out.conforming_points,
        out.refinement.segment_splits,
        out.refinement.interior_points,
        out.refinement.off_centers,
        out.refinement.rejected_forever
    );
    (out, excused)
}

fn angle_only(degrees: f64) -> QualityOptions {
    QualityOptions {
        min_angle_degrees: degrees,
        ..QualityOptions::default()
    }
}

/// A capital A: an outer outline of 11 points and a triangular counter (a hole).
fn letter_a() -> (Vec<[f64; 2]>, Vec<[u32; 2]>, [f64; 2]) {
    let outer = [
        [0.0, 0.0],
        [1.1, 0.0],
        [1.55, 1.3],
        [3.45, 1.3],
        [3.9, 0.0],
        [5.0, 0.0],
        [3.05, 6.0],
        [1.95, 6.0],
    ];
    let counter = [[1.95, 2.3], [3.05, 2.3], [2.5, 4.3]];
    let mut xy = outer.to_vec();
    xy.extend(counter);
    let mut segments = polyline(outer.len(), true);
    let n = outer.len() as u32;
    segments.extend([[n, n + 1], [n + 1, n + 2], [n + 2, n]]);
    (xy, segments, [2.5, 3.0])
}

fn square_with_hole() -> (Vec<[f64; 2]>, Vec<[u32; 2]>) {
    let xy = vec![
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 4.0],
        [0.0, 4.0],
        [1.5, 1.5],
        [2.5, 1.5],
        [2.5, 2.5],
        [1.5, 2.5],
    ];
    let mut segments = polyline(4, true);
    segments.extend([[4, 5], [5, 6], [6, 7], [7, 4]]);
    (xy, segments)
}

#[test]
fn quality_letter_a_with_its_counter_removed() {
    let (xy, segments, hole) = letter_a();
    for degrees in [20.0, 25.0, 30.0, 33.0] {
        let name = format!("letter A at {degrees} degrees");
        let case = QualityCase {
            name: &name,
            xy: xy.clone(),
            segments: segments.clone(),
            options: QualityOptions {
                holes: vec![hole],
                ..angle_only(degrees)
            },
        };
        let (out, excused) = refine_checked(&case);
        assert_eq!(
            excused, 0,
            "{name}: the A has no input angle below 60 degrees"
        );
        for t in out.mesh.triangles.chunks_exact(3) {
            let c = [0, 1, 2].map(|k| vertex2(&out.mesh, t[k]));
            let centroid = [
                (c[0][0] + c[1][0] + c[2][0]) / 3.0,
                (c[0][1] + c[1][1] + c[2][1]) / 3.0,
            ];
            let inside_counter = centroid[1] > 2.3 && centroid[1] < 4.3 && {
                let half = 0.55 * (4.3 - centroid[1]) / 2.0;
                (centroid[0] - 2.5).abs() < half
            };
            assert!(!inside_counter, "{name}: a triangle in the counter");
        }
    }
}

#[test]
fn quality_thin_rhombus_is_left_alone() {
    let xy = vec![[0.0, 0.0], [4.0, 0.6], [8.0, 0.0], [4.0, -0.6]];
    let case = QualityCase {
        name: "thin rhombus at 25 degrees",
        xy,
        segments: polyline(4, true),
        options: angle_only(25.0),
    };
    let (out, excused) = refine_checked(&case);
    assert_eq!(
        out.mesh.triangles.len() / 3,
        2,
        "the two triangles are skinny at input angles only"
    );
    assert_eq!(excused, 2);
}

#[test]
fn quality_square_with_a_hole_and_area_bound() {
    let (xy, segments) = square_with_hole();
    for (degrees, area) in [(30.0, 0.0), (25.0, 0.05)] {
        let name = format!("square with a hole, {degrees} degrees, area {area}");
        let case = QualityCase {
            name: &name,
            xy: xy.clone(),
            segments: segments.clone(),
            options: QualityOptions {
                holes: vec![[2.0, 2.0]],
                max_area: area,
                ..angle_only(degrees)
            },
        };
        let (out, _) = refine_checked(&case);
        let total: f64 = out
            .mesh
            .triangles
            .chunks_exact(3)
            .map(|t| triangle_area(&out.mesh, t))
            .sum();
        assert!(
            (total - 15.0).abs() < 1e-9,
            "{name}: area {total}, not 16 - 1"
        );
    }
}

#[test]
fn quality_regions_get_their_labels_and_area_bounds() {
    // A rectangle cut in two by a vertical segment; left region label 7 with a fine bound,
    // right region unlabeled (label 1) with the global bound.
    let xy = vec![
        [0.0, 0.0],
        [2.0, 0.0],
        [4.0, 0.0],
        [4.0, 2.0],
        [2.0, 2.0],
        [0.0, 2.0],
    ];
    let mut segments = polyline(6, true);
    segments.push([1, 4]);
    let case = QualityCase {
        name: "two regions",
        xy,
        segments,
        options: QualityOptions {
            max_area: 0.5,
            regions: vec![RegionSeed {
                seed: [1.0, 1.0],
                label: 7,
                max_area: 0.02,
            }],
            ..angle_only(28.0)
        },
    };
    let (out, _) = refine_checked(&case);
    let mesh = &out.mesh;
    let (mut left, mut right) = (0.0, 0.0);
    for (t, tri) in mesh.triangles.chunks_exact(3).enumerate() {
        let x = (0..3).map(|k| vertex2(mesh, tri[k])[0]).sum::<f64>() / 3.0;
        let (label, area) = (mesh.triangle_labels[t], triangle_area(mesh, tri));
        if x < 2.0 {
            assert_eq!(label, 7);
            assert!(area <= 0.02);
            left += area;
        } else {
            assert_eq!(label, 1);
            assert!(area <= 0.5);
            right += area;
        }
    }
    assert!((left - 4.0).abs() < 1e-9 && (right - 4.0).abs() < 1e-9);
}

#[test]
fn quality_small_input_angles_terminate() {
    for degrees in [1.0f64, 5.0, 10.0, 20.0, 45.0] {
        let a = degrees.to_radians();
        // A fan of three segments from the origin closed into a polygon.
        let xy = vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [0.8 * a.cos(), 0.8 * a.sin()],
            [1.0 * (2.0 * a).cos(), 1.0 * (2.0 * a).sin()],
        ];
        let segments = vec![[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]];
        for bound in [25.0, 30.0] {
            let name = format!("{degrees} degree angles at {bound}");
            let case = QualityCase {
                name: &name,
                xy: xy.clone(),
                segments: segments.clone(),
                options: angle_only(bound),
            };
            refine_checked(&case);
        }
    }
}

#[test]
fn quality_points_only_mesh_their_convex_hull() {
    let xy = random_points(200, 61);
    let case = QualityCase {
        name: "200 random points",
        xy,
        segments: Vec::new(),
        options: angle_only(30.0),
    };
    let (out, _) = refine_checked(&case);
    assert!(!out.mesh.edges.is_empty(), "the hull edges are segments");
}

#[test]
fn quality_options_are_checked() {
    let (xy, segments) = square_with_hole();
    let flat_segments: Vec<u32> = segments.iter().flatten().copied().collect();
    let run = |options: QualityOptions| quality_2d(&flat(&xy), &flat_segments, &options);
    let e = run(angle_only(35.0)).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidArgument);
    assert!(e.message.contains("34"), "{}", e.message);
    assert!(run(QualityOptions {
        max_area: f64::NAN,
        ..angle_only(20.0)
    })
    .is_err());
    assert!(run(QualityOptions {
        holes: vec![[f64::INFINITY, 0.0]],
        ..angle_only(20.0)
    })
    .is_err());
    let one_segment = quality_2d(&[0.0, 0.0, 1.0, 0.0, 0.5, 1.0], &[0, 1], &angle_only(20.0));
    let e = one_segment.unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidInput);
    assert!(e.message.contains("enclose no region"), "{}", e.message);
}

#[test]
fn quality_cocircular_grid_with_inner_segments() {
    let xy = grid(8, 8);
    let id = |x: u32, y: u32| y * 8 + x;
    let mut segments = Vec::new();
    for i in 0..7 {
        segments.push([id(i, 0), id(i + 1, 0)]);
        segments.push([id(i, 7), id(i + 1, 7)]);
        segments.push([id(0, i), id(0, i + 1)]);
        segments.push([id(7, i), id(7, i + 1)]);
    }
    segments.extend([
        [id(1, 1), id(6, 3)],
        [id(1, 6), id(6, 5)],
        [id(2, 2), id(3, 5)],
    ]);
    for bound in [25.0, 30.0] {
        let name = format!("cocircular grid at {bound}");
        refine_checked(&QualityCase {
            name: &name,
            xy: xy.clone(),
            segments: segments.clone(),
            options: angle_only(bound),
        });
    }
}
