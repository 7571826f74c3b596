//! The exact predicates against an independent reference: determinants of the homogeneous
//! matrices `[1 p]` and `[1 p l(p)]` of the untranslated points over `BigRational`, evaluated
//! by Bareiss's fraction-free elimination; the perturbed predicates against the same
//! determinants with an explicit perturbation of the lifted column.
//!
//! Inputs: uniform random points; points a few ulps away from a plane, sphere or circle;
//! the latter scaled to where the filters' determinants underflow or approach overflow;
//! exactly degenerate integer configurations (lattices, cospherical and cocircular sets), also
//! scaled by powers of two from the subnormal range up to `2^400` and translated by `2^40`;
//! lattices at the ulp scale of huge and tiny values; coordinates with exponents spread over
//! `2^-330..2^330`.
//! Every random stream has a fixed seed.

use std::cmp::Ordering;

use delmesh::predicates::{
    incircle, incircle_coplanar, incircle_coplanar_sos, insphere, insphere_sos, lex_cmp, orient2d,
    orient3d, power_test, power_test_coplanar, power_test_coplanar_sos, power_test_sos, BoxFilter,
    Point, Sign, WeightedPoint,
};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

type Q = BigRational;
type P2 = [f64; 2];

// ---------------------------------------------------------------------------------------------
// The exact reference.

fn q(x: f64) -> Q {
    Q::from_float(x).expect("finite input")
}

fn sign(x: &BigInt) -> Sign {
    if x.is_positive() {
        Sign::Positive
    } else if x.is_negative() {
        Sign::Negative
    } else {
        Sign::Zero
    }
}

/// Sign of the determinant of a matrix of dyadic rationals (as all the inputs and the
/// perturbation are): each column is scaled to integers by its largest denominator, a power of
/// two, which keeps the sign; then Bareiss's fraction-free elimination.
fn det_sign(m: Vec<Vec<Q>>) -> Sign {
    let n = m.len();
    let scales: Vec<BigInt> = (0..n)
        .map(|j| {
            let denominators = m.iter().map(|row| row[j].denom());
            assert!(denominators
                .clone()
                .all(|d| d.bits() == d.trailing_zeros().unwrap() + 1));
            denominators.max().unwrap().clone()
        })
        .collect();
    let mut m: Vec<Vec<BigInt>> = m
        .iter()
        .map(|row| {
            row.iter()
                .zip(&scales)
                .map(|(x, scale)| x.numer() * (scale / x.denom()))
                .collect()
        })
        .collect();
    let mut negated = false;
    let mut previous = BigInt::one();
    for k in 0..n {
        let Some(pivot) = (k..n).find(|&r| !m[r][k].is_zero()) else {
            return Sign::Zero;
        };
        if pivot != k {
            m.swap(pivot, k);
            negated = !negated;
        }
        for i in k + 1..n {
            for j in k + 1..n {
                m[i][j] = (&m[i][j] * &m[k][k] - &m[i][k] * &m[k][j]) / &previous;
            }
        }
        previous = m[k][k].clone();
    }
    if negated {
        sign(&previous).negate()
    } else {
        sign(&previous)
    }
}

/// A point of the reference: exact coordinates and lifted coordinate `|p|^2 - w`.
#[derive(Clone)]
struct Lifted {
    coordinates: Vec<Q>,
    lift: Q,
}

impl Lifted {
    fn new(coordinates: &[f64], weight: f64) -> Lifted {
        let coordinates: Vec<Q> = coordinates.iter().map(|&x| q(x)).collect();
        let lift = coordinates.iter().map(|x| x * x).sum::<Q>() - q(weight);
        Lifted { coordinates, lift }
    }

    fn row(&self, lifted: bool) -> Vec<Q> {
        let mut row = vec![Q::one()];
        row.extend(self.coordinates.iter().cloned());
        if lifted {
            row.push(self.lift.clone());
        }
        row
    }
}

fn orientation(points: &[Lifted]) -> Sign {
    det_sign(points.iter().map(|p| p.row(false)).collect())
}

/// `-det[1 p l(p)]`: positive when the lifted last point is below the hyperplane through the
/// others, for a positively oriented simplex of the others.
fn lifted_test(points: &[Lifted]) -> Sign {
    det_sign(points.iter().map(|p| p.row(true)).collect()).negate()
}

