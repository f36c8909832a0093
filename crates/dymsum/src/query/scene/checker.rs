//! Exact state checks and certified motion checks of a body against a
//! scene, both given as triangles of any topology ([`SceneChecker`]): the
//! checker and its buffers here; state checks in `scene::state`, the
//! clearance in `scene::clearance`, the certified motion search (and its
//! soundness argument) in `scene::sweep`.
//!
//! # Contact
//! The body at a pose *collides* when a triangle of it meets a triangle of
//! the scene (closed sets), or a component of one lies inside a solid
//! component of the other ([`MeshBody`]'s semantics). The posed vertices
//! are `R p + t` rounded once per coordinate, as in every query of this
//! crate; everything after that is exact: the broad phase drops a pair of
//! triangles only when their exact boxes are apart, the narrow phase is
//! the exact closed triangle–triangle test, and containment the exact
//! winding number of the other body's enclosing triangles about a point,
//! by signed ray crossings ([`crate::body::winding`]; per obstacle in a scene).
//! When no triangles meet, a component lies where that winding number is
//! not zero exactly when any one of its points does (it is connected and
//! meets no triangle, and the winding number changes only across
//! triangles), so one corner per component is tested.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

use glam::DVec3;

use crate::body::{ContainmentStats, MeshBody};
use crate::kernel::rotation::Pose;
use crate::query::checker::{Checker, MotionCheck};
use crate::query::error::MotionError;
use crate::query::error::QueryError;
use crate::query::interval_search::{Pending, DEFAULT_BUDGET};
use crate::solid::aabb::{Aabb, AabbTree, NearPair};
use crate::solid::obb::{Obb, PosedObb};

/// Body vertices posed on demand, each once per query: `pts[v]` is
/// current when `stamp[v] == epoch`.
///
/// This buffer is allocated zeroed (`vec![0; n]` of plain numbers asks the
/// allocator for zeroed memory, which a large buffer gets as untouched
/// pages) rather than filled: a query touches a few of a large body's
/// entries, and filling them all made a checker's first query on a
/// 45,000-triangle body take 6.6 ms, in page faults. [`LazyTriangles`],
/// eight times larger, goes further and allocates by pages.
#[derive(Default)]
pub(super) struct Lazy {
    pts: Vec<[f64; 3]>,
    stamp: Vec<u32>,
    pub(super) epoch: u32,
}

impl Lazy {
    /// A new query over `n` vertices.
    pub(super) fn start(&mut self, n: usize) {
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 || self.stamp.len() != n {
            self.stamp = vec![0; n];
            if self.pts.len() != n {
                self.pts = vec![[0.0; 3]; n];
            }
            self.epoch = 1;
        }
    }

    /// Vertex `v` of `vertices` at `pose`.
    #[inline]
    pub(super) fn get(&mut self, vertices: &[DVec3], pose: &Pose, v: u32) -> DVec3 {
        let v = v as usize;
        if self.stamp[v] != self.epoch {
            self.stamp[v] = self.epoch;
            self.pts[v] = pose.apply(vertices[v]).to_array();
        }
        DVec3::from(self.pts[v])
    }
}

/// Body triangles posed on demand, each once per query (stamped with the
/// query's epoch): their corners (from [`Lazy`]) and the exact box of
/// those corners.
#[derive(Default)]
pub(super) struct LazyTriangles {
    stamp: Vec<u32>,
    /// The three corners, then the box's `lo` and `hi`, in pages of
    /// [`TRIANGLE_PAGE`] triangles, each allocated when a triangle in it is
    /// first posed: a scratch's first query on a large body touches a few
    /// pages, not the whole buffer (which an allocator reusing freed memory
    /// must clear: a 45,000-triangle body's first parallel query took 8 ms
    /// after other checkers had been dropped, 1 ms once its scratch
    /// existed).
    pages: Vec<Vec<[f64; 15]>>,
}

/// Triangles per page of [`LazyTriangles`].
const TRIANGLE_PAGE: usize = 256;

impl LazyTriangles {
    /// Forgets every triangle (the stamps restart with the epoch).
    pub(super) fn clear(&mut self) {
        self.stamp.clear();
        self.pages.clear();
    }

