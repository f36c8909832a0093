//! The mesh of a certified slab, by exact polar duality.
//!
//! [`Slab::mesh`] contains the polytope `P = {N x ≤ d}`. By polar duality
//! about an interior point `c` (the mean of `H`'s vertices), the vertices
//! of `P' = {x : n_i·(x − c) ≤ t_i}` are the poles of the facets of the
//! hull of the points `q_i = n_i / t_i`; that hull is built with exact
//! predicates on the rational `q_i` (homogeneous coordinates `(n_i, t_i)`,
//! a float filter first), so its facets are exactly `P'`'s vertices. Each
//! vertex is computed by Cramer's rule (floats with determinant error
//! bounds, or exact determinants rounded once) within a bound `τ`. The
//! mesh is the exact hull of the rounded vertices, which contains
//! `P' ⊖ ball(τ) = {n_i·(x − c) ≤ t_i − τ|n_i|}` (the hull of points each
//! within `τ` of a polytope's vertices has a support function at most `τ`
//! below the polytope's). With `t_i ≥ d_i − n_i·c + μ`, `μ ≥ τ max|n_i|`
//! (rounded up; `μ` starts at `2⁻⁴⁰` of the coordinates' magnitude and is
//! raised when `τ` needs it), that is `⊇ P`. The mesh passes
//! [`crate::sum::validate::check_convex_mesh`]; one that failed would be an
//! error, never returned. Its faces are maximal for the rounded vertices:
//! a face of `P` with four or more corners is usually split by rounding.
//!

use super::{above, below, Slab, ROTATION_SLACK};
use crate::hull::{convex_hull, FloatPoints};
use crate::kernel::exact::{self, Dyadic};
use crate::kernel::{bounds, Sign};
use crate::mesh::PolygonMesh;
use crate::query::error::QueryError;
use crate::query::frame::up;
use crate::sum::{validate::check_convex_mesh, MeshError};
use glam::DVec3;
use rayon::prelude::*;

impl Slab {
    /// The slab as a closed convex mesh (maximal faces, counter-clockwise
    /// outward) that **contains** the polytope `{N x ≤ d}`: the vertices of
    /// `{N x ≤ d + μ}` (`μ` a tiny push, module docs) rounded, and their
    /// exact hull, checked with [`check_convex_mesh`]. Where rounding bends
    /// a face of four or more corners, the hull splits it.
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when a vertex overflows `f64`;
    /// [`QueryError::Mesh`] or [`QueryError::Inconsistent`] only for an
    /// internal error (a mesh failing its check is never returned).
    pub fn mesh(&self) -> Result<PolygonMesh, QueryError> {
        let centre = self.hull.centroid_of_vertices();
        let size = self.hull.diameter() + 2.0 * self.margin;
        if !(centre.is_finite() && size.is_finite()) {
            return Err(QueryError::OutOfRange(
                "the slab's mesh coordinates overflow f64".into(),
            ));
        }
        let longest = self
            .planes
            .normals()
            .iter()
            .map(|n| up(n.length()))
            .fold(0.0, f64::max);
        // 2^-40 of the coordinates' magnitude: far above the rounding of
        // the vertices, far below anything a planner resolves.
        let mut push = (centre.abs().max_element() + size) * ROTATION_SLACK;
        for _ in 0..8 {
            let (vertices, rounding) = self.pushed_vertices(centre, push)?;
            let needed = up(rounding * longest);
            if needed <= push {
                let points = FloatPoints(&vertices);
                let hull = convex_hull(&points).map_err(|e| {
                    QueryError::Inconsistent(format!("the slab's vertices span no volume: {e}"))
                })?;
                let mesh = hull.to_mesh(&points);
                check_convex_mesh(&mesh).map_err(MeshError::from)?;
                return Ok(mesh);
            }
            push = 2.0 * needed;
        }
        Err(QueryError::Inconsistent(
            "the slab's vertices could not be bounded".into(),
        ))
    }

