//! `la2011` (**reconstruction**): per-tile time bounds in dual space and per-tile lens
//! bounds, after Laine, Aila, Karras & Lehtinen 2011, "Clipless Dual-Space Bounds for
//! Faster Stochastic Rasterization" (LAKL11, ACM TOG 30(4) 106). That paper is not
//! available to this project; this file follows `docs/reconstructions.md` (§2 "The
//! dual-space quantity" with its clipless column test, §3 "la2011" with LA's time and
//! lens bounds), built on what the available papers say about LA: Munkberg &
//! Akenine-Möller 2012 §1 (LA culls "by clipping down the extents of u, v, and t
//! individually", Figure 1; cost in Table 3) and Wu 2013 ch. 2 (the motion part uses
//! `delta = x - w gamma`, linear in t, and bounds time "by linear interpolation"; the
//! defocus part bounds the lens from the triangle's extents at two lens positions).
//! Every formula below is derived again here; none is quoted from LAKL11.
//!
//! # The dual-space quantity
//! For a screen column X, vertex i, lens coordinate u and time t,
//! `delta_i(X, u, t) = x_i(t) + u c_i(t) - X w_i(t)`: the x of the sheared vertex
//! after translating column X to the origin (`P_i.x` of `docs/model.md`). It is affine in each
//! of X, u, t separately (the `u t` term comes from `c_i(t)`). In y:
//! `eps_i(Y, v, t) = y_i(t) + k v c_i(t) - Y w_i(t)`. Everything below is said for x;
//! y is the same with (Y, v, k c_i) in place of (X, u, c_i).
//!
//! # Lemma (why deltas bound coverage, for any sign of w)
//! For a sample (x, y, u, v, t) put `P_k = (delta_k(x, u, t), eps_k(y, v, t), w_k(t))`.
//! The edge values `E_k` are the w-components of `P_i x P_j`, and the adjugate
//! identity `sum_k P_k (P_i x P_j)^T = det(P) I` read on its w column gives
//! `sum_k E_k P_k = (0, 0, D)`. An interior sample has every `E_k` of the strict sign
//! of `D != 0`, so `sum_k E_k delta_k = 0` with positive (or all negative) weights:
//! the deltas cannot all be >= 0 (they would all be 0, the x column of P would vanish
//! and D = 0). Hence **interior => min_k delta_k(x,u,t) < 0 < max_k delta_k(x,u,t)**,
//! and the same for eps. No assumption on the sign of w is needed.
//!
//! # Clipless column test (from the tile's x to its two columns)
//! `delta_i(x)` is affine in x, so for x in [X0, X1]
//! `min(delta_i(X0), delta_i(X1)) <= delta_i(x) <= max(delta_i(X0), delta_i(X1))`.
//! Hence a covered sample in the tile at (u, t) has
//! `m(u,t) := min over i, X in {X0,X1} of delta_i(X,u,t) < 0` and
//! `M(u,t) := max over the same 6 values > 0`. If every `w_i > 0`, `delta_i` decreases
//! with X and `m = min_i delta_i(X1)`, `M = max_i delta_i(X0)`: the reconstruction's
//! formulas. Taking both columns for both sides is what keeps the test valid when a
//! vertex is behind the lens (w <= 0), without clipping ("clipless"). In f32 it gives
//! bit-identical values to the X1-only / X0-only form when every w > 0, because
//! `fl(X w)` and `fl(x - fl(X w))` are monotone in X.
//!
//! # LA time bounds
//! For a time t to hold a covered sample, `m(u, t) < 0` for some u in [-1, 1].
//! `delta_i` is affine in u, so `min_u delta_i(X,u,t) = delta_i(X,±1,t)`, i.e.
//! `x_i(t) - X w_i(t) - |c_i(t)|`; the lens is fixed at u = ±1 (both copies of each
//! vertex). So t can hold a covered sample only if
//! `F(t) := min over i, X, s = ±1 of delta_i(X, s, t) < 0`. Each of the 12 functions is
//! affine in t, so F is concave and lies above its chord:
//! `F(t) >= (1-t) L0 + t L1`, `L0 = F(0)`, `L1 = F(1)` (at t = 0, 1 the min over
//! s = ±1 is `d - |c|` with `c = c0_i` or `c1_i`). Cull the t where the chord is > 0:
//! - `L0 > 0` and `L1 > 0`: the chord is positive on [0, 1]: the tile is **Empty**
//!   (this is the clipless column test over the whole lens and shutter);
//! - `L0 > 0 >= L1`: keep `t >= t* = L0 / (L0 - L1)`;
//! - `L1 > 0 >= L0`: keep `t <= t*` (same formula);
//! - both <= 0: no cut.
//!
//! Symmetrically `G(t) := max ... delta_i(X, s, t) = max (x_i - X w_i + |c_i|)` is convex,
//! below its chord, and t needs `G(t) > 0`: cull where the chord `(1-t) H0 + t H1` is
//! < 0. The same is done in y with `|k c_i|`, and `t^` is the intersection of the four
//! ranges. Between the lens extremes nothing is lost: the bound holds for every u in
//! [-1, 1] because the minimum over u of an affine function is at u = ±1.
//!
//! # LA lens bounds
//! A covered sample at (u, t) needs `delta_i(X, u, t) < 0` for some (i, X) (condition
//! a) and `delta_j(X', u, t) > 0` for some (j, X') (condition b). For one (i, X), with
//! `d(t) = x_i(t) - X w_i(t)` and `c(t) = c_i(t)`, the set of u where
//! `d(t) + u c(t) < 0` is, per shutter time:
//! - `u < theta(t)` if `c(t) > 0`, `u > theta(t)` if `c(t) < 0`, with the per-vertex
//!   lens threshold `theta(t) = u_i(X, t) = (X w_i(t) - x_i(t)) / c_i(t)`;
//! - everything or nothing if `c(t) = 0`.
//!
//! If `c_i` has one strict sign at both shutter ends it has it on all of [0, 1], and
//! `theta` is a ratio of affine functions with a non-vanishing denominator, hence
//! monotone (its derivative has the constant numerator `d'c - d c'` over `c^2`): its
//! extremes over the shutter are at t = 0, 1. So the union over t is
//! `u < max(theta(0), theta(1))` (c > 0) or `u > min(theta(0), theta(1))` (c < 0). If
//! `c_i = 0` at both ends, the set is everything when `d(0) < 0` or `d(1) < 0` and
//! empty otherwise. If `c_i` changes sign or touches 0 at one end only, we take the
//! whole lens for that (i, X) (the reconstruction's "use the full lens"). The lens
//! range of condition (a) is the hull of the union over the 6 (i, X); (b) is the same
//! with the inequality reversed; `u^` is the intersection of both hulls with [-1, 1].
//! Empty when that intersection is empty (or when no (i, X) can satisfy a condition).
//!
//! # What we are unsure of in the reconstruction
//! - Whether LAKL11 evaluates its time bounds with the lens fixed at u = ±1 (as here)
//!   or inside the tile's already-clipped lens range, and whether it bounds time from
//!   the chord of the min over vertices (as here) or by per-vertex crossing times;
//!   the chord is the tightest bound that uses only the two shutter ends.
//! - Wu 2013 describes LA's lens part as interpolating the triangle's AABBs at two lens
//!   positions. For one time, with every w > 0, the per-vertex thresholds give exactly
//!   the lens range where the triangle's AABB at lens u meets the tile's columns (the
//!   AABB side `min_i (x_i + u c_i) / w_i` is a concave min of lines in u). Linear
//!   interpolation between AABBs at two lens positions replaces that min by its chord,
//!   which is below it: also conservative, never tighter. We implement the thresholds
//!   that `docs/reconstructions.md` specifies; LAKL11 may be looser here.
//! - The reconstruction asks for the full lens when some `w_i <= 0` in the shutter. The
//!   derivation above (both columns, the lemma) never uses the sign of w, so we keep
//!   the lens bounds then; with every w > 0 the thresholds at the other column are
//!   dominated and the result is identical (this is a deviation only for w <= 0).
//! - The "per tile" costs of munkberg2012 Table 3 (LA: 500 / 40 / -) suggest part of
//!   the work sits in the triangle setup; we recompute everything per tile.
//!
//! # f32
//! All values are computed in f32 without FMA: `d = fl(x - fl(X w))`, `fl(d ± |c|)`,
//! `t* = fl(L0 / fl(L0 - L1))`, `theta = fl(fl(fl(X w) - x) / c)`. A computed `L_k` can
//! differ from the real one by a few ulps of `|x| + |X w| + |c|`, and `t*` and `theta`
//! carry a few more ulps: a bound can cut a covered sample within those few ulps of
//! it, and a tile can be called Empty when the real `L0` or `L1` is within those ulps of
//! 0. No epsilon is added. Non-finite intermediate values (overflow, NaN from
//! degenerate input) make the affected quantity fall back to its full range.
//!
//! # Degenerate input
//! No division by a quantity that can be 0: `L0 - L1 > 0` where it is used, and `theta`
//! is only formed when `c` has a strict sign. Zero-area or coincident vertices need no
//! special case.
//!
//! # `la2011-safe`: the same bounds in f32 interval arithmetic
//! `la2011` above is the reconstruction computed in f32 rounded to nearest and stays as
//! it is: the gate finds covered samples just outside its `t` and `u`/`v` ends (margins
//! ~1e-7..3e-5), far from the origin (1e4..1e6 px) `fl(X w)` and `fl(x - X w)` lose up to
//! 1/16 px so its bounds miss by up to 1e-2 and a covered tile can be culled outright,
//! and its f32 tile reject culls covered tiles at the limit. All three are rounding:
//! the derivation above holds in real arithmetic for every sign of w (lemma, clipless
//! columns, concave `F` above its chord, monotone `theta` between shears of one strict
//! sign), so **no correction beyond rounding is needed**. `la2011-safe` runs the same
//! algorithm (`Axis::bounds` is generic over the arithmetic `R`; `la2011` is
//! `R = Nearest`, bit for bit the code it was) in **f32 interval arithmetic**
//! (`R = Outward`): every quantity is an interval `[lo, hi]` of f32 values that encloses
//! its exact value for the f32 inputs, every rounded operation is followed by one
//! `next_down` (a lower end) or `next_up` (an upper end).
//!
//! *Why a step encloses.* Rust's f32 operations are IEEE round-to-nearest, without FMA
//! contraction. If `r = fl(z)` for a real `z`, then `next_down(r) <= z <= next_up(r)`:
//! for finite `r`, z lies within half the gap between r and its neighbour on z's side
//! (in the subnormal range the gaps are a uniform 2^-149, so underflow is covered; at a
//! power of two the gap towards zero is the smaller one, and z is within half of it);
//! `r = ±0` means `|z| <= 2^-150 < 2^-149`; `r = +inf` means `z > f32::MAX =
//! next_down(inf)` (round to nearest overflows only beyond MAX + ulp/2), and the same
//! for -inf. This holds with no assumption on magnitudes, which is why steps are used
//! rather than a `gamma_n` bound: `d = x - X w` cancels (far from the origin both terms
//! are ~1e6 and the result ~1), the thresholds divide by shears that can be tiny, and a
//! relative bound would need its own absolute underflow terms at each of those steps.
//! A step costs one ulp per operation (the error bound of nearest rounding is half).
//!
//! *The quantities* (exact inputs: the f32 vertex values, `c0`, `c1`, `k`, tile edges):
//! - shear `s = k c` (y; `s = c` for x): `[dn(fl(k c)), up(fl(k c))]`, or `fl(k c)`
//!   alone when it is exact (a factor 0 or ±1). Its sign class is `Pos` only when the
//!   lower ends are > 0 at both shutter ends, `Neg` when the upper ends are < 0, `Zero`
//!   only when `s` is exactly 0 (a zero factor), else `Cross` (full lens for that
//!   vertex, as in `la2011`): a `k c` that underflows to 0 is `Cross`, not `Zero`.
//! - `X w`: the same; `d = p - X w` is `[dn(fl(p - Xw_hi)), up(fl(p - Xw_lo))]`.
//! - time: `m = dn(fl(d_lo - a))`, `mm = up(fl(d_hi + a))` with `a = max(|s_lo|,
//!   |s_hi|) >= |s|`; their min / max (exact) give `F_lo(e) <= F(e)` and
//!   `G_hi(e) >= G(e)`. The chord through `F_lo(0)`, `F_lo(1)` lies below the exact
//!   chord, hence below `F`, so the `t` where it is > 0 hold no covered sample (and the
//!   same for G above); the tile is Empty when `F_lo(0) > 0` and `F_lo(1) > 0` (or the
//!   G side), comparisons of f32 values being exact.
//! - the crossing `t* = l0 / (l0 - l1)` of that chord, `l0`, `l1` f32: the denominator
//!   is rounded up, `D = up(fl(l0 - l1))`. If `l0 > 0 >= l1`, `t*` is the lower end of
//!   the kept range and `D >= l0 - l1 > 0` makes `l0 / D <= t*`, so `dn(fl(l0 / D))` is
//!   below it; if `l0 <= 0 < l1`, `t*` is the upper end and `l0 - l1 <= D <= 0`
//!   makes `|l0| / |D| >= t*`, so `up(fl(l0 / D))` is above it (`D = -0` gives inf or
//!   NaN: the end stays at 1). Clamping to [0, 1] is exact.
//! - thresholds `theta = -d / s` at each shutter end: for `Pos` the largest value over
//!   the enclosures, at `n = -d_lo` divided by `s_lo` if `n >= 0` (by `s_hi` if not),
//!   rounded up; for `Neg` the smallest, at the same `n` divided by `s_hi` if `n >= 0`
//!   (by `s_lo` if not), rounded down. `theta` is monotone in t between the ends (exact
//!   argument above), so these enclose its extreme over the shutter. `Zero`: the set is
//!   everything when some `d_lo < 0`.
//! - hulls, intersections and the clamp to [-1, 1]: min / max of f32 values, exact.
//!
//! *Non-finite values.* A non-finite input (any component of `q`, `r`, `c0`, `c1`, `k`,
//! or a tile edge) gives every tile the full domain, never Empty. A non-finite
//! intermediate (overflow, or NaN from inf / inf) gives the full `t` range for that
//! axis (time part) or the full lens for that vertex and column (a threshold or a `d`
//! of a `Zero` shear); `la2011` does this for NaN only. No division by w happens
//! anywhere, so w near 0 (or crossing 0) needs no case of its own; a shear whose
//! enclosure touches 0 (the focal plane: CoC crossing or reaching 0) is `Cross`.
//!
//! *Cost.* Per operation one step more, two subtractions for `d` (one per end), two
//! comparisons to pick the divisor of `theta`. The intervals are a few ulps wider than
//! `la2011`'s values: near the origin no STE figure can see it; at 1e6 px the enclosure
//! of `X w` is ~1/8 px wide, so `t` bounds widen by ~1/8 px over the motion and `u`/`v`
//! bounds by ~1/8 px over the CoC (tiny CoCs there lose their lens bounds entirely:
//! that is the precision f32 has at 1e6 px, not a choice).

