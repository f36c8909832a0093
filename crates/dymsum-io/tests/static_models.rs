//! Every pair of the paper's reference models (Fogel's collection) in random
//! orientations: the three static methods agree, the sums pass their sanity
//! checks, and the merged mesh matches the exact hull of pairwise sums.

use dymsum::hull::{convex_hull, PairwiseSums};
use dymsum::polytope::MeshPolicy;
use dymsum::sum::{minkowski_sum_posed, Method, SumError};
use dymsum::{DVec3, Polytope, Pose, Rotation};
use dymsum_io::models::model;

const FOGEL: [&str; 11] = [
    "cube",
    "dd",
    "ellipse",
    "ellipsoid_1.0_0.5_0.5",
    "gs1",
    "gs2",
    "gs3",
    "gs4",
    "hp",
    "t",
    "ti",
];

fn load(name: &str) -> Polytope {
    Polytope::from_mesh(&model(name).unwrap(), MeshPolicy::default())
        .unwrap()
        .0
}

/// A deterministic pseudo-random unit quaternion (no rand dependency).
fn rotation(seed: u64) -> Rotation {
    let mut x = seed.wrapping_mul(0x9E3779B97F4A7C15) | 1;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    Rotation::from_wxyz(next(), next(), next(), next()).unwrap()
}

#[test]
fn every_pair_of_reference_models_in_random_orientations() {
    let polys: Vec<(&str, Polytope)> = FOGEL.iter().map(|&n| (n, load(n))).collect();
    let mut seed = 1;
    for (i, (np, p)) in polys.iter().enumerate() {
        for (nq, q) in polys.iter().skip(i) {
            seed += 1;
            let pose = Pose::new(rotation(seed), DVec3::new(0.25, -0.5, 1.0));
            let walk = minkowski_sum_posed(p, pose, q, Pose::IDENTITY, Method::Walk).unwrap();
            let brute = minkowski_sum_posed(p, pose, q, Pose::IDENTITY, Method::Brute).unwrap();
            assert_eq!(walk.facets(), brute.facets(), "{np} + {nq}: walk != brute");
            match minkowski_sum_posed(p, pose, q, Pose::IDENTITY, Method::Hull) {
                Ok(h) => assert_eq!(walk.facets(), h.facets(), "{np} + {nq}: walk != hull"),
                Err(SumError::HullMismatch(_)) => {}
                Err(e) => panic!("{np} + {nq}: {e}"),
            }
            walk.sanity_check()
                .unwrap_or_else(|e| panic!("{np} + {nq}: {e}"));
            // Volume against the exact hull of the pairwise sums.
            let pp: Vec<DVec3> = p.vertices().iter().map(|&v| pose.apply(v)).collect();
            let qq = q.vertices().to_vec();
            let sums = PairwiseSums { p: &pp, q: &qq };
            let hull = convex_hull(&sums).unwrap();
            let hm = hull.to_mesh(&sums);
            let (vm, vh) = (
                walk.try_to_mesh().unwrap().signed_volume(),
                hm.signed_volume(),
            );
            assert!(
                (vm - vh).abs() <= 1e-9 * vh,
                "{np} + {nq}: volume {vm} vs {vh}"
            );
        }
    }
}

#[test]
fn every_reference_model_with_itself_unrotated_keeps_its_faces() {
    for name in FOGEL {
        let p = load(name);
        let s = minkowski_sum_posed(&p, Pose::IDENTITY, &p, Pose::IDENTITY, Method::Walk).unwrap();
        // P ⊕ P = 2P: every face pairs with its twin.
        assert_eq!(
            s.try_to_mesh().unwrap().faces.len(),
            p.face_count(),
            "{name}"
        );
        let h = minkowski_sum_posed(&p, Pose::IDENTITY, &p, Pose::IDENTITY, Method::Hull).unwrap();
        assert_eq!(s.facets(), h.facets(), "{name}");
    }
}
