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

use super::*;

/// The bilinear ut / vt test of Munkberg and Akenine-Möller 2012, §2.1.
pub struct Mam2012;

static INFO: MethodInfo = MethodInfo {
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
/// its x-slopes at t = 0, 1.
#[derive(Clone, Copy, Debug)]
struct Patch {
    xa: f32,
    at_xa: [f32; 2],
    slope: [f32; 2],
}

impl Patch {
    /// The tile line (values at t = 0 and t = 1) for the tile `[xc - h, xc + h]`:
    /// lowered by `h |S_k|` (`dir = -1`, lower patch) or raised (`dir = 1`).
    fn line(&self, xc: f32, h: f32, dir: f32) -> Option<[f32; 2]> {
        let e = |k: usize| self.at_xa[k] + (xc - self.xa) * self.slope[k] + dir * (h * self.slope[k].abs());
        let l = [e(0), e(1)];
        (l[0].is_finite() && l[1].is_finite()).then_some(l)
    }
}

/// The lower and upper patch of one lens axis (u with x, or v with y).
#[derive(Clone, Copy, Debug)]
struct Axis {
    lo: Option<Patch>,
    hi: Option<Patch>,
}

#[derive(Clone, Copy, Debug)]
struct Setup {
    u: Axis,
    v: Axis,
}

struct Prep(Result<Setup, &'static str>);

/// Lower and upper values at t = 0 and t = 1 of the Figure 5 lines (chord and tangent
/// at 1/2) of `f(t) = N(t) / C(t)`, N and C linear, C != 0 on [0, 1]. With
/// `literal_fig5` the tangent is replaced by the line as printed in Figure 5 (slope
/// `f'(1/2) / 2`; only for the test that shows it is not a bound). Non-finite results
/// give -inf / +inf.
fn fig5_corners(n: [f32; 2], c: [f32; 2], literal_fig5: bool) -> ([f32; 2], [f32; 2]) {
    let chord = [n[0] / c[0], n[1] / c[1]];
    let ch = 0.5 * (c[0] + c[1]);
    let fh = (0.5 * (n[0] + n[1])) / ch;
    let d = (n[1] * c[0] - n[0] * c[1]) / (ch * ch);
    let tan = if literal_fig5 { [fh - 0.5 * d, fh] } else { [fh - 0.5 * d, fh + 0.5 * d] };
    let mut lo = [f32::NEG_INFINITY; 2];
    let mut hi = [f32::INFINITY; 2];
    for k in 0..2 {
        let (a, b) = (chord[k], tan[k]);
        if a.is_finite() && b.is_finite() {
            lo[k] = if a < b { a } else { b };
            hi[k] = if a > b { a } else { b };
        }
    }
    (lo, hi)
}

/// The patches of one axis: `pos[j]`, `w[j]`, `den[j]` are vertex j's coordinate, w and
/// CoC denominator (`c` or `k c`) at t = 0, 1; `[xa, xb]` the patch domain.
fn axis(pos: [[f32; 2]; 3], w: [[f32; 2]; 3], den: [[f32; 2]; 3], xa: f32, xb: f32, literal_fig5: bool) -> Axis {
    // corners[side][k]: side 0 at xa, 1 at xb; k = t end.
    let mut lo = [[f32::INFINITY; 2]; 2];
    let mut hi = [[f32::NEG_INFINITY; 2]; 2];
    for (side, x) in [xa, xb].into_iter().enumerate() {
        for j in 0..3 {
            let n = [x * w[j][0] - pos[j][0], x * w[j][1] - pos[j][1]];
            let (l, h) = fig5_corners(n, den[j], literal_fig5);
            for k in 0..2 {
                // Explicit comparisons: l is never NaN here (fig5_corners maps it to -inf).
                if l[k] < lo[side][k] {
                    lo[side][k] = l[k];
                }
                if h[k] > hi[side][k] {
                    hi[side][k] = h[k];
                }
            }
        }
    }
    let width = xb - xa;
    let patch = |c: [[f32; 2]; 2]| -> Option<Patch> {
        if !c.iter().flatten().all(|v| v.is_finite()) {
            return None;
        }
        let slope = if width > 0.0 { [(c[1][0] - c[0][0]) / width, (c[1][1] - c[0][1]) / width] } else { [0.0, 0.0] };
        (slope[0].is_finite() && slope[1].is_finite()).then_some(Patch { xa, at_xa: c[0], slope })
    };
    Axis { lo: patch(lo), hi: patch(hi) }
}

/// Screen extent along `axis` (0: x, 1: y) of the moving, defocused triangle, from the
/// corners (lens +-1, t = 0, 1) of each vertex. Requires every w > 0 (checked by caller).
fn extent(tri: &Triangle, ax: usize) -> Option<(f32, f32)> {
    let kf = if ax == 0 { 1.0 } else { tri.k };
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for j in 0..3 {
        for (p, c) in [(tri.q[j], tri.c0[j]), (tri.r[j], tri.c1[j])] {
            for s in [-1.0f32, 1.0] {
                let x = (p[ax] + s * (kf * c)) / p[3];
                if !x.is_finite() {
                    return None;
                }
                lo = lo.min(x);
                hi = hi.max(x);
            }
        }
    }
    Some((lo, hi))
}

/// The reason the test cannot run on this triangle, if any.
fn why_disabled(tri: &Triangle) -> Option<&'static str> {
    for j in 0..3 {
        let (a, b) = (tri.c0[j], tri.c1[j]);
        if a == 0.0 || b == 0.0 || (a > 0.0) != (b > 0.0) {
            return Some("some c_j(t) = 0 in the shutter (a vertex touches or crosses the focal plane)");
        }
    }
    let pos = tri.c0[0] > 0.0;
    if tri.c0.iter().chain(tri.c1.iter()).any(|&c| (c > 0.0) != pos) {
        return Some("the vertices' CoC differ in sign (the triangle straddles the focal plane)");
    }
    if (0..3).any(|j| !(tri.q[j][3] > 0.0 && tri.r[j][3] > 0.0)) {
        return Some("a vertex has w <= 0 in the shutter (no finite screen extent for the patch domain)");
    }
    None
}

fn setup(tri: &Triangle, literal_fig5: bool) -> Result<Setup, &'static str> {
    if let Some(why) = why_disabled(tri) {
        return Err(why);
    }
    let (Some((xa, xb)), Some((ya, yb))) = (extent(tri, 0), extent(tri, 1)) else {
        return Err("the screen extent of the triangle is not finite in f32");
    };
    let w = [0, 1, 2].map(|j| [tri.q[j][3], tri.r[j][3]]);
    let px = [0, 1, 2].map(|j| [tri.q[j][0], tri.r[j][0]]);
    let py = [0, 1, 2].map(|j| [tri.q[j][1], tri.r[j][1]]);
    let cu = [0, 1, 2].map(|j| [tri.c0[j], tri.c1[j]]);
    let cv = [0, 1, 2].map(|j| [tri.k * tri.c0[j], tri.k * tri.c1[j]]);
    Ok(Setup { u: axis(px, w, cu, xa, xb, literal_fig5), v: axis(py, w, cv, ya, yb, literal_fig5) })
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

impl Prepared for Prep {
    fn tile(&self, tile: &Tile) -> TileResult {
        let s = match &self.0 {
            Ok(s) => s,
            Err(_) => return TileResult::Bounds(TileBounds::full()),
        };
        let (xc, yc) = tile.center();
        let (hx, hy) = (0.5 * (tile.x1 - tile.x0), 0.5 * (tile.y1 - tile.y0));
        let mut out = TileBounds::full();
        for (is_v, ax, c, h) in [(false, &s.u, xc, hx), (true, &s.v, yc, hy)] {
            let lo = ax.lo.and_then(|p| p.line(c, h, -1.0));
            let hi = ax.hi.and_then(|p| p.line(c, h, 1.0));
            let r_lo = lo.map_or(-1.0, |l| l[0].min(l[1]).max(-1.0));
            let r_hi = hi.map_or(1.0, |l| l[0].max(l[1]).min(1.0));
            let nonempty = r_lo <= r_hi; // false on NaN too
            if !nonempty {
                return TileResult::Empty;
            }
            if is_v {
                out.v = [r_lo, r_hi];
            } else {
                out.u = [r_lo, r_hi];
            }
            for (upper, l) in [(false, lo), (true, hi)] {
                if let Some(l) = l {
                    let a = l[1] - l[0];
                    if a.is_finite() {
                        out.constraints.push(Box::new(Line { is_v, upper, a, b: l[0] }));
                    }
                }
            }
        }
        TileResult::Bounds(out)
    }
    fn disabled(&self) -> Option<&'static str> {
        self.0.as_ref().err().copied()
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::{assert_keeps_covered, covered, near_miss_check, random_sample, spot_check};
    use super::*;
    use crate::model::ThinLens;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn cam() -> ThinLens {
        // c(w) = -50 + 12.5 w: zero at w = 4.
        ThinLens { fx: 100.0, fy: 100.0, cx: 0.0, cy: 0.0, radius: 0.5, focus: 4.0, near: 0.1, far: 100.0 }
    }

    /// Figure 1: a small out-of-focus triangle moving across the screen.
    fn fig1() -> Triangle {
        let q = [[-2.0, -0.05, 8.0], [-1.9, -0.05, 8.0], [-1.95, 0.05, 8.0]];
        let r = q.map(|p| [p[0] + 4.0, p[1], p[2]]);
        cam().triangle(q, r)
    }

    /// Cases for the spot check: (triangle, tiles).
    fn cases() -> Vec<(Triangle, Vec<Tile>)> {
        let c = cam();
        let mut v = vec![(
            fig1(),
            vec![Tile::square(-0.5, -0.5, 1.0), Tile::square(-3.0, -2.0, 4.0), Tile::square(10.0, 0.0, 2.0)],
        )];
        // In front of the focal plane (c < 0), moving and approaching the lens.
        v.push((
            c.triangle(
                [[-1.0, -1.0, 3.0], [1.0, -0.8, 3.0], [0.0, 1.0, 3.2]],
                [[-0.6, -0.7, 1.5], [0.9, -0.5, 1.6], [0.3, 0.8, 1.7]],
            ),
            vec![Tile::square(0.0, 0.0, 2.0), Tile::square(-40.0, -40.0, 8.0), Tile::square(30.0, 10.0, 4.0)],
        ));
        // Large perspective motion behind the focal plane: c goes from 200 to 6.25.
        v.push((
            c.triangle(
                [[-1.0, -1.0, 20.0], [2.0, -1.0, 20.0], [0.0, 2.0, 20.0]],
                [[-1.0, -1.0, 4.5], [2.0, -1.0, 4.5], [0.0, 2.0, 4.5]],
            ),
            vec![Tile::square(0.0, 0.0, 2.0), Tile::square(-24.0, -24.0, 4.0), Tile::square(40.0, -20.0, 4.0)],
        ));
        // Per-vertex CoC variant (no physical lens), aspect k = 0.75.
        let mut t = Triangle::fixed([[-10.0, -5.0, 0.0, 2.0], [12.0, -4.0, 0.0, 2.5], [0.0, 14.0, 0.0, 3.0]]);
        t.r = [[-4.0, -2.0, 0.0, 1.0], [14.0, 0.0, 0.0, 3.0], [6.0, 12.0, 0.0, 2.0]];
        t.c0 = [3.0, 1.0, 5.0];
        t.c1 = [0.5, 6.0, 2.0];
        t.k = 0.75;
        v.push((t, vec![Tile::square(0.0, 0.0, 1.0), Tile::square(-12.0, -6.0, 4.0), Tile::square(4.0, 6.0, 2.0)]));
        v
    }

    #[test]
    fn conservative_on_random_samples() {
        for (ci, (tri, tiles)) in cases().into_iter().enumerate() {
            let p = METHOD.setup(&tri);
            assert_eq!(p.disabled(), None, "case {ci}");
            let mut total = 0;
            for (ti, tile) in tiles.iter().enumerate() {
                let (cov, bad) = spot_check(p.as_ref(), &tri, tile, 50_000, 1000 + 10 * ci as u64 + ti as u64);
                assert!(
                    bad.is_empty(),
                    "case {ci} tile {ti}: {} covered samples culled, first {:?}",
                    bad.len(),
                    bad[0]
                );
                total += cov;
                let (_, bad) = near_miss_check(p.as_ref(), &tri, tile, 3000, 5000 + ti as u64);
                assert!(bad.is_empty(), "case {ci} tile {ti}: covered sample culled near a bound {:?}", bad[0]);
            }
            assert!(total > 100, "case {ci}: only {total} covered samples, the check is too weak");
        }
    }

    /// Many random physical triangles on one side of the focal plane (strong perspective
    /// motion included) and tiles near them.
    #[test]
    fn conservative_on_random_triangles() {
        let mut rng = ChaCha8Rng::seed_from_u64(98);
        let c = cam();
        let (mut near_total, mut cov_total, mut culled_tiles, mut constrained) = (0, 0, 0, 0);
        for it in 0..300 {
            let range = if it % 2 == 0 { 4.2..40.0 } else { 0.3..3.8 };
            let z0: f32 = rng.gen_range(range.clone());
            let z1: f32 = if it % 3 == 0 { z0 } else { rng.gen_range(range) };
            let mut v = || -> [f32; 3] {
                [rng.gen_range(-0.3..0.3f32), rng.gen_range(-0.3..0.3f32), rng.gen_range(-0.04..0.04f32)]
            };
            let (a, b, d) = (v(), v(), v());
            let mv = v();
            let q = [a, b, d].map(|p| [p[0] * z0, p[1] * z0, z0 * (1.0 + p[2])]);
            let r = [a, b, d].map(|p| [(p[0] + mv[0]) * z1, (p[1] + mv[1]) * z1, z1 * (1.0 + p[2])]);
            let tri = c.triangle(q, r);
            let p = METHOD.setup(&tri);
            assert_eq!(p.disabled(), None, "{tri:?}");
            for _ in 0..3 {
                let size = [1.0f32, 2.0, 4.0][rng.gen_range(0..3)];
                let tile = Tile::square(rng.gen_range(-40.0..40.0), rng.gen_range(-40.0..40.0), size);
                match p.tile(&tile) {
                    TileResult::Empty => culled_tiles += 1,
                    TileResult::Bounds(b) => constrained += (b.u != [-1.0, 1.0] || b.v != [-1.0, 1.0]) as usize,
                }
                let (cov, tried) =
                    assert_keeps_covered(p.as_ref(), &tri, &tile, (2000, 300), it * 7 + 1, &format!("triangle {it}"));
                cov_total += cov;
                near_total += tried;
            }
        }
        eprintln!("near-miss probes {near_total}, covered {cov_total}, culled tiles {culled_tiles}, narrowed lens {constrained}");
        assert!(cov_total > 5000 && culled_tiles > 50);
    }

    #[test]
    fn static_triangle_keeps_time() {
        // In focus: disabled, full bounds.
        let tri = Triangle::fixed([[-20.0, -20.0, 0.0, 1.0], [20.0, -20.0, 0.0, 1.0], [0.0, 20.0, 0.0, 1.0]]);
        let p = METHOD.setup(&tri);
        assert!(p.disabled().is_some());
        let TileResult::Bounds(b) = p.tile(&Tile::square(-1.0, -1.0, 2.0)) else { panic!("empty") };
        assert_eq!((b.u, b.v, b.t), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]));
        // Defocused but static (behind the focal plane): the whole lens and shutter stay.
        let tri = cam().triangle(
            [[-2.0, -2.0, 8.0], [2.0, -2.0, 8.0], [0.0, 2.0, 8.0]],
            [[-2.0, -2.0, 8.0], [2.0, -2.0, 8.0], [0.0, 2.0, 8.0]],
        );
        let p = METHOD.setup(&tri);
        assert_eq!(p.disabled(), None);
        let TileResult::Bounds(b) = p.tile(&Tile::square(-1.0, -1.0, 2.0)) else { panic!("empty") };
        assert_eq!((b.u, b.v, b.t), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]));
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for _ in 0..1000 {
            let s = random_sample(&mut rng, &Tile::square(-1.0, -1.0, 2.0));
            assert!(b.admits(&s), "{s:?}");
        }
    }

    #[test]
    fn far_tile_is_culled() {
        let p = METHOD.setup(&fig1());
        assert!(matches!(p.tile(&Tile::square(200.0, 0.0, 2.0)), TileResult::Empty));
        assert!(matches!(p.tile(&Tile::square(0.0, -300.0, 2.0)), TileResult::Empty));
        assert!(matches!(p.tile(&Tile::square(-0.5, -0.5, 1.0)), TileResult::Bounds(_)));
    }

    #[test]
    fn focal_plane_crossing_is_disabled() {
        let mut tri = fig1();
        // Vertex 1 moves from in front of the focal plane to behind it.
        tri.q[1][3] = 3.0;
        tri.c0[1] = cam().coc(3.0);
        assert!(tri.c0[1] < 0.0 && tri.c1[1] > 0.0);
        let p = METHOD.setup(&tri);
        assert!(p.disabled().unwrap().contains("c_j(t) = 0"));
        let TileResult::Bounds(b) = p.tile(&Tile::square(200.0, 0.0, 2.0)) else { panic!("empty") };
        assert_eq!((b.u, b.v, b.t, b.constraints.len()), ([-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0], 0));
        // A vertex exactly on the focal plane at t = 0.
        let mut tri = fig1();
        tri.c0[2] = 0.0;
        assert!(METHOD.setup(&tri).disabled().is_some());
    }

    /// With constant CoC of mixed signs (no vertex crosses the focal plane, the triangle
    /// straddles it), `[min u_ij, max u_ij]` is not a bound: witness below. So the test
    /// is disabled for such triangles.
    #[test]
    fn mixed_coc_signs_need_disabling() {
        // A at x = -10 with c = +5, B at x = +10 with c = -5, C above A with c = +5; w = 1.
        let mut tri = Triangle::fixed([[-10.0, -1.0, 0.0, 1.0], [10.0, -1.0, 0.0, 1.0], [-10.0, 10.0, 0.0, 1.0]]);
        tri.c0 = [5.0, -5.0, 5.0];
        tri.c1 = tri.c0;
        let tile = Tile::square(-0.5, -0.5, 1.0);
        let s = Sample::new(0.0, 0.0, 0.0, 0.0, 0.5);
        assert!(covered(&tri, &s));
        // u_ij over both tile sides and all vertices at t = 0.5.
        let u_ij: Vec<f64> = [tile.x0, tile.x1]
            .iter()
            .flat_map(|&x| (0..3).map(move |j| (x as f64 - tri.q[j][0] as f64) / tri.c0[j] as f64))
            .collect();
        let lo = u_ij.iter().cloned().fold(f64::INFINITY, f64::min);
        assert!(lo > 0.0, "the naive interval [{lo}, ..] excludes the covered sample at u = 0");
        let p = METHOD.setup(&tri);
        assert!(p.disabled().unwrap().contains("straddles"));
    }

    /// Figure 5 as printed (tangent slope halved) is not a lower bound of a decreasing
    /// convex curve once used in the corner construction of Appendix A; the tangent is.
    /// Witness: the Figure 1 triangle moving towards the focal plane.
    #[test]
    fn fig5_as_printed_culls_a_covered_sample() {
        // Pure curve: f = 1 / (1 + 3t); the lower line through the corner values.
        let (lit, _) = fig5_corners([1.0, 1.0], [1.0, 4.0], true);
        let (tan, _) = fig5_corners([1.0, 1.0], [1.0, 4.0], false);
        let f = |t: f32| 1.0 / (1.0 + 3.0 * t);
        let line = |c: [f32; 2], t: f32| c[0] + t * (c[1] - c[0]);
        assert!(line(lit, 0.9) > f(0.9), "printed form bounds f");
        assert!((0..=100).all(|i| line(tan, i as f32 / 100.0) <= f(i as f32 / 100.0)));
        // A full witness: a thin triangle moving right by 8.6 px while it moves away from
        // the lens behind the focal plane (w 4.5 -> 20, c 6.25 -> 200): its u_j(t) at a
        // column right of it are convex and decreasing.
        let c = cam();
        let at = |scr: [[f32; 2]; 3], z: f32| scr.map(|p| [p[0] * z / 100.0, p[1] * z / 100.0, z]);
        let tri = c.triangle(
            at([[-8.0, -5.0], [-8.0, 10.0], [-8.3, 2.0]], 4.5),
            at([[0.6, -5.0], [0.6, 10.0], [0.3, 2.0]], 20.0),
        );
        let lit = Prep(setup(&tri, true));
        let exact = Prep(setup(&tri, false));
        let (mut n_lit, mut n_tan, mut cov) = (0, 0, 0);
        for (i, tile) in
            [Tile::square(2.5, 0.0, 1.0), Tile::square(4.5, 0.0, 1.0), Tile::square(0.0, -1.0, 2.0)].iter().enumerate()
        {
            let (c1, b1) = spot_check(&lit, &tri, tile, 20_000, 77 + i as u64);
            let (_, b2) = spot_check(&exact, &tri, tile, 20_000, 77 + i as u64);
            n_lit += b1.len();
            n_tan += b2.len();
            cov += c1;
            if let Some(s) = b1.first() {
                eprintln!("printed Fig. 5 culls covered {s:?} ({} of {c1})", b1.len());
            }
        }
        // Seen: 72 of 323 covered samples culled by the printed form, e.g. (x, y, u, v, t) =
        // (2.8271384, 0.6382387, 0.28470385, -0.028111339, 0.83432174); none by the tangent.
        assert!(cov > 200);
        assert_eq!(n_tan, 0);
        assert!(n_lit > 0, "expected the printed formula to cull a covered sample");
    }

    /// Figure 1: the ut region between the lines is much smaller than the axis-aligned
    /// dual-space box [u^] x [t^] (computed by brute force over a fine t grid).
    #[test]
    fn fig1_region_is_smaller_than_the_axis_aligned_box() {
        let tri = fig1();
        let tile = Tile::square(-0.5, -0.5, 1.0);
        // Brute-force box: min / max of u_ij(t) over both tile sides and all vertices.
        let n = 20_000;
        let (mut t_lo, mut t_hi, mut u_lo, mut u_hi) =
            (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..=n {
            let t = i as f64 / n as f64;
            let (mut a, mut b) = (f64::INFINITY, f64::NEG_INFINITY);
            for x in [tile.x0 as f64, tile.x1 as f64] {
                for j in 0..3 {
                    let l = |p: f32, q: f32| (1.0 - t) * p as f64 + t * q as f64;
                    let u = (x * l(tri.q[j][3], tri.r[j][3]) - l(tri.q[j][0], tri.r[j][0])) / l(tri.c0[j], tri.c1[j]);
                    a = a.min(u);
                    b = b.max(u);
                }
            }
            let (a, b) = (a.max(-1.0), b.min(1.0));
            if a <= b {
                t_lo = t_lo.min(t);
                t_hi = t_hi.max(t);
                u_lo = u_lo.min(a);
                u_hi = u_hi.max(b);
            }
        }
        let box_area = (t_hi - t_lo) * (u_hi - u_lo);
        assert!(box_area > 0.1, "box {box_area}");
        // The region between the mam2012 lines inside that box.
        let p = METHOD.setup(&tri);
        let TileResult::Bounds(bd) = p.tile(&tile) else { panic!("empty") };
        let lines: Vec<&Box<dyn SampleConstraint>> =
            bd.constraints.iter().filter(|c| c.name().starts_with("ut")).collect();
        assert_eq!(lines.len(), 2);
        let m = 4000;
        let mut area = 0.0;
        for i in 0..m {
            let t = t_lo + (t_hi - t_lo) * (i as f64 + 0.5) / m as f64;
            // g(u) is affine in u: find where each line admits.
            let (mut a, mut b) = (u_lo.max(bd.u[0] as f64), u_hi.min(bd.u[1] as f64));
            for c in &lines {
                let s0 = Sample::new(0.0, 0.0, 0.0, 0.0, t as f32);
                let s1 = Sample::new(0.0, 0.0, 1.0, 0.0, t as f32);
                let (g0, g1) = (c.eval(&s0) as f64, c.eval(&s1) as f64);
                let root = -g0 / (g1 - g0);
                if g1 > g0 {
                    a = a.max(root);
                } else {
                    b = b.min(root);
                }
            }
            area += (b - a).max(0.0) * (t_hi - t_lo) / m as f64;
        }
        eprintln!("axis-aligned box {box_area:.4}, mam2012 region {area:.4}");
        assert!(area > 0.0);
        assert!(area < 0.5 * box_area, "region {area} vs box {box_area}");
        // The per-tile u^ alone is no better than the box: the gain is the correlation.
        assert!(bd.u[1] - bd.u[0] > 1.5);
        // The same against la2011's axis-aligned box, once that file is implemented.
        if super::super::la2011::METHOD.info().source != "STUB" {
            let la = match super::super::la2011::METHOD.setup(&tri).tile(&tile) {
                TileResult::Bounds(b) => ((b.u[1] - b.u[0]) * (b.t[1] - b.t[0])) as f64,
                TileResult::Empty => panic!("la2011 rejects a tile with covered samples"),
            };
            eprintln!("la2011 box {la:.4}");
            assert!(area < 0.5 * la, "region {area} vs la2011 box {la}");
        }
    }

    #[test]
    fn eval_box_encloses_eval() {
        let tri = cases()[3].0;
        let p = METHOD.setup(&tri);
        let TileResult::Bounds(b) = p.tile(&Tile::square(0.0, 0.0, 1.0)) else { panic!("empty") };
        assert_eq!(b.constraints.len(), 4);
        super::super::testkit::assert_eval_box_encloses(&b, &Tile::square(0.0, 0.0, 1.0), 3);
    }

    #[test]
    fn degenerate_input_does_not_panic() {
        let mut tri = Triangle::fixed([[0.0, 0.0, 0.0, 1.0]; 3]);
        tri.c0 = [1e-45; 3];
        tri.c1 = [1e-45; 3];
        let p = METHOD.setup(&tri);
        let _ = p.tile(&Tile::square(0.0, 0.0, 1.0));
        tri.c0 = [3e38; 3];
        tri.q[0] = [3e38, -3e38, 0.0, 1e-30];
        let p = METHOD.setup(&tri);
        let _ = p.tile(&Tile::square(-1e30, 0.0, 1e30));
        let mut t = fig1();
        t.q[0][3] = -1.0;
        assert!(METHOD.setup(&t).disabled().unwrap().contains("w <= 0"));
    }

    #[test]
    fn degenerate_and_huge_input_is_answered_in_the_domain() {
        super::super::testkit::assert_degenerate_input_is_answered(METHOD, &super::super::la2011::figure1::triangle());
    }
}
