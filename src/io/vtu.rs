//! VTK XML unstructured grid (`.vtu`) ASCII writer.
//!
//! Cells are the tetrahedra (VTK_TETRA) followed by the triangles of a 2D result
//! (VTK_TRIANGLE), with their label as cell data `label` (Int32); the vertex dimension is
//! point data `dimension` (Int8). Facets and edges are not written: a viewer derives the
//! boundary from the cells. Indices start at 0.

use std::fmt::Display;
use std::io::{self, Write};

use super::Real;
use crate::mesh::Mesh;

/// VTK cell type numbers.
const VTK_TRIANGLE: u8 = 5;
const VTK_TETRA: u8 = 10;

pub fn write(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    let tetrahedra = mesh.tetrahedron_count();
    let triangles = mesh.triangle_labels.len();
    writeln!(out, "<?xml version=\"1.0\"?>")?;
    writeln!(
        out,
        "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">"
    )?;
    writeln!(out, "<UnstructuredGrid>")?;
    writeln!(
        out,
        "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        mesh.vertex_count(),
        tetrahedra + triangles
    )?;
    if !mesh.vertex_dimensions.is_empty() {
        writeln!(out, "<PointData>")?;
        data_array(
            out,
            "Int8",
            "Name=\"dimension\"",
            &mesh.vertex_dimensions,
            1,
        )?;
        writeln!(out, "</PointData>")?;
    }
    writeln!(out, "<CellData>")?;
    let labels: Vec<i32> = mesh
        .tetrahedron_labels
        .iter()
        .chain(&mesh.triangle_labels)
        .copied()
        .collect();
    data_array(out, "Int32", "Name=\"label\"", &labels, 1)?;
    writeln!(out, "</CellData>")?;
    writeln!(out, "<Points>")?;
    let points: Vec<Real> = mesh.vertices.iter().map(|&x| Real(x)).collect();
    data_array(out, "Float64", "NumberOfComponents=\"3\"", &points, 3)?;
    writeln!(out, "</Points>")?;
    write_cells(mesh, out)?;
    writeln!(out, "</Piece>\n</UnstructuredGrid>\n</VTKFile>")
}

/// Connectivity, offsets and types of the tetrahedra then the triangles.
fn write_cells(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    let tetrahedra = mesh.tetrahedron_count();
    let triangles = mesh.triangle_labels.len();
    let connectivity: Vec<u32> = mesh
        .tetrahedra
        .iter()
        .chain(&mesh.triangles)
        .copied()
        .collect();
    let offsets: Vec<usize> = (1..=tetrahedra)
        .map(|t| 4 * t)
        .chain((1..=triangles).map(|t| 4 * tetrahedra + 3 * t))
        .collect();
    let mut types = vec![VTK_TETRA; tetrahedra];
    types.resize(tetrahedra + triangles, VTK_TRIANGLE);
    writeln!(out, "<Cells>")?;
    data_array(out, "Int64", "Name=\"connectivity\"", &connectivity, 4)?;
    data_array(out, "Int64", "Name=\"offsets\"", &offsets, 1)?;
    data_array(out, "UInt8", "Name=\"types\"", &types, 1)?;
    writeln!(out, "</Cells>")
}

/// An ASCII `DataArray`, `per_line` values a line.
fn data_array<T: Display>(
    out: &mut impl Write,
    vtk_type: &str,
    attributes: &str,
    values: &[T],
    per_line: usize,
) -> io::Result<()> {
    writeln!(
        out,
        "<DataArray type=\"{vtk_type}\" {attributes} format=\"ascii\">"
    )?;
    for line in values.chunks(per_line) {
        let mut separator = "";
        for value in line {
            write!(out, "{separator}{value}")?;
            separator = " ";
        }
        writeln!(out)?;
    }
    writeln!(out, "</DataArray>")
}
