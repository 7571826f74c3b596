//! Quality refinement of a conforming triangulation (API.md "2D", quality mode): Ruppert's
//! Delaunay refinement (J. Ruppert, "A Delaunay refinement algorithm for quality 2-dimensional
//! mesh generation", J. Algorithms 18, 1995) with Shewchuk's treatment of small input angles
//! (J. R. Shewchuk, "Delaunay refinement algorithms for triangular mesh generation", CGTA 22,
//! 2002: concentric-shell splitting, and skinny triangles at small input angles left alone),
//! and Üngör's off-centers (A. Üngör, "Off-centers: a new type of Steiner points for computing
//! size-optimal quality-guaranteed Delaunay triangulations", LATIN 2004). In the level
//! architecture of Rineau's thesis §5.4, sub-segments are the first level and triangles the
//! second: a triangle is refined only when no sub-segment is encroached.
//!
//! Phases ([`super::quality_2d`]):
//! 1. [`split_segments`]: the input segments are split at concentric shells or midpoints until
//!    every sub-segment is strongly Delaunay-admissible (Pébay's Theorem 2.1) relative to the
//!    points on segments; the Delaunay triangulation of those points then contains every
//!    sub-segment. (Pébay's projections, used by the conforming mode, would leave short
//!    sub-segments near acute angles, which refinement propagates into many small triangles.)
//! 2. [`Refiner`]: the sub-segments become constrained edges; four far corners enclose
//!    everything (so that no split point rounds onto a concave hull); regions are flooded
//!    from the outside, the hole seeds and the region seeds; the input points off the segments
//!    that lie in the domain are inserted (the others are left out: they constrain nothing).
//! 3. [`Refiner::run`], in the level order of Rineau's thesis §5.4 (sub-segments first, then
//!    triangles):
//!    - a sub-segment is split when a vertex of a triangle on a side of it in the domain
//!      *encroaches* it: lies in its diametral lens, seeing it under at least
//!      `180° - 2 × bound` (Shewchuk's lens, smaller than Ruppert's diametral disk: fewer
//!      splits; the closed diametral disk without an angle bound), or when it is not strictly
//!      locally Delaunay (its two apices cocircular with its ends, or one inside the other's
//!      circle: then it would not be in every Delaunay triangulation). It is split at a
//!      power-of-two distance from its end when that end is an input point where two segments
//!      form an acute angle (concentric shells, so that sub-segments around a small angle end
//!      on common circles), else at its midpoint;
//!    - a triangle of the domain is *bad* when its smallest angle is below the bound or its
//!      area above the bound of its region; it is split at its off-center (the point on the
//!      bisector of its shortest edge from which that edge is seen under slightly more than
//!      the bound) when the angle is bad and that is nearer than the circumcenter, else at its
//!      circumcenter. A point that would encroach sub-segments, or that lies beyond one in
//!      its diametral disk, is not inserted: they are split instead, and the triangle is
//!      reconsidered. Bad triangles are taken smallest first, by buckets of their shortest
//!      edge (a factor `sqrt(2)` of squared length per bucket), first in, first out within a
//!      bucket: the order of Shewchuk's Triangle. Small features are resolved first and the
//!      mesh grows away from them; taking the worst angle first instead sends off-centers
//!      from every short boundary edge of a finely sampled curve, rows of points parallel to
//!      it at its own spacing that the mesh cannot grade away from (on a 10^4-edge star
//!      polygon at 25 degrees: 29% more triangles than CGAL's circumcenters, against 9% more
//!      in this order);
//!    - a triangle bad by angle only whose shortest edge joins two points on segments meeting
//!      at an end at an angle below 60 degrees, at equal distances from it (within
//!      [`SHELL_TOLERANCE`]), is skinny because of a small input angle: splitting it would not
//!      terminate. It is dropped and counted
//!      ([`RefinementReport::rejected_forever`]).
//!
//! Invariants. Between two steps, every sub-segment is an edge of the triangulation and every
//! other edge is locally Delaunay (symbolic perturbation as in [`super::delaunay`]); a
//! triangle's region never changes (cavities never cross a sub-segment but the one being
//! split, whose two sides are then refilled from their own side). At the end every edge is
//! locally Delaunay, the sub-segments strictly: the triangulation is the Delaunay
//! triangulation of its vertices and every sub-segment is in all of them (strongly
//! Delaunay-admissible) — the result is still conforming, and every triangle of the domain has
//! an empty circumcircle.

use std::collections::{BinaryHeap, VecDeque};

use super::classify::strongly_admissible;
use super::cloud::Cloud;
use super::delaunay::{conflict, hilbert_order, INFINITE};
use super::exact::dot_sign;
use super::input::Crossings;
use crate::error::{Error, ErrorKind, Result};
use crate::predicates::{incircle, orient2d, Sign};

/// No triangle, no segment.
const NONE: u32 = u32::MAX;

/// Largest accepted lower bound on angles, in degrees: refinement is proven to terminate up to
/// about 20.7° (Ruppert) and observed to terminate up to about 33.8° (Shewchuk).
pub const MAX_MIN_ANGLE_DEGREES: f64 = 34.0;

/// Two points on segments sharing an end are on a common concentric shell when their
/// distances to that end differ by at most this fraction.
pub const SHELL_TOLERANCE: f64 = 1e-3;

/// The off-center sits at this fraction of the distance that makes the new triangle's apex
/// angle exactly the bound (a margin for rounding).
const OFF_CENTER_MARGIN: f64 = 0.95;

/// Points added by refinement at most (a guard against runaway refinement).
pub const MAX_REFINEMENT_POINTS: usize = 1 << 24;

/// A region seed: the triangles reachable from `seed` without crossing a sub-segment get
/// `label`, and `max_area` (0: the global bound) as their area bound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegionSeed {
    pub seed: [f64; 2],
    pub label: i32,
    pub max_area: f64,
}

