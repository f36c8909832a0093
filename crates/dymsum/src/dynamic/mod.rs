//! DYMSUM: the Minkowski sum `P ⊕ Q` kept up to date while P and Q move
//! (paper §4).
//!
//! # What it computes
//! A [`DynamicSum`] holds both polytopes, their poses and the overlay of their
//! Gaussian maps (for every face of P its vertex of Q, for every face of Q its
//! vertex of P, and the crossing edge pairs). [`DynamicSum::set_pose`] moves
//! the bodies and repairs the overlay; the result is *identical* to the static
//! [`crate::sum::Method::Walk`] sum at the new poses, for every step size.
//!
//! # Steps of one update (Algorithm 4.1)
//! [`DynamicSum::set_pose`] reads as the paper's algorithm; each step lives
//! in its own file:
//! 1. **Rotate** (`DynamicSum::rotate`, here): the new relative rotation
//!    `R = R_q⁻¹ R_p`. P's reference normals and arc normals are rotated by
//!    it when they are read (`gauss::Turn`: always from the reference data,
//!    so no drift, and O(1) per step instead of O(m)).
//! 2. **FindErrors** (§4.1, `find_errors.rs`, with the float bounds of
//!    `margins.rs` and the persistent ties of `ties.rs`): check the fv-pairs
//!    of both maps. A float margin (the sine of the distance from the normal
//!    to the nearest great circle of its cell's arcs, computed from accurate
//!    arc normals) decides clear cases; the rest use the exact predicate. A
//!    normal whose last margin, less the rotation accumulated since, still
//!    exceeds this step's reach is not checked at all (lazy margins). When
//!    few normals are checked, the kinetic schedule (`schedule.rs`) keeps
//!    every normal's deadline (the accumulated rotation at which its lazy
//!    margin runs out) in a calendar queue, and a step visits only the
//!    normals whose deadline it reaches instead of passing over all of them.
//! 3. **Correct fv-errors** (§4.2) by hill climbing from the old vertex, in
//!    the same pass, where each error is found (`find_errors.rs`).
//! 4. **Correct ee-errors** (§4.3, `correct_ee.rs`): a normal that certainly
//!    crossed exactly one arc `x` of the other map flips exactly the pairs
//!    (arc at that normal, `x`): those are toggled. The arcs at every other
//!    *at-risk* normal are re-walked through the other map between the
//!    corrected fv-pairs, and their crossings diffed against the stored ones.
//! 5. **Fallback** (`fallback.rs`): too large a step, or too many arcs at
//!    risk, is recomputed by `walk`; **report** (`report.rs`): what changed.
//!
//! The state is two `Side`s, P's and Q's, with the same fields (a face's
//! cell in the other map, an arc's crossings, margins, tie certificates);
//! every pass runs once per side.
//!
//! # Why every step is correct, not only small ones
//! The paper's locality argument (Theorem 4.1) holds for an infinitesimal
//! motion: the overlay changes only when a normal of one map crosses an arc
//! of the other. Over a finite step a normal can leave its cell and come back
//! (so checking fv-pairs alone misses ee-changes). We certify instead.
//! Move from the old relative rotation to the new one along the geodesic of
//! SO(3): a rotation about a fixed axis by the step angle `θ`. Every
//! combinatorial event on that path is a normal `x` crossing an arc of the
//! other map, and flips exactly the crossing status of the pairs formed by
//! that arc and the arcs incident to `x`; a pair's final status is its
//! initial one flipped once per event involving it. Relative to the other
//! map, `x` moves along a small-circle arc of length at most `θ`.
//!
//! * *No event.* For an interior point of a convex cell, the distance to the
//!   boundary is the smallest distance to the great circles of its arcs, so
//!   if the margin (a sine, hence at most the chordal distance) exceeds `θ`
//!   the normal cannot reach the boundary. Margins decay by at most the
//!   rotation since they were computed, which makes the lazy skip sound.
//!   The kinetic schedule skips exactly the same normals without reading
//!   them: a normal is left in the queue only while its deadline
//!   `margin_at + margin − δ` exceeds `after + drift`, which is the lazy
//!   skip test rearranged (see `schedule.rs`; a tie-certified normal is
//!   keyed by its tie deadline only while its run about one axis lasts).
//!   For a normal that ends in its old cell the bound is sharper: its path
//!   lies within chordal distance `δ = θ²/4` of the great arc joining its end
//!   positions, which lies in the convex cell, and along that great arc each
//!   `m · x` is a positive sinusoid lobe, at least its smaller end value; so
//!   if both end margins exceed `δ`, the path never leaves the cell.
//! * *Exactly one event.* If the old and new cells `v`, `w` are adjacent
//!   across arc `x`, the old position is farther than `θ` from every other
//!   great circle of `v` and the new one from every other great circle of
//!   `w`, then the path lies in `v ∪ w` (the intersection of those
//!   half-spaces), whose common boundary is `x`, and meets `x`'s great circle
//!   an odd number of times but at most twice (a small circle meets a great
//!   circle in at most two points): exactly once. Its flips are known.
//! * *Anything else* is at risk: all arcs at that normal are re-walked from
//!   scratch, which recomputes every pair an event at that normal can flip.
//!
//! * *Persistent ties.* Exact ties have margin 0. When both relative
//!   rotations of a step turn exactly about a coordinate axis `e_k` (row and
//!   column `k` of both matrices are `e_k`, as for boxes turning about `z`),
//!   the step is taken along rotations about `e_k`, on which the
//!   `k`-components of P's rotated normals are constant. A determinant
//!   `det[a, b, x]` that is then zero at every rotation (read off the exact
//!   zero pattern of the normals and of the arcs' cross products, computed
//!   once) keeps its SoS sign if the first SoS term that is not itself zero
//!   at every rotation stays away from zero: for P's normal (lowest index)
//!   that term is a component of Q's fixed `a × b`, constant; for Q's normal
//!   it is a minor or entry of the rotating rows, certified by its size
//!   against its rate of change. A normal all of whose arcs are so certified
//!   (the others by their margins) stays in its cell and has no event; its
//!   certified margin is reused lazily while the steps stay about `e_k`.
//!
//! * *Certified normals.* After every update, each normal's lazy margin
//!   less the rotation accumulated since it was computed bounds its float
//!   margin in its current cell from below (the lazy skip above rests on
//!   the same bound; a fallback or a fresh start recomputes every margin).
//!   Where that bound exceeds the face's direction error `δ` and twice the
//!   slack, the exact normal lies strictly inside its cell, on no arc of
//!   the other map (`DynamicSum::normal_strictly_inside`). Readers of the
//!   overlay use it to skip exact coplanarity tests
//!   (`sum::merge::coplanar_groups_certified`): a normal on no arc of the
//!   other map equals no normal of it (those are its cells' corners), and
//!   an ee-facet of arcs `ab` (P's) and `cd` (Q's) is coplanar with face
//!   `a` only when `a` lies on the great circle of `cd`; the arcs cross,
//!   so then `a` is their crossing (the great circles are distinct, else
//!   the arcs overlap and an end of one lies on the other; the other
//!   common point `−a` is not on the arc `ab`, shorter than a half turn),
//!   on the arc `cd`. So an ee-facet whose four normals are certified is
//!   neither coplanar with anything nor degenerate. (With all four ends
//!   strictly off the other map's arcs, two arcs either cross
//!   transversally or are apart, so the symbolic rule for ties decides no
//!   crossing there: the stored pairs are the exact ones.) The bound needs
//!   the accumulated rotation to count at least the exact one (below).
//!   An independent review (2026-12-02) read every path that writes a
//!   normal's cell or margin (passes, the kinetic schedule, persistent
//!   ties, fallbacks and backoff, rebasing, both bodies moving) and found
//!   each keeps margin and cell together; it drove 47,188 states (boxes,
//!   integer and lattice hulls with coplanar faces, hulls of 500–600
//!   faces, exact quarter turns, tiny and huge steps, three rebases,
//!   bodies `10⁷` from the origin) and after every update compared both
//!   groupings (17.97 million facets), checked each of 11.47 million
//!   certified normals strictly inside its cell with exact determinants,
//!   and the overlay against `walk`: no fault but the accumulated
//!   rotation's, mended below. Its wording remarks are applied.
//!
//! * *The accumulated rotation counts up.* The lazy margins decay by the
//!   accumulated rotation, so it must never count less than the bodies
//!   turned. A plain float sum did: at an accumulated `θ` in `[512, 1024)`
//!   a step below half an ulp (`5.7·10⁻¹⁴`) added nothing, and a
//!   constant step lost up to half an ulp at every step, in the same
//!   direction; the one slack of `10⁻¹⁰` covers one rounding, not a
//!   thousand. The independent review of 2026-12-02 built two motions that
//!   ended with a normal exactly on an arc while its margin still
//!   certified it inside (60,000 steps of `5·10⁻¹⁴` rad; 62,000 steps of
//!   `3·10⁻⁸` rad each losing 0.45 ulp), which made the overlay differ
//!   from `walk`. Each step's angle (`Rotation::angle_to`, from the float
//!   product of the two quaternions, off by at most about `18u`
//!   absolutely) is now padded by `32u` and a relative `2⁻⁴⁸`, and the
//!   sum is rounded up (TwoSum, one ulp more where it rounded down):
//!   pinned by `a_rotation_of_many_small_steps_is_counted_in_full` and
//!   `steps_below_half_an_ulp_still_count` (`find_errors.rs`). Rebasing subtracts the same float from every `margin_at`:
//!   exact for those within a factor two of it (Sterbenz), and a single
//!   rounding of at most `1.2·10⁻¹³` otherwise, covered by the slack.
//!
//! A pair not on a re-walked arc therefore had events only at normals with a
//! known event set, and toggling by parity gives its final status. Margins
//! are computed in floats from accurate arc normals, and every comparison
//! adds the face's bound on its float normal's direction error plus a slack
//! of `1e-10`; exact ties have margin 0 and are at risk unless certified as
//! persistent (above). Steps above
//! [`DynamicConfig::max_step_angle`], or steps where more than
//! [`DynamicConfig::fallback_fraction`] of all arcs would be re-walked, are
//! recomputed from scratch by `walk` instead (cheaper, and trivially correct);
//! after such a fallback a few steps at least 90% as large go straight to the
//! recomputation (an exponential backoff; not after steps about a coordinate
//! axis, where many arcs at risk means an isolated exact coincidence such as
//! a quarter turn), and the update's report is the diff of the two overlays.
//!
//! # Complexity
//! With passes, O(m + n) per step to test every normal's lazy margin; with
//! the kinetic schedule (used while under 1/8 of the normals are checked
//! per pass, left above 1/4 due per step; never for a side of fewer than 48
//! normals, whose pass costs less than the schedule's bookkeeping) O(k + 1)
//! for the `k` due normals.
//! Plus O(deg) per visited normal and per certified crossing, and the walks
//! along the arcs at uncertain normals. The due normals are those within a
//! step of their cell's boundary, so for small steps the work follows the
//! number of changes, up to the factor by which normals near a boundary
//! outnumber those crossing it (docs/BENCHMARKS.md measures both).
//!
//! ```
//! use dymsum::{DynamicSum, Polytope, Pose, Rotation, DVec3};
//! use dymsum::sum::{minkowski_sum_posed, Method};
//! let pts: Vec<[f64; 3]> = (0..8).map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64]).collect();
//! let cube = Polytope::from_points(&pts).unwrap();
//! let tet = Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]]).unwrap();
//! let mut dynamic = DynamicSum::new(&tet, Pose::IDENTITY, &cube, Pose::IDENTITY).unwrap();
//! let step = Rotation::from_axis_angle(DVec3::new(1.0, 2.0, 3.0), 0.01).unwrap();
//! for _ in 0..100 {
//!     let report = dynamic.rotate_p_by(step);
//!     assert!(report.fv_errors <= tet.face_count() + cube.face_count());
//! }
//! let fresh = minkowski_sum_posed(&tet, dynamic.pose_p(), &cube, dynamic.pose_q(), Method::Walk).unwrap();
//! assert_eq!(dynamic.facets(), fresh.facets());
//! ```

