//! Exact state checks and certified motion checks of a body against a
//! scene, both given as triangles of any topology ([`SceneChecker`]).
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
//! by signed ray crossings ([`super::inside`]; per obstacle in a scene).
//! When no triangles meet, a component lies where that winding number is
//! not zero exactly when any one of its points does (it is connected and
//! meets no triangle, and the winding number changes only across
//! triangles), so one corner per component is tested.
//!
//! # Motions: why "free" is certain
//! The motion is [`Motion`]'s (linear translation, slerp rotation, the
//! arc decided exactly). Over an interval `[a, b]` the rotation turns by
//! `δ = Θ (b − a)` about one fixed axis (`Θ` the whole angle: slerp turns
//! at a constant rate), so a body point `p` (`|p| ≤ r`, the body's reach)
//! moves on a circle arc of angle `δ ≤ π` and radius at most `r`, within
//! the sagitta `s = r (1 − cos(δ/2))` of the chord between `R(a) p` and
//! `R(b) p`; the translation moves on the segment `[T(a), T(b)]`. So a
//! body triangle `P`, at every `t` in `[a, b]`, lies in
//!
//! `conv(R(a) P ∪ R(b) P) ⊕ [T(a), T(b)] ⊕ ball(s)`,
//!
//! the hull of twelve points (each corner turned as at `a` and at `b`,
//! moved as at `a` and at `b`) grown by `s`: the motion search's
//! *swept hull* (the convex checker's bound, [`crate::query::MotionChecker`],
//! per triangle). If every pair of a swept hull and a scene triangle is
//! more than `s` plus `e` apart, no triangles meet anywhere in `[a, b]`:
//! `e = 2⁻⁴³ r + 6u (M + D)` (`u = 2⁻⁵³`, `M` the largest end translation
//! coordinate, `D` the largest of their difference) bounds the distance
//! between each of the twelve points as computed (posed in floats, then
//! moved by the float difference of the translations) and its exact
//! value on the exact motion (`query::rounding`: the rotation's error is
//! relative to the reach, the translation's a few ulps of the
//! coordinates), and `δ` is rounded up from the float angle plus its
//! error bound (`2⁻⁴⁶`). Pairs whose boxes are more than that apart on an axis are
//! dropped by the broad phase (an exact comparison after a monotone
//! rounding), the others are certified by [`super::gap`]: floats propose
//! an axis, and the gap along it is bounded below rigorously, about the
//! scene triangle's first corner (so its rounding is a few ulps of the
//! local sizes, not of the coordinates). A slide
//! along a wall certifies in one interval (the hull stays on its side);
//! the sagitta is second order in the interval's width. Containment
//! cannot begin without triangles meeting, and the body is not inside
//! anything at `t = 0` (checked first), so the certified intervals,
//! examined left to right from `0`, are free of every contact.
//!
//! # The search
//! Intervals are examined left to right from `[0, 1]`: one that is
//! certified is done; one that is not is halved, and once it is no wider
//! than the tolerance its right end is checked exactly, and a contact
//! there ends the check with the bracket `(t_safe, t_contact)`. When
//! halving keeps ending just before a contact (an interval a thousand
//! times narrower than the tolerance, its end free but not certified: the
//! body within the rounding margin of an obstacle it is about to enter),
//! the times `a + tol/128`, …, `a + tol` are checked, and a contact at any
//! of them is a valid bracket, since `[0, a]` is certified. A thin
//! wall is not stepped over: an interval sweeping through it is never
//! certified. An interval narrower than [`MIN_WIDTH`] that is neither
//! certified nor colliding at its end (a grazing motion) is
//! [`MotionError::Undecided`]; past the budget of intervals,
//! [`MotionError::BudgetExhausted`]. Neither is ever a guess.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

use glam::DVec3;

