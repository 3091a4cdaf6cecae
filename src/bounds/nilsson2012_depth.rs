//! nilsson2012-depth: a conservative depth interval `z^` over a tile, after Nilsson,
//! Clarberg, Johnsson, Munkberg, Hasselgren, Toth, Salvi, Akenine-Möller, "Design and
//! Novel Uses of Higher-Dimensional Rasterization", HPG 2012, Appendix A ("Conservative
//! Depth Computations", Eq. 1 and Figure 18), used for z-culling, 5D occlusion queries
//! and continuous collision detection (§3).
//!
//! # What "depth" the paper bounds, and what we output
//! Appendix A works with clip-space points `(x, y, w)`: the plane normal is negated
//! "if n_w < 0", a plane must not "sweep through the camera origin", and the depth is
//! evaluated by intersecting a tile corner's ray with the plane. Along the ray through
//! pixel (X, Y) a point is `w (X, Y, 1)`, so what the paper bounds is **w** (camera-space
//! depth, linear). The model's hit depth is `zeta = z_hit / w_hit`, the barycentric blend
//! of the vertices' clip z over `w_hit` (`docs/model.md` §3.4; the oracle's `N / D`).
//! We bound w as the paper does and convert at the end (see "Conversion" below).
//!
//! # The hit point
//! For an interior sample (x, y, u, v, t) the barycentrics `b_k = E_k / sum E` are all
//! positive and sum to 1, and the hit point is `H = sum b_k p'_k(t)` where
//! `p'_k = p_k(t) + c_k(t) (u, k v, 0)` are the sheared vertices, with
//! `H = w_hit (x, y, 1)` in (x', y', w) and `w_hit > 0` (`docs/model.md`). Its depth is
//! `zeta = (sum b_k z_k(t)) / (sum b_k w_k(t))`. The shear moves x', y' only, never z, w.
//!
//! # Test 1: the moving bounding box (only its depth faces are used)
//! `w_hit` is a convex combination of `w_k(t)`, each a lerp of its two ends, so
//! `w_hit in [min, max]` of the six vertex w values: the nearest / farthest rectangle of
//! the moving box, as the paper uses only the far face for z_max and the near one for
//! z_min. We use only the depth of those faces (not their x, y extent: a ray that misses
//! the far rectangle would need the side faces, which the paper does not use either).
//! When all six w are > 0 the same box also bounds zeta directly: `zeta` is then a
//! weighted mean of `z_k / w_k` with weights `b_k w_k > 0`, and each `z_k(t) / w_k(t)`
//! is a linear fraction of t with no pole in [0, 1], hence monotone; so
//! `zeta in [min, max]` of the six `z / w` values. Both are used.
//!
//! # Test 2: moving planes (Eq. 1)
//! For each end of the shutter (base `t = 0` with the triangle `q`, and `t = 1` with `r`)
//! the normal `n = (P1 - P0) x (P2 - P0)` of the base triangle in (x, y, w) is taken,
//! negated if `n_w < 0` (the paper's orientation rule). The paper's plane for maximum
//! depth is `Pi(t): n . p + d + v t = 0` with `d = -n . q_0` and
//! `v = -max_i (n . r_i + d)` (Eq. 1), i.e. every vertex satisfies
//! `n . p_i(t) <= M(t) = (1 - t) M_base + t M_other` with `M_base = n . q_0` and
//! `M_other = max_i n . r_i`: the function `n . p_i(t) - M(t)` is linear in t, `<= 0` at
//! both ends, hence `<= 0` in between, and so is any convex combination. The paper's
//! "similarly ... minimum depth" is the same construction with min:
//! `n . p_i(t) >= m(t) = lerp(m_base, m_other)`.
//!
//! Choices and deviations here:
//! - `M_base = max_i n . P_i` (and `m_base = min_i`) over the three base vertices
//!   instead of `n . q_0`: identical in exact arithmetic (the base vertices lie on the
//!   plane), and it also covers the f32 rounding of the normal.
//! - Defocus (the paper's extension is one sentence: "the depth estimations need to be
//!   done at the four corners of the two-dimensional bounding box of the lens shape ...
//!   the second test has to be disabled if the plane sweeps over any part of the lens").
//!   We make it rigorous in sheared coordinates, where each lens position (u, v) sees
//!   its own triangle `p'_k` and its own lens point at the origin: with one normal n for
//!   all lens positions, `n . p'_i = n . p_i + c_i (n_x u + n_y k v)`, which is affine in
//!   (u, v), so its maximum over the lens square is at a corner:
//!   `n . p_i + |c_i| (|n_x| + k |n_y|)`. The plane offsets `M_base`, `M_other` take
//!   that maximum (and m the minimum); the planes then hold for every lens position,
//!   and "the plane sweeps over the lens" becomes "the origin of the sheared space lies
//!   on the plane for some t": `M(t) = 0` for some t in [0, 1].
//! - The paper disables a plane that sweeps through the camera origin (lens); so do we,
//!   per plane: the max plane is used only if `M_base`, `M_other` have the same strict
//!   sign, the min plane only if `m_base`, `m_other` do.
//! - The paper evaluates the planes "at the appropriate tile corner using the time
//!   interval t^ from the tile test". This method has no time bound of its own and
//!   outputs the full t range, so t^ = [0, 1] (the range of M over the shutter is
//!   `[min, max]` of its two ends).
//!
//! **From a plane to a bound on w.** Along the ray of (x, y), `n . H = w_hit m(x, y)` with
//! `m(x, y) = n_x x + n_y y + n_w`, affine in (x, y): its range over the tile is spanned by
//! the four tile corners (`[m_lo, m_hi]`). The max plane gives `w m <= E` for some
//! `m in [m_lo, m_hi]`, `E in [E_lo, E_hi]` (E = M(t)), and `w > 0`:
//! - `m_lo > 0`: `w <= E_hi / m_lo` if `E_hi > 0`; if `E_hi <= 0` no hit is possible and
//!   the tile is empty.
//! - `m_lo <= 0` and `E_hi < 0`: only rays with `m < 0` can hit, at `w >= E_hi / m_lo`
//!   (empty if `m_lo = 0`).
//! - otherwise (`m_lo <= 0 <= E_hi`): nothing.
//!
//! The min plane gives `w m >= E'`, i.e. `w (-m) <= -E'`, the same rule. These cases
//! are the paper's "evaluate the plane equation at the appropriate tile corner" made
//! explicit, including the corners where the ray is parallel to the plane and the case
//! where the plane lies behind the lens point for the whole tile (the tile cannot see
//! the triangle, so the answer is Empty: this method can reject tiles).
//!
//! # Conversion from w to zeta
//! For any constants A, B write `z_k(t) = A w_k(t) + B + rho_k(t)`; `rho_k` is again
//! linear in t. Then `zeta = A + (B + rho_H) / w_hit` with `rho_H = sum b_k rho_k(t)` in
//! `[min, max]` of the six `rho` values at the shutter ends. So, with
//! `c in [B + rho_min, B + rho_max]` and `w_hit in [w_lo, w_hi]`, `zeta in A + c / w`,
//! whose extremes lie at the corners (or are infinite on a side when `w_lo = 0`). This is
//! exact for any A, B in real arithmetic; we take the line through the (w, z) of the
//! vertices with the smallest and the largest w (A = B = 0 if those w are equal). For a
//! perspective camera `z = A w + B` holds for every vertex up to the f32 rounding of
//! the clip transform, the residuals are tiny, and the conversion is the monotone map
//! `zeta = A + B / w` of the paper's w bounds. The result is intersected with the direct
//! zeta box of test 1 (when all w > 0). A side that stays unbounded is `-inf` / `+inf`;
//! `z = None` when both are.
//!
//! # Output, degenerate input
//! `TileBounds { u, v, t: full, z: Some([zeta_lo, zeta_hi]) }`, or Empty when the w or
//! zeta interval is empty. A plane whose normal or offsets are not finite, or whose
//! offsets vanish or change sign (sweeps the lens), is dropped; zero-area base
//! triangles give n = 0 and offsets 0, hence dropped. NaN anywhere in a bound drops that
//! bound. `disabled()` is `Some` only when the triangle holds non-finite numbers.
//!
//! # Where f32 can make it non-conservative
//! Every quantity (normal, dot products, corner evaluations of m, divisions, the A, B
//! fit and residuals) is rounded to f32 with no outward rounding, so each bound can be
//! off by a few ulps of the magnitudes involved: a depth exactly at a bound (e.g. a
//! static triangle at constant depth, where the interval is a single value) may fall
//! just outside it. The tile rejection `E_hi <= 0` / `m_lo = 0` near the horizon of the
//! plane (m close to 0) depends on the sign of rounded values. The cancellation in
//! `n = (P1 - P0) x (P2 - P0)` for slivers makes the normal inaccurate, but the offsets
//! are taken from the same rounded normal, so only their own rounding matters.
//!
//! # `nilsson2012-depth-safe`: the same bounds, rounded outward
//! The f32 bounds above are the published ones and stay as they are: the gate finds
//! depths 1e-8..1e-7 outside z^ at tile corners (4.2e-5 far from the origin, where the
//! plane terms are coordinates of 1e6 px times w), covered tiles culled at the f32
//! reject limit, and on screen-parallel triangles (all six w equal) an EMPTY interval:
//! the plane bound `fl(fl(n_w w) / n_w)` rounds one ulp below the vertex box `[w, w]`
//! and the intersection of the two culls every covered tile. `nilsson2012-depth-safe`
//! runs the same code (one generic algorithm, `Round = Nearest` or `Outward`) with every
//! rounded result that a bound depends on moved one f32 step outward.
//!
//! *Error analysis: directed steps (f32 interval arithmetic).* Every operation `a op b`
//! on f32 values rounds to nearest, so the exact result lies between the computed
//! `r = fl(a op b)` and its neighbour on the exact value's side, subnormals included
//! (their spacing is uniform, 2^-149). Hence `next_down(r) <= a op b <= next_up(r)`.
//! On overflow `r = +inf` means `a op b > f32::MAX`, so `next_down(+inf) = MAX` is a
//! valid lower bound and `next_up(+inf) = +inf` a valid upper one (the same for -inf);
//! a result of 0 steps to +-2^-149. The code writes `R::up(..)` around each result
//! that must be an upper bound and `R::dn(..)` around each lower one, and only ever
//! combines bounds monotonically: sums of same-sided bounds; products of exact f32
//! inputs (`n_x x`, `a w`, `k |n_y|`) or of a non-negative exact factor and a
//! non-negative upper bound (`|c| L`); a quotient `E_hi / m_lo` only where the rule
//! above is monotone in both (below). This encloses every exact value for every
//! finite input: huge, tiny (subnormal) and far-from-origin coordinates cost nothing
//! but a loose bound; overflow gives an infinite (unbounded) side; `inf - inf` gives
//! NaN, which the safe variant propagates through min / max (`f32::min` would skip it)
//! so that it drops the bound it appears in. Non-finite input disables the test (full
//! bounds), as in the original.
//!
//! What is enclosed, and why that is enough (real arithmetic on the f32 values):
//! - *The normal needs no rounding.* Every step of the planes holds for any vector n;
//!   the f32 cross product is used as an exact n, and the offsets and the plane value
//!   m are computed for that very n. So `M_base, M_other` are upper bounds of
//!   `max_i n . p_i + |c_i| (|n_x| + k |n_y|)` (dot products rounded up term by term,
//!   `L = |n_x| + k |n_y|` rounded up, `|c_i| L` rounded up), `m_base, m_other` lower
//!   bounds. The lens term is convex in t (`|c_i(t)|`), so the max plane still holds
//!   between the shutter ends (and the min plane, concave, too).
//! - *m over the tile*: each corner value `n_x x + n_y y + n_w` rounded down for
//!   `m_lo` (the least) and up for `m_hi`: `m_lo <= m(x, y) <= m_hi` on the tile.
//! - *w from a plane* (`w m <= E`, `E <= e_hi`, `m >= m_lo`, `w > 0`): if `m_lo > 0`
//!   then `w <= E / m <= e_hi / m_lo` (for `e_hi > 0`), rounded up; `e_hi <= 0` is no
//!   hit (`w m > 0 >= E`). If `m_lo <= 0` and `e_hi < 0`, a hit needs `m < 0` (empty when
//!   `m_lo = 0`) and then `w >= E / m >= e_hi / m_lo` (`|E| >= |e_hi|`,
//!   `|m| <= |m_lo|`), rounded down. The min plane is the same rule on `-m`, `-E`.
//! - *The vertex boxes*: the six w are exact; the six `z / w` rounded down for the
//!   least and up for the greatest.
//! - *The conversion* `zeta = A + c / w` holds for any f32 A (and B): `c = z - A w` of
//!   a vertex is enclosed by `dn(B + dn(dn(z - up(A w)) - B))` and the mirror image, the
//!   four (or two) quotients of `c_over_w` are rounded outward, and so is `A + q`.
//!
//! Every interval the tile test intersects is then an enclosure of the same exact hit
//! depth (or w) of every covered sample, so their intersection holds it and cannot be
//! empty while a covered sample exists: this is what the screen-parallel failure
//! needed, with no special case. Each Empty answer (`e_hi <= 0 < m_lo`,
//! `m_lo = 0 > e_hi`, `hi <= 0`, `lo > hi`, `z_lo > z_hi`) compares enclosures, so it
//! is a proof that the tile holds no covered sample. No correction beyond rounding is
//! needed: the derivation above holds in real arithmetic for any f32 normal, A and B.
//!
//! *Cost*: a step after each operation (the corner values of m twice, once per
//! side); the interval grows by a few ulps of the terms it is computed from, which far
//! from the origin (terms of 1e6 px times w) is the same 1e-5 the original misses by.
//! No sample test efficiency figure sees it (z^ is a depth test; the tile reject moves
//! by ulps).

