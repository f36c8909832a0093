//! One entry for bodies of either kind: [`Body`] (convex pieces, or
//! triangles of any topology) and [`Validator`] (a planner's state and
//! motion validator over them), which keeps convex pieces on the convex
//! fast path ([`MotionChecker`]) and takes everything else as triangles
//! ([`SceneChecker`]).

use super::body::{placed_polytope, MeshBody};
use super::checker::SceneChecker;
use crate::kernel::rotation::Pose;
use crate::mesh::PolygonMesh;
use crate::query::error::QueryError;
use crate::query::motion::{MotionCheck, MotionChecker, MotionError};
use crate::query::union::ConvexUnion;
use crate::solid::SolidError;

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
    /// ([`MeshBody::as_convex`]), a [`Validator`] takes it on the convex
    /// fast path (the same contact semantics: a convex solid). Nothing is
    /// approximated: a mesh convex only within rounding stays triangles.
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
    /// # Ok::<(), dymsum::query::QueryError>(())
    /// ```
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when a posed coordinate is not finite, or
    /// a convex piece flattens under rounding (no longer a polytope).
    pub fn placed(&self, pose: Pose) -> Result<Body, QueryError> {
        Ok(match self {
            Body::Convex(u) => Body::Convex(
                ConvexUnion::new(
                    u.pieces()
                        .iter()
                        .map(|p| placed_polytope(p, pose))
                        .collect::<Result<_, _>>()?,
                )
                .ok_or_else(|| QueryError::OutOfRange("a union without pieces".into()))?,
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
    fn as_union(&self) -> Option<ConvexUnion> {
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

/// A planner's state and motion validator for a body against obstacles of
/// either kind: the convex checker when every one is convex pieces, else
/// the triangle checker with the convex pieces as solid components (the
/// same contact semantics).
#[derive(Debug)]
#[allow(clippy::large_enum_variant)] // one per checker, built once
pub enum Validator {
    /// Every body convex pieces.
    Convex(MotionChecker),
    /// Some body triangles.
    Mesh(SceneChecker),
}

impl Validator {
    /// Prepares `body` (in its own frame) against `obstacles` (world frame).
    ///
    /// # Errors
    /// Those of [`MotionChecker::new`] and [`SceneChecker::new`].
    pub fn new(body: &Body, obstacles: &[Body]) -> Result<Validator, QueryError> {
        if let (Some(b), Some(o)) = (
            body.as_union(),
            obstacles
                .iter()
                .map(Body::as_union)
                .collect::<Option<Vec<_>>>(),
        ) {
            return Ok(Validator::Convex(MotionChecker::new(&b, &o)?));
        }
        let scene: Vec<MeshBody> = obstacles.iter().map(Body::to_mesh_body).collect();
        Ok(Validator::Mesh(SceneChecker::new(
            &body.to_mesh_body(),
            &scene,
        )?))
    }

    /// The same validator with a motion budget of `steps` intervals.
    pub fn with_budget(self, steps: u64) -> Validator {
        match self {
            Validator::Convex(c) => Validator::Convex(c.with_budget(steps)),
            Validator::Mesh(c) => Validator::Mesh(c.with_budget(steps)),
        }
    }

    /// The motion budget, in intervals.
    pub fn budget(&self) -> u64 {
        match self {
            Validator::Convex(c) => c.budget(),
            Validator::Mesh(c) => c.budget(),
        }
    }

    /// The intervals examined by all motion checks so far.
    pub fn steps(&self) -> u64 {
        match self {
            Validator::Convex(c) => c.steps(),
            Validator::Mesh(c) => c.steps(),
        }
    }

    /// Whether the body at `pose` touches or overlaps an obstacle (exact).
    ///
    /// # Errors
    /// Those of [`MotionChecker::collides_at`] and
    /// [`SceneChecker::collides_at`].
    pub fn collides_at(&self, pose: Pose) -> Result<bool, QueryError> {
        match self {
            Validator::Convex(c) => c.collides_at(pose),
            Validator::Mesh(c) => c.collides_at(pose),
        }
    }

    /// The clearance of the body at `pose` from the obstacles (`0` in
    /// contact): [`MotionChecker::distance_at`] (exact) or
    /// [`SceneChecker::distance_at`] (certified from below, within
    /// rounding).
    ///
    /// # Errors
    /// Those of [`Validator::collides_at`].
    pub fn distance_at(&self, pose: Pose) -> Result<f64, QueryError> {
        match self {
            Validator::Convex(c) => c.distance_at(pose),
            Validator::Mesh(c) => c.distance_at(pose),
        }
    }

    /// [`Validator::collides_at`] for many poses, in parallel, in order.
    ///
    /// # Errors
    /// The first error of [`Validator::collides_at`].
    pub fn collides_many(&self, poses: &[Pose]) -> Result<Vec<bool>, QueryError> {
        use rayon::prelude::*;
        poses.par_iter().map(|&p| self.collides_at(p)).collect()
    }

    /// Checks the straight motion from `from` to `to`.
    ///
    /// # Errors
    /// Those of [`MotionChecker::check`] and [`SceneChecker::check`].
    pub fn check(&self, from: Pose, to: Pose, tolerance: f64) -> Result<MotionCheck, MotionError> {
        match self {
            Validator::Convex(c) => c.check(from, to, tolerance),
            Validator::Mesh(c) => c.check(from, to, tolerance),
        }
    }

    /// [`Validator::check`] for many motions, in parallel, in order.
    ///
    /// # Errors
    /// The first error of [`Validator::check`].
    pub fn check_many(
        &self,
        motions: &[(Pose, Pose)],
        tolerance: f64,
    ) -> Result<Vec<MotionCheck>, MotionError> {
        match self {
            Validator::Convex(c) => c.check_many(motions, tolerance),
            Validator::Mesh(c) => c.check_many(motions, tolerance),
        }
    }
}
