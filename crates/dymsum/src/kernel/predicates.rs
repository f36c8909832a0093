//! Exact geometric predicates on `f64` input.
//!
//! All predicates return the exact sign of a polynomial in their float
//! inputs, computed with Shewchuk's adaptive-precision arithmetic (the
//! `robust` crate). Floats are used only to build inputs; never to decide.
//!
//! # Directions with exact values
//!
//! Gaussian-map predicates take [`ExactVector`]s: a float approximation with a
//! certified error bound, and the exact value on demand. A face normal is the
//! cross product of two exact vertex differences (times a float rotation
//! matrix taken as exact), so it is *not* a float; the filter decides from
//! the approximation when the error bound allows and otherwise evaluates
//! exactly with `super::exact::Dyadic` arithmetic. So "a normal lies exactly
//! on an arc" or "two faces are exactly parallel" is decided on the true
//! geometry, never on rounded normals.
//!
//! # Symbolic perturbation
//!
//! [`sos_det3`] implements Simulation of Simplicity (Edelsbrunner and Mücke,
//! ACM TOG 1990) for the 3×3 determinant `det[a, b, c]` of three direction
//! vectors, each carrying a global index. Entry `(i, k)` of vector `i` is
//! perturbed by `ε^(2^(3i + 2 − k))`; the sign of the perturbed determinant is
//! the sign of the first non-vanishing coefficient of its expansion in `ε`,
//! ordered by increasing exponent. The expansion has 34 terms: the determinant
//! itself, nine cofactors (exact 2×2 determinants), eighteen single entries and
//! six constants `±1`, so the result is never zero when the three indices
//! differ. The sign of every term is invariant under positive scaling of a
//! vector, so scaled normals perturb consistently. Every cross-map decision of
//! the Minkowski sum algorithms uses it, so all algorithms see one and the
//! same generic configuration.

use super::dd::{self, DDVec, DD};
use super::exact::{float, ExactVec};
use glam::DVec3;
use robust::{Coord, Coord3D};
use std::sync::OnceLock;

/// The sign of a determinant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    /// Strictly negative.
    Negative,
    /// Exactly zero.
    Zero,
    /// Strictly positive.
    Positive,
}

impl Sign {
    /// The sign of a float (`Zero` only for ±0).
    #[inline]
    pub fn of(x: f64) -> Sign {
        if x > 0.0 {
            Sign::Positive
        } else if x < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }
    /// The opposite sign.
    #[inline]
    pub fn flip(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }
    /// The sign of `value` if `|value| > bound` (a certified error bound),
    /// else `None`: the filters' one decision rule.
    #[inline]
    pub fn certified(value: f64, bound: f64) -> Option<Sign> {
        if value > bound {
            Some(Sign::Positive)
        } else if -value > bound {
            Some(Sign::Negative)
        } else {
            None
        }
    }
    /// `true` for `Positive`.
    #[inline]
    pub fn is_positive(self) -> bool {
        self == Sign::Positive
    }
    /// `true` for `Negative`.
    #[inline]
    pub fn is_negative(self) -> bool {
        self == Sign::Negative
    }
}

