//! What several test files share: a seeded generator and soups of long,
//! thin, slanted triangles (robot parts' slivers).

use dymsum::{DVec3, PolygonMesh};

/// A xorshift generator: small, seeded, the same on every machine.
pub struct Rng(pub u64);

impl Rng {
    /// A number in `[-1, 1)`.
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    /// A unit vector.
    pub fn direction(&mut self) -> DVec3 {
        loop {
            let d = DVec3::new(self.unit(), self.unit(), self.unit());
            if (0.01..=1.0).contains(&d.length_squared()) {
                return d.normalize();
            }
        }
    }
}

/// The corners of `n` slivers: from a point in a box of side 4 about
/// `centre`, a long edge of length 1 to 4 in a random direction, a third
/// corner 0.025 to 1 off its middle (`flat`: all in the plane
/// `z = centre.z`).
pub fn sliver_corners(rng: &mut Rng, n: usize, centre: DVec3, flat: bool) -> Vec<[f64; 3]> {
    let mut vertices = Vec::new();
    for _ in 0..n {
        let mut p = centre + DVec3::new(rng.unit(), rng.unit(), rng.unit()) * 2.0;
        let mut d = rng.direction();
        if flat {
            p.z = centre.z;
            d.z = 0.0;
            d = d.normalize();
        }
        let len = 2.5 + 1.5 * rng.unit();
        let side = if flat {
            DVec3::Z.cross(d)
        } else {
            d.cross(rng.direction())
                .normalize_or(d.any_orthonormal_vector())
        };
        let width = 10f64.powf(-0.8 + 0.8 * rng.unit());
        let q = p + d * len;
        vertices.extend([p, q, p + d * (0.5 * len) + side * width].map(|v| v.to_array()));
    }
    vertices
}

/// A soup of the triangles `(3t, 3t + 1, 3t + 2)` of `corners`, each
/// coordinate times `scale`.
pub fn soup(corners: &[[f64; 3]], scale: f64) -> PolygonMesh {
    let n = corners.len() / 3;
    let faces = (0..n).map(|t| vec![3 * t, 3 * t + 1, 3 * t + 2]).collect();
    PolygonMesh::new(
        corners.iter().map(|p| p.map(|x| x * scale)).collect(),
        faces,
    )
}
