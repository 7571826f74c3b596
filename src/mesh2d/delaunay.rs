//! 2D Delaunay triangulation (DESIGN.md layer 2, the 2D counterpart): Bowyer–Watson insertion
//! in flat arrays, point location by a stochastic visibility walk, an infinite vertex closing
//! the convex hull.
//!
//! Invariants (checked exactly by [`Delaunay2d::validate`]):
//! - every live triangle `t` has three distinct vertices `v`; a finite one is
//!   counter-clockwise (`orient2d > 0`); an infinite one holds [`INFINITE`] once, and with the
//!   infinite vertex at slot `k`, its finite edge `(v[k+1], v[k+2])` has the hull on its right
//!   (the outside strictly on its left);
//! - its neighbour `n[k]` is the live triangle across the edge opposite slot `k`, and that
//!   triangle holds `t` across the same edge (symmetry);
//! - no finite triangle has the opposite vertex of a finite neighbour inside its circumcircle
//!   under [`incircle_sos`] (locally Delaunay, hence globally);
//! - every inserted, non-duplicate point is a vertex.
//!
//! Exact ties (four or more cocircular points) are broken by the symbolic perturbation of
//! [`incircle_sos`], so the triangulation is a function of the point set, not of the
//! insertion order. Points on the line of a hull edge are in conflict with its infinite
//! triangle only when they lie strictly between its ends.
//!
//! The points are inserted in BRIO rounds, each along a Hilbert curve (`brio_rounds`: points
//! along a curve would otherwise make a cavity of every insertion a long fan); the storage
//! order of the triangles (hence of [`Delaunay2d::triangles`] and [`Delaunay2d::compact`])
//! follows from that order, from the walk, from the order in which each cavity is searched
//! and from the reuse of freed slots, last freed first (the tests pin it).
//!
//! Layout and costs: a triangle is one record of its vertices and neighbours; vertices are
//! numbered in insertion order and their coordinates stored in that order, so that what one
//! insertion touches is close in memory; the orientation and in-circle tests first try a
//! static filter whose error bound is fixed by the bounding box ([`BoxFilter2d`]). No hash map
//! and no allocation is on the insertion path: the cavity is searched as a tree, the outcome
//! of each in-circle test used as a number rather than a branch, and the fan is closed
//! through an array indexed by vertex.

use std::collections::HashMap;

use super::exact::{dot_sign, incircle_sos, Adaptive, Predicates2d};
use crate::error::{Error, Result};
use crate::predicates::BoxFilter2d;
use crate::predicates::{orient2d, Sign};

/// The vertex at infinity.
pub const INFINITE: u32 = u32::MAX;

/// No triangle.
const NONE: u32 = u32::MAX;

/// Bits per axis of the Hilbert curve of the insertion order (a multiple of 4, see
/// [`hilbert_key`]).
const HILBERT_BITS: u32 = 16;
const _: () = assert!(HILBERT_BITS.is_multiple_of(4) && HILBERT_BITS <= 16);

/// The first BRIO round has about this many points at least (see [`brio_rounds`]).
const FIRST_ROUND: usize = 64;

/// A triangle of the triangulation: its vertices and its neighbours.
#[derive(Clone, Copy, Debug)]
struct Triangle {
    /// Vertex ids (ranks in the insertion order), counter-clockwise.
    v: [u32; 3],
    /// Neighbour across the edge opposite each slot.
    n: [u32; 3],
}

/// The vertices of a free slot (no live triangle has two infinite vertices).
const FREED: [u32; 3] = [INFINITE; 3];

