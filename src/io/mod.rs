//! Reading and writing, below every other layer: bad input quoted in a bounded prefix
//! ([`quote`]), numbers that may be infinite in JSON ([`num_or_inf`]), and output paths
//! checked before a run and written whole after it ([`output`]).

pub mod num_or_inf;
pub mod output;
pub mod quote;
