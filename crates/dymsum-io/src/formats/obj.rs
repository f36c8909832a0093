//! Wavefront OBJ, geometry only.
//!
//! An own parser rather than `tobj`: `tobj` stores positions as `f32` unless
//! built with its `use_f64` feature, reports errors without line numbers, and
//! with `single_index` duplicates positions per texture/normal combination.
//!
//! Reading: `v x y z [w]` (a `w` other than 1 divides the coordinates; extra
//! values such as vertex colours are ignored), `f` faces with `v`, `v/vt`,
//! `v//vn` or `v/vt/vn` entries, 1-based or negative (relative) indices,
//! `o` / `g` to split objects (see [`super::read_obj_objects`]), `\` line
//! continuations and `#` comments. Texture coordinates, normals, materials,
//! smoothing groups, lines, points and unknown statements are ignored;
//! free-form geometry (`cstype`, `curv`, `surf`, ...) is rejected as
//! unsupported.
//!
//! Writing: `v` lines with every coordinate in shortest round-trip form,
//! then `f` lines with 1-based indices.

use std::fmt::Write;

use dymsum::PolygonMesh;

use super::{parse_coord, push_coords, text, FormatError, Location};

/// Everything read from an OBJ file.
struct Parsed {
    vertices: Vec<[f64; 3]>,
    faces: Vec<Vec<usize>>,
    /// For each face, the index of its object/group in `pieces`.
    face_piece: Vec<usize>,
    /// For each vertex, the index of the object/group it was defined in.
    vertex_piece: Vec<usize>,
    /// Object/group names, in order of their `o`/`g` statements.
    pieces: Vec<String>,
}

const FREE_FORM: &[&str] = &[
    "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp",
    "end", "con",
];

/// Logical lines (joined over trailing `\`) with their first line's 1-based
/// number, comments stripped.
fn logical_lines(src: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut pending: Option<(usize, String)> = None;
    for (i, raw) in src.lines().enumerate() {
        let l = match raw.find('#') {
            Some(p) => &raw[..p],
            None => raw,
        };
        let (l, cont) = match l.trim_end().strip_suffix('\\') {
            Some(s) => (s, true),
            None => (l, false),
        };
        let entry = pending.get_or_insert_with(|| (i + 1, String::new()));
        entry.1.push_str(l);
        entry.1.push(' ');
        if !cont {
            out.extend(pending.take());
        }
    }
    out.extend(pending.take());
    out
}

fn parse(bytes: &[u8], name: &str) -> Result<Parsed, FormatError> {
    let src = text(bytes);
    let mut p = Parsed {
        vertices: Vec::new(),
        faces: Vec::new(),
        face_piece: Vec::new(),
        vertex_piece: Vec::new(),
        pieces: vec!["default".to_string()],
    };
    let mut face_lines: Vec<usize> = Vec::new();
    let mut current = 0usize;

    for (no, line) in logical_lines(&src) {
        let mut tokens = line.split_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        match keyword {
            "v" => {
                p.vertices.push(parse_vertex(tokens, name, no)?);
                p.vertex_piece.push(current);
            }
            "f" | "fo" => {
                p.faces
                    .push(parse_face(tokens, p.vertices.len(), name, no)?);
                p.face_piece.push(current);
                face_lines.push(no);
            }
            "o" | "g" => {
                p.pieces.push(piece_name(tokens));
                current = p.pieces.len() - 1;
            }
            k if FREE_FORM.contains(&k) => {
                return Err(FormatError::unsupported(
                    name,
                    Location::Line(no),
                    format!("free-form geometry statement {k:?}"),
                ));
            }
            // vt, vn, vp, s, usemtl, mtllib, l, p, mg, lod, ... and unknown
            // statements carry no polygon geometry.
            _ => {}
        }
    }

    if p.vertices.is_empty() {
        return Err(FormatError::Empty {
            source_name: name.to_string(),
        });
    }
    check_forward_references(&p, &face_lines, name)?;
    Ok(p)
}

/// The values after a `v` keyword: `x y z [w]`, divided by `w` when it is
/// present and not 1 (a zero `w` or a non-finite quotient is an error);
/// further values such as vertex colours are ignored.
fn parse_vertex<'a>(
    tokens: impl Iterator<Item = &'a str>,
    name: &str,
    no: usize,
) -> Result<[f64; 3], FormatError> {
    let vals: Vec<&str> = tokens.collect();
    if vals.len() < 3 {
        return Err(FormatError::parse(
            name,
            Location::Line(no),
            format!("vertex needs 3 coordinates, found {}", vals.len()),
        ));
    }
    let mut v = [
        parse_coord(vals[0], name, no)?,
        parse_coord(vals[1], name, no)?,
        parse_coord(vals[2], name, no)?,
    ];
    if vals.len() == 4 {
        let w = parse_coord(vals[3], name, no)?;
        if w == 0.0 {
            return Err(FormatError::parse(
                name,
                Location::Line(no),
                "vertex weight w is zero",
            ));
        }
        if w != 1.0 {
            for c in &mut v {
                *c /= w;
            }
            if v.iter().any(|c| !c.is_finite()) {
                return Err(FormatError::NonFinite {
                    source_name: name.to_string(),
                    at: Location::Line(no),
                    value: format!("{v:?} after dividing by w = {w}"),
                });
            }
        }
    }
    Ok(v)
}

