//! Medit / INRIA `.mesh` ASCII writer (`MeshVersionFormatted 2`, double precision).
//!
//! Sections, each omitted when empty: `Vertices` (reference 0: no reference), `Tetrahedra`
//! (reference = subdomain label), `Triangles` (the facets, reference = patch number, then
//! the triangles of a 2D result, reference = region label), `Edges` (reference 0).
//! Indices start at 1.

use std::io::{self, Write};

use super::{Patches, Real};
use crate::mesh::Mesh;

pub fn write(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    writeln!(out, "MeshVersionFormatted 2\n\nDimension 3\n")?;
    write_vertices(mesh, out)?;
    let tetrahedra = mesh
        .tetrahedra
        .chunks_exact(4)
        .zip(mesh.tetrahedron_labels.iter().map(|&l| i64::from(l)));
    write_elements(out, "Tetrahedra", mesh.tetrahedron_count(), tetrahedra)?;
    let patches = Patches::new(&mesh.facet_labels);
    let facets = mesh
        .facets
        .chunks_exact(3)
        .zip(patches.of_facet.iter().map(|&p| p as i64));
    let triangles = mesh
        .triangles
        .chunks_exact(3)
        .zip(mesh.triangle_labels.iter().map(|&l| i64::from(l)));
    let count = patches.of_facet.len() + mesh.triangle_labels.len();
    write_elements(out, "Triangles", count, facets.chain(triangles))?;
    let edges = mesh.edges.chunks_exact(2).map(|e| (e, 0));
    write_elements(out, "Edges", mesh.edges.len() / 2, edges)?;
    writeln!(out, "End")
}

fn write_vertices(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    writeln!(out, "Vertices\n{}", mesh.vertex_count())?;
    for p in mesh.vertices.chunks_exact(3) {
        writeln!(out, "{} {} {} 0", Real(p[0]), Real(p[1]), Real(p[2]))?;
    }
    writeln!(out)
}

/// One element section: `count` rows of 1-based vertex indices and a reference.
fn write_elements<'a>(
    out: &mut impl Write,
    keyword: &str,
    count: usize,
    rows: impl Iterator<Item = (&'a [u32], i64)>,
) -> io::Result<()> {
    if count == 0 {
        return Ok(());
    }
    writeln!(out, "{keyword}\n{count}")?;
    for (vertices, reference) in rows {
        for &v in vertices {
            write!(out, "{} ", u64::from(v) + 1)?;
        }
        writeln!(out, "{reference}")?;
    }
    writeln!(out)
}
