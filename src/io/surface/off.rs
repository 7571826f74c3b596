//! Object File Format (`.off`).

use std::path::Path;

use super::polygon::triangulate_polygon;
use super::text::Lines;
use crate::error::Result;
use crate::predicates::Point;
use crate::recovery::Surface;

/// Reads the OFF text `text` of the file `path`.
pub(super) fn read(path: &Path, text: &str) -> Result<Surface> {
    let mut lines = Lines::new(path, text, Some('#'), 1);
    let header = lines.expect("the OFF header")?;
    let keyword = header.field(0, "the OFF header")?;
    check_keyword(keyword).map_err(|m| header.error(m))?;
    if header.fields.get(1) == Some(&"BINARY") {
        return Err(header.error("binary OFF is not supported"));
    }
    // The counts follow the keyword, on its line or on the next one.
    let (counts, first) = if header.fields.len() > 1 {
        (header, 1)
    } else {
        (
            lines.expect("the counts \"<#vertices> <#faces> <#edges>\"")?,
            0,
        )
    };
    let n_vertices = counts.count(first, "vertex count")?;
    let n_faces = counts.count(first + 1, "face count")?;
    if u32::try_from(n_vertices).is_err() {
        return Err(counts.error(format!("{n_vertices} vertices: at most 2^32 - 1")));
    }
    let mut points: Vec<Point> = Vec::with_capacity(n_vertices.min(text.len()));
    for k in 0..n_vertices {
        let line = lines.expect(&format!("vertex {} of {n_vertices}", k + 1))?;
        points.push(line.point(0)?);
    }
    let mut triangles = Vec::with_capacity(3 * n_faces.min(text.len()));
    let mut corners = Vec::new();
    for k in 0..n_faces {
        let line = lines.expect(&format!("face {} of {n_faces}", k + 1))?;
        let n = line.count(0, "corner count")?;
        corners.clear();
        for c in 0..n {
            corners.push(line.index(1 + c, 0, n_vertices, "vertex index")?);
        }
        triangulate_polygon(&points, &corners, &mut triangles)
            .map_err(|reason| line.error(format!("face {}: {reason}", k + 1)))?;
    }
    Ok(Surface {
        xyz: points.into_flattened(),
        triangles,
        ..Surface::default()
    })
}

/// Checks the header keyword `[ST][C][N]OFF`; the vertex fields that the prefixes announce
/// (texture coordinates, colour, normal) follow the coordinates and are skipped.
fn check_keyword(keyword: &str) -> std::result::Result<(), String> {
    let rest = keyword.strip_prefix("ST").unwrap_or(keyword);
    let rest = rest.strip_prefix('C').unwrap_or(rest);
    let rest = rest.strip_prefix('N').unwrap_or(rest);
    if rest == "OFF" {
        Ok(())
    } else {
        Err(format!(
            "header \"{keyword}\": expected OFF, COFF, NOFF or CNOFF (4OFF and nOFF are not \
             supported)"
        ))
    }
}
