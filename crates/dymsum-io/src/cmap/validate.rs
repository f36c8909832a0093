//! Validating a C-obstacle map whole before use, from a file ([`read_map`])
//! or from arrays ([`Map::from_arrays`]), with one list of checks.
//!
//! A file is opened only if it is a regular file (a FIFO or device is
//! refused before opening, so reading cannot block), and must be an `.npz`
//! archive ([`crate::npz::NpzArchive`]) whose entries are named once each
//! and are the fields of a map of its `form` and nothing else. Each field's
//! `.npy` header is read first, so shapes and dtypes are checked before
//! any data is: the fields' dtypes ([`FIELDS`]: signed integers, float64 or
//! float32, unicode strings) and dimensions; `format` is
//! `"dymsum-cobstacle-map"`, `version` 1, `form` `halfspaces` or `mesh`,
//! `certified` 0 or 1 (half-spaces only); `slices_per_pair` is `K` (`K − 1`
//! or `K` when certified) for `K` orientations; starts arrays have one
//! entry per slice (or face) and one more, begin at 0, never decrease and
//! end at their array's length; `normals` and `offsets` agree. Then the
//! values: finite floats, unit quaternions, pairs of existing pieces each
//! listed once, corners that index their own slice's vertices. Memory is
//! therefore bounded by the arrays the headers describe, and a header that
//! lies about its shape is refused before its data is inflated.

use super::{Form, Map, Slices, FORMAT};
use crate::atomic::{open_regular_file, FileError};
use crate::npz::{shape_text, Array, Data, Dtype, NpyHeader, NpzArchive, NpzError};
use std::collections::{HashMap, HashSet};
use std::io;
use std::path::{Path, PathBuf};

/// The fields of a map: name, NumPy dtype kind (`i` a signed integer, read
/// as int64; `f` float64 or float32, read as float64; `U` unicode) and
/// number of dimensions.
pub const FIELDS: [(&str, char, usize); 17] = [
    ("format", 'U', 0),
    ("version", 'i', 0),
    ("form", 'U', 0),
    ("certified", 'i', 0),
    ("orientations_xyzw", 'f', 2),
    ("robot_pieces", 'U', 1),
    ("obstacle_pieces", 'U', 1),
    ("pairs", 'i', 2),
    ("slices_per_pair", 'i', 0),
    ("plane_start", 'i', 1),
    ("normals", 'f', 2),
    ("offsets", 'f', 1),
    ("vertex_start", 'i', 1),
    ("vertices", 'f', 2),
    ("face_start", 'i', 1),
    ("corner_start", 'i', 1),
    ("corners", 'i', 1),
];

/// The fields every map has, in the order they are checked.
const COMMON: [&str; 9] = [
    "format",
    "version",
    "form",
    "certified",
    "orientations_xyzw",
    "robot_pieces",
    "obstacle_pieces",
    "pairs",
    "slices_per_pair",
];

fn form_fields(form: Form) -> &'static [&'static str] {
    match form {
        Form::HalfSpaces => &["plane_start", "normals", "offsets"],
        Form::Mesh => &[
            "vertex_start",
            "vertices",
            "face_start",
            "corner_start",
            "corners",
        ],
    }
}

/// Why arrays are not a valid map: the field to blame (when one is) and
/// the reason. `Display` is `field 'NAME': REASON`, or the reason alone.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InvalidMap {
    /// The field, `None` when the file is not a map at all.
    pub field: Option<String>,
    /// What is wrong.
    pub reason: String,
}

impl std::fmt::Display for InvalidMap {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.field {
            Some(field) => write!(f, "field '{field}': {}", self.reason),
            None => f.write_str(&self.reason),
        }
    }
}

impl std::error::Error for InvalidMap {}

/// A map file that cannot be read or is not a valid map. `Display` names
/// the path.
#[derive(Debug, thiserror::Error)]
pub enum MapError {
    /// The path names something other than a regular file (refused before
    /// it is opened: it could block forever or never end).
    #[error("{}: not a regular file ({kind}); give a map file", path.display())]
    NotRegular {
        /// The path given.
        path: PathBuf,
        /// What it is instead.
        kind: &'static str,
    },
    /// Opening or reading failed (missing file, permissions, a read error).
    #[error("{}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: io::Error,
    },
    /// The file is not a valid map ("not a dymsum C-obstacle map" when it
    /// is not a map at all).
    #[error("{}: {invalid}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// The field and the reason.
        invalid: InvalidMap,
    },
}

