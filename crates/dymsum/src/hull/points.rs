//! Point sets for the hull: plain float points, and the m×n pairwise sums
//! of two float point sets with an exact orientation predicate.
//!
//! # Exactness
//!
//! [`FloatPoints`] uses [`crate::kernel::predicates::orient`] (Shewchuk's
//! adaptive `orient3d`) on the coordinates themselves.
//!
//! [`PairwiseSums`] represents the point `p[i] + q[j]` *exactly*, although
//! the float sum is rounded. Its predicates work on the exact differences
//! `(p_b − p_a) + (q_b − q_a)` in three stages:
//!
//! 1. a float filter: the determinant of the rounded differences together
//!    with a rigorous (deliberately generous) forward error bound; the sign
//!    is returned when the value exceeds the bound;
//! 2. if every difference was computed without rounding (checked with
//!    Knuth's error-free `TwoSum`) and lies in a safe exponent range, the
//!    differences are exact floats and Shewchuk's adaptive predicate on them
//!    is exact;
//! 3. otherwise an exact evaluation in allocation-free dyadic arithmetic
//!    ([`crate::kernel::exact::Dyadic`]): every finite `f64` is `m · 2^e`
//!    with an integer `m`, so the determinant is exact.
//!
//! All coordinates must be finite (callers check); the predicates are exact
//! for all finite inputs.

use super::HullPoints;
use crate::kernel::exact::{self, Dyadic, ExactVec};
use crate::kernel::predicates::{det2, orient};
use crate::kernel::Sign;
use glam::DVec3;

/// Plain float points; the hull predicates are exact on the coordinates.
///
/// Coordinates must be finite; the predicates are then exact at any scale
/// ([`orient`] normalises exponents by a power of two, or falls back to
/// exact dyadic arithmetic).
#[derive(Clone, Copy, Debug)]
pub struct FloatPoints<'a>(pub &'a [DVec3]);

impl HullPoints for FloatPoints<'_> {
    #[inline]
    fn len(&self) -> usize {
        self.0.len()
    }
    #[inline]
    fn coords(&self, i: usize) -> DVec3 {
        self.0[i]
    }
    #[inline]
    fn orient(&self, a: usize, b: usize, c: usize, d: usize) -> Sign {
        orient(self.0[a], self.0[b], self.0[c], self.0[d])
    }
}

/// Exactly whether three float points lie on one line (also `true` when two
/// of them coincide): the three components of `(b − a) × (c − a)` are the
/// 2-D orientations of the projections on the coordinate planes, each
/// evaluated exactly.
pub(crate) fn collinear_floats(a: DVec3, b: DVec3, c: DVec3) -> bool {
    use crate::kernel::predicates::orient2;
    let o = |i: usize, j: usize| orient2([a[i], a[j]], [b[i], b[j]], [c[i], c[j]]);
    o(0, 1) == Sign::Zero && o(1, 2) == Sign::Zero && o(2, 0) == Sign::Zero
}

/// The m×n pairwise sums `p[i] + q[j]` of two float point sets (the candidate
/// vertices of the Minkowski sum `conv(p) ⊕ conv(q)`), with exact predicates
/// on the real (unrounded) sums.
///
/// Point index `k` is `p[k / q.len()] + q[k % q.len()]`; see
/// [`PairwiseSums::index`] and [`PairwiseSums::split`]. All coordinates must
/// be finite (callers check); every predicate is then exact.
#[derive(Clone, Copy, Debug)]
pub struct PairwiseSums<'a> {
    /// The first point set (`m` points).
    pub p: &'a [DVec3],
    /// The second point set (`n` points).
    pub q: &'a [DVec3],
}

/// Unit roundoff bound used by the filters (`2^-52`, twice the unit roundoff).
const EPS: f64 = f64::EPSILON;
/// Absolute slack covering underflow in the filter's float evaluation.
const TINY: f64 = 1e-290;
/// Components of exactly computed differences must lie within
/// `[MIN_SAFE, MAX_SAFE]` (or be zero) for the adaptive predicates to be
/// exact: products of up to three such values neither overflow nor underflow.
const MIN_SAFE: f64 = 1e-90;
const MAX_SAFE: f64 = 1e90;

/// Knuth's TwoSum: `s = fl(a + b)` and whether `s` is exact.
#[inline]
fn sum_is_exact(a: f64, b: f64, s: f64) -> bool {
    let bb = s - a;
    let err = (a - (s - bb)) + (b - bb);
    err == 0.0
}