use super::gap::{apart_by_more_than, distance_lower_bound};
use super::inside::inside_solid;
use crate::body::mesh::triangle_boxes_into;
use crate::body::MeshBody;
use crate::kernel::rotation::Pose;
use crate::query::error::QueryError;
use crate::query::motion::{
    Motion, MotionCheck, MotionError, DEFAULT_BUDGET, MIN_TOLERANCE, MIN_WIDTH,
};
use crate::query::rounding::{pose_rounding_bound, ANGLE_ROUNDING};
use crate::solid::aabb::{Aabb, AabbTree};
use crate::solid::intersect::triangles_meet;

/// Body vertices posed on demand, each once per query: `pts[v]` is
/// current when `stamp[v] == epoch`.
#[derive(Default)]
struct Lazy {
    pts: Vec<DVec3>,
    stamp: Vec<u32>,
    epoch: u32,
}

impl Lazy {
    /// A new query over `n` vertices.
    fn start(&mut self, n: usize) {
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 || self.stamp.len() != n {
            self.stamp.clear();
            self.stamp.resize(n, 0);
            self.pts.resize(n, DVec3::ZERO);
            self.epoch = 1;
        }
    }

    /// Vertex `v` of `vertices` at `pose`.
    #[inline]
    fn get(&mut self, vertices: &[DVec3], pose: &Pose, v: u32) -> DVec3 {
        let v = v as usize;
        if self.stamp[v] != self.epoch {
            self.stamp[v] = self.epoch;
            self.pts[v] = pose.apply(vertices[v]);
        }
        self.pts[v]
    }
}

/// Node bounds computed on demand, each once per query (stamped with the
/// query's epoch).
type NodeCache = Vec<std::cell::Cell<(u32, Aabb)>>;

/// The value of node `n` from the cache, or computed and kept.
#[inline]
fn cached(cache: &NodeCache, epoch: u32, n: usize, compute: impl Fn() -> Aabb) -> Aabb {
    let (stamp, b) = cache[n].get();
    if stamp == epoch {
        return b;
    }
    let b = compute();
    cache[n].set((epoch, b));
    b
}

/// A box moved by `shift` (monotone rounding: it holds the moved points
/// as computed).
#[inline]
fn shifted(b: &Aabb, shift: DVec3) -> Aabb {
    Aabb {
        lo: (DVec3::from(b.lo) + shift).to_array(),
        hi: (DVec3::from(b.hi) + shift).to_array(),
    }
}

