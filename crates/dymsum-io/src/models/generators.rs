//! Geometry generators for the built-in models.
//!
//! Every generator returns a closed, convex [`PolygonMesh`] whose faces are
//! counter-clockwise seen from outside, centred at the origin (bounding box
//! centre), except [`random_ball`], which returns a point cloud.
//! Parameters are validated by the caller (`super`); the functions here
//! assume sane values.

use std::collections::HashMap;
use std::f64::consts::TAU;

use dymsum::PolygonMesh;
use rand::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;

type P3 = [f64; 3];

fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: P3, b: P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: P3) -> f64 {
    dot(a, a).sqrt()
}

fn scale(a: P3, s: f64) -> P3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// The golden ratio.
const PHI: f64 = 1.618_033_988_749_895;

/// An axis-aligned box with full side lengths `x`, `y`, `z`, centred at the
/// origin: 8 vertices, 6 quadrilaterals.
pub(crate) fn box_mesh(x: f64, y: f64, z: f64) -> PolygonMesh {
    // Vertex index = bx + 2 by + 4 bz, bit set meaning the positive side.
    let vertices = (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { -x / 2.0 } else { x / 2.0 },
                if i & 2 == 0 { -y / 2.0 } else { y / 2.0 },
                if i & 4 == 0 { -z / 2.0 } else { z / 2.0 },
            ]
        })
        .collect();
    let faces = vec![
        vec![0, 4, 6, 2], // -x
        vec![1, 3, 7, 5], // +x
        vec![0, 1, 5, 4], // -y
        vec![2, 6, 7, 3], // +y
        vec![0, 2, 3, 1], // -z
        vec![4, 5, 7, 6], // +z
    ];
    PolygonMesh::new(vertices, faces)
}

/// The cube of the paper's Fig. 5: side `side`, centred at the origin, each
/// square face split into `k` x `k` squares and each square into two
/// triangles (12 k² triangles, 6 k² + 2 shared vertices).
pub(crate) fn tessellated_cube(side: f64, k: usize) -> PolygonMesh {
    let mut index: HashMap<[usize; 3], usize> = HashMap::new();
    let mut vertices: Vec<P3> = Vec::with_capacity(6 * k * k + 2);
    let step = side / k as f64;
    let half = side / 2.0;
    let mut vertex = |l: [usize; 3]| -> usize {
        *index.entry(l).or_insert_with(|| {
            vertices.push([
                l[0] as f64 * step - half,
                l[1] as f64 * step - half,
                l[2] as f64 * step - half,
            ]);
            vertices.len() - 1
        })
    };
    let mut faces = Vec::with_capacity(12 * k * k);
    for axis in 0..3 {
        // (u, v, axis) is a right-handed frame, so u x v points along +axis.
        let (ua, va) = ((axis + 1) % 3, (axis + 2) % 3);
        for positive in [false, true] {
            let level = if positive { k } else { 0 };
            let mut lattice = |u: usize, v: usize| {
                let mut l = [0; 3];
                l[axis] = level;
                l[ua] = u;
                l[va] = v;
                vertex(l)
            };
            for u in 0..k {
                for v in 0..k {
                    let p00 = lattice(u, v);
                    let p10 = lattice(u + 1, v);
                    let p11 = lattice(u + 1, v + 1);
                    let p01 = lattice(u, v + 1);
                    if positive {
                        faces.push(vec![p00, p10, p11]);
                        faces.push(vec![p00, p11, p01]);
                    } else {
                        faces.push(vec![p00, p11, p10]);
                        faces.push(vec![p00, p01, p11]);
                    }
                }
            }
        }
    }
    PolygonMesh::new(vertices, faces)
}

fn ring_point(i: usize, n: usize, r: f64, z: f64) -> P3 {
    let t = TAU * i as f64 / n as f64;
    [r * t.cos(), r * t.sin(), z]
}

