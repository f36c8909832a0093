//! One proximity query of two convex bodies, step by step (the order is
//! [`evaluate`]'s): support functions ([`support`]), GJK's exact yes/no
//! ([`gjk`]), EPA's polytope inside the difference ([`epa`]), the
//! certificates that a small set of the overlay's facets decides the
//! answer ([`certificate`]), and the answer from those facets: penetration
//! depth ([`depth`]), distance ([`distance`]) and closest points
//! ([`closest`]).

pub(in crate::query) mod certificate;
pub(in crate::query) mod closest;
pub(in crate::query) mod depth;
pub(in crate::query) mod distance;
pub(in crate::query) mod epa;
pub(in crate::query) mod evaluate;
pub(in crate::query) mod from_facets;
pub(in crate::query) mod gjk;
pub(in crate::query) mod hulls_meet;
pub(in crate::query) mod scratch;
pub(in crate::query) mod support;

use crate::kernel::rotation::Pose;
use crate::polytope::Polytope;
use crate::query::answer::{Contact, Proximity, Separation};
use crate::query::error::QueryError;
use crate::query::pair::ConvexPair;
use scratch::with_scratch;

/// The queries of a prepared pair (the steps are `proximity::evaluate`'s).
impl ConvexPair {
    /// Depth or distance at the given poses (a static `walk` sum).
    ///
    /// # Errors
    /// * [`QueryError::Sum`] wrapping [`crate::sum::SumError::OutOfRange`] when a posed
    ///   vertex of A or of `−B` overflows `f64` (|coordinate| > 1.8e308);
    /// * [`QueryError::OutOfRange`] when the answer (depth, distance or a
    ///   witness point) overflows `f64`;
    /// * [`QueryError::Sum`] wrapping [`crate::sum::SumError::Inconsistent`] only for an
    ///   internal error of the sum (a bug: please report the poses).
    pub fn query(&self, pose_a: Pose, pose_b: Pose) -> Result<Proximity, QueryError> {
        self.stats.count_query();
        with_scratch(|s| {
            crate::query::proximity::evaluate::evaluate(
                self,
                pose_a,
                pose_b,
                crate::query::proximity::evaluate::Facets::Certified,
                s,
            )
        })
    }

    /// [`ConvexPair::query`] by evaluating every facet of `A ⊕ (−B)` (a
    /// static `walk` sum): the exhaustive reference the certified query is
    /// tested against. Always the same answer, at O(mn) cost.
    ///
    /// # Errors
    /// The same as [`ConvexPair::query`].
    pub fn query_exhaustive(&self, pose_a: Pose, pose_b: Pose) -> Result<Proximity, QueryError> {
        with_scratch(|s| {
            crate::query::proximity::evaluate::evaluate(
                self,
                pose_a,
                pose_b,
                crate::query::proximity::evaluate::Facets::Exhaustive,
                s,
            )
        })
    }

    /// [`ConvexPair::query`] at many poses `(pose_a, pose_b)`, in order:
    /// the batch a planner or a physics step needs. The poses are split
    /// into chunks answered in parallel (rayon), each chunk warm-starting
    /// from the pose before, so the answers are the static query's, in any
    /// order and on any number of threads.
    ///
    /// ```
    /// use dymsum::{ConvexPair, DVec3, Polytope, Pose, Rotation};
    /// let corners: Vec<[f64; 3]> = (0..8)
    ///     .map(|i| [(i & 1) as f64 - 0.5, ((i >> 1) & 1) as f64 - 0.5, ((i >> 2) & 1) as f64 - 0.5])
    ///     .collect();
    /// let cube = Polytope::from_points(&corners)?;
    /// let pair = ConvexPair::new(&cube, &cube)?;
    /// let poses: Vec<(Pose, Pose)> = (0..100)
    ///     .map(|k| (Pose::IDENTITY, Pose::new(Rotation::IDENTITY, DVec3::new(0.02 * k as f64, 0.0, 0.0))))
    ///     .collect();
    /// let answers = pair.query_many(&poses)?;
    /// assert_eq!(answers[25].depth(), 0.5); // centres 0.5 apart
    /// assert_eq!(answers[75].distance(), 0.5); // centres 1.5 apart
    /// assert_eq!(answers[75], pair.query(poses[75].0, poses[75].1)?);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// The first error of [`ConvexPair::query`] among the poses.
    pub fn query_many(&self, poses: &[(Pose, Pose)]) -> Result<Vec<Proximity>, QueryError> {
        self.many(poses, |pair, (pa, pb), s| {
            crate::query::proximity::evaluate::evaluate(
                pair,
                pa,
                pb,
                crate::query::proximity::evaluate::Facets::Certified,
                s,
            )
        })
    }

