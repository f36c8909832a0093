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
    ///
    /// A pair `(e, x)` can be flipped by four crossings at most: P's two
    /// faces at `e` crossing `x`, and Q's two faces at `x` crossing `e`
    /// (a face crosses at most one arc in a step, its certified one). Each
    /// face's crossing is marked, so a pair's flips are counted where it is
    /// met, in O(1), and it is handled once, from the first of the four
    /// that crossed (no sort of all the toggles).
    pub(super) fn apply_certified_crossings(
        &mut self,
        certified_p: &[(u32, u32)],
        certified_q: &[(u32, u32)],
        report: &mut UpdateReport,
    ) {
        let step = self.step;
        for &(f, x) in certified_p {
            self.p.crossed[f as usize] = (step, x);
        }
        for &(g, y) in certified_q {
            self.q.crossed[g as usize] = (step, y);
        }
        for &(f, x) in certified_p {
            for k in 0..self.ops.p.face_edges(f as usize).len() {
                let e = self.ops.p.face_edges(f as usize)[k];
                let first = usize::from(self.ops.p.edge(e as usize).faces[0] != f);
                self.flip_by_parity(e, x, first, report);
            }
        }
        for &(g, y) in certified_q {
            for k in 0..self.ops.q.face_edges(g as usize).len() {
                let x = self.ops.q.face_edges(g as usize)[k];
                let first = 2 + usize::from(self.ops.q.edge(x as usize).faces[0] != g);
                self.flip_by_parity(y, x, first, report);
            }
        }
    }

    /// The pair `(e, x)` met from crossing `from` of its four (module
    /// docs of [`Self::apply_certified_crossings`]): toggled, and reported,
    /// when `from` is the first of them that happened this step and an odd
    /// number happened, unless an arc of the pair is re-walked.
    fn flip_by_parity(&mut self, e: u32, x: u32, from: usize, report: &mut UpdateReport) {
        let step = self.step;
        let [f0, f1] = self.ops.p.edge(e as usize).faces;
        let [g0, g1] = self.ops.q.edge(x as usize).faces;
        let happened = [
            self.p.crossed[f0 as usize] == (step, x),
            self.p.crossed[f1 as usize] == (step, x),
            self.q.crossed[g0 as usize] == (step, e),
            self.q.crossed[g1 as usize] == (step, e),
        ];
        if happened[..from].contains(&true)
            || happened.iter().filter(|&&h| h).count() % 2 == 0
            || self.p.stamp[e as usize] == step
            || self.q.stamp[x as usize] == step
        {
            return;
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
