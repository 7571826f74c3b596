//! Quality refinement of the recovered mesh that never splits an input triangle: Shewchuk's
//! Delaunay refinement restricted to interior points, with the rules TetGen applies when the
//! surface must be kept (`-q`, `-a` with `-Y`).
//!
//! 1. The kept regions are made as Delaunay as flips allow (Lawson's flips: 2-3, and 3-2
//!    where an edge of the facet has a shell of three), never across an input triangle;
//!    where neither applies, an edge of the facet is removed when that lowers its shell's
//!    lifted volume (TetGen's recovery of the Delaunay property); skipped when recovery
//!    changed nothing in the Delaunay triangulation.
//! 2. A tetrahedron whose radius-edge ratio (circumradius over shortest edge) or volume is
//!    above its bound gets its circumcenter, the worst first ([`BadQueue`]), inserted by a
//!    Bowyer–Watson cavity that stops at the input triangles and is shrunk until it is
//!    star-shaped from the point; Lawson's flips follow when it was shrunk.
//! 3. A circumcenter is declined when it lies beyond the surface seen from its tetrahedron,
//!    when it would be joined by an edge shorter than its tetrahedron's shortest edge (only
//!    where the mesh is not Delaunay: a guard against cascades),
//!    in the diametral ball of an input triangle on its cavity's boundary or of an input edge
//!    of its cavity, or, for a ratio split, in the protecting ball of an input vertex of its
//!    cavity: radius the distance from the vertex to the nearest vertex, input edge or input
//!    triangle of its link (the local feature size TetGen uses). These are the tetrahedra the
//!    input forces: they stay, and are counted.
//! 4. A tetrahedron above its volume bound whose circumcenter is declined gets its centroid,
//!    which only the star-shape rule can decline: volume bounds are met unless a cavity
//!    cannot be made star-shaped.
//!
//! Invariants: every inserted point lies strictly inside a kept region (the cavity never
//! crosses an input triangle and contains the tetrahedron holding the point); input
//! triangles and edges stay facets and edges; the mesh stays valid ([`TetMesh::validate`]);
//! new tetrahedra inherit their cavity's region.

use std::collections::VecDeque;

use super::by_vertex::ByVertex;
use super::classify::{Regions, NOT_INPUT};
use super::flips::{flip32, remove_non_delaunay_edge, Protected};
use super::tetmesh::{key, TetMesh};
use crate::error::{Error, ErrorKind, Result};
use crate::geometry::{circumcenter, dist, dist2, dot, sub, tet_volume, triangle_circumcenter};
use crate::predicates::{Point, Sign};
use crate::triangulation::tets::{FACE, INFINITE};

/// The tetrahedra above their bounds, worst first: in buckets by how far above (on a log
/// scale, [`BadQueue::PER_DOUBLING`] to a doubling), first in first out within a bucket
/// (Shewchuk's Triangle orders its bad triangles so). Splitting the worst first takes 5% and
/// 7% fewer points than first in first out on armadillo and bunny00 with a bound of 1.414.
struct BadQueue {
    buckets: Vec<VecDeque<(u32, [u32; 4], Split)>>,
    /// No bucket above this one holds anything.
    top: usize,
}

impl BadQueue {
    const PER_DOUBLING: f64 = 16.0;
    const BUCKETS: usize = 256;

    fn new() -> Self {
        BadQueue {
            buckets: (0..Self::BUCKETS).map(|_| VecDeque::new()).collect(),
            top: 0,
        }
    }

    /// Queues a tetrahedron `excess` times above its bound (> 1; the last bucket holds those
    /// from 2^(255/16), about 6 × 10^4, and the infinitely bad).
    fn push(&mut self, excess: f64, item: (u32, [u32; 4], Split)) {
        let b = (excess.log2() * Self::PER_DOUBLING).clamp(0.0, (Self::BUCKETS - 1) as f64);
        let b = if b.is_nan() {
            Self::BUCKETS - 1
        } else {
            b as usize
        };
        self.top = self.top.max(b);
        self.buckets[b].push_back(item);
    }

    fn pop(&mut self) -> Option<(u32, [u32; 4], Split)> {
        loop {
            if let Some(item) = self.buckets[self.top].pop_front() {
                return Some(item);
            }
            if self.top == 0 {
                return None;
            }
            self.top -= 1;
        }
    }
}

/// Steps of a point-location walk before it gives up.
const WALK: usize = 1 << 16;

/// The mark of a tetrahedron waiting on the Lawson stack (other searches mark 1 to 8 and
/// clear their marks).
const WAITING: u8 = 9;

