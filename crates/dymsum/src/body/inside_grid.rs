//! Containment at a cost that does not grow with the triangles: a grid
//! over a body's solids, in the body's own frame, whose cells that meet no
//! triangle of a solid are classified once, as inside a solid or outside
//! every one ([`InsideGrid`]). A point that lies in such a cell is
//! answered by reading it; any other point by a ray ([`super::winding`]).
//!
//! # Why a cell's answer is each of its points' answer
//! A solid component's winding number about a point (its triangles' signed
//! ray crossings, [`super::winding`]) changes only where the point crosses
//! one of its triangles. A closed cell that meets no triangle of any solid
//! component is connected, so every point of it has the same winding
//! numbers (per obstacle of a joined scene); so has the union of two such
//! cells that share a face, which is connected too and meets no triangle.
//! The empty cells therefore fall into regions (connected through shared
//! faces) on which "inside some solid" is one answer: the exact ray from
//! the centre of one cell of the region (the computed midpoint of its
//! planes, clamped to them: for a cell of zero width at an odd multiple
//! of the least subnormal the midpoint rounds outside it; so in the cell,
//! on no triangle) decides it. A region
//! whose rays are degenerate in every direction (never seen), and every
//! cell that meets a triangle, stay unclassified, and points there are
//! decided by their own rays.
//!
//! A cell is *empty* when the certified separating-axis test
//! along the triangle's plane ([`PlaneAxis`]) parts it from every triangle of a solid
//! component whose box reaches it (the test is made on blocks of cells
//! first and split down to single cells only where it cannot part the
//! block). A test that cannot part them marks the cell as meeting the
//! triangle: a false "meets" only sends that cell's points to the ray.
//!
//! # Windings kept
//! The ray that classifies a region finds the winding number of each
//! source about its cell's centre, and every point of the region has the
//! same ones (above). An inside region's windings (sources with a number
//! other than zero, sorted, the same list for every region that has it)
//! are kept in a table of at most [`WINDINGS_KEPT`] distinct lists, and the
//! region's cells say which: [`InsideGrid::windings_at`] reads them (an
//! empty list for an outside cell), so a containment segment may start from a point
//! of an inside cell as from one of an outside cell (`body::winding`, "A
//! start outside"). A region whose list finds no room (more distinct ones
//! than the table holds; never seen) is inside with no windings kept, and
//! is never a start. Test: `classified_cells_answer_as_the_ray` (the kept
//! windings are each point's own ray's, source by source: nested shells,
//! a cavity, touching and joined solids, two sources side by side).
//!
//! An independent review (2026-12-02, ninth stop) found this sound: the
//! grid is read at a pose only with the matrix near a rotation and
//! `det M > 0.5` (so each number keeps its sign), a component whose box
//! misses a segment keeps its number along it (its entry carried
//! unchanged), the codes fit (252 lists, `EMPTY` only while building), and
//! a block of classified cells is one region (one code). Its randomized
//! comparison, 68,640 states (nested shells winding 2, inward shells
//! winding −1 and −2, solids in cavities, two and three joined sources,
//! scales 10⁻³ to 10³, offsets to 3·10⁸, quarter and nudged turns), with
//! 53,364 segments started in inside cells, found no disagreement with
//! an oracle that reads no grid. Its coverage remark (no test failed when
//! the kept windings were all given to source 0) is applied: the two
//! sources side by side; and its wording remarks.
//!
//! # Asking
//! [`InsideGrid::classify`] answers for a point known to within `e` per
//! coordinate (`e = 0`: the point itself) when the box of half-width `e`
//! about it lies in one classified cell: every point of that box then has
//! the cell's answer. The box's ends are computed widened (`2e` plus four
//! ulps of the coordinate), so that their rounding cannot narrow it, and
//! compared with the cell's planes exactly. How a posed body's point is
//! carried back into the body's frame, and why the answer there is the
//! answer at the pose, is `query::scene::state`'s ("The grid at a pose").
//!
//! # Size
//! About two cells per triangle of the solids (at least 27; fewer where
//! the near-cubic counts, at most 1024 an axis, would exceed
//! [`MAX_CELLS`]), one byte each; building marks each
//! triangle's cells (the blocks its box reaches, split where the test
//! cannot part them) and casts one ray per region, at most [`MAX_RAYS`]
//! (regions beyond that stay unclassified).