/// A Delaunay triangulation of a point set given by index into `points`.
///
/// Vertices are numbered internally by insertion order (their coordinates stored in that
/// order, so that the points a walk or a cavity touches are close in memory); every method
/// takes and returns the indices of `points`.
pub struct Delaunay2d<'a> {
    points: &'a [[f64; 2]],
    /// The coordinates of the vertices, in insertion order.
    coords: Vec<[f64; 2]>,
    /// The index in `points` of each vertex.
    label: Vec<u32>,
    /// The triangles, live or freed ([`FREED`]).
    tris: Vec<Triangle>,
    /// Freed slots, reused last freed first.
    free: Vec<u32>,
    /// Where the next walk starts: the last triangle created.
    hint: u32,
    /// The state of the walk's xorshift generator.
    rng: u32,
    /// `duplicate_of[i]`: the vertex point `i` was merged onto (`i` when it is a vertex, NONE
    /// when not inserted).
    duplicate_of: Vec<u32>,
    /// The predicates for the box of the points.
    filter: BoxFilter2d,
    // Scratch of one insertion, kept to avoid allocations.
    /// The triangles in conflict with the point inserted, in search order.
    cavity: Vec<u32>,
    /// Cavity triangles to visit, each with the slot it was reached through.
    stack: Vec<(u32, u32)>,
    /// The boundary edges of the current cavity (cavity triangle, slot) and the slots of
    /// their new triangles.
    boundary: Vec<(u32, u32)>,
    created: Vec<u32>,
    /// `fan[a]`: the new triangle from vertex `a` of the current fan; the infinite vertex's
    /// is last.
    fan: Vec<u32>,
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
        let (lo, hi) = bounding_box(points);
        let (first, unique) = first_along(points, &hilbert_sorted(points, lo, hi));
        let label = brio_rounds(unique.into_iter().filter(|&i| keep(i)).collect());
        // Every insertion adds two triangles, and the slots its cavity frees are reused.
        let capacity = 2 * label.len() + 16;
        let vertices = label.len();
        let mut t = Delaunay2d {
            points,
            coords: label.iter().map(|&i| points[i as usize]).collect(),
            label,
            tris: Vec::with_capacity(capacity),
            free: Vec::new(),
            hint: 0,
            rng: 0x9e37_79b9,
            duplicate_of: first
                .into_iter()
                .map(|f| if keep(f) { f } else { NONE })
                .collect(),
            filter: BoxFilter2d::new(&lo, &hi),
            cavity: Vec::new(),
            stack: Vec::new(),
            boundary: Vec::new(),
            created: Vec::new(),
            fan: vec![NONE; vertices + 1],
        };
        let seed = t.seed()?;
        for v in 0..t.coords.len() as u32 {
            if !seed.contains(&v) {
                t.insert(v);
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
        self.tris
            .iter()
            .filter(|t| !t.v.contains(&INFINITE))
            .map(|t| self.labeled(t.v))
            .collect()
    }

    /// Every live triangle, finite or infinite, renumbered compactly: its vertices and its
    /// neighbours (same conventions as the module documentation).
    pub fn compact(&self) -> (Vec<[u32; 3]>, Vec<[u32; 3]>) {
        let mut id = vec![NONE; self.tris.len()];
        let live: Vec<&Triangle> = self.tris.iter().filter(|t| t.v != FREED).collect();
        let mut next = 0;
        for (t, slot) in self.tris.iter().zip(&mut id) {
            if t.v != FREED {
                *slot = next;
                next += 1;
            }
        }
        let tri = live.iter().map(|t| self.labeled(t.v)).collect();
        let adj = live.iter().map(|t| t.n.map(|n| id[n as usize])).collect();
        (tri, adj)
    }

    /// Every live triangle's directed edges: `(a, b)` -> (triangle, slot opposite the edge),
    /// for edges of finite and infinite triangles alike.
    pub fn directed_edges(&self) -> HashMap<(u32, u32), (u32, usize)> {
        let mut map = HashMap::new();
        for (t, tri) in self.tris.iter().enumerate() {
            if tri.v == FREED {
                continue;
            }
            let v = self.labeled(tri.v);
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
        let c = self.tris[t as usize].v[k];
        let d = self.tris[u as usize].v[l];
        if c == INFINITE || d == INFINITE {
            return true;
        }
        let p = |i: u32| &self.points[i as usize];
        let [c, d] = [c, d].map(|v| self.label[v as usize]);
        crate::predicates::incircle(p(a), p(b), p(c), p(d)) != Sign::Zero
    }

    /// The input indices of vertices `v`.
    fn labeled(&self, v: [u32; 3]) -> [u32; 3] {
        v.map(|x| {
            if x == INFINITE {
                x
            } else {
                self.label[x as usize]
            }
        })
    }

    /// The first triangle: vertices 0 and 1 and the first vertex after them that is not on
    /// their line.
    fn seed(&mut self) -> Result<[u32; 3]> {
        let p = |v: usize| &self.coords[v];
        if self.coords.len() < 2 {
            return Err(Error::invalid_input(
                "fewer than 3 distinct points: no triangle can be formed",
            ));
        }
        let Some(c) = (2..self.coords.len()).find(|&c| orient2d(p(0), p(1), p(c)) != Sign::Zero)
        else {
            return Err(Error::invalid_input(
                "all points are collinear: no triangle can be formed",
            ));
        };
        let (a, b) = if orient2d(p(0), p(1), p(c)) == Sign::Positive {
            (0, 1)
        } else {
            (1, 0)
        };
        let c = c as u32;
        let triangles = [
            [a, b, c],
            [c, b, INFINITE],
            [a, c, INFINITE],
            [b, a, INFINITE],
        ];
        self.tris
            .extend(triangles.map(|v| Triangle { v, n: [NONE; 3] }));
        self.link_by_edges(4);
        Ok([a, b, c])
    }

    /// Links the first `count` triangles to each other across their shared edges.
    fn link_by_edges(&mut self, count: usize) {
        for t in 0..count {
            for u in 0..count {
                let (v, w) = (self.tris[t].v, self.tris[u].v);
                for (k, l) in (0..3).flat_map(|k| (0..3).map(move |l| (k, l))) {
                    if v[(k + 1) % 3] == w[(l + 2) % 3] && v[(k + 2) % 3] == w[(l + 1) % 3] {
                        self.tris[t].n[k] = u as u32;
                    }
                }
            }
        }
    }

    fn point(&self, v: u32) -> &[f64; 2] {
        &self.coords[v as usize]
    }

    /// Inserts vertex `v`.
    fn insert(&mut self, v: u32) {
        let start = self.locate(v);
        self.replace_cavity(start, v);
    }

    /// A triangle containing vertex `i`'s point (closed), or an infinite triangle whose
    /// outside contains it strictly, by a stochastic visibility walk from the last created
    /// triangle. Either is in conflict with the point: a point of a closed triangle other
    /// than its vertices is strictly inside its circumcircle.
    fn locate(&mut self, i: u32) -> u32 {
        let p = *self.point(i);
        let mut t = self.hint;
        if t as usize >= self.tris.len() || self.tris[t as usize].v == FREED {
            t = (0..self.tris.len() as u32)
                .find(|&t| self.tris[t as usize].v != FREED)
                .unwrap_or(0);
        }
        // The triangle the walk came from: the point is on the inner side of the shared edge.
        let mut came_from = NONE;
        loop {
            let Triangle { v, n } = self.tris[t as usize];
            let k = if let Some(k) = v.iter().position(|&x| x == INFINITE) {
                // Step back into the hull when the point is not outside this edge.
                if self.edge_orientation(v, k, &p) == Sign::Positive {
                    return t;
                }
                k
            } else {
                let s = self.next_random() % 3;
                let exit = (0..3).map(|j| (s + j) % 3).find(|&k| {
                    n[k] != came_from && self.edge_orientation(v, k, &p) == Sign::Negative
                });
                match exit {
                    Some(k) => k,
                    None => return t,
                }
            };
            came_from = t;
            t = n[k];
        }
    }

    /// The orientation of the edge of vertices `v` opposite slot `k` and point `p`.
    fn edge_orientation(&self, v: [u32; 3], k: usize, p: &[f64; 2]) -> Sign {
        let (a, b) = (self.point(v[(k + 1) % 3]), self.point(v[(k + 2) % 3]));
        self.filter.orient2d(a, b, p)
    }

    /// The next number of the walk's xorshift generator.
    fn next_random(&mut self) -> usize {
        self.rng ^= self.rng << 13;
        self.rng ^= self.rng >> 17;
        self.rng ^= self.rng << 5;
        self.rng as usize
    }

    /// Replaces the cavity of vertex `i` (the triangles in conflict with it, a connected set
    /// grown from `start`, which is in conflict) by the fan from `i` over its boundary.
    fn replace_cavity(&mut self, start: u32, i: u32) {
        self.search_cavity(start, i);
        self.allocate_fan();
        self.build_fan(i);
    }

    /// The cavity of vertex `i` grown depth first from `start`, in `cavity`, and its boundary
    /// edges (cavity triangle, slot) in `boundary`: each cavity triangle's, once its
    /// neighbours are tested, in slot order.
    ///
    /// The cavity is a disk all of whose vertices are on its boundary (no vertex disappears),
    /// so the adjacency of its triangles is a tree: the only neighbour of a cavity triangle
    /// already in the cavity is the one it was reached from, which is not tested again. The
    /// outcome of a test is used as a number rather than a branch (it is unpredictable).
    fn search_cavity(&mut self, start: u32, i: u32) {
        self.cavity.clear();
        self.boundary.clear();
        let mut search = CavitySearch {
            tris: &self.tris,
            coords: &self.coords,
            filter: &self.filter,
            p: self.coords[i as usize],
            stack: &mut self.stack,
            boundary: &mut self.boundary,
        };
        self.cavity.push(start);
        let n = search.tris[start as usize].n;
        search.test(start, n[0], 0);
        search.test(start, n[1], 1);
        search.test(start, n[2], 2);
        while let Some((t, from)) = search.stack.pop() {
            self.cavity.push(t);
            // The other two slots, in increasing order.
            let n = search.tris[t as usize].n;
            let first = usize::from(from == 0);
            let second = 3 - first - from as usize;
            search.test(t, n[first], first);
            search.test(t, n[second], second);
        }
    }

    /// A slot for each boundary edge's new triangle, in `created`: freed slots first, last
    /// freed first, then slots added at the end.
    fn allocate_fan(&mut self) {
        self.created.clear();
        for _ in 0..self.boundary.len() {
            let slot = self.free.pop().unwrap_or_else(|| {
                self.tris.push(Triangle {
                    v: FREED,
                    n: [NONE; 3],
                });
                (self.tris.len() - 1) as u32
            });
            self.created.push(slot);
        }
    }

    /// The fan from vertex `i`: the new triangle of each boundary edge `(a, b)` is
    /// `[a, b, i]`, in the slot `created` gives it, linked to the outer triangle across the
    /// edge, then to the new triangles from `b` and to `a` (found through `fan`). The
    /// cavity's slots are freed.
    fn build_fan(&mut self, i: u32) {
        let Self {
            tris,
            fan,
            cavity,
            boundary,
            created,
            free,
            hint,
            ..
        } = self;
        let tris = &mut tris[..];
        let infinite = fan.len() - 1;
        let at = |v: u32| (v as usize).min(infinite);
        for (&(t, k), &new) in boundary.iter().zip(created.iter()) {
            let Triangle { v, n } = tris[t as usize];
            let k = k as usize;
            let (a, b, outer) = (v[(k + 1) % 3], v[(k + 2) % 3], n[k]);
            tris[new as usize] = Triangle {
                v: [a, b, i],
                n: [NONE, NONE, outer],
            };
            let back = &mut tris[outer as usize].n;
            back[usize::from(back[1] == t) + 2 * usize::from(back[2] == t)] = new;
            fan[at(a)] = new;
        }
        for &new in created.iter() {
            let next = fan[at(tris[new as usize].v[1])];
            tris[new as usize].n[0] = next;
            tris[next as usize].n[1] = new;
        }
        for &t in cavity.iter() {
            tris[t as usize].v = FREED;
        }
        free.extend_from_slice(cavity);
        *hint = created.last().copied().unwrap_or(*hint);
    }

    /// Checks the invariants of the module documentation; the error names the first
    /// triangle that breaks one (by storage slot; vertices by input index).
    pub fn validate(&self) -> std::result::Result<(), String> {
        for (t, tri) in self.tris.iter().enumerate() {
            if tri.v != FREED {
                self.validate_triangle(t)?;
            }
        }
        let mut used = vec![false; self.coords.len()];
        for tri in self.tris.iter().filter(|t| t.v != FREED) {
            for &x in &tri.v {
                if x != INFINITE {
                    used[x as usize] = true;
                }
            }
        }
        if let Some(v) = used.iter().position(|&u| !u) {
            return Err(format!("vertex {} is in no triangle", self.label[v]));
        }
        if let Some(i) = (0..self.points.len()).find(|&i| {
            let d = self.duplicate_of[i];
            d != NONE && self.points[d as usize] != self.points[i]
        }) {
            return Err(format!("point {i} is merged onto a different point"));
        }
        if self
            .label
            .iter()
            .any(|&i| self.duplicate_of[i as usize] != i)
        {
            return Err("a vertex is merged onto another point".to_string());
        }
        Ok(())
    }

    /// Checks the invariants of live triangle `t`.
    fn validate_triangle(&self, t: usize) -> std::result::Result<(), String> {
        let v = self.tris[t].v;
        let name = self.labeled(v);
        if v[0] == v[1] || v[1] == v[2] || v[0] == v[2] {
            return Err(format!("triangle {t} {name:?} repeats a vertex"));
        }
        for k in 0..3 {
            let n = self.tris[t].n[k] as usize;
            if n >= self.tris.len() || self.tris[n].v == FREED {
                return Err(format!(
                    "triangle {t}: neighbour {k} is not a live triangle"
                ));
            }
            let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
            let w = self.tris[n].v;
            let Some(l) = (0..3).find(|&l| w[(l + 1) % 3] == b && w[(l + 2) % 3] == a) else {
                return Err(format!("triangles {t} and {n} do not share an edge"));
            };
            if self.tris[n].n[l] as usize != t {
                return Err(format!(
                    "adjacency of triangles {t} and {n} is not symmetric"
                ));
            }
            if !v.contains(&INFINITE) && !w.contains(&INFINITE) {
                let [p, q, r] = v.map(|x| self.point(x));
                if incircle_sos(p, q, r, self.point(w[l])) == Sign::Positive {
                    return Err(format!(
                        "edge {k} of triangle {t} {name:?} is not locally Delaunay"
                    ));
                }
            }
        }
        if let Some(k) = v.iter().position(|&x| x == INFINITE) {
            // The next hull edge (b, c) turns clockwise from (a, b), or goes straight.
            let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
            let n = self.tris[self.tris[t].n[(k + 1) % 3] as usize].v;
            let kn = n.iter().position(|&x| x == INFINITE);
            let Some(kn) = kn.filter(|&kn| n[(kn + 1) % 3] == b) else {
                return Err(format!(
                    "hull edge {k} of triangle {t} {name:?} is not followed by a hull edge"
                ));
            };
            let c = n[(kn + 2) % 3];
            if orient2d(self.point(a), self.point(b), self.point(c)) == Sign::Positive {
                return Err(format!(
                    "hull is not convex at vertex {}",
                    self.label[b as usize]
                ));
            }
        } else {
            let [p, q, r] = v.map(|x| self.point(x));
            if orient2d(p, q, r) != Sign::Positive {
                return Err(format!("triangle {t} {name:?} is not counter-clockwise"));
            }
        }
        Ok(())
    }
}

/// The state of [`Delaunay2d::search_cavity`].
struct CavitySearch<'s> {
    tris: &'s [Triangle],
    coords: &'s [[f64; 2]],
    filter: &'s BoxFilter2d,
    /// The point inserted.
    p: [f64; 2],
    /// Cavity triangles to visit, each with the slot it was reached through.
    stack: &'s mut Vec<(u32, u32)>,
    boundary: &'s mut Vec<(u32, u32)>,
}

