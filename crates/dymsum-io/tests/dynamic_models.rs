//! The dynamic sum (`dymsum::DynamicSum`) on the real models: the paper's
//! models from the built-in library (Fogel's files where they exist) and the
//! tessellated cubes. After every step the dynamic facets must equal the
//! static `walk` facets at the same poses and the update report must be the
//! exact diff; the hull-of-pairwise-sums oracle runs at the end of each run.
//! The oracles are shared with `dymsum/tests/dynamic_sums.rs`.

use dymsum::dynamic::DynamicConfig;
use dymsum::polytope::MeshPolicy;
use dymsum::{DVec3, DynamicSum, Polytope, Pose, Rotation};
use dymsum_io::models::model;
use dymsum_testkit::oracle::*;
use dymsum_testkit::*;
use std::f64::consts::{FRAC_PI_2, TAU};

fn load(name: &str) -> Polytope {
    let mesh = model(name).unwrap_or_else(|e| panic!("model {name}: {e}"));
    let (p, _) = Polytope::from_mesh(&mesh, MeshPolicy::default())
        .unwrap_or_else(|e| panic!("model {name}: {e}"));
    p
}

fn load_file(file: &str) -> Polytope {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("models/fogel")
        .join(file);
    let mesh = dymsum_io::formats::read_mesh(&path).unwrap_or_else(|e| panic!("{file}: {e}"));
    let (p, _) =
        Polytope::from_mesh(&mesh, MeshPolicy::default()).unwrap_or_else(|e| panic!("{file}: {e}"));
    p
}

fn rot(axis: DVec3, angle: f64) -> Rotation {
    Rotation::from_axis_angle(axis, angle).unwrap()
}

/// `steps` steps of the paper's motion at a fixed `steps_per_turn` (axis
/// held for 1..=50 steps), checked against walk after every step; the
/// hull-of-sums oracle and the sanity check at the end.
fn run(p_name: &str, q_name: &str, steps_per_turn: f64, steps: usize, seed: u64) {
    run_with(
        p_name,
        q_name,
        steps_per_turn,
        steps,
        seed,
        DynamicConfig::default(),
    );
}

/// Never falls back to a from-scratch `walk`.
const INCREMENTAL: DynamicConfig = DynamicConfig {
    max_step_angle: f64::INFINITY,
    fallback_fraction: f64::INFINITY,
};

fn run_with(
    p_name: &str,
    q_name: &str,
    steps_per_turn: f64,
    steps: usize,
    seed: u64,
    cfg: DynamicConfig,
) {
    let (p, q) = (&load(p_name), &load(q_name));
    let mut r = rng(seed);
    let start = Pose::new(random_rotation(&mut r), DVec3::new(1.0, -2.0, 0.5));
    let d = DynamicSum::with_config(p, start, q, Pose::IDENTITY, cfg).unwrap();
    let mut c = Checked::new(
        d,
        0,
        format!("{p_name}+{q_name} X={steps_per_turn} seed={seed} {cfg:?}"),
    );
    let mut motion = PaperMotion::new(seed, Some(steps_per_turn), 0.0);
    let mut changes = 0;
    for _ in 0..steps {
        let rep = motion.apply(&mut c);
        changes += rep.removed.len();
    }
    c.deep_check().unwrap_or_else(|e| panic!("{e}"));
    eprintln!(
        "{p_name}+{q_name} X={steps_per_turn}: {steps} steps, {changes} facets changed, {} recomputed",
        c.recomputed
    );
}

const PAIRS: [(&str, &str); 5] = [
    ("ellipse", "gs4"),
    ("ti", "vrod"),
    ("cube", "cone"),
    ("dd", "hp"),
    ("tcube:2", "tcube:2"),
];

#[test]
fn model_pairs_500_steps_per_turn() {
    for (i, (p, q)) in PAIRS.iter().enumerate() {
        run(p, q, 500.0, 200, 100 + i as u64);
    }
}

#[test]
fn model_pairs_10_steps_per_turn() {
    for (i, (p, q)) in PAIRS.iter().enumerate() {
        run(p, q, 10.0, 50, 200 + i as u64);
    }
}