    /// Triangle `i` of `body` at `pose`, its corners posed by `at` (whose
    /// epoch is the query's).
    #[inline]
    pub(super) fn get(
        &mut self,
        at: &mut Lazy,
        body: &MeshBody,
        pose: &Pose,
        i: usize,
    ) -> ([DVec3; 3], Aabb) {
        let n = body.triangles.len();
        if self.stamp.len() != n {
            self.stamp = vec![0; n];
            self.pages = vec![Vec::new(); n.div_ceil(TRIANGLE_PAGE)];
        }
        let page = &mut self.pages[i / TRIANGLE_PAGE];
        if page.is_empty() {
            *page = vec![[0.0; 15]; TRIANGLE_PAGE];
        }
        let c = &mut page[i % TRIANGLE_PAGE];
        if self.stamp[i] != at.epoch {
            let t = body.triangles[i].map(|v| at.get(&body.vertices, pose, v));
            let b = Aabb::of(t.map(|p| p.to_array()));
            for (k, x) in t
                .iter()
                .flat_map(|p| p.to_array())
                .chain(b.lo)
                .chain(b.hi)
                .enumerate()
            {
                c[k] = x;
            }
            self.stamp[i] = at.epoch;
        }
        let p = |k: usize| DVec3::new(c[k], c[k + 1], c[k + 2]);
        (
            [p(0), p(3), p(6)],
            Aabb {
                lo: [c[9], c[10], c[11]],
                hi: [c[12], c[13], c[14]],
            },
        )
    }
}

/// Node bounds computed on demand, each once per query: slot `n` holds the
/// query's epoch (exact in an `f64`; `0` is no query's) and the value, as
/// plain numbers, so that a cache is allocated zeroed (see [`Lazy`]). A
/// query views it as cells ([`cells`]) to fill it from `Fn` closures.
pub(super) type NodeCache<T = Aabb> = Vec<<T as Slot>::Raw>;

/// A value kept in a [`NodeCache`] slot: its stamp and numbers.
pub(super) trait Slot: Copy {
    /// The slot: the stamp, then the value's numbers.
    type Raw: Copy;
    /// `stamp` and `self` as a slot.
    fn pack(self, stamp: u32) -> Self::Raw;
    /// A slot's stamp and value.
    fn unpack(raw: Self::Raw) -> (u32, Self);
}

impl Slot for Aabb {
    type Raw = [f64; 7];
    #[inline]
    fn pack(self, stamp: u32) -> [f64; 7] {
        let [a, b, c] = self.lo;
        let [d, e, f] = self.hi;
        [f64::from(stamp), a, b, c, d, e, f]
    }
    #[inline]
    fn unpack(r: [f64; 7]) -> (u32, Aabb) {
        let b = Aabb {
            lo: [r[1], r[2], r[3]],
            hi: [r[4], r[5], r[6]],
        };
        (r[0] as u32, b)
    }
}

impl Slot for PosedObb {
    type Raw = [f64; 13];
    #[inline]
    fn pack(self, stamp: u32) -> [f64; 13] {
        let mut r = [0.0; 13];
        r[0] = f64::from(stamp);
        for (k, v) in [self.c, self.f[0], self.f[1], self.f[2]].iter().enumerate() {
            r[1 + 3 * k..4 + 3 * k].copy_from_slice(&v.to_array());
        }
        r
    }
    #[inline]
    fn unpack(r: [f64; 13]) -> (u32, PosedObb) {
        let v = |k: usize| DVec3::new(r[1 + 3 * k], r[2 + 3 * k], r[3 + 3 * k]);
        (
            r[0] as u32,
            PosedObb {
                c: v(0),
                f: [v(1), v(2), v(3)],
            },
        )
    }
}

/// Triangles' own boxes (`solid::obb`, "Triangles' own boxes") in a
/// small direct-mapped cache: slot `i mod TRIANGLE_BOX_SLOTS` keeps
/// triangle `i`'s box and the stamp it was computed for (a scene
/// triangle's box holds for every query; a body triangle's for its
/// query's epoch). The walk meets the same few thick leaves many times
/// in a query, and a planner's next query meets them again.
pub(super) type TriangleBoxes = Vec<TriangleBox>;

/// A slot of [`TriangleBoxes`]: the triangle's number, the stamp, the box.
pub(super) type TriangleBox = (u32, u32, Obb);

/// Slots of a [`TriangleBoxes`] cache.
pub(super) const TRIANGLE_BOX_SLOTS: usize = 128;

