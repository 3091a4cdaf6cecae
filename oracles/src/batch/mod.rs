//! Exact coverage of many samples of one triangle, side by side in lanes.
//!
//! [`Batch::new`] precomputes, once per triangle, the coefficients of the coverage
//! values as polynomials in the sample coordinates, in the form the triangle's regime
//! needs and no more:
//! - **static** (no motion, no defocus): each edge value is linear in the pixel,
//!   `E_k = A_k + B_k x + C_k y`, and the determinant `D` is a constant whose exact sign
//!   is computed once (certified in floating point by the bounds below, else in dyadic
//!   arithmetic);
//! - **defocus**, **motion**, **both**: the sheared vertex of [`crate::coverage`]
//!   `P_i = (a_i(t) + u g_i(t) - x w_i(t),  b_i(t) + k v g_i(t) - y w_i(t),  w_i(t))`
//!   with `a_i, b_i, w_i, g_i` either constants (no motion) or `q + t (r - q)` with the
//!   slope `r - q` precomputed, and `g_i` absent without a lens. The edge values are
//!   `E_k = P_i.x P_j.y - P_i.y P_j.x` and `D = w_0 E_0 + w_1 E_1 + w_2 E_2` (the
//!   expansion of the determinant along its w column, which the translation by the pixel
//!   does not change).
//!
//! Samples are taken [`LANES`] at a time, each coordinate in its own array, and the
//! values are computed lane by lane in plain `f64` (the compiler turns the lane loops
//! into vector instructions). A lane's class is taken from this fast evaluation only
//! when every sign it needs is certified; every other lane (and every sample of a
//! block holding a number that is not finite, and every sample of a triangle that is
//! not finite) goes to [`crate::coverage::classify_traced`], the scalar oracle with its
//! exact dyadic fallback. So the answer is the scalar oracle's for every sample.
//!
//! # The certified error bound (the soundness argument)
//!
//! One generic formula (`eval`, written with fused multiply-adds where they save an
//! operation) is evaluated in two rings. On lanes ([`Lanes`]) it is
//! plain round-to-nearest `f64`. In the bound ring ([`Mag`]) each quantity `z` carries
//! two numbers `(m, e)`, with the invariant, for every lane of a block of samples:
//! `|z^| <= m` and `|z^ - z| <= e`, where `z^` is the lane's computed value and `z`
//! the exact real value of the same formula at the same sample. With `u = 2^-53` and
//! `eta = 2^-1075` (the largest error of a rounding into the subnormal range), the
//! rules of round-to-nearest give, operation by operation:
//! - an exact number c (a coordinate of the triangle, the constant 1): `(|c|, 0)`; a
//!   sample coordinate: `(max over the block of |coordinate|, 0)`;
//! - `z = a +- b`: `|z^| <= (1 + u)(m_a + m_b)` and
//!   `|z^ - z| <= e_a + e_b + u (m_a + m_b)` (a sum that lands in the subnormal range is
//!   exact, so no eta);
//! - `z = a * b`: `|z^| <= (1 + u) m_a m_b + eta` and, since
//!   `a^ b^ - a b = a^ (b^ - b) + b (a^ - a)` with `|b| <= m_b + e_b`,
//!   `|z^ - z| <= m_a e_b + m_b e_a + e_a e_b + u m_a m_b + eta`;
//! - `z = a * b + c` rounded once (`f64::mul_add`, a fused multiply-add on every
//!   platform): `|z^| <= (1 + u)(m_a m_b + m_c) + eta` and
//!   `|z^ - z| <= m_a e_b + m_b e_a + e_a e_b + e_c + u (m_a m_b + m_c) + eta`;
//! - `z = -a` is exact: `(m_a, e_a)`.
//!
//! Coefficients precomputed per triangle ([`Cst`]) carry their value and an error bound
//! by the same rules with `m = |value|` (for a rounded result `|z^ - z| <= u |z^| +
//! eta`), and enter the bound ring as `(|value|, e)`.
//!
//! The bounds themselves are computed in floating point, which may round them down. So
//! every sum or product of the (nonnegative) bound terms is passed through
//! `up(x) = x * (1 + 2^-50) + 2^-1070` (two more round-to-nearest operations): if
//! `x >= r (1 - u) - eta` for the real result r >= 0 of the operation (true for a
//! rounded sum or product of nonnegative numbers), then
//! `up(x) >= ((r (1 - u) - eta)(1 + 8u)(1 - u) - eta + 2^-1070)(1 - u) >= r`, because
//! `(1 + 8u)(1 - u)^3 >= 1` and `2^-1070 = 32 eta` exceeds the two etas lost. By
//! induction every computed `(m, e)` is at least the real bound above: no rounding of
//! the bound arithmetic can make it too small, and nothing is left to a safety factor.
//!
//! A lane's value `v` then has a certified sign when `v > e` (positive) or `-v > e`
//! (negative); both tests are false when `v` or `e` is NaN, and an overflowed value or
//! bound never passes (an overflow in a lane makes its bound infinite too: the bound
//! ring is monotone and rounds up, so it overflows no later than the lane). The class
//! is then read off the certified signs exactly as the scalar oracle does: two
//! certified opposite signs among `E_0, E_1, E_2, D` make the sample outside, four
//! certified equal signs make it interior, and anything else (a value on or too close
//! to zero) defers the lane to the exact path. Boundary samples are never decided
//! here: they always have a zero value, which no bound excludes.
//!
//! The bound is a *static filter*: it is computed once per block of [`BLOCK`] samples
//! from the largest magnitudes of the block's coordinates, so the lanes pay only the
//! comparisons.

