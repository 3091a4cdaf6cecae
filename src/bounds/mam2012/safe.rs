//! `mam2012-safe`: the patches and lines of `mam2012` in f32 interval arithmetic
//! rounded outward, the per-sample lines stepped outward, and the per-axis grid.
//! The derivation and the error analysis are in the parent's module doc (section
//! "`mam2012-safe`").
//!
//! Written once over [`F32Arith`] and a rounding discipline [`Round`] (the `-safe`
//! arithmetic [`Outward`], or a planted slip that drops one side's steps): the gate runs
//! it in f32 ([`Plain`]), and the enclosure check of `cullproof proofs` traces the same
//! code for every input. Where the derivation takes an end as the number that defines
//! the next step (the patch domain, its corner values, the tile's columns, the lines'
//! ends), the code says so with [`F32Arith::pin`], [`F32Arith::pin_range`] and
//! [`F32Arith::pin_same`], each naming the lemma that carries the step; every other
//! instance of [`F32Arith`] ignores them.

use super::*;
use crate::bounds::arith::End;
use crate::bounds::round::{Outward, Round};
use std::marker::PhantomData;

/// A closed interval `[lo, hi]` of values of some [`F32Arith`], holding an exact real
/// value.
pub(super) type Iv<F> = [F; 2];

/// f32 interval arithmetic over any [`F32Arith`]: every operation rounds to nearest and
/// steps each end one f32 outward (`R::dn` / `R::up`; see the module's error analysis).
/// Products and quotients take the least and the greatest of the four end combinations;
/// a NaN among them, or a divisor interval not of one strict sign, gives NaN ends.
pub(super) struct IvOps<'a, A, R> {
    ar: &'a A,
    round: PhantomData<R>,
}

impl<'a, A: F32Arith, R: Round> IvOps<'a, A, R> {
    pub(super) fn new(ar: &'a A) -> Self {
        IvOps { ar, round: PhantomData }
    }
    fn nan(&self) -> A::F {
        self.ar.lit(f32::NAN)
    }
    /// The point interval `[x, x]`.
    pub(super) fn point(&self, x: &A::F) -> Iv<A::F> {
        [x.clone(), x.clone()]
    }
    /// The four end products (or quotients), rounded, then stepped outward: NaN when
    /// one of them is NaN.
    #[inline(always)]
    fn outward(&self, v: [A::F; 4]) -> Iv<A::F> {
        let ar = self.ar;
        let lo = ar.min_nan(&ar.min_nan(&ar.min_nan(&v[0], &v[1]), &v[2]), &v[3]);
        let hi = ar.max_nan(&ar.max_nan(&ar.max_nan(&v[0], &v[1]), &v[2]), &v[3]);
        [R::dn(ar, &lo), R::up(ar, &hi)]
    }
    /// Finite ends in order (false on NaN).
    pub(super) fn usable(&self, x: &Iv<A::F>) -> A::B {
        let ar = self.ar;
        ar.all(&[ar.is_finite(&x[0]), ar.is_finite(&x[1]), ar.le(&x[0], &x[1])])
    }
}

impl<A: F32Arith, R: Round> Ops for IvOps<'_, A, R> {
    type T = Iv<A::F>;
    fn lit(&self, v: f32) -> Iv<A::F> {
        self.point(&self.ar.lit(v))
    }
    #[inline]
    fn add(&self, a: &Iv<A::F>, b: &Iv<A::F>) -> Iv<A::F> {
        let ar = self.ar;
        [R::dn(ar, &ar.add(&a[0], &b[0])), R::up(ar, &ar.add(&a[1], &b[1]))]
    }
    #[inline]
    fn sub(&self, a: &Iv<A::F>, b: &Iv<A::F>) -> Iv<A::F> {
        let ar = self.ar;
        [R::dn(ar, &ar.sub(&a[0], &b[1])), R::up(ar, &ar.sub(&a[1], &b[0]))]
    }
    #[inline]
    fn mul(&self, a: &Iv<A::F>, b: &Iv<A::F>) -> Iv<A::F> {
        let ar = self.ar;
        self.outward([ar.mul(&a[0], &b[0]), ar.mul(&a[0], &b[1]), ar.mul(&a[1], &b[0]), ar.mul(&a[1], &b[1])])
    }
    #[inline]
    fn div(&self, a: &Iv<A::F>, b: &Iv<A::F>) -> Iv<A::F> {
        let ar = self.ar;
        let q = self.outward([ar.div(&a[0], &b[0]), ar.div(&a[0], &b[1]), ar.div(&a[1], &b[0]), ar.div(&a[1], &b[1])]);
        // Only a divisor of one strict sign (false on NaN); each sign its own branch.
        let zero = ar.lit(0.0);
        let (pos, neg) = (ar.lt(&zero, &b[0]), ar.lt(&b[1], &zero));
        q.map(|e| ar.select(&pos, &e, &ar.select(&neg, &e, &self.nan())))
    }
}