/// A refusal while validating: the map is invalid, or the file could not
/// be read.
enum Fail {
    Invalid(InvalidMap),
    Io(io::Error),
}

fn invalid(field: Option<&str>, reason: impl Into<String>) -> Fail {
    Fail::Invalid(InvalidMap {
        field: field.map(str::to_string),
        reason: reason.into(),
    })
}

fn not_a_map(why: impl std::fmt::Display) -> Fail {
    invalid(None, format!("not a dymsum C-obstacle map ({why})"))
}

impl From<NpzError> for Fail {
    fn from(e: NpzError) -> Fail {
        match e {
            NpzError::NotAnArchive(why) => not_a_map(format!("not a NumPy .npz archive: {why}")),
            NpzError::Entry { entry, reason } => invalid(Some(&entry), reason),
            NpzError::Io(e) => Fail::Io(e),
        }
    }
}

/// Where the arrays come from: an archive or memory.
trait Source {
    /// The entries' names (`x.npy` for the array `x`), in order, each with
    /// what makes it unreadable (encryption, a compression method), if
    /// anything.
    fn entries(&self) -> Vec<(String, Option<String>)>;
    /// The header of `field`, present once.
    fn header(&mut self, field: &str) -> Result<NpyHeader, Fail>;
    /// The values of `field` (called at most once per field).
    fn values(&mut self, field: &str, header: &NpyHeader) -> Result<Data, Fail>;
}

struct ArchiveSource<R> {
    npz: NpzArchive<R>,
    index: HashMap<String, usize>,
}

impl<R: io::Read + io::Seek> Source for ArchiveSource<R> {
    fn entries(&self) -> Vec<(String, Option<String>)> {
        self.npz
            .entries()
            .iter()
            .map(|e| {
                let problem = if e.encrypted {
                    Some("the entry is encrypted".to_string())
                } else if e.method != 0 && e.method != 8 {
                    Some(format!("unsupported compression method {}", e.method))
                } else {
                    None
                };
                (e.name.clone(), problem)
            })
            .collect()
    }

    fn header(&mut self, field: &str) -> Result<NpyHeader, Fail> {
        Ok(self.npz.header(self.index[field])?)
    }

    fn values(&mut self, field: &str, header: &NpyHeader) -> Result<Data, Fail> {
        Ok(self.npz.values(self.index[field], header)?)
    }
}

struct MemorySource {
    arrays: Vec<Array>,
}

impl MemorySource {
    fn array(&mut self, field: &str) -> &mut Array {
        self.arrays
            .iter_mut()
            .find(|a| a.name == field)
            .expect("a field present")
    }
}

impl Source for MemorySource {
    fn entries(&self) -> Vec<(String, Option<String>)> {
        self.arrays
            .iter()
            .map(|a| (format!("{}.npy", a.name), None))
            .collect()
    }

    fn header(&mut self, field: &str) -> Result<NpyHeader, Fail> {
        let a = self.array(field);
        Ok(NpyHeader {
            dtype: Dtype::of(&a.data),
            shape: a.shape.iter().map(|&d| d as u64).collect(),
            fortran_order: false,
            data_offset: 0,
        })
    }

    fn values(&mut self, field: &str, header: &NpyHeader) -> Result<Data, Fail> {
        let a = self.array(field);
        let data = std::mem::replace(&mut a.data, Data::I64(Vec::new()));
        let len = match &data {
            Data::F64(v) => v.len(),
            Data::I64(v) => v.len(),
            Data::Str(v) => v.len(),
        };
        if Some(len as u64) != header.count() {
            return Err(invalid(
                Some(field),
                format!(
                    "{len} values where its shape {} needs {}",
                    shape_text(&header.shape),
                    header.count().map_or("more".into(), |n| n.to_string())
                ),
            ));
        }
        Ok(data)
    }
}

