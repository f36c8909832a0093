//! C-obstacle slices as half-spaces, read straight from the facets of the
//! dynamic sum: no mesh is built.
//!
//! A slice `S = O ⊕ (−R·A)` is `{x : n_i·x ≤ d_i}` over its faces. The
//! faces are the groups of coplanar facets of the sum (the exact
//! coplanarity test of the mesh merge, `sum::merge`: parallel faces,
//! normals on arcs; degenerate parallelograms are dropped), one plane per
//! group. Its normal is the float unit normal of the group's first facet: a
//! face normal of P or Q turned by its pose when the group holds an
//! fv- or vf-facet, else the normalised cross product of the posed edges of
//! the ee-facet.
//!
//! **The offsets are rounded outward.** The mesh of a slice
//! ([`DynamicSum::try_to_mesh`]) has the vertices `fl(p' + q')` with `p'`,
//! `q'` the rounded posed vertices of the two operands. For a normal `n`,
//! `max n·p'` and `max n·q'` are bounded from above rigorously by the
//! near-extreme search of `query::support` (hill climbing from the facet's
//! own vertices, then every vertex within the float dot products' error
//! bound of the best), and `d = up_P + up_Q + 2|n|₁·u·(s_P + s_Q) + err`
//! (`s` the coordinates' magnitudes, `err` one dot product's rounding),
//! every sum rounded up. So every vertex `x` of the slice's mesh satisfies
//! `n·x ≤ d` both exactly and in floats: the region is never smaller than
//! the mesh. Each plane touches the slice: `d` exceeds the largest `n·x` by
//! a few units of rounding of the coordinates.
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

use super::frame::{up, BodyBounds};
use super::support::{dot_error, near_max, Marks};
use super::{CObstacle, QueryError};
use crate::polytope::Polytope;
use crate::sum::merge::coplanar_groups;
use crate::sum::{Operands, Overlay};
use crate::{DVec3, DynamicSum, Rotation};

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
    /// The normals and offsets, consumed.
    pub fn into_parts(self) -> (Vec<DVec3>, Vec<f64>) {
        (self.normals, self.offsets)
    }
}

/// The bounds on one posed operand: `scale` its coordinates' magnitude,
/// `eta` the rounding of a posed vertex.
#[derive(Clone, Copy, Debug)]
struct Posed {
    scale: f64,
    eta: f64,
}

impl Posed {
    /// `|R v + t| ≤ r(1 + 2⁻⁴⁰) + |t|`; each coordinate of `fl(R v + t)`
    /// within `√3·u(4.02 r + |t|) < 8u(r + |t|)` of `R v + t` (`query::slabs`).
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
}

/// The largest `|v|` of each body, computed once per pair.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Reaches {
    p: f64,
    q: f64,
}

impl Reaches {
    pub(super) fn of(p: &Polytope, q: &Polytope) -> Reaches {
        Reaches {
            p: BodyBounds::of(p).reach,
            q: BodyBounds::of(q).reach,
        }
    }
}

/// The half-spaces of the sum held by `sum` (module docs).
fn sum_halfspaces(
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
    let (pp, pq) = (&scratch.posed_p, &scratch.posed_q);
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
            let c = (pp[u2 as usize] - pp[u1 as usize])
                .cross(pq[w2 as usize] - pq[w1 as usize])
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
            |v| pp[v as usize],
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
            |v| pq[v as usize],
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
        SCRATCH.with(|c| sum_halfspaces(sum, self.reaches, &mut c.borrow_mut()))
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
        sum_halfspaces(s, self.reaches(), &mut Scratch::default())
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
        let reach = self.reaches();
        let mut scratch = Scratch::default();
        let mut sum = None;
        orientations
            .iter()
            .map(|&r| {
                let s = self.advance(&mut sum, r)?;
                sum_halfspaces(s, reach, &mut scratch)
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
