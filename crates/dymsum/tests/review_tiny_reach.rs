//! Review (A): `radius_about` (query/motion.rs) measures the reach `r`
//! with `(v − c).length()`, whose squares underflow for coordinates below
//! ~1.6e-162 (they round to a multiple of the smallest subnormal, or to 0),
//! so `r` can be far below the true vertex norm. The sagitta `2 r sin²(δ/4)`
//! and the pose rounding bound are then too small, and a turn whose arc
//! sweeps through an obstacle beside the chord is certified free. (LIMITS.md:
//! "Any overall scale is supported, from about 1e-300 to 1e300".)

use dymsum::query::{ConvexUnion, MotionCheck, MotionChecker};
use dymsum::{DVec3, Pose, Rotation};
use dymsum_testkit::cuboid;

fn turn(deg: f64) -> Pose {
    Pose::new(
        Rotation::from_axis_angle(DVec3::Z, deg.to_radians()).unwrap(),
        DVec3::ZERO,
    )
}

#[test]
fn a_tiny_turn_through_an_obstacle_is_not_free() {
    // X² = 1.49 of the smallest subnormal: rounded to 1 of it, so the
    // computed reach is 2.22e-162 for a true 2.71e-162.
    let x = 2.71e-162;
    let h = 2e-164;
    let body = ConvexUnion::from(cuboid([x - h, -h, -h], [x, h, h]));
    // Beside the chord of the turn, within the arc (at 90° the body's
    // outer end is at (0, x, 0)).
    let block = ConvexUnion::from(cuboid(
        [-5e-163, 2.45e-162, -5e-163],
        [5e-163, 3e-162, 5e-163],
    ));
    let checker = MotionChecker::new(&body, &[block]).unwrap();
    assert!(!checker.collides_at(turn(0.0)).unwrap());
    assert!(!checker.collides_at(turn(179.0)).unwrap());
    assert!(
        checker.collides_at(turn(90.0)).unwrap(),
        "at 90° the body is inside the block"
    );
    let answer = checker.check(turn(0.0), turn(179.0), 1e-6);
    assert!(
        !matches!(answer, Ok(MotionCheck::Free)),
        "a turn sweeping through the block certified free: {answer:?}"
    );
    eprintln!("{answer:?}");
}

/// The same configuration scaled by 2^540 (exactly): decided as colliding.
#[test]
fn the_same_turn_at_unit_scale_collides() {
    let s = 2f64.powi(540);
    let (x, h) = (2.71e-162 * s, 2e-164 * s);
    let body = ConvexUnion::from(cuboid([x - h, -h, -h], [x, h, h]));
    let block = ConvexUnion::from(cuboid(
        [-5e-163 * s, 2.45e-162 * s, -5e-163 * s],
        [5e-163 * s, 3e-162 * s, 5e-163 * s],
    ));
    let checker = MotionChecker::new(&body, &[block]).unwrap();
    let answer = checker.check(turn(0.0), turn(179.0), 1e-6);
    assert!(
        matches!(answer, Ok(MotionCheck::Collides { .. })),
        "{answer:?}"
    );
}
