//! Double-double arithmetic: a value as an unevaluated sum `hi + lo` of two `f64` with
//! `|lo| <= ulp(hi)/2`, about 106 significant bits (Dekker 1971; Hida, Li and Bailey's QD).
//!
//! Used only for the reference values of [`super::reference`] (the accuracy study, the exact
//! kernel's tests, the peers' check), never on a hot path. Inputs are `f32`
//! scene and ray values, so differences of two inputs are exact (see [`Dd::diff`]) and every
//! later operation carries a relative error near `2^-104`.

pub use super::expansion::{two_prod, two_sum};
use glam::Vec3A;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A double-double number `hi + lo`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dd {
    pub hi: f64,
    pub lo: f64,
}

/// Renormalizes `a + b` when `|a| >= |b|`.
#[inline]
fn quick_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd {
        hi: s,
        lo: b - (s - a),
    }
}

impl Dd {
    pub const ZERO: Dd = Dd { hi: 0.0, lo: 0.0 };

    pub fn new(x: f64) -> Dd {
        Dd { hi: x, lo: 0.0 }
    }

    /// `a - b` exactly (TwoSum is exact for any two `f64`).
    pub fn diff(a: f64, b: f64) -> Dd {
        let (s, e) = two_sum(a, -b);
        quick_two_sum(s, e)
    }

    /// The nearest `f64`.
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    /// `-1`, `0` or `1` (the sign of `hi`, which is the sign of the value).
    pub fn signum(self) -> i32 {
        if self.hi > 0.0 {
            1
        } else if self.hi < 0.0 {
            -1
        } else {
            0
        }
    }

    pub fn abs(self) -> Dd {
        if self.hi < 0.0 { -self } else { self }
    }

    /// Square root (0 for values `<= 0`): one Newton step from the `f64` root.
    pub fn sqrt(self) -> Dd {
        if self.hi <= 0.0 {
            return Dd::ZERO;
        }
        let x = self.hi.sqrt();
        let (p, e) = two_prod(x, x);
        let r = (self - Dd { hi: p, lo: e }).to_f64();
        quick_two_sum(x, r / (2.0 * x))
    }
}

impl Add for Dd {
    type Output = Dd;
    fn add(self, o: Dd) -> Dd {
        let (s, e) = two_sum(self.hi, o.hi);
        let (t, f) = two_sum(self.lo, o.lo);
        let r = quick_two_sum(s, e + t);
        quick_two_sum(r.hi, r.lo + f)
    }
}

impl Neg for Dd {
    type Output = Dd;
    fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Sub for Dd {
    type Output = Dd;
    fn sub(self, o: Dd) -> Dd {
        self + (-o)
    }
}

impl Mul for Dd {
    type Output = Dd;
    fn mul(self, o: Dd) -> Dd {
        let (p, e) = two_prod(self.hi, o.hi);
        quick_two_sum(p, e + (self.hi * o.lo + self.lo * o.hi))
    }
}

impl Div for Dd {
    type Output = Dd;
    fn div(self, o: Dd) -> Dd {
        let q1 = self.hi / o.hi;
        let r = self - o * Dd::new(q1);
        let q2 = r.hi / o.hi;
        let r = r - o * Dd::new(q2);
        let q3 = r.hi / o.hi;
        let q = quick_two_sum(q1, q2);
        q + Dd::new(q3)
    }
}

/// A vector of three double-doubles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DdVec3 {
    pub x: Dd,
    pub y: Dd,
    pub z: Dd,
}

impl DdVec3 {
    /// An `f32` vector, exactly.
    pub fn from_f32(v: Vec3A) -> DdVec3 {
        DdVec3 {
            x: Dd::new(v.x as f64),
            y: Dd::new(v.y as f64),
            z: Dd::new(v.z as f64),
        }
    }

    /// `a - b` for `f32` vectors, exactly.
    pub fn diff(a: Vec3A, b: Vec3A) -> DdVec3 {
        DdVec3 {
            x: Dd::diff(a.x as f64, b.x as f64),
            y: Dd::diff(a.y as f64, b.y as f64),
            z: Dd::diff(a.z as f64, b.z as f64),
        }
    }

    pub fn dot(self, o: DdVec3) -> Dd {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    pub fn cross(self, o: DdVec3) -> DdVec3 {
        DdVec3 {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_what_f64_loses() {
        // (1 + 2^-60) - 1 is 0 in f64 and 2^-60 in double-double.
        let tiny = 2f64.powi(-60);
        let x = Dd::new(1.0) + Dd::new(tiny);
        assert_eq!((x - Dd::new(1.0)).to_f64(), tiny);
        assert_eq!(Dd::diff(1.0, tiny).lo, -tiny);
        // 1/3 * 3 == 1 to about 1e-32.
        let third = Dd::new(1.0) / Dd::new(3.0);
        let one = third * Dd::new(3.0) - Dd::new(1.0);
        assert!(one.to_f64().abs() < 1e-31, "{one:?}");
        let r = Dd::new(2.0).sqrt();
        assert!((r * r - Dd::new(2.0)).to_f64().abs() < 1e-31);
        assert_eq!(Dd::new(-3.0).signum(), -1);
        assert_eq!(Dd::new(-3.0).sqrt(), Dd::ZERO);
    }
}