/// Asserts that the matrix `[1 p l(p)]` has small integer entries: its Hadamard bound (which
/// bounds every minor) is below `2^150`. The perturbed determinant is then a polynomial in
/// `eps` with integer coefficients below `2^150`, whose sign for `eps = 2^-200` is the sign of
/// its first nonzero coefficient (at least 1, the others adding up to less than `5 2^150 eps`).
fn assert_small_integers(points: &[Lifted]) {
    let integral = points
        .iter()
        .flat_map(|p| p.coordinates.iter().chain([&p.lift]))
        .all(|x| x.is_integer());
    assert!(integral, "the perturbed reference needs integers");
    let hadamard_squared: Q = points
        .iter()
        .map(|p| p.row(true).iter().map(|x| x * x).sum::<Q>())
        .product();
    assert!(hadamard_squared < Q::from_integer(BigInt::one() << 300u32));
}

/// Adds `eps^(n - r)`, `eps = 2^-200`, to the lift of each of the `n` points, `r` its rank
/// (0 = smallest) in the lexicographic order of the coordinates.
fn perturb(points: &mut [Lifted]) {
    let eps = Q::new(BigInt::one(), BigInt::one() << 200u32);
    let n = points.len();
    let ranks: Vec<usize> = (0..n)
        .map(|i| {
            (0..n)
                .filter(|&j| points[j].coordinates < points[i].coordinates)
                .count()
        })
        .collect();
    for (p, rank) in points.iter_mut().zip(ranks) {
        p.lift += (rank..n).fold(Q::one(), |power, _| power * &eps);
    }
}

fn ref_orient2d(p: &[P2; 3]) -> Sign {
    orientation(&p.map(|p| Lifted::new(&p, 0.0)))
}

fn ref_incircle(p: &[P2; 4]) -> Sign {
    lifted_test(&p.map(|p| Lifted::new(&p, 0.0)))
}

fn ref_orient3d(p: &[Point; 4]) -> Sign {
    orientation(&p.map(|p| Lifted::new(&p, 0.0)))
}

fn ref_power(p: &[WeightedPoint; 5], perturbed: bool) -> Sign {
    let mut points = p.map(|p| Lifted::new(&p[..3], p[3]));
    if perturbed {
        assert_small_integers(&points);
        perturb(&mut points);
    }
    lifted_test(&points)
}

/// The coplanar power test as a 3D one: with `n` the normal of `abc`, `(a, b, c, a + n)` is
/// positively oriented, and the hyperplane through the lifted vertices (whatever the lift of
/// `a + n`) restricts to the plane of `abc` as the plane through the lifted `a, b, c`.
fn ref_power_coplanar(p: &[WeightedPoint; 4], perturbed: bool) -> Sign {
    let mut points = p.map(|p| Lifted::new(&p[..3], p[3]));
    let [a, b, c, _] = &points;
    let ab: Vec<Q> = (0..3)
        .map(|k| &b.coordinates[k] - &a.coordinates[k])
        .collect();
    let ac: Vec<Q> = (0..3)
        .map(|k| &c.coordinates[k] - &a.coordinates[k])
        .collect();
    let cross = |i: usize, j: usize| &ab[i] * &ac[j] - &ab[j] * &ac[i];
    let normal = [cross(1, 2), cross(2, 0), cross(0, 1)];
    assert!(normal.iter().any(|x| !x.is_zero()), "collinear triangle");
    let apex = Lifted {
        coordinates: (0..3).map(|k| &a.coordinates[k] + &normal[k]).collect(),
        lift: Q::zero(),
    };
    if perturbed {
        let mut all = points.to_vec();
        all.push(apex.clone());
        assert_small_integers(&all);
        perturb(&mut points);
    }
    let [a, b, c, d] = points;
    let simplex = [a.clone(), b.clone(), c.clone(), apex.clone()];
    assert_eq!(orientation(&simplex), Sign::Positive);
    assert_eq!(
        orientation(&[a.clone(), b.clone(), c.clone(), d.clone()]),
        Sign::Zero
    );
    lifted_test(&[a, b, c, apex, d])
}

fn xyz(p: &WeightedPoint) -> Point {
    [p[0], p[1], p[2]]
}

fn weighted(p: &Point, w: f64) -> WeightedPoint {
    [p[0], p[1], p[2], w]
}

// ---------------------------------------------------------------------------------------------
// Inputs.

/// `x` moved by `ulps` representable steps (up when positive).
fn nudge(x: f64, ulps: i64) -> f64 {
    (0..ulps.unsigned_abs()).fold(x, |x, _| {
        let up = ulps > 0;
        if x == 0.0 {
            let tiny = f64::from_bits(1);
            return if up { tiny } else { -tiny };
        }
        let bits = x.to_bits();
        f64::from_bits(if (x > 0.0) == up { bits + 1 } else { bits - 1 })
    })
}

fn uniform<const D: usize>(rng: &mut Pcg64) -> [f64; D] {
    std::array::from_fn(|_| rng.gen_range(-1.0..1.0))
}

