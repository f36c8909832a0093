//! Certified motion checks (issue 20 §1) against dense sampling: a motion
//! reported free has no colliding pose among thousands of interpolated
//! poses (exact queries); a reported contact is a real contact (the exact
//! query at `t_contact`) after a prefix `[0, t_safe]` in which no sampled
//! pose collides, with `t_contact − t_safe` within the tolerance. Named
//! cases: thin walls between free poses, a bar turning past a box, grazing,
//! touching, starting in contact, zero motion, quarter turns, unions.

use dymsum::query::{ConvexUnion, Motion, MotionCheck, MotionChecker, MotionError};
use dymsum::{DVec3, Polytope, Pose, Rotation};
use dymsum_testkit::{cuboid, random_polytope, random_rotation, random_unit as unit, rng, Kind};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

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

/// Found by the Python dense-sampling test (seed 2, motion 7): the piece
/// passes within 7·10⁻⁹ of the obstacle just before touching it, where
/// GJK's direction (off by about ε·size/distance) cannot certify the
/// intervals left of the contact; halving then ended at `MIN_WIDTH` as
/// `Undecided`. The exact-distance advancement bound and the look-ahead
/// past a stuck interval close it with a real bracket.
#[test]
fn regression_near_contact_gjk_direction_too_coarse() {
    let body = Polytope::from_points(&[
        [
            0.18905338179353307,
            -0.1568245324442242,
            -0.12391906301756803,
        ],
        [-2.4414673826398556, 0.5399122148162706, 0.3432497616111686],
        [
            -0.32542283686782436,
            0.23214197601829842,
            0.08436320093929477,
        ],
        [
            -0.5538228364240524,
            0.2932702353378107,
            -0.09316696399774577,
        ],
        [
            -0.3288239040579627,
            -0.23764402660766945,
            0.13648742137225664,
        ],
        [
            -0.09919805171738795,
            0.1635866141894045,
            -0.18215570996119113,
        ],
        [0.12682784711186987, -0.2676822130289371, 0.2524394917110429],
        [
            0.18803508698068597,
            0.09917130244059784,
            0.12315117389107885,
        ],
        [-1.0107575001533344, 0.2349542988432232, 0.6170108455027106],
        [
            -1.6384425032355252,
            -0.5188234401463444,
            -0.45144942415929595,
        ],
        [0.8414588934539998, 0.03861469724222054, 0.32350273222178944],
        [0.722430872307499, 0.06317154371258417, 0.08521144357511125],
    ])
    .unwrap();
    let obstacle = Polytope::from_points(&[
        [-1.1566624583074956, 1.284013824191332, -1.2909868860083873],
        [-1.483041984220473, 0.8711377784622559, -1.3180397319391062],
        [
            -1.6878544669302544,
            0.32593942636208467,
            -0.5806926397703924,
        ],
        [-1.044439564011392, 0.8465206729544646, -1.3980250540926322],
        [-1.4620676276472389, 1.0366283851707672, -1.3292549478337043],
        [-1.4898230468399742, 0.6263146512025743, -1.6496467734531681],
        [-1.1101614667043573, 1.1316571109700095, -1.6218384332215263],
        [-0.6147622000724885, 0.4129180794778105, -1.2260395016746517],
        [-1.5207344122624775, 0.5910719924006594, -1.268442601766577],
        [-1.360053780610173, 0.39881090071339137, -1.5585588430296922],
    ])
    .unwrap();
    let pose = |m: [[f64; 3]; 3], t: [f64; 3]| {
        let rows = [
            [m[0][0], m[0][1], m[0][2], t[0]],
            [m[1][0], m[1][1], m[1][2], t[1]],
            [m[2][0], m[2][1], m[2][2], t[2]],
            [0.0, 0.0, 0.0, 1.0],
        ];
        Pose::from_mat4(glam::DMat4::from_cols_array_2d(&rows).transpose()).unwrap()
    };
    let from = pose(
        [
            [-0.5015407330266497, -0.6818782239298856, -0.532446223430419],
            [
                -0.8638455937902362,
                0.42829036575353024,
                0.26521340971357654,
            ],
            [
                0.047198338999217354,
                0.5929666519568635,
                -0.8038425632316211,
            ],
        ],
        [-0.5130468502901477, -2.1487816340969568, -3.47698103426627],
    );
    let to = pose(
        [
            [-0.7289349063882623, 0.6683114810209769, 0.14837003263558268],
            [0.15661427378832593, 0.3737799113822062, -0.9141994022601774],
            [
                -0.666427694123294,
                -0.6431549907935556,
                -0.37712834197770234,
            ],
        ],
        [
            -3.6427881186410156,
            0.9832501895373849,
            -0.058268161071183044,
        ],
    );
    let checker =
        MotionChecker::new(&ConvexUnion::from(body), &[ConvexUnion::from(obstacle)]).unwrap();
    let answer = check_against_samples(&checker, from, to, 1e-7, 4000, "near contact");
    let MotionCheck::Collides { t_contact, .. } = answer else {
        panic!("the piece reaches the obstacle");
    };
    assert!((t_contact - 0.704312147).abs() < 1e-6, "{t_contact}");
}

/// A random convex blob of `n` points on the unit sphere about `c`.
fn blob(r: &mut ChaCha8Rng, n: usize, c: DVec3) -> Polytope {
    let points: Vec<[f64; 3]> = (0..n).map(|_| (c + unit(r)).to_array()).collect();
    Polytope::from_points(&points).unwrap()
}

