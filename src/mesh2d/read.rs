//! Readers of planar straight-line graphs: Shewchuk's Triangle `.node` and `.poly` files and
//! CGAL's `.edg` files, returning what [`super::quality_2d`] and [`super::conforming_2d`]
//! take (points, segments as index pairs, hole and region seeds).
//!
//! - `.node`: a header `<#points> <dimension = 2> <#attributes> <#markers (0 or 1)>`, then one
//!   line per point `<index> <x> <y> [attributes...] [marker]`.
//! - `.poly`: the `.node` section (with 0 points: the points are read from the `.node` file of
//!   the same name), then `<#segments> <#markers>` and `<index> <end> <end> [marker]`, then
//!   `<#holes>` and `<index> <x> <y>`, then optionally `<#regions>` and
//!   `<index> <x> <y> <attribute> [max area]`. Missing hole or region sections are empty.
//!   Indices are 0- or 1-based as the first point's index says; segment ends use that base.
//!   A region's attribute must be an integer (it becomes the region label); a negative or
//!   absent maximum area means none (0).
//! - `.edg`: `<#segments>` then `x1 y1 x2 y2` per segment; points are identified by their
//!   coordinates (equal coordinates, one point) in order of first appearance; a segment from
//!   a point to itself adds the point only.
//!
//! In Triangle files `#` starts a comment up to the end of the line; blank lines are skipped.
//! Every syntax error is `InvalidInput` naming the file and the line; a file that cannot be
//! read is `Io`.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use super::refine::RegionSeed;
use crate::error::{Error, ErrorKind, Result};

/// A planar straight-line graph as read from a file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Pslg {
    /// x y interleaved.
    pub xy: Vec<f64>,
    /// Point index pairs (0-based).
    pub segments: Vec<u32>,
    /// Hole seeds.
    pub holes: Vec<[f64; 2]>,
    /// Region seeds (label, maximum area; 0 = none).
    pub regions: Vec<RegionSeed>,
    /// Attributes per point (`n_attributes` each), from `.node` / `.poly` files.
    pub n_attributes: usize,
    pub point_attributes: Vec<f64>,
    /// Boundary markers of the points and of the segments (empty when the file has none).
    pub point_markers: Vec<i32>,
    pub segment_markers: Vec<i32>,
    /// The numbering base the file declares by its first point index (0 or 1; 0 for `.edg`).
    pub first_index: u32,
}

impl Pslg {
    pub fn n_points(&self) -> usize {
        self.xy.len() / 2
    }
}

/// Reads the file `path`, in the format its extension names (`.node`, `.poly`, `.edg`, ASCII
/// case ignored). Errors: another extension is `InvalidArgument`; an unreadable file `Io`; a
/// syntax error `InvalidInput` naming the file and line.
pub fn read_pslg(path: &Path) -> Result<Pslg> {
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    match extension.to_ascii_lowercase().as_str() {
        "node" => parse_node(&read_text(path)?, &path.display().to_string()),
        "poly" => {
            let text = read_text(path)?;
            let node_path = path.with_extension("node");
            let node = || -> Result<Pslg> {
                parse_node(&read_text(&node_path)?, &node_path.display().to_string())
            };
            parse_poly(&text, &path.display().to_string(), Some(&node))
        }
        "edg" => parse_edg(&read_text(path)?, &path.display().to_string()),
        _ => Err(Error::invalid_argument(format!(
            "unknown planar graph file extension \"{extension}\" in \"{}\": expected .node, \
             .poly or .edg",
            path.display()
        ))),
    }
}

fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|e| {
        Error::new(
            ErrorKind::Io,
            format!("cannot read \"{}\": {e}", PathBuf::from(path).display()),
        )
    })
}

/// The meaningful lines of a Triangle file: (1-based line number, fields), comments and
/// blank lines left out.
struct Lines<'a> {
    name: &'a str,
    /// The number of the file's last line.
    last: usize,
    lines: Vec<(usize, Vec<&'a str>)>,
    next: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str, name: &'a str) -> Self {
        let lines = text
            .lines()
            .enumerate()
            .filter_map(|(k, line)| {
                let line = line.split('#').next().unwrap_or("");
                let fields: Vec<&str> = line.split_whitespace().collect();
                (!fields.is_empty()).then_some((k + 1, fields))
            })
            .collect();
        Lines {
            name,
            last: text.lines().count().max(1),
            lines,
            next: 0,
        }
    }

    /// The next line, or an error saying what was expected at the end of the file.
    fn line(&mut self, what: &str) -> Result<Line<'a, '_>> {
        match self.lines.get(self.next) {
            Some((number, fields)) => {
                self.next += 1;
                Ok(Line {
                    name: self.name,
                    number: *number,
                    fields,
                })
            }
            None => Err(Error::invalid_input(format!(
                "{}:{}: end of file where {what} was expected",
                self.name, self.last
            ))),
        }
    }

    fn at_end(&self) -> bool {
        self.next >= self.lines.len()
    }
}

