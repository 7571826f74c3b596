//! The exact stage: called only when a filter cannot certify a sign.
//!
//! The in-circle, orient3d and in-sphere tests first try fixed-width integers (256 bits, 384
//! for the in-sphere) when the coordinates are integers of one power of two spanning at most
//! 61 bits ([`fixed_integers`]): near-degenerate tests on nearby points, grids and decimal
//! inputs above all, are decided there many times faster than by the expansions or big
//! integers. Otherwise orient2d, orient3d and in-circle use Shewchuk's adaptive expansions
//! (the `robust` crate) whenever those are exact for the given coordinates, and big integers
//! otherwise; the in-sphere, weighted and coplanar predicates use big integers.
//!
//! Shewchuk's expansion arithmetic is exact as long as no operation underflows or overflows. For
//! a predicate of degree `k` (2 for orient2d, 3 for orient3d, 4 for incircle),
//! every value the expansions hold is a sum of products of at most `k` input coordinates and of
//! their differences and split halves. If every nonzero coordinate has an exponent in
//! `[52 - 1022/k, 950/k]` (binary exponents, `|x| = 1.m * 2^e`), every coordinate is an integer
//! multiple of `2^-(1022/k)`, so every nonzero value is a multiple of `2^-1022`, hence a normal
//! number, and never underflows. Differences are below `2^(950/k + 2)`, every value (a sum of
//! at most `2^8` products of `k` of them) below `2^(950 + 2k + 8) <= 2^968`, and below `2^996`
//! after multiplication by the splitter `2^27 + 1`: none overflows.
//!
//! The big-integer path scales every coordinate by a common power of two, `x = X 2^q`, and every
//! weight by the square of that power, `w = W 2^(2q)`, making all of them integers. The predicates are
//! homogeneous (a determinant of degree `k` is multiplied by `2^(kq) > 0`), so the sign of the
//! same determinant over the integers `X, W` is the answer. The determinants are those the
//! filters evaluate (`filter.rs`), on the same translated rows, expanded along the last column.

use num_bigint::{BigInt, Sign as BigSign};
use num_traits::{Float, Zero};

use super::{Point, Sign, WeightedPoint};

/// Degree of orient2d in the coordinates.
const ORIENT2D_DEGREE: i32 = 2;
/// Degree of orient3d in the coordinates.
const ORIENT3D_DEGREE: i32 = 3;
/// Degree of incircle in the coordinates.
const INCIRCLE_DEGREE: i32 = 4;

