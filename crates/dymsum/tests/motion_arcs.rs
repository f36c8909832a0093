//! Which way a motion to a nearly opposite orientation turns (issue 26 §1):
//! the arc is decided from the rotations as given, by the exact sign of the
//! dot product of their quaternions, never after snapping.
//!
//! The scene of the finding: a bar `[0, 2] × [−.05, .05]²` turning about z
//! from the identity to `180° ± ε`, and a block at `y ∈ [−1.6, −1.4]` that
//! only the clockwise arc sweeps. The oracle is independent of
//! [`dymsum::query::Motion`]: the poses of the intended arc are built by
//! `Rotation::from_axis_angle` and checked with the exact query.

use dymsum::glam::{DMat3, DQuat};
use dymsum::kernel::predicates::{dot4, Sign};
use dymsum::query::{ConvexUnion, Motion, MotionChecker};
use dymsum::{DVec3, Pose, Rotation};
use dymsum_testkit::cuboid;
use std::f64::consts::PI;

fn scene() -> MotionChecker {
    let bar = ConvexUnion::from(cuboid([0.0, -0.05, -0.05], [2.0, 0.05, 0.05]));
    let block = ConvexUnion::from(cuboid([-0.1, -1.6, -1.0], [0.1, -1.4, 1.0]));
    MotionChecker::new(&bar, &[block]).unwrap()
}

fn at(rotation: Rotation) -> Pose {
    Pose::new(rotation, DVec3::ZERO)
}

/// Whether the bar turning about z by `total` radians (signed: negative is
/// clockwise) hits the block, by the exact query at 2,001 poses built
/// without `Motion`.
fn sampled_arc_collides(checker: &MotionChecker, total: f64) -> bool {
    (0..=2000).any(|k| {
        let r = Rotation::from_axis_angle(DVec3::Z, total * k as f64 / 2000.0)
            .unwrap_or(Rotation::IDENTITY);
        checker.collides_at(at(r)).unwrap()
    })
}

/// The motion from the identity to `to`, checked, and its answer compared
/// with the arc the exact rule picks (`clockwise`).
fn assert_turns(to: Rotation, clockwise: bool, label: &str) {
    let checker = scene();
    let answer = checker.check(Pose::IDENTITY, at(to), 1e-6).unwrap();
    // The oracle: the clockwise half turn sweeps the block, the
    // counter-clockwise one does not.
    let total = if clockwise { -PI } else { PI };
    assert_eq!(
        sampled_arc_collides(&checker, total),
        clockwise,
        "{label}: oracle"
    );
    assert_eq!(
        !answer.is_free(),
        clockwise,
        "{label}: the check answered {answer:?}, the {} arc is meant",
        if clockwise {
            "clockwise"
        } else {
            "counter-clockwise"
        }
    );
    // The interpolated motion itself turns that way: at t = 1/2 the bar
    // points along −y (clockwise) or +y.
    let mid = Motion::new(Pose::IDENTITY, at(to))
        .at(0.5)
        .rotation
        .apply(DVec3::X);
    assert!(
        (mid.y < -0.99) == clockwise && (mid.y > 0.99) != clockwise,
        "{label}: the motion's halfway direction {mid}"
    );
}

/// `w` of the half turn plus `eps` radians about +z (`w = cos((π + ε)/2)
/// = −sin(ε/2)`), as given exactly.
fn half_turn_plus(eps: f64) -> (f64, f64) {
    (-(eps / 2.0).sin(), (eps / 2.0).cos())
}

#[test]
fn regression_half_turn_plus_1e_12_degrees_turns_clockwise_from_a_quaternion() {
    let (w, z) = half_turn_plus(1e-12f64.to_radians());
    assert!(
        w < 0.0 && w.abs() < 1e-14,
        "w = {w}: snapped to zero by Rotation"
    );
    let to = Rotation::from_wxyz(w, 0.0, 0.0, z).unwrap();
    assert_eq!(to.wxyz()[0], 0.0, "the rotation itself is snapped");
    assert_turns(to, true, "180° + 1e-12°");
    // The finding's literal CLI value.
    let to = Rotation::from_wxyz(-8.598507252118853e-15, 0.0, 0.0, 1.0).unwrap();
    assert_turns(to, true, "w = -8.598507252118853e-15");
}

#[test]
fn half_turn_minus_1e_12_degrees_turns_counter_clockwise() {
    let (w, z) = half_turn_plus(-1e-12f64.to_radians());
    assert!(w > 0.0);
    assert_turns(
        Rotation::from_wxyz(w, 0.0, 0.0, z).unwrap(),
        false,
        "180° − 1e-12°",
    );
}

#[test]
fn half_turn_plus_minus_1e_300_decides_by_the_exact_sign() {
    assert_turns(
        Rotation::from_wxyz(-5e-301, 0.0, 0.0, 1.0).unwrap(),
        true,
        "w = −5e-301",
    );
    assert_turns(
        Rotation::from_wxyz(5e-301, 0.0, 0.0, 1.0).unwrap(),
        false,
        "w = 5e-301",
    );
    // Subnormal.
    let tiny = f64::from_bits(1);
    assert_turns(
        Rotation::from_wxyz(-tiny, 0.0, 0.0, 1.0).unwrap(),
        true,
        "w = −2⁻¹⁰⁷⁴",
    );
    assert_turns(
        Rotation::from_wxyz(tiny, 0.0, 0.0, 1.0).unwrap(),
        false,
        "w = 2⁻¹⁰⁷⁴",
    );
}

