//! Times certified short motions on robot part pairs (issue 35):
//! `PAIR=a,b cargo run --release -p dymsum-bench --example parts_motions
//! -- DIR [MOTIONS]`: from the free ends of near-contact bisections, turns
//! of 1° to 5° about a random axis through the body's box centre, and a
//! move of up to 1% of the obstacle's diagonal; prints the median and
//! 99th percentile of `SceneChecker::check` and the interval counts.
//! `REPEAT=k` runs the motions k times (the random turns differ each
//! round). With `DECISION=1` each motion is decided as the OMPL validator decides
//! it: `sampled_contact` on the discrete check's states (`SEGMENTS`, 2 by
//! default), then `check` backwards with the contact bracketed to 1/8.
//! `ONLY=k` times the k-th motion alone (`VERBOSE=1` lists them).

use std::time::Instant;

use dymsum::query::{Checker, MotionCheck};
use dymsum::{DVec3, Pose, Rotation};
use dymsum_bench::parts::{pair_states, part_checker, parts};
use rand::{Rng, SeedableRng};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = std::path::Path::new(args.get(1).map_or("/tmp/rm", |s| s));
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(40);
    let pair = std::env::var("PAIR").unwrap_or_else(|_| "link_2,piston".into());
    let all = parts(dir);
    let (a, b) = pair.split_once(',').expect("PAIR=a,b");
    let find = |s: &str| all.iter().find(|q| q.name.contains(s)).expect("a part");
    let (pa, pb) = (find(a), find(b));
    let checker = part_checker(&pa.mesh, &pb.mesh);
    let (_, near) = pair_states(&checker, &pa.mesh, &pb.mesh, n, 11);
    let decision = std::env::var("DECISION").is_ok_and(|v| v == "1");
    let segments: usize = std::env::var("SEGMENTS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(2);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    let centre = {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for p in &pa.mesh.vertices {
            lo = lo.min(DVec3::from(*p));
            hi = hi.max(DVec3::from(*p));
        }
        (lo + hi) * 0.5
    };
    let diag = {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for p in &pb.mesh.vertices {
            lo = lo.min(DVec3::from(*p));
            hi = hi.max(DVec3::from(*p));
        }
        (hi - lo).length()
    };
    let (mut times, mut free, mut steps) = (Vec::new(), 0, Vec::new());
    // `REPEAT=k` runs the same motions k times (for profiles).
    let repeat: usize = std::env::var("REPEAT")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1);
    let starts: Vec<Pose> = near.iter().skip(1).step_by(2).copied().collect();
    // `ONLY=k`: the k-th start alone (its turn is drawn as in the full run).
    let only: Option<usize> = std::env::var("ONLY").ok().and_then(|v| v.parse().ok());
    let starts = starts.iter().cycle().take(starts.len() * repeat);
    for (k, p0) in starts.enumerate() {
        let axis = DVec3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        )
        .normalize();
        let turn =
            Rotation::from_axis_angle(axis, rng.random_range(1.0f64..5.0).to_radians()).unwrap();
        let c = p0.apply(centre);
        let shift = DVec3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        ) * (0.01 * diag);
        let p1 = Pose::new(
            p0.rotation.then(&turn),
            turn.apply(p0.translation - c) + c + shift,
        );
        if only.is_some_and(|o| o != k) {
            continue;
        }
        let before = checker.steps();
        let t = Instant::now();
        let r = if decision {
            match checker.sampled_contact(p1, *p0, segments, 7) {
                Ok(Some(t)) => Ok(MotionCheck::Collides {
                    t_safe: None,
                    t_contact: t,
                }),
                _ => checker.check(p1, *p0, 0.125),
            }
        } else {
            checker.check(*p0, p1, 1e-6)
        };
        times.push(t.elapsed().as_secs_f64() * 1e6);
        steps.push(checker.steps() - before);
        free += usize::from(matches!(r, Ok(MotionCheck::Free)));
        if std::env::var("VERBOSE").is_ok() {
            println!(
                "{:>9.0} µs {:>5} intervals {r:?}",
                times[times.len() - 1],
                steps[steps.len() - 1]
            );
        }
    }
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    let q = |x: f64| sorted[((sorted.len() - 1) as f64 * x).round() as usize];
    steps.sort_unstable();
    println!(
        "{} vs {}: {} motions, {free} free; median {:.0} µs, p99 {:.0} µs; intervals median {} max {}",
        pa.name,
        pb.name,
        times.len(),
        q(0.5),
        q(0.99),
        steps[steps.len() / 2],
        steps[steps.len() - 1]
    );
}
