//! `mam2012-safe`: the patches and lines of `mam2012` in f32 interval arithmetic
//! rounded outward (`Iv`), the per-sample lines stepped outward, and the per-axis grid.
//! The derivation and the error analysis are in the parent's module doc (section
//! "`mam2012-safe`").

use super::*;
use std::ops::{Add, Div, Mul, Sub};

/// A closed f32 interval `[lo, hi]` holding an exact real value: every operation rounds
/// to nearest and steps each end one f32 outward (see the module's error analysis). A
/// NaN end, or a division by an interval holding 0, gives NaN ends: not [`usable`](Iv::usable).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Iv {
    pub(super) lo: f32,
    pub(super) hi: f32,
}

/// NaN-propagating min and max (`f32::min` / `max` would drop a NaN).
fn nan_min(a: f32, b: f32) -> f32 {
    if a.is_nan() || b.is_nan() {
        f32::NAN
    } else if b < a {
        b
    } else {
        a
    }
}
fn nan_max(a: f32, b: f32) -> f32 {
    -nan_min(-a, -b)
}

impl Iv {
    const NAN: Iv = Iv { lo: f32::NAN, hi: f32::NAN };
    /// Finite ends in order (false on NaN).
    pub(super) fn usable(self) -> bool {
        self.lo.is_finite() && self.hi.is_finite() && self.lo <= self.hi
    }
    /// Both enclosures hold the value, so their intersection does; an unusable one is
    /// ignored.
    fn meet(self, o: Iv) -> Iv {
        match (self.usable(), o.usable()) {
            (true, true) => Iv { lo: self.lo.max(o.lo), hi: self.hi.min(o.hi) },
            (true, false) => self,
            (false, true) => o,
            (false, false) => Iv::NAN,
        }
    }
    /// The four end products (or quotients), rounded, then stepped outward.
    fn outward(v: [f32; 4]) -> Iv {
        Iv {
            lo: v.into_iter().fold(f32::INFINITY, nan_min).next_down(),
            hi: v.into_iter().fold(f32::NEG_INFINITY, nan_max).next_up(),
        }
    }
}

impl From<f32> for Iv {
    fn from(x: f32) -> Iv {
        Iv { lo: x, hi: x }
    }
}
impl Add for Iv {
    type Output = Iv;
    fn add(self, o: Iv) -> Iv {
        Iv { lo: (self.lo + o.lo).next_down(), hi: (self.hi + o.hi).next_up() }
    }
}
impl Sub for Iv {
    type Output = Iv;
    fn sub(self, o: Iv) -> Iv {
        Iv { lo: (self.lo - o.hi).next_down(), hi: (self.hi - o.lo).next_up() }
    }
}
impl Mul for Iv {
    type Output = Iv;
    fn mul(self, o: Iv) -> Iv {
        Iv::outward([self.lo * o.lo, self.lo * o.hi, self.hi * o.lo, self.hi * o.hi])
    }
}
impl Div for Iv {
    type Output = Iv;
    fn div(self, o: Iv) -> Iv {
        // Only a divisor of one strict sign (false on NaN).
        if !(o.lo > 0.0 || o.hi < 0.0) {
            return Iv::NAN;
        }
        Iv::outward([self.lo / o.lo, self.lo / o.hi, self.hi / o.lo, self.hi / o.hi])
    }
}

/// [`Iv`]'s operations as the [`Ops`] the shared formulas are written in.
struct IvOps;

impl Ops for IvOps {
    type T = Iv;
    fn lit(&self, v: f32) -> Iv {
        Iv::from(v)
    }
    fn add(&self, a: &Iv, b: &Iv) -> Iv {
        *a + *b
    }
    fn sub(&self, a: &Iv, b: &Iv) -> Iv {
        *a - *b
    }
    fn mul(&self, a: &Iv, b: &Iv) -> Iv {
        *a * *b
    }
    fn div(&self, a: &Iv, b: &Iv) -> Iv {
        *a / *b
    }
}

/// The patch of `mam2012-safe` over `[xa, xb] x [0, 1]`: its corner values
/// `at[side][k]` (side 0 at xa, 1 at xb; f32 numbers that define the exact patch) and an
/// enclosure of its exact x-slope at t = k.
#[derive(Clone, Copy, Debug)]
struct SafePatch {
    dom: [f32; 2],
    at: [[f32; 2]; 2],
    slope: [Iv; 2],
}