use crate::kernel::exact::{self, ExactVec};
use crate::kernel::predicates::{others, sos_terms, ExactVector, SosTerm};
use crate::kernel::rotation::Pose;
use crate::kernel::rotation::Rotation;
use crate::kernel::Sign;
use crate::polytope::Polytope;
use crate::sum::{
    relative_rotation, walk_overlay, Facet, GaussView, MinkowskiSum, Operands, Overlay, SumError,
};
use glam::{DMat3, DVec3};

mod correct_ee;
mod fallback;
mod find_errors;
mod margins;
mod report;
mod schedule;
mod ties;

use fallback::Backoff;
use find_errors::SideScan;
use margins::{
    arc_normals, direction_errors, locate_certified, margin, single_crossing, EXACT_BELOW, SLACK,
};
use report::overlay_diff;
pub use report::UpdateReport;
use schedule::{Deadlines, REBASE_AFTER};
use ties::{coordinate_axis, stays_in_cell_tied, ExactZeros, Tied};

/// Tuning of the dynamic update. The defaults are right for almost all uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DynamicConfig {
    /// Steps whose relative rotation angle exceeds this (radians) are
    /// recomputed from scratch. Default `π/4`.
    pub max_step_angle: f64,
    /// When more than this fraction of all arcs would be re-walked, recompute
    /// from scratch instead. Default `0.5`.
    pub fallback_fraction: f64,
}

