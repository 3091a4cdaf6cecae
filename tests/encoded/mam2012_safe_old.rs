//! The code `mam2012-safe` had before it was written over `F32Arith` (f32 intervals as a
//! type with operator overloads), verbatim but for its method glue and the constraint's
//! type: the reference `tests/encoded.rs` compares it with, answer for answer.

use super::mam2012_old::{fig5_lines, numerators, projected, why_disabled, Line};
use cullproof::bounds::{SampleBox, SampleConstraint, TileBounds, TileResult};
use cullproof::{Interval, Sample, Tile, Triangle};
use std::ops::{Add, Div, Mul, Sub};

/// A closed f32 interval `[lo, hi]` holding an exact real value: every operation rounds
/// to nearest and steps each end one f32 outward (see the module's error analysis). A
/// NaN end, or a division by an interval holding 0, gives NaN ends: not [`usable`](Iv::usable).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Iv {
    lo: f32,
    hi: f32,
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
    fn usable(self) -> bool {
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
                let x = projected(Iv::from(p[ax]), s, kf, Iv::from(c), Iv::from(p[3]));
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
                let n = numerators(Iv::from(x), w, pos);
                let (chord, tan) = fig5_lines(n, *den_j, false);
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
    if let Some(why) = why_disabled(tri) {
        return Err(why);
    }
    match (axis_safe(tri, 0), axis_safe(tri, 1)) {
        (Some(u), Some(v)) => Ok([u, v]),
        _ => Err("the screen extent of the triangle is not finite in f32"),
    }
}

const LINE_PAD: f32 = 1.0 / (1u32 << 20) as f32;

/// A line as the old code stored it (its Debug form is the constraint's).
#[derive(Debug, Clone, Copy)]
#[allow(dead_code)] // read through its Debug form
struct SafeLine(Line);

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
            out.constraints.push(Box::new(SafeLineC(*l)));
        }
    }
    TileResult::Bounds(out)
}

/// The line as a constraint, printed as the old one (`SafeLine(Line { .. })`); only its
/// Debug form is compared.
struct SafeLineC(SafeLine);

impl std::fmt::Debug for SafeLineC {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl SampleConstraint for SafeLineC {
    fn name(&self) -> String {
        String::new()
    }
    fn eval(&self, _: &Sample) -> f32 {
        f32::NAN
    }
    fn eval_box(&self, _: &SampleBox) -> Interval {
        Interval::new(f64::NEG_INFINITY, f64::INFINITY)
    }
}

/// The old tile answer.
pub fn answer(tri: &Triangle, tile: &Tile) -> TileResult {
    match setup_safe(tri) {
        Err(_) => TileResult::Bounds(TileBounds::full()),
        Ok(axes) => join_safe(&axes[0].answer(false, tile.x0, tile.x1), &axes[1].answer(true, tile.y0, tile.y1)),
    }
}
