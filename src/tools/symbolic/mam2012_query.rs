//! The symbolic query for `mam2012`: f32 inputs in stated ranges for which its tile
//! reject culls a tile that the exact footprint reaches, on either template (the static
//! one of [`super::bbox_query`] or the moving one of [`super::moving_query`]).
//!
//! The method's side is its whole encoded setup and tile answer
//! ([`crate::bounds::mam2012::setup_of`] with the tangent of its own derivation, as
//! the registered method runs it, and [`crate::bounds::mam2012::tile_answer`]): the test
//! runs (none of its disabling conditions holds) and the tile answer says Empty (the u
//! or the v patch leaves no lens range over the tile).

use super::bbox_query::{Side, TemplateCull};
use super::smt::Smt;
use crate::bounds::arith::{F32Arith, TriOf};
use crate::bounds::mam2012::{setup_of, tile_answer};

/// mam2012's tile reject.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mam2012Cull;

impl TemplateCull for Mam2012Cull {
    fn cull(&self, smt: &Smt, _side: Side, tri: &TriOf<String>, tile: &[String; 4]) -> String {
        let (why, s) = setup_of(smt, tri, false);
        let (nonempty, ..) = tile_answer(smt, &s, tile);
        let runs = smt.not(&smt.any(&why));
        smt.and(&runs, &smt.not(&nonempty))
    }
}