/// A coordinate `m 2^e`, `m` in `[1, 2)`, `e` in `[-330, 330]`, random sign, sometimes zero.
fn spread<const D: usize>(rng: &mut Pcg64) -> [f64; D] {
    std::array::from_fn(|_| {
        if rng.gen_bool(0.1) {
            return 0.0;
        }
        let x = rng.gen_range(1.0..2.0) * 2f64.powi(rng.gen_range(-330..=330));
        if rng.gen_bool(0.5) {
            x
        } else {
            -x
        }
    })
}

/// `base + k ulp(base)` per coordinate, `k` in `0..4`: an exactly degenerate-prone lattice at
/// the scale of `base`.
fn ulp_lattice<const D: usize>(rng: &mut Pcg64, base: f64) -> [f64; D] {
    std::array::from_fn(|_| nudge(base, rng.gen_range(0..4)))
}

/// All points with the coordinates of `base` permuted and their signs changed.
fn signed_permutations<const D: usize>(base: [f64; D]) -> Vec<[f64; D]> {
    let mut points: Vec<[f64; D]> = Vec::new();
    for permutation in permutations(D) {
        for signs in 0..1u32 << D {
            let p = std::array::from_fn(|k| {
                let x = base[permutation[k]];
                if signs >> k & 1 == 1 {
                    -x
                } else {
                    x
                }
            });
            if !points.contains(&p) {
                points.push(p);
            }
        }
    }
    points
}

fn permutations(n: usize) -> Vec<Vec<usize>> {
    if n == 0 {
        return vec![vec![]];
    }
    let mut all = Vec::new();
    for shorter in permutations(n - 1) {
        for position in 0..n {
            let mut p = shorter.clone();
            p.insert(position, n - 1);
            all.push(p);
        }
    }
    all
}

fn is_even(permutation: &[usize]) -> bool {
    let inversions = (0..permutation.len())
        .flat_map(|i| (i + 1..permutation.len()).map(move |j| (i, j)))
        .filter(|&(i, j)| permutation[i] > permutation[j])
        .count();
    inversions % 2 == 0
}

/// Integer points on the sphere of radius 3 and 7 centred at the origin.
fn cospherical_sets() -> [Vec<Point>; 2] {
    let mut r3 = signed_permutations([0.0, 0.0, 3.0]);
    r3.extend(signed_permutations([1.0, 2.0, 2.0]));
    let mut r7 = signed_permutations([0.0, 0.0, 7.0]);
    r7.extend(signed_permutations([2.0, 3.0, 6.0]));
    [r3, r7]
}

/// Integer points on the circle of radius 5 centred at the origin.
fn cocircular_set() -> Vec<P2> {
    let mut r5 = signed_permutations([0.0, 5.0]);
    r5.extend(signed_permutations([3.0, 4.0]));
    r5
}

fn lattice<const D: usize>(size: usize) -> Vec<[f64; D]> {
    (0..size.pow(D as u32))
        .map(|i| std::array::from_fn(|k| (i / size.pow(k as u32) % size) as f64))
        .collect()
}

/// `N` distinct points of `set`.
fn pick<const D: usize, const N: usize>(rng: &mut Pcg64, set: &[[f64; D]]) -> [[f64; D]; N] {
    let mut chosen: Vec<usize> = Vec::new();
    while chosen.len() < N {
        let i = rng.gen_range(0..set.len());
        if !chosen.contains(&i) {
            chosen.push(i);
        }
    }
    std::array::from_fn(|k| set[chosen[k]])
}

/// Tuples of `N` points of dimension `D` from every family; `near` builds a tuple whose last
/// point is a few ulps away from a degenerate position, `sets` are exactly degenerate sets.
fn tuples<const D: usize, const N: usize>(
    seed: u64,
    count: usize,
    near: impl Fn(&mut Pcg64) -> [[f64; D]; N],
    sets: &[Vec<[f64; D]>],
) -> Vec<[[f64; D]; N]> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let rng = &mut rng;
    let mut all = Vec::new();
    for _ in 0..count {
        let uniform: [[f64; D]; N] = std::array::from_fn(|_| uniform(rng));
        let near = near(rng);
        all.extend([uniform, near]);
        // where the determinants of degree 2 to 5 reach the subnormal range, and near overflow
        for exponent in [-537, -358, -268, -215, 205, 250] {
            let extreme = 2f64.powi(exponent + rng.gen_range(-2..=10));
            let tuple = if rng.gen_bool(0.5) { uniform } else { near };
            all.push(tuple.map(|p| p.map(|x| x * extreme)));
        }
        let set = &sets[rng.gen_range(0..sets.len())];
        let offset = f64::from(rng.gen_range(-4..=4));
        let degenerate: [[f64; D]; N] = pick(rng, set).map(|p| p.map(|x| x + offset));
        all.push(degenerate);
        let scale = [
            2f64.powi(-1060),
            2f64.powi(-600),
            2f64.powi(-300),
            2f64.powi(400),
        ][rng.gen_range(0..4)];
        all.push(degenerate.map(|p| p.map(|x| x * scale)));
        all.push(degenerate.map(|p| p.map(|x| x + 2f64.powi(40))));
        let base = rng.gen_range(1.0..2.0) * 2f64.powi(rng.gen_range(-300..=300));
        all.push(std::array::from_fn(|_| ulp_lattice(rng, base)));
        all.push(std::array::from_fn(|_| {
            ulp_lattice(rng, 1.5 * 2f64.powi(300))
        }));
        all.push(std::array::from_fn(|_| spread(rng)));
    }
    all
}

