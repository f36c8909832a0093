//! PLY (Stanford polygon format): ASCII, binary little endian and binary big
//! endian.
//!
//! Reading goes through `ply-rs-bw`. The `vertex` element must have scalar
//! `x`, `y`, `z` properties of any numeric type (usually `float` or
//! `double`); the optional `face` element must have a `vertex_indices` (or
//! `vertex_index`) list of integers. Other properties and elements are
//! ignored. In ASCII PLY, `ply-rs-bw` accepts numbers of the form
//! `[-+]digits[.digits][e[-+]digits]` only, so `nan`, `inf`, `1.` or `.5`
//! are parse errors naming the line.
//!
//! Writing (own code, so the output is exactly known): `double` coordinates
//! (ASCII in shortest round-trip form, or binary little endian), faces as
//! `list uchar int vertex_indices` (`list uint int` if a face has more than
//! 255 vertices). Both are bit-exact.

use std::fmt::Write;
use std::io::Cursor;

use dymsum::PolygonMesh;
use ply_rs_bw::parser::{ParseError, Parser, Reader};
use ply_rs_bw::ply::{Encoding, Header, PropertyAccess, PropertyAccessResult, PropertyType};

use super::{push_vertices_and_faces, vertex_index, FormatError, Location};

/// One PLY element of any kind: only the properties we use are kept.
#[derive(Default)]
struct Elem {
    xyz: [Option<f64>; 3],
    indices: Option<Vec<i64>>,
}

impl Elem {
    fn scalar(&mut self, name: &str, v: f64) -> PropertyAccessResult {
        let slot = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => return PropertyAccessResult::Ignored,
        };
        self.xyz[slot] = Some(v);
        PropertyAccessResult::Set
    }

    fn list<T: Into<i64>>(&mut self, name: &str, v: Vec<T>) -> PropertyAccessResult {
        if is_index_list(name) {
            self.indices = Some(v.into_iter().map(Into::into).collect());
            PropertyAccessResult::Set
        } else {
            PropertyAccessResult::Ignored
        }
    }
}

fn is_index_list(name: &str) -> bool {
    name == "vertex_indices" || name == "vertex_index"
}

impl PropertyAccess for Elem {
    fn new() -> Self {
        Self::default()
    }
    fn set_char(&mut self, name: &str, v: i8) -> PropertyAccessResult {
        self.scalar(name, v.into())
    }
    fn set_uchar(&mut self, name: &str, v: u8) -> PropertyAccessResult {
        self.scalar(name, v.into())
    }
    fn set_short(&mut self, name: &str, v: i16) -> PropertyAccessResult {
        self.scalar(name, v.into())
    }
    fn set_ushort(&mut self, name: &str, v: u16) -> PropertyAccessResult {
        self.scalar(name, v.into())
    }
    fn set_int(&mut self, name: &str, v: i32) -> PropertyAccessResult {
        self.scalar(name, v.into())
    }
    fn set_uint(&mut self, name: &str, v: u32) -> PropertyAccessResult {
        self.scalar(name, v.into())
    }
    fn set_float(&mut self, name: &str, v: f32) -> PropertyAccessResult {
        self.scalar(name, v.into())
    }
    fn set_double(&mut self, name: &str, v: f64) -> PropertyAccessResult {
        self.scalar(name, v)
    }
    fn set_list_char(&mut self, name: &str, v: Vec<i8>) -> PropertyAccessResult {
        self.list(name, v)
    }
    fn set_list_uchar(&mut self, name: &str, v: Vec<u8>) -> PropertyAccessResult {
        self.list(name, v)
    }
    fn set_list_short(&mut self, name: &str, v: Vec<i16>) -> PropertyAccessResult {
        self.list(name, v)
    }
    fn set_list_ushort(&mut self, name: &str, v: Vec<u16>) -> PropertyAccessResult {
        self.list(name, v)
    }
    fn set_list_int(&mut self, name: &str, v: Vec<i32>) -> PropertyAccessResult {
        self.list(name, v)
    }
    fn set_list_uint(&mut self, name: &str, v: Vec<u32>) -> PropertyAccessResult {
        self.list(name, v)
    }
    fn set_list_float(&mut self, name: &str, _v: Vec<f32>) -> PropertyAccessResult {
        if is_index_list(name) {
            PropertyAccessResult::UnsupportedType
        } else {
            PropertyAccessResult::Ignored
        }
    }
    fn set_list_double(&mut self, name: &str, _v: Vec<f64>) -> PropertyAccessResult {
        if is_index_list(name) {
            PropertyAccessResult::UnsupportedType
        } else {
            PropertyAccessResult::Ignored
        }
    }
}

