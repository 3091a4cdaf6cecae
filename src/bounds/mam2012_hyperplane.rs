//! `mam2012-hyperplane` and `mam2012-hyperplane-ps`: one xyuvt hyperplane per triangle
//! edge and tile.
//!
//! Source: J. Munkberg and T. Akenine-Möller, "Hyperplane Culling for Stochastic
//! Rasterization", Eurographics 2012 short paper: §2.2 (Eqs. 2, 3, the trivial reject,
//! the refined bounds, the tile-centre evaluation, selective enabling) and Appendix B
//! (Eqs. 4-9). Text: Munkberg and Akenine-Möller 2012, "Hyperplane Culling for Stochastic
//! Rasterization", §2.2 and Appendix B.
//!
//! # The edge function in the model's notation (Eqs. 2, 4-6)
//! With `p = (x, y, w)` of a vertex (z is not used) and the model's shear
//! `p'(u, v, t) = p(t) + c(t) (u, k v, 0)` (the paper's Appendix B uses the same shear),
//! the model's edge value of the edge (i, j) (k = the opposite vertex) is
//! `E_k = (p'_i x p'_j) . (x, y, 1)` (expand the model's `P_i.x P_j.y - P_i.y P_j.x` with
//! `P = p' - (x w, y w, 0)` to check), and
//!
//! `p'_i x p'_j = n(t) + m(t) x (u, k v, 0)`, `n = p_i x p_j = n0 + n1 t + n2 t^2`,
//! `m = c_j p_i - c_i p_j` (Eq. 5 with the paper's vertices 0, 1 = our i, j), so
//! `E_k = n(t) . X + (u, k v, 0) . (X x m(t))` with `X = (x, y, 1)` (Eq. 4).
//!
//! # Orientation (converting the paper's one-sided edge to the model's two-sided rule)
//! The paper's edge function is positive outside (it culls where its lower bound is
//! positive). The model calls a sample interior when every `E_k` has the strict sign of
//! `D = det(P'_0, P'_1, P'_2)`; D does not depend on (x, y) and is affine in (u, v) for
//! fixed t (the `u v det(C, C, W)` term vanishes), so its sign over the whole lens and
//! shutter is that of the four cubics `D(+-1, +-1, t)`. We write each in the Bernstein
//! basis on [0, 1] (the determinant is multilinear in three vertices linear in t: the
//! j-th coefficient is the mean of the determinants with j vertices taken at t = 1) and
//! prove a strict sign when all coefficients share it (with up to 4 de Casteljau halvings
//! where they do not). If D > 0 everywhere, interior means every `E_k > 0`, and we use
//! `e = -E_k` as the paper's e (positive outside); if D < 0 everywhere, `e = E_k`; i.e.
//! `e = sigma E_k` with `sigma = -sign(D)`, applied to n and m in the setup. If no sign
//! can be proven (the triangle may flip facing or degenerate during the shutter or over
//! the lens) the test is disabled: "D (the facing) may vanish or change sign". The paper
//! does not discuss this case.
//!
//! # The hyperplane (Eqs. 7-9), for a tile `[xc +- hx] x [yc +- hy]`, t in [0, 1]
//! **Eq. 7 (e_n).** `e_n = n0.X + t (n1.X) + t^2 (n2.X)`. With `A = n2.X`,
//! `A t^2 = A t - A t (1 - t) >= A t - max(A, 0) / 4` (tangent at t = 1/2 when A > 0, chord
//! when A < 0). The remaining `t (n1 + n2).X` is bilinear in (x, t): split
//! `(n1 + n2).X = (n1 + n2).Xc + delta` with `|delta| <= Z = |(n1+n2)_x| hx + |(n1+n2)_y| hy`
//! and use `t delta >= -Z t` (the McCormick bound for t in [0, 1]). So
//! `e_n >= n0.X + t ((n1 + n2).Xc - Z) - max(n2.Xc + |n2_x| hx + |n2_y| hy, 0) / 4`:
//! the x, y coefficients are those of `n0` (exact), the t coefficient is taken at the
//! tile centre and padded by the half-tile extents, and the constant is padded by the
//! t^2 term. The paper only says it follows \[MCH*11\] and pads "with half of a tile's
//! screen space extents"; this padding is our choice.
//!
//! **Eq. 8 (e_m).** `e_m = u d_x + k v d_y` with `d = X x m`: `d_x = y m_z - m_y`,
//! `d_y = m_x - x m_z`. Each component of `m(t)` (quadratic) is enclosed by the hull of
//! its three Bernstein coefficients on [0, 1] (the paper only says "bound each component
//! of m(t)"), stored as midpoint and radius. Per tile, midpoint-radius products give
//! `d_x in avg_x +- rad_x` with `avg_x = yc mzc - myc` and
//! `rad_x = |yc| mzr + hy (|mzc| + mzr) + myr` (likewise `d_y`), i.e. the paper's
//! "average and width ... as linear functions of the tile center ..., padded to take the
//! half-tile extents into account" (`|yc|` makes it piecewise linear). For |u|, |v| <= 1,
//! `e_m >= alpha u + beta v + xi` with `alpha = avg_x`, `beta = k avg_y`,
//! `xi = -(rad_x + k rad_y)` (Eq. 8; the paper's width |d| is twice our radius).
//!
//! **Eq. 9.** `e >= a . (1, x, y, u, v, t)` with
//! `a = (n0_z + xi - P, n0_x, n0_y, alpha, beta, (n1 + n2).Xc - Z)` and `P` the t^2
//! padding, valid for (x, y) in the tile, (u, v) in [-1, 1]^2, t in [0, 1].
//!
//! # The tests (§2.2)
//! An interior sample has `e < 0`, so `a . s < 0`. With the xy part evaluated once at
//! the tile centre and padded, `m_xy = a_1 + a_x xc + a_y yc - |a_x| hx - |a_y| hy` (the
//! paper pads a_const in the setup for its fixed tile size; our tiles vary, so we pad per
//! tile with the same value), the hypercube corner farthest along `-a` gives
//! `m = m_xy - |a_u| - |a_v| + min(a_t, 0)`: the tile is rejected when `m > 0` (the
//! paper's `a . c > 0`). Refined bounds: for coordinate k in {u, v, t} with
//! `R_k = m - min_k(a_k x_k)` (the minimum of the other terms), an interior sample has
//! `a_k x_k < -R_k`, so `x_k < -R_k / a_k` if `a_k > 0` and `x_k > -R_k / a_k` if
//! `a_k < 0` (no bound when `a_k = 0`). Each edge's bounds are computed from the full
//! hypercube and intersected; results are clamped to u, v in [-1, 1], t in [0, 1] and an
//! empty interval rejects the tile.
//!
//! `METHOD` (`mam2012-hyperplane`) is this per-tile test. `METHOD_PS`
//! (`mam2012-hyperplane-ps`) adds one per-sample constraint per edge,
//! `g(s) = -(a . (1, x, y, u, v, t))` with the unpadded `a_1` and the sample's own x, y
//! (the paper's parenthesised STE numbers of Table 1; "9 FMA" per sample).
//!
//! # Selective enabling
//! The paper enables the test per triangle by comparing the screen AABB at
//! (u, v, t) = (0, 0, 0) with the AABB of the blurred triangle, disabling it when the
//! former is "significantly smaller", without a threshold. [`Mam2012Hyperplane::selective`]
//! builds a variant that disables itself when `ratio * area(static) < area(blurred)`
//! (blurred AABB from each vertex at lens corners and t = 0, 1, valid when every w > 0;
//! a vertex at w <= 0 makes the blurred AABB unbounded, which disables the test too);
//! [`SELECTIVE_ENABLE_RATIO`] is our default ratio. Selective enabling is a performance
//! heuristic, not a bound: the registered `METHOD` and `METHOD_PS` are always enabled
//! (except for the orientation rule above), so that the bound itself is what is checked.
//!
//! # Degenerate input and f32 rounding
//! Everything is f32. An edge whose coefficients are not finite (overflow) is skipped
//! (no bound from it); a division `-R / a_k` that is not finite gives no bound. A
//! degenerate triangle (D identically 0) is disabled by the orientation rule.
//! The bound is conservative in real arithmetic. In f32 the cross products (which can
//! cancel heavily for large coordinates), the Bernstein coefficients of D (whose proven
//! sign can be wrong when |D| is within rounding of 0), the per-tile padding and the
//! final comparisons are rounded, so samples within rounding of an edge can be culled;
//! no epsilon hides this. `eval_box` encloses the f32 evaluation of the per-sample
//! constraint: the real value widened by `2^-20 sum_i |a_i s_i| + 2^-140` (a length-6
//! dot product evaluated in order errs by at most `gamma_6 < 2^-21` of the sum of
//! magnitudes, plus denormal absolute errors below `2^-146`).