impl SafePatch {
    fn new(dom: [f32; 2], at: [[f32; 2]; 2]) -> Option<SafePatch> {
        if !at.iter().flatten().all(|v| v.is_finite()) {
            return None;
        }
        let width = Iv::from(dom[1]) - Iv::from(dom[0]);
        let slope = |k: usize| {
            if dom[1] > dom[0] {
                (Iv::from(at[1][k]) - Iv::from(at[0][k])) / width
            } else {
                Iv::from(0.0) // one column: the corner values are the patch
            }
        };
        let slope = [slope(0), slope(1)];
        (slope[0].usable() && slope[1].usable()).then_some(SafePatch { dom, at, slope })
    }
    /// An enclosure of the patch's values at t = k over the columns `[x0, x1]` (within
    /// the domain): the same exact patch written from either end, intersected.
    fn range(&self, x0: f32, x1: f32, k: usize) -> Iv {
        let x = Iv { lo: x0, hi: x1 };
        let from = |side: usize| Iv::from(self.at[side][k]) + (x - Iv::from(self.dom[side])) * self.slope[k];
        from(0).meet(from(1))
    }
}

/// The lower and upper patch of one lens axis for `mam2012-safe`, and the enclosed
/// screen extent `dom` they are valid over.
#[derive(Clone, Copy, Debug)]
struct SafeAxis {
    dom: [f32; 2],
    lo: Option<SafePatch>,
    hi: Option<SafePatch>,
}

/// `mam2012` in f32 interval arithmetic (see the module's `mam2012-safe` section).
pub struct Mam2012Safe;

static INFO_SAFE: MethodInfo = MethodInfo {
    id: "mam2012-safe",
    source: "Munkberg & Akenine-Möller 2012, Hyperplane Culling for Stochastic Rasterization, §2.1 (Eq. 1, Fig. 3, Fig. 5) and Appendix A; every quantity computed in f32 interval arithmetic rounded outward (error analysis in this file): conservative for every finite input",
    ..INFO
};

/// `mam2012-safe`: the bilinear test with outward-rounded patches, lines and extents.
pub static METHOD_SAFE: &dyn Method = &Mam2012Safe;

impl Method for Mam2012Safe {
    fn info(&self) -> &'static MethodInfo {
        &INFO_SAFE
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(PrepSafe(setup_safe(tri)))
    }
}

struct PrepSafe(Result<[SafeAxis; 2], &'static str>);

/// The patches of one axis in interval arithmetic (`axis` of `mam2012`, enclosed): `kf`
/// is 1 for u / x and k for v / y.
fn axis_safe(tri: &Triangle, ax: usize) -> Option<SafeAxis> {
    let kf = Iv::from(if ax == 0 { 1.0 } else { tri.k });
    let ends = |j: usize| [(tri.q[j], tri.c0[j]), (tri.r[j], tri.c1[j])];
    // The screen extent, enclosed: every corner projection's interval.
    let (mut xa, mut xb) = (f32::INFINITY, f32::NEG_INFINITY);
    for j in 0..3 {
        for (p, c) in ends(j) {
            for s in [-1.0f32, 1.0] {
                let x = projected(&IvOps, &Iv::from(p[ax]), s, &kf, &Iv::from(c), &Iv::from(p[3]));
                if !x.usable() {
                    return None;
                }
                xa = xa.min(x.lo);
                xb = xb.max(x.hi);
            }
        }
    }
    let dom = [xa, xb];
    // Every denominator k c_j(t) of one strict sign, the same for all j (the u axis
    // has this from `why_disabled`; k c can underflow to 0 or k be 0 for v).
    let den = [0, 1, 2].map(|j| ends(j).map(|(_, c)| kf * Iv::from(c)));
    let all = |f: fn(&Iv) -> bool| den.iter().flatten().all(f);
    let (lo, hi) = if all(|d| d.lo > 0.0) || all(|d| d.hi < 0.0) {
        let mut lo = [[f32::INFINITY; 2]; 2];
        let mut hi = [[f32::NEG_INFINITY; 2]; 2];
        for (side, x) in dom.into_iter().enumerate() {
            for (j, den_j) in den.iter().enumerate() {
                let [(p0, _), (p1, _)] = ends(j);
                let (w, pos) = ([Iv::from(p0[3]), Iv::from(p1[3])], [Iv::from(p0[ax]), Iv::from(p1[ax])]);
                let n = numerators(&IvOps, &Iv::from(x), &w, &pos);
                let (chord, tan) = fig5_lines(&IvOps, &n, den_j, false);
                for k in 0..2 {
                    // A NaN end makes the corner NaN: no patch on that side.
                    let (a, b) = (chord[k], tan[k]);
                    lo[side][k] = nan_min(lo[side][k], nan_min(a.lo, b.lo));
                    hi[side][k] = nan_max(hi[side][k], nan_max(a.hi, b.hi));
                }
            }
        }
        (SafePatch::new(dom, lo), SafePatch::new(dom, hi))
    } else {
        (None, None)
    };
    Some(SafeAxis { dom, lo, hi })
}

fn setup_safe(tri: &Triangle) -> Result<[SafeAxis; 2], &'static str> {
    let finite =
        tri.q.iter().chain(tri.r.iter()).flatten().chain(tri.c0.iter()).chain(tri.c1.iter()).all(|v| v.is_finite());
    if !(finite && tri.k.is_finite()) {
        return Err("a vertex, CoC or the aspect is NaN or infinite");
    }
    if let Some(why) = why_disabled_f32(tri) {
        return Err(why);
    }
    match (axis_safe(tri, 0), axis_safe(tri, 1)) {
        (Some(u), Some(v)) => Ok([u, v]),
        _ => Err("the screen extent of the triangle is not finite in f32"),
    }
}

