//! C-obstacle slices as half-spaces, read straight from the facets of the
//! dynamic sum: no mesh is built.
//!
//! A slice `S = O ⊕ (−R·A)` is `{x : n_i·x ≤ d_i}` over its faces. The
//! faces are the groups of coplanar facets of the sum (the exact
//! coplanarity test of the mesh merge, `sum::merge`: parallel faces,
//! normals on arcs; degenerate parallelograms are dropped), one plane per
//! group. The exact tests are made only at normals the dynamic sum's lazy
//! margins do not certify strictly inside their cells (`dynamic`, module
//! docs, "Certified normals"; `sum::merge::coplanar_groups_certified`):
//! such a normal is on no arc of the other map, so its facets are coplanar
//! with none, and the groups are the same. On `cobst_map`'s 4,000 slices
//! this cut the grouping from 26% of the read-out's instructions to 6%. Its normal is the float unit normal of the group's first facet: a
//! face normal of P or Q turned by its pose when the group holds an
//! fv- or vf-facet, else the normalised cross product of the posed edges of
//! the ee-facet.
//!
//! **The offsets are rounded outward.** The mesh of a slice
//! ([`DynamicSum::try_to_mesh`]) has the vertices `fl(p' + q')` with `p'`,
//! `q'` the rounded posed vertices of the two operands. For a normal `n`,
//! `max n·p'` and `max n·q'` are bounded from above rigorously by the
//! near-extreme search of `query::support` (breadth-first from the facet's
//! own vertex over every vertex within the float dot products' error bound
//! of the best: the largest float `n·p'` over all vertices, plus its
//! rounding; for a plane from a face of the obstacle, which does not move,
//! the obstacle's term is carried over from slice to slice while its posed
//! vertices are the same bit for bit), and
//! `d = up_P + up_Q + 2|n|₁·u·(s_P + s_Q) + err`
//! (`s` the coordinates' magnitudes, `err` one dot product's rounding),
//! every sum rounded up. So every vertex `x` of the slice's mesh satisfies
//! `n·x ≤ d` both exactly and in floats: the region is never smaller than
//! the mesh. Each plane touches the slice: `d` exceeds the largest `n·x` by
//! a few units of rounding of the coordinates.
//!
//! **An fv-plane's robot term in O(1).** For the plane of an fv-facet
//! (face `f` of P turned, `n = fl(M n̂)` with `M` P's rotation matrix and
//! `n̂` the face's float unit normal), the search's result, the largest
//! float `n·p'` over every vertex, is the largest over `f`'s own vertices
//! `V_f` whenever every vertex `u` next to the face (`N_f`: adjacent to a
//! vertex of `V_f`, not in it) lies below every vertex `v` of it by
//! `d·(p_v − p_u) > 2(η|n| + err)`, `d = Mᵀn` (then no other vertex's float
//! value can exceed the best face vertex's: below). Once per C-obstacle,
//! `face_depths.rs` bounds `n̂·(p_v − p_u)` from below over those pairs
//! (`depth`, float rounding included) and `|p_v − p_u|` from above
//! (`span`, without squares); per plane, `|d − n̂| ≤ ‖MᵀM − I‖·|n̂| +
//! ‖Mᵀ‖·|fl(M n̂) − M n̂| < 10⁻¹³` (`|n̂|` and `‖M‖` within `10⁻¹⁵` of 1,
//! the matrix's entries within `2⁻⁴⁷` of a rotation's: `‖MᵀM − I‖ ≲
//! 4.3·10⁻¹⁴`), so `depth − 10⁻¹³·span > 2(η|n| + err)` certifies the
//! pairs, and the term is the face vertices' largest value plus `err`, the
//! same float as the search's.
//! Why the pairs suffice: the exact posed vertices `M p + t` form a convex
//! polytope with P's graph, on which `φ = n·(M p + t)` is linear. The best
//! face vertex beats its face neighbours (it is the face's best) and its
//! other neighbours (the pairs), so it is a local, hence global, maximum of
//! `φ`; and the best vertex off the face is adjacent to the face (else it
//! is at least as high as all its neighbours, all off the face, and is a
//! global maximum too, so the maximisers form a face of the polytope
//! holding it and the face's best vertex, whose connected graph leads from
//! the face to it through a vertex of `N_f` as high as the maximum:
//! excluded by the pairs). So every
//! vertex `u` off the face has `φ(u) < φ(v*) − 2(η|n| + err)`, and its
//! float value `≤ φ(u) + η|n| + err` is below the best face vertex's `≥
//! φ(v*) − η|n| − err`. Where the bound does not hold (a face with a
//! neighbour almost in its plane, a body far from the origin) the search
//! runs as before.
//!
//! *Independent review (2026-12-01).* A second reading checked the
//! convexity argument (including ties), the `10⁻¹³` bound against the
//! snapped matrices, the depths' rounding allowance and the bit identity
//! with the search, and found: the span was computed from squares, which
//! underflow to 0 for parts below about 10⁻¹⁶² (a hand-built wedge at
//! scale 2⁻⁶⁰⁰ turned by 1.18·10⁻⁷ about z was certified below the
//! search's value); `halfspaces_of` indexed the depths of its own robot
//! for any sum with as many vertices (a panic, or another body's depths);
//! the depths took O(Σ|f|²·degree). All three are mended (no squares, the
//! depths only for a sum of the very same bodies, a face-local origin:
//! O(Σ|f|·degree)), with a test at scales 2^±600 and snapped turns
//! (`face_depths_hold_at_extreme_scales_and_snapped_turns`); that test does
//! not isolate the `10⁻¹³·span` term (it passes without it).
//!
//! The cost is that of the facets: a few dot products per facet, no merge,
//! no vertex sums and no convexity check.
//!
//! ```
//! use dymsum::query::orientations_about_axis;
//! use dymsum::{CObstacle, DVec3, Polytope};
//! let tet = Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]])?;
//! let corners: Vec<[f64; 3]> = (0..8)
//!     .map(|i| [4.0 + 2.0 * (i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
//!     .collect();
//! let cobst = CObstacle::new(&tet, &Polytope::from_points(&corners)?)?;
//! let turns = orientations_about_axis(DVec3::Z, 12).ok_or("zero axis")?;
//! let planes = cobst.halfspace_slices(&turns)?;
//! for (h, &turn) in planes.iter().zip(&turns) {
//!     let mesh = cobst.slice(turn)?;
//!     // One plane per face of the slice, and every vertex inside.
//!     assert_eq!(h.len(), mesh.faces.len());
//!     assert!(mesh.vertices.iter().all(|&v| h.contains(v.into())));
//! }
//! assert_eq!(cobst.halfspace_slices_par(&turns)?, planes);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::dynamic::DynamicSum;
use crate::kernel::rotation::Rotation;
use crate::polytope::Polytope;
use crate::query::cobstacle::face_depths::FaceDepth;
use crate::query::cobstacle::slices::{CObstacle, Reaches};
use crate::query::error::QueryError;
use crate::query::frame::up;
use crate::query::proximity::support::{dot_error, near_max_upper, search_slack, Marks};
use crate::sum::merge::coplanar_groups_certified;
use crate::sum::{Operands, Overlay};
use glam::DVec3;

