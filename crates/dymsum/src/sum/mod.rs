//! Static Minkowski sums of convex polytopes: three independent methods, one
//! answer.
//!
//! The facets of `P ⊕ Q` come from the overlay of the Gaussian maps of `P`
//! and `Q` (paper §3): an *fv*-facet for each face `f` of `P` with the vertex
//! of `Q` whose cell contains `f`'s normal, a *vf*-facet symmetrically, and an
//! *ee*-facet for each pair of edges whose Gaussian arcs cross.
//!
//! | method | how | cost |
//! |---|---|---|
//! | [`Method::Brute`] | test every face–vertex and edge–edge pair (paper Alg. 3.1) | O(mn) |
//! | [`Method::Walk`] | hill-climb fv-pairs from solved neighbours, walk each arc of `P` through `Q`'s map | O(m + n + k) |
//! | [`Method::Hull`] | exact hull of all m·n vertex sums, then label its faces | O(mn log mn) |
//!
//! All three use the same exact predicates with the same symbolic
//! perturbation (`overlay`), so they return identical facet sets, which
//! [`MinkowskiSum::facets`] lists in canonical order. [`MinkowskiSum::try_to_mesh`]
//! merges coplanar facets into the true faces (see `merge`).
//!
//! ```
//! use dymsum::{Polytope, Pose, Rotation, DVec3};
//! use dymsum::sum::{minkowski_sum, minkowski_sum_posed, Method};
//! let tet = Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]]).unwrap();
//! let cube = Polytope::from_points(&[
//!     [0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [1., 1., 0.],
//!     [0., 0., 1.], [1., 0., 1.], [0., 1., 1.], [1., 1., 1.],
//! ]).unwrap();
//! let walk = minkowski_sum(&tet, &cube, Method::Walk).unwrap();
//! let brute = minkowski_sum(&tet, &cube, Method::Brute).unwrap();
//! assert_eq!(walk.facets(), brute.facets());
//! // P may be posed: rotated about the origin, then translated.
//! let turn = Pose::new(Rotation::from_axis_angle(DVec3::Z, 0.3).unwrap(), DVec3::X);
//! let moved = minkowski_sum_posed(&tet, turn, &cube, Pose::IDENTITY, Method::Walk).unwrap();
//! assert!(moved.try_to_mesh().unwrap().faces.len() > 6);
//! ```

mod brute;
pub mod contained;
mod hull_method;
pub(crate) mod merge;
mod repair;
pub mod validate;
mod walk;

pub use crate::error::{MeshError, SumError};
pub use repair::{Precision, SumMesh};

pub(crate) use crate::gauss::GaussView;
use crate::kernel::rotation::Pose;
use crate::polytope::Polytope;
use glam::DVec3;

/// Which static algorithm computes the sum.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Test every face–vertex and edge–edge pair (the paper's baseline).
    Brute,
    /// Output-sensitive walks in the Gaussian maps (fastest; reused by the
    /// dynamic update).
    Walk,
    /// The exact convex hull of all pairwise vertex sums, labelled.
    Hull,
}

impl Method {
    /// All methods.
    pub const ALL: [Method; 3] = [Method::Brute, Method::Walk, Method::Hull];
    /// Lower-case name (`brute`, `walk`, `hull`).
    pub fn name(self) -> &'static str {
        match self {
            Method::Brute => "brute",
            Method::Walk => "walk",
            Method::Hull => "hull",
        }
    }
}

impl std::str::FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "brute" => Ok(Method::Brute),
            "walk" => Ok(Method::Walk),
            "hull" => Ok(Method::Hull),
            _ => Err(format!(
                "unknown method `{s}` (expected walk, brute or hull)"
            )),
        }
    }
}

/// One facet of `P ⊕ Q` with its generating features.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Facet {
    /// Face `p_face` of P translated by vertex `q_vertex` of Q.
    Fv {
        /// Face of P.
        p_face: u32,
        /// Vertex of Q.
        q_vertex: u32,
    },
    /// Vertex `p_vertex` of P plus face `q_face` of Q.
    Vf {
        /// Vertex of P.
        p_vertex: u32,
        /// Face of Q.
        q_face: u32,
    },
    /// Edge `p_edge` of P plus edge `q_edge` of Q (a parallelogram).
    Ee {
        /// Edge of P.
        p_edge: u32,
        /// Edge of Q.
        q_edge: u32,
    },
}

