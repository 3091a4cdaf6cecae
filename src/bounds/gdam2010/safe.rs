//! `gdam2010-safe`: a certified superset of the covered time set, each culled piece
//! of the shutter proven by outward-rounded f32 enclosures of the edge functions, with
//! the box enclosures and cuts the judge uses. The derivation and the error analysis
//! are in the parent's module doc (section "`gdam2010-safe`").

use super::*;
use crate::bounds::arith::{F32Arith, Plain};
use crate::bounds::round::{Outward, Round};
use std::marker::PhantomData;

/// A closed f32 interval `[lo, hi]` that encloses one exact real: outward-rounded f32
/// arithmetic for `gdam2010-safe` (each rounded result stepped to the next f32 outward;
/// see the module doc). NaN ends make every sign test below false.
pub type Iv<F> = [F; 2];

/// A point relative to the sample's pixel, `(x - X w, y - Y w)`, enclosed.
pub type Rel<F> = [Iv<F>; 2];

/// The shortcuts of one exact value ([`F32Arith::select_same`]; the enclosure check
/// verifies each).
const ZERO_SUM: &str = "gdam2010-safe: an operand enclosed as [0, 0] is exactly 0, so the sum is the other operand";
const ZERO_PRODUCT: &str = "gdam2010-safe: an operand enclosed as [0, 0] is exactly 0, so the product is 0";
const STILL: &str = "gdam2010-safe: a vertex whose inputs are equal at both shutter ends does not move";
const AT_ZERO: &str = "gdam2010-safe: at t = 0 the vertex is its value at t = 0";
const AT_ONE: &str = "gdam2010-safe: at t = 1 the vertex is its value at t = 1";

/// The interval arithmetic of `gdam2010-safe` over any [`F32Arith`], with the rounding
/// discipline `R` ([`Outward`]: one step outward after each rounded result). Every
/// shortcut of an exact zero is a select, so that the check traces all of it.
pub struct IvOps<'a, A, R> {
    ar: &'a A,
    round: PhantomData<R>,
}

impl<'a, A: F32Arith, R: Round> IvOps<'a, A, R> {
    pub fn new(ar: &'a A) -> Self {
        IvOps { ar, round: PhantomData }
    }
    #[inline(always)]
    fn zero(&self) -> Iv<A::F> {
        [self.ar.lit(0.0), self.ar.lit(0.0)]
    }
    /// Both ends are 0: the enclosed value is exactly 0.
    #[inline(always)]
    fn is_zero(&self, a: &Iv<A::F>) -> A::B {
        let (ar, z) = (self.ar, self.ar.lit(0.0));
        ar.and(&ar.eq(&a[0], &z), &ar.eq(&a[1], &z))
    }
    /// `if c { a } else { b }`, both one exact value where `c` holds (`why`).
    #[inline(always)]
    fn same(&self, c: &A::B, a: &Iv<A::F>, b: &Iv<A::F>, why: &'static str) -> Iv<A::F> {
        [self.ar.select_same(c, &a[0], &b[0], why), self.ar.select_same(c, &a[1], &b[1], why)]
    }
    /// The exact value lies within one f32 step of `r`, a result rounded to nearest.
    #[inline(always)]
    fn near(&self, r: &A::F) -> Iv<A::F> {
        [R::dn(self.ar, r), R::up(self.ar, r)]
    }
    /// The sum; an exact 0 operand gives the other one unchanged.
    #[inline(always)]
    fn add(&self, a: &Iv<A::F>, b: &Iv<A::F>) -> Iv<A::F> {
        let ar = self.ar;
        let s = [R::dn(ar, &ar.add(&a[0], &b[0])), R::up(ar, &ar.add(&a[1], &b[1]))];
        self.same(&self.is_zero(a), b, &self.same(&self.is_zero(b), a, &s, ZERO_SUM), ZERO_SUM)
    }
    #[inline(always)]
    fn neg(&self, a: &Iv<A::F>) -> Iv<A::F> {
        [self.ar.neg(&a[1]), self.ar.neg(&a[0])]
    }
    #[inline(always)]
    fn sub(&self, a: &Iv<A::F>, b: &Iv<A::F>) -> Iv<A::F> {
        self.add(a, &self.neg(b))
    }
    /// The product: the least and greatest of the four end products, stepped outward
    /// (NaN when one of them is NaN); an exact 0 operand gives an exact 0.
    #[inline(always)]
    fn mul(&self, a: &Iv<A::F>, b: &Iv<A::F>) -> Iv<A::F> {
        let ar = self.ar;
        let p = [ar.mul(&a[0], &b[0]), ar.mul(&a[0], &b[1]), ar.mul(&a[1], &b[0]), ar.mul(&a[1], &b[1])];
        let lo = ar.min_nan(&ar.min_nan(&ar.min_nan(&p[0], &p[1]), &p[2]), &p[3]);
        let hi = ar.max_nan(&ar.max_nan(&ar.max_nan(&p[0], &p[1]), &p[2]), &p[3]);
        let out = [R::dn(ar, &lo), R::up(ar, &hi)];
        self.same(&ar.or(&self.is_zero(a), &self.is_zero(b)), &self.zero(), &out, ZERO_PRODUCT)
    }
    /// `p.x q.y - p.y q.x`, enclosed.
    #[inline(always)]
    fn cross(&self, p: &Rel<A::F>, q: &Rel<A::F>) -> Iv<A::F> {
        self.sub(&self.mul(&p[0], &q[1]), &self.mul(&p[1], &q[0]))
    }
}

