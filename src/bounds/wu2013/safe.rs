//! `wu2013-safe`: the same two stages in f32 interval arithmetic rounded outward, with
//! the sign-aware hull for mixed crossing directions and both CoC signs. The derivation
//! and the error analysis are in the parent's module doc (section "`wu2013-safe`").
//!
//! Written once over [`F32Arith`] and a rounding discipline [`Round`] (the `-safe`
//! arithmetic [`Outward`], or a planted slip that drops one side's steps): the gate runs
//! it in f32 ([`Plain`], the tile path here and the grid of `grid.rs`), and the enclosure
//! check of `cullproof proofs` traces the same code for every input. Where the
//! derivation takes an end as the number that defines the next step (the lens range as
//! the corners of stage 2's rectangle, a line's intercept), the code says so with
//! [`F32Arith::pin`], naming the lemma that carries the step; the padded intercept is
//! [`F32Arith::moved_out`] of it, and the slope, which any value would do for, is
//! [`F32Arith::choose`]. Every other instance of [`F32Arith`] ignores them.
//!
//! Decisions that were early returns in f32 (`None`: no bound from a stage) are truth
//! values here: every value is computed and the answer selects, so that one description
//! serves the f32 method and its trace.

use super::*;
use crate::bounds::arith::{End, F32Arith, Plain, TriOf};
use crate::bounds::round::{Outward, Round};
use std::marker::PhantomData;

/// A closed interval `[lo, hi]` of values of some [`F32Arith`] enclosing an exact real
/// value; NaN ends mean "no information" (every test on them is false).
pub type Iv<F> = [F; 2];

/// f32 interval arithmetic over any [`F32Arith`]: every operation rounds to nearest and
/// steps each end one f32 value outward (`R::dn` / `R::up`), which encloses the exact
/// result of the operation on any reals in the operands (module doc). A non-finite end
/// (NaN, an overflow) makes both ends NaN, so that nothing is bounded from it.
pub(crate) struct IvOps<'a, A, R> {
    ar: &'a A,
    round: PhantomData<R>,
}

impl<'a, A: F32Arith, R: Round> IvOps<'a, A, R> {
    pub(crate) fn new(ar: &'a A) -> Self {
        IvOps { ar, round: PhantomData }
    }
    fn nan(&self) -> A::F {
        self.ar.lit(f32::NAN)
    }
    /// An exact input `[x, x]` (finite: the setup falls back on any non-finite input
    /// before a tile is answered).
    pub(crate) fn pt(&self, x: &A::F) -> Iv<A::F> {
        [x.clone(), x.clone()]
    }
    /// `[lo, hi]` are round-to-nearest values of the exact ends: one step outward, or NaN
    /// ends unless both are finite.
    #[inline(always)]
    fn out(&self, lo: &A::F, hi: &A::F) -> Iv<A::F> {
        let ar = self.ar;
        let ok = ar.and(&ar.is_finite(lo), &ar.is_finite(hi));
        [ar.select(&ok, &R::dn(ar, lo), &self.nan()), ar.select(&ok, &R::up(ar, hi), &self.nan())]
    }
    /// Both ends finite.
    pub(crate) fn ok(&self, x: &Iv<A::F>) -> A::B {
        self.ar.and(&self.ar.is_finite(&x[0]), &self.ar.is_finite(&x[1]))
    }
    /// Strictly positive / strictly negative (false on NaN ends).
    pub(crate) fn pos(&self, x: &Iv<A::F>) -> A::B {
        self.ar.lt(&self.ar.lit(0.0), &x[0])
    }
    pub(crate) fn neg(&self, x: &Iv<A::F>) -> A::B {
        self.ar.lt(&x[1], &self.ar.lit(0.0))
    }
    pub(crate) fn add(&self, a: &Iv<A::F>, b: &Iv<A::F>) -> Iv<A::F> {
        self.out(&self.ar.add(&a[0], &b[0]), &self.ar.add(&a[1], &b[1]))
    }
    pub(crate) fn sub(&self, a: &Iv<A::F>, b: &Iv<A::F>) -> Iv<A::F> {
        self.out(&self.ar.sub(&a[0], &b[1]), &self.ar.sub(&a[1], &b[0]))
    }
    /// The hull of the four end products (quotients) stepped outward, NaN ends unless
    /// all four are finite.
    #[inline(always)]
    fn hull4(&self, p: [A::F; 4]) -> Iv<A::F> {
        let ar = self.ar;
        let fin = ar.all(&[ar.is_finite(&p[0]), ar.is_finite(&p[1]), ar.is_finite(&p[2]), ar.is_finite(&p[3])]);
        let lo = ar.min(&ar.min(&p[0], &p[1]), &ar.min(&p[2], &p[3]));
        let hi = ar.max(&ar.max(&p[0], &p[1]), &ar.max(&p[2], &p[3]));
        self.out(&lo, &hi).map(|e| ar.select(&fin, &e, &self.nan()))
    }
    pub(crate) fn mul(&self, a: &Iv<A::F>, b: &Iv<A::F>) -> Iv<A::F> {
        let ar = self.ar;
        self.hull4([ar.mul(&a[0], &b[0]), ar.mul(&a[0], &b[1]), ar.mul(&a[1], &b[0]), ar.mul(&a[1], &b[1])])
    }
    /// `pt(a) * pt(b)`, the four equal products taken once: the product stepped outward.
    pub(crate) fn pt_mul(&self, a: &A::F, b: &A::F) -> Iv<A::F> {
        let p = self.ar.mul(a, b);
        self.out(&p, &p)
    }
    /// `pt(a) * x`, the two distinct products taken once: their hull stepped outward,
    /// NaN ends unless both are finite. The order of two products equal in value but of
    /// opposite zero signs does not matter: both ends are stepped off zero.
    pub(crate) fn pt_scale(&self, x: &Iv<A::F>, a: &A::F) -> Iv<A::F> {
        let ar = self.ar;
        let (p, q) = (ar.mul(a, &x[0]), ar.mul(a, &x[1]));
        let fin = ar.and(&ar.is_finite(&p), &ar.is_finite(&q));
        self.out(&ar.min(&p, &q), &ar.max(&p, &q)).map(|e| ar.select(&fin, &e, &self.nan()))
    }
    /// NaN ends unless the divisor has one strict sign (each sign its own branch).
    pub(crate) fn div(&self, a: &Iv<A::F>, b: &Iv<A::F>) -> Iv<A::F> {
        let ar = self.ar;
        let q = self.hull4([ar.div(&a[0], &b[0]), ar.div(&a[0], &b[1]), ar.div(&a[1], &b[0]), ar.div(&a[1], &b[1])]);
        let (pos, neg) = (self.pos(b), self.neg(b));
        q.map(|e| ar.select(&pos, &e, &ar.select(&neg, &e, &self.nan())))
    }
}