/// The overlay state: for every face of P its vertex of Q, for every face of
/// Q its vertex of P, and the crossing edge pairs (sorted).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Overlay {
    /// `fv[f]`: the vertex of Q whose cell contains face `f` of P.
    pub fv: Vec<u32>,
    /// `vf[g]`: the vertex of P whose cell contains face `g` of Q.
    pub vf: Vec<u32>,
    /// Crossing `(edge of P, edge of Q)` pairs, sorted.
    pub ee: Vec<(u32, u32)>,
}

impl Overlay {
    /// All facets in canonical order (fv by face, vf by face, ee sorted).
    pub fn facets(&self) -> Vec<Facet> {
        let mut out = Vec::with_capacity(self.fv.len() + self.vf.len() + self.ee.len());
        out.extend(self.fv.iter().enumerate().map(|(f, &v)| Facet::Fv {
            p_face: f as u32,
            q_vertex: v,
        }));
        out.extend(self.vf.iter().enumerate().map(|(g, &u)| Facet::Vf {
            p_vertex: u,
            q_face: g as u32,
        }));
        out.extend(
            self.ee
                .iter()
                .map(|&(p_edge, q_edge)| Facet::Ee { p_edge, q_edge }),
        );
        out
    }
    /// Number of facets.
    pub fn len(&self) -> usize {
        self.fv.len() + self.vf.len() + self.ee.len()
    }
    /// `true` if there are no facets.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The two posed operands of a sum: polytopes, poses and the normals in the
/// *combinatorial frame* (Q's body frame).
///
/// The overlay depends only on the relative rotation `R = R_q⁻¹ R_p`: P's
/// normals are `R n`, Q's are its own reference normals. Translations and a
/// common rotation of both bodies therefore never change the facet set.
#[derive(Clone, Debug)]
pub(crate) struct Operands {
    /// P.
    pub p: Polytope,
    /// Q.
    pub q: Polytope,
    /// P's pose.
    pub pose_p: Pose,
    /// Q's pose.
    pub pose_q: Pose,
    /// The relative rotation `R_q⁻¹ R_p`.
    pub relative: crate::kernel::rotation::Rotation,
    /// P's normals rotated by the relative rotation.
    pub np: Vec<DVec3>,
    /// Q's reference normals.
    pub nq: Vec<DVec3>,
    /// The relative rotation's matrix, `None` for the identity.
    pub rot_p: Option<glam::DMat3>,
    /// P's arc normals rotated by the relative rotation.
    pub arc_p: Vec<DVec3>,
    /// Error bounds of `arc_p`.
    pub arc_p_err: Vec<f64>,
    /// Exact ties met at this relative rotation.
    pub(crate) ties: crate::gauss::TieCache,
    /// When set (a dynamic sum, [`Operands::make_lazy`]), `np` and `arc_p`
    /// are not kept: P's view rotates its own normals and arcs by `turn` on
    /// access, so a new rotation costs O(1) instead of O(m).
    lazy: bool,
    /// The relative rotation's matrix and cofactor matrix (for `lazy`).
    turn: crate::gauss::Turn,
}

/// P's arc normals under a rotation, and their error bounds. Exact normals
/// map by `R`, so cross products map by its cofactor matrix `det(R) R⁻ᵀ`
/// (equal to `R` only for an exactly orthogonal `R`). The bounds do not
/// depend on the rotation (they cover the rounding of any nearly orthogonal
/// matrix and of the identity), so they are computed once, when `errs` is
/// empty; only the arcs are recomputed per rotation.
pub(crate) fn rotate_arcs(
    p: &Polytope,
    rot: Option<&glam::DMat3>,
    arcs: &mut Vec<DVec3>,
    errs: &mut Vec<f64>,
) {
    if errs.len() != p.edge_count() {
        let u = f64::EPSILON / 2.0;
        errs.clear();
        errs.extend(
            p.arc_normals()
                .iter()
                .zip(p.arc_errors())
                .map(|(a, e)| 1.05 * e + 64.0 * u * a.abs().max_element() * 1.7320508075688774),
        );
    }
    arcs.clear();
    match rot {
        None => arcs.extend_from_slice(p.arc_normals()),
        Some(m) => {
            let c = cofactor(m);
            arcs.extend(p.arc_normals().iter().map(|a| c * *a));
        }
    }
}

/// The matrix and cofactor matrix of a rotation, for lazy views.
pub(crate) fn turn_of(r: crate::kernel::rotation::Rotation) -> crate::gauss::Turn {
    let rot = r.matrix();
    crate::gauss::Turn {
        rot,
        cof: cofactor(&rot),
    }
}

/// The cofactor matrix `cof(M)` with `cof(M) (a × b) = (M a) × (M b)`.
fn cofactor(m: &glam::DMat3) -> glam::DMat3 {
    let (c0, c1, c2) = (m.x_axis, m.y_axis, m.z_axis);
    // (M a) × (M b) = cof(M)(a × b) where cof(M) = det(M) M^{-T}; its
    // columns are c1 × c2, c2 × c0, c0 × c1.
    glam::DMat3::from_cols(c1.cross(c2), c2.cross(c0), c0.cross(c1))
}

/// The relative rotation `R_q⁻¹ R_p` (exactly `R_p` when Q is not rotated).
pub(crate) fn relative_rotation(pose_p: &Pose, pose_q: &Pose) -> crate::kernel::rotation::Rotation {
    if pose_q.rotation == crate::kernel::rotation::Rotation::IDENTITY {
        pose_p.rotation
    } else {
        pose_p.rotation.then(&pose_q.rotation.inverse())
    }
}

impl Operands {
    /// Rotates P's normals into Q's frame.
    pub fn new(p: &Polytope, pose_p: Pose, q: &Polytope, pose_q: Pose) -> Self {
        let relative = relative_rotation(&pose_p, &pose_q);
        let mut ops = Operands {
            p: p.clone(),
            q: q.clone(),
            np: p.normals().iter().map(|&n| relative.apply(n)).collect(),
            nq: q.normals().to_vec(),
            rot_p: (relative != crate::kernel::rotation::Rotation::IDENTITY)
                .then(|| relative.matrix()),
            arc_p: Vec::new(),
            arc_p_err: Vec::new(),
            ties: crate::gauss::TieCache::new(),
            pose_p,
            pose_q,
            relative,
            lazy: false,
            turn: turn_of(relative),
        };
        rotate_arcs(p, ops.rot_p.as_ref(), &mut ops.arc_p, &mut ops.arc_p_err);
        ops
    }
    /// Turns P to the relative rotation `new`: its normals, its arcs, and
    /// a fresh tie memo.
    pub(crate) fn set_relative(&mut self, new: crate::kernel::rotation::Rotation) {
        self.relative = new;
        self.rot_p = (new != crate::kernel::rotation::Rotation::IDENTITY).then(|| new.matrix());
        self.ties.clear();
        if self.lazy {
            self.turn = turn_of(new);
            return;
        }
        rotate_arcs(
            &self.p,
            self.rot_p.as_ref(),
            &mut self.arc_p,
            &mut self.arc_p_err,
        );
        for (n, r) in self.np.iter_mut().zip(self.p.normals()) {
            *n = new.apply(*r);
        }
    }

