//! The refinement levels (thesis ch. 5: a chain of levels, each with its own queue of bad
//! elements; CGAL's `Mesher_level`). A level proposes a refinement point for its worst
//! element; every higher level then checks the point's conflict zone and answers
//! [`Verdict::Accepted`], [`Verdict::Rejected`] (the point encroaches an element that level
//! refines first; the element is reconsidered later) or [`Verdict::RejectedForever`] (the
//! element is dropped). After an insertion every level updates its queue from the new
//! tetrahedra only. A curve-edge level slots in above the facet level unchanged.
//!
//! - [`FacetLevel`]: rules R1 (a restricted facet with a vertex off the surface) and R2 (a
//!   restricted facet failing the angle, size or distance bound); the point is the center
//!   of the facet's surface Delaunay ball. It rejects a lower level's point that lies
//!   inside a restricted facet's surface Delaunay ball, and queues that facet (R3.2).
//! - [`CellLevel`]: rule R3, a cell in the complex failing the radius-edge or size bound, or a
//!   surface sliver (three or four vertices on the surface, see `criteria`); the point is its
//!   circumcenter.

use super::complex::{Complex, SURFACE, VOLUME};
use super::queue::{Element, Queue};
use crate::criteria::{Badness, Criteria, TOPOLOGY};
use crate::error::Result;
use crate::geometry::dist2;
use crate::predicates::Point;

/// What a level says of a point proposed by a lower level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    Accepted,
    Rejected,
    RejectedForever,
}

/// A refinement point: where, a tetrahedron near it, and the dimension of the new vertex.
pub struct Proposal {
    pub point: Point,
    pub near: u32,
    pub dimension: i8,
}

pub trait Level {
    /// The next element that still exists and still needs refinement.
    fn next(&mut self, c: &Complex, criteria: &Criteria) -> Result<Option<Element>>;

    fn refinement_point(&self, c: &Complex, e: &Element) -> Proposal;

    /// Whether this level accepts `p`, whose conflict zone is pending in `c`.
    fn check_refinement_point(&mut self, c: &Complex, p: &Point) -> Verdict;

    /// Queues the bad elements among those the last insertion created.
    fn after_insertion(&mut self, c: &Complex, criteria: &Criteria) -> Result<()>;

    /// Puts back an element whose point was rejected.
    fn requeue(&mut self, e: Element);

    /// Entries queued (stale ones included), for progress reports.
    fn queued(&self) -> usize;
}

/// Priority class of a facet whose ball a lower level's point falls in: refined first.
const ENCROACHED: Badness = Badness {
    class: TOPOLOGY + 1,
    ratio: 0.0,
};

#[derive(Default)]
pub struct FacetLevel {
    queue: Queue,
}

impl FacetLevel {
    fn badness(c: &Complex, criteria: &Criteria, facet: u32) -> Result<Option<Badness>> {
        let Some(ball) = c.ball(facet) else {
            return Ok(None);
        };
        let v = c.facet_vertices(facet >> 2, (facet & 3) as usize);
        let on_surface = v.iter().all(|&x| c.dimension(x) == SURFACE);
        let p = v.map(|x| c.tri.vertex(x));
        criteria.facet(p, &ball.center, ball.radius2, ball.labels, on_surface)
    }

    fn element(c: &Complex, facet: u32, badness: Badness) -> Element {
        Element::new(facet, c.stamp(facet >> 2), badness)
    }
}

impl Level for FacetLevel {
    fn next(&mut self, c: &Complex, criteria: &Criteria) -> Result<Option<Element>> {
        while let Some(e) = self.queue.pop() {
            if !c.is_current(e.handle >> 2, e.stamp) || c.ball(e.handle).is_none() {
                continue;
            }
            if e.class() == ENCROACHED.class || Self::badness(c, criteria, e.handle)?.is_some() {
                return Ok(Some(e));
            }
        }
        Ok(None)
    }

    fn refinement_point(&self, c: &Complex, e: &Element) -> Proposal {
        let ball = c.ball(e.handle).copied();
        Proposal {
            point: ball.map_or([f64::NAN; 3], |b| b.center),
            near: e.handle >> 2,
            dimension: SURFACE,
        }
    }

    fn check_refinement_point(&mut self, c: &Complex, p: &Point) -> Verdict {
        let mut verdict = Verdict::Accepted;
        for &t in c.tri.cavity() {
            for i in 0..4 {
                let facet = 4 * t + i;
                if let Some(ball) = c.ball(facet) {
                    if dist2(p, &ball.center) < ball.radius2 {
                        self.queue.push(Self::element(c, facet, ENCROACHED));
                        verdict = Verdict::Rejected;
                    }
                }
            }
        }
        verdict
    }

    fn after_insertion(&mut self, c: &Complex, criteria: &Criteria) -> Result<()> {
        for &facet in c.fresh_facets() {
            if let Some(badness) = Self::badness(c, criteria, facet)? {
                self.queue.push(Self::element(c, facet, badness));
            }
        }
        Ok(())
    }

    fn requeue(&mut self, e: Element) {
        self.queue.push(e);
    }

    fn queued(&self) -> usize {
        self.queue.len()
    }
}

#[derive(Default)]
pub struct CellLevel {
    queue: Queue,
}

impl CellLevel {
    fn badness(c: &Complex, criteria: &Criteria, t: u32) -> Result<Option<Badness>> {
        if c.label(t) <= 0 {
            return Ok(None);
        }
        let ids = c.tri.tets().vertices(t);
        let v = ids.map(|x| c.tri.vertex(x));
        if ids.iter().filter(|&&x| c.dimension(x) == SURFACE).count() >= 3 {
            if let Some(b) = criteria.surface_sliver(v) {
                return Ok(Some(b));
            }
        }
        criteria.cell(v, c.center(t), c.label(t))
    }
}

impl Level for CellLevel {
    fn next(&mut self, c: &Complex, _: &Criteria) -> Result<Option<Element>> {
        while let Some(e) = self.queue.pop() {
            if c.is_current(e.handle, e.stamp) {
                return Ok(Some(e));
            }
        }
        Ok(None)
    }

    fn refinement_point(&self, c: &Complex, e: &Element) -> Proposal {
        Proposal {
            point: *c.center(e.handle),
            near: e.handle,
            dimension: VOLUME,
        }
    }

    fn check_refinement_point(&mut self, _: &Complex, _: &Point) -> Verdict {
        Verdict::Accepted
    }

    fn after_insertion(&mut self, c: &Complex, criteria: &Criteria) -> Result<()> {
        for &t in c.created() {
            if let Some(badness) = Self::badness(c, criteria, t)? {
                self.queue.push(Element::new(t, c.stamp(t), badness));
            }
        }
        Ok(())
    }

    fn requeue(&mut self, e: Element) {
        self.queue.push(e);
    }

    fn queued(&self) -> usize {
        self.queue.len()
    }
}
