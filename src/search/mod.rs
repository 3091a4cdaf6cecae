//! The search for counterexamples and what a user does with one: the randomized search
//! ([`search()`]) and its shrinker ([`shrink()`]) over case files anyone can replay
//! ([`crate::gate::case_file`]), the re-judging of a case file ([`replay()`]), a case in
//! words ([`describe()`], [`explain`]) and the same calls as a library for a bound in no
//! registry ([`counterexamples`]).

pub mod counterexamples;
mod describe;
pub mod explain;
mod find;
mod replay;
mod shrink;

pub use crate::gate::case_file::*;
pub use describe::{describe, describe_with};
pub use find::{
    beyond_line, render_search, search, search_with, Found, KindSeen, RegimeSeen, SearchOptions, SearchReport,
};
pub use replay::{rejudge, rejudge_with, replay, replay_with, Rejudge, Replay, WitnessCheck};
pub use shrink::{shrink, shrink_while};

#[cfg(test)]
mod tests;