/// One vertex on one axis for `wu2013-safe`: position and w exact (f32 inputs), the CoC
/// (c, or k c on the y axis) as an enclosure, and the enclosures of `p0 - p1`,
/// `w0 - w1` and `c0 - c1` (they do not depend on the tile: computed once, at setup).
#[derive(Clone, Debug)]
pub struct SafeVertex<F> {
    p0: F,
    w0: F,
    c0: Iv<F>,
    p1: F,
    w1: F,
    c1: Iv<F>,
    dp: Iv<F>,
    dw: Iv<F>,
    dc: Iv<F>,
}

/// One axis (x with u, or y with v) for `wu2013-safe`.
#[derive(Clone, Debug)]
pub struct SafeAxis<F> {
    pub(crate) v: [SafeVertex<F>; 3],
}

/// One crossing, for [`IvOps::sign_parts`]: `delta_k` is affine in the variable z (u,
/// or t), increasing (the truth value) or decreasing, and vanishes at some `z_k` in
/// `[m, hi]` for every (column, other coordinate) of the tile.
pub type Crossing<F, B> = (B, F, F);

/// Per vertex its [`Crossing`], and whether every value they come from is usable.
pub type Crossings<F, B> = (B, [Crossing<F, B>; 3]);

/// Per vertex, [`IvOps::at_column`] at the tile's two columns (shared by stage 2's tile
/// interval and its lines).
pub type Columns<F> = [[(Iv<F>, Iv<F>); 2]; 3];

/// One vertex's part of the published lines at one column ([`IvOps::line_ends`]):
/// whether it is there (D of one strict sign at l = -1 and +1, every value finite),
/// whether D > 0 and whether D < 0 there, and the upper ends at l = -1, +1, then the
/// lower ends at l = -1, +1.
pub type LineEnds<F, B> = (B, [B; 2], [F; 4]);

/// `wu2013-safe`'s line pad, 2^-21 = 8u (proof: `src/bounds/proofs/wu2013_safe.g`).
pub(crate) const PAD: f32 = 1.0 / (1u32 << 21) as f32;
/// `wu2013-safe`'s line pad floor, 2^-100.
pub(crate) const FLOOR: f32 = 1.0 / (1u128 << 100) as f32;

/// The lemma that lets the ends of stage 1's lens range stand for the exact range.
pub const LENS_LEMMA: &str = "wu2013-safe lens range: stage 2's rectangle of columns x [l0, l1] with l0 at or \
     below the exact lens range's least value and l1 at or above its greatest holds every covered (column, lens) \
     pair, so its corners' crossing times and the lines' values at l0, l1 bound those of the covered samples";
