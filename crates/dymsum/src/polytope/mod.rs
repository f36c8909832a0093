//! Convex polytopes with O(1) adjacency and their Gaussian maps.
//!
//! A [`Polytope`] is built from a point cloud ([`Polytope::from_points`], an
//! exact convex hull) or from a polygon mesh ([`Polytope::from_mesh`],
//! validated, see [`build`]). Faces are maximal convex polygons: coplanar
//! neighbours are merged and vertices in the middle of a straight edge are
//! dropped, so a fan-triangulated or tessellated cube has 6 faces.
//!
//! # Adjacency
//! Half-edges are stored per face in counter-clockwise order (seen from
//! outside); half-edge `face_start[f] + k` runs from the `k`-th to the
//! `k+1`-th vertex of face `f`. Every query the sum algorithms need is O(1):
//! a face's vertices and edges, an edge's two vertices and two faces, a
//! vertex's ring of faces, edges and neighbours.
//!
//! # Gaussian map
//! Face `f` maps to its outward normal `normal(f)` (a point of the sphere,
//! stored unnormalised: a cross product of vertex differences scaled by a
//! power of two, so that exactly parallel axis-aligned or integer faces get
//! exactly parallel normals). Edge `e` maps to the great arc from the normal of its left face
//! to the normal of its right face. Vertex `v` maps to the convex spherical
//! polygon (its *cell*) spanned by the normals of its faces, listed
//! counter-clockwise by [`Polytope::ring`]. Construction checks exactly that
//! every cell is strictly convex ([`PolytopeError::DegenerateGaussMap`]).
//!
//! # Scale
//! Every constructor checks that the coordinates span at most
//! `crate::kernel::exact::MAX_COORD_SPAN` = 960 bits (else
//! [`PolytopeError::OutOfRange`]: one shape mixing `1e300` and `1e-300`),
//! and works in the shape's power-of-two *frame* (coordinates times `2^k`,
//! the largest in `[1, 2)`; exact): the hull is built on frame coordinates
//! and all float data (normals, arcs, error bounds) is derived from them.
//! So the same shape scaled by any `2^j` has identical faces, identical
//! normals and identical Gaussian-map decisions, at any overall scale from
//! about `1e-300` to `1e300`. A face whose float normal is lost to
//! cancellation (a sliver) gets its exact normal rounded instead; a face
//! below about `2^-500` of the shape's size is
//! [`PolytopeError::FaceOutOfRange`].

pub mod build;
mod convexity;
mod error;
mod reflect;
mod sanity;
pub(crate) mod topology;

pub use build::{ConvexityReport, MeshPolicy};
pub use error::PolytopeError;

use crate::kernel::dd::{self, DDVec, DD};
use crate::kernel::exact::{self, ExactVec};
use crate::kernel::predicates::ExactVector;
use glam::{DMat3, DVec3};
use topology::HalfEdges;

/// One undirected edge: its endpoints and the faces on its left and right.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Edge {
    /// Endpoints `[a, b]`; the half-edge `a → b` belongs to `faces[0]`.
    pub vertices: [u32; 2],
    /// `[left, right]`: the face containing half-edge `a → b`, then its twin's.
    pub faces: [u32; 2],
}

/// One entry of a vertex ring (one corner of its Gaussian cell).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RingEntry {
    /// A face incident to the vertex (a corner of the cell).
    pub face: u32,
    /// The edge between this face and the next face of the ring (the arc from
    /// this corner to the next one).
    pub edge: u32,
    /// The vertex at the other end of `edge` (the cell across that arc).
    pub neighbor: u32,
}

/// A convex polytope with O(1) adjacency and its Gaussian map.
///
/// A cheap, immutable, shareable handle: the data lives behind an
/// [`Arc`](std::sync::Arc), so `clone()` costs one reference count and
/// every structure built from a polytope ([`crate::dynamic::DynamicSum`],
/// [`crate::query::ConvexPair`], [`crate::query::ContactTracker`],
/// [`crate::query::CObstacle`], ...) owns its own handle: none of them has
/// a lifetime parameter, all are `Send + Sync`, and a program can keep them
/// in its own structs. `Polytope` itself is `Send + Sync`.
///
/// ```
/// use dymsum::Polytope;
///
/// let cube = Polytope::from_points(&[
///     [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0],
///     [0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0], [1.0, 1.0, 1.0],
/// ])?;
/// assert_eq!((cube.vertex_count(), cube.edge_count(), cube.face_count()), (8, 12, 6));
/// let shared = cube.clone(); // shares the data
/// assert!(shared.same_data(&cube));
/// # Ok::<(), dymsum::PolytopeError>(())
/// ```
#[derive(Clone)]
pub struct Polytope {
    data: std::sync::Arc<PolytopeData>,
}