/// What `gdam2010-safe` computes once per sample position `(X, Y)`: the vertices
/// relative to the pixel at both shutter ends (`a`, `b`: one fused multiply-add per
/// coordinate; `ai`, `bi`: enclosed), the motion of each (`di`; exactly 0 for a vertex
/// whose three inputs are equal at both ends), each edge's pad, and whether no vertex
/// moves (`still`).
#[derive(Clone, Debug)]
pub struct SampleOf<F, B> {
    pub a: [[F; 2]; 3],
    pub b: [[F; 2]; 3],
    ai: [Rel<F>; 3],
    bi: [Rel<F>; 3],
    di: [Rel<F>; 3],
    pub pad: [F; 3],
    still: B,
}

/// Why any f32 value is a valid pad: a piece is culled only when its Bernstein
/// coefficients clear it, so the pad only moves culls inward (the code also tests
/// `0 <= pad`, so that the culls imply the unpadded ones).
pub const PAD_CHOICE: &str = "gdam2010-safe pad: any value >= 0 only shrinks the culled set (it is there for the \
     judge's certificates)";

/// The per-sample setup over any [`F32Arith`]: `q`, `r` the vertices' `(x, y, w)` at
/// t = 0 and t = 1, `(x, y)` the sample position; `padded` false gives every pad 0
/// (the code before the pad, for the tests).
pub fn sample_of<R: Round, A: F32Arith>(
    ar: &A,
    q: &[[A::F; 3]; 3],
    r: &[[A::F; 3]; 3],
    x: &A::F,
    y: &A::F,
    padded: bool,
) -> SampleOf<A::F, A::B> {
    let o = IvOps::<A, R>::new(ar);
    let (nx, ny) = (ar.neg(x), ar.neg(y));
    // The vertices relative to the pixel at both shutter ends: one fused
    // multiply-add (one rounding) per coordinate, then one step outward.
    let rel = |p: &[A::F; 3]| [ar.fma(&nx, &p[2], &p[0]), ar.fma(&ny, &p[2], &p[1])];
    let (a, b) = (q.each_ref().map(rel), r.each_ref().map(rel));
    let pad = if padded {
        edge_pads(ar, q, r, x, y, &a, &b).map(|p| ar.choose(&p, PAD_CHOICE))
    } else {
        [0, 1, 2].map(|_| ar.lit(0.0))
    };
    let ai = a.each_ref().map(|p| p.each_ref().map(|v| o.near(v)));
    let bi = b.each_ref().map(|p| p.each_ref().map(|v| o.near(v)));
    // The motion of each, exactly 0 for a vertex that does not move.
    let still_v: [A::B; 3] = std::array::from_fn(|i| ar.all(&[0, 1, 2].map(|c| ar.eq(&q[i][c], &r[i][c]))));
    let di: [Rel<A::F>; 3] = std::array::from_fn(|i| {
        let moved = [o.sub(&bi[i][0], &ai[i][0]), o.sub(&bi[i][1], &ai[i][1])];
        [0, 1].map(|c| o.same(&still_v[i], &o.zero(), &moved[c], STILL))
    });
    let still = ar.all(&still_v);
    SampleOf { a, b, ai, bi, di, pad, still }
}

/// One end `t` of a piece of the shutter: the vertices relative to the pixel there
/// (enclosed) and each edge's value, `P_i(t) x P_j(t)`.
#[derive(Clone, Debug)]
pub struct EndOf<F> {
    p: [Rel<F>; 3],
    e: [Iv<F>; 3],
}

/// The vertices and each edge's value at the end `t` (an f32 in [0, 1]) of a piece:
/// `A_i` at 0, `B_i` at 1, `A_i + t (B_i - A_i)` between, enclosed.
pub fn end_of<R: Round, A: F32Arith>(ar: &A, s: &SampleOf<A::F, A::B>, t: &A::F) -> EndOf<A::F> {
    let o = IvOps::<A, R>::new(ar);
    let (at0, at1) = (ar.eq(t, &ar.lit(0.0)), ar.eq(t, &ar.lit(1.0)));
    let tt = [t.clone(), t.clone()];
    let p: [Rel<A::F>; 3] = std::array::from_fn(|i| {
        let mid = [o.add(&s.ai[i][0], &o.mul(&tt, &s.di[i][0])), o.add(&s.ai[i][1], &o.mul(&tt, &s.di[i][1]))];
        std::array::from_fn(|c| o.same(&at0, &s.ai[i][c], &o.same(&at1, &s.bi[i][c], &mid[c], AT_ONE), AT_ZERO))
    });
    let e = EDGES.map(|(i, j)| o.cross(&p[i], &p[j]));
    EndOf { p, e }
}