impl Default for DynamicConfig {
    fn default() -> Self {
        DynamicConfig {
            max_step_angle: std::f64::consts::FRAC_PI_4,
            fallback_fraction: 0.5,
        }
    }
}

/// The dynamic Minkowski sum (see the module docs).
///
/// Each [`DynamicSum::set_pose`] (or [`DynamicSum::rotate_p_by`]) repairs
/// the facet set; after every step it equals a fresh static `walk` sum at
/// the same poses, and the [`UpdateReport`] is the exact difference:
///
/// ```
/// use dymsum::{minkowski_sum_posed, DVec3, DynamicSum, Method, Polytope, Pose, Rotation};
/// let corners: Vec<[f64; 3]> = (0..8)
///     .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
///     .collect();
/// let cube = Polytope::from_points(&corners)?;
/// let tet = Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]])?;
/// let mut sum = DynamicSum::new(&tet, Pose::IDENTITY, &cube, Pose::IDENTITY)?;
/// let step = Rotation::from_axis_angle(DVec3::new(1.0, 2.0, 3.0), 0.05).ok_or("zero axis")?;
/// for _ in 0..40 {
///     let before = sum.facet_count();
///     let report = sum.rotate_p_by(step);
///     assert_eq!(sum.facet_count(), before - report.removed.len() + report.added.len());
///     let fresh = minkowski_sum_posed(&tet, sum.pose_p(), &cube, sum.pose_q(), Method::Walk)?;
///     assert_eq!(sum.facets(), fresh.facets());
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct DynamicSum {
    ops: Operands,
    /// P's half: its faces in Q's cells (the fv-pairs), its arcs' crossings.
    p: Side,
    /// Q's half: its faces in P's cells (the vf-pairs), its arcs' crossings.
    q: Side,
    theta_acc: f64,
    /// Buffers of one step, reused (no allocation per step), and the
    /// crossings of the arc being re-walked.
    scratch: Option<Box<Scratch>>,
    fresh: Vec<u32>,
    /// Exact zero structure of P's and Q's maps, computed at the first step
    /// about a coordinate axis (see [`stays_in_cell_tied`]).
    zeros: Option<Box<[ExactZeros; 2]>>,
    /// Incremental steps so far.
    tick: u64,
    /// The coordinate axis of the current run of incremental steps about
    /// one axis, and the step that began the run.
    axis_run: Option<usize>,
    axis_since: u64,
    /// After fallbacks, how many steps of similar size skip the scan.
    backoff: Backoff,
    step: u32,
    config: DynamicConfig,
}

