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
//! `METHOD_SAFE` and `METHOD_PS_SAFE` are the same two tests rounded outward (last
//! section).
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
//!
//! # `mam2012-hyperplane-safe` and `mam2012-hyperplane-ps-safe`: the same planes, rounded outward
//! The f32 planes above are the published method and stay as they are: the gate finds
//! covered tiles they cull (the reject plane's rounding at a tile corner: static, sliver,
//! tiny, far-from-origin, screen-parallel cases), refined u/v bounds of sub-pixel
//! triangles that miss by up to 5e-2 (their cross products cancel), refined t bounds
//! that miss, and per-sample planes whose f32 value `n . s + d` (terms of size pixel x w)
//! errs by up to 0.21 plane units. `METHOD_SAFE` / `METHOD_PS_SAFE` compute the same
//! hyperplane (Eqs. 7-9), the same reject, refined bounds and per-sample test, with every
//! quantity they depend on rounded outward, so that each claim holds for the exact
//! triangle (the issue's "tile reject that keeps its plane outside the hypercube's exact
//! extreme").
//! Their code (setup, planes, tile tests, grid) lives in `mam2012_hyperplane/safe.rs`.
//!
//! *Arithmetic: f32 intervals by directed steps* (`Iv`). Every operation rounds to
//! nearest and steps one f32 outward (`next_down` on the low end, `next_up` on the high
//! end). It encloses: the exact result z of an operation on f32 numbers rounds to r only
//! if z is nearer to r than to r's neighbours, so z lies between them, subnormals
//! included (their spacing 2^-149 is uniform); an overflow to +-inf steps back to +-MAX,
//! still on the far side of z; an end that would be NaN (inf - inf, 0 x inf) becomes
//! -inf / +inf. Steps rather than a gamma_n running bound because the setup is deep
//! (determinants of sheared vertices, de Casteljau halvings, cross products of
//! differences): intervals carry the error of every level mechanically and treat
//! underflow and overflow the same way. The shared pieces (cross and dot products,
//! determinants, the Bernstein sign test `cubic_sign`, the edge's expressions) are written
//! once, generic over the arithmetic (`Ar`); with f32 they are the published method's,
//! operation for operation (checked bit for bit on 76,800 tiles of every regime against
//! the file before the change). `-safe` feeds them forms of the same quantities that
//! avoid rounded differences of the inputs (below).
//!
//! *Setup.* Inputs are exact f32 values; a non-finite input or `k <= 0` disables the test
//! (full domain). Every difference of two products of inputs, `a b - c d` (the cross
//! products' components, m's coefficients), is enclosed by `dop_exact`: Kahan's
//! difference of products with FMA (`p = fl(c d)`, `e = fl(p - c d)`, `f = fl(a b - p)`,
//! three single roundings, `a b - c d = f' + e'` with `f'`, `e'` the exact values of the
//! two FMAs, each enclosed by its rounded value's neighbours), so the enclosure is a few
//! ulps of the result, not of the products: this is what keeps sub-pixel and
//! far-from-origin triangles (whose cross products cancel) usable.
//! - The facing (`facing_safe`): D is linear in each column of its matrix, so
//!   `D(u, v, t) = det[x | y | w] + u det[c | y | w] + k v det[x | c | w]` (the u v term
//!   `det[c | c | w]` vanishes), computed from the exact inputs without rounding a shear,
//!   with x and y first moved to vertex 0's pixel o (`x - o_x w` by `dop_exact`; a column
//!   operation, D unchanged). Each cubic gets its Bernstein coefficients in intervals
//!   (1/3 enclosed by the neighbours of fl(1/3)), each corner `(+-1, +-1)` their sum, the
//!   halvings are done in intervals; a sign is proven only when a whole interval lies on
//!   one side of 0, so sigma is the exact sign of D (otherwise: disabled, as in the
//!   original). The same D as `facing`, in a form whose terms stay at the triangle's
//!   own size: the original's f32 facing test fails (disables itself) on many more tiny
//!   and far-from-origin triangles than this one.
//! - Per edge (`raw_edge_safe`): `n(t)` from its Bernstein coefficients
//!   `b0 = q_i x q_j`, `s = q_i x r_j + r_i x q_j`, `b2 = r_i x r_j` (cross products of
//!   exact inputs; `n0 = b0`, `n1 + n2 = b2 - b0`, `n2 = b0 + b2 - s`, the same values as
//!   the original's in real arithmetic without its rounded `r - q`), and each component
//!   of `m(t)` enclosed by the hull of its three Bernstein coefficients. An edge with an
//!   unbounded enclosure gives no bound (as the original skips a non-finite edge).
//!
//! *Per tile* (`plane_safe`), over the tile `[x0, x1] x [y0, y1]` itself (its exact f32
//! ends: no centre or half extent is rounded):
//! - `a_x`, `a_y` are f32 numbers in the enclosures of `n0_x`, `n0_y` (their midpoints;
//!   the plane is exact for whatever numbers are chosen), and the rest of `n0 . X`,
//!   `(n0_x - a_x) x + (n0_y - a_y) y + n0_z`, is enclosed over the tile; its low end
//!   goes into the constant. Far from the origin this is where the cost shows: the few
//!   ulps of `x_i w_j` in the n0 enclosure times |x| up to 1e6 px, i.e. the published
//!   plane's own rounding, bounded instead of ignored;
//! - `a_t` = the low end of the enclosure of `(n1 + n2) . X` over the tile (Eq. 7:
//!   `t (n1 + n2) . X >= a_t t` for t >= 0);
//! - `P` = an upper bound of `max(n2 . X, 0) / 4` over the tile (Eq. 7's t^2 padding);
//! - `d_x = y m_z - m_y` and `k d_y = k (m_x - x m_z)` enclosed over the tile and the
//!   shutter; `alpha`, `beta` their midpoints and `rad_x`, `rad_y` upper bounds of
//!   `|d_x - alpha|`, `|k d_y - beta|` (`Iv::dev`), so `u d_x + k v d_y >= alpha u +
//!   beta v - rad_x - rad_y` for |u|, |v| <= 1 (Eq. 8; the interval products are never
//!   wider than the original's midpoint-radius products);
//! - `a_1` = the n0 rest's low end `- P - rad_x - rad_y`, each subtraction rounded to
//!   nearest and stepped down.
//!
//! So `e >= a . (1, x, y, u, v, t)` holds in real arithmetic for these f32 numbers `a`
//! on the whole box (the derivation above with every enclosure exact).
//!
//! *Reject and refined bounds.* `m = a_1 + min(a_x x0, a_x x1) + min(a_y y0, a_y y1) -
//! |a_u| - |a_v| + min(a_t, 0)` with each product and partial sum stepped down is a lower
//! bound of the plane's exact minimum over the hypercube: `m > 0` proves `e > 0` on the
//! box, no interior sample. For coordinate k, `R_k` is the same sum without k's term
//! (again rounded down, so below the exact one); an interior sample has
//! `a_k x_k < -R_exact <= -R_k`, and the quotient of the two f32 numbers `-R_k / a_k`,
//! rounded and stepped up (a_k > 0) or down (a_k < 0), encloses the exact quotient.
//! Non-finite values give no bound, as in the original.
//!
//! *The t bound near double roots.* When the edge's quadratic in t has a (near) double
//! root over the tile (a moving edge that grazes the tile's corner and turns back), `a_t`
//! and `R_t` are both small differences of large terms, and the published quotient
//! `-R_t / a_t` divides one rounding error by another: `cullproof stability --family
//! double-root` finds the original's t bounds missing by 4e-4 .. 2e-2 as the graze depth
//! goes from 1e-3 to 1e-6 px. The algebra is not at fault: Eq. 7's
//! `A t^2 >= A t - max(A, 0) / 4` holds for every A (tangent at t = 1/2 for A > 0, chord
//! for A < 0), so it holds at a double root too, and no fallback is needed. In `-safe`,
//! `a_t` is an exact f32 lower bound of `(n1 + n2) . X` (the sign tested is the sign of
//! the number divided by) and `R_t` a proven lower bound, so the outward-rounded quotient
//! is a valid bound however small they are (a tiny `a_t` gives a far, harmless bound or an
//! inf that is skipped); the same family finds no violation of either `-safe` variant.
//!
//! *Per sample* (`-ps-safe`). `eval` computes `a . s` with every product and partial sum
//! stepped down (10 operations), a lower bound of the exact value, and returns its
//! negation, an upper bound of `g(s) = -(a . s) > 0` for every interior sample. Its error:
//! each step errs by at most `u |z| + 2u |r| <= 3.01 u |z|` (u = 2^-24; rounding to
//! nearest, then one ulp <= 2u|r|) for normal results and `2^-150 + 2^-149` for
//! subnormal ones, partial sums are below `1.01 sum |a_i s_i|`, so
//! `|eval + a . s| <= (5 x 3.01 + 5 x 3.01 x 1.01) u sum |a_i s_i| + 30 x 2^-150
//! < 2^-19 sum |a_i s_i| + 2^-140`, the widening `eval_box` uses for `-safe` (the
//! original's: `2^-20` for rounding to nearest).
//!
//! *Cost*: setup in intervals with FMA differences of products (about three times the
//! original's operations, plus the steps); per tile about twice the products (interval
//! products over the tile); per sample 10 steps more (what a directed rounding mode gives
//! for free). Tightness (`check --seed 1`, fraction of the boundary tiles' samples the
//! tile answer admits, original -> `-safe`): within 0.2% in 12 of the 16 regimes; tighter
//! on tiny (0.882 -> 0.823) and huge-CoC triangles (0.705 -> 0.697), where the
//! original's f32 facing test gives up more often; looser far from the origin
//! (0.735 -> 0.789, where the original culls covered samples in 148 of 600 cases) and on
//! degenerate triangles (0.897 -> 0.912: zero area at a shutter end, where the original's
//! f32 facing "proves" a sign that intervals cannot).
//!
//! # Grids
//! Over a grid of tiles ([`Prepared::grid`]) the terms of the plane and of the tile
//! tests that read one axis of the tile only are computed once per column and once per
//! row: for the published variants the products with the tile's centre and half extent
//! of that axis (`PlainGrid`), for `-safe` the interval products of `plane_safe` with
//! that axis's range, kept as the one end each later sum reads, `alpha` or `beta` with
//! its radius, and the axis's corner term of `m_xy` (`SafeGrid`). A tile forms the sums
//! that mix x and y with the same operations in the same order as `tile`, so the answers
//! are `tile`'s bit for bit (`grid_tests.rs`).

