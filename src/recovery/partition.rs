//! The partition of the input surface while points are added on it (George and Borouchaki
//! §5.2: "the input faces exist as a partition").
//!
//! Every input triangle holds a list of *subfaces* (vertex triples with its orientation) that
//! tile it; a point added on the surface has a *host*: the input edge or the input triangle
//! whose interior it was added in. The partition is combinatorial: a point added on an input
//! edge is in its chain whatever the rounding of its coordinates.
//!
//! Invariants: the subfaces of a triangle form a disk whose boundary is the chains of its
//! three edges; `protected` holds exactly the current subfaces and their edges.

use rustc_hash::FxHashMap as HashMap;

use super::flips::Protected;
use super::tetmesh::key;

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
    /// Per input triangle, its subfaces.
    pub subfaces: Vec<Vec<[u32; 3]>>,
    /// Input triangles around each input edge.
    edge_faces: HashMap<[u32; 2], Vec<usize>>,
    /// Input triangles around each input vertex.
    vertex_faces: HashMap<u32, Vec<usize>>,
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
        let mut p = Partition {
            input: triangles.to_vec(),
            subfaces: triangles.iter().map(|&f| vec![f]).collect(),
            edge_faces: HashMap::default(),
            vertex_faces: HashMap::default(),
            host: HashMap::default(),
            protected: Protected::default(),
        };
        for (k, &f) in triangles.iter().enumerate() {
            for e in sides(f) {
                p.edge_faces.entry(e).or_default().push(k);
            }
            for v in f {
                p.vertex_faces.entry(v).or_default().push(k);
            }
            p.protect(f);
        }
        p
    }

    fn protect(&mut self, f: [u32; 3]) {
        self.protected.facets.insert(key(f));
        for e in sides(f) {
            self.protected.edges.insert(e);
        }
    }

    /// Drops subface `f` from the protected set, and those of its edges no other subface
    /// uses.
    fn unprotect(&mut self, f: [u32; 3]) {
        self.protected.facets.remove(&key(f));
        for e in sides(f) {
            let used = self
                .faces_of(e[0])
                .iter()
                .any(|&g| self.subfaces[g].iter().any(|&s| sides(s).contains(&e)));
            if !used {
                self.protected.edges.remove(&e);
            }
        }
    }

    /// The input triangles whose closure holds vertex `v`.
    pub fn faces_of(&self, v: u32) -> Vec<usize> {
        match self.host.get(&v) {
            Some(Host::Face(f)) => vec![*f],
            Some(Host::Edge(e)) => self.edge_faces.get(e).cloned().unwrap_or_default(),
            None => self.vertex_faces.get(&v).cloned().unwrap_or_default(),
        }
    }

    /// The input triangles around input edge `e`.
    pub fn faces_of_edge(&self, e: [u32; 2]) -> &[usize] {
        self.edge_faces.get(&e).map_or(&[], |v| v.as_slice())
    }

    /// Where a point added on sub-edge `(p, q)` lies.
    pub fn host_of_subedge(&self, p: u32, q: u32) -> Host {
        let on_edge =
            |v: u32, e: [u32; 2]| e.contains(&v) || self.host.get(&v) == Some(&Host::Edge(e));
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
                if on_edge(p, e) && on_edge(q, e) {
                    return Host::Edge(e);
                }
            }
        }
        Host::Face(common.first().copied().unwrap_or(0))
    }

    /// Every current sub-edge, sorted.
    pub fn subedges(&self) -> Vec<[u32; 2]> {
        let mut e: Vec<[u32; 2]> = self.protected.edges.iter().copied().collect();
        e.sort_unstable();
        e
    }

    /// Every current subface with its input triangle, in triangle order.
    pub fn all_subfaces(&self) -> Vec<(usize, [u32; 3])> {
        self.subfaces
            .iter()
            .enumerate()
            .flat_map(|(f, subs)| subs.iter().map(move |&s| (f, s)))
            .collect()
    }

    /// Records point `s` added on sub-edge `(p, q)`: every subface on that edge is halved.
    pub fn split_edge(&mut self, p: u32, q: u32, s: u32) {
        let host = self.host_of_subedge(p, q);
        let faces: Vec<usize> = match host {
            Host::Edge(e) => self.faces_of_edge(e).to_vec(),
            Host::Face(f) => vec![f],
        };
        let e = pair(p, q);
        for &f in &faces {
            let hit: Vec<[u32; 3]> = self.subfaces[f]
                .iter()
                .copied()
                .filter(|&t| sides(t).contains(&e))
                .collect();
            self.subfaces[f].retain(|&t| !sides(t).contains(&e));
            for t in hit {
                self.protected.facets.remove(&key(t));
                let r = (0..3).find(|&k| t[k] != p && t[k] != q).unwrap_or(0);
                let [x, y, z] = [t[r], t[(r + 1) % 3], t[(r + 2) % 3]];
                // (x, y, z) with the split edge y -> z: both halves keep the orientation.
                for half in [[x, y, s], [x, s, z]] {
                    self.subfaces[f].push(half);
                    self.protect(half);
                }
            }
        }
        self.protected.edges.remove(&e);
        self.host.insert(s, host);
    }

    /// Records point `s` added inside subface `t` of input triangle `f`.
    pub fn split_face(&mut self, f: usize, t: [u32; 3], s: u32) {
        self.subfaces[f].retain(|&u| u != t);
        self.protected.facets.remove(&key(t));
        for k in 0..3 {
            let third = [t[k], t[(k + 1) % 3], s];
            self.subfaces[f].push(third);
            self.protect(third);
        }
        self.host.insert(s, Host::Face(f));
    }

    /// The subfaces of `f` around vertex `v`.
    pub fn fan(&self, f: usize, v: u32) -> Vec<[u32; 3]> {
        self.subfaces[f]
            .iter()
            .copied()
            .filter(|t| t.contains(&v))
            .collect()
    }

    /// Replaces, in triangle `f`, the subfaces `old` by `new` (the retriangulated link of a
    /// removed point), keeping `protected` in step.
    pub fn retriangulate(&mut self, f: usize, old: &[[u32; 3]], new: &[[u32; 3]]) {
        self.subfaces[f].retain(|t| !old.contains(t));
        for &t in new {
            self.subfaces[f].push(t);
            self.protect(t);
        }
        for &t in old {
            self.unprotect(t);
        }
    }
}