/// The same pairs with the fallback switched off: the certified
/// incremental update on every step, also at 10 steps per turn.
#[test]
fn model_pairs_always_incremental() {
    for (i, (p, q)) in PAIRS.iter().enumerate() {
        run_with(p, q, 10.0, 50, 500 + i as u64, INCREMENTAL);
        run_with(p, q, 500.0, 200, 600 + i as u64, INCREMENTAL);
        run_with(p, q, 100_000.0, 100, 700 + i as u64, INCREMENTAL);
    }
}

/// Every Fogel file paired with the next one, read from disk, under the
/// paper's mixed protocol (steps per turn from 10 to 100,000, jumps).
#[test]
fn fogel_files_mixed_protocol() {
    let files = [
        "cube.off",
        "dioctagonal_dipyramid.off",
        "ellipsoid.off",
        "ellipsoid_1.0_0.5_0.5.off",
        "geodesic_sphere1.off",
        "geodesic_sphere2.off",
        "geodesic_sphere3.off",
        "geodesic_sphere4.off",
        "hexagonal_pyramid.off",
        "triakis_icosahedron.off",
        "truncated_icosidodecahedron.off",
    ];
    for i in 0..files.len() {
        let (a, b) = (files[i], files[(i + 1) % files.len()]);
        let (p, q) = (&load_file(a), &load_file(b));
        let mut r = rng(300 + i as u64);
        let mut c = Checked::start(
            p,
            Pose::new(random_rotation(&mut r), DVec3::ZERO),
            q,
            Pose::IDENTITY,
            0,
            format!("{a}+{b}"),
        );
        let mut motion = PaperMotion::new(300 + i as u64, None, 0.05);
        for _ in 0..40 {
            motion.apply(&mut c);
        }
        c.deep_check().unwrap_or_else(|e| panic!("{e}"));
    }
}

/// Both models turning, Q about its own axis, and the fallback switched
/// off (every step incremental).
#[test]
fn models_both_moving_always_incremental() {
    let incremental = INCREMENTAL;
    for (i, (pn, qn)) in [("gs2", "t"), ("ti", "dd"), ("cylinder", "cone")]
        .iter()
        .enumerate()
    {
        let (p, q) = (&load(pn), &load(qn));
        let d = DynamicSum::with_config(p, Pose::IDENTITY, q, Pose::IDENTITY, incremental).unwrap();
        let mut c = Checked::new(d, 0, format!("{pn}+{qn} both moving"));
        let mut r = rng(400 + i as u64);
        let (ap, aq) = (random_axis(&mut r), random_axis(&mut r));
        for k in 1..=60 {
            let pp = Pose::new(
                rot(ap, k as f64 * TAU / 100.0),
                DVec3::new(k as f64, 0.0, 0.0),
            );
            let pq = Pose::new(rot(aq, -(k as f64) * TAU / 77.0), DVec3::ZERO);
            c.set_pose(pp, pq);
        }
        // A few large steps, incremental too.
        for angle in [0.5, 1.5, 3.0] {
            let mut pp = c.d.pose_p();
            pp.rotation = pp.rotation.then(&rot(random_axis(&mut r), angle));
            let pq = c.d.pose_q();
            c.set_pose(pp, pq);
        }
        c.deep_check().unwrap_or_else(|e| panic!("{e}"));
    }
}

/// Tessellated cubes (`tcube:3`, a cube after face merging) with each other
/// and with the cube model: turning about z through exact quarter turns,
/// and tiny turns off the aligned pose.
#[test]
fn tessellated_cubes_through_quarter_turns() {
    let t3 = &load("tcube:3");
    assert_eq!(t3.face_count(), 6);
    for (label, q) in [("tcube:3", t3), ("cube", &load("cube"))] {
        let mut c = Checked::start(t3, Pose::IDENTITY, q, Pose::IDENTITY, 4, label);
        for k in 1..=8 {
            for _ in 0..10 {
                c.rotate_p_by(rot(DVec3::Z, TAU / 40.0));
            }
            c.set_pose_p(Pose::new(rot(DVec3::Z, k as f64 * FRAC_PI_2), DVec3::ZERO));
            if label == "tcube:3" {
                assert_eq!(
                    c.d.try_to_mesh().unwrap().faces.len(),
                    6,
                    "{label} at {k}·90°"
                );
            }
        }
        for angle in [1e-12, 1e-9, 1e-6] {
            c.rotate_p_by(rot(DVec3::new(1.0, 2.0, 3.0), angle));
            c.set_pose_p(Pose::IDENTITY);
        }
    }
}