use super::*;
use crate::bounds::arith::{tile_of, End, F32Arith, Plain, TriOf};
use crate::bounds::round::{Nearest, Outward, Round};
use std::marker::PhantomData;

/// An f32 interval `[lo, hi]`; in `la2011` both ends are the one rounded value.
type Iv = [f32; 2];

/// Encloses the exact product `a b` of two f32 values: `fl(a b)` stepped outward, or
/// `fl(a b)` itself when it is exact (a factor 0 or ±1).
fn mul<R: Round, A: F32Arith>(ar: &A, a: &A::F, b: &A::F) -> [A::F; 2] {
    let p = ar.mul(a, b);
    let (zero, one) = (ar.lit(0.0), ar.lit(1.0));
    let exact = ar.any(&[ar.eq(a, &zero), ar.eq(b, &zero), ar.eq(&ar.abs(a), &one), ar.eq(&ar.abs(b), &one)]);
    [ar.select(&exact, &p, &R::dn(ar, &p)), ar.select(&exact, &p, &R::up(ar, &p))]
}

/// `-[lo, hi] = [-hi, -lo]` (exact).
fn neg<A: F32Arith>(ar: &A, a: &[A::F; 2]) -> [A::F; 2] {
    [ar.neg(&a[1]), ar.neg(&a[0])]
}