/// What Lawson's pass may do besides 2-3 and 3-2 flips.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Lawson {
    FlipsOnly,
    /// Also remove an edge of a facet those flips leave not locally Delaunay, where its
    /// shell gets more Delaunay ([`remove_non_delaunay_edge`], TetGen's recovery of the
    /// Delaunay property): before refinement only. After a shrunk cavity, it made handle take
    /// 664 points instead of 608 with the bound 1.414, and anchor and dragknob no fewer.
    RemovingEdges,
}

/// Why a point is tried: the checks differ (TetGen's `qflag`).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Split {
    /// A circumcenter for the ratio bound: every rule of the module documentation.
    Ratio,
    /// A circumcenter for a volume bound: protecting balls do not apply.
    Volume,
    /// A centroid for a volume bound: only the star-shape rule applies.
    Centroid,
}

/// Refines the kept regions until every tetrahedron meets the bound `ratio` (0 = none) and
/// its region's volume bound, except those whose points rule 3 declines. Returns the
/// protecting radii it used.
pub fn refine(
    mesh: &mut TetMesh,
    protected: &Protected,
    regions: &mut Regions,
    ratio: f64,
    n_input: u32,
) -> Result<ProtectingRadii> {
    let mut refiner = Refiner::new(mesh, protected, regions, ratio);
    refiner.run(n_input)?;
    Ok(ProtectingRadii(refiner.lfs))
}

/// The protecting-ball radii of the input vertices (rule 3), measured once on the mesh
/// refinement starts from.
pub struct ProtectingRadii(Vec<f64>);

/// [`refine`] of the tetrahedra `queue` and of those their points make, with the radii that
/// refinement measured and without Lawson's pass first (which would undo the flips that
/// followed refinement): after the wedges are split ([`super::wedges`]).
pub fn refine_these(
    mesh: &mut TetMesh,
    protected: &Protected,
    regions: &mut Regions,
    (ratio, radii): (f64, ProtectingRadii),
    queue: Vec<u32>,
) -> Result<()> {
    let mut refiner = Refiner::new(mesh, protected, regions, ratio);
    refiner.flips_left = flips_for(queue.len());
    refiner.lfs = radii.0;
    refiner.refine(queue)
}

/// The flips Lawson's passes may make in a refinement of `tetrahedra` tetrahedra.
fn flips_for(tetrahedra: usize) -> usize {
    64 * tetrahedra + 1024
}

/// A Bowyer–Watson cavity as [`Refiner::cavity`] finds it.
#[derive(Default)]
struct Cavity {
    /// Its tetrahedra, the one holding the point first.
    tets: Vec<u32>,
    /// Its boundary facets that see the point on their positive side, in the order of
    /// `tets` and of their facets, each with the facet glued to it outside.
    cone: Vec<([u32; 3], u32)>,
    /// The input triangle each facet of `cone` is ([`Regions::triangle`]).
    triangles: Vec<u32>,
    /// The tetrahedra with a boundary facet that does not (the cavity must be shrunk).
    blocked: Vec<u32>,
}

impl Cavity {
    fn clear(&mut self) {
        self.tets.clear();
        self.cone.clear();
        self.triangles.clear();
        self.blocked.clear();
    }
}

struct Refiner<'a> {
    mesh: &'a mut TetMesh,
    protected: &'a Protected,
    regions: &'a mut Regions,
    ratio: f64,
    /// Protecting-ball radius of every input vertex (0 for those not in the mesh); Steiner
    /// points, numbered after them, have none.
    lfs: Vec<f64>,
    /// Tetrahedra above their bounds, with their vertices (a slot reused since is skipped).
    queue: BadQueue,
    /// Flips Lawson's pass may still make.
    flips_left: usize,
    /// Edges of facets Lawson's flips found not locally Delaunay and could not flip, with a
    /// tetrahedron holding them and its vertices then.
    unflipped: Vec<(u32, [u32; 4], [u32; 2])>,
    /// The lists of the cavity under way, kept from point to point.
    cavity: Cavity,
    /// Per vertex, the last cavity that counted it (see [`Refiner::star_shaped`]).
    seen: Vec<u32>,
    cavities: u32,
}

impl<'a> Refiner<'a> {
    fn new(
        mesh: &'a mut TetMesh,
        protected: &'a Protected,
        regions: &'a mut Regions,
        ratio: f64,
    ) -> Self {
        Refiner {
            lfs: Vec::new(),
            protected,
            mesh,
            regions,
            ratio,
            queue: BadQueue::new(),
            flips_left: 0,
            unflipped: Vec::new(),
            cavity: Cavity::default(),
            seen: Vec::new(),
            cavities: 0,
        }
    }

