//! Issue 8 §2: exactly parallel faces at full speed. Box ⊕ box
//! (`box:1,2,3` and `box:2,1,1`) with P turning about `z` (the top and
//! bottom faces stay exactly parallel, so exact ties occur in every query)
//! against the same workload about a generic axis, in one run:
//!
//! * `update`: one DYMSUM step (`DynamicSum::set_pose_p`) to the next pose;
//! * `tracker`: one `ContactTracker::update` (dynamic update plus the
//!   penetration-depth query; B is offset so the boxes overlap);
//! * `query`: one static `ConvexPair::query` at the pose.
//!
//! Poses are 500 steps per full turn, used cyclically (the step from the
//! last pose to the first is an ordinary step too). The ratio `z / generic`
//! of the medians is the figure of merit (target ≤ 1.5).
//!
//! `cargo bench -p dymsum-bench --bench parallel_faces -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use dymsum::query::ConvexPair;
use dymsum::{DVec3, DynamicSum, Pose, Rotation};
use dymsum_bench::load;

const STEPS: usize = 500;

fn poses(axis: DVec3) -> Vec<Pose> {
    (0..STEPS)
        .map(|i| {
            let angle = std::f64::consts::TAU * i as f64 / STEPS as f64;
            Pose::new(
                Rotation::from_axis_angle(axis, angle).expect("non-zero axis"),
                DVec3::ZERO,
            )
        })
        .collect()
}

fn parallel_faces(c: &mut Criterion) {
    let p = load("box:1,2,3");
    let q = load("box:2,1,1");
    let axes = [
        ("z", DVec3::Z),
        ("generic", DVec3::new(0.31, -0.57, 0.76).normalize()),
    ];
    let mut group = c.benchmark_group("parallel_faces");
    group.sample_size(20);
    let pose_b = Pose::new(Rotation::IDENTITY, DVec3::new(0.4, 0.3, 0.2));
    for (name, axis) in axes {
        let poses = poses(axis);
        let mut dy = DynamicSum::new(&p, poses[0], &q, Pose::IDENTITY).unwrap();
        let mut k = 0usize;
        group.bench_function(BenchmarkId::new("update", name), |b| {
            b.iter(|| {
                k = (k + 1) % STEPS;
                black_box(dy.set_pose_p(poses[k]))
            })
        });
        let pair = ConvexPair::new(&p, &q).unwrap();
        let mut tracker = pair.tracker(poses[0], pose_b).unwrap();
        let mut k = 0usize;
        group.bench_function(BenchmarkId::new("tracker", name), |b| {
            b.iter(|| {
                k = (k + 1) % STEPS;
                black_box(tracker.update(poses[k], pose_b).unwrap())
            })
        });
        let mut k = 0usize;
        group.bench_function(BenchmarkId::new("query", name), |b| {
            b.iter(|| {
                k = (k + 1) % STEPS;
                black_box(pair.query(poses[k], pose_b).unwrap())
            })
        });
    }
    group.finish();
}

criterion_group!(benches, parallel_faces);
criterion_main!(benches);
