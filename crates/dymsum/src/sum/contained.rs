//! Which convex meshes lie inside another: the culling rule of non-convex
//! sums (a piece-pair sum inside another adds nothing to their union), one
//! implementation for Rust's `nonconvex` and Python's `dymsum.nonconvex`.
//!
//! A convex mesh lies inside an outward convex mesh when every one of its
//! vertices lies strictly on the inner side of every face plane of the
//! other, decided by exact `orient3d` on the float coordinates (so no
//! tolerance: a sum touching the other's boundary is kept). Bounding boxes
//! filter first; larger boxes are kept first, so of two equal sums the
//! earlier is kept.

use crate::mesh::PolygonMesh;
use glam::DVec3;

/// The indices, in order, of the convex meshes to keep: every mesh not
/// certified inside a kept one (module docs).
///
/// ```
/// use dymsum::sum::contained::uncontained;
/// use dymsum::PolygonMesh;
/// let cube = |lo: f64, hi: f64| -> PolygonMesh {
///     let p = dymsum::Polytope::from_points(
///         &(0..8).map(|i| std::array::from_fn(|k| if i >> k & 1 == 0 { lo } else { hi })).collect::<Vec<[f64; 3]>>(),
///     ).unwrap();
///     p.to_mesh()
/// };
/// let (big, small, touching) = (cube(0.0, 4.0), cube(1.0, 2.0), cube(0.0, 1.0));
/// assert_eq!(uncontained(&[&small, &big, &touching]), vec![1, 2]);
/// ```
pub fn uncontained(meshes: &[&PolygonMesh]) -> Vec<usize> {
    let boxes: Vec<(DVec3, DVec3)> = meshes.iter().map(|m| bbox(m)).collect();
    let mut order: Vec<usize> = (0..meshes.len()).collect();
    let size = |k: usize| (boxes[k].1 - boxes[k].0).element_product();
    order.sort_by(|&x, &y| size(y).total_cmp(&size(x)).then(x.cmp(&y)));
    let mut kept: Vec<usize> = Vec::new();
    for &k in &order {
        let (lo, hi) = boxes[k];
        let inside = kept.iter().any(|&o| {
            let (olo, ohi) = boxes[o];
            lo.cmpge(olo).all() && hi.cmple(ohi).all() && strictly_inside(meshes[k], meshes[o])
        });
        if !inside {
            kept.push(k);
        }
    }
    kept.sort_unstable();
    kept
}

/// Bounding box of a mesh's vertices.
fn bbox(m: &PolygonMesh) -> (DVec3, DVec3) {
    m.vertices.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(DVec3::from(p)), hi.max(DVec3::from(p))),
    )
}

/// Every vertex of `inner` strictly on the inner side of every face plane
/// of the outward mesh `outer` (exact predicates).
pub fn strictly_inside(inner: &PolygonMesh, outer: &PolygonMesh) -> bool {
    use crate::kernel::predicates::coord3d;
    let at = |p: [f64; 3]| coord3d(DVec3::from(p));
    outer.faces.iter().all(|f| {
        f[1..].windows(2).all(|w| {
            let (a, b, d) = (
                outer.vertices[f[0]],
                outer.vertices[w[0]],
                outer.vertices[w[1]],
            );
            inner
                .vertices
                .iter()
                .all(|&p| robust::orient3d(at(a), at(b), at(d), at(p)) > 0.0)
        })
    })
}