impl std::fmt::Debug for Polytope {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Polytope")
            .field("vertices", &self.vertex_count())
            .field("edges", &self.edge_count())
            .field("faces", &self.face_count())
            .finish()
    }
}

/// The data behind a [`Polytope`] handle.
#[derive(Clone, Debug)]
struct PolytopeData {
    vertices: Vec<DVec3>,
    face_start: Vec<u32>,
    face_verts: Vec<u32>,
    he_edge: Vec<u32>,
    edges: Vec<Edge>,
    normals: Vec<DVec3>,
    normal_triple: Vec<[u32; 3]>,
    normal_err: Vec<f64>,
    /// Per face: bit `k` set when component `k` of the exact normal may be
    /// non-zero, i.e. clear only for components known to be exactly zero
    /// (the float normal is exact and that component is 0, or the zero
    /// pattern of the defining triple's edge vectors forces it: see
    /// `cross_support`). Exact zeros keep exact predicates on boxes and
    /// axis-aligned plates on their cheap paths even when the normal itself
    /// is not a float.
    normal_support: Vec<u8>,
    /// Per face: the power of two the normal is scaled by (its largest
    /// component in `[0.5, 1)`). [`Polytope::refined_normal`] is computed
    /// from it and the defining triple when asked: only the arcs (once, at
    /// construction) and the exact fallbacks of predicates on normals read
    /// it, and keeping it cost 48 bytes a face.
    normal_scale: Vec<f64>,
    arc_normals: Vec<DVec3>,
    arc_err: Vec<f64>,
    /// Per face: `1 / |normal|`; the unit normal is `normal · inv_normal_len`
    /// (bit for bit glam's `normalize`), computed when asked.
    inv_normal_len: Vec<f64>,
    ring_start: Vec<u32>,
    ring: Vec<RingEntry>,
    /// The power-of-two frame: all float data derived from the geometry
    /// (normals, arcs, error bounds) is computed from `vertices · 2^frame`
    /// (exact, see [`exact::frame_exponent`]), so it is bit-identical for
    /// the same shape at any scale `2^k`.
    frame: i32,
    /// Data a higher layer derives from this body once and shares between
    /// its handles ([`Polytope::derived`]): the proximity queries'
    /// preparation (reflection, bounds), computed on the first query.
    derived: DerivedCell,
}

/// A slot for data a higher layer derives from a polytope, typed by that
/// layer (this layer never reads it).
type DerivedCell = std::sync::OnceLock<std::sync::Arc<dyn std::any::Any + Send + Sync>>;