use glam::DVec3;

use super::winding::{some_winds, Windings};
use super::MeshBody;
use crate::kernel::separation::PlaneAxis;
use crate::sanity::SanityError;
use crate::solid::aabb::Aabb;
use crate::solid::soup::ComponentKind;

/// The most cells a grid has (one byte each).
pub(crate) const MAX_CELLS: usize = 1 << 18;

/// The most regions a grid classifies by a ray each.
pub(crate) const MAX_RAYS: usize = 1024;

/// A cell that meets a triangle of a solid, or a region left
/// unclassified: its points are asked by a ray.
const UNKNOWN: u8 = 0;
/// Outside every solid: every source winds zero times.
const OUTSIDE: u8 = 1;
/// Inside a solid, its windings not kept (more distinct ones than
/// [`WINDINGS_KEPT`]).
const INSIDE: u8 = 2;
/// Inside a solid with the windings `InsideGrid::windings[code − 3]`
/// (module docs, "Windings kept").
const INSIDE_KEPT: u8 = 3;
/// The most distinct windings a grid keeps.
const WINDINGS_KEPT: usize = (EMPTY - INSIDE_KEPT) as usize;
/// While building: empty, its region not yet walked.
const EMPTY: u8 = u8::MAX;

/// Whether a cell's class is inside a solid (kept windings or not).
fn is_inside(class: u8) -> bool {
    (INSIDE..EMPTY).contains(&class)
}

/// The box asked for a point `x` known to within `e` per coordinate
/// (module docs, "Asking"): the point itself where `e = 0`, else widened
/// by `2e` plus four ulps of the coordinate, so that rounding cannot
/// narrow it.
fn widened(x: DVec3, e: f64) -> (DVec3, DVec3) {
    if e == 0.0 {
        return (x, x);
    }
    let w = DVec3::splat(2.0 * e) + 4.0 * f64::EPSILON * x.abs();
    (x - w, x + w)
}

/// A body's empty cells classified as inside a solid or outside every one
/// (module docs).
#[derive(Clone, Debug, Default)]
pub(crate) struct InsideGrid {
    /// The cells' planes along each axis, nondecreasing: cell `i` along
    /// axis `k` is `[planes[k][i], planes[k][i + 1]]`.
    planes: [Vec<f64>; 3],
    /// Cells per unit length along each axis (`n / (planes[n] − planes[0])`:
    /// [`InsideGrid::guess`]'s scale, computed once).
    scale: [f64; 3],
    /// Each cell's class (`UNKNOWN`, `OUTSIDE`, `INSIDE`, or
    /// `INSIDE_KEPT + k` for the windings `windings[k]`), `x` fastest.
    cells: Vec<u8>,
    /// The distinct windings of the inside regions, sorted by source,
    /// without zeros (module docs, "Windings kept").
    windings: Vec<Windings>,
}

impl InsideGrid {
    /// The grid of `body`'s solid components (empty when it has none).
    pub(crate) fn new(body: &MeshBody) -> InsideGrid {
        let is_solid =
            |t: usize| body.components[body.component_of[t] as usize].0 == ComponentKind::Solid;
        let solid = (0..body.triangles.len()).filter(|&t| is_solid(t)).count();
        let around = body.solid_components.iter().fold(Aabb::EMPTY, |b, &c| {
            b.join(&body.component_boxes[c as usize])
        });
        let (lo, hi) = (DVec3::from(around.lo), DVec3::from(around.hi));
        let extent = hi - lo;
        if solid == 0 || !(extent.min_element() > 0.0 && extent.is_finite()) {
            return InsideGrid::default();
        }
        // Near-cubic cells: edge `h` with about `target` of them in the box
        // (from the logarithms, which neither overflow nor underflow),
        // fewer while the rounded and clamped counts exceed the most.
        let counts_for = |target: f64| {
            let log_h = (extent.x.ln() + extent.y.ln() + extent.z.ln() - target.ln()) / 3.0;
            [0, 1, 2].map(|k| {
                let n = (extent[k].ln() - log_h).exp().round();
                if n.is_finite() {
                    (n as usize).clamp(1, 1024)
                } else {
                    1
                }
            })
        };
        let mut target = (2 * solid).clamp(27, MAX_CELLS) as f64;
        let mut counts = counts_for(target);
        while counts.iter().product::<usize>() > MAX_CELLS {
            target *= 0.75;
            counts = counts_for(target);
        }
        let planes = [0, 1, 2].map(|k| {
            let n = counts[k];
            let mut p: Vec<f64> = (0..=n)
                .map(|i| (lo[k] + extent[k] * (i as f64 / n as f64)).min(hi[k]))
                .collect();
            p[0] = lo[k];
            p[n] = hi[k];
            p
        });
        let scale = [0, 1, 2].map(|k| counts[k] as f64 / (planes[k][counts[k]] - planes[k][0]));
        let mut grid = InsideGrid {
            planes,
            scale,
            cells: vec![EMPTY; counts.iter().product()],
            windings: Vec::new(),
        };
        let mag = lo.abs().max(hi.abs());
        for t in (0..body.triangles.len()).filter(|&t| is_solid(t)) {
            let tri = body.triangles[t].map(|v| body.vertices[v as usize]);
            grid.mark_meeting(&tri, mag);
        }
        grid.classify_regions(body);
        grid
    }

