//! Planar triangulations: the 2D Delaunay triangulation, Pébay's classification `Θ₂` and
//! strong Delaunay-admissibility (Theorem 2.1), and the conforming subdivision (Algorithm 3.2)
//! on the paper's situations. Admissibility of the output is checked independently, in exact
//! rational arithmetic.

use std::collections::{HashMap, HashSet};

use delmesh::error::ErrorKind;
use delmesh::mesh2d::classify::{classify, Theta2};
use delmesh::mesh2d::cloud::Cloud;
use delmesh::mesh2d::delaunay::Delaunay2d;
use delmesh::mesh2d::exact::incircle_sos;
use delmesh::mesh2d::subdivide::Algorithm;
use delmesh::mesh2d::{
    conforming_2d, conforming_2d_with, delaunay_2d, validate_mesh, Conforming2d,
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
/// vertices: its closed small disk holds no other vertex (checked in rationals, by brute
/// force), or else it is in the Delaunay cover of the vertices (an edge of the triangulation
/// whose two triangles are not cocircular, or a hull edge).
fn assert_admissible(mesh: &Mesh, case: &str) {
    let n = mesh.vertex_count() as u32;
    let used: Vec<u32> = (0..n)
        .filter(|&i| mesh.duplicate_of.is_empty() || mesh.duplicate_of[i as usize] == i)
        .collect();
    let points: Vec<[f64; 2]> = (0..n).map(|i| vertex2(mesh, i)).collect();
    let dt = Delaunay2d::new(&points).expect("triangulation of the output vertices");
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
    let flat_segments: Vec<u32> = segments.iter().flatten().copied().collect();
    let out = conforming_2d_with(&flat(xy), &flat_segments, algorithm)
        .unwrap_or_else(|e| panic!("{case}: {e}"));
    validate_mesh(&out.mesh).unwrap_or_else(|e| panic!("{case}: {e}"));
    assert_admissible(&out.mesh, case);
    assert_union(&out.mesh, xy, segments, case);
    let again = conforming_2d_with(&flat(xy), &flat_segments, algorithm).expect("second run");
    assert_eq!(out.mesh, again.mesh, "{case}: not deterministic");
    eprintln!(
        "{case} ({algorithm:?}): {} points, {} segments -> {} inserted ({} projections, {} cleanings, {} nodes), degradation worst {:.1} mean {:.2}",
        xy.len(),
        segments.len(),
        out.inserted,
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

fn grid(nx: usize, ny: usize) -> Vec<[f64; 2]> {
    (0..ny)
        .flat_map(|y| (0..nx).map(move |x| [x as f64, y as f64]))
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
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    let points: Vec<[f64; 2]> = (0..2000)
        .map(|_| [rng.gen::<f64>(), rng.gen::<f64>()])
        .collect();
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
        let first = delmesh::mesh2d::delaunay::first_duplicates(&points);
        let points: Vec<[f64; 2]> = (0..points.len())
            .filter(|&i| first[i] as usize == i)
            .map(|i| points[i])
            .collect();
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
