//! The coordinate plane in which the coplanar predicates are evaluated.
//!
//! Let `a, b, c, p` be coplanar, `a, b, c` not collinear, and drop the axis `t` such that the
//! projections onto the axes `u = t+1`, `v = t+2` (mod 3) of `a, b, c` are not collinear. The
//! plane of the points is then the graph of an affine function over the `(u, v)` plane, so the
//! affine functions on it are the affine functions of `(u, v)`. The lifted coordinate
//! `l(x) = |x|^2 - w` keeps the full 3D `|x|^2`: the circle (or power circle) through `a, b, c`
//! is `{ l = A }` for the affine `A` interpolating `l` at `a, b, c`, and `p` is inside (in
//! conflict) exactly when `l(p) < A(p)`. Expanding along the lifted column,
//! `det[1 u v l](a,b,c,p) = orient2d(a', b', c') * (l(p) - A(p))` (primes: projections), and
//! translating the rows by `p` gives `det[1 u v l] = -det[u v l](a-p, b-p, c-p)`. Hence the
//! test is `sign(det[u v l](a-p, b-p, c-p)) * orient2d(a', b', c')`: exactly the 3D test,
//! independent of the orientation of `a, b, c` and of which valid axis is dropped.
//!
//! Invariant of [`Projection`]: `orientation` is the exact, nonzero `orient2d` of the projected
//! `a, b, c` it was built from.

use super::{exact, filter, orient2d, Point, Sign, WeightedPoint};

/// A coordinate plane onto which a triangle projects to a proper triangle.
pub(super) struct Projection {
    /// The kept axes `u, v` and the dropped axis `t`, in this order; `(u, v, t)` is a cyclic
    /// permutation of `(0, 1, 2)`.
    axes: [usize; 3],
    /// The orientation of the projected triangle; never `Zero`.
    pub(super) orientation: Sign,
}

impl Projection {
    /// The projection that keeps `a, b, c` a proper triangle, preferring the axis along which
    /// their (floating-point) normal is largest; `None` when `a, b, c` are collinear.
    pub(super) fn of(a: &Point, b: &Point, c: &Point) -> Option<Projection> {
        let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let ac = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let normal = [
            (ab[1] * ac[2] - ab[2] * ac[1]).abs(),
            (ab[2] * ac[0] - ab[0] * ac[2]).abs(),
            (ab[0] * ac[1] - ab[1] * ac[0]).abs(),
        ];
        let mut dropped = [0, 1, 2];
        dropped.sort_unstable_by(|&i, &j| normal[j].total_cmp(&normal[i]).then(i.cmp(&j)));
        dropped.into_iter().find_map(|t| {
            let axes = [(t + 1) % 3, (t + 2) % 3, t];
            let orientation = orient_projected(axes, a, b, c);
            (orientation != Sign::Zero).then_some(Projection { axes, orientation })
        })
    }

    /// The exact `orient2d` of the projections of `a, b, c`.
    pub(super) fn orient(&self, a: &Point, b: &Point, c: &Point) -> Sign {
        orient_projected(self.axes, a, b, c)
    }

    /// The coplanar power test of `p` against `a, b, c` (positive: `p` in conflict), with the
    /// orientation of the projected `a, b, c` corrected.
    pub(super) fn power_test(
        &self,
        a: &WeightedPoint,
        b: &WeightedPoint,
        c: &WeightedPoint,
        p: &WeightedPoint,
    ) -> Sign {
        let det = filter::power_coplanar(a, b, c, p, self.axes)
            .unwrap_or_else(|| exact::power_coplanar(a, b, c, p, self.axes));
        self.orientation * det
    }
}

/// The exact `orient2d` of the projections of `a, b, c` onto the first two of `axes`.
fn orient_projected(axes: [usize; 3], a: &Point, b: &Point, c: &Point) -> Sign {
    let project = |p: &Point| [p[axes[0]], p[axes[1]]];
    orient2d(&project(a), &project(b), &project(c))
}
