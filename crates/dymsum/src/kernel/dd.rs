//! Double-double arithmetic: an unevaluated sum `hi + lo` of two floats, with
//! about 106 bits of precision (Dekker 1971, Knuth's TwoSum).
//!
//! The second stage of the filtered predicates: when the plain float filter
//! cannot certify a sign (nearly parallel normals, e.g. the two triangles of
//! a quad that is planar only to the last printed digit), the exact normals
//! are evaluated in double-double with a certified error bound of order
//! `u²`, which settles everything but true degeneracies; those go to the
//! exact [`super::exact::Dyadic`] stage.

/// `hi + lo` with `|lo| ≤ ulp(hi)/2`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DD {
    /// Leading part.
    pub hi: f64,
    /// Trailing part.
    pub lo: f64,
}

/// Knuth's TwoSum: `(fl(a + b), error)` with `a + b = s + error` exactly.
#[inline]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

#[inline]
fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

#[inline]
fn split(a: f64) -> (f64, f64) {
    const SPLITTER: f64 = 134_217_729.0; // 2^27 + 1
    let t = SPLITTER * a;
    let hi = t - (t - a);
    (hi, a - hi)
}

#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

impl DD {
    /// The exact value of a float.
    #[inline]
    pub fn from(x: f64) -> DD {
        DD { hi: x, lo: 0.0 }
    }
    /// `a − b` for floats, exactly.
    #[inline]
    pub fn diff(a: f64, b: f64) -> DD {
        let (hi, lo) = two_sum(a, -b);
        DD { hi, lo }
    }
    /// Product with a float scaled by a power of two (exact scaling).
    #[inline]
    pub fn scale(self, s: f64) -> DD {
        DD {
            hi: self.hi * s,
            lo: self.lo * s,
        }
    }
    /// `|hi|`, a good enough magnitude for error bounds.
    #[inline]
    pub fn abs_hi(self) -> f64 {
        self.hi.abs()
    }
}

impl std::ops::Add for DD {
    type Output = DD;
    /// Sum (relative error ≤ 2u², Shewchuk/Bailey's accurate addition).
    #[inline]
    fn add(self, o: DD) -> DD {
        let (s, e) = two_sum(self.hi, o.hi);
        let (t, f) = two_sum(self.lo, o.lo);
        let (s, e) = quick_two_sum(s, e + t);
        let (hi, lo) = quick_two_sum(s, e + f);
        DD { hi, lo }
    }
}

impl std::ops::Neg for DD {
    type Output = DD;
    #[inline]
    fn neg(self) -> DD {
        DD {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl std::ops::Sub for DD {
    type Output = DD;
    #[inline]
    fn sub(self, o: DD) -> DD {
        self + (-o)
    }
}

impl std::ops::Mul for DD {
    type Output = DD;
    /// Product (relative error ≤ 4u²).
    #[inline]
    fn mul(self, o: DD) -> DD {
        let (p, e) = two_prod(self.hi, o.hi);
        let e = e + (self.hi * o.lo + self.lo * o.hi);
        let (hi, lo) = quick_two_sum(p, e);
        DD { hi, lo }
    }
}

/// A vector of double-doubles.
pub type DDVec = [DD; 3];

/// Cross product in double-double.
#[inline]
pub fn cross(a: &DDVec, b: &DDVec) -> DDVec {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Dot product in double-double.
#[inline]
pub fn dot(a: &DDVec, b: &DDVec) -> DD {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_prod_is_exact() {
        let (a, b) = (0.1f64, 0.3f64);
        let (p, e) = two_prod(a, b);
        // Check with exact dyadics.
        use crate::kernel::exact::Dyadic;
        let exact = Dyadic::from_f64(a).mul(&Dyadic::from_f64(b));
        let sum = Dyadic::from_f64(p).add(&Dyadic::from_f64(e));
        assert_eq!(exact.sub(&sum).sign(), crate::kernel::Sign::Zero);
    }

    #[test]
    fn cancellation_survives() {
        let x = DD::diff(1.0, 1e-20);
        let y = x - DD::from(1.0);
        assert_eq!(y.hi, -1e-20);
    }
}