/// The checks, over a source (module docs).
struct Check<'s> {
    src: &'s mut dyn Source,
    present: HashSet<String>,
    headers: HashMap<&'static str, NpyHeader>,
}

impl Check<'_> {
    /// The header of `field`, its dtype kind and dimensions checked.
    fn header(&mut self, field: &'static str) -> Result<NpyHeader, Fail> {
        if let Some(h) = self.headers.get(field) {
            return Ok(h.clone());
        }
        if !self.present.contains(field) {
            return Err(invalid(Some(field), "missing"));
        }
        let h = self.src.header(field)?;
        let &(_, kind, ndim) = FIELDS
            .iter()
            .find(|f| f.0 == field)
            .expect("a field of a map");
        let dt = &h.dtype;
        let ok = match kind {
            'f' => dt.kind == 'f' && matches!(dt.itemsize, 4 | 8),
            k => dt.kind == k,
        };
        if !ok {
            let want = match kind {
                'i' => "a signed integer (int64)",
                'f' => "float64",
                _ => "a unicode string",
            };
            return Err(invalid(
                Some(field),
                format!("dtype {} where {want} is expected", dt.descr()),
            ));
        }
        if h.shape.len() != ndim {
            return Err(invalid(
                Some(field),
                format!(
                    "shape {}: expected {ndim} dimension{}",
                    shape_text(&h.shape),
                    if ndim == 1 { "" } else { "s" }
                ),
            ));
        }
        self.headers.insert(field, h.clone());
        Ok(h)
    }

    fn values(&mut self, field: &'static str) -> Result<Data, Fail> {
        let h = self.header(field)?;
        self.src.values(field, &h)
    }

    fn ints(&mut self, field: &'static str) -> Result<Vec<i64>, Fail> {
        match self.values(field)? {
            Data::I64(v) => Ok(v),
            _ => Err(invalid(Some(field), "not integers")),
        }
    }

    fn strings(&mut self, field: &'static str) -> Result<Vec<String>, Fail> {
        match self.values(field)? {
            Data::Str(v) => Ok(v),
            _ => Err(invalid(Some(field), "not strings")),
        }
    }

    fn scalar_int(&mut self, field: &'static str) -> Result<i64, Fail> {
        Ok(self.ints(field)?[0])
    }

    fn scalar_str(&mut self, field: &'static str) -> Result<String, Fail> {
        Ok(self.strings(field)?.swap_remove(0))
    }

    /// The values of a float field, every one finite.
    fn finite(&mut self, field: &'static str) -> Result<Vec<f64>, Fail> {
        let shape = self.header(field)?.shape;
        let Data::F64(v) = self.values(field)? else {
            return Err(invalid(Some(field), "not floats"));
        };
        if let Some(at) = v.iter().position(|x| !x.is_finite()) {
            // The index as a tuple, row-major.
            let mut index = vec![0u64; shape.len()];
            let mut rest = at as u64;
            for (k, &d) in shape.iter().enumerate().rev() {
                index[k] = rest % d.max(1);
                rest /= d.max(1);
            }
            return Err(invalid(
                Some(field),
                format!(
                    "holds a value that is not finite ({} at {})",
                    v[at],
                    shape_text(&index)
                ),
            ));
        }
        Ok(v)
    }

    /// A starts array: `length` entries, first 0, non-decreasing, last
    /// `end` (when known).
    fn starts(
        &mut self,
        field: &'static str,
        length: i128,
        end: Option<u64>,
        what: &str,
    ) -> Result<Vec<i64>, Fail> {
        let shape = self.header(field)?.shape;
        if shape.len() != 1 || i128::from(shape[0]) != length {
            return Err(invalid(
                Some(field),
                format!(
                    "shape {}: expected ({length},) ({what} + 1)",
                    shape_text(&shape)
                ),
            ));
        }
        let a = self.ints(field)?;
        if a[0] != 0 {
            return Err(invalid(Some(field), format!("starts at {}, not 0", a[0])));
        }
        if let Some(k) = a.windows(2).position(|w| w[1] < w[0]) {
            return Err(invalid(
                Some(field),
                format!(
                    "decreases at entry {} ({} after {}): starts must be non-decreasing",
                    k + 1,
                    a[k + 1],
                    a[k]
                ),
            ));
        }
        let last = a[a.len() - 1];
        if let Some(end) = end.filter(|&e| i128::from(e) != i128::from(last)) {
            return Err(invalid(
                Some(field),
                format!("ends at {last}, but {end} entries are there"),
            ));
        }
        Ok(a)
    }

    /// The whole validation (module docs).
    fn run(mut self) -> Result<Map, Fail> {
        let entries = self.src.entries();
        if !entries.iter().any(|(n, _)| n == "format.npy") {
            return Err(not_a_map("no 'format' entry"));
        }
        let mut seen = HashSet::new();
        for (n, _) in &entries {
            if !seen.insert(n.as_str()) {
                let field = n.strip_suffix(".npy").unwrap_or(n);
                return Err(invalid(
                    Some(field),
                    format!("the archive holds the entry '{n}' twice"),
                ));
            }
        }
        for (n, problem) in &entries {
            let field = n
                .strip_suffix(".npy")
                .filter(|f| FIELDS.iter().any(|k| k.0 == *f));
            let Some(field) = field else {
                return Err(invalid(
                    None,
                    format!("unexpected entry '{n}' (not a field of a map)"),
                ));
            };
            if let Some(p) = problem {
                return Err(invalid(Some(field), p.clone()));
            }
            self.present.insert(field.to_string());
        }

        if self.scalar_str("format")? != FORMAT {
            return Err(not_a_map(format!("its format is not '{FORMAT}'")));
        }
        let version = self.scalar_int("version")?;
        if version != 1 {
            return Err(invalid(
                Some("version"),
                format!("version {version} is not supported (this dymsum reads version 1)"),
            ));
        }
        let form = match self.scalar_str("form")?.as_str() {
            "halfspaces" => Form::HalfSpaces,
            "mesh" => Form::Mesh,
            other => {
                return Err(invalid(
                    Some("form"),
                    format!("'{other}': expected 'halfspaces' or 'mesh'"),
                ))
            }
        };
        let wanted: Vec<&'static str> = COMMON.iter().chain(form_fields(form)).copied().collect();
        let mut extra: Vec<&String> = self
            .present
            .iter()
            .filter(|f| !wanted.contains(&f.as_str()))
            .collect();
        extra.sort();
        if let Some(field) = extra.first() {
            return Err(invalid(
                Some(field.as_str()),
                format!("not a field of a {} map", form.name()),
            ));
        }
        for &field in &wanted {
            self.header(field)?;
        }
        let certified = self.scalar_int("certified")?;
        if certified != 0 && certified != 1 {
            return Err(invalid(
                Some("certified"),
                format!("{certified}: expected 0 or 1"),
            ));
        }
        let certified = certified == 1;
        if certified && form != Form::HalfSpaces {
            return Err(invalid(
                Some("certified"),
                "certified slabs come as half-spaces only, not in a mesh map",
            ));
        }
        let per = self.scalar_int("slices_per_pair")?;
        let quats_shape = self.header("orientations_xyzw")?.shape;
        let k = i128::from(quats_shape[0]);
        if quats_shape[1] != 4 {
            return Err(invalid(
                Some("orientations_xyzw"),
                format!("shape {}: expected (K, 4)", shape_text(&quats_shape)),
            ));
        }
        let per_ok = if certified {
            i128::from(per) == k - 1 || i128::from(per) == k
        } else {
            i128::from(per) == k
        };
        if !per_ok || per < 0 {
            let expected = if certified {
                format!("{} or {k}", k - 1)
            } else {
                k.to_string()
            };
            return Err(invalid(
                Some("slices_per_pair"),
                format!("{per} with {k} orientations (expected {expected})"),
            ));
        }
        let quats: Vec<[f64; 4]> = self
            .finite("orientations_xyzw")?
            .chunks_exact(4)
            .map(|q| [q[0], q[1], q[2], q[3]])
            .collect();
        let norms = quats
            .iter()
            .map(|q| q.iter().map(|x| x * x).sum::<f64>().sqrt());
        // Finite values, so a norm is a number (an overflow is infinite).
        if let Some((i, norm)) = norms.enumerate().find(|(_, n)| (n - 1.0).abs() > 1e-6) {
            return Err(invalid(
                Some("orientations_xyzw"),
                format!("not unit quaternions (row {i} has norm {norm})"),
            ));
        }
        let robot = self.strings("robot_pieces")?;
        let obstacle = self.strings("obstacle_pieces")?;
        let pairs_shape = self.header("pairs")?.shape;
        if pairs_shape[1] != 2 {
            return Err(invalid(
                Some("pairs"),
                format!("shape {}: expected (P, 2)", shape_text(&pairs_shape)),
            ));
        }
        let pairs: Vec<[i64; 2]> = self
            .ints("pairs")?
            .chunks_exact(2)
            .map(|p| [p[0], p[1]])
            .collect();
        let in_range = |i: i64, n: usize| usize::try_from(i).is_ok_and(|i| i < n);
        if pairs
            .iter()
            .any(|p| !in_range(p[0], robot.len()) || !in_range(p[1], obstacle.len()))
        {
            return Err(invalid(
                Some("pairs"),
                format!(
                    "a piece index out of range ({} robot, {} obstacle pieces)",
                    robot.len(),
                    obstacle.len()
                ),
            ));
        }
        if pairs.iter().collect::<HashSet<_>>().len() != pairs.len() {
            return Err(invalid(Some("pairs"), "a piece pair is listed twice"));
        }
        let slices = pairs.len() as i128 * i128::from(per);
        let rows = |v: Vec<f64>| -> Vec<[f64; 3]> {
            v.chunks_exact(3).map(|r| [r[0], r[1], r[2]]).collect()
        };
        let slices = match form {
            Form::HalfSpaces => {
                let n_shape = self.header("normals")?.shape;
                if n_shape[1] != 3 {
                    return Err(invalid(
                        Some("normals"),
                        format!("shape {}: expected (N, 3)", shape_text(&n_shape)),
                    ));
                }
                let d_shape = self.header("offsets")?.shape;
                if d_shape != [n_shape[0]] {
                    return Err(invalid(
                        Some("offsets"),
                        format!(
                            "shape {}, but normals has {} rows",
                            shape_text(&d_shape),
                            n_shape[0]
                        ),
                    ));
                }
                let plane_start =
                    self.starts("plane_start", slices + 1, Some(n_shape[0]), "slices")?;
                Slices::HalfSpaces {
                    plane_start,
                    normals: rows(self.finite("normals")?),
                    offsets: self.finite("offsets")?,
                }
            }
            Form::Mesh => {
                let v_shape = self.header("vertices")?.shape;
                if v_shape[1] != 3 {
                    return Err(invalid(
                        Some("vertices"),
                        format!("shape {}: expected (V, 3)", shape_text(&v_shape)),
                    ));
                }
                let c_len = self.header("corners")?.shape[0];
                let vs = self.starts("vertex_start", slices + 1, Some(v_shape[0]), "slices")?;
                let fs = self.starts("face_start", slices + 1, None, "slices")?;
                let faces = i128::from(fs[fs.len() - 1]);
                let cs = self.starts("corner_start", faces + 1, Some(c_len), "faces")?;
                let corners = self.ints("corners")?;
                // Each corner indexes a vertex of its own slice.
                for s in 0..fs.len() - 1 {
                    let nv = vs[s + 1] - vs[s];
                    let (first, end) =
                        (cs[fs[s] as usize] as usize, cs[fs[s + 1] as usize] as usize);
                    if let Some(c) = (first..end).find(|&c| !(0..nv).contains(&corners[c])) {
                        return Err(invalid(
                            Some("corners"),
                            format!(
                                "corner {c} indexes vertex {} of a slice of {nv} vertices",
                                corners[c]
                            ),
                        ));
                    }
                }
                Slices::Mesh {
                    vertex_start: vs,
                    vertices: rows(self.finite("vertices")?),
                    face_start: fs,
                    corner_start: cs,
                    corners,
                }
            }
        };
        Ok(Map {
            certified,
            orientations_xyzw: quats,
            robot_pieces: robot,
            obstacle_pieces: obstacle,
            pairs,
            slices_per_pair: per as usize,
            slices,
        })
    }
}

