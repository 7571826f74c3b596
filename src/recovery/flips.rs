//! Topological flips on a [`TetMesh`]: the 2-3 flip of a facet and the removal of an edge
//! (Shewchuk, "Two discrete optimization algorithms for the topological improvement of
//! tetrahedral meshes", 2002: the shell of `n` tetrahedra around the edge becomes `2n - 4`
//! tetrahedra over a triangulation of its ring, chosen by dynamic programming; `n = 3` is the
//! 3-2 flip and `n = 4` the 4-4 flip).
//!
//! [`improve_by_flips`] applies flips that raise the worst shape, within a [`Bound`], at the
//! end (undoing, by [`TetMesh::begin`] and [`TetMesh::undo`], the deeper sequences that do
//! not, among them the recovery of an edge by the flips of [`super::edges`]);
//! [`remove_non_delaunay_edge`] removes an edge where the most Delaunay triangulation of its
//! shell lowers the lifted volume (before refinement).
//!
//! A flip never destroys a protected edge or facet ([`Protected`]: the input surface) and is
//! applied only when every new tetrahedron is positively oriented (exact).

use rustc_hash::{FxHashMap, FxHashSet};
use smallvec::SmallVec;

use super::edges::{first_crossing, recover_edge, Crossing, Guard, DEPTH};
use super::partition::{pair, sides};
use super::tetmesh::{key, Key, TetMesh};
use crate::error::{Error, ErrorKind, Result};
use crate::geometry::{dist2, tet_volume};
use crate::predicates::Point;
use crate::quality::radius_edge;
use crate::triangulation::tets::INFINITE;

/// Longest shell an edge removal considers (the dynamic program is cubic in it).
const MAX_SHELL: usize = 24;

/// The edges and facets no flip may destroy.
///
/// Invariant: every vertex of a protected edge or facet is flagged in `touched` (they are
/// added by [`Protected::insert_facet`] alone; removing them leaves the flags). The flags
/// answer first, so that the many questions about edges and facets with another vertex
/// (interior points above all) need no lookup in the large hash sets, whose random accesses
/// miss the cache.
#[derive(Default)]
pub struct Protected {
    pub edges: FxHashSet<[u32; 2]>,
    pub facets: FxHashSet<Key>,
    touched: Vec<bool>,
}

impl Protected {
    /// Protects facet `f` with its sides: the sides of a protected facet are protected
    /// edges ([`Protected::shell_may_go`] relies on it).
    pub fn insert_facet(&mut self, f: [u32; 3]) {
        self.facets.insert(key(f));
        self.edges.extend(sides(f));
        for v in f {
            let v = v as usize;
            if v >= self.touched.len() {
                self.touched.resize(v + 1, false);
            }
            self.touched[v] = true;
        }
    }

    /// Whether every vertex of `vertices` may be on a protected edge or facet.
    fn all_touched(&self, vertices: &[u32]) -> bool {
        vertices
            .iter()
            .all(|&v| self.touched.get(v as usize) == Some(&true))
    }

    pub fn edge(&self, a: u32, b: u32) -> bool {
        self.all_touched(&[a, b]) && self.edges.contains(&pair(a, b))
    }

    /// Per vertex `0..vertices`, whether it is an end of a protected edge (lies on the
    /// surface).
    pub fn vertices_on_edges(&self, vertices: usize) -> Vec<bool> {
        let mut on = vec![false; vertices];
        for &v in self.edges.iter().flatten() {
            on[v as usize] = true;
        }
        on
    }

    pub fn facet(&self, f: [u32; 3]) -> bool {
        self.all_touched(&f) && self.facets.contains(&key(f))
    }

    /// Whether the shell of the unprotected edge `(a, b)` with ring `ring` may be replaced:
    /// it is finite. None of its facets `(a, b, w)`, which vanish, is protected: the sides
    /// of a protected facet are protected edges ([`Protected::insert_facet`]; the partition
    /// drops an edge only once no subface has it).
    fn shell_may_go(&self, [a, b]: [u32; 2], ring: &[u32]) -> bool {
        debug_assert!(!self.edge(a, b) && !ring.iter().any(|&w| self.facet([a, b, w])));
        !ring.contains(&INFINITE)
    }
}

/// What a flip may create: every new edge `(u, w)` is asked first, then every new facet
/// through it. A closure over edges is a rule that accepts every facet.
pub trait Rule {
    fn edge(&self, mesh: &TetMesh, u: u32, w: u32) -> bool;

    /// A name for the rule when what it allows depends on nothing but the vertices' positions
    /// and that name, so that rings it leaves without a triangulation are remembered
    /// ([`RingMemo`]); `None`, the default, for rules that depend on more.
    fn memo_key(&self) -> Option<[u32; 2]> {
        None
    }

    fn facet(&self, _mesh: &TetMesh, _f: [u32; 3]) -> bool {
        true
    }
}

impl<F: Fn(&TetMesh, u32, u32) -> bool> Rule for F {
    fn edge(&self, mesh: &TetMesh, u: u32, w: u32) -> bool {
        self(mesh, u, w)
    }
}

/// The rule that allows every new edge and facet.
pub struct Any;

impl Rule for Any {
    fn edge(&self, _: &TetMesh, _: u32, _: u32) -> bool {
        true
    }

    fn memo_key(&self) -> Option<[u32; 2]> {
        Some([INFINITE; 2])
    }
}

/// Shape of a positively oriented tetrahedron, scale-free, larger is better (0 when flat).
pub fn shape(mesh: &TetMesh, q: [u32; 4]) -> f64 {
    let p = q.map(|v| *mesh.point(v));
    let mut s = 0.0;
    for i in 0..4 {
        for j in i + 1..4 {
            s += dist2(&p[i], &p[j]);
        }
    }
    tet_volume([&p[0], &p[1], &p[2], &p[3]]).abs() / (s * s.sqrt())
}

/// Flips the facet `i` of `t` (with the tetrahedron across it) into three tetrahedra around
/// the edge joining the two apexes. Returns `false`, changing nothing, when the facet is
/// protected, a tetrahedron is infinite, `allowed` refuses the new edge, or a new
/// tetrahedron would not be positive.
pub fn flip23(
    mesh: &mut TetMesh,
    protected: &Protected,
    t: u32,
    i: usize,
    allowed: &dyn Rule,
) -> Result<bool> {
    let Some((n, new)) = flip23_tetrahedra(mesh, protected, t, i) else {
        return Ok(false);
    };
    let (d, e) = (new[0][0], new[0][3]);
    if !allowed.edge(mesh, d, e) {
        return Ok(false);
    }
    // Positive tetrahedra are finite: the rule sees finite facets only.
    if !new.iter().all(|&q| mesh.positive(q))
        || !new.iter().all(|&q| allowed.facet(mesh, [d, e, q[1]]))
    {
        return Ok(false);
    }
    mesh.replace(&[t, n], &new)?;
    Ok(true)
}

