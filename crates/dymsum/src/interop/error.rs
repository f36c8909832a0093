//! The conversions' error: why a value could not be converted.

/// Why a value of another crate could not be converted into a dymsum type,
/// or a dymsum shape into another crate's. Each variant carries the
/// offending value.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum InteropError {
    /// The quaternion is zero or has a non-finite component: it is no
    /// rotation. Components in the order `x, y, z, w` (scalar last).
    #[error("quaternion (x, y, z, w) = {xyzw:?} is zero or not finite, so it is no rotation")]
    BadQuaternion {
        /// The components, scalar last.
        xyzw: [f64; 4],
    },
    /// The 3×3 matrix is not a rotation: not finite, not orthonormal, or
    /// its determinant is not +1 (each within `1e-6`, see
    /// [`Rotation::from_matrix`](crate::kernel::rotation::Rotation::from_matrix)). Columns listed in order.
    #[error("matrix with columns {columns:?} is not a rotation (orthonormal with determinant +1, within 1e-6)")]
    NotRotation {
        /// The matrix, column by column.
        columns: [[f64; 3]; 3],
    },
    /// The 4×4 matrix is not a rigid transform: its last row is not exactly
    /// `0, 0, 0, 1`, an entry is not finite, or its upper 3×3 block is not a
    /// rotation (see [`Pose::from_mat4`](crate::kernel::rotation::Pose::from_mat4)). Columns listed in order.
    #[error("4x4 matrix with columns {columns:?} is not a rigid transform (a rotation block, a finite translation, last row exactly 0, 0, 0, 1)")]
    NotRigid {
        /// The matrix, column by column (boxed: it is large).
        columns: Box<[[f64; 4]; 4]>,
    },
    /// The translation of a pose has a non-finite component.
    #[error("translation {translation:?} is not finite")]
    NonFiniteTranslation {
        /// The translation.
        translation: [f64; 3],
    },
    /// parry3d-f64's `ConvexPolyhedron::from_convex_mesh` returned `None` for
    /// the polytope's vertices and fan-triangulated faces, or a polyhedron
    /// without faces (it refuses a mesh with a triangle repeating a vertex,
    /// an edge shared by more than two triangles, or an open edge; a valid
    /// polytope has none of these).
    #[error("parry3d-f64 refused the polytope's mesh ({vertices} vertices, {triangles} triangles): ConvexPolyhedron::from_convex_mesh gave no polyhedron or one without faces")]
    ParryRefused {
        /// Vertices passed to parry.
        vertices: usize,
        /// Triangles passed to parry.
        triangles: usize,
    },
    /// A triangle of the polytope's fan triangulation (vertex indices of the
    /// polytope) has an edge direction or a normal that parry's float
    /// arithmetic cannot normalise accurately: parry squares coordinate
    /// differences and their cross products, and a square that is not a
    /// normal float (zero, subnormal or infinite) makes it drop the edge,
    /// give the face a zero normal, or a "unit" normal off by up to 100%.
    /// That happens for edges shorter than about `1.5e-154` or longer than
    /// about `1.3e154` and for cross products (edge length times edge
    /// length) outside the same range, so for a shape of even aspect below
    /// about `1e-77` or above about `1e77` in size. dymsum works in a scaled
    /// frame and supports these shapes. Scale the shape into parry's range.
    #[error("triangle {triangle:?} of the polytope is outside parry3d-f64's float range: its edge directions or normal cannot be normalised accurately (squares underflow or overflow; sizes below about 1e-77 or above about 1e77)")]
    ParryOutOfRange {
        /// The triangle's vertices (indices of the polytope's vertices).
        triangle: [u32; 3],
    },
    /// parry3d-f64 built its face `face` with a normal that is not a finite
    /// unit vector (a check on parry's output, behind
    /// [`InteropError::ParryOutOfRange`], which should make it unreachable).
    #[error("parry3d-f64 built face {face} with the normal {normal:?}, not a finite unit vector")]
    ParryDegenerateNormal {
        /// The face, numbered as parry's `faces()`.
        face: usize,
        /// The normal parry computed.
        normal: [f64; 3],
    },
}
