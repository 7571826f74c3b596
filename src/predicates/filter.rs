//! Semi-static floating-point filters: the first stage of every predicate.
//!
//! Each filter evaluates its determinant in binary64 on coordinates translated to one of the
//! points and returns its sign when `|det| > eps`, `eps = C * unit`, where `unit` is a product
//! of the largest translated coordinates per axis (`mx, my, mz`), as CGAL's static filters do;
//! otherwise (`None`) the caller goes to the exact stage. A certified sign is the exact one.
//!
//! # Error bounds
//!
//! Let `u = 2^-53`. For every value `v` of an evaluation track `B(v) >= |v|` and
//! `E(v) >= |v - v*|`, `v*` being the same expression evaluated exactly on the exact
//! differences of the inputs. Rounding to nearest without underflow satisfies
//! `|fl(z) - z| <= u|z|` and `|fl(z) - z| <= u|fl(z)|`, hence:
//! - a translated coordinate along an axis of maximum `m`: `B = m`, `E = u m`;
//! - a product: `B = (1+u) B1 B2`, `E = B1 E2 + B2 E1 + E1 E2 + u B1 B2`;
//! - a sum or difference: `B = (1+u)(B1 + B2)`, `E = E1 + E2 + u (B1 + B2)`.
//!
//! Carried through the evaluation order of each filter (kept exactly as written below), the
//! first-order coefficient of `E(det) / unit` is, with `M` the largest of the per-axis maxima
//! and `mw` the largest weight difference:
//!
//! | filter | evaluation | `E(det)/unit` | `unit` |
//! |---|---|---|---|
//! | orient2d | `bx*cy - by*cx` | `8u` | `mx my` |
//! | incircle | `(la*bc - lb*ac) + lc*ab`, `l = x*x + y*y` | `128u` | `mx my M^2` |
//! | orient3d | `(az*bc - bz*ac) + cz*ab` | `46u` | `mx my mz` |
//! | insphere | `(ld*abc - lc*abd) + (lb*acd - la*bcd)`, `l = (x*x + y*y) + z*z` | `1104u` | `mx my mz M^2` |
//! | power test | as insphere, `l = ((x*x + y*y) + z*z) - dw` | `392u` | `mx my mz (3M^2 + mw)` |
//! | coplanar power test | as incircle in the axes `u, v`, `l = ((u*u + v*v) + t*t) - dw` | `74u` | `mu mv (3M^2 + mw)` |
//!
//! (`ab = ax*by - bx*ay` and so on; the minors of orient3d are those of the translated rows.
//! The power tests' coefficient is largest for `mw = 0`; the ratio is monotone in `mw`.)
//! The terms of order `u^2` and beyond add less than `10^-15` relative, evaluating `eps` in
//! floating point (at most 8 roundings, each by a factor `>= 1 - u`) less than `2^-49`
//! relative; [`SLACK`] covers both. The orient3d constant, `46u = 5.1070e-15`, is the one
//! CGAL's `Orientation_3` static filter derives (`5.1107e-15` with its own slack).
//!
//! # Range
//!
//! A filter only decides when every per-axis maximum lies in `[lower, upper]`:
//! - `lower` keeps `eps` a normal number (`C * lower^degree >= 2^-1010`), and bounds the
//!   absolute error of products that underflow (at most `2^-1075` each) by `2^-64 eps`, inside
//!   [`SLACK`];
//! - `upper` keeps `|det|` and every intermediate value below `2^1007`, far from overflow.
//!
//! When the smallest maximum is zero a whole column of the translated determinant is zero and
//! the sign is exactly `Zero` (a difference of two doubles is zero only when they are equal).

use super::{Point, Sign, WeightedPoint};

/// Unit roundoff of binary64.
const U: f64 = f64::EPSILON / 2.0;

/// Relative margin over the first-order coefficients: covers the higher-order terms, the
/// rounding of `eps` itself and underflow within the range (see the module documentation).
const SLACK: f64 = 1.0 + 1e-12;

