//! Issue 8 §4: loading a large convex polygon mesh (`Polytope::from_mesh`,
//! full validation and convexity check) against building the same points as
//! a point cloud (`Polytope::from_points`, the exact hull only).
//!
//! The mesh is the hull of `n` points on the unit sphere (golden spiral),
//! fan-triangulated, at ~25k and ~200k vertices. Before timing, one call
//! checks that the mesh loads as exactly convex with the hull's counts.
//!
//! `cargo bench -p dymsum-bench --bench mesh_load -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use dymsum::polytope::MeshPolicy;
use dymsum::Polytope;
use dymsum_testkit::sphere_mesh;

fn mesh_load(c: &mut Criterion) {
    let mut group = c.benchmark_group("mesh_load");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for n in [25_000, 200_000] {
        let mesh = sphere_mesh(n);
        let (p, r) = Polytope::from_mesh(&mesh, MeshPolicy::default()).expect("mesh loads");
        let q = Polytope::from_points(&mesh.vertices).expect("cloud loads");
        assert!(r.exactly_convex);
        assert_eq!(p.vertex_count(), q.vertex_count());
        let label = format!("{}v", mesh.vertices.len());
        group.bench_with_input(BenchmarkId::new("mesh", &label), &mesh, |b, m| {
            b.iter(|| black_box(Polytope::from_mesh(m, MeshPolicy::default()).unwrap()))
        });
        group.bench_with_input(BenchmarkId::new("points", &label), &mesh, |b, m| {
            b.iter(|| black_box(Polytope::from_points(&m.vertices).unwrap()))
        });
    }
    group.finish();
}

criterion_group!(benches, mesh_load);
criterion_main!(benches);