use super::*;
use crate::bounds::arith::{tile_of, End, F32Arith, Plain, TriOf};
use crate::bounds::round::{max_g, min_g, Nearest, Outward, Round};
use std::marker::PhantomData;

// Every bound below is written once over [`F32Arith`], with `R::up` around a result
// that must not fall below the exact value and `R::dn` around one that must not exceed
// it ([`Round`]): with `Nearest` both are the identity and the code is the published f32
// computation, operation for operation; with `Outward` each is one f32 step outward.
// The same code is the method the gate runs ([`Plain`]) and its SMT-LIB 2 encoding.

/// One moving plane with fixed normal n in (x, y, w): for every vertex, lens position
/// and time, `n . p' <= max(e)` over the shutter (max plane) or `>= min(e)` (min plane).
/// Its numbers are values of some [`F32Arith`].
#[derive(Clone, Debug)]
pub struct Plane<F, B> {
    pub n: [F; 3],
    /// The max plane's offsets at the two shutter ends, used when `upper_on`.
    pub upper: [F; 2],
    pub upper_on: B,
    /// The min plane's offsets at the two shutter ends, used when `lower_on`.
    pub lower: [F; 2],
    pub lower_on: B,
}

/// What one plane says about w over a tile: no hit is possible (`empty`), or
/// `lo <= w <= hi` (lo >= 0, hi may be +inf).
#[derive(Clone, Debug)]
pub struct WBound<F, B> {
    pub empty: B,
    pub lo: F,
    pub hi: F,
}

