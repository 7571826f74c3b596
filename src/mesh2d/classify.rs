//! The classification `Θ₂` of a constraint edge (Pébay §2.1, Definition 2.2) and strong
//! Delaunay-admissibility (§2.3, Theorem 2.1), decided with exact predicates.
//!
//! Notation of the paper: `f = [Pi Pj]`, `Δij` its closed small disk, `Cij` the small circle,
//! `Sij = Δij ∩ S`, `E = Sij \ {Pi, Pj}`, `H+` / `H-` the open half-planes of the line
//! `(Pi Pj)`; when `E` lies in one of them, `Q*` is a point of `E` seeing `[Pi Pj]` under the
//! largest angle, `t = Pi Pj Q*` and `Δt` its closed circumdisk.

use super::cloud::Cloud;
use super::exact::{dot_sign, in_circumcircle};
use crate::predicates::{orient2d, Sign};

/// The type `Θ₂(f)` of an edge (Definition 2.2). [`Theta2::Through`] is outside the paper's
/// hypotheses: a point of `S` on the open edge (never the case for valid input).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Theta2 {
    /// `Sij = {Pi, Pj}`: the small disk is empty.
    T0,
    /// `E` on one side, and `Q* ∈ Cij` or `Δt ∩ S = {Pi, Pj, Q*}`.
    T1_0,
    /// `E` on one side and the open `Δt` holds a point of `S`.
    T1_1,
    /// `E` on one side, the open `Δt` empty, other points `F` on the circle of `t`, all of
    /// `F ∪ {Q*}` on one side.
    T1_2_0,
    /// As `T1_2_0` but `F ∪ {Q*}` meets both sides.
    T1_2_1,
    /// `E` meets both sides and no point of `E` is on the line.
    T2,
    /// A point of `S` lies on the open edge.
    Through,
}

impl Theta2 {
    /// Theorem 2.1: the edge belongs to every Delaunay triangulation of `Conv(S)` iff its type
    /// is 0, 1.0 or 1.2.0.
    pub fn strongly_admissible(self) -> bool {
        matches!(self, Theta2::T0 | Theta2::T1_0 | Theta2::T1_2_0)
    }

    /// The paper's notation: "0", "1.0", "1.1", "1.2.0", "1.2.1", "2" (and "through").
    pub fn name(self) -> &'static str {
        match self {
            Theta2::T0 => "0",
            Theta2::T1_0 => "1.0",
            Theta2::T1_1 => "1.1",
            Theta2::T1_2_0 => "1.2.0",
            Theta2::T1_2_1 => "1.2.1",
            Theta2::T2 => "2",
            Theta2::Through => "through",
        }
    }
}

/// `Θ₂([Pi Pj])` relative to the points of `cloud` (`i != j`, distinct coordinates).
pub fn classify(cloud: &Cloud, i: u32, j: u32) -> Theta2 {
    classify_with(cloud, i, j, cloud.small_disk(i, j))
}

/// Theorem 2.1 for `[Pi Pj]` relative to the points of `cloud`.
pub fn strongly_admissible(cloud: &Cloud, i: u32, j: u32) -> bool {
    classify(cloud, i, j).strongly_admissible()
}

/// [`classify`] when `E` (the points of the closed small disk but the ends, in any order)
/// is given; one pass over it.
///
/// The pass keeps `Q*`, a point of `E` seeing `[Pi Pj]` under the largest angle so far (`q`
/// sees it under a larger angle than `r`, on the same side, iff `q` is strictly inside the
/// circle through `Pi, Pj, r`), and whether another point seen so far is on that circle
/// (a point on the circle of an earlier, narrower `Q*` is strictly outside the later one's).
/// Points tied with `Q*` share its circle, so which of them is `Q*` does not change the type.
pub fn classify_with(cloud: &Cloud, i: u32, j: u32, e: impl IntoIterator<Item = u32>) -> Theta2 {
    let p = |k: u32| &cloud.points[k as usize];
    let (pi, pj) = (p(i), p(j));
    let mut e = e.into_iter();
    let Some(first) = e.next() else {
        return Theta2::T0;
    };
    let side = orient2d(pi, pj, p(first));
    if side == Sign::Zero {
        return Theta2::Through;
    }
    let (mut q_star, mut tied, mut both) = (first, false, false);
    for q in e {
        match orient2d(pi, pj, p(q)) {
            Sign::Zero => return Theta2::Through,
            s if s != side => both = true,
            // Past the other side, only a point on the line can change the type.
            _ if both => {}
            _ => match in_circumcircle(pi, pj, p(q_star), p(q)) {
                Sign::Positive => (q_star, tied) = (q, false),
                Sign::Zero => tied = true,
                Sign::Negative => {}
            },
        }
    }
    if both {
        return Theta2::T2;
    }
    if dot_sign(pi, pj, p(q_star)) == Sign::Zero {
        return Theta2::T1_0;
    }
    // A point on Q*'s side in the closed `Δt` sees `[Pi Pj]` under an angle at least Q*'s,
    // above 90°: it is in `E`, and on the circle (Q* sees it under the largest angle). So
    // the open `Δt` can only hold points beyond the line, and `F` on Q*'s side is `tied`.
    match cloud.circumdisk_beyond(i, j, q_star) {
        Sign::Positive => Theta2::T1_1,
        Sign::Zero => Theta2::T1_2_1,
        Sign::Negative if tied => Theta2::T1_2_0,
        Sign::Negative => Theta2::T1_0,
    }
}
