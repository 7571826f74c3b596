//! Wavefront `.obj`: vertices and faces; every other statement is ignored.

use std::path::Path;

use super::polygon::triangulate_polygon;
use super::text::{to_index, Line, Lines};
use crate::error::Result;
use crate::predicates::Point;
use crate::recovery::Surface;

/// Reads the OBJ text `text` of the file `path`.
pub(super) fn read(path: &Path, text: &str) -> Result<Surface> {
    let mut lines = Lines::new(path, text, Some('#'), 1);
    let mut points: Vec<Point> = Vec::new();
    let mut triangles = Vec::new();
    let mut corners = Vec::new();
    let mut n_faces = 0;
    while let Some(line) = lines.next_line() {
        match line.fields[0] {
            "v" => {
                if points.len() >= u32::MAX as usize {
                    return Err(line.error("too many vertices: at most 2^32 - 1"));
                }
                points.push(line.point(1)?);
            }
            "f" => {
                n_faces += 1;
                corners.clear();
                for k in 1..line.fields.len() {
                    corners.push(corner(&line, k, points.len())?);
                }
                triangulate_polygon(&points, &corners, &mut triangles)
                    .map_err(|reason| line.error(format!("face {n_faces}: {reason}")))?;
            }
            _ => {}
        }
    }
    Ok(Surface {
        xyz: points.into_flattened(),
        triangles,
        ..Surface::default()
    })
}

/// The vertex of the face corner in field `k` (`i`, `i/t`, `i//n` or `i/t/n`; `i` from 1,
/// or negative: counted back from the last of the `n` vertices read so far).
fn corner(line: &Line, k: usize, n: usize) -> Result<u32> {
    let field = line.fields[k];
    let text = field.split('/').next().unwrap_or("");
    let i: i64 = text.parse().map_err(|_| {
        line.error(format!(
            "face corner \"{field}\": the vertex is not an integer"
        ))
    })?;
    let index = if i < 0 { n as i64 + i } else { i - 1 };
    to_index(index, n).ok_or_else(|| {
        line.error(format!(
            "face corner \"{field}\": vertex {i} is out of range ({n} vertices so far)"
        ))
    })
}
