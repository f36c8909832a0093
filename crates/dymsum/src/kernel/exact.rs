//! Exact dyadic arithmetic: every finite `f64` is `m · 2^e` with integer `m`,
//! so sums, differences and products of floats are exact as [`Dyadic`]s.
//!
//! Used only on the slow path of the filtered predicates, when the float
//! evaluation cannot certify a sign (near or exact degeneracies).

use super::Sign;
use glam::{DMat3, DVec3};
use num_bigint::BigInt;
use num_traits::{Signed, Zero};

/// Decomposes a finite `f64` into `(m, e)` with value exactly `m · 2^e`
/// (`|m| < 2^53`).
#[inline]
pub fn decompose(x: f64) -> (i64, i32) {
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i32;
    let frac = (bits & ((1u64 << 52) - 1)) as i64;
    let (m, e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1i64 << 52), exp - 1075)
    };
    if bits >> 63 == 1 {
        (-m, e)
    } else {
        (m, e)
    }
}

/// An exact dyadic rational `m · 2^e`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Dyadic {
    m: BigInt,
    e: i32,
}

impl Dyadic {
    /// Zero.
    pub fn zero() -> Dyadic {
        Dyadic {
            m: BigInt::zero(),
            e: 0,
        }
    }

    /// The exact value of a finite float (non-finite values map to zero;
    /// callers validate finiteness first).
    pub fn from_f64(x: f64) -> Dyadic {
        if x == 0.0 || !x.is_finite() {
            return Dyadic::zero();
        }
        let (m, e) = decompose(x);
        Dyadic {
            m: BigInt::from(m),
            e,
        }
    }

    /// The sign.
    pub fn sign(&self) -> Sign {
        if self.m.is_zero() {
            Sign::Zero
        } else if self.m.is_positive() {
            Sign::Positive
        } else {
            Sign::Negative
        }
    }

    /// `self + other`, exactly.
    pub fn add(&self, other: &Dyadic) -> Dyadic {
        if self.m.is_zero() {
            return other.clone();
        }
        if other.m.is_zero() {
            return self.clone();
        }
        let e = self.e.min(other.e);
        let a = &self.m << (self.e - e) as usize;
        let b = &other.m << (other.e - e) as usize;
        Dyadic { m: a + b, e }
    }

    /// `self − other`, exactly.
    pub fn sub(&self, other: &Dyadic) -> Dyadic {
        self.add(&other.neg())
    }

    /// `−self`.
    pub fn neg(&self) -> Dyadic {
        Dyadic {
            m: -&self.m,
            e: self.e,
        }
    }

    /// `self · other`, exactly.
    pub fn mul(&self, other: &Dyadic) -> Dyadic {
        if self.m.is_zero() || other.m.is_zero() {
            return Dyadic::zero();
        }
        Dyadic {
            m: &self.m * &other.m,
            e: self.e + other.e,
        }
    }
}

/// An exact 3-vector.
pub type ExactVec = [Dyadic; 3];

/// The exact vector of a float vector.
pub fn exact(v: DVec3) -> ExactVec {
    [
        Dyadic::from_f64(v.x),
        Dyadic::from_f64(v.y),
        Dyadic::from_f64(v.z),
    ]
}

/// `a − b`, exactly.
pub fn sub(a: DVec3, b: DVec3) -> ExactVec {
    let (a, b) = (exact(a), exact(b));
    [a[0].sub(&b[0]), a[1].sub(&b[1]), a[2].sub(&b[2])]
}

/// `a × b`, exactly.
pub fn cross(a: &ExactVec, b: &ExactVec) -> ExactVec {
    [
        a[1].mul(&b[2]).sub(&a[2].mul(&b[1])),
        a[2].mul(&b[0]).sub(&a[0].mul(&b[2])),
        a[0].mul(&b[1]).sub(&a[1].mul(&b[0])),
    ]
}

/// `a · b`, exactly.
pub fn dot(a: &ExactVec, b: &ExactVec) -> Dyadic {
    a[0].mul(&b[0]).add(&a[1].mul(&b[1])).add(&a[2].mul(&b[2]))
}

/// `M v` for a float matrix `M` taken as exact, exactly.
pub fn mat_vec(m: &DMat3, v: &ExactVec) -> ExactVec {
    let row = |r: usize| {
        let row = m.row(r);
        dot(&exact(row), v)
    };
    [row(0), row(1), row(2)]
}

/// `det[a, b, c] = (a × b) · c`, exactly.
pub fn det3(a: &ExactVec, b: &ExactVec, c: &ExactVec) -> Dyadic {
    dot(&cross(a, b), c)
}

/// `p0 q1 − p1 q0`, exactly.
pub fn det2(p0: &Dyadic, p1: &Dyadic, q0: &Dyadic, q1: &Dyadic) -> Dyadic {
    p0.mul(q1).sub(&p1.mul(q0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_are_exact() {
        for x in [0.1, -3.5, 1e-300, 5e-324, 1e300, f64::MAX, -0.0] {
            let d = Dyadic::from_f64(x);
            // m · 2^e reproduces x: compare via f64 when representable.
            let back = d.m.to_string().parse::<f64>().unwrap() * 2f64.powi(d.e);
            if x.abs() > 1e-290 && x.abs() < 1e290 {
                assert_eq!(back, x);
            }
        }
    }

    #[test]
    fn hidden_cancellation_is_exact() {
        // 0.1 + 0.2 - 0.3 is not zero in binary; the float sum says 5.5e-17.
        let s = Dyadic::from_f64(0.1)
            .add(&Dyadic::from_f64(0.2))
            .sub(&Dyadic::from_f64(0.3));
        assert_eq!(s.sign(), Sign::Positive);
        let z = Dyadic::from_f64(1e300).sub(&Dyadic::from_f64(1e300));
        assert_eq!(z.sign(), Sign::Zero);
    }

    #[test]
    fn exact_det() {
        let a = exact(DVec3::X);
        let b = exact(DVec3::Y);
        let c = exact(DVec3::Z);
        assert_eq!(det3(&a, &b, &c).sign(), Sign::Positive);
        assert_eq!(det3(&b, &a, &c).sign(), Sign::Negative);
        assert_eq!(det3(&a, &b, &a).sign(), Sign::Zero);
    }
}
