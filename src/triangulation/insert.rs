//! Bowyer–Watson insertion of one point: walk, conflict cavity, cone over its boundary.
//!
//! The cavity is found by a graph search (a stack, so depth-first) from the located
//! tetrahedron, with a one-byte mark per tetrahedron (in conflict / tested, not in conflict)
//! that the filling clears again: the marked tetrahedra are exactly the cavity and its outer
//! neighbours. The new tetrahedra reuse the cavity's slots and are glued to each other through
//! a small open-addressing table keyed by the cavity-boundary edges: the two new facets that
//! contain `p` and the boundary edge `{x, y}` meet there. Nothing is allocated per insertion
//! once the scratch buffers have grown to the largest cavity.

use super::edge_table::EdgeTable;
use super::tets::{FACE, INFINITE};
use super::{PointState, Triangulation};
use crate::error::{Error, Result};
use crate::predicates::{
    incircle_coplanar_sos, power_test_coplanar_sos, power_test_sos, Point, Sign, WeightedPoint,
};

/// Conflict marks of the insertion under way; every mark is cleared before the next one.
const UNMARKED: u8 = 0;
const IN_CONFLICT: u8 = 1;
const NOT_IN_CONFLICT: u8 = 2;

/// Reused buffers of the insertion.
#[derive(Default)]
pub struct Scratch {
    stack: Vec<u32>,
    pub(super) cavity: Vec<u32>,
    /// Boundary facets as (new vertex quadruple, outer facet `4*t'+j`, local index of p).
    pub(super) boundary: Vec<([u32; 4], u32, u8)>,
    pub(super) new_tets: Vec<u32>,
    edges: EdgeTable,
}

/// Where a walk ended.
pub(super) enum Located {
    /// A tetrahedron in conflict with the point.
    Conflict(u32),
    /// The point coincides with this vertex (Delaunay triangulations only).
    Duplicate(u32),
    /// The point's power cell is empty (regular triangulations only).
    Hidden,
}