use crate::coverage::{classify_traced, Coverage};
use crate::dyadic::Dyadic;
use crate::ring::Ring;
use crate::tri::Tri;

/// Samples evaluated side by side.
pub const LANES: usize = 16;
/// Samples sharing one error bound (computed from their largest coordinates).
pub const BLOCK: usize = 256;

const U: f64 = 1.0 / 9007199254740992.0; // 2^-53
const ONE_2U: f64 = 1.0 + 2.0 * U; // 1 + 2^-52 >= 1 + u, exact
const UP_FACTOR: f64 = 1.0 + 8.0 * U; // 1 + 2^-50, exact
const UP_ADD: f64 = f64::from_bits(1 << 4); // 2^-1070
const ETA: f64 = f64::from_bits(1); // 2^-1074 >= eta

/// An upper bound of the real result r >= 0 of a sum or product of nonnegative numbers
/// whose rounded value is `x` (see the module documentation).
#[inline(always)]
fn up(x: f64) -> f64 {
    x * UP_FACTOR + UP_ADD
}

/// A bound on the magnitude `m` of a computed value and on its error `e`, valid for
/// every lane of a block (see the module documentation).
#[derive(Clone, Copy, Debug)]
pub struct Mag {
    pub m: f64,
    pub e: f64,
}

impl Mag {
    #[inline(always)]
    fn sum(&self, o: &Self) -> Self {
        let s = up(self.m + o.m);
        Mag { m: up(s * ONE_2U), e: up(up(self.e + o.e) + up(s * U)) }
    }
}

impl Ring for Mag {
    #[inline(always)]
    fn c(x: f64) -> Self {
        Mag { m: x.abs(), e: 0.0 }
    }
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        self.sum(o)
    }
    #[inline(always)]
    fn sub(&self, o: &Self) -> Self {
        self.sum(o)
    }
    #[inline(always)]
    fn mul(&self, o: &Self) -> Self {
        let p = up(self.m * o.m);
        let m = up(up(p * ONE_2U) + ETA);
        let cross = up(up(self.m * o.e) + up(o.m * self.e));
        let rest = up(up(self.e * o.e) + up(p * U));
        Mag { m, e: up(up(cross + rest) + ETA) }
    }
}

/// The lane arithmetic: the ring operations, plus the fused multiply-add `a * b + c`
/// (one rounding) and the negation (exact).
pub trait Fused: Ring {
    fn fma(&self, b: &Self, c: &Self) -> Self;
    fn neg(&self) -> Self;
}

impl Fused for Mag {
    #[inline(always)]
    fn fma(&self, b: &Self, c: &Self) -> Self {
        let s = up(up(self.m * b.m) + c.m);
        let m = up(up(s * ONE_2U) + ETA);
        let cross = up(up(self.m * b.e) + up(b.m * self.e));
        let rest = up(up(self.e * b.e) + up(s * U));
        Mag { m, e: up(up(up(cross + rest) + c.e) + ETA) }
    }
    #[inline(always)]
    fn neg(&self) -> Self {
        *self
    }
}

/// A coefficient computed once per triangle: its rounded value and a bound on its
/// error (the rules of [`Mag`] with `m = |v|`).
#[derive(Clone, Copy, Debug)]
pub struct Cst {
    pub v: f64,
    pub e: f64,
}

