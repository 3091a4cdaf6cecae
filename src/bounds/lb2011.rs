//! `lb2011` (**reconstruction**): dual-space bounds with u-t and v-t correlation, as
//! four bilinear patches evaluated per sample, after Laine & Karras 2011, "Improved
//! Dual-Space Bounds for Simultaneous Motion and Defocus Blur", NVIDIA Technical
//! Report NVR-2011-004 (LK11). The report is not available to this project; this file
//! follows `docs/reconstructions.md` (§2 "The dual-space quantity", §4 "lb2011", LB's
//! per-sample patches), built on Munkberg & Akenine-Möller 2012: §1 (LK11 extends the
//! dual-space motion blur test "to a trilinear equation that takes correlations
//! between u&t and v&t into account", with "four bilinear patches ... evaluated for
//! each sample"), §2.1 under Eq. 1 (moving the denominator of `u_ij(t)` to the left
//! gives LK11's trilinear equation) and Table 3 (LB costs 400 per triangle, 16 per
//! tile, 12 per sample). Every formula below is derived again here.
//!
//! # The trilinear quantity
//! `delta_i(X, u, t) = x_i(t) + u c_i(t) - X w_i(t)` (`P_i.x` of `docs/model.md` for the
//! column X; affine in X, u, t separately) and in y `eps_i(Y, v, t) = y_i(t) + k v c_i(t) -
//! Y w_i(t)`. Munkberg's Eq. 1 threshold `u_ij(t) = n_i^x . p_j(t) / c_j(t)` is the root
//! in u of `delta_j(x_i, u, t) = 0` (their `n^x . p = x_i w - x = -delta` at u = 0).
//!
//! # Lemma (as in `la2011`; no assumption on the sign of w)
//! `sum_k E_k P_k = (0, 0, D)` (adjugate identity), so an interior-covered sample has
//! `min_k delta_k(x, u, t) < 0 < max_k delta_k(x, u, t)`; since `delta_k` is affine in
//! x, for x in the tile's [X0, X1]:
//! `m(u, t) := min over k, X in {X0, X1} of delta_k(X, u, t) < 0` and
//! `M(u, t) := max over the same 6 values > 0`. With every w > 0, `m = min_k
//! delta_k(X1, u, t)` and `M = max_k delta_k(X0, u, t)` (the reconstruction's tile sides;
//! bit-identical in f32 too, as `fl` is monotone); taking both columns keeps the test
//! valid for vertices behind the lens without clipping. Sign convention: the X1
//! patch culls where the min is > 0 (the triangle lies right of the tile); the X0
//! patch culls where the max is < 0 (left of it).
//!
//! # The patches
//! Per tile and axis, evaluate m at the four (u, t) corners u = ±1, t = 0, 1 (12
//! values each: 3 vertices x 2 columns) and let `B(u, t)` be their bilinear
//! interpolant. **Claim: B <= m on [-1, 1] x [0, 1].** Proof 1: each
//! `f_k = delta_k(X, ., .)` is bilinear in (u, t), so it equals its own bilinear
//! interpolant; bilinear interpolation is a positive linear operator (weights
//! `(1-a)(1-t), a(1-t), (1-a)t, a t >= 0`, `a = (u+1)/2`), so corners `m <= f_k` give
//! `B <= f_k` everywhere, for each k, hence `B <= min_k f_k = m`. Proof 2 (the
//! reconstruction's argument, which holds for *any* function concave along every
//! axis-parallel line, and m is one: along a line it is a min of affine functions):
//! on the edges t = 0 and t = 1, B is the chord of m in u, so `B(u, e) <= m(u, e)`;
//! for fixed u, B is the chord in t between `B(u, 0) <= m(u, 0)` and `B(u, 1) <=
//! m(u, 1)`, so `B(u, t) <= (1-t) m(u, 0) + t m(u, 1) <= m(u, t)` by concavity in t.
//! So the claim is true (no counterexample exists) and no deviation is needed.
//! A sample is culled when `B(u_s, t_s) > 0`; symmetrically the max patch `B'`
//! (interpolating M) is >= M and culls when `B'(u_s, t_s) < 0`. As `SampleConstraint`s
//! (culled when g < 0): `g = -B` (min patch) and `g = B'` (max patch), for x in u-t
//! and for y in v-t (with `k c`): four patches, as in munkberg2012.
//!
//! Each patch is stored as `g(l, t) = P + Q l + t (R + S l)` (l = u or v), with
//! `P = (g(-1,0) + g(1,0))/2`, `Q = (g(1,0) - g(-1,0))/2`, `R = (g(-1,1) + g(1,1))/2 - P`,
//! `S = (g(1,1) - g(-1,1))/2 - Q`, and evaluated per sample in f32 as
//! `fl(fl(P + fl(Q l)) + fl(t fl(R + fl(S l))))` (separate multiplies and adds, no
//! FMA): 3 multiply-adds per patch, 12 for the four, which matches the 12 per-sample
//! operations munkberg2012 Table 3 gives LB if a multiply-add counts as one.
//!
//! # Tile-level consequences (our addition: "what the patches imply")
//! A bilinear function on a box takes its extremes at the corners, and is affine along
//! each axis. So: the tile is **Empty** when a patch is < 0 (g) at all four corners
//! (then it culls the whole (l, t) square; for the min patches this is exactly LA's
//! clipless column test); `t^` keeps the t where `g(-1, t) >= 0` or `g(1, t) >= 0`
//! (hull of two chord ranges); `u^` (`v^`) keeps the l where `g(l, 0) >= 0` or
//! `g(l, 1) >= 0`. These cut nothing the patches would not cut, they only let the
//! tile pipeline skip samples early. A patch that is >= 0 at all four corners cannot
//! cull and is not emitted. The t range is at least as tight as LA's chord bound
//! (`min` of the two lines `g(±1, t)` is above the chord of the minima).
//!
//! # Choices the reconstruction leaves open
//! - Which samples' x is used: the patches are per tile (the sample's own x is not
//!   used; LK11's trilinear form could interpolate in x too).
//! - The tile ranges above and dropping patches that cannot cull.
//! - Both columns per patch (clipless; identical to the one-column form when w > 0).
//!
//! # f32 and the box enclosure
//! Corner values are `fl(fl(x - fl(X w)) ± s)` (`s = c` or `fl(k c)`): a few ulps of
//! `|x| + |X w| + |s|` off the real ones; the coefficients add one rounding each and
//! `eval` four more along its longest path. So B can exceed the real min by a few ulps
//! of the magnitudes involved, and a sample whose real `min_k delta_k` is within those
//! ulps of 0 can be culled: that is where f32 rounding can make the test
//! non-conservative; no epsilon is added. `eval_box` evaluates `P + Q l + t (R + S l)`
//! in outward-rounded f64 intervals over the box (P..S are the stored f32 values, exact
//! in f64) and widens by `2^-20 * (|P| + |Q| L + max(1, T) (|R| + |S| L)) + 2^-146 (1 +
//! L)(1 + T)` (L, T the largest |l|, |t| in the box): the f32 evaluation has at most 4
//! roundings on any path, relative error `<= 4 * 2^-24 < 2^-20` of that magnitude sum,
//! plus at most `2^-150` absolute for each rounding whose result underflows (a sum that
//! underflows is exact), scaled by at most `(1 + L)(1 + T)`: `2^-148 (1 + L)(1 + T)` in
//! all, within the `2^-146` term. (Until 2026-12-07 that term was `2^-126 (1 + L)(1 +
//! T)`, 2^20 times more than the argument needs: with clip coordinates near 1e-36 it
//! swallowed the patches, and lb2011-safe and lc-safe were left unproven on a third of
//! such cases. `tests.rs` checks the bound against the exact patch where the evaluation
//! underflows.) When that magnitude reaches `2^126` an f32 intermediate may
//! overflow and the enclosure is the whole real line. A NaN corner value (degenerate
//! input) drops that axis's patches and ranges; a patch whose coefficients are not
//! finite or sum in magnitude to `2^125` or more is dropped (its f32 `eval` could
//! overflow to NaN, which would cull).
//!
//! # `lb2011-safe`: the same patches, rounded outward
//! The f32 test above is the reconstruction and stays as it is: the gate finds covered
//! samples it culls (a corner value, an interval end or a patch value a few ulps on the
//! wrong side, worst where the patch values are large: CoCs of thousands of pixels,
//! |X w| near 2^18, tiles far from the origin) and covered tiles it rejects at the
//! limit. The claim above (B <= m) is true in real arithmetic, so no correction of the
//! algorithm is needed: `lb2011-safe` is the same algorithm with every quantity the
//! answer depends on rounded outward. Nothing else changes: the same corners, ranges,
//! reject and four patches. It is written once over `F32Arith` (`lb2011/safe.rs`, with a
//! rounding discipline `Round`): the gate runs it in f32, and the enclosure check of
//! `cullproof proofs` traces the same code for every input (`docs/proofs.md` §3c, §4c).
//! The published `lb2011` keeps its own f32 code; both share the tile combination
//! ([`tile_of`]) and the per-sample evaluation ([`eval_of`]).
//!
//! *Corner values: f32 interval arithmetic by directed steps.* A result r of one f32
//! operation rounded to nearest has the exact result between r and its neighbour on
//! one side, so `next_up(r)` (`next_down(r)`) is an upper (lower) bound of it; that
//! holds for subnormal results too (the neighbour is 2^-149 away and so is the step),
//! and for an overflow: a value rounded to +inf is above `f32::MAX = next_down(inf)`,
//! one rounded to -inf below `next_up(-inf)`. Computing an upper bound from upper
//! bounds of the operands (lower bounds where they enter with a minus sign) and then
//! stepping up therefore encloses the exact value, operation by operation. The shear
//! `s` is exact for x (`1 c`); for y it is `fl(k c)`, enclosed by
//! `[next_down(s), next_up(s)]`. The difference `p - X w` is one fused multiply-add,
//! `a = fl(p - X w)` with a single rounding (`f32::mul_add`, correctly rounded as
//! IEEE 754 fusedMultiplyAdd and GPU FMA units are), so it is enclosed by
//! `[next_down(a), next_up(a)]`, a step of an ulp of the *difference*: far from the
//! origin, where `p` and `X w` are both near 10^6 w and cancel, this is much tighter
//! than rounding `X w` first (the plain test does, and its error is an ulp of `X w`).
//! Then:
//!
//! ```text
//! a_lo = next_down(a)                       a_hi = next_up(a)
//! lower of p - X w - k c = next_down(a_lo - s_hi),  of p - X w + k c = next_down(a_lo + s_lo)
//! upper of p - X w - k c = next_up(a_hi - s_lo),    of p - X w + k c = next_up(a_hi + s_hi)
//! ```
//!
//! and the min (max) over vertices and columns of the lower (upper) bounds is a lower
//! bound of the exact `m` (upper bound of `M`) at each (l, t) corner: min and max are
//! exact. Any non-finite bound (NaN or infinite input, an overflow) drops the whole
//! axis: no reject, no range, no patch from it (full domain for its outputs). Cost per
//! column and vertex: one FMA and four adds (the plain test: a multiply, a subtract and
//! two adds) plus a step after each.
//!
//! *Why these corners suffice (real arithmetic).* Let `g_ij` be the f32 corner values
//! now (`-mn_lo` for the min patch, `mx_hi` for the max patch) and G their exact
//! bilinear interpolant. Proof 1 of the claim only uses that each corner value is <=
//! every `f_k` at that corner (for the min), so `G >= -m` (min patch) and `G >= M` (max
//! patch) on the whole square: a covered sample has `G(l_s, t_s) > 0`. Everything
//! below is rounded so that it keeps every (l, t) with `G(l, t) >= 0`.
//!
//! *Reject and ranges.* The tile is Empty when all four `g_ij < 0` (exact comparisons;
//! G < 0 on the square). For t: G is affine in l, so `G(l_s, t) >= 0` needs
//! `G(-1, t) >= 0` or `G(1, t) >= 0`; the crossing of a chord `(1-t) a + t b` that
//! changes sign is `t* = |a| / (|a| + |b|)`, and `la2011`'s chord, given `-a, -b`,
//! keeps `[t_lo, 1]` with `t_lo = next_down(-a / next_up(fl(b - a)))` when it rises (a
//! quotient of positive numbers with the denominator rounded up is below t*, its
//! rounding is enclosed by the step) and `[0, t_hi]`,
//! `t_hi = next_up(-a / next_up(fl(b - a)))` (the same quotient: both negative) when it falls (a zero or non-finite
//! quotient gives the whole [0, 1]); the same for l in sigma = (l + 1)/2 along t = 0 and
//! t = 1, and `l = 2 sigma - 1` is one fused multiply-add (`2 sigma` is exact, so it is
//! `fl(2 sigma - 1)`) stepped outward. The corner values are pinned (`F32Arith::pin`)
//! as upper ends of `-m` and `M` at the corners: from there on the patch is the one
//! through them, exact, and every range is an end of its exact counterpart.
//!
//! *Per-sample evaluation: one padded coefficient.* `eval` stays the plain f32
//! `fl(fl(P + fl(Q l)) + fl(t fl(R + fl(S l))))` with the rounded coefficients
//! `P~, Q~, R~, S~` of `Patch::from_corners`; only `P` is raised by a pad. The
//! machine-checked bound is the Gappa script `src/bounds/proofs/lb2011_safe.g`
//! (`docs/proofs.md` §3c: about 25 ulps of `mg = max |g_ij|` against the pad's 32, in
//! the error model `|fl(z) - z| <= 2^-23 |fl(z)| + 2^-149`); the same bound in Higham's
//! style, u = 2^-24, `eta = 2^-150` (the absolute error of a product or halving that
//! underflows; a sum that underflows is exact), for |l| <= 1 and t in [0, 1] (the
//! domain; a covered sample lies in it):
//! - coefficients: `|P~ - P|, |Q~ - Q| <= u mg + eta` (one rounded sum, an exact or
//!   underflowing halving); `R~ = fl(fl(fl(g01 + g11) 0.5) - P~)` errs by the half-sum's
//!   `u mg + eta`, `P~`'s `u mg + eta` and its own `u |R~| <= 2u mg (1 + u) + 2u eta`:
//!   `|R~ - R|, |S~ - S| <= 4.01 u mg + 2.01 eta`, so the coefficients move the patch
//!   by at most `Ec = |dP| + |dQ| + |dR| + |dS| <= 10.1 u mg + 7 eta` on the square;
//!   `|P~|, |Q~| <= 1.001 mg + eta`, `|R~|, |S~| <= 2.001 mg + 3 eta`;
//! - `eval`: at most 4 roundings on any path (`S l` then `R +`, `t *`, the last `+`),
//!   so `|eval - (P' + Q~ l + t (R~ + S~ l))| <= gamma_4 (|P'| + |Q~| + |R~| + |S~|) + 3.01 eta`,
//!   `gamma_4 = 4u / (1 - 4u) <= 4.01 u`, with `P' = next_up(fl(P~ + pad)) >= P~ + pad`
//!   and `|P'| <= 1.001 (mg + pad) + 2^-148`.
//!
//! So `eval >= G - Ec + pad - gamma_4 (6.01 mg + 1.001 pad) - 4 eta >= G` as soon as
//! `pad >= 35 u mg + 13 eta`. The pad is computed as `fl(mg 2^-18 + 2^-140)`: the
//! scaling is exact or underflows by at most eta, the sum rounds down by at most a
//! factor (1 - u), so `pad >= 63.9 u mg + 2^-141`, enough. A patch with `mg >= 2^120`
//! (or a NaN corner value: `mg` is a NaN-propagating max) is dropped: the bound assumes
//! no overflow, and below the limit the script bounds every rounded value of the
//! evaluation below 2^125, so `lb2011`'s `usable` test is not needed.
//! The padded coefficient is stored in the same `Patch`, so `eval_box` (which encloses
//! the f32 `eval` of any stored coefficients, see above) is unchanged and still
//! encloses it. Cost: per patch and tile a max over 4 values, a multiply, two adds and
//! a step; per sample nothing (the same 3 multiply-adds).
//!
//! *What it costs in tightness.* Corner values move outward by a few ulps of
//! `|p - X w| + |k c|`, interval ends by a few ulps, and every patch by `2^-18 mg`
//! (about 32 ulps of its largest corner value; in clip units, 4e-3 w for a corner value
//! of 1000 px w): far below the resolution of any STE figure. On the gate's seed 1 the
//! fractions of tile samples admitted agree with `lb2011` to 1e-5 in every regime (far
//! from the origin `lb2011-safe` admits slightly fewer: the FMA is more accurate than
//! `lb2011`'s rounded product).
//!
//! # Grids
//! Each axis's corner values, patch ranges and patches read only that axis's two tile
//! edges, so over a grid of tiles ([`Prepared::grid`]) they are computed once per column
//! (x, u) and once per row (y, v); a tile meets its column's t with its row's two t
//! ranges in the order `tile` uses and boxes the two axes' patches (`PatchGrid`). Both
//! variants (each a `Parts`: an axis's part from its two edges); the answers are
//! `tile`'s bit for bit (`grid_tests.rs`).