impl CavitySearch<'_> {
    /// Tests `u`, the neighbour across slot `k` of cavity triangle `t`: in conflict, it is to
    /// be visited; otherwise the edge is on the boundary. The outcome is used as a number
    /// rather than a branch (it is unpredictable).
    #[inline(always)]
    fn test(&mut self, t: u32, u: u32, k: usize) {
        let Triangle { v, n } = self.tris[u as usize];
        let inside = conflict_by(self.filter, v, |x| &self.coords[x as usize], &self.p);
        let back = u32::from(n[1] == t) + 2 * u32::from(n[2] == t);
        self.stack.push((u, back));
        self.stack.truncate(self.stack.len() - usize::from(!inside));
        self.boundary.push((t, k as u32));
        self.boundary
            .truncate(self.boundary.len() - usize::from(inside));
    }
}

/// For each point, the first point (in index order) with the same coordinates.
pub fn first_duplicates(points: &[[f64; 2]]) -> Vec<u32> {
    let (lo, hi) = bounding_box(points);
    first_along(points, &hilbert_sorted(points, lo, hi)).0
}

/// [`first_duplicates`] from `sorted`, the points by Hilbert key (see [`hilbert_sorted`]),
/// and the points that are their own first, in that order: identical points have the same
/// key, so only runs of equal keys need comparing.
fn first_along(points: &[[f64; 2]], sorted: &[u64]) -> (Vec<u32>, Vec<u32>) {
    let coordinates =
        |i: u32| points[i as usize].map(|x| if x == 0.0 { 0u64 } else { x.to_bits() });
    let mut first: Vec<u32> = (0..points.len() as u32).collect();
    let mut unique = Vec::with_capacity(points.len());
    let mut run = Vec::new();
    for same_key in sorted.chunk_by(|x, y| x >> 32 == y >> 32) {
        if let [single] = same_key {
            unique.push(*single as u32);
            continue;
        }
        run.clear();
        run.extend(same_key.iter().map(|&x| (coordinates(x as u32), x as u32)));
        run.sort_unstable();
        for same_point in run.chunk_by(|x, y| x.0 == y.0) {
            for &(_, i) in same_point {
                first[i as usize] = same_point[0].1;
            }
        }
        unique.extend(
            same_key
                .iter()
                .map(|&x| x as u32)
                .filter(|&i| first[i as usize] == i),
        );
    }
    (first, unique)
}

