//! Certified joint-space motions: for `q(t) = q₀ + t (q₁ − q₀)`, either
//! every instant is free (certified) or the first contact is bracketed,
//! as [`crate::query::MotionCheck`] reports it for rigid bodies.
//!
//! # Why "free" is certain
//! **The chain bound.** Along the motion every joint's value is linear in
//! `t` (mimics too), changing by `Δₖ` over the whole motion. A point `x`
//! of link `i` moves with velocity `Σₖ ωₖ × (x − oₖ) + Σₖ vₖ` over the
//! joints `k` between the root and link `i` (`ωₖ` of magnitude `|Δₖ|`
//! about a revolute or continuous joint's axis, which passes through its
//! frame's origin `oₖ`; `vₖ` of magnitude `|Δₖ|` along a prismatic one).
//! `|x − oₖ|` is at most `ρₖᵢ`: the lengths of the joint origins after
//! `k` on the chain to link `i`, each prismatic joint's largest `|value|`
//! on this motion among them (one of its ends: values are linear; a
//! mimic's value may lie beyond its own limits, so limits would not do),
//! and link `i`'s reach about its own frame (the largest norm of its hull
//! corners, which is the largest of all its vertices'; every length is
//! rounded up by `norm_up`, which never squares a coordinate into
//! underflow or overflow). So a point of
//! link `i` moves at most
//! `vᵢ = Σ |Δₖ| ρₖᵢ + Σ_prismatic |Δₖ|` per unit of `t`
//! (Schwarzer, Saha and Latombe's bound for exact path checking), and
//! over `[a, t]` at most `(t − a) vᵢ`.
//!
//! **A pair's relative motion.** Whether links `i` and `j` meet depends
//! only on `i`'s pose in `j`'s frame, `pose_j⁻¹ ∘ pose_i`: the joints
//! above their common ancestor cancel. That relative pose is itself a
//! serial chain rooted at `j`: the joints from `j` up to the ancestor,
//! each inverted (its motion reversed, about or along the same axis
//! through its child frame's origin), then the joints from the ancestor
//! down to `i`. The bound above applies to it unchanged: walking up from
//! `i`, `ρ` grows by each joint's origin and travel as before; walking
//! down towards `j`, a joint's child frame lies at most its origin's
//! length and its travel from its parent's, so `ρ` grows by those before
//! the joint's `|Δₖ| ρ` is added (the inverse motion turns about an axis
//! through the child frame's origin). Distances are the same in either
//! link's frame, so `vᵢⱼ` is the smaller of `i` seen from `j` and `j`
//! seen from `i` (`chain_speed`). A link against the scene uses `vᵢ`
//! (the scene is the root's). Before this, a pair took `vᵢ + vⱼ`, both
//! from the root: a turn of the base counted twice for links that it
//! carries alike.
//!
//! **The certificate.** For a pair of links `i`, `j` (or a link and the
//! scene, `vᵢⱼ = vᵢ`) over an interval `[a, b]`, the scene checker's swept
//! test with both ends at `q(a)` certifies that every triangle of link
//! `i`, at its pose relative to `j` there, is more than
//! `r = (b − a) vᵢⱼ + m` from every triangle of `j` (the tree walk
//! drops node pairs whose boxes are more than `r` apart, the rest by a
//! gap bounded below rigorously: `query::scene::sweep`). The float poses
//! differ from the exact forward kinematics at `q(a)` and at any `q(t)`
//! by at most `ε` a point (below), and posing a vertex rounds by at most
//! `pad`; with the margin `m = 2(2ε + pad)` the exact links stay more
//! than `0` apart over all of `[a, b]`, and so do the links at every
//! float configuration `q(t)` (the factor 2: float `q(a)` to exact
//! `q(a)`, the motion, exact `q(t)` to float `q(t)`, each `2ε + pad` at
//! most). No triangles meet, and a link cannot come to lie inside
//! another without its triangles meeting one first (the start is checked
//! whole, containment included). A pair certified on `[a, b]` is not
//! tested again before `b` (the search examines intervals left to right,
//! so `[a, b]` and the certified `[0, a]` are contiguous); an interval is
//! certified when every pair is.
//!
//! **The plane certificate.** Before walking a pair's triangles, a
//! separating plane between the two links' hull corners at `q(a)` (link
//! `i`'s corners carried into `j`'s frame by the float products
//! `R_jᵀ R_i` and `R_jᵀ (t_i − t_j)` of the float poses: a few ulps of
//! `R` from the exactly composed relative pose, far within the four
//! joints' worth of rounding the margin holds for it, below)
//! (`robot::separation`: Gilbert's iteration, warm-started per pair)
//! gives a float gap `g`; a link against the scene takes one plane per
//! obstacle (up to `PLANE_OBSTACLES` of them) and the least gap: outside
//! every obstacle's hull a point is inside no obstacle's solid (a
//! component's winding number vanishes outside its hull). The horizon `h = a + 0.999 (g − m) / v`,
//! clamped to `1`, is used when it reaches `b`, and only once the plane
//! certifies the corners, posed at `q(a)`, more than
//! `r = (h − a) vᵢⱼ + m` apart (rounded up as above): the same statement
//! the swept test makes for `[a, h]`, so the same argument covers it. A
//! plane separating the hulls separates the meshes and the solids they
//! bound. `h` may lie beyond `b`: the pair is then not tested again
//! before `h` (conservative advancement, one step a call). Pairs far
//! apart cost a few dozen dot products per step instead of a tree walk.
//! When the plane falls short and two corners (vertices of the meshes)
//! lie closer than `r`, the walk could not certify `r` either; when the
//! plane's gap exceeds both `r / 8` and `2m`, a few halvings of the
//! interval let the plane certify, for far less than a walk at a reach
//! that wide (every triangle pair within `r` is visited). Either way the
//! interval is "not proved" without walking (a `false` is always sound).
//! A gap nearer `m` could never be certified by the plane (halving would
//! end undecided), so such a pair is walked, as are pairs whose hulls
//! overlap or nearly (nested, interleaved or non-convex links close
//! together). When the plane's certificate fails at its own horizon
//! (rounding), it is tried once more at `b`.
//!
//! **Review (2026-11-29, of the first version).** A second reading
//! confirmed the pair bound (1,600 random trees with revolute,
//! continuous, prismatic, fixed and mimic joints at 40 digits: the
//! largest ratio of a measured displacement to the bound was
//! `1/(1 + 10⁻¹²)`), the hull argument with containment, and the
//! horizons' soundness. It found two faults, both mended: a direction
//! whose square underflows made the plane test's length wrong (a false
//! certificate for a stale direction near `10⁻¹⁵⁴`; directions are now
//! scaled by a power of two, `robot::separation`), and the shortcut
//! declined to walk pairs the plane could never certify (a box `10⁻¹¹`
//! above the hull of two pillars 1.5 m below it ended undecided, free
//! before; the `2m` condition and the retry at `b` above; pinned by
//! `review_a_hull_gap_within_the_margin_is_walked_not_undecided`).
//!
//! **Rounding.** `ε` bounds how far a point of a link at its float pose
//! ([`Robot::forward`], composed joint by joint) lies from the same point
//! at the exact forward kinematics of the exact `q(t)`. Per joint: up to
//! three rotation snaps (`from_axis_angle`, the composition with the
//! origin, with the motion), each below `2√3·10⁻¹⁴` rad
//! (`kernel::rotation`: quaternion components within `10⁻¹⁴` of zero),
//! the matrix entries' snap (`2⁻⁴⁷` an entry) and a few ulps of the
//! products: at most `2·10⁻¹³ R` for a point within `R` of the root (`R`
//! every origin's length, every prismatic travel on the motion and the
//! largest link reach and scene reach). Four joints' worth more cover the
//! relative pose of a pair (`pose_j⁻¹ ∘ pose_i`). The interpolated values
//! round by an ulp of the value, not of `R`: `4u(max|v| + |Δ|)` a joint,
//! times `R` for a turn, doubled. So
//! `ε = (2n + 8)·10⁻¹³ R + 2Σₖ 4u(max|vₖ| + |Δₖ|)(R or 1)`.
//! A motion whose bounds are not finite is refused.
//!
//! # Independent review (2026-11-29)
//! A second reading (of the first version, which measured a clearance
//! per pair and certified up to the horizon it allowed; the swept test
//! above replaced it: 22× faster on `bench_robot.py`'s Panda motions) found the search and the
//! horizons sound (intervals are examined with non-decreasing left ends,
//! so a pair certified from `a' ≤ a` covers `[a', h]`, contiguous with
//! the certified `[0, a]`) and
//! one wrong answer, mended: prismatic travel was taken from the joint's
//! limits, and a mimic's value may lie beyond them (a prismatic joint of
//! limits `[0, 0]` mimicking another at twice its value made a colliding
//! swing certified free; `crates/dymsum-io/tests/urdf_robots.rs` pins it).
//! It also corrected the rounding: three snaps a joint, the interpolated
//! values' ulps (which grow with the values, not with `R`), the horizon
//! rounded down, and a NaN horizon (an overflowing mimic) that passed.