/// A point as `robust`'s coordinate type.
#[inline]
pub(crate) fn coord3d(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// Where Shewchuk's adaptive predicates are exact: every intermediate value
/// of a degree-`n` predicate must neither overflow nor underflow inexactly.
///
/// Inputs whose non-zero magnitudes lie in `[fast_min, fast_max]` are safe
/// as they are (checked with a few comparisons). Otherwise the inputs are
/// scaled by one power of two so that every top exponent is at most `top`
/// and every lowest set bit at least `low`: then every product of `n`
/// differences is a multiple of `2^(n·low) ≥ 2^-1074` (so even subnormal
/// intermediate values are exact) and below `2^(n·(top+1)) ≤ 2^960` (no
/// overflow, also in Dekker's splitting). Scaling all inputs by a positive
/// power of two does not change the sign. When no shift fits (the inputs
/// span more bits than `top − low`), the sign is evaluated with exact
/// dyadic arithmetic instead, so the predicates are exact for **every**
/// finite input.
struct ShewchukRange {
    fast_min: f64,
    fast_max: f64,
    low: i32,
    top: i32,
}

/// `orient3d` (degree 3): `3 · (−358) ≥ −1074`, `3 · 320 = 960`.
const ORIENT3_RANGE: ShewchukRange = ShewchukRange {
    fast_min: 4.909093465297727e-91, // 2^-300 (lowest bit ≥ 2^-352)
    fast_max: 2.13598703592091e96,   // 2^320
    low: -358,
    top: 319,
};

/// `orient2d` (degree 2): `2 · (−537) = −1074`, `2 · 480 = 960`.
const ORIENT2_RANGE: ShewchukRange = ShewchukRange {
    fast_min: 1.2813331809171846e-144, // 2^-478 (lowest bit ≥ 2^-530)
    fast_max: 3.1217485503159922e144,  // 2^480
    low: -537,
    top: 479,
};

impl ShewchukRange {
    /// `true` when every value is zero or within `[fast_min, fast_max]`.
    #[inline]
    fn fast(&self, xs: &[f64]) -> bool {
        xs.iter().all(|x| {
            let a = x.abs();
            a <= self.fast_max && (a >= self.fast_min || a == 0.0)
        })
    }

    /// Scales `xs` by one power of two into the safe range; `false` (and
    /// `xs` unchanged) when their exponents span too much for any shift.
    fn fit(&self, xs: &mut [f64]) -> bool {
        let Some((top, low)) = super::exact::exponent_range(xs.iter().copied()) else {
            return true; // all zero
        };
        let (lo, hi) = (self.low - low, self.top - top);
        if lo > hi {
            return false;
        }
        let shift = 0.clamp(lo, hi);
        for x in xs.iter_mut() {
            *x = super::exact::mul_pow2(*x, shift);
        }
        true
    }
}

/// Exact orientation of `d` relative to the plane through `a`, `b`, `c`:
/// `Positive` when `d` lies on the side from which `a, b, c` appear
/// counter-clockwise ("above"), i.e. the sign of `det[b − a, c − a, d − a]`.
///
/// Exact for every finite input, at any scale: Shewchuk's adaptive
/// `orient3d` where its arithmetic is exact (directly for magnitudes in
/// `[2^-300, 2^320]` or zero, else after scaling all twelve coordinates by
/// one power of two), exact dyadic arithmetic when the coordinates of one
/// call span more than about 670 bits. So scaling all inputs by `2^k`
/// never changes the answer.
#[inline]
pub fn orient(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
    let xs = [a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, d.x, d.y, d.z];
    if ORIENT3_RANGE.fast(&xs) {
        // robust::orient3d is positive when d is *below* the ccw plane.
        return Sign::of(-robust::orient3d(
            coord3d(a),
            coord3d(b),
            coord3d(c),
            coord3d(d),
        ));
    }
    orient_wide(xs)
}

#[cold]
#[inline(never)]
fn orient_wide(mut xs: [f64; 12]) -> Sign {
    let p = |xs: &[f64; 12], i: usize| DVec3::new(xs[3 * i], xs[3 * i + 1], xs[3 * i + 2]);
    if ORIENT3_RANGE.fit(&mut xs) {
        let (a, b, c, d) = (p(&xs, 0), p(&xs, 1), p(&xs, 2), p(&xs, 3));
        return Sign::of(-robust::orient3d(
            coord3d(a),
            coord3d(b),
            coord3d(c),
            coord3d(d),
        ));
    }
    let (a, b, c, d) = (p(&xs, 0), p(&xs, 1), p(&xs, 2), p(&xs, 3));
    let e = super::exact::sub;
    super::exact::det3(&e(b, a), &e(c, a), &e(d, a)).sign()
}

/// Exact sign of the 2-D orientation `(a − c) × (b − c)`:
/// `Positive` when `a, b, c` turn counter-clockwise. Exact for every finite
/// input, like [`orient`].
#[inline]
pub fn orient2(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Sign {
    let xs = [a[0], a[1], b[0], b[1], c[0], c[1]];
    if ORIENT2_RANGE.fast(&xs) {
        return Sign::of(robust::orient2d(coord2d(a), coord2d(b), coord2d(c)));
    }
    orient2_wide(xs)
}

#[inline]
fn coord2d(p: [f64; 2]) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}

#[cold]
#[inline(never)]
fn orient2_wide(mut xs: [f64; 6]) -> Sign {
    if ORIENT2_RANGE.fit(&mut xs) {
        let (a, b, c) = ([xs[0], xs[1]], [xs[2], xs[3]], [xs[4], xs[5]]);
        return Sign::of(robust::orient2d(coord2d(a), coord2d(b), coord2d(c)));
    }
    use super::exact::Dyadic;
    let d = Dyadic::from_f64;
    let (ax, ay) = (d(xs[0]).sub(&d(xs[4])), d(xs[1]).sub(&d(xs[5])));
    let (bx, by) = (d(xs[2]).sub(&d(xs[4])), d(xs[3]).sub(&d(xs[5])));
    super::exact::det2(&ax, &ay, &bx, &by).sign()
}

/// A direction known exactly, with a float approximation for fast filters.
pub trait ExactVector {
    /// Float approximation.
    fn approx(&self) -> DVec3;
    /// Upper bound on the Euclidean distance between `approx()` and the
    /// exact value.
    fn error(&self) -> f64;
    /// Global index for symbolic perturbation.
    fn index(&self) -> u32;
    /// The exact value.
    fn exact(&self) -> ExactVec;
    /// A double-double approximation of the exact value and a bound on its
    /// Euclidean error (of order `u²` times its size).
    fn refined(&self) -> (DDVec, f64);
    /// The exact value when it is a float vector obtainable without
    /// rounding (then the cheap exact stage decides), else `None`.
    fn exact_float(&self) -> Option<DVec3> {
        None
    }
    /// The components whose exact value is a float obtainable without
    /// rounding (a subset of what [`ExactVector::exact_float`] gives: a
    /// rotated normal may have an exactly zero component although the
    /// others are not floats).
    fn exact_components(&self) -> [Option<f64>; 3] {
        match self.exact_float() {
            Some(v) => [Some(v.x), Some(v.y), Some(v.z)],
            None => [None; 3],
        }
    }
    /// Components known to be exactly zero without any arithmetic (bit `k`
    /// for component `k`): a subset of the zeros of
    /// [`ExactVector::exact_components`] (a rotated normal may report only
    /// the components that are zero by the structure of the rotation
    /// matrix). Together with `error() == 0` (then `approx()` is exact), this
    /// is where the tie-breaking stage starts; it asks for
    /// [`ExactVector::exact_components`] only when that does not suffice.
    fn zero_mask(&self) -> u8 {
        let c = self.exact_components();
        (0..3).fold(0, |m, k| m | u8::from(c[k] == Some(0.0)) << k)
    }
}

/// A float vector taken as exact (error 0), with an SoS index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plain(pub DVec3, pub u32);

impl ExactVector for Plain {
    #[inline]
    fn approx(&self) -> DVec3 {
        self.0
    }
    #[inline]
    fn error(&self) -> f64 {
        0.0
    }
    #[inline]
    fn index(&self) -> u32 {
        self.1
    }
    fn exact(&self) -> ExactVec {
        super::exact::exact(self.0)
    }
    fn refined(&self) -> (DDVec, f64) {
        (
            [DD::from(self.0.x), DD::from(self.0.y), DD::from(self.0.z)],
            0.0,
        )
    }
    #[inline]
    fn exact_float(&self) -> Option<DVec3> {
        Some(self.0)
    }
}

const U: f64 = f64::EPSILON / 2.0;

/// Float determinant and a bound on its distance from the exact one
/// ([`super::bounds::det3`]).
#[inline]
fn det3_filter<V: ExactVector>(a: &V, b: &V, c: &V) -> (f64, f64) {
    super::bounds::det3(
        [a.approx(), b.approx(), c.approx()],
        [a.error(), b.error(), c.error()],
    )
}

/// Exact sign of `det[a, b, c] = (a × b) · c` (no perturbation: `Zero` on
/// exact degeneracy). `Positive` when `a, b, c` turn counter-clockwise seen
/// from outside the unit sphere (directions within an open hemisphere).
#[inline]
pub fn det3<V: ExactVector>(a: &V, b: &V, c: &V) -> Sign {
    let (det, bound) = det3_filter(a, b, c);
    Sign::certified(det, bound).unwrap_or_else(|| det3_exact(a, b, c))
}

/// Second stage: the determinant of the double-double normals, with a
/// certified bound. `None` when even that cannot decide.
fn det3_refined<V: ExactVector>(a: &V, b: &V, c: &V) -> Option<Sign> {
    let ((x, ex), (y, ey), (z, ez)) = (a.refined(), b.refined(), c.refined());
    let det = dd::dot(&dd::cross(&x, &y), &z);
    let m = |v: &DDVec| {
        v.iter().map(|d| d.abs_hi()).fold(0.0, f64::max) * 1.7320508075688774 * (1.0 + 1e-15)
    };
    let (nx, ny, nz) = (m(&x) + ex, m(&y) + ey, m(&z) + ez);
    let input = ex * ny * nz + nx * ey * nz + nx * ny * ez;
    let rounding = 64.0 * U * U * nx * ny * nz;
    let bound = 1.01 * (input + rounding) + f64::MIN_POSITIVE;
    Sign::certified(det.hi + det.lo, bound)
}

/// What the cheap exact stage knows about three vectors: approximations,
/// error bounds, and the components known exactly as floats.
struct Known {
    approx: [DVec3; 3],
    err: [f64; 3],
    exact: [[Option<f64>; 3]; 3],
    /// Bit `3r + k` set when entry `(r, k)` is known to be exactly zero.
    zeros: u16,
}

impl Known {
    fn of<V: ExactVector>(v: [&V; 3]) -> Known {
        Known::with(
            v,
            [
                v[0].exact_components(),
                v[1].exact_components(),
                v[2].exact_components(),
            ],
        )
    }

    /// What is known without arithmetic: exact rows (error bound zero) and
    /// the zeros of [`ExactVector::zero_mask`].
    fn cheap<V: ExactVector>(v: [&V; 3]) -> Known {
        let row = |x: &V| {
            let (a, m) = (x.approx(), x.zero_mask());
            if x.error() == 0.0 {
                [Some(a.x), Some(a.y), Some(a.z)]
            } else {
                [0, 1, 2].map(|k| (m >> k & 1 != 0).then_some(0.0))
            }
        };
        Known::with(v, [row(v[0]), row(v[1]), row(v[2])])
    }

    #[inline]
    fn with<V: ExactVector>(v: [&V; 3], exact: [[Option<f64>; 3]; 3]) -> Known {
        let mut zeros = 0;
        for (r, row) in exact.iter().enumerate() {
            for (k, x) in row.iter().enumerate() {
                if *x == Some(0.0) {
                    zeros |= 1 << (3 * r + k);
                }
            }
        }
        Known {
            approx: [v[0].approx(), v[1].approx(), v[2].approx()],
            err: [v[0].error(), v[1].error(), v[2].error()],
            exact,
            zeros,
        }
    }

    /// `true` when every term of the Leibniz expansion
    /// `Σ_σ sgn σ · A[0][σ0] A[1][σ1] A[2][σ2]` has an exactly zero factor,
    /// so the determinant is exactly zero by the zero pattern alone (a
    /// column of zeros, two rows supported on one coordinate, a normal on an
    /// arc whose cross product vanishes where the normal does not).
    #[inline]
    fn zero_by_pattern(&self) -> bool {
        // The entries (r, σ(r)) of each permutation σ, as bit masks.
        const fn term(p: [usize; 3]) -> u16 {
            1 << p[0] | 1 << (3 + p[1]) | 1 << (6 + p[2])
        }
        const TERMS: [u16; 6] = [
            term([0, 1, 2]),
            term([0, 2, 1]),
            term([1, 0, 2]),
            term([1, 2, 0]),
            term([2, 0, 1]),
            term([2, 1, 0]),
        ];
        TERMS.iter().all(|&t| self.zeros & t != 0)
    }

    /// The exact sign of entry `(r, k)`, when known cheaply.
    #[inline]
    fn entry_sign(&self, r: usize, k: usize) -> Option<Sign> {
        match self.exact[r][k] {
            Some(x) => Some(Sign::of(x)),
            None => Sign::certified(self.approx[r][k], self.err[r]),
        }
    }

    #[inline]
    fn is_zero(&self, r: usize, k: usize) -> bool {
        self.zeros >> (3 * r + k) & 1 != 0
    }

    /// Row `r` as an exact float vector, if all its components are known.
    #[inline]
    fn row(&self, r: usize) -> Option<DVec3> {
        let [x, y, z] = self.exact[r];
        Some(DVec3::new(x?, y?, z?))
    }

    /// The exact sign of the 2×2 minor `A[r0][c0] A[r1][c1] − A[r0][c1] A[r1][c0]`
    /// when it can be decided cheaply.
    fn minor_sign(&self, r0: usize, r1: usize, c0: usize, c1: usize) -> Option<Sign> {
        let x_zero = self.is_zero(r0, c0) || self.is_zero(r1, c1);
        let y_zero = self.is_zero(r0, c1) || self.is_zero(r1, c0);
        let prod = |p: Option<Sign>, q: Option<Sign>| -> Option<Sign> {
            Some(match (p?, q?) {
                (Sign::Zero, _) | (_, Sign::Zero) => Sign::Zero,
                (a, b) if a == b => Sign::Positive,
                _ => Sign::Negative,
            })
        };
        match (x_zero, y_zero) {
            (true, true) => return Some(Sign::Zero),
            (true, false) => {
                return prod(self.entry_sign(r0, c1), self.entry_sign(r1, c0)).map(Sign::flip)
            }
            (false, true) => return prod(self.entry_sign(r0, c0), self.entry_sign(r1, c1)),
            _ => {}
        }
        if let (Some(p0), Some(q1), Some(p1), Some(q0)) = (
            self.exact[r0][c0],
            self.exact[r1][c1],
            self.exact[r0][c1],
            self.exact[r1][c0],
        ) {
            if let Some(d) = float::det2(p0, p1, q0, q1) {
                return Some(Sign::of(d));
            }
        }
        // Float filter on the approximations.
        let (d, bound) = super::bounds::minor(
            self.approx[r0],
            self.err[r0],
            self.approx[r1],
            self.err[r1],
            c0,
            c1,
        );
        Sign::certified(d, bound)
    }

    /// `Some(Zero)` when the determinant is exactly zero for a structural
    /// reason seen cheaply (a column of exact zeros, two exactly parallel
    /// float rows), or its sign when all entries are floats and it
    /// evaluates exactly.
    fn det_sign(&self) -> Option<Sign> {
        if (0..3).any(|k| (0..3).all(|r| self.is_zero(r, k))) {
            return Some(Sign::Zero);
        }
        let rows = [self.row(0), self.row(1), self.row(2)];
        if let [Some(x), Some(y), Some(z)] = rows {
            if let Some(d) = float::det3(x, y, z) {
                return Some(Sign::of(d));
            }
        }
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            if let (Some(x), Some(y)) = (rows[i], rows[j]) {
                if float::cross(x, y) == Some(DVec3::ZERO) {
                    return Some(Sign::Zero);
                }
            }
        }
        None
    }
}