/// The quality criteria and the domain description.
#[derive(Clone, Debug, PartialEq)]
pub struct QualityOptions {
    /// Lower bound on angles, degrees; 0: none. At most [`MAX_MIN_ANGLE_DEGREES`].
    pub min_angle_degrees: f64,
    /// Upper bound on areas; 0: none.
    pub max_area: f64,
    /// Hole seeds: the region containing each is removed.
    pub holes: Vec<[f64; 2]>,
    pub regions: Vec<RegionSeed>,
    /// Off-centers (default) or circumcenters only.
    pub off_centers: bool,
    /// Crossing segments: an error by default, or split at their intersection points.
    pub crossings: Crossings,
}

impl Default for QualityOptions {
    fn default() -> Self {
        QualityOptions {
            min_angle_degrees: 0.0,
            max_area: 0.0,
            holes: Vec::new(),
            regions: Vec::new(),
            off_centers: true,
            crossings: Crossings::Reject,
        }
    }
}

impl QualityOptions {
    /// Checks the bounds; the error gives the reason.
    pub fn check(&self) -> Result<()> {
        let angle = self.min_angle_degrees;
        if !(0.0..=MAX_MIN_ANGLE_DEGREES).contains(&angle) {
            return Err(Error::invalid_argument(format!(
                "min_angle_degrees = {angle}: must be in [0, {MAX_MIN_ANGLE_DEGREES}] \
                 (refinement is not known to terminate for larger bounds)"
            )));
        }
        let areas = std::iter::once(self.max_area).chain(self.regions.iter().map(|r| r.max_area));
        for area in areas {
            if !(area >= 0.0 && area.is_finite()) {
                return Err(Error::invalid_argument(format!(
                    "max_area = {area}: must be finite and >= 0"
                )));
            }
        }
        let seeds = self
            .holes
            .iter()
            .chain(self.regions.iter().map(|r| &r.seed));
        if let Some(s) = seeds.into_iter().find(|s| s.iter().any(|x| !x.is_finite())) {
            return Err(Error::invalid_argument(format!(
                "seed ({}, {}) is not finite",
                s[0], s[1]
            )));
        }
        Ok(())
    }
}

/// What refinement did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RefinementReport {
    /// Points inserted on sub-segments.
    pub segment_splits: usize,
    /// Points inserted inside the domain (off-centers and circumcenters).
    pub interior_points: usize,
    /// Of those, off-centers.
    pub off_centers: usize,
    /// Skinny triangles at small input angles left unsplit.
    pub rejected_forever: usize,
    /// Candidate points not inserted because they encroached sub-segments.
    pub encroaching_points: usize,
    /// Bad triangles dropped because their point could not be inserted (outside the domain,
    /// on a vertex, or behind a sub-segment it does not encroach).
    pub dropped: usize,
    /// Sub-segments too short to split in floating point.
    pub unsplittable: usize,
}

/// The triangles in conflict with a point, and the boundary edges of their union (triangle,
/// slot opposite the edge).
type Cavity = (Vec<u32>, Vec<(u32, usize)>);

/// Where a walk towards a point ends.
enum Walk {
    /// A triangle containing the point (closed).
    Inside(u32),
    /// Stopped by the sub-segment opposite slot `k` of triangle `t`.
    Blocked(u32, usize),
    /// Left the triangulation or did not converge.
    Lost,
}

/// A bad triangle in the queue, taken smallest first: by the [`length_bucket`] of its shortest
/// edge, then first in, first out (`seq`, the order of queueing).
#[derive(PartialEq, Eq)]
struct Bad {
    bucket: i32,
    seq: u64,
    t: u32,
    v: [u32; 3],
}

impl Ord for Bad {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        other
            .bucket
            .cmp(&self.bucket)
            .then(other.seq.cmp(&self.seq))
    }
}

impl PartialOrd for Bad {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

/// The constrained triangulation under refinement.
pub struct Refiner {
    pub points: Vec<[f64; 2]>,
    /// Input segment (index into `segments`) each point lies inside of; NONE for others.
    pub on_segment: Vec<u32>,
    /// Input segments at each input point (none for others).
    incident: Incidence,
    /// Whether each input point is the apex of an acute angle between two segments.
    acute: Vec<bool>,
    /// The input segments (point pairs).
    pub segments: Vec<[u32; 2]>,
    tri: Vec<[u32; 3]>,
    adj: Vec<[u32; 3]>,
    /// Bit `k`: the edge opposite slot `k` is a sub-segment.
    seg: Vec<u8>,
    /// 0: outside the domain; else an index into `region_table`.
    region: Vec<u32>,
    alive: Vec<bool>,
    mark: Vec<u32>,
    stamp: u32,
    free: Vec<u32>,
    /// A live triangle at each vertex.
    vtri: Vec<u32>,
    /// (label, max_area) of each region; entry 0 unused.
    pub region_table: Vec<(i32, f64)>,
    cos_bound: f64,
    min_angle: f64,
    off_centers: bool,
    encroached: VecDeque<(u32, u32)>,
    bad: BinaryHeap<Bad>,
    /// Bad triangles queued so far.
    queued: u64,
    rng: u32,
    pub report: RefinementReport,
}

impl Refiner {
    /// The triangulation `tri`/`adj` (live triangles of a [`super::delaunay::Delaunay2d`],
    /// compacted) of `points`, whose sub-segments `sub_edges` (point pairs with their input
    /// segment) are edges of it. `on_segment` gives the input segment of points added on
    /// segments; `segments` are the input segments, `acute` their [`acute_apices`].
    pub fn new(
        points: Vec<[f64; 2]>,
        (tri, adj): (Vec<[u32; 3]>, Vec<[u32; 3]>),
        segments: Vec<[u32; 2]>,
        acute: Vec<bool>,
        on_segment: Vec<u32>,
        sub_edges: &[[u32; 2]],
    ) -> Result<Self> {
        let n = points.len();
        let incident = Incidence::new(n, &segments);
        let count = tri.len();
        let mut r = Refiner {
            points,
            on_segment,
            incident,
            acute,
            segments,
            tri,
            adj,
            seg: vec![0; count],
            region: vec![0; count],
            alive: vec![true; count],
            mark: vec![0; count],
            stamp: 0,
            free: Vec::new(),
            vtri: vec![NONE; n],
            region_table: vec![(0, 0.0)],
            cos_bound: 1.0,
            min_angle: 0.0,
            off_centers: true,
            encroached: VecDeque::new(),
            bad: BinaryHeap::new(),
            queued: 0,
            rng: 0x2545_f491,
            report: RefinementReport::default(),
        };
        for t in 0..count {
            for &v in &r.tri[t] {
                if v != INFINITE {
                    r.vtri[v as usize] = t as u32;
                }
            }
        }
        for e in sub_edges {
            let (t, k) = r.find_edge(e[0], e[1]).ok_or_else(|| {
                Error::internal(format!("sub-segment {e:?} is not a triangle edge"))
            })?;
            r.set_segment(t, k);
        }
        Ok(r)
    }

