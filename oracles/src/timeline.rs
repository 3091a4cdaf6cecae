//! Per-ray exact time intervals.
//!
//! For a fixed ray `(x, y, u, v)` each edge value `E_k(t)` is a quadratic in t and `D(t)`
//! a cubic (each sheared, translated coordinate is linear in t). Their coefficients
//! are computed exactly (dyadic), the distinct real roots of each in [0, 1] are
//! isolated with a Sturm sequence over the rationals and bisected at dyadic points to
//! a requested width, so every root lies in a certified enclosure `[lo, hi]`. Between
//! two consecutive enclosures no polynomial changes sign, so one exact classification
//! at any point of the gap is the class of the whole gap. The covered set is the union
//! of the interior gaps (the idea of analytic motion blur, Gribel et al. 2010).

use crate::coverage::{class_of_signs, edge_values, Coverage};
use crate::dyadic::Dyadic;
use crate::poly::{sign_changes, DyPoly, RatPoly};
use crate::ring::Ring;
use crate::tri::Tri;
use num_rational::BigRational;

/// A certified enclosure `[lo, hi]` of one boundary time (lo == hi when exact).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Enclosure {
    pub lo: f64,
    pub hi: f64,
}

/// One maximal open time interval of interior coverage: every t strictly between
/// `start.hi` and `end.lo` is interior-covered, and the true endpoints lie in the
/// enclosures. At the shutter ends the enclosure is the exact point 0 or 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoveredSpan {
    pub start: Enclosure,
    pub end: Enclosure,
}

/// The four coverage polynomials of one ray, exact.
pub fn ray_polys(tri: &Tri, x: f64, y: f64, u: f64, v: f64) -> [DyPoly; 4] {
    let c = DyPoly::c;
    let ev = edge_values(tri, &c(x), &c(y), &c(u), &c(v), &DyPoly::t());
    let [e0, e1, e2] = ev.e;
    [e0, e1, e2, ev.d]
}

fn rat(x: f64) -> BigRational {
    Dyadic::from_f64(x).to_rational()
}

/// Enclosures of the distinct roots of `p` in [0, 1], each of width <= `width`
/// (or an exact dyadic point), sorted.
pub fn roots_in_unit(p: &RatPoly, width: f64) -> Vec<Enclosure> {
    if p.is_zero() || p.degree() == 0 {
        return Vec::new();
    }
    let sf = p.square_free();
    let seq = sf.sturm();
    let mut out = Vec::new();
    let (a, b) = (0.0f64, 1.0f64);
    for end in [a, b] {
        if sf.sign_at(&rat(end)) == 0 {
            out.push(Enclosure { lo: end, hi: end });
        }
    }
    // roots in the open interval (0, 1): V(0) - V(1) counts (0, 1]; drop a root at 1.
    let v = |t: f64| sign_changes(&seq, &rat(t));
    let root_at_1 = sf.sign_at(&rat(1.0)) == 0;
    let n = v(0.0) - v(1.0) - root_at_1 as usize;
    let mut stack = vec![(a, b, n)];
    while let Some((lo, hi, n)) = stack.pop() {
        if n == 0 {
            continue;
        }
        let mid = lo + 0.5 * (hi - lo);
        // An interval no f64 can split is kept as it is, even when it holds several
        // roots (distinct roots closer than one f64 step): splitting it again would
        // never end.
        if (n == 1 && hi - lo <= width) || mid <= lo || mid >= hi {
            out.push(Enclosure { lo, hi });
            continue;
        }
        let m = rat(mid);
        let at_mid = sf.sign_at(&m) == 0;
        if at_mid {
            out.push(Enclosure { lo: mid, hi: mid });
        }
        let left = v(lo) - v(mid) - at_mid as usize;
        let right = n - left - at_mid as usize;
        stack.push((lo, mid, left));
        stack.push((mid, hi, right));
    }
    out.sort_by(|p, q| p.lo.partial_cmp(&q.lo).unwrap());
    out
}

