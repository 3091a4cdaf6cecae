//! wu2013: the two-stage clip-space sample culling of Yi-Jeng Wu, "Clip Space Sample
//! Culling for Stochastic Rasterization", M.Sc. thesis, National Chiao Tung University,
//! 2013 (advisor Zen-Chung Shih): §3.3 (stage 1, lens bounds), §3.4 (stage 2, time
//! bounds linear in the lens coordinate: Eq. 1, its rewritten form, the green / red
//! linear bounds of Figures 3.7 and 3.8) and §3.5 (controllable defocus).
//!
//! # Notation
//! Model notation throughout (`docs/model.md`): vertex i at time t is `p_i(t) = lerp(q_i, r_i)`,
//! CoC `c_i(t) = lerp(c_i0, c_i1)`; seen from lens u it sits at `x_i + u c_i` (and at
//! `y_i + k v c_i`). Everything below is written for the x axis and u; the y axis is the
//! same with `y`, v and the CoC `k c_i`. For a pixel column X define the dual-space
//! quantity `delta_i(X, u, t) = x_i(t) + u c_i(t) - X w_i(t)`.
//!
//! **Why both stages rest on delta.** For an interior sample at column X the hit point
//! is `H = sum b_k p'_k` with all barycentrics `b_k > 0`, and `x'_H = X w_H`, so
//! `sum_k b_k delta_k = 0`: the three `delta_k` cannot all have one strict sign. This holds
//! for any w (also behind the lens), because it never divides by w.
//!
//! # Stage 1 (§3.3): lens bounds
//! The thesis joins each of the six vertices (t = 0, 1) to the pixel's focus point and
//! intersects the line with the lens: `u = (n^x . p(t)) / (p(t).z - focusDepth) / R`.
//! In model terms this is the lens position at which vertex i appears exactly on column
//! X, `u_i(X, t) = (X w_i(t) - x_i(t)) / c_i(t)` (the same number: for the thin lens
//! `c = fx R (w - F) / F`). The bound is `u in [min, max]` over the six vertices.
//! *Why it holds:* if every `c_i` has one strict sign, say > 0, every `delta_i` increases
//! with u and vanishes at `u_i`; for `u > max_i u_i` all `delta_i > 0` and the pixel
//! cannot be covered (likewise below the minimum, and mirrored for c < 0). Over t,
//! `u_i(X, t)` is a linear fraction with no pole while `c_i(t) != 0`, hence monotone, so
//! its extremes are at t = 0, 1 (the thesis's six vertices).
//!
//! # Stage 2 (§3.4): time bounds linear in u
//! Eq. 1 (similar triangles in the xw plane) gives the time at which vertex i, seen from
//! lens u, crosses the ray of column X; rewritten with `x -> x + u c(t)` it is the
//! rational function
//! `t_i(u) = N_i(u) / D_i(u)`, `N_i = x_i0 + u c_i0 - X w_i0 = delta_i(t=0)`,
//! `D_i = delta_i(t=0) - delta_i(t=1) = (x_i0 - x_i1) - X (w_i0 - w_i1) + u (c_i0 - c_i1)`
//! (the thesis writes it with the opposite sign in numerator and denominator). We use
//! the signed form: the thesis's unsigned lengths `|v0 - x0| / |v1 - x1|` would put a
//! crossing in [0, 1] even for a vertex that never crosses.
//! On u in [-1, 1], if `D_i` does not vanish there, `t_i` is monotone and either convex
//! or concave (`t_i'' = -2 K d1 / D^3` with `K = n1 d0 - n0 d1`, for `N = n0 + n1 u`,
//! `D = d0 + d1 u`), so it lies between its chord (the thesis's green line through
//! `t(-1)`, `t(1)`) and its tangent at u = 0 (the red line `t(0) + u t'(0)`). Instead of
//! deciding convexity from the sign of `K d1 d0`, the upper line of a vertex is the line
//! through `max(chord, tangent)` at u = -1 and at u = +1, the lower through the mins:
//! that picks the same line in exact arithmetic and is robust when the function is
//! nearly linear. The three vertices are combined (Figure 3.8) into one upper line
//! through `(-1, max_i upper_i(-1))`, `(1, max_i upper_i(1))` (a maximum of lines is
//! convex, so it lies below its chord) and one lower line through the minima. The
//! stage-2 claim is that interior coverage at (X, u) only happens for
//! `t in [min_i t_i(u), max_i t_i(u)]`.
//!
//! # From a pixel to a tile (our choice)
//! The thesis works per pixel, at the pixel's ray. Our contract covers every continuous
//! (x, y) of the tile `[x0, x1] x [y0, y1]` (corners need not be integers, a 1x1 tile
//! covers the whole pixel area, not only its centre). We take the **union of the
//! per-pixel bounds over every column X in [x0, x1]** (and row Y in [y0, y1]), computed
//! exactly from the tile's sides:
//! - stage 1: `u_i(X, t)` is affine in X, so the union over X of `[min_i, max_i]` is
//!   spanned by the 12 values at X in {x0, x1}, t in {0, 1};
//! - stage 2: `N_i` and `D_i` are affine in (X, u) jointly; if `D_i` has one strict sign
//!   at the four corners (X in {x0, x1}, u = +-1) it has it on the whole rectangle, so
//!   for fixed u `t_i` is a linear fraction of X without a pole, monotone, and
//!   `max_X t_i(X, u) = max(t_i(x0, u), t_i(x1, u))`. The per-vertex linear bounds are
//!   built at both sides (six upper and six lower lines per axis) and combined as above.
//!
//! So for a 1x1 tile at a pixel the bounds are those of the thesis's pixel, widened to
//! the pixel's area.
//!
//! # Outputs
//! - `u^`, `v^`: stage 1, clipped to [-1, 1] (Empty if disjoint from it).
//! - four per-sample constraints (x lower / upper in u, y lower / upper in v):
//!   `g = t - (a l + b)` for a lower line, `g = (a l + b) - t` for an upper line, l = u or
//!   v, in f32 (culled when g < 0). Lines with zero slope (no defocus on that axis) are
//!   not emitted as constraints (the tile interval says the same), nor lines that cut
//!   nothing on the lens range.
//! - `t^`: the lines' extremes over `u^` / `v^`, intersected with [0, 1] (Empty if empty).
//!
//! # Conditions, fallbacks, and §3.5
//! - **§3.5 (controllable defocus, Munkberg et al. 2012's per-vertex CoC)** is the same
//!   algorithm with per-vertex c: the thesis modifies only the CoC values (c = 0 inside
//!   an extended focus range, a + w b outside, linear inside the triangle), and both
//!   stages are written per vertex already. Our Triangle carries per-vertex `c0`, `c1`,
//!   so `METHOD` covers it; no separate method. Its rule "if the triangle vertex is
//!   inside the extended focus range, all samples pass stage 1" is applied: stage 1 is
//!   off when some `c_i0` or `c_i1` is 0. Its "set u = v = 0 to compute the stage 2 time
//!   bounds" is read per vertex: a vertex with c = 0 has `t_i` independent of u, which
//!   is what our per-vertex formula gives; applying u = v = 0 to the *other* vertices
//!   (which still have c != 0) would not be conservative, so we do not.
//! - A vertex whose CoC changes sign during the shutter (it crosses the focal plane):
//!   `u_i(X, t)` has a pole inside the shutter (division blows up; the thesis says
//!   nothing) -> stage 1 off (full lens).
//! - Stage 2, a vertex with `D_i` not of one strict sign on the tile-lens rectangle
//!   (vertex not moving relative to the column for some lens position, e.g. a static
//!   vertex, or a pole of `t_i(u)` inside [-1, 1]; the thesis's "this function is also
//!   monotone" fails): no time bound on that axis. Non-finite intermediate values: the
//!   same. A line endpoint beyond `2^100` in magnitude: that line is dropped.
//! - Vertices behind the lens (w <= 0): no special case; the thesis only clips its
//!   screen bounding geometry (§3.2, not part of this test), and the delta argument
//!   above does not need w > 0.
//! - `disabled()` is `Some` when neither stage can ever apply: stage 1 off and, on both
//!   axes, some vertex with `D_i` identically 0 (e.g. a static, in-focus triangle).
//!
//! # Unstated assumptions of the thesis (findings, not fixed here)
//! Both stages are published without conditions, and both are kept as published:
//! - Stage 1 needs all `c_i` to share one strict sign. A triangle straddling the focal
//!   plane (some vertices in front, some behind, none exactly on it) breaks it: vertices
//!   with c < 0 and c > 0 move in opposite directions as u grows, so a pixel can stay
//!   covered for u beyond `max_i u_i`. (E.g. a pixel whose focus point lies on the
//!   triangle sees it from the whole lens, while all `u_i` are 0.)
//! - Stage 2 needs all `D_i` to share one sign at each (X, u) (all vertices crossing the
//!   column in the same direction). With opposite directions (a triangle rotating in the
//!   image, or growing across the column) the covered times need not lie between the
//!   crossing times at all.
//!
//! Both failures are common, not corner cases: on 150 random thin-lens triangles with
//! vertices on both sides of the focal plane and each vertex moving on its own (unit
//! test `published_test_on_unconstrained_triangles`), 112 triangles lose covered samples
//! and 19453 of 43975 covered samples drawn in 2x2 tiles on them are culled. The most
//! basic stage-2 failure: no vertex crosses the row during the shutter, two stay above
//! it and one below, all crossing times are negative and `[min t_i, max t_i]` is empty,
//! while the row is straddled (and the pixel covered) for the whole shutter. The
//! thesis's unsigned Eq. 1 (`|v0 - x0| / |v1 - x1| = t / (1 - t)`) would not help: it
//! puts a "crossing" in [0, 1] for every vertex, crossing or not.
//! The unit tests `finding_*` hold the witnesses (they pass while the bound culls the
//! covered sample); the conservativeness spot checks use triangles that satisfy both
//! assumptions (rigid translation in camera space gives every vertex the same D; all
//! vertices on one side of the focal plane).
//!
//! A guarded variant (not registered, tested in `guarded_variant_is_conservative`)
//! adds the two missing conditions: stage 1 only when all six CoC values share one
//! strict sign, stage 2 on an axis only when all `D_i` share one strict sign on the
//! tile-lens rectangle. It culls no covered sample on the same random triangles.
//! `wu2013-safe` (below) keeps its stage-2 guard for the lines and replaces both guards'
//! fallbacks by a bound that handles mixed signs.
//!
//! # Where f32 can make it non-conservative
//! Every value (u_i, N, D, t(+-1), t(0), the slope, line coefficients, tile extremes,
//! and the f32 evaluation of a line at a sample) is rounded with no outward rounding:
//! a covered sample within a few ulps of a bound (relative to the magnitudes of
//! `x`, `X w`, `u c`) can be culled. `t_i` is ill-conditioned when `D_i` is small (slow
//! relative motion): its error grows like `1 / D_i`. The corner sign test of `D_i` can
//! be decided wrongly when `D_i` is within rounding of 0 at a corner.
//!
//! # `wu2013-safe`: both crossing directions, both CoC signs, rounded outward
//! `wu2013` above is the published test and stays as it is (the gate finds its
//! violations). `wu2013-safe` (`METHOD_SAFE`) computes the same two stages with two
//! corrections beyond rounding and every quantity enclosed in f32 interval arithmetic.
//! It rests on the one fact derived at the top (no assumption on w or on the CoC signs):
//! at an interior sample (X, l, t) the three `delta_k` do not all have one strict sign,
//! i.e. some `delta_k <= 0` and some `delta_j >= 0`.
//! Its code (intervals, crossings, padded lines, setup and tile test) lives in `wu2013/safe.rs`.
//!
//! **The sign-aware hull** (both corrections). Let `delta_k` be affine in a variable z
//! (u in stage 1, t in stage 2), increasing (set I) or decreasing (set J) over the
//! whole tile, and vanishing at `z_k`, with `z_k in [m_k, M_k]` for every column of the
//! tile (and lens or time position). For k in I, `delta_k <= 0` iff `z <= z_k <= M_k`
//! and `delta_k >= 0` iff `z >= z_k >= m_k`; for k in J the reverse. So a covered z lies
//! in `((-inf, M_I] u [m_J, inf)) n ([m_I, inf) u (-inf, M_J])`
//! `= [m_I, M_I] u (-inf, min(M_I, M_J)] u [max(m_I, m_J), inf) u [m_J, M_J]`
//! (`M_I = max_I M_k`, `m_I = min_I m_k`, empty set: -inf / +inf), and the bound is the
//! hull of its part in the domain (`sign_hull`; Empty when there is none). With one
//! direction only (J empty) this is the published `[min_k, max_k]`.
//!
//! **Correction 1, stage 1 (failed assumption: all CoC of one strict sign).** `delta_k`
//! is affine in u with slope `c_k(t)`: increasing for c > 0, decreasing for c < 0. A
//! vertex whose CoC keeps one strict sign over the shutter (c0, c1 both > 0 or both
//! < 0) has `u_k(X, t)` affine in X and monotone in t, so its range over the tile's
//! columns and the shutter is spanned by the 4 corners (as published); vertices may
//! now differ in sign (a triangle straddling the focal plane, the focus point of a
//! pixel on the triangle: the hull is then the whole lens, as it must be). A vertex
//! whose CoC is 0 or changes sign in the shutter (a pole of `u_k`): **fallback**, no lens
//! bound on that axis (the y axis uses `k c`).
//!
//! **Correction 2, stage 2 (failed assumption: all D_i of one sign, one crossing
//! direction).** `delta_k(t) = N_k - t D_k` is increasing iff `D_k < 0`. `N_k` and `D_k`
//! are affine in (X, l) jointly, so where `D_k` keeps one strict sign on the rectangle
//! `[x0, x1] x l^` (`l^` the stage-1 range of that axis: covered samples lie in it) the
//! crossing time `t_k = N_k / D_k` is a linear fraction of (X, l) without a pole, whose
//! level sets are lines: its extremes over the rectangle are at its 4 corners. The hull
//! with I = {D < 0}, J = {D > 0} bounds t^ for perspective motion, wobbling and turning
//! triangles alike. A vertex whose `D_k` is not of one strict sign on the rectangle
//! (static relative to some pixel ray, or turning there): **fallback**, no time bound
//! from that axis. The published lines (per-sample constraints) need more: their
//! chord / tangent argument needs every `D_k` of one common strict sign on
//! `[x0, x1] x [-1, 1]`, which is exactly the stage-2 guard of the unregistered
//! `Wu2013 { guarded: true }` (its stage-1 guard is superseded by correction 1); only
//! then are they built, and t^ is the intersection of the hull and the lines' range.
//!
//! **w <= 0** needs nothing more: the delta fact never divides by w, and a vertex that
//! moves behind the lens changes the sign of its CoC (thin lens) or of its D, which the
//! fallbacks above catch.
//!
//! **Rounding: f32 interval arithmetic (`Iv`), not a gamma_n bound.** Every quantity the
//! answer depends on (`X w - p`, `u_k`, `N`, `D`, `t_k` at the corners, `t(+-1)`,
//! `t(0)`, the tangent slope, `k c`) is an interval of f32 values: each operation rounds
//! its end results to nearest and steps each one to the next f32 value outward
//! (`next_down` / `next_up`; +, - on the matching ends, *, / as the hull of the four end
//! products / quotients, a divisor only of one strict sign). Why it encloses: a finite
//! result r rounded to nearest from an exact z has z between r and its neighbour on z's
//! side (subnormals included: an underflow to 0 is enclosed by +-2^-149), and the exact
//! operation on any reals of the operand intervals lies between the exact end results.
//! It was chosen because the chains are long (the slope is ten dependent operations) and
//! cancel (`X w - p` at X = 1e6 px loses up to 1/16 px: the interval carries exactly that
//! absolute width, where a relative gamma_n bound would need the magnitudes of every
//! intermediate). Decisions (CoC sign, D sign) are taken on enclosures (an enclosure
//! above 0 means the exact value is); comparisons of enclosure ends with tile edges and
//! the domain are exact. A non-finite end (overflow, a divisor enclosure through 0) gives
//! that quantity no bound (full lens or shutter on that axis), and a non-finite input
//! anywhere gives the full domain for every tile (never a cull).
//!
//! **The lines in f32.** Upper endpoints are maxima of upper ends of the chord / tangent
//! enclosures (lower: minima of lower ends), so the line through them lies above the
//! exact published line on [-1, 1] (a line between two points is their convex
//! combination there). Its f32 form: `a = fl(ur / 2 - ul / 2)` (any slope would do) and
//! `b = max(up(ul + a), up(ur - a))`, so `a l + b >= line` at l = +-1, hence on [-1, 1].
//! `TimeLine::eval` computes `fl(fl(fl(a l) + b') - t)` (the same code as `wu2013`):
//! for |l| <= 1 and u = 2^-24, `|fl(fl(a l) + b') - (a l + b')| <= u |a| + 2^-150 +
//! u (|a| (1 + u) + 2^-150 + |b'|) <= 1.1 u (2 |a| + |b|) + 2^-148`, so
//! `b' = up(fl(b + p))` with `p = fl(fl(2 |a| + |b|) + 2^-100) * 2^-21 >=
//! 8 u (1 - u)^2 (2 |a| + |b| + 2^-100)` (the scaling by 2^-21 is exact, the result being
//! above 2^-121) keeps the computed line above `a l + b >= t` for every covered sample;
//! the last subtraction of two f32 values whose exact difference is not negative
//! rounds to a value that is not negative, so `g >= 0` (lower lines mirrored). `eval_box` is the published one (same
//! `eval`). t^ from a line: its value at the ends of `l^` by `Iv`.
//!
//! **Cost and tightness.** Per tile and axis 12 corner crossings and the lines at two
//! columns, each operation with two steps; the enclosures widen the published values by
//! a few ulps of the magnitudes involved (far from the origin, 1/16 px of `X w`), which
//! no STE figure sees. The real loss is the fallbacks: no lines where the vertices cross
//! in opposite directions (the hull still gives t^), and no lens bound on an axis where
//! a CoC changes sign in the shutter.
//! Over a grid of tiles (`grid.rs`, [`Prepared::grid`]) both methods share the axis
//! work: `wu2013-safe` computes the vertices' column parts, lens crossings and line ends
//! once per column (row) boundary, the lens range, crossing hull parts and lines once per
//! column (row), and per tile only meets the row's hull and lines with the column's time
//! range (`wu2013`: lens ranges and lines per column and row, the lines' time ranges per
//! tile).

