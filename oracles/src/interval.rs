//! A small outward-rounded interval type on `f64`.
//!
//! Why our own and not `inari`: every operation the coverage polynomials need is `+`,
//! `-` and `*` (no division, no transcendental functions), and the one rule that makes
//! an enclosure sound here is simple: IEEE round-to-nearest errs by at most half an
//! ulp, so stepping each computed bound one ulp outward (`next_down` / `next_up`)
//! encloses the exact result. That needs no rounding-mode switch, no special target
//! CPU flags (`inari` needs `-Ctarget-cpu=x86-64-v3`) and is auditable in a page.
//! NaN never escapes as a false verdict: every sign query compares with `>`/`<`,
//! which is false for NaN, so a NaN interval is "undecided" and goes to the exact path.

use std::ops::{Add, Mul, Neg, Sub};

/// A closed interval `[lo, hi]` of reals that is guaranteed to contain the exact value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    pub lo: f64,
    pub hi: f64,
}

#[inline(always)]
fn down(x: f64) -> f64 {
    x.next_down()
}
#[inline(always)]
fn up(x: f64) -> f64 {
    x.next_up()
}

impl Interval {
    /// The degenerate interval holding exactly `x`.
    #[inline(always)]
    pub const fn point(x: f64) -> Self {
        Interval { lo: x, hi: x }
    }
    /// `[lo, hi]`, which the caller promises encloses the value (lo <= hi).
    #[inline(always)]
    pub const fn new(lo: f64, hi: f64) -> Self {
        Interval { lo, hi }
    }
    /// True if every value in the interval is > 0.
    #[inline(always)]
    pub fn is_pos(self) -> bool {
        self.lo > 0.0
    }
    /// True if every value in the interval is < 0.
    #[inline(always)]
    pub fn is_neg(self) -> bool {
        self.hi < 0.0
    }
    /// The sign of every value: Some(1), Some(-1), or None when it straddles 0
    /// (or touches it, or is NaN).
    #[inline(always)]
    pub fn strict_sign(self) -> Option<i8> {
        if self.lo > 0.0 {
            Some(1)
        } else if self.hi < 0.0 {
            Some(-1)
        } else {
            None
        }
    }
    #[inline(always)]
    pub fn width(self) -> f64 {
        self.hi - self.lo
    }
    #[inline(always)]
    pub fn mid(self) -> f64 {
        0.5 * self.lo + 0.5 * self.hi
    }
    #[inline(always)]
    pub fn contains(self, x: f64) -> bool {
        self.lo <= x && x <= self.hi
    }
    /// Smallest interval containing both.
    #[inline(always)]
    pub fn hull(self, o: Interval) -> Interval {
        Interval { lo: self.lo.min(o.lo), hi: self.hi.max(o.hi) }
    }
}

impl Add for Interval {
    type Output = Interval;
    #[inline(always)]
    fn add(self, o: Interval) -> Interval {
        // Adding an exact zero is exact: keep it so (zeros stay zeros).
        if o.lo == 0.0 && o.hi == 0.0 {
            return self;
        }
        if self.lo == 0.0 && self.hi == 0.0 {
            return o;
        }
        Interval { lo: down(self.lo + o.lo), hi: up(self.hi + o.hi) }
    }
}

impl Sub for Interval {
    type Output = Interval;
    #[inline(always)]
    fn sub(self, o: Interval) -> Interval {
        if o.lo == 0.0 && o.hi == 0.0 {
            return self;
        }
        Interval { lo: down(self.lo - o.hi), hi: up(self.hi - o.lo) }
    }
}

impl Neg for Interval {
    type Output = Interval;
    #[inline(always)]
    fn neg(self) -> Interval {
        Interval { lo: -self.hi, hi: -self.lo }
    }
}

impl Mul for Interval {
    type Output = Interval;
    #[inline(always)]
    fn mul(self, o: Interval) -> Interval {
        // A product with an exact zero (of finite numbers) is an exact zero.
        if (self.lo == 0.0 && self.hi == 0.0 && o.lo.is_finite() && o.hi.is_finite())
            || (o.lo == 0.0 && o.hi == 0.0 && self.lo.is_finite() && self.hi.is_finite())
        {
            return Interval::point(0.0);
        }
        let a = self.lo * o.lo;
        let b = self.lo * o.hi;
        let c = self.hi * o.lo;
        let d = self.hi * o.hi;
        // min/max propagate NaN unpredictably; an explicit NaN check keeps NaN visible.
        let lo = a.min(b).min(c.min(d));
        let hi = a.max(b).max(c.max(d));
        if a.is_nan() || b.is_nan() || c.is_nan() || d.is_nan() {
            return Interval { lo: f64::NAN, hi: f64::NAN };
        }
        Interval { lo: down(lo), hi: up(hi) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encloses_a_rounded_sum() {
        // 0.1 + 0.2 is not 0.3 in f64; the enclosure must contain both neighbours of the
        // exact real sum of the two doubles.
        let s = Interval::point(0.1) + Interval::point(0.2);
        assert!(s.lo < 0.1 + 0.2 && s.hi > 0.1 + 0.2);
        assert!(s.lo <= 0.30000000000000004 && s.hi >= 0.30000000000000004);
    }

    #[test]
    fn nan_is_never_signed() {
        let n = Interval::point(f64::INFINITY) * Interval::point(0.0);
        assert_eq!(n.strict_sign(), None);
        assert!(!n.is_pos() && !n.is_neg());
    }

    #[test]
    fn product_of_mixed_signs() {
        let p = Interval::new(-2.0, 3.0) * Interval::new(-5.0, 1.0);
        assert!(p.lo <= -15.0 && p.hi >= 10.0);
        assert!(p.lo > -15.0000001 && p.hi < 10.0000001);
    }
}
