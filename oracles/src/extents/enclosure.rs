//! Box enclosures: the coverage values E_0, E_1, E_2, D (and the depth numerator) over
//! a box of samples, and the judgement empty / full / undecided they imply.

use super::cut::{cut_certified, Cut};
use super::depth::covered_depth;
use super::elimination::{no_covered_xy, Elimination};
use super::lanes::{lconst, LPoly};
use super::tpoly::TPoly;
use crate::coverage::interval_div;
use crate::interval::Interval;
use crate::ring::Ring;
use crate::tri::Tri;

/// Coordinates of a sample box, in the order x, y, u, v, t.
pub type Box5 = [Interval; 5];

/// The judgement of one box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BoxClass {
    Empty,
    Full,
    Undecided,
}

/// Enclosures of E_0, E_1, E_2, D and the depth numerator N over a box.
#[derive(Clone, Copy, Debug)]
pub struct BoxValues {
    pub e: [Interval; 3],
    pub d: Interval,
    pub nz: Interval,
    /// Enclosure of the hit depth N / D over the box, when D keeps one sign.
    pub depth: Option<Interval>,
    /// How much each coordinate (x, y, u, v, t) moves the values over the box: the
    /// largest change of an edge value or D between corners that differ in that
    /// coordinate only (t: the non-constant terms of the Taylor form). Guides splitting.
    /// Indexed `[quantity][coordinate]`, quantities E_0, E_1, E_2, D.
    pub smear: [[f64; 5]; 4],
    /// The same for the hit depth N / D (zero where D's sign is open).
    pub depth_smear: [f64; 5],
    /// Enclosure of the hit depth of every covered sample in the box, from the vertices
    /// alone (in front of the lens only; None otherwise or without depth): the hit
    /// depth is `sum b_k z_k / sum b_k w_k` with barycentrics `b_k > 0`, a weighted
    /// mean of the vertex depths `z_k / w_k` when every `w_k > 0`, so it lies between
    /// the least and the greatest of them at that time. Each `z_k(t) / w_k(t)` is
    /// linear-fractional in t (its derivative has the constant sign of
    /// `z'_k w_k - z_k w'_k`), so its extremes over the box's times are at the ends.
    /// Unlike [`BoxValues::depth`] it ignores the samples of the box that are not
    /// covered, so it bounds the depth objective where the box straddles an edge.
    pub vertex_depth: Option<Interval>,
    /// Every w_i > 0 over the box: for each (u, v, t) the covered (x, y) are the
    /// interior of the projected triangle.
    pub in_front: bool,
    /// In front, and for every (u, v, t) of the box all three projected vertices lie
    /// on the far side of one side of the box's (x, y) rectangle: nothing is covered.
    pub separated: bool,
    /// For every (u, v, t) of the box, the covered pixels (a convex polygon) miss the
    /// box's (x, y) rectangle, certified by a combination of the edge values (see
    /// the module `elimination`); only from [`box_values_eliminating`], else false.
    pub eliminated: bool,
    /// When the elimination ran and did not certify the box: how much u, v and t each
    /// move the combination it tried (zero otherwise). Guides splitting.
    pub elim_smear: [f64; 3],
    /// Bounds on the hit depth of every covered sample of the box certified by a
    /// combination of the depth with the edge values (see the module `depth`; the
    /// whole line where it certified nothing; only from [`box_values_eliminating`]
    /// with depth).
    pub covered_depth: Interval,
    /// How much u, v and t each move [`BoxValues::covered_depth`] over the box (zero
    /// where it is not known). Guides splitting.
    pub covered_smear: [f64; 3],
}

impl BoxValues {
    /// The smear of the quantities whose sign is still open over the box.
    pub fn open_smear(&self) -> [f64; 5] {
        let q = [self.e[0], self.e[1], self.e[2], self.d];
        let mut s = [0.0f64; 5];
        for (qk, smear) in q.iter().zip(&self.smear) {
            if !(qk.lo > 0.0 || qk.hi < 0.0) {
                for (si, m) in s.iter_mut().zip(smear) {
                    *si = si.max(*m);
                }
            }
        }
        s
    }
}

pub(super) fn ends(iv: Interval) -> ([f64; 2], usize) {
    if iv.lo == iv.hi {
        ([iv.lo, iv.lo], 1)
    } else {
        ([iv.lo, iv.hi], 2)
    }
}

