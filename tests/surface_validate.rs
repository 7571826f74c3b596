//! The checks of a triangulated surface before boundary recovery (`recovery::validate`): valid
//! surfaces (closed, several regions, nested), one failing input per check with the culprits
//! named, random pairs of tetrahedra on a small grid against an independent integer oracle,
//! extreme coordinate scales, arbitrary input (no panic), a fine sphere, and the closed surfaces
//! of the shared data when present (`$DELMESH_CORPUS/MANIFEST.tsv`, by default
//! `../shared/data`).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use delmesh::error::ErrorKind;
use delmesh::recovery::validate::{check_intersections, check_intersections_of, check_surface};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Points and triangles, with vertices merged by exact position as they are added.
#[derive(Clone, Debug, Default)]
struct Soup {
    points: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
}

impl Soup {
    /// The index of the vertex at `p`, added when new.
    fn vertex(&mut self, p: [f64; 3]) -> u32 {
        match self.points.iter().position(|q| *q == p) {
            Some(i) => i as u32,
            None => {
                self.points.push(p);
                (self.points.len() - 1) as u32
            }
        }
    }

    /// Adds the triangle `a b c` unless a triangle with the same vertices is already there.
    fn triangle(&mut self, a: [f64; 3], b: [f64; 3], c: [f64; 3]) {
        let t = [self.vertex(a), self.vertex(b), self.vertex(c)];
        let mut key = t;
        key.sort_unstable();
        let known = self.triangles.iter().any(|s| {
            let mut k = *s;
            k.sort_unstable();
            k == key
        });
        if !known {
            self.triangles.push(t);
        }
    }

    /// Adds the box `lo..hi`, outward, each face split along the diagonal through its smallest
    /// corner (so two boxes glued along a face split it the same way). Faces come in the order
    /// x-, x+, y-, y+, z-, z+, two triangles each.
    fn cuboid(&mut self, lo: [f64; 3], hi: [f64; 3]) {
        for axis in 0..3 {
            for high in [false, true] {
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                let corner = |cu: bool, cv: bool| {
                    let mut p = lo;
                    p[axis] = if high { hi[axis] } else { lo[axis] };
                    p[u] = if cu { hi[u] } else { lo[u] };
                    p[v] = if cv { hi[v] } else { lo[v] };
                    p
                };
                let (p00, p10, p11, p01) = (
                    corner(false, false),
                    corner(true, false),
                    corner(true, true),
                    corner(false, true),
                );
                if high {
                    self.triangle(p00, p10, p11);
                    self.triangle(p00, p11, p01);
                } else {
                    self.triangle(p00, p11, p10);
                    self.triangle(p00, p01, p11);
                }
            }
        }
    }

    /// Adds the tetrahedron `a b c d` (its four faces, in the order `abc, abd, acd, bcd`).
    fn tetrahedron(&mut self, [a, b, c, d]: [[f64; 3]; 4]) {
        self.triangle(a, b, c);
        self.triangle(a, b, d);
        self.triangle(a, c, d);
        self.triangle(b, c, d);
    }

    fn check(&self) -> delmesh::error::Result<()> {
        check_surface(&self.points, &self.triangles)
    }

    /// The message of the expected invalid-input failure.
    fn failure(&self) -> String {
        let e = self.check().expect_err("the surface should be rejected");
        assert_eq!(e.kind, ErrorKind::InvalidInput, "{}", e.message);
        e.message
    }

    /// "k (vertices a, b, c)".
    fn named(&self, k: usize) -> String {
        let t = self.triangles[k];
        format!("{k} (vertices {}, {}, {})", t[0], t[1], t[2])
    }

    /// The index of the triangle with the vertices at `corners` (any order).
    fn find(&self, corners: [[f64; 3]; 3]) -> usize {
        let mut key = corners.map(|p| self.points.iter().position(|q| *q == p).unwrap() as u32);
        key.sort_unstable();
        self.triangles
            .iter()
            .position(|t| {
                let mut k = *t;
                k.sort_unstable();
                k == key
            })
            .unwrap()
    }
}