impl Polytope {
    /// Number of vertices.
    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.data.vertices.len()
    }
    /// Number of (maximal) faces.
    #[inline]
    pub fn face_count(&self) -> usize {
        self.data.face_start.len() - 1
    }
    /// Number of edges.
    #[inline]
    pub fn edge_count(&self) -> usize {
        self.data.edges.len()
    }
    /// Vertex coordinates.
    #[inline]
    pub fn vertices(&self) -> &[DVec3] {
        &self.data.vertices
    }
    /// Vertex `v`.
    #[inline]
    pub fn vertex(&self, v: usize) -> DVec3 {
        self.data.vertices[v]
    }
    /// The vertices of face `f`, counter-clockwise seen from outside.
    #[inline]
    pub fn face(&self, f: usize) -> &[u32] {
        &self.data.face_verts
            [self.data.face_start[f] as usize..self.data.face_start[f + 1] as usize]
    }
    /// The edges of face `f`: the `k`-th runs from `face(f)[k]` to `face(f)[k+1]`.
    #[inline]
    pub fn face_edges(&self, f: usize) -> &[u32] {
        &self.data.he_edge[self.data.face_start[f] as usize..self.data.face_start[f + 1] as usize]
    }
    /// All edges.
    #[inline]
    pub fn edges(&self) -> &[Edge] {
        &self.data.edges
    }
    /// Edge `e`.
    #[inline]
    pub fn edge(&self, e: usize) -> Edge {
        self.data.edges[e]
    }
    /// The exact-input outward normal of face `f` (not unit length; see the
    /// module docs). This is the face's point on the Gaussian sphere.
    #[inline]
    pub fn normal(&self, f: usize) -> DVec3 {
        self.data.normals[f]
    }
    /// All exact-input normals.
    #[inline]
    pub fn normals(&self) -> &[DVec3] {
        &self.data.normals
    }
    /// `1 / |normal(f)|`, so a rotated exact-input normal becomes a unit
    /// normal with one multiplication.
    #[inline]
    pub fn inverse_normal_length(&self, f: usize) -> f64 {
        self.data.inv_normal_len[f]
    }
    /// The unit outward normal of face `f` (a float construction:
    /// `normal(f).normalize()`, bit for bit).
    #[inline]
    pub fn unit_normal(&self, f: usize) -> DVec3 {
        self.data.normals[f] * self.data.inv_normal_len[f]
    }
    /// The ring of vertex `v`: its faces counter-clockwise seen from outside,
    /// i.e. the corners and arcs of its Gaussian cell.
    #[inline]
    pub fn ring(&self, v: usize) -> &[RingEntry] {
        &self.data.ring[self.data.ring_start[v] as usize..self.data.ring_start[v + 1] as usize]
    }
    /// Offset of vertex `v`'s ring in the flat array of all rings (so
    /// per-ring-entry data can be stored in one `Vec`).
    #[inline]
    pub fn ring_offset(&self, v: usize) -> usize {
        self.data.ring_start[v] as usize
    }
    /// Total number of ring entries (twice the number of edges).
    #[inline]
    pub fn ring_len_total(&self) -> usize {
        self.data.ring.len()
    }
    /// Degree of vertex `v`.
    #[inline]
    pub fn degree(&self, v: usize) -> usize {
        (self.data.ring_start[v + 1] - self.data.ring_start[v]) as usize
    }
    /// Faces as vertex-index polygons.
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        (0..self.face_count()).map(move |f| self.face(f))
    }
    /// The polytope as a polygon mesh (maximal faces).
    pub fn to_mesh(&self) -> crate::mesh::PolygonMesh {
        crate::mesh::PolygonMesh {
            vertices: self.data.vertices.iter().map(|v| v.to_array()).collect(),
            faces: self
                .faces()
                .map(|f| f.iter().map(|&v| v as usize).collect())
                .collect(),
        }
    }
    /// Number of triangles of a fan triangulation of the faces.
    pub fn triangle_count(&self) -> usize {
        self.faces().map(|f| f.len() - 2).sum()
    }
    /// The vertex maximising `dir · v` (a float support query, O(V)).
    pub fn support_vertex(&self, dir: DVec3) -> usize {
        let mut best = 0;
        let mut best_val = f64::NEG_INFINITY;
        for (i, v) in self.data.vertices.iter().enumerate() {
            let d = dir.dot(*v);
            if d > best_val {
                best_val = d;
                best = i;
            }
        }
        best
    }
    /// Volume, by the divergence theorem (a float construction, made in the
    /// shape's power-of-two frame and scaled back, so it scales exactly
    /// with the shape; `inf` only when the volume exceeds `f64`).
    pub fn volume(&self) -> f64 {
        let vs: Vec<DVec3> = self
            .data
            .vertices
            .iter()
            .map(|&v| self.to_frame(v))
            .collect();
        let c = vs.iter().copied().sum::<DVec3>() / vs.len() as f64;
        let vol = crate::mesh::six_signed_volume(self.faces(), |i| vs[i] - c);
        exact::mul_pow2(vol / 6.0, -3 * self.data.frame)
    }
    /// The frame exponent `k`: the largest coordinate magnitude times `2^k`
    /// lies in `[1, 2)`. Float data derived from the geometry (normals,
    /// arcs) is computed from the vertices scaled by `2^k`.
    #[inline]
    pub fn frame_exponent(&self) -> i32 {
        self.data.frame
    }
    /// `v · 2^frame` (exact for the polytope's vertices).
    #[inline]
    pub fn to_frame(&self, v: DVec3) -> DVec3 {
        exact::mul_pow2_vec(v, self.data.frame)
    }
    /// Mean of the vertices.
    pub fn centroid_of_vertices(&self) -> DVec3 {
        self.data.vertices.iter().copied().sum::<DVec3>() / self.data.vertices.len() as f64
    }
    /// Length of the bounding-box diagonal.
    pub fn diameter(&self) -> f64 {
        let (lo, hi) = bounds(&self.data.vertices);
        let d = (self.to_frame(hi) - self.to_frame(lo)).length();
        exact::mul_pow2(d, -self.data.frame)
    }

    /// Builds the half-edge structure from maximal ccw faces over `vertices`
    /// (already validated as a closed, oriented 2-manifold by the caller).
    pub(crate) fn from_faces(
        vertices: Vec<DVec3>,
        faces: &[Vec<u32>],
    ) -> Result<Polytope, PolytopeError> {
        let mut face_start = Vec::with_capacity(faces.len() + 1);
        let mut face_verts = Vec::new();
        face_start.push(0u32);
        for f in faces {
            face_verts.extend_from_slice(f);
            face_start.push(face_verts.len() as u32);
        }
        let HalfEdges {
            he_edge,
            edges,
            ring_start,
            ring,
        } = HalfEdges::new(vertices.len(), faces)?;
        check_span(&vertices)?;
        let frame = exact::frame_exponent(vertices.iter().flat_map(|v| v.to_array()));
        let framed: Vec<DVec3> = vertices
            .iter()
            .map(|&v| exact::mul_pow2_vec(v, frame))
            .collect();
        let mut normals = Vec::with_capacity(faces.len());
        let mut normal_triple = Vec::with_capacity(faces.len());
        let mut normal_err = Vec::with_capacity(faces.len());
        let mut normal_scale = Vec::with_capacity(faces.len());
        let mut normal_support = Vec::with_capacity(faces.len());
        for (face, f) in faces.iter().enumerate() {
            let (n, triple, err, scale) =
                face_normal(&framed, f).ok_or(PolytopeError::FaceOutOfRange { face })?;
            let [a, b, c] = triple.map(|v| framed[v as usize]);
            let exact_zeros = if err == 0.0 {
                n.cmpne(DVec3::ZERO).bitmask() as u8
            } else {
                0b111
            };
            normal_support.push(exact_zeros & cross_support(b - a, c - a));
            normals.push(n);
            normal_triple.push(triple);
            normal_err.push(err);
            normal_scale.push(scale);
        }
        // The refined normals, kept only while the arcs are computed and the
        // Gaussian map checked.
        let refined: Vec<(DDVec, f64)> = normal_triple
            .iter()
            .zip(&normal_scale)
            .map(|(t, &s)| refine_normal(t.map(|v| framed[v as usize]), s))
            .collect();
        let (arc_normals, arc_err) = edges
            .iter()
            .map(|e| {
                accurate_arc_normal(&refined[e.faces[0] as usize], &refined[e.faces[1] as usize])
            })
            .unzip();
        let inv_normal_len = normals.iter().map(|n| 1.0 / n.length()).collect();
        let data = PolytopeData {
            vertices,
            face_start,
            face_verts,
            he_edge,
            edges,
            normals,
            normal_triple,
            normal_err,
            normal_support,
            normal_scale,
            arc_normals,
            arc_err,
            inv_normal_len,
            ring_start,
            ring,
            frame,
            derived: Default::default(),
        };
        let poly = Polytope {
            data: std::sync::Arc::new(data),
        };
        poly.check_gauss_map(&refined)?;
        Ok(poly)
    }

    /// `true` when both handles share the same data (a clone of the other).
    pub fn same_data(&self, other: &Polytope) -> bool {
        std::sync::Arc::ptr_eq(&self.data, &other.data)
    }

    /// Checks exactly that every Gaussian cell is a strictly convex spherical
    /// polygon: every corner strictly left of every arc of its cell.
    /// `refined` holds every face's [`Polytope::refined_normal`], computed
    /// once by the caller (the exact fallbacks of nearly coplanar faces read
    /// them many times).
    fn check_gauss_map(&self, refined: &[(DDVec, f64)]) -> Result<(), PolytopeError> {
        use crate::kernel::predicates::det3;
        let normal = |f: u32| RefinedNormal {
            normal: self.face_normal(f),
            refined: refined[f as usize],
        };
        for v in 0..self.vertex_count() {
            let r = self.ring(v);
            if r.len() < 3 {
                return Err(PolytopeError::DegenerateGaussMap { vertex: v });
            }
            for i in 0..r.len() {
                let a = normal(r[i].face);
                let b = normal(r[(i + 1) % r.len()].face);
                for (j, e) in r.iter().enumerate() {
                    if j == i || j == (i + 1) % r.len() {
                        continue;
                    }
                    if !det3(&a, &b, &normal(e.face)).is_positive() {
                        return Err(PolytopeError::DegenerateGaussMap { vertex: v });
                    }
                }
            }
        }
        Ok(())
    }

    /// The exact normal of face `f` (unrotated), as a predicate argument
    /// with SoS index `f`.
    #[inline]
    pub fn face_normal(&self, f: u32) -> FaceNormal<'_> {
        FaceNormal {
            poly: self,
            face: f,
            approx: self.data.normals[f as usize],
            err: self.data.normal_err[f as usize],
            idx: f,
            rotation: None,
        }
    }

    /// Bound on the distance between [`Polytope::normal`] and the exact
    /// normal (scaled alike).
    #[inline]
    pub fn normal_error(&self, f: usize) -> f64 {
        self.data.normal_err[f]
    }

    /// The exact normal of face `f`, scaled like [`Polytope::normal`], in
    /// double-double, with a bound on its error (computed from the face's
    /// defining triple, in the polytope's frame).
    pub fn refined_normal(&self, f: usize) -> (DDVec, f64) {
        let triple =
            self.data.normal_triple[f].map(|v| self.to_frame(self.data.vertices[v as usize]));
        refine_normal(triple, self.data.normal_scale[f])
    }

    /// Great-circle normals of all edge arcs (`n(left) × n(right)`, accurate to a few ulps).
    #[inline]
    pub fn arc_normals(&self) -> &[DVec3] {
        &self.data.arc_normals
    }
    /// Error bounds of [`Polytope::arc_normals`].
    #[inline]
    pub fn arc_errors(&self) -> &[f64] {
        &self.data.arc_err
    }

    /// The data one higher layer derives from this body, computed by `make`
    /// on first use and kept for every handle (the proximity queries keep
    /// their preparation here, so this layer does not name their types).
    /// One type per polytope: the crate has one such user.
    ///
    /// # Panics
    /// If a value of another type was stored first (a bug in dymsum: one
    /// user only).
    pub(crate) fn derived<T: std::any::Any + Send + Sync + Clone>(
        &self,
        make: impl FnOnce() -> T,
    ) -> T {
        let slot = self
            .data
            .derived
            .get_or_init(|| std::sync::Arc::new(make()));
        slot.downcast_ref::<T>()
            .expect("one type of derived data per polytope")
            .clone()
    }

    /// The exact (unscaled) normal of face `f`: `(B − A) × (C − A)` for the
    /// face's defining vertex triple.
    pub fn exact_normal(&self, f: usize) -> ExactVec {
        let [a, b, c] = self.data.normal_triple[f].map(|v| self.data.vertices[v as usize]);
        exact::cross(&exact::sub(b, a), &exact::sub(c, a))
    }
}