/// Three points around a line: the last a few ulps off it.
fn near_collinear(rng: &mut Pcg64) -> [P2; 3] {
    let [a, b]: [P2; 2] = [uniform(rng), uniform(rng)];
    let t = rng.gen_range(-1.0..2.0);
    let c = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
    [a, b, nudge_one(rng, c)]
}

/// Four points around a circle: the last a few ulps off it.
fn near_cocircular(rng: &mut Pcg64) -> [P2; 4] {
    let center: P2 = uniform(rng);
    let radius = rng.gen_range(0.1..2.0);
    let mut p: [P2; 4] = std::array::from_fn(|_| {
        let angle: f64 = rng.gen_range(0.0..std::f64::consts::TAU);
        [
            center[0] + radius * angle.cos(),
            center[1] + radius * angle.sin(),
        ]
    });
    p[3] = nudge_one(rng, p[3]);
    p
}

/// Four points around a plane: the last a few ulps off it.
fn near_coplanar(rng: &mut Pcg64) -> [Point; 4] {
    let [a, b, c]: [Point; 3] = std::array::from_fn(|_| uniform(rng));
    let (s, t) = (rng.gen_range(-1.0..2.0), rng.gen_range(-1.0..2.0));
    let d = std::array::from_fn(|k| a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]));
    [a, b, c, nudge_one(rng, d)]
}

/// Five points around a sphere: the last a few ulps off it.
fn near_cospherical(rng: &mut Pcg64) -> [Point; 5] {
    let center: Point = uniform(rng);
    let radius = rng.gen_range(0.1..2.0);
    let mut p: [Point; 5] = std::array::from_fn(|_| {
        let v: Point = uniform(rng);
        let norm = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        std::array::from_fn(|k| center[k] + radius * v[k] / norm)
    });
    p[4] = nudge_one(rng, p[4]);
    p
}

fn nudge_one<const D: usize>(rng: &mut Pcg64, mut p: [f64; D]) -> [f64; D] {
    let k = rng.gen_range(0..D);
    p[k] = nudge(p[k], rng.gen_range(-3..=3));
    p
}

/// Weights for a tuple: zero, constant, random, and on a hyperplane of the lifting map
/// (`w = |p|^2 - s alpha.p - s^2 beta` for small integers `alpha, beta` and the largest
/// coordinate `s`: exact for scaled integer points, a few ulps off otherwise).
fn weightings<const N: usize>(rng: &mut Pcg64, p: &[Point; N]) -> Vec<[WeightedPoint; N]> {
    let norm = |p: &Point| p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    let constant = rng.gen_range(-1.0..1.0) * norm(&p[0]);
    let alpha: [f64; 3] = std::array::from_fn(|_| f64::from(rng.gen_range(-2..=2)));
    let beta = f64::from(rng.gen_range(-3..=3));
    let scale = p.iter().map(|p| p[0].abs().max(p[1].abs()).max(p[2].abs()));
    let scale = scale.fold(0.0, f64::max);
    let hyperplane = |p: &Point| {
        norm(p)
            - scale * (alpha[0] * p[0] + alpha[1] * p[1] + alpha[2] * p[2])
            - beta * scale * scale
    };
    vec![
        p.map(|p| weighted(&p, 0.0)),
        p.map(|p| weighted(&p, constant)),
        p.map(|p| weighted(&p, rng.gen_range(0.0..0.5) * norm(&p))),
        p.map(|p| weighted(&p, hyperplane(&p))),
    ]
}