/// The lemma that lets the patch domain's ends stand for the exact screen extent.
pub const DOMAIN_LEMMA: &str = "mam2012-safe domain: a patch domain [xa, xb] with xa at or below the \
     exact screen extent's least x and xb at or above its greatest holds every covered column";
/// The lemma that lets corner values below (above) the exact ones define the patch.
pub const CORNER_LEMMA: &str = "mam2012-safe corners: the bilinear patch through corner values at or below \
     the exact ones is at or below the exact patch on the domain (at or above: above)";
/// The lemma that lets the clamped tile sides stand for the tile's coverable columns.
pub const COLUMNS_LEMMA: &str = "mam2012-safe columns: a covered column of the tile [t0, t1] lies in the \
     exact extent, so in [x0, x1] for x0 <= max(t0, least x), x1 >= min(t1, greatest x)";
/// The lemma that the patch read from either corner is one exact value.
pub const SAME_LEMMA: &str = "mam2012-safe patch from either corner: at0 + (x - d0) S = at1' + (x - d1) S \
     where S = (at1 - at0) / (d1 - d0), at1' = at1 for d1 > d0, and S = 0, at1' = at0 otherwise";
/// The lemma that lets the lines' ends define the lines.
pub const LINE_LEMMA: &str = "mam2012-safe lines: the line through lower ends of the patch's values at \
     t = 0 and t = 1 is at or below the line through the exact values for t in [0, 1] (upper ends: above)";

/// The patch of `mam2012-safe` over `[dom[0], dom[1]] x [0, 1]`: its corner values
/// `at[side][k]` (side 0 at `dom[0]`, 1 at `dom[1]`; f32 numbers that define the exact
/// patch), an enclosure of its exact x-slope at t = k, and whether it is used (`ok`:
/// the axis's denominators of one strict sign, finite corners and usable slopes).
#[derive(Clone, Debug)]
pub struct SafePatch<F, B> {
    ok: B,
    dom: [F; 2],
    at: [[F; 2]; 2],
    slope: [Iv<F>; 2],
}

/// The lower and upper patch of one lens axis for `mam2012-safe`, and the enclosed
/// screen extent `dom` they are valid over.
#[derive(Clone, Debug)]
pub struct SafeAxis<F, B> {
    dom: [F; 2],
    lo: SafePatch<F, B>,
    hi: SafePatch<F, B>,
}

/// Why `mam2012-safe` cannot run on a triangle, in the order the reasons are reported.
const WHY_SAFE: [&str; 5] = ["a vertex, CoC or the aspect is NaN or infinite", WHY[0], WHY[1], WHY[2], WHY[3]];

/// The disabling conditions of `mam2012-safe` (each reason of `WHY_SAFE`, in order) and
/// both axes, as values of some [`F32Arith`].
pub type SafeSetupOf<F, B> = ([B; 5], [SafeAxis<F, B>; 2]);

/// The setup over any [`F32Arith`].
pub fn setup_safe_of<R: Round, A: F32Arith>(ar: &A, tri: &TriOf<A::F>) -> SafeSetupOf<A::F, A::B> {
    let [n, c, m, b] = first_reasons(ar, tri);
    let (ext, axes) = axes_of::<R, A>(ar, tri);
    ([n, c, m, b, ext], axes)
}

