//! Certifying that a per-sample cull removes no interior sample of a box, without
//! splitting the box down to the gap between the cull and the covered set.
//!
//! A culling test's per-sample value `c` culls a sample when `c(s) < 0`. Many such
//! values are (up to a bounded rounding error) multilinear polynomials in the sample
//! coordinates: planes in (x, y, u, v, t), lines in (u, t) or (v, t), bilinear patches
//! in (u, t). A [`Cut`] states what such a bound vouches for: where `P(s) >= err`, the
//! sample is not culled (`c(s) >= 0`). A lower bound `c(s) >= P(s) - err` gives that;
//! so does an evaluation whose sign is exact for a quantity `>= P(s)` (directed
//! rounding), with `err = 0`.
//!
//! The certificate is the one the (x, y) elimination uses ([`super::elimination`]),
//! with one more function. An interior sample has `sigma E_k > 0` for the three edge
//! values (`sigma` the sign of `D`), and a culled one has `c < 0`, hence `P < err`, that
//! is `a_3 = err - P > 0`. So if non-negative multipliers, not all zero, make
//!
//! `G = lambda_0 sigma E_0 + lambda_1 sigma E_1 + lambda_2 sigma E_2 + lambda_3 a_3 <= 0`
//!
//! on the whole box, no sample of the box is both interior and culled (at such a sample
//! every term with a positive multiplier would be positive). `G` is affine in each of
//! x, y, u, v separately (the edge values are, and `P` is multilinear), so its extremes
//! over the box are at the 16 corners, and in t it is a polynomial of degree 2 bounded
//! term by term with the corners' rigorous rounding-error bounds
//! ([`super::tpoly::TPoly::range`]). The multipliers are a heuristic (the small linear
//! programme of the elimination, now over four functions); only the check certifies.
//!
//! # The vertex facts
//!
//! A second certificate needs no multipliers on the edges. Write the vertices moved to
//! the sample's (u, v, t) and translated so that its pixel is the origin as
//! `P_k = (T_k, S_k, w_k)`, `T_k = x_k(t) + u c_k(t) - x w_k(t)` and `S_k = y_k(t) + k v
//! c_k(t) - y w_k(t)` (the coverage rule's [`super::super::coverage`] quantities). The
//! adjugate of the matrix `(P_0 P_1 P_2)` gives `sum_k E_k P_k = (0, 0, D)`, so
//! `sum_k E_k T_k = 0` and `sum_k E_k S_k = 0`. At an interior sample every `sigma E_k`
//! is positive and `D != 0`; the `T_k` are not all zero (else D, a determinant with a
//! zero row, would be 0), so some `T_k` is negative and some positive, and the same
//! for the `S_k`. These are the four facts: some `T_k < 0`, some `T_k > 0`, some
//! `S_k < 0`, some `S_k > 0`. (They say that the pixel lies between the vertices on
//! each axis: what every separating-axis cull rests on.)
//!
//! A fact "some `F_k < 0`" certifies a cut when for every k a multiplier
//! `lambda_k >= 0` makes `a_3 - lambda_k F_k <= 0` on the whole box: at an interior
//! sample take the k with `F_k < 0`; then `a_3 <= lambda_k F_k <= 0`, so `P >= err`. For
//! "some `F_k > 0`" the combination is `a_3 + lambda_k F_k`. The combination is affine in
//! each of x, y, u, v and of degree 2 in t, so the same corner-and-t-polynomial range
//! decides it. A cut that bounds a vertex's place against a column of the tile (culled
//! only where every vertex lies beyond it, with its rounding padded) is certified this
//! way over the whole tile at once, however close the covered set comes to it: the
//! multiplier cancels the cut's dependence on (u, t) exactly, and what is left is
//! `w_k(t)` times the pixel's distance to the column, plus the cut's pad. The edge
//! certificate above, by contrast, must split the box down to the square root of that
//! pad around the contact. The multipliers are chosen from the corners at three
//! times; only the range check certifies.
//!
//! The multiplier of a vertex may also carry a weight linear in time on the cut:
//! `mu(t) a_3 - lambda_k F_k <= 0` with `mu > 0` on the box is as good (divide by
//! `mu`). With `mu` proportional to the vertex's CoC `c_k(t)` (or its `w_k(t)`), the
//! combination cancels the lens coordinate (or the pixel) at every time of the box, not
//! at one time only: a line in (u, t) that bounds a vertex's lens position, for a vertex
//! whose CoC changes tenfold over the shutter, is then certified without splitting u,
//! and what is left is the line's distance to `u_k(x, t)` itself.
//!
//! Where the cull lies close to one edge (a plane that bounds an edge's value, a line
//! that bounds a vertex's lens position), the combination `c - lambda E_k` cancels the
//! first-order part that both share, so a box is decided when it is about the square
//! root of the gap wide instead of the gap itself.

use super::lanes::{lconst, LPoly};
use crate::interval::Interval;
use crate::tri::Tri;

/// What a polynomial vouches for a per-sample cull value over a box: at every sample
/// `s = (x, y, u, v, t)` of the box with `P(s) >= err`, the value is `>= 0` or NaN (the
/// sample is not culled; a lower bound `value >= P(s) - err` gives that), with
/// `P(s) = sum over m of coef[m] * prod of s_i for the bits i of m
///       + t^2 sum over m < 16 of t2[m] * prod of s_i for the bits i of m`
/// (bit 0 x, bit 1 y, bit 2 u, bit 3 v, bit 4 t): multilinear, plus a square in t (the
/// edge values of a moving triangle are quadratic in t). The coefficients and `err`
/// are exact real numbers (f64 values); `err >= 0`.
///
/// A cut with `d_sign` 1 (or -1) is certified only against the interior samples whose
/// `D` is positive (negative): a constraint whose culls are bounded differently on the
/// two sides of a facing flip offers one family of cuts per side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cut {
    pub coef: [f64; 32],
    /// The coefficients of `t^2` times the monomials in x, y, u, v.
    pub t2: [f64; 16],
    pub err: f64,
    /// 0: every interior sample; 1 or -1: those whose D has that sign.
    pub d_sign: i8,
}

impl Cut {
    /// The zero polynomial with no error.
    pub fn zero() -> Self {
        Cut { coef: [0.0; 32], t2: [0.0; 16], err: 0.0, d_sign: 0 }
    }

    /// The cut of a polynomial known only by enclosures of its coefficients over the
    /// box `b`: `lin[m]` of the multilinear monomial m, `sq[m]` of `t^2` times the
    /// monomial m of x, y, u, v. Each coefficient's midpoint goes into the cut and its
    /// width times its monomial's largest size over the box into the error, with
    /// `extra` (another bound on what the cut leaves out); the sum is padded by far more
    /// than its own rounding. None when a coefficient or the error is not finite.
    pub(super) fn enclosing(lin: &[Interval; 32], sq: &[Interval; 16], b: &[Interval; 5], extra: f64) -> Option<Cut> {
        let mag: [f64; 5] = std::array::from_fn(|i| b[i].lo.abs().max(b[i].hi.abs()));
        let size = |m: usize| (0..5).filter(|i| m >> i & 1 == 1).fold(1.0f64, |acc, i| acc * mag[i]);
        let mut cut = Cut::zero();
        let mut err = extra;
        for (m, iv) in lin.iter().enumerate() {
            if !(iv.lo.is_finite() && iv.hi.is_finite()) {
                return None;
            }
            cut.coef[m] = iv.mid();
            err += (iv.hi - iv.lo) * size(m);
        }
        for (m, iv) in sq.iter().enumerate() {
            if !(iv.lo.is_finite() && iv.hi.is_finite()) {
                return None;
            }
            cut.t2[m] = iv.mid();
            err += (iv.hi - iv.lo) * (size(m) * (mag[4] * mag[4]));
        }
        cut.err = err * (1.0 + 1e-10) + f64::MIN_POSITIVE;
        cut.err.is_finite().then_some(cut)
    }
    /// Bit masks of the coordinates: x, y, u, v, t.
    pub const X: usize = 1;
    pub const Y: usize = 2;
    pub const U: usize = 4;
    pub const V: usize = 8;
    pub const T: usize = 16;

