//! Eliminating (x, y): for a fixed lens position and time the covered pixels of a box's
//! (x, y) rectangle form a convex polygon, decided without splitting x or y.
//!
//! For fixed (u, v, t) each edge value `E_k` is affine in (x, y) (the `x y` terms of
//! `P_i.x P_j.y - P_i.y P_j.x` cancel) and `D` does not depend on (x, y), so the
//! interior samples at that (u, v, t) are the pixels where the three affine functions
//! `sigma E_k` are all positive (`sigma` the sign of `D`): an intersection of three open
//! half-planes, bounded or not, whatever the signs of the `w_i`. It misses the
//! rectangle exactly when some non-negative combination of the three (Farkas, and Helly
//! in the plane: at most three of the seven half-planes are needed) is `<= 0` on the
//! whole rectangle.
//!
//! [`no_covered_xy`] certifies that for a whole box of (u, v, t): it picks the
//! multipliers `lambda` from the mid values (a tiny linear programme over the simplex,
//! solved by enumerating its vertices) and then checks `G = sum lambda_k sigma E_k <= 0`
//! over the box with the same outward-rounded corner enclosures as the edge values
//! themselves. `G` is affine in each of x, y, u, v separately (as every `E_k` is), so its
//! extremes over the box are at the 16 corners, and in t it is bounded term by term
//! ([`super::tpoly::TPoly::range`]). A covered sample of the box would make every
//! `sigma E_k > 0` and so `G > 0`: the check rules every one out. The multipliers are
//! a heuristic (any non-negative, not all zero, are sound); only the check certifies.
//!
//! [`clipped_point`] proposes a witness at one (u, v, t): the centroid of the
//! rectangle clipped by the three half-planes (plain f64: the exact classifier judges
//! it).

use super::enclosure::Box5;
use super::lanes::{lconst, LPoly};
use crate::interval::Interval;
use crate::tri::Tri;

/// What the elimination learnt about a box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Elimination {
    /// No sample of the box is interior (certified).
    Empty,
    /// Not certified; for the combination that came closest, how much u, v and t each
    /// move it over the box (the largest change between corners that differ in that
    /// coordinate only; t: its non-constant terms): where to split next.
    Open([f64; 3]),
    /// No combination was tried (D unknown, or none is negative at the middle).
    Unknown,
}

/// Certify that no sample of the box is interior, by one combination of the edge
/// values per sign of `D` that `d` (D's enclosure over the box) leaves possible.
/// `ev` are the edge values in the lanes of [`super::box_values_with`] (lane
/// `8 iu + 4 iv + 2 ix + iy`), `h` the half-width of the box's times.
pub(super) fn no_covered_xy(ev: &[LPoly<3, 16>; 3], h: f64, d: Interval) -> Elimination {
    if d.lo.is_nan() || d.hi.is_nan() {
        return Elimination::Unknown;
    }
    // D > 0 needs every E_k > 0; D < 0 every E_k < 0.
    let signs: &[f64] = match (d.lo > 0.0, d.hi < 0.0) {
        (true, _) => &[1.0],
        (_, true) => &[-1.0],
        _ => &[1.0, -1.0],
    };
    let mut out = Elimination::Empty;
    for &sg in signs {
        match (certified(ev, h, sg), out) {
            (Elimination::Empty, _) => {}
            (Elimination::Open(a), Elimination::Open(b)) => {
                out = Elimination::Open(std::array::from_fn(|i| a[i].max(b[i])))
            }
            (Elimination::Open(a), Elimination::Empty) => out = Elimination::Open(a),
            _ => return Elimination::Unknown,
        }
    }
    out
}