/// `[f(0), f(1), f(2)]` for an expression in `i`, expanded in place (`array::map` and
/// closures move their large elements).
macro_rules! three {
    (|$i:ident| $e:expr) => {
        [
            {
                let $i = 0;
                $e
            },
            {
                let $i = 1;
                $e
            },
            {
                let $i = 2;
                $e
            },
        ]
    };
}

/// Enclosures of the coverage values over a box (corners in x, y, u, v; Taylor in t).
pub fn box_values(tri: &Tri, b: &Box5) -> BoxValues {
    box_values_with(tri, b, true)
}

/// [`box_values`], with the depth enclosures (`nz`, `depth`, `depth_smear`) only when
/// `with_depth`: without them `nz` is the whole line, `depth` None and `depth_smear`
/// zero, and the coverage values are the same. Searches for u, v, t and occupancy
/// never look at the depth, and it is a third of the work.
pub fn box_values_with(tri: &Tri, b: &Box5, with_depth: bool) -> BoxValues {
    values(tri, b, with_depth, false)
}

/// [`box_values_with`], and for a box that the enclosures leave undecided, the
/// elimination of (x, y) ([`BoxValues::eliminated`]): the same enclosures, one more way
/// to find a box empty. The extent searches use it; it costs about a third of a box
/// judgement where it runs.
pub fn box_values_eliminating(tri: &Tri, b: &Box5, with_depth: bool) -> BoxValues {
    values(tri, b, with_depth, true)
}

/// [`box_values_eliminating`] with depth for a search of one end of the depth (the
/// greatest when `max`): [`BoxValues::covered_depth`] is certified at that end only (the
/// other is infinite), and the corner quotient [`BoxValues::depth`] is left out (None,
/// with a zero `depth_smear`): that end's bound has it among its candidates.
pub(super) fn box_values_for_depth(tri: &Tri, b: &Box5, max: bool) -> BoxValues {
    values_ends(tri, b, true, true, [!max, max], &[], &mut [])
}

fn values(tri: &Tri, b: &Box5, with_depth: bool, eliminate: bool) -> BoxValues {
    values_ends(tri, b, with_depth, eliminate, [true, true], &[], &mut [])
}

/// [`box_values_eliminating`] (without depth), and for each of `cuts` whether it is
/// certified to cull no interior sample of the box (`ok[i]`, see [`Cut`]): all
/// true when the box holds no interior sample. `ok` has the length of `cuts`.
pub fn box_values_cutting(tri: &Tri, b: &Box5, cuts: &[Cut], ok: &mut [bool]) -> BoxValues {
    values_ends(tri, b, false, true, [true, true], cuts, ok)
}

