//! The symbolic query for `nilsson2012-depth` (and `nilsson2012-depth-safe` and its
//! planted slips): f32 inputs in stated ranges for which the method's tile reject culls
//! a tile that the exact footprint reaches, on either template (the static one of
//! [`super::bbox_query`] or the moving one of [`super::moving_query`]).
//!
//! The method's side is its whole encoded setup and tile answer
//! ([`crate::bounds::nilsson2012_depth::setup_of`] and
//! [`crate::bounds::nilsson2012_depth::tile_answer`]: the two moving planes, the vertex
//! boxes in w and zeta, the w bounds over the tile, the conversion to depth and the
//! Empty decision). Both templates put every vertex at one depth `w` (at each shutter
//! end): the screen-parallel triangles on which the published method's plane bound can
//! round below the vertex depth.
//!
//! The method's output is a depth interval as well as the reject, so the query asks for
//! either failure: the tile is culled, **or** its depth interval `[z0, z1]` excludes the
//! depth of the covered samples. The second part is asserted only where that depth is
//! one number: when all six vertices share one `z` and one `w > 0` (the static template;
//! the moving one when its two ends agree), every hit has depth `z / w` exactly, and
//! `z1 < z / w` is `z1 w < z` for the exact product of two f32 values, decided by the
//! product rounded down and up (no real arithmetic; see [`product_below`]).

use super::bbox_query::{Side, TemplateCull};
use super::rounding::{CullArgs, Rounding, WithRound};
use super::smt::Smt;
use crate::bounds::arith::{F32Arith, TriOf};
use crate::bounds::nilsson2012_depth::{setup_of, tile_answer};
use crate::bounds::round::Round;

/// Whether the exact product `x y` of two f32 values is below the f32 value `z`: the
/// product rounded up is below `z`, or the product is not representable and `z` lies
/// above its rounding down (then `z` is the rounding up, the next f32, and the exact
/// product lies strictly below it). NaN gives false.
pub fn product_below(smt: &Smt, x: &str, y: &str, z: &str) -> String {
    let lo = smt.op_mode("fp.mul", "RTN", x, y);
    let hi = smt.op_mode("fp.mul", "RTP", x, y);
    format!("(or (fp.lt {hi} {z}) (and (fp.lt {lo} {z}) (not (fp.eq {lo} {hi}))))")
}

/// Whether the exact product `x y` is above `z`: the mirror image of [`product_below`].
pub fn product_above(smt: &Smt, x: &str, y: &str, z: &str) -> String {
    let lo = smt.op_mode("fp.mul", "RTN", x, y);
    let hi = smt.op_mode("fp.mul", "RTP", x, y);
    format!("(or (fp.gt {lo} {z}) (and (fp.gt {hi} {z}) (not (fp.eq {lo} {hi}))))")
}

/// nilsson2012-depth's tile reject, in one of its arithmetics.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Nilsson2012Cull(pub Rounding);

impl TemplateCull for Nilsson2012Cull {
    fn cull(&self, smt: &Smt, _side: Side, tri: &TriOf<String>, tile: &[String; 4]) -> String {
        self.0.with(Reject(CullArgs { smt, tri, tile }))
    }
    fn depth(&self) -> bool {
        true
    }
}

/// The setup and tile answer: the term that the answer is Empty, or that its depth
/// interval excludes the one depth of a flat triangle's hits.
struct Reject<'a>(CullArgs<'a>);

impl WithRound<String> for Reject<'_> {
    fn run<R: Round>(self) -> String {
        let CullArgs { smt, tri, tile } = self.0;
        let s = setup_of::<R, Smt>(smt, tri);
        let (nonempty, z) = tile_answer::<R, Smt>(smt, &s, tile);
        let (zv, wv) = (&tri.q[0][2], &tri.q[0][3]);
        let mut flat = vec![smt.gt(wv, &smt.lit(0.0))];
        for p in tri.q.iter().chain(&tri.r) {
            flat.push(smt.eq(&p[2], zv));
            flat.push(smt.eq(&p[3], wv));
        }
        let excluded = smt.or(&product_below(smt, &z[1], wv, zv), &product_above(smt, &z[0], wv, zv));
        let wrong_depth = smt.all(&[nonempty.clone(), smt.all(&flat), excluded]);
        smt.or(&smt.not(&nonempty), &wrong_depth)
    }
}

/// The cull of `id`, if it is nilsson2012-depth, its `-safe` variant or a planted slip
/// of that.
pub fn cull_of(id: &str) -> Option<Nilsson2012Cull> {
    Rounding::of(id, "nilsson2012-depth").map(Nilsson2012Cull)
}