    /// The number of cells along each axis.
    fn counts(&self) -> [usize; 3] {
        [0, 1, 2].map(|k| self.planes[k].len().saturating_sub(1))
    }

    fn index(&self, c: [usize; 3]) -> usize {
        let n = self.counts();
        c[0] + n[0] * (c[1] + n[1] * c[2])
    }

    /// The cells `from..=to` (per axis) as one box.
    fn block(&self, from: [usize; 3], to: [usize; 3]) -> (DVec3, DVec3) {
        let lo = [0, 1, 2].map(|k| self.planes[k][from[k]]);
        let hi = [0, 1, 2].map(|k| self.planes[k][to[k] + 1]);
        (DVec3::from(lo), DVec3::from(hi))
    }

    /// The cell along axis `k` that `x` would lie in if the planes were
    /// exactly evenly spaced (a start, settled by comparing with them).
    fn guess(&self, k: usize, x: f64) -> usize {
        let p = &self.planes[k];
        // `as` saturates (NaN to 0); a signed conversion is the cheaper.
        (((x - p[0]) * self.scale[k]) as i64).clamp(0, p.len() as i64 - 2) as usize
    }

    /// The cells along axis `k` that meet `[lo, hi]` (`from > to` when
    /// none): those with `planes[i] <= hi` and `lo <= planes[i + 1]`,
    /// found from the planes' even spacing and settled by comparing with
    /// the planes themselves.
    fn cells_meeting(&self, k: usize, lo: f64, hi: f64) -> (usize, usize) {
        let p = &self.planes[k];
        let n = p.len() - 1;
        let mut from = self.guess(k, lo);
        while from > 0 && p[from] >= lo {
            from -= 1;
        }
        while from < n - 1 && p[from + 1] < lo {
            from += 1;
        }
        let mut to = self.guess(k, hi);
        while to < n - 1 && p[to + 1] <= hi {
            to += 1;
        }
        while to > 0 && p[to] > hi {
            to -= 1;
        }
        if p[from] > hi || p[to + 1] < lo {
            return (1, 0);
        }
        (from, to)
    }

    /// Marks `UNKNOWN` every cell the triangle may meet: those its box
    /// reaches, split into blocks its plane parts from it where it can
    /// (`mag` bounds every coordinate of the grid and the triangle).
    fn mark_meeting(&mut self, tri: &[DVec3; 3], mag: DVec3) {
        let lo = tri[0].min(tri[1]).min(tri[2]);
        let hi = tri[0].max(tri[1]).max(tri[2]);
        let mut from = [0; 3];
        let mut to = [0; 3];
        for k in 0..3 {
            (from[k], to[k]) = self.cells_meeting(k, lo[k], hi[k]);
            if from[k] > to[k] {
                return;
            }
        }
        if from == to {
            // The triangle lies in this cell.
            let i = self.index(from);
            self.cells[i] = UNKNOWN;
            return;
        }
        let plane = PlaneAxis::new(tri, mag);
        if (0..3).map(|k| to[k] - from[k] + 1).product::<usize>() <= 16 {
            // A few cells: each tested, unless already marked.
            for z in from[2]..=to[2] {
                for y in from[1]..=to[1] {
                    for x in from[0]..=to[0] {
                        self.mark_cell(&plane, [x, y, z]);
                    }
                }
            }
            return;
        }
        self.mark_block(&plane, from, to);
    }

