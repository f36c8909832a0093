//! The query frame: the two bodies at their poses, their vertices posed on
//! demand in one power-of-two frame, and the error bounds every certificate
//! of the query uses.
//!
//! # The frame
//! Posed vertices are `2^k (R v + t)`, rounded once per component; `k` is
//! chosen from a bound on every posed coordinate, `B = max(reach + |t|∞)`
//! over the two bodies (`reach` the largest `|v|` in the body's own frame),
//! so that `B · 2^k` lies in `[1, 2)`. Scaling both bodies and their
//! translations by `2^j` scales `B` by exactly `2^j`, so frame coordinates,
//! and every answer scaled back, are bit-identical at every scale. Nothing
//! is posed until it is read: a query that visits a few dozen vertices of
//! two large hulls poses a few dozen, not all of them.
//!
//! # The bounds
//! * `tol`, the tie tolerance: `16 ε B` in frame units. Candidates whose
//!   support values lie within `tol` of each other are tied
//!   ([`crate::query::proximity::certificate::candidates::winner`]).
//! * `eta_a`, `eta_b`: the Euclidean distance between a rounded posed
//!   vertex and its exact value `R v + t` (with the float matrix `R` taken
//!   as exact) is at most `16 ε (reach + |t|∞)` (three products and three
//!   sums per component, each off by at most half an ulp of the component's
//!   magnitude, `√3` for the norm), in frame units.
//! * `rho_a`, `rho_b`: every vertex lies within `rho` of the body's vertex
//!   mean (rounded up; rotation preserves it up to the matrix's rounding,
//!   covered by a factor `1 + 2^-40`).
//!
//! These are the only quantities the certificates of [`crate::query::proximity::certificate`]
//! need about the rounding; they are rigorous upper bounds.

use crate::gauss::{GaussView, Turn};
use crate::kernel::dd::DD;
use crate::kernel::exact::{frame_exponent, mul_pow2, mul_pow2_vec};
use crate::kernel::rotation::Pose;
use crate::kernel::rotation::Rotation;
use crate::polytope::Polytope;
use crate::query::error::QueryError;
use crate::query::pair::ConvexPair;
use crate::query::prep::Reflected;
use crate::sum::{relative_rotation, turn_of};
use glam::{DMat3, DVec3};
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering::Relaxed};

pub(in crate::query) use crate::kernel::bounds::up;

/// Values computed on first read in a query and kept for the rest of it:
/// a value is current when its stamp equals the query's generation.
/// Relaxed atomics rather than `Cell`s, so that the structures holding a
/// query's scratch stay `Sync`; they compile to plain loads and stores.
#[derive(Debug, Default)]
struct Lazy {
    slots: Vec<Slot>,
}

/// One lazily computed vector and the generation it was computed in, side
/// by side (one bounds check and one cache line a read).
#[derive(Debug, Default)]
struct Slot {
    stamp: AtomicU32,
    vals: [AtomicU64; 3],
}

impl Clone for Lazy {
    fn clone(&self) -> Self {
        Lazy {
            slots: self
                .slots
                .iter()
                .map(|s| Slot {
                    stamp: AtomicU32::new(s.stamp.load(Relaxed)),
                    vals: s.vals.each_ref().map(|x| AtomicU64::new(x.load(Relaxed))),
                })
                .collect(),
        }
    }
}

impl Lazy {
    /// Sizes the buffers for `n` values; `clear` forgets every value (the
    /// generation counter wrapped). Values of an earlier query, of this
    /// pair or another, carry older stamps and are recomputed.
    fn reset(&mut self, n: usize, clear: bool) {
        if self.slots.len() != n {
            self.slots = (0..n).map(|_| Slot::default()).collect();
        } else if clear {
            self.slots.iter_mut().for_each(|s| *s.stamp.get_mut() = 0);
        }
    }

    /// The value of slot `i`, computed by `f` unless this generation has.
    /// The read is inlined at every caller; the computation is not.
    #[inline(always)]
    fn get(&self, i: usize, gen: u32, f: impl FnOnce() -> DVec3) -> DVec3 {
        let slot = &self.slots[i];
        if slot.stamp.load(Relaxed) == gen {
            DVec3::new(
                f64::from_bits(slot.vals[0].load(Relaxed)),
                f64::from_bits(slot.vals[1].load(Relaxed)),
                f64::from_bits(slot.vals[2].load(Relaxed)),
            )
        } else {
            Self::fill(slot, gen, f)
        }
    }