/// `w m <= E` for some `m in [m_lo, m_hi]`, `E in [e_lo, e_hi]`, with `w > 0`.
#[inline(always)]
pub fn w_from<R: Round, A: F32Arith>(ar: &A, m_lo: &A::F, e_hi: &A::F) -> WBound<A::F, A::B> {
    let (m_lo, e_hi) = (&ar.pin(m_lo, End::Lo, W_LEMMA), &ar.pin(e_hi, End::Hi, W_LEMMA));
    let (zero, inf) = (ar.lit(0.0), ar.lit(f32::INFINITY));
    let fin = ar.and(&ar.is_finite(m_lo), &ar.is_finite(e_hi));
    let pos = ar.and(&fin, &ar.gt(m_lo, &zero));
    let below = ar.and(&fin, &ar.lt(e_hi, &zero));
    // m_lo > 0: e_hi <= 0 is no hit; else w <= e_hi / m_lo. m_lo <= 0 > e_hi: a hit
    // needs m < 0, none when m_lo = 0 (Empty; the lower end is then left at 0), and
    // with m_lo < 0, w >= e_hi / m_lo.
    let neg = ar.and(&below, &ar.lt(m_lo, &zero));
    let empty = ar.or(&ar.and(&pos, &ar.le(e_hi, &zero)), &ar.and(&below, &ar.eq(m_lo, &zero)));
    let q = ar.div(e_hi, m_lo);
    WBound { empty, lo: ar.select(&neg, &R::dn(ar, &q), &zero), hi: ar.select(&pos, &R::up(ar, &q), &inf) }
}

