//! Development probe: one pair's tracker frames or static queries in a loop
//! (for profiling): `probe_intersects A B [t|s|c|q|i]` (tracker auto, sum,
//! certified; static query; intersects).
use dymsum::query::{ContactTracker, ConvexPair, TrackerStrategy};
use dymsum_bench::contact::contact_motion;
use dymsum_bench::load;
fn main() {
    let a = load(&std::env::args().nth(1).unwrap_or("box:1,2,3".into()));
    let b = load(&std::env::args().nth(2).unwrap_or("box:2,1,1".into()));
    let what = std::env::args().nth(3).unwrap_or("t".into());
    let pair = ConvexPair::new(&a, &b).unwrap();
    let poses = contact_motion(&a, &b, 500.0, 1000);
    let strategy = match what.as_str() {
        "s" => TrackerStrategy::DynamicSum,
        "c" => TrackerStrategy::Certified,
        _ => TrackerStrategy::Auto,
    };
    let mut tr = ContactTracker::with_strategy(&pair, poses[0].0, poses[0].1, strategy).unwrap();
    let t = std::time::Instant::now();
    for _ in 0..50 {
        for &(pa, pb) in &poses {
            match what.as_str() {
                "i" => {
                    std::hint::black_box(pair.intersects(pa, pb).unwrap());
                }
                "q" => {
                    std::hint::black_box(pair.query(pa, pb).unwrap());
                }
                _ => {
                    std::hint::black_box(tr.update(pa, pb).unwrap());
                }
            }
        }
    }
    println!("{:.2} µs", t.elapsed().as_secs_f64() * 1e6 / 50000.0);
}
