//! `brute`: the paper's baseline (§3, Algorithm 3.1).
//!
//! Tests every (face of P, vertex of Q) and (vertex of P, face of Q) pair for
//! compatibility (normal inside the vertex's Gaussian cell) and every (edge of
//! P, edge of Q) pair for crossing arcs, with the exact perturbed predicates
//! of [`super::overlay`]. O(m·n) predicates; no search structure, no
//! seeding, so it shares nothing with `walk` but the predicates.
//! Degeneracies: all ties broken by SoS, so exactly one cell contains each
//! normal; finding zero or two is reported as an internal inconsistency.

use super::{Operands, Overlay, SumError};
use crate::gauss::{edges_cross, GaussView};
use crate::polytope::FaceNormal;

fn containing_vertex(cells: &GaussView<'_>, x: &FaceNormal<'_>) -> Result<u32, SumError> {
    let mut found = None;
    for v in 0..cells.poly.vertex_count() as u32 {
        if cells.in_cell(v, x) {
            if found.is_some() {
                return Err(SumError::Inconsistent(format!(
                    "normal {} lies in two cells",
                    x.idx
                )));
            }
            found = Some(v);
        }
    }
    found.ok_or_else(|| SumError::Inconsistent(format!("normal {} lies in no cell", x.idx)))
}

pub(crate) fn overlay(ops: &Operands) -> Result<Overlay, SumError> {
    let (vp, vq) = (ops.view_p(), ops.view_q());
    let fv = (0..ops.p.face_count() as u32)
        .map(|f| containing_vertex(&vq, &vp.normal(f)))
        .collect::<Result<Vec<_>, _>>()?;
    let vf = (0..ops.q.face_count() as u32)
        .map(|g| containing_vertex(&vp, &vq.normal(g)))
        .collect::<Result<Vec<_>, _>>()?;
    let mut ee = Vec::new();
    for e in 0..ops.p.edge_count() as u32 {
        for e2 in 0..ops.q.edge_count() as u32 {
            if edges_cross(&vp, e, &vq, e2) {
                ee.push((e, e2));
            }
        }
    }
    Ok(Overlay { fv, vf, ee })
}