/// Maps positions in the payload to [`Location`]s.
struct Locator<'h> {
    header: &'h Header,
    /// 1-based line number of the first payload line (ASCII).
    first_data_line: usize,
}

impl Locator<'_> {
    fn ascii(&self) -> bool {
        self.header.encoding == Encoding::Ascii
    }

    /// Location of element `index` of element kind `kind`.
    fn element(&self, kind: &str, index: usize) -> Location {
        if self.ascii() {
            let before: usize = self
                .header
                .elements
                .iter()
                .take_while(|(k, _)| k.as_str() != kind)
                .map(|(_, e)| e.count)
                .fold(0usize, usize::saturating_add);
            Location::Line(
                self.first_data_line
                    .saturating_add(before)
                    .saturating_add(index),
            )
        } else {
            Location::Element {
                kind: kind.to_string(),
                index,
            }
        }
    }

    /// Location of a payload error reported by ply-rs-bw at its "line".
    fn payload_error(&self, line: Option<usize>) -> Location {
        let Some(line) = line else {
            return Location::Whole;
        };
        if self.ascii() {
            return Location::Line(line);
        }
        // In binary payloads ply-rs-bw counts one "line" per element.
        let Some(mut g) = line.checked_sub(self.first_data_line) else {
            return Location::Whole;
        };
        for (kind, e) in &self.header.elements {
            if g < e.count {
                return Location::Element {
                    kind: kind.clone(),
                    index: g,
                };
            }
            g -= e.count;
        }
        Location::Whole
    }
}

impl Locator<'_> {
    /// The element kind on a payload line (ASCII) or at a payload error.
    fn kind_at(&self, line: Option<usize>) -> Option<String> {
        let mut g = line?.checked_sub(self.first_data_line)?;
        for (kind, e) in &self.header.elements {
            if g < e.count {
                return Some(kind.clone());
            }
            g -= e.count;
        }
        None
    }
}

/// ply-rs-bw's error text, restated in our own words: its text is
/// multi-line, quotes parser internals (`ParseError { location: ... }`) and
/// its own line numbers, which our [`Location`] replaces.
fn message(e: &ParseError, kind: Option<&str>) -> String {
    let raw = e.to_string();
    let raw = match raw.split_once(": ") {
        Some((prefix, rest)) if prefix.starts_with("Line ") => rest,
        _ => raw.as_str(),
    };
    let head = raw.lines().next().unwrap_or("").trim();
    let quoted = raw
        .split_once("String: '")
        .and_then(|(_, r)| r.split_once('\''))
        .map(|(t, _)| t.trim());
    let detail = raw.rsplit_once("Error: ").map(|(_, d)| d.trim());
    if head.contains("magic number") {
        return "not a PLY file: the first line must be `ply`".to_string();
    }
    if head.starts_with("Unexpected end of file") {
        return end_of_file_message(head);
    }
    if let Some(d) = detail.filter(|d| d.contains("list elements")) {
        return short_list_message(d, quoted.unwrap_or(""));
    }
    if head.starts_with("Couldn't parse line") {
        return match quoted {
            Some(t) => format!("cannot understand the header line `{t}`"),
            None => "cannot understand a header line".to_string(),
        };
    }
    if head.starts_with("Couldn't read element line")
        || head.starts_with("Couldn't parse element line")
    {
        return element_line_message(quoted, kind);
    }
    // Anything else: its first line, without the parser's internals.
    match head.split_once("ParseError {") {
        Some((before, _)) => before.trim().to_string(),
        None => head.trim_end_matches('.').to_string(),
    }
}