use super::*;

mod safe;
pub use safe::METHOD_SAFE;
pub(crate) use safe::{safe_line, FLOOR, PAD};
pub use safe::{
    setup_of, tile_answer, AnswerOf, AxisCut, SafeAxis, SafeLineOf, SafeSetupOf, SafeVertex, SideCut, Wu2013Safe,
    KEEP_CHOICE, LENS_LEMMA, LIMIT_CHOICE, LINE_LEMMA, SLOPE_CHOICE,
};

/// One vertex on one axis: position (x or y), w, and CoC (c or k c) at both ends.
#[derive(Clone, Copy, Debug)]
struct AxisVertex {
    p0: f32,
    w0: f32,
    c0: f32,
    p1: f32,
    w1: f32,
    c1: f32,
    /// Per-vertex constants of D = dp - X dw + l dc.
    dp: f32,
    dw: f32,
    dc: f32,
}

/// One axis (x with u, or y with v) of the triangle.
#[derive(Clone, Copy, Debug)]
struct Axis {
    v: [AxisVertex; 3],
}

/// The four line endpoints of stage 2 on one axis: upper line through (-1, ul), (1, ur),
/// lower line through (-1, ll), (1, lr).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Lines {
    ul: f32,
    ur: f32,
    ll: f32,
    lr: f32,
}