/// The points of `hilbert` (indices, in Hilbert order) in biased randomized insertion order
/// (BRIO, Amenta, Choi and Rote 2003): rounds of geometrically growing size, each in Hilbert
/// order. A point is in the last round with probability 7/8, in the one before with 7/64, and
/// so on, the first round taking the rest (about [`FIRST_ROUND`] to 8 times that many points);
/// the draw is a hash of the point's index, so the order is a function of the indices. The
/// rounds keep the expected cavity sizes of a random order (points along a curve inserted
/// in curve order would each conflict with a long fan of triangles), the Hilbert order within
/// a round keeps walks short.
fn brio_rounds(hilbert: Vec<u32>) -> Vec<u32> {
    let mut last = 0;
    while hilbert.len() >> (3 * (last + 1)) >= FIRST_ROUND {
        last += 1;
    }
    let round = |i: u32| {
        let mut z = u64::from(i).wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        let level = (((z ^ (z >> 31)).trailing_zeros() / 3) as usize).min(last);
        last - level
    };
    let rounds: Vec<u8> = hilbert.iter().map(|&i| round(i) as u8).collect();
    let mut start = vec![0usize; last + 2];
    for &r in &rounds {
        start[r as usize + 1] += 1;
    }
    for r in 1..start.len() {
        start[r] += start[r - 1];
    }
    let mut order = vec![0u32; hilbert.len()];
    for (&i, &r) in hilbert.iter().zip(&rounds) {
        order[start[r as usize]] = i;
        start[r as usize] += 1;
    }
    order
}