fn unit_cube() -> Soup {
    let mut s = Soup::default();
    s.cuboid([0.0; 3], [1.0; 3]);
    s
}

/// The pair of triangle numbers of an "triangles i (...) and j (...) intersect" message.
fn intersecting_pair(message: &str) -> (usize, usize) {
    assert!(message.ends_with("intersect"), "{message}");
    let number = |s: &str| s.split(' ').next().unwrap().parse::<usize>().unwrap();
    let first = message.strip_prefix("triangles ").expect(message);
    let second = &first[first.find(") and ").expect(message) + ") and ".len()..];
    (number(first), number(second))
}

#[test]
fn cube_and_octahedron_pass() {
    let cube = unit_cube();
    assert_eq!(cube.triangles.len(), 12);
    cube.check().unwrap();
    let mut octahedron = Soup::default();
    let axis = |k: usize, s: f64| {
        let mut p = [0.0; 3];
        p[k] = s;
        p
    };
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            for sz in [-1.0, 1.0] {
                octahedron.triangle(axis(0, sx), axis(1, sy), axis(2, sz));
            }
        }
    }
    assert_eq!(octahedron.triangles.len(), 8);
    octahedron.check().unwrap();
}

#[test]
fn several_regions_pass() {
    // Two cubes sharing an edge: 4 triangles on it, coplanar faces meeting at its ends.
    let mut edge = unit_cube();
    edge.cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]);
    edge.check().unwrap();
    // Two cubes sharing a vertex only.
    let mut vertex = unit_cube();
    vertex.cuboid([1.0; 3], [2.0; 3]);
    assert_eq!(vertex.points.len(), 15);
    vertex.check().unwrap();
    // Two cubes glued along a face given once: its 4 edges have 3 triangles each.
    let mut face = unit_cube();
    face.cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
    assert_eq!(face.triangles.len(), 22);
    face.check().unwrap();
    // A row of three cubes, and nested cubes.
    face.cuboid([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]);
    face.check().unwrap();
    let mut nested = Soup::default();
    nested.cuboid([0.0; 3], [3.0; 3]);
    nested.cuboid([1.0; 3], [2.0; 3]);
    nested.check().unwrap();
}

#[test]
fn unused_vertices_are_ignored() {
    let mut cube = unit_cube();
    cube.points.push([f64::NAN, f64::INFINITY, 1e300]);
    cube.points.push(cube.points[0]);
    cube.check().unwrap();
}

#[test]
fn empty_and_out_of_range() {
    let e = check_surface(&[[0.0; 3]; 3], &[]).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidInput);
    assert!(e.message.contains("no triangles"), "{}", e.message);
    let mut cube = unit_cube();
    cube.triangles[5][1] = 99;
    let message = cube.failure();
    assert!(
        message.starts_with(&format!("triangle {} references vertex 99", cube.named(5))),
        "{message}"
    );
}

#[test]
fn non_finite_or_huge_coordinates() {
    let mut cube = unit_cube();
    cube.points[3][1] = f64::NAN;
    let first = cube.triangles.iter().position(|t| t.contains(&3)).unwrap();
    let message = cube.failure();
    assert!(
        message.starts_with(&format!("vertex 3 of triangle {}", cube.named(first))),
        "{message}"
    );
    cube.points[3][1] = -2e60;
    assert!(cube.failure().starts_with("vertex 3 of triangle"));
}

#[test]
fn coincident_vertices() {
    let mut cube = unit_cube();
    let k = cube.triangles.iter().position(|t| t.contains(&2)).unwrap();
    cube.points.push(cube.points[2]);
    let corner = cube.triangles[k].iter().position(|&v| v == 2).unwrap();
    cube.triangles[k][corner] = 8;
    let message = cube.failure();
    assert!(
        message.starts_with("vertices 2 and 8 are at the same position"),
        "{message}"
    );
    // Signed zeros are one position.
    let mut cube = unit_cube();
    assert_eq!(cube.points[0], [0.0; 3]);
    let k = cube.triangles.iter().position(|t| t.contains(&0)).unwrap();
    cube.points.push([-0.0, 0.0, -0.0]);
    let corner = cube.triangles[k].iter().position(|&v| v == 0).unwrap();
    cube.triangles[k][corner] = 8;
    assert!(cube.failure().starts_with("vertices 0 and 8 are at"));
}

