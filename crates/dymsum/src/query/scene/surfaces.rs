//! Whether two meshes at their poses touch as *surfaces*
//! ([`surfaces_touch`]): some triangle of one meets some triangle of the
//! other, as FCL's mesh–mesh `collide` answers, decided exactly on the
//! posed vertices as computed (`R p + t` rounded once per coordinate). The
//! broad phase is a box tree over one mesh's posed triangles (exact `f64`
//! bounds, closed boxes, so a touching pair is never culled); the narrow
//! phase the exact closed triangle–triangle test of
//! [`crate::solid::intersect`]. Containment is not reported here (that is
//! the scene checker's).

use crate::kernel::rotation::Pose;
use crate::mesh::PolygonMesh;
use crate::query::error::QueryError;
use crate::solid::aabb::{Aabb, AabbTree};
use crate::solid::intersect::triangles_meet;
use glam::DVec3;

/// Whether mesh `a` at `pose_a` and mesh `b` at `pose_b` touch or overlap
/// as surfaces: some (fan) triangle of one meets some triangle of the
/// other, closed sets, decided exactly (module docs).
///
/// ```
/// use dymsum::query::surfaces_touch;
/// use dymsum::{DVec3, PolygonMesh, Pose, Rotation};
/// // Two unit squares (open surfaces): touching along an edge, then 1e-300 apart.
/// let square = PolygonMesh::new(
///     vec![[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]],
///     vec![vec![0, 1, 2, 3]],
/// );
/// let turned = Rotation::from_axis_angle(DVec3::Y, std::f64::consts::FRAC_PI_2).unwrap();
/// let at = |x: f64| Pose::new(turned, DVec3::new(x, 0.0, 0.0));
/// assert!(surfaces_touch(&square, Pose::IDENTITY, &square, at(1.0))?);
/// assert!(!surfaces_touch(&square, Pose::IDENTITY, &square, at(1.0 + 1e-15))?);
/// # Ok::<(), dymsum::QueryError>(())
/// ```
///
/// # Errors
/// [`QueryError::OutOfRange`] when a posed coordinate is not finite, or a
/// face has fewer than three corners or names a vertex out of range.
pub fn surfaces_touch(
    a: &PolygonMesh,
    pose_a: Pose,
    b: &PolygonMesh,
    pose_b: Pose,
) -> Result<bool, QueryError> {
    let ta = posed_triangles(a, pose_a, "A")?;
    let tb = posed_triangles(b, pose_b, "B")?;
    // The tree over the larger set, the smaller one queried.
    let (tree_tris, query_tris) = if ta.len() >= tb.len() {
        (&ta, &tb)
    } else {
        (&tb, &ta)
    };
    let boxes: Vec<Aabb> = tree_tris.iter().map(triangle_box).collect();
    let tree = AabbTree::new(&boxes);
    let mut touch = false;
    for t in query_tris {
        if touch {
            break;
        }
        tree.for_each_meeting(&triangle_box(t), |k| {
            if !touch && triangles_meet(t, &tree_tris[k]) {
                touch = true;
            }
        });
    }
    Ok(touch)
}

/// The fan triangles of `mesh` at `pose`.
fn posed_triangles(
    mesh: &PolygonMesh,
    pose: Pose,
    which: &str,
) -> Result<Vec<[DVec3; 3]>, QueryError> {
    let posed: Vec<DVec3> = mesh
        .vertices
        .iter()
        .map(|&p| pose.apply(DVec3::from(p)))
        .collect();
    if let Some(v) = posed.iter().position(|p| !p.is_finite()) {
        return Err(QueryError::OutOfRange(format!(
            "mesh {which}: posed vertex {v} is not finite"
        )));
    }
    let mut out = Vec::new();
    for (face, f) in mesh.faces.iter().enumerate() {
        if f.len() < 3 || f.iter().any(|&v| v >= posed.len()) {
            return Err(QueryError::OutOfRange(format!(
                "mesh {which}: face {face} has fewer than three corners or names a vertex out \
                 of range"
            )));
        }
        for w in f[1..].windows(2) {
            out.push([posed[f[0]], posed[w[0]], posed[w[1]]]);
        }
    }
    Ok(out)
}

fn triangle_box(t: &[DVec3; 3]) -> Aabb {
    Aabb::of(t.iter().map(|p| p.to_array()))
}
