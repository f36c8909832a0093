//! Grazing motions (issue 26 §4): a bar `[0, 2] × [−.05, .05]²` turning
//! 90° about z past an obstacle at its reach `√4.0025` plus a gap, the
//! obstacle a thin plate facing the bar's tip (face against corner) or a
//! square rod presenting an edge (edge against corner and edges). Before
//! this issue the gap of 1e-9 took 3–15 s, 1e-10 104 s and 0 287 s; each
//! row times one `MotionChecker::check` (tolerance 1e-6, default budget)
//! and prints its answer and the intervals it examined on stderr.
//!
//! `cargo bench -p dymsum-bench --bench motion_grazing`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use dymsum::query::{ConvexUnion, MotionChecker};
use dymsum::{DVec3, Pose, Rotation};
use dymsum_testkit::grazing;

fn obstacle(kind: &str, gap: f64) -> ConvexUnion {
    ConvexUnion::from(if kind == "plate" {
        grazing::plate(gap)
    } else {
        grazing::rod_edge(gap)
    })
}

fn turn(deg: f64) -> Pose {
    Pose::new(
        Rotation::from_axis_angle(DVec3::Z, deg.to_radians()).unwrap(),
        DVec3::ZERO,
    )
}

fn bench(c: &mut Criterion) {
    let bar = ConvexUnion::from(grazing::bar());
    let mut group = c.benchmark_group("grazing");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    for kind in ["plate", "rod_edge"] {
        for gap in [1e-6, 1e-9, 1e-10, 1e-12, 0.0] {
            let checker = MotionChecker::new(&bar, &[obstacle(kind, gap)]).unwrap();
            let answer = checker.check(turn(-45.0), turn(45.0), 1e-6);
            eprintln!(
                "grazing {kind} gap {gap:e}: {answer:?}, {} intervals",
                checker.steps()
            );
            group.bench_function(BenchmarkId::new(kind, format!("{gap:e}")), |b| {
                b.iter(|| black_box(checker.check(turn(-45.0), turn(45.0), 1e-6)))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