    /// `P(s)` in plain f64 (an estimate, for tests and proposals only).
    pub fn estimate(&self, s: [f64; 5]) -> f64 {
        let lin: f64 = (0..32)
            .filter(|&m| self.coef[m] != 0.0)
            .map(|m| (0..5).filter(|i| m >> i & 1 == 1).fold(self.coef[m], |a, i| a * s[i]))
            .sum();
        let sq: f64 = (0..16)
            .filter(|&m| self.t2[m] != 0.0)
            .map(|m| (0..4).filter(|i| m >> i & 1 == 1).fold(self.t2[m], |a, i| a * s[i]))
            .sum();
        lin + sq * s[4] * s[4]
    }

    /// Usable: finite coefficients and error, error not negative.
    fn usable(&self) -> bool {
        matches!(self.d_sign, -1..=1)
            && self.err.is_finite()
            && self.err >= 0.0
            && self.coef.iter().all(|c| c.is_finite())
            && self.t2.iter().all(|c| c.is_finite())
    }
}

/// The lanes `err - P` at the 16 corners (lane `8 iu + 4 iv + 2 ix + iy`) as
/// polynomials in `s = t - tm` of degree 2, with rigorous rounding-error bounds.
fn cut_lanes(cut: &Cut, lane: &[[f64; 16]; 4], tm: f64) -> LPoly<3, 16> {
    // Non-t part of each monomial, per lane: coef * prod of the lane's corner values.
    let zero = lconst(&[0.0; 16]).0[0];
    let mut p = LPoly::<3, 16>::zero();
    let t = LPoly::<2, 16>([lconst(&[tm; 16]).0[0], lconst(&[1.0; 16]).0[0]]);
    let part = |c: f64, m: usize| {
        let mut term: LPoly<1, 16> = lconst(&[c; 16]);
        for (i, vals) in lane.iter().enumerate() {
            if m >> i & 1 == 1 {
                term = term.mul::<1, 1>(&lconst(vals));
            }
        }
        term
    };
    for m in 0..32 {
        let c = cut.coef[m];
        if c == 0.0 {
            continue;
        }
        let term = part(c, m);
        let term3: LPoly<3, 16> = if m & Cut::T != 0 {
            let tt: LPoly<2, 16> = term.mul::<2, 2>(&t);
            LPoly([tt.0[0], tt.0[1], zero])
        } else {
            LPoly([term.0[0], zero, zero])
        };
        p = p.add(&term3);
    }
    for m in 0..16 {
        let c = cut.t2[m];
        if c == 0.0 {
            continue;
        }
        let tt: LPoly<2, 16> = part(c, m).mul::<2, 2>(&t);
        p = p.add(&tt.mul::<2, 3>(&t));
    }
    LPoly::<3, 16>([lconst(&[cut.err; 16]).0[0], zero, zero]).sub(&p)
}

/// True when no sample of the box is both interior and culled by a value bounded
/// below by `cut` (see the module doc). `ev` are the edge values in the lanes of the
/// box's corners, `h` the half-width of its times around `tm`, `d` D's enclosure,
/// `lane` the corner values of x, y, u, v per lane.
#[allow(clippy::too_many_arguments)]
pub(super) fn cut_certified(
    tri: &Tri,
    times: Interval,
    ev: &[LPoly<3, 16>; 3],
    lane: &[[f64; 16]; 4],
    tm: f64,
    h: f64,
    d: Interval,
    shifted: &[[LPoly<2, 16>; 3]; 2],
    cut: &Cut,
) -> bool {
    if d.lo.is_nan() || d.hi.is_nan() || !cut.usable() {
        return false;
    }
    let signs: &[f64] = match (d.lo > 0.0, d.hi < 0.0) {
        (true, _) => &[1.0],
        (_, true) => &[-1.0],
        _ => &[1.0, -1.0],
    };
    if cut.d_sign != 0 && !signs.contains(&(cut.d_sign as f64)) {
        // No interior sample of the box is on this cut's side of D.
        return true;
    }
    let a3 = cut_lanes(cut, lane, tm);
    signs.iter().all(|&sg| {
        // A cut for one side of D answers only for the interior samples of that side.
        if cut.d_sign != 0 && sg != cut.d_sign as f64 {
            return true;
        }
        let f = [ev[0], ev[1], ev[2], a3];
        let sgn = [sg, sg, sg, 1.0];
        let holds = |lam: &[f64; 4]| {
            let mut g = LPoly::<3, 16>::zero();
            for k in 0..4 {
                if lam[k] != 0.0 {
                    g = g.add(&lconst(&[sgn[k] * lam[k]; 16]).mul::<3, 3>(&f[k]));
                }
            }
            let (_, hi) = g.range(h);
            hi.iter().all(|&v| v <= 0.0)
        };
        let mid: [[f64; 16]; 4] = std::array::from_fn(|k| f[k].0[0].v.map(|v| sgn[k] * v));
        if super::elimination::multipliers(&mid).is_some_and(|lam| holds(&lam)) {
            return true;
        }
        // The heuristic equalises the (x, y) corners only; where the cut shares its
        // first-order part with the edges in u, v or t, the multipliers must cancel
        // that too: the small linear programme over every corner and three times.
        let vals: Vec<[f64; 4]> = [-h, 0.0, h]
            .iter()
            .flat_map(|&s| {
                (0..16).map(move |n| {
                    std::array::from_fn(|k| sgn[k] * (f[k].0[0].v[n] + s * (f[k].0[1].v[n] + s * f[k].0[2].v[n])))
                })
            })
            .collect();
        minimax_multipliers(&vals).is_some_and(|lam| holds(&lam))
    }) || fact_certified(&a3, shifted, h, &Exact { side: is_side(cut), tri, cut, lane, tm, times })
}

/// The second certificate (see the module doc, "The vertex facts"): for one of the four
/// facts, every vertex k has a multiplier `lambda_k >= 0` with
/// `a_3 - s lambda_k T_k <= 0` on the whole box (`s = 1` for the fact "some `T_k < 0`",
/// `-1` for "some `T_k > 0`"). `shifted` holds the vertices' `(P_k.x, P_k.y)` in the
/// lanes of the box's corners.
fn fact_certified(a3: &LPoly<3, 16>, shifted: &[[LPoly<2, 16>; 3]; 2], h: f64, exact: &Exact) -> bool {
    let zero = lconst(&[0.0; 16]).0[0];
    let lift = |p: &LPoly<2, 16>| LPoly::<3, 16>([p.0[0], p.0[1], zero]);
    shifted.iter().enumerate().any(|(axis, coord)| {
        [1.0f64, -1.0].iter().any(|&sg| {
            coord.iter().enumerate().all(|(k, tk)| {
                let tk = lift(tk);
                let fact = Fact { axis, k, sg };
                weighted(a3, &tk, sg, h, 0.0, exact, fact)
                    || time_weights(&tk, h).iter().any(|&m| {
                        let ok = weighted(a3, &tk, sg, h, m, exact, fact);
                        #[cfg(test)]
                        WEIGHTED.with(|c| c.set(c.get() + ok as usize));
                        ok
                    })
            })
        })
    })
}

