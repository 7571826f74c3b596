//! The tetrahedral mesh that boundary recovery edits by local operations (George and
//! Borouchaki §5.2: flips, shell and face splits, point moves), on the flat storage of the
//! Delaunay triangulation it starts from ([`Tets`]).
//!
//! Unlike [`crate::triangulation::Triangulation`] the mesh is not kept Delaunay: every change
//! is a [`TetMesh::replace`] of a set of tetrahedra by another set with the same boundary,
//! accepted only when every new tetrahedron is positively oriented (exact `orient3d`). A
//! point added on the input surface is, for the orientation tests, exactly the combination
//! of input vertices it was added as ([`TetMesh::add_point_on`]), until it moves.
//!
//! Invariants (those of [`Tets`], checked by [`TetMesh::validate`]): vertex ids index
//! `points`; every live finite tetrahedron is positively oriented; adjacency is symmetric;
//! `vertex_tet[v]` is a live tetrahedron incident to `v` for every vertex in use;
//! `rings` and `exact_signs` hold only triangulations, failures and signs that the points'
//! current positions make (they are emptied when a point moves, is rounded or its number is
//! given back); `failed_fills` holds only failures of
//! surfaces whose key, positions included, it stores; `bounds` holds every point.

use std::cell::RefCell;

use rustc_hash::FxHashSet;
use smallvec::SmallVec;

use super::by_vertex::ByVertex;
use super::flips::{Memo, Protected, RingMemo};
use super::suppress::FailedFills;
use crate::error::{Error, Result};
use crate::predicates::combination::{self, Combination, Exact};
use crate::predicates::{insphere, orient3d, BoxFilter, Point, Sign};
use crate::triangulation::edge_table::EdgeTable;
use crate::triangulation::tets::{Tets, FACE, INFINITE};
use crate::triangulation::Triangulation;

/// The tetrahedra or the ring vertices of an edge's shell: most have at most 16, kept
/// without allocating (edge removal looks at shells by the thousand).
pub type Shell = SmallVec<[u32; 16]>;

/// No tetrahedron (a vertex not in the mesh).
pub const NONE: u32 = u32::MAX;

/// A facet by its sorted vertices.
pub type Key = [u32; 3];

/// The set of `items`, one per flag set in `flags`, allocated once.
fn flagged<T: Eq + std::hash::Hash>(
    flags: &[bool],
    items: impl Iterator<Item = T>,
) -> FxHashSet<T> {
    let n = flags.iter().filter(|&&f| f).count();
    let mut set = FxHashSet::with_capacity_and_hasher(n, Default::default());
    set.extend(items);
    set
}

/// The sorted vertices of a facet.
pub fn key([a, b, c]: [u32; 3]) -> Key {
    // A sorting network: three compare-exchanges.
    let (a, b) = (a.min(b), a.max(b));
    let (b, c) = (b.min(c), b.max(c));
    let (a, b) = (a.min(b), a.max(b));
    [a, b, c]
}

/// The vertices of `q` in increasing order.
fn sorted(mut q: [u32; 4]) -> [u32; 4] {
    q.sort_unstable();
    q
}

/// A point added on the input surface: exactly the combination `at` of the input vertices
/// `corners` (an edge's ends with the first repeated, or a triangle's corners).
#[derive(Clone, Debug)]
struct OnSurface {
    at: Combination,
    corners: [u32; 3],
}

pub struct TetMesh {
    /// Moved only by [`TetMesh::move_point`]; for a point added on the input surface, the
    /// rounding of its combination.
    pub points: Vec<Point>,
    /// The exact position of every point added on the input surface, as a combination of
    /// an input triangle's or edge's corners ([`TetMesh::add_point_on`]), which the
    /// orientation tests use.
    on_surface: Vec<Option<Box<OnSurface>>>,
    pub tets: Tets,
    vertex_tet: Vec<u32>,
    /// The search buffer of [`TetMesh::search_ball`].
    scratch: Vec<u32>,
    /// The edge table of [`TetMesh::try_replace_by_cone`].
    edges: EdgeTable,
    /// Points from this id on were added after the Delaunay triangulation.
    first_added: u32,
    /// A tetrahedron was replaced or a point added since the Delaunay triangulation.
    changed: bool,
    /// The triangulations of edges' rings (or their absence) known while no point moves.
    pub rings: RingMemo,
    /// Orientations that needed the exact stage of [`TetMesh::orient_on_surface`].
    exact_signs: RefCell<ExactSigns>,
    /// Surfaces known to have no filling without points.
    pub failed_fills: FailedFills,
    /// A box holding every point (grown as points are added or moved), and the filter of the
    /// predicates for points in it: its bound is fixed by the box, not computed per call
    /// (as the Delaunay triangulation's). A point tested before it is added, outside the
    /// box, gets the ordinary filter.
    bounds: [Point; 2],
    filter: BoxFilter,
    /// The largest [`Combination::error`] of the points added on the surface.
    surface_error: f64,
    /// The replacements made since [`TetMesh::begin`], while one is under way.
    journal: Option<Vec<Replacement>>,
    /// The order in which recovery takes the sub-edges it finds missing in this mesh, and in
    /// the meshes that fill regions of it anew.
    pub edge_order: EdgeOrder,
}

/// The order in which recovery takes missing sub-edges: the partition's, or the reverse. Which
/// sub-edges flips recover depends on it (a recovered one is no longer flipped away).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeOrder {
    Partition,
    Reversed,
}

/// One replacement of tetrahedra (their vertices, as stored): what [`TetMesh::undo`] puts
/// back.
#[derive(Debug)]
struct Replacement {
    old: Vec<[u32; 4]>,
    new: Vec<[u32; 4]>,
}

/// What the replacements since [`TetMesh::begin`] changed, each tetrahedron by its vertices
/// as stored: those gone that were there before, those there that were not, and all those
/// made that are still there (with the ones removed and made again, under new ids).
#[derive(Debug, Default)]
pub struct Change {
    pub removed: Vec<[u32; 4]>,
    pub created: Vec<[u32; 4]>,
    pub made: Vec<[u32; 4]>,
    journal: Vec<Replacement>,
}

/// The signs of the orientations that [`TetMesh::orient_on_surface`] could not decide by its
/// filter, by the tetrahedron's sorted vertices: a cache. The flips that recover edges and
/// fill stars test the same tetrahedra again and again (on anchor, 98% of 6.9 million such
/// tests had been made before, and the exact stage took a quarter of the time). At most
/// [`ExactSigns::MOST`] are held; then all are forgotten and remembered anew.
#[derive(Default)]
struct ExactSigns(Memo<[u32; 4], Sign, { ExactSigns::MOST }>);

impl ExactSigns {
    const MOST: usize = 1 << 17;

