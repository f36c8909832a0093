//! Bodies: what the queries take, each prepared once ([`Body`]: convex
//! pieces or triangles of any topology; [`ConvexUnion`]; [`MeshBody`] with
//! its box trees and [`MeshReport`]). A mesh is read into a body by
//! [`Body::from_mesh`] (the cleaning of `solid::soup`, the winding-number
//! meaning of inside: `winding` by a ray, read from `inside_grid`'s
//! classified cells where it can), or by the ladder of [`Body::from_mesh_with`]
//! (convex, convex shells, triangles; the hull when asked) with a
//! [`BodyReport`] of what it did; an obstacle given in its own frame is
//! placed by [`Body::placed`]; the questions asked of bodies live in
//! `query`.

mod error;
pub(crate) mod inside_grid;
mod ladder;
pub mod mesh;
mod union;
pub(crate) mod winding;

pub use error::BodyError;
#[cfg(feature = "union-mesh")]
pub(crate) use ladder::solid_shells;
pub use ladder::{BodyOptions, BodyReport, Rung};
pub use mesh::{MeshBody, MeshReport};
pub use union::ConvexUnion;
pub use winding::ContainmentStats;

use crate::kernel::rotation::Pose;
use crate::mesh::PolygonMesh;
use crate::solid::SolidError;
use mesh::placed_polytope;

/// A body for collision and motion checks: convex pieces, or triangles of
/// any topology.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)] // one per body, built once: a box gains nothing
pub enum Body {
    /// A union of convex pieces (the fast path).
    Convex(ConvexUnion),
    /// Triangles of any topology, cleaned exactly ([`MeshBody`]).
    Mesh(MeshBody),
}

impl Body {
    /// A mesh as it comes: cleaned exactly ([`MeshBody::new`]). When what
    /// remains is one solid component that is exactly convex
    /// ([`MeshBody::as_convex`]), a `query::Validator` takes it on the convex
    /// fast path (the same contact semantics: a convex solid). Nothing is
    /// approximated: a mesh convex only within rounding stays triangles.
    /// [`Body::from_mesh_with`] also takes a solid of convex shells as
    /// their union, and the hull when asked, and reports what it did.
    ///
    /// ```
    /// use dymsum::query::Body;
    /// use dymsum::PolygonMesh;
    /// let v = vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
    /// let closed = vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]];
    /// assert!(Body::from_mesh(&PolygonMesh::new(v.clone(), closed.clone()))?.is_convex());
    /// // Without its bottom face it is an open surface: triangles.
    /// let open = closed[1..].to_vec();
    /// assert!(!Body::from_mesh(&PolygonMesh::new(v, open))?.is_convex());
    /// # Ok::<(), dymsum::SolidError>(())
    /// ```
    ///
    /// # Errors
    /// Those of [`MeshBody::new`].
    pub fn from_mesh(mesh: &PolygonMesh) -> Result<Body, SolidError> {
        Ok(Body::Mesh(MeshBody::new(mesh)?))
    }

    /// The body placed at `pose` (an obstacle given in its own frame): its
    /// vertices posed once, in floats (`R p + t`, rounded to the nearest
    /// `f64`), and everything built from them again; the checks are then
    /// exact for those coordinates. What the cleaning decided (which
    /// triangles enclose, their weights) is kept: it does not depend on
    /// where the body is, and the enclosing part is closed edge for edge.
    ///
    /// ```
    /// use dymsum::query::{Body, ConvexUnion, Validator};
    /// use dymsum::{DVec3, Polytope, Pose, Rotation};
    /// let cube = |h: f64| {
    ///     let c: Vec<[f64; 3]> = (0..8)
    ///         .map(|i| std::array::from_fn(|k| if i >> k & 1 == 0 { -h } else { h }))
    ///         .collect();
    ///     Body::Convex(ConvexUnion::from(Polytope::from_points(&c).unwrap()))
    /// };
    /// let at = |x: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, 0.0));
    /// let wall = cube(1.0).placed(at(10.0))?;
    /// let checker = Validator::new(&cube(0.5), &[wall])?;
    /// assert!(checker.collides_at(at(8.5))? && !checker.collides_at(at(8.0))?);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`BodyError::NotFinite`] when a posed coordinate is not finite,
    /// [`BodyError::Flattened`] when a convex piece flattens under rounding
    /// (no longer a polytope).
    pub fn placed(&self, pose: Pose) -> Result<Body, BodyError> {
        Ok(match self {
            Body::Convex(u) => Body::Convex(
                ConvexUnion::new(
                    u.pieces()
                        .iter()
                        .map(|p| placed_polytope(p, pose))
                        .collect::<Result<_, _>>()?,
                )
                .ok_or_else(|| BodyError::Flattened("a union without pieces".into()))?,
            ),
            Body::Mesh(m) => Body::Mesh(m.placed(pose)?),
        })
    }

    /// Whether the body takes the convex fast path: convex pieces, or a
    /// mesh that is one exactly convex solid.
    pub fn is_convex(&self) -> bool {
        self.as_union().is_some()
    }

    /// The body as convex pieces, when it is.
    pub(crate) fn as_union(&self) -> Option<ConvexUnion> {
        match self {
            Body::Convex(u) => Some(u.clone()),
            Body::Mesh(m) => m.as_convex().cloned().map(ConvexUnion::from),
        }
    }

    /// The body as triangles (convex pieces as solid components).
    pub fn to_mesh_body(&self) -> MeshBody {
        match self {
            Body::Convex(u) => MeshBody::from_union(u),
            Body::Mesh(m) => m.clone(),
        }
    }
}

impl From<ConvexUnion> for Body {
    fn from(u: ConvexUnion) -> Body {
        Body::Convex(u)
    }
}

impl From<MeshBody> for Body {
    fn from(m: MeshBody) -> Body {
        Body::Mesh(m)
    }
}