/// The lemma that lets a line's intercept define the line.
pub const LINE_LEMMA: &str = "wu2013-safe lines: a line a l + b (any a) with b at or above both e_left + a and \
     e_right - a, for e_left, e_right at or above the exact upper line's values at l = -1, +1, lies at or above \
     that line for l in [-1, 1] (lower lines: at or below, mirrored)";
/// What a line's slope is: any value will do.
pub const SLOPE_CHOICE: &str = "wu2013-safe line slope: the intercept is then chosen to dominate both endpoints, \
     so any finite slope gives a line through or beyond them";
/// Why the endpoints' limit is the code's choice.
pub const LIMIT_CHOICE: &str = "wu2013-safe builds a line only from endpoints within LINE_LIMIT: it only turns \
     lines off, and its f32 truth is the hypothesis under which wu2013_safe.g proves the padded line's value finite";
/// Why keeping a line as a per-sample constraint is the code's choice.
pub const KEEP_CHOICE: &str = "wu2013-safe keeps a line as a constraint only where it can cut (a slope other than \
     0, a value inside the shutter): dropping a constraint only culls less";

/// A padded line `t = a l + b'` of `wu2013-safe` (upper or lower): whether it is there
/// (endpoints within `LINE_LIMIT`, `a` and `b'` finite), its slope `a`, its intercept
/// `b` through or beyond both endpoints (pinned, [`LINE_LEMMA`]) and `b'`, that
/// intercept moved outward by the f32 error of [`TimeLine::eval`] (module doc).
#[derive(Clone, Debug)]
pub struct SafeLineOf<F, B> {
    pub ok: B,
    /// The endpoints' values at l = -1 and l = +1.
    pub ends: [F; 2],
    pub a: F,
    pub b: F,
    pub padded: F,
}

/// What one line does to a tile over its lens range: whether it bounds the tile's times
/// (`has`: the line is there and its values at the range's ends are finite), that bound
/// (an upper line's greatest value over the range, a lower line's least), and whether
/// the line is kept as a per-sample constraint.
#[derive(Clone, Debug)]
pub struct SideCut<F, B> {
    pub has: B,
    pub bound: F,
    pub keep: B,
    pub line: SafeLineOf<F, B>,
}

/// One axis's lines over a tile: the upper, then the lower.
pub type AxisCut<F, B> = [SideCut<F, B>; 2];

