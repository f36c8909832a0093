//! The C-obstacle map container: every slice of every (robot piece,
//! obstacle piece) pair over a list of orientations, in one `.npz` of plain
//! arrays ([`crate::npz`]; loads with `np.load(path, allow_pickle=False)`).
//!
//! Slices are numbered pair-major: slice `s = pair·K + k` is orientation
//! `k` of pair `pair` (`K` orientations; `K − 1` for certified slabs
//! between consecutive orientations, `K` for a closed turn). Arrays:
//!
//! | name | shape | |
//! | --- | --- | --- |
//! | `format` | `()` str | `"dymsum-cobstacle-map"` |
//! | `version` | `()` int64 | `1` |
//! | `form` | `()` str | `"halfspaces"` or `"mesh"` |
//! | `certified` | `()` int64 | `1` for certified slabs, else `0` |
//! | `orientations_xyzw` | `(K, 4)` float64 | unit quaternions, scalar last |
//! | `robot_pieces`, `obstacle_pieces` | `(R,)`, `(O,)` str | piece names |
//! | `pairs` | `(P, 2)` int64 | robot piece, obstacle piece of each pair |
//! | `slices_per_pair` | `()` int64 | `S` slices per pair |
//! | halfspaces: `plane_start` | `(P·S + 1,)` int64 | slice `s` has the planes `plane_start[s]:plane_start[s+1]` |
//! | halfspaces: `normals`, `offsets` | `(N, 3)`, `(N,)` float64 | `{x : n·x ≤ d}`, unit outward normals, offsets rounded outward |
//! | mesh: `vertex_start`, `face_start` | `(P·S + 1,)` int64 | slice `s`'s vertices and faces |
//! | mesh: `vertices` | `(V, 3)` float64 | |
//! | mesh: `corner_start` | `(F + 1,)` int64 | face `f` has the corners `corners[corner_start[f]:corner_start[f+1]]` |
//! | mesh: `corners` | `(C,)` int64 | vertex indices local to the slice, counter-clockwise seen from outside |

use crate::atomic::FileError;
use crate::npz::{write_npz, Array};
use dymsum::query::HalfSpaces;
use dymsum::{DVec3, PolygonMesh, Rotation};
use std::path::Path;

/// The value of the `format` entry.
pub const FORMAT: &str = "dymsum-cobstacle-map";

/// The slices' form.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// Half-spaces `{x : n·x ≤ d}`.
    HalfSpaces,
    /// Convex polygon meshes.
    Mesh,
}

impl Form {
    /// `"halfspaces"` or `"mesh"`.
    pub fn name(self) -> &'static str {
        match self {
            Form::HalfSpaces => "halfspaces",
            Form::Mesh => "mesh",
        }
    }
}

/// A map being filled, slice by slice, pair-major (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct MapBuilder {
    form: Form,
    certified: bool,
    orientations: Vec<Rotation>,
    robot_pieces: Vec<String>,
    obstacle_pieces: Vec<String>,
    pairs: Vec<[i64; 2]>,
    slices_per_pair: usize,
    /// `plane_start` or `vertex_start`.
    start: Vec<i64>,
    normals: Vec<f64>,
    offsets: Vec<f64>,
    vertices: Vec<f64>,
    face_start: Vec<i64>,
    corner_start: Vec<i64>,
    corners: Vec<i64>,
}

impl MapBuilder {
    /// An empty map of `form` over `orientations`, with `slices_per_pair`
    /// slices per piece pair, pairs of the named pieces added in order by
    /// [`MapBuilder::add_pair`].
    pub fn new(
        form: Form,
        certified: bool,
        orientations: &[Rotation],
        slices_per_pair: usize,
        robot_pieces: Vec<String>,
        obstacle_pieces: Vec<String>,
    ) -> MapBuilder {
        MapBuilder {
            form,
            certified,
            orientations: orientations.to_vec(),
            robot_pieces,
            obstacle_pieces,
            pairs: Vec::new(),
            slices_per_pair,
            start: vec![0],
            normals: Vec::new(),
            offsets: Vec::new(),
            vertices: Vec::new(),
            face_start: vec![0],
            corner_start: vec![0],
            corners: Vec::new(),
        }
    }

    /// The form.
    pub fn form(&self) -> Form {
        self.form
    }