/// Exact [`super::orient2d`].
#[cold]
#[inline(never)]
pub(super) fn orient2d(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> Sign {
    if shewchuk_exact(&[a, b, c], ORIENT2D_DEGREE) {
        return Sign::of(robust::orient2d(c2(a), c2(b), c2(c)));
    }
    let [a, b, c] = integers::<2, 3>([a, b, c], None);
    let rows = [sub(&b, &a), sub(&c, &a)];
    sign(&det2(&rows))
}

/// Exact [`super::incircle`].
#[cold]
#[inline(never)]
pub(super) fn incircle(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> Sign {
    if let Some(sign) = incircle_fixed(a, b, c, d) {
        return sign;
    }
    if shewchuk_exact(&[a, b, c, d], INCIRCLE_DEGREE) {
        return Sign::of(robust::incircle(c2(a), c2(b), c2(c), c2(d)));
    }
    incircle_big(a, b, c, d)
}

/// [`incircle`] in big integers.
fn incircle_big(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> Sign {
    let [a, b, c, d] = integers::<2, 4>([a, b, c, d], None);
    let rows = [&a, &b, &c].map(|p| {
        let r = sub(p, &d);
        let lift = square_norm(&r);
        [r[0].clone(), r[1].clone(), lift]
    });
    sign(&det3(&rows))
}

/// [`incircle`] in fixed-width integers, when the eight coordinates are [`fixed_integers`]
/// (nearby points, the usual case of a near-degenerate test, grids above all): the
/// differences `a - d`, `b - d`, `c - d` are then below `2^62`, the lifted coordinates and the
/// 2 by 2 minors below `2^125` in `i128`, and the determinant below `2^252` in a 256-bit sum.
/// `None` when the coordinates do not qualify.
fn incircle_fixed(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> Option<Sign> {
    let x = fixed_integers([a[0], a[1], b[0], b[1], c[0], c[1], d[0], d[1]])?;
    let r: [i64; 6] = std::array::from_fn(|k| x[k] - x[6 + k % 2]);
    let lift = |k: usize| product(r[2 * k], r[2 * k]) + product(r[2 * k + 1], r[2 * k + 1]);
    let minor =
        |i: usize, j: usize| product(r[2 * i], r[2 * j + 1]) - product(r[2 * j], r[2 * i + 1]);
    let det = [(0, 1, 2), (1, 2, 0), (2, 0, 1)]
        .map(|(k, i, j)| wide_product(lift(k), minor(i, j)))
        .into_iter()
        .fold((0i128, 0u128), wide_sum);
    Some(wide_sign(det))
}

/// [`orient3d`] in fixed-width integers, when the twelve coordinates are [`fixed_integers`]:
/// the rows `b - a`, `c - a`, `d - a` are then below `2^62`, their 2 by 2 minors below
/// `2^125` in `i128`, and the determinant (expanded along `z`, as the filter does) below
/// `2^189` in a 256-bit sum. `None` when the coordinates do not qualify.
fn orient3d_fixed(a: &Point, b: &Point, c: &Point, d: &Point) -> Option<Sign> {
    let points = [a, b, c, d];
    let x: [i64; 12] = fixed_integers(std::array::from_fn(|k| points[k / 3][k % 3]))?;
    let [r, s, t]: [[i64; 3]; 3] =
        std::array::from_fn(|i| std::array::from_fn(|k| x[3 * (i + 1) + k] - x[k]));
    Some(wide_sign(det3_fixed(&r, &s, &t)))
}

/// The determinant of the rows `r, s, t` (each below `2^62`), expanded along `z` as the
/// filters do: 2 by 2 minors below `2^125` in `i128`, the result below `2^189` in 256 bits.
fn det3_fixed(r: &[i64; 3], s: &[i64; 3], t: &[i64; 3]) -> (i128, u128) {
    let minor = |p: &[i64; 3], q: &[i64; 3]| product(p[0], q[1]) - product(q[0], p[1]);
    [
        wide_product(i128::from(r[2]), minor(s, t)),
        wide_product(-i128::from(s[2]), minor(r, t)),
        wide_product(i128::from(t[2]), minor(r, s)),
    ]
    .into_iter()
    .fold((0i128, 0u128), wide_sum)
}

/// [`insphere`] in fixed-width integers, when the fifteen coordinates are
/// [`fixed_integers`]: the rows `p - e` are then below `2^62`, their lifted coordinates below
/// `2^126` and 2 by 2 minors below `2^125` in `i128`, their 3 by 3 minors below `2^189` in
/// 256 bits, and the 4 by 4 determinant (expanded as the filter does) below `2^317` in 384
/// bits. `None` when the coordinates do not qualify.
fn insphere_fixed(a: &Point, b: &Point, c: &Point, d: &Point, e: &Point) -> Option<Sign> {
    let points = [a, b, c, d, e];
    let x: [i64; 15] = fixed_integers(std::array::from_fn(|k| points[k / 3][k % 3]))?;
    let rows: [[i64; 3]; 4] =
        std::array::from_fn(|i| std::array::from_fn(|k| x[3 * i + k] - x[12 + k]));
    let lift = |r: &[i64; 3]| product(r[0], r[0]) + product(r[1], r[1]) + product(r[2], r[2]);
    let [ra, rb, rc, rd] = &rows;
    // (ld*abc - lc*abd) + (lb*acd - la*bcd), the translated determinant, is -insphere.
    let terms = [
        (lift(rd), det3_fixed(ra, rb, rc), true),
        (lift(rc), det3_fixed(ra, rb, rd), false),
        (lift(rb), det3_fixed(ra, rc, rd), true),
        (lift(ra), det3_fixed(rb, rc, rd), false),
    ];
    let det = terms
        .into_iter()
        .map(|(l, m, plus)| {
            let term = lift_times_minor(l, m);
            if plus {
                term
            } else {
                negate(term)
            }
        })
        .fold([0u128; 3], add_limbs);
    Some(match det {
        [0, 0, 0] => Sign::Zero,
        [_, _, top] if (top as i128) < 0 => Sign::Positive,
        _ => Sign::Negative,
    })
}

/// The coordinates as integers `X` of one power of two, `x = X 2^e`, when all are finite and
/// `|X| < 2^61` (they span at most 61 bits, zeros aside): differences of two are below `2^62`.
/// The predicates are homogeneous, so the sign of a determinant of such differences is that
/// of the original one.
fn fixed_integers<const N: usize>(coordinates: [f64; N]) -> Option<[i64; N]> {
    // Each nonzero coordinate is m 2^e with m odd: its lowest bit 2^e, its highest below
    // 2^(e + bits of m).
    let mut parts = [(0i64, 0i32); N];
    let (mut lowest, mut highest) = (i32::MAX, i32::MIN);
    for (part, &x) in parts.iter_mut().zip(&coordinates) {
        if x == 0.0 {
            continue;
        }
        if !x.is_finite() {
            return None;
        }
        let (mantissa, exponent, sign) = x.integer_decode();
        let zeros = mantissa.trailing_zeros();
        let odd = (mantissa >> zeros) as i64 * i64::from(sign);
        let low = i32::from(exponent) + zeros as i32;
        lowest = lowest.min(low);
        highest = highest.max(low + (64 - (mantissa >> zeros).leading_zeros()) as i32);
        *part = (odd, low);
    }
    if lowest == i32::MAX {
        return Some([0; N]);
    }
    if highest - lowest > 61 {
        return None;
    }
    // Zeros kept their (0, 0): no shift, which `low - lowest` could make negative.
    Some(parts.map(|(odd, low)| if odd == 0 { 0 } else { odd << (low - lowest) }))
}

/// `a b` in `i128`, for `|a|, |b| < 2^63`.
fn product(a: i64, b: i64) -> i128 {
    i128::from(a) * i128::from(b)
}

/// The sign of a 256-bit two's complement integer `(high, low)`.
fn wide_sign(x: (i128, u128)) -> Sign {
    match x {
        (0, 0) => Sign::Zero,
        (high, _) if high < 0 => Sign::Negative,
        _ => Sign::Positive,
    }
}

/// `a b` as a 256-bit two's complement integer `(high, low)`, for `|a|, |b| < 2^126`.
fn wide_product(a: i128, b: i128) -> (i128, u128) {
    let (high, low) = unsigned_product(a.unsigned_abs(), b.unsigned_abs());
    if (a < 0) != (b < 0) {
        let [low, high] = negate([low, high]);
        (high as i128, low)
    } else {
        (high as i128, low)
    }
}

/// `x y` as `(high, low)` 128-bit halves.
fn unsigned_product(x: u128, y: u128) -> (u128, u128) {
    const HALF: u128 = u64::MAX as u128;
    let (x1, x0, y1, y0) = (x >> 64, x & HALF, y >> 64, y & HALF);
    let (cross0, cross1) = (x0 * y1, x1 * y0);
    let (low, carry0) = (x0 * y0).overflowing_add(cross0 << 64);
    let (low, carry1) = low.overflowing_add(cross1 << 64);
    // The true high half is below 2^128 and every term is nonnegative: no overflow.
    let high = x1 * y1 + (cross0 >> 64) + (cross1 >> 64) + u128::from(carry0) + u128::from(carry1);
    (high, low)
}

/// Two's complement negation of a little-endian multi-limb integer.
fn negate<const N: usize>(x: [u128; N]) -> [u128; N] {
    let mut out = x.map(|limb| !limb);
    for limb in &mut out {
        let (sum, carry) = limb.overflowing_add(1);
        *limb = sum;
        if !carry {
            break;
        }
    }
    out
}

/// The sum of two little-endian multi-limb two's complement integers, modulo `2^(128 N)`.
fn add_limbs<const N: usize>(x: [u128; N], y: [u128; N]) -> [u128; N] {
    let mut carry = false;
    std::array::from_fn(|k| {
        let (sum, c1) = x[k].overflowing_add(y[k]);
        let (sum, c2) = sum.overflowing_add(u128::from(carry));
        carry = c1 || c2;
        sum
    })
}

/// `l m` as a 384-bit two's complement integer (three little-endian limbs), for
/// `0 <= l < 2^126` and a 256-bit `m` (as [`wide_product`] gives it) with `|m| < 2^254`.
fn lift_times_minor(l: i128, (high, low): (i128, u128)) -> [u128; 3] {
    let magnitude = if high < 0 {
        negate([low, high as u128])
    } else {
        [low, high as u128]
    };
    let l = l.unsigned_abs();
    let (p1, p0) = unsigned_product(l, magnitude[0]);
    let (q1, q0) = unsigned_product(l, magnitude[1]);
    let (middle, carry) = p1.overflowing_add(q0);
    let product = [p0, middle, q1 + u128::from(carry)];
    if high < 0 {
        negate(product)
    } else {
        product
    }
}

/// The sum of two 256-bit two's complement integers (no overflow for the magnitudes of
/// [`incircle_fixed`]).
fn wide_sum((h1, l1): (i128, u128), (h2, l2): (i128, u128)) -> (i128, u128) {
    let (low, carry) = l1.overflowing_add(l2);
    (h1 + h2 + i128::from(carry), low)
}

/// Exact [`super::orient3d`].
#[cold]
#[inline(never)]
pub(super) fn orient3d(a: &Point, b: &Point, c: &Point, d: &Point) -> Sign {
    if let Some(sign) = orient3d_fixed(a, b, c, d) {
        return sign;
    }
    if shewchuk_exact(&[a, b, c, d], ORIENT3D_DEGREE) {
        // Shewchuk's orient3d is the opposite of ours.
        return Sign::of(-robust::orient3d(c3(a), c3(b), c3(c), c3(d)));
    }
    let [a, b, c, d] = integers::<3, 4>([a, b, c, d], None);
    sign(&det3(&[sub(&b, &a), sub(&c, &a), sub(&d, &a)]))
}

/// Exact [`super::insphere`].
#[cold]
#[inline(never)]
pub(super) fn insphere(a: &Point, b: &Point, c: &Point, d: &Point, e: &Point) -> Sign {
    if let Some(sign) = insphere_fixed(a, b, c, d, e) {
        return sign;
    }
    // Big integers, not the expansions: `robust`'s in-sphere zeroes arrays of thousands of
    // doubles on every call, which makes it several times slower here (fandisk: 147,000
    // instructions a call against 22,000).
    insphere_big(a, b, c, d, e)
}

/// [`insphere`] in big integers: the power test of the points with zero weights.
fn insphere_big(a: &Point, b: &Point, c: &Point, d: &Point, e: &Point) -> Sign {
    let [a, b, c, d, e] = [a, b, c, d, e].map(|p| [p[0], p[1], p[2], 0.0]);
    power_test(&a, &b, &c, &d, &e)
}

/// Exact [`super::power_test`]: minus the determinant with rows `(x, y, z, l)` of `a..d`
/// translated to `e`, `l = |p - e|^2 - (w_p - w_e)`.
#[cold]
#[inline(never)]
pub(super) fn power_test(
    a: &WeightedPoint,
    b: &WeightedPoint,
    c: &WeightedPoint,
    d: &WeightedPoint,
    e: &WeightedPoint,
) -> Sign {
    let [a, b, c, d, e] = integers::<4, 5>([a, b, c, d, e], Some(3));
    let rows = [&a, &b, &c, &d].map(|p| {
        let r = sub(p, &e);
        let lift = square_norm(&r[..3]) - &r[3];
        [r[0].clone(), r[1].clone(), r[2].clone(), lift]
    });
    sign(&det4(&rows)).negate()
}

/// Exact coplanar power test determinant (see `filter::power_coplanar`): rows `(u, v, l)` of
/// `a - p, b - p, c - p`, `l` the full 3D lifted coordinate.
#[cold]
#[inline(never)]
pub(super) fn power_coplanar(
    a: &WeightedPoint,
    b: &WeightedPoint,
    c: &WeightedPoint,
    p: &WeightedPoint,
    [u, v, _]: [usize; 3],
) -> Sign {
    let [a, b, c, p] = integers::<4, 4>([a, b, c, p], Some(3));
    let rows = [&a, &b, &c].map(|q| {
        let r = sub(q, &p);
        let lift = square_norm(&r[..3]) - &r[3];
        [r[u].clone(), r[v].clone(), lift]
    });
    sign(&det3(&rows))
}

/// Whether Shewchuk's expansions evaluate a predicate of degree `degree` exactly on these
/// coordinates (see the module documentation).
fn shewchuk_exact<const D: usize>(points: &[&[f64; D]], degree: i32) -> bool {
    let range = 52 - 1022 / degree..=950 / degree;
    points
        .iter()
        .flat_map(|p| p.iter())
        .all(|&x| x == 0.0 || range.contains(&binary_exponent(x)))
}

/// The exponent `e` of a normal `x = 1.m * 2^e`; below `-1022` for subnormal numbers.
fn binary_exponent(x: f64) -> i32 {
    ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023
}

fn c2(p: &[f64; 2]) -> robust::Coord<f64> {
    robust::Coord { x: p[0], y: p[1] }
}

fn c3(p: &Point) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    }
}

/// The integers `X = x 2^-q` for the coordinates and `W = w 2^-2q` for the component
/// `weight` (if any) of `N` points of dimension `D`, for the largest `q` making all of them
/// integers.
fn integers<const D: usize, const N: usize>(
    points: [&[f64; D]; N],
    weight: Option<usize>,
) -> [[BigInt; D]; N] {
    let is_weight = |k: usize| weight == Some(k);
    let parts = points.map(|p| p.map(dyadic));
    let q = parts
        .iter()
        .flat_map(|p| p.iter().enumerate())
        .filter_map(|(k, part)| {
            let (_, exponent) = (*part)?;
            Some(if is_weight(k) {
                exponent.div_euclid(2)
            } else {
                exponent
            })
        })
        .min()
        .unwrap_or(0);
    parts.map(|p| {
        std::array::from_fn(|k| match p[k] {
            None => BigInt::zero(),
            Some((mantissa, exponent)) => {
                let scale = if is_weight(k) { 2 * q } else { q };
                let shift = usize::try_from(exponent - scale)
                    .expect("the common exponent is the smallest one");
                BigInt::from(mantissa) << shift
            }
        })
    })
}

/// `x = m 2^e` for integers `m, e`; `None` for zero.
pub(super) fn dyadic(x: f64) -> Option<(i64, i32)> {
    let (mantissa, exponent, sign) = Float::integer_decode(x);
    let mantissa = i64::try_from(mantissa).expect("53-bit mantissa");
    (mantissa != 0).then(|| (i64::from(sign) * mantissa, i32::from(exponent)))
}

pub(super) fn sign(x: &BigInt) -> Sign {
    match x.sign() {
        BigSign::Minus => Sign::Negative,
        BigSign::NoSign => Sign::Zero,
        BigSign::Plus => Sign::Positive,
    }
}

fn sub<const D: usize>(p: &[BigInt; D], q: &[BigInt; D]) -> [BigInt; D] {
    std::array::from_fn(|k| &p[k] - &q[k])
}

fn square_norm(r: &[BigInt]) -> BigInt {
    r.iter().map(|x| x * x).sum()
}

/// `r0[0] r1[1] - r1[0] r0[1]`.
fn minor(r0: &[BigInt], r1: &[BigInt]) -> BigInt {
    &r0[0] * &r1[1] - &r1[0] * &r0[1]
}

fn det2(rows: &[[BigInt; 2]; 2]) -> BigInt {
    minor(&rows[0], &rows[1])
}

/// Expanded along the last column.
pub(super) fn det3(rows: &[[BigInt; 3]; 3]) -> BigInt {
    let [a, b, c] = rows;
    &a[2] * minor(b, c) - &b[2] * minor(a, c) + &c[2] * minor(a, b)
}

/// Expanded along the last column.
fn det4(rows: &[[BigInt; 4]; 4]) -> BigInt {
    (0..4).fold(BigInt::zero(), |det, i| {
        let others: [usize; 3] = std::array::from_fn(|k| if k < i { k } else { k + 1 });
        let minor = others.map(|j| [0, 1, 2].map(|k| rows[j][k].clone()));
        let term = &rows[i][3] * det3(&minor);
        // Cofactor sign of entry (i, 3): (-1)^(i+3).
        if i % 2 == 1 {
            det + term
        } else {
            det - term
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::predicates::splitmix64 as next;

    /// Runs `case` on 40000 rounds (the round number and a draw of `0..n`); each gives the
    /// fixed-width sign, if the inputs qualified, and the big-integer one, which must agree.
    /// More than half the rounds must qualify and more than 500 be degenerate.
    fn assert_agreement(
        mut state: u64,
        mut case: impl FnMut(usize, &mut dyn FnMut(u64) -> u64) -> Option<(Sign, Sign)>,
    ) {
        let (mut decided, mut zeros) = (0, 0);
        for round in 0..40000 {
            let Some((sign, expected)) = case(round, &mut |n| next(&mut state) % n) else {
                continue;
            };
            assert_eq!(sign, expected, "round {round}");
            decided += 1;
            zeros += usize::from(expected == Sign::Zero);
        }
        assert!(
            decided > 20000 && zeros > 500,
            "{decided} decided, {zeros} zero"
        );
    }

    /// A grid spacing and an offset for a round.
    fn scale_of(round: usize) -> (f64, f64) {
        (
            [1.0, 0.01, 1e-7, 3.0e5][round % 4],
            [0.0, 0.3, -17.25, 1e6][(round / 4) % 4],
        )
    }

    #[test]
    fn fixed_width_incircle_agrees_with_big_integers() {
        assert_agreement(11, |round, draw| {
            // Points of a grid of spacing h around an offset (exact differences, often
            // cocircular), or near a circle (nearly cocircular), or anywhere.
            let (h, offset) = scale_of(round);
            let mut point = |_| match round % 3 {
                0 => [
                    offset + h * (draw(9) as f64 - 4.0),
                    offset + h * (draw(9) as f64 - 4.0),
                ],
                1 => {
                    let t = draw(1 << 20) as f64 * std::f64::consts::TAU / (1 << 20) as f64;
                    [offset + h * 4.0 * t.cos(), offset + h * 4.0 * t.sin()]
                }
                _ => [
                    offset + h * (draw(1 << 30) as f64 / (1 << 20) as f64),
                    h * (draw(1 << 30) as f64 / (1 << 26) as f64),
                ],
            };
            let [a, b, c, d] = [0, 1, 2, 3].map(&mut point);
            Some((
                incircle_fixed(&a, &b, &c, &d)?,
                incircle_big(&a, &b, &c, &d),
            ))
        });
    }

    /// A point of round `round` in 3D: on a grid of `grid` steps per axis around an offset
    /// (often degenerate), with decimal coordinates `k / scale`, `|k| < range` (inexact
    /// differences), or anywhere.
    fn point3(
        round: usize,
        draw: &mut dyn FnMut(u64) -> u64,
        grid: u64,
        (range, scale): (u64, f64),
    ) -> Point {
        let (h, offset) = scale_of(round);
        let half = (grid / 2) as f64;
        [0, 1, 2].map(|_| match round % 3 {
            0 => offset + h * (draw(grid) as f64 - half),
            1 => (draw(2 * range) as f64 - range as f64) / scale,
            _ => offset + h * (draw(1 << 30) as f64 / (1 << 20) as f64),
        })
    }

    #[test]
    fn fixed_width_orient3d_agrees_with_big_integers() {
        assert_agreement(13, |round, draw| {
            let [a, b, c, d] = [0, 1, 2, 3].map(|_| point3(round, draw, 5, (1000, 1e4)));
            let [ia, ib, ic, id] = integers::<3, 4>([&a, &b, &c, &d], None);
            let expected = super::sign(&det3(&[sub(&ib, &ia), sub(&ic, &ia), sub(&id, &ia)]));
            Some((orient3d_fixed(&a, &b, &c, &d)?, expected))
        });
    }

    #[test]
    fn fixed_width_insphere_agrees_with_big_integers() {
        assert_agreement(17, |round, draw| {
            let [a, b, c, d, e] = [0, 1, 2, 3, 4].map(|_| point3(round, draw, 3, (100, 1e3)));
            Some((
                insphere_fixed(&a, &b, &c, &d, &e)?,
                insphere_big(&a, &b, &c, &d, &e),
            ))
        });
    }

    #[test]
    fn wide_products_and_sums() {
        let big = (1i128 << 125) - 3;
        for (a, b) in [
            (big, big),
            (-big, big),
            (big, -1),
            (-1, -1),
            (0, -big),
            (7, -9),
        ] {
            let (high, low) = wide_product(a, b);
            let expected = num_bigint::BigInt::from(a) * num_bigint::BigInt::from(b);
            let got = (num_bigint::BigInt::from(high) << 128) + num_bigint::BigInt::from(low);
            assert_eq!(got, expected, "{a} * {b}");
        }
        let sum = wide_sum(wide_product(big, big), wide_product(-big, big));
        assert_eq!(sum, (0, 0));
        assert_eq!(wide_sum((0, u128::MAX), (0, 1)), (1, 0));
        assert_eq!(wide_sum((-1, u128::MAX), (0, 1)), (0, 0));
        // 384-bit products of a lift and a 256-bit minor, and their sums.
        let limbs = |x: [u128; 3]| {
            let top = num_bigint::BigInt::from(x[2] as i128) << 256;
            top + (num_bigint::BigInt::from(x[1]) << 128) + num_bigint::BigInt::from(x[0])
        };
        let lift = (1i128 << 126) - 1;
        for m in [
            wide_product(big, big),
            wide_product(-big, big),
            wide_product(big, -7),
            (0, 5),
            (-1, u128::MAX),
        ] {
            let minor = (num_bigint::BigInt::from(m.0) << 128) + num_bigint::BigInt::from(m.1);
            for l in [lift, 1, 0] {
                let got = lift_times_minor(l, m);
                assert_eq!(
                    limbs(got),
                    num_bigint::BigInt::from(l) * &minor,
                    "{l} * {m:?}"
                );
                let sum = add_limbs(got, negate(got));
                assert_eq!(sum, [0; 3]);
            }
        }
    }
}
