//! Issue 9 §2: the library's structures own their shapes. A program can keep
//! a tracker, a dynamic sum, a prepared pair and a C-obstacle in its own
//! struct with no lifetime parameter, build it in one function, and move it
//! to another thread; the answers equal fresh static computations.

use dymsum::query::{CObstacle, ContactTracker, ConvexPair, ConvexUnion};
use dymsum::{minkowski_sum_posed, DVec3, DynamicSum, Method, Polytope, Pose, Rotation};

/// What a physics or planning program would keep between frames.
struct World {
    tracker: ContactTracker,
    sum: DynamicSum,
    pair: ConvexPair,
    slicer: CObstacle,
    union: ConvexUnion,
}

fn assert_send_sync<T: Send + Sync + 'static>() {}

fn cuboid(x: f64, y: f64, z: f64) -> Polytope {
    let pts: Vec<[f64; 3]> = (0..8)
        .map(|i| {
            let s = |b: u32| if i >> b & 1 == 1 { 1.0 } else { -1.0 };
            [s(0) * x, s(1) * y, s(2) * z]
        })
        .collect();
    Polytope::from_points(&pts).unwrap()
}

/// Builds the world from shapes that go out of scope here: the world keeps
/// its own handles.
fn build_world() -> World {
    let a = cuboid(1.0, 0.5, 0.25);
    let b = cuboid(0.5, 0.5, 0.5);
    let pair = ConvexPair::new(&a, &b).unwrap();
    let near = Pose::new(Rotation::IDENTITY, DVec3::new(1.2, 0.0, 0.0));
    World {
        tracker: pair.tracker(Pose::IDENTITY, near).unwrap(),
        sum: DynamicSum::new(&a, Pose::IDENTITY, &b, Pose::IDENTITY).unwrap(),
        slicer: CObstacle::new(&a, &b).unwrap(),
        union: ConvexUnion::new(vec![a.clone(), b.clone()]).unwrap(),
        pair,
    }
}

#[test]
fn world_without_lifetimes_is_send_sync_and_owns_its_shapes() {
    assert_send_sync::<World>();
    assert_send_sync::<Polytope>();
    let world = build_world();
    let handle = std::thread::spawn(move || {
        let mut world = world;
        let near = Pose::new(Rotation::IDENTITY, DVec3::new(1.2, 0.0, 0.0));
        for k in 1..=20 {
            let turn =
                Rotation::from_axis_angle(DVec3::new(0.3, -0.5, 0.8), 0.05 * k as f64).unwrap();
            let pose = Pose::new(turn, DVec3::ZERO);
            let tracked = world.tracker.update(pose, near).unwrap();
            assert_eq!(tracked, world.pair.query(pose, near).unwrap(), "step {k}");
            world.sum.set_pose_p(pose);
            let fresh = minkowski_sum_posed(
                world.sum.p(),
                pose,
                world.sum.q(),
                Pose::IDENTITY,
                Method::Walk,
            )
            .unwrap();
            assert_eq!(world.sum.sum().facets(), fresh.facets(), "step {k}");
        }
        let slices: Vec<_> = world
            .slicer
            .slices(&[Rotation::IDENTITY])
            .collect::<Result<_, _>>()
            .unwrap();
        assert_eq!(slices.len(), 1);
        assert_eq!(world.union.pieces().len(), 2);
        world
    });
    let world = handle.join().expect("the worker thread panicked");
    assert!(world.pair.a().same_data(world.sum.p()));
}

#[test]
fn cloning_a_polytope_shares_its_data() {
    let a = cuboid(1.0, 2.0, 3.0);
    let b = a.clone();
    assert!(a.same_data(&b));
    assert!(!a.same_data(&cuboid(1.0, 2.0, 3.0)));
    assert_eq!(a.vertices(), b.vertices());
}
