//! Correcting ee-errors (paper §4.3): certified single crossings toggle the
//! pairs they flip (`apply_certified_crossings`), every other arc at a
//! normal at risk is re-walked through the other map between its corrected
//! fv-pairs (`rewalk`) and its crossings are diffed against the stored ones.
//!
//! Complexity: O(degree) per certified crossing; a re-walk costs the number
//! of cells the arc crosses.

use super::*;

impl DynamicSum {
    /// Toggles the ee-pairs flipped by certified single crossings: a face
    /// normal of P that crossed exactly the arc `x` of Q flips the pairs
    /// (edge of that face, `x`), and symmetrically for Q. Toggles combine by
    /// parity; pairs on a re-walked arc are left to the re-walk.
    pub(super) fn apply_certified_crossings(
        &mut self,
        certified_p: &[(u32, u32)],
        certified_q: &[(u32, u32)],
        report: &mut UpdateReport,
    ) {
        let mut pending = std::mem::take(&mut self.scratch_toggled);
        pending.clear();
        for &(f, x) in certified_p {
            pending.extend(self.ops.p.face_edges(f as usize).iter().map(|&e| (e, x)));
        }
        for &(g, y) in certified_q {
            pending.extend(self.ops.q.face_edges(g as usize).iter().map(|&x| (y, x)));
        }
        // Toggles combine by parity (both ends of an edge may cross the same
        // arc in one step); pairs on re-walked arcs are left to the re-walk.
        // Sorted by one u64 key: the pairs' order, cheaper comparisons.
        pending.sort_unstable_by_key(|&(e, x)| (u64::from(e) << 32) | u64::from(x));
        let mut i = 0;
        while i < pending.len() {
            let (e, x) = pending[i];
            let mut j = i + 1;
            while j < pending.len() && pending[j] == (e, x) {
                j += 1;
            }
            let odd = (j - i) % 2 == 1;
            i = j;
            if !odd
                || self.p.stamp[e as usize] == self.step
                || self.q.stamp[x as usize] == self.step
            {
                continue;
            }
            let facet = Facet::Ee {
                p_edge: e,
                q_edge: x,
            };
            if self.toggle_pair(e, x) {
                report.removed.push(facet);
                report.ee_errors += 1;
            } else {
                report.added.push(facet);
            }
        }
        self.scratch_toggled = pending;
    }

    /// Flips the membership of the pair `(e, x)`; returns whether it was
    /// present before.
    pub(super) fn toggle_pair(&mut self, e: u32, x: u32) -> bool {
        let list = &mut self.p.ee[e as usize];
        if let Some(k) = list.iter().position(|&y| y == x) {
            list.swap_remove(k);
            let back = &mut self.q.ee[x as usize];
            if let Some(k) = back.iter().position(|&y| y == e) {
                back.swap_remove(k);
            }
            true
        } else {
            list.push(x);
            self.q.ee[x as usize].push(e);
            false
        }
    }

    /// Re-walks the arc of edge `e` of P through Q's map (`side = P`) or of
    /// edge `e` of Q through P's map (`side = Q`), and diffs its crossings
    /// against the stored ones, keeping both indices in step.
    pub(super) fn rewalk(
        &mut self,
        side: Which,
        e: u32,
        fresh: &mut Vec<u32>,
        report: &mut UpdateReport,
    ) -> Result<(), SumError> {
        fresh.clear();
        let (vp, vq) = (self.ops.view_p(), self.ops.view_q());
        let (walked, through, assign, lists) = match side {
            Which::P => (&vp, &vq, &self.p.assign, &self.p.ee),
            Which::Q => (&vq, &vp, &self.q.assign, &self.q.ee),
        };
        let [f0, f1] = walked.poly.edge(e as usize).faces;
        let (from, to) = (assign[f0 as usize], assign[f1 as usize]);
        through.walk_arc_hinted(walked, e, from, to, &lists[e as usize], |x| fresh.push(x))?;
        let (own, other) = match side {
            Which::P => (&mut self.p.ee, &mut self.q.ee),
            Which::Q => (&mut self.q.ee, &mut self.p.ee),
        };
        let old = std::mem::take(&mut own[e as usize]);
        let facet = |x: u32| match side {
            Which::P => Facet::Ee {
                p_edge: e,
                q_edge: x,
            },
            Which::Q => Facet::Ee {
                p_edge: x,
                q_edge: e,
            },
        };
        for &x in &old {
            if !fresh.contains(&x) {
                let list = &mut other[x as usize];
                if let Some(i) = list.iter().position(|&y| y == e) {
                    list.swap_remove(i);
                }
                report.removed.push(facet(x));
                report.ee_errors += 1;
            }
        }
        for &x in fresh.iter() {
            if !old.contains(&x) {
                other[x as usize].push(e);
                report.added.push(facet(x));
            }
        }
        // The arc keeps its own buffer (it grows only past its largest
        // list so far) and `fresh` keeps the re-walks' one: no allocation
        // once both have grown.
        let mut list = old;
        list.clear();
        list.extend_from_slice(fresh);
        own[e as usize] = list;
        Ok(())
    }

    /// The arcs at the normals at risk (the edges of their faces), each once
    /// per step, P's then Q's.
    pub(super) fn arcs_at_risk(
        &mut self,
        [scan_p, scan_q]: &[SideScan; 2],
        [arcs_p, arcs_q]: &mut [Vec<u32>; 2],
    ) {
        let step = self.step;
        let collect = |side: &mut Side, poly: &Polytope, uncertain: &[u32], arcs: &mut Vec<u32>| {
            arcs.clear();
            for &f in uncertain {
                for &e in poly.face_edges(f as usize) {
                    if side.stamp[e as usize] != step {
                        side.stamp[e as usize] = step;
                        arcs.push(e);
                    }
                }
            }
        };
        collect(&mut self.p, &self.ops.p, &scan_p.uncertain, arcs_p);
        collect(&mut self.q, &self.ops.q, &scan_q.uncertain, arcs_q);
    }

    /// Algorithm 4.1, line 3 for the ee-pairs (§4.3): toggles the pairs of
    /// the certified single crossings, then re-walks every arc at risk.
    pub(super) fn correct_ee_errors(
        &mut self,
        scratch: &Scratch,
        report: &mut UpdateReport,
    ) -> Result<(), SumError> {
        let ([scan_p, scan_q], [arcs_p, arcs_q]) = (&scratch.scans, &scratch.at_risk);
        report.rewalked_arcs = arcs_p.len() + arcs_q.len();
        self.apply_certified_crossings(&scan_p.certified, &scan_q.certified, report);
        let mut fresh = std::mem::take(&mut self.fresh);
        let mut result = Ok(());
        for (side, arcs) in [(Which::P, arcs_p), (Which::Q, arcs_q)] {
            for &e in arcs {
                result = self.rewalk(side, e, &mut fresh, report);
                if result.is_err() {
                    break;
                }
            }
            if result.is_err() {
                break;
            }
        }
        self.fresh = fresh;
        result
    }
}
