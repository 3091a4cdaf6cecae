//! `mam2012`: linear bounds in ut and vt space from bilinear patches.
//!
//! Source: J. Munkberg and T. Akenine-Möller, "Hyperplane Culling for Stochastic
//! Rasterization", Eurographics 2012 short paper: §2.1 (Eq. 1, Figure 3), Figure 5 and
//! Appendix A. The text we work from is that paper itself (Munkberg and Akenine-Möller
//! 2012, "Hyperplane Culling for Stochastic Rasterization", §2.1, Figure 5, Appendix A).
//!
//! # The quantity bounded (Eq. 1 in the model's notation)
//! For a screen column `X` (a tile side `x_i` in the paper), vertex j and time t let
//!
//! `u_j(X, t) = (X w_j(t) - x_j(t)) / c_j(t)`,   `v_j(Y, t) = (Y w_j(t) - y_j(t)) / (k c_j(t))`.
//!
//! This is the paper's `u_ij(t) = n_i^x . p_j(t) / c_j(t)` with `n_i^x = (-1, 0, x_i)` and
//! `p = (x, y, w)`: no conversion is needed, because the paper shears a vertex exactly as
//! the model does (`p' = p + c (u, k v, 0)`, Appendix B) and both use clip-space x, y, w.
//! (Appendix A prints the numerator as `x p_jx - p_jx`; it is `x p_jw - p_jx`.)
//! `u_j(X, t)` is the lens coordinate from which vertex j's sheared image lies exactly on
//! column X: the dual-space value `delta_j(X, u, t) = x_j + u c_j - X w_j` equals
//! `c_j(t) (u - u_j(X, t))`.
//!
//! # Why `u` is bounded by the `u_j` (real arithmetic)
//! An interior-covered sample (x, y, u, v, t) has weights `lambda_j > 0` and `mu > 0`
//! with `sum_j lambda_j P'_j = mu (x, y, 1)` (the model's two-sided rule with a hit in
//! front of the lens), so `sum_j lambda_j delta_j(x, u, t) = 0`: the three `delta_j(x)`
//! are not all of one strict sign. If every `c_j(t)` has the same strict sign, `delta_j`
//! has the sign of `u - u_j(x, t)` (or the opposite sign for all j), so a covered sample
//! has `min_j u_j(x, t) <= u <= max_j u_j(x, t)`. This holds at every pixel column x,
//! for any sign of w. It needs all six `c_j0, c_j1` non-zero and of one sign:
//! - if a `c_j(t)` is 0 somewhere in the shutter, `u_j` has a pole (the paper: "if the
//!   triangle intersects the focal plane, e.g., c_j(t) = 0, ... the culling test is
//!   disabled");
//! - if the vertices' CoC have different (constant) signs the triangle straddles the
//!   focal plane without any vertex crossing it; then `u > max u_j` moves the c > 0
//!   vertices right and the c < 0 vertices left, the triangle spans the column, and the
//!   interval `[min u_j, max u_j]` is NOT a bound (test
//!   `mixed_coc_signs_need_disabling` holds a witness). We read the paper's "the triangle
//!   intersects the focal plane" as covering this case and disable the test too.
//!
//! # Figure 5: linear bounds of the rational curve
//! For fixed X, `f(t) = N(t) / C(t)` with `N = X w_j - x_j` and `C = c_j` (or `k c_j`)
//! linear in t. `f' = K / C^2` with the constant `K = N1 C0 - N0 C1`, and
//! `f'' = -2 K C' / C^3`: with C != 0 on [0, 1], f is monotone (increasing iff K > 0)
//! and either convex (iff `K C' C < 0`, e.g. a vertex behind the focal plane moving away,
//! C > 0 growing, with u decreasing) or concave (`K C' C > 0`) on the whole shutter, and
//! linear when `K C' = 0` (constant CoC, or `N` proportional to `C`). The chord
//! `u_a(t) = f(0) + t (f(1) - f(0))` and the tangent at 1/2,
//! `u_b(t) = f(1/2) + (t - 1/2) f'(1/2)` with `f'(1/2) = K / C(1/2)^2`, are then one an
//! upper and one a lower bound (convex: tangent below, chord above; concave: the
//! reverse), so `min(u_a, u_b) <= f <= max(u_a, u_b)` on [0, 1] in every case. How much
//! `w_j` or `c_j` change (large perspective motion) does not matter for validity: `C`
//! has no zero in [0, 1] by the enabling test, so the curve has no inflection there. It
//! only matters for tightness: when `c_j(t)` comes close to 0 the curve bends sharply and
//! the tangent at 1/2 lies far from f at one end ("a hard case for our coarser
//! approximation is triangles with large perspective motion").
//!
//! **Misprint.** Figure 5 of our copy prints `u_b(t) = u(1/2) - 1/2 u'(1/2) + t 1/2 u'(1/2)`,
//! a line of slope `u'(1/2)/2` that is not the tangent. Used literally in the corner
//! construction below it is not conservative for a decreasing convex curve (the line from
//! the tangent's value at t = 0 to f(1) cuts above f near t = 1). We implement the
//! tangent; `fig5_as_printed_culls_a_covered_sample` keeps the witness.
//!
//! # Appendix A: bilinear patches, and lines per tile
//! `u_j(x, t)` is linear in x. Over the patch domain `[xa, xb] x [0, 1]` the lower patch
//! has corner values `L(X, k) = min_j min(u_a, u_b)(k)` for X in {xa, xb}, k in {0, 1}
//! (the chord of the concave `min(u_a, u_b)` lies below it, so the t-lerp of the corner
//! values bounds each `u_j(X, .)` from below; bilinear interpolation is monotone in the
//! corner values and exact for the x-linear `u_j`, so the patch `B(x, t)` bounds
//! `min_j u_j(x, t)` for every x in [xa, xb]). The upper patch uses max instead of min.
//!
//! Per tile `[x0, x1]`, centre `xc`, half width `h`: write `B(x, k) = B(xc, k) + (x - xc) S_k`
//! with the patch's x-slope `S_k` at t = k. Since `|S(t)|` is convex in t,
//! `min_{x in tile} B(x, t) >= (1 - t) l_0 + t l_1` with `l_k = B(xc, k) - h |S_k|` (the
//! paper: "pad the bounds with the half the tile size times the x-slope of the patch, so
//! that we can conservatively evaluate the patch once at the tile-center"). The paper
//! pads with a fixed tile size in the setup; our tiles come in any size, so `h` is the
//! tile's own half width, applied per tile (same value). The lower ut line is
//! `u >= l(t) = l_0 + t (l_1 - l_0)`, the upper `u <= h(t)` likewise with `+ h |S_k|`,
//! and the vt lines the same with y and `k c_j`.
//!
//! The patch domain is the screen x extent of the moving, defocused triangle: vertex j
//! is seen at `(x_j(t) + u c_j(t)) / w_j(t)`, linear in u and (with `w_j > 0` on the
//! shutter) linear-fractional hence monotone in t, so its extremes are at the four
//! corners u = +-1, t = 0, 1; with every w > 0 a covered sample lies in the hull of the
//! projected vertices. A covered sample's x is therefore in [xa, xb], where the patch
//! bounds hold; over the part of a tile outside [xa, xb] nothing is covered, so the
//! padding evaluated over the whole tile is still conservative and tiles outside the
//! domain need no special case. When some `w_j <= 0` in the shutter this extent is
//! unbounded; the paper's rasterizer traverses a finite AABB and says nothing about
//! this case, so the test is disabled ("a vertex has w <= 0 in the shutter").
//!
//! # Outputs
//! - Per-sample constraints (the paper's four "linear interpolations per sample"):
//!   `u - (a t + b) >= 0` (lower ut line, `b = l_0`, `a = l_1 - l_0` in f32), `(a t + b) - u`
//!   for the upper line, and the same two in vt.
//! - Per-tile u^ and v^: the lines evaluated at t = 0 and t = 1 (the paper: "by
//!   evaluating the four bounding lines at t = 0 and t = 1, we get bounds for the u and
//!   v ranges per tile"), `u^ = [min(l_0, l_1), max(h_0, h_1)]` clamped to [-1, 1]; the
//!   tile is rejected when u^ or v^ is empty. t^ stays [0, 1]: the paper derives no time
//!   bound from these lines (the per-sample lines carry the ut correlation). The t range
//!   used is the whole shutter (the paper allows a sub-range `[t0, t1]`, e.g. from
//!   another test; we have none per triangle).
//!
//! # Degenerate input
//! All computation is f32. A value that is not finite (a pole from `c` underflowing, an
//! overflow) makes that patch corner unusable: the corresponding line is dropped (full
//! range on that side, no constraint). NaN is never passed through `min`/`max` (which
//! would silently drop it). A zero-width domain (`xa == xb`) gives slope 0.
//!
//! # f32 rounding
//! The bound is conservative in real arithmetic. In f32, the corner values (`N / C`, the
//! tangent), the screen extent, the tile centre and half width, the per-tile
//! interpolation and the constraint's `a = l_1 - l_0` are rounded, so a covered sample
//! within a few ulps of a line (or of the patch domain edge) can be culled; no epsilon
//! hides this. `eval_box` of each constraint encloses the f32 evaluation of
//! `u - (a t + b)` for the stored f32 `a`, `b`: the real value widened by
//! `2^-20 (|u| + |a t| + |b|) + 2^-140` (three rounded operations cost at most
//! `3 * 2^-24` of that sum, plus denormal absolute errors below `2^-148`).
//!
//! # `mam2012-safe`: the same patches and lines in f32 interval arithmetic
//! `mam2012` above is the published test in f32 and stays as it is (the gate's evidence:
//! f32 rounding at tile corners, margins ~1e-7..3e-5; 1e-2 of the lens at 1e4..1e6 px;
//! covered tiles culled at the reject limit; a whole lens unit near w = 0). `mam2012-safe`
//! computes the same quantities through the same formulas (`fig5_lines`,
//! `numerators`, `projected`, generic over the arithmetic) as **enclosures**, and
//! applies the real-arithmetic derivation above to numbers on the safe side of the
//! exact ones. Every cull is then implied by that derivation.
//! Its code (intervals, patches, lines, setup and tile test) lives in `mam2012/safe.rs`.
//!
//! *Arithmetic: directed steps (f32 interval arithmetic, `IvOps`, written over
//! `F32Arith` like the rest of the variant, so that `cullproof proofs` traces the same
//! code the gate runs: docs/proofs.md, section 4c).* Each operation rounds
//! to nearest and steps each end one f32 outward (`next_down` / `next_up`); products and
//! quotients take the extremes of the four end combinations. It encloses: a result r
//! rounded to nearest from the exact z is within half an ulp of z, and r's neighbour on
//! either side is at least that far (at a power of two the lower neighbour is half an
//! ulp of the binade below away, and z rounded to r lies within half of that), so z is in
//! `[next_down r, next_up r]`; subnormals err by at most 2^-150 and step by 2^-149; a zero
//! from underflow steps to +-2^-149; an overflow to +-inf steps to +-MAX on the inner side
//! (still a bound) and leaves an infinite end. A divisor interval that holds 0 or NaN
//! gives NaN. Directed steps, not a Higham gamma_n running bound, because every quantity
//! chains divisions through cancellations (`X w - x` at 1e6 px, `n1 c0 - n0 c1`, the
//! patch read 1e8 px from its corner near w = 0) whose size a relative bound per
//! formula would have to track case by case; a step costs one ulp per operation,
//! gamma_1's size, and composes mechanically.
//!
//! *What is enclosed, in order.*
//! 1. Disabled (full bounds, never a cull) as `mam2012`, and when any vertex coordinate,
//!    CoC or the aspect is NaN or infinite. Per axis, every `k c_j` at t = 0, 1 must be
//!    an interval of one strict sign, the same for all j (`k c` can underflow to 0, k
//!    can be 0): otherwise that axis has no patch (full u^ or v^, no lines).
//! 2. The patch domain `[xa, xb]` is the hull of the 12 projected corners' intervals, so
//!    it holds the exact screen extent and every covered column; a non-finite end
//!    disables the test.
//! 3. At `X = xa, xb` (f32 values, exact) the chord and tangent ends are intervals; the
//!    lower corner `L(X, k)` is the smallest lower end over vertex, chord and tangent, the
//!    upper `H(X, k)` the largest upper end (NaN propagates: no patch on that side).
//!    The Appendix A argument needs only corner values at or below (above) the exact
//!    `min(u_a, u_b)` (`max`), so the exact bilinear patch through these f32 corner
//!    values bounds every covered u on `[xa, xb] x [0, 1]`.
//! 4. Per tile, the exact patch at t = k is affine in x with slope
//!    `S_k = (L(xb, k) - L(xa, k)) / (xb - xa)`, held as an interval. Over the tile's
//!    columns clamped to `[xa, xb]` (no other column is covered; a tile beside the domain
//!    is Empty) its values are enclosed from both corners, `L(xa) + (x - xa) S` and
//!    `L(xb) + (x - xb) S`, and the two enclosures intersected. The interval over x is
//!    the original's `B(xc) - h |S|` (an affine function's minimum over an interval is at
//!    an end) on the coverable columns; the lower end is `l_k`, the upper patch's upper
//!    end `h_k`.
//! 5. `u^ = [min(l_0, l_1), max(h_0, h_1)]` clamped to [-1, 1] (min, max and clamp are
//!    exact); Empty when u^ or v^ is empty, as in `mam2012`.
//! 6. Lines: lower `b = fl(l_0 - LINE_PAD)` (a rounded difference with a representable
//!    `l_0` never exceeds it), `a = next_down(fl(l_1 - l_0))`, so `a t + b <= l(t)` for
//!    t in [0, 1]; upper mirrored. `eval` computes
//!    `u - next_down(fl(next_down(fl(a t)) + b))`, rounded: the subtrahend is at most
//!    `a t + b`, the exact difference at least `u - l(t) >= 0` for a covered sample, and
//!    rounding to nearest keeps a non-negative number non-negative. `eval_box`'s lower
//!    end is the exact `u - (a t + b)` over the box (outward f64) rounded down to f32
//!    (rounding is monotone), its upper end `mam2012`'s widening `2^-20 (|u| + |a t| +
//!    |b|) + 2^-140` (three roundings and two steps cost under `2^-21` of that sum plus
//!    four subnormal steps).
//!
//! *Lines tight to the covered set.* Where the exact line is attained (a defocused
//! triangle with constant CoC: the extreme `u_j` at a tile side is approached by covered
//! samples) a line a few ulps outside is conservative but the gate's certified box search
//! cannot separate it from the covered set within its budget (304 of 600 defocus cases
//! of seed 1 unproven). `LINE_PAD = 2^-20` lens units (eight ulps at 1) moves each line
//! out far enough to be certified (600 of 600 proven); no STE figure can see 1e-6 of the
//! lens.
//!
//! *Near w = 0: rounding, not a failed assumption.* The issue's "mam2012 misses by 0.25
//! near w = 0" is `stability --family w-zero` at w = 1e-6 (test
//! `safe_keeps_the_near_w0_witness`): vertex 0 at w = 1e-6 at t = 0 projects to 1e8 px,
//! so the y domain is `[-1.2e8, -61]` and the corner values at `ya` are about 4.5e7 (ulp
//! 4). `mam2012` reads the patch at the tile (y near -66) as `B(ya) + (yc - ya) S`: two
//! terms of 4.5e7 cancel to about 1 and keep the rounding of each, whole lens units (its
//! vt upper line at t = 0 is 0.745, the exact patch 1.65). Every w > 0 and every c keeps
//! its sign on the shutter, the same formulas in f64 agree with the exact values, and
//! the derivation holds: nothing but rounding fails. The correction is the
//! evaluation from the nearer corner (item 4) and the enclosure, no change of the
//! bound itself.
//!
//! *Cost.* Setup: each operation twice plus two steps, four products per
//! multiplication or division; tile: two interval evaluations per line end instead of
//! one multiply-add; per sample: two steps more per line.