/// A convex region `{x : n_i·x ≤ d_i}`: unit outward normals (floats) and
/// offsets rounded outward (module docs).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HalfSpaces {
    normals: Vec<DVec3>,
    offsets: Vec<f64>,
}

impl HalfSpaces {
    /// The unit outward normals `n_i`.
    pub fn normals(&self) -> &[DVec3] {
        &self.normals
    }
    /// The offsets `d_i`.
    pub fn offsets(&self) -> &[f64] {
        &self.offsets
    }
    /// Number of half-spaces.
    pub fn len(&self) -> usize {
        self.normals.len()
    }
    /// `true` if there are none.
    pub fn is_empty(&self) -> bool {
        self.normals.is_empty()
    }
    /// Whether `n_i·x ≤ d_i` for every `i`, in floats.
    pub fn contains(&self, x: DVec3) -> bool {
        self.normals
            .iter()
            .zip(&self.offsets)
            .all(|(n, &d)| n.dot(x) <= d)
    }
    /// Half-spaces from their normals and offsets (the same length).
    pub(in crate::query) fn from_parts(normals: Vec<DVec3>, offsets: Vec<f64>) -> HalfSpaces {
        debug_assert_eq!(normals.len(), offsets.len());
        HalfSpaces { normals, offsets }
    }
    /// The normals and offsets, consumed.
    pub fn into_parts(self) -> (Vec<DVec3>, Vec<f64>) {
        (self.normals, self.offsets)
    }
}