/// The vertex references after an `f` keyword as 0-based indices, `nv`
/// being the number of vertices defined so far (for negative, relative
/// references). Positive references past `nv` are kept: forward references
/// are checked against the final count by [`check_forward_references`].
fn parse_face<'a>(
    tokens: impl Iterator<Item = &'a str>,
    nv: usize,
    name: &str,
    no: usize,
) -> Result<Vec<usize>, FormatError> {
    let mut face = Vec::new();
    for tok in tokens {
        face.push(parse_vertex_reference(tok, nv, name, no)?);
    }
    if face.len() < 3 {
        return Err(FormatError::DegenerateFace {
            source_name: name.to_string(),
            at: Location::Line(no),
            len: face.len(),
        });
    }
    Ok(face)
}

/// One face entry `v`, `v/vt`, `v//vn` or `v/vt/vn` as a 0-based vertex
/// index: `v > 0` is 1-based, `v < 0` counts back from the `nv` vertices
/// defined so far (-1 is the latest), `v = 0` is invalid.
fn parse_vertex_reference(
    tok: &str,
    nv: usize,
    name: &str,
    no: usize,
) -> Result<usize, FormatError> {
    let first = tok.split('/').next().unwrap_or("");
    let raw = first.parse::<i64>().map_err(|_| {
        FormatError::parse(
            name,
            Location::Line(no),
            format!("expected a vertex reference like 3, 3/1 or 3//2, found {tok:?}"),
        )
    })?;
    let bad = || FormatError::BadIndex {
        source_name: name.to_string(),
        at: Location::Line(no),
        index: raw,
        vertex_count: nv,
    };
    if raw > 0 {
        usize::try_from(raw - 1).map_err(|_| bad())
    } else if raw < 0 {
        let back = raw.unsigned_abs();
        if back > nv as u64 {
            return Err(bad());
        }
        Ok(nv - back as usize)
    } else {
        Err(bad())
    }
}

/// The name after an `o` or `g` keyword (`default` if none).
fn piece_name<'a>(tokens: impl Iterator<Item = &'a str>) -> String {
    let rest: Vec<&str> = tokens.collect();
    if rest.is_empty() {
        "default".to_string()
    } else {
        rest.join(" ")
    }
}

/// Checks every face index against the final vertex count (faces may refer
/// forward to vertices defined later in the file); `face_lines` holds each
/// face's line number.
fn check_forward_references(
    p: &Parsed,
    face_lines: &[usize],
    name: &str,
) -> Result<(), FormatError> {
    let nv = p.vertices.len();
    for (face, &no) in p.faces.iter().zip(face_lines) {
        if let Some(&bad) = face.iter().find(|&&i| i >= nv) {
            return Err(FormatError::BadIndex {
                source_name: name.to_string(),
                at: Location::Line(no),
                index: bad as i64 + 1,
                vertex_count: nv,
            });
        }
    }
    Ok(())
}

pub(crate) fn read(bytes: &[u8], name: &str) -> Result<PolygonMesh, FormatError> {
    let p = parse(bytes, name)?;
    Ok(PolygonMesh {
        vertices: p.vertices,
        faces: p.faces,
    })
}

/// Union-find root with path halving.
fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// The bodies of an OBJ file (see [`super::read_obj_objects`]): faces joined
/// by shared vertices form one body whatever their `o`/`g` statements say;
/// the vertices of an object with no faces (not used by any face) form a
/// point-cloud body.
pub(crate) fn read_objects(
    bytes: &[u8],
    name: &str,
) -> Result<Vec<(String, PolygonMesh)>, FormatError> {
    let p = parse(bytes, name)?;
    if p.faces.is_empty() {
        return Ok(vec![(
            p.pieces[0].clone(),
            PolygonMesh {
                vertices: p.vertices,
                faces: Vec::new(),
            },
        )]);
    }
    let mut remap = vec![usize::MAX; p.vertices.len()];
    let mut out: Vec<(String, PolygonMesh)> = face_components(&p)
        .into_iter()
        .map(|(piece, face_ids)| {
            let body = body_of_faces(&p, &face_ids, &mut remap);
            (p.pieces[piece].clone(), body)
        })
        .collect();
    out.extend(point_clouds(&p));
    Ok(out)
}