    /// Starts the slices of the pair (robot piece `r`, obstacle piece `o`).
    pub fn add_pair(&mut self, r: usize, o: usize) {
        self.pairs.push([r as i64, o as i64]);
    }

    /// Appends a slice as half-spaces (a half-space map).
    pub fn push_halfspaces(&mut self, h: &HalfSpaces) {
        self.push_planes(h.normals(), h.offsets());
    }

    /// Appends a slice (or a certified slab) as the half-spaces
    /// `{x : n_i·x ≤ d_i}`.
    pub fn push_planes(&mut self, normals: &[DVec3], offsets: &[f64]) {
        debug_assert_eq!(self.form, Form::HalfSpaces);
        debug_assert_eq!(normals.len(), offsets.len());
        self.normals
            .extend(normals.iter().flat_map(|n| n.to_array()));
        self.offsets.extend_from_slice(offsets);
        self.start.push(self.offsets.len() as i64);
    }

    /// Appends a slice as a mesh (a mesh map).
    pub fn push_mesh(&mut self, m: &PolygonMesh) {
        debug_assert_eq!(self.form, Form::Mesh);
        self.vertices.extend(m.vertices.iter().flatten());
        self.start.push((self.vertices.len() / 3) as i64);
        for f in &m.faces {
            self.corners.extend(f.iter().map(|&i| i as i64));
            self.corner_start.push(self.corners.len() as i64);
        }
        self.face_start.push((self.corner_start.len() - 1) as i64);
    }

    /// Slices appended so far.
    pub fn slice_count(&self) -> usize {
        self.start.len() - 1
    }

    /// The arrays of the container (module docs).
    ///
    /// # Panics
    /// If the slices appended are not `slices_per_pair` for each pair.
    pub fn arrays(&self) -> Vec<Array> {
        assert_eq!(
            self.slice_count(),
            self.pairs.len() * self.slices_per_pair,
            "a map needs {} slices for each of its {} pairs",
            self.slices_per_pair,
            self.pairs.len()
        );
        let k = self.orientations.len();
        let mut out = vec![
            Array::str("format", vec![FORMAT.into()]),
            Array::i64("version", vec![], vec![1]),
            Array::str("form", vec![self.form.name().into()]),
            Array::i64("certified", vec![], vec![self.certified as i64]),
            Array::f64(
                "orientations_xyzw",
                vec![k, 4],
                self.orientations.iter().flat_map(|r| r.xyzw()).collect(),
            ),
            Array::str("robot_pieces", self.robot_pieces.clone()),
            Array::str("obstacle_pieces", self.obstacle_pieces.clone()),
            Array::i64(
                "pairs",
                vec![self.pairs.len(), 2],
                self.pairs.iter().flatten().copied().collect(),
            ),
            Array::i64("slices_per_pair", vec![], vec![self.slices_per_pair as i64]),
        ];
        // Scalars for the strings: shape () rather than (1,).
        for a in &mut out[..3] {
            a.shape = vec![];
        }
        let s = self.start.len();
        match self.form {
            Form::HalfSpaces => out.extend([
                Array::i64("plane_start", vec![s], self.start.clone()),
                Array::f64("normals", vec![self.offsets.len(), 3], self.normals.clone()),
                Array::f64("offsets", vec![self.offsets.len()], self.offsets.clone()),
            ]),
            Form::Mesh => out.extend([
                Array::i64("vertex_start", vec![s], self.start.clone()),
                Array::f64(
                    "vertices",
                    vec![self.vertices.len() / 3, 3],
                    self.vertices.clone(),
                ),
                Array::i64("face_start", vec![s], self.face_start.clone()),
                Array::i64(
                    "corner_start",
                    vec![self.corner_start.len()],
                    self.corner_start.clone(),
                ),
                Array::i64("corners", vec![self.corners.len()], self.corners.clone()),
            ]),
        }
        out
    }

    /// Writes the container to `path`, atomically ([`write_npz`]).
    ///
    /// # Errors
    /// Those of [`write_npz`].
    ///
    /// # Panics
    /// As [`MapBuilder::arrays`].
    pub fn write(&self, path: &Path) -> Result<(), FileError> {
        write_npz(path, &self.arrays())
    }
}
