//! Points constructed from exact points and decided on exactly: `a + u (b - a) + v (c - a)`
//! for three points `a, b, c` and floating-point weights `u, v` ([`Combination`]). Such a point
//! lies exactly on the plane of `a, b, c` (on line `ab` when `v = 0`) whatever the weights,
//! while its rounded coordinates ([`Combination::approx`]) do not: surface recovery
//! (`crate::recovery`) adds its points on the input surface as combinations of an input
//! triangle's or edge's corners, so that four of them on one triangle are coplanar for the
//! predicates too, as they are for the partition of the surface.
//!
//! [`orient3d`] takes points that are either floating-point (exact as given) or combinations.
//! Its filter evaluates the determinant on the rounded coordinates and widens the bound of
//! that evaluation by what the rounding of the combinations can change (the determinant is
//! trilinear in its rows); the exact stage expands every coordinate as a dyadic number (a big
//! integer times a power of two), on which the combination is computed without rounding.

use num_bigint::BigInt;
use num_traits::Zero;

use super::exact::{det3, dyadic, sign};
use super::filter::certify;
use super::{Point, Sign};
use crate::geometry::{cross, dot, sub};

/// `a + u (b - a) + v (c - a)`, with its rounded and exact coordinates.
#[derive(Clone, Debug)]
pub struct Combination {
    approx: Point,
    error: f64,
    exact: [Dyadic; 3],
}

/// Relative rounding of one floating-point operation (`2^-53`), with room: the bounds below
/// count at most four roundings per term and multiply by more than that.
const UNIT: f64 = 1.12e-16;

impl Combination {
    pub fn new([a, b, c]: [Point; 3], u: f64, v: f64) -> Self {
        let approx = std::array::from_fn(|k| a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]));
        // Three subtractions, two products and two sums, each rounded once.
        let sizes =
            (0..3).map(|k| a[k].abs() + (u * (b[k] - a[k])).abs() + (v * (c[k] - a[k])).abs());
        let error = 8.0 * UNIT * sizes.fold(0.0, f64::max);
        let (u, v) = (Dyadic::of(u), Dyadic::of(v));
        let exact = std::array::from_fn(|k| {
            let a_k = Dyadic::of(a[k]);
            let along_b = u.times(&Dyadic::of(b[k]).minus(&a_k));
            let along_c = v.times(&Dyadic::of(c[k]).minus(&a_k));
            a_k.plus(&along_b).plus(&along_c)
        });
        Combination {
            approx,
            error,
            exact,
        }
    }

    /// The combination of `corners` nearest to `p`: its weights are those of the orthogonal
    /// projection of `p` on their line (`v = 0`) when the third corner repeats the first,
    /// on their plane otherwise. `None` where the corners are degenerate.
    pub fn nearest(corners: [Point; 3], p: &Point) -> Option<Self> {
        let [a, b, c] = corners;
        let (e, f, w) = (sub(&b, &a), sub(&c, &a), sub(p, &a));
        let (ee, ef, ff) = (dot(&e, &e), dot(&e, &f), dot(&f, &f));
        let (we, wf) = (dot(&w, &e), dot(&w, &f));
        let (u, v) = if c == a {
            (we / ee, 0.0)
        } else {
            let det = ee * ff - ef * ef;
            ((we * ff - wf * ef) / det, (wf * ee - we * ef) / det)
        };
        (u.is_finite() && v.is_finite()).then(|| Combination::new(corners, u, v))
    }

    /// The coordinates, rounded.
    pub fn approx(&self) -> Point {
        self.approx
    }

    /// A bound on the distance, in each coordinate, between [`Combination::approx`] and the
    /// exact point.
    pub fn error(&self) -> f64 {
        self.error
    }
}

/// A point given to [`orient3d`]: its floating-point coordinates, exact, or a combination.
#[derive(Clone, Copy, Debug)]
pub enum Exact<'a> {
    Float(&'a Point),
    Combination(&'a Combination),
}

impl Exact<'_> {
    fn approx(&self) -> Point {
        match self {
            Exact::Float(p) => **p,
            Exact::Combination(c) => c.approx(),
        }
    }

    fn error(&self) -> f64 {
        match self {
            Exact::Float(_) => 0.0,
            Exact::Combination(c) => c.error(),
        }
    }
}

/// [`super::orient3d`] of points that may be combinations.
pub fn orient3d(points: [Exact; 4]) -> Sign {
    orient3d_or(points, || false)
}

/// [`orient3d`], where `coplanar` may tell, before the exact stage, that the points lie on
/// one plane (from what they are combinations of).
pub fn orient3d_or(points: [Exact; 4], coplanar: impl FnOnce() -> bool) -> Sign {
    filter(&points).unwrap_or_else(|| {
        if coplanar() {
            Sign::Zero
        } else {
            exact(&points)
        }
    })
}

