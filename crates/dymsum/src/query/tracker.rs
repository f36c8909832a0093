//! Contact tracking over time, frame after frame, with the answer of the
//! static query at every frame.
//!
//! Two strategies ([`TrackerStrategy`]):
//! * **certified** (the default): the certified query of
//!   [`crate::query::pair::ConvexPair::query`], warm-started from the last frame (GJK
//!   from the last support vertices and direction; the searches from
//!   there; in contact, EPA from the last frame's polytope re-posed, see
//!   [`crate::query::pair::QueryStats::carried_polytopes`]), so a frame of
//!   coherent motion costs a few support-function steps plus the
//!   certificates;
//! * **dynamic sum**: a [`DynamicSum`] of `A ⊕ (−B)` repaired from frame to
//!   frame (DYMSUM updates, not recomputation) and every facet evaluated:
//!   O(F) per frame, for callers who also want the sum itself
//!   ([`ContactTracker::sum`]) or for tiny shapes.
//!
//! A frame allocates nothing once its buffers have grown
//! (`tests/no_alloc.rs`). Both strategies give the static query's answer
//! exactly: the certified one by its certificates, the dynamic one because
//! the dynamic overlay is identical to the static `walk` overlay.
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

use crate::dynamic::DynamicSum;
use crate::dynamic::UpdateReport;
use crate::kernel::rotation::Pose;
use crate::query::answer::Proximity;
use crate::query::error::QueryError;
use crate::query::pair::ConvexPair;
use crate::query::prep::Reflected;
use crate::query::proximity::certificate::candidates::FacetSet;
use crate::query::proximity::evaluate::{evaluate, Facets};
use crate::query::proximity::scratch::Scratch;
use crate::sum::Overlay;

/// How a [`ContactTracker`] answers each frame. Every strategy gives the
/// same answers (the static query's); they differ in speed only.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TrackerStrategy {
    /// Measures both of the others on the first 16 frames (`PROBE_FRAMES`)
    /// (and again every 4096 frames, `REPROBE_EVERY`) and uses the faster: the
    /// dynamic sum wins on tiny shapes, whose whole sum is a few dozen
    /// facets, the certified query on everything else.
    #[default]
    Auto,
    /// The certified query, warm-started from the last frame: support
    /// functions, GJK, EPA and exact certificates over the facets near the
    /// answer (every facet when a certificate cannot be made, counted in
    /// [`crate::query::pair::QueryStats`]).
    Certified,
    /// A [`DynamicSum`] of `A ⊕ (−B)` repaired by DYMSUM each frame, every
    /// facet evaluated (the sum is available from [`ContactTracker::sum`]).
    DynamicSum,
}

/// Frames an [`TrackerStrategy::Auto`] tracker times each strategy on.
pub const PROBE_FRAMES: u32 = 16;

/// Frames after which an [`TrackerStrategy::Auto`] tracker measures again
/// (the motion may have changed: contact, separation, speed).
pub const REPROBE_EVERY: u32 = 4096;

/// What an [`TrackerStrategy::Auto`] tracker is doing.
#[derive(Clone, Copy, Debug)]
enum Phase {
    /// Running both strategies, timing each (nanoseconds so far).
    Probing {
        frames: u32,
        certified: u64,
        sum: u64,
    },
    /// Running the one chosen, for this many more frames.
    Using { sum: bool, left: u32 },
}

/// Depth or distance of two moving convex bodies, frame after frame.
///
/// Built by [`ConvexPair::tracker`] (or [`ContactTracker::new`],
/// [`ContactTracker::with_strategy`]); each [`ContactTracker::update`]
/// answers exactly what the static [`ConvexPair::query`] answers at the
/// same poses. A box slides through a turning box:
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
    strategy: TrackerStrategy,
    /// The automatic strategy's state.
    phase: Phase,
    /// The dynamic sum (the [`TrackerStrategy::DynamicSum`] strategy).
    sum: Option<DynamicSum>,
    poses: (Pose, Pose),
    last: Proximity,
    report: UpdateReport,
    /// The overlay of `sum`, rebuilt in place every frame.
    overlay: Overlay,
    /// Its facets, as the evaluation takes them.
    facets: FacetSet,
    /// Evaluation buffers and the warm start, reused every frame.
    scratch: Scratch,
}