//! # The search
//! The interval search of `query::interval_search` (left to right,
//! halving, probes ahead when stuck, the budget, undecided below
//! [`crate::query::MIN_WIDTH`]); a time is checked by
//! [`RobotChecker::collides_at`] at `q(t)`, each value clamped into the
//! range between its ends.

use super::checker::RobotChecker;
use super::error::RobotError;
use super::model::{JointKind, Robot};
use super::separation::PlaneCertificate;
use crate::kernel::rotation::Pose;
use crate::query::interval_search::{bisection_order, first_contact, Stop, Sweep};
use crate::query::rounding::norm_up;
use crate::query::{MotionCheck, MotionError};

/// The largest `|value|` joint `k` takes along the motion (values are
/// linear in `t`, so one of the ends), for the prismatic joints' travel:
/// a mimic's value may lie beyond its own limits, so the limits would not
/// do (the review's counterexample).
fn travel(robot: &Robot, k: usize, ends: (&[f64], &[f64])) -> f64 {
    match robot.joints[k].spec.kind {
        JointKind::Prismatic { .. } => ends.0[k].abs().max(ends.1[k].abs()),
        _ => 0.0,
    }
}

/// The joints from link `l` up to the root, child first.
fn chain_to_root(robot: &Robot, l: usize) -> Vec<usize> {
    let mut chain = Vec::new();
    let mut at = l;
    while let Some(k) = robot.joints.iter().position(|j| j.child == at) {
        chain.push(k);
        at = robot.joints[k].parent;
    }
    chain
}

