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
//! 1. Rotate P's reference normals by the new relative rotation
//!    `R = R_q⁻¹ R_p` (always from the reference data: no drift).
//! 2. FindErrors (§4.1): check every fv-pair of both maps. A float margin
//!    (the sine of the distance from the normal to the nearest great circle of
//!    its cell's arcs) decides clear cases; the rest use the exact predicate.
//! 3. Correct fv-errors (§4.2) by hill climbing from the old vertex.
//! 4. Correct ee-errors (§4.3): re-walk the Gaussian arcs incident to the
//!    *at-risk* normals (below) through the other map, between the corrected
//!    fv-pairs, and diff the crossings against the stored ones.
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
//! that arc and the arcs incident to `x`. Relative to the other map, `x`
//! moves along a small-circle arc whose points lie within chordal distance
//! `δ = θ²/4` of the great arc joining its end positions. If `x` is in the
//! same convex cell `C` at both ends, the great arc between the two positions
//! lies in `C`, and for each boundary great circle with unit normal `m` the
//! function `m · x` along that great arc is a positive sinusoid lobe, hence at
//! least the smaller end value. So if the smaller of the start and end margins
//! (`min m · x` over the arcs of `C`) exceeds `δ`, `x` never leaves `C` and
//! has no event. Every other normal is *at risk*, and all arcs incident to
//! at-risk normals are re-walked from scratch; any pair whose status flipped
//! had an event at one of its four endpoints, so it is re-walked. Margins are
//! computed in floats from accurate arc normals, and every comparison
//! subtracts the face's bound on its float normal's direction error plus a
//! slack of `1e-10`; exact ties have margin 0 and are always at risk.
//! Steps above [`DynamicConfig::max_step_angle`], or steps where more than
//! [`DynamicConfig::fallback_fraction`] of all arcs would be re-walked, are
//! recomputed from scratch by `walk` instead (cheaper, and trivially correct).
//!
//! # Complexity
//! O(m + n) for FindErrors (one dot product per cell arc checked), plus the
//! cost of the walks along at-risk arcs, which for small steps is
//! proportional to the number of changes.
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
//!     let report = dynamic.rotate_p_by(step).unwrap();
//!     assert!(report.fv_errors <= tet.face_count() + cube.face_count());
//! }
//! let fresh = minkowski_sum_posed(&tet, dynamic.pose_p(), &cube, dynamic.pose_q(), Method::Walk).unwrap();
//! assert_eq!(dynamic.facets(), fresh.facets());
//! ```

use crate::polytope::Polytope;
use crate::sum::{
    relative_rotation, walk_overlay, Facet, MinkowskiSum, Operands, Overlay, SumError,
};
use crate::{Pose, Rotation};
use glam::{DMat3, DVec3};

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

/// What one update changed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct UpdateReport {
    /// Faces of P or Q whose compatible vertex changed (fv- and vf-errors).
    pub fv_errors: usize,
    /// ee-pairs that stopped being compatible.
    pub ee_errors: usize,
    /// Facets of the previous sum that are gone.
    pub removed: Vec<Facet>,
    /// Facets of the new sum that were not in the previous one.
    pub added: Vec<Facet>,
    /// Gaussian arcs re-walked to repair ee-pairs.
    pub rewalked_arcs: usize,
    /// The relative rotation angle of the step (radians).
    pub step_angle: f64,
    /// The step was recomputed from scratch (large step or too many arcs at
    /// risk).
    pub recomputed: bool,
}

/// The dynamic Minkowski sum (see the module docs).
#[derive(Clone, Debug)]
pub struct DynamicSum<'a> {
    ops: Operands<'a>,
    fv: Vec<u32>,
    vf: Vec<u32>,
    ee_p: Vec<Vec<u32>>,
    ee_q: Vec<Vec<u32>>,
    arc_p: Vec<DVec3>,
    arc_q: Vec<DVec3>,
    dir_err_p: Vec<f64>,
    dir_err_q: Vec<f64>,
    margin_p: Vec<f64>,
    margin_q: Vec<f64>,
    stamp_p: Vec<u32>,
    stamp_q: Vec<u32>,
    step: u32,
    config: DynamicConfig,
}