/// Sign class of a per-vertex lens shear over the shutter: `pos` (> 0 at both ends, so
/// on all of [0, 1]), `neg` (< 0 at both ends), `zero` (exactly 0 at both ends), at
/// most one of them true; none means it changes sign, touches 0 at one end, or is NaN.
#[derive(Clone, Debug)]
pub struct Class<B> {
    pos: B,
    neg: B,
    zero: B,
}

impl<B: Clone> Class<B> {
    /// The class of a shear whose end values lie in `s0`, `s1`: a strict sign only
    /// when the whole enclosure has it, zero only when it is exactly 0.
    fn of<A: F32Arith<B = B>>(ar: &A, s0: &[A::F; 2], s1: &[A::F; 2]) -> Class<B> {
        let z = ar.lit(0.0);
        let pos = ar.and(&ar.gt(&s0[0], &z), &ar.gt(&s1[0], &z));
        let neg = ar.and(&ar.not(&pos), &ar.and(&ar.lt(&s0[1], &z), &ar.lt(&s1[1], &z)));
        let exact = ar.all(&[ar.eq(&s0[0], &z), ar.eq(&s0[1], &z), ar.eq(&s1[0], &z), ar.eq(&s1[1], &z)]);
        let zero = ar.all(&[ar.not(&pos), ar.not(&neg), exact]);
        Class { pos, neg, zero }
    }
    fn flip(&self) -> Class<B> {
        Class { pos: self.neg.clone(), neg: self.pos.clone(), zero: self.zero.clone() }
    }
}

