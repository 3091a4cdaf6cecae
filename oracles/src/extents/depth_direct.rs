//! Depth ends cut by the depth's own numerator, with no plane in between.
//!
//! The hit depth of an interior sample is `N / D` with `N = sum_k E_k z_k` and `D = sum_k
//! E_k w_k` (the coverage rule's edge values `E_k` and determinant, [`crate::coverage`]).
//! So for a bound `z`, on the interior samples whose `D` has the sign `sigma`,
//!
//! `depth >= z  <=>  sigma H >= 0`,  `H = N - z D = sum_k E_k (z_k - z w_k)`.
//!
//! `H` is a polynomial in the sample's coordinates: each `E_k` is a product of a term
//! affine in (x, u) and one affine in (y, v), with coefficients affine in t, so `H` is
//! multilinear in x, y, u, v (no product of x with u, or of y with v) and of degree 3 in
//! t. It does not depend on the box: [`DepthNumerator::new`] builds its coefficients
//! once, as outward-rounded intervals, by evaluating the coverage rule's own formula
//! ([`crate::coverage::edge_values`]) in a ring of such polynomials.
//!
//! Over a box with times `tm +- h`, the cubic part is brought to degree 2 exactly,
//! `t^3 = tm^3 - 3 tm^2 t + 3 tm t^2 + (t - tm)^3`, and the last term's size (at most
//! `|a_3| h^3` times its monomial) goes into the cut's error, as does each coefficient
//! interval's width times its monomial's largest size over the box. The two cuts, one
//! per sign of D ([`Cut::d_sign`]), are then certified like every other cut: with the
//! edge values' multipliers, so only the interior samples count, and near the covered
//! set's extreme depth the combination cancels the first-order part that `H` and the
//! edge through the extreme share. Unlike the moving planes of
//! [`super::depth_plane`], nothing here is a heuristic that a facing flip (a plane
//! turning edge-on, its slopes unbounded) can defeat.

use super::Cut;
use crate::coverage::edge_values;
use crate::interval::Interval;
use crate::ring::Ring;
use crate::tri::Tri;

/// Monomials in x, y, u, v (bit 0 x, bit 1 y, bit 2 u, bit 3 v), as [`Cut`] numbers them.
const MONOMIALS: usize = 16;
/// Powers of t kept: 0 to 3.
const DEGREE: usize = 4;

/// A polynomial multilinear in x, y, u, v and of degree at most 3 in t, with
/// outward-rounded interval coefficients (`c[m][d]`: monomial `m` times `t^d`). A product
/// leaving that form (a square of a coordinate, t^4) marks the result unusable.
#[derive(Clone, Debug)]
struct MPoly {
    c: [[Interval; DEGREE]; MONOMIALS],
    bad: bool,
}

impl MPoly {
    fn zero() -> Self {
        MPoly { c: [[Interval::point(0.0); DEGREE]; MONOMIALS], bad: false }
    }
    /// The coordinate `i` (0 x, 1 y, 2 u, 3 v, 4 t).
    fn var(i: usize) -> Self {
        let mut p = Self::zero();
        if i == 4 {
            p.c[0][1] = Interval::point(1.0);
        } else {
            p.c[1 << i][0] = Interval::point(1.0);
        }
        p
    }
}

impl Ring for MPoly {
    fn c(x: f64) -> Self {
        let mut p = Self::zero();
        p.c[0][0] = Interval::point(x);
        p
    }
    fn add(&self, o: &Self) -> Self {
        let mut p = self.clone();
        p.bad |= o.bad;
        for m in 0..MONOMIALS {
            for d in 0..DEGREE {
                p.c[m][d] = p.c[m][d] + o.c[m][d];
            }
        }
        p
    }
    fn sub(&self, o: &Self) -> Self {
        let mut p = self.clone();
        p.bad |= o.bad;
        for m in 0..MONOMIALS {
            for d in 0..DEGREE {
                p.c[m][d] = p.c[m][d] - o.c[m][d];
            }
        }
        p
    }
    fn mul(&self, o: &Self) -> Self {
        let mut p = Self::zero();
        p.bad = self.bad || o.bad;
        let zero = |iv: &Interval| iv.lo == 0.0 && iv.hi == 0.0;
        for a in 0..MONOMIALS {
            for da in 0..DEGREE {
                if zero(&self.c[a][da]) {
                    continue;
                }
                for b in 0..MONOMIALS {
                    for db in 0..DEGREE {
                        if zero(&o.c[b][db]) {
                            continue;
                        }
                        if a & b != 0 || da + db >= DEGREE {
                            p.bad = true;
                            continue;
                        }
                        p.c[a | b][da + db] = p.c[a | b][da + db] + self.c[a][da] * o.c[b][db];
                    }
                }
            }
        }
        p
    }
}

/// `H = N - z D` of a triangle for one bound `z`, as a polynomial in the sample's
/// coordinates with rigorous coefficients (see the module doc).
#[derive(Clone, Debug)]
pub struct DepthNumerator {
    h: MPoly,
}

