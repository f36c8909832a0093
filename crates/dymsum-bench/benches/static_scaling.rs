//! Issue 10 §4: the static `walk` sum (facets, and facets plus the merged
//! polygon mesh) against the hull of all pairwise vertex sums (the `hull`
//! method, plus its mesh), which is what manifold3d and OpenSCAD-style
//! tools compute, at 100, 300, 1,000 and 10,000 vertices per operand.
//! Operands: random points on the unit sphere, and on the ellipsoid with
//! semi-axes 1, 0.5 and 0.25 (the same points scaled), P turned by a fixed
//! random rotation. `hull` is timed up to 1,000 vertices per operand (at
//! 10,000 it would hull 10⁸ points).
//!
//! Before timing, one untimed call checks that `hull` finds the same facets
//! as `walk`.
//!
//! `cargo bench -p dymsum-bench --bench static_scaling`

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use dymsum::sum::{minkowski_sum_posed, Method};
use dymsum::{DVec3, Polytope, Pose};
use dymsum_bench::{random_rotation, sample_size_for, STATIC_SEED};
use dymsum_testkit::{random_polytope, rng, Kind};

/// Vertices per operand (points drawn; the hull keeps all of them on a
/// sphere).
const SIZES: [usize; 4] = [100, 300, 1_000, 10_000];
/// The largest size at which `hull` is timed.
const HULL_UP_TO: usize = 1_000;

/// The two operands of one size and shape.
fn operands(n: usize, ellipsoid: bool) -> (Polytope, Polytope) {
    let mut r = rng(n as u64 + u64::from(ellipsoid));
    let mut make = || {
        let sphere = random_polytope(Kind::Sphere, n, &mut r);
        if !ellipsoid {
            return sphere;
        }
        let scaled: Vec<[f64; 3]> = sphere
            .vertices()
            .iter()
            .map(|v| (*v * DVec3::new(1.0, 0.5, 0.25)).to_array())
            .collect();
        Polytope::from_points(&scaled).expect("an ellipsoid hull")
    };
    (make(), make())
}

fn static_scaling(c: &mut Criterion) {
    let pose_p = Pose::new(random_rotation(STATIC_SEED), DVec3::ZERO);
    let pose_q = Pose::IDENTITY;
    let mut group = c.benchmark_group("static_scaling");
    group
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for ellipsoid in [false, true] {
        for n in SIZES {
            let (p, q) = operands(n, ellipsoid);
            let label = format!("{}{n}", if ellipsoid { "ellipsoid" } else { "sphere" });
            let sum = |m: Method| minkowski_sum_posed(&p, pose_p, &q, pose_q, m).unwrap();
            let start = Instant::now();
            let walk = sum(Method::Walk);
            let one_call = start.elapsed();
            eprintln!(
                "note {label}: {} and {} vertices, {} facets",
                p.vertex_count(),
                q.vertex_count(),
                walk.facets().len()
            );
            group.sample_size(sample_size_for(one_call));
            group.bench_function(BenchmarkId::new("walk", &label), |b| {
                b.iter(|| black_box(sum(Method::Walk)))
            });
            group.bench_function(BenchmarkId::new("walk+mesh", &label), |b| {
                b.iter(|| black_box(sum(Method::Walk).try_to_mesh().unwrap()))
            });
            if n <= HULL_UP_TO {
                let start = Instant::now();
                let hull = sum(Method::Hull);
                let one_call = start.elapsed();
                assert_eq!(
                    hull.facets(),
                    walk.facets(),
                    "{label}: hull differs from walk"
                );
                group.sample_size(sample_size_for(one_call));
                group.bench_function(BenchmarkId::new("hull+mesh", &label), |b| {
                    b.iter(|| black_box(sum(Method::Hull).try_to_mesh().unwrap()))
                });
            }
        }
    }
    group.finish();
}

criterion_group!(benches, static_scaling);
criterion_main!(benches);
