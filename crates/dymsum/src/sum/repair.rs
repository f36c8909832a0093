//! The merged mesh made exact: [`validated_mesh`] takes the merge of
//! [`super::merge`] and returns it when the exact check
//! ([`super::validate::check_convex_mesh`]) passes; where rounding the
//! vertices to `f64` bent faces or made edges reflex it folds, flips or
//! rebuilds only around the defects (a local exact hull), and only when
//! that fails the exact hull of all rounded vertices. A broken overlay
//! (exact coordinates that fail the check) is an error, never repaired.

use super::merge::{merged_mesh, Merged};
use super::validate::{
    check_convex_faces, check_convex_geometry, check_sphere_faces, corners_test_cheaply,
    edge_is_convex, face_defect, vertex_is_convex, ExactPoints,
};
use super::{Operands, Overlay};
use crate::error::MeshError;
use crate::kernel::Sign;
use crate::mesh::PolygonMesh;
use crate::polytope::topology::DirectedEdges;
use glam::DVec3;

/// How faithfully the output coordinates hold the exact sum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Precision {
    /// The rounding step (ulp) of the largest output coordinate.
    pub ulp: f64,
    /// The size of the sum (sum of the operands' bounding-box diagonals).
    pub size: f64,
}

impl Precision {
    /// Relative rounding above which callers should warn (about eight
    /// significant digits of the size left).
    pub const WARN_RELATIVE: f64 = 1e-8;
    /// `ulp / size` (infinite for a zero size).
    pub fn relative(&self) -> f64 {
        self.ulp / self.size
    }
    /// `true` when [`Self::relative`] exceeds [`Self::WARN_RELATIVE`].
    pub fn is_coarse(&self) -> bool {
        self.relative().is_nan() || self.relative() > Self::WARN_RELATIVE
    }
}

impl std::fmt::Display for Precision {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "rounding step {:.3e} relative to size {:.3e} ({:.1e})",
            self.ulp,
            self.size,
            self.relative()
        )
    }
}

/// A validated mesh of a sum.
#[derive(Clone, Debug, PartialEq)]
pub struct SumMesh {
    /// The mesh: closed, oriented, convex, maximal faces, checked exactly.
    pub mesh: PolygonMesh,
    /// The rounding of its coordinates relative to the sum's size.
    pub precision: Precision,
    /// `true` when rounding broke the exact faces and the mesh is the exact
    /// hull of the rounded vertices instead (the merged mesh with its bent
    /// faces folded, or, if that fails the check, a hull from scratch).
    pub hull_fallback: bool,
}

fn ulp(x: f64) -> f64 {
    let a = x.abs();
    if a.is_finite() {
        f64::from_bits(a.to_bits() + 1) - a
    } else {
        f64::INFINITY
    }
}

/// The merged mesh, validated exactly (see [`super::validate`]): the
/// combinatorial merge when its float coordinates are exactly convex, else
/// the exact hull of the rounded vertices.
pub(crate) fn validated_mesh(ops: &Operands, overlay: &Overlay) -> Result<SumMesh, MeshError> {
    let merged = merged_mesh(ops, overlay, true).map_err(MeshError::Merge)?;
    let merged = if merged.shortcut {
        match checked_or_repaired(ops, merged, Attempt::Shortcut)? {
            Some(mesh) => return Ok(mesh),
            // The facets as faces failed the check: merge in full, which
            // also names a broken facet complex.
            None => merged_mesh(ops, overlay, false).map_err(MeshError::Merge)?,
        }
    } else {
        merged
    };
    checked_or_repaired(ops, merged, Attempt::Final)?
        .ok_or_else(|| MeshError::Merge("no mesh and no hull".into()))
}

/// Which try of [`validated_mesh`] a merged mesh is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Attempt {
    /// The facets taken as faces (the shortcut): a mesh failing the check
    /// gives `None`, and the full merge is tried.
    Shortcut,
    /// The full merge: a mesh failing the check is repaired or replaced by
    /// the exact hull of its rounded vertices, and is an error when its
    /// coordinates are exact (a broken overlay).
    Final,
}