/// The tetrahedron across facet `i` of `t` and the three tetrahedra `(d, x, y, e)`,
/// `(d, y, z, e)`, `(d, z, x, e)` of the facet's 2-3 flip (`d` and `e` the apexes), their
/// orientation not tested; `None` when the facet is protected or an apex infinite.
fn flip23_tetrahedra(
    mesh: &TetMesh,
    protected: &Protected,
    t: u32,
    i: usize,
) -> Option<(u32, [[u32; 4]; 3])> {
    let (d, [x, y, z]) = mesh.with_apex(t, i);
    let (n, e) = (mesh.tets.neighbor(t, i), mesh.across(t, i));
    if protected.facet([x, y, z]) || d == INFINITE || e == INFINITE {
        return None;
    }
    Some((n, [[d, x, y, e], [d, y, z, e], [d, z, x, e]]))
}

/// Removes edge `(a, b)`: its shell becomes two fans, from `a` and from
/// `b`, over the triangulation of the ring that maximizes the worst new tetrahedron's shape
/// among those whose diagonals `allowed` accepts. Returns `false`, changing nothing, when the
/// edge or a facet around it is protected, the shell is infinite or longer than
/// [`MAX_SHELL`], or no triangulation gives positive tetrahedra.
pub fn remove_edge(
    mesh: &mut TetMesh,
    protected: &Protected,
    [a, b]: [u32; 2],
    allowed: &dyn Rule,
) -> Result<bool> {
    if protected.edge(a, b) {
        return Ok(false);
    }
    let Some(t) = mesh.find_edge(a, b) else {
        return Ok(false);
    };
    let Some((shell, ring)) = mesh.shell(t, a, b, MAX_SHELL) else {
        return Ok(false);
    };
    remove_shell(mesh, protected, [a, b], (&shell, &ring), allowed)
}

/// [`remove_edge`] of the unprotected edge `(a, b)` whose shell and ring are given.
fn remove_shell(
    mesh: &mut TetMesh,
    protected: &Protected,
    [a, b]: [u32; 2],
    (shell, ring): (&[u32], &[u32]),
    allowed: &dyn Rule,
) -> Result<bool> {
    let Some(triangles) = shell_triangulation(mesh, protected, [a, b], ring, allowed) else {
        return Ok(false);
    };
    mesh.remove_edge_by_ring([a, b], (shell, ring), &triangles)?;
    Ok(true)
}

/// The triangulation of the ring of the unprotected edge `(a, b)` that [`remove_shell`]
/// makes, `None` where it fails (remembered, as `allowed` lets it be: [`RingMemo`]).
fn shell_triangulation(
    mesh: &mut TetMesh,
    protected: &Protected,
    [a, b]: [u32; 2],
    ring: &[u32],
    allowed: &dyn Rule,
) -> Option<RingTriangles> {
    if !protected.shell_may_go([a, b], ring) {
        return None;
    }
    let memo = allowed
        .memo_key()
        .and_then(|rule| RingMemo::key(rule, [a, b], ring));
    if let Some(known) = memo.and_then(|k| mesh.rings.get(&k)) {
        return known;
    }
    let found = best_ring_triangulation(
        mesh,
        [a, b],
        ring,
        allowed,
        (Goal::Shape, f64::NEG_INFINITY),
    )
    .map(|(triangles, _)| triangles);
    if let Some(k) = memo {
        mesh.rings.insert(k, found.as_deref());
    }
    found
}

/// Results of searches, keyed by everything they depend on: a cache, looked up before
/// searching again. At most `MOST` keys are held; then all are forgotten and remembered anew.
#[derive(Clone, Debug)]
pub struct Memo<K, V, const MOST: usize>(FxHashMap<K, V>);

impl<K, V, const MOST: usize> Default for Memo<K, V, MOST> {
    fn default() -> Self {
        Memo(FxHashMap::default())
    }
}

impl<K: std::hash::Hash + Eq, V, const MOST: usize> Memo<K, V, MOST> {
    pub fn get<Q>(&self, k: &Q) -> Option<&V>
    where
        K: std::borrow::Borrow<Q>,
        Q: std::hash::Hash + Eq + ?Sized,
    {
        self.0.get(k)
    }

    pub fn contains<Q>(&self, k: &Q) -> bool
    where
        K: std::borrow::Borrow<Q>,
        Q: std::hash::Hash + Eq + ?Sized,
    {
        self.0.contains_key(k)
    }

    pub fn insert(&mut self, k: K, v: V) {
        if self.0.len() == MOST {
            self.0.clear();
        }
        self.0.insert(k, v);
    }

    pub fn len(&self) -> usize {
        self.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Forgets every result; an empty table is left as it is (clearing costs its capacity).
    pub fn clear(&mut self) {
        if !self.0.is_empty() {
            self.0.clear();
        }
    }
}

/// The triangulations [`best_ring_triangulation`] gives the rings of edges under a rule with
/// a name ([`Rule::memo_key`]), and the rings it finds none for: a cache. Its answer depends
/// on nothing else than the positions of the edge's and the ring's vertices, so answers are
/// remembered while no point moves ([`TetMesh::move_point`] forgets them). Unblocking a
/// segment and filling a star anew remove the same edges of the same shells again and
/// again: on fandisk, 92% of the failed searches had been made before, in the same ring; on
/// pipe and on Chazelle's polyhedron with two notches a side, 95% and 94% of the successful
/// ones. At most [`RingMemo::MOST`] (2^17 was no faster).
#[derive(Clone, Debug, Default)]
pub struct RingMemo(Memo<[u32; 4 + RingMemo::RING], Option<PackedTriangles>, { RingMemo::MOST }>);

/// A ring's triangles by their corners' positions in the ring (below [`RingMemo::RING`]).
type PackedTriangles = SmallVec<[[u8; 3]; 6]>;

impl RingMemo {
    /// Longer rings are not remembered (and rarely met: shells are short).
    const RING: usize = 16;
    const MOST: usize = 1 << 15;

