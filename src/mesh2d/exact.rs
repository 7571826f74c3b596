//! The 2D predicates the planar tools need beyond `crate::predicates`: the sign of a dot
//! product (small-disk membership, acute angles) and the in-circle test with the symbolic
//! perturbation of `crate::predicates` (ties broken by lexicographic rank).
//!
//! Sign conventions:
//! - [`dot_sign`]`(a, b, q)` is the sign of `(a - q) . (b - q)`: `Negative` when `q` is strictly
//!   inside the closed disk of diameter `[a b]` (the *small disk*, Pébay Definition 2.1), `Zero`
//!   on its circle, `Positive` outside. With `q` the apex, it is also the sign of the cosine of
//!   the angle `a q b`: `Positive` for an acute angle.
//! - [`incircle_sos`]`(a, b, c, d)`, for counter-clockwise `a, b, c`: `Positive` when `d` is
//!   inside their circumcircle, never `Zero` for four distinct points.
//!
//! [`scaled_integers`] turns coordinates into big integers over their common power of two, for
//! exact polynomial evaluation (here and in `crossing.rs`).
//!
//! [`Predicates2d`] lets the conflict test of `delaunay.rs` run on the crate's predicates
//! ([`Adaptive`]) or on those of one box with a static filter first ([`BoxFilter2d`]).

use std::cmp::Ordering;

use num_bigint::BigInt;
use num_traits::Float;

use crate::predicates::{incircle, orient2d, BoxFilter2d, Sign};

/// Sums of products smaller than this may have lost bits to underflow: the filter defers.
const UNDERFLOW_GUARD: f64 = 1e-280;

/// Relative error bound of the floating-point dot product of two differences: each of the two
/// products carries at most `3u` relative error (`u = 2^-53`: two rounded differences and the
/// product), the sum one more `u`; `8u = 4 * EPSILON` covers it with room to spare.
const DOT_ERROR: f64 = 4.0 * f64::EPSILON;

