//! A plain polygon mesh: the exchange type between the core and file formats.
//!
//! No validation happens here; [`crate::Polytope::from_mesh`] validates.

use glam::DVec3;

/// Vertices and polygonal faces (each a list of vertex indices, counter-clockwise
/// seen from outside for a well-formed closed mesh).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PolygonMesh {
    /// Vertex coordinates.
    pub vertices: Vec<[f64; 3]>,
    /// Faces as vertex index lists.
    pub faces: Vec<Vec<usize>>,
}

impl PolygonMesh {
    /// Builds a mesh from vertices and faces.
    pub fn new(vertices: Vec<[f64; 3]>, faces: Vec<Vec<usize>>) -> Self {
        Self { vertices, faces }
    }

    /// Number of triangles a fan triangulation of the faces would have.
    pub fn triangle_count(&self) -> usize {
        self.faces.iter().map(|f| f.len().saturating_sub(2)).sum()
    }

    /// Signed volume (positive for an outward-oriented closed mesh), by the
    /// divergence theorem over fan-triangulated faces.
    pub fn signed_volume(&self) -> f64 {
        let mut vol = 0.0;
        for f in &self.faces {
            if f.len() < 3 {
                continue;
            }
            let a = DVec3::from(self.vertices[f[0]]);
            for w in f[1..].windows(2) {
                let b = DVec3::from(self.vertices[w[0]]);
                let c = DVec3::from(self.vertices[w[1]]);
                vol += a.dot(b.cross(c));
            }
        }
        vol / 6.0
    }

    /// Number of undirected edges (pairs of consecutive face vertices).
    pub fn edge_count(&self) -> usize {
        let mut edges = std::collections::HashSet::new();
        for f in &self.faces {
            for i in 0..f.len() {
                let (a, b) = (f[i], f[(i + 1) % f.len()]);
                edges.insert((a.min(b), a.max(b)));
            }
        }
        edges.len()
    }

    /// The same mesh with every face fan-triangulated.
    pub fn triangulated(&self) -> PolygonMesh {
        let mut faces = Vec::with_capacity(self.triangle_count());
        for f in &self.faces {
            for i in 1..f.len().saturating_sub(1) {
                faces.push(vec![f[0], f[i], f[i + 1]]);
            }
        }
        PolygonMesh {
            vertices: self.vertices.clone(),
            faces,
        }
    }
}