    /// How many rings are remembered.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The rule's name, the edge and its ring, padded with the infinite vertex (never in
    /// a ring that is searched).
    fn key(rule: [u32; 2], [a, b]: [u32; 2], ring: &[u32]) -> Option<[u32; 4 + Self::RING]> {
        if ring.len() > Self::RING {
            return None;
        }
        let mut k = [INFINITE; 4 + Self::RING];
        k[..4].copy_from_slice(&[rule[0], rule[1], a, b]);
        k[4..4 + ring.len()].copy_from_slice(ring);
        Some(k)
    }

    /// The remembered answer for `k`: `Some(None)` where the ring has no triangulation.
    fn get(&self, k: &[u32; 4 + Self::RING]) -> Option<Option<RingTriangles>> {
        let known = self.0.get(k)?;
        Some(
            known
                .as_ref()
                .map(|packed| (packed.iter()).map(|t| t.map(usize::from)).collect()),
        )
    }

    fn insert(&mut self, k: [u32; 4 + Self::RING], triangles: Option<&[[usize; 3]]>) {
        // The ring is at most `RING` long: its positions fit a byte.
        let packed = triangles.map(|t| t.iter().map(|c| c.map(|x| x as u8)).collect());
        self.0.insert(k, packed);
    }

    /// Forgets every ring (a point moved).
    pub fn clear(&mut self) {
        self.0.clear();
    }
}

/// [`remove_edge`], and when it fails, shrinks the shell first (TetGen's `flipnm`): a 2-3
/// flip of a facet `(a, b, w)` takes `w` out of the ring; where that flip gives a tetrahedron
/// that is not positive, the edges `(a, w)` and `(b, w)` that do so ([`blocking_sides`], the
/// reflex edges of the link) are removed the same way, `level` deep. Flips that do not lead
/// to the removal are kept (they leave a valid mesh with the protected entities intact).
/// Every attempt spends one unit of `budget`; at 0 the search gives up.
pub fn remove_edge_deep(
    mesh: &mut TetMesh,
    protected: &Protected,
    [a, b]: [u32; 2],
    allowed: &dyn Rule,
    level: u32,
    budget: &mut usize,
) -> Result<bool> {
    loop {
        if *budget == 0 {
            return Ok(false);
        }
        *budget -= 1;
        if protected.edge(a, b) {
            return Ok(false);
        }
        // Gone (flips made since the caller saw it, or a shrinking pass here): reported as
        // removed when this call may shrink, so that the caller looks at its shell again.
        let Some(t) = mesh.find_edge(a, b) else {
            return Ok(level > 0);
        };
        let Some((shell, ring)) = mesh.shell(t, a, b, MAX_SHELL) else {
            return Ok(false);
        };
        if remove_shell(mesh, protected, [a, b], (&shell, &ring), allowed)? {
            return Ok(true);
        }
        if level == 0 || ring.len() <= 3 || ring.contains(&INFINITE) {
            return Ok(false);
        }
        let mut shrunk = false;
        let quads: SmallVec<[[u32; 4]; 8]> = shell.iter().map(|&u| mesh.tets.vertices(u)).collect();
        for (i, &s) in shell.iter().enumerate() {
            if shell
                .iter()
                .zip(&quads)
                .any(|(&u, q)| mesh.tets.vertices(u) != *q)
            {
                // A failed deeper attempt kept some flips: look at the shell again.
                shrunk = true;
                break;
            }
            // Facet (a, b, w_i) of tetrahedron (a, b, w_i, w_i+1): opposite w_i+1.
            let next = ring[(i + 1) % ring.len()];
            let j = mesh
                .tets
                .vertices(s)
                .iter()
                .position(|&x| x == next)
                .unwrap_or(0);
            // Where a side blocks the flip, flip23 would fail on the same orientations.
            let blocking = blocking_sides(mesh, s, j);
            if blocking.is_empty() && flip23(mesh, protected, s, j, allowed)? {
                shrunk = true;
                break;
            }
            let w = ring[i];
            for side in [[a, w], [b, w]] {
                if !blocking.contains(&pair(side[0], side[1])) {
                    continue;
                }
                if remove_edge_deep(mesh, protected, side, allowed, level - 1, budget)? {
                    shrunk = true;
                    break;
                }
            }
            if shrunk {
                break;
            }
        }
        if !shrunk {
            return Ok(false);
        }
    }
}

/// The sides of the finite facet `i` of `t`, between finite tetrahedra, that keep its 2-3
/// flip from giving positive tetrahedra, sorted pairs: the side `(u, v)` whose new
/// tetrahedron `(d, u, v, e)` (`d` and `e` the apexes) is not positive, a reflex edge of the
/// link (TetGen's `flipnm` flips only those).
pub(super) fn blocking_sides(mesh: &TetMesh, t: u32, i: usize) -> SmallVec<[[u32; 2]; 3]> {
    let (d, [x, y, z]) = mesh.with_apex(t, i);
    let e = mesh.across(t, i);
    [[x, y], [y, z], [z, x]]
        .into_iter()
        .filter(|&[u, v]| !mesh.positive([d, u, v, e]))
        .map(|[u, v]| pair(u, v))
        .collect()
}

/// The triangles of a ring's triangulation, by their corners' positions in the ring.
type RingTriangles = SmallVec<[[usize; 3]; 6]>;

/// What the triangulation of a ring optimizes ([`best_ring_triangulation`]).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Goal {
    /// The largest smallest shape of the new tetrahedra.
    Shape,
    /// The smallest sum of their lifted volumes ([`lifted_volume`], taken from the edge's
    /// first vertex): the most Delaunay.
    Delaunay,
}

impl Goal {
    /// The score of no tetrahedron (a side of the ring).
    fn empty(self) -> f64 {
        match self {
            Goal::Shape => f64::INFINITY,
            Goal::Delaunay => 0.0,
        }
    }

    /// The score of the two new tetrahedra of a triangle, larger is better: never above
    /// [`Goal::empty`], so that joining scores never raises them.
    fn pair(self, mesh: &TetMesh, ta: [u32; 4], tb: [u32; 4]) -> f64 {
        match self {
            Goal::Shape => shape(mesh, ta).min(shape(mesh, tb)),
            Goal::Delaunay => {
                let origin = mesh.point(ta[0]);
                -(lifted_volume(mesh, origin, ta) + lifted_volume(mesh, origin, tb))
            }
        }
    }

    fn join(self, x: f64, y: f64) -> f64 {
        match self {
            Goal::Shape => x.min(y),
            Goal::Delaunay => x + y,
        }
    }
}