/// The sign of the determinant of the rounded coordinates where it exceeds the bound of its
/// evaluation plus the largest change the combinations' rounding can make: with the exact
/// rows `R_k = r_k + d_k`, `|d_k| <= e_k + e_0` in each coordinate,
/// `det R - det r = det(d_1, R_2, R_3) + det(r_1, d_2, R_3) + det(r_1, r_2, d_3)`, and a
/// determinant is at most `3 sqrt 3` times the product of its rows' largest coordinates.
fn filter(points: &[Exact; 4]) -> Option<Sign> {
    let p = points.map(|q| q.approx());
    let e = points.map(|q| q.error());
    let r = [1, 2, 3].map(|k| sub(&p[k], &p[0]));
    let det = dot(&r[0], &cross(&r[1], &r[2]));
    let a = r.map(|row| row.map(f64::abs));
    let permanent = a[0][0] * (a[1][1] * a[2][2] + a[1][2] * a[2][1])
        + a[0][1] * (a[1][0] * a[2][2] + a[1][2] * a[2][0])
        + a[0][2] * (a[1][0] * a[2][1] + a[1][1] * a[2][0]);
    let m = a.map(|row| row[0].max(row[1]).max(row[2]) * (1.0 + 2.0 * UNIT));
    let d = [1, 2, 3].map(|k| e[k] + e[0]);
    let moved = 5.2
        * (d[0] * (m[1] + d[1]) * (m[2] + d[2]) + m[0] * d[1] * (m[2] + d[2]) + m[0] * m[1] * d[2]);
    let bound = (8.0 * UNIT * permanent + moved) * (1.0 + 16.0 * UNIT);
    // Below this, rounding in the products is no longer relative (subnormal numbers).
    const TINY: f64 = 1e-250;
    if !(det.is_finite() && bound.is_finite()) || (permanent < TINY && permanent > 0.0) {
        return None;
    }
    certify(det, bound)
}

/// The determinant over the exact coordinates, scaled by a common power of two to integers.
#[cold]
#[inline(never)]
fn exact(points: &[Exact; 4]) -> Sign {
    // The combinations' exact coordinates are borrowed, the others' made here.
    let floats = points.map(|q| match q {
        Exact::Float(p) => p.map(Dyadic::of),
        Exact::Combination(_) => [(); 3].map(|()| Dyadic::zero()),
    });
    let p: [&[Dyadic; 3]; 4] = std::array::from_fn(|k| match points[k] {
        Exact::Combination(c) => &c.exact,
        Exact::Float(_) => &floats[k],
    });
    let lowest = p
        .iter()
        .flat_map(|q| q.iter())
        .filter(|x| !x.mantissa.is_zero())
        .map(|x| x.exponent)
        .min()
        .unwrap_or(0);
    let integer = |x: &Dyadic| &x.mantissa << (x.exponent - lowest) as usize;
    let p = p.map(|q| q.each_ref().map(integer));
    let rows: [[BigInt; 3]; 3] =
        std::array::from_fn(|k| std::array::from_fn(|i| &p[k + 1][i] - &p[0][i]));
    sign(&det3(&rows))
}

/// `mantissa 2^exponent`.
#[derive(Clone, Debug)]
struct Dyadic {
    mantissa: BigInt,
    exponent: i32,
}

impl Dyadic {
    fn of(x: f64) -> Self {
        match dyadic(x) {
            Some((m, e)) => Dyadic {
                mantissa: BigInt::from(m),
                exponent: e,
            },
            None => Dyadic::zero(),
        }
    }

    fn zero() -> Self {
        Dyadic {
            mantissa: BigInt::zero(),
            exponent: 0,
        }
    }

    fn times(&self, o: &Dyadic) -> Dyadic {
        Dyadic {
            mantissa: &self.mantissa * &o.mantissa,
            exponent: self.exponent + o.exponent,
        }
    }

    fn plus(&self, o: &Dyadic) -> Dyadic {
        if self.mantissa.is_zero() {
            return o.clone();
        }
        if o.mantissa.is_zero() {
            return self.clone();
        }
        let exponent = self.exponent.min(o.exponent);
        let lifted = |x: &Dyadic| &x.mantissa << (x.exponent - exponent) as usize;
        Dyadic {
            mantissa: lifted(self) + lifted(o),
            exponent,
        }
    }