#[cold]
fn det3_exact<V: ExactVector>(a: &V, b: &V, c: &V) -> Sign {
    det3_exact_known(a, b, c, &Known::of([a, b, c]))
}

fn det3_exact_known<V: ExactVector>(a: &V, b: &V, c: &V, k: &Known) -> Sign {
    // Cheap exact stage: exact ties of simple geometry (parallel faces, all
    // normals in one coordinate plane) end here without multi-limb work.
    if let Some(s) = k.det_sign() {
        return s;
    }
    if let Some(s) = det3_refined(a, b, c) {
        return s;
    }
    super::exact::det3(&a.exact(), &b.exact(), &c.exact()).sign()
}

/// `true` when `a` and `b` point in exactly the same direction (positive
/// multiples of each other), decided exactly.
pub fn same_direction<V: ExactVector>(a: &V, b: &V) -> bool {
    let (x, y) = (a.approx(), b.approx());
    let cr = x.cross(y);
    let (mx, my) = (
        x.abs().max_element() * 1.7320508075688774,
        y.abs().max_element() * 1.7320508075688774,
    );
    let bound =
        1.01 * (a.error() * (my + b.error()) + (mx + a.error()) * b.error() + 4.0 * U * mx * my);
    if cr.abs().max_element() > bound || x.dot(y) < -bound {
        return false;
    }
    if let (Some(x), Some(y)) = (a.exact_float(), b.exact_float()) {
        if let (Some(c), Some(d)) = (float::cross(x, y), float::dot(x, y)) {
            return c == DVec3::ZERO && d > 0.0;
        }
    }
    let (ea, eb) = (a.exact(), b.exact());
    let c = super::exact::cross(&ea, &eb);
    if c.iter().any(|d| d.sign() != Sign::Zero) {
        return false;
    }
    super::exact::dot(&ea, &eb).sign() == Sign::Positive
}