impl<A: F32Arith, R: Round> IvOps<'_, A, R> {
    fn vertex(&self, p0: &A::F, w0: &A::F, c0: Iv<A::F>, p1: &A::F, w1: &A::F, c1: Iv<A::F>) -> SafeVertex<A::F> {
        let dp = self.sub(&self.pt(p0), &self.pt(p1));
        let dw = self.sub(&self.pt(w0), &self.pt(w1));
        let dc = self.sub(&c0, &c1);
        SafeVertex { p0: p0.clone(), w0: w0.clone(), c0, p1: p1.clone(), w1: w1.clone(), c1, dp, dw, dc }
    }

    /// One axis of the triangle (`j`: 0 for x, 1 for y; `scale`: 1 or the aspect k).
    fn axis(&self, tri: &TriOf<A::F>, j: usize, scale: &A::F) -> SafeAxis<A::F> {
        let k = self.pt(scale);
        SafeAxis {
            v: std::array::from_fn(|i| {
                let (q, r) = (&tri.q[i], &tri.r[i]);
                let (c0, c1) = (self.mul(&k, &self.pt(&tri.c0[i])), self.mul(&k, &self.pt(&tri.c1[i])));
                self.vertex(&q[j], &q[3], c0, &r[j], &r[3], c1)
            }),
        }
    }

    /// The parts of `N` and `D` at column `X = s` that do not depend on `l`:
    /// `p0 - X w0` and `(p0 - p1) - X (w0 - w1)` (shared by the lens values of a column).
    pub(crate) fn at_column(&self, v: &SafeVertex<A::F>, s: &A::F) -> (Iv<A::F>, Iv<A::F>) {
        (self.sub(&self.pt(&v.p0), &self.pt_mul(s, &v.w0)), self.sub(&v.dp, &self.pt_scale(&v.dw, s)))
    }

    /// `N(X, l) = p0 - X w0 + l c0 = delta(t = 0)` and
    /// `D(X, l) = (p0 - p1) - X (w0 - w1) + l (c0 - c1) = delta(0) - delta(1)`, from the
    /// column's parts ([`at_column`](Self::at_column)).
    fn nd_from(&self, v: &SafeVertex<A::F>, col: &(Iv<A::F>, Iv<A::F>), l: &A::F) -> (Iv<A::F>, Iv<A::F>) {
        (self.add(&col.0, &self.pt_scale(&v.c0, l)), self.add(&col.1, &self.pt_scale(&v.dc, l)))
    }

    /// Per vertex, the direction of `delta_k` in the lens coordinate (true: increasing,
    /// `c_k > 0`), and whether every CoC is of one strict sign over the shutter (else
    /// stage 1 gives no lens bound on this axis, for every tile).
    pub(crate) fn lens_directions(&self, axis: &SafeAxis<A::F>) -> (A::B, [A::B; 3]) {
        let ar = self.ar;
        let inc = axis.v.each_ref().map(|a| ar.and(&self.pos(&a.c0), &self.pos(&a.c1)));
        let one = axis.v.each_ref().map(|a| ar.and(&self.neg(&a.c0), &self.neg(&a.c1)));
        let ok: Vec<A::B> = inc.iter().zip(&one).map(|(i, d)| ar.or(i, d)).collect();
        (ar.all(&ok), inc)
    }

    /// Per vertex, the enclosures of its lens crossing `u_k(X, t) = (X w_k(t) - p_k(t)) /
    /// c_k(t)` at column `X = s`, at t = 0 and t = 1 (they read one column boundary only).
    pub(crate) fn lens_at(&self, axis: &SafeAxis<A::F>, s: &A::F) -> [[Iv<A::F>; 2]; 3] {
        axis.v.each_ref().map(|a| {
            [(&a.p0, &a.w0, &a.c0), (&a.p1, &a.w1, &a.c1)]
                .map(|(p, w, c)| self.div(&self.sub(&self.pt_mul(s, w), &self.pt(p)), c))
        })
    }

    /// Stage 1's crossings from the directions and the values at the two boundaries
    /// `at` (left, right): per vertex the extremes over the shutter ends and the two
    /// columns, and whether every value is finite.
    pub(crate) fn lens_crossings_from(&self, inc: &[A::B; 3], at: [&[[Iv<A::F>; 2]; 3]; 2]) -> Crossings<A::F, A::B> {
        let ar = self.ar;
        let mut ok = vec![];
        let out = std::array::from_fn(|k| {
            let (mut m, mut h) = (ar.lit(f32::INFINITY), ar.lit(f32::NEG_INFINITY));
            for end in 0..2 {
                for side in at {
                    let l = &side[k][end];
                    ok.push(self.ok(l));
                    m = ar.min(&m, &l[0]);
                    h = ar.max(&h, &l[1]);
                }
            }
            (inc[k].clone(), m, h)
        });
        (ar.all(&ok), out)
    }

    /// The four intervals whose union holds the z at which not all `delta_k` have one
    /// strict sign (the necessary condition for coverage, module doc). With I the
    /// increasing and J the decreasing deltas, some `delta_k <= 0` only for z in
    /// `(-inf, max_I hi] u [min_J m, inf)` and some `delta_k >= 0` only for z in
    /// `[min_I m, inf) u (-inf, max_J hi]`; the intersection is the union of these four
    /// (exact comparisons, no rounding). They depend on the crossings only: a grid
    /// computes them once per column or row.
    pub(crate) fn sign_parts(&self, items: &[Crossing<A::F, A::B>; 3]) -> [[A::F; 2]; 4] {
        let ar = self.ar;
        let (inf, ninf) = (ar.lit(f32::INFINITY), ar.lit(f32::NEG_INFINITY));
        let (mut mi, mut hi_i, mut mj, mut hi_j) = (inf.clone(), ninf.clone(), inf.clone(), ninf.clone());
        for (inc, m, h) in items {
            mi = ar.select(inc, &ar.min(&mi, m), &mi);
            hi_i = ar.select(inc, &ar.max(&hi_i, h), &hi_i);
            mj = ar.select(inc, &mj, &ar.min(&mj, m));
            hi_j = ar.select(inc, &hi_j, &ar.max(&hi_j, h));
        }
        let (cross_lo, cross_hi) = (ar.min(&hi_i, &hi_j), ar.max(&mj, &mi));
        [[mi, hi_i], [ninf, cross_lo], [cross_hi, inf], [mj, hi_j]]
    }

    /// The hull of the parts of [`sign_parts`](Self::sign_parts) within `dom`, and
    /// whether any part meets it (false: no covered sample).
    pub(crate) fn hull_within(&self, parts: &[[A::F; 2]; 4], dom: &[A::F; 2]) -> (A::B, [A::F; 2]) {
        let ar = self.ar;
        let (mut lo, mut hi) = (ar.lit(f32::INFINITY), ar.lit(f32::NEG_INFINITY));
        let mut some = vec![];
        for [a, b] in parts {
            let (a, b) = (ar.max(a, &dom[0]), ar.min(b, &dom[1]));
            let meets = ar.le(&a, &b);
            lo = ar.select(&meets, &ar.min(&lo, &a), &lo);
            hi = ar.select(&meets, &ar.max(&hi, &b), &hi);
            some.push(meets);
        }
        (ar.any(&some), [lo, hi])
    }

    /// Stage 1, corrected, on columns `[s0, s1]` (their lens values `at`): whether it
    /// applies (every CoC of one strict sign, every value finite), whether any lens value
    /// is left, and the hull of those within [-1, 1].
    pub(crate) fn stage1(&self, axis: &SafeAxis<A::F>, at: [&[[Iv<A::F>; 2]; 3]; 2]) -> (A::B, A::B, [A::F; 2]) {
        let ar = self.ar;
        let (one_sign, inc) = self.lens_directions(axis);
        let (finite, cr) = self.lens_crossings_from(&inc, at);
        let (some, r) = self.hull_within(&self.sign_parts(&cr), &[ar.lit(-1.0), ar.lit(1.0)]);
        (ar.and(&one_sign, &finite), some, r)
    }

    /// Stage 2, corrected (tile level): per vertex the enclosure of its crossing time
    /// `t_k = N / D` over the rectangle of columns (`cols`) and lens `l` (a linear
    /// fraction of (X, l) jointly: its extremes are at the 4 corners when D keeps one
    /// strict sign there), with the direction of `delta_k(t) = N - t D` in t (increasing
    /// iff D < 0); vertices may cross in opposite directions. With it, whether every D is
    /// of one strict sign on the rectangle and every value finite (else no time bound
    /// from this axis).
    pub(crate) fn time_crossings(
        &self,
        axis: &SafeAxis<A::F>,
        cols: &Columns<A::F>,
        l: &[A::F; 2],
    ) -> Crossings<A::F, A::B> {
        let ar = self.ar;
        let mut ok = vec![];
        let out = std::array::from_fn(|k| {
            let (a, ac) = (&axis.v[k], &cols[k]);
            let (mut pos, mut neg) = (vec![], vec![]);
            let (mut m, mut h) = (ar.lit(f32::INFINITY), ar.lit(f32::NEG_INFINITY));
            for col in ac {
                for lv in l {
                    let (n, d) = self.nd_from(a, col, lv);
                    pos.push(self.pos(&d));
                    neg.push(self.neg(&d));
                    let t = self.div(&n, &d);
                    ok.push(self.ok(&t));
                    m = ar.min(&m, &t[0]);
                    h = ar.max(&h, &t[1]);
                }
            }
            // Every t finite makes every D of one strict sign: then "not both signs" is
            // "all of one sign".
            let dec = ar.all(&neg);
            ok.push(ar.or(&ar.all(&pos), &dec));
            (dec, m, h)
        });
        (ar.all(&ok), out)
    }

    /// The vertex's chord and tangent enclosures at column `col` (its
    /// [`at_column`](Self::at_column) parts) and l = -1, +1: the upper ends' maxima and
    /// the lower ends' minima, with the sign of D. It reads one column boundary only.
    pub(crate) fn line_ends(&self, v: &SafeVertex<A::F>, col: &(Iv<A::F>, Iv<A::F>)) -> LineEnds<A::F, A::B> {
        let ar = self.ar;
        let (n0, d0) = self.nd_from(v, col, &ar.lit(0.0));
        let (nm, dm) = self.nd_from(v, col, &ar.lit(-1.0));
        let (np, dp) = self.nd_from(v, col, &ar.lit(1.0));
        let d_pos = ar.and(&self.pos(&dm), &self.pos(&dp));
        let d_neg = ar.and(&self.neg(&dm), &self.neg(&dp));
        let (n1, d1) = (&v.c0, &v.dc);
        let tm = self.div(&nm, &dm);
        let tp = self.div(&np, &dp);
        let tz = self.div(&n0, &d0);
        let slope = self.div(&self.sub(n1, &self.mul(&tz, d1)), &d0);
        let (gm, gp) = (self.sub(&tz, &slope), self.add(&tz, &slope));
        let ok = ar.all(&[ar.or(&d_pos, &d_neg), self.ok(&tm), self.ok(&tp), self.ok(&gm), self.ok(&gp)]);
        // (d_pos and d_neg are not both true: one value is not > 0 and < 0.)
        let ends = [ar.max(&tm[1], &gm[1]), ar.max(&tp[1], &gp[1]), ar.min(&tm[0], &gm[0]), ar.min(&tp[0], &gp[0])];
        (ok, [d_pos, d_neg], ends)
    }

    /// Stage 2 as published (the green / red lines), enclosed, from each vertex's
    /// [`line_ends`](Self::line_ends) at the two columns (`ends[vertex][side]`): whether
    /// every one is there and all share one sign of D (the guarded condition), and the
    /// lines' endpoints `[ul, ur, ll, lr]` (the upper ones the maxima, the lower ones the
    /// minima).
    pub(crate) fn lines_from(&self, ends: &[[LineEnds<A::F, A::B>; 2]; 3]) -> (A::B, [A::F; 4]) {
        let ar = self.ar;
        let (ninf, inf) = (ar.lit(f32::NEG_INFINITY), ar.lit(f32::INFINITY));
        let mut out = [ninf.clone(), ninf, inf.clone(), inf];
        let (mut ok, mut pos, mut neg) = (vec![], vec![], vec![]);
        for (there, [d_pos, d_neg], e) in ends.iter().flatten() {
            ok.push(there.clone());
            pos.push(d_pos.clone());
            neg.push(d_neg.clone());
            out[0] = ar.max(&out[0], &e[0]);
            out[1] = ar.max(&out[1], &e[1]);
            out[2] = ar.min(&out[2], &e[2]);
            out[3] = ar.min(&out[3], &e[3]);
        }
        // Each end there has D > 0 or D < 0 at both l: "not both signs" is "all of one".
        ok.push(ar.or(&ar.all(&pos), &ar.all(&neg)));
        (ar.all(&ok), out)
    }

    /// The padded line through or beyond `(-1, e_left)`, `(1, e_right)`: above both for
    /// an upper line, below both for a lower one.
    pub(crate) fn safe_line(&self, upper: bool, e_left: &A::F, e_right: &A::F) -> SafeLineOf<A::F, A::B> {
        let ar = self.ar;
        let lim = ar.lit(LINE_LIMIT);
        let within =
            ar.choose_truth(&ar.and(&ar.le(&ar.abs(e_left), &lim), &ar.le(&ar.abs(e_right), &lim)), LIMIT_CHOICE);
        let half = ar.lit(0.5);
        let a = ar.choose(&ar.sub(&ar.mul(&half, e_right), &ar.mul(&half, e_left)), SLOPE_CHOICE);
        let (l, r) = (ar.add(e_left, &a), ar.sub(e_right, &a));
        let b = if upper { ar.max(&R::up(ar, &l), &R::up(ar, &r)) } else { ar.min(&R::dn(ar, &l), &R::dn(ar, &r)) };
        let b = ar.pin(&b, if upper { End::Hi } else { End::Lo }, LINE_LEMMA);
        let sum = ar.add(&ar.add(&ar.add(&ar.abs(&a), &ar.abs(&a)), &ar.abs(&b)), &ar.lit(FLOOR));
        let pad = ar.mul(&sum, &ar.lit(PAD));
        let padded = if upper {
            ar.moved_out(&R::up(ar, &ar.add(&b, &pad)), &b, End::Hi)
        } else {
            ar.moved_out(&R::dn(ar, &ar.sub(&b, &pad)), &b, End::Lo)
        };
        let ok = ar.all(&[within, ar.is_finite(&a), ar.is_finite(&padded)]);
        SafeLineOf { ok, ends: [e_left.clone(), e_right.clone()], a, b, padded }
    }

    /// What the padded line does over the lens range `l` (`there`: the axis has lines).
    fn side_cut(&self, upper: bool, there: &A::B, e: [&A::F; 2], l: &[A::F; 2]) -> SideCut<A::F, A::B> {
        let ar = self.ar;
        let line = self.safe_line(upper, e[0], e[1]);
        let at = |x: &A::F| self.add(&self.pt_mul(&line.a, x), &self.pt(&line.padded));
        let (e0, e1) = (at(&l[0]), at(&l[1]));
        let has = ar.all(&[there.clone(), line.ok.clone(), self.ok(&e0), self.ok(&e1)]);
        let zero = ar.lit(0.0);
        let sloped = ar.not(&ar.eq(&line.a, &zero));
        let (bound, cuts) = if upper {
            (ar.max(&e0[1], &e1[1]), ar.lt(&ar.min(&e0[0], &e1[0]), &ar.lit(1.0)))
        } else {
            (ar.min(&e0[0], &e1[0]), ar.lt(&zero, &ar.max(&e0[1], &e1[1])))
        };
        let keep = ar.and(&has, &ar.choose_truth(&ar.and(&sloped, &cuts), KEEP_CHOICE));
        SideCut { has, bound, keep, line }
    }

    /// The safe lines of one axis over the lens range `l`, from the endpoints
    /// [`lines_from`](Self::lines_from) gives (`there`: whether it gives any).
    pub(crate) fn axis_cut(&self, there: &A::B, ends: &[A::F; 4], l: &[A::F; 2]) -> AxisCut<A::F, A::B> {
        [self.side_cut(true, there, [&ends[0], &ends[1]], l), self.side_cut(false, there, [&ends[2], &ends[3]], l)]
    }

    /// Narrow the time range `t` by an axis's lines (the upper line first).
    pub(crate) fn bound(&self, cut: &AxisCut<A::F, A::B>, t: [A::F; 2]) -> [A::F; 2] {
        let ar = self.ar;
        let [up, dn] = cut;
        let t1 = ar.select(&up.has, &ar.min(&t[1], &up.bound), &t[1]);
        let t0 = ar.select(&dn.has, &ar.max(&t[0], &dn.bound), &t[0]);
        [t0, t1]
    }
}

