//! [`SolidError`]: why a mesh is not a solid, the one error of the solid
//! layer. [`check_solid_mesh`](super::check_solid_mesh) reports every
//! variant but [`SolidError::NonPositiveTotalVolume`];
//! [`check_closed_mesh`](super::closed::check_closed_mesh) (a closed,
//! oriented 2-manifold of positive total volume, the check of every merged
//! mesh) reports its share of them (rules 1 and 5 and the total volume);
//! [`clean_soup`](super::soup::clean_soup) reports the malformed input.

/// Why a mesh is not a solid, or not a closed mesh (the rules: the
/// [`solid`](super) module docs). Faces and vertices are numbered as in the
/// caller's mesh.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SolidError {
    /// The mesh has no faces.
    #[error("the mesh has no faces")]
    Empty,
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} is not finite")]
    NonFinite {
        /// The vertex.
        vertex: usize,
    },
    /// A face has fewer than three corners, a vertex out of range, or a
    /// repeated vertex.
    #[error("face {face} is malformed (fewer than 3 corners, a vertex out of range, or a repeated vertex)")]
    BadFace {
        /// The face.
        face: usize,
    },
    /// The coordinates span more bits than the exact arithmetic takes.
    #[error("the coordinates span 2^{low} to 2^{top}, more than 2^960 apart: too wide for exact predicates")]
    OutOfRange {
        /// The largest binary exponent.
        top: i32,
        /// The smallest binary exponent.
        low: i32,
    },
    /// Two faces have the same corners: one face listed twice, or two
    /// faces back to back.
    #[error(
        "faces {a} and {b} have the same corners (a face listed twice, or two faces back to back)"
    )]
    DuplicateFace {
        /// The first face.
        a: usize,
        /// The later face.
        b: usize,
    },
    /// Three corners of a face's fan are exactly collinear.
    #[error("face {face} has a zero-area triangle (corners {corners:?} exactly collinear)")]
    ZeroAreaTriangle {
        /// The face.
        face: usize,
        /// The three collinear corners (vertex indices).
        corners: [usize; 3],
    },
    /// A polygon face is not exactly planar.
    #[error("face {face} is not planar (vertex {vertex} is off the plane of its first three corners); triangulate it")]
    NonPlanarFace {
        /// The face.
        face: usize,
        /// A corner off the plane.
        vertex: usize,
    },
    /// A directed edge has no reverse: the surface is open there.
    #[error("open mesh: edge ({from}, {to}) of face {face} has no opposite edge (no opposite half-edge ({to}, {from}) in any face: the surface has a hole there)")]
    OpenEdge {
        /// Its first vertex.
        from: usize,
        /// Its second vertex.
        to: usize,
        /// The face holding it.
        face: usize,
    },
    /// Two faces run their common edge the same way.
    #[error("faces {} and {} both run edge ({from}, {to}) the same way: inconsistent orientation", faces[0], faces[1])]
    InconsistentOrientation {
        /// Its first vertex.
        from: usize,
        /// Its second vertex.
        to: usize,
        /// The two faces.
        faces: [usize; 2],
    },
    /// An edge is in more than two faces.
    #[error(
        "edge ({from}, {to}) is in {count} faces (a non-manifold edge), among them face {face}"
    )]
    NonManifoldEdge {
        /// Its first vertex.
        from: usize,
        /// Its second vertex.
        to: usize,
        /// How many faces hold it.
        count: usize,
        /// One of them.
        face: usize,
    },
    /// The faces about a vertex form more than one fan: the surface
    /// touches itself there.
    #[error("vertex {vertex} is non-manifold (pinched: its faces form more than one fan, so the surface touches itself there)")]
    NonManifoldVertex {
        /// The vertex.
        vertex: usize,
    },
    /// Two triangles of one shell meet other than along a shared edge or
    /// vertex (`a == b`: a polygon face whose fan overlaps itself).
    #[error("{}", crossing(*a, *b))]
    TrianglesCross {
        /// The first face.
        a: usize,
        /// The second face (not smaller).
        b: usize,
    },
    /// A shell encloses a zero or negative volume.
    #[error("shell {shell} (the connected part holding face {face}) encloses a {} volume: it is inward (faces clockwise seen from outside, e.g. a cavity) or flat",
        if *negative { "negative" } else { "zero" })]
    NonPositiveVolume {
        /// The shell (numbered by its first face).
        shell: usize,
        /// Its first face.
        face: usize,
        /// Negative (`true`) or zero.
        negative: bool,
    },
    /// The shells of a closed mesh enclose a zero or negative volume in
    /// all (the exact sign of the sum over every shell; a cavity inside a
    /// larger shell is allowed): the mesh is inward or flat. Only
    /// [`check_closed_mesh`](super::closed::check_closed_mesh) reports it.
    #[error("the mesh encloses a {} volume in all: it is inward (faces clockwise seen from outside) or flat",
        if *negative { "negative" } else { "zero" })]
    NonPositiveTotalVolume {
        /// Negative (`true`) or zero.
        negative: bool,
    },
}

fn crossing(a: usize, b: usize) -> String {
    if a == b {
        format!("face {a} overlaps itself (its fan triangulation folds)")
    } else {
        format!("faces {a} and {b} cross (they meet other than along a shared edge or vertex)")
    }
}