/// The largest line endpoint a line is built from (2^100; `wu2013_safe.g` reads it).
pub(crate) const LINE_LIMIT: f32 = 1.2676506e30; // 2^100

impl Axis {
    /// Stage 1: the lens range over columns [s0, s1], or None (full lens).
    fn lens_range(&self, s0: f32, s1: f32) -> Option<[f32; 2]> {
        let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
        for a in &self.v {
            for (p, w, c) in [(a.p0, a.w0, a.c0), (a.p1, a.w1, a.c1)] {
                for s in [s0, s1] {
                    let l = (s * w - p) / c;
                    if !l.is_finite() {
                        return None;
                    }
                    lo = lo.min(l);
                    hi = hi.max(l);
                }
            }
        }
        Some([lo, hi])
    }

    /// Stage 2: the combined lines over columns [s0, s1] and the lens [-1, 1], or None.
    /// `guarded`: also require one common sign of D for all three vertices.
    fn lines(&self, s0: f32, s1: f32, guarded: bool) -> Option<Lines> {
        let mut out = Lines { ul: f32::NEG_INFINITY, ur: f32::NEG_INFINITY, ll: f32::INFINITY, lr: f32::INFINITY };
        let mut signs = [false; 2]; // some D > 0, some D < 0
        for a in &self.v {
            // D must keep one strict sign on the (X, l) rectangle: check its corners.
            let d = [s0, s1].map(|s| [-1.0f32, 1.0].map(|l| a.dp - s * a.dw + l * a.dc));
            let flat = [d[0][0], d[0][1], d[1][0], d[1][1]];
            if flat.iter().all(|&x| x > 0.0) {
                signs[0] = true;
            } else if flat.iter().all(|&x| x < 0.0) {
                signs[1] = true;
            } else {
                return None;
            }
            if guarded && signs[0] && signs[1] {
                return None;
            }
            for s in [s0, s1] {
                let (n0, n1) = (a.p0 - s * a.w0, a.c0);
                let (d0, d1) = (a.dp - s * a.dw, a.dc);
                let tm = (n0 - n1) / (d0 - d1);
                let tp = (n0 + n1) / (d0 + d1);
                let tz = n0 / d0;
                let slope = (n1 - tz * d1) / d0;
                let (gm, gp) = (tz - slope, tz + slope);
                out.ul = out.ul.max(tm.max(gm));
                out.ur = out.ur.max(tp.max(gp));
                out.ll = out.ll.min(tm.min(gm));
                out.lr = out.lr.min(tp.min(gp));
                if !(tm.is_finite() && tp.is_finite() && gm.is_finite() && gp.is_finite()) {
                    return None;
                }
            }
        }
        Some(out)
    }

