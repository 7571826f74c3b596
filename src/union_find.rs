//! Disjoint sets over `0..n` (union by smaller root, path halving), shared by the modules that
//! group items: grid crossings into surface components (`domain`), coincident crossing points
//! (`mesh2d::crossing`), acute edges at a node and cocircular triangles (`mesh2d`).
//!
//! Invariant: a root is the smallest element of its set, so the partition and every root
//! are functions of the unions made, whatever their order.

pub struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    /// `n` singletons.
    pub fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n as u32).collect(),
        }
    }

    /// The root (smallest element) of the set of `x`.
    pub fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let up = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = up;
            x = up;
        }
        x
    }

    /// Joins the sets of `a` and `b`; false when they were one set already.
    pub fn union(&mut self, a: u32, b: u32) -> bool {
        let (a, b) = (self.find(a), self.find(b));
        if a == b {
            return false;
        }
        self.parent[a.max(b) as usize] = a.min(b);
        true
    }
}
