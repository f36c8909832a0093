//! The grazing family of issue 26 §4: a bar turning 90° past a thin plate
//! at its reach, at gaps from 1e-6 down to 0; prints each check's answer,
//! time and work.
use dymsum::query::{ConvexUnion, MotionChecker};
use dymsum::{DVec3, Polytope, Pose, Rotation};
use std::time::Instant;

fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> Polytope {
    let corners: Vec<[f64; 3]> = (0..8)
        .map(|i| {
            let pick = |k: usize| if i >> k & 1 == 0 { lo[k] } else { hi[k] };
            [pick(0), pick(1), pick(2)]
        })
        .collect();
    Polytope::from_points(&corners).unwrap()
}

fn main() {
    let bar = ConvexUnion::from(cuboid([0.0, -0.05, -0.05], [2.0, 0.05, 0.05]));
    let reach = (4.0f64 + 0.0025).sqrt();
    let gaps: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    for gap in gaps {
        let x = reach + gap;
        let plate = ConvexUnion::from(cuboid([x, -1.0, -1.0], [x + 0.01, 1.0, 1.0]));
        let checker = MotionChecker::new(&bar, &[plate]).unwrap();
        let turn = |deg: f64| {
            Pose::new(
                Rotation::from_axis_angle(DVec3::Z, deg.to_radians()).unwrap(),
                DVec3::ZERO,
            )
        };
        let t = Instant::now();
        let r = checker.check(turn(-45.0), turn(45.0), 1e-6);
        println!(
            "gap {gap:e}: {:?} in {:.4} s, {} steps, {:?}",
            r,
            t.elapsed().as_secs_f64(),
            checker.steps(),
            checker.stats()
        );
    }
}
