//! Proximity queries and configuration-space obstacles built on the sums
//! (paper §1): penetration depth, distance and collision of two convex
//! bodies, a per-frame contact tracker, batches, C-obstacle slices, and
//! unions of convex pieces.
//!
//! Certified C-obstacle slabs ([`Slab`]): one convex region, as half-spaces
//! rounded outward or as a checked mesh, that holds every slice over a
//! range of orientations (between two orientations of a turn, or in a cell
//! of SO(3)); what is certified and why is in [`slabs`].
//!
//! # The answer is defined by the Minkowski difference
//! For convex bodies `A` and `B` at their poses, `D = A ⊕ (−B)` contains the
//! origin exactly when they overlap, and translating `A` by `t` translates
//! `D` by `t`. Hence
//!
//! * **intersects**: the origin lies in `D` (touching counts);
//! * **penetration depth**: the distance from the origin to the boundary of
//!   `D`, which is `min` over the facet normals `n` of `D` of the support
//!   value `h_D(n) = h_A(n) + h_B(−n)`;
//! * **distance**: the distance from the origin to `D` when it lies outside.
//!
//! The facets of `D` are the facets of the exact overlay of the two
//! Gaussian maps ([`crate::sum`]), with `−B` the point reflection of `B`
//! ([`Reflected`]); their labels name the features of `A` and `B` that
//! generate them, and those give the witness points. Every facet is a
//! *candidate* ([`candidates`](self)): a direction and its support value.
//! The answer is the winner among all of them, by rules that depend only
//! on the set of candidates: the least value, ties within `16 ε B` settled
//! by the direction's lexicographic key, then by the features' order. The
//! candidate set is complete, so no direction is missed, which is where
//! GJK/EPA implementations lose accuracy (EPA stops on a tolerance and can
//! report an edge–edge depth too large, or a wrong direction).
//!
//! # How it is computed: support functions and certificates
//! Building all of `D` costs O(mn); a query does not. The files, by what
//! they answer:
//!
//! * [`pair`](self): [`ConvexPair`], the two bodies prepared once
//!   (reflection, cached per body), and the one-off query functions;
//!   [`answer`](self) and [`error`](self): what a query returns;
//! * `frame`: the bodies posed on demand in one power-of-two frame, with
//!   rigorous bounds on the posing's rounding;
//! * `proximity`: one query, step by step: `support` (support functions by
//!   hill climbing from a warm start, the complete near-extreme sets with
//!   rigorous bounds), `gjk` (the yes/no answer **certified exactly**: a
//!   separating direction compared exactly, or the origin in its simplex
//!   by exact determinants, else the exhaustive exact method, counted in
//!   [`QueryStats`]), `epa` (EPA's polytope `K ⊆ D'` around the origin,
//!   checked exactly), `evaluate` (the order of the steps, and the answer
//!   from a set of facets: the same code for the certified set, the whole
//!   sum ([`ConvexPair::query_exhaustive`], the tests' reference) and a
//!   tracker's dynamic sum), `depth` (**how penetration depth is
//!   computed**), `distance` and `closest` (**how distance and witness
//!   points are computed**), and `certificate` (the proofs that every facet
//!   outside a small set near the answer cannot change it: caps around
//!   `K`'s faces for a penetration, a slab and its lateral bound for a
//!   separation, the one-facet shortcut; `certificate::candidates`, the
//!   facets' directions and exact sides);
//! * `tracker`: [`ContactTracker`], warm-started frame to frame, or
//!   evaluating a DYMSUM-kept sum ([`TrackerStrategy`]);
//! * `cobstacle`: configuration-space obstacles: `slices` ([`CObstacle`],
//!   one convex slice per orientation by DYMSUM), `halfspaces` (slices as
//!   half-spaces), [`slabs`] (certified slabs over ranges of orientations);
//! * `union`: [`ConvexUnion`], bodies made of convex pieces;
//! * `motion`: **how a motion is certified** ([`MotionChecker`]);
//!   `interval_search`: the interval search both motion checkers run (left
//!   to right, halving, probes, budget, undecided) and the margin both add
//!   (its soundness argument); [`Checker`] (`checker`): what the convex
//!   checker, the triangle checker ([`SceneChecker`]) and [`Validator`]
//!   answer alike, the batches written once.
//!
//! Every soundness argument is written where it is used: the near-extreme
//! sets in `support`, the yes/no certificates in `gjk`, the caps, the slab
//! and the one-facet shortcut in `certificate`, the candidates' directions
//! in `certificate::candidates`, the motion search in `interval_search`, the
//! motion bounds in `motion` and `scene::sweep`. Where a certificate cannot be made (the origin within
//! rounding of `D`'s boundary, a degenerate EPA polytope), the whole sum
//! is evaluated instead and [`QueryStats`] counts it; on the benchmark
//! workloads this never happens. With the `check-reference` feature every
//! certified answer is also compared with the exhaustive one.
//!
//! # Conventions
//! * [`Contact::normal`] is the unit contact normal pointing **from A towards
//!   B** (outward from A at the contact, like parry's `normal1`). Translating
//!   `A` by `−depth · normal` (or `B` by `+depth · normal`) separates the
//!   bodies to touching; no shorter translation does.
//!   `point_on_a − point_on_b = depth · normal`: `point_on_a` is A's deepest
//!   point inside B and `point_on_b` B's deepest point inside A.
//! * [`Separation::direction`] is the unit vector from `point_on_a` to
//!   `point_on_b` (from A towards B); `distance = |point_on_b − point_on_a|`.
//! * Touching bodies (origin on the boundary of `D`) are *intersecting*, with
//!   depth `0`.
//!
//! # Exactness and tolerance
//! * **Yes or no is exact.** Whether the bodies overlap or touch is decided
//!   exactly on the posed bodies as computed (`R p + t` rounded once per
//!   coordinate), with no tolerance: touching is touching.
//! * **Which facet wins is exact** up to the tie rule: the facet set of `D`
//!   is the exact overlay, and the certificates prove the winner among all
//!   facets.
//! * **Depths, distances and points are float constructions** from the
//!   winning facet's features: a support value carries an error of a few
//!   ulps of the coordinates' magnitude, about `1e-15 · B` where `B` bounds
//!   the posed coordinates.
//!
//! # Determinism and symmetry
//! The answer depends only on the bodies and poses: not on the warm start,
//! the order of the candidates, the strategy or the thread (a tracker frame
//! equals a cold query bit for bit). Swapping A and B reports the same
//! depth and the opposite normal — except when the tied directions include
//! both some `n` and `−n` (identical bodies at the same pose: no rule can
//! then be antisymmetric, and the direction with positive first non-zero
//! component is returned), and to rounding where an edge–edge direction had
//! to be computed from the overlay (nearly parallel edges) or the overlay's
//! symbolic perturbation picks different equivalent facets for the two
//! orders.
//!
//! # Scale
//! Answers are computed in the pair's power-of-two frame (posed coordinates
//! times `2^k`, their bound in `[1, 2)`) and scaled back, so scaling both
//! bodies and their translations by `2^j` scales depth, distance and
//! witness points by exactly `2^j` (directions unchanged), with no overflow
//! or underflow of intermediate squared lengths at any scale. A posed
//! coordinate or an answer beyond `f64` is [`QueryError::OutOfRange`] (or
//! [`crate::sum::SumError::OutOfRange`] from the sum); never NaN.
//!
//! ```
//! use dymsum::{Polytope, Pose, Rotation, DVec3};
//! use dymsum::query::{penetration_depth, distance};
//! let cube: Vec<[f64; 3]> = (0..8)
//!     .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
//!     .collect();
//! let c = Polytope::from_points(&cube).unwrap();
//! let at = |x: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, 0.0));
//! let hit = penetration_depth(&c, at(0.0), &c, at(0.75)).unwrap().unwrap();
//! assert_eq!(hit.depth, 0.25);
//! assert_eq!(hit.normal, DVec3::X); // from A towards B
//! let gap = distance(&c, at(0.0), &c, at(1.5)).unwrap();
//! assert_eq!(gap.distance, 0.5);
//! ```