    /// Marks cell `c` unless it is marked already or the plane parts it.
    fn mark_cell(&mut self, plane: &PlaneAxis, c: [usize; 3]) {
        let i = self.index(c);
        if self.cells[i] != UNKNOWN {
            let (lo, hi) = self.block(c, c);
            if !plane.parts(lo, hi) {
                self.cells[i] = UNKNOWN;
            }
        }
    }

    fn mark_block(&mut self, plane: &PlaneAxis, from: [usize; 3], to: [usize; 3]) {
        if from == to {
            self.mark_cell(plane, from);
            return;
        }
        let (lo, hi) = self.block(from, to);
        if plane.parts(lo, hi) {
            return;
        }
        let widest = (0..3).max_by_key(|&k| to[k] - from[k]).unwrap_or(0);
        let mid = (from[widest] + to[widest]) / 2;
        let (mut left_to, mut right_from) = (to, from);
        left_to[widest] = mid;
        right_from[widest] = mid + 1;
        self.mark_block(plane, from, left_to);
        self.mark_block(plane, right_from, to);
    }

    /// Walks the empty cells' regions (through shared faces) and classifies
    /// each by one ray from its first cell's centre (module docs), at most
    /// [`MAX_RAYS`] of them, writing the class as it walks.
    fn classify_regions(&mut self, body: &MeshBody) {
        let n = self.counts();
        let at = |i: usize| [i % n[0], i / n[0] % n[1], i / (n[0] * n[1])];
        let mut stack: Vec<u32> = Vec::new();
        let mut parity = Vec::new();
        let mut rays = 0;
        for start in 0..self.cells.len() {
            if self.cells[start] != EMPTY {
                continue;
            }
            let class = if rays < MAX_RAYS {
                rays += 1;
                let (lo, hi) = self.block(at(start), at(start));
                let centre = (0.5 * lo + 0.5 * hi).clamp(lo, hi);
                match body.windings_by_ray(centre, &mut parity) {
                    Some(w) if some_winds(&w) => self.keep(w),
                    Some(_) => OUTSIDE,
                    None => UNKNOWN,
                }
            } else {
                UNKNOWN
            };
            self.cells[start] = class;
            stack.push(start as u32);
            while let Some(i) = stack.pop() {
                let c = at(i as usize);
                for k in 0..3 {
                    for next in [c[k].wrapping_sub(1), c[k] + 1] {
                        if next >= n[k] {
                            continue;
                        }
                        let mut d = c;
                        d[k] = next;
                        let j = self.index(d);
                        if self.cells[j] == EMPTY {
                            self.cells[j] = class;
                            stack.push(j as u32);
                        }
                    }
                }
            }
        }
    }

    /// The class of an inside region whose ray found the windings `w`
    /// (module docs, "Windings kept"): `INSIDE_KEPT` plus their index
    /// among those kept, kept if new and room is left, else `INSIDE`.
    fn keep(&mut self, mut w: Windings) -> u8 {
        w.retain(|e| e.1 != 0);
        w.sort_unstable();
        let k = match self.windings.iter().position(|kept| *kept == w) {
            Some(k) => k,
            None if self.windings.len() < WINDINGS_KEPT => {
                self.windings.push(w);
                self.windings.len() - 1
            }
            None => return INSIDE,
        };
        INSIDE_KEPT + k as u8
    }

    /// Whether the point `x` of the body's frame lies inside a solid, when
    /// the grid knows: the box of half-width `e` about it lies in one
    /// classified cell (module docs, "Asking"); `None` otherwise.
    #[inline]
    pub(crate) fn classify(&self, x: DVec3, e: f64) -> Option<bool> {
        let (lo, hi) = widened(x, e);
        self.classify_box(lo, hi)
    }

    /// Whether every point of the box `[lo, hi]` of the body's frame lies
    /// inside a solid, or every one outside, when the box lies in one
    /// classified cell; `None` otherwise.
    #[inline]
    pub(crate) fn classify_box(&self, lo: DVec3, hi: DVec3) -> Option<bool> {
        match self.class_of_box(lo, hi)? {
            OUTSIDE => Some(false),
            class if is_inside(class) => Some(true),
            _ => None,
        }
    }

