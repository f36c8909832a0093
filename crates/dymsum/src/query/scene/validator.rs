//! One entry for bodies of either kind ([`Body`]): [`Validator`], a
//! planner's state and motion validator over them, which keeps convex pieces on the convex
//! fast path ([`MotionChecker`]) and takes everything else as triangles
//! ([`SceneChecker`]).

use super::checker::SceneChecker;
use crate::body::{Body, MeshBody};
use crate::kernel::rotation::Pose;
use crate::query::checker::{Checker, MotionCheck};
use crate::query::error::{MotionError, QueryError};
use crate::query::motion::MotionChecker;

/// A planner's state and motion validator for a body against obstacles of
/// either kind: the convex checker when every one is convex pieces, else
/// the triangle checker with the convex pieces as solid components (the
/// same contact semantics).
///
/// It answers every [`Checker`] method through the checker it holds
/// ([`Validator::checker`]), with or without the trait in scope (it
/// dereferences to `dyn Checker`):
///
/// ```
/// use dymsum::query::{Body, ConvexUnion, MotionCheck, Validator};
/// use dymsum::{DVec3, Polytope, Pose, Rotation};
/// let cuboid = |lo: [f64; 3], hi: [f64; 3]| {
///     let c: Vec<[f64; 3]> = (0..8)
///         .map(|i| [0, 1, 2].map(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
///         .collect();
///     Body::from(ConvexUnion::from(Polytope::from_points(&c).unwrap()))
/// };
/// let wall = cuboid([2.0, -1.0, -1.0], [3.0, 1.0, 1.0]);
/// let validator = Validator::new(&cuboid([-0.5; 3], [0.5; 3]), &[wall])?.with_budget(100);
/// assert!(matches!(validator, Validator::Convex(_))); // every body convex
/// let at = |x: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, 0.0));
/// assert_eq!(validator.collides_many(&[at(0.0), at(1.5)])?, [false, true]);
/// assert_eq!(validator.check(at(0.0), at(-3.0), 1e-6)?, MotionCheck::Free);
/// assert_eq!(validator.budget(), 100);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
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

    /// The checker that answers: the convex one or the triangle one.
    pub fn checker(&self) -> &(dyn Checker + 'static) {
        match self {
            Validator::Convex(c) => c,
            Validator::Mesh(c) => c,
        }
    }

    /// The same validator with a motion budget of `steps` intervals
    /// ([`Checker::with_budget`]).
    pub fn with_budget(self, steps: u64) -> Validator {
        match self {
            Validator::Convex(c) => Validator::Convex(c.with_budget(steps)),
            Validator::Mesh(c) => Validator::Mesh(c.with_budget(steps)),
        }
    }
}

/// The held checker's methods, callable on a validator without the trait
/// in scope.
impl std::ops::Deref for Validator {
    type Target = dyn Checker;

    fn deref(&self) -> &Self::Target {
        self.checker()
    }
}

impl Checker for Validator {
    fn collides_at(&self, pose: Pose) -> Result<bool, QueryError> {
        self.checker().collides_at(pose)
    }

    fn distance_at(&self, pose: Pose) -> Result<f64, QueryError> {
        self.checker().distance_at(pose)
    }

    fn check(&self, from: Pose, to: Pose, tolerance: f64) -> Result<MotionCheck, MotionError> {
        self.checker().check(from, to, tolerance)
    }

    fn budget(&self) -> u64 {
        self.checker().budget()
    }

    fn with_budget(self, steps: u64) -> Validator {
        Validator::with_budget(self, steps)
    }

    fn steps(&self) -> u64 {
        self.checker().steps()
    }
}
