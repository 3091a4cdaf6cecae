//! Exact sample coverage: interior / boundary / outside, by the rule of the model.
//!
//! For a sample `s = (x, y, u, v, t)` each vertex is moved to time t, sheared by its
//! circle of confusion `c_i(t)` towards lens position (u, v), and translated so that
//! the sample's pixel is the origin:
//! `P_i = (x_i(t) + u c_i(t) - x w_i(t),  y_i(t) + k v c_i(t) - y w_i(t),  w_i(t))`.
//! The edge values are `E_k = P_i.x P_j.y - P_i.y P_j.x` for (k, i, j) in
//! (0,1,2), (1,2,0), (2,0,1), and `D = det(P_0, P_1, P_2)`.
//!
//! Two facts keep the evaluation cheap and tight. Subtracting `x` times the w column
//! from the x column (and `y` times it from the y column) does not change a
//! determinant, so `D` is the determinant of the sheared vertices alone and does not
//! depend on (x, y). Expanding that determinant along its w column gives
//! `D = w_0 E_0' + w_1 E_1' + w_2 E_2'` where `E_k'` are the edge values at x = y = 0.
//!
//! A sample is **interior** when `D != 0` and every `E_k` has the strict sign of `D`;
//! **boundary** when it is not interior but all four values lie in {0, s} for one sign
//! s (it is in the closure); **outside** otherwise. Interior implies a hit in front of
//! the lens: the hit depth `w_hit = D / (E_0 + E_1 + E_2)` is then positive.
//!
//! The fast path evaluates the four values as certified enclosures (midpoint-radius
//! intervals, [`crate::filter::Fe`]: the f64 value and a rigorous bound on its rounding
//! error); when the signs they prove do not settle the class, every value is recomputed
//! in exact dyadic arithmetic. There is no epsilon anywhere: a sign is taken from the
//! fast path only when the enclosure excludes zero.
//!
//! Input outside the model (a NaN or infinite number in the triangle or the sample)
//! never panics and is never judged by arithmetic: [`try_classify`] answers None, and
//! [`classify`] answers [`Coverage::Outside`] (such a triangle covers nothing: there is
//! no point to cover). Finite input of any size is judged exactly: a value whose f64
//! enclosure overflows simply goes to the exact path.

use crate::dyadic::Dyadic;
use crate::filter::Fe;
use crate::interval::Interval;
use crate::ring::Ring;
use crate::tri::Tri;

/// The class of a sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Coverage {
    Interior,
    Boundary,
    Outside,
}

/// The four polynomials of the coverage rule, plus the depth numerator
/// `N = sum_k E_k z_k(t)` (hit depth = N / D).
#[derive(Clone, Debug)]
pub struct EdgeValues<R> {
    pub e: [R; 3],
    pub d: R,
    pub nz: R,
}

/// The sheared vertices at the sample's (u, v, t): `(x', y', z, w)` per vertex.
pub fn sheared<R: Ring>(tri: &Tri, u: &R, v: &R, t: &R) -> [[R; 4]; 3] {
    let kv = R::c(tri.k).mul(v);
    let one = |i: usize| {
        let l = |j: usize| R::lerp(&R::c(tri.q[i][j]), &R::c(tri.r[i][j]), t);
        let c = R::lerp(&R::c(tri.c0[i]), &R::c(tri.c1[i]), t);
        [l(0).add(&u.mul(&c)), l(1).add(&kv.mul(&c)), l(2), l(3)]
    };
    [one(0), one(1), one(2)]
}

/// D, the determinant of the sheared vertices (independent of x, y).
pub fn det_of<R: Ring>(p: &[[R; 4]; 3]) -> R {
    let e = |i: usize, j: usize| p[i][0].mul(&p[j][1]).sub(&p[i][1].mul(&p[j][0]));
    p[0][3].mul(&e(1, 2)).add(&p[1][3].mul(&e(2, 0))).add(&p[2][3].mul(&e(0, 1)))
}

