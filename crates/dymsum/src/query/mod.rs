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
//! Building all of `D` costs O(mn); a query does not. The layout of this
//! module follows the steps of [`ConvexPair::query`]:
//!
//! * `frame`: the bodies posed on demand in one power-of-two frame, with
//!   rigorous bounds on the posing's rounding;
//! * `support`: support functions by hill climbing from a warm start, and
//!   the complete near-extreme sets with rigorous bounds;
//! * `gjk`: GJK on the posed difference; its yes/no answer **certified
//!   exactly** (a separating direction compared exactly, or the origin in
//!   its simplex by exact determinants), else decided by the exhaustive
//!   exact method (counted in [`QueryStats`]);
//! * `epa`: EPA's polytope `K ⊆ D'` around the origin, checked exactly;
//! * `certify`: the certificates that every facet outside a small set near
//!   the answer cannot change it (caps around `K`'s faces for a
//!   penetration, a slab and its lateral bound for a separation), and the
//!   search that finds that set with the overlay's own exact predicates;
//! * `candidates`, `evaluate`, `separation`, `closest`: the answer from a
//!   set of facets, the same code for the certified set, for the whole
//!   sum ([`ConvexPair::query_exhaustive`], the reference in the tests)
//!   and for a tracker's dynamic sum;
//! * `tracker`: [`ContactTracker`], warm-started frame to frame, or
//!   evaluating a DYMSUM-kept sum ([`TrackerStrategy`]).
//!
//! Every soundness argument is written where it is used: the near-extreme
//! sets in `support`, the yes/no certificates in `gjk`, the caps, the slab
//! and the one-facet shortcut in `certify`, the candidates' directions in
//! `candidates`. Where a certificate cannot be made (the origin within
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
//! [`SumError::OutOfRange`] from the sum); never NaN.
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

mod candidates;
mod certify;
mod closest;
mod cobst;
mod epa;
mod evaluate;
mod frame;
mod gjk;
mod halfspaces;
mod motion;
mod separation;
pub mod slabs;
mod support;
mod tracker;
mod union;

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
}

pub use cobst::{cobstacle_slices, cobstacle_slices_par, orientations_about_axis, CObstacle};
pub use halfspaces::HalfSpaces;
pub use motion::{
    check_motion, check_motions, Motion, MotionCheck, MotionChecker, MotionError, DEFAULT_BUDGET,
    MIN_TOLERANCE, MIN_WIDTH,
};
pub use slabs::{
    certified_slab_in_cell, certified_slabs_about_axis, certified_slabs_about_axis_par,
    full_turn_angles, rotations_about_axis, slab_meshes_par, Slab, SlabCover, SlabError,
    ROTATION_SLACK,
};
pub use tracker::{ContactTracker, TrackerStrategy};
pub use union::{ConvexUnion, UnionProximity};

use crate::kernel::rotation::Pose;
use crate::polytope::{Polytope, PolytopeError};
use crate::sum::SumError;
use glam::DVec3;
use std::collections::HashMap;

