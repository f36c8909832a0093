//! Exact contact per frame against parry3d-f64's GJK/EPA (issues 10 §3
//! and 18). For each pair, body A turns at 500 and at 5,000 steps per turn
//! while it slides in and out of contact with B (`dymsum_bench::contact`),
//! 1,000 frames used cyclically:
//!
//! * `dymsum`: one `ContactTracker::update` (strategy `Auto`: the certified
//!   query warm-started from the last frame, or the DYMSUM-kept sum where
//!   that measured faster; the exact depth or distance, direction and
//!   witness features);
//! * `static`: one cold `ConvexPair::query` (no warm start) at the same
//!   poses;
//! * `intersects`: `ConvexPair::intersects` alone (GJK with its exact
//!   certificates);
//! * `parry`: one `parry3d_f64::query::contact` (GJK/EPA, depth only when
//!   touching, no distance).
//!
//! Pairs: the small shapes physics engines use most (box vs box, a box vs
//! random hulls of 20 and 60 vertices, capsule-like hulls) and the paper's
//! models of the tracker table in docs/BENCHMARKS.md.
//!
//! Before timing, every frame's depth is compared with parry's (both must
//! agree on contact, depths to 1e-6 of the shapes' size, else the pair is
//! reported on stderr).
//!
//! `cargo bench -p dymsum-bench --bench tracker_vs_parry`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use dymsum::query::ConvexPair;
use dymsum::Polytope;
use dymsum_bench::contact::{
    agreement, contact_motion, parry_pose, parry_shape, radius, Agreement,
};
use dymsum_bench::load;
use dymsum_testkit::{random_polytope, rng, Kind};

const FRAMES: usize = 1000;

fn pairs() -> Vec<(String, Polytope, Polytope)> {
    let mut r = rng(10);
    let mut out = vec![
        ("box+box".to_string(), load("box:1,2,3"), load("box:2,1,1")),
        (
            "box+hull20".to_string(),
            load("box:1,2,3"),
            random_polytope(Kind::Sphere, 20, &mut r),
        ),
        (
            "box+hull60".to_string(),
            load("box:1,2,3"),
            random_polytope(Kind::Sphere, 60, &mut r),
        ),
        (
            "capsule+capsule".to_string(),
            load("capsule:8:4"),
            load("capsule:8:4"),
        ),
    ];
    for (a, b) in [
        ("dd", "hp"),
        ("cone", "cube"),
        ("gs2", "cylinder"),
        ("ti", "vrod"),
        ("gs4", "ellipse"),
    ] {
        out.push((format!("{a}+{b}"), load(a), load(b)));
    }
    out
}

fn tracker_vs_parry(c: &mut Criterion) {
    let mut group = c.benchmark_group("tracker_vs_parry");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2));
    for (label, a, b) in pairs() {
        let (sa, sb) = (parry_shape(&a), parry_shape(&b));
        let size = radius(&a) + radius(&b);
        for steps in [500.0, 5000.0] {
            let poses = contact_motion(&a, &b, steps, FRAMES);
            let parry: Vec<_> = poses
                .iter()
                .map(|&(x, y)| (parry_pose(x), parry_pose(y)))
                .collect();
            let pair = ConvexPair::new(&a, &b).expect("a convex pair");
            let mut tracker = pair.tracker(poses[0].0, poses[0].1).expect("a tracker");
            // Untimed: both answer every frame, and agree.
            let (mut hits, mut worst) = (0, 0.0f64);
            for (&(pa, pb), (qa, qb)) in poses.iter().zip(&parry) {
                let ours = tracker.update(pa, pb).expect("a tracker update");
                let theirs =
                    parry3d_f64::query::contact(qa, &sa, qb, &sb, 0.0).expect("parry's contact");
                match agreement(&ours, theirs.as_ref()) {
                    Agreement::Depths(d) => worst = worst.max(d),
                    Agreement::OnlyParry => {
                        eprintln!("note {label}: parry reports a depth where dymsum finds none")
                    }
                    Agreement::OnlyOurs => {
                        eprintln!("note {label}: dymsum reports a depth where parry finds none")
                    }
                    Agreement::Apart => {}
                }
                hits += ours.intersects() as usize;
            }
            if worst > 1e-6 * size {
                eprintln!("note {label}: parry's depth differs from dymsum's by up to {worst:.2e}");
            }
            let id = format!("{label}@{steps}");
            eprintln!(
                "note {id}: {} and {} vertices, {hits} of {FRAMES} frames in contact, tracker uses {:?}, {:?}",
                a.vertex_count(),
                b.vertex_count(),
                tracker.active_strategy(),
                pair.stats()
            );
            let mut k = 0usize;
            group.bench_function(BenchmarkId::new("dymsum", &id), |bench| {
                bench.iter(|| {
                    k = (k + 1) % FRAMES;
                    black_box(
                        tracker
                            .update(poses[k].0, poses[k].1)
                            .expect("a tracker update"),
                    )
                })
            });
            let mut k = 0usize;
            group.bench_function(BenchmarkId::new("static", &id), |bench| {
                bench.iter(|| {
                    k = (k + 1) % FRAMES;
                    black_box(pair.query(poses[k].0, poses[k].1).expect("a query"))
                })
            });
            let mut k = 0usize;
            group.bench_function(BenchmarkId::new("intersects", &id), |bench| {
                bench.iter(|| {
                    k = (k + 1) % FRAMES;
                    black_box(pair.intersects(poses[k].0, poses[k].1).expect("a query"))
                })
            });
            let mut k = 0usize;
            group.bench_function(BenchmarkId::new("parry", &id), |bench| {
                bench.iter(|| {
                    k = (k + 1) % FRAMES;
                    let (qa, qb) = &parry[k];
                    black_box(
                        parry3d_f64::query::contact(qa, &sa, qb, &sb, 0.0)
                            .expect("parry's contact"),
                    )
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, tracker_vs_parry);
criterion_main!(benches);
