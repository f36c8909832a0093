//! Object File Format (OFF), text only.
//!
//! Reading: `#` starts a comment (to the end of the line), blank lines are
//! skipped. The `OFF` keyword is optional and may stand on its own line or
//! start the counts line (`OFF 8 6 12`). The counts line holds the vertex and
//! face counts and optionally the edge count (ignored). Then one vertex per
//! line (`x y z`) and one face per line (`k i1 .. ik`, 0-based indices,
//! anything after the indices, such as a colour, is ignored). The `ST`, `C`
//! and `N` prefixes (`COFF`, `NOFF`, `STCNOFF`, ...) are accepted and the
//! extra per-vertex values ignored; `4OFF`, `nOFF` and binary OFF are
//! rejected as unsupported.
//!
//! Writing: `OFF`, the counts, then the vertices with every coordinate in
//! shortest round-trip form, then the faces.

use std::fmt::Write;

use dymsum::PolygonMesh;

use super::{
    capped, parse_coord, push_vertices_and_faces, text, vertex_index, FormatError, Location,
};

/// Content lines: 1-based number and text with comments stripped and
/// surrounding whitespace trimmed; blank lines skipped.
fn content_lines(src: &str) -> impl Iterator<Item = (usize, &str)> {
    src.lines().enumerate().filter_map(|(i, l)| {
        let l = match l.find('#') {
            Some(p) => &l[..p],
            None => l,
        };
        let l = l.trim();
        (!l.is_empty()).then_some((i + 1, l))
    })
}

/// What an `*OFF` header keyword says about the vertex lines.
struct Header {
    /// Whether vertex lines may carry extra values (normals, colours, texture
    /// coordinates) after `x y z`.
    extra_vertex_values: bool,
}

/// Recognises an OFF header keyword like `OFF`, `COFF`, `STCNOFF`, `4OFF`.
/// `Ok(None)` if `token` is not a header keyword at all.
fn parse_keyword(token: &str, name: &str, line: usize) -> Result<Option<Header>, FormatError> {
    let Some(prefix) = token.strip_suffix("OFF") else {
        return Ok(None);
    };
    let mut rest = prefix;
    rest = rest.strip_prefix("ST").unwrap_or(rest);
    rest = rest.strip_prefix('C').unwrap_or(rest);
    rest = rest.strip_prefix('N').unwrap_or(rest);
    let dims = rest;
    if dims.is_empty() {
        return Ok(Some(Header {
            extra_vertex_values: !prefix.is_empty(),
        }));
    }
    if dims == "4" || dims == "n" || dims == "4n" {
        return Err(FormatError::unsupported(
            name,
            Location::Line(line),
            format!("{token} (only 3-D OFF is supported)"),
        ));
    }
    Err(FormatError::parse(
        name,
        Location::Line(line),
        format!("unknown OFF header keyword {token:?}"),
    ))
}

fn parse_count(token: &str, what: &str, name: &str, line: usize) -> Result<usize, FormatError> {
    token.parse::<usize>().map_err(|_| {
        FormatError::parse(
            name,
            Location::Line(line),
            format!("expected the number of {what}, found {token:?}"),
        )
    })
}

/// The counts a header declares: vertices and faces (the edge count, when
/// present, is checked to be a number and ignored).
struct Counts {
    vertices: usize,
    faces: usize,
}

pub(crate) fn read(bytes: &[u8], name: &str) -> Result<PolygonMesh, FormatError> {
    let src = text(bytes);
    let eof = Location::Line(src.lines().count() + 1);
    let mut lines = content_lines(&src);
    let (header, counts) = read_header(&mut lines, name, &eof)?;
    let vertices = read_vertices(&mut lines, &header, counts.vertices, name, &eof)?;
    let faces = read_faces(&mut lines, counts.vertices, counts.faces, name, &eof)?;
    if let Some((no, _)) = lines.next() {
        return Err(FormatError::CountMismatch {
            source_name: name.to_string(),
            at: Location::Line(no),
            what: "faces",
            declared: counts.faces,
            found: counts.faces + 1,
        });
    }
    Ok(PolygonMesh { vertices, faces })
}

/// Reads the optional `*OFF` keyword and the counts line (the keyword may
/// stand alone on its line or start the counts line). Rejects binary OFF,
/// malformed counts and a zero vertex count.
fn read_header<'a>(
    lines: &mut impl Iterator<Item = (usize, &'a str)>,
    name: &str,
    eof: &Location,
) -> Result<(Header, Counts), FormatError> {
    let Some((first_no, first)) = lines.next() else {
        return Err(FormatError::Empty {
            source_name: name.to_string(),
        });
    };
    let mut tokens: Vec<&str> = first.split_whitespace().collect();
    let mut header = Header {
        extra_vertex_values: false,
    };
    let mut counts_line = first_no;
    if let Some(h) = parse_keyword(tokens[0], name, first_no)? {
        header = h;
        tokens.remove(0);
        if tokens
            .first()
            .is_some_and(|t| t.eq_ignore_ascii_case("BINARY"))
        {
            return Err(FormatError::unsupported(
                name,
                Location::Line(first_no),
                "binary OFF",
            ));
        }
        if tokens.is_empty() {
            let Some((no, l)) = lines.next() else {
                return Err(FormatError::parse(
                    name,
                    eof.clone(),
                    "missing the counts line after the OFF header",
                ));
            };
            counts_line = no;
            tokens = l.split_whitespace().collect();
        }
    }
    let counts = parse_counts(&tokens, name, counts_line)?;
    Ok((header, counts))
}