/// The four tests of one edge on a piece from its (enclosed) Bernstein coefficients `b`
/// (the middle one doubled: only signs, and the pad, matter) and its pad: every `b <=
/// -pad` (no value > 0 on the piece), every `b >= pad` (none < 0), every `b > 0`, every
/// `b < 0`. The first two also test `0 <= pad`.
fn edge_tests<A: F32Arith>(ar: &A, b: &[Iv<A::F>; 3], pad: &A::F) -> [A::B; 4] {
    let zero = ar.lit(0.0);
    let (ok, np) = (ar.le(&zero, pad), ar.neg(pad));
    let le = ar.all(&[ok.clone(), ar.le(&b[0][1], &np), ar.le(&b[1][1], &np), ar.le(&b[2][1], &np)]);
    let ge = ar.all(&[ok, ar.le(pad, &b[0][0]), ar.le(pad, &b[1][0]), ar.le(pad, &b[2][0])]);
    let gt = ar.all(&b.each_ref().map(|v| ar.lt(&zero, &v[0])));
    let lt = ar.all(&b.each_ref().map(|v| ar.lt(&v[1], &zero)));
    [le, ge, gt, lt]
}

/// A piece's answer from its edges' tests: culled (certified: no t in it is covered)
/// when some edge is `<= 0` and some edge `>= 0` throughout; covered when every edge is
/// `> 0`, or every edge `< 0`, throughout.
fn answer_of<A: F32Arith>(ar: &A, tests: &[[A::B; 4]; 3]) -> (A::B, A::B) {
    let col = |k: usize| tests.each_ref().map(|t| t[k].clone());
    let culled = ar.and(&ar.any(&col(0)), &ar.any(&col(1)));
    let covered = ar.or(&ar.all(&col(2)), &ar.all(&col(3)));
    (culled, covered)
}

/// The piece between `l` and `h` (the values at its two ends): each edge is the cross
/// product of two vertices linear in t, so on the piece it is a quadratic with Bernstein
/// coefficients `P_i(l) x P_j(l)`, `(P_i(l) x P_j(h) + P_i(h) x P_j(l)) / 2`,
/// `P_i(h) x P_j(h)`, and its values lie between the least and the greatest of them.
/// Returns (culled, covered).
pub fn piece_of<R: Round, A: F32Arith>(
    ar: &A,
    s: &SampleOf<A::F, A::B>,
    l: &EndOf<A::F>,
    h: &EndOf<A::F>,
) -> (A::B, A::B) {
    let o = IvOps::<A, R>::new(ar);
    let (pl, ph) = (&l.p, &h.p);
    let zero = ar.lit(0.0);
    let tests: [[A::B; 4]; 3] = std::array::from_fn(|k| {
        let (i, j) = EDGES[k];
        let ends = [&l.e[k], &h.e[k]];
        // Each test needs the ends <= 0 or the ends >= 0: only then does the middle
        // coefficient matter (a conjunction with a test it implies: the same truth).
        let le = ar.and(&ar.le(&ends[0][1], &zero), &ar.le(&ends[1][1], &zero));
        let ge = ar.and(&ar.le(&zero, &ends[0][0]), &ar.le(&zero, &ends[1][0]));
        ar.and_each(&ar.or(&le, &ge), || {
            let mid = o.add(&o.cross(&pl[i], &ph[j]), &o.cross(&ph[i], &pl[j]));
            edge_tests(ar, &[l.e[k].clone(), mid, h.e[k].clone()], &s.pad[k])
        })
    });
    answer_of(ar, &tests)
}

/// [`piece_of`] for the whole shutter of a triangle none of whose vertices moves
/// (their inputs equal at both ends, a condition of the cull): each edge's value is the
/// same at every t, so its Bernstein coefficients are its value at 0 and that value
/// doubled. Returns (culled, covered).
pub fn still_of<R: Round, A: F32Arith>(ar: &A, s: &SampleOf<A::F, A::B>, e: &EndOf<A::F>) -> (A::B, A::B) {
    let o = IvOps::<A, R>::new(ar);
    let tests: [[A::B; 4]; 3] = std::array::from_fn(|k| {
        let v = &e.e[k];
        edge_tests(ar, &[v.clone(), o.add(v, v), v.clone()], &s.pad[k])
    });
    let (culled, covered) = answer_of(ar, &tests);
    (ar.and(&s.still, &culled), covered)
}

