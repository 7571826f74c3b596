//! The partition of the input surface while points are added on it (George and Borouchaki
//! §5.2: "the input faces exist as a partition").
//!
//! Every input triangle holds a list of *subfaces* (vertex triples with its orientation) that
//! tile it; a point added on the surface has a *host*: the input edge or the input triangle
//! whose interior it was added in. The partition is combinatorial: a point added on an input
//! edge is in its chain whatever the rounding of its coordinates.
//!
//! A point splits the subfaces it lies on; with [`Partition::delaunay_around`], Lawson's
//! flips then make the subfaces around it Delaunay in the triangle's plane (the chains of its
//! edges stay), so that they do not grow thin where many points go on one triangle. A
//! sub-edge inside a triangle may also be flipped to the other diagonal of its two subfaces
//! ([`Partition::flip`]): recovery does so where that diagonal is already a mesh edge.
//!
//! Invariants: the subfaces of a triangle form a disk whose boundary is the chains of its
//! three edges; `protected` holds exactly the current subfaces and their edges.

use rustc_hash::FxHashMap as HashMap;

use super::by_vertex::{vertex_count, ByVertex};
use super::flips::Protected;
use super::tetmesh::key;
use crate::geometry::{cross, sub};
use crate::io::surface::project;
use crate::predicates::{incircle, orient2d, Point, Sign};

/// Where a point added on the surface lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Host {
    /// In the interior of this input edge (sorted vertex pair).
    Edge([u32; 2]),
    /// In the interior of this input triangle.
    Face(usize),
}

pub struct Partition {
    /// The input triangles.
    input: Vec<[u32; 3]>,
    /// The subfaces of the input triangles that points split; an input triangle missing here
    /// is its own only subface.
    split: HashMap<usize, Vec<[u32; 3]>>,
    /// Input triangles around each input vertex.
    vertex_faces: ByVertex<u32>,
    /// The host of every point added on the surface (and still there).
    pub host: HashMap<u32, Host>,
    pub protected: Protected,
}

/// The sorted pair.
pub fn pair(a: u32, b: u32) -> [u32; 2] {
    [a.min(b), a.max(b)]
}

/// The three edges of a triangle.
pub fn sides(f: [u32; 3]) -> [[u32; 2]; 3] {
    [pair(f[0], f[1]), pair(f[1], f[2]), pair(f[2], f[0])]
}

impl Partition {
    pub fn new(triangles: &[[u32; 3]]) -> Self {
        let vertices = vertex_count(triangles);
        let incidences = triangles
            .iter()
            .enumerate()
            .flat_map(|(k, f)| f.map(|v| (v, k as u32)));
        let mut p = Partition {
            input: triangles.to_vec(),
            split: HashMap::default(),
            vertex_faces: ByVertex::new(vertices, incidences),
            host: HashMap::default(),
            protected: Protected::default(),
        };
        p.protected.facets.reserve(triangles.len());
        p.protected.edges.reserve(triangles.len() * 3 / 2);
        for &f in triangles {
            p.protected.insert_facet(f);
        }
        p
    }

    /// The subfaces of input triangle `f`.
    fn subfaces(&self, f: usize) -> &[[u32; 3]] {
        self.split
            .get(&f)
            .map_or(std::slice::from_ref(&self.input[f]), Vec::as_slice)
    }

    /// The subfaces of input triangle `f`, to change.
    fn subfaces_mut(&mut self, f: usize) -> &mut Vec<[u32; 3]> {
        let whole = self.input[f];
        self.split.entry(f).or_insert_with(|| vec![whole])
    }

    /// Drops subface `f` from the protected set, and those of its edges no other subface
    /// uses.
    fn unprotect(&mut self, f: [u32; 3]) {
        self.protected.facets.remove(&key(f));
        for e in sides(f) {
            let used = self
                .faces_of(e[0])
                .iter()
                .any(|&g| self.subfaces(g).iter().any(|&s| sides(s).contains(&e)));
            if !used {
                self.protected.edges.remove(&e);
            }
        }
    }

    /// The input triangles whose closure holds vertex `v`.
    pub fn faces_of(&self, v: u32) -> Vec<usize> {
        match self.host.get(&v) {
            Some(&host) => self.faces_of_host(host),
            None => self.faces_of_vertex(v).map(|f| f as usize).collect(),
        }
    }

