//! [`ConvexPair`]: two convex bodies prepared for repeated exact queries
//! (the reflection `−B`, each body's cached [`BodyPrep`], the counters of
//! [`QueryStats`]), and the one-off query functions.

use crate::polytope::Polytope;
use crate::query::error::QueryError;
use crate::query::prep::{BodyPrep, Reflected};

/// Two convex bodies prepared for repeated queries: `B`'s reflection is
/// built once. Use it (or a [`crate::query::ContactTracker`]) instead of the free functions
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
    /// B's reflection, numbered as B (kept by B's preparation).
    pub(in crate::query) refl_b: std::sync::Arc<Reflected>,
    pub(in crate::query) stats: std::sync::Arc<Counters>,
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
    /// Penetrations whose EPA polytope was the last frame's, re-posed (a
    /// tracker's frames in contact).
    pub carried_polytopes: u64,
    /// Of those, how many could not use it (a face turned, too many faces,
    /// or its certificate failed) and grew a fresh one from GJK's simplex.
    pub carried_restarts: u64,
}

/// The counters behind [`QueryStats`].
#[derive(Debug, Default)]
pub(in crate::query) struct Counters {
    pub(in crate::query) queries: std::sync::atomic::AtomicU64,
    pub(in crate::query) exhaustive_decisions: std::sync::atomic::AtomicU64,
    pub(in crate::query) exhaustive_answers: std::sync::atomic::AtomicU64,
    pub(in crate::query) carried_polytopes: std::sync::atomic::AtomicU64,
    pub(in crate::query) carried_restarts: std::sync::atomic::AtomicU64,
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
    pub(in crate::query) fn count_carried_polytope(&self, restarted: bool) {
        Self::bump(&self.carried_polytopes);
        if restarted {
            Self::bump(&self.carried_restarts);
        }
    }
    pub(in crate::query) fn snapshot(&self) -> QueryStats {
        let get = |c: &std::sync::atomic::AtomicU64| c.load(std::sync::atomic::Ordering::Relaxed);
        QueryStats {
            queries: get(&self.queries),
            exhaustive_decisions: get(&self.exhaustive_decisions),
            exhaustive_answers: get(&self.exhaustive_answers),
            carried_polytopes: get(&self.carried_polytopes),
            carried_restarts: get(&self.carried_restarts),
        }
    }
}

impl ConvexPair {
    /// Prepares `a` and `b`: the data each body's queries need (bounds,
    /// balls and caps; B's reflection as well, the first time the body is
    /// someone's B) is computed on the body's first query and kept by its
    /// [`Polytope`] handle, so pairing bodies again costs nothing. The
    /// pair keeps its own handles on the bodies (cheap clones); a clone of
    /// the pair shares everything.
    ///
    /// # Errors
    /// None for polytopes built by this crate: B's reflection is read off
    /// B ([`Reflected::new`]) and cannot fail. The result stays so that a
    /// preparation that can fail may be added without changing callers.
    pub fn new(a: &Polytope, b: &Polytope) -> Result<Self, QueryError> {
        let prep_b = BodyPrep::of_cached(b);
        Ok(ConvexPair {
            a: a.clone(),
            b: b.clone(),
            prep_a: BodyPrep::of_cached(a),
            refl_b: prep_b.reflection(b),
            prep_b,
            stats: std::sync::Arc::new(Counters::default()),
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
        &self.refl_b
    }

    /// B's reflection (crate-internal shorthand).
    #[inline]
    pub(crate) fn neg_b(&self) -> &Reflected {
        &self.refl_b
    }

    /// How this pair's queries (and its clones' and trackers') were
    /// answered so far: see [`QueryStats`].
    pub fn stats(&self) -> QueryStats {
        self.stats.snapshot()
    }
}