/// `p.x q.y - p.y q.x` in f32 (round to nearest: a guess for the cut points only).
fn cross2(p: [f32; 2], q: [f32; 2]) -> f32 {
    p[0] * q[1] - p[1] * q[0]
}

/// The pad of a culling test: this share of the square of the edge's size relative to
/// the pixel (module doc, "The pad").
const PAD_REL: f32 = 1.0 / 67_108_864.0; // 2^-26
/// ... plus this share of the square of the size of its terms in screen coordinates.
const PAD_ABS: f32 = 1.0 / 4_503_599_627_370_496.0; // 2^-52

/// Each edge's pad at pixel `(x, y)`, in f32: `PAD_REL (m_i + m_j)^2 +
/// PAD_ABS (n_i + n_j)^2 + 2^-126` with `m_i = |a_i.x| + |a_i.y| + |b_i.x - a_i.x| +
/// |b_i.y - a_i.y|` from the vertices relative to the pixel at both shutter ends (`a`
/// at t = 0, `b` at t = 1) and `n_i = |x_i| + |y_i|` at both ends `+ (|w_i| at both
/// ends) (|x| + |y|)`. A piece is culled for an edge only when its enclosures clear
/// the pad (module doc). NaN (from overflow) culls nothing.
fn edge_pads<A: F32Arith>(
    ar: &A,
    q: &[[A::F; 3]; 3],
    r: &[[A::F; 3]; 3],
    x: &A::F,
    y: &A::F,
    a: &[[A::F; 2]; 3],
    b: &[[A::F; 2]; 3],
) -> [A::F; 3] {
    let sum = |v: &[A::F]| v[1..].iter().fold(v[0].clone(), |acc, x| ar.add(&acc, x));
    let abs = |v: &A::F| ar.abs(v);
    let m: [A::F; 3] = std::array::from_fn(|i| {
        let (a, b) = (&a[i], &b[i]);
        sum(&[abs(&a[0]), abs(&a[1]), abs(&ar.sub(&b[0], &a[0])), abs(&ar.sub(&b[1], &a[1]))])
    });
    let xy = ar.add(&abs(x), &abs(y));
    let n: [A::F; 3] = std::array::from_fn(|i| {
        let w = ar.mul(&ar.add(&abs(&q[i][2]), &abs(&r[i][2])), &xy);
        sum(&[abs(&q[i][0]), abs(&q[i][1]), abs(&r[i][0]), abs(&r[i][1]), w])
    });
    EDGES.map(|(i, j)| {
        let (s, u) = (ar.add(&m[i], &m[j]), ar.add(&n[i], &n[j]));
        let rel = ar.mul(&ar.mul(&ar.lit(PAD_REL), &s), &s);
        let abs_part = ar.mul(&ar.mul(&ar.lit(PAD_ABS), &u), &u);
        ar.add(&ar.add(&rel, &abs_part), &ar.lit(f32::MIN_POSITIVE))
    })
}

/// One edge's exact value as a polynomial in the sample's pixel position `(X, Y)` and
/// time `t`: `E = g(X, Y) + b(X, Y) t + a(X, Y) t^2`, each coefficient affine in X and
/// Y (the `X Y` terms cancel exactly), enclosed in outward-rounded f64: `c[0..3]` the
/// constant, X and Y parts of g, `c[3..6]` of b, `c[6..9]` of a (module doc, "What the
/// gate can prove").
#[derive(Clone, Copy, Debug)]
struct EdgePoly {
    c: [Interval; 9],
    /// The vertices' `(x, y, w)` at t = 0 and their motion, enclosed.
    p: [[Interval; 3]; 2],
    d: [[Interval; 3]; 2],
    /// Per vertex, `|x| + |y|` at both ends and `|w|` at both ends (exact reals rounded
    /// down: the screen-size part of the pad's floor).
    n: [[f64; 2]; 2],
}

impl EdgePoly {
    fn new(q: [[f32; 3]; 3], r: [[f32; 3]; 3], i: usize, j: usize) -> Self {
        let pt = |v: f32| Interval::point(v as f64);
        let p = [q[i].map(pt), q[j].map(pt)];
        let d: [[Interval; 3]; 2] = [i, j]
            .map(|v| std::array::from_fn(|c| if q[v][c] == r[v][c] { pt(0.0) } else { pt(r[v][c]) - pt(q[v][c]) }));
        let ([xi, yi, wi], [xj, yj, wj]) = (p[0], p[1]);
        let ([dxi, dyi, dwi], [dxj, dyj, dwj]) = (d[0], d[1]);
        let c = [
            xi * yj - yi * xj,
            wj * yi - wi * yj,
            wi * xj - wj * xi,
            xi * dyj + dxi * yj - yi * dxj - dyi * xj,
            yi * dwj + dyi * wj - wi * dyj - dwi * yj,
            wi * dxj + dwi * xj - xi * dwj - dxi * wj,
            dxi * dyj - dyi * dxj,
            dyi * dwj - dwi * dyj,
            dwi * dxj - dxi * dwj,
        ];
        let n = [i, j].map(|v| {
            let sum = |a: f32, b: f32, c: f32, d: f32| {
                ((a.abs() as f64 + b.abs() as f64 + c.abs() as f64 + d.abs() as f64) * (1.0 - 2f64.powi(-50))).max(0.0)
            };
            [sum(q[v][0], q[v][1], r[v][0], r[v][1]), sum(q[v][2], r[v][2], 0.0, 0.0)]
        });
        EdgePoly { c, p, d, n }
    }

