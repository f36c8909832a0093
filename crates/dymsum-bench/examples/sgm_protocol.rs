//! The DYMSUM side of issue 36's comparison with CGAL's spherical Gaussian
//! maps (`python/benchmarks/cgal/bench_sgm.py` runs both; protocol in
//! docs/BENCHMARKS.md, "DYMSUM against CGAL's Gaussian maps").
//!
//! `sgm_protocol P Q STEPS DIR [REPEATS]` writes `DIR/p.off` and `DIR/q.off`
//! (the polytopes as dymsum loads them: their vertices, exact in OFF's
//! shortest round-trip decimals, and faces) and `DIR/rotations.txt` (P's
//! rotation matrix at each of `STEPS` steps of the paper's motion, 500
//! steps per turn, seed 1, row-major, the same doubles DYMSUM turns by),
//! then times the DYMSUM updates along those rotations (Q fixed at the
//! identity; the sum is built at the motion's first pose, untimed) and
//! prints one JSON line: the median and mean microseconds per update, each
//! update keeping its fastest time over `REPEATS` runs (default 5), and
//! the facet count after the last step.
use std::fmt::Write as _;
use std::time::Instant;

use dymsum::{DVec3, DynamicSum, Pose};
use dymsum_bench::{load, paper_motion};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 4 {
        eprintln!("usage: sgm_protocol P Q STEPS DIR [REPEATS]");
        std::process::exit(2);
    }
    let (p, q) = (load(&args[0]), load(&args[1]));
    let steps: usize = args[2].parse().expect("STEPS");
    let dir = std::path::Path::new(&args[3]);
    let repeats: usize = args.get(4).map_or(5, |r| r.parse().expect("REPEATS"));
    std::fs::create_dir_all(dir).unwrap();
    // dymsum-io's OFF writer prints each coordinate's shortest round-trip
    // decimal: the vertices are exact.
    for (body, name) in [(&p, "p.off"), (&q, "q.off")] {
        dymsum_io::formats::write_mesh(&dir.join(name), &body.to_mesh()).unwrap();
    }
    // One more pose than steps: the sum starts at the first.
    let poses = paper_motion(500.0, steps + 1, 1);
    let mut rotations = String::new();
    for r in &poses[1..] {
        let m = r.matrix();
        let rows = [m.row(0), m.row(1), m.row(2)];
        let line: Vec<String> = rows
            .iter()
            .flat_map(|row| row.to_array())
            .map(|x| format!("{x:?}"))
            .collect();
        writeln!(rotations, "{}", line.join(" ")).unwrap();
    }
    std::fs::write(dir.join("rotations.txt"), rotations).unwrap();

    let mut best = vec![f64::INFINITY; steps];
    let mut facets = 0;
    for _ in 0..repeats {
        let mut dy = DynamicSum::new(&p, Pose::new(poses[0], DVec3::ZERO), &q, Pose::IDENTITY)
            .expect("the initial sum");
        for (k, r) in poses[1..].iter().enumerate() {
            let t = Instant::now();
            std::hint::black_box(dy.set_pose_p(Pose::new(*r, DVec3::ZERO)));
            best[k] = best[k].min(t.elapsed().as_secs_f64() * 1e6);
        }
        facets = dy.facet_count();
    }
    let mut sorted = best.clone();
    sorted.sort_by(f64::total_cmp);
    let mean = best.iter().sum::<f64>() / steps as f64;
    println!(
        "{{\"median_us\": {:.4}, \"mean_us\": {:.4}, \"steps\": {steps}, \"repeats\": {repeats}, \"facets\": {facets}}}",
        sorted[steps / 2],
        mean
    );
}
