//! Obstacles given in their own frame with a pose (issue 34: a newcomer
//! had to move vertices by hand): `Body::placed` poses the vertices once
//! and keeps what the cleaning decided. Oracle: the same obstacle built
//! from vertices posed by hand with the same `Pose::apply` (the same f64
//! coordinates) answers identically, state for state and motion for
//! motion, on the convex and the triangle paths.

use dymsum::query::{Body, ConvexUnion, MotionCheck, Validator};
use dymsum::{DVec3, PolygonMesh, Pose, Rotation};
use dymsum_testkit::cuboid;

fn two_boxes() -> PolygonMesh {
    let mut m = cuboid([0.0; 3], [1.0; 3]).to_mesh();
    let b = cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]).to_mesh();
    let base = m.vertices.len();
    m.vertices.extend(b.vertices);
    m.faces
        .extend(b.faces.iter().map(|f| f.iter().map(|v| v + base).collect()));
    m
}

fn posed_by_hand(m: &PolygonMesh, pose: Pose) -> PolygonMesh {
    PolygonMesh::new(
        m.vertices
            .iter()
            .map(|&v| pose.apply(DVec3::from(v)).to_array())
            .collect(),
        m.faces.clone(),
    )
}

#[test]
fn a_placed_obstacle_answers_as_one_moved_by_hand() {
    let pose = Pose::new(
        Rotation::from_axis_angle(DVec3::new(1.0, 2.0, 0.5), 0.7).unwrap(),
        DVec3::new(3.0, -1.0, 2.5),
    );
    let robot = Body::Convex(ConvexUnion::from(cuboid([-0.2; 3], [0.2; 3])));
    for (name, mesh) in [
        ("touching boxes", two_boxes()),
        ("one box", cuboid([0.0; 3], [1.0, 2.0, 0.5]).to_mesh()),
    ] {
        let placed = Body::from_mesh(&mesh).unwrap().placed(pose).unwrap();
        let by_hand = Body::from_mesh(&posed_by_hand(&mesh, pose)).unwrap();
        assert_eq!(placed.is_convex(), by_hand.is_convex(), "{name}");
        let a = Validator::new(&robot, &[placed]).unwrap();
        let b = Validator::new(&robot, &[by_hand]).unwrap();
        for i in 0..400 {
            let f = i as f64;
            let t = DVec3::new(
                1.0 + (f * 0.37).sin() * 2.5,
                (f * 0.53).cos() * 2.5,
                2.0 + (f * 0.71).sin() * 2.5,
            );
            let at = Pose::new(
                Rotation::from_axis_angle(DVec3::new(f.cos(), 1.0, f.sin()), f).unwrap(),
                t,
            );
            assert_eq!(
                a.collides_at(at).unwrap(),
                b.collides_at(at).unwrap(),
                "{name} {i}"
            );
            if i % 20 == 0 {
                let to = Pose::new(at.rotation, t + DVec3::new(-2.0, 1.0, 0.5));
                let (ma, mb) = (
                    a.check(at, to, 1e-6).unwrap(),
                    b.check(at, to, 1e-6).unwrap(),
                );
                match (ma, mb) {
                    (MotionCheck::Free, MotionCheck::Free) => {}
                    (
                        MotionCheck::Collides { t_contact: x, .. },
                        MotionCheck::Collides { t_contact: y, .. },
                    ) => assert_eq!(x, y, "{name} {i}"),
                    other => panic!("{name} {i}: {other:?}"),
                }
            }
        }
    }
}

#[test]
fn a_pose_that_is_not_finite_is_refused() {
    let body = Body::from_mesh(&two_boxes()).unwrap();
    let bad = Pose::new(Rotation::IDENTITY, DVec3::new(f64::NAN, 0.0, 0.0));
    assert!(body.placed(bad).is_err());
    let convex = Body::Convex(ConvexUnion::from(cuboid([0.0; 3], [1.0; 3])));
    assert!(convex.placed(bad).is_err());
}