/// A cache of [`TRIANGLE_BOX_SLOTS`] empty slots (stamp `0` is nobody's).
pub(super) fn triangle_boxes() -> TriangleBoxes {
    let empty = Obb {
        c: DVec3::ZERO,
        axes: [DVec3::X, DVec3::Y, DVec3::Z],
        h: DVec3::ZERO,
        fuzz: 0.0,
    };
    vec![(u32::MAX, 0, empty); TRIANGLE_BOX_SLOTS]
}

/// Triangle `i`'s own box for `stamp` from `cache`, or fitted to
/// `corners()` and kept.
#[inline]
pub(super) fn triangle_box(
    cache: &[std::cell::Cell<TriangleBox>],
    i: usize,
    stamp: u32,
    corners: impl FnOnce() -> [DVec3; 3],
) -> Obb {
    let slot = &cache[i % TRIANGLE_BOX_SLOTS];
    let (key, at, b) = slot.get();
    if key as usize == i && at == stamp {
        return b;
    }
    let b = Obb::of_triangle(&corners());
    slot.set((i as u32, stamp, b));
    b
}

/// A cache's slots as cells, for one query.
pub(super) fn cells<R>(cache: &mut [R]) -> &[std::cell::Cell<R>] {
    std::cell::Cell::from_mut(cache).as_slice_of_cells()
}

/// The value of node `n` from the cache, or computed and kept.
#[inline]
pub(super) fn cached<T: Slot>(
    cache: &[std::cell::Cell<T::Raw>],
    epoch: u32,
    n: usize,
    compute: impl Fn() -> T,
) -> T {
    let (stamp, b) = T::unpack(cache[n].get());
    if stamp == epoch {
        return b;
    }
    let b = compute();
    cache[n].set(b.pack(epoch));
    b
}

/// A box moved by `shift` (monotone rounding: it holds the moved points
/// as computed).
#[inline]
pub(super) fn shifted(b: &Aabb, shift: DVec3) -> Aabb {
    Aabb {
        lo: (DVec3::from(b.lo) + shift).to_array(),
        hi: (DVec3::from(b.hi) + shift).to_array(),
    }
}

/// The scene triangles met over one interval, in the body's frame
/// (`super::sweep`'s `relative_triangle`), each computed once: a scene
/// triangle near the body meets many body triangles (on the Cassie shin
/// against Talos's gripper, 47 to 100 scene triangles in 360 to 540 pairs
/// an interval).
#[derive(Default)]
pub(super) struct RelativeTriangles {
    /// For each scene triangle, the index of its entry, valid when that
    /// entry is there and names it (nothing to clear between intervals).
    slot: Vec<u32>,
    entries: Vec<RelativeTriangle>,
}

impl RelativeTriangles {
    /// Forgets the last interval's triangles, for a scene of `triangles`.
    pub(super) fn start(&mut self, triangles: usize) {
        self.entries.clear();
        if self.slot.len() < triangles {
            self.slot.resize(triangles, 0);
        }
    }

    /// Scene triangle `j`'s entry, computed by `compute` when missing.
    pub(super) fn get(
        &mut self,
        j: usize,
        compute: impl FnOnce() -> RelativeTriangle,
    ) -> &RelativeTriangle {
        let k = self.slot[j] as usize;
        let k = if k < self.entries.len() && self.entries[k].scene_triangle as usize == j {
            k
        } else {
            self.slot[j] = self.entries.len() as u32;
            self.entries.push(compute());
            self.entries.len() - 1
        };
        &self.entries[k]
    }
}

/// A scene triangle over an interval in the body's frame
/// (`super::sweep`'s `relative_triangle`).
pub(super) struct RelativeTriangle {
    pub(super) scene_triangle: u32,
    /// Its corners relative to the body at both ends (`R(a)ᵀ q_a`,
    /// `R(b)ᵀ q_b`), then each end's rotation with the other end's
    /// translation (`R(b)ᵀ q_a`, `R(a)ᵀ q_b`): the twelve points of the
    /// module docs of `super::sweep`, "In the body's frame".
    pub(super) points: [DVec3; 12],
    /// `e'`, the points' rounding.
    pub(super) rounding: f64,
    /// The swept hull's margin: the sagitta for the points' radius, and
    /// `e'`.
    pub(super) margin: f64,
    /// The bow of the points' paths between the ends.
    pub(super) bow: f64,
}

