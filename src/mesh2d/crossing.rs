//! Splitting crossing segments at their intersection points (the option of
//! [`input::segments`](super::input::segments)).
//!
//! Given the pairs of segments that cross properly (found by exact `orient2d` signs), every
//! intersection point is handled in exact rational arithmetic (big integers over the doubles'
//! common power of two): on segment `[a b]` crossed by `[c d]` it is `a + λ (b - a)` with
//! `λ = cross(c - a, d - c) / cross(b - a, d - c)` in `(0, 1)`. The crossings on each segment
//! are sorted by their exact `λ`; two of them with the same `λ` are the same point (several
//! segments through one point), so the intersections of different pairs are merged exactly,
//! whatever the number of segments through the point. Each distinct point then gets one new
//! vertex, the double nearest to it (rounded once), numbered after the existing points in the
//! order of the first crossing pair (by segment index) through it; each segment becomes its
//! pieces between consecutive points along it, oriented as the segment.
//!
//! The rounding of a point can in principle make a piece cross another segment or pass
//! through a point; the caller checks the pieces again ([`input`](super::input)).

use std::cmp::Ordering;

use num_bigint::BigInt;
use num_traits::{Signed, ToPrimitive, Zero};

use super::cloud::Cloud;
use super::exact::scaled_integers;
use crate::union_find::UnionFind;

/// One crossing pair's intersection point, exact: on the pair's first segment at
/// `λ = lambda[0] / den`, on its second at `lambda[1] / den`; its coordinates are
/// `numerator[k] / den * 2^exponent`. `den > 0`.
struct Crossing {
    lambda: [BigInt; 2],
    numerator: [BigInt; 2],
    den: BigInt,
    exponent: i32,
}

