//! Adversarial motions for DYMSUM's kinetic schedule (issue 10 §1,
//! `dynamic/schedule.rs`), every step checked against a fresh `walk` by
//! `oracle::Checked`: step sizes jumping by more than 16× in random blocks
//! (the calendar re-files), runs about coordinate axes on grids and cubes
//! (tie deadlines, ended by generic turns), runs long enough to cross the
//! 1024-rad rebase of the accumulated rotation, and both bodies turning about
//! z with generic interruptions. (The crate's own unit tests add, on every
//! scheduled step, the check that each normal left in the queue passes the
//! old lazy-skip test.)
use dymsum::dynamic::DynamicConfig;
use dymsum::{DVec3, DynamicSum, Pose, Rotation};
use dymsum_testkit::oracle::*;
use dymsum_testkit::*;
use rand::Rng;

const INCREMENTAL: DynamicConfig = DynamicConfig {
    max_step_angle: f64::INFINITY,
    fallback_fraction: f64::INFINITY,
};

fn rot(axis: DVec3, angle: f64) -> Rotation {
    Rotation::from_axis_angle(axis, angle).unwrap()
}

fn kinds() -> [Kind; 5] {
    [
        Kind::Ball,
        Kind::Grid,
        Kind::Coplanar,
        Kind::Sphere,
        Kind::Cube,
    ]
}

fn make(seed: u64, cfg: DynamicConfig, label: &str) -> (Checked, rand_chacha::ChaCha8Rng) {
    let mut r = rng(seed);
    let kp = kinds()[r.random_range(0..5)];
    let kq = kinds()[r.random_range(0..5)];
    let np = r.random_range(6..30);
    let nq = r.random_range(6..30);
    let p = random_polytope(kp, np, &mut r);
    let q = random_polytope(kq, nq, &mut r);
    let d = DynamicSum::with_config(&p, Pose::IDENTITY, &q, Pose::IDENTITY, cfg).unwrap();
    (
        Checked::new(d, 0, format!("{label} seed {seed} {kp:?}{np} {kq:?}{nq}")),
        r,
    )
}

/// Step sizes jumping by more than 16x back and forth, axes mixing
/// coordinate axes and generic ones, both bodies sometimes moving.
#[test]
fn jumping_step_sizes_and_tie_runs() {
    for seed in 0..40u64 {
        for cfg in [INCREMENTAL, DynamicConfig::default()] {
            let (mut c, mut r) = make(seed, cfg, "jump");
            let sizes = [1e-5, 3e-4, 1e-2, 0.2, 1e-6];
            for _block in 0..30 {
                let s = sizes[r.random_range(0..sizes.len())];
                let axis = match r.random_range(0..4) {
                    0 => DVec3::X,
                    1 => DVec3::Y,
                    2 => DVec3::Z,
                    _ => oracle::random_axis(&mut r),
                };
                let both = r.random_bool(0.2);
                let len = r.random_range(1..40);
                for _ in 0..len {
                    let a = s * r.random_range(0.5..1.5);
                    if both {
                        let mut pp = c.d.pose_p();
                        pp.rotation = pp.rotation.then(&rot(axis, a));
                        let mut pq = c.d.pose_q();
                        pq.rotation = pq.rotation.then(&rot(DVec3::Z, -a * 0.7));
                        c.set_pose(pp, pq);
                    } else {
                        c.rotate_p_by(rot(axis, a));
                    }
                }
            }
        }
    }
}

/// Accumulates more than 1024 rad fast with large steps, then small ones,
/// several times (the rebase).
#[test]
fn rebase_after_long_runs() {
    for seed in 0..4u64 {
        let (mut c, mut r) = make(seed + 100, INCREMENTAL, "rebase");
        for _round in 0..3 {
            let axis = oracle::random_axis(&mut r);
            for _ in 0..2100 {
                c.rotate_p_by(rot(axis, 0.5 * r.random_range(0.9..1.0)));
            }
            for i in 0..600 {
                let axis = if i % 200 < 100 { DVec3::Z } else { axis };
                c.rotate_p_by(rot(axis, 1e-3 * r.random_range(0.5..1.5)));
            }
        }
    }
}

/// Alternating short runs about a coordinate axis and generic axes on
/// cubes and grids, small steps (the schedule is on).
#[test]
fn tie_runs_alternating_on_grids() {
    for seed in 0..30u64 {
        let mut r = rng(seed + 1000);
        let k = if seed % 2 == 0 {
            Kind::Grid
        } else {
            Kind::Cube
        };
        let p = random_polytope(k, r.random_range(8..40), &mut r);
        let q = random_polytope(Kind::Grid, r.random_range(8..40), &mut r);
        let cfg = if seed % 3 == 0 {
            INCREMENTAL
        } else {
            DynamicConfig::default()
        };
        let d = DynamicSum::with_config(&p, Pose::IDENTITY, &q, Pose::IDENTITY, cfg).unwrap();
        let mut c = Checked::new(d, 0, format!("ties seed {seed}"));
        let axes = [DVec3::X, DVec3::Y, DVec3::Z];
        for _ in 0..200 {
            let axis = if r.random_bool(0.7) {
                axes[r.random_range(0..3)]
            } else {
                oracle::random_axis(&mut r)
            };
            let n = r.random_range(1..6);
            let s = [1e-3, 0.01, std::f64::consts::FRAC_PI_2 / 64.0][r.random_range(0..3)];
            for _ in 0..n {
                c.rotate_p_by(rot(axis, s));
            }
        }
    }
}

/// Both bodies turning about z (the relative rotation stays about z: tie
/// runs with Q moving), interrupted by generic turns of Q.
#[test]
fn both_bodies_about_z() {
    for seed in 0..20u64 {
        let mut r = rng(seed + 5000);
        let p = random_polytope(Kind::Grid, r.random_range(8..40), &mut r);
        let q = random_polytope(
            if seed % 2 == 0 {
                Kind::Grid
            } else {
                Kind::Cube
            },
            r.random_range(8..40),
            &mut r,
        );
        let cfg = if seed % 3 == 0 {
            INCREMENTAL
        } else {
            DynamicConfig::default()
        };
        let d = DynamicSum::with_config(&p, Pose::IDENTITY, &q, Pose::IDENTITY, cfg).unwrap();
        let mut c = Checked::new(d, 0, format!("both z seed {seed}"));
        let (mut a, mut b) = (0.0f64, 0.0f64);
        for block in 0..60 {
            let generic = block % 7 == 6;
            for _ in 0..r.random_range(1..50) {
                a += 1e-3 * r.random_range(0.5..1.5);
                b -= 7e-4 * r.random_range(0.5..1.5);
                let pp = Pose::new(rot(DVec3::Z, a), DVec3::ZERO);
                let qr = if generic {
                    rot(DVec3::Z, b).then(&rot(
                        DVec3::new(1.0, 2.0, 3.0).normalize(),
                        1e-3 * block as f64,
                    ))
                } else {
                    rot(DVec3::Z, b)
                };
                c.set_pose(pp, Pose::new(qr, DVec3::ZERO));
            }
        }
    }
}