    /// Stops storing P's rotated normals and arcs: from now on P's view
    /// rotates them on access ([`crate::gauss::Turn`]), so
    /// [`Operands::set_relative`] is O(1). For a dynamic sum, which visits
    /// few of them per step; a static sum reads every one several times
    /// and keeps them stored.
    pub(crate) fn make_lazy(&mut self) {
        self.lazy = true;
        self.turn = turn_of(self.relative);
        self.np = Vec::new();
        self.arc_p = Vec::new();
    }

    /// P's Gaussian map (global indices `0..m`).
    #[inline]
    pub fn view_p(&self) -> GaussView<'_> {
        let (normals, arcs, turn) = match (self.lazy, self.rot_p.is_some()) {
            (false, _) => (&self.np[..], &self.arc_p[..], None),
            (true, false) => (self.p.normals(), self.p.arc_normals(), None),
            (true, true) => (self.p.normals(), self.p.arc_normals(), Some(&self.turn)),
        };
        GaussView {
            poly: &self.p,
            normals,
            arcs,
            turn,
            arc_errs: &self.arc_p_err,
            base: 0,
            rotation: self.rot_p.as_ref(),
            ties: Some(&self.ties),
        }
    }
    /// Q's Gaussian map (global indices `m..m+n`).
    #[inline]
    pub fn view_q(&self) -> GaussView<'_> {
        GaussView {
            poly: &self.q,
            normals: &self.nq,
            arcs: self.q.arc_normals(),
            turn: None,
            arc_errs: self.q.arc_errors(),
            base: self.p.face_count() as u32,
            rotation: None,
            ties: Some(&self.ties),
        }
    }
    /// [`SumError::OutOfRange`] when a posed vertex of P or Q overflows.
    pub fn check_range(&self) -> Result<(), SumError> {
        let bad = |n: usize, f: &dyn Fn(u32) -> DVec3| (0..n as u32).find(|&v| !f(v).is_finite());
        if let Some(v) = bad(self.p.vertex_count(), &|u| self.p_vertex(u)) {
            return Err(SumError::OutOfRange {
                operand: "P",
                vertex: v as usize,
            });
        }
        if let Some(v) = bad(self.q.vertex_count(), &|w| self.q_vertex(w)) {
            return Err(SumError::OutOfRange {
                operand: "Q",
                vertex: v as usize,
            });
        }
        Ok(())
    }
    /// Position of vertex `u` of P under its pose.
    #[inline]
    pub fn p_vertex(&self, u: u32) -> DVec3 {
        self.pose_p.apply(self.p.vertex(u as usize))
    }
    /// Position of vertex `w` of Q under its pose.
    #[inline]
    pub fn q_vertex(&self, w: u32) -> DVec3 {
        self.pose_q.apply(self.q.vertex(w as usize))
    }
}