/// A face normal whose refinement is already computed (the construction's
/// checks): the same predicate argument as [`FaceNormal`], bit for bit.
struct RefinedNormal<'a> {
    normal: FaceNormal<'a>,
    refined: (DDVec, f64),
}

impl ExactVector for RefinedNormal<'_> {
    #[inline]
    fn approx(&self) -> DVec3 {
        self.normal.approx()
    }
    #[inline]
    fn error(&self) -> f64 {
        self.normal.error()
    }
    #[inline]
    fn index(&self) -> u32 {
        self.normal.index()
    }
    fn exact(&self) -> ExactVec {
        self.normal.exact()
    }
    fn refined(&self) -> (DDVec, f64) {
        self.refined
    }
    #[inline]
    fn exact_float(&self) -> Option<DVec3> {
        self.normal.exact_float()
    }
    #[inline]
    fn exact_components(&self) -> [Option<f64>; 3] {
        self.normal.exact_components()
    }
    #[inline]
    fn zero_mask(&self) -> u8 {
        self.normal.zero_mask()
    }
}

/// A face normal as an exact predicate argument: the polytope's float
/// normal (optionally rotated by a float matrix taken as exact), its error
/// bound, and its exact value on demand.
#[derive(Clone, Copy, Debug)]
pub struct FaceNormal<'a> {
    /// The polytope.
    pub poly: &'a Polytope,
    /// The face.
    pub face: u32,
    /// Float approximation (rotated if `rotation` is set).
    pub approx: DVec3,
    /// Error bound of `approx`.
    pub err: f64,
    /// Global SoS index.
    pub idx: u32,
    /// The rotation applied, if any.
    pub rotation: Option<&'a DMat3>,
}

