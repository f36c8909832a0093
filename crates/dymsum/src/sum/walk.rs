//! `walk`: the output-sensitive static sum (paper §4.2 and §4.3 run for
//! every feature).
//!
//! Steps:
//! 1. fv-pairs: visit P's faces in breadth-first order over face adjacency;
//!    locate each face normal in Q's map by hill climbing from the vertex
//!    found for an already solved neighbouring face (the first face is seeded
//!    by a float support query). vf-pairs symmetrically.
//! 2. ee-pairs: for every edge of P, walk its Gaussian arc through Q's map
//!    from the cell of its left face's vertex to the cell of its right
//!    face's vertex, recording every arc of Q it crosses.
//!
//! Complexity: O(m + n + k) for k ee-facets, since neighbouring normals lie in
//! nearby cells and each arc walk costs the cells it crosses.
//! Degeneracies: every decision is an exact SoS predicate, so ties are broken
//! exactly as in `brute`; hill climbing falls back to an exhaustive exact
//! scan if rounding-level degeneracies ever made it cycle.

use super::{Operands, Overlay, SumError};
use crate::gauss::GaussView;
use std::collections::VecDeque;

/// Locates every face normal of `faces` in the cells of `cells`, seeding each
/// search from a solved neighbour.
fn locate_all(faces: &GaussView<'_>, cells: &GaussView<'_>) -> Vec<u32> {
    let nf = faces.poly.face_count();
    let mut out = vec![u32::MAX; nf];
    let mut queue = VecDeque::with_capacity(nf);
    let first_seed = cells.poly.support_vertex(faces.n(0)) as u32;
    out[0] = cells.locate(&faces.normal(0), first_seed).0;
    queue.push_back(0u32);
    while let Some(f) = queue.pop_front() {
        let seed = out[f as usize];
        for &e in faces.poly.face_edges(f as usize) {
            let [f0, f1] = faces.poly.edge(e as usize).faces;
            let g = if f0 == f { f1 } else { f0 };
            if out[g as usize] == u32::MAX {
                out[g as usize] = cells.locate(&faces.normal(g), seed).0;
                queue.push_back(g);
            }
        }
    }
    out
}

/// The ee-pairs along edge `e` of P, given the fv-pairs: appends
/// `(e, edge of Q)` for every arc of Q the arc of `e` crosses.
pub fn walk_ee_of_p_edge(
    ops: &Operands,
    fv: &[u32],
    e: u32,
    out: &mut Vec<(u32, u32)>,
) -> Result<usize, SumError> {
    let (vp, vq) = (ops.view_p(), ops.view_q());
    let [f0, f1] = ops.p.edge(e as usize).faces;
    vq.walk_arc(&vp, e, fv[f0 as usize], fv[f1 as usize], |e2| {
        out.push((e, e2))
    })
}

/// The full overlay by walking.
pub fn overlay(ops: &Operands) -> Result<Overlay, SumError> {
    let (vp, vq) = (ops.view_p(), ops.view_q());
    let fv = locate_all(&vp, &vq);
    let vf = locate_all(&vq, &vp);
    let mut ee = Vec::new();
    for e in 0..ops.p.edge_count() as u32 {
        walk_ee_of_p_edge(ops, &fv, e, &mut ee)?;
    }
    ee.sort_unstable();
    Ok(Overlay { fv, vf, ee })
}