/// The volume between tetrahedron `q` and its lift onto the paraboloid `|x - origin|^2`: its
/// volume times the mean of its vertices' lifts (TetGen's "tetprism volume"). Among the
/// triangulations of a region with the same vertices, the Delaunay one has the smallest sum;
/// differences of sums do not depend on `origin`.
fn lifted_volume(mesh: &TetMesh, origin: &Point, q: [u32; 4]) -> f64 {
    let p = q.map(|v| mesh.point(v));
    let lift: f64 = p.iter().map(|x| dist2(x, origin)).sum();
    tet_volume(p).abs() * lift / 4.0
}

/// The two tetrahedra `(a, w_j, w_i, w_k)` and `(b, w_j, w_k, w_i)` that the triangle
/// `(i, k, j)` of edge `(a, b)`'s ring polygon `w` gives when the edge is removed
/// ([`TetMesh::remove_edge_by_ring`] makes them so).
fn ring_tetrahedra([a, b]: [u32; 2], ring: &[u32], [i, k, j]: [usize; 3]) -> [[u32; 4]; 2] {
    let (wi, wk, wj) = (ring[i], ring[k], ring[j]);
    [[a, wj, wi, wk], [b, wj, wk, wi]]
}

/// The triangles `(i, k, j)`, `i < k < j`, of the triangulation of the ring polygon that
/// gives the new tetrahedra `(a, w_j, w_i, w_k)` and `(b, w_j, w_k, w_i)` the best `goal`
/// score, all of them positive, and that score; `None` if there is none with a score above
/// `floor` (the triangles of a lower score are not tested for orientation).
fn best_ring_triangulation(
    mesh: &TetMesh,
    [a, b]: [u32; 2],
    ring: &[u32],
    allowed: &dyn Rule,
    (goal, floor): (Goal, f64),
) -> Option<(RingTriangles, f64)> {
    let n = ring.len();
    // best[i * n + j]: the best score over triangulations of the sub-polygon i..=j, and the
    // apex k of the triangle on side (i, j). Sized to the ring, without allocation up to
    // rings of 8 (most rings are short, and this runs millions of times on hard inputs).
    let mut best: SmallVec<[(f64, usize); 64]> =
        smallvec::smallvec![(f64::NEG_INFINITY, usize::MAX); n * n];
    for i in 0..n - 1 {
        best[i * n + i + 1] = (goal.empty(), usize::MAX);
    }
    let side = |i: usize, j: usize| j == i + 1 || (i == 0 && j == n - 1);
    // With no floor (recovery's searches), the orientations first: a third of the triangles
    // give a tetrahedron that is not positive (pipe: 1.6 of 4.9 million), and nearly all the
    // others score above the best so far. With a floor, most triangles score below it: the
    // measures first.
    let oriented_first = floor == f64::NEG_INFINITY;
    // A diagonal (u, w) brings the edge and the facets (a, u, w) and (b, u, w).
    let diagonal = |u: u32, w: u32| {
        allowed.edge(mesh, u, w) && allowed.facet(mesh, [a, u, w]) && allowed.facet(mesh, [b, u, w])
    };
    for len in 2..n {
        for i in 0..n - len {
            let j = i + len;
            if !(side(i, j) || diagonal(ring[i], ring[j])) {
                continue;
            }
            for k in i + 1..j {
                // The triangle's score can only lower this bound.
                let bound = goal.join(best[i * n + k].0, best[k * n + j].0);
                if bound <= best[i * n + j].0 {
                    continue;
                }
                let (wi, wk, wj) = (ring[i], ring[k], ring[j]);
                let [ta, tb] = ring_tetrahedra([a, b], ring, [i, k, j]);
                let positive = || mesh.positive(ta) && mesh.positive(tb);
                if oriented_first && !positive() {
                    continue;
                }
                let q = goal.join(bound, goal.pair(mesh, ta, tb));
                if q <= best[i * n + j].0 || q <= floor {
                    continue;
                }
                if !oriented_first && !positive() || !allowed.facet(mesh, [wi, wk, wj]) {
                    continue;
                }
                if q > best[i * n + j].0 {
                    best[i * n + j] = (q, k);
                }
            }
        }
    }
    let (score, apex) = best[n - 1];
    if apex == usize::MAX {
        return None;
    }
    let mut triangles = RingTriangles::new();
    let mut stack: SmallVec<[(usize, usize); 16]> = smallvec::smallvec![(0, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j > i + 1 {
            let k = best[i * n + j].1;
            triangles.push([i, k, j]);
            stack.push((i, k));
            stack.push((k, j));
        }
    }
    Some((triangles, score))
}

/// Longest shell [`remove_non_delaunay_edge`] looks at (TetGen's star size for its recovery
/// of the Delaunay property).
const MAX_DELAUNAY_SHELL: usize = 10;

/// Removes the unprotected edge `(a, b)` of tetrahedron `t` when the most Delaunay
/// triangulation of its shell (two fans over a triangulation of the ring) has a smaller sum
/// of lifted volumes ([`lifted_volume`]) than the shell, by more than rounding can account
/// for (TetGen's recovery of the Delaunay property by edge removal): that sum over the whole
/// mesh decreases at every removal, so removals cannot cycle. Returns the new tetrahedra;
/// `None`, changing nothing, when the edge or a facet around it is protected, the shell is
/// infinite or longer than [`MAX_DELAUNAY_SHELL`], or no triangulation lowers the sum.
pub fn remove_non_delaunay_edge(
    mesh: &mut TetMesh,
    protected: &Protected,
    t: u32,
    [a, b]: [u32; 2],
) -> Result<Option<Vec<u32>>> {
    if protected.edge(a, b) {
        return Ok(None);
    }
    let Some((shell, ring)) = mesh.shell(t, a, b, MAX_DELAUNAY_SHELL) else {
        return Ok(None);
    };
    if !protected.shell_may_go([a, b], &ring) {
        return Ok(None);
    }
    let origin = mesh.point(a);
    let before: f64 = shell
        .iter()
        .map(|&u| lifted_volume(mesh, origin, mesh.tets.vertices(u)))
        .sum();
    // Each tetrahedron's volume is off by at most a few units in the last place of the cube
    // of the shell's reach, its lift by as many of the reach's square.
    let reach2 = ring
        .iter()
        .chain([&b])
        .map(|&w| dist2(mesh.point(w), origin))
        .fold(0.0, f64::max);
    let rounding = 1e-12 * (2 * shell.len()) as f64 * reach2 * reach2 * reach2.sqrt();
    let Some((triangles, score)) = best_ring_triangulation(
        mesh,
        [a, b],
        &ring,
        &Any,
        (Goal::Delaunay, f64::NEG_INFINITY),
    ) else {
        return Ok(None);
    };
    if -score >= before - rounding {
        return Ok(None);
    }
    mesh.remove_edge_by_ring([a, b], (&shell, &ring), &triangles)
        .map(Some)
}

/// The shape below which [`improve_by_flips`] tries to replace a tetrahedron: half a regular
/// tetrahedron's (0.00802); above it the flips gain little.
pub const IMPROVED_BELOW: f64 = 0.004;

/// The shape below which a tetrahedron is nearly flat (an eight-thousandth of a regular
/// one's: a smallest dihedral angle around a hundredth of a degree, or a radius-edge ratio of
/// some thousands): [`improve_by_flips`] then also removes its edges by flips several
/// levels deep, undone when they do not raise the worst shape. Without a ratio bound, only
/// such tetrahedra are replaced: with 1e-5, bunny00's Delaunay slivers (4,757 below it, 40
/// below 1e-6) took 96 ms against 7.
pub const FLAT_BELOW: f64 = 1e-6;

/// The longest shell of an edge [`improve_by_flips`] removes at once: 3-2 and 4-4 flips.
/// Longer shells gained little (armadillo with the bound 1.414: tetrahedra with a dihedral
/// angle below 5, 10, 15 degrees 804, 1908, 3300 with shells of 4, 783, 1864, 3262 with shells
/// up to 24, 1221, 2648, 4410 with 3-2 flips alone), and took 112 ms against 150 (65 ms),
/// measured with the nearly flat threshold at 1e-5.
const IMPROVING_SHELL: usize = 4;

/// Passes of [`improve_by_flips`] over the tetrahedra the previous pass made and their
/// neighbours.
const IMPROVING_PASSES: usize = 8;

/// How deep, and with how many edge removals, [`improve_by_flips`] removes an edge of a
/// nearly flat tetrahedron ([`remove_edge_deep`]).
const FLAT_DEPTH: u32 = 3;
const FLAT_BUDGET: usize = 64;

/// What the new tetrahedra of [`improve_by_flips`] must meet.
#[derive(Clone, Copy, Debug)]
pub struct Bound<'a> {
    /// Tetrahedra shaped worse than this are replaced where flips allow.
    pub below: f64,
    /// No new tetrahedron has a radius-edge ratio above this one (0: none is asked), unless
    /// `exempt` lets it be no worse than the worst of those it replaces.
    pub ratio: f64,
    pub exempt: Exempt<'a>,
    /// No new tetrahedron is larger than the largest it replaces (volume bounds hold).
    pub no_larger: bool,
}