/// One sign: multipliers from the mid values, then the rigorous check.
fn certified(ev: &[LPoly<3, 16>; 3], h: f64, sg: f64) -> Elimination {
    let mid: [[f64; 16]; 3] = std::array::from_fn(|k| ev[k].0[0].v.map(|v| sg * v));
    let Some(lam) = multipliers(&mid) else { return Elimination::Unknown };
    let mut g = LPoly::<3, 16>::zero();
    for (k, &l) in lam.iter().enumerate() {
        if l != 0.0 {
            g = g.add(&lconst(&[sg * l; 16]).mul::<3, 3>(&ev[k]));
        }
    }
    let (_, hi) = g.range(h);
    if hi.iter().all(|&v| v <= 0.0) {
        return Elimination::Empty;
    }
    let gm = &g.0[0].v;
    let spread = |bit: usize| (0..16).filter(|n| n & bit == 0).map(|n| (gm[n | bit] - gm[n]).abs()).fold(0.0, f64::max);
    let t = g.variation(h).iter().fold(0.0f64, |a, &v| a.max(v));
    Elimination::Open([spread(8), spread(4), t])
}

/// Non-negative multipliers (summing to 1) that make `sum_k lam_k a_k` as negative as
/// possible at the rectangle's four corners at the box's middle (u, v) (the mean of
/// the four lens corners: exact for a function affine in u and in v), scored by the
/// largest value over all 16 corner lanes. None when no candidate is negative there.
/// The candidates are the vertices of that small linear programme: one function alone,
/// two where two corners tie, three where three corners tie.
pub(super) fn multipliers<const F: usize>(a: &[[f64; 16]; F]) -> Option<[f64; F]> {
    // Values at the (x, y) corners c = 2 ix + iy, at the middle of the lens box.
    let m: [[f64; 4]; F] =
        std::array::from_fn(|k| std::array::from_fn(|c| 0.25 * (a[k][c] + a[k][4 + c] + a[k][8 + c] + a[k][12 + c])));
    let score = |l: &[f64; F]| -> f64 {
        (0..16).map(|n| (0..F).map(|k| l[k] * a[k][n]).sum::<f64>()).fold(f64::NEG_INFINITY, f64::max)
    };
    // The largest value at the middle (u, v): a lower bound of the score (each middle
    // value is the mean of four lanes), which rules most candidates out cheaply.
    let mid_score = |l: &[f64; F]| -> f64 {
        (0..4).map(|c| (0..F).map(|k| l[k] * m[k][c]).sum::<f64>()).fold(f64::NEG_INFINITY, f64::max)
    };
    let mut best: Option<([f64; F], f64)> = None;
    let mut consider = |l: [f64; F]| {
        if l.iter().any(|v| !(v.is_finite() && *v >= 0.0)) {
            return;
        }
        let ms = mid_score(&l);
        if ms >= 0.0 || best.is_some_and(|(_, b)| ms >= b) {
            return;
        }
        let s = score(&l);
        if s < 0.0 && best.is_none_or(|(_, b)| s < b) {
            best = Some((l, s));
        }
    };
    for k in 0..F {
        let mut l = [0.0; F];
        l[k] = 1.0;
        consider(l);
    }
    for k in 0..F {
        for j in k + 1..F {
            for c in 0..4 {
                for c2 in c + 1..4 {
                    let (dk, dj) = (m[k][c] - m[k][c2], m[j][c] - m[j][c2]);
                    let den = dk - dj;
                    if den != 0.0 {
                        let s = dk / den;
                        if s > 0.0 && s < 1.0 {
                            let mut l = [0.0; F];
                            (l[k], l[j]) = (1.0 - s, s);
                            consider(l);
                        }
                    }
                }
            }
        }
    }
    for k in 0..F {
        for j in k + 1..F {
            for i in j + 1..F {
                let f = [k, j, i];
                for skip in 0..4 {
                    let cs = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]][skip];
                    let p: [f64; 3] = std::array::from_fn(|q| m[f[q]][cs[0]] - m[f[q]][cs[1]]);
                    let r: [f64; 3] = std::array::from_fn(|q| m[f[q]][cs[0]] - m[f[q]][cs[2]]);
                    let n = [p[1] * r[2] - p[2] * r[1], p[2] * r[0] - p[0] * r[2], p[0] * r[1] - p[1] * r[0]];
                    let sum = n[0] + n[1] + n[2];
                    if sum != 0.0 {
                        let mut l = [0.0; F];
                        for q in 0..3 {
                            l[f[q]] = n[q] / sum;
                        }
                        consider(l);
                    }
                }
            }
        }
    }
    best.map(|(l, _)| l)
}

