//! The `Checker` trait (issue 34): its batches, written once, answer
//! exactly what the single calls answer, in order, for the convex checker,
//! the triangle checker and both kinds of `Validator`; a validator answers
//! what the checker it holds answers; and the work counted by `steps` is
//! the same one by one and in a batch.

use dymsum::query::{
    Body, Checker, ConvexUnion, MeshBody, MotionCheck, MotionChecker, MotionError, SceneChecker,
    Validator,
};
use dymsum::{DVec3, Pose};
use dymsum_testkit::{cuboid, random_rotation, rng};
use rand::Rng;

/// A body of two boxes, and obstacles: three boxes and a floor.
fn bodies() -> (ConvexUnion, Vec<ConvexUnion>) {
    let body = ConvexUnion::new(vec![
        cuboid([-0.5, -0.2, -0.2], [0.5, 0.2, 0.2]),
        cuboid([0.3, -0.5, -0.1], [0.5, 0.5, 0.1]),
    ])
    .unwrap();
    let obstacles = [
        ([1.0, -1.0, -1.0], [1.4, 1.0, 1.0]),
        ([-2.0, 1.0, -0.5], [-1.0, 2.0, 0.5]),
        ([0.0, -2.5, -0.3], [0.6, -1.9, 0.3]),
        ([-4.0, -4.0, -2.0], [4.0, 4.0, -1.5]),
    ]
    .map(|(lo, hi)| ConvexUnion::from(cuboid(lo, hi)))
    .to_vec();
    (body, obstacles)
}

/// Poses around the obstacles (some colliding), and motions between them.
fn poses_and_motions() -> (Vec<Pose>, Vec<(Pose, Pose)>) {
    let mut r = rng(34);
    let poses: Vec<Pose> = (0..48)
        .map(|_| {
            let t = DVec3::new(
                r.random_range(-3.0..3.0),
                r.random_range(-3.0..3.0),
                r.random_range(-1.2..1.2),
            );
            Pose::new(random_rotation(&mut r), t)
        })
        .collect();
    let motions = poses
        .iter()
        .zip(poses.iter().rev())
        .map(|(&a, &b)| (a, b))
        .collect();
    (poses, motions)
}

/// The batches of `checker` against its single calls (and the steps of a
/// batch against those of the single calls on `twin`, a fresh copy); which
/// motions are free.
fn batches_equal_single_calls<C: Checker>(checker: &C, twin: &C, name: &str) -> Vec<bool> {
    let (poses, motions) = poses_and_motions();
    let single: Vec<bool> = poses
        .iter()
        .map(|&p| checker.collides_at(p).unwrap())
        .collect();
    assert_eq!(checker.collides_many(&poses).unwrap(), single, "{name}");
    assert!(
        single.iter().any(|&c| c) && single.iter().any(|&c| !c),
        "{name}"
    );
    let tol = 1e-6;
    let before = twin.steps();
    let single: Vec<MotionCheck> = motions
        .iter()
        .map(|&(a, b)| twin.check(a, b, tol).unwrap())
        .collect();
    let used = twin.steps() - before;
    let before = checker.steps();
    assert_eq!(checker.check_many(&motions, tol).unwrap(), single, "{name}");
    assert_eq!(checker.steps() - before, used, "{name}: the work counted");
    let free: Vec<bool> = single.iter().map(MotionCheck::is_free).collect();
    assert!(free.contains(&true) && free.contains(&false), "{name}");
    // An error of the batch is one of the single calls' errors.
    let bad = checker.check_many(&motions, 0.0).unwrap_err();
    assert_eq!(bad, MotionError::Tolerance(0.0), "{name}");
    free
}

