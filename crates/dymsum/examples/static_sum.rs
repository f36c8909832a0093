//! The static Minkowski sum `P ⊕ Q`, the smallest complete use: build two
//! convex polytopes from point clouds ([`Polytope::from_points`], an exact
//! hull), sum them with each of the three methods (`brute`, `walk`,
//! `hull`), print the facet counts, and check that the three labelled facet
//! sets are identical. Nothing is written to disk.
//!
//! Run: `cargo run --release -p dymsum --example static_sum`

use dymsum::{minkowski_sum, DVec3, Method, Polytope};

/// `n` points on the ellipsoid with semi-axes `radii`, spread by the golden
/// angle (a Fibonacci sphere): a smooth convex body with many faces.
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
    // P: a flattened ellipsoid; Q: a box with one corner cut off.
    let p = Polytope::from_points(&ellipsoid(200, DVec3::new(2.0, 1.0, 0.5)))?;
    let q = Polytope::from_points(&[
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 2.0, 0.0],
        [1.0, 2.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [0.0, 2.0, 1.0],
        [1.0, 1.5, 1.0],
        [0.5, 2.0, 1.0],
    ])?;
    println!(
        "P: {} vertices, {} faces; Q: {} vertices, {} faces",
        p.vertex_count(),
        p.face_count(),
        q.vertex_count(),
        q.face_count()
    );

    let mut sums = Vec::new();
    for method in Method::ALL {
        let sum = minkowski_sum(&p, &q, method)?;
        let (fv, vf, ee) = sum.counts();
        println!(
            "{:>5}: {fv} fv + {vf} vf + {ee} ee = {} facets",
            method.name(),
            fv + vf + ee
        );
        sums.push((method, sum));
    }

    // The three methods are independent algorithms; their labelled facet
    // sets must be identical, not merely the same size.
    let (_, reference) = &sums[0];
    for (method, sum) in &sums[1..] {
        if sum.facets() != reference.facets() {
            return Err(format!("{} disagrees with brute", method.name()).into());
        }
    }
    println!("brute, walk and hull give the identical facet set");

    // Coplanar facets merged into maximal faces, checked exactly.
    let mesh = reference.try_to_mesh()?;
    println!(
        "merged mesh: {} vertices, {} faces, volume {:.6}",
        mesh.vertices.len(),
        mesh.faces.len(),
        mesh.signed_volume()
    );
    Ok(())
}
