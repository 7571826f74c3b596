//! The result of refinement as a [`Mesh`] (DESIGN.md layer 7): the cells in the complex,
//! the facets between different labels, the used vertices compactly numbered.

use super::complex::Complex;
use crate::mesh::Mesh;
use crate::triangulation::tets::FACE;

pub fn mesh(c: &Complex) -> Mesh {
    let tets = c.tri.tets();
    let cells: Vec<u32> = tets.live().filter(|&t| c.label(t) > 0).collect();
    let mut number = vec![u32::MAX; c.vertex_count()];
    for &t in &cells {
        for v in tets.vertices(t) {
            number[v as usize] = 0;
        }
    }
    let mut m = Mesh::default();
    for (v, n) in number.iter_mut().enumerate() {
        if *n == 0 {
            *n = m.vertex_dimensions.len() as u32;
            m.vertices.extend_from_slice(c.tri.vertex(v as u32));
            m.vertex_dimensions.push(c.dimension(v as u32));
        }
    }
    for &t in &cells {
        let v = tets.vertices(t).map(|x| number[x as usize]);
        m.tetrahedra.extend_from_slice(&v);
        m.tetrahedron_labels.push(c.label(t));
        for (i, face) in FACE.iter().enumerate() {
            // Each facet once, from the side with the larger label; the face listed
            // counter-clockwise from inside `t` is reversed to face away from it.
            let other = c.label(tets.neighbor(t, i));
            if other < c.label(t) {
                let [a, b, cc] = face.map(|k| v[k]);
                m.facets.extend_from_slice(&[a, cc, b]);
                m.facet_labels.extend_from_slice(&[c.label(t), other]);
            }
        }
    }
    m
}
