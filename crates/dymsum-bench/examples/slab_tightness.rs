//! How tight the certified C-obstacle slabs are (`dymsum::query::Slab`,
//! issue 20 §2), against the number of slices `K` over a full turn.
//!
//! For each pair (robot ⊕ obstacle) and each `K`, the `K` slabs of a full
//! turn about a fixed axis are built (timed, on rayon's threads), and 16 of
//! them, evenly spaced, are measured against the swept C-obstacle sampled
//! densely: 65 angles across the slab's interval (both ends included), each
//! slice computed by DYMSUM (one dynamic sum moved along the samples), `G`
//! the exact hull of all their vertices. Reported:
//!
//! * **excess**: the largest, over the measured slabs and their face
//!   planes `(n, d)`, of `d − max_{v ∈ G} n·v` — how far a plane reaches
//!   beyond the sampled swept C-obstacle in its own direction — relative to
//!   the size of the C-obstacle (`G`'s bounding-box diagonal);
//! * **margin**: the push `m` of the planes (sagitta term plus rounding,
//!   the bound on the excess over the true swept set), relative alike;
//! * **volume**: the slab's mesh volume over `G`'s, the mean over the
//!   measured slabs (how much free space a planner loses), and the same
//!   for the plain hull of the two end slices (not certified: below 1 when
//!   the middle of the turn pokes out of it).
//!
//! Run: `cargo run --release -p dymsum-bench --example slab_tightness`
//! (about a minute on 2 cores; `-- --quick` for K = 16, 64 only).

use dymsum::polytope::MeshPolicy;
use dymsum::query::{full_turn_angles, rotations_about_axis, Slab};
use dymsum::{CObstacle, DVec3, Polytope};
use std::time::Instant;

/// Dense samples per slab: 64 steps, 65 angles.
const SAMPLES: usize = 64;
/// Slabs measured per `K` (evenly spaced over the turn).
const MEASURED: usize = 16;

fn load(name: &str) -> Polytope {
    dymsum_io::load_polytope(name, MeshPolicy::default())
        .expect("built-in model")
        .polytope
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let ks: &[usize] = if quick {
        &[16, 64]
    } else {
        &[16, 64, 256, 1024]
    };
    let axis = DVec3::new(0.31, -0.57, 0.76);
    println!(
        "axis ({}, {}, {}); {SAMPLES} samples per measured slab, {MEASURED} slabs measured per K",
        axis.x, axis.y, axis.z
    );
    println!();
    println!("| robot ⊕ obstacle | K | step (rad) | build ms per slab | planes per slab | excess / size | margin / size | volume slab / swept | volume plain hull / swept |");
    println!("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    for (robot, obstacle) in [
        ("gs4", "ellipse"),
        ("box:1,2,0.5", "box:2,1,1"),
        ("box:4,0.2,0.2", "box:1"),
    ] {
        let (a, o) = (load(robot), load(obstacle));
        let cobst = CObstacle::new(&a, &o).expect("reflecting the robot");
        for &k in ks {
            run(&cobst, &format!("{robot} ⊕ {obstacle}"), axis, k);
        }
    }
}

/// Builds and measures the `k` slabs of a full turn.
fn run(cobst: &CObstacle, label: &str, axis: DVec3, k: usize) {
    let angles = full_turn_angles(k);
    let turns = rotations_about_axis(axis, &angles).expect("valid turn");
    let start = Instant::now();
    let slabs = cobst.certified_slabs_par(&turns).expect("slabs");
    let build_ms = start.elapsed().as_secs_f64() * 1e3 / k as f64;
    let planes: usize = slabs.iter().map(Slab::len).sum::<usize>() / k;
    let (mut excess, mut margin) = (0.0f64, 0.0f64);
    let (mut vol, mut vol_plain) = (0.0, 0.0);
    let measured: Vec<usize> = (0..MEASURED.min(k))
        .map(|j| j * k / MEASURED.min(k))
        .collect();
    for &s in &measured {
        let slab = &slabs[s];
        let (lo, hi) = (angles[s], angles[s + 1]);
        let dense: Vec<f64> = (0..=SAMPLES)
            .map(|j| lo + (hi - lo) * j as f64 / SAMPLES as f64)
            .collect();
        let samples = rotations_about_axis(axis, &dense).expect("valid samples");
        let mut points = Vec::new();
        for slice in cobst.slices(&samples) {
            points.extend(
                slice
                    .expect("slice")
                    .vertices
                    .iter()
                    .map(|&v| DVec3::from(v)),
            );
        }
        let swept = Polytope::from_dvec3s(&points).expect("hull of the samples");
        let size = swept.diameter();
        for (&n, &d) in slab.normals().iter().zip(slab.offsets()) {
            let top = swept.vertex(swept.support_vertex(n)).dot(n);
            excess = excess.max((d - top) / size);
        }
        margin = margin.max(slab.margin() / size);
        let mesh = slab.mesh().expect("slab mesh");
        vol += mesh.signed_volume() / swept.volume();
        vol_plain += slab.hull().volume() / swept.volume();
    }
    let m = measured.len() as f64;
    println!(
        "| {label} | {k} | {:.4} | {build_ms:.2} | {planes} | {excess:.2e} | {margin:.2e} | {:.5} | {:.5} |",
        std::f64::consts::TAU / k as f64,
        vol / m,
        vol_plain / m,
    );
}