    /// The vertices of `{x : n_i·(x − c) ≤ t_i}` with every
    /// `t_i ≥ d_i − n_i·c + push` (rounded up), by polar duality (module
    /// docs), and a bound on their rounding (Euclidean, each vertex).
    fn pushed_vertices(&self, c: DVec3, push: f64) -> Result<(Vec<DVec3>, f64), QueryError> {
        let mut t: Vec<f64> = self
            .planes
            .normals()
            .iter()
            .zip(self.planes.offsets())
            .map(|(&n, &d)| {
                let (v, err) = bounds::dot(n, 0.0, c, 0.0);
                above(above(d - below(v - err)) + push)
            })
            .collect();
        if let Some(i) = t.iter().position(|x| !(x.is_finite() && *x > 0.0)) {
            return Err(QueryError::Inconsistent(format!(
                "the slab's centre is not inside its plane {i} ({:e})",
                t[i]
            )));
        }
        // Scale the offsets by a power of two (exact) to about 1: the dual
        // points and their determinants stay far from overflow and
        // underflow at any scale; the vertices scale back exactly.
        let k = exact::frame_exponent(t.iter().copied());
        t.iter_mut().for_each(|x| *x = exact::mul_pow2(*x, k));
        let dual = PolarPoints::new(self.planes.normals(), &t);
        let hull = convex_hull(&dual)
            .map_err(|e| QueryError::Inconsistent(format!("the slab's dual hull failed: {e}")))?;
        let mut rounding = 0.0f64;
        let mut vertices = Vec::with_capacity(hull.faces.len());
        for f in &hull.faces {
            let rows = [f[0], f[1], f[2]].map(|i| (self.planes.normals()[i], t[i]));
            let (z, err) = solve_planes(rows)?;
            let (z, err) = (exact::mul_pow2_vec(z, -k), exact::mul_pow2(err, -k));
            let v = c + z;
            if !v.is_finite() {
                return Err(QueryError::OutOfRange(
                    "a vertex of the slab overflows f64".into(),
                ));
            }
            // The sum adds at most half an ulp per coordinate; the scaling
            // back may lose bits only below 2^-1022.
            let sum = SQRT3 * f64::EPSILON * v.abs().max_element() + 4.0 * f64::MIN_POSITIVE;
            rounding = rounding.max(up(err + sum));
            vertices.push(v);
        }
        Ok((vertices, rounding))
    }
}

/// `√3`, rounded up.
const SQRT3: f64 = 1.732_050_807_568_877_4;

/// The point `z` on the three planes `n_j·z = t_j`, and a bound on its
/// Euclidean rounding error: Cramer's rule in floats with the
/// determinants' error bounds ([`bounds::det3`]) when they are small
/// against the determinant, else in exact arithmetic rounded once per
/// determinant.
fn solve_planes(rows: [(DVec3, f64); 3]) -> Result<(DVec3, f64), QueryError> {
    let n = rows.map(|(n, _)| n);
    let with_t = |k: usize| {
        rows.map(|(mut n, t)| {
            n[k] = t;
            n
        })
    };
    let (det, det_err) = bounds::det3(n, [0.0; 3]);
    if det_err.is_finite() && det_err * 1048576.0 < det.abs() {
        let mut z = DVec3::ZERO;
        let mut err = 0.0;
        for k in 0..3 {
            let (num, num_err) = bounds::det3(with_t(k), [0.0; 3]);
            z[k] = num / det;
            let e = (num_err + z[k].abs() * det_err) / (det.abs() - det_err)
                + z[k].abs() * f64::EPSILON;
            err += e * e;
        }
        return Ok((z, up(1.01 * err.sqrt())));
    }
    let exact_det = |rows: [DVec3; 3]| {
        let [a, b, c] = rows.map(exact::exact);
        exact::det3(&a, &b, &c)
    };
    let det = exact_det(n);
    let top = det.top_exponent().ok_or_else(|| {
        QueryError::Inconsistent("three planes of a slab vertex are dependent".into())
    })?;
    let d = det.to_f64_shifted(-top);
    let mut z = DVec3::ZERO;
    for k in 0..3 {
        z[k] = exact_det(with_t(k)).to_f64_shifted(-top) / d;
    }
    // Each determinant within 3u, the division u: 8·2^-52 relative, plus
    // underflow.
    Ok((
        z,
        up(8.0 * f64::EPSILON * z.length() + 4.0 * f64::MIN_POSITIVE),
    ))
}