    /// The sign of `q`'s orientation, if known.
    fn get(&self, q: [u32; 4]) -> Option<Sign> {
        let (key, odd) = sorted_with_parity(q);
        let sign = *self.0.get(&key)?;
        Some(if odd { sign.negate() } else { sign })
    }

    fn insert(&mut self, q: [u32; 4], sign: Sign) {
        let (key, odd) = sorted_with_parity(q);
        self.0.insert(key, if odd { sign.negate() } else { sign });
    }

    fn clear(&mut self) {
        self.0.clear();
    }
}

/// The vertices of `q` in increasing order, and whether that order is an odd permutation of
/// `q` (the orientation's sign changes with each exchange).
fn sorted_with_parity(mut q: [u32; 4]) -> ([u32; 4], bool) {
    let mut odd = false;
    for i in 1..4 {
        let mut j = i;
        while j > 0 && q[j - 1] > q[j] {
            q.swap(j - 1, j);
            odd = !odd;
            j -= 1;
        }
    }
    (q, odd)
}

/// A copy without the scratch tables and with no ring, exact sign or failed filling
/// remembered: those are only looked up again, the copy meshes as the original would.
impl Clone for TetMesh {
    fn clone(&self) -> Self {
        TetMesh {
            points: self.points.clone(),
            on_surface: self.on_surface.clone(),
            tets: self.tets.clone(),
            vertex_tet: self.vertex_tet.clone(),
            scratch: Vec::new(),
            edges: EdgeTable::default(),
            first_added: self.first_added,
            changed: self.changed,
            rings: RingMemo::default(),
            exact_signs: RefCell::default(),
            failed_fills: FailedFills::default(),
            bounds: self.bounds,
            filter: self.filter,
            surface_error: self.surface_error,
            journal: None,
            edge_order: self.edge_order,
        }
    }
}