/// The lemma of the pins of [`w_from`]: for `w > 0`, `m >= m_lo` and `E <= e_hi`,
/// `w m <= E` gives `w <= e_hi / m_lo` when `m_lo > 0`, and `w >= e_hi / m_lo` when
/// `m_lo < 0` and `e_hi < 0` (checked by z3 in real arithmetic, `cullproof proofs`).
pub const W_LEMMA: &str = "w m <= E bounds w by e_hi / m_lo for every m >= m_lo, E <= e_hi";

fn sub3<A: F32Arith>(ar: &A, a: &[A::F; 3], b: &[A::F; 3]) -> [A::F; 3] {
    [0, 1, 2].map(|i| ar.sub(&a[i], &b[i]))
}

fn cross<A: F32Arith>(ar: &A, p: &[A::F; 3], q: &[A::F; 3]) -> [A::F; 3] {
    let d = |a: usize, b: usize| ar.sub(&ar.mul(&p[a], &q[b]), &ar.mul(&p[b], &q[a]));
    [d(1, 2), d(2, 0), d(0, 1)]
}

/// `a . b` rounded up (`R::up` after each operation): `>=` the exact dot product.
fn dot_up<R: Round, A: F32Arith>(ar: &A, a: &[A::F; 3], b: &[A::F; 3]) -> A::F {
    let m = |i: usize| R::up(ar, &ar.mul(&a[i], &b[i]));
    R::up(ar, &ar.add(&R::up(ar, &ar.add(&m(0), &m(1))), &m(2)))
}

/// `a . b` rounded down: `<=` the exact dot product.
fn dot_dn<R: Round, A: F32Arith>(ar: &A, a: &[A::F; 3], b: &[A::F; 3]) -> A::F {
    let m = |i: usize| R::dn(ar, &ar.mul(&a[i], &b[i]));
    R::dn(ar, &ar.add(&R::dn(ar, &ar.add(&m(0), &m(1))), &m(2)))
}

/// The derivation's step that puts a covered sample's w in the tile's w range.
pub const W_RANGE: &str = "derivation: a covered sample's w lies in the tile's w range (nilsson2012_depth.rs)";
/// The derivation's step that writes a covered sample's depth as a + c / w.
pub const C_RANGE: &str =
    "derivation: a covered sample's depth is a + c / w for a c in the residuals' range (nilsson2012_depth.rs)";