/// How far `mam2012-safe` moves each per-sample line outward beyond its enclosure, in
/// lens units (2^-20, eight f32 ulps at 1): see "Lines tight to the covered set".
const LINE_PAD: f32 = 1.0 / (1u32 << 20) as f32;

/// A per-sample line of `mam2012-safe`: as [`Line`], with the slope `a` rounded so the
/// stored line lies outside the exact one on [0, 1], and evaluated with directed steps
/// so that `eval` is never below the exact value of `u - (a t + b)` (lower) or
/// `(a t + b) - u` (upper) rounded to f32.
#[derive(Debug, Clone, Copy)]
pub(super) struct SafeLine(pub(super) Line);

/// The largest f32 not above `x` (f64), as an f64.
fn f32_down(x: f64) -> f64 {
    let r = x as f32;
    (if r as f64 > x { r.next_down() } else { r }) as f64
}

impl SampleConstraint for SafeLine {
    fn name(&self) -> String {
        self.0.name()
    }
    fn eval(&self, s: &Sample) -> f32 {
        let Line { is_v, upper, a, b } = self.0;
        let w = if is_v { s.v } else { s.u };
        if upper {
            // fl(l) - w with l >= a t + b.
            ((a * s.t).next_up() + b).next_up() - w
        } else {
            w - ((a * s.t).next_down() + b).next_down()
        }
    }
    /// `eval` over the columns (the same operations and steps per sample; the steps
    /// written as selects, the same bits as `next_up` / `next_down`, so the samples run
    /// side by side).
    fn eval_row(&self, c: &SampleCols, out: &mut [f32]) {
        use super::step::{dn, up};
        let Line { is_v, upper, a, b } = self.0;
        let w = if is_v { c.v } else { c.u };
        if upper {
            for ((o, &w), &t) in out.iter_mut().zip(w).zip(c.t) {
                *o = up(up(a * t) + b) - w;
            }
        } else {
            for ((o, &w), &t) in out.iter_mut().zip(w).zip(c.t) {
                *o = w - dn(dn(a * t) + b);
            }
        }
    }
    fn eval_box(&self, bx: &SampleBox) -> Interval {
        // Below: the exact g over the box rounded down to f32 (eval rounds the exact
        // difference of w and a line at least as far out, and rounding to nearest is
        // monotone). Above: the original's widening for three roundings and two steps.
        let g = self.0.eval_box(bx);
        let exact = {
            let Line { is_v, upper, a, b } = self.0;
            let w = if is_v { bx.v } else { bx.u };
            let l = Interval::point(a as f64) * bx.t + Interval::point(b as f64);
            if upper {
                l - w
            } else {
                w - l
            }
        };
        Interval::new(f32_down(exact.lo), g.hi)
    }
    /// The exact `g` (`w - (a t + b)` or `(a t + b) - w`) with no error: `eval` rounds
    /// to nearest the difference of `w` and a line stepped outward (`a t` and the sum
    /// each rounded and stepped one f32 away), a value `>= g` (`+inf` when the line
    /// overflows), and rounding to nearest keeps the sign of a non-negative value. So
    /// where `g >= 0`, `eval >= 0`: the sign is exact, and the cut needs no error term.
    fn lower_cut(&self, _bx: &SampleBox) -> Option<Cut> {
        let Line { is_v, upper, a, b } = self.0;
        let sign = if upper { 1.0 } else { -1.0 };
        let mut cut = Cut::zero();
        cut.coef[0] = sign * b as f64;
        cut.coef[Cut::T] = sign * a as f64;
        cut.coef[if is_v { Cut::V } else { Cut::U }] = -sign;
        Some(cut)
    }
}

/// One axis's part of a `mam2012-safe` tile answer, from that axis's tile sides only.
#[derive(Clone, Copy, Debug)]
enum SafeAxisAnswer {
    /// A NaN or reversed pair of sides: the tile answers the whole domain.
    Full,
    /// No covered sample (beside the enclosed extent, or an empty lens range).
    Empty,
    /// The lens range and the lines emitted (lower, upper).
    Kept([f32; 2], [Option<SafeLine>; 2]),
}