/// How far a point of the link below `up` moves per unit of `t`, walking
/// `up` (joints child first, from the link upwards) then `down` (joints
/// parent first, downwards to the frame the motion is measured in), the
/// link's points within `reach` of its own frame (module docs, "The chain
/// bound" and "A pair's relative motion").
fn chain_speed(
    robot: &Robot,
    up: &[usize],
    down: &[usize],
    ends: (&[f64], &[f64]),
    reach: f64,
) -> f64 {
    let turn = |k: usize| (ends.1[k] - ends.0[k]).abs();
    let offset =
        |k: usize| travel(robot, k, ends) + norm_up(robot.joints[k].spec.origin.translation);
    // ρ: how far the link's points lie from the current frame's origin.
    let mut rho = reach;
    let mut speed = 0.0;
    for &k in up {
        // Joint k's axis passes through its child frame's origin, within
        // ρ of every point; then the parent's frame is `offset` away.
        match robot.joints[k].spec.kind {
            JointKind::Revolute { .. } | JointKind::Continuous => speed += turn(k) * rho,
            JointKind::Prismatic { .. } => speed += turn(k),
            JointKind::Fixed => {}
        }
        rho += offset(k);
    }
    for &k in down {
        // Seen from joint k's child frame, the points move by the joint's
        // inverse motion, about an axis through that frame's origin, at
        // most `offset` farther from it than from the parent's.
        rho += offset(k);
        match robot.joints[k].spec.kind {
            JointKind::Revolute { .. } | JointKind::Continuous => speed += turn(k) * rho,
            JointKind::Prismatic { .. } => speed += turn(k),
            JointKind::Fixed => {}
        }
    }
    speed * (1.0 + 1e-12)
}

/// A link's motion bound in the root's frame (module docs): how far any
/// point of link `l` moves per unit of `t` along a motion whose joint
/// values go from `ends.0` to `ends.1` (one per joint, in the robot's
/// joint order).
fn link_speed(robot: &Robot, l: usize, ends: (&[f64], &[f64]), reaches: &[f64]) -> f64 {
    chain_speed(robot, &chain_to_root(robot, l), &[], ends, reaches[l])
}

/// A pair's relative motion bound (module docs): how fast the distance
/// between links `i` and `j` may shrink, from the joints between them
/// only (those above their common ancestor move both alike). The smaller
/// of link `i` seen from `j` and `j` seen from `i`.
fn pair_speed(robot: &Robot, i: usize, j: usize, ends: (&[f64], &[f64]), reaches: &[f64]) -> f64 {
    let (i_from_j, j_from_i) = pair_speeds(robot, i, j, ends, reaches);
    i_from_j.min(j_from_i)
}