/// No coordinate axis.
const NO_AXIS: u8 = u8::MAX;

impl DynamicSum {
    /// Starts from a static `walk` sum at the given poses.
    ///
    /// # Errors
    /// [`SumError::Inconsistent`] only if an internal invariant of the walk
    /// fails (a bug in dymsum: please report the input). The overlay depends
    /// on the rotations alone, so no pose is out of range here; a pose whose
    /// posed coordinates overflow `f64` surfaces as
    /// [`crate::sum::MeshError::OutOfRange`] from [`Self::try_to_mesh`].
    pub fn new(p: &Polytope, pose_p: Pose, q: &Polytope, pose_q: Pose) -> Result<Self, SumError> {
        Self::with_config(p, pose_p, q, pose_q, DynamicConfig::default())
    }

    /// [`DynamicSum::new`] with explicit tuning.
    ///
    /// # Errors
    /// [`SumError::Inconsistent`] only if an internal invariant of the walk
    /// fails (a bug in dymsum: please report the input). The overlay depends
    /// on the rotations alone, so no pose is out of range here; a pose whose
    /// posed coordinates overflow `f64` surfaces as
    /// [`crate::sum::MeshError::OutOfRange`] from [`Self::try_to_mesh`].
    pub fn with_config(
        p: &Polytope,
        pose_p: Pose,
        q: &Polytope,
        pose_q: Pose,
        config: DynamicConfig,
    ) -> Result<Self, SumError> {
        let mut ops = Operands::new(p, pose_p, q, pose_q);
        let overlay = walk_overlay(&ops)?;
        // From here on P's normals and arcs are rotated when visited.
        ops.make_lazy();
        let mut s = DynamicSum {
            p: Side::new(p),
            q: Side::new(q),
            theta_acc: 0.0,

            scratch: Some(Box::default()),
            fresh: Vec::new(),
            zeros: None,
            tick: 0,
            axis_run: None,
            axis_since: 0,
            backoff: Backoff::default(),
            step: 0,
            ops,
            config,
        };
        s.load_overlay(overlay);
        Ok(s)
    }