#[inline]
fn safe(x: f64) -> bool {
    let a = x.abs();
    a == 0.0 || (MIN_SAFE..=MAX_SAFE).contains(&a)
}

/// Permanent-style bound `|x| · (|y| ⊗ |z|)` for non-negative vectors:
/// the sum of the absolute values of the six terms of `det[x, y, z]`.
#[inline]
fn perm(x: DVec3, y: DVec3, z: DVec3) -> f64 {
    x.x * (y.y * z.z + y.z * z.y) + x.y * (y.z * z.x + y.x * z.z) + x.z * (y.x * z.y + y.y * z.x)
}

/// A float difference of two sums with a rigorous componentwise bound on its
/// error, and whether it is exact.
#[derive(Clone, Copy)]
struct Diff {
    /// The rounded difference `fl(fl(p_b − p_a) + fl(q_b − q_a))`.
    v: DVec3,
    /// Componentwise bound on `|v − exact|`.
    err: DVec3,
    /// `true` when `v` is the exact difference (all three roundings exact)
    /// and all components are in the safe range.
    exact: bool,
}

/// Exact values `vals[k][0] − vals[k][1] + vals[k][2] − vals[k][3]` for the
/// three components `k`.
fn exact_row(vals: [[f64; 4]; 3]) -> ExactVec {
    vals.map(|c| {
        let d = |x: f64| Dyadic::from_f64(x);
        d(c[0]).sub(&d(c[1])).add(&d(c[2]).sub(&d(c[3])))
    })
}

impl<'a> PairwiseSums<'a> {
    /// The pairwise sums of `p` and `q`.
    pub fn new(p: &'a [DVec3], q: &'a [DVec3]) -> Self {
        PairwiseSums { p, q }
    }

    /// The point index of `p[i] + q[j]`.
    #[inline]
    pub fn index(&self, i: usize, j: usize) -> usize {
        i * self.q.len() + j
    }

    /// The pair `(i, j)` of point index `k`, the inverse of [`Self::index`].
    #[inline]
    pub fn split(&self, k: usize) -> (usize, usize) {
        let n = self.q.len();
        (k / n, k % n)
    }

    /// The four float values whose combination `p_b − p_a + q_b − q_a` is
    /// component `c` of the exact difference `b − a`.
    #[inline]
    fn terms(&self, a: usize, b: usize) -> [[f64; 4]; 3] {
        let (ia, ja) = self.split(a);
        let (ib, jb) = self.split(b);
        let (pa, pb, qa, qb) = (self.p[ia], self.p[ib], self.q[ja], self.q[jb]);
        [
            [pb.x, pa.x, qb.x, qa.x],
            [pb.y, pa.y, qb.y, qa.y],
            [pb.z, pa.z, qb.z, qa.z],
        ]
    }

    /// The float difference `b − a` with an error bound.
    #[inline]
    fn diff(&self, a: usize, b: usize) -> Diff {
        let (ia, ja) = self.split(a);
        let (ib, jb) = self.split(b);
        let (pa, pb, qa, qb) = (self.p[ia], self.p[ib], self.q[ja], self.q[jb]);
        let dp = pb - pa;
        let dq = qb - qa;
        let v = dp + dq;
        // |fl(x ∘ y) − (x ∘ y)| ≤ u/(1−u)·|fl(x ∘ y)| for u = 2^-53, so the
        // total error is below (u/(1−u))·(|dp| + |dq| + |v|) < EPS/2·(...).
        // EPS (twice that) also covers the rounding of this expression.
        let err = (dp.abs() + dq.abs() + v.abs()) * EPS;
        Diff {
            v,
            err,
            exact: false,
        }
    }

    /// [`Self::diff`] plus the check whether the difference is exact.
    #[inline]
    fn diff_checked(&self, a: usize, b: usize) -> Diff {
        let (ia, ja) = self.split(a);
        let (ib, jb) = self.split(b);
        let (pa, pb, qa, qb) = (self.p[ia], self.p[ib], self.q[ja], self.q[jb]);
        let dp = pb - pa;
        let dq = qb - qa;
        let v = dp + dq;
        let mut exact = true;
        for k in 0..3 {
            exact &= sum_is_exact(pb[k], -pa[k], dp[k])
                && sum_is_exact(qb[k], -qa[k], dq[k])
                && sum_is_exact(dp[k], dq[k], v[k])
                && safe(v[k]);
        }
        let err = (dp.abs() + dq.abs() + v.abs()) * EPS;
        Diff { v, err, exact }
    }