use super::la2011::chord_nonpos;
use super::*;
use crate::bounds::arith::{F32Arith, Plain, TriOf};
use crate::bounds::round::{Outward, Round};
use std::marker::PhantomData;

mod safe;
pub use safe::{
    axis_answer, axis_of, coefficients, largest, SafeAxis, SafePatch, CORNER_LEMMA, EVAL_LEMMA, FLOOR, LIMIT, PAD,
};

/// `[min, max]` corner values of one axis, each indexed `[lens index][shutter end]`.
type Corners = [[[f32; 2]; 2]; 2];

/// One screen axis at the two shutter ends (index e = 0 at t = 0, 1 at t = 1), for
/// `lb2011` (f32, rounded to nearest).
#[derive(Clone, Copy, Debug)]
struct Axis {
    /// Vertex position on this axis (x or y), clip space.
    p: [[f32; 3]; 2],
    w: [[f32; 3]; 2],
    /// Lens shear per unit lens coordinate: `c` for x, `fl(k c)` for y.
    s: [[f32; 3]; 2],
}

impl Axis {
    fn new(tri: &Triangle, axis: usize, scale: f32) -> Axis {
        Axis {
            p: [tri.q.map(|v| v[axis]), tri.r.map(|v| v[axis])],
            w: [tri.q.map(|v| v[3]), tri.r.map(|v| v[3])],
            s: [tri.c0.map(|c| scale * c), tri.c1.map(|c| scale * c)],
        }
    }

