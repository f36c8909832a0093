//! Issue 3 §6: the per-step update time of `DynamicSum` under the paper's
//! motion (§5: a random axis held for 1 to 50 steps, 500 steps per full
//! turn), next to the static `walk` and `brute` sums at the same poses, on
//! cube+cube, gs4+gs4, ellipse+ellipse and ti+vrod.
//!
//! The pose sequence is `paper_motion(500, 1000, MOTION_SEED)` for P (Q stays
//! at the identity), used cyclically. The `DynamicSum` is created at the
//! identity (`DynamicSum::new(&p, IDENTITY, &q, IDENTITY)`) and moved to
//! pose 0 untimed; one timed `dymsum` iteration is one `set_pose_p` to the
//! next pose (1 to 999). When the sequence wraps around, the sum jumps from
//! pose 999 back to pose 0 (a large jump, recomputed from scratch)
//! *outside* the timed region, so every timed update is a genuine 2π/500
//! step. `walk` and `brute` compute the static sum at the same poses 1 to
//! 999 in the same cyclic order.
//!
//! `cargo bench -p dymsum-bench --bench dynamic_update`

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use dymsum::sum::{minkowski_sum_posed, Method};
use dymsum::{DVec3, DynamicSum, Pose};
use dymsum_bench::{
    load, pair_label, paper_motion, sample_size_for, time_cyclic_updates, DYNAMIC_GROUP,
    MOTION_SEED, MOTION_STEPS, PAIRS, STEPS_PER_REV,
};

fn dynamic_update(c: &mut Criterion) {
    let poses: Vec<Pose> = paper_motion(STEPS_PER_REV, MOTION_STEPS, MOTION_SEED)
        .into_iter()
        .map(|r| Pose::new(r, DVec3::ZERO))
        .collect();
    // The timed steps: pose i-1 -> pose i for i = 1..len.
    let timed = &poses[1..];
    let mut group = c.benchmark_group(DYNAMIC_GROUP);
    group
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for (pn, qn) in PAIRS {
        let p = load(pn);
        let q = load(qn);
        let pair = pair_label(pn, qn);

        // Untimed check: one pass of the sequence; the dynamic facet count
        // must match the static walk every 100 steps.
        {
            let mut dy = DynamicSum::new(&p, Pose::IDENTITY, &q, Pose::IDENTITY).unwrap();
            dy.set_pose_p(poses[0]);
            let mut recomputed = 0;
            for (i, pose) in timed.iter().enumerate() {
                recomputed += dy.set_pose_p(*pose).recomputed as usize;
                if i % 100 == 0 {
                    let walk =
                        minkowski_sum_posed(&p, *pose, &q, Pose::IDENTITY, Method::Walk).unwrap();
                    if walk.overlay().len() != dy.facet_count() {
                        eprintln!(
                            "WARNING {pair}: step {}: dynamic has {} facets, walk {}",
                            i + 1,
                            dy.facet_count(),
                            walk.overlay().len()
                        );
                    }
                }
            }
            eprintln!(
                "note {pair}: {recomputed} of {} timed steps fell back to a from-scratch sum",
                timed.len()
            );
        }

        let mut dy = DynamicSum::new(&p, Pose::IDENTITY, &q, Pose::IDENTITY).unwrap();
        dy.set_pose_p(poses[0]);
        let mut next = 0usize;
        group.sample_size(20);
        group.bench_function(BenchmarkId::new("dymsum", &pair), |b| {
            b.iter_custom(|iters| time_cyclic_updates(&mut dy, poses[0], timed, &mut next, iters))
        });

        for m in [Method::Walk, Method::Brute] {
            let start = Instant::now();
            black_box(minkowski_sum_posed(&p, timed[0], &q, Pose::IDENTITY, m).unwrap());
            group.sample_size(sample_size_for(start.elapsed()));
            let mut next = 0usize;
            group.bench_function(BenchmarkId::new(m.name(), &pair), |b| {
                b.iter(|| {
                    let pose = timed[next];
                    next = (next + 1) % timed.len();
                    black_box(minkowski_sum_posed(&p, pose, &q, Pose::IDENTITY, m).unwrap())
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, dynamic_update);
criterion_main!(benches);