#[test]
fn degenerate_triangles() {
    let mut cube = unit_cube();
    cube.triangles.push([0, 4, 0]);
    assert_eq!(
        cube.failure(),
        "triangle 12 (vertices 0, 4, 0) is degenerate (zero area)"
    );
    // The midpoint of an edge: three collinear vertices, in no coordinate plane.
    let mut cube = unit_cube();
    let (a, b) = (cube.vertex([0.0; 3]), cube.vertex([1.0; 3]));
    let m = cube.vertex([0.5; 3]);
    cube.triangles.push([a, m, b]);
    assert_eq!(
        cube.failure(),
        format!("triangle 12 (vertices {a}, {m}, {b}) is degenerate (zero area)")
    );
}

#[test]
fn duplicate_triangles() {
    let mut cube = unit_cube();
    let [a, b, c] = cube.triangles[4];
    cube.triangles.push([c, b, a]);
    assert_eq!(
        cube.failure(),
        format!(
            "triangle {} and triangle {} have the same vertices",
            cube.named(4),
            cube.named(12)
        )
    );
}

#[test]
fn open_surface() {
    let mut cube = unit_cube();
    let removed = cube.triangles.pop().unwrap();
    let message = cube.failure();
    assert!(
        message.ends_with("only: the surface is not closed"),
        "{message}"
    );
    // The named edge is an edge of the removed triangle, and of the named triangle.
    let edge: Vec<u32> = message["edge (".len()..message.find(')').unwrap()]
        .split(", ")
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(edge.iter().all(|v| removed.contains(v)), "{message}");
    let k: usize = message[message.find("triangle ").unwrap() + "triangle ".len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(edge.iter().all(|v| cube.triangles[k].contains(v)));
    // The smallest such triangle is named.
    let first = (0..cube.triangles.len())
        .find(|&j| {
            let t = cube.triangles[j];
            (0..3).any(|i| removed.contains(&t[i]) && removed.contains(&t[(i + 1) % 3]))
        })
        .unwrap();
    assert_eq!(k, first, "{message}");
}

#[test]
fn overlapping_cubes() {
    let mut s = Soup::default();
    s.cuboid([0.0; 3], [2.0; 3]);
    s.cuboid([1.0; 3], [3.0; 3]);
    let (i, j) = intersecting_pair(&s.failure());
    assert!(i < 12 && j >= 12, "{i} {j}");
    // A cube moved into another along one axis only: faces overlap in their planes.
    let mut s = Soup::default();
    s.cuboid([0.0; 3], [2.0; 3]);
    s.cuboid([0.5, 0.0, 0.0], [2.5, 2.0, 2.0]);
    let (i, j) = intersecting_pair(&s.failure());
    assert!(i < 12 && j >= 12, "{i} {j}");
}

#[test]
fn vertex_touching_a_face() {
    // A tetrahedron standing on the top of the cube with its apex inside the top face.
    let mut s = unit_cube();
    s.tetrahedron([
        [0.25, 0.5, 1.0],
        [0.0, 0.0, 2.0],
        [1.0, 0.0, 2.0],
        [0.5, 1.0, 2.0],
    ]);
    let top = s.find([[0.0, 0.0, 1.0], [0.0, 1.0, 1.0], [1.0, 1.0, 1.0]]);
    let message = s.failure();
    assert_eq!(
        message,
        format!("triangles {} and {} intersect", s.named(top), s.named(12))
    );
    // Lifted by the smallest step, it is clear.
    s.points[8][2] = 1.0 + f64::EPSILON;
    s.check().unwrap();
}

#[test]
fn folded_face() {
    // The top face of the cube, given first, folded: its fourth corner moved inside the
    // triangle of the three others. The two top triangles share an edge and overlap.
    let mut s = unit_cube();
    let top = [
        s.find([[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0]]),
        s.find([[0.0, 0.0, 1.0], [1.0, 1.0, 1.0], [0.0, 1.0, 1.0]]),
    ];
    let first: Vec<[u32; 3]> = top.iter().map(|&k| s.triangles[k]).collect();
    s.triangles.retain(|t| !first.contains(t));
    s.triangles.splice(0..0, first);
    s.check().unwrap();
    let corner = s.vertex([0.0, 1.0, 1.0]) as usize;
    s.points[corner] = [0.75, 0.25, 1.0];
    assert_eq!(
        s.failure(),
        format!("triangles {} and {} intersect", s.named(0), s.named(1))
    );
}

#[test]
fn piercing_a_neighbour_sharing_a_vertex() {
    // Triangle v p q crosses the face v a b of the other tetrahedron: p q pierces it.
    let v = [0.0; 3];
    let mut s = Soup::default();
    s.tetrahedron([v, [4.0, 0.0, 0.0], [0.0, 4.0, 0.0], [0.0, 0.0, -4.0]]);
    s.tetrahedron([v, [1.0, 1.0, 1.0], [1.0, 1.0, -1.0], [-1.0, 1.0, 1.0]]);
    assert_eq!(
        s.failure(),
        format!("triangles {} and {} intersect", s.named(0), s.named(4))
    );
    // Moved up so that q is on the face: still wrong (touching beyond v).
    s.points[5] = [1.0, 1.0, 0.0];
    assert_eq!(
        s.failure(),
        format!("triangles {} and {} intersect", s.named(0), s.named(4))
    );
    // Touching at v only.
    s.points[5] = [1.0, 1.0, 0.5];
    s.check().unwrap();
}

#[test]
fn coplanar_angles_at_a_shared_vertex() {
    // Two tetrahedra with a face each in the plane z = 0, sharing the vertex v.
    let v = [0.0; 3];
    let base = |a: [f64; 3], b: [f64; 3]| {
        let mut s = Soup::default();
        s.tetrahedron([v, [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 1.0]]);
        s.tetrahedron([v, a, b, [0.0, 0.0, -1.0]]);
        s
    };
    // Opposite angle: fine. Angles with opposite sides on one line: fine.
    base([-2.0, 0.0, 0.0], [0.0, -2.0, 0.0]).check().unwrap();
    base([-2.0, 0.0, 0.0], [-1.0, -2.0, 0.0]).check().unwrap();
    // A common side ray.
    let (i, j) = intersecting_pair(&base([-2.0, 0.0, 0.0], [0.0, 1.0, 0.0]).failure());
    assert_eq!((i, j), (0, 4));
    // Side by side: the shared ray is an overlap; a gap is fine.
    let s = base([0.0, -2.0, 0.0], [3.0, 0.0, 0.0]);
    let (i, j) = intersecting_pair(&s.failure());
    assert_eq!((i, j), (0, 4));
    base([1.0, -2.0, 0.0], [3.0, -0.5, 0.0]).check().unwrap();
    // Overlapping angles.
    let (i, j) = intersecting_pair(&base([1.0, 1.0, 0.0], [3.0, -1.0, 0.0]).failure());
    assert_eq!((i, j), (0, 4));
}

#[test]
fn extreme_scales() {
    for scale in [5e58, 1e-200, 3e-320] {
        let scaled = |lo: f64, hi: f64| {
            let mut s = Soup::default();
            s.cuboid([lo * scale; 3], [hi * scale; 3]);
            s
        };
        let mut nested = scaled(0.0, 10.0);
        let inner = scaled(3.0, 7.0);
        let n = nested.points.len() as u32;
        nested.points.extend(&inner.points);
        nested
            .triangles
            .extend(inner.triangles.iter().map(|t| t.map(|v| v + n)));
        nested
            .check()
            .unwrap_or_else(|e| panic!("{scale}: {}", e.message));
        let mut overlapping = scaled(0.0, 10.0);
        let moved = scaled(5.0, 15.0);
        overlapping.points.extend(&moved.points);
        overlapping
            .triangles
            .extend(moved.triangles.iter().map(|t| t.map(|v| v + n)));
        let (i, j) = intersecting_pair(&overlapping.failure());
        assert!(i < 12 && j >= 12, "{scale}: {i} {j}");
    }
}

#[test]
fn arbitrary_input_never_panics() {
    let mut rng = StdRng::seed_from_u64(5);
    let values = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        1e-310,
        1e60,
        f64::NAN,
        f64::INFINITY,
    ];
    for _ in 0..20_000 {
        let n = rng.gen_range(0..7);
        let points: Vec<[f64; 3]> = (0..n)
            .map(|_| [0; 3].map(|_: u8| values[rng.gen_range(0..values.len())]))
            .collect();
        let triangles: Vec<[u32; 3]> = (0..rng.gen_range(0..9))
            .map(|_| [0; 3].map(|_: u8| rng.gen_range(0..n as u32 + 1)))
            .collect();
        if let Err(e) = check_surface(&points, &triangles) {
            assert_eq!(e.kind, ErrorKind::InvalidInput);
        }
    }
}

