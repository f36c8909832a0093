//! Contact tracking over time: a [`DynamicSum`] of `A ⊕ (−B)` repaired from
//! frame to frame (DYMSUM updates, not recomputation), queried each frame.
//!
//! Each frame costs one dynamic update (proportional to the changes of the
//! overlay for small steps; translations alone change nothing) plus one O(F)
//! pass over the facets for the depth or the distance, and allocates nothing
//! once its buffers have grown (the overlay is rebuilt in place, the
//! evaluation reuses its buffers; `tests/no_alloc.rs`). The answer is
//! identical to the static query at the same poses, because the dynamic
//! overlay is identical to the static `walk` overlay.
//!
//! ```
//! use dymsum::{Polytope, Pose, Rotation, DVec3};
//! use dymsum::query::ConvexPair;
//! let pts: Vec<[f64; 3]> = (0..8)
//!     .map(|i| [(i & 1) as f64 - 0.5, ((i >> 1) & 1) as f64 - 0.5, ((i >> 2) & 1) as f64 - 0.5])
//!     .collect();
//! let cube = Polytope::from_points(&pts).unwrap();
//! let pair = ConvexPair::new(&cube, &cube).unwrap();
//! let b = Pose::new(Rotation::IDENTITY, DVec3::new(0.9, 0.0, 0.0));
//! let mut tracker = pair.tracker(Pose::IDENTITY, b).unwrap();
//! for k in 0..10 {
//!     let turn = Rotation::from_axis_angle(DVec3::Z, 0.01 * k as f64).unwrap();
//!     let hit = tracker.update(Pose::new(turn, DVec3::ZERO), b).unwrap();
//!     assert!(hit.intersects());
//! }
//! ```

use super::{ConvexPair, Proximity, QueryError, Reflected};
use crate::dynamic::UpdateReport;
use crate::sum::Overlay;
use crate::{DynamicSum, Pose};

/// Depth or distance of two moving convex bodies, frame after frame.
///
/// Built by [`ConvexPair::tracker`] (or [`ContactTracker::new`]); each
/// [`ContactTracker::update`] answers exactly what the static
/// [`ConvexPair::query`] answers at the same poses. A box slides through
/// a turning box:
///
/// ```
/// use dymsum::{ContactTracker, ConvexPair, DVec3, Polytope, Pose, Rotation};
/// let corners: Vec<[f64; 3]> = (0..8)
///     .map(|i| [(i & 1) as f64 - 0.5, ((i >> 1) & 1) as f64 - 0.5, ((i >> 2) & 1) as f64 - 0.5])
///     .collect();
/// let cube = Polytope::from_points(&corners)?;
/// let pair = ConvexPair::new(&cube, &cube)?;
/// let slide = |k: usize| Pose::new(Rotation::IDENTITY, DVec3::new(2.0 - 0.05 * k as f64, 0.1, 0.0));
/// let mut tracker: ContactTracker = pair.tracker(Pose::IDENTITY, slide(0))?;
/// assert!(!tracker.last().intersects()); // centres 2 apart: no contact yet
/// for k in 1..=40 {
///     let turn = Rotation::from_axis_angle(DVec3::Z, 0.01 * k as f64).ok_or("zero axis")?;
///     let pose_a = Pose::new(turn, DVec3::ZERO);
///     let answer = tracker.update(pose_a, slide(k))?;
///     assert_eq!(answer, pair.query(pose_a, slide(k))?);
/// }
/// assert!(tracker.last().intersects()); // centres 0.1 apart at the end
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct ContactTracker {
    pair: ConvexPair,
    sum: DynamicSum,
    last: Proximity,
    report: UpdateReport,
    /// The overlay of `sum`, rebuilt in place every frame.
    overlay: Overlay,
    /// Its facets, as the evaluation takes them.
    facets: super::candidates::FacetSet,
    /// Evaluation buffers, reused every frame.
    scratch: super::depth::Scratch,
}

impl ContactTracker {
    /// A tracker at the given poses (one static sum). It keeps its own
    /// handle on the pair (a cheap clone: the bodies and `B`'s reflection
    /// are shared).
    ///
    /// # Errors
    /// * [`QueryError::OutOfRange`] when a posed vertex of A or B, or the
    ///   answer, overflows `f64` (the dynamic sum itself depends only on the
    ///   rotations, so the range is checked when the answer is evaluated);
    /// * [`QueryError::Sum`] wrapping [`crate::SumError::Inconsistent`] only for an
    ///   internal error of the dynamic sum (a bug: please report the poses).
    pub fn new(pair: &ConvexPair, pose_a: Pose, pose_b: Pose) -> Result<Self, QueryError> {
        let pair = pair.clone();
        let sum = DynamicSum::new(
            &pair.a,
            pose_a,
            &pair.neg_b.polytope,
            Reflected::pose(pose_b),
        )?;
        let mut scratch = super::depth::Scratch::default();
        let overlay = sum.overlay();
        let mut facets = super::candidates::FacetSet::default();
        facets.fill_from(&overlay);
        let last = super::depth::evaluate(&pair, pose_a, pose_b, &facets, &mut scratch)?;
        Ok(ContactTracker {
            pair,
            sum,
            last,
            report: UpdateReport::default(),
            overlay,
            facets,
            scratch,
        })
    }

    /// Moves both bodies (a dynamic update) and answers the query.
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when a posed vertex of A or B, or the
    /// answer, overflows `f64` (the dynamic update itself depends only on the
    /// rotations and cannot fail, so the range is checked when the answer is
    /// evaluated). The dynamic sum has moved to the new poses even then;
    /// [`ContactTracker::last`] keeps the previous answer.
    pub fn update(&mut self, pose_a: Pose, pose_b: Pose) -> Result<Proximity, QueryError> {
        self.sum
            .set_pose_into(pose_a, Reflected::pose(pose_b), &mut self.report);
        self.sum.overlay_into(&mut self.overlay);
        self.facets.fill_from(&self.overlay);
        self.last =
            super::depth::evaluate(&self.pair, pose_a, pose_b, &self.facets, &mut self.scratch)?;
        Ok(self.last)
    }

    /// The answer of the last update (or of construction).
    pub fn last(&self) -> &Proximity {
        &self.last
    }

    /// What the last dynamic update changed.
    pub fn last_update(&self) -> &UpdateReport {
        &self.report
    }

    /// The current poses of A and B.
    pub fn poses(&self) -> (Pose, Pose) {
        let pb = self.sum.pose_q();
        (self.sum.pose_p(), Reflected::pose(pb))
    }

    /// The dynamic sum `A ⊕ (−B)`.
    pub fn sum(&self) -> &DynamicSum {
        &self.sum
    }
}