/// The reasons of `WHY_SAFE` that need no interval arithmetic: a non-finite input, and
/// `mam2012`'s three.
fn first_reasons<A: F32Arith>(ar: &A, tri: &TriOf<A::F>) -> [A::B; 4] {
    let inputs = tri.q.iter().chain(tri.r.iter()).flatten().chain(tri.c0.iter()).chain(tri.c1.iter());
    let finite: Vec<A::B> = inputs.chain(std::iter::once(&tri.k)).map(|v| ar.is_finite(v)).collect();
    let [c, m, b] = why_disabled(ar, tri);
    [ar.not(&ar.all(&finite)), c, m, b]
}

/// The last reason of `WHY_SAFE` (an unusable screen extent) and both axes.
type AxesOf<F, B> = (B, [SafeAxis<F, B>; 2]);

/// Both axes, and the last reason of `WHY_SAFE` (an unusable screen extent).
fn axes_of<R: Round, A: F32Arith>(ar: &A, tri: &TriOf<A::F>) -> AxesOf<A::F, A::B> {
    let (okx, x) = axis_safe::<R, A>(ar, tri, 0);
    let (oky, y) = axis_safe::<R, A>(ar, tri, 1);
    (ar.not(&ar.and(&okx, &oky)), [x, y])
}

/// The patches of one axis in interval arithmetic (`axis` of `mam2012`, enclosed), and
/// whether its screen extent is usable.
fn axis_safe<R: Round, A: F32Arith>(ar: &A, tri: &TriOf<A::F>, ax: usize) -> (A::B, SafeAxis<A::F, A::B>) {
    let o = IvOps::<A, R>::new(ar);
    let kf = if ax == 0 { o.lit(1.0) } else { o.point(&tri.k) };
    let ends = |j: usize| [(&tri.q[j], &tri.c0[j]), (&tri.r[j], &tri.c1[j])];
    // The screen extent, enclosed: every corner projection's interval.
    let (mut xa, mut xb) = (ar.lit(f32::INFINITY), ar.lit(f32::NEG_INFINITY));
    let mut usable = vec![];
    for j in 0..3 {
        for (p, c) in ends(j) {
            for s in [-1.0f32, 1.0] {
                let x = projected(&o, &o.point(&p[ax]), s, &kf, &o.point(c), &o.point(&p[3]));
                usable.push(o.usable(&x));
                xa = ar.min(&xa, &x[0]);
                xb = ar.max(&xb, &x[1]);
            }
        }
    }
    let dom = [xa, xb];
    // The patch is defined over the domain's f32 ends.
    let pd = [ar.pin(&dom[0], End::Lo, DOMAIN_LEMMA), ar.pin(&dom[1], End::Hi, DOMAIN_LEMMA)];
    // Every denominator k c_j(t) of one strict sign, the same for all j (the u axis
    // has this from `why_disabled`; k c can underflow to 0 or k be 0 for v).
    let den = [0, 1, 2].map(|j| ends(j).map(|(_, c)| o.mul(&kf, &o.point(c))));
    let zero = ar.lit(0.0);
    let all_pos: Vec<A::B> = den.iter().flatten().map(|d| ar.lt(&zero, &d[0])).collect();
    let all_neg: Vec<A::B> = den.iter().flatten().map(|d| ar.lt(&d[1], &zero)).collect();
    let den_ok = ar.or(&ar.all(&all_pos), &ar.all(&all_neg));
    let mut lo = [[(); 2]; 2].map(|r| r.map(|_| ar.lit(f32::INFINITY)));
    let mut hi = [[(); 2]; 2].map(|r| r.map(|_| ar.lit(f32::NEG_INFINITY)));
    for (side, x) in pd.iter().enumerate() {
        for (j, den_j) in den.iter().enumerate() {
            let [(p0, _), (p1, _)] = ends(j);
            let (w, pos) = ([o.point(&p0[3]), o.point(&p1[3])], [o.point(&p0[ax]), o.point(&p1[ax])]);
            let n = numerators(&o, &o.point(x), &w, &pos);
            let (chord, tan) = fig5_lines(&o, &n, den_j, false);
            for k in 0..2 {
                // A NaN end makes the corner NaN: no patch on that side.
                let (a, b) = (&chord[k], &tan[k]);
                lo[side][k] = ar.min_nan(&lo[side][k], &ar.min_nan(&a[0], &b[0]));
                hi[side][k] = ar.max_nan(&hi[side][k], &ar.max_nan(&a[1], &b[1]));
            }
        }
    }
    let pin = |c: [[A::F; 2]; 2], end: End| c.map(|r| r.map(|v| ar.pin(&v, end, CORNER_LEMMA)));
    let patch = |at: [[A::F; 2]; 2]| {
        let finite = at.iter().flatten().map(|v| ar.is_finite(v)).collect::<Vec<_>>();
        let width = o.sub(&o.point(&pd[1]), &o.point(&pd[0]));
        // One column (xa == xb): the corner values are the patch, its slope 0.
        let wide = ar.gt(&pd[1], &pd[0]);
        let slope = [0, 1].map(|k| {
            let s = o.div(&o.sub(&o.point(&at[1][k]), &o.point(&at[0][k])), &width);
            s.map(|e| ar.select(&wide, &e, &zero))
        });
        let ok = ar.all(&[den_ok.clone(), ar.all(&finite), o.usable(&slope[0]), o.usable(&slope[1])]);
        SafePatch { ok, dom: pd.clone(), at, slope }
    };
    let ext_ok = ar.all(&usable);
    (ext_ok, SafeAxis { lo: patch(pin(lo, End::Lo)), hi: patch(pin(hi, End::Hi)), dom })
}

