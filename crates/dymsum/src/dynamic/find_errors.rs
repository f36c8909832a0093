//! FindErrors (paper §4.1) and the fv-corrections (§4.2), one map's face
//! normals at a time (`scan_side`).
//!
//! For each face normal of the moving map that the kinetic schedule
//! ([`super::schedule`]) says is due (the others are certified by their
//! lazy margins without being looked at): skip it if its lazy margin
//! certifies it stays in its cell; else certify its persistent exact ties
//! (steps about a coordinate axis, [`super::ties`]); else decide its cell
//! exactly and, if it left, correct the fv-pair at once by hill climbing
//! (§4.2: the correction happens at detection) and classify the move as a
//! certified single crossing or as at risk (its arcs are re-walked, §4.3).
//! The scan does not touch the ee-pairs.
//!
//! Complexity: O((k + 1) log(m + n)) for the `k` due normals, plus the hill
//! climbs of the normals that moved.

use super::*;

/// The bounds of one step, shared by both sides' scans.
pub(super) struct StepBounds {
    /// The step angle.
    pub(super) theta: f64,
    /// `θ²/4` plus slack: how far a moving normal's path strays from the
    /// great arc between its end positions.
    pub(super) drift: f64,
    /// Accumulated rotation before and after this step (for lazy margins).
    pub(super) before: f64,
    pub(super) after: f64,
    /// The coordinate axis `k` the step turns about exactly, if any (see
    /// [`coordinate_axis`]): then exact ties that persist along the whole
    /// step are certified by [`stays_in_cell_tied`].
    pub(super) axis: Option<usize>,
    /// This step's number, and the one that began the current run of steps
    /// about `axis`: tie margins computed since then (every step in between
    /// was about the same axis) are valid for this step.
    pub(super) tick: u64,
    pub(super) run_start: u64,
    /// The new and the old relative rotation matrices.
    pub(super) rot: DMat3,
    pub(super) rot_old: DMat3,
}

/// A face whose cell changed.
#[derive(Clone, Copy, Debug)]
pub(super) struct Change {
    pub(super) face: u32,
    pub(super) old: u32,
    pub(super) new: u32,
}

/// What a side's FindErrors pass found.
#[derive(Clone, Debug, Default)]
pub(super) struct SideScan {
    pub(super) changed: Vec<Change>,
    pub(super) checked: usize,
    /// Faces whose normal may have had events that are not certified: all
    /// arcs at them are re-walked.
    pub(super) uncertain: Vec<u32>,
    /// `(face, arc)`: the normal crossed exactly that arc of the other map.
    pub(super) certified: Vec<(u32, u32)>,
}

/// FindErrors and fv-corrections for the face normals of `faces` in the
/// cells of `cells` (paper §4.1–4.2), with the certification of the module
/// docs. `to_cells` maps a unit normal of `faces` into the reference frame
/// of `cells` at the new and at the old orientation.
pub(super) fn scan_side(
    views: (&GaussView<'_>, &GaussView<'_>),
    cell_arcs: &[DVec3],
    to_cells: (DMat3, DMat3),
    tied: Option<Tied<'_>>,
    state: &mut Side,
    step: &StepBounds,
    out: &mut SideScan,
) {
    out.changed.clear();
    out.uncertain.clear();
    out.certified.clear();
    out.checked = 0;
    let n = state.assign.len();
    let visit = |f: usize, state: &mut Side, out: &mut SideScan| {
        visit_normal(
            f,
            views,
            cell_arcs,
            to_cells,
            tied.as_ref(),
            state,
            step,
            out,
        );
    };
    if state.scanning {
        // Many normals are due each step (large steps, or small cells): a
        // pass over all of them is cheaper than a schedule. The lazy test
        // first, over the margin arrays in step (no bounds checks), then
        // the visits: a visit changes only its own normal's state, so this
        // visits the same normals in the same order as testing each just
        // before its visit.
        let mut due = std::mem::take(&mut state.due);
        due.clear();
        due.reserve(n);
        if step.axis.is_none() {
            let lazy = state
                .margin
                .iter()
                .zip(&state.margin_at)
                .zip(&state.dir_err);
            for (f, ((&margin, &at), &delta)) in lazy.enumerate() {
                // `lazily_certified` without tie certificates (no axis).
                if !margin_certifies(margin, at, delta, step) {
                    due.push(f as u32);
                }
            }
        } else {
            due.extend((0..n as u32).filter(|&f| !lazily_certified(f as usize, state, step)));
        }
        for &f in &due {
            visit(f as usize, state, out);
        }
        state.due = due;
        if n >= SCHEDULE_FROM && out.checked * SCHEDULE_BELOW < n {
            state.start_schedule(step);
        }
        return;
    }
    // The kinetic schedule: only the normals whose deadline falls inside
    // this step (the others would pass the lazy-margin test unseen).
    if step.run_start == step.tick {
        state.end_tie_keys();
    }
    let mut due = std::mem::take(&mut state.due);
    due.clear();
    state
        .schedule
        .pop_due(step.after + step.drift, step.theta, &mut due);
    due.sort_unstable();
    #[cfg(test)]
    check_schedule_against_scan(state, step, &due);
    for &f in &due {
        visit(f as usize, state, out);
    }
    for &f in &due {
        state.rekey(f as usize, step);
    }
    if due.len() * SCAN_ABOVE > n {
        state.scanning = true;
    }
    state.due = due;
}

