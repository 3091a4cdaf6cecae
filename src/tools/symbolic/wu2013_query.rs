//! The symbolic query for `wu2013-safe` (and its planted slips): f32 inputs in stated
//! ranges for which its tile reject culls a tile that the exact footprint reaches, on
//! either template (the static one of [`super::bbox_query`] or the moving one of
//! [`super::moving_query`]).
//!
//! The method's side is its whole encoded setup and tile answer
//! ([`crate::bounds::wu2013::setup_of`], [`crate::bounds::wu2013::tile_answer`]: stage 1
//! on both axes, then stage 2 on x and on y with their lines), the same code the gate
//! runs: every input finite and the answer's reject. The published `wu2013` is not
//! written over `F32Arith` and has no encoding.

use super::bbox_query::{Side, TemplateCull};
use super::smt::Smt;
use crate::bounds::arith::{F32Arith, TriOf};
use crate::bounds::broken::planted::{NoDn, NoUp};
use crate::bounds::round::{Outward, Round};
use crate::bounds::wu2013::{setup_of, tile_answer};

/// Which arithmetic of wu2013-safe a query encodes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wu2013Arith {
    /// `wu2013-safe`.
    #[default]
    Safe,
    /// `broken/planted-no-up/wu2013-safe`.
    NoUp,
    /// `broken/planted-no-dn/wu2013-safe`.
    NoDn,
}

/// wu2013-safe's tile reject (or a slip's).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Wu2013Cull(pub Wu2013Arith);

/// The tile reject of wu2013-safe in the arithmetic `R`: every input finite (else the
/// method answers the full domain) and the answer Empty.
fn safe_cull<R: Round>(smt: &Smt, tri: &TriOf<String>, tile: &[String; 4]) -> String {
    let (finite, axes) = setup_of::<R, Smt>(smt, tri);
    let a = tile_answer::<R, Smt>(smt, &axes, tile);
    smt.and(&finite, &a.reject)
}

impl TemplateCull for Wu2013Cull {
    fn cull(&self, smt: &Smt, _side: Side, tri: &TriOf<String>, tile: &[String; 4]) -> String {
        match self.0 {
            Wu2013Arith::Safe => safe_cull::<Outward>(smt, tri, tile),
            Wu2013Arith::NoUp => safe_cull::<NoUp>(smt, tri, tile),
            Wu2013Arith::NoDn => safe_cull::<NoDn>(smt, tri, tile),
        }
    }
}

/// The cull of a wu2013-safe method, if `id` is one.
pub fn cull_of(id: &str) -> Option<Wu2013Cull> {
    Some(Wu2013Cull(match id {
        "wu2013-safe" => Wu2013Arith::Safe,
        "broken/planted-no-up/wu2013-safe" => Wu2013Arith::NoUp,
        "broken/planted-no-dn/wu2013-safe" => Wu2013Arith::NoDn,
        _ => return None,
    }))
}