/// What the exact check of a fact certificate needs beside the lanes: the triangle, the
/// cut, the box's corner values and its times (see [`exact_fact`]).
pub(super) struct Exact<'a> {
    /// Whether the cut is a side's claim (one coordinate, `P = a + b s_i`): the only
    /// cuts checked exactly. The check costs big-number arithmetic at 16 corners, and
    /// the depth ends' moving planes, whose combinations often come that close, would
    /// run it at every box.
    side: bool,
    tri: &'a Tri,
    cut: &'a Cut,
    lane: &'a [[f64; 16]; 4],
    tm: f64,
    times: Interval,
}

/// A cut in one coordinate: `P = a + b s_i`, no square in t.
fn is_side(cut: &Cut) -> bool {
    cut.t2.iter().all(|&c| c == 0.0)
        && cut.coef.iter().enumerate().all(|(mm, &c)| c == 0.0 || mm.count_ones() <= 1)
        && cut.coef.iter().filter(|&&c| c != 0.0).count() <= 2
}

/// One vertex's part of a fact: its axis (0: `T_k`, pixel x and lens u; 1: `S_k`, y
/// and v), the vertex, and the side (`sg T_k < 0` at the fact's vertex).
#[derive(Clone, Copy)]
struct Fact {
    axis: usize,
    k: usize,
    sg: f64,
}