/// One screen axis at the two shutter ends (index e = 0 at t = 0, 1 at t = 1), its
/// numbers values of some [`F32Arith`].
#[derive(Clone, Debug)]
pub struct Axis<F, B> {
    /// Vertex position on this axis (x or y), clip space.
    p: [[F; 3]; 2],
    /// w.
    w: [[F; 3]; 2],
    /// Lens shear per unit lens coordinate: `c` for x, `k c` for y (an enclosure).
    s: [[[F; 2]; 3]; 2],
    class: [Class<B>; 3],
}

/// The setup of one axis (0: x with scale 1, 1: y with scale `k`).
pub fn axis_of<R: Round, A: F32Arith>(ar: &A, tri: &TriOf<A::F>, axis: usize) -> Axis<A::F, A::B> {
    let scale = if axis == 0 { ar.lit(1.0) } else { tri.k.clone() };
    let p = [tri.q.each_ref().map(|v| v[axis].clone()), tri.r.each_ref().map(|v| v[axis].clone())];
    let w = [tri.q.each_ref().map(|v| v[3].clone()), tri.r.each_ref().map(|v| v[3].clone())];
    let s =
        [tri.c0.each_ref().map(|c| mul::<R, A>(ar, &scale, c)), tri.c1.each_ref().map(|c| mul::<R, A>(ar, &scale, c))];
    let class = [0, 1, 2].map(|i| Class::of(ar, &s[0][i], &s[1][i]));
    Axis { p, w, s, class }
}

impl<F: Clone, B: Clone> Axis<F, B> {
    /// Encloses `d = p - X w` for end e, vertex i.
    fn d<R: Round, A: F32Arith<F = F, B = B>>(&self, ar: &A, e: usize, i: usize, x: &F) -> [F; 2] {
        let p = &self.p[e][i];
        let xw = mul::<R, A>(ar, x, &self.w[e][i]);
        [R::dn(ar, &ar.sub(p, &xw[1])), R::up(ar, &ar.sub(p, &xw[0]))]
    }

    /// Time range for the tile columns `cols` of this axis, and false when it proves
    /// the tile empty: F(e) = min (d - |s|), G(e) = max (d + |s|) over i and both
    /// columns (a lower bound of F, an upper bound of G), cut by their chords.
    pub fn time<R: Round, A: F32Arith<F = F, B = B>>(&self, ar: &A, cols: &[F; 2]) -> (B, [F; 2]) {
        let mut f = [ar.lit(f32::INFINITY), ar.lit(f32::INFINITY)];
        let mut g = [ar.lit(f32::NEG_INFINITY), ar.lit(f32::NEG_INFINITY)];
        let mut nan = ar.truth(false);
        for e in 0..2 {
            for i in 0..3 {
                let s = &self.s[e][i];
                let a = ar.max(&ar.abs(&s[0]), &ar.abs(&s[1]));
                for x in cols {
                    let d = self.d::<R, A>(ar, e, i, x);
                    let (m, mm) = (R::dn(ar, &ar.sub(&d[0], &a)), R::up(ar, &ar.add(&d[1], &a)));
                    nan = ar.or(&nan, &ar.or(&R::bad(ar, &m), &R::bad(ar, &mm)));
                    f[e] = ar.min(&f[e], &m);
                    g[e] = ar.max(&g[e], &mm);
                }
            }
        }
        let (okf, tf) = chord::<R, A>(ar, &f[0], &f[1]);
        let (okg, tg) = chord::<R, A>(ar, &ar.neg(&g[0]), &ar.neg(&g[1]));
        let cut = [ar.max(&tf[0], &tg[0]), ar.min(&tf[1], &tg[1])];
        let t = [ar.select(&nan, &ar.lit(0.0), &cut[0]), ar.select(&nan, &ar.lit(1.0), &cut[1])];
        let ok = ar.and(&ar.or(&nan, &ar.and(&okf, &okg)), &ar.not(&ar.gt(&t[0], &t[1])));
        (ok, t)
    }

