//! Exact 3-D convex hulls.
//!
//! [`convex_hull`] computes the convex hull of a finite point set as its
//! corner vertices and its *maximal* faces: polygons, counter-clockwise seen
//! from outside, with exactly coplanar neighbours merged and points in the
//! middle of an edge or face left out. It is generic over [`HullPoints`], so
//! the same code builds the hull of plain float points ([`FloatPoints`]) and
//! of the `m·n` pairwise vertex sums of two polytopes ([`PairwiseSums`], the
//! brute-force Minkowski sum), whose float coordinates are rounded but whose
//! predicates are exact for the real sums.
//!
//! # Algorithm
//!
//! Quickhull (Barber, Dobkin and Huhdanpaa, 1996) with conflict lists, where
//! every decision is an exact predicate and floats only steer heuristics:
//!
//! 1. **Initial simplex.** Two points far apart (float extremes), a third
//!    far from their line, a fourth far from their plane; each choice is
//!    confirmed exactly ([`HullPoints::coincident`],
//!    [`HullPoints::collinear`], [`HullPoints::orient`]) and, if the float
//!    choice fails, replaced by an exact scan over all points. A failed scan
//!    is the error: all points coincident, collinear or coplanar.
//! 2. **Outside sets.** Every other point goes to the first simplex triangle
//!    it sees *strictly* (`orient == Positive`); points seeing none are
//!    inside or on the hull and are dropped for good.
//! 3. **Insertion.** While some triangle has an outside set, its point
//!    furthest from the triangle's float plane (the *eye*) is inserted: the
//!    triangles it sees strictly are found by a search over neighbours from
//!    that triangle (they form a disk), deleted, and replaced by a cone of
//!    triangles from the horizon edges to the eye. The outside points of the
//!    deleted triangles are re-assigned to the new triangles only; a point
//!    strictly outside the new hull always strictly sees a new triangle
//!    (along any path of faces it sees, from a deleted to a kept one, it sees
//!    both triangles at a horizon edge and therefore the new one there).
//! 4. **Output.** Adjacent triangles whose planes coincide exactly (the
//!    neighbour's far vertex has `orient == Zero`) are merged with a
//!    union-find; each merged region is a convex polygon whose boundary
//!    edges form one simple cycle. A vertex is a corner, and is kept, if at
//!    least three merged faces meet there; this removes points in the middle
//!    of an edge (two faces) and in the interior of a face (one).
//!
//! # Degeneracies
//!
//! Duplicated points, points on faces and edges, and huge numbers of exactly
//! coplanar and collinear points (tessellated boxes, parallelogram faces of
//! Minkowski sums) are handled exactly: strict visibility never creates a
//! flat triangle (the eye is strictly off the plane of every triangle it
//! replaces an edge of), and coplanar triangles are merged only at output.
//!
//! # Complexity
//!
//! `O(n log n)` expected for typical inputs (`O(n·h)` worst case for `h`
//! hull triangles), `O(n)` extra memory in flat arrays, no allocation per
//! point. Results are deterministic (no randomisation): faces start at their
//! smallest index and are sorted. Exact predicates cost a float filter in
//! the common case and fall back to exact arithmetic only near degeneracies.

use crate::kernel::Sign;
use glam::DVec3;

mod error;
mod points;
mod quickhull;

pub use error::HullError;
pub use points::{FloatPoints, PairwiseSums};
pub use quickhull::convex_hull;

/// A point set the hull can be built over: float coordinates for heuristics
/// and constructions, and an *exact* orientation predicate for decisions.
pub trait HullPoints {
    /// Number of points.
    fn len(&self) -> usize;
    /// `true` if there are no points.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Float coordinates of point `i` (used for heuristics only).
    fn coords(&self, i: usize) -> DVec3;
    /// Exact sign of `det[b − a, c − a, d − a]` for points with these indices:
    /// `Positive` when `d` is above the plane through `a, b, c` (the side from
    /// which `a, b, c` appear counter-clockwise).
    fn orient(&self, a: usize, b: usize, c: usize, d: usize) -> Sign;
    /// Exactly whether points `a` and `b` are the same point.
    ///
    /// The provided implementation compares [`HullPoints::coords`], which is
    /// exact when the coordinates *are* the points; implementations whose
    /// coordinates are rounded (such as [`PairwiseSums`]) override it.
    fn coincident(&self, a: usize, b: usize) -> bool {
        self.coords(a) == self.coords(b)
    }
    /// Exactly whether points `a`, `b`, `c` lie on one line (also `true`
    /// when two of them coincide).
    ///
    /// The provided implementation evaluates the three components of
    /// `(b − a) × (c − a)` exactly on [`HullPoints::coords`] (the 2-D
    /// orientations of the projections on the coordinate planes); like
    /// [`HullPoints::coincident`] it must be overridden when the coordinates
    /// are rounded.
    fn collinear(&self, a: usize, b: usize, c: usize) -> bool {
        points::collinear_floats(self.coords(a), self.coords(b), self.coords(c))
    }
}

/// A convex hull with maximal faces.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexHull {
    /// Indices of the points that are hull vertices (corners), ascending.
    pub vertices: Vec<usize>,
    /// Maximal faces: counter-clockwise seen from outside, coplanar neighbours
    /// merged, points in the middle of an edge or face left out.
    pub faces: Vec<Vec<usize>>,
}

impl ConvexHull {
    /// The hull as a polygon mesh over its corners only (re-indexed), with
    /// the points' float coordinates.
    ///
    /// ```
    /// use dymsum::hull::{convex_hull, FloatPoints};
    /// use dymsum::DVec3;
    /// let pts: Vec<DVec3> = (0..9).map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64 * 0.5 + (i / 8) as f64 * 0.25)).collect();
    /// let mesh = convex_hull(&FloatPoints(&pts)).unwrap().to_mesh(&FloatPoints(&pts));
    /// assert_eq!((mesh.vertices.len(), mesh.faces.len()), (8, 6)); // the inner point is dropped
    /// ```
    pub fn to_mesh<P: HullPoints + ?Sized>(&self, points: &P) -> crate::mesh::PolygonMesh {
        let mut index = std::collections::HashMap::with_capacity(self.vertices.len());
        let vertices = self
            .vertices
            .iter()
            .enumerate()
            .map(|(k, &i)| {
                index.insert(i, k);
                points.coords(i).to_array()
            })
            .collect();
        let faces = self
            .faces
            .iter()
            .map(|f| f.iter().map(|i| index[i]).collect())
            .collect();
        crate::mesh::PolygonMesh { vertices, faces }
    }
}

/// `n` points on the unit sphere in a Fibonacci spiral (generic: no four on
/// a circle), for tests.
#[cfg(test)]
pub(crate) fn fibonacci_sphere(n: usize) -> Vec<DVec3> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - y * y).sqrt();
            let t = golden * i as f64;
            DVec3::new(r * t.cos(), y, r * t.sin())
        })
        .collect()
}
