//! `mam2012-hyperplane-safe` and `mam2012-hyperplane-ps-safe`: the hyperplanes of the
//! published method from an outward-rounded f32 setup (`Iv`, `dop_exact`), with the
//! reject, the refined bounds and the per-tile grid rounded outward. The derivation and
//! the error analysis are in the parent's module doc (its `-safe` section).

use super::*;
use std::ops::{Add, Mul, Neg, Sub};

static INFO_SAFE: MethodInfo = MethodInfo {
    id: "mam2012-hyperplane-safe",
    source: "Munkberg & Akenine-Möller 2012, Hyperplane Culling for Stochastic Rasterization, §2.2 (Eqs. 2-3) and Appendix B (Eqs. 4-9); per-tile reject and refined u/v/t bounds. The same planes from an outward-rounded f32 setup, with the reject and the bounds rounded outward (error analysis in this file)",
    ..INFO
};
static INFO_PS_SAFE: MethodInfo = MethodInfo {
    id: "mam2012-hyperplane-ps-safe",
    source: "Munkberg & Akenine-Möller 2012, Hyperplane Culling for Stochastic Rasterization, §2.2 (Eqs. 2-3), Appendix B (Eqs. 4-9) and §3 Discussion (per-sample hyperplane test). The same planes from an outward-rounded f32 setup, with the reject, the bounds and the per-sample test rounded outward (error analysis in this file)",
    ..INFO_PS
};

/// `mam2012-hyperplane-safe`: the per-tile test, rounded outward (see the module doc).
pub static METHOD_SAFE: &dyn Method =
    &Mam2012Hyperplane { info: &INFO_SAFE, per_sample: false, selective_enable_ratio: None, safe: true };
/// `mam2012-hyperplane-ps-safe`: with the per-sample planes, rounded outward.
pub static METHOD_PS_SAFE: &dyn Method =
    &Mam2012Hyperplane { info: &INFO_PS_SAFE, per_sample: true, selective_enable_ratio: None, safe: true };

/// [`facing`] for `-safe`, from the exact inputs without rounding the shear: D is linear
/// in each column of its matrix with rows `(x + u c, y + k v c, w)`, so
/// `D(u, v, t) = det[x | y | w] + u det[c | y | w] + k v det[x | c | w]` (the u v term
/// `det[c | c | w]` vanishes), and the columns x, y are first moved to the origin `o`
/// (`x - o_x w`, `y - o_y w`: column operations, D unchanged), which keeps the
/// determinants' terms at the triangle's own size far from the screen origin. Each of the
/// three cubics gets its Bernstein coefficients as in [`facing`] (rows linear in t), in
/// intervals; the corner `(u, v)`'s coefficients are their combination.
fn facing_safe(tri: &Triangle, o: [f32; 2]) -> Option<f32> {
    let row = |p: [f32; 4], c: f32| -> [Iv; 4] {
        [dop_exact(p[0], 1.0, o[0], p[3]), dop_exact(p[1], 1.0, o[1], p[3]), Iv::point(p[3]), Iv::point(c)]
    };
    let a = [0, 1, 2].map(|i| row(tri.q[i], tri.c0[i]));
    let b = [0, 1, 2].map(|i| row(tri.r[i], tri.c1[i]));
    let third = Iv::third();
    // The Bernstein coefficients of det[col0 | col1 | col2] (columns of the rows above).
    let bern = |cols: [usize; 3]| -> [Iv; 4] {
        let d = |at1: [bool; 3]| {
            let r = [0, 1, 2].map(|i| {
                let v = if at1[i] { b[i] } else { a[i] };
                cols.map(|c| v[c])
            });
            det(r[0], r[1], r[2])
        };
        let (f, t) = (false, true);
        [
            d([f, f, f]),
            (d([t, f, f]) + d([f, t, f]) + d([f, f, t])) * third,
            (d([f, t, t]) + d([t, f, t]) + d([t, t, f])) * third,
            d([t, t, t]),
        ]
    };
    let (d0, du, dv) = (bern([0, 1, 2]), bern([3, 1, 2]), bern([0, 3, 2]));
    let k = Iv::point(tri.k);
    let mut sign = None;
    for (u, v) in [(-1.0f32, -1.0f32), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
        let coef = [0, 1, 2, 3].map(|j| {
            let su = if u > 0.0 { d0[j] + du[j] } else { d0[j] - du[j] };
            let kv = k * dv[j];
            if v > 0.0 {
                su + kv
            } else {
                su - kv
            }
        });
        let s = cubic_sign(coef, 4)?;
        if sign.is_some_and(|p| p != s) {
            return None;
        }
        sign = Some(s);
    }
    sign
}

