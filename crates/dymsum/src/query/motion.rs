//! Certified motion checks: whether a body moving straight from one pose
//! to another touches any obstacle at any instant, never by sampling.
//!
//! # The motion
//! Between `from` (at `t = 0`) and `to` (at `t = 1`) the translation moves
//! linearly and the rotation by spherical linear interpolation of the
//! unit quaternions along the shorter arc: exactly OMPL's interpolation of
//! its SE(2) and SE(3) states (SE(2): the yaw along the shorter way, which
//! is slerp between rotations about z). The body's points move as
//! `x(t) = R(t) p + T(t)`.
//!
//! # The arc
//! Which way the rotation turns is decided once, from the rotations *as
//! given* ([`Rotation::quat_as_given`]: the quaternions the caller passed,
//! or converted from the matrices they passed, before the snapping of tiny
//! components and the canonical sign that [`Rotation`] applies): the exact
//! sign of the dot product of the two quaternions
//! ([`crate::kernel::predicates::dot4`]); when it is negative the second is
//! negated (the shorter arc), when it is exactly zero (a half turn) it is
//! kept, so the rotation turns from the first quaternion towards the
//! second as given. Nothing done afterwards changes the arc. This is
//! OMPL's rule (`SO3StateSpace::interpolate` negates when its float dot
//! product is negative) decided exactly: at `180° + 1e-12°` about z
//! (`w = −8.6e-15`) the motion turns the short way, clockwise, although
//! the snapped rotation is an exact half turn. (`dymsum.ompl` follows
//! OMPL's float decision itself, and OMPL's rule of keeping the first
//! rotation when `|dot| > 1 − 1e-9`; see its module docs.)
//!
//! # The answer
//! [`MotionCheck::Free`]: no contact at any `t` in `[0, 1]`, certified; or
//! [`MotionCheck::Collides`] with `t_safe < t_contact`, `t_contact − t_safe`
//! at most the tolerance: every `t ≤ t_safe` is certified free (what OMPL
//! calls the last valid state) and at `t_contact` the exact query
//! ([`ConvexPair::intersects`]) says the body touches or overlaps an
//! obstacle. A body that already collides at `t = 0` gives
//! `t_safe = None`, `t_contact = 0`.
//!
//! # Why "free" is certain (the bound)
//! Over an interval `[a, b]` every point of a body piece `P` (`r` its
//! largest vertex norm about the body's origin) stays within the margin
//! `s + e` of `query::interval_search` (`s` the sagitta of the turn over
//! the interval, `e` the float poses' rounding, both rounded up; derived
//! there, once for both motion checkers) of
//!
//! `H ⊕ [T(a), T(b)]`, `H = conv(R(a) P ∪ R(b) P)`,
//!
//! a convex set given by its support function
//! `h(d) = max(h_P(R(a)ᵀ d), h_P(R(b)ᵀ d)) + max(d · T(a), d · T(b))`.
//! GJK between that set and an obstacle piece `O` proposes a unit direction
//! `n`; the *gap* `min_{H ⊕ [T]} n · x − max_O n · o` is then bounded
//! from below rigorously (the near-extreme searches of
//! [`crate::query::proximity::support`], whose maxima are certified, on the unposed piece
//! and the obstacle's vertices), and if it exceeds `s + e`, the distance
//! between the moving piece and `O` stays positive over the whole
//! interval (`R̃`, `T̃` the float poses of [`Motion::at`] are what `H` and
//! the translations are built from; `e` covers their distance from the
//! exact motion's). The gap is taken about the obstacle ball's
//! centre `c` (the same difference about any point): the translations and
//! the obstacle's vertices less `c`, rounded (an exact translate of the
//! obstacle within `2u` of its scale per vertex, which the near-extreme
//! search allows for), so every dot product and sum rounds by a few ulps of
//! the local sizes, not of the coordinates, and those roundings are
//! subtracted from the gap.
//!
//! GJK's direction is off by about `ε · size / distance`, so when the
//! pieces come within about `√ε · size` of each other the gap along it can
//! fall short of the true distance. Where the swept set and the obstacle
//! are apart in floats but the gap does not certify, a second bound is
//! tried (conservative advancement): over `[a, b]` a point `p` of the piece
//! moves by at most `|T(b) − T(a)| + r δ` from its place at `a`
//! (`|(R(t) − R(a)) p| ≤ 2 r sin(δ/2) ≤ r δ`, and the translation is
//! linear; `δ` the turn, rounded up, of `query::interval_search`), so the
//! interval is free when the exact distance at `a`
//! ([`ConvexPair::query`]) exceeds that, plus the rounding of the
//! distance (taken as `10⁻¹²` of the coordinates' scale, far above it:
//! far from the origin this bound rarely helps, the gap does) and three
//! times the pose error `e` (the pose at `a`, and both translations).
//!
//! # Between the ends
//! Where the swept hull's gap along GJK's direction, or along a feature
//! axis, does not exceed `s + e`, the same axis is tried against the bow
//! of `query::interval_search` ("The bow"): the gaps of the piece posed
//! at `a` alone and at `b` alone ([`GapTerms`], the same terms and
//! roundings as the swept hull's, per end), each less `e|n|`, against
//! `|n| δ² r / 2` with `r` the piece's reach. It certifies an interval
//! that leaves a grazing pose to first order along a fixed axis (a
//! translation away, a turn about an axis through the contact). Where
//! GJK finds the swept hull overlapping the obstacle in floats, which its
//! decoupled turn and translation allow where the motion does not (a turn
//! towards the obstacle while moving away from it), the direction of GJK
//! between the piece posed at `a` and the obstacle, and its feature axes,
//! are tried against the bow instead: any axis gives valid gaps.
//!
//! A body face leaving an obstacle's corner while turning tilts against
//! every fixed axis by its length times the turn, so the faces around the
//! piece's support vertices are tried in the body's frame too, where
//! they stand still (as `scene::sweep` does for triangles, "In the body's
//! frame"). Along a body-frame axis `m`, the gap at an end is `min_p m·p −
//! max_o (R m)·(o − T)`: the piece's part is a near-extreme search of the
//! unposed piece along `−m`; the obstacle's, one along the float `R̃ m`
//! about the obstacle ball's centre `c`, plus `R̃m·(c − T̃)` and its
//! rounding. `R̃ m` is within `681u |m|` of `R m` and `T̃` within `6u (M +
//! D)` of `T` (`query::rounding`), so with `ρ ≥ |o − T|` for every
//! obstacle point (`|c − T̃| + ` the ball's radius `+ 6u (M + D)`, rounded
//! up; `o − T(λ)` is linear in `λ`, so the ends' largest bounds it over
//! the interval) each end's
//! gap is at least the computed one less `pose_rounding_bound(ρ)`. An
//! obstacle point seen from the body, `R(t)ᵀ (o − T(t))`, strays from its
//! chord by at most `λ(1 − λ) (δ² ρ / 2 + δ |T(b) − T(a)|)` (the bow in
//! the body's frame, `scene::sweep`, "Between the ends"), `|T(b) − T(a)|`
//! at most the float difference's norm (rounded up) plus two translation
//! roundings. On the robot-part benchmark's seventh sample it took two
//! convex pairs from 1,452 and 516 µs a decision to 61 and 56.
//!
//! # Independent review (2026-11-30): between the ends
//! Of the per-end gaps (bit for bit the swept hull's gap when combined),
//! the fallback where GJK finds the swept hull overlapping, and the test
//! in the body's frame. Verified: the hints only seed certified
//! near-extreme searches, any axis gives valid gaps; `−near_max(−m)`
//! bounds the piece's side; `R̃ m` and `T̃` are used consistently, their
//! errors inside `pose_rounding_bound(ρ)`; the ball's radius bounds the
//! obstacle about its centre; the ends' `ρ` bounds the interval (`o −
//! T(λ)` is linear); the `|m|` factor and the sign. Found: `ρ` bounded
//! `|o − T̃|`, not `|o − T|` for the exact `T` (a few ulps of the
//! coordinates; now `6u (M + D)` more), and the feature axes were
//! normalised with squares that underflow below about `10⁻⁷⁷`
//! (`NearestAxes::offer` now divides by the largest magnitude first).
//! Tried to break it: about 2,900 motions whose obstacle corner dips into
//! the body between clear ends, scales `10⁻¹⁵⁰` to `10¹⁰⁰`, turns to
//! nearly π: none called free (a halved bow gave 833 wrong answers);
//! pinned as `tests/review_convex_dips.rs`.
//!
//! # The search
//! Each piece of the body against each obstacle piece runs the interval
//! search of `query::interval_search` (left to right over `[0, limit]`,
//! halving, probes ahead when stuck, the budget, undecided below
//! [`MIN_WIDTH`](crate::query::MIN_WIDTH); its soundness argument is
//! there), with the bound above certifying an interval and the pair's
//! exact query
//! ([`ConvexPair::intersects`]) checking a time. The pairs share one
//! budget, and each is searched only up to the earliest contact found so
//! far (`limit`): the answer's `t_contact` is the earliest bracketed, and
//! its `t_safe` the least certified end over the pairs that bracketed a
//! contact (every other pair is certified free up to `limit`, beyond
//! `t_contact`). When the budget runs out inside one pair, the pairs not
//! yet searched are each tried by one interval up to that pair's
//! certified end, else the check is certified only at the start.

