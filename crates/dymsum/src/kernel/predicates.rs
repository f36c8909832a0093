//! Exact geometric predicates on `f64` input.
//!
//! All predicates return the exact sign of a polynomial in their float
//! inputs, computed with Shewchuk's adaptive-precision arithmetic (the
//! `robust` crate). Floats are used only to build inputs; never to decide.
//!
//! # Symbolic perturbation
//!
//! [`sos_det3`] implements Simulation of Simplicity (Edelsbrunner and Mücke,
//! ACM TOG 1990) for the 3×3 determinant `det[a, b, c]` of three direction
//! vectors, each carrying a global index. Entry `(i, k)` of vector `i` is
//! perturbed by `ε^(2^(3i + 2 − k))`; the sign of the perturbed determinant is
//! the sign of the first non-vanishing coefficient of its expansion in `ε`,
//! ordered by increasing exponent. The expansion has 34 terms: the determinant
//! itself, nine cofactors (exact 2×2 determinants), eighteen single entries and
//! six constants `±1`, so the result is never zero when the three indices
//! differ. Every cross-map decision of the Minkowski sum algorithms uses it, so
//! all algorithms see one and the same generic configuration.

use glam::DVec3;
use robust::{Coord, Coord3D};
use std::sync::OnceLock;

/// The sign of a determinant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    /// Strictly negative.
    Negative,
    /// Exactly zero.
    Zero,
    /// Strictly positive.
    Positive,
}

impl Sign {
    /// The sign of a float (`Zero` only for ±0).
    #[inline]
    pub fn of(x: f64) -> Sign {
        if x > 0.0 {
            Sign::Positive
        } else if x < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }
    /// The opposite sign.
    #[inline]
    pub fn flip(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }
    /// `true` for `Positive`.
    #[inline]
    pub fn is_positive(self) -> bool {
        self == Sign::Positive
    }
    /// `true` for `Negative`.
    #[inline]
    pub fn is_negative(self) -> bool {
        self == Sign::Negative
    }
}