use super::*;
use crate::bounds::arith::{tile_of, F32Arith, Plain, TriOf};

mod safe;
pub use safe::{answer_of, line_eval, rejects_of, setup_safe_of, SafeAxis, SafeAxisAnswerOf, SafeSetupOf};
pub use safe::{Mam2012Safe, METHOD_SAFE};

/// The bilinear ut / vt test of Munkberg and Akenine-Möller 2012, §2.1.
pub struct Mam2012;

pub(crate) static INFO: MethodInfo = MethodInfo {
    id: "mam2012",
    source: "Munkberg & Akenine-Möller 2012, Hyperplane Culling for Stochastic Rasterization, §2.1 (Eq. 1, Fig. 3, Fig. 5) and Appendix A",
    reconstruction: false,
    dims: &[Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: true, time: false, depth: false, per_sample: true },
};

pub static METHOD: &dyn Method = &Mam2012;

impl Method for Mam2012 {
    fn info(&self) -> &'static MethodInfo {
        &INFO
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(Prep(setup(tri, false)))
    }
}

/// A bilinear patch over `[xa, xb] x [0, 1]`: its values at `x = xa` for t = 0, 1 and
/// its x-slopes at t = 0, 1, numbers of some [`F32Arith`]; `ok` false when the patch is
/// dropped (a non-finite corner value or slope: no line on that side).
#[derive(Clone, Debug)]
pub struct Patch<F, B> {
    ok: B,
    xa: F,
    at_xa: [F; 2],
    slope: [F; 2],
}