/// The edge values after translating the pixel (x, y) to the origin.
pub fn edges_of<R: Ring>(p: &[[R; 4]; 3], x: &R, y: &R) -> [R; 3] {
    let px = |i: usize| p[i][0].sub(&x.mul(&p[i][3]));
    let py = |i: usize| p[i][1].sub(&y.mul(&p[i][3]));
    let (x0, x1, x2) = (px(0), px(1), px(2));
    let (y0, y1, y2) = (py(0), py(1), py(2));
    [x1.mul(&y2).sub(&y1.mul(&x2)), x2.mul(&y0).sub(&y2.mul(&x0)), x0.mul(&y1).sub(&y0.mul(&x1))]
}

/// All the values of the coverage rule at one sample (or box, or ray), in ring R.
pub fn edge_values<R: Ring>(tri: &Tri, x: &R, y: &R, u: &R, v: &R, t: &R) -> EdgeValues<R> {
    let p = sheared(tri, u, v, t);
    let d = det_of(&p);
    let e = edges_of(&p, x, y);
    let nz = e[0].mul(&p[0][2]).add(&e[1].mul(&p[1][2])).add(&e[2].mul(&p[2][2]));
    EdgeValues { e, d, nz }
}

/// Class from exact signs (each -1, 0 or 1) of E_0, E_1, E_2, D.
pub fn class_of_signs(s: [i8; 4]) -> Coverage {
    let d = s[3];
    if d != 0 && s.iter().all(|&x| x == d) {
        return Coverage::Interior;
    }
    let has_pos = s.iter().any(|&x| x > 0);
    let has_neg = s.iter().any(|&x| x < 0);
    if has_pos && has_neg {
        Coverage::Outside
    } else {
        Coverage::Boundary
    }
}

/// Counts of how samples were decided.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CoverageStats {
    pub samples: u64,
    pub exact_fallbacks: u64,
}

impl CoverageStats {
    pub fn merge(self, o: CoverageStats) -> CoverageStats {
        CoverageStats { samples: self.samples + o.samples, exact_fallbacks: self.exact_fallbacks + o.exact_fallbacks }
    }
}

/// True when every number of the triangle and of the sample is finite (the input the
/// model admits; see [`crate::tri::Tri::check_finite`] for which one is not).
#[inline]
pub fn finite_input(tri: &Tri, s: &[f64; 5]) -> bool {
    let all = |v: &[f64]| v.iter().all(|x| x.is_finite());
    all(s) && tri.q.iter().chain(tri.r.iter()).all(|p| all(p)) && all(&tri.c0) && all(&tri.c1) && tri.k.is_finite()
}

/// Certified signs, if they settle the class: `None` means go exact.
#[inline]
fn fast_class(ev: &EdgeValues<Fe>) -> Option<Coverage> {
    let s = [ev.e[0].sign(), ev.e[1].sign(), ev.e[2].sign(), ev.d.sign()];
    let any_pos = s.contains(&Some(1));
    let any_neg = s.contains(&Some(-1));
    if any_pos && any_neg {
        return Some(Coverage::Outside);
    }
    if s.iter().all(|&x| x == Some(1)) || s.iter().all(|&x| x == Some(-1)) {
        return Some(Coverage::Interior);
    }
    None
}

/// Exact signs of the four values at a point sample (finite input: see
/// [`finite_input`]; a non-finite number would take the stand-in of
/// [`Dyadic::from_f64`]).
pub fn exact_signs(tri: &Tri, s: [f64; 5]) -> [i8; 4] {
    let c = Dyadic::from_f64;
    let ev = edge_values(tri, &c(s[0]), &c(s[1]), &c(s[2]), &c(s[3]), &c(s[4]));
    [ev.e[0].signum(), ev.e[1].signum(), ev.e[2].signum(), ev.d.signum()]
}

/// Classify one sample `[x, y, u, v, t]`; also says whether the exact path was needed.
/// Non-finite input is [`Coverage::Outside`] (see the module documentation).
#[inline]
pub fn classify_traced(tri: &Tri, s: [f64; 5]) -> (Coverage, bool) {
    // The fast path never decides on a value that overflowed or is NaN (see
    // [`Fe::sign`]), so non-finite input always reaches the check below, which keeps
    // it from the exact path; finite input pays nothing for it on the fast path.
    if let Some(c) = fast_path(tri, s) {
        return (c, false);
    }
    if !finite_input(tri, &s) {
        return (Coverage::Outside, false);
    }
    (class_of_signs(exact_signs(tri, s)), true)
}