/// The robot term of an fv-plane of face `face` with normal `n` in O(1)
/// when its [`FaceDepth`] certifies it (module docs): the largest float
/// `n·p'` over the face's vertices plus `err`, the same float as
/// [`near_max_upper`]'s; else `None`.
#[inline]
fn face_top(
    poly: &Polytope,
    posed: &[DVec3],
    face: usize,
    n: DVec3,
    bounds: Posed,
    depth: FaceDepth,
) -> Option<f64> {
    let (err, slack) = search_slack(n, bounds.eta, bounds.scale);
    // The rounding of these few operations is far below the factor (a NaN
    // certifies nothing).
    let certified = depth.depth - 1e-13 * depth.span > slack * (1.0 + 1e-9);
    if !certified {
        return None;
    }
    let mut best = f64::NEG_INFINITY;
    for &v in poly.face(face) {
        let x = n.dot(posed[v as usize]);
        if x > best {
            best = x;
        }
    }
    Some(best + err)
}

/// The bounds on one posed operand: `scale` its coordinates' magnitude,
/// `eta` the rounding of a posed vertex.
#[derive(Clone, Copy, Debug)]
struct Posed {
    scale: f64,
    eta: f64,
}

impl Posed {
    /// `|R v + t| ≤ r(1 + 2⁻⁴⁰) + |t|`; `fl(R v + t)` within `√3·u(4.02 r +
    /// |t|) < 8u(r + |t|)` of `R v + t` (the vector's length, as `η|n|`
    /// needs; `query::slabs`).
    fn of(reach: f64, translation: DVec3) -> Posed {
        let t = up(translation.length());
        Posed {
            scale: up(up(reach * (1.0 + 2f64.powi(-40))) + t),
            eta: up(8.0 * f64::EPSILON * up(reach + t)),
        }
    }
}

/// Scratch of one walk over slices (marks of the near-extreme searches and
/// the overlay buffer), reused from slice to slice.
#[derive(Default)]
struct Scratch {
    overlay: Overlay,
    /// The posed vertices of P and Q (`Operands::p_vertex`, `q_vertex`),
    /// computed once per slice rather than once per visit.
    posed_p: Vec<DVec3>,
    posed_q: Vec<DVec3>,
    marks_p: Marks,
    marks_q: Marks,
    set: Vec<u32>,
    /// The Q-side offset term of each vf-plane (per face of Q: its normal
    /// and `max n·q'` bounded, as the search gives it), valid while Q's
    /// posed vertices and bounds are those of `q_key` (Q does not move
    /// between the slices of a C-obstacle).
    vf_q: Vec<Option<([u64; 3], f64)>>,
    q_key: (Vec<DVec3>, [u64; 2]),
    /// How many Q-side searches of vf-planes the cache saved, and how many
    /// it did not (tests).
    #[cfg(test)]
    vf_hits: (usize, usize),
    /// How many fv-planes' robot terms the face depths certified, and how
    /// many fell back to the search (tests).
    #[cfg(test)]
    fv_certified: (usize, usize),
}

/// The bits of a vector (a cache key: `-0.0` and `0.0` differ).
#[inline]
fn bits(v: DVec3) -> [u64; 3] {
    v.to_array().map(f64::to_bits)
}

