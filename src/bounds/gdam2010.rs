//! gdam2010: the exact time intervals in which a sample position lies inside a moving
//! (motion-only) triangle, after Gribel, Doggett and Akenine-Möller, "Analytical
//! Motion Blur Rasterization with Compression", HPG 2010 (cited by Nilsson et al. 2012,
//! §2 and §4, where it gives the "exact time interval when the pixel is inside all
//! three moving triangle edges"). The GDAM10 paper itself is not available to this
//! project: the edge-function coefficients are those of Munkberg et al. 2011 as restated in
//! `docs/reconstructions.md` (§7); the rest is derived below from `docs/model.md`.
//!
//! # Equations (model notation)
//! With no defocus (every `c = 0`), vertex i at time t is `p_i(t) = p_i0 + t dp_i`,
//! `p = (x, y, w)` in clip space, `dp_i = r_i - q_i`. For the sample's own pixel
//! position `s = (X, Y, 1)` the model's edge value of edge k = (i, j),
//! `E_k = P_i.x P_j.y - P_i.y P_j.x` with `P = (x - X w, y - Y w)`, equals
//! `e_k(t) = (p_i(t) x p_j(t)) . s = alpha_k t^2 + beta_k t + gamma_k` with
//!
//! - `alpha_k = (dp_i x dp_j) . s`
//! - `beta_k  = (p_i0 x dp_j + dp_i x p_j0) . s`
//! - `gamma_k = (p_i0 x p_j0) . s`
//!
//! (expand the cross product and collect the terms: it is the same bilinear form).
//! Setup computes the three cross-product vectors of each edge (27 f32 values); a
//! sample needs three dot products per edge and the roots of three quadratics.
//!
//! # Which set is computed
//! The model calls a sample interior when `D != 0` and all `E_k` have the strict sign
//! of D. Since `D = w_0 E_0 + w_1 E_1 + w_2 E_2` at any pixel, when every `w_i(t) > 0`
//! "all `E_k > 0`" already implies `D > 0` (and likewise for `< 0`): interior is then
//! exactly "all three `e_k(t)` non-zero with one sign", either sign (both windings,
//! and a triangle that flips facing during the shutter). We compute
//! `S = {t in [0, 1] : all e_k(t) > 0} U {t : all e_k(t) < 0}` and ignore D. For any
//! w, S contains every interior time (interior requires one common strict sign of the
//! E_k), so dropping D is conservative; it is exact when all w > 0 over the shutter
//! and may admit extra times when a vertex is behind the lens.
//!
//! In the computation (f32, as hardware would): every real root of the three
//! quadratics in (0, 1) is found (stable form `q = -(beta + sign(beta) sqrt(disc))/2`,
//! roots `q / alpha` and `gamma / q`; the linear root `-gamma / beta` when `alpha = 0`;
//! the double root `-beta / (2 alpha)` when `disc = 0`). Together with 0 and 1 they cut
//! [0, 1] into at most 7 gaps; no `e_k` changes sign inside a gap (in exact arithmetic),
//! so each gap is classified by the signs of the three `e_k` at its midpoint, and
//! adjacent covered gaps are merged into closed intervals `[a_m, b_m]`. This midpoint
//! classification replaces GDAM10's per-edge reasoning on the sign of the leading
//! coefficient; both give the same set in exact arithmetic (a choice the paper leaves
//! to the implementation; ours needs no case analysis and handles both windings).
//!
//! # The per-sample constraint
//! `g(s) = max_m min(t - a_m, b_m - t)` over the computed intervals of the sample's
//! own (x, y), in f32; `g(s) = -1` when the set is empty. So g is the signed distance in
//! t to leaving the set: `>= 0` iff t lies in some `[a_m, b_m]` (the value is the
//! distance to the nearer end of that interval; the shutter ends 0 and 1 count as ends),
//! `< 0` outside (minus the distance to the nearest interval). Culled iff `g < 0`.
//!
//! `eval_box`: g is a complicated, discontinuous function of (x, y) once f32 rounding of
//! the roots is taken into account, so the enclosure is wide on purpose:
//! - if the box is a single f32 point in x and y, the intervals are recomputed exactly
//!   as `eval` does and g is enclosed over the box's t range in f64 intervals, widened by
//!   `2^-20 (|t| + |a_m|)` per subtraction (an f32 subtraction errs by at most
//!   `2^-24 |result|`; min and max are exact);
//! - otherwise only what holds for every interval set in [0, 1] is used:
//!   `g in [min(-1, t - 1, -t), min(t, 1 - t)]` over the box's t (proves `g < 0` when
//!   the box's t lies outside [0, 1], nothing more).
//!
//! # Tile output, dimensions, disabling
//! The tile answer is the full domain (u, v, t) plus this one constraint; GDAM10 gives
//! no tile interval. The method is motion-only: if any `c != 0` the triangle is
//! defocused, `disabled()` says "defocus: gdam2010 is motion-only" and the tile answer
//! is the full domain with no constraint.
//!
//! # Where f32 can make it non-conservative
//! - **Near-double roots (where f32 is fragile).** When an edge grazes the sample
//!   position (the moving edge line comes within a hair of the pixel and turns back,
//!   `disc ~ 0`), `beta^2 - 4 alpha gamma` cancels catastrophically and the coefficients
//!   themselves carry rounding of the order of an ulp of `|x_i y_j X|`: a short covered
//!   span is shortened, or lost entirely (its discriminant comes out <= 0), or a
//!   spurious one appears. The error in t grows like the square root of the coefficient
//!   error. Measured (unit test `near_double_root_is_where_f32_is_fragile`, an edge with
//!   `E = 4 (t - 1/2)^2 - 19 d`, covered span `|t - 1/2| < sqrt(19 d / 4)`): at pixel
//!   (10.5, 10.5) the ends are off by up to 6e-4 in t (a shortened span: covered samples
//!   culled); at (100.5, 100.5) a covered span of width 0.012 is lost entirely; at
//!   (1000.5, 1000.5) one of width 0.034 is lost, and the ends of longer spans are off
//!   by up to 0.017.
//! - **A vertex passing exactly through the pixel centre** makes two edges vanish at the
//!   same t; rounding splits the double cut and a spurious span appears (an extra, not a
//!   loss): 5.7e-6 long near the screen origin, 1.6e-3 at a screen offset of 1000 pixels
//!   (unit test `agrees_with_exact_time_spans`).
//! - **Generic pixels.** Roots are rounded (a few ulps of the coefficients' magnitudes,
//!   more when `alpha` is tiny against `beta`), so an end can be off by that much and a
//!   sample that close to an end may be culled. Measured on pixel centres of moving
//!   triangles (same test): longest run of covered times missed 5.4e-7 (near the screen
//!   origin), 1.0e-7 (a triangle flipping facing), 2.6e-6 (screen offset 1000 pixels).
//! - The coefficients come from f32 cross products of f32 differences `r - q`, so the
//!   quadratics themselves are rounded versions of the model's.
//! - A gap narrower than f32 resolution is classified at a midpoint that may coincide
//!   with one of its ends.
//!
//! # `gdam2010-safe`: a certified superset of the covered time set
//! The f32 set above is the published computation and stays as it is: the gate finds
//! covered samples it culls (spans lost or shortened near edges and near double roots;
//! in static cases a sample within rounding distance of an edge loses the whole
//! shutter). The issue asks for "certified root isolation or a fallback".
//! `gdam2010-safe` keeps the algorithm's shape (cut [0, 1] at the edges' roots, decide
//! each piece, merge the covered ones into closed spans, the same `g(s)`) but a piece
//! is culled only when f32 interval arithmetic *proves* that no time in it is covered;
//! the roots only say where to cut, so their errors cost tightness, never correctness.
//! Its code (intervals, pads, pieces, cuts) lives in `gdam2010/safe.rs`; the part a
//! cull rests on is written once over `F32Arith` (the per-sample setup `sample_of`, a
//! piece end `end_of`, a piece's answer `piece_of`, a still triangle's `still_of`), and
//! the enclosure check of `cullproof proofs` traces it for every input: each cull implies
//! its exact counterpart (docs/proofs.md, section 4c). The cut points and the splitting
//! stay plain f32 code: they only choose the pieces.
//!
//! *The edge values, relative to the pixel.* For the sample's (X, Y) the model's edge
//! value is `E_k(t) = P_i(t) x P_j(t)` (2D cross product) with
//! `P_i(t) = (x_i(t) - X w_i(t), y_i(t) - Y w_i(t))`, linear in t:
//! `P_i(t) = A_i + t (B_i - A_i)`, `A_i` from `q_i`, `B_i` from `r_i`. Each coordinate
//! of `A_i`, `B_i` is one fused multiply-add, `fma(-X, w, x)`, rounded once; far from
//! the origin this keeps the pixel-relative offsets to an ulp of themselves (the
//! published setup's cross products of absolute coordinates lose that).
//!
//! *Error analysis: directed steps (f32 interval arithmetic, `Iv`).* Every f32
//! operation rounds to nearest, so the exact result lies between the computed `r` and
//! its neighbour on the exact value's side (subnormals included, their spacing is
//! uniform): `[next_down(r), next_up(r)]` encloses it. Interval sums and products
//! (the four end products, min and max, then one step out) enclose the exact sum or
//! product of any two enclosed reals; an exact 0 (a vertex that does not move has
//! `B_i - A_i = 0`, and `0 * x = 0`) is kept exact. Overflow gives `+-inf`, and
//! `next_down(+inf) = MAX` is still a lower bound (the exact value exceeds MAX); a
//! product `0 * inf` gives NaN, and a NaN end makes every sign test below false, so it
//! culls nothing. Non-finite triangle data disables the method (no constraint), a
//! non-finite sample position gets the whole shutter.
//!
//! *Deciding a piece (real arithmetic).* On a piece `[l, h]` of [0, 1], with
//! `s = (t - l) / (h - l)`, `P_i = (1 - s) P_i(l) + s P_i(h)`, so
//! `E_k = (1 - s)^2 b0 + 2 s (1 - s) b1 + s^2 b2` with `b0 = P_i(l) x P_j(l)`,
//! `b1 = (P_i(l) x P_j(h) + P_i(h) x P_j(l)) / 2`, `b2 = P_i(h) x P_j(h)`: the Bernstein
//! form, whose weights are >= 0 and sum to 1, so `E_k(t)` lies between the least and
//! the greatest `b`. `P_i(l)`, `P_i(h)` are enclosed (`A_i + l (B_i - A_i)`, or
//! `A_i`, `B_i` at 0 and 1), hence the `b`s (the middle one doubled: only signs
//! matter). A covered time needs all three `E_k` non-zero with one strict sign
//! (`docs/model.md` §3.3; D is ignored as in the original, a superset). So the piece is
//! culled iff some edge has every enclosed `b <= 0` (no `E_k > 0` on the piece) and
//! some edge has every `b >= 0` (no `E_k < 0`): then no t of the closed piece is
//! covered. With the pad (below) the tests are stricter: culled iff some edge k has
//! every enclosed `b <= -pad_k` and some edge j every `b >= pad_j`, each test also
//! requiring `0 <= pad` (always true of the pad below; it makes the tests' exact
//! counterparts imply the unpadded ones). Every other piece is
//! kept (a piece with all `b` of one strict sign for all
//! edges is certainly covered; one with neither answer is "open" and is split at its
//! midpoint, at most 12 times per sample and only while wider than 2^-12, then kept).
//! Kept pieces share their ends, so their union is a union of closed spans holding
//! every covered t; with more than 8 spans the last one is extended over the gap
//! (conservative). `g(s) = max_m min(t - a_m, b_m - t)` is then `>= 0` for every t in
//! a span (an f32 difference of ordered f32 values is `>= 0`), as in the original; its
//! `eval_box` is the original's, for these spans.
//!
//! *Where to cut (tightness only).* The Bernstein bounds are exact in real arithmetic
//! on a piece where `E_k` is monotone (then `b1` lies between `b0` and `b2`) and on
//! one that ends at the vertex of the parabola (then `b1` is its value there), so the
//! cuts are: each root `r` of each edge quadratic (f32, the original's
//! `roots_in_unit` on coefficients from the rounded `A`, `B`), moved out to `r +- d`
//! and `r +- d / 16` with `d = err / |E'(r)| + 2^-21`, and the parabola's vertex `t_v`
//! with `t_v`, `t_v +- d'` and `t_v +- d' / 16`, `d' = sqrt(err / |alpha|) + 2^-21`
//! (`err`: 2^-21 times the size of the edge's terms, a few ulps, plus twice the edge's
//! pad, so the pieces beyond the cuts clear the pad). The pieces between
//! them are decided by the enclosures; the small pieces around each root are kept.
//! This is the fallback the issue asks for: near a double root, or where the
//! discriminant or the leading coefficient is within its error of 0, the pieces around
//! the vertex cannot be decided and the whole span there is kept; in static cases (no
//! roots) a sample within the rounding of an edge gets an open piece and keeps the
//! whole shutter, one clearly outside is culled.
//!
//! *Cost and tightness*: per sample 12 fused multiply-adds, per piece 3 x 4 interval
//! cross products (8 products each), usually 3..10 pieces: several times the
//! original's arithmetic. The kept set exceeds the exact one by the pieces around the
//! roots (about `err / |E'|`, a few ulps of t for a clean crossing; `sqrt(err)` near a
//! double root). On the gate's boundary tiles (seed 1) it admits the same share of
//! samples as the original within 0.01 in most regimes; fewer far from the origin
//! (0.685 against 0.717: the original's spurious spans there are gone; the stability
//! sweep `far` gives an STE of 27..34 % against 11..16 % at 1e5..1e7 px), more on
//! degenerate triangles (0.679 against 0.617: open pieces are kept there).
//!
//! *The pad (a deviation, for the judge).* A piece culled for edge k has every
//! enclosed `b <= -pad_k`, so `E_k <= -pad_k / 2` at every time of it (the middle `b`
//! is doubled); a piece culled for edge j has `E_j >= pad_j / 2`. Without a pad the
//! culled samples touch the covered ones along every edge, and no certificate with
//! rounding in it can separate them; with it there is a gap the judge can certify.
//! `pad_k = 2^-26 (m_i + m_j)^2 + 2^-52 (n_i + n_j)^2 + 2^-126` in f32 at the sample's
//! pixel, with `m_i = |A_i| + |B_i - A_i|` (1-norms of the vertex relative to the
//! pixel and of its motion, the size of the edge's terms) and `n_i` the 1-norm of the
//! vertex's screen coordinates at both ends plus its `|w|` at both ends times
//! `|X| + |Y|` (the size of the terms of `E_k` in screen coordinates, where the cuts
//! below are written). It costs about `pad / |E'|` of shutter at a clean crossing and
//! `2 sqrt(pad / |alpha|)` at a grazing edge (measured below 1e-3 near the origin in
//! the tests), and a band of about `2^-26` of the edge's size in pixels in static
//! cases.
//!
//! *What the gate can prove.* Over a box of pixels (not a single f32 point), two
//! claims, each from the edges' exact values `E_k = g + b t + a t^2` (coefficients
//! affine in the pixel, enclosed in outward-rounded f64; the range over the box is the
//! tighter of that form and the cross product of the relative vertices):
//! - `eval_box >= 0` when every edge stays above `-pad_k / 2` over the box (or every
//!   one below `pad_k / 2`), with the pad's floor over the box (its `|A|` terms only,
//!   every f32 rounding of it taken against it): no piece can then be culled at any
//!   sample of the box, the kept set is all of [0, 1] and `g = min(t, 1 - t) >= 0`;
//! - `lower_cuts`: for the orientation `sigma` of the interior (the sign of D over the
//!   box, D = the determinant of the `(x, y, w)` rows as a cubic in t), each edge not
//!   already above `-pad_k / 2` gets the cut `sigma E_k + pad_k / 4` (its coefficients
//!   rounded to f64, that rounding times each monomial's largest value in `err`).
//!   Where every cut is `>= err`, every edge is above minus half its pad, so nothing is
//!   culled; the judge certifies each cut alone against the interior samples (which
//!   have `sigma E_k > 0`), so boxes next to an edge and around a vertex are decided
//!   whole. Across a facing flip (D of both signs in the box) each orientation gives
//!   its family of cuts, each tagged with the side of D it answers for.
//!
//! `tests/gdam_cut.rs` attacks both claims with dense f32 samples on the band where the
//! pad decides, and every tile the judge proves with covered samples at its edges.

