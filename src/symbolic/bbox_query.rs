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
//! No division, no reals: the query stays in the floating-point theory. The solver's
//! answer is a hint, never a verdict: every model becomes a case that the exact judge
//! decides.

use super::arith::{F32Arith, Plain, TriOf};
use super::smt::Smt;
use crate::bounds::bbox::{aabb_of, Corner};
use anyhow::{bail, Result};

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
}

/// The names of the inputs, in order.
pub const INPUTS: [&str; 4] = ["a", "c", "w", "t"];

/// One query: a side and a half-open range `[lo, hi)` per input.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Query {
    pub side: Side,
    pub ranges: [[f32; 2]; 4],
}

impl Query {
    /// The ranges as `a=LO:HI,c=...` (the syntax of `--ranges`).
    pub fn ranges_text(&self) -> String {
        INPUTS.iter().zip(&self.ranges).map(|(n, r)| format!("{n}={}:{}", r[0], r[1])).collect::<Vec<_>>().join(",")
    }
}

/// The default queries, each on both sides: inputs confined to a few binades (the
/// solver finds rounding coincidences far faster there), a middle set in which inputs
/// can coincide (`a` and `c` overlap), and wide ranges.
pub fn default_queries() -> Vec<Query> {
    let sets: [[[f32; 2]; 4]; 3] = [
        [[64.0, 256.0], [1.0, 2.0], [1.0, 2.0], [64.0, 128.0]],
        [[-64.0, 64.0], [0.5, 64.0], [0.5, 4.0], [-64.0, 64.0]],
        [[-4096.0, 4096.0], [0.25, 64.0], [0.25, 64.0], [-4096.0, 4096.0]],
    ];
    let mut out = Vec::new();
    for r in sets {
        out.push(Query { side: Side::XMin, ranges: r });
        out.push(Query { side: Side::XMax, ranges: mirrored(r) });
    }
    out
}

/// The ranges of the other side: `a` and `t` negated (the x-max template is the
/// mirror image of the x-min one).
fn mirrored(r: [[f32; 2]; 4]) -> [[f32; 2]; 4] {
    let neg = |x: [f32; 2]| [-x[1], -x[0]];
    [neg(r[0]), r[1], r[2], neg(r[3])]
}

/// Parse `--ranges a=LO:HI,c=LO:HI,w=LO:HI,t=LO:HI` (every input named once; c and w
/// positive, each range non-empty) into one query per side.
pub fn parse_ranges(flag: &str, s: &str) -> Result<Vec<Query>> {
    let mut ranges: [Option<[f32; 2]>; 4] = [None; 4];
    for part in s.split(',') {
        let Some((name, r)) = part.trim().split_once('=') else {
            bail!("{flag} {s}: `{part}` is not NAME=LO:HI (names: a, c, w, t)");
        };
        let Some(k) = INPUTS.iter().position(|n| *n == name.trim()) else {
            bail!("{flag} {s}: `{name}` is not an input (names: a, c, w, t)");
        };
        let Some((lo, hi)) = r.split_once(':') else {
            bail!("{flag} {s}: `{r}` for `{name}` is not LO:HI");
        };
        let num = |v: &str| -> Result<f32> {
            match v.trim().parse::<f32>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => bail!("{flag} {s}: `{v}` for `{name}` is not a finite number"),
            }
        };
        let (lo, hi) = (num(lo)?, num(hi)?);
        if lo >= hi {
            bail!("{flag} {s}: the range {lo}:{hi} of `{name}` is empty (LO must be below HI)");
        }
        if (k == 1 || k == 2) && lo <= 0.0 {
            bail!(
                "{flag} {s}: the range of `{name}` must be positive (the template has c > 0 and w > 0), not from {lo}"
            );
        }
        if ranges[k].replace([lo, hi]).is_some() {
            bail!("{flag} {s}: `{name}` is given twice");
        }
    }
    let mut out = [[0.0f32; 2]; 4];
    for (k, r) in ranges.iter().enumerate() {
        match r {
            Some(r) => out[k] = *r,
            None => bail!("{flag} {s}: no range for `{}` (give a, c, w and t)", INPUTS[k]),
        }
    }
    Ok(vec![Query { side: Side::XMin, ranges: out }, Query { side: Side::XMax, ranges: out }])
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

/// The SMT-LIB2 script of a query against a corner rule: the inputs in their ranges,
/// the method's setup and tile reject on the template (the reject asserted), and the
/// exact footprint reaching into the tile.
pub fn script<C: Corner>(corner: &C, q: &Query) -> String {
    let smt = Smt::new();
    let v = INPUTS.map(|n| smt.var(n));
    for (name, r) in v.iter().zip(&q.ranges) {
        smt.range(name, r[0], r[1]);
    }
    let (tri, tile) = template(&smt, q.side, &v);
    let (enabled, bx) = aabb_of(&smt, corner, &tri);
    // The method's reject is `enabled` and one of four disjoint-side tests; the query
    // asserts the side it attacks (a model satisfies the whole reject, and z3 need not
    // rule out the y sides, whose terms then drop out of the query).
    let side = match q.side {
        Side::XMin => smt.lt(&tile[2], &bx[0]),
        Side::XMax => smt.gt(&tile[0], &bx[1]),
    };
    smt.assert(&smt.and(&enabled, &side));
    let [a, c, w, t] = &v;
    let reach = match q.side {
        Side::XMin => {
            let lo = smt.fma_mode("RTN", t, w, c);
            let hi = smt.fma_mode("RTP", t, w, c);
            format!("(or (fp.lt {a} {lo}) (and (fp.eq {a} {lo}) (fp.lt {lo} {hi})))")
        }
        Side::XMax => {
            let mc = smt.neg(c);
            let lo = smt.fma_mode("RTN", t, w, &mc);
            let hi = smt.fma_mode("RTP", t, w, &mc);
            format!("(or (fp.gt {a} {hi}) (and (fp.eq {a} {hi}) (fp.lt {lo} {hi})))")
        }
    };
    smt.assert(&reach);
    smt.script(&v)
}

/// The triangle and tile of a model's inputs, computed in f32 by the same template.
pub fn instance(side: Side, inputs: [f32; 4]) -> (crate::model::Triangle, crate::model::Tile) {
    let (tri, t) = template(&Plain, side, &inputs);
    (tri.triangle(), crate::model::Tile { x0: t[0], y0: t[1], x1: t[2], y1: t[3] })
}