impl ExactVector for FaceNormal<'_> {
    #[inline]
    fn approx(&self) -> DVec3 {
        self.approx
    }
    #[inline]
    fn error(&self) -> f64 {
        self.err
    }
    #[inline]
    fn index(&self) -> u32 {
        self.idx
    }
    fn exact(&self) -> ExactVec {
        let n = self.poly.exact_normal(self.face as usize);
        match self.rotation {
            Some(m) => exact::mat_vec(m, &n),
            None => n,
        }
    }
    #[inline]
    fn exact_float(&self) -> Option<DVec3> {
        if self.poly.data.normal_err[self.face as usize] != 0.0 {
            return None;
        }
        let n = self.poly.data.normals[self.face as usize];
        match self.rotation {
            None => Some(n),
            Some(m) => exact::float::mat_vec(m, n),
        }
    }
    #[inline]
    fn exact_components(&self) -> [Option<f64>; 3] {
        if self.poly.data.normal_err[self.face as usize] != 0.0 {
            // Only the components known to be zero.
            let zero = self.zero_mask();
            return [0, 1, 2].map(|k| (zero >> k & 1 != 0).then_some(0.0));
        }
        let n = self.poly.data.normals[self.face as usize];
        match self.rotation {
            None => [Some(n.x), Some(n.y), Some(n.z)],
            Some(m) => [
                rotated_component(m.row(0), n),
                rotated_component(m.row(1), n),
                rotated_component(m.row(2), n),
            ],
        }
    }
    #[inline]
    fn zero_mask(&self) -> u8 {
        let support = self.poly.data.normal_support[self.face as usize];
        let Some(m) = self.rotation else {
            // Unrotated: the components known to be zero.
            return !support & 0b111;
        };
        // (M n)_r is exactly zero when M[r][k] = 0 for every k where n_k
        // may be non-zero.
        let mut zero = 0b111;
        for (k, col) in [m.x_axis, m.y_axis, m.z_axis].into_iter().enumerate() {
            if support >> k & 1 != 0 {
                zero &= col.cmpeq(DVec3::ZERO).bitmask() as u8;
            }
        }
        zero
    }
    fn refined(&self) -> (DDVec, f64) {
        let (n, err) = self.poly.refined_normal(self.face as usize);
        match self.rotation {
            None => (n, err),
            Some(m) => {
                let row = |r: usize| {
                    let row = m.row(r);
                    DD::from(row.x) * n[0] + DD::from(row.y) * n[1] + DD::from(row.z) * n[2]
                };
                let mag = n.iter().map(|d| d.abs_hi()).fold(0.0, f64::max) * 1.7320508075688774;
                (
                    [row(0), row(1), row(2)],
                    1.01 * err + 32.0 * U * U * mag * 1.7320508075688774,
                )
            }
        }
    }
}