/// How fast points of link `i` move in `j`'s frame, and points of `j` in
/// `i`'s (module docs).
fn pair_speeds(
    robot: &Robot,
    i: usize,
    j: usize,
    ends: (&[f64], &[f64]),
    reaches: &[f64],
) -> (f64, f64) {
    let (mut ci, mut cj) = (chain_to_root(robot, i), chain_to_root(robot, j));
    while let (Some(a), Some(b)) = (ci.last(), cj.last()) {
        if a != b {
            break;
        }
        ci.pop();
        cj.pop();
    }
    let down = |c: &[usize]| c.iter().rev().copied().collect::<Vec<_>>();
    (
        chain_speed(robot, &ci, &down(&cj), ends, reaches[i]),
        chain_speed(robot, &cj, &down(&ci), ends, reaches[j]),
    )
}

/// `R` of the module docs: every origin's length, every prismatic
/// joint's largest travel on the motion and the largest link reach (sums
/// of magnitudes: no squares to underflow).
fn robot_size(robot: &Robot, ends: (&[f64], &[f64]), reaches: &[f64]) -> f64 {
    let joints: f64 = (0..robot.joints.len())
        .map(|k| {
            travel(robot, k, ends) + robot.joints[k].spec.origin.translation.abs().element_sum()
        })
        .sum();
    (joints + reaches.iter().copied().fold(0.0, f64::max)) * (1.0 + 1e-12)
}

/// The rounding of the interpolated joint values, as a distance (module
/// docs): `4u (max|v| + |Δ|)` a joint, times `R` for a turn.
fn interpolation_error(robot: &Robot, ends: (&[f64], &[f64]), size: f64) -> f64 {
    let u = f64::EPSILON / 2.0;
    (0..robot.joints.len())
        .map(|k| {
            let (a, b) = (ends.0[k], ends.1[k]);
            let e = 4.0 * u * (a.abs().max(b.abs()) + (b - a).abs());
            match robot.joints[k].spec.kind {
                JointKind::Revolute { .. } | JointKind::Continuous => e * size,
                JointKind::Prismatic { .. } => e,
                JointKind::Fixed => 0.0,
            }
        })
        .sum::<f64>()
        * 2.0
}

/// What the plane certificate found for a pair over an interval.
enum Plane {
    /// Certified free up to this horizon (at or beyond the interval's end).
    Certified(f64),
    /// Not up to the interval's end: the float gap along the plane, and
    /// the distance of two corners (the links are no farther apart, up to
    /// rounding).
    Short { gap: f64, nearest: f64 },
}

/// The search over one motion (module docs).
struct RobotSweep<'a> {
    checker: &'a RobotChecker,
    q0: Vec<f64>,
    q1: Vec<f64>,
    /// Per measured checker (scene links, then pairs): how fast its two
    /// sides may approach each other.
    speed: Vec<f64>,
    /// `2(2ε + pad)` of the module docs, per unit of pad's scale.
    margin: f64,
    /// Per scene link then per pair: the horizon certified so far.
    horizon: Vec<f64>,
    /// Per measured checker, per target (the other link, or each
    /// obstacle): the plane certificate's buffer and warm start.
    planes: Vec<Vec<PlaneCertificate>>,
    /// A buffer: a link's corners posed.
    posed: Vec<glam::DVec3>,
}