impl TetMesh {
    /// The Delaunay triangulation of the points `used` (indices into `points`, pairwise
    /// distinct positions, not all coplanar); other points are not in the mesh.
    pub fn delaunay(points: Vec<Point>, used: &[u32]) -> Result<Self> {
        let xyz: Vec<f64> = used.iter().flat_map(|&v| points[v as usize]).collect();
        let mut triangulation = Triangulation::new(&xyz, None)?;
        triangulation.insert_all()?;
        let mut tets = triangulation.into_input_numbered();
        for t in 0..tets.slots() as u32 {
            if tets.is_live(t) {
                let v = tets.vertices(t);
                tets.set(
                    t,
                    v.map(|x| if x == INFINITE { x } else { used[x as usize] }),
                );
            }
        }
        let mut mesh = TetMesh {
            vertex_tet: vec![NONE; points.len()],
            on_surface: vec![None; points.len()],
            points,
            tets,
            scratch: Vec::new(),
            edges: EdgeTable::default(),
            first_added: 0,
            changed: false,
            rings: RingMemo::default(),
            exact_signs: RefCell::default(),
            failed_fills: FailedFills::default(),
            bounds: [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]],
            filter: BoxFilter::new(&[0.0; 3], &[0.0; 3]),
            surface_error: 0.0,
            journal: None,
            edge_order: EdgeOrder::Partition,
        };
        for v in 0..mesh.points.len() as u32 {
            mesh.enclose(v);
        }
        mesh.first_added = mesh.points.len() as u32;
        for t in 0..mesh.tets.slots() as u32 {
            if mesh.tets.is_live(t) {
                mesh.note_vertices(t);
            }
        }
        Ok(mesh)
    }

    fn note_vertices(&mut self, t: u32) {
        for v in self.tets.vertices(t) {
            if v != INFINITE {
                self.vertex_tet[v as usize] = t;
            }
        }
    }

    #[inline]
    pub fn point(&self, v: u32) -> &Point {
        &self.points[v as usize]
    }

    /// Whether the mesh is still the Delaunay triangulation it was built as: no tetrahedron
    /// replaced and no point added since (added points are the only ones that move).
    pub fn is_delaunay(&self) -> bool {
        !self.changed
    }

    /// Adds a point (in no tetrahedron yet) and returns its id.
    pub fn add_point(&mut self, p: Point) -> u32 {
        self.changed = true;
        self.points.push(p);
        self.on_surface.push(None);
        self.vertex_tet.push(NONE);
        let v = (self.points.len() - 1) as u32;
        self.enclose(v);
        v
    }

    /// Adds the point `at`, a combination of the vertices `corners` (in no tetrahedron yet),
    /// and returns its id: its coordinates are the rounding of `at`, its position for the
    /// orientation tests `at` itself.
    pub fn add_point_on(&mut self, at: Combination, corners: [u32; 3]) -> u32 {
        let v = self.add_point(at.approx());
        self.surface_error = self.surface_error.max(at.error());
        self.on_surface[v as usize] = Some(Box::new(OnSurface { at, corners }));
        v
    }

    /// Drops the exact position of every point added on the surface that is still in the
    /// mesh: its coordinates are its position from now on, and the orientation tests take
    /// the plain path again. `false` where a tetrahedron around such a point is no longer
    /// positive then (those points stay as they were).
    pub fn round_points_on_surface(&mut self) -> bool {
        let left: Vec<u32> = (self.first_added..self.points.len() as u32)
            .filter(|&v| self.on_surface[v as usize].is_some() && self.in_mesh(v))
            .collect();
        let kept = std::mem::replace(&mut self.on_surface, vec![None; self.points.len()]);
        let error = std::mem::replace(&mut self.surface_error, 0.0);
        let positive = left.iter().all(|&v| {
            let ball = self.ball(v);
            ball.iter().all(|&t| {
                let q = self.tets.vertices(t);
                q.contains(&INFINITE) || self.orient(q) == Sign::Positive
            })
        });
        if positive {
            self.exact_signs.get_mut().clear();
            self.rings.clear();
        } else {
            self.on_surface = kept;
            self.surface_error = error;
        }
        positive
    }

    /// How the orientation tests take vertex `v`.
    fn exact(&self, v: u32) -> Exact<'_> {
        match &self.on_surface[v as usize] {
            Some(c) => Exact::Combination(&c.at),
            None => Exact::Float(self.point(v)),
        }
    }

    /// The vertices `v`, and in place of the points on the surface among them the vertices
    /// they are combinations of, each once.
    fn spanning(&self, v: [u32; 4]) -> SmallVec<[u32; 12]> {
        let mut ids = SmallVec::new();
        for x in v {
            let of = match &self.on_surface[x as usize] {
                Some(c) => c.corners,
                None => [x; 3],
            };
            for w in of {
                if !ids.contains(&w) {
                    ids.push(w);
                }
            }
        }
        ids
    }

    /// Whether the vertices `ids` (spanning four points, [`TetMesh::spanning`]) are at most
    /// three, or lie on the plane of three of them that are not collinear (exact tests on
    /// their coordinates): points on one input triangle, or on coplanar ones, are decided so
    /// without their exact coordinates.
    fn on_one_plane(&self, ids: &[u32]) -> bool {
        if ids.len() <= 3 {
            return true;
        }
        let p = |x: u32| self.point(x);
        let (a, b) = (p(ids[0]), p(ids[1]));
        let Some(c) = ids[2..]
            .iter()
            .map(|&x| p(x))
            .find(|c| !super::validate::is_degenerate(&[a, b, c]))
        else {
            return true;
        };
        ids[2..]
            .iter()
            .all(|&x| orient3d(a, b, c, p(x)) == Sign::Zero)
    }

    /// Whether one of `vertices` was added on the surface, exactly (input vertices, most
    /// vertices of most tests, are not looked up).
    #[inline]
    fn any_on_surface(&self, vertices: &[u32]) -> bool {
        self.surface_error > 0.0
            && vertices
                .iter()
                .any(|&v| v >= self.first_added && self.on_surface[v as usize].is_some())
    }

    /// Grows the filter's box to hold point `v` where it does not.
    fn enclose(&mut self, v: u32) {
        let p = self.points[v as usize];
        if self.in_box(&p) {
            return;
        }
        let [lo, hi] = &mut self.bounds;
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
        self.filter = BoxFilter::new(lo, hi);
    }

    /// Whether `p` lies in the filter's box.
    fn in_box(&self, p: &Point) -> bool {
        let [lo, hi] = &self.bounds;
        (0..3).all(|k| lo[k] <= p[k] && p[k] <= hi[k])
    }

    /// Exact orientation of the facet of vertices `f` and point `p`.
    #[inline]
    pub fn orient_point(&self, f: [u32; 3], p: &Point) -> Sign {
        if self.any_on_surface(&f) {
            let [a, b, c] = f.map(|x| self.exact(x));
            return combination::orient3d([a, b, c, Exact::Float(p)]);
        }
        let [a, b, c] = f.map(|x| self.point(x));
        if self.in_box(p) {
            self.filter.orient3d(a, b, c, p)
        } else {
            orient3d(a, b, c, p)
        }
    }

    /// Exact in-sphere test of point `e` against the tetrahedron of vertices `v` (positively
    /// oriented): positive when `e` is strictly inside its circumsphere.
    #[inline]
    pub fn insphere(&self, v: [u32; 4], e: &Point) -> Sign {
        let [a, b, c, d] = v.map(|x| self.point(x));
        if self.in_box(e) {
            self.filter.insphere(a, b, c, d, e)
        } else {
            insphere(a, b, c, d, e)
        }
    }

    /// The first point added after the Delaunay triangulation.
    pub fn first_added(&self) -> u32 {
        self.first_added
    }

    /// Whether `v` was added after the Delaunay triangulation (a Steiner point).
    pub fn is_added(&self, v: u32) -> bool {
        v >= self.first_added
    }

    /// Drops the last point added, which no tetrahedron uses.
    pub fn pop_point(&mut self) {
        self.points.pop();
        self.on_surface.pop();
        self.vertex_tet.pop();
        // The next point added takes its number.
        self.rings.clear();
        self.exact_signs.get_mut().clear();
    }

    /// Moves point `v` to `p`.
    pub fn move_point(&mut self, v: u32, p: Point) {
        self.points[v as usize] = p;
        self.on_surface[v as usize] = None;
        self.enclose(v);
        self.rings.clear();
        self.exact_signs.get_mut().clear();
    }

    /// Whether vertex `v` is in some tetrahedron.
    pub fn in_mesh(&self, v: u32) -> bool {
        self.vertex_tet[v as usize] != NONE
    }

    /// A vertex of a tetrahedron at vertex `v` off the plane of `v`, `p` and `q` (none when
    /// `v` is not in the mesh or that tetrahedron has its finite vertices in the plane).
    pub fn off_plane(&self, [v, p, q]: [u32; 3]) -> Option<u32> {
        let t = *self.vertex_tet.get(v as usize).filter(|&&t| t != NONE)?;
        (self.tets.vertices(t).into_iter())
            .find(|&x| x != INFINITE && self.orient([v, p, q, x]) != Sign::Zero)
    }

    /// Exact orientation of four finite vertices.
    #[inline]
    pub fn orient(&self, v: [u32; 4]) -> Sign {
        if self.any_on_surface(&v) {
            return self.orient_on_surface(v);
        }
        self.filter.orient3d(
            self.point(v[0]),
            self.point(v[1]),
            self.point(v[2]),
            self.point(v[3]),
        )
    }

    /// [`TetMesh::orient`] where a vertex was added on the surface: the box's filter widened
    /// by the rounding of such points, then the filter and exact stage of combinations,
    /// asking before the exact stage whether the vertices they are combinations of lie on
    /// one plane.
    #[inline(never)]
    fn orient_on_surface(&self, v: [u32; 4]) -> Sign {
        let [a, b, c, d] = v.map(|x| self.point(x));
        if let Some(sign) = self.filter.orient3d_moved(a, b, c, d, self.surface_error) {
            return sign;
        }
        if let Some(sign) = self.exact_signs.borrow().get(v) {
            return sign;
        }
        let on_one_plane = || self.on_one_plane(&self.spanning(v));
        let sign = combination::orient3d_or(v.map(|x| self.exact(x)), on_one_plane);
        self.exact_signs.borrow_mut().insert(v, sign);
        sign
    }

    /// Whether the quadruple is a finite, positively oriented tetrahedron.
    pub fn positive(&self, v: [u32; 4]) -> bool {
        !v.contains(&INFINITE) && self.orient(v) == Sign::Positive
    }

    /// The tetrahedra incident to `v`, found by a search across facets from `vertex_tet`.
    pub fn ball(&mut self, v: u32) -> Vec<u32> {
        let mut ball = Vec::new();
        self.search_ball(v, |_, t| {
            ball.push(t);
            None::<()>
        });
        ball
    }

    /// Visits the tetrahedra incident to `v` (a search across facets from `vertex_tet`) until
    /// `found` returns something.
    pub fn search_ball<T>(
        &mut self,
        v: u32,
        mut found: impl FnMut(&Self, u32) -> Option<T>,
    ) -> Option<T> {
        let start = self.vertex_tet[v as usize];
        if start == NONE {
            return None;
        }
        let mut seen = std::mem::take(&mut self.scratch);
        seen.clear();
        seen.push(start);
        self.tets.mark[start as usize] = 1;
        let mut k = 0;
        let mut result = None;
        while k < seen.len() {
            let t = seen[k];
            k += 1;
            result = found(self, t);
            if result.is_some() {
                break;
            }
            let verts = self.tets.vertices(t);
            for (i, &x) in verts.iter().enumerate() {
                if x == v {
                    continue;
                }
                let n = self.tets.neighbor(t, i);
                if self.tets.mark[n as usize] == 0 {
                    self.tets.mark[n as usize] = 1;
                    seen.push(n);
                }
            }
        }
        for &t in &seen {
            self.tets.mark[t as usize] = 0;
        }
        self.scratch = seen;
        result
    }

    /// The tetrahedron whose closure holds `c`, by a visibility walk from `t`: facet `i` of
    /// tetrahedron `at`, whose plane has `c` strictly beyond it, is crossed into `next` when
    /// `may_cross(self, at, i, next)`. `None` when a crossing is refused or the walk takes
    /// more than `steps` steps.
    pub fn walk(
        &self,
        t: u32,
        c: &Point,
        steps: usize,
        may_cross: impl Fn(&TetMesh, u32, usize, u32) -> bool,
    ) -> Option<u32> {
        let mut at = t;
        'walk: for _ in 0..steps {
            for i in 0..4 {
                if self.orient_point(self.facet(at, i), c) == Sign::Negative {
                    let n = self.tets.neighbor(at, i);
                    if !may_cross(self, at, i, n) {
                        return None;
                    }
                    at = n;
                    continue 'walk;
                }
            }
            return Some(at);
        }
        None
    }

    /// The protected edges (sorted pairs) and facets (sorted triples) that are in the mesh;
    /// `None` when they all are (every protected edge is a side of a protected facet: most
    /// inputs are so in their Delaunay triangulation, and their sets are not built).
    /// The protected sets are looked up in lists by smallest vertex ([`ByVertex`]), the
    /// hits flagged, and the result sets built once from the flags. Facets are found in one
    /// pass over the tetrahedra, each facet once; only when some is missing are the edges
    /// listed: a facet found brings its edges, and only the protected edges of no facet
    /// found are searched around their smaller vertex (bunny00: 158 -> 97 million
    /// instructions against looking up the six edges of every tetrahedron).
    pub fn present(
        &mut self,
        protected: &Protected,
    ) -> Option<(FxHashSet<[u32; 2]>, FxHashSet<Key>)> {
        let n = self.points.len();
        let facet_lists = ByVertex::new(n, protected.facets.iter().map(|&[a, b, c]| (a, [b, c])));
        let mut facet_found = vec![false; facet_lists.items.len()];
        for t in self.tets.live() {
            for i in 0..4 {
                if self.tets.neighbor(t, i) < t {
                    continue; // each facet once, from the lower of its two tetrahedra
                }
                let [a, b, c] = key(self.facet(t, i));
                if let Some(k) = facet_lists.position(a, &[b, c]) {
                    facet_found[k] = true;
                }
            }
        }
        if facet_found.iter().all(|&f| f) {
            return None;
        }
        let edge_lists = ByVertex::new(n, protected.edges.iter().map(|&[a, b]| (a, b)));
        let mut edge_found = vec![false; edge_lists.items.len()];
        for (a, [b, c]) in facet_lists.pairs(&facet_found) {
            for (x, y) in [(a, b), (a, c), (b, c)] {
                if let Some(j) = edge_lists.position(x, &y) {
                    edge_found[j] = true;
                }
            }
        }
        for (a, k) in edge_lists.entries() {
            if !edge_found[k] {
                edge_found[k] = self.find_edge(a, edge_lists.items[k]).is_some();
            }
        }
        let edges = flagged(
            &edge_found,
            edge_lists.pairs(&edge_found).map(|(a, b)| [a, b]),
        );
        let facets = flagged(
            &facet_found,
            facet_lists.pairs(&facet_found).map(|(a, [b, c])| [a, b, c]),
        );
        Some((edges, facets))
    }

    /// A tetrahedron with edge `(a, b)`, if the edge exists.
    pub fn find_edge(&mut self, a: u32, b: u32) -> Option<u32> {
        self.search_ball(a, |m, t| m.tets.vertices(t).contains(&b).then_some(t))
    }

    /// The facet `(t, i)` (tetrahedron and local index of the opposite vertex) with vertices
    /// `f`, if it exists; either of its two tetrahedra.
    pub fn find_face(&mut self, f: [u32; 3]) -> Option<(u32, usize)> {
        self.search_ball(f[0], |m, t| {
            let v = m.tets.vertices(t);
            if !(v.contains(&f[1]) && v.contains(&f[2])) {
                return None;
            }
            v.iter().position(|x| !f.contains(x)).map(|i| (t, i))
        })
    }

    /// The vertices of facet `i` of `t` (opposite vertex `i`), seen counter-clockwise from
    /// inside `t`.
    #[inline]
    pub fn facet(&self, t: u32, i: usize) -> [u32; 3] {
        let v = self.tets.vertices(t);
        FACE[i].map(|k| v[k])
    }

    /// Whether `t` lies in front of (on the right-hand normal side of) its facet `i`, given
    /// as the oriented triangle `s`: the apex of `t` sees its stored facet counter-clockwise,
    /// so `t` is in front of `s` iff `s` is an even rotation of it.
    pub fn in_front(&self, t: u32, i: usize, s: [u32; 3]) -> bool {
        even_rotation(self.facet(t, i), s)
    }

    /// The vertex of the tetrahedron across facet `i` of `t` that is not on that facet.
    pub fn across(&self, t: u32, i: usize) -> u32 {
        let g = self.tets.glued(t, i);
        self.tets.vertices(g >> 2)[(g & 3) as usize]
    }

    /// `(apex, [x, y, z])` with `apex` the vertex `i` of `t` and `(apex, x, y, z)` positively
    /// oriented (an even permutation of the stored order).
    pub fn with_apex(&self, t: u32, i: usize) -> (u32, [u32; 3]) {
        let v = self.tets.vertices(t);
        let [f0, f1, f2] = FACE[i].map(|k| v[k]);
        (v[i], [f0, f2, f1])
    }

    /// The vertices `c, d` of tetrahedron `t` other than `a, b`, ordered so that `(a, b, c, d)`
    /// is an even permutation of the stored order.
    pub fn others(&self, t: u32, a: u32, b: u32) -> [u32; 2] {
        let v = self.tets.vertices(t);
        let i = v.iter().position(|&x| x == a).unwrap_or(0);
        let (_, f) = self.with_apex(t, i);
        // (a, f0, f1, f2) is even; rotate f (an even permutation) until b comes first.
        let r = f.iter().position(|&x| x == b).unwrap_or(0);
        [f[(r + 1) % 3], f[(r + 2) % 3]]
    }

    /// The tetrahedra around edge `(a, b)` of tetrahedron `t`, and the ring `w` of their other
    /// vertices: tetrahedron `k` is `(a, b, w[k], w[k+1])`, positively oriented (indices mod
    /// the ring length). `None` if the ring is not closed within `limit` steps.
    pub fn shell(&self, t: u32, a: u32, b: u32, limit: usize) -> Option<(Shell, Shell)> {
        let (mut tets, mut ring) = (Shell::new(), Shell::new());
        let closed = self.around_edge(t, a, b, limit, |u, w| {
            tets.push(u);
            ring.push(w);
        });
        closed.then_some((tets, ring))
    }

    /// Calls `visit` on every vertex of the ring of edge `(a, b)` of tetrahedron `t`, in
    /// [`TetMesh::shell`] order, without allocating.
    pub fn ring(&self, t: u32, a: u32, b: u32, mut visit: impl FnMut(u32)) {
        self.around_edge(t, a, b, self.tets.slots(), |_, w| visit(w));
    }

    /// Calls `visit(u, w)` on the tetrahedra `u = (a, b, w, w')` around edge `(a, b)` of
    /// tetrahedron `t`, in turn from `t`; whether they closed a ring within `limit`.
    fn around_edge(
        &self,
        t: u32,
        a: u32,
        b: u32,
        limit: usize,
        mut visit: impl FnMut(u32, u32),
    ) -> bool {
        // Tetrahedron `current` is (a, b, opposite, last): across the facet opposite
        // `opposite` is (a, b, last, next).
        let [c, d] = self.others(t, a, b);
        let (mut current, mut opposite, mut last) = (t, c, d);
        for _ in 0..limit {
            visit(current, opposite);
            let v = self.tets.vertices(current);
            let Some(i) = v.iter().position(|&x| x == opposite) else {
                return false;
            };
            let g = self.tets.glued(current, i);
            current = g >> 2;
            if current == t {
                return true;
            }
            let next = self.tets.vertices(current)[(g & 3) as usize];
            (opposite, last) = (last, next);
        }
        false
    }

    /// [`TetMesh::shell`] of an edge with exactly three tetrahedra around it (the 3-2 flip's),
    /// without allocating; `None` for any other count.
    pub fn shell3(&self, t: u32, a: u32, b: u32) -> Option<([u32; 3], [u32; 3])> {
        let [c, d] = self.others(t, a, b);
        let cross = |from: u32, opposite: u32| {
            let i = self
                .tets
                .vertices(from)
                .iter()
                .position(|&x| x == opposite)?;
            Some(self.tets.neighbor(from, i))
        };
        let t1 = cross(t, c)?;
        let [_, n1] = self.others(t1, a, b);
        let t2 = cross(t1, d)?;
        (t1 != t && t2 != t && cross(t2, n1)? == t).then_some(([t, t1, t2], [c, d, n1]))
    }

    /// The 3-2 flip of edge `(a, b)` whose shell and ring [`TetMesh::shell3`] gave: the
    /// tetrahedra `(a, w0, w1, w2)` and `(b, w0, w2, w1)`, glued directly (no facet matching);
    /// orientation is the caller's business. Returns their ids.
    pub fn flip32(
        &mut self,
        [a, b]: [u32; 2],
        shell: [u32; 3],
        [w0, w1, w2]: [u32; 3],
    ) -> Result<Vec<u32>> {
        // The facet of shell tetrahedron k, (a, b, w[k], w[k+1]), opposite x, glued outside.
        let outside = |k: usize, x: u32| self.outside(shell[k], x);
        // Facet i of a new tetrahedron is opposite its vertex i.
        let gluing = [
            [
                Glue::Inner(1, 0),
                outside(1, b),
                outside(2, b),
                outside(0, b),
            ],
            [
                Glue::Inner(0, 0),
                outside(1, a),
                outside(0, a),
                outside(2, a),
            ],
        ];
        let new = [[a, w0, w1, w2], [b, w0, w2, w1]];
        self.apply(&shell, &new, &gluing)
    }

    /// The facet glued to the facet of `t` opposite its vertex `x`, as a gluing of a new
    /// tetrahedron that replaces `t` on that side.
    fn outside(&self, t: u32, x: u32) -> Glue {
        let v = self.tets.vertices(t);
        let i = v.iter().position(|&y| y == x).unwrap_or(0);
        Glue::Outer(self.tets.glued(t, i))
    }

    /// Removes edge `(a, b)`, with the shell and ring [`TetMesh::shell`] gave, by the
    /// triangulation `triangles` of its ring polygon (index triples `(i, k, j)`, `i < k < j`):
    /// the tetrahedra `(a, w_j, w_i, w_k)` and `(b, w_j, w_k, w_i)` of each triangle, in that
    /// order, glued directly: across the triangle to each other, across a side of the ring to
    /// the shell's outside, across a diagonal to the two of the other triangle on it (no
    /// facet matching). Orientation is the caller's business. Returns their ids.
    pub fn remove_edge_by_ring(
        &mut self,
        [a, b]: [u32; 2],
        (shell, ring): (&[u32], &[u32]),
        triangles: &[[usize; 3]],
    ) -> Result<Vec<u32>> {
        let n = ring.len();
        // The facet of shell tetrahedron m, (a, b, w_m, w_m+1), opposite x, glued outside.
        let outside = |m: usize, x: u32| self.outside(shell[m], x);
        let mut new = Vec::with_capacity(2 * triangles.len());
        let mut gluing = Vec::with_capacity(2 * triangles.len());
        // Diagonals met once: (i, j), the triangle's first new tetrahedron, and the facets
        // of both new tetrahedra on it.
        let mut open: Vec<([usize; 2], usize, [usize; 2])> = Vec::with_capacity(n);
        for (t, &[i, k, j]) in triangles.iter().enumerate() {
            let (wi, wk, wj) = (ring[i], ring[k], ring[j]);
            new.push([a, wj, wi, wk]);
            new.push([b, wj, wk, wi]);
            let (x, y) = (2 * t, 2 * t + 1);
            gluing.push([Glue::Inner(y, 0); 4]);
            gluing.push([Glue::Inner(x, 0); 4]);
            // Facet 1 of (a, w_j, w_i, w_k) holds (w_i, w_k), facet 2 (w_k, w_j), facet 3
            // (w_i, w_j); of (b, w_j, w_k, w_i), facets 1, 3, 2.
            for (edge, [fa, fb]) in [([i, k], [1, 1]), ([k, j], [2, 3]), ([i, j], [3, 2])] {
                let side = match edge {
                    [p, q] if q == p + 1 => Some(p),
                    [0, q] if q == n - 1 => Some(q),
                    _ => None,
                };
                if let Some(m) = side {
                    gluing[x][fa] = outside(m, b);
                    gluing[y][fb] = outside(m, a);
                } else if let Some(o) = open.iter().position(|&(e, ..)| e == edge) {
                    let (_, u, [ga, gb]) = open.swap_remove(o);
                    gluing[x][fa] = Glue::Inner(u, ga);
                    gluing[u][ga] = Glue::Inner(x, fa);
                    gluing[y][fb] = Glue::Inner(u + 1, gb);
                    gluing[u + 1][gb] = Glue::Inner(y, fb);
                } else {
                    open.push((edge, x, [fa, fb]));
                }
            }
        }
        if !open.is_empty() || triangles.len() + 2 != n {
            return Err(Error::internal(format!(
                "the ring triangulation {triangles:?} of edge ({a}, {b}) does not tile its \
                 polygon of {n} vertices"
            )));
        }
        self.apply(shell, &new, &gluing)
    }

    /// Replaces the tetrahedra `old` by `new` (vertex quadruples), which must fill the same
    /// region: every facet of a new tetrahedron is either a boundary facet of `old` or a facet
    /// of exactly one other new tetrahedron, and every boundary facet of `old` is used. The
    /// check is done before anything changes; orientation is the caller's business. Returns
    /// the new tetrahedra's ids, in the order of `new`.
    pub fn replace(&mut self, old: &[u32], new: &[[u32; 4]]) -> Result<Vec<u32>> {
        let outer = self.outer_facets(old);
        let gluing = match_facets(&outer, new)?;
        self.apply(old, new, &gluing)
    }

    /// [`TetMesh::replace`] when `new` fills exactly the region of `old`, facet for facet,
    /// and every glued pair of facets is oppositely oriented (each new tetrahedron on the side
    /// of the old one it borders outside, two new ones on opposite sides of their facet);
    /// `None`, changing nothing, when it does not. With every new tetrahedron positive, the
    /// new ones then cover the region once: their oriented boundary is the region's.
    pub fn try_replace(&mut self, old: &[u32], new: &[[u32; 4]]) -> Result<Option<Vec<u32>>> {
        let outer = self.outer_facets(old);
        match match_facets(&outer, new) {
            Ok(gluing) if self.opposite(new, &gluing) => self.apply(old, new, &gluing).map(Some),
            _ => Ok(None),
        }
    }

    /// Whether every facet of `new` is glued to a facet of the opposite orientation.
    fn opposite(&self, new: &[[u32; 4]], gluing: &[[Glue; 4]]) -> bool {
        let facet = |q: &[u32; 4], i: usize| FACE[i].map(|k| q[k]);
        new.iter().zip(gluing).all(|(q, glue)| {
            glue.iter().enumerate().all(|(i, g)| match *g {
                Glue::Outer(f) => !self.in_front(f >> 2, (f & 3) as usize, facet(q, i)),
                Glue::Inner(m, j) => !even_rotation(facet(&new[m], j), facet(q, i)),
            })
        })
    }

    /// Replaces the tetrahedra `old` by the cone from vertex `s` over their boundary: the
    /// tetrahedra `[a, b, d, s]` of the boundary facets `(a, b, d)` in `cone`, each given with
    /// the facet glued to it outside. The facets through `s` are paired by their edge opposite
    /// `s` in a hash table (not by sorting `4n` facets and the boundary). `None` (nothing
    /// changed) when the cone's facets through `s` do not pair up.
    pub fn try_replace_by_cone(
        &mut self,
        old: &[u32],
        s: u32,
        cone: &[([u32; 3], u32)],
    ) -> Result<Option<Vec<u32>>> {
        let new: Vec<[u32; 4]> = cone.iter().map(|&([a, b, d], _)| [a, b, d, s]).collect();
        match cone_gluing(&mut self.edges, &new, cone) {
            Some(gluing) => self.apply(old, &new, &gluing).map(Some),
            None => Ok(None),
        }
    }

    fn apply(&mut self, old: &[u32], new: &[[u32; 4]], gluing: &[[Glue; 4]]) -> Result<Vec<u32>> {
        self.changed = true;
        if let Some(journal) = &mut self.journal {
            let old = old.iter().map(|&t| self.tets.vertices(t)).collect();
            journal.push(Replacement {
                old,
                new: new.to_vec(),
            });
        }
        for &t in old {
            self.tets.kill(t);
        }
        let mut ids = Vec::with_capacity(new.len());
        for &q in new {
            let t = self.tets.allocate()?;
            self.tets.set(t, q);
            ids.push(t);
        }
        for (n, glue) in gluing.iter().enumerate() {
            for (i, g) in glue.iter().enumerate() {
                let facet = 4 * ids[n] + i as u32;
                match *g {
                    Glue::Outer(f) => self.tets.glue(facet, f),
                    Glue::Inner(m, j) if m > n => self.tets.glue(facet, 4 * ids[m] + j as u32),
                    Glue::Inner(..) => {}
                }
            }
        }
        for &t in &ids {
            self.note_vertices(t);
        }
        Ok(ids)
    }

    /// The boundary facets of the set `old`, each with the facet glued to it outside.
    fn outer_facets(&mut self, old: &[u32]) -> Vec<(Key, u32)> {
        for &t in old {
            self.tets.mark[t as usize] = 2;
        }
        let mut outer: Vec<(Key, u32)> = Vec::with_capacity(2 * old.len() + 2);
        for &t in old {
            for i in 0..4 {
                if self.tets.mark[self.tets.neighbor(t, i) as usize] != 2 {
                    outer.push((key(self.facet(t, i)), self.tets.glued(t, i)));
                }
            }
        }
        for &t in old {
            self.tets.mark[t as usize] = 0;
        }
        outer
    }

    /// Starts noting the replacements, so that they can be undone together (TetGen's
    /// `flipnm` with its `unflip`): [`TetMesh::end`] tells what they changed.
    pub fn begin(&mut self) {
        self.journal = Some(Vec::new());
    }

    /// Stops noting the replacements made since [`TetMesh::begin`]: what they changed, to be
    /// kept as it is or undone ([`TetMesh::undo`]).
    pub fn end(&mut self) -> Change {
        let journal = self.journal.take().unwrap_or_default();
        // Per tetrahedron (by its vertices): made minus removed, whether it was made last,
        // and its vertices as stored. Each is made and removed at most once in turn.
        let mut count: rustc_hash::FxHashMap<[u32; 4], (i32, bool, [u32; 4])> = Default::default();
        for r in &journal {
            for &q in &r.old {
                let c = count.entry(sorted(q)).or_insert((0, false, q));
                (c.0, c.1) = (c.0 - 1, false);
            }
            for &q in &r.new {
                let c = count.entry(sorted(q)).or_insert((0, true, q));
                (c.0, c.1) = (c.0 + 1, true);
            }
        }
        let mut change = Change::default();
        let mut all: Vec<(i32, bool, [u32; 4])> = count.into_values().collect();
        all.sort_unstable();
        for (c, last_made, q) in all {
            if c < 0 {
                change.removed.push(q);
            } else if c > 0 {
                change.created.push(q);
            }
            if last_made {
                change.made.push(q);
            }
        }
        change.journal = journal;
        change
    }

    /// The live tetrahedron with the vertices `q`, if there is one.
    pub fn tet_of(&mut self, q: [u32; 4]) -> Option<u32> {
        let (t, i) = self.find_face([q[0], q[1], q[2]])?;
        [t, self.tets.neighbor(t, i)]
            .into_iter()
            .find(|&u| sorted(self.tets.vertices(u)) == sorted(q))
    }

    /// Undoes the replacements of `change`, the last first; returns the ids of the
    /// tetrahedra put back (the ones [`Change::removed`] lists).
    pub fn undo(&mut self, change: Change) -> Result<Vec<u32>> {
        let mut back = Vec::new();
        for r in change.journal.into_iter().rev() {
            let ids = r
                .new
                .iter()
                .map(|&q| self.tet_of(q))
                .collect::<Option<Vec<u32>>>()
                .ok_or_else(|| Error::internal("a replacement to undo is not in the mesh"))?;
            back.extend(self.replace(&ids, &r.old)?);
        }
        // Ids put back and removed again by an earlier replacement's undo may be reused.
        back.retain(|&t| self.tets.is_live(t));
        back.sort_unstable();
        back.dedup();
        Ok(back)
    }

    /// Marks `v` as no longer in the mesh (after a replacement that dropped it).
    pub fn forget(&mut self, v: u32) {
        self.vertex_tet[v as usize] = NONE;
    }

    /// Checks the invariants of the module documentation exactly.
    pub fn validate(&self) -> std::result::Result<(), String> {
        for t in self.tets.live() {
            let v = self.tets.vertices(t);
            if !v.contains(&INFINITE) && self.orient(v) != Sign::Positive {
                return Err(format!("tetrahedron {t} {v:?} is not positively oriented"));
            }
            for i in 0..4 {
                let g = self.tets.glued(t, i);
                let (n, j) = (g >> 2, (g & 3) as usize);
                if !self.tets.is_live(n) || self.tets.glued(n, j) != 4 * t + i as u32 {
                    return Err(format!("facet {i} of tetrahedron {t} is not glued back"));
                }
                if key(self.facet(t, i)) != key(self.facet(n, j)) {
                    return Err(format!(
                        "facet {i} of tetrahedron {t} is glued to another facet"
                    ));
                }
                if self.in_front(n, j, self.facet(t, i)) {
                    return Err(format!(
                        "tetrahedra {t} and {n} lie on the same side of their facet"
                    ));
                }
            }
        }
        let mut seen = FxHashSet::default();
        for t in self.tets.live() {
            let mut v = self.tets.vertices(t);
            v.sort_unstable();
            if !seen.insert(v) {
                return Err(format!("two tetrahedra have the vertices {v:?}"));
            }
        }
        for (v, &t) in self.vertex_tet.iter().enumerate() {
            if t != NONE && (!self.tets.is_live(t) || !self.tets.vertices(t).contains(&(v as u32)))
            {
                return Err(format!(
                    "vertex {v} points to tetrahedron {t}, not incident"
                ));
            }
        }
        Ok(())
    }
}

