//! Mesh writers (DESIGN.md layer 7), all ASCII: Medit `.mesh`, Gmsh `.msh` 4.1 and
//! VTK `.vtu`. The file extension chooses the format.
//!
//! Conventions shared by the writers:
//! - files number vertices and elements from 1 (VTK from 0), in the order of the [`Mesh`]
//!   arrays; tetrahedra keep their vertex order, which is positively oriented in all
//!   three formats;
//! - facets are grouped by their (from, to) label pair into *patches*, numbered from 1 in
//!   increasing (from, to) order ([`Patches`]);
//! - reals are written with the fewest digits that read back to the same `f64` ([`Real`]).

pub mod gmsh;
pub mod medit;
pub mod surface;
pub mod vtu;

use std::fmt;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

use crate::error::{Error, ErrorKind, Result};
use crate::mesh::Mesh;

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Medit / INRIA `.mesh`, ASCII.
    Medit,
    /// Gmsh `.msh`, version 4.1 ASCII.
    Gmsh,
    /// VTK XML unstructured grid `.vtu`, ASCII.
    Vtu,
}

impl Format {
    /// The format named by the extension of `path` (ASCII case ignored).
    pub fn from_path(path: &Path) -> Result<Format> {
        let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        match extension.to_ascii_lowercase().as_str() {
            "mesh" => Ok(Format::Medit),
            "msh" => Ok(Format::Gmsh),
            "vtu" => Ok(Format::Vtu),
            _ => Err(Error::invalid_argument(format!(
                "unknown mesh file extension \"{}\" in \"{}\": expected .mesh, .msh or .vtu",
                extension,
                path.display()
            ))),
        }
    }

    /// Writes `mesh` in this format to `out`.
    pub fn write(self, mesh: &Mesh, out: &mut impl Write) -> io::Result<()> {
        match self {
            Format::Medit => medit::write(mesh, out),
            Format::Gmsh => gmsh::write(mesh, out),
            Format::Vtu => vtu::write(mesh, out),
        }
    }
}

/// Writes `mesh` to the file `path` (replaced if it exists) in the format its extension
/// names. Errors: an unknown extension is `InvalidArgument`; a failure to create or write
/// the file is `Io`, naming the path and the system's reason.
pub fn write(mesh: &Mesh, path: &Path) -> Result<()> {
    let format = Format::from_path(path)?;
    let io_error = |e: io::Error| {
        Error::new(
            ErrorKind::Io,
            format!("cannot write \"{}\": {e}", path.display()),
        )
    };
    let mut out = BufWriter::new(File::create(path).map_err(io_error)?);
    format.write(mesh, &mut out).map_err(io_error)?;
    out.into_inner().map_err(|e| io_error(e.into_error()))?;
    Ok(())
}

/// A real number written with the fewest digits that read back exactly: plain decimal
/// for moderate magnitudes, scientific notation otherwise (never hundreds of zeros).
#[derive(Clone, Copy, Debug)]
pub struct Real(pub f64);

impl fmt::Display for Real {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let magnitude = self.0.abs();
        if magnitude == 0.0 || (1e-5..1e16).contains(&magnitude) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// Facets grouped by (from, to) label pair.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Patches {
    /// The distinct (from, to) pairs, increasing; patch `k + 1` is `pairs[k]`.
    pub pairs: Vec<[i32; 2]>,
    /// The patch number (from 1) of each facet.
    pub of_facet: Vec<usize>,
}

impl Patches {
    pub fn new(facet_labels: &[i32]) -> Patches {
        let labels: Vec<[i32; 2]> = facet_labels.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
        let mut pairs = labels.clone();
        pairs.sort_unstable();
        pairs.dedup();
        let of_facet = labels
            .iter()
            .map(|l| 1 + pairs.partition_point(|p| p < l))
            .collect();
        Patches { pairs, of_facet }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reals_read_back_exactly() {
        for x in [
            0.0,
            -0.0,
            1.0,
            0.1,
            -2.5e-7,
            1e300,
            5e-324,
            123456.789,
            1e16,
            f64::MAX,
        ] {
            let text = Real(x).to_string();
            assert_eq!(
                text.parse::<f64>().unwrap().to_bits(),
                x.to_bits(),
                "{text}"
            );
            assert!(text.len() < 30, "{text}");
        }
    }

    #[test]
    fn patches_are_numbered_by_increasing_pair() {
        let patches = Patches::new(&[2, 0, 1, 0, 2, 1, 1, 0]);
        assert_eq!(patches.pairs, vec![[1, 0], [2, 0], [2, 1]]);
        assert_eq!(patches.of_facet, vec![2, 1, 3, 1]);
    }

    #[test]
    fn extension_chooses_the_format() {
        assert_eq!(
            Format::from_path(Path::new("a/b.MESH")).unwrap(),
            Format::Medit
        );
        assert_eq!(Format::from_path(Path::new("b.msh")).unwrap(), Format::Gmsh);
        assert_eq!(Format::from_path(Path::new("b.vtu")).unwrap(), Format::Vtu);
        let error = Format::from_path(Path::new("b.stl")).unwrap_err();
        assert_eq!(error.kind, ErrorKind::InvalidArgument);
        assert!(error.message.contains("\"stl\""), "{}", error.message);
    }
}
