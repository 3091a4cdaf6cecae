//! Certified bounds on the hit depth of the covered samples of a box, by one
//! Lagrangian combination of the depth with the edge values per end.
//!
//! The hit depth is `N / D`. For a fixed (u, v, t), `N` is affine in (x, y) and `D`
//! does not depend on them, so the depth over the covered polygon is a linear
//! programme: its supremum is at a vertex of the polygon clipped to the box's
//! rectangle. A covered sample has every `E_k / D > 0` (all four values of one strict
//! sign), so for any multipliers `lambda_k >= 0`
//!
//! `(N - sum lambda_k E_k) / D  <=  N / D  <=  (N + sum lambda_k E_k) / D`
//!
//! at every covered sample, whatever the signs of the `w_i`, as long as `D` keeps one
//! sign over the box. The outer quotients are bounded over the whole box like the
//! depth itself: the numerator is affine in each of x, y, u, v separately (as every
//! `E_k` and `N` is) and `D` in each of u, v, so each quotient is monotone in each
//! coordinate and takes its extremes at the 16 corners; in t it is written around its
//! value at the middle, `z_c + (G - z_c D) / D`, so that `G` and `D` moving together in
//! t cost nothing (a centred form), and bounded term by term with outward rounding.
//!
//! With `lambda = 0` this is the corner quotient of the depth over every sample of the
//! box, covered or not. The multipliers that make it exact at the box's middle (u, v, t)
//! are those of the linear programme's dual: at most two are non-zero, and the optimum
//! is where as many rectangle corners tie. [`multipliers`] enumerates those vertices
//! (plain f64, a heuristic: any non-negative multipliers are sound; only the
//! outward-rounded enclosure certifies), so the bound converges to the true extreme
//! as the (u, v, t) box shrinks, without splitting x or y.

use super::lanes::{lconst, LPoly};
use crate::coverage::interval_div;
use crate::interval::Interval;

/// Certified bounds on the hit depth of every covered sample of a box, and how much
/// u, v and t each move them (a guide for splitting).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct CoveredDepth {
    /// The bounds; an end is infinite where nothing was certified.
    pub bounds: Interval,
    /// For each of u, v, t: the largest change of the bounds' lane values between
    /// corners that differ in that coordinate only (t: the non-constant terms over |D|).
    pub smear: [f64; 3],
}