/// Both axes of `wu2013-safe` and whether every input is finite (otherwise every tile
/// gets the full domain).
pub type SafeSetupOf<F, B> = (B, [SafeAxis<F>; 2]);

/// The setup of `wu2013-safe` over any [`F32Arith`].
pub fn setup_of<R: Round, A: F32Arith>(ar: &A, tri: &TriOf<A::F>) -> SafeSetupOf<A::F, A::B> {
    let o = IvOps::<A, R>::new(ar);
    let inputs = tri.q.iter().chain(tri.r.iter()).flatten().chain(tri.c0.iter()).chain(tri.c1.iter());
    let finite: Vec<A::B> = inputs.chain(std::iter::once(&tri.k)).map(|v| ar.is_finite(v)).collect();
    (ar.all(&finite), [o.axis(tri, 0, &ar.lit(1.0)), o.axis(tri, 1, &tri.k)])
}

/// A `wu2013-safe` tile answer over any [`F32Arith`] (where every input is finite).
#[derive(Clone, Debug)]
pub struct AnswerOf<F, B> {
    /// No covered sample: a stage leaves no lens value or time, or the time range is
    /// NaN or reversed.
    pub reject: B,
    pub u: [F; 2],
    pub v: [F; 2],
    pub t: [F; 2],
    /// Per axis (x with u, then y with v), its lines.
    pub lines: [AxisCut<F, B>; 2],
}