/// The half-spaces of the sum held by `sum` (module docs).
fn sum_halfspaces(
    sum: &DynamicSum,
    (reach, depths): (Reaches, &[FaceDepth]),
    scratch: &mut Scratch,
) -> Result<HalfSpaces, QueryError> {
    let ops: &Operands = sum.operands();
    sum.overlay_into(&mut scratch.overlay);
    let overlay = &scratch.overlay;
    // The exact coplanarity tests only where the sum's margins do not
    // certify the normals strictly inside their cells (`dynamic`, module
    // docs, "Certified normals"): the same groups.
    let (mut groups, degenerate, _) = coplanar_groups_certified(
        ops,
        overlay,
        |f| sum.normal_strictly_inside(false, f as usize),
        |g| sum.normal_strictly_inside(true, g as usize),
    );
    let bp = Posed::of(reach.p, ops.pose_p.translation);
    let bq = Posed::of(reach.q, ops.pose_q.translation);
    let (rp, rq) = (ops.pose_p.rotation, ops.pose_q.rotation);
    let (m, nf) = (overlay.fv.len(), overlay.vf.len());
    scratch.posed_p.clear();
    scratch
        .posed_p
        .extend((0..ops.p.vertex_count() as u32).map(|v| ops.p_vertex(v)));
    scratch.posed_q.clear();
    scratch
        .posed_q
        .extend((0..ops.q.vertex_count() as u32).map(|v| ops.q_vertex(v)));
    // The vf-planes' Q-side terms carry over while Q's posed vertices do
    // (`near_max_upper` depends on the direction and the posed vertices
    // only).
    let q_bounds = [bq.scale.to_bits(), bq.eta.to_bits()];
    if scratch.q_key.1 != q_bounds
        || scratch.q_key.0.len() != scratch.posed_q.len()
        || scratch
            .q_key
            .0
            .iter()
            .zip(&scratch.posed_q)
            .any(|(a, b)| bits(*a) != bits(*b))
        || scratch.vf_q.len() != nf
    {
        scratch.vf_q.clear();
        scratch.vf_q.resize(nf, None);
        scratch.q_key.0.clone_from(&scratch.posed_q);
        scratch.q_key.1 = q_bounds;
    }
    let (posed_p, posed_q) = (&scratch.posed_p, &scratch.posed_q);
    let mut out = HalfSpaces {
        normals: Vec::with_capacity(overlay.len()),
        offsets: Vec::with_capacity(overlay.len()),
    };
    for (id, &flat) in degenerate.iter().enumerate() {
        if flat || groups.find(id as u32) != id as u32 {
            continue;
        }
        // The normal, and a vertex of each operand on the facet.
        let (n, u, w) = if id < m {
            let w = overlay.fv[id];
            (rp.apply(ops.p.unit_normal(id)), ops.p.face(id)[0], w)
        } else if id < m + nf {
            let g = id - m;
            (
                rq.apply(ops.q.unit_normal(g)),
                overlay.vf[g],
                ops.q.face(g)[0],
            )
        } else {
            let (e, e2) = overlay.ee[id - m - nf];
            let pe = ops.p.edge(e as usize);
            let qe = ops.q.edge(e2 as usize);
            let [u1, u2] = pe.vertices;
            let [w1, w2] = qe.vertices;
            let c = (posed_p[u2 as usize] - posed_p[u1 as usize])
                .cross(posed_q[w2 as usize] - posed_q[w1 as usize])
                .normalize_or_zero();
            // Outward: towards the normals of P's faces at the edge.
            let [f0, f1] = pe.faces;
            let out = rp.apply(ops.p.unit_normal(f0 as usize) + ops.p.unit_normal(f1 as usize));
            let c = if c.dot(out) < 0.0 { -c } else { c };
            if c == DVec3::ZERO || !c.is_finite() {
                return Err(QueryError::Inconsistent(format!(
                    "the normal of facet ee({e}, {e2}) is zero or not finite"
                )));
            }
            (c, u1, w1)
        };
        // No depths (a sum not of this C-obstacle's own bodies): the search.
        let certified = match depths.get(id).filter(|_| id < m) {
            Some(&depth) => face_top(&ops.p, posed_p, id, n, bp, depth),
            None => None,
        };
        #[cfg(test)]
        if id < m {
            let count = &mut scratch.fv_certified;
            *if certified.is_some() {
                &mut count.0
            } else {
                &mut count.1
            } += 1;
        }
        let search_p = |marks: &mut Marks, set: &mut Vec<u32>| {
            near_max_upper(
                &ops.p,
                |v| posed_p[v as usize],
                n,
                u,
                bp.eta,
                bp.scale,
                marks,
                set,
            )
        };
        let sp = match certified {
            Some(sp) => {
                debug_assert_eq!(
                    sp.to_bits(),
                    search_p(&mut scratch.marks_p, &mut scratch.set).to_bits(),
                    "the face's certified term is the search's"
                );
                sp
            }
            None => search_p(&mut scratch.marks_p, &mut scratch.set),
        };
        let mut search_q = || {
            near_max_upper(
                &ops.q,
                |v| posed_q[v as usize],
                n,
                w,
                bq.eta,
                bq.scale,
                &mut scratch.marks_q,
                &mut scratch.set,
            )
        };
        let sq = if (m..m + nf).contains(&id) {
            match scratch.vf_q[id - m] {
                Some((key, sq)) if key == bits(n) => {
                    #[cfg(test)]
                    {
                        scratch.vf_hits.0 += 1;
                    }
                    sq
                }
                _ => {
                    let sq = search_q();
                    scratch.vf_q[id - m] = Some((bits(n), sq));
                    #[cfg(test)]
                    {
                        scratch.vf_hits.1 += 1;
                    }
                    sq
                }
            }
        } else {
            search_q()
        };
        let s = up(bp.scale + bq.scale);
        let l1 = up(n.x.abs() + n.y.abs() + n.z.abs());
        let rounding = up(2.0 * l1 * f64::EPSILON * s) + dot_error(n, s);
        let d = above(above(sp + sq) + rounding);
        if !d.is_finite() {
            return Err(QueryError::OutOfRange(format!(
                "a half-space offset overflows f64 (facet {id} of the slice)"
            )));
        }
        out.normals.push(n);
        out.offsets.push(d);
    }
    Ok(out)
}

