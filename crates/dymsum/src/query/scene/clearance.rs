//! The clearance of a [`SceneChecker`]'s body at a pose: a certified lower
//! bound within rounding of the distance (best-first over both trees).

use super::checker::{cached, SceneChecker, Scratch};

use super::gap::distance_lower_bound;
use crate::kernel::rotation::Pose;
use crate::query::error::QueryError;

impl SceneChecker {
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

    pub(super) fn clearance(&self, pose: Pose, s: &mut Scratch) -> Result<f64, QueryError> {
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
}