    #[inline(never)]
    fn fill(slot: &Slot, gen: u32, f: impl FnOnce() -> DVec3) -> DVec3 {
        let x = f();
        slot.vals[0].store(x.x.to_bits(), Relaxed);
        slot.vals[1].store(x.y.to_bits(), Relaxed);
        slot.vals[2].store(x.z.to_bits(), Relaxed);
        slot.stamp.store(gen, Relaxed);
        x
    }
}

/// The two bodies at their poses, in the query's frame (module docs).
/// Reused from query to query (a [`crate::query::tracker::ContactTracker`] keeps one), so a
/// query allocates nothing once the buffers have their size.
#[derive(Clone, Debug, Default)]
pub(in crate::query) struct Posed {
    a_body: Option<Polytope>,
    b_body: Option<Polytope>,
    /// A's pose.
    pub pose_a: Pose,
    /// B's pose.
    pub pose_b: Pose,
    /// The frame's exponent: frame coordinates are world ones times `2^k`.
    pub k: i32,
    /// The tie tolerance, `16 ε B` (frame units).
    pub tol: f64,
    /// Bound on `|posed coordinate|` (frame units, `< 2` unless the bound
    /// overflowed and the frame was taken from the coordinates).
    pub scale: f64,
    /// Bounds on the rounding of one posed vertex of A and of B (Euclidean,
    /// frame units).
    pub eta_a: f64,
    /// See `eta_a`.
    pub eta_b: f64,
    /// Every vertex of A (of B) lies within `rho_a` (`rho_b`) of one point
    /// (frame units).
    pub rho_a: f64,
    /// See `rho_a`.
    pub rho_b: f64,
    /// The relative rotation of A in the combinatorial frame of `−B`
    /// (`R_b⁻¹ R_a`), as the overlay sees it; `None` for the identity.
    pub turn: Option<Turn>,
    /// B's rotation matrix (the combinatorial frame to the world).
    pub rot_b: DMat3,

    gen: u32,
    a: Lazy,
    b: Lazy,
    na: Lazy,
    nb: Lazy,
}

impl Posed {
    /// Sets the bodies and poses for a new query.
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when a posed coordinate overflows `f64`.
    pub(in crate::query) fn reset(
        &mut self,
        pair: &ConvexPair,
        pose_a: Pose,
        pose_b: Pose,
    ) -> Result<(), QueryError> {
        if !self.a_body.as_ref().is_some_and(|p| p.same_data(&pair.a)) {
            self.a_body = Some(pair.a.clone());
        }
        if !self.b_body.as_ref().is_some_and(|p| p.same_data(&pair.b)) {
            self.b_body = Some(pair.b.clone());
        }
        self.gen = self.gen.wrapping_add(1);
        let wrapped = self.gen == 0;
        if wrapped {
            self.gen = 1;
        }
        self.a.reset(pair.a.vertex_count(), wrapped);
        self.b.reset(pair.b.vertex_count(), wrapped);
        self.na.reset(pair.a.face_count(), wrapped);
        self.nb.reset(pair.b.face_count(), wrapped);
        self.pose_a = pose_a;
        self.pose_b = pose_b;
        let relative = relative_rotation(&pose_a, &Reflected::pose(pose_b));
        self.turn = (relative != Rotation::IDENTITY).then(|| turn_of(relative));

        self.rot_b = pose_b.rotation.matrix();
        let (ba, bb) = (&pair.prep_a.bounds, &pair.prep_b.bounds);
        let (ta, tb) = (
            pose_a.translation.abs().max_element(),
            pose_b.translation.abs().max_element(),
        );
        let bound_a = up(ba.reach + ta);
        let bound_b = up(bb.reach + tb);
        let bound = bound_a.max(bound_b);
        if !pose_a.translation.is_finite() || !pose_b.translation.is_finite() {
            return Err(out_of_range());
        }
        let (k, bound) = if bound.is_finite() && bound < 1e300 {
            (frame_exponent(std::iter::once(bound)), bound)
        } else {
            // The bound overflows: take the frame from the coordinates
            // themselves (posing every vertex once).
            let mut m = 0.0f64;
            for (p, pose) in [(&pair.a, pose_a), (&pair.b, pose_b)] {
                for &v in p.vertices() {
                    let x = pose.apply(v);
                    if !x.is_finite() {
                        return Err(out_of_range());
                    }
                    m = m.max(x.abs().max_element());
                }
            }
            (frame_exponent(std::iter::once(m)), m)
        };
        self.k = k;
        self.scale = mul_pow2(bound, k);
        self.tol = 16.0 * f64::EPSILON * self.scale.max(f64::MIN_POSITIVE);
        self.eta_a = mul_pow2(16.0 * f64::EPSILON * bound_a, k);
        self.eta_b = mul_pow2(16.0 * f64::EPSILON * bound_b, k);
        let turned = 1.0 + 2f64.powi(-40);
        self.rho_a = mul_pow2(ba.radius * turned, k);
        self.rho_b = mul_pow2(bb.radius * turned, k);
        Ok(())
    }

