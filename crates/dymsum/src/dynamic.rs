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
//! 1. Rotate P's reference normals and arc normals by the new relative
//!    rotation `R = R_q⁻¹ R_p` (always from the reference data: no drift).
//! 2. FindErrors (§4.1): check the fv-pairs of both maps. A float margin
//!    (the sine of the distance from the normal to the nearest great circle
//!    of its cell's arcs, computed from accurate arc normals) decides clear
//!    cases; the rest use the exact predicate. A normal whose last margin,
//!    less the rotation accumulated since, still exceeds this step's reach
//!    is not checked at all (lazy margins).
//! 3. Correct fv-errors (§4.2) by hill climbing from the old vertex.
//! 4. Correct ee-errors (§4.3): a normal that certainly crossed exactly one
//!    arc `x` of the other map flips exactly the pairs (arc at that normal,
//!    `x`): those are toggled. The arcs at every other *at-risk* normal are
//!    re-walked through the other map between the corrected fv-pairs, and
//!    their crossings diffed against the stored ones.
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
//! that arc and the arcs incident to `x`; a pair's final status is its
//! initial one flipped once per event involving it. Relative to the other
//! map, `x` moves along a small-circle arc of length at most `θ`.
//!
//! * *No event.* For an interior point of a convex cell, the distance to the
//!   boundary is the smallest distance to the great circles of its arcs, so
//!   if the margin (a sine, hence at most the chordal distance) exceeds `θ`
//!   the normal cannot reach the boundary. Margins decay by at most the
//!   rotation since they were computed, which makes the lazy skip sound.
//!   For a normal that ends in its old cell the bound is sharper: its path
//!   lies within chordal distance `δ = θ²/4` of the great arc joining its end
//!   positions, which lies in the convex cell, and along that great arc each
//!   `m · x` is a positive sinusoid lobe, at least its smaller end value; so
//!   if both end margins exceed `δ`, the path never leaves the cell.
//! * *Exactly one event.* If the old and new cells `v`, `w` are adjacent
//!   across arc `x`, the old position is farther than `θ` from every other
//!   great circle of `v` and the new one from every other great circle of
//!   `w`, then the path lies in `v ∪ w` (the intersection of those
//!   half-spaces), whose common boundary is `x`, and meets `x`'s great circle
//!   an odd number of times but at most twice (a small circle meets a great
//!   circle in at most two points): exactly once. Its flips are known.
//! * *Anything else* is at risk: all arcs at that normal are re-walked from
//!   scratch, which recomputes every pair an event at that normal can flip.
//!
//! * *Persistent ties.* Exact ties have margin 0. When both relative
//!   rotations of a step turn exactly about a coordinate axis `e_k` (row and
//!   column `k` of both matrices are `e_k`, as for boxes turning about `z`),
//!   the step is taken along rotations about `e_k`, on which the
//!   `k`-components of P's rotated normals are constant. A determinant
//!   `det[a, b, x]` that is then zero at every rotation (read off the exact
//!   zero pattern of the normals and of the arcs' cross products, computed
//!   once) keeps its SoS sign if the first SoS term that is not itself zero
//!   at every rotation stays away from zero: for P's normal (lowest index)
//!   that term is a component of Q's fixed `a × b`, constant; for Q's normal
//!   it is a minor or entry of the rotating rows, certified by its size
//!   against its rate of change. A normal all of whose arcs are so certified
//!   (the others by their margins) stays in its cell and has no event; its
//!   certified margin is reused lazily while the steps stay about `e_k`.
//!
//! A pair not on a re-walked arc therefore had events only at normals with a
//! known event set, and toggling by parity gives its final status. Margins
//! are computed in floats from accurate arc normals, and every comparison
//! adds the face's bound on its float normal's direction error plus a slack
//! of `1e-10`; exact ties have margin 0 and are at risk unless certified as
//! persistent (above). Steps above
//! [`DynamicConfig::max_step_angle`], or steps where more than
//! [`DynamicConfig::fallback_fraction`] of all arcs would be re-walked, are
//! recomputed from scratch by `walk` instead (cheaper, and trivially correct);
//! after such a fallback a few steps at least 90% as large go straight to the
//! recomputation (an exponential backoff; not after steps about a coordinate
//! axis, where many arcs at risk means an isolated exact coincidence such as
//! a quarter turn), and the update's report is the diff of the two overlays.
//!
//! # Complexity
//! O(m + n) to scan the normals near their cells' boundaries (the others are
//! skipped by their margins), O(deg) per certified crossing, plus the walks
//! along the arcs at uncertain normals; for small steps the work is
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