/// The merged mesh if it passes the exact check (with its bent faces
/// folded); else, on the [`Attempt::Final`] try, the mesh repaired locally
/// or the exact hull of its rounded vertices; else `None`.
fn checked_or_repaired(
    ops: &Operands,
    merged: Merged,
    attempt: Attempt,
) -> Result<Option<SumMesh>, MeshError> {
    let hull = matches!(attempt, Attempt::Final);
    use super::validate::check_convex_mesh;
    let max = merged
        .mesh
        .vertices
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let precision = Precision {
        ulp: ulp(max),
        // Bounding-box diagonals, computed in each shape's frame (no
        // overflow of squared lengths at large scales).
        size: ops.p.diameter() + ops.q.diameter(),
    };
    if !max.is_finite() {
        return Err(MeshError::OutOfRange);
    }
    let pts: Vec<DVec3> = merged.mesh.vertices.iter().map(|&v| v.into()).collect();
    let points = ExactPoints::new(&pts);
    // Rounded sums usually bend the faces of four or more corners (the
    // parallelograms of edge pairs). Rounding moves each vertex by at most
    // half an ulp, so the exact hull of the rounded vertices is almost
    // always the merged mesh with its bent faces folded: try that first
    // (O(size)), keep it only if it passes the full exact check, else build
    // the hull from scratch.
    let mut faces = merged.mesh.faces;
    let folded = if merged.exact {
        Some(false)
    } else {
        fold_bent_faces(&mut faces, &points)
    };
    if let Some(bent) = folded {
        // The directed-edge index is built once here and reused by the
        // repairs of the same faces.
        let (checked, directed) = match check_sphere_faces(&faces, points.points().len()) {
            Ok(d) => (check_convex_geometry(&faces, &d, &points), Some(d)),
            Err(defect) => (Err(defect), None),
        };
        match checked {
            Ok(()) => {
                return Ok(Some(SumMesh {
                    mesh: PolygonMesh {
                        vertices: merged.mesh.vertices,
                        faces,
                    },
                    precision,
                    hull_fallback: bent,
                }))
            }
            // Exact coordinates cannot bend anything: a failure is a broken
            // overlay, reported (after the full merge, which names it)
            // and never repaired into a plausible mesh.
            Err(defect) if merged.exact => {
                return match hull {
                    true => Err(MeshError::Invalid(defect)),
                    false => Ok(None),
                }
            }
            Err(_) => {
                // Rounding made some neighbouring faces reflex or coplanar,
                // or pushed a vertex inside: rebuild only around those.
                // Flips first (cheap, local); what they leave, a local hull.
                let vertices = &merged.mesh.vertices;
                let local_hull = |faces: &[Vec<usize>], directed: &DirectedEdges| {
                    repair_defects(faces, directed, &points)
                        .and_then(|faces| compact_checked(vertices, &faces, &points))
                };
                // Not a closed sphere (no index): nothing local to repair.
                let repaired = directed.and_then(|directed| {
                    match flip_reflex_edges(faces.clone(), &directed, &points) {
                        Some(flipped) => {
                            compact_checked(vertices, &flipped, &points).or_else(|| {
                                let n = points.points().len();
                                let d = check_sphere_faces(&flipped, n).ok()?;
                                local_hull(&flipped, &d)
                            })
                        }
                        None => local_hull(&faces, &directed),
                    }
                });
                if let Some(mesh) = repaired {
                    return Ok(Some(SumMesh {
                        mesh,
                        precision,
                        hull_fallback: true,
                    }));
                }
            }
        }
    }
    if !hull {
        return Ok(None);
    }
    let hull = crate::hull::convex_hull(&points).map_err(|e| MeshError::PrecisionLost {
        ulp: precision.ulp,
        size: precision.size,
        collapse: match e {
            crate::hull::HullError::AllCoincident { .. } => "coincide".into(),
            crate::hull::HullError::AllCollinear { .. } => "are collinear".into(),
            crate::hull::HullError::AllCoplanar { .. } => "are coplanar (flat)".into(),
            other => other.to_string(),
        },
    })?;
    let mesh = hull.to_mesh(&points);
    check_convex_mesh(&mesh)?;
    Ok(Some(SumMesh {
        mesh,
        precision,
        hull_fallback: true,
    }))
}