/// "Unexpected end of file ... element 'vertex' (expected 4, got 3)." in
/// our words.
fn end_of_file_message(head: &str) -> String {
    let what = head
        .split_once("element '")
        .and_then(|(_, r)| r.split_once('\''))
        .map(|(k, _)| k);
    let counts = head
        .split_once("(expected ")
        .and_then(|(_, r)| r.split_once(')'))
        .and_then(|(c, _)| c.split_once(", got "));
    if let (Some(what), Some((declared, found))) = (what, counts) {
        return format!(
            "the file ends after {found} of the {declared} `{what}` elements the header declares"
        );
    }
    "the file ends before all elements the header declares".to_string()
}

/// A list shorter than its count: `detail` holds the two numbers, `text`
/// the offending payload line.
fn short_list_message(detail: &str, text: &str) -> String {
    let counts: Vec<&str> = detail
        .split(|c: char| !c.is_ascii_digit())
        .filter(|t| !t.is_empty())
        .collect();
    match counts.as_slice() {
        [want, got] => {
            format!("`{text}`: the list count says {want} entries, but only {got} follow")
        }
        _ => format!("`{text}`: a list is shorter than its count"),
    }
}

/// A payload line whose values cannot be read (`quoted`: the line, `kind`:
/// its element kind).
fn element_line_message(quoted: Option<&str>, kind: Option<&str>) -> String {
    let element = kind.map_or_else(|| "an".to_string(), |k| format!("a `{k}`"));
    match quoted {
        Some(t) => format!(
            "cannot read `{t}` as the values of {element} element (plain decimal numbers, \
             one per property of the header; nan and inf are not allowed)"
        ),
        None => format!("cannot read the values of {element} element"),
    }
}

pub(crate) fn read(bytes: &[u8], name: &str) -> Result<PolygonMesh, FormatError> {
    if bytes.is_empty() {
        return Err(FormatError::Empty {
            source_name: name.to_string(),
        });
    }
    let parser = Parser::<Elem>::new();
    let mut reader = Reader::new(Cursor::new(bytes));
    let header = parser.read_header(&mut reader).map_err(|e| {
        let at = e.line().map_or(Location::Whole, Location::Line);
        FormatError::parse(name, at, format!("PLY header: {}", message(&e, None)))
    })?;
    let loc = Locator {
        header: &header,
        first_data_line: reader.line(),
    };
    let header_end = Location::Line(reader.line().saturating_sub(1));
    check_mesh_header(&header, name, header_end)?;

    let mut payload = parser.read_payload(&mut reader, &header).map_err(|e| {
        let kind = loc.kind_at(e.line());
        FormatError::parse(
            name,
            loc.payload_error(e.line()),
            message(&e, kind.as_deref()),
        )
    })?;
    let vertices = vertex_positions(
        &payload.swap_remove("vertex").unwrap_or_default(),
        &loc,
        name,
    )?;
    let faces = face_lists(
        payload.swap_remove("face").unwrap_or_default(),
        vertices.len(),
        &loc,
        name,
    )?;
    Ok(PolygonMesh { vertices, faces })
}

/// Checks the header describes a polygon mesh before the payload is read: a
/// non-empty `vertex` element with scalar `x`, `y`, `z`, and, if there are
/// faces, a `vertex_indices` list on them. Errors point at `header_end`.
fn check_mesh_header(header: &Header, name: &str, header_end: Location) -> Result<(), FormatError> {
    let Some(vdef) = header.elements.get("vertex") else {
        return Err(FormatError::unsupported(
            name,
            header_end,
            "PLY without a \"vertex\" element",
        ));
    };
    for axis in ["x", "y", "z"] {
        match vdef.properties.get(axis).map(|p| &p.data_type) {
            Some(PropertyType::Scalar(_)) => {}
            Some(PropertyType::List(..)) => {
                return Err(FormatError::unsupported(
                    name,
                    header_end,
                    format!("vertex property {axis} is a list"),
                ))
            }
            None => {
                return Err(FormatError::unsupported(
                    name,
                    header_end,
                    format!("PLY vertex element without an \"{axis}\" property"),
                ))
            }
        }
    }
    if vdef.count == 0 {
        return Err(FormatError::Empty {
            source_name: name.to_string(),
        });
    }
    if let Some(fdef) = header.elements.get("face") {
        let has_list = fdef
            .properties
            .iter()
            .any(|(k, p)| is_index_list(k) && matches!(p.data_type, PropertyType::List(..)));
        if fdef.count > 0 && !has_list {
            return Err(FormatError::unsupported(
                name,
                header_end,
                "PLY face element without a \"vertex_indices\" list",
            ));
        }
    }
    Ok(())
}