/// Why a query failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum QueryError {
    /// The sum could not be computed (an internal error of the sum).
    #[error(transparent)]
    Sum(#[from] SumError),
    /// The reflected body `−B` could not be built (cannot happen for a valid
    /// polytope; reported rather than panicking).
    #[error("reflecting a body failed: {0}")]
    Reflect(#[from] PolytopeError),
    /// An internal invariant failed (a bug: please report the input).
    #[error("internal inconsistency: {0}")]
    Inconsistent(String),
    /// The mesh of a slice could not be produced (see [`crate::sum::MeshError`]).
    #[error(transparent)]
    Mesh(#[from] crate::sum::MeshError),
    /// The exact penetration depth of a non-convex union is not supported:
    /// the minimum over piece pairs is *not* the union's depth (separating
    /// one pair can push it into another). Use [`ConvexUnion::collides`],
    /// [`ConvexUnion::distance`] or the per-pair contacts instead.
    #[error(
        "penetration depth of a non-convex union of convex pieces is not supported \
         (the minimum over piece pairs is not the union's depth)"
    )]
    UnionDepthUnsupported,
    /// The bodies at their poses are beyond what `f64` holds: a posed
    /// coordinate (`R p + t`) or the answer overflows (magnitudes above
    /// `1.8e308`). Every finite pose whose posed coordinates and answer are
    /// finite is supported, at any scale.
    #[error("outside the supported range: {0}")]
    OutOfRange(String),
    /// Bad input to a certified slab ([`Slab`]): the variant names it.
    #[error(transparent)]
    Slab(#[from] SlabError),
}

/// The features of `A` and `B` generating a facet of `A ⊕ (−B)` (indices
/// into the original bodies). The order (face–vertex, vertex–face,
/// edge–edge, then by indices) settles the last ties between candidates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum FeaturePair {
    /// Face `a_face` of A against vertex `b_vertex` of B.
    FaceVertex {
        /// Face of A.
        a_face: u32,
        /// Vertex of B.
        b_vertex: u32,
    },
    /// Vertex `a_vertex` of A against face `b_face` of B.
    VertexFace {
        /// Vertex of A.
        a_vertex: u32,
        /// Face of B.
        b_face: u32,
    },
    /// Edge `a_edge` of A against edge `b_edge` of B.
    EdgeEdge {
        /// Edge of A.
        a_edge: u32,
        /// Edge of B.
        b_edge: u32,
    },
}

/// Two overlapping (or touching) bodies: the penetration depth and where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// The length of the shortest translation separating the bodies
    /// (`0` when they touch).
    pub depth: f64,
    /// Unit contact normal, from A towards B: translate A by
    /// `−depth · normal` (or B by `+depth · normal`) to separate them.
    pub normal: DVec3,
    /// A's deepest point inside B (on A's boundary).
    pub point_on_a: DVec3,
    /// B's deepest point inside A (on B's boundary);
    /// `point_on_a − point_on_b = depth · normal`.
    pub point_on_b: DVec3,
    /// The features whose facet of `A ⊕ (−B)` is nearest the origin.
    pub features: FeaturePair,
}

/// Two bodies apart: their distance and closest points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Separation {
    /// The distance between the bodies (`> 0`).
    pub distance: f64,
    /// The closest point of A.
    pub point_on_a: DVec3,
    /// The closest point of B.
    pub point_on_b: DVec3,
    /// Unit vector from A towards B (`point_on_b − point_on_a`, normalised).
    pub direction: DVec3,
    /// The features of the facet of `A ⊕ (−B)` nearest the origin.
    pub features: FeaturePair,
}

/// The answer of a query: overlapping (with the depth) or apart (with the
/// distance).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Proximity {
    /// Overlapping or touching.
    Penetrating(Contact),
    /// Apart.
    Separated(Separation),
}

impl Proximity {
    /// `true` when the bodies overlap or touch.
    pub fn intersects(&self) -> bool {
        matches!(self, Proximity::Penetrating(_))
    }
    /// The penetration depth (`0` when apart).
    pub fn depth(&self) -> f64 {
        match self {
            Proximity::Penetrating(c) => c.depth,
            Proximity::Separated(_) => 0.0,
        }
    }
    /// The distance (`0` when touching or overlapping).
    pub fn distance(&self) -> f64 {
        match self {
            Proximity::Penetrating(_) => 0.0,
            Proximity::Separated(s) => s.distance,
        }
    }
    /// The contact, when overlapping.
    pub fn contact(&self) -> Option<&Contact> {
        match self {
            Proximity::Penetrating(c) => Some(c),
            Proximity::Separated(_) => None,
        }
    }
    /// The separation, when apart.
    pub fn separation(&self) -> Option<&Separation> {
        match self {
            Proximity::Penetrating(_) => None,
            Proximity::Separated(s) => Some(s),
        }
    }
    /// A's shortest separating translation direction (unit) when
    /// overlapping (`−normal`), or the unit direction from A towards B when
    /// apart.
    pub fn a_direction(&self) -> DVec3 {
        match self {
            Proximity::Penetrating(c) => -c.normal,
            Proximity::Separated(s) => s.direction,
        }
    }
}

