//! One measurement: P turns under the paper's motion; every step is a timed
//! DYMSUM update, and the static methods are timed afterwards on the same
//! poses (all of them, or an evenly spaced deterministic subsample).
//!
//! The static methods are timed after the dynamic run, pose by pose, so the
//! DYMSUM timings are not disturbed by the (much larger) working sets of
//! `brute` and `hull`. At every pose where `brute` or `hull` is timed the
//! dynamic facet set is saved (untimed) and compared with theirs, and after
//! the last step the dynamic facets are compared with a fresh `walk` sum.
//! The whole measurement is repeated [`Plan::repeats`] times with the same
//! motion, and each method's figure is the median of the repeats' means.

use std::io::Write;
use std::time::Instant;

use anyhow::Context;
use dymsum::sum::{minkowski_sum_posed, Facet, Method, SumError};
use dymsum::{DVec3, DynamicSum, Polytope, Pose, Rotation};

use super::num;
use crate::random_motion::PaperMotion;
use crate::stats::{mean, median, micros};

/// What to measure.
#[derive(Clone, Copy, Debug)]
pub struct Plan {
    /// Steps per full turn (the paper's X).
    pub steps_per_rev: f64,
    /// Seed of the motion.
    pub seed: u64,
    /// DYMSUM updates per run (all timed).
    pub steps: usize,
    /// Poses at which `walk` is timed (capped at `steps`).
    pub walk_poses: usize,
    /// Poses at which `brute` is timed (capped at `steps`).
    pub brute_poses: usize,
    /// Poses at which `hull` is timed (capped at `steps`).
    pub hull_poses: usize,
    /// How many times the whole measurement is repeated (same motion, fresh
    /// DYMSUM state); each method's figure is the median of the repeats'
    /// means, which keeps one run disturbed by other load on a shared
    /// machine from moving the result.
    pub repeats: usize,
}

impl Plan {
    /// The plan of the rotation and size experiments: DYMSUM and `walk` at
    /// every one of `steps` steps, `brute` at `brute_poses` poses, no `hull`.
    pub fn walk_and_brute(
        steps_per_rev: f64,
        seed: u64,
        steps: usize,
        brute_poses: usize,
        repeats: usize,
    ) -> Plan {
        Plan {
            steps_per_rev,
            seed,
            steps,
            walk_poses: steps,
            brute_poses,
            hull_poses: 0,
            repeats,
        }
    }
}

/// The timings of one pair: for each method, the mean time (microseconds
/// per update or per static sum) of every repeat.
#[derive(Clone, Debug, Default)]
pub struct Timings {
    /// DYMSUM updates per repeat.
    pub steps: usize,
    /// Mean DYMSUM update time of each repeat.
    pub dymsum: Vec<f64>,
    /// Mean `walk` time of each repeat.
    pub walk: Vec<f64>,
    /// Mean `brute` time of each repeat.
    pub brute: Vec<f64>,
    /// Mean `hull` time of each repeat (over its successful calls).
    pub hull: Vec<f64>,
    /// Poses per repeat at which `walk`, `brute`, `hull` are timed.
    pub static_poses: [usize; 3],
    /// `hull` calls that returned an error (not timed), over all repeats.
    pub hull_errors: usize,
    /// `hull` calls made, over all repeats.
    pub hull_calls: usize,
    /// Updates of the first repeat that fell back to a from-scratch sum.
    pub recomputed: usize,
    /// Facet changes per update in the first repeat: `(removed + added) / 2`
    /// facets, averaged over the updates.
    pub changes: f64,
    /// Facet-set comparisons made (sampled poses and the final pose).
    pub checks: usize,
    /// Comparisons where a method disagreed with DYMSUM (must be 0).
    pub mismatches: usize,
}