fn check(src: &mut dyn Source) -> Result<Map, Fail> {
    Check {
        src,
        present: HashSet::new(),
        headers: HashMap::new(),
    }
    .run()
}

impl Map {
    /// The map of `arrays` (named as the container's fields, module
    /// docs), validated as [`read_map`] validates a file; integers and
    /// strings are taken as they are, floats as float64.
    ///
    /// ```
    /// use dymsum_io::cmap::{Form, Map, MapBuilder};
    /// use dymsum::Rotation;
    /// let mut b = MapBuilder::new(Form::Mesh, false, &[Rotation::IDENTITY], 1, vec!["r".into()], vec!["o".into()]);
    /// b.add_pair(0, 0);
    /// b.push_mesh(&dymsum::PolygonMesh { vertices: vec![[0.0; 3]; 3], faces: vec![vec![0, 1, 2]] });
    /// let mut arrays = b.arrays();
    /// assert_eq!(Map::from_arrays(arrays.clone())?.form(), Form::Mesh);
    /// let corners = arrays.iter_mut().find(|a| a.name == "corners").unwrap();
    /// corners.data = dymsum_io::npz::Data::I64(vec![0, 1, 3]);
    /// let err = Map::from_arrays(arrays).unwrap_err();
    /// assert_eq!(err.to_string(), "field 'corners': corner 2 indexes vertex 3 of a slice of 3 vertices");
    /// # Ok::<(), dymsum_io::cmap::InvalidMap>(())
    /// ```
    ///
    /// # Errors
    /// [`InvalidMap`] naming the field and what is wrong with it.
    pub fn from_arrays(arrays: Vec<Array>) -> Result<Map, InvalidMap> {
        match check(&mut MemorySource { arrays }) {
            Ok(map) => Ok(map),
            Err(Fail::Invalid(e)) => Err(e),
            // Memory is never read through the file system.
            Err(Fail::Io(e)) => Err(InvalidMap {
                field: None,
                reason: e.to_string(),
            }),
        }
    }
}