/// Replaces, in place, each face whose rounded corners are not coplanar by
/// the outer side of their hull: a quadrilateral is split along the
/// diagonal that folds outward (the same exact `orient3d` that found it
/// bent), a larger face by the faces of its corners' hull that face the
/// same way as the polygon. Extra pieces go to the end of the list.
/// Returns whether any face was bent, or `None` when a bent face's corners
/// have no usable hull. The result is a candidate only:
/// [`super::validate::check_convex_faces`] decides.
fn fold_bent_faces(faces: &mut Vec<Vec<usize>>, points: &ExactPoints) -> Option<bool> {
    let mut bent = false;
    for i in 0..faces.len() {
        let f = &mut faces[i];
        // The sign of the first off-plane corner, if any.
        let Some(sign) = f[3..]
            .iter()
            .map(|&d| points.orient3(f[0], f[1], f[2], d))
            .find(|&s| s != Sign::Zero)
        else {
            continue;
        };
        bent = true;
        if let [a, b, c, d] = f[..] {
            // `d` below the plane of `a, b, c`: the fold along `a c` is
            // convex; above: the fold along `b d` is.
            let other = if sign == Sign::Negative {
                f.truncate(3);
                vec![a, c, d]
            } else {
                f.remove(2);
                f[0..3].copy_from_slice(&[b, c, d]);
                vec![a, b, d]
            };
            faces.push(other);
            continue;
        }
        let mut side = outer_side(f, points)?.into_iter();
        faces[i] = side.next()?;
        faces.extend(side);
    }
    Some(bent)
}

/// A subset of exact points (by index), for local hulls.
struct Corners<'a>(&'a [usize], &'a ExactPoints);

impl crate::hull::HullPoints for Corners<'_> {
    fn len(&self) -> usize {
        self.0.len()
    }
    fn coords(&self, i: usize) -> DVec3 {
        self.1.points()[self.0[i]]
    }
    fn orient(&self, a: usize, b: usize, c: usize, d: usize) -> Sign {
        self.1.orient3(self.0[a], self.0[b], self.0[c], self.0[d])
    }
    fn collinear(&self, a: usize, b: usize, c: usize) -> bool {
        (0..3).all(|axis| self.1.orient2(axis, self.0[a], self.0[b], self.0[c]) == Sign::Zero)
    }
}

/// The faces of the hull of the polygon `face`'s corners whose normals point
/// the polygon's way (float normals: a wrong pick fails the exact check).
fn outer_side(face: &[usize], points: &ExactPoints) -> Option<Vec<Vec<usize>>> {
    // Scaled coordinates: the normals neither underflow nor depend on the
    // scale.
    let pts = points.scaled_points();
    let newell = |f: &mut dyn Iterator<Item = usize>| {
        let ring: Vec<DVec3> = f.map(|i| pts[i]).collect();
        let o = ring[0];
        (1..ring.len())
            .map(|k| (ring[k] - o).cross(ring[(k + 1) % ring.len()] - o))
            .sum::<DVec3>()
    };
    let normal = newell(&mut face.iter().copied());
    let corners = Corners(face, points);
    let hull = crate::hull::convex_hull(&corners).ok()?;
    let outer: Vec<Vec<usize>> = hull
        .faces
        .iter()
        .filter(|h| newell(&mut h.iter().map(|&i| face[i])).dot(normal) > 0.0)
        .map(|h| h.iter().map(|&i| face[i]).collect())
        .collect();
    (!outer.is_empty()).then_some(outer)
}