impl<F: Clone, B: Clone> Patch<F, B> {
    /// The tile line (values at t = 0 and t = 1) for the tile `[xc - h, xc + h]`:
    /// lowered by `h |S_k|` (`dir = -1`, lower patch) or raised (`dir = 1`); the flag is
    /// false when there is none (no patch, or a non-finite value).
    fn line<A: F32Arith<F = F, B = B>>(&self, ar: &A, xc: &F, h: &F, dir: f32) -> (B, [F; 2]) {
        let dir = ar.lit(dir);
        let e = |k: usize| {
            let at = ar.add(&self.at_xa[k], &ar.mul(&ar.sub(xc, &self.xa), &self.slope[k]));
            ar.add(&at, &ar.mul(&dir, &ar.mul(h, &ar.abs(&self.slope[k]))))
        };
        let l = [e(0), e(1)];
        (ar.all(&[self.ok.clone(), ar.is_finite(&l[0]), ar.is_finite(&l[1])]), l)
    }
}

/// The lower and upper patch of one lens axis (u with x, or v with y).
#[derive(Clone, Debug)]
pub struct Axis<F, B> {
    lo: Patch<F, B>,
    hi: Patch<F, B>,
}

/// Both axes' patches.
#[derive(Clone, Debug)]
pub struct Setup<F, B> {
    u: Axis<F, B>,
    v: Axis<F, B>,
}