/// Reads the map container at `path` (written by [`MapBuilder`],
/// [`Map::write`], `dymsum cobst --format npz|npz-mesh` or Python's
/// `CObstacleMap.save`), validated whole before use with bounded memory
/// (module docs).
///
/// # Errors
/// [`MapError::NotRegular`] for a FIFO, device or directory (refused before
/// it is opened), [`MapError::Read`] when the file cannot be opened or
/// read, [`MapError::Invalid`] naming the field (or saying "not a dymsum
/// C-obstacle map") for a file that is not a valid map.
///
/// [`MapBuilder`]: super::MapBuilder
pub fn read_map(path: &Path) -> Result<Map, MapError> {
    let file = open_regular_file(path).map_err(|e| match e {
        FileError::NotRegular { kind, .. } => MapError::NotRegular {
            path: path.to_path_buf(),
            kind,
        },
        FileError::Read { source, .. } | FileError::Write { source, .. } => MapError::Read {
            path: path.to_path_buf(),
            source,
        },
    })?;
    let fail = |f: Fail| match f {
        Fail::Invalid(invalid) => MapError::Invalid {
            path: path.to_path_buf(),
            invalid,
        },
        Fail::Io(source) => MapError::Read {
            path: path.to_path_buf(),
            source,
        },
    };
    let npz = NpzArchive::new(io::BufReader::new(file)).map_err(|e| fail(e.into()))?;
    let index = npz
        .entries()
        .iter()
        .enumerate()
        .map(|(i, e)| (e.array_name().to_string(), i))
        .collect();
    check(&mut ArchiveSource { npz, index }).map_err(fail)
}