    /// Corner values `[min, max]`, each indexed `[lens index (0: -1, 1: +1)][end]`, of
    /// `d + l s` over the 3 vertices and both columns; None if any is NaN.
    fn corners(&self, lo: f32, hi: f32) -> Option<Corners> {
        let mut mn = [[f32::INFINITY; 2]; 2];
        let mut mx = [[f32::NEG_INFINITY; 2]; 2];
        for e in 0..2 {
            for i in 0..3 {
                for x in [lo, hi] {
                    let d = self.p[e][i] - x * self.w[e][i];
                    for (li, val) in [(0, d - self.s[e][i]), (1, d + self.s[e][i])] {
                        if val.is_nan() {
                            return None;
                        }
                        mn[li][e] = mn[li][e].min(val);
                        mx[li][e] = mx[li][e].max(val);
                    }
                }
            }
        }
        Some([mn, mx])
    }
}

/// Which lens coordinate a patch reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Lens {
    U,
    V,
}

/// One bilinear patch as a per-sample constraint: `g(l, t) = P + Q l + t (R + S l)`,
/// the sample is culled when g < 0.
#[derive(Clone, Copy, Debug)]
pub struct Patch {
    name: &'static str,
    lens: Lens,
    p: f32,
    q: f32,
    r: f32,
    s: f32,
}