/// The predicates the conflict test needs: `orient2d` and [`incircle_sos`], both exact.
pub trait Predicates2d {
    fn orient2d(&self, a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> Sign;
    fn incircle_sos(&self, a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> Sign;
}

/// The crate's predicates as they are (semi-static filter, then the exact stage), for points
/// anywhere.
pub struct Adaptive;

impl Predicates2d for Adaptive {
    #[inline]
    fn orient2d(&self, a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> Sign {
        orient2d(a, b, c)
    }

    #[inline]
    fn incircle_sos(&self, a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> Sign {
        incircle_sos(a, b, c, d)
    }
}

impl Predicates2d for BoxFilter2d {
    #[inline]
    fn orient2d(&self, a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> Sign {
        BoxFilter2d::orient2d(self, a, b, c)
    }

    #[inline]
    fn incircle_sos(&self, a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> Sign {
        self.incircle_or([a, b, c, d], || incircle_sos(a, b, c, d))
    }
}

/// Exact sign of `(a - q) . (b - q)`.
pub fn dot_sign(a: &[f64; 2], b: &[f64; 2], q: &[f64; 2]) -> Sign {
    let p0 = (a[0] - q[0]) * (b[0] - q[0]);
    let p1 = (a[1] - q[1]) * (b[1] - q[1]);
    let det = p0 + p1;
    let magnitude = p0.abs() + p1.abs();
    if magnitude > UNDERFLOW_GUARD && det.abs() > DOT_ERROR * magnitude {
        return Sign::of(det);
    }
    exact_dot_sign(a, b, q)
}

/// [`dot_sign`] exactly: in floating-point expansions when no operation can underflow or
/// overflow, else in big integers.
#[cold]
#[inline(never)]
fn exact_dot_sign(a: &[f64; 2], b: &[f64; 2], q: &[f64; 2]) -> Sign {
    // A product with a zero factor (a right angle along the axes, points on a grid line) is
    // zero: the sign is that of the other product, the product of the signs of its factors.
    let axis_sign = |k: usize| {
        let side = |x: f64| Sign::of(x - q[k]);
        side(a[k]) * side(b[k])
    };
    for k in 0..2 {
        if a[k] == q[k] || b[k] == q[k] {
            return axis_sign(1 - k);
        }
    }
    let coords = [a[0], a[1], b[0], b[1], q[0], q[1]];
    if coords.iter().all(|&x| expansion_safe(x)) {
        return expansion_dot_sign(a, b, q);
    }
    bigint_dot_sign(a, b, q)
}

/// [`dot_sign`] in big integers: every coordinate is an integer multiple of the smallest power
/// of two among them, so the scaled polynomial is evaluated without rounding.
fn bigint_dot_sign(a: &[f64; 2], b: &[f64; 2], q: &[f64; 2]) -> Sign {
    let ([ax, ay, bx, by, qx, qy], _) = scaled_integers([a[0], a[1], b[0], b[1], q[0], q[1]]);
    let det = (&ax - &qx) * (&bx - &qx) + (&ay - &qy) * (&by - &qy);
    sign_of(&det)
}

/// Whether `x` is zero or of magnitude in `[2^-459, 2^476)`: then `x` is a multiple of
/// `2^-511`, so that every nonzero product of two differences of such numbers and its rounding
/// error are multiples of `2^-1022` (normal numbers, no underflow), and every sum stays far
/// below overflow (the bounds of `crate::predicates` for a predicate of degree 2).
fn expansion_safe(x: f64) -> bool {
    const LOW: f64 = f64::from_bits((1023 - 459) << 52);
    const HIGH: f64 = f64::from_bits((1023 + 476) << 52);
    x == 0.0 || (LOW..HIGH).contains(&x.abs())
}

/// `(s, e)` with `s = fl(a + b)` and `s + e = a + b` exactly (Knuth's two-sum).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) + (b - bv))
}

/// The sign of `(a - q) . (b - q)` as a floating-point expansion (Shewchuk's arithmetic):
/// each difference is exact as two doubles (two-sum), each of the 8 products of their parts
/// exact as two (the fused multiply-add gives the rounding error), and the 16 terms are summed
/// into a nonoverlapping expansion, whose largest nonzero component has the sign of the sum.
/// Exact when every coordinate passes [`expansion_safe`].
fn expansion_dot_sign(a: &[f64; 2], b: &[f64; 2], q: &[f64; 2]) -> Sign {
    // Components in increasing magnitude, nonoverlapping, no zeros; one per term at most.
    let mut e = [0.0f64; 16];
    let mut len = 0;
    for k in 0..2 {
        let (u, v) = (two_sum(a[k], -q[k]), two_sum(b[k], -q[k]));
        for (x, y) in [(u.0, v.0), (u.0, v.1), (u.1, v.0), (u.1, v.1)] {
            let p = x * y;
            for term in [x.mul_add(y, -p), p] {
                if term == 0.0 {
                    continue;
                }
                // Shewchuk's GROW-EXPANSION with zero elimination, in place.
                let (mut sum, mut kept) = (term, 0);
                for i in 0..len {
                    let (s, t) = two_sum(sum, e[i]);
                    sum = s;
                    if t != 0.0 {
                        e[kept] = t;
                        kept += 1;
                    }
                }
                if sum != 0.0 {
                    e[kept] = sum;
                    kept += 1;
                }
                len = kept;
            }
        }
    }
    e[..len].last().map_or(Sign::Zero, |&x| Sign::of(x))
}

/// The finite `coords` as big integers `k` with `coords[i] = k[i] * 2^e`, and that exponent
/// `e`: the smallest power of two among them, so that polynomials in the coordinates are
/// evaluated without rounding.
pub fn scaled_integers<const N: usize>(coords: [f64; N]) -> ([BigInt; N], i32) {
    let decoded = coords.map(|x| x.integer_decode());
    let min_exponent = decoded
        .iter()
        .filter(|d| d.0 != 0)
        .map(|d| d.1)
        .min()
        .unwrap_or(0);
    let integers = decoded.map(|(mantissa, exponent, sign)| {
        if mantissa == 0 {
            return BigInt::from(0);
        }
        let value = BigInt::from(mantissa) << (exponent - min_exponent) as usize;
        if sign < 0 {
            -value
        } else {
            value
        }
    });
    (integers, i32::from(min_exponent))
}

/// The sign of a big integer.
fn sign_of(x: &BigInt) -> Sign {
    match x.sign() {
        num_bigint::Sign::Minus => Sign::Negative,
        num_bigint::Sign::NoSign => Sign::Zero,
        num_bigint::Sign::Plus => Sign::Positive,
    }
}

/// Lexicographic order of 2D points (x, then y): the order of the symbolic perturbation.
pub fn lex_cmp2(a: &[f64; 2], b: &[f64; 2]) -> Ordering {
    let axis = |k: usize| a[k].partial_cmp(&b[k]).unwrap_or(Ordering::Equal);
    axis(0).then_with(|| axis(1))
}

/// For counter-clockwise `a, b, c`: `Positive` when `d` is inside their circumcircle, exact
/// ties broken as by `crate::predicates::incircle_coplanar_sos`: the lifted coordinate of each
/// point is raised by `eps^(4 - rank)`, rank in lexicographic order. The perturbed determinant
/// is then decided by the cofactors of the lifted column in decreasing lexicographic order of
/// their point: `Negative` when `d` comes first, else the orientation of the triangle with that
/// vertex replaced by `d` (derivation in `predicates/perturb.rs`).
///
/// Precondition: `orient2d(a, b, c) > 0` and the four points are distinct.
///
/// The corners of an axis-parallel rectangle (common in grid-like inputs, where they would
/// take the slowest path of the exact stage) are recognized by comparisons of coordinates:
/// they are cocircular.
pub fn incircle_sos(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> Sign {
    if axis_rectangle([a, b, c, d]) {
        return perturbed_incircle(a, b, c, d);
    }
    match incircle(a, b, c, d) {
        Sign::Zero => perturbed_incircle(a, b, c, d),
        sign => sign,
    }
}

/// Whether the four distinct points `p` are the corners of an axis-parallel rectangle: each
/// shares its abscissa with exactly one other point and its ordinate with exactly one other.
/// (Then the abscissae form two pairs of distinct values, the ordinates too, and no two points
/// share both: the points are `(x1, y1), (x1, y2), (x2, y1), (x2, y2)`.)
fn axis_rectangle(p: [&[f64; 2]; 4]) -> bool {
    (0..2).all(|k| (0..4).all(|i| (0..4).filter(|&j| j != i && p[j][k] == p[i][k]).count() == 1))
}

#[cold]
fn perturbed_incircle(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> Sign {
    let points = [a, b, c, d];
    let mut order = [0usize, 1, 2, 3];
    order.sort_unstable_by(|&i, &j| lex_cmp2(points[j], points[i]));
    for &i in &order {
        if i == 3 {
            return Sign::Negative;
        }
        let mut triangle = [a, b, c];
        triangle[i] = d;
        let sign = orient2d(triangle[0], triangle[1], triangle[2]);
        if sign != Sign::Zero {
            return sign;
        }
    }
    Sign::Negative
}

/// Sign of "q is inside the circumcircle of `a, b, c`" whatever the orientation of `a, b, c`
/// (exact, no perturbation): `Positive` inside, `Zero` on the circle, `Negative` outside;
/// `Zero` when `a, b, c` are collinear (no circle).
pub fn in_circumcircle(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], q: &[f64; 2]) -> Sign {
    orient2d(a, b, c) * incircle(a, b, c, q)
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::predicates::splitmix64 as next;

    #[test]
    fn expansion_dot_sign_agrees_with_big_integers() {
        let mut state = 7;
        let mut uniform =
            |scale: f64| (next(&mut state) >> 11) as f64 / (1u64 << 53) as f64 * scale;
        let mut zeros = 0;
        for round in 0..20000 {
            let scale = [1.0, 1e-3, 1e7, 0.1][round % 4];
            let a = [uniform(scale), uniform(scale)];
            let b = [uniform(scale), uniform(scale)];
            // q on the small circle of [a b] (up to rounding), on grid lines through a and b, or
            // free.
            let q = match round % 3 {
                0 => {
                    let t = uniform(std::f64::consts::TAU);
                    let (c, r) = (
                        [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5],
                        (a[0] - b[0]).hypot(a[1] - b[1]) * 0.5,
                    );
                    [c[0] + r * t.cos(), c[1] + r * t.sin()]
                }
                1 if round % 2 == 0 => [a[0], b[1]],
                1 => [uniform(scale), b[1]],
                _ => [uniform(scale), uniform(scale)],
            };
            let expected = bigint_dot_sign(&a, &b, &q);
            zeros += usize::from(expected == Sign::Zero);
            assert_eq!(
                expansion_dot_sign(&a, &b, &q),
                expected,
                "{a:?} {b:?} {q:?}"
            );
            assert_eq!(dot_sign(&a, &b, &q), expected, "{a:?} {b:?} {q:?}");
        }
        assert!(zeros > 1000, "{zeros} exact zeros");
    }
}