/// The new tetrahedra a [`Bound`] lets exceed its ratio, up to the worst ratio replaced.
#[derive(Clone, Copy, Debug)]
pub enum Exempt<'a> {
    None,
    /// Those with three or four vertices `v` on the surface (`on[v]`; vertices past its end
    /// are not): refinement leaves such tetrahedra above the bound where the surface forces
    /// them.
    OnSurface(&'a [bool]),
    All,
}

/// Whether the tetrahedron `q` has three or four vertices `v` on the surface (`on[v]`;
/// vertices past its end are not).
pub fn on_surface(on: &[bool], q: &[u32; 4]) -> bool {
    q.iter()
        .filter(|&&v| on.get(v as usize) == Some(&true))
        .count()
        >= 3
}

impl Bound<'_> {
    /// Whether the tetrahedra `new`, replacing `old`, raise the worst shape and meet the
    /// bound.
    pub(super) fn improved(&self, mesh: &TetMesh, old: &[[u32; 4]], new: &[[u32; 4]]) -> bool {
        self.improves_on(
            mesh,
            Before::of(self, mesh, old),
            &|| worst_ratio(mesh, old),
            new,
        )
    }

    /// Whether the tetrahedra `new` raise the worst shape `before.shape` of what they replace
    /// and meet the bound, where `old_ratio` gives the worst radius-edge ratio replaced (asked
    /// only of an exempt tetrahedron above the bound).
    pub(super) fn improves_on(
        &self,
        mesh: &TetMesh,
        before: Before,
        old_ratio: &dyn Fn() -> f64,
        new: &[[u32; 4]],
    ) -> bool {
        if worst_shape(mesh, new) <= before.shape {
            return false;
        }
        if self.no_larger && new.iter().any(|q| volume(mesh, q) > before.largest) {
            return false;
        }
        let exempt = |q: &[u32; 4]| match self.exempt {
            Exempt::None => false,
            Exempt::OnSurface(on) => on_surface(on, q),
            Exempt::All => true,
        };
        new.iter().all(|q| {
            let r = ratio(mesh, q);
            r <= self.ratio || exempt(q) && r <= old_ratio()
        })
    }
}

/// What a replacement must improve on ([`Bound::improves_on`]).
#[derive(Clone, Copy, Debug)]
pub struct Before {
    /// The worst shape replaced.
    pub shape: f64,
    /// The largest volume replaced (read only where [`Bound::no_larger`]).
    pub largest: f64,
}

impl Before {
    /// What replacing `tets` under `bound` must improve on.
    pub fn of(bound: &Bound, mesh: &TetMesh, tets: &[[u32; 4]]) -> Before {
        Before {
            shape: worst_shape(mesh, tets),
            largest: if bound.no_larger {
                largest(mesh, tets)
            } else {
                0.0
            },
        }
    }
}

/// The worst shape of `tets`.
pub fn worst_shape(mesh: &TetMesh, tets: &[[u32; 4]]) -> f64 {
    tets.iter()
        .map(|&q| shape(mesh, q))
        .fold(f64::INFINITY, f64::min)
}

/// The largest volume of `tets`.
fn largest(mesh: &TetMesh, tets: &[[u32; 4]]) -> f64 {
    tets.iter().map(|q| volume(mesh, q)).fold(0.0, f64::max)
}

/// The worst radius-edge ratio of `tets`.
pub fn worst_ratio(mesh: &TetMesh, tets: &[[u32; 4]]) -> f64 {
    tets.iter().map(|q| ratio(mesh, q)).fold(0.0, f64::max)
}

fn volume(mesh: &TetMesh, q: &[u32; 4]) -> f64 {
    tet_volume(q.map(|v| mesh.point(v))).abs()
}

fn ratio(mesh: &TetMesh, q: &[u32; 4]) -> f64 {
    radius_edge(q.map(|v| mesh.point(v)))
}

