//! Polygon File Format `.ply`: ASCII, binary little-endian and binary big-endian.

use std::path::Path;

use super::polygon::triangulate_polygon;
use super::text::{self, error_at, to_index, Lines, Tokens};
use crate::error::{Error, Result};
use crate::predicates::Point;
use crate::recovery::Surface;

/// Reads the PLY file `path` of contents `bytes`.
pub(super) fn read(path: &Path, bytes: &[u8]) -> Result<Surface> {
    let header = read_header(path, bytes)?;
    let body = &bytes[header.body..];
    match header.encoding {
        Encoding::Ascii => {
            let first_line = header.lines + 1;
            let text = text::utf8(path, body, first_line)?;
            let tokens = Tokens::new(Lines::new(path, text, None, first_line));
            read_body(&header, &mut Ascii(tokens), body.len())
        }
        Encoding::LittleEndian | Encoding::BigEndian => {
            let mut values = Binary {
                path,
                bytes,
                offset: header.body,
                last: header.body,
                big_endian: header.encoding == Encoding::BigEndian,
            };
            read_body(&header, &mut values, body.len())
        }
    }
}

/// A scalar type of the format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    /// The type named `name` (`char` or `int8`, ..., `double` or `float64`).
    fn parse(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    /// Its size in bytes in binary files.
    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Ascii,
    LittleEndian,
    BigEndian,
}

/// What the reader takes from a property.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    /// Coordinate `k` of a vertex.
    Coordinate(usize),
    /// The corners of a face.
    Corners,
    Skip,
}

/// A property: a scalar, or a list (`count` values of type `item`, after the count).
#[derive(Clone, Copy, Debug)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

struct Element {
    name: String,
    count: usize,
    properties: Vec<(Kind, Role)>,
}

struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// The number of vertices.
    n_vertices: usize,
    /// The byte offset of the data, after the header's last line.
    body: usize,
    /// The number of lines of the header.
    lines: usize,
}

/// Reads the header: `ply`, `format <encoding> 1.0`, `comment` and `obj_info` lines,
/// `element <name> <count>` followed by its `property <type> <name>` and
/// `property list <count type> <index type> <name>` lines, `end_header`.
fn read_header(path: &Path, bytes: &[u8]) -> Result<Header> {
    let mut position = 0;
    let mut number = 0;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        number += 1;
        let rest = &bytes[position..];
        let Some(length) = rest.iter().position(|&b| b == b'\n') else {
            return Err(error_at(
                path,
                number,
                "end of file in the header (no \"end_header\")",
            ));
        };
        let line = text::utf8(path, &rest[..length], number)?;
        position += length + 1;
        let fields: Vec<&str> = line.split_ascii_whitespace().collect();
        let error = |message: String| error_at(path, number, message);
        if number == 1 {
            if fields != ["ply"] {
                return Err(error(
                    "not a PLY file: the first line is not \"ply\"".into(),
                ));
            }
            continue;
        }
        match fields.first().copied() {
            None | Some("comment") | Some("obj_info") => {}
            Some("format") => encoding = Some(parse_format(&fields).map_err(error)?),
            Some("element") => elements.push(parse_element(&fields).map_err(error)?),
            Some("property") => {
                let element = elements
                    .last_mut()
                    .ok_or_else(|| error("property before any element".into()))?;
                let property = parse_property(&fields, &element.name).map_err(error)?;
                element.properties.push(property);
            }
            Some("end_header") => break,
            Some(other) => return Err(error(format!("unknown header keyword \"{other}\""))),
        }
    }
    let encoding = encoding.ok_or_else(|| error_at(path, number, "no \"format\" line"))?;
    let n_vertices = check_elements(&elements).map_err(|m| error_at(path, number, m))?;
    Ok(Header {
        encoding,
        elements,
        n_vertices,
        body: position,
        lines: number,
    })
}

/// The encoding of the line `format <encoding> <version>`.
fn parse_format(fields: &[&str]) -> std::result::Result<Encoding, String> {
    match fields.get(1).copied() {
        Some("ascii") => Ok(Encoding::Ascii),
        Some("binary_little_endian") => Ok(Encoding::LittleEndian),
        Some("binary_big_endian") => Ok(Encoding::BigEndian),
        other => Err(format!(
            "format \"{}\": expected ascii, binary_little_endian or binary_big_endian",
            other.unwrap_or("")
        )),
    }
}

/// The element of the line `element <name> <count>`, without properties yet.
fn parse_element(fields: &[&str]) -> std::result::Result<Element, String> {
    let [_, name, count] = fields else {
        return Err("expected \"element <name> <count>\"".into());
    };
    let count = count
        .parse::<usize>()
        .map_err(|_| format!("element count \"{count}\" is not a non-negative integer"))?;
    Ok(Element {
        name: name.to_string(),
        count,
        properties: Vec::new(),
    })
}