use super::*;

/// Default ratio of the selective enabling rule: with selective enabling, the test is
/// disabled for a triangle whose blurred screen AABB has more than this times the area
/// of its AABB at (u, v, t) = (0, 0, 0). The paper gives no number; this is our choice.
pub const SELECTIVE_ENABLE_RATIO: f32 = 4.0;

/// The hyperplane test of §2.2 / Appendix B.
pub struct Mam2012Hyperplane {
    info: &'static MethodInfo,
    /// Add the per-edge per-sample constraints.
    pub per_sample: bool,
    /// `Some(r)`: selective enabling with ratio r (see [`SELECTIVE_ENABLE_RATIO`]).
    pub selective_enable_ratio: Option<f32>,
}

impl Mam2012Hyperplane {
    /// A variant with selective enabling (not registered; it reports the same id as
    /// the registered method of the same `per_sample`).
    pub fn selective(per_sample: bool, ratio: f32) -> Self {
        Mam2012Hyperplane {
            info: if per_sample { &INFO_PS } else { &INFO },
            per_sample,
            selective_enable_ratio: Some(ratio),
        }
    }
}

static INFO: MethodInfo = MethodInfo {
    id: "mam2012-hyperplane",
    source: "Munkberg & Akenine-Möller 2012, Hyperplane Culling for Stochastic Rasterization, §2.2 (Eqs. 2-3) and Appendix B (Eqs. 4-9); per-tile reject and refined u/v/t bounds",
    reconstruction: false,
    dims: &[Dims::Static, Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: true, time: true, depth: false, per_sample: false },
};
static INFO_PS: MethodInfo = MethodInfo {
    id: "mam2012-hyperplane-ps",
    source: "Munkberg & Akenine-Möller 2012, Hyperplane Culling for Stochastic Rasterization, §2.2 (Eqs. 2-3), Appendix B (Eqs. 4-9) and §3 Discussion (per-sample hyperplane test)",
    outputs: Outputs { tile_reject: true, lens: true, time: true, depth: false, per_sample: true },
    ..INFO
};

