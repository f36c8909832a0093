//! Times dymsum's state checks on robot part pairs against parry's BVH
//! test (issue 35): `cargo run --release -p dymsum-bench --example
//! parts_probe -- DIR [PAIRS] [STATES]` prints, per seeded pair of the
//! meshes in DIR, the build time and the medians and 99th percentiles of
//! one call per state, random and near contact (`DISTANCE=1`:
//! `distance_at` on the free states; `DISTANCE=all`: on every state,
//! `DISTANCE=colliding`: on the colliding ones; `SLOWEST=k`: the k slowest
//! states' checks again, each alone in `replay`, for a profiler's toggle;
//! `MIDDLE=k`: the k states nearest the median time, likewise; `SEED=s`:
//! another sample of pairs; `KIND=random` or `KIND=near`: those states
//! alone; `VERDICTS` set: the medians split by dymsum's answer; `STATS`
//! set: the containment tests' counts and both meshes' reports; `PER_STATE=path`: every state's
//! two times and the answer; `REPLAY=i,j`: those states again, each in
//! `replay`).
//!
//! `TIMING` says how the two tools' calls are timed. `interleaved` (the
//! default): one call of each per state, dymsum's then parry's, so each
//! runs in the caches the other's call has just used; after one of
//! parry's long calls (hundreds of µs where the surfaces cross) dymsum's
//! short one finds little of its data, and the medians measure that.
//! `passes`: each tool over every state in its own pass, twice in turn, a
//! state's time the better of its two. `cold`: as `interleaved`, with a
//! sweep of `EVICT` bytes (8 MiB unless told) before every timed call, so
//! both tools start each call without their data in the core's caches.

use std::time::Instant;

use dymsum_bench::parts::{pair_states, part_checker, parts, picked_pairs};
use dymsum_bench::scenes::{parry_collides, parry_mesh};

/// One check, alone in a function so that a profiler can collect it (the
/// timed calls too: `--toggle-collect='*replay'` counts them and not
/// `pair_states`' bisections).
#[inline(never)]
fn replay(checker: &dymsum::query::SceneChecker, p: dymsum::Pose, distance: bool) {
    if distance {
        std::hint::black_box(checker.distance_at(p).unwrap());
    } else {
        std::hint::black_box(checker.collides_at(p).unwrap());
    }
}

/// The bytes `TIMING=cold` sweeps before each timed call (`EVICT`, 8 MiB
/// unless told): more than a core's private caches.
fn evict_bytes() -> usize {
    std::env::var("EVICT")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(8 << 20)
}

/// Writes every cache line of `sweep` (nothing where it is empty), so the
/// next call finds none of its own data in the core's private caches.
fn evict(sweep: &mut [u8]) {
    for line in sweep.chunks_mut(64) {
        line[0] = line[0].wrapping_add(1);
    }
    std::hint::black_box(&sweep);
}

/// One parry test, alone likewise (`MIDDLE` replays parry's on the same
/// states once each, for `--toggle-collect='*replay_parry*'`).
#[inline(never)]
fn replay_parry(a: &parry3d_f64::shape::TriMesh, b: &parry3d_f64::shape::TriMesh, p: dymsum::Pose) {
    std::hint::black_box(parry_collides(a, b, p));
}

