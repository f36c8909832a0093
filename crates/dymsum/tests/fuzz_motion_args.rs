//! Issue 26: a fuzz harness for the motion checker's argument handling
//! (proptest, stable Rust).
//!
//! Random and extreme poses (quaternion components from `0`, `−0`,
//! `±1e-300`, subnormals, `±1`, `±1e300` and random values; rotations
//! given as matrices, including non-rotations; translations up to
//! `±f64::MAX`), tolerances (`0`, negative, NaN, infinities, `1e-300`,
//! `2^-38`, `0.999`, `1`, ...) and budgets (`0` clamps to `1`, `1`, `2`,
//! large) on small random convex bodies. Whatever the arguments:
//!
//! * `MotionChecker::check` returns `Ok` or a typed [`MotionError`]
//!   (`Tolerance` exactly for a tolerance outside `[MIN_TOLERANCE, 1)`,
//!   `Query` only for coordinates beyond `f64`, `Undecided`,
//!   `BudgetExhausted`), never panics;
//! * for modest poses (`|translation| ≤ 10`) a `Free` answer is confirmed
//!   by exact queries at 200 instants of `Motion::at`, a `Collides`
//!   bracket by exact queries on `[0, t_safe]` and at `t_contact`, and a
//!   `BudgetExhausted` prefix `[0, t_safe]` by exact queries too;
//! * `check_many` and `check_motion` agree with `check`.
//!
//! CI runs a few dozen cases per property (a few seconds in release);
//! `DYMSUM_PROPTEST_CASES=2000` (or `PROPTEST_CASES`) runs longer.

use dymsum::glam::{DMat3, DQuat};
use dymsum::query::{
    check_motion, ConvexUnion, Motion, MotionCheck, MotionChecker, MotionError, QueryError,
    DEFAULT_BUDGET, MIN_TOLERANCE,
};
use dymsum::{DVec3, Polytope, Pose, Rotation};
use dymsum_testkit::{random_polytope, rng, Kind};
use proptest::prelude::*;

/// The case count: `default`, or `PROPTEST_CASES` /
/// `DYMSUM_PROPTEST_CASES` for longer runs.
fn cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| dymsum_testkit::proptest_cases(default))
}

// ---------------------------------------------------------------------------
// Generators

/// A quaternion component: the awkward values well represented.
fn component() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        3 => -1.0..1.0f64,
        1 => Just(0.0),
        1 => Just(-0.0),
        1 => Just(1e-300),
        1 => Just(-1e-300),
        1 => Just(5e-324),
        1 => Just(-f64::MIN_POSITIVE / 3.0),
        1 => Just(1.0),
        1 => Just(-1.0),
        1 => Just(1e300),
        1 => Just(-1e300),
        1 => Just(1e-15),
        1 => Just(-8.598507252118853e-15),
    ]
}

/// A translation component: modest or extreme.
fn offset(extreme: bool) -> BoxedStrategy<f64> {
    if extreme {
        prop_oneof![
            3 => -10.0..10.0f64,
            1 => Just(0.0),
            1 => Just(-0.0),
            1 => Just(1e-300),
            1 => Just(1e300),
            1 => Just(-1e300),
            1 => Just(f64::MAX),
            1 => Just(-f64::MAX),
            1 => -1e300..1e300f64,
        ]
        .boxed()
    } else {
        prop_oneof![
            6 => -3.0..3.0f64,
            1 => -10.0..10.0f64,
            1 => Just(0.0),
            1 => Just(-0.0),
            1 => Just(1e-300),
        ]
        .boxed()
    }
}

/// How a rotation is given.
#[derive(Clone, Debug)]
enum RotationArg {
    /// Quaternion components `w, x, y, z` for `Rotation::from_wxyz`.
    Wxyz([f64; 4]),
    /// A matrix for `Rotation::from_matrix`: a random rotation's, perhaps
    /// perturbed, reflected, or with a non-finite entry.
    Matrix([f64; 4], MatrixTwist),
    /// Axis and angle.
    AxisAngle([f64; 3], f64),
}