/// Why a plane may be used or dropped on any condition.
pub const PLANE_ON_CHOICE: &str =
    "a plane's bound on w holds for every normal and offsets; dropping it only culls less";

/// Why the plane's normal may be any f32 vector (see [`F32Arith::choose`]).
pub const NORMAL_CHOICE: &str = "the planes' offsets are bounded for the normal computed, whatever it is";
/// Why the depth line may be any f32 line.
pub const LINE_CHOICE: &str = "the residuals about the (w, z) line are bounded for the line computed, whatever it is";

/// Same strict sign, both finite.
fn same_sign<A: F32Arith>(ar: &A, a: &A::F, b: &A::F) -> A::B {
    let zero = ar.lit(0.0);
    let fin = ar.and(&ar.is_finite(a), &ar.is_finite(b));
    let pos = ar.and(&ar.gt(a, &zero), &ar.gt(b, &zero));
    let neg = ar.and(&ar.lt(a, &zero), &ar.lt(b, &zero));
    ar.and(&fin, &ar.or(&pos, &neg))
}

impl<F: Clone, B: Clone> Plane<F, B> {
    /// The planes with the normal of the triangle `base` (a shutter end, with CoC `cb`),
    /// bounding the triangle at that end and at the other end `oth` (CoC `co`).
    fn new<R: Round, A: F32Arith<F = F, B = B>>(
        ar: &A,
        (base, cb): (&[[F; 3]; 3], &[F; 3]),
        (oth, co): (&[[F; 3]; 3], &[F; 3]),
        k: &F,
    ) -> Self {
        // Any f32 normal will do (the offsets below are taken for this very n), so
        // n needs no outward rounding; it is turned to face +w.
        let n = cross(ar, &sub3(ar, &base[1], &base[0]), &sub3(ar, &base[2], &base[0]));
        let n = n.map(|x| ar.choose(&x, NORMAL_CHOICE));
        let flip = ar.lt(&n[2], &ar.lit(0.0));
        let n = n.map(|x| ar.select(&flip, &ar.neg(&x), &x));
        let lens = R::up(ar, &ar.add(&ar.abs(&n[0]), &R::up(ar, &ar.mul(k, &ar.abs(&n[1])))));
        let ext = |pts: &[[F; 3]; 3], c: &[F; 3]| -> (F, F) {
            let mut hi = ar.lit(f32::NEG_INFINITY);
            let mut lo = ar.lit(f32::INFINITY);
            for i in 0..3 {
                let s = R::up(ar, &ar.mul(&ar.abs(&c[i]), &lens));
                hi = max_g::<R, A>(ar, &hi, &R::up(ar, &ar.add(&dot_up::<R, A>(ar, &n, &pts[i]), &s)));
                lo = min_g::<R, A>(ar, &lo, &R::dn(ar, &ar.sub(&dot_dn::<R, A>(ar, &n, &pts[i]), &s)));
            }
            (lo, hi)
        };
        let (lb, hb) = ext(base, cb);
        let (lo, ho) = ext(oth, co);
        let finite = ar.all(&n.each_ref().map(|x| ar.is_finite(x)));
        Plane {
            upper_on: ar.choose_truth(&ar.and(&finite, &same_sign(ar, &hb, &ho)), PLANE_ON_CHOICE),
            lower_on: ar.choose_truth(&ar.and(&finite, &same_sign(ar, &lb, &lo)), PLANE_ON_CHOICE),
            n,
            upper: [hb, ho],
            lower: [lb, lo],
        }
    }

    /// The range of `m = n_x x + n_y y + n_w` over the tile `[x0, y0, x1, y1]` (its four
    /// corners): the least corner value rounded down, the greatest rounded up.
    #[inline(always)]
    fn m_range<R: Round, A: F32Arith<F = F, B = B>>(&self, ar: &A, tile: &[F; 4]) -> (F, F) {
        let n = &self.n;
        let lo = |x: &F, y: &F| {
            R::dn(ar, &ar.add(&R::dn(ar, &ar.add(&R::dn(ar, &ar.mul(&n[0], x)), &R::dn(ar, &ar.mul(&n[1], y)))), &n[2]))
        };
        let hi = |x: &F, y: &F| {
            R::up(ar, &ar.add(&R::up(ar, &ar.add(&R::up(ar, &ar.mul(&n[0], x)), &R::up(ar, &ar.mul(&n[1], y)))), &n[2]))
        };
        let [x0, y0, x1, y1] = tile;
        let corners = [(x0, y0), (x1, y0), (x0, y1), (x1, y1)];
        let (mut m_lo, mut m_hi) = (ar.lit(f32::INFINITY), ar.lit(f32::NEG_INFINITY));
        for (x, y) in corners {
            m_lo = min_g::<R, A>(ar, &m_lo, &lo(x, y));
            m_hi = max_g::<R, A>(ar, &m_hi, &hi(x, y));
        }
        (m_lo, m_hi)
    }