/// [`raw_edge`] for `-safe`, from cross products and differences of products of the
/// exact inputs only (each enclosed to a few ulps of its result by [`dop_exact`]): with
/// `b0 = q_i x q_j`, `s = q_i x r_j + r_i x q_j`, `b2 = r_i x r_j` (n(t) in the Bernstein
/// basis), `n0 = b0`, `n1 + n2 = b2 - b0`, `n2 = b0 + b2 - s`; and m's coefficients
/// `c_j0 q_i - c_i0 q_j`, `((c_j0 r_i - c_i0 r_j) + (c_j1 q_i - c_i1 q_j)) / 2`,
/// `c_j1 r_i - c_i1 r_j`. The same values as [`raw_edge`] in real arithmetic, without
/// its rounded differences `r - q`, whose error times the far-from-origin coordinates
/// would swamp `n1`.
fn raw_edge_safe(tri: &Triangle, i: usize, j: usize) -> RawEdge<Iv> {
    let p3 = |p: [f32; 4]| -> V3 { [p[0], p[1], p[3]] };
    let (qi, qj, ri, rj) = (p3(tri.q[i]), p3(tri.q[j]), p3(tri.r[i]), p3(tri.r[j]));
    let cr = |a: V3, b: V3| cross(a.map(Iv::point), b.map(Iv::point));
    let (b0, b2) = (cr(qi, qj), cr(ri, rj));
    let sum = add(cr(qi, rj), cr(ri, qj));
    let (ci0, ci1, cj0, cj1) = (tri.c0[i], tri.c1[i], tri.c0[j], tri.c1[j]);
    let half = Iv::point(0.5);
    let mb = [0, 1, 2].map(|a| {
        [
            dop_exact(cj0, qi[a], ci0, qj[a]),
            half * (dop_exact(cj0, ri[a], ci0, rj[a]) + dop_exact(cj1, qi[a], ci1, qj[a])),
            dop_exact(cj1, ri[a], ci1, rj[a]),
        ]
    });
    RawEdge { n0: b0, n12: sub(b2, b0), n2: sub(add(b0, b2), sum), mb }
}

/// A closed f32 interval `[lo, hi]` with outward rounding (`-safe`): every operation
/// rounds to nearest and then steps one f32 outward (`next_down` / `next_up`), which
/// encloses the exact result (it lies between the rounded value and its neighbour on
/// its side, subnormals included; an overflow to inf steps back to +-MAX, still beyond
/// the exact value). Endpoints may be infinite (then the quantity is unbounded), never
/// NaN: an operation whose endpoint would be NaN (inf - inf, 0 * inf) gives the whole
/// line on that side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Iv {
    pub(super) lo: f32,
    pub(super) hi: f32,
}

impl Iv {
    pub(super) fn new(lo: f32, hi: f32) -> Iv {
        Iv { lo: if lo.is_nan() { f32::NEG_INFINITY } else { lo }, hi: if hi.is_nan() { f32::INFINITY } else { hi } }
    }
    pub(super) fn point(x: f32) -> Iv {
        Iv::new(x, x)
    }
    fn hull(self, o: Iv) -> Iv {
        Iv { lo: self.lo.min(o.lo), hi: self.hi.max(o.hi) }
    }
    /// Some f32 value in (or near) the interval: the coefficient the plane uses.
    fn mid(self) -> f32 {
        0.5 * self.lo + 0.5 * self.hi
    }
    /// An upper bound of `|x - c|` over the interval (each `|end - c|` rounded, one step
    /// up).
    pub(super) fn dev(self, c: f32) -> f32 {
        (self.lo - c).abs().next_up().max((self.hi - c).abs().next_up())
    }
    fn finite(self) -> bool {
        self.lo.is_finite() && self.hi.is_finite()
    }
}