#[derive(Clone, Copy, Debug)]
enum MatrixTwist {
    None,
    /// Each entry moved by this much (within or beyond 1e-6).
    Perturb(f64),
    /// The first column negated (determinant −1).
    Reflect,
    /// One entry replaced.
    Entry(usize, f64),
}

fn rotation_arg() -> impl Strategy<Value = RotationArg> {
    let quat = prop::array::uniform4(component());
    let twist = prop_oneof![
        4 => Just(MatrixTwist::None),
        1 => prop_oneof![Just(1e-300), Just(1e-9), Just(1e-3)].prop_map(MatrixTwist::Perturb),
        1 => Just(MatrixTwist::Reflect),
        1 => (0usize..9, prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(1e300)])
            .prop_map(|(i, v)| MatrixTwist::Entry(i, v)),
    ];
    prop_oneof![
        4 => quat.clone().prop_map(RotationArg::Wxyz),
        2 => (quat, twist).prop_map(|(q, t)| RotationArg::Matrix(q, t)),
        1 => (
            prop::array::uniform3(component()),
            prop_oneof![
                -7.0..7.0f64,
                Just(std::f64::consts::PI),
                Just(-std::f64::consts::PI),
                Just(f64::NAN),
                Just(1e300),
            ],
        )
            .prop_map(|(a, t)| RotationArg::AxisAngle(a, t)),
    ]
}

/// The rotation the argument gives, or `None` where the constructor
/// refuses it (it must not panic either way).
fn rotation(arg: &RotationArg) -> Option<Rotation> {
    match *arg {
        RotationArg::Wxyz([w, x, y, z]) => Rotation::from_wxyz(w, x, y, z),
        RotationArg::Matrix([w, x, y, z], twist) => {
            let q = DQuat::from_xyzw(x, y, z, w);
            let l = q.length();
            if !(l.is_finite() && l > 1e-150) {
                return None;
            }
            let mut m = DMat3::from_quat(q / l).to_cols_array();
            match twist {
                MatrixTwist::None => {}
                MatrixTwist::Perturb(d) => m.iter_mut().for_each(|e| *e += d),
                MatrixTwist::Reflect => m[..3].iter_mut().for_each(|e| *e = -*e),
                MatrixTwist::Entry(i, v) => m[i] = v,
            }
            Rotation::from_matrix(DMat3::from_cols_array(&m))
        }
        RotationArg::AxisAngle(a, t) => Rotation::from_axis_angle(DVec3::from_array(a), t),
    }
}

fn tolerance() -> impl Strategy<Value = f64> {
    // About two thirds accepted, one third refused.
    prop_oneof![
        6 => Just(1e-6),
        3 => Just(1e-3),
        3 => Just(0.1),
        1 => Just(0.999),
        1 => Just(MIN_TOLERANCE),
        2 => 1e-11..1.0f64,
        1 => Just(MIN_TOLERANCE * (1.0 - f64::EPSILON)),
        1 => Just(1.0),
        1 => prop_oneof![Just(0.0), Just(-0.0), Just(-1e-6)],
        1 => Just(1e-300),
        1 => prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(f64::NEG_INFINITY)],
        1 => Just(f64::MIN_POSITIVE),
        1 => -2.0..2.0f64,
    ]
}

fn budget() -> impl Strategy<Value = Option<u64>> {
    prop_oneof![
        2 => Just(None),
        1 => Just(Some(0)),
        1 => Just(Some(1)),
        1 => Just(Some(2)),
        1 => (3u64..64).prop_map(Some),
        1 => Just(Some(1 << 20)),
        1 => Just(Some(u64::MAX)),
    ]
}

