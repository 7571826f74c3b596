//! 2D Delaunay triangulation (DESIGN.md layer 2, the 2D counterpart): Bowyer–Watson insertion
//! in flat arrays, point location by a stochastic visibility walk, an infinite vertex closing
//! the convex hull.
//!
//! Invariants (checked exactly by [`Delaunay2d::validate`]):
//! - every live triangle `t` has three distinct vertices `tri[t]`; a finite one is
//!   counter-clockwise (`orient2d > 0`); an infinite one holds [`INFINITE`] once, and with the
//!   infinite vertex at slot `k`, its finite edge `(tri[t][k+1], tri[t][k+2])` has the hull on
//!   its right (the outside strictly on its left);
//! - `adj[t][k]` is the live triangle across the edge opposite slot `k`, and that triangle
//!   holds `t` across the same edge (symmetry);
//! - no finite triangle has the opposite vertex of a finite neighbour inside its circumcircle
//!   under [`incircle_sos`] (locally Delaunay, hence globally);
//! - every inserted, non-duplicate point is a vertex.
//!
//! Exact ties (four or more cocircular points) are broken by the symbolic perturbation of
//! [`incircle_sos`], so the triangulation is a function of the point set, not of the
//! insertion order. Points on the line of a hull edge are in conflict with its infinite
//! triangle only when they lie strictly between its ends.

use std::collections::HashMap;

use super::exact::{dot_sign, incircle_sos};
use crate::error::{Error, Result};
use crate::predicates::{orient2d, Sign};

/// The vertex at infinity.
pub const INFINITE: u32 = u32::MAX;

/// No triangle.
const NONE: u32 = u32::MAX;

/// A Delaunay triangulation of a point set given by index into `points`.
pub struct Delaunay2d<'a> {
    points: &'a [[f64; 2]],
    /// Three vertex ids per triangle.
    tri: Vec<[u32; 3]>,
    /// Neighbour across the edge opposite each slot.
    adj: Vec<[u32; 3]>,
    alive: Vec<bool>,
    free: Vec<u32>,
    hint: u32,
    rng: u32,
    /// `duplicate_of[i]`: the vertex point `i` was merged onto (`i` when it is a vertex, NONE
    /// when not inserted).
    duplicate_of: Vec<u32>,
    // Scratch of one insertion, kept to avoid allocations.
    mark: Vec<u32>,
    stamp: u32,
    cavity: Vec<u32>,
    stack: Vec<u32>,
    starts: HashMap<u32, u32>,
    created: Vec<u32>,
}

impl<'a> Delaunay2d<'a> {
    /// The Delaunay triangulation of all `points` (finite, at most 2^31 of them). Identical
    /// points are merged onto the first in index order ([`Self::duplicate_of`]). Fails when
    /// the points do not span the plane.
    pub fn new(points: &'a [[f64; 2]]) -> Result<Self> {
        Self::of_subset(points, |_| true)
    }

    /// The Delaunay triangulation of the points `i` with `keep(i)` (the others are no
    /// vertex; [`Self::duplicate_of`] is NONE for them), as [`Self::new`].
    pub fn of_subset(points: &'a [[f64; 2]], keep: impl Fn(u32) -> bool) -> Result<Self> {
        let mut t = Delaunay2d {
            points,
            tri: Vec::new(),
            adj: Vec::new(),
            alive: Vec::new(),
            free: Vec::new(),
            hint: 0,
            rng: 0x9e37_79b9,
            duplicate_of: vec![NONE; points.len()],
            mark: Vec::new(),
            stamp: 0,
            cavity: Vec::new(),
            stack: Vec::new(),
            starts: HashMap::new(),
            created: Vec::new(),
        };
        let first = first_duplicates(points);
        let order: Vec<u32> = hilbert_order(points)
            .into_iter()
            .filter(|&i| keep(first[i as usize]))
            .collect();
        let seed = t.seed(&order, &first)?;
        for &i in &order {
            if seed.contains(&i) {
                continue;
            }
            if first[i as usize] != i {
                continue;
            }
            t.insert(i)?;
        }
        for (i, &f) in first.iter().enumerate() {
            if f as usize != i && keep(f) {
                t.duplicate_of[i] = f;
            }
        }
        Ok(t)
    }

    /// The vertex each input point became: itself, or the first identical point.
    pub fn duplicate_of(&self) -> &[u32] {
        &self.duplicate_of
    }

    /// The finite triangles, counter-clockwise, in storage order.
    pub fn triangles(&self) -> Vec<[u32; 3]> {
        (0..self.tri.len())
            .filter(|&t| self.alive[t] && !self.tri[t].contains(&INFINITE))
            .map(|t| self.tri[t])
            .collect()
    }

