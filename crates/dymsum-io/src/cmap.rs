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
//!
//! [`MapBuilder`] fills a map slice by slice; [`read_map`] reads one back,
//! validated whole with bounded memory, and [`Map::from_arrays`] validates
//! arrays from elsewhere (a Python `CObstacleMap` being saved) the same way.
//!
//! ```
//! use dymsum_io::cmap::{read_map, Form, MapBuilder, Slices};
//! use dymsum::{DVec3, Rotation};
//! let dir = std::env::temp_dir().join(format!("dymsum-cmap-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir)?;
//! let turn = [Rotation::IDENTITY, Rotation::IDENTITY];
//! let mut map = MapBuilder::new(Form::HalfSpaces, false, &turn, 2, vec!["r0".into()], vec!["o0".into()]);
//! map.add_pair(0, 0);
//! for _ in 0..2 {
//!     map.push_planes(&[DVec3::X, DVec3::NEG_X], &[1.0, 1.0]);
//! }
//! map.write(&dir.join("map.npz"))?;
//! let back = read_map(&dir.join("map.npz"))?;
//! assert_eq!((back.form(), back.slices_per_pair(), back.pairs()), (Form::HalfSpaces, 2, &[[0, 0]][..]));
//! let Slices::HalfSpaces { plane_start, .. } = back.slices() else { unreachable!() };
//! assert_eq!(plane_start, &[0, 2, 4]);
//! std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::atomic::FileError;
use crate::npz::{write_npz, Array};
use dymsum::query::HalfSpaces;
use dymsum::{DVec3, PolygonMesh, Rotation};
use std::path::Path;

mod validate;

pub use validate::{read_map, InvalidMap, MapError, FIELDS};

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

/// The slices of a map, all pairs' one after the other (slice `s =
/// pair·S + k`), in its form (module docs).
#[derive(Clone, Debug, PartialEq)]
pub enum Slices {
    /// Slice `s` is `{x : normals[i]·x ≤ offsets[i]}` for `i` in
    /// `plane_start[s]..plane_start[s + 1]`.
    HalfSpaces {
        /// Where each slice's planes start, and the plane count last.
        plane_start: Vec<i64>,
        /// The planes' unit outward normals.
        normals: Vec<[f64; 3]>,
        /// The planes' offsets.
        offsets: Vec<f64>,
    },
    /// Slice `s` has the vertices `vertex_start[s]..vertex_start[s + 1]`
    /// and the faces `face_start[s]..face_start[s + 1]`; face `f` the
    /// corners `corners[corner_start[f]..corner_start[f + 1]]`, indices
    /// into its slice's vertices.
    Mesh {
        /// Where each slice's vertices start, and the vertex count last.
        vertex_start: Vec<i64>,
        /// The vertices.
        vertices: Vec<[f64; 3]>,
        /// Where each slice's faces start, and the face count last.
        face_start: Vec<i64>,
        /// Where each face's corners start, and the corner count last.
        corner_start: Vec<i64>,
        /// The faces' corners, counter-clockwise seen from outside.
        corners: Vec<i64>,
    },
}

/// A C-obstacle map: the container's arrays, as [`read_map`] and
/// [`Map::from_arrays`] give them (validated) and [`MapBuilder`] fills
/// them.
#[derive(Clone, Debug, PartialEq)]
pub struct Map {
    certified: bool,
    orientations_xyzw: Vec<[f64; 4]>,
    robot_pieces: Vec<String>,
    obstacle_pieces: Vec<String>,
    pairs: Vec<[i64; 2]>,
    slices_per_pair: usize,
    slices: Slices,
}

impl Map {
    /// The slices' form.
    pub fn form(&self) -> Form {
        match self.slices {
            Slices::HalfSpaces { .. } => Form::HalfSpaces,
            Slices::Mesh { .. } => Form::Mesh,
        }
    }

    /// Whether the slices are certified slabs (between consecutive
    /// orientations).
    pub fn certified(&self) -> bool {
        self.certified
    }

    /// The orientations, unit quaternions `(x, y, z, w)`.
    pub fn orientations_xyzw(&self) -> &[[f64; 4]] {
        &self.orientations_xyzw
    }

    /// The robot's piece names.
    pub fn robot_pieces(&self) -> &[String] {
        &self.robot_pieces
    }

    /// The obstacles' piece names.
    pub fn obstacle_pieces(&self) -> &[String] {
        &self.obstacle_pieces
    }

    /// The pairs: (robot piece, obstacle piece) indices.
    pub fn pairs(&self) -> &[[i64; 2]] {
        &self.pairs
    }

    /// The slices per pair.
    pub fn slices_per_pair(&self) -> usize {
        self.slices_per_pair
    }

    /// The slices.
    pub fn slices(&self) -> &Slices {
        &self.slices
    }

    /// The number of slices held: entries of the starts array less one.
    fn slice_count(&self) -> usize {
        match &self.slices {
            Slices::HalfSpaces { plane_start, .. } => plane_start.len() - 1,
            Slices::Mesh { vertex_start, .. } => vertex_start.len() - 1,
        }
    }

