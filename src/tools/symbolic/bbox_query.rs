//! The symbolic queries for `bbox` (and `bbox-safe` and the planted slips): f32 inputs
//! in stated ranges for which the method culls a tile that the exact footprint reaches.
//!
//! # The template
//! Four f32 inputs: `a` (a vertex's clip x), `c` (every vertex's CoC, > 0, the same
//! at both shutter ends), `w` (every vertex's depth) and `t` (the tile's edge). The
//! triangle is static, with vertices `(a, 0)`, `(a, 64 w)` and `(a ± 64 w, 0)` (all at
//! depth `w`, `z = 0.5`, aspect 1), built by the same [`F32Arith`] code in both
//! meanings. Seen from the lens edge `u = -1` (side `x-min`) every vertex is shifted by
//! `-c`, and the triangle's left edge is the vertical segment at
//! `X = (a - c) / w` from `y = 0` to `y = 64` (the third vertex lies 64 pixels to
//! the right). The tile is `[t - 1, t] x [8, 9]`. Side `x-max` mirrors it: third vertex
//! to the left, lens edge `u = +1`, right edge at `X = (a + c) / w`, tile
//! `[t, t + 1] x [8, 9]`.
//!
//! # The exact side, in pure floating point
//! For side `x-min` the tile holds covered samples (at `u` near -1, `y` in (8, 9), `x`
//! in `(X, t]`) when `X < t` exactly, that is `a < t w + c` (w > 0). With `lo` and `hi`
//! that real number rounded down and up (`fp.fma RTN t w c` and `fp.fma RTP t w c`,
//! one rounding each), `a < t w + c` exactly iff `a < lo`, or `a = lo` and `lo < hi`
//! (then `lo` is below the real value). Side `x-max` asks `a > t w - c` the same way.
//! No real arithmetic: the query stays in the floating-point theory.
//!
//! One redundant constraint helps the solver without changing the set of solutions: the
//! exact side implies a bound on the tile's edge `t` computed with directed roundings
//! (x-min: `a < t w + c` with `w > 0` gives `t > (a - c) / w`, and `(a - c) / w >=
//! RTN(RTN(a - c) / w)` because both roundings go down and `w > 0`; x-max the mirror
//! with RTP). When `a`, `c` and `w` are fixed the bound is a constant, and the solver
//! places `t` in the gap between it and the method's box without searching through the
//! multiplications of the exact side. The solver's
//! answer is a hint, never a verdict: every model becomes a case that the exact judge
//! decides.

use super::family::Family;
use super::prove::Rule;
use super::smt::Smt;
use crate::bounds::arith::{F32Arith, Plain, TriOf};
use crate::bounds::bbox::aabb_of;

/// Which side of the box a query attacks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Side {
    XMin,
    XMax,
}

impl Side {
    pub fn name(self) -> &'static str {
        match self {
            Side::XMin => "x-min",
            Side::XMax => "x-max",
        }
    }
    /// The side of a [`Family`] side index.
    pub fn of(i: usize) -> Side {
        if i == 0 {
            Side::XMin
        } else {
            Side::XMax
        }
    }
}

/// The names of the inputs, in order.
pub const INPUTS: [&str; 4] = ["a", "c", "w", "t"];

/// The default range sets of the x-min side: a middle set in which inputs can coincide
/// (`a` and `c` overlap; the f32 culls are densest there, about one triangle in 140
/// drawn uniformly admits a culled tile) and wide ranges. The x-max side mirrors them.
/// Narrower ranges (e.g. `a=128:256,c=1:2,w=1.875:2,t=0:256`, about one in 5000) are a
/// `--ranges` away.
const SETS: [[[f32; 2]; 4]; 2] = [
    [[-64.0, 64.0], [0.5, 64.0], [0.5, 4.0], [-256.0, 256.0]],
    [[-4096.0, 4096.0], [0.25, 64.0], [0.25, 64.0], [-16384.0, 16384.0]],
];

/// The ranges of the other side: `a` and `t` negated (the x-max template is the
/// mirror image of the x-min one).
fn mirrored(r: [[f32; 2]; 4]) -> [[f32; 2]; 4] {
    let neg = |x: [f32; 2]| [-x[1], -x[0]];
    [neg(r[0]), r[1], r[2], neg(r[3])]
}

/// What a method says on a template: the term that it culls the template's tile of
/// `side` (the tile `[x0, y0, x1, y1]`, the triangle built by [`template`] or the moving
/// template's). Defining terms go into `smt`; the query asserts the returned term.
pub trait TemplateCull: Sync {
    fn cull(&self, smt: &Smt, side: Side, tri: &TriOf<String>, tile: &[String; 4]) -> String;
    /// When only some parts of the method are encoded (a conjunction whose other parts
    /// can only cull more): the parts left out. A model is still a counterexample (the
    /// judge runs the whole method), but an `unsat` proves nothing.
    fn partial(&self) -> Option<&'static str> {
        None
    }
    /// Whether the term also holds where the method keeps the tile but its depth
    /// interval excludes the covered samples' depth (a depth bound's failure).
    fn depth(&self) -> bool {
        false
    }
}