#[cfg(test)]
mod tests {
    use super::super::MapBuilder;
    use super::*;
    use crate::npz::write_npz_to;
    use dymsum::{DVec3, PolygonMesh, Rotation};

    fn halfspace_map() -> MapBuilder {
        let turn = [Rotation::IDENTITY; 3];
        let mut b = MapBuilder::new(
            Form::HalfSpaces,
            false,
            &turn,
            3,
            vec!["r0".into(), "r1".into()],
            vec!["o0".into()],
        );
        for r in 0..2 {
            b.add_pair(r, 0);
            for k in 0..3 {
                b.push_planes(&[DVec3::X, DVec3::Y][..k.min(2)], &[1.0, 2.0][..k.min(2)]);
            }
        }
        b
    }

    fn mesh_map() -> MapBuilder {
        let mut b = MapBuilder::new(
            Form::Mesh,
            false,
            &[Rotation::IDENTITY; 2],
            2,
            vec!["r0".into()],
            vec!["o0".into()],
        );
        b.add_pair(0, 0);
        let tri = PolygonMesh {
            vertices: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            faces: vec![vec![0, 1, 2], vec![2, 1, 0]],
        };
        b.push_mesh(&tri);
        b.push_mesh(&tri);
        b
    }

    /// The map's arrays with `field` replaced (or removed, `None`).
    fn with(b: &MapBuilder, field: &str, data: Option<Array>) -> Vec<Array> {
        let mut a: Vec<Array> = b.arrays().into_iter().filter(|a| a.name != field).collect();
        a.extend(data);
        a
    }

