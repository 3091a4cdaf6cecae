//! Exact dyadic rationals `m * 2^e` with a big-integer mantissa.
//!
//! Every finite `f32`/`f64` is dyadic, and the coverage polynomials use only `+`, `-`,
//! `*`, so their exact values are dyadic too: this is the exact fallback of the
//! oracle, used when an interval straddles zero. No rounding ever happens here.

use num_bigint::{BigInt, Sign};
use num_rational::BigRational;
use num_traits::{One, Zero};
use std::cmp::Ordering;
use std::ops::{Add, Mul, Neg, Sub};

/// The exact value `m * 2^e`.
#[derive(Clone, Debug)]
pub struct Dyadic {
    pub m: BigInt,
    pub e: i64,
}

impl Dyadic {
    pub fn zero() -> Self {
        Dyadic { m: BigInt::zero(), e: 0 }
    }
    pub fn one() -> Self {
        Dyadic { m: BigInt::one(), e: 0 }
    }
    /// The exact value of a finite double; None for NaN and the infinities (which no
    /// dyadic equals). The checked form: the coverage entry points test their input
    /// with it (see [`crate::coverage::try_classify`]).
    pub fn try_from_f64(x: f64) -> Option<Self> {
        x.is_finite().then(|| Dyadic::from_f64(x))
    }
    /// The exact value of a finite double. Never panics: a non-finite `x` (outside the
    /// model: the oracles judge finite numbers only, and their entry points check
    /// before they get here) takes a stand-in so that no entry point can panic on
    /// hostile input: `+-inf` is `+-2^1024` (beyond every finite double, so an infinite
    /// coordinate acts as one larger than any finite one) and NaN is 0. A verdict
    /// computed from a stand-in means nothing; use [`Dyadic::try_from_f64`] to tell.
    pub fn from_f64(x: f64) -> Self {
        if !x.is_finite() {
            return if x.is_nan() {
                Dyadic::zero()
            } else {
                Dyadic { m: BigInt::from(if x > 0.0 { 1 } else { -1 }), e: 1024 }
            };
        }
        if x == 0.0 {
            return Dyadic::zero();
        }
        let bits = x.to_bits();
        let sign = if bits >> 63 == 1 { -1i64 } else { 1 };
        let exp = ((bits >> 52) & 0x7ff) as i64;
        let frac = bits & ((1u64 << 52) - 1);
        let (mant, e) = if exp == 0 { (frac, -1074) } else { (frac | (1u64 << 52), exp - 1075) };
        Dyadic { m: BigInt::from(mant) * sign, e }.normalized()
    }
    /// Strip trailing zero bits of the mantissa (keeps numbers small).
    pub fn normalized(mut self) -> Self {
        if self.m.is_zero() {
            self.e = 0;
            return self;
        }
        let tz = self.m.trailing_zeros().unwrap_or(0);
        if tz > 0 {
            self.m >>= tz;
            self.e += tz as i64;
        }
        self
    }
    /// -1, 0 or 1.
    pub fn signum(&self) -> i8 {
        match self.m.sign() {
            Sign::Minus => -1,
            Sign::NoSign => 0,
            Sign::Plus => 1,
        }
    }
    pub fn is_zero(&self) -> bool {
        self.m.is_zero()
    }
    /// The exact value as a big rational (for reference computations and root finding).
    pub fn to_rational(&self) -> BigRational {
        if self.e >= 0 {
            BigRational::from_integer(&self.m << (self.e as usize))
        } else {
            BigRational::new(self.m.clone(), BigInt::one() << ((-self.e) as usize))
        }
    }
    /// Nearest-ish double below or equal (for reporting only; never used for a verdict).
    pub fn to_f64(&self) -> f64 {
        if self.m.is_zero() {
            return 0.0;
        }
        let bits = self.m.bits() as i64;
        let shift = (bits - 53).max(0);
        let mm = &self.m >> (shift as usize);
        let e = self.e + shift;
        // |mm| < 2^53 converts exactly; scale in two steps so only the last can round.
        let mf = i64::try_from(&mm).map(|v| v as f64).unwrap_or(f64::NAN);
        let first = e.clamp(-1022, 1023);
        let rest = (e - first).clamp(-2000, 2000);
        mf * 2f64.powi(first as i32) * 2f64.powi(rest as i32)
    }
    fn align(a: &Dyadic, b: &Dyadic) -> (BigInt, BigInt, i64) {
        match a.e.cmp(&b.e) {
            Ordering::Equal => (a.m.clone(), b.m.clone(), a.e),
            Ordering::Greater => (&a.m << ((a.e - b.e) as usize), b.m.clone(), b.e),
            Ordering::Less => (a.m.clone(), &b.m << ((b.e - a.e) as usize), a.e),
        }
    }
    /// Exact comparison.
    pub fn cmp_exact(&self, o: &Dyadic) -> Ordering {
        (self - o).signum().cmp(&0)
    }
}