impl Cst {
    fn mag(&self) -> Mag {
        Mag { m: self.v.abs(), e: self.e }
    }
    fn lanes(&self) -> Lanes {
        Lanes([self.v; LANES])
    }
    #[inline]
    fn sum(v: f64, ea: f64, eb: f64) -> Self {
        Cst { v, e: up(up(ea + eb) + up(v.abs() * U)) }
    }
}

impl Ring for Cst {
    fn c(x: f64) -> Self {
        Cst { v: x, e: 0.0 }
    }
    fn add(&self, o: &Self) -> Self {
        Cst::sum(self.v + o.v, self.e, o.e)
    }
    fn sub(&self, o: &Self) -> Self {
        Cst::sum(self.v - o.v, self.e, o.e)
    }
    fn mul(&self, o: &Self) -> Self {
        let v = self.v * o.v;
        let cross = up(up(self.v.abs() * o.e) + up(o.v.abs() * self.e));
        let rest = up(up(self.e * o.e) + up(v.abs() * U));
        Cst { v, e: up(up(cross + rest) + ETA) }
    }
}

/// [`LANES`] values, one per sample, computed lane by lane in round-to-nearest `f64`.
#[derive(Clone, Copy, Debug)]
pub struct Lanes(pub [f64; LANES]);

// Index loops over the fixed-size lane arrays: the form the compiler vectorizes best.
#[allow(clippy::needless_range_loop)]
impl Ring for Lanes {
    #[inline(always)]
    fn c(x: f64) -> Self {
        Lanes([x; LANES])
    }
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        let mut r = [0.0; LANES];
        for l in 0..LANES {
            r[l] = self.0[l] + o.0[l];
        }
        Lanes(r)
    }
    #[inline(always)]
    fn sub(&self, o: &Self) -> Self {
        let mut r = [0.0; LANES];
        for l in 0..LANES {
            r[l] = self.0[l] - o.0[l];
        }
        Lanes(r)
    }
    #[inline(always)]
    fn mul(&self, o: &Self) -> Self {
        let mut r = [0.0; LANES];
        for l in 0..LANES {
            r[l] = self.0[l] * o.0[l];
        }
        Lanes(r)
    }
}

// Index loops over the fixed-size lane arrays: the form the compiler vectorizes best.
#[allow(clippy::needless_range_loop)]
impl Fused for Lanes {
    #[inline(always)]
    fn fma(&self, b: &Self, c: &Self) -> Self {
        let mut r = [0.0; LANES];
        for l in 0..LANES {
            r[l] = self.0[l].mul_add(b.0[l], c.0[l]);
        }
        Lanes(r)
    }
    #[inline(always)]
    fn neg(&self) -> Self {
        let mut r = [0.0; LANES];
        for l in 0..LANES {
            r[l] = -self.0[l];
        }
        Lanes(r)
    }
}

/// The sample coordinates `x, y, u, v, t`, in a ring.
type Coords<R> = [R; 5];

/// Coefficients of the static regime: `E_k = A_k + B_k x + C_k y`, and D's exact sign.
#[derive(Clone, Debug)]
struct Linear<R> {
    a: [R; 3],
    b: [R; 3],
    c: [R; 3],
    d: R,
}

impl Linear<Cst> {
    fn new(tri: &Tri, d_sign: i8) -> Self {
        let p = |i: usize, j: usize| Cst::c(tri.q[i][j]);
        let (mut a, mut b, mut c) = ([Cst::c(0.0); 3], [Cst::c(0.0); 3], [Cst::c(0.0); 3]);
        for (k, (i, j)) in [(1, 2), (2, 0), (0, 1)].into_iter().enumerate() {
            // (X_i - x w_i)(Y_j - y w_j) - (Y_i - y w_i)(X_j - x w_j); the xy terms cancel.
            a[k] = p(i, 0).mul(&p(j, 1)).sub(&p(i, 1).mul(&p(j, 0)));
            b[k] = p(i, 1).mul(&p(j, 3)).sub(&p(i, 3).mul(&p(j, 1)));
            c[k] = p(i, 3).mul(&p(j, 0)).sub(&p(i, 0).mul(&p(j, 3)));
        }
        Linear { a, b, c, d: Cst::c(d_sign as f64) }
    }
    fn map<R>(&self, f: impl Fn(&Cst) -> R) -> Linear<R> {
        Linear {
            a: self.a.each_ref().map(&f),
            b: self.b.each_ref().map(&f),
            c: self.c.each_ref().map(&f),
            d: f(&self.d),
        }
    }
}