/// A sphere: the icosahedron with every triangle split in 4, `levels` times, vertices pushed
/// onto the unit sphere.
fn icosphere(levels: usize) -> Soup {
    let g = (1.0 + 5f64.sqrt()) / 2.0;
    let mut points: Vec<[f64; 3]> = vec![
        [-1.0, g, 0.0],
        [1.0, g, 0.0],
        [-1.0, -g, 0.0],
        [1.0, -g, 0.0],
        [0.0, -1.0, g],
        [0.0, 1.0, g],
        [0.0, -1.0, -g],
        [0.0, 1.0, -g],
        [g, 0.0, -1.0],
        [g, 0.0, 1.0],
        [-g, 0.0, -1.0],
        [-g, 0.0, 1.0],
    ];
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut middles = HashMap::new();
        let mut middle = |a: u32, b: u32, points: &mut Vec<[f64; 3]>| {
            *middles.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (points[a as usize], points[b as usize]);
                points.push([0, 1, 2].map(|k| (p[k] + q[k]) / 2.0));
                (points.len() - 1) as u32
            })
        };
        triangles = triangles
            .iter()
            .flat_map(|&[a, b, c]| {
                let ab = middle(a, b, &mut points);
                let bc = middle(b, c, &mut points);
                let ca = middle(c, a, &mut points);
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    for p in &mut points {
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        *p = p.map(|x| x / r);
    }
    Soup { points, triangles }
}

#[test]
fn fine_sphere_and_a_poke() {
    let mut sphere = icosphere(5);
    assert_eq!(sphere.triangles.len(), 20480);
    let start = Instant::now();
    sphere.check().unwrap();
    eprintln!(
        "sphere of {} triangles: {:.1} ms",
        sphere.triangles.len(),
        start.elapsed().as_secs_f64() * 1e3
    );
    // Vertex 0 pulled through the sphere to beyond its far side: its fan crosses the sphere.
    let original = sphere.points[0];
    sphere.points[0] = original.map(|x| -1.5 * x);
    let (i, j) = intersecting_pair(&sphere.failure());
    assert!(
        sphere.triangles[i].contains(&0) != sphere.triangles[j].contains(&0),
        "{i} {j}"
    );
    // Vertex 0 pushed past a neighbour, folding its fan over the neighbour's.
    let neighbour = sphere.triangles[0][1] as usize;
    let n = sphere.points[neighbour];
    sphere.points[0] = [0, 1, 2].map(|k| original[k] + 1.5 * (n[k] - original[k]));
    let (i, j) = intersecting_pair(&sphere.failure());
    assert!(
        sphere.triangles[i].contains(&0) || sphere.triangles[j].contains(&0),
        "{i} {j}"
    );
}

#[test]
fn suspects_cover_every_intersection() {
    // Only vertex 0 moves: every intersecting pair has a triangle of its fan, and the check
    // restricted to the pairs with a suspect names the pair the whole check names.
    let mut sphere = icosphere(3);
    let fan: Vec<usize> = (0..sphere.triangles.len())
        .filter(|&k| sphere.triangles[k].contains(&0))
        .collect();
    let all: Vec<usize> = (0..sphere.triangles.len()).collect();
    check_intersections_of(&sphere.points, &sphere.triangles, &fan).unwrap();
    let original = sphere.points[0];
    let neighbour = sphere.points[sphere.triangles[fan[0]][1] as usize];
    let moves = [
        original.map(|x| -1.5 * x),
        original.map(|x| -1.1 * x),
        [0, 1, 2].map(|k| original[k] + 1.5 * (neighbour[k] - original[k])),
    ];
    for moved in moves {
        sphere.points[0] = moved;
        let whole = check_intersections(&sphere.points, &sphere.triangles).unwrap_err();
        assert_eq!(whole.kind, ErrorKind::InvalidInput);
        intersecting_pair(&whole.message);
        for suspects in [&fan, &all] {
            let part = check_intersections_of(&sphere.points, &sphere.triangles, suspects);
            assert_eq!(part.unwrap_err().message, whole.message);
        }
    }
}

// An independent oracle on small integer coordinates: separating axes with exact integer
// arithmetic.

type IPoint = [i64; 3];

fn sub(a: IPoint, b: IPoint) -> IPoint {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: IPoint, b: IPoint) -> IPoint {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: IPoint, b: IPoint) -> i64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Whether the closed triangles share a point: no separating axis among the normals, the
/// in-plane edge normals and the cross products of edges.
fn oracle_triangles_meet(s: [IPoint; 3], t: [IPoint; 3]) -> bool {
    let edges = |x: [IPoint; 3]| [sub(x[1], x[0]), sub(x[2], x[1]), sub(x[0], x[2])];
    let (es, et) = (edges(s), edges(t));
    let (ns, nt) = (cross(es[0], es[1]), cross(et[0], et[1]));
    let mut axes = vec![ns, nt];
    for e in es {
        axes.push(cross(ns, e));
        for f in et {
            axes.push(cross(e, f));
        }
    }
    for f in et {
        axes.push(cross(nt, f));
    }
    let range = |x: [IPoint; 3], u: IPoint| {
        let d = x.map(|p| dot(p, u));
        (*d.iter().min().unwrap(), *d.iter().max().unwrap())
    };
    !axes.into_iter().filter(|u| *u != [0; 3]).any(|u| {
        let ((a0, a1), (b0, b1)) = (range(s, u), range(t, u));
        a1 < b0 || b1 < a0
    })
}

/// Whether triangles `v a b` and `v p q` share more than `v`: the origin is in the convex hull
/// of `a - v, b - v, v - p, v - q` (a common direction of both angles). The hull is a segment,
/// a polygon or a polyhedron; the candidate separating directions are the points, their
/// differences, the cross products of those, and the cross products of these with them.
fn oracle_meet_beyond_vertex(v: IPoint, [a, b]: [IPoint; 2], [p, q]: [IPoint; 2]) -> bool {
    let x = [sub(a, v), sub(b, v), sub(v, p), sub(v, q)];
    let mut base = x.to_vec();
    for i in 0..4 {
        for j in i + 1..4 {
            base.push(sub(x[j], x[i]));
        }
    }
    let mut axes = base.clone();
    for &d in &base {
        for &e in &base {
            let n = cross(d, e);
            if n != [0; 3] {
                axes.push(n);
                axes.extend(base.iter().map(|&f| cross(n, f)));
            }
        }
    }
    !axes
        .into_iter()
        .filter(|u| *u != [0; 3])
        .any(|u| x.iter().all(|&y| dot(y, u) > 0) || x.iter().all(|&y| dot(y, u) < 0))
}

/// Whether triangles `u w a` and `u w p` overlap: coplanar, `a` and `p` on one side of `u w`.
fn oracle_overlap_across_edge(u: IPoint, w: IPoint, a: IPoint, p: IPoint) -> bool {
    let (na, np) = (cross(sub(w, u), sub(a, u)), cross(sub(w, u), sub(p, u)));
    cross(na, np) == [0; 3] && dot(na, np) > 0
}

/// Whether the triangles `s` and `t` of `points` meet other than at shared vertices and edge.
fn oracle_improper(points: &[IPoint], s: [u32; 3], t: [u32; 3]) -> bool {
    let p = |i: u32| points[i as usize];
    let shared: Vec<u32> = s.iter().copied().filter(|v| t.contains(v)).collect();
    let own = |x: [u32; 3]| -> Vec<IPoint> {
        x.iter()
            .filter(|v| !shared.contains(v))
            .map(|&v| p(v))
            .collect()
    };
    match shared.len() {
        0 => oracle_triangles_meet(s.map(p), t.map(p)),
        1 => {
            let (a, b) = (own(s), own(t));
            oracle_meet_beyond_vertex(p(shared[0]), [a[0], a[1]], [b[0], b[1]])
        }
        _ => oracle_overlap_across_edge(p(shared[0]), p(shared[1]), own(s)[0], own(t)[0]),
    }
}

fn orientation(a: IPoint, b: IPoint, c: IPoint, d: IPoint) -> i64 {
    dot(sub(b, a), cross(sub(c, a), sub(d, a)))
}

/// Two random tetrahedra on the grid `0..=2`, sharing `shared` vertices (0, 1 or 2): each
/// triangle pair of the two is compared with the oracle, and the smallest improper pair must be
/// the one named.
fn random_pairs(shared: usize, trials: usize, seed: u64) -> [usize; 2] {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut outcomes = [0; 2];
    let mut done = 0;
    while done < trials {
        let n = 8 - shared;
        let points: Vec<IPoint> = (0..n)
            .map(|_| [0; 3].map(|_: i64| rng.gen_range(0..=2)))
            .collect();
        let distinct = (0..n).all(|i| (i + 1..n).all(|j| points[i] != points[j]));
        let first = [0u32, 1, 2, 3];
        let second: [u32; 4] = match shared {
            0 => [4, 5, 6, 7],
            1 => [0, 4, 5, 6],
            _ => [0, 1, 4, 5],
        };
        let volume = |t: [u32; 4]| {
            let [a, b, c, d] = t.map(|i| points[i as usize]);
            orientation(a, b, c, d)
        };
        if !distinct || volume(first) == 0 || volume(second) == 0 {
            continue;
        }
        done += 1;
        let faces = |[a, b, c, d]: [u32; 4]| [[a, b, c], [a, b, d], [a, c, d], [b, c, d]];
        let mut triangles: Vec<[u32; 3]> = faces(first).into_iter().chain(faces(second)).collect();
        // Any orientation and starting vertex.
        for t in &mut triangles {
            t.rotate_left(rng.gen_range(0..3));
            if rng.gen() {
                t.swap(0, 1);
            }
        }
        let expected = (0..4)
            .flat_map(|i| (4..8).map(move |j| (i, j)))
            .find(|&(i, j)| oracle_improper(&points, triangles[i], triangles[j]));
        let coordinates: Vec<[f64; 3]> = points.iter().map(|p| p.map(|x| x as f64)).collect();
        let result = check_surface(&coordinates, &triangles);
        match expected {
            None => {
                assert!(result.is_ok(), "{points:?} {triangles:?}: {result:?}");
                outcomes[0] += 1;
            }
            Some((i, j)) => {
                let e = result.expect_err(&format!("{points:?} {triangles:?}: accepted"));
                assert_eq!(e.kind, ErrorKind::InvalidInput);
                assert_eq!(
                    intersecting_pair(&e.message),
                    (i, j),
                    "{points:?} {triangles:?}: {}",
                    e.message
                );
                outcomes[1] += 1;
            }
        }
    }
    outcomes
}

#[test]
fn random_tetrahedra_against_the_oracle() {
    for shared in 0..3 {
        let [fine, rejected] = random_pairs(shared, 20_000, 17 + shared as u64);
        eprintln!("{shared} shared vertices: {fine} valid, {rejected} intersecting");
        assert!(fine > 1000 && rejected > 1000, "{fine} {rejected}");
    }
}

/// The shared data directory, when present.
fn corpus() -> Option<PathBuf> {
    let root = std::env::var_os("DELMESH_CORPUS")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data"));
    root.join("MANIFEST.tsv").is_file().then_some(root)
}

/// Points and faces of an OFF file (polygons of any size, as read).
fn read_off(path: &Path) -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text
        .lines()
        .map(|l| l.split('#').next().unwrap().trim())
        .filter(|l| !l.is_empty());
    let header = lines.next().unwrap();
    let counts: Vec<usize> = match header.strip_prefix("OFF") {
        Some(rest) if !rest.trim().is_empty() => rest.split_whitespace(),
        Some(_) => lines.next().unwrap().split_whitespace(),
        None => panic!("{}: not an OFF file", path.display()),
    }
    .map(|x| x.parse().unwrap())
    .collect();
    let points = (0..counts[0])
        .map(|_| {
            let v: Vec<f64> = lines
                .next()
                .unwrap()
                .split_whitespace()
                .take(3)
                .map(|x| x.parse().unwrap())
                .collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    let faces = (0..counts[1])
        .map(|_| {
            let mut fields = lines.next().unwrap().split_whitespace();
            let n: usize = fields.next().unwrap().parse().unwrap();
            fields.take(n).map(|x| x.parse().unwrap()).collect()
        })
        .collect();
    (points, faces)
}

/// Closed surfaces of the corpus that intersect themselves, checked with exact rationals apart
/// from this crate. `elk.off`: the edge (1493, 1494) of triangle 2877 crosses the interior of
/// triangle 669, which shares only vertex 409 with it (the edge's end 1494 lies 0.01 of the
/// edge's length beyond the plane of 669).
const SELF_INTERSECTING: &[&str] = &["elk.off"];

/// Closed surfaces of the corpus with non-convex polygons, whose fans from their first vertex
/// are not valid triangulations (the other polygons are fanned).
const NON_CONVEX_FACES: &[&str] = &["mpi.off"];

#[test]
fn shared_closed_surfaces() {
    let Some(root) = corpus() else {
        eprintln!("skipped: no shared data");
        return;
    };
    let manifest = std::fs::read_to_string(root.join("MANIFEST.tsv")).unwrap();
    let mut checked = 0;
    for row in manifest.lines().skip(1) {
        let fields: Vec<&str> = row.split('\t').collect();
        let (file, description) = (fields[0], fields[fields.len() - 1]);
        if !(file.starts_with("surfaces/")
            && file.ends_with(".off")
            && description.contains("CLOSED 2-manifold"))
        {
            continue;
        }
        let path = root.join(file);
        let name = file.rsplit('/').next().unwrap();
        if NON_CONVEX_FACES.contains(&name) {
            eprintln!("{file}: skipped, its faces have no fan triangulation");
            continue;
        }
        let (points, faces) = read_off(&path);
        let triangles: Vec<[u32; 3]> = faces
            .iter()
            .flat_map(|f| (1..f.len() - 1).map(|k| [f[0], f[k], f[k + 1]]))
            .collect();
        let start = Instant::now();
        let result = check_surface(&points, &triangles);
        eprintln!(
            "{file}: {} triangles, {:.1} ms: {result:?}",
            triangles.len(),
            start.elapsed().as_secs_f64() * 1e3
        );
        if SELF_INTERSECTING.contains(&name) {
            let message = result.unwrap_err().message;
            assert!(message.ends_with("intersect"), "{file}: {message}");
        } else {
            result.unwrap_or_else(|e| panic!("{file}: {}", e.message));
        }
        checked += 1;
    }
    assert!(checked > 20, "{checked}");
}
