//! Persistent exact ties along a step about a coordinate axis (boxes turning
//! about `z`): the exact zero structure of the maps ([`ExactZeros`]), the
//! axis test (`coordinate_axis`) and the certification that a tie keeps its
//! symbolic-perturbation sign over the whole step (`stays_in_cell_tied`,
//! `sos_term_certified`). The argument is in the module docs of
//! [`super`] ("Persistent ties").
//!
//! Complexity: O(degree) per normal, O(1) per tie; the zero structure is
//! computed once, exactly, at the first step about an axis.

use super::*;

/// Which components of the exact reference normals and of the exact arc
/// normals (cross products of the two faces' exact normals) are zero:
/// computed once, exactly, for the certification of persistent ties.
#[derive(Clone, Debug)]
pub(super) struct ExactZeros {
    /// Per face.
    pub(super) normal: Vec<[bool; 3]>,
    /// Per edge.
    pub(super) arc: Vec<[bool; 3]>,
}

impl ExactZeros {
    pub(super) fn of(poly: &Polytope) -> ExactZeros {
        let view = GaussView {
            poly,
            normals: poly.normals(),
            arcs: poly.arc_normals(),
            turn: None,
            arc_errs: poly.arc_errors(),
            base: 0,
            rotation: None,
            ties: None,
        };
        let zero = |v: &ExactVec| [0, 1, 2].map(|c| v[c].sign() == Sign::Zero);
        let exact: Vec<ExactVec> = (0..poly.face_count() as u32)
            .map(|f| view.normal(f).exact())
            .collect();
        ExactZeros {
            normal: exact.iter().map(zero).collect(),
            arc: (0..poly.edge_count())
                .map(|e| {
                    let [f0, f1] = poly.edge(e).faces;
                    zero(&exact::cross(&exact[f0 as usize], &exact[f1 as usize]))
                })
                .collect(),
        }
    }
}

/// The coordinate axis `k` about which both relative rotations turn
/// exactly: in both (snapped) matrices row and column `k` are the unit
/// vector `e_k`, and the other two rows and columns form a matrix
/// `[[c, −s], [s, c]]` exactly (a positive multiple of a plane rotation).
/// Then the step can be taken along rotations about `e_k`, on which the
/// `k`-components of P's rotated normals are constant and the sign of every
/// SoS term is invariant under the positive scale.
pub(super) fn coordinate_axis(a: &DMat3, b: &DMat3) -> Option<usize> {
    (0..3).find(|&k| {
        [a, b].iter().all(|m| {
            let (i, j) = plane(k);
            let e = DVec3::AXES[k];
            let (c, s) = (m.col(i)[i], m.col(i)[j]);
            m.row(k) == e
                && m.col(k) == e
                && m.col(j)[j] == c
                && m.col(j)[i] == -s
                && c * c + s * s > 0.5
        })
    })
}