    /// True when some vertex has D identically 0 (stage 2 can never apply).
    fn dead(&self) -> bool {
        self.v.iter().any(|a| a.dp == 0.0 && a.dw == 0.0 && a.dc == 0.0)
    }
}

/// Which lens coordinate a line is in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Lens {
    U,
    V,
}

/// A stage-2 line `t = a l + b` as a per-sample constraint.
#[derive(Clone, Copy, Debug)]
pub struct TimeLine {
    lens: Lens,
    upper: bool,
    pub(crate) a: f32,
    pub(crate) b: f32,
}

impl TimeLine {
    fn line(&self, l: f32) -> f32 {
        self.a * l + self.b
    }
    /// How far `eval` can lie from the exact value for lens values `l` and times `t`:
    /// `2^-20 (|a| |l| + |b| + |t|)` (three f32 roundings of at most `2^-24` of partial
    /// results bounded by those magnitudes) plus `2^-140` for subnormal results.
    fn error_over(&self, l: Interval, t: Interval) -> f64 {
        self.error_scaled(l, t, 2f64.powi(-20))
    }
    /// The bound a cut states: three roundings along one path (`a l`, `+ b`, `- t`), each
    /// of a partial result bounded by the magnitudes below, so at most
    /// `gamma_3 = 3u / (1 - 3u) < 4u = 2^-22` of `|a| |l| + |b| + |t|` (Higham's bound
    /// for a recursive sum), plus `2^-140` for subnormal results. `eval_box` keeps the
    /// looser [`error_over`](Self::error_over).
    fn cut_error_over(&self, l: Interval, t: Interval) -> f64 {
        self.error_scaled(l, t, 2f64.powi(-22))
    }
    /// `rel (|a| |l| + |b| + |t|) + 2^-140` over lens values `l` and times `t`.
    fn error_scaled(&self, l: Interval, t: Interval, rel: f64) -> f64 {
        let lm = l.lo.abs().max(l.hi.abs());
        let tm = t.lo.abs().max(t.hi.abs());
        rel * ((self.a as f64).abs() * lm + (self.b as f64).abs() + tm) + 2f64.powi(-140)
    }
}