#[inline]
fn c3(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// Exact orientation of `d` relative to the plane through `a`, `b`, `c`:
/// `Positive` when `d` lies on the side from which `a, b, c` appear
/// counter-clockwise ("above"), i.e. the sign of `det[b − a, c − a, d − a]`.
#[inline]
pub fn orient(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
    // robust::orient3d is positive when d is *below* the ccw plane.
    Sign::of(-robust::orient3d(c3(a), c3(b), c3(c), c3(d)))
}

/// Exact sign of `det[a, b, c]` (rows `a`, `b`, `c`) = `(a × b) · c`.
/// `Positive` when `a, b, c` turn counter-clockwise seen from outside the
/// unit sphere (for directions within a common open hemisphere).
#[inline]
pub fn det3(a: DVec3, b: DVec3, c: DVec3) -> Sign {
    // Fast filter: the float determinant with a forward error bound.
    let bc = b.cross(c);
    let det = a.dot(bc);
    let perm = a.x.abs() * (b.y * c.z).abs().max((b.z * c.y).abs()) * 2.0
        + a.y.abs() * (b.z * c.x).abs().max((b.x * c.z).abs()) * 2.0
        + a.z.abs() * (b.x * c.y).abs().max((b.y * c.x).abs()) * 2.0;
    let bound = 8.0 * f64::EPSILON * perm;
    if det > bound {
        return Sign::Positive;
    }
    if -det > bound {
        return Sign::Negative;
    }
    // det[a, b, c] = det[a - 0, b - 0, c - 0]; the differences with the origin
    // are exact, so Shewchuk's orient3d with d = 0 is exact.
    orient(DVec3::ZERO, a, b, c)
}

/// Exact sign of the 2×2 determinant `p.0 * q.1 − p.1 * q.0`.
#[inline]
pub fn det2(p0: f64, p1: f64, q0: f64, q1: f64) -> Sign {
    Sign::of(robust::orient2d(
        Coord { x: p0, y: p1 },
        Coord { x: q0, y: q1 },
        Coord { x: 0.0, y: 0.0 },
    ))
}

/// `true` when `a` and `b` point in exactly the same direction
/// (positive multiples of each other), decided exactly.
pub fn same_direction(a: DVec3, b: DVec3) -> bool {
    if det2(a.y, a.z, b.y, b.z) != Sign::Zero
        || det2(a.z, a.x, b.z, b.x) != Sign::Zero
        || det2(a.x, a.y, b.x, b.y) != Sign::Zero
    {
        return false;
    }
    // Parallel: compare the sign of one non-zero coordinate.
    for k in 0..3 {
        if a[k] != 0.0 {
            return (a[k] > 0.0) == (b[k] > 0.0) && b[k] != 0.0;
        }
    }
    false
}

/// One term of the SoS expansion of a 3×3 determinant.
#[derive(Clone, Copy, Debug)]
enum SosTerm {
    /// The cofactor of entry (row, col): the signed 2×2 minor.
    Cofactor { row: u8, col: u8 },
    /// `sign * A[row][col]`.
    Entry { row: u8, col: u8, sign: i8 },
    /// A constant `±1`.
    Constant(i8),
}

fn perm_sign(p: [usize; 3]) -> i8 {
    let mut s = 1;
    for i in 0..3 {
        for j in i + 1..3 {
            if p[i] > p[j] {
                s = -s;
            }
        }
    }
    s
}

/// The 33 perturbation terms in decreasing order of significance.
fn sos_terms() -> &'static [SosTerm] {
    static TERMS: OnceLock<Vec<SosTerm>> = OnceLock::new();
    TERMS.get_or_init(|| {
        // Bit of the perturbation exponent of entry (row, col): row-major with
        // z (col 2) the most significant within a row.
        let bit = |r: usize, c: usize| 3 * r + (2 - c);
        let mut terms: Vec<(u32, SosTerm)> = Vec::new();
        let perms: [[usize; 3]; 6] = [
            [0, 1, 2],
            [0, 2, 1],
            [1, 0, 2],
            [1, 2, 0],
            [2, 0, 1],
            [2, 1, 0],
        ];
        // Single perturbations: coefficient is the cofactor.
        for r in 0..3 {
            for c in 0..3 {
                terms.push((
                    1 << bit(r, c),
                    SosTerm::Cofactor {
                        row: r as u8,
                        col: c as u8,
                    },
                ));
            }
        }
        // Pairs: rows r1 < r2 perturbed at columns of a permutation sigma; the
        // coefficient is sgn(sigma) * A[r3][sigma(r3)].
        for p in perms {
            for skip in 0..3 {
                let rows: Vec<usize> = (0..3).filter(|&r| r != skip).collect();
                let exp = rows.iter().map(|&r| 1u32 << bit(r, p[r])).sum();
                terms.push((
                    exp,
                    SosTerm::Entry {
                        row: skip as u8,
                        col: p[skip] as u8,
                        sign: perm_sign(p),
                    },
                ));
            }
            let exp = (0..3).map(|r| 1u32 << bit(r, p[r])).sum();
            terms.push((exp, SosTerm::Constant(perm_sign(p))));
        }
        terms.sort_by_key(|t| t.0);
        // Distinct exponents by construction (distinct bit sets); pairs with
        // the same positions from different permutations collapse: keep one.
        terms.dedup_by_key(|t| t.0);
        terms.into_iter().map(|t| t.1).collect()
    })
}

fn cofactor_sign(m: &[[f64; 3]; 3], row: usize, col: usize) -> Sign {
    let rows: Vec<usize> = (0..3).filter(|&r| r != row).collect();
    let cols: Vec<usize> = (0..3).filter(|&c| c != col).collect();
    let s = det2(
        m[rows[0]][cols[0]],
        m[rows[0]][cols[1]],
        m[rows[1]][cols[0]],
        m[rows[1]][cols[1]],
    );
    if (row + col) % 2 == 1 {
        s.flip()
    } else {
        s
    }
}