    /// The bounds on w of the max and the min plane over the tile (t^ = [0, 1]).
    #[inline(always)]
    fn w_bounds<R: Round, A: F32Arith<F = F, B = B>>(&self, ar: &A, tile: &[F; 4]) -> [WBound<F, B>; 2] {
        let (m_lo, m_hi) = self.m_range::<R, A>(ar, tile);
        // A NaN end of m, or a plane not enabled: no bound.
        let unknown = ar.or(&ar.is_nan(&m_lo), &ar.is_nan(&m_hi));
        let or_none = |on: &B, b: WBound<F, B>| {
            let use_it = ar.and(on, &ar.not(&unknown));
            WBound {
                empty: ar.and(&use_it, &b.empty),
                lo: ar.select(&use_it, &b.lo, &ar.lit(0.0)),
                hi: ar.select(&use_it, &b.hi, &ar.lit(f32::INFINITY)),
            }
        };
        // max plane: w m <= M(t), M in [min, max] of its ends.
        let up = w_from::<R, A>(ar, &m_lo, &ar.max(&self.upper[0], &self.upper[1]));
        // min plane: w m >= m(t)  <=>  w (-m) <= -m(t).
        let lo = w_from::<R, A>(ar, &ar.neg(&m_hi), &ar.neg(&ar.min(&self.lower[0], &self.lower[1])));
        [or_none(&self.upper_on, up), or_none(&self.lower_on, lo)]
    }
}

/// The setup of `nilsson2012-depth` (`R = Nearest`) or `nilsson2012-depth-safe`
/// (`R = Outward`), its numbers values of some [`F32Arith`].
#[derive(Clone, Debug)]
pub struct Setup<F, B> {
    pub planes: [Plane<F, B>; 2],
    /// w range of the six vertices (test 1).
    pub w_box: [F; 2],
    /// zeta range of the six vertices, used when all w > 0 (`zeta_on`; test 1 in zeta).
    pub zeta_box: [F; 2],
    pub zeta_on: B,
    /// Conversion: zeta = a + c / w with c in [c_lo, c_hi].
    pub a: F,
    pub c: [F; 2],
    /// Some number is not finite: the test is off.
    pub disabled: B,
}

/// `c / w` over `c in [c0, c1]`, `w in [w0, w1]`, `0 <= w0 <= w1 < inf`, `w > 0`.
#[inline(always)]
fn c_over_w<R: Round, A: F32Arith>(ar: &A, c: &[A::F; 2], w: &[A::F; 2]) -> [A::F; 2] {
    let zero = ar.lit(0.0);
    let q = [ar.div(&c[0], &w[0]), ar.div(&c[0], &w[1]), ar.div(&c[1], &w[0]), ar.div(&c[1], &w[1])];
    let (lo, hi) = if R::GUARD {
        // By signs (w0 > 0 here): the least quotient is c0 / w1 when c0 >= 0, else
        // c0 / w0; the greatest c1 / w0 when c1 >= 0, else c1 / w1. Rounding and the
        // steps are monotone, so these are the least and the greatest of the four
        // quotients rounded outward, bit for bit; NaN when one of the four is NaN.
        let nan = ar.any(&q.each_ref().map(|x| ar.is_nan(x)));
        let lo = ar.select(&ar.le(&zero, &c[0]), &R::dn(ar, &q[1]), &R::dn(ar, &q[0]));
        let hi = ar.select(&ar.le(&zero, &c[1]), &R::up(ar, &q[2]), &R::up(ar, &q[3]));
        let none = ar.lit(f32::NAN);
        (ar.select(&nan, &none, &lo), ar.select(&nan, &none, &hi))
    } else {
        // The published method: the least and greatest of the four (a NaN one skipped).
        let (mut lo, mut hi) = (ar.lit(f32::INFINITY), ar.lit(f32::NEG_INFINITY));
        for q in &q {
            lo = min_g::<R, A>(ar, &lo, &R::dn(ar, q));
            hi = max_g::<R, A>(ar, &hi, &R::up(ar, q));
        }
        (lo, hi)
    };
    // w0 = 0: only the far end bounds the quotient, on the side c keeps its sign.
    let lo0 = ar.select(&ar.le(&zero, &c[0]), &R::dn(ar, &q[1]), &ar.lit(f32::NEG_INFINITY));
    let hi0 = ar.select(&ar.le(&c[1], &zero), &R::up(ar, &q[3]), &ar.lit(f32::INFINITY));
    let pos = ar.gt(&w[0], &zero);
    [ar.select(&pos, &lo, &lo0), ar.select(&pos, &hi, &hi0)]
}