/// The components of `d1 × d2` that may be non-zero (bit `k` set), from
/// the zero pattern of the *float* differences `d1`, `d2` alone: a float
/// difference `x − y` is zero exactly when `x = y`, so its zeros are those
/// of the exact difference, and a component of the cross product whose two
/// products each have a zero factor is exactly zero however the others
/// round (a box of side 0.05 has axis-parallel normals although their
/// lengths, 0.05², are not floats).
fn cross_support(d1: DVec3, d2: DVec3) -> u8 {
    let zero = |v: DVec3, k: usize| v[k] == 0.0;
    let mut support = 0;
    for (k, (i, j)) in [(1, 2), (2, 0), (0, 1)].into_iter().enumerate() {
        let vanishes = (zero(d1, i) || zero(d2, j)) && (zero(d1, j) || zero(d2, i));
        if !vanishes {
            support |= 1 << k;
        }
    }
    support
}

/// `row · n` when it is a float obtainable without rounding. Terms with an
/// exactly zero factor are skipped, so the components that a rotation about
/// a coordinate axis leaves alone (and the exact zeros it produces) cost a
/// compare or one product, not a compensated dot product.
#[inline]
fn rotated_component(row: DVec3, n: DVec3) -> Option<f64> {
    let live = |k: usize| row[k] != 0.0 && n[k] != 0.0;
    match (live(0), live(1), live(2)) {
        (false, false, false) => Some(0.0),
        (true, false, false) => exact::float::mul(row.x, n.x),
        (false, true, false) => exact::float::mul(row.y, n.y),
        (false, false, true) => exact::float::mul(row.z, n.z),
        _ => exact::float::dot(row, n),
    }
}