/// The buffers of one query (kept between queries by the checker).
#[derive(Default)]
struct Scratch {
    /// The body's vertices at the pose (at an interval's start).
    at: Lazy,
    /// The body's vertices at an interval's end.
    at_b: Lazy,
    /// The body's node bounds at the pose, or swept over an interval.
    node_cache: NodeCache,
    posed: Vec<DVec3>,
    /// The body's component boxes at a pose.
    component_boxes: Vec<Aabb>,
    boxes: Vec<Aabb>,
    bounds: Vec<Aabb>,
    stack: Vec<(u32, u32)>,
    parity: Vec<u8>,
    intervals: Vec<(f64, f64)>,
    /// The pair that last kept an interval from being certified (tried
    /// first next time).
    blocker: Option<(usize, usize)>,
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
    body: MeshBody,
    scene: MeshBody,
    /// The scene components' corners (one each), as point boxes.
    scene_corners: AabbTree,
    budget: u64,
    steps: AtomicU64,
    pool: Mutex<Vec<Scratch>>,
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
        let scene = MeshBody::join(scene);
        if body.triangles.is_empty() {
            return Err(QueryError::OutOfRange("the body has no triangles".into()));
        }
        let corners: Vec<Aabb> = scene
            .components
            .iter()
            .map(|&(_, v)| {
                let p = scene.vertices[v as usize].to_array();
                Aabb { lo: p, hi: p }
            })
            .collect();
        Ok(SceneChecker {
            body: body.clone(),
            scene,
            scene_corners: AabbTree::new(&corners),
            budget: DEFAULT_BUDGET,
            steps: AtomicU64::new(0),
            pool: Mutex::new(Vec::new()),
        })
    }

    /// The same checker with a work budget of `steps` intervals per motion
    /// check (at least 1; [`DEFAULT_BUDGET`] unless set).
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

    fn scratch(&self) -> Scratch {
        self.pool
            .lock()
            .ok()
            .and_then(|mut p| p.pop())
            .unwrap_or_default()
    }

    fn give_back(&self, s: Scratch) {
        if let Ok(mut p) = self.pool.lock() {
            p.push(s);
        }
    }

    /// Whether the body at `pose` touches or overlaps the scene (exact;
    /// module docs).
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when a posed coordinate is not finite, or
    /// (never seen) when no ray decides a containment.
    pub fn collides_at(&self, pose: Pose) -> Result<bool, QueryError> {
        let mut s = self.scratch();
        let out = self.collides_with(pose, &mut s);
        self.give_back(s);
        out
    }

    /// [`SceneChecker::collides_at`] for many poses, in parallel, in order.
    ///
    /// # Errors
    /// The first error of [`SceneChecker::collides_at`].
    pub fn collides_many(&self, poses: &[Pose]) -> Result<Vec<bool>, QueryError> {
        use rayon::prelude::*;
        poses.par_iter().map(|&p| self.collides_at(p)).collect()
    }

    /// The clearance of the body at `pose` from the scene: `0` when they
    /// collide ([`SceneChecker::collides_at`]), else the least distance
    /// between a body triangle and a scene triangle, rounded down: a
    /// certified lower bound within rounding of it (each pair's bound is
    /// the gap along the direction of its closest points found in floating
    /// point, `query::scene::gap`; the broad phase skips only pairs whose boxes
    /// are farther apart than the best so far). For clearance objectives.
    ///
    /// # Errors
    /// Those of [`SceneChecker::collides_at`].
    pub fn distance_at(&self, pose: Pose) -> Result<f64, QueryError> {
        let mut s = self.scratch();
        let out = self.clearance(pose, &mut s);
        self.give_back(s);
        out
    }

    fn clearance(&self, pose: Pose, s: &mut Scratch) -> Result<f64, QueryError> {
        if self.collides_with(pose, s)? {
            return Ok(0.0);
        }
        s.at.start(self.body.vertices.len());
        self.fit_node_cache(s);
        let (m, t, pad) = (pose.rotation.matrix(), pose.translation, self.pad(&pose));
        let (bounds, boxes) = (self.body.tree.bounds(), self.body.tree.boxes());
        let cache = std::mem::take(&mut s.node_cache);
        let epoch = s.at.epoch;
        let mut stack = std::mem::take(&mut s.stack);
        let best = self.body.tree.nearest_pair(
            |n| cached(&cache, epoch, n, || bounds[n].transformed(&m, t, pad)),
            |i| boxes[i].transformed(&m, t, pad),
            &self.scene.tree,
            &mut stack,
            |i, j| {
                let tri = self.body.triangles[i].map(|v| s.at.get(&self.body.vertices, &pose, v));
                distance_lower_bound(&tri, &self.scene_triangle(j))
            },
        );
        s.stack = stack;
        s.node_cache = cache;
        Ok(best)
    }

    /// Every posed coordinate is at most `|t| + reach` in size: that must
    /// stay far below `f64::MAX` (no bound, box or sum overflows).
    fn check_range(&self, pose: &Pose) -> Result<(), QueryError> {
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

    fn collides_with(&self, pose: Pose, s: &mut Scratch) -> Result<bool, QueryError> {
        self.check_range(&pose)?;
        s.at.start(self.body.vertices.len());
        self.fit_node_cache(s);
        Ok(self.surfaces_meet_lazily(pose, s) || self.one_inside_the_other(pose, s)?)
    }

    fn fit_node_cache(&self, s: &mut Scratch) {
        let n = self.body.tree.bounds().len();
        if s.node_cache.len() != n || s.at.epoch == 1 {
            s.node_cache = vec![std::cell::Cell::new((0, Aabb::EMPTY)); n];
        }
    }

    /// The rounding bound of posing the body at `pose` (module docs).
    fn pad(&self, pose: &Pose) -> f64 {
        64.0 * f64::EPSILON * (self.body.reach + pose.translation.abs().max_element())
    }

    /// Whether some body triangle at `pose` meets some scene triangle: the
    /// body's tree is walked with its body-frame boxes carried to the pose
    /// (each grown by a bound on the rounding of the points it holds, so
    /// no touching pair is dropped), and only the corners of the triangles
    /// reached are posed.
    fn surfaces_meet_lazily(&self, pose: Pose, s: &mut Scratch) -> bool {
        let m = pose.rotation.matrix();
        let t = pose.translation;
        let size = self.body.reach + t.abs().max_element();
        let pad = self.pad(&pose);
        // The scene's boxes carried back into the body's frame: `Mᵀ` undoes
        // `M` up to its distance from a rotation (at most 2⁻⁴⁷ an entry
        // after snapping), far inside `2⁻⁴⁰` of the sizes involved.
        let (mi, ti) = (m.transpose(), -(m.transpose() * t));
        let back_pad = size * (1.0 / (1u64 << 40) as f64);
        // Carrying a scene box back also rounds in the box's own
        // coordinates (its centre and half-size, then the sums): grow it by
        // a bound on that too, taken once for the whole scene (its box's
        // largest coordinate bounds every box's).
        let root = self.scene.tree.root();
        let mag = root
            .lo
            .iter()
            .chain(root.hi.iter())
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let back_pad = back_pad + 16.0 * f64::EPSILON * (2.0 * mag + t.abs().max_element());
        let back = |o: &Aabb| o.transformed(&mi, ti, back_pad);
        let (bounds, boxes) = (self.body.tree.bounds(), self.body.tree.boxes());
        // A pair of nodes or of triangles is kept only when their boxes meet
        // both in the world and in the body's frame (the six face axes of a
        // separating-axis test); the body's node boxes at the pose are
        // computed once per query.
        let meets = |own: &Aabb, other: &Aabb| {
            own.transformed(&m, t, pad).within(other, 0.0) && back(other).within(own, 0.0)
        };
        let cache = std::mem::take(&mut s.node_cache);
        let epoch = s.at.epoch;
        let world = |n: usize| cached(&cache, epoch, n, || bounds[n].transformed(&m, t, pad));
        let scene = &self.scene.tree;
        let mut stack = std::mem::take(&mut s.stack);
        let hit = self.body.tree.for_each_pair(
            |n, o| world(n).within(o, 0.0) && back(o).within(&bounds[n], 0.0),
            |n| bounds[n].size(),
            |i, o| meets(&boxes[i], o),
            scene,
            scene.boxes(),
            scene.bounds(),
            &mut stack,
            |i, j| {
                let tri = self.body.triangles[i].map(|v| s.at.get(&self.body.vertices, &pose, v));
                triangles_meet(&tri, &self.scene_triangle(j))
            },
        );
        s.stack = stack;
        s.node_cache = cache;
        hit
    }

    /// The posed vertices, triangle boxes and tree bounds of the body.
    fn pose_body(&self, pose: Pose, s: &mut Scratch) -> Result<(), QueryError> {
        self.pose_into(pose, &mut s.posed)?;
        triangle_boxes_into(&s.posed, &self.body.triangles, &mut s.boxes);
        self.body.tree.refit(&s.boxes, &mut s.bounds);
        Ok(())
    }

    /// The body's vertices at `pose`.
    fn pose_into(&self, pose: Pose, out: &mut Vec<DVec3>) -> Result<(), QueryError> {
        out.clear();
        out.extend(self.body.vertices.iter().map(|&p| pose.apply(p)));
        match out.iter().position(|p| !p.is_finite()) {
            Some(v) => Err(QueryError::OutOfRange(format!(
                "the body's vertex {v} at the pose is not finite"
            ))),
            None => Ok(()),
        }
    }

    fn scene_triangle(&self, j: usize) -> [DVec3; 3] {
        self.scene.triangles[j].map(|v| self.scene.vertices[v as usize])
    }

    /// A body component inside a scene solid, or a scene component inside
    /// a body solid (when no triangles meet; module docs).
    fn one_inside_the_other(&self, pose: Pose, s: &mut Scratch) -> Result<bool, QueryError> {
        let mut parity = std::mem::take(&mut s.parity);
        let out = self.inside_either(pose, s, &mut parity);
        s.parity = parity;
        out
    }

    fn inside_either(
        &self,
        pose: Pose,
        s: &mut Scratch,
        parity: &mut Vec<u8>,
    ) -> Result<bool, QueryError> {
        if !self.scene.solid_components.is_empty() {
            for &(_, v) in &self.body.components {
                let p = s.at.get(&self.body.vertices, &pose, v);
                if self.scene.inside_solid(p, parity)? {
                    return Ok(true);
                }
            }
        }
        if self.body.solid_components.is_empty() {
            return Ok(false);
        }
        // The scene components with a corner in the body's box at the pose.
        let m = pose.rotation.matrix();
        let pad = 64.0 * f64::EPSILON * (self.body.reach + pose.translation.abs().max_element());
        let reach = self.body.tree.root().transformed(&m, pose.translation, pad);
        let mut corners = Vec::new();
        self.scene_corners
            .for_each_meeting(&reach, |k| corners.push(k));
        if corners.is_empty() {
            return Ok(false);
        }
        // Pose the whole body once: its triangle, node and component boxes.
        self.pose_body(pose, s)?;
        s.component_boxes.clear();
        s.component_boxes
            .resize(self.body.components.len(), Aabb::EMPTY);
        for (t, b) in s.boxes.iter().enumerate() {
            let c = self.body.component_of[t] as usize;
            s.component_boxes[c] = s.component_boxes[c].join(b);
        }
        let mut candidates = Vec::new();
        for k in corners {
            let p = self.scene.vertices[self.scene.components[k].1 as usize];
            candidates.clear();
            candidates.extend(
                self.body
                    .solid_components
                    .iter()
                    .filter(|&&c| s.component_boxes[c as usize].holds(p.to_array())),
            );
            if inside_solid(
                &self.body,
                &s.posed,
                &s.boxes,
                &s.bounds,
                &s.component_boxes,
                &candidates,
                p,
                parity,
            )? {
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// The twelve points of body triangle `i`'s swept hull (module docs):
    /// its corners posed at both ends, and each moved by the other end's
    /// translation.
    fn swept_points(&self, s: &mut Scratch, i: usize, from: &Pose, to: &Pose) -> [DVec3; 12] {
        let shift = to.translation - from.translation;
        let t = self.body.triangles[i];
        let a = t.map(|v| s.at.get(&self.body.vertices, from, v));
        let b = t.map(|v| s.at_b.get(&self.body.vertices, to, v));
        std::array::from_fn(|k| match k / 3 {
            0 => a[k % 3],
            1 => b[k % 3],
            2 => a[k % 3] + shift,
            _ => b[k % 3] - shift,
        })
    }

    /// Whether swept hull `i` comes within `reach` of scene triangle `j`
    /// (not certified apart).
    fn swept_near(
        &self,
        s: &mut Scratch,
        i: usize,
        j: usize,
        from: &Pose,
        to: &Pose,
        reach: f64,
    ) -> bool {
        let hull = self.swept_points(s, i, from, to);
        // The hull's exact box first: more than `reach` from the scene
        // triangle's box on an axis is apart (the tree's boxes, carried
        // from the body's frame, are looser for thin slanted triangles).
        let (lo, hi) = hull[1..]
            .iter()
            .fold((hull[0], hull[0]), |(l, h), p| (l.min(*p), h.max(*p)));
        let own = Aabb {
            lo: lo.to_array(),
            hi: hi.to_array(),
        };
        if !own.within(&self.scene.tree.boxes()[j], reach) {
            return false;
        }
        let ends = [[hull[0], hull[1], hull[2]], [hull[3], hull[4], hull[5]]];
        !apart_by_more_than(&hull, &ends, &self.scene_triangle(j), reach)
    }

    /// Whether no swept hull of a body triangle over `[from, to]` (poses
    /// at the interval's ends) comes within `reach` of a scene triangle,
    /// certified (module docs); `false` means "not proved". The body's
    /// tree is walked with each node's box carried to both poses, joined
    /// with both moved by the other end's translation (which holds the
    /// swept hulls of its triangles), computed once per interval for the
    /// nodes reached; only the corners of the triangles reached are posed.
    fn certified_apart(&self, from: Pose, to: Pose, reach: f64, s: &mut Scratch) -> bool {
        let n = self.body.vertices.len();
        s.at.start(n);
        s.at_b.start(n);
        self.fit_node_cache(s);
        if let Some((i, j)) = s.blocker {
            if self.swept_near(s, i, j, &from, &to, reach) {
                return false;
            }
        }
        let (ma, ta, mb, tb) = (
            from.rotation.matrix(),
            from.translation,
            to.rotation.matrix(),
            to.translation,
        );
        let pad = self.pad(&from).max(self.pad(&to));
        let shift = tb - ta;
        let swept = |b: &Aabb| {
            let (a, z) = (b.transformed(&ma, ta, pad), b.transformed(&mb, tb, pad));
            a.join(&z)
                .join(&shifted(&a, shift))
                .join(&shifted(&z, -shift))
        };
        let (bounds, boxes) = (self.body.tree.bounds(), self.body.tree.boxes());
        let cache = std::mem::take(&mut s.node_cache);
        let epoch = s.at.epoch;
        let scene = &self.scene.tree;
        let mut stack = std::mem::take(&mut s.stack);
        let mut blocker = None;
        let blocked = self.body.tree.for_each_pair(
            |k, o| cached(&cache, epoch, k, || swept(&bounds[k])).within(o, reach),
            |k| bounds[k].size(),
            |i, o| swept(&boxes[i]).within(o, reach),
            scene,
            scene.boxes(),
            scene.bounds(),
            &mut stack,
            |i, j| {
                let near = self.swept_near(s, i, j, &from, &to, reach);
                if near {
                    blocker = Some((i, j));
                }
                near
            },
        );
        s.stack = stack;
        s.node_cache = cache;
        if blocked {
            s.blocker = blocker;
        }
        !blocked
    }

    /// Checks the straight motion from `from` to `to` (module docs) with
    /// the bracket no wider than `tolerance` (in `t`).
    ///
    /// # Errors
    /// [`MotionError::Tolerance`] for a tolerance outside
    /// `[MIN_TOLERANCE, 1)`; [`MotionError::Query`] when a posed coordinate
    /// is not finite; [`MotionError::Undecided`] for a grazing motion;
    /// [`MotionError::BudgetExhausted`] past the budget.
    pub fn check(&self, from: Pose, to: Pose, tolerance: f64) -> Result<MotionCheck, MotionError> {
        if !(MIN_TOLERANCE..1.0).contains(&tolerance) {
            return Err(MotionError::Tolerance(tolerance));
        }
        let mut s = self.scratch();
        let out = self.search(from, to, tolerance, &mut s);
        self.give_back(s);
        out
    }

    fn search(
        &self,
        from: Pose,
        to: Pose,
        tolerance: f64,
        s: &mut Scratch,
    ) -> Result<MotionCheck, MotionError> {
        self.check_range(&to)?;
        if self.collides_with(from, s)? {
            return Ok(MotionCheck::Collides {
                t_safe: None,
                t_contact: 0.0,
            });
        }
        let motion = Motion::new(from, to);
        let r = self.body.reach;
        // The float angle is within ANGLE_ROUNDING of the exact one, and
        // every posed and swept point within `margin` of the exact motion's
        // (`query::rounding`): a few ulps of the coordinates.
        let angle = (motion.angle() + ANGLE_ROUNDING) * (1.0 + 1e-12);
        let margin = pose_rounding_bound(r, motion.translation_extent());
        let mut intervals = std::mem::take(&mut s.intervals);
        intervals.clear();
        intervals.push((0.0, 1.0));
        let mut steps = 0u64;
        let mut known_free_end = f64::NAN;
        let mut probed_from = f64::NAN;
        let out = loop {
            let Some((a, b)) = intervals.pop() else {
                break Ok(MotionCheck::Free);
            };
            if steps == self.budget {
                break Err(MotionError::BudgetExhausted {
                    t_safe: a,
                    steps: self.budget,
                });
            }
            steps += 1;
            let w = b - a;
            let mid = a + w / 2.0;
            // The sagitta r (1 - cos(δ/2)) = 2 r sin²(δ/4), rounded up.
            let quarter = (angle * w / 4.0).min(std::f64::consts::FRAC_PI_2);
            let sagitta = 2.0 * r * quarter.sin().powi(2) * (1.0 + 1e-12);
            let reach = sagitta + margin;
            if self.certified_apart(motion.at(a), motion.at(b), reach, s) {
                continue;
            }
            if w <= tolerance && b != known_free_end {
                match self.collides_with(motion.at(b), s) {
                    Ok(true) => {
                        break Ok(MotionCheck::Collides {
                            t_safe: Some(a),
                            t_contact: b,
                        })
                    }
                    Ok(false) => known_free_end = b,
                    Err(e) => break Err(e.into()),
                }
            }
            // Halving keeps ending just before a contact (the body within
            // the rounding margin of an obstacle it is about to enter):
            // `[0, a]` is certified, so a contact at any later time within
            // the tolerance is a valid bracket. Probed once per `a`.
            if w * 1024.0 < tolerance && a != probed_from {
                probed_from = a;
                match self.probe_after(&motion, a, tolerance, s) {
                    Ok(Some(t)) => {
                        break Ok(MotionCheck::Collides {
                            t_safe: Some(a),
                            t_contact: t,
                        })
                    }
                    Ok(None) => {}
                    Err(e) => break Err(e.into()),
                }
            }
            if w < MIN_WIDTH {
                break Err(MotionError::Undecided { t_safe: a, t: b });
            }
            intervals.push((mid, b));
            intervals.push((a, mid));
        };
        s.intervals = intervals;
        self.steps.fetch_add(steps, Ordering::Relaxed);
        out
    }

    /// The first of `a + tolerance / 2^k` (`k` = 7 down to 0, at most 1) at
    /// which the body collides, if any.
    fn probe_after(
        &self,
        motion: &Motion,
        a: f64,
        tolerance: f64,
        s: &mut Scratch,
    ) -> Result<Option<f64>, QueryError> {
        for k in (0..8).rev() {
            let t = (a + tolerance / f64::from(1u32 << k)).min(1.0);
            if t - a > tolerance {
                continue; // rounded past the tolerance
            }
            if self.collides_with(motion.at(t), s)? {
                return Ok(Some(t));
            }
        }
        Ok(None)
    }

    /// [`SceneChecker::check`] for many motions `(from, to)`, in parallel,
    /// in order.
    ///
    /// # Errors
    /// The first error of [`SceneChecker::check`].
    pub fn check_many(
        &self,
        motions: &[(Pose, Pose)],
        tolerance: f64,
    ) -> Result<Vec<MotionCheck>, MotionError> {
        use rayon::prelude::*;
        motions
            .par_iter()
            .map(|&(a, b)| self.check(a, b, tolerance))
            .collect()
    }
}