/// The buffers of one query (kept between queries by the checker).
#[derive(Default)]
pub(super) struct Scratch {
    /// The body's vertices at the pose (at an interval's start).
    pub(super) at: Lazy,
    /// The body's triangles at the pose (state checks).
    pub(super) tris: LazyTriangles,
    /// The body's vertices at an interval's end.
    pub(super) at_b: Lazy,
    /// The body's node bounds at the pose, or swept over an interval.
    pub(super) node_cache: NodeCache,
    /// The scene's node bounds carried back into the body's frame at the
    /// pose (state checks).
    pub(super) scene_cache: NodeCache,
    /// The body's oriented node boxes at the pose (state checks; an
    /// interval's start in motion checks).
    pub(super) obb_cache: NodeCache<PosedObb>,
    /// The body's oriented node boxes at an interval's end.
    pub(super) obb_cache_b: NodeCache<PosedObb>,
    /// The exact boxes of the body triangles' swept hulls over an
    /// interval (motion checks; sized on the first, and forgotten when the
    /// epoch wraps, by whichever query wraps it).
    pub(super) swept_boxes: NodeCache,
    /// The scene's and the body's (posed) triangles' own boxes (state
    /// checks; `state`).
    pub(super) scene_triangle_boxes: TriangleBoxes,
    pub(super) body_triangle_boxes: TriangleBoxes,
    pub(super) stack: Vec<(u32, u32)>,
    /// The clearance's queue of node pairs.
    pub(super) near: Vec<NearPair>,
    pub(super) parity: Vec<u8>,
    /// The points a containment test asks (`state`: the body components
    /// near the scene's solids, the scene components near the body).
    pub(super) asked: Vec<usize>,
    pub(super) intervals: Vec<Pending>,
    /// The triangle pairs that intervals left uncertified, for the
    /// intervals cut from them (`super::sweep`, "Reuse across halving").
    pub(super) front: Vec<(u32, u32)>,
    /// Whether the last interval examined was certified (a walk records
    /// only then; `super::sweep`).
    pub(super) last_certified: bool,
    /// The pair that last kept an interval from being certified (tried
    /// first next time).
    pub(super) blocker: Option<(usize, usize)>,
    /// The scene triangles met in the body's frame over an interval
    /// (`super::sweep`, "In the body's frame").
    pub(super) relative: RelativeTriangles,
    /// How this scratch's containment tests decided their points since it
    /// was last given back.
    pub(super) tally: ContainmentStats,
}

/// A body and a scene prepared for many state and motion checks (a
/// planner's validators), both as triangles of any topology
/// ([`MeshBody`]): contact and the motion bound as in the module docs.
///
/// A rod swinging past a thin open plate (a surface, one square):
///
/// ```
/// use dymsum::query::{MeshBody, MotionCheck, SceneChecker};
/// use dymsum::{DVec3, PolygonMesh, Pose, Rotation};
/// let plate = PolygonMesh::new(
///     vec![[1.5, -1.0, 0.5], [1.5, 1.0, 0.5], [1.5, 1.0, 2.5], [1.5, -1.0, 2.5]],
///     vec![vec![0, 1, 2, 3]],
/// );
/// // A rod: a long thin triangle from the origin along x.
/// let rod = PolygonMesh::new(
///     vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 0.0, 0.01]],
///     vec![vec![0, 1, 2]],
/// );
/// let checker = SceneChecker::new(&MeshBody::new(&rod)?, &[MeshBody::new(&plate)?])?;
/// let pitch = |deg: f64| {
///     Pose::new(Rotation::from_axis_angle(DVec3::Y, -deg.to_radians()).unwrap(), DVec3::ZERO)
/// };
/// // Level and straight up are free; the swing between passes the plate.
/// assert!(!checker.collides_at(pitch(0.0))? && !checker.collides_at(pitch(90.0))?);
/// match checker.check(pitch(0.0), pitch(90.0), 1e-6)? {
///     MotionCheck::Collides { t_safe, t_contact } => {
///         assert!(t_contact - t_safe.unwrap() <= 1e-6);
///         assert!(checker.collides_at(pitch(90.0 * t_contact))?);
///     }
///     MotionCheck::Free => panic!("the rod swings through the plate"),
/// }
/// // Swinging the other way, down and back, misses it.
/// assert_eq!(checker.check(pitch(0.0), pitch(-90.0), 1e-6)?, MotionCheck::Free);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct SceneChecker {
    pub(super) body: MeshBody,
    pub(super) scene: MeshBody,
    /// The scene components' corners (one each), as point boxes.
    pub(super) scene_corners: AabbTree,
    pub(super) budget: u64,
    pub(super) steps: AtomicU64,
    /// Boxed, so that taking one out and putting it back moves a pointer,
    /// not the buffers' hundreds of bytes of headers (measured: a tenth of
    /// a state check whose roots are apart). Hence the lint's exception.
    #[allow(clippy::vec_box)]
    pub(super) pool: Mutex<Vec<Box<Scratch>>>,
    /// The scratches' containment tallies, added as each is given back.
    pub(super) containment: Mutex<ContainmentStats>,
}