fn quantile(v: &mut [f64], q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = std::path::Path::new(args.get(1).map_or("/tmp/rm", |s| s));
    let pairs: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(12);
    let n: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(100);
    // `DYMSUM_ONLY=1`: time dymsum alone (e.g. under `perf stat`);
    // `DISTANCE=1`: time `distance_at` on the free states instead.
    let skip_parry = std::env::var("DYMSUM_ONLY").is_ok();
    let distance = std::env::var("DISTANCE").is_ok();
    // `DISTANCE=all`: on the colliding states too (the answer is 0);
    // `DISTANCE=colliding`: on those alone.
    let every_state = std::env::var("DISTANCE").is_ok_and(|v| v == "all");
    let colliding_only = std::env::var("DISTANCE").is_ok_and(|v| v == "colliding");
    let only: Option<String> = std::env::var("PAIR").ok();
    // `TIMING=interleaved` (the default), `passes` or `cold` (module docs).
    let timing = std::env::var("TIMING").unwrap_or_else(|_| "interleaved".into());
    assert!(
        ["interleaved", "passes", "cold"].contains(&timing.as_str()),
        "TIMING={timing}: interleaved, passes or cold"
    );
    let mut sweep = vec![0u8; if timing == "cold" { evict_bytes() } else { 0 }];
    let all = parts(dir);
    // `SEED=s`: another seeded sample of pairs (3 unless told).
    let seed: u64 = std::env::var("SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(3);
    let picks = picked_pairs(&all, only.as_deref(), seed, pairs);
    let (mut ratios_med, mut ratios_p99) = (Vec::new(), Vec::new());
    for (a, b) in picks {
        let (pa, pb) = (&all[a], &all[b]);
        let t0 = Instant::now();
        let checker = part_checker(&pa.mesh, &pb.mesh);
        let build = t0.elapsed().as_secs_f64();
        let (ra, rb) = (parry_mesh(&pa.mesh), parry_mesh(&pb.mesh));
        if std::env::var("STATS").is_ok() {
            for m in [&pa.mesh, &pb.mesh] {
                println!("{:?}", dymsum::query::MeshBody::new(m).map(|b| b.report()));
            }
        }
        let (random, near) = pair_states(&checker, &pa.mesh, &pb.mesh, n, 11);
        for (what, states) in [("random", &random), ("near", &near)] {
            // `KIND=random` or `KIND=near`: that kind of state alone.
            if std::env::var("KIND").is_ok_and(|k| k != what) {
                continue;
            }
            let which: Vec<usize> = (0..states.len())
                .filter(|&i| {
                    !distance
                        || every_state
                        || checker.collides_at(states[i]).unwrap() == colliding_only
                })
                .collect();
            let ours_once = |p: dymsum::Pose| {
                let t = Instant::now();
                replay(&checker, p, distance);
                t.elapsed().as_secs_f64() * 1e6
            };
            let theirs_once = |p: dymsum::Pose| {
                if skip_parry {
                    return 1.0;
                }
                let t = Instant::now();
                replay_parry(&ra, &rb, p);
                t.elapsed().as_secs_f64() * 1e6
            };
            let (mut ours, mut theirs) = (Vec::new(), Vec::new());
            match timing.as_str() {
                // Each tool over every state in its own pass, twice in
                // turn; a state's time is the better of its two: neither
                // tool's call runs in the caches the other's has just
                // filled (module docs).
                "passes" => {
                    ours = vec![f64::INFINITY; which.len()];
                    theirs = vec![f64::INFINITY; which.len()];
                    for _ in 0..2 {
                        for (k, &i) in which.iter().enumerate() {
                            ours[k] = ours[k].min(ours_once(states[i]));
                        }
                        for (k, &i) in which.iter().enumerate() {
                            theirs[k] = theirs[k].min(theirs_once(states[i]));
                        }
                    }
                }
                // One call of each per state, in turn, each after a sweep
                // of `EVICT` bytes (`cold`) or right after the other's
                // (`interleaved`, the default).
                _ => {
                    for &i in &which {
                        evict(&mut sweep);
                        ours.push(ours_once(states[i]));
                        evict(&mut sweep);
                        theirs.push(theirs_once(states[i]));
                    }
                }
            }
            if ours.is_empty() {
                continue;
            }
            // `SLOWEST=k`: the k slowest states' checks once more, each in
            // `replay` (for `valgrind --toggle-collect='*replay*'`).
            if let Some(k) = std::env::var("SLOWEST")
                .ok()
                .and_then(|v| v.parse::<usize>().ok())
            {
                let mut order: Vec<usize> = (0..ours.len()).collect();
                order.sort_by(|&i, &j| ours[j].total_cmp(&ours[i]));
                for &i in order.iter().take(k) {
                    println!("{what} state {}: {:.1} µs", which[i], ours[i]);
                    replay(&checker, states[which[i]], distance);
                }
            }
            // `MIDDLE=k`: the k states nearest the median time, each once
            // more in `replay` (what a typical check costs, for a profile).
            if let Some(k) = std::env::var("MIDDLE")
                .ok()
                .and_then(|v| v.parse::<usize>().ok())
            {
                let mut order: Vec<usize> = (0..ours.len()).collect();
                order.sort_by(|&i, &j| ours[i].total_cmp(&ours[j]));
                let from = (order.len() / 2).saturating_sub(k / 2);
                let t = Instant::now();
                let mut calls = 0;
                for &i in order.iter().skip(from).take(k) {
                    // `TIMING=cold`: each after a sweep, as timed.
                    evict(&mut sweep);
                    replay(&checker, states[which[i]], distance);
                    calls += 1;
                }
                let cold = t.elapsed().as_secs_f64() * 1e6 / calls.max(1) as f64;
                if !skip_parry {
                    for &i in order.iter().skip(from).take(k) {
                        evict(&mut sweep);
                        replay_parry(&ra, &rb, states[which[i]]);
                    }
                }
                let t = Instant::now();
                let repeats = if sweep.is_empty() { 100 } else { 0 };
                for &i in order.iter().skip(from).take(k) {
                    for _ in 0..repeats {
                        replay(&checker, states[which[i]], distance);
                    }
                }
                let warm = t.elapsed().as_secs_f64() * 1e6 / (repeats * calls).max(1) as f64;
                println!("{what}: {calls} middle states, {cold:.2} µs each once, {warm:.2} µs each repeated");
            }
            // `REPLAY=i,j,...`: those states (indices in `states`, as
            // `PER_STATE` prints them) once more each, in `replay`.
            if let Ok(list) = std::env::var("REPLAY") {
                for i in list
                    .split(',')
                    .filter_map(|v| v.trim().parse::<usize>().ok())
                {
                    replay(&checker, states[i], distance);
                }
            }
            // `PER_STATE=path`: each state's time, parry's and the answer,
            // one line each (to see which states make a median).
            if let Ok(path) = std::env::var("PER_STATE") {
                let lines: String = which
                    .iter()
                    .enumerate()
                    .map(|(k, &i)| {
                        let hit = checker.collides_at(states[i]).unwrap();
                        format!("{what} {i} {:.3} {:.3} {hit}\n", ours[k], theirs[k])
                    })
                    .collect();
                std::fs::write(&path, lines).expect("PER_STATE's file");
            }
            if std::env::var("VERDICTS").is_ok() {
                for answer in [true, false] {
                    let (mut a, mut b) = (Vec::new(), Vec::new());
                    for (k, &i) in which.iter().enumerate() {
                        if checker.collides_at(states[i]).unwrap() == answer {
                            a.push(ours[k]);
                            b.push(theirs[k]);
                        }
                    }
                    if !a.is_empty() {
                        println!(
                            "{what} {}: {} states, median {:.2} µs, parry {:.2} µs",
                            if answer { "colliding" } else { "free" },
                            a.len(),
                            quantile(&mut a, 0.5),
                            quantile(&mut b, 0.5)
                        );
                    }
                }
            }
            // `STATS` set: how the containment tests decided their points
            // (counted since the checker was made).
            if std::env::var("STATS").is_ok() {
                println!("{what}: containment {:?}", checker.containment_stats());
            }
            let (m1, m2) = (quantile(&mut ours, 0.5), quantile(&mut theirs, 0.5));
            let (q1, q2) = (quantile(&mut ours, 0.99), quantile(&mut theirs, 0.99));
            ratios_med.push(m1 / m2);
            ratios_p99.push(q1 / q2);
            println!(
                "{:>40} {:>6} | {:>40} {:>6} {what:>6} build {:7.1} ms  median {m1:9.2} µs parry {m2:8.2} ({:5.2}x)  p99 {q1:9.1} parry {q2:8.1} ({:5.2}x)",
                &pa.name[pa.name.len().saturating_sub(40)..],
                pa.mesh.faces.len(),
                &pb.name[pb.name.len().saturating_sub(40)..],
                pb.mesh.faces.len(),
                build * 1e3,
                m1 / m2,
                q1 / q2
            );
        }
    }
    let gm = |v: &[f64]| (v.iter().map(|x| x.ln()).sum::<f64>() / v.len() as f64).exp();
    println!(
        "geometric mean of ratios: median {:.2}x, p99 {:.2}x; worst median {:.2}x",
        gm(&ratios_med),
        gm(&ratios_p99),
        ratios_med.iter().cloned().fold(0.0, f64::max)
    );
}