/// Witness proposals for an extreme of the hit depth at (u, v, t) = `s[2..5]`: the
/// vertex of the covered polygon (within the box's rectangle) of least depth (greatest
/// when `max`; the depth is affine in (x, y) there, so its extremes over the polygon
/// are at vertices) moved a little towards the polygon's centroid, by a few fractions
/// (the extreme is on the boundary, which is not covered). Plain f64: the exact
/// classifier judges them.
pub(super) fn depth_extreme_points(tri: &Tri, s: [f64; 5], b: &Box5, max: bool) -> Vec<[f64; 5]> {
    let Some((poly, lines, d, zs)) = clipped_polygon(tri, s, b) else { return Vec::new() };
    let depth =
        |p: &(f64, f64)| (0..3).map(|k| zs[k] * (lines[k][2] + lines[k][0] * p.0 + lines[k][1] * p.1)).sum::<f64>() / d;
    let key = |p: &(f64, f64)| if max { -depth(p) } else { depth(p) };
    let Some(ext) = poly.iter().min_by(|p, q| key(p).total_cmp(&key(q))) else { return Vec::new() };
    let Some((cx, cy)) = poly.centroid() else { return Vec::new() };
    [1e-9, 1e-6, 1e-3]
        .iter()
        .map(|f| {
            let mut p = s;
            p[0] = (ext.0 + f * (cx - ext.0)).clamp(b[0].lo, b[0].hi);
            p[1] = (ext.1 + f * (cy - ext.1)).clamp(b[1].lo, b[1].hi);
            p
        })
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .collect()
}

/// The centroid of the box's (x, y) rectangle clipped by the half-planes where every
/// `sigma E_k > 0` at (u, v, t) = `s[2..5]` (any signs of the `w_i`), clamped into the
/// rectangle; None when the clipped polygon is empty or D is 0 there. Plain f64: it only
/// proposes a point.
pub fn clipped_point(tri: &Tri, s: [f64; 5], b: &Box5) -> Option<(f64, f64)> {
    let (poly, ..) = clipped_polygon(tri, s, b)?;
    let (cx, cy) = poly.centroid()?;
    Some((cx.clamp(b[0].lo, b[0].hi), cy.clamp(b[1].lo, b[1].hi)))
}

/// A covered polygon, its edge lines `E_k = C_k + A_k x + B_k y` as `[A, B, C]`, D and
/// the vertex depth rows `z_k`.
type Clipped = (Polygon, [[f64; 3]; 3], f64, [f64; 3]);

/// A convex polygon of at most 8 vertices, kept on the stack: a rectangle clipped by
/// three half-planes (or a triangle by four) has at most 7.
#[derive(Clone, Copy, Debug)]
pub(super) struct Polygon {
    pts: [(f64, f64); 8],
    len: usize,
}

impl Polygon {
    pub(super) fn new() -> Self {
        Polygon { pts: [(0.0, 0.0); 8], len: 0 }
    }
    /// Append a vertex (beyond 8 the polygon is not convex: a bug; ignored).
    pub(super) fn push(&mut self, p: (f64, f64)) {
        if self.len < 8 {
            self.pts[self.len] = p;
            self.len += 1;
        }
    }
    pub(super) fn len(&self) -> usize {
        self.len
    }
    pub(super) fn is_empty(&self) -> bool {
        self.len == 0
    }
    pub(super) fn iter(&self) -> impl Iterator<Item = &(f64, f64)> {
        self.pts[..self.len].iter()
    }
    /// The vertex `k` (modulo the length).
    pub(super) fn at(&self, k: usize) -> (f64, f64) {
        self.pts[k % self.len]
    }
    /// The mean of the vertices, None when empty or not finite.
    pub(super) fn centroid(&self) -> Option<(f64, f64)> {
        let n = self.len as f64;
        let (sx, sy) = self.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
        let c = (sx / n, sy / n);
        (c.0.is_finite() && c.1.is_finite()).then_some(c)
    }
}

