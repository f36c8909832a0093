//! The clearance of random sliver soups scaled by exact powers of two
//! scales with them: every computation is scale-invariant but for
//! underflow and overflow, so `distance_at` at scale `2^k` above `2^k`
//! times its value at scale 1 is above the true distance. Found by the
//! independent review of `solid::obb`'s gap (2026-11-30): the oriented
//! boxes' face sums were squared unscaled, and the clearance came out
//! 1.157 times the distance at `2⁻⁵⁴⁰` and 8.8 times at `2⁶⁰⁰`.
use dymsum::query::{MeshBody, SceneChecker};
use dymsum::{DVec3, Pose, Rotation};

mod common;
use common::{sliver_corners as slivers, soup, Rng};

fn mesh(v: &[[f64; 3]], s: f64) -> MeshBody {
    MeshBody::new(&soup(v, s)).unwrap()
}

#[test]
fn clearance_never_exceeds_the_distance_at_extreme_scales() {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    let ks: [i32; 10] = [-545, -540, -538, -536, -534, -532, -528, 0, 515, 600];
    let mut worst = vec![(0.0f64, 0usize); ks.len()];
    let mut above = vec![0usize; ks.len()];
    let mut cases = 0;
    for case in 0..400 {
        let flat = case % 2 == 0;
        let a = slivers(&mut rng, 6, DVec3::ZERO, flat);
        let b = slivers(&mut rng, 16, DVec3::ZERO, flat);
        let r = if flat && case % 4 == 0 {
            Rotation::IDENTITY
        } else {
            Rotation::from_axis_angle(rng.direction(), 3.0 * rng.unit()).unwrap()
        };
        let dir = if flat { DVec3::Z } else { rng.direction() };
        let t = dir * (6.0 + 0.3 * rng.unit()) + DVec3::new(rng.unit(), rng.unit(), 0.0);
        let base = {
            let c = SceneChecker::new(&mesh(&a, 1.0), &[mesh(&b, 1.0)]).unwrap();
            c.distance_at(Pose::new(r, t)).unwrap()
        };
        if base <= 0.0 {
            continue;
        }
        cases += 1;
        for (i, &k) in ks.iter().enumerate() {
            let s = 2f64.powi(k);
            let c = SceneChecker::new(&mesh(&a, s), &[mesh(&b, s)]).unwrap();
            let d = c.distance_at(Pose::new(r, t * s)).unwrap();
            let ratio = d / (base * s);
            if ratio > worst[i].0 {
                worst[i] = (ratio, case);
            }
            if ratio > 1.0 + 1e-9 {
                above[i] += 1;
                if above[i] <= 2 {
                    eprintln!("case {case} k {k}: distance_at {d:e} against 2^k x {base:e} = {:e} (ratio {ratio})", base * s);
                }
            }
        }
    }
    for (i, &k) in ks.iter().enumerate() {
        eprintln!(
            "k = {k}: worst ratio {:?}, above {} of {cases}",
            worst[i], above[i]
        );
    }
    assert!(above.iter().all(|&n| n == 0), "{above:?}");
}