/// The box values; `depth_ends` says which ends (lower, upper) of the covered depth to certify.
fn values_ends(
    tri: &Tri,
    b: &Box5,
    with_depth: bool,
    eliminate: bool,
    depth_ends: [bool; 2],
    cuts: &[Cut],
    cut_ok: &mut [bool],
) -> BoxValues {
    let tm = b[4].mid();
    let h = (b[4].hi - tm).max(tm - b[4].lo).max(0.0);
    let t = TPoly::t_at(tm);
    let (xs, nx) = ends(b[0]);
    let (ys, ny) = ends(b[1]);
    let (us, nu) = ends(b[2]);
    let (vs, nv) = ends(b[3]);
    // Per vertex, as polynomials in s: position, depth row, w, CoC at time t.
    // (`Ring::lerp`'s operations, with its `1 - t` formed once.)
    let one_minus_t = TPoly::c(1.0).sub(&t);
    let lerp2 = |a: f64, b: f64| one_minus_t.mul(&TPoly::c(a)).add(&t.mul(&TPoly::c(b)));
    let lerp = |i: usize, j: usize| lerp2(tri.q[i][j], tri.r[i][j]);
    let xb = three!(|i| lerp(i, 0));
    let yb = three!(|i| lerp(i, 1));
    let zb = three!(|i| lerp(i, 2));
    let wb = three!(|i| lerp(i, 3));
    let cb = three!(|i| lerp2(tri.c0[i], tri.c1[i]));
    // Corner n of the box is lane n = 8 iu + 4 iv + 2 ix + iy (a coordinate that is a
    // point repeats its value); D, which does not depend on (x, y), has lanes m = 2 iu + iv.
    let corner = |n: usize| (n >> 3 & 1, n >> 2 & 1, n >> 1 & 1, n & 1);
    let lane_u: [f64; 16] = std::array::from_fn(|n| us[corner(n).0]);
    let lane_v: [f64; 16] = std::array::from_fn(|n| vs[corner(n).1]);
    let lane_x: [f64; 16] = std::array::from_fn(|n| xs[corner(n).2]);
    let lane_y: [f64; 16] = std::array::from_fn(|n| ys[corner(n).3]);
    // Sheared coordinates: x' depends on u only, y' on v only.
    type Sheared<const N: usize> = ([LPoly<2, N>; 3], [LPoly<2, N>; 3]);
    #[inline(always)]
    fn sheared<const N: usize>(k: f64, vert: [&[TPoly; 3]; 3], u: &[f64; N], v: &[f64; N]) -> Sheared<N> {
        let [xb, yb, cb] = vert;
        let kv: LPoly<1, N> = LPoly::<1, N>::splat(&TPoly::c(k)).mul(&lconst(v));
        let xa = three!(|i| LPoly::splat(&xb[i]).add(&lconst(u).mul(&LPoly::<2, N>::splat(&cb[i]))));
        let ya = three!(|i| LPoly::splat(&yb[i]).add(&kv.mul(&LPoly::<2, N>::splat(&cb[i]))));
        (xa, ya)
    }
    let (xa, ya) = sheared(tri.k, [&xb, &yb, &cb], &lane_u, &lane_v);
    let wl: [LPoly<2, 16>; 3] = three!(|i| LPoly::splat(&wb[i]));
    // Translated coordinates: P.x depends on (x, u), P.y on (y, v).
    let px: [LPoly<2, 16>; 3] = three!(|i| xa[i].sub(&lconst(&lane_x).mul(&wl[i])));
    let py: [LPoly<2, 16>; 3] = three!(|i| ya[i].sub(&lconst(&lane_y).mul(&wl[i])));
    const EDGES: [(usize, usize); 3] = [(1, 2), (2, 0), (0, 1)];
    let ev: [LPoly<3, 16>; 3] = three!(|k| {
        let (i, j) = EDGES[k];
        px[i].mul::<2, 3>(&py[j]).sub(&py[i].mul(&px[j]))
    });
    // D = sum_i w_i E_i at x = y = 0 (the determinant of the sheared vertices), on the
    // lanes m = 2 iu + iv.
    let uv_u: [f64; 4] = std::array::from_fn(|m| us[m >> 1 & 1]);
    let uv_v: [f64; 4] = std::array::from_fn(|m| vs[m & 1]);
    let (xd, yd) = sheared(tri.k, [&xb, &yb, &cb], &uv_u, &uv_v);
    let mut dp = LPoly::<4, 4>::zero();
    for (k, &(i, j)) in EDGES.iter().enumerate() {
        let cross: LPoly<3, 4> = xd[i].mul(&yd[j]).sub(&yd[i].mul(&xd[j]));
        dp = dp.add(&LPoly::<2, 4>::splat(&wb[k]).mul(&cross));
    }
    let (d_lo, d_hi) = dp.range(h);
    let d_var = dp.variation(h);
    let mut smear = [[0.0f64; 5]; 4];
    let mut depth_smear = [0.0f64; 5];
    let hull_lanes = |lo: &[f64], hi: &[f64]| -> Interval {
        if lo.iter().chain(hi).any(|v| v.is_nan()) {
            return Interval::new(f64::NAN, f64::NAN);
        }
        Interval::new(
            lo.iter().cloned().fold(f64::INFINITY, f64::min),
            hi.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
        )
    };
    let d = hull_lanes(&d_lo, &d_hi);
    smear[3][4] = d_var.iter().fold(0.0, |a, &v| a.max(v));
    let dm: [f64; 4] = dp.0[0].v;
    if nu == 2 {
        smear[3][2] = (0..2).map(|iv| (dm[2 + iv] - dm[iv]).abs()).fold(0.0, f64::max);
    }
    if nv == 2 {
        smear[3][3] = (0..2).map(|iu| (dm[2 * iu + 1] - dm[2 * iu]).abs()).fold(0.0, f64::max);
    }
    // The largest change of lane values between corners that differ in one coordinate.
    let spread = |vals: &[f64; 16], open: [bool; 4]| -> [f64; 4] {
        let bits = [8usize, 4, 2, 1]; // u, v, x, y
        let mut out = [0.0f64; 4];
        for (q, &bit) in bits.iter().enumerate() {
            if open[q] {
                out[q] = (0..16).filter(|n| n & bit == 0).map(|n| (vals[n | bit] - vals[n]).abs()).fold(0.0, f64::max);
            }
        }
        out
    };
    let open = [nu == 2, nv == 2, nx == 2, ny == 2];
    let mut e = [Interval::point(0.0); 3];
    for k in 0..3 {
        let (lo, hi) = ev[k].range(h);
        e[k] = hull_lanes(&lo, &hi);
        smear[k][4] = ev[k].variation(h).iter().fold(0.0, |a, &v| a.max(v));
        let [su, sv, sx, sy] = spread(&ev[k].0[0].v, open);
        smear[k][0] = sx;
        smear[k][1] = sy;
        smear[k][2] = su;
        smear[k][3] = sv;
    }
    let mut nz: Option<Interval> = None;
    // N and D in the 16 lanes, kept for the depth certificate of the elimination.
    let mut depth_lanes: Option<(LPoly<4, 16>, LPoly<4, 16>)> = None;
    let mut depth: Option<Interval> = None;
    if with_depth {
        let nk = |k: usize| -> LPoly<4, 16> { ev[k].mul(&LPoly::<2, 16>::splat(&zb[k])) };
        let n = nk(0).add(&nk(1)).add(&nk(2));
        let (n_lo, n_hi) = n.range(h);
        nz = Some(hull_lanes(&n_lo, &n_hi));
        let mut dp16 = LPoly::<4, 16>::zero();
        for q in 0..4 {
            for c in 0..16 {
                let (iu, iv, _, _) = corner(c);
                dp16.0[q].v[c] = dp.0[q].v[2 * iu + iv];
                dp16.0[q].e[c] = dp.0[q].e[2 * iu + iv];
            }
        }
        // The corner quotient of the depth, unless only one end of the covered depth is
        // wanted (that end's bound over the covered polygon has it among its candidates).
        if depth_ends == [true, true] {
            // The depth N / D around a centre value z_c: N / D = z_c + M / D with
            // M = N - z_c D. M keeps the correlation of N and D in t, so the quotient of
            // enclosures stays tight where N and D move together.
            let dmid: [f64; 16] = std::array::from_fn(|c| {
                let (iu, iv, _, _) = corner(c);
                dm[2 * iu + iv]
            });
            let zc: [f64; 16] = std::array::from_fn(|c| n.0[0].v[c] / dmid[c]);
            let m = n.sub(&lconst(&zc).mul(&dp16));
            let (m_lo, m_hi) = m.range(h);
            let m_var = m.variation(h);
            let mut ok = true;
            let mut acc: Option<Interval> = None;
            for c in 0..16 {
                let (iu, iv, _, _) = corner(c);
                let dc = Interval::new(d_lo[2 * iu + iv], d_hi[2 * iu + iv]);
                // N / D is linear-fractional in each of x, y, u, v separately, hence
                // monotone in each while D keeps its sign: its extremes over the box are at
                // the corners too.
                let zq = if zc[c].is_finite() {
                    depth_smear[4] = depth_smear[4].max(m_var[c] / dmid[c].abs());
                    interval_div(Interval::new(m_lo[c], m_hi[c]), dc).map(|q| Interval::point(zc[c]) + q)
                } else {
                    None
                };
                match zq {
                    Some(z) if ok => {
                        acc = Some(match acc {
                            Some(a) if z.lo.is_nan() || z.hi.is_nan() || a.lo.is_nan() => {
                                Interval::new(f64::NAN, f64::NAN)
                            }
                            Some(a) => a.hull(z),
                            None => z,
                        })
                    }
                    _ => ok = false,
                }
            }
            if ok {
                depth = acc;
            }
            let [su, sv, sx, sy] = spread(&zc, open);
            depth_smear[0] = sx;
            depth_smear[1] = sy;
            depth_smear[2] = su;
            depth_smear[3] = sv;
        }
        if eliminate {
            depth_lanes = Some((n, dp16));
        }
    }
    // Separation by a side of the (x, y) rectangle: P_i.x at x = x_lo is
    // x'_i - x_lo w_i, negative iff vertex i projects left of x_lo (w_i > 0).
    let in_front = wb.iter().all(|w| w.range(h).lo > 0.0);
    let separated = in_front && {
        // Lanes with iv = iy = 0 hold P.x at each (x, u); with iu = ix = 0, P.y at (y, v).
        let side_x = |ix: usize, beyond_hi: bool| {
            (0..3).all(|i| {
                (0..nu).all(|iu| {
                    let r = px[i].lane(8 * iu + 2 * ix).range(h);
                    if beyond_hi {
                        r.lo >= 0.0
                    } else {
                        r.hi <= 0.0
                    }
                })
            })
        };
        let side_y = |iy: usize, beyond_hi: bool| {
            (0..3).all(|i| {
                (0..nv).all(|iv| {
                    let r = py[i].lane(4 * iv + iy).range(h);
                    if beyond_hi {
                        r.lo >= 0.0
                    } else {
                        r.hi <= 0.0
                    }
                })
            })
        };
        side_x(0, false) || side_x(nx - 1, true) || side_y(0, false) || side_y(ny - 1, true)
    };
    // The per-corner quotients bound the depth only if D has one sign over the box.
    let depth = if depth.is_some() && (d.lo > 0.0 || d.hi < 0.0) { depth } else { None };
    if depth.is_none() || depth_smear.iter().any(|v| !v.is_finite()) {
        depth_smear = [0.0; 5];
    }
    let nz = nz.unwrap_or(Interval::new(f64::NEG_INFINITY, f64::INFINITY));
    let vertex_depth = if with_depth && in_front { vertex_depths(tri, b[4]) } else { None };
    let mut bv = BoxValues {
        e,
        d,
        nz,
        depth,
        vertex_depth,
        smear,
        depth_smear,
        in_front,
        separated,
        eliminated: false,
        elim_smear: [0.0; 3],
        covered_depth: Interval::new(f64::NEG_INFINITY, f64::INFINITY),
        covered_smear: [0.0; 3],
    };
    if eliminate && classify_values(&bv) == BoxClass::Undecided {
        match no_covered_xy(&ev, h, d) {
            Elimination::Empty => bv.eliminated = true,
            Elimination::Open(s) => bv.elim_smear = s,
            Elimination::Unknown => {}
        }
    }
    let empty = classify_values(&bv) == BoxClass::Empty;
    for (cut, ok) in cuts.iter().zip(cut_ok.iter_mut()) {
        *ok = empty || cut_certified(tri, b[4], &ev, &[lane_x, lane_y, lane_u, lane_v], tm, h, d, &[px, py], cut);
    }
    if let Some((n, dl)) = depth_lanes.filter(|_| !bv.eliminated && (d.lo > 0.0 || d.hi < 0.0)) {
        let cd = covered_depth(&ev, &n, &dl, h, depth_ends);
        (bv.covered_depth, bv.covered_smear) = (cd.bounds, cd.smear);
    }
    bv
}

