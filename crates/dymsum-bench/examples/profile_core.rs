//! A fixed workload for instruction-count profiles of the paper's core
//! (issue 36): `valgrind --tool=callgrind target/release/examples/profile_core MODE`.
//!
//! * `update`: 2,000 DYMSUM updates of ellipse ⊕ gs4 under the paper's
//!   motion (500 steps per turn), as `dymsum demo` moves them;
//! * `walk`: the static `walk` sums at the same 2,000 poses;
//! * `halfspaces`: the half-space read-out of `cobst_map` (gs4 among
//!   ellipse, 4,000 orientations about `(1, 2, 3)`);
//! * `slices`: the same DYMSUM updates without the read-out.
//!
//! Each mode runs its work once; a profile's difference between modes is
//! the read-out's or the update's own cost.
use std::hint::black_box;

use dymsum::query::orientations_about_axis;
use dymsum::sum::{minkowski_sum_posed, Method};
use dymsum::{CObstacle, DVec3, DynamicSum, Pose};
use dymsum_bench::{load, paper_motion};

fn main() {
    let mode = std::env::args().nth(1).unwrap_or_else(|| "update".into());
    match mode.as_str() {
        "update" | "walk" => {
            let (p, q) = (load("ellipse"), load("gs4"));
            let poses: Vec<Pose> = paper_motion(500.0, 2001, 1)
                .into_iter()
                .map(|r| Pose::new(r, DVec3::ZERO))
                .collect();
            if mode == "update" {
                let mut dy = DynamicSum::new(&p, poses[0], &q, Pose::IDENTITY).unwrap();
                let (mut checked, mut fv, mut rewalked, mut crossings) = (0, 0, 0, 0);
                let (mut recomputed, mut recovered) = (0, 0);
                for pose in &poses[1..] {
                    let r = dy.set_pose_p(*pose);
                    checked += r.checked_normals;
                    fv += r.fv_errors;
                    rewalked += r.rewalked_arcs;
                    crossings += r.certified_crossings;
                    recomputed += usize::from(r.recomputed);
                    recovered += usize::from(r.recovered.is_some());
                }
                let n = (poses.len() - 1) as f64;
                eprintln!(
                    "per update: {:.1} normals checked, {:.1} fv-errors, {:.1} certified crossings, {:.1} arcs re-walked; {} facets; {recomputed} recomputed ({recovered} recovered)",
                    checked as f64 / n,
                    fv as f64 / n,
                    crossings as f64 / n,
                    rewalked as f64 / n,
                    dy.facet_count()
                );
            } else {
                for pose in &poses[1..] {
                    let s =
                        minkowski_sum_posed(&p, *pose, &q, Pose::IDENTITY, Method::Walk).unwrap();
                    black_box(s.facets().len());
                }
            }
        }
        "halfspaces" | "slices" => {
            let (robot, obstacle) = (load("gs4"), load("ellipse"));
            let cobst = CObstacle::new(&robot, &obstacle).unwrap();
            let turns = orientations_about_axis(DVec3::new(1.0, 2.0, 3.0), 4000).unwrap();
            if mode == "halfspaces" {
                black_box(cobst.halfspace_slices(&turns).unwrap().len());
            } else {
                let pose = |k: usize| Pose::new(turns[k], DVec3::ZERO);
                let mut s =
                    DynamicSum::new(cobst.reflected_robot(), pose(0), &obstacle, Pose::IDENTITY)
                        .unwrap();
                for k in 1..turns.len() {
                    s.set_pose(pose(k), Pose::IDENTITY);
                }
                black_box(s.facet_count());
            }
        }
        other => panic!("unknown mode {other:?}: update, walk, halfspaces or slices"),
    }
}