    /// A's Gaussian map at its relative rotation, exactly as the static
    /// and dynamic overlays of `A ⊕ (−B)` see it (the same rotated normals,
    /// arc normals, error bounds and SoS indices, so every predicate
    /// answers the same), without a tie memo.
    pub(in crate::query) fn view_a<'a>(&'a self, pair: &'a ConvexPair) -> GaussView<'a> {
        let a = &pair.a;
        GaussView {
            poly: a,
            normals: a.normals(),
            arcs: a.arc_normals(),
            turn: self.turn.as_ref(),
            arc_errs: &pair.prep_a.arc_err,
            base: 0,
            rotation: self.turn.as_ref().map(|t| &t.rot),
            ties: None,
        }
    }

    /// `−B`'s Gaussian map (its own frame; SoS indices after A's faces).
    pub(in crate::query) fn view_neg_b<'a>(&self, pair: &'a ConvexPair) -> GaussView<'a> {
        let q = &pair.neg_b().polytope;
        GaussView {
            poly: q,
            normals: q.normals(),
            arcs: q.arc_normals(),
            turn: None,
            arc_errs: q.arc_errors(),
            base: pair.a.face_count() as u32,
            rotation: None,
            ties: None,
        }
    }

    /// Body A.
    #[inline]
    fn body_a(&self) -> &Polytope {
        self.a_body.as_ref().expect("reset before use")
    }

    /// Body B.
    #[inline]
    fn body_b(&self) -> &Polytope {
        self.b_body.as_ref().expect("reset before use")
    }

    /// Posed vertex `v` of A (frame units).
    #[inline]
    pub(in crate::query) fn a(&self, v: u32) -> DVec3 {
        self.a.get(v as usize, self.gen, || {
            mul_pow2_vec(self.pose_a.apply(self.body_a().vertex(v as usize)), self.k)
        })
    }

    /// Posed vertex `w` of B (frame units).
    #[inline]
    pub(in crate::query) fn b(&self, w: u32) -> DVec3 {
        self.b.get(w as usize, self.gen, || {
            mul_pow2_vec(self.pose_b.apply(self.body_b().vertex(w as usize)), self.k)
        })
    }

    /// A's rotated unit normal of face `f`.
    #[inline]
    pub(in crate::query) fn na(&self, f: u32) -> DVec3 {
        self.na.get(f as usize, self.gen, || {
            self.pose_a
                .rotation
                .apply(self.body_a().unit_normal(f as usize))
        })
    }

    /// B's rotated unit normal of face `g`.
    #[inline]
    pub(in crate::query) fn nb(&self, g: u32) -> DVec3 {
        self.nb.get(g as usize, self.gen, || {
            self.pose_b
                .rotation
                .apply(self.body_b().unit_normal(g as usize))
        })
    }

    /// A world length or point back from frame units.
    #[inline]
    pub(in crate::query) fn back(&self, x: f64) -> f64 {
        mul_pow2(x, -self.k)
    }

    /// A world point back from frame units.
    #[inline]
    pub(in crate::query) fn back_vec(&self, v: DVec3) -> DVec3 {
        mul_pow2_vec(v, -self.k)
    }
}

/// `cof(M)` with `cof(M)(a × b) = (M a) × (M b)`, row by row
/// (`[row][column]`), in double-double: its columns are
/// `c1 × c2`, `c2 × c0`, `c0 × c1` for the columns `c_i` of `M`; each entry
/// a difference of two products, exact to double-double rounding.
pub(in crate::query) fn cofactor_dd(m: &DMat3) -> [[DD; 3]; 3] {
    let (c0, c1, c2) = (m.x_axis, m.y_axis, m.z_axis);
    let cross = |a: DVec3, b: DVec3| {
        let d =
            |p: f64, q: f64, r: f64, s: f64| DD::from(p) * DD::from(q) - DD::from(r) * DD::from(s);
        [
            d(a.y, b.z, a.z, b.y),
            d(a.z, b.x, a.x, b.z),
            d(a.x, b.y, a.y, b.x),
        ]
    };
    let cols = [cross(c1, c2), cross(c2, c0), cross(c0, c1)];
    let mut out = [[DD::default(); 3]; 3];
    for (j, col) in cols.iter().enumerate() {
        for (r, &x) in col.iter().enumerate() {
            out[r][j] = x;
        }
    }
    out
}

fn out_of_range() -> QueryError {
    QueryError::OutOfRange("the posed coordinates overflow f64 (|x| > 1.8e308)".into())
}