/// A float at least `x` and at least the value `x` was rounded from (one
/// rounded operation).
#[inline]
fn above(x: f64) -> f64 {
    x + (x.abs() * f64::EPSILON + f64::MIN_POSITIVE)
}

impl CObstacle {
    fn reaches(&self) -> Reaches {
        self.reaches
    }

    /// The half-spaces of the slice held by `sum`, a dynamic sum of this
    /// C-obstacle's reflected robot and obstacle (as handed to the closure
    /// of [`CObstacle::map_par`]).
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when an offset overflows `f64`;
    /// [`QueryError::Inconsistent`] for an internal error, or when `sum`
    /// is not a sum of this C-obstacle's bodies.
    pub fn halfspaces_of(&self, sum: &DynamicSum) -> Result<HalfSpaces, QueryError> {
        if sum.p().vertex_count() != self.reflected_robot().vertex_count()
            || sum.q().vertex_count() != self.obstacle().vertex_count()
        {
            return Err(QueryError::Inconsistent(
                "halfspaces_of: the dynamic sum is not of this C-obstacle's bodies".into(),
            ));
        }
        // The face depths are the reflected robot's: only for a sum of the
        // very same bodies (`map_par`'s; a sum of equal copies is read out
        // by the searches).
        let depths = if sum.p().same_data(self.reflected_robot()) {
            self.face_depths()
        } else {
            &[]
        };
        SCRATCH.with(|c| sum_halfspaces(sum, (self.reaches, depths), &mut c.borrow_mut()))
    }

    /// The slice at one orientation as half-spaces, computed from scratch
    /// (module docs).
    ///
    /// # Errors
    /// [`QueryError::Sum`] for an internal error of the sum;
    /// [`QueryError::OutOfRange`] when an offset overflows `f64`.
    pub fn halfspace_slice(&self, orientation: Rotation) -> Result<HalfSpaces, QueryError> {
        let mut sum = None;
        let s = self.advance(&mut sum, orientation)?;
        sum_halfspaces(
            s,
            (self.reaches(), self.face_depths()),
            &mut Scratch::default(),
        )
    }

    /// The slices as half-spaces, in order, by one dynamic sum moved from
    /// slice to slice; the same as [`CObstacle::halfspace_slice`] at each
    /// orientation.
    ///
    /// # Errors
    /// The first failing slice, as [`CObstacle::halfspace_slice`].
    pub fn halfspace_slices(
        &self,
        orientations: &[Rotation],
    ) -> Result<Vec<HalfSpaces>, QueryError> {
        let bounds = (self.reaches(), self.face_depths());
        let mut scratch = Scratch::default();
        let mut sum = None;
        orientations
            .iter()
            .map(|&r| {
                let s = self.advance(&mut sum, r)?;
                sum_halfspaces(s, bounds, &mut scratch)
            })
            .collect()
    }

    /// [`CObstacle::halfspace_slices`] on rayon's threads, in contiguous
    /// chunks ([`CObstacle::map_par`]): the same result.
    ///
    /// # Errors
    /// The same as [`CObstacle::halfspace_slices`] (the first in order).
    pub fn halfspace_slices_par(
        &self,
        orientations: &[Rotation],
    ) -> Result<Vec<HalfSpaces>, QueryError> {
        self.map_par(orientations, |_, _, s| self.halfspaces_of(s))?
            .into_iter()
            .collect()
    }
}

thread_local! {
    /// Per-thread scratch of [`CObstacle::halfspace_slices_par`].
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::default());
}

