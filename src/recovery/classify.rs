//! Regions of the recovered mesh and the output (George and Borouchaki §5.3, last remark:
//! the tetrahedra outside the surface are dropped).
//!
//! Regions are the connected components of tetrahedra across facets that are not input
//! triangles. The component of the infinite tetrahedra (around the enclosing box) is the
//! outside. The other components are numbered by their smallest bounding input triangle
//! (the one on its front side first); those between the surface and a kept convex hull get
//! one label after them. Then seeds relabel or remove regions.
//!
//! Output invariants: vertices are the input vertices in input order, then the Steiner points
//! used by kept tetrahedra; facet `k` is input triangle `k`, labels (from, to) with the
//! right-hand normal pointing from `from` to `to`.

use super::by_vertex::ByVertex;
use super::tetmesh::{key, TetMesh};
use super::SurfaceOptions;
use crate::error::{Error, Result};
use crate::mesh::{Mesh, DIMENSION_UNKNOWN};
use crate::predicates::Sign;
use crate::triangulation::tets::{FACE, INFINITE};

/// Component id of the outside.
const OUTSIDE: u32 = 0;

/// The regions of the mesh: the component of every tetrahedron slot, and per component its
/// label (0 = dropped: the outside and holes) and volume bound (0 = none).
pub struct Regions {
    pub component: Vec<u32>,
    pub label: Vec<i32>,
    pub max_volume: Vec<f64>,
    /// Where the bounding triangles are, kept up to date by [`Regions::assign`].
    input: InputFacets,
}

impl Regions {
    /// Whether tetrahedron `t` is in a kept region.
    pub fn kept(&self, t: u32) -> bool {
        self.label[self.component[t as usize] as usize] != 0
    }

    /// Puts the new tetrahedra `created`, which replaced tetrahedra of `mesh` without
    /// crossing a bounding triangle, in component `c`, and notes which of their facets are
    /// bounding triangles.
    pub fn assign(&mut self, mesh: &TetMesh, created: &[u32], c: u32) {
        self.put(created, c);
        self.input.renew(mesh, created);
    }

    /// Puts the tetrahedra `created` in component `c`.
    fn put(&mut self, created: &[u32], c: u32) {
        for &t in created {
            if self.component.len() <= t as usize {
                self.component.resize(t as usize + 1, u32::MAX);
            }
            self.component[t as usize] = c;
        }
    }

    /// [`Regions::assign`] for the cone of [`TetMesh::try_replace_by_cone`]: facet 3 of
    /// `created[j]` is glued outside to the facet that was the bounding triangle
    /// `triangles[j]` ([`Regions::triangle`]) of the replaced tetrahedra, the others to
    /// tetrahedra of the cone. (What [`Regions::assign`] would look up outside, at random
    /// places of memory, the caller had at hand.)
    pub fn assign_cone(&mut self, created: &[u32], triangles: &[u32], c: u32) {
        self.put(created, c);
        for (&t, &k) in created.iter().zip(triangles) {
            self.input.set(t, [NOT_INPUT, NOT_INPUT, NOT_INPUT, k]);
        }
    }

    /// Whether facet `i` of tetrahedron `t` is a bounding triangle.
    pub fn on_surface(&self, t: u32, i: usize) -> bool {
        self.input.contains(t, i)
    }

    /// The number of the bounding triangle facet `i` of tetrahedron `t` is, or
    /// [`NOT_INPUT`].
    pub fn triangle(&self, t: u32, i: usize) -> u32 {
        self.input.triangle[t as usize][i]
    }

    /// Asks the processor to bring what [`Regions::triangle`] reads of `t` into the cache.
    pub fn prefetch(&self, t: u32) {
        crate::prefetch::prefetch(&self.input.triangle, t as usize);
    }

    /// One facet `(t, i)` per bounding triangle.
    pub fn surface_facets(&self) -> &[(u32, usize)] {
        &self.input.at
    }
}

/// The regions of the recovered mesh, labelled and bounded by `options`: `triangles` are the
/// input triangles, then from `first_hull` on the convex hull's (`keep_convex_hull`): the
/// tetrahedra between the surface and the hull get one label, after the others.
pub fn regions(
    mesh: &mut TetMesh,
    triangles: &[[u32; 3]],
    first_hull: usize,
    options: &SurfaceOptions,
) -> Result<Regions> {
    let input = InputFacets::find(mesh, triangles)?;
    let component = components(mesh, &input);
    label(mesh, input, component, (triangles, first_hull), options)
}