/// The tile `[x0, y0, x1, y1]`'s answer over any [`F32Arith`]: stage 1 on both axes,
/// then stage 2 on x, then on y, each axis's sign-aware time hull and lines over the
/// lens range stage 1 left on it.
pub fn tile_answer<R: Round, A: F32Arith>(
    ar: &A,
    axes: &[SafeAxis<A::F>; 2],
    tile: &[A::F; 4],
) -> AnswerOf<A::F, A::B> {
    let o = IvOps::<A, R>::new(ar);
    let sides = [[&tile[0], &tile[2]], [&tile[1], &tile[3]]];
    let mut culls = vec![];
    let mut lens = vec![];
    for (axis, [s0, s1]) in axes.iter().zip(sides) {
        let at = [o.lens_at(axis, s0), o.lens_at(axis, s1)];
        let (on, some, r) = o.stage1(axis, [&at[0], &at[1]]);
        culls.push(ar.and(&on, &ar.not(&some)));
        lens.push([ar.select(&on, &r[0], &ar.lit(-1.0)), ar.select(&on, &r[1], &ar.lit(1.0))]);
    }
    let mut t = [ar.lit(0.0), ar.lit(1.0)];
    let mut lines = vec![];
    for ((axis, [s0, s1]), range) in axes.iter().zip(sides).zip(&lens) {
        let l = [ar.pin(&range[0], End::Lo, LENS_LEMMA), ar.pin(&range[1], End::Hi, LENS_LEMMA)];
        let cols: Columns<A::F> = axis.v.each_ref().map(|a| [o.at_column(a, s0), o.at_column(a, s1)]);
        let (on, cr) = o.time_crossings(axis, &cols, &l);
        let (some, r) = o.hull_within(&o.sign_parts(&cr), &t);
        culls.push(ar.and(&on, &ar.not(&some)));
        t = [ar.select(&on, &r[0], &t[0]), ar.select(&on, &r[1], &t[1])];
        let ends =
            std::array::from_fn(|k| [o.line_ends(&axis.v[k], &cols[k][0]), o.line_ends(&axis.v[k], &cols[k][1])]);
        let (there, e) = o.lines_from(&ends);
        let cut = o.axis_cut(&there, &e, &l);
        t = o.bound(&cut, t);
        lines.push(cut);
    }
    culls.extend([ar.is_nan(&t[0]), ar.is_nan(&t[1]), ar.lt(&t[1], &t[0])]);
    let [u, v]: [[A::F; 2]; 2] = lens.try_into().unwrap_or_else(|_| unreachable!("two axes"));
    let lines: [AxisCut<A::F, A::B>; 2] = lines.try_into().unwrap_or_else(|_| unreachable!("two axes"));
    AnswerOf { reject: ar.any(&culls), u, v, t, lines }
}

