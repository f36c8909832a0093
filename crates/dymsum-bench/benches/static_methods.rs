//! Issue 2 §7: the three static methods (`walk`, `brute`, `hull`) on
//! cube+cube, gs4+gs4, ellipse+ellipse and ti+vrod, with P at one fixed,
//! seeded random orientation (`random_rotation(STATIC_SEED)`) and Q at its
//! input pose. One iteration is one `minkowski_sum_posed` call (the facet
//! set, no mesh merging); `walk+merge` adds `.try_to_mesh().unwrap()`.
//!
//! Before each bench one untimed call checks that the method succeeds and
//! finds the same facet counts as `walk`; a method that fails is reported
//! on stderr and not timed.
//!
//! `cargo bench -p dymsum-bench --bench static_methods`

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use dymsum::sum::{minkowski_sum_posed, Method};
use dymsum::{DVec3, Pose};
use dymsum_bench::{
    load, pair_label, random_rotation, sample_size_for, PAIRS, STATIC_GROUP, STATIC_SEED,
};

fn static_methods(c: &mut Criterion) {
    let pose_p = Pose::new(random_rotation(STATIC_SEED), DVec3::ZERO);
    let pose_q = Pose::IDENTITY;
    let mut group = c.benchmark_group(STATIC_GROUP);
    group
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for (pn, qn) in PAIRS {
        let p = load(pn);
        let q = load(qn);
        let pair = pair_label(pn, qn);
        let reference = match minkowski_sum_posed(&p, pose_p, &q, pose_q, Method::Walk) {
            Ok(s) => s.counts(),
            Err(e) => {
                eprintln!("WARNING {pair}: walk failed ({e:?}); pair skipped");
                continue;
            }
        };
        for m in [Method::Walk, Method::Brute, Method::Hull] {
            let start = Instant::now();
            let counts = match minkowski_sum_posed(&p, pose_p, &q, pose_q, m) {
                Ok(s) => s.counts(),
                Err(e) => {
                    eprintln!("WARNING {pair}: {} failed ({e:?}); not timed", m.name());
                    continue;
                }
            };
            let one_call = start.elapsed();
            if counts != reference {
                eprintln!(
                    "WARNING {pair}: {} facet counts {counts:?} differ from walk {reference:?}",
                    m.name()
                );
            }
            group.sample_size(sample_size_for(one_call));
            group.bench_with_input(BenchmarkId::new(m.name(), &pair), &m, |b, &m| {
                b.iter(|| black_box(minkowski_sum_posed(&p, pose_p, &q, pose_q, m).unwrap()))
            });
        }
        group.sample_size(20);
        group.bench_function(BenchmarkId::new("walk+merge", &pair), |b| {
            b.iter(|| {
                let sum = minkowski_sum_posed(&p, pose_p, &q, pose_q, Method::Walk).unwrap();
                black_box(sum.try_to_mesh().unwrap())
            })
        });
    }
    group.finish();
}

criterion_group!(benches, static_methods);
criterion_main!(benches);