/// A right prism over a regular `n`-gon of circumradius `r`, height `h`,
/// axis along z: two `n`-gon caps and `n` quadrilaterals
/// (2 (n - 2) + 2 n triangles when fan-triangulated).
pub(crate) fn cylinder(n: usize, r: f64, h: f64) -> PolygonMesh {
    let mut vertices = Vec::with_capacity(2 * n);
    for i in 0..n {
        vertices.push(ring_point(i, n, r, -h / 2.0));
    }
    for i in 0..n {
        vertices.push(ring_point(i, n, r, h / 2.0));
    }
    let mut faces = Vec::with_capacity(n + 2);
    faces.push((0..n).rev().collect());
    faces.push((n..2 * n).collect());
    for i in 0..n {
        let j = (i + 1) % n;
        faces.push(vec![i, j, n + j, n + i]);
    }
    PolygonMesh::new(vertices, faces)
}

/// A right pyramid over a regular `n`-gon of circumradius `r` (at z = -h/2)
/// with its apex at z = +h/2: one `n`-gon and `n` triangles
/// ((n - 2) + n triangles when fan-triangulated).
pub(crate) fn cone(n: usize, r: f64, h: f64) -> PolygonMesh {
    let mut vertices: Vec<P3> = (0..n).map(|i| ring_point(i, n, r, -h / 2.0)).collect();
    vertices.push([0.0, 0.0, h / 2.0]);
    let mut faces = Vec::with_capacity(n + 1);
    faces.push((0..n).rev().collect());
    for i in 0..n {
        faces.push(vec![i, (i + 1) % n, n]);
    }
    PolygonMesh::new(vertices, faces)
}

/// A solid of revolution about the z axis: a pole at `z_bottom`, rings
/// `(z, radius)` listed bottom to top (each with `n` vertices at the same
/// azimuths), a pole at `z_top`. Polar fans of triangles, planar
/// quadrilaterals (isosceles trapezoids) between consecutive rings.
fn revolution(n: usize, z_bottom: f64, rings: &[(f64, f64)], z_top: f64) -> PolygonMesh {
    let mut vertices = Vec::with_capacity(rings.len() * n + 2);
    vertices.push([0.0, 0.0, z_bottom]);
    for &(z, r) in rings {
        for i in 0..n {
            vertices.push(ring_point(i, n, r, z));
        }
    }
    let top = vertices.len();
    vertices.push([0.0, 0.0, z_top]);
    let at = |ring: usize, i: usize| 1 + ring * n + i % n;
    let mut faces = Vec::new();
    for i in 0..n {
        faces.push(vec![0, at(0, i + 1), at(0, i)]);
    }
    for ring in 0..rings.len() - 1 {
        for i in 0..n {
            faces.push(vec![
                at(ring, i),
                at(ring, i + 1),
                at(ring + 1, i + 1),
                at(ring + 1, i),
            ]);
        }
    }
    let last = rings.len() - 1;
    for i in 0..n {
        faces.push(vec![top, at(last, i), at(last, i + 1)]);
    }
    PolygonMesh::new(vertices, faces)
}

/// A capsule (a cylinder with hemispherical end caps) along z: radius `r`,
/// cylindrical part of length `l`, `n` vertices around each ring and `k`
/// rings per hemisphere at latitudes 90°·(1 - j/k), j = 1..k (the last one
/// on the equator, shared with the cylinder), closed by polar fans.
///
/// Faces: 2 n polar triangles, 2 n (k - 1) cap quadrilaterals and n
/// cylinder quadrilaterals, i.e. 4 n k triangles when fan-triangulated.
/// Every vertex lies on one of the two cap spheres and on the hull, and no
/// two adjacent faces are coplanar, so the capsule is strictly convex at
/// every vertex (for `l > 0`, and also for `l = 0`).
pub(crate) fn capsule(n: usize, k: usize, r: f64, l: f64) -> PolygonMesh {
    let a = l / 2.0;
    let lat = |j: usize| std::f64::consts::FRAC_PI_2 * (1.0 - j as f64 / k as f64);
    let mut rings = Vec::with_capacity(2 * k);
    // Bottom cap from the pole towards the equator, then the top cap.
    for j in 1..=k {
        let p = lat(j);
        rings.push((-a - r * p.sin(), r * p.cos()));
    }
    for j in (1..=k).rev() {
        let p = lat(j);
        rings.push((a + r * p.sin(), r * p.cos()));
    }
    if l == 0.0 {
        // Both equator rings coincide: keep one.
        rings.remove(k);
    }
    revolution(n, -a - r, &rings, a + r)
}

