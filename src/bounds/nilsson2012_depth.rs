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
//! runs the same code (one generic algorithm, `Round = Near` or `Outward`) with every
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
use std::marker::PhantomData;

/// How each rounded f32 result is taken: as it comes (`Near`, the published method) or
/// moved one f32 step outward (`Outward`, `nilsson2012-depth-safe`). Every bound below
/// is written once, with `R::up` around a result that must not fall below the exact
/// value and `R::dn` around one that must not exceed it; with `Near` both are the
/// identity and the code is the published f32 computation, operation for operation.
trait Round: Send + Sync + 'static {
    /// True for the outward variant: NaN also propagates through min / max.
    const SAFE: bool;
    fn up(x: f32) -> f32;
    fn dn(x: f32) -> f32;
}

/// Round to nearest, nothing more (`nilsson2012-depth`).
struct Near;

/// One step outward after each rounded operation (`nilsson2012-depth-safe`).
struct Outward;

impl Round for Near {
    const SAFE: bool = false;
    #[inline(always)]
    fn up(x: f32) -> f32 {
        x
    }
    #[inline(always)]
    fn dn(x: f32) -> f32 {
        x
    }
}

impl Round for Outward {
    const SAFE: bool = true;
    #[inline(always)]
    fn up(x: f32) -> f32 {
        x.next_up()
    }
    #[inline(always)]
    fn dn(x: f32) -> f32 {
        x.next_down()
    }
}

/// `a.min(b)`; for the safe variant a NaN operand gives NaN (an unknown value must not
/// be skipped as `f32::min` does).
fn min_r<R: Round>(a: f32, b: f32) -> f32 {
    if R::SAFE && (a.is_nan() || b.is_nan()) {
        f32::NAN
    } else {
        a.min(b)
    }
}

/// `a.max(b)`, NaN-propagating for the safe variant (see [`min_r`]).
fn max_r<R: Round>(a: f32, b: f32) -> f32 {
    if R::SAFE && (a.is_nan() || b.is_nan()) {
        f32::NAN
    } else {
        a.max(b)
    }
}

/// One moving plane with fixed normal n in (x, y, w): for every vertex, lens position
/// and time, `n . p' <= max(e)` over the shutter (max plane) or `>= min(e)` (min plane).
#[derive(Clone, Copy, Debug)]
struct Plane {
    n: [f32; 3],
    /// The max plane's offsets at the two shutter ends, if it is enabled.
    upper: Option<[f32; 2]>,
    /// The min plane's offsets at the two shutter ends, if it is enabled.
    lower: Option<[f32; 2]>,
}

/// What one plane says about w over a tile.
#[derive(Clone, Copy, Debug, PartialEq)]
enum WBound {
    /// No hit is possible.
    Empty,
    /// `lo <= w <= hi` (lo >= 0, hi may be +inf).
    Range(f32, f32),
}

/// `w m <= E` for some `m in [m_lo, m_hi]`, `E in [e_lo, e_hi]`, with `w > 0`.
fn w_from<R: Round>(m_lo: f32, e_hi: f32) -> WBound {
    if !(m_lo.is_finite() && e_hi.is_finite()) {
        return WBound::Range(0.0, f32::INFINITY);
    }
    if m_lo > 0.0 {
        if e_hi <= 0.0 {
            WBound::Empty
        } else {
            WBound::Range(0.0, R::up(e_hi / m_lo))
        }
    } else if e_hi < 0.0 {
        if m_lo == 0.0 {
            WBound::Empty
        } else {
            WBound::Range(R::dn(e_hi / m_lo), f32::INFINITY)
        }
    } else {
        WBound::Range(0.0, f32::INFINITY)
    }
}

fn sub3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(p: [f32; 3], q: [f32; 3]) -> [f32; 3] {
    [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]]
}

/// `a . b` rounded up (`R::up` after each operation): `>=` the exact dot product.
fn dot_up<R: Round>(a: [f32; 3], b: [f32; 3]) -> f32 {
    R::up(R::up(R::up(a[0] * b[0]) + R::up(a[1] * b[1])) + R::up(a[2] * b[2]))
}

/// `a . b` rounded down: `<=` the exact dot product.
fn dot_dn<R: Round>(a: [f32; 3], b: [f32; 3]) -> f32 {
    R::dn(R::dn(R::dn(a[0] * b[0]) + R::dn(a[1] * b[1])) + R::dn(a[2] * b[2]))
}

/// Same strict sign, both finite.
fn same_sign(a: f32, b: f32) -> bool {
    (a > 0.0 && b > 0.0 && b.is_finite() && a.is_finite()) || (a < 0.0 && b < 0.0 && a.is_finite() && b.is_finite())
}

