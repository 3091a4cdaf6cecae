//! The enclosure check: the composition of a `-safe` variant's rounding argument,
//! machine-checked over the method's own code for **every** input
//! (`docs/proofs.md`, section 4c).
//!
//! The variant's f32 code (written once over [`crate::bounds::arith::F32Arith`], the
//! description the gate runs) is run once over [`Trace`], an instance that records every
//! operation instead of computing it: the code's whole data flow for symbolic inputs, as
//! one graph (equal operations on equal operands are one node). Over that graph
//! [`Check`] gives each value a **direction** towards its **exact value** (the same
//! operations in real arithmetic, without rounding or outward steps, along the branches
//! the f32 code takes): exact, a lower or an upper end, or the rounding to nearest of a
//! real with one of those directions (a result before its outward step).
//!
//! Directions follow fixed rules: rounding then stepping outward in the right direction
//! encloses (STEP, `step.smt2`); sums, products by a factor of known sign, products of
//! ends of one sign, quotients by a divisor of one strict sign, min and max of ends
//! (NaN-free operands, or a min that gives NaN on a NaN operand), the min or max of the
//! four end products or quotients of two intervals, `max(|lo|, |hi|)` of one interval,
//! comparisons of ends; and from MONO, an end moved outward by a literal and a rounded
//! end compared with 0. The rules, read as statements about reals, are proven by z3 in
//! `src/bounds/proofs/enclosure_rules.smt2` (the script `enclosure rules`). Conditions
//! the code tests become facts inside their branch (signs, finiteness, NaN-freedom,
//! exact products). A value no rule covers is no end.
//!
//! The check demands that every output end of the tile answer is an end of its side and
//! NaN-free, that every cull implies its counterpart over the exact values, and that every
//! value the code pins (`F32Arith::pin`, `pin_range`: a step whose argument is a named
//! lemma; `F32Arith::pin_same`: an interval of a value the lemma equates with another)
//! is an end of the side the lemma needs, and that every shortcut the code declares
//! (`F32Arith::select_same`) keeps its exact value: both branches one polynomial under
//! the condition's equalities (`check::same`). Values the code may choose freely
//! (`F32Arith::choose`, `choose_truth`) are taken as exact and listed. A lemma about a
//! whole formula (bbox-safe's Gappa-proven pad) is declared on the formula built from the
//! script's own constants ([`Trace::known_end`]); it reaches the code only where the code
//! computes exactly that formula.
//!
//! What stays an argument: the method's derivation in real arithmetic (that the exact
//! values bound the covered samples), the lemmas whose names begin with "derivation",
//! and that the branches the f32 code takes on its ends are ones the exact values allow.
//!
//! - [`trace`]: the recording arithmetic;
//! - [`check`](mod@check): the directions, their rules, the facts of branches, the demands;
//! - [`variants`]: the variants traced, and what each must show.

pub mod check;
pub mod trace;
pub mod variants;

pub use check::{Check, Failure, Outcome};
pub use trace::{Bn, Trace, N};
pub use variants::{
    check, check_bbox_with, check_lb2011_with, check_traced, check_wu2013_with, BBOX_LEMMA, CHECKED, WU_LEMMA,
};
