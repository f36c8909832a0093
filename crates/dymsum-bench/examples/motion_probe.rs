//! Per-scene motion-check timing and counts (a development probe):
//! `cargo run --release -p dymsum-bench --example motion_probe [SCENE] [REPS]`.
use dymsum::query::{MotionCheck, MotionChecker};
use dymsum_bench::motion::scenes;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let only = args.get(1).cloned();
    let reps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(200);
    for scene in scenes(64) {
        if only.as_deref().is_some_and(|o| o != scene.name) {
            continue;
        }
        let checker = MotionChecker::new(&scene.body_union(), &scene.obstacle_unions()).unwrap();
        let start = Instant::now();
        let mut collide = 0;
        for _ in 0..reps {
            for &(a, b) in &scene.motions {
                if let MotionCheck::Collides { .. } = checker.check(a, b, 1e-6).unwrap() {
                    collide += 1;
                }
            }
        }
        let check_us = start.elapsed().as_secs_f64() * 1e6 / (reps * scene.motions.len()) as f64;
        println!("  check: {check_us:.2} µs; {:?}", checker.stats());
        let t2 = Instant::now();
        let mut hits = 0;
        for _ in 0..reps {
            for &(a, b) in &scene.motions {
                let m = dymsum::query::Motion::new(a, b);
                for k in 0..4 {
                    hits += checker.collides_at(m.at(k as f64 / 4.0)).unwrap() as usize;
                }
            }
        }
        println!(
            "  collides_at: {:.2} µs ({hits})",
            t2.elapsed().as_secs_f64() * 1e6 / (reps * 64 * 4) as f64
        );
        let pair = dymsum::query::ConvexPair::new(&scene.body, &scene.obstacles[0]).unwrap();
        let t3 = Instant::now();
        for _ in 0..reps {
            for &(a, b) in &scene.motions {
                let m = dymsum::query::Motion::new(a, b);
                for k in 0..4 {
                    std::hint::black_box(
                        pair.query(m.at(k as f64 / 4.0), dymsum::Pose::IDENTITY)
                            .unwrap(),
                    );
                }
            }
        }
        println!(
            "  query: {:.2} µs; stats {:?}",
            t3.elapsed().as_secs_f64() * 1e6 / (reps * 64 * 4) as f64,
            pair.stats()
        );
        let per = start.elapsed().as_secs_f64() / (reps * scene.motions.len()) as f64;
        println!(
            "{}: {:.1} µs per motion in all, {} colliding",
            scene.name,
            per * 1e6,
            collide / reps
        );
    }
}
