//! The one result type, [`Mesh`] (DESIGN.md layer 7): flat arrays in the layout the
//! C API hands out, so `ffi` returns pointers into them without copying.
//!
//! Invariants (checked by [`Mesh::validate`]):
//! - `vertices.len() == 3 * n`, `vertex_dimensions.len() == n`;
//! - `tetrahedra.len() == 4 * tetrahedron_labels.len()`, every index `< n`,
//!   every tetrahedron positively oriented (exact `orient3d > 0`);
//! - `facets.len() == 3 * (facet_labels.len() / 2)`, `edges.len()` even,
//!   `triangles.len() == 3 * triangle_labels.len()`;
//! - `duplicate_of` is empty or has `n` entries, `duplicate_of[i] <= i`.

use crate::predicates::{orient3d, Sign};

/// Vertex dimension code for "not known" (triangulations do not classify vertices).
pub const DIMENSION_UNKNOWN: i8 = -1;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// xyz interleaved, 3 per vertex.
    pub vertices: Vec<f64>,
    /// 0 corner, 1 curve, 2 surface, 3 volume, -1 unknown; one per vertex.
    pub vertex_dimensions: Vec<i8>,
    /// 4 vertex indices per tetrahedron, positively oriented.
    pub tetrahedra: Vec<u32>,
    /// Subdomain label (> 0) per tetrahedron.
    pub tetrahedron_labels: Vec<i32>,
    /// 3 vertex indices per boundary or interface facet.
    pub facets: Vec<u32>,
    /// 2 labels per facet: (from, to); the right-hand normal points from `from` to `to`.
    pub facet_labels: Vec<i32>,
    /// 2 vertex indices per feature-curve edge (2D: constraint sub-segments).
    pub edges: Vec<u32>,
    /// 3 vertex indices per triangle (2D results), counter-clockwise.
    pub triangles: Vec<u32>,
    /// Region label per triangle (2D results).
    pub triangle_labels: Vec<i32>,
    /// For inputs given as points: `duplicate_of[i]` is the first input point with the
    /// same coordinates as point `i` (`i` itself when unique). Empty otherwise.
    pub duplicate_of: Vec<u32>,
}

impl Mesh {
    pub fn vertex_count(&self) -> usize {
        self.vertices.len() / 3
    }

    pub fn tetrahedron_count(&self) -> usize {
        self.tetrahedron_labels.len()
    }

    pub fn vertex(&self, i: u32) -> [f64; 3] {
        let i = i as usize * 3;
        [self.vertices[i], self.vertices[i + 1], self.vertices[i + 2]]
    }

    /// Number of input points merged onto an earlier identical point.
    pub fn duplicate_count(&self) -> usize {
        self.duplicate_of
            .iter()
            .enumerate()
            .filter(|&(i, &d)| d as usize != i)
            .count()
    }

    /// Checks the invariants listed in the module documentation; the error names the
    /// first element that breaks one.
    pub fn validate(&self) -> Result<(), String> {
        let n = self.vertex_count();
        if self.vertices.len() != 3 * n || self.vertex_dimensions.len() != n {
            return Err("vertex arrays have inconsistent lengths".into());
        }
        if self.tetrahedra.len() != 4 * self.tetrahedron_labels.len() {
            return Err("tetrahedron arrays have inconsistent lengths".into());
        }
        if self.facets.len() * 2 != self.facet_labels.len() * 3
            || !self.edges.len().is_multiple_of(2)
            || self.triangles.len() != 3 * self.triangle_labels.len()
        {
            return Err("facet, edge or triangle arrays have inconsistent lengths".into());
        }
        let all = [&self.tetrahedra, &self.facets, &self.edges, &self.triangles];
        if let Some(&bad) = all
            .iter()
            .flat_map(|a| a.iter())
            .find(|&&v| v as usize >= n)
        {
            return Err(format!("vertex index {bad} out of range (n = {n})"));
        }
        for (t, tet) in self.tetrahedra.chunks_exact(4).enumerate() {
            let p = [0, 1, 2, 3].map(|k| self.vertex(tet[k]));
            if orient3d(&p[0], &p[1], &p[2], &p[3]) != Sign::Positive {
                return Err(format!(
                    "tetrahedron {t} {tet:?} is not positively oriented"
                ));
            }
        }
        if !self.duplicate_of.is_empty() && self.duplicate_of.len() != n {
            return Err("duplicate_of has the wrong length".into());
        }
        if let Some(i) = (0..self.duplicate_of.len()).find(|&i| self.duplicate_of[i] as usize > i) {
            return Err(format!("duplicate_of[{i}] points forward"));
        }
        Ok(())
    }
}