/// The faces with the region around every defect replaced by the outer side
/// of the hull of the region's corners. A defect is a face that is not a
/// strictly convex planar polygon or an edge that is not strictly convex;
/// the region is the faces at the defects grown by one ring of faces
/// around their corners. The outer side is found from the region's
/// boundary: the hull faces holding its edges (same direction) and all hull
/// faces reached from them without crossing it. `faces` must be a closed
/// sphere with the directed-edge index `directed` ([`check_sphere_faces`]).
/// `None` when the region is the whole mesh (then the caller's hull from
/// scratch is the same work) or the boundary is not on the hull. The
/// result is a candidate only (its corners may have lost vertices pushed
/// inside): [`compact_checked`] decides.
fn repair_defects(
    faces: &[Vec<usize>],
    directed: &DirectedEdges,
    points: &ExactPoints,
) -> Option<Vec<Vec<usize>>> {
    let n = points.points().len();
    // The face across the edge at `pos`, leaving `a`.
    let across = |a: usize, pos: usize| directed.face_of(directed.target[pos], a);
    let cheap_corners = corners_test_cheaply(directed);
    let mut in_region: Vec<bool> = faces
        .iter()
        .enumerate()
        .map(|(fi, f)| face_defect(fi, f, points).is_err())
        .collect();
    for a in 0..n {
        for pos in directed.start[a]..directed.start[a + 1] {
            if directed.target[pos] > a && !edge_is_convex(faces, directed, pos, points) {
                in_region[directed.face_corner(pos).0] = true;
                in_region[across(a, pos)?] = true;
            }
        }
        // A corner whose faces fold around it twice: all of them (where
        // the corners' test is cheap; else the check after the repair
        // finds such a corner and the hull from scratch is built).
        if cheap_corners && !vertex_is_convex(faces, directed, a, points) {
            for pos in directed.start[a]..directed.start[a + 1] {
                in_region[directed.face_corner(pos).0] = true;
            }
        }
    }
    // Grow by the faces around the region's corners.
    let mut corner = vec![false; n];
    for (f, _) in faces.iter().zip(&in_region).filter(|(_, &r)| r) {
        for &v in f {
            corner[v] = true;
        }
    }
    for v in (0..n).filter(|&v| corner[v]) {
        for pos in directed.start[v]..directed.start[v + 1] {
            in_region[directed.face_corner(pos).0] = true;
        }
    }
    let mut sub = Vec::new();
    corner.iter_mut().for_each(|c| *c = false);
    for (f, _) in faces.iter().zip(&in_region).filter(|(_, &r)| r) {
        for &v in f {
            if !corner[v] {
                corner[v] = true;
                sub.push(v);
            }
        }
    }
    let hull = crate::hull::convex_hull(&Corners(&sub, points)).ok()?;
    let hull_faces: Vec<Vec<usize>> = hull
        .faces
        .iter()
        .map(|h| h.iter().map(|&i| sub[i]).collect())
        .collect();
    // The region's boundary, directed as in its faces.
    let mut boundary = Vec::new();
    for a in 0..n {
        for pos in directed.start[a]..directed.start[a + 1] {
            if in_region[directed.face_corner(pos).0] && !in_region[across(a, pos)?] {
                boundary.push((a, directed.target[pos]));
            }
        }
    }
    if boundary.is_empty() {
        // The region is the whole mesh: that is the hull from scratch.
        return None;
    }
    boundary.sort_unstable();
    let hull_edges = DirectedEdges::new(n, &hull_faces);
    let mut top = vec![false; hull_faces.len()];
    let mut stack = Vec::new();
    for &(a, b) in &boundary {
        let h = hull_edges.face_of(a, b)?;
        if !top[h] {
            top[h] = true;
            stack.push(h);
        }
    }
    while let Some(h) = stack.pop() {
        let f = &hull_faces[h];
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            if boundary.binary_search(&(a, b)).is_ok() {
                continue;
            }
            let g = hull_edges.face_of(b, a)?;
            if !top[g] {
                top[g] = true;
                stack.push(g);
            }
        }
    }
    let kept = faces
        .iter()
        .zip(&in_region)
        .filter(|(_, &r)| !r)
        .map(|(f, _)| f.clone());
    let outer = hull_faces
        .into_iter()
        .zip(top)
        .filter(|(_, t)| *t)
        .map(|(f, _)| f);
    Some(kept.chain(outer).collect())
}