mod answer;
mod checker;
mod cobstacle;
mod error;
mod frame;
pub(crate) mod interval_search;
mod motion;
mod pair;
mod prep;
mod proximity;
pub(crate) mod rounding;
pub(crate) mod scene;
mod tracker;
mod union;

pub use cobstacle::slabs;

pub use crate::body::{ContainmentStats, ConvexUnion};
pub use answer::{Contact, FeaturePair, Proximity, Separation};
pub use checker::{Checker, MotionCheck};
pub use cobstacle::halfspaces::HalfSpaces;
pub use cobstacle::slabs::{
    certified_slab_in_cell, certified_slabs_about_axis, certified_slabs_about_axis_par,
    full_turn_angles, rotations_about_axis, slab_meshes_par, Slab, SlabCover, SlabError,
    ROTATION_SLACK,
};
pub use cobstacle::slices::{
    cobstacle_slices, cobstacle_slices_par, orientations_about_axis, CObstacle,
};
pub use error::{MotionError, QueryError};
pub use interval_search::{DEFAULT_BUDGET, MIN_TOLERANCE, MIN_WIDTH};
pub use motion::{check_motion, check_motions, Motion, MotionChecker};
pub use pair::{ConvexPair, QueryStats};
pub use prep::Reflected;
pub use proximity::{distance, intersects, penetration_depth, query};
pub use scene::{surfaces_touch, Body, MeshBody, MeshReport, SceneChecker, Validator};
pub use tracker::{ContactTracker, TrackerStrategy};
pub use union::UnionProximity;

