//! Flat tetrahedron storage: vertex `i` of tetrahedron `t`, and the facet `4*t'+j` glued to
//! facet `i` of `t` (the facet opposite vertex `i`), so the facing
//! facet is never searched for (the layout of geogram and HXT).
//!
//! Invariants (checked by `Triangulation::validate`):
//! - a live tetrahedron has four distinct vertices; at most one is [`INFINITE`];
//! - a finite tetrahedron is positively oriented (`orient3d(v0,v1,v2,v3) > 0`); an infinite one
//!   is positively oriented when its infinite vertex is replaced by any point strictly outside
//!   the convex hull beyond its finite facet;
//! - adjacency is symmetric: facet `4t+i` is glued to `4t'+j` iff `4t'+j` is glued to `4t+i`, and glued facets have the same vertex set;
//! - dead tetrahedra have `DEAD` as first vertex and are listed in `free`.

use crate::error::{Error, ErrorKind, Result};

/// Most tetrahedra a triangulation holds: facets are addressed as `4*t+i` in 32 bits.
pub const MAX_TETRAHEDRA: usize = 1 << 30;

/// The vertex at infinity that closes the convex hull.
pub const INFINITE: u32 = u32::MAX;
/// First vertex of a dead (recyclable) tetrahedron.
pub const DEAD: u32 = u32::MAX - 1;

/// `FACE[i]` lists the local positions of the facet opposite vertex `i`, ordered so that
/// `(FACE[i], i)` is positively oriented whenever `(0, 1, 2, 3)` is: the facet seen from the
/// inside of its tetrahedron is counter-clockwise.
pub const FACE: [[usize; 3]; 4] = [[1, 3, 2], [0, 2, 3], [0, 3, 1], [0, 1, 2]];

/// Tetrahedra in one flat array of 8 words each: 4 vertices then 4 glued facets, so that a
/// visit to a tetrahedron touches one cache line.
#[derive(Clone, Default)]
pub struct Tets {
    data: Vec<u32>,
    /// Per-tetrahedron conflict mark of the insertion under way (see `insert`).
    pub mark: Vec<u8>,
    pub free: Vec<u32>,
}

impl Tets {
    pub fn with_capacity(tets: usize) -> Result<Self> {
        let mut s = Tets::default();
        let oom = |_| Error::new(ErrorKind::OutOfMemory, "cannot reserve tetrahedra");
        s.data.try_reserve(8 * tets).map_err(oom)?;
        s.mark.try_reserve(tets).map_err(oom)?;
        Ok(s)
    }

    /// Number of slots, live or dead.
    #[inline]
    pub fn slots(&self) -> usize {
        self.mark.len()
    }

    #[inline]
    pub fn is_live(&self, t: u32) -> bool {
        self.data[8 * t as usize] != DEAD
    }

    #[inline]
    pub fn vertices(&self, t: u32) -> [u32; 4] {
        let i = 8 * t as usize;
        [
            self.data[i],
            self.data[i + 1],
            self.data[i + 2],
            self.data[i + 3],
        ]
    }

    /// The facet `4*t'+j` glued to facet `i` of `t`.
    #[inline]
    pub fn glued(&self, t: u32, i: usize) -> u32 {
        self.data[8 * t as usize + 4 + i]
    }

    /// The tetrahedron across facet `i` of `t`.
    #[inline]
    pub fn neighbor(&self, t: u32, i: usize) -> u32 {
        self.glued(t, i) >> 2
    }

    /// Asks the processor to bring tetrahedron `t` into the cache, for a visit soon.
    #[inline]
    pub fn prefetch(&self, t: u32) {
        crate::prefetch::prefetch(&self.data, 8 * t as usize);
    }

    /// Local position of the infinite vertex, if any.
    #[inline]
    pub fn infinite_position(&self, t: u32) -> Option<usize> {
        self.vertices(t).iter().position(|&v| v == INFINITE)
    }

    /// A slot for a new tetrahedron: a recycled one if any. Growth past the reservation is
    /// fallible, so an input with far more tetrahedra than points (points on the moment curve
    /// have quadratically many) ends in an error, not an abort.
    #[inline]
    pub fn allocate(&mut self) -> Result<u32> {
        if let Some(t) = self.free.pop() {
            return Ok(t);
        }
        let t = self.mark.len();
        if t == self.mark.capacity() {
            self.grow()?;
        }
        self.data
            .extend_from_slice(&[DEAD, DEAD, DEAD, DEAD, 0, 0, 0, 0]);
        self.mark.push(0);
        Ok(t as u32)
    }

    #[cold]
    fn grow(&mut self) -> Result<()> {
        let slots = self.slots();
        if slots >= MAX_TETRAHEDRA {
            return Err(Error::new(
                ErrorKind::Limit,
                format!("the triangulation needs more than {MAX_TETRAHEDRA} tetrahedra"),
            ));
        }
        let more = (slots / 2 + 16).min(MAX_TETRAHEDRA - slots);
        let oom = |_| {
            let message = format!("cannot grow past {slots} tetrahedra");
            Error::new(ErrorKind::OutOfMemory, message)
        };
        self.data.try_reserve_exact(8 * more).map_err(oom)?;
        self.mark.try_reserve_exact(more).map_err(oom)
    }

    #[inline]
    pub fn kill(&mut self, t: u32) {
        self.data[8 * t as usize] = DEAD;
        self.mark[t as usize] = 0;
        self.free.push(t);
    }

    #[inline]
    pub fn set(&mut self, t: u32, verts: [u32; 4]) {
        let i = 8 * t as usize;
        self.data[i..i + 4].copy_from_slice(&verts);
    }

    /// Glues facet `a` (`4*t+i`) to facet `b`, both ways.
    #[inline]
    pub fn glue(&mut self, a: u32, b: u32) {
        let slot = |f: u32| 8 * (f >> 2) as usize + 4 + (f & 3) as usize;
        self.data[slot(a)] = b;
        self.data[slot(b)] = a;
    }

    pub fn live(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.slots() as u32).filter(move |&t| self.is_live(t))
    }

    /// The vertex quadruples of the live tetrahedra without the infinite vertex, compacted
    /// into the storage's own memory (the glued facets are dropped).
    pub fn into_finite(self) -> Vec<u32> {
        let mut data = self.data;
        let mut kept = 0;
        for t in 0..data.len() / 8 {
            let q = [0, 1, 2, 3].map(|k| data[8 * t + k]);
            if q[0] != DEAD && !q.contains(&INFINITE) {
                data[4 * kept..4 * kept + 4].copy_from_slice(&q);
                kept += 1;
            }
        }
        data.truncate(4 * kept);
        data.shrink_to_fit();
        data
    }
}