/// Quadruples `(a, b, c, p)` of exactly coplanar points, `a, b, c` not collinear.
fn coplanar_quadruples(seed: u64, count: usize) -> Vec<[Point; 4]> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let rng = &mut rng;
    // an orthogonal pair of integer vectors of the same length: circles map to circles
    let (e1, e2) = ([1.0, 2.0, 2.0], [2.0, 1.0, -2.0]);
    let embed = |origin: &Point, uv: &P2| -> Point {
        std::array::from_fn(|k| origin[k] + uv[0] * e1[k] + uv[1] * e2[k])
    };
    let grid = lattice::<2>(5);
    let circle = cocircular_set();
    let mut all = Vec::new();
    for _ in 0..count {
        let axis = rng.gen_range(0..3);
        let level = rng.gen_range(-1.0..1.0);
        let in_axis_plane = |uv: P2| -> Point {
            let mut p = [level; 3];
            p[(axis + 1) % 3] = uv[0];
            p[(axis + 2) % 3] = uv[1];
            p
        };
        all.push(std::array::from_fn(|_| in_axis_plane(uniform(rng))));
        let near: [Point; 4] = near_cocircular(rng).map(in_axis_plane);
        all.push(near);
        // where the filter's determinant underflows, and near overflow
        for exponent in [-268, 250] {
            let extreme = 2f64.powi(exponent + rng.gen_range(-2..=10));
            all.push(near.map(|p| p.map(|x| x * extreme)));
        }
        let origin = [0, 1, 2].map(|_| f64::from(rng.gen_range(-3..=3)));
        let set = if rng.gen_bool(0.5) { &grid } else { &circle };
        let degenerate = pick::<2, 4>(rng, set).map(|uv| embed(&origin, &uv));
        all.push(degenerate);
        let scale = [2f64.powi(-600), 2f64.powi(300)][rng.gen_range(0..2)];
        all.push(degenerate.map(|p| p.map(|x| x * scale)));
        all.push(degenerate.map(|p| p.map(|x| x + 2f64.powi(40))));
        let [a, u, v]: [Point; 3] =
            std::array::from_fn(|_| [0, 1, 2].map(|_| f64::from(rng.gen_range(-8..=8))));
        all.push(std::array::from_fn(|_| {
            let (s, t) = (
                rng.gen_range(-32..=32) as f64 / 16.0,
                rng.gen_range(-32..=32) as f64 / 16.0,
            );
            std::array::from_fn(|k| a[k] + s * u[k] + t * v[k])
        }));
    }
    all.retain(|[a, b, c, _]| !collinear(a, b, c));
    all
}

fn collinear(a: &Point, b: &Point, c: &Point) -> bool {
    let project = |p: &Point, i: usize, j: usize| [p[i], p[j]];
    [(0, 1), (1, 2), (2, 0)].iter().all(|&(i, j)| {
        ref_orient2d(&[project(a, i, j), project(b, i, j), project(c, i, j)]) == Sign::Zero
    })
}

/// `(a, b, c, d, e)` with `(a, b, c, d)` positively oriented, or `None` when it is flat.
fn positively_oriented<T: Copy>(p: [T; 5], orientation: Sign) -> Option<[T; 5]> {
    match orientation {
        Sign::Positive => Some(p),
        Sign::Negative => Some([p[1], p[0], p[2], p[3], p[4]]),
        Sign::Zero => None,
    }
}

/// Counts of the outcomes of a test, to check that every kind of answer was exercised.
#[derive(Default, Debug)]
struct Tally([usize; 3]);

impl Tally {
    fn add(&mut self, sign: Sign) {
        self.0[(sign as i8 + 1) as usize] += 1;
    }

    fn assert_all_seen(&self, name: &str) {
        assert!(
            self.0.iter().all(|&n| n > 0),
            "{name}: outcomes {:?}",
            self.0
        );
    }
}

// ---------------------------------------------------------------------------------------------
// The conventions of the reference, on configurations with known answers.