impl<'a> Add<&'a Dyadic> for &'a Dyadic {
    type Output = Dyadic;
    fn add(self, o: &Dyadic) -> Dyadic {
        if self.m.is_zero() {
            return o.clone();
        }
        if o.m.is_zero() {
            return self.clone();
        }
        let (a, b, e) = Dyadic::align(self, o);
        Dyadic { m: a + b, e }.normalized()
    }
}
impl<'a> Sub<&'a Dyadic> for &'a Dyadic {
    type Output = Dyadic;
    fn sub(self, o: &Dyadic) -> Dyadic {
        if o.m.is_zero() {
            return self.clone();
        }
        let (a, b, e) = Dyadic::align(self, o);
        Dyadic { m: a - b, e }.normalized()
    }
}
impl<'a> Mul<&'a Dyadic> for &'a Dyadic {
    type Output = Dyadic;
    fn mul(self, o: &Dyadic) -> Dyadic {
        if self.m.is_zero() || o.m.is_zero() {
            return Dyadic::zero();
        }
        Dyadic { m: &self.m * &o.m, e: self.e + o.e }
    }
}
impl Neg for &Dyadic {
    type Output = Dyadic;
    fn neg(self) -> Dyadic {
        Dyadic { m: -&self.m, e: self.e }
    }
}
impl Add for Dyadic {
    type Output = Dyadic;
    fn add(self, o: Dyadic) -> Dyadic {
        &self + &o
    }
}
impl Sub for Dyadic {
    type Output = Dyadic;
    fn sub(self, o: Dyadic) -> Dyadic {
        &self - &o
    }
}
impl Mul for Dyadic {
    type Output = Dyadic;
    fn mul(self, o: Dyadic) -> Dyadic {
        &self * &o
    }
}
impl Neg for Dyadic {
    type Output = Dyadic;
    fn neg(self) -> Dyadic {
        -&self
    }
}
impl PartialEq for Dyadic {
    fn eq(&self, o: &Dyadic) -> bool {
        self.cmp_exact(o) == Ordering::Equal
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_f64_is_exact() {
        for &x in &[1.0, -0.1, 3.5e-310, f64::MAX, f64::MIN_POSITIVE, 1e-45f32 as f64, 123456.789] {
            let d = Dyadic::from_f64(x);
            assert_eq!(d.to_f64(), x, "{x}");
        }
    }

    #[test]
    fn non_finite_values_never_panic() {
        assert!(Dyadic::try_from_f64(f64::NAN).is_none());
        assert!(Dyadic::try_from_f64(f64::INFINITY).is_none());
        assert_eq!(Dyadic::try_from_f64(-2.5).unwrap().to_f64(), -2.5);
        // The stand-ins: +-2^1024 lies beyond every double, NaN is 0.
        let big = Dyadic::from_f64(f64::INFINITY);
        assert_eq!(big.cmp_exact(&Dyadic::from_f64(f64::MAX)), Ordering::Greater);
        assert_eq!(Dyadic::from_f64(f64::NEG_INFINITY).cmp_exact(&Dyadic::from_f64(f64::MIN)), Ordering::Less);
        assert!(Dyadic::from_f64(f64::NAN).is_zero());
    }

    #[test]
    fn catches_what_f64_rounds_away() {
        // (1 + 2^-60) - 1 is 2^-60 exactly, but 0 in f64.
        let a = Dyadic::from_f64(1.0) + Dyadic::from_f64(2f64.powi(-60));
        let d = a - Dyadic::from_f64(1.0);
        assert_eq!(d.signum(), 1);
        assert_eq!(d.to_f64(), 2f64.powi(-60));
    }
}