/// Where the input triangles are in the mesh: the triangle number of every facet of every
/// tetrahedron slot ([`NOT_INPUT`] for the other facets), and one facet `(t, i)` per
/// triangle. Found in one pass over the tetrahedra (a search of each triangle's facet from a
/// vertex costs several times more), then renewed where tetrahedra are replaced.
struct InputFacets {
    triangle: Vec<[u32; 4]>,
    at: Vec<(u32, usize)>,
}

/// The triangle number of a facet that is no input triangle.
pub const NOT_INPUT: u32 = u32::MAX;
/// The triangle number of the facets of a new tetrahedron, while [`InputFacets::renew`] runs.
const NEW: u32 = u32::MAX - 1;

impl InputFacets {
    /// Errors when an input triangle is not a facet of the mesh.
    fn find(mesh: &TetMesh, triangles: &[[u32; 3]]) -> Result<Self> {
        let index = ByVertex::new(
            mesh.points.len(),
            triangles.iter().enumerate().map(|(k, &f)| {
                let [a, b, c] = key(f);
                (a, ([b, c], k as u32))
            }),
        );
        let mut triangle = vec![[NOT_INPUT; 4]; mesh.tets.slots()];
        let mut at = vec![(u32::MAX, 0); triangles.len()];
        for t in mesh.tets.live() {
            for i in 0..4 {
                // Each facet once, from the lower of its two tetrahedra.
                let g = mesh.tets.glued(t, i);
                let (n, j) = (g >> 2, (g & 3) as usize);
                if n < t {
                    continue;
                }
                let [a, b, c] = key(mesh.facet(t, i));
                if let Some(&(_, k)) = index.find(a, |(bc, _)| *bc == [b, c]) {
                    triangle[t as usize][i] = k;
                    triangle[n as usize][j] = k;
                    at[k as usize] = (t, i);
                }
            }
        }
        if let Some(k) = at.iter().position(|&(t, _)| t == u32::MAX) {
            let f = triangles[k];
            return Err(Error::internal(format!(
                "input triangle {k} {f:?} is not a facet"
            )));
        }
        Ok(InputFacets { triangle, at })
    }

    /// Notes the input triangles among the facets of the tetrahedra `created`, which
    /// replaced others without crossing an input triangle: a facet glued to an older
    /// tetrahedron is the triangle that one has there, and a facet between two new ones is
    /// none (the input triangles were all facets before, and a triangle is the facet of one
    /// pair of tetrahedra only).
    fn renew(&mut self, mesh: &TetMesh, created: &[u32]) {
        for &t in created {
            self.set(t, [NEW; 4]);
        }
        // A facet between two new tetrahedra reads `NEW` or, once the other is set,
        // `NOT_INPUT`.
        for &t in created {
            let row = std::array::from_fn(|i| {
                let g = mesh.tets.glued(t, i);
                match self.triangle[(g >> 2) as usize][(g & 3) as usize] {
                    NEW => NOT_INPUT,
                    k => k,
                }
            });
            self.set(t, row);
        }
    }

    /// Sets the triangle numbers of the facets of `t`.
    fn set(&mut self, t: u32, row: [u32; 4]) {
        if self.triangle.len() <= t as usize {
            self.triangle.resize(t as usize + 1, [NOT_INPUT; 4]);
        }
        self.triangle[t as usize] = row;
        for (i, &k) in row.iter().enumerate() {
            if k < NEW {
                self.at[k as usize] = (t, i);
            }
        }
    }

    /// Whether facet `i` of tetrahedron `t` is an input triangle.
    fn contains(&self, t: u32, i: usize) -> bool {
        self.triangle[t as usize][i] != NOT_INPUT
    }

    /// The tetrahedra on the front (right-hand normal) and back sides of input triangle `k`,
    /// `f`.
    fn sides(&self, mesh: &TetMesh, k: usize, f: [u32; 3]) -> (u32, u32) {
        let (t, i) = self.at[k];
        let n = mesh.tets.neighbor(t, i);
        if mesh.in_front(t, i, f) {
            (t, n)
        } else {
            (n, t)
        }
    }
}

