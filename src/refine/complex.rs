//! The restricted Delaunay triangulation that refinement maintains (thesis §3.2: the
//! Delaunay triangulation of the sample *restricted* to the domain; CGAL's
//! `Mesh_complex_3_in_triangulation_3`).
//!
//! For every live tetrahedron: its circumcenter and the label of the subdomain containing it
//! (0 outside the domain, for tetrahedra with the infinite vertex, and for circumcenters
//! outside the box); the tetrahedra with a label > 0 are the cells *in the complex*.
//! For every facet whose dual Voronoi edge (or ray, on the convex hull) crosses the surface:
//! its *surface Delaunay ball*, centered at the crossing and passing through the facet's
//! vertices; such facets are the *restricted* (surface) facets.
//!
//! Everything is updated from each insertion's cavity only: the balls of the cavity's facets
//! are dropped before the insertion, the new tetrahedra and all their facets (those on the
//! cavity boundary included, whose dual changed) are computed after it.
//!
//! Invariants (checked by [`Complex::validate`]): `center`, `label` and the ball of every
//! facet are what [`Complex::compute_cell`] and [`Complex::restricted`] give for the current
//! triangulation; both sides of a facet name the same ball; no ball is named by a dead slot.

use crate::criteria::Criteria;
use crate::domain::{first_crossing, Domain};
use crate::error::Result;
use crate::geometry::{add, circumcenter, cross, dist2, midpoint, sub};
use crate::predicates::Point;
use crate::triangulation::tets::{FACE, INFINITE};
use crate::triangulation::{Conflicts, Triangulation};

/// Vertex dimension of surface points (the output's convention).
pub const SURFACE: i8 = 2;
/// Vertex dimension of points inside a subdomain.
pub const VOLUME: i8 = 3;

/// No ball: the facet is not restricted.
const NONE: u32 = u32::MAX;

/// Most interior samples of one dual segment looking for a crossing its ends do not show.
const MAX_SAMPLES: usize = 16;

/// A surface Delaunay ball of a restricted facet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    pub center: Point,
    pub radius2: f64,
    /// The labels on the two sides of the crossing.
    pub labels: (i32, i32),
}

pub struct Complex<'a> {
    pub tri: Triangulation<'static>,
    domain: &'a dyn Domain,
    criteria: &'a Criteria,
    center: Vec<Point>,
    label: Vec<i32>,
    /// Per facet slot `4*t+i`: index in `balls`, or `NONE`.
    ball: Vec<u32>,
    balls: Vec<Ball>,
    free_balls: Vec<u32>,
    /// Per vertex: [`SURFACE`] or [`VOLUME`].
    dimension: Vec<i8>,
    /// Per tetrahedron: the insertion that created it (to visit each new facet once).
    stamp: Vec<u32>,
    generation: u32,
    /// Facets `4*t+i` that received a ball in the last update.
    fresh: Vec<u32>,
    /// The tetrahedra of the last update.
    created: Vec<u32>,
}

impl<'a> Complex<'a> {
    /// The restricted Delaunay triangulation of `initial` surface points.
    pub fn new(
        domain: &'a dyn Domain,
        criteria: &'a Criteria,
        initial: Vec<Point>,
    ) -> Result<Self> {
        let b = domain.bbox();
        let tri = Triangulation::growable(initial, &b.lo, &b.hi)?;
        let n = tri.vertex_count();
        let mut c = Complex {
            tri,
            domain,
            criteria,
            center: Vec::new(),
            label: Vec::new(),
            ball: Vec::new(),
            balls: Vec::new(),
            free_balls: Vec::new(),
            dimension: vec![SURFACE; n],
            stamp: Vec::new(),
            generation: 0,
            fresh: Vec::new(),
            created: Vec::new(),
        };
        let all: Vec<u32> = c.tri.tets().live().collect();
        c.update(&all)?;
        c.created = all;
        Ok(c)
    }

    pub fn label(&self, t: u32) -> i32 {
        self.label[t as usize]
    }

    pub fn center(&self, t: u32) -> &Point {
        &self.center[t as usize]
    }

    /// The insertion that created tetrahedron `t` (slots are reused: a slot with another
    /// stamp holds another tetrahedron).
    pub fn stamp(&self, t: u32) -> u32 {
        self.stamp[t as usize]
    }