    /// The input triangles around input vertex `v`.
    fn faces_of_vertex(&self, v: u32) -> impl Iterator<Item = u32> + '_ {
        self.vertex_faces.of(v).iter().copied()
    }

    /// The input triangles around input edge `e`.
    pub fn faces_of_edge(&self, [a, b]: [u32; 2]) -> Vec<usize> {
        self.faces_of_vertex(a)
            .map(|f| f as usize)
            .filter(|&f| self.input[f].contains(&b))
            .collect()
    }

    /// Where a point added on sub-edge `(p, q)` lies.
    pub fn host_of_subedge(&self, p: u32, q: u32) -> Host {
        let common: Vec<usize> = {
            let fq = self.faces_of(q);
            self.faces_of(p)
                .into_iter()
                .filter(|f| fq.contains(f))
                .collect()
        };
        for &f in &common {
            let tri = self.input[f];
            for e in sides(tri) {
                if self.on_edge(p, e) && self.on_edge(q, e) {
                    return Host::Edge(e);
                }
            }
        }
        // Inside the triangle whose subfaces have it as a side (two triangles can share both
        // ends: a corner and a point on the edge they share, joined by a flip).
        let e = pair(p, q);
        let inside = common
            .iter()
            .copied()
            .find(|&f| self.with_side(f, e).next().is_some());
        Host::Face(inside.or(common.first().copied()).unwrap_or(0))
    }

    /// The input triangles whose closure holds a point of `host`.
    fn faces_of_host(&self, host: Host) -> Vec<usize> {
        match host {
            Host::Edge(e) => self.faces_of_edge(e),
            Host::Face(f) => vec![f],
        }
    }

    /// The input vertices a point of `host` is a combination of: the triangle's corners, or
    /// the edge's ends with the first repeated.
    pub fn corners(&self, host: Host) -> [u32; 3] {
        match host {
            Host::Edge([a, b]) => [a, b, a],
            Host::Face(f) => self.input[f],
        }
    }

    /// Whether vertex `v` lies on input edge `e`: an end of it, or a point added on it.
    pub fn on_edge(&self, v: u32, e: [u32; 2]) -> bool {
        e.contains(&v) || self.host.get(&v) == Some(&Host::Edge(e))
    }

    /// Whether the three vertices of `t` lie on one input edge: a flat subface.
    pub fn on_one_edge(&self, t: [u32; 3]) -> bool {
        t.iter().any(|v| match self.host.get(v) {
            Some(&Host::Edge(e)) => t.iter().all(|&w| self.on_edge(w, e)),
            _ => false,
        })
    }

    /// Every current sub-edge, sorted.
    pub fn subedges(&self) -> Vec<[u32; 2]> {
        let mut e: Vec<[u32; 2]> = self.protected.edges.iter().copied().collect();
        e.sort_unstable_by_key(|&[a, b]| (a as u64) << 32 | b as u64);
        e
    }

    /// The subfaces of input triangle `f` with side `e` (a sorted pair).
    fn with_side(&self, f: usize, e: [u32; 2]) -> impl Iterator<Item = [u32; 3]> + '_ {
        self.subfaces(f)
            .iter()
            .copied()
            .filter(move |&t| sides(t).contains(&e))
    }

    /// Every current subface with its input triangle, in triangle order.
    pub fn all_subfaces(&self) -> Vec<(usize, [u32; 3])> {
        (0..self.input.len())
            .flat_map(|f| self.subfaces(f).iter().map(move |&s| (f, s)))
            .collect()
    }

    /// Records point `s` added on sub-edge `(p, q)`: every subface on that edge is halved.
    pub fn split_edge(&mut self, p: u32, q: u32, s: u32) {
        let host = self.host_of_subedge(p, q);
        let faces = self.faces_of_host(host);
        let e = pair(p, q);
        for &f in &faces {
            let hit: Vec<[u32; 3]> = self.with_side(f, e).collect();
            self.subfaces_mut(f).retain(|&t| !sides(t).contains(&e));
            for t in hit {
                self.protected.facets.remove(&key(t));
                let r = (0..3).find(|&k| t[k] != p && t[k] != q).unwrap_or(0);
                let [x, y, z] = [t[r], t[(r + 1) % 3], t[(r + 2) % 3]];
                // (x, y, z) with the split edge y -> z: both halves keep the orientation.
                for half in [[x, y, s], [x, s, z]] {
                    self.subfaces_mut(f).push(half);
                    self.protected.insert_facet(half);
                }
            }
        }
        self.protected.edges.remove(&e);
        self.host.insert(s, host);
    }

    /// Records point `s` added inside subface `t` of input triangle `f`.
    pub fn split_face(&mut self, f: usize, t: [u32; 3], s: u32) {
        self.subfaces_mut(f).retain(|&u| u != t);
        self.protected.facets.remove(&key(t));
        for k in 0..3 {
            let third = [t[k], t[(k + 1) % 3], s];
            self.subfaces_mut(f).push(third);
            self.protected.insert_facet(third);
        }
        self.host.insert(s, Host::Face(f));
    }

    /// Makes the subfaces around point `s`, just added, Delaunay in each input triangle
    /// holding it.
    pub fn delaunay_around(&mut self, s: u32, points: &[Point]) {
        for f in self.faces_of(s) {
            let fan = self.fan(f, s);
            self.delaunay_flips(f, &fan, points);
        }
    }

    /// Makes the subfaces of input triangle `f` around the sides of `start` Delaunay in the
    /// triangle's plane (Lawson's flips of sub-edges inside `f`; the chains of its edges stay).
    fn delaunay_flips(&mut self, f: usize, start: &[[u32; 3]], points: &[Point]) {
        let plane = Plane::of(self.input[f].map(|v| &points[v as usize]));
        let mut stack: Vec<[u32; 2]> = start.iter().flat_map(|&t| sides(t)).collect();
        // Lawson's flips end; the bound is for subfaces that rounding left overlapping.
        let mut budget = 64 * (self.subfaces(f).len() + 8);
        while let Some(e) = stack.pop() {
            if budget == 0 {
                return;
            }
            budget -= 1;
            let Some(quad) = self.flippable(f, e, &plane, points) else {
                continue;
            };
            let [x, y, w, z] = quad.corners;
            let [px, py, pz, pw] = [x, y, z, w].map(|v| plane.project(&points[v as usize]));
            if incircle(&px, &py, &pz, &pw) != Sign::Positive {
                continue;
            }
            self.flip(f, &quad);
            stack.extend([[x, y], [y, w], [w, z], [z, x]].map(|[p, q]| pair(p, q)));
        }
    }

    /// The two subfaces of input triangle `f` on sub-edge `e`, where flipping `e` to the
    /// other diagonal of their quadrilateral keeps them inside `f` ([`Partition::flip`]): the
    /// triangle's subfaces are the partition's own choice.
    pub fn flippable_in(&self, f: usize, e: [u32; 2], points: &[Point]) -> Option<Quad> {
        let plane = Plane::of(self.input[f].map(|v| &points[v as usize]));
        self.flippable(f, e, &plane, points)
    }

    /// The two subfaces of `f` on sub-edge `e` when their quadrilateral is strictly convex
    /// in the triangle's plane and its other diagonal is not along an edge of `f`.
    fn flippable(&self, f: usize, e: [u32; 2], plane: &Plane, points: &[Point]) -> Option<Quad> {
        let mut on_e = self.with_side(f, e);
        let (Some(t), Some(u), None) = (on_e.next(), on_e.next(), on_e.next()) else {
            return None;
        };
        let r = (0..3).find(|&k| !e.contains(&t[k])).unwrap_or(0);
        let [x, y, z] = [t[r], t[(r + 1) % 3], t[(r + 2) % 3]];
        let w = u.into_iter().find(|v| !e.contains(v)).unwrap_or(u[0]);
        let [px, py, pz, pw] = [x, y, z, w].map(|v| plane.project(&points[v as usize]));
        // x y z and y w z positive, and the quadrilateral x y w z strictly convex.
        let convex = [
            [&px, &py, &pz],
            [&py, &pw, &pz],
            [&px, &py, &pw],
            [&px, &pw, &pz],
        ]
        .into_iter()
        .all(|[p, q, r]| orient2d(p, q, r) == Sign::Positive);
        // A diagonal along an edge of `f` (its ends on one chain, the points between them
        // off it by rounding) would not be inside `f`.
        let along = sides(self.input[f])
            .iter()
            .any(|&side| self.on_edge(x, side) && self.on_edge(w, side));
        (convex && !along).then_some(Quad {
            old: [t, u],
            corners: [x, y, w, z],
        })
    }

    /// Replaces the two subfaces of `quad` in input triangle `f` by those on its other
    /// diagonal.
    pub fn flip(&mut self, f: usize, quad: &Quad) {
        let [x, y, w, z] = quad.corners;
        self.retriangulate(f, &quad.old, &[[x, y, w], [x, w, z]]);
    }

    /// The subfaces of `f` around vertex `v`.
    pub fn fan(&self, f: usize, v: u32) -> Vec<[u32; 3]> {
        self.subfaces(f)
            .iter()
            .copied()
            .filter(|t| t.contains(&v))
            .collect()
    }

    /// Replaces, in triangle `f`, the subfaces `old` by `new` (the retriangulated link of a
    /// removed point), keeping `protected` in step.
    pub fn retriangulate(&mut self, f: usize, old: &[[u32; 3]], new: &[[u32; 3]]) {
        self.subfaces_mut(f).retain(|t| !old.contains(t));
        for &t in new {
            self.subfaces_mut(f).push(t);
            self.protected.insert_facet(t);
        }
        for &t in old {
            self.unprotect(t);
        }
    }
}