/// Unit normals of the great circles of every ring arc, in the reference
/// frame, laid out like the rings and oriented so that the cell is on the
/// positive side. Taken from the polytope's accurate arc normals (not from
/// a float cross product of unit normals, which is meaningless for the
/// very short arcs between nearly coplanar faces).
fn arc_normals(poly: &Polytope) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(poly.ring_len_total());
    for v in 0..poly.vertex_count() {
        for r in poly.ring(v) {
            let m = poly.arc_normals()[r.edge as usize].normalize_or_zero();
            let forward = poly.edge(r.edge as usize).faces[0] == r.face;
            out.push(if forward { m } else { -m });
        }
    }
    out
}

/// Per face, a bound on the angle between the float unit normal (also
/// after a rotation) and the exact normal's direction.
fn direction_errors(poly: &Polytope) -> Vec<f64> {
    (0..poly.face_count())
        .map(|f| 1.01 * poly.normal_error(f) / poly.normal(f).length() + 1e-14)
        .collect()
}

/// `min m · x` over the arcs of the cell of `v` (a lower bound of the sine of
/// the distance from `x` to the cell's boundary; negative when outside).
#[inline]
fn margin(poly: &Polytope, arcs: &[DVec3], v: u32, x: DVec3) -> f64 {
    let off = poly.ring_offset(v as usize);
    arcs[off..off + poly.degree(v as usize)]
        .iter()
        .map(|m| m.dot(x))
        .fold(f64::INFINITY, f64::min)
}

/// Below this float margin (plus the face's direction error) the exact
/// predicate decides.
const EXACT_BELOW: f64 = 1e-12;
/// Slack added to the drift bound to cover float error in margins.
const SLACK: f64 = 1e-10;

impl<'a> DynamicSum<'a> {
    /// Starts from a static `walk` sum at the given poses.
    pub fn new(
        p: &'a Polytope,
        pose_p: Pose,
        q: &'a Polytope,
        pose_q: Pose,
    ) -> Result<Self, SumError> {
        Self::with_config(p, pose_p, q, pose_q, DynamicConfig::default())
    }

    /// [`DynamicSum::new`] with explicit tuning.
    pub fn with_config(
        p: &'a Polytope,
        pose_p: Pose,
        q: &'a Polytope,
        pose_q: Pose,
        config: DynamicConfig,
    ) -> Result<Self, SumError> {
        let ops = Operands::new(p, pose_p, q, pose_q);
        let overlay = walk_overlay(&ops)?;
        let mut s = DynamicSum {
            fv: Vec::new(),
            vf: Vec::new(),
            ee_p: vec![Vec::new(); p.edge_count()],
            ee_q: vec![Vec::new(); q.edge_count()],
            arc_p: arc_normals(p),
            arc_q: arc_normals(q),
            dir_err_p: direction_errors(p),
            dir_err_q: direction_errors(q),
            margin_p: vec![0.0; p.face_count()],
            margin_q: vec![0.0; q.face_count()],
            stamp_p: vec![0; p.edge_count()],
            stamp_q: vec![0; q.edge_count()],
            step: 0,
            ops,
            config,
        };
        s.load_overlay(overlay);
        Ok(s)
    }

    fn load_overlay(&mut self, overlay: Overlay) {
        self.ee_p.iter_mut().for_each(Vec::clear);
        self.ee_q.iter_mut().for_each(Vec::clear);
        for &(e, e2) in &overlay.ee {
            self.ee_p[e as usize].push(e2);
            self.ee_q[e2 as usize].push(e);
        }
        self.fv = overlay.fv;
        self.vf = overlay.vf;
        let rot = self.ops.relative.matrix();
        let inv = rot.transpose();
        for f in 0..self.fv.len() {
            self.margin_p[f] = self.margin_of_p_face(rot, f);
        }
        for g in 0..self.vf.len() {
            self.margin_q[g] = self.margin_of_q_face(inv, g);
        }
    }