/// The setup over any [`F32Arith`].
pub fn setup_of<R: Round, A: F32Arith>(ar: &A, tri: &TriOf<A::F>) -> Setup<A::F, A::B> {
    let nums: Vec<A::B> = tri
        .q
        .iter()
        .chain(tri.r.iter())
        .flatten()
        .chain(tri.c0.iter())
        .chain(tri.c1.iter())
        .chain(std::iter::once(&tri.k))
        .map(|v| ar.is_finite(v))
        .collect();
    let xyw = |p: &[A::F; 4]| [p[0].clone(), p[1].clone(), p[3].clone()];
    let (q, r) = (tri.q.each_ref().map(xyw), tri.r.each_ref().map(xyw));
    let planes = [
        Plane::new::<R, A>(ar, (&q, &tri.c0), (&r, &tri.c1), &tri.k),
        Plane::new::<R, A>(ar, (&r, &tri.c1), (&q, &tri.c0), &tri.k),
    ];
    let verts: Vec<&[A::F; 4]> = tri.q.iter().chain(tri.r.iter()).collect();
    let zero = ar.lit(0.0);
    let (mut w_lo, mut w_hi) = (ar.lit(f32::INFINITY), ar.lit(f32::NEG_INFINITY));
    let (mut z_lo, mut z_hi) = (ar.lit(f32::INFINITY), ar.lit(f32::NEG_INFINITY));
    let mut pos = vec![];
    for p in &verts {
        w_lo = ar.min(&w_lo, &p[3]);
        w_hi = ar.max(&w_hi, &p[3]);
        pos.push(ar.gt(&p[3], &zero));
        let zw = ar.div(&p[2], &p[3]);
        z_lo = min_g::<R, A>(ar, &z_lo, &R::dn(ar, &zw));
        z_hi = max_g::<R, A>(ar, &z_hi, &R::up(ar, &zw));
    }
    // The (w, z) line through the vertices of least and greatest w (the first one met).
    let pick = |least: bool| {
        let mut best = verts[0].clone();
        for p in &verts[1..] {
            let b = if least { ar.lt(&p[3], &best[3]) } else { ar.gt(&p[3], &best[3]) };
            best = [0, 1, 2, 3].map(|i| ar.select(&b, &p[i], &best[i]));
        }
        best
    };
    let (lo_v, hi_v) = (pick(true), pick(false));
    let slope = ar.div(&ar.sub(&hi_v[2], &lo_v[2]), &ar.sub(&hi_v[3], &lo_v[3]));
    let off = ar.sub(&lo_v[2], &ar.mul(&slope, &lo_v[3]));
    let (slope, off) = (ar.choose(&slope, LINE_CHOICE), ar.choose(&off, LINE_CHOICE));
    let line = ar.all(&[ar.gt(&hi_v[3], &lo_v[3]), ar.is_finite(&slope), ar.is_finite(&off)]);
    let (a, bb) = (ar.select(&line, &slope, &zero), ar.select(&line, &off, &zero));
    // Residuals z - a w - bb, rounded down for the least and up for the greatest (a
    // and bb are any f32 values: the conversion is exact for every A, B).
    let (mut res_lo, mut res_hi) = (ar.lit(f32::INFINITY), ar.lit(f32::NEG_INFINITY));
    for p in &verts {
        let lo = R::dn(ar, &ar.sub(&R::dn(ar, &ar.sub(&p[2], &R::up(ar, &ar.mul(&a, &p[3])))), &bb));
        let hi = R::up(ar, &ar.sub(&R::up(ar, &ar.sub(&p[2], &R::dn(ar, &ar.mul(&a, &p[3])))), &bb));
        res_lo = min_g::<R, A>(ar, &res_lo, &lo);
        res_hi = max_g::<R, A>(ar, &res_hi, &hi);
    }
    let mut c = [R::dn(ar, &ar.add(&bb, &res_lo)), R::up(ar, &ar.add(&bb, &res_hi))];
    if R::GUARD {
        let nan = ar.or(&ar.is_nan(&c[0]), &ar.is_nan(&c[1]));
        c = [ar.select(&nan, &ar.lit(f32::NEG_INFINITY), &c[0]), ar.select(&nan, &ar.lit(f32::INFINITY), &c[1])];
    }
    Setup {
        planes,
        w_box: [w_lo, w_hi],
        zeta_box: [z_lo, z_hi],
        zeta_on: ar.all(&pos),
        a,
        c,
        disabled: ar.not(&ar.all(&nums)),
    }
}