/// The bounds of [`CoveredDepth`] from the edge values `ev`, the depth numerator `n`
/// and `D` (`d`), all in the 16 lanes of the box corners (lane `8 iu + 4 iv + 2 ix +
/// iy`) as polynomials in `s = t - t_mid` over `s in [-h, h]`. `D`'s enclosure must keep
/// one sign over the box (else nothing is certified). Only the ends asked for in
/// `ends` (lower, upper) are certified; the others stay infinite.
pub(super) fn covered_depth(
    ev: &[LPoly<3, 16>; 3],
    n: &LPoly<4, 16>,
    d: &LPoly<4, 16>,
    h: f64,
    ends: [bool; 2],
) -> CoveredDepth {
    let whole = CoveredDepth { bounds: Interval::new(f64::NEG_INFINITY, f64::INFINITY), smear: [0.0; 3] };
    let (d_lo, d_hi) = d.range(h);
    let pos = d_lo.iter().all(|&v| v > 0.0);
    let neg = d_hi.iter().all(|&v| v < 0.0);
    if !(pos || neg) {
        return whole;
    }
    let sg = if pos { 1.0 } else { -1.0 };
    let dm = &d.0[0].v;
    let mut out = whole;
    for upper in [true, false] {
        if !ends[upper as usize] {
            continue;
        }
        // Upper end: maximise sg N / |D| subject to sg E_k > 0; lower end: the same for
        // -sg N. Both relax to max (a + sum lambda_k b_k) / |D|, b_k = sg E_k.
        let s = if upper { 1.0 } else { -1.0 };
        let a: [f64; 16] = std::array::from_fn(|c| s * sg * n.0[0].v[c]);
        let b: [[f64; 16]; 3] = std::array::from_fn(|k| std::array::from_fn(|c| sg * ev[k].0[0].v[c]));
        let inv: [f64; 16] = std::array::from_fn(|c| 1.0 / dm[c].abs());
        let lam = multipliers(&a, &b, &inv);
        // G = N + s sum lambda_k E_k (the quotient G / D bounds the depth on the side s).
        let mut g = *n;
        for (k, &l) in lam.iter().enumerate() {
            if l != 0.0 {
                g = g.add(&widen(&lconst(&[s * l; 16]).mul::<3, 3>(&ev[k])));
            }
        }
        let zc: [f64; 16] = std::array::from_fn(|c| g.0[0].v[c] / dm[c]);
        if zc.iter().any(|z| !z.is_finite()) {
            continue;
        }
        let m = g.sub(&lconst(&zc).mul::<4, 4>(d));
        let (m_lo, m_hi) = m.range(h);
        let m_var = m.variation(h);
        let mut end = if upper { f64::NEG_INFINITY } else { f64::INFINITY };
        let mut lane_end = [0.0; 16];
        let mut ok = true;
        for c in 0..16 {
            let q = interval_div(Interval::new(m_lo[c], m_hi[c]), Interval::new(d_lo[c], d_hi[c]))
                .map(|q| Interval::point(zc[c]) + q);
            match q {
                Some(q) if !(q.lo.is_nan() || q.hi.is_nan()) => {
                    lane_end[c] = if upper { q.hi } else { q.lo };
                    end = if upper { end.max(q.hi) } else { end.min(q.lo) };
                }
                _ => ok = false,
            }
        }
        if !ok || !end.is_finite() {
            continue;
        }
        if upper {
            out.bounds.hi = end;
        } else {
            out.bounds.lo = end;
        }
        let spread = |bit: usize| {
            (0..16).filter(|c| c & bit == 0).map(|c| (lane_end[c | bit] - lane_end[c]).abs()).fold(0.0, f64::max)
        };
        let t = (0..16).map(|c| m_var[c] / dm[c].abs()).fold(0.0, f64::max);
        for (o, v) in out.smear.iter_mut().zip([spread(8), spread(4), t]) {
            if v.is_finite() {
                *o = o.max(v);
            }
        }
    }
    out
}

/// A polynomial of degree 2 as one of degree 3 (an exact zero cubic term).
fn widen(p: &LPoly<3, 16>) -> LPoly<4, 16> {
    let mut r = LPoly::<4, 16>::zero();
    r.0[..3].copy_from_slice(&p.0);
    r
}

/// For each rectangle corner, the other three.
const OTHERS: [[usize; 3]; 4] = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];