/// A step's angle `θ` as computed by `Rotation::angle_to`, padded to at
/// least the exact angle between the two float rotations (module docs,
/// "The accumulated rotation counts up"): `2 atan2(|v|, |w|)` of the
/// quaternions' float product, whose four components each err by at most
/// `5u` (sums of four products of unit quaternions' entries), so `|v|` by
/// at most `9u` absolutely, and the angle by at most `18u` absolutely plus
/// a few `u` relatively (the root, the quotient and `atan2`'s own
/// rounding): `32u` and a relative `2⁻⁴⁸` cover both.
#[inline]
fn angle_up(theta: f64) -> f64 {
    theta * (1.0 + 1.0 / (1u64 << 48) as f64) + 32.0 * crate::kernel::bounds::U
}

/// `a + b` rounded up (for `a, b ≥ 0`): the float sum, one ulp more where
/// Knuth's TwoSum shows it rounded down (module docs, "The accumulated
/// rotation counts up").
#[inline]
fn sum_up(a: f64, b: f64) -> f64 {
    let (s, err) = crate::kernel::dd::two_sum(a, b);
    if err > 0.0 {
        f64::from_bits(s.to_bits() + 1)
    } else {
        s
    }
}

/// Below `1/SCHEDULE_BELOW` of the normals checked in a pass, the side
/// switches to the kinetic schedule; above `1/SCAN_ABOVE` due in a step, back
/// to passes (hysteresis: `SCAN_ABOVE < SCHEDULE_BELOW`).
const SCHEDULE_BELOW: usize = 8;
/// Below this many normals a side always passes over all of them: the
/// pass tests a lazy margin in a few instructions per normal, less than the
/// schedule's bookkeeping (popping, re-keying, relinking) costs per step.
const SCHEDULE_FROM: usize = 48;
const SCAN_ABOVE: usize = 4;

/// Whether face `f`'s normal is certified to stay in its cell over this
/// step without being looked at: its lazy margin (the margin when last
/// computed, less the rotation since) still exceeds this step's needs, or
/// the same through its persistent ties, as long as every step since was
/// about the same coordinate axis. Tested before the call to
/// [`visit_normal`] in a pass over all normals (most pass it), and again
/// inside it.
#[inline(always)]
fn lazily_certified(f: usize, state: &Side, step: &StepBounds) -> bool {
    let delta = state.dir_err[f];
    if margin_certifies(state.margin[f], state.margin_at[f], delta, step) {
        return true;
    }
    if let Some(k) = step.axis {
        if state.tie_axis[f] == k as u8 && state.tie_tick[f] >= step.run_start {
            let tie_lower = state.tie_margin[f] - (step.before - state.margin_at[f]);
            if tie_lower - step.theta > step.drift + delta {
                return true;
            }
        }
    }
    false
}

/// Whether a lazy margin `margin` computed at accumulated rotation `at`
/// (less the rotation since) still exceeds this step's needs, for a normal
/// with direction error `delta`.
#[inline(always)]
fn margin_certifies(margin: f64, at: f64, delta: f64, step: &StepBounds) -> bool {
    let lower = margin - (step.before - at);
    lower - step.theta > step.drift + delta
}