/// The hull of the vertex depths `z_k(t) / w_k(t)` over the times `t` (see
/// [`BoxValues::vertex_depth`]); None when some `w_k` may be <= 0 there or a quotient
/// cannot be enclosed.
pub(super) fn vertex_depths(tri: &Tri, t: Interval) -> Option<Interval> {
    let mut acc: Option<Interval> = None;
    for i in 0..3 {
        for te in [t.lo, t.hi] {
            let tt = Interval::point(te);
            let at = |j: usize| {
                (Interval::point(1.0) - tt) * Interval::point(tri.q[i][j]) + tt * Interval::point(tri.r[i][j])
            };
            let w = at(3);
            if w.lo.is_nan() || w.lo <= 0.0 {
                return None;
            }
            let q = interval_div(at(2), w)?;
            acc = Some(acc.map_or(q, |a| a.hull(q)));
        }
    }
    acc.filter(|a| a.lo.is_finite() && a.hi.is_finite())
}

/// Empty / full / undecided from the enclosures.
pub fn classify_values(bv: &BoxValues) -> BoxClass {
    let vals = [bv.e[0], bv.e[1], bv.e[2], bv.d];
    if bv.separated || bv.eliminated {
        return BoxClass::Empty;
    }
    if vals.iter().any(|v| v.lo.is_nan() || v.hi.is_nan()) {
        return BoxClass::Undecided;
    }
    if vals.iter().any(|v| v.lo >= 0.0 && v.hi <= 0.0) {
        return BoxClass::Empty;
    }
    let nonneg = vals.iter().any(|v| v.lo >= 0.0);
    let nonpos = vals.iter().any(|v| v.hi <= 0.0);
    if nonneg && nonpos {
        return BoxClass::Empty;
    }
    if vals.iter().all(|v| v.lo > 0.0) || vals.iter().all(|v| v.hi < 0.0) {
        return BoxClass::Full;
    }
    BoxClass::Undecided
}
