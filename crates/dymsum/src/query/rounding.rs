//! How far the floating-point poses of a motion are from the exact motion:
//! the one rounding bound both motion searches add to their swept sets
//! ([`crate::query::MotionChecker`] and [`crate::query::SceneChecker`]).
//!
//! # The exact motion and its float poses
//! A motion ([`Motion`](crate::query::Motion)) from `(q₀, t₀)` to `(q₁, t₁)` is exactly
//! `x(t) = R(t) p + T(t)`: `R(t)` the rotation of the slerp, at the constant
//! rate, between the unit quaternions `q₀ = g₀/|g₀|` and `±g₁/|g₁|` (the
//! quaternions as given, the arc decided exactly), and
//! `T(t) = t₀ + (t₁ − t₀) t`. [`Motion::at`](crate::query::Motion::at) computes in floats: `q₀`, `q₁`
//! normalised, the half angle `φ̃ = 2 asin(|q̃₁ − q̃₀|/2)`, the weights
//! `sin((1 − t) φ̃)/sin φ̃`, `sin(t φ̃)/sin φ̃` (below `φ̃ = 1e-9` the plain
//! lerp), the sum normalised; then [`crate::Rotation::from_quat`] snaps
//! components below `1e-14`, renormalises, and builds the matrix `R̃(t)`
//! (entries within `2⁻⁴⁷` of `0` or `±1` snapped); `T̃(t) = t₀ ⊕ ((t₁ ⊖ t₀) ⊗ t)`.
//! A body point is posed as `fl(fl(R̃ p) + T̃)`, and the scene checker's
//! swept points add `fl(T̃(b) − T̃(a))` to posed points once more.
//!
//! Below, `u = 2⁻⁵³`, `r` bounds `|p|` (the reach), `M = max(|t₀|∞, |t₁|∞)`
//! and `D = |t₁ − t₀|∞`. Every term is rounded up.
//!
//! # The rotation: relative to the reach
//! Angles between unit quaternions (a quaternion angle `α` is a rotation by
//! `2α`, which moves a point `p` by at most `2α |p|`):
//! * `q̃₀`, `q̃₁` are within `5u` of `q₀`, `q₁` (length, reciprocal, product);
//! * `|q̃₁ − q̃₀|/2` is within `8u` of `sin(φ/2)`; `asin` has slope at most
//!   `√2` on `[0, sin(π/4)]` (`φ ≤ π/2` on the shorter arc) and is within an
//!   ulp, so `|φ̃ − φ| ≤ 25u`, and the motion's angle `Θ̃ = 2φ̃` is within
//!   `50u` of `Θ` ([`ANGLE_ROUNDING`] = `2⁻⁴⁶ = 128u`);
//! * the slerp with `φ̃` for `φ`: the angle of the result moves by at most
//!   `0.11 |φ̃ − φ|` (its derivative in the angle used, over `φ ≤ π/2`,
//!   `t ∈ [0, 1]`), `3u`; the weights (arguments, `sin` within an ulp, the
//!   division) are within `7u` relative and at most `1/cos(φ/2) ≤ √2` in
//!   sum, `10u`; `q̃₀`, `q̃₁` for `q₀`, `q₁`, `8u`; the products, sum and
//!   normalisation, `8u`: within `30u`, say `50u` (the lerp below `1e-9`
//!   is off by `φ³ < 1e-27` more);
//! * the snap of components below `1e-14`: the snapped part `e` is
//!   orthogonal to what remains, `|e| ≤ √3 · 1e-14`, an angle of at most
//!   `1.74e-14 ≤ 157u`; the renormalisation, `3u`.
//!
//! So the float quaternion's rotation is within a rotation by
//! `2 (50 + 157 + 3) u = 420u` of `R(t)`: `‖R_q̃ − R(t)‖₂ ≤ 420u`. The matrix
//! of a quaternion of squared length `1 + δ`, `|δ| ≤ 8u` (not renormalised
//! within `4ε`), has entries within `16u` of its rotation's, plus `5u`
//! rounding and the `2⁻⁴⁷ = 64u` snap: `85u` an entry, `‖·‖₂ ≤ ‖·‖_F ≤ 255u`.
//! The product `fl(R̃ p)` rounds by `γ₃ |R̃ᵢ| |p| ≤ 3.01u r` a coordinate,
//! `5.3u r` in norm. In all `|fl(R̃ p) − R(t) p| ≤ 681u r ≤ 2⁻⁴³ r`.
//!
//! # The translation: ulps of the coordinates
//! Per coordinate, `T̃ − T = (t₁ − t₀) t (δ₁ + δ₂ + δ₁δ₂) + δ₃ (t₀ + p̃)`
//! (`|δᵢ| ≤ u` the three roundings), at most `2.01u D + 1.02u M` (`T̃ = t₁`
//! exactly at `t = 1`): one rounding of the coordinate, and two of the
//! displacement, not of the coordinate. Adding `fl(R̃ p)` rounds by
//! `1.01u (M + r)`; the swept points `x̃(a) + fl(T̃(b) − T̃(a))` stand for
//! `R(a) p + T(b)` (`T̃(a)` cancels): the difference rounds by `1.01u D`, the
//! sum by `1.01u (M + r)` again. Per coordinate at most
//! `3.02u D + 3.04u M + 2.02u r`, in norm (`√3`) `5.24u D + 5.27u M + 3.5u r`.
//!
//! # The bound
//! [`pose_rounding_bound`] `= 2⁻⁴³ r + 6u (M + D)`, rounded up, bounds the
//! distance between every point the motion searches use (a posed vertex,
//! a swept point, or `R̃ p` and `T̃` taken exactly, as the convex search
//! does) and the exact motion's point, at every `t`. For a `1e-3` body at
//! `1e6` that is `6.7e-10`, about six ulps of the coordinates, where
//! `2⁻⁴⁰ (r + |T|)` was `9.1e-7`. A body whose vertices are themselves far
//! from its own origin has a large `r`: its rotation moves them by that
//! much, an honest limit.
//!
//! # Second reading (2026-11-28)
//! An independent review of this bound and of its uses found the tally
//! above sound for coordinates in the normal range, and two ways to break
//! the convex search's promises, both mended and pinned by tests that
//! failed before: the ball test's segment distance overflowed once an
//! interval's translations differed by more than about 1.3e154 (a motion
//! through the obstacle was certified free;
//! `tests/review_segment_overflow.rs`), and the reach of a body below about
//! 1e-162 came out under its vertices' norms because the squares
//! underflowed (`tests/review_tiny_reach.rs`); lengths are now taken after
//! scaling by a power of two. Gaps in the written argument it noted, none
//! giving a wrong answer: the renormalisation threshold tests the computed
//! squared length, so the quaternion's error is up to 12u, not 8u (about
//! 705u in all, still under `2⁻⁴³ = 1024u`); the convex gap is compared
//! without dividing by `|n|` (up to `1 + 2u`), which the slack of its sizes
//! covers; the scene search checks containment at the start's float pose
//! while its intervals bound `Motion::at(0)`, the same quaternion within
//! about `180u r`, inside `e`.