/// The smallest box `[lo, hi]` containing `points`.
fn bounding_box(points: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// The indices of `points` along a Hilbert curve over their bounding box (ties by index):
/// consecutive points are close, so that walks from one to the next are short.
pub fn hilbert_order(points: &[[f64; 2]]) -> Vec<u32> {
    let (lo, hi) = bounding_box(points);
    hilbert_sorted(points, lo, hi)
        .into_iter()
        .map(|x| x as u32)
        .collect()
}

/// The points as `key << 32 | index`, `key` their distance along the Hilbert curve of
/// [`HILBERT_BITS`] bits per axis over the square of side the longest side of their bounding
/// box `lo`, `hi`, sorted (by key, then index): the order within each insertion round,
/// consecutive points close so that walks are short.
fn hilbert_sorted(points: &[[f64; 2]], lo: [f64; 2], hi: [f64; 2]) -> Vec<u64> {
    let side = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let scale = if side > 0.0 {
        ((1u32 << HILBERT_BITS) - 1) as f64 / side
    } else {
        0.0
    };
    let keyed: Vec<u64> = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let x = ((p[0] - lo[0]) * scale) as u32;
            let y = ((p[1] - lo[1]) * scale) as u32;
            u64::from(hilbert_key(x, y)) << 32 | i as u64
        })
        .collect();
    radix_sort_by_high_half(keyed)
}

