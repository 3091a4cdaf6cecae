//! Bit-precise symbolic counterexamples: a bound written once over [`arith::F32Arith`]
//! is both the f32 method the gate runs ([`arith::Plain`]) and an SMT-LIB2 encoding
//! ([`smt::Smt`], IEEE binary32, round-to-nearest-even, the same operations in the same
//! order), so the encoding cannot drift from the code. `cullproof prove --method ID
//! --symbolic` asks z3 ([`z3`]) for f32 inputs in stated ranges where the method culls
//! a tile that the exact footprint reaches; every model becomes a case that the exact
//! judge decides, and a confirmed one is shrunk and written to the corpus.
//!
//! # What is encoded
//! - `bbox` and `bbox-safe`: the whole setup (every corner value, the box's minimum and
//!   maximum, the finiteness and `w > 0` guards) and the tile reject
//!   (`crate::bounds::bbox::aabb_of`, `crate::bounds::bbox::rejects`).
//! - Two slips planted in `bbox-safe` ([`planted`]), to measure the search on rare bugs.
//!
//! The queries ([`bbox_query`]) attack the x sides of the box on a template triangle
//! (four inputs); the other methods have no encoding yet. A method's template is a
//! [`family::Family`]; by default the search runs the concolic plan ([`concolic`]):
//! many small queries, each with some inputs fixed, under a deterministic resource
//! limit, in parallel.

pub mod arith;
pub mod bbox_query;
pub mod concolic;
pub mod family;
pub mod planted;
pub mod prove;
pub mod smt;
pub mod z3;
