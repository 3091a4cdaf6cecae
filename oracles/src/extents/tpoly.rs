//! Time polynomials: the coverage values at a box corner as exact polynomials in the
//! offset from the box's middle time, with rigorous rounding-error bounds.

use crate::filter::Fe;
use crate::interval::Interval;
use crate::ring::Ring;

/// A polynomial of degree <= 3 in `s = t - t_mid`, each coefficient an f64 value with
/// a rigorous bound on its rounding error ([`Fe`]); the degree is tracked so that
/// coefficients known to be zero stay out of products. At a box corner every input is a
/// point and t is symbolic, so the coefficients carry rounding error only: the
/// value-plus-error form is as tight as an interval there, and cheaper.
#[derive(Clone, Copy, Debug)]
pub struct TPoly {
    pub c: [Fe; 4],
    pub deg: usize,
}

pub(super) const FE0: Fe = Fe { v: 0.0, e: 0.0 };

impl TPoly {
    /// `t_mid + s`.
    pub fn t_at(tm: f64) -> Self {
        TPoly { c: [Fe::c(tm), Fe::c(1.0), FE0, FE0], deg: 1 }
    }
    /// The value at `s = 0` (the box's middle time), without its error.
    pub fn mid(&self) -> f64 {
        self.c[0].v
    }
    /// How much the non-constant terms can move the value over `s in [-h, h]`.
    pub fn variation(&self, h: f64) -> f64 {
        let m = |k: usize| self.c[k].v.abs() + self.c[k].e;
        m(1) * h + m(2) * h * h + m(3) * h * h * h
    }
    /// Enclosure of the values for `s in [-h, h]` (h >= 0). Each coefficient `c_k` lies
    /// in `[v_k - e_k, v_k + e_k]`; odd terms span `+-|c_k| h^k`, the square term has the
    /// sign of `c_2`. The bounds are summed in f64 and then widened by `2^-48` of the
    /// sum of magnitudes (the dozen roundings of the sum cost less) plus an underflow
    /// floor. NaN when anything overflowed: such a box stays undecided.
    pub fn range(&self, h: f64) -> Interval {
        let c = &self.c;
        let h2 = (h * h).next_up();
        let h3 = (h2 * h).next_up();
        let (mut lo, mut hi) = (c[0].v - c[0].e, c[0].v + c[0].e);
        let mut mag = c[0].v.abs() + c[0].e;
        if self.deg >= 1 {
            let a = (c[1].v.abs() + c[1].e) * h;
            lo -= a;
            hi += a;
            mag += a;
        }
        if self.deg >= 2 {
            lo += (c[2].v - c[2].e).min(0.0) * h2;
            hi += (c[2].v + c[2].e).max(0.0) * h2;
            mag += (c[2].v.abs() + c[2].e) * h2;
        }
        if self.deg >= 3 {
            let a = (c[3].v.abs() + c[3].e) * h3;
            lo -= a;
            hi += a;
            mag += a;
        }
        if !(mag.is_finite() && lo.is_finite() && hi.is_finite()) {
            return Interval::new(f64::NAN, f64::NAN);
        }
        let pad = mag * (1.0 / 281474976710656.0) + f64::from_bits(64);
        Interval::new(lo - pad, hi + pad)
    }
}

impl Ring for TPoly {
    #[inline(always)]
    fn c(x: f64) -> Self {
        TPoly { c: [Fe::c(x), FE0, FE0, FE0], deg: 0 }
    }
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        let deg = self.deg.max(o.deg);
        let mut c = [FE0; 4];
        for (k, ck) in c.iter_mut().enumerate().take(deg + 1) {
            *ck = self.c[k].add(&o.c[k]);
        }
        TPoly { c, deg }
    }
    #[inline(always)]
    fn sub(&self, o: &Self) -> Self {
        let deg = self.deg.max(o.deg);
        let mut c = [FE0; 4];
        for (k, ck) in c.iter_mut().enumerate().take(deg + 1) {
            *ck = self.c[k].sub(&o.c[k]);
        }
        TPoly { c, deg }
    }
    #[inline(always)]
    fn mul(&self, o: &Self) -> Self {
        let deg = self.deg + o.deg;
        if deg > 3 {
            // Never happens for the coverage polynomials (degree <= 3); if it did, the
            // result would be unusable: poison it so the box stays undecided.
            let nan = Fe { v: f64::NAN, e: f64::NAN };
            return TPoly { c: [nan; 4], deg: 3 };
        }
        let mut r = [FE0; 4];
        for i in 0..=self.deg {
            for j in 0..=o.deg {
                r[i + j] = r[i + j].add(&self.c[i].mul(&o.c[j]));
            }
        }
        TPoly { c: r, deg }
    }
}