/// The patch's value `fl(fl(P + fl(Q l)) + fl(t fl(R + fl(S l))))` over any
/// [`F32Arith`], for the coefficients `[P, Q, R, S]`: what [`Patch::eval`] computes.
#[inline(always)]
pub fn eval_of<A: F32Arith>(ar: &A, c: &[A::F; 4], l: &A::F, t: &A::F) -> A::F {
    ar.add(&ar.add(&c[0], &ar.mul(&c[1], l)), &ar.mul(t, &ar.add(&c[2], &ar.mul(&c[3], l))))
}

impl Patch {
    /// From the g values at (l, t) = (-1, 0), (1, 0), (-1, 1), (1, 1).
    fn from_corners(name: &'static str, lens: Lens, g: [[f32; 2]; 2]) -> Patch {
        let [p, q, r, s] = coefficients(&Plain, &g);
        Patch { name, lens, p, q, r, s }
    }
    /// True when every coefficient is finite and `|P| + |Q| + |R| + |S| < 2^125`, so
    /// that no f32 intermediate of `eval` can overflow for |l| <= 1, 0 <= t <= 1.
    fn usable(&self) -> bool {
        let m = [self.p, self.q, self.r, self.s].iter().map(|c| c.abs() as f64).sum::<f64>();
        m < 2f64.powi(125)
    }
    /// The magnitude sum over lens values `l` and times `t` and the bound on `eval`'s
    /// error it gives (module doc, "Per-sample evaluation").
    fn error_over(&self, l: Interval, t: Interval) -> (f64, f64) {
        let lm = l.lo.abs().max(l.hi.abs());
        let tm = t.lo.abs().max(t.hi.abs());
        let a = |x: f32| (x as f64).abs();
        let mag = a(self.p) + a(self.q) * lm + tm.max(1.0) * (a(self.r) + a(self.s) * lm);
        (mag, mag * 2f64.powi(-20) + 2f64.powi(-146) * (1.0 + lm) * (1.0 + tm))
    }
    fn lens_of(&self, smp: &Sample) -> f32 {
        match self.lens {
            Lens::U => smp.u,
            Lens::V => smp.v,
        }
    }
    fn coef(&self) -> [f32; 4] {
        [self.p, self.q, self.r, self.s]
    }
}