impl<F: Clone, B: Clone> SafePatch<F, B> {
    /// An enclosure of the patch's values at t = k over the columns `x` (an interval
    /// within the domain): the same exact patch written from either corner,
    /// intersected.
    fn range<A: F32Arith<F = F, B = B>, R: Round>(&self, ar: &A, x: &Iv<F>, k: usize) -> Iv<F> {
        let o = IvOps::<A, R>::new(ar);
        let at1 = ar.select(&ar.gt(&self.dom[1], &self.dom[0]), &self.at[1][k], &self.at[0][k]);
        let from = |at: &F, d: &F| o.add(&o.point(at), &o.mul(&o.sub(x, &o.point(d)), &self.slope[k]));
        let f0 = from(&self.at[0][k], &self.dom[0]);
        let f1 = ar.pin_same(&from(&at1, &self.dom[1]), &f0[0], SAME_LEMMA);
        // Both enclosures hold the value, so their intersection does; an unusable one
        // is ignored.
        let (u0, u1) = (o.usable(&f0), o.usable(&f1));
        let meet = |i: usize, both: F| {
            ar.select(&u0, &ar.select(&u1, &both, &f0[i]), &ar.select(&u1, &f1[i], &ar.lit(f32::NAN)))
        };
        [meet(0, ar.max(&f0[0], &f1[0])), meet(1, ar.min(&f0[1], &f1[1]))]
    }
}

/// How far `mam2012-safe` moves each per-sample line outward beyond its enclosure, in
/// lens units (2^-20, eight f32 ulps at 1): see "Lines tight to the covered set".
const LINE_PAD: f32 = 1.0 / (1u32 << 20) as f32;

/// One axis's part of a `mam2012-safe` tile answer over any [`F32Arith`].
#[derive(Clone, Debug)]
pub struct SafeAxisAnswerOf<F, B> {
    /// A NaN or reversed pair of tile sides: the whole domain.
    pub full: B,
    /// No covered sample (beside the enclosed extent, or an empty lens range); only
    /// where not `full`.
    pub empty: B,
    /// The lens range.
    pub range: [F; 2],
    /// The lower and upper line: whether it is emitted, its slope `a` and intercept `b`.
    pub lines: [(B, F, F); 2],
}