/// `items` sorted by their high 32 bits, stably: a least-significant-digit radix sort in
/// passes of 8 bits, skipping the digits every item shares.
fn radix_sort_by_high_half(mut items: Vec<u64>) -> Vec<u64> {
    let mut counts = [[0usize; 256]; 4];
    for &x in &items {
        for (d, count) in counts.iter_mut().enumerate() {
            count[digit(x, d)] += 1;
        }
    }
    let mut out = vec![0u64; items.len()];
    for (d, count) in counts.iter().enumerate() {
        if count.contains(&items.len()) {
            continue;
        }
        let mut start = [0usize; 256];
        for b in 1..256 {
            start[b] = start[b - 1] + count[b - 1];
        }
        for &x in &items {
            let b = digit(x, d);
            out[start[b]] = x;
            start[b] += 1;
        }
        std::mem::swap(&mut items, &mut out);
    }
    items
}

/// Digit `d` (of 8 bits, from the least significant) of the high half of `x`.
#[inline]
fn digit(x: u64, d: usize) -> usize {
    (x >> (32 + 8 * d)) as usize & 0xff
}

/// Distance along the Hilbert curve of order [`HILBERT_BITS`] of the cell `(x, y)` (each
/// below `2^HILBERT_BITS`), four levels at a time by [`HILBERT_STEPS`].
fn hilbert_key(x: u32, y: u32) -> u32 {
    let mut d = 0u32;
    let mut state = 0usize;
    for shift in (0..HILBERT_BITS).step_by(4).rev() {
        let cell = ((x >> shift) as usize & 0xf) << 4 | ((y >> shift) as usize & 0xf);
        let step = HILBERT_STEPS[state << 8 | cell];
        d = d << 8 | u32::from(step & 0xff);
        state = usize::from(step >> 8);
    }
    d
}