/// A stage-2 line's value at a sample over any [`F32Arith`](crate::bounds::arith::F32Arith):
/// `fl(fl(fl(a l) + b) - t)` for an upper line, `fl(t - fl(fl(a l) + b))` for a lower
/// one; the sample is culled where it is below 0 ([`TimeLine::eval`]).
pub fn line_gap<A: crate::bounds::arith::F32Arith>(
    ar: &A,
    upper: bool,
    a: &A::F,
    b: &A::F,
    l: &A::F,
    t: &A::F,
) -> A::F {
    let line = ar.add(&ar.mul(a, l), b);
    if upper {
        ar.sub(&line, t)
    } else {
        ar.sub(t, &line)
    }
}

impl SampleConstraint for TimeLine {
    fn name(&self) -> String {
        let (ax, l) = match self.lens {
            Lens::U => ("x", "u"),
            Lens::V => ("y", "v"),
        };
        if self.upper {
            format!("wu2013 {ax} upper line: t <= {} {l} + {}", self.a, self.b)
        } else {
            format!("wu2013 {ax} lower line: t >= {} {l} + {}", self.a, self.b)
        }
    }
    fn eval(&self, s: &Sample) -> f32 {
        let l = match self.lens {
            Lens::U => s.u,
            Lens::V => s.v,
        };
        line_gap(&crate::bounds::arith::Plain, self.upper, &self.a, &self.b, &l, &s.t)
    }
    /// `eval` over the columns (the same operations per sample, side by side).
    fn eval_row(&self, c: &SampleCols, out: &mut [f32]) {
        let ls = match self.lens {
            Lens::U => c.u,
            Lens::V => c.v,
        };
        let (a, b) = (self.a, self.b);
        if self.upper {
            for ((o, &l), &t) in out.iter_mut().zip(ls).zip(c.t) {
                *o = (a * l + b) - t;
            }
        } else {
            for ((o, &l), &t) in out.iter_mut().zip(ls).zip(c.t) {
                *o = t - (a * l + b);
            }
        }
    }
    /// Real value `+-(t - (a l + b))` over the box, widened by `2^-20 (|a| |l| + |b| + |t|)`
    /// (three f32 roundings of at most `2^-24` of partial results bounded by those
    /// magnitudes) plus `2^-140` for subnormal results.
    fn eval_box(&self, bx: &SampleBox) -> Interval {
        let l = match self.lens {
            Lens::U => bx.u,
            Lens::V => bx.v,
        };
        let p = |x: f32| Interval::point(x as f64);
        let line = p(self.a) * l + p(self.b);
        let g = if self.upper { line - bx.t } else { bx.t - line };
        let err = self.error_over(l, bx.t);
        if g.lo.is_nan() || g.hi.is_nan() || !err.is_finite() {
            return Interval::new(f64::NEG_INFINITY, f64::INFINITY);
        }
        g + Interval::new(-err, err)
    }
    /// The exact `+-(t - (a l + b))`, less the error bound of
    /// [`eval_box`](Self::eval_box) over the box.
    fn lower_cut(&self, bx: &SampleBox) -> Option<Cut> {
        let (l, lb) = match self.lens {
            Lens::U => (bx.u, Cut::U),
            Lens::V => (bx.v, Cut::V),
        };
        let err = self.cut_error_over(l, bx.t);
        if !err.is_finite() {
            return None;
        }
        let sign = if self.upper { 1.0 } else { -1.0 };
        let mut cut = Cut::zero();
        cut.coef[0] = sign * self.b as f64;
        cut.coef[lb] = sign * self.a as f64;
        cut.coef[Cut::T] = -sign;
        cut.err = err;
        Some(cut)
    }
}