    /// The three coefficients over the pixel box.
    fn coefs(&self, x: Interval, y: Interval) -> [Interval; 3] {
        let c = &self.c;
        [0, 3, 6].map(|k| c[k] + c[k + 1] * x + c[k + 2] * y)
    }

    /// The edge's value over the box, enclosed: the better of the polynomial form and
    /// the cross product of the vertices relative to the pixel (both enclose it).
    fn range(&self, x: Interval, y: Interval, t: Interval) -> Interval {
        let [g, b, a] = self.coefs(x, y);
        let poly = g + b * t + a * (t * t);
        let rel = |v: usize| {
            let (p, d) = (self.p[v], self.d[v]);
            let w = p[2] + d[2] * t;
            [p[0] + d[0] * t - x * w, p[1] + d[1] * t - y * w]
        };
        let (pi, pj) = (rel(0), rel(1));
        let cross = pi[0] * pj[1] - pi[1] * pj[0];
        let (lo, hi) = (poly.lo.max(cross.lo), poly.hi.min(cross.hi));
        if lo <= hi {
            Interval::new(lo, hi)
        } else {
            poly
        }
    }

    /// A lower bound of this edge's [`edge_pads`] value at every f32 pixel of the box
    /// (the `|a|` terms of `m` only, every rounding taken against it; at least 2^-126).
    fn pad_floor(&self, x: Interval, y: Interval) -> f64 {
        let mig = |i: Interval| {
            if i.lo > 0.0 {
                i.lo
            } else if i.hi < 0.0 {
                -i.hi
            } else {
                0.0
            }
        };
        let m = |v: usize| {
            let p = self.p[v];
            let (ax, ay) = (p[0] - x * p[2], p[1] - y * p[2]);
            mig(ax) + mig(ay)
        };
        let xy = mig(x) + mig(y);
        let n = |v: usize| self.n[v][0] + self.n[v][1] * xy;
        let shrink = |v: f64| (v * (1.0 - 2f64.powi(-20)) - 2f64.powi(-140)).max(0.0);
        let (s, u) = (shrink(m(0) + m(1)), shrink(n(0) + n(1)));
        let v = shrink(PAD_REL as f64 * s * s) + shrink(PAD_ABS as f64 * u * u);
        let v = v * (1.0 - 2f64.powi(-40));
        if v.is_nan() {
            2f64.powi(-126)
        } else {
            v.max(2f64.powi(-126))
        }
    }
}

/// How the edges stand over a box, for [`SafeTimeSpans::eval_box`] and the cut: each
/// edge's value enclosed and its pad's floor there.
fn edge_ranges(polys: &[EdgePoly; 3], b: &SampleBox) -> ([Interval; 3], [f64; 3]) {
    (polys.map(|p| p.range(b.x, b.y, b.t)), polys.map(|p| p.pad_floor(b.x, b.y)))
}

/// The per-sample constraint of `gdam2010-safe` with the rounding discipline `R`: a
/// certified superset of the covered time set (module doc, "`gdam2010-safe`").
pub struct SafeSpans<R> {
    /// `(x, y, w)` of each vertex at t = 0 and t = 1.
    q: [[f32; 3]; 3],
    r: [[f32; 3]; 3],
    /// Per edge, the exact coefficients of its value as a polynomial in the sample's
    /// pixel position and time, enclosed (for the box enclosures and cuts only).
    poly: [EdgePoly; 3],
    round: PhantomData<fn() -> R>,
}

/// `gdam2010-safe`'s per-sample constraint.
pub type SafeTimeSpans = SafeSpans<Outward>;

impl<R> Clone for SafeSpans<R> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<R> Copy for SafeSpans<R> {}
/// Printed as the constraint's type name, `SafeTimeSpans`, for every rounding discipline.
impl<R> std::fmt::Debug for SafeSpans<R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SafeTimeSpans").field("q", &self.q).field("r", &self.r).finish_non_exhaustive()
    }
}

/// Edges as vertex pairs (k, (i, j)), as in [`TimeSpans`].
const EDGES: [(usize, usize); 3] = [(1, 2), (2, 0), (0, 1)];
/// Pieces narrower than this are kept when open rather than split (t units).
const MIN_SPLIT: f32 = 1.0 / 4096.0;
/// Splits of open pieces per sample.
const SPLITS: usize = 12;