struct Line<'a, 'b> {
    name: &'a str,
    number: usize,
    fields: &'b [&'a str],
}

impl Line<'_, '_> {
    fn error(&self, message: impl std::fmt::Display) -> Error {
        Error::invalid_input(format!("{}:{}: {message}", self.name, self.number))
    }

    fn at_least(&self, n: usize, what: &str) -> Result<()> {
        if self.fields.len() < n {
            return Err(self.error(format!(
                "expected {what} ({n} fields), found {} field{}",
                self.fields.len(),
                if self.fields.len() == 1 { "" } else { "s" }
            )));
        }
        Ok(())
    }

    fn real(&self, k: usize, what: &str) -> Result<f64> {
        let field = self.fields[k];
        field
            .parse::<f64>()
            .map_err(|_| self.error(format!("{what} \"{field}\" is not a number")))
    }

    fn integer(&self, k: usize, what: &str) -> Result<i64> {
        let field = self.fields[k];
        field
            .parse::<i64>()
            .map_err(|_| self.error(format!("{what} \"{field}\" is not an integer")))
    }

    fn count(&self, k: usize, what: &str) -> Result<usize> {
        let n = self.integer(k, what)?;
        usize::try_from(n).map_err(|_| self.error(format!("{what} {n} is negative")))
    }
}

/// Parses the text of a Triangle `.node` file (`name` is used in error messages).
pub fn parse_node(text: &str, name: &str) -> Result<Pslg> {
    let mut lines = Lines::new(text, name);
    let mut out = Pslg::default();
    out.first_index = read_points(&mut lines, &mut out)? as u32;
    Ok(out)
}

/// Reads a `.node` section into `out`; returns the first point's index (the base), 0 when
/// there is no point.
fn read_points(lines: &mut Lines, out: &mut Pslg) -> Result<i64> {
    let header = lines.line("the point header \"<#points> 2 <#attributes> <#markers>\"")?;
    let n = header.count(0, "point count")?;
    let mut n_attributes = 0;
    let mut n_markers = 0;
    if header.fields.len() > 1 {
        let dimension = header.integer(1, "dimension")?;
        if dimension != 2 {
            return Err(header.error(format!("dimension {dimension}: must be 2")));
        }
    }
    if header.fields.len() > 2 {
        n_attributes = header.count(2, "attribute count")?;
    }
    if header.fields.len() > 3 {
        n_markers = header.count(3, "boundary marker count")?;
        if n_markers > 1 {
            return Err(header.error(format!("boundary marker count {n_markers}: must be 0 or 1")));
        }
    }
    out.n_attributes = n_attributes;
    let mut base = 0;
    for k in 0..n {
        let line = lines.line(&format!("point {} of {n}", k + 1))?;
        line.at_least(3 + n_attributes + n_markers, "<index> <x> <y> ...")?;
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
        out.xy.push(line.real(1, "x")?);
        out.xy.push(line.real(2, "y")?);
        for a in 0..n_attributes {
            out.point_attributes.push(line.real(3 + a, "attribute")?);
        }
        if n_markers == 1 {
            out.point_markers.push(marker(&line, 3 + n_attributes)?);
        }
    }
    Ok(base)
}

fn marker(line: &Line, k: usize) -> Result<i32> {
    let m = line.integer(k, "boundary marker")?;
    i32::try_from(m).map_err(|_| line.error(format!("boundary marker {m} is not a 32-bit integer")))
}