struct Prep {
    x: Axis,
    y: Axis,
    /// Stage 1 applies (every vertex's CoC keeps one strict sign over the shutter; in
    /// the guarded variant, one sign shared by all six values).
    lens_ok: bool,
    guarded: bool,
    disabled: Option<&'static str>,
}

/// Upper line t <= a l + b and lower line t >= a l + b from stage-2 endpoints, with the
/// time range they imply over lens range [l0, l1], and the constraints worth keeping.
fn apply_lines(ln: Lines, lens: Lens, l: [f32; 2], t: &mut [f32; 2], cons: &mut Vec<Box<dyn SampleConstraint>>) {
    let ok = |a: f32, b: f32| a.abs() <= LINE_LIMIT && b.abs() <= LINE_LIMIT;
    if ok(ln.ul, ln.ur) {
        let c = TimeLine { lens, upper: true, a: 0.5 * ln.ur - 0.5 * ln.ul, b: 0.5 * ln.ul + 0.5 * ln.ur };
        let (e0, e1) = (c.line(l[0]), c.line(l[1]));
        t[1] = t[1].min(e0.max(e1));
        if c.a != 0.0 && e0.min(e1) < 1.0 {
            cons.push(Box::new(c));
        }
    }
    if ok(ln.ll, ln.lr) {
        let c = TimeLine { lens, upper: false, a: 0.5 * ln.lr - 0.5 * ln.ll, b: 0.5 * ln.ll + 0.5 * ln.lr };
        let (e0, e1) = (c.line(l[0]), c.line(l[1]));
        t[0] = t[0].max(e0.min(e1));
        if c.a != 0.0 && e0.max(e1) > 0.0 {
            cons.push(Box::new(c));
        }
    }
}

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let mut b = TileBounds::full();
        // Stage 1.
        if self.lens_ok {
            for (axis, s0, s1, out) in [(&self.x, tile.x0, tile.x1, &mut b.u), (&self.y, tile.y0, tile.y1, &mut b.v)] {
                if let Some([lo, hi]) = axis.lens_range(s0, s1) {
                    *out = [lo.max(-1.0), hi.min(1.0)];
                    if out[0] > out[1] {
                        return TileResult::Empty;
                    }
                }
            }
        }
        // Stage 2.
        let mut t = [0.0f32, 1.0];
        let mut cons: Vec<Box<dyn SampleConstraint>> = Vec::new();
        if let Some(ln) = self.x.lines(tile.x0, tile.x1, self.guarded) {
            apply_lines(ln, Lens::U, b.u, &mut t, &mut cons);
        }
        if let Some(ln) = self.y.lines(tile.y0, tile.y1, self.guarded) {
            apply_lines(ln, Lens::V, b.v, &mut t, &mut cons);
        }
        if t[0].is_nan() || t[1].is_nan() || t[0] > t[1] {
            return TileResult::Empty;
        }
        b.t = t;
        b.constraints = cons;
        TileResult::Bounds(b)
    }
    /// Each axis's lens range and lines read its own tile edges only: computed once per
    /// column and once per row ([`grid::PublishedGrid`]).
    fn grid<'a>(&'a self, grid: Grid<'a>) -> Box<dyn TileGrid + 'a> {
        Box::new(grid::PublishedGrid::new(self, grid))
    }
    fn disabled(&self) -> Option<&'static str> {
        self.disabled
    }
}