use super::*;

mod safe;
pub use safe::{
    end_of, piece_of, sample_of, still_of, EndOf, Gdam2010Safe, SafeSpans, SafeTimeSpans, SampleOf, METHOD_SAFE,
    PAD_CHOICE,
};

/// The three cross-product vectors of one moving edge: `alpha = a . (X, Y, 1)` etc.
#[derive(Clone, Copy, Debug)]
struct EdgeQuad {
    a: [f32; 3],
    b: [f32; 3],
    c: [f32; 3],
}

fn cross(p: [f32; 3], q: [f32; 3]) -> [f32; 3] {
    [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]]
}

fn add3(p: [f32; 3], q: [f32; 3]) -> [f32; 3] {
    [p[0] + q[0], p[1] + q[1], p[2] + q[2]]
}

fn dot_s(v: [f32; 3], x: f32, y: f32) -> f32 {
    v[0] * x + v[1] * y + v[2]
}

/// The time set of one pixel position: up to 8 closed intervals in [0, 1], sorted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spans {
    pub n: usize,
    pub s: [[f32; 2]; 8],
}

impl Spans {
    pub fn as_slice(&self) -> &[[f32; 2]] {
        &self.s[..self.n]
    }
    /// `max_m min(t - a_m, b_m - t)`, or -1 when empty (f32).
    pub fn signed_distance(&self, t: f32) -> f32 {
        if self.n == 0 {
            return -1.0;
        }
        let mut g = f32::NEG_INFINITY;
        for &[a, b] in self.as_slice() {
            g = g.max((t - a).min(b - t));
        }
        g
    }
}

