//! The cost of a dynamic sum's first updates against its steady state
//! (issue 36: "no cold-start penalty a user would feel"): for each pair,
//! many fresh runs of the paper's motion (500 steps per turn, the
//! `table1` motion), the median time of update `k` over the runs, for the
//! first steps and for a late one.
//!
//! `cargo run --release -p dymsum-bench --example cold_start [A B ...]`
//! (pairs of model names; default `hp hp cube cube ellipse gs4`).
use std::time::Instant;

use dymsum::{DVec3, DynamicSum, Pose};
use dymsum_bench::{load, paper_motion};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let names: Vec<String> = if args.is_empty() {
        ["hp", "hp", "cube", "cube", "ellipse", "gs4"]
            .map(String::from)
            .to_vec()
    } else {
        args
    };
    let runs = 301;
    if let Ok(n) = std::env::var("CONSTRUCT") {
        // For profiles: `n` constructions and first steps of the first pair.
        let (p, q) = (load(&names[0]), load(&names[1]));
        let first = paper_motion(500.0, 1, 1)[0];
        for _ in 0..n.parse::<usize>().unwrap() {
            let mut dy = DynamicSum::new(&p, Pose::IDENTITY, &q, Pose::IDENTITY).unwrap();
            if std::env::var("STEP").is_ok() {
                std::hint::black_box(dy.set_pose_p(Pose::new(first, DVec3::ZERO)));
            }
        }
        return;
    }
    if let Ok(n) = std::env::var("STEADY") {
        // For profiles: one sum of the first pair through `n` steps.
        let (p, q) = (load(&names[0]), load(&names[1]));
        let mut dy = DynamicSum::new(&p, Pose::IDENTITY, &q, Pose::IDENTITY).unwrap();
        let per_turn = std::env::var("PER_TURN").map_or(500.0, |s| s.parse().unwrap());
        for r in paper_motion(per_turn, n.parse().unwrap(), 1) {
            std::hint::black_box(dy.set_pose_p(Pose::new(r, DVec3::ZERO)));
        }
        return;
    }
    if std::env::var("REPORTS").is_ok() {
        let (p, q) = (load(&names[0]), load(&names[1]));
        let mut dy = DynamicSum::new(&p, Pose::IDENTITY, &q, Pose::IDENTITY).unwrap();
        for (k, r) in paper_motion(500.0, 20, 1).into_iter().enumerate() {
            let rep = dy.set_pose_p(Pose::new(r, DVec3::ZERO));
            println!("{k}: angle {:.4} checked {} fv {} ee {} rewalked {} certified {} recomputed {} added {} removed {}", rep.step_angle, rep.checked_normals, rep.fv_errors, rep.ee_errors, rep.rewalked_arcs, rep.certified_crossings, rep.recomputed, rep.added.len(), rep.removed.len());
        }
        return;
    }
    let steps = 60;
    println!(
        "pair | construct µs | update 1 | 2 | 3 | 5 | 10 | 30 | 60 | mean of 60 | mean of 2..60"
    );
    for pair in names.chunks(2) {
        let (p, q) = (load(&pair[0]), load(&pair[1]));
        let poses: Vec<Pose> = paper_motion(500.0, steps, 1)
            .into_iter()
            .map(|r| Pose::new(r, DVec3::ZERO))
            .collect();
        let mut at: Vec<Vec<f64>> = (0..steps).map(|_| Vec::with_capacity(runs)).collect();
        let mut build = Vec::with_capacity(runs);
        for _ in 0..runs {
            let t = Instant::now();
            let mut dy = DynamicSum::new(&p, Pose::IDENTITY, &q, Pose::IDENTITY).unwrap();
            build.push(t.elapsed().as_secs_f64() * 1e6);
            for (k, pose) in poses.iter().enumerate() {
                let t = Instant::now();
                std::hint::black_box(dy.set_pose_p(*pose));
                at[k].push(t.elapsed().as_secs_f64() * 1e6);
            }
        }
        let med = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let meds: Vec<f64> = at.iter_mut().map(med).collect();
        let mean_all = meds.iter().sum::<f64>() / steps as f64;
        let mean_late = meds[1..].iter().sum::<f64>() / (steps - 1) as f64;
        println!(
            "{} ⊕ {} | {:.2} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3}",
            pair[0],
            pair[1],
            med(&mut build),
            meds[0],
            meds[1],
            meds[2],
            meds[4],
            meds[9],
            meds[29],
            meds[59],
            mean_all,
            mean_late
        );
    }
}