/// A Minkowski sum: the operands and their overlay.
///
/// Built by [`minkowski_sum`] or [`minkowski_sum_posed`]; every [`Method`]
/// gives the identical labelled facet set. A box plus a box is a box:
///
/// ```
/// use dymsum::{minkowski_sum, Method, Polytope};
/// let cuboid = |x: f64, y: f64, z: f64| {
///     let corners: Vec<[f64; 3]> = (0..8)
///         .map(|i| [x * (i & 1) as f64, y * ((i >> 1) & 1) as f64, z * ((i >> 2) & 1) as f64])
///         .collect();
///     Polytope::from_points(&corners)
/// };
/// let a = cuboid(1.0, 1.0, 1.0)?;
/// let b = cuboid(2.0, 1.0, 3.0)?;
/// let sum = minkowski_sum(&a, &b, Method::Walk)?;
/// // Every face of each box is translated by one vertex of the other.
/// let (fv, vf, ee) = sum.counts();
/// assert_eq!((fv, vf), (6, 6));
/// assert_eq!(sum.facets().len(), fv + vf + ee);
/// assert_eq!(minkowski_sum(&a, &b, Method::Brute)?.facets(), sum.facets());
/// // Coplanar facets merge: the mesh is the 3 × 2 × 4 box.
/// let mesh = sum.try_to_mesh()?;
/// assert_eq!((mesh.vertices.len(), mesh.faces.len()), (8, 6));
/// assert_eq!(mesh.signed_volume(), 24.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct MinkowskiSum {
    operands: Operands,
    overlay: Overlay,
}