    fn load_overlay(&mut self, overlay: Overlay) {
        self.p.ee.iter_mut().for_each(Vec::clear);
        self.q.ee.iter_mut().for_each(Vec::clear);
        for &(e, e2) in &overlay.ee {
            self.p.ee[e as usize].push(e2);
            self.q.ee[e2 as usize].push(e);
        }
        // Room for crossings to come, so that later toggles rarely grow a
        // list (an allocation in the update path): at least 8 in all and 4
        // spare. (Asking for 8 more every time reallocated every list at
        // each reload, such as the first step after a degenerate start.)
        for list in self.p.ee.iter_mut().chain(self.q.ee.iter_mut()) {
            list.reserve(8usize.saturating_sub(list.len()).max(4));
        }
        self.p.assign = overlay.fv;
        self.q.assign = overlay.vf;
        self.p.tie_axis.fill(NO_AXIS);
        self.q.tie_axis.fill(NO_AXIS);
        let rot = self.ops.relative.matrix();
        let inv = rot.transpose();
        for f in 0..self.p.assign.len() {
            self.p.margin[f] = self.margin_of_p_face(rot, f);
            self.p.margin_at[f] = self.theta_acc;
        }
        for g in 0..self.q.assign.len() {
            self.q.margin[g] = self.margin_of_q_face(inv, g);
            self.q.margin_at[g] = self.theta_acc;
        }
        self.p.reschedule();
        self.q.reschedule();
    }

    #[inline]
    fn margin_of_p_face(&self, rot: DMat3, f: usize) -> f64 {
        let x = rot * self.ops.p.unit_normal(f);
        margin(&self.ops.q, &self.q.arcs, self.p.assign[f], x)
    }

    #[inline]
    fn margin_of_q_face(&self, inv: DMat3, g: usize) -> f64 {
        let x = inv * self.ops.q.unit_normal(g);
        margin(&self.ops.p, &self.p.arcs, self.q.assign[g], x)
    }

    /// P's current pose.
    pub fn pose_p(&self) -> Pose {
        self.ops.pose_p
    }
    /// Q's current pose.
    pub fn pose_q(&self) -> Pose {
        self.ops.pose_q
    }
    /// P.
    pub fn p(&self) -> &Polytope {
        &self.ops.p
    }
    /// Q.
    pub fn q(&self) -> &Polytope {
        &self.ops.q
    }
    /// The tuning in force.
    pub fn config(&self) -> DynamicConfig {
        self.config
    }

    /// Turns P further by `r` (applied after its current rotation, about the
    /// origin of the world frame; P's translation is kept). See
    /// [`DynamicSum::set_pose`].
    pub fn rotate_p_by(&mut self, r: Rotation) -> UpdateReport {
        let mut pose = self.ops.pose_p;
        pose.rotation = pose.rotation.then(&r);
        self.set_pose(pose, self.ops.pose_q)
    }

    /// Moves P to `pose_p`, keeping Q where it is. See
    /// [`DynamicSum::set_pose`].
    pub fn set_pose_p(&mut self, pose_p: Pose) -> UpdateReport {
        self.set_pose(pose_p, self.ops.pose_q)
    }

    /// Moves both bodies and repairs the overlay: the paper's Algorithm 4.1
    /// (see the module docs for why every step is exact).
    ///
    /// Infallible: no input makes an update fail. Poses are not range
    /// checked here (the overlay depends on the rotations alone); posed
    /// coordinates beyond `f64` surface as
    /// [`crate::sum::MeshError::OutOfRange`] from [`Self::try_to_mesh`]. If
    /// an internal invariant failed while repairing (an arc walk finding no
    /// exit: a bug, never a property of the input), the step is recomputed
    /// from scratch instead, still exactly, and the report says so in
    /// [`UpdateReport::recovered`].
    ///
    /// # Panics
    /// Only if the static `walk` and the brute-force method both fail on the
    /// same poses as well, which would be a bug in dymsum (please report the
    /// poses); no input is known to do this.
    pub fn set_pose(&mut self, pose_p: Pose, pose_q: Pose) -> UpdateReport {
        let mut report = UpdateReport::default();
        self.set_pose_into(pose_p, pose_q, &mut report);
        report
    }

