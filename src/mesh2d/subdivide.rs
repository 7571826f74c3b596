//! A-priori subdivision of the constraint edges (Pébay §3.3, Algorithm 3.2): split the edges
//! of `Γ` until every sub-edge is strongly Delaunay-admissible relative to the augmented point
//! set `S'`.
//!
//! - A *nodal centre* is a point where two constraint edges form an acute angle; its *node* is
//!   every edge at that point (Definition 3.1). The node is *closed* when a cyclic sequence of
//!   its edges has every two consecutive ones at an acute angle, i.e. when the graph "edges at
//!   an acute angle" has a cycle; otherwise it is *open*.
//! - A non-admissible edge at a closed nodal centre `P*` triggers `nettoyage` on the node:
//!   node edges `[P* M]` are cut at the same distance `d` from `P*`.
//! - Any other non-admissible edge `[Pi Pj]` is cut by `projection`: at the orthogonal
//!   projection of a point of its small disk, the one nearest to the edge's midpoint (the paper
//!   leaves the choice open: "choisir `Pn ∈ Sij \ {Pi, Pj}`"). The point is then outside both
//!   new small disks, and the most even cut leaves the fewest neighbours in them: on the
//!   generated cases of `c_tests/test_2d_vs_cgal.c` it adds fewer points than projecting the
//!   point nearest to the edge's line, most on long nearly parallel edges (a zigzag: 35
//!   instead of 50). Distances are compared squared: exact ties, of points placed
//!   symmetrically about the midpoint, go to the smallest index.
//! - Non-admissible edges are processed by decreasing number of points in their small disk
//!   (§3.3's heuristic); the small-disk queries use the bucket grid of [`Cloud`]. A point
//!   added can only spoil the edges whose closed small disk holds it, or an admissible edge
//!   with points in its small disk (type 1.0 or 1.2.0), through the part of the circumdisk the
//!   classification looks at beyond its line. The first are found in a bucket grid of the
//!   edges' disks ([`DiskGrid`]) and checked again at once; the second are watched, and
//!   checked again after the queue empties, with the edges that `nettoyage` made or touched
//!   (3 or 4 rounds instead of one per wave of projections, up to 93: a random star polygon
//!   of 10^4 edges with 10^4 points inside, 22.2 s -> 4.5 s -> 3.6 s).
//!
//! The distance `d` of `nettoyage`, and which node edges it cuts. The paper cuts every node
//! edge at `d = d*/2`, `d*` the distance from `P*` to the nearest other point in the small
//! disks of the node, and attributes the poor triangles of its examples to that choice. A
//! point `Q` at distance `r` and angle `β` from an edge is outside the small disk of its first
//! piece `[P* M]` (length `d`) iff `d < r / cos β`; with `d_max` the least of these bounds over
//! the node (and its edge lengths), the paper-like choice here is
//! `d₀ = min(L_min / 2, 3/4 d_max, 3/4 d_seg)`, where `L_min` is the shortest node edge and
//! `d_seg` the distance from `P*` to every constraint edge not at `P*` (no point inserted
//! later, always on a constraint edge, can come that close); `d₀` is never below the paper's.
//! Cutting every edge is often more than needed: an edge may stay whole when it is strongly
//! admissible once the other cuts are made (an edge of the node whose far end is at about the
//! distance `d` of the cuts, or whose small disk holds node points on one side only). So the
//! candidate distances are `d₀`, `min(3/4 d_max, 3/4 d_seg)` and every node edge length up to
//! `3/4 d_seg`, those not below `d₀`; for each, edges are cut one at a time, starting from
//! none, while some edge or first piece is not strongly admissible with the planned cut points
//! added (classified exactly, the planned points in the cloud for the test); a candidate where
//! a piece that cannot be cut (too short, or a first piece already) fails is dropped. The
//! candidate cutting
//! the fewest edges, at least one, wins (the largest distance on ties); with none left, every
//! edge is cut at `d₀`. This departs from the paper's `nettoyage` (every node edge, `d < d*`),
//! so its termination proof (Theorem 3.2) no longer applies as such; every `nettoyage` adds at
//! least one point, and the limit on added points turns a run that would not end into an
//! error (`ErrorKind::Limit`).
//!
//! Constructions are floating point (projections and cut points are rounded); every decision
//! is exact. A rounded projection that would not separate its point from the two new edges'
//! small disks is replaced by the midpoint, whose disks shrink geometrically.