#[test]
fn reference_conventions_are_the_geometric_ones() {
    let tetrahedron = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    // dot(b-a, cross(c-a, d-a)) = dot(x, cross(y, z)) = 1
    assert_eq!(ref_orient3d(&tetrahedron), Sign::Positive);
    let with = |e: Point| {
        let [a, b, c, d] = tetrahedron;
        [a, b, c, d, e].map(|p| weighted(&p, 0.0))
    };
    // the circumcentre (1/2, 1/2, 1/2) is inside, (2, 2, 2) outside, (1, 1, 0) on the sphere
    assert_eq!(ref_power(&with([0.5; 3]), false), Sign::Positive);
    assert_eq!(ref_power(&with([2.0; 3]), false), Sign::Negative);
    assert_eq!(ref_power(&with([1.0, 1.0, 0.0]), false), Sign::Zero);
    // a weight lowers the lifted point: the sphere-point becomes in conflict
    let mut heavy = with([1.0, 1.0, 0.0]);
    heavy[4][3] = 0.25;
    assert_eq!(ref_power(&heavy, false), Sign::Positive);
    let triangle = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    assert_eq!(ref_orient2d(&triangle), Sign::Positive);
    let [a, b, c] = triangle;
    assert_eq!(ref_incircle(&[a, b, c, [0.5, 0.5]]), Sign::Positive);
    assert_eq!(ref_incircle(&[a, b, c, [1.0, 1.0]]), Sign::Zero);
    assert_eq!(ref_incircle(&[a, b, c, [2.0, 2.0]]), Sign::Negative);
    // the same triangle in the plane z = 1, in both orientations
    let lift = |p: P2| weighted(&[p[0], p[1], 1.0], 0.0);
    for [a, b] in [[a, b], [b, a]] {
        let quad = |p| [lift(a), lift(b), lift(c), lift(p)];
        assert_eq!(ref_power_coplanar(&quad([0.5, 0.5]), false), Sign::Positive);
        assert_eq!(ref_power_coplanar(&quad([1.0, 1.0]), false), Sign::Zero);
        assert_eq!(ref_power_coplanar(&quad([2.0, 2.0]), false), Sign::Negative);
    }
}

// ---------------------------------------------------------------------------------------------
// The predicates against the reference.

#[test]
fn orient2d_and_incircle_match_the_reference() {
    let sets2 = [lattice::<2>(5), cocircular_set()];
    let (mut orientations, mut circles) = (Tally::default(), Tally::default());
    for p in tuples(1, 150, near_collinear, &sets2) {
        let expected = ref_orient2d(&p);
        assert_eq!(orient2d(&p[0], &p[1], &p[2]), expected, "orient2d {p:?}");
        orientations.add(expected);
    }
    for p in tuples(2, 150, near_cocircular, &sets2) {
        let expected = ref_incircle(&p);
        assert_eq!(
            incircle(&p[0], &p[1], &p[2], &p[3]),
            expected,
            "incircle {p:?}"
        );
        circles.add(expected);
    }
    orientations.assert_all_seen("orient2d");
    circles.assert_all_seen("incircle");
}

#[test]
fn orient3d_matches_the_reference() {
    let sets = [lattice::<3>(4)];
    let mut tally = Tally::default();
    for p in tuples(3, 200, near_coplanar, &sets) {
        let expected = ref_orient3d(&p);
        assert_eq!(orient3d(&p[0], &p[1], &p[2], &p[3]), expected, "{p:?}");
        tally.add(expected);
    }
    tally.assert_all_seen("orient3d");
}

#[test]
fn insphere_and_power_test_match_the_reference() {
    let [r3, r7] = cospherical_sets();
    let sets = [lattice::<3>(4), r3, r7];
    let mut rng = Pcg64::seed_from_u64(4);
    let (mut spheres, mut powers) = (Tally::default(), Tally::default());
    for p in tuples(5, 60, near_cospherical, &sets) {
        let orientation = ref_orient3d(&[p[0], p[1], p[2], p[3]]);
        let Some([a, b, c, d, e]) = positively_oriented(p, orientation) else {
            continue;
        };
        let unweighted = ref_power(&[a, b, c, d, e].map(|p| weighted(&p, 0.0)), false);
        assert_eq!(insphere(&a, &b, &c, &d, &e), unweighted, "insphere {p:?}");
        spheres.add(unweighted);
        for w in weightings(&mut rng, &[a, b, c, d, e]) {
            let expected = ref_power(&w, false);
            assert_eq!(
                power_test(&w[0], &w[1], &w[2], &w[3], &w[4]),
                expected,
                "{w:?}"
            );
            powers.add(expected);
        }
    }
    spheres.assert_all_seen("insphere");
    powers.assert_all_seen("power_test");
}

#[test]
fn coplanar_tests_match_the_reference() {
    let mut rng = Pcg64::seed_from_u64(6);
    let (mut circles, mut powers) = (Tally::default(), Tally::default());
    for p in coplanar_quadruples(7, 80) {
        let [a, b, c, d] = p;
        let unweighted = ref_power_coplanar(&p.map(|p| weighted(&p, 0.0)), false);
        assert_eq!(incircle_coplanar(&a, &b, &c, &d), unweighted, "{p:?}");
        circles.add(unweighted);
        for w in weightings(&mut rng, &p) {
            let expected = ref_power_coplanar(&w, false);
            assert_eq!(
                power_test_coplanar(&w[0], &w[1], &w[2], &w[3]),
                expected,
                "{w:?}"
            );
            powers.add(expected);
        }
    }
    circles.assert_all_seen("incircle_coplanar");
    powers.assert_all_seen("power_test_coplanar");
}

