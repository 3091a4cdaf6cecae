//! The symbolic query for `mam2012`: f32 inputs in stated ranges for which its tile
//! reject culls a tile that the exact footprint reaches, on either template (the static
//! one of [`super::bbox_query`] or the moving one of [`super::moving_query`]).
//!
//! The method's side is its whole encoded setup and tile answer
//! ([`crate::bounds::mam2012::setup_of`] with the tangent of its own derivation, as
//! the registered method runs it, and [`crate::bounds::mam2012::tile_answer`]): the test
//! runs (none of its disabling conditions holds) and the tile answer says Empty (the u
//! or the v patch leaves no lens range over the tile). `mam2012-safe` (and its planted
//! slips) the same way: [`crate::bounds::mam2012::setup_safe_of`] and
//! [`crate::bounds::mam2012::answer_of`] on both axes, the u axis first.

use super::bbox_query::{Side, TemplateCull};
use super::smt::Smt;
use crate::bounds::arith::{F32Arith, TriOf};
use crate::bounds::broken::planted::{NoDn, NoUp};
use crate::bounds::mam2012::{answer_of, rejects_of, setup_of, setup_safe_of, tile_answer};
use crate::bounds::round::{Outward, Round};

/// Which arithmetic of mam2012 a query encodes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Mam2012Arith {
    /// The published test (f32, round to nearest).
    #[default]
    Published,
    /// `mam2012-safe`.
    Safe,
    /// `broken/planted-no-up/mam2012-safe`.
    NoUp,
    /// `broken/planted-no-dn/mam2012-safe`.
    NoDn,
}

/// mam2012's tile reject (or mam2012-safe's, or a slip's).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Mam2012Cull(pub Mam2012Arith);

/// The tile reject of mam2012-safe in the arithmetic `R`.
fn safe_cull<R: Round>(smt: &Smt, tri: &TriOf<String>, tile: &[String; 4]) -> String {
    let (why, axes) = setup_safe_of::<R, Smt>(smt, tri);
    let u = answer_of::<R, Smt>(smt, &axes[0], &tile[0], &tile[2]);
    let v = answer_of::<R, Smt>(smt, &axes[1], &tile[1], &tile[3]);
    rejects_of(smt, &why, &u, &v)
}

impl TemplateCull for Mam2012Cull {
    fn cull(&self, smt: &Smt, _side: Side, tri: &TriOf<String>, tile: &[String; 4]) -> String {
        match self.0 {
            Mam2012Arith::Published => {
                let (why, s) = setup_of(smt, tri, false);
                let (nonempty, ..) = tile_answer(smt, &s, tile);
                let runs = smt.not(&smt.any(&why));
                smt.and(&runs, &smt.not(&nonempty))
            }
            Mam2012Arith::Safe => safe_cull::<Outward>(smt, tri, tile),
            Mam2012Arith::NoUp => safe_cull::<NoUp>(smt, tri, tile),
            Mam2012Arith::NoDn => safe_cull::<NoDn>(smt, tri, tile),
        }
    }
}

/// The cull of a mam2012 method, if `id` is one.
pub fn cull_of(id: &str) -> Option<Mam2012Cull> {
    Some(Mam2012Cull(match id {
        "mam2012" => Mam2012Arith::Published,
        "mam2012-safe" => Mam2012Arith::Safe,
        "broken/planted-no-up/mam2012-safe" => Mam2012Arith::NoUp,
        "broken/planted-no-dn/mam2012-safe" => Mam2012Arith::NoDn,
        _ => return None,
    }))
}
