//! Times certified motion checks on one OMPL.app problem's recorded
//! motions (a development probe for issue 35):
//! `cargo run --release -p dymsum-bench --example scene_motions -- SCENE MOTIONS [REPS]`,
//! `SCENE` a folder of `python/benchmarks/export_scenes.py` (`robot.obj`,
//! `env.obj`) and `MOTIONS` a text file of motions, one per line: the two
//! 4×4 poses row by row (32 numbers). Prints, for the free and the
//! colliding motions apart, the median and mean time of
//! `SceneChecker::check` at the yes/no tolerance `2⁻³` (backwards, as the
//! OMPL validator asks) and the intervals examined per motion.

use std::time::Instant;

use dymsum::glam::DMat4;
use dymsum::query::{MeshBody, MotionCheck, SceneChecker};
use dymsum::Pose;

/// The pose of a 4×4 matrix given row by row.
fn pose(m: &[f64]) -> Pose {
    let m: [f64; 16] = m.try_into().expect("16 numbers");
    Pose::from_mat4(DMat4::from_cols_array(&m).transpose()).expect("a rigid pose")
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = std::path::Path::new(&args[1]);
    let motions: Vec<(Pose, Pose)> = std::fs::read_to_string(&args[2])
        .expect("a motions file")
        .lines()
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            (pose(&v[..16]), pose(&v[16..32]))
        })
        .collect();
    let reps: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1);
    // FORWARD=1: from the first pose (the validator asks backwards).
    let forward = std::env::var("FORWARD").is_ok_and(|v| v == "1");
    // VERBOSE=1: each motion's time and intervals.
    let verbose = std::env::var("VERBOSE").is_ok_and(|v| v == "1");
    let read = |f: &str| dymsum_io::formats::read_mesh(&dir.join(f)).expect("an OBJ file");
    let robot = MeshBody::new(&read("robot.obj")).expect("a robot");
    let env = MeshBody::new(&read("env.obj")).expect("an environment");
    let checker = SceneChecker::new(&robot, &[env]).expect("a checker");
    let mut times: [Vec<f64>; 3] = Default::default();
    let mut steps: [u64; 3] = [0; 3];
    for (i, &(a, b)) in motions.iter().enumerate() {
        let before = checker.steps();
        let start = Instant::now();
        let mut out = None;
        for _ in 0..reps {
            out = Some(if forward {
                checker.check(a, b, 0.125)
            } else {
                checker.check(b, a, 0.125)
            });
        }
        let us = start.elapsed().as_secs_f64() * 1e6 / reps as f64;
        let k = match out.unwrap() {
            Ok(MotionCheck::Free) => 0,
            Ok(MotionCheck::Collides { .. }) => 1,
            Err(_) => 2,
        };
        times[k].push(us);
        if verbose {
            println!(
                "{i}: {us:.1} µs, {} intervals, {k}",
                checker.steps() - before
            );
        }
        steps[k] += (checker.steps() - before) / reps as u64;
    }
    for (k, name) in ["free", "contact", "error"].iter().enumerate() {
        let t = &mut times[k];
        if t.is_empty() {
            continue;
        }
        t.sort_by(f64::total_cmp);
        let mean = t.iter().sum::<f64>() / t.len() as f64;
        println!(
            "{name}: {} motions, median {:.1} µs, mean {:.1} µs, max {:.1} µs, {:.1} intervals each",
            t.len(),
            t[t.len() / 2],
            mean,
            t[t.len() - 1],
            steps[k] as f64 / t.len() as f64
        );
    }
}