struct Prep(Result<Setup<f32, bool>, &'static str>);

/// The arithmetic of the formulas `mam2012` (any [`F32Arith`]: f32, or SMT-LIB2
/// terms) and `mam2012-safe` (intervals of any [`F32Arith`] rounded outward, `IvOps`)
/// share: written once, evaluated in either.
pub trait Ops {
    type T: Clone;
    fn lit(&self, v: f32) -> Self::T;
    fn add(&self, a: &Self::T, b: &Self::T) -> Self::T;
    fn sub(&self, a: &Self::T, b: &Self::T) -> Self::T;
    fn mul(&self, a: &Self::T, b: &Self::T) -> Self::T;
    fn div(&self, a: &Self::T, b: &Self::T) -> Self::T;
}

impl<A: F32Arith> Ops for A {
    type T = A::F;
    fn lit(&self, v: f32) -> A::F {
        F32Arith::lit(self, v)
    }
    fn add(&self, a: &A::F, b: &A::F) -> A::F {
        F32Arith::add(self, a, b)
    }
    fn sub(&self, a: &A::F, b: &A::F) -> A::F {
        F32Arith::sub(self, a, b)
    }
    fn mul(&self, a: &A::F, b: &A::F) -> A::F {
        F32Arith::mul(self, a, b)
    }
    fn div(&self, a: &A::F, b: &A::F) -> A::F {
        F32Arith::div(self, a, b)
    }
}

/// The values at t = 0 and t = 1 of the chord and of the tangent at 1/2 (or, with
/// `literal_fig5`, of Figure 5's printed line) of `f(t) = N(t) / C(t)`.
fn fig5_lines<O: Ops>(o: &O, n: &[O::T; 2], c: &[O::T; 2], literal_fig5: bool) -> ([O::T; 2], [O::T; 2]) {
    let half = o.lit(0.5);
    let chord = [o.div(&n[0], &c[0]), o.div(&n[1], &c[1])];
    let ch = o.mul(&half, &o.add(&c[0], &c[1]));
    let fh = o.div(&o.mul(&half, &o.add(&n[0], &n[1])), &ch);
    let d = o.div(&o.sub(&o.mul(&n[1], &c[0]), &o.mul(&n[0], &c[1])), &o.mul(&ch, &ch));
    let lo = o.sub(&fh, &o.mul(&half, &d));
    let tan = if literal_fig5 { [lo, fh] } else { [lo, o.add(&fh, &o.mul(&half, &d))] };
    (chord, tan)
}

/// `N(t) = X w_j(t) - x_j(t)` at t = 0, 1 for the column `x`.
fn numerators<O: Ops>(o: &O, x: &O::T, w: &[O::T; 2], pos: &[O::T; 2]) -> [O::T; 2] {
    [o.sub(&o.mul(x, &w[0]), &pos[0]), o.sub(&o.mul(x, &w[1]), &pos[1])]
}

/// Vertex j's screen position seen from the lens edge `s = +-1`: `(p + s (kf c)) / w`.
fn projected<O: Ops>(o: &O, p: &O::T, s: f32, kf: &O::T, c: &O::T, w: &O::T) -> O::T {
    o.div(&o.add(p, &o.mul(&o.lit(s), &o.mul(kf, c))), w)
}

/// Lower and upper values at t = 0 and t = 1 of the Figure 5 lines (chord and tangent
/// at 1/2) of `f(t) = N(t) / C(t)`, N and C linear, C != 0 on [0, 1]. With
/// `literal_fig5` the tangent is replaced by the line as printed in Figure 5 (slope
/// `f'(1/2) / 2`; only for the test that shows it is not a bound). Non-finite results
/// give -inf / +inf.
fn fig5_corners_of<A: F32Arith>(ar: &A, n: &[A::F; 2], c: &[A::F; 2], literal_fig5: bool) -> ([A::F; 2], [A::F; 2]) {
    let (chord, tan) = fig5_lines(ar, n, c, literal_fig5);
    let end = |k: usize| {
        let (a, b) = (&chord[k], &tan[k]);
        let fin = ar.and(&ar.is_finite(a), &ar.is_finite(b));
        let lo = ar.select(&fin, &ar.select(&ar.lt(a, b), a, b), &ar.lit(f32::NEG_INFINITY));
        let hi = ar.select(&fin, &ar.select(&ar.gt(a, b), a, b), &ar.lit(f32::INFINITY));
        (lo, hi)
    };
    let ((l0, h0), (l1, h1)) = (end(0), end(1));
    ([l0, l1], [h0, h1])
}

/// [`fig5_corners_of`] in f32.
#[cfg(test)]
fn fig5_corners(n: [f32; 2], c: [f32; 2], literal_fig5: bool) -> ([f32; 2], [f32; 2]) {
    fig5_corners_of(&Plain, &n, &c, literal_fig5)
}

/// Per vertex j, a value at t = 0 and t = 1.
type Ends<F> = [[F; 2]; 3];

/// The patches of one axis: `pos[j]`, `w[j]`, `den[j]` are vertex j's coordinate, w and
/// CoC denominator (`c` or `k c`) at t = 0, 1; `[xa, xb]` the patch domain.
fn axis<A: F32Arith>(
    ar: &A,
    [pos, w, den]: [&Ends<A::F>; 3],
    xa: &A::F,
    xb: &A::F,
    literal_fig5: bool,
) -> Axis<A::F, A::B> {
    // corners[side][k]: side 0 at xa, 1 at xb; k = t end.
    let mut lo = [[(); 2]; 2].map(|r| r.map(|_| ar.lit(f32::INFINITY)));
    let mut hi = [[(); 2]; 2].map(|r| r.map(|_| ar.lit(f32::NEG_INFINITY)));
    for (side, x) in [xa, xb].into_iter().enumerate() {
        for j in 0..3 {
            let n = numerators(ar, x, &w[j], &pos[j]);
            let (l, h) = fig5_corners_of(ar, &n, &den[j], literal_fig5);
            for k in 0..2 {
                // Explicit comparisons: l is never NaN here (fig5_corners maps it to -inf).
                lo[side][k] = ar.select(&ar.lt(&l[k], &lo[side][k]), &l[k], &lo[side][k]);
                hi[side][k] = ar.select(&ar.gt(&h[k], &hi[side][k]), &h[k], &hi[side][k]);
            }
        }
    }
    let width = ar.sub(xb, xa);
    let patch = |c: [[A::F; 2]; 2]| -> Patch<A::F, A::B> {
        let finite = [&c[0][0], &c[0][1], &c[1][0], &c[1][1]].map(|v| ar.is_finite(v));
        let wide = ar.gt(&width, &ar.lit(0.0));
        let slope = [0, 1].map(|k| ar.select(&wide, &ar.div(&ar.sub(&c[1][k], &c[0][k]), &width), &ar.lit(0.0)));
        let ok = ar.all(&[ar.all(&finite), ar.is_finite(&slope[0]), ar.is_finite(&slope[1])]);
        let [at_xa, _] = c;
        Patch { ok, xa: xa.clone(), at_xa, slope }
    };
    Axis { lo: patch(lo), hi: patch(hi) }
}

/// Screen extent along `axis` (0: x, 1: y) of the moving, defocused triangle, from the
/// corners (lens +-1, t = 0, 1) of each vertex, and whether every corner is finite.
/// Requires every w > 0 (checked by caller).
fn extent<A: F32Arith>(ar: &A, tri: &TriOf<A::F>, ax: usize) -> (A::B, A::F, A::F) {
    let kf = if ax == 0 { ar.lit(1.0) } else { tri.k.clone() };
    let (mut lo, mut hi) = (ar.lit(f32::INFINITY), ar.lit(f32::NEG_INFINITY));
    let mut finite = vec![];
    for j in 0..3 {
        for (p, c) in [(&tri.q[j], &tri.c0[j]), (&tri.r[j], &tri.c1[j])] {
            for s in [-1.0f32, 1.0] {
                let x = projected(ar, &p[ax], s, &kf, c, &p[3]);
                finite.push(ar.is_finite(&x));
                lo = ar.min(&lo, &x);
                hi = ar.max(&hi, &x);
            }
        }
    }
    (ar.all(&finite), lo, hi)
}

/// Why the test cannot run on this triangle, as three conditions in order: some
/// `c_j(t) = 0` in the shutter, the CoC differ in sign, some vertex has w <= 0.
fn why_disabled<A: F32Arith>(ar: &A, tri: &TriOf<A::F>) -> [A::B; 3] {
    let zero = ar.lit(0.0);
    // `(a > 0) != (b > 0)`
    let differ = |a: &A::B, b: &A::B| ar.or(&ar.and(a, &ar.not(b)), &ar.and(&ar.not(a), b));
    let crossing: Vec<A::B> = (0..3)
        .map(|j| {
            let (a, b) = (&tri.c0[j], &tri.c1[j]);
            ar.any(&[ar.eq(a, &zero), ar.eq(b, &zero), differ(&ar.gt(a, &zero), &ar.gt(b, &zero))])
        })
        .collect();
    let pos = ar.gt(&tri.c0[0], &zero);
    let mixed: Vec<A::B> = tri.c0.iter().chain(tri.c1.iter()).map(|c| differ(&ar.gt(c, &zero), &pos)).collect();
    let behind: Vec<A::B> =
        (0..3).map(|j| ar.not(&ar.and(&ar.gt(&tri.q[j][3], &zero), &ar.gt(&tri.r[j][3], &zero)))).collect();
    [ar.any(&crossing), ar.any(&mixed), ar.any(&behind)]
}

/// The reasons of [`why_disabled`], and the screen extent's.
const WHY: [&str; 4] = [
    "some c_j(t) = 0 in the shutter (a vertex touches or crosses the focal plane)",
    "the vertices' CoC differ in sign (the triangle straddles the focal plane)",
    "a vertex has w <= 0 in the shutter (no finite screen extent for the patch domain)",
    "the screen extent of the triangle is not finite in f32",
];

/// The disabling conditions and the setup, as values of some [`F32Arith`].
pub type SetupOf<F, B> = ([B; 4], Setup<F, B>);

/// The setup over any [`F32Arith`]: whether the test runs (false for each reason of
/// `WHY`, in order) and the patches of both axes.
pub fn setup_of<A: F32Arith>(ar: &A, tri: &TriOf<A::F>, literal_fig5: bool) -> SetupOf<A::F, A::B> {
    let [c, m, b] = why_disabled(ar, tri);
    let ((okx, xa, xb), (oky, ya, yb)) = (extent(ar, tri, 0), extent(ar, tri, 1));
    let ends = |f: &dyn Fn(&[A::F; 4]) -> A::F| [0, 1, 2].map(|j| [f(&tri.q[j]), f(&tri.r[j])]);
    let w = ends(&|p| p[3].clone());
    let px = ends(&|p| p[0].clone());
    let py = ends(&|p| p[1].clone());
    let cu = [0, 1, 2].map(|j| [tri.c0[j].clone(), tri.c1[j].clone()]);
    let cv = [0, 1, 2].map(|j| [ar.mul(&tri.k, &tri.c0[j]), ar.mul(&tri.k, &tri.c1[j])]);
    let u = axis(ar, [&px, &w, &cu], &xa, &xb, literal_fig5);
    let v = axis(ar, [&py, &w, &cv], &ya, &yb, literal_fig5);
    ([c, m, b, ar.not(&ar.and(&okx, &oky))], Setup { u, v })
}

/// The f32 setup, or the reason the test is disabled.
fn setup(tri: &Triangle, literal_fig5: bool) -> Result<Setup<f32, bool>, &'static str> {
    let (why, s) = setup_of(&Plain, &TriOf::of(tri), literal_fig5);
    match why.iter().position(|&w| w) {
        Some(k) => Err(WHY[k]),
        None => Ok(s),
    }
}