use crate::body::ConvexUnion;
use crate::kernel::predicates::{dot4, Sign};
use crate::kernel::rotation::Pose;
use crate::kernel::rotation::Rotation;
use crate::polytope::Polytope;
use crate::query::answer::Proximity;
use crate::query::checker::{Checker, MotionCheck};
use crate::query::error::{MotionError, QueryError};
use crate::query::interval_search::{
    bow, bowed_chord_stays_positive, first_contact, Pending, Stop, Sweep, SweepMargin,
    DEFAULT_BUDGET,
};
use crate::query::pair::ConvexPair;
use crate::query::pair::QueryStats;
use crate::query::proximity::support::{
    climb, climb_unposed, dot_error, near_max, Marks, NearestAxes,
};
use crate::query::rounding::{norm_up, pose_rounding_bound};
use glam::DQuat;
use glam::DVec3;

/// How many feature axes [`PieceSearch::feature_gap`] tries.
const FEATURE_AXES: usize = 4;

/// A straight motion between two poses (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    q0: DQuat,
    q1: DQuat,
    t0: DVec3,
    t1: DVec3,
    /// Half the rotation angle between the ends (the quaternions' angle).
    half: f64,
}

impl Motion {
    /// The motion from `from` to `to`.
    pub fn new(from: Pose, to: Pose) -> Motion {
        let (g0, g1) = (from.rotation.quat_as_given(), to.rotation.quat_as_given());
        let (q0, mut q1) = (g0.normalize(), g1.normalize());
        // The arc, from the quaternions as given (module docs, "The arc"):
        // the exact sign of their dot product, before any rounding.
        if dot4(g0.to_array(), g1.to_array()) == Sign::Negative {
            q1 = -q1; // the shorter arc
        }
        // The angle between unit quaternions, accurately for small angles.
        let half = 2.0 * ((q1 - q0).length() / 2.0).clamp(0.0, 1.0).asin();
        Motion {
            q0,
            q1,
            t0: from.translation,
            t1: to.translation,
            half,
        }
    }

    /// The pose at `t` (in `[0, 1]`).
    pub fn at(&self, t: f64) -> Pose {
        let q = if self.half < 1e-9 {
            (self.q0 * (1.0 - t) + self.q1 * t).normalize()
        } else {
            let s = self.half.sin();
            let (w0, w1) = (((1.0 - t) * self.half).sin() / s, (t * self.half).sin() / s);
            (self.q0 * w0 + self.q1 * w1).normalize()
        };
        let translation = if t == 1.0 {
            self.t1
        } else {
            self.t0 + (self.t1 - self.t0) * t
        };
        Pose::new(Rotation::from_quat(q), translation)
    }

