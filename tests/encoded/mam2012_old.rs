//! `mam2012` as it was before its setup and tile path were written over `F32Arith`
//! (kept verbatim, the method's metadata aside): the reference the encoded code is
//! compared with, bit for bit.
#![allow(dead_code)]

use cullproof::bounds::{Prepared, SampleBox, SampleConstraint, TileBounds, TileResult};
use cullproof::{Interval, Sample, Tile, Triangle};
use std::ops::{Add, Div, Mul, Sub};

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

/// The arithmetic of the formulas `mam2012` (plain f32) and `mam2012-safe` (f32
/// intervals rounded outward, [`Iv`]) share: written once, evaluated in either.
pub(crate) trait Arith:
    Copy + From<f32> + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
}
impl<T: Copy + From<f32> + Add<Output = T> + Sub<Output = T> + Mul<Output = T> + Div<Output = T>> Arith for T {}

/// The values at t = 0 and t = 1 of the chord and of the tangent at 1/2 (or, with
/// `literal_fig5`, of Figure 5's printed line) of `f(t) = N(t) / C(t)`.
pub(crate) fn fig5_lines<T: Arith>(n: [T; 2], c: [T; 2], literal_fig5: bool) -> ([T; 2], [T; 2]) {
    let half = T::from(0.5);
    let chord = [n[0] / c[0], n[1] / c[1]];
    let ch = half * (c[0] + c[1]);
    let fh = (half * (n[0] + n[1])) / ch;
    let d = (n[1] * c[0] - n[0] * c[1]) / (ch * ch);
    let tan = if literal_fig5 { [fh - half * d, fh] } else { [fh - half * d, fh + half * d] };
    (chord, tan)
}

/// `N(t) = X w_j(t) - x_j(t)` at t = 0, 1 for the column `x`.
pub(crate) fn numerators<T: Arith>(x: T, w: [T; 2], pos: [T; 2]) -> [T; 2] {
    [x * w[0] - pos[0], x * w[1] - pos[1]]
}

/// Vertex j's screen position seen from the lens edge `s = +-1`: `(p + s (kf c)) / w`.
pub(crate) fn projected<T: Arith>(p: T, s: f32, kf: T, c: T, w: T) -> T {
    (p + T::from(s) * (kf * c)) / w
}

/// Lower and upper values at t = 0 and t = 1 of the Figure 5 lines (chord and tangent
/// at 1/2) of `f(t) = N(t) / C(t)`, N and C linear, C != 0 on [0, 1]. With
/// `literal_fig5` the tangent is replaced by the line as printed in Figure 5 (slope
/// `f'(1/2) / 2`; only for the test that shows it is not a bound). Non-finite results
/// give -inf / +inf.
fn fig5_corners(n: [f32; 2], c: [f32; 2], literal_fig5: bool) -> ([f32; 2], [f32; 2]) {
    let (chord, tan) = fig5_lines(n, c, literal_fig5);
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
            let n = numerators(x, w[j], pos[j]);
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
                let x = projected(p[ax], s, kf, c, p[3]);
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
pub(crate) fn why_disabled(tri: &Triangle) -> Option<&'static str> {
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
pub(crate) struct Line {
    pub(crate) is_v: bool,
    pub(crate) upper: bool,
    pub(crate) a: f32,
    pub(crate) b: f32,
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

/// The old answer of `mam2012` for a triangle and a tile.
pub fn answer(tri: &Triangle, tile: &Tile) -> TileResult {
    Prep(setup(tri, false)).tile(tile)
}
