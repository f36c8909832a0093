//! State checks on triangle-mesh scenes (issue 28): dymsum's exact
//! `SceneChecker::collides_at` against parry3d-f64's BVH mesh–mesh
//! `intersection_test` on the same 1,000 seeded random states per scene,
//! and on up to 200 states within 2⁻⁴⁰ of contact (bisected from free to
//! colliding), one call per state, as a planner makes them. The scenes: OMPL.app's
//! problems exported as OBJ into the folder `DYMSUM_SCENES` names
//! (`python/benchmarks/export_scenes.py`; `DYMSUM_SCENES_ONLY=a,b` picks
//! some), else a built-in room. Before timing, the answers are compared
//! and the disagreements printed on stderr (parry works in floats with
//! its own tolerances; dymsum's containment of a body inside a solid is
//! a contact parry does not report).
//!
//! `DYMSUM_SCENES=/path cargo bench -p dymsum-bench --bench scenes_vs_parry`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use dymsum_bench::scenes::{dymsum_checker, near_contact, parry_collides, parry_mesh, scenes};

const STATES: usize = 1000;

fn scenes_vs_parry(c: &mut Criterion) {
    let mut group = c.benchmark_group("scenes_vs_parry");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    for scene in scenes(STATES) {
        let checker = dymsum_checker(&scene);
        let (robot, env) = (parry_mesh(&scene.robot), parry_mesh(&scene.env));
        let ours: Vec<bool> = scene
            .states
            .iter()
            .map(|&p| checker.collides_at(p).unwrap())
            .collect();
        let theirs: Vec<bool> = scene
            .states
            .iter()
            .map(|&p| parry_collides(&robot, &env, p))
            .collect();
        let only_ours = ours
            .iter()
            .zip(&theirs)
            .filter(|(a, b)| **a && !**b)
            .count();
        let only_parry = ours
            .iter()
            .zip(&theirs)
            .filter(|(a, b)| !**a && **b)
            .count();
        eprintln!(
            "{}: {} states, {} colliding; only dymsum {only_ours}, only parry {only_parry}",
            scene.name,
            STATES,
            ours.iter().filter(|&&h| h).count()
        );
        let near = near_contact(&checker, &scene.states, 200);
        let near_ours: Vec<bool> = near
            .iter()
            .map(|&p| checker.collides_at(p).unwrap())
            .collect();
        let near_theirs: Vec<bool> = near
            .iter()
            .map(|&p| parry_collides(&robot, &env, p))
            .collect();
        eprintln!(
            "{} near contact: {} states; disagreements {}",
            scene.name,
            near.len(),
            near_ours
                .iter()
                .zip(&near_theirs)
                .filter(|(a, b)| a != b)
                .count()
        );
        for (kind, states) in [("random", &scene.states), ("near", &near)] {
            let id = format!("{}/{kind}", scene.name);
            group.bench_with_input(BenchmarkId::new("dymsum", &id), states, |b, s| {
                b.iter(|| {
                    for &p in s {
                        black_box(checker.collides_at(p).unwrap());
                    }
                })
            });
            group.bench_with_input(BenchmarkId::new("parry", &id), states, |b, s| {
                b.iter(|| {
                    for &p in s {
                        black_box(parry_collides(&robot, &env, p));
                    }
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, scenes_vs_parry);
criterion_main!(benches);