/// Parses `vertex_count face_count [edge_count]` from the counts line's
/// tokens; a zero vertex count means the file holds no mesh.
fn parse_counts(tokens: &[&str], name: &str, line: usize) -> Result<Counts, FormatError> {
    if tokens.len() != 2 && tokens.len() != 3 {
        return Err(FormatError::parse(
            name,
            Location::Line(line),
            format!(
                "expected \"vertex_count face_count [edge_count]\", found {:?}",
                tokens.join(" ")
            ),
        ));
    }
    let vertices = parse_count(tokens[0], "vertices", name, line)?;
    let faces = parse_count(tokens[1], "faces", name, line)?;
    if tokens.len() == 3 {
        parse_count(tokens[2], "edges", name, line)?;
    }
    if vertices == 0 {
        return Err(FormatError::Empty {
            source_name: name.to_string(),
        });
    }
    Ok(Counts { vertices, faces })
}

/// Reads `nv` vertex lines `x y z` (extra values allowed only if the header
/// keyword announced them).
fn read_vertices<'a>(
    lines: &mut impl Iterator<Item = (usize, &'a str)>,
    header: &Header,
    nv: usize,
    name: &str,
    eof: &Location,
) -> Result<Vec<[f64; 3]>, FormatError> {
    let mut vertices = Vec::with_capacity(capped(nv));
    while vertices.len() < nv {
        let Some((no, l)) = lines.next() else {
            return Err(FormatError::CountMismatch {
                source_name: name.to_string(),
                at: eof.clone(),
                what: "vertices",
                declared: nv,
                found: vertices.len(),
            });
        };
        let t: Vec<&str> = l.split_whitespace().collect();
        if t.len() < 3 || (t.len() > 3 && !header.extra_vertex_values) {
            return Err(FormatError::parse(
                name,
                Location::Line(no),
                format!(
                    "vertex {} should be 3 coordinates \"x y z\", found {} values \
                     (does the header's vertex count {nv} match the file?)",
                    vertices.len(),
                    t.len()
                ),
            ));
        }
        vertices.push([
            parse_coord(t[0], name, no)?,
            parse_coord(t[1], name, no)?,
            parse_coord(t[2], name, no)?,
        ]);
    }
    Ok(vertices)
}

/// Reads `nf` face lines `k i1 .. ik` with indices below `nv`.
fn read_faces<'a>(
    lines: &mut impl Iterator<Item = (usize, &'a str)>,
    nv: usize,
    nf: usize,
    name: &str,
    eof: &Location,
) -> Result<Vec<Vec<usize>>, FormatError> {
    let mut faces = Vec::with_capacity(capped(nf));
    while faces.len() < nf {
        let Some((no, l)) = lines.next() else {
            return Err(FormatError::CountMismatch {
                source_name: name.to_string(),
                at: eof.clone(),
                what: "faces",
                declared: nf,
                found: faces.len(),
            });
        };
        faces.push(parse_face(l, faces.len(), nv, name, no)?);
    }
    Ok(faces)
}

/// Parses face number `index` from its line `k i1 .. ik [ignored...]`:
/// `k >= 3` indices, each in `0..nv`.
fn parse_face(
    l: &str,
    index: usize,
    nv: usize,
    name: &str,
    no: usize,
) -> Result<Vec<usize>, FormatError> {
    let mut t = l.split_whitespace();
    let k_tok = t.next().unwrap_or("");
    let k = k_tok.parse::<usize>().map_err(|_| {
        FormatError::parse(
            name,
            Location::Line(no),
            format!("face {index}: expected the vertex count, found {k_tok:?}"),
        )
    })?;
    if k < 3 {
        return Err(FormatError::DegenerateFace {
            source_name: name.to_string(),
            at: Location::Line(no),
            len: k,
        });
    }
    let mut face = Vec::with_capacity(k.min(64));
    for j in 0..k {
        let Some(tok) = t.next() else {
            return Err(FormatError::parse(
                name,
                Location::Line(no),
                format!("face {index} declares {k} vertices but lists only {j}"),
            ));
        };
        let idx = tok.parse::<i64>().map_err(|_| {
            FormatError::parse(
                name,
                Location::Line(no),
                format!("expected a vertex index, found {tok:?}"),
            )
        })?;
        face.push(vertex_index(idx, nv, name, Location::Line(no))?);
    }
    // Remaining tokens (e.g. a face colour) are ignored.
    Ok(face)
}

pub(crate) fn write(mesh: &PolygonMesh) -> Vec<u8> {
    let mut out = String::with_capacity(32 + 40 * mesh.vertices.len() + 16 * mesh.faces.len());
    let _ = writeln!(
        out,
        "OFF\n{} {} {}",
        mesh.vertices.len(),
        mesh.faces.len(),
        mesh.edge_count()
    );
    push_vertices_and_faces(&mut out, mesh);
    out.into_bytes()
}