const U: f64 = f64::EPSILON / 2.0;

/// The exact normal `(b − a) × (c − a)` of a face's defining triple (in
/// the frame), scaled by `s` (a power of two), in double-double, with a
/// bound on its error: [`Polytope::refined_normal`].
fn refine_normal([a, b, c]: [DVec3; 3], s: f64) -> (DDVec, f64) {
    let d1 = [DD::diff(b.x, a.x), DD::diff(b.y, a.y), DD::diff(b.z, a.z)];
    let d2 = [DD::diff(c.x, a.x), DD::diff(c.y, a.y), DD::diff(c.z, a.z)];
    let n = dd::cross(&d1, &d2).map(|x| x.scale(s));
    // Each component: two DD products and a DD difference, relative
    // error ≤ ~12u² of |d1||d2|; plus the absolute error of low parts
    // that underflow (a few units of 2^-1074 per operation).
    let err = (32.0 * U * U * (b - a).length() * (c - a).length() + 64.0 * TINY) * s * 1.01;
    (n, err)
}
/// The normal of the great circle of an edge's Gaussian arc,
/// `n(left) × n(right)` of the exact (scaled) normals, rounded once from
/// their double-double refinements `left`, `right`, and a bound on its
/// error. `det[n(left), n(right), x]` is then one dot product, even for
/// very short arcs.
fn accurate_arc_normal((a, ea): &(DDVec, f64), (b, eb): &(DDVec, f64)) -> (DVec3, f64) {
    let (ea, eb) = (*ea, *eb);
    let c = dd::cross(a, b);
    let m = DVec3::new(c[0].hi + c[0].lo, c[1].hi + c[1].lo, c[2].hi + c[2].lo);
    let mag =
        |v: &DDVec| v.iter().map(|d| d.abs_hi()).fold(0.0, f64::max) * 1.7320508075688774 * 1.01;
    let (na, nb) = (mag(a) + ea, mag(b) + eb);
    let err = ea * nb
        + na * eb
        + 32.0 * U * U * na * nb
        + U * 1.7320508075688774 * m.abs().max_element() * 1.01;
    (m, 1.01 * err + f64::MIN_POSITIVE)
}

/// The smallest positive subnormal, `2^-1074`.
const TINY: f64 = 5e-324;

/// [`PolytopeError::OutOfRange`] when the coordinates span more than
/// [`exact::MAX_COORD_SPAN`] bits, naming their largest and smallest
/// non-zero magnitudes.
pub(crate) fn check_span(points: &[DVec3]) -> Result<(), PolytopeError> {
    let coords = || points.iter().flat_map(|p| p.to_array());
    if exact::coordinate_span_ok(coords()).is_ok() {
        return Ok(());
    }
    let mags = coords().map(f64::abs).filter(|&x| x > 0.0);
    Err(PolytopeError::OutOfRange {
        largest: mags.clone().fold(0.0, f64::max),
        smallest: mags.fold(f64::INFINITY, f64::min),
    })
}

