//! STL, ASCII and binary.
//!
//! STL stores independent triangles with `f32` coordinates. Reading merges
//! corners with bit-identical positions (`-0.0` counting as `0.0`) into shared
//! vertices, numbered in order of first appearance, so a closed surface comes
//! back as a closed mesh. Normals and attribute bytes are ignored.
//!
//! * Binary: detected when the file length is exactly `84 + 50 * count`, or
//!   when the file does not start with `solid`. Triangles are read with
//!   `stl_io` after the length has been checked against the header count, so
//!   a truncated file or a lying count gives [`FormatError::CountMismatch`] at
//!   the byte offset of the first incomplete triangle, and bytes beyond the
//!   declared triangles give [`FormatError::Parse`] at the first extra byte.
//! * ASCII: an own line-based parser (so errors carry line numbers and a bare
//!   `solid` line without a name is accepted); coordinates are parsed as `f32`
//!   like binary STL, so ASCII and binary STL of the same data read alike.
//!   Several `solid ... endsolid` blocks may follow one another.
//!
//! Writing is lossy: every coordinate is rounded to the nearest `f32` and
//! every polygon is fan-triangulated (`[a, b, c, d]` becomes `[a, b, c]` and
//! `[a, c, d]`). Binary STL is written with `stl_io` (zero header, normals
//! computed in `f64` and rounded); ASCII STL prints each `f32` in its
//! shortest round-trip form.

use std::fmt::Write;
use std::io::Cursor;

use dymsum::PolygonMesh;

use super::{capped, FormatError, Location};

/// The merging map: foldhash (seeded per process, as std's maps are)
/// hashes the coordinate bits several times faster than SipHash, which
/// took most of reading a 46,000-triangle STL.
type HashMap<K, V> = std::collections::HashMap<K, V, foldhash::fast::RandomState>;

/// Builds a mesh from triangle corners, merging identical positions.
#[derive(Default)]
struct Merger {
    index: HashMap<[u64; 3], usize>,
    vertices: Vec<[f64; 3]>,
    faces: Vec<Vec<usize>>,
}

impl Merger {
    fn vertex(&mut self, v: [f64; 3]) -> usize {
        // `+ 0.0` turns -0.0 into 0.0 so both merge.
        let key = v.map(|c| (c + 0.0).to_bits());
        let next = self.vertices.len();
        let i = *self.index.entry(key).or_insert(next);
        if i == next {
            self.vertices.push(v);
        }
        i
    }

    fn triangle(&mut self, t: [[f64; 3]; 3]) {
        let face = t.iter().map(|&v| self.vertex(v)).collect();
        self.faces.push(face);
    }

    fn finish(self, name: &str) -> Result<PolygonMesh, FormatError> {
        if self.vertices.is_empty() {
            return Err(FormatError::Empty {
                source_name: name.to_string(),
            });
        }
        Ok(PolygonMesh {
            vertices: self.vertices,
            faces: self.faces,
        })
    }
}

fn looks_ascii(bytes: &[u8]) -> bool {
    let start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    bytes[start..]
        .get(..5)
        .is_some_and(|s| s.eq_ignore_ascii_case(b"solid"))
}

fn binary_count(bytes: &[u8]) -> Option<u32> {
    let c = bytes.get(80..84)?;
    Some(u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
}

pub(crate) fn read(bytes: &[u8], name: &str) -> Result<PolygonMesh, FormatError> {
    if bytes.is_empty() {
        return Err(FormatError::Empty {
            source_name: name.to_string(),
        });
    }
    let exact_binary =
        binary_count(bytes).is_some_and(|n| 84 + 50 * n as u64 == bytes.len() as u64);
    if !exact_binary && looks_ascii(bytes) {
        read_ascii(bytes, name)
    } else {
        read_binary(bytes, name)
    }
}

fn read_binary(bytes: &[u8], name: &str) -> Result<PolygonMesh, FormatError> {
    let count = checked_binary_count(bytes, name)?;
    // stl_io takes anything whose first line starts with "solid " for ASCII;
    // the 80-byte header carries no data, so blank it in that case.
    let data: std::borrow::Cow<'_, [u8]> = if bytes.starts_with(b"solid") {
        let mut v = bytes[..84 + 50 * count].to_vec();
        v[..80].fill(0);
        v.into()
    } else {
        bytes[..84 + 50 * count].into()
    };
    let mut cursor = Cursor::new(&data[..]);
    let reader = stl_io::create_stl_reader(&mut cursor)
        .map_err(|e| FormatError::parse(name, Location::Byte(0), e.to_string()))?;
    let mut m = Merger {
        index: HashMap::with_capacity_and_hasher(capped(count), Default::default()),
        vertices: Vec::with_capacity(capped(count)),
        faces: Vec::with_capacity(capped(count)),
    };
    for (i, t) in reader.enumerate() {
        let at = || Location::Element {
            kind: "triangle".to_string(),
            index: i,
        };
        let t = t.map_err(|e| FormatError::parse(name, at(), e.to_string()))?;
        let corners = t.vertices.map(|v| v.0.map(f64::from));
        if let Some(bad) = corners.iter().flatten().find(|c| !c.is_finite()) {
            return Err(FormatError::NonFinite {
                source_name: name.to_string(),
                at: at(),
                value: bad.to_string(),
            });
        }
        m.triangle(corners);
    }
    m.finish(name)
}