    /// [`DynamicSum::set_pose`], writing the report into `report` (cleared
    /// first) and reusing its vectors' capacity: with a report kept from
    /// step to step, an incremental update makes no heap allocation once
    /// its buffers have grown (a step recomputed from scratch does
    /// allocate).
    ///
    /// ```
    /// use dymsum::{DVec3, DynamicSum, Polytope, Pose, Rotation, UpdateReport};
    /// let pts: Vec<[f64; 3]> = (0..8).map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64]).collect();
    /// let cube = Polytope::from_points(&pts)?;
    /// let mut sum = DynamicSum::new(&cube, Pose::IDENTITY, &cube, Pose::IDENTITY)?;
    /// let mut report = UpdateReport::default();
    /// let step = Rotation::from_axis_angle(DVec3::new(1.0, 2.0, 3.0), 0.01).expect("a unit axis");
    /// let mut pose = Pose::IDENTITY;
    /// for _ in 0..10 {
    ///     pose.rotation = pose.rotation.then(&step);
    ///     sum.set_pose_into(pose, Pose::IDENTITY, &mut report);
    ///     assert!(report.fv_errors <= report.removed.len());
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Panics
    /// As [`DynamicSum::set_pose`].
    pub fn set_pose_into(&mut self, pose_p: Pose, pose_q: Pose, report: &mut UpdateReport) {
        report.clear();
        // Line 1: Rotate (the new relative rotation; P's normals and arcs are
        // turned when read).
        let Some((old, theta)) = self.rotate(pose_p, pose_q) else {
            return;
        };
        report.step_angle = theta;
        if self.must_recompute(theta) {
            return self.recompute(report);
        }
        // Line 2: FindErrors (§4.1), each fv-error corrected where found (§4.2).
        let step = self.step_bounds(old, theta);
        // Taken out of `self` for the step (the passes borrow `self`): a
        // box, so that taking and restoring it moves a pointer, not the
        // buffers' headers (memory copies that cost tiny sums 7% of a step).
        let mut scratch = self.scratch.take().unwrap_or_default();
        self.find_errors(&step, &mut scratch.scans);
        report.record_fv_errors(&scratch.scans);
        // Line 3: CorrectErrors for the ee-pairs (§4.3), or fall back.
        self.arcs_at_risk(&scratch.scans, &mut scratch.at_risk);
        let outcome = if self.too_many_at_risk(&scratch.at_risk) {
            self.note_fallback(step.axis, theta);
            Err(None)
        } else {
            self.backoff = Backoff::default();
            self.correct_ee_errors(&scratch, report).map_err(Some)
        };
        self.scratch = Some(scratch);
        if let Err(bug) = outcome {
            report.recovered = bug.map(|b| b.to_string());
            self.recompute(report);
        }
    }

    /// Algorithm 4.1, line 1: stores the poses and turns P's normals and arcs
    /// to the new relative rotation. Returns the old relative rotation and
    /// the step's angle, or `None` when the relative rotation did not change
    /// (a translation or a common rotation of both bodies changes no facet).
    fn rotate(&mut self, pose_p: Pose, pose_q: Pose) -> Option<(Rotation, f64)> {
        let old = self.ops.relative;
        let new = relative_rotation(&pose_p, &pose_q);
        self.ops.pose_p = pose_p;
        self.ops.pose_q = pose_q;
        if new == old {
            return None;
        }
        self.ops.set_relative(new);
        Some((old, old.angle_to(&new)))
    }

    /// The posed operands (for readers of the current state).
    pub(crate) fn operands(&self) -> &crate::sum::Operands {
        &self.ops
    }

    /// Whether the normal of face `f` of P (`of_q` false) or of Q (`of_q`
    /// true) is certified strictly inside its cell of the other map at the
    /// current poses (module docs, "Certified normals"): its lazy margin,
    /// less the rotation accumulated since it was computed, exceeds its
    /// direction error and twice the margins' slack. `false` proves
    /// nothing.
    #[inline]
    pub(crate) fn normal_strictly_inside(&self, of_q: bool, f: usize) -> bool {
        let side = if of_q { &self.q } else { &self.p };
        side.margin[f] - (self.theta_acc - side.margin_at[f]) > side.dir_err[f] + 2.0 * SLACK
    }

    /// The current overlay, with ee-pairs sorted.
    pub fn overlay(&self) -> Overlay {
        let mut out = Overlay::default();
        self.overlay_into(&mut out);
        out
    }

    /// [`Self::overlay`] into `out`, reusing its buffers (no allocation
    /// once they are large enough). The pairs come out sorted by edge of P
    /// already, so only each edge's few pairs are sorted.
    pub(crate) fn overlay_into(&self, out: &mut Overlay) {
        out.fv.clear();
        out.fv.extend_from_slice(&self.p.assign);
        out.vf.clear();
        out.vf.extend_from_slice(&self.q.assign);
        out.ee.clear();
        for (e, l) in self.p.ee.iter().enumerate() {
            let from = out.ee.len();
            out.ee.extend(l.iter().map(|&e2| (e as u32, e2)));
            out.ee[from..].sort_unstable();
        }
    }

