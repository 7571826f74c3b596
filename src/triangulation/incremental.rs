//! A Delaunay triangulation that grows one point at a time, for Delaunay refinement
//! (Rineau's thesis §5.1: a refinement level tests a point's conflict zone before it commits
//! to inserting the point).
//!
//! Insertion is split in two: [`Triangulation::find_conflicts`] locates the point and marks
//! its conflict cavity without changing the triangulation; the caller inspects the cavity
//! ([`Triangulation::cavity`], [`Triangulation::cavity_boundary`]) and then either
//! [`Triangulation::commit`]s — the cavity is replaced by the cone from the new vertex,
//! whose tetrahedra [`Triangulation::created`] lists — or [`Triangulation::abandon`]s, which
//! clears the marks and forgets the point.
//!
//! Invariants: between two insertions no tetrahedron is marked; every vertex lies in the box
//! given at construction (the predicates' filter bounds are derived from it).

use super::tets::{Tets, INFINITE};
use super::{bounding_box, sort, validate_points, PointState, Triangulation};
use crate::error::{Error, Result};
use crate::predicates::{lex_cmp, BoxFilter, Point};

/// The outcome of [`Triangulation::find_conflicts`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Conflicts {
    /// The cavity is marked; `commit` or `abandon` must follow.
    Cavity,
    /// The point coincides with this vertex; nothing is marked.
    Duplicate(u32),
}

impl Triangulation<'static> {
    /// A Delaunay triangulation of `initial` (at least 4 affinely independent points, exact
    /// copies dropped) that further points of the box `lo..=hi` may be inserted into.
    /// Vertex ids are insertion positions: `initial` is inserted in spatial order.
    pub fn growable(mut initial: Vec<Point>, lo: &Point, hi: &Point) -> Result<Self> {
        initial.sort_unstable_by(lex_cmp);
        initial.dedup();
        validate_points(&initial, None)?;
        if let Some(p) = initial.iter().find(|p| !inside(p, lo, hi)) {
            return Err(Error::internal(format!(
                "initial point {p:?} lies outside the box {lo:?}..{hi:?}"
            )));
        }
        let (blo, bhi) = bounding_box(&initial);
        let order = sort::brio_order(&initial, &blo, &bhi);
        let points: Vec<Point> = order.iter().map(|&i| initial[i as usize]).collect();
        let n = points.len();
        let mut t = Triangulation {
            filter: BoxFilter::new(lo, hi),
            input: &[],
            order: (0..n as u32).collect(),
            points,
            weights: Vec::new(),
            tets: Tets::with_capacity(7 * n + 16)?,
            state: vec![PointState::Pending; n],
            hint: 0,
            rng: 0x9e37_79b9,
            scratch: Default::default(),
            bounds: (*lo, *hi),
        };
        t.insert_all()?;
        Ok(t)
    }

    /// Locates `q` (starting from tetrahedron `near`, a good guess saves the walk) and marks
    /// the tetrahedra in conflict with it. On `Cavity`, exactly one of [`Self::commit`] or
    /// [`Self::abandon`] must follow before anything else changes the triangulation.
    pub fn find_conflicts(&mut self, q: Point, near: u32) -> Result<Conflicts> {
        if !inside(&q, &self.bounds.0, &self.bounds.1) || !q.iter().all(|c| c.is_finite()) {
            return Err(Error::internal(format!(
                "refinement point {q:?} lies outside the box {:?}",
                self.bounds
            )));
        }
        let p = self.points.len() as u32;
        self.points.push(q);
        self.order.push(p);
        self.state.push(PointState::Pending);
        if self.tets.is_live(near) {
            self.hint = near;
        }
        let start = if self.tets.is_live(near) && self.in_conflict(near, p) {
            near
        } else {
            match self.locate(p)? {
                super::insert::Located::Conflict(t) => t,
                super::insert::Located::Duplicate(w) => {
                    self.forget_point();
                    return Ok(Conflicts::Duplicate(w));
                }
                super::insert::Located::Hidden => {
                    self.forget_point();
                    return Err(Error::internal("a Delaunay point cannot be hidden"));
                }
            }
        };
        self.find_cavity(start, p);
        // A copy of a vertex lies on the spheres of its tetrahedra: the perturbation may put
        // some of them in conflict, so the cavity's vertices are checked for copies.
        let copy = self.scratch.cavity.iter().find_map(|&t| {
            self.tets
                .vertices(t)
                .into_iter()
                .find(|&w| w != INFINITE && w != p && self.points[w as usize] == q)
        });
        if let Some(w) = copy {
            self.abandon();
            return Ok(Conflicts::Duplicate(w));
        }
        Ok(Conflicts::Cavity)
    }

    /// The tetrahedra in conflict with the pending point.
    pub fn cavity(&self) -> &[u32] {
        &self.scratch.cavity
    }

    /// The facets `4*t+j` of the tetrahedra outside the cavity that bound it.
    pub fn cavity_boundary(&self) -> impl Iterator<Item = u32> + '_ {
        self.scratch.boundary.iter().map(|&(_, outer, _)| outer)
    }

    /// Inserts the pending point; returns its vertex id.
    pub fn commit(&mut self) -> Result<u32> {
        let p = self.points.len() as u32 - 1;
        self.fill_cavity(p)?;
        self.state[p as usize] = PointState::Inserted;
        Ok(p)
    }

    /// The tetrahedra created by the last commit (they may reuse slots of the cavity).
    pub fn created(&self) -> &[u32] {
        &self.scratch.new_tets
    }

    /// Clears the marks of the pending point's cavity and forgets the point.
    pub fn abandon(&mut self) {
        self.clear_marks();
        self.forget_point();
    }

    fn forget_point(&mut self) {
        self.points.pop();
        self.order.pop();
        self.state.pop();
    }
}

impl Triangulation<'_> {
    /// The live tetrahedra and their adjacency.
    pub fn tets(&self) -> &Tets {
        &self.tets
    }

    /// Coordinates of vertex `v` (an internal id: insertion position).
    #[inline]
    pub fn vertex(&self, v: u32) -> &Point {
        self.point(v)
    }

    /// Number of vertex ids handed out (inserted or not).
    pub fn vertex_count(&self) -> usize {
        self.points.len()
    }
}

fn inside(p: &Point, lo: &Point, hi: &Point) -> bool {
    (0..3).all(|k| lo[k] <= p[k] && p[k] <= hi[k])
}