/// FindErrors and the fv-correction for face `f` (module docs).
#[allow(clippy::too_many_arguments)]
fn visit_normal(
    f: usize,
    (faces, cells): (&GaussView<'_>, &GaussView<'_>),
    cell_arcs: &[DVec3],
    to_cells: (DMat3, DMat3),
    tied: Option<&Tied<'_>>,
    state: &mut Side,
    step: &StepBounds,
    out: &mut SideScan,
) {
    let cpoly = cells.poly;
    let delta = state.dir_err[f];
    if lazily_certified(f, state, step) {
        return;
    }
    let lower = state.margin[f] - (step.before - state.margin_at[f]);
    state.tie_axis[f] = NO_AXIS;
    out.checked += 1;
    let unit = faces.poly.unit_normal(f);
    let x_new = to_cells.0 * unit;
    let v = state.assign[f];
    let mut m1 = margin(cpoly, cell_arcs, v, x_new);
    // Exact ties that persist along a step about a coordinate axis: the
    // normal is certified to stay in its cell without exact predicates.
    if let (Some(k), Some(tied)) = (step.axis, &tied) {
        if m1 <= EXACT_BELOW + delta || lower.min(m1) <= step.drift + delta {
            if let Some(tm) = stays_in_cell_tied(
                (faces, cells),
                cell_arcs,
                (f as u32, v),
                (to_cells.1 * unit, x_new),
                step.drift + delta,
                (k, step.theta),
                tied,
            ) {
                state.margin[f] = m1;
                state.margin_at[f] = step.after;
                state.tie_margin[f] = tm;
                state.tie_axis[f] = k as u8;
                state.tie_tick[f] = step.tick;
                return;
            }
        }
    }
    if m1 <= EXACT_BELOW + delta {
        // A margin clearly below zero is certainly outside. The exact
        // normal (a turned view's rotation and error bound) only when an
        // exact predicate needs it.
        if m1 < -(EXACT_BELOW + delta) || !cells.in_cell(v, &faces.normal(f as u32)) {
            let (v2, m2, new_side) =
                match locate_certified(cpoly, cell_arcs, x_new, EXACT_BELOW + delta, v) {
                    Some(l) => (l.cell, l.margin, Some(l.least_off_start)),
                    None => {
                        let v2 = cells.locate(&faces.normal(f as u32), v).0;
                        (v2, margin(cpoly, cell_arcs, v2, x_new), None)
                    }
                };
            state.assign[f] = v2;
            m1 = m2;
            out.changed.push(Change {
                face: f as u32,
                old: v,
                new: v2,
            });
            let x_old = to_cells.1 * unit;
            match single_crossing(
                cpoly,
                cell_arcs,
                (v, x_old),
                (v2, x_new),
                step.theta + delta,
                new_side,
            ) {
                Some(arc) => out.certified.push((f as u32, arc)),
                None => out.uncertain.push(f as u32),
            }
        } else if lower.min(m1) <= step.drift + delta {
            out.uncertain.push(f as u32);
        }
    } else if lower.min(m1) <= step.drift + delta {
        out.uncertain.push(f as u32);
    }
    state.margin[f] = m1;
    state.margin_at[f] = step.after;
}

impl DynamicSum {
    /// The bounds of this step, and the bookkeeping they rest on (the
    /// accumulated rotation of the lazy margins, the current run of steps
    /// about one coordinate axis, the exact zero structure at its first
    /// step).
    pub(super) fn step_bounds(&mut self, old: Rotation, theta: f64) -> StepBounds {
        self.step = self.step.wrapping_add(1).max(1);
        let (rot, rot_old) = (self.ops.relative.matrix(), old.matrix());
        if self.theta_acc > REBASE_AFTER {
            let shift = self.theta_acc;
            self.theta_acc = 0.0;
            self.p.rebase(shift);
            self.q.rebase(shift);
        }
        // The rotation the lazy margins decay by must never count less
        // than the exact one: the step's angle padded for `angle_to`'s
        // rounding, and the sum rounded up (module docs, "The accumulated
        // rotation counts up").
        let theta = angle_up(theta);
        let before = self.theta_acc;
        self.theta_acc = sum_up(before, theta);
        let axis = coordinate_axis(&rot_old, &rot);
        self.tick += 1;
        if axis != self.axis_run {
            self.axis_run = axis;
            self.axis_since = self.tick;
        }
        if axis.is_some() && self.zeros.is_none() {
            let (p, q) = (&self.ops.p, &self.ops.q);
            self.zeros = Some(Box::new([ExactZeros::of(p), ExactZeros::of(q)]));
        }
        StepBounds {
            theta,
            drift: theta * theta / 4.0 + SLACK,
            before,
            after: self.theta_acc,
            axis,
            tick: self.tick,
            run_start: self.axis_since,
            rot,
            rot_old,
        }
    }