/// Whether `s` is `stored` (the same three vertices) turned the same way round.
fn even_rotation(stored: [u32; 3], s: [u32; 3]) -> bool {
    let r = stored.iter().position(|&x| x == s[0]).unwrap_or(0);
    stored[(r + 1) % 3] == s[1]
}

/// Where facet `i` of a new tetrahedron is glued.
#[derive(Clone, Copy)]
enum Glue {
    /// To this facet outside the replaced region.
    Outer(u32),
    /// To facet `j` of new tetrahedron `m`.
    Inner(usize, usize),
}

/// The gluing of the cone `new` (`[a, b, d, s]`, facet 3 glued outside as `cone` says): facet
/// `i < 3` of a tetrahedron holds `s` and the edge of its base without vertex `i`, shared
/// with exactly one other tetrahedron of the cone (the cavity is star-shaped from `s`, its
/// boundary a sphere); `None` when the edges do not pair up.
fn cone_gluing(
    edges: &mut EdgeTable,
    new: &[[u32; 4]],
    cone: &[([u32; 3], u32)],
) -> Option<Vec<[Glue; 4]>> {
    edges.reset(3 * new.len());
    let mut gluing: Vec<[Glue; 4]> = cone.iter().map(|&(_, f)| [Glue::Outer(f); 4]).collect();
    let mut pairs = 0;
    for (n, q) in new.iter().enumerate() {
        for i in 0..3 {
            let (x, y) = (q[(i + 1) % 3], q[(i + 2) % 3]);
            if let Some(other) = edges.take_or_insert(x, y, (4 * n + i) as u32) {
                let (m, j) = (other as usize / 4, other as usize % 4);
                gluing[n][i] = Glue::Inner(m, j);
                gluing[m][j] = Glue::Inner(n, i);
                pairs += 1;
            }
        }
    }
    (2 * pairs == 3 * new.len()).then_some(gluing)
}

