//! [`Checker`]: what a planner asks of a body prepared against obstacles
//! (state, clearance, motion, and their batches), answered alike by the
//! convex checker ([`MotionChecker`]), the triangle checker
//! ([`SceneChecker`]) and the [`Validator`] that picks one of them; the
//! batches are written once here, over the single calls. [`MotionCheck`]:
//! the answer of a motion check.
//!
//! [`MotionChecker`]: crate::query::MotionChecker
//! [`SceneChecker`]: crate::query::SceneChecker
//! [`Validator`]: crate::query::Validator

use crate::kernel::rotation::Pose;
use crate::query::error::{MotionError, QueryError};

/// The answer of a motion check.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MotionCheck {
    /// No contact at any `t` in `[0, 1]` (certified).
    Free,
    /// A contact: every `t ≤ t_safe` is certified free (`None` when the
    /// body collides at `t = 0`), and at `t_contact` the body touches or
    /// overlaps an obstacle (the exact query says so); `t_contact − t_safe`
    /// is at most the tolerance.
    Collides {
        /// The last time certified free.
        t_safe: Option<f64>,
        /// A time of contact.
        t_contact: f64,
    },
}

impl MotionCheck {
    /// `true` for [`MotionCheck::Free`].
    pub fn is_free(&self) -> bool {
        matches!(self, MotionCheck::Free)
    }
}

/// A body prepared against obstacles for many state and motion checks (a
/// planner's state and motion validator): [`MotionChecker`] (convex
/// pieces), [`SceneChecker`] (triangles of any topology) and
/// [`Validator`] (either, picked by the bodies). Contact is closed: touching
/// is colliding; every yes/no is exact, every motion answer certified
/// (`query::interval_search`).
///
/// The checkers also have each method inherently (no `use` needed); the
/// trait is for code written once over all of them:
///
/// ```
/// use dymsum::query::{Checker, ConvexUnion, MeshBody, MotionCheck, MotionChecker, SceneChecker};
/// use dymsum::{DVec3, Polytope, Pose, Rotation};
/// let cuboid = |lo: [f64; 3], hi: [f64; 3]| {
///     let c: Vec<[f64; 3]> = (0..8)
///         .map(|i| [0, 1, 2].map(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
///         .collect();
///     ConvexUnion::from(Polytope::from_points(&c).unwrap())
/// };
/// let body = cuboid([-0.5; 3], [0.5; 3]);
/// let wall = cuboid([2.0, -1.0, -1.0], [3.0, 1.0, 1.0]);
/// let convex = MotionChecker::new(&body, &[wall.clone()])?;
/// let mesh = MeshBody::from_union(&wall);
/// let triangles = SceneChecker::new(&MeshBody::from_union(&body), &[mesh])?;
/// let at = |x: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, 0.0));
/// for checker in [&convex as &dyn Checker, &triangles] {
///     assert_eq!(checker.collides_many(&[at(0.0), at(1.5), at(2.0)])?, [false, true, true]);
///     assert!(checker.distance_at(at(0.0))? >= 1.5 - 1e-12);
///     let checks = checker.check_many(&[(at(0.0), at(-3.0)), (at(0.0), at(3.0))], 1e-6)?;
///     assert_eq!(checks[0], MotionCheck::Free);
///     assert!(!checks[1].is_free()); // through the wall
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// [`MotionChecker`]: crate::query::MotionChecker
/// [`SceneChecker`]: crate::query::SceneChecker
/// [`Validator`]: crate::query::Validator
pub trait Checker: Sync {
    /// Whether the body at `pose` touches or overlaps an obstacle (exact).
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when a posed coordinate is beyond `f64`.
    fn collides_at(&self, pose: Pose) -> Result<bool, QueryError>;

    /// The clearance of the body at `pose` from the obstacles: `0` when
    /// it collides, else the least distance (exact for convex pieces,
    /// certified from below within rounding for triangles). For clearance
    /// objectives.
    ///
    /// # Errors
    /// Those of [`Checker::collides_at`].
    fn distance_at(&self, pose: Pose) -> Result<f64, QueryError>;