/// Parses the text of a Triangle `.poly` file (`name` is used in error messages). With 0
/// points in its header, the points come from `node` (the `.node` file of the same name);
/// without it, that is an error.
pub fn parse_poly(text: &str, name: &str, node: Option<&dyn Fn() -> Result<Pslg>>) -> Result<Pslg> {
    let mut lines = Lines::new(text, name);
    let mut out = Pslg::default();
    let header_number = lines.lines.first().map(|l| l.0).unwrap_or(1);
    let mut base = read_points(&mut lines, &mut out)?;
    if out.xy.is_empty() {
        let Some(node) = node else {
            return Err(Error::invalid_input(format!(
                "{name}:{header_number}: no points in the file, and no .node file to read them from"
            )));
        };
        let points = node()?;
        base = points.first_index as i64;
        out.xy = points.xy;
        out.n_attributes = points.n_attributes;
        out.point_attributes = points.point_attributes;
        out.point_markers = points.point_markers;
    }
    out.first_index = base as u32;
    let n = out.n_points();
    let header = lines.line("the segment header \"<#segments> <#markers>\"")?;
    let n_segments = header.count(0, "segment count")?;
    let n_markers = if header.fields.len() > 1 {
        header.count(1, "boundary marker count")?
    } else {
        0
    };
    if n_markers > 1 {
        return Err(header.error(format!("boundary marker count {n_markers}: must be 0 or 1")));
    }
    let mut raw = Vec::with_capacity(n_segments);
    for k in 0..n_segments {
        let line = lines.line(&format!("segment {} of {n_segments}", k + 1))?;
        line.at_least(3 + n_markers, "<index> <end> <end>")?;
        let ends = [
            line.integer(1, "segment end")?,
            line.integer(2, "segment end")?,
        ];
        raw.push((line.number, ends));
        if n_markers == 1 {
            out.segment_markers.push(marker(&line, 3)?);
        }
    }
    for (number, ends) in raw {
        for e in ends {
            let i = e - base;
            if i < 0 || i >= n as i64 {
                return Err(Error::invalid_input(format!(
                    "{name}:{number}: segment end {e} is not a point index ({} to {})",
                    base,
                    base + n as i64 - 1
                )));
            }
            out.segments.push(i as u32);
        }
    }
    if lines.at_end() {
        return Ok(out);
    }
    let header = lines.line("the hole count")?;
    let n_holes = header.count(0, "hole count")?;
    for k in 0..n_holes {
        let line = lines.line(&format!("hole {} of {n_holes}", k + 1))?;
        line.at_least(3, "<index> <x> <y>")?;
        out.holes.push([line.real(1, "x")?, line.real(2, "y")?]);
    }
    if lines.at_end() {
        return Ok(out);
    }
    let header = lines.line("the region count")?;
    let n_regions = header.count(0, "region count")?;
    for k in 0..n_regions {
        let line = lines.line(&format!("region {} of {n_regions}", k + 1))?;
        line.at_least(4, "<index> <x> <y> <attribute> [max area]")?;
        let attribute = line.real(3, "regional attribute")?;
        if !(attribute.fract() == 0.0 && attribute.abs() <= i32::MAX as f64) {
            return Err(line.error(format!(
                "regional attribute {attribute} is not a 32-bit integer (it is the region label)"
            )));
        }
        let max_area = if line.fields.len() > 4 {
            line.real(4, "maximum area")?
        } else {
            0.0
        };
        if max_area.is_nan() {
            return Err(line.error("maximum area is NaN"));
        }
        out.regions.push(RegionSeed {
            seed: [line.real(1, "x")?, line.real(2, "y")?],
            label: attribute as i32,
            max_area: if max_area > 0.0 { max_area } else { 0.0 },
        });
    }
    if !lines.at_end() {
        let line = lines.line("")?;
        return Err(line.error("unexpected content after the regions"));
    }
    Ok(out)
}

/// Parses the text of a CGAL `.edg` file (`name` is used in error messages).
pub fn parse_edg(text: &str, name: &str) -> Result<Pslg> {
    let mut tokens = text
        .lines()
        .enumerate()
        .flat_map(|(k, line)| line.split_whitespace().map(move |t| (k + 1, t)));
    let mut last_line = 1;
    let mut next = |what: &str| -> Result<(usize, &str)> {
        match tokens.next() {
            Some((number, token)) => {
                last_line = number;
                Ok((number, token))
            }
            None => Err(Error::invalid_input(format!(
                "{name}:{last_line}: end of file where {what} was expected"
            ))),
        }
    };
    let (number, token) = next("the segment count")?;
    let n: usize = token.parse().map_err(|_| {
        Error::invalid_input(format!(
            "{name}:{number}: segment count \"{token}\" is not a non-negative integer"
        ))
    })?;
    let mut out = Pslg::default();
    let mut index: HashMap<[u64; 2], u32> = HashMap::new();
    for k in 0..n {
        let mut ends = [0u32; 2];
        for end in &mut ends {
            let mut p = [0.0; 2];
            for (c, x) in p.iter_mut().enumerate() {
                let what = format!("coordinate {} of segment {} of {n}", ["x", "y"][c], k + 1);
                let (number, token) = next(&what)?;
                *x = token.parse::<f64>().map_err(|_| {
                    Error::invalid_input(format!(
                        "{name}:{number}: {what}: \"{token}\" is not a number"
                    ))
                })?;
            }
            // +0 and -0 are one point; NaN is left to the input checks (one point per NaN).
            let key = p.map(|x| if x == 0.0 { 0u64 } else { x.to_bits() });
            *end = if p.iter().any(|x| x.is_nan()) {
                out.xy.extend(p);
                (out.xy.len() / 2 - 1) as u32
            } else {
                *index.entry(key).or_insert_with(|| {
                    out.xy.extend(p);
                    (out.xy.len() / 2 - 1) as u32
                })
            };
        }
        if ends[0] != ends[1] {
            out.segments.extend(ends);
        }
    }
    if let Some((number, token)) = tokens.next() {
        return Err(Error::invalid_input(format!(
            "{name}:{number}: unexpected \"{token}\" after the {n} segments"
        )));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edg_points_are_shared_by_coordinates() {
        let p = parse_edg("3\n0 0 1 0\n1 0 -0 1\n0 1 0 1\n", "t.edg").unwrap();
        assert_eq!(p.xy, vec![0.0, 0.0, 1.0, 0.0, -0.0, 1.0]);
        assert_eq!(p.segments, vec![0, 1, 1, 2]);
    }
}