/// Exact sign of the 2×2 determinant `p.0 * q.1 − p.1 * q.0` (exact for
/// every finite input, see [`orient2`]).
#[inline]
pub fn det2(p0: f64, p1: f64, q0: f64, q1: f64) -> Sign {
    orient2([p0, p1], [q0, q1], [0.0, 0.0])
}

/// Exact sign of the dot product `a · b` of two 4-vectors (quaternions),
/// for every finite input: a float filter (the sum of the four products
/// with a bound on its rounding and on underflow), else exact dyadic
/// arithmetic. Decides the arc of a motion (`query::motion`), where the
/// dot product of two nearly opposite rotations can be a few ulps.
///
/// ```
/// use dymsum::kernel::predicates::{dot4, Sign};
/// assert_eq!(dot4([1.0, 0.0, 0.0, 0.0], [-8.6e-15, 0.0, 0.0, 1.0]), Sign::Negative);
/// assert_eq!(dot4([1.0, 0.0, 0.0, 0.0], [-0.0, 0.0, 0.0, 1.0]), Sign::Zero);
/// assert_eq!(dot4([1e-300, 1.0, 0.0, 0.0], [1e-300, -1e-300, 0.0, 0.0]), Sign::Negative);
/// ```
pub fn dot4(a: [f64; 4], b: [f64; 4]) -> Sign {
    let mut sum = 0.0;
    let mut magnitude = 0.0;
    for k in 0..4 {
        let p = a[k] * b[k];
        sum += p;
        magnitude += p.abs();
    }
    // Each product and each of the three additions rounds by at most ε/2
    // relative (γ₄ < 4.5 ε overall), and each product may underflow by at
    // most 2⁻¹⁰⁷⁴; a non-finite magnitude (overflow) goes the exact way.
    let bound = 4.5 * f64::EPSILON * magnitude + 8.0 * f64::from_bits(1);
    if magnitude.is_finite() {
        if let Some(s) = Sign::certified(sum, bound) {
            return s;
        }
    }
    use super::exact::Dyadic;
    let mut exact = Dyadic::zero();
    for k in 0..4 {
        if a[k] != 0.0 && b[k] != 0.0 {
            exact = exact.add(&Dyadic::from_f64(a[k]).mul(&Dyadic::from_f64(b[k])));
        }
    }
    exact.sign()
}