/// Convex hull of a small point set (a few dozen points) by brute force,
/// with coplanar points merged into polygons. Used for the Platonic solids.
fn small_hull(points: &[P3]) -> PolygonMesh {
    let size = points
        .iter()
        .map(|&p| norm(p))
        .fold(0.0, f64::max)
        .max(1e-300);
    let mut seen: HashMap<Vec<usize>, ()> = HashMap::new();
    let mut faces = Vec::new();
    let m = points.len();
    for i in 0..m {
        for j in i + 1..m {
            for k in j + 1..m {
                let n = cross(sub(points[j], points[i]), sub(points[k], points[i]));
                let len = norm(n);
                if len <= 1e-12 * size * size {
                    continue;
                }
                let n = scale(n, 1.0 / len);
                let d: Vec<f64> = points.iter().map(|&p| dot(n, sub(p, points[i]))).collect();
                let tol = 1e-9 * size;
                let normal = if d.iter().all(|&x| x <= tol) {
                    n
                } else if d.iter().all(|&x| x >= -tol) {
                    scale(n, -1.0)
                } else {
                    continue;
                };
                let on: Vec<usize> = (0..m).filter(|&q| d[q].abs() <= tol).collect();
                if seen.insert(on.clone(), ()).is_some() {
                    continue;
                }
                faces.push(order_ccw(points, on, normal));
            }
        }
    }
    PolygonMesh::new(points.to_vec(), faces)
}

/// Sorts coplanar points counter-clockwise around `normal`.
fn order_ccw(points: &[P3], mut face: Vec<usize>, normal: P3) -> Vec<usize> {
    let mut c = [0.0; 3];
    for &q in &face {
        for (ci, pi) in c.iter_mut().zip(points[q]) {
            *ci += pi / face.len() as f64;
        }
    }
    let u0 = sub(points[face[0]], c);
    let u = scale(u0, 1.0 / norm(u0));
    let w = cross(normal, u);
    let angle = |q: usize| {
        let d = sub(points[q], c);
        dot(d, w).atan2(dot(d, u))
    };
    face.sort_by(|&a, &b| angle(a).total_cmp(&angle(b)));
    face
}

fn normalized(points: Vec<P3>) -> Vec<P3> {
    points
        .into_iter()
        .map(|p| scale(p, 1.0 / norm(p)))
        .collect()
}

/// Regular tetrahedron with circumradius 1.
pub(crate) fn tetrahedron() -> PolygonMesh {
    small_hull(&normalized(vec![
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ]))
}

/// Regular octahedron with circumradius 1.
pub(crate) fn octahedron() -> PolygonMesh {
    let mut pts = Vec::new();
    for axis in 0..3 {
        for s in [1.0, -1.0] {
            let mut p = [0.0; 3];
            p[axis] = s;
            pts.push(p);
        }
    }
    small_hull(&pts)
}

fn icosahedron_points() -> Vec<P3> {
    let mut pts = Vec::new();
    for s1 in [1.0, -1.0] {
        for s2 in [PHI, -PHI] {
            pts.push([0.0, s1, s2]);
            pts.push([s1, s2, 0.0]);
            pts.push([s2, 0.0, s1]);
        }
    }
    normalized(pts)
}

/// Regular icosahedron with circumradius 1 (20 triangles).
pub(crate) fn icosahedron() -> PolygonMesh {
    small_hull(&icosahedron_points())
}