/// The triangle count of a binary STL, checked against the file size: the
/// header must be complete, the file exactly `84 + 50 * count` bytes long
/// and the count non-zero.
fn checked_binary_count(bytes: &[u8], name: &str) -> Result<usize, FormatError> {
    let Some(count) = binary_count(bytes) else {
        return Err(FormatError::parse(
            name,
            Location::Byte(bytes.len() as u64),
            format!(
                "truncated binary STL header: {} bytes, 84 needed",
                bytes.len()
            ),
        ));
    };
    let count = count as usize;
    let complete = (bytes.len() - 84) / 50;
    if complete < count {
        return Err(FormatError::CountMismatch {
            source_name: name.to_string(),
            at: Location::Byte(84 + 50 * complete as u64),
            what: "triangles",
            declared: count,
            found: complete,
        });
    }
    let expected = 84 + 50 * count as u64;
    if bytes.len() as u64 != expected {
        // More bytes than the header's count: trailing data or a count that
        // lies (the file is binary, so its size fixes the count).
        let extra = bytes.len() as u64 - expected;
        return Err(FormatError::parse(
            name,
            Location::Byte(expected),
            format!(
                "the header declares {count} triangles ({expected} bytes), but the file has \
                 {} bytes ({extra} more)",
                bytes.len()
            ),
        ));
    }
    if count == 0 {
        return Err(FormatError::Empty {
            source_name: name.to_string(),
        });
    }
    Ok(count)
}

fn read_ascii(bytes: &[u8], name: &str) -> Result<PolygonMesh, FormatError> {
    let src = String::from_utf8_lossy(bytes);
    let total_lines = src.lines().count();
    let mut lines = src
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.split_whitespace().collect::<Vec<_>>()))
        .filter(|(_, t)| !t.is_empty());
    let eof = Location::Line(total_lines + 1);
    let err = |at: Location, msg: String| FormatError::parse(name, at, msg);

    let mut m = Merger::default();
    let mut in_solid = false;
    loop {
        let Some((no, t)) = lines.next() else {
            if in_solid {
                return Err(err(eof, "end of file before \"endsolid\"".to_string()));
            }
            break;
        };
        let kw = t[0].to_ascii_lowercase();
        if !in_solid {
            if kw != "solid" {
                return Err(err(
                    Location::Line(no),
                    format!("expected \"solid\", found {:?}", t.join(" ")),
                ));
            }
            in_solid = true;
            continue;
        }
        match kw.as_str() {
            "endsolid" => in_solid = false,
            "facet" => m.triangle(read_facet_body(&mut lines, name, &eof)?),
            _ => {
                return Err(err(
                    Location::Line(no),
                    format!(
                        "expected \"facet\" or \"endsolid\", found {:?}",
                        t.join(" ")
                    ),
                ))
            }
        }
    }
    m.finish(name)
}

/// The lines of a facet after its `facet normal ...` line (the normal is
/// ignored): `outer loop`, three `vertex x y z`, `endloop`, `endfacet`.
/// Returns the three corners.
fn read_facet_body<'a>(
    lines: &mut impl Iterator<Item = (usize, Vec<&'a str>)>,
    name: &str,
    eof: &Location,
) -> Result<[[f64; 3]; 3], FormatError> {
    expect_line(lines, "outer loop", name, eof)?;
    let mut corners = [[0.0f64; 3]; 3];
    for corner in &mut corners {
        let Some((no, t)) = lines.next() else {
            return Err(FormatError::parse(
                name,
                eof.clone(),
                "end of file, expected \"vertex x y z\"",
            ));
        };
        *corner = parse_vertex_line(&t, name, no)?;
    }
    expect_line(lines, "endloop", name, eof)?;
    expect_line(lines, "endfacet", name, eof)?;
    Ok(corners)
}

