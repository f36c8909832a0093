//! URDF's primitive shapes as meshes: a box exactly (its eight corners), a
//! sphere, a cylinder and a capsule as convex polytopes that *contain*
//! them, with the largest deviation stated (checks are exact for these
//! polytopes; an exact sphere, as coal has it, may differ within the
//! deviation).

use glam::DVec3;

use crate::mesh::PolygonMesh;
use crate::polytope::Polytope;

/// The box of side lengths `size` centred on the origin (six quads).
pub fn box_mesh(size: DVec3) -> PolygonMesh {
    let h = size * 0.5;
    let corner = |i: usize| {
        [
            if i & 1 == 0 { -h.x } else { h.x },
            if i & 2 == 0 { -h.y } else { h.y },
            if i & 4 == 0 { -h.z } else { h.z },
        ]
    };
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    PolygonMesh::new(
        (0..8).map(corner).collect(),
        faces.iter().map(|f| f.to_vec()).collect(),
    )
}

/// A convex polytope holding every point of `points` grown until its
/// faces clear `inside(direction)`: the hull of the points scaled about
/// the origin so that every face plane lies at least as far as the shape's
/// support in its normal's direction (`support(n)`, the shape's extent
/// along the unit normal `n`). Returns the mesh and the largest distance
/// from a vertex to the shape (the deviation), both in floats with a
/// relative margin of `1e-9` outward.
fn circumscribed(
    points: &[DVec3],
    support: impl Fn(DVec3) -> f64,
    distance_out: impl Fn(DVec3) -> f64,
) -> Option<(PolygonMesh, f64)> {
    let arrays: Vec<[f64; 3]> = points.iter().map(|p| p.to_array()).collect();
    let hull = Polytope::from_points(&arrays).ok()?;
    let mesh = hull.to_mesh();
    // The least ratio of a face plane's offset to the shape's support.
    let mut scale = 1.0f64;
    for f in &mesh.faces {
        let p: Vec<DVec3> = f.iter().map(|&v| DVec3::from(mesh.vertices[v])).collect();
        let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
        let offset = n.dot(p[0]);
        let need = support(n);
        if offset <= 0.0 {
            return None;
        }
        scale = scale.max(need / offset);
    }
    let scale = scale * (1.0 + 1e-9);
    let vertices: Vec<[f64; 3]> = mesh
        .vertices
        .iter()
        .map(|v| (DVec3::from(*v) * scale).to_array())
        .collect();
    let deviation = vertices
        .iter()
        .map(|v| distance_out(DVec3::from(*v)))
        .fold(0.0, f64::max)
        * (1.0 + 1e-9);
    Some((PolygonMesh::new(vertices, mesh.faces), deviation))
}

/// A polytope of `segments` around (at least 8) holding the sphere of
/// `radius` about the origin, and its deviation (the farthest a vertex
/// lies from the sphere).
pub fn sphere_polytope(radius: f64, segments: usize) -> Option<(PolygonMesh, f64)> {
    let n = segments.max(8);
    let rings = n / 2;
    let mut pts = vec![DVec3::new(0.0, 0.0, radius), DVec3::new(0.0, 0.0, -radius)];
    for i in 1..rings {
        let th = std::f64::consts::PI * i as f64 / rings as f64;
        for k in 0..n {
            let ph = std::f64::consts::TAU * k as f64 / n as f64;
            pts.push(DVec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()) * radius);
        }
    }
    circumscribed(&pts, |_| radius, |v| v.length() - radius)
}

/// A prism of `segments` sides (at least 8) holding the cylinder of
/// `radius` and `length` along z about the origin, and its deviation.
pub fn cylinder_polytope(radius: f64, length: f64, segments: usize) -> Option<(PolygonMesh, f64)> {
    let n = segments.max(8);
    let h = 0.5 * length;
    let mut pts = Vec::new();
    for k in 0..n {
        let ph = std::f64::consts::TAU * k as f64 / n as f64;
        for z in [-h, h] {
            pts.push(DVec3::new(radius * ph.cos(), radius * ph.sin(), z));
        }
    }
    let support = |u: DVec3| radius * u.truncate().length() + h * u.z.abs();
    let out = |v: DVec3| (v.truncate().length() - radius).max(0.0) + (v.z.abs() - h).max(0.0);
    circumscribed(&pts, support, out)
}

/// A polytope holding the capsule of `radius` and `length` (the distance
/// between the two hemispheres' centres) along z about the origin, and
/// its deviation.
pub fn capsule_polytope(radius: f64, length: f64, segments: usize) -> Option<(PolygonMesh, f64)> {
    let (sphere, _) = sphere_polytope(radius, segments)?;
    let h = 0.5 * length;
    let mut pts = Vec::new();
    for v in &sphere.vertices {
        let p = DVec3::from(*v);
        pts.push(p + DVec3::Z * h);
        pts.push(p - DVec3::Z * h);
    }
    let support = |u: DVec3| radius + h * u.z.abs();
    let out = |v: DVec3| {
        let z = v.z.clamp(-h, h);
        (v - DVec3::new(0.0, 0.0, z)).length() - radius
    };
    circumscribed(&pts, support, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every point of the shape is inside the polytope: random points of
    /// the surface against every face plane; the deviation bounds the
    /// vertices' distance.
    #[test]
    fn primitives_are_held_by_their_polytopes() {
        let mut rng = crate::kernel::test_rng::Xorshift::new(0x1234_5678_9abc_def1u64);
        let mut unit = move || rng.signed();
        let (r, l) = (0.3, 1.1);
        let shapes = [
            (sphere_polytope(r, 16).unwrap(), 0.0),
            (cylinder_polytope(r, l, 16).unwrap(), 1.0),
            (capsule_polytope(r, l, 16).unwrap(), 2.0),
        ];
        for ((mesh, deviation), kind) in shapes {
            assert!(deviation > 0.0 && deviation < 0.1 * r, "{deviation}");
            for _ in 0..2000 {
                let d = DVec3::new(unit(), unit(), unit()).normalize();
                let p = if kind == 0.0 {
                    d * r
                } else if kind == 1.0 {
                    let rim = DVec3::new(d.x, d.y, 0.0).normalize() * r;
                    rim + DVec3::Z * (0.5 * l * unit())
                } else {
                    d * r + DVec3::Z * (0.5 * l * d.z.signum())
                };
                for f in &mesh.faces {
                    let v: Vec<DVec3> = f.iter().map(|&k| DVec3::from(mesh.vertices[k])).collect();
                    let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
                    assert!(n.dot(p - v[0]) <= 1e-12, "kind {kind}: {p:?} outside");
                }
            }
        }
        assert_eq!(box_mesh(DVec3::new(1.0, 2.0, 3.0)).faces.len(), 6);
    }
}