/// `2⁻⁵³`, the unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;

/// A bound on `|Θ̃ − Θ|`, the motion's float angle ([`Motion::angle`](crate::query::Motion::angle))
/// against the exact one (module docs): `2⁻⁴⁶`.
pub(crate) const ANGLE_ROUNDING: f64 = 1.0 / (1u64 << 46) as f64;

/// A bound on the distance between a float-posed point of a motion and
/// the exact motion's point, for a body of reach `reach` (module docs):
/// `2⁻⁴³ reach + 6u (M + D)`, rounded up; `(m, d)` is `(M, D)`, the
/// motion's `Motion::translation_extent`.
pub(crate) fn pose_rounding_bound(reach: f64, (m, d): (f64, f64)) -> f64 {
    let bound = reach * (1.0 / (1u64 << 43) as f64) + 6.0 * U * (m + d);
    bound * (1.0 + 8.0 * U) + 1e-300
}

/// `|v|`, rounded up, without squaring small coordinates into underflow
/// or large ones into overflow: the largest magnitude `m` times the length
/// of `v / m` (every coordinate of which is at most 1, one of them 1),
/// each of the half-dozen roundings below `u`, covered by `10⁻¹²`, and
/// [`SUBNORMAL_SLACK`] for the last product, which rounds to a multiple
/// of `2⁻¹⁰⁷⁴` when `m` is subnormal. NaN for a NaN coordinate.
pub(crate) fn norm_up(v: glam::DVec3) -> f64 {
    if v.is_nan() {
        return f64::NAN;
    }
    let m = v.abs().max_element();
    if !(m > 0.0 && m.is_finite()) {
        return m;
    }
    m * (v / m).length() * (1.0 + 1e-12) + SUBNORMAL_SLACK
}

