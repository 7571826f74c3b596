//! 3D Delaunay and regular (weighted Delaunay) triangulations (DESIGN.md layer 2).
//!
//! Bowyer–Watson insertion: locate the point by a visibility walk from the last created
//! tetrahedron, grow its conflict cavity by a search across facets, and fill the cavity with the
//! cone from the new point over the cavity boundary. The convex hull is closed by tetrahedra
//! incident to an [`INFINITE`](tets::INFINITE) vertex, so every point, inside or outside the
//! current hull, is inserted the same way.
//!
//! Every decision is an exact predicate with symbolic perturbation (`predicates::*_sos`), so
//! the triangulation of a point set is unique — also for cospherical or coplanar inputs — and
//! does not depend on the insertion order: it is the regular triangulation of the points with
//! infinitesimally perturbed weights.
//!
//! Invariants: see [`tets`]; in addition every inserted, non-hidden vertex is a vertex of some
//! live tetrahedron, and no tetrahedron is in conflict with the vertex opposite any of its
//! facets (local Delaunay/regularity, equivalent to the global property). `validate` checks
//! them all exactly.

pub mod edge_table;
mod incremental;
mod insert;
mod remove;
mod sort;
pub mod tets;
mod validate;

pub use incremental::Conflicts;

use crate::error::{Error, ErrorKind, Result};
use crate::mesh::{Mesh, DIMENSION_UNKNOWN};
use crate::predicates::{orient2d, orient3d, BoxFilter, Point, Sign};
use tets::{Tets, INFINITE};

/// Delaunay tetrahedralization of `xyz` (3 coordinates per point). Output vertex `i` is
/// input point `i`; duplicates are merged onto their first occurrence (`Mesh::duplicate_of`).
pub fn delaunay_tetrahedralize(xyz: &[f64]) -> Result<Mesh> {
    let mut t = Triangulation::new(xyz, None)?;
    t.insert_all()?;
    Ok(t.into_mesh())
}

/// Regular (weighted Delaunay) tetrahedralization: the power of `x` with respect to point `p`
/// of weight `w` is `|x - p|^2 - w`. Hidden (redundant) points are referenced by no
/// tetrahedron. An input point identical to an earlier one in position and weight is merged
/// onto it (`Mesh::duplicate_of`); points at one position with different weights are not
/// copies: the heaviest is kept and the others are hidden, as in the power diagram.
pub fn regular_tetrahedralize(xyz: &[f64], weights: &[f64]) -> Result<Mesh> {
    let mut t = Triangulation::new(xyz, Some(weights))?;
    t.insert_all()?;
    Ok(t.into_mesh())
}

/// Largest number of input points: tetrahedron facets are addressed as `4*t+i` in 32 bits,
/// and a triangulation has fewer than 7 tetrahedra per point in practice.
pub const MAX_POINTS: usize = 1 << 27;

/// Largest accepted coordinate magnitude: the in-sphere determinant has degree 5, and its
/// terms must stay below the largest double.
pub const MAX_COORDINATE: f64 = 1e60;

/// What happened to an input point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointState {
    /// Not yet inserted.
    Pending,
    /// A vertex of the triangulation (it may since have been hidden by a heavier point).
    Inserted,
    /// Same position (and weight) as the given input point; merged onto it.
    Duplicate(u32),
    /// A weighted point whose power cell is empty at insertion.
    Hidden,
    /// A vertex since removed (`Triangulation::remove`).
    Removed,
}

/// A 3D Delaunay or regular triangulation of borrowed points.
///
/// Vertices are numbered internally in insertion order (`order[v]` is the input index of
/// vertex `v`), so that the coordinates of nearby vertices are close in memory; the public
/// interface speaks of input indices only.
pub struct Triangulation<'a> {
    input: &'a [[f64; 3]],
    order: Vec<u32>,
    /// Coordinates and weights in insertion order; `weights` is empty for Delaunay.
    points: Vec<[f64; 3]>,
    weights: Vec<f64>,
    tets: Tets,
    /// Filters whose bounds are fixed by the points' bounding box.
    filter: BoxFilter,
    /// What became of each vertex, in insertion order.
    state: Vec<PointState>,
    /// Where the next walk starts.
    hint: u32,
    /// Walk randomization (xorshift32), deterministic.
    rng: u32,
    scratch: insert::Scratch,
    /// The box every vertex lies in (the filters' bounds).
    bounds: (Point, Point),
}