#[cfg(test)]
mod tests {
    //! The fast read-out (`near_max_upper`, the vf-planes' Q-side terms
    //! carried over between slices) against the read-out it replaced, kept
    //! here as the reference: the same planes, bit for bit.
    use super::*;
    use crate::polytope::Polytope;
    use crate::query::proximity::support::near_max;
    use crate::sum::merge::coplanar_groups;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The per-slice read-out before the fast path (every plane's two
    /// searches done in full by `near_max`, nothing carried over).
    pub(in crate::query) fn reference_halfspaces(
        sum: &DynamicSum,
        reach: Reaches,
        scratch: &mut Scratch,
    ) -> Result<HalfSpaces, QueryError> {
        let ops: &Operands = sum.operands();
        sum.overlay_into(&mut scratch.overlay);
        let overlay = &scratch.overlay;
        let (mut groups, degenerate, _) = coplanar_groups(ops, overlay);
        let bp = Posed::of(reach.p, ops.pose_p.translation);
        let bq = Posed::of(reach.q, ops.pose_q.translation);
        let (rp, rq) = (ops.pose_p.rotation, ops.pose_q.rotation);
        let (m, nf) = (overlay.fv.len(), overlay.vf.len());
        scratch.posed_p.clear();
        scratch
            .posed_p
            .extend((0..ops.p.vertex_count() as u32).map(|v| ops.p_vertex(v)));
        scratch.posed_q.clear();
        scratch
            .posed_q
            .extend((0..ops.q.vertex_count() as u32).map(|v| ops.q_vertex(v)));
        let (posed_p, posed_q) = (&scratch.posed_p, &scratch.posed_q);
        let mut out = HalfSpaces {
            normals: Vec::with_capacity(overlay.len()),
            offsets: Vec::with_capacity(overlay.len()),
        };
        for (id, &flat) in degenerate.iter().enumerate() {
            if flat || groups.find(id as u32) != id as u32 {
                continue;
            }
            // The normal, and a vertex of each operand on the facet.
            let (n, u, w) = if id < m {
                let w = overlay.fv[id];
                (rp.apply(ops.p.unit_normal(id)), ops.p.face(id)[0], w)
            } else if id < m + nf {
                let g = id - m;
                (
                    rq.apply(ops.q.unit_normal(g)),
                    overlay.vf[g],
                    ops.q.face(g)[0],
                )
            } else {
                let (e, e2) = overlay.ee[id - m - nf];
                let pe = ops.p.edge(e as usize);
                let qe = ops.q.edge(e2 as usize);
                let [u1, u2] = pe.vertices;
                let [w1, w2] = qe.vertices;
                let c = (posed_p[u2 as usize] - posed_p[u1 as usize])
                    .cross(posed_q[w2 as usize] - posed_q[w1 as usize])
                    .normalize_or_zero();
                // Outward: towards the normals of P's faces at the edge.
                let [f0, f1] = pe.faces;
                let out = rp.apply(ops.p.unit_normal(f0 as usize) + ops.p.unit_normal(f1 as usize));
                let c = if c.dot(out) < 0.0 { -c } else { c };
                if c == DVec3::ZERO || !c.is_finite() {
                    return Err(QueryError::Inconsistent(format!(
                        "the normal of facet ee({e}, {e2}) is zero or not finite"
                    )));
                }
                (c, u1, w1)
            };
            let sp = near_max(
                &ops.p,
                |v| posed_p[v as usize],
                n,
                u,
                0.0,
                bp.eta,
                bp.scale,
                &mut scratch.marks_p,
                &mut scratch.set,
            );
            let sq = near_max(
                &ops.q,
                |v| posed_q[v as usize],
                n,
                w,
                0.0,
                bq.eta,
                bq.scale,
                &mut scratch.marks_q,
                &mut scratch.set,
            );
            let s = up(bp.scale + bq.scale);
            let l1 = up(n.x.abs() + n.y.abs() + n.z.abs());
            let rounding = up(2.0 * l1 * f64::EPSILON * s) + dot_error(n, s);
            let d = above(above(sp.upper + sq.upper) + rounding);
            if !d.is_finite() {
                return Err(QueryError::OutOfRange(format!(
                    "a half-space offset overflows f64 (facet {id} of the slice)"
                )));
            }
            out.normals.push(n);
            out.offsets.push(d);
        }
        Ok(out)
    }

    fn random_body(rng: &mut ChaCha8Rng, n: usize, kind: u32) -> Polytope {
        let mut pts: Vec<[f64; 3]> = (0..n)
            .map(|_| {
                let v = DVec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                match kind {
                    // On a sphere: mostly triangles.
                    0 => (v.normalize_or_zero() * 1.5).to_array(),
                    // A grid: coplanar faces, merged planes.
                    1 => (v * 4.0).round().to_array(),
                    // Far from the origin, tiny.
                    2 => (v * 1e-3 + DVec3::new(1e3, -2e3, 5e2)).to_array(),
                    // Farther and tinier: the rounding of the posed
                    // vertices is near the faces' depths.
                    3 => (v * 1e-10 + DVec3::new(1e3, -2e3, 5e2)).to_array(),
                    // A dome of faces at angles near 1e-13: neighbours
                    // almost in a face's plane.
                    _ => [v.x, v.y, -(v.x * v.x + v.y * v.y) * 5e-14],
                }
            })
            .collect();
        if kind == 4 {
            pts.push([0.0, 0.0, -1.0]);
        }
        Polytope::from_points(&pts).unwrap()
    }

    /// The face depths at extreme scales (2⁻⁶⁰⁰: a span computed from
    /// squares underflowed to 0, found by the review of 2026-12-01) and
    /// under rotations whose matrices are snapped (a turn of 1.18e-7 about
    /// z, quarter turns and turns near them), on a body with a vertex
    /// almost in a tilted face's plane: every plane the same as the
    /// reference's (and, in debug builds, every certified term the
    /// search's).
    #[test]
    fn face_depths_hold_at_extreme_scales_and_snapped_turns() {
        let turns: Vec<Rotation> = [
            (DVec3::Z, 1.18e-7),
            (DVec3::Z, std::f64::consts::FRAC_PI_2),
            (DVec3::X, std::f64::consts::FRAC_PI_2 + 1e-9),
            (DVec3::new(1.0, 1.0, 0.0), std::f64::consts::PI - 3e-8),
            (DVec3::new(0.3, -0.2, 1.0), 0.7),
        ]
        .iter()
        .map(|&(axis, angle)| Rotation::from_axis_angle(axis, angle).unwrap())
        .collect();
        let mut certified = 0;
        for scale in [2f64.powi(-600), 1.0, 2f64.powi(600)] {
            for delta in [0.0, 5e-15, 1e-14, 1e-12] {
                // A tilted face z = x, a vertex `delta` below its plane
                // across an edge, and a sphere's points below.
                let mut pts = vec![
                    [0.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [1.0, 0.0, 1.0],
                    [-1.0, 1.0, -1.0 - delta],
                ];
                pts.extend((0..12).map(|k| {
                    let a = k as f64 * 0.52;
                    [
                        0.6 * a.cos(),
                        0.5 + 0.6 * a.sin(),
                        -2.5 - 0.1 * (k % 3) as f64,
                    ]
                }));
                let pts: Vec<[f64; 3]> = pts.iter().map(|p| p.map(|c| c * scale)).collect();
                let robot = Polytope::from_points(&pts).unwrap();
                let obstacle = Polytope::from_points(
                    &(0..8)
                        .map(|i| {
                            [i & 1, (i >> 1) & 1, (i >> 2) & 1].map(|b| (b as f64 + 3.0) * scale)
                        })
                        .collect::<Vec<_>>(),
                )
                .unwrap();
                let cobst = CObstacle::new(&robot, &obstacle).unwrap();
                let (mut scratch, mut reference) = (Scratch::default(), Scratch::default());
                let mut sum = None;
                for &r in &turns {
                    let s = cobst.advance(&mut sum, r).unwrap();
                    let bounds = (cobst.reaches(), cobst.face_depths());
                    let (Ok(fast), Ok(slow)) = (
                        sum_halfspaces(s, bounds, &mut scratch),
                        reference_halfspaces(s, cobst.reaches(), &mut reference),
                    ) else {
                        continue;
                    };
                    assert_eq!(fast, slow, "scale {scale}, delta {delta}, {r:?}");
                }
                certified += scratch.fv_certified.0;
            }
        }
        assert!(certified > 0);
    }

    #[test]
    fn fast_halfspaces_equal_the_reference_on_random_rotations() {
        let mut rng = ChaCha8Rng::seed_from_u64(22);
        let (mut hits, mut faces) = ((0, 0), (0, 0));
        for case in 0..13u32 {
            // The robot's kinds 3 and 4 make the face depths fall back.
            let kind = if case < 9 { case % 3 } else { 3 + case % 2 };
            let robot = random_body(&mut rng, 40 + 20 * (case % 9) as usize, kind);
            let obstacle = random_body(&mut rng, 60, (case / 3) % 3);
            let cobst = CObstacle::new(&robot, &obstacle).unwrap();
            // Random orientations, and a run of small steps about one axis
            // (the walk the cache is for).
            let axis = DVec3::new(rng.random_range(-1.0..1.0), 0.3, 1.0);
            let mut turns: Vec<Rotation> = (0..12)
                .map(|_| {
                    let a = DVec3::new(
                        rng.random_range(-1.0..1.0),
                        rng.random_range(-1.0..1.0),
                        rng.random_range(-1.0..1.0),
                    );
                    Rotation::from_axis_angle(a, rng.random_range(0.0..6.3)).unwrap()
                })
                .collect();
            turns
                .extend((0..12).map(|k| Rotation::from_axis_angle(axis, 0.01 * k as f64).unwrap()));
            let mut scratch = Scratch::default();
            let mut reference = Scratch::default();
            let mut sum = None;
            for (k, &r) in turns.iter().enumerate() {
                let s = cobst.advance(&mut sum, r).unwrap();
                let bounds = (cobst.reaches(), cobst.face_depths());
                let fast = sum_halfspaces(s, bounds, &mut scratch).unwrap();
                let slow = reference_halfspaces(s, cobst.reaches(), &mut reference).unwrap();
                assert_eq!(fast.len(), slow.len(), "case {case}, slice {k}");
                for (i, ((a, b), (c, d))) in fast
                    .normals()
                    .iter()
                    .zip(fast.offsets())
                    .zip(slow.normals().iter().zip(slow.offsets()))
                    .enumerate()
                {
                    assert_eq!(bits(*a), bits(*c), "case {case}, slice {k}, plane {i}");
                    assert_eq!(
                        b.to_bits(),
                        d.to_bits(),
                        "case {case}, slice {k}, plane {i}"
                    );
                }
            }
            // And the public entry points agree with the reference too.
            assert_eq!(
                cobst.halfspace_slices(&turns).unwrap(),
                turns
                    .iter()
                    .map(|&r| cobst.halfspace_slice(r).unwrap())
                    .collect::<Vec<_>>()
            );
            hits.0 += scratch.vf_hits.0;
            hits.1 += scratch.vf_hits.1;
            faces.0 += scratch.fv_certified.0;
            faces.1 += scratch.fv_certified.1;
        }
        // The Q-side terms of vf-planes are carried over between slices.
        assert!(hits.0 > hits.1, "{hits:?}");
        // Most fv-planes' robot terms are certified by the face depths, and
        // the search decides the others.
        assert!(faces.0 > 2 * faces.1 && faces.1 > 100, "{faces:?}");
    }
}

/// Timing of the fast read-out against the reference, interleaved in one
/// process (docs/BENCHMARKS.md, "C-obstacle maps"): robot and obstacle
/// vertices, one `x y z` a line, in `DYMSUM_HS_ROBOT` and
/// `DYMSUM_HS_OBSTACLE`; 4,000 orientations about `(1, 2, 3)`.
/// `cargo test --release -p dymsum --lib halfspace_timing -- --ignored --nocapture`
#[cfg(test)]
mod timing {
    use super::tests::reference_halfspaces;
    use super::*;
    use crate::kernel::rotation::Pose;
    use crate::polytope::Polytope;
    use crate::query::orientations_about_axis;
    use std::time::Instant;

    fn read(var: &str) -> Polytope {
        let path = std::env::var(var).unwrap_or_else(|_| panic!("set {var}"));
        let pts: Vec<[f64; 3]> = std::fs::read_to_string(path)
            .unwrap()
            .lines()
            .map(|l| {
                let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
                [v[0], v[1], v[2]]
            })
            .collect();
        Polytope::from_points(&pts).unwrap()
    }

    #[test]
    #[ignore = "timing: needs DYMSUM_HS_ROBOT and DYMSUM_HS_OBSTACLE"]
    fn halfspace_timing() {
        let (robot, obstacle) = (read("DYMSUM_HS_ROBOT"), read("DYMSUM_HS_OBSTACLE"));
        let cobst = CObstacle::new(&robot, &obstacle).unwrap();
        let turns = orientations_about_axis(DVec3::new(1.0, 2.0, 3.0), 4000).unwrap();
        let run = |f: &mut dyn FnMut(&DynamicSum) -> usize| {
            let t = Instant::now();
            let mut sum = None;
            let mut n = 0;
            for &r in &turns {
                n += f(cobst.advance(&mut sum, r).unwrap());
            }
            (t.elapsed().as_secs_f64(), n)
        };
        for rep in 0..3 {
            let (tu, _) = run(&mut |s| s.facet_count());
            let mut scratch = Scratch::default();
            let (tf, nf) = run(&mut |s| {
                sum_halfspaces(s, (cobst.reaches(), cobst.face_depths()), &mut scratch)
                    .unwrap()
                    .len()
            });
            let mut scratch = Scratch::default();
            let (tr, nr) = run(&mut |s| {
                reference_halfspaces(s, cobst.reaches(), &mut scratch)
                    .unwrap()
                    .len()
            });
            assert_eq!(nf, nr);
            println!(
                "rep {rep}: updates {:.1} ms, fast {:.1} ms ({:.1}× updates), reference {:.1} ms ({:.1}× updates): fast/reference {:.3}",
                tu * 1e3,
                tf * 1e3,
                tf / tu,
                tr * 1e3,
                tr / tu,
                tf / tr
            );
        }
        let _ = Pose::IDENTITY;
    }
}