/// Error bound of a float normal rotated by a (nearly orthogonal) float
/// matrix, relative to the exact product of that matrix and the exact normal.
#[inline]
pub fn rotated_error(err: f64, approx: DVec3) -> f64 {
    crate::kernel::bounds::rotated(err, approx)
}

/// The normal of a planar polygon as the cross product of the two edges of
/// its largest fan triangle from the first vertex, scaled by a power of two
/// (exactly) so its largest component lies in `[0.5, 1)`. Returns the float
/// normal, the defining vertex triple (whose exact cross product is the
/// exact normal) and a bound on the float normal's error.
///
/// Because the exact normal is a cross product of exact vertex differences,
/// exact coincidences of the geometry (parallel faces, a normal on an arc)
/// are exact coincidences of the normals.
fn face_normal(vertices: &[DVec3], face: &[u32]) -> Option<(DVec3, [u32; 3], f64, f64)> {
    let a = vertices[face[0] as usize];
    let mut best = (DVec3::ZERO, [face[0], face[1], face[2]], -1.0, 0.0);
    for w in face[1..].windows(2) {
        let (d1, d2) = (vertices[w[0] as usize] - a, vertices[w[1] as usize] - a);
        let c = d1.cross(d2);
        let l = c.length_squared();
        if l > best.2 {
            best = (c, [face[0], w[0], w[1]], l, d1.length() * d2.length());
        }
    }
    let (n, triple, _, lens) = best;
    // Whether the float normal is the exact cross product (then its error
    // is 0 and exact ties are decided by the cheap float stage).
    let [ta, tb, tc] = triple.map(|v| vertices[v as usize]);
    let exact_n = exact::float::sub(tb, ta)
        .zip(exact::float::sub(tc, ta))
        .and_then(|(d1, d2)| exact::float::cross(d1, d2))
        .filter(|&c| c == n);
    // |fl(d1 × d2) − (B−A) × (C−A)| ≤ ~7u |d1||d2|; use 16u. Products that
    // underflow add an absolute error of at most 2^-1074 each.
    let mut err = (16.0 * f64::EPSILON / 2.0 * lens + 8.0 * TINY) * 1.01;
    let m = n.abs().max_element();
    // A sliver face (float cancellation leaves the float normal mostly
    // rounding error, or exactly zero) or a normal below 2^-1000 in the
    // frame: round the exact normal instead.
    if !(m > 64.0 * err && m >= 9.332636185032189e-302) {
        return exact_rounded_normal(ta, tb, tc).map(|(n, err, s)| (n, triple, err, s));
    }
    let e = exact::top_exponent(m) + 1;
    let s = exact::mul_pow2(1.0, -e);
    // (+ TINY: scaling down may round a subnormal component.)
    err = err * s + TINY;
    if exact_n.and_then(|c| exact::float::scale(c, s)).is_some() {
        err = 0.0;
    }
    Some((n * s, triple, err, s))
}

/// The exact normal `(B − A) × (C − A)` scaled by `s = 2^-e` so that its
/// largest component lies in `[0.5, 1)`, rounded componentwise (error below
/// `3u` of the largest component), with an error bound and `s`. `None`
/// when the exact normal is zero or below `2^-1000` (a face about `2^-500`
/// of the shape's size: beyond the supported range).
fn exact_rounded_normal(a: DVec3, b: DVec3, c: DVec3) -> Option<(DVec3, f64, f64)> {
    let n = exact::cross(&exact::sub(b, a), &exact::sub(c, a));
    let top = n.iter().filter_map(|d| d.top_exponent()).max()?;
    if top < -1000 {
        return None;
    }
    let e = top + 1;
    let v = DVec3::new(
        n[0].to_f64_shifted(-e),
        n[1].to_f64_shifted(-e),
        n[2].to_f64_shifted(-e),
    );
    Some((v, 4.0 * f64::EPSILON + TINY, exact::mul_pow2(1.0, -e)))
}

pub(crate) fn bounds(pts: &[DVec3]) -> (DVec3, DVec3) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for p in pts {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    (lo, hi)
}
