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
//! algorithm is needed: `lb2011-safe` is the same algorithm (one code path, `Arith`
//! chooses the arithmetic) with every quantity the answer depends on rounded outward.
//! Nothing else changes: the same corners, ranges, reject and four patches.
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
//! changes sign is `t* = |a| / (|a| + |b|)`, and `chord_nonneg_safe` keeps `[t_lo, 1]`
//! with `t_lo = next_down(|a| / next_up(fl(|a| + |b|)))` when it rises (a quotient of
//! positive numbers with the denominator rounded up is below t*, its rounding is
//! enclosed by the step) and `[0, t_hi]`, `t_hi = next_up(|a| / next_down(fl(|a| +
//! |b|)))` when it falls (a zero or non-finite quotient gives the whole [0, 1]); the
//! same for l in sigma = (l + 1)/2 along t = 0 and t = 1, and `l = 2 sigma - 1` is
//! rounded outward by one step (`2 sigma` is exact).
//!
//! *Per-sample evaluation: one padded coefficient.* `eval` stays the plain f32
//! `fl(fl(P + fl(Q l)) + fl(t fl(R + fl(S l))))` with the rounded coefficients
//! `P~, Q~, R~, S~` of `Patch::from_corners`; only `P` is raised by a pad. Error
//! bound in Higham's style, u = 2^-24, `eta = 2^-150` (the absolute error of a product
//! or halving that underflows; a sum that underflows is exact), `mg = max |g_ij|`, for
//! |l| <= 1 and t in [0, 1] (the domain; a covered sample lies in it):
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
//! is dropped (the bound assumes no overflow; `usable` drops the rest as before).
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
//! variants; the answers are `tile`'s bit for bit (`grid_tests.rs`).

use super::la2011::chord_nonpos;
use super::*;

/// `[min, max]` corner values of one axis, each indexed `[lens index][shutter end]`.
type Corners = [[[f32; 2]; 2]; 2];

/// One screen axis at the two shutter ends (index e = 0 at t = 0, 1 at t = 1).
#[derive(Clone, Copy, Debug)]
struct Axis {
    /// Vertex position on this axis (x or y), clip space.
    p: [[f32; 3]; 2],
    w: [[f32; 3]; 2],
    /// Lens shear per unit lens coordinate: `c` for x, `k c` for y.
    s: [[f32; 3]; 2],
    /// True when `s` is exact (`1 c` for x); else `fl(k c)`, one rounding off `k c`.
    s_exact: bool,
}