use crate::kernel::exact::{self, ExactVec};
use crate::kernel::predicates::{others, sos_terms, ExactVector, SosTerm};
use crate::kernel::Sign;
use crate::polytope::Polytope;
use crate::sum::{
    relative_rotation, walk_overlay, Facet, GaussView, MinkowskiSum, Operands, Overlay, SumError,
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
    /// Face normals whose cell was checked (the others were certified to
    /// stay in their cells by their margins).
    pub checked_normals: usize,
    /// Face normals that changed cell across exactly one arc, repaired by
    /// toggling instead of re-walking.
    pub certified_crossings: usize,
    /// The relative rotation angle of the step (radians).
    pub step_angle: f64,
    /// The step was recomputed from scratch (large step or too many arcs at
    /// risk).
    pub recomputed: bool,
}

/// The dynamic Minkowski sum (see the module docs).
#[derive(Clone, Debug)]
pub struct DynamicSum {
    ops: Operands,
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
    margin_at_p: Vec<f64>,
    margin_at_q: Vec<f64>,
    theta_acc: f64,
    stamp_p: Vec<u32>,
    stamp_q: Vec<u32>,
    scratch_toggled: Vec<(u32, u32)>,
    /// Exact zero structure of P's and Q's maps, computed at the first step
    /// about a coordinate axis (see [`stays_in_cell_tied`]).
    zeros: Option<Box<[ExactZeros; 2]>>,
    /// Per face: the rotation about the coordinate axis `tie_axis` it can
    /// still absorb with its persistent ties certified (see
    /// [`stays_in_cell_tied`]); `NO_AXIS` when not certified that way.
    tie_margin_p: Vec<f64>,
    tie_margin_q: Vec<f64>,
    tie_axis_p: Vec<u8>,
    tie_axis_q: Vec<u8>,
    /// The incremental step at which each face's tie margin was computed.
    tie_tick_p: Vec<u64>,
    tie_tick_q: Vec<u64>,
    /// Incremental steps so far.
    tick: u64,
    /// The coordinate axis of the current run of incremental steps about
    /// one axis, and the step that began the run.
    axis_run: Option<usize>,
    axis_since: u64,
    /// After fallbacks, how many steps of similar size skip the scan.
    backoff: Backoff,
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
/// No coordinate axis.
const NO_AXIS: u8 = u8::MAX;
/// Unit roundoff.
const U: f64 = f64::EPSILON / 2.0;

impl DynamicSum {
    /// Starts from a static `walk` sum at the given poses.
    pub fn new(p: &Polytope, pose_p: Pose, q: &Polytope, pose_q: Pose) -> Result<Self, SumError> {
        Self::with_config(p, pose_p, q, pose_q, DynamicConfig::default())
    }

    /// [`DynamicSum::new`] with explicit tuning.
    pub fn with_config(
        p: &Polytope,
        pose_p: Pose,
        q: &Polytope,
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
            margin_at_p: vec![0.0; p.face_count()],
            margin_at_q: vec![0.0; q.face_count()],
            theta_acc: 0.0,
            stamp_p: vec![0; p.edge_count()],
            stamp_q: vec![0; q.edge_count()],
            scratch_toggled: Vec::new(),
            zeros: None,
            tie_margin_p: vec![0.0; p.face_count()],
            tie_margin_q: vec![0.0; q.face_count()],
            tie_axis_p: vec![NO_AXIS; p.face_count()],
            tie_axis_q: vec![NO_AXIS; q.face_count()],
            tie_tick_p: vec![0; p.face_count()],
            tie_tick_q: vec![0; q.face_count()],
            tick: 0,
            axis_run: None,
            axis_since: 0,
            backoff: Backoff::default(),
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
        self.tie_axis_p.fill(NO_AXIS);
        self.tie_axis_q.fill(NO_AXIS);
        let rot = self.ops.relative.matrix();
        let inv = rot.transpose();
        for f in 0..self.fv.len() {
            self.margin_p[f] = self.margin_of_p_face(rot, f);
            self.margin_at_p[f] = self.theta_acc;
        }
        for g in 0..self.vf.len() {
            self.margin_q[g] = self.margin_of_q_face(inv, g);
            self.margin_at_q[g] = self.theta_acc;
        }
    }

    #[inline]
    fn margin_of_p_face(&self, rot: DMat3, f: usize) -> f64 {
        let x = rot * self.ops.p.unit_normal(f);
        margin(&self.ops.q, &self.arc_q, self.fv[f], x)
    }