/// The tile answer over any [`F32Arith`] for the tile `[x0, y0, x1, y1]`:
/// `(nonempty, z)`, the tile Empty when `nonempty` is false (the tile reject); `z` the
/// depth bounds (infinite ends: none on that side; all infinite when the test is off).
#[inline(always)]
pub fn tile_answer<R: Round, A: F32Arith>(ar: &A, s: &Setup<A::F, A::B>, tile: &[A::F; 4]) -> (A::B, [A::F; 2]) {
    let (zero, inf, ninf) = (ar.lit(0.0), ar.lit(f32::INFINITY), ar.lit(f32::NEG_INFINITY));
    // w: the box, w > 0, and the planes.
    let (mut lo, mut hi) = (ar.max(&s.w_box[0], &zero), s.w_box[1].clone());
    let mut empty = ar.truth(false);
    for p in &s.planes {
        for wb in p.w_bounds::<R, A>(ar, tile) {
            empty = ar.or(&empty, &wb.empty);
            lo = ar.select(&ar.is_nan(&wb.lo), &lo, &ar.max(&lo, &wb.lo));
            hi = ar.select(&ar.is_nan(&wb.hi), &hi, &ar.min(&hi, &wb.hi));
        }
    }
    let empty = ar.any(&[empty, ar.is_nan(&hi), ar.le(&hi, &zero), ar.gt(&lo, &hi)]);
    // Every covered sample's w lies in [lo, hi] (the vertices' box, w > 0, the planes),
    // and its depth is a + c / w for a c in s.c (the method's derivation, above).
    let w = ar.pin_range(&[lo, hi], true, W_RANGE);
    let c = ar.pin_range(&s.c, false, C_RANGE);
    let q = c_over_w::<R, A>(ar, &c, &w);
    let (z0, z1) = (R::dn(ar, &ar.add(&s.a, &q[0])), R::up(ar, &ar.add(&s.a, &q[1])));
    let (z0, z1) = (ar.select(&ar.is_nan(&z0), &ninf, &z0), ar.select(&ar.is_nan(&z1), &inf, &z1));
    let z0 = ar.select(&s.zeta_on, &ar.max(&z0, &s.zeta_box[0]), &z0);
    let z1 = ar.select(&s.zeta_on, &ar.min(&z1, &s.zeta_box[1]), &z1);
    let empty = ar.or(&empty, &ar.gt(&z0, &z1));
    let nonempty = ar.or(&s.disabled, &ar.not(&empty));
    (nonempty, [ar.select(&s.disabled, &ninf, &z0), ar.select(&s.disabled, &inf, &z1)])
}

/// The prepared f32 method.
struct Prep<R> {
    s: Setup<f32, bool>,
    round: PhantomData<fn() -> R>,
}

impl<R: Round> Prepared for Prep<R> {
    fn tile(&self, tile: &Tile) -> TileResult {
        let (nonempty, z) = tile_answer::<R, Plain>(&Plain, &self.s, &tile_of(tile));
        if !nonempty {
            return TileResult::Empty;
        }
        let mut b = TileBounds::full();
        if z[0] > f32::NEG_INFINITY || z[1] < f32::INFINITY {
            b.z = Some(z);
        }
        TileResult::Bounds(b)
    }
    fn disabled(&self) -> Option<&'static str> {
        self.s.disabled.then_some("non-finite triangle data")
    }
}

/// nilsson2012-depth (`Nearest`) or nilsson2012-depth-safe (`Outward`).
pub(crate) struct Nilsson2012Depth<R> {
    pub(crate) info: &'static MethodInfo,
    pub(crate) round: PhantomData<fn() -> R>,
}

pub(crate) static INFO: MethodInfo = MethodInfo {
    id: "nilsson2012-depth",
    source: "Nilsson et al. 2012, Design and Novel Uses of Higher-Dimensional Rasterization, HPG 2012, \
             Appendix A (moving bounding box; moving planes, Eq. 1, Figure 18)",
    reconstruction: false,
    dims: &[Dims::Static, Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: false, time: false, depth: true, per_sample: false },
};

/// The published setup (round to nearest).
#[cfg(test)]
fn prepare(tri: &Triangle) -> Setup<f32, bool> {
    setup_of::<Nearest, Plain>(&Plain, &TriOf::of(tri))
}

impl<R: Round> Method for Nilsson2012Depth<R> {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(Prep::<R> { s: setup_of::<R, Plain>(&Plain, &TriOf::of(tri)), round: PhantomData })
    }
}

pub static METHOD: &dyn Method = &Nilsson2012Depth::<Nearest> { info: &INFO, round: PhantomData };

static INFO_SAFE: MethodInfo = MethodInfo {
    id: "nilsson2012-depth-safe",
    source: "Nilsson et al. 2012, Design and Novel Uses of Higher-Dimensional Rasterization, HPG 2012, \
             Appendix A (moving bounding box; moving planes, Eq. 1, Figure 18); every bound rounded \
             outward, one f32 step after each rounded operation (error analysis in this file)",
    ..INFO
};

/// `nilsson2012-depth-safe`: the same bounds rounded outward (see the module's error
/// analysis).
pub static METHOD_SAFE: &dyn Method = &Nilsson2012Depth::<Outward> { info: &INFO_SAFE, round: PhantomData };

#[cfg(test)]
mod tests;
