//! Exact state checks of a [`SceneChecker`]: the body's tree walked at the
//! pose against the scene's, the exact triangle test, then containment by
//! the winding number (the contact rule in `scene::checker`'s docs).

use super::checker::{cached, SceneChecker, Scratch};

use super::inside::inside_solid;
use crate::kernel::rotation::Pose;
use crate::query::error::QueryError;
use crate::solid::aabb::Aabb;
use crate::solid::intersect::triangles_meet;

impl SceneChecker {
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

    pub(super) fn collides_with(&self, pose: Pose, s: &mut Scratch) -> Result<bool, QueryError> {
        self.check_range(&pose)?;
        s.at.start(self.body.vertices.len());
        self.fit_node_cache(s);
        Ok(self.surfaces_meet_lazily(pose, s) || self.one_inside_the_other(pose, s)?)
    }

    /// Whether some body triangle at `pose` meets some scene triangle: the
    /// body's tree is walked with its body-frame boxes carried to the pose
    /// (each grown by a bound on the rounding of the points it holds, so
    /// no touching pair is dropped), and only the corners of the triangles
    /// reached are posed.
    pub(super) fn surfaces_meet_lazily(&self, pose: Pose, s: &mut Scratch) -> bool {
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

    /// A body component inside a scene solid, or a scene component inside
    /// a body solid (when no triangles meet; module docs).
    pub(super) fn one_inside_the_other(
        &self,
        pose: Pose,
        s: &mut Scratch,
    ) -> Result<bool, QueryError> {
        let mut parity = std::mem::take(&mut s.parity);
        let out = self.inside_either(pose, s, &mut parity);
        s.parity = parity;
        out
    }

    pub(super) fn inside_either(
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
}