    /// Every live triangle, finite or infinite, renumbered compactly: its vertices and its
    /// neighbours (same conventions as the module documentation).
    pub fn compact(&self) -> (Vec<[u32; 3]>, Vec<[u32; 3]>) {
        let mut id = vec![NONE; self.tri.len()];
        let live: Vec<usize> = (0..self.tri.len()).filter(|&t| self.alive[t]).collect();
        for (new, &t) in live.iter().enumerate() {
            id[t] = new as u32;
        }
        let tri = live.iter().map(|&t| self.tri[t]).collect();
        let adj = live
            .iter()
            .map(|&t| self.adj[t].map(|n| id[n as usize]))
            .collect();
        (tri, adj)
    }

    /// Every live triangle's directed edges: `(a, b)` -> (triangle, slot opposite the edge),
    /// for edges of finite and infinite triangles alike.
    pub fn directed_edges(&self) -> HashMap<(u32, u32), (u32, usize)> {
        let mut map = HashMap::new();
        for t in 0..self.tri.len() {
            if !self.alive[t] {
                continue;
            }
            let v = self.tri[t];
            for k in 0..3 {
                map.insert((v[(k + 1) % 3], v[(k + 2) % 3]), (t as u32, k));
            }
        }
        map
    }

    /// Whether `[a b]` belongs to the Delaunay cover (every Delaunay triangulation contains
    /// it): it is an edge here, and a hull edge or an edge between two triangles that are not
    /// cocircular (exact test). `edges` is [`Self::directed_edges`].
    pub fn in_delaunay_cover(
        &self,
        a: u32,
        b: u32,
        edges: &HashMap<(u32, u32), (u32, usize)>,
    ) -> bool {
        let (Some(&(t, k)), Some(&(u, l))) = (edges.get(&(a, b)), edges.get(&(b, a))) else {
            return false;
        };
        let c = self.tri[t as usize][k];
        let d = self.tri[u as usize][l];
        if c == INFINITE || d == INFINITE {
            return true;
        }
        let p = |i: u32| &self.points[i as usize];
        crate::predicates::incircle(p(a), p(b), p(c), p(d)) != Sign::Zero
    }

    /// The first triangle: three non-collinear points, the earliest in `order`.
    fn seed(&mut self, order: &[u32], first: &[u32]) -> Result<[u32; 3]> {
        let unique: Vec<u32> = order
            .iter()
            .copied()
            .filter(|&i| first[i as usize] == i)
            .collect();
        let p = |i: u32| &self.points[i as usize];
        let (Some(&a), Some(&b)) = (unique.first(), unique.get(1)) else {
            return Err(Error::invalid_input(
                "fewer than 3 distinct points: no triangle can be formed",
            ));
        };
        let Some(&c) = unique[2..]
            .iter()
            .find(|&&c| orient2d(p(a), p(b), p(c)) != Sign::Zero)
        else {
            return Err(Error::invalid_input(
                "all points are collinear: no triangle can be formed",
            ));
        };
        let (a, b) = if orient2d(p(a), p(b), p(c)) == Sign::Positive {
            (a, b)
        } else {
            (b, a)
        };
        let triangles = [
            [a, b, c],
            [c, b, INFINITE],
            [a, c, INFINITE],
            [b, a, INFINITE],
        ];
        for v in triangles {
            self.new_triangle(v);
        }
        self.link_by_edges(&[0, 1, 2, 3]);
        for v in [a, b, c] {
            self.duplicate_of[v as usize] = v;
        }
        Ok([a, b, c])
    }

    /// Links the given triangles to each other across their shared edges.
    fn link_by_edges(&mut self, ts: &[u32]) {
        let mut open: HashMap<(u32, u32), (u32, usize)> = HashMap::new();
        for &t in ts {
            let v = self.tri[t as usize];
            for k in 0..3 {
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                if let Some((u, l)) = open.remove(&(b, a)) {
                    self.adj[t as usize][k] = u;
                    self.adj[u as usize][l] = t;
                } else {
                    open.insert((a, b), (t, k));
                }
            }
        }
    }

    fn new_triangle(&mut self, v: [u32; 3]) -> u32 {
        if let Some(t) = self.free.pop() {
            self.tri[t as usize] = v;
            self.adj[t as usize] = [NONE; 3];
            self.alive[t as usize] = true;
            self.mark[t as usize] = 0;
            t
        } else {
            self.tri.push(v);
            self.adj.push([NONE; 3]);
            self.alive.push(true);
            self.mark.push(0);
            (self.tri.len() - 1) as u32
        }
    }