/// Two subfaces sharing a sub-edge: `old`, and the corners `x y w z` of their
/// quadrilateral in order, the shared sub-edge `(y, z)`.
pub struct Quad {
    old: [[u32; 3]; 2],
    corners: [u32; 4],
}

impl Quad {
    /// The diagonal a flip makes, `(x, w)`.
    pub fn other_diagonal(&self) -> [u32; 2] {
        [self.corners[0], self.corners[2]]
    }
}

/// The plane of an input triangle, where decisions are exact on the points projected along
/// the axis nearest its normal, turning the way the triangle does.
struct Plane {
    axis: usize,
    upward: bool,
}

impl Plane {
    fn of([a, b, c]: [&Point; 3]) -> Self {
        let n = cross(&sub(b, a), &sub(c, a));
        let axis = (0..3).fold(0, |m, k| if n[k].abs() > n[m].abs() { k } else { m });
        Plane {
            axis,
            upward: n[axis] > 0.0,
        }
    }

    fn project(&self, p: &Point) -> [f64; 2] {
        let [u, v] = project(p, self.axis);
        if self.upward {
            [u, v]
        } else {
            [v, u]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::recovery::tetmesh::Key;

    /// Triangle (0, 1, 2) with a point on two of its edges: 3 on (0, 1), 4 on (1, 2).
    fn split_triangle() -> (Partition, Vec<Point>) {
        let points = vec![
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [0.0, 4.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
        ];
        let mut part = Partition::new(&[[0, 1, 2]]);
        part.split_edge(0, 1, 3);
        part.split_edge(1, 2, 4);
        (part, points)
    }

    #[test]
    fn a_sub_edge_inside_a_triangle_flips_where_its_quadrilateral_is_convex() {
        let (mut part, points) = split_triangle();
        let quad = part.flippable_in(0, [2, 3], &points).expect("convex");
        assert_eq!(quad.other_diagonal(), [0, 4]);
        part.flip(0, &quad);
        let mut tiles: Vec<Key> = part.subfaces(0).iter().map(|&t| key(t)).collect();
        tiles.sort_unstable();
        let mut expected = vec![key([0, 3, 4]), key([0, 4, 2]), key([3, 1, 4])];
        expected.sort_unstable();
        assert_eq!(tiles, expected);
        assert!(part.protected.edge(0, 4) && !part.protected.edge(2, 3));
        assert!(part.protected.facet([0, 3, 4]) && !part.protected.facet([0, 3, 2]));
        // Every subface keeps the triangle's orientation.
        for t in part.subfaces(0) {
            let [a, b, c] = t.map(|v| points[v as usize]);
            assert!(cross(&sub(&b, &a), &sub(&c, &a))[2] > 0.0);
        }
    }

    #[test]
    fn no_flip_where_the_quadrilateral_is_not_strictly_convex_or_the_edge_is_input() {
        let (part, points) = split_triangle();
        // 1, 4, 2 lie on the input edge (1, 2): the quadrilateral 1 4 2 3 is not convex.
        assert!(part.flippable_in(0, [3, 4], &points).is_none());
        // (0, 3) lies on the input edge (0, 1): one subface only.
        assert!(part.flippable_in(0, [0, 3], &points).is_none());
    }
}