/// The exact class of the ray at time t.
pub fn class_at(polys: &[DyPoly; 4], t: f64) -> Coverage {
    let s =
        [polys[0].eval(t).signum(), polys[1].eval(t).signum(), polys[2].eval(t).signum(), polys[3].eval(t).signum()];
    class_of_signs(s)
}

/// The interior-covered time set of the ray `(x, y, u, v)` within [0, 1], as spans with
/// certified endpoint enclosures of width <= `width` (e.g. 1e-12).
pub fn covered_spans(tri: &Tri, x: f64, y: f64, u: f64, v: f64, width: f64) -> Vec<CoveredSpan> {
    let polys = ray_polys(tri, x, y, u, v);
    let mut roots: Vec<Enclosure> = Vec::new();
    for p in &polys {
        roots.extend(roots_in_unit(&p.to_rational(), width));
    }
    roots.sort_by(|p, q| p.lo.partial_cmp(&q.lo).unwrap());
    // Merge overlapping enclosures into clusters; the shutter ends are cut points too.
    let mut cuts: Vec<Enclosure> = vec![Enclosure { lo: 0.0, hi: 0.0 }];
    for r in roots {
        let last = cuts.last_mut().unwrap();
        if r.lo <= last.hi {
            last.hi = last.hi.max(r.hi);
        } else {
            cuts.push(r);
        }
    }
    if cuts.last().unwrap().hi < 1.0 {
        cuts.push(Enclosure { lo: 1.0, hi: 1.0 });
    } else {
        cuts.last_mut().unwrap().hi = 1.0;
    }
    let mut spans = Vec::new();
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let mid = a.hi + 0.5 * (b.lo - a.hi);
        if !(mid > a.hi && mid < b.lo) {
            continue; // no double strictly between: the gap is too thin to hold a span
        }
        if class_at(&polys, mid) == Coverage::Interior {
            spans.push(CoveredSpan { start: a, end: b });
        }
    }
    spans
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadratic_roots_are_enclosed() {
        // (t - 1/4)(t - 1/3) = t^2 - 7/12 t + 1/12
        let p = RatPoly(vec![rat(1.0) / rat(12.0), -rat(7.0) / rat(12.0), rat(1.0)]);
        let r = roots_in_unit(&p, 1e-12);
        assert_eq!(r.len(), 2);
        assert!(r[0].lo <= 0.25 && 0.25 <= r[0].hi);
        assert!(r[1].lo <= 1.0 / 3.0 && 1.0 / 3.0 <= r[1].hi + 1e-16);
        assert!(r[1].hi - r[1].lo <= 1e-12);
    }

    #[test]
    fn double_root_counts_once() {
        // (t - 1/2)^2
        let p = RatPoly(vec![rat(0.25), rat(-1.0), rat(1.0)]);
        let r = roots_in_unit(&p, 1e-9);
        assert_eq!(r, vec![Enclosure { lo: 0.5, hi: 0.5 }]);
    }

    #[test]
    fn moving_triangle_span() {
        // A triangle translating in x by 8 pixels over the shutter; the pixel x = 5
        // is inside when 0 < 5 - 8t < 2 roughly (for y small), i.e. t in (3/8, 5/8).
        let mk = |x: f64, y: f64| [x, y, 0.5, 1.0];
        let q = [mk(0.0, 0.0), mk(4.0, 0.0), mk(0.0, 4.0)];
        let r = [mk(8.0, 0.0), mk(12.0, 0.0), mk(8.0, 4.0)];
        let tri = Tri { q, r, c0: [0.0; 3], c1: [0.0; 3], k: 1.0 };
        // pixel (5, 2): inside when 0 < 5 - 8t and (5 - 8t) + 2 < 4 -> t in (3/8, 5/8)
        let s = covered_spans(&tri, 5.0, 2.0, 0.0, 0.0, 1e-12);
        assert_eq!(s.len(), 1);
        assert!(s[0].start.lo <= 0.375 && 0.375 <= s[0].start.hi);
        assert!(s[0].end.lo <= 0.625 && 0.625 <= s[0].end.hi);
    }
}