impl<R: Fused> Linear<R> {
    #[inline(always)]
    fn eval(&self, s: &Coords<R>) -> [R; 4] {
        let e = |k: usize| self.c[k].fma(&s[1], &self.b[k].fma(&s[0], &self.a[k]));
        [e(0), e(1), e(2), self.d.clone()]
    }
}

/// Coefficients of the moving and/or defocused regimes, per vertex: the base values
/// `a, b, w, g` (x, y, w, circle of confusion at t = 0), their slopes over the shutter
/// (`r - q`, used only with MOTION), and `k` (used only with LENS).
#[derive(Clone, Debug)]
struct Direct<R> {
    base: [[R; 4]; 3],
    slope: [[R; 4]; 3],
    k: R,
}

impl Direct<Cst> {
    fn new(tri: &Tri) -> Self {
        let base = std::array::from_fn(|i| [tri.q[i][0], tri.q[i][1], tri.q[i][3], tri.c0[i]].map(Cst::c));
        let end: [[Cst; 4]; 3] =
            std::array::from_fn(|i| [tri.r[i][0], tri.r[i][1], tri.r[i][3], tri.c1[i]].map(Cst::c));
        let slope = std::array::from_fn(|i| std::array::from_fn(|j| end[i][j].sub(&base[i][j])));
        Direct { base, slope, k: Cst::c(tri.k) }
    }
    fn map<R>(&self, f: impl Fn(&Cst) -> R) -> Direct<R> {
        let m = |a: &[[Cst; 4]; 3]| a.each_ref().map(|r| r.each_ref().map(&f));
        Direct { base: m(&self.base), slope: m(&self.slope), k: f(&self.k) }
    }
}

impl<R: Fused> Direct<R> {
    /// Coordinate j of vertex i at the sample's time.
    #[inline(always)]
    fn at<const MOTION: bool>(&self, i: usize, j: usize, t: &R) -> R {
        if MOTION {
            t.fma(&self.slope[i][j], &self.base[i][j])
        } else {
            self.base[i][j].clone()
        }
    }

    /// Vertex i sheared to the sample's lens position and translated to its pixel:
    /// `(P_i.x, P_i.y, w_i)`.
    #[inline(always)]
    fn vertex<const MOTION: bool, const LENS: bool>(&self, i: usize, s: &Coords<R>, kv: &R, nxy: &[R; 2]) -> [R; 3] {
        let (u, t) = (&s[2], &s[4]);
        let (mut a, mut b, w) = (self.at::<MOTION>(i, 0, t), self.at::<MOTION>(i, 1, t), self.at::<MOTION>(i, 2, t));
        if LENS {
            let g = self.at::<MOTION>(i, 3, t);
            a = u.fma(&g, &a);
            b = kv.fma(&g, &b);
        }
        [nxy[0].fma(&w, &a), nxy[1].fma(&w, &b), w]
    }

    #[inline(always)]
    fn eval<const MOTION: bool, const LENS: bool>(&self, s: &Coords<R>) -> [R; 4] {
        let kv = self.k.mul(&s[3]);
        let nxy = [s[0].neg(), s[1].neg()];
        let p0 = self.vertex::<MOTION, LENS>(0, s, &kv, &nxy);
        let p1 = self.vertex::<MOTION, LENS>(1, s, &kv, &nxy);
        let p2 = self.vertex::<MOTION, LENS>(2, s, &kv, &nxy);
        let e0 = edge(&p1, &p2);
        let e1 = edge(&p2, &p0);
        let e2 = edge(&p0, &p1);
        let d = p0[2].fma(&e0, &p1[2].fma(&e1, &p2[2].mul(&e2)));
        [e0, e1, e2, d]
    }
}

/// The edge value `P_i.x P_j.y - P_i.y P_j.x`.
#[inline(always)]
fn edge<R: Fused>(pi: &[R; 3], pj: &[R; 3]) -> R {
    pi[0].fma(&pj[1], &pi[1].mul(&pj[0]).neg())
}

/// The triangle's regime, with its coefficients.
#[derive(Clone, Debug)]
enum Kind {
    /// A number of the triangle is not finite: every sample goes to the scalar oracle.
    NotFinite,
    Static(Linear<Cst>),
    /// Moving and/or defocused: (motion, lens, coefficients).
    Moving(bool, bool, Box<Direct<Cst>>),
}

