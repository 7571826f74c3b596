//! Exact geometric predicates (DESIGN.md layer 1).
//!
//! Decisions are exact: every function returns the sign of a polynomial in the input
//! coordinates, evaluated exactly. Constructions elsewhere are floating point.
//!
//! Sign conventions (all positive cases are "the expected, non-degenerate" side):
//! - [`orient2d`]`(a,b,c)` is positive when `a, b, c` turn counter-clockwise.
//! - [`incircle`]`(a,b,c,d)`, for counter-clockwise `a, b, c`: positive when `d` lies strictly
//!   inside their circumcircle.
//! - [`orient3d`]`(a,b,c,d)` is the sign of `dot(b-a, cross(c-a, d-a))`: positive when
//!   `(a,b,c,d)` is a positively oriented tetrahedron (the C API's convention). This is the
//!   opposite of Shewchuk's `orient3d`.
//! - [`insphere`]`(a,b,c,d,e)`, for positively oriented `(a,b,c,d)`: positive when `e` lies
//!   strictly inside the circumsphere.
//! - [`power_test`]: the weighted version: positive when the lifted point
//!   `(e, |e|^2 - w_e)` lies strictly below the hyperplane through the lifted `a..d`, i.e.
//!   `e` is in conflict with the tetrahedron in the regular triangulation.
//! - [`incircle_coplanar`] and [`power_test_coplanar`]: the same tests for four coplanar points,
//!   in the plane of the triangle `a, b, c`, whatever its orientation.
//!
//! In terms of determinants, with the lifted coordinate `l(p) = |p|^2 - w_p` (`w_p = 0` for
//! unweighted points) and rows listed in argument order:
//! `orient3d = det[1 p]`, `insphere = power_test = -det[1 p l(p)]`, `orient2d = det[1 p]`,
//! `incircle = -det[1 p l(p)]` (the last two in the plane).
//!
//! Every predicate first runs a semi-static floating-point filter (`filter.rs`); only the calls
//! it cannot certify go to the exact stage (`exact.rs`). Neither allocates unless the exact stage
//! falls back to big integers (coordinates outside the range of Shewchuk's expansions, or the
//! weighted and coplanar predicates).
//!
//! The `_sos` variants never return [`Sign::Zero`] for a non-degenerate simplex: exact ties are
//! broken by a symbolic perturbation of the lifted coordinate, `l(p) + eps^(n - r_p)` for the
//! `n` points of the test, where `r_p` in `0..n` is the rank of `p` in the lexicographic order
//! of the coordinates ([`lex_cmp`], weights play no part), so the lexicographically largest
//! point is lifted the most. The outcome depends on the points only, never on the order in
//! which they are given or inserted; it is the perturbation of CGAL's
//! `Delaunay_triangulation_3::side_of_oriented_sphere`, `coplanar_side_of_bounded_circle` and
//! `Regular_triangulation_3::side_of_power_sphere` with `perturb = true` (derivation in `perturb.rs`).

pub mod combination;
mod exact;

/// splitmix64: the fixed-seed generator of the predicate tests.
#[cfg(test)]
pub(crate) fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}
mod filter;
mod perturb;
mod plane;

use std::cmp::Ordering;

use plane::Projection;

/// A point of R^3.
pub type Point = [f64; 3];

/// A weighted point: `x, y, z, weight`. Its lifted coordinate is `|p|^2 - weight`.
pub type WeightedPoint = [f64; 4];

/// The sign of an exactly evaluated determinant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(i8)]
pub enum Sign {
    Negative = -1,
    Zero = 0,
    Positive = 1,
}

impl Sign {
    /// The sign of a floating-point value known to be exact (or of an exact expansion's top term).
    pub fn of(x: f64) -> Sign {
        if x > 0.0 {
            Sign::Positive
        } else if x < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }

    pub fn negate(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }
}

/// The sign of a product is the product of the signs.
impl std::ops::Mul for Sign {
    type Output = Sign;

    fn mul(self, other: Sign) -> Sign {
        match other {
            Sign::Positive => self,
            Sign::Zero => Sign::Zero,
            Sign::Negative => self.negate(),
        }
    }
}

/// Lexicographic order of points: by `x`, then `y`, then `z`. The order of the symbolic
/// perturbation. Inputs are finite; `-0.0` and `0.0` compare equal.
pub fn lex_cmp(a: &Point, b: &Point) -> Ordering {
    let axis = |k: usize| a[k].partial_cmp(&b[k]).unwrap_or(Ordering::Equal);
    axis(0).then_with(|| axis(1)).then_with(|| axis(2))
}

