//! The report of one DYMSUM step ([`UpdateReport`]) and the diff of two
//! overlays (used when a step is recomputed from scratch).
//!
//! `overlay_diff` compares fv- and vf-pairs by face and merges the two
//! sorted ee-lists: O(m + n + k), no hashing.

use super::*;

/// What one update changed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct UpdateReport {
    /// Faces of P or Q whose compatible vertex changed (fv- and vf-errors).
    pub fv_errors: usize,
    /// ee-pairs that stopped being compatible.
    pub ee_errors: usize,
    /// Facets of the previous sum that are gone.
    pub removed: Vec<Facet>,
    /// Facets of the new sum that were not in the previous one.
    pub added: Vec<Facet>,
    /// Gaussian arcs re-walked to repair ee-pairs.
    pub rewalked_arcs: usize,
    /// Face normals whose cell was checked (the others were certified to
    /// stay in their cells by their margins).
    pub checked_normals: usize,
    /// Face normals that changed cell across exactly one arc, repaired by
    /// toggling instead of re-walking.
    pub certified_crossings: usize,
    /// The relative rotation angle of the step (radians).
    pub step_angle: f64,
    /// The step was recomputed from scratch (large step or too many arcs at
    /// risk).
    pub recomputed: bool,
    /// `Some(reason)` when the incremental repair met an internal
    /// inconsistency (a bug, never a property of the input) and the step was
    /// recomputed from scratch instead; the result is exact either way. The
    /// test suites check that this never happens.
    pub recovered: Option<String>,
}

/// The facets of `before` missing from `after`, and those of `after`
/// missing from `before`: fv- and vf-pairs compared by face, ee-pairs by
/// merging the two sorted lists. O(m + n + k), no hashing.
pub(super) fn overlay_diff(before: &Overlay, after: &Overlay) -> (Vec<Facet>, Vec<Facet>) {
    let (mut removed, mut added) = (Vec::new(), Vec::new());
    for (f, (&u, &v)) in before.fv.iter().zip(&after.fv).enumerate() {
        if u != v {
            removed.push(Facet::Fv {
                p_face: f as u32,
                q_vertex: u,
            });
            added.push(Facet::Fv {
                p_face: f as u32,
                q_vertex: v,
            });
        }
    }
    for (g, (&u, &v)) in before.vf.iter().zip(&after.vf).enumerate() {
        if u != v {
            removed.push(Facet::Vf {
                p_vertex: u,
                q_face: g as u32,
            });
            added.push(Facet::Vf {
                p_vertex: v,
                q_face: g as u32,
            });
        }
    }
    let ee = |(p_edge, q_edge): (u32, u32)| Facet::Ee { p_edge, q_edge };
    let (x, y) = (&before.ee, &after.ee);
    let (mut i, mut j) = (0, 0);
    while i < x.len() || j < y.len() {
        match (x.get(i), y.get(j)) {
            (Some(a), Some(b)) if a == b => {
                i += 1;
                j += 1;
            }
            (Some(&a), Some(&b)) if a < b => {
                removed.push(ee(a));
                i += 1;
            }
            (Some(&a), None) => {
                removed.push(ee(a));
                i += 1;
            }
            (_, Some(&b)) => {
                added.push(ee(b));
                j += 1;
            }
            (None, None) => unreachable!("the loop condition excludes it"),
        }
    }
    (removed, added)
}

impl UpdateReport {
    /// Empties the report, keeping its vectors' capacity.
    pub fn clear(&mut self) {
        let (mut removed, mut added) = (
            std::mem::take(&mut self.removed),
            std::mem::take(&mut self.added),
        );
        removed.clear();
        added.clear();
        *self = UpdateReport {
            removed,
            added,
            ..UpdateReport::default()
        };
    }

    /// Records the fv- and vf-errors FindErrors found (and corrected), and
    /// what it checked.
    pub(super) fn record_fv_errors(&mut self, [scan_p, scan_q]: &[SideScan; 2]) {
        for c in &scan_p.changed {
            self.removed.push(Facet::Fv {
                p_face: c.face,
                q_vertex: c.old,
            });
            self.added.push(Facet::Fv {
                p_face: c.face,
                q_vertex: c.new,
            });
        }
        for c in &scan_q.changed {
            self.removed.push(Facet::Vf {
                p_vertex: c.old,
                q_face: c.face,
            });
            self.added.push(Facet::Vf {
                p_vertex: c.new,
                q_face: c.face,
            });
        }
        self.fv_errors = self.removed.len();
        self.checked_normals = scan_p.checked + scan_q.checked;
        self.certified_crossings = scan_p.certified.len() + scan_q.certified.len();
    }
}