/// The per-sample constraint: the moving edge quadratics of the triangle.
#[derive(Clone, Copy, Debug)]
pub struct TimeSpans {
    edges: [EdgeQuad; 3],
}

/// Real roots of `a t^2 + b t + c` strictly inside (0, 1), appended to `out`.
fn roots_in_unit(a: f32, b: f32, c: f32, out: &mut [f32; 8], n: &mut usize) {
    let mut push = |r: f32| {
        if r > 0.0 && r < 1.0 {
            out[*n] = r;
            *n += 1;
        }
    };
    if a == 0.0 {
        if b != 0.0 {
            push(-c / b);
        }
        return;
    }
    let disc = b * b - 4.0 * a * c;
    if disc.is_nan() || disc < 0.0 {
        return; // negative, or NaN from overflow
    }
    if disc == 0.0 {
        push(-b / (2.0 * a));
        return;
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    push(q / a);
    if q != 0.0 {
        push(c / q);
    }
}

impl TimeSpans {
    fn new(tri: &Triangle) -> Self {
        let xyw = |p: [f32; 4]| [p[0], p[1], p[3]];
        let p0 = tri.q.map(xyw);
        let dp: [[f32; 3]; 3] = std::array::from_fn(|i| {
            let (q, r) = (xyw(tri.q[i]), xyw(tri.r[i]));
            [r[0] - q[0], r[1] - q[1], r[2] - q[2]]
        });
        let edge = |i: usize, j: usize| EdgeQuad {
            a: cross(dp[i], dp[j]),
            b: add3(cross(p0[i], dp[j]), cross(dp[i], p0[j])),
            c: cross(p0[i], p0[j]),
        };
        TimeSpans { edges: [edge(1, 2), edge(2, 0), edge(0, 1)] }
    }

    /// The computed time set at pixel position (x, y), in f32.
    pub fn spans_at(&self, x: f32, y: f32) -> Spans {
        let coef = self.edges.map(|e| [dot_s(e.a, x, y), dot_s(e.b, x, y), dot_s(e.c, x, y)]);
        let mut cuts = [0.0f32; 8];
        let mut n = 1; // cuts[0] = 0
        for &[a, b, c] in &coef {
            roots_in_unit(a, b, c, &mut cuts, &mut n);
        }
        cuts[n] = 1.0;
        n += 1;
        cuts[1..n - 1].sort_by(|p, q| p.partial_cmp(q).unwrap());
        let mut out = Spans { n: 0, s: [[0.0; 2]; 8] };
        for w in cuts[..n].windows(2) {
            let (lo, hi) = (w[0], w[1]);
            if hi <= lo {
                continue;
            }
            let mid = lo + 0.5 * (hi - lo);
            let e = coef.map(|[a, b, c]| (a * mid + b) * mid + c);
            let inside = e.iter().all(|&v| v > 0.0) || e.iter().all(|&v| v < 0.0);
            if !inside {
                continue;
            }
            if out.n > 0 && out.s[out.n - 1][1] == lo {
                out.s[out.n - 1][1] = hi;
            } else {
                out.s[out.n] = [lo, hi];
                out.n += 1;
            }
        }
        out
    }
}

/// Is the f64 interval a single f32 value?
fn f32_point(i: Interval) -> Option<f32> {
    (i.lo == i.hi && (i.lo as f32) as f64 == i.lo).then_some(i.lo as f32)
}

impl SampleConstraint for TimeSpans {
    fn name(&self) -> String {
        "gdam2010 covered time set at the sample's (x, y)".to_string()
    }
    fn eval(&self, s: &Sample) -> f32 {
        self.spans_at(s.x, s.y).signed_distance(s.t)
    }
    /// `eval` over the columns (the time set at each sample's (x, y), sample by sample,
    /// without a call through the trait object per sample).
    fn eval_row(&self, c: &SampleCols, out: &mut [f32]) {
        for (((o, &x), &y), &t) in out.iter_mut().zip(c.x).zip(c.y).zip(c.t) {
            *o = self.spans_at(x, y).signed_distance(t);
        }
    }
    fn eval_box(&self, b: &SampleBox) -> Interval {
        spans_eval_box(|x, y| self.spans_at(x, y), b)
    }
}

/// The enclosure of `g` over a box (see the module doc, "The per-sample constraint"),
/// for the time sets computed by `spans_at` (any sets of intervals within [0, 1]).
fn spans_eval_box(spans_at: impl Fn(f32, f32) -> Spans, b: &SampleBox) -> Interval {
    let t = b.t;
    let tm = t.lo.abs().max(t.hi.abs());
    let floor = 2f64.powi(-140);
    if let (Some(x), Some(y)) = (f32_point(b.x), f32_point(b.y)) {
        let sp = spans_at(x, y);
        if sp.n == 0 {
            return Interval::point(-1.0);
        }
        let mut g: Option<Interval> = None;
        for &[a0, a1] in sp.as_slice() {
            let e0 = 2f64.powi(-20) * (tm + (a0 as f64).abs()) + floor;
            let e1 = 2f64.powi(-20) * (tm + (a1 as f64).abs()) + floor;
            let d0 = t - Interval::point(a0 as f64) + Interval::new(-e0, e0);
            let d1 = Interval::point(a1 as f64) - t + Interval::new(-e1, e1);
            let m = Interval::new(d0.lo.min(d1.lo), d0.hi.min(d1.hi));
            g = Some(match g {
                None => m,
                Some(g) => Interval::new(g.lo.max(m.lo), g.hi.max(m.hi)),
            });
        }
        return g.unwrap();
    }
    // Any interval set within [0, 1]: each term min(t - a, b - t) lies in
    // [min(t - 1, -t), min(t, 1 - t)]; the empty set gives -1.
    let e = 2f64.powi(-20) * (tm + 1.0) + floor;
    let lo = (-1.0f64).min(t.lo - 1.0).min(-t.hi) - e;
    let hi = t.hi.min(1.0 - t.lo) + e;
    Interval::new(lo.next_down(), hi.next_up())
}

struct Prep<S> {
    spans: Option<S>,
    why: &'static str,
}

impl<S: SampleConstraint + Copy + 'static> Prepared for Prep<S> {
    fn tile(&self, _tile: &Tile) -> TileResult {
        let mut b = TileBounds::full();
        if let Some(s) = self.spans {
            b.constraints.push(Box::new(s));
        }
        TileResult::Bounds(b)
    }
    fn disabled(&self) -> Option<&'static str> {
        self.spans.is_none().then_some(self.why)
    }
    /// The answer never reads the tile: the full domain and the time set at the
    /// sample's (x, y).
    fn tile_independent(&self) -> bool {
        true
    }
}

struct Gdam2010;

pub(crate) static INFO: MethodInfo = MethodInfo {
    id: "gdam2010",
    source: "Gribel, Doggett, Akenine-Möller 2010, Analytical Motion Blur Rasterization with Compression \
             (cited by Nilsson et al. 2012 §2, §4); quadratic moving edge functions of Munkberg et al. 2011 \
             (as restated in docs/reconstructions.md)",
    reconstruction: false,
    dims: &[Dims::Motion],
    outputs: Outputs { tile_reject: false, lens: false, time: false, depth: false, per_sample: true },
};

fn defocused(tri: &Triangle) -> bool {
    tri.c0.iter().chain(tri.c1.iter()).any(|&c| c != 0.0)
}

impl Method for Gdam2010 {
    fn info(&self) -> &'static MethodInfo {
        &INFO
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        let defocus = defocused(tri);
        Box::new(Prep { spans: (!defocus).then(|| TimeSpans::new(tri)), why: "defocus: gdam2010 is motion-only" })
    }
}

pub static METHOD: &dyn Method = &Gdam2010;

#[cfg(test)]
mod tests;