/// The property of the line `property <type> <name>` or
/// `property list <count type> <item type> <name>` of the element `element`.
fn parse_property(fields: &[&str], element: &str) -> std::result::Result<(Kind, Role), String> {
    let scalar = |name: &str| Scalar::parse(name).ok_or(format!("unknown type \"{name}\""));
    let (kind, name) = match fields {
        [_, "list", count, item, name] => {
            let (count, item) = (scalar(count)?, scalar(item)?);
            if !count.is_integer() {
                return Err(format!(
                    "list \"{name}\": its count type is not an integer type"
                ));
            }
            (Kind::List { count, item }, *name)
        }
        [_, ty, name] => (Kind::Scalar(scalar(ty)?), *name),
        _ => {
            return Err(
                "expected \"property <type> <name>\" or \"property list <count type> \
                 <item type> <name>\""
                    .into(),
            )
        }
    };
    let role = match (element, name, kind) {
        ("vertex", "x" | "y" | "z", Kind::Scalar(_)) => {
            Role::Coordinate(usize::from(name == "y") + 2 * usize::from(name == "z"))
        }
        ("vertex", "x" | "y" | "z", Kind::List { .. }) => {
            return Err(format!("vertex coordinate \"{name}\" is a list"))
        }
        ("face", "vertex_indices" | "vertex_index", Kind::List { item, .. }) => {
            if !item.is_integer() {
                return Err(format!(
                    "face list \"{name}\": its index type is not an integer type"
                ));
            }
            Role::Corners
        }
        ("face", "vertex_indices" | "vertex_index", Kind::Scalar(_)) => {
            return Err(format!("face property \"{name}\" is not a list"))
        }
        _ => Role::Skip,
    };
    Ok((kind, role))
}

/// Checks that there is one `vertex` element with `x`, `y` and `z`, and one `face` element
/// with its corners; returns the number of vertices.
fn check_elements(elements: &[Element]) -> std::result::Result<usize, String> {
    let one = |name: &str| -> std::result::Result<&Element, String> {
        match elements
            .iter()
            .filter(|e| e.name == name)
            .collect::<Vec<_>>()[..]
        {
            [element] => Ok(element),
            [] => Err(format!("no \"{name}\" element")),
            _ => Err(format!("several \"{name}\" elements")),
        }
    };
    let (vertex, face) = (one("vertex")?, one("face")?);
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        if !vertex.properties.iter().any(|p| p.1 == Role::Coordinate(k)) {
            return Err(format!("the vertex element has no property \"{axis}\""));
        }
    }
    if !face.properties.iter().any(|p| p.1 == Role::Corners) {
        return Err("the face element has no list \"vertex_indices\" or \"vertex_index\"".into());
    }
    if u32::try_from(vertex.count).is_err() {
        return Err(format!("{} vertices: at most 2^32 - 1", vertex.count));
    }
    Ok(vertex.count)
}

/// The values of the data, one after the other.
trait Values {
    /// The next value, of type `ty`, as a finite real number.
    fn real(&mut self, ty: Scalar, what: &str) -> Result<f64>;
    /// The next value, of the integer type `ty`.
    fn integer(&mut self, ty: Scalar, what: &str) -> Result<i64>;
    /// Skips the next value, of type `ty`.
    fn skip(&mut self, ty: Scalar, what: &str) -> Result<()>;
    /// Where the last value read is (a line number or a byte offset).
    fn position(&self) -> usize;
    /// A syntax error at `position`.
    fn error_at(&self, position: usize, message: String) -> Error;
}

/// The values of ASCII data: whitespace-separated fields, whatever the lines.
struct Ascii<'a>(Tokens<'a>);

impl Values for Ascii<'_> {
    fn real(&mut self, _: Scalar, what: &str) -> Result<f64> {
        self.0.real(what)
    }

    fn integer(&mut self, _: Scalar, what: &str) -> Result<i64> {
        self.0.integer(what)
    }

    fn skip(&mut self, _: Scalar, what: &str) -> Result<()> {
        self.0.next(what).map(|_| ())
    }

    fn position(&self) -> usize {
        self.0.line()
    }

    fn error_at(&self, position: usize, message: String) -> Error {
        self.0.error_at(position, message)
    }
}

/// The values of binary data.
struct Binary<'a> {
    path: &'a Path,
    bytes: &'a [u8],
    /// The offset of the next value.
    offset: usize,
    /// The offset of the last value read.
    last: usize,
    big_endian: bool,
}

/// A value read from binary data.
enum Number {
    Integer(i64),
    Real(f64),
}

impl Binary<'_> {
    /// The next value, of type `ty`.
    fn next(&mut self, ty: Scalar, what: &str) -> Result<Number> {
        let bytes = self
            .bytes
            .get(self.offset..self.offset + ty.size())
            .ok_or_else(|| {
                self.error_at(
                    self.offset,
                    format!("end of file where {what} was expected"),
                )
            })?;
        self.last = self.offset;
        self.offset += ty.size();
        Ok(decode(ty, bytes, self.big_endian))
    }
}

