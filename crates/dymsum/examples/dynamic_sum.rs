//! DYMSUM, the dynamic Minkowski sum: a [`DynamicSum`] of `P ⊕ Q` is turned
//! in 100 small steps about a fixed axis; each step repairs only what the
//! turn changed, and the [`UpdateReport`] says what that was (faces whose
//! vertex changed, edge pairs that stopped crossing, facets removed and
//! added, arcs re-walked). At the end the dynamic facet set is checked
//! against a fresh static `walk` sum at the final poses.
//!
//! Run: `cargo run --release -p dymsum --example dynamic_sum`

use dymsum::dynamic::UpdateReport;
use dymsum::{minkowski_sum_posed, DVec3, DynamicSum, Method, Polytope, Pose, Rotation};

/// `n` points on the ellipsoid with semi-axes `radii` (a Fibonacci sphere).
fn ellipsoid(n: usize, radii: DVec3) -> Vec<[f64; 3]> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - z * z).sqrt();
            let (s, c) = (golden * i as f64).sin_cos();
            (DVec3::new(r * c, r * s, z) * radii).to_array()
        })
        .collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let p = Polytope::from_points(&ellipsoid(300, DVec3::new(2.0, 1.0, 0.5)))?;
    let q = Polytope::from_points(&ellipsoid(100, DVec3::new(1.0, 1.0, 1.0)))?;
    let mut sum = DynamicSum::new(&p, Pose::IDENTITY, &q, Pose::IDENTITY)?;
    println!(
        "P: {} faces, Q: {} faces; P ⊕ Q starts with {} facets",
        p.face_count(),
        q.face_count(),
        sum.facet_count()
    );

    // 100 steps of 0.01 rad (about 0.6°) about a fixed, generic axis.
    let step = Rotation::from_axis_angle(DVec3::new(1.0, 2.0, 3.0), 0.01).ok_or("zero axis")?;
    let mut total = UpdateReport::default();
    println!("step  fv-repairs  ee-repairs  removed  added  rewalked arcs  facets");
    for k in 1..=100 {
        let report = sum.rotate_p_by(step);
        println!(
            "{k:4}  {:10}  {:10}  {:7}  {:5}  {:13}  {:6}{}",
            report.fv_errors,
            report.ee_errors,
            report.removed.len(),
            report.added.len(),
            report.rewalked_arcs,
            sum.facet_count(),
            if report.recomputed {
                "  (recomputed)"
            } else {
                ""
            }
        );
        total.fv_errors += report.fv_errors;
        total.ee_errors += report.ee_errors;
        total.rewalked_arcs += report.rewalked_arcs;
    }
    println!(
        "in all: {} fv-repairs, {} ee-repairs, {} arcs re-walked",
        total.fv_errors, total.ee_errors, total.rewalked_arcs
    );

    // The dynamic result must be the static one at the final poses.
    let fresh = minkowski_sum_posed(&p, sum.pose_p(), &q, sum.pose_q(), Method::Walk)?;
    if fresh.facets() != sum.facets() {
        return Err("the dynamic facets differ from a fresh walk sum".into());
    }
    println!(
        "checked: the dynamic facet set equals a fresh static walk sum ({} facets)",
        fresh.facets().len()
    );
    Ok(())
}