/// Four levels of the Hilbert curve at once: entry `state << 8 | x << 4 | y`, for 4 bits of
/// `x` and of `y` (the next levels, most significant first) in the frame `state`, holds the
/// 4 base-4 digits of the distance (low byte) and the frame of the levels after (above).
const HILBERT_STEPS: [u16; 1024] = hilbert_steps();

/// The table [`HILBERT_STEPS`]. The frame of a level is the transformation of the cell
/// coordinates accumulated by the levels before it: bit 0 swaps `x` and `y`, bit 1
/// complements both. At each level, with `rx` and `ry` the transformed bits, the digit is
/// `3 rx ^ ry`; in the lower half (`ry = 0`) the curve turns: `x` and `y` are swapped, and
/// complemented first in the lower right quadrant (`rx = 1`).
const fn hilbert_steps() -> [u16; 1024] {
    let mut table = [0u16; 1024];
    let mut entry = 0;
    while entry < 1024 {
        let mut frame = entry >> 8;
        let mut digits = 0;
        let mut level = 4;
        while level > 0 {
            level -= 1;
            let bx = (entry >> (4 + level)) & 1;
            let by = (entry >> level) & 1;
            let (swap, complement) = (frame & 1, frame >> 1);
            let rx = if swap == 1 { by } else { bx } ^ complement;
            let ry = if swap == 1 { bx } else { by } ^ complement;
            digits = digits << 2 | ((3 * rx) ^ ry);
            if ry == 0 {
                frame ^= 1 | (rx << 1);
            }
        }
        table[entry] = (frame << 8 | digits) as u16;
        entry += 1;
    }
    table
}

