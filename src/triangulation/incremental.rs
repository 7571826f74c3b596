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
    /// The weighted point's power cell would be empty (regular triangulations); nothing is
    /// marked.
    Hidden,
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
        self.find_conflicts_weighted(q, 0.0, near)
    }

    /// [`Self::find_conflicts`] for a point of weight `w` (regular triangulations; ignored in
    /// Delaunay ones).
    pub fn find_conflicts_weighted(&mut self, q: Point, w: f64, near: u32) -> Result<Conflicts> {
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
        if self.is_regular() {
            self.weights.push(w);
        }
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
                    return Ok(Conflicts::Hidden);
                }
            }
        };
        self.find_cavity(&[start], p);
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

    /// Turns the triangulation into the regular triangulation of its vertices with weight 0
    /// (the same triangulation), so that vertices can be re-weighted (sliver exudation).
    pub fn make_regular(&mut self) {
        if self.weights.is_empty() {
            self.weights = vec![0.0; self.points.len()];
        }
    }

    /// The weight of vertex `v` (0 in a Delaunay triangulation).
    pub fn weight(&self, v: u32) -> f64 {
        self.weights.get(v as usize).copied().unwrap_or(0.0)
    }

    /// Marks the cavity of raising the weight of vertex `v`, a vertex of tetrahedron `t`, to
    /// `w` (above its weight; regular triangulations only): the tetrahedra incident to `v` and
    /// every tetrahedron in conflict with the heavier copy of `v`. [`Self::cavity_boundary`]
    /// and [`Self::cavity`] then describe the change; [`Self::commit_reweight`] applies it,
    /// [`Self::abandon`] forgets it.
    pub fn find_reweight_conflicts(&mut self, v: u32, t: u32, w: f64) -> Result<()> {
        let heavier = w > self.weight(v);
        if !self.is_regular() || !heavier || !self.tets.vertices(t).contains(&v) {
            return Err(Error::internal(format!(
                "cannot raise the weight of vertex {v} to {w} from tetrahedron {t}"
            )));
        }
        let star = self.star(v, t);
        let q = self.points.len() as u32;
        self.points.push(self.points[v as usize]);
        self.weights.push(w);
        self.order.push(q);
        self.state.push(PointState::Pending);
        self.find_cavity(&star, q);
        Ok(())
    }

    /// Applies the pending re-weighting of `v`: the heavier copy replaces it (`v` is removed
    /// from the point set); returns the copy's vertex id.
    pub fn commit_reweight(&mut self, v: u32) -> Result<u32> {
        let q = self.commit()?;
        self.state[v as usize] = PointState::Removed;
        Ok(q)
    }

    /// The tetrahedra incident to vertex `v`, found from `t` (one of them) across the facets
    /// that contain `v`.
    pub fn star(&self, v: u32, t: u32) -> Vec<u32> {
        let mut star = vec![t];
        let mut k = 0;
        while k < star.len() {
            let s = star[k];
            k += 1;
            for (i, &x) in self.tets.vertices(s).iter().enumerate() {
                let u = self.tets.neighbor(s, i);
                if x != v && !star.contains(&u) {
                    star.push(u);
                }
            }
        }
        star
    }

    /// Whether `p` lies in the box every vertex must lie in.
    pub fn in_bounds(&self, p: &Point) -> bool {
        inside(p, &self.bounds.0, &self.bounds.1) && p.iter().all(|c| c.is_finite())
    }

    /// The tetrahedra in conflict with the pending point.
    pub fn cavity(&self) -> &[u32] {
        &self.scratch.cavity
    }

    /// Whether tetrahedron `t` is in the pending cavity.
    pub fn in_cavity(&self, t: u32) -> bool {
        self.marked_in_conflict(t)
    }

    /// The facets `4*t+j` of the tetrahedra outside the cavity that bound it.
    pub fn cavity_boundary(&self) -> impl Iterator<Item = u32> + '_ {
        self.scratch.boundary.iter().map(|&(_, outer, _)| outer)
    }

    /// The tetrahedra a commit would create, as (vertices, the outer facet `4*t+j` it is
    /// glued to, the local position of the new vertex); [`Self::created`] lists them in
    /// this order after the commit.
    pub fn cavity_cone(&self) -> &[([u32; 4], u32, u8)] {
        &self.scratch.boundary
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
        if self.weights.len() > self.points.len() {
            self.weights.pop();
        }
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