#[test]
fn exact_half_turn_keeps_the_second_quaternion_as_given() {
    // Dot product exactly zero (w = ±0.0): no negation, the rotation turns
    // from the first quaternion towards the second as given.
    for w in [0.0, -0.0] {
        assert_turns(
            Rotation::from_wxyz(w, 0.0, 0.0, 1.0).unwrap(),
            false,
            "w = ±0, z = 1",
        );
        assert_turns(
            Rotation::from_wxyz(w, 0.0, 0.0, -1.0).unwrap(),
            true,
            "w = ±0, z = −1",
        );
    }
}

#[test]
fn the_start_quaternions_sign_does_not_change_the_shorter_arc() {
    // −identity as the start: the dot product changes sign, the negation
    // follows, and the motion still turns the short way.
    let checker = scene();
    let from = at(Rotation::from_wxyz(-1.0, 0.0, 0.0, 0.0).unwrap());
    let (w, z) = half_turn_plus(1e-12f64.to_radians());
    let cw = checker
        .check(from, at(Rotation::from_wxyz(w, 0.0, 0.0, z).unwrap()), 1e-6)
        .unwrap();
    assert!(!cw.is_free(), "{cw:?}");
    let ccw = checker
        .check(
            from,
            at(Rotation::from_wxyz(-w, 0.0, 0.0, z).unwrap()),
            1e-6,
        )
        .unwrap();
    assert!(ccw.is_free(), "{ccw:?}");
}

#[test]
fn matrices_keep_the_arc_through_their_quaternion() {
    // A rotation matrix of 180° ± ε about z, as scipy's `as_matrix` gives
    // it: sin(π + ε) = −sin ε.
    let matrix = |eps: f64| {
        let (s, c) = (PI + eps).sin_cos();
        DMat3::from_cols(DVec3::new(c, s, 0.0), DVec3::new(-s, c, 0.0), DVec3::Z)
    };
    for (eps, clockwise) in [
        (1e-12f64.to_radians(), true),
        (-1e-12f64.to_radians(), false),
    ] {
        let r = Rotation::from_matrix(matrix(eps)).unwrap();
        assert_turns(r, clockwise, &format!("matrix at 180° + {eps:e} rad"));
    }
    // The exact matrix entries ±1e-300 (no float rotation gives them, a
    // user may).
    for (s, clockwise) in [(-1e-300, true), (1e-300, false)] {
        let m = DMat3::from_cols(
            DVec3::new(-1.0, s, 0.0),
            DVec3::new(-s, -1.0, 0.0),
            DVec3::Z,
        );
        assert_turns(
            Rotation::from_matrix(m).unwrap(),
            clockwise,
            &format!("sin = {s:e}"),
        );
    }
}

#[test]
fn handed_out_matrices_round_trip_the_arc() {
    // `matrix_as_given` (what Python's `dymsum.pose` returns) converted
    // back keeps the side of the half turn; exact quarter turns stay exact.
    for (w, clockwise) in [
        (-8.6e-15, true),
        (8.6e-15, false),
        (-5e-301, true),
        (5e-301, false),
    ] {
        let r = Rotation::from_wxyz(w, 0.0, 0.0, 1.0).unwrap();
        let back = Rotation::from_matrix(r.matrix_as_given()).unwrap();
        assert_turns(back, clockwise, &format!("round trip of w = {w:e}"));
    }
    let quarter = Rotation::from_axis_angle(DVec3::Z, PI / 2.0).unwrap();
    assert_eq!(quarter.matrix_as_given(), quarter.matrix());
    assert_eq!(quarter.matrix_as_given().x_axis, DVec3::Y);
}

#[test]
fn compositions_and_inverses_carry_the_quaternion_as_given() {
    let (w, z) = half_turn_plus(1e-12f64.to_radians());
    let to = Rotation::from_wxyz(w, 0.0, 0.0, z).unwrap();
    // identity ∘ to, and (to⁻¹)⁻¹.
    assert_turns(to.then(&Rotation::IDENTITY), true, "to then identity");
    assert_turns(Rotation::IDENTITY.then(&to), true, "identity then to");
    assert_turns(to.inverse().inverse(), true, "double inverse");
    // The inverse turns the other way round.
    assert_turns(to.inverse(), false, "inverse");
}

#[test]
fn dot4_is_exact_on_tiny_and_cancelling_products() {
    assert_eq!(
        dot4([1.0, 0.0, 0.0, 0.0], [-1e-300, 0.0, 0.0, 1.0]),
        Sign::Negative
    );
    // 1 + 2⁻⁶⁰ − 1 − 2⁻⁶⁰·(1 − 2⁻⁵²): rounds to zero in floats.
    let e = 2f64.powi(-60);
    let a = [1.0, e, 1.0, e];
    let b = [1.0, 1.0, -1.0, -(1.0 - f64::EPSILON)];
    assert_eq!(dot4(a, b), Sign::Positive);
    assert_eq!(dot4(a, [1.0, 1.0, -1.0, -1.0]), Sign::Zero);
    // Products that underflow in floats.
    assert_eq!(
        dot4([1e-200, 0.0, 0.0, 0.0], [-1e-200, 0.0, 0.0, 0.0]),
        Sign::Negative
    );
    assert_eq!(
        dot4([1e-200, 1e-300, 0.0, 0.0], [1e-200, -1e-100, 0.0, 0.0]),
        Sign::Negative
    );
    let q = DQuat::from_xyzw(0.0, 0.0, 1.0, -8.6e-15);
    assert_eq!(
        dot4(DQuat::IDENTITY.to_array(), q.to_array()),
        Sign::Negative
    );
}