    fn run(&mut self, n_input: u32) -> Result<()> {
        let mut kept = self.kept();
        self.flips_left = flips_for(kept.len());
        // Every facet of the Delaunay triangulation is locally Delaunay: nothing to flip.
        if !self.mesh.is_delaunay() {
            self.lawson(kept, Lawson::RemovingEdges)?;
            kept = self.kept();
        }
        self.lfs = self.protecting_radii(n_input);
        self.refine(kept)
    }

    /// Splits the tetrahedra of `queue` above their bounds and those the splits make, the
    /// worst first.
    fn refine(&mut self, queue: Vec<u32>) -> Result<()> {
        let budget = self.point_budget();
        for t in queue {
            self.enqueue(t);
        }
        let mut inserted = 0;
        while let Some((t, quad, split)) = self.queue.pop() {
            if !self.mesh.tets.is_live(t) || self.mesh.tets.vertices(t) != quad {
                continue;
            }
            if inserted == budget {
                return Err(Error::new(
                    ErrorKind::Limit,
                    format!(
                        "quality refinement stopped after {inserted} points with tetrahedra \
                         left above their bounds"
                    ),
                ));
            }
            if self.split(t, split)? {
                inserted += 1;
            }
        }
        Ok(())
    }

    /// The live tetrahedra of the kept regions.
    fn kept(&self) -> Vec<u32> {
        let regions = &self.regions;
        self.mesh.tets.live().filter(|&t| regions.kept(t)).collect()
    }

    /// At most this many points: a multiple of the mesh for the ratio bound, plus what the
    /// volume bounds ask for.
    fn point_budget(&self) -> usize {
        let mut wanted = 0.0;
        let mut count = 0usize;
        for t in self.mesh.tets.live() {
            if !self.regions.kept(t) {
                continue;
            }
            count += 1;
            let bound = self.regions.max_volume[self.regions.component[t as usize] as usize];
            if bound > 0.0 {
                wanted += self.volume(t) / bound;
            }
        }
        (64.0 * count as f64 + 16.0 * wanted + 1e5).min(1e9) as usize
    }

    fn volume(&self, t: u32) -> f64 {
        let p = self.mesh.tets.vertices(t).map(|v| *self.mesh.point(v));
        tet_volume([&p[0], &p[1], &p[2], &p[3]]).abs()
    }

    /// Queues `t` when it is above a bound.
    fn enqueue(&mut self, t: u32) {
        if let Some((split, excess)) = self.badness(t) {
            self.queue
                .push(excess, (t, self.mesh.tets.vertices(t), split));
        }
    }

    /// What tetrahedron `t` needs, and by how much it exceeds that bound (volume over the
    /// bound, or ratio over the bound); `None` when it meets its bounds.
    fn badness(&self, t: u32) -> Option<(Split, f64)> {
        let bound = self.regions.max_volume[self.regions.component[t as usize] as usize];
        if bound > 0.0 {
            let volume = self.volume(t);
            if volume > bound {
                return Some((Split::Volume, volume / bound));
            }
        }
        if self.ratio == 0.0 {
            return None;
        }
        let excess = radius_edge_ratio(self.mesh, t) / self.ratio;
        (excess > 1.0).then_some((Split::Ratio, excess))
    }

    /// Tries the circumcenter of `t`, then for a volume bound its centroid; whether a point
    /// went in.
    fn split(&mut self, t: u32, split: Split) -> Result<bool> {
        let p = self.mesh.tets.vertices(t).map(|v| *self.mesh.point(v));
        let center = well_conditioned_circumcenter(&p);
        if self.insert(t, center, split)? {
            return Ok(true);
        }
        if split == Split::Ratio {
            return Ok(false);
        }
        let centroid = [0, 1, 2].map(|k| (p[0][k] + p[1][k] + p[2][k] + p[3][k]) / 4.0);
        self.insert(t, centroid, Split::Centroid)
    }

    /// Inserts `c`, located from tetrahedron `t`, unless a rule of the module documentation
    /// declines it (nothing changes then).
    fn insert(&mut self, t: u32, c: Point, split: Split) -> Result<bool> {
        if !c.iter().all(|x| x.is_finite()) {
            return Ok(false);
        }
        let Some(start) = self.locate(t, &c) else {
            return Ok(false);
        };
        // The cavity's lists are the refiner's, reused from point to point.
        let mut cavity = std::mem::take(&mut self.cavity);
        let inserted = self.insert_from(t, start, c, split, &mut cavity);
        self.cavity = cavity;
        inserted
    }