    /// Checks the straight motion from `from` to `to`
    /// ([`crate::query::Motion`]) with the bracket of a contact no wider
    /// than `tolerance` (in `t`): [`MotionCheck::Free`] certified, or
    /// [`MotionCheck::Collides`] with `[0, t_safe]` certified free and an
    /// exact contact at `t_contact`.
    ///
    /// # Errors
    /// [`MotionError::Tolerance`] for a tolerance outside
    /// `[MIN_TOLERANCE, 1)` ([`crate::query::MIN_TOLERANCE`]);
    /// [`MotionError::Query`] when a posed coordinate is beyond `f64`;
    /// [`MotionError::Undecided`] for a motion grazing an obstacle within
    /// rounding; [`MotionError::BudgetExhausted`] past the budget.
    fn check(&self, from: Pose, to: Pose, tolerance: f64) -> Result<MotionCheck, MotionError>;

    /// A cheap refutation before a certificate: the first time `k /
    /// segments` (`0 < k < segments`, visited in bisection order, the
    /// middle first, at most `most` of them) at which the body on the
    /// straight motion from `from` to `to` ([`crate::query::Motion::at`],
    /// the poses [`Checker::check`] checks) touches or overlaps an
    /// obstacle (exact), or `None` when none does, which proves nothing:
    /// the motion may still collide between the samples, and only
    /// [`Checker::check`] certifies it free. A planner's yes/no motion
    /// validator runs it with its sampled check's own count first, so that
    /// a colliding motion costs what sampling costs (a colliding state is
    /// a colliding motion):
    ///
    /// ```
    /// use dymsum::query::{Checker, ConvexUnion, MotionChecker};
    /// use dymsum::{DVec3, Polytope, Pose, Rotation};
    /// let cuboid = |lo: [f64; 3], hi: [f64; 3]| {
    ///     let c: Vec<[f64; 3]> = (0..8)
    ///         .map(|i| [0, 1, 2].map(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
    ///         .collect();
    ///     ConvexUnion::from(Polytope::from_points(&c).unwrap())
    /// };
    /// let block = cuboid([2.0, -1.0, -1.0], [3.0, 1.0, 1.0]);
    /// let checker = MotionChecker::new(&cuboid([-0.5; 3], [0.5; 3]), &[block])?;
    /// let at = |x: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, 0.0));
    /// // Through the block: the middle sample (x = 2.5) collides.
    /// assert_eq!(checker.sampled_contact(at(0.0), at(5.0), 8, 7)?, Some(0.5));
    /// // Into the block only over the last 2% of the motion: none of the 7
    /// // inner samples collides, and the certified check finds the contact.
    /// assert_eq!(checker.sampled_contact(at(-6.0), at(1.6), 8, 7)?, None);
    /// assert!(!checker.check(at(-6.0), at(1.6), 1e-6)?.is_free());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// Those of [`Checker::collides_at`].
    fn sampled_contact(
        &self,
        from: Pose,
        to: Pose,
        segments: usize,
        most: usize,
    ) -> Result<Option<f64>, QueryError> {
        let motion = crate::query::Motion::new(from, to);
        for k in crate::query::interval_search::bisection_order(segments, most) {
            let t = k as f64 / segments as f64;
            if self.collides_at(motion.at(t))? {
                return Ok(Some(t));
            }
        }
        Ok(None)
    }

    /// The work budget of one motion check, in intervals
    /// ([`crate::query::DEFAULT_BUDGET`] unless set).
    fn budget(&self) -> u64;

    /// The same checker with a work budget of `steps` intervals per motion
    /// check (at least 1): a check that has examined that many without a
    /// decision ends with [`MotionError::BudgetExhausted`] and its
    /// certified `t_safe`. The count is deterministic: the same check gives
    /// the same answer on any machine and under any load.
    fn with_budget(self, steps: u64) -> Self
    where
        Self: Sized;

    /// The intervals examined by all motion checks so far (the work the
    /// budget counts), for benchmarks and tests.
    fn steps(&self) -> u64;

    /// [`Checker::collides_at`] for many poses, in parallel (rayon), in
    /// order.
    ///
    /// # Errors
    /// The first error of [`Checker::collides_at`].
    fn collides_many(&self, poses: &[Pose]) -> Result<Vec<bool>, QueryError> {
        use rayon::prelude::*;
        poses.par_iter().map(|&p| self.collides_at(p)).collect()
    }

    /// [`Checker::check`] for many motions `(from, to)`, in parallel
    /// (rayon), in order.
    ///
    /// # Errors
    /// The first error of [`Checker::check`].
    fn check_many(
        &self,
        motions: &[(Pose, Pose)],
        tolerance: f64,
    ) -> Result<Vec<MotionCheck>, MotionError> {
        use rayon::prelude::*;
        motions
            .par_iter()
            .map(|&(a, b)| self.check(a, b, tolerance))
            .collect()
    }
}
