//! Errors raised while building or validating a polytope.

use crate::hull::HullError;

/// Why a polytope could not be built. Each variant names what is wrong and
/// where (a point, vertex, edge or face index of the input).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PolytopeError {
    /// A coordinate is NaN or infinite. Fix the input point.
    #[error("point {index} has a non-finite coordinate {coords:?}")]
    NonFinite {
        /// Index of the offending point.
        index: usize,
        /// Its coordinates.
        coords: [f64; 3],
    },
    /// Fewer than 4 points: a 3-D polytope needs at least 4.
    #[error("too few points: {count} given, a 3-D polytope needs at least 4")]
    TooFewPoints {
        /// How many points were given.
        count: usize,
    },
    /// All points coincide, lie on a line, or lie in a plane: no volume.
    #[error("degenerate input: {0}")]
    Flat(HullError),
    /// A face has fewer than 3 vertices, or repeats a vertex.
    #[error("face {face} is degenerate (fewer than 3 distinct vertices)")]
    BadFace {
        /// Index of the face in the input mesh.
        face: usize,
    },
    /// A face refers to a vertex that does not exist.
    #[error("face {face} refers to vertex {index}, but there are only {count} vertices")]
    IndexOutOfRange {
        /// Index of the face.
        face: usize,
        /// The bad vertex index.
        index: usize,
        /// Number of vertices.
        count: usize,
    },
    /// The mesh is open: the edge `a → b` has no face on its other side.
    /// Fix: close the hole (or build from the points with `from_points`).
    #[error("open mesh: edge ({a}, {b}) borders only one face")]
    OpenEdge {
        /// First vertex of the edge.
        a: usize,
        /// Second vertex of the edge.
        b: usize,
    },
    /// The directed edge `a → b` is used by two faces: either more than two
    /// faces meet at the edge, or two neighbouring faces are oriented
    /// inconsistently. Fix the face orientation or the topology.
    #[error(
        "non-manifold or inconsistently oriented edge ({a}, {b}): used twice in the same direction"
    )]
    NonManifoldEdge {
        /// First vertex of the edge.
        a: usize,
        /// Second vertex of the edge.
        b: usize,
    },
    /// More than one fan of faces meets at this vertex (a pinch point).
    #[error("non-manifold vertex {vertex}")]
    NonManifoldVertex {
        /// The vertex.
        vertex: usize,
    },
    /// A vertex referenced by no face (internal; meshes drop unused vertices).
    #[error("vertex {vertex} is used by no face")]
    UnusedVertex {
        /// The vertex.
        vertex: usize,
    },
    /// The mesh is closed but not a sphere (V − E + F ≠ 2), so not convex.
    #[error(
        "mesh is not a topological sphere: Euler characteristic V - E + F = {euler}, expected 2"
    )]
    NotSphere {
        /// The Euler characteristic found.
        euler: i64,
    },
    /// The mesh is not convex beyond the tolerance: `vertex` lies `distance`
    /// inside the convex hull of the mesh (a dent), or `face` does not lie on
    /// the hull's boundary.
    #[error("non-convex mesh: {what} is {distance:.3e} away from the convex hull boundary (tolerance {tolerance:.3e})")]
    NonConvex {
        /// `"vertex N"` or `"face N"`.
        what: String,
        /// Distance from the hull boundary.
        distance: f64,
        /// The tolerance in force.
        tolerance: f64,
    },
    /// `--strict`: the mesh is convex only within tolerance (e.g. faces planar
    /// only up to printed rounding) and would have been replaced by its hull.
    #[error("strict mode: mesh is not exactly convex ({what}, off by {distance:.3e}); it would be replaced by the exact hull of its vertices")]
    NotExactlyConvex {
        /// What is off: `"face N is not planar"`, `"vertex N is not a hull vertex"`, ….
        what: String,
        /// By how much.
        distance: f64,
    },
    /// Two faces around `vertex` have (numerically) identical normals after
    /// rounding, so its Gaussian cell is degenerate. Happens only for
    /// pathologically thin features at the limit of `f64`.
    #[error("degenerate Gaussian map at vertex {vertex}: its incident face normals are not strictly convex")]
    DegenerateGaussMap {
        /// The vertex.
        vertex: usize,
    },
    /// The coordinates span more binary orders of magnitude than the exact
    /// predicates decide: from the top bit of the largest magnitude to the
    /// lowest set bit of any non-zero coordinate, one polytope may span at
    /// most `crate::kernel::exact::MAX_COORD_SPAN` = 960 bits (`2^960` ≈
    /// `1e289`; about `1e273` between magnitudes of full-precision values).
    /// Any overall scale is fine (`1e-300` to `1e300`); what is refused is
    /// a shape mixing, say, `1e300` and `1e-300`. Round the tiny
    /// coordinates to zero, or split the input.
    #[error(
        "coordinates outside the supported range: largest magnitude {largest:e}, smallest non-zero \
         {smallest:e}; the coordinates of one polytope may span at most 960 bits (2^960, about \
         1e289, from the largest magnitude down to the lowest bit of the smallest; any overall \
         scale is supported)"
    )]
    OutOfRange {
        /// The largest coordinate magnitude.
        largest: f64,
        /// The smallest non-zero coordinate magnitude.
        smallest: f64,
    },
    /// A face is so small relative to the whole shape (below about `2^-500`
    /// of its size) that its normal is not representable in `f64` in the
    /// shape's frame; such a face is beyond the supported range.
    #[error(
        "face {face} is too small relative to the shape (below about 2^-500 of its size) for \
         its normal to be represented; outside the supported range"
    )]
    FaceOutOfRange {
        /// The face (of the polytope's maximal faces).
        face: usize,
    },
}

impl From<HullError> for PolytopeError {
    fn from(e: HullError) -> Self {
        match e {
            HullError::TooFewPoints { count } => PolytopeError::TooFewPoints { count },
            other => PolytopeError::Flat(other),
        }
    }
}

impl From<super::topology::TopologyDefect> for PolytopeError {
    fn from(d: super::topology::TopologyDefect) -> Self {
        use super::topology::TopologyDefect as T;
        match d {
            T::EdgeUsedTwice(a, b) => PolytopeError::NonManifoldEdge { a, b },
            T::OpenEdge(a, b) => PolytopeError::OpenEdge { a, b },
            T::UnusedVertex(vertex) => PolytopeError::UnusedVertex { vertex },
            T::PinchedVertex(vertex) => PolytopeError::NonManifoldVertex { vertex },
            T::Euler(euler) => PolytopeError::NotSphere { euler },
        }
    }
}