/// Flips that raise the worst shape of the tetrahedra they replace (TetGen's mesh
/// optimization by flips). Each tetrahedron of `queue` shaped worse than `bound.below` is
/// replaced by the first of: the removal of one of its edges with a shell of at most
/// [`IMPROVING_SHELL`] (a 3-2 or 4-4 flip, the ring triangulation with the best worst
/// shape), a 2-3 flip of one of its facets, and, when it is nearly flat ([`FLAT_BELOW`]), the
/// removal of one of its edges by flips [`FLAT_DEPTH`] levels deep ([`remove_edge_deep`]),
/// undone unless what they made as a whole is better (TetGen's `flipnm` with `unflip`); each
/// must raise the worst shape of what it replaces and make tetrahedra that meet `bound`. Then
/// the same on the tetrahedra each pass makes and on their neighbours in the region (the
/// shells of the edges they share changed, so a flip refused there may now be found; TetGen
/// queues the faces of each flip's new tetrahedra so). The caps the passes leave
/// ([`is_cap`], whether below `bound.below` or not) are then taken away, where that raises
/// the worst shape, through the recovery of an edge from one of their corners to a vertex
/// nearby ([`improving_edge`]), and the passes run again on what that made.
/// `made(mesh, old, new)` is told the new tetrahedra of each replacement and one it replaced
/// (no protected facet separates them), and the tetrahedra an undo put back.
pub fn improve_by_flips(
    mesh: &mut TetMesh,
    protected: &Protected,
    bound: Bound,
    queue: Vec<u32>,
    made: &mut dyn FnMut(&TetMesh, u32, &[u32]),
) -> Result<Improved> {
    let mut caps = Vec::new();
    let mut replaced = flip_passes(mesh, protected, bound, queue, made, &mut caps)?;
    let mut next = Vec::new();
    let mut through_edges = 0;
    for quad in caps {
        let Some(t) = mesh.tet_of(quad) else {
            continue;
        };
        if let Some(new) = improving_edge(mesh, protected, bound, t, made)? {
            made(mesh, t, &new);
            next.extend(new);
            through_edges += 1;
        }
    }
    next.retain(|&t| mesh.tets.is_live(t));
    replaced += flip_passes(mesh, protected, bound, next, made, &mut Vec::new())?;
    Ok(Improved {
        replaced,
        through_edges,
    })
}

/// What [`improve_by_flips`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Improved {
    /// Single flips and edge removals, each replacing a tetrahedron.
    pub replaced: usize,
    /// Caps taken away through the recovery of an edge ([`improving_edge`]).
    pub through_edges: usize,
}

/// The passes of [`improve_by_flips`] before its edges are recovered: the caps they leave
/// ([`is_cap`]) are noted in `caps`, by their vertices, as often as a pass meets them (a
/// neighbour of several flips is met again): the recovery of an edge that fails for a cap may
/// succeed once the others are done (anchor without a bound: largest ratio 3,246, 24,083
/// with each cap tried once).
fn flip_passes(
    mesh: &mut TetMesh,
    protected: &Protected,
    bound: Bound,
    mut queue: Vec<u32>,
    made: &mut dyn FnMut(&TetMesh, u32, &[u32]),
    caps: &mut Vec<[u32; 4]>,
) -> Result<usize> {
    let mut replaced = 0;
    for _ in 0..IMPROVING_PASSES {
        let mut next = Vec::new();
        for t in queue {
            if !mesh.tets.is_live(t) || mesh.tets.vertices(t).contains(&INFINITE) {
                continue;
            }
            let quad = mesh.tets.vertices(t);
            let s = shape(mesh, quad);
            if s >= bound.below {
                if is_cap(mesh, quad, s) {
                    caps.push(quad);
                }
                continue;
            }
            let mut new = improving_flip(mesh, protected, bound, t)?;
            if new.is_none() && s < FLAT_BELOW {
                new = improving_deep_removal(mesh, protected, bound, t, made)?;
            }
            if new.is_none() && is_cap(mesh, quad, s) {
                caps.push(quad);
            }
            if let Some(new) = new {
                made(mesh, t, &new);
                next.extend(neighbours_in_region(mesh, protected, &new));
                next.extend(new);
                replaced += 1;
            }
        }
        if next.is_empty() {
            break;
        }
        next.sort_unstable();
        next.dedup();
        queue = next;
    }
    Ok(replaced)
}

/// The tetrahedra across the facets of `tets` that are not protected (some may be in `tets`).
fn neighbours_in_region<'a>(
    mesh: &'a TetMesh,
    protected: &'a Protected,
    tets: &'a [u32],
) -> impl Iterator<Item = u32> + 'a {
    tets.iter().flat_map(move |&u| {
        (0..4)
            .filter(move |&i| !protected.facet(mesh.facet(u, i)))
            .map(move |i| mesh.tets.neighbor(u, i))
    })
}

/// The first removal of an edge of `t` or 2-3 flip of one of its facets that raises the worst
/// shape of what it replaces and whose new tetrahedra meet `bound`, made; their ids.
fn improving_flip(
    mesh: &mut TetMesh,
    protected: &Protected,
    bound: Bound,
    t: u32,
) -> Result<Option<Vec<u32>>> {
    let v = mesh.tets.vertices(t);
    for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
        let (a, b) = (v[i], v[j]);
        if protected.edge(a, b) {
            continue;
        }
        let Some((shell, ring)) = mesh.shell(t, a, b, IMPROVING_SHELL) else {
            continue;
        };
        if !protected.shell_may_go([a, b], &ring) {
            continue;
        }
        let worst = shell
            .iter()
            .map(|&u| shape(mesh, mesh.tets.vertices(u)))
            .fold(f64::INFINITY, f64::min);
        let goal = (Goal::Shape, worst);
        let Some((triangles, _)) = best_ring_triangulation(mesh, [a, b], &ring, &Any, goal) else {
            continue;
        };
        let (old, new) = shell_and_fans(mesh, [a, b], (&shell, &ring), &triangles);
        if bound.improved(mesh, &old, &new) {
            return mesh
                .remove_edge_by_ring([a, b], (&shell, &ring), &triangles)
                .map(Some);
        }
    }
    for i in 0..4 {
        let Some((n, new)) = flip23_tetrahedra(mesh, protected, t, i) else {
            continue;
        };
        // The orientations first: most of these flips would invert a tetrahedron (armadillo
        // with the bound 1.414: 105,678 of 150,474), and measuring costs more.
        let old = [v, mesh.tets.vertices(n)];
        if new.iter().all(|&q| mesh.positive(q)) && bound.improved(mesh, &old, &new) {
            return mesh.replace(&[t, n], &new).map(Some);
        }
    }
    Ok(None)
}