pub static METHOD: &dyn Method = &Mam2012Hyperplane { info: &INFO, per_sample: false, selective_enable_ratio: None };
pub static METHOD_PS: &dyn Method =
    &Mam2012Hyperplane { info: &INFO_PS, per_sample: true, selective_enable_ratio: None };

impl Method for Mam2012Hyperplane {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        let s = match self.selective_enable_ratio.and_then(|r| selective_disable(tri, r)) {
            Some(why) => Err(why),
            None => setup(tri),
        };
        Box::new(Prep { s, per_sample: self.per_sample })
    }
}

type V3 = [f32; 3];

fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
fn dot(a: V3, b: V3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(s: f32, a: V3) -> V3 {
    [s * a[0], s * a[1], s * a[2]]
}
fn det(a: V3, b: V3, c: V3) -> f32 {
    dot(a, cross(b, c))
}

/// The strict sign of a cubic on [0, 1] from its Bernstein coefficients, if provable
/// within `depth` halvings.
fn cubic_sign(b: [f32; 4], depth: u32) -> Option<f32> {
    if b.iter().all(|&x| x > 0.0) {
        return Some(1.0);
    }
    if b.iter().all(|&x| x < 0.0) {
        return Some(-1.0);
    }
    // A sign change or zero at an end, NaN, or no budget left: not provable.
    let same_sign_ends = b[0] * b[3] > 0.0; // false on NaN too
    if depth == 0 || !same_sign_ends {
        return None;
    }
    let m = |p: f32, q: f32| 0.5 * (p + q);
    let (p01, p12, p23) = (m(b[0], b[1]), m(b[1], b[2]), m(b[2], b[3]));
    let (p012, p123) = (m(p01, p12), m(p12, p23));
    let mid = m(p012, p123);
    let l = cubic_sign([b[0], p01, p012, mid], depth - 1)?;
    let r = cubic_sign([mid, p123, p23, b[3]], depth - 1)?;
    (l == r).then_some(l)
}

/// The sign of D over the whole lens and shutter, if provable.
fn facing(tri: &Triangle) -> Option<f32> {
    let mut sign = None;
    for (u, v) in [(-1.0f32, -1.0f32), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
        let sh = |p: [f32; 4], c: f32| -> V3 { [p[0] + u * c, p[1] + (tri.k * v) * c, p[3]] };
        let a = [0, 1, 2].map(|i| sh(tri.q[i], tri.c0[i]));
        let b = [0, 1, 2].map(|i| sh(tri.r[i], tri.c1[i]));
        let third = 1.0 / 3.0;
        let bern = [
            det(a[0], a[1], a[2]),
            (det(b[0], a[1], a[2]) + det(a[0], b[1], a[2]) + det(a[0], a[1], b[2])) * third,
            (det(a[0], b[1], b[2]) + det(b[0], a[1], b[2]) + det(b[0], b[1], a[2])) * third,
            det(b[0], b[1], b[2]),
        ];
        let s = cubic_sign(bern, 4)?;
        if sign.is_some_and(|p| p != s) {
            return None;
        }
        sign = Some(s);
    }
    sign
}

/// Per-edge setup state (already multiplied by sigma = -sign(D)).
#[derive(Clone, Copy, Debug)]
struct Edge {
    n0: V3,
    n12: V3,
    n2: V3,
    /// Midpoint and radius of each component of m(t) over [0, 1].
    mc: V3,
    mr: V3,
}

#[derive(Clone, Copy, Debug)]
struct Setup {
    edges: [Edge; 3],
    k: f32,
}

struct Prep {
    s: Result<Setup, &'static str>,
    per_sample: bool,
}

fn setup(tri: &Triangle) -> Result<Setup, &'static str> {
    let Some(d_sign) = facing(tri) else {
        return Err("D (the facing) may vanish or change sign over the lens and shutter");
    };
    let sigma = -d_sign;
    let p3 = |p: [f32; 4]| -> V3 { [p[0], p[1], p[3]] };
    let edge = |i: usize, j: usize| -> Edge {
        let (qi, qj) = (p3(tri.q[i]), p3(tri.q[j]));
        let (ri, rj) = (p3(tri.r[i]), p3(tri.r[j]));
        let (di, dj) = ([ri[0] - qi[0], ri[1] - qi[1], ri[2] - qi[2]], [rj[0] - qj[0], rj[1] - qj[1], rj[2] - qj[2]]);
        let n0 = cross(qi, qj);
        let n1 = add(cross(qi, dj), cross(di, qj));
        let n2 = cross(di, dj);
        // m(t) = c_j(t) p_i(t) - c_i(t) p_j(t): Bernstein coefficients of each component.
        let (ci0, ci1, cj0, cj1) = (tri.c0[i], tri.c1[i], tri.c0[j], tri.c1[j]);
        let mut mc = [0.0; 3];
        let mut mr = [0.0; 3];
        for a in 0..3 {
            let b0 = cj0 * qi[a] - ci0 * qj[a];
            let b1 = 0.5 * ((cj0 * ri[a] + cj1 * qi[a]) - (ci0 * rj[a] + ci1 * qj[a]));
            let b2 = cj1 * ri[a] - ci1 * rj[a];
            let (lo, hi) = (b0.min(b1).min(b2), b0.max(b1).max(b2));
            // sigma = -1 negates m: the midpoint flips, the radius stays.
            mc[a] = sigma * (0.5 * (lo + hi));
            mr[a] = 0.5 * (hi - lo);
            if b0.is_nan() || b1.is_nan() || b2.is_nan() {
                mc[a] = f32::NAN;
            }
        }
        Edge { n0: scale(sigma, n0), n12: scale(sigma, add(n1, n2)), n2: scale(sigma, n2), mc, mr }
    };
    Ok(Setup { edges: [edge(1, 2), edge(2, 0), edge(0, 1)], k: tri.k })
}