    /// [`ConvexPair::intersects`] at many poses, as
    /// [`ConvexPair::query_many`].
    ///
    /// # Errors
    /// The first error of [`ConvexPair::intersects`] among the poses.
    pub fn intersects_many(&self, poses: &[(Pose, Pose)]) -> Result<Vec<bool>, QueryError> {
        self.many(poses, |pair, (pa, pb), s| {
            s.posed.reset(pair, pa, pb)?;
            Ok(crate::query::proximity::evaluate::decide(pair, s, true))
        })
    }

    /// Answers `one` at every pose, in parallel chunks of warm-started
    /// queries.
    pub(in crate::query) fn many<T: Send>(
        &self,
        poses: &[(Pose, Pose)],
        one: impl Fn(
                &ConvexPair,
                (Pose, Pose),
                &mut crate::query::proximity::scratch::Scratch,
            ) -> Result<T, QueryError>
            + Sync,
    ) -> Result<Vec<T>, QueryError> {
        use rayon::prelude::*;
        const CHUNK: usize = 64;
        let chunks: Vec<Result<Vec<T>, QueryError>> = poses
            .par_chunks(CHUNK)
            .map(|chunk| {
                let mut scratch = crate::query::proximity::scratch::Scratch::default();
                chunk
                    .iter()
                    .map(|&p| {
                        self.stats.count_query();
                        one(self, p, &mut scratch)
                    })
                    .collect()
            })
            .collect();
        let mut out = Vec::with_capacity(poses.len());
        for c in chunks {
            out.extend(c?);
        }
        Ok(out)
    }

    /// The penetration depth, or `None` when apart.
    ///
    /// # Errors
    /// The same as [`ConvexPair::query`].
    pub fn penetration_depth(
        &self,
        pose_a: Pose,
        pose_b: Pose,
    ) -> Result<Option<Contact>, QueryError> {
        Ok(self.query(pose_a, pose_b)?.contact().copied())
    }

    /// The distance (`0` and the contact features when touching or
    /// overlapping).
    ///
    /// # Errors
    /// The same as [`ConvexPair::query`].
    pub fn distance(&self, pose_a: Pose, pose_b: Pose) -> Result<Separation, QueryError> {
        Ok(match self.query(pose_a, pose_b)? {
            Proximity::Separated(s) => s,
            Proximity::Penetrating(c) => Separation {
                distance: 0.0,
                point_on_a: c.point_on_a,
                point_on_b: c.point_on_a,
                direction: c.normal,
                features: c.features,
            },
        })
    }

    /// `true` when the bodies overlap or touch, decided exactly on the
    /// posed bodies by GJK and its certificates alone (no depth or
    /// distance is computed).
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when a posed vertex overflows `f64`.
    pub fn intersects(&self, pose_a: Pose, pose_b: Pose) -> Result<bool, QueryError> {
        self.stats.count_query();
        with_scratch(|s| {
            s.posed.reset(self, pose_a, pose_b)?;
            Ok(crate::query::proximity::evaluate::decide(self, s, true))
        })
    }
}

/// Penetration depth of `a` and `b` at their poses, or `None` when they are
/// apart (see the [module docs](crate::query) for the conventions).
///
/// # Errors
/// Those of [`ConvexPair::new`] (internal only) and of
/// [`ConvexPair::query`]: an overflowing posed vertex or answer.
pub fn penetration_depth(
    a: &Polytope,
    pose_a: Pose,
    b: &Polytope,
    pose_b: Pose,
) -> Result<Option<Contact>, QueryError> {
    ConvexPair::new(a, b)?.penetration_depth(pose_a, pose_b)
}

/// Distance between `a` and `b` at their poses (`0` when touching or
/// overlapping), with the closest points.
///
/// # Errors
/// Those of [`ConvexPair::new`] (internal only) and of
/// [`ConvexPair::query`]: an overflowing posed vertex or answer.
pub fn distance(
    a: &Polytope,
    pose_a: Pose,
    b: &Polytope,
    pose_b: Pose,
) -> Result<Separation, QueryError> {
    ConvexPair::new(a, b)?.distance(pose_a, pose_b)
}

/// `true` when `a` and `b` overlap or touch at their poses.
///
/// # Errors
/// Those of [`ConvexPair::new`] (internal only) and of
/// [`ConvexPair::query`]: an overflowing posed vertex or answer.
pub fn intersects(
    a: &Polytope,
    pose_a: Pose,
    b: &Polytope,
    pose_b: Pose,
) -> Result<bool, QueryError> {
    ConvexPair::new(a, b)?.intersects(pose_a, pose_b)
}

/// Depth or distance of `a` and `b` at their poses.
///
/// # Errors
/// Those of [`ConvexPair::new`] (internal only) and of
/// [`ConvexPair::query`]: an overflowing posed vertex or answer.
pub fn query(
    a: &Polytope,
    pose_a: Pose,
    b: &Polytope,
    pose_b: Pose,
) -> Result<Proximity, QueryError> {
    ConvexPair::new(a, b)?.query(pose_a, pose_b)
}
