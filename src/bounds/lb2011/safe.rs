//! `lb2011-safe`: the corners, ranges and patches of `lb2011` in f32 interval
//! arithmetic rounded outward, with each patch's constant term padded. The derivation
//! and the error analysis are in the parent's module doc (section "`lb2011-safe`").
//!
//! Written once over [`F32Arith`] and a rounding discipline [`Round`] (the `-safe`
//! arithmetic `Outward`, or a planted slip that drops one side's steps): the gate runs
//! it in f32 ([`Plain`](crate::bounds::arith::Plain)), and the enclosure check of
//! `cullproof proofs` traces the same code for every input. The corner values are
//! pinned ([`F32Arith::pin`], [`CORNER_LEMMA`]): from there on the patch is the one
//! through them, an exact function, and every range is computed from it with outward
//! steps; the patch's per-sample value is an upper end of that exact patch by the Gappa
//! script `lb2011_safe.g` ([`EVAL_LEMMA`]).

use crate::bounds::arith::{End, F32Arith, TriOf};
use crate::bounds::la2011::{chord, join};
use crate::bounds::round::Round;

use super::AxisAnswer;

/// The pad of a patch's constant term per unit of its largest |corner value|: 2^-18
/// (`lb2011_safe.g`'s `PAD`).
pub const PAD: f32 = 1.0 / (1u32 << 18) as f32;
/// The pad's absolute part: 2^-140 (`lb2011_safe.g`'s `FLOOR`).
pub const FLOOR: f32 = 1.0 / (1u128 << 120) as f32 / (1u32 << 20) as f32;
/// No patch is emitted whose largest |corner value| is not below 2^120
/// (`lb2011_safe.g`'s `LIMIT`: no rounding of its evaluation overflows).
pub const LIMIT: f32 = (1u128 << 120) as f32;

/// The lemma that lets the corner values define the patch.
pub const CORNER_LEMMA: &str = "lb2011-safe corners: the patch P + Q l + t (R + S l) through corner values at \
     or above the exact ones (P = (g(-1,0) + g(1,0)) / 2, Q = (g(1,0) - g(-1,0)) / 2, R, S likewise at t = 1, \
     less P and Q) is at or above the bilinear interpolant of the exact ones for |l| <= 1, t in [0, 1]";

/// The lemma that the padded patch's f32 value is an upper end of the exact patch.
pub const EVAL_LEMMA: &str = "lb2011_safe.g: for corner values with max |g| < LIMIT, |l| <= 1 and t in [0, 1], \
     the padded patch's f32 value is finite and at or above the exact patch through the corner values";

/// One screen axis of `lb2011-safe` at the two shutter ends (index e = 0 at t = 0, 1
/// at t = 1), its numbers values of some [`F32Arith`].
#[derive(Clone, Debug)]
pub struct SafeAxis<F> {
    /// Vertex position on this axis (x or y), clip space.
    p: [[F; 3]; 2],
    w: [[F; 3]; 2],
    /// Lens shear per unit lens coordinate, enclosed: `[c, c]` for x; for y `fl(k c)`
    /// stepped outward (itself when k is 1).
    s: [[[F; 2]; 3]; 2],
}

/// The setup of one axis (0: x, 1: y).
pub fn axis_of<R: Round, A: F32Arith>(ar: &A, tri: &TriOf<A::F>, axis: usize) -> SafeAxis<A::F> {
    let p = [tri.q.each_ref().map(|v| v[axis].clone()), tri.r.each_ref().map(|v| v[axis].clone())];
    let w = [tri.q.each_ref().map(|v| v[3].clone()), tri.r.each_ref().map(|v| v[3].clone())];
    let shear = |c: &A::F| {
        if axis == 0 {
            return [c.clone(), c.clone()];
        }
        let s = ar.mul(&tri.k, c);
        let exact = ar.eq(&tri.k, &ar.lit(1.0));
        [ar.select(&exact, &s, &R::dn(ar, &s)), ar.select(&exact, &s, &R::up(ar, &s))]
    };
    SafeAxis { p, w, s: [tri.c0.each_ref().map(shear), tri.c1.each_ref().map(shear)] }
}

