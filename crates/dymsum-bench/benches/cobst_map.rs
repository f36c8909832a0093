//! Issue 22 §1: C-obstacle maps of gs4 (robot) among ellipse, 4,000
//! orientations about `(1, 2, 3)` (`orientations_about_axis`), one thread.
//!
//! * `updates`: the DYMSUM updates alone, one `DynamicSum` moved from
//!   slice to slice (`set_pose`), nothing read out;
//! * `halfspaces`: `CObstacle::halfspace_slices` over the same turn (the
//!   updates plus the planes read from the facets);
//! * `mesh_off` and `mesh_npz` over the first 400 of those orientations
//!   (the same steps; the meshes cost ~100× the updates): every slice's
//!   mesh written as an OFF file (`dymsum_io::formats::write_mesh`, what
//!   `cobst --format off` does) against the meshes gathered into one map
//!   container (`dymsum_io::cmap`, what `--format npz-mesh` does).
//!
//! Targets: `halfspaces` ≤ 3× `updates`; `mesh_npz` ≥ 3× faster than
//! `mesh_off`.
//!
//! `cargo bench -p dymsum-bench --bench cobst_map`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dymsum::query::orientations_about_axis;
use dymsum::{CObstacle, DVec3, DynamicSum, Pose};
use dymsum_bench::load;
use dymsum_io::cmap::{Form, MapBuilder};

const SLICES: usize = 4000;
const MESH_SLICES: usize = 400;

fn cobst_map(c: &mut Criterion) {
    let robot = load("gs4");
    let obstacle = load("ellipse");
    let cobst = CObstacle::new(&robot, &obstacle).unwrap();
    let turns = orientations_about_axis(DVec3::new(1.0, 2.0, 3.0), SLICES).unwrap();
    let mesh_turns = &turns[..MESH_SLICES];
    let dir = std::env::temp_dir().join(format!("dymsum-bench-cobst-map-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();

    let mut group = c.benchmark_group("cobst_map");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    group.bench_function("updates", |b| {
        b.iter(|| {
            let pose = |k: usize| Pose::new(turns[k], DVec3::ZERO);
            let mut s =
                DynamicSum::new(cobst.reflected_robot(), pose(0), &obstacle, Pose::IDENTITY)
                    .unwrap();
            for k in 1..turns.len() {
                s.set_pose(pose(k), Pose::IDENTITY);
            }
            black_box(s.facet_count())
        })
    });
    group.bench_function("halfspaces", |b| {
        b.iter(|| black_box(cobst.halfspace_slices(&turns).unwrap().len()))
    });
    group.bench_function("mesh_off", |b| {
        b.iter(|| {
            for (k, m) in cobst.slices(mesh_turns).enumerate() {
                let path = dir.join(format!("slice_{k:05}.off"));
                dymsum_io::formats::write_mesh(&path, &m.unwrap()).unwrap();
            }
        })
    });
    group.bench_function("mesh_npz", |b| {
        b.iter(|| {
            let mut map = MapBuilder::new(
                Form::Mesh,
                false,
                mesh_turns,
                MESH_SLICES,
                vec!["r0".into()],
                vec!["o0".into()],
            );
            map.add_pair(0, 0);
            for m in cobst.slices(mesh_turns) {
                map.push_mesh(&m.unwrap());
            }
            map.write(&dir.join("map.npz")).unwrap();
        })
    });
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, cobst_map);
criterion_main!(benches);
