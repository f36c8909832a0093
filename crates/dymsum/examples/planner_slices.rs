//! A motion planner's use of C-obstacles: slice the configuration space of
//! a rotating, translating robot among an obstacle into one translational
//! C-obstacle per orientation (`O ⊕ (−R·A)`, DYMSUM from slice to slice,
//! spread over cores), then answer "is the robot at (R_k, t) free?" by a
//! point-in-convex-polygon-mesh test on slice k, and check it against the
//! direct collision query.
//!
//! Run: `cargo run --release -p dymsum --example planner_slices`

use dymsum::query::{intersects, orientations_about_axis, CObstacle};
use dymsum::{DVec3, PolygonMesh, Polytope, Pose};
use std::time::Instant;

fn inside(mesh: &PolygonMesh, t: DVec3) -> bool {
    mesh.faces.iter().all(|f| {
        let v: Vec<DVec3> = f.iter().map(|&i| DVec3::from(mesh.vertices[i])).collect();
        let mut n = DVec3::ZERO;
        for i in 0..v.len() {
            n += v[i].cross(v[(i + 1) % v.len()]);
        }
        n.dot(t - v[0]) <= 0.0
    })
}

fn main() {
    // A long thin robot (a rod with a pointed end) and a box obstacle.
    let robot = Polytope::from_points(&[
        [-1.0, -0.1, -0.1],
        [-1.0, 0.1, -0.1],
        [-1.0, -0.1, 0.1],
        [-1.0, 0.1, 0.1],
        [1.0, -0.1, -0.1],
        [1.0, 0.1, -0.1],
        [1.0, -0.1, 0.1],
        [1.0, 0.1, 0.1],
        [1.4, 0.0, 0.0],
    ])
    .unwrap();
    let obstacle = Polytope::from_points(&[
        [2.0, -1.0, -1.0],
        [3.0, -1.0, -1.0],
        [2.0, 1.0, -1.0],
        [3.0, 1.0, -1.0],
        [2.0, -1.0, 1.0],
        [3.0, -1.0, 1.0],
        [2.0, 1.0, 1.0],
        [3.0, 1.0, 1.0],
    ])
    .unwrap();
    let turns = orientations_about_axis(DVec3::Z, 360).unwrap();
    let cob = CObstacle::new(&robot, &obstacle).unwrap();
    let start = Instant::now();
    let slices = cob.slices_par(&turns).unwrap();
    println!(
        "{} slices in {:.1} ms ({} to {} faces)",
        slices.len(),
        start.elapsed().as_secs_f64() * 1e3,
        slices.iter().map(|s| s.faces.len()).min().unwrap(),
        slices.iter().map(|s| s.faces.len()).max().unwrap()
    );
    // Free or blocked? The robot's reference point at t = (x, 0, 0).
    let mut agree = 0;
    for k in (0..360).step_by(45) {
        let free: String = (0..24)
            .map(|i| {
                let t = DVec3::new(-1.0 + 0.125 * i as f64, 0.0, 0.0);
                let blocked = inside(&slices[k], t);
                let direct =
                    intersects(&robot, Pose::new(turns[k], t), &obstacle, Pose::IDENTITY).unwrap();
                if blocked == direct {
                    agree += 1;
                }
                if blocked {
                    '#'
                } else {
                    '.'
                }
            })
            .collect();
        println!("{:3}°  x = -1 … 1.875:  {free}", k);
    }
    println!("slice lookups agreeing with direct collision queries: {agree}/192");
}