    /// [`Refiner::insert`] from `start`, the tetrahedron holding `c`, in `cavity`.
    fn insert_from(
        &mut self,
        t: u32,
        start: u32,
        c: Point,
        split: Split,
        cavity: &mut Cavity,
    ) -> Result<bool> {
        if !self.cavity(start, &c, split, cavity) {
            return Ok(false);
        }
        let full = cavity.tets.len();
        if !self.star_shaped(start, cavity, &c) {
            return Ok(false);
        }
        let shrunk = cavity.tets.len() != full;
        if split == Split::Ratio && self.too_close(t, &cavity.cone, &c) {
            return Ok(false);
        }
        let s = self.mesh.add_point(c);
        let component = self.regions.component[start as usize];
        let Some(created) = self
            .mesh
            .try_replace_by_cone(&cavity.tets, s, &cavity.cone)?
        else {
            self.mesh.pop_point();
            return Ok(false);
        };
        self.regions
            .assign_cone(&created, &cavity.triangles, component);
        // After a whole Bowyer-Watson cavity, Lawson's flips are skipped: each boundary facet
        // is locally Delaunay (the facet test is symmetric, and `c` is outside the
        // circumsphere of every tetrahedron across the boundary, or an input triangle lies
        // between), and so are the facets inside the cone where the mesh around was Delaunay.
        // Measured: 1 flip in 2,583 such insertions on fandisk, none on knot and elephant.
        // Only a cavity that star-shaping shrank leaves facets to flip.
        let created = if shrunk {
            self.lawson(created, Lawson::FlipsOnly)?
        } else {
            let mut created = created;
            created.sort_unstable();
            created
        };
        for t in created {
            self.enqueue(t);
        }
        Ok(true)
    }

    /// The tetrahedron of `t`'s region whose closure holds `c`, by a walk that never crosses
    /// an input triangle nor leaves the kept regions (the convex hull when it is kept);
    /// `None` when `c` is beyond one, on one, on a vertex, or the walk does not end.
    fn locate(&self, t: u32, c: &Point) -> Option<u32> {
        let at = self.mesh.walk(t, c, WALK, |_, u, i, n| {
            !self.regions.on_surface(u, i) && self.regions.kept(n)
        })?;
        let mut zeros = 0;
        for i in 0..4 {
            if self.mesh.orient_point(self.mesh.facet(at, i), c) == Sign::Zero {
                if self.regions.on_surface(at, i) {
                    return None;
                }
                zeros += 1;
            }
        }
        (zeros < 3).then_some(at)
    }

    /// Finds in `cavity` the Bowyer–Watson cavity of `c`: `start`, first, and the tetrahedra
    /// connected to it across non-input facets whose circumsphere strictly holds `c`, with
    /// its boundary facets; false when `c` encroaches (unless `split` is a centroid's): it
    /// lies in the diametral ball of an input triangle bounding the cavity or of an input
    /// edge on its boundary, or (ratio splits) in the protecting ball of a cavity vertex.
    /// Input triangles and edges can only be on the boundary: the cavity never crosses an
    /// input triangle, and the surfaces are closed. A neighbour the search declines is
    /// declined for good (the tests do not depend on where it is reached from), so each
    /// boundary facet is known, and checked, as soon as it is found: an encroaching point
    /// stops the search there.
    fn cavity(&mut self, start: u32, c: &Point, split: Split, cavity: &mut Cavity) -> bool {
        cavity.clear();
        cavity.tets.push(start);
        self.mesh.tets.mark[start as usize] = 7;
        let mut hit = self.in_protecting_ball(start, c, split);
        let mut k = 0;
        while !hit && k < cavity.tets.len() {
            let u = cavity.tets[k];
            k += 1;
            for i in 0..4 {
                hit = self.extend(cavity, u, i, c, split);
                if hit {
                    break;
                }
            }
        }
        for &u in &cavity.tets {
            self.mesh.tets.mark[u as usize] = 0;
        }
        !hit
    }

    /// Takes the neighbour across facet `i` of the cavity's tetrahedron `u` into `cavity`, or
    /// notes that facet as a boundary facet; whether `c` encroaches what was found.
    fn extend(&mut self, cavity: &mut Cavity, u: u32, i: usize, c: &Point, split: Split) -> bool {
        let n = self.mesh.tets.neighbor(u, i);
        if self.mesh.tets.mark[n as usize] == 7 {
            return false;
        }
        let triangle = self.regions.triangle(u, i);
        let surface = triangle != NOT_INPUT;
        let q = self.mesh.tets.vertices(n);
        if !surface && !q.contains(&INFINITE) && self.mesh.insphere(q, c) == Sign::Positive {
            self.mesh.tets.mark[n as usize] = 7;
            cavity.tets.push(n);
            // Its row and neighbours are read when the search comes to it, a few
            // tetrahedra later: asked for now, their loads overlap the work until then.
            self.regions.prefetch(n);
            for j in 0..4 {
                self.mesh.tets.prefetch(self.mesh.tets.neighbor(n, j));
            }
            return self.in_protecting_ball(n, c, split);
        }
        let f = self.mesh.facet(u, i);
        if split != Split::Centroid && self.in_diametral_ball(f, surface, c) {
            return true;
        }
        self.add_boundary_facet(cavity, u, i, f, triangle, c);
        false
    }