    fn p(&self, v: u32) -> &[f64; 2] {
        &self.points[v as usize]
    }

    fn is_segment(&self, t: u32, k: usize) -> bool {
        self.seg[t as usize] & (1 << k) != 0
    }

    /// Marks the edge opposite slot `k` of `t` as a sub-segment, on both sides.
    fn set_segment(&mut self, t: u32, k: usize) {
        self.seg[t as usize] |= 1 << k;
        let (u, l) = self.across(t, k);
        self.seg[u as usize] |= 1 << l;
    }

    /// The triangle across the edge opposite slot `k` of `t`, and that edge's slot there.
    fn across(&self, t: u32, k: usize) -> (u32, usize) {
        let u = self.adj[t as usize][k];
        let v = self.tri[t as usize];
        let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
        let w = self.tri[u as usize];
        let l = (0..3)
            .find(|&l| w[(l + 1) % 3] == b && w[(l + 2) % 3] == a)
            .unwrap_or(0);
        (u, l)
    }

    /// The edge `(a, b)`: a triangle holding it and the slot opposite it.
    fn find_edge(&self, a: u32, b: u32) -> Option<(u32, usize)> {
        let start = *self.vtri.get(a as usize)?;
        if start == NONE {
            return None;
        }
        let mut t = start;
        for _ in 0..self.tri.len() + 1 {
            let v = self.tri[t as usize];
            let j = v.iter().position(|&x| x == a)?;
            if let Some(m) = v.iter().position(|&x| x == b) {
                return Some((t, 3 - j - m));
            }
            t = self.adj[t as usize][(j + 1) % 3];
            if t == start {
                return None;
            }
        }
        None
    }

    /// Inserts the point `p`, outside the convex hull of the vertices, without crossing a
    /// sub-segment (the enclosing box of [`super::quality_2d`]).
    pub fn insert_outside(&mut self, p: [f64; 2]) -> Result<()> {
        let start = (0..self.tri.len() as u32).find(|&t| {
            let v = self.tri[t as usize];
            self.alive[t as usize]
                && v.iter().position(|&x| x == INFINITE).is_some_and(|k| {
                    let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                    orient2d(self.p(a), self.p(b), &p) == Sign::Positive
                })
        });
        let cavity = start.and_then(|t| self.cavity(&[t], &p));
        let Some((cavity, boundary)) = cavity else {
            return Err(Error::internal(format!(
                "point {p:?} is not outside the convex hull"
            )));
        };
        let i = self.push_point(p, NONE);
        self.fill(i, &cavity, &boundary);
        Ok(())
    }

    /// Inserts the points `points` of the point list (not yet vertices, inside the convex hull
    /// of the vertices) that lie in the domain, without crossing a sub-segment, along a Hilbert
    /// curve: each is located by a walk from the triangle of the one before.
    pub fn insert_if_inside(&mut self, points: &[u32]) -> Result<()> {
        let coords: Vec<[f64; 2]> = points.iter().map(|&i| self.points[i as usize]).collect();
        let mut start = self.any_finite();
        for k in hilbert_order(&coords) {
            let (i, p) = (points[k as usize], coords[k as usize]);
            let walk = start.map(|t| self.walk(t, &p, false));
            if let Some(Walk::Inside(t)) = walk {
                start = Some(t);
                if self.region[t as usize] == 0 {
                    continue;
                }
            }
            let cavity = match walk {
                Some(Walk::Inside(t))
                    if !self.tri[t as usize]
                        .iter()
                        .any(|&v| self.points[v as usize] == p) =>
                {
                    self.cavity(&[t], &p)
                }
                _ => None,
            };
            let Some((cavity, boundary)) = cavity else {
                return Err(Error::internal(format!("point {i} could not be inserted")));
            };
            start = self.fill(i, &cavity, &boundary).first().copied();
        }
        Ok(())
    }

