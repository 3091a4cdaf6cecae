//! The four arithmetics of a method written with the shared rounding discipline
//! ([`crate::bounds::round`]): the published one, the `-safe` one, and the two planted
//! slips of the `-safe` one ([`crate::bounds::broken::planted`]), named by method id.

use super::smt::Smt;
use crate::bounds::arith::TriOf;
use crate::bounds::broken::planted::{NoDn, NoUp};
use crate::bounds::round::{Nearest, Outward, Round};

/// Which [`Round`] a method id runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rounding {
    /// The published method: rounded to nearest.
    Nearest,
    /// The `-safe` variant: every rounding stepped outward.
    Outward,
    /// The planted slips: the upper (lower) ends' steps dropped.
    NoUp,
    NoDn,
}

impl Rounding {
    /// The arithmetic of `id` if it is `base`, `base-safe` or one of the planted slips of
    /// `base-safe`.
    pub fn of(id: &str, base: &str) -> Option<Rounding> {
        let safe = format!("{base}-safe");
        if id == base {
            Some(Rounding::Nearest)
        } else if id == safe {
            Some(Rounding::Outward)
        } else if id == format!("broken/planted-no-up/{safe}") {
            Some(Rounding::NoUp)
        } else if id == format!("broken/planted-no-dn/{safe}") {
            Some(Rounding::NoDn)
        } else {
            None
        }
    }

    /// Run `f` with this arithmetic's [`Round`].
    pub fn with<T>(self, f: impl WithRound<T>) -> T {
        match self {
            Rounding::Nearest => f.run::<Nearest>(),
            Rounding::Outward => f.run::<Outward>(),
            Rounding::NoUp => f.run::<NoUp>(),
            Rounding::NoDn => f.run::<NoDn>(),
        }
    }
}

/// Code generic over a [`Round`], run by [`Rounding::with`].
pub trait WithRound<T> {
    fn run<R: Round>(self) -> T;
}

/// What a template cull reads: the SMT builder, the template's triangle and its tile.
#[derive(Clone, Copy)]
pub struct CullArgs<'a> {
    pub smt: &'a Smt,
    pub tri: &'a TriOf<String>,
    pub tile: &'a [String; 4],
}