    /// Lens range for the tile columns `cols`: the hull of condition (a) "some
    /// d + u s < 0" met with that of (b) "some d + u s > 0" and [-1, 1]; false when it
    /// is empty.
    pub fn lens<R: Round, A: F32Arith<F = F, B = B>>(&self, ar: &A, cols: &[F; 2]) -> (B, [F; 2]) {
        let none = || (ar.truth(false), [ar.lit(f32::NEG_INFINITY), ar.lit(f32::INFINITY)]);
        let (mut ha, mut hb) = (none(), none());
        for i in 0..3 {
            let s = [self.s[0][i].clone(), self.s[1][i].clone()];
            for x in cols {
                let d = [self.d::<R, A>(ar, 0, i, x), self.d::<R, A>(ar, 1, i, x)];
                ha = join(ar, &ha, &neg_hull::<R, A>(ar, &d, &s, &self.class[i]));
                let (dn, sn) = (d.each_ref().map(|v| neg(ar, v)), s.each_ref().map(|v| neg(ar, v)));
                hb = join(ar, &hb, &neg_hull::<R, A>(ar, &dn, &sn, &self.class[i].flip()));
            }
        }
        let lens =
            [ar.max(&ar.max(&ha.1[0], &hb.1[0]), &ar.lit(-1.0)), ar.min(&ar.min(&ha.1[1], &hb.1[1]), &ar.lit(1.0))];
        let ok = ar.all(&[ha.0, hb.0, ar.not(&ar.gt(&lens[0], &lens[1]))]);
        (ok, lens)
    }

    /// Time range and lens range for the tile columns `cols`, and false when the axis
    /// proves the tile empty.
    pub fn bounds<R: Round, A: F32Arith<F = F, B = B>>(&self, ar: &A, cols: &[F; 2]) -> (B, [F; 2], [F; 2]) {
        let (okt, t) = self.time::<R, A>(ar, cols);
        let (okl, lens) = self.lens::<R, A>(ar, cols);
        (ar.and(&okt, &okl), t, lens)
    }
}

/// The f32 time and lens ranges of one axis, or None when it proves the tile empty:
/// [`Axis::bounds`] with the lens part skipped when the time part already said empty
/// (its answer cannot change the result).
fn bounds_f32<R: Round>(ax: &Axis<f32, bool>, cols: &Iv) -> Option<(Iv, Iv)> {
    let (ok, t) = ax.time::<R, Plain>(&Plain, cols);
    if !ok {
        return None;
    }
    let (ok, lens) = ax.lens::<R, Plain>(&Plain, cols);
    ok.then_some((t, lens))
}

/// The union of two lens hulls `(nonempty, [lo, hi])`.
pub(crate) fn join<A: F32Arith>(ar: &A, h: &(A::B, [A::F; 2]), r: &(A::B, [A::F; 2])) -> (A::B, [A::F; 2]) {
    let lo = ar.select(&r.0, &ar.select(&h.0, &ar.min(&h.1[0], &r.1[0]), &r.1[0]), &h.1[0]);
    let hi = ar.select(&r.0, &ar.select(&h.0, &ar.max(&h.1[1], &r.1[1]), &r.1[1]), &h.1[1]);
    (ar.or(&h.0, &r.0), [lo, hi])
}

/// The t in [0, 1] where the chord `(1-t) l0 + t l1` is <= 0 (the rest is culled);
/// None when the chord is > 0 on all of [0, 1].
pub(crate) fn chord_nonpos(l0: f32, l1: f32) -> Option<[f32; 2]> {
    let (some, t) = chord::<Nearest, Plain>(&Plain, &l0, &l1);
    some.then_some(t)
}

/// `chord_nonpos` over any [`F32Arith`] (false: the chord is > 0 on all of [0, 1]),
/// with the crossing `t* = l0 / (l0 - l1)` rounded by `R` towards the kept side: down
/// where it is the lower end (`l0 > 0 >= l1`), up where it is the upper end
/// (`l0 <= 0 < l1`); the denominator is rounded up in both cases (see the module's
/// `la2011-safe` analysis). A NaN crossing leaves that end at 0 (lower) or 1 (upper).
pub fn chord<R: Round, A: F32Arith>(ar: &A, l0: &A::F, l1: &A::F) -> (A::B, [A::F; 2]) {
    // The chord through two lower ends lies below the exact chord: the t it keeps
    // (where it is <= 0) include those the exact chord keeps. From here on the chord
    // is the one through `l0`, `l1` themselves.
    let (l0, l1) = (&ar.pin(l0, End::Lo, CHORD_LEMMA), &ar.pin(l1, End::Lo, CHORD_LEMMA));
    let (zero, one) = (ar.lit(0.0), ar.lit(1.0));
    let den = R::up(ar, &ar.sub(l0, l1));
    let q = ar.div(l0, &den);
    // `t.clamp(0, 1)`: `if t < 0 { 0 }`, then `if t > 1 { 1 }`.
    let clamp = |t: &A::F| {
        let t = ar.select(&ar.lt(t, &zero), &zero, t);
        ar.select(&ar.gt(&t, &one), &one, &t)
    };
    let (lo, hi) = (R::dn(ar, &q), R::up(ar, &q));
    let (p0, p1) = (ar.gt(l0, &zero), ar.gt(l1, &zero));
    // The lower end is used only where l0 > 0 >= l1 (then the denominator is > 0);
    // the upper end only where l0 <= 0 < l1 and the denominator is < 0 (a -0
    // denominator gives an infinite or NaN quotient: the end stays at 1 either way).
    let lower = ar.select(&ar.or(&ar.is_nan(&lo), &p1), &zero, &clamp(&lo));
    let upper = ar.select(&ar.or(&ar.is_nan(&hi), &ar.not(&ar.lt(&den, &zero))), &one, &clamp(&hi));
    let t = [ar.select(&p0, &lower, &zero), ar.select(&p0, &one, &ar.select(&p1, &upper, &one))];
    (ar.not(&ar.and(&p0, &p1)), t)
}

