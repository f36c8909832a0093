//! The motion-check workloads shared by the `motion_vs_parry` bench and its
//! agreement check: a body, obstacles and straight motions between two
//! poses (translation linear, rotation by slerp), and the same motions for
//! parry3d-f64's nonlinear shape cast (conservative advancement with a
//! tolerance: constant linear and angular velocity over `t ∈ [0, 1]`, which
//! is exactly the slerp motion about the body's origin).

use crate::contact::{parry_pose, parry_shape};
use dymsum::query::ConvexUnion;
use dymsum::{DVec3, Polytope, Pose, Rotation};
use parry3d_f64::math::Vector;
use parry3d_f64::query::{cast_shapes_nonlinear, NonlinearRigidMotion};
use parry3d_f64::shape::ConvexPolyhedron;
use rand::Rng;
use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// A body, its obstacles (convex, world frame) and motions `(from, to)`.
pub struct Scene {
    /// The scene's name in the tables.
    pub name: &'static str,
    /// The moving body (its own frame).
    pub body: Polytope,
    /// The obstacles, placed in the world frame.
    pub obstacles: Vec<Polytope>,
    /// The motions.
    pub motions: Vec<(Pose, Pose)>,
}

impl Scene {
    /// The body as a union (for `MotionChecker`).
    pub fn body_union(&self) -> ConvexUnion {
        ConvexUnion::from(self.body.clone())
    }
    /// The obstacles as unions (for `MotionChecker`).
    pub fn obstacle_unions(&self) -> Vec<ConvexUnion> {
        self.obstacles
            .iter()
            .cloned()
            .map(ConvexUnion::from)
            .collect()
    }
}

/// An axis-aligned box.
///
/// # Panics
/// For an empty box.
pub fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> Polytope {
    let corners: Vec<[f64; 3]> = (0..8)
        .map(|i| {
            let pick = |k: usize| if i >> k & 1 == 0 { lo[k] } else { hi[k] };
            [pick(0), pick(1), pick(2)]
        })
        .collect();
    Polytope::from_points(&corners).expect("a box")
}

fn about_z(rad: f64) -> Rotation {
    Rotation::from_axis_angle(DVec3::Z, rad).expect("z")
}

fn random_unit(r: &mut ChaCha8Rng) -> DVec3 {
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

/// Points on a sphere of radius `radius` about `c`: their hull.
fn round_hull(n: usize, radius: f64, c: DVec3, r: &mut ChaCha8Rng) -> Polytope {
    let pts: Vec<DVec3> = (0..n).map(|_| c + random_unit(r) * radius).collect();
    Polytope::from_dvec3s(&pts).expect("a round hull")
}

/// The scenes, `count` motions each:
///
/// * `thin_wall`: a box of side 0.05 crossing 10 units through a wall
///   0.002 thick (about half the motions pass beside it), turning a
///   little;
/// * `turning_bar`: a bar 4 long turning up to 90° about its centre past a
///   block near its tip (about half sweep through it between free ends);
/// * `planner_short`: a 20-vertex round hull making short moves (up to 0.5
///   and 0.5 rad) among three round obstacles of 60 vertices, as a
///   sampling planner's local steps (some collide, most come close).
///
/// # Panics
/// Never for these fixed shapes (their hulls are built with `expect`).
pub fn scenes(count: usize) -> Vec<Scene> {
    let mut r = ChaCha8Rng::seed_from_u64(20);
    let small = cuboid([-0.025; 3], [0.025; 3]);
    let wall = cuboid([5.049, -5.0, -5.0], [5.051, 5.0, 5.0]);
    let thin_wall = (0..count)
        .map(|_| {
            let y = r.random_range(-8.0..8.0);
            let z = r.random_range(-1.0..1.0);
            (
                Pose::new(about_z(r.random_range(-0.2..0.2)), DVec3::new(0.0, y, z)),
                Pose::new(about_z(r.random_range(-0.2..0.2)), DVec3::new(10.0, y, z)),
            )
        })
        .collect();
    let bar = cuboid([-2.0, -0.05, -0.05], [2.0, 0.05, 0.05]);
    let block = cuboid([1.7, 0.6, -1.0], [1.9, 0.8, 1.0]);
    let turning = (0..count)
        .map(|_| {
            let a = r.random_range(-1.2..0.2);
            let b = a + r.random_range(0.3..1.5);
            (
                Pose::new(about_z(a), DVec3::ZERO),
                Pose::new(about_z(b), DVec3::ZERO),
            )
        })
        .collect();
    let robot = round_hull(20, 0.5, DVec3::ZERO, &mut r);
    let obstacles: Vec<Polytope> = [
        DVec3::new(1.5, 0.0, 0.0),
        DVec3::new(-1.0, 1.2, 0.3),
        DVec3::new(0.0, -1.4, -0.5),
    ]
    .iter()
    .map(|&c| round_hull(60, 0.8, c, &mut r))
    .collect();
    let short = (0..count)
        .map(|_| {
            let rot = |r: &mut ChaCha8Rng| {
                Rotation::from_axis_angle(random_unit(r), r.random_range(0.0..std::f64::consts::PI))
                    .expect("unit axis")
            };
            let from = Pose::new(
                rot(&mut r),
                DVec3::new(
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                ),
            );
            let turn = Rotation::from_axis_angle(random_unit(&mut r), r.random_range(0.0..0.5))
                .expect("unit axis");
            let to = Pose::new(
                from.rotation.then(&turn),
                from.translation + random_unit(&mut r) * r.random_range(0.0..0.5),
            );
            (from, to)
        })
        .collect();
    vec![
        Scene {
            name: "thin_wall",
            body: small,
            obstacles: vec![wall],
            motions: thin_wall,
        },
        Scene {
            name: "turning_bar",
            body: bar,
            obstacles: vec![block],
            motions: turning,
        },
        Scene {
            name: "planner_short",
            body: robot,
            obstacles,
            motions: short,
        },
    ]
}

/// parry's shapes of a scene's body and obstacles.
pub fn parry_shapes(scene: &Scene) -> (ConvexPolyhedron, Vec<ConvexPolyhedron>) {
    (
        parry_shape(&scene.body),
        scene.obstacles.iter().map(parry_shape).collect(),
    )
}

/// parry's answer for one motion: the earliest time of impact over the
/// obstacles (`None`: no impact in `[0, 1]`), from `cast_shapes_nonlinear`
/// with the body rotating about its origin at constant rate (slerp's motion).
///
/// # Panics
/// If parry does not support convex polyhedra (it does).
pub fn parry_time_of_impact(
    body: &ConvexPolyhedron,
    obstacles: &[ConvexPolyhedron],
    from: Pose,
    to: Pose,
) -> Option<f64> {
    let turn = to.rotation.quat() * from.rotation.quat().inverse();
    let turn = if turn.w < 0.0 { -turn } else { turn };
    let (axis, angle) = turn.to_axis_angle();
    let angvel = axis * angle;
    let moving = NonlinearRigidMotion::new(
        parry_pose(from),
        Vector::ZERO,
        {
            let d = to.translation - from.translation;
            Vector::new(d.x, d.y, d.z)
        },
        Vector::new(angvel.x, angvel.y, angvel.z),
    );
    let fixed = NonlinearRigidMotion::constant_position(parry_pose(Pose::IDENTITY));
    obstacles
        .iter()
        .filter_map(|o| {
            cast_shapes_nonlinear(&moving, body, &fixed, o, 0.0, 1.0, true)
                .expect("convex polyhedra are supported")
                .map(|hit| hit.time_of_impact)
        })
        .min_by(f64::total_cmp)
}