impl RobotSweep<'_> {
    /// The horizon separating planes certify for measured checker `k`
    /// (link `i` against link `j`, or against each obstacle when `j` is
    /// `None`; approaching at most at `v`) from `a`, when it reaches `b`
    /// (module docs, "The plane certificate").
    fn plane_horizon(
        &mut self,
        k: usize,
        poses: &[Pose],
        (i, j): (usize, Option<usize>),
        (a, b): (f64, f64),
        v: f64,
    ) -> Plane {
        let checker = self.checker;
        let none = Plane::Short {
            gap: f64::NEG_INFINITY,
            nearest: f64::INFINITY,
        };
        // Link i's pose in j's frame as a float matrix product (module
        // docs: within a few ulps of the composed relative pose).
        let (mi, ti) = (poses[i].rotation.matrix(), poses[i].translation);
        let (Some(ci), (pose, targets)) = (
            checker.corners(i),
            match j {
                Some(j) => {
                    let back = poses[j].rotation.matrix().transpose();
                    (
                        (back * mi, back * (ti - poses[j].translation)),
                        checker.corners(j).map(std::slice::from_ref).unwrap_or(&[]),
                    )
                }
                None => ((mi, ti), checker.obstacle_corners()),
            },
        ) else {
            return none;
        };
        if targets.is_empty() {
            return none;
        }
        let planes = &mut self.planes[k];
        planes.resize_with(targets.len(), PlaneCertificate::default);
        let posed = &mut self.posed;
        ci.pose_into(pose, posed);
        let (mut gap, mut nearest) = (f64::INFINITY, f64::INFINITY);
        let mut horizon = f64::INFINITY;
        for (plane, target) in planes.iter_mut().zip(targets) {
            // A target certified past b by an earlier step is not tested.
            if plane.horizon >= b {
                horizon = horizon.min(plane.horizon);
                continue;
            }
            // Enough: a gap that certifies four times the interval.
            let g = plane.prepare(posed, ci, target, 4.0 * (b - a) * v + 2.0 * self.margin);
            gap = gap.min(g);
            nearest = nearest.min(plane.nearest);
            // The width this target's float gap allows, a little less;
            // then certified.
            let w = (g - self.margin) / v * 0.999;
            let h = if w.is_finite() { (a + w).min(1.0) } else { 1.0 };
            if !(g > self.margin && h >= b) {
                return Plane::Short { gap, nearest };
            }
            let reach_to = |h: f64| ((h - a) * v * (1.0 + 1e-12) + self.margin) * (1.0 + 1e-12);
            // At the gap's own horizon, else (rounding) at b.
            let Some(h) = [h, b]
                .into_iter()
                .find(|&h| plane.apart_by(posed, target, reach_to(h)))
            else {
                return Plane::Short { gap, nearest };
            };
            plane.horizon = h;
            horizon = horizon.min(h);
        }
        Plane::Certified(horizon)
    }

    /// Every target of measured checker `k` is certified to `b` (by the
    /// swept test).
    fn planes_certified_to(&mut self, k: usize, b: f64) {
        for p in &mut self.planes[k] {
            p.horizon = p.horizon.max(b);
        }
    }

    fn q_at(&self, t: f64) -> Vec<f64> {
        configuration_at(&self.q0, &self.q1, t)
    }
}

/// `q(t) = q₀ + t (q₁ − q₀)`, each value clamped into the range between
/// its ends (the float product may round past them).
fn configuration_at(q0: &[f64], q1: &[f64], t: f64) -> Vec<f64> {
    q0.iter()
        .zip(q1)
        .map(|(&a, &b)| (a + t * (b - a)).clamp(a.min(b), a.max(b)))
        .collect()
}

impl Sweep for RobotSweep<'_> {
    type Error = RobotError;

    fn certified_free(&mut self, a: f64, b: f64) -> Result<bool, RobotError> {
        if self.horizon.iter().all(|&h| h >= b) {
            return Ok(true);
        }
        let q = self.q_at(a);
        let poses = self.checker.robot().forward(&q)?;
        let mut all = true;
        for (k, c, (i, j)) in self.checker.measured_pairs() {
            if self.horizon[k] >= b {
                continue;
            }
            let v = self.speed[k];
            // How far the two links may come towards each other over
            // [a, b], rounded up; then certified at q(a).
            let reach = ((b - a) * v * (1.0 + 1e-12) + self.margin) * (1.0 + 1e-12);
            match self.plane_horizon(k, &poses, (i, j), (a, b), v) {
                Plane::Certified(h) => {
                    self.horizon[k] = h;
                    continue;
                }
                // Two corners closer than the reach: the walk cannot
                // certify it. A plane gap of an eighth of the reach: a
                // few halvings let the plane certify, cheaper than a walk
                // this wide (module docs). Not proved, without walking.
                Plane::Short { gap, nearest }
                    if reach > nearest * 1.01
                        || (gap > 0.125 * reach && gap > 2.0 * self.margin) =>
                {
                    all = false;
                    break;
                }
                Plane::Short { .. } => {}
            }
            if !(reach.is_finite() && self.checker.apart_by(c, &poses, i, j, reach)) {
                all = false;
                break;
            }
            // Nothing moves the two apart or together (a link fixed to the
            // root against the scene): certified to the end.
            self.horizon[k] = if v == 0.0 { 1.0 } else { b };
            self.planes_certified_to(k, self.horizon[k]);
        }
        Ok(all)
    }

    fn collides_at_time(&mut self, t: f64) -> Result<bool, RobotError> {
        self.checker.collides_at(&self.q_at(t))
    }
}