impl MinkowskiSum {
    /// Wraps an overlay computed for these operands.
    pub(crate) fn from_overlay(operands: Operands, overlay: Overlay) -> Self {
        MinkowskiSum { operands, overlay }
    }
    /// The overlay (fv, vf and ee pairs).
    pub fn overlay(&self) -> &Overlay {
        &self.overlay
    }
    /// All facets, labelled, in canonical order.
    pub fn facets(&self) -> Vec<Facet> {
        self.overlay.facets()
    }
    /// Facet counts `(fv, vf, ee)`.
    pub fn counts(&self) -> (usize, usize, usize) {
        (
            self.overlay.fv.len(),
            self.overlay.vf.len(),
            self.overlay.ee.len(),
        )
    }
    /// The merged polygon mesh: coplanar facets merged into maximal faces,
    /// collinear vertices dropped, counter-clockwise outward, checked
    /// without tolerance ([`validate::check_convex_mesh`]). Where rounding of
    /// the coordinates breaks the exact faces, it is the exact hull of the
    /// rounded vertices instead (see `repair::validated_mesh`).
    ///
    /// # Errors
    /// [`MeshError::PrecisionLost`] when the rounded vertices collapse (the
    /// sum is too far from the origin for its size);
    /// [`MeshError::OutOfRange`] when a vertex of the sum (a posed `p + q`)
    /// overflows `f64`;
    /// [`MeshError::Merge`] / [`MeshError::Invalid`] are internal errors.
    pub fn try_to_mesh(&self) -> Result<crate::mesh::PolygonMesh, MeshError> {
        self.mesh_with_precision().map(|m| m.mesh)
    }
    /// [`Self::try_to_mesh`] with the coordinates' rounding relative to the
    /// sum's size, and whether the hull fallback was used.
    ///
    /// # Errors
    /// The same as [`Self::try_to_mesh`].
    pub fn mesh_with_precision(&self) -> Result<repair::SumMesh, MeshError> {
        repair::validated_mesh(&self.operands, &self.overlay)
    }
    /// Checks the facet complex: every facet edge shared by exactly two facets
    /// in opposite directions (closed, 2-manifold, consistently oriented),
    /// Euler `V − E + F = 2`, and the merged mesh closed and convex.
    ///
    /// # Errors
    /// The first broken invariant ([`crate::sanity::SanityError`]).
    pub fn sanity_check(&self) -> Result<(), crate::sanity::SanityError> {
        merge::check_facet_complex(&self.operands, &self.overlay)?;
        self.try_to_mesh()?;
        Ok(())
    }
}

/// `P ⊕ Q` at the polytopes' own coordinates.
///
/// # Errors
/// As [`minkowski_sum_posed`] at the identity poses:
/// [`SumError::OutOfRange`] cannot occur (the vertices are finite), so
/// [`SumError::HullMismatch`] (only with [`Method::Hull`]) and the internal
/// [`SumError::Inconsistent`] remain.
pub fn minkowski_sum(p: &Polytope, q: &Polytope, method: Method) -> Result<MinkowskiSum, SumError> {
    minkowski_sum_posed(p, Pose::IDENTITY, q, Pose::IDENTITY, method)
}

/// `(R_p P + t_p) ⊕ (R_q Q + t_q)`.
///
/// # Errors
/// * [`SumError::OutOfRange`] when a posed vertex `R p + t` of P or Q
///   overflows `f64` (naming the operand and the vertex);
/// * [`SumError::HullMismatch`], only with [`Method::Hull`], when the hull
///   of the rounded pairwise vertex sums disagrees with the exact overlay
///   (rotation rounding bent a face of P); [`Method::Walk`] and
///   [`Method::Brute`] never return it;
/// * [`SumError::Inconsistent`] if an internal invariant fails (a bug in
///   dymsum: please report the input).
pub fn minkowski_sum_posed(
    p: &Polytope,
    pose_p: Pose,
    q: &Polytope,
    pose_q: Pose,
    method: Method,
) -> Result<MinkowskiSum, SumError> {
    let ops = Operands::new(p, pose_p, q, pose_q);
    ops.check_range()?;
    let overlay = match method {
        Method::Brute => brute::overlay(&ops)?,
        Method::Walk => walk::overlay(&ops)?,
        Method::Hull => hull_method::overlay(&ops)?,
    };
    Ok(MinkowskiSum::from_overlay(ops, overlay))
}

pub(crate) use brute::overlay as brute_overlay;
pub(crate) use walk::overlay as walk_overlay;
