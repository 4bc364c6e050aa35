//! Error-free transformations and the exact sign of a sum of `f64` values (Shewchuk's
//! Grow-Expansion with zero elimination, "Adaptive Precision Floating-Point Arithmetic and Fast
//! Robust Geometric Predicates", 1997). Used by the exact triangle kernel's fallback and by the
//! accuracy study's double-double arithmetic.

/// `a + b` as an exact sum `s + e` with `s = fl(a + b)` (Knuth's TwoSum; exact for any finite
/// `f64`).
#[inline]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a * b` as an exact sum `p + e` with `p = fl(a * b)` (by a fused multiply-add; exact unless
/// the product underflows).
#[inline]
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// Capacity of an [`ExactSum`]: the number of terms it can absorb.
pub const EXACT_SUM_TERMS: usize = 40;

/// A running exact sum of up to [`EXACT_SUM_TERMS`] finite `f64` terms, kept as a nonoverlapping
/// expansion ordered by increasing magnitude with zeros eliminated, so its sign is the sign of
/// its last component.
#[derive(Debug, Clone)]
pub struct ExactSum {
    parts: [f64; EXACT_SUM_TERMS],
    len: usize,
}

impl Default for ExactSum {
    fn default() -> Self {
        ExactSum {
            parts: [0.0; EXACT_SUM_TERMS],
            len: 0,
        }
    }
}

impl ExactSum {
    /// Adds `b` exactly (Grow-Expansion). Each call grows the expansion by at most one
    /// component; panics after more than [`EXACT_SUM_TERMS`] nonzero additions (a caller bug).
    pub fn add(&mut self, b: f64) {
        let mut q = b;
        let mut out = 0;
        for i in 0..self.len {
            let (s, e) = two_sum(q, self.parts[i]);
            q = s;
            if e != 0.0 {
                self.parts[out] = e;
                out += 1;
            }
        }
        if q != 0.0 {
            self.parts[out] = q;
            out += 1;
        }
        self.len = out;
    }

    /// Adds the exact product `a * b * c` (two components: `a * b` must be exact in `f64`,
    /// as it is for `f32` inputs, and the product must not underflow).
    pub fn add_product3(&mut self, a: f64, b: f64, c: f64) {
        let (p, e) = two_prod(a * b, c);
        self.add(p);
        self.add(e);
    }

    /// The exact sign of the sum: `-1`, `0` or `1`.
    pub fn sign(&self) -> i32 {
        match self.len {
            0 => 0,
            n => {
                let top = self.parts[n - 1];
                (top > 0.0) as i32 - (top < 0.0) as i32
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sign_of_cancelling_sums_is_exact() {
        let mut s = ExactSum::default();
        for x in [1e30, 1.0, -1e30, 1e-30, -1.0] {
            s.add(x);
        }
        assert_eq!(s.sign(), 1, "only 1e-30 survives");
        s.add(-1e-30);
        assert_eq!(s.sign(), 0);
        s.add(-f64::MIN_POSITIVE);
        assert_eq!(s.sign(), -1);
    }

    #[test]
    fn triple_products_are_exact() {
        // (1 + 2^-23)^3 = 1 + 3*2^-23 + 3*2^-46 + 2^-69: 70 bits, more than one f64 holds.
        let a = 1.0 + (2.0f64).powi(-23);
        let mut s = ExactSum::default();
        s.add_product3(a, a, a);
        for x in [-1.0, -3.0 * 2f64.powi(-23), -3.0 * 2f64.powi(-46)] {
            s.add(x);
        }
        assert_eq!(s.sign(), 1);
        s.add(-(2f64.powi(-69)));
        assert_eq!(s.sign(), 0);
    }
}