    /// Notes facet `i` of `u`, `f`, input triangle `triangle`, as a boundary facet of
    /// `cavity` seen from `c`.
    fn add_boundary_facet(
        &self,
        cavity: &mut Cavity,
        u: u32,
        i: usize,
        f: [u32; 3],
        triangle: u32,
        c: &Point,
    ) {
        if self.mesh.orient_point(f, c) == Sign::Positive {
            cavity.cone.push((f, self.mesh.tets.glued(u, i)));
            cavity.triangles.push(triangle);
        } else {
            cavity.blocked.push(u);
        }
    }

    /// Whether `c` lies in the diametral ball of the input triangle `f` (when `surface`) or
    /// of an input edge of `f`.
    fn in_diametral_ball(&self, f: [u32; 3], surface: bool, c: &Point) -> bool {
        if surface {
            let p = f.map(|x| self.mesh.point(x));
            let center = triangle_circumcenter(p);
            if dist2(c, &center) < dist2(p[0], &center) {
                return true;
            }
        }
        // The diametral-ball test first: it is cheaper than the lookup and rarely holds.
        (0..3).any(|k| {
            let (x, y) = (f[k], f[(k + 1) % 3]);
            let (a, b) = (self.mesh.point(x), self.mesh.point(y));
            dot(&sub(a, c), &sub(b, c)) < 0.0 && self.protected.edge(x, y)
        })
    }

    /// Whether `c`, a ratio split, lies in the protecting ball of a vertex of `u`.
    fn in_protecting_ball(&self, u: u32, c: &Point, split: Split) -> bool {
        split == Split::Ratio
            && self.mesh.tets.vertices(u).iter().any(|&x| {
                let r = self.lfs.get(x as usize);
                r.is_some_and(|&r| dist(c, self.mesh.point(x)) <= r)
            })
    }

    /// Breadth-first search from `start` across facets: `n`, across facet `i` of `u`, is
    /// taken when `joins(self, u, i, n)`; taken tetrahedra are marked `mark`.
    fn search(
        &mut self,
        start: u32,
        mark: u8,
        joins: impl Fn(&Self, u32, usize, u32) -> bool,
    ) -> Vec<u32> {
        let mut found = vec![start];
        self.mesh.tets.mark[start as usize] = mark;
        let mut k = 0;
        while k < found.len() {
            let u = found[k];
            k += 1;
            for i in 0..4 {
                let n = self.mesh.tets.neighbor(u, i);
                if joins(self, u, i, n) {
                    self.mesh.tets.mark[n as usize] = mark;
                    found.push(n);
                }
            }
        }
        found
    }

    /// Whether `c` would be joined to a vertex of the cavity's boundary `cone` by an edge
    /// shorter than the shortest edge of tetrahedron `t`, whose ratio it is meant to fix. In a
    /// Delaunay mesh it never is (the circumsphere is empty); where the surface or unflippable
    /// facets keep the mesh from being Delaunay, this keeps every new edge at least as long as
    /// an existing one, so refinement cannot cascade toward a point close to the surface.
    fn too_close(&self, t: u32, cone: &[([u32; 3], u32)], c: &Point) -> bool {
        let q = self.mesh.tets.vertices(t).map(|v| *self.mesh.point(v));
        let shortest = crate::quality::shortest_edge(&q);
        cone.iter()
            .flat_map(|(f, _)| f)
            .any(|&v| dist(c, self.mesh.point(v)) < shortest)
    }

    /// Shrinks `cavity` (always keeping `start`) until every boundary facet sees `c` on its
    /// positive side and every cavity vertex is on the boundary, renewing its boundary; false
    /// when `start` itself would have to go.
    fn star_shaped(&mut self, start: u32, cavity: &mut Cavity, c: &Point) -> bool {
        while !cavity.blocked.is_empty() {
            // The blocked tetrahedra go, and those no longer reachable from `start`.
            for &u in &cavity.tets {
                self.mesh.tets.mark[u as usize] = 7;
            }
            for &u in &cavity.blocked {
                self.mesh.tets.mark[u as usize] = 0;
            }
            if self.mesh.tets.mark[start as usize] != 7 {
                for &u in &cavity.tets {
                    self.mesh.tets.mark[u as usize] = 0;
                }
                return false;
            }
            self.reachable(start, &mut cavity.tets);
            self.boundary(cavity, c);
        }
        // Every cavity vertex must stay, on a boundary facet. The boundary, every facet
        // seeing `c` inside, is a sphere around it: `F / 2 + 2` vertices.
        self.distinct_vertices(&cavity.tets) == cavity.cone.len() / 2 + 2
    }

