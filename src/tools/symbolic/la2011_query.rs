//! The symbolic query for `la2011` (and `la2011-safe`): f32 inputs in stated ranges for
//! which the method rejects a tile that the exact footprint reaches.
//!
//! The template is `bbox`'s ([`super::bbox_query::template`]: a static triangle whose
//! left (right) edge is the vertical segment at `(a ∓ c) / w`, the tile
//! `[t - 1, t] x [8, 9]` or `[t, t + 1] x [8, 9]`), and so is the exact side (`a < t w + c`,
//! decided by two fused multiply-adds rounded down and up). The method's side is the whole
//! encoded setup and tile answer of `la2011` ([`crate::bounds::la2011::setup_of`],
//! [`crate::bounds::la2011::tile_answer`]: time chords, lens thresholds and the tile's
//! Empty), with the reject asserted. On this template la2011's time test culls the tile
//! when `fl(fl(a - fl(t w)) - c) > 0` for every vertex and column: the exact difference
//! is `a - t w - c`, so a tile whose column is within a rounding of the edge is the
//! target, as for `bbox`, without a division.
//!
//! Only the x axis's time part of the reject is asserted: when it says Empty the whole
//! answer is Empty (`tile_answer`'s non-empty flag is a conjunction with it), and the
//! lens thresholds' divisions and the y axis stay out of the script. Asserting the
//! whole answer's reject instead made a query z3 4.8.12 did not decide within 900 s.

use super::bbox_query::{Side, TemplateCull};
use super::rounding::{CullArgs, Rounding, WithRound};
use super::smt::Smt;
use crate::bounds::arith::{F32Arith, TriOf};
use crate::bounds::la2011::setup_of;
use crate::bounds::round::Round;

/// la2011's cull on the template, in one of its arithmetics ([`Rounding`]: `la2011`,
/// `la2011-safe` or a planted slip of it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct La2011Cull(pub Rounding);

impl TemplateCull for La2011Cull {
    fn cull(&self, smt: &Smt, _side: Side, tri: &TriOf<String>, tile: &[String; 4]) -> String {
        self.0.with(TimeReject(CullArgs { smt, tri, tile }))
    }
}

/// la2011's setup, the term that its x time part says Empty.
struct TimeReject<'a>(CullArgs<'a>);

impl WithRound<String> for TimeReject<'_> {
    fn run<R: Round>(self) -> String {
        let CullArgs { smt, tri, tile } = self.0;
        let s = setup_of::<R, Smt>(smt, tri);
        let (time_ok, _) = s.x.time::<R, Smt>(smt, &[tile[0].clone(), tile[2].clone()]);
        smt.not(&time_ok)
    }
}

/// The cull of `id`, if it is la2011, la2011-safe or one of its planted slips.
pub fn cull_of(id: &str) -> Option<La2011Cull> {
    Rounding::of(id, "la2011").map(La2011Cull)
}