impl Plane {
    /// The planes with the normal of the triangle `base` (a shutter end, with CoC `cb`),
    /// bounding the triangle at that end and at the other end `oth` (CoC `co`).
    fn new<R: Round>(base: [[f32; 3]; 3], cb: [f32; 3], oth: [[f32; 3]; 3], co: [f32; 3], k: f32) -> Plane {
        // Any f32 normal will do (the offsets below are taken for this very n), so
        // n needs no outward rounding.
        let mut n = cross(sub3(base[1], base[0]), sub3(base[2], base[0]));
        if n[2] < 0.0 {
            n = n.map(|x| -x);
        }
        let lens = R::up(n[0].abs() + R::up(k * n[1].abs()));
        let ext = |pts: [[f32; 3]; 3], c: [f32; 3]| -> (f32, f32) {
            let mut hi = f32::NEG_INFINITY;
            let mut lo = f32::INFINITY;
            for i in 0..3 {
                let s = R::up(c[i].abs() * lens);
                hi = max_r::<R>(hi, R::up(dot_up::<R>(n, pts[i]) + s));
                lo = min_r::<R>(lo, R::dn(dot_dn::<R>(n, pts[i]) - s));
            }
            (lo, hi)
        };
        let (lb, hb) = ext(base, cb);
        let (lo, ho) = ext(oth, co);
        let finite = n.iter().all(|x| x.is_finite());
        Plane {
            n,
            upper: (finite && same_sign(hb, ho)).then_some([hb, ho]),
            lower: (finite && same_sign(lb, lo)).then_some([lb, lo]),
        }
    }

    /// The range of `m = n_x x + n_y y + n_w` over the tile (its four corners): the
    /// least corner value rounded down, the greatest rounded up.
    fn m_range<R: Round>(&self, tile: &Tile) -> (f32, f32) {
        let n = self.n;
        let lo = |x: f32, y: f32| R::dn(R::dn(R::dn(n[0] * x) + R::dn(n[1] * y)) + n[2]);
        let hi = |x: f32, y: f32| R::up(R::up(R::up(n[0] * x) + R::up(n[1] * y)) + n[2]);
        let corners = [(tile.x0, tile.y0), (tile.x1, tile.y0), (tile.x0, tile.y1), (tile.x1, tile.y1)];
        (
            corners.iter().map(|&(x, y)| lo(x, y)).fold(f32::INFINITY, min_r::<R>),
            corners.iter().map(|&(x, y)| hi(x, y)).fold(f32::NEG_INFINITY, max_r::<R>),
        )
    }

    /// The bounds on w of the max and the min plane over the tile (t^ = [0, 1]).
    fn w_bounds<R: Round>(&self, tile: &Tile) -> [WBound; 2] {
        let none = WBound::Range(0.0, f32::INFINITY);
        let (m_lo, m_hi) = self.m_range::<R>(tile);
        if m_lo.is_nan() || m_hi.is_nan() {
            return [none, none];
        }
        // max plane: w m <= M(t), M in [min, max] of its ends.
        let up = self.upper.map_or(none, |e| w_from::<R>(m_lo, e[0].max(e[1])));
        // min plane: w m >= m(t)  <=>  w (-m) <= -m(t).
        let lo = self.lower.map_or(none, |e| w_from::<R>(-m_hi, -(e[0].min(e[1]))));
        [up, lo]
    }
}

#[derive(Debug)]
struct Prep<R> {
    planes: [Plane; 2],
    /// w range of the six vertices (test 1).
    w_box: [f32; 2],
    /// zeta range of the six vertices when all w > 0 (test 1 in zeta).
    zeta_box: Option<[f32; 2]>,
    /// Conversion: zeta = a + c / w with c in [c_lo, c_hi].
    a: f32,
    c: [f32; 2],
    disabled: Option<&'static str>,
    round: PhantomData<fn() -> R>,
}

/// `c / w` over `c in [c0, c1]`, `w in [w0, w1]`, `0 <= w0 <= w1 < inf`, `w > 0`.
fn c_over_w<R: Round>(c: [f32; 2], w: [f32; 2]) -> [f32; 2] {
    if w[0] > 0.0 {
        let q = [(c[0], w[0]), (c[0], w[1]), (c[1], w[0]), (c[1], w[1])];
        return [
            q.iter().map(|&(c, w)| R::dn(c / w)).fold(f32::INFINITY, min_r::<R>),
            q.iter().map(|&(c, w)| R::up(c / w)).fold(f32::NEG_INFINITY, max_r::<R>),
        ];
    }
    let lo = if c[0] >= 0.0 { R::dn(c[0] / w[1]) } else { f32::NEG_INFINITY };
    let hi = if c[1] <= 0.0 { R::up(c[1] / w[1]) } else { f32::INFINITY };
    [lo, hi]
}