use std::collections::BinaryHeap;

use super::classify::{classify_with, strongly_admissible};
use super::cloud::{clamped_cell, widened_box, Cloud};
use super::exact::dot_sign;
use crate::error::{Error, ErrorKind, Result};
use crate::predicates::Sign;
use crate::union_find::UnionFind;

/// Which of Pébay's algorithms runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Algorithm {
    /// Algorithm 3.1: `nettoyage` at every end of a non-admissible edge where two edges form
    /// an acute angle, on the edges there that form one.
    Brutal,
    /// Algorithm 3.2: `nettoyage` at closed nodes only, on the whole node.
    #[default]
    ClosedNodes,
}

/// A constraint sub-edge.
#[derive(Clone, Copy, Debug)]
struct Edge {
    a: u32,
    b: u32,
    /// The input segment it is part of.
    segment: u32,
    alive: bool,
}

/// What the subdivision did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SubdivisionReport {
    /// Points added by `projection` (midpoint fallbacks included).
    pub projections: usize,
    /// Points added by `nettoyage`.
    pub cleanings: usize,
    /// Projections replaced by a midpoint (rounding would have kept the point in a disk).
    pub midpoint_fallbacks: usize,
    /// Nodes cleaned (closed nodes for Algorithm 3.2).
    pub nodes_cleaned: usize,
    /// Full re-classification passes.
    pub rounds: usize,
}

/// The subdivision state: `S'` (in the cloud) and `Γ'`.
pub struct Subdivision {
    pub cloud: Cloud,
    edges: Vec<Edge>,
    /// The live edges by the boxes of their small disks.
    disks: DiskGrid,
    /// Live edges whose closed small disk received a point since they were last checked.
    touched: Vec<u32>,
    /// Edges found admissible with points in their small disk since the round began.
    watched: Vec<u32>,
    /// Edges at each point (ids into `edges`, live or not: filtered on use).
    incident: Vec<Vec<u32>>,
    pub report: SubdivisionReport,
    limit: usize,
    algorithm: Algorithm,
}

impl Subdivision {
    /// `cloud` holds `S`; `segments` are pairs of distinct point indices forming a valid
    /// constraint field (no crossing, no point on an open segment). At most `limit` points are
    /// added.
    pub fn new(cloud: Cloud, segments: &[[u32; 2]], limit: usize, algorithm: Algorithm) -> Self {
        let mut incident = vec![Vec::new(); cloud.points.len()];
        let edges: Vec<Edge> = segments
            .iter()
            .enumerate()
            .map(|(k, s)| {
                incident[s[0] as usize].push(k as u32);
                incident[s[1] as usize].push(k as u32);
                Edge {
                    a: s[0],
                    b: s[1],
                    segment: k as u32,
                    alive: true,
                }
            })
            .collect();
        let mut disks = DiskGrid::new(cloud.bounds(), edges.len());
        for (k, e) in edges.iter().enumerate() {
            disks.insert(
                k as u32,
                &cloud.points[e.a as usize],
                &cloud.points[e.b as usize],
            );
        }
        Subdivision {
            cloud,
            edges,
            disks,
            touched: Vec::new(),
            watched: Vec::new(),
            incident,
            report: SubdivisionReport::default(),
            limit,
            algorithm,
        }
    }