// ---------------------------------------------------------------------------------------------
// The perturbed predicates against the perturbed determinants.

/// The same exactly representable configuration, scaled and translated: the perturbed answer
/// depends on the lexicographic order and the signs of orientations only, both invariant.
fn transformed<const N: usize>(p: &[WeightedPoint; N]) -> [[WeightedPoint; N]; 4] {
    let scaled = |s: f64| p.map(|p| [p[0] * s, p[1] * s, p[2] * s, p[3] * s * s]);
    let shift = 2f64.powi(40);
    let translated = p.map(|p| [p[0] + shift, p[1] + shift, p[2] + shift, p[3]]);
    [
        *p,
        scaled(2f64.powi(-300)),
        scaled(2f64.powi(300)),
        translated,
    ]
}

/// Integer weights: zero, on a hyperplane of the lifting map, or small random.
fn integer_weightings<const N: usize>(rng: &mut Pcg64, p: &[Point; N]) -> Vec<[WeightedPoint; N]> {
    let alpha: [f64; 3] = std::array::from_fn(|_| f64::from(rng.gen_range(-2..=2)));
    let beta = f64::from(rng.gen_range(-3..=3));
    let hyperplane = |p: &Point| {
        p[0] * p[0] + p[1] * p[1] + p[2] * p[2]
            - (alpha[0] * p[0] + alpha[1] * p[1] + alpha[2] * p[2])
            - beta
    };
    vec![
        p.map(|p| weighted(&p, 0.0)),
        p.map(|p| weighted(&p, hyperplane(&p))),
        p.map(|p| weighted(&p, f64::from(rng.gen_range(0..3)))),
    ]
}

#[test]
fn perturbed_3d_tests_match_the_perturbed_determinant() {
    let [r3, r7] = cospherical_sets();
    let sets = [lattice::<3>(3), r3, r7];
    let mut rng = Pcg64::seed_from_u64(8);
    let mut ties = 0;
    for round in 0..240 {
        let p: [Point; 5] = pick(&mut rng, &sets[round % 3]);
        let Some(p) = positively_oriented(p, ref_orient3d(&[p[0], p[1], p[2], p[3]])) else {
            continue;
        };
        for w in integer_weightings(&mut rng, &p) {
            ties += usize::from(ref_power(&w, false) == Sign::Zero);
            let expected = ref_power(&w, true);
            assert_ne!(expected, Sign::Zero, "the perturbation leaves no tie");
            for [a, b, c, d, e] in transformed(&w) {
                assert_eq!(power_test_sos(&a, &b, &c, &d, &e), expected, "{w:?}");
                if w.iter().all(|p| p[3] == 0.0) {
                    let [a, b, c, d, e] = [a, b, c, d, e].map(|p| xyz(&p));
                    assert_eq!(insphere_sos(&a, &b, &c, &d, &e), expected, "{w:?}");
                }
            }
        }
    }
    assert!(ties > 100, "only {ties} exact ties");
}

#[test]
fn perturbed_coplanar_tests_match_the_perturbed_determinant() {
    let mut rng = Pcg64::seed_from_u64(9);
    let mut ties = 0;
    let integral = |p: &[Point; 4]| {
        p.iter()
            .flatten()
            .all(|x| x.fract() == 0.0 && x.abs() < 64.0)
    };
    for p in coplanar_quadruples(10, 60).into_iter().filter(integral) {
        for w in integer_weightings(&mut rng, &p) {
            ties += usize::from(ref_power_coplanar(&w, false) == Sign::Zero);
            let expected = ref_power_coplanar(&w, true);
            assert_ne!(expected, Sign::Zero, "the perturbation leaves no tie");
            for [a, b, c, d] in transformed(&w) {
                assert_eq!(power_test_coplanar_sos(&a, &b, &c, &d), expected, "{w:?}");
                if w.iter().all(|p| p[3] == 0.0) {
                    let [a, b, c, d] = [a, b, c, d].map(|p| xyz(&p));
                    assert_eq!(incircle_coplanar_sos(&a, &b, &c, &d), expected, "{w:?}");
                }
            }
        }
    }
    assert!(ties > 50, "only {ties} exact ties");
}