/// A filter's error coefficient `C` and the range of per-axis maxima in which it holds. The
/// limits are decimal numbers inside the analysed ranges: `[2^-480, 2^500]` for orient2d,
/// `[2^-240, 2^250]` for incircle and the coplanar power test, `[2^-320, 2^330]` for orient3d,
/// `[2^-190, 2^200]` for insphere and the power test.
struct Bound {
    coefficient: f64,
    lower: f64,
    upper: f64,
}

const ORIENT2D: Bound = Bound {
    coefficient: 8.0 * U * SLACK,
    lower: 1e-144,
    upper: 1e150,
};

const INCIRCLE: Bound = Bound {
    coefficient: 128.0 * U * SLACK,
    lower: 1e-72,
    upper: 1e75,
};

const ORIENT3D: Bound = Bound {
    coefficient: 46.0 * U * SLACK,
    lower: 1e-96,
    upper: 1e99,
};

const INSPHERE: Bound = Bound {
    coefficient: 1104.0 * U * SLACK,
    lower: 1e-57,
    upper: 1e60,
};

const POWER_TEST: Bound = Bound {
    coefficient: 392.0 * U * SLACK,
    ..INSPHERE
};

const POWER_COPLANAR: Bound = Bound {
    coefficient: 74.0 * U * SLACK,
    ..INCIRCLE
};

/// Largest weight difference of the power test (`<= 2^400`): with the coordinate limit it keeps
/// `3M^2 + mw <= 2^402` and `|det| <= 24 mx my mz (3M^2 + mw) < 2^1007`.
const POWER_TEST_WEIGHT_UPPER: f64 = 1e120;

/// Largest weight difference of the coplanar power test (`<= 2^500`, `|det| < 2^1005`).
const POWER_COPLANAR_WEIGHT_UPPER: f64 = 1e150;

impl Bound {
    /// The error bound `coefficient * unit` for every call within a box whose extents have
    /// extremes `smallest` and `largest`; infinite (nothing certified) outside the range the
    /// bound was derived for.
    fn over_box(&self, unit: f64, smallest: f64, largest: f64) -> f64 {
        if self.lower <= smallest && largest <= self.upper {
            self.coefficient * unit
        } else {
            f64::INFINITY
        }
    }

    /// The sign of `det`, if its error bound `coefficient * unit` certifies it. `smallest` and
    /// `largest` are the extreme per-axis maxima the bound depends on.
    #[inline]
    fn certify(&self, det: f64, unit: f64, smallest: f64, largest: f64) -> Option<Sign> {
        if smallest == 0.0 {
            return Some(Sign::Zero);
        }
        if !(self.lower <= smallest && largest <= self.upper) {
            return None;
        }
        let eps = self.coefficient * unit;
        if det > eps {
            Some(Sign::Positive)
        } else if det < -eps {
            Some(Sign::Negative)
        } else {
            None
        }
    }
}

/// The first `D` coordinates of `p - q`.
#[inline]
fn diff<const D: usize, const N: usize>(p: &[f64; N], q: &[f64; N]) -> [f64; D] {
    const { assert!(D <= N) };
    std::array::from_fn(|k| p[k] - q[k])
}

/// The largest absolute value per axis.
#[inline]
fn maxima<const N: usize, const D: usize>(rows: &[[f64; D]; N]) -> [f64; D] {
    let mut maxima = [0.0f64; D];
    for row in rows {
        for (m, x) in maxima.iter_mut().zip(row) {
            *m = m.max(x.abs());
        }
    }
    maxima
}

/// The smallest and the largest of `values`.
#[inline]
fn extremes(values: &[f64]) -> (f64, f64) {
    values.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
        (lo.min(x), hi.max(x))
    })
}

/// `p[0] q[1] - q[0] p[1]`.
#[inline]
fn minor(p: &[f64], q: &[f64]) -> f64 {
    p[0] * q[1] - q[0] * p[1]
}

/// `(x*x + y*y) + z*z`.
#[inline]
fn square_norm(p: &[f64; 3]) -> f64 {
    (p[0] * p[0] + p[1] * p[1]) + p[2] * p[2]
}