/// The point reflection `−B` of a body, with the maps from its features back
/// to `B`'s (a reflection renumbers vertices, faces and edges).
#[derive(Clone, Debug)]
pub struct Reflected {
    /// `−B` as a polytope.
    pub polytope: Polytope,
    /// Vertex of `−B` → vertex of `B`.
    pub vertex_map: Vec<u32>,
    /// Face of `−B` → face of `B`.
    pub face_map: Vec<u32>,
    /// Edge of `−B` → edge of `B`.
    pub edge_map: Vec<u32>,
}

fn bits(v: DVec3) -> [u64; 3] {
    [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]
}

impl Reflected {
    /// Reflects `b` through the origin (exact: negation is exact).
    ///
    /// # Errors
    /// Only internal errors, for a polytope built by this crate:
    /// [`QueryError::Reflect`] if rebuilding the reflected body from the
    /// negated vertices fails, [`QueryError::Inconsistent`] if its faces or
    /// edges do not match the original's (a bug in dymsum either way).
    pub fn new(b: &Polytope) -> Result<Reflected, QueryError> {
        let neg: Vec<DVec3> = b.vertices().iter().map(|&v| -v).collect();
        let polytope = Polytope::from_dvec3s(&neg)?;
        let index: HashMap<[u64; 3], u32> = neg
            .iter()
            .enumerate()
            .map(|(i, &v)| (bits(v), i as u32))
            .collect();
        let bad = || QueryError::Inconsistent("the reflected body's vertices differ".into());
        let vertex_map = polytope
            .vertices()
            .iter()
            .map(|&v| index.get(&bits(v)).copied().ok_or_else(bad))
            .collect::<Result<Vec<u32>, _>>()?;
        if polytope.vertex_count() != b.vertex_count()
            || polytope.face_count() != b.face_count()
            || polytope.edge_count() != b.edge_count()
        {
            return Err(bad());
        }
        let key = |vs: &mut Vec<u32>| {
            vs.sort_unstable();
            vs.clone()
        };
        let faces: HashMap<Vec<u32>, u32> = b
            .faces()
            .enumerate()
            .map(|(f, vs)| (key(&mut vs.to_vec()), f as u32))
            .collect();
        let face_map = polytope
            .faces()
            .map(|vs| {
                let mut m: Vec<u32> = vs.iter().map(|&v| vertex_map[v as usize]).collect();
                faces.get(&key(&mut m)).copied().ok_or_else(bad)
            })
            .collect::<Result<Vec<u32>, _>>()?;
        let edge_key = |[x, y]: [u32; 2]| (x.min(y), x.max(y));
        let edges: HashMap<(u32, u32), u32> = b
            .edges()
            .iter()
            .enumerate()
            .map(|(e, ed)| (edge_key(ed.vertices), e as u32))
            .collect();
        let edge_map = polytope
            .edges()
            .iter()
            .map(|ed| {
                let [x, y] = ed.vertices;
                let k = edge_key([vertex_map[x as usize], vertex_map[y as usize]]);
                edges.get(&k).copied().ok_or_else(bad)
            })
            .collect::<Result<Vec<u32>, _>>()?;
        Ok(Reflected {
            polytope,
            vertex_map,
            face_map,
            edge_map,
        })
    }

    /// The pose of `−B` for `B` at `pose`: `−(R b + t) = R(−b) − t`.
    pub fn pose(pose: Pose) -> Pose {
        Pose::new(pose.rotation, -pose.translation)
    }
}

