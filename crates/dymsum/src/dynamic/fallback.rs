//! Falling back to a recomputation: steps too large for DYMSUM, or with
//! too many arcs at risk, are recomputed by the static `walk` and reported
//! as the diff of the two overlays; an exponential [`Backoff`] skips the
//! scan on the next steps of similar size.

use super::*;

/// Exponential backoff of the incremental attempt after fallbacks. A first
/// fallback skips nothing: it is most often a one-off (a degenerate start,
/// such as two equal bodies at the same orientation, whose every normal is
/// tied), and the next step, from a generic pose, is incremental again. A
/// second fallback in a row makes the next 4 steps at least 90% as large
/// recompute without scanning first; each further one doubles the count
/// (up to 64), an incremental step resets it. So a degenerate start costs
/// one recomputation, not five, and a motion too fast for incremental
/// updates wastes a scan on at most one step in 64. Either way the result
/// is exact: only the work differs.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Backoff {
    pub(super) theta: f64,
    pub(super) skip: u32,
    pub(super) next: u32,
}

impl Backoff {
    pub(super) fn fell_back(&mut self, theta: f64) {
        self.theta = theta;
        // 0 → 2 (a first fallback: nothing skipped), then 4, 8, …, 64.
        self.next = if self.next == 0 {
            2
        } else {
            (self.next * 2).clamp(4, 64)
        };
        self.skip = if self.next < 4 { 0 } else { self.next };
    }
}

impl DynamicSum {
    /// Recomputes from scratch (large steps, too many arcs at risk, or the
    /// recovery from a failed repair), reporting the diff against the
    /// overlay before this step.
    pub(super) fn recompute(&mut self, report: &mut UpdateReport) {
        let before = self.overlay_before(report);
        let fresh = self.fresh_overlay(report);
        let (removed, added) = overlay_diff(&before, &fresh);
        report.removed = removed;
        report.added = added;
        report.fv_errors = report
            .removed
            .iter()
            .filter(|f| !matches!(f, Facet::Ee { .. }))
            .count();
        report.ee_errors = report.removed.len() - report.fv_errors;
        report.rewalked_arcs = self.p.ee.len();
        report.recomputed = true;
        self.load_overlay(fresh);
    }

    /// The overlay before this step: the current one with the changes this
    /// step already made (listed in the report) undone.
    fn overlay_before(&self, report: &UpdateReport) -> Overlay {
        let mut before = self.overlay();
        let mut ee: std::collections::BTreeSet<(u32, u32)> = before.ee.drain(..).collect();
        for f in &report.removed {
            match *f {
                Facet::Fv { p_face, q_vertex } => before.fv[p_face as usize] = q_vertex,
                Facet::Vf { p_vertex, q_face } => before.vf[q_face as usize] = p_vertex,
                Facet::Ee { p_edge, q_edge } => {
                    ee.insert((p_edge, q_edge));
                }
            }
        }
        for f in &report.added {
            if let Facet::Ee { p_edge, q_edge } = *f {
                ee.remove(&(p_edge, q_edge));
            }
        }
        before.ee = ee.into_iter().collect();
        before
    }

    /// The overlay at the current poses from scratch, by `walk`; should that
    /// report an internal inconsistency (a bug), by the independent
    /// brute-force method, noting it in the report.
    fn fresh_overlay(&self, report: &mut UpdateReport) -> Overlay {
        match walk_overlay(&self.ops) {
            Ok(fresh) => fresh,
            Err(walk) => {
                report.recovered = Some(walk.to_string());
                crate::sum::brute_overlay(&self.ops).unwrap_or_else(|brute| {
                    panic!(
                        "dymsum internal error: walk ({walk}) and brute force ({brute}) \
                         both failed at the same poses; please report them"
                    )
                })
            }
        }
    }

    /// Too large a step, or a step within the backoff after a step as large
    /// fell back: recompute without scanning.
    pub(super) fn must_recompute(&mut self, theta: f64) -> bool {
        if theta > self.config.max_step_angle {
            return true;
        }
        if self.backoff.skip > 0 && theta >= 0.9 * self.backoff.theta {
            self.backoff.skip -= 1;
            return true;
        }
        false
    }

    /// More than [`DynamicConfig::fallback_fraction`] of all arcs at risk.
    pub(super) fn too_many_at_risk(&self, at_risk: &[Vec<u32>; 2]) -> bool {
        let total = self.p.ee.len() + self.q.ee.len();
        (at_risk[0].len() + at_risk[1].len()) as f64 > self.config.fallback_fraction * total as f64
    }

    /// Starts or extends the backoff after a fallback, except about a
    /// coordinate axis: there many arcs at risk means an isolated exact
    /// coincidence (faces becoming parallel at a quarter turn), and the next
    /// steps are certified by their persistent ties again.
    pub(super) fn note_fallback(&mut self, axis: Option<usize>, theta: f64) {
        if axis.is_none() {
            self.backoff.fell_back(theta);
        }
    }
}
