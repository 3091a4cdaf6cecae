//! Bit-precise symbolic counterexamples: a bound written once over
//! [`F32Arith`](crate::bounds::arith::F32Arith) (`src/bounds/arith.rs`) is both the f32
//! method the gate runs ([`Plain`](crate::bounds::arith::Plain)) and an SMT-LIB2 encoding
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
//! - Two slips planted in `bbox-safe` ([`crate::bounds::broken::planted`]), to measure
//!   the search on rare bugs.
//! - `la2011` and `la2011-safe`: the whole setup (the shears `k c` and their enclosures,
//!   the sign classes, the finiteness guard of `-safe`) and the whole tile answer (time
//!   chords, lens thresholds and hulls, the Empty decision, the t, u, v ranges):
//!   `crate::bounds::la2011::setup_of`, `crate::bounds::la2011::tile_answer`.
//! - `mam2012`: the whole setup (the enabling conditions, the screen extent, the Figure 5
//!   corners, the patches) and the tile answer (the reject, u^, v^ and the four
//!   per-sample lines' coefficients): `crate::bounds::mam2012::setup_of`,
//!   `crate::bounds::mam2012::tile_answer`. `mam2012-safe` (and its planted slips): its
//!   setup and tile answer, intervals included (`crate::bounds::mam2012::setup_safe_of`,
//!   `answer_of`; [`mam2012_query`]).
//! - `wu2013-safe` (and its planted slips): the whole setup (the vertices' enclosures
//!   per axis) and the whole tile answer (stage 1's lens hulls, stage 2's time hulls and
//!   padded lines, the reject): `crate::bounds::wu2013::setup_of`,
//!   `crate::bounds::wu2013::tile_answer` ([`wu2013_query`]). The published `wu2013` is
//!   not encoded.
//! - `nilsson2012-depth` and `nilsson2012-depth-safe`: the whole setup (the two moving
//!   planes and their offsets, the vertex boxes, the (w, z) line of the conversion) and
//!   the whole tile answer (the w bounds of the planes over the tile, the depth
//!   interval, the Empty decision): `crate::bounds::nilsson2012_depth::setup_of`,
//!   `crate::bounds::nilsson2012_depth::tile_answer`.
//! - Two slips planted in each of `la2011-safe` and `nilsson2012-depth-safe` (one
//!   outward step dropped on one side; [`rounding`]), for the proofs tied to the code.
//! - `mam2012-hyperplane` (and `-ps`): the tile path only (the planes of Eq. 7-9, the
//!   reject, the range cuts and the clamp), from the f32 setup's edges
//!   (`crate::bounds::mam2012_hyperplane::edges_of`, `tile_answer`); the setup (the
//!   facing test, the edge coefficients) and the `-safe` variants are not encoded.
//!
//! The queries attack the x sides of the box (of the footprint, for la2011) on a
//! template triangle (four inputs): [`bbox_query`] for bbox, bbox-safe and the planted
//! slips, [`la2011_query`] for la2011 and la2011-safe, [`mam2012_query`],
//! [`nilsson2012_query`] and [`wu2013_query`]; the moving template ([`moving_query`], seven inputs) takes
//! every method's cull too. A method's template is a
//! [`family::Family`]; by default the search runs the concolic plan ([`concolic`]):
//! many small queries, each with some inputs fixed, under a deterministic resource
//! limit, in parallel.

pub mod bbox_query;
pub mod concolic;
pub mod family;
pub mod la2011_query;
pub mod mam2012_query;
pub mod moving_query;
pub mod nilsson2012_query;
pub mod prove;
pub mod rounding;
pub mod smt;
pub mod solver;
pub mod wu2013_query;
pub mod z3;