impl SampleConstraint for Patch {
    fn name(&self) -> String {
        self.name.to_string()
    }
    fn eval(&self, smp: &Sample) -> f32 {
        eval_of(&Plain, &self.coef(), &self.lens_of(smp), &smp.t)
    }
    /// `eval` over the columns (the same four operations per sample, side by side).
    fn eval_row(&self, c: &SampleCols, out: &mut [f32]) {
        let ls = match self.lens {
            Lens::U => c.u,
            Lens::V => c.v,
        };
        // (`eval_of` written out: the same operations; the row test checks it bit for bit.)
        let (p, q, r, s) = (self.p, self.q, self.r, self.s);
        for ((o, &l), &t) in out.iter_mut().zip(ls).zip(c.t) {
            *o = (p + q * l) + t * (r + s * l);
        }
    }
    fn eval_box(&self, b: &SampleBox) -> Interval {
        let l = match self.lens {
            Lens::U => b.u,
            Lens::V => b.v,
        };
        let t = b.t;
        let pt = |x: f32| Interval::point(x as f64);
        let val = (pt(self.p) + pt(self.q) * l) + t * (pt(self.r) + pt(self.s) * l);
        let (mag, err) = self.error_over(l, t);
        if mag.is_nan() || mag >= 2f64.powi(126) || val.lo.is_nan() || val.hi.is_nan() || !err.is_finite() {
            return Interval::new(f64::NEG_INFINITY, f64::INFINITY);
        }
        val + Interval::new(-err, err)
    }
    /// The exact patch `P + Q l + R t + S l t`, less the error bound of
    /// [`eval_box`](Self::eval_box) over the box (None where that gives up).
    fn lower_cut(&self, b: &SampleBox) -> Option<Cut> {
        let (l, lb) = match self.lens {
            Lens::U => (b.u, Cut::U),
            Lens::V => (b.v, Cut::V),
        };
        // Where `eval_box` gives up (magnitudes near overflow, or NaN), so does the cut.
        let (mag, err) = self.error_over(l, b.t);
        if !(mag < 2f64.powi(126) && err.is_finite()) {
            return None;
        }
        let mut cut = Cut::zero();
        cut.coef[0] = self.p as f64;
        cut.coef[lb] = self.q as f64;
        cut.coef[Cut::T] = self.r as f64;
        cut.coef[lb | Cut::T] = self.s as f64;
        cut.err = err;
        Some(cut)
    }
}