/// One of the four per-sample lines: `g = s.u - (a t + b)` (lower) or `(a t + b) - s.u`
/// (upper), with v in place of u for the vt lines.
#[derive(Debug, Clone, Copy)]
struct Line {
    is_v: bool,
    upper: bool,
    a: f32,
    b: f32,
}

fn abs_max(i: Interval) -> f64 {
    i.lo.abs().max(i.hi.abs())
}

impl SampleConstraint for Line {
    fn name(&self) -> String {
        format!("{}t {} line", if self.is_v { "v" } else { "u" }, if self.upper { "upper" } else { "lower" })
    }
    fn eval(&self, s: &Sample) -> f32 {
        let w = if self.is_v { s.v } else { s.u };
        let l = self.a * s.t + self.b;
        if self.upper {
            l - w
        } else {
            w - l
        }
    }
    /// `eval` over the columns (the same two f32 operations per sample, side by side).
    fn eval_row(&self, c: &SampleCols, out: &mut [f32]) {
        let (w, a, b) = (if self.is_v { c.v } else { c.u }, self.a, self.b);
        if self.upper {
            for ((o, &w), &t) in out.iter_mut().zip(w).zip(c.t) {
                *o = (a * t + b) - w;
            }
        } else {
            for ((o, &w), &t) in out.iter_mut().zip(w).zip(c.t) {
                *o = w - (a * t + b);
            }
        }
    }
    fn eval_box(&self, bx: &SampleBox) -> Interval {
        let w = if self.is_v { bx.v } else { bx.u };
        let (a, b) = (Interval::point(self.a as f64), Interval::point(self.b as f64));
        let l = a * bx.t + b;
        let g = if self.upper { l - w } else { w - l };
        let mag = Interval::point(abs_max(w))
            + Interval::point((self.a as f64).abs()) * Interval::point(abs_max(bx.t))
            + Interval::point((self.b as f64).abs());
        let err = (Interval::point(mag.hi) * Interval::point(2f64.powi(-20)) + Interval::point(2f64.powi(-140))).hi;
        g + Interval::new(-err, err)
    }
}

