//! The moving and defocused template: the static template of [`super::bbox_query`]
//! set in motion, with a CoC that changes over the shutter.
//!
//! # The template
//! Seven f32 inputs: `a0`, `a1` (a vertex's clip x at the shutter's open and close),
//! `c0`, `c1` (every vertex's CoC at open and close, > 0), `w0`, `w1` (every vertex's
//! depth at open and close, > 0) and `t` (the tile's edge). At each shutter end `e` the
//! triangle is the static template's: vertices `(a_e, 0)`, `(a_e, 64 w_e)` and
//! `(a_e ± 64 w_e, 0)`, all at depth `w_e`, `z = 0.5`, aspect 1. Between the ends every
//! coordinate moves linearly (the model's motion), so at every time the triangle is the
//! same right triangle in screen space, moved: seen from the lens edge `u = -1` (side
//! `x-min`) its left edge is the vertical segment at `X(τ) = (a(τ) - c(τ)) / w(τ)` from
//! `y = 0` to `y = 64`, with `a`, `c`, `w` the linear interpolations of the end values.
//! The tile is `[t - 1, t] x [8, 9]`; side `x-max` mirrors it (third vertex to the
//! left, lens edge `u = +1`, right edge `(a(τ) + c(τ)) / w(τ)`, tile `[t, t + 1] x [8, 9]`).
//!
//! # The exact side
//! `X(τ)` is a ratio of two affine functions of τ whose denominator `w(τ)` stays > 0
//! (both ends are), so it is monotone in τ (its derivative has the constant numerator
//! `n' w0 - n0 w'` over `w(τ)^2`, with `n = a - c`): its least value over the shutter is
//! at an end. So the tile holds covered samples (at `u` near -1, `y` in (8, 9), some
//! time) exactly when `X(0) < t` or `X(1) < t`, that is `a0 < t w0 + c0` or
//! `a1 < t w1 + c1`: each decided in floating point with two fused multiply-adds rounded
//! down and up, as the static template decides its one end
//! ([`super::bbox_query::assert_reach`]). `x-max` asks `a_e > t w_e - c_e` for some end.
//! The same implied bound on `t` (the least of the two ends' directed-rounding bounds)
//! spares the solver the multiplications, and the far edge of the tile must lie inside
//! the triangle's largest extent over the lens and the shutter (the larger of the two
//! ends' far vertex shifted by its CoC, rounded away from the tile). A model is a hint:
//! the exact judge decides every case.
//!
//! What the template adds to the static one: the methods' time handling (la2011's time
//! chords, bbox's hull over both ends, mam2012's patches in time) and a CoC that differs
//! at the two ends, with the tile edge free and the triangle fixed by the concolic plan.

use super::bbox_query::{Side, TemplateCull};
use super::family::Family;
use super::smt::Smt;
use crate::bounds::arith::{F32Arith, Plain, TriOf};

/// The names of the inputs, in order.
pub const INPUTS: [&str; 7] = ["a0", "a1", "c0", "c1", "w0", "w1", "t"];

/// The default range sets of the x-min side: the static template's middle and wide sets
/// with each of `a`, `c`, `w` free at both shutter ends.
const SETS: [[[f32; 2]; 7]; 2] = [
    [[-64.0, 64.0], [-64.0, 64.0], [0.5, 64.0], [0.5, 64.0], [0.5, 4.0], [0.5, 4.0], [-256.0, 256.0]],
    [[-4096.0, 4096.0], [-4096.0, 4096.0], [0.25, 64.0], [0.25, 64.0], [0.25, 64.0], [0.25, 64.0], [-16384.0, 16384.0]],
];

/// The ranges of the other side: `a0`, `a1` and `t` negated (mirror image).
fn mirrored(r: [[f32; 2]; 7]) -> [[f32; 2]; 7] {
    let neg = |x: [f32; 2]| [-x[1], -x[0]];
    [neg(r[0]), neg(r[1]), r[2], r[3], r[4], r[5], neg(r[6])]
}

/// The query family of a method on the moving template: inputs, sides, ranges and the
/// exact side are the template's, the cull is the method's ([`TemplateCull`], shared
/// with the static template).
#[derive(Clone, Copy, Debug)]
pub struct MovingFamily<C>(pub C);

impl<C: TemplateCull> Family for MovingFamily<C> {
    fn depth(&self) -> bool {
        self.0.depth()
    }
    fn partial(&self) -> Option<&'static str> {
        self.0.partial()
    }
    fn inputs(&self) -> &'static [&'static str] {
        &INPUTS
    }
    fn sides(&self) -> &'static [&'static str] {
        &["x-min", "x-max"]
    }
    fn tile_inputs(&self) -> &'static [usize] {
        &[6]
    }
    fn default_ranges(&self, side: usize) -> Vec<Vec<[f32; 2]>> {
        SETS.iter().map(|r| if side == 0 { r.to_vec() } else { mirrored(*r).to_vec() }).collect()
    }
    fn check_range(&self, k: usize, lo: f32, _hi: f32) -> Result<(), String> {
        if (2..=5).contains(&k) && lo <= 0.0 {
            return Err(format!(
                "the range of `{}` must be positive (the template has c > 0 and w > 0 at both shutter ends), not from {lo}",
                INPUTS[k]
            ));
        }
        Ok(())
    }
    fn assert_reached(&self, smt: &Smt, side: usize, v: &[String]) {
        let side = Side::of(side);
        let v: [String; 7] = std::array::from_fn(|k| v[k].clone());
        let (tri, tile) = template(smt, side, &v);
        assert_reach(smt, side, &v);
        assert_far_reach(smt, side, &v, &tri, &tile);
    }
    fn assert_violation(&self, smt: &Smt, side: usize, v: &[String]) {
        let (s, w): (Side, [String; 7]) = (Side::of(side), std::array::from_fn(|k| v[k].clone()));
        let (tri, tile) = template(smt, s, &w);
        smt.assert(&self.0.cull(smt, s, &tri, &tile));
        self.assert_reached(smt, side, v);
    }
    fn instance(&self, side: usize, v: &[f32]) -> (crate::model::Triangle, crate::model::Tile) {
        let (tri, t) = template(&Plain, Side::of(side), &std::array::from_fn(|k| v[k]));
        (tri.triangle(), crate::model::Tile { x0: t[0], y0: t[1], x1: t[2], y1: t[3] })
    }
}