    /// Whether slot `t` still holds the live tetrahedron created at `stamp`.
    pub fn is_current(&self, t: u32, stamp: u32) -> bool {
        self.tri.tets().is_live(t) && self.stamp[t as usize] == stamp
    }

    /// Labels per tetrahedron slot.
    pub fn labels(&self) -> &[i32] {
        &self.label
    }

    /// Dimensions per vertex.
    pub fn dimensions(&self) -> &[i8] {
        &self.dimension
    }

    /// The triangulation with its labels and vertex dimensions, for the optimization passes
    /// (the surface balls and circumcenters are dropped: they belong to refinement).
    pub fn into_labeled(self) -> super::Labeled {
        super::Labeled {
            tri: self.tri,
            label: self.label,
            dimension: self.dimension,
        }
    }

    pub fn dimension(&self, v: u32) -> i8 {
        self.dimension[v as usize]
    }

    /// The surface Delaunay ball of facet `4*t+i`, if it is restricted.
    pub fn ball(&self, facet: u32) -> Option<&Ball> {
        match self.ball[facet as usize] {
            NONE => None,
            b => Some(&self.balls[b as usize]),
        }
    }

    /// The facets that became restricted in the last update.
    pub fn fresh_facets(&self) -> &[u32] {
        &self.fresh
    }

    /// The tetrahedra created by the last insertion (all of them after [`Complex::new`]).
    pub fn created(&self) -> &[u32] {
        &self.created
    }

    pub fn vertex_count(&self) -> usize {
        self.tri.vertex_count()
    }

    /// The vertices of facet `i` of `t`, seen from inside `t` counter-clockwise.
    pub fn facet_vertices(&self, t: u32, i: usize) -> [u32; 3] {
        let v = self.tri.tets().vertices(t);
        FACE[i].map(|k| v[k])
    }

    /// [`Triangulation::find_conflicts`].
    pub fn find_conflicts(&mut self, p: Point, near: u32) -> Result<Conflicts> {
        self.tri.find_conflicts(p, near)
    }

    pub fn abandon(&mut self) {
        self.tri.abandon();
    }

    /// Inserts the pending point as a vertex of `dimension` and updates the complex.
    pub fn commit(&mut self, dimension: i8) -> Result<u32> {
        for k in 0..self.tri.cavity().len() {
            let t = self.tri.cavity()[k];
            for i in 0..4 {
                self.drop_ball(4 * t + i);
            }
        }
        let v = self.tri.commit()?;
        self.dimension.push(dimension);
        let mut created = std::mem::take(&mut self.created);
        created.clear();
        created.extend_from_slice(self.tri.created());
        let result = self.update(&created);
        self.created = created;
        result.map(|()| v)
    }

    fn drop_ball(&mut self, facet: u32) {
        let b = self.ball[facet as usize];
        if b != NONE {
            self.free_balls.push(b);
            let mirror = self.tri.tets().glued(facet >> 2, (facet & 3) as usize);
            self.ball[facet as usize] = NONE;
            self.ball[mirror as usize] = NONE;
        }
    }

    /// Computes the cells `created` and all their facets.
    fn update(&mut self, created: &[u32]) -> Result<()> {
        let slots = self.tri.tets().slots();
        self.center.resize(slots, [f64::NAN; 3]);
        self.label.resize(slots, 0);
        self.stamp.resize(slots, 0);
        self.ball.resize(4 * slots, NONE);
        self.generation = self.generation.wrapping_add(1);
        for &t in created {
            let (c, l) = self.compute_cell(t)?;
            self.center[t as usize] = c;
            self.label[t as usize] = l;
            self.stamp[t as usize] = self.generation;
        }
        self.fresh.clear();
        for &t in created {
            for i in 0..4 {
                let u = self.tri.tets().neighbor(t, i);
                if self.stamp[u as usize] == self.generation && u < t {
                    continue;
                }
                if let Some(ball) = self.restricted(t, i)? {
                    let facet = 4 * t + i as u32;
                    let mirror = self.tri.tets().glued(t, i);
                    let b = match self.free_balls.pop() {
                        Some(b) => {
                            self.balls[b as usize] = ball;
                            b
                        }
                        None => {
                            self.balls.push(ball);
                            self.balls.len() as u32 - 1
                        }
                    };
                    self.ball[facet as usize] = b;
                    self.ball[mirror as usize] = b;
                    self.fresh.push(facet);
                }
            }
        }
        Ok(())
    }