/// `lb2011`: the patch with these corner values, or None when it cannot cull (no
/// corner < 0) or its `eval` could overflow (a non-finite coefficient, or one so large
/// that `eval` could give inf - inf = NaN, which culls).
fn plain_patch(name: &'static str, lens: Lens, g: [[f32; 2]; 2]) -> Option<Patch> {
    let can_cull = g.iter().flatten().any(|&v| v < 0.0);
    let patch = Patch::from_corners(name, lens, g);
    (can_cull && patch.usable()).then_some(patch)
}

/// `lb2011`: the ranges implied by one patch (g values at the corners, `g[l][e]`): the
/// t where some l has g >= 0 and the l where some t has g >= 0, or None if g < 0 on
/// the whole square.
fn plain_ranges(g: [[f32; 2]; 2]) -> Option<([f32; 2], [f32; 2])> {
    // g >= 0  <=>  -g <= 0: chord_nonpos keeps where its argument line is <= 0.
    let chord = |a: f32, b: f32| chord_nonpos(-a, -b);
    let hull = |a: Option<[f32; 2]>, b: Option<[f32; 2]>| match (a, b) {
        (Some(a), Some(b)) => Some([a[0].min(b[0]), a[1].max(b[1])]),
        (a, b) => a.or(b),
    };
    let t = hull(chord(g[0][0], g[0][1]), chord(g[1][0], g[1][1]))?;
    let sigma = hull(chord(g[0][0], g[1][0]), chord(g[0][1], g[1][1]))?;
    Some((t, [(2.0 * sigma[0] - 1.0).max(-1.0), (2.0 * sigma[1] - 1.0).min(1.0)]))
}

/// What one axis (x with u, or y with v) says of a tile, over any [`F32Arith`]: its
/// part of [`tile_of`]'s answer.
#[derive(Clone, Debug)]
pub struct AxisAnswer<F, B> {
    /// The axis's corner values are finite: its ranges and patches are used (else it
    /// gives nothing: the whole lens range, no patch).
    pub ok: B,
    /// Where `ok`: some patch is < 0 at all four corners (no covered sample: the tile is
    /// Empty).
    pub none: B,
    /// The two patches' t ranges (where `ok` and not `none`).
    pub ts: [[F; 2]; 2],
    /// `[-1, 1]` met with the two patches' lens ranges.
    pub l: [F; 2],
}