fn axis(tri: &Triangle, j: usize, scale: f32) -> Axis {
    Axis {
        v: std::array::from_fn(|i| {
            let (q, r) = (tri.q[i], tri.r[i]);
            let (c0, c1) = (scale * tri.c0[i], scale * tri.c1[i]);
            AxisVertex { p0: q[j], w0: q[3], c0, p1: r[j], w1: r[3], c1, dp: q[j] - r[j], dw: q[3] - r[3], dc: c0 - c1 }
        }),
    }
}

fn prepare(tri: &Triangle, guarded: bool) -> Prep {
    let x = axis(tri, 0, 1.0);
    let y = axis(tri, 1, tri.k);
    let cs = || tri.c0.iter().chain(tri.c1.iter());
    let lens_ok = if guarded {
        cs().all(|&c| c > 0.0) || cs().all(|&c| c < 0.0)
    } else {
        (0..3).all(|i| {
            let (a, b) = (tri.c0[i], tri.c1[i]);
            (a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0)
        })
    };
    let disabled = (!lens_ok && x.dead() && y.dead()).then_some(
        "no stage applies: a CoC is 0 or changes sign in the shutter (stage 1 off, §3.5) and on both axes a vertex \
         has no motion relative to the pixel rays (stage 2 denominators vanish)",
    );
    Prep { x, y, lens_ok, guarded, disabled }
}