    /// The whole motion's rotation angle (radians, at most π).
    pub fn angle(&self) -> f64 {
        2.0 * self.half
    }

    /// `(M, D)`: the largest absolute coordinate of the two end
    /// translations, and of their float difference (the sizes of the
    /// rounding bound of the float poses, `query::rounding`).
    pub(crate) fn translation_extent(&self) -> (f64, f64) {
        let m = self.t0.abs().max(self.t1.abs()).max_element();
        let d = (self.t1 - self.t0).abs().max_element();
        (m, d)
    }
}

/// What the search needs of one piece pair.
struct PieceSearch<'a> {
    pair: &'a ConvexPair,
    body: &'a Polytope,
    obstacle: &'a Polytope,
    /// The body piece's reach about its origin (rounded up).
    reach: f64,
    /// The largest absolute vertex coordinate of the body piece and of the
    /// obstacle piece (for the dot products' error bounds).
    scales: (f64, f64),
    /// The obstacle's bounding ball: centre and radius (world). The centre
    /// is also the local origin the gap is computed about.
    obstacle_ball: (DVec3, f64),
    /// The largest absolute coordinate of the obstacle piece's vertices
    /// less the ball's centre, as rounded.
    obstacle_local_scale: f64,
    /// The motion checked.
    motion: &'a Motion,
    /// The body piece's margin over the motion (`query::interval_search`).
    margin: SweepMargin,
}

/// The buffers of a check (kept by a [`MotionChecker`] between checks).
#[derive(Default)]
struct Scratch {
    marks_a: Marks,
    marks_b: Marks,
    set: Vec<u32>,
    stack: Vec<Pending>,
}

/// A body and obstacles prepared for many motion checks (a planner's
/// motion validator): the piece pairs are set up once.
///
/// A bar turning about its centre past a small box: both end poses are
/// free and so is the halfway pose, but the motion sweeps through the box
/// (a sampling check at these three poses would miss it).
///
/// ```
/// use dymsum::query::{ConvexUnion, MotionCheck, MotionChecker};
/// use dymsum::{DVec3, Polytope, Pose, Rotation};
/// let cuboid = |lo: [f64; 3], hi: [f64; 3]| {
///     let corners: Vec<[f64; 3]> = (0..8)
///         .map(|i| {
///             let pick = |k: usize| if i >> k & 1 == 0 { lo[k] } else { hi[k] };
///             [pick(0), pick(1), pick(2)]
///         })
///         .collect();
///     Polytope::from_points(&corners)
/// };
/// let bar = ConvexUnion::from(cuboid([-2.0, -0.05, -0.05], [2.0, 0.05, 0.05])?);
/// let block = ConvexUnion::from(cuboid([1.7, 0.6, -1.0], [1.9, 0.8, 1.0])?);
/// let turn = |deg: f64| {
///     Pose::new(Rotation::from_axis_angle(DVec3::Z, deg.to_radians()).unwrap(), DVec3::ZERO)
/// };
/// let checker = MotionChecker::new(&bar, &[block])?;
/// for deg in [0.0, 45.0, 90.0] {
///     assert!(!checker.collides_at(turn(deg))?); // free at both ends and halfway
/// }
/// match checker.check(turn(0.0), turn(90.0), 1e-6)? {
///     MotionCheck::Collides { t_safe, t_contact } => {
///         let t_safe = t_safe.unwrap();
///         assert!(t_safe < t_contact && t_contact - t_safe <= 1e-6);
///         assert!(checker.collides_at(turn(90.0 * t_contact))?); // exactly in contact
///     }
///     MotionCheck::Free => panic!("the bar sweeps through the block"),
/// }
/// assert_eq!(checker.check(turn(-90.0), turn(-1.0), 1e-6)?, MotionCheck::Free);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct MotionChecker {
    body: ConvexUnion,
    obstacles: Vec<ConvexUnion>,
    pairs: Vec<(usize, usize, usize)>,
    prepared: Vec<ConvexPair>,
    reach: Vec<f64>,
    body_scale: Vec<f64>,
    balls: Vec<Vec<(DVec3, f64)>>,
    obstacle_scale: Vec<Vec<f64>>,
    obstacle_local_scale: Vec<Vec<f64>>,
    pool: std::sync::Mutex<Vec<Scratch>>,
    budget: u64,
    steps: std::sync::atomic::AtomicU64,
}

impl std::fmt::Debug for MotionChecker {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MotionChecker")
            .field("body_pieces", &self.body.pieces().len())
            .field("obstacles", &self.obstacles.len())
            .finish()
    }
}

/// The largest distance of a vertex from `c`, rounded up: the lengths are
/// taken after scaling by a power of two (exact), so that no square
/// underflows (a 1e-162 body's lengths did, and its reach came out below
/// its vertices' norms) or overflows.
fn radius_about(p: &Polytope, c: DVec3) -> f64 {
    let m = p
        .vertices()
        .iter()
        .map(|&v| (v - c).abs().max_element())
        .fold(0.0, f64::max);
    let (down, up) = power_of_two_scale(m);
    let r = p
        .vertices()
        .iter()
        .map(|&v| ((v - c) * down).length())
        .fold(0.0, f64::max);
    r * up * (1.0 + 1e-12) + 1e-300
}

/// `(2^-e, 2^e)` with `2^e` near `m` (`e` within ±1000, so both are normal
/// numbers): multiplying by the first brings coordinates of magnitude up
/// to `m` near 1 exactly (a power of two), where squares neither overflow
/// nor underflow; `(1, 1)` for a zero or non-finite `m`.
fn power_of_two_scale(m: f64) -> (f64, f64) {
    if m == 0.0 || !m.is_finite() {
        return (1.0, 1.0);
    }
    let e = (m.log2().floor() as i32).clamp(-1000, 1000);
    (2f64.powi(-e), 2f64.powi(e))
}