/// Screen AABB area at (u, v, t) = (0, 0, 0) and of the blurred triangle, or None when
/// some w <= 0 (the blurred AABB is unbounded).
fn aabb_areas(tri: &Triangle) -> Option<(f32, f32)> {
    if (0..3).any(|j| !(tri.q[j][3] > 0.0 && tri.r[j][3] > 0.0)) {
        return None;
    }
    let area = |pts: &[(f32, f32)]| -> f32 {
        let (mut x0, mut x1, mut y0, mut y1) = (f32::INFINITY, f32::NEG_INFINITY, f32::INFINITY, f32::NEG_INFINITY);
        for &(x, y) in pts {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        (x1 - x0) * (y1 - y0)
    };
    let st: Vec<(f32, f32)> = (0..3).map(|j| (tri.q[j][0] / tri.q[j][3], tri.q[j][1] / tri.q[j][3])).collect();
    let mut bl = Vec::new();
    for j in 0..3 {
        for (p, c) in [(tri.q[j], tri.c0[j]), (tri.r[j], tri.c1[j])] {
            for s in [-1.0f32, 1.0] {
                bl.push(((p[0] + s * c) / p[3], (p[1] + s * (tri.k * c)) / p[3]));
            }
        }
    }
    Some((area(&st), area(&bl)))
}

/// The reason selective enabling turns the test off, if it does.
fn selective_disable(tri: &Triangle, ratio: f32) -> Option<&'static str> {
    match aabb_areas(tri) {
        None => Some("selective enabling: a vertex has w <= 0, the blurred AABB is unbounded"),
        Some((st, bl)) if ratio * st < bl || bl.is_nan() || st.is_nan() => {
            Some("selective enabling: the AABB at (u, v, t) = (0, 0, 0) is much smaller than the blurred AABB")
        }
        _ => None,
    }
}

