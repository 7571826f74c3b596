//! TetGen piecewise linear complexes: `.smesh` and `.poly` (points possibly in `.node`).

use std::path::Path;

use super::polygon::{triangulate_facet, triangulate_polygon};
use super::text::{self, Line, Lines};
use crate::error::Result;
use crate::predicates::Point;
use crate::recovery::{RegionSeed, Surface};

/// How a file lists its facets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Facets {
    /// `.smesh`: one polygon per facet, on one line.
    Simple,
    /// `.poly`: a block per facet, with polygons and hole points.
    Blocks,
}

/// Reads the TetGen text `text` of the file `path`, whose facets are listed as `facets`
/// says. With no point in it, the points come from the `.node` file of the same name.
pub(super) fn read(path: &Path, text: &str, facets: Facets) -> Result<Surface> {
    let mut lines = Lines::new(path, text, Some('#'), 1);
    let (mut points, mut base) = read_points(&mut lines)?;
    if points.is_empty() {
        let node_path = path.with_extension("node");
        let bytes = super::read_file(&node_path)?;
        let node_text = text::utf8(&node_path, &bytes, 1)?;
        (points, base) = read_points(&mut Lines::new(&node_path, node_text, Some('#'), 1))?;
    }
    let mut surface = Surface {
        triangles: read_facets(&mut lines, &points, base, facets)?,
        ..Surface::default()
    };
    surface.xyz = points.into_flattened();
    if let Some(header) = lines.next_line() {
        let n = header.count(0, "hole count")?;
        for k in 0..n {
            let line = lines.expect(&format!("hole {} of {n}", k + 1))?;
            surface.holes.push(line.point(1)?);
        }
    }
    if let Some(header) = lines.next_line() {
        let n = header.count(0, "region count")?;
        for k in 0..n {
            surface
                .regions
                .push(region(&lines.expect(&format!("region {} of {n}", k + 1))?)?);
        }
    }
    if let Some(line) = lines.next_line() {
        return Err(line.error("unexpected content after the regions"));
    }
    Ok(surface)
}

/// Reads the point list: `<#points> <dimension = 3> <#attributes> <#markers (0 or 1)>`, then
/// `<index> <x> <y> <z> [attributes...] [marker]` per point, numbered consecutively from 0
/// or 1. Returns the points and that base (0 without points).
fn read_points(lines: &mut Lines) -> Result<(Vec<Point>, i64)> {
    let header = lines.expect("the point header \"<#points> 3 <#attributes> <#markers>\"")?;
    let n = header.count(0, "point count")?;
    if header.fields.len() > 1 && header.integer(1, "dimension")? != 3 {
        return Err(header.error(format!("dimension {}: must be 3", header.fields[1])));
    }
    let optional = |k: usize, what: &str| -> Result<usize> {
        if header.fields.len() > k {
            header.count(k, what)
        } else {
            Ok(0)
        }
    };
    let n_attributes = optional(2, "attribute count")?;
    let n_markers = optional(3, "boundary marker count")?;
    if n_markers > 1 {
        return Err(header.error(format!("boundary marker count {n_markers}: must be 0 or 1")));
    }
    if u32::try_from(n).is_err() {
        return Err(header.error(format!("{n} points: at most 2^32 - 1")));
    }
    let mut points = Vec::new();
    let mut base = 0;
    for k in 0..n {
        let line = lines.expect(&format!("point {} of {n}", k + 1))?;
        let index = line.integer(0, "point index")?;
        if k == 0 {
            if index != 0 && index != 1 {
                return Err(line.error(format!(
                    "first point index {index}: must be 0 or 1 (the file's base)"
                )));
            }
            base = index;
        }
        if index != base + k as i64 {
            return Err(line.error(format!(
                "point index {index}: expected {} (points are numbered consecutively)",
                base + k as i64
            )));
        }
        points.push(line.point(1)?);
        if n_attributes + n_markers > 0 {
            line.field(3 + n_attributes + n_markers, "point attributes and marker")?;
        }
    }
    Ok((points, base))
}

/// Reads the facet list `<#facets> [#markers]` and the facets; returns their triangles.
fn read_facets(lines: &mut Lines, points: &[Point], base: i64, facets: Facets) -> Result<Vec<u32>> {
    let header = lines.expect("the facet header \"<#facets> <#markers>\"")?;
    let n = header.count(0, "facet count")?;
    let mut triangles = Vec::new();
    for k in 0..n {
        let what = format!("facet {} of {n}", k + 1);
        let line = lines.expect(&what)?;
        let facet = match facets {
            Facets::Simple => {
                let corners = polygon(&line, points.len(), base)?;
                triangulate_polygon(points, &corners, &mut triangles)
            }
            Facets::Blocks => {
                let (polygons, holes) = facet_block(lines, &line, points.len(), base, &what)?;
                triangulate_facet(points, &polygons, &holes, &mut triangles)
            }
        };
        facet.map_err(|reason| line.error(format!("facet {}: {reason}", k + 1)))?;
    }
    Ok(triangles)
}

/// The corners (0-based) of the polygon `<#corners> <v1> ... <vn>` of `line`, among `n`
/// points numbered from `base`.
fn polygon(line: &Line, n: usize, base: i64) -> Result<Vec<u32>> {
    let count = line.count(0, "corner count")?;
    (0..count)
        .map(|c| line.index(1 + c, base, n, "point index"))
        .collect()
}

/// Reads the rest of the `.poly` facet block whose first line is `header`
/// (`<#polygons> [#holes] [marker]`): the polygons, then the hole points `<index> x y z`.
fn facet_block(
    lines: &mut Lines,
    header: &Line,
    n: usize,
    base: i64,
    what: &str,
) -> Result<(Vec<Vec<u32>>, Vec<Point>)> {
    let n_polygons = header.count(0, "polygon count")?;
    let n_holes = if header.fields.len() > 1 {
        header.count(1, "hole count")?
    } else {
        0
    };
    let mut polygons = Vec::new();
    for k in 0..n_polygons {
        let line = lines.expect(&format!("polygon {} of {n_polygons} of {what}", k + 1))?;
        polygons.push(polygon(&line, n, base)?);
    }
    let mut holes = Vec::new();
    for k in 0..n_holes {
        let line = lines.expect(&format!("hole {} of {n_holes} of {what}", k + 1))?;
        holes.push(line.point(1)?);
    }
    Ok((polygons, holes))
}

/// The region of the line `<index> <x> <y> <z> <attribute> [max volume]`: the attribute,
/// an integer, is the label; a negative or absent volume bound is none (0).
fn region(line: &Line) -> Result<RegionSeed> {
    let attribute = line.real(4, "region attribute")?;
    if !(attribute.fract() == 0.0 && attribute.abs() <= i32::MAX as f64) {
        return Err(line.error(format!(
            "region attribute {attribute} is not a 32-bit integer (it is the region label)"
        )));
    }
    let max_volume = if line.fields.len() > 5 {
        line.real(5, "maximum volume")?
    } else {
        0.0
    };
    Ok(RegionSeed {
        point: line.point(1)?,
        label: attribute as i32,
        max_volume: max_volume.max(0.0),
    })
}
