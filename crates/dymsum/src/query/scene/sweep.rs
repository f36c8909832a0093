//! The certified motion search of a [`SceneChecker`].
//!
//! # Why "free" is certain
//! The motion is [`Motion`]'s (linear translation, slerp rotation, the
//! arc decided exactly). Over an interval `[a, b]` the rotation turns by
//! `δ = Θ (b − a)` about one fixed axis (`Θ` the whole angle: slerp turns
//! at a constant rate), so a body point `p` (`|p| ≤ r`, the body's reach)
//! moves on a circle arc of angle `δ ≤ π` and radius at most `r`, within
//! the sagitta `s = r (1 − cos(δ/2))` of the chord between `R(a) p` and
//! `R(b) p`; the translation moves on the segment `[T(a), T(b)]`. So a
//! body triangle `P`, at every `t` in `[a, b]`, lies in
//!
//! `conv(R(a) P ∪ R(b) P) ⊕ [T(a), T(b)] ⊕ ball(s)`,
//!
//! the hull of twelve points (each corner turned as at `a` and at `b`,
//! moved as at `a` and at `b`) grown by `s`: the motion search's
//! *swept hull* (the convex checker's bound, [`crate::query::MotionChecker`],
//! per triangle). If every pair of a swept hull and a scene triangle is
//! more than `s` plus `e` apart, no triangles meet anywhere in `[a, b]`:
//! `e = 2⁻⁴³ r + 6u (M + D)` (`u = 2⁻⁵³`, `M` the largest end translation
//! coordinate, `D` the largest of their difference) bounds the distance
//! between each of the twelve points as computed (posed in floats, then
//! moved by the float difference of the translations) and its exact
//! value on the exact motion (`query::rounding`: the rotation's error is
//! relative to the reach, the translation's a few ulps of the
//! coordinates), and `δ` is rounded up from the float angle plus its
//! error bound (`2⁻⁴⁶`). Pairs whose boxes are more than that apart on an axis are
//! dropped by the broad phase (an exact comparison after a monotone
//! rounding), the others are certified by [`super::gap`]: floats propose
//! an axis, and the gap along it is bounded below rigorously, about the
//! scene triangle's first corner (so its rounding is a few ulps of the
//! local sizes, not of the coordinates). A slide
//! along a wall certifies in one interval (the hull stays on its side);
//! the sagitta is second order in the interval's width. Containment
//! cannot begin without triangles meeting, and the body is not inside
//! anything at `t = 0` (checked first), so the certified intervals,
//! examined left to right from `0`, are free of every contact.
//!
//! # The search
//! Intervals are examined left to right from `[0, 1]`: one that is
//! certified is done; one that is not is halved, and once it is no wider
//! than the tolerance its right end is checked exactly, and a contact
//! there ends the check with the bracket `(t_safe, t_contact)`. When
//! halving keeps ending just before a contact (an interval a thousand
//! times narrower than the tolerance, its end free but not certified: the
//! body within the rounding margin of an obstacle it is about to enter),
//! the times `a + tol/128`, …, `a + tol` are checked, and a contact at any
//! of them is a valid bracket, since `[0, a]` is certified. A thin
//! wall is not stepped over: an interval sweeping through it is never
//! certified. An interval narrower than [`MIN_WIDTH`] that is neither
//! certified nor colliding at its end (a grazing motion) is
//! [`MotionError::Undecided`]; past the budget of intervals,
//! [`MotionError::BudgetExhausted`]. Neither is ever a guess.

use super::checker::{cached, shifted, SceneChecker, Scratch};
use std::sync::atomic::Ordering;

use glam::DVec3;

use super::gap::apart_by_more_than;
use crate::kernel::rotation::Pose;
use crate::query::error::QueryError;
use crate::query::motion::{Motion, MotionCheck, MotionError, MIN_TOLERANCE, MIN_WIDTH};
use crate::query::rounding::{pose_rounding_bound, ANGLE_ROUNDING};
use crate::solid::aabb::Aabb;

