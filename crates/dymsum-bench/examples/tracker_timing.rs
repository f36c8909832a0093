//! Per-frame contact query timing on two of the paper's models (gs4 and
//! ellipse), 500 steps per turn: the DYMSUM [`ContactTracker`], parry3d's
//! GJK/EPA `contact`, and a static recompute (`walk` sum + evaluation).
//! Also reports the largest disagreement of parry's depth with ours.
//!
//! Run: `cargo run --release -p dymsum-bench --example tracker_timing`

use dymsum::polytope::MeshPolicy;
use dymsum::query::ConvexPair;
use dymsum::{DVec3, Polytope, Pose};
use dymsum_bench::contact::{agreement, contact_motion, parry_pose, parry_shape, Agreement};
use std::time::Instant;

fn load(name: &str) -> Polytope {
    dymsum_io::load_polytope(name, MeshPolicy::default())
        .expect("built-in model")
        .polytope
}

fn main() {
    println!("| A vs B | frames in contact | DYMSUM tracker µs | of which update µs | static recompute µs | parry contact µs | max depth diff vs parry | verdicts differing |");
    println!("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    for (na, nb) in [
        ("gs4", "ellipse"),
        ("ti", "vrod"),
        ("cone", "cube"),
        ("dd", "hp"),
        ("gs2", "cylinder"),
    ] {
        run_pair(na, nb);
    }
}

/// Penetration depth by brute force: the exact hull of all pairwise
/// differences of the posed vertices, minimum distance from the origin to
/// its face planes (the origin inside).
fn brute_depth(a: &Polytope, pa: Pose, b: &Polytope, pb: Pose) -> f64 {
    use dymsum::hull::{convex_hull, PairwiseSums};
    let va: Vec<DVec3> = a.vertices().iter().map(|&v| pa.apply(v)).collect();
    let vb: Vec<DVec3> = b.vertices().iter().map(|&v| -pb.apply(v)).collect();
    let sums = PairwiseSums { p: &va, q: &vb };
    let hull = convex_hull(&sums).unwrap();
    let pt = |k: usize| {
        let (i, j) = sums.split(k);
        va[i] + vb[j]
    };
    hull.faces
        .iter()
        .map(|f| {
            let (p0, p1, p2) = (pt(f[0]), pt(f[1]), pt(f[2]));
            let n = (p1 - p0).cross(p2 - p0).normalize();
            n.dot(p0)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Times one pair: A turns about a fixed axis at 500 steps per turn while it
/// slides in and out of contact with B, which turns slowly the other way
/// (`dymsum_bench::contact::contact_motion`).
fn run_pair(na: &str, nb: &str) {
    let a = load(na);
    let b = load(nb);
    let frames = 1000; // two turns at 500 steps per turn
    let poses = contact_motion(&a, &b, 500.0, frames);
    let pair = ConvexPair::new(&a, &b).unwrap();

    // DYMSUM tracker.
    let mut tracker = pair.tracker(poses[0].0, poses[0].1).unwrap();
    let t0 = Instant::now();
    let mut ours = Vec::with_capacity(frames);
    for &(pa, pb) in &poses {
        ours.push(tracker.update(pa, pb).unwrap());
    }
    let tracker_us = t0.elapsed().as_secs_f64() * 1e6 / frames as f64;

    // The dynamic update alone (no query), for the split.
    let neg_b = dymsum::query::Reflected::new(&b);
    let mut dynamic = dymsum::DynamicSum::new(
        &a,
        poses[0].0,
        &neg_b.polytope,
        dymsum::query::Reflected::pose(poses[0].1),
    )
    .unwrap();
    let t0 = Instant::now();
    for &(pa, pb) in &poses {
        dynamic.set_pose(pa, dymsum::query::Reflected::pose(pb));
    }
    let update_us = t0.elapsed().as_secs_f64() * 1e6 / frames as f64;

    // Static recompute.
    let t0 = Instant::now();
    for (k, &(pa, pb)) in poses.iter().enumerate().step_by(5) {
        let r = pair.query(pa, pb).unwrap();
        assert_eq!(r, ours[k], "frame {k}");
    }
    let static_us = t0.elapsed().as_secs_f64() * 1e6 / (frames / 5) as f64;

    // parry3d-f64 GJK/EPA.
    let (sa, sb) = (parry_shape(&a), parry_shape(&b));
    let pp: Vec<_> = poses
        .iter()
        .map(|&(x, y)| (parry_pose(x), parry_pose(y)))
        .collect();
    let t0 = Instant::now();
    let mut theirs = Vec::with_capacity(frames);
    for (pa, pb) in &pp {
        theirs.push(parry3d_f64::query::contact(pa, &sa, pb, &sb, 0.0).unwrap());
    }
    let parry_us = t0.elapsed().as_secs_f64() * 1e6 / frames as f64;

    let (mut worst, mut hits, mut disagree, mut worst_frame) = (0.0f64, 0, 0, 0);
    for (k, (o, t)) in ours.iter().zip(&theirs).enumerate() {
        if o.intersects() {
            hits += 1;
        }
        match agreement(o, t.as_ref()) {
            Agreement::Depths(d) if d > worst => {
                worst = d;
                worst_frame = k;
            }
            Agreement::OnlyOurs | Agreement::OnlyParry => disagree += 1,
            _ => {}
        }
    }
    // Independent check of the frame where parry differs most: the exact
    // hull of all pairwise differences, minimum over its face planes.
    let brute = brute_depth(&a, poses[worst_frame].0, &b, poses[worst_frame].1);
    let ours_w = ours[worst_frame].depth();
    assert!(
        (brute - ours_w).abs() <= 1e-9 * (1.0 + brute.abs()),
        "{na} vs {nb}: ours {ours_w} vs brute force {brute}"
    );
    println!(
        "| {na} vs {nb} | {hits} of {frames} | {tracker_us:.1} | {update_us:.1} | {static_us:.1} | {parry_us:.1} | {worst:.1e} | {disagree} |"
    );
}