/// The hit depth at the sample `s` in plain f64 (None when D is 0 there): an estimate,
/// for choosing among witness proposals only.
pub(super) fn depth_estimate(tri: &Tri, s: [f64; 5]) -> Option<f64> {
    let (lines, d, zs) = edge_lines(tri, s)?;
    let z = (0..3).map(|k| zs[k] * (lines[k][2] + lines[k][0] * s[0] + lines[k][1] * s[1])).sum::<f64>() / d;
    z.is_finite().then_some(z)
}

/// The edge lines `E_k = C_k + A_k x + B_k y` as `[A, B, C]` at (u, v, t) = `s[2..5]`,
/// D and the vertex depth rows `z_k` (plain f64); None when D is 0 or not finite.
fn edge_lines(tri: &Tri, s: [f64; 5]) -> Option<([[f64; 3]; 3], f64, [f64; 3])> {
    let (u, v, t) = (s[2], s[3], s[4]);
    let mut xs = [0.0; 3];
    let mut ys = [0.0; 3];
    let mut ws = [0.0; 3];
    let mut zs = [0.0; 3];
    for i in 0..3 {
        let at = |j: usize| (1.0 - t) * tri.q[i][j] + t * tri.r[i][j];
        let c = (1.0 - t) * tri.c0[i] + t * tri.c1[i];
        xs[i] = at(0) + u * c;
        ys[i] = at(1) + tri.k * v * c;
        zs[i] = at(2);
        ws[i] = at(3);
    }
    // E_k = C_k + A_k x + B_k y for (k, i, j) = (0, 1, 2), (1, 2, 0), (2, 0, 1).
    let lines: [[f64; 3]; 3] = std::array::from_fn(|k| {
        let (i, j) = [(1, 2), (2, 0), (0, 1)][k];
        [ys[i] * ws[j] - ws[i] * ys[j], ws[i] * xs[j] - xs[i] * ws[j], xs[i] * ys[j] - ys[i] * xs[j]]
    });
    let d: f64 = (0..3).map(|k| ws[k] * lines[k][2]).sum();
    (d.is_finite() && d != 0.0).then_some((lines, d, zs))
}

/// The box's rectangle clipped by the half-planes `sigma E_k > 0` at (u, v, t) =
/// `s[2..5]` (plain f64); None when empty or D is 0 there.
fn clipped_polygon(tri: &Tri, s: [f64; 5], b: &Box5) -> Option<Clipped> {
    let (lines, d, zs) = edge_lines(tri, s)?;
    let sg = d.signum();
    let mut poly = Polygon::new();
    for p in [(b[0].lo, b[1].lo), (b[0].hi, b[1].lo), (b[0].hi, b[1].hi), (b[0].lo, b[1].hi)] {
        poly.push(p);
    }
    for l in &lines {
        let f = |p: &(f64, f64)| sg * (l[0] * p.0 + l[1] * p.1 + l[2]);
        let mut out = Polygon::new();
        for k in 0..poly.len() {
            let (p, q) = (poly.at(k), poly.at(k + 1));
            let (fp, fq) = (f(&p), f(&q));
            if fp > 0.0 {
                out.push(p);
            }
            if (fp > 0.0) != (fq > 0.0) && fp != fq {
                let r = fp / (fp - fq);
                out.push((p.0 + r * (q.0 - p.0), p.1 + r * (q.1 - p.1)));
            }
        }
        poly = out;
        if poly.is_empty() {
            return None;
        }
    }
    Some((poly, lines, d, zs))
}

