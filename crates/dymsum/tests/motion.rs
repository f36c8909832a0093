//! Certified motion checks (issue 20 §1) against dense sampling: a motion
//! reported free has no colliding pose among thousands of interpolated
//! poses (exact queries); a reported contact is a real contact (the exact
//! query at `t_contact`) after a prefix `[0, t_safe]` in which no sampled
//! pose collides, with `t_contact − t_safe` within the tolerance. Named
//! cases: thin walls between free poses, a bar turning past a box, grazing,
//! touching, starting in contact, zero motion, quarter turns, unions.

use dymsum::query::{ConvexUnion, Motion, MotionCheck, MotionChecker, MotionError};
use dymsum::{DVec3, Polytope, Pose, Rotation};
use dymsum_testkit::{random_polytope, random_rotation, rng, Kind};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> Polytope {
    let corners: Vec<[f64; 3]> = (0..8)
        .map(|i| {
            let pick = |k: usize| if i >> k & 1 == 0 { lo[k] } else { hi[k] };
            [pick(0), pick(1), pick(2)]
        })
        .collect();
    Polytope::from_points(&corners).unwrap()
}

fn unit(r: &mut ChaCha8Rng) -> DVec3 {
    loop {
        let v = DVec3::new(
            r.random_range(-1.0..1.0),
            r.random_range(-1.0..1.0),
            r.random_range(-1.0..1.0),
        );
        let l = v.length();
        if l > 0.1 && l <= 1.0 {
            return v / l;
        }
    }
}

/// The check's answer against `samples` + 1 evenly spaced poses.
fn check_against_samples(
    checker: &MotionChecker,
    from: Pose,
    to: Pose,
    tol: f64,
    samples: usize,
    label: &str,
) -> MotionCheck {
    let answer = checker.check(from, to, tol).unwrap();
    let motion = Motion::new(from, to);
    let hit = |t: f64| checker.collides_at(motion.at(t)).unwrap();
    match answer {
        MotionCheck::Free => {
            for k in 0..=samples {
                let t = k as f64 / samples as f64;
                assert!(!hit(t), "{label}: reported free, collides at t = {t}");
            }
        }
        MotionCheck::Collides { t_safe, t_contact } => {
            assert!(
                hit(t_contact),
                "{label}: no contact at t_contact = {t_contact}"
            );
            match t_safe {
                None => assert_eq!(t_contact, 0.0, "{label}"),
                Some(s) => {
                    assert!(
                        s < t_contact && t_contact - s <= tol,
                        "{label}: {s} {t_contact}"
                    );
                    for k in 0..=samples {
                        let t = k as f64 / samples as f64 * s;
                        assert!(!hit(t), "{label}: t_safe = {s} but collides at t = {t}");
                    }
                }
            }
        }
    }
    answer
}

#[test]
fn random_motions_agree_with_dense_sampling() {
    let mut r = rng(20);
    let shapes = [
        cuboid([-0.5, -0.2, -0.1], [0.5, 0.2, 0.1]),
        random_polytope(Kind::Sphere, 30, &mut r),
        cuboid([-2.0, -0.05, -0.05], [2.0, 0.05, 0.05]),
    ];
    let obstacles = [
        ConvexUnion::from(random_polytope(Kind::Ball, 20, &mut r)),
        ConvexUnion::from(cuboid([1.0, -0.5, -0.5], [1.02, 0.5, 0.5])),
        ConvexUnion::new(vec![
            cuboid([-3.0, 3.0, -1.0], [3.0, 3.1, 1.0]),
            cuboid([-3.0, -3.1, -1.0], [3.0, -3.0, 1.0]),
        ])
        .unwrap(),
    ];
    let (mut free, mut collide) = (0, 0);
    for (i, body) in shapes.iter().enumerate() {
        let body = ConvexUnion::from(body.clone());
        let checker = MotionChecker::new(&body, &obstacles).unwrap();
        for k in 0..40 {
            let pose = |r: &mut ChaCha8Rng| {
                Pose::new(
                    random_rotation(r),
                    unit(r) * (2.0 + 4.0 * r.random_range(0.0..1.0)),
                )
            };
            let (from, to) = (pose(&mut r), pose(&mut r));
            let tol = [1e-3, 1e-6][k % 2];
            match check_against_samples(&checker, from, to, tol, 2000, &format!("body {i} #{k}")) {
                MotionCheck::Free => free += 1,
                MotionCheck::Collides { .. } => collide += 1,
            }
        }
    }
    assert!(
        free > 10 && collide > 10,
        "{free} free, {collide} colliding"
    );
}

/// A wall thinner than any sampling step between two free poses: the
/// motion crosses it, and the check says so at the wall.
#[test]
fn thin_walls_are_not_stepped_over() {
    let cube = ConvexUnion::from(cuboid([-0.1, -0.1, -0.1], [0.1, 0.1, 0.1]));
    for thickness in [1e-2, 1e-5, 1e-9] {
        let wall = ConvexUnion::from(cuboid([0.0, -5.0, -5.0], [thickness, 5.0, 5.0]));
        let checker = MotionChecker::new(&cube, &[wall]).unwrap();
        let at = |x: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, 0.0));
        assert!(!checker.collides_at(at(-3.0)).unwrap() && !checker.collides_at(at(3.0)).unwrap());
        match checker.check(at(-3.0), at(3.0), 1e-7).unwrap() {
            MotionCheck::Collides { t_safe, t_contact } => {
                // First contact at x = −0.1, t = 2.9 / 6.
                let t = 2.9 / 6.0;
                assert!((t_contact - t).abs() <= 1e-6, "{thickness}: {t_contact}");
                assert!(t_safe.unwrap() <= t && t_contact >= t - 1e-12);
            }
            MotionCheck::Free => panic!("stepped over a wall {thickness} thick"),
        }
    }
}

