//! One entry for bodies of either kind ([`Body`]): [`Validator`], a
//! planner's state and motion validator over them, which keeps convex pieces on the convex
//! fast path ([`MotionChecker`]) and takes everything else as triangles
//! ([`SceneChecker`]).

use super::checker::SceneChecker;
use crate::body::{Body, MeshBody};
use crate::kernel::rotation::Pose;
use crate::query::error::QueryError;
use crate::query::motion::{MotionCheck, MotionChecker, MotionError};

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