/// True when the fast path alone certifies the sample interior (false: outside, on the
/// boundary, too close to tell without the exact path, or non-finite input). A cheap
/// test for searches that only want certified interior points and can do without the
/// rest.
#[inline]
pub fn certainly_interior(tri: &Tri, s: [f64; 5]) -> bool {
    finite_input(tri, &s) && fast_path(tri, s) == Some(Coverage::Interior)
}

/// The class from the fast path alone (None: go exact). A value that overflows or is
/// NaN never decides (see [`Fe::sign`]).
#[inline]
fn fast_path(tri: &Tri, s: [f64; 5]) -> Option<Coverage> {
    let p = Fe::c;
    let ev = edge_values(tri, &p(s[0]), &p(s[1]), &p(s[2]), &p(s[3]), &p(s[4]));
    fast_class(&ev)
}

/// Classify one sample `[x, y, u, v, t]` exactly. Non-finite input is
/// [`Coverage::Outside`]; [`try_classify`] tells it apart.
#[inline]
pub fn classify(tri: &Tri, s: [f64; 5]) -> Coverage {
    classify_traced(tri, s).0
}

/// Classify one sample, or None when a number of the triangle or the sample is NaN or
/// infinite (input outside the model, which no verdict fits).
#[inline]
pub fn try_classify(tri: &Tri, s: [f64; 5]) -> Option<Coverage> {
    finite_input(tri, &s).then(|| classify(tri, s))
}

/// Classify many samples, counting exact fallbacks.
pub fn classify_all(tri: &Tri, samples: &[[f64; 5]], out: &mut Vec<Coverage>) -> CoverageStats {
    out.clear();
    out.reserve(samples.len());
    let mut st = CoverageStats::default();
    for &s in samples {
        let (c, ex) = classify_traced(tri, s);
        st.samples += 1;
        st.exact_fallbacks += ex as u64;
        out.push(c);
    }
    st
}

/// True when no interior sample, at any pixel, lens position and time in [0, 1], has a
/// hit depth below `z` (`lower`) or above it (not `lower`), by the vertices alone.
///
/// The adjugate identity of the coverage rule gives `D = sum_k E_k w_k(t)`, and `N =
/// sum_k E_k z_k(t)` by definition, so `N - z D = sum_k E_k (z_k(t) - z w_k(t))`. At an
/// interior sample every `E_k` has the strict sign of D, so `N / D - z = sum_k (E_k / D)
/// (z_k(t) - z w_k(t))` is a combination with positive weights: when every
/// `z_k(t) - z w_k(t)` is `>= 0` (`<= 0`) the depth is `>= z` (`<= z`). Neither the CoC
/// nor the pixel enter; each term is affine in t, so its signs at t = 0 and t = 1 decide
/// it over the shutter. Evaluated exactly (dyadic). False for a `z` that is not finite
/// (or input outside the model): nothing is claimed then.
pub fn depth_bound_holds(tri: &Tri, z: f64, lower: bool) -> bool {
    if !z.is_finite() || !finite_input(tri, &[0.0; 5]) {
        return false;
    }
    let c = Dyadic::from_f64;
    let zd = c(z);
    (0..3).all(|k| {
        [tri.q[k], tri.r[k]].iter().all(|p| {
            let s = (&c(p[2]) - &(&zd * &c(p[3]))).signum();
            if lower {
                s >= 0
            } else {
                s <= 0
            }
        })
    })
}

/// Where the hit depth `N / D` of an interior sample lies relative to `[z0, z1]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthCheck {
    /// The sample is not interior: it has no hit depth.
    NotInterior,
    Below,
    Inside,
    Above,
}