/// The mesh of `faces` over the vertices they use (renumbered in order),
/// if it passes the exact check and every vertex it leaves out lies inside
/// or on it (so it is the exact hull of all of `vertices`).
fn compact_checked(
    vertices: &[[f64; 3]],
    faces: &[Vec<usize>],
    points: &ExactPoints,
) -> Option<PolygonMesh> {
    let n = vertices.len();
    let mut new_id = vec![usize::MAX; n];
    for &v in faces.iter().flatten() {
        new_id[v] = 0;
    }
    let mut kept = Vec::with_capacity(n);
    for (v, id) in new_id.iter_mut().enumerate() {
        if *id == 0 {
            *id = kept.len();
            kept.push(v);
        }
    }
    let renumbered: Vec<Vec<usize>> = faces
        .iter()
        .map(|f| f.iter().map(|&v| new_id[v]).collect())
        .collect();
    let compact;
    let ep = if kept.len() == n {
        points
    } else {
        let pts: Vec<DVec3> = kept.iter().map(|&v| points.points()[v]).collect();
        compact = ExactPoints::new(&pts);
        &compact
    };
    check_convex_faces(&renumbered, ep).ok()?;
    for v in (0..n).filter(|&v| new_id[v] == usize::MAX) {
        if faces
            .iter()
            .any(|f| points.orient3(f[0], f[1], f[2], v) == Sign::Positive)
        {
            return None;
        }
    }
    Some(PolygonMesh {
        vertices: kept.iter().map(|&v| vertices[v]).collect(),
        faces: renumbered,
    })
}