impl SceneChecker {
    /// The twelve points of body triangle `i`'s swept hull (module docs):
    /// its corners posed at both ends, and each moved by the other end's
    /// translation.
    pub(super) fn swept_points(
        &self,
        s: &mut Scratch,
        i: usize,
        from: &Pose,
        to: &Pose,
    ) -> [DVec3; 12] {
        let shift = to.translation - from.translation;
        let t = self.body.triangles[i];
        let a = t.map(|v| s.at.get(&self.body.vertices, from, v));
        let b = t.map(|v| s.at_b.get(&self.body.vertices, to, v));
        std::array::from_fn(|k| match k / 3 {
            0 => a[k % 3],
            1 => b[k % 3],
            2 => a[k % 3] + shift,
            _ => b[k % 3] - shift,
        })
    }

    /// Whether swept hull `i` comes within `reach` of scene triangle `j`
    /// (not certified apart).
    pub(super) fn swept_near(
        &self,
        s: &mut Scratch,
        i: usize,
        j: usize,
        from: &Pose,
        to: &Pose,
        reach: f64,
    ) -> bool {
        let hull = self.swept_points(s, i, from, to);
        // The hull's exact box first: more than `reach` from the scene
        // triangle's box on an axis is apart (the tree's boxes, carried
        // from the body's frame, are looser for thin slanted triangles).
        let (lo, hi) = hull[1..]
            .iter()
            .fold((hull[0], hull[0]), |(l, h), p| (l.min(*p), h.max(*p)));
        let own = Aabb {
            lo: lo.to_array(),
            hi: hi.to_array(),
        };
        if !own.within(&self.scene.tree.boxes()[j], reach) {
            return false;
        }
        let ends = [[hull[0], hull[1], hull[2]], [hull[3], hull[4], hull[5]]];
        !apart_by_more_than(&hull, &ends, &self.scene_triangle(j), reach)
    }

    /// Whether no swept hull of a body triangle over `[from, to]` (poses
    /// at the interval's ends) comes within `reach` of a scene triangle,
    /// certified (module docs); `false` means "not proved". The body's
    /// tree is walked with each node's box carried to both poses, joined
    /// with both moved by the other end's translation (which holds the
    /// swept hulls of its triangles), computed once per interval for the
    /// nodes reached; only the corners of the triangles reached are posed.
    pub(super) fn certified_apart(
        &self,
        from: Pose,
        to: Pose,
        reach: f64,
        s: &mut Scratch,
    ) -> bool {
        let n = self.body.vertices.len();
        s.at.start(n);
        s.at_b.start(n);
        self.fit_node_cache(s);
        if let Some((i, j)) = s.blocker {
            if self.swept_near(s, i, j, &from, &to, reach) {
                return false;
            }
        }
        let (ma, ta, mb, tb) = (
            from.rotation.matrix(),
            from.translation,
            to.rotation.matrix(),
            to.translation,
        );
        let pad = self.pad(&from).max(self.pad(&to));
        let shift = tb - ta;
        let swept = |b: &Aabb| {
            let (a, z) = (b.transformed(&ma, ta, pad), b.transformed(&mb, tb, pad));
            a.join(&z)
                .join(&shifted(&a, shift))
                .join(&shifted(&z, -shift))
        };
        let (bounds, boxes) = (self.body.tree.bounds(), self.body.tree.boxes());
        let cache = std::mem::take(&mut s.node_cache);
        let epoch = s.at.epoch;
        let scene = &self.scene.tree;
        let mut stack = std::mem::take(&mut s.stack);
        let mut blocker = None;
        let blocked = self.body.tree.for_each_pair(
            |k, _, o| cached(&cache, epoch, k, || swept(&bounds[k])).within(o, reach),
            |k| bounds[k].size(),
            |i, o| swept(&boxes[i]).within(o, reach),
            scene,
            scene.boxes(),
            scene.bounds(),
            &mut stack,
            |i, j| {
                let near = self.swept_near(s, i, j, &from, &to, reach);
                if near {
                    blocker = Some((i, j));
                }
                near
            },
        );
        s.stack = stack;
        s.node_cache = cache;
        if blocked {
            s.blocker = blocker;
        }
        !blocked
    }

    /// Checks the straight motion from `from` to `to` (module docs) with
    /// the bracket no wider than `tolerance` (in `t`).
    ///
    /// # Errors
    /// [`MotionError::Tolerance`] for a tolerance outside
    /// `[MIN_TOLERANCE, 1)`; [`MotionError::Query`] when a posed coordinate
    /// is not finite; [`MotionError::Undecided`] for a grazing motion;
    /// [`MotionError::BudgetExhausted`] past the budget.
    pub fn check(&self, from: Pose, to: Pose, tolerance: f64) -> Result<MotionCheck, MotionError> {
        if !(MIN_TOLERANCE..1.0).contains(&tolerance) {
            return Err(MotionError::Tolerance(tolerance));
        }
        let mut s = self.scratch();
        let out = self.search(from, to, tolerance, &mut s);
        self.give_back(s);
        out
    }