    fn point(&self, v: u32) -> &[f64; 2] {
        &self.points[v as usize]
    }

    /// Inserts point `i` (not a copy of an inserted point).
    fn insert(&mut self, i: u32) -> Result<()> {
        let start = self.locate(i);
        if !self.in_conflict(start, i) {
            return Err(Error::internal(format!(
                "2D Delaunay: point {i} is not in conflict with the triangle that contains it"
            )));
        }
        self.grow_cavity(start, i);
        self.fill_cavity(i);
        self.duplicate_of[i as usize] = i;
        Ok(())
    }

    /// A triangle containing point `i` (closed), or an infinite triangle whose outside
    /// contains it strictly, by a stochastic visibility walk from the last created triangle.
    fn locate(&mut self, i: u32) -> u32 {
        let p = *self.point(i);
        let mut t = self.hint;
        if t as usize >= self.tri.len() || !self.alive[t as usize] {
            t = (0..self.tri.len() as u32)
                .find(|&t| self.alive[t as usize])
                .unwrap_or(0);
        }
        loop {
            let v = self.tri[t as usize];
            if v.contains(&INFINITE) {
                let k = v.iter().position(|&x| x == INFINITE).unwrap_or(0);
                // Step back into the hull when the point is not outside this edge.
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                if orient2d(self.point(a), self.point(b), &p) == Sign::Positive {
                    return t;
                }
                t = self.adj[t as usize][k];
                continue;
            }
            self.rng ^= self.rng << 13;
            self.rng ^= self.rng >> 17;
            self.rng ^= self.rng << 5;
            let s = (self.rng % 3) as usize;
            let next = (0..3).map(|j| (s + j) % 3).find(|&k| {
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                orient2d(self.point(a), self.point(b), &p) == Sign::Negative
            });
            match next {
                Some(k) => t = self.adj[t as usize][k],
                None => return t,
            }
        }
    }

    /// Whether point `i` is in conflict with triangle `t` (see the module documentation).
    fn in_conflict(&self, t: u32, i: u32) -> bool {
        conflict(self.tri[t as usize], |v| self.point(v), self.point(i))
    }

    /// The triangles in conflict with point `i`, a connected set grown from `start`.
    fn grow_cavity(&mut self, start: u32, i: u32) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.mark.iter_mut().for_each(|m| *m = 0);
            self.stamp = 1;
        }
        self.cavity.clear();
        self.stack.clear();
        self.stack.push(start);
        self.mark[start as usize] = self.stamp;
        while let Some(t) = self.stack.pop() {
            self.cavity.push(t);
            for k in 0..3 {
                let n = self.adj[t as usize][k];
                if self.mark[n as usize] != self.stamp && self.in_conflict(n, i) {
                    self.mark[n as usize] = self.stamp;
                    self.stack.push(n);
                }
            }
        }
    }

    /// Replaces the cavity by the fan from point `i` over its boundary.
    fn fill_cavity(&mut self, i: u32) {
        self.starts.clear();
        self.created.clear();
        let cavity = std::mem::take(&mut self.cavity);
        for &t in &cavity {
            for k in 0..3 {
                let n = self.adj[t as usize][k];
                if self.mark[n as usize] == self.stamp {
                    continue;
                }
                let v = self.tri[t as usize];
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                let new = self.new_triangle([a, b, i]);
                self.adj[new as usize][2] = n;
                let back = self.adj[n as usize]
                    .iter()
                    .position(|&x| x == t)
                    .unwrap_or(0);
                self.adj[n as usize][back] = new;
                self.starts.insert(a, new);
                self.created.push(new);
            }
        }
        for &new in &self.created {
            let b = self.tri[new as usize][1];
            let next = self.starts[&b];
            self.adj[new as usize][0] = next;
            self.adj[next as usize][1] = new;
        }
        for &t in &cavity {
            self.alive[t as usize] = false;
            self.free.push(t);
        }
        self.hint = self.created.last().copied().unwrap_or(self.hint);
        self.cavity = cavity;
    }

    /// Checks the invariants of the module documentation; the error names the first
    /// triangle that breaks one.
    pub fn validate(&self) -> std::result::Result<(), String> {
        for t in 0..self.tri.len() {
            if !self.alive[t] {
                continue;
            }
            let v = self.tri[t];
            if v[0] == v[1] || v[1] == v[2] || v[0] == v[2] {
                return Err(format!("triangle {t} {v:?} repeats a vertex"));
            }
            for k in 0..3 {
                let n = self.adj[t][k] as usize;
                if n >= self.tri.len() || !self.alive[n] {
                    return Err(format!(
                        "triangle {t}: neighbour {k} is not a live triangle"
                    ));
                }
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                let w = self.tri[n];
                let Some(l) = (0..3).find(|&l| w[(l + 1) % 3] == b && w[(l + 2) % 3] == a) else {
                    return Err(format!(
                        "triangles {t} and {n} do not share edge ({a}, {b})"
                    ));
                };
                if self.adj[n][l] as usize != t {
                    return Err(format!(
                        "adjacency of triangles {t} and {n} is not symmetric"
                    ));
                }
                if !v.contains(&INFINITE) && !w.contains(&INFINITE) {
                    let [p, q, r] = v.map(|x| self.point(x));
                    if incircle_sos(p, q, r, self.point(w[l])) == Sign::Positive {
                        return Err(format!(
                            "edge ({a}, {b}) of triangle {t} is not locally Delaunay"
                        ));
                    }
                }
            }
            if let Some(k) = v.iter().position(|&x| x == INFINITE) {
                // The next hull edge (b, c) turns clockwise from (a, b), or goes straight.
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                let n = self.tri[self.adj[t][(k + 1) % 3] as usize];
                let kn = n.iter().position(|&x| x == INFINITE);
                let Some(kn) = kn.filter(|&kn| n[(kn + 1) % 3] == b) else {
                    return Err(format!(
                        "hull edge ({a}, {b}) is not followed by a hull edge"
                    ));
                };
                let c = n[(kn + 2) % 3];
                if orient2d(self.point(a), self.point(b), self.point(c)) == Sign::Positive {
                    return Err(format!("hull is not convex at vertex {b}"));
                }
            }
            if !v.contains(&INFINITE) {
                let [p, q, r] = v.map(|x| self.point(x));
                if orient2d(p, q, r) != Sign::Positive {
                    return Err(format!("triangle {t} {v:?} is not counter-clockwise"));
                }
            }
        }
        let mut used = vec![false; self.points.len()];
        for t in (0..self.tri.len()).filter(|&t| self.alive[t]) {
            for &x in &self.tri[t] {
                if x != INFINITE {
                    used[x as usize] = true;
                }
            }
        }
        if let Some(i) =
            (0..self.points.len()).find(|&i| self.duplicate_of[i] as usize == i && !used[i])
        {
            return Err(format!("vertex {i} is in no triangle"));
        }
        Ok(())
    }
}