/// A tile answer `(reject, t, u, v)` over any [`F32Arith`].
pub type TileAnswer<F, B> = (B, [F; 2], [F; 2], [F; 2]);

/// The tile answer from its column's x part and its row's y part: `[0, 1]` met with
/// x's two t ranges, then y's (in that order), the lens ranges, and the reject (a patch
/// < 0 on its whole square, or an empty range). Both variants, every tile path.
pub fn tile_of<A: F32Arith>(ar: &A, x: &AxisAnswer<A::F, A::B>, y: &AxisAnswer<A::F, A::B>) -> TileAnswer<A::F, A::B> {
    let mut t = [ar.lit(0.0), ar.lit(1.0)];
    for a in [x, y] {
        for r in &a.ts {
            t = [ar.select(&a.ok, &ar.max(&t[0], &r[0]), &t[0]), ar.select(&a.ok, &ar.min(&t[1], &r[1]), &t[1])];
        }
    }
    let lens = |a: &AxisAnswer<A::F, A::B>| {
        [ar.select(&a.ok, &a.l[0], &ar.lit(-1.0)), ar.select(&a.ok, &a.l[1], &ar.lit(1.0))]
    };
    let (u, v) = (lens(x), lens(y));
    let none = ar.or(&ar.and(&x.ok, &x.none), &ar.and(&y.ok, &y.none));
    let empty = [ar.gt(&t[0], &t[1]), ar.gt(&u[0], &u[1]), ar.gt(&v[0], &v[1])];
    (ar.or(&none, &ar.any(&empty)), t, u, v)
}

/// One column's (x, u) or one row's (y, v) part of a tile answer, in f32: the axis's
/// answer and the patches it emits, in order.
struct AxisPart {
    ans: AxisAnswer<f32, bool>,
    patches: Vec<Patch>,
}

/// The part of an axis with no usable corners, or one proving the tile Empty.
fn part_without(ok: bool, none: bool) -> AxisPart {
    AxisPart { ans: AxisAnswer { ok, none, ts: [[0.0, 1.0]; 2], l: [-1.0, 1.0] }, patches: Vec::new() }
}

/// The per-axis computation of one variant: an axis's part for the edges `[lo, hi]` of
/// a column (x) or a row (y).
trait Parts: Send + Sync {
    fn part(&self, y: bool, edges: [f32; 2]) -> AxisPart;
}

const NAMES: [[&str; 2]; 2] = [
    ["x1 patch (min delta, u-t)", "x0 patch (max delta, u-t)"],
    ["y1 patch (min eps, v-t)", "y0 patch (max eps, v-t)"],
];

/// `lb2011`'s axes.
struct PlainParts {
    x: Axis,
    y: Axis,
}

impl Parts for PlainParts {
    fn part(&self, y: bool, [lo, hi]: [f32; 2]) -> AxisPart {
        let (ax, lens) = if y { (&self.y, Lens::V) } else { (&self.x, Lens::U) };
        let Some([mn, mx]) = ax.corners(lo, hi) else {
            return part_without(false, false);
        };
        // g = -min (culls where the min patch is > 0), g = max (culls where < 0).
        let gs = [mn.map(|r| r.map(|v| -v)), mx];
        let mut part = part_without(true, false);
        for (k, (g, name)) in gs.into_iter().zip(NAMES[y as usize]).enumerate() {
            let Some((t, l)) = plain_ranges(g) else {
                return part_without(true, true);
            };
            part.ans.ts[k] = t;
            part.ans.l = [part.ans.l[0].max(l[0]), part.ans.l[1].min(l[1])];
            part.patches.extend(plain_patch(name, lens, g));
        }
        part
    }
}

/// `lb2011-safe`'s axes (or a planted slip's: the rounding discipline `R`).
struct SafeParts<R> {
    x: SafeAxis<f32>,
    y: SafeAxis<f32>,
    round: PhantomData<fn() -> R>,
}

impl<R: Round> Parts for SafeParts<R> {
    fn part(&self, y: bool, [lo, hi]: [f32; 2]) -> AxisPart {
        let (ax, lens) = if y { (&self.y, Lens::V) } else { (&self.x, Lens::U) };
        // (An axis without corners emits nothing: `emit` holds `ok`; one that proves the
        // tile Empty is never read past its reject.)
        let (ans, patches) = axis_answer::<R, Plain>(&Plain, ax, &lo, &hi);
        let emitted = patches.iter().zip(NAMES[y as usize]).filter(|(p, _)| p.emit);
        let patches = emitted.map(|(p, name)| {
            let [p, q, r, s] = p.coef;
            Patch { name, lens, p, q, r, s }
        });
        AxisPart { ans, patches: patches.collect() }
    }
}