/// The 3x3 determinant of rows `a, b, c` with columns `(x, y, l)`, expanded along `l`:
/// `(la*bc - lb*ac) + lc*ab`.
#[inline]
fn lifted_det3(rows: &[[f64; 2]; 3], lifts: &[f64; 3]) -> f64 {
    let [a, b, c] = rows;
    (lifts[0] * minor(b, c) - lifts[1] * minor(a, c)) + lifts[2] * minor(a, b)
}

/// The 4x4 determinant of rows `a, b, c, d` with columns `(x, y, z, l)`, expanded along `l`:
/// `(ld*abc - lc*abd) + (lb*acd - la*bcd)`, each 3x3 minor expanded along `z`.
#[inline]
fn lifted_det4(rows: &[[f64; 3]; 4], lifts: &[f64; 4]) -> f64 {
    let [a, b, c, d] = rows;
    let (ab, ac, ad) = (minor(a, b), minor(a, c), minor(a, d));
    let (bc, bd, cd) = (minor(b, c), minor(b, d), minor(c, d));
    let abc = (a[2] * bc - b[2] * ac) + c[2] * ab;
    let abd = (a[2] * bd - b[2] * ad) + d[2] * ab;
    let acd = (a[2] * cd - c[2] * ad) + d[2] * ac;
    let bcd = (b[2] * cd - c[2] * bd) + d[2] * bc;
    (lifts[3] * abc - lifts[2] * abd) + (lifts[1] * acd - lifts[0] * bcd)
}