    /// Finds the boundary facets of `cavity.tets` anew.
    fn boundary(&mut self, cavity: &mut Cavity, c: &Point) {
        cavity.cone.clear();
        cavity.triangles.clear();
        cavity.blocked.clear();
        let tets = std::mem::take(&mut cavity.tets);
        for &u in &tets {
            self.mesh.tets.mark[u as usize] = 7;
        }
        for &u in &tets {
            for i in 0..4 {
                if self.mesh.tets.mark[self.mesh.tets.neighbor(u, i) as usize] != 7 {
                    let f = self.mesh.facet(u, i);
                    self.add_boundary_facet(cavity, u, i, f, self.regions.triangle(u, i), c);
                }
            }
        }
        for &u in &tets {
            self.mesh.tets.mark[u as usize] = 0;
        }
        cavity.tets = tets;
    }

    /// The number of distinct vertices of the tetrahedra `cavity`.
    fn distinct_vertices(&mut self, cavity: &[u32]) -> usize {
        self.seen.resize(self.mesh.points.len(), 0);
        self.cavities += 1;
        if self.cavities == u32::MAX {
            self.seen.fill(0);
            self.cavities = 1;
        }
        let mut count = 0;
        for &u in cavity {
            for v in self.mesh.tets.vertices(u) {
                let seen = &mut self.seen[v as usize];
                if *seen != self.cavities {
                    *seen = self.cavities;
                    count += 1;
                }
            }
        }
        count
    }

    /// Keeps the marked tetrahedra of `cavity` reachable from `start` through marked ones;
    /// clears the marks.
    fn reachable(&mut self, start: u32, cavity: &mut Vec<u32>) {
        let marked = std::mem::take(cavity);
        *cavity = self.search(start, 8, |me, _, _, n| me.mesh.tets.mark[n as usize] == 7);
        for u in marked {
            self.mesh.tets.mark[u as usize] = 0;
        }
    }

    /// Lawson's flips from the tetrahedra `start`, within the kept regions and never across
    /// an input triangle, and the edge removals `mode` allows once no flip is left; returns
    /// the live tetrahedra among `start` and those flips made.
    ///
    /// A facet between two tetrahedra waiting on the stack is tested once, from the second
    /// one taken off it (the test is symmetric: either apex is inside the other tetrahedron's
    /// circumsphere exactly when the other is); marks tell waiting tetrahedra from the others.
    fn lawson(&mut self, start: Vec<u32>, mode: Lawson) -> Result<Vec<u32>> {
        let mut touched = start.clone();
        let mut stack: Vec<(u32, [u32; 4])> = Vec::with_capacity(start.len());
        for &t in &start {
            self.wait(&mut stack, t);
        }
        loop {
            self.flip_waiting(&mut stack, &mut touched, mode)?;
            // Then an edge of a facet no 2-3 or 3-2 flip could remove, where removing it
            // makes its shell more Delaunay, and Lawson's flips around the new tetrahedra.
            if self.flips_left == 0 {
                self.unflipped.clear();
                break;
            }
            let Some((t, quad, edge)) = self.unflipped.pop() else {
                break;
            };
            if !self.mesh.tets.is_live(t) || self.mesh.tets.vertices(t) != quad {
                continue;
            }
            if let Some(created) = remove_non_delaunay_edge(self.mesh, self.protected, t, edge)? {
                self.flipped(t, &created, &mut stack, &mut touched);
            }
        }
        for &t in &touched {
            self.mesh.tets.mark[t as usize] = 0;
        }
        touched.sort_unstable();
        touched.dedup();
        touched.retain(|&t| self.mesh.tets.is_live(t));
        Ok(touched)
    }

    /// Lawson's flips of the facets of the tetrahedra on `stack` (and of those the flips
    /// make) until none is left; the new tetrahedra are added to `touched`. With
    /// [`Lawson::RemovingEdges`], the edges of the facets no flip removes are noted in
    /// `unflipped`.
    fn flip_waiting(
        &mut self,
        stack: &mut Vec<(u32, [u32; 4])>,
        touched: &mut Vec<u32>,
        mode: Lawson,
    ) -> Result<()> {
        while let Some((t, quad)) = stack.pop() {
            if !self.mesh.tets.is_live(t) || self.mesh.tets.vertices(t) != quad {
                continue;
            }
            self.mesh.tets.mark[t as usize] = 0;
            for i in 0..4 {
                if self.flips_left == 0 {
                    break;
                }
                if self.mesh.tets.mark[self.mesh.tets.neighbor(t, i) as usize] == WAITING {
                    continue;
                }
                if let Some(created) = self.flip_if_not_delaunay(t, i, mode)? {
                    self.flipped(t, &created, stack, touched);
                    break;
                }
            }
        }
        Ok(())
    }