/// The tile answer from an x part and a y part ([`tile_of`] in f32, then the patches
/// of both, x's first).
fn answer(x: &AxisPart, y: &AxisPart) -> TileResult {
    let (reject, t, u, v) = tile_of(&Plain, &x.ans, &y.ans);
    if reject {
        return TileResult::Empty;
    }
    let mut constraints: Vec<Box<dyn SampleConstraint>> = Vec::with_capacity(x.patches.len() + y.patches.len());
    for &p in x.patches.iter().chain(&y.patches) {
        constraints.push(Box::new(p));
    }
    TileResult::Bounds(TileBounds { u, v, t, z: None, constraints })
}

struct Prep<P> {
    parts: P,
}

impl<P: Parts> Prepared for Prep<P> {
    fn tile(&self, tile: &Tile) -> TileResult {
        answer(&self.parts.part(false, [tile.x0, tile.x1]), &self.parts.part(true, [tile.y0, tile.y1]))
    }
    /// Each axis's corners, patch ranges and patches read only its own two tile edges:
    /// computed once per column (x) and once per row (y), then met per tile as
    /// [`tile`](Self::tile) meets them (see [`PatchGrid`]).
    fn grid<'a>(&'a self, grid: Grid<'a>) -> Box<dyn TileGrid + 'a> {
        let cols = (0..grid.columns()).map(|i| self.parts.part(false, grid.column(i))).collect();
        let rows = (0..grid.rows()).map(|j| self.parts.part(true, grid.row(j))).collect();
        Box::new(PatchGrid { cols, rows })
    }
}

/// [`Prep::grid`]: per column the x part and per row the y part ([`AxisPart`]), met per
/// tile by [`answer`].
struct PatchGrid {
    cols: Vec<AxisPart>,
    rows: Vec<AxisPart>,
}

impl TileGrid for PatchGrid {
    fn tile(&self, i: usize, j: usize) -> TileResult {
        answer(&self.cols[i], &self.rows[j])
    }
}

/// `lb2011`: the published test in f32.
struct Lb2011 {
    info: &'static MethodInfo,
}

pub(crate) static INFO: MethodInfo = MethodInfo {
    id: "lb2011",
    source: "reconstruction of Laine & Karras 2011, NVR-2011-004 (LK11), as described in \
             Munkberg & Akenine-Möller 2012 §1, §2.1 (under Eq. 1) and Table 3; per \
             docs/reconstructions.md: four bilinear patches in u-t / v-t of the \
             min / max of delta = x + u c - X w over a tile's columns, evaluated per sample",
    reconstruction: true,
    dims: &[Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: true, time: true, depth: false, per_sample: true },
};

impl Method for Lb2011 {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(Prep { parts: PlainParts { x: Axis::new(tri, 0, 1.0), y: Axis::new(tri, 1, tri.k) } })
    }
}

pub static METHOD: &dyn Method = &Lb2011 { info: &INFO };

/// `lb2011-safe` (`R = Outward`), or a planted slip in its arithmetic.
pub(crate) struct Lb2011Safe<R> {
    pub(crate) info: &'static MethodInfo,
    pub(crate) round: PhantomData<fn() -> R>,
}

static INFO_SAFE: MethodInfo = MethodInfo {
    id: "lb2011-safe",
    source: "reconstruction of Laine & Karras 2011, NVR-2011-004 (LK11), as described in \
             Munkberg & Akenine-Möller 2012 §1, §2.1 (under Eq. 1) and Table 3; per \
             docs/reconstructions.md: four bilinear patches in u-t / v-t of the \
             min / max of delta = x + u c - X w over a tile's columns, evaluated per sample; \
             with every corner value, interval end and patch rounded outward by a bound on \
             its f32 error (error analysis in this file): conservative for every finite input",
    ..INFO
};

impl<R: Round> Method for Lb2011Safe<R> {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        let tri = TriOf::of(tri);
        let axis = |a| safe::axis_of::<R, Plain>(&Plain, &tri, a);
        Box::new(Prep { parts: SafeParts::<R> { x: axis(0), y: axis(1), round: PhantomData } })
    }
}

/// `lb2011-safe`: lb2011 rounded outward (see the module's error analysis).
pub static METHOD_SAFE: &dyn Method = &Lb2011Safe::<Outward> { info: &INFO_SAFE, round: PhantomData };

#[cfg(test)]
mod grid_cases;

#[cfg(test)]
mod tests;
