//! A plain polygon mesh: the exchange type between the core and file formats.
//!
//! No validation happens here; [`crate::polytope::Polytope::from_mesh`] validates.

use glam::DVec3;

/// A vertex index as stored in a face list.
pub(crate) trait VertexIndex: Copy {
    fn index(self) -> usize;
}

impl VertexIndex for usize {
    #[inline]
    fn index(self) -> usize {
        self
    }
}

impl VertexIndex for u32 {
    #[inline]
    fn index(self) -> usize {
        self as usize
    }
}

/// A vertex cycle rotated to start at its smallest index (the same cycle
/// from any start gives the same key).
pub(crate) fn canonical_cycle(cycle: &[usize]) -> Vec<usize> {
    let start = (0..cycle.len()).min_by_key(|&i| cycle[i]).unwrap_or(0);
    cycle[start..]
        .iter()
        .chain(&cycle[..start])
        .copied()
        .collect()
}

/// Six times the signed volume enclosed by polygons (positive for an
/// outward-oriented closed mesh), by the divergence theorem over their fan
/// triangulations, each corner read through `point`. A float construction;
/// callers translate and scale the points first (to a frame) when the
/// result must not depend on position. Polygons of fewer than three
/// corners add nothing. The one volume formula of the crate.
pub(crate) fn six_signed_volume<'a, I: VertexIndex + 'a>(
    faces: impl IntoIterator<Item = &'a [I]>,
    point: impl Fn(usize) -> DVec3,
) -> f64 {
    let mut vol = 0.0;
    for f in faces {
        let Some((&first, rest)) = f.split_first() else {
            continue;
        };
        let a = point(first.index());
        for w in rest.windows(2) {
            vol += a.dot(point(w[0].index()).cross(point(w[1].index())));
        }
    }
    vol
}

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
        let faces = self.faces.iter().map(Vec::as_slice);
        six_signed_volume(faces, |i| DVec3::from(self.vertices[i])) / 6.0
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
