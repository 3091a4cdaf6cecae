//! Time polynomials side by side in lanes, one lane per box corner, so that the
//! enclosure of a box runs all its corners at once and the compiler vectorises it.

use super::tpoly::TPoly;
use crate::filter::{Fe, ETA, U};
use crate::ring::Ring;

/// `N` [`Fe`] values side by side (values and error bounds): a coefficient of an
/// [`LPoly`], one lane per box corner, so that [`box_values_with`](super::box_values_with) runs all corners of
/// a box at once and the compiler vectorises the loop.
#[derive(Clone, Copy, Debug)]
pub(super) struct Lanes<const N: usize> {
    pub(super) v: [f64; N],
    pub(super) e: [f64; N],
}

/// A polynomial in s with `K` coefficients (degree `K - 1`, fixed at compile time) in
/// `N` lanes. Its operations are those of [`TPoly`], coefficient by coefficient in the
/// same order, so that lane n holds bit for bit what a [`TPoly`] would.
#[derive(Clone, Copy, Debug)]
pub(super) struct LPoly<const K: usize, const N: usize>(pub(super) [Lanes<N>; K]);

impl<const K: usize, const N: usize> LPoly<K, N> {
    /// The polynomial `p` (of degree `K - 1`) in every lane.
    #[inline(always)]
    pub(super) fn splat(p: &TPoly) -> Self {
        debug_assert_eq!(p.deg + 1, K);
        let mut r = Self::zero();
        for k in 0..K {
            r.0[k] = Lanes { v: [p.c[k].v; N], e: [p.c[k].e; N] };
        }
        r
    }
    #[inline(always)]
    pub(super) fn zero() -> Self {
        LPoly([Lanes { v: [0.0; N], e: [0.0; N] }; K])
    }
    #[inline(always)]
    pub(super) fn add(&self, o: &Self) -> Self {
        let mut r = Self::zero();
        for k in 0..K {
            let (a, b, q) = (&self.0[k], &o.0[k], &mut r.0[k]);
            for n in 0..N {
                let v = a.v[n] + b.v[n];
                q.v[n] = v;
                q.e[n] = a.e[n] + b.e[n] + U * v.abs() + ETA;
            }
        }
        r
    }
    #[inline(always)]
    pub(super) fn sub(&self, o: &Self) -> Self {
        let mut r = Self::zero();
        for k in 0..K {
            let (a, b, q) = (&self.0[k], &o.0[k], &mut r.0[k]);
            for n in 0..N {
                let v = a.v[n] - b.v[n];
                q.v[n] = v;
                q.e[n] = a.e[n] + b.e[n] + U * v.abs() + ETA;
            }
        }
        r
    }
    /// The product, `C = K + B - 1` coefficients: [`TPoly`]'s loop (each coefficient
    /// starts at zero and gathers its products in the order i, then j).
    #[inline(always)]
    pub(super) fn mul<const B: usize, const C: usize>(&self, o: &LPoly<B, N>) -> LPoly<C, N> {
        debug_assert_eq!(C, K + B - 1);
        let mut r = LPoly::<C, N>::zero();
        for i in 0..K {
            for j in 0..B {
                let (a, b, q) = (&self.0[i], &o.0[j], &mut r.0[i + j]);
                for n in 0..N {
                    // The product as [`Fe`] forms it, then added to the coefficient.
                    let pv = a.v[n] * b.v[n];
                    let pe = a.v[n].abs() * b.e[n] + b.v[n].abs() * a.e[n] + a.e[n] * b.e[n] + U * pv.abs() + ETA;
                    let v = q.v[n] + pv;
                    q.e[n] = q.e[n] + pe + U * v.abs() + ETA;
                    q.v[n] = v;
                }
            }
        }
        r
    }
    /// Lane `n` as a [`TPoly`].
    pub(super) fn lane(&self, n: usize) -> TPoly {
        let mut p = TPoly::c(0.0);
        for k in 0..K {
            p.c[k] = Fe { v: self.0[k].v[n], e: self.0[k].e[n] };
        }
        p.deg = K - 1;
        p
    }
    /// [`TPoly::range`] in every lane (the same expressions, lane by lane): the lower
    /// and upper ends.
    #[inline(always)]
    pub(super) fn range(&self, h: f64) -> ([f64; N], [f64; N]) {
        let c = &self.0;
        let h2 = (h * h).next_up();
        let h3 = (h2 * h).next_up();
        let mut out_lo = [0.0; N];
        let mut out_hi = [0.0; N];
        for n in 0..N {
            let (mut lo, mut hi) = (c[0].v[n] - c[0].e[n], c[0].v[n] + c[0].e[n]);
            let mut mag = c[0].v[n].abs() + c[0].e[n];
            if K >= 2 {
                let a = (c[1].v[n].abs() + c[1].e[n]) * h;
                lo -= a;
                hi += a;
                mag += a;
            }
            if K >= 3 {
                lo += (c[2].v[n] - c[2].e[n]).min(0.0) * h2;
                hi += (c[2].v[n] + c[2].e[n]).max(0.0) * h2;
                mag += (c[2].v[n].abs() + c[2].e[n]) * h2;
            }
            if K >= 4 {
                let a = (c[3].v[n].abs() + c[3].e[n]) * h3;
                lo -= a;
                hi += a;
                mag += a;
            }
            let pad = mag * (1.0 / 281474976710656.0) + f64::from_bits(64);
            let ok = mag.is_finite() && lo.is_finite() && hi.is_finite();
            out_lo[n] = if ok { lo - pad } else { f64::NAN };
            out_hi[n] = if ok { hi + pad } else { f64::NAN };
        }
        (out_lo, out_hi)
    }
    /// [`TPoly::variation`] in every lane.
    #[inline(always)]
    pub(super) fn variation(&self, h: f64) -> [f64; N] {
        let c = &self.0;
        std::array::from_fn(|n| {
            let m = |k: usize| if k < K { c[k].v[n].abs() + c[k].e[n] } else { 0.0 };
            m(1) * h + m(2) * h * h + m(3) * h * h * h
        })
    }
}

/// The constant (degree-0) polynomial holding the exact value `v[n]` in lane n.
#[inline(always)]
pub(super) fn lconst<const N: usize>(v: &[f64; N]) -> LPoly<1, N> {
    LPoly([Lanes { v: *v, e: [0.0; N] }])
}