/// The query family of every method on this template: the inputs, sides, ranges and
/// exact side are the template's, the cull is the method's ([`TemplateCull`]).
#[derive(Clone, Copy, Debug)]
pub struct TemplateFamily<C>(pub C);

impl<C: TemplateCull> Family for TemplateFamily<C> {
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
        &[3]
    }
    fn default_ranges(&self, side: usize) -> Vec<Vec<[f32; 2]>> {
        SETS.iter().map(|r| if side == 0 { r.to_vec() } else { mirrored(*r).to_vec() }).collect()
    }
    fn check_range(&self, k: usize, lo: f32, _hi: f32) -> Result<(), String> {
        if (k == 1 || k == 2) && lo <= 0.0 {
            return Err(format!(
                "the range of `{}` must be positive (the template has c > 0 and w > 0), not from {lo}",
                INPUTS[k]
            ));
        }
        Ok(())
    }
    fn assert_reached(&self, smt: &Smt, side: usize, v: &[String]) {
        let (side, v) = (Side::of(side), [v[0].clone(), v[1].clone(), v[2].clone(), v[3].clone()]);
        let (tri, tile) = template(smt, side, &v);
        assert_reach(smt, side, &v);
        assert_far_reach(smt, side, &v, &tri, &tile);
    }
    fn assert_violation(&self, smt: &Smt, side: usize, v: &[String]) {
        let (s, w) = (Side::of(side), [v[0].clone(), v[1].clone(), v[2].clone(), v[3].clone()]);
        let (tri, tile) = template(smt, s, &w);
        smt.assert(&self.0.cull(smt, s, &tri, &tile));
        self.assert_reached(smt, side, v);
    }
    fn instance(&self, side: usize, v: &[f32]) -> (crate::model::Triangle, crate::model::Tile) {
        instance(Side::of(side), [v[0], v[1], v[2], v[3]])
    }
}

/// The template triangle and tile `[x0, y0, x1, y1]` of a side, from the inputs
/// `a, c, w, t`, in either meaning.
pub fn template<A: F32Arith>(ar: &A, side: Side, v: &[A::F; 4]) -> (TriOf<A::F>, [A::F; 4]) {
    let [a, c, w, t] = v;
    let h = ar.mul(&ar.lit(64.0), w);
    let far = match side {
        Side::XMin => ar.add(a, &h),
        Side::XMax => ar.sub(a, &h),
    };
    let (zero, z) = (ar.lit(0.0), ar.lit(0.5));
    let p = [
        [a.clone(), zero.clone(), z.clone(), w.clone()],
        [a.clone(), h.clone(), z.clone(), w.clone()],
        [far, zero, z, w.clone()],
    ];
    let cs = [c.clone(), c.clone(), c.clone()];
    let tri = TriOf { q: p.clone(), r: p, c0: cs.clone(), c1: cs, k: ar.lit(1.0) };
    let one = ar.lit(1.0);
    let tile = match side {
        Side::XMin => [ar.sub(t, &one), ar.lit(8.0), t.clone(), ar.lit(9.0)],
        Side::XMax => [t.clone(), ar.lit(8.0), ar.add(t, &one), ar.lit(9.0)],
    };
    (tri, tile)
}

/// bbox's cull under one corner rule (bbox, bbox-safe or a planted slip): its setup and
/// tile reject on the template.
impl TemplateCull for Rule {
    fn cull(&self, smt: &Smt, side: Side, tri: &TriOf<String>, tile: &[String; 4]) -> String {
        let (enabled, bx) = aabb_of(smt, self, tri);
        // The method's reject is `enabled` and one of four disjoint-side tests; the query
        // asserts the side it attacks (a model satisfies the whole reject, and z3 need
        // not rule out the y sides, whose terms then drop out of the query).
        let cull = match side {
            Side::XMin => smt.lt(&tile[2], &bx[0]),
            Side::XMax => smt.gt(&tile[0], &bx[1]),
        };
        smt.and(&enabled, &cull)
    }
}