impl<R: Round> SafeSpans<R> {
    /// The constraint of a triangle (its vertices' `(x, y, w)` at both shutter ends;
    /// the CoC is not read).
    pub fn new(tri: &Triangle) -> Self {
        let xyw = |p: [f32; 4]| [p[0], p[1], p[3]];
        let (q, r) = (tri.q.map(xyw), tri.r.map(xyw));
        SafeSpans { q, r, poly: EDGES.map(|(i, j)| EdgePoly::new(q, r, i, j)), round: PhantomData }
    }

    /// A superset of the covered time set at pixel position (x, y), in f32: closed
    /// intervals whose complement in [0, 1] is certified uncovered.
    pub fn spans_at(&self, x: f32, y: f32) -> Spans {
        self.spans_with(x, y, true)
    }

    /// [`spans_at`](Self::spans_at), and without the pad (`padded` false) the time set
    /// of the code before the pad, which the tests compare with its old text.
    pub(super) fn spans_with(&self, x: f32, y: f32, padded: bool) -> Spans {
        let mut out = Spans { n: 0, s: [[0.0; 2]; 8] };
        if !(x.is_finite() && y.is_finite()) {
            out.n = 1;
            out.s[0] = [0.0, 1.0];
            return out;
        }
        let ar = &Plain;
        let s = sample_of::<R, Plain>(ar, &self.q, &self.r, &x, &y, padded);
        if self.fixed() {
            // No vertex moves: every vertex is `ai` at every t (`bi` is the same bits and
            // the motion is exactly 0), so there is one cut piece, [0, 1], whose two ends
            // are the same and whose middle coefficients are each edge's value doubled.
            // Culled, nothing is kept; covered, or open and split into pieces that are
            // all open, [0, 1] is kept.
            let e = end_of::<R, Plain>(ar, &s, &0.0);
            if !still_of::<R, Plain>(ar, &s, &e).0 {
                out.n = 1;
                out.s[0] = [0.0, 1.0];
            }
            return out;
        }
        let mut buf = [0.0f32; MAX_CUTS];
        let n = self.cuts(s.a, s.b, s.pad, &mut buf);
        let cuts = &buf[..n];
        // Classify each piece between consecutive cuts (splitting open ones while the
        // budget lasts), left to right; keep all but the certified-uncovered pieces. The
        // next piece starts where the last one started (after a split) or ended: both
        // ends of the last piece are kept, so each end is evaluated once.
        let mut stack = [(0.0f32, 0.0f32); MAX_CUTS + SPLITS];
        let mut top = 0;
        for w in cuts.windows(2).rev() {
            stack[top] = (w[0], w[1]);
            top += 1;
        }
        let mut splits = SPLITS;
        let mut last: Option<([f32; 2], [EndOf<f32>; 2])> = None;
        while top > 0 {
            top -= 1;
            let (l, h) = stack[top];
            let same = |u: f32, t: f32| u.to_bits() == t.to_bits();
            let el = match &last {
                Some((t, e)) if same(t[0], l) => e[0].clone(),
                Some((t, e)) if same(t[1], l) => e[1].clone(),
                _ => end_of::<R, Plain>(ar, &s, &l),
            };
            let eh = end_of::<R, Plain>(ar, &s, &h);
            let (culled, covered) = piece_of::<R, Plain>(ar, &s, &el, &eh);
            last = Some(([l, h], [el, eh]));
            let open = !culled && !covered;
            if open && splits > 0 && h - l > MIN_SPLIT {
                let m = l + 0.5 * (h - l);
                if m > l && m < h {
                    splits -= 1;
                    stack[top] = (m, h);
                    stack[top + 1] = (l, m);
                    top += 2;
                    continue;
                }
            }
            if culled {
                continue;
            }
            if out.n > 0 && out.s[out.n - 1][1] >= l {
                out.s[out.n - 1][1] = h;
            } else if out.n == out.s.len() {
                out.s[out.n - 1][1] = h; // full: keep the gap too (conservative)
            } else {
                out.s[out.n] = [l, h];
                out.n += 1;
            }
        }
        out
    }