/// The hyperplane `a = (a_1, a_x, a_y, a_u, a_v, a_t)` of one edge for one tile.
fn plane(e: &Edge, k: f32, xc: f32, yc: f32, hx: f32, hy: f32) -> Option<[f32; 6]> {
    let xc3 = [xc, yc, 1.0];
    // Eq. 7.
    let z = e.n12[0].abs() * hx + e.n12[1].abs() * hy;
    let a_t = dot(e.n12, xc3) - z;
    let a2 = dot(e.n2, xc3) + (e.n2[0].abs() * hx + e.n2[1].abs() * hy);
    let p = 0.25 * a2.max(0.0);
    // Eq. 8.
    let pad_z = e.mc[2].abs() + e.mr[2];
    let avg_x = yc * e.mc[2] - e.mc[1];
    let rad_x = yc.abs() * e.mr[2] + hy * pad_z + e.mr[1];
    let avg_y = e.mc[0] - xc * e.mc[2];
    let rad_y = e.mr[0] + xc.abs() * e.mr[2] + hx * pad_z;
    let xi = -(rad_x + k * rad_y);
    let a = [e.n0[2] + xi - p, e.n0[0], e.n0[1], avg_x, k * avg_y, a_t];
    a.iter().all(|v| v.is_finite()).then_some(a)
}

/// One per-sample hyperplane: culled when `a . (1, x, y, u, v, t) > 0`.
#[derive(Debug, Clone, Copy)]
struct Plane {
    edge: usize,
    a: [f32; 6],
}

