//! The Gaussian map of a polytope at an orientation ([`GaussView`]) and
//! the overlay of two of them: the exact predicates and local searches
//! shared by every sum method and by the dynamic update. `locate.rs` finds
//! the cell that holds a direction (hill climbing, paper §4.2), `walk.rs`
//! walks an arc of one map through the other (paper §4.3), `ties.rs` settles
//! exact ties once ([`TieCache`]).
//!
//! Paper §3–§4. A face normal `x` of one map lies in the cell of vertex `v`
//! of the other map iff it is strictly left of every arc of that cell
//! ([`GaussView::in_cell`]); two arcs cross iff each separates the other's
//! endpoints and they meet in the right hemisphere ([`edges_cross`]). Both use
//! [`sos_det3`](crate::kernel::predicates::sos_det3) with global indices (faces of P first, then faces of Q), so
//! exact ties — parallel faces, a normal on an arc, overlapping arcs — are
//! broken by one consistent symbolic perturbation and every method sees the
//! same generic overlay.
//!
//! Speed: `det[a, b, x]` for an arc `a → b` is `m · x` with the arc's
//! great-circle normal `m = a × b` precomputed accurately per edge
//! ([`crate::polytope::Polytope::arc_normals`]), so the common case is one dot product
//! and a certified error bound; only near-ties evaluate the exact normals.
//!
//! Exact ties (issue 8 §2: a box turning about a coordinate axis puts every
//! face normal of one box exactly on an arc or a vertex of the other's map,
//! some 80 ties per sum) are settled in three tiers, each exact:
//! 1. a [`TieCache`] shared by both maps of one pair of operands returns a
//!    tie already settled at this relative rotation (each recurs two or
//!    three times per sum);
//! 2. `GaussView::structural_tie` proves the determinant zero from the
//!    zero pattern of the vectors alone (no arithmetic) and reads the
//!    leading perturbation term off the certified arc normal or one
//!    certified 2×2 minor;
//! 3. otherwise the general symbolic perturbation decides.
//!
//! Tiers 1 and 2 are checked against tier 3 on every (arc, normal) pair of
//! axis-aligned, prismatic, slanted and zonotopal parts turning about each
//! axis (`ties::tests::structural_ties_agree_with_symbolic_perturbation`).

mod locate;
mod ties;
mod walk;

pub(crate) use ties::TieCache;

use crate::kernel::bounds;
use crate::kernel::predicates::sos_det3_unfiltered;
use crate::kernel::Sign;
use crate::polytope::{rotated_error, FaceNormal, Polytope, RingEntry};
use glam::{DMat3, DVec3};

/// A polytope's Gaussian map at a given orientation: the polytope, its
/// rotated face normals and arc normals, and the base of its global SoS
/// indices.
#[derive(Clone, Copy)]
pub(crate) struct GaussView<'a> {
    /// The polytope.
    pub poly: &'a Polytope,
    /// Rotated exact-input normals, one per face; with `turn`, the
    /// polytope's own normals, rotated on access.
    pub normals: &'a [DVec3],
    /// Rotated great-circle normals of the edge arcs, one per edge; with
    /// `turn`, the polytope's own arc normals, rotated on access.
    pub arcs: &'a [DVec3],
    /// `Some` when `normals` and `arcs` are unrotated and rotated on access
    /// (lazily: a dynamic sum turns only what it visits).
    pub turn: Option<&'a Turn>,
    /// Error bounds of `arcs`.
    pub arc_errs: &'a [f64],
    /// Global SoS index of face 0.
    pub base: u32,
    /// The rotation taking the polytope's reference normals to `normals`
    /// (`None`: identity, and then `normals` are the polytope's own,
    /// bit for bit), taken as exact.
    pub rotation: Option<&'a DMat3>,
    /// The memo of exact ties shared by both maps of one pair of operands
    /// (`None`: no memo).
    pub ties: Option<&'a TieCache>,
}

/// A rotation `R` applied on access: normals map by `R`, arc normals (cross
/// products of normals) by its cofactor matrix, exactly as
/// [`crate::sum::rotate_arcs`] maps them when it stores them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Turn {
    /// `R`.
    pub rot: DMat3,
    /// `cof(R)`, with `cof(R) (a × b) = (R a) × (R b)`.
    pub cof: DMat3,
}