/// The class of a sample and, if interior, where its exact hit depth lies against
/// the closed interval `[z0, z1]`. Non-finite triangle or sample: NotInterior (as
/// [`classify`]). A bound that is not finite is taken as the comparison `z0 <= depth
/// <= z1` takes it: -inf below and +inf above every depth, and no depth is within a
/// NaN bound (NaN z0: Below; NaN z1: Above).
pub fn classify_depth(tri: &Tri, s: [f64; 5], z0: f64, z1: f64) -> DepthCheck {
    if classify(tri, s) != Coverage::Interior {
        return DepthCheck::NotInterior;
    }
    // The sign of depth - z0 (lower) or z1 - depth (upper) for a bound that is not finite.
    let limit = |z: f64, lower: bool| -> Option<i8> {
        if z.is_nan() {
            Some(-1)
        } else if z.is_infinite() {
            Some(if (z < 0.0) == lower { 1 } else { -1 })
        } else {
            None
        }
    };
    let (a_lim, b_lim) = (limit(z0, true), limit(z1, false));
    // depth >= z0  <=>  sign(D) * (N - z0 D) >= 0; likewise for z1.
    let p = Interval::point;
    let ev = edge_values(tri, &p(s[0]), &p(s[1]), &p(s[2]), &p(s[3]), &p(s[4]));
    let sd = ev.d.strict_sign();
    let fast = |x: Interval| -> Option<i8> { Some(sd? * x.strict_sign()?) };
    let fa = a_lim.or_else(|| fast(ev.nz - p(z0) * ev.d));
    let fb = b_lim.or_else(|| fast(p(z1) * ev.d - ev.nz));
    let (a, b) = match (fa, fb) {
        (Some(a), Some(b)) => (a, b),
        _ => {
            let c = Dyadic::from_f64;
            let ev = edge_values(tri, &c(s[0]), &c(s[1]), &c(s[2]), &c(s[3]), &c(s[4]));
            let sd = ev.d.signum();
            let a = a_lim.unwrap_or_else(|| (&ev.nz - &(&c(z0) * &ev.d)).signum() * sd);
            let b = b_lim.unwrap_or_else(|| (&(&c(z1) * &ev.d) - &ev.nz).signum() * sd);
            (a, b)
        }
    };
    if a < 0 {
        DepthCheck::Below
    } else if b < 0 {
        DepthCheck::Above
    } else {
        DepthCheck::Inside
    }
}

/// The hit depth of a sample as an enclosing interval (None if D's enclosure holds 0).
pub fn depth_enclosure(tri: &Tri, s: [f64; 5]) -> Option<Interval> {
    let p = Interval::point;
    let ev = edge_values(tri, &p(s[0]), &p(s[1]), &p(s[2]), &p(s[3]), &p(s[4]));
    interval_div(ev.nz, ev.d)
}

/// How far the hit depth of a sample lies from `z` (`|N / D - z|`), from the exact
/// values of `N` and `D` (the quotient itself rounded to f64); None when `D` is 0 or an
/// input is not finite. The size of a violation, not a decision: [`classify_depth`]
/// decides.
pub fn depth_distance(tri: &Tri, s: [f64; 5], z: f64) -> Option<f64> {
    if !z.is_finite() || s.iter().any(|v| !v.is_finite()) || tri.check_finite().is_err() {
        return None;
    }
    let c = Dyadic::from_f64;
    let ev = edge_values(tri, &c(s[0]), &c(s[1]), &c(s[2]), &c(s[3]), &c(s[4]));
    if ev.d.is_zero() {
        return None;
    }
    let q = (&ev.nz - &(&c(z) * &ev.d)).to_rational() / ev.d.to_rational();
    use num_traits::{Signed, ToPrimitive};
    q.abs().to_f64()
}