impl SampleConstraint for Plane {
    fn name(&self) -> String {
        format!("edge {} hyperplane", self.edge)
    }
    fn eval(&self, s: &Sample) -> f32 {
        let a = &self.a;
        let mut acc = a[0];
        acc += a[1] * s.x;
        acc += a[2] * s.y;
        acc += a[3] * s.u;
        acc += a[4] * s.v;
        acc += a[5] * s.t;
        -acc
    }
    fn eval_box(&self, b: &SampleBox) -> Interval {
        let p = |i: usize| Interval::point(self.a[i] as f64);
        let terms = [p(0), p(1) * b.x, p(2) * b.y, p(3) * b.u, p(4) * b.v, p(5) * b.t];
        let mut sum = Interval::point(0.0);
        let mut mag = Interval::point(0.0);
        for t in terms {
            sum = sum + t;
            mag = mag + Interval::point(t.lo.abs().max(t.hi.abs()));
        }
        let err = (Interval::point(mag.hi) * Interval::point(2f64.powi(-20)) + Interval::point(2f64.powi(-140))).hi;
        -(sum + Interval::new(-err, err))
    }
}

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let s = match &self.s {
            Ok(s) => s,
            Err(_) => return TileResult::Bounds(TileBounds::full()),
        };
        let (xc, yc) = tile.center();
        let (hx, hy) = (0.5 * (tile.x1 - tile.x0), 0.5 * (tile.y1 - tile.y0));
        let mut out = TileBounds::full();
        for (ei, e) in s.edges.iter().enumerate() {
            let Some(a) = plane(e, s.k, xc, yc, hx, hy) else {
                continue;
            };
            // The xy part once at the tile centre, padded by the half extents.
            let m_xy = a[0] + a[1] * xc + a[2] * yc - (a[1].abs() * hx + a[2].abs() * hy);
            let (mu, mv, mt) = (-a[3].abs(), -a[4].abs(), a[5].min(0.0));
            let m = m_xy + mu + mv + mt;
            if m > 0.0 {
                return TileResult::Empty;
            }
            for (ak, rest, range) in [
                (a[3], m_xy + mv + mt, &mut out.u),
                (a[4], m_xy + mu + mt, &mut out.v),
                (a[5], m_xy + mu + mv, &mut out.t),
            ] {
                let bound = -rest / ak;
                if !bound.is_finite() {
                    continue;
                }
                if ak > 0.0 {
                    range[1] = range[1].min(bound);
                } else if ak < 0.0 {
                    range[0] = range[0].max(bound);
                }
            }
            if self.per_sample {
                out.constraints.push(Box::new(Plane { edge: ei, a }));
            }
        }
        let clamp = |r: [f32; 2], lo: f32, hi: f32| [r[0].max(lo), r[1].min(hi)];
        out.u = clamp(out.u, -1.0, 1.0);
        out.v = clamp(out.v, -1.0, 1.0);
        out.t = clamp(out.t, 0.0, 1.0);
        if !(out.u[0] <= out.u[1] && out.v[0] <= out.v[1] && out.t[0] <= out.t[1]) {
            return TileResult::Empty;
        }
        TileResult::Bounds(out)
    }
    fn disabled(&self) -> Option<&'static str> {
        self.s.as_ref().err().copied()
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::{assert_keeps_covered, near_miss_check, random_sample, spot_check};
    use super::*;
    use crate::model::ThinLens;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn cam() -> ThinLens {
        ThinLens { fx: 100.0, fy: 100.0, cx: 0.0, cy: 0.0, radius: 0.5, focus: 4.0, near: 0.1, far: 100.0 }
    }

    fn cases() -> Vec<(Triangle, Vec<Tile>)> {
        let c = cam();
        let mut v = Vec::new();
        // Small defocused triangle moving across the screen (Figure 1).
        let q = [[-2.0, -0.05, 8.0], [-1.9, -0.05, 8.0], [-1.95, 0.05, 8.0]];
        v.push((
            c.triangle(q, q.map(|p| [p[0] + 4.0, p[1], p[2]])),
            vec![Tile::square(-0.5, -0.5, 1.0), Tile::square(-3.0, -2.0, 4.0)],
        ));
        // Large moving triangle across the focal plane (c changes sign: fine here).
        v.push((
            c.triangle(
                [[-1.0, -1.0, 3.0], [1.0, -0.8, 5.0], [0.0, 1.0, 3.2]],
                [[-0.6, -0.7, 2.5], [0.9, -0.5, 6.0], [0.3, 0.8, 4.5]],
            ),
            vec![
                Tile::square(0.0, 0.0, 2.0),
                Tile::square(-30.0, -30.0, 8.0),
                Tile::square(20.0, 10.0, 4.0),
                Tile::square(-4.0, 20.0, 4.0),
            ],
        ));
        // Large perspective motion behind the focal plane.
        v.push((
            c.triangle(
                [[-1.0, -1.0, 20.0], [2.0, -1.0, 20.0], [0.0, 2.0, 20.0]],
                [[-1.0, -1.0, 4.5], [2.0, -1.0, 4.5], [0.0, 2.0, 4.5]],
            ),
            vec![Tile::square(0.0, 0.0, 2.0), Tile::square(-24.0, -24.0, 4.0), Tile::square(40.0, -20.0, 4.0)],
        ));
        // Per-vertex CoC, aspect 0.75, clockwise on screen.
        let mut t = Triangle::fixed([[-10.0, -5.0, 0.0, 2.0], [0.0, 14.0, 0.0, 3.0], [12.0, -4.0, 0.0, 2.5]]);
        t.r = [[-4.0, -2.0, 0.0, 1.0], [6.0, 12.0, 0.0, 2.0], [14.0, 0.0, 0.0, 3.0]];
        t.c0 = [3.0, 5.0, -1.0];
        t.c1 = [0.5, 2.0, 6.0];
        t.k = 0.75;
        v.push((
            t,
            vec![
                Tile::square(0.0, 0.0, 1.0),
                Tile::square(-12.0, -6.0, 4.0),
                Tile::square(4.0, 6.0, 2.0),
                Tile::square(1.0, -3.0, 1.0),
            ],
        ));
        v
    }

    #[test]
    fn conservative_on_random_samples() {
        for m in [METHOD, METHOD_PS] {
            for (ci, (tri, tiles)) in cases().into_iter().enumerate() {
                let p = m.setup(&tri);
                assert_eq!(p.disabled(), None, "case {ci}");
                let mut total = 0;
                for (ti, tile) in tiles.iter().enumerate() {
                    let (cov, bad) = spot_check(p.as_ref(), &tri, tile, 60_000, 2000 + 10 * ci as u64 + ti as u64);
                    assert!(
                        bad.is_empty(),
                        "{} case {ci} tile {ti}: {} covered samples culled, first {:?}",
                        m.info().id,
                        bad.len(),
                        bad[0]
                    );
                    total += cov;
                    let (_, bad) = near_miss_check(p.as_ref(), &tri, tile, 3000, 5000 + ti as u64);
                    assert!(bad.is_empty(), "case {ci} tile {ti}: covered sample culled near a bound {:?}", bad[0]);
                }
                assert!(total > 100, "case {ci}: only {total} covered samples");
                eprintln!("{} case {ci}: {total} covered", m.info().id);
            }
        }
    }

    /// Many random physical triangles (both facings, any depth, some behind the lens)
    /// and tiles near them.
    #[test]
    fn conservative_on_random_triangles() {
        let mut rng = ChaCha8Rng::seed_from_u64(99);
        let c = cam();
        let (mut near_total, mut enabled, mut cov_total, mut culled_tiles) = (0, 0, 0, 0);
        for it in 0..300 {
            let z0: f32 = rng.gen_range(0.5..30.0);
            let z1: f32 = if it % 3 == 0 { z0 } else { rng.gen_range(0.5..30.0) };
            let mut v = || -> [f32; 3] {
                [rng.gen_range(-0.3..0.3f32), rng.gen_range(-0.3..0.3f32), rng.gen_range(-0.2..0.2f32)]
            };
            let (a, b, d) = (v(), v(), v());
            let mv = [v(), v(), v()];
            let q = [a, b, d].map(|p| [p[0] * z0, p[1] * z0, z0 + p[2] * z0]);
            let r = [0, 1, 2].map(|i| {
                [(([a, b, d][i][0] + mv[i][0]) * z1), ([a, b, d][i][1] + mv[i][1]) * z1, z1 + [a, b, d][i][2] * z1]
            });
            let tri = c.triangle(q, r);
            let p = METHOD_PS.setup(&tri);
            if p.disabled().is_some() {
                continue;
            }
            enabled += 1;
            for _ in 0..3 {
                let size = [1.0f32, 2.0, 4.0][rng.gen_range(0..3)];
                let tile = Tile::square(rng.gen_range(-40.0..40.0), rng.gen_range(-40.0..40.0), size);
                if matches!(p.tile(&tile), TileResult::Empty) {
                    culled_tiles += 1;
                }
                let (cov, tried) =
                    assert_keeps_covered(p.as_ref(), &tri, &tile, (2000, 300), it * 7 + 1, &format!("triangle {it}"));
                cov_total += cov;
                near_total += tried;
            }
        }
        eprintln!("near-miss probes {near_total}, enabled {enabled}, covered {cov_total}, culled tiles {culled_tiles}");
        assert!(enabled > 150 && cov_total > 5000 && culled_tiles > 50);
    }

    #[test]
    fn static_triangle_keeps_time_and_far_tile_is_culled() {
        for m in [METHOD, METHOD_PS] {
            for tri in [
                Triangle::fixed([[-20.0, -20.0, 0.0, 1.0], [20.0, -20.0, 0.0, 1.0], [0.0, 20.0, 0.0, 1.0]]),
                Triangle::fixed([[-20.0, -20.0, 0.0, 1.0], [0.0, 20.0, 0.0, 1.0], [20.0, -20.0, 0.0, 1.0]]),
            ] {
                let p = m.setup(&tri);
                assert_eq!(p.disabled(), None);
                let TileResult::Bounds(b) = p.tile(&Tile::square(-1.0, -1.0, 2.0)) else { panic!("empty") };
                assert_eq!((b.u, b.v, b.t), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]));
                let mut rng = ChaCha8Rng::seed_from_u64(5);
                for _ in 0..1000 {
                    assert!(b.admits(&random_sample(&mut rng, &Tile::square(-1.0, -1.0, 2.0))));
                }
                assert!(matches!(p.tile(&Tile::square(100.0, 0.0, 2.0)), TileResult::Empty));
                assert!(matches!(p.tile(&Tile::square(0.0, 21.0, 1.0)), TileResult::Empty));
            }
        }
    }

    /// A triangle sliding right: a tile it enters late gets a refined t lower bound.
    #[test]
    fn refined_time_bounds() {
        let mut tri = Triangle::fixed([[-40.0, -10.0, 0.0, 1.0], [-20.0, -10.0, 0.0, 1.0], [-30.0, 10.0, 0.0, 1.0]]);
        tri.r = tri.q.map(|p| [p[0] + 60.0, p[1], p[2], p[3]]);
        let p = METHOD.setup(&tri);
        let TileResult::Bounds(b) = p.tile(&Tile::square(5.0, 0.0, 2.0)) else { panic!("empty") };
        // For y in [0, 2] the right edge is at x = -25 - y/2 + 60 t: it reaches x = 5 at
        // t = 0.5; the left edge (x = -35 + y/2 + 60 t) leaves x = 7 at t = 0.7. Pure
        // screen motion (w fixed) makes n2 = 0 and the hyperplane exact.
        assert!(b.t[0] > 0.49 && b.t[0] <= 0.5, "{:?}", b.t);
        assert!(b.t[1] >= 0.7 && b.t[1] < 0.71, "{:?}", b.t);
    }

    #[test]
    fn facing_flip_is_disabled() {
        // Vertex 2 crosses the opposite edge during the shutter.
        let mut tri = Triangle::fixed([[-10.0, -10.0, 0.0, 1.0], [10.0, -10.0, 0.0, 1.0], [0.0, 10.0, 0.0, 1.0]]);
        tri.r[2] = [0.0, -30.0, 0.0, 1.0];
        let p = METHOD.setup(&tri);
        assert!(p.disabled().unwrap().contains("facing"));
        let TileResult::Bounds(b) = p.tile(&Tile::square(500.0, 0.0, 1.0)) else { panic!("empty") };
        assert_eq!((b.u, b.v, b.t), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]));
        // Degenerate (zero area): disabled, no panic.
        let tri = Triangle::fixed([[0.0, 0.0, 0.0, 1.0]; 3]);
        assert!(METHOD_PS.setup(&tri).disabled().is_some());
    }

    #[test]
    fn selective_enabling() {
        let c = cam();
        // A 2-unit triangle at the focal plane neighbourhood: little blur, enabled.
        let big = [[-1.0, -1.0, 4.2], [1.0, -1.0, 4.2], [0.0, 1.0, 4.2]];
        let m = Mam2012Hyperplane::selective(false, SELECTIVE_ENABLE_RATIO);
        assert_eq!(m.setup(&c.triangle(big, big)).disabled(), None);
        // A small, very defocused triangle: disabled.
        let small = [[-0.05, -0.05, 20.0], [0.05, -0.05, 20.0], [0.0, 0.05, 20.0]];
        assert!(m.setup(&c.triangle(small, small)).disabled().unwrap().contains("selective"));
        // The registered method never uses it.
        assert_eq!(METHOD.setup(&c.triangle(small, small)).disabled(), None);
        assert_eq!(m.info().id, "mam2012-hyperplane");
    }

    #[test]
    fn per_sample_planes_cull_more() {
        // Figure 1 triangle: the per-sample planes admit fewer samples than the tile test.
        let c = cam();
        let q = [[-2.0, -0.05, 8.0], [-1.9, -0.05, 8.0], [-1.95, 0.05, 8.0]];
        let tri = c.triangle(q, q.map(|p| [p[0] + 4.0, p[1], p[2]]));
        let tile = Tile::square(-0.5, -0.5, 1.0);
        let TileResult::Bounds(a) = METHOD.setup(&tri).tile(&tile) else { panic!("empty") };
        let TileResult::Bounds(b) = METHOD_PS.setup(&tri).tile(&tile) else { panic!("empty") };
        assert_eq!(b.constraints.len(), 3);
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let (mut na, mut nb) = (0, 0);
        for _ in 0..20_000 {
            let s = random_sample(&mut rng, &tile);
            na += a.admits(&s) as usize;
            nb += b.admits(&s) as usize;
        }
        assert!(nb < na, "{nb} vs {na}");
    }

    #[test]
    fn eval_box_encloses_eval() {
        let tri = cases()[3].0;
        let tile = Tile::square(0.0, 0.0, 1.0);
        let TileResult::Bounds(b) = METHOD_PS.setup(&tri).tile(&tile) else { panic!("empty") };
        assert_eq!(b.constraints.len(), 3);
        super::super::testkit::assert_eval_box_encloses(&b, &tile, 3);
    }

    #[test]
    fn degenerate_input_is_answered_in_the_domain() {
        let mut tri = Triangle::fixed([[3e38, -3e38, 0.0, 1e-30], [1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, -1.0]]);
        tri.c0 = [3e38, 0.0, -1e-45];
        let tiles = [Tile::square(-1e30, 0.0, 1e30), Tile::square(0.0, 0.0, 1.0)];
        for m in [METHOD, METHOD_PS] {
            super::super::testkit::assert_answered_in_domain(m.setup(&tri).as_ref(), &tiles);
        }
        let selective = Mam2012Hyperplane::selective(true, 4.0).setup(&tri);
        super::super::testkit::assert_answered_in_domain(selective.as_ref(), &tiles);
    }

    #[test]
    fn degenerate_and_huge_input_is_answered_in_the_domain() {
        super::super::testkit::assert_degenerate_input_is_answered(METHOD, &super::super::la2011::figure1::triangle());
        super::super::testkit::assert_degenerate_input_is_answered(
            METHOD_PS,
            &super::super::la2011::figure1::triangle(),
        );
    }
}