impl Timings {
    /// DYMSUM: median over the repeats of the mean update time.
    pub fn dymsum_us(&self) -> f64 {
        median_or_nan(&self.dymsum)
    }
    /// `walk`: median of the repeats' means (NaN if not timed).
    pub fn walk_us(&self) -> f64 {
        median_or_nan(&self.walk)
    }
    /// `brute`: median of the repeats' means (NaN if not timed).
    pub fn brute_us(&self) -> f64 {
        median_or_nan(&self.brute)
    }
    /// `hull`: median of the repeats' means (NaN if not timed or every
    /// call failed).
    pub fn hull_us(&self) -> f64 {
        median_or_nan(&self.hull)
    }
    /// The figures one point of the rotation and size experiments reports.
    pub fn figures(&self) -> Figures {
        Figures {
            steps: self.steps,
            dymsum: self.dymsum_us(),
            walk: self.walk_us(),
            brute: self.brute_us(),
            recomputed: self.recomputed,
            changes: self.changes,
            checks: self.checks,
            mismatches: self.mismatches,
        }
    }
}

/// The figures of one measurement that the rotation and size experiments
/// report (DYMSUM, `walk` and `brute`; no `hull`).
#[derive(Clone, Copy, Debug)]
pub struct Figures {
    /// DYMSUM updates per repeat.
    pub steps: usize,
    /// DYMSUM: median of the repeats' mean update times (µs).
    pub dymsum: f64,
    /// `walk`: median of the repeats' means (µs).
    pub walk: f64,
    /// `brute`: median of the repeats' means (µs).
    pub brute: f64,
    /// Updates of the first repeat that fell back to a from-scratch sum.
    pub recomputed: usize,
    /// Facet changes per update, `(removed + added) / 2` (see
    /// [`Timings::changes`]).
    pub changes: f64,
    /// Facet-set comparisons made.
    pub checks: usize,
    /// Comparisons where a method disagreed with DYMSUM.
    pub mismatches: usize,
}

impl Figures {
    /// The CSV fields `steps, dymsum_us, walk_us, brute_us,
    /// recomputed_steps, checks, mismatches, changes_per_step,
    /// dymsum_ns_per_change`.
    pub fn csv_fields(&self) -> [String; 9] {
        [
            self.steps.to_string(),
            num(self.dymsum, 3),
            num(self.walk, 3),
            num(self.brute, 3),
            self.recomputed.to_string(),
            self.checks.to_string(),
            self.mismatches.to_string(),
            num(self.changes, 2),
            num(self.ns_per_change(), 1),
        ]
    }

    /// DYMSUM's mean update time per facet change (ns; NaN without
    /// changes).
    pub fn ns_per_change(&self) -> f64 {
        if self.changes > 0.0 {
            1000.0 * self.dymsum / self.changes
        } else {
            f64::NAN
        }
    }
}

/// Writes the `verified:` line over all the measurements; returns the
/// total number of mismatches.
///
/// # Errors
/// The I/O error of writing to `out`.
pub fn write_verified<'a>(
    out: &mut dyn Write,
    figures: impl IntoIterator<Item = &'a Figures>,
) -> std::io::Result<usize> {
    let (checks, mismatches) = figures
        .into_iter()
        .fold((0, 0), |(c, m), f| (c + f.checks, m + f.mismatches));
    writeln!(
        out,
        "verified: {checks} facet-set comparisons (DYMSUM vs a fresh walk after every run, vs brute at its poses): {mismatches} mismatches"
    )?;
    Ok(mismatches)
}

/// Fails when any facet-set comparison disagreed with DYMSUM.
///
/// # Errors
/// An internal error naming the count when `mismatches > 0`.
pub fn ensure_no_mismatches(mismatches: usize) -> anyhow::Result<()> {
    if mismatches > 0 {
        anyhow::bail!("internal error: {mismatches} facet-set comparisons disagreed with DYMSUM (please report)");
    }
    Ok(())
}

fn median_or_nan(xs: &[f64]) -> f64 {
    if xs.is_empty() {
        f64::NAN
    } else {
        median(xs)
    }
}

/// `k` evenly spaced step indices out of `n` (the middle of each of `k`
/// equal blocks; all of them when `k >= n`).
///
/// ```
/// use dymsum_cli::commands::bench::measure::sample_indices;
/// assert_eq!(sample_indices(10, 2), vec![2, 7]);
/// assert_eq!(sample_indices(3, 5), vec![0, 1, 2]);
/// assert!(sample_indices(5, 0).is_empty());
/// ```
pub fn sample_indices(n: usize, k: usize) -> Vec<usize> {
    if k >= n {
        return (0..n).collect();
    }
    (0..k).map(|j| ((2 * j + 1) * n) / (2 * k)).collect()
}

