//! [`SanityError`]: which invariant a `sanity_check()` found broken.
//!
//! `Polytope::sanity_check`, `MinkowskiSum::sanity_check` and
//! `DynamicSum::sanity_check` re-derive their structure's invariants exactly
//! (for tests and fuzzers; O(F · V) for a polytope). A failure is a bug in
//! dymsum, or a structure assembled by hand from inconsistent parts: each
//! variant names the element where the invariant breaks, so a failing fuzz
//! case can be pinned as a regression test.

use crate::error::MeshError;

/// A broken invariant, with the element where it breaks. Indices are those
/// of the structure checked (vertices, edges, faces of a polytope; sum
/// vertices as `(vertex of P, vertex of Q)`).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SanityError {
    /// `V − E + F` is not 2: the boundary is not a sphere.
    #[error("Euler characteristic {chi} != 2")]
    EulerCharacteristic {
        /// The computed `V − E + F`.
        chi: i64,
    },
    /// An edge has the same face on both sides.
    #[error("edge {edge} has the same face on both sides")]
    EdgeWithOneFace {
        /// The edge.
        edge: usize,
    },
    /// A vertex has fewer than three incident faces.
    #[error("vertex {vertex} has degree {degree}")]
    VertexDegree {
        /// The vertex.
        vertex: usize,
        /// Its number of incident faces.
        degree: usize,
    },
    /// A vertex ring entry names an edge that does not join the vertex to
    /// the entry's neighbour.
    #[error("ring of vertex {vertex} entry {entry} names a wrong edge")]
    RingWrongEdge {
        /// The vertex.
        vertex: usize,
        /// The ring entry.
        entry: usize,
    },
    /// A vertex ring entry's edge does not separate the entry's face from
    /// the next one.
    #[error("ring of vertex {vertex} entry {entry}: edge does not separate consecutive faces")]
    RingNotSeparating {
        /// The vertex.
        vertex: usize,
        /// The ring entry.
        entry: usize,
    },
    /// A face has fewer than three corners.
    #[error("face {face} has {corners} vertices")]
    FaceTooSmall {
        /// The face.
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// No vertex lies strictly below a face's plane (the polytope is flat or
    /// the face faces inwards).
    #[error("face {face}: no vertex strictly below its plane")]
    NothingBelowFace {
        /// The face.
        face: usize,
    },
    /// A corner of a face is off the plane of its first three corners.
    #[error("face {face} is not planar at its vertex {corner}")]
    FaceNotPlanar {
        /// The face.
        face: usize,
        /// The corner (position in the face).
        corner: usize,
    },
    /// A face turns the wrong way, or not at all, at a corner.
    #[error("face {face} is not strictly convex at its vertex {corner}")]
    FaceNotConvex {
        /// The face.
        face: usize,
        /// The corner (position in the face).
        corner: usize,
    },
    /// A vertex lies above a face's plane: the polytope is not convex.
    #[error("vertex {vertex} is above face {face}: not convex")]
    VertexAboveFace {
        /// The vertex.
        vertex: usize,
        /// The face.
        face: usize,
    },
    /// The two faces of an edge are coplanar: the faces are not maximal.
    #[error("the faces of edge {edge} are coplanar: not maximal")]
    CoplanarFaces {
        /// The edge.
        edge: usize,
    },
    /// A directed facet edge of a sum occurs in two facets.
    #[error("facet edge {from:?} -> {to:?} used twice in one direction")]
    FacetEdgeTwice {
        /// Its first sum vertex.
        from: (u32, u32),
        /// Its second sum vertex.
        to: (u32, u32),
    },
    /// A directed facet edge of a sum has no facet using it backwards (the
    /// facet complex is open or inconsistently oriented).
    #[error("facet edge {from:?} -> {to:?} has no opposite facet")]
    FacetEdgeUnmatched {
        /// Its first sum vertex.
        from: (u32, u32),
        /// Its second sum vertex.
        to: (u32, u32),
    },
    /// The facets around a sum vertex form more than one fan (the facet
    /// complex is pinched there).
    #[error("facets pinch at sum vertex {vertex:?}")]
    FacetVertexPinched {
        /// The sum vertex.
        vertex: (u32, u32),
    },
    /// The facet complex of a sum is closed but not a sphere.
    #[error("facet complex Euler characteristic {chi} != 2")]
    FacetComplexEuler {
        /// The computed `V − E + F`.
        chi: i64,
    },
    /// The merged mesh of a sum failed its exact validation.
    #[error("merged mesh: {0}")]
    Mesh(#[from] MeshError),
    /// A dynamic sum's two indices of crossing edge pairs (by edge of P and
    /// by edge of Q) disagree.
    #[error("the ee indices by P edge and by Q edge disagree")]
    EeIndicesDisagree,
    /// The merged mesh of a non-convex sum (`nonconvex::UnionSum`, feature
    /// `union-mesh`) is not a valid closed mesh, or not the one recorded.
    #[error("union mesh: {reason}")]
    UnionMesh {
        /// The check that failed.
        reason: String,
    },
    /// A body of triangles (`query::MeshBody`) breaks an invariant the
    /// queries rely on.
    #[error("mesh body: {reason}")]
    MeshBody {
        /// The invariant, and where it breaks.
        reason: String,
    },
    /// A box tree's node does not hold what lies below it, or its items are
    /// not listed once each.
    #[error("box tree node {node}: {reason}")]
    BoxTree {
        /// The node.
        node: usize,
        /// The invariant broken.
        reason: String,
    },
}

#[cfg(test)]
mod tests {
    use super::SanityError;
    use crate::kernel::rotation::Pose;
    use crate::polytope::Polytope;
    use crate::sum::{minkowski_sum, Method, MinkowskiSum, Operands};

    fn unit_cube() -> Polytope {
        let pts: Vec<[f64; 3]> = (0..8)
            .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
            .collect();
        Polytope::from_points(&pts).unwrap()
    }

    #[test]
    fn valid_structures_pass() {
        let cube = unit_cube();
        assert_eq!(cube.sanity_check(), Ok(()));
        let sum = minkowski_sum(&cube, &cube, Method::Walk).unwrap();
        assert_eq!(sum.sanity_check(), Ok(()));
    }

    /// A corrupted overlay (one face of P paired with the wrong vertex of Q)
    /// no longer closes up: the check names a facet edge, typed.
    #[test]
    fn a_corrupted_overlay_is_named_by_its_facet_edge() {
        let cube = unit_cube();
        let good = minkowski_sum(&cube, &cube, Method::Walk).unwrap();
        let mut overlay = good.overlay().clone();
        let q_vertices = cube.vertex_count() as u32;
        overlay.fv[0] = (overlay.fv[0] + 1) % q_vertices;
        let ops = Operands::new(&cube, Pose::IDENTITY, &cube, Pose::IDENTITY);
        let bad = MinkowskiSum::from_overlay(ops, overlay);
        let err = bad.sanity_check().unwrap_err();
        assert!(
            matches!(
                err,
                SanityError::FacetEdgeTwice { .. }
                    | SanityError::FacetEdgeUnmatched { .. }
                    | SanityError::FacetVertexPinched { .. }
                    | SanityError::FacetComplexEuler { .. }
            ),
            "{err:?}"
        );
        assert!(err.to_string().starts_with("facet"), "{err}");
    }
}