    /// FindErrors on both maps: P's normals in Q's cells, then Q's in P's,
    /// each fv-error corrected where it is found.
    pub(super) fn find_errors(&mut self, step: &StepBounds, [scan_p, scan_q]: &mut [SideScan; 2]) {
        let zeros = self.zeros.as_deref();
        scan_side(
            (&self.ops.view_p(), &self.ops.view_q()),
            &self.q.arcs,
            (step.rot, step.rot_old),
            zeros.map(|[zp, zq]| Tied {
                moving: zp,
                fixed: zq,
                moving_is_p: true,
            }),
            &mut self.p,
            step,
            scan_p,
        );
        scan_side(
            (&self.ops.view_q(), &self.ops.view_p()),
            &self.p.arcs,
            (step.rot.transpose(), step.rot_old.transpose()),
            zeros.map(|[zp, zq]| Tied {
                moving: zq,
                fixed: zp,
                moving_is_p: false,
            }),
            &mut self.q,
            step,
            scan_q,
        );
    }
}

/// The schedule's invariant, checked on every scheduled step of the unit
/// tests: every normal it did not pop passes the old lazy-skip test (plain
/// margin or a valid tie certificate), i.e. a pass over all normals would
/// have skipped it too.
#[cfg(test)]
pub(super) static SCHEDULED_STEPS: std::sync::atomic::AtomicUsize =
    std::sync::atomic::AtomicUsize::new(0);
#[cfg(test)]
pub(super) static TIE_SKIPS: std::sync::atomic::AtomicUsize =
    std::sync::atomic::AtomicUsize::new(0);
#[cfg(test)]
fn check_schedule_against_scan(state: &Side, step: &StepBounds, due: &[u32]) {
    SCHEDULED_STEPS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let n = state.assign.len();
    let mut popped = vec![false; n];
    for &f in due {
        popped[f as usize] = true;
    }
    for (f, _) in popped.iter().enumerate().filter(|(_, &p)| !p) {
        let delta = state.dir_err[f];
        let lower = state.margin[f] - (step.before - state.margin_at[f]);
        let plain = lower - step.theta > step.drift + delta;
        let tied = step.axis.is_some_and(|k| {
            state.tie_axis[f] == k as u8
                && state.tie_tick[f] >= step.run_start
                && state.tie_margin[f] - (step.before - state.margin_at[f]) - step.theta
                    > step.drift + delta
        });
        if tied && !plain {
            TIE_SKIPS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        }
        assert!(
            plain || tied,
            "face {f} not popped but the old test visits it: margin {} at {} tie {} axis {} tick {} run {} step {:?} {} {} {}",
            state.margin[f],
            state.margin_at[f],
            state.tie_margin[f],
            state.tie_axis[f],
            state.tie_tick[f],
            step.run_start,
            step.axis,
            step.before,
            step.after,
            step.theta
        );
    }
}

#[cfg(test)]
mod accumulated_rotation {
    //! The accumulated rotation counts up (module docs of `dynamic`): the
    //! two motions of the independent review of 2026-12-02 that made a
    //! plain float sum count less than the bodies turned.
    use super::*;
    use crate::sum::{minkowski_sum_posed, Method};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn turn(axis: DVec3, angle: f64) -> Rotation {
        Rotation::from_axis_angle(axis, angle).unwrap()
    }

    /// The hull of a face's three corners and twelve seeded points drawn
    /// in `ranges` (one per coordinate) on the face's inner side.
    fn face_and_points(face: [[f64; 3]; 3], seed: u64, ranges: [(f64, f64); 3]) -> Polytope {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut pts = face.to_vec();
        for _ in 0..12 {
            pts.push(ranges.map(|(lo, hi)| rng.random_range(lo..hi)));
        }
        Polytope::from_points(&pts).unwrap()
    }

    /// Turns P back and forth by 0.3 rad until the accumulated rotation is
    /// past 700 (where an ulp of it is `1.1·10⁻¹³`).
    fn accumulate(sum: &mut DynamicSum) {
        let axis = DVec3::new(1.0, 2.0, 3.0).normalize();
        let (mut t, mut dir) = (0.0f64, 1.0);
        while sum.theta_acc < 700.0 {
            t += 0.3 * dir;
            if !(0.0..=3.0).contains(&t) {
                dir = -dir;
            }
            sum.set_pose(Pose::new(turn(axis, t), DVec3::ZERO), Pose::IDENTITY);
        }
        assert!(sum.theta_acc < 1000.0);
    }