/// Two convex bodies prepared for repeated queries: `B`'s reflection is
/// built once. Use it (or a [`ContactTracker`]) instead of the free functions
/// when querying the same pair at many poses.
///
/// Two unit cubes whose centres are `0.75` apart along `x` overlap by
/// `0.25`: that is the penetration depth, along `+x` (from A towards B).
/// At `1.5` apart they are `0.5` apart.
///
/// ```
/// use dymsum::{ConvexPair, DVec3, Polytope, Pose, Rotation};
/// let corners: Vec<[f64; 3]> = (0..8)
///     .map(|i| [(i & 1) as f64 - 0.5, ((i >> 1) & 1) as f64 - 0.5, ((i >> 2) & 1) as f64 - 0.5])
///     .collect();
/// let cube = Polytope::from_points(&corners)?;
/// let pair = ConvexPair::new(&cube, &cube)?;
/// let at = |x: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, 0.0));
/// let contact = pair.penetration_depth(Pose::IDENTITY, at(0.75))?.ok_or("apart")?;
/// assert_eq!(contact.depth, 0.25);
/// assert_eq!(contact.normal, DVec3::X);
/// assert_eq!(contact.point_on_a - contact.point_on_b, contact.depth * contact.normal);
/// assert!(!pair.intersects(Pose::IDENTITY, at(1.5))?);
/// assert_eq!(pair.distance(Pose::IDENTITY, at(1.5))?.distance, 0.5);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct ConvexPair {
    a: Polytope,
    b: Polytope,
    prep_a: std::sync::Arc<BodyPrep>,
    prep_b: std::sync::Arc<BodyPrep>,
    stats: std::sync::Arc<Counters>,
    /// Query buffers kept between the static queries of this pair and its
    /// clones (one per query running at a time), so that a query
    /// allocates nothing once they have grown.
    pool: std::sync::Arc<std::sync::Mutex<Vec<evaluate::Scratch>>>,
}

/// What the queries need of one body beyond the body itself, computed once
/// per body (on its first query) and kept by the body's [`Polytope`]
/// handle, so preparing a pair costs nothing after the first time.
#[derive(Debug)]
pub(crate) struct BodyPrep {
    /// Balls around the faces and edges (the separation's branch and
    /// bound).
    balls: separation::FeatureBalls,
    /// Reach and radius (the query frame's bounds).
    bounds: frame::BodyBounds,
    /// Error bounds of the arc normals under any rotation, exactly as the
    /// overlay's operands compute them (the body as A).
    arc_err: Vec<f64>,
    /// The reflection `−body` (the body as B).
    neg: Reflected,
    /// Vertex, face and edge → the same of the reflection (the inverses of
    /// [`Reflected`]'s maps).
    neg_vertex: Vec<u32>,
    neg_face: Vec<u32>,
    neg_edge: Vec<u32>,
    /// Caps holding each vertex's Gaussian cell and each edge's Gaussian
    /// arc (body frame): the certificates' quick rejections.
    caps: certify::GaussCaps,
}

impl BodyPrep {
    /// The data of `p`, computed on its first query and kept with the
    /// polytope (shared by every handle of it).
    ///
    /// # Errors
    /// Those of [`Reflected::new`] (internal only).
    pub(crate) fn of_cached(p: &Polytope) -> Result<std::sync::Arc<BodyPrep>, QueryError> {
        p.derived(|| BodyPrep::of(p).map(std::sync::Arc::new))
    }

    /// Computes the data of `p`.
    ///
    /// # Errors
    /// Those of [`Reflected::new`] (internal only).
    pub(crate) fn of(p: &Polytope) -> Result<BodyPrep, QueryError> {
        let (mut arcs, mut arc_err) = (Vec::new(), Vec::new());
        crate::sum::rotate_arcs(p, None, &mut arcs, &mut arc_err);
        let neg = Reflected::new(p)?;
        let inverse = |map: &[u32]| {
            let mut inv = vec![0; map.len()];
            for (i, &j) in map.iter().enumerate() {
                inv[j as usize] = i as u32;
            }
            inv
        };
        Ok(BodyPrep {
            balls: separation::FeatureBalls::of(p),
            bounds: frame::BodyBounds::of(p),
            arc_err,
            neg_vertex: inverse(&neg.vertex_map),
            neg_face: inverse(&neg.face_map),
            neg_edge: inverse(&neg.edge_map),
            neg,
            caps: certify::GaussCaps::of(p),
        })
    }
}

