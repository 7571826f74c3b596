//! Removal of a vertex (Devillers, "On deletion in Delaunay triangulations", IJCGA 2002): the
//! star of the vertex leaves a star-shaped hole bounded by its link; the tetrahedra that fill
//! it are those of the triangulation of the link vertices alone that are in conflict with the
//! removed vertex. Both decisions use the same exact predicates with the same symbolic
//! perturbation as insertion, so the result is the triangulation the remaining points would
//! have had, with or without weights.
//!
//! The filling is computed and checked in full — its boundary must be the link, facet for
//! facet — before anything changes; a hull vertex (whose star holds infinite tetrahedra) is
//! not removed.

use std::collections::HashMap;

use super::tets::{FACE, INFINITE};
use super::{PointState, Triangulation};
use crate::error::{Error, Result};

/// A facet by its sorted vertices.
type Key = [u32; 3];

fn key(f: [u32; 3]) -> Key {
    let mut k = f;
    k.sort_unstable();
    k
}

impl Triangulation<'static> {
    /// Removes vertex `v`, a vertex of tetrahedron `t`. Returns `false` (and changes nothing)
    /// for a vertex of the convex hull. [`Triangulation::created`] then lists the tetrahedra
    /// that fill the hole.
    pub fn remove(&mut self, v: u32, t: u32) -> Result<bool> {
        let star = self.star(v, t);
        if star
            .iter()
            .any(|&s| self.tets.vertices(s).contains(&INFINITE))
        {
            return Ok(false);
        }
        // The link: facets opposite v, with the outer facets glued to them.
        let mut link: HashMap<Key, u32> = HashMap::with_capacity(star.len());
        let mut vertices: Vec<u32> = Vec::new();
        for &s in &star {
            let verts = self.tets.vertices(s);
            let i = verts.iter().position(|&x| x == v).unwrap_or(0);
            let f = FACE[i].map(|k| verts[k]);
            link.insert(key(f), self.tets.glued(s, i));
            vertices.extend_from_slice(&f);
        }
        vertices.sort_unstable();
        vertices.dedup();
        let filling = self.fill_hole(v, &vertices)?;
        self.check_filling(v, &filling, &link)?;
        self.replace(&star, &filling, &link)?;
        self.state[v as usize] = PointState::Removed;
        Ok(true)
    }

    /// The tetrahedra of the triangulation of `link` that are in conflict with `v`.
    fn fill_hole(&self, v: u32, link: &[u32]) -> Result<Vec<[u32; 4]>> {
        let xyz: Vec<f64> = link.iter().flat_map(|&u| *self.point(u)).collect();
        let weights: Vec<f64> = link.iter().map(|&u| self.weight(u)).collect();
        let mut small = Triangulation::new(&xyz, self.is_regular().then_some(&weights[..]))?;
        small.insert_all()?;
        Ok(small
            .finite_tetrahedra()
            .map(|q| q.map(|k| link[k as usize]))
            .filter(|&q| self.finite_conflict(q, v))
            .collect())
    }

    /// The filling's boundary is the link, each link facet once, and its inner facets pair up.
    fn check_filling(&self, v: u32, filling: &[[u32; 4]], link: &HashMap<Key, u32>) -> Result<()> {
        let mut inner: HashMap<Key, usize> = HashMap::new();
        let mut on_link = 0;
        for q in filling {
            for f in FACE.map(|face| key(face.map(|k| q[k]))) {
                if link.contains_key(&f) {
                    on_link += 1;
                } else {
                    *inner.entry(f).or_default() += 1;
                }
            }
        }
        if on_link != link.len() || inner.values().any(|&n| n != 2) {
            let i = self.input_index(v);
            return Err(Error::internal(format!(
                "the hole of vertex {i} is not filled by the triangulation of its link \
                 ({on_link} of {} link facets covered)",
                link.len()
            )));
        }
        Ok(())
    }

    /// Replaces the star's tetrahedra by the filling, glued to the link's outer facets and to
    /// each other.
    fn replace(
        &mut self,
        star: &[u32],
        filling: &[[u32; 4]],
        link: &HashMap<Key, u32>,
    ) -> Result<()> {
        let mut slots = Vec::with_capacity(filling.len());
        for k in 0..filling.len() {
            slots.push(match star.get(k) {
                Some(&s) => s,
                None => self.tets.allocate()?,
            });
        }
        for &s in star.iter().skip(filling.len()) {
            self.tets.kill(s);
        }
        let mut waiting: HashMap<Key, u32> = HashMap::new();
        for (&slot, q) in slots.iter().zip(filling) {
            self.tets.set(slot, *q);
            for (j, face) in FACE.iter().enumerate() {
                let f = key(face.map(|k| q[k]));
                let facet = 4 * slot + j as u32;
                match link.get(&f) {
                    Some(&outer) => self.tets.glue(facet, outer),
                    None => {
                        if let Some(other) = waiting.remove(&f) {
                            self.tets.glue(facet, other);
                        } else {
                            waiting.insert(f, facet);
                        }
                    }
                }
            }
        }
        self.hint = slots[0];
        self.scratch.new_tets.clear();
        self.scratch.new_tets.extend_from_slice(&slots);
        Ok(())
    }
}