/// The answer of an axis's patches over the tile sides `[t0, t1]` on that axis (x for
/// u, y for v).
pub fn answer_of<R: Round, A: F32Arith>(
    ar: &A,
    ax: &SafeAxis<A::F, A::B>,
    t0: &A::F,
    t1: &A::F,
) -> SafeAxisAnswerOf<A::F, A::B> {
    let full = ar.not(&ar.le(t0, t1));
    // Covered columns lie in the enclosed extent: clamp the tile to it; a tile beside
    // it holds no covered sample.
    let (x0, x1) = (ar.max(t0, &ax.dom[0]), ar.min(t1, &ax.dom[1]));
    let beside = ar.lt(&x1, &x0);
    let x = ar.pin_range(&[x0, x1], false, COLUMNS_LEMMA);
    let ends = |p: &SafePatch<A::F, A::B>, upper: bool| {
        let e = [0, 1].map(|k| p.range::<A, R>(ar, &x, k)[upper as usize].clone());
        (ar.all(&[p.ok.clone(), ar.is_finite(&e[0]), ar.is_finite(&e[1])]), e)
    };
    let ((lo_ok, l), (hi_ok, h)) = (ends(&ax.lo, false), ends(&ax.hi, true));
    let (m1, p1) = (ar.lit(-1.0), ar.lit(1.0));
    let r_lo = ar.select(&lo_ok, &ar.max(&ar.min(&l[0], &l[1]), &m1), &m1);
    let r_hi = ar.select(&hi_ok, &ar.min(&ar.max(&h[0], &h[1]), &p1), &p1);
    let empty = ar.and(&ar.not(&full), &ar.or(&beside, &ar.lt(&r_hi, &r_lo)));
    // The slope rounded outward (the line then lies outside the one through the ends on
    // t in [0, 1]) and the intercept moved out by LINE_PAD (a rounded difference with a
    // representable end never crosses the end).
    let line = |ok: &A::B, e: &[A::F; 2], upper: bool| {
        let end = if upper { End::Hi } else { End::Lo };
        let [e0, e1] = e.each_ref().map(|v| ar.pin(v, end, LINE_LEMMA));
        let slope = ar.sub(&e1, &e0);
        let pad = ar.lit(LINE_PAD);
        let (a, b) = if upper {
            (R::up(ar, &slope), ar.moved_out(&ar.add(&e0, &pad), &e0, End::Hi))
        } else {
            (R::dn(ar, &slope), ar.moved_out(&ar.sub(&e0, &pad), &e0, End::Lo))
        };
        (ar.all(&[ok.clone(), ar.is_finite(&a), ar.is_finite(&b)]), a, b)
    };
    let lines = [line(&lo_ok, &l, false), line(&hi_ok, &h, true)];
    SafeAxisAnswerOf { full, empty, range: [r_lo, r_hi], lines }
}

/// A line's value at a sample: `w - (a t + b)` (lower) or `(a t + b) - w` (upper), with
/// `a t` and the sum each rounded and stepped outward (`R`), the difference rounded.
#[inline(always)]
pub fn line_eval<R: Round, A: F32Arith>(ar: &A, upper: bool, a: &A::F, b: &A::F, t: &A::F, w: &A::F) -> A::F {
    if upper {
        ar.sub(&R::up(ar, &ar.add(&R::up(ar, &ar.mul(a, t)), b)), w)
    } else {
        ar.sub(w, &R::dn(ar, &ar.add(&R::dn(ar, &ar.mul(a, t)), b)))
    }
}

/// `mam2012` in f32 interval arithmetic (see the module's `mam2012-safe` section), with
/// the rounding discipline `R` ([`Outward`]; a planted slip drops one side's steps).
pub struct Mam2012Safe<R: Round = Outward> {
    pub info: &'static MethodInfo,
    pub round: PhantomData<fn() -> R>,
}

