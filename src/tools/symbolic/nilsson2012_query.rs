//! The symbolic query for `nilsson2012-depth` (and `nilsson2012-depth-safe` and its
//! planted slips): f32 inputs in stated ranges for which the method's tile reject culls
//! a tile that the exact footprint reaches, on either template (the static one of
//! [`super::bbox_query`] or the moving one of [`super::moving_query`]).
//!
//! The method's side is its whole encoded setup and tile answer
//! ([`crate::bounds::nilsson2012_depth::setup_of`] and
//! [`crate::bounds::nilsson2012_depth::tile_answer`]: the two moving planes, the vertex
//! boxes in w and zeta, the w bounds over the tile, the conversion to depth and the
//! Empty decision), with the reject asserted. Both templates put every vertex at one
//! depth `w` (at each shutter end): the screen-parallel triangles on which the
//! published method's plane bound can round below the vertex depth.

use super::bbox_query::{Side, TemplateCull};
use super::rounding::{Rounding, WithRound};
use super::smt::Smt;
use crate::bounds::arith::{F32Arith, TriOf};
use crate::bounds::nilsson2012_depth::{setup_of, tile_answer};
use crate::bounds::round::Round;

/// nilsson2012-depth's tile reject, in one of its arithmetics.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Nilsson2012Cull(pub Rounding);

impl TemplateCull for Nilsson2012Cull {
    fn cull(&self, smt: &Smt, _side: Side, tri: &TriOf<String>, tile: &[String; 4]) -> String {
        self.0.with(Reject { smt, tri, tile })
    }
}

/// The setup and tile answer: the term that the answer is Empty.
struct Reject<'a> {
    smt: &'a Smt,
    tri: &'a TriOf<String>,
    tile: &'a [String; 4],
}

impl WithRound<String> for Reject<'_> {
    fn run<R: Round>(self) -> String {
        let s = setup_of::<R, Smt>(self.smt, self.tri);
        let (nonempty, _) = tile_answer::<R, Smt>(self.smt, &s, self.tile);
        self.smt.not(&nonempty)
    }
}

/// The cull of `id`, if it is nilsson2012-depth, its `-safe` variant or a planted slip
/// of that.
pub fn cull_of(id: &str) -> Option<Nilsson2012Cull> {
    Rounding::of(id, "nilsson2012-depth").map(Nilsson2012Cull)
}