    /// The windings about every point of the box of half-width `e` about
    /// `x` (as [`InsideGrid::classify`] widens it), when that box lies in
    /// one classified cell whose windings are known: outside (none wind)
    /// or an inside region's kept ones (module docs, "Windings kept").
    pub(crate) fn windings_at(&self, x: DVec3, e: f64) -> Option<Windings> {
        let (lo, hi) = widened(x, e);
        match self.class_of_box(lo, hi)? {
            OUTSIDE => Some(Windings::new()),
            class if (INSIDE_KEPT..EMPTY).contains(&class) => {
                Some(self.windings[usize::from(class - INSIDE_KEPT)].clone())
            }
            _ => None,
        }
    }

    /// The class of the one cell holding the box `[lo, hi]`; `None` where
    /// no cell holds it.
    #[inline]
    fn class_of_box(&self, lo: DVec3, hi: DVec3) -> Option<u8> {
        if self.cells.is_empty() {
            return None;
        }
        let mut index = 0;
        let mut stride = 1;
        for k in 0..3 {
            let (lo, hi) = (lo[k], hi[k]);
            let p = &self.planes[k];
            let n = p.len() - 1;
            // The cell with `p[i] <= lo < p[i + 1]`, from the planes' even
            // spacing, settled by comparing with them.
            let mut i = self.guess(k, lo);
            while i > 0 && p[i] > lo {
                i -= 1;
            }
            while i < n - 1 && p[i + 1] <= lo {
                i += 1;
            }
            if !(p[i] <= lo && hi <= p[i + 1]) {
                return None;
            }
            index += i * stride;
            stride *= n;
        }
        Some(self.cells[index])
    }

    /// The widest cell's width along any axis (zero for an empty grid).
    pub(crate) fn cell_width(&self) -> f64 {
        if self.cells.is_empty() {
            return 0.0;
        }
        self.scale.iter().fold(0.0, |w, &s| w.max(1.0 / s))
    }

    /// Whether a box `width` wide along
    /// every axis is at most `cells` cells wide along each (computed
    /// loosely: only whether [`InsideGrid::classify_cells`] is worth
    /// asking, which decides exactly).
    pub(crate) fn spans_at_most(&self, width: f64, cells: f64) -> bool {
        !self.cells.is_empty() && self.scale.iter().all(|&s| width * s <= cells)
    }

    /// Whether every point of the box `[lo, hi]` of the body's frame lies
    /// inside a solid, or every one outside, when the box lies in the
    /// grid and the (closed) cells it meets, at most `most` of them, are
    /// all classified alike; `None` otherwise. Each point of the box lies
    /// in one of those cells and has its answer, the same for all. (A
    /// block of classified cells is always classified alike: cells that
    /// share a face and meet no triangle are one region. The comparison
    /// costs little and does not rely on it.)
    pub(crate) fn classify_cells(&self, lo: DVec3, hi: DVec3, most: usize) -> Option<bool> {
        if self.cells.is_empty() {
            return None;
        }
        let mut range = [(0, 0); 3];
        let mut count = 1;
        for k in 0..3 {
            let p = &self.planes[k];
            if !(p[0] <= lo[k] && lo[k] <= hi[k] && hi[k] <= p[p.len() - 1]) {
                return None;
            }
            let (from, to) = self.cells_meeting(k, lo[k], hi[k]);
            if from > to {
                return None;
            }
            count *= to - from + 1;
            if count > most {
                return None;
            }
            range[k] = (from, to);
        }
        let first = self.cells[self.index([range[0].0, range[1].0, range[2].0])];
        if first != OUTSIDE && !is_inside(first) {
            return None;
        }
        for z in range[2].0..=range[2].1 {
            for y in range[1].0..=range[1].1 {
                for x in range[0].0..=range[0].1 {
                    if self.cells[self.index([x, y, z])] != first {
                        return None;
                    }
                }
            }
        }
        Some(is_inside(first))
    }

    /// The cells' planes along each axis (for tests).
    #[cfg(test)]
    pub(crate) fn planes(&self) -> &[Vec<f64>; 3] {
        &self.planes
    }

    /// The share of cells classified.
    #[cfg(test)]
    pub(crate) fn classified(&self) -> f64 {
        let known = self.cells.iter().filter(|&&c| c != UNKNOWN).count();
        known as f64 / self.cells.len().max(1) as f64
    }