impl std::fmt::Debug for SceneChecker {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SceneChecker")
            .field("body", &self.body.report())
            .field("scene", &self.scene.report())
            .field("budget", &self.budget)
            .finish()
    }
}

impl SceneChecker {
    /// Prepares `body` (in its own frame) against `scene` (bodies placed in
    /// the world frame, joined into one).
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when the body or the scene has no
    /// triangles.
    pub fn new(body: &MeshBody, scene: &[MeshBody]) -> Result<SceneChecker, QueryError> {
        // Every query walks both triangle trees (built on first use, as a
        // body on the convex path never needs them): built here, so the
        // first query costs what the others do, and on the caller's
        // bodies, so that the checkers made from one body share its tree.
        // One after the other on this thread, not side by side: a tree
        // built on a worker thread grows that thread's heap, while here it
        // reuses what the bodies' cleaning freed. On a 100,000-triangle
        // soup as body and obstacle, the peak fell from 100–120 MB to 73
        // MB (`mem_probe`), for about a third more time
        // (docs/BENCHMARKS.md, "Builds one at a time").
        // So are the grids their containment reads (`body::inside_grid`).
        body.tree();
        body.inside_grid();
        if let [one] = scene {
            one.tree();
            one.inside_grid();
        }
        let scene = MeshBody::join(scene);
        scene.tree();
        scene.inside_grid();
        if body.triangles.is_empty() {
            return Err(QueryError::OutOfRange("the body has no triangles".into()));
        }
        let corners: Vec<[f64; 3]> = scene
            .components
            .iter()
            .map(|&(_, v)| scene.vertices[v as usize].to_array())
            .collect();
        Ok(SceneChecker {
            body: body.clone(),
            scene,
            // A point per component: a k-d tree (the area heuristic has no
            // areas to weigh), as there may be one per triangle of a soup.
            scene_corners: AabbTree::over_points(&corners),
            budget: DEFAULT_BUDGET,
            steps: AtomicU64::new(0),
            pool: Mutex::new(Vec::new()),
            containment: Mutex::new(ContainmentStats::default()),
        })
    }

    /// The same checker with a work budget of `steps` intervals per motion
    /// check (at least 1; [`DEFAULT_BUDGET`] unless set): a check that has
    /// examined that many intervals without a decision ends with
    /// [`MotionError::BudgetExhausted`] and its certified `t_safe`.
    pub fn with_budget(mut self, steps: u64) -> SceneChecker {
        self.budget = steps.max(1);
        self
    }

    /// The work budget of one motion check, in intervals.
    pub fn budget(&self) -> u64 {
        self.budget
    }

    /// The intervals examined by all motion checks so far.
    pub fn steps(&self) -> u64 {
        self.steps.load(Ordering::Relaxed)
    }

    /// The body, as prepared.
    pub fn body(&self) -> &MeshBody {
        &self.body
    }

    /// The scene, as prepared (all obstacles joined).
    pub fn scene(&self) -> &MeshBody {
        &self.scene
    }

    pub(super) fn scratch(&self) -> Box<Scratch> {
        self.pool
            .lock()
            .ok()
            .and_then(|mut p| p.pop())
            .unwrap_or_default()
    }