/// How a pair's queries were answered: how many, and how many needed an
/// exhaustive exact method because a certificate could not decide (see
/// [`ConvexPair::stats`]). Counted over every clone of the pair and every
/// tracker made from it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QueryStats {
    /// Queries answered (every method, trackers' frames included).
    pub queries: u64,
    /// Yes/no answers GJK's certificates could not decide, answered by the
    /// exact hull of all vertex differences instead (the origin within
    /// rounding of the boundary of `A ⊕ (−B)`).
    pub exhaustive_decisions: u64,
    /// Depths or distances the local certificates could not settle,
    /// answered from the whole sum instead.
    pub exhaustive_answers: u64,
}

/// The counters behind [`QueryStats`].
#[derive(Debug, Default)]
struct Counters {
    queries: std::sync::atomic::AtomicU64,
    exhaustive_decisions: std::sync::atomic::AtomicU64,
    exhaustive_answers: std::sync::atomic::AtomicU64,
}

impl Counters {
    fn bump(c: &std::sync::atomic::AtomicU64) {
        c.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }
    fn count_query(&self) {
        Self::bump(&self.queries);
    }
    fn count_exhaustive_decision(&self) {
        Self::bump(&self.exhaustive_decisions);
    }
    fn count_exhaustive_answer(&self) {
        Self::bump(&self.exhaustive_answers);
    }
    fn snapshot(&self) -> QueryStats {
        let get = |c: &std::sync::atomic::AtomicU64| c.load(std::sync::atomic::Ordering::Relaxed);
        QueryStats {
            queries: get(&self.queries),
            exhaustive_decisions: get(&self.exhaustive_decisions),
            exhaustive_answers: get(&self.exhaustive_answers),
        }
    }
}

impl ConvexPair {
    /// Prepares `a` and `b`: the data each body's queries need (its
    /// reflection, one convex hull; bounds and balls) is computed on the
    /// body's first query and kept by its [`Polytope`] handle, so pairing
    /// bodies again costs nothing. The pair keeps its own handles on the
    /// bodies (cheap clones); a clone of the pair shares everything.
    ///
    /// # Errors
    /// Only internal errors of the reflection ([`Reflected::new`]), for a polytope built by this crate:
    /// [`QueryError::Reflect`] if rebuilding the reflected body from the
    /// negated vertices fails, [`QueryError::Inconsistent`] if its faces or
    /// edges do not match the original's (a bug in dymsum either way).
    pub fn new(a: &Polytope, b: &Polytope) -> Result<Self, QueryError> {
        Ok(ConvexPair {
            a: a.clone(),
            b: b.clone(),
            prep_a: BodyPrep::of_cached(a)?,
            prep_b: BodyPrep::of_cached(b)?,
            stats: std::sync::Arc::new(Counters::default()),
            pool: Default::default(),
        })
    }
    /// Body A.
    pub fn a(&self) -> &Polytope {
        &self.a
    }
    /// Body B.
    pub fn b(&self) -> &Polytope {
        &self.b
    }
    /// B's reflection.
    pub fn reflected_b(&self) -> &Reflected {
        &self.prep_b.neg
    }

    /// B's reflection (crate-internal shorthand).
    #[inline]
    pub(crate) fn neg_b(&self) -> &Reflected {
        &self.prep_b.neg
    }

    /// Depth or distance at the given poses (a static `walk` sum).
    ///
    /// # Errors
    /// * [`QueryError::Sum`] wrapping [`SumError::OutOfRange`] when a posed
    ///   vertex of A or of `−B` overflows `f64` (|coordinate| > 1.8e308);
    /// * [`QueryError::OutOfRange`] when the answer (depth, distance or a
    ///   witness point) overflows `f64`;
    /// * [`QueryError::Sum`] wrapping [`SumError::Inconsistent`] only for an
    ///   internal error of the sum (a bug: please report the poses).
    pub fn query(&self, pose_a: Pose, pose_b: Pose) -> Result<Proximity, QueryError> {
        self.stats.count_query();
        self.with_scratch(|s| {
            evaluate::evaluate(self, pose_a, pose_b, evaluate::Facets::Certified, s)
        })
    }