    /// Runs the algorithm to completion: afterwards every live sub-edge is strongly
    /// Delaunay-admissible relative to all points of the cloud.
    pub fn run(&mut self) -> Result<()> {
        let mut candidates: Vec<u32> = (0..self.edges.len() as u32).collect();
        loop {
            self.report.rounds += 1;
            let bad = self.non_admissible(candidates);
            if bad.is_empty() {
                return Ok(());
            }
            self.touched.clear();
            let before = self.edges.len() as u32;
            self.clean_nodes(&bad)?;
            // The edges cleaning made, and those whose disk a cleaning point fell in, are
            // checked at the next round.
            candidates = std::mem::take(&mut self.touched);
            candidates.extend(before..self.edges.len() as u32);
            let mut heap: BinaryHeap<(usize, std::cmp::Reverse<u32>)> = BinaryHeap::new();
            for e in bad {
                let edge = self.edges[e as usize];
                let count = self.cloud.small_disk(edge.a, edge.b).count();
                heap.push((count, std::cmp::Reverse(e)));
            }
            // Whether an edge is in the heap: a touched one there is checked when it comes out.
            let mut queued = vec![false; self.edges.len()];
            for &(_, std::cmp::Reverse(e)) in heap.iter() {
                queued[e as usize] = true;
            }
            while let Some((_, std::cmp::Reverse(e))) = heap.pop() {
                queued[e as usize] = false;
                if !self.edges[e as usize].alive {
                    continue;
                }
                let disk = self.disk_points(e);
                if self.admissible_with(e, &disk) {
                    continue;
                }
                let [e1, e2] = self.project(e, &disk)?;
                // The new halves, and the edges whose small disk the new point fell in.
                let mut check = std::mem::take(&mut self.touched);
                check.extend([e1, e2]);
                check.sort_unstable();
                check.dedup();
                queued.resize(self.edges.len(), false);
                for f in check {
                    if !self.edges[f as usize].alive || queued[f as usize] {
                        continue;
                    }
                    let disk = self.disk_points(f);
                    if !self.admissible_with(f, &disk) {
                        heap.push((disk.len(), std::cmp::Reverse(f)));
                        queued[f as usize] = true;
                    }
                }
            }
            // Edges found admissible with points in their small disk: a point added beyond
            // their line may have spoilt them.
            candidates.append(&mut self.watched);
        }
    }