/// Corner values `[min, max]` of one axis, each indexed `[lens index][shutter end]`.
pub type CornersOf<F> = [[[F; 2]; 2]; 2];

/// The corner values over the tile's columns `lo`, `hi`: lower ends of the exact min
/// and upper ends of the exact max over the 3 vertices and both columns of
/// `p - X w + l s` at l = -1, 1 and each shutter end (f32 interval arithmetic: the
/// fused multiply-add `p - X w` stepped both ways, then each sum stepped outward), and
/// whether every one of those ends is finite.
pub fn corners_of<R: Round, A: F32Arith>(ar: &A, ax: &SafeAxis<A::F>, lo: &A::F, hi: &A::F) -> (A::B, CornersOf<A::F>) {
    let mut mn = [[(); 2]; 2].map(|r| r.map(|_| ar.lit(f32::INFINITY)));
    let mut mx = [[(); 2]; 2].map(|r| r.map(|_| ar.lit(f32::NEG_INFINITY)));
    let mut ok = ar.truth(true);
    for e in 0..2 {
        for i in 0..3 {
            let [s_lo, s_hi] = &ax.s[e][i];
            for x in [lo, hi] {
                let a = ar.fma(&ar.neg(x), &ax.w[e][i], &ax.p[e][i]);
                let (a_lo, a_hi) = (R::dn(ar, &a), R::up(ar, &a));
                let lows = [R::dn(ar, &ar.sub(&a_lo, s_hi)), R::dn(ar, &ar.add(&a_lo, s_lo))];
                let highs = [R::up(ar, &ar.sub(&a_hi, s_lo)), R::up(ar, &ar.add(&a_hi, s_hi))];
                for li in 0..2 {
                    ok = ar.and(&ok, &ar.and(&ar.is_finite(&lows[li]), &ar.is_finite(&highs[li])));
                    mn[li][e] = ar.min_nan(&mn[li][e], &lows[li]);
                    mx[li][e] = ar.max_nan(&mx[li][e], &highs[li]);
                }
            }
        }
    }
    (ok, [mn, mx])
}

/// The coefficients `[P, Q, R, S]` of the patch `P + Q l + t (R + S l)` through the
/// values `g[l][e]` at (l, t) = (-1, 0), (1, 0), (-1, 1), (1, 1), in f32:
/// `P = fl(fl(g00 + g10) / 2)`, `Q = fl(fl(g10 - g00) / 2)`,
/// `R = fl(fl(fl(g01 + g11) / 2) - P)`, `S = fl(fl(fl(g11 - g01) / 2) - Q)`.
pub fn coefficients<A: F32Arith>(ar: &A, g: &[[A::F; 2]; 2]) -> [A::F; 4] {
    let half = ar.lit(0.5);
    let (g00, g10, g01, g11) = (&g[0][0], &g[1][0], &g[0][1], &g[1][1]);
    let p = ar.mul(&ar.add(g00, g10), &half);
    let q = ar.mul(&ar.sub(g10, g00), &half);
    let r = ar.sub(&ar.mul(&ar.add(g01, g11), &half), &p);
    let s = ar.sub(&ar.mul(&ar.sub(g11, g01), &half), &q);
    [p, q, r, s]
}

/// The ranges implied by one patch through the (pinned) values `g[l][e]`: whether some
/// (l, t) of the square has g >= 0, the t where some l has (the hull of the chords along
/// t at l = -1 and l = 1, `la2011`'s chord with its crossing rounded outward), and the l
/// where some t has (the same along l at t = 0 and t = 1, in sigma = (l + 1) / 2; then
/// `l = 2 sigma - 1`, one fused multiply-add, stepped outward and clamped to [-1, 1]).
fn ranges_of<R: Round, A: F32Arith>(ar: &A, g: &[[A::F; 2]; 2]) -> (A::B, [A::F; 2], [A::F; 2]) {
    // g >= 0  <=>  -g <= 0: the chord keeps where its line is <= 0.
    let ch = |a: &A::F, b: &A::F| chord::<R, A>(ar, &ar.neg(a), &ar.neg(b));
    let t = join(ar, &ch(&g[0][0], &g[0][1]), &ch(&g[1][0], &g[1][1]));
    let sigma = join(ar, &ch(&g[0][0], &g[1][0]), &ch(&g[0][1], &g[1][1]));
    let (two, m1, p1) = (ar.lit(2.0), ar.lit(-1.0), ar.lit(1.0));
    let l = [
        ar.max(&R::dn(ar, &ar.fma(&two, &sigma.1[0], &m1)), &m1),
        ar.min(&R::up(ar, &ar.fma(&two, &sigma.1[1], &m1)), &p1),
    ];
    (t.0, t.1, l)
}