/// Witness proposals at the corners of the box's (u, v, t) (each with the point of
/// [`clipped_point`] there). Near an extreme the covered set of a box is often a thin
/// wedge: behind the lens its apex, in front of it the place where a vertex or edge
/// enters the tile at the end of a lens or time range. The box's centre keeps missing
/// it while a corner on the wedge's open side lies in it.
pub(super) fn corner_points(tri: &Tri, b: &Box5) -> Vec<[f64; 5]> {
    let mut pts = Vec::with_capacity(8);
    for n in 0..8 {
        let mut p = b.map(|i| i.mid());
        for (bit, k) in [(4, 2), (2, 3), (1, 4)] {
            p[k] = if n & bit == 0 { b[k].lo } else { b[k].hi };
        }
        if let Some((x, y)) = clipped_point(tri, p, b) {
            (p[0], p[1]) = (x, y);
            pts.push(p);
        }
    }
    pts
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::{classify, Coverage};
    use crate::extents::enclosure::{box_values_eliminating, box_values_with, classify_values, BoxClass};
    use crate::extents::testgen::{random_tri, unit_stream};

    /// A box around `s`: (x, y) a rectangle of 1/64 to 4 pixels (as a tile), (u, v, t)
    /// each of a random width from 1 down to 2^-20 of its range.
    fn box_around(s: [f64; 5], next: &mut impl FnMut() -> f64) -> Box5 {
        let scale = [4.0, 4.0, 2.0, 2.0, 1.0];
        std::array::from_fn(|k| {
            let f = scale[k] * 0.5f64.powi((next() * if k < 2 { 8.0 } else { 20.0 }) as i32);
            Interval::new(s[k] - f * next(), s[k] + f * next())
        })
    }

    /// The certificate never rules out a box that holds an interior sample: boxes of
    /// every size drawn around interior samples (w of every sign, crossing 0 too) are
    /// never eliminated, while undecided boxes where random points find no covered
    /// sample are eliminated at a fair rate (the test would notice an elimination that
    /// never fires).
    #[test]
    fn elimination_keeps_every_box_with_a_covered_sample() {
        let mut next = unit_stream(0x2545_F491_4F6C_DD1D);
        let (mut kept, mut crossing, mut eliminated, mut undecided) = (0, 0, 0, 0);
        for _ in 0..400 {
            let tri = random_tri(&mut next);
            for _ in 0..40 {
                let s = [next() * 8.0 - 4.0, next() * 8.0 - 4.0, next() * 2.0 - 1.0, next() * 2.0 - 1.0, next()];
                let b = box_around(s, &mut next);
                let bv = box_values_eliminating(&tri, &b, false);
                if classify(&tri, s) == Coverage::Interior {
                    assert!(!bv.eliminated, "box {b:?} eliminated but {s:?} is interior in {tri:?}");
                    assert_ne!(classify_values(&bv), BoxClass::Empty, "{b:?} {s:?} {tri:?}");
                    kept += 1;
                    let w = |t: f64| (0..3).map(move |i| (1.0 - t) * tri.q[i][3] + t * tri.r[i][3]);
                    crossing += w(b[4].lo).zip(w(b[4].hi)).any(|(a, c)| a * c <= 0.0) as usize;
                } else if classify_values(&box_values_with(&tri, &b, false)) == BoxClass::Undecided {
                    let hit = (0..200).any(|_| {
                        let p: [f64; 5] = std::array::from_fn(|k| b[k].lo + next() * b[k].width());
                        classify(&tri, p) == Coverage::Interior
                    });
                    if !hit {
                        undecided += 1;
                        eliminated += bv.eliminated as usize;
                    }
                }
            }
        }
        assert!(kept > 1000 && crossing > 50, "{kept} covered boxes, {crossing} with w crossing 0");
        // (boxes wide in (u, v, t) need splitting before one combination serves them)
        assert!(eliminated * 20 > undecided, "eliminated {eliminated} of {undecided} undecided boxes");
    }

    /// The depth bounds the elimination certifies hold the exact hit depth of every
    /// covered sample of the box: boxes of every size around interior samples (w of
    /// every sign, crossing 0 too), and the bounds are finite on a fair share of them.
    #[test]
    fn covered_depth_holds_the_depth_of_covered_samples() {
        let mut next = unit_stream(0x6A09_E667_F3BC_C908);
        let (mut checked, mut bounded) = (0, 0);
        for _ in 0..600 {
            let tri = random_tri(&mut next);
            for _ in 0..40 {
                let s = [next() * 8.0 - 4.0, next() * 8.0 - 4.0, next() * 2.0 - 1.0, next() * 2.0 - 1.0, next()];
                if classify(&tri, s) != Coverage::Interior {
                    continue;
                }
                let b = box_around(s, &mut next);
                let cd = box_values_eliminating(&tri, &b, true).covered_depth;
                let z = crate::coverage::depth_enclosure(&tri, s).expect("interior: D != 0");
                assert!(cd.lo <= z.lo && z.hi <= cd.hi, "depth {z:?} outside {cd:?} at {s:?} in {b:?} of {tri:?}");
                checked += 1;
                bounded += (cd.lo.is_finite() || cd.hi.is_finite()) as usize;
            }
        }
        assert!(checked > 1000 && bounded * 10 > checked, "{bounded} of {checked} boxes bounded");
    }

    /// An eliminated box holds no interior sample: random points of every eliminated box
    /// are judged exactly.
    #[test]
    fn eliminated_boxes_hold_no_covered_sample() {
        let mut next = unit_stream(0x9E37_79B9_7F4A_7C15);
        let mut checked = 0;
        for _ in 0..1200 {
            let tri = random_tri(&mut next);
            for _ in 0..30 {
                let s = [next() * 8.0 - 4.0, next() * 8.0 - 4.0, next() * 2.0 - 1.0, next() * 2.0 - 1.0, next()];
                let b = box_around(s, &mut next);
                if !box_values_eliminating(&tri, &b, false).eliminated {
                    continue;
                }
                for _ in 0..50 {
                    let p: [f64; 5] = std::array::from_fn(|k| b[k].lo + next() * b[k].width());
                    assert_ne!(classify(&tri, p), Coverage::Interior, "{p:?} in eliminated {b:?} of {tri:?}");
                    checked += 1;
                }
            }
        }
        assert!(checked > 4000, "only {checked} points checked");
    }

    /// The clipped point is a covered sample whenever the rectangle holds one at that
    /// (u, v, t) (up to f64 rounding at slivers), and None when it holds none.
    #[test]
    fn clipped_points_are_covered() {
        let mut next = unit_stream(0xD1B5_4A32_D192_ED03);
        let (mut found, mut interior, mut missed) = (0, 0, 0);
        for _ in 0..3000 {
            let tri = random_tri(&mut next);
            let s = [0.0, 0.0, next() * 2.0 - 1.0, next() * 2.0 - 1.0, next()];
            let (x0, y0) = (next() * 8.0 - 4.0, next() * 8.0 - 4.0);
            let b: Box5 = [
                Interval::new(x0, x0 + 2.0),
                Interval::new(y0, y0 + 2.0),
                Interval::point(s[2]),
                Interval::point(s[3]),
                Interval::point(s[4]),
            ];
            let any = (0..64).any(|_| {
                let p = [x0 + 2.0 * next(), y0 + 2.0 * next(), s[2], s[3], s[4]];
                classify(&tri, p) == Coverage::Interior
            });
            match clipped_point(&tri, s, &b) {
                Some((x, y)) => {
                    found += 1;
                    assert!(b[0].contains(x) && b[1].contains(y));
                    interior += (classify(&tri, [x, y, s[2], s[3], s[4]]) == Coverage::Interior) as usize;
                }
                None => missed += any as usize,
            }
        }
        assert!(found > 300, "{found} rectangles with a covered part");
        assert!(interior * 100 >= found * 99, "{interior} of {found} clipped points interior");
        assert_eq!(missed, 0, "{missed} rectangles with covered samples and no clipped point");
    }
}