    /// The live sub-edges, as `(a, b, segment)`.
    pub fn sub_edges(&self) -> impl Iterator<Item = (u32, u32, u32)> + '_ {
        self.edges
            .iter()
            .filter(|e| e.alive)
            .map(|e| (e.a, e.b, e.segment))
    }

    /// The live edges among `candidates` that are not strongly admissible, in id order.
    fn non_admissible(&mut self, mut candidates: Vec<u32>) -> Vec<u32> {
        candidates.sort_unstable();
        candidates.dedup();
        candidates.retain(|&e| {
            self.edges[e as usize].alive && !self.admissible_with(e, &self.disk_points(e))
        });
        candidates
    }

    /// The points of the closed small disk of edge `e` but its ends, as the grid meets them
    /// (their uses do not depend on the order: the classification, and the point nearest the
    /// midpoint, ties to the smallest index).
    fn disk_points(&self, e: u32) -> Vec<u32> {
        let edge = self.edges[e as usize];
        self.cloud.small_disk(edge.a, edge.b).collect()
    }

    /// Whether edge `e` is strongly admissible, `disk` the points of its small disk. An
    /// admissible edge with points in its small disk (type 1.0 or 1.2.0) is watched: a point
    /// added beyond its line, outside its small disk, can still spoil it.
    fn admissible_with(&mut self, e: u32, disk: &[u32]) -> bool {
        let edge = self.edges[e as usize];
        let admissible =
            classify_with(&self.cloud, edge.a, edge.b, disk.iter().copied()).strongly_admissible();
        if admissible && !disk.is_empty() {
            self.watched.push(e);
        }
        admissible
    }

    fn point(&self, i: u32) -> [f64; 2] {
        self.cloud.points[i as usize]
    }

    /// The live edges at point `p`, each oriented away from `p`: (edge id, far end).
    fn node(&self, p: u32) -> Vec<(u32, u32)> {
        self.incident[p as usize]
            .iter()
            .filter(|&&e| self.edges[e as usize].alive)
            .map(|&e| {
                let edge = self.edges[e as usize];
                (e, if edge.a == p { edge.b } else { edge.a })
            })
            .collect()
    }

    /// Whether the edges at `p` make it a closed nodal centre: the graph joining every two
    /// edges at an acute angle has a cycle (union-find: an edge joining a component to
    /// itself).
    fn is_closed_node(&self, p: u32) -> bool {
        let node = self.node(p);
        if node.len() < 3 {
            return false;
        }
        let centre = self.point(p);
        let mut sets = UnionFind::new(node.len());
        for u in 0..node.len() {
            for v in u + 1..node.len() {
                let (a, b) = (self.point(node[u].1), self.point(node[v].1));
                if dot_sign(&a, &b, &centre) != Sign::Positive {
                    continue;
                }
                if !sets.union(u as u32, v as u32) {
                    return true;
                }
            }
        }
        false
    }

    /// The edges to cut by `nettoyage` at `p`, if any: the whole node at a closed nodal
    /// centre (Algorithm 3.2), or every edge at an acute angle with another (Algorithm 3.1).
    fn edges_to_clean(&self, p: u32) -> Vec<(u32, u32)> {
        let node = self.node(p);
        match self.algorithm {
            Algorithm::ClosedNodes if self.is_closed_node(p) => node,
            Algorithm::ClosedNodes => Vec::new(),
            Algorithm::Brutal => {
                let centre = self.point(p);
                let acute = |u: usize| {
                    (0..node.len()).any(|v| {
                        v != u
                            && dot_sign(&self.point(node[u].1), &self.point(node[v].1), &centre)
                                == Sign::Positive
                    })
                };
                (0..node.len())
                    .filter(|&u| acute(u))
                    .map(|u| node[u])
                    .collect()
            }
        }
    }

    /// `nettoyage` at every end of a non-admissible edge of `bad` that calls for it.
    fn clean_nodes(&mut self, bad: &[u32]) -> Result<()> {
        let mut centres: Vec<u32> = bad
            .iter()
            .flat_map(|&e| [self.edges[e as usize].a, self.edges[e as usize].b])
            .collect();
        centres.sort_unstable();
        centres.dedup();
        for p in centres {
            let edges = self.edges_to_clean(p);
            if !edges.is_empty() {
                self.clean_node(p, edges)?;
            }
        }
        Ok(())
    }

    /// `nettoyage(P*, M, d)` on the given edges at `p` (edge id, far end): the edges that
    /// [`Subdivision::cut_plan`] picks are cut at its distance `d` from `p`.
    fn clean_node(&mut self, p: u32, node: Vec<(u32, u32)>) -> Result<()> {
        let (d, cut) = self.cut_plan(p, &node)?;
        for ((e, far), cut) in node.into_iter().zip(cut) {
            if cut {
                let m = self.point_at(p, far, d);
                self.split(e, m)?;
                self.report.cleanings += 1;
            }
        }
        self.report.nodes_cleaned += 1;
        Ok(())
    }

    /// Whether the point at distance `d` from `p` towards `far` rounds to neither of them.
    fn can_cut(&self, p: u32, far: u32, d: f64) -> bool {
        let m = self.point_at(p, far, d);
        m != self.point(p) && m != self.point(far)
    }

    /// The point at distance `d` from point `p` towards point `far` (rounded).
    fn point_at(&self, p: u32, far: u32, d: f64) -> [f64; 2] {
        let (c, f) = (self.point(p), self.point(far));
        let t = d / (f[0] - c[0]).hypot(f[1] - c[1]);
        [c[0] + t * (f[0] - c[0]), c[1] + t * (f[1] - c[1])]
    }

    /// The distance `d` of `nettoyage` at `p` and which of the `node` edges to cut there (see
    /// the module documentation): of the candidate distances, the one that cuts the fewest
    /// edges (the largest on ties), at least one.
    fn cut_plan(&mut self, p: u32, node: &[(u32, u32)]) -> Result<(f64, Vec<bool>)> {
        let centre = self.point(p);
        let mut lengths = Vec::with_capacity(node.len());
        // `d` below `r / cos β` for every point of a small disk, at distance `r` from `p` and
        // angle `β` from the edge, keeps it out of the first piece.
        let mut bound = f64::INFINITY;
        for &(e, far) in node {
            let f = self.point(far);
            let (ux, uy) = (f[0] - centre[0], f[1] - centre[1]);
            let length = ux.hypot(uy);
            lengths.push(length);
            bound = bound.min(length);
            for q in self.disk_points(e) {
                let q = self.point(q);
                let (vx, vy) = (q[0] - centre[0], q[1] - centre[1]);
                let along = (ux * vx + uy * vy) / length;
                if along > 0.0 {
                    bound = bound.min((vx * vx + vy * vy) / along);
                }
            }
        }
        let shortest = lengths.iter().copied().fold(f64::INFINITY, f64::min);
        let margin = 0.75 * self.distance_to_other_edges(p);
        let paper = (shortest * 0.5).min(0.75 * bound).min(margin);
        if paper.is_nan() || paper <= 0.0 {
            return Err(Error::internal(format!(
                "nettoyage at point {p}: no positive cut distance"
            )));
        }
        let mut candidates: Vec<f64> = lengths.iter().copied().filter(|&l| l <= margin).collect();
        candidates.extend([paper, margin.min(0.75 * bound)]);
        candidates.retain(|&d| d.is_finite() && d >= paper);
        candidates.sort_by(|x, y| y.total_cmp(x));
        candidates.dedup();
        let mut best: Option<(usize, f64, Vec<bool>)> = None;
        for d in candidates {
            let Some(cut) = self.cuts_at(p, node, &lengths, d) else {
                continue;
            };
            let count = cut.iter().filter(|&&c| c).count();
            if count > 0 && best.as_ref().is_none_or(|b| count < b.0) {
                best = Some((count, d, cut));
            }
        }
        Ok(match best {
            Some((_, d, cut)) => (d, cut),
            None => (paper, vec![true; node.len()]),
        })
    }

    /// Which `node` edges to cut at distance `d` from `p` (`None`: no choice works): starting
    /// from none, the first edge (whole, or its first piece when cut) that is not strongly
    /// admissible with the planned cut points in the cloud is cut, until none fails; a failing
    /// first piece, or a failing edge no longer than `d` (or whose cut point would round onto
    /// an end), rules `d` out.
    fn cuts_at(
        &mut self,
        p: u32,
        node: &[(u32, u32)],
        lengths: &[f64],
        d: f64,
    ) -> Option<Vec<bool>> {
        let mut cut = vec![false; node.len()];
        loop {
            let planned: Vec<[f64; 2]> = (0..node.len())
                .filter(|&j| cut[j])
                .map(|j| self.point_at(p, node[j].1, d))
                .collect();
            let base = self.cloud.points.len();
            for &m in &planned {
                self.cloud.push(m);
            }
            // The planned first pieces and the whole edges, checked with the planned points:
            // the first failing one, and whether it can still be cut.
            let mut failing = None;
            let mut index = base as u32;
            for (j, &(_, far)) in node.iter().enumerate() {
                let end = if cut[j] {
                    index += 1;
                    index - 1
                } else {
                    far
                };
                if !strongly_admissible(&self.cloud, p, end) {
                    failing = Some((j, !cut[j] && lengths[j] > d && self.can_cut(p, far, d)));
                    break;
                }
            }
            for _ in &planned {
                self.cloud.pop();
            }
            match failing {
                None => return Some(cut),
                Some((j, true)) => cut[j] = true,
                Some((_, false)) => return None,
            }
        }
    }

    /// The distance from point `p` to the nearest live edge not at `p`.
    fn distance_to_other_edges(&self, p: u32) -> f64 {
        let c = self.point(p);
        self.edges
            .iter()
            .filter(|e| e.alive && e.a != p && e.b != p)
            .map(|e| point_segment_distance(&c, &self.point(e.a), &self.point(e.b)))
            .fold(f64::INFINITY, f64::min)
    }

    /// `projection(Pi, Pj, Pn)` on edge `e` with `Pn` the point of `disk` nearest to the
    /// edge's midpoint (ties: lowest index); the midpoint when rounding defeats the projection.
    fn project(&mut self, e: u32, disk: &[u32]) -> Result<[u32; 2]> {
        let edge = self.edges[e as usize];
        let (a, b) = (self.point(edge.a), self.point(edge.b));
        let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
        let mid = [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5];
        let off_centre = |q: u32| {
            let q = self.point(q);
            (q[0] - mid[0]) * (q[0] - mid[0]) + (q[1] - mid[1]) * (q[1] - mid[1])
        };
        let n = disk
            .iter()
            .map(|&x| (off_centre(x), x))
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
            .map(|(_, x)| x)
            .ok_or_else(|| Error::internal(format!("projection on edge {e}: empty small disk")))?;
        let q = self.point(n);
        let t = ((q[0] - a[0]) * ux + (q[1] - a[1]) * uy) / (ux * ux + uy * uy);
        let m = [a[0] + t * ux, a[1] + t * uy];
        let separates = t > 0.0
            && t < 1.0
            && m != a
            && m != b
            && dot_sign(&a, &m, &q) == Sign::Positive
            && dot_sign(&m, &b, &q) == Sign::Positive;
        self.report.projections += 1;
        if separates {
            return self.split(e, m);
        }
        self.report.midpoint_fallbacks += 1;
        self.split(e, mid)
    }

    /// Notes the live edges whose closed small disk holds the new point `p` (exact test):
    /// they are checked again ([`Subdivision::run`]).
    fn note_point(&mut self, p: u32) {
        let q = self.point(p);
        let (edges, points) = (&self.edges, &self.cloud.points);
        let bucket = self.disks.cell_of(&q);
        // Dead edges leave the bucket as they are met.
        bucket.retain(|&k| edges[k as usize].alive);
        for &k in bucket.iter() {
            let e = edges[k as usize];
            if e.a != p
                && e.b != p
                && dot_sign(&points[e.a as usize], &points[e.b as usize], &q) != Sign::Positive
            {
                self.touched.push(k);
            }
        }
    }

    /// Splits edge `e` at the new point `m`; returns the two new edges.
    fn split(&mut self, e: u32, m: [f64; 2]) -> Result<[u32; 2]> {
        if self.report.projections + self.report.cleanings > self.limit {
            return Err(Error::new(
                ErrorKind::Limit,
                format!(
                    "constraint subdivision stopped after adding {} points (limit {})",
                    self.report.projections + self.report.cleanings,
                    self.limit
                ),
            ));
        }
        let edge = self.edges[e as usize];
        let (a, b) = (self.point(edge.a), self.point(edge.b));
        if m == a || m == b || !m[0].is_finite() || !m[1].is_finite() {
            return Err(Error::internal(format!(
                "edge {e} ({}, {}) is too short to split in floating point",
                edge.a, edge.b
            )));
        }
        self.edges[e as usize].alive = false;
        let mid = self.cloud.push(m);
        let first = self.edges.len() as u32;
        for (x, y) in [(edge.a, mid), (mid, edge.b)] {
            self.edges.push(Edge {
                a: x,
                b: y,
                segment: edge.segment,
                alive: true,
            });
        }
        self.incident.push(vec![first, first + 1]);
        for (end, new) in [(edge.a, first), (edge.b, first + 1)] {
            let list = &mut self.incident[end as usize];
            if let Some(slot) = list.iter_mut().find(|x| **x == e) {
                *slot = new;
            }
        }
        self.note_point(mid);
        self.disks.insert(first, &a, &m);
        self.disks.insert(first + 1, &m, &b);
        if self.disks.crowded() {
            let live: Vec<(u32, [f64; 2], [f64; 2])> = (0..self.edges.len() as u32)
                .filter(|&k| self.edges[k as usize].alive)
                .map(|k| {
                    let e = self.edges[k as usize];
                    (k, self.point(e.a), self.point(e.b))
                })
                .collect();
            let mut disks = DiskGrid::new(self.cloud.bounds(), live.len());
            for (k, a, b) in live {
                disks.insert(k, &a, &b);
            }
            self.disks = disks;
        }
        Ok([first, first + 1])
    }
}

