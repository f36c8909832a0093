//! `hull`: the convex hull of all m·n pairwise vertex sums — the way other
//! libraries compute convex Minkowski sums — kept as a baseline.
//!
//! Steps:
//! 1. the exact hull ([`crate::hull::convex_hull`]) of the sums
//!    `p_i + q_j`, with an exact orientation predicate on the *real* sums
//!    (rounded float sums would break parallelogram faces);
//! 2. each hull face `F` has the vertex sets `S_P`, `S_Q` of its corners;
//!    its facets are found by a local brute force over the features inside
//!    or next to them (faces and edges of P at a vertex of `S_P` against
//!    vertices and edges of Q at `S_Q`) with the same SoS predicates as the
//!    other methods, so a
//!    degenerate face such as `f ⊕ g` for parallel faces is split exactly as
//!    `brute` and `walk` split it.
//!
//! Complexity: O(mn log mn) for the hull. Degeneracies: exact planarity of
//! sums; when P is rotated its rounded vertices are no longer exactly
//! coplanar, and the hull sees a slightly different shape than the exact
//! normals; the generous candidate sets absorb that. Any remaining mismatch
//! is detected (every face of P and Q must get exactly one vertex and the
//! facets must form a closed 2-manifold) and reported as
//! [`SumError::HullMismatch`], never returned as a wrong answer.

use super::{Operands, Overlay, SumError};
use crate::gauss::edges_cross;
use crate::hull::{convex_hull, PairwiseSums};
use crate::polytope::Polytope;
use std::collections::BTreeSet;

/// Faces and edges of `poly` incident to a vertex of `set`: the candidate
/// features of a hull face. Rounded rotated vertices can split a face of P
/// over several hull faces, so candidates are generous; the exact
/// predicates decide, and extra candidates cannot change their answers.
fn features_near(poly: &Polytope, set: &[u32]) -> (Vec<u32>, Vec<u32>) {
    let mut faces = BTreeSet::new();
    let mut edges = BTreeSet::new();
    for &v in set {
        for r in poly.ring(v as usize) {
            faces.insert(r.face);
            edges.insert(r.edge);
        }
    }
    (faces.into_iter().collect(), edges.into_iter().collect())
}

/// Scales both posed vertex sets by one power of two (their common frame,
/// largest magnitude in `[1, 2)`) when that is exact for every coordinate.
/// The hull's exact predicates answer the same either way; its float
/// heuristics then see bit-identical input for the same pair at any scale
/// `2^k`, and pairwise sums cannot overflow.
fn to_common_frame(p_points: &mut [glam::DVec3], q_points: &mut [glam::DVec3]) {
    use crate::kernel::exact::{frame_exponent, mul_pow2, mul_pow2_vec};
    let k = frame_exponent(
        p_points
            .iter()
            .chain(q_points.iter())
            .flat_map(|v| v.to_array()),
    );
    let exact = p_points
        .iter()
        .chain(q_points.iter())
        .flat_map(|v| v.to_array())
        .all(|x| mul_pow2(mul_pow2(x, k), -k) == x);
    if k == 0 || !exact {
        return;
    }
    for v in p_points.iter_mut().chain(q_points.iter_mut()) {
        *v = mul_pow2_vec(*v, k);
    }
}

pub(super) fn overlay(ops: &Operands) -> Result<Overlay, SumError> {
    let mut p_points: Vec<_> = (0..ops.p.vertex_count() as u32)
        .map(|u| ops.p_vertex(u))
        .collect();
    let mut q_points: Vec<_> = (0..ops.q.vertex_count() as u32)
        .map(|w| ops.q_vertex(w))
        .collect();
    to_common_frame(&mut p_points, &mut q_points);
    let sums = PairwiseSums {
        p: &p_points,
        q: &q_points,
    };
    let hull = convex_hull(&sums).map_err(|e| SumError::HullMismatch(e.to_string()))?;
    let (vp, vq) = (ops.view_p(), ops.view_q());
    let mut fv = vec![u32::MAX; ops.p.face_count()];
    let mut vf = vec![u32::MAX; ops.q.face_count()];
    let mut ee = BTreeSet::new();
    let assign = |slot: &mut u32, v: u32, what: &str| -> Result<(), SumError> {
        if *slot != u32::MAX && *slot != v {
            return Err(SumError::HullMismatch(format!("{what} gets two vertices")));
        }
        *slot = v;
        Ok(())
    };
    for face in &hull.faces {
        let mut sp: Vec<u32> = face.iter().map(|&k| sums.split(k).0 as u32).collect();
        let mut sq: Vec<u32> = face.iter().map(|&k| sums.split(k).1 as u32).collect();
        sp.sort_unstable();
        sp.dedup();
        sq.sort_unstable();
        sq.dedup();
        let (pf, pe) = features_near(&ops.p, &sp);
        let (qf, qe) = features_near(&ops.q, &sq);
        for &f in &pf {
            if fv[f as usize] != u32::MAX {
                continue;
            }
            for &w in &sq {
                if vq.in_cell(w, &vp.normal(f)) {
                    assign(&mut fv[f as usize], w, "a face of P")?;
                }
            }
        }
        for &g in &qf {
            if vf[g as usize] != u32::MAX {
                continue;
            }
            for &u in &sp {
                if vp.in_cell(u, &vq.normal(g)) {
                    assign(&mut vf[g as usize], u, "a face of Q")?;
                }
            }
        }
        for &e in &pe {
            for &e2 in &qe {
                if edges_cross(&vp, e, &vq, e2) {
                    ee.insert((e, e2));
                }
            }
        }
    }
    if let Some(f) = fv.iter().position(|&v| v == u32::MAX) {
        return Err(SumError::HullMismatch(format!(
            "face {f} of P has no vertex of Q"
        )));
    }
    if let Some(g) = vf.iter().position(|&v| v == u32::MAX) {
        return Err(SumError::HullMismatch(format!(
            "face {g} of Q has no vertex of P"
        )));
    }
    let overlay = Overlay {
        fv,
        vf,
        ee: ee.into_iter().collect(),
    };
    // A crossing the hull did not expose would leave a hole: check.
    super::merge::check_facet_complex(ops, &overlay)
        .map_err(|e| SumError::HullMismatch(e.to_string()))?;
    Ok(overlay)
}
