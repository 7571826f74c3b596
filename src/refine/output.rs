//! The result of refinement as a [`Mesh`] (DESIGN.md layer 7): the cells in the complex,
//! the facets between different labels, the used vertices compactly numbered.

use super::complex::Complex;
use crate::mesh::Mesh;
use crate::triangulation::tets::FACE;
use crate::triangulation::Triangulation;

/// A triangulation with a subdomain label per tetrahedron slot (0 outside) and a dimension per
/// vertex: what refinement hands to the optimization passes, and what becomes the mesh.
pub struct Labeled {
    pub tri: Triangulation<'static>,
    pub label: Vec<i32>,
    pub dimension: Vec<i8>,
}

impl Labeled {
    /// The mesh: the tetrahedra with a label > 0, the facets between different labels (each
    /// once, from the side with the larger label, normal toward the smaller), the used
    /// vertices in id order.
    pub fn to_mesh(&self) -> Mesh {
        mesh(&self.tri, &self.label, &self.dimension)
    }
}

impl Complex<'_> {
    /// The mesh of the complex (see the module documentation).
    pub fn to_mesh(&self) -> Mesh {
        mesh(&self.tri, self.labels(), self.dimensions())
    }

    /// How far the output boundary (the facets between different labels) is from the
    /// restricted facets: (label changes that are not restricted, restricted facets that
    /// are not label changes). Both are 0 when the restricted Delaunay triangulation is the
    /// boundary of the cells in the complex, which refinement reaches in practice.
    pub fn boundary_disagreement(&self) -> (usize, usize) {
        let tets = self.tri.tets();
        let (mut unrestricted, mut same_label) = (0, 0);
        for t in tets.live() {
            for i in 0..4 {
                let u = tets.neighbor(t, i);
                let (a, b) = (self.label(t), self.label(u));
                let restricted = self.ball(4 * t + i as u32).is_some();
                // Each facet counted once: from its side with the larger slot.
                if t < u {
                    continue;
                }
                if a != b && !restricted {
                    unrestricted += 1;
                } else if a == b && restricted {
                    same_label += 1;
                }
            }
        }
        (unrestricted, same_label)
    }
}

fn mesh(tri: &Triangulation, label: &[i32], dimension: &[i8]) -> Mesh {
    let tets = tri.tets();
    let cells: Vec<u32> = tets.live().filter(|&t| label[t as usize] > 0).collect();
    let mut number = vec![u32::MAX; tri.vertex_count()];
    for &t in &cells {
        for v in tets.vertices(t) {
            number[v as usize] = 0;
        }
    }
    let mut m = Mesh::default();
    for (v, n) in number.iter_mut().enumerate() {
        if *n == 0 {
            *n = m.vertex_dimensions.len() as u32;
            m.vertices.extend_from_slice(tri.vertex(v as u32));
            m.vertex_dimensions.push(dimension[v]);
        }
    }
    for &t in &cells {
        let l = label[t as usize];
        let v = tets.vertices(t).map(|x| number[x as usize]);
        m.tetrahedra.extend_from_slice(&v);
        m.tetrahedron_labels.push(l);
        for (i, face) in FACE.iter().enumerate() {
            // Each facet once, from the side with the larger label; the face listed
            // counter-clockwise from inside `t` is reversed to face away from it.
            let other = label[tets.neighbor(t, i) as usize];
            if other < l {
                let [a, b, c] = face.map(|k| v[k]);
                m.facets.extend_from_slice(&[a, c, b]);
                m.facet_labels.extend_from_slice(&[l, other]);
            }
        }
    }
    m
}
