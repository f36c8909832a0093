//! The paper's motion (§5): P turns about a random unit axis, held for a
//! random number of steps (1 to 50), then a new axis is drawn; every step
//! turns P by `2π / steps_per_rev`. It drives `dymsum bench`, `dymsum demo`
//! and `dymsum animate` (and the benchmarks, through `dymsum-bench`); the
//! `dymsum motion` subcommand, a certified straight motion, is
//! [`crate::commands::motion`].
//!
//! Deterministic for a seed on every platform (ChaCha8).
//!
//! ```
//! use dymsum_cli::random_motion::PaperMotion;
//! let mut a = PaperMotion::new(500.0, 7);
//! let mut b = PaperMotion::new(500.0, 7);
//! for _ in 0..100 {
//!     assert_eq!(a.next_step(), b.next_step());
//! }
//! let step = PaperMotion::new(500.0, 1).next_step();
//! assert!((step.angle() - std::f64::consts::TAU / 500.0).abs() < 1e-12);
//! ```

use dymsum::{DVec3, Rotation};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Longest hold of one axis, in steps.
pub const MAX_HOLD: u32 = 50;

/// The random motion of P: a sequence of step rotations.
#[derive(Clone, Debug)]
pub struct PaperMotion {
    rng: ChaCha8Rng,
    angle: f64,
    step: Rotation,
    left: u32,
}

impl PaperMotion {
    /// A motion of `steps_per_rev` steps per full turn (finite, > 0), seeded.
    pub fn new(steps_per_rev: f64, seed: u64) -> Self {
        PaperMotion {
            rng: ChaCha8Rng::seed_from_u64(seed),
            angle: std::f64::consts::TAU / steps_per_rev,
            step: Rotation::IDENTITY,
            left: 0,
        }
    }

    /// The rotation of the next step (about the current axis, drawing a new
    /// axis and hold time when the current one is used up).
    pub fn next_step(&mut self) -> Rotation {
        if self.left == 0 {
            let axis = random_unit_vector(&mut self.rng);
            self.step = Rotation::from_axis_angle(axis, self.angle).unwrap_or(Rotation::IDENTITY);
            self.left = self.rng.random_range(1..=MAX_HOLD);
        }
        self.left -= 1;
        self.step
    }
}

/// A uniformly distributed unit vector (rejection sampling in the cube).
pub fn random_unit_vector(rng: &mut impl Rng) -> DVec3 {
    loop {
        let v = DVec3::new(
            rng.random::<f64>() * 2.0 - 1.0,
            rng.random::<f64>() * 2.0 - 1.0,
            rng.random::<f64>() * 2.0 - 1.0,
        );
        let l2 = v.length_squared();
        if l2 > 1e-6 && l2 <= 1.0 {
            return v / l2.sqrt();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes_are_held_for_1_to_50_steps() {
        let mut m = PaperMotion::new(100.0, 3);
        let mut runs = Vec::new();
        let mut last = m.next_step();
        let mut run = 1;
        for _ in 0..5000 {
            let s = m.next_step();
            if s == last {
                run += 1;
            } else {
                runs.push(run);
                run = 1;
                last = s;
            }
        }
        assert!(runs.len() > 50);
        assert!(runs.iter().all(|&r| (1..=MAX_HOLD as usize).contains(&r)));
        assert!(runs.iter().any(|&r| r > 25));
    }

    #[test]
    fn unit_vectors_are_unit() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..1000 {
            assert!((random_unit_vector(&mut rng).length() - 1.0).abs() < 1e-12);
        }
    }
}