impl<'a> Triangulation<'a> {
    /// Checks the input and prepares an empty triangulation; `weights` selects a regular one.
    pub fn new(xyz: &'a [f64], weights: Option<&'a [f64]>) -> Result<Self> {
        let (points, rest) = xyz.as_chunks::<3>();
        if !rest.is_empty() {
            return Err(Error::invalid_input(format!(
                "{} coordinates is not a multiple of 3",
                xyz.len()
            )));
        }
        validate_points(points, weights)?;
        let (lo, hi) = bounding_box(points);
        let order = sort::brio_order(points, &lo, &hi);
        let sorted = order.iter().map(|&i| points[i as usize]).collect();
        let weights = match weights {
            Some(w) => order.iter().map(|&i| w[i as usize]).collect(),
            None => Vec::new(),
        };
        Ok(Triangulation {
            filter: BoxFilter::new(&lo, &hi),
            input: points,
            order,
            points: sorted,
            weights,
            tets: Tets::with_capacity(7 * points.len() + 16)?,
            state: vec![PointState::Pending; points.len()],
            hint: 0,
            rng: 0x9e37_79b9,
            scratch: insert::Scratch::default(),
            bounds: (lo, hi),
        })
    }

    /// Whether this is a regular (weighted) triangulation.
    #[inline]
    pub fn is_regular(&self) -> bool {
        !self.weights.is_empty()
    }

    #[inline]
    fn point(&self, v: u32) -> &Point {
        &self.points[v as usize]
    }

    /// Input index of vertex `v`.
    #[inline]
    fn input_index(&self, v: u32) -> u32 {
        self.order[v as usize]
    }

    /// What became of each input point, by input index.
    pub fn states(&self) -> Vec<PointState> {
        let mut by_input = vec![PointState::Pending; self.state.len()];
        for (v, &s) in self.state.iter().enumerate() {
            by_input[self.order[v] as usize] = s;
        }
        by_input
    }

    /// Finite live tetrahedra, as quadruples of input indices (positively oriented).
    pub fn finite_tetrahedra(&self) -> impl Iterator<Item = [u32; 4]> + '_ {
        self.tets
            .live()
            .map(|t| self.tets.vertices(t))
            .filter(|v| !v.contains(&INFINITE))
            .map(|v| v.map(|x| self.input_index(x)))
    }

    /// Inserts every point in BRIO/Hilbert order.
    pub fn insert_all(&mut self) -> Result<()> {
        if self.is_regular() {
            self.mark_exact_copies();
        }
        let first = self.initial_tetrahedron()?;
        for p in 0..self.points.len() as u32 {
            if !first.contains(&p) && self.state[p as usize] == PointState::Pending {
                self.insert(p)?;
            }
        }
        Ok(())
    }

    /// Regular triangulations: marks every exact copy (same position and weight) of an earlier
    /// input point as its duplicate before anything is inserted, so that copies of points that
    /// end up hidden are reported too. (Delaunay insertion finds copies on its own: there, every
    /// point that is not a copy becomes a vertex.)
    fn mark_exact_copies(&mut self) {
        let value = |v: u32| {
            let [x, y, z] = self.points[v as usize];
            [x, y, z, self.weights[v as usize]]
        };
        let mut by_value: Vec<u32> = (0..self.points.len() as u32).collect();
        by_value.sort_unstable_by(|&u, &v| {
            let order = value(u)
                .partial_cmp(&value(v))
                .unwrap_or(std::cmp::Ordering::Equal);
            order.then(self.order[u as usize].cmp(&self.order[v as usize]))
        });
        for run in by_value.chunk_by(|&u, &v| value(u) == value(v)) {
            let first = self.input_index(run[0]);
            for &v in &run[1..] {
                self.state[v as usize] = PointState::Duplicate(first);
            }
        }
    }

    /// Finds four affinely independent points (the first ones in insertion order that are not
    /// copies) and builds the first tetrahedron with its four infinite neighbours.
    fn initial_tetrahedron(&mut self) -> Result<[u32; 4]> {
        let n = self.points.len();
        let p = |i: u32| self.point(i);
        let pending = |i: &u32| self.state[*i as usize] == PointState::Pending;
        let mut all = (0..n as u32).filter(pending);
        let a = all.next().unwrap_or(0);
        let b = all.clone().find(|&i| p(i) != p(a));
        let b = b.ok_or_else(|| too_few(n, "all points coincide"))?;
        let c = all.clone().find(|&i| !collinear(p(a), p(b), p(i)));
        let c = c.ok_or_else(|| too_few(n, "all points are collinear"))?;
        let d = all.find(|&i| orient3d(p(a), p(b), p(c), p(i)) != Sign::Zero);
        let d = d.ok_or_else(|| too_few(n, "all points are coplanar"))?;
        let (a, b) = if orient3d(p(a), p(b), p(c), p(d)) == Sign::Positive {
            (a, b)
        } else {
            (b, a)
        };
        self.build_first_tetrahedron([a, b, c, d])?;
        Ok([a, b, c, d])
    }

    fn build_first_tetrahedron(&mut self, v: [u32; 4]) -> Result<()> {
        let t0 = self.tets.allocate()?;
        self.tets.set(t0, v);
        for i in 0..4 {
            let [f0, f1, f2] = tets::FACE[i].map(|k| v[k]);
            // Reversed facet + infinite vertex: positive with the outer side substituted.
            let ti = self.tets.allocate()?;
            self.tets.set(ti, [f1, f0, f2, INFINITE]);
            self.tets.glue(4 * t0 + i as u32, 4 * ti + 3);
        }
        // The four infinite tetrahedra meet pairwise along the hull edges.
        for a in 1..5u32 {
            for b in a + 1..5u32 {
                let (fa, fb) = self.shared_facet(a, b);
                self.tets.glue(4 * a + fa, 4 * b + fb);
            }
        }
        for i in v {
            self.state[i as usize] = PointState::Inserted;
        }
        self.hint = t0;
        Ok(())
    }

    /// Local facet indices by which tetrahedra `a` and `b` (sharing three vertices) touch.
    fn shared_facet(&self, a: u32, b: u32) -> (u32, u32) {
        let (va, vb) = (self.tets.vertices(a), self.tets.vertices(b));
        let fa = va.iter().position(|x| !vb.contains(x)).unwrap_or(0) as u32;
        let fb = vb.iter().position(|x| !va.contains(x)).unwrap_or(0) as u32;
        (fa, fb)
    }

    /// The tetrahedra with every finite vertex renumbered as its input index (glued facets
    /// kept), for callers that go on editing the triangulation by local operations. The input
    /// must have no duplicate points (a duplicate is referenced by no tetrahedron).
    pub fn into_input_numbered(mut self) -> Tets {
        for t in 0..self.tets.slots() as u32 {
            if self.tets.is_live(t) {
                let v = self.tets.vertices(t);
                let renumbered = v.map(|x| {
                    if x == INFINITE {
                        x
                    } else {
                        self.order[x as usize]
                    }
                });
                self.tets.set(t, renumbered);
            }
        }
        self.tets
    }

    /// The result mesh: input points in input order, finite tetrahedra, label 1.
    pub fn into_mesh(self) -> Mesh {
        let n = self.input.len();
        let rep = self.representatives();
        let mut tetrahedra = self.tets.into_finite();
        for v in &mut tetrahedra {
            *v = rep[self.order[*v as usize] as usize];
        }
        Mesh {
            vertices: self.input.as_flattened().to_vec(),
            vertex_dimensions: vec![DIMENSION_UNKNOWN; n],
            tetrahedron_labels: vec![1; tetrahedra.len() / 4],
            tetrahedra,
            duplicate_of: rep,
            ..Mesh::default()
        }
    }

    /// For every input point, the input point that stands for its position: the smallest
    /// index among a group of merged duplicates, itself otherwise.
    fn representatives(&self) -> Vec<u32> {
        let mut rep: Vec<u32> = (0..self.input.len() as u32).collect();
        let duplicates = || {
            self.state.iter().enumerate().filter_map(|(v, s)| match *s {
                PointState::Duplicate(w) => Some((self.order[v], w)),
                _ => None,
            })
        };
        for (i, w) in duplicates() {
            rep[w as usize] = rep[w as usize].min(i);
        }
        for (i, w) in duplicates() {
            rep[i as usize] = rep[w as usize];
        }
        rep
    }
}

