//! Certified motion checks against parry3d-f64's nonlinear shape cast and
//! against sampling (issue 20 §1). For each scene of
//! `dymsum_bench::motion::scenes` (a box through a thin wall, a bar turning
//! past a block, short planner steps among round obstacles), 64 motions
//! used cyclically:
//!
//! * `dymsum`: one `MotionChecker::check` (tolerance 1e-6; certified free,
//!   or a contact bracket no wider than the tolerance);
//! * `parry_cast`: one `cast_shapes_nonlinear` per obstacle (conservative
//!   advancement with parry's tolerance: the same motion, constant linear
//!   and angular velocity);
//! * `sampled_101`: the exact yes/no query at 101 evenly spaced poses,
//!   stopping at the first collision (what OMPL's discrete validator does
//!   at 1% steps; it can step over the thin wall).
//!
//! Before timing, each motion's answers are compared: how often parry and
//! sampling call free a motion dymsum certifies colliding, and how far
//! parry's time of impact is from dymsum's bracket (printed on stderr).
//!
//! `cargo bench -p dymsum-bench --bench motion_vs_parry`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use dymsum::query::{Motion, MotionCheck, MotionChecker};
use dymsum_bench::motion::{parry_shapes, parry_time_of_impact, scenes};

const MOTIONS: usize = 64;
const TOLERANCE: f64 = 1e-6;

fn sampled_free(checker: &MotionChecker, from: dymsum::Pose, to: dymsum::Pose) -> bool {
    let m = Motion::new(from, to);
    (0..=100).all(|k| !checker.collides_at(m.at(k as f64 / 100.0)).unwrap())
}

fn motion_vs_parry(c: &mut Criterion) {
    let mut group = c.benchmark_group("motion_vs_parry");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2));
    for scene in scenes(MOTIONS) {
        let checker = MotionChecker::new(&scene.body_union(), &scene.obstacle_unions()).unwrap();
        let (pb, po) = parry_shapes(&scene);
        // Agreement first.
        let (mut colliding, mut parry_missed, mut sampling_missed, mut worst) = (0, 0, 0, 0.0f64);
        let mut most_steps = 0;
        for &(from, to) in &scene.motions {
            let before = checker.steps();
            // Unwrapped: an undecided answer (grazing, or the default work
            // budget used up) fails the bench.
            let ours = checker.check(from, to, TOLERANCE).unwrap();
            most_steps = most_steps.max(checker.steps() - before);
            let parry = parry_time_of_impact(&pb, &po, from, to);
            if let MotionCheck::Collides { t_safe, t_contact } = ours {
                colliding += 1;
                match parry {
                    None => parry_missed += 1,
                    Some(t) => {
                        let lo = t_safe.unwrap_or(0.0);
                        worst = worst.max((t - t_contact).max(lo - t).max(0.0));
                    }
                }
                if sampled_free(&checker, from, to) {
                    sampling_missed += 1;
                }
            }
        }
        eprintln!(
            "{}: {colliding}/{} motions collide (certified); parry's cast calls {parry_missed} \
             of them free, sampling at 1% steps {sampling_missed}; parry's time of impact at most \
             {worst:.2e} outside dymsum's bracket; at most {most_steps} intervals per check \
             (budget {})",
            scene.name,
            scene.motions.len(),
            checker.budget()
        );
        let n = scene.motions.len();
        let mut k = 0;
        group.bench_function(BenchmarkId::new("dymsum", scene.name), |bench| {
            bench.iter(|| {
                let (from, to) = scene.motions[k % n];
                k += 1;
                black_box(checker.check(from, to, TOLERANCE).unwrap())
            })
        });
        group.bench_function(BenchmarkId::new("parry_cast", scene.name), |bench| {
            bench.iter(|| {
                let (from, to) = scene.motions[k % n];
                k += 1;
                black_box(parry_time_of_impact(&pb, &po, from, to))
            })
        });
        group.bench_function(BenchmarkId::new("sampled_101", scene.name), |bench| {
            bench.iter(|| {
                let (from, to) = scene.motions[k % n];
                k += 1;
                black_box(sampled_free(&checker, from, to))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, motion_vs_parry);
criterion_main!(benches);