impl Add for Iv {
    type Output = Iv;
    fn add(self, o: Iv) -> Iv {
        Iv::new((self.lo + o.lo).next_down(), (self.hi + o.hi).next_up())
    }
}
impl Neg for Iv {
    type Output = Iv;
    fn neg(self) -> Iv {
        Iv { lo: -self.hi, hi: -self.lo }
    }
}
impl Sub for Iv {
    type Output = Iv;
    fn sub(self, o: Iv) -> Iv {
        self + -o
    }
}
impl Mul for Iv {
    type Output = Iv;
    fn mul(self, o: Iv) -> Iv {
        let p = [self.lo * o.lo, self.lo * o.hi, self.hi * o.lo, self.hi * o.hi];
        if p.iter().any(|x| x.is_nan()) {
            return Iv { lo: f32::NEG_INFINITY, hi: f32::INFINITY };
        }
        let (lo, hi) = p.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), &x| (l.min(x), h.max(x)));
        Iv::new(lo.next_down(), hi.next_up())
    }
}

impl Ar for Iv {
    fn c(x: f32) -> Self {
        Iv::point(x)
    }
    fn third() -> Self {
        let t = 1.0f32 / 3.0;
        Iv { lo: t.next_down(), hi: t.next_up() }
    }
    fn is_pos(self) -> bool {
        self.lo > 0.0
    }
    fn is_neg(self) -> bool {
        self.hi < 0.0
    }
    fn same_sign(a: Self, b: Self) -> bool {
        (a.is_pos() && b.is_pos()) || (a.is_neg() && b.is_neg())
    }
    fn dop(a: Self, b: Self, c: Self, d: Self) -> Self {
        let pt = |x: Iv| (x.lo == x.hi).then_some(x.lo);
        match (pt(a), pt(b), pt(c), pt(d)) {
            (Some(a), Some(b), Some(c), Some(d)) => dop_exact(a, b, c, d),
            _ => a * b - c * d,
        }
    }
}

/// `a b - c d` of four f32 numbers, enclosed to a few ulps of the result rather than of
/// the products (Kahan's difference of products with FMA): `p = fl(c d)`,
/// `e = fl(p - c d)` and `f = fl(a b - p)` are single roundings (FMA), and
/// `a b - c d = (a b - p) + (p - c d)` lies in `[f, f] + [e, e]` widened by one step per
/// rounding. A non-finite `p` gives the whole line.
fn dop_exact(a: f32, b: f32, c: f32, d: f32) -> Iv {
    let p = c * d;
    if !p.is_finite() {
        return Iv { lo: f32::NEG_INFINITY, hi: f32::INFINITY };
    }
    let e = (-c).mul_add(d, p);
    let f = a.mul_add(b, -p);
    Iv::new((f.next_down() + e.next_down()).next_down(), (f.next_up() + e.next_up()).next_up())
}

/// Per-edge setup of `-safe` (already multiplied by sigma): enclosures of `n0`,
/// `n1 + n2`, `n2` and of each component of `m(t)` over t in [0, 1].
#[derive(Clone, Copy, Debug)]
pub(super) struct SafeEdge {
    n0: [Iv; 3],
    n12: [Iv; 3],
    n2: [Iv; 3],
    m: [Iv; 3],
}

pub(super) struct SafePrep {
    /// Per edge; `None` when an enclosure is unbounded (that edge gives no bound).
    pub(super) s: Result<[Option<SafeEdge>; 3], &'static str>,
    pub(super) k: f32,
    pub(super) per_sample: bool,
}

