//! Review (A): the convex motion search's ball test (`certified_free`,
//! query/motion.rs) trusts `segment_distance` (query/motion.rs), whose
//! `l2 = |b − a|²` overflows to `inf` once the translations of an interval
//! differ by more than ~1.34e154.
//! Then `t = (p − a)·d / l2 = 0`, the "distance" from the obstacle's centre
//! to the segment is `|a|`, far above the true distance (here 0: the
//! segment passes straight through the obstacle), and the interval is
//! certified free without any further test.

use dymsum::query::{ConvexUnion, MotionCheck, MotionChecker};
use dymsum::{DVec3, Pose, Rotation};
use dymsum_testkit::cuboid;

fn at(x: f64) -> Pose {
    Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, 0.0))
}

fn run(half: f64, from: f64, to: f64) {
    let body = ConvexUnion::from(cuboid([-half; 3], [half; 3]));
    let block = ConvexUnion::from(cuboid([-half; 3], [half; 3]));
    let checker = MotionChecker::new(&body, &[block]).unwrap();
    // Free at the start, colliding at translation 0 (which the straight
    // motion from `from` to `to` passes through).
    assert!(!checker.collides_at(at(from)).unwrap());
    assert!(checker.collides_at(at(0.0)).unwrap());
    let answer = checker.check(at(from), at(to), 1e-6);
    eprintln!("{half:e} {from:e} {to:e}: {answer:?}");
    assert!(
        !matches!(answer, Ok(MotionCheck::Free)),
        "a motion straight through the obstacle certified free: {answer:?}"
    );
}

#[test]
fn huge_translation_through_the_obstacle_is_not_free() {
    // Bodies 2e145 wide (not collapsed by rounding at 7e153), moving from
    // 7e153 left of the obstacle to 7e153 right of it: |a|², |b|² and
    // (p − a)·d are finite (so `seg_err` is too), |b − a|² = 1.96e308 is
    // not, t = 0 and the "distance" is |a| = 7e153; the true one is 0.
    run(1e145, -7e153, 7e153);
}