/// Helpers shared by the query modules' unit tests.
#[cfg(test)]
pub(crate) mod test_support {
    use crate::polytope::Polytope;
    use glam::DVec3;

    /// A small deterministic generator (no dev-dependency in unit tests).
    pub(crate) struct Lcg(pub(crate) u64);

    impl Lcg {
        /// Uniform in `[-1, 1)`.
        pub(crate) fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }

        /// A random unit vector.
        pub(crate) fn unit(&mut self) -> DVec3 {
            loop {
                let v = DVec3::new(self.next(), self.next(), self.next());
                if v.length() > 0.1 && v.length() <= 1.0 {
                    return v.normalize();
                }
            }
        }
    }

    /// The box `[-x, x] × [-y, y] × [-z, z]`.
    pub(crate) fn boxed(x: f64, y: f64, z: f64) -> Polytope {
        let pts: Vec<[f64; 3]> = (0..8)
            .map(|i| {
                [
                    if i & 1 == 0 { -x } else { x },
                    if i & 2 == 0 { -y } else { y },
                    if i & 4 == 0 { -z } else { z },
                ]
            })
            .collect();
        Polytope::from_points(&pts).unwrap()
    }

    /// Two boxes and random hulls of `sizes` points: the shapes the
    /// yes/no oracles are compared on.
    pub(crate) fn boxes_and_hulls(r: &mut Lcg, sizes: &[usize]) -> Vec<Polytope> {
        let mut shapes = vec![boxed(0.5, 0.5, 0.5), boxed(1.0, 0.25, 0.5)];
        for &n in sizes {
            let pts: Vec<DVec3> = (0..n).map(|_| r.unit()).collect();
            shapes.push(Polytope::from_dvec3s(&pts).unwrap());
        }
        shapes
    }

    /// The `k`-th pose pair of those comparisons: A turned (identity, an
    /// exact quarter turn about z, or random), B moved: every fourth one
    /// along x to touch the unit box exactly or an ulp either side, the
    /// others at random within 2.5.
    pub(crate) fn oracle_poses(
        r: &mut Lcg,
        k: usize,
    ) -> (crate::kernel::rotation::Pose, crate::kernel::rotation::Pose) {
        use crate::kernel::rotation::{Pose, Rotation};
        let rot = match k % 3 {
            0 => Rotation::IDENTITY,
            1 => Rotation::from_axis_angle(DVec3::Z, std::f64::consts::FRAC_PI_2).unwrap(),
            _ => Rotation::from_axis_angle(r.unit(), 3.0 * r.next()).unwrap(),
        };
        let t = if k % 4 == 0 {
            let x = 1.0 + [0.0, f64::EPSILON, -f64::EPSILON][k % 3];
            DVec3::new(x, 0.0, 0.0)
        } else {
            r.unit() * (2.5 * r.next().abs())
        };
        (
            Pose::new(rot, DVec3::ZERO),
            Pose::new(Rotation::IDENTITY, t),
        )
    }
}
