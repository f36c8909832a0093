//! Bounded work for motion checks (issue 26 §4): a bar turning 90° past a
//! thin plate at its reach took 15 s at a gap of 1e-9, 104 s at 1e-10 and
//! 287 s at 0; a tolerance of 1e-300 was accepted and then a head-on
//! collision came back undecided. Now: gaps down to 1e-12 of the bar's
//! size are decided free in a few hundred intervals (the feature axes of
//! the nearly touching features), touching is undecided within the
//! budget, the budget is deterministic and reports a certified `t_safe`,
//! and tolerances the search cannot bracket are refused.

use dymsum::query::{
    ConvexUnion, Motion, MotionCheck, MotionChecker, MotionError, DEFAULT_BUDGET, MIN_TOLERANCE,
};
use dymsum::{DVec3, Pose, Rotation};
use dymsum_testkit::{cuboid, grazing};

fn turn(deg: f64) -> Pose {
    Pose::new(
        Rotation::from_axis_angle(DVec3::Z, deg.to_radians()).unwrap(),
        DVec3::ZERO,
    )
}

fn bar() -> ConvexUnion {
    ConvexUnion::from(grazing::bar())
}

/// A plate facing the turning bar's tip, `gap` beyond its reach.
fn plate_at(gap: f64) -> ConvexUnion {
    ConvexUnion::from(grazing::plate(gap))
}

/// A square rod with one edge towards the bar's tip, `gap` beyond its
/// reach.
fn rod_edge_at(gap: f64) -> ConvexUnion {
    ConvexUnion::from(grazing::rod_edge(gap))
}

#[test]
fn regression_grazing_plate_is_decided_within_a_few_hundred_intervals() {
    for gap in [1e-6, 1e-9, 1e-10, 1e-12] {
        for (label, obstacle) in [("plate", plate_at(gap)), ("rod edge", rod_edge_at(gap))] {
            let checker = MotionChecker::new(&bar(), &[obstacle]).unwrap();
            let answer = checker.check(turn(-45.0), turn(45.0), 1e-6);
            assert_eq!(answer, Ok(MotionCheck::Free), "{label} at gap {gap:e}");
            assert!(
                checker.steps() <= 1000,
                "{label} at gap {gap:e}: {} intervals",
                checker.steps()
            );
        }
    }
}

#[test]
fn regression_touching_plate_ends_within_the_budget() {
    // At gap 0 (and below rounding) no checked time touches and no
    // interval around the tangent instant certifies: undecided, never
    // free, and within the budget.
    for gap in [0.0, 1e-15] {
        for (label, obstacle) in [("plate", plate_at(gap)), ("rod edge", rod_edge_at(gap))] {
            let checker = MotionChecker::new(&bar(), &[obstacle]).unwrap();
            let answer = checker.check(turn(-45.0), turn(45.0), 1e-6);
            assert!(
                matches!(
                    answer,
                    Err(MotionError::Undecided { .. } | MotionError::BudgetExhausted { .. })
                        | Ok(MotionCheck::Collides { .. })
                ),
                "{label} at gap {gap:e}: {answer:?}"
            );
            assert!(
                checker.steps() <= DEFAULT_BUDGET,
                "{label}: {} steps",
                checker.steps()
            );
        }
    }
}

#[test]
fn budget_is_deterministic_and_reports_a_certified_prefix() {
    let block = ConvexUnion::from(cuboid([1.7, -0.5, -1.0], [1.9, -0.3, 1.0]));
    let make = |budget: u64| {
        MotionChecker::new(&bar(), std::slice::from_ref(&block))
            .unwrap()
            .with_budget(budget)
    };
    let (from, to) = (turn(45.0), turn(-45.0));
    let full = make(DEFAULT_BUDGET).check(from, to, 1e-9).unwrap();
    let MotionCheck::Collides { t_contact, .. } = full else {
        panic!("the bar sweeps through the block: {full:?}");
    };
    let mut undecided = 0;
    for budget in [1, 2, 3, 5, 8, 13] {
        let checker = make(budget);
        assert_eq!(checker.budget(), budget);
        let first = checker.check(from, to, 1e-9);
        // The same answer every time (counted steps, not time).
        for _ in 0..3 {
            assert_eq!(make(budget).check(from, to, 1e-9), first, "budget {budget}");
        }
        match first {
            Err(MotionError::BudgetExhausted { t_safe, steps }) => {
                undecided += 1;
                assert_eq!(steps, budget);
                assert!(t_safe < t_contact, "budget {budget}: t_safe {t_safe}");
                // The prefix is really free (dense exact sampling).
                let motion = Motion::new(from, to);
                for k in 0..=2000 {
                    let t = t_safe * k as f64 / 2000.0;
                    assert!(!checker.collides_at(motion.at(t)).unwrap(), "t = {t}");
                }
            }
            Ok(MotionCheck::Collides { .. }) => {}
            other => panic!("budget {budget}: {other:?}"),
        }
    }
    assert!(undecided > 0, "a budget of one interval must run out");
}

#[test]
fn budget_counts_all_pieces_and_later_pairs_bound_the_prefix() {
    // Two obstacles: the budget runs out on the first pair; the second
    // (far away) is certified over the same prefix by one interval.
    let near = ConvexUnion::from(cuboid([1.7, -0.5, -1.0], [1.9, -0.3, 1.0]));
    let far = ConvexUnion::from(cuboid([50.0, 50.0, 50.0], [51.0, 51.0, 51.0]));
    let checker = MotionChecker::new(&bar(), &[near, far])
        .unwrap()
        .with_budget(2);
    match checker.check(turn(45.0), turn(-45.0), 1e-9) {
        Err(MotionError::BudgetExhausted { t_safe, .. }) => assert!(t_safe > 0.0),
        other => panic!("{other:?}"),
    }
}

#[test]
fn regression_tolerance_below_what_the_search_can_bracket_is_refused() {
    let cube = ConvexUnion::from(cuboid([-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]));
    let checker = MotionChecker::new(&cube, std::slice::from_ref(&cube)).unwrap();
    let at = |x: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, 0.0));
    for bad in [1e-300, 1e-13, MIN_TOLERANCE / 2.0] {
        let err = checker.check(at(3.0), at(0.0), bad).unwrap_err();
        assert!(matches!(err, MotionError::Tolerance(_)), "{bad:e}: {err:?}");
        let message = err.to_string();
        assert!(message.contains("3.637978807091713e-12"), "{message}");
    }
    // The smallest accepted tolerance decides a head-on collision.
    let answer = checker.check(at(3.0), at(0.0), MIN_TOLERANCE).unwrap();
    let MotionCheck::Collides { t_safe, t_contact } = answer else {
        panic!("{answer:?}");
    };
    assert!(t_contact - t_safe.unwrap() <= MIN_TOLERANCE);
    assert!((t_contact - 2.0 / 3.0).abs() <= MIN_TOLERANCE);
}