static INFO_SAFE: MethodInfo = MethodInfo {
    id: "mam2012-safe",
    source: "Munkberg & Akenine-Möller 2012, Hyperplane Culling for Stochastic Rasterization, §2.1 (Eq. 1, Fig. 3, Fig. 5) and Appendix A; every quantity computed in f32 interval arithmetic rounded outward (error analysis in this file): conservative for every finite input",
    ..INFO
};

/// `mam2012-safe`: the bilinear test with outward-rounded patches, lines and extents.
pub static METHOD_SAFE: &dyn Method = &Mam2012Safe::<Outward> { info: &INFO_SAFE, round: PhantomData };

impl<R: Round> Method for Mam2012Safe<R> {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    /// [`setup_safe_of`] in f32, its parts in its order: a triangle disabled by one of the
    /// first four reasons costs no interval arithmetic.
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        let tri = TriOf::of(tri);
        let setup = match first_reasons(&Plain, &tri).iter().position(|&w| w) {
            Some(k) => Err(WHY_SAFE[k]),
            None => match axes_of::<R, Plain>(&Plain, &tri) {
                (true, _) => Err(WHY_SAFE[4]),
                (false, axes) => Ok(axes),
            },
        };
        Box::new(PrepSafe::<R> { setup, round: PhantomData })
    }
}

struct PrepSafe<R> {
    setup: Result<[SafeAxis<f32, bool>; 2], &'static str>,
    round: PhantomData<fn() -> R>,
}

/// Whether `R` is the `-safe` arithmetic itself (a planted slip's lines claim less).
fn is_outward<R: Round>() -> bool {
    std::any::TypeId::of::<R>() == std::any::TypeId::of::<Outward>()
}

/// A per-sample line of `mam2012-safe`: as [`Line`], with the slope `a` rounded so the
/// stored line lies outside the one through its ends on [0, 1], and evaluated with
/// directed steps ([`line_eval`]) so that `eval` is never below the exact value of
/// `u - (a t + b)` (lower) or `(a t + b) - u` (upper) rounded to f32.
pub(super) struct SafeLine<R = Outward>(pub(super) Line, pub(super) PhantomData<fn() -> R>);

impl<R> Clone for SafeLine<R> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<R> Copy for SafeLine<R> {}
impl<R> std::fmt::Debug for SafeLine<R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_tuple("SafeLine").field(&self.0).finish()
    }
}

impl<R: Round> SafeLine<R> {
    pub(super) fn new(line: Line) -> Self {
        SafeLine(line, PhantomData)
    }
}

/// The largest f32 not above `x` (f64), as an f64.
fn f32_down(x: f64) -> f64 {
    let r = x as f32;
    (if r as f64 > x { r.next_down() } else { r }) as f64
}