/// The template triangle and tile `[x0, y0, x1, y1]` of a side, from the inputs
/// `a0, a1, c0, c1, w0, w1, t`, in either meaning.
pub fn template<A: F32Arith>(ar: &A, side: Side, v: &[A::F; 7]) -> (TriOf<A::F>, [A::F; 4]) {
    let [a0, a1, c0, c1, w0, w1, t] = v;
    let (zero, z) = (ar.lit(0.0), ar.lit(0.5));
    let end = |a: &A::F, w: &A::F| {
        let h = ar.mul(&ar.lit(64.0), w);
        let far = match side {
            Side::XMin => ar.add(a, &h),
            Side::XMax => ar.sub(a, &h),
        };
        [
            [a.clone(), zero.clone(), z.clone(), w.clone()],
            [a.clone(), h, z.clone(), w.clone()],
            [far, zero.clone(), z.clone(), w.clone()],
        ]
    };
    let tri = TriOf {
        q: end(a0, w0),
        r: end(a1, w1),
        c0: [c0.clone(), c0.clone(), c0.clone()],
        c1: [c1.clone(), c1.clone(), c1.clone()],
        k: ar.lit(1.0),
    };
    let one = ar.lit(1.0);
    let tile = match side {
        Side::XMin => [ar.sub(t, &one), ar.lit(8.0), t.clone(), ar.lit(9.0)],
        Side::XMax => [t.clone(), ar.lit(8.0), ar.add(t, &one), ar.lit(9.0)],
    };
    (tri, tile)
}

/// Assert that the exact footprint reaches into the tile of `side` at some shutter end
/// (hence, by monotonicity in τ, exactly when it does at some time): `a_e < t w_e + c_e`
/// for some end (x-min), `a_e > t w_e - c_e` (x-max), each decided by two fused
/// multiply-adds rounded down and up; with the implied bound on `t` (the least, or
/// greatest, of the two ends' directed-rounding bounds).
pub fn assert_reach(smt: &Smt, side: Side, v: &[String; 7]) {
    let [a0, a1, c0, c1, w0, w1, t] = v;
    let mut reach = Vec::new();
    let mut bounds = Vec::new();
    for (a, c, w) in [(a0, c0, w0), (a1, c1, w1)] {
        match side {
            Side::XMin => {
                let lo = smt.fma_mode("RTN", t, w, c);
                let hi = smt.fma_mode("RTP", t, w, c);
                // a < t w + c with w > 0 gives t > (a - c) / w >= RTN(RTN(a - c) / w).
                let d = smt.op_mode("fp.sub", "RTN", a, c);
                bounds.push(format!("(fp.lt {} {t})", smt.op_mode("fp.div", "RTN", &d, w)));
                reach.push(format!("(or (fp.lt {a} {lo}) (and (fp.eq {a} {lo}) (fp.lt {lo} {hi})))"));
            }
            Side::XMax => {
                let mc = smt.neg(c);
                let lo = smt.fma_mode("RTN", t, w, &mc);
                let hi = smt.fma_mode("RTP", t, w, &mc);
                // a > t w - c with w > 0 gives t < (a + c) / w <= RTP(RTP(a + c) / w).
                let d = smt.op_mode("fp.add", "RTP", a, c);
                bounds.push(format!("(fp.lt {t} {})", smt.op_mode("fp.div", "RTP", &d, w)));
                reach.push(format!("(or (fp.gt {a} {hi}) (and (fp.eq {a} {hi}) (fp.lt {lo} {hi})))"));
            }
        }
    }
    smt.assert(&format!("(or {})", bounds.join(" ")));
    smt.assert(&format!("(or {})", reach.join(" ")));
}

/// Assert that the tile's far edge lies inside the triangle's largest extent over the
/// lens and the shutter: for x-min, a covered sample has `x < (far_e + c_e) / w_e` for
/// the larger of the two ends (each end's extent is monotone in τ as above), rounded
/// up; x-max mirrors it. Only looser than exact, so no reached tile is excluded.
fn assert_far_reach(smt: &Smt, side: Side, v: &[String; 7], tri: &TriOf<String>, tile: &[String; 4]) {
    let ends = [(&tri.q[2][0], &v[2], &v[4]), (&tri.r[2][0], &v[3], &v[5])];
    let conds: Vec<String> = ends
        .into_iter()
        .map(|(far, c, w)| match side {
            Side::XMin => {
                let n = smt.op_mode("fp.add", "RTP", far, c);
                format!("(fp.lt {} {})", tile[0], smt.op_mode("fp.div", "RTP", &n, w))
            }
            Side::XMax => {
                let n = smt.op_mode("fp.sub", "RTN", far, c);
                format!("(fp.gt {} {})", tile[2], smt.op_mode("fp.div", "RTN", &n, w))
            }
        })
        .collect();
    smt.assert(&format!("(or {})", conds.join(" ")));
}