    /// Checks the grid's invariants: nondecreasing finite planes, one cell
    /// per triple of intervals, each cell's class a final one.
    ///
    /// # Errors
    /// [`SanityError::MeshBody`] naming the broken invariant.
    pub(crate) fn sanity_check(&self) -> Result<(), SanityError> {
        let bad = |reason: &str| {
            Err(SanityError::MeshBody {
                reason: format!("inside grid: {reason}"),
            })
        };
        if self.cells.is_empty() {
            return Ok(());
        }
        for p in &self.planes {
            if p.len() < 2 || p.iter().any(|q| !q.is_finite()) || p.windows(2).any(|w| w[0] > w[1])
            {
                return bad("planes not finite and nondecreasing");
            }
        }
        if self.cells.len() != self.counts().iter().product::<usize>() {
            return bad("not one cell per triple of intervals");
        }
        if self.cells.contains(&EMPTY) {
            return bad("a cell left mid-build");
        }
        let kept = self.windings.len();
        if self
            .cells
            .iter()
            .any(|&c| c >= INSIDE_KEPT && usize::from(c - INSIDE_KEPT) >= kept)
        {
            return bad("a cell's windings not kept");
        }
        if self.windings.iter().any(|w| {
            !some_winds(w) || w.iter().any(|e| e.1 == 0) || w.windows(2).any(|p| p[0].0 >= p[1].0)
        }) {
            return bad("kept windings not by increasing source, zero or with a zero entry");
        }
        Ok(())
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::mesh::PolygonMesh;
    use crate::solid::intersect::triangles_meet;
    use rand::{Rng, SeedableRng};

    /// Appends the box `[lo, hi]`, outward or inward, each face cut into
    /// `cuts` × `cuts` quads at equal steps (exact where the steps are; one
    /// quad of the exact corners when `cuts` is 1).
    pub(crate) fn push_box(
        m: &mut PolygonMesh,
        lo: [f64; 3],
        hi: [f64; 3],
        outward: bool,
        cuts: usize,
    ) {
        // The corners numbered as `box_mesh`'s (bit k: coordinate k high),
        // its outward quads.
        let corner =
            |i: usize| DVec3::from([0, 1, 2].map(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }));
        for f in crate::robot::shapes::box_mesh(DVec3::ONE).faces {
            let (a, b, d) = (corner(f[0]), corner(f[1]), corner(f[3]));
            let at = |i: usize, j: usize| match (cuts, i, j) {
                (1, _, _) => corner(f[[[0, 3], [1, 2]][i][j]]).to_array(),
                _ => {
                    let (u, v) = (i as f64 / cuts as f64, j as f64 / cuts as f64);
                    (a + (b - a) * u + (d - a) * v).to_array()
                }
            };
            for i in 0..cuts {
                for j in 0..cuts {
                    let base = m.vertices.len();
                    m.vertices
                        .extend([at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                    let mut q = vec![base, base + 1, base + 2, base + 3];
                    if !outward {
                        q.reverse();
                    }
                    m.faces.push(q);
                }
            }
        }
    }

    /// Boxes `[lo, hi]`, each outward or inward, as one body, each face cut
    /// into 4 × 4 quads (so that the grid is fine enough to classify cells
    /// of them; the cuts are exact, at quarters of the edges).
    fn boxes(list: &[([f64; 3], [f64; 3], bool)]) -> MeshBody {
        let mut m = PolygonMesh::new(Vec::new(), Vec::new());
        for &(lo, hi, outward) in list {
            push_box(&mut m, lo, hi, outward, 4);
        }
        MeshBody::new(&m).unwrap()
    }

    /// The hull of `n` random points on a sphere of radius `r` about `c`.
    fn ball(n: usize, c: [f64; 3], r: f64, seed: u64) -> PolygonMesh {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let points: Vec<[f64; 3]> = (0..n)
            .map(|_| loop {
                let v = DVec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                if (0.01..1.0).contains(&v.length_squared()) {
                    break (DVec3::from(c) + v.normalize() * r).to_array();
                }
            })
            .collect();
        crate::polytope::Polytope::from_points(&points)
            .unwrap()
            .to_mesh()
    }

    /// Bodies whose grids classify cells of every kind: a cavity, nested
    /// and touching solids, a joined scene whose obstacles wind apart (an
    /// inward box inside another obstacle's solid), a fine convex ball and
    /// a ball with a box-shaped cavity.
    fn bodies() -> Vec<MeshBody> {
        // A cavity holding a small solid within one cell.
        let cavity = boxes(&[
            ([0.0; 3], [9.0; 3], true),
            ([3.0; 3], [6.0; 3], false),
            ([4.625; 3], [4.75; 3], true),
        ]);
        let nested = boxes(&[([0.0; 3], [9.0; 3], true), ([3.0; 3], [6.0; 3], true)]);
        let touching = boxes(&[
            ([0.0; 3], [4.0, 8.0, 8.0], true),
            ([4.0, 0.0, 0.0], [8.0; 3], true),
        ]);
        let a = boxes(&[([0.0; 3], [10.0; 3], true), ([20.0; 3], [23.0; 3], false)]);
        let b = boxes(&[([18.0; 3], [25.0; 3], true)]);
        let joined = MeshBody::join(&[a, b]);
        // Two sources side by side, each with cells inside it alone.
        let side_by_side = MeshBody::join(&[
            boxes(&[([0.0; 3], [9.0; 3], true)]),
            boxes(&[([10.0, 0.0, 0.0], [19.0, 9.0, 9.0], true)]),
        ]);
        let fine = MeshBody::new(&ball(400, [1.0, -2.0, 0.5], 3.0, 1)).unwrap();
        let mut hollow = ball(300, [0.0; 3], 5.0, 2);
        push_box(&mut hollow, [-1.5; 3], [1.5; 3], false, 1);
        let hollow = MeshBody::new(&hollow).unwrap();
        vec![cavity, nested, touching, joined, fine, hollow, side_by_side]
    }

    /// Whether `p` lies on a triangle of one of `body`'s solids (exact).
    fn on_a_solid(body: &MeshBody, p: DVec3) -> bool {
        (0..body.triangles.len()).any(|t| {
            body.components[body.component_of[t] as usize].0 == ComponentKind::Solid
                && triangles_meet(
                    &[p; 3],
                    &body.triangles[t].map(|v| body.vertices[v as usize]),
                )
        })
    }

    /// Every point the grid answers for is on no triangle of a solid, and
    /// its ray answers the same, and where the grid knows the windings
    /// (module docs, "Windings kept") they are the ray's, source by
    /// source: random points, the cells' corners and centres, the
    /// triangles' centroids and points just off them on both sides, and
    /// points of the boxes about random points the grid answers for with a
    /// half-width. Fails when a region keeps another's windings.
    #[test]
    fn classified_cells_answer_as_the_ray() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let (mut kept_inside, mut kept_twice) = (0, 0);
        for (b, body) in bodies().iter().enumerate() {
            let grid = body.inside_grid();
            grid.sanity_check().unwrap();
            let (mut answered, mut inside) = (0, 0);
            let mut check = |p: DVec3, answer: Option<bool>| {
                if let Some(v) = answer {
                    answered += 1;
                    inside += usize::from(v);
                    assert!(!on_a_solid(body, p), "body {b}: {p} is on a solid");
                    assert_eq!(
                        body.inside_by_ray(p, &mut Vec::new()),
                        Some(v),
                        "body {b}: {p}"
                    );
                }
                if let Some(w) = grid.windings_at(p, 0.0) {
                    let mut ray = body.windings_by_ray(p, &mut Vec::new()).unwrap();
                    ray.retain(|e| e.1 != 0);
                    ray.sort_unstable();
                    assert_eq!(w, ray, "body {b}: {p}");
                    assert_eq!(answer, Some(some_winds(&w)), "body {b}: {p}");
                    kept_inside += usize::from(some_winds(&w));
                    kept_twice += usize::from(w.iter().any(|e| e.1.abs() > 1) || w.len() > 1);
                }
            };
            let planes = grid.planes.clone();
            let (lo, hi) = (
                planes.each_ref().map(|p| p[0]),
                planes.each_ref().map(|p| p[p.len() - 1]),
            );
            for _ in 0..3000 {
                let p = DVec3::from([0, 1, 2].map(|k| {
                    let w = hi[k] - lo[k];
                    rng.random_range(lo[k] - 0.1 * w..hi[k] + 0.1 * w)
                }));
                check(p, grid.classify(p, 0.0));
                let e = 0.05 * rng.random_range(0.0..1.0) * (hi[0] - lo[0]);
                if let Some(v) = grid.classify(p, e) {
                    for corner in 0..8 {
                        let q = p + DVec3::from([0, 1, 2].map(|k| {
                            if corner >> k & 1 == 0 {
                                -e
                            } else {
                                e
                            }
                        }));
                        check(q, Some(v));
                    }
                }
            }
            for tri in &body.triangles {
                let [a, b, c] = tri.map(|v| body.vertices[v as usize]);
                let (centroid, normal) = ((a + b + c) / 3.0, (b - a).cross(c - a).normalize());
                for off in [-1e-3, 0.0, 1e-3] {
                    let p = centroid + normal * off;
                    check(p, grid.classify(p, 0.0));
                }
            }
            let n = grid.counts();
            for z in 0..=n[2] {
                for y in 0..=n[1] {
                    for x in 0..=n[0] {
                        let corner = DVec3::new(planes[0][x], planes[1][y], planes[2][z]);
                        check(corner, grid.classify(corner, 0.0));
                        if x < n[0] && y < n[1] && z < n[2] {
                            let (lo, hi) = grid.block([x, y, z], [x, y, z]);
                            let centre = 0.5 * lo + 0.5 * hi;
                            check(centre, grid.classify(centre, 0.0));
                        }
                    }
                }
            }
            assert!(answered > 100, "body {b}: only {answered} points answered");
            assert!(
                inside > 10,
                "body {b}: only {inside} points answered inside"
            );
        }
        // Nested shells wind twice, the joined bodies' sources once each.
        assert!(
            kept_inside > 1_000 && kept_twice > 10,
            "{kept_inside} inside points' windings kept, {kept_twice} of them not one source once"
        );
    }

    /// A cube 8 least subnormals wide, each face cut 8 × 8: its grid has
    /// cells of zero width at odd multiples of the least subnormal, whose
    /// computed midpoint rounds outside them; the inside region's first
    /// cell is one, and its ray from the cube's corner called the whole
    /// inside outside (found by the review recorded in `scene::state`).
    #[test]
    fn a_region_is_asked_from_inside_its_first_cell_at_subnormal_sizes() {
        let t = f64::from_bits(1);
        let mut m = PolygonMesh::new(Vec::new(), Vec::new());
        push_box(&mut m, [0.0; 3], [8.0 * t; 3], true, 8);
        let body = MeshBody::new(&m).unwrap();
        assert_eq!(body.report().solids, 1);
        let grid = body.inside_grid();
        let n = grid.counts();
        for z in 0..n[2] {
            for y in 0..n[1] {
                for x in 0..n[0] {
                    let (lo, hi) = grid.block([x, y, z], [x, y, z]);
                    let centre = (0.5 * lo + 0.5 * hi).clamp(lo, hi);
                    if let Some(v) = grid.classify(centre, 0.0) {
                        assert!(!on_a_solid(&body, centre), "{centre}");
                        assert_eq!(body.inside_by_ray(centre, &mut Vec::new()), Some(v));
                    }
                }
            }
        }
        let middle = DVec3::splat(4.0 * t);
        assert_eq!(body.inside_by_ray(middle, &mut Vec::new()), Some(true));
        assert_ne!(grid.classify(middle, 0.0), Some(false));
    }

    /// The grid does the work it is for: most cells of a fine ball are
    /// classified, its centre is answered inside, and a cavity's centre
    /// outside.
    #[test]
    fn grids_classify_most_of_a_fine_solid() {
        let b = bodies();
        // The cavity's small solid lies in one cell (what the first test
        // needs to see a triangle inside one cell marked).
        let small = b[0].inside_grid();
        assert_eq!(small.counts(), [10; 3]);
        assert!(small.planes[0][5] < 4.625 && 4.75 < small.planes[0][6]);
        let fine = b[4].inside_grid();
        assert!(fine.classified() > 0.5, "{}", fine.classified());
        assert_eq!(fine.classify(DVec3::new(1.0, -2.0, 0.5), 0.0), Some(true));
        assert_eq!(b[5].inside_grid().classify(DVec3::ZERO, 0.0), Some(false));
        assert_eq!(
            b[5].inside_grid().classify(DVec3::new(3.0, 0.0, 0.0), 0.0),
            Some(true)
        );
    }
}