/// One term of the SoS expansion of a 3×3 determinant.
#[derive(Clone, Copy, Debug)]
pub(crate) enum SosTerm {
    /// The cofactor of entry (row, col): the signed 2×2 minor.
    Cofactor { row: u8, col: u8 },
    /// `sign * A[row][col]`.
    Entry { row: u8, col: u8, sign: i8 },
    /// A constant `±1`.
    Constant(i8),
}

fn perm_sign(p: [usize; 3]) -> i8 {
    let mut s = 1;
    for i in 0..3 {
        for j in i + 1..3 {
            if p[i] > p[j] {
                s = -s;
            }
        }
    }
    s
}

/// Number of SoS terms: 9 cofactors, 18 entries, 6 constants.
pub(crate) const SOS_TERMS: usize = 9 + 18 + 6;

/// The 33 perturbation terms in decreasing order of significance (computed
/// once, without allocation).
pub(crate) fn sos_terms() -> &'static [SosTerm; SOS_TERMS] {
    static TERMS: OnceLock<[SosTerm; SOS_TERMS]> = OnceLock::new();
    TERMS.get_or_init(|| {
        // Bit of the perturbation exponent of entry (row, col): row-major with
        // z (col 2) the most significant within a row.
        let bit = |r: usize, c: usize| 3 * r + (2 - c);
        let mut terms = [(0u32, SosTerm::Constant(1)); SOS_TERMS];
        let mut n = 0;
        let perms: [[usize; 3]; 6] = [
            [0, 1, 2],
            [0, 2, 1],
            [1, 0, 2],
            [1, 2, 0],
            [2, 0, 1],
            [2, 1, 0],
        ];
        // Single perturbations: coefficient is the cofactor.
        for r in 0..3 {
            for c in 0..3 {
                terms[n] = (
                    1 << bit(r, c),
                    SosTerm::Cofactor {
                        row: r as u8,
                        col: c as u8,
                    },
                );
                n += 1;
            }
        }
        // Pairs: rows r1 < r2 perturbed at columns of a permutation sigma; the
        // coefficient is sgn(sigma) * A[r3][sigma(r3)].
        for p in perms {
            for skip in 0..3 {
                let exp = (0..3)
                    .filter(|&r| r != skip)
                    .map(|r| 1u32 << bit(r, p[r]))
                    .sum();
                terms[n] = (
                    exp,
                    SosTerm::Entry {
                        row: skip as u8,
                        col: p[skip] as u8,
                        sign: perm_sign(p),
                    },
                );
                n += 1;
            }
            let exp = (0..3).map(|r| 1u32 << bit(r, p[r])).sum();
            terms[n] = (exp, SosTerm::Constant(perm_sign(p)));
            n += 1;
        }
        debug_assert_eq!(n, SOS_TERMS);
        // Distinct exponents by construction (distinct bit sets).
        terms.sort_unstable_by_key(|t| t.0);
        debug_assert!(terms.windows(2).all(|w| w[0].0 < w[1].0));
        terms.map(|t| t.1)
    })
}