/// The lemma of the pins of [`chord`]: for `l0 <= L0`, `l1 <= L1` and t in [0, 1],
/// `(1-t) L0 + t L1 <= 0` implies `(1-t) l0 + t l1 <= 0` (checked by z3 in real
/// arithmetic, `cullproof proofs`).
pub const CHORD_LEMMA: &str = "a chord through lower ends keeps every t the exact chord keeps";

/// Hull over t in [0, 1] of `{u real : d(t) + u s(t) < 0}`, for `d`, `s` affine in t
/// with end values in `d[e]`, `s[e]` and sign class `class` of `s`; false when empty.
/// Bounds may be infinite.
fn neg_hull<R: Round, A: F32Arith>(
    ar: &A,
    d: &[[A::F; 2]; 2],
    s: &[[A::F; 2]; 2],
    class: &Class<A::B>,
) -> (A::B, [A::F; 2]) {
    let zero = ar.lit(0.0);
    // The threshold `theta = -d / s` takes its largest value over the enclosures at the
    // largest numerator `n = -d_lo`, over the smallest |s| if n >= 0 (the largest if
    // n < 0) when s > 0; its smallest value at the same n, over the smallest |s| if
    // n >= 0 (the largest if n < 0) when s < 0.
    let top = |e: usize| {
        let n = ar.neg(&d[e][0]);
        R::up(ar, &ar.select(&ar.le(&zero, &n), &ar.div(&n, &s[e][0]), &ar.div(&n, &s[e][1])))
    };
    let bottom = |e: usize| {
        let n = ar.neg(&d[e][0]);
        R::dn(ar, &ar.select(&ar.le(&zero, &n), &ar.div(&n, &s[e][1]), &ar.div(&n, &s[e][0])))
    };
    let (ta, tb) = (top(0), top(1));
    let (ba, bb) = (bottom(0), bottom(1));
    let pos_ok = ar.and(&class.pos, &ar.not(&ar.or(&R::bad(ar, &ta), &R::bad(ar, &tb))));
    let neg_ok = ar.and(&class.neg, &ar.not(&ar.or(&R::bad(ar, &ba), &R::bad(ar, &bb))));
    let bad_d = [R::bad(ar, &d[0][0]), R::bad(ar, &d[0][1]), R::bad(ar, &d[1][0]), R::bad(ar, &d[1][1])];
    let zero_some = ar.any(&[ar.lt(&d[0][0], &zero), ar.lt(&d[1][0], &zero), ar.any(&bad_d)]);
    // Some u qualifies unless the shear is exactly 0 and no d is < 0 (pos, neg and the
    // crossing class all have some; zero excludes pos and neg).
    let some = ar.or(&ar.not(&class.zero), &zero_some);
    let lo = ar.select(&neg_ok, &ar.min(&ba, &bb), &ar.lit(f32::NEG_INFINITY));
    let hi = ar.select(&pos_ok, &ar.max(&ta, &tb), &ar.lit(f32::INFINITY));
    (some, [lo, hi])
}

/// The setup of `la2011` (`R = Nearest`) or `la2011-safe` (`R = Outward`) over any
/// [`F32Arith`]: both axes, and whether some input is not finite (only `la2011-safe`
/// looks: then every tile gets the full domain).
#[derive(Clone, Debug)]
pub struct Setup<F, B> {
    pub x: Axis<F, B>,
    pub y: Axis<F, B>,
    pub full: B,
}

/// [`Setup`] of a triangle.
pub fn setup_of<R: Round, A: F32Arith>(ar: &A, tri: &TriOf<A::F>) -> Setup<A::F, A::B> {
    let inputs: Vec<&A::F> =
        tri.q.iter().chain(&tri.r).flatten().chain(&tri.c0).chain(&tri.c1).chain([&tri.k]).collect();
    let finite: Vec<A::B> = inputs.into_iter().map(|v| ar.is_finite(v)).collect();
    let full = ar.and(&ar.truth(R::GUARD), &ar.not(&ar.all(&finite)));
    Setup { x: axis_of::<R, A>(ar, tri, 0), y: axis_of::<R, A>(ar, tri, 1), full }
}

/// A tile answer `(nonempty, t, u, v)` as values of some [`F32Arith`].
pub type Answer<F, B> = (B, [F; 2], [F; 2], [F; 2]);

/// The answer for a tile `[x0, y0, x1, y1]` over any [`F32Arith`]: `(nonempty, t, u,
/// v)`; the tile is Empty when `nonempty` is false (the tile reject).
pub fn tile_answer<R: Round, A: F32Arith>(ar: &A, s: &Setup<A::F, A::B>, tile: &[A::F; 4]) -> Answer<A::F, A::B> {
    let full = guard::<R, A>(ar, s, tile);
    let (okx, tx, u) = s.x.bounds::<R, A>(ar, &[tile[0].clone(), tile[2].clone()]);
    let (oky, ty, v) = s.y.bounds::<R, A>(ar, &[tile[1].clone(), tile[3].clone()]);
    let (okt, t) = meet(ar, &tx, &ty);
    let nonempty = ar.or(&full, &ar.all(&[okx, oky, okt]));
    let pick = |f: [f32; 2], v: &[A::F; 2]| [0, 1].map(|k| ar.select(&full, &ar.lit(f[k]), &v[k]));
    let b = TileBounds::full();
    (nonempty, pick(b.t, &t), pick(b.u, &u), pick(b.v, &v))
}