/// The faces with every reflex edge between two triangles flipped to the
/// other diagonal of their quadrilateral (which is then convex), and the
/// edges around each flip re-tested, until no such edge is left: the local
/// convexification of a mesh whose vertices rounding moved by an ulp.
/// Other defects (a reflex edge at a polygon, a flat edge, a flip that
/// would duplicate an edge) are left for [`repair_defects`]. `faces` must
/// be a closed sphere with the directed-edge index `directed`
/// ([`check_sphere_faces`]). `None` when flips do not settle. The result
/// is a candidate only: [`compact_checked`] decides.
fn flip_reflex_edges(
    mut faces: Vec<Vec<usize>>,
    directed: &DirectedEdges,
    points: &ExactPoints,
) -> Option<Vec<Vec<usize>>> {
    use std::collections::HashMap;
    let n = points.points().len();
    let mut queue = Vec::new();
    for a in 0..n {
        for pos in directed.start[a]..directed.start[a + 1] {
            let b = directed.target[pos];
            if b > a && !edge_is_convex(&faces, directed, pos, points) {
                queue.push((a, b));
            }
        }
    }
    // Directed edges changed by flips (`None`: removed), over the index.
    let mut changed: HashMap<(usize, usize), Option<usize>> = HashMap::new();
    let face_of =
        |changed: &HashMap<(usize, usize), Option<usize>>, a: usize, b: usize| match changed
            .get(&(a, b))
        {
            Some(&f) => f,
            None => directed.face_of(a, b),
        };
    let mut budget = 8 * queue.len() + 64;
    while let Some((a, b)) = queue.pop() {
        budget = budget.checked_sub(1)?;
        // An edge queued twice may have been flipped away meanwhile.
        let (Some(fi), Some(gi)) = (face_of(&changed, a, b), face_of(&changed, b, a)) else {
            continue;
        };
        let (f, g) = (&faces[fi], &faces[gi]);
        if f.len() != 3 || g.len() != 3 {
            continue;
        }
        // f runs a → b → c, g runs b → a → d.
        let c = f[(f.iter().position(|&v| v == b)? + 1) % 3];
        let d = g[(g.iter().position(|&v| v == a)? + 1) % 3];
        if points.orient3(a, b, c, d) != Sign::Positive
            || c == d
            || face_of(&changed, c, d).is_some()
            || face_of(&changed, d, c).is_some()
        {
            continue;
        }
        faces[fi] = vec![a, d, c];
        faces[gi] = vec![d, b, c];
        changed.insert((a, b), None);
        changed.insert((b, a), None);
        for (e, face) in [
            ((a, d), fi),
            ((d, c), fi),
            ((c, a), fi),
            ((d, b), gi),
            ((b, c), gi),
            ((c, d), gi),
        ] {
            changed.insert(e, Some(face));
        }
        queue.extend([(a, d), (d, b), (b, c), (c, a)]);
    }
    Some(faces)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hull::{convex_hull, FloatPoints};

    /// A triangulated convex mesh: the hull of points on the unit sphere
    /// (generic, so every face is a triangle).
    fn sphere_mesh(n: usize) -> (Vec<DVec3>, Vec<Vec<usize>>) {
        let pts = crate::hull::fibonacci_sphere(n);
        let hull = convex_hull(&FloatPoints(&pts)).unwrap();
        assert!(hull.faces.iter().all(|f| f.len() == 3));
        (pts, hull.faces)
    }

    /// Flips the edge `a → b` of `faces` to the other diagonal.
    fn flip(faces: &mut [Vec<usize>], a: usize, b: usize) {
        let at =
            |f: &Vec<usize>, x: usize, y: usize| (0..3).any(|k| f[k] == x && f[(k + 1) % 3] == y);
        let fi = faces.iter().position(|f| at(f, a, b)).unwrap();
        let gi = faces.iter().position(|f| at(f, b, a)).unwrap();
        let c = *faces[fi].iter().find(|&&v| v != a && v != b).unwrap();
        let d = *faces[gi].iter().find(|&&v| v != a && v != b).unwrap();
        faces[fi] = vec![a, d, c];
        faces[gi] = vec![d, b, c];
    }

    fn as_mesh(pts: &[DVec3]) -> Vec<[f64; 3]> {
        pts.iter().map(|p| p.to_array()).collect()
    }

    #[test]
    fn flips_undo_reflex_edges() {
        let (pts, good) = sphere_mesh(60);
        let ep = ExactPoints::new(&pts);
        let mut bad = good.clone();
        let (a, b) = (bad[0][0], bad[0][1]);
        flip(&mut bad, a, b);
        let (c, d) = (bad[7][0], bad[7][1]);
        flip(&mut bad, c, d);
        assert!(check_convex_faces(&bad, &ep).is_err());
        let d = check_sphere_faces(&bad, pts.len()).unwrap();
        let fixed = flip_reflex_edges(bad, &d, &ep).unwrap();
        let mesh = compact_checked(&as_mesh(&pts), &fixed, &ep).expect("flips repair it");
        assert_eq!(mesh.faces.len(), good.len());
    }

    /// Review finding: a queued edge flipped away by a neighbouring flip
    /// must be skipped, not end the flips (two edges of one triangle).
    #[test]
    fn flips_skip_edges_already_flipped_away() {
        let (pts, good) = sphere_mesh(60);
        let ep = ExactPoints::new(&pts);
        let mut repaired = 0;
        for t in 0..good.len() {
            let mut bad = good.clone();
            let f = good[t].clone();
            flip(&mut bad, f[0], f[1]);
            flip(&mut bad, f[1], f[2]);
            if check_convex_faces(&bad, &ep).is_ok() {
                continue;
            }
            let d = check_sphere_faces(&bad, pts.len()).unwrap();
            let fixed = flip_reflex_edges(bad, &d, &ep).expect("flips settle");
            assert!(
                compact_checked(&as_mesh(&pts), &fixed, &ep).is_some(),
                "triangle {t}"
            );
            repaired += 1;
        }
        assert!(repaired > 50, "{repaired}");
    }

    /// Review finding: exact coordinates that fail the check are a broken
    /// overlay; the mesh must be refused, never repaired.
    #[test]
    fn an_exact_mesh_that_fails_is_refused_not_repaired() {
        let (pts, mut faces) = sphere_mesh(40);
        let (a, b) = (faces[0][0], faces[0][1]);
        flip(&mut faces, a, b);
        let cube = crate::polytope::Polytope::from_points(&[
            [0., 0., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [0., 0., 1.],
        ])
        .unwrap();
        let ops = Operands::new(
            &cube,
            crate::kernel::rotation::Pose::IDENTITY,
            &cube,
            crate::kernel::rotation::Pose::IDENTITY,
        );
        let merged = |shortcut| Merged {
            mesh: PolygonMesh {
                vertices: as_mesh(&pts),
                faces: faces.clone(),
            },
            exact: true,
            shortcut,
        };
        assert!(matches!(
            checked_or_repaired(&ops, merged(true), Attempt::Shortcut),
            Ok(None)
        ));
        assert!(matches!(
            checked_or_repaired(&ops, merged(false), Attempt::Final),
            Err(MeshError::Invalid(_))
        ));
    }

    /// Review finding: a region that covers the whole mesh has no boundary;
    /// the repair declines (the hull from scratch is the same work).
    #[test]
    fn a_region_over_the_whole_mesh_is_declined() {
        let mut pts = vec![
            DVec3::X,
            -DVec3::X,
            DVec3::Y,
            -DVec3::Y,
            DVec3::Z,
            -DVec3::Z,
        ];
        let hull = convex_hull(&FloatPoints(&pts)).unwrap();
        // The top vertex pushed through to below the equator: every face
        // meets a reflex edge.
        pts[4] = DVec3::new(0.0, 0.0, -0.25);
        let ep = ExactPoints::new(&pts);
        assert!(check_convex_faces(&hull.faces, &ep).is_err());
        let d = check_sphere_faces(&hull.faces, pts.len()).unwrap();
        assert!(repair_defects(&hull.faces, &d, &ep).is_none());
    }

    #[test]
    fn a_local_hull_drops_a_vertex_pushed_inside() {
        let (mut pts, mut faces) = sphere_mesh(60);
        // A new vertex just inside face 0, which is split into three.
        let f = faces[0].clone();
        let centre = (pts[f[0]] + pts[f[1]] + pts[f[2]]) / 3.0;
        let v = pts.len();
        pts.push(centre * (1.0 - 1e-9));
        faces[0] = vec![f[0], f[1], v];
        faces.push(vec![f[1], f[2], v]);
        faces.push(vec![f[2], f[0], v]);
        let ep = ExactPoints::new(&pts);
        assert!(check_convex_faces(&faces, &ep).is_err());
        let d = check_sphere_faces(&faces, pts.len()).unwrap();
        let region = repair_defects(&faces, &d, &ep).unwrap();
        let mesh = compact_checked(&as_mesh(&pts), &region, &ep).expect("a local hull repairs it");
        assert_eq!(mesh.vertices.len(), pts.len() - 1);
        // A vertex pushed *outside* is kept, never dropped.
        pts[v] = centre * (1.0 + 1e-9);
        let ep = ExactPoints::new(&pts);
        let mesh = compact_checked(&as_mesh(&pts), &faces, &ep).expect("convex as is");
        assert_eq!(mesh.vertices.len(), pts.len());
    }

    #[test]
    fn a_dropped_vertex_outside_is_refused() {
        let (pts, faces) = sphere_mesh(40);
        let ep = ExactPoints::new(&pts);
        // The hull of every vertex but 0 is closed and convex, but vertex 0
        // lies outside it: not the hull of all the vertices.
        let rest: Vec<usize> = (1..pts.len()).collect();
        let hull = convex_hull(&Corners(&rest, &ep)).unwrap();
        let without: Vec<Vec<usize>> = hull
            .faces
            .iter()
            .map(|f| f.iter().map(|&i| rest[i]).collect())
            .collect();
        assert!(compact_checked(&as_mesh(&pts), &without, &ep).is_none());
        assert!(compact_checked(&as_mesh(&pts), &faces, &ep).is_some());
    }
}