impl<'a> GaussView<'a> {
    /// Normal of face `f` as an exact predicate argument.
    #[inline]
    pub fn normal(&self, f: u32) -> FaceNormal<'a> {
        let approx = self.n(f);
        let err = self.poly.normal_error(f as usize);
        // Unrotated views hold the polytope's own normals, bit for bit
        // (`FaceNormal::zero_mask` reads exactness off them).
        debug_assert!(self.rotation.is_some() || approx == self.poly.normal(f as usize));
        FaceNormal {
            poly: self.poly,
            face: f,
            approx,
            err: if self.rotation.is_some() {
                rotated_error(err, approx)
            } else {
                err
            },
            idx: self.base + f,
            rotation: self.rotation,
        }
    }

    /// Float approximation of the normal of face `f`.
    #[inline]
    pub fn n(&self, f: u32) -> DVec3 {
        let n = self.normals[f as usize];
        match self.turn {
            Some(t) => t.rot * n,
            None => n,
        }
    }

    /// Float approximation of the (rotated) great-circle normal of the arc
    /// of edge `e`; its error bound is `arc_errs[e]`.
    #[inline]
    pub fn arc(&self, e: u32) -> DVec3 {
        let a = self.arcs[e as usize];
        match self.turn {
            Some(t) => t.cof * a,
            None => a,
        }
    }

    /// The side of `x` relative to the arc of edge `e` (from its left face's
    /// normal to its right face's): the SoS sign of `det[n_left, n_right, x]`.
    #[inline]
    pub fn arc_side(&self, e: u32, x: &FaceNormal<'_>) -> Sign {
        let (m, em) = (self.arc(e), self.arc_errs[e as usize]);
        let (v, bound) = bounds::dot(m, em, x.approx, x.err);
        Sign::certified(v, bound).unwrap_or_else(|| self.tie_side(e, x))
    }

    /// [`GaussView::arc_side`] when the float filter cannot decide: the
    /// exact, perturbed sign, through the tie memo.
    #[cold]
    fn tie_side(&self, e: u32, x: &FaceNormal<'_>) -> Sign {
        let memo = self
            .ties
            .and_then(|t| Some((t, TieCache::key(self.base != 0, e, x.idx)?)));
        if let Some(s) = memo.and_then(|(t, k)| t.get(k)) {
            return s;
        }
        let (a, b) = self.edge_arc(e);
        let s = self
            .structural_tie(e, &a, &b, x)
            .unwrap_or_else(|| sos_det3_unfiltered(&a, &b, x));
        if let Some((t, k)) = memo {
            t.put(k, s);
        }
        s
    }

    /// The perturbed sign of `det[a, b, x]` for the arc `a → b` of edge `e`
    /// when the determinant is exactly zero by the zero pattern of the
    /// vectors (every component of `a × b` or of `x` is structurally zero:
    /// a normal on an arc under a rotation about a coordinate axis, or at
    /// the arc's end) and the leading perturbation terms decide; `None`
    /// otherwise (then the general symbolic perturbation decides).
    ///
    /// With the rows sorted by index `(v0, v1, v2)`, the leading terms of
    /// the perturbed determinant are the cofactors of row 0, i.e. the
    /// components of `v1 × v2` in the order z, y, x
    /// ([`crate::kernel::predicates::sos_det3`]). An arc joins two normals
    /// of one polytope and `x` belongs to the other, so `x` comes first or
    /// last:
    /// * first: `v1 × v2 = ±(a × b)` and the sort's parity cancels the sign,
    ///   so the answer is the sign of the first non-zero component of the
    ///   arc normal, read off its certified float value;
    /// * last: the terms are `b × x` (or `a × x`, with one transposition,
    ///   when `b` sorts first), evaluated with the same zero pattern and a
    ///   certified float filter; if that vanishes (`x` parallel to an end
    ///   of the arc) the general path decides.
    #[inline]
    fn structural_tie(
        &self,
        e: u32,
        a: &FaceNormal<'_>,
        b: &FaceNormal<'_>,
        x: &FaceNormal<'_>,
    ) -> Option<Sign> {
        use crate::kernel::predicates::ExactVector;
        let (za, zb, zx) = (a.zero_mask(), b.zero_mask(), x.zero_mask());
        // Component c of u × w is u_i w_j − u_j w_i, (i, j) cyclic after c.
        let cross_zero = |zu: u8, zw: u8| -> u8 {
            (0..3).fold(0, |m, c| {
                let (i, j) = ((c + 1) % 3, (c + 2) % 3);
                let bit = |z: u8, k: usize| z >> k & 1 != 0;
                let zero = (bit(zu, i) || bit(zw, j)) && (bit(zu, j) || bit(zw, i));
                m | u8::from(zero) << c
            })
        };
        if cross_zero(za, zb) | zx != 0b111 {
            return None;
        }
        if x.idx < a.idx.min(b.idx) {
            let (m, em) = (self.arc(e), self.arc_errs[e as usize]);
            let known_zero = cross_zero(za, zb);
            return [2, 1, 0]
                .into_iter()
                .find(|&c| known_zero >> c & 1 == 0)
                .and_then(|c| Sign::certified(m[c], em));
        }
        if x.idx < a.idx.max(b.idx) {
            return None;
        }
        let (hi, zh, flip) = if a.idx < b.idx {
            (b, zb, false)
        } else {
            (a, za, true)
        };
        let known_zero = cross_zero(zh, zx);
        let (u, w) = (hi.approx, x.approx);
        let (eu, ew) = (hi.err, x.err);
        for c in [2, 1, 0] {
            if known_zero >> c & 1 != 0 {
                continue;
            }
            let (i, j) = ((c + 1) % 3, (c + 2) % 3);
            let (d, bound) = bounds::minor(u, eu, w, ew, i, j);
            let s = Sign::certified(d, bound)?;
            return Some(if flip { s.flip() } else { s });
        }
        None
    }

    /// The side of `x` relative to ring arc `i` of a vertex (from the ring's
    /// `i`-th face to the next): positive means inside the cell.
    #[inline]
    fn ring_side(&self, ring: &[RingEntry], i: usize, x: &FaceNormal<'_>) -> Sign {
        let e = ring[i].edge;
        let s = self.arc_side(e, x);
        if self.poly.edge(e as usize).faces[0] == ring[i].face {
            s
        } else {
            s.flip()
        }
    }

    /// `true` when the direction `x` lies in the cell of vertex `v`
    /// (perturbed, so never on its boundary).
    #[inline]
    pub fn in_cell(&self, v: u32, x: &FaceNormal<'_>) -> bool {
        let ring = self.poly.ring(v as usize);
        (0..ring.len()).all(|i| self.ring_side(ring, i, x).is_positive())
    }

    /// The arc of edge `e`: normals of its left and right faces.
    #[inline]
    pub fn edge_arc(&self, e: u32) -> (FaceNormal<'a>, FaceNormal<'a>) {
        let [f0, f1] = self.poly.edge(e as usize).faces;
        (self.normal(f0), self.normal(f1))
    }
}

/// `true` when the Gaussian arcs of edge `e` of map `x` and edge `e2` of map
/// `y` cross, under symbolic perturbation (so never a touching case): each
/// arc separates the other's endpoints, and `det[a, b, c] = −det[c, d, a]`
/// picks the crossing of the two great circles that lies on both arcs
/// (arcs `a → b` and `c → d`, each shorter than π).
#[inline]
pub fn edges_cross(x: &GaussView<'_>, e: u32, y: &GaussView<'_>, e2: u32) -> bool {
    let (c, d) = y.edge_arc(e2);
    let s1 = x.arc_side(e, &c);
    let s2 = x.arc_side(e, &d);
    if s1 == s2 {
        return false;
    }
    let (a, b) = x.edge_arc(e);
    let s3 = y.arc_side(e2, &a);
    if s3 == s1 {
        return false;
    }
    let s4 = y.arc_side(e2, &b);
    s3 != s4
}