/// An absolute slack for products that round in the subnormal range
/// (each off by at most `2⁻¹⁰⁷⁵`): `2⁻¹⁰⁷¹`.
const SUBNORMAL_SLACK: f64 = 8.0 * 5e-324;

/// An upper bound on the spectral norm of `m`: `√(‖m‖₁ ‖m‖∞)` (the
/// largest column and row sums of magnitudes; Hölder), taken of `m`
/// scaled by its largest magnitude so that the product neither underflows
/// nor overflows, rounded up past the few ulps the sums, the product and
/// the root may lose (and [`SUBNORMAL_SLACK`] for a subnormal scale). NaN
/// for a NaN entry (no bound: every comparison with it fails).
pub(crate) fn spectral_norm_up(m: glam::DMat3) -> f64 {
    if m.is_nan() {
        return f64::NAN;
    }
    let cols = [m.x_axis.abs(), m.y_axis.abs(), m.z_axis.abs()];
    let big = cols[0].max(cols[1]).max(cols[2]).max_element();
    if !(big > 0.0 && big.is_finite()) {
        return big;
    }
    let cols = cols.map(|c| c / big);
    let col_sum = cols.map(|c| c.element_sum());
    let row_sum = [0, 1, 2].map(|k| cols[0][k] + cols[1][k] + cols[2][k]);
    let one = col_sum[0].max(col_sum[1]).max(col_sum[2]);
    let inf = row_sum[0].max(row_sum[1]).max(row_sum[2]);
    big * (one * inf).sqrt() * (1.0 + 1e-12) + SUBNORMAL_SLACK
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// `norm_up` is never below the Euclidean norm, at any scale (squares
    /// of 1e-200 would underflow, of 1e200 overflow), and within 1e-11 of
    /// it.
    #[test]
    fn norms_are_rounded_up_at_every_scale() {
        for scale in [1e-300, 1e-200, 1e-150, 1.0, 1e150, 1e200, 1e300] {
            for v in [
                DVec3::new(3.0, 4.0, 0.0),
                DVec3::new(-1.0, 2.0, -2.0),
                DVec3::new(0.0, 0.0, -7.0),
            ] {
                let exact = v.length();
                let n = norm_up(v * scale) / scale;
                assert!(
                    n >= exact && n <= exact * (1.0 + 1e-11),
                    "{v} at {scale}: {n}"
                );
            }
        }
        assert_eq!(norm_up(DVec3::ZERO), 0.0);
        assert_eq!(norm_up(DVec3::new(f64::INFINITY, 0.0, 0.0)), f64::INFINITY);
    }

    /// `spectral_norm_up` is never below the spectral norm (a Rayleigh
    /// quotient of `AᵀA` after many power steps is a lower estimate of
    /// it), at any scale, and within `√3` of it, on differences of
    /// rotation matrices and on random matrices.
    #[test]
    fn spectral_norms_are_rounded_up_at_every_scale() {
        use glam::{DMat3, DQuat};
        let below = |a: DMat3| {
            let ata = a.transpose() * a;
            let mut x = DVec3::new(0.6, -0.7, 0.39).normalize();
            for _ in 0..200 {
                let y = ata * x;
                if y.length() == 0.0 {
                    return 0.0;
                }
                x = y.normalize();
            }
            (a * x).length()
        };
        let mut rng = crate::kernel::test_rng::Xorshift::new(0x9e37_79b9_7f4a_7c15u64);
        let mut unit = move || rng.signed();
        for k in 0..400 {
            let a = if k % 2 == 0 {
                let q = DQuat::from_xyzw(unit(), unit(), unit(), unit()).normalize();
                let turn = DQuat::from_axis_angle(
                    DVec3::new(unit(), unit(), unit()).normalize(),
                    0.5 * unit(),
                );
                DMat3::from_quat(turn * q) - DMat3::from_quat(q)
            } else {
                DMat3::from_cols_array(&std::array::from_fn(|_| unit()))
            };
            let exact = below(a);
            for scale in [1e-300, 1e-200, 1e-150, 1.0, 1e150, 1e200] {
                let n = spectral_norm_up(a * scale) / scale;
                assert!(n >= exact * (1.0 - 1e-12), "{a} at {scale}: {n} < {exact}");
                assert!(n <= exact * 1.7321, "{a} at {scale}: {n} > √3 {exact}");
            }
        }
        // Subnormal scales: the last product's rounding is covered.
        let m = f64::from_bits(1);
        let (n, a) = (
            norm_up(DVec3::new(m, m, 0.0)),
            DMat3::from_cols_array(&[m, 0.0, 0.0, m, 0.0, 0.0, 0.0, 0.0, 0.0]),
        );
        assert!(n >= 2.0 * m && spectral_norm_up(a) >= 2.0 * m, "{n:e}");
        assert!(norm_up(DVec3::new(f64::NAN, 0.0, 0.0)).is_nan());
        let mut with_nan = DMat3::ZERO;
        with_nan.y_axis.z = f64::NAN;
        assert!(spectral_norm_up(with_nan).is_nan());
        assert_eq!(spectral_norm_up(DMat3::ZERO), 0.0);
        assert_eq!(
            spectral_norm_up(DMat3::from_diagonal(DVec3::new(0.0, f64::INFINITY, 0.0))),
            f64::INFINITY
        );
    }

    /// Far from the origin the bound is a few ulps of the coordinates, and
    /// the float translations (computed as `Motion::at` does) stay within
    /// it of the exact lerp (computed here from differences that are
    /// exact: the ends are within a factor of two of each other).
    #[test]
    fn the_bound_is_a_few_ulps_far_away() {
        let t0 = DVec3::new(1e6, -1e6 / 3.0, 2e6 / 7.0);
        let t1 = t0 + DVec3::new(3e-3, -1e-3, 2e-3);
        let m = t0.abs().max(t1.abs()).max_element();
        let d = (t1 - t0).abs().max_element();
        let e = pose_rounding_bound(1e-3, (m, d));
        let ulp = 2f64.powi(-33); // of coordinates in [2^19, 2^20)
        assert!(e > 5.0 * ulp && e < 8.0 * ulp, "{e:e}");
        for k in 0..=64 {
            let t = k as f64 / 64.0;
            let at = t0 + (t1 - t0) * t;
            let off = (at - t0) - (t1 - t0) * t;
            assert!(off.length() <= e, "{t}: {off:?}");
        }
        // Near the origin, the reach's part: 2⁻⁴³ of it.
        let e = pose_rounding_bound(2.0, (0.0, 0.0));
        assert!(e >= 2.0 * 2f64.powi(-43) && e < 2.0 * 2f64.powi(-42));
    }
}