/// The two coordinates other than `k`.
#[inline]
pub(super) fn plane(k: usize) -> (usize, usize) {
    match k {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

/// The exact zero structure of the moving and the fixed map of a scan.
pub(super) struct Tied<'t> {
    pub(super) moving: &'t ExactZeros,
    pub(super) fixed: &'t ExactZeros,
    /// The moving normals are P's (lower SoS indices than Q's).
    pub(super) moving_is_p: bool,
}

/// Whether the face normal `f` of `faces`, in cell `v` of `cells` at the
/// start of a step about coordinate axis `k` by angle `θ`, certainly stays
/// in that cell along the whole step (under the symbolic perturbation), so
/// that it has no event and its fv-pair is unchanged.
///
/// Per arc of the cell, one of:
/// * both end margins exceed `reach` (the drift argument of the module
///   docs);
/// * the determinant `det[a, b, x]` is zero at every rotation about `e_k`
///   (a *persistent tie*, read off the exact zero structure: for P's normal
///   `x = R n`, `(a × b) · R n = (a × b)_k n_k + (a × b)_⊥ · R_⊥ n_⊥`, and
///   symmetrically for an arc of P), and its SoS sign is constant along the
///   step. When the normal is P's it has the lowest index, so the first SoS
///   terms are the cofactors of its row, the components of `a × b` of Q's
///   fixed arc: constant, and not all zero. When it is Q's, the sign is
///   decided by [`sos_term_certified`].
///
/// Returns the rotation about `e_k` the normal can still absorb from the
/// new pose with all this still certain (the smallest margin of a non-tied
/// arc, or of a deciding SoS term; a sine of an angle, or an angle), or
/// `None` in any other case (a tie that may break during the step): then the
/// caller's exact path takes over.
pub(super) fn stays_in_cell_tied(
    (faces, cells): (&GaussView<'_>, &GaussView<'_>),
    cell_arcs: &[DVec3],
    (f, v): (u32, u32),
    (x_old, x_new): (DVec3, DVec3),
    reach: f64,
    (k, theta): (usize, f64),
    tied: &Tied<'_>,
) -> Option<f64> {
    let (i, j) = plane(k);
    let off = cells.poly.ring_offset(v as usize);
    let nz = tied.moving.normal[f as usize];
    let mut least = f64::INFINITY;
    for (r, entry) in cells.poly.ring(v as usize).iter().enumerate() {
        let m = cell_arcs[off + r];
        let now = m.dot(x_new);
        if m.dot(x_old).min(now) > reach {
            least = least.min(now);
            continue;
        }
        let cz = tied.fixed.arc[entry.edge as usize];
        let persistent = (cz[k] || nz[k]) && ((cz[i] && cz[j]) || (nz[i] && nz[j]));
        if !persistent {
            return None;
        }
        if !tied.moving_is_p {
            let absorb = sos_term_certified(cells, entry.edge, faces, f, k, tied)?;
            if absorb <= theta {
                return None;
            }
            least = least.min(absorb);
        }
    }
    Some(least)
}

/// For an arc `e` of P (the `arcs` view, rotated to the new pose) and a
/// face normal `g` of Q whose determinant is a persistent tie: whether the
/// SoS sign is constant along the step. Rows sorted by index are P's two
/// normals, then Q's. The SoS terms are scanned in order of significance:
/// a term that vanishes at every rotation about `e_k` (a product of exact
/// structural zeros, or the rotation-invariant minor `(a × b)_k = 0` of P's
/// two rows in the plane coordinates) is skipped; the first other term
/// decides the sign, and stays non-zero over any rotation by less than
/// (its value less its float error and slack) divided by its rate of change
/// (at most `|u| |v|` per radian for each rotating row of a 2×2 minor, `|u|`
/// for an entry).
/// Returns that rotation (`∞` for a constant term), or `None` when the
/// deciding term is not certainly non-zero now.
pub(super) fn sos_term_certified(
    arcs: &GaussView<'_>,
    e: u32,
    normals: &GaussView<'_>,
    g: u32,
    k: usize,
    tied: &Tied<'_>,
) -> Option<f64> {
    let [f0, f1] = arcs.poly.edge(e as usize).faces;
    let (lo, hi) = (f0.min(f1), f0.max(f1));
    let rows = [arcs.normal(lo), arcs.normal(hi), normals.normal(g)];
    let a = rows.each_ref().map(|r| r.approx());
    let err = rows.each_ref().map(|r| r.error());
    let (pz, qz) = (&tied.fixed.normal, &tied.moving.normal);
    let zeros = [pz[lo as usize], pz[hi as usize], qz[g as usize]];
    let (i, j) = plane(k);
    // Structurally zero at every rotation about e_k; varying along it.
    let zero = |r: usize, c: usize| {
        if r == 2 || c == k {
            zeros[r][c]
        } else {
            zeros[r][i] && zeros[r][j]
        }
    };
    let varies = |r: usize, c: usize| r < 2 && c != k && !(zeros[r][i] && zeros[r][j]);
    let norm = |r: usize| a[r].length() + err[r];
    for t in sos_terms() {
        match *t {
            SosTerm::Cofactor { row, col } => {
                let [r0, r1] = others(row as usize);
                let [c0, c1] = others(col as usize);
                if (zero(r0, c0) || zero(r1, c1)) && (zero(r0, c1) || zero(r1, c0)) {
                    continue;
                }
                if r1 < 2 && c0 != k && c1 != k {
                    // P's two rows in the plane: `det(B) (a × b)_k`, constant.
                    if tied.fixed.arc[e as usize][k] {
                        continue;
                    }
                    return Some(f64::INFINITY);
                }
                let (d, bound) =
                    crate::kernel::bounds::minor(a[r0], err[r0], a[r1], err[r1], c0, c1);
                // Rows with an entry that varies: each changes the minor by
                // at most |u| |v| per radian.
                let moving = [r0, r1]
                    .iter()
                    .filter(|&&r| varies(r, c0) || varies(r, c1))
                    .count();
                let scale = norm(r0) * norm(r1);
                let left = d.abs() - bound - SLACK * scale;
                return (left > 0.0).then(|| {
                    if moving > 0 {
                        left / (1.01 * moving as f64 * scale)
                    } else {
                        f64::INFINITY
                    }
                });
            }
            SosTerm::Entry { row, col, .. } => {
                let (r, c) = (row as usize, col as usize);
                if zero(r, c) {
                    continue;
                }
                let left = a[r][c].abs() - 1.01 * err[r] - SLACK * norm(r);
                return (left > 0.0).then(|| {
                    if varies(r, c) {
                        left / (1.01 * norm(r))
                    } else {
                        f64::INFINITY
                    }
                });
            }
            SosTerm::Constant(_) => return Some(f64::INFINITY),
        }
    }
    Some(f64::INFINITY)
}