/// Assert that the template's exact footprint reaches into the tile of `side`:
/// `a < t w + c` for x-min, `a > t w - c` for x-max, decided by two fused
/// multiply-adds rounded down and up, with one implied bound on `t` that spares the
/// solver the search through the multiplications. Shared by every family on this
/// template.
pub fn assert_reach(smt: &Smt, side: Side, v: &[String; 4]) {
    let [a, c, w, t] = v;
    let reach = match side {
        Side::XMin => {
            let lo = smt.fma_mode("RTN", t, w, c);
            let hi = smt.fma_mode("RTP", t, w, c);
            // Implied: a < t w + c with w > 0 gives t > (a - c) / w >= RTN(RTN(a - c) / w).
            let d = smt.op_mode("fp.sub", "RTN", a, c);
            let bound = smt.op_mode("fp.div", "RTN", &d, w);
            smt.assert(&format!("(fp.lt {bound} {t})"));
            format!("(or (fp.lt {a} {lo}) (and (fp.eq {a} {lo}) (fp.lt {lo} {hi})))")
        }
        Side::XMax => {
            let mc = smt.neg(c);
            let lo = smt.fma_mode("RTN", t, w, &mc);
            let hi = smt.fma_mode("RTP", t, w, &mc);
            // Implied: a > t w - c with w > 0 gives t < (a + c) / w <= RTP(RTP(a + c) / w).
            let d = smt.op_mode("fp.add", "RTP", a, c);
            let bound = smt.op_mode("fp.div", "RTP", &d, w);
            smt.assert(&format!("(fp.lt {t} {bound})"));
            format!("(or (fp.gt {a} {hi}) (and (fp.eq {a} {hi}) (fp.lt {lo} {hi})))")
        }
    };
    smt.assert(&reach);
}

/// Assert the other half of "reached": the tile's far edge lies before the triangle's
/// far edge at the tile's nearest row. For x-min the vertices are `(a, 0)`, `(a, 64 w)`
/// and `(far, 0)` (`far` the f32 `a + 64 w` of the template, `64 w` exact), so on the
/// screen the far edge at row `y` is `x = far / w - s y` with the slope
/// `s = (far - a) / (64 w)`, the largest over the tile's rows `[8, 9]` at `y = 8`:
/// `(7 far + a) / (8 w)`. Seen from lens point `(u, v)` every vertex moves by
/// `(u c / w, v c / w)` (aspect 1), which moves that edge at a fixed row by
/// `(u + s v) c / w`, at most `(1 + s) c / w` (`u = v = 1`). So the bound is
/// `x0 < (7 far + a + 8 c + c (far - a) / (8 w)) / (8 w)`; x-max mirrors it with
/// `x1 > (7 far + a - 8 c - c (a - far) / (8 w)) / (8 w)`. Computed rounded away from
/// the tile (RTP for x-min, RTN for x-max; `8 c` and `8 w` are exact), it excludes no
/// reached tile. It is exact as well (no tile beyond it is reached) when `c / w <= 8`,
/// so that the row the lens brings to `y = 8` lies inside the triangle: the triangle is
/// about 56 px wide there, so the `u` that puts the near edge before the tile and the
/// `u` that puts the far edge after it overlap. Without this bound a solver may place
/// the tile beyond the triangle's far edge: there every method culls it rightly, and a
/// method whose depth interval is wrong everywhere (a planted slip of
/// nilsson2012-depth-safe) fails on it too, each a model the judge finds empty, not a
/// violation; and on wide ranges an `unsat` could not be had. An earlier form bounded
/// `x0` by the far vertex, `(far + c) / w`, up to 8 px too far at these rows.
fn assert_far_reach(smt: &Smt, side: Side, v: &[String; 4], tri: &TriOf<String>, tile: &[String; 4]) {
    let (a, c, w, far) = (&v[0], &v[1], &v[2], &tri.q[2][0]);
    let eight = smt.lit(8.0);
    let (c8, w8) = (smt.mul(&eight, c), smt.mul(&eight, w));
    let seven_far = |mode: &str| smt.op_mode("fp.mul", mode, &smt.lit(7.0), far);
    // c |far - a| / (8 w), rounded up: the lens's vertical part, moved along the slope.
    let tilt = |d: &str| smt.op_mode("fp.div", "RTP", &smt.op_mode("fp.mul", "RTP", c, d), &w8);
    let cond = match side {
        Side::XMin => {
            let p = tilt(&smt.op_mode("fp.sub", "RTP", far, a));
            let n = smt.op_mode("fp.add", "RTP", &smt.op_mode("fp.add", "RTP", &seven_far("RTP"), a), &c8);
            let e = smt.op_mode("fp.div", "RTP", &smt.op_mode("fp.add", "RTP", &n, &p), &w8);
            format!("(fp.lt {} {e})", tile[0])
        }
        Side::XMax => {
            let p = tilt(&smt.op_mode("fp.sub", "RTP", a, far));
            let n = smt.op_mode("fp.sub", "RTN", &smt.op_mode("fp.add", "RTN", &seven_far("RTN"), a), &c8);
            let e = smt.op_mode("fp.div", "RTN", &smt.op_mode("fp.sub", "RTN", &n, &p), &w8);
            format!("(fp.gt {} {e})", tile[2])
        }
    };
    smt.assert(&cond);
}

/// The triangle and tile of a model's inputs, computed in f32 by the same template.
pub fn instance(side: Side, inputs: [f32; 4]) -> (crate::model::Triangle, crate::model::Tile) {
    let (tri, t) = template(&Plain, side, &inputs);
    (tri.triangle(), crate::model::Tile { x0: t[0], y0: t[1], x1: t[2], y1: t[3] })
}
