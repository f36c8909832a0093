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
//! and link `i`'s reach about its own frame (the largest norm of its
//! vertices; sums of coordinate magnitudes throughout). So a point of
//! link `i` moves at most
//! `vᵢ = Σ |Δₖ| ρₖᵢ + Σ_prismatic |Δₖ|` per unit of `t`
//! (Schwarzer, Saha and Latombe's bound for exact path checking), and
//! over `[a, t]` at most `(t − a) vᵢ`.
//!
//! **The certificate.** For a pair of links `i`, `j` (or a link and the
//! scene, `vⱼ = 0`) over an interval `[a, b]`, the scene checker's swept
//! test with both ends at `q(a)` certifies that every triangle of link
//! `i`, at its pose relative to `j` there, is more than
//! `r = (b − a)(vᵢ + vⱼ) + m` from every triangle of `j` (the tree walk
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
use crate::query::interval_search::{first_contact, Stop, Sweep};
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

/// A link's motion bound (module docs): how far any point of link `l`
/// moves per unit of `t` along a motion whose joint values go from
/// `ends.0` to `ends.1` (one per joint, in the robot's joint order).
fn link_speed(robot: &Robot, l: usize, ends: (&[f64], &[f64]), reaches: &[f64]) -> f64 {
    // The joints from link `l` up to the root, child first.
    let mut chain = Vec::new();
    let mut at = l;
    while let Some(k) = robot.joints.iter().position(|j| j.child == at) {
        chain.push(k);
        at = robot.joints[k].parent;
    }
    // ρ grows as the walk goes up: for joint k, what lies below it; then
    // joint k's own travel and origin are added for the joints above.
    let mut rho = reaches[l];
    let mut speed = 0.0;
    for &k in &chain {
        let joint = &robot.joints[k];
        let d = (ends.1[k] - ends.0[k]).abs();
        match joint.spec.kind {
            JointKind::Revolute { .. } | JointKind::Continuous => speed += d * rho,
            JointKind::Prismatic { .. } => speed += d,
            JointKind::Fixed => {}
        }
        rho += travel(robot, k, ends) + joint.spec.origin.translation.abs().element_sum();
    }
    speed * (1.0 + 1e-12)
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

/// The search over one motion (module docs).
struct RobotSweep<'a> {
    checker: &'a RobotChecker,
    q0: Vec<f64>,
    q1: Vec<f64>,
    /// Per link, its speed bound.
    speed: Vec<f64>,
    /// `2(2ε + pad)` of the module docs, per unit of pad's scale.
    margin: f64,
    /// Per scene link then per pair: the horizon certified so far.
    horizon: Vec<f64>,
}

impl RobotSweep<'_> {
    fn q_at(&self, t: f64) -> Vec<f64> {
        self.q0
            .iter()
            .zip(&self.q1)
            .map(|(&a, &b)| (a + t * (b - a)).clamp(a.min(b), a.max(b)))
            .collect()
    }
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
            let v = self.speed[i] + j.map_or(0.0, |j| self.speed[j]);
            // How far the two links may come towards each other over
            // [a, b], rounded up; then certified at q(a).
            let reach = ((b - a) * v * (1.0 + 1e-12) + self.margin) * (1.0 + 1e-12);
            if !(reach.is_finite() && self.checker.apart_by(c, &poses, i, j, reach)) {
                all = false;
                break;
            }
            self.horizon[k] = b;
        }
        Ok(all)
    }

    fn collides_at_time(&mut self, t: f64) -> Result<bool, RobotError> {
        self.checker.collides_at(&self.q_at(t))
    }
}

impl RobotChecker {
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
        let speed: Vec<f64> = (0..robot.links.len())
            .map(|l| link_speed(robot, l, ends, &reaches))
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
        };
        let mut steps_left = budget.max(1);
        let mut stack = Vec::new();
        match first_contact(&mut sweep, 1.0, tolerance, &mut steps_left, &mut stack) {
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
