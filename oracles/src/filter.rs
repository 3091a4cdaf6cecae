//! The fast path of exact coverage: midpoint-radius intervals on plain `f64`.
//!
//! Each value carries `v` (the f64 result) and `e`, a bound on `|v - exact|`. With
//! `u = 2^-53` (unit roundoff) and `eta = 4 * 2^-1074`, the rules are, for exact
//! inputs `e = 0`:
//! - `a ± b`: `e = e_a + e_b + u |v| + eta`
//! - `a * b`: `e = |a| e_b + |b| e_a + e_a e_b + u |v| + eta`
//!
//! `eta` covers what underflow can lose in one operation: the value's own rounding
//! (at most 2^-1075 below the normal range) and the three error products, each of which
//! may round to zero (at most 2^-1075 each). These are the error bounds of IEEE round-to-nearest. The bounds are themselves
//! computed in rounded arithmetic, so a sign is trusted only when
//! `|v| > e (1 + 2^-40)`: the few dozen roundings in the error terms cannot inflate
//! them by more than that factor. An overflowed or NaN value never decides. This is an
//! enclosure `[v - e, v + e]` like the outward-rounded interval type, at a third of its
//! cost (no branches, no `next_up`), which is why the per-sample fast path uses it.

use crate::ring::Ring;

pub(crate) const U: f64 = 1.0 / 9007199254740992.0; // 2^-53
pub(crate) const ETA: f64 = f64::from_bits(4); // 4 * 2^-1074

/// A value and a bound on its absolute error.
#[derive(Clone, Copy, Debug)]
pub struct Fe {
    pub v: f64,
    pub e: f64,
}

impl Fe {
    /// The certain sign: Some(1), Some(-1), or None if the error bound cannot exclude 0.
    #[inline(always)]
    pub fn sign(self) -> Option<i8> {
        let lim = self.e * (1.0 + 1.0 / 1099511627776.0);
        if !(self.v.is_finite() && lim.is_finite()) {
            None
        } else if self.v > lim {
            Some(1)
        } else if -self.v > lim {
            Some(-1)
        } else {
            None
        }
    }
}

impl Ring for Fe {
    #[inline(always)]
    fn c(x: f64) -> Self {
        Fe { v: x, e: 0.0 }
    }
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        let v = self.v + o.v;
        Fe { v, e: self.e + o.e + U * v.abs() + ETA }
    }
    #[inline(always)]
    fn sub(&self, o: &Self) -> Self {
        let v = self.v - o.v;
        Fe { v, e: self.e + o.e + U * v.abs() + ETA }
    }
    #[inline(always)]
    fn mul(&self, o: &Self) -> Self {
        let v = self.v * o.v;
        Fe { v, e: self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e + U * v.abs() + ETA }
    }
}
