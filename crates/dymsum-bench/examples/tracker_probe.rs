//! One pair's contact tracker alone, for profiles (issue 36):
//! `valgrind --tool=callgrind target/release/examples/tracker_probe A B [FRAMES]`
//! runs `ContactTracker::update` along `tracker_timing`'s motion (500 steps
//! per turn) and, with `PARRY=1`, parry's `contact` on the same frames
//! instead; `STRATEGY=certified|sum` fixes the tracker's strategy (else
//! `Auto`, which times both on its first frames: under a profiler its
//! choice can differ from a native run's), and `STRATEGY=static` runs a
//! cold `ConvexPair::query` per frame instead of the tracker.
use dymsum::query::{ContactTracker, ConvexPair, TrackerStrategy};
use dymsum_bench::contact::{contact_motion, parry_pose, parry_shape};
use dymsum_bench::load;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (a, b) = (load(&args[0]), load(&args[1]));
    let frames: usize = args.get(2).map_or(1000, |s| s.parse().expect("FRAMES"));
    let poses = contact_motion(&a, &b, 500.0, frames);
    let mut hits = 0;
    if std::env::var("STRATEGY").as_deref() == Ok("static") {
        let pair = ConvexPair::new(&a, &b).unwrap();
        for &(pa, pb) in &poses {
            hits += usize::from(pair.query(pa, pb).unwrap().intersects());
        }
        eprintln!("{:?}", pair.stats());
    } else if std::env::var("PARRY").is_ok() {
        let (sa, sb) = (parry_shape(&a), parry_shape(&b));
        for &(pa, pb) in &poses {
            let c = parry3d_f64::query::contact(&parry_pose(pa), &sa, &parry_pose(pb), &sb, 0.0);
            hits += usize::from(c.unwrap().is_some_and(|c| c.dist <= 0.0));
        }
    } else {
        let pair = ConvexPair::new(&a, &b).unwrap();
        let strategy = match std::env::var("STRATEGY").as_deref() {
            Ok("certified") => TrackerStrategy::Certified,
            Ok("sum") => TrackerStrategy::DynamicSum,
            _ => TrackerStrategy::Auto,
        };
        let mut tracker =
            ContactTracker::with_strategy(&pair, poses[0].0, poses[0].1, strategy).unwrap();
        for &(pa, pb) in &poses {
            hits += usize::from(tracker.update(pa, pb).unwrap().intersects());
        }
        eprintln!("{:?}", pair.stats());
    }
    eprintln!("{hits} of {frames} frames in contact");
}