pub(super) fn setup_safe(tri: &Triangle) -> Result<[Option<SafeEdge>; 3], &'static str> {
    let vals = tri.q.iter().chain(&tri.r).flatten().chain(&tri.c0).chain(&tri.c1);
    if !(vals.into_iter().all(|v| v.is_finite()) && tri.k.is_finite() && tri.k > 0.0) {
        return Err("a non-finite input or k <= 0");
    }
    // The origin: vertex 0's pixel at t = 0 (any finite f32 pair is valid; a vertex at
    // w <= 0 or beyond 2^24 px gives 0).
    let o = [tri.q[0][0] / tri.q[0][3], tri.q[0][1] / tri.q[0][3]];
    let usable = tri.q[0][3] > 0.0 && o.iter().all(|v| v.abs() < (1u32 << 24) as f32);
    let o = if usable { o } else { [0.0; 2] };
    let Some(d_sign) = facing_safe(tri, o) else {
        return Err(FACING_MAY_VANISH);
    };
    let orient = |v: [Iv; 3]| if d_sign < 0.0 { v } else { v.map(|x| -x) };
    let edge = |i: usize, j: usize| -> Option<SafeEdge> {
        let r = raw_edge_safe(tri, i, j);
        let m = r.mb.map(|[b0, b1, b2]| b0.hull(b1).hull(b2));
        let e = SafeEdge { n0: orient(r.n0), n12: orient(r.n12), n2: orient(r.n2), m: orient(m) };
        [e.n0, e.n12, e.n2, e.m].iter().flatten().all(|x| x.finite()).then_some(e)
    };
    Ok([edge(1, 2), edge(2, 0), edge(0, 1)])
}

/// Eq. 9 for `-safe`: f32 coefficients `a` with `e >= a . (1, x, y, u, v, t)` in real
/// arithmetic for every (x, y) in `xs` x `ys`, (u, v) in [-1, 1]^2, t in [0, 1] (see the
/// module doc); None when some value is not finite.
pub(super) fn plane_safe(e: &SafeEdge, k: f32, xs: Iv, ys: Iv) -> Option<[f32; 6]> {
    let dn = f32::next_down;
    let x3 = [xs, ys, Iv::point(1.0)];
    // Eq. 7: the x, y coefficients are f32 values near n0's; the rest of n0 . X over the
    // tile goes into the constant.
    let (ax, ay) = (e.n0[0].mid(), e.n0[1].mid());
    let c_n0 = (e.n0[0] - Iv::point(ax)) * xs + (e.n0[1] - Iv::point(ay)) * ys + e.n0[2];
    let a_t = dot(e.n12, x3).lo;
    let p = (0.25 * dot(e.n2, x3).hi.max(0.0)).next_up();
    // Eq. 8: d_x = y m_z - m_y, k d_y = k (m_x - x m_z) over the tile and the shutter.
    let dx = ys * e.m[2] - e.m[1];
    let dy = Iv::point(k) * (e.m[0] - xs * e.m[2]);
    let (alpha, beta) = (dx.mid(), dy.mid());
    let a_1 = dn(dn(dn(c_n0.lo - p) - dx.dev(alpha)) - dy.dev(beta));
    let a = [a_1, ax, ay, alpha, beta, a_t];
    a.iter().all(|v| v.is_finite()).then_some(a)
}

/// One edge's reject and bounds for `-safe`, from its plane `a` and `m_xy`, a lower bound
/// of the plane's x, y part over the tile: the minimum over the hypercube bounded below
/// by adding the u, v, t corner terms (each sum rounded down); false when that bound is
/// positive (the tile is Empty). Otherwise each of u, v, t is cut where the plane's bound
/// on it, `-rest / a_k` with the other terms at their minimum, is finite: stepped
/// outward.
fn safe_cut(a: &[f32; 6], m_xy: f32, out: &mut TileBounds) -> bool {
    let (dn, up) = (f32::next_down, f32::next_up);
    let (mu, mv, mt) = (-a[3].abs(), -a[4].abs(), a[5].min(0.0));
    let m = dn(dn(dn(m_xy + mu) + mv) + mt);
    if m > 0.0 {
        return false;
    }
    for (ak, rest, range) in [
        (a[3], dn(dn(m_xy + mv) + mt), &mut out.u),
        (a[4], dn(dn(m_xy + mu) + mt), &mut out.v),
        (a[5], dn(dn(m_xy + mu) + mv), &mut out.t),
    ] {
        let bound = -rest / ak;
        if !bound.is_finite() {
            continue;
        }
        if ak > 0.0 {
            range[1] = range[1].min(up(bound));
        } else if ak < 0.0 {
            range[0] = range[0].max(dn(bound));
        }
    }
    true
}