/// Short motions (turns of 1° to 5°, moves of up to 8% of the size) from
/// free poses within 2⁻⁴² of contact: every verdict agrees with 400
/// sampled poses, and the free ones are certified in a few intervals
/// each (`query::interval_search`, "The bow": with the sagitta alone as
/// the margin, an interval next to a grazing pose was certified only once
/// its sagitta fell below the clearance there).
#[test]
fn motions_leaving_a_grazing_pose_are_certified_in_few_steps() {
    let mut r = rng(41);
    let body = ConvexUnion::from(blob(&mut r, 60, DVec3::ZERO));
    let wall = ConvexUnion::from(blob(&mut r, 60, DVec3::new(3.0, 0.0, 0.0)));
    let checker = MotionChecker::new(&body, &[wall]).unwrap();
    let (mut steps, mut undecided) = (Vec::new(), 0);
    for _ in 0..40 {
        let turn = Rotation::from_axis_angle(unit(&mut r), 1.0).unwrap();
        // Free at 0, overlapping the wall at 3: bisected along x.
        let place = |x: f64| Pose::new(turn, DVec3::new(x, 0.0, 0.0));
        let (mut free_x, mut hit_x) = (0.0, 3.0);
        for _ in 0..42 {
            let mid = 0.5 * (free_x + hit_x);
            if checker.collides_at(place(mid)).unwrap() {
                hit_x = mid;
            } else {
                free_x = mid;
            }
        }
        let from = place(free_x);
        let spin =
            Rotation::from_axis_angle(unit(&mut r), r.random_range(1.0f64..5.0).to_radians())
                .unwrap();
        let to = Pose::new(
            from.rotation.then(&spin),
            from.translation + unit(&mut r) * r.random_range(0.0..0.08),
        );
        let before = checker.steps();
        // A motion into the wall meets it within about 10⁻¹⁴ of its start,
        // below the search's least width: undecided, as documented.
        let got = match checker.check(from, to, 1e-6) {
            Ok(got) => got,
            Err(MotionError::Undecided { .. }) => {
                undecided += 1;
                continue;
            }
            Err(e) => panic!("{e}"),
        };
        let motion = Motion::new(from, to);
        match got {
            MotionCheck::Free => {
                steps.push(checker.steps() - before);
                for k in 0..=400 {
                    assert!(!checker
                        .collides_at(motion.at(f64::from(k) / 400.0))
                        .unwrap());
                }
            }
            MotionCheck::Collides { t_contact, .. } => {
                assert!(checker.collides_at(motion.at(t_contact)).unwrap());
            }
        }
    }
    assert!(
        steps.len() >= 10 && undecided <= 10,
        "{steps:?}, {undecided} undecided"
    );
    // With the sagitta alone none took fewer than 29 (median 65); with the
    // bow along the swept hull's GJK direction alone, a quarter took one
    // or two (the rest: their swept hull overlapped in floats).
    steps.sort_unstable();
    assert!(steps[steps.len() / 2] <= 4, "{steps:?}");
}

/// A spike with its corner at radius 10 on the x axis, its base at 5.
fn spike() -> Polytope {
    Polytope::from_points(&[
        [10.0, 0.0, 0.0],
        [5.0, 0.1, 0.1],
        [5.0, -0.1, 0.1],
        [5.0, 0.0, -0.1],
    ])
    .unwrap()
}

/// `body` turning 0.2 rad about z against `obstacle`, clear at both ends
/// and colliding at the middle: the check finds an exact contact, never
/// "free".
fn turning_through_the_middle_is_never_free(body: Polytope, obstacle: Polytope) {
    let checker =
        MotionChecker::new(&ConvexUnion::from(body), &[ConvexUnion::from(obstacle)]).unwrap();
    let yaw = |a: f64| Pose::new(Rotation::from_axis_angle(DVec3::Z, a).unwrap(), DVec3::ZERO);
    let (from, to) = (yaw(-0.1), yaw(0.1));
    assert!(!checker.collides_at(from).unwrap() && !checker.collides_at(to).unwrap());
    assert!(checker.collides_at(yaw(0.0)).unwrap());
    match checker.check(from, to, 1e-6).unwrap() {
        MotionCheck::Collides { t_contact, .. } => {
            assert!(checker
                .collides_at(Motion::new(from, to).at(t_contact))
                .unwrap());
        }
        MotionCheck::Free => panic!("a motion through an obstacle called free"),
    }
}

/// A corner turning 0.2 rad on an arc of radius 10 pokes `0.01` into a
/// wall at its apex, while at both ends it is clear of it by about
/// `0.04`: the chord between the ends stays clear, only the bow of the
/// arc meets the wall (`query::interval_search`, "The bow"). Never free.
#[test]
fn an_arc_through_a_wall_between_clear_ends_is_never_free() {
    let wall = cuboid([9.99, -5.0, -5.0], [11.0, 5.0, 5.0]);
    turning_through_the_middle_is_never_free(spike(), wall);
}

/// The same arc seen from the body (`query::motion`, "Between the ends",
/// the body's frame): a slab turning 0.2 rad about the origin, its near
/// face at radius `10 − 0.01`, and an obstacle's corner at radius 10.
/// From the body the corner runs on an arc that pokes `0.01` into the
/// slab at the apex, while at both ends it is clear by about `0.04`.
/// Never free.
#[test]
fn an_obstacle_corner_through_a_turning_slab_is_never_free() {
    let slab = cuboid([9.99, -5.0, -5.0], [11.0, 5.0, 5.0]);
    turning_through_the_middle_is_never_free(slab, spike());
}