    /// Circumcenter and label of tetrahedron `t`.
    fn compute_cell(&self, t: u32) -> Result<(Point, i32)> {
        let v = self.tri.tets().vertices(t);
        if v.contains(&INFINITE) {
            return Ok(([f64::NAN; 3], 0));
        }
        let c = circumcenter(v.map(|x| self.tri.vertex(x)));
        let label = if c.iter().all(|x| x.is_finite()) {
            self.domain.label(&c)?
        } else {
            0
        };
        Ok((c, label))
    }

    /// The surface Delaunay ball of facet `i` of `t`, if its dual crosses the surface.
    ///
    /// The dual runs from the circumcenter of `t` to that of its neighbour; on the hull (or
    /// when a circumcenter is not finite) it is the ray from the finite one along the facet's
    /// normal, away from its tetrahedron. It is clipped to the box, where the label is 0.
    pub fn restricted(&self, t: u32, i: usize) -> Result<Option<Ball>> {
        let tri = self.facet_vertices(t, i);
        if tri.contains(&INFINITE) {
            return Ok(None);
        }
        let u = self.tri.tets().neighbor(t, i);
        let (ct, cu) = (self.center[t as usize], self.center[u as usize]);
        let finite = |p: &Point| p.iter().all(|x| x.is_finite());
        let p = tri.map(|v| self.tri.vertex(v));
        // (start, its label, end or direction point, its label, parameter range)
        let (a, la, b, lb, end) = if finite(&ct) && finite(&cu) {
            (ct, self.label(t), cu, self.label(u), 1.0)
        } else if finite(&ct) {
            let n = outward_normal(p);
            (ct, self.label(t), add(&ct, &n), 0, f64::INFINITY)
        } else if finite(&cu) {
            let n = outward_normal(p).map(|x| -x);
            (cu, self.label(u), add(&cu, &n), 0, f64::INFINITY)
        } else {
            return Ok(None);
        };
        let Some(s) = self.domain.bbox().clip(&a, &b, end) else {
            return Ok(None);
        };
        let ls = if s.start_is_a { la } else { 0 };
        let le = if s.end_is_b { lb } else { 0 };
        let step = if ls == le {
            self.criteria
                .sampling_step(&midpoint(&s.start, &s.end), (ls, le))?
        } else {
            f64::INFINITY
        };
        let x = first_crossing(self.domain, &s.start, ls, &s.end, le, step, MAX_SAMPLES)?;
        Ok(x.map(|x| Ball {
            center: x.point,
            radius2: dist2(&x.point, p[0]),
            labels: x.labels,
        }))
    }

    /// Checks the invariants of the module documentation by recomputing everything.
    pub fn validate(&mut self) -> std::result::Result<(), String> {
        self.tri.validate()?;
        for t in self.tri.tets().live() {
            let (c, l) = self.compute_cell(t).map_err(|e| e.message)?;
            let same = c == self.center[t as usize]
                || (c[0].is_nan() && self.center[t as usize][0].is_nan());
            if !same || l != self.label[t as usize] {
                return Err(format!("tetrahedron {t}: stale circumcenter or label"));
            }
            for i in 0..4 {
                let facet = 4 * t + i as u32;
                let mirror = self.tri.tets().glued(t, i);
                if self.ball[facet as usize] != self.ball[mirror as usize] {
                    return Err(format!("facet {facet}: its two sides name different balls"));
                }
                let want = self.restricted(t, i).map_err(|e| e.message)?;
                if want.is_some() != self.ball(facet).is_some() {
                    return Err(format!(
                        "facet {facet}: restricted is {} but the complex says {}",
                        want.is_some(),
                        self.ball(facet).is_some()
                    ));
                }
            }
        }
        Ok(())
    }
}

/// The normal of a facet listed counter-clockwise from inside its tetrahedron, pointing out
/// of it: `(c - a) x (b - a)`.
fn outward_normal(p: [&Point; 3]) -> Point {
    cross(&sub(p[2], p[0]), &sub(p[1], p[0]))
}