impl Axis {
    fn new(tri: &Triangle, axis: usize, scale: f32) -> Axis {
        Axis {
            p: [tri.q.map(|v| v[axis]), tri.r.map(|v| v[axis])],
            w: [tri.q.map(|v| v[3]), tri.r.map(|v| v[3])],
            s: [tri.c0.map(|c| scale * c), tri.c1.map(|c| scale * c)],
            s_exact: scale == 1.0,
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

    /// `lb2011-safe`: the same corner values as [`corners`](Self::corners) rounded
    /// outward (f32 interval arithmetic, one `next_up` / `next_down` step after every
    /// rounded operation): `[lower bounds of the min, upper bounds of the max]` of the
    /// exact `p - X w + l k c`. None if any is NaN or infinite.
    fn corners_safe(&self, lo: f32, hi: f32) -> Option<Corners> {
        let mut mn = [[f32::INFINITY; 2]; 2];
        let mut mx = [[f32::NEG_INFINITY; 2]; 2];
        for e in 0..2 {
            for i in 0..3 {
                let s = self.s[e][i];
                let (s_lo, s_hi) = if self.s_exact { (s, s) } else { (s.next_down(), s.next_up()) };
                for x in [lo, hi] {
                    // p - X w with one rounding (fused multiply-add), enclosed by a step.
                    let a = (-x).mul_add(self.w[e][i], self.p[e][i]);
                    let (a_lo, a_hi) = (a.next_down(), a.next_up());
                    let lows = [(a_lo - s_hi).next_down(), (a_lo + s_lo).next_down()];
                    let highs = [(a_hi - s_lo).next_up(), (a_hi + s_hi).next_up()];
                    for li in 0..2 {
                        if !(lows[li].is_finite() && highs[li].is_finite()) {
                            return None;
                        }
                        mn[li][e] = mn[li][e].min(lows[li]);
                        mx[li][e] = mx[li][e].max(highs[li]);
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

impl Patch {
    /// From the g values at (l, t) = (-1, 0), (1, 0), (-1, 1), (1, 1).
    fn from_corners(name: &'static str, lens: Lens, g: [[f32; 2]; 2]) -> Patch {
        let (g00, g10, g01, g11) = (g[0][0], g[1][0], g[0][1], g[1][1]);
        let p = (g00 + g10) * 0.5;
        let q = (g10 - g00) * 0.5;
        let r = (g01 + g11) * 0.5 - p;
        let s = (g11 - g01) * 0.5 - q;
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
}

impl SampleConstraint for Patch {
    fn name(&self) -> String {
        self.name.to_string()
    }
    fn eval(&self, smp: &Sample) -> f32 {
        let l = self.lens_of(smp);
        let t = smp.t;
        (self.p + self.q * l) + t * (self.r + self.s * l)
    }
    /// `eval` over the columns (the same four operations per sample, side by side).
    fn eval_row(&self, c: &SampleCols, out: &mut [f32]) {
        let ls = match self.lens {
            Lens::U => c.u,
            Lens::V => c.v,
        };
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

/// The arithmetic of one variant: `lb2011` (f32 rounded to nearest, the published
/// test) or `lb2011-safe` (every quantity rounded outward). The algorithm
/// ([`patch_ranges`], [`Prep::tile`]) is shared.
struct Arith {
    /// `[min, max]` corner values of one axis for the tile's columns (or rows); see
    /// [`Axis::corners`].
    corners: fn(&Axis, f32, f32) -> Option<Corners>,
    /// The part of [0, 1] where the chord `(1-t) a + t b` is >= 0; None if it is < 0
    /// on all of it.
    chord: fn(f32, f32) -> Option<[f32; 2]>,
    /// The lens range `2 sigma - 1` (within [-1, 1]) of a range of sigma in [0, 1].
    lens: fn([f32; 2]) -> [f32; 2],
    /// The constraint of a patch with these corner values, or None to emit none.
    patch: fn(&'static str, Lens, [[f32; 2]; 2]) -> Option<Patch>,
}

/// The published arithmetic (f32, round to nearest, no epsilon).
static PLAIN: Arith = Arith {
    corners: Axis::corners,
    // g >= 0  <=>  -g <= 0: chord_nonpos keeps where its argument line is <= 0.
    chord: |a, b| chord_nonpos(-a, -b),
    lens: |sigma| [(2.0 * sigma[0] - 1.0).max(-1.0), (2.0 * sigma[1] - 1.0).min(1.0)],
    patch: |name, lens, g| {
        let can_cull = g.iter().flatten().any(|&v| v < 0.0);
        let patch = Patch::from_corners(name, lens, g);
        // A non-finite coefficient, or one so large that `eval` could overflow to
        // inf - inf = NaN (which culls), drops the patch.
        (can_cull && patch.usable()).then_some(patch)
    },
};

/// `lb2011-safe`'s arithmetic: outward rounding (see the module's error analysis).
static SAFE: Arith =
    Arith { corners: Axis::corners_safe, chord: chord_nonneg_safe, lens: lens_safe, patch: patch_safe };

/// `lb2011-safe`: the part of [0, 1] where `(1-t) a + t b >= 0`, rounded outward (a, b
/// finite). The crossing `t* = a / (a - b)` is a quotient of two positive numbers when
/// the chord changes sign; its lower bound divides by an upper bound of the denominator
/// and steps down, its upper bound divides by a lower bound and steps up.
fn chord_nonneg_safe(a: f32, b: f32) -> Option<[f32; 2]> {
    if a < 0.0 && b < 0.0 {
        None
    } else if a < 0.0 {
        // Rising through 0: kept [t*, 1], t* = (-a) / ((-a) + b), -a > 0, b >= 0. The
        // denominator rounds to >= -a > 0; an overflow to inf gives 0 (still below t*).
        let t = (-a / (b - a).next_up()).next_down();
        Some([t.max(0.0), 1.0])
    } else if b < 0.0 {
        // Falling through 0: kept [0, t*], t* = a / (a + (-b)), a >= 0, -b > 0. The
        // lower bound of the denominator can be 0 (a = 0, b = -2^-149): the quotient is
        // then NaN or inf, and the range the whole [0, 1].
        let t = (a / (a - b).next_down()).next_up();
        Some([0.0, if (0.0..1.0).contains(&t) { t } else { 1.0 }])
    } else {
        Some([0.0, 1.0])
    }
}

/// `lb2011-safe`: `l = 2 sigma - 1` rounded outward (`2 sigma` is exact, the difference
/// is rounded once: one step encloses it).
fn lens_safe(sigma: [f32; 2]) -> [f32; 2] {
    [(2.0 * sigma[0] - 1.0).next_down().max(-1.0), (2.0 * sigma[1] - 1.0).next_up().min(1.0)]
}

/// `lb2011-safe`: the patch with its constant coefficient raised by
/// `pad = 2^-18 mg + 2^-140` (mg the largest |corner value|), so that its f32 `eval`
/// is >= the exact bilinear interpolant of the corner values for |l| <= 1, t in
/// [0, 1] (module doc, "Per-sample evaluation"). None when no corner is < 0 (it cannot
/// cull) or mg >= 2^120 (the analysis assumes no overflow; dropping a patch is always
/// conservative).
fn patch_safe(name: &'static str, lens: Lens, g: [[f32; 2]; 2]) -> Option<Patch> {
    const PAD: f32 = 1.0 / (1u32 << 18) as f32; // 2^-18 = 64 u
    const FLOOR: f32 = 1.0 / (1u128 << 120) as f32 / (1u32 << 20) as f32; // 2^-140
    const LIMIT: f32 = (1u128 << 120) as f32; // 2^120
    if !g.iter().flatten().any(|&v| v < 0.0) {
        return None;
    }
    let mg = g.iter().flatten().fold(0.0f32, |m, v| m.max(v.abs()));
    // (A NaN cannot reach here: corners are finite.)
    if mg >= LIMIT || mg.is_nan() {
        return None;
    }
    let mut patch = Patch::from_corners(name, lens, g);
    patch.p = (patch.p + (mg * PAD + FLOOR)).next_up();
    patch.usable().then_some(patch)
}

/// Ranges implied by one patch (g values at the corners, `g[l][e]`): the t where some
/// l has g >= 0 and the l where some t has g >= 0, or None if g < 0 on the whole square.
fn patch_ranges(ar: &Arith, g: [[f32; 2]; 2]) -> Option<([f32; 2], [f32; 2])> {
    let hull = |a: Option<[f32; 2]>, b: Option<[f32; 2]>| match (a, b) {
        (Some(a), Some(b)) => Some([a[0].min(b[0]), a[1].max(b[1])]),
        (a, b) => a.or(b),
    };
    let t = hull((ar.chord)(g[0][0], g[0][1]), (ar.chord)(g[1][0], g[1][1]))?;
    let sigma = hull((ar.chord)(g[0][0], g[1][0]), (ar.chord)(g[0][1], g[1][1]))?;
    Some((t, (ar.lens)(sigma)))
}

struct Prep {
    x: Axis,
    y: Axis,
    arith: &'static Arith,
}

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let ar = self.arith;
        let mut out = TileBounds::full();
        let axes = [
            (&self.x, tile.x0, tile.x1, Lens::U, ["x1 patch (min delta, u-t)", "x0 patch (max delta, u-t)"]),
            (&self.y, tile.y0, tile.y1, Lens::V, ["y1 patch (min eps, v-t)", "y0 patch (max eps, v-t)"]),
        ];
        for (ax, lo, hi, lens, names) in axes {
            let Some([mn, mx]) = (ar.corners)(ax, lo, hi) else {
                continue;
            };
            // g = -min (culls where the min patch is > 0), g = max (culls where < 0).
            let gs = [mn.map(|r| r.map(|v| -v)), mx];
            for (g, name) in gs.into_iter().zip(names) {
                let Some((t, l)) = patch_ranges(ar, g) else {
                    return TileResult::Empty;
                };
                out.t = [out.t[0].max(t[0]), out.t[1].min(t[1])];
                let lr = if lens == Lens::U { &mut out.u } else { &mut out.v };
                *lr = [lr[0].max(l[0]), lr[1].min(l[1])];
                if let Some(patch) = (ar.patch)(name, lens, g) {
                    out.constraints.push(Box::new(patch));
                }
            }
        }
        if out.t[0] > out.t[1] || out.u[0] > out.u[1] || out.v[0] > out.v[1] {
            return TileResult::Empty;
        }
        TileResult::Bounds(out)
    }
    /// Each axis's corners, patch ranges and patches read only its own two tile edges:
    /// computed once per column (x) and once per row (y), then met per tile in
    /// [`tile`](Self::tile)'s order (see [`PatchGrid`]).
    fn grid<'a>(&'a self, grid: Grid<'a>) -> Box<dyn TileGrid + 'a> {
        let x = ["x1 patch (min delta, u-t)", "x0 patch (max delta, u-t)"];
        let y = ["y1 patch (min eps, v-t)", "y0 patch (max eps, v-t)"];
        let cols = (0..grid.columns()).map(|i| self.axis_part(&self.x, grid.column(i), Lens::U, x)).collect();
        let rows = (0..grid.rows()).map(|j| self.axis_part(&self.y, grid.row(j), Lens::V, y)).collect();
        Box::new(PatchGrid { cols, rows })
    }
}

impl Prep {
    /// One axis's part of [`tile`](Prepared::tile) for the edges `[lo, hi]` of a column
    /// (or row), in the same operations: None when a patch proves the tile Empty.
    fn axis_part(&self, ax: &Axis, [lo, hi]: [f32; 2], lens: Lens, names: [&'static str; 2]) -> Option<AxisPart> {
        let ar = self.arith;
        let full = TileBounds::full();
        let mut part = AxisPart { t: full.t, ts: None, l: full.u, patches: Vec::new() };
        let Some([mn, mx]) = (ar.corners)(ax, lo, hi) else {
            return Some(part);
        };
        let gs = [mn.map(|r| r.map(|v| -v)), mx];
        let mut ts = [[0.0; 2]; 2];
        for ((g, name), tr) in gs.into_iter().zip(names).zip(&mut ts) {
            let (t, l) = patch_ranges(ar, g)?;
            *tr = t;
            part.t = [part.t[0].max(t[0]), part.t[1].min(t[1])];
            part.l = [part.l[0].max(l[0]), part.l[1].min(l[1])];
            part.patches.extend((ar.patch)(name, lens, g));
        }
        part.ts = Some(ts);
        Some(part)
    }
}

/// One column's (x, u) or one row's (y, v) part of a tile answer ([`Prep::axis_part`]).
struct AxisPart {
    /// `[0, 1]` met with the axis's two patches' t ranges, in order (a column's share of
    /// the tile's t: x comes first).
    t: [f32; 2],
    /// The two patches' t ranges themselves (a row's share, met after x's), or None when
    /// the axis's corners are None (it gives nothing).
    ts: Option<[[f32; 2]; 2]>,
    /// `[-1, 1]` met with the two patches' lens ranges, in order: the tile's u (column)
    /// or v (row).
    l: [f32; 2],
    /// The patches the axis emits, in order.
    patches: Vec<Patch>,
}

/// [`Prep::grid`]: per column the x part and per row the y part ([`AxisPart`]; None:
/// that axis proves every tile of its column / row Empty, as [`tile`](Prepared::tile)'s
/// early return does whichever axis it comes from). Per tile only: the column's t met
/// with the row's two t ranges (f32 `max` / `min` in [`tile`](Prepared::tile)'s order:
/// x's ranges, then y's), the emptiness check and the boxed patches (x's, then y's).
struct PatchGrid {
    cols: Vec<Option<AxisPart>>,
    rows: Vec<Option<AxisPart>>,
}

impl TileGrid for PatchGrid {
    fn tile(&self, i: usize, j: usize) -> TileResult {
        let (Some(x), Some(y)) = (&self.cols[i], &self.rows[j]) else {
            return TileResult::Empty;
        };
        let mut t = x.t;
        for r in y.ts.iter().flatten() {
            t = [t[0].max(r[0]), t[1].min(r[1])];
        }
        let (u, v) = (x.l, y.l);
        if t[0] > t[1] || u[0] > u[1] || v[0] > v[1] {
            return TileResult::Empty;
        }
        let mut constraints: Vec<Box<dyn SampleConstraint>> = Vec::with_capacity(x.patches.len() + y.patches.len());
        for &p in x.patches.iter().chain(&y.patches) {
            constraints.push(Box::new(p));
        }
        TileResult::Bounds(TileBounds { u, v, t, z: None, constraints })
    }
}

/// lb2011 or lb2011-safe: the same algorithm in another arithmetic.
struct Lb2011 {
    info: &'static MethodInfo,
    arith: &'static Arith,
}

static INFO: MethodInfo = MethodInfo {
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
        Box::new(Prep { x: Axis::new(tri, 0, 1.0), y: Axis::new(tri, 1, tri.k), arith: self.arith })
    }
}

pub static METHOD: &dyn Method = &Lb2011 { info: &INFO, arith: &PLAIN };

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

/// `lb2011-safe`: lb2011 rounded outward (see the module's error analysis).
pub static METHOD_SAFE: &dyn Method = &Lb2011 { info: &INFO_SAFE, arith: &SAFE };

#[cfg(test)]
mod grid_cases;

#[cfg(test)]
mod tests;