/// Euclidean distance from `p` to the segment `[a b]` (floating point).
fn point_segment_distance(p: &[f64; 2], a: &[f64; 2], b: &[f64; 2]) -> f64 {
    let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
    let (vx, vy) = (p[0] - a[0], p[1] - a[1]);
    let len2 = ux * ux + uy * uy;
    let t = if len2 > 0.0 {
        ((vx * ux + vy * uy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (vx - t * ux).hypot(vy - t * uy)
}

/// A bucket grid of edges by the boxes of their small disks: the candidates whose disk may
/// hold a point are the edges filed in its cell. Boxes and points are clamped to the grid, as
/// in [`Cloud`], so a point of a disk is in a cell its edge is filed in. Dead edges leave a
/// bucket when a query meets them; the grid is laid again, from the live edges, when the
/// edges filed outnumber its cells four times.
struct DiskGrid {
    lo: [f64; 2],
    scale: f64,
    n: usize,
    cells: Vec<Vec<u32>>,
    filed: usize,
}

impl DiskGrid {
    /// About `edges` cells over the box `(lo, hi)`.
    fn new((lo, hi): ([f64; 2], [f64; 2]), edges: usize) -> Self {
        let side = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let n = ((edges as f64).sqrt().ceil() as usize).clamp(1, 1 << 10);
        let scale = if side > 0.0 && side.is_finite() {
            n as f64 / side
        } else {
            0.0
        };
        DiskGrid {
            lo,
            scale,
            n,
            cells: vec![Vec::new(); n * n],
            filed: 0,
        }
    }

    /// The clamped cell coordinate of `x` along axis `k`.
    fn axis(&self, x: f64, k: usize) -> usize {
        clamped_cell(x, self.lo[k], self.scale, self.n)
    }

    /// Files edge `k` from `a` to `b` in the cells its small disk's box meets (the box
    /// [`Cloud`]'s small-disk queries use).
    fn insert(&mut self, k: u32, a: &[f64; 2], b: &[f64; 2]) {
        let (lo, hi) = widened_box(a, b);
        let (x0, x1) = (self.axis(lo[0], 0), self.axis(hi[0], 0));
        let (y0, y1) = (self.axis(lo[1], 1), self.axis(hi[1], 1));
        for y in y0..=y1 {
            for x in x0..=x1 {
                self.cells[y * self.n + x].push(k);
            }
        }
        self.filed += 1;
    }

    /// The bucket of the cell of `p`.
    fn cell_of(&mut self, p: &[f64; 2]) -> &mut Vec<u32> {
        let id = self.axis(p[1], 1) * self.n + self.axis(p[0], 0);
        &mut self.cells[id]
    }

    /// Whether the edges filed outnumber the cells four times.
    fn crowded(&self) -> bool {
        self.filed > 4 * self.cells.len() && self.n < 1 << 10
    }
}