impl ContactTracker {
    /// A tracker at the given poses with the automatic strategy
    /// ([`TrackerStrategy::Auto`]). It keeps its own handle on the pair (a
    /// cheap clone: the bodies and `B`'s reflection are shared).
    ///
    /// # Errors
    /// Those of [`ConvexPair::query`]: [`QueryError::OutOfRange`] when a
    /// posed vertex of A or B, or the answer, overflows `f64`.
    pub fn new(pair: &ConvexPair, pose_a: Pose, pose_b: Pose) -> Result<Self, QueryError> {
        Self::with_strategy(pair, pose_a, pose_b, TrackerStrategy::Auto)
    }

    /// A tracker at the given poses with the given strategy.
    ///
    /// # Errors
    /// Those of [`ConvexPair::query`]; with
    /// [`TrackerStrategy::DynamicSum`] or [`TrackerStrategy::Auto`], also
    /// [`QueryError::Sum`] wrapping
    /// [`crate::error::SumError::Inconsistent`] for an internal error of the
    /// dynamic sum (a bug: please report the poses).
    pub fn with_strategy(
        pair: &ConvexPair,
        pose_a: Pose,
        pose_b: Pose,
        strategy: TrackerStrategy,
    ) -> Result<Self, QueryError> {
        let pair = pair.clone();
        let sum = match strategy {
            TrackerStrategy::Certified => None,
            TrackerStrategy::DynamicSum | TrackerStrategy::Auto => {
                Some(new_sum(&pair, pose_a, pose_b)?)
            }
        };
        let phase = match strategy {
            TrackerStrategy::Auto => Phase::Probing {
                frames: 0,
                certified: 0,
                sum: 0,
            },
            other => Phase::Using {
                sum: other == TrackerStrategy::DynamicSum,
                left: u32::MAX,
            },
        };
        let mut tracker = ContactTracker {
            pair,
            strategy,
            phase,
            sum,
            poses: (pose_a, pose_b),
            last: Proximity::Penetrating(crate::query::answer::Contact {
                depth: 0.0,
                normal: glam::DVec3::X,
                point_on_a: glam::DVec3::ZERO,
                point_on_b: glam::DVec3::ZERO,
                features: crate::query::answer::FeaturePair::FaceVertex {
                    a_face: 0,
                    b_vertex: 0,
                },
            }),
            report: UpdateReport::default(),
            overlay: Overlay::default(),
            facets: FacetSet::default(),
            scratch: Scratch::default(),
        };
        if let Some(sum) = &tracker.sum {
            tracker.overlay = sum.overlay();
        }
        tracker.answer(strategy == TrackerStrategy::DynamicSum)?;
        Ok(tracker)
    }

    /// Moves both bodies and answers the query.
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when a posed vertex of A or B, or the
    /// answer, overflows `f64`. The tracker has moved to the new poses even
    /// then (with the dynamic strategy, so has its sum, whose update itself
    /// depends only on the rotations and cannot fail);
    /// [`ContactTracker::last`] keeps the previous answer.
    pub fn update(&mut self, pose_a: Pose, pose_b: Pose) -> Result<Proximity, QueryError> {
        self.poses = (pose_a, pose_b);
        match self.phase {
            Phase::Using { sum, left } => {
                if sum {
                    self.move_sum()?;
                }
                self.answer(sum)?;
                self.phase = match (self.strategy, left) {
                    (TrackerStrategy::Auto, 0) => {
                        if self.sum.is_none() {
                            self.sum = Some(new_sum(&self.pair, pose_a, pose_b)?);
                        }
                        Phase::Probing {
                            frames: 0,
                            certified: 0,
                            sum: 0,
                        }
                    }
                    _ => Phase::Using {
                        sum,
                        left: left.saturating_sub(1),
                    },
                };
            }
            Phase::Probing {
                frames,
                certified,
                sum,
            } => {
                let start = std::time::Instant::now();
                self.answer(false)?;
                let mid = std::time::Instant::now();
                self.move_sum()?;
                self.answer(true)?;
                let end = std::time::Instant::now();
                let (c, s) = (
                    certified + (mid - start).as_nanos() as u64,
                    sum + (end - mid).as_nanos() as u64,
                );
                self.phase = if frames + 1 < PROBE_FRAMES {
                    Phase::Probing {
                        frames: frames + 1,
                        certified: c,
                        sum: s,
                    }
                } else {
                    let use_sum = s < c;
                    if !use_sum {
                        self.sum = None;
                        self.report = UpdateReport::default();
                    }
                    Phase::Using {
                        sum: use_sum,
                        left: REPROBE_EVERY,
                    }
                };
            }
        }
        Ok(self.last)
    }