/// Sign of `cross(b-a, c-a)`: positive when `a, b, c` turn counter-clockwise.
pub fn orient2d(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> Sign {
    filter::orient2d(a, b, c).unwrap_or_else(|| exact::orient2d(a, b, c))
}

/// For counter-clockwise `a, b, c`: positive when `d` is strictly inside their circumcircle
/// (the sign flips for clockwise `a, b, c`).
pub fn incircle(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> Sign {
    filter::incircle(a, b, c, d).unwrap_or_else(|| exact::incircle(a, b, c, d))
}

/// Sign of `dot(b-a, cross(c-a, d-a))`; positive for a positively oriented tetrahedron.
#[inline]
pub fn orient3d(a: &Point, b: &Point, c: &Point, d: &Point) -> Sign {
    match filter::orient3d(a, b, c, d) {
        Some(sign) => sign,
        None => exact::orient3d(a, b, c, d),
    }
}

/// For positively oriented `(a,b,c,d)`: positive when `e` is strictly inside their circumsphere.
#[inline]
pub fn insphere(a: &Point, b: &Point, c: &Point, d: &Point, e: &Point) -> Sign {
    match filter::insphere(a, b, c, d, e) {
        Some(sign) => sign,
        None => exact::insphere(a, b, c, d, e),
    }
}

/// The hot predicates of a triangulation whose points all lie in one box: a first filter
/// whose bound is fixed by the box (no per-call maxima), then the ordinary filter bound on the
/// same determinant, then the exact stage.
#[derive(Clone, Copy, Debug)]
pub struct BoxFilter(filter::BoxBounds);

impl BoxFilter {
    /// For points with `lo <= p <= hi` coordinate-wise.
    pub fn new(lo: &Point, hi: &Point) -> Self {
        BoxFilter(filter::BoxBounds::new(lo, hi))
    }

    /// [`orient3d`] of points of the box.
    #[inline]
    pub fn orient3d(&self, a: &Point, b: &Point, c: &Point, d: &Point) -> Sign {
        match self.0.orient3d(a, b, c, d) {
            Some(sign) => sign,
            None => exact::orient3d(a, b, c, d),
        }
    }

    /// [`orient3d`] of points of the box, where it is certain though any of them may move by
    /// up to `moved` in each coordinate: the box's bound widened by what such moves can
    /// change (see [`combination`]); `None` otherwise.
    #[inline]
    pub fn orient3d_moved(
        &self,
        a: &Point,
        b: &Point,
        c: &Point,
        d: &Point,
        moved: f64,
    ) -> Option<Sign> {
        self.0
            .orient3d_beyond(a, b, c, d, self.0.moved_margin(moved))
    }

    /// [`insphere`] of points of the box.
    #[inline]
    pub fn insphere(&self, a: &Point, b: &Point, c: &Point, d: &Point, e: &Point) -> Sign {
        match self.0.insphere(a, b, c, d, e) {
            Some(sign) => sign,
            None => exact::insphere(a, b, c, d, e),
        }
    }

    /// [`insphere_sos`] of points of the box.
    #[inline]
    pub fn insphere_sos(&self, a: &Point, b: &Point, c: &Point, d: &Point, e: &Point) -> Sign {
        match self.0.insphere(a, b, c, d, e) {
            Some(sign) => sign,
            None => match exact::insphere(a, b, c, d, e) {
                Sign::Zero => perturb::insphere(a, b, c, d, e),
                sign => sign,
            },
        }
    }
}

/// The planar predicates of points that all lie in one box: a first filter whose bound is
/// fixed by the box, then [`orient2d`] / the caller's in-circle test.
#[derive(Clone, Copy, Debug)]
pub struct BoxFilter2d(filter::BoxBounds2d);

impl BoxFilter2d {
    /// For points with `lo <= p <= hi` coordinate-wise.
    pub fn new(lo: &[f64; 2], hi: &[f64; 2]) -> Self {
        BoxFilter2d(filter::BoxBounds2d::new(lo, hi))
    }

    /// [`orient2d`] of points of the box.
    #[inline]
    pub fn orient2d(&self, a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> Sign {
        self.0
            .orient2d(a, b, c)
            .unwrap_or_else(|| orient2d(a, b, c))
    }

    /// The sign of [`incircle`] of points of the box when the box's bound decides it, else
    /// `fallback()` (the caller's exact test, with its tie-breaking).
    #[inline]
    pub fn incircle_or(&self, points: [&[f64; 2]; 4], fallback: impl FnOnce() -> Sign) -> Sign {
        self.0.incircle_or(points, fallback)
    }
}

/// [`insphere`] with ties broken by the symbolic perturbation: never `Zero`.
///
/// Precondition: `(a,b,c,d)` is positively oriented and the five points are distinct.
pub fn insphere_sos(a: &Point, b: &Point, c: &Point, d: &Point, e: &Point) -> Sign {
    match insphere(a, b, c, d, e) {
        Sign::Zero => perturb::insphere(a, b, c, d, e),
        sign => sign,
    }
}

/// For positively oriented `(a,b,c,d)`: positive when the lifted `e` lies strictly below the
/// hyperplane through the lifted `a..d` (`e` is in conflict). With zero weights it is
/// [`insphere`].
pub fn power_test(
    a: &WeightedPoint,
    b: &WeightedPoint,
    c: &WeightedPoint,
    d: &WeightedPoint,
    e: &WeightedPoint,
) -> Sign {
    filter::power_test(a, b, c, d, e).unwrap_or_else(|| exact::power_test(a, b, c, d, e))
}

/// [`power_test`] with ties broken by the symbolic perturbation (by coordinates only): never
/// `Zero`.
///
/// Precondition: `(a,b,c,d)` is positively oriented and the five points have distinct
/// coordinates.
pub fn power_test_sos(
    a: &WeightedPoint,
    b: &WeightedPoint,
    c: &WeightedPoint,
    d: &WeightedPoint,
    e: &WeightedPoint,
) -> Sign {
    match power_test(a, b, c, d, e) {
        Sign::Zero => perturb::power_test(a, b, c, d, e),
        sign => sign,
    }
}

/// For `p` coplanar with the non-collinear `a, b, c` (`orient3d(a,b,c,p) == Zero`): positive
/// when `p` is strictly inside the circumcircle of `a, b, c`, whatever their orientation.
/// `Zero` when `a, b, c` are collinear. It is [`power_test_coplanar`] with zero weights.
pub fn incircle_coplanar(a: &Point, b: &Point, c: &Point, p: &Point) -> Sign {
    power_test_coplanar(
        &unweighted(a),
        &unweighted(b),
        &unweighted(c),
        &unweighted(p),
    )
}

/// [`incircle_coplanar`] with ties broken by the symbolic perturbation: never `Zero` when
/// `a, b, c` are not collinear (and the four points are distinct).
pub fn incircle_coplanar_sos(a: &Point, b: &Point, c: &Point, p: &Point) -> Sign {
    power_test_coplanar_sos(
        &unweighted(a),
        &unweighted(b),
        &unweighted(c),
        &unweighted(p),
    )
}

/// The power test in the plane of the non-collinear `a, b, c`, for a coplanar `p`: positive
/// when the lifted `p` lies strictly below the plane through the lifted `a, b, c` (`p` is in
/// conflict with the triangle), whatever the orientation of `a, b, c`. `Zero` when `a, b, c`
/// are collinear. With zero weights it is [`incircle_coplanar`].
pub fn power_test_coplanar(
    a: &WeightedPoint,
    b: &WeightedPoint,
    c: &WeightedPoint,
    p: &WeightedPoint,
) -> Sign {
    match Projection::of(&xyz(a), &xyz(b), &xyz(c)) {
        Some(plane) => plane.power_test(a, b, c, p),
        None => Sign::Zero,
    }
}

/// [`power_test_coplanar`] with ties broken by the symbolic perturbation (by coordinates only):
/// never `Zero` when `a, b, c` are not collinear (and the four points have distinct
/// coordinates).
pub fn power_test_coplanar_sos(
    a: &WeightedPoint,
    b: &WeightedPoint,
    c: &WeightedPoint,
    p: &WeightedPoint,
) -> Sign {
    let Some(plane) = Projection::of(&xyz(a), &xyz(b), &xyz(c)) else {
        return Sign::Zero;
    };
    match plane.power_test(a, b, c, p) {
        Sign::Zero => perturb::power_test_coplanar(&plane, a, b, c, p),
        sign => sign,
    }
}

/// The point of a weighted point.
fn xyz(p: &WeightedPoint) -> Point {
    [p[0], p[1], p[2]]
}

/// A point with zero weight.
fn unweighted(p: &Point) -> WeightedPoint {
    [p[0], p[1], p[2], 0.0]
}