/// The first removal of an edge of the nearly flat `t` by flips [`FLAT_DEPTH`] levels deep
/// whose net change raises the worst shape and meets `bound`; its new tetrahedra. A removal
/// without shrinking is measured before it is made ([`plain_removal`]); the others are made,
/// and undone (`made` is told the tetrahedra put back) where they do not improve.
fn improving_deep_removal(
    mesh: &mut TetMesh,
    protected: &Protected,
    bound: Bound,
    t: u32,
    made: &mut dyn FnMut(&TetMesh, u32, &[u32]),
) -> Result<Option<Vec<u32>>> {
    let v = mesh.tets.vertices(t);
    for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
        let (a, b) = (v[i], v[j]);
        if protected.edge(a, b) {
            continue;
        }
        match plain_removal(mesh, protected, bound, [a, b])? {
            Plain::Made(new) => return Ok(Some(new)),
            Plain::Declined => continue,
            Plain::NeedsShrinking => {}
        }
        mesh.begin();
        let mut budget = FLAT_BUDGET;
        let removed = remove_edge_deep(mesh, protected, [a, b], &Any, FLAT_DEPTH, &mut budget);
        if let Some(new) = kept_if_improved(mesh, bound, t, removed, made)? {
            return Ok(Some(new));
        }
    }
    Ok(None)
}

/// What [`plain_removal`] did.
enum Plain {
    /// The removal, made: its new tetrahedra.
    Made(Vec<u32>),
    /// Nothing: the removal does not raise the worst shape or does not meet the bound.
    Declined,
    /// Nothing: the shell cannot go at once.
    NeedsShrinking,
}

/// Where the shell of edge `(a, b)` can go at once, the removal [`remove_edge_deep`] would
/// make, measured before it is made rather than made and undone (on knot without a bound, 693
/// of the 830 removals tried): made where it raises the worst shape and meets `bound`.
fn plain_removal(
    mesh: &mut TetMesh,
    protected: &Protected,
    bound: Bound,
    [a, b]: [u32; 2],
) -> Result<Plain> {
    let Some((shell, ring)) = mesh
        .find_edge(a, b)
        .and_then(|t| mesh.shell(t, a, b, MAX_SHELL))
    else {
        return Ok(Plain::NeedsShrinking);
    };
    let Some(triangles) = shell_triangulation(mesh, protected, [a, b], &ring, &Any) else {
        return Ok(Plain::NeedsShrinking);
    };
    let (old, new) = shell_and_fans(mesh, [a, b], (&shell, &ring), &triangles);
    if !bound.improved(mesh, &old, &new) {
        return Ok(Plain::Declined);
    }
    let made = mesh.remove_edge_by_ring([a, b], (&shell, &ring), &triangles)?;
    Ok(Plain::Made(made))
}

/// Tetrahedra by their vertices, `N` of them without allocation.
type Quads<const N: usize> = SmallVec<[[u32; 4]; N]>;

/// The tetrahedra of the shell of `(a, b)` and the two fans over the ring's `triangles` that
/// replace them.
fn shell_and_fans(
    mesh: &TetMesh,
    [a, b]: [u32; 2],
    (shell, ring): (&[u32], &[u32]),
    triangles: &[[usize; 3]],
) -> (Quads<16>, Quads<32>) {
    let old = shell.iter().map(|&u| mesh.tets.vertices(u)).collect();
    let new = triangles
        .iter()
        .flat_map(|&triangle| ring_tetrahedra([a, b], ring, triangle))
        .collect();
    (old, new)
}

/// Ends the replacements noted since [`TetMesh::begin`]: kept when `done` holds and their net
/// change raises the worst shape and meets `bound` (the ids of the tetrahedra they made),
/// undone otherwise (`made` is told the tetrahedra put back, with `t`, of their region).
fn kept_if_improved(
    mesh: &mut TetMesh,
    bound: Bound,
    t: u32,
    done: Result<bool>,
    made: &mut dyn FnMut(&TetMesh, u32, &[u32]),
) -> Result<Option<Vec<u32>>> {
    let change = mesh.end();
    if done? && bound.improved(mesh, &change.removed, &change.created) {
        let ids: Option<Vec<u32>> = change.made.iter().map(|&q| mesh.tet_of(q)).collect();
        return ids
            .map(Some)
            .ok_or_else(|| Error::internal("a tetrahedron made by flips is not in the mesh"));
    }
    if !change.made.is_empty() {
        let back = mesh.undo(change)?;
        made(mesh, t, &back);
    }
    Ok(None)
}

/// The first edge from a vertex of the cap `t` to a vertex nearby ([`near_region`])
/// whose recovery by flips ([`recover_edge`] as recovery first tries it, [`DEPTH`] levels
/// deep), followed by a flip or the removal of an edge of `t` ([`EDGE_DEPTH`] levels deep)
/// that takes `t` away, raises the worst shape of what changed as a whole
/// and meets `bound`; the new tetrahedra. The others are undone (`made` is told the tetrahedra
/// put back). Where an input edge is the diagonal of a quadrilateral of nearly coplanar
/// vertices, the flat tetrahedron of its corners has one edge that is not an input edge, and
/// its ring may have no triangulation (part.off: edge 132-134, ring 131, 135, 73, 72, the
/// quadrilateral's corner 134 on the wrong side of the plane 131-73-72); TetGen's mesh joins
/// both input triangles to vertex 73 instead, through the edge 131-73, which this recovers
/// (the largest radius-edge ratio 7,721 -> 65 with the bound 1.414).
fn improving_edge(
    mesh: &mut TetMesh,
    protected: &Protected,
    bound: Bound,
    t: u32,
    made: &mut dyn FnMut(&TetMesh, u32, &[u32]),
) -> Result<Option<Vec<u32>>> {
    let v = mesh.tets.vertices(t);
    let region = near_region(mesh, protected, t);
    let mut near: Vec<u32> = region
        .iter()
        .flat_map(|&u| mesh.tets.vertices(u))
        .filter(|w| !v.contains(w))
        .collect();
    near.sort_unstable();
    near.dedup();
    for x in v {
        for &w in &near {
            if !starts_in(mesh, [x, w], &region)? || !starts_in(mesh, [w, x], &region)? {
                continue;
            }
            mesh.begin();
            let taken = edge_taking(mesh, protected, bound, [x, w], v);
            if let Some(new) = kept_if_improved(mesh, bound, t, taken, made)? {
                return Ok(Some(new));
            }
        }
    }
    Ok(None)
}

/// Whether the tetrahedron `q` of shape `s` is a cap: shaped worse than [`IMPROVED_BELOW`],
/// with a radius-edge ratio of at least [`CAP_RATIO`].
fn is_cap(mesh: &TetMesh, q: [u32; 4], s: f64) -> bool {
    s < IMPROVED_BELOW && ratio(mesh, &q) >= CAP_RATIO
}