/// The rows and columns other than `i`.
#[inline]
pub(crate) fn others(i: usize) -> [usize; 2] {
    match i {
        0 => [1, 2],
        1 => [0, 2],
        _ => [0, 1],
    }
}

/// Sign of `det[a, b, c]` under Simulation of Simplicity, with the vectors'
/// global indices (all distinct). Never `Zero` for distinct indices; equals
/// [`det3`] whenever that is non-zero.
#[inline]
pub fn sos_det3<V: ExactVector>(a: &V, b: &V, c: &V) -> Sign {
    let (det, bound) = det3_filter(a, b, c);
    Sign::certified(det, bound).unwrap_or_else(|| sos_slow(a, b, c))
}

/// [`sos_det3`] without its float filter, for callers whose own filter
/// (say, against a precomputed arc normal) has just failed.
#[cold]
pub(crate) fn sos_det3_unfiltered<V: ExactVector>(a: &V, b: &V, c: &V) -> Sign {
    sos_slow(a, b, c)
}

#[cold]
fn sos_slow<V: ExactVector>(a: &V, b: &V, c: &V) -> Sign {
    let (ia, ib, ic) = (a.index(), b.index(), c.index());
    debug_assert!(
        ia != ib && ib != ic && ia != ic,
        "SoS needs distinct indices"
    );
    // Sort rows by index; an odd permutation flips the sign.
    let mut order = [(ia, 0usize), (ib, 1), (ic, 2)];
    let mut flips = 0;
    for i in 0..3 {
        for j in 0..2 - i {
            if order[j].0 > order[j + 1].0 {
                order.swap(j, j + 1);
                flips += 1;
            }
        }
    }
    let vs = [a, b, c];
    let [v0, v1, v2] = order.map(|(_, k)| vs[k]);
    // Exact ties of simple geometry (parallel faces, normals on arcs under a
    // rotation about a coordinate axis) are zero by their zero pattern: the
    // perturbation terms then start from what is known without arithmetic.
    let cheap = Known::cheap([v0, v1, v2]);
    let known = if cheap.zero_by_pattern() {
        cheap
    } else {
        Known::of([v0, v1, v2])
    };
    let s = if known.zero_by_pattern() {
        Sign::Zero
    } else {
        det3_exact_known(v0, v1, v2, &known)
    };
    if s != Sign::Zero {
        return if flips % 2 == 1 { s.flip() } else { s };
    }
    // The exact matrix, computed only if the cheap stage cannot decide.
    let mut exact: Option<[ExactVec; 3]> = None;
    let mut result = Sign::Zero;
    for t in sos_terms() {
        let s = match *t {
            SosTerm::Cofactor { row, col } => {
                let (row, col) = (row as usize, col as usize);
                let [r0, r1] = others(row);
                let [c0, c1] = others(col);
                let s = match known.minor_sign(r0, r1, c0, c1) {
                    Some(s) => s,
                    None => {
                        let m = exact.get_or_insert_with(|| [v0.exact(), v1.exact(), v2.exact()]);
                        super::exact::det2(&m[r0][c0], &m[r0][c1], &m[r1][c0], &m[r1][c1]).sign()
                    }
                };
                if (row + col) % 2 == 1 {
                    s.flip()
                } else {
                    s
                }
            }
            SosTerm::Entry { row, col, sign } => {
                let (row, col) = (row as usize, col as usize);
                let v = match known.entry_sign(row, col) {
                    Some(s) => s,
                    None => {
                        let m = exact.get_or_insert_with(|| [v0.exact(), v1.exact(), v2.exact()]);
                        m[row][col].sign()
                    }
                };
                if sign < 0 {
                    v.flip()
                } else {
                    v
                }
            }
            SosTerm::Constant(sign) => {
                if sign < 0 {
                    Sign::Negative
                } else {
                    Sign::Positive
                }
            }
        };
        if s != Sign::Zero {
            result = s;
            break;
        }
    }
    if flips % 2 == 1 {
        result.flip()
    } else {
        result
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64, z: f64, i: u32) -> Plain {
        Plain(DVec3::new(x, y, z), i)
    }

    #[test]
    fn orient_convention() {
        let o = DVec3::ZERO;
        let x = DVec3::X;
        let y = DVec3::Y;
        assert_eq!(orient(o, x, y, DVec3::Z), Sign::Positive);
        assert_eq!(orient(o, x, y, -DVec3::Z), Sign::Negative);
        assert_eq!(orient(o, x, y, DVec3::new(3.0, 4.0, 0.0)), Sign::Zero);
    }

    #[test]
    fn det3_matches_cross_dot() {
        let (x, y, z) = (p(1., 0., 0., 0), p(0., 1., 0., 1), p(0., 0., 1., 2));
        assert_eq!(det3(&x, &y, &z), Sign::Positive);
        assert_eq!(det3(&y, &x, &z), Sign::Negative);
        assert_eq!(det3(&x, &y, &x), Sign::Zero);
        // A case where naive float evaluation is wrong: exactly 1e-34 > 0.
        let a = p(1.0, 1e-17, 0.0, 0);
        let b = p(1.0, 0.0, 1e-17, 1);
        let c = p(1.0, 0.0, 0.0, 2);
        assert_eq!(det3(&a, &b, &c), Sign::Positive);
    }

    #[test]
    fn sos_is_antisymmetric_and_nonzero() {
        let a = p(1., 0., 0., 0);
        let b = p(1., 1., 0., 1);
        let c = p(0., 1., 0., 2);
        // coplanar: det = 0
        let s = sos_det3(&a, &b, &c);
        assert_ne!(s, Sign::Zero);
        assert_eq!(sos_det3(&b, &a, &c), s.flip());
        assert_eq!(sos_det3(&a, &c, &b), s.flip());
        assert_eq!(sos_det3(&c, &a, &b), s);
        // identical vectors with distinct indices
        let (a5, a3, a9) = (p(1., 0., 0., 5), p(1., 0., 0., 3), p(1., 0., 0., 9));
        let s2 = sos_det3(&a5, &a3, &a9);
        assert_ne!(s2, Sign::Zero);
        assert_eq!(sos_det3(&a3, &a5, &a9), s2.flip());
        assert_eq!(sos_terms().len(), 9 + 18 + 6);
        // invariant under positive scaling of a vector
        let b2 = p(2., 2., 0., 1);
        assert_eq!(sos_det3(&a, &b2, &c), s);
    }

    #[test]
    fn range_constants_are_powers_of_two() {
        assert_eq!(ORIENT3_RANGE.fast_min, 2f64.powi(-300));
        assert_eq!(ORIENT3_RANGE.fast_max, 2f64.powi(320));
        assert_eq!(ORIENT2_RANGE.fast_min, 2f64.powi(-478));
        assert_eq!(ORIENT2_RANGE.fast_max, 2f64.powi(480));
    }

    /// `orient` and `orient2` against exact dyadic evaluation on points
    /// with awkward mantissas scaled by powers of two from `2^-1074` to
    /// `2^990`: one common scale (the fast and the scaled Shewchuk paths)
    /// and independent scales per point (up to the dyadic fallback).
    #[test]
    fn orient_is_exact_at_every_scale() {
        use super::super::exact::{self, mul_pow2};
        let mut s = 99u64;
        let mut next = |m: u64| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 33) % m
        };
        let mut seen = [0usize; 3];
        for round in 0..6000 {
            let common = round % 2 == 0;
            let ints = round % 4 == 0;
            let base = next(1960) as i32 - 1000;
            let mut pt = |i: usize| {
                let k = if common {
                    base
                } else {
                    next(1960) as i32 - 1000
                };
                // Small integers (exact ties) or full 53-bit mantissas.
                let c = |x: u64| {
                    let v = if ints {
                        (x % 3) as f64 - 1.0
                    } else if i.is_multiple_of(2) {
                        (x % 7) as f64 - 3.0
                    } else {
                        x as f64 / 7.0
                    };
                    mul_pow2(v, k.max(-1070))
                };
                DVec3::new(c(next(1 << 30)), c(next(1 << 30)), c(next(1 << 30)))
            };
            let (a, b, c, d) = (pt(0), pt(1), pt(2), pt(3));
            let e = exact::sub;
            let want = exact::det3(&e(b, a), &e(c, a), &e(d, a)).sign();
            assert_eq!(orient(a, b, c, d), want, "{a:?} {b:?} {c:?} {d:?}");
            seen[(want as usize).min(2)] += 1;
            // 2-D: the projection on (x, y).
            let d2 = |p: DVec3, q: DVec3| {
                [
                    exact::Dyadic::from_f64(p.x).sub(&exact::Dyadic::from_f64(q.x)),
                    exact::Dyadic::from_f64(p.y).sub(&exact::Dyadic::from_f64(q.y)),
                ]
            };
            let (u, v) = (d2(a, c), d2(b, c));
            let want2 = exact::det2(&u[0], &u[1], &v[0], &v[1]).sign();
            assert_eq!(orient2([a.x, a.y], [b.x, b.y], [c.x, c.y]), want2);
        }
        // Both signs and exact zeros occurred.
        assert!(seen.iter().all(|&n| n > 100), "{seen:?}");
    }

    #[test]
    fn unit_cube_orientation_at_extreme_scales() {
        for k in [-1074, -1050, -600, -300, -110, 0, 150, 320, 500, 1000, 1023] {
            let s = super::super::exact::mul_pow2(1.0, k);
            let (o, x, y, z) = (DVec3::ZERO, DVec3::X * s, DVec3::Y * s, DVec3::Z * s);
            assert_eq!(orient(o, x, y, z), Sign::Positive, "2^{k}");
            assert_eq!(orient(o, x, y, -z), Sign::Negative, "2^{k}");
            assert_eq!(orient(o, x, y, x + y), Sign::Zero, "2^{k}");
            assert_eq!(
                orient2([0.0, 0.0], [s, 0.0], [0.0, s]),
                Sign::Positive,
                "2^{k}"
            );
        }
        // Mixed scales in one call (the dyadic fallback): 1e300 and 1e-300.
        let (big, tiny) = (1e300, 1e-300);
        let (o, x, y) = (DVec3::ZERO, DVec3::X * big, DVec3::Y * big);
        assert_eq!(orient(o, x, y, DVec3::Z * tiny), Sign::Positive);
        assert_eq!(orient(o, x, y, DVec3::new(tiny, tiny, 0.0)), Sign::Zero);
    }

    #[test]
    fn same_direction_exact() {
        assert!(same_direction(&p(1.0, 2.0, 3.0, 0), &p(2.0, 4.0, 6.0, 1)));
        assert!(!same_direction(
            &p(1.0, 2.0, 3.0, 0),
            &p(-2.0, -4.0, -6.0, 1)
        ));
        assert!(!same_direction(
            &p(1.0, 2.0, 3.0, 0),
            &p(2.0, 4.0, 6.000000000000001, 1)
        ));
    }
}
