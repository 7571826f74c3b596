//! Gmsh `.msh` version 4.1 ASCII writer.
//!
//! The model is made of discrete entities, each in one physical group of the same
//! number, named in `$PhysicalNames`:
//! - one volume per subdomain label `L` (entity and physical tag `L`, "subdomain L") with
//!   its tetrahedra;
//! - one surface per facet patch `k` (tag `k`, "facets FROM TO") with its facets as
//!   triangles, then for a 2D result one surface per region label `L` (physical tag `L`,
//!   "region L") with its triangles;
//! - one curve (tag 1, "edges") with the edges.
//!
//! Every node lies in one block, classified on the entity of the last element block (a
//! volume, or a surface for 2D results). Node tags are vertex indices + 1; element tags
//! run from 1 over the blocks in the order curves, surfaces, volumes.

use std::collections::BTreeMap;
use std::io::{self, Write};

use super::{Patches, Real};
use crate::mesh::Mesh;

/// Gmsh element type numbers.
const LINE: u8 = 1;
const TRIANGLE: u8 = 2;
const TETRAHEDRON: u8 = 4;

/// An entity and the elements classified on it.
struct Block<'a> {
    dim: u8,
    tag: i32,
    physical: i32,
    name: String,
    element_type: u8,
    elements: Vec<&'a [u32]>,
}

pub fn write(mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
    let blocks = blocks(mesh);
    writeln!(out, "$MeshFormat\n4.1 0 8\n$EndMeshFormat")?;
    write_physical_names(&blocks, out)?;
    write_entities(mesh, &blocks, out)?;
    write_nodes(mesh, &blocks, out)?;
    write_elements(&blocks, out)
}

/// The element blocks in file order: curves, surfaces, volumes.
fn blocks(mesh: &Mesh) -> Vec<Block<'_>> {
    let mut blocks = Vec::new();
    if !mesh.edges.is_empty() {
        blocks.push(Block {
            dim: 1,
            tag: 1,
            physical: 1,
            name: "edges".into(),
            element_type: LINE,
            elements: mesh.edges.chunks_exact(2).collect(),
        });
    }
    let patches = Patches::new(&mesh.facet_labels);
    for (patch, facets) in grouped(&mesh.facets, 3, &patches.of_facet) {
        let [from, to] = patches.pairs[patch - 1];
        blocks.push(Block {
            dim: 2,
            tag: patch as i32,
            physical: patch as i32,
            name: format!("facets {from} {to}"),
            element_type: TRIANGLE,
            elements: facets,
        });
    }
    let regions = grouped(&mesh.triangles, 3, &mesh.triangle_labels);
    for (k, (label, triangles)) in regions.into_iter().enumerate() {
        blocks.push(Block {
            dim: 2,
            tag: (patches.pairs.len() + k + 1) as i32,
            physical: label,
            name: format!("region {label}"),
            element_type: TRIANGLE,
            elements: triangles,
        });
    }
    for (label, tetrahedra) in grouped(&mesh.tetrahedra, 4, &mesh.tetrahedron_labels) {
        blocks.push(Block {
            dim: 3,
            tag: label,
            physical: label,
            name: format!("subdomain {label}"),
            element_type: TETRAHEDRON,
            elements: tetrahedra,
        });
    }
    blocks
}

/// The elements (`per` vertices each) grouped by key, keys increasing, elements in order.
fn grouped<'a, K: Ord + Copy>(
    vertices: &'a [u32],
    per: usize,
    keys: &[K],
) -> BTreeMap<K, Vec<&'a [u32]>> {
    let mut groups: BTreeMap<K, Vec<&[u32]>> = BTreeMap::new();
    for (element, &key) in vertices.chunks_exact(per).zip(keys) {
        groups.entry(key).or_default().push(element);
    }
    groups
}

fn write_physical_names(blocks: &[Block], out: &mut impl Write) -> io::Result<()> {
    if blocks.is_empty() {
        return Ok(());
    }
    writeln!(out, "$PhysicalNames\n{}", blocks.len())?;
    for b in blocks {
        writeln!(out, "{} {} \"{}\"", b.dim, b.physical, b.name)?;
    }
    writeln!(out, "$EndPhysicalNames")
}

/// Entities with the bounding box of the whole mesh (a valid enclosing box for each),
/// one physical tag and no bounding entities.
fn write_entities(mesh: &Mesh, blocks: &[Block], out: &mut impl Write) -> io::Result<()> {
    let count = |dim| blocks.iter().filter(|b| b.dim == dim).count();
    writeln!(out, "$Entities\n0 {} {} {}", count(1), count(2), count(3))?;
    let [lo, hi] = bounding_box(mesh);
    for b in blocks {
        write!(out, "{} ", b.tag)?;
        for x in lo.iter().chain(&hi) {
            write!(out, "{} ", Real(*x))?;
        }
        writeln!(out, "1 {} 0", b.physical)?;
    }
    writeln!(out, "$EndEntities")
}

/// Lowest and highest coordinates of the vertices (zeros for an empty mesh).
fn bounding_box(mesh: &Mesh) -> [[f64; 3]; 2] {
    if mesh.vertices.is_empty() {
        return [[0.0; 3]; 2];
    }
    let mut bounds = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
    for p in mesh.vertices.chunks_exact(3) {
        for axis in 0..3 {
            bounds[0][axis] = bounds[0][axis].min(p[axis]);
            bounds[1][axis] = bounds[1][axis].max(p[axis]);
        }
    }
    bounds
}

fn write_nodes(mesh: &Mesh, blocks: &[Block], out: &mut impl Write) -> io::Result<()> {
    let n = mesh.vertex_count();
    writeln!(out, "$Nodes")?;
    if n == 0 {
        return writeln!(out, "0 0 0 0\n$EndNodes");
    }
    let (dim, tag) = blocks.last().map_or((0, 1), |b| (b.dim, b.tag));
    writeln!(out, "1 {n} 1 {n}\n{dim} {tag} 0 {n}")?;
    for tag in 1..=n {
        writeln!(out, "{tag}")?;
    }
    for p in mesh.vertices.chunks_exact(3) {
        writeln!(out, "{} {} {}", Real(p[0]), Real(p[1]), Real(p[2]))?;
    }
    writeln!(out, "$EndNodes")
}

fn write_elements(blocks: &[Block], out: &mut impl Write) -> io::Result<()> {
    let total: usize = blocks.iter().map(|b| b.elements.len()).sum();
    writeln!(
        out,
        "$Elements\n{} {total} {} {total}",
        blocks.len(),
        total.min(1)
    )?;
    let mut tag = 0u64;
    for b in blocks {
        writeln!(
            out,
            "{} {} {} {}",
            b.dim,
            b.tag,
            b.element_type,
            b.elements.len()
        )?;
        for element in &b.elements {
            tag += 1;
            write!(out, "{tag}")?;
            for &v in *element {
                write!(out, " {}", u64::from(v) + 1)?;
            }
            writeln!(out)?;
        }
    }
    writeln!(out, "$EndElements")
}