/// The value of type `ty` in `bytes` (of its size).
fn decode(ty: Scalar, bytes: &[u8], big_endian: bool) -> Number {
    /// The first `N` bytes of `bytes` in little-endian order.
    fn array<const N: usize>(bytes: &[u8], big_endian: bool) -> [u8; N] {
        let mut a = bytes.first_chunk::<N>().copied().unwrap_or([0; N]);
        if big_endian {
            a.reverse();
        }
        a
    }
    let b = bytes;
    let e = big_endian;
    match ty {
        Scalar::I8 => Number::Integer(i8::from_le_bytes(array(b, e)).into()),
        Scalar::U8 => Number::Integer(u8::from_le_bytes(array(b, e)).into()),
        Scalar::I16 => Number::Integer(i16::from_le_bytes(array(b, e)).into()),
        Scalar::U16 => Number::Integer(u16::from_le_bytes(array(b, e)).into()),
        Scalar::I32 => Number::Integer(i32::from_le_bytes(array(b, e)).into()),
        Scalar::U32 => Number::Integer(u32::from_le_bytes(array(b, e)).into()),
        Scalar::F32 => Number::Real(f32::from_le_bytes(array(b, e)).into()),
        Scalar::F64 => Number::Real(f64::from_le_bytes(array(b, e))),
    }
}

impl Values for Binary<'_> {
    fn real(&mut self, ty: Scalar, what: &str) -> Result<f64> {
        let x = match self.next(ty, what)? {
            Number::Integer(i) => i as f64,
            Number::Real(x) => x,
        };
        if !x.is_finite() {
            return Err(self.error_at(self.last, format!("{what} is not finite")));
        }
        Ok(x)
    }

    fn integer(&mut self, ty: Scalar, what: &str) -> Result<i64> {
        match self.next(ty, what)? {
            Number::Integer(i) => Ok(i),
            Number::Real(_) => Err(self.error_at(self.last, format!("{what} is not an integer"))),
        }
    }

    fn skip(&mut self, ty: Scalar, what: &str) -> Result<()> {
        self.next(ty, what).map(|_| ())
    }

    fn position(&self) -> usize {
        self.last
    }

    fn error_at(&self, position: usize, message: String) -> Error {
        Error::invalid_input(format!(
            "{}: byte {position}: {message}",
            self.path.display()
        ))
    }
}

/// The faces read: corners of face `f` at `corners[ends[f - 1]..ends[f]]`, read at
/// `positions[f]`.
#[derive(Default)]
struct Faces {
    corners: Vec<u32>,
    ends: Vec<usize>,
    positions: Vec<usize>,
}

/// Reads the data of the elements of `header` (`size` bytes), then triangulates the faces.
fn read_body(header: &Header, values: &mut impl Values, size: usize) -> Result<Surface> {
    let mut points: Vec<Point> = Vec::new();
    let mut faces = Faces::default();
    // An element without properties has no data, however many instances it has.
    for element in header.elements.iter().filter(|e| !e.properties.is_empty()) {
        let is_vertex = element.name == "vertex";
        if is_vertex {
            points.reserve(element.count.min(size));
        }
        for _ in 0..element.count {
            let mut p = [0.0; 3];
            for &(kind, role) in &element.properties {
                read_property(kind, role, values, header.n_vertices, &mut p, &mut faces)?;
            }
            if is_vertex {
                points.push(p);
            }
        }
    }
    let mut triangles = Vec::new();
    let mut start = 0;
    for (f, (&end, &position)) in faces.ends.iter().zip(&faces.positions).enumerate() {
        triangulate_polygon(&points, &faces.corners[start..end], &mut triangles)
            .map_err(|reason| values.error_at(position, format!("face {}: {reason}", f + 1)))?;
        start = end;
    }
    Ok(Surface {
        xyz: points.into_flattened(),
        triangles,
        ..Surface::default()
    })
}

/// Reads one property of an element: a coordinate into `p`, corners into `faces`, or
/// nothing.
fn read_property(
    kind: Kind,
    role: Role,
    values: &mut impl Values,
    n_vertices: usize,
    p: &mut Point,
    faces: &mut Faces,
) -> Result<()> {
    match (kind, role) {
        (Kind::Scalar(ty), Role::Coordinate(k)) => {
            p[k] = values.real(ty, ["vertex x", "vertex y", "vertex z"][k])?;
        }
        (Kind::Scalar(ty), _) => values.skip(ty, "a property value")?,
        (Kind::List { count, item }, role) => {
            let n = values.integer(count, "a list count")?;
            let position = values.position();
            if n < 0 {
                return Err(values.error_at(position, format!("list count {n} is negative")));
            }
            for _ in 0..n {
                if role == Role::Corners {
                    let i = values.integer(item, "a vertex index")?;
                    let index = to_index(i, n_vertices).ok_or_else(|| {
                        values.error_at(
                            values.position(),
                            format!(
                                "vertex index {i} is out of range (0 to {})",
                                n_vertices as i64 - 1
                            ),
                        )
                    })?;
                    faces.corners.push(index);
                } else {
                    values.skip(item, "a list item")?;
                }
            }
            if role == Role::Corners {
                faces.ends.push(faces.corners.len());
                faces.positions.push(position);
            }
        }
    }
    Ok(())
}