/// Regular dodecahedron with circumradius 1 (12 pentagons).
pub(crate) fn dodecahedron() -> PolygonMesh {
    let mut pts = Vec::new();
    for sx in [1.0, -1.0] {
        for sy in [1.0, -1.0] {
            for sz in [1.0, -1.0] {
                pts.push([sx, sy, sz]);
            }
            pts.push([0.0, sx / PHI, sy * PHI]);
            pts.push([sx / PHI, sy * PHI, 0.0]);
            pts.push([sx * PHI, 0.0, sy / PHI]);
        }
    }
    small_hull(&normalized(pts))
}

/// Geodesic sphere of radius 1: every face of the icosahedron split into
/// `freq`² triangles on a triangular grid, grid points projected onto the
/// sphere (20 freq² triangles, 10 freq² + 2 vertices). All vertices lie on
/// the sphere, so each is a strictly convex vertex of the hull.
pub(crate) fn geodesic_sphere(freq: usize) -> PolygonMesh {
    let base = icosahedron();
    let corners = base.vertices;
    let mut index: HashMap<Vec<(usize, usize)>, usize> = HashMap::new();
    let mut vertices: Vec<P3> = Vec::with_capacity(10 * freq * freq + 2);
    let mut faces = Vec::with_capacity(20 * freq * freq);
    for tri in &base.faces {
        let (a, b, c) = (tri[0], tri[1], tri[2]);
        let mut grid = |i: usize, j: usize| -> usize {
            // Exact key: the corner weights, so shared edge points coincide.
            let mut key: Vec<(usize, usize)> = [(a, freq - i - j), (b, i), (c, j)]
                .into_iter()
                .filter(|&(_, w)| w > 0)
                .collect();
            key.sort_unstable();
            let len = vertices.len();
            let id = *index.entry(key.clone()).or_insert(len);
            if id == len {
                let mut p = [0.0; 3];
                for &(v, w) in &key {
                    for (pk, ck) in p.iter_mut().zip(corners[v]) {
                        *pk += w as f64 * ck;
                    }
                }
                vertices.push(scale(p, 1.0 / norm(p)));
            }
            id
        };
        for i in 0..freq {
            for j in 0..freq - i {
                let p00 = grid(i, j);
                let p10 = grid(i + 1, j);
                let p01 = grid(i, j + 1);
                faces.push(vec![p00, p10, p01]);
                if i + j + 2 <= freq {
                    let p11 = grid(i + 1, j + 1);
                    faces.push(vec![p10, p11, p01]);
                }
            }
        }
    }
    PolygonMesh::new(vertices, faces)
}

/// The geodesic sphere of frequency `freq` scaled by the semi-axes
/// `a`, `b`, `c` along x, y, z (an affine image, so still convex).
pub(crate) fn ellipsoid(a: f64, b: f64, c: f64, freq: usize) -> PolygonMesh {
    let mut mesh = geodesic_sphere(freq);
    for v in &mut mesh.vertices {
        *v = [v[0] * a, v[1] * b, v[2] * c];
    }
    mesh
}

/// `n` points uniformly distributed in the unit ball, from the ChaCha8
/// generator seeded with `seed` (`ChaCha8Rng::seed_from_u64`). Each
/// coordinate is `2 u - 1` with `u = (next_u64() >> 11) · 2⁻⁵³`; candidates
/// with `x² + y² + z² > 1` are rejected. Only integer operations feed the
/// generator and the arithmetic is exact IEEE, so a seed gives the same
/// points on every platform. The mesh has **no faces**: `vertices` is a
/// point cloud whose convex hull the caller builds.
pub(crate) fn random_ball(n: usize, seed: u64) -> PolygonMesh {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut unit = move || ((rng.next_u64() >> 11) as f64) * (1.0 / (1u64 << 53) as f64);
    let mut vertices = Vec::with_capacity(n);
    while vertices.len() < n {
        let p = [2.0 * unit() - 1.0, 2.0 * unit() - 1.0, 2.0 * unit() - 1.0];
        if dot(p, p) <= 1.0 {
            vertices.push(p);
        }
    }
    PolygonMesh::new(vertices, Vec::new())
}
