//! Shared generators for the oracle tests.
#![allow(dead_code)]

use dymsum::{DVec3, Polytope, Rotation};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// The kinds of random polytopes the oracle tests draw from.
#[derive(Clone, Copy, Debug)]
pub enum Kind {
    /// Uniform in a ball.
    Ball,
    /// Integer grid points (many exactly coplanar faces and parallel edges).
    Grid,
    /// Points on a few planes (coplanar clusters).
    Coplanar,
    /// On a sphere.
    Sphere,
}

pub fn points(kind: Kind, n: usize, r: &mut ChaCha8Rng) -> Vec<DVec3> {
    (0..n)
        .map(|_| match kind {
            Kind::Ball => loop {
                let p = DVec3::new(
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                );
                if p.length() <= 1.0 {
                    break p;
                }
            },
            Kind::Grid => DVec3::new(
                r.random_range(-2..=2) as f64,
                r.random_range(-2..=2) as f64,
                r.random_range(-2..=2) as f64,
            ),
            Kind::Coplanar => {
                let axis = r.random_range(0..3);
                let mut p = DVec3::new(
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                );
                p[axis] = if r.random_bool(0.5) { 1.0 } else { -1.0 };
                p
            }
            Kind::Sphere => loop {
                let p = DVec3::new(
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                );
                let l = p.length();
                if l > 0.1 && l <= 1.0 {
                    break p / l;
                }
            },
        })
        .collect()
}

pub fn random_polytope(kind: Kind, n: usize, r: &mut ChaCha8Rng) -> Polytope {
    loop {
        let pts = points(kind, n, r);
        if let Ok(p) = Polytope::from_dvec3s(&pts) {
            return p;
        }
    }
}

pub fn random_rotation(r: &mut ChaCha8Rng) -> Rotation {
    loop {
        let q = [
            r.random_range(-1.0..1.0),
            r.random_range(-1.0..1.0),
            r.random_range(-1.0..1.0),
            r.random_range(-1.0..1.0),
        ];
        let l: f64 = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        if l > 0.1 && l <= 1.0 {
            return Rotation::from_wxyz(q[0], q[1], q[2], q[3]).unwrap();
        }
    }
}

pub fn cube_points(lo: f64, hi: f64) -> Vec<[f64; 3]> {
    (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { lo } else { hi },
                if i & 2 == 0 { lo } else { hi },
                if i & 4 == 0 { lo } else { hi },
            ]
        })
        .collect()
}

pub fn box_points(x: f64, y: f64, z: f64) -> Vec<[f64; 3]> {
    (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { -x } else { x },
                if i & 2 == 0 { -y } else { y },
                if i & 4 == 0 { -z } else { z },
            ]
        })
        .collect()
}