/// A padded f32 line through (or beyond) `(-1, e_left)`, `(1, e_right)` as a
/// per-sample constraint ([`IvOps::safe_line`] in f32), or None where it is not there.
pub(crate) fn safe_line(lens: Lens, upper: bool, e_left: f32, e_right: f32) -> Option<TimeLine> {
    let c = IvOps::<Plain, Outward>::new(&Plain).safe_line(upper, &e_left, &e_right);
    c.ok.then_some(TimeLine { lens, upper, a: c.a, b: c.padded })
}

/// The kept lines of one axis (upper first) as per-sample constraints.
pub(super) fn constraints_of(cut: &AxisCut<f32, bool>, lens: Lens, cons: &mut Vec<Box<dyn SampleConstraint>>) {
    for (side, upper) in cut.iter().zip([true, false]) {
        if side.keep {
            cons.push(Box::new(TimeLine { lens, upper, a: side.line.a, b: side.line.padded }));
        }
    }
}

/// The prepared triangle of `wu2013-safe` (with the rounding discipline `R`).
pub(super) struct SafePrep<R> {
    /// Every input is finite (otherwise every tile gets the full domain).
    pub(super) finite: bool,
    pub(super) x: SafeAxis<f32>,
    pub(super) y: SafeAxis<f32>,
    disabled: Option<&'static str>,
    round: PhantomData<fn() -> R>,
}