/// Outward-rounded `a / b`, None if b's enclosure touches 0.
pub fn interval_div(a: Interval, b: Interval) -> Option<Interval> {
    if !(b.lo > 0.0 || b.hi < 0.0) {
        return None;
    }
    let q = [a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi];
    if q.iter().any(|v| v.is_nan()) {
        return None;
    }
    let lo = q.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = q.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    Some(Interval::new(lo.next_down(), hi.next_up()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(v: [[f64; 2]; 3]) -> Tri {
        let mk = |p: [f64; 2]| [p[0], p[1], 0.5, 1.0];
        let q = [mk(v[0]), mk(v[1]), mk(v[2])];
        Tri { q, r: q, c0: [0.0; 3], c1: [0.0; 3], k: 1.0 }
    }

    #[test]
    fn static_triangle_interior_boundary_outside() {
        let t = flat([[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]]);
        assert_eq!(classify(&t, [1.0, 1.0, 0.0, 0.0, 0.5]), Coverage::Interior);
        assert_eq!(classify(&t, [2.0, 2.0, 0.0, 0.0, 0.5]), Coverage::Boundary);
        assert_eq!(classify(&t, [0.0, 0.0, 0.0, 0.0, 0.5]), Coverage::Boundary);
        assert_eq!(classify(&t, [3.0, 3.0, 0.0, 0.0, 0.5]), Coverage::Outside);
        // both windings
        let t2 = flat([[0.0, 0.0], [0.0, 4.0], [4.0, 0.0]]);
        assert_eq!(classify(&t2, [1.0, 1.0, 0.0, 0.0, 0.5]), Coverage::Interior);
    }

    #[test]
    fn boundary_needs_the_exact_path() {
        let t = flat([[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]]);
        let (c, exact) = classify_traced(&t, [0.125, 3.875, 0.0, 0.0, 0.3]);
        assert_eq!(c, Coverage::Boundary);
        assert!(exact);
        // 0.1 + 3.9 is not 4 for doubles: the exact oracle sees the true sum.
        assert_eq!(classify(&t, [0.1, 3.9, 0.0, 0.0, 0.3]), Coverage::Interior);
    }

    #[test]
    fn behind_the_lens_is_not_covered() {
        // All w < 0: the triangle is behind the lens; its projection would cover the
        // pixel, but the hit is at negative depth.
        let mk = |p: [f64; 2]| [-p[0], -p[1], -0.5, -1.0];
        let q = [mk([0.0, 0.0]), mk([4.0, 0.0]), mk([0.0, 4.0])];
        let t = Tri { q, r: q, c0: [0.0; 3], c1: [0.0; 3], k: 1.0 };
        assert_eq!(classify(&t, [1.0, 1.0, 0.0, 0.0, 0.0]), Coverage::Outside);
    }

    #[test]
    fn non_finite_input_is_outside_and_huge_input_is_exact() {
        let t = flat([[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]]);
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for i in 0..5 {
                let mut s = [1.0, 1.0, 0.0, 0.0, 0.5];
                s[i] = bad;
                assert_eq!(classify(&t, s), Coverage::Outside, "{s:?}");
                assert_eq!(try_classify(&t, s), None);
                assert_eq!(classify_depth(&t, s, 0.0, 1.0), DepthCheck::NotInterior);
                assert!(!certainly_interior(&t, s));
            }
            let mut u = t;
            u.q[1][0] = bad;
            assert_eq!(classify_traced(&u, [1.0, 1.0, 0.0, 0.0, 0.0]), (Coverage::Outside, false));
            assert_eq!(try_classify(&u, [1.0, 1.0, 0.0, 0.0, 0.0]), None);
        }
        // Finite but huge: the f64 enclosures overflow, the exact path decides.
        let big = flat([[0.0, 0.0], [1e300, 0.0], [0.0, 1e300]]);
        assert_eq!(classify_traced(&big, [1e299, 1e299, 0.0, 0.0, 0.5]), (Coverage::Interior, true));
        assert_eq!(classify(&big, [1e300, 1e300, 0.0, 0.0, 0.5]), Coverage::Outside);
        assert_eq!(try_classify(&big, [5e299, 5e299, 0.0, 0.0, 0.5]), Some(Coverage::Boundary));
        // Bounds that are not finite: the comparison's limits.
        let s = [1.0, 1.0, 0.0, 0.0, 0.0];
        assert_eq!(classify_depth(&t, s, f64::NEG_INFINITY, f64::INFINITY), DepthCheck::Inside);
        assert_eq!(classify_depth(&t, s, f64::INFINITY, f64::INFINITY), DepthCheck::Below);
        assert_eq!(classify_depth(&t, s, 0.0, f64::NEG_INFINITY), DepthCheck::Above);
        assert_eq!(classify_depth(&t, s, f64::NAN, 1.0), DepthCheck::Below);
        assert_eq!(classify_depth(&t, s, 0.0, f64::NAN), DepthCheck::Above);
    }

    #[test]
    fn depth_of_a_flat_triangle() {
        let t = flat([[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]]);
        // z/w = 0.5 everywhere
        assert_eq!(classify_depth(&t, [1.0, 1.0, 0.0, 0.0, 0.0], 0.5, 0.5), DepthCheck::Inside);
        assert_eq!(classify_depth(&t, [1.0, 1.0, 0.0, 0.0, 0.0], 0.6, 0.9), DepthCheck::Below);
        assert_eq!(classify_depth(&t, [1.0, 1.0, 0.0, 0.0, 0.0], 0.0, 0.4), DepthCheck::Above);
    }
}
