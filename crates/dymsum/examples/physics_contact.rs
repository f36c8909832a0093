//! A physics-style contact per frame: a box falls, turning, onto a slab; a
//! [`ContactTracker`] keeps `A ⊕ (−B)` up to date by DYMSUM updates and
//! reports the exact penetration depth, normal and witness points every
//! frame; the "solver" pushes the box out along the contact normal.
//!
//! Run: `cargo run --release -p dymsum --example physics_contact`

use dymsum::query::{ConvexPair, Proximity};
use dymsum::{DVec3, Polytope, Pose, Rotation};

fn cuboid(half: DVec3) -> Polytope {
    let pts: Vec<DVec3> = (0..8)
        .map(|i| {
            DVec3::new(
                if i & 1 == 0 { -half.x } else { half.x },
                if i & 2 == 0 { -half.y } else { half.y },
                if i & 4 == 0 { -half.z } else { half.z },
            )
        })
        .collect();
    Polytope::from_dvec3s(&pts).expect("a box")
}

fn main() {
    let body = cuboid(DVec3::new(0.5, 0.3, 0.2));
    let ground = cuboid(DVec3::new(5.0, 5.0, 0.5));
    let pair = ConvexPair::new(&body, &ground).expect("prepared");
    let ground_pose = Pose::IDENTITY;
    let spin = DVec3::new(0.3, 1.0, 0.2);
    let (mut z, mut vz, dt, g) = (2.0, 0.0, 1.0 / 60.0, -9.81);
    let pose = |z: f64, k: usize| {
        let r = Rotation::from_axis_angle(spin, 0.02 * k as f64).unwrap();
        Pose::new(r, DVec3::new(0.1, -0.2, z))
    };
    let mut tracker = pair.tracker(pose(z, 0), ground_pose).expect("tracker");
    for k in 1..=150 {
        vz += g * dt;
        z += vz * dt;
        let p = pose(z, k);
        match tracker.update(p, ground_pose).expect("update") {
            Proximity::Penetrating(c) => {
                // Push the body out: translate it by −depth · normal.
                z -= c.depth * c.normal.z;
                vz = 0.0; // perfectly inelastic
                if k % 5 == 0 {
                    println!(
                        "frame {k:3}: contact depth {:.6} normal ({:+.3}, {:+.3}, {:+.3}) \
                         on body ({:.3}, {:.3}, {:.3}) features {:?}",
                        c.depth,
                        c.normal.x,
                        c.normal.y,
                        c.normal.z,
                        c.point_on_a.x,
                        c.point_on_a.y,
                        c.point_on_a.z,
                        c.features
                    );
                }
            }
            Proximity::Separated(s) => {
                if k % 10 == 0 {
                    println!("frame {k:3}: falling, {:.4} above the ground", s.distance);
                }
            }
        }
    }
    let u = tracker.last_update();
    println!(
        "last frame: {} facet changes repaired incrementally (recomputed: {})",
        u.added.len() + u.removed.len(),
        u.recomputed
    );
}
