//! Polynomials in t: exact dyadic coefficients for building the coverage polynomials
//! of one ray, and rational coefficients for isolating their real roots (Sturm).

use crate::dyadic::Dyadic;
use crate::ring::Ring;
use num_rational::BigRational;
use num_traits::{Signed, Zero};

/// `sum_i c[i] t^i` with exact dyadic coefficients.
#[derive(Clone, Debug)]
pub struct DyPoly(pub Vec<Dyadic>);

impl DyPoly {
    /// The polynomial `t`.
    pub fn t() -> Self {
        DyPoly(vec![Dyadic::zero(), Dyadic::one()])
    }
    fn trim(mut self) -> Self {
        while self.0.len() > 1 && self.0.last().is_some_and(|c| c.is_zero()) {
            self.0.pop();
        }
        self
    }
    pub fn to_rational(&self) -> RatPoly {
        RatPoly(self.0.iter().map(|c| c.to_rational()).collect()).trim()
    }
    /// Exact value at a double.
    pub fn eval(&self, t: f64) -> Dyadic {
        let t = Dyadic::from_f64(t);
        let mut acc = Dyadic::zero();
        for c in self.0.iter().rev() {
            acc = &(&acc * &t) + c;
        }
        acc
    }
}

impl Ring for DyPoly {
    fn c(x: f64) -> Self {
        DyPoly(vec![Dyadic::from_f64(x)])
    }
    fn add(&self, o: &Self) -> Self {
        let n = self.0.len().max(o.0.len());
        let z = Dyadic::zero();
        DyPoly((0..n).map(|i| self.0.get(i).unwrap_or(&z) + o.0.get(i).unwrap_or(&z)).collect()).trim()
    }
    fn sub(&self, o: &Self) -> Self {
        let n = self.0.len().max(o.0.len());
        let z = Dyadic::zero();
        DyPoly((0..n).map(|i| self.0.get(i).unwrap_or(&z) - o.0.get(i).unwrap_or(&z)).collect()).trim()
    }
    fn mul(&self, o: &Self) -> Self {
        let mut r = vec![Dyadic::zero(); self.0.len() + o.0.len() - 1];
        for (i, a) in self.0.iter().enumerate() {
            if a.is_zero() {
                continue;
            }
            for (j, b) in o.0.iter().enumerate() {
                r[i + j] = &r[i + j] + &(a * b);
            }
        }
        DyPoly(r).trim()
    }
}

/// `sum_i c[i] t^i` with rational coefficients; the zero polynomial is `[0]`.
#[derive(Clone, Debug, PartialEq)]
pub struct RatPoly(pub Vec<BigRational>);

impl RatPoly {
    fn trim(mut self) -> Self {
        while self.0.len() > 1 && self.0.last().is_some_and(|c| c.is_zero()) {
            self.0.pop();
        }
        if self.0.is_empty() {
            self.0.push(BigRational::zero());
        }
        self
    }
    pub fn is_zero(&self) -> bool {
        self.0.iter().all(|c| c.is_zero())
    }
    /// Degree; 0 for constants including zero.
    pub fn degree(&self) -> usize {
        self.0.len() - 1
    }
    pub fn eval(&self, t: &BigRational) -> BigRational {
        let mut acc = BigRational::zero();
        for c in self.0.iter().rev() {
            acc = acc * t + c;
        }
        acc
    }
    pub fn sign_at(&self, t: &BigRational) -> i8 {
        let v = self.eval(t);
        if v.is_zero() {
            0
        } else if v.is_positive() {
            1
        } else {
            -1
        }
    }
    pub fn derivative(&self) -> RatPoly {
        if self.0.len() <= 1 {
            return RatPoly(vec![BigRational::zero()]);
        }
        RatPoly(
            self.0.iter().enumerate().skip(1).map(|(i, c)| c * BigRational::from_integer((i as i64).into())).collect(),
        )
        .trim()
    }
    /// Quotient and remainder of polynomial division (divisor non-zero).
    pub fn div_rem(&self, d: &RatPoly) -> (RatPoly, RatPoly) {
        assert!(!d.is_zero(), "polynomial division by zero");
        let mut r = self.0.clone();
        let dd = d.degree();
        let lead = d.0[dd].clone();
        if self.degree() < dd || self.is_zero() {
            return (RatPoly(vec![BigRational::zero()]), self.clone());
        }
        let mut q = vec![BigRational::zero(); self.degree() - dd + 1];
        for i in (0..q.len()).rev() {
            let coef = &r[i + dd] / &lead;
            for j in 0..=dd {
                r[i + j] = &r[i + j] - &coef * &d.0[j];
            }
            q[i] = coef;
        }
        r.truncate(dd.max(1));
        (RatPoly(q).trim(), RatPoly(r).trim())
    }
    fn neg(&self) -> RatPoly {
        RatPoly(self.0.iter().map(|c| -c).collect())
    }
    /// Greatest common divisor (up to a constant factor).
    pub fn gcd(&self, o: &RatPoly) -> RatPoly {
        let (mut a, mut b) = (self.clone(), o.clone());
        while !b.is_zero() {
            let (_, r) = a.div_rem(&b);
            a = b;
            b = r;
        }
        a
    }
    /// The square-free part: same distinct roots, each simple.
    pub fn square_free(&self) -> RatPoly {
        let g = self.gcd(&self.derivative());
        if g.degree() == 0 {
            return self.clone();
        }
        self.div_rem(&g).0
    }
    /// The Sturm sequence of a square-free polynomial.
    pub fn sturm(&self) -> Vec<RatPoly> {
        let mut s = vec![self.clone(), self.derivative()];
        while !s.last().is_some_and(|p| p.is_zero()) && s.last().is_some_and(|p| p.degree() > 0) {
            let n = s.len();
            let (_, r) = s[n - 2].div_rem(&s[n - 1]);
            s.push(r.neg());
        }
        if s.last().is_some_and(|p| p.is_zero()) {
            s.pop();
        }
        s
    }
}

/// Sign changes of a Sturm sequence at t (zeros skipped).
pub fn sign_changes(seq: &[RatPoly], t: &BigRational) -> usize {
    let mut last = 0i8;
    let mut n = 0;
    for p in seq {
        let s = p.sign_at(t);
        if s != 0 {
            if last != 0 && s != last {
                n += 1;
            }
            last = s;
        }
    }
    n
}