impl MotionChecker {
    /// Prepares `body` (the moving union, in its own frame) against
    /// `obstacles` (unions placed in the world frame).
    ///
    /// # Errors
    /// Those of [`ConvexPair::new`] (not expected for valid polytopes).
    pub fn new(body: &ConvexUnion, obstacles: &[ConvexUnion]) -> Result<MotionChecker, QueryError> {
        let mut pairs = Vec::new();
        let mut prepared = Vec::new();
        for (i, p) in body.pieces().iter().enumerate() {
            for (j, o) in obstacles.iter().enumerate() {
                for (k, q) in o.pieces().iter().enumerate() {
                    pairs.push((i, j, k));
                    prepared.push(ConvexPair::new(p, q)?);
                }
            }
        }
        let reach = body
            .pieces()
            .iter()
            .map(|p| radius_about(p, DVec3::ZERO))
            .collect();
        let scale = |p: &Polytope| {
            p.vertices()
                .iter()
                .map(|v| v.abs().max_element())
                .fold(0.0, f64::max)
        };
        let body_scale = body.pieces().iter().map(scale).collect();
        let obstacle_scale = obstacles
            .iter()
            .map(|o| o.pieces().iter().map(scale).collect())
            .collect();
        let balls: Vec<Vec<(DVec3, f64)>> = obstacles
            .iter()
            .map(|o| {
                o.pieces()
                    .iter()
                    .map(|q| {
                        let n = q.vertex_count() as f64;
                        let c = q.vertices().iter().fold(DVec3::ZERO, |s, &v| s + v) / n;
                        (c, radius_about(q, c))
                    })
                    .collect()
            })
            .collect();
        let obstacle_local_scale = obstacles
            .iter()
            .zip(&balls)
            .map(|(o, b)| {
                o.pieces()
                    .iter()
                    .zip(b)
                    .map(|(q, &(c, _))| {
                        q.vertices()
                            .iter()
                            .map(|&v| (v - c).abs().max_element())
                            .fold(0.0, f64::max)
                    })
                    .collect()
            })
            .collect();
        Ok(MotionChecker {
            body: body.clone(),
            obstacles: obstacles.to_vec(),
            pairs,
            prepared,
            reach,
            body_scale,
            balls,
            obstacle_scale,
            obstacle_local_scale,
            pool: std::sync::Mutex::new(Vec::new()),
            budget: DEFAULT_BUDGET,
            steps: std::sync::atomic::AtomicU64::new(0),
        })
    }

    /// The same checker with a work budget of `steps` intervals per check
    /// (at least 1; [`DEFAULT_BUDGET`] unless set): a check that has
    /// examined that many intervals over all piece pairs without a
    /// decision ends with [`MotionError::BudgetExhausted`] and its
    /// certified `t_safe`. The count is deterministic: the same check gives
    /// the same answer on any machine and under any load.
    pub fn with_budget(mut self, steps: u64) -> MotionChecker {
        self.budget = steps.max(1);
        self
    }

    /// The work budget of one check, in intervals ([`Self::with_budget`]).
    pub fn budget(&self) -> u64 {
        self.budget
    }

    /// The intervals examined by all checks so far (the work the budget
    /// counts), for benchmarks and tests.
    pub fn steps(&self) -> u64 {
        self.steps.load(std::sync::atomic::Ordering::Relaxed)
    }

    /// The exact queries' counters summed over the piece pairs
    /// ([`ConvexPair::stats`]): how many the search asked, and how many of
    /// them no certificate could settle (answered from the exhaustive
    /// method instead).
    pub fn stats(&self) -> QueryStats {
        self.prepared
            .iter()
            .map(ConvexPair::stats)
            .fold(QueryStats::default(), |s, p| QueryStats {
                queries: s.queries + p.queries,
                exhaustive_decisions: s.exhaustive_decisions + p.exhaustive_decisions,
                exhaustive_answers: s.exhaustive_answers + p.exhaustive_answers,
                carried_polytopes: s.carried_polytopes + p.carried_polytopes,
                carried_restarts: s.carried_restarts + p.carried_restarts,
            })
    }

