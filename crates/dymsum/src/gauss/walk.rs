//! Walking an arc of one map through the other (paper §4.3): from the cell
//! that holds its start to the cell that holds its end, reporting every arc
//! it crosses. Each convex cell is crossed once, so a walk takes at most `E`
//! steps; an exit that cannot be found is an internal inconsistency, reported
//! as [`crate::error::SumError::Inconsistent`].

use super::{edges_cross, GaussView};

impl GaussView<'_> {
    /// Walks the arc of edge `e` of the `other` map through this map, from
    /// the cell of `from` (which contains the arc's start) to the cell of
    /// `to` (which contains its end), calling `cross(edge)` for every arc of
    /// this map it crosses, in order (paper §4.3). Returns the number of
    /// cells visited. The walk crosses each convex cell once, so it needs at
    /// most `E` steps; exceeding that is reported as an error.
    pub fn walk_arc(
        &self,
        other: &GaussView<'_>,
        e: u32,
        from: u32,
        to: u32,
        cross: impl FnMut(u32),
    ) -> Result<usize, crate::error::SumError> {
        self.walk_arc_hinted(other, e, from, to, &[], cross)
    }

    /// [`GaussView::walk_arc`] with the arcs crossed before a small motion
    /// as a hint: in each cell the next hinted arc is tested first. An arc of
    /// the cell that the walked arc crosses, other than the one it entered
    /// by, is the unique exit of the convex cell, so the hint only changes
    /// the order of the tests, never the result.
    pub fn walk_arc_hinted(
        &self,
        other: &GaussView<'_>,
        e: u32,
        from: u32,
        to: u32,
        hint: &[u32],
        mut cross: impl FnMut(u32),
    ) -> Result<usize, crate::error::SumError> {
        let mut u = from;
        let mut came = u32::MAX;
        let mut steps = 0;
        let mut k = 0;
        while u != to {
            let ring = self.poly.ring(u as usize);
            let mut next = None;
            if let Some(&h) = hint.get(k) {
                if h != came {
                    if let Some(entry) = ring.iter().find(|r| r.edge == h) {
                        if edges_cross(other, e, self, h) {
                            next = Some(*entry);
                        }
                    }
                }
            }
            if next.is_none() {
                for entry in ring {
                    if entry.edge == came {
                        continue;
                    }
                    if edges_cross(other, e, self, entry.edge) {
                        next = Some(*entry);
                        break;
                    }
                }
            }
            let Some(entry) = next else {
                return Err(crate::error::SumError::Inconsistent(format!(
                    "arc walk found no exit from cell {u}"
                )));
            };
            cross(entry.edge);
            k = match hint.iter().position(|&h| h == entry.edge) {
                Some(i) => i + 1,
                None => k,
            };
            came = entry.edge;
            u = entry.neighbor;
            steps += 1;
            if steps > self.poly.edge_count() {
                return Err(crate::error::SumError::Inconsistent(
                    "arc walk did not terminate".into(),
                ));
            }
        }
        Ok(steps)
    }
}