#[cfg(test)]
thread_local! {
    /// Boxes whose fact certificate needed a time weight (`m != 0`), for the tests.
    static WEIGHTED: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
    /// Vertex certificates that only the exact check gave, for the tests.
    static EXACTLY: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// The weights `m` worth trying for vertex k's fact (see [`weighted`]): the relative
/// rates of change in time of `T_k`'s coefficient of u (its CoC `c_k(t)`) and of x
/// (its `w_k(t)`), where they keep the weight positive over the box. With such a
/// weight the combination cancels that coordinate at every time of the box, where a
/// constant multiplier cancels it at one time only: a vertex whose CoC or depth
/// changes a lot over the box (strong perspective) then needs no split in it.
fn time_weights(tk: &LPoly<3, 16>, h: f64) -> Vec<f64> {
    // Lane 8 differs from lane 0 in u only, lane 2 in x only.
    [8usize, 2]
        .iter()
        .map(|&other| {
            let q0 = tk.0[0].v[other] - tk.0[0].v[0];
            let q1 = tk.0[1].v[other] - tk.0[1].v[0];
            q1 / q0
        })
        .filter(|m| m.is_finite() && *m != 0.0 && (m.abs() * h).next_up() < 1.0)
        .collect()
}

/// The fact certificate for one vertex: a multiplier `lambda >= 0` with
/// `mu(s) a_3 - sg lambda T_k <= 0` on the whole box, where `mu(s) = 1 + m s` (`m = 0`:
/// a constant multiplier). The caller keeps `mu > 0` on `[-h, h]` (`|m| h < 1`, the
/// product rounded up); then at an interior sample whose `sg T_k` is negative (the
/// fact's vertex) `a_3 <= sg lambda T_k / mu <= 0`.
fn weighted(a3: &LPoly<3, 16>, tk: &LPoly<3, 16>, sg: f64, h: f64, m: f64, exact: &Exact, fact: Fact) -> bool {
    // The values at the corners and three times (for choosing the multiplier only).
    let at = |p: &LPoly<3, 16>, n: usize, s: f64| p.0[0].v[n] + s * (p.0[1].v[n] + s * p.0[2].v[n]);
    // Need a - lambda b <= 0 at every row, b = sg T_k: lambda >= a / b where b > 0,
    // lambda <= a / b where b < 0, a <= 0 where b = 0.
    let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
    for s in [-h, 0.0, h] {
        for n in 0..16 {
            let (a, b) = (at(a3, n, s) * (1.0 + m * s), sg * at(tk, n, s));
            if !(a.is_finite() && b.is_finite()) {
                return false;
            }
            if b > 0.0 {
                lo = lo.max(a / b);
            } else if b < 0.0 {
                hi = hi.min(a / b);
            } else if a > 0.0 {
                return false;
            }
        }
    }
    if lo > hi {
        return false;
    }
    // The weighted cut: `a_3` itself, or times `1 + m s` (degree 3 in s).
    let zero = lconst(&[0.0; 16]).0[0];
    let wa: LPoly<4, 16> = if m == 0.0 {
        LPoly([a3.0[0], a3.0[1], a3.0[2], zero])
    } else {
        a3.mul::<2, 4>(&LPoly([lconst(&[1.0; 16]).0[0], lconst(&[m; 16]).0[0]]))
    };
    // The least multiplier raised a little (rounding of the rows), or the middle of the
    // range; only the rigorous range decides.
    let tries = [lo * (1.0 + 1e-9) + f64::MIN_POSITIVE, if hi.is_finite() { 0.5 * (lo + hi) } else { 2.0 * lo }];
    tries.iter().any(|&lam| {
        if !(lam >= 0.0 && lam.is_finite()) {
            return false;
        }
        let g = if m == 0.0 {
            // Degree 2: the range of the cubic would be the same with a zero top term.
            let g = a3.sub(&lconst(&[sg * lam; 16]).mul::<3, 3>(tk));
            LPoly([g.0[0], g.0[1], g.0[2], zero])
        } else {
            let lt = lconst(&[sg * lam; 16]).mul::<3, 3>(tk);
            wa.sub(&LPoly([lt.0[0], lt.0[1], lt.0[2], zero]))
        };
        let top = g.range(h).1;
        if top.iter().all(|&v| v <= 0.0) {
            return true;
        }
        // Within the rounding of the lanes (their error bounds and the range's pad,
        // about 2^-48 of the terms): the same combination checked exactly. A contact
        // that is exact (a vertex on a side of the box at an end of its times) leaves
        // the combination at exactly 0 there, which no enclosure can show.
        let scale = || {
            (0..16)
                .map(|n| (0..4).map(|j| g.0[j].v[n].abs() * h.max(1.0).powi(j as i32)).sum::<f64>())
                .fold(0.0, f64::max)
        };
        let ok = exact.side && top.iter().all(|&v| v <= 1e-12 * scale()) && exact_fact(exact, fact, lam, m);
        #[cfg(test)]
        EXACTLY.with(|c| c.set(c.get() + ok as usize));
        ok
    })
}

/// The fact certificate checked in exact dyadic arithmetic: for every corner of the
/// box, `G(s) = (1 + m s)(err - P) - sg lambda T_k` as a polynomial in `s = t - tm`
/// (degree at most 3, every coefficient exact: the triangle's, the cut's and the
/// corners' values are f64 numbers), and its upper bound
/// `g0 + |g1| h + max(g2, 0) h^2 + |g3| h^3 <= 0` over `|s| <= h`, with h the exact
/// larger distance from `tm` to the ends of the box's times. `G` is affine in each of
/// x, y, u, v, so the corners bound it; the weight is checked positive (`|m| h < 1`).
fn exact_fact(e: &Exact, f: Fact, lam: f64, m: f64) -> bool {
    use crate::dyadic::Dyadic as D;
    type P = [D; 4];
    let d = D::from_f64;
    let zero = || [D::zero(), D::zero(), D::zero(), D::zero()];
    let add = |a: &P, b: &P| -> P { std::array::from_fn(|j| &a[j] + &b[j]) };
    let scale = |a: &P, c: &D| -> P { std::array::from_fn(|j| &a[j] * c) };
    // Products of degree above 3 do not occur (checked by the caller's shapes: a cut of
    // degree 2 times a linear weight, a vertex term of degree 1).
    let mul = |a: &P, b: &P| -> P {
        let mut r = zero();
        for i in 0..4 {
            for j in 0..4 - i {
                r[i + j] = &r[i + j] + &(&a[i] * &b[j]);
            }
        }
        r
    };
    let finite = [e.tm, e.times.lo, e.times.hi, lam, m, e.cut.err].iter().all(|v| v.is_finite());
    if !finite || e.cut.t2.iter().chain(e.cut.coef.iter()).any(|c| !c.is_finite()) {
        return false;
    }
    let tm = d(e.tm);
    let h = {
        let (a, b) = (&d(e.times.hi) - &tm, &tm - &d(e.times.lo));
        if a.cmp_exact(&b) == std::cmp::Ordering::Less {
            b
        } else {
            a
        }
    };
    let abs = |x: &D| if x.signum() < 0 { -x } else { x.clone() };
    // The weight 1 + m s stays positive over |s| <= h.
    if (&abs(&d(m)) * &h).cmp_exact(&D::one()) != std::cmp::Ordering::Less {
        return false;
    }
    let t: P = [tm.clone(), D::one(), D::zero(), D::zero()];
    let lerp = |a: f64, b: f64| -> P { add(&[d(a), D::zero(), D::zero(), D::zero()], &scale(&t, &(&d(b) - &d(a)))) };
    let tri = e.tri;
    let (pos, cc, w) = (
        lerp(tri.q[f.k][f.axis], tri.r[f.k][f.axis]),
        lerp(tri.c0[f.k], tri.c1[f.k]),
        lerp(tri.q[f.k][3], tri.r[f.k][3]),
    );
    let aspect = if f.axis == 0 { D::one() } else { d(tri.k) };
    let weight: P = [D::one(), d(m), D::zero(), D::zero()];
    let sl = &d(f.sg) * &d(lam);
    (0..16).all(|n| {
        let corner: [D; 4] = std::array::from_fn(|i| d(e.lane[i][n]));
        // A coefficient times the corner's values of the monomial's coordinates.
        let monomial = |c: f64, mm: usize| {
            corner.iter().enumerate().filter(|(i, _)| mm >> i & 1 == 1).fold(d(c), |a, (_, ci)| &a * ci)
        };
        // err - P at this corner: the monomials without t, times t, times t^2.
        let mut p = zero();
        for mm in (0..32).filter(|&mm| e.cut.coef[mm] != 0.0) {
            let term = monomial(e.cut.coef[mm], mm);
            let tp: P = if mm & Cut::T != 0 { scale(&t, &term) } else { [term, D::zero(), D::zero(), D::zero()] };
            p = add(&p, &tp);
        }
        for mm in (0..16).filter(|&mm| e.cut.t2[mm] != 0.0) {
            p = add(&p, &scale(&mul(&t, &t), &monomial(e.cut.t2[mm], mm)));
        }
        let a3 = add(&[d(e.cut.err), D::zero(), D::zero(), D::zero()], &scale(&p, &-D::one()));
        // The vertex term at this corner's pixel and lens coordinate.
        let (pix, lens) = (&corner[f.axis], &corner[2 + f.axis]);
        let tk = add(&add(&pos, &scale(&cc, &(lens * &aspect))), &scale(&w, &-pix.clone()));
        let g = add(&mul(&weight, &a3), &scale(&tk, &-sl.clone()));
        let h2 = &h * &h;
        let pos2 = if g[2].signum() > 0 { g[2].clone() } else { D::zero() };
        let ub = &(&(&g[0] + &(&abs(&g[1]) * &h)) + &(&pos2 * &h2)) + &(&abs(&g[3]) * &(&h2 * &h));
        ub.signum() <= 0
    })
}

/// Non-negative multipliers summing to 1 that minimise the largest of
/// `sum_k lam_k rows[n][k]` over the rows (a matrix game, solved as the packing linear
/// programme `max sum x` s.t. `B^T x <= 1`, `x >= 0` with `B = C - rows > 0`, by the
/// simplex method; the multipliers are its dual values). None when the programme's
/// value is not negative or the arithmetic breaks down. A heuristic: only the check of
/// the combination certifies.
fn minimax_multipliers<const F: usize>(rows: &[[f64; F]]) -> Option<[f64; F]> {
    let n = rows.len();
    let (mut amin, mut amax) = (f64::INFINITY, f64::NEG_INFINITY);
    for r in rows {
        for &v in r {
            if !v.is_finite() {
                return None;
            }
            amin = amin.min(v);
            amax = amax.max(v);
        }
    }
    let scale = (amax - amin).max(amax.abs()).max(amin.abs());
    if scale <= 0.0 || amin >= 0.0 {
        return None;
    }
    // B = (C - A) / scale with C above every value: entries in (0, 3].
    let c = amax + 0.5 * scale;
    // Tableau: F rows (one per multiplier), columns the n row weights x, then F slacks,
    // then the right-hand side; the objective row holds the reduced costs.
    let w = n + F + 1;
    let mut t = vec![0.0f64; (F + 1) * w];
    for k in 0..F {
        for (j, r) in rows.iter().enumerate() {
            t[k * w + j] = (c - r[k]) / scale;
        }
        t[k * w + n + k] = 1.0;
        t[k * w + n + F] = 1.0;
    }
    for j in 0..n {
        t[F * w + j] = -1.0;
    }
    for _ in 0..64 {
        // Entering column: the most negative reduced cost.
        let (mut col, mut best) = (usize::MAX, -1e-12);
        for j in 0..n + F {
            if t[F * w + j] < best {
                best = t[F * w + j];
                col = j;
            }
        }
        if col == usize::MAX {
            break;
        }
        // Leaving row: the least ratio.
        let (mut row, mut ratio) = (usize::MAX, f64::INFINITY);
        for k in 0..F {
            let a = t[k * w + col];
            if a > 1e-12 {
                let r = t[k * w + n + F] / a;
                if r < ratio {
                    ratio = r;
                    row = k;
                }
            }
        }
        if row == usize::MAX {
            return None;
        }
        let p = t[row * w + col];
        for j in 0..w {
            t[row * w + j] /= p;
        }
        for k in 0..=F {
            if k != row {
                let f = t[k * w + col];
                if f != 0.0 {
                    for j in 0..w {
                        t[k * w + j] -= f * t[row * w + j];
                    }
                }
            }
        }
    }
    // Dual values: the reduced costs of the slacks.
    let y: [f64; F] = std::array::from_fn(|k| t[F * w + n + k].max(0.0));
    let sum: f64 = y.iter().sum();
    if !(sum.is_finite() && sum > 0.0) {
        return None;
    }
    let lam = y.map(|v| v / sum);
    let value = rows.iter().map(|r| (0..F).map(|k| lam[k] * r[k]).sum::<f64>()).fold(f64::NEG_INFINITY, f64::max);
    (value < 0.0).then_some(lam)
}

#[cfg(test)]
mod tests {
    //! An independent attack on the certificate: every (box, cut) it certifies is
    //! sampled densely, with extra points pushed just across the cut's zero set, and
    //! each sample is judged exactly (the coverage signs and `P - err` in dyadic
    //! arithmetic): none may be interior with `P - err < 0`.
    use super::*;
    use crate::coverage::{class_of_signs, exact_signs, Coverage};
    use crate::dyadic::Dyadic;
    use crate::extents::enclosure::{box_values_cutting, Box5};
    use crate::extents::testgen::{random_sliver, random_tri, unit_stream};
    use crate::tri::Tri;

    /// `P(s) - err < 0`, exactly.
    fn culls_exactly(cut: &Cut, s: [f64; 5]) -> bool {
        let mut acc = -Dyadic::from_f64(cut.err);
        for m in 0..16 {
            if cut.t2[m] == 0.0 {
                continue;
            }
            let mut t = &Dyadic::from_f64(cut.t2[m]) * &(&Dyadic::from_f64(s[4]) * &Dyadic::from_f64(s[4]));
            for (i, &si) in s.iter().take(4).enumerate() {
                if m >> i & 1 == 1 {
                    t = &t * &Dyadic::from_f64(si);
                }
            }
            acc = &acc + &t;
        }
        for m in 0..32 {
            if cut.coef[m] == 0.0 {
                continue;
            }
            let mut t = Dyadic::from_f64(cut.coef[m]);
            for (i, &si) in s.iter().enumerate() {
                if m >> i & 1 == 1 {
                    t = &t * &Dyadic::from_f64(si);
                }
            }
            acc = &acc + &t;
        }
        acc.signum() < 0
    }

    /// sigma E_k at s, plain f64 (for building cuts near an edge only).
    fn edge_estimate(tri: &Tri, s: [f64; 5], k: usize) -> f64 {
        use crate::filter::Fe;
        use crate::ring::Ring;
        let f = |x: f64| Fe::c(x);
        let ev = crate::coverage::edge_values(tri, &f(s[0]), &f(s[1]), &f(s[2]), &f(s[3]), &f(s[4]));
        ev.e[k].v * ev.d.v.signum()
    }

    /// A cut near edge k: the edge's linearisation at the box middle (finite
    /// differences), shifted by `shift` times its spread over the box, with a
    /// random extra term in u t and an error.
    fn cut_near_edge(tri: &Tri, b: &Box5, k: usize, shift: f64, next: &mut impl FnMut() -> f64) -> Cut {
        let m: [f64; 5] = std::array::from_fn(|i| b[i].mid());
        let e0 = edge_estimate(tri, m, k);
        let mut cut = Cut::zero();
        let mut spread = 0.0;
        let mut c0 = e0;
        for i in 0..5 {
            let hw = 0.5 * b[i].width();
            let g = if hw > 0.0 {
                let (mut a, mut c) = (m, m);
                a[i] += hw;
                c[i] -= hw;
                (edge_estimate(tri, a, k) - edge_estimate(tri, c, k)) / (2.0 * hw)
            } else {
                0.0
            };
            cut.coef[1 << i] = g;
            c0 -= g * m[i];
            spread += (g * hw).abs();
        }
        // The error is large at times (a fifth of the spread): a certificate that left
        // it out would be caught.
        cut.err = next() * [1e-6, 1e-3, 0.2][(next() * 3.0) as usize % 3] * spread;
        cut.coef[0] = c0 + shift * spread + cut.err;
        cut.coef[Cut::U | Cut::T] = (next() - 0.5) * 1e-3 * spread;
        cut
    }

    #[test]
    fn minimax_multipliers_solve_small_games() {
        // Two functions, each negative where the other is positive: the even mix is
        // -0.5 everywhere, the best any mix can do.
        let rows = [[1.0, -2.0], [-2.0, 1.0]];
        let l = minimax_multipliers(&rows).expect("a negative value");
        assert!((l[0] - 0.5).abs() < 1e-12 && (l[1] - 0.5).abs() < 1e-12, "{l:?}");
        // A game whose value is 0: no multipliers.
        assert!(minimax_multipliers(&[[1.0, -1.0], [-1.0, 1.0]]).is_none());
        // One function negative everywhere: it alone.
        let l = minimax_multipliers(&[[1.0, -1.0, 3.0], [2.0, -0.5, 1.0], [0.5, -2.0, 1.0]]).unwrap();
        assert!(l[1] > 0.999, "{l:?}");
        // Three functions, none negative alone or in pairs over all rows, the three
        // together negative: the programme finds the mix (checked by its value).
        let rows = [[1.0, -1.0, -1.0], [-1.0, 1.0, -1.0], [-1.0, -1.0, 1.0], [-0.2, -0.2, -0.2]];
        let l = minimax_multipliers(&rows).unwrap();
        let worst = rows.iter().map(|r| (0..3).map(|k| l[k] * r[k]).sum::<f64>()).fold(f64::MIN, f64::max);
        // (the last row is -0.2 for every mix; the first three need all three weights)
        assert!(worst < -0.2 + 1e-9 && l.iter().all(|&v| v > 0.0), "{l:?} {worst}");
        // Non-finite values: none.
        assert!(minimax_multipliers(&[[f64::NAN, -1.0]]).is_none());
    }

    /// A box around a random point: pixels up to 16 wide within [-8, 8], lens and time
    /// ranges whole or down to `smallest` of the domain.
    fn random_box(next: &mut impl FnMut() -> f64, smallest: f64) -> Box5 {
        let mut b: Box5 = [crate::interval::Interval::point(0.0); 5];
        for (i, bi) in b.iter_mut().enumerate() {
            let (lo, hi) = [(-8.0, 8.0), (-8.0, 8.0), (-1.0, 1.0), (-1.0, 1.0), (0.0, 1.0)][i];
            let w = (hi - lo) * [1.0, 0.25, 0.02, smallest][(next() * 4.0) as usize % 4];
            let a = lo + (hi - lo - w) * next();
            *bi = crate::interval::Interval::new(a, a + w);
        }
        b
    }

    #[test]
    fn no_certified_cut_culls_an_interior_sample() {
        let mut next = unit_stream(0x5eed_c075);
        let (mut certified, mut judged, mut tight) = (0usize, 0usize, 0usize);
        for case in 0..1500 {
            let tri = if case % 4 == 3 { random_sliver(&mut next, case % 8 == 7) } else { random_tri(&mut next) };
            // A box around a random point: pixels up to 2 wide, lens and time ranges small
            // or whole.
            let b = random_box(&mut next, 1e-4);
            let k = (next() * 3.0) as usize % 3;
            let shift = [-0.05, 0.0, 0.02, 0.1, 0.5][(next() * 5.0) as usize % 5];
            let cut = cut_near_edge(&tri, &b, k, shift, &mut next);
            let mut ok = [false];
            box_values_cutting(&tri, &b, &[cut], &mut ok);
            if !ok[0] {
                continue;
            }
            certified += 1;
            // Dense samples, and samples pushed onto the cut's zero set along one
            // coordinate (just beyond the claim: P - err slightly below 0).
            let mut pts = Vec::new();
            for n in 0..32usize {
                pts.push(std::array::from_fn(|i| if n >> i & 1 == 1 { b[i].hi } else { b[i].lo }));
            }
            for _ in 0..400 {
                pts.push(std::array::from_fn(|i| b[i].lo + b[i].width() * next()));
            }
            for _ in 0..200 {
                let mut p: [f64; 5] = std::array::from_fn(|i| b[i].lo + b[i].width() * next());
                let i = (next() * 5.0) as usize % 5;
                let g = cut.coef[1 << i]
                    + if i == 2 {
                        cut.coef[Cut::U | Cut::T] * p[4]
                    } else if i == 4 {
                        cut.coef[Cut::U | Cut::T] * p[2]
                    } else {
                        0.0
                    };
                if g != 0.0 {
                    let target = cut.err * (1.0 - 1e-9) - 1e-12;
                    p[i] += (target - cut.estimate(p)) / g;
                    p[i] = p[i].clamp(b[i].lo, b[i].hi);
                }
                pts.push(p);
            }
            for p in pts {
                judged += 1;
                let culled = culls_exactly(&cut, p);
                let interior = class_of_signs(exact_signs(&tri, p)) == Coverage::Interior;
                if culled && !interior {
                    tight += 1;
                }
                assert!(
                    !(culled && interior),
                    "case {case}: certified cut culls the interior sample {p:?}\n{tri:?}\n{b:?}\n{cut:?}"
                );
            }
        }
        eprintln!("{certified} certified cuts, {judged} exact samples, {tight} culled (none interior)");
        assert!(certified > 200, "the certificate should decide many boxes: {certified}");
        assert!(tight > 1000, "the attack should reach the culled side: {tight}");
    }

    /// `lam * T_k` as a cut: `T_k = P_k.x` at the box's pixels (axis 0, lens u) or
    /// `P_k.y` (axis 1, lens v), `x_k(t) + u c_k(t) - x w_k(t)`.
    fn vertex_term(tri: &Tri, k: usize, axis: usize, lam: f64, at_col: Option<f64>) -> Cut {
        let (pix, lens) = if axis == 0 { (Cut::X, Cut::U) } else { (Cut::Y, Cut::V) };
        let kk = if axis == 0 { 1.0 } else { tri.k };
        let mut c = Cut::zero();
        let (qp, rp, qw, rw) = (tri.q[k][axis], tri.r[k][axis], tri.q[k][3], tri.r[k][3]);
        c.coef[0] = lam * qp;
        c.coef[Cut::T] = lam * (rp - qp);
        c.coef[lens] = lam * kk * tri.c0[k];
        c.coef[lens | Cut::T] = lam * kk * (tri.c1[k] - tri.c0[k]);
        match at_col {
            // At a fixed column (row): the pixel enters as a constant.
            Some(col) => {
                c.coef[0] -= lam * col * qw;
                c.coef[Cut::T] -= lam * col * (rw - qw);
            }
            None => {
                c.coef[pix] = -lam * qw;
                c.coef[pix | Cut::T] = -lam * (rw - qw);
            }
        }
        c
    }

    /// The vertex facts: cuts that bound a vertex's place against a column or row of
    /// the box (as separating-axis culls do: culled only where every vertex lies beyond
    /// it), shifted a little either way, are certified or not; every certified one is
    /// attacked with dense exact samples and with samples at the vertices' tips inside
    /// the box (where the covered set meets such a cull).
    #[test]
    fn no_vertex_fact_cut_culls_an_interior_sample() {
        let mut next = unit_stream(0x7e47_f4c7);
        let (mut certified, mut by_fact, mut judged) = (0usize, 0usize, 0usize);
        for case in 0..3000 {
            let tri = if case % 4 == 3 { random_sliver(&mut next, case % 8 == 7) } else { random_tri(&mut next) };
            let mut b = random_box(&mut next, 1e-3);
            let axis = (next() * 2.0) as usize % 2;
            let k = (next() * 3.0) as usize % 3;
            if next() < 0.7 {
                // Around a vertex tip: the pixels reach just past vertex k's screen
                // point at the middle (u, v, t), so the contact lies in the box.
                let t = b[4].mid();
                let l = |a: f64, c: f64| (1.0 - t) * a + t * c;
                let c = l(tri.c0[k], tri.c1[k]);
                let w = l(tri.q[k][3], tri.r[k][3]);
                let sc = [
                    (l(tri.q[k][0], tri.r[k][0]) + b[2].mid() * c) / w,
                    (l(tri.q[k][1], tri.r[k][1]) + tri.k * b[3].mid() * c) / w,
                ];
                for (i, &v) in sc.iter().enumerate() {
                    let near = [0.0, 1e-6, 1e-3][(next() * 3.0) as usize % 3];
                    let far = [1e-3, 0.1, 2.0][(next() * 3.0) as usize % 3];
                    if v.is_finite() && v.abs() < 1e6 {
                        b[i] = if next() < 0.5 {
                            crate::interval::Interval::new(v - far, v + near)
                        } else {
                            crate::interval::Interval::new(v - near, v + far)
                        };
                    }
                }
            }
            // min side (culls where the vertex is beyond the high column: -T_k(col)) or
            // max side (T_k(col) at the low column), scaled, shifted by a fraction of
            // its spread either way, sometimes with a stray u t or v t term.
            let high = next() < 0.5;
            let col = if high { b[axis].hi } else { b[axis].lo };
            let lam = [1.0, 0.37, 3.0][(next() * 3.0) as usize % 3] * if high { -1.0 } else { 1.0 };
            let mut cut = vertex_term(&tri, k, axis, lam, Some(col));
            let spread = cut.coef.iter().map(|c| c.abs()).sum::<f64>() * 1e-3;
            cut.coef[0] += [-0.3, -1e-3, 0.0, 1e-6, 1e-3][(next() * 5.0) as usize % 5] * spread;
            if next() < 0.3 {
                cut.coef[Cut::U | Cut::T] += (next() - 0.5) * 1e-4 * spread;
            }
            if next() < 0.3 {
                // A square in t (as a cut from a moving edge has), bending the cut
                // between the times the multipliers are chosen at.
                let hw = 0.5 * b[4].width();
                let a = (next() - 0.3) * spread * [1e-3, 0.1, 1.0][(next() * 3.0) as usize % 3] / (hw * hw).max(1e-12);
                cut.t2[0] += a;
                cut.coef[Cut::T] -= a * (b[4].lo + b[4].hi);
                cut.coef[0] += a * b[4].lo * b[4].hi;
            }
            cut.err = next() * 1e-4 * spread;
            let mut ok = [false];
            box_values_cutting(&tri, &b, &[cut], &mut ok);
            if !ok[0] {
                continue;
            }
            certified += 1;
            let mut pts = Vec::new();
            for n in 0..32usize {
                pts.push(std::array::from_fn(|i| if n >> i & 1 == 1 { b[i].hi } else { b[i].lo }));
            }
            for _ in 0..300 {
                pts.push(std::array::from_fn(|i| b[i].lo + b[i].width() * next()));
            }
            // Tips: at a random (u, v, t) of the box, each vertex's screen point and
            // points around it at 1e-9 to 1e-2 px, clamped into the box.
            for _ in 0..100 {
                let mut p: [f64; 5] = std::array::from_fn(|i| b[i].lo + b[i].width() * next());
                let j = (next() * 3.0) as usize % 3;
                let t = p[4];
                let l = |a: f64, c: f64| (1.0 - t) * a + t * c;
                let c = l(tri.c0[j], tri.c1[j]);
                let w = l(tri.q[j][3], tri.r[j][3]);
                let sx = (l(tri.q[j][0], tri.r[j][0]) + p[2] * c) / w;
                let sy = (l(tri.q[j][1], tri.r[j][1]) + tri.k * p[3] * c) / w;
                let d = [0.0, 1e-9, 1e-6, 1e-2][(next() * 4.0) as usize % 4];
                let ang = next() * std::f64::consts::TAU;
                if sx.is_finite() && sy.is_finite() {
                    p[0] = (sx + d * ang.cos()).clamp(b[0].lo, b[0].hi);
                    p[1] = (sy + d * ang.sin()).clamp(b[1].lo, b[1].hi);
                    pts.push(p);
                }
            }
            let mut culled_any = false;
            for p in pts {
                judged += 1;
                let culled = culls_exactly(&cut, p);
                culled_any |= culled;
                let interior = class_of_signs(exact_signs(&tri, p)) == Coverage::Interior;
                assert!(
                    !(culled && interior),
                    "case {case}: certified cut culls the interior sample {p:?}\n{tri:?}\n{b:?}\n{cut:?}"
                );
            }
            by_fact += culled_any as usize;
        }
        eprintln!("{certified} certified vertex cuts ({by_fact} culling some attacked sample), {judged} exact samples");
        assert!(certified > 300 && by_fact > 100, "{certified} certified, {by_fact} culling");
    }

    /// Judges each of `pts` exactly: none may be interior and culled by `cut` (the box
    /// was certified). Returns how many the cut culls.
    fn attack(tri: &Tri, b: &Box5, cut: &Cut, pts: &[[f64; 5]], case: usize) -> usize {
        let mut culled_pts = 0;
        for &p in pts {
            let culled = culls_exactly(cut, p);
            culled_pts += culled as usize;
            let interior = class_of_signs(exact_signs(tri, p)) == Coverage::Interior;
            assert!(
                !(culled && interior),
                "case {case}: certified cut culls the interior sample {p:?}\n{tri:?}\n{b:?}\n{cut:?}"
            );
        }
        culled_pts
    }

    /// The time-weighted vertex facts: per-sample lines in (u, t) or (v, t) that bound a
    /// vertex's lens coordinate at a column of the box from below or above (as the
    /// ut / vt lines of the lens-and-time bounds do: the tangent or the chord of
    /// `u_k(X, t) = (X w_k(t) - x_k(t)) / c_k(t)`, moved by a pad that is sometimes
    /// negative), for vertices whose CoC changes up to tenfold over the shutter. Every
    /// certified cut is attacked with dense exact samples and with samples pushed just
    /// beyond the line, along the lens coordinate, at the vertices' lens positions.
    #[test]
    fn no_time_weighted_fact_culls_an_interior_sample() {
        let mut next = unit_stream(0x71e3_a417);
        let (mut certified, mut by_weight, mut judged, mut culled_pts) = (0usize, 0usize, 0usize, 0usize);
        for case in 0..12_000 {
            let mut tri = if case % 4 == 3 { random_sliver(&mut next, case % 8 == 7) } else { random_tri(&mut next) };
            // Strong perspective: every CoC of one sign, changing up to tenfold, and in
            // most cases every vertex in front of the lens.
            if next() < 0.7 {
                for j in 0..3 {
                    tri.q[j][3] = 0.5 + 2.0 * next();
                    tri.r[j][3] = 0.5 + 2.0 * next();
                }
            }
            let sign = if next() < 0.5 { 1.0 } else { -1.0 };
            for j in 0..3 {
                let c0 = 0.2 + 3.0 * next();
                tri.c0[j] = sign * c0;
                tri.c1[j] = sign * c0 * [0.3, 3.0, 0.1, 10.0][(next() * 4.0) as usize % 4];
            }
            let mut b = random_box(&mut next, 1e-3);
            // Wide in time: where a constant multiplier cannot follow the CoC.
            if next() < 0.5 {
                let a = 0.75 * next();
                b[4] = crate::interval::Interval::new(a, a + 0.25);
            }
            let axis = (next() * 2.0) as usize % 2;
            let k = (next() * 3.0) as usize % 3;
            let kk = if axis == 0 { 1.0 } else { tri.k };
            let lens_at = |j: usize, col: f64, t: f64| {
                let l = |a: f64, c: f64| (1.0 - t) * a + t * c;
                let (qp, rp, qw, rw) = (tri.q[j][axis], tri.r[j][axis], tri.q[j][3], tri.r[j][3]);
                (col * l(qw, rw) - l(qp, rp)) / (kk * l(tri.c0[j], tri.c1[j]))
            };
            let lower = next() < 0.5;
            let sgn = if lower { 1.0 } else { -1.0 };
            // The vertices' lens coordinates at the box's columns, least (lower line) or
            // greatest (upper), on a grid of times; the line: the slope there at a time
            // of the grid, lowered (raised) until it touches the grid values.
            let (ta, tb) = (b[4].lo, b[4].hi);
            let grid: Vec<(f64, f64)> = (0..=64)
                .map(|i| {
                    let t = ta + (tb - ta) * i as f64 / 64.0;
                    let vals = (0..3).flat_map(|j| [b[axis].lo, b[axis].hi].map(|c| lens_at(j, c, t)));
                    (t, vals.fold(sgn * f64::INFINITY, |a, v| if sgn * v < sgn * a { v } else { a }))
                })
                .collect();
            let i0 = (next() * 63.0) as usize;
            let slope = (grid[i0 + 1].1 - grid[i0].1) / (grid[i0 + 1].0 - grid[i0].0);
            // Lowered (raised) once more by the grid's largest second difference, so that
            // the line stays clear of the values between the grid's times too.
            let bend = (1..64).map(|i| (grid[i + 1].1 - 2.0 * grid[i].1 + grid[i - 1].1).abs()).fold(0.0, f64::max);
            let off = (grid.iter().map(|&(t, f)| sgn * (f - slope * t)).fold(f64::INFINITY, f64::min) - bend) * sgn;
            let at0 = grid[i0].1;
            if !(slope.is_finite() && off.is_finite() && at0.abs() < 1e3) {
                continue;
            }
            // The lens range: around the line, so the contact lies in the box.
            let lens = 2 + axis;
            let wl = [2.0, 0.1, 1e-3][(next() * 3.0) as usize % 3];
            let a = at0 - wl * next();
            b[lens] = crate::interval::Interval::new(a, a + wl);
            let pad = [-1e-3, -1e-6, 0.0, 1e-7, 1e-5, 1e-3, 1e-2][(next() * 7.0) as usize % 7];
            // lower: lens >= line (P = lens - line, culls below); upper: the reverse.
            let mut cut = Cut::zero();
            let base = off - sgn * pad;
            cut.coef[0] = -sgn * base;
            cut.coef[Cut::T] = -sgn * slope;
            cut.coef[if axis == 0 { Cut::U } else { Cut::V }] = sgn;
            let before = WEIGHTED.with(|c| c.get());
            let mut ok = [false];
            box_values_cutting(&tri, &b, &[cut], &mut ok);
            if !ok[0] {
                continue;
            }
            certified += 1;
            let weighted = WEIGHTED.with(|c| c.get()) > before;
            by_weight += weighted as usize;
            // The boxes a time weight decided are attacked densely, the others lightly
            // (the constant multipliers have their own attack above).
            let dense = if weighted { 1 } else { 10 };
            let mut pts = Vec::new();
            for n in 0..32usize {
                pts.push(std::array::from_fn(|i| if n >> i & 1 == 1 { b[i].hi } else { b[i].lo }));
            }
            for _ in 0..300 / dense {
                pts.push(std::array::from_fn(|i| b[i].lo + b[i].width() * next()));
            }
            // Just beyond the line along the lens coordinate (culled by 1e-12 to 1e-6),
            // at random pixels and at vertex k's own screen point.
            for n in 0..300 / dense {
                let mut p: [f64; 5] = std::array::from_fn(|i| b[i].lo + b[i].width() * next());
                let line = base + slope * p[4];
                p[lens] = (line - sgn * [1e-12, 1e-9, 1e-6][n % 3]).clamp(b[lens].lo, b[lens].hi);
                if n % 2 == 0 {
                    let t = p[4];
                    let l = |a: f64, c: f64| (1.0 - t) * a + t * c;
                    for (i, j) in [(0usize, 0usize), (1, 1)] {
                        let cj = l(tri.c0[k], tri.c1[k]) * if i == 0 { 1.0 } else { tri.k };
                        let s = (l(tri.q[k][j], tri.r[k][j]) + p[2 + i] * cj) / l(tri.q[k][3], tri.r[k][3]);
                        if s.is_finite() {
                            p[i] = s.clamp(b[i].lo, b[i].hi);
                        }
                    }
                }
                pts.push(p);
            }
            judged += pts.len();
            culled_pts += attack(&tri, &b, &cut, &pts, case);
        }
        eprintln!("{certified} certified lens-line cuts ({by_weight} by a time weight), {judged} exact samples, {culled_pts} culled");
        assert!(
            by_weight > 100 && culled_pts > 100_000,
            "{certified} certified, {by_weight} weighted, {culled_pts} culled"
        );
    }

    /// Exact contacts: a vertex exactly on the low x side of the box at t = 0, moving
    /// away (or, in some cases, other vertices reaching into the box), and a cut that
    /// culls the times after a bound that is 0, 2^-149, tiny or negative: the claim of a
    /// tile at a method's reject limit. The enclosures cannot close such a box (the
    /// combination is exactly 0 at the contact); the exact check can. Every certified
    /// box is attacked with dense exact samples and with samples at the contact, just
    /// after the bound and just inside the side.
    #[test]
    fn no_exactly_checked_fact_culls_an_interior_sample() {
        let mut next = unit_stream(0xe7ac_7c0d);
        let (mut certified, mut exactly, mut judged, mut culled_pts) = (0usize, 0usize, 0usize, 0usize);
        for case in 0..1500 {
            let w = [0.5, 1.0, 2.0, 0.375][(next() * 4.0) as usize % 4];
            let x0 = ((next() - 0.5) * 400.0) as f32 as f64;
            let y0 = ((next() - 0.5) * 400.0) as f32 as f64;
            let width = [1.0, 2.0, 8.0][(next() * 3.0) as usize % 3];
            let speed = [1e-3, 0.5, 30.0][(next() * 3.0) as usize % 3];
            let mut q = [[0.0; 4]; 3];
            let mut r = [[0.0; 4]; 3];
            // Vertex 0 on the side x = x0 at t = 0, moving left.
            q[0] = [x0 * w, y0 * w, 0.3, w];
            r[0] = [(x0 - speed) * w, (y0 + (next() - 0.5) * 4.0) * w, 0.3, w];
            let reach = next() < 0.25;
            for j in 1..3 {
                let dx = if reach { (next() - 0.3) * 2.0 * width } else { -(1.0 + 20.0 * next()) };
                let dy = (next() - 0.5) * 40.0;
                q[j] = [(x0 + dx) * w, (y0 + dy) * w, 0.3, w];
                r[j] = [(x0 + dx - speed * next()) * w, (y0 + dy) * w, 0.3, w];
            }
            let tri = Tri { q, r, c0: [0.0; 3], c1: [0.0; 3], k: 1.0 };
            let t_hi = [1.0, 0.25, 1e-3][(next() * 3.0) as usize % 3];
            let bound = [0.0, f64::from(f32::from_bits(1)), 1e-9, -1e-9, 1e-3][(next() * 5.0) as usize % 5];
            let b: Box5 = [
                crate::interval::Interval::new(x0, x0 + width),
                crate::interval::Interval::new(y0 - 20.0, y0 + 20.0),
                crate::interval::Interval::new(-1.0, 1.0),
                crate::interval::Interval::new(-1.0, 1.0),
                crate::interval::Interval::new(0.0, t_hi),
            ];
            // Culls t > bound: P = bound - t.
            let mut cut = Cut::zero();
            cut.coef[0] = bound;
            cut.coef[Cut::T] = -1.0;
            let before = EXACTLY.with(|c| c.get());
            let mut ok = [false];
            box_values_cutting(&tri, &b, &[cut], &mut ok);
            // The exact check on its own too (without the enclosures' filter), with
            // multipliers from a grid: certified when every vertex passes one fact.
            let lane: [[f64; 16]; 4] = std::array::from_fn(|i| {
                std::array::from_fn(|n| {
                    let bit = [(n >> 1) & 1, n & 1, (n >> 3) & 1, (n >> 2) & 1][i];
                    if bit == 1 {
                        b[i].hi
                    } else {
                        b[i].lo
                    }
                })
            });
            let e = Exact { side: true, tri: &tri, cut: &cut, lane: &lane, tm: b[4].mid(), times: b[4] };
            let grid = [1e-3, 1e-2, 0.1, 1.0, 10.0, 1.0 / (speed * w)];
            let direct = (0..2).any(|axis| {
                [1.0, -1.0]
                    .iter()
                    .any(|&sg| (0..3).all(|k| grid.iter().any(|&lam| exact_fact(&e, Fact { axis, k, sg }, lam, 0.0))))
            });
            if !(ok[0] || direct) {
                continue;
            }
            certified += 1;
            let by_exact = EXACTLY.with(|c| c.get()) > before || (direct && !ok[0]);
            exactly += by_exact as usize;
            let mut pts: Vec<[f64; 5]> = Vec::new();
            for _ in 0..if by_exact { 400 } else { 40 } {
                pts.push(std::array::from_fn(|i| b[i].lo + b[i].width() * next()));
            }
            // At the contact: just after the bound, just inside the side, near vertex 0.
            for n in 0..if by_exact { 400 } else { 40 } {
                let t = (bound.max(0.0) + [1e-300, 1e-45, 1e-15, 1e-9, 1e-4][n % 5]).min(t_hi);
                let l = |a: f64, c: f64| (1.0 - t) * a + t * c;
                let sy = l(q[0][1], r[0][1]) / w;
                let d = [0.0, 1e-300, 1e-12, 1e-6, 1e-2][(n / 5) % 5];
                let p = [
                    (x0 + d * next()).clamp(b[0].lo, b[0].hi),
                    (sy + (next() - 0.5) * d).clamp(b[1].lo, b[1].hi),
                    next() * 2.0 - 1.0,
                    next() * 2.0 - 1.0,
                    t,
                ];
                pts.push(p);
            }
            judged += pts.len();
            culled_pts += attack(&tri, &b, &cut, &pts, case);
        }
        eprintln!("{certified} certified time claims ({exactly} by the exact check), {judged} exact samples, {culled_pts} culled");
        assert!(exactly > 100 && culled_pts > 50_000, "{certified} certified, {exactly} exactly, {culled_pts} culled");
    }
}