/// The exact sign of D for a triangle that neither moves nor defocuses: certified in
/// floating point when its bound allows, else in dyadic arithmetic.
fn static_det_sign(tri: &Tri) -> i8 {
    let z = Cst::c(0.0);
    let d = crate::coverage::det_of(&crate::coverage::sheared(tri, &z, &z, &z));
    if d.v > d.e {
        1
    } else if -d.v > d.e {
        -1
    } else {
        let z = Dyadic::zero();
        crate::coverage::det_of(&crate::coverage::sheared(tri, &z, &z, &z)).signum()
    }
}

/// How a batch was decided.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BatchStats {
    pub samples: u64,
    /// Samples whose class the lanes could not certify (sent to the scalar oracle).
    pub deferred: u64,
    /// Deferred samples that needed the exact dyadic path.
    pub exact_fallbacks: u64,
}

impl BatchStats {
    pub fn merge(self, o: BatchStats) -> BatchStats {
        BatchStats {
            samples: self.samples + o.samples,
            deferred: self.deferred + o.deferred,
            exact_fallbacks: self.exact_fallbacks + o.exact_fallbacks,
        }
    }
}

/// One triangle, prepared for classifying many samples (see the module documentation).
#[derive(Clone, Debug)]
pub struct Batch {
    tri: Tri,
    kind: Kind,
}

/// Lane codes: what the certified signs say.
const INTERIOR: u8 = 0;
const OUTSIDE: u8 = 2;
const UNDECIDED: u8 = 3;

impl Batch {
    /// Precompute the coefficients of `tri` for its regime.
    pub fn new(tri: &Tri) -> Batch {
        let kind = if tri.check_finite().is_err() {
            Kind::NotFinite
        } else {
            let motion = tri.q != tri.r || tri.c0 != tri.c1;
            let lens = !tri.is_pinhole();
            if !motion && !lens {
                Kind::Static(Linear::new(tri, static_det_sign(tri)))
            } else {
                Kind::Moving(motion, lens, Box::new(Direct::new(tri)))
            }
        };
        Batch { tri: *tri, kind }
    }

    /// The triangle's regime: "static", "defocus", "motion", "both" or "not finite".
    pub fn regime(&self) -> &'static str {
        match self.kind {
            Kind::NotFinite => "not finite",
            Kind::Static(_) => "static",
            Kind::Moving(false, _, _) => "defocus",
            Kind::Moving(true, false, _) => "motion",
            Kind::Moving(true, true, _) => "both",
        }
    }

    /// Classify every sample `[x, y, u, v, t]`, in order, into `out` (cleared first):
    /// the same class as [`crate::coverage::classify`] gives each sample.
    pub fn classify(&self, samples: &[[f64; 5]], out: &mut Vec<Coverage>) -> BatchStats {
        out.clear();
        out.reserve(samples.len());
        let mut st = BatchStats { samples: samples.len() as u64, ..Default::default() };
        match &self.kind {
            Kind::NotFinite => {
                for &s in samples {
                    self.defer(s, out, &mut st);
                }
            }
            Kind::Static(c) => {
                let (lanes, mag) = (c.map(Cst::lanes), c.map(Cst::mag));
                self.run(samples, out, &mut st, |s| lanes.eval(s), |s| mag.eval(s));
            }
            Kind::Moving(motion, lens, c) => {
                let (lanes, mag) = (c.map(Cst::lanes), c.map(Cst::mag));
                macro_rules! go {
                    ($m:literal, $l:literal) => {
                        self.run(samples, out, &mut st, |s| lanes.eval::<$m, $l>(s), |s| mag.eval::<$m, $l>(s))
                    };
                }
                match (motion, lens) {
                    (false, _) => go!(false, true),
                    (true, false) => go!(true, false),
                    (true, true) => go!(true, true),
                }
            }
        }
        st
    }

    fn defer(&self, s: [f64; 5], out: &mut Vec<Coverage>, st: &mut BatchStats) {
        out.push(self.deferred(s, st));
    }

    /// The scalar oracle's class of a sample the lanes did not decide.
    fn deferred(&self, s: [f64; 5], st: &mut BatchStats) -> Coverage {
        let (c, exact) = classify_traced(&self.tri, s);
        st.deferred += 1;
        st.exact_fallbacks += exact as u64;
        c
    }

    /// Blocks of samples: one bound per block, then the lanes.
    #[inline(always)]
    fn run(
        &self,
        samples: &[[f64; 5]],
        out: &mut Vec<Coverage>,
        st: &mut BatchStats,
        lanes: impl Fn(&Coords<Lanes>) -> [Lanes; 4],
        bound: impl Fn(&Coords<Mag>) -> [Mag; 4],
    ) {
        // The block's coordinates, one array per coordinate (a short last chunk repeats
        // the block's first sample, which is already within the maxima).
        let mut soa = [[0.0f64; BLOCK]; 5];
        let lane = |soa: &[[f64; BLOCK]; 5], c: usize| -> Coords<Lanes> {
            std::array::from_fn(|j| Lanes(soa[j][c * LANES..][..LANES].try_into().unwrap()))
        };
        for block in samples.chunks(BLOCK) {
            let n = block.len();
            let chunks = n.div_ceil(LANES);
            for (j, col) in soa.iter_mut().enumerate() {
                let (head, pad) = col[..chunks * LANES].split_at_mut(n);
                for (d, smp) in head.iter_mut().zip(block) {
                    *d = smp[j];
                }
                pad.fill(block[0][j]);
            }
            let base = out.len();
            let Some(max) = block_maxima(&soa, chunks) else {
                for &smp in block {
                    self.defer(smp, out, st);
                }
                continue;
            };
            let b = bound(&max.map(|m| Mag { m, e: 0.0 })).map(|z| z.e);
            out.resize(base + n, Coverage::Outside);
            for c in 0..chunks {
                let codes = certified(&lanes(&lane(&soa, c)), &b);
                let m = LANES.min(n - c * LANES);
                let dst = &mut out[base + c * LANES..][..m];
                for l in 0..m {
                    dst[l] = if codes[l] == INTERIOR { Coverage::Interior } else { Coverage::Outside };
                }
                if codes[..m].contains(&UNDECIDED) {
                    for l in 0..m {
                        if codes[l] == UNDECIDED {
                            out[base + c * LANES + l] = self.deferred(block[c * LANES + l], st);
                        }
                    }
                }
            }
        }
    }
}