/// The `x y z` of each `vertex` element, all finite.
fn vertex_positions(
    velems: &[Elem],
    loc: &Locator<'_>,
    name: &str,
) -> Result<Vec<[f64; 3]>, FormatError> {
    let mut vertices = Vec::with_capacity(velems.len());
    for (i, e) in velems.iter().enumerate() {
        let (Some(x), Some(y), Some(z)) = (e.xyz[0], e.xyz[1], e.xyz[2]) else {
            return Err(FormatError::parse(
                name,
                loc.element("vertex", i),
                "vertex lacks a coordinate",
            ));
        };
        if let Some(bad) = [x, y, z].into_iter().find(|c| !c.is_finite()) {
            return Err(FormatError::NonFinite {
                source_name: name.to_string(),
                at: loc.element("vertex", i),
                value: bad.to_string(),
            });
        }
        vertices.push([x, y, z]);
    }
    Ok(vertices)
}

/// The index list of each `face` element: at least 3 indices, each in
/// `0..nv`.
fn face_lists(
    felems: Vec<Elem>,
    nv: usize,
    loc: &Locator<'_>,
    name: &str,
) -> Result<Vec<Vec<usize>>, FormatError> {
    let mut faces = Vec::with_capacity(felems.len());
    for (j, e) in felems.into_iter().enumerate() {
        let raw = e.indices.unwrap_or_default();
        if raw.len() < 3 {
            return Err(FormatError::DegenerateFace {
                source_name: name.to_string(),
                at: loc.element("face", j),
                len: raw.len(),
            });
        }
        let face = raw
            .into_iter()
            .map(|r| vertex_index(r, nv, name, loc.element("face", j)))
            .collect::<Result<Vec<usize>, _>>()?;
        faces.push(face);
    }
    Ok(faces)
}

/// Header for writing; `format` is `ascii` or `binary_little_endian`.
fn header(mesh: &PolygonMesh, format: &str) -> (String, bool) {
    let wide_count = mesh.faces.iter().any(|f| f.len() > 255);
    let count_type = if wide_count { "uint" } else { "uchar" };
    let mut h = String::new();
    let _ = write!(
        h,
        "ply\nformat {format} 1.0\ncomment written by dymsum\n\
         element vertex {}\nproperty double x\nproperty double y\nproperty double z\n\
         element face {}\nproperty list {count_type} int vertex_indices\nend_header\n",
        mesh.vertices.len(),
        mesh.faces.len()
    );
    (h, wide_count)
}

pub(crate) fn write_ascii(mesh: &PolygonMesh) -> Vec<u8> {
    let (mut out, _) = header(mesh, "ascii");
    out.reserve(40 * mesh.vertices.len() + 16 * mesh.faces.len());
    push_vertices_and_faces(&mut out, mesh);
    out.into_bytes()
}

pub(crate) fn write_binary_le(mesh: &PolygonMesh) -> Vec<u8> {
    let (h, wide_count) = header(mesh, "binary_little_endian");
    let mut out = h.into_bytes();
    out.reserve(24 * mesh.vertices.len() + 16 * mesh.faces.len());
    for v in &mesh.vertices {
        for c in v {
            out.extend_from_slice(&c.to_le_bytes());
        }
    }
    for f in &mesh.faces {
        if wide_count {
            out.extend_from_slice(&(f.len() as u32).to_le_bytes());
        } else {
            out.push(f.len() as u8);
        }
        for &i in f {
            // `write_mesh_bytes` rejects more than i32::MAX vertices.
            out.extend_from_slice(&(i as i32).to_le_bytes());
        }
    }
    out
}