impl RobotChecker {
    /// A cheap refutation before a certificate: the first configuration
    /// `q(k / segments)` of the straight motion from `q0` to `q1` (values
    /// clamped between the ends), visited in bisection order and at most
    /// `most` of them, at which the robot collides (exact), as its `t`;
    /// `None` when none of them does (which proves nothing: the motion
    /// may still collide between them; [`RobotChecker::check`] decides).
    /// A planner's motion validator runs it with the sampled check's own
    /// count first, so that a colliding motion costs what sampling costs.
    ///
    /// # Errors
    /// [`RobotError::BadConfiguration`] for an end outside the limits;
    /// [`RobotError::Query`] when a check fails.
    pub fn sampled_contact(
        &self,
        q0: &[f64],
        q1: &[f64],
        segments: usize,
        most: usize,
    ) -> Result<Option<f64>, RobotError> {
        let robot = self.robot();
        robot.joint_values(q0)?;
        robot.joint_values(q1)?;
        for k in bisection_order(segments, most) {
            let t = k as f64 / segments as f64;
            if self.collides_at(&configuration_at(q0, q1, t))? {
                return Ok(Some(t));
            }
        }
        Ok(None)
    }

    /// Checks the straight joint-space motion from `q0` to `q1` (module
    /// docs) with the bracket no wider than `tolerance` (in `t`): the
    /// answer as [`crate::query::MotionChecker::check`]'s, at most
    /// `budget` intervals examined ([`crate::query::DEFAULT_BUDGET`] is a
    /// good default).
    ///
    /// # Errors
    /// [`RobotError::BadConfiguration`] for an end outside the limits
    /// (naming the joint); [`RobotError::Motion`] for a tolerance outside
    /// `[MIN_TOLERANCE, 1)`, a grazing motion (undecided) or a spent
    /// budget; [`RobotError::Query`] when a check fails.
    pub fn check(
        &self,
        q0: &[f64],
        q1: &[f64],
        tolerance: f64,
        budget: u64,
    ) -> Result<MotionCheck, RobotError> {
        MotionError::check_tolerance(tolerance)?;
        let robot = self.robot();
        let (v0, v1) = (robot.joint_values(q0)?, robot.joint_values(q1)?);
        if self.collides_at(q0)? {
            return Ok(MotionCheck::Collides {
                t_safe: None,
                t_contact: 0.0,
            });
        }
        let ends = (v0.as_slice(), v1.as_slice());
        let reaches: Vec<f64> = robot
            .links
            .iter()
            .map(|l| l.body.as_ref().map_or(0.0, |b| b.reach))
            .collect();
        // The speeds from each link's largest vertex norm (its hull
        // corners', `robot::separation`), tighter than the body's reach.
        let norms: Vec<f64> = (0..robot.links.len())
            .map(|l| self.corners(l).map_or(0.0, |c| c.largest_norm()))
            .collect();
        let speed: Vec<f64> = self
            .measured_pairs()
            .map(|(_, _, (i, j))| match j {
                None => link_speed(robot, i, ends, &norms),
                Some(j) => pair_speed(robot, i, j, ends, &norms),
            })
            .collect();
        let size = robot_size(robot, ends, &reaches) + self.scene_size();
        let epsilon = (2.0 * robot.joints.len() as f64 + 8.0) * 1e-13 * size
            + interpolation_error(robot, ends, size);
        if !(epsilon.is_finite() && speed.iter().all(|v| v.is_finite())) {
            return Err(RobotError::BadConfiguration(
                "the motion's joint values are too large to bound (not finite)".into(),
            ));
        }
        let pad = 64.0 * f64::EPSILON * size;
        let mut sweep = RobotSweep {
            checker: self,
            q0: q0.to_vec(),
            q1: q1.to_vec(),
            speed,
            margin: 2.0 * (2.0 * epsilon + pad) + 1e-300,
            horizon: vec![0.0; self.measured_pairs().count()],
            planes: vec![Vec::new(); self.measured_pairs().count()],
            posed: Vec::new(),
        };
        let mut steps_left = budget.max(1);
        let mut stack = Vec::new();
        match first_contact(&mut sweep, 1.0, 1, tolerance, &mut steps_left, &mut stack) {
            Ok(None) => Ok(MotionCheck::Free),
            Ok(Some((t_safe, t_contact))) => Ok(MotionCheck::Collides {
                t_safe: Some(t_safe),
                t_contact,
            }),
            Err(Stop::Failed(e)) => Err(e),
            Err(Stop::Budget { t_safe }) => Err(RobotError::Motion(MotionError::BudgetExhausted {
                t_safe,
                steps: budget.max(1),
            })),
            Err(Stop::Undecided { t_safe, t }) => {
                Err(RobotError::Motion(MotionError::Undecided { t_safe, t }))
            }
        }
    }
}