    /// The cut points, sorted, from 0 to 1, written to the front of `out` (their number
    /// returned): around each edge's roots and the vertex of its parabola, computed in
    /// f32 from the rounded relative vertices (`a` at t = 0, `b` at t = 1). They only
    /// decide where pieces end: any cut points give a superset.
    fn cuts(&self, a: [[f32; 2]; 3], b: [[f32; 2]; 3], pad: [f32; 3], out: &mut [f32; MAX_CUTS]) -> usize {
        out[0] = 0.0;
        out[1] = 1.0;
        let mut n = 2;
        let mut put = |c: f32| {
            // Only the cuts within [0, 1] are kept (NaN is not).
            if (0.0..=1.0).contains(&c) {
                out[n] = c;
                n += 1;
            }
        };
        let d: [[f32; 2]; 3] = std::array::from_fn(|i| [b[i][0] - a[i][0], b[i][1] - a[i][1]]);
        for (k, (i, j)) in EDGES.into_iter().enumerate() {
            let alpha = cross2(d[i], d[j]);
            let beta = cross2(a[i], d[j]) + cross2(d[i], a[j]);
            let gamma = cross2(a[i], a[j]);
            // Error scale of the edge's values: a few ulps of its terms.
            let mag = |p: [f32; 2], q: [f32; 2]| p[0].abs() + p[1].abs() + q[0].abs() + q[1].abs();
            // (and twice the pad: a piece is culled for the edge only beyond it)
            let err = 2f32.powi(-21) * mag(a[i], d[i]) * mag(a[j], d[j]) + f32::MIN_POSITIVE + 2.0 * pad[k];
            let mut roots = [0.0f32; 8];
            let mut nr = 0;
            roots_in_unit(alpha, beta, gamma, &mut roots, &mut nr);
            for &r in &roots[..nr] {
                let slope = (2.0 * alpha * r + beta).abs();
                let delta = (err / slope).min(0.5) + 2f32.powi(-21);
                for c in [r - delta, r - delta / 16.0, r + delta / 16.0, r + delta] {
                    put(c);
                }
            }
            if alpha != 0.0 {
                let tv = -beta / (2.0 * alpha);
                if tv > 0.0 && tv < 1.0 {
                    let delta = (err / alpha.abs()).sqrt().min(0.5) + 2f32.powi(-21);
                    for c in [tv - delta, tv - delta / 16.0, tv, tv + delta / 16.0, tv + delta] {
                        put(c);
                    }
                }
            }
        }
        // A stable sort, then the first of each run of equal values kept (as
        // `Vec::dedup`: -0 and 0 are equal, the first one stays).
        let cuts = &mut out[..n];
        cuts.sort_by(|p, q| p.partial_cmp(q).unwrap());
        let mut k = 1;
        for i in 1..n {
            if cuts[i] != cuts[k - 1] {
                cuts[k] = cuts[i];
                k += 1;
            }
        }
        k
    }
}

impl<R: Round> SafeSpans<R> {
    /// True when no vertex moves (each the same f32 bits at both shutter ends) and every
    /// input is finite.
    fn fixed(&self) -> bool {
        let bits = |p: &[f32; 3]| p.map(f32::to_bits);
        (0..3).all(|i| bits(&self.q[i]) == bits(&self.r[i]) && self.q[i].iter().all(|v| v.is_finite()))
    }
}

/// At most this many cut points: 0, 1, and per edge 4 around each of 2 roots and 5
/// around its parabola's vertex.
const MAX_CUTS: usize = 2 + 3 * (2 * 4 + 5);