    /// Counts a flip that replaced `t` (and others of its region) by `created`, which go on
    /// the Lawson stack.
    fn flipped(
        &mut self,
        t: u32,
        created: &[u32],
        stack: &mut Vec<(u32, [u32; 4])>,
        touched: &mut Vec<u32>,
    ) {
        self.flips_left -= 1;
        let component = self.regions.component[t as usize];
        self.regions.assign(self.mesh, created, component);
        for &u in created {
            self.wait(stack, u);
        }
        touched.extend_from_slice(created);
    }

    /// Puts `t` on the Lawson stack, marked as waiting.
    fn wait(&mut self, stack: &mut Vec<(u32, [u32; 4])>, t: u32) {
        self.mesh.tets.mark[t as usize] = WAITING;
        stack.push((t, self.mesh.tets.vertices(t)));
    }

    /// Flips facet `i` of `t` away (2-3, or 3-2 around one of its edges) when the apex
    /// across it is strictly inside `t`'s circumsphere and a flip gives positive
    /// tetrahedra; returns the new tetrahedra. Where no flip does, with
    /// [`Lawson::RemovingEdges`], the facet's edges are noted in `unflipped`.
    fn flip_if_not_delaunay(&mut self, t: u32, i: usize, mode: Lawson) -> Result<Option<Vec<u32>>> {
        let (d, [x, y, z]) = self.mesh.with_apex(t, i);
        let n = self.mesh.tets.neighbor(t, i);
        if self.regions.on_surface(t, i) || !self.regions.kept(n) {
            return Ok(None);
        }
        let e = self.mesh.across(t, i);
        let q = self.mesh.tets.vertices(t);
        if q.contains(&INFINITE) || e == INFINITE {
            return Ok(None);
        }
        if self.mesh.insphere(q, self.mesh.point(e)) != Sign::Positive {
            return Ok(None);
        }
        let new = [[d, x, y, e], [d, y, z, e], [d, z, x, e]];
        if new.iter().all(|&q| self.mesh.positive(q)) {
            return self.mesh.replace(&[t, n], &new).map(Some);
        }
        // A 3-2 flip around an edge of the facet, inside the kept regions.
        let kept = |_: &TetMesh, shell: [u32; 3], _| shell.iter().all(|&u| self.regions.kept(u));
        for edge in [[x, y], [y, z], [z, x]] {
            if let Some(created) = flip32(self.mesh, self.protected, t, edge, &kept)? {
                return Ok(Some(created));
            }
        }
        if mode == Lawson::RemovingEdges {
            let quad = self.mesh.tets.vertices(t);
            for edge in [[x, y], [y, z], [z, x]] {
                self.unflipped.push((t, quad, edge));
            }
        }
        Ok(None)
    }

    /// The protecting-ball radius of every input vertex (TetGen's feature size with `-Y`):
    /// the distance to the nearest other input vertex, input edge or input triangle of its
    /// link, the latter two only where the vertex projects inside them; 0 for those not in
    /// the mesh. The nearest vertex is found from every tetrahedron's edges; the input
    /// triangles from where the regions know them: both tetrahedra of one have it in their
    /// apex's link, and every vertex of the ring of one of its sides has that side in its
    /// link (every input edge is a side of an input triangle). Squared distances are
    /// compared, and the square root (monotone) taken once per vertex.
    fn protecting_radii(&self, n_input: u32) -> Vec<f64> {
        let mesh = &*self.mesh;
        let n = mesh.points.len();
        let input = |v: u32| v < n_input;
        let mut nearest2 = vec![f64::INFINITY; n];
        let mut nearest_facet = vec![f64::INFINITY; n];
        for t in mesh.tets.live() {
            let q = mesh.tets.vertices(t);
            for [i, j] in EDGES {
                if input(q[i]) && input(q[j]) {
                    let d2 = dist2(mesh.point(q[i]), mesh.point(q[j]));
                    for v in [q[i], q[j]] {
                        nearest2[v as usize] = nearest2[v as usize].min(d2);
                    }
                }
            }
        }
        let protected = self.protected;
        let edges = ByVertex::new(n, protected.edges.iter().map(|&[a, b]| (a, b)));
        let mut edge_done = vec![false; edges.items.len()];
        for &(t, i) in self.regions.surface_facets() {
            let g = mesh.tets.glued(t, i);
            for (u, k) in [(t, i), (g >> 2, (g & 3) as usize)] {
                let q = mesh.tets.vertices(u);
                if input(q[k]) {
                    let d = triangle_distance(mesh.point(q[k]), FACE[k].map(|m| mesh.point(q[m])));
                    let near = &mut nearest_facet[q[k] as usize];
                    *near = near.min(d);
                }
            }
            let [a, b, c] = key(mesh.facet(t, i));
            for [x, y] in [[a, b], [a, c], [b, c]] {
                let Some(e) = edges.position(x, &y) else {
                    continue;
                };
                if std::mem::replace(&mut edge_done[e], true) {
                    continue;
                }
                let (px, py) = (mesh.point(x), mesh.point(y));
                mesh.ring(t, x, y, |w| {
                    if input(w) {
                        let d2 = segment_distance2(mesh.point(w), px, py);
                        nearest2[w as usize] = nearest2[w as usize].min(d2);
                    }
                });
            }
        }
        (0..n_input)
            .map(|v| {
                if mesh.in_mesh(v) {
                    nearest2[v as usize].sqrt().min(nearest_facet[v as usize])
                } else {
                    0.0
                }
            })
            .collect()
    }
}