impl From<MotionError> for RobotError {
    fn from(e: MotionError) -> RobotError {
        match e {
            MotionError::Query(q) => RobotError::Query(q),
            other => RobotError::Motion(other),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::rotation::{Pose, Rotation};
    use crate::robot::kinematics::{compose, inverse};
    use crate::robot::model::{JointSpec, LinkSpec, Mimic};
    use glam::DVec3;

    struct Rng(crate::kernel::test_rng::Xorshift);
    impl Rng {
        /// Uniform in [−1, 1).
        fn unit(&mut self) -> f64 {
            self.0.signed()
        }
        fn vec(&mut self) -> DVec3 {
            DVec3::new(self.unit(), self.unit(), self.unit())
        }
        fn below(&mut self, n: usize) -> usize {
            ((self.unit() + 1.0) * 0.5 * n as f64) as usize % n
        }
    }

    /// A random tree of `n` links: each joint's parent one of the links
    /// before it, kinds, origins and axes at random, one mimic sometimes.
    fn random_tree(r: &mut Rng, n: usize) -> Robot {
        let links = (0..n)
            .map(|l| LinkSpec {
                name: format!("l{l}"),
                body: None,
            })
            .collect();
        let mut joints = Vec::new();
        for c in 1..n {
            let kind = match r.below(4) {
                0 => JointKind::Revolute {
                    lower: -2.0,
                    upper: 2.0,
                },
                1 => JointKind::Continuous,
                2 => JointKind::Prismatic {
                    lower: -0.5,
                    upper: 0.7,
                },
                _ => JointKind::Fixed,
            };
            let mimic =
                (c > 2 && r.below(4) == 0 && !matches!(kind, JointKind::Fixed)).then(|| Mimic {
                    joint: "j1".into(),
                    multiplier: 2.5 * r.unit(),
                    offset: r.unit(),
                });
            let parent = if r.below(3) == 0 { r.below(c) } else { c - 1 };
            let turn =
                Rotation::from_axis_angle(r.vec() + DVec3::splat(0.01), 3.0 * r.unit()).unwrap();
            joints.push(JointSpec {
                name: format!("j{c}"),
                kind,
                parent: format!("l{parent}"),
                child: format!("l{c}"),
                origin: Pose::new(turn, r.vec()),
                axis: r.vec() + DVec3::splat(0.01),
                mimic,
            });
        }
        // j1 must be a degree of freedom for the mimics.
        joints[0].kind = JointKind::Revolute {
            lower: -2.0,
            upper: 2.0,
        };
        joints[0].mimic = None;
        Robot::new(links, joints).unwrap()
    }

    fn random_q(r: &mut Rng, robot: &Robot) -> Vec<f64> {
        robot
            .dofs
            .iter()
            .map(|&j| match robot.joints[j].spec.kind {
                JointKind::Revolute { lower, upper } | JointKind::Prismatic { lower, upper } => {
                    lower + (upper - lower) * 0.5 * (r.unit() + 1.0)
                }
                _ => 6.0 * r.unit(),
            })
            .collect()
    }

    /// The chain bounds against the motion itself: points of a link within
    /// its reach, posed at many times along random motions of random
    /// trees, never move faster than the bound, in the root's frame
    /// (`link_speed`) nor in another link's (`pair_speed`).
    #[test]
    fn links_move_no_faster_than_their_chain_bounds() {
        let mut r = Rng(crate::kernel::test_rng::Xorshift::new(
            0x9e37_79b9_7f4a_7c15,
        ));
        let mut tight = 0.0f64;
        for _ in 0..300 {
            let size = 2 + r.below(6);
            let robot = random_tree(&mut r, size);
            let n = robot.links.len();
            let reaches: Vec<f64> = (0..n).map(|_| 0.1 + r.unit().abs()).collect();
            let (q0, q1) = (random_q(&mut r, &robot), random_q(&mut r, &robot));
            let (v0, v1) = (
                robot.joint_values(&q0).unwrap(),
                robot.joint_values(&q1).unwrap(),
            );
            let ends = (v0.as_slice(), v1.as_slice());
            let (i, j) = (r.below(n), r.below(n));
            let within = |r: &mut Rng, reach: f64| -> Vec<DVec3> {
                (0..8)
                    .map(|_| r.vec().clamp_length_max(1.0) * reach / 3f64.sqrt())
                    .collect()
            };
            let (pi, pj) = (within(&mut r, reaches[i]), within(&mut r, reaches[j]));
            let vi = link_speed(&robot, i, ends, &reaches);
            let (i_from_j, j_from_i) = pair_speeds(&robot, i, j, ends, &reaches);
            let vij = pair_speed(&robot, i, j, ends, &reaches);
            let at = |t: f64| {
                let q: Vec<f64> = q0.iter().zip(&q1).map(|(a, b)| a + t * (b - a)).collect();
                robot.forward(&q).unwrap()
            };
            let steps = 400;
            let dt = 1.0 / steps as f64;
            let rel = |p: &[Pose], a: usize, b: usize| compose(&inverse(&p[b]), &p[a]);
            let mut before = at(0.0);
            for s in 1..=steps {
                let now = at(s as f64 / steps as f64);
                for x in &pi {
                    let moved = (now[i].apply(*x) - before[i].apply(*x)).length();
                    assert!(moved <= dt * vi + 1e-12, "link {i}: {moved} > {}", dt * vi);
                    let moved = (rel(&now, i, j).apply(*x) - rel(&before, i, j).apply(*x)).length();
                    assert!(
                        moved <= dt * i_from_j + 1e-12,
                        "{i} from {j}: {moved} > {}",
                        dt * i_from_j
                    );
                    if i_from_j > 0.0 {
                        tight = tight.max(moved / (dt * i_from_j));
                    }
                    // The distance to any point of j changes no faster than
                    // the smaller bound.
                    for y in &pj {
                        let d = |p: &[Pose]| (p[i].apply(*x) - p[j].apply(*y)).length();
                        let change = (d(&now) - d(&before)).abs();
                        assert!(
                            change <= dt * vij + 1e-12,
                            "pair {i}, {j}: {change} > {}",
                            dt * vij
                        );
                    }
                }
                for y in &pj {
                    let moved = (rel(&now, j, i).apply(*y) - rel(&before, j, i).apply(*y)).length();
                    assert!(
                        moved <= dt * j_from_i + 1e-12,
                        "{j} from {i}: {moved} > {}",
                        dt * j_from_i
                    );
                }
                before = now;
            }
        }
        // The bound is not vacuous: some motion comes within half of it.
        assert!(tight > 0.5, "{tight}");
    }

    /// Links carried alike by a turn of a joint above both do not move
    /// relative to each other: the pair's bound is zero, while each
    /// link's own bound is not.
    #[test]
    fn a_turn_above_both_links_does_not_count_for_the_pair() {
        let spec = |name: &str, parent: &str, child: &str, kind| JointSpec {
            name: name.into(),
            kind,
            parent: parent.into(),
            child: child.into(),
            origin: Pose::new(Rotation::IDENTITY, DVec3::new(1.0, 0.0, 0.0)),
            axis: DVec3::Z,
            mimic: None,
        };
        let turn = JointKind::Revolute {
            lower: -3.0,
            upper: 3.0,
        };
        let links = ["base", "arm", "a", "b"].map(|n| LinkSpec {
            name: n.into(),
            body: None,
        });
        let robot = Robot::new(
            links.to_vec(),
            vec![
                spec("pan", "base", "arm", turn),
                spec("fa", "arm", "a", JointKind::Fixed),
                spec("fb", "arm", "b", JointKind::Fixed),
            ],
        )
        .unwrap();
        let ends = ([0.0, 0.0, 0.0].as_slice(), [3.0, 0.0, 0.0].as_slice());
        let reaches = [1.0; 4];
        assert!(link_speed(&robot, 2, ends, &reaches) > 3.0);
        assert_eq!(pair_speed(&robot, 2, 3, ends, &reaches), 0.0);
        assert!(pair_speed(&robot, 0, 2, ends, &reaches) > 3.0);
    }
}