    /// 62,000 steps of `3·10⁻⁸` rad about z, each `0.45` ulp of the
    /// accumulated rotation past a whole number of ulps, bring P's face
    /// `x = 1` head-on onto an arc of an octahedron's map: a plain sum lost
    /// `3.2·10⁻⁹` rad, the face was never revisited, and the overlay
    /// differed from `walk`'s.
    #[test]
    fn a_rotation_of_many_small_steps_is_counted_in_full() {
        let phi = 0.6f64;
        let m = turn(DVec3::Z, phi).matrix();
        let (c, s) = (m.col(0)[0], m.col(0)[1]);
        // The arc between the faces (+, +, ±) crosses the equator at
        // exactly (c, s, 0), where P's face normal ends.
        let q = Polytope::from_points(&[
            [s, 0.0, 0.0],
            [-s, 0.0, 0.0],
            [0.0, c, 0.0],
            [0.0, -c, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ])
        .unwrap();
        let face = [[1.0, 0.25, 0.5], [1.0, -0.5, 0.125], [1.0, 0.375, -0.625]];
        let p = face_and_points(face, 11, [(-1.5, 0.5), (-1.5, 1.5), (-1.5, 1.5)]);
        let mut sum = DynamicSum::new(&p, Pose::IDENTITY, &q, Pose::IDENTITY).unwrap();
        accumulate(&mut sum);
        let ulp = 2f64.powi(-43);
        let step = ((3e-8 / ulp).round() + 0.45) * ulp;
        let n = 62_000usize;
        sum.set_pose(
            Pose::new(turn(DVec3::Z, phi - n as f64 * step), DVec3::ZERO),
            Pose::IDENTITY,
        );
        let before = sum.theta_acc;
        for k in 1..=n {
            let at = if k == n {
                phi
            } else {
                phi - (n - k) as f64 * step
            };
            sum.set_pose(Pose::new(turn(DVec3::Z, at), DVec3::ZERO), Pose::IDENTITY);
        }
        assert!(sum.theta_acc - before >= n as f64 * step * (1.0 - 1e-9));
        let fresh = minkowski_sum_posed(&p, sum.pose_p(), &q, sum.pose_q(), Method::Walk).unwrap();
        assert_eq!(sum.facets(), fresh.facets());
    }

    /// 60,000 steps of `5·10⁻¹⁴` rad (below half an ulp of the accumulated
    /// rotation: a plain sum added nothing) end at an exact quarter turn
    /// about z, where P's face `y + z = 1` has its normal exactly on an arc
    /// of the box's map: its margin must not certify it strictly inside.
    #[test]
    fn steps_below_half_an_ulp_still_count() {
        let face = [[0.25, 0.25, 0.75], [-0.5, 0.875, 0.125], [0.75, 0.5, 0.5]];
        let p = face_and_points(face, 1, [(-1.0, 1.5), (-1.5, 0.4), (-1.5, 0.4)]);
        let q = crate::query::test_support::boxed(1.0, 0.5, 0.75);
        let f = (0..p.face_count())
            .find(|&f| {
                let n = p.unit_normal(f);
                n.x == 0.0 && (n.y - n.z).abs() < 1e-15 && n.y > 0.0
            })
            .expect("the face y + z = 1");
        let mut sum = DynamicSum::new(&p, Pose::IDENTITY, &q, Pose::IDENTITY).unwrap();
        accumulate(&mut sum);
        let (eps, step) = (3e-9, 5e-14);
        let start = std::f64::consts::FRAC_PI_2 - eps;
        sum.set_pose(
            Pose::new(turn(DVec3::Z, start), DVec3::ZERO),
            Pose::IDENTITY,
        );
        let before = sum.theta_acc;
        let n = (eps / step) as usize;
        for j in 1..=n {
            let at = start + step * j as f64;
            sum.set_pose(Pose::new(turn(DVec3::Z, at), DVec3::ZERO), Pose::IDENTITY);
        }
        let quarter = turn(DVec3::Z, std::f64::consts::FRAC_PI_2);
        sum.set_pose(Pose::new(quarter, DVec3::ZERO), Pose::IDENTITY);
        assert!(sum.theta_acc - before >= eps * (1.0 - 1e-6));
        assert!(!sum.normal_strictly_inside(false, f));
        let fresh = minkowski_sum_posed(&p, sum.pose_p(), &q, sum.pose_q(), Method::Walk).unwrap();
        assert_eq!(sum.facets(), fresh.facets());
    }
}
