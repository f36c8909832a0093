//! The non-convex sums' error.

use crate::error::SumError;
use crate::polytope::PolytopeError;
use crate::query::QueryError;
use crate::sum::MeshError;

/// Why a non-convex sum (or its decomposition, or a depth from it) failed.
#[derive(Debug, thiserror::Error)]
pub enum UnionMeshError {
    /// The input mesh is not a closed, outward solid.
    #[error("the mesh is not a closed solid: {reason}")]
    Input {
        /// Why.
        reason: String,
    },
    /// The input mesh is not a solid by the exact check
    /// ([`crate::solid::check_solid_mesh`]).
    #[error("the mesh is not a valid solid: {0}")]
    Solid(#[from] crate::solid::SolidError),
    /// A shell (connected component) is not exactly convex and no
    /// decomposition was chosen.
    #[error(
        "a non-convex mesh ({nonconvex} of its {components} connected components not exactly convex) \
         needs a convex decomposition: choose V-HACD (Rust: Decomposition::Vhacd with the `parry` \
         feature; CLI: --decomposition vhacd), or give its convex pieces (files joined with `+`, \
         OBJ objects)"
    )]
    NeedsDecomposition {
        /// Connected components of the mesh.
        components: usize,
        /// Those not exactly convex (or inward shells: cavities).
        nonconvex: usize,
    },
    /// The chosen decomposition is not compiled in.
    #[error("the {0} decomposition needs dymsum's `parry` feature")]
    DecompositionUnavailable(&'static str),
    /// The decomposition failed or returned no solid part.
    #[error("decomposition: {0}")]
    Decomposition(String),
    /// `boolmesh` refused a mesh or failed on a boolean.
    #[error("mesh boolean ({step}): {message}")]
    Boolean {
        /// The mesh or the operation.
        step: String,
        /// `boolmesh`'s message.
        message: String,
    },
    /// The merged mesh failed validation (it is not returned).
    #[error("the merged mesh is not a valid closed mesh: {0}")]
    Invalid(crate::solid::SolidError),
    /// A piece-pair sum failed.
    #[error(transparent)]
    Sum(#[from] SumError),
    /// The mesh of a piece-pair sum failed.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// A piece could not be built.
    #[error(transparent)]
    Polytope(#[from] PolytopeError),
    /// A collision query failed.
    #[error(transparent)]
    Query(#[from] QueryError),
}