/// Whether the tile gets the full domain before any arithmetic (`la2011-safe` on a
/// non-finite triangle or tile).
fn guard<R: Round, A: F32Arith>(ar: &A, s: &Setup<A::F, A::B>, tile: &[A::F; 4]) -> A::B {
    let finite = tile.each_ref().map(|v| ar.is_finite(v));
    ar.and(&ar.truth(R::GUARD), &ar.or(&s.full, &ar.not(&ar.all(&finite))))
}

/// The time ranges of both axes met; false when the meet is empty.
fn meet<A: F32Arith>(ar: &A, tx: &[A::F; 2], ty: &[A::F; 2]) -> (A::B, [A::F; 2]) {
    let t = [ar.max(&tx[0], &ty[0]), ar.min(&tx[1], &ty[1])];
    (ar.not(&ar.gt(&t[0], &t[1])), t)
}

struct Prep<R> {
    s: Setup<f32, bool>,
    round: PhantomData<fn() -> R>,
}

impl<R: Round> Prepared for Prep<R> {
    fn tile(&self, tile: &Tile) -> TileResult {
        let tv = tile_of(tile);
        if guard::<R, Plain>(&Plain, &self.s, &tv) {
            return TileResult::Bounds(TileBounds::full());
        }
        let Some((tx, u)) = bounds_f32::<R>(&self.s.x, &[tv[0], tv[2]]) else {
            return TileResult::Empty;
        };
        let Some((ty, v)) = bounds_f32::<R>(&self.s.y, &[tv[1], tv[3]]) else {
            return TileResult::Empty;
        };
        let (ok, t) = meet(&Plain, &tx, &ty);
        if !ok {
            return TileResult::Empty;
        }
        TileResult::Bounds(TileBounds { u, v, t, z: None, constraints: Vec::new() })
    }
    /// Each axis's ranges depend on its own tile edges only: computed once per column and
    /// once per row, then met per tile exactly as [`tile`](Self::tile) meets them.
    fn grid<'a>(&'a self, grid: Grid<'a>) -> Box<dyn TileGrid + 'a> {
        let cols = (0..grid.columns()).map(|i| bounds_f32::<R>(&self.s.x, &grid.column(i))).collect();
        let rows = (0..grid.rows()).map(|j| bounds_f32::<R>(&self.s.y, &grid.row(j))).collect();
        Box::new(AxisGrid { prep: self, grid, cols, rows })
    }
}

/// [`Prep::grid`]: each column's and each row's [`bounds_f32`].
struct AxisGrid<'a, R> {
    prep: &'a Prep<R>,
    grid: Grid<'a>,
    cols: Vec<Option<(Iv, Iv)>>,
    rows: Vec<Option<(Iv, Iv)>>,
}

impl<R: Round> TileGrid for AxisGrid<'_, R> {
    fn tile(&self, i: usize, j: usize) -> TileResult {
        if guard::<R, Plain>(&Plain, &self.prep.s, &tile_of(&self.grid.tile(i, j))) {
            return TileResult::Bounds(TileBounds::full());
        }
        let Some((tx, u)) = self.cols[i] else {
            return TileResult::Empty;
        };
        let Some((ty, v)) = self.rows[j] else {
            return TileResult::Empty;
        };
        let (ok, t) = meet(&Plain, &tx, &ty);
        if !ok {
            return TileResult::Empty;
        }
        TileResult::Bounds(TileBounds { u, v, t, z: None, constraints: Vec::new() })
    }
}

/// la2011 (`R = Nearest`) or la2011-safe (`R = Outward`): one algorithm, two arithmetics
/// (the planted slips of [`crate::bounds::broken::planted`] are a third and fourth).
pub(crate) struct La2011<R> {
    pub(crate) info: &'static MethodInfo,
    pub(crate) round: PhantomData<fn() -> R>,
}

pub(crate) static INFO: MethodInfo = MethodInfo {
    id: "la2011",
    source: "reconstruction of Laine, Aila, Karras, Lehtinen 2011, Clipless Dual-Space \
             Bounds (LAKL11), as described in Munkberg & Akenine-Möller 2012 §1, Fig. 1, \
             Table 3 and Wu 2013 ch. 2; formulas per docs/reconstructions.md \
             (dual-space delta = x + u c - X w, chord time bounds, per-vertex lens thresholds)",
    reconstruction: true,
    dims: &[Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: true, time: true, depth: false, per_sample: false },
};

impl<R: Round> Method for La2011<R> {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(Prep::<R> { s: setup_of::<R, Plain>(&Plain, &TriOf::of(tri)), round: PhantomData })
    }
}

pub static METHOD: &dyn Method = &La2011::<Nearest> { info: &INFO, round: PhantomData };

static INFO_SAFE: MethodInfo = MethodInfo {
    id: "la2011-safe",
    source: "reconstruction of Laine, Aila, Karras, Lehtinen 2011, Clipless Dual-Space \
             Bounds (LAKL11), as described in Munkberg & Akenine-Möller 2012 §1, Fig. 1, \
             Table 3 and Wu 2013 ch. 2; formulas per docs/reconstructions.md \
             (dual-space delta = x + u c - X w, chord time bounds, per-vertex lens thresholds); \
             computed in f32 interval arithmetic (every rounding stepped outward, analysis \
             in this file): conservative for every finite input",
    ..INFO
};

