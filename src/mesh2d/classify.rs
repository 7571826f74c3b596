//! The classification `Θ₂` of a constraint edge (Pébay §2.1, Definition 2.2) and strong
//! Delaunay-admissibility (§2.3, Theorem 2.1), decided with exact predicates.
//!
//! Notation of the paper: `f = [Pi Pj]`, `Δij` its closed small disk, `Cij` the small circle,
//! `Sij = Δij ∩ S`, `E = Sij \ {Pi, Pj}`, `H+` / `H-` the open half-planes of the line
//! `(Pi Pj)`; when `E` lies in one of them, `Q*` is a point of `E` seeing `[Pi Pj]` under the
//! largest angle, `t = Pi Pj Q*` and `Δt` its closed circumdisk.

use super::cloud::{Circumdisk, Cloud};
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
    classify_with(cloud, i, j, &cloud.in_small_disk(i, j))
}

/// Theorem 2.1 for `[Pi Pj]` relative to the points of `cloud`.
pub fn strongly_admissible(cloud: &Cloud, i: u32, j: u32) -> bool {
    classify(cloud, i, j).strongly_admissible()
}

/// [`classify`] when `E` (the points of the closed small disk but the ends) is known.
pub fn classify_with(cloud: &Cloud, i: u32, j: u32, e: &[u32]) -> Theta2 {
    let p = |k: u32| &cloud.points[k as usize];
    let (pi, pj) = (p(i), p(j));
    if e.is_empty() {
        return Theta2::T0;
    }
    let mut side = Sign::Zero;
    for &q in e {
        match orient2d(pi, pj, p(q)) {
            Sign::Zero => return Theta2::Through,
            s if side == Sign::Zero => side = s,
            s if s != side => return Theta2::T2,
            _ => {}
        }
    }
    let q_star = widest_angle(cloud, i, j, e);
    if dot_sign(pi, pj, p(q_star)) == Sign::Zero {
        return Theta2::T1_0;
    }
    let disk = match cloud.circumdisk(i, j, q_star) {
        Circumdisk::Inside => return Theta2::T1_1,
        Circumdisk::OnCircle(disk) => disk,
    };
    if disk.is_empty() {
        return Theta2::T1_0;
    }
    // Every point of F is on the circle of t, hence off the line (Pi Pj).
    if disk.iter().all(|&q| orient2d(pi, pj, p(q)) == side) {
        Theta2::T1_2_0
    } else {
        Theta2::T1_2_1
    }
}

/// A point of `e` (all on one side of `(Pi Pj)`) seeing `[Pi Pj]` under the largest angle:
/// `q` sees it under a larger angle than `r` iff `q` is strictly inside the circle through
/// `Pi, Pj, r`. The first such point in `e`'s order.
fn widest_angle(cloud: &Cloud, i: u32, j: u32, e: &[u32]) -> u32 {
    let p = |k: u32| &cloud.points[k as usize];
    let mut best = e[0];
    for &q in &e[1..] {
        if in_circumcircle(p(i), p(j), p(best), p(q)) == Sign::Positive {
            best = q;
        }
    }
    best
}
