//! The buffers of a query ([`Scratch`]), kept by a tracker from frame to
//! frame, and this thread's pool of them for static queries
//! ([`with_scratch`]).
use crate::query::frame::Posed;
use crate::query::pair::ConvexPair;
use crate::query::proximity::certificate::candidates::{Candidate, FacetSet};
use crate::query::proximity::certificate::LocalScratch;
use crate::query::proximity::gjk::{CertScratch, Gjk, Simplex};
use glam::DVec3;

/// The buffers of one evaluation, kept by a [`crate::query::tracker::ContactTracker`] from
/// frame to frame so that a frame allocates nothing once they are large
/// enough.
#[derive(Clone, Debug, Default)]
pub(crate) struct Scratch {
    pub(in crate::query) posed: Posed,
    /// The last support vertices (GJK's warm start).
    pub(in crate::query) warm: Warm,
    /// The last GJK direction.
    pub(in crate::query) dir: DVec3,
    /// The last GJK run.
    pub(in crate::query) gjk: Option<Gjk>,
    /// Its final simplex (the next query's start).
    pub(in crate::query) simplex: Simplex,
    /// The last penetration's contact normal (EPA's first direction).
    pub(in crate::query) normal: Option<DVec3>,
    /// `local.epa` holds the polytope of the last query on this scratch, a
    /// certified penetration of the same pair: the next penetration
    /// re-poses it rather than starting afresh. Taken (reset) by every
    /// query, set by a certified penetration.
    pub(in crate::query) epa_carried: bool,
    pub(in crate::query) cert: CertScratch,
    /// Every facet (the exhaustive evaluation).
    pub(in crate::query) all: FacetSet,
    /// The certificates' local searches.
    pub(in crate::query) local: LocalScratch,
    pub(in crate::query) cands: Vec<Candidate>,
    /// A face's posed corners (the separation).
    pub(in crate::query) poly: Vec<DVec3>,
    /// The facing facets' distance bounds (the separation).
    pub(in crate::query) bounds: Vec<f64>,
}

impl Scratch {
    /// Keeps GJK's end as the next query's warm start.
    pub(in crate::query) fn remember(&mut self, g: &Gjk) {
        self.warm = Warm(g.warm.0, g.warm.1);
        if g.v.length_squared() > 0.0 {
            self.dir = g.v;
        }
        self.gjk = Some(*g);
        self.simplex = g.simplex;
    }

    /// Forgets the warm start (the buffers stay).
    pub(in crate::query) fn cold(&mut self) {
        self.warm = Warm::default();
        self.dir = DVec3::ZERO;
        self.gjk = None;
        self.simplex = Simplex::default();
        self.normal = None;
        self.epa_carried = false;
    }
}

/// Support vertices of A and B to start the next GJK from.
#[derive(Clone, Copy, Debug, Default)]
pub(in crate::query) struct Warm(u32, u32);

impl Warm {
    /// The vertices, or vertex 0 where one is out of range (a scratch
    /// reused with another pair).
    pub(in crate::query) fn clamp(self, pair: &ConvexPair) -> (u32, u32) {
        let ok = |v: u32, n: usize| if (v as usize) < n { v } else { 0 };
        (
            ok(self.0, pair.a.vertex_count()),
            ok(self.1, pair.b.vertex_count()),
        )
    }
}

std::thread_local! {
    /// Query buffers of this thread, reused from query to query (a stack:
    /// a query run inside another, as the `check-reference` comparison
    /// does, takes its own).
    /// Boxed: a query moves a pointer in and out of the pool, not the
    /// buffers' few kilobytes of inline state (measured: 1.1 k
    /// instructions of copying a query, hence the allowance).
    #[allow(clippy::vec_box)]
    static SCRATCH: std::cell::RefCell<Vec<Box<Scratch>>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Runs `f` with this thread's query buffers, reset to a cold start (no
/// warm start from an earlier query: a static query's cost does not depend
/// on the queries before it).
pub(in crate::query) fn with_scratch<T>(f: impl FnOnce(&mut Scratch) -> T) -> T {
    let mut scratch = SCRATCH
        .with(|pool| pool.borrow_mut().pop())
        .unwrap_or_default();
    scratch.cold();
    let out = f(&mut scratch);
    SCRATCH.with(|pool| pool.borrow_mut().push(scratch));
    out
}