/// Sign of `det[a, b, c]` under Simulation of Simplicity, where `ia`, `ib`,
/// `ic` are the vectors' global indices (all distinct). Never `Zero` for
/// distinct indices; equals [`det3`] whenever that is non-zero.
pub fn sos_det3(a: DVec3, ia: u32, b: DVec3, ib: u32, c: DVec3, ic: u32) -> Sign {
    let s = det3(a, b, c);
    if s != Sign::Zero {
        return s;
    }
    sos_tiebreak(a, ia, b, ib, c, ic)
}

#[cold]
fn sos_tiebreak(a: DVec3, ia: u32, b: DVec3, ib: u32, c: DVec3, ic: u32) -> Sign {
    debug_assert!(
        ia != ib && ib != ic && ia != ic,
        "SoS needs distinct indices"
    );
    // Sort rows by index; an odd permutation flips the sign.
    let mut rows = [(ia, a), (ib, b), (ic, c)];
    let mut flips = 0;
    for i in 0..3 {
        for j in 0..2 - i {
            if rows[j].0 > rows[j + 1].0 {
                rows.swap(j, j + 1);
                flips += 1;
            }
        }
    }
    let m = [
        rows[0].1.to_array(),
        rows[1].1.to_array(),
        rows[2].1.to_array(),
    ];
    let mut result = Sign::Zero;
    for t in sos_terms() {
        let s = match *t {
            SosTerm::Cofactor { row, col } => cofactor_sign(&m, row as usize, col as usize),
            SosTerm::Entry { row, col, sign } => {
                let v = Sign::of(m[row as usize][col as usize]);
                if sign < 0 {
                    v.flip()
                } else {
                    v
                }
            }
            SosTerm::Constant(sign) => {
                if sign < 0 {
                    Sign::Negative
                } else {
                    Sign::Positive
                }
            }
        };
        if s != Sign::Zero {
            result = s;
            break;
        }
    }
    if flips % 2 == 1 {
        result.flip()
    } else {
        result
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orient_convention() {
        let o = DVec3::ZERO;
        let x = DVec3::X;
        let y = DVec3::Y;
        assert_eq!(orient(o, x, y, DVec3::Z), Sign::Positive);
        assert_eq!(orient(o, x, y, -DVec3::Z), Sign::Negative);
        assert_eq!(orient(o, x, y, DVec3::new(3.0, 4.0, 0.0)), Sign::Zero);
    }

    #[test]
    fn det3_matches_cross_dot() {
        assert_eq!(det3(DVec3::X, DVec3::Y, DVec3::Z), Sign::Positive);
        assert_eq!(det3(DVec3::Y, DVec3::X, DVec3::Z), Sign::Negative);
        assert_eq!(det3(DVec3::X, DVec3::Y, DVec3::X), Sign::Zero);
        // A case where naive float evaluation is wrong.
        let a = DVec3::new(1.0, 1e-17, 0.0);
        let b = DVec3::new(1.0, 0.0, 1e-17);
        let c = DVec3::new(1.0, 0.0, 0.0);
        assert_eq!(det3(a, b, c), Sign::Positive); // exactly 1e-34
    }

    #[test]
    fn sos_is_antisymmetric_and_nonzero() {
        let a = DVec3::X;
        let b = DVec3::new(1.0, 1.0, 0.0);
        let c = DVec3::Y;
        // coplanar: det = 0
        let s = sos_det3(a, 0, b, 1, c, 2);
        assert_ne!(s, Sign::Zero);
        assert_eq!(sos_det3(b, 1, a, 0, c, 2), s.flip());
        assert_eq!(sos_det3(a, 0, c, 2, b, 1), s.flip());
        assert_eq!(sos_det3(c, 2, a, 0, b, 1), s);
        // identical vectors with distinct indices
        let s2 = sos_det3(a, 5, a, 3, a, 9);
        assert_ne!(s2, Sign::Zero);
        assert_eq!(sos_det3(a, 3, a, 5, a, 9), s2.flip());
        assert_eq!(sos_terms().len(), 9 + 18 + 6);
    }

    #[test]
    fn same_direction_exact() {
        assert!(same_direction(
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(2.0, 4.0, 6.0)
        ));
        assert!(!same_direction(
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(-2.0, -4.0, -6.0)
        ));
        assert!(!same_direction(
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(2.0, 4.0, 6.000000000000001)
        ));
    }
}