/// For each point, the first point (in index order) with the same coordinates.
pub fn first_duplicates(points: &[[f64; 2]]) -> Vec<u32> {
    let key = |p: &[f64; 2]| p.map(|x| if x == 0.0 { 0u64 } else { x.to_bits() });
    let mut seen: HashMap<[u64; 2], u32> = HashMap::with_capacity(points.len());
    points
        .iter()
        .enumerate()
        .map(|(i, p)| *seen.entry(key(p)).or_insert(i as u32))
        .collect()
}

/// Indices of `points` sorted along a Hilbert curve over their bounding box (ties by index),
/// so that consecutive insertions are close and walks are short.
fn hilbert_order(points: &[[f64; 2]]) -> Vec<u32> {
    const BITS: u32 = 16;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let side = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let scale = if side > 0.0 {
        ((1u32 << BITS) - 1) as f64 / side
    } else {
        0.0
    };
    let mut keyed: Vec<(u64, u32)> = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let x = ((p[0] - lo[0]) * scale) as u32;
            let y = ((p[1] - lo[1]) * scale) as u32;
            (hilbert_key(x, y, BITS), i as u32)
        })
        .collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// Distance along the Hilbert curve of order `bits` of the cell `(x, y)`.
fn hilbert_key(mut x: u32, mut y: u32, bits: u32) -> u64 {
    let last = (1u32 << bits) - 1;
    let mut d = 0u64;
    let mut s = 1u32 << (bits - 1);
    while s > 0 {
        let rx = u32::from(x & s > 0);
        let ry = u32::from(y & s > 0);
        d += u64::from(s) * u64::from(s) * u64::from((3 * rx) ^ ry);
        if ry == 0 {
            if rx == 1 {
                x = last - x;
                y = last - y;
            }
            std::mem::swap(&mut x, &mut y);
        }
        s >>= 1;
    }
    d
}