impl<R: Round> Prepared for Prep<R> {
    fn tile(&self, tile: &Tile) -> TileResult {
        let mut b = TileBounds::full();
        if self.disabled.is_some() {
            return TileResult::Bounds(b);
        }
        // w: the box, w > 0, and the planes.
        let (mut lo, mut hi) = (self.w_box[0].max(0.0), self.w_box[1]);
        for p in &self.planes {
            for wb in p.w_bounds::<R>(tile) {
                match wb {
                    WBound::Empty => return TileResult::Empty,
                    WBound::Range(l, h) => {
                        if !l.is_nan() {
                            lo = lo.max(l);
                        }
                        if !h.is_nan() {
                            hi = hi.min(h);
                        }
                    }
                }
            }
        }
        if hi.is_nan() || hi <= 0.0 || lo > hi {
            return TileResult::Empty;
        }
        let q = c_over_w::<R>(self.c, [lo, hi]);
        let mut z = [R::dn(self.a + q[0]), R::up(self.a + q[1])];
        if z[0].is_nan() {
            z[0] = f32::NEG_INFINITY;
        }
        if z[1].is_nan() {
            z[1] = f32::INFINITY;
        }
        if let Some(zb) = self.zeta_box {
            z = [z[0].max(zb[0]), z[1].min(zb[1])];
        }
        if z[0] > z[1] {
            return TileResult::Empty;
        }
        if z[0] > f32::NEG_INFINITY || z[1] < f32::INFINITY {
            b.z = Some(z);
        }
        TileResult::Bounds(b)
    }
    fn disabled(&self) -> Option<&'static str> {
        self.disabled
    }
}

/// nilsson2012-depth (`Near`) or nilsson2012-depth-safe (`Outward`).
struct Nilsson2012Depth<R> {
    info: &'static MethodInfo,
    round: PhantomData<fn() -> R>,
}

static INFO: MethodInfo = MethodInfo {
    id: "nilsson2012-depth",
    source: "Nilsson et al. 2012, Design and Novel Uses of Higher-Dimensional Rasterization, HPG 2012, \
             Appendix A (moving bounding box; moving planes, Eq. 1, Figure 18)",
    reconstruction: false,
    dims: &[Dims::Static, Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: false, time: false, depth: true, per_sample: false },
};

fn prepare_with<R: Round>(tri: &Triangle) -> Prep<R> {
    let xyw = |p: [f32; 4]| [p[0], p[1], p[3]];
    let finite =
        tri.q.iter().chain(tri.r.iter()).flatten().chain(tri.c0.iter()).chain(tri.c1.iter()).all(|v| v.is_finite())
            && tri.k.is_finite();
    let (q, r) = (tri.q.map(xyw), tri.r.map(xyw));
    let planes = [Plane::new::<R>(q, tri.c0, r, tri.c1, tri.k), Plane::new::<R>(r, tri.c1, q, tri.c0, tri.k)];
    let verts: Vec<[f32; 4]> = tri.q.iter().chain(tri.r.iter()).cloned().collect();
    let w_box = [
        verts.iter().map(|p| p[3]).fold(f32::INFINITY, f32::min),
        verts.iter().map(|p| p[3]).fold(f32::NEG_INFINITY, f32::max),
    ];
    let zeta_box = verts.iter().all(|p| p[3] > 0.0).then(|| {
        [
            verts.iter().map(|p| R::dn(p[2] / p[3])).fold(f32::INFINITY, min_r::<R>),
            verts.iter().map(|p| R::up(p[2] / p[3])).fold(f32::NEG_INFINITY, max_r::<R>),
        ]
    });
    // The (w, z) line through the vertices of least and greatest w.
    let lo_v = verts.iter().cloned().fold(verts[0], |a, p| if p[3] < a[3] { p } else { a });
    let hi_v = verts.iter().cloned().fold(verts[0], |a, p| if p[3] > a[3] { p } else { a });
    let (mut a, mut bb) = (0.0f32, 0.0f32);
    if hi_v[3] > lo_v[3] {
        a = (hi_v[2] - lo_v[2]) / (hi_v[3] - lo_v[3]);
        bb = lo_v[2] - a * lo_v[3];
        if !(a.is_finite() && bb.is_finite()) {
            a = 0.0;
            bb = 0.0;
        }
    }
    // Residuals z - a w - bb, rounded down for the least and up for the greatest (a
    // and bb are any f32 values: the conversion is exact for every A, B).
    let res_lo = verts.iter().map(|p| R::dn(R::dn(p[2] - R::up(a * p[3])) - bb)).fold(f32::INFINITY, min_r::<R>);
    let res_hi = verts.iter().map(|p| R::up(R::up(p[2] - R::dn(a * p[3])) - bb)).fold(f32::NEG_INFINITY, max_r::<R>);
    let mut c = [R::dn(bb + res_lo), R::up(bb + res_hi)];
    if R::SAFE && (c[0].is_nan() || c[1].is_nan()) {
        c = [f32::NEG_INFINITY, f32::INFINITY];
    }
    Prep {
        planes,
        w_box,
        zeta_box,
        a,
        c,
        disabled: (!finite).then_some("non-finite triangle data"),
        round: PhantomData,
    }
}

/// The published setup (round to nearest).
#[cfg(test)]
fn prepare(tri: &Triangle) -> Prep<Near> {
    prepare_with::<Near>(tri)
}

impl<R: Round> Method for Nilsson2012Depth<R> {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(prepare_with::<R>(tri))
    }
}

pub static METHOD: &dyn Method = &Nilsson2012Depth::<Near> { info: &INFO, round: PhantomData };

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