#[test]
fn perturbed_tests_are_invariant_under_reordering_of_the_simplex() {
    let [r3, r7] = cospherical_sets();
    let mut rng = Pcg64::seed_from_u64(11);
    let even: Vec<Vec<usize>> = permutations(4).into_iter().filter(|p| is_even(p)).collect();
    assert_eq!(even.len(), 12);
    for round in 0..200 {
        let p: [Point; 5] = pick(&mut rng, if round % 2 == 0 { &r3 } else { &r7 });
        let Some(p) = positively_oriented(p, orient3d(&p[0], &p[1], &p[2], &p[3])) else {
            continue;
        };
        let answers: Vec<Sign> = even
            .iter()
            .map(|s| insphere_sos(&p[s[0]], &p[s[1]], &p[s[2]], &p[s[3]], &p[4]))
            .collect();
        assert!(
            answers.iter().all(|&s| s == answers[0] && s != Sign::Zero),
            "{p:?}"
        );
        for w in integer_weightings(&mut rng, &p) {
            let answers: Vec<Sign> = even
                .iter()
                .map(|s| power_test_sos(&w[s[0]], &w[s[1]], &w[s[2]], &w[s[3]], &w[4]))
                .collect();
            assert!(
                answers.iter().all(|&s| s == answers[0] && s != Sign::Zero),
                "{w:?}"
            );
        }
    }
    let circle = cocircular_set();
    for _ in 0..200 {
        let uv: [P2; 4] = pick(&mut rng, &circle);
        let p = uv.map(|[u, v]| [u + 2.0 * v, 2.0 * u + v, 2.0 * u - 2.0 * v]);
        if collinear(&p[0], &p[1], &p[2]) {
            continue;
        }
        let answers: Vec<Sign> = permutations(3)
            .iter()
            .map(|s| incircle_coplanar_sos(&p[s[0]], &p[s[1]], &p[s[2]], &p[3]))
            .collect();
        assert!(
            answers.iter().all(|&s| s == answers[0] && s != Sign::Zero),
            "{p:?}"
        );
    }
}

#[test]
fn lex_cmp_orders_by_x_then_y_then_z() {
    let (a, b, c, d) = (
        [0.0, 5.0, 5.0],
        [1.0, 0.0, 0.0],
        [1.0, 0.0, 2.0],
        [1.0, 1.0, -9.0],
    );
    assert_eq!(lex_cmp(&a, &b), Ordering::Less);
    assert_eq!(lex_cmp(&b, &c), Ordering::Less);
    assert_eq!(lex_cmp(&c, &d), Ordering::Less);
    assert_eq!(lex_cmp(&d, &a), Ordering::Greater);
    assert_eq!(
        lex_cmp(&[-0.0, 0.0, 1.0], &[0.0, -0.0, 1.0]),
        Ordering::Equal
    );
}

/// The box filter decides exactly as the full predicates for points of its box: random
/// points, exactly degenerate lattice points, and lattice points nudged by a few ulps.
#[test]
fn box_filter_agrees_with_the_full_predicates() {
    let mut rng = Pcg64::seed_from_u64(0xb0c5);
    let boxes = [([0.0; 3], [1.0; 3]), ([-1e3, 5.0, 2e-3], [1e3, 6.0, 3e-3])];
    for (lo, hi) in boxes {
        let filter = BoxFilter::new(&lo, &hi);
        let point = |rng: &mut Pcg64, lattice: bool| -> Point {
            std::array::from_fn(|k| {
                let t = if lattice {
                    // The box's corners: all cospherical.
                    f64::from(rng.gen_range(0..2u8))
                } else {
                    rng.gen_range(0.0..1.0)
                };
                let x = lo[k] + t * (hi[k] - lo[k]);
                let x = if lattice && rng.gen_bool(0.02) {
                    nudge(x, rng.gen_range(-2..=2))
                } else {
                    x
                };
                x.clamp(lo[k], hi[k])
            })
        };
        let (mut decided, mut degenerate) = (0, 0);
        for round in 0..40_000 {
            let lattice = round % 2 == 1;
            let mut p: [Point; 5] = std::array::from_fn(|_| point(&mut rng, lattice));
            assert_eq!(
                filter.orient3d(&p[0], &p[1], &p[2], &p[3]),
                orient3d(&p[0], &p[1], &p[2], &p[3])
            );
            match orient3d(&p[0], &p[1], &p[2], &p[3]) {
                Sign::Zero => continue,
                Sign::Negative => p.swap(0, 1),
                Sign::Positive => {}
            }
            if (0..4).any(|i| p[i] == p[4]) {
                continue;
            }
            let exact = insphere(&p[0], &p[1], &p[2], &p[3], &p[4]);
            degenerate += usize::from(exact == Sign::Zero);
            decided += 1;
            assert_eq!(
                filter.insphere_sos(&p[0], &p[1], &p[2], &p[3], &p[4]),
                insphere_sos(&p[0], &p[1], &p[2], &p[3], &p[4]),
                "{p:?}"
            );
        }
        assert!(
            decided > 10_000 && degenerate > 100,
            "{decided} {degenerate}"
        );
    }
}