impl Crossing {
    /// The intersection of the properly crossing `[a b]` and `[c d]`.
    fn new(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> Self {
        let ([ax, ay, bx, by, cx, cy, dx, dy], exponent) =
            scaled_integers([a[0], a[1], b[0], b[1], c[0], c[1], d[0], d[1]]);
        let cross = |ux: &BigInt, uy: &BigInt, vx: &BigInt, vy: &BigInt| ux * vy - uy * vx;
        let (ux, uy) = (&bx - &ax, &by - &ay);
        let (vx, vy) = (&dx - &cx, &dy - &cy);
        let (wx, wy) = (&cx - &ax, &cy - &ay);
        let mut den = cross(&ux, &uy, &vx, &vy);
        let mut lambda = [cross(&wx, &wy, &vx, &vy), cross(&wx, &wy, &ux, &uy)];
        if den.is_negative() {
            den = -den;
            lambda = lambda.map(|x| -x);
        }
        let numerator = [&ax * &den + &lambda[0] * &ux, &ay * &den + &lambda[0] * &uy];
        Crossing {
            lambda,
            numerator,
            den,
            exponent,
        }
    }

    /// The double nearest to the point.
    fn rounded(&self) -> [f64; 2] {
        self.numerator
            .each_ref()
            .map(|x| quotient_to_f64(x, &self.den, self.exponent))
    }
}

/// `num / den * 2^exponent` rounded to the nearest double (`den > 0`): an integer quotient of
/// 64 to 66 bits with a sticky bit for a non-zero remainder rounds as the exact value does.
fn quotient_to_f64(num: &BigInt, den: &BigInt, exponent: i32) -> f64 {
    if num.is_zero() {
        return 0.0;
    }
    let shift = 65 - (num.bits() as i64 - den.bits() as i64);
    let magnitude = num.abs();
    let (q, r) = if shift >= 0 {
        let scaled = magnitude << shift as usize;
        (&scaled / den, &scaled % den)
    } else {
        let scaled = den << (-shift) as usize;
        (&magnitude / &scaled, &magnitude % &scaled)
    };
    let q = q.to_u128().unwrap_or(u128::MAX) | u128::from(!r.is_zero());
    let value = scale_by_power_of_two(q as f64, i64::from(exponent) - shift);
    if num.is_negative() {
        -value
    } else {
        value
    }
}

/// `x * 2^k`, in two steps so that no factor overflows or underflows on its own.
fn scale_by_power_of_two(x: f64, k: i64) -> f64 {
    let k = k.clamp(-2200, 2200) as i32;
    let half = k / 2;
    x * 2f64.powi(half) * 2f64.powi(k - half)
}

/// Compares `x / den_x` with `y / den_y` (positive denominators).
fn cmp_ratio(x: &BigInt, den_x: &BigInt, y: &BigInt, den_y: &BigInt) -> Ordering {
    (x * den_y).cmp(&(y * den_x))
}

/// The segments `segs` (point indices into `cloud`) split at the intersections of the
/// `pairs` (indices into `segs`, each pair crossing properly, sorted): the pieces, each with
/// the index of the segment it comes from, in segment order and along each segment; the new
/// points are pushed to `cloud`. Returns the pieces and the number of points added.
pub fn split_at_crossings(
    segs: &[[u32; 2]],
    pairs: &[(u32, u32)],
    cloud: &mut Cloud,
) -> (Vec<[u32; 2]>, Vec<u32>, usize) {
    let p = |i: u32| cloud.points[i as usize];
    let crossings: Vec<Crossing> = pairs
        .iter()
        .map(|&(s, t)| {
            let ([a, b], [c, d]) = (segs[s as usize], segs[t as usize]);
            Crossing::new(p(a), p(b), p(c), p(d))
        })
        .collect();
    // The crossings on each segment: (pair, which side of the pair the segment is).
    let mut on: Vec<Vec<(u32, usize)>> = vec![Vec::new(); segs.len()];
    for (k, &(s, t)) in pairs.iter().enumerate() {
        on[s as usize].push((k as u32, 0));
        on[t as usize].push((k as u32, 1));
    }
    let lambda = |&(k, side): &(u32, usize)| {
        let c = &crossings[k as usize];
        (&c.lambda[side], &c.den)
    };
    let mut sets = UnionFind::new(pairs.len());
    for list in &mut on {
        list.sort_by(|x, y| {
            let ((lx, dx), (ly, dy)) = (lambda(x), lambda(y));
            cmp_ratio(lx, dx, ly, dy).then(x.0.cmp(&y.0))
        });
        for w in list.windows(2) {
            let ((lx, dx), (ly, dy)) = (lambda(&w[0]), lambda(&w[1]));
            if cmp_ratio(lx, dx, ly, dy) == Ordering::Equal {
                // The same point: the union keeps the smaller pair as the root.
                sets.union(w[0].0, w[1].0);
            }
        }
    }
    // One vertex per class, in the order of its first pair.
    let mut vertex = vec![u32::MAX; pairs.len()];
    let mut added = 0;
    for k in 0..pairs.len() as u32 {
        let r = sets.find(k);
        if r == k {
            vertex[k as usize] = cloud.push(crossings[k as usize].rounded());
            added += 1;
        }
    }
    let mut pieces = Vec::with_capacity(segs.len() + 2 * pairs.len());
    let mut origin = Vec::with_capacity(pieces.capacity());
    for (s, list) in on.iter().enumerate() {
        let mut last = segs[s][0];
        for &(k, _) in list {
            let v = vertex[sets.find(k) as usize];
            if v != last {
                pieces.push([last, v]);
                origin.push(s as u32);
                last = v;
            }
        }
        pieces.push([last, segs[s][1]]);
        origin.push(s as u32);
    }
    (pieces, origin, added)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quotients_round_to_nearest() {
        let big = |x: i64| BigInt::from(x);
        assert_eq!(quotient_to_f64(&big(1), &big(3), 0), 1.0 / 3.0);
        assert_eq!(quotient_to_f64(&big(-2), &big(3), -4), -2.0 / 48.0);
        assert_eq!(quotient_to_f64(&big(10), &big(4), 1), 5.0);
        // 7 2^-1060, a subnormal: 7 units of 2^-1060 = 2^14 units of the least one, 2^-1074
        // (`powi` is not exact there in every build).
        assert_eq!(
            quotient_to_f64(&big(7), &big(1), -1060),
            f64::from_bits(7 << 14)
        );
    }

    #[test]
    fn crossing_of_the_diagonals_is_the_centre() {
        let c = Crossing::new([0.0, 0.0], [2.0, 2.0], [0.0, 2.0], [2.0, 0.0]);
        assert_eq!(c.rounded(), [1.0, 1.0]);
        let third = Crossing::new([0.0, 0.0], [3.0, 0.0], [1.0, -1.0], [1.0, 1.0]);
        assert_eq!(third.rounded(), [1.0, 0.0]);
    }
}