/// Connected components across non-input facets; the infinite tetrahedra's is [`OUTSIDE`].
fn components(mesh: &TetMesh, input: &InputFacets) -> Vec<u32> {
    let slots = mesh.tets.slots();
    let mut component = vec![u32::MAX; slots];
    let start = mesh
        .tets
        .live()
        .find(|&t| mesh.tets.vertices(t).contains(&INFINITE));
    let order = start.into_iter().chain(mesh.tets.live());
    let mut next = 0;
    let mut stack = Vec::new();
    for seed in order {
        if component[seed as usize] != u32::MAX {
            continue;
        }
        component[seed as usize] = next;
        stack.push(seed);
        while let Some(t) = stack.pop() {
            for i in 0..4 {
                let n = mesh.tets.neighbor(t, i);
                if component[n as usize] == u32::MAX && !input.contains(t, i) {
                    component[n as usize] = next;
                    stack.push(n);
                }
            }
        }
        next += 1;
    }
    component
}

/// Labels of the components: numbered by smallest bounding triangle (front side first), then
/// region seeds relabel and hole seeds drop theirs.
fn label(
    mesh: &mut TetMesh,
    input: InputFacets,
    component: Vec<u32>,
    (triangles, first_hull): (&[[u32; 3]], usize),
    options: &SurfaceOptions,
) -> Result<Regions> {
    let count = component
        .iter()
        .filter(|&&c| c != u32::MAX)
        .max()
        .map_or(0, |&c| c + 1);
    let mut label = vec![0i32; count as usize];
    let mut max_volume = vec![options.max_volume; count as usize];
    let mut next = 1 + options
        .regions
        .iter()
        .map(|r| r.label)
        .max()
        .unwrap_or(0)
        .max(0);
    // The tetrahedra between the surface and the hull (next to a hull triangle, past the
    // `first_hull` input ones) get one label, after the others': those keep their labels.
    let mut between = vec![false; count as usize];
    for (k, &f) in triangles.iter().enumerate().skip(first_hull) {
        let (front, back) = input.sides(mesh, k, f);
        for t in [front, back] {
            between[component[t as usize] as usize] = true;
        }
    }
    for (k, &f) in triangles.iter().enumerate() {
        let (front, back) = input.sides(mesh, k, f);
        for t in [front, back] {
            let c = component[t as usize];
            if c != OUTSIDE && label[c as usize] == 0 && !between[c as usize] {
                label[c as usize] = next;
                next += 1;
            }
        }
    }
    for (c, &b) in between.iter().enumerate() {
        if b && c != OUTSIDE as usize {
            label[c] = next;
        }
    }
    for seed in &options.regions {
        let c = seed_component(mesh, &input, &component, seed.point, "region")?;
        if c == OUTSIDE {
            return Err(Error::invalid_argument(format!(
                "region seed {:?} lies outside the surface",
                seed.point
            )));
        }
        label[c as usize] = seed.label;
        if seed.max_volume > 0.0 {
            max_volume[c as usize] = seed.max_volume;
        }
    }
    for &h in &options.holes {
        let c = seed_component(mesh, &input, &component, h, "hole")?;
        label[c as usize] = 0;
    }
    Ok(Regions {
        component,
        label,
        max_volume,
        input,
    })
}

/// The component of a tetrahedron whose closure holds `p` (exact tests); a point on an input
/// triangle is refused.
fn seed_component(
    mesh: &TetMesh,
    input: &InputFacets,
    component: &[u32],
    p: [f64; 3],
    what: &str,
) -> Result<u32> {
    for t in mesh.tets.live() {
        let v = mesh.tets.vertices(t);
        if v.contains(&INFINITE) {
            continue;
        }
        let signs: Vec<Sign> = (0..4)
            .map(|i| {
                let [a, b, c] = FACE[i].map(|k| *mesh.point(v[k]));
                crate::predicates::orient3d(&a, &b, &c, &p)
            })
            .collect();
        if signs.contains(&Sign::Negative) {
            continue;
        }
        // In the closed tetrahedron: fine unless on an input triangle.
        let on_surface = (0..4).any(|i| signs[i] == Sign::Zero && input.contains(t, i));
        if on_surface {
            return Err(Error::invalid_argument(format!(
                "{what} seed {p:?} lies on the surface: move it into a region"
            )));
        }
        return Ok(component[t as usize]);
    }
    Err(Error::invalid_argument(format!(
        "{what} seed {p:?} lies outside the enclosing box of the surface"
    )))
}

