//! Where a robot part pair's slow state checks go (issue 35): `cargo run
//! --release -p dymsum-bench --example parts_tails -- DIR [STATES]` times
//! every state of a pair (`PAIR=a,b`, the meshes whose names contain `a`
//! and `b`) or of a seeded sample (`SEED=s PAIRS=k`, as `parts_probe`
//! draws them), random and near contact, best of three calls each, and
//! prints per pair the median, the 99th percentile, the segments the
//! containment test made and its counters (`containment_stats`, which
//! also count `pair_states`' bisections); `TOP=k`: the k slowest states
//! with what their first call's containment test did; `VERDICTS_TO=path`:
//! every state's answer, one character each (to compare two builds).

use std::time::Instant;

use dymsum_bench::parts::{pair_states, part_checker, parts, picked_pairs};

/// One state: its best time (µs), index, answer, and its first call's
/// grid readings, segments and rays.
type Row = (f64, usize, bool, u64, u64, u64);

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = std::path::Path::new(args.get(1).map_or("/tmp/erd", |s| s));
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(200);
    let env = |k: &str| std::env::var(k).ok();
    let all = parts(dir);
    let seed: u64 = env("SEED").and_then(|v| v.parse().ok()).unwrap_or(3);
    let count: usize = env("PAIRS").and_then(|v| v.parse().ok()).unwrap_or(12);
    let picks = picked_pairs(&all, env("PAIR").as_deref(), seed, count);
    let top: usize = env("TOP").and_then(|v| v.parse().ok()).unwrap_or(0);
    let mut verdicts = String::new();
    for (a, b) in picks {
        let (pa, pb) = (&all[a], &all[b]);
        let checker = part_checker(&pa.mesh, &pb.mesh);
        let (random, near) = pair_states(&checker, &pa.mesh, &pb.mesh, n, 11);
        let mut rows: Vec<Row> = Vec::new();
        for (i, &pose) in random.iter().chain(near.iter()).enumerate() {
            let before = checker.containment_stats();
            let hit = checker.collides_at(pose).unwrap();
            let after = checker.containment_stats();
            let mut best = f64::MAX;
            for _ in 0..3 {
                let t = Instant::now();
                std::hint::black_box(checker.collides_at(pose).unwrap());
                best = best.min(t.elapsed().as_secs_f64() * 1e6);
            }
            verdicts.push(if hit { '1' } else { '0' });
            rows.push((
                best,
                i,
                hit,
                after.by_grid - before.by_grid,
                after.by_segment - before.by_segment,
                after.by_ray - before.by_ray,
            ));
        }
        let mut times: Vec<f64> = rows.iter().map(|r| r.0).collect();
        times.sort_by(f64::total_cmp);
        let segments: u64 = rows.iter().map(|r| r.4).sum();
        println!(
            "{} / {}: {} states, median {:.2} µs, p99 {:.2} µs, {segments} segments; {:?}",
            pa.name,
            pb.name,
            rows.len(),
            times[times.len() / 2],
            times[(times.len() - 1) * 99 / 100],
            checker.containment_stats()
        );
        rows.sort_by(|x, y| y.0.total_cmp(&x.0));
        for r in rows.iter().take(top) {
            println!(
                "{:8.2} µs  state {:5} (random first)  collides {:5}  grid {} segments {} rays {}",
                r.0, r.1, r.2, r.3, r.4, r.5
            );
        }
    }
    if let Some(path) = env("VERDICTS_TO") {
        std::fs::write(path, verdicts).expect("the verdicts' file");
    }
}
