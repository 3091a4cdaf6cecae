//! The tools built on the gate and the search: how tight each bound is and what it
//! costs ([`tightness`]), where each method fails as an input moves towards a limit
//! ([`stability`]), the SMT search for f32 counterexamples ([`symbolic`]) and the
//! proofs for all inputs ([`proofs`]).

pub mod proofs;
pub mod stability;
pub mod symbolic;
pub mod tightness;