    /// Assigns regions: 0 to the outside (reached from an infinite triangle without crossing
    /// a sub-segment) and to holes, `region_table` entries to seeded regions, 1 (label 1,
    /// the global area bound) to the rest.
    pub fn assign_regions(&mut self, options: &QualityOptions) {
        self.region_table = vec![(0, 0.0), (1, options.max_area)];
        for t in 0..self.tri.len() {
            self.region[t] = if self.tri[t].contains(&INFINITE) {
                0
            } else {
                1
            };
        }
        let outside: Vec<u32> = (0..self.tri.len() as u32)
            .filter(|&t| self.tri[t as usize].contains(&INFINITE))
            .collect();
        for t in outside {
            for k in 0..3 {
                if !self.is_segment(t, k) {
                    let u = self.adj[t as usize][k];
                    self.flood(u, 0);
                }
            }
        }
        let seeds: Vec<[f64; 2]> = (options.holes.iter().copied())
            .chain(options.regions.iter().map(|r| r.seed))
            .collect();
        let found = self.locate_all(&seeds);
        let (holes, regions) = found.split_at(options.holes.len());
        for &t in holes.iter().flatten() {
            self.flood(t, 0);
        }
        for (r, &t) in options.regions.iter().zip(regions) {
            let area = if r.max_area > 0.0 {
                r.max_area
            } else {
                options.max_area
            };
            if let Some(t) = t {
                if self.region[t as usize] != 0 {
                    self.region_table.push((r.label, area));
                    let id = (self.region_table.len() - 1) as u32;
                    self.flood(t, id);
                }
            }
        }
    }

    /// Sets the region of every finite triangle reachable from `t` without crossing a
    /// sub-segment (nor entering a triangle already at `id`).
    fn flood(&mut self, t: u32, id: u32) {
        let mut stack = vec![t];
        while let Some(t) = stack.pop() {
            if self.tri[t as usize].contains(&INFINITE) || self.region[t as usize] == id {
                continue;
            }
            self.region[t as usize] = id;
            for k in 0..3 {
                if !self.is_segment(t, k) {
                    stack.push(self.adj[t as usize][k]);
                }
            }
        }
    }

    /// A live finite triangle.
    fn any_finite(&self) -> Option<u32> {
        (0..self.tri.len() as u32)
            .find(|&t| self.alive[t as usize] && !self.tri[t as usize].contains(&INFINITE))
    }

    /// A finite triangle containing each point of `seeds` (closed), or `None` outside the
    /// triangulation: walks that ignore sub-segments, the seeds taken along a Hilbert curve,
    /// each walk from the triangle of the seed before.
    fn locate_all(&mut self, seeds: &[[f64; 2]]) -> Vec<Option<u32>> {
        let mut found = vec![None; seeds.len()];
        let Some(mut start) = self.any_finite() else {
            return found;
        };
        for i in hilbert_order(seeds) {
            if let Walk::Inside(t) = self.walk(start, &seeds[i as usize], false) {
                found[i as usize] = Some(t);
                start = t;
            }
        }
        found
    }

    /// A visibility walk from the finite triangle `start` towards `p`. With `blocked`, the
    /// walk does not cross sub-segments: it stops at one when every edge it could cross is one.
    fn walk(&mut self, start: u32, p: &[f64; 2], blocked: bool) -> Walk {
        let mut t = start;
        for _ in 0..4 * self.tri.len() + 16 {
            let v = self.tri[t as usize];
            if v.contains(&INFINITE) {
                return Walk::Lost;
            }
            self.rng ^= self.rng << 13;
            self.rng ^= self.rng >> 17;
            self.rng ^= self.rng << 5;
            let s = (self.rng % 3) as usize;
            let mut wall = None;
            let mut next = None;
            for j in 0..3 {
                let k = (s + j) % 3;
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                if orient2d(self.p(a), self.p(b), p) == Sign::Negative {
                    if blocked && self.is_segment(t, k) {
                        wall.get_or_insert(k);
                    } else {
                        next = Some(k);
                        break;
                    }
                }
            }
            match (next, wall) {
                (Some(k), _) => t = self.adj[t as usize][k],
                (None, Some(k)) => return Walk::Blocked(t, k),
                (None, None) => return Walk::Inside(t),
            }
        }
        Walk::Lost
    }

    /// Whether point `q` encroaches the sub-segment `(a, b)`: it lies in its closed
    /// diametral lens, the points that see it under at least `180° - 2 × min_angle`
    /// (Shewchuk's lens; the closed small disk when there is no angle bound). Decided in
    /// floating point past the exact small-disk test: it steers refinement, the conformity of
    /// the result is decided exactly by [`Self::apex_encroached`].
    fn encroaches(&self, a: u32, b: u32, q: &[f64; 2]) -> bool {
        if dot_sign(self.p(a), self.p(b), q) == Sign::Positive {
            return false;
        }
        if self.min_angle <= 0.0 {
            return true;
        }
        let (pa, pb) = (self.p(a), self.p(b));
        let (u, v) = ([pa[0] - q[0], pa[1] - q[1]], [pb[0] - q[0], pb[1] - q[1]]);
        let dot = u[0] * v[0] + u[1] * v[1];
        let lens = (2.0 * self.min_angle).to_radians().cos();
        dot * dot >= lens * lens * (u[0] * u[0] + u[1] * u[1]) * (v[0] * v[0] + v[1] * v[1])
    }

    /// Whether the sub-segment opposite slot `k` of `t` must be split: an apex on a side in
    /// the domain encroaches it (Ruppert's rule with Shewchuk's lens), or it is not strictly
    /// locally Delaunay (its two apices cocircular with it, or one inside the other's circle),
    /// which would let it out of some Delaunay triangulation of the vertices.
    fn apex_encroached(&self, t: u32, k: usize) -> bool {
        let v = self.tri[t as usize];
        let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
        let (u, l) = self.across(t, k);
        let (c, d) = (v[k], self.tri[u as usize][l]);
        for (apex, side) in [(c, t), (d, u)] {
            if apex != INFINITE
                && self.region[side as usize] != 0
                && self.encroaches(a, b, &self.points[apex as usize])
            {
                return true;
            }
        }
        if c == INFINITE || d == INFINITE {
            return false;
        }
        // (a, b, c) is counter-clockwise.
        incircle(self.p(a), self.p(b), self.p(c), self.p(d)) != Sign::Negative
    }

    /// Whether triangle `t`'s conflict with `p` holds (see [`super::delaunay`]).
    fn in_conflict(&self, t: u32, p: &[f64; 2]) -> bool {
        conflict(self.tri[t as usize], |v| self.p(v), p)
    }