    /// The arrays of the container, taking the map apart (module docs;
    /// strings `format` and `form` are scalars).
    pub fn into_arrays(self) -> Vec<Array> {
        let k = self.orientations_xyzw.len();
        let scalar_str = |name: &str, value: &str| Array {
            shape: vec![],
            ..Array::str(name, vec![value.into()])
        };
        let mut out = vec![
            scalar_str("format", FORMAT),
            Array::i64("version", vec![], vec![1]),
            scalar_str("form", self.form().name()),
            Array::i64("certified", vec![], vec![self.certified as i64]),
            Array::f64(
                "orientations_xyzw",
                vec![k, 4],
                self.orientations_xyzw.into_flattened(),
            ),
            Array::str("robot_pieces", self.robot_pieces),
            Array::str("obstacle_pieces", self.obstacle_pieces),
            Array::i64(
                "pairs",
                vec![self.pairs.len(), 2],
                self.pairs.into_flattened(),
            ),
            Array::i64("slices_per_pair", vec![], vec![self.slices_per_pair as i64]),
        ];
        match self.slices {
            Slices::HalfSpaces {
                plane_start,
                normals,
                offsets,
            } => out.extend([
                Array::i64("plane_start", vec![plane_start.len()], plane_start),
                Array::f64("normals", vec![normals.len(), 3], normals.into_flattened()),
                Array::f64("offsets", vec![offsets.len()], offsets),
            ]),
            Slices::Mesh {
                vertex_start,
                vertices,
                face_start,
                corner_start,
                corners,
            } => out.extend([
                Array::i64("vertex_start", vec![vertex_start.len()], vertex_start),
                Array::f64(
                    "vertices",
                    vec![vertices.len(), 3],
                    vertices.into_flattened(),
                ),
                Array::i64("face_start", vec![face_start.len()], face_start),
                Array::i64("corner_start", vec![corner_start.len()], corner_start),
                Array::i64("corners", vec![corners.len()], corners),
            ]),
        }
        out
    }

    /// The arrays of the container ([`Map::into_arrays`] of a copy).
    pub fn arrays(&self) -> Vec<Array> {
        self.clone().into_arrays()
    }

    /// Writes the container to `path`, atomically ([`write_npz`]).
    ///
    /// # Errors
    /// Those of [`write_npz`].
    pub fn write(&self, path: &Path) -> Result<(), FileError> {
        write_npz(path, &self.arrays())
    }
}

/// A map being filled, slice by slice, pair-major (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct MapBuilder {
    map: Map,
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
        let slices = match form {
            Form::HalfSpaces => Slices::HalfSpaces {
                plane_start: vec![0],
                normals: Vec::new(),
                offsets: Vec::new(),
            },
            Form::Mesh => Slices::Mesh {
                vertex_start: vec![0],
                vertices: Vec::new(),
                face_start: vec![0],
                corner_start: vec![0],
                corners: Vec::new(),
            },
        };
        MapBuilder {
            map: Map {
                certified,
                orientations_xyzw: orientations.iter().map(|r| r.xyzw()).collect(),
                robot_pieces,
                obstacle_pieces,
                pairs: Vec::new(),
                slices_per_pair,
                slices,
            },
        }
    }

    /// The form.
    pub fn form(&self) -> Form {
        self.map.form()
    }

    /// Starts the slices of the pair (robot piece `r`, obstacle piece `o`).
    pub fn add_pair(&mut self, r: usize, o: usize) {
        self.map.pairs.push([r as i64, o as i64]);
    }

    /// Appends a slice as half-spaces (a half-space map).
    pub fn push_halfspaces(&mut self, h: &HalfSpaces) {
        self.push_planes(h.normals(), h.offsets());
    }

    /// Appends a slice (or a certified slab) as the half-spaces
    /// `{x : n_i·x ≤ d_i}`.
    ///
    /// # Panics
    /// In a mesh map, or when `normals` and `offsets` differ in length.
    pub fn push_planes(&mut self, normals: &[DVec3], offsets: &[f64]) {
        assert_eq!(normals.len(), offsets.len(), "a plane's normal and offset");
        let Slices::HalfSpaces {
            plane_start,
            normals: ns,
            offsets: ds,
        } = &mut self.map.slices
        else {
            panic!("planes pushed to a mesh map");
        };
        ns.extend(normals.iter().map(|n| n.to_array()));
        ds.extend_from_slice(offsets);
        plane_start.push(ds.len() as i64);
    }

    /// Appends a slice as a mesh (a mesh map).
    ///
    /// # Panics
    /// In a half-space map.
    pub fn push_mesh(&mut self, m: &PolygonMesh) {
        let Slices::Mesh {
            vertex_start,
            vertices,
            face_start,
            corner_start,
            corners,
        } = &mut self.map.slices
        else {
            panic!("a mesh pushed to a half-space map");
        };
        vertices.extend_from_slice(&m.vertices);
        vertex_start.push(vertices.len() as i64);
        for f in &m.faces {
            corners.extend(f.iter().map(|&i| i as i64));
            corner_start.push(corners.len() as i64);
        }
        face_start.push((corner_start.len() - 1) as i64);
    }

    /// Slices appended so far.
    pub fn slice_count(&self) -> usize {
        self.map.slice_count()
    }

    /// The map, complete.
    ///
    /// # Panics
    /// If the slices appended are not `slices_per_pair` for each pair.
    pub fn finish(self) -> Map {
        self.check_complete();
        self.map
    }

    fn check_complete(&self) {
        assert_eq!(
            self.slice_count(),
            self.map.pairs.len() * self.map.slices_per_pair,
            "a map needs {} slices for each of its {} pairs",
            self.map.slices_per_pair,
            self.map.pairs.len()
        );
    }

    /// The arrays of the container (module docs).
    ///
    /// # Panics
    /// As [`MapBuilder::finish`].
    pub fn arrays(&self) -> Vec<Array> {
        self.check_complete();
        self.map.arrays()
    }

    /// Writes the container to `path`, atomically ([`write_npz`]).
    ///
    /// # Errors
    /// Those of [`write_npz`].
    ///
    /// # Panics
    /// As [`MapBuilder::finish`].
    pub fn write(&self, path: &Path) -> Result<(), FileError> {
        self.check_complete();
        self.map.write(path)
    }
}
