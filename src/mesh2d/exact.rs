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

/// [`dot_sign`] in big integers: every coordinate is an integer multiple of the smallest power
/// of two among them, so the scaled polynomial is evaluated without rounding.
#[cold]
#[inline(never)]
fn exact_dot_sign(a: &[f64; 2], b: &[f64; 2], q: &[f64; 2]) -> Sign {
    let ([ax, ay, bx, by, qx, qy], _) = scaled_integers([a[0], a[1], b[0], b[1], q[0], q[1]]);
    let det = (&ax - &qx) * (&bx - &qx) + (&ay - &qy) * (&by - &qy);
    sign_of(&det)
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
pub fn incircle_sos(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> Sign {
    match incircle(a, b, c, d) {
        Sign::Zero => perturbed_incircle(a, b, c, d),
        sign => sign,
    }
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