    fn minus(&self, o: &Dyadic) -> Dyadic {
        self.plus(&Dyadic {
            mantissa: -&o.mantissa,
            exponent: o.exponent,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::predicates::splitmix64;

    fn uniform(state: &mut u64) -> f64 {
        (splitmix64(state) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn random_point(state: &mut u64) -> Point {
        std::array::from_fn(|_| 2.0 * uniform(state) - 1.0)
    }

    /// Four combinations of one triangle's corners are coplanar, exactly, though their
    /// rounded coordinates are not; three of one edge's and any fourth point, too.
    #[test]
    fn combinations_of_one_triangle_are_coplanar() {
        let mut state = 7;
        let mut rounded_off = 0;
        for _ in 0..200 {
            let corners = [0; 3].map(|_| random_point(&mut state));
            let c = [0; 4]
                .map(|_| Combination::new(corners, uniform(&mut state), uniform(&mut state) * 0.5));
            let exact = orient3d(c.each_ref().map(Exact::Combination));
            assert_eq!(exact, Sign::Zero);
            let approx = c.map(|x| x.approx());
            if crate::predicates::orient3d(&approx[0], &approx[1], &approx[2], &approx[3])
                != Sign::Zero
            {
                rounded_off += 1;
            }
            let edge = [corners[0], corners[1], corners[0]];
            let on_edge = [0.3, 0.7].map(|u| Combination::new(edge, u, 0.0));
            let p = random_point(&mut state);
            let mixed = [
                Exact::Float(&corners[0]),
                Exact::Combination(&on_edge[0]),
                Exact::Combination(&on_edge[1]),
                Exact::Float(&p),
            ];
            assert_eq!(orient3d(mixed), Sign::Zero);
        }
        // The test means something: rounding alone would not give zero.
        assert!(rounded_off > 100, "{rounded_off}");
    }

    /// Off the plane, the sign is that of the exact determinant, also within the filter's
    /// bound: a combination and its rounded coordinates on either side of a plane.
    #[test]
    fn the_sign_is_exact_near_the_plane() {
        let mut state = 11;
        let mut decided_exactly = 0;
        for _ in 0..500 {
            let corners = [0; 3].map(|_| random_point(&mut state));
            let (u, v) = (uniform(&mut state), uniform(&mut state) * 0.5);
            let c = Combination::new(corners, u, v);
            let x = c.approx();
            // The plane of the triangle itself: the combination is on it, its rounding not.
            let s = orient3d([
                Exact::Float(&corners[0]),
                Exact::Float(&corners[1]),
                Exact::Float(&corners[2]),
                Exact::Combination(&c),
            ]);
            assert_eq!(s, Sign::Zero);
            // A plane through the rounded point: the combination's side is the sign of the
            // exact determinant, checked on rationals.
            let q = [random_point(&mut state), random_point(&mut state)];
            let pts = [Exact::Float(&x), Exact::Float(&q[0]), Exact::Float(&q[1])];
            let s = orient3d([pts[0], pts[1], pts[2], Exact::Combination(&c)]);
            let reference = reference_orient(&[x, q[0], q[1]], corners, u, v);
            assert_eq!(s, reference);
            if filter(&[pts[0], pts[1], pts[2], Exact::Combination(&c)]).is_none() {
                decided_exactly += 1;
            }
        }
        assert!(decided_exactly > 0);
    }

    /// orient3d over rationals, the fourth point the combination.
    fn reference_orient(p: &[Point; 3], [a, b, cc]: [Point; 3], u: f64, v: f64) -> Sign {
        use num_rational::BigRational;
        use num_traits::FromPrimitive;
        let q = |x: f64| BigRational::from_f64(x).unwrap();
        let exact_c: Vec<BigRational> = (0..3)
            .map(|k| q(a[k]) + q(u) * (q(b[k]) - q(a[k])) + q(v) * (q(cc[k]) - q(a[k])))
            .collect();
        let rows: Vec<Vec<BigRational>> = [&p[1], &p[2]]
            .iter()
            .map(|r| (0..3).map(|k| q(r[k]) - q(p[0][k])).collect())
            .chain(std::iter::once(
                (0..3).map(|k| exact_c[k].clone() - q(p[0][k])).collect(),
            ))
            .collect();
        let m = |i: usize, j: usize| {
            rows[1][i].clone() * rows[2][j].clone() - rows[1][j].clone() * rows[2][i].clone()
        };
        let det = rows[0][0].clone() * m(1, 2) - rows[0][1].clone() * m(0, 2)
            + rows[0][2].clone() * m(0, 1);
        match det.cmp(&BigRational::zero()) {
            std::cmp::Ordering::Less => Sign::Negative,
            std::cmp::Ordering::Equal => Sign::Zero,
            std::cmp::Ordering::Greater => Sign::Positive,
        }
    }
}
