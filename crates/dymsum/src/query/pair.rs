//! [`ConvexPair`]: two convex bodies prepared for repeated exact queries
//! (the reflection `−B`, each body's cached [`BodyPrep`], the counters of
//! [`QueryStats`]), and the one-off query functions.

use crate::kernel::rotation::Pose;
use crate::polytope::Polytope;
use crate::query::answer::{Contact, Proximity, Separation};
use crate::query::error::QueryError;
use crate::query::tracker::ContactTracker;
use glam::DVec3;
use std::collections::HashMap;

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

pub(in crate::query) fn bits(v: DVec3) -> [u64; 3] {
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
    pub(in crate::query) a: Polytope,
    pub(in crate::query) b: Polytope,
    pub(in crate::query) prep_a: std::sync::Arc<BodyPrep>,
    pub(in crate::query) prep_b: std::sync::Arc<BodyPrep>,
    pub(in crate::query) stats: std::sync::Arc<Counters>,
    /// Query buffers kept between the static queries of this pair and its
    /// clones (one per query running at a time), so that a query
    /// allocates nothing once they have grown.
    pub(in crate::query) pool:
        std::sync::Arc<std::sync::Mutex<Vec<crate::query::proximity::evaluate::Scratch>>>,
}

/// What the queries need of one body beyond the body itself, computed once
/// per body (on its first query) and kept by the body's [`Polytope`]
/// handle, so preparing a pair costs nothing after the first time.
#[derive(Debug)]
pub(crate) struct BodyPrep {
    /// Balls around the faces and edges (the separation's branch and
    /// bound).
    pub(in crate::query) balls: crate::query::proximity::distance::FeatureBalls,
    /// Reach and radius (the query frame's bounds).
    pub(in crate::query) bounds: crate::query::frame::BodyBounds,
    /// Error bounds of the arc normals under any rotation, exactly as the
    /// overlay's operands compute them (the body as A).
    pub(in crate::query) arc_err: Vec<f64>,
    /// The reflection `−body` (the body as B).
    pub(in crate::query) neg: Reflected,
    /// Vertex, face and edge → the same of the reflection (the inverses of
    /// [`Reflected`]'s maps).
    pub(in crate::query) neg_vertex: Vec<u32>,
    pub(in crate::query) neg_face: Vec<u32>,
    pub(in crate::query) neg_edge: Vec<u32>,
    /// Caps holding each vertex's Gaussian cell and each edge's Gaussian
    /// arc (body frame): the certificates' quick rejections.
    pub(in crate::query) caps: crate::query::proximity::certificate::GaussCaps,
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
            balls: crate::query::proximity::distance::FeatureBalls::of(p),
            bounds: crate::query::frame::BodyBounds::of(p),
            arc_err,
            neg_vertex: inverse(&neg.vertex_map),
            neg_face: inverse(&neg.face_map),
            neg_edge: inverse(&neg.edge_map),
            neg,
            caps: crate::query::proximity::certificate::GaussCaps::of(p),
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
pub(in crate::query) struct Counters {
    pub(in crate::query) queries: std::sync::atomic::AtomicU64,
    pub(in crate::query) exhaustive_decisions: std::sync::atomic::AtomicU64,
    pub(in crate::query) exhaustive_answers: std::sync::atomic::AtomicU64,
}

impl Counters {
    pub(in crate::query) fn bump(c: &std::sync::atomic::AtomicU64) {
        c.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }
    pub(in crate::query) fn count_query(&self) {
        Self::bump(&self.queries);
    }
    pub(in crate::query) fn count_exhaustive_decision(&self) {
        Self::bump(&self.exhaustive_decisions);
    }
    pub(in crate::query) fn count_exhaustive_answer(&self) {
        Self::bump(&self.exhaustive_answers);
    }
    pub(in crate::query) fn snapshot(&self) -> QueryStats {
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
            crate::query::proximity::evaluate::evaluate(
                self,
                pose_a,
                pose_b,
                crate::query::proximity::evaluate::Facets::Certified,
                s,
            )
        })
    }

    /// Runs `f` with buffers from the pool, reset to a cold start (no warm
    /// start from an earlier query: a static query's cost does not depend
    /// on the queries before it).
    pub(in crate::query) fn with_scratch<T>(
        &self,
        f: impl FnOnce(&mut crate::query::proximity::evaluate::Scratch) -> T,
    ) -> T {
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
            crate::query::proximity::evaluate::evaluate(
                self,
                pose_a,
                pose_b,
                crate::query::proximity::evaluate::Facets::Exhaustive,
                s,
            )
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
            crate::query::proximity::evaluate::evaluate(
                pair,
                pa,
                pb,
                crate::query::proximity::evaluate::Facets::Certified,
                s,
            )
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
            Ok(crate::query::proximity::evaluate::decide(pair, s, true))
        })
    }

    /// Answers `one` at every pose, in parallel chunks of warm-started
    /// queries.
    pub(in crate::query) fn many<T: Send>(
        &self,
        poses: &[(Pose, Pose)],
        one: impl Fn(
                &ConvexPair,
                (Pose, Pose),
                &mut crate::query::proximity::evaluate::Scratch,
            ) -> Result<T, QueryError>
            + Sync,
    ) -> Result<Vec<T>, QueryError> {
        use rayon::prelude::*;
        const CHUNK: usize = 64;
        let chunks: Vec<Result<Vec<T>, QueryError>> = poses
            .par_chunks(CHUNK)
            .map(|chunk| {
                let mut scratch = crate::query::proximity::evaluate::Scratch::default();
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
            Ok(crate::query::proximity::evaluate::decide(self, s, true))
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