/// The connected components of the faces through shared vertices, in order
/// of their first face: for each, the object/group of its first face and
/// its face indices in file order.
fn face_components(p: &Parsed) -> Vec<(usize, Vec<usize>)> {
    let nv = p.vertices.len();
    let mut parent: Vec<usize> = (0..nv).collect();
    for f in &p.faces {
        let a = root(&mut parent, f[0]);
        for &v in &f[1..] {
            let b = root(&mut parent, v);
            if a != b {
                parent[b] = a;
            }
        }
    }
    let mut component_of_root = vec![usize::MAX; nv];
    let mut components: Vec<(usize, Vec<usize>)> = Vec::new();
    for (fi, f) in p.faces.iter().enumerate() {
        let r = root(&mut parent, f[0]);
        if component_of_root[r] == usize::MAX {
            component_of_root[r] = components.len();
            components.push((p.face_piece[fi], Vec::new()));
        }
        components[component_of_root[r]].1.push(fi);
    }
    components
}

/// The mesh of the faces `face_ids`: their vertices in file order,
/// re-indexed from 0. `remap` is scratch space of one entry per vertex.
fn body_of_faces(p: &Parsed, face_ids: &[usize], remap: &mut [usize]) -> PolygonMesh {
    let mut verts: Vec<usize> = face_ids
        .iter()
        .flat_map(|&fi| p.faces[fi].iter().copied())
        .collect();
    verts.sort_unstable();
    verts.dedup();
    for (new, &old) in verts.iter().enumerate() {
        remap[old] = new;
    }
    let vertices = verts.iter().map(|&i| p.vertices[i]).collect();
    let faces = face_ids
        .iter()
        .map(|&fi| p.faces[fi].iter().map(|&i| remap[i]).collect())
        .collect();
    PolygonMesh { vertices, faces }
}

/// Objects with vertices but no faces: point clouds of their own vertices
/// that no face uses, in object order.
fn point_clouds(p: &Parsed) -> Vec<(String, PolygonMesh)> {
    let mut used = vec![false; p.vertices.len()];
    for f in &p.faces {
        for &v in f {
            used[v] = true;
        }
    }
    let mut has_faces = vec![false; p.pieces.len()];
    for &piece in &p.face_piece {
        has_faces[piece] = true;
    }
    let mut clouds: Vec<Vec<[f64; 3]>> = vec![Vec::new(); p.pieces.len()];
    for (i, v) in p.vertices.iter().enumerate() {
        let piece = p.vertex_piece[i];
        if !used[i] && !has_faces[piece] {
            clouds[piece].push(*v);
        }
    }
    clouds
        .into_iter()
        .enumerate()
        .filter(|(_, vertices)| !vertices.is_empty())
        .map(|(piece, vertices)| {
            let mesh = PolygonMesh {
                vertices,
                faces: Vec::new(),
            };
            (p.pieces[piece].clone(), mesh)
        })
        .collect()
}

pub(crate) fn write(mesh: &PolygonMesh) -> Vec<u8> {
    let mut out = String::with_capacity(32 + 40 * mesh.vertices.len() + 16 * mesh.faces.len());
    out.push_str("# written by dymsum\n");
    for v in &mesh.vertices {
        out.push_str("v ");
        push_coords(&mut out, v);
        out.push('\n');
    }
    for f in &mesh.faces {
        out.push('f');
        for i in f {
            let _ = write!(out, " {}", i + 1);
        }
        out.push('\n');
    }
    out.into_bytes()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vertex_references_are_one_based_or_relative() {
        let r = |tok: &str, nv: usize| parse_vertex_reference(tok, nv, "m", 4);
        assert_eq!(r("3", 5).unwrap(), 2);
        assert_eq!(r("3/1", 5).unwrap(), 2);
        assert_eq!(r("3//2", 5).unwrap(), 2);
        assert_eq!(r("3/1/2", 5).unwrap(), 2);
        // Forward references pass here; check_forward_references bounds them.
        assert_eq!(r("7", 5).unwrap(), 6);
        // -1 is the latest vertex, -nv the first.
        assert_eq!(r("-1", 5).unwrap(), 4);
        assert_eq!(r("-5", 5).unwrap(), 0);
        for (tok, raw) in [("-6", -6), ("0", 0)] {
            let e = r(tok, 5).unwrap_err();
            assert!(
                matches!(
                    &e,
                    FormatError::BadIndex { at: Location::Line(4), index, vertex_count: 5, .. }
                        if *index == raw
                ),
                "{tok}: {e:?}"
            );
        }
        assert!(matches!(r("x/1", 5), Err(FormatError::Parse { .. })));
    }
}