/// The output arrays: the mesh of the kept regions, with the input triangles as facets (the
/// first of those [`regions`] was given). Steiner points have dimension 3, or 2 when
/// `on_hull` (left on a kept convex hull).
pub fn assemble(
    mesh: &TetMesh,
    n_input: usize,
    triangles: &[[u32; 3]],
    regions: &Regions,
    on_hull: &dyn Fn(u32) -> bool,
) -> Result<Mesh> {
    let label_of = |t: u32| regions.label[regions.component[t as usize] as usize];
    let mut number = vec![u32::MAX; mesh.points.len()];
    for (v, n) in number.iter_mut().enumerate().take(n_input) {
        *n = v as u32;
    }
    let mut vertices: Vec<f64> = mesh.points[..n_input].as_flattened().to_vec();
    let mut dimensions = vec![DIMENSION_UNKNOWN; n_input];
    for f in triangles {
        for &v in f {
            dimensions[v as usize] = 2;
        }
    }
    let mut tetrahedra = Vec::new();
    let mut labels = Vec::new();
    let kept: Vec<u32> = mesh
        .tets
        .live()
        .filter(|&t| !mesh.tets.vertices(t).contains(&INFINITE) && label_of(t) != 0)
        .collect();
    for t in kept {
        for v in mesh.tets.vertices(t) {
            if (v as usize) < n_input && dimensions[v as usize] == DIMENSION_UNKNOWN {
                // An input vertex no triangle uses, inside a kept region.
                dimensions[v as usize] = 3;
            }
            if number[v as usize] == u32::MAX {
                number[v as usize] = (vertices.len() / 3) as u32;
                vertices.extend_from_slice(mesh.point(v));
                dimensions.push(if on_hull(v) { 2 } else { 3 });
            }
            tetrahedra.push(number[v as usize]);
        }
        labels.push(label_of(t));
    }
    let input = &regions.input;
    let mut facet_labels = Vec::with_capacity(2 * triangles.len());
    for (k, &f) in triangles.iter().enumerate() {
        let (front, back) = input.sides(mesh, k, f);
        let side = |t: u32| {
            if mesh.tets.vertices(t).contains(&INFINITE) {
                0
            } else {
                label_of(t)
            }
        };
        facet_labels.extend_from_slice(&[side(back), side(front)]);
    }
    Ok(Mesh {
        vertices,
        vertex_dimensions: dimensions,
        tetrahedra,
        tetrahedron_labels: labels,
        facets: triangles.as_flattened().to_vec(),
        facet_labels,
        ..Mesh::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::recovery::partition::Partition;

    /// The triangle numbers renewed through refinement, which replaces tetrahedra by
    /// cavities and flips, are those a new search finds, and every triangle's facet is live.
    #[test]
    fn input_facets_renewed_through_refinement_are_where_a_search_finds_them() {
        let points: Vec<[f64; 3]> = [
            [1, 0, 0],
            [-1, 0, 0],
            [0, 1, 0],
            [0, -1, 0],
            [0, 0, 1],
            [0, 0, -1],
        ]
        .map(|p| p.map(f64::from))
        .to_vec();
        let triangles = [
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ];
        let mut mesh = super::super::enclosed_delaunay(&points, &triangles, &[]).unwrap();
        let options = SurfaceOptions {
            max_volume: 0.002,
            ..SurfaceOptions::default()
        };
        let mut regions = regions(&mut mesh, &triangles, triangles.len(), &options).unwrap();
        let protected = Partition::new(&triangles).protected;
        super::super::refine::refine(&mut mesh, &protected, &mut regions, 0.0, 6).unwrap();
        // Six input vertices and the box's eight corners.
        assert!(mesh.points.len() > 14 + 200, "{} points", mesh.points.len());
        let found = InputFacets::find(&mesh, &triangles).unwrap();
        for t in mesh.tets.live() {
            assert_eq!(
                regions.input.triangle[t as usize], found.triangle[t as usize],
                "tetrahedron {t}"
            );
        }
        for (k, &(t, i)) in regions.input.at.iter().enumerate() {
            assert!(mesh.tets.is_live(t));
            assert_eq!(found.triangle[t as usize][i], k as u32);
        }
    }
}
