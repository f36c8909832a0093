//! Development probe: certified static queries on the tracker workload,
//! with the fallback counters and per-call times against parry.
use dymsum::query::ConvexPair;
use dymsum_bench::contact::{contact_motion, parry_pose, parry_shape};
use dymsum_bench::load;
use dymsum_testkit::{random_polytope, rng, Kind};
use std::time::Instant;

fn main() {
    let mut r = rng(10);
    let mut pairs = vec![
        ("box+box".to_string(), load("box:1,2,3"), load("box:2,1,1")),
        (
            "box+hull20".to_string(),
            load("box:1,2,3"),
            random_polytope(Kind::Sphere, 20, &mut r),
        ),
        (
            "box+hull60".to_string(),
            load("box:1,2,3"),
            random_polytope(Kind::Sphere, 60, &mut r),
        ),
        (
            "capsule+capsule".to_string(),
            load("capsule:8:4"),
            load("capsule:8:4"),
        ),
    ];
    for (a, b) in [
        ("dd", "hp"),
        ("cone", "cube"),
        ("gs2", "cylinder"),
        ("ti", "vrod"),
        ("gs4", "ellipse"),
    ] {
        pairs.push((format!("{a}+{b}"), load(a), load(b)));
    }
    for (label, a, b) in pairs {
        let pair = ConvexPair::new(&a, &b).unwrap();
        let poses = contact_motion(&a, &b, 500.0, 1000);
        let t = Instant::now();
        let mut hits = 0;
        for &(pa, pb) in &poses {
            hits += pair.query(pa, pb).unwrap().intersects() as usize;
        }
        let ours = t.elapsed().as_secs_f64() * 1e6 / poses.len() as f64;
        let t = Instant::now();
        for &(pa, pb) in &poses {
            std::hint::black_box(pair.intersects(pa, pb).unwrap());
        }
        let yes_no = t.elapsed().as_secs_f64() * 1e6 / poses.len() as f64;
        let mut tr = pair.tracker(poses[0].0, poses[0].1).unwrap();
        let t = Instant::now();
        for &(pa, pb) in &poses {
            std::hint::black_box(tr.update(pa, pb).unwrap());
        }
        let tracker = t.elapsed().as_secs_f64() * 1e6 / poses.len() as f64;
        let active = tr.active_strategy();
        let (sa, sb) = (parry_shape(&a), parry_shape(&b));
        let pp: Vec<_> = poses
            .iter()
            .map(|&(x, y)| (parry_pose(x), parry_pose(y)))
            .collect();
        let t = Instant::now();
        for (qa, qb) in &pp {
            std::hint::black_box(parry3d_f64::query::contact(qa, &sa, qb, &sb, 0.0).unwrap());
        }
        let parry = t.elapsed().as_secs_f64() * 1e6 / poses.len() as f64;
        println!("{label:16} hits {hits:4}  query {ours:8.2} µs  intersects {yes_no:6.2} µs  tracker {tracker:6.2} µs ({active:?})  parry {parry:6.2} µs  {:?}", pair.stats());
    }
}