/// One `vertex x y z` line; the coordinates are read as `f32`, as the
/// format stores them, and must be finite.
fn parse_vertex_line(t: &[&str], name: &str, no: usize) -> Result<[f64; 3], FormatError> {
    if t.len() != 4 || !t[0].eq_ignore_ascii_case("vertex") {
        return Err(FormatError::parse(
            name,
            Location::Line(no),
            format!("expected \"vertex x y z\", found {:?}", t.join(" ")),
        ));
    }
    let mut corner = [0.0f64; 3];
    for (c, tok) in corner.iter_mut().zip(&t[1..]) {
        let v = tok.parse::<f32>().map_err(|_| {
            FormatError::parse(
                name,
                Location::Line(no),
                format!("expected a number, found {tok:?}"),
            )
        })?;
        if !v.is_finite() {
            return Err(FormatError::NonFinite {
                source_name: name.to_string(),
                at: Location::Line(no),
                value: tok.to_string(),
            });
        }
        *c = f64::from(v);
    }
    Ok(corner)
}

/// Consumes the next content line, which must be `what` (case insensitive).
fn expect_line<'a>(
    lines: &mut impl Iterator<Item = (usize, Vec<&'a str>)>,
    what: &str,
    name: &str,
    eof: &Location,
) -> Result<(), FormatError> {
    match lines.next() {
        Some((_, t)) if t.join(" ").eq_ignore_ascii_case(what) => Ok(()),
        Some((no, t)) => Err(FormatError::parse(
            name,
            Location::Line(no),
            format!("expected {what:?}, found {:?}", t.join(" ")),
        )),
        None => Err(FormatError::parse(
            name,
            eof.clone(),
            format!("end of file, expected {what:?}"),
        )),
    }
}

/// A triangle for writing: unit normal and corners, in `f32`.
type F32Triangle = ([f32; 3], [[f32; 3]; 3]);

/// The fan triangles of a mesh as `f32` corners with a unit normal.
fn triangles(mesh: &PolygonMesh) -> Result<Vec<F32Triangle>, FormatError> {
    let to_f32 = |v: [f64; 3]| -> Result<[f32; 3], FormatError> {
        let w = v.map(|c| c as f32);
        if w.iter().any(|c| !c.is_finite()) {
            return Err(FormatError::InvalidMesh {
                reason: format!("vertex {v:?} is outside the f32 range STL can store"),
            });
        }
        Ok(w)
    };
    let mut out = Vec::with_capacity(mesh.triangle_count());
    for f in &mesh.faces {
        for k in 1..f.len() - 1 {
            let [a, b, c] = [f[0], f[k], f[k + 1]].map(|i| mesh.vertices[i]);
            let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            let n = [
                u[1] * w[2] - u[2] * w[1],
                u[2] * w[0] - u[0] * w[2],
                u[0] * w[1] - u[1] * w[0],
            ];
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let normal = if len > 0.0 && len.is_finite() {
                n.map(|x| (x / len) as f32)
            } else {
                [0.0; 3]
            };
            out.push((normal, [to_f32(a)?, to_f32(b)?, to_f32(c)?]));
        }
    }
    if u32::try_from(out.len()).is_err() {
        return Err(FormatError::InvalidMesh {
            reason: format!("{} triangles exceed the STL limit of 2^32 - 1", out.len()),
        });
    }
    Ok(out)
}

pub(crate) fn write_binary(mesh: &PolygonMesh) -> Result<Vec<u8>, FormatError> {
    let tris: Vec<stl_io::Triangle> = triangles(mesh)?
        .into_iter()
        .map(|(n, v)| stl_io::Triangle {
            normal: stl_io::Normal::new(n),
            vertices: v.map(stl_io::Vertex::new),
        })
        .collect();
    let mut out = Vec::with_capacity(84 + 50 * tris.len());
    stl_io::write_stl(&mut out, tris.iter()).map_err(|e| FormatError::InvalidMesh {
        reason: format!("STL encoding failed: {e}"),
    })?;
    Ok(out)
}

pub(crate) fn write_ascii(mesh: &PolygonMesh) -> Result<Vec<u8>, FormatError> {
    let tris = triangles(mesh)?;
    let mut out = String::with_capacity(32 + 200 * tris.len());
    out.push_str("solid dymsum\n");
    for (n, v) in &tris {
        let _ = writeln!(out, "  facet normal {} {} {}", n[0], n[1], n[2]);
        out.push_str("    outer loop\n");
        for p in v {
            let _ = writeln!(out, "      vertex {} {} {}", p[0], p[1], p[2]);
        }
        out.push_str("    endloop\n  endfacet\n");
    }
    out.push_str("endsolid dymsum\n");
    Ok(out.into_bytes())
}