    /// How the containment tests of all queries so far decided their
    /// points (those of queries still running are added when they end).
    ///
    /// ```
    /// use dymsum::query::{MeshBody, SceneChecker};
    /// use dymsum::robot::shapes::box_mesh;
    /// use dymsum::{DVec3, Pose, Rotation};
    /// let cube = |side: f64| MeshBody::new(&box_mesh(DVec3::splat(side)));
    /// // A small cube well inside a large one: the large one's grid holds
    /// // it whole, and no point is asked.
    /// let checker = SceneChecker::new(&cube(0.1)?, &[cube(10.0)?])?;
    /// assert!(checker.collides_at(Pose::new(Rotation::IDENTITY, DVec3::ZERO))?);
    /// assert_eq!(checker.containment_stats().bodies_by_grid, 1);
    /// // Inside by the large one's face, in a cell that the face meets: its
    /// // corners are asked.
    /// assert!(checker.collides_at(Pose::new(Rotation::IDENTITY, DVec3::X * 4.9))?);
    /// let stats = checker.containment_stats();
    /// assert!(stats.by_grid + stats.by_segment + stats.by_ray >= 1);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn containment_stats(&self) -> ContainmentStats {
        self.containment.lock().map(|t| *t).unwrap_or_default()
    }

    pub(super) fn give_back(&self, mut s: Box<Scratch>) {
        if s.tally != ContainmentStats::default() {
            if let Ok(mut t) = self.containment.lock() {
                t.add(&s.tally);
            }
            s.tally = ContainmentStats::default();
        }
        if let Ok(mut p) = self.pool.lock() {
            p.push(s);
        }
    }

    /// Every posed coordinate is at most `|t| + reach` in size: that must
    /// stay far below `f64::MAX` (no bound, box or sum overflows).
    pub(super) fn check_range(&self, pose: &Pose) -> Result<(), QueryError> {
        if !pose.translation.is_finite() || !pose.rotation.matrix().is_finite() {
            return Err(QueryError::OutOfRange(format!(
                "the pose is not finite (translation {:?})",
                pose.translation.to_array()
            )));
        }
        let size = self.body.reach + pose.translation.abs().max_element();
        if size.is_nan() || size >= 1e300 {
            return Err(QueryError::OutOfRange(format!(
                "the body at translation {:?} reaches {size:e}, beyond 1e300",
                pose.translation.to_array()
            )));
        }
        Ok(())
    }

    pub(super) fn fit_node_cache(&self, s: &mut Scratch) {
        let n = self.body.tree().bounds().len();
        if s.node_cache.len() != n || s.at.epoch == 1 {
            s.node_cache = vec![[0.0; 7]; n];
        }
        if s.obb_cache.len() != n || s.at.epoch == 1 {
            s.obb_cache = vec![[0.0; 13]; n];
        }
        if s.obb_cache_b.len() != n || s.at.epoch == 1 {
            s.obb_cache_b = vec![[0.0; 13]; n];
        }
        let k = self.scene.tree().bounds().len();
        if s.scene_cache.len() != k || s.at.epoch == 1 {
            s.scene_cache = vec![[0.0; 7]; k];
        }
        if s.scene_triangle_boxes.len() != TRIANGLE_BOX_SLOTS {
            s.scene_triangle_boxes = triangle_boxes();
        }
        if s.body_triangle_boxes.len() != TRIANGLE_BOX_SLOTS || s.at.epoch == 1 {
            s.body_triangle_boxes = triangle_boxes();
        }
        if s.at.epoch == 1 {
            // The epoch wrapped (or this is the first query): stamps from
            // the last cycle must not pass for this one's.
            s.tris.clear();
            s.swept_boxes.clear();
        }
    }

    /// The rounding bound of posing the body at `pose` (module docs).
    pub(super) fn pad(&self, pose: &Pose) -> f64 {
        64.0 * f64::EPSILON * (self.body.reach + pose.translation.abs().max_element())
    }

    pub(super) fn scene_triangle(&self, j: usize) -> [DVec3; 3] {
        self.scene.triangles[j].map(|v| self.scene.vertices[v as usize])
    }
}

impl Checker for SceneChecker {
    fn collides_at(&self, pose: Pose) -> Result<bool, QueryError> {
        SceneChecker::collides_at(self, pose)
    }

    fn distance_at(&self, pose: Pose) -> Result<f64, QueryError> {
        SceneChecker::distance_at(self, pose)
    }

    fn check(&self, from: Pose, to: Pose, tolerance: f64) -> Result<MotionCheck, MotionError> {
        SceneChecker::check(self, from, to, tolerance)
    }

    fn budget(&self) -> u64 {
        SceneChecker::budget(self)
    }

    fn with_budget(self, steps: u64) -> SceneChecker {
        SceneChecker::with_budget(self, steps)
    }

    fn steps(&self) -> u64 {
        SceneChecker::steps(self)
    }
}