impl<R: Round> SampleConstraint for SafeLine<R> {
    fn name(&self) -> String {
        self.0.name()
    }
    fn eval(&self, s: &Sample) -> f32 {
        let Line { is_v, upper, a, b } = self.0;
        line_eval::<R, Plain>(&Plain, upper, &a, &b, &s.t, if is_v { &s.v } else { &s.u })
    }
    /// `eval` over the columns: for the `-safe` arithmetic the same operations and steps
    /// per sample, the steps written as selects (the same bits as `next_up` /
    /// `next_down`), so the samples run side by side; a planted slip sample by sample.
    fn eval_row(&self, c: &SampleCols, out: &mut [f32]) {
        use crate::bounds::step::{dn, up};
        if !is_outward::<R>() {
            for (i, o) in out.iter_mut().enumerate().take(c.len()) {
                *o = self.eval(&c.sample(i));
            }
            return;
        }
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
        // Above: the original's widening for three roundings and two steps. Below
        // (outward steps only): the exact g over the box rounded down to f32 (eval
        // rounds the exact difference of w and a line at least as far out, and
        // rounding to nearest is monotone); a planted slip keeps the widening.
        let g = self.0.eval_box(bx);
        if !is_outward::<R>() {
            return g;
        }
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
    /// (None for a planted slip.)
    fn lower_cut(&self, _bx: &SampleBox) -> Option<Cut> {
        if !is_outward::<R>() {
            return None;
        }
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
enum SafeAxisAnswer<R> {
    /// A NaN or reversed pair of sides: the tile answers the whole domain.
    Full,
    /// No covered sample (beside the enclosed extent, or an empty lens range).
    Empty,
    /// The lens range and the lines emitted (lower, upper).
    Kept([f32; 2], [Option<SafeLine<R>>; 2]),
}

/// The f32 answer of an axis ([`answer_of`] in [`Plain`]).
fn answer<R: Round>(ax: &SafeAxis<f32, bool>, is_v: bool, t0: f32, t1: f32) -> SafeAxisAnswer<R> {
    let a = answer_of::<R, Plain>(&Plain, ax, &t0, &t1);
    if a.full {
        return SafeAxisAnswer::Full;
    }
    if a.empty {
        return SafeAxisAnswer::Empty;
    }
    let line = |upper: bool, (ok, a, b): (bool, f32, f32)| ok.then_some(SafeLine::new(Line { is_v, upper, a, b }));
    let [lo, hi] = a.lines;
    SafeAxisAnswer::Kept(a.range, [line(false, lo), line(true, hi)])
}

/// The tile reject of `mam2012-safe`'s f32 answer, over any [`F32Arith`]: the test runs (no
/// reason of `why` holds), the u part is not Full, and it is Empty or the v part, not
/// Full, is Empty (what the enclosure check and the symbolic search assert).
pub fn rejects_of<A: F32Arith>(
    ar: &A,
    why: &[A::B; 5],
    u: &SafeAxisAnswerOf<A::F, A::B>,
    v: &SafeAxisAnswerOf<A::F, A::B>,
) -> A::B {
    let v_empty = ar.and(&ar.not(&v.full), &v.empty);
    ar.all(&[ar.not(&ar.any(why)), ar.not(&u.full), ar.or(&u.empty, &v_empty)])
}

/// A tile's answer from its u part and its v part (the u part first: a u part that is
/// Full or Empty decides before the v part is looked at).
fn join_safe<R: Round>(u: &SafeAxisAnswer<R>, v: &SafeAxisAnswer<R>) -> TileResult {
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

impl<R: Round> Prepared for PrepSafe<R> {
    fn tile(&self, tile: &Tile) -> TileResult {
        let axes = match &self.setup {
            Ok(s) => s,
            Err(_) => return TileResult::Bounds(TileBounds::full()),
        };
        join_safe(&answer::<R>(&axes[0], false, tile.x0, tile.x1), &answer::<R>(&axes[1], true, tile.y0, tile.y1))
    }
    fn disabled(&self) -> Option<&'static str> {
        self.setup.as_ref().err().copied()
    }
    /// The u part of the answer reads only the tile's x sides, the v part only its y
    /// sides ([`answer_of`]): each is computed once per column and once per row, and a
    /// tile joins its column's and its row's as [`tile`](Self::tile) does. A disabled
    /// test answers full bounds tile by tile.
    fn grid<'a>(&'a self, grid: Grid<'a>) -> Box<dyn TileGrid + 'a> {
        let Ok([u, v]) = &self.setup else {
            return Box::new(PerTile { prep: self, grid });
        };
        let cols = (0..grid.columns()).map(|i| answer::<R>(u, false, grid.xs[i], grid.xs[i + 1])).collect();
        let rows = (0..grid.rows()).map(|j| answer::<R>(v, true, grid.ys[j], grid.ys[j + 1])).collect();
        Box::new(SafeGrid { cols, rows })
    }
}

/// [`PrepSafe::grid`]: per column the u part of the answer, per row the v part; per tile
/// only their join ([`join_safe`]: the check of both and the tile's own constraints).
struct SafeGrid<R> {
    cols: Vec<SafeAxisAnswer<R>>,
    rows: Vec<SafeAxisAnswer<R>>,
}

impl<R: Round> TileGrid for SafeGrid<R> {
    fn tile(&self, i: usize, j: usize) -> TileResult {
        join_safe(&self.cols[i], &self.rows[j])
    }
}
