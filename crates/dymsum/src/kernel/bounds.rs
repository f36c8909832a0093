//! Certified error bounds of the float filters, in one place.
//!
//! Every combinatorial decision is a sign. A filter evaluates the expression
//! in floats from approximations of its inputs, each known within a
//! Euclidean error bound, and returns the value together with a bound on its
//! distance from the exact value; the caller takes the sign only when the
//! value clears the bound ([`super::Sign::certified`]) and otherwise asks the
//! exact stage. The bounds follow the standard model of floating-point
//! arithmetic (`|fl(a ∘ b) − a ∘ b| ≤ u |a ∘ b|`, `u = 2⁻⁵³`) with a 1%
//! margin for the rounding of the bound itself; a non-finite value or bound
//! is returned as an infinite bound, so it never decides.
//!
//! Used by the kernel's tie-breaking stage (`predicates`), the overlay's arc
//! tests and structural ties (`gauss`) and the certification of
//! persistent ties in DYMSUM (`dynamic::ties`), the determinant filter of
//! the predicates (`det3`) and the bound of a rotated normal (`rotated`).
//! The double-double second stage keeps its own bound beside its
//! arithmetic (`predicates::det3_refined`); DYMSUM's margins add a fixed
//! slack to float distances instead (`dynamic::margins`).

use glam::DVec3;

/// The unit roundoff `2⁻⁵³`.
pub(crate) const U: f64 = f64::EPSILON / 2.0;
/// `√3`: `|x|₂ ≤ √3 |x|∞`.
const SQRT3: f64 = 1.7320508075688774;

/// The 2×2 minor `u[c0] w[c1] − u[c1] w[c0]` of two approximate vectors
/// (errors `eu`, `ew`) and a bound on its error: each product is off by at
/// most `e_u |w| + |u| e_w` from the inputs, twice, plus its rounding.
#[inline]
pub(crate) fn minor(u: DVec3, eu: f64, w: DVec3, ew: f64, c0: usize, c1: usize) -> (f64, f64) {
    let d = u[c0] * w[c1] - u[c1] * w[c0];
    let (mu, mw) = (u[c0].abs().max(u[c1].abs()), w[c0].abs().max(w[c1].abs()));
    let bound = 1.01 * (2.0 * (eu * (mw + ew) + mu * ew) + 8.0 * U * mu * mw) + f64::MIN_POSITIVE;
    finite(d, bound)
}

/// The dot product `m · x` of two approximate vectors (errors `em`, `ex`)
/// and a bound on its error: `e_m |x| + |m| e_x` from the inputs, plus the
/// rounding of three products and two sums.
#[inline]
pub(crate) fn dot(m: DVec3, em: f64, x: DVec3, ex: f64) -> (f64, f64) {
    let v = m.dot(x);
    let mm = m.abs().max_element() * SQRT3;
    let xm = x.abs().max_element() * SQRT3;
    finite(v, 1.01 * (em * (xm + ex) + mm * ex + 6.0 * U * mm * xm))
}

/// The determinant `det[x, y, z] = x · (y × z)` of three approximate
/// vectors (errors `e`) and a bound on its error: from the inputs,
/// `e_x |y| |z|  +  |x'| e_y |z|  +  |x'| |y'| e_z` (with
/// `|x'| ≤ |x| + e_x`), plus the rounding of the products and the sums. Not passed through the
/// non-finite guard: the determinant of normals in `[0.5, 1)` never
/// overflows, and the exact stage takes over whenever this does not decide.
#[inline]
pub(crate) fn det3([x, y, z]: [DVec3; 3], [ex, ey, ez]: [f64; 3]) -> (f64, f64) {
    let det = x.dot(y.cross(z));
    let (mx, my, mz) = (
        x.abs().max_element(),
        y.abs().max_element(),
        z.abs().max_element(),
    );
    let (nx, ny, nz) = (SQRT3 * mx + ex, SQRT3 * my + ey, SQRT3 * mz + ez);
    let input = ex * ny * nz + nx * ey * nz + nx * ny * ez;
    let rounding = 8.0 * U * 6.0 * mx * my * mz;
    (det, 1.01 * (input + rounding))
}

/// Error bound of a float vector rotated by a (nearly orthogonal) float
/// matrix taken as exact, relative to the exact product of that matrix and
/// the exact vector: the input's bound (scaled by the matrix's norm, at
/// most `1.01`) plus the rounding of three products and two sums per row.
#[inline]
pub(crate) fn rotated(err: f64, approx: DVec3) -> f64 {
    1.01 * err + 8.0 * f64::EPSILON * approx.abs().max_element() * SQRT3
}

#[inline]
fn finite(v: f64, bound: f64) -> (f64, f64) {
    if v.is_finite() && bound.is_finite() {
        (v, bound)
    } else {
        (v, f64::INFINITY)
    }
}

/// Rounds a computed non-negative length up past its rounding error.
#[inline]
pub(crate) fn up(x: f64) -> f64 {
    x * (1.0 + 8.0 * f64::EPSILON)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::Sign;

    #[test]
    fn bounds_cover_the_rounding_of_inexact_inputs() {
        // 0.1 is not exact: the float minor of (0.1, 0.3) and (0.3, 0.9) is
        // not exactly zero, but within the bound; an exact zero input gives
        // exactly zero.
        let (d, b) = minor(
            DVec3::new(0.1, 0.3, 0.0),
            0.0,
            DVec3::new(0.3, 0.9, 0.0),
            0.0,
            0,
            1,
        );
        assert!(d.abs() <= b);
        let (d, b) = minor(
            DVec3::new(1.0, 2.0, 0.0),
            1e-3,
            DVec3::new(2.0, 1.0, 0.0),
            1e-3,
            0,
            1,
        );
        assert_eq!(Sign::certified(d, b), Some(Sign::Negative));
        let (v, b) = dot(
            DVec3::new(1.0, 0.0, 0.0),
            1e-9,
            DVec3::new(1e-10, 1.0, 0.0),
            0.0,
        );
        assert_eq!(Sign::certified(v, b), None);
        let (_, b) = dot(DVec3::splat(f64::MAX), 0.0, DVec3::splat(f64::MAX), 0.0);
        assert_eq!(b, f64::INFINITY);
    }
}