/// The dual points `q_i = n_i / t_i` (`t_i > 0`) of a slab's planes, with
/// predicates exact for the rational points: homogeneous coordinates
/// `(n_i, t_i)`, so `det[q_b − q_a, q_c − q_a, q_d − q_a]` has the sign of
/// `−det[(n_a, t_a); (n_b, t_b); (n_c, t_c); (n_d, t_d)]`. A float filter
/// on the rounded `q_i` decides almost always; exact arithmetic otherwise.
struct PolarPoints<'a> {
    normals: &'a [DVec3],
    offsets: &'a [f64],
    /// `fl(n_i / t_i)`, each component within `u` of its own magnitude.
    q: Vec<DVec3>,
}

impl<'a> PolarPoints<'a> {
    fn new(normals: &'a [DVec3], offsets: &'a [f64]) -> Self {
        let q = normals.iter().zip(offsets).map(|(&n, &t)| n / t).collect();
        PolarPoints {
            normals,
            offsets,
            q,
        }
    }

    /// The homogeneous row `(n_i, t_i)`, exactly.
    fn row(&self, i: usize) -> [Dyadic; 4] {
        let n = self.normals[i];
        [n.x, n.y, n.z, self.offsets[i]].map(Dyadic::from_f64)
    }

    /// The 3×3 minor of rows `rows` and columns `cols`, exactly.
    fn minor(&self, rows: [usize; 3], cols: [usize; 3]) -> Dyadic {
        let [a, b, c] = rows.map(|i| {
            let r = self.row(i);
            cols.map(|j| r[j])
        });
        exact::det3(&a, &b, &c)
    }
}

impl crate::hull::HullPoints for PolarPoints<'_> {
    fn len(&self) -> usize {
        self.q.len()
    }

    fn coords(&self, i: usize) -> DVec3 {
        self.q[i]
    }

    fn orient(&self, a: usize, b: usize, c: usize, d: usize) -> Sign {
        // The rounded differences, each within ε(|q_i| + |q_a| + |v|)
        // componentwise (the quotients' and the subtraction's rounding).
        let diff = |i: usize| {
            let v = self.q[i] - self.q[a];
            let e = (self.q[i].abs() + self.q[a].abs() + v.abs()) * f64::EPSILON;
            (v, e.length())
        };
        let ((u, eu), (v, ev), (w, ew)) = (diff(b), diff(c), diff(d));
        let (det, bound) = bounds::det3([u, v, w], [eu, ev, ew]);
        if let Some(sign) = Sign::certified(det, bound + f64::MIN_POSITIVE) {
            return sign;
        }
        // Laplace along the offsets' column: det4 = Σ_i (−1)^(i+3) t_i M_i.
        let rows = [a, b, c, d];
        let mut det4 = Dyadic::zero();
        for skip in 0..4 {
            let mut rest = [0; 3];
            let mut k = 0;
            for (j, &r) in rows.iter().enumerate() {
                if j != skip {
                    rest[k] = r;
                    k += 1;
                }
            }
            let term = self
                .minor(rest, [0, 1, 2])
                .mul(&Dyadic::from_f64(self.offsets[rows[skip]]));
            det4 = if (skip + 3) % 2 == 0 {
                det4.add(&term)
            } else {
                det4.sub(&term)
            };
        }
        det4.sign().flip()
    }

    fn coincident(&self, a: usize, b: usize) -> bool {
        let (ra, rb) = (self.row(a), self.row(b));
        (0..4).all(|i| (i + 1..4).all(|j| exact::det2(&ra[i], &ra[j], &rb[i], &rb[j]).is_zero()))
    }

    fn collinear(&self, a: usize, b: usize, c: usize) -> bool {
        [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]
            .into_iter()
            .all(|cols| self.minor([a, b, c], cols).is_zero())
    }
}

/// The meshes of `slabs` ([`Slab::mesh`]) on rayon's threads, in order.
///
/// # Errors
/// The first error of [`Slab::mesh`], in order.
pub fn slab_meshes_par(slabs: &[Slab]) -> Result<Vec<PolygonMesh>, QueryError> {
    slabs.par_iter().map(Slab::mesh).collect()
}