    #[cold]
    #[inline(never)]
    fn orient_slow(&self, a: usize, b: usize, c: usize, d: usize) -> Sign {
        let u = self.diff_checked(a, b);
        let v = self.diff_checked(a, c);
        let w = self.diff_checked(a, d);
        if u.exact && v.exact && w.exact {
            // det[u, v, w] = orient3d(0, u, v, w); subtracting 0 is exact.
            return orient(DVec3::ZERO, u.v, v.v, w.v);
        }
        let u = exact_row(self.terms(a, b));
        let v = exact_row(self.terms(a, c));
        let w = exact_row(self.terms(a, d));
        exact::det3(&u, &v, &w).sign()
    }
}

impl HullPoints for PairwiseSums<'_> {
    #[inline]
    fn len(&self) -> usize {
        self.p.len() * self.q.len()
    }

    #[inline]
    fn coords(&self, k: usize) -> DVec3 {
        let (i, j) = self.split(k);
        self.p[i] + self.q[j]
    }

    /// Exact sign of `det[b − a, c − a, d − a]` for the real sums.
    #[inline]
    fn orient(&self, a: usize, b: usize, c: usize, d: usize) -> Sign {
        let u = self.diff(a, b);
        let v = self.diff(a, c);
        let w = self.diff(a, d);
        let det = u.v.dot(v.v.cross(w.v));
        // Bound on |det[U, V, W] − det[u, v, w]| with U = u + δu etc.:
        // det(δu, V, W) + det(u, δv, W) + det(u, v, δw), each bounded by the
        // permanent of absolute values; plus the rounding of the float
        // determinant itself (≤ 6u·perm, taken as 8·EPS·perm = 16u·perm).
        let (au, av, aw) = (u.v.abs(), v.v.abs(), w.v.abs());
        let (bv, bw) = (av + v.err, aw + w.err);
        let bound = (8.0 * EPS * perm(au, av, aw)
            + perm(u.err, bv, bw)
            + perm(au, v.err, bw)
            + perm(au, av, w.err))
            * (1.0 + 64.0 * EPS)
            + TINY;
        if det > bound {
            Sign::Positive
        } else if -det > bound {
            Sign::Negative
        } else {
            self.orient_slow(a, b, c, d)
        }
    }

    fn coincident(&self, a: usize, b: usize) -> bool {
        let (ia, ja) = self.split(a);
        let (ib, jb) = self.split(b);
        if ia == ib && ja == jb {
            return true;
        }
        let d = self.diff_checked(a, b);
        if d.exact {
            return d.v == DVec3::ZERO;
        }
        exact_row(self.terms(a, b)).iter().all(|x| x.is_zero())
    }

    fn collinear(&self, a: usize, b: usize, c: usize) -> bool {
        let u = self.diff_checked(a, b);
        let v = self.diff_checked(a, c);
        if u.exact && v.exact {
            let (u, v) = (u.v, v.v);
            return det2(u.y, u.z, v.y, v.z) == Sign::Zero
                && det2(u.z, u.x, v.z, v.x) == Sign::Zero
                && det2(u.x, u.y, v.x, v.y) == Sign::Zero;
        }
        let u = exact_row(self.terms(a, b));
        let v = exact_row(self.terms(a, c));
        exact::cross(&u, &v).iter().all(|x| x.is_zero())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn index_split_roundtrip() {
        let p = [DVec3::ZERO; 3];
        let q = [DVec3::ONE; 5];
        let s = PairwiseSums::new(&p, &q);
        assert_eq!(s.len(), 15);
        for i in 0..3 {
            for j in 0..5 {
                assert_eq!(s.split(s.index(i, j)), (i, j));
            }
        }
    }

    #[test]
    fn decompose_is_exact() {
        use crate::kernel::exact::decompose;
        for x in [0.0, -0.0, 1.0, -0.1, 1e300, 5e-324, -2.5e-310, 1e6 + 0.1] {
            let (m, e) = decompose(x);
            assert_eq!(m as f64 * 2f64.powi(e), x);
        }
    }

    #[test]
    fn parallelogram_exactly_planar() {
        // Sums p_i + q_j with awkward floats: the four sums p0+q0, p1+q0,
        // p0+q1, p1+q1 form an exact parallelogram although the float sums
        // are rounded.
        let p = [DVec3::new(0.1, 0.7, 1e6 + 0.1), DVec3::new(0.3, 1e-6, 0.2)];
        let q = [DVec3::new(1e6 + 0.3, 0.1, 0.3), DVec3::new(0.7, 1e-7, 1e6)];
        let s = PairwiseSums::new(&p, &q);
        let (a, b, c, d) = (s.index(0, 0), s.index(1, 0), s.index(0, 1), s.index(1, 1));
        assert_eq!(s.orient(a, b, c, d), Sign::Zero);
        assert_eq!(s.orient(d, c, b, a), Sign::Zero);
        assert!(!s.collinear(a, b, c));
        assert!(s.collinear(a, b, a));
        assert!(!s.coincident(a, d));
    }

    #[test]
    fn hidden_coincidence_and_collinearity() {
        // Different pairs with the same real sum: 0.1 + 0.2 vs 0.2 + 0.1.
        let p = [DVec3::splat(0.1), DVec3::splat(0.2), DVec3::splat(1e300)];
        let q = [DVec3::splat(0.2), DVec3::splat(0.1), DVec3::splat(-1e300)];
        let s = PairwiseSums::new(&p, &q);
        assert!(s.coincident(s.index(0, 0), s.index(1, 1)));
        assert!(s.coincident(s.index(2, 2), s.index(2, 2)));
        // 0.1+0.2, 0.2+0.2, and 1e300-1e300 = 0 lie on the diagonal line.
        assert!(s.collinear(s.index(0, 0), s.index(1, 0), s.index(2, 2)));
        assert!(!s.coincident(s.index(0, 0), s.index(2, 2)));
    }

    #[test]
    fn filter_agrees_with_exact_dyadics() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        // Awkward magnitudes; the last points form exact parallelograms.
        let mut r = |s: f64| {
            DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            ) * s
        };
        let p: Vec<DVec3> = [1e6, 1e-6, 1.0, 1e6, 0.1]
            .iter()
            .map(|&s| r(s) + DVec3::splat(s))
            .collect();
        let q: Vec<DVec3> = [1e-6, 1e6, 1.0, 0.3, 1e-3]
            .iter()
            .map(|&s| r(s) - DVec3::splat(s))
            .collect();
        let s = PairwiseSums::new(&p, &q);
        let n = s.len();
        let big = |a: usize, b: usize, c: usize, d: usize| {
            let u = exact_row(s.terms(a, b));
            let v = exact_row(s.terms(a, c));
            let w = exact_row(s.terms(a, d));
            exact::det3(&u, &v, &w).sign()
        };
        let mut zeros = 0;
        for a in (0..n).step_by(3) {
            for b in (0..n).step_by(4) {
                for c in (0..n).step_by(2) {
                    for d in 0..n {
                        let e = big(a, b, c, d);
                        assert_eq!(s.orient(a, b, c, d), e, "{a} {b} {c} {d}");
                        zeros += (e == Sign::Zero) as usize;
                    }
                }
            }
        }
        assert!(zeros > 0);
    }

    #[test]
    fn orient_matches_float_points_on_exact_inputs() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        // Small integers: float sums are exact, so both predicates agree.
        let mut r = || {
            DVec3::new(
                rng.random_range(-4..=4) as f64,
                rng.random_range(-4..=4) as f64,
                rng.random_range(-4..=4) as f64,
            )
        };
        let p: Vec<DVec3> = (0..6).map(|_| r()).collect();
        let q: Vec<DVec3> = (0..6).map(|_| r()).collect();
        let s = PairwiseSums::new(&p, &q);
        let sums: Vec<DVec3> = (0..s.len()).map(|k| s.coords(k)).collect();
        let f = FloatPoints(&sums);
        let mut zeros = 0;
        for a in (0..36).step_by(5) {
            for b in (1..36).step_by(7) {
                for c in (2..36).step_by(3) {
                    for d in 0..36 {
                        let e = f.orient(a, b, c, d);
                        assert_eq!(s.orient(a, b, c, d), e);
                        zeros += (e == Sign::Zero) as usize;
                    }
                }
            }
        }
        assert!(zeros > 0);
    }
}