impl<R: Round> Prepared for SafePrep<R> {
    fn tile(&self, tile: &Tile) -> TileResult {
        if !self.finite {
            return TileResult::Bounds(TileBounds::full());
        }
        let axes = [self.x.clone(), self.y.clone()];
        let a = tile_answer::<R, Plain>(&Plain, &axes, &[tile.x0, tile.y0, tile.x1, tile.y1]);
        if a.reject {
            return TileResult::Empty;
        }
        let mut cons: Vec<Box<dyn SampleConstraint>> = Vec::new();
        constraints_of(&a.lines[0], Lens::U, &mut cons);
        constraints_of(&a.lines[1], Lens::V, &mut cons);
        let mut b = TileBounds::full();
        (b.u, b.v, b.t, b.constraints) = (a.u, a.v, a.t, cons);
        TileResult::Bounds(b)
    }
    /// Everything but the meeting of the axes' time ranges reads one axis only:
    /// computed once per column boundary, column, row boundary and row
    /// ([`grid::SafeGrid`]).
    fn grid<'a>(&'a self, grid: Grid<'a>) -> Box<dyn TileGrid + 'a> {
        Box::new(grid::SafeGrid::new::<R>(self, grid))
    }
    fn disabled(&self) -> Option<&'static str> {
        self.disabled
    }
}

fn prepare_safe<R: Round>(tri: &Triangle) -> SafePrep<R> {
    let (finite, [x, y]) = setup_of::<R, Plain>(&Plain, &TriOf::of(tri));
    let o = IvOps::<Plain, R>::new(&Plain);
    let one_sign = |ax: &SafeAxis<f32>| o.lens_directions(ax).0;
    // A vertex with D identically 0 on axis j: no motion relative to any pixel ray.
    let dead =
        |j: usize| (0..3).any(|i| tri.q[i][j] == tri.r[i][j] && tri.q[i][3] == tri.r[i][3] && tri.c0[i] == tri.c1[i]);
    let disabled = (!one_sign(&x) && !one_sign(&y) && dead(0) && dead(1)).then_some(
        "no stage applies: a CoC is 0 or changes sign in the shutter on both axes (stage 1 off) and on both axes a \
         vertex has no motion relative to the pixel rays (stage 2 denominators vanish)",
    );
    let disabled = if finite { disabled } else { Some("a non-finite input: the full domain for every tile") };
    SafePrep { finite, x, y, disabled, round: PhantomData }
}

/// `wu2013-safe` with the rounding discipline `R` (see the module doc); a planted slip
/// (`crate::bounds::broken::planted`) is the same code with one side's steps dropped.
pub struct Wu2013Safe<R> {
    pub info: &'static MethodInfo,
    pub round: PhantomData<fn() -> R>,
}

static INFO_SAFE: MethodInfo = MethodInfo {
    id: "wu2013-safe",
    source: "Wu 2013, Clip Space Sample Culling for Stochastic Rasterization (M.Sc. thesis, NCTU): §3.3 stage 1 \
             lens bounds; §3.4 stage 2 Eq. 1 rewritten, linear bounds of Figs. 3.7-3.8; §3.5 per-vertex CoC; in f32 \
             interval arithmetic, with both crossing directions and both CoC signs handled (derived in this file)",
    ..INFO
};

impl<R: Round> Method for Wu2013Safe<R> {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        Box::new(prepare_safe::<R>(tri))
    }
}

/// `wu2013-safe`: outward-rounded and corrected (see the module doc).
pub static METHOD_SAFE: &dyn Method = &Wu2013Safe::<Outward> { info: &INFO_SAFE, round: PhantomData };