impl Prepared for SafePrep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let Ok(edges) = &self.s else {
            return TileResult::Bounds(TileBounds::full());
        };
        let (x0, x1, y0, y1) = (tile.x0, tile.x1, tile.y0, tile.y1);
        if !([x0, x1, y0, y1].iter().all(|v| v.is_finite()) && x0 <= x1 && y0 <= y1) {
            return TileResult::Bounds(TileBounds::full());
        }
        let dn = f32::next_down;
        let (xs, ys) = (Iv::new(x0, x1), Iv::new(y0, y1));
        let mut out = TileBounds::full();
        for (ei, e) in edges.iter().enumerate() {
            let Some(a) = e.as_ref().and_then(|e| plane_safe(e, self.k, xs, ys)) else {
                continue;
            };
            // Lower bound of the xy part over the tile: at the tile's corner, each product
            // and sum rounded down.
            let m_xy = dn(dn(a[0] + dn(a[1] * x0).min(dn(a[1] * x1))) + dn(a[2] * y0).min(dn(a[2] * y1)));
            if !safe_cut(&a, m_xy, &mut out) {
                return TileResult::Empty;
            }
            if self.per_sample {
                out.constraints.push(Box::new(Plane { edge: ei, a, safe: true }));
            }
        }
        finish(out)
    }
    fn disabled(&self) -> Option<&'static str> {
        self.s.as_ref().err().copied()
    }
    /// The interval products that read one axis of the tile, once per column and per
    /// row ([`SafeGrid`]).
    fn grid<'a>(&'a self, grid: Grid<'a>) -> Box<dyn TileGrid + 'a> {
        let Ok(edges) = &self.s else {
            return Box::new(PerTile { prep: self, grid });
        };
        let consts = edges.map(|e| {
            e.map(|e| {
                let (ax, ay) = (e.n0[0].mid(), e.n0[1].mid());
                let one = Iv::point(1.0);
                SafeConst {
                    ax,
                    ay,
                    rx: e.n0[0] - Iv::point(ax),
                    ry: e.n0[1] - Iv::point(ay),
                    n12z: e.n12[2] * one,
                    n2z: e.n2[2] * one,
                }
            })
        });
        let axis = |a: usize, r: [f32; 2]| SafeGrid::axis(edges, &consts, self.k, a, r);
        let cols = (0..grid.columns()).map(|i| axis(0, grid.column(i))).collect();
        let rows = (0..grid.rows()).map(|j| axis(1, grid.row(j))).collect();
        Box::new(SafeGrid { prep: self, edges, consts, cols, rows })
    }
}

/// The f32 `a + b` of two low ends of [`Iv`]s: `Iv::add`'s low end (rounded, one step
/// down, NaN -> -inf), which reads the operands' low ends only.
fn lo_add(a: f32, b: f32) -> f32 {
    Iv::new((a + b).next_down(), 0.0).lo
}

/// [`lo_add`] for high ends: `Iv::add`'s high end.
fn hi_add(a: f32, b: f32) -> f32 {
    Iv::new(0.0, (a + b).next_up()).hi
}

/// One edge's share of [`SafePrep::tile`] for one column (`xs`) or one row (`ys`) of a
/// grid: the interval products of [`plane_safe`] that read only that axis, kept as the
/// ends the per-tile sums read, and the axis's corner term of `m_xy`.
#[derive(Clone, Copy, Debug)]
struct SafeAxis {
    /// Low end of `(n0_x - a_x) xs` (`(n0_y - a_y) ys`): a term of the n0 rest.
    n0_lo: f32,
    /// Low end of `n12_x xs` (`n12_y ys`): a term of `dot(n12, X)`.
    n12_lo: f32,
    /// High end of `n2_x xs` (`n2_y ys`): a term of `dot(n2, X)`.
    n2_hi: f32,
    /// A column: `beta` (= `a_v`) and its radius `|k d_y - beta|`; a row: `alpha` (= `a_u`)
    /// and its radius.
    mid: f32,
    dev: f32,
    /// `min(dn(a_x x0), dn(a_x x1))` (`a_y`, `y0`, `y1` for a row).
    corner: f32,
}

/// Per edge, what [`plane_safe`] computes from the setup alone (no tile).
#[derive(Clone, Copy, Debug)]
struct SafeConst {
    /// `a_x`, `a_y`: the midpoints of `n0_x`, `n0_y`.
    ax: f32,
    ay: f32,
    /// `n0_x - a_x`, `n0_y - a_y`.
    rx: Iv,
    ry: Iv,
    /// `n12_z 1` and `n2_z 1` (the third terms of the dots).
    n12z: Iv,
    n2z: Iv,
}

