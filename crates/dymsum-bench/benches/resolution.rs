//! Issue 10 §1: the DYMSUM update against the rotational resolution, on
//! ellipse ⊕ ellipse, next to the static `walk` at the same poses: at 500
//! steps per turn the update must be at least 12× faster than `walk`, and
//! at 100,000 steps per turn it must cost at most 1/20 of the update at 500
//! (its cost proportional to the changes, not to the sizes).
//!
//! P follows `paper_motion(steps_per_rev, 2000, MOTION_SEED)` (Q fixed), one
//! timed iteration is one `set_pose_p` to the next pose, and the wrap-around
//! back to pose 0 happens outside the timed region (as in
//! `dynamic_update`). Before timing, one untimed pass prints the mean number
//! of changed facets per step (removed plus added, halved) and checks the
//! last step against a fresh `walk`.
//!
//! `cargo bench -p dymsum-bench --bench resolution`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use dymsum::sum::{minkowski_sum_posed, Method};
use dymsum::{DVec3, DynamicSum, Pose};
use dymsum_bench::{load, paper_motion, time_cyclic_updates, MOTION_SEED};

/// Steps per turn measured.
const RESOLUTIONS: [f64; 3] = [500.0, 5_000.0, 100_000.0];
/// Length of each pose sequence.
const STEPS: usize = 2000;

fn resolution(c: &mut Criterion) {
    let (p, q) = (load("ellipse"), load("ellipse"));
    let mut group = c.benchmark_group("resolution");
    group
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .sample_size(20);
    for spr in RESOLUTIONS {
        let poses: Vec<Pose> = paper_motion(spr, STEPS, MOTION_SEED)
            .into_iter()
            .map(|r| Pose::new(r, DVec3::ZERO))
            .collect();
        let timed = &poses[1..];
        let mut dy = DynamicSum::new(&p, poses[0], &q, Pose::IDENTITY).unwrap();
        let (mut changes, mut fallbacks, mut visited) = (0usize, 0usize, 0usize);
        for pose in timed {
            let r = dy.set_pose_p(*pose);
            visited += r.checked_normals;
            changes += (r.removed.len() + r.added.len()) / 2;
            fallbacks += usize::from(r.recomputed);
        }
        let walk =
            minkowski_sum_posed(&p, timed[timed.len() - 1], &q, Pose::IDENTITY, Method::Walk)
                .unwrap();
        assert_eq!(dy.facets(), walk.facets(), "dynamic differs from walk");
        eprintln!(
            "note ellipse+ellipse at {spr} steps/turn: {:.2} changed facets per step, \
             {:.1} normals visited per step (of {}), {fallbacks} fallbacks in {} steps",
            changes as f64 / timed.len() as f64,
            visited as f64 / timed.len() as f64,
            p.face_count() + q.face_count(),
            timed.len()
        );
        dy.set_pose_p(poses[0]);
        let mut next = 0usize;
        group.bench_function(BenchmarkId::new("dymsum", spr), |b| {
            b.iter_custom(|iters| time_cyclic_updates(&mut dy, poses[0], timed, &mut next, iters))
        });
        if spr == RESOLUTIONS[0] {
            let mut next = 0usize;
            group.bench_function(BenchmarkId::new("walk", spr), |b| {
                b.iter(|| {
                    let pose = timed[next];
                    next = (next + 1) % timed.len();
                    black_box(minkowski_sum_posed(
                        &p,
                        pose,
                        &q,
                        Pose::IDENTITY,
                        Method::Walk,
                    ))
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, resolution);
criterion_main!(benches);