/// Times one static sum of P at `pose_p` and Q at the identity; returns
/// microseconds and the facets (or the error). Only the sum is timed, not
/// the extraction of its facets.
pub(crate) fn time_static(
    p: &Polytope,
    pose_p: Pose,
    q: &Polytope,
    method: Method,
) -> (f64, Result<Vec<Facet>, SumError>) {
    let start = Instant::now();
    let sum = minkowski_sum_posed(p, pose_p, q, Pose::IDENTITY, method);
    let us = micros(start.elapsed());
    (us, sum.map(|s| s.facets()))
}

/// Runs the plan on P (moving) and Q (fixed at the identity).
///
/// # Errors
/// The initial dynamic sum, a DYMSUM update (naming the step) or the final
/// static `walk` sum fails, or a sampled static `walk` or `brute` sum fails
/// (naming the method and step). A failing `hull` sum is not an error: it
/// is counted in [`Timings::hull_errors`].
pub fn measure(p: &Polytope, q: &Polytope, plan: &Plan) -> anyhow::Result<Timings> {
    let n = plan.steps.max(1);
    let walk_at = sample_indices(n, plan.walk_poses);
    let brute_at = sample_indices(n, plan.brute_poses);
    let hull_at = sample_indices(n, plan.hull_poses);
    let mut check_at = vec![false; n];
    for &i in brute_at.iter().chain(&hull_at) {
        check_at[i] = true;
    }
    let mut t = Timings {
        steps: n,
        static_poses: [walk_at.len(), brute_at.len(), hull_at.len()],
        ..Timings::default()
    };
    // Warm-up (untimed): one static sum at the start pose.
    let _ = time_static(p, Pose::IDENTITY, q, Method::Walk);

    // The first repeat also records the poses and the facets to compare.
    let first_run = run_dynamic(p, q, plan, &check_at, true)?;
    t.dymsum.push(mean(&first_run.times));
    t.recomputed = first_run.recomputed;
    t.changes = first_run.changes as f64 / n as f64;
    if let Some(agrees) = first_run.final_agrees {
        t.checks += 1;
        t.mismatches += usize::from(!agrees);
    }
    for _ in 1..plan.repeats.max(1) {
        let run = run_dynamic(p, q, plan, &check_at, false)?;
        t.dymsum.push(mean(&run.times));
    }

    for repeat in 0..plan.repeats.max(1) {
        // Only the first repeat compares facet sets with the saved ones.
        let saved = (repeat == 0).then_some(first_run.saved.as_slice());
        for (method, at) in [
            (Method::Walk, &walk_at),
            (Method::Brute, &brute_at),
            (Method::Hull, &hull_at),
        ] {
            let times = time_static_at(p, q, method, at, &first_run.poses, saved, &mut t)?;
            if !times.is_empty() {
                let m = mean(&times);
                match method {
                    Method::Walk => t.walk.push(m),
                    Method::Brute => t.brute.push(m),
                    Method::Hull => t.hull.push(m),
                }
            }
        }
    }
    Ok(t)
}

/// One timed DYMSUM run along the motion.
struct DynamicRun {
    /// Time of each update (µs).
    times: Vec<f64>,
    /// P's rotation after each step (recorded runs only).
    poses: Vec<Rotation>,
    /// The dynamic facets at the steps marked for checking (recorded runs
    /// only).
    saved: Vec<Option<Vec<Facet>>>,
    /// Updates that fell back to a from-scratch sum (recorded runs only).
    recomputed: usize,
    /// Facet changes, `(removed + added) / 2` summed over the updates
    /// (recorded runs only).
    changes: usize,
    /// Whether the final dynamic facets equal a fresh `walk` sum's
    /// (recorded runs only).
    final_agrees: Option<bool>,
}

