//! Stereolithography `.stl`, ASCII and binary, with the vertices shared by coordinates.

use std::collections::HashMap;
use std::path::Path;

use super::polygon::triangulate_polygon;
use super::text::{self, Lines, Tokens};
use crate::error::{Error, Result};
use crate::predicates::Point;
use crate::recovery::Surface;

/// Size of a binary file's header (80 bytes, then the `u32` triangle count).
const HEADER: usize = 84;
/// Size of a binary triangle record: normal, 3 vertices (12 `f32`), attribute (`u16`).
const RECORD: usize = 50;

/// Reads the STL file `path` of contents `bytes`, binary when its size is that of a binary
/// file with the triangle count of its header, ASCII otherwise.
pub(super) fn read(path: &Path, bytes: &[u8]) -> Result<Surface> {
    let mut vertices = Vertices::default();
    let mut triangles = Vec::new();
    match binary_count(bytes) {
        Some(count) => read_binary(path, bytes, count, &mut vertices, &mut triangles)?,
        None => {
            let text = std::str::from_utf8(bytes)
                .ok()
                .filter(|t| starts_with_solid(t))
                .ok_or_else(|| {
                    text::error_at(
                        path,
                        1,
                        "neither a binary STL file (its size is not 84 + 50 x the triangle \
                         count of its header) nor an ASCII one (text starting with \"solid\")",
                    )
                })?;
            read_ascii(path, text, &mut vertices, &mut triangles)?;
        }
    }
    Ok(Surface {
        xyz: vertices.points.into_flattened(),
        triangles,
        ..Surface::default()
    })
}

/// True when the first word of `text` is `solid` (ASCII case ignored).
fn starts_with_solid(text: &str) -> bool {
    text.split_ascii_whitespace()
        .next()
        .is_some_and(|word| word.eq_ignore_ascii_case("solid"))
}

/// The triangle count of a binary file: the count in the header, when the file has exactly
/// the size it implies.
fn binary_count(bytes: &[u8]) -> Option<usize> {
    let count = u32::from_le_bytes(bytes.get(80..HEADER)?.try_into().ok()?) as usize;
    (count.checked_mul(RECORD)?.checked_add(HEADER)? == bytes.len()).then_some(count)
}

/// The vertices of a file, one per distinct coordinate triple in order of first appearance.
#[derive(Default)]
struct Vertices {
    points: Vec<Point>,
    index: HashMap<[u64; 3], u32>,
}

impl Vertices {
    /// The index of the vertex at `p` (finite), added if new. `+0` and `-0` are one
    /// coordinate. `None` past 2^32 - 1 vertices.
    fn add(&mut self, p: Point) -> Option<u32> {
        let key = p.map(|x| (x + 0.0).to_bits());
        if let Some(&i) = self.index.get(&key) {
            return Some(i);
        }
        let i = u32::try_from(self.points.len())
            .ok()
            .filter(|&i| i < u32::MAX)?;
        self.points.push(p);
        self.index.insert(key, i);
        Some(i)
    }
}

/// Reads the `count` triangles of a binary file.
fn read_binary(
    path: &Path,
    bytes: &[u8],
    count: usize,
    vertices: &mut Vertices,
    triangles: &mut Vec<u32>,
) -> Result<()> {
    triangles.reserve(3 * count);
    for (k, record) in bytes[HEADER..].chunks_exact(RECORD).enumerate() {
        let offset = HEADER + k * RECORD;
        for c in 0..3 {
            let start = 12 + 12 * c;
            let mut p = [0.0; 3];
            for (j, x) in p.iter_mut().enumerate() {
                let field = &record[start + 4 * j..start + 4 * j + 4];
                *x = f64::from(f32::from_le_bytes([field[0], field[1], field[2], field[3]]));
            }
            let at = offset + start;
            if !p.iter().all(|x| x.is_finite()) {
                return Err(at_byte(
                    path,
                    at,
                    format!("triangle {}: coordinate is not finite", k + 1),
                ));
            }
            triangles.push(
                vertices
                    .add(p)
                    .ok_or_else(|| at_byte(path, at, "too many vertices: at most 2^32 - 1"))?,
            );
        }
    }
    Ok(())
}

/// A syntax error at byte `offset` of the binary file `path`.
fn at_byte(path: &Path, offset: usize, message: impl std::fmt::Display) -> Error {
    Error::invalid_input(format!("{}: byte {offset}: {message}", path.display()))
}

/// Reads the solids of an ASCII file: `solid [name]`, facets
/// `facet normal nx ny nz outer loop vertex x y z ... endloop endfacet`, `endsolid [name]`.
fn read_ascii(
    path: &Path,
    text: &str,
    vertices: &mut Vertices,
    triangles: &mut Vec<u32>,
) -> Result<()> {
    let mut tokens = Tokens::new(Lines::new(path, text, None, 1));
    tokens.keyword("solid")?;
    tokens.skip_line();
    let mut n_facets = 0;
    let mut corners = Vec::new();
    loop {
        let token = tokens.next("\"facet\" or \"endsolid\"")?;
        if token.text.eq_ignore_ascii_case("endsolid") {
            tokens.skip_line();
            if tokens.at_end() {
                return Ok(());
            }
            tokens.keyword("solid")?;
            tokens.skip_line();
            continue;
        }
        if !token.text.eq_ignore_ascii_case("facet") {
            return Err(tokens.error_at(
                token.line,
                format!(
                    "expected \"facet\" or \"endsolid\", found \"{}\"",
                    token.text
                ),
            ));
        }
        n_facets += 1;
        tokens.keyword("normal")?;
        for what in ["normal x", "normal y", "normal z"] {
            tokens.real(what)?;
        }
        tokens.keyword("outer")?;
        tokens.keyword("loop")?;
        corners.clear();
        loop {
            let word = tokens.next("\"vertex\" or \"endloop\"")?;
            if word.text.eq_ignore_ascii_case("endloop") {
                break;
            }
            if !word.text.eq_ignore_ascii_case("vertex") {
                return Err(tokens.error_at(
                    word.line,
                    format!(
                        "expected \"vertex\" or \"endloop\", found \"{}\"",
                        word.text
                    ),
                ));
            }
            let p = [tokens.real("x")?, tokens.real("y")?, tokens.real("z")?];
            let index = vertices
                .add(p)
                .ok_or_else(|| tokens.error_at(word.line, "too many vertices: at most 2^32 - 1"))?;
            corners.push(index);
        }
        tokens.keyword("endfacet")?;
        triangulate_polygon(&vertices.points, &corners, triangles)
            .map_err(|reason| tokens.error_at(token.line, format!("facet {n_facets}: {reason}")))?;
    }
}