impl Triangulation<'_> {
    /// Inserts input point `p`.
    pub(super) fn insert(&mut self, p: u32) -> Result<()> {
        let state = match self.locate(p)? {
            Located::Duplicate(w) => PointState::Duplicate(self.input_index(w)),
            Located::Hidden => PointState::Hidden,
            Located::Conflict(t0) => {
                self.find_cavity(&[t0], p);
                self.fill_cavity(p)?;
                PointState::Inserted
            }
        };
        self.state[p as usize] = state;
        Ok(())
    }

    /// Visibility walk from the hint toward `p`, then the duplicate and hidden checks.
    pub(super) fn locate(&mut self, p: u32) -> Result<Located> {
        let q = *self.point(p);
        let mut t = self.hint;
        if let Some(k) = self.tets.infinite_position(t) {
            if self.orient_with(t, k, &q) == Sign::Positive {
                return Ok(Located::Conflict(t));
            }
            t = self.tets.neighbor(t, k);
        }
        let limit = 64 + 4 * self.tets.slots();
        let mut previous = u32::MAX;
        let mut steps = 0;
        'walk: loop {
            steps += 1;
            if steps > limit {
                let i = self.input_index(p);
                return Err(Error::internal(format!(
                    "the walk toward point {i} does not end"
                )));
            }
            self.rng ^= self.rng << 13;
            self.rng ^= self.rng >> 17;
            self.rng ^= self.rng << 5;
            let start = self.rng as usize;
            for r in 0..4 {
                let i = (start + r) & 3;
                let next = self.tets.neighbor(t, i);
                if next == previous || self.orient_with(t, i, &q) != Sign::Negative {
                    continue;
                }
                previous = t;
                t = next;
                if self.tets.infinite_position(t).is_some() {
                    return Ok(Located::Conflict(t));
                }
                continue 'walk;
            }
            break;
        }
        self.classify_in(t, p)
    }

    /// `p` lies in the closed finite tetrahedron `t`: duplicate, hidden, or in conflict.
    fn classify_in(&self, t: u32, p: u32) -> Result<Located> {
        // Exact copies of weighted points are set aside before insertion: a weighted point at a
        // vertex's position has another weight, and the power test decides between them.
        if !self.is_regular() {
            let q = self.point(p);
            if let Some(w) = self
                .tets
                .vertices(t)
                .into_iter()
                .find(|&w| self.point(w) == q)
            {
                return Ok(Located::Duplicate(w));
            }
        }
        if self.in_conflict(t, p) {
            Ok(Located::Conflict(t))
        } else if self.is_regular() {
            Ok(Located::Hidden)
        } else {
            let (i, v) = (self.input_index(p), self.tets.vertices(t));
            Err(Error::internal(format!(
                "point {i} lies in tetrahedron {v:?} but is not in conflict with it"
            )))
        }
    }

    /// Orientation of tetrahedron `t` with its vertex `i` replaced by `q`: negative when `q`
    /// is strictly beyond facet `i`.
    #[inline]
    pub(super) fn orient_with(&self, t: u32, i: usize, q: &Point) -> Sign {
        let v = self.tets.vertices(t);
        let pt = |k: usize| if k == i { q } else { self.point(v[k]) };
        self.filter.orient3d(pt(0), pt(1), pt(2), pt(3))
    }

    /// Whether `p` is in conflict with tetrahedron `t` (perturbed, never a tie).
    #[inline]
    pub(super) fn in_conflict(&self, t: u32, p: u32) -> bool {
        let v = self.tets.vertices(t);
        let q = self.point(p);
        match v.iter().position(|&x| x == INFINITE) {
            None => self.finite_conflict(v, p),
            Some(k) => match self.orient_with(t, k, q) {
                Sign::Positive => true,
                Sign::Negative => false,
                Sign::Zero => self.in_conflict_coplanar(FACE[k].map(|j| v[j]), p),
            },
        }
    }

    /// Whether `p` is in conflict with the finite, positively oriented tetrahedron `v` (its
    /// vertices need not form a tetrahedron of this triangulation).
    #[inline]
    pub(super) fn finite_conflict(&self, v: [u32; 4], p: u32) -> bool {
        if self.is_regular() {
            let w = v.map(|x| self.weighted(x));
            power_test_sos(&w[0], &w[1], &w[2], &w[3], &self.weighted(p)) == Sign::Positive
        } else {
            let [a, b, c, d] = v.map(|x| self.point(x));
            self.filter.insphere_sos(a, b, c, d, self.point(p)) == Sign::Positive
        }
    }

    /// `p` is coplanar with the hull facet `f`: conflict iff inside its (power) circle.
    fn in_conflict_coplanar(&self, f: [u32; 3], p: u32) -> bool {
        if self.is_regular() {
            let [a, b, c] = f.map(|x| self.weighted(x));
            power_test_coplanar_sos(&a, &b, &c, &self.weighted(p)) == Sign::Positive
        } else {
            let [a, b, c] = f.map(|x| self.point(x));
            incircle_coplanar_sos(a, b, c, self.point(p)) == Sign::Positive
        }
    }

    #[inline]
    fn weighted(&self, v: u32) -> WeightedPoint {
        let p = self.point(v);
        [p[0], p[1], p[2], self.weights[v as usize]]
    }

    /// Search of the tetrahedra in conflict with `p`, starting from `seeds` (in conflict,
    /// forming a connected set). Fills `scratch.cavity` and `scratch.boundary`.
    pub(super) fn find_cavity(&mut self, seeds: &[u32], p: u32) {
        let mut s = std::mem::take(&mut self.scratch);
        s.cavity.clear();
        s.boundary.clear();
        s.stack.clear();
        for &t0 in seeds {
            self.tets.mark[t0 as usize] = IN_CONFLICT;
            s.cavity.push(t0);
            s.stack.push(t0);
        }
        while let Some(t) = s.stack.pop() {
            for i in 0..4 {
                let facet = self.tets.glued(t, i);
                let nb = facet >> 2;
                let inside = match self.tets.mark[nb as usize] {
                    IN_CONFLICT => true,
                    NOT_IN_CONFLICT => false,
                    _ => {
                        let c = self.in_conflict(nb, p);
                        self.tets.mark[nb as usize] = if c { IN_CONFLICT } else { NOT_IN_CONFLICT };
                        if c {
                            s.cavity.push(nb);
                            s.stack.push(nb);
                        }
                        c
                    }
                };
                if !inside {
                    let mut v = self.tets.vertices(t);
                    v[i] = p;
                    s.boundary.push((v, facet, i as u8));
                }
            }
        }
        self.scratch = s;
    }

    /// Whether tetrahedron `t` is in the cavity under way.
    pub(super) fn marked_in_conflict(&self, t: u32) -> bool {
        self.tets.mark[t as usize] == IN_CONFLICT
    }

    /// Clears the marks [`Self::find_cavity`] left (on the cavity and its outer neighbours).
    pub(super) fn clear_marks(&mut self) {
        for &t in &self.scratch.cavity {
            self.tets.mark[t as usize] = UNMARKED;
        }
        for &(_, outer, _) in &self.scratch.boundary {
            self.tets.mark[(outer >> 2) as usize] = UNMARKED;
        }
    }

    /// Replaces the cavity by the cone from `p` over its boundary.
    pub(super) fn fill_cavity(&mut self, p: u32) -> Result<()> {
        let mut s = std::mem::take(&mut self.scratch);
        let nb = s.boundary.len();
        s.new_tets.clear();
        for k in 0..nb {
            let t = match s.cavity.get(k) {
                Some(&t) => t,
                None => self.tets.allocate()?,
            };
            s.new_tets.push(t);
        }
        for &t in s.cavity.iter().skip(nb) {
            self.tets.kill(t);
        }
        s.edges.reset(3 * nb / 2 + 1);
        let mut glued = 0;
        for (k, &(verts, outer, i)) in s.boundary.iter().enumerate() {
            let t = s.new_tets[k];
            self.tets.set(t, verts);
            self.tets.mark[t as usize] = UNMARKED;
            self.tets.mark[(outer >> 2) as usize] = UNMARKED;
            self.tets.glue(4 * t + u32::from(i), outer);
            for j in 0..4 {
                if j == i as usize {
                    continue;
                }
                // Facet j contains p and the edge {x, y} of the boundary facet.
                let k = (0..4).find(|&k| k != i as usize && k != j).unwrap_or(0);
                let (x, y) = (verts[k], verts[6 - i as usize - j - k]);
                let facet = 4 * t + j as u32;
                if let Some(other) = s.edges.take_or_insert(x, y, facet) {
                    self.tets.glue(facet, other);
                    glued += 1;
                }
            }
        }
        // Every boundary edge is shared by exactly two boundary facets.
        let unmatched = 2 * glued != 3 * nb;
        self.hint = *s.new_tets.last().unwrap_or(&self.hint);
        self.scratch = s;
        if unmatched {
            let i = self.input_index(p);
            return Err(Error::internal(format!(
                "the cavity of point {i} is not a topological ball"
            )));
        }
        Ok(())
    }
}