/// Non-negative multipliers that make `max_c (a_c + sum_k lambda_k b_kc) / |D_c|` small,
/// from the values at the box's middle time in the 16 corner lanes (`inv` holds
/// `1 / |D_c|`). The candidates are the vertices of the linear programme at the
/// middle (u, v) (the mean of the four lens corners: exact for a function affine in u
/// and in v, and D is the same at the four (x, y) corners): no multiplier, one where
/// two rectangle corners tie, two where three tie; each is scored over all 16 lanes.
fn multipliers(a: &[f64; 16], b: &[[f64; 16]; 3], inv: &[f64; 16]) -> [f64; 3] {
    let mid = |v: &[f64; 16]| -> [f64; 4] { std::array::from_fn(|c| 0.25 * (v[c] + v[4 + c] + v[8 + c] + v[12 + c])) };
    let am = mid(a);
    let bm: [[f64; 4]; 3] = std::array::from_fn(|k| mid(&b[k]));
    let score = |l: &[f64; 3]| -> f64 {
        (0..16)
            .map(|c| (a[c] + l[0] * b[0][c] + l[1] * b[1][c] + l[2] * b[2][c]) * inv[c])
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let mut best = ([0.0; 3], score(&[0.0; 3]));
    let mut consider = |l: [f64; 3]| {
        if l.iter().any(|v| !(v.is_finite() && *v >= 0.0)) {
            return;
        }
        let s = score(&l);
        if s < best.1 {
            best = (l, s);
        }
    };
    for k in 0..3 {
        for c in 0..4 {
            for c2 in c + 1..4 {
                // a_c + l b_kc = a_c2 + l b_kc2
                let den = bm[k][c] - bm[k][c2];
                if den != 0.0 {
                    let mut l = [0.0; 3];
                    l[k] = (am[c2] - am[c]) / den;
                    consider(l);
                }
            }
        }
    }
    for k in 0..3 {
        for j in k + 1..3 {
            for cs in OTHERS {
                // Corners cs[0], cs[1], cs[2] tie: two equations in (l_k, l_j).
                let row = |p: usize| {
                    let (c0, c1) = (cs[0], cs[p]);
                    (bm[k][c0] - bm[k][c1], bm[j][c0] - bm[j][c1], am[c1] - am[c0])
                };
                let (p11, p12, r1) = row(1);
                let (p21, p22, r2) = row(2);
                let det = p11 * p22 - p12 * p21;
                if det != 0.0 {
                    let mut l = [0.0; 3];
                    l[k] = (r1 * p22 - p12 * r2) / det;
                    l[j] = (p11 * r2 - r1 * p21) / det;
                    consider(l);
                }
            }
        }
    }
    best.0
}

#[cfg(test)]
mod tests {
    use crate::coverage::{classify, depth_enclosure, Coverage};
    use crate::extents::enclosure::{box_values_eliminating, Box5};
    use crate::extents::testgen::{random_sliver, random_tri, unit_stream};
    use crate::interval::Interval;

    /// The certified depth bounds of a box hold the exact depth of every covered sample
    /// drawn in it, on random boxes of random triangles (behind the lens and slivers
    /// included), and they are finite and tighter than the corner quotient at one end
    /// or both on a fair share of them (the test would notice bounds that never certify anything).
    #[test]
    fn covered_depth_holds_the_depth_of_every_covered_sample() {
        let mut next = unit_stream(0x3C6E_F372_FE94_F82B);
        let (mut checked, mut boxes, mut bounded, mut tighter) = (0, 0, 0, 0);
        for round in 0..800 {
            let tri = if round % 2 == 1 { random_sliver(&mut next, true) } else { random_tri(&mut next) };
            for _ in 0..12 {
                let s = [next() * 8.0 - 4.0, next() * 8.0 - 4.0, next() * 2.0 - 1.0, next() * 2.0 - 1.0, next()];
                if classify(&tri, s) != Coverage::Interior {
                    continue;
                }
                let scale = [2.0, 2.0, 2.0, 2.0, 1.0];
                let b: Box5 = std::array::from_fn(|k| {
                    let f = scale[k] * 0.5f64.powi((next() * if k < 2 { 6.0 } else { 16.0 }) as i32);
                    Interval::new(s[k] - f * next(), s[k] + f * next())
                });
                let bv = box_values_eliminating(&tri, &b, true);
                let cd = bv.covered_depth;
                boxes += 1;
                if cd.lo.is_finite() && cd.hi.is_finite() {
                    bounded += 1;
                    if let Some(q) = bv.depth {
                        tighter += (cd.hi < q.hi || cd.lo > q.lo) as usize;
                    }
                }
                for _ in 0..40 {
                    let p: [f64; 5] = std::array::from_fn(|k| b[k].lo + next() * b[k].width());
                    if classify(&tri, p) != Coverage::Interior {
                        continue;
                    }
                    let z = depth_enclosure(&tri, p).expect("interior: D != 0");
                    assert!(cd.lo <= z.lo && z.hi <= cd.hi, "depth {z:?} outside {cd:?} at {p:?} in {b:?} of {tri:?}");
                    checked += 1;
                }
            }
        }
        assert!(checked > 5000 && boxes > 1000, "{checked} samples in {boxes} boxes");
        assert!(bounded * 2 > boxes && tighter * 5 > bounded, "{bounded} of {boxes} bounded, {tighter} tighter");
    }
}
