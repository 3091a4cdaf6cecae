//! The arithmetic the coverage polynomials need: a commutative ring with constants.
//!
//! One generic formula (`coverage::edge_values`) is evaluated in three rings:
//! outward-rounded intervals (fast path), exact dyadics (fallback) and polynomials in
//! t with dyadic coefficients (per-ray time intervals).

use crate::dyadic::Dyadic;
use crate::interval::Interval;

pub trait Ring: Clone {
    /// The exact constant `x` (x finite).
    fn c(x: f64) -> Self;
    fn add(&self, o: &Self) -> Self;
    fn sub(&self, o: &Self) -> Self;
    fn mul(&self, o: &Self) -> Self;
    /// `(1 - t) * a + t * b`, the model's linear motion.
    #[inline]
    fn lerp(a: &Self, b: &Self, t: &Self) -> Self {
        Self::c(1.0).sub(t).mul(a).add(&t.mul(b))
    }
}

impl Ring for Interval {
    #[inline(always)]
    fn c(x: f64) -> Self {
        Interval::point(x)
    }
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        *self + *o
    }
    #[inline(always)]
    fn sub(&self, o: &Self) -> Self {
        *self - *o
    }
    #[inline(always)]
    fn mul(&self, o: &Self) -> Self {
        *self * *o
    }
}

impl Ring for Dyadic {
    fn c(x: f64) -> Self {
        Dyadic::from_f64(x)
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
}