use super::*;
use crate::bounds::arith::{tile_of, F32Arith, Plain};
use std::ops::{Add, Mul, Sub};

mod safe;
use safe::{setup_safe, SafePrep};
pub use safe::{METHOD_PS_SAFE, METHOD_SAFE};

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
    /// `-safe`: the setup in outward-rounded f32 intervals, the plane and its tests
    /// rounded outward (see the module doc).
    safe: bool,
}

impl Mam2012Hyperplane {
    /// A variant with selective enabling (not registered; it reports the same id as
    /// the registered method of the same `per_sample`).
    pub fn selective(per_sample: bool, ratio: f32) -> Self {
        Mam2012Hyperplane {
            info: if per_sample { &INFO_PS } else { &INFO },
            per_sample,
            selective_enable_ratio: Some(ratio),
            safe: false,
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

pub static METHOD: &dyn Method =
    &Mam2012Hyperplane { info: &INFO, per_sample: false, selective_enable_ratio: None, safe: false };
pub static METHOD_PS: &dyn Method =
    &Mam2012Hyperplane { info: &INFO_PS, per_sample: true, selective_enable_ratio: None, safe: false };

impl Method for Mam2012Hyperplane {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        let off = self.selective_enable_ratio.and_then(|r| selective_disable(tri, r));
        if self.safe {
            let s = match off {
                Some(why) => Err(why),
                None => setup_safe(tri),
            };
            return Box::new(SafePrep { s, k: tri.k, per_sample: self.per_sample });
        }
        let s = match off {
            Some(why) => Err(why),
            None => setup(tri),
        };
        Box::new(Prep { s, per_sample: self.per_sample })
    }
}

type V3 = [f32; 3];

/// The arithmetic of the setup: plain f32 (the published method) or outward-rounded f32
/// intervals ([`Iv`](safe::Iv), `-safe`). The expressions below are written once for both; with
/// f32 they are the published method's, operation for operation.
trait Ar: Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> {
    /// An f32 constant.
    fn c(x: f32) -> Self;
    /// 1/3 (f32: rounded; interval: enclosed).
    fn third() -> Self;
    /// Provably > 0 / < 0 (f32: the comparison; false on NaN).
    fn is_pos(self) -> bool;
    fn is_neg(self) -> bool;
    /// Both provably nonzero with the same sign.
    fn same_sign(a: Self, b: Self) -> bool;
    /// `a b - c d` (f32: as written).
    fn dop(a: Self, b: Self, c: Self, d: Self) -> Self;
}

impl Ar for f32 {
    fn c(x: f32) -> Self {
        x
    }
    fn third() -> Self {
        1.0 / 3.0
    }
    fn is_pos(self) -> bool {
        self > 0.0
    }
    fn is_neg(self) -> bool {
        self < 0.0
    }
    fn same_sign(a: Self, b: Self) -> bool {
        a * b > 0.0 // false on NaN too
    }
    fn dop(a: Self, b: Self, c: Self, d: Self) -> Self {
        a * b - c * d
    }
}

fn cross<T: Ar>(a: [T; 3], b: [T; 3]) -> [T; 3] {
    [T::dop(a[1], b[2], a[2], b[1]), T::dop(a[2], b[0], a[0], b[2]), T::dop(a[0], b[1], a[1], b[0])]
}
fn dot<T: Ar>(a: [T; 3], b: [T; 3]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn add<T: Ar>(a: [T; 3], b: [T; 3]) -> [T; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub<T: Ar>(a: [T; 3], b: [T; 3]) -> [T; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn scale(s: f32, a: V3) -> V3 {
    [s * a[0], s * a[1], s * a[2]]
}
fn det<T: Ar>(a: [T; 3], b: [T; 3], c: [T; 3]) -> T {
    dot(a, cross(b, c))
}

/// The strict sign of a cubic on [0, 1] from its Bernstein coefficients, if provable
/// within `depth` halvings.
fn cubic_sign<T: Ar>(b: [T; 4], depth: u32) -> Option<f32> {
    if b.iter().all(|&x| x.is_pos()) {
        return Some(1.0);
    }
    if b.iter().all(|&x| x.is_neg()) {
        return Some(-1.0);
    }
    // A sign change or zero at an end, NaN, or no budget left: not provable.
    let same_sign_ends = T::same_sign(b[0], b[3]);
    if depth == 0 || !same_sign_ends {
        return None;
    }
    let m = |p: T, q: T| T::c(0.5) * (p + q);
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

/// The edge (i, j) before orientation: `n0`, `n1 + n2`, `n2` and the three Bernstein
/// coefficients on [0, 1] of each component of `m(t) = c_j(t) p_i(t) - c_i(t) p_j(t)`.
struct RawEdge<T> {
    n0: [T; 3],
    n12: [T; 3],
    n2: [T; 3],
    mb: [[T; 3]; 3],
}

fn raw_edge<T: Ar>(tri: &Triangle, i: usize, j: usize) -> RawEdge<T> {
    let p3 = |p: [f32; 4]| -> [T; 3] { [T::c(p[0]), T::c(p[1]), T::c(p[3])] };
    let (qi, qj) = (p3(tri.q[i]), p3(tri.q[j]));
    let (ri, rj) = (p3(tri.r[i]), p3(tri.r[j]));
    let (di, dj) = (sub(ri, qi), sub(rj, qj));
    let n0 = cross(qi, qj);
    let n1 = add(cross(qi, dj), cross(di, qj));
    let n2 = cross(di, dj);
    let (ci0, ci1, cj0, cj1) = (T::c(tri.c0[i]), T::c(tri.c1[i]), T::c(tri.c0[j]), T::c(tri.c1[j]));
    let mb = [0, 1, 2].map(|a| {
        [
            cj0 * qi[a] - ci0 * qj[a],
            T::c(0.5) * ((cj0 * ri[a] + cj1 * qi[a]) - (ci0 * rj[a] + ci1 * qj[a])),
            cj1 * ri[a] - ci1 * rj[a],
        ]
    });
    RawEdge { n0, n12: add(n1, n2), n2, mb }
}

/// Per-edge setup state (already multiplied by sigma = -sign(D)), its numbers f32 (the
/// method) or values of another [`F32Arith`] (the encoding of the tile path).
#[derive(Clone, Copy, Debug)]
pub struct Edge<F = f32> {
    pub n0: [F; 3],
    pub n12: [F; 3],
    pub n2: [F; 3],
    /// Midpoint and radius of each component of m(t) over [0, 1].
    pub mc: [F; 3],
    pub mr: [F; 3],
}

impl Edge {
    /// The same edge with every number mapped.
    pub fn map<G>(&self, f: impl Fn(f32) -> G) -> Edge<G> {
        let m = |v: &V3| v.map(&f);
        Edge { n0: m(&self.n0), n12: m(&self.n12), n2: m(&self.n2), mc: m(&self.mc), mr: m(&self.mr) }
    }
}

/// The f32 setup of `mam2012-hyperplane` (without selective enabling): the three
/// edges and the aspect `k`, or the reason the test is disabled. The tile path
/// ([`tile_answer`]) is encoded from these values.
pub fn edges_of(tri: &Triangle) -> Result<([Edge; 3], f32), &'static str> {
    setup(tri).map(|s| (s.edges, s.k))
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

const FACING_MAY_VANISH: &str = "D (the facing) may vanish or change sign over the lens and shutter";

fn setup(tri: &Triangle) -> Result<Setup, &'static str> {
    let Some(d_sign) = facing(tri) else {
        return Err(FACING_MAY_VANISH);
    };
    let sigma = -d_sign;
    let edge = |i: usize, j: usize| -> Edge {
        let r = raw_edge::<f32>(tri, i, j);
        let mut mc = [0.0; 3];
        let mut mr = [0.0; 3];
        for (a, &[b0, b1, b2]) in r.mb.iter().enumerate() {
            let (lo, hi) = (b0.min(b1).min(b2), b0.max(b1).max(b2));
            // sigma = -1 negates m: the midpoint flips, the radius stays.
            mc[a] = sigma * (0.5 * (lo + hi));
            mr[a] = 0.5 * (hi - lo);
            if b0.is_nan() || b1.is_nan() || b2.is_nan() {
                mc[a] = f32::NAN;
            }
        }
        Edge { n0: scale(sigma, r.n0), n12: scale(sigma, r.n12), n2: scale(sigma, r.n2), mc, mr }
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

/// The hyperplane `a = (a_1, a_x, a_y, a_u, a_v, a_t)` of one edge for one tile, over
/// any [`F32Arith`] (`xc`, `yc`: the tile's centre, `hx`, `hy`: its half extents), and
/// whether every coefficient is finite (else the edge gives no bound).
pub fn plane_of<A: F32Arith>(ar: &A, e: &Edge<A::F>, k: &A::F, c: &[A::F; 2], h: &[A::F; 2]) -> (A::B, [A::F; 6]) {
    let ([xc, yc], [hx, hy]) = (c, h);
    let xc3 = [xc.clone(), yc.clone(), ar.lit(1.0)];
    let dot = |a: &[A::F; 3], b: &[A::F; 3]| {
        ar.add(&ar.add(&ar.mul(&a[0], &b[0]), &ar.mul(&a[1], &b[1])), &ar.mul(&a[2], &b[2]))
    };
    let pad = |n: &[A::F; 3]| ar.add(&ar.mul(&ar.abs(&n[0]), hx), &ar.mul(&ar.abs(&n[1]), hy));
    // Eq. 7.
    let z = pad(&e.n12);
    let a_t = ar.sub(&dot(&e.n12, &xc3), &z);
    let a2 = ar.add(&dot(&e.n2, &xc3), &pad(&e.n2));
    let p = ar.mul(&ar.lit(0.25), &ar.max(&a2, &ar.lit(0.0)));
    // Eq. 8.
    let (mc, mr) = (&e.mc, &e.mr);
    let pad_z = ar.add(&ar.abs(&mc[2]), &mr[2]);
    let avg_x = ar.sub(&ar.mul(yc, &mc[2]), &mc[1]);
    let rad_x = ar.add(&ar.add(&ar.mul(&ar.abs(yc), &mr[2]), &ar.mul(hy, &pad_z)), &mr[1]);
    let avg_y = ar.sub(&mc[0], &ar.mul(xc, &mc[2]));
    let rad_y = ar.add(&ar.add(&mr[0], &ar.mul(&ar.abs(xc), &mr[2])), &ar.mul(hx, &pad_z));
    let xi = ar.neg(&ar.add(&rad_x, &ar.mul(k, &rad_y)));
    let a0 = ar.sub(&ar.add(&e.n0[2], &xi), &p);
    let a = [a0, e.n0[0].clone(), e.n0[1].clone(), avg_x, ar.mul(k, &avg_y), a_t];
    let finite: Vec<A::B> = a.iter().map(|v| ar.is_finite(v)).collect();
    (ar.all(&finite), a)
}

/// The refined `[u^, v^, t^]` (before the clamp of [`finish_of`]) as values of some
/// [`F32Arith`].
pub type Ranges<F> = [[F; 2]; 3];

/// One edge's part of the tile answer over any [`F32Arith`]: from its plane `a` (used
/// only when `ok`), whether it rejects the tile (the plane's minimum over the tile, lens
/// and shutter is > 0) and the ranges cut by it. The xy part is evaluated once at the
/// tile centre, padded by the half extents.
pub fn edge_tile<A: F32Arith>(
    ar: &A,
    (ok, a): (&A::B, &[A::F; 6]),
    c: &[A::F; 2],
    h: &[A::F; 2],
    ranges: &Ranges<A::F>,
) -> (A::B, Ranges<A::F>) {
    let at_c = ar.add(&ar.add(&a[0], &ar.mul(&a[1], &c[0])), &ar.mul(&a[2], &c[1]));
    let m_xy = ar.sub(&at_c, &ar.add(&ar.mul(&ar.abs(&a[1]), &h[0]), &ar.mul(&ar.abs(&a[2]), &h[1])));
    edge_cut(ar, (ok, a), &m_xy, ranges)
}

/// [`edge_tile`] from `m_xy`, the plane's x, y part at the tile centre minus its pad:
/// the reject (the plane's minimum over the tile, lens and shutter is > 0) and the ranges
/// cut by the plane.
pub fn edge_cut<A: F32Arith>(
    ar: &A,
    (ok, a): (&A::B, &[A::F; 6]),
    m_xy: &A::F,
    ranges: &Ranges<A::F>,
) -> (A::B, Ranges<A::F>) {
    let m_xy = m_xy.clone();
    let zero = ar.lit(0.0);
    let (mu, mv, mt) = (ar.neg(&ar.abs(&a[3])), ar.neg(&ar.abs(&a[4])), ar.min(&a[5], &zero));
    let m = ar.add(&ar.add(&ar.add(&m_xy, &mu), &mv), &mt);
    let rejects = ar.and(ok, &ar.gt(&m, &zero));
    let rests = [ar.add(&ar.add(&m_xy, &mv), &mt), ar.add(&ar.add(&m_xy, &mu), &mt), ar.add(&ar.add(&m_xy, &mu), &mv)];
    let cut = [0, 1, 2].map(|r| {
        let ak = &a[3 + r];
        let bound = ar.div(&ar.neg(&rests[r]), ak);
        let usable = ar.and(ok, &ar.is_finite(&bound));
        let (up, down) = (ar.and(&usable, &ar.gt(ak, &zero)), ar.and(&usable, &ar.lt(ak, &zero)));
        let [lo, hi] = &ranges[r];
        [ar.select(&down, &ar.max(lo, &bound), lo), ar.select(&up, &ar.min(hi, &bound), hi)]
    });
    (rejects, cut)
}

/// The tile answer of `mam2012-hyperplane` over any [`F32Arith`] for an enabled
/// setup's edges and aspect `k`: `(nonempty, [u^, v^, t^], planes)`; the tile is Empty
/// when `nonempty` is false (the tile reject).
#[allow(clippy::type_complexity)]
pub fn tile_answer<A: F32Arith>(
    ar: &A,
    edges: &[Edge<A::F>; 3],
    k: &A::F,
    tile: &[A::F; 4],
) -> (A::B, Ranges<A::F>, [(A::B, [A::F; 6]); 3]) {
    let (c, h) = centre(ar, tile);
    let full = TileBounds::full();
    let mut ranges = [full.u, full.v, full.t].map(|r| r.map(|x| ar.lit(x)));
    let mut rejects = vec![];
    let planes = edges.each_ref().map(|e| plane_of(ar, e, k, &c, &h));
    for (ok, a) in &planes {
        let (rej, cut) = edge_tile(ar, (ok, a), &c, &h, &ranges);
        rejects.push(rej);
        ranges = cut;
    }
    let (ok, ranges) = finish_of(ar, &ranges);
    (ar.and(&ar.not(&ar.any(&rejects)), &ok), ranges, planes)
}

/// The tile's centre and half extents, `[xc, yc]` and `[hx, hy]`.
fn centre<A: F32Arith>(ar: &A, tile: &[A::F; 4]) -> ([A::F; 2], [A::F; 2]) {
    let half = ar.lit(0.5);
    let c = |a: usize| ar.mul(&half, &ar.add(&tile[a], &tile[a + 2]));
    let h = |a: usize| ar.mul(&half, &ar.sub(&tile[a + 2], &tile[a]));
    ([c(0), c(1)], [h(0), h(1)])
}

/// One per-sample hyperplane: culled when `a . (1, x, y, u, v, t) > 0`.
#[derive(Debug, Clone, Copy)]
struct Plane {
    edge: usize,
    a: [f32; 6],
    /// `-safe`: `eval` rounds every step of `a . s` down (an upper bound of `-(a . s)`).
    safe: bool,
}

impl Plane {
    /// The exact `a . (1, s)` over the box (outward-rounded) and the bound on how far
    /// `-eval` lies from it (see the module doc).
    fn sum_and_err(&self, b: &SampleBox) -> (Interval, f64) {
        let p = |i: usize| Interval::point(self.a[i] as f64);
        let terms = [p(0), p(1) * b.x, p(2) * b.y, p(3) * b.u, p(4) * b.v, p(5) * b.t];
        let mut sum = Interval::point(0.0);
        let mut mag = Interval::point(0.0);
        for t in terms {
            sum = sum + t;
            mag = mag + Interval::point(t.lo.abs().max(t.hi.abs()));
        }
        // Rounded to nearest: gamma_6 < 2^-21 of the magnitudes (see the module doc);
        // rounded down with a step after each of the 10 operations: below 2^-19 (`-safe`).
        let rel = if self.safe { 2f64.powi(-19) } else { 2f64.powi(-20) };
        let err = (Interval::point(mag.hi) * Interval::point(rel) + Interval::point(2f64.powi(-140))).hi;
        (sum, err)
    }
}

impl SampleConstraint for Plane {
    fn name(&self) -> String {
        format!("edge {} hyperplane", self.edge)
    }
    fn eval(&self, s: &Sample) -> f32 {
        let a = &self.a;
        if self.safe {
            let dn = f32::next_down;
            let mut acc = a[0];
            for (ai, si) in a[1..].iter().zip([s.x, s.y, s.u, s.v, s.t]) {
                acc = dn(acc + dn(ai * si));
            }
            return -acc;
        }
        let mut acc = a[0];
        acc += a[1] * s.x;
        acc += a[2] * s.y;
        acc += a[3] * s.u;
        acc += a[4] * s.v;
        acc += a[5] * s.t;
        -acc
    }
    /// `eval` over the columns: per sample the same f32 operations in the same order
    /// (the sum from `a[0]` through the x, y, u, v, t terms), side by side.
    fn eval_row(&self, c: &SampleCols, out: &mut [f32]) {
        let a = self.a;
        let n = c.len().min(out.len());
        let (xs, ys, us, vs, ts, out) = (&c.x[..n], &c.y[..n], &c.u[..n], &c.v[..n], &c.t[..n], &mut out[..n]);
        if self.safe {
            // `f32::next_down` written as selects (the same bits), so the samples run
            // side by side.
            let dn = super::step::dn;
            for i in 0..n {
                let mut acc = a[0];
                for (ai, si) in a[1..].iter().zip([xs[i], ys[i], us[i], vs[i], ts[i]]) {
                    acc = dn(acc + dn(ai * si));
                }
                out[i] = -acc;
            }
            return;
        }
        for i in 0..n {
            let mut acc = a[0];
            acc += a[1] * xs[i];
            acc += a[2] * ys[i];
            acc += a[3] * us[i];
            acc += a[4] * vs[i];
            acc += a[5] * ts[i];
            out[i] = -acc;
        }
    }
    fn eval_box(&self, b: &SampleBox) -> Interval {
        let (sum, err) = self.sum_and_err(b);
        -(sum + Interval::new(-err, err))
    }
    /// `-(a . (1, s))` exactly, less the error bound of [`eval_box`](Self::eval_box)
    /// over the box (the same analysis: `eval` lies within it of the exact value). In
    /// `-safe` with no error: every product and partial sum is stepped down, so the
    /// f32 sum is at most the exact `a . (1, s)` (an overflow steps to `-inf` or
    /// `f32::MAX`, still below), and `eval`, its negation, is at least `-(a . (1, s))`.
    fn lower_cut(&self, b: &SampleBox) -> Option<Cut> {
        let err = if self.safe { 0.0 } else { self.sum_and_err(b).1 };
        let mut cut = Cut::zero();
        for (m, a) in [0, Cut::X, Cut::Y, Cut::U, Cut::V, Cut::T].into_iter().zip(self.a) {
            cut.coef[m] = -(a as f64);
        }
        cut.err = err;
        Some(cut)
    }
}

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let s = match &self.s {
            Ok(s) => s,
            Err(_) => return TileResult::Bounds(TileBounds::full()),
        };
        let (c, h) = centre(&Plain, &tile_of(tile));
        let mut out = TileBounds::full();
        for (ei, e) in s.edges.iter().enumerate() {
            let (ok, a) = plane_of(&Plain, e, &s.k, &c, &h);
            if !ok {
                continue;
            }
            let (rejects, [u, v, t]) = edge_tile(&Plain, (&ok, &a), &c, &h, &[out.u, out.v, out.t]);
            if rejects {
                return TileResult::Empty;
            }
            (out.u, out.v, out.t) = (u, v, t);
            if self.per_sample {
                out.constraints.push(Box::new(Plane { edge: ei, a, safe: false }));
            }
        }
        finish(out)
    }
    fn disabled(&self) -> Option<&'static str> {
        self.s.as_ref().err().copied()
    }
    /// The plane's terms that read one axis of the tile, once per column and per row
    /// ([`PlainGrid`]).
    fn grid<'a>(&'a self, grid: Grid<'a>) -> Box<dyn TileGrid + 'a> {
        let Ok(s) = &self.s else {
            return Box::new(PerTile { prep: self, grid });
        };
        Box::new(PlainGrid {
            s,
            per_sample: self.per_sample,
            // `plane_of`'s third dot-product terms (times the centre's literal 1, as there).
            z: s.edges.map(|e| [e.n12[2] * 1.0, e.n2[2] * 1.0]),
            cols: (0..grid.columns()).map(|i| PlainGrid::axis(s, 0, grid.column(i))).collect(),
            rows: (0..grid.rows()).map(|j| PlainGrid::axis(s, 1, grid.row(j))).collect(),
        })
    }
}

/// The refined ranges clamped to the domain over any [`F32Arith`]; false when one is
/// empty.
pub fn finish_of<A: F32Arith>(ar: &A, r: &Ranges<A::F>) -> (A::B, Ranges<A::F>) {
    let clamp = |r: &[A::F; 2], lo: f32, hi: f32| [ar.max(&r[0], &ar.lit(lo)), ar.min(&r[1], &ar.lit(hi))];
    let r = [clamp(&r[0], -1.0, 1.0), clamp(&r[1], -1.0, 1.0), clamp(&r[2], 0.0, 1.0)];
    let ok = r.each_ref().map(|x| ar.le(&x[0], &x[1]));
    (ar.all(&ok), r)
}

/// Clamp the refined intervals to the domain; Empty when one is empty.
fn finish(mut out: TileBounds) -> TileResult {
    let (ok, [u, v, t]) = finish_of(&Plain, &[out.u, out.v, out.t]);
    if !ok {
        return TileResult::Empty;
    }
    (out.u, out.v, out.t) = (u, v, t);
    TileResult::Bounds(out)
}

// ---------------------------------------------------------------------------------
// Grids: the parts of the plane that read one axis of the tile, once per column / row.
// ---------------------------------------------------------------------------------

/// One edge's share of [`Prep::tile`] for one column (`x`) or one row (`y`) of a grid:
/// the terms of [`plane_of`] and [`edge_tile`] that read only that axis's centre and
/// half extent, as f32 values computed by the same operations.
#[derive(Clone, Copy, Debug, Default)]
struct PlainAxis {
    /// `n12_x xc` (`n12_y yc`): the axis's term of `dot(n12, Xc)`.
    t_dot: f32,
    /// `|n12_x| hx` (`|n12_y| hy`): the axis's term of Eq. 7's pad `Z`.
    t_pad: f32,
    /// `n2_x xc`, `|n2_x| hx`: the same for `n2`.
    p_dot: f32,
    p_pad: f32,
    /// A row: `avg_x` (= `a_u`) and `rad_x`; a column: `k avg_y` (= `a_v`) and `k rad_y`.
    avg: f32,
    rad: f32,
    /// `a_x xc`, `|a_x| hx` (`a_y yc`, `|a_y| hy`): the axis's terms of `m_xy`.
    at_c: f32,
    pad: f32,
}

/// [`Prep::grid`]: per column and edge the x terms ([`PlainAxis`]), per row and edge the
/// y terms, per edge `n12_z 1` and `n2_z 1`. Per tile and edge only the sums of
/// [`plane_of`] (`a_t`, `P`, `xi`, `a_1`) and [`edge_tile`] (`m_xy`, the reject, the
/// three rests and quotients), with the same operations in the same order.
struct PlainGrid<'a> {
    s: &'a Setup,
    per_sample: bool,
    /// `[n12_z 1, n2_z 1]` per edge.
    z: [[f32; 2]; 3],
    cols: Vec<[PlainAxis; 3]>,
    rows: Vec<[PlainAxis; 3]>,
}

impl PlainGrid<'_> {
    /// The column (`axis` 0, edges `[x0, x1]`) or row (`axis` 1) terms of every edge.
    fn axis(s: &Setup, axis: usize, [lo, hi]: [f32; 2]) -> [PlainAxis; 3] {
        let ar = &Plain;
        // `centre`'s operations on this axis.
        let half = 0.5f32;
        let (c, h) = (half * (lo + hi), half * (hi - lo));
        s.edges.map(|e| {
            let (mc, mr) = (&e.mc, &e.mr);
            let pad_z = ar.add(&ar.abs(&mc[2]), &mr[2]);
            let (avg, rad) = if axis == 1 {
                let avg_x = ar.sub(&ar.mul(&c, &mc[2]), &mc[1]);
                let rad_x = ar.add(&ar.add(&ar.mul(&ar.abs(&c), &mr[2]), &ar.mul(&h, &pad_z)), &mr[1]);
                (avg_x, rad_x)
            } else {
                let avg_y = ar.sub(&mc[0], &ar.mul(&c, &mc[2]));
                let rad_y = ar.add(&ar.add(&mr[0], &ar.mul(&ar.abs(&c), &mr[2])), &ar.mul(&h, &pad_z));
                (ar.mul(&s.k, &avg_y), ar.mul(&s.k, &rad_y))
            };
            let a = e.n0[axis];
            PlainAxis {
                t_dot: ar.mul(&e.n12[axis], &c),
                t_pad: ar.mul(&ar.abs(&e.n12[axis]), &h),
                p_dot: ar.mul(&e.n2[axis], &c),
                p_pad: ar.mul(&ar.abs(&e.n2[axis]), &h),
                avg,
                rad,
                at_c: ar.mul(&a, &c),
                pad: ar.mul(&ar.abs(&a), &h),
            }
        })
    }
}

impl TileGrid for PlainGrid<'_> {
    fn tile(&self, i: usize, j: usize) -> TileResult {
        let ar = &Plain;
        let zero = 0.0f32;
        let mut out = TileBounds::full();
        for (ei, e) in self.s.edges.iter().enumerate() {
            let (x, y) = (&self.cols[i][ei], &self.rows[j][ei]);
            let [n12z, n2z] = self.z[ei];
            // plane_of: Eq. 7 and Eq. 8 from the column's and the row's terms.
            let z = ar.add(&x.t_pad, &y.t_pad);
            let a_t = ar.sub(&ar.add(&ar.add(&x.t_dot, &y.t_dot), &n12z), &z);
            let a2 = ar.add(&ar.add(&ar.add(&x.p_dot, &y.p_dot), &n2z), &ar.add(&x.p_pad, &y.p_pad));
            let p = ar.mul(&0.25, &ar.max(&a2, &zero));
            let xi = ar.neg(&ar.add(&y.rad, &x.rad));
            let a0 = ar.sub(&ar.add(&e.n0[2], &xi), &p);
            let a = [a0, e.n0[0], e.n0[1], y.avg, x.avg, a_t];
            if !a.iter().all(|v| v.is_finite()) {
                continue;
            }
            // edge_tile: m_xy from the column's and the row's terms, then its cut.
            let at_c = ar.add(&ar.add(&a0, &x.at_c), &y.at_c);
            let m_xy = ar.sub(&at_c, &ar.add(&x.pad, &y.pad));
            let (rejects, [u, v, t]) = edge_cut(ar, (&true, &a), &m_xy, &[out.u, out.v, out.t]);
            if rejects {
                return TileResult::Empty;
            }
            (out.u, out.v, out.t) = (u, v, t);
            if self.per_sample {
                out.constraints.push(Box::new(Plane { edge: ei, a, safe: false }));
            }
        }
        finish(out)
    }
}

#[cfg(test)]
mod grid_cases;

#[cfg(test)]
mod tests;