    /// Runs `f` with buffers from the pool, reset to a cold start (no warm
    /// start from an earlier query: a static query's cost does not depend
    /// on the queries before it).
    fn with_scratch<T>(&self, f: impl FnOnce(&mut evaluate::Scratch) -> T) -> T {
        let taken = self.pool.lock().ok().and_then(|mut p| p.pop());
        let mut scratch = taken.unwrap_or_default();
        scratch.cold();
        let out = f(&mut scratch);
        if let Ok(mut p) = self.pool.lock() {
            p.push(scratch);
        }
        out
    }

    /// [`ConvexPair::query`] by evaluating every facet of `A ⊕ (−B)` (a
    /// static `walk` sum): the exhaustive reference the certified query is
    /// tested against. Always the same answer, at O(mn) cost.
    ///
    /// # Errors
    /// The same as [`ConvexPair::query`].
    pub fn query_exhaustive(&self, pose_a: Pose, pose_b: Pose) -> Result<Proximity, QueryError> {
        self.with_scratch(|s| {
            evaluate::evaluate(self, pose_a, pose_b, evaluate::Facets::Exhaustive, s)
        })
    }

    /// [`ConvexPair::query`] at many poses `(pose_a, pose_b)`, in order:
    /// the batch a planner or a physics step needs. The poses are split
    /// into chunks answered in parallel (rayon), each chunk warm-starting
    /// from the pose before, so the answers are the static query's, in any
    /// order and on any number of threads.
    ///
    /// ```
    /// use dymsum::{ConvexPair, DVec3, Polytope, Pose, Rotation};
    /// let corners: Vec<[f64; 3]> = (0..8)
    ///     .map(|i| [(i & 1) as f64 - 0.5, ((i >> 1) & 1) as f64 - 0.5, ((i >> 2) & 1) as f64 - 0.5])
    ///     .collect();
    /// let cube = Polytope::from_points(&corners)?;
    /// let pair = ConvexPair::new(&cube, &cube)?;
    /// let poses: Vec<(Pose, Pose)> = (0..100)
    ///     .map(|k| (Pose::IDENTITY, Pose::new(Rotation::IDENTITY, DVec3::new(0.02 * k as f64, 0.0, 0.0))))
    ///     .collect();
    /// let answers = pair.query_many(&poses)?;
    /// assert_eq!(answers[25].depth(), 0.5); // centres 0.5 apart
    /// assert_eq!(answers[75].distance(), 0.5); // centres 1.5 apart
    /// assert_eq!(answers[75], pair.query(poses[75].0, poses[75].1)?);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// The first error of [`ConvexPair::query`] among the poses.
    pub fn query_many(&self, poses: &[(Pose, Pose)]) -> Result<Vec<Proximity>, QueryError> {
        self.many(poses, |pair, (pa, pb), s| {
            evaluate::evaluate(pair, pa, pb, evaluate::Facets::Certified, s)
        })
    }

    /// [`ConvexPair::intersects`] at many poses, as
    /// [`ConvexPair::query_many`].
    ///
    /// # Errors
    /// The first error of [`ConvexPair::intersects`] among the poses.
    pub fn intersects_many(&self, poses: &[(Pose, Pose)]) -> Result<Vec<bool>, QueryError> {
        self.many(poses, |pair, (pa, pb), s| {
            s.posed.reset(pair, pa, pb)?;
            Ok(evaluate::decide(pair, s, true))
        })
    }

    /// Answers `one` at every pose, in parallel chunks of warm-started
    /// queries.
    fn many<T: Send>(
        &self,
        poses: &[(Pose, Pose)],
        one: impl Fn(&ConvexPair, (Pose, Pose), &mut evaluate::Scratch) -> Result<T, QueryError> + Sync,
    ) -> Result<Vec<T>, QueryError> {
        use rayon::prelude::*;
        const CHUNK: usize = 64;
        let chunks: Vec<Result<Vec<T>, QueryError>> = poses
            .par_chunks(CHUNK)
            .map(|chunk| {
                let mut scratch = evaluate::Scratch::default();
                chunk
                    .iter()
                    .map(|&p| {
                        self.stats.count_query();
                        one(self, p, &mut scratch)
                    })
                    .collect()
            })
            .collect();
        let mut out = Vec::with_capacity(poses.len());
        for c in chunks {
            out.extend(c?);
        }
        Ok(out)
    }