    #[inline]
    fn margin_of_q_face(&self, inv: DMat3, g: usize) -> f64 {
        let x = inv * self.ops.q.unit_normal(g);
        margin(&self.ops.p, &self.arc_p, self.vf[g], x)
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
    pub fn p(&self) -> &Polytope {
        &self.ops.p
    }
    /// Q.
    pub fn q(&self) -> &Polytope {
        &self.ops.q
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
        self.ops.set_relative(new);
        // Too large a step, or within the backoff after a step as large fell
        // back because too many arcs were at risk: recompute without scanning.
        if theta > self.config.max_step_angle {
            return self.recompute(report);
        }
        if self.backoff.skip > 0 && theta >= 0.9 * self.backoff.theta {
            self.backoff.skip -= 1;
            return self.recompute(report);
        }
        self.step = self.step.wrapping_add(1).max(1);
        let drift = theta * theta / 4.0 + SLACK;
        let (rot, rot_old) = (new.matrix(), old.matrix());
        let before = self.theta_acc;
        self.theta_acc += theta;
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
        let step = StepBounds {
            theta,
            drift,
            before,
            after: self.theta_acc,
            axis,
            tick: self.tick,
            run_start: self.axis_since,
        };
        let scan_p = scan_side(
            (&self.ops.view_p(), &self.ops.view_q()),
            &self.arc_q,
            (rot, rot_old),
            Some(&self.ops.np),
            self.zeros.as_deref().map(|[zp, zq]| Tied {
                moving: zp,
                fixed: zq,
                moving_is_p: true,
            }),
            SideState {
                assign: &mut self.fv,
                margin: &mut self.margin_p,
                margin_at: &mut self.margin_at_p,
                tie_margin: &mut self.tie_margin_p,
                tie_axis: &mut self.tie_axis_p,
                tie_tick: &mut self.tie_tick_p,
                dir_err: &self.dir_err_p,
            },
            &step,
        );
        let scan_q = scan_side(
            (&self.ops.view_q(), &self.ops.view_p()),
            &self.arc_p,
            (rot.transpose(), rot_old.transpose()),
            None,
            self.zeros.as_deref().map(|[zp, zq]| Tied {
                moving: zq,
                fixed: zp,
                moving_is_p: false,
            }),
            SideState {
                assign: &mut self.vf,
                margin: &mut self.margin_q,
                margin_at: &mut self.margin_at_q,
                tie_margin: &mut self.tie_margin_q,
                tie_axis: &mut self.tie_axis_q,
                tie_tick: &mut self.tie_tick_q,
                dir_err: &self.dir_err_q,
            },
            &step,
        );
        for c in &scan_p.changed {
            report.removed.push(Facet::Fv {
                p_face: c.face,
                q_vertex: c.old,
            });
            report.added.push(Facet::Fv {
                p_face: c.face,
                q_vertex: c.new,
            });
        }
        for c in &scan_q.changed {
            report.removed.push(Facet::Vf {
                p_vertex: c.old,
                q_face: c.face,
            });
            report.added.push(Facet::Vf {
                p_vertex: c.new,
                q_face: c.face,
            });
        }
        report.fv_errors = report.removed.len();
        report.checked_normals = scan_p.checked + scan_q.checked;
        report.certified_crossings = scan_p.certified.len() + scan_q.certified.len();
        // Arcs incident to uncertain normals (the edges of their faces) are
        // re-walked; certified single crossings are toggled.
        let mut arcs_p = Vec::new();
        for &f in &scan_p.uncertain {
            for &e in self.ops.p.face_edges(f as usize) {
                if self.stamp_p[e as usize] != self.step {
                    self.stamp_p[e as usize] = self.step;
                    arcs_p.push(e);
                }
            }
        }
        let mut arcs_q = Vec::new();
        for &g in &scan_q.uncertain {
            for &e in self.ops.q.face_edges(g as usize) {
                if self.stamp_q[e as usize] != self.step {
                    self.stamp_q[e as usize] = self.step;
                    arcs_q.push(e);
                }
            }
        }
        let total_arcs = self.ee_p.len() + self.ee_q.len();
        if (arcs_p.len() + arcs_q.len()) as f64 > self.config.fallback_fraction * total_arcs as f64
        {
            // About a coordinate axis, many arcs at risk means an isolated
            // exact coincidence (faces becoming parallel at a quarter turn):
            // the next steps are certified by their persistent ties again, so
            // no backoff.
            if axis.is_none() {
                self.backoff.fell_back(theta);
            }
            return self.recompute(report);
        }
        self.backoff = Backoff::default();
        report.rewalked_arcs = arcs_p.len() + arcs_q.len();
        self.apply_certified_crossings(&scan_p.certified, &scan_q.certified, &mut report);
        let mut fresh = Vec::new();
        for &e in &arcs_p {
            self.rewalk(Side::P, e, &mut fresh, &mut report)?;
        }
        for &e in &arcs_q {
            self.rewalk(Side::Q, e, &mut fresh, &mut report)?;
        }
        Ok(report)
    }

    /// Toggles the ee-pairs flipped by certified single crossings: a face
    /// normal of P that crossed exactly the arc `x` of Q flips the pairs
    /// (edge of that face, `x`), and symmetrically for Q. Toggles combine by
    /// parity; pairs on a re-walked arc are left to the re-walk.
    fn apply_certified_crossings(
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
        pending.sort_unstable();
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
                || self.stamp_p[e as usize] == self.step
                || self.stamp_q[x as usize] == self.step
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
    fn toggle_pair(&mut self, e: u32, x: u32) -> bool {
        let list = &mut self.ee_p[e as usize];
        if let Some(k) = list.iter().position(|&y| y == x) {
            list.swap_remove(k);
            let back = &mut self.ee_q[x as usize];
            if let Some(k) = back.iter().position(|&y| y == e) {
                back.swap_remove(k);
            }
            true
        } else {
            list.push(x);
            self.ee_q[x as usize].push(e);
            false
        }
    }

    /// Re-walks the arc of edge `e` of P through Q's map (`side = P`) or of
    /// edge `e` of Q through P's map (`side = Q`), and diffs its crossings
    /// against the stored ones, keeping both indices in step.
    fn rewalk(
        &mut self,
        side: Side,
        e: u32,
        fresh: &mut Vec<u32>,
        report: &mut UpdateReport,
    ) -> Result<(), SumError> {
        fresh.clear();
        let (vp, vq) = (self.ops.view_p(), self.ops.view_q());
        let (walked, through, assign, lists) = match side {
            Side::P => (&vp, &vq, &self.fv, &self.ee_p),
            Side::Q => (&vq, &vp, &self.vf, &self.ee_q),
        };
        let [f0, f1] = walked.poly.edge(e as usize).faces;
        let (from, to) = (assign[f0 as usize], assign[f1 as usize]);
        through.walk_arc_hinted(walked, e, from, to, &lists[e as usize], |x| fresh.push(x))?;
        let (own, other) = match side {
            Side::P => (&mut self.ee_p, &mut self.ee_q),
            Side::Q => (&mut self.ee_q, &mut self.ee_p),
        };
        let old = std::mem::take(&mut own[e as usize]);
        let facet = |x: u32| match side {
            Side::P => Facet::Ee {
                p_edge: e,
                q_edge: x,
            },
            Side::Q => Facet::Ee {
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
        own[e as usize] = fresh.clone();
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
        let (removed, added) = overlay_diff(&before, &fresh);
        report.removed = removed;
        report.added = added;
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
    pub fn sum(&self) -> MinkowskiSum {
        MinkowskiSum::from_overlay(self.ops.clone(), self.overlay())
    }

    /// The merged, validated mesh of the current sum (see
    /// [`MinkowskiSum::try_to_mesh`]).
    pub fn try_to_mesh(&self) -> Result<crate::PolygonMesh, crate::sum::MeshError> {
        self.sum().try_to_mesh()
    }
    /// [`Self::try_to_mesh`] with the coordinates' rounding relative to the
    /// sum's size (see [`MinkowskiSum::mesh_with_precision`]).
    pub fn mesh_with_precision(&self) -> Result<crate::sum::SumMesh, crate::sum::MeshError> {
        self.sum().mesh_with_precision()
    }

    /// Checks the internal state: the two ee indices agree, and the current
    /// sum passes [`MinkowskiSum::sanity_check`].
    ///
    /// # Errors
    /// The first broken invariant ([`crate::SanityError`]).
    pub fn sanity_check(&self) -> Result<(), crate::SanityError> {
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
            return Err(crate::SanityError::EeIndicesDisagree);
        }
        self.sum().sanity_check()
    }
}

/// Exponential backoff of the incremental attempt after fallbacks: a step
/// that falls back because too many arcs are at risk makes the next `skip`
/// steps at least 90% as large recompute without scanning first; each
/// further fallback doubles the count (up to 64), an incremental step resets
/// it. A one-off fallback (say, a degenerate start) costs a few steps; a
/// motion too fast for incremental updates wastes a scan on at most one step
/// in 64. Either way the result is exact: only the work differs.
#[derive(Clone, Copy, Debug, Default)]
struct Backoff {
    theta: f64,
    skip: u32,
    next: u32,
}

impl Backoff {
    fn fell_back(&mut self, theta: f64) {
        self.theta = theta;
        self.next = (self.next * 2).clamp(4, 64);
        self.skip = self.next;
    }
}

/// Which polytope's arc is re-walked.
#[derive(Clone, Copy)]
enum Side {
    P,
    Q,
}

/// The bounds of one step, shared by both sides' scans.
struct StepBounds {
    /// The step angle.
    theta: f64,
    /// `θ²/4` plus slack: how far a moving normal's path strays from the
    /// great arc between its end positions.
    drift: f64,
    /// Accumulated rotation before and after this step (for lazy margins).
    before: f64,
    after: f64,
    /// The coordinate axis `k` the step turns about exactly, if any (see
    /// [`coordinate_axis`]): then exact ties that persist along the whole
    /// step are certified by [`stays_in_cell_tied`].
    axis: Option<usize>,
    /// This step's number, and the one that began the current run of steps
    /// about `axis`: tie margins computed since then (every step in between
    /// was about the same axis) are valid for this step.
    tick: u64,
    run_start: u64,
}

/// One side's mutable state: for each moving face, its cell and margin.
struct SideState<'s> {
    assign: &'s mut [u32],
    margin: &'s mut [f64],
    margin_at: &'s mut [f64],
    tie_margin: &'s mut [f64],
    tie_axis: &'s mut [u8],
    tie_tick: &'s mut [u64],
    dir_err: &'s [f64],
}

/// A face whose cell changed.
struct Change {
    face: u32,
    old: u32,
    new: u32,
}

/// What a side's FindErrors pass found.
#[derive(Default)]
struct SideScan {
    changed: Vec<Change>,
    checked: usize,
    /// Faces whose normal may have had events that are not certified: all
    /// arcs at them are re-walked.
    uncertain: Vec<u32>,
    /// `(face, arc)`: the normal crossed exactly that arc of the other map.
    certified: Vec<(u32, u32)>,
}

/// FindErrors and fv-corrections for the face normals of `faces` in the
/// cells of `cells` (paper §4.1–4.2), with the certification of the module
/// docs. `to_cells` maps a unit normal of `faces` into the reference frame
/// of `cells` at the new and at the old orientation.
fn scan_side(
    (faces, cells): (&GaussView<'_>, &GaussView<'_>),
    cell_arcs: &[DVec3],
    to_cells: (DMat3, DMat3),
    rotated: Option<&[DVec3]>,
    tied: Option<Tied<'_>>,
    state: SideState<'_>,
    step: &StepBounds,
) -> SideScan {
    let mut out = SideScan::default();
    let cpoly = cells.poly;
    for f in 0..state.assign.len() {
        let delta = state.dir_err[f];
        // Lazy margins: a normal whose margin, less the rotation since it was
        // computed, still exceeds this step's needs cannot have had an event.
        let lower = state.margin[f] - (step.before - state.margin_at[f]);
        if lower - step.theta > step.drift + delta {
            continue;
        }
        // The same for a normal certified through its persistent ties, as
        // long as every step since was about the same coordinate axis.
        if let Some(k) = step.axis {
            if state.tie_axis[f] == k as u8 && state.tie_tick[f] >= step.run_start {
                let tie_lower = state.tie_margin[f] - (step.before - state.margin_at[f]);
                if tie_lower - step.theta > step.drift + delta {
                    continue;
                }
            }
        }
        state.tie_axis[f] = NO_AXIS;
        out.checked += 1;
        let unit = faces.poly.unit_normal(f);
        // The moving normals are already rotated into the cells' frame (P's
        // in `set_pose`); a fixed map's normals are rotated here.
        let x_new = match rotated {
            Some(n) => n[f] * faces.poly.inverse_normal_length(f),
            None => to_cells.0 * unit,
        };
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
                    continue;
                }
            }
        }
        if m1 <= EXACT_BELOW + delta {
            let x = faces.normal(f as u32);
            // A margin clearly below zero is certainly outside.
            if m1 < -(EXACT_BELOW + delta) || !cells.in_cell(v, &x) {
                let v2 = locate_certified(cpoly, cell_arcs, x_new, EXACT_BELOW + delta, v)
                    .unwrap_or_else(|| cells.locate(&x, v).0);
                state.assign[f] = v2;
                m1 = margin(cpoly, cell_arcs, v2, x_new);
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
    out
}

/// Which components of the exact reference normals and of the exact arc
/// normals (cross products of the two faces' exact normals) are zero:
/// computed once, exactly, for the certification of persistent ties.
#[derive(Clone, Debug)]
struct ExactZeros {
    /// Per face.
    normal: Vec<[bool; 3]>,
    /// Per edge.
    arc: Vec<[bool; 3]>,
}

impl ExactZeros {
    fn of(poly: &Polytope) -> ExactZeros {
        let view = GaussView {
            poly,
            normals: poly.normals(),
            arcs: poly.arc_normals(),
            arc_errs: poly.arc_errors(),
            base: 0,
            rotation: None,
            ties: None,
        };
        let zero = |v: &ExactVec| [0, 1, 2].map(|c| v[c].sign() == Sign::Zero);
        let exact: Vec<ExactVec> = (0..poly.face_count() as u32)
            .map(|f| view.normal(f).exact())
            .collect();
        ExactZeros {
            normal: exact.iter().map(zero).collect(),
            arc: (0..poly.edge_count())
                .map(|e| {
                    let [f0, f1] = poly.edge(e).faces;
                    zero(&exact::cross(&exact[f0 as usize], &exact[f1 as usize]))
                })
                .collect(),
        }
    }
}

/// The coordinate axis `k` about which both relative rotations turn
/// exactly: in both (snapped) matrices row and column `k` are the unit
/// vector `e_k`, and the other two rows and columns form a matrix
/// `[[c, −s], [s, c]]` exactly (a positive multiple of a plane rotation).
/// Then the step can be taken along rotations about `e_k`, on which the
/// `k`-components of P's rotated normals are constant and the sign of every
/// SoS term is invariant under the positive scale.
fn coordinate_axis(a: &DMat3, b: &DMat3) -> Option<usize> {
    (0..3).find(|&k| {
        [a, b].iter().all(|m| {
            let (i, j) = plane(k);
            let e = DVec3::AXES[k];
            let (c, s) = (m.col(i)[i], m.col(i)[j]);
            m.row(k) == e
                && m.col(k) == e
                && m.col(j)[j] == c
                && m.col(j)[i] == -s
                && c * c + s * s > 0.5
        })
    })
}

/// The two coordinates other than `k`.
#[inline]
fn plane(k: usize) -> (usize, usize) {
    match k {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

/// The exact zero structure of the moving and the fixed map of a scan.
struct Tied<'t> {
    moving: &'t ExactZeros,
    fixed: &'t ExactZeros,
    /// The moving normals are P's (lower SoS indices than Q's).
    moving_is_p: bool,
}

/// Whether the face normal `f` of `faces`, in cell `v` of `cells` at the
/// start of a step about coordinate axis `k` by angle `θ`, certainly stays
/// in that cell along the whole step (under the symbolic perturbation), so
/// that it has no event and its fv-pair is unchanged.
///
/// Per arc of the cell, one of:
/// * both end margins exceed `reach` (the drift argument of the module
///   docs);
/// * the determinant `det[a, b, x]` is zero at every rotation about `e_k`
///   (a *persistent tie*, read off the exact zero structure: for P's normal
///   `x = R n`, `(a × b) · R n = (a × b)_k n_k + (a × b)_⊥ · R_⊥ n_⊥`, and
///   symmetrically for an arc of P), and its SoS sign is constant along the
///   step. When the normal is P's it has the lowest index, so the first SoS
///   terms are the cofactors of its row, the components of `a × b` of Q's
///   fixed arc: constant, and not all zero. When it is Q's, the sign is
///   decided by [`sos_term_certified`].
///
/// Returns the rotation about `e_k` the normal can still absorb from the
/// new pose with all this still certain (the smallest margin of a non-tied
/// arc, or of a deciding SoS term; a sine of an angle, or an angle), or
/// `None` in any other case (a tie that may break during the step): then the
/// caller's exact path takes over.
fn stays_in_cell_tied(
    (faces, cells): (&GaussView<'_>, &GaussView<'_>),
    cell_arcs: &[DVec3],
    (f, v): (u32, u32),
    (x_old, x_new): (DVec3, DVec3),
    reach: f64,
    (k, theta): (usize, f64),
    tied: &Tied<'_>,
) -> Option<f64> {
    let (i, j) = plane(k);
    let off = cells.poly.ring_offset(v as usize);
    let nz = tied.moving.normal[f as usize];
    let mut least = f64::INFINITY;
    for (r, entry) in cells.poly.ring(v as usize).iter().enumerate() {
        let m = cell_arcs[off + r];
        let now = m.dot(x_new);
        if m.dot(x_old).min(now) > reach {
            least = least.min(now);
            continue;
        }
        let cz = tied.fixed.arc[entry.edge as usize];
        let persistent = (cz[k] || nz[k]) && ((cz[i] && cz[j]) || (nz[i] && nz[j]));
        if !persistent {
            return None;
        }
        if !tied.moving_is_p {
            let absorb = sos_term_certified(cells, entry.edge, faces, f, k, tied)?;
            if absorb <= theta {
                return None;
            }
            least = least.min(absorb);
        }
    }
    Some(least)
}

/// For an arc `e` of P (the `arcs` view, rotated to the new pose) and a
/// face normal `g` of Q whose determinant is a persistent tie: whether the
/// SoS sign is constant along the step. Rows sorted by index are P's two
/// normals, then Q's. The SoS terms are scanned in order of significance:
/// a term that vanishes at every rotation about `e_k` (a product of exact
/// structural zeros, or the rotation-invariant minor `(a × b)_k = 0` of P's
/// two rows in the plane coordinates) is skipped; the first other term
/// decides the sign, and stays non-zero over any rotation by less than
/// (its value less its float error and slack) divided by its rate of change
/// (at most `|u| |v|` per radian for each rotating row of a 2×2 minor, `|u|`
/// for an entry).
/// Returns that rotation (`∞` for a constant term), or `None` when the
/// deciding term is not certainly non-zero now.
fn sos_term_certified(
    arcs: &GaussView<'_>,
    e: u32,
    normals: &GaussView<'_>,
    g: u32,
    k: usize,
    tied: &Tied<'_>,
) -> Option<f64> {
    let [f0, f1] = arcs.poly.edge(e as usize).faces;
    let (lo, hi) = (f0.min(f1), f0.max(f1));
    let rows = [arcs.normal(lo), arcs.normal(hi), normals.normal(g)];
    let a = rows.each_ref().map(|r| r.approx());
    let err = rows.each_ref().map(|r| r.error());
    let (pz, qz) = (&tied.fixed.normal, &tied.moving.normal);
    let zeros = [pz[lo as usize], pz[hi as usize], qz[g as usize]];
    let (i, j) = plane(k);
    // Structurally zero at every rotation about e_k; varying along it.
    let zero = |r: usize, c: usize| {
        if r == 2 || c == k {
            zeros[r][c]
        } else {
            zeros[r][i] && zeros[r][j]
        }
    };
    let varies = |r: usize, c: usize| r < 2 && c != k && !(zeros[r][i] && zeros[r][j]);
    let norm = |r: usize| a[r].length() + err[r];
    for t in sos_terms() {
        match *t {
            SosTerm::Cofactor { row, col } => {
                let [r0, r1] = others(row as usize);
                let [c0, c1] = others(col as usize);
                if (zero(r0, c0) || zero(r1, c1)) && (zero(r0, c1) || zero(r1, c0)) {
                    continue;
                }
                if r1 < 2 && c0 != k && c1 != k {
                    // P's two rows in the plane: `det(B) (a × b)_k`, constant.
                    if tied.fixed.arc[e as usize][k] {
                        continue;
                    }
                    return Some(f64::INFINITY);
                }
                let (u, w) = (a[r0], a[r1]);
                let d = u[c0] * w[c1] - u[c1] * w[c0];
                let (mu, mw) = (u[c0].abs().max(u[c1].abs()), w[c0].abs().max(w[c1].abs()));
                let (eu, ew) = (err[r0], err[r1]);
                let bound = 1.01 * (2.0 * (eu * (mw + ew) + mu * ew) + 8.0 * U * mu * mw)
                    + f64::MIN_POSITIVE;
                // Rows with an entry that varies: each changes the minor by
                // at most |u| |v| per radian.
                let moving = [r0, r1]
                    .iter()
                    .filter(|&&r| varies(r, c0) || varies(r, c1))
                    .count();
                let scale = norm(r0) * norm(r1);
                let left = d.abs() - bound - SLACK * scale;
                return (left > 0.0).then(|| {
                    if moving > 0 {
                        left / (1.01 * moving as f64 * scale)
                    } else {
                        f64::INFINITY
                    }
                });
            }
            SosTerm::Entry { row, col, .. } => {
                let (r, c) = (row as usize, col as usize);
                if zero(r, c) {
                    continue;
                }
                let left = a[r][c].abs() - 1.01 * err[r] - SLACK * norm(r);
                return (left > 0.0).then(|| {
                    if varies(r, c) {
                        left / (1.01 * norm(r))
                    } else {
                        f64::INFINITY
                    }
                });
            }
            SosTerm::Constant(_) => return Some(f64::INFINITY),
        }
    }
    Some(f64::INFINITY)
}

/// Hill climbing in floats on the unit ring arcs (oriented inwards): cross
/// the most violated arc until every arc is clearly satisfied. Returns
/// `None` as soon as a decision is within `thr` of zero (the exact
/// [`GaussView::locate`] takes over) or after `V` steps.
fn locate_certified(
    poly: &Polytope,
    arcs: &[DVec3],
    x: DVec3,
    thr: f64,
    start: u32,
) -> Option<u32> {
    let mut v = start;
    for _ in 0..poly.vertex_count() {
        let off = poly.ring_offset(v as usize);
        let ring = poly.ring(v as usize);
        let mut worst = (thr, u32::MAX);
        for (i, r) in ring.iter().enumerate() {
            let s = arcs[off + i].dot(x);
            if s.abs() <= thr {
                return None;
            }
            if s < -worst.0 {
                worst = (-s, r.neighbor);
            }
        }
        if worst.1 == u32::MAX {
            return Some(v);
        }
        v = worst.1;
    }
    None
}

/// The arc a moving normal certainly crossed, and only it: the old cell `v`
/// and new cell `w` are adjacent across arc `x`, the old position is farther
/// than `reach` from every other arc of `v` and the new one from every other
/// arc of `w`. Then the path (no longer than `reach`) stays in `v ∪ w`,
/// whose common boundary is `x`, and meets `x`'s great circle at most twice
/// (a small circle meets a great circle in at most two points) and an odd
/// number of times: exactly once.
fn single_crossing(
    poly: &Polytope,
    arcs: &[DVec3],
    (v, x_old): (u32, DVec3),
    (w, x_new): (u32, DVec3),
    reach: f64,
) -> Option<u32> {
    let x = poly.ring(v as usize).iter().find(|r| r.neighbor == w)?.edge;
    let clear = |cell: u32, pos: DVec3| {
        let off = poly.ring_offset(cell as usize);
        poly.ring(cell as usize)
            .iter()
            .enumerate()
            .all(|(i, r)| r.edge == x || arcs[off + i].dot(pos) > reach)
    };
    (clear(v, x_old) && clear(w, x_new)).then_some(x)
}

/// The facets of `before` missing from `after`, and those of `after`
/// missing from `before`: fv- and vf-pairs compared by face, ee-pairs by
/// merging the two sorted lists. O(m + n + k), no hashing.
fn overlay_diff(before: &Overlay, after: &Overlay) -> (Vec<Facet>, Vec<Facet>) {
    let (mut removed, mut added) = (Vec::new(), Vec::new());
    for (f, (&u, &v)) in before.fv.iter().zip(&after.fv).enumerate() {
        if u != v {
            removed.push(Facet::Fv {
                p_face: f as u32,
                q_vertex: u,
            });
            added.push(Facet::Fv {
                p_face: f as u32,
                q_vertex: v,
            });
        }
    }
    for (g, (&u, &v)) in before.vf.iter().zip(&after.vf).enumerate() {
        if u != v {
            removed.push(Facet::Vf {
                p_vertex: u,
                q_face: g as u32,
            });
            added.push(Facet::Vf {
                p_vertex: v,
                q_face: g as u32,
            });
        }
    }
    let ee = |(p_edge, q_edge): (u32, u32)| Facet::Ee { p_edge, q_edge };
    let (x, y) = (&before.ee, &after.ee);
    let (mut i, mut j) = (0, 0);
    while i < x.len() || j < y.len() {
        match (x.get(i), y.get(j)) {
            (Some(a), Some(b)) if a == b => {
                i += 1;
                j += 1;
            }
            (Some(&a), Some(&b)) if a < b => {
                removed.push(ee(a));
                i += 1;
            }
            (Some(&a), None) => {
                removed.push(ee(a));
                i += 1;
            }
            (_, Some(&b)) => {
                added.push(ee(b));
                j += 1;
            }
            (None, None) => unreachable!("the loop condition excludes it"),
        }
    }
    (removed, added)
}
