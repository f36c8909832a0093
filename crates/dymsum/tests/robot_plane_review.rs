//! Review of the joint-space motion search's plane certificate
//! (2026-11-29, `dymsum::robot::motion`): a pair whose hulls are within
//! the rounding margin of each other while their meshes are far apart can
//! never be certified by the plane; the search must walk it, not halve
//! until it gives up.

use dymsum::query::MeshBody;
use dymsum::robot::shapes::box_mesh;
use dymsum::robot::{JointKind, JointSpec, LinkSpec, Robot, RobotChecker};
use dymsum::{DVec3, Pose, Rotation};

fn block(size: DVec3, centre: DVec3) -> MeshBody {
    MeshBody::new(&box_mesh(size))
        .unwrap()
        .placed(Pose::new(Rotation::IDENTITY, centre))
        .unwrap()
}

/// A box on the root link rests `d` above the tops of two pillars (x in
/// ±[2, 3], z in [0, 1]) given as one obstacle: the obstacle's hull is `d`
/// below the box, its triangles 1.5 m aside. A hand far above turns
/// through a right angle. Free for every `d`, certified (the box never
/// moves: it ended undecided for `d` within the margin before the
/// review's mend).
#[test]
fn review_a_hull_gap_within_the_margin_is_walked_not_undecided() {
    let pillars = MeshBody::join(&[
        block(DVec3::new(1.0, 1.0, 1.0), DVec3::new(-2.5, 0.0, 0.5)),
        block(DVec3::new(1.0, 1.0, 1.0), DVec3::new(2.5, 0.0, 0.5)),
    ]);
    for d in [1e-11, 3e-11, 5e-11, 1e-9, 1e-3] {
        let links = vec![
            LinkSpec {
                name: "base".into(),
                body: Some(block(
                    DVec3::new(1.0, 1.0, 0.5),
                    DVec3::new(0.0, 0.0, 1.25 + d),
                )),
            },
            LinkSpec {
                name: "hand".into(),
                body: Some(block(DVec3::splat(0.2), DVec3::new(0.3, 0.0, 0.0))),
            },
        ];
        let joint = JointSpec {
            name: "wrist".into(),
            kind: JointKind::Revolute {
                lower: -2.0,
                upper: 2.0,
            },
            parent: "base".into(),
            child: "hand".into(),
            origin: Pose::new(Rotation::IDENTITY, DVec3::new(0.0, 0.0, 5.0)),
            axis: DVec3::Z,
            mimic: None,
        };
        let robot = Robot::new(links, vec![joint]).unwrap();
        let checker = RobotChecker::new(robot, std::slice::from_ref(&pillars)).unwrap();
        let answer = checker.check(&[0.0], &[std::f64::consts::FRAC_PI_2], 1e-6, 4096);
        assert!(
            matches!(answer, Ok(ref c) if c.is_free()),
            "d = {d}: {answer:?}"
        );
    }
}
