//! The clearance of a [`SceneChecker`]'s body at a pose: a certified lower
//! bound within rounding of the distance (best-first over both trees).

use super::checker::{cached, cells, SceneChecker, Scratch};

use super::gap::distance_lower_bound_beyond;
use crate::kernel::rotation::Pose;
use crate::query::error::QueryError;
use crate::solid::obb::pose_skew;

impl SceneChecker {
    /// The clearance of the body at `pose` from the scene: `0` when they
    /// collide ([`SceneChecker::collides_at`]), else the least distance
    /// between a body triangle and a scene triangle, rounded down: a
    /// certified lower bound within rounding of it (each pair's bound is
    /// the gap along the direction of its closest points found in floating
    /// point, `query::scene::gap`; the broad phase skips only pairs whose boxes
    /// are farther apart than the best so far). For clearance objectives.
    /// The walk runs first: when its bound is positive no triangles meet,
    /// so only containment is left to test (the state check's triangle
    /// walk would repeat the work).
    ///
    /// # Errors
    /// Those of [`SceneChecker::collides_at`].
    pub fn distance_at(&self, pose: Pose) -> Result<f64, QueryError> {
        let mut s = self.scratch();
        let out = self.clearance(pose, &mut s);
        self.give_back(s);
        out
    }

    pub(super) fn clearance(&self, pose: Pose, s: &mut Scratch) -> Result<f64, QueryError> {
        self.check_range(&pose)?;
        s.at.start(self.body.vertices.len());
        self.fit_node_cache(s);
        let (m, t, pad) = (pose.rotation.matrix(), pose.translation, self.pad(&pose));
        let bounds = self.body.tree().bounds();
        let mut cache = std::mem::take(&mut s.node_cache);
        let cache_cells = cells(&mut cache);
        let epoch = s.at.epoch;
        let mut near = std::mem::take(&mut s.near);
        // Each body triangle posed once (corners and exact box): the exact
        // box of the posed corners bounds the pair's distance from below
        // more tightly than the carried box of a slanted triangle.
        let lazy = std::cell::RefCell::new((&mut s.at, &mut s.tris));
        let posed = |i: usize| {
            let (at, tris) = &mut *lazy.borrow_mut();
            tris.get(at, &self.body, &pose, i)
        };
        // The oriented boxes' certified gap (`solid::obb`), when the
        // pose's matrix is close enough to a rotation for their test: a
        // slanted node's axis-aligned box is mostly empty, and its
        // distance bounds little.
        let oriented = pose_skew(&m).is_some();
        let mut obb_cache = std::mem::take(&mut s.obb_cache);
        let obb_cache_cells = cells(&mut obb_cache);
        let (body_obbs, scene_obbs) = (self.body.obbs(), self.scene.obbs());
        let obb_gap = |n: usize, k: usize| {
            if !oriented {
                return 0.0;
            }
            let a = &body_obbs[n];
            let posed = cached(obb_cache_cells, epoch, n, || a.posed(&m, t));
            scene_obbs[k].gap(&posed, a.h, a.fuzz, pad)
        };
        let best = self.body.tree().nearest_pair(
            |n| cached(cache_cells, epoch, n, || bounds[n].transformed(&m, t, pad)),
            |i| posed(i).1,
            obb_gap,
            self.scene.tree(),
            &mut near,
            |i, j, best| distance_lower_bound_beyond(&posed(i).0, &self.scene_triangle(j), best),
        );
        s.near = near;
        s.node_cache = cache;
        s.obb_cache = obb_cache;
        // A positive bound proves every triangle pair apart (each pair was
        // bounded, or dropped by a bound at least as large): no surfaces
        // meet, and the bodies collide only when one holds the other. A
        // zero bound is the answer whether or not they touch.
        if best > 0.0 && self.one_inside_the_other(pose, s, 0..usize::MAX)? {
            return Ok(0.0);
        }
        Ok(best)
    }
}