impl DepthNumerator {
    /// None for a triangle or bound that is not finite, or coefficients that overflow.
    pub fn new(tri: &Tri, z: f64) -> Option<Self> {
        if !z.is_finite() || tri.check_finite().is_err() {
            return None;
        }
        let v = MPoly::var;
        let ev = edge_values(tri, &v(0), &v(1), &v(2), &v(3), &v(4));
        let h = ev.nz.sub(&MPoly::c(z).mul(&ev.d));
        let finite = h.c.iter().flatten().all(|iv| iv.lo.is_finite() && iv.hi.is_finite());
        (!h.bad && finite).then_some(DepthNumerator { h })
    }

    /// The two cuts over the box `b` (x, y, u, v, t) for a lower end (`depth >= z`) or
    /// an upper one: `sigma H` (or `-sigma H`) tagged with the side `sigma` of D. None
    /// when the box or an error bound is not finite.
    pub fn cuts(&self, b: &[Interval; 5], lower: bool) -> Option<[Cut; 2]> {
        if b.iter().any(|iv| !iv.lo.is_finite() || !iv.hi.is_finite()) {
            return None;
        }
        let pt = Interval::point;
        let mag: [f64; 5] = std::array::from_fn(|i| b[i].lo.abs().max(b[i].hi.abs()));
        let tm = b[4].mid();
        let h = (b[4].hi - tm).max(tm - b[4].lo).max(0.0);
        let (tmi, tm2) = (pt(tm), pt(tm) * pt(tm));
        let tm3 = tm2 * tmi;
        let mut lin = [pt(0.0); 32];
        let mut sq = [pt(0.0); 16];
        // What the cut leaves out: the cube's remainder.
        let mut rest = 0.0f64;
        for m in 0..MONOMIALS {
            let [a0, a1, a2, a3] = self.h.c[m];
            // a3 t^3 = a3 (tm^3 - 3 tm^2 t + 3 tm t^2) + a3 (t - tm)^3.
            lin[m] = a0 + a3 * tm3;
            lin[m | Cut::T] = a1 - pt(3.0) * a3 * tm2;
            sq[m] = a2 + pt(3.0) * a3 * tmi;
            let size = (0..4).filter(|i| m >> i & 1 == 1).fold(1.0f64, |acc, i| acc * mag[i]);
            rest += a3.lo.abs().max(a3.hi.abs()) * size * h * h * h;
        }
        let base = Cut::enclosing(&lin, &sq, b, rest)?;
        let signed = |s: f64, d_sign: i8| {
            let mut c = base;
            c.coef.iter_mut().chain(c.t2.iter_mut()).for_each(|v| *v *= s);
            c.d_sign = d_sign;
            c
        };
        // Lower end: sigma H >= 0 on the side sigma of D; upper end: sigma H <= 0.
        let s = if lower { 1.0 } else { -1.0 };
        Some([signed(s, 1), signed(-s, -1)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dyadic::Dyadic;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The polynomial reproduces `N - z D` at random samples: its coefficients enclose
    /// the exact ones, so the exact value lies within the coefficients' spread.
    #[test]
    fn the_numerator_polynomial_encloses_n_minus_z_d() {
        let mut g = ChaCha8Rng::seed_from_u64(7);
        let mut next = super::super::testgen::unit_stream(11);
        for _ in 0..300 {
            let tri = super::super::testgen::random_tri(&mut next);
            let z: f64 = g.gen_range(-1.0..1.0);
            let Some(p) = DepthNumerator::new(&tri, z) else { continue };
            for _ in 0..20 {
                let s: [f64; 5] = [
                    g.gen_range(-30.0..30.0),
                    g.gen_range(-30.0..30.0),
                    g.gen_range(-1.0..1.0),
                    g.gen_range(-1.0..1.0),
                    g.gen_range(0.0..1.0),
                ];
                let c = Dyadic::from_f64;
                let ev = edge_values(&tri, &c(s[0]), &c(s[1]), &c(s[2]), &c(s[3]), &c(s[4]));
                let exact = (&ev.nz - &(&c(z) * &ev.d)).to_f64();
                let mut lo = 0.0f64;
                let mut hi = 0.0f64;
                let mut scale = 0.0f64;
                for m in 0..MONOMIALS {
                    for d in 0..DEGREE {
                        let mon = (0..4).filter(|i| m >> i & 1 == 1).fold(1.0, |a, i| a * s[i]) * s[4].powi(d as i32);
                        let iv = p.h.c[m][d];
                        let (a, b) = (iv.lo * mon, iv.hi * mon);
                        lo += a.min(b);
                        hi += a.max(b);
                        scale += iv.lo.abs().max(iv.hi.abs()) * mon.abs();
                    }
                }
                let slack = scale * 1e-12 + 1e-300;
                assert!(lo - slack <= exact && exact <= hi + slack, "{exact} not in [{lo}, {hi}]");
            }
        }
    }
}