    /// Moves the dynamic sum to the current poses (a DYMSUM update).
    fn move_sum(&mut self) -> Result<(), QueryError> {
        let (pose_a, pose_b) = self.poses;
        let sum = match &mut self.sum {
            Some(s) => s,
            None => self.sum.insert(new_sum(&self.pair, pose_a, pose_b)?),
        };
        sum.set_pose_into(pose_a, Reflected::pose(pose_b), &mut self.report);
        sum.overlay_into(&mut self.overlay);
        Ok(())
    }

    /// Answers at the current poses, from the dynamic sum's facets or by
    /// the certified query.
    fn answer(&mut self, from_sum: bool) -> Result<(), QueryError> {
        let (pose_a, pose_b) = self.poses;
        self.pair.stats.count_query();
        let facets = if from_sum {
            self.facets.fill_from(&self.overlay);
            Facets::Overlay(&self.facets)
        } else {
            Facets::Certified
        };
        self.last = evaluate(&self.pair, pose_a, pose_b, facets, &mut self.scratch)?;
        Ok(())
    }

    /// The answer of the last update (or of construction).
    pub fn last(&self) -> &Proximity {
        &self.last
    }

    /// What the last dynamic update changed (empty while no sum is kept).
    pub fn last_update(&self) -> &UpdateReport {
        &self.report
    }

    /// The current poses of A and B.
    pub fn poses(&self) -> (Pose, Pose) {
        self.poses
    }

    /// The strategy asked for.
    pub fn strategy(&self) -> TrackerStrategy {
        self.strategy
    }

    /// The strategy answering now: [`TrackerStrategy::Certified`] or
    /// [`TrackerStrategy::DynamicSum`] (an automatic tracker measuring both
    /// reports the one it answered the last frame with).
    pub fn active_strategy(&self) -> TrackerStrategy {
        match self.phase {
            Phase::Using { sum: true, .. } | Phase::Probing { .. } => TrackerStrategy::DynamicSum,
            Phase::Using { sum: false, .. } => TrackerStrategy::Certified,
        }
    }

    /// The dynamic sum `A ⊕ (−B)`, while one is kept (the dynamic-sum
    /// strategy, or an automatic tracker that measured it faster).
    pub fn sum(&self) -> Option<&DynamicSum> {
        self.sum.as_ref()
    }

    /// How the pair's queries were answered so far (this tracker's frames
    /// included): see [`crate::query::pair::QueryStats`].
    pub fn stats(&self) -> crate::query::pair::QueryStats {
        self.pair.stats()
    }
}

/// A dynamic sum `A ⊕ (−B)` at these poses.
fn new_sum(pair: &ConvexPair, pose_a: Pose, pose_b: Pose) -> Result<DynamicSum, QueryError> {
    Ok(DynamicSum::new(
        &pair.a,
        pose_a,
        &pair.neg_b().polytope,
        Reflected::pose(pose_b),
    )?)
}

impl ConvexPair {
    /// A tracker starting at the given poses.
    ///
    /// # Errors
    /// The same as [`ContactTracker::new`].
    pub fn tracker(&self, pose_a: Pose, pose_b: Pose) -> Result<ContactTracker, QueryError> {
        ContactTracker::new(self, pose_a, pose_b)
    }
}