/// Whether `p` is in conflict with the counter-clockwise triangle `v` (one vertex may be
/// [`INFINITE`]), `at` giving the coordinates of its vertices: strictly inside its circle with
/// ties broken by the symbolic perturbation; for an infinite triangle, strictly beyond its
/// hull edge or on the edge's open segment.
pub(super) fn conflict<'a>(v: [u32; 3], at: impl Fn(u32) -> &'a [f64; 2], p: &[f64; 2]) -> bool {
    match v.iter().position(|&x| x == INFINITE) {
        None => {
            let [a, b, c] = v.map(&at);
            incircle_sos(a, b, c, p) == Sign::Positive
        }
        Some(k) => {
            let a = at(v[(k + 1) % 3]);
            let b = at(v[(k + 2) % 3]);
            match orient2d(a, b, p) {
                Sign::Positive => true,
                Sign::Zero => dot_sign(a, b, p) == Sign::Negative,
                Sign::Negative => false,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    //! The output of the triangulation, storage order included, is pinned by digests recorded
    //! from the first implementation: faster versions must return the very same arrays.

    use super::*;

    /// FNV-1a over 32-bit words.
    fn digest(words: impl IntoIterator<Item = u32>) -> u64 {
        words.into_iter().fold(0xcbf2_9ce4_8422_2325, |h, w| {
            (h ^ u64::from(w)).wrapping_mul(0x0000_0100_0000_01b3)
        })
    }

    /// Digests of [`Delaunay2d::triangles`], of [`Delaunay2d::compact`] and of
    /// [`Delaunay2d::duplicate_of`].
    fn digests(t: &Delaunay2d) -> [u64; 3] {
        t.validate().expect("valid triangulation");
        let (tri, adj) = t.compact();
        [
            digest(t.triangles().into_iter().flatten()),
            digest(tri.into_iter().chain(adj).flatten()),
            digest(t.duplicate_of().iter().copied()),
        ]
    }

    /// `n` points uniform in the unit square (splitmix64).
    fn random(n: usize, seed: u64) -> Vec<[f64; 2]> {
        let mut s = seed;
        let mut next = move || {
            s = s.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = s;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..n).map(|_| [next(), next()]).collect()
    }

    /// A grid of `nx` by `ny` points with spacing `h` from `origin`, row by row, then a copy
    /// of every seventh point.
    fn grid(nx: usize, ny: usize, origin: [f64; 2], h: f64) -> Vec<[f64; 2]> {
        let mut points: Vec<[f64; 2]> = (0..nx * ny)
            .map(|i| {
                let (x, y) = ((i % nx) as f64, (i / nx) as f64);
                [origin[0] + h * x, origin[1] + h * y]
            })
            .collect();
        let copies: Vec<[f64; 2]> = points.iter().step_by(7).copied().collect();
        points.extend(copies);
        points
    }

    /// The 12 integer points of the circle of radius 5, then points inside and outside it
    /// on the axes and diagonals, some on the lines of hull edges.
    fn circle_and_lines() -> Vec<[f64; 2]> {
        let mut points = Vec::new();
        for (x, y) in [(5.0, 0.0), (4.0, 3.0), (3.0, 4.0)] {
            for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
                points.push([sx * x, sy * y]);
            }
        }
        for k in -8..=8 {
            let k = f64::from(k);
            points.extend([[k, 0.0], [0.0, k], [k, k], [k, -k], [k, 8.0], [8.0, k]]);
        }
        points
    }

    /// Checks the digests of the triangulation of `points`.
    fn pinned(name: &str, points: &[[f64; 2]], expected: [u64; 3]) {
        let t = Delaunay2d::new(points).expect("triangulation");
        assert_eq!(digests(&t), expected, "{name}");
    }

    #[test]
    fn output_is_pinned() {
        let random_5000 = [
            7266733511350691420,
            3018588063268334660,
            8360184612080058621,
        ];
        pinned("random 5000", &random(5000, 1), random_5000);
        let grid_60x45 = [
            10692263968186970707,
            13903305351444640834,
            11106632706369812180,
        ];
        pinned("grid 60x45", &grid(60, 45, [0.0, 0.0], 1.0), grid_60x45);
        let far_grid = [
            11039683707364735046,
            16231483669408021937,
            15035201911905487843,
        ];
        pinned("far grid", &grid(30, 30, [1e6, -3e5], 0.125), far_grid);
        let circle = [
            12000577562879130945,
            4969806758058743661,
            13965967664374871501,
        ];
        pinned("circle and lines", &circle_and_lines(), circle);
        let tiny = [37743822014092726, 8608560544623792813, 10952987118811563378];
        pinned("tiny random 10", &random(10, 2), tiny);
        let points = grid(25, 25, [0.0, 0.0], 1.0);
        let t = Delaunay2d::of_subset(&points, |i| i % 3 != 1 || i > 600).expect("subset");
        let subset = [
            9299206514313908263,
            14637634767595405173,
            4365311750728550582,
        ];
        assert_eq!(digests(&t), subset, "subset of a grid");
    }
}