/// `la2011-safe`: the same bounds in f32 interval arithmetic (see the module's
/// `la2011-safe` analysis). `lc` and `mam2012-new` safe variants build on it.
pub static METHOD_SAFE: &dyn Method = &La2011::<Outward> { info: &INFO_SAFE, round: PhantomData };

/// The case of Munkberg & Akenine-Möller 2012, Figure 1: a small out-of-focus triangle
/// moving across the screen, and a tile around x = 0. Shared with the other methods'
/// tests so that their (u, t) regions can be compared with LA's box.
#[cfg(test)]
pub(crate) mod figure1 {
    use super::*;

    /// A 2 x 2 px triangle (w = 1, so clip units are pixels) moving from x = -20 to
    /// x = +20 over the shutter, with a constant CoC of 8 px (out of focus), k = 1.
    pub fn triangle() -> Triangle {
        Triangle {
            q: [[-21.0, -1.0, 0.5, 1.0], [-19.0, -1.0, 0.5, 1.0], [-20.0, 1.0, 0.5, 1.0]],
            r: [[19.0, -1.0, 0.5, 1.0], [21.0, -1.0, 0.5, 1.0], [20.0, 1.0, 0.5, 1.0]],
            c0: [8.0; 3],
            c1: [8.0; 3],
            k: 1.0,
        }
    }
    /// Tiles right of everything the triangle reaches (x <= 21 + 8), left of it, above
    /// and below: every method must cull them.
    pub fn far_tiles() -> [Tile; 4] {
        [
            Tile::square(30.0, -0.5, 1.0),
            Tile::square(-31.0, -0.5, 1.0),
            Tile::square(0.0, 10.0, 1.0),
            Tile::square(0.0, -11.0, 1.0),
        ]
    }
    /// The 1 x 1 px tile around x = 0 (and y = 0).
    pub fn tile() -> Tile {
        Tile { x0: -0.5, y0: -0.5, x1: 0.5, y1: 0.5 }
    }
    /// LA's u^ for it: the whole lens (every vertex crosses the tile at some lens
    /// position over the shutter: thresholds (X - x_i)/8 run from -2.69 to 2.69).
    pub const LA_U: [f32; 2] = [-1.0, 1.0];
    /// LA's t^: the min of x_i - X1 - 8 is -29.5 at t = 0 and 10.5 at t = 1, so
    /// t <= 29.5 / 40; the max of x_i - X0 + 8 is -10.5 and 29.5, so t >= 10.5 / 40.
    pub const LA_T: [f32; 2] = [0.2625, 0.7375];
    /// LA's v^: the triangle spans y in [-1, 1] and is sheared by 8 v, so it meets the
    /// rows [-0.5, 0.5] only for |v| <= 1.5 / 8.
    pub const LA_V: [f32; 2] = [-0.1875, 0.1875];
}

/// Hand-made hard cases shared by the tests of la2011, lb2011 and lc.
#[cfg(test)]
pub(crate) mod cases {
    use super::*;

    /// Triangles of every kind in the model: thin lens crossing the focal plane,
    /// vertices behind the lens (w <= 0, clipless), per-vertex CoC with a zero and a
    /// sign change, perspective motion.
    pub fn hard_triangles() -> Vec<Triangle> {
        let cam = crate::model::ThinLens {
            fx: 50.0,
            fy: 60.0,
            cx: 0.0,
            cy: 0.0,
            radius: 0.3,
            focus: 4.0,
            near: 0.1,
            far: 100.0,
        };
        let a = cam.triangle(
            [[-1.0, -1.0, 2.0], [1.0, -0.5, 6.0], [0.0, 1.0, 3.0]],
            [[-0.5, -1.0, 3.0], [1.5, 0.0, 5.0], [0.5, 1.5, 2.5]],
        );
        // One vertex behind the lens at t = 1, one passing through w = 0.
        let b = cam.triangle(
            [[-1.0, -1.0, 2.0], [1.0, -0.5, 1.0], [0.0, 1.0, 3.0]],
            [[-0.5, -1.0, 3.0], [1.5, 0.0, -1.0], [0.5, 1.5, 2.5]],
        );
        let c = Triangle {
            q: [[-10.0, -5.0, 0.5, 1.0], [10.0, -4.0, 0.5, 1.5], [0.0, 12.0, 0.5, 2.0]],
            r: [[-4.0, -6.0, 0.5, 1.2], [16.0, -2.0, 0.5, 1.0], [4.0, 10.0, 0.5, 3.0]],
            c0: [3.0, 0.0, -2.0],
            c1: [-1.0, 0.0, -4.0],
            k: 0.7,
        };
        // Crossing behind the lens in clip units directly, large motion and blur.
        let d = Triangle {
            q: [[-3.0, 0.0, 0.5, 1.0], [3.0, 1.0, 0.5, 0.5], [0.0, 4.0, 0.5, -0.5]],
            r: [[5.0, 2.0, 0.5, 2.0], [9.0, -1.0, 0.5, -1.0], [2.0, 6.0, 0.5, 1.0]],
            c0: [2.0, 1.0, 1.5],
            c1: [0.5, 3.0, -1.0],
            k: 1.0,
        };
        vec![a, b, c, d]
    }
}

#[cfg(test)]
mod tests;