/// A long bar turning about its centre: free at both ends and halfway,
/// but it sweeps through a box; turned the other way it is free.
#[test]
fn a_turning_bar_sweeps_through_a_box_between_free_poses() {
    let bar = ConvexUnion::from(cuboid([-2.0, -0.05, -0.05], [2.0, 0.05, 0.05]));
    let block = ConvexUnion::from(cuboid([1.7, 0.6, -1.0], [1.9, 0.8, 1.0]));
    let checker = MotionChecker::new(&bar, &[block]).unwrap();
    let turn = |deg: f64| {
        Pose::new(
            Rotation::from_axis_angle(DVec3::Z, deg.to_radians()).unwrap(),
            DVec3::ZERO,
        )
    };
    for deg in [0.0, 45.0, 90.0] {
        assert!(!checker.collides_at(turn(deg)).unwrap());
    }
    check_against_samples(&checker, turn(0.0), turn(90.0), 1e-6, 20000, "bar");
    assert!(!checker
        .check(turn(0.0), turn(90.0), 1e-6)
        .unwrap()
        .is_free());
    assert!(checker
        .check(turn(-90.0), turn(-1.0), 1e-6)
        .unwrap()
        .is_free());
    // SE(2)-style: the same turn composed with a translation.
    let moved = |deg: f64, x: f64| Pose::new(turn(deg).rotation, DVec3::new(x, 0.0, 0.0));
    check_against_samples(
        &checker,
        moved(0.0, -1.0),
        moved(80.0, 0.5),
        1e-6,
        20000,
        "bar moving",
    );
}

#[test]
fn grazing_touching_and_starting_in_contact() {
    let cube = ConvexUnion::from(cuboid([-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]));
    let floor = ConvexUnion::from(cuboid([-10.0, -10.0, -1.0], [10.0, 10.0, 0.0]));
    let checker = MotionChecker::new(&cube, &[floor]).unwrap();
    let at = |x: f64, z: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, z));
    // Sliding 1e-3 above the floor: free.
    assert_eq!(
        checker
            .check(at(-3.0, 0.501), at(3.0, 0.501), 1e-6)
            .unwrap(),
        MotionCheck::Free
    );
    // Sliding on it (touching all along): collides at the start.
    assert_eq!(
        checker.check(at(-3.0, 0.5), at(3.0, 0.5), 1e-6).unwrap(),
        MotionCheck::Collides {
            t_safe: None,
            t_contact: 0.0
        }
    );
    // Coming down to touch exactly at the end.
    match checker.check(at(0.0, 2.0), at(0.0, 0.5), 1e-9).unwrap() {
        MotionCheck::Collides { t_safe, t_contact } => {
            assert_eq!(t_contact, 1.0);
            assert!(t_safe.unwrap() >= 1.0 - 1e-9);
        }
        MotionCheck::Free => panic!("touching counts as contact"),
    }
    // No motion at all, apart: free.
    assert_eq!(
        checker.check(at(0.0, 2.0), at(0.0, 2.0), 1e-6).unwrap(),
        MotionCheck::Free
    );
    // Quarter turns about z, sliding 1e-6 above the floor: free.
    let quarter = |k: f64, x: f64| {
        Pose::new(
            Rotation::from_axis_angle(DVec3::Z, k * std::f64::consts::FRAC_PI_2).unwrap(),
            DVec3::new(x, 0.0, 0.500001),
        )
    };
    check_against_samples(
        &checker,
        quarter(0.0, -1.0),
        quarter(3.0, 1.0),
        1e-6,
        5000,
        "quarter turns",
    );
}

#[test]
fn bad_tolerances_are_typed_errors_and_batches_equal_single_checks() {
    let cube = ConvexUnion::from(cuboid([-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]));
    let checker = MotionChecker::new(&cube, std::slice::from_ref(&cube)).unwrap();
    let at = |x: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, 0.0));
    for bad in [0.0, -1.0, 1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            checker.check(at(3.0), at(2.0), bad),
            Err(MotionError::Tolerance(_))
        ));
    }
    let motions: Vec<(Pose, Pose)> = (0..50)
        .map(|k| (at(3.0), at(3.0 - 0.05 * k as f64)))
        .collect();
    let many = checker.check_many(&motions, 1e-6).unwrap();
    for (m, &(a, b)) in many.iter().zip(&motions) {
        assert_eq!(*m, checker.check(a, b, 1e-6).unwrap());
    }
    // Contact at x = 1: t = (3 − 1) / (0.05 k) for k ≥ 40.
    assert!(many[39].is_free() && !many[40].is_free());
}