    /// The current facets in canonical order (as [`MinkowskiSum::facets`]).
    pub fn facets(&self) -> Vec<Facet> {
        self.overlay().facets()
    }

    /// Number of facets.
    pub fn facet_count(&self) -> usize {
        self.p.assign.len() + self.q.assign.len() + self.p.ee.iter().map(Vec::len).sum::<usize>()
    }

    /// The current sum as a static [`MinkowskiSum`] (no recomputation).
    pub fn sum(&self) -> MinkowskiSum {
        MinkowskiSum::from_overlay(self.ops.clone(), self.overlay())
    }

    /// The merged, validated mesh of the current sum (see
    /// [`MinkowskiSum::try_to_mesh`]).
    ///
    /// # Errors
    /// As [`MinkowskiSum::try_to_mesh`]:
    /// [`crate::sum::MeshError::PrecisionLost`] when the rounded vertices
    /// collapse (the sum is too far from the origin for its size),
    /// [`crate::sum::MeshError::OutOfRange`] when a vertex of the sum
    /// overflows `f64`; [`crate::sum::MeshError::Merge`] and
    /// [`crate::sum::MeshError::Invalid`] are internal errors.
    pub fn try_to_mesh(&self) -> Result<crate::mesh::PolygonMesh, crate::sum::MeshError> {
        self.sum().try_to_mesh()
    }
    /// [`Self::try_to_mesh`] with the coordinates' rounding relative to the
    /// sum's size (see [`MinkowskiSum::mesh_with_precision`]).
    ///
    /// # Errors
    /// The same as [`Self::try_to_mesh`].
    pub fn mesh_with_precision(&self) -> Result<crate::sum::SumMesh, crate::sum::MeshError> {
        self.sum().mesh_with_precision()
    }

    /// Checks the internal state: the two ee indices agree, and the current
    /// sum passes [`MinkowskiSum::sanity_check`].
    ///
    /// # Errors
    /// The first broken invariant ([`crate::sanity::SanityError`]).
    pub fn sanity_check(&self) -> Result<(), crate::sanity::SanityError> {
        let mut a: Vec<(u32, u32)> = self.overlay().ee;
        let mut b: Vec<(u32, u32)> = self
            .q
            .ee
            .iter()
            .enumerate()
            .flat_map(|(e2, l)| l.iter().map(move |&e| (e, e2 as u32)))
            .collect();
        a.sort_unstable();
        b.sort_unstable();
        if a != b {
            return Err(crate::sanity::SanityError::EeIndicesDisagree);
        }
        self.sum().sanity_check()
    }
}

/// The buffers of one step: both FindErrors passes and the arcs at risk.
#[derive(Clone, Debug, Default)]
struct Scratch {
    scans: [SideScan; 2],
    at_risk: [Vec<u32>; 2],
}

/// Which polytope's arc is re-walked.
#[derive(Clone, Copy)]
enum Which {
    P,
    Q,
}

/// One operand's half of the state, the same for P and Q: where each of its
/// face normals lies in the other map, which arcs of the other map each of
/// its arcs crosses, its own cells' arc normals (for the other operand's
/// margins), and per face the lazy margin and the persistent-tie
/// certificate.
#[derive(Clone, Debug)]
struct Side {
    /// Per face: the vertex of the other polytope whose cell holds its normal.
    assign: Vec<u32>,
    /// Per edge: the edges of the other polytope whose arcs its arc crosses.
    ee: Vec<Vec<u32>>,
    /// Unit normals of this polytope's ring arcs, oriented into the cells.
    arcs: Vec<DVec3>,
    /// Per face: bound on its float unit normal's direction error.
    dir_err: Vec<f64>,
    /// Per face: its last margin and the accumulated rotation then.
    margin: Vec<f64>,
    margin_at: Vec<f64>,
    /// Per edge: the last step that queued its arc for a re-walk.
    stamp: Vec<u32>,
    /// Per face: the last step whose certified single crossing it made,
    /// and the arc it crossed then.
    crossed: Vec<(u32, u32)>,
    /// Per face: the rotation about the coordinate axis `tie_axis` it can
    /// still absorb with its persistent ties certified (see
    /// `ties::stays_in_cell_tied`); `NO_AXIS` when not certified that way;
    /// and the incremental step that computed it.
    tie_margin: Vec<f64>,
    tie_axis: Vec<u8>,
    tie_tick: Vec<u64>,
    /// The kinetic schedule: per face, the accumulated rotation by which it
    /// must be visited ([`schedule`]).
    schedule: Deadlines,
    /// Faces keyed by a persistent-tie deadline (valid for the current run
    /// of steps about one coordinate axis only), and a flag per face.
    tie_keyed: Vec<u32>,
    in_tie_keyed: Vec<bool>,
    /// Reused buffer of the faces due in a step.
    due: Vec<u32>,
    /// `true`: FindErrors passes over all normals and `schedule` is not
    /// kept; `false`: it visits the normals `schedule` says are due.
    scanning: bool,
}