/// The largest magnitude of each coordinate over the first `chunks` lanes of a block,
/// or None when a coordinate is not finite (then the block goes to the scalar oracle,
/// which answers such samples).
#[inline(always)]
fn block_maxima(soa: &[[f64; BLOCK]; 5], chunks: usize) -> Option<[f64; 5]> {
    let mut max = [0.0f64; 5];
    for j in 0..5 {
        let (mut m, mut finite) = ([0.0f64; LANES], [0.0f64; LANES]);
        for c in 0..chunks {
            for l in 0..LANES {
                let x = soa[j][c * LANES + l];
                let a = x.abs();
                m[l] = if a > m[l] { a } else { m[l] };
                // 0 for a finite number, NaN for an infinite or NaN one; NaN sticks.
                finite[l] += x * 0.0;
            }
        }
        if finite.iter().any(|f| *f != 0.0) {
            return None;
        }
        max[j] = m.iter().fold(0.0, |a, &b| if b > a { b } else { a });
    }
    Some(max)
}

/// The lane codes from certified signs of `E_0, E_1, E_2, D` (bounds `b`).
#[inline(always)]
fn certified(v: &[Lanes; 4], b: &[f64; 4]) -> [u8; LANES] {
    let (mut any_pos, mut any_neg, mut all_pos, mut all_neg) =
        ([false; LANES], [false; LANES], [true; LANES], [true; LANES]);
    for k in 0..4 {
        for l in 0..LANES {
            let (pos, neg) = (v[k].0[l] > b[k], -v[k].0[l] > b[k]);
            any_pos[l] |= pos;
            any_neg[l] |= neg;
            all_pos[l] &= pos;
            all_neg[l] &= neg;
        }
    }
    let mut codes = [UNDECIDED; LANES];
    for l in 0..LANES {
        let outside = any_pos[l] & any_neg[l];
        let interior = all_pos[l] | all_neg[l];
        codes[l] = if outside {
            OUTSIDE
        } else if interior {
            INTERIOR
        } else {
            UNDECIDED
        };
    }
    codes
}

/// Classify many samples of one triangle in lanes (see [`Batch`]).
pub fn classify_batch(tri: &Tri, samples: &[[f64; 5]], out: &mut Vec<Coverage>) -> BatchStats {
    Batch::new(tri).classify(samples, out)
}

#[cfg(test)]
mod tests;