impl SafeAxis {
    /// The answer of this axis's patches (`is_v`: the v axis) over the tile sides
    /// `[t0, t1]` on that axis (x for u, y for v).
    fn answer(&self, is_v: bool, t0: f32, t1: f32) -> SafeAxisAnswer {
        // A NaN or reversed tile: answer the whole domain.
        if t0.partial_cmp(&t1).is_none_or(|o| o == std::cmp::Ordering::Greater) {
            return SafeAxisAnswer::Full;
        }
        // Covered columns lie in the enclosed extent: clamp the tile to it; a tile
        // beside it holds no covered sample.
        let (x0, x1) = (t0.max(self.dom[0]), t1.min(self.dom[1]));
        if x0 > x1 {
            return SafeAxisAnswer::Empty;
        }
        let ends = |p: Option<SafePatch>, upper: bool| {
            let p = p?;
            let e = |k: usize| {
                let r = p.range(x0, x1, k);
                if upper {
                    r.hi
                } else {
                    r.lo
                }
            };
            let l = [e(0), e(1)];
            (l[0].is_finite() && l[1].is_finite()).then_some(l)
        };
        let (lo, hi) = (ends(self.lo, false), ends(self.hi, true));
        let r_lo = lo.map_or(-1.0, |l| l[0].min(l[1]).max(-1.0));
        let r_hi = hi.map_or(1.0, |l| l[0].max(l[1]).min(1.0));
        if r_lo > r_hi {
            return SafeAxisAnswer::Empty;
        }
        let line = |upper: bool, l: Option<[f32; 2]>| {
            let l = l?;
            // The slope rounded outward (the line then lies outside the exact one on t in
            // [0, 1]) and the intercept moved out by LINE_PAD (a rounded difference with a
            // representable l[0] never crosses l[0]).
            let (a, b) = if upper {
                ((l[1] - l[0]).next_up(), l[0] + LINE_PAD)
            } else {
                ((l[1] - l[0]).next_down(), l[0] - LINE_PAD)
            };
            (a.is_finite() && b.is_finite()).then_some(SafeLine(Line { is_v, upper, a, b }))
        };
        SafeAxisAnswer::Kept([r_lo, r_hi], [line(false, lo), line(true, hi)])
    }
}

/// A tile's answer from its u part and its v part (the u part first: a u part that is
/// Full or Empty decides before the v part is looked at).
fn join_safe(u: &SafeAxisAnswer, v: &SafeAxisAnswer) -> TileResult {
    let mut out = TileBounds::full();
    for (is_v, part) in [(false, u), (true, v)] {
        let (range, lines) = match part {
            SafeAxisAnswer::Full => return TileResult::Bounds(TileBounds::full()),
            SafeAxisAnswer::Empty => return TileResult::Empty,
            SafeAxisAnswer::Kept(range, lines) => (range, lines),
        };
        if is_v {
            out.v = *range;
        } else {
            out.u = *range;
        }
        for l in lines.iter().flatten() {
            out.constraints.push(Box::new(*l));
        }
    }
    TileResult::Bounds(out)
}

impl Prepared for PrepSafe {
    fn tile(&self, tile: &Tile) -> TileResult {
        let axes = match &self.0 {
            Ok(s) => s,
            Err(_) => return TileResult::Bounds(TileBounds::full()),
        };
        join_safe(&axes[0].answer(false, tile.x0, tile.x1), &axes[1].answer(true, tile.y0, tile.y1))
    }
    fn disabled(&self) -> Option<&'static str> {
        self.0.as_ref().err().copied()
    }
    /// The u part of the answer reads only the tile's x sides, the v part only its y
    /// sides ([`SafeAxis::answer`]): each is computed once per column and once per row,
    /// and a tile joins its column's and its row's as [`tile`](Self::tile) does. A
    /// disabled test answers full bounds tile by tile.
    fn grid<'a>(&'a self, grid: Grid<'a>) -> Box<dyn TileGrid + 'a> {
        let Ok([u, v]) = &self.0 else {
            return Box::new(PerTile { prep: self, grid });
        };
        let cols = (0..grid.columns()).map(|i| u.answer(false, grid.xs[i], grid.xs[i + 1])).collect();
        let rows = (0..grid.rows()).map(|j| v.answer(true, grid.ys[j], grid.ys[j + 1])).collect();
        Box::new(SafeGrid { cols, rows })
    }
}

/// [`PrepSafe::grid`]: per column the u part of the answer, per row the v part; per tile
/// only their join ([`join_safe`]: the check of both and the tile's own constraints).
struct SafeGrid {
    cols: Vec<SafeAxisAnswer>,
    rows: Vec<SafeAxisAnswer>,
}

impl TileGrid for SafeGrid {
    fn tile(&self, i: usize, j: usize) -> TileResult {
        join_safe(&self.cols[i], &self.rows[j])
    }
}