impl Side {
    fn new(poly: &Polytope) -> Side {
        let (faces, edges) = (poly.face_count(), poly.edge_count());
        Side {
            assign: Vec::new(),
            ee: vec![Vec::new(); edges],
            arcs: arc_normals(poly),
            dir_err: direction_errors(poly),
            margin: vec![0.0; faces],
            margin_at: vec![0.0; faces],
            stamp: vec![0; edges],
            crossed: vec![(0, 0); faces],
            tie_margin: vec![0.0; faces],
            tie_axis: vec![NO_AXIS; faces],
            tie_tick: vec![0; faces],
            schedule: Deadlines::default(),
            tie_keyed: Vec::new(),
            in_tie_keyed: vec![false; faces],
            due: Vec::new(),
            scanning: true,
        }
    }

    /// The deadline of face `f` from its lazy margin alone: the accumulated
    /// rotation at which it may first be at risk.
    fn margin_deadline(&self, f: usize) -> f64 {
        self.margin_at[f] + self.margin[f] - self.dir_err[f]
    }

    /// After all margins were recomputed: back to passes over all normals
    /// (no tie certificate survives); the schedule starts again when few
    /// normals are due.
    fn reschedule(&mut self) {
        self.scanning = true;
        self.forget_tie_keys();
    }

    fn forget_tie_keys(&mut self) {
        for &f in &self.tie_keyed {
            self.in_tie_keyed[f as usize] = false;
        }
        self.tie_keyed.clear();
    }

    /// Leaves passes for the kinetic schedule after a pass in `step`: every
    /// face keyed by its deadline, in O(n).
    fn start_schedule(&mut self, step: &find_errors::StepBounds) {
        self.scanning = false;
        self.forget_tie_keys();
        let n = self.assign.len();
        for f in 0..n {
            if self.key_of(f, step) > self.margin_deadline(f) {
                self.in_tie_keyed[f] = true;
                self.tie_keyed.push(f as u32);
            }
        }
        let mut schedule = std::mem::take(&mut self.schedule);
        schedule.rebuild(n, step.theta, |f| self.key_of(f, step));
        self.schedule = schedule;
        // At most every normal is due in a step: no growth later.
        self.due.reserve(n);
    }

    /// The deadline of face `f` after `step`: its margin's, or the later
    /// one of its persistent-tie certificate while that is valid (this run
    /// of steps about one coordinate axis).
    fn key_of(&self, f: usize, step: &find_errors::StepBounds) -> f64 {
        let key = self.margin_deadline(f);
        let tie_valid = step.axis.is_some_and(|k| self.tie_axis[f] == k as u8)
            && self.tie_tick[f] >= step.run_start;
        if tie_valid {
            key.max(self.margin_at[f] + self.tie_margin[f] - self.dir_err[f])
        } else {
            key
        }
    }

    /// Re-keys face `f` after its visit in `step`.
    fn rekey(&mut self, f: usize, step: &find_errors::StepBounds) {
        let key = self.key_of(f, step);
        if key > self.margin_deadline(f) && !self.in_tie_keyed[f] {
            self.in_tie_keyed[f] = true;
            self.tie_keyed.push(f as u32);
        }
        self.schedule.set(f as u32, key);
    }

    /// The run of steps about one coordinate axis ended: keys taken from
    /// tie certificates fall back to the margins' deadlines.
    fn end_tie_keys(&mut self) {
        let mut keyed = std::mem::take(&mut self.tie_keyed);
        for &f in &keyed {
            self.in_tie_keyed[f as usize] = false;
            let key = self.margin_deadline(f as usize);
            self.schedule.set(f, key);
        }
        keyed.clear();
        self.tie_keyed = keyed;
    }

    /// Subtracts `shift` from the accumulated rotation of every margin and
    /// deadline (see [`schedule::REBASE_AFTER`]).
    fn rebase(&mut self, shift: f64) {
        for at in &mut self.margin_at {
            *at -= shift;
        }
        if !self.scanning {
            self.schedule.shift(shift);
        }
    }
}