#[test]
fn batches_equal_single_calls_for_every_checker() {
    let (body, obstacles) = bodies();
    let convex = || MotionChecker::new(&body, &obstacles).unwrap();
    let meshes: Vec<MeshBody> = obstacles.iter().map(MeshBody::from_union).collect();
    let scene = || SceneChecker::new(&MeshBody::from_union(&body), &meshes).unwrap();
    let a = batches_equal_single_calls(&convex(), &convex(), "convex");
    let b = batches_equal_single_calls(&scene(), &scene(), "scene");
    // Both certified, by different bounds: the same motions are free.
    assert_eq!(a, b, "free motions: convex, scene");
    // Validators of both kinds: convex bodies, and an open (non-convex)
    // obstacle that sends them to the triangles.
    let bodies: Vec<Body> = obstacles.iter().cloned().map(Body::from).collect();
    let robot = Body::from(body.clone());
    let convex_validator = || Validator::new(&robot, &bodies).unwrap();
    assert!(matches!(convex_validator(), Validator::Convex(_)));
    batches_equal_single_calls(
        &convex_validator(),
        &convex_validator(),
        "validator (convex)",
    );
    let mut open = cuboid([-1.0, 2.5, -1.0], [1.0, 3.5, 1.0]).to_mesh();
    open.faces.pop();
    let mut with_open = bodies.clone();
    with_open.push(Body::from_mesh(&open).unwrap());
    let mesh_validator = || Validator::new(&robot, &with_open).unwrap();
    assert!(matches!(mesh_validator(), Validator::Mesh(_)));
    batches_equal_single_calls(&mesh_validator(), &mesh_validator(), "validator (mesh)");
}

#[test]
fn a_validator_answers_what_its_checker_answers() {
    let (body, obstacles) = bodies();
    let bodies: Vec<Body> = obstacles.iter().cloned().map(Body::from).collect();
    let validator = Validator::new(&Body::from(body.clone()), &bodies)
        .unwrap()
        .with_budget(300);
    let direct = MotionChecker::new(&body, &obstacles)
        .unwrap()
        .with_budget(300);
    assert_eq!(Checker::budget(&validator), 300);
    assert_eq!(validator.checker().budget(), 300);
    let (poses, motions) = poses_and_motions();
    for &p in &poses {
        assert_eq!(
            Checker::collides_at(&validator, p),
            direct.collides_at(p),
            "{p:?}"
        );
        assert_eq!(
            Checker::distance_at(&validator, p),
            direct.distance_at(p),
            "{p:?}"
        );
    }
    for &(a, b) in &motions {
        assert_eq!(
            Checker::check(&validator, a, b, 1e-6),
            direct.check(a, b, 1e-6)
        );
    }
    assert_eq!(Checker::steps(&validator), direct.steps());
    // Through the trait, as a trait object, and through `Deref`: alike.
    let dynamic: &dyn Checker = &validator;
    assert_eq!(
        dynamic.check_many(&motions, 1e-6),
        direct.check_many(&motions, 1e-6)
    );
    assert_eq!(
        Checker::collides_many(&validator, &poses),
        validator.checker().collides_many(&poses)
    );
}

#[test]
fn with_budget_through_the_trait_bounds_the_work() {
    fn tight<C: Checker>(checker: C) -> C {
        checker.with_budget(3)
    }
    let (body, obstacles) = bodies();
    let convex = tight(MotionChecker::new(&body, &obstacles).unwrap());
    let meshes: Vec<MeshBody> = obstacles.iter().map(MeshBody::from_union).collect();
    let scene = tight(SceneChecker::new(&MeshBody::from_union(&body), &meshes).unwrap());
    let (_, motions) = poses_and_motions();
    for checker in [&convex as &dyn Checker, &scene] {
        assert_eq!(checker.budget(), 3);
        let mut spent = 0;
        for &(a, b) in &motions {
            let before = checker.steps();
            match checker.check(a, b, 1e-6) {
                Ok(_) => {}
                Err(MotionError::BudgetExhausted { steps, .. }) => {
                    assert_eq!(steps, 3);
                    spent += 1;
                }
                Err(e) => panic!("{e}"),
            }
            assert!(checker.steps() - before <= 3);
        }
        assert!(spent > 0);
    }
}