/// A per-tile line `a t + b` of some [`F32Arith`], and whether it is emitted.
pub type LineOf<F, B> = (B, F, F);

/// One axis's tile answer: non-empty, the range, the lower and upper line.
pub type AxisAnswer<F, B> = (B, [F; 2], [LineOf<F, B>; 2]);

/// One axis of the tile answer over any [`F32Arith`]: whether its lens range is
/// non-empty, the range (`u^` or `v^`) and the lower and upper line, for the tile's
/// centre `c` and half width `h` on that axis.
pub fn axis_tile<A: F32Arith>(ar: &A, ax: &Axis<A::F, A::B>, c: &A::F, h: &A::F) -> AxisAnswer<A::F, A::B> {
    let (lo_ok, lo) = ax.lo.line(ar, c, h, -1.0);
    let (hi_ok, hi) = ax.hi.line(ar, c, h, 1.0);
    let (one, minus) = (ar.lit(1.0), ar.lit(-1.0));
    let r_lo = ar.select(&lo_ok, &ar.max(&ar.min(&lo[0], &lo[1]), &minus), &minus);
    let r_hi = ar.select(&hi_ok, &ar.min(&ar.max(&hi[0], &hi[1]), &one), &one);
    let nonempty = ar.le(&r_lo, &r_hi); // false on NaN too
    let line = |ok: &A::B, l: &[A::F; 2]| {
        let a = ar.sub(&l[1], &l[0]);
        (ar.and(ok, &ar.is_finite(&a)), a, l[0].clone())
    };
    (nonempty, [r_lo, r_hi], [line(&lo_ok, &lo), line(&hi_ok, &hi)])
}