/// Runs DYMSUM from the identity through `check_at.len()` steps of the
/// paper's motion, timing each update and saving (untimed) the facets at
/// the steps `check_at` marks; then compares the final facets with a fresh
/// `walk` sum (untimed). Poses, facets, fallbacks and the final comparison
/// are recorded only if `record`.
fn run_dynamic(
    p: &Polytope,
    q: &Polytope,
    plan: &Plan,
    check_at: &[bool],
    record: bool,
) -> anyhow::Result<DynamicRun> {
    let n = check_at.len();
    let mut dynamic =
        DynamicSum::new(p, Pose::IDENTITY, q, Pose::IDENTITY).context("initial DYMSUM sum")?;
    let mut motion = PaperMotion::new(plan.steps_per_rev, plan.seed);
    let mut rot = Rotation::IDENTITY;
    let mut run = DynamicRun {
        times: Vec::with_capacity(n),
        poses: Vec::with_capacity(n),
        saved: vec![None; n],
        recomputed: 0,
        changes: 0,
        final_agrees: None,
    };
    for (i, save) in check_at.iter().enumerate() {
        rot = rot.then(&motion.next_step());
        let start = Instant::now();
        let report = dynamic.set_pose_p(Pose::new(rot, DVec3::ZERO));
        run.times.push(micros(start.elapsed()));
        if record {
            run.recomputed += usize::from(report.recomputed);
            run.changes += (report.removed.len() + report.added.len()) / 2;
            run.poses.push(rot);
            if *save {
                run.saved[i] = Some(dynamic.facets());
            }
        }
    }
    if record {
        // The final pose: the dynamic facets against a fresh walk sum.
        let fresh = minkowski_sum_posed(p, dynamic.pose_p(), q, Pose::IDENTITY, Method::Walk)
            .context("final static walk sum")?;
        run.final_agrees = Some(fresh.facets() == dynamic.facets());
    }
    Ok(run)
}

/// Times `method` at the steps `at` (poses from `poses`), returning the
/// successful calls' times. Where `saved` holds DYMSUM's facets for a step,
/// they are compared with the method's (counted in `t.checks` and
/// `t.mismatches`); `hull` calls and failures are counted in `t`, a failure
/// of another method is an error.
fn time_static_at(
    p: &Polytope,
    q: &Polytope,
    method: Method,
    at: &[usize],
    poses: &[Rotation],
    saved: Option<&[Option<Vec<Facet>>]>,
    t: &mut Timings,
) -> anyhow::Result<Vec<f64>> {
    let mut times = Vec::with_capacity(at.len());
    for &i in at {
        let (us, facets) = time_static(p, Pose::new(poses[i], DVec3::ZERO), q, method);
        if method == Method::Hull {
            t.hull_calls += 1;
        }
        match facets {
            Ok(f) => {
                times.push(us);
                if let Some(Some(d)) = saved.map(|s| &s[i]) {
                    t.checks += 1;
                    t.mismatches += usize::from(*d != f);
                }
            }
            Err(_) if method == Method::Hull => t.hull_errors += 1,
            Err(e) => {
                anyhow::bail!("static {} sum at step {}: {e}", method.name(), i + 1)
            }
        }
    }
    Ok(times)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_small_run_agrees_everywhere() {
        let p = dymsum_io::load_polytope("gs1", Default::default())
            .unwrap()
            .polytope;
        let q = dymsum_io::load_polytope("cube", Default::default())
            .unwrap()
            .polytope;
        let plan = Plan {
            steps_per_rev: 500.0,
            seed: 1,
            steps: 40,
            walk_poses: 40,
            brute_poses: 3,
            hull_poses: 2,
            repeats: 3,
        };
        let t = measure(&p, &q, &plan).unwrap();
        assert_eq!(t.steps, 40);
        assert_eq!(t.dymsum.len(), 3);
        assert_eq!(t.walk.len(), 3);
        assert_eq!(t.brute.len(), 3);
        assert_eq!(t.static_poses, [40, 3, 2]);
        assert_eq!(t.hull_calls, 6);
        assert_eq!(t.mismatches, 0);
        // The final pose, 3 brute poses and 2 hull poses (if hull succeeded).
        assert!(t.checks >= 4);
        assert!(t.dymsum_us() > 0.0 && t.brute_us() > 0.0);
    }
}