    /// The cavity of `p`: the triangles in conflict with it reachable from `start` (all
    /// included) without crossing a sub-segment. Returns the cavity and its boundary edges
    /// (triangle, slot), or `None` when `p` does not see every boundary edge from inside.
    fn cavity(&mut self, start: &[u32], p: &[f64; 2]) -> Option<Cavity> {
        let (cavity, boundary, visible) = self.conflicts(start, p);
        visible.then_some((cavity, boundary))
    }

    /// [`Self::cavity`] whether or not `p` sees every boundary edge from inside (the last
    /// value says whether it does).
    fn conflicts(&mut self, start: &[u32], p: &[f64; 2]) -> (Vec<u32>, Vec<(u32, usize)>, bool) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.mark.iter_mut().for_each(|m| *m = 0);
            self.stamp = 1;
        }
        let mut cavity = Vec::new();
        let mut stack: Vec<u32> = start.to_vec();
        for &t in start {
            self.mark[t as usize] = self.stamp;
        }
        while let Some(t) = stack.pop() {
            cavity.push(t);
            for k in 0..3 {
                let n = self.adj[t as usize][k];
                if self.mark[n as usize] != self.stamp
                    && !self.is_segment(t, k)
                    && self.in_conflict(n, p)
                {
                    self.mark[n as usize] = self.stamp;
                    stack.push(n);
                }
            }
        }
        let mut boundary = Vec::new();
        let mut visible = true;
        for &t in &cavity {
            for k in 0..3 {
                let n = self.adj[t as usize][k];
                if self.mark[n as usize] == self.stamp {
                    continue;
                }
                let v = self.tri[t as usize];
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                if a != INFINITE
                    && b != INFINITE
                    && orient2d(self.p(a), self.p(b), p) != Sign::Positive
                {
                    visible = false;
                }
                boundary.push((t, k));
            }
        }
        (cavity, boundary, visible)
    }

    fn new_triangle(&mut self, v: [u32; 3], region: u32) -> u32 {
        let region = if v.contains(&INFINITE) { 0 } else { region };
        if let Some(t) = self.free.pop() {
            let i = t as usize;
            self.tri[i] = v;
            self.adj[i] = [NONE; 3];
            self.seg[i] = 0;
            self.region[i] = region;
            self.alive[i] = true;
            self.mark[i] = 0;
            t
        } else {
            self.tri.push(v);
            self.adj.push([NONE; 3]);
            self.seg.push(0);
            self.region.push(region);
            self.alive.push(true);
            self.mark.push(0);
            (self.tri.len() - 1) as u32
        }
    }

    /// Adds the point `p` (on input segment `on`, or NONE) to the point list; returns its
    /// index.
    fn push_point(&mut self, p: [f64; 2], on: u32) -> u32 {
        self.points.push(p);
        self.on_segment.push(on);
        self.vtri.push(NONE);
        (self.points.len() - 1) as u32
    }

    /// Replaces the cavity by the fan from point `i`; returns the new triangles.
    fn fill(&mut self, i: u32, cavity: &[u32], boundary: &[(u32, usize)]) -> Vec<u32> {
        // The new triangle from each boundary vertex, sorted by that vertex.
        let mut starts = Vec::with_capacity(boundary.len());
        let mut created = Vec::with_capacity(boundary.len());
        for &(t, k) in boundary {
            let v = self.tri[t as usize];
            let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
            let n = self.adj[t as usize][k];
            let segment = self.is_segment(t, k);
            let new = self.new_triangle([a, b, i], self.region[t as usize]);
            self.adj[new as usize][2] = n;
            if segment {
                self.seg[new as usize] |= 1 << 2;
            }
            let back = self.adj[n as usize]
                .iter()
                .position(|&x| x == t)
                .unwrap_or(0);
            self.adj[n as usize][back] = new;
            starts.push((a, new));
            created.push(new);
        }
        starts.sort_unstable();
        for &new in &created {
            let b = self.tri[new as usize][1];
            let next = starts[starts.partition_point(|&(a, _)| a < b)].1;
            self.adj[new as usize][0] = next;
            self.adj[next as usize][1] = new;
        }
        for &t in cavity {
            self.alive[t as usize] = false;
            self.free.push(t);
        }
        for &new in &created {
            for &v in &self.tri[new as usize] {
                if v != INFINITE {
                    self.vtri[v as usize] = new;
                }
            }
        }
        created
    }

    /// The input segment the sub-segment `(a, b)` is part of.
    fn segment_of(&self, a: u32, b: u32) -> u32 {
        for v in [a, b] {
            let s = self.on_segment[v as usize];
            if s != NONE {
                return s;
            }
        }
        // Both ends are input points: the segment between them.
        self.incident
            .of(a)
            .iter()
            .copied()
            .find(|&k| self.segments[k as usize].contains(&b))
            .unwrap_or(NONE)
    }

    /// Whether `v` is an input point where two segments meet at an acute angle (a centre of
    /// concentric shells).
    fn is_apex(&self, v: u32) -> bool {
        self.acute.get(v as usize).copied().unwrap_or(false)
    }

    fn split_point(&self, a: u32, b: u32) -> [f64; 2] {
        split_point(*self.p(a), *self.p(b), self.is_apex(a), self.is_apex(b))
    }

    /// Splits the sub-segment `(a, b)` if it still exists; returns whether it was split.
    fn split_segment(&mut self, a: u32, b: u32) -> Result<bool> {
        let Some((t, k)) = self.find_edge(a, b) else {
            return Ok(false);
        };
        if !self.is_segment(t, k) {
            return Ok(false);
        }
        self.budget()?;
        let m = self.split_point(a, b);
        let (pa, pb) = (*self.p(a), *self.p(b));
        let (u, _) = self.across(t, k);
        let cavity = if m == pa || m == pb || !m[0].is_finite() || !m[1].is_finite() {
            None
        } else {
            self.cavity(&[t, u], &m)
        };
        let Some((cavity, boundary)) = cavity else {
            self.report.unsplittable += 1;
            return Ok(false);
        };
        let on = self.segment_of(a, b);
        let i = self.push_point(m, on);
        let created = self.fill(i, &cavity, &boundary);
        self.report.segment_splits += 1;
        for &new in &created {
            let v = self.tri[new as usize];
            if v[1] == a || v[1] == b {
                self.set_segment(new, 0);
            }
            if v[0] == a || v[0] == b {
                self.set_segment(new, 1);
            }
        }
        self.after_insertion(&created);
        Ok(true)
    }

    /// Queues the sub-segments of the new triangles that an apex encroaches (the new point,
    /// or the other apex of a new half of a split sub-segment), and the new bad triangles.
    fn after_insertion(&mut self, created: &[u32]) {
        for &new in created {
            for k in 0..3 {
                if self.is_segment(new, k) && self.apex_encroached(new, k) {
                    let v = self.tri[new as usize];
                    self.encroached.push_back((v[(k + 1) % 3], v[(k + 2) % 3]));
                }
            }
            self.push_if_bad(new);
        }
    }

    fn budget(&self) -> Result<()> {
        let added = self.report.segment_splits + self.report.interior_points;
        if added >= MAX_REFINEMENT_POINTS {
            return Err(Error::new(
                ErrorKind::Limit,
                format!("quality refinement stopped after adding {added} points"),
            ));
        }
        Ok(())
    }

    /// The squared length of the shortest edge of triangle `t`, its area, and whether it is
    /// bad.
    fn quality(&self, t: u32) -> (f64, f64, bool) {
        let v = self.tri[t as usize];
        let [a, b, c] = v.map(|x| *self.p(x));
        let sq = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
        let (ab, bc, ca) = (sq(a, b), sq(b, c), sq(c, a));
        let area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        // The smallest angle is opposite the shortest edge.
        let (short, x, y) = if ab <= bc && ab <= ca {
            (ab, bc, ca)
        } else if bc <= ca {
            (bc, ca, ab)
        } else {
            (ca, ab, bc)
        };
        let cos = (x + y - short) / (2.0 * (x * y).sqrt());
        let max_area = self.region_table[self.region[t as usize] as usize].1;
        let bad =
            (self.min_angle > 0.0 && cos > self.cos_bound) || (max_area > 0.0 && area > max_area);
        (short, area, bad)
    }

    fn push_if_bad(&mut self, t: u32) {
        if self.region[t as usize] == 0 {
            return;
        }
        let (short, _, bad) = self.quality(t);
        if bad {
            self.queued += 1;
            self.bad.push(Bad {
                bucket: length_bucket(short),
                seq: self.queued,
                t,
                v: self.tri[t as usize],
            });
        }
    }

    /// The input segments point `v` lies on (inside or at an end).
    fn segments_at(&self, v: u32) -> &[u32] {
        let s = &self.on_segment[v as usize];
        if *s != NONE {
            std::slice::from_ref(s)
        } else {
            self.incident.of(v)
        }
    }

    /// Whether `p` and `q` lie on two segments that meet at an end at an angle below 60
    /// degrees, at equal distances from it (the shortest edge of a triangle skinny because of
    /// a small input angle).
    fn on_common_shell(&self, p: u32, q: u32) -> bool {
        let (sp, sq) = (self.segments_at(p), self.segments_at(q));
        for &s in sp {
            for &r in sq {
                if s == r {
                    continue;
                }
                let (s, r) = (self.segments[s as usize], self.segments[r as usize]);
                for z in s {
                    if z == p || z == q || !r.contains(&z) {
                        continue;
                    }
                    let pz = *self.p(z);
                    let d = |x: u32| {
                        let x = self.p(x);
                        (x[0] - pz[0]).hypot(x[1] - pz[1])
                    };
                    let (dp, dq) = (d(p), d(q));
                    if (dp - dq).abs() > SHELL_TOLERANCE * dp.max(dq) {
                        continue;
                    }
                    // The segments meet at z at an angle below 60 degrees.
                    let far = |g: [u32; 2]| if g[0] == z { g[1] } else { g[0] };
                    let (u, w) = (*self.p(far(s)), *self.p(far(r)));
                    let (u, w) = ([u[0] - pz[0], u[1] - pz[1]], [w[0] - pz[0], w[1] - pz[1]]);
                    let dot = u[0] * w[0] + u[1] * w[1];
                    if dot > 0.5 * u[0].hypot(u[1]) * w[0].hypot(w[1]) {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// The point that splits the bad triangle `t`: its off-center when the angle is bad and
    /// the off-center is nearer the shortest edge than the circumcenter, else its
    /// circumcenter. Also returns whether it is an off-center and the shortest edge.
    fn steiner_point(&self, t: u32, angle_bad: bool) -> ([f64; 2], bool, [u32; 2]) {
        let v = self.tri[t as usize];
        let [a, b, c] = v.map(|x| *self.p(x));
        let sq = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
        let lengths = [sq(b, c), sq(c, a), sq(a, b)];
        let k = (0..3)
            .min_by(|&i, &j| lengths[i].total_cmp(&lengths[j]))
            .unwrap_or(0);
        let (p, q) = (v[(k + 1) % 3], v[(k + 2) % 3]);
        let (bx, by) = (b[0] - a[0], b[1] - a[1]);
        let (cx, cy) = (c[0] - a[0], c[1] - a[1]);
        let d = 2.0 * (bx * cy - by * cx);
        let (b2, c2) = (bx * bx + by * by, cx * cx + cy * cy);
        let centre = [
            a[0] + (cy * b2 - by * c2) / d,
            a[1] + (bx * c2 - cx * b2) / d,
        ];
        if angle_bad && self.off_centers {
            let (pp, pq) = (*self.p(p), *self.p(q));
            let mid = [(pp[0] + pq[0]) * 0.5, (pp[1] + pq[1]) * 0.5];
            let half = lengths[k].sqrt() * 0.5;
            let reach = OFF_CENTER_MARGIN * half / (0.5 * self.min_angle.to_radians()).tan();
            let to_centre = (centre[0] - mid[0]).hypot(centre[1] - mid[1]);
            if reach < to_centre {
                let s = reach / to_centre;
                let off = [
                    mid[0] + s * (centre[0] - mid[0]),
                    mid[1] + s * (centre[1] - mid[1]),
                ];
                return (off, true, [p, q]);
            }
        }
        (centre, false, [p, q])
    }

    /// Refines the bad triangle `t`.
    fn split_triangle(&mut self, t: u32) -> Result<()> {
        let (_, area, _) = self.quality(t);
        let max_area = self.region_table[self.region[t as usize] as usize].1;
        let area_bad = max_area > 0.0 && area > max_area;
        let angle_bad = !area_bad;
        let (x, off, [p, q]) = self.steiner_point(t, angle_bad);
        if angle_bad && self.on_common_shell(p, q) {
            self.report.rejected_forever += 1;
            return Ok(());
        }
        if !x[0].is_finite() || !x[1].is_finite() {
            self.report.dropped += 1;
            return Ok(());
        }
        let u = match self.walk(t, &x, true) {
            Walk::Inside(u) => u,
            Walk::Blocked(u, k) => {
                let v = self.tri[u as usize];
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                // A point beyond a sub-segment in its small disk: split the sub-segment.
                if dot_sign(self.p(a), self.p(b), &x) != Sign::Positive
                    && self.split_segment(a, b)?
                {
                    self.report.encroaching_points += 1;
                    self.push_if_bad(t);
                } else {
                    self.report.dropped += 1;
                }
                return Ok(());
            }
            Walk::Lost => {
                self.report.dropped += 1;
                return Ok(());
            }
        };
        if self.region[u as usize] == 0 || self.tri[u as usize].iter().any(|&w| *self.p(w) == x) {
            self.report.dropped += 1;
            return Ok(());
        }
        let (cavity, boundary, visible) = self.conflicts(&[u], &x);
        let hit: Vec<(u32, u32)> = boundary
            .iter()
            .filter(|&&(c, k)| self.is_segment(c, k))
            .map(|&(c, k)| {
                let v = self.tri[c as usize];
                (v[(k + 1) % 3], v[(k + 2) % 3])
            })
            .filter(|&(a, b)| self.encroaches(a, b, &x))
            .collect();
        if !hit.is_empty() {
            self.report.encroaching_points += 1;
            let mut split = false;
            for (a, b) in hit {
                split |= self.split_segment(a, b)?;
            }
            if split {
                self.push_if_bad(t);
            } else {
                self.report.dropped += 1;
            }
            return Ok(());
        }
        if !visible {
            self.report.dropped += 1;
            return Ok(());
        }
        self.budget()?;
        let i = self.push_point(x, NONE);
        let created = self.fill(i, &cavity, &boundary);
        self.report.interior_points += 1;
        if off {
            self.report.off_centers += 1;
        }
        self.after_insertion(&created);
        Ok(())
    }

    /// Refines until no sub-segment is encroached and no triangle of the domain is bad but
    /// those dropped.
    pub fn run(&mut self, options: &QualityOptions) -> Result<()> {
        self.min_angle = options.min_angle_degrees;
        self.cos_bound = options.min_angle_degrees.to_radians().cos();
        self.off_centers = options.off_centers;
        for t in 0..self.tri.len() as u32 {
            for k in 0..3 {
                let v = self.tri[t as usize];
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                if a < b && self.is_segment(t, k) && self.apex_encroached(t, k) {
                    self.encroached.push_back((a, b));
                }
            }
        }
        for t in 0..self.tri.len() as u32 {
            self.push_if_bad(t);
        }
        loop {
            if let Some((a, b)) = self.encroached.pop_front() {
                if let Some((t, k)) = self.find_edge(a, b) {
                    if self.is_segment(t, k) && self.apex_encroached(t, k) {
                        self.split_segment(a, b)?;
                    }
                }
                continue;
            }
            let Some(bad) = self.bad.pop() else {
                return Ok(());
            };
            let t = bad.t;
            if !self.alive[t as usize] || self.tri[t as usize] != bad.v {
                continue;
            }
            if !self.quality(t).2 {
                continue;
            }
            self.split_triangle(t)?;
        }
    }

    /// The finite triangles of the domain with their labels.
    pub fn domain_triangles(&self) -> (Vec<u32>, Vec<i32>) {
        let mut triangles = Vec::new();
        let mut labels = Vec::new();
        for t in 0..self.tri.len() {
            if self.alive[t] && self.region[t] != 0 {
                triangles.extend_from_slice(&self.tri[t]);
                labels.push(self.region_table[self.region[t] as usize].0);
            }
        }
        (triangles, labels)
    }

    /// Every sub-segment once, with its input segment: `(a, b, segment)`.
    pub fn sub_segments(&self) -> Vec<(u32, u32, u32)> {
        let mut out = Vec::new();
        for t in 0..self.tri.len() {
            if !self.alive[t] {
                continue;
            }
            for k in 0..3 {
                let v = self.tri[t];
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                if a < b && b != INFINITE && self.is_segment(t as u32, k) {
                    out.push((a, b, self.segment_of(a, b)));
                }
            }
        }
        out
    }
}

/// The queue bucket of a squared length: `floor(2 log2(square))`, from the bits of the number
/// (exact, the same on every platform): squared lengths within a factor `sqrt(2)` of each
/// other share a bucket (Triangle's bucketing).
fn length_bucket(square: f64) -> i32 {
    let bits = square.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i32;
    if exponent == 0 {
        // Zero or subnormal: below every normal square.
        return -2 * 1023;
    }
    let mantissa = f64::from_bits((bits & ((1 << 52) - 1)) | (1023 << 52));
    2 * (exponent - 1023) + i32::from(mantissa >= std::f64::consts::SQRT_2)
}

/// For each point of `points`, whether two of the `segments` at it form an acute angle.
pub fn acute_apices(points: &[[f64; 2]], segments: &[[u32; 2]]) -> Vec<bool> {
    let incident = Incidence::new(points.len(), segments);
    (0..points.len() as u32)
        .map(|z| {
            let far = |k: u32| {
                let s = segments[k as usize];
                &points[(if s[0] == z { s[1] } else { s[0] }) as usize]
            };
            let list = incident.of(z);
            (0..list.len()).any(|i| {
                list[i + 1..]
                    .iter()
                    .any(|&j| dot_sign(far(list[i]), far(j), &points[z as usize]) == Sign::Positive)
            })
        })
        .collect()
}

/// The segments at each point, in increasing order, in one array.
struct Incidence {
    start: Vec<u32>,
    list: Vec<u32>,
}

impl Incidence {
    /// For the points `0..n` and the segments `segments` (ends below `n`).
    fn new(n: usize, segments: &[[u32; 2]]) -> Self {
        let mut start = vec![0u32; n + 1];
        for s in segments {
            start[s[0] as usize + 1] += 1;
            start[s[1] as usize + 1] += 1;
        }
        for i in 1..start.len() {
            start[i] += start[i - 1];
        }
        let mut list = vec![0u32; 2 * segments.len()];
        let mut next = start.clone();
        for (k, s) in segments.iter().enumerate() {
            for v in s {
                list[next[*v as usize] as usize] = k as u32;
                next[*v as usize] += 1;
            }
        }
        Incidence { start, list }
    }

    /// The segments at point `v` (none past the points of [`Incidence::new`]).
    fn of(&self, v: u32) -> &[u32] {
        match (self.start.get(v as usize), self.start.get(v as usize + 1)) {
            (Some(&a), Some(&b)) => &self.list[a as usize..b as usize],
            _ => &[],
        }
    }
}

/// Where to split the sub-segment `[a b]`: at the power of two nearest to half its length
/// from its end when exactly one end is an apex (an input point where two segments form an
/// acute angle), else at its midpoint.
fn split_point(a: [f64; 2], b: [f64; 2], a_apex: bool, b_apex: bool) -> [f64; 2] {
    let midpoint = [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5];
    let (from, to) = match (a_apex, b_apex) {
        (true, false) => (a, b),
        (false, true) => (b, a),
        _ => return midpoint,
    };
    let length = (to[0] - from[0]).hypot(to[1] - from[1]);
    let t = (length * 0.5).log2().round().exp2() / length;
    if !(t > 0.25 && t < 0.75) {
        return midpoint;
    }
    [
        from[0] + t * (to[0] - from[0]),
        from[1] + t * (to[1] - from[1]),
    ]
}

/// The first phase: splits the input segments `segments` (point pairs of `cloud`, which holds
/// the input points) at concentric shells or midpoints until every sub-segment is strongly
/// Delaunay-admissible relative to the points of the cloud's grid (Pébay's criterion, with
/// Ruppert's split points rather than Pébay's projections, which leave short sub-segments
/// near acute angles that refinement would then propagate); the sub-segments are then edges of
/// every Delaunay triangulation of those points. Returns the sub-segments with their input
/// segment and the input segment of each added point. `acute` is [`acute_apices`].
pub fn split_segments(
    cloud: &mut Cloud,
    segments: &[[u32; 2]],
    acute: &[bool],
    limit: usize,
) -> Result<(Vec<[u32; 3]>, Vec<u32>)> {
    let apex = |v: u32| acute.get(v as usize).copied().unwrap_or(false);
    let mut stack: Vec<[u32; 3]> = segments
        .iter()
        .enumerate()
        .rev()
        .map(|(k, s)| [s[0], s[1], k as u32])
        .collect();
    // Accepted sub-segments, with the number of points they were accepted against.
    let mut done: Vec<([u32; 3], usize)> = Vec::new();
    let mut on_segment = Vec::new();
    loop {
        let Some([a, b, s]) = stack.pop() else {
            // Points added later may have entered the disks of earlier sub-segments.
            let now = cloud.points.len();
            let (clean, dirty): (Vec<_>, Vec<_>) = done
                .into_iter()
                .partition(|&(e, seen)| seen == now || strongly_admissible(cloud, e[0], e[1]));
            done = clean.into_iter().map(|(e, _)| (e, now)).collect();
            if dirty.is_empty() {
                break;
            }
            stack = dirty.into_iter().rev().map(|(e, _)| e).collect();
            continue;
        };
        if strongly_admissible(cloud, a, b) {
            done.push(([a, b, s], cloud.points.len()));
            continue;
        }
        if on_segment.len() >= limit {
            return Err(Error::new(
                ErrorKind::Limit,
                format!("segment splitting stopped after adding {limit} points"),
            ));
        }
        let (pa, pb) = (cloud.points[a as usize], cloud.points[b as usize]);
        let m = split_point(pa, pb, apex(a), apex(b));
        if m == pa || m == pb {
            return Err(Error::internal(format!(
                "sub-segment ({a}, {b}) is too short to split in floating point"
            )));
        }
        let i = cloud.push(m);
        on_segment.push(s);
        stack.push([i, b, s]);
        stack.push([a, i, s]);
    }
    Ok((done.into_iter().map(|(e, _)| e).collect(), on_segment))
}