/// The tile's centre and half width on both axes, `[xc, yc]` and `[hx, hy]`.
fn centre<A: F32Arith>(ar: &A, tile: &[A::F; 4]) -> ([A::F; 2], [A::F; 2]) {
    let half = ar.lit(0.5);
    let c = |a: usize| ar.mul(&half, &ar.add(&tile[a], &tile[a + 2]));
    let h = |a: usize| ar.mul(&half, &ar.sub(&tile[a + 2], &tile[a]));
    ([c(0), c(1)], [h(0), h(1)])
}

/// The answer for a tile `[x0, y0, x1, y1]` of an enabled setup, over any
/// [`F32Arith`]: `(nonempty, u^, v^, lines)`, the lines in the order lower u, upper u,
/// lower v, upper v; the tile is Empty when `nonempty` is false (the tile reject).
#[allow(clippy::type_complexity)]
pub fn tile_answer<A: F32Arith>(
    ar: &A,
    s: &Setup<A::F, A::B>,
    tile: &[A::F; 4],
) -> (A::B, [A::F; 2], [A::F; 2], [LineOf<A::F, A::B>; 4]) {
    let (c, h) = centre(ar, tile);
    let (oku, u, [lu0, lu1]) = axis_tile(ar, &s.u, &c[0], &h[0]);
    let (okv, v, [lv0, lv1]) = axis_tile(ar, &s.v, &c[1], &h[1]);
    (ar.and(&oku, &okv), u, v, [lu0, lu1, lv0, lv1])
}

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let s = match &self.0 {
            Ok(s) => s,
            Err(_) => return TileResult::Bounds(TileBounds::full()),
        };
        let (c, h) = centre(&Plain, &tile_of(tile));
        let mut out = TileBounds::full();
        for (is_v, ax) in [(false, &s.u), (true, &s.v)] {
            let k = is_v as usize;
            let (nonempty, range, lines) = axis_tile(&Plain, ax, &c[k], &h[k]);
            if !nonempty {
                return TileResult::Empty;
            }
            if is_v {
                out.v = range;
            } else {
                out.u = range;
            }
            for (upper, (ok, a, b)) in [false, true].into_iter().zip(lines) {
                if ok {
                    out.constraints.push(Box::new(Line { is_v, upper, a, b }));
                }
            }
        }
        TileResult::Bounds(out)
    }
    fn disabled(&self) -> Option<&'static str> {
        self.0.as_ref().err().copied()
    }
    /// The u answer reads only the tile's x sides (the u patches at the column's centre
    /// and half width), the v answer only its y sides: each is computed once per column
    /// and once per row (by [`axis_tile`], as [`tile`](Self::tile) does), and a tile
    /// joins its column's and its row's. A disabled test answers full bounds tile by tile.
    fn grid<'a>(&'a self, grid: Grid<'a>) -> Box<dyn TileGrid + 'a> {
        let Ok(s) = &self.0 else {
            return Box::new(PerTile { prep: self, grid });
        };
        let cols = (0..grid.columns()).map(|i| AxisLines::of(&s.u, false, grid.column(i))).collect();
        let rows = (0..grid.rows()).map(|j| AxisLines::of(&s.v, true, grid.row(j))).collect();
        Box::new(LinesGrid { cols, rows })
    }
}