    /// How this pair's queries (and its clones' and trackers') were
    /// answered so far: see [`QueryStats`].
    pub fn stats(&self) -> QueryStats {
        self.stats.snapshot()
    }

    /// The penetration depth, or `None` when apart.
    ///
    /// # Errors
    /// The same as [`ConvexPair::query`].
    pub fn penetration_depth(
        &self,
        pose_a: Pose,
        pose_b: Pose,
    ) -> Result<Option<Contact>, QueryError> {
        Ok(self.query(pose_a, pose_b)?.contact().copied())
    }

    /// The distance (`0` and the contact features when touching or
    /// overlapping).
    ///
    /// # Errors
    /// The same as [`ConvexPair::query`].
    pub fn distance(&self, pose_a: Pose, pose_b: Pose) -> Result<Separation, QueryError> {
        Ok(match self.query(pose_a, pose_b)? {
            Proximity::Separated(s) => s,
            Proximity::Penetrating(c) => Separation {
                distance: 0.0,
                point_on_a: c.point_on_a,
                point_on_b: c.point_on_a,
                direction: c.normal,
                features: c.features,
            },
        })
    }

    /// `true` when the bodies overlap or touch, decided exactly on the
    /// posed bodies by GJK and its certificates alone (no depth or
    /// distance is computed).
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when a posed vertex overflows `f64`.
    pub fn intersects(&self, pose_a: Pose, pose_b: Pose) -> Result<bool, QueryError> {
        self.stats.count_query();
        self.with_scratch(|s| {
            s.posed.reset(self, pose_a, pose_b)?;
            Ok(evaluate::decide(self, s, true))
        })
    }

    /// A tracker starting at the given poses.
    ///
    /// # Errors
    /// The same as [`ContactTracker::new`].
    pub fn tracker(&self, pose_a: Pose, pose_b: Pose) -> Result<ContactTracker, QueryError> {
        ContactTracker::new(self, pose_a, pose_b)
    }
}

/// Penetration depth of `a` and `b` at their poses, or `None` when they are
/// apart (see the [module docs](self) for the conventions).
///
/// # Errors
/// Those of [`ConvexPair::new`] (internal only) and of
/// [`ConvexPair::query`]: an overflowing posed vertex or answer.
pub fn penetration_depth(
    a: &Polytope,
    pose_a: Pose,
    b: &Polytope,
    pose_b: Pose,
) -> Result<Option<Contact>, QueryError> {
    ConvexPair::new(a, b)?.penetration_depth(pose_a, pose_b)
}

/// Distance between `a` and `b` at their poses (`0` when touching or
/// overlapping), with the closest points.
///
/// # Errors
/// Those of [`ConvexPair::new`] (internal only) and of
/// [`ConvexPair::query`]: an overflowing posed vertex or answer.
pub fn distance(
    a: &Polytope,
    pose_a: Pose,
    b: &Polytope,
    pose_b: Pose,
) -> Result<Separation, QueryError> {
    ConvexPair::new(a, b)?.distance(pose_a, pose_b)
}

/// `true` when `a` and `b` overlap or touch at their poses.
///
/// # Errors
/// Those of [`ConvexPair::new`] (internal only) and of
/// [`ConvexPair::query`]: an overflowing posed vertex or answer.
pub fn intersects(
    a: &Polytope,
    pose_a: Pose,
    b: &Polytope,
    pose_b: Pose,
) -> Result<bool, QueryError> {
    ConvexPair::new(a, b)?.intersects(pose_a, pose_b)
}

/// Depth or distance of `a` and `b` at their poses.
///
/// # Errors
/// Those of [`ConvexPair::new`] (internal only) and of
/// [`ConvexPair::query`]: an overflowing posed vertex or answer.
pub fn query(
    a: &Polytope,
    pose_a: Pose,
    b: &Polytope,
    pose_b: Pose,
) -> Result<Proximity, QueryError> {
    ConvexPair::new(a, b)?.query(pose_a, pose_b)
}