    /// Whether the body at `pose` touches or overlaps an obstacle (exact).
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when a posed coordinate overflows.
    pub fn collides_at(&self, pose: Pose) -> Result<bool, QueryError> {
        for pair in &self.prepared {
            if pair.intersects(pose, Pose::IDENTITY)? {
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// The clearance of the body at `pose` from the obstacles: `0` when it
    /// touches or overlaps one, else the least exact distance over the
    /// piece pairs ([`ConvexPair::query`]). For clearance objectives.
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when a posed coordinate overflows.
    pub fn distance_at(&self, pose: Pose) -> Result<f64, QueryError> {
        let mut best = f64::INFINITY;
        for pair in &self.prepared {
            match pair.query(pose, Pose::IDENTITY)? {
                Proximity::Penetrating(_) => return Ok(0.0),
                Proximity::Separated(s) => best = best.min(s.distance),
            }
        }
        Ok(best)
    }

    /// Checks the straight motion from `from` to `to` (module docs) with the
    /// bracket no wider than `tolerance` (in `t`).
    ///
    /// # Errors
    /// [`MotionError::Tolerance`] for a tolerance outside
    /// `[MIN_TOLERANCE, 1)` ([`crate::query::MIN_TOLERANCE`]);
    /// [`MotionError::Query`] when a posed coordinate overflows;
    /// [`MotionError::Undecided`] for a motion grazing an obstacle within
    /// rounding; [`MotionError::BudgetExhausted`] past the budget.
    pub fn check(&self, from: Pose, to: Pose, tolerance: f64) -> Result<MotionCheck, MotionError> {
        MotionError::check_tolerance(tolerance)?;
        if self.collides_at(from)? {
            return Ok(MotionCheck::Collides {
                t_safe: None,
                t_contact: 0.0,
            });
        }
        let motion = Motion::new(from, to);
        let mut scratch = self
            .pool
            .lock()
            .ok()
            .and_then(|mut p| p.pop())
            .unwrap_or_default();
        let mut stack = std::mem::take(&mut scratch.stack);
        let mut best: Option<(f64, f64)> = None;
        let mut frontier = 1.0f64;
        let mut result = Ok(());
        let mut steps_left = self.budget;
        for idx in 0..self.pairs.len() {
            let limit = best.map_or(1.0, |b| b.1);
            let mut sweep = PieceSweep {
                search: self.piece_search(idx, &motion),
                scratch: &mut scratch,
            };
            match first_contact(&mut sweep, limit, 1, tolerance, &mut steps_left, &mut stack) {
                Ok(Some((safe, contact))) => {
                    frontier = frontier.min(safe);
                    if best.is_none_or(|b| contact < b.1) {
                        best = Some((safe, contact));
                    }
                }
                Ok(None) => {}
                Err(Stop::Budget { t_safe }) => {
                    // The pairs not searched yet: certified up to the same
                    // time by one interval each, or only at the start.
                    let mut t_safe = t_safe.min(frontier);
                    for later in idx + 1..self.pairs.len() {
                        if t_safe > 0.0
                            && !self
                                .piece_search(later, &motion)
                                .certified_free(0.0, t_safe, &mut scratch)
                                .unwrap_or(false)
                        {
                            t_safe = 0.0;
                        }
                    }
                    result = Err(MotionError::from_stop(Stop::Budget { t_safe }, self.budget));
                    break;
                }
                Err(stop) => {
                    result = Err(MotionError::from_stop(stop, self.budget));
                    break;
                }
            }
        }
        self.steps.fetch_add(
            self.budget - steps_left,
            std::sync::atomic::Ordering::Relaxed,
        );
        scratch.stack = stack;
        if let Ok(mut p) = self.pool.lock() {
            p.push(scratch);
        }
        result?;
        Ok(match best {
            None => MotionCheck::Free,
            Some((_, contact)) => MotionCheck::Collides {
                t_safe: Some(frontier.min(contact)),
                t_contact: contact,
            },
        })
    }

    /// The search of piece pair `idx` over `motion`.
    fn piece_search<'a>(&'a self, idx: usize, motion: &'a Motion) -> PieceSearch<'a> {
        let (i, j, k) = self.pairs[idx];
        PieceSearch {
            pair: &self.prepared[idx],
            body: &self.body.pieces()[i],
            obstacle: &self.obstacles[j].pieces()[k],
            reach: self.reach[i],
            scales: (self.body_scale[i], self.obstacle_scale[j][k]),
            obstacle_ball: self.balls[j][k],
            obstacle_local_scale: self.obstacle_local_scale[j][k],
            motion,
            margin: SweepMargin::new(motion.angle(), motion.translation_extent(), self.reach[i]),
        }
    }

    /// [`Checker::collides_many`] (here without the trait in scope).
    ///
    /// # Errors
    /// The first error of [`MotionChecker::collides_at`].
    pub fn collides_many(&self, poses: &[Pose]) -> Result<Vec<bool>, QueryError> {
        Checker::collides_many(self, poses)
    }

    /// [`Checker::check_many`] (here without the trait in scope): the
    /// motions `(from, to)` in parallel (rayon), in order.
    ///
    /// # Errors
    /// The first error of [`MotionChecker::check`].
    pub fn check_many(
        &self,
        motions: &[(Pose, Pose)],
        tolerance: f64,
    ) -> Result<Vec<MotionCheck>, MotionError> {
        Checker::check_many(self, motions, tolerance)
    }
}

impl Checker for MotionChecker {
    fn collides_at(&self, pose: Pose) -> Result<bool, QueryError> {
        MotionChecker::collides_at(self, pose)
    }

    fn distance_at(&self, pose: Pose) -> Result<f64, QueryError> {
        MotionChecker::distance_at(self, pose)
    }

    fn check(&self, from: Pose, to: Pose, tolerance: f64) -> Result<MotionCheck, MotionError> {
        MotionChecker::check(self, from, to, tolerance)
    }

    fn budget(&self) -> u64 {
        MotionChecker::budget(self)
    }

    fn with_budget(self, steps: u64) -> MotionChecker {
        MotionChecker::with_budget(self, steps)
    }

    fn steps(&self) -> u64 {
        MotionChecker::steps(self)
    }
}

/// One piece pair's search with the check's buffers: what the interval
/// search runs (`query::interval_search`).
struct PieceSweep<'a, 's> {
    search: PieceSearch<'a>,
    scratch: &'s mut Scratch,
}

impl Sweep for PieceSweep<'_, '_> {
    type Error = QueryError;

    fn certified_free(&mut self, a: f64, b: f64) -> Result<bool, QueryError> {
        self.search.certified_free(a, b, self.scratch)
    }

    fn collides_at_time(&mut self, t: f64) -> Result<bool, QueryError> {
        self.search
            .pair
            .intersects(self.search.motion.at(t), Pose::IDENTITY)
    }
}

/// Checks the straight motion of `body` from `from` to `to` against
/// `obstacles` (module docs): [`MotionChecker::new`] then
/// [`MotionChecker::check`]. Prepare a [`MotionChecker`] for many checks.
///
/// # Errors
/// Those of [`MotionChecker::new`] and [`MotionChecker::check`].
pub fn check_motion(
    body: &ConvexUnion,
    obstacles: &[ConvexUnion],
    from: Pose,
    to: Pose,
    tolerance: f64,
) -> Result<MotionCheck, MotionError> {
    MotionChecker::new(body, obstacles)?.check(from, to, tolerance)
}

/// [`check_motion`] for many motions, in parallel, in order.
///
/// # Errors
/// Those of [`MotionChecker::new`] and [`MotionChecker::check`].
pub fn check_motions(
    body: &ConvexUnion,
    obstacles: &[ConvexUnion],
    motions: &[(Pose, Pose)],
    tolerance: f64,
) -> Result<Vec<MotionCheck>, MotionError> {
    MotionChecker::new(body, obstacles)?.check_many(motions, tolerance)
}

impl PieceSearch<'_> {
    /// Whether the piece cannot touch the obstacle piece for any `t` in
    /// `[a, b]`: the swept-hull bound, then the advancement bound (module
    /// docs).
    fn certified_free(&self, a: f64, b: f64, s: &mut Scratch) -> Result<bool, QueryError> {
        let (pa, pb) = (self.motion.at(a), self.motion.at(b));
        let r = self.reach;
        // The sagitta of the turn over [a, b] and the rounding of the
        // interpolated poses against the exact motion, both rounded up
        // (`query::interval_search`, "The margin").
        let inflate = self.margin.inflation(b - a);
        let (delta, pose_err) = (self.margin.turn(b - a), self.margin.pose_error());
        // The balls first: the piece stays within r of the segment
        // [T(a), T(b)] (any rotation). About the ball's centre `c`: the
        // float distance (the differences, the nearest point's parameter
        // and coordinates, its length) is within 12u (|a'| + |b'|) of the
        // exact distance from `c` to the float segment, taken as 16u.
        let (c, ro) = self.obstacle_ball;
        let (la, lb) = (pa.translation - c, pb.translation - c);
        let seg_err = 8.0 * f64::EPSILON * (la.length() + lb.length());
        if segment_distance(la, lb, DVec3::ZERO) - seg_err
            > (r + ro + inflate) * (1.0 + 1e-12) + 1e-300
        {
            return Ok(true);
        }
        // GJK between the swept hull and the obstacle, then the gap along
        // its direction, bounded rigorously.
        let Some((n, estimate, hints)) = self.separating_direction(pa, pb) else {
            // The swept hull overlaps the obstacle in floats, which its
            // decoupled turn and translation allow where the motion does
            // not (a turn towards the obstacle while moving away): the
            // ends may still be apart (module docs, "Between the ends"),
            // along the direction at the start and its feature axes.
            return Ok(self
                .separating_direction(pa, pa)
                .is_some_and(|(n, _, hints)| {
                    self.ends_apart((a, b), &self.gap_terms(pa, pb, n, hints, s))
                        || self.feature_gap((a, b), (pa, pb), n, hints, inflate, s)
                }));
        };
        // One set of near-extreme bounds for the swept hull and its ends.
        let terms = self.gap_terms(pa, pb, n, hints, s);
        if terms.swept() > inflate || self.ends_apart((a, b), &terms) {
            return Ok(true);
        }
        // Nearly touching, GJK's direction is off by about ε·size/distance:
        // face normals and edge cross products of the features GJK ended
        // on are exact to rounding whatever the distance.
        if self.feature_gap((a, b), (pa, pb), n, hints, inflate, s) {
            return Ok(true);
        }
        // Apart in floats by more than the inflation but not certified
        // (GJK's direction is off by about ε·size/distance when nearly
        // touching): the exact distance at `a` against how far any point
        // of the piece moves over [a, b]. Not tried when GJK's estimate is
        // within the inflation: the swept set really is that near, and
        // halving is what helps.
        let t_mag = pa.translation.abs().max_element() + pb.translation.abs().max_element();
        let scale = r + t_mag + self.scales.1;
        if estimate <= inflate {
            return Ok(false);
        }
        let Proximity::Separated(sep) = self.pair.query(pa, Pose::IDENTITY)? else {
            return Ok(false);
        };
        let moved = (pb.translation - pa.translation).length() + r * delta;
        // The query's distance is within rounding of the posed bodies' (far
        // below 1e-12 of the coordinates' scale; module docs); the pose at
        // `a` and both translations are within `pose_err` of the exact
        // motion's.
        let margin = 1e-12 * scale + 3.0 * pose_err;
        Ok(sep.distance > moved * (1.0 + 1e-12) + margin)
    }

    /// A unit direction `n` from the obstacle towards the swept hull that
    /// GJK proposes, with GJK's float estimate of their distance (`None`
    /// when they overlap in floats).
    fn separating_direction(&self, pa: Pose, pb: Pose) -> Option<(DVec3, f64, [u32; 3])> {
        let (body, obstacle) = (self.body, self.obstacle);
        let (ra, rb) = (pa.rotation.matrix(), pb.rotation.matrix());
        let (to_a, to_b) = (ra.transpose(), rb.transpose());
        // About the obstacle's centre: the differences stay accurate when
        // both are far from the origin.
        let c = self.obstacle_ball.0;
        let (ta, tb) = (pa.translation - c, pb.translation - c);
        let (mut wa, mut wb, mut wo) = (0u32, 0u32, 0u32);
        // The point of the swept hull ⊖ obstacle minimising d · x.
        let mut support = |d: DVec3| -> DVec3 {
            let u = climb_unposed(body, &to_a, -d, wa);
            let w = climb_unposed(body, &to_b, -d, wb);
            let (o, _) = climb(obstacle, |v| obstacle.vertex(v as usize), d, wo);
            (wa, wb, wo) = (u, w, o);
            let (ha, hb) = (ra * body.vertex(u as usize), rb * body.vertex(w as usize));
            let h = if (-d).dot(ha) >= (-d).dot(hb) { ha } else { hb };
            let t = if (-d).dot(ta) >= (-d).dot(tb) { ta } else { tb };
            h + t - (obstacle.vertex(o as usize) - c)
        };
        let mut v = (ta + tb) * 0.5 - (obstacle.vertices()[0] - c);
        if v.length_squared() == 0.0 {
            v = DVec3::X;
        }
        let mut simplex = crate::query::proximity::gjk::Simplex::default();
        for _ in 0..64 {
            let w = support(v);
            let vv = v.dot(v);
            if v.dot(w) > 0.0 && v.dot(w) * v.dot(w) >= vv * vv * (1.0 - 1e-6) {
                break; // converged enough for a direction
            }
            let before = simplex;
            simplex.push_point(w);
            let (next, nv) = crate::query::proximity::gjk::closest(&simplex);
            if next.len == 4 || nv.length_squared() == 0.0 {
                return None;
            }
            if before.len > 0 && nv.length_squared() >= vv {
                break;
            }
            simplex = next;
            v = nv;
        }
        // Normalised after scaling by a power of two: the length of a
        // vector whose squares are subnormal is off by far more than the
        // unit length the gaps assume.
        let (down, up) = power_of_two_scale(v.abs().max_element());
        let scaled = v * down;
        let len = scaled.length();
        (len > 0.0 && len.is_finite()).then(|| (scaled / len, len * up, [wa, wb, wo]))
    }

    /// Whether the gap along one of the feature axes of GJK's final
    /// support vertices (the obstacle's face normals around its vertex,
    /// the body's face normals at both end poses, and cross products of
    /// their edges), the [`FEATURE_AXES`] nearest GJK's direction `v`,
    /// exceeds `inflate`. Any unit direction gives a rigorous gap
    /// ([`GapTerms::swept`]), so only the choice of direction changes here.
    fn feature_gap(
        &self,
        interval: (f64, f64),
        (pa, pb): (Pose, Pose),
        v: DVec3,
        hints: [u32; 3],
        inflate: f64,
        s: &mut Scratch,
    ) -> bool {
        let (body, obstacle) = (self.body, self.obstacle);
        let mut best = NearestAxes::<(), FEATURE_AXES>::new(v);
        let mut offer = |d: DVec3| best.offer(d, ());
        let o = hints[2] as usize;
        for r in obstacle.ring(o) {
            offer(obstacle.unit_normal(r.face as usize));
        }
        for (pose, w) in [(pa, hints[0]), (pb, hints[1])] {
            let rot = pose.rotation.matrix();
            for r in body.ring(w as usize) {
                offer(-(rot * body.unit_normal(r.face as usize)));
                let e = rot * (body.vertex(r.neighbor as usize) - body.vertex(w as usize));
                for q in obstacle.ring(o) {
                    let c = e.cross(obstacle.vertex(q.neighbor as usize) - obstacle.vertex(o));
                    offer(if c.dot(v) < 0.0 { -c } else { c });
                }
            }
        }
        let certified = best.facing().any(|(d, ())| {
            let terms = self.gap_terms(pa, pb, d, hints, s);
            terms.swept() * (1.0 - 4.0 * f64::EPSILON) > inflate
                || self.ends_apart(interval, &terms)
        });
        // The body's faces around its support vertices, in the body's
        // frame, where they stand still (module docs, "Between the ends").
        certified
            || [hints[0], hints[1]].iter().enumerate().any(|(k, &w)| {
                (k == 0 || hints[1] != hints[0])
                    && body.ring(w as usize).iter().any(|r| {
                        let m = -body.unit_normal(r.face as usize);
                        self.ends_apart_in_body_frame(interval, (pa, pb), m, hints, s)
                    })
            })
    }

    /// Whether the piece stays apart from the obstacle piece over `[a, b]`
    /// by the bow of its path (module docs, "Between the ends"): the gaps
    /// of the two ends along the axis of `terms` (`|n| ≤ 1 + 4ε`), each
    /// less the pose error, against the bow of the piece's reach.
    fn ends_apart(&self, (a, b): (f64, f64), terms: &GapTerms) -> bool {
        let [ga, gb] = terms.ends();
        let long = 1.0 + 4.0 * f64::EPSILON;
        let e = self.margin.pose_error() * long * (1.0 + 4.0 * f64::EPSILON);
        let c = bow(self.margin.turn(b - a), self.reach) * long * (1.0 + 4.0 * f64::EPSILON);
        bowed_chord_stays_positive(ga - e, gb - e, c)
    }

    /// Whether the piece stays apart from the obstacle piece over `[a, b]`
    /// along the body-frame axis `m` (`|m| ≤ 1 + 4ε`), in the body's frame
    /// (module docs, "Between the ends"): the piece stands still there, and
    /// the obstacle's points run within their bow of their chords.
    fn ends_apart_in_body_frame(
        &self,
        (a, b): (f64, f64),
        (pa, pb): (Pose, Pose),
        m: DVec3,
        hints: [u32; 3],
        s: &mut Scratch,
    ) -> bool {
        let (c, radius) = self.obstacle_ball;
        // min over the piece of m · p: the body frame's, no pose.
        let body_max = self.piece_max(-m, hints[0], s);
        let extent = self.motion.translation_extent();
        let mut reach = 0.0f64;
        let mut end_gap = |pose: Pose| {
            // The obstacle seen from the body at this end along `m`:
            // `max (R m) · (o − T)`, with `R m` as rounded.
            let w = pose.rotation.matrix() * m;
            let obstacle_max = self.obstacle_max(w, hints[2], s);
            let to_centre = c - pose.translation;
            let moved = w.dot(to_centre) + dot_error(w, to_centre.abs().max_element());
            // Every obstacle point within `ρ` of the body's origin here,
            // about the exact translation (within `6u (M + D)` of the
            // float one; found missing by the independent review).
            let rho =
                (norm_up(to_centre) + radius + pose_rounding_bound(0.0, extent)) * (1.0 + 1e-12);
            reach = reach.max(rho);
            // `R̃ m` within `681u |m|` of `R m`, `T̃` within `6u (M + D)`
            // of `T` (`query::rounding`): `pose_rounding_bound` of `ρ`.
            let rounding = pose_rounding_bound(rho, extent) * (1.0 + 4.0 * f64::EPSILON);
            let sizes = body_max.abs() + obstacle_max.abs() + moved.abs() + rounding;
            -body_max - obstacle_max - moved - rounding - 8.0 * f64::EPSILON * sizes - 1e-300
        };
        let (ga, gb) = (end_gap(pa), end_gap(pb));
        // The bow in the body's frame: `δ² ρ / 2 + δ |T(b) − T(a)|`, the
        // translations' difference as rounded plus their two roundings.
        let turn = self.margin.turn(b - a);
        let shift = norm_up(pb.translation - pa.translation) * (1.0 + 4.0 * f64::EPSILON)
            + 2.0 * pose_rounding_bound(0.0, extent);
        let c_bow = (bow(turn, reach) + turn * shift * (1.0 + 8.0 * f64::EPSILON))
            * (1.0 + 4.0 * f64::EPSILON)
            * (1.0 + 4.0 * f64::EPSILON);
        bowed_chord_stays_positive(ga, gb, c_bow)
    }

    /// A rigorous upper bound on `max_p d · p` over the body piece's
    /// vertices (its own frame), the near-extreme search from `start`.
    fn piece_max(&self, d: DVec3, start: u32, s: &mut Scratch) -> f64 {
        let body = self.body;
        near_max(
            body,
            |v| body.vertex(v as usize),
            d,
            start,
            0.0,
            0.0,
            self.scales.0,
            &mut s.marks_a,
            &mut s.set,
        )
        .upper
    }

    /// A rigorous upper bound on `max_o n · (o − c)` over the obstacle
    /// piece's exact vertices, `c` the obstacle ball's centre: the
    /// vertices less `c`, each within `η = 2u·scale` of the exact
    /// difference (an exact translate of the obstacle), so the
    /// near-extreme search bounds the rounded ones' maximum, and `η|n|`
    /// more bounds the exact ones' (`|n| ≤ 1 + 4ε`).
    fn obstacle_max(&self, n: DVec3, start: u32, s: &mut Scratch) -> f64 {
        let (obstacle, c) = (self.obstacle, self.obstacle_ball.0);
        let so = self.obstacle_local_scale;
        let eta = f64::EPSILON * so;
        near_max(
            obstacle,
            |v| obstacle.vertex(v as usize) - c,
            n,
            start,
            0.0,
            eta,
            so,
            &mut s.marks_b,
            &mut s.set,
        )
        .upper
            + eta * (1.0 + 4.0 * f64::EPSILON)
    }

    /// The terms of [`GapTerms::swept`] along `n`, per end (module docs).
    fn gap_terms(
        &self,
        pa: Pose,
        pb: Pose,
        n: DVec3,
        hints: [u32; 3],
        s: &mut Scratch,
    ) -> GapTerms {
        let c = self.obstacle_ball.0;
        // max over the piece turned as at each end of −n · x: the body's
        // max along Rᵀ(−n) (the float Rᵀ(−n) off by at most 4ε, times r).
        let ua = self.piece_max(pa.rotation.matrix().transpose() * -n, hints[0], s);
        let ub = self.piece_max(pb.rotation.matrix().transpose() * -n, hints[1], s);
        // fl(T − c) is within u|T − c| a coordinate of T − c, and the dot
        // product rounds by γ₃ Σ|nₖ||xₖ|: 8u Σ|nₖ| max|xₖ| covers both.
        let (ta, tb) = (pa.translation - c, pb.translation - c);
        let local = ta.abs().max(tb.abs()).max_element();
        let obstacle_max = self.obstacle_max(n, hints[2], s);
        GapTerms {
            turned: [ua, ub],
            moved: [(-n).dot(ta), (-n).dot(tb)],
            dot_error: dot_error(n, local),
            turn_error: 8.0 * f64::EPSILON * self.reach,
            obstacle_max,
        }
    }
}

/// The terms of a gap along a direction `n` ([`PieceSearch::gap_terms`]):
/// per end, the body piece's maximum along `−n` turned as there (rounded
/// up) and the translation's `−n · (T − c)`; their roundings; and the
/// obstacle's maximum along `n`, rounded up.
struct GapTerms {
    turned: [f64; 2],
    moved: [f64; 2],
    dot_error: f64,
    turn_error: f64,
    obstacle_max: f64,
}

impl GapTerms {
    /// A rigorous lower bound on `min_{H ⊕ [T]} n · x − max_O n · o`
    /// (for `|n| ≤ 1 + 4ε`), computed about the obstacle ball's centre `c`
    /// (the difference is the same about any point): the translations and
    /// the obstacle's vertices less `c`, rounded, and every rounding
    /// bounded in the local coordinates' size, not in the world's.
    fn swept(&self) -> f64 {
        self.lower(
            self.turned[0].max(self.turned[1]),
            self.moved[0].max(self.moved[1]),
        )
    }

    /// The same bounds for the piece at each end alone, posed at `a` and
    /// at `b` (module docs, "Between the ends").
    fn ends(&self) -> [f64; 2] {
        [0, 1].map(|k| self.lower(self.turned[k], self.moved[k]))
    }

    /// `min n · x − max_O n · o` for the set of the body's points whose
    /// turned part is at most `turned` and moved part at most `moved`
    /// along `−n`, rounded down: `min_H' n · x − max_O n · o = −max_H'
    /// (−n · x) − max_O n · o`, less the rounding of the sums (two for
    /// the body's, one for the difference, one for this subtraction, and
    /// the additions of the error terms to the moved part, the
    /// near-extreme maxima and `η`: each at most u of the terms' sizes,
    /// nine in all, taken as 16u).
    fn lower(&self, turned: f64, moved: f64) -> f64 {
        let ut = moved + self.dot_error;
        let hull_max = turned + self.turn_error + ut;
        let sizes = turned.abs() + self.turn_error + ut.abs() + self.obstacle_max.abs();
        -hull_max - self.obstacle_max - 8.0 * f64::EPSILON * sizes - 1e-300
    }
}

/// Distance from `p` to the segment `[a, b]`, computed about `p` after
/// scaling by a power of two (exact), so that no square overflows (with
/// `|b − a|²` infinite the nearest point was taken as `a`: a motion
/// through the obstacle at 1e154 was certified free) or underflows; `0.0`
/// (nothing proved) for coordinates that are not finite.
fn segment_distance(a: DVec3, b: DVec3, p: DVec3) -> f64 {
    let (a, b) = (a - p, b - p);
    let m = a.abs().max_element().max(b.abs().max_element());
    if !m.is_finite() {
        return 0.0;
    }
    let (down, up) = power_of_two_scale(m);
    let (a, b) = (a * down, b * down);
    let d = b - a;
    let l2 = d.length_squared();
    let t = if l2 > 0.0 {
        ((-a).dot(d) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + t * d).length() * up
}