/// Whether `p` is in conflict with the counter-clockwise triangle `v` (one vertex may be
/// [`INFINITE`]), `at` giving the coordinates of its vertices: strictly inside its circle with
/// ties broken by the symbolic perturbation; for an infinite triangle, strictly beyond its
/// hull edge or on the edge's open segment.
pub(super) fn conflict<'a>(v: [u32; 3], at: impl Fn(u32) -> &'a [f64; 2], p: &[f64; 2]) -> bool {
    conflict_by(&Adaptive, v, at, p)
}

/// [`conflict`] decided by `predicates`: the usual finite case inline, the infinite one
/// apart.
#[inline(always)]
fn conflict_by<'a>(
    predicates: &impl Predicates2d,
    v: [u32; 3],
    at: impl Fn(u32) -> &'a [f64; 2],
    p: &[f64; 2],
) -> bool {
    // One test (vertex ids are below INFINITE).
    if v[0].max(v[1]).max(v[2]) != INFINITE {
        let [a, b, c] = v.map(&at);
        predicates.incircle_sos(a, b, c, p) == Sign::Positive
    } else {
        infinite_conflict(predicates, v, at, p)
    }
}

/// [`conflict`] for an infinite triangle `v`.
#[inline(never)]
fn infinite_conflict<'a>(
    predicates: &impl Predicates2d,
    v: [u32; 3],
    at: impl Fn(u32) -> &'a [f64; 2],
    p: &[f64; 2],
) -> bool {
    let k = usize::from(v[1] == INFINITE) + 2 * usize::from(v[2] == INFINITE);
    let a = at(v[(k + 1) % 3]);
    let b = at(v[(k + 2) % 3]);
    match predicates.orient2d(a, b, p) {
        Sign::Positive => true,
        Sign::Zero => dot_sign(a, b, p) == Sign::Negative,
        Sign::Negative => false,
    }
}

#[cfg(test)]
mod tests {
    //! The output of the triangulation, storage order included, is pinned by digests (recorded
    //! when the insertion order became BRIO rounds): faster versions must return the very same
    //! arrays.

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

    /// The distance along the Hilbert curve of order 16 of the cell `(x, y)`, one level at a
    /// time (Wikipedia's `xy2d`).
    fn hilbert_key_by_levels(mut x: u32, mut y: u32) -> u32 {
        let last = (1u32 << 16) - 1;
        let mut d = 0;
        let mut s = 1u32 << 15;
        while s > 0 {
            let rx = u32::from(x & s > 0);
            let ry = u32::from(y & s > 0);
            d += s * s * ((3 * rx) ^ ry);
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

    #[test]
    fn hilbert_keys_four_levels_at_a_time() {
        let cells = random(20000, 3)
            .into_iter()
            .map(|p| p.map(|c| (c * 65536.0) as u32));
        let corners = [0, 1, 15, 16, 255, 256, 65534, 65535];
        let corners = corners.iter().flat_map(|&x| corners.map(|y| [x, y]));
        for [x, y] in cells.chain(corners) {
            assert_eq!(hilbert_key(x, y), hilbert_key_by_levels(x, y), "({x}, {y})");
        }
    }

    #[test]
    fn output_is_pinned() {
        let random_5000 = [
            18175973464611838678,
            13645086053628140430,
            8360184612080058621,
        ];
        pinned("random 5000", &random(5000, 1), random_5000);
        let grid_60x45 = [
            3073711055166546631,
            17021012198431613808,
            11106632706369812180,
        ];
        pinned("grid 60x45", &grid(60, 45, [0.0, 0.0], 1.0), grid_60x45);
        let far_grid = [
            10572167537825115336,
            12058789718774953637,
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