    pub(super) fn search(
        &self,
        from: Pose,
        to: Pose,
        tolerance: f64,
        s: &mut Scratch,
    ) -> Result<MotionCheck, MotionError> {
        self.check_range(&to)?;
        if self.collides_with(from, s)? {
            return Ok(MotionCheck::Collides {
                t_safe: None,
                t_contact: 0.0,
            });
        }
        let motion = Motion::new(from, to);
        let r = self.body.reach;
        // The float angle is within ANGLE_ROUNDING of the exact one, and
        // every posed and swept point within `margin` of the exact motion's
        // (`query::rounding`): a few ulps of the coordinates.
        let angle = (motion.angle() + ANGLE_ROUNDING) * (1.0 + 1e-12);
        let margin = pose_rounding_bound(r, motion.translation_extent());
        let mut intervals = std::mem::take(&mut s.intervals);
        intervals.clear();
        intervals.push((0.0, 1.0));
        let mut steps = 0u64;
        let mut known_free_end = f64::NAN;
        let mut probed_from = f64::NAN;
        let out = loop {
            let Some((a, b)) = intervals.pop() else {
                break Ok(MotionCheck::Free);
            };
            if steps == self.budget {
                break Err(MotionError::BudgetExhausted {
                    t_safe: a,
                    steps: self.budget,
                });
            }
            steps += 1;
            let w = b - a;
            let mid = a + w / 2.0;
            // The sagitta r (1 - cos(δ/2)) = 2 r sin²(δ/4), rounded up.
            let quarter = (angle * w / 4.0).min(std::f64::consts::FRAC_PI_2);
            let sagitta = 2.0 * r * quarter.sin().powi(2) * (1.0 + 1e-12);
            let reach = sagitta + margin;
            if self.certified_apart(motion.at(a), motion.at(b), reach, s) {
                continue;
            }
            if w <= tolerance && b != known_free_end {
                match self.collides_with(motion.at(b), s) {
                    Ok(true) => {
                        break Ok(MotionCheck::Collides {
                            t_safe: Some(a),
                            t_contact: b,
                        })
                    }
                    Ok(false) => known_free_end = b,
                    Err(e) => break Err(e.into()),
                }
            }
            // Halving keeps ending just before a contact (the body within
            // the rounding margin of an obstacle it is about to enter):
            // `[0, a]` is certified, so a contact at any later time within
            // the tolerance is a valid bracket. Probed once per `a`.
            if w * 1024.0 < tolerance && a != probed_from {
                probed_from = a;
                match self.probe_after(&motion, a, tolerance, s) {
                    Ok(Some(t)) => {
                        break Ok(MotionCheck::Collides {
                            t_safe: Some(a),
                            t_contact: t,
                        })
                    }
                    Ok(None) => {}
                    Err(e) => break Err(e.into()),
                }
            }
            if w < MIN_WIDTH {
                break Err(MotionError::Undecided { t_safe: a, t: b });
            }
            intervals.push((mid, b));
            intervals.push((a, mid));
        };
        s.intervals = intervals;
        self.steps.fetch_add(steps, Ordering::Relaxed);
        out
    }

    /// The first of `a + tolerance / 2^k` (`k` = 7 down to 0, at most 1) at
    /// which the body collides, if any.
    pub(super) fn probe_after(
        &self,
        motion: &Motion,
        a: f64,
        tolerance: f64,
        s: &mut Scratch,
    ) -> Result<Option<f64>, QueryError> {
        for k in (0..8).rev() {
            let t = (a + tolerance / f64::from(1u32 << k)).min(1.0);
            if t - a > tolerance {
                continue; // rounded past the tolerance
            }
            if self.collides_with(motion.at(t), s)? {
                return Ok(Some(t));
            }
        }
        Ok(None)
    }

    /// [`SceneChecker::check`] for many motions `(from, to)`, in parallel,
    /// in order.
    ///
    /// # Errors
    /// The first error of [`SceneChecker::check`].
    pub fn check_many(
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