fn too_few(n: usize, what: &str) -> Error {
    Error::invalid_input(format!(
        "{what} ({n} points): a tetrahedralization needs 4 affinely independent points"
    ))
}

/// The smallest box containing the points.
pub(crate) fn bounding_box(points: &[[f64; 3]]) -> (Point, Point) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// Exact collinearity: the cross product vanishes iff its three projections do.
fn collinear(a: &Point, b: &Point, c: &Point) -> bool {
    [(0, 1), (1, 2), (0, 2)]
        .iter()
        .all(|&(i, j)| orient2d(&[a[i], a[j]], &[b[i], b[j]], &[c[i], c[j]]) == Sign::Zero)
}

fn validate_points(points: &[[f64; 3]], weights: Option<&[f64]>) -> Result<()> {
    if points.len() < 4 {
        return Err(Error::invalid_input(format!(
            "{} points given: a tetrahedralization needs at least 4",
            points.len()
        )));
    }
    if points.len() > MAX_POINTS {
        return Err(Error::new(
            ErrorKind::Limit,
            format!(
                "{} points given: at most {MAX_POINTS} are supported",
                points.len()
            ),
        ));
    }
    if let Some(i) = points.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
        return Err(Error::invalid_input(format!(
            "point {i} has a non-finite coordinate {:?}",
            points[i]
        )));
    }
    if let Some(i) = points
        .iter()
        .position(|p| p.iter().any(|c| c.abs() > MAX_COORDINATE))
    {
        return Err(Error::invalid_input(format!(
            "point {i} {:?} has a coordinate beyond {MAX_COORDINATE:e}, where the exact in-sphere \
             test would overflow",
            points[i]
        )));
    }
    if let Some(w) = weights {
        if w.len() != points.len() {
            return Err(Error::invalid_input(format!(
                "{} weights for {} points",
                w.len(),
                points.len()
            )));
        }
        if let Some(i) = w.iter().position(|x| !x.is_finite()) {
            return Err(Error::invalid_input(format!(
                "point {i} has a non-finite weight {}",
                w[i]
            )));
        }
    }
    Ok(())
}