/// The method; `guarded` adds the two conditions the thesis leaves unstated (see
/// "Unstated assumptions"): it is not registered (the registry holds the published
/// test), only kept so that the fix is tested.
struct Wu2013 {
    guarded: bool,
}

pub(crate) static INFO: MethodInfo = MethodInfo {
    id: "wu2013",
    source: "Wu 2013, Clip Space Sample Culling for Stochastic Rasterization (M.Sc. thesis, NCTU): §3.3 stage 1 \
             lens bounds; §3.4 stage 2 Eq. 1 rewritten, linear bounds of Figs. 3.7-3.8; §3.5 per-vertex CoC",
    reconstruction: false,
    dims: &[Dims::Motion, Dims::Defocus, Dims::Both],
    outputs: Outputs { tile_reject: true, lens: true, time: true, depth: false, per_sample: true },
};

impl Method for Wu2013 {
    fn info(&self) -> &'static MethodInfo {
        &INFO
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(prepare(tri, self.guarded))
    }
}

pub static METHOD: &dyn Method = &Wu2013 { guarded: false };

/// The guarded variant (not registered; see `Wu2013`).
#[cfg(test)]
static GUARDED: &dyn Method = &Wu2013 { guarded: true };

mod grid;

#[cfg(test)]
mod safe_tests;
#[cfg(test)]
mod tests;