/// The radius-edge ratio from which a poorly shaped tetrahedron counts as a cap (its nearly
/// coplanar vertices far from any common circle, so that its circumsphere is huge), which
/// [`improve_by_flips`] tries to take away through an edge; below it are slivers (vertices
/// near a common circle), for which that search costs and rarely succeeds: for every nearly
/// flat one, knot (largest ratio 7) took 0.042 s instead of 0.015 without a bound, no better.
const CAP_RATIO: f64 = 100.0;

/// How deep [`improving_edge`] removes an edge of the cap once its edge is recovered.
const EDGE_DEPTH: u32 = 2;

/// How many steps across unprotected facets from a cap [`improving_edge`] looks for
/// vertices: with 2, the largest ratios stay 161,165 on armadillo, 9,748 on handle and 7,721
/// on part with the bound 1.414, and anchor's without a bound is 24,083 (354, 735, 65 and
/// 3,246 with 4).
const NEAR_STEPS: usize = 4;

/// The finite tetrahedra at most [`NEAR_STEPS`] facets away from `t` across unprotected
/// facets between finite tetrahedra (all of `t`'s region), sorted.
fn near_region(mesh: &TetMesh, protected: &Protected, t: u32) -> Vec<u32> {
    let mut found = vec![t];
    let mut layer = 0..1;
    for _ in 0..NEAR_STEPS {
        let end = found.len();
        for k in layer {
            let u = found[k];
            for i in 0..4 {
                let n = mesh.tets.neighbor(u, i);
                let finite = !mesh.tets.vertices(n).contains(&INFINITE);
                if finite && !protected.facet(mesh.facet(u, i)) && !found.contains(&n) {
                    found.push(n);
                }
            }
        }
        layer = end..found.len();
    }
    found.sort_unstable();
    found
}

/// Whether the segment from `x` to `w` starts into a tetrahedron of `region` (sorted): then
/// the flips recovering it stay in that region, which the surface bounds (the segment
/// leaves `x`'s star through a facet or an edge of one of those tetrahedra).
fn starts_in(mesh: &mut TetMesh, [x, w]: [u32; 2], region: &[u32]) -> Result<bool> {
    let start = match first_crossing(mesh, x, w)? {
        Some(Crossing::Facet(u, _)) | Some(Crossing::Edge(_, u)) => u,
        Some(Crossing::Vertex(_)) | None => return Ok(false),
    };
    Ok(region.binary_search(&start).is_ok())
}

/// Recovers the edge `e` by flips, then takes the tetrahedron `q` away by an improving flip or
/// the removal of one of its edges; whether both happened.
fn edge_taking(
    mesh: &mut TetMesh,
    protected: &Protected,
    bound: Bound,
    e: [u32; 2],
    q: [u32; 4],
) -> Result<bool> {
    match recover_edge(mesh, protected, e, DEPTH, Guard::Open, false) {
        Ok(true) => {}
        Ok(false) => return Ok(false),
        // A vertex on the segment, the only error recovery reports but a bug's: no such edge.
        Err(error) if error.kind != ErrorKind::Internal => return Ok(false),
        Err(error) => return Err(error),
    }
    let Some(t) = mesh.tet_of(q) else {
        return Ok(true);
    };
    if improving_flip(mesh, protected, bound, t)?.is_some() {
        return Ok(true);
    }
    for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
        if protected.edge(q[i], q[j]) {
            continue;
        }
        let mut budget = FLAT_BUDGET;
        if remove_edge_deep(mesh, protected, [q[i], q[j]], &Any, EDGE_DEPTH, &mut budget)? {
            return Ok(true);
        }
    }
    Ok(false)
}

/// What [`flip32`] asks of a flip: the mesh, the three tetrahedra replaced, the two new ones.
pub type Accept32<'a> = dyn Fn(&TetMesh, [u32; 3], [[u32; 4]; 2]) -> bool + 'a;

/// The 3-2 flip of edge `(a, b)` of `t`: when the edge has a shell of three tetrahedra, no
/// protected edge or facet is lost, `accept(mesh, shell, new)` agrees (it is asked first,
/// before the exact orientations) and both new tetrahedra are positive; their ids.
pub fn flip32(
    mesh: &mut TetMesh,
    protected: &Protected,
    t: u32,
    [a, b]: [u32; 2],
    accept: &Accept32<'_>,
) -> Result<Option<Vec<u32>>> {
    if protected.edge(a, b) {
        return Ok(None);
    }
    let Some((shell, ring)) = mesh.shell3(t, a, b) else {
        return Ok(None);
    };
    if !protected.shell_may_go([a, b], &ring) {
        return Ok(None);
    }
    let [w0, w1, w2] = ring;
    let new = [[a, w0, w1, w2], [b, w0, w2, w1]];
    if !accept(mesh, shell, new) || !new.iter().all(|&q| mesh.positive(q)) {
        return Ok(None);
    }
    mesh.flip32([a, b], shell, ring).map(Some)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a Delaunay tetrahedralization of points spread through a cube (a Kronecker sequence:
    /// the fractional parts of multiples of three irrationals), with nothing protected, the
    /// 2-3 flip of an inner facet succeeds exactly where [`blocking_sides`] finds no side
    /// blocking it ([`remove_edge_deep`] skips the flip where a side blocks it, and removes
    /// the sides named).
    #[test]
    fn a_facet_flips_exactly_where_no_side_blocks_it() {
        let steps = [2f64.sqrt(), 3f64.sqrt(), 5f64.sqrt()];
        let points: Vec<Point> = (1..=40)
            .map(|k| steps.map(|s| (f64::from(k) * s).fract()))
            .collect();
        let used: Vec<u32> = (0..40).collect();
        let mesh = TetMesh::delaunay(points, &used).unwrap();
        let (mut flipped, mut blocked) = (0, 0);
        for t in mesh.tets.live() {
            for i in 0..4 {
                let v = mesh.tets.vertices(t);
                if v.contains(&INFINITE) || mesh.across(t, i) == INFINITE {
                    continue;
                }
                let sides = blocking_sides(&mesh, t, i);
                let mut copy = mesh.clone();
                let done = flip23(&mut copy, &Protected::default(), t, i, &Any).unwrap();
                assert_eq!(done, sides.is_empty(), "facet {i} of {v:?}: {sides:?}");
                if done {
                    flipped += 1;
                } else {
                    blocked += 1;
                }
            }
        }
        assert!(flipped > 20 && blocked > 20, "{flipped} {blocked}");
    }
}