/// A body of 1 or 2 pieces about the origin and 1 or 2 obstacles near it,
/// from a seed (the testkit's random polytopes, of every kind).
fn scene(seed: u64) -> (ConvexUnion, Vec<ConvexUnion>) {
    use rand::Rng;
    let mut r = rng(seed);
    let kinds = [
        Kind::Ball,
        Kind::Grid,
        Kind::Coplanar,
        Kind::Sphere,
        Kind::Cube,
    ];
    let piece = |r: &mut rand_chacha::ChaCha8Rng, scale: f64, centre: DVec3| {
        let kind = kinds[r.random_range(0..kinds.len())];
        let n = r.random_range(4..12);
        let p = random_polytope(kind, n, r);
        let pts: Vec<DVec3> = p.vertices().iter().map(|&v| v * scale + centre).collect();
        Polytope::from_dvec3s(&pts).expect("a scaled polytope")
    };
    let body_pieces = (0..r.random_range(1..=2))
        .map(|_| {
            let c = DVec3::new(r.random_range(-0.5..0.5), 0.0, 0.0);
            let scale = r.random_range(0.2..0.8);
            piece(&mut r, scale, c)
        })
        .collect();
    let body = ConvexUnion::new(body_pieces).unwrap();
    let obstacles = (0..r.random_range(1..=2))
        .map(|_| {
            let c = DVec3::new(
                r.random_range(-2.0..2.0),
                r.random_range(-2.0..2.0),
                r.random_range(-1.0..1.0),
            );
            let scale = r.random_range(0.2..1.0);
            ConvexUnion::from(piece(&mut r, scale, c))
        })
        .collect();
    (body, obstacles)
}

// ---------------------------------------------------------------------------
// The invariants

/// The error is one the docs promise for these arguments.
fn check_error(e: &MotionError, tolerance: f64, budget: u64) -> Result<(), TestCaseError> {
    let _ = e.to_string();
    match e {
        MotionError::Tolerance(t) => {
            prop_assert!(!(MIN_TOLERANCE..1.0).contains(&tolerance));
            prop_assert!(t.to_bits() == tolerance.to_bits(), "{t} vs {tolerance}");
        }
        MotionError::Query(q) => prop_assert!(
            matches!(q, QueryError::OutOfRange(_) | QueryError::Sum(_)),
            "an exact query failed other than by range: {q:?}"
        ),
        MotionError::Undecided { t_safe, t } => {
            prop_assert!(
                (0.0..=1.0).contains(t_safe) && t_safe <= t && *t <= 1.0,
                "{e:?}"
            )
        }
        MotionError::BudgetExhausted { t_safe, steps } => {
            prop_assert_eq!(*steps, budget);
            prop_assert!((0.0..=1.0).contains(t_safe), "{:?}", e);
        }
    }
    Ok(())
}

/// Exact queries at `n + 1` instants of `[a, b]` of the motion: none
/// collides.
fn sampled_free(
    checker: &MotionChecker,
    motion: &Motion,
    a: f64,
    b: f64,
    n: usize,
    what: &str,
) -> Result<(), TestCaseError> {
    for i in 0..=n {
        let t = a + (b - a) * (i as f64 / n as f64);
        let hit = checker.collides_at(motion.at(t));
        prop_assert!(
            matches!(hit, Ok(false)),
            "{what}: the body collides at t = {t} (in [{a}, {b}]): {hit:?}"
        );
    }
    Ok(())
}