/// One patch of `lb2011-safe`: whether it is emitted, the (pinned) corner values it is
/// built on, and its coefficients with the constant term padded.
#[derive(Clone, Debug)]
pub struct SafePatch<F, B> {
    /// The axis's corners are finite, some corner value is < 0 (else it cannot cull) and
    /// the largest |corner value| is below [`LIMIT`].
    pub emit: B,
    /// The corner values `g[l][e]`.
    pub g: [[F; 2]; 2],
    /// `[P', Q, R, S]`: [`coefficients`] with `P' = next_up(fl(P + fl(fl(mg PAD) +
    /// FLOOR)))`, `mg` the largest |corner value|.
    pub coef: [F; 4],
}

/// The largest |corner value| of a patch, NaN if one is NaN (from 0: a fold of
/// `max_nan`).
pub fn largest<A: F32Arith>(ar: &A, g: &[[A::F; 2]; 2]) -> A::F {
    g.iter().flatten().fold(ar.lit(0.0), |m, v| ar.max_nan(&m, &ar.abs(v)))
}

/// The patch through `g` (see [`SafePatch`]).
pub(super) fn patch_of<R: Round, A: F32Arith>(ar: &A, ok: &A::B, g: [[A::F; 2]; 2]) -> SafePatch<A::F, A::B> {
    let zero = ar.lit(0.0);
    let negative: Vec<A::B> = g.iter().flatten().map(|v| ar.lt(v, &zero)).collect();
    let mg = largest(ar, &g);
    let [p, q, r, s] = coefficients(ar, &g);
    let pad = ar.add(&ar.mul(&mg, &ar.lit(PAD)), &ar.lit(FLOOR));
    let p1 = R::up(ar, &ar.add(&p, &pad));
    let emit = ar.all(&[ok.clone(), ar.any(&negative), ar.lt(&mg, &ar.lit(LIMIT))]);
    SafePatch { emit, g, coef: [p1, q, r, s] }
}

/// An axis's answer and its two patches.
pub type AxisOf<F, B> = (AxisAnswer<F, B>, [SafePatch<F, B>; 2]);

/// One axis's answer for the edges `lo`, `hi` of a column (x) or a row (y), and its two
/// patches (the min patch `g = -min`, culling where the min is > 0, then the max patch
/// `g = max`, culling where the max is < 0).
pub fn axis_answer<R: Round, A: F32Arith>(ar: &A, ax: &SafeAxis<A::F>, lo: &A::F, hi: &A::F) -> AxisOf<A::F, A::B> {
    let (ok, [mn, mx]) = corners_of::<R, A>(ar, ax, lo, hi);
    // Upper ends of -min and of max: from here on the patch is the one through them.
    let pin = |c: [[A::F; 2]; 2]| c.map(|r| r.map(|v| ar.pin(&v, End::Hi, CORNER_LEMMA)));
    let gs = [pin(mn.map(|r| r.map(|v| ar.neg(&v)))), pin(mx)];
    let (some0, t0, l0) = ranges_of::<R, A>(ar, &gs[0]);
    let (some1, t1, l1) = ranges_of::<R, A>(ar, &gs[1]);
    let l = [ar.max(&ar.max(&ar.lit(-1.0), &l0[0]), &l1[0]), ar.min(&ar.min(&ar.lit(1.0), &l0[1]), &l1[1])];
    let none = ar.not(&ar.and(&some0, &some1));
    let [g0, g1] = gs;
    let patches = [patch_of::<R, A>(ar, &ok, g0), patch_of::<R, A>(ar, &ok, g1)];
    (AxisAnswer { ok, none, ts: [t0, t1], l }, patches)
}
