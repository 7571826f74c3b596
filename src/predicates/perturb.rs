//! The symbolic perturbation of the `_sos` predicates, as in CGAL's
//! `Delaunay_triangulation_3::side_of_oriented_sphere(..., perturb = true)`,
//! `coplanar_side_of_bounded_circle(..., perturb = true)` and
//! `Regular_triangulation_3::side_of_power_sphere(..., perturb = true)`.
//!
//! The lifted coordinate `l(p) = |p|^2 - w_p` of each of the `n` points of a test becomes
//! `l(p) + eps^(n - r_p)`, `r_p` in `0..n` the rank of `p` in the lexicographic order of the
//! coordinates, for an infinitesimal `eps > 0`. The test determinant is linear in its lifted
//! column, so the perturbed determinant is `det + sum_p eps^(n - r_p) C_p`, `C_p` the cofactor
//! of `l(p)`. When `det = 0`, its sign is that of the first nonzero `C_p` in decreasing
//! lexicographic order of `p`.
//!
//! 3D (`insphere = power_test = -det[1 x y z l](a, b, c, d, e)`): the cofactors are
//! `C_e = orient3d(a,b,c,d)`, `C_d = -orient3d(a,b,c,e)`, `C_c = orient3d(a,b,d,e)`,
//! `C_b = -orient3d(a,c,d,e)`, `C_a = orient3d(b,c,d,e)`. So the answer is `Negative` when `e`
//! comes first (`(a,b,c,d)` is positively oriented), and otherwise `-C_p`, which is in every case
//! the orientation of `(a,b,c,d)` with `p` replaced by `e`: `orient3d(a,b,c,e)`,
//! `orient3d(a,b,e,d) = -orient3d(a,b,d,e)`, `orient3d(a,e,c,d) = orient3d(a,c,d,e)`,
//! `orient3d(e,b,c,d) = -orient3d(b,c,d,e)`.
//!
//! Coplanar (`test = -det[1 u v l](a, b, c, p) * o`, `o = orient2d(a', b', c')` in the
//! projection of `plane.rs`): `C_p = o`, `C_c = -orient2d(a',b',p')`, `C_b = orient2d(a',c',p')`,
//! `C_a = -orient2d(b',c',p')`. So `Negative` when `p` comes first, and otherwise
//! `o * orient2d` of the projected triangle with that vertex replaced by `p`.
//!
//! The walk stops at the query point at the latest, since its cofactor is the orientation of the
//! (non-degenerate) simplex. For unweighted points it never goes past the second point: a point on
//! the sphere (circle) and on the line through two others is one of them.

use super::plane::Projection;
use super::{lex_cmp, orient3d, xyz, Point, Sign, WeightedPoint};

/// Perturbed [`super::insphere`], for an exact tie.
pub(super) fn insphere(a: &Point, b: &Point, c: &Point, d: &Point, e: &Point) -> Sign {
    debug_assert_eq!(orient3d(a, b, c, d), Sign::Positive);
    let tetrahedron = [a, b, c, d];
    first_nonzero_cofactor(&[a, b, c, d, e], |i| {
        let mut replaced = tetrahedron;
        replaced[i] = e;
        orient3d(replaced[0], replaced[1], replaced[2], replaced[3])
    })
}

/// Perturbed [`super::power_test`], for an exact tie.
pub(super) fn power_test(
    a: &WeightedPoint,
    b: &WeightedPoint,
    c: &WeightedPoint,
    d: &WeightedPoint,
    e: &WeightedPoint,
) -> Sign {
    insphere(&xyz(a), &xyz(b), &xyz(c), &xyz(d), &xyz(e))
}

/// Perturbed coplanar power test, for an exact tie.
pub(super) fn power_test_coplanar(
    plane: &Projection,
    a: &WeightedPoint,
    b: &WeightedPoint,
    c: &WeightedPoint,
    p: &WeightedPoint,
) -> Sign {
    let triangle = [xyz(a), xyz(b), xyz(c)];
    let p = xyz(p);
    first_nonzero_cofactor(&[&triangle[0], &triangle[1], &triangle[2], &p], |i| {
        let mut replaced = triangle;
        replaced[i] = p;
        plane.orientation * plane.orient(&replaced[0], &replaced[1], &replaced[2])
    })
}

/// Walks `points` (a simplex, then the query point) from the lexicographically largest down
/// and returns the first nonzero `replaced(i)`, the sign for the simplex vertex `i`; `Negative`
/// once the query point is reached.
fn first_nonzero_cofactor(points: &[&Point], replaced: impl Fn(usize) -> Sign) -> Sign {
    let query = points.len() - 1;
    let mut order = [0, 1, 2, 3, 4];
    let order = &mut order[..points.len()];
    order.sort_unstable_by(|&i, &j| lex_cmp(points[j], points[i]));
    order
        .iter()
        .take_while(|&&i| i != query)
        .map(|&i| replaced(i))
        .find(|&sign| sign != Sign::Zero)
        .unwrap_or(Sign::Negative)
}