/// Checks one motion and every invariant of the module docs.
fn check_motion_args(
    seed: u64,
    from: Pose,
    to: Pose,
    tol: f64,
    budget: Option<u64>,
    modest: bool,
) -> Result<(), TestCaseError> {
    let (body, obstacles) = scene(seed);
    let mut checker = MotionChecker::new(&body, &obstacles).expect("valid polytopes");
    if let Some(b) = budget {
        checker = checker.with_budget(b);
        prop_assert_eq!(checker.budget(), b.max(1));
    } else {
        prop_assert_eq!(checker.budget(), DEFAULT_BUDGET);
    }
    let steps = checker.budget();
    let answer = checker.check(from, to, tol);
    // The same answer from the batch and the one-shot entry points (the
    // budget counts per check, so both are deterministic).
    let many = checker.check_many(&[(from, to), (from, to)], tol);
    // Compared as text: `Tolerance(NaN)` is the same answer.
    let one = format!("{answer:?}");
    let both = match &many {
        Ok(v) => format!(
            "{:?}",
            v.iter()
                .map(|a| Ok(*a))
                .collect::<Vec<Result<_, MotionError>>>()
        ),
        Err(e) => format!("{:?}", Err::<MotionCheck, _>(e.clone())),
    };
    let expected = match &answer {
        Ok(_) => format!("[{one}, {one}]"),
        Err(_) => one.clone(),
    };
    prop_assert_eq!(both, expected, "check_many");
    if budget.is_none() {
        let once = check_motion(&body, &obstacles, from, to, tol);
        prop_assert_eq!(format!("{once:?}"), one, "check_motion");
    }
    let motion = Motion::new(from, to);
    match answer {
        Err(e) => {
            check_error(&e, tol, steps)?;
            if let MotionError::BudgetExhausted { t_safe, .. } = e {
                if modest {
                    sampled_free(&checker, &motion, 0.0, t_safe, 100, "budget prefix")?;
                }
            }
            if let MotionError::Undecided { t_safe, .. } = e {
                if modest {
                    sampled_free(&checker, &motion, 0.0, t_safe, 100, "undecided prefix")?;
                }
            }
        }
        Ok(MotionCheck::Free) => {
            prop_assert!((MIN_TOLERANCE..1.0).contains(&tol));
            if modest {
                sampled_free(&checker, &motion, 0.0, 1.0, 200, "Free")?;
            }
        }
        Ok(MotionCheck::Collides { t_safe, t_contact }) => {
            prop_assert!((MIN_TOLERANCE..1.0).contains(&tol));
            prop_assert!((0.0..=1.0).contains(&t_contact));
            match t_safe {
                None => {
                    prop_assert_eq!(t_contact, 0.0);
                    prop_assert!(checker.collides_at(from).unwrap());
                }
                Some(s) => {
                    prop_assert!(s < t_contact && t_contact - s <= tol, "{s} {t_contact}");
                    if modest {
                        sampled_free(&checker, &motion, 0.0, s, 100, "Collides t_safe")?;
                        prop_assert!(
                            checker.collides_at(motion.at(t_contact)).unwrap(),
                            "no contact at t_contact = {t_contact}"
                        );
                    }
                }
            }
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// Properties

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(128), ..ProptestConfig::default() })]

    /// Modest translations, any rotations, tolerances and budgets: answers
    /// confirmed by dense exact sampling.
    #[test]
    fn modest_poses_answers_are_confirmed_by_sampling(
        seed in any::<u64>(),
        r0 in rotation_arg(),
        r1 in rotation_arg(),
        t0 in prop::array::uniform3(offset(false)),
        t1 in prop::array::uniform3(offset(false)),
        tol in tolerance(),
        budget in budget(),
    ) {
        let from = Pose::new(rotation(&r0).unwrap_or_default(), DVec3::from_array(t0));
        let to = Pose::new(rotation(&r1).unwrap_or_default(), DVec3::from_array(t1));
        check_motion_args(seed, from, to, tol, budget, true)?;
    }

    /// Extreme translations (up to `±f64::MAX`): `Ok` or a typed error.
    #[test]
    fn extreme_poses_give_answers_or_typed_errors(
        seed in any::<u64>(),
        r0 in rotation_arg(),
        r1 in rotation_arg(),
        t0 in prop::array::uniform3(offset(true)),
        t1 in prop::array::uniform3(offset(true)),
        tol in tolerance(),
        budget in budget(),
    ) {
        let from = Pose::new(rotation(&r0).unwrap_or_default(), DVec3::from_array(t0));
        let to = Pose::new(rotation(&r1).unwrap_or_default(), DVec3::from_array(t1));
        check_motion_args(seed, from, to, tol, budget, false)?;
    }

    /// Rotation constructors on any components: `None` only for a zero or
    /// non-finite quaternion, otherwise a unit quaternion and a finite
    /// matrix; never a panic.
    #[test]
    fn rotation_constructors_take_any_components(q in prop::array::uniform4(component())) {
        let [w, x, y, z] = q;
        match Rotation::from_wxyz(w, x, y, z) {
            None => prop_assert!(q.iter().all(|&c| c == 0.0)),
            Some(r) => {
                prop_assert!((r.quat().length() - 1.0).abs() < 1e-12, "{r:?}");
                prop_assert!(r.matrix().is_finite());
                prop_assert!(r.quat().w >= 0.0);
            }
        }
    }

    /// Translations that are not finite: a typed error (or an answer),
    /// never a panic.
    #[test]
    fn non_finite_translations_are_refused_or_answered(
        seed in any::<u64>(),
        bad in prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(f64::NEG_INFINITY)],
        at_end in any::<bool>(),
        axis in 0usize..3,
    ) {
        let mut t = [0.5, 0.5, 0.5];
        t[axis] = bad;
        let (from, to) = if at_end {
            (Pose::IDENTITY, Pose::new(Rotation::IDENTITY, DVec3::from_array(t)))
        } else {
            (Pose::new(Rotation::IDENTITY, DVec3::from_array(t)), Pose::IDENTITY)
        };
        let (body, obstacles) = scene(seed);
        let checker = MotionChecker::new(&body, &obstacles).unwrap();
        let _ = checker.collides_at(from);
        match checker.check(from, to, 1e-6) {
            Ok(MotionCheck::Free) => prop_assert!(false, "Free through a non-finite pose"),
            Ok(_) => {}
            Err(e) => check_error(&e, 1e-6, DEFAULT_BUDGET)?,
        }
    }
}

