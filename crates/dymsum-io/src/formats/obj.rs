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
                p.vertices.push(v);
                p.vertex_piece.push(current);
            }
            "f" | "fo" => {
                let nv = p.vertices.len();
                let mut face = Vec::new();
                for tok in tokens {
                    let first = tok.split('/').next().unwrap_or("");
                    let raw = first.parse::<i64>().map_err(|_| {
                        FormatError::parse(
                            name,
                            Location::Line(no),
                            format!(
                                "expected a vertex reference like 3, 3/1 or 3//2, found {tok:?}"
                            ),
                        )
                    })?;
                    let bad = || FormatError::BadIndex {
                        source_name: name.to_string(),
                        at: Location::Line(no),
                        index: raw,
                        vertex_count: nv,
                    };
                    let idx = if raw > 0 {
                        // Checked against the final vertex count below
                        // (forward references are tolerated).
                        usize::try_from(raw - 1).map_err(|_| bad())?
                    } else if raw < 0 {
                        // -1 is the most recently defined vertex.
                        let back = raw.unsigned_abs();
                        if back > nv as u64 {
                            return Err(bad());
                        }
                        nv - back as usize
                    } else {
                        return Err(bad());
                    };
                    face.push(idx);
                }
                if face.len() < 3 {
                    return Err(FormatError::DegenerateFace {
                        source_name: name.to_string(),
                        at: Location::Line(no),
                        len: face.len(),
                    });
                }
                p.faces.push(face);
                p.face_piece.push(current);
                face_lines.push(no);
            }
            "o" | "g" => {
                let rest: Vec<&str> = tokens.collect();
                let piece = if rest.is_empty() {
                    "default".to_string()
                } else {
                    rest.join(" ")
                };
                p.pieces.push(piece);
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
    let nv = p.vertices.len();
    for (face, &no) in p.faces.iter().zip(&face_lines) {
        if let Some(&bad) = face.iter().find(|&&i| i >= nv) {
            return Err(FormatError::BadIndex {
                source_name: name.to_string(),
                at: Location::Line(no),
                index: bad as i64 + 1,
                vertex_count: nv,
            });
        }
    }
    Ok(p)
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
    let nv = p.vertices.len();
    // Connected components of the faces through shared vertices.
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
    let mut used = vec![false; nv];
    for f in &p.faces {
        for &v in f {
            used[v] = true;
        }
    }
    // Components in order of their first face.
    let mut component_of_root = vec![usize::MAX; nv];
    let mut components: Vec<(usize, Vec<usize>)> = Vec::new(); // (piece of first face, faces)
    for (fi, f) in p.faces.iter().enumerate() {
        let r = root(&mut parent, f[0]);
        if component_of_root[r] == usize::MAX {
            component_of_root[r] = components.len();
            components.push((p.face_piece[fi], Vec::new()));
        }
        components[component_of_root[r]].1.push(fi);
    }
    let mut remap = vec![usize::MAX; nv];
    let mut out = Vec::new();
    for (piece, face_ids) in components {
        // The body's vertices in file order.
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
        out.push((p.pieces[piece].clone(), PolygonMesh { vertices, faces }));
    }
    // Objects with vertices but no faces: point clouds of their own
    // vertices that no face uses.
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
    for (piece, vertices) in clouds.into_iter().enumerate() {
        if !vertices.is_empty() {
            out.push((
                p.pieces[piece].clone(),
                PolygonMesh {
                    vertices,
                    faces: Vec::new(),
                },
            ));
        }
    }
    Ok(out)
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