    fn refused(arrays: Vec<Array>) -> String {
        Map::from_arrays(arrays).unwrap_err().to_string()
    }

    #[test]
    fn valid_maps_of_both_forms_pass_and_read_back_equal() {
        let dir = std::env::temp_dir().join(format!("dymsum-cmap-valid-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for b in [halfspace_map(), mesh_map()] {
            let map = Map::from_arrays(b.arrays()).unwrap();
            assert_eq!(map, b.clone().finish());
            let path = dir.join("map.npz");
            b.write(&path).unwrap();
            assert_eq!(read_map(&path).unwrap(), map);
            assert_eq!(map.arrays(), b.arrays());
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn every_check_names_its_field() {
        let h = halfspace_map();
        let m = mesh_map();
        let reversed = Array::i64("plane_start", vec![7], vec![0, 2, 1, 0, 1, 2, 2]);
        for (arrays, needles) in [
            (
                with(&h, "plane_start", Some(reversed)),
                &["'plane_start'", "non-decreasing"][..],
            ),
            (
                with(
                    &h,
                    "offsets",
                    Some(Array::f64("offsets", vec![1], vec![1.0])),
                ),
                &["'offsets'", "normals has 6 rows"],
            ),
            (with(&h, "offsets", None), &["'offsets'", "missing"]),
            (
                with(&h, "normals", Some(Array::str("normals", vec!["x".into()]))),
                &["'normals'", "dtype <U1 where float64"],
            ),
            (
                with(&h, "version", Some(Array::i64("version", vec![], vec![99]))),
                &["'version'", "version 99", "version 1"],
            ),
            (
                with(
                    &h,
                    "form",
                    Some(Array {
                        shape: vec![],
                        ..Array::str("form", vec!["voxels".into()])
                    }),
                ),
                &["'form'", "voxels"],
            ),
            (
                with(
                    &h,
                    "certified",
                    Some(Array::i64("certified", vec![], vec![2])),
                ),
                &["'certified'", "0 or 1"],
            ),
            (
                with(
                    &h,
                    "slices_per_pair",
                    Some(Array::i64("slices_per_pair", vec![], vec![2])),
                ),
                &["'slices_per_pair'", "expected 3"],
            ),
            (
                with(
                    &h,
                    "pairs",
                    Some(Array::i64("pairs", vec![2, 2], vec![0, 0, 7, 0])),
                ),
                &["'pairs'", "out of range"],
            ),
            (
                with(
                    &h,
                    "pairs",
                    Some(Array::i64("pairs", vec![2, 2], vec![0, 0, 0, 0])),
                ),
                &["'pairs'", "twice"],
            ),
            (
                with(
                    &h,
                    "orientations_xyzw",
                    Some(Array::f64(
                        "orientations_xyzw",
                        vec![3, 4],
                        [0.0, 0.0, 0.0, 2.0].repeat(3),
                    )),
                ),
                &["'orientations_xyzw'", "unit"],
            ),
            (
                with(
                    &h,
                    "normals",
                    Some(Array::f64(
                        "normals",
                        vec![6, 3],
                        [1.0, f64::NAN, 0.0].repeat(6),
                    )),
                ),
                &["'normals'", "not finite (NaN at (0, 1))"],
            ),
            (
                with(
                    &h,
                    "robot_pieces",
                    Some(Array::f64("robot_pieces", vec![1], vec![1.0])),
                ),
                &["'robot_pieces'", "dtype <f8"],
            ),
            (
                with(
                    &h,
                    "format",
                    Some(Array {
                        shape: vec![],
                        ..Array::str("format", vec!["other".into()])
                    }),
                ),
                &["not a dymsum C-obstacle map"],
            ),
            (
                with(&h, "format", None),
                &["not a dymsum C-obstacle map (no 'format' entry)"],
            ),
            (
                with(
                    &h,
                    "vertices",
                    Some(Array::f64("vertices", vec![0, 3], vec![])),
                ),
                &["'vertices'", "not a field of a halfspaces map"],
            ),
            (
                with(&h, "x", Some(Array::i64("x", vec![], vec![1]))),
                &["unexpected entry 'x.npy'"],
            ),
            (
                with(
                    &m,
                    "corners",
                    Some(Array::i64(
                        "corners",
                        vec![12],
                        [0, 1, 2, 2, 1, 0, 0, 1, 2, 2, 1, 1_000_000].to_vec(),
                    )),
                ),
                &[
                    "'corners'",
                    "corner 11 indexes vertex 1000000 of a slice of 3 vertices",
                ],
            ),
            (
                with(
                    &m,
                    "face_start",
                    Some(Array::i64("face_start", vec![3], vec![1, 2, 4])),
                ),
                &["'face_start'", "not 0"],
            ),
            (
                with(
                    &m,
                    "vertex_start",
                    Some(Array::i64("vertex_start", vec![3], vec![0, 3, 5])),
                ),
                &["'vertex_start'", "ends at 5, but 6"],
            ),
            (
                with(
                    &m,
                    "certified",
                    Some(Array::i64("certified", vec![], vec![1])),
                ),
                &["'certified'", "half-spaces only"],
            ),
            (
                with(
                    &m,
                    "corners",
                    Some(Array::i64("corners", vec![2, 3], vec![0; 6])),
                ),
                &["'corners'", "expected 1 dimension"],
            ),
        ] {
            let e = refused(arrays);
            for n in needles {
                assert!(e.contains(n), "{e} lacks {n}");
            }
        }
    }

    #[test]
    fn files_that_are_not_maps_say_so_and_name_the_path() {
        let dir = std::env::temp_dir().join(format!("dymsum-cmap-not-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let text = dir.join("notes.npz");
        std::fs::write(&text, "just some text\n".repeat(50)).unwrap();
        let other = dir.join("other.npz");
        let mut bytes = Vec::new();
        write_npz_to(&mut bytes, &[Array::i64("x", vec![3], vec![0, 1, 2])]).unwrap();
        std::fs::write(&other, bytes).unwrap();
        for p in [&text, &other] {
            let e = read_map(p).unwrap_err();
            assert!(matches!(e, MapError::Invalid { .. }), "{e}");
            let e = e.to_string();
            assert!(
                e.contains("not a dymsum C-obstacle map") && e.contains(&*p.to_string_lossy()),
                "{e}"
            );
        }
        let e = read_map(&dir).unwrap_err().to_string();
        assert!(
            e.contains("not a regular file (a directory); give a map file"),
            "{e}"
        );
        let missing = read_map(&dir.join("nothing.npz")).unwrap_err();
        assert!(
            matches!(&missing, MapError::Read { source, .. } if source.kind() == io::ErrorKind::NotFound)
        );
        // Every cut of a valid map is refused as invalid, never a panic.
        let path = dir.join("map.npz");
        halfspace_map().write(&path).unwrap();
        let whole = std::fs::read(&path).unwrap();
        for cut in (0..whole.len()).step_by(7) {
            std::fs::write(&path, &whole[..cut]).unwrap();
            assert!(
                matches!(read_map(&path), Err(MapError::Invalid { .. })),
                "cut {cut}"
            );
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