/// [`SafePrep::grid`]: per edge its [`SafeConst`], per column and edge the x parts
/// ([`SafeAxis`], None when the column's ends are not finite or out of order: every tile
/// of it answers the full domain), per row the y parts. Per tile and edge only the
/// interval sums of the n0 rest, `dot(n12, X)` and `dot(n2, X)` (the one end each uses,
/// by `Iv::add`'s operations), `a_1`, the finiteness check, and [`SafePrep::tile`]'s
/// `m_xy`, reject and bounds.
struct SafeGrid<'a> {
    prep: &'a SafePrep,
    edges: &'a [Option<SafeEdge>; 3],
    consts: [Option<SafeConst>; 3],
    cols: Vec<Option<[SafeAxis; 3]>>,
    rows: Vec<Option<[SafeAxis; 3]>>,
}

impl SafeGrid<'_> {
    /// The parts of every edge for the column (`axis` 0) or row (`axis` 1) `[lo, hi]`.
    fn axis(
        edges: &[Option<SafeEdge>; 3],
        consts: &[Option<SafeConst>; 3],
        k: f32,
        axis: usize,
        [lo, hi]: [f32; 2],
    ) -> Option<[SafeAxis; 3]> {
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return None;
        }
        let dn = f32::next_down;
        let r = Iv::new(lo, hi);
        Some([0, 1, 2].map(|ei| {
            let (Some(e), Some(c)) = (&edges[ei], &consts[ei]) else {
                // An edge without a plane: never read.
                return SafeAxis { n0_lo: 0.0, n12_lo: 0.0, n2_hi: 0.0, mid: 0.0, dev: 0.0, corner: 0.0 };
            };
            let (rest, a) = if axis == 0 { (c.rx, c.ax) } else { (c.ry, c.ay) };
            // Eq. 8: k d_y = k (m_x - x m_z) (column), d_x = y m_z - m_y (row).
            let d = if axis == 0 { Iv::point(k) * (e.m[0] - r * e.m[2]) } else { r * e.m[2] - e.m[1] };
            let mid = d.mid();
            SafeAxis {
                n0_lo: (rest * r).lo,
                n12_lo: (e.n12[axis] * r).lo,
                n2_hi: (e.n2[axis] * r).hi,
                mid,
                dev: d.dev(mid),
                corner: dn(a * lo).min(dn(a * hi)),
            }
        }))
    }
}

impl TileGrid for SafeGrid<'_> {
    fn tile(&self, i: usize, j: usize) -> TileResult {
        let (Some(cols), Some(rows)) = (&self.cols[i], &self.rows[j]) else {
            return TileResult::Bounds(TileBounds::full());
        };
        let dn = f32::next_down;
        let mut out = TileBounds::full();
        for (ei, (e, c)) in self.edges.iter().zip(&self.consts).enumerate() {
            let (Some(e), Some(c)) = (e, c) else {
                continue;
            };
            let (x, y) = (&cols[ei], &rows[ei]);
            // plane_safe.
            let c_n0 = lo_add(lo_add(x.n0_lo, y.n0_lo), e.n0[2].lo);
            let a_t = lo_add(lo_add(x.n12_lo, y.n12_lo), c.n12z.lo);
            let p = (0.25 * hi_add(hi_add(x.n2_hi, y.n2_hi), c.n2z.hi).max(0.0)).next_up();
            let a_1 = dn(dn(dn(c_n0 - p) - y.dev) - x.dev);
            let a = [a_1, c.ax, c.ay, y.mid, x.mid, a_t];
            if !a.iter().all(|v| v.is_finite()) {
                continue;
            }
            // SafePrep::tile.
            let m_xy = dn(dn(a[0] + x.corner) + y.corner);
            if !safe_cut(&a, m_xy, &mut out) {
                return TileResult::Empty;
            }
            if self.prep.per_sample {
                out.constraints.push(Box::new(Plane { edge: ei, a, safe: true }));
            }
        }
        finish(out)
    }
}