/// The six edges of a tetrahedron, by local vertex indices.
const EDGES: [[usize; 2]; 6] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];

/// The circumcenter of tetrahedron `p`, or, when rounding leaves it undetermined (a flat
/// tetrahedron of nearly cocircular points: its distances to the vertices differ by more than
/// 1e-6 relative), the circumcenter of its largest face, which is what a split of it needs.
fn well_conditioned_circumcenter(p: &[Point; 4]) -> Point {
    let c = circumcenter([&p[0], &p[1], &p[2], &p[3]]);
    let d = p.map(|q| dist(&c, &q));
    let (lo, hi) = d
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(l, h), &x| (l.min(x), h.max(x)));
    if hi - lo <= 1e-6 * hi {
        return c;
    }
    let area = |f: [usize; 3]| {
        let n = crate::geometry::cross(&sub(&p[f[1]], &p[f[0]]), &sub(&p[f[2]], &p[f[0]]));
        dot(&n, &n)
    };
    let faces = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];
    let largest = faces
        .into_iter()
        .max_by(|&a, &b| area(a).total_cmp(&area(b)))
        .unwrap_or([0, 1, 2]);
    triangle_circumcenter(largest.map(|k| &p[k]))
}

/// Circumradius over shortest edge of tetrahedron `t` (infinite when flat).
fn radius_edge_ratio(mesh: &TetMesh, t: u32) -> f64 {
    crate::quality::radius_edge(mesh.tets.vertices(t).map(|v| mesh.point(v)))
}

/// Squared distance from `p` to segment `ab` where `p` projects inside it, else infinity.
fn segment_distance2(p: &Point, a: &Point, b: &Point) -> f64 {
    let ab = sub(b, a);
    let s = dot(&sub(p, a), &ab) / dot(&ab, &ab);
    if !(0.0..=1.0).contains(&s) {
        return f64::INFINITY;
    }
    dist2(p, &[a[0] + s * ab[0], a[1] + s * ab[1], a[2] + s * ab[2]])
}

/// Distance from `p` to the plane of triangle `t` where `p` projects inside it, else
/// infinity.
fn triangle_distance(p: &Point, t: [&Point; 3]) -> f64 {
    let (u, w) = (sub(t[1], t[0]), sub(t[2], t[0]));
    let n = crate::geometry::cross(&u, &w);
    let nn = dot(&n, &n);
    let h = dot(&sub(p, t[0]), &n) / nn;
    let q = [p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]];
    let inside = (0..3).all(|k| {
        let (a, b) = (t[k], t[(k + 1) % 3]);
        dot(&crate::geometry::cross(&sub(b, a), &sub(&q, a)), &n) >= 0.0
    });
    if inside {
        h.abs() * nn.sqrt()
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::{BadQueue, Split};

    #[test]
    fn bad_queue_gives_the_worst_first_and_keeps_arrival_order_among_equals() {
        let mut queue = BadQueue::new();
        let excesses = [1.5, 40.0, 1.5, f64::INFINITY, 3.0, 1.0 + 1e-9, 40.0];
        for (t, &excess) in excesses.iter().enumerate() {
            queue.push(excess, (t as u32, [0; 4], Split::Ratio));
        }
        let order: Vec<u32> = std::iter::from_fn(|| queue.pop().map(|(t, _, _)| t)).collect();
        assert_eq!(order, [3, 1, 6, 4, 0, 2, 5]);
        queue.push(2.0, (7, [0; 4], Split::Volume));
        assert_eq!(queue.pop().map(|(t, _, _)| t), Some(7));
        assert!(queue.pop().is_none());
    }
}