/// The gluing of the new tetrahedra's facets, or an internal error naming the first facet
/// that matches nothing (or too much).
fn match_facets(outer: &[(Key, u32)], new: &[[u32; 4]]) -> Result<Vec<[Glue; 4]>> {
    // Keys packed above a 32-bit payload: sorting integers, not tuples of arrays.
    let pack = |k: Key, low: u32| {
        (k[0] as u128) << 96 | (k[1] as u128) << 64 | (k[2] as u128) << 32 | low as u128
    };
    let unpack_key = |x: u128| [(x >> 96) as u32, (x >> 64) as u32, (x >> 32) as u32];
    let mut facets: Vec<u128> = Vec::with_capacity(4 * new.len());
    for (n, q) in new.iter().enumerate() {
        for (i, face) in FACE.iter().enumerate() {
            facets.push(pack(key(face.map(|k| q[k])), (4 * n + i) as u32));
        }
    }
    facets.sort_unstable();
    let mut outer: Vec<u128> = outer.iter().map(|&(k, f)| pack(k, f)).collect();
    outer.sort_unstable();
    let mut gluing = vec![[Glue::Outer(0); 4]; new.len()];
    let mismatch =
        |k: &Key| Error::internal(format!("retriangulation facet {k:?} matches no facet"));
    // The new tetrahedron and facet a packed facet of `new` names.
    let slot = |x: u128| ((x as u32 / 4) as usize, (x as u32 % 4) as usize);
    let (mut a, mut b) = (0, 0);
    while a < facets.len() {
        let k = facets[a] >> 32;
        let (n, i) = slot(facets[a]);
        if a + 1 < facets.len() && facets[a + 1] >> 32 == k {
            if a + 2 < facets.len() && facets[a + 2] >> 32 == k {
                return Err(mismatch(&unpack_key(facets[a])));
            }
            let (m, j) = slot(facets[a + 1]);
            gluing[n][i] = Glue::Inner(m, j);
            gluing[m][j] = Glue::Inner(n, i);
            a += 2;
            continue;
        }
        if b < outer.len() && outer[b] >> 32 < k {
            return Err(mismatch(&unpack_key(outer[b])));
        }
        if b == outer.len() || outer[b] >> 32 != k {
            return Err(mismatch(&unpack_key(facets[a])));
        }
        gluing[n][i] = Glue::Outer(outer[b] as u32);
        b += 1;
        a += 1;
    }
    if b < outer.len() {
        return Err(mismatch(&unpack_key(outer[b])));
    }
    Ok(gluing)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tetrahedron with awkward coordinates (none a short binary fraction).
    fn mesh() -> TetMesh {
        let points = vec![
            [0.1, 0.2, 0.3],
            [1.7, 0.3, 0.1],
            [0.3, 1.9, 0.7],
            [0.5, 0.6, 2.3],
        ];
        TetMesh::delaunay(points, &[0, 1, 2, 3]).unwrap()
    }

    /// Points added on a triangle or an edge are on its plane for the orientation tests, by
    /// the corners they are combinations of or by their exact coordinates, though their
    /// rounded coordinates are not; moved, they are their coordinates.
    #[test]
    fn points_added_on_the_surface_are_exactly_on_it() {
        let mut mesh = mesh();
        let corners = [0, 1, 2];
        let at = |m: &TetMesh, u, v| Combination::new(corners.map(|x| *m.point(x)), u, v);
        let mut added = Vec::new();
        let mut rounded_off = 0;
        for k in 0..40 {
            let (u, v) = (0.013 * f64::from(k), 0.31 - 0.007 * f64::from(k));
            let s = mesh.add_point_on(at(&mesh, u, v), corners);
            assert_eq!(mesh.orient([0, 1, 2, s]), Sign::Zero);
            let [a, b, c] = corners.map(|x| mesh.point(x));
            if orient3d(a, b, c, mesh.point(s)) != Sign::Zero {
                rounded_off += 1;
            }
            added.push(s);
        }
        assert!(rounded_off > 10, "{rounded_off}");
        // Two points of the triangle and two on its edge (0, 1): spanned by its corners.
        let edge = [0, 1, 0].map(|x| *mesh.point(x));
        let e = [0.37, 0.61].map(|u| mesh.add_point_on(Combination::new(edge, u, 0.0), [0, 1, 0]));
        let four = [added[3], added[17], e[0], e[1]];
        assert_eq!(mesh.orient(four), Sign::Zero);
        assert_eq!(mesh.spanning(four).len(), 3);
        // Two of the triangle and two of the edge from its corner 0 to the apex: four
        // vertices span them, not on one plane, decided on their exact coordinates.
        let apex_edge = [0, 3, 0].map(|x| *mesh.point(x));
        let f = mesh.add_point_on(Combination::new(apex_edge, 0.5, 0.0), [0, 3, 0]);
        assert_eq!(mesh.spanning([added[3], added[17], e[0], f]).len(), 4);
        assert!(!mesh.on_one_plane(&mesh.spanning([added[3], added[17], e[0], f])));
        assert_ne!(mesh.orient([added[3], added[17], e[0], f]), Sign::Zero);
        // Off the plane: the apex.
        assert_eq!(mesh.orient([0, 1, 2, 3]), mesh.orient([added[0], 1, 2, 3]));
        assert_ne!(mesh.orient([added[5], added[9], e[0], 3]), Sign::Zero);
        // The rounded coordinates of a point of the triangle against a face of three others:
        // that face's plane is the triangle's, turned the other way ((u, v) of the three,
        // (0.039, 0.289), (0.221, 0.191), (0.37, 0), turn clockwise).
        let p = *mesh.point(added[7]);
        let [a, b, c] = corners.map(|x| mesh.point(x));
        let face = [added[3], added[17], e[0]];
        assert_eq!(mesh.orient_point(face, &p), orient3d(a, b, c, &p).negate());
        // Moved, a point is its coordinates.
        let s = added[11];
        mesh.move_point(s, p);
        assert!(matches!(mesh.exact(s), Exact::Float(_)));
    }

    /// A remembered sign answers for every order of the tetrahedron's vertices (each exchange
    /// turns it), and is forgotten when a point moves or is dropped.
    #[test]
    fn exact_signs_follow_the_order_and_are_forgotten_on_moves() {
        let mut mesh = mesh();
        let mut signs = ExactSigns::default();
        signs.insert([2, 0, 3, 1], mesh.orient([2, 0, 3, 1]));
        let mut orders = 0;
        for code in 0..256u32 {
            let q = [0, 2, 4, 6].map(|shift| code >> shift & 3);
            if (0..4).all(|k| q.contains(&k)) {
                let p = q.map(|v| mesh.point(v));
                assert_eq!(signs.get(q), Some(orient3d(p[0], p[1], p[2], p[3])));
                orders += 1;
            }
        }
        assert_eq!(orders, 24);
        // A point of the triangle (0, 1, 2): the filter cannot tell that it is on the plane.
        let corners = [0, 1, 2];
        let at = |m: &TetMesh| Combination::new(corners.map(|x| *m.point(x)), 0.21, 0.34);
        let s = mesh.add_point_on(at(&mesh), corners);
        assert_eq!(mesh.orient([1, 0, 2, s]), Sign::Zero);
        assert_eq!(
            mesh.exact_signs.borrow().get([0, 1, 2, s]),
            Some(Sign::Zero)
        );
        mesh.move_point(s, [0.5, 0.6, 1.1]);
        assert_eq!(mesh.exact_signs.borrow().get([0, 1, 2, s]), None);
        assert_eq!(mesh.orient([0, 1, 2, s]), Sign::Positive);
        let t = mesh.add_point_on(at(&mesh), corners);
        assert_eq!(mesh.orient([0, 1, 2, t]), Sign::Zero);
        mesh.pop_point();
        assert_eq!(mesh.exact_signs.borrow().get([0, 1, 2, t]), None);
    }
}