/// Filter of [`super::orient2d`].
#[inline]
pub(super) fn orient2d(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> Option<Sign> {
    let rows = [diff::<2, 2>(b, a), diff::<2, 2>(c, a)];
    let m = maxima(&rows);
    let (smallest, largest) = extremes(&m);
    ORIENT2D.certify(minor(&rows[0], &rows[1]), m[0] * m[1], smallest, largest)
}

/// Filter of [`super::incircle`].
#[inline]
pub(super) fn incircle(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> Option<Sign> {
    let rows = [diff::<2, 2>(a, d), diff::<2, 2>(b, d), diff::<2, 2>(c, d)];
    let lifts = rows.map(|r| r[0] * r[0] + r[1] * r[1]);
    let m = maxima(&rows);
    let (smallest, largest) = extremes(&m);
    let unit = m[0] * m[1] * largest * largest;
    INCIRCLE.certify(lifted_det3(&rows, &lifts), unit, smallest, largest)
}

/// Filter of [`super::orient3d`].
#[inline]
pub(super) fn orient3d(a: &Point, b: &Point, c: &Point, d: &Point) -> Option<Sign> {
    let [r, s, t] = [diff::<3, _>(b, a), diff::<3, _>(c, a), diff::<3, _>(d, a)];
    let det = (r[2] * minor(&s, &t) - s[2] * minor(&r, &t)) + t[2] * minor(&r, &s);
    let m = maxima(&[r, s, t]);
    let (smallest, largest) = extremes(&m);
    ORIENT3D.certify(det, m[0] * m[1] * m[2], smallest, largest)
}

/// Filter of [`super::insphere`]: the translated determinant is `-insphere`.
#[inline]
pub(super) fn insphere(a: &Point, b: &Point, c: &Point, d: &Point, e: &Point) -> Option<Sign> {
    let rows = [a, b, c, d].map(|p| diff::<3, _>(p, e));
    let lifts = rows.map(|r| square_norm(&r));
    let m = maxima(&rows);
    let (smallest, largest) = extremes(&m);
    let unit = m[0] * m[1] * m[2] * largest * largest;
    INSPHERE.certify(-lifted_det4(&rows, &lifts), unit, smallest, largest)
}

/// Filter of [`super::power_test`]: the translated determinant is `-power_test`.
pub(super) fn power_test(
    a: &WeightedPoint,
    b: &WeightedPoint,
    c: &WeightedPoint,
    d: &WeightedPoint,
    e: &WeightedPoint,
) -> Option<Sign> {
    let points = [a, b, c, d];
    let rows = points.map(|p| diff::<3, _>(p, e));
    let weights = points.map(|p| p[3] - e[3]);
    let lifts = std::array::from_fn(|i| square_norm(&rows[i]) - weights[i]);
    let m = maxima(&rows);
    let (smallest, largest) = extremes(&m);
    let (_, mw) = extremes(&weights.map(f64::abs));
    if mw > POWER_TEST_WEIGHT_UPPER {
        return None;
    }
    let unit = m[0] * m[1] * m[2] * (3.0 * (largest * largest) + mw);
    POWER_TEST.certify(-lifted_det4(&rows, &lifts), unit, smallest, largest)
}

/// Filter of the coplanar power test in the plane of the axes `[u, v, t]` (`t` dropped): the
/// sign of the determinant with rows `(u, v, l)` of `a - p, b - p, c - p`, `l` the full 3D
/// lifted coordinate (see `plane.rs`).
pub(super) fn power_coplanar(
    a: &WeightedPoint,
    b: &WeightedPoint,
    c: &WeightedPoint,
    p: &WeightedPoint,
    [u, v, t]: [usize; 3],
) -> Option<Sign> {
    let points = [a, b, c];
    let rows = points.map(|q| [q[u] - p[u], q[v] - p[v]]);
    let dropped = points.map(|q| q[t] - p[t]);
    let weights = points.map(|q| q[3] - p[3]);
    let lifts =
        std::array::from_fn(|i| square_norm(&[rows[i][0], rows[i][1], dropped[i]]) - weights[i]);
    let m = maxima(&rows);
    let (_, mt) = extremes(&dropped.map(f64::abs));
    let (_, mw) = extremes(&weights.map(f64::abs));
    if mw > POWER_COPLANAR_WEIGHT_UPPER {
        return None;
    }
    let (smallest, largest) = extremes(&[m[0], m[1]]);
    let largest = largest.max(mt);
    let unit = m[0] * m[1] * (3.0 * (largest * largest) + mw);
    POWER_COPLANAR.certify(lifted_det3(&rows, &lifts), unit, smallest, largest)
}

/// Filter bounds fixed once for every point of a box.
///
/// A filter's bound `C * unit` grows with the per-axis maxima of the translated coordinates,
/// and no computed difference of two coordinates in the box exceeds the box's computed extent
/// (rounding is monotone). The bound taken at the extents therefore holds for every call on
/// points of the box: the same determinant, evaluated in the same order as [`orient3d`] and
/// [`insphere`], is certified by one comparison, without computing the maxima. The range
/// conditions are checked on the extents once; outside them the bounds are infinite and never
/// decide.
#[derive(Clone, Copy, Debug)]
pub struct BoxBounds {
    orient3d: f64,
    insphere: f64,
    /// The box's largest extent.
    extent: f64,
}

impl BoxBounds {
    pub fn new(lo: &Point, hi: &Point) -> Self {
        let m: [f64; 3] = std::array::from_fn(|k| hi[k] - lo[k]);
        let (smallest, largest) = extremes(&m);
        let bound = |b: &Bound, unit: f64| b.over_box(unit, smallest, largest);
        BoxBounds {
            orient3d: bound(&ORIENT3D, m[0] * m[1] * m[2]),
            insphere: bound(&INSPHERE, m[0] * m[1] * m[2] * largest * largest),
            extent: largest,
        }
    }

    /// [`orient3d`]: the box's bound first, then, on the same determinant, the bound of the
    /// call's own maxima.
    #[inline]
    pub fn orient3d(&self, a: &Point, b: &Point, c: &Point, d: &Point) -> Option<Sign> {
        let [r, s, t] = [diff::<3, _>(b, a), diff::<3, _>(c, a), diff::<3, _>(d, a)];
        let det = (r[2] * minor(&s, &t) - s[2] * minor(&r, &t)) + t[2] * minor(&r, &s);
        certify(det, self.orient3d).or_else(|| {
            let m = maxima(&[r, s, t]);
            let (smallest, largest) = extremes(&m);
            ORIENT3D.certify(det, m[0] * m[1] * m[2], smallest, largest)
        })
    }

    /// A bound on the change of an orientation determinant of points of the box when each
    /// moves by up to `moved` in each coordinate: its rows move by `d = 2 moved` and are at
    /// most the extent `l`, and a determinant changes by at most `3 sqrt 3 * 3 d (l + d)^2`
    /// (it is trilinear in its rows, see `combination.rs`).
    pub fn moved_margin(&self, moved: f64) -> f64 {
        let d = 2.0 * moved;
        let reach = self.extent + d;
        15.6 * d * reach * reach * (1.0 + 1e-10)
    }

    /// [`orient3d`] where the determinant is farther from zero than the box's bound plus
    /// `margin`; `None` otherwise.
    #[inline]
    pub fn orient3d_beyond(
        &self,
        a: &Point,
        b: &Point,
        c: &Point,
        d: &Point,
        margin: f64,
    ) -> Option<Sign> {
        let [r, s, t] = [diff::<3, _>(b, a), diff::<3, _>(c, a), diff::<3, _>(d, a)];
        let det = (r[2] * minor(&s, &t) - s[2] * minor(&r, &t)) + t[2] * minor(&r, &s);
        certify(det, self.orient3d + margin)
    }

    /// [`insphere`]: the box's bound first, then, on the same determinant, the bound of the
    /// call's own maxima.
    #[inline]
    pub fn insphere(&self, a: &Point, b: &Point, c: &Point, d: &Point, e: &Point) -> Option<Sign> {
        let rows = [a, b, c, d].map(|p| diff::<3, _>(p, e));
        let lifts = rows.map(|r| square_norm(&r));
        let det = -lifted_det4(&rows, &lifts);
        certify(det, self.insphere).or_else(|| {
            let m = maxima(&rows);
            let (smallest, largest) = extremes(&m);
            let unit = m[0] * m[1] * m[2] * largest * largest;
            INSPHERE.certify(det, unit, smallest, largest)
        })
    }
}

/// [`BoxBounds`] for planar points: the bounds of [`orient2d`] and [`incircle`] taken at the
/// box's extents, for the same determinants evaluated in the same order.
#[derive(Clone, Copy, Debug)]
pub struct BoxBounds2d {
    orient2d: f64,
    incircle: f64,
}

impl BoxBounds2d {
    pub fn new(lo: &[f64; 2], hi: &[f64; 2]) -> Self {
        let m: [f64; 2] = std::array::from_fn(|k| hi[k] - lo[k]);
        let (smallest, largest) = extremes(&m);
        let bound = |b: &Bound, unit: f64| b.over_box(unit, smallest, largest);
        BoxBounds2d {
            orient2d: bound(&ORIENT2D, m[0] * m[1]),
            incircle: bound(&INCIRCLE, m[0] * m[1] * largest * largest),
        }
    }

    /// [`orient2d`] decided by the box's bound alone.
    #[inline]
    pub fn orient2d(&self, a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> Option<Sign> {
        certify(
            minor(&diff::<2, 2>(b, a), &diff::<2, 2>(c, a)),
            self.orient2d,
        )
    }

    /// [`incircle`] decided by the box's bound, else `fallback()`. The sign is taken as a
    /// value, not a branch: it is unpredictable in a Delaunay cavity search, the certification
    /// is not.
    #[inline]
    pub fn incircle_or(
        &self,
        [a, b, c, d]: [&[f64; 2]; 4],
        fallback: impl FnOnce() -> Sign,
    ) -> Sign {
        let rows = [diff::<2, 2>(a, d), diff::<2, 2>(b, d), diff::<2, 2>(c, d)];
        let lifts = rows.map(|r| r[0] * r[0] + r[1] * r[1]);
        let det = lifted_det3(&rows, &lifts);
        if det.abs() > self.incircle {
            if det > 0.0 {
                Sign::Positive
            } else {
                Sign::Negative
            }
        } else {
            fallback()
        }
    }
}

#[inline]
pub(super) fn certify(det: f64, eps: f64) -> Option<Sign> {
    if det > eps {
        Some(Sign::Positive)
    } else if det < -eps {
        Some(Sign::Negative)
    } else {
        None
    }
}