// ---------------------------------------------------------------------------
// Named cases

/// The tolerances at and around the accepted range's ends.
#[test]
fn tolerance_range_ends() {
    let (body, obstacles) = scene(7);
    let checker = MotionChecker::new(&body, &obstacles).unwrap();
    let far = Pose::new(Rotation::IDENTITY, DVec3::new(0.0, 0.0, 50.0));
    let farther = Pose::new(Rotation::IDENTITY, DVec3::new(1.0, 0.0, 50.0));
    for tol in [
        MIN_TOLERANCE,
        2f64.powi(-38),
        0.5,
        0.999,
        1.0 - f64::EPSILON / 2.0,
    ] {
        assert_eq!(
            checker.check(far, farther, tol),
            Ok(MotionCheck::Free),
            "{tol}"
        );
    }
    for tol in [
        0.0,
        -0.0,
        1.0,
        1e-300,
        MIN_TOLERANCE * (1.0 - f64::EPSILON),
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ] {
        let e = checker.check(far, farther, tol).unwrap_err();
        assert!(
            matches!(e, MotionError::Tolerance(t) if t.to_bits() == tol.to_bits()),
            "{tol}: {e:?}"
        );
        assert!(e.to_string().contains("tolerance"), "{e}");
    }
}

/// `with_budget(0)` is a budget of one interval, and a budget of one
/// stops a motion that needs more with a certified prefix.
#[test]
fn budget_zero_is_one_and_one_step_stops_with_a_prefix() {
    let bar = ConvexUnion::from(
        Polytope::from_points(&[
            [0.0, -0.05, -0.05],
            [2.0, -0.05, -0.05],
            [0.0, 0.05, -0.05],
            [2.0, 0.05, -0.05],
            [0.0, -0.05, 0.05],
            [2.0, -0.05, 0.05],
            [0.0, 0.05, 0.05],
            [2.0, 0.05, 0.05],
        ])
        .unwrap(),
    );
    let block = ConvexUnion::from(
        Polytope::from_points(&[
            [1.0, 1.0, -1.0],
            [1.5, 1.0, -1.0],
            [1.0, 1.5, -1.0],
            [1.5, 1.5, -1.0],
            [1.0, 1.0, 1.0],
            [1.5, 1.0, 1.0],
            [1.0, 1.5, 1.0],
            [1.5, 1.5, 1.0],
        ])
        .unwrap(),
    );
    let checker = MotionChecker::new(&bar, &[block]).unwrap().with_budget(0);
    assert_eq!(checker.budget(), 1);
    let turn = |deg: f64| {
        Pose::new(
            Rotation::from_axis_angle(DVec3::Z, deg.to_radians()).unwrap(),
            DVec3::ZERO,
        )
    };
    match checker.check(turn(0.0), turn(90.0), 1e-6) {
        Err(MotionError::BudgetExhausted { t_safe, steps: 1 }) => {
            let motion = Motion::new(turn(0.0), turn(90.0));
            for i in 0..=100 {
                let t = t_safe * f64::from(i) / 100.0;
                assert!(!checker.collides_at(motion.at(t)).unwrap(), "{t}");
            }
        }
        other => panic!("{other:?}"),
    }
}