impl<R: Round> SampleConstraint for SafeSpans<R> {
    fn name(&self) -> String {
        "gdam2010-safe covered time set at the sample's (x, y)".to_string()
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
    /// At a single f32 pixel, the time set recomputed (as for `gdam2010`); over a wider
    /// box, `>= 0` when every edge stays above the floor of minus half its pad (or every
    /// one below half its pad) throughout the box, within [0, 1] in t: then no piece is
    /// culled at any of its samples, the kept set is all of [0, 1] and `g = min(t, 1 - t)`
    /// (module doc, "What the gate can prove"); otherwise the generic range.
    fn eval_box(&self, b: &SampleBox) -> Interval {
        let g = spans_eval_box(|x, y| self.spans_at(x, y), b);
        if f32_point(b.x).is_some() && f32_point(b.y).is_some() {
            return g;
        }
        if !(b.t.lo >= 0.0 && b.t.hi <= 1.0) {
            return g;
        }
        let (e, pad) = edge_ranges(&self.poly, b);
        let above = (0..3).all(|k| e[k].lo > -0.5 * pad[k]);
        let below = (0..3).all(|k| e[k].hi < 0.5 * pad[k]);
        if above || below {
            Interval::new(0.0, g.hi.max(0.0))
        } else {
            g
        }
    }
    /// Where the edges that are not certified above minus half their pads over the box
    /// (or below half, for the other orientation) each get a cut `sigma E_k + pad_k / 4`
    /// (exact coefficients, quadratic in t, their rounding in `err`): where every cut is
    /// `>= err`, every edge is above minus half its pad (below half), so no piece is
    /// culled (module doc, "What the gate can prove"). Each orientation `sigma` gives a
    /// family, tagged with the side of D whose interior samples have `sigma E_k > 0`.
    fn lower_cuts(&self, b: &SampleBox, out: &mut Vec<Cut>) -> bool {
        if !(b.t.lo >= 0.0 && b.t.hi <= 1.0) {
            return false;
        }
        let (e, pad) = edge_ranges(&self.poly, b);
        let safe = |sigma: f64, j: usize| if sigma > 0.0 { e[j].lo > -0.5 * pad[j] } else { e[j].hi < 0.5 * pad[j] };
        // One family of cuts per side of D, each tagged with its side: the judge
        // certifies a family only against the interior samples of its side (where its
        // own enclosure of D has one sign, the other family is never needed).
        let families: &[(f64, i8)] = &[(1.0, 1), (-1.0, -1)];
        let start = out.len();
        for &(sigma, tag) in families {
            for (k, (poly, &pad)) in self.poly.iter().zip(&pad).enumerate() {
                if safe(sigma, k) {
                    continue;
                }
                match edge_cut(poly, sigma, pad, b) {
                    Some(mut c) => {
                        c.d_sign = tag;
                        out.push(c)
                    }
                    None => {
                        out.truncate(start);
                        return false;
                    }
                }
            }
        }
        true
    }
}

/// The cut of [`SafeTimeSpans::lower_cuts`] for one edge and orientation: the exact
/// `sigma E + pad / 4`, its coefficients rounded to f64 and that rounding (times the
/// largest value of each monomial over the box) in `err`.
fn edge_cut(p: &EdgePoly, sigma: f64, pad: f64, b: &SampleBox) -> Option<Cut> {
    let pt = Interval::point;
    let s = pt(sigma);
    let c = &p.c;
    // (monomial, in t^2?, coefficient)
    let coefs: [(usize, bool, Interval); 9] = [
        (0, false, s * c[0] + pt(0.25 * pad)),
        (Cut::X, false, s * c[1]),
        (Cut::Y, false, s * c[2]),
        (Cut::T, false, s * c[3]),
        (Cut::X | Cut::T, false, s * c[4]),
        (Cut::Y | Cut::T, false, s * c[5]),
        (0, true, s * c[6]),
        (Cut::X, true, s * c[7]),
        (Cut::Y, true, s * c[8]),
    ];
    let mag = |i: Interval| i.lo.abs().max(i.hi.abs());
    let (mx, my, mt) = (mag(b.x), mag(b.y), mag(b.t));
    let mono = |m: usize, sq: bool| {
        let mut v = 1.0f64;
        if m & Cut::X != 0 {
            v = (v * mx).next_up();
        }
        if m & Cut::Y != 0 {
            v = (v * my).next_up();
        }
        if m & Cut::T != 0 {
            v = (v * mt).next_up();
        }
        if sq {
            v = ((v * mt).next_up() * mt).next_up();
        }
        v
    };
    let mut cut = Cut::zero();
    let mut err = 0.0f64;
    for (m, sq, iv) in coefs {
        let v = iv.mid();
        if sq {
            cut.t2[m] = v;
        } else {
            cut.coef[m] = v;
        }
        let off = (v - iv.lo).max(iv.hi - v).next_up();
        err = (err + (off * mono(m, sq)).next_up()).next_up();
    }
    cut.err = err;
    let finite = cut.err.is_finite() && cut.coef.iter().chain(cut.t2.iter()).all(|c| c.is_finite());
    finite.then_some(cut)
}

/// `gdam2010-safe` with the rounding discipline `R` (the planted slips use another).
pub struct Gdam2010Safe<R> {
    pub info: &'static MethodInfo,
    pub round: PhantomData<fn() -> R>,
}

static INFO_SAFE: MethodInfo = MethodInfo {
    id: "gdam2010-safe",
    source: "Gribel, Doggett, Akenine-Möller 2010, Analytical Motion Blur Rasterization with Compression \
             (cited by Nilsson et al. 2012 §2, §4); quadratic moving edge functions of Munkberg et al. 2011 \
             (as restated in docs/reconstructions.md); every culled time piece certified by outward-rounded \
             Bernstein enclosures of the edge functions (derivation in this file)",
    ..INFO
};

impl<R: Round> Method for Gdam2010Safe<R> {
    fn info(&self) -> &'static MethodInfo {
        self.info
    }
    fn setup(&self, tri: &Triangle) -> Box<dyn Prepared> {
        let finite = tri.q.iter().chain(tri.r.iter()).flatten().all(|v| v.is_finite());
        // (a NaN CoC counts as defocus: NaN != 0)
        let (spans, why) = if defocused(tri) {
            (None, "defocus: gdam2010 is motion-only")
        } else if !finite {
            (None, "non-finite triangle data")
        } else {
            (Some(SafeSpans::<R>::new(tri)), "")
        };
        Box::new(Prep { spans, why })
    }
}

/// `gdam2010-safe`: a certified superset of the covered time set (see the module doc).
pub static METHOD_SAFE: &dyn Method = &Gdam2010Safe::<Outward> { info: &INFO_SAFE, round: PhantomData };