/// One axis's part of a `mam2012` tile answer: the lens range and the lines that are
/// emitted, in the order [`tile`](Prep::tile) pushes them (lower, upper).
#[derive(Clone, Copy)]
struct AxisLines {
    range: [f32; 2],
    lines: [Option<Line>; 2],
}

impl AxisLines {
    /// The answer of the axis's patches over the tile sides `[a0, a1]` (x for u, y for
    /// v), or None when its lens range is empty (the tile is Empty). The centre and half
    /// width come from [`centre`], which reads only the sides of their own axis.
    fn of(ax: &Axis<f32, bool>, is_v: bool, [a0, a1]: [f32; 2]) -> Option<AxisLines> {
        let k = is_v as usize;
        let mut sides = [0.0; 4];
        (sides[k], sides[k + 2]) = (a0, a1);
        let (c, h) = centre(&Plain, &sides);
        let (nonempty, range, lines) = axis_tile(&Plain, ax, &c[k], &h[k]);
        let line = |upper: bool, (ok, a, b): LineOf<f32, bool>| ok.then_some(Line { is_v, upper, a, b });
        let [lo, hi] = lines;
        nonempty.then_some(AxisLines { range, lines: [line(false, lo), line(true, hi)] })
    }
}

/// [`Prep::grid`]: per column the u part of the answer, per row the v part; per tile
/// only the check of both and the tile's own constraints (u lines, then v lines).
struct LinesGrid {
    cols: Vec<Option<AxisLines>>,
    rows: Vec<Option<AxisLines>>,
}

impl TileGrid for LinesGrid {
    fn tile(&self, i: usize, j: usize) -> TileResult {
        // `tile` answers Empty on the u axis before it looks at v.
        let (Some(u), Some(v)) = (&self.cols[i], &self.rows[j]) else {
            return TileResult::Empty;
        };
        let lines = u.lines.iter().chain(&v.lines).flatten();
        let constraints = lines.map(|&l| Box::new(l) as Box<dyn SampleConstraint>).collect();
        TileResult::Bounds(TileBounds { u: u.range, v: v.range, constraints, ..TileBounds::full() })
    }
}

#[cfg(test)]
mod tests;
