//! Readers of triangulated surfaces, and of polygonal ones triangulated on reading.
//!
//! The extension of the file names its format (ASCII case ignored):
//! - `.off` (Object File Format): the header keyword `OFF`, `COFF`, `NOFF` or `CNOFF` (also
//!   prefixed by `ST`), the counts `<#vertices> <#faces> [#edges]` on the keyword's line or
//!   on the next one, one vertex per line (`x y z`, then the fields the prefixes announce,
//!   skipped), one face per line (`n v1 ... vn`, vertices from 0, then an optional colour,
//!   skipped). `#` starts a comment. Binary OFF is not supported.
//! - `.stl` (stereolithography): binary when the file's size is exactly 84 + 50 x the
//!   triangle count of its header (an 80-byte header that may start with `solid`, the `u32`
//!   count, then per triangle a normal, 3 vertices as little-endian `f32` and a `u16`
//!   attribute); otherwise ASCII: `solid [name]`, then
//!   `facet normal nx ny nz`, `outer loop`, `vertex x y z` (3 or more), `endloop`,
//!   `endfacet` per facet, and `endsolid [name]`; keywords in any ASCII case, several solids
//!   one after the other. Vertices with equal coordinates (`+0` and `-0` alike) are one
//!   vertex, numbered in order of first appearance; normals are ignored.
//! - `.obj` (Wavefront): `v x y z [w]` (`w` ignored) and `f c1 c2 ... cn` with corners `i`,
//!   `i/t`, `i//n` or `i/t/n`, where `i` counts from 1, or back from the last vertex read
//!   when negative. `#` starts a comment; every other statement is ignored.
//! - `.ply` (Polygon File Format): `format ascii`, `binary_little_endian` or
//!   `binary_big_endian`; the element `vertex` with scalar properties `x`, `y`, `z` of any
//!   type, and the element `face` with a list property `vertex_indices` (or
//!   `vertex_index`) of integer count and index types, vertices from 0. Other properties
//!   and elements are skipped (`comment` and `obj_info` lines too).
//! - `.smesh` and `.poly` (TetGen): the points `<#points> <dimension = 3> <#attributes>
//!   <#markers>` and `<index> x y z [attributes] [marker]`, numbered consecutively from 0
//!   or 1 as the first index says (with no point, they are read from the `.node` file of
//!   the same name, same syntax); the facets `<#facets> [#markers]` (markers are
//!   ignored); the hole points
//!   `<#holes>` and `<index> x y z`; the regions `<#regions>` and
//!   `<index> x y z <attribute> [max volume]`, the attribute, an integer, as the label and a
//!   negative or absent volume as none (0). Missing hole and region lists are empty. A
//!   `.smesh` facet is one line `<#corners> v1 ... vn [marker]`; a `.poly` facet is a line
//!   `<#polygons> [#holes] [marker]`, a line `<#corners> v1 ... vn` per polygon, then its
//!   hole points `<index> x y z`, in the facet's plane. `#` starts a comment.
//!
//! Faces of 3 corners are triangles as is. Larger faces are triangulated in their plane
//! with their own corners only, after repeated consecutive corners are dropped: projected
//! to the coordinate plane that their normal is closest to (exactly), then cut by ear
//! clipping with exact orientation tests, the best-shaped ear first; the triangles keep the
//! face's orientation, and a corner between collinear sides never gets a flat triangle.
//! Faces of fewer than 3 corners are errors. A `.poly` facet without hole points is its
//! polygons, each triangulated alone; with hole points, it is the region its polygons
//! enclose (a polygon inside another one is a hole of it), less the parts holding a hole
//! point.
//!
//! Errors: an unknown extension is `InvalidArgument`; a file that cannot be read is `Io`;
//! any syntax error (missing or malformed number, non-finite coordinate, index out of
//! range, truncated file, face that cannot be triangulated) is `InvalidInput`, naming the
//! file and the line (the byte offset in binary files).

mod ears;
mod obj;
mod off;
mod ply;
mod polygon;
mod stl;
mod tetgen;
mod text;

pub(crate) use polygon::{project, triangulate_polygon_avoiding};

use std::path::Path;

use crate::error::{Error, ErrorKind, Result};
use crate::recovery::Surface;

/// Reads the surface of the file `path`, in the format its extension names.
pub fn read_surface(path: &Path) -> Result<Surface> {
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let extension = extension.to_ascii_lowercase();
    if !["off", "stl", "obj", "ply", "smesh", "poly"].contains(&extension.as_str()) {
        return Err(Error::invalid_argument(format!(
            "unknown surface file extension \"{extension}\" in \"{}\": expected .off, .stl, \
             .obj, .ply, .smesh or .poly",
            path.display()
        )));
    }
    let bytes = read_file(path)?;
    match extension.as_str() {
        "stl" => stl::read(path, &bytes),
        "ply" => ply::read(path, &bytes),
        _ => {
            let text = text::utf8(path, &bytes, 1)?;
            match extension.as_str() {
                "off" => off::read(path, text),
                "obj" => obj::read(path, text),
                "smesh" => tetgen::read(path, text, tetgen::Facets::Simple),
                _ => tetgen::read(path, text, tetgen::Facets::Blocks),
            }
        }
    }
}

/// The contents of the file `path`.
fn read_file(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|e| {
        Error::new(
            ErrorKind::Io,
            format!("cannot read \"{}\": {e}", path.display()),
        )
    })
}