    #[inline]
    fn margin_of_p_face(&self, rot: DMat3, f: usize) -> f64 {
        let x = rot * self.ops.p.unit_normal(f);
        margin(self.ops.q, &self.arc_q, self.fv[f], x)
    }

    #[inline]
    fn margin_of_q_face(&self, inv: DMat3, g: usize) -> f64 {
        let x = inv * self.ops.q.unit_normal(g);
        margin(self.ops.p, &self.arc_p, self.vf[g], x)
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
    pub fn p(&self) -> &'a Polytope {
        self.ops.p
    }
    /// Q.
    pub fn q(&self) -> &'a Polytope {
        self.ops.q
    }
    /// The tuning in force.
    pub fn config(&self) -> DynamicConfig {
        self.config
    }

    /// Turns P further by `r` (applied after its current rotation, about the
    /// origin of the world frame; P's translation is kept).
    pub fn rotate_p_by(&mut self, r: Rotation) -> Result<UpdateReport, SumError> {
        let mut pose = self.ops.pose_p;
        pose.rotation = pose.rotation.then(&r);
        self.set_pose(pose, self.ops.pose_q)
    }

    /// Moves P to `pose_p`, keeping Q where it is.
    pub fn set_pose_p(&mut self, pose_p: Pose) -> Result<UpdateReport, SumError> {
        self.set_pose(pose_p, self.ops.pose_q)
    }

    /// Moves both bodies and repairs the overlay (see the module docs).
    pub fn set_pose(&mut self, pose_p: Pose, pose_q: Pose) -> Result<UpdateReport, SumError> {
        let old = self.ops.relative;
        let new = relative_rotation(&pose_p, &pose_q);
        self.ops.pose_p = pose_p;
        self.ops.pose_q = pose_q;
        let theta = old.angle_to(&new);
        let mut report = UpdateReport {
            step_angle: theta,
            ..UpdateReport::default()
        };
        if new == old {
            return Ok(report);
        }
        self.ops.relative = new;
        self.ops.rot_p = (new != Rotation::IDENTITY).then(|| new.matrix());
        crate::sum::rotate_arcs(
            self.ops.p,
            self.ops.rot_p.as_ref(),
            &mut self.ops.arc_p,
            &mut self.ops.arc_p_err,
        );
        for (n, r) in self.ops.np.iter_mut().zip(self.ops.p.normals()) {
            *n = new.apply(*r);
        }
        if theta > self.config.max_step_angle {
            return self.recompute(report);
        }
        self.step = self.step.wrapping_add(1).max(1);
        let drift = theta * theta / 4.0 + SLACK;
        let mut at_risk_p = Vec::new();
        let mut at_risk_q = Vec::new();
        let rot = new.matrix();
        let inv = rot.transpose();
        // FindErrors and fv-corrections on P's faces.
        for f in 0..self.fv.len() {
            let mut m1 = self.margin_of_p_face(rot, f);
            let mut changed = false;
            let delta = self.dir_err_p[f];
            if m1 <= EXACT_BELOW + delta {
                let vq = self.ops.view_q();
                let v = self.fv[f];
                let x = self.ops.view_p().normal(f as u32);
                if !vq.in_cell(v, &x) {
                    let (v2, _) = vq.locate(&x, v);
                    report.removed.push(Facet::Fv {
                        p_face: f as u32,
                        q_vertex: v,
                    });
                    report.added.push(Facet::Fv {
                        p_face: f as u32,
                        q_vertex: v2,
                    });
                    self.fv[f] = v2;
                    m1 = self.margin_of_p_face(rot, f);
                    changed = true;
                }
            }
            if changed || self.margin_p[f].min(m1) <= drift + delta {
                at_risk_p.push(f);
            }
            self.margin_p[f] = m1;
        }
        // ... and on Q's faces.
        for g in 0..self.vf.len() {
            let mut m1 = self.margin_of_q_face(inv, g);
            let mut changed = false;
            let delta = self.dir_err_q[g];
            if m1 <= EXACT_BELOW + delta {
                let vp = self.ops.view_p();
                let u = self.vf[g];
                let x = self.ops.view_q().normal(g as u32);
                if !vp.in_cell(u, &x) {
                    let (u2, _) = vp.locate(&x, u);
                    report.removed.push(Facet::Vf {
                        p_vertex: u,
                        q_face: g as u32,
                    });
                    report.added.push(Facet::Vf {
                        p_vertex: u2,
                        q_face: g as u32,
                    });
                    self.vf[g] = u2;
                    m1 = self.margin_of_q_face(inv, g);
                    changed = true;
                }
            }
            if changed || self.margin_q[g].min(m1) <= drift + delta {
                at_risk_q.push(g);
            }
            self.margin_q[g] = m1;
        }
        report.fv_errors = report.removed.len();
        // The arcs incident to at-risk normals are the edges of their faces.
        let mut arcs_p = Vec::new();
        for &f in &at_risk_p {
            for &e in self.ops.p.face_edges(f) {
                if self.stamp_p[e as usize] != self.step {
                    self.stamp_p[e as usize] = self.step;
                    arcs_p.push(e);
                }
            }
        }
        let mut arcs_q = Vec::new();
        for &g in &at_risk_q {
            for &e in self.ops.q.face_edges(g) {
                if self.stamp_q[e as usize] != self.step {
                    self.stamp_q[e as usize] = self.step;
                    arcs_q.push(e);
                }
            }
        }
        let total_arcs = self.ee_p.len() + self.ee_q.len();
        if (arcs_p.len() + arcs_q.len()) as f64 > self.config.fallback_fraction * total_arcs as f64
        {
            return self.recompute(report);
        }
        report.rewalked_arcs = arcs_p.len() + arcs_q.len();
        let mut fresh = Vec::new();
        for &e in &arcs_p {
            self.rewalk_p_edge(e, &mut fresh, &mut report)?;
        }
        for &e in &arcs_q {
            self.rewalk_q_edge(e, &mut fresh, &mut report)?;
        }
        Ok(report)
    }

    fn rewalk_p_edge(
        &mut self,
        e: u32,
        fresh: &mut Vec<u32>,
        report: &mut UpdateReport,
    ) -> Result<(), SumError> {
        fresh.clear();
        let [f0, f1] = self.ops.p.edge(e as usize).faces;
        let (fv0, fv1) = (self.fv[f0 as usize], self.fv[f1 as usize]);
        self.ops.view_q().walk_arc_hinted(
            &self.ops.view_p(),
            e,
            fv0,
            fv1,
            &self.ee_p[e as usize],
            |e2| fresh.push(e2),
        )?;
        let old = std::mem::take(&mut self.ee_p[e as usize]);
        for &e2 in &old {
            if !fresh.contains(&e2) {
                let list = &mut self.ee_q[e2 as usize];
                if let Some(i) = list.iter().position(|&x| x == e) {
                    list.swap_remove(i);
                }
                report.removed.push(Facet::Ee {
                    p_edge: e,
                    q_edge: e2,
                });
                report.ee_errors += 1;
            }
        }
        for &e2 in fresh.iter() {
            if !old.contains(&e2) {
                self.ee_q[e2 as usize].push(e);
                report.added.push(Facet::Ee {
                    p_edge: e,
                    q_edge: e2,
                });
            }
        }
        self.ee_p[e as usize] = fresh.clone();
        Ok(())
    }

    fn rewalk_q_edge(
        &mut self,
        e2: u32,
        fresh: &mut Vec<u32>,
        report: &mut UpdateReport,
    ) -> Result<(), SumError> {
        fresh.clear();
        let [g0, g1] = self.ops.q.edge(e2 as usize).faces;
        let (vf0, vf1) = (self.vf[g0 as usize], self.vf[g1 as usize]);
        self.ops.view_p().walk_arc_hinted(
            &self.ops.view_q(),
            e2,
            vf0,
            vf1,
            &self.ee_q[e2 as usize],
            |e| fresh.push(e),
        )?;
        let old = std::mem::take(&mut self.ee_q[e2 as usize]);
        for &e in &old {
            if !fresh.contains(&e) {
                let list = &mut self.ee_p[e as usize];
                if let Some(i) = list.iter().position(|&x| x == e2) {
                    list.swap_remove(i);
                }
                report.removed.push(Facet::Ee {
                    p_edge: e,
                    q_edge: e2,
                });
                report.ee_errors += 1;
            }
        }
        for &e in fresh.iter() {
            if !old.contains(&e) {
                self.ee_p[e as usize].push(e2);
                report.added.push(Facet::Ee {
                    p_edge: e,
                    q_edge: e2,
                });
            }
        }
        self.ee_q[e2 as usize] = fresh.clone();
        Ok(())
    }

    /// Recomputes from scratch with `walk` (large steps), reporting the diff.
    fn recompute(&mut self, mut report: UpdateReport) -> Result<UpdateReport, SumError> {
        // Diff whole overlays: the state before this step is the current one
        // with the fv-corrections already made in this step undone.
        let mut before = self.overlay();
        for f in &report.removed {
            match *f {
                Facet::Fv { p_face, q_vertex } => before.fv[p_face as usize] = q_vertex,
                Facet::Vf { p_vertex, q_face } => before.vf[q_face as usize] = p_vertex,
                Facet::Ee { .. } => {}
            }
        }
        let fresh = walk_overlay(&self.ops)?;
        let (old_f, new_f) = (before.facets(), fresh.facets());
        report.removed = sorted_difference(&old_f, &new_f);
        report.added = sorted_difference(&new_f, &old_f);
        report.fv_errors = report
            .removed
            .iter()
            .filter(|f| !matches!(f, Facet::Ee { .. }))
            .count();
        report.ee_errors = report.removed.len() - report.fv_errors;
        report.rewalked_arcs = self.ee_p.len();
        report.recomputed = true;
        self.load_overlay(fresh);
        Ok(report)
    }

    /// The current overlay, with ee-pairs sorted.
    pub fn overlay(&self) -> Overlay {
        let mut ee: Vec<(u32, u32)> = self
            .ee_p
            .iter()
            .enumerate()
            .flat_map(|(e, l)| l.iter().map(move |&e2| (e as u32, e2)))
            .collect();
        ee.sort_unstable();
        Overlay {
            fv: self.fv.clone(),
            vf: self.vf.clone(),
            ee,
        }
    }

    /// The current facets in canonical order (as [`MinkowskiSum::facets`]).
    pub fn facets(&self) -> Vec<Facet> {
        self.overlay().facets()
    }

    /// Number of facets.
    pub fn facet_count(&self) -> usize {
        self.fv.len() + self.vf.len() + self.ee_p.iter().map(Vec::len).sum::<usize>()
    }

    /// The current sum as a static [`MinkowskiSum`] (no recomputation).
    pub fn sum(&self) -> MinkowskiSum<'a> {
        MinkowskiSum::from_overlay(self.ops.clone(), self.overlay())
    }

    /// The merged mesh of the current sum.
    pub fn to_mesh(&self) -> crate::PolygonMesh {
        self.sum().to_mesh()
    }

    /// Checks the internal state: the two ee indices agree, and the current
    /// sum passes [`MinkowskiSum::sanity_check`].
    pub fn sanity_check(&self) -> Result<(), String> {
        let mut a: Vec<(u32, u32)> = self.overlay().ee;
        let mut b: Vec<(u32, u32)> = self
            .ee_q
            .iter()
            .enumerate()
            .flat_map(|(e2, l)| l.iter().map(move |&e| (e, e2 as u32)))
            .collect();
        a.sort_unstable();
        b.sort_unstable();
        if a != b {
            return Err("the ee indices by P edge and by Q edge disagree".into());
        }
        self.sum().sanity_check()
    }
}

fn sorted_difference(a: &[Facet], b: &[Facet]) -> Vec<Facet> {
    let set: std::collections::HashSet<&Facet> = b.iter().collect();
    a.iter().filter(|f| !set.contains(f)).copied().collect()
}
