//! `cullproof proofs`: the tool that re-runs the proofs for all inputs. What is proven,
//! by which scripts, and the checks that tie the scripts to the code are declared with
//! the bounds ([`crate::bounds::proofs`]); this module runs them and adds the checks
//! that read the code itself.
//!
//! - [`check`], [`run`]: the checks that tie the scripts to the code, and a script run
//!   with its tool (the command: [`crate::cli::proofs`]).
//! - [`enclosure`]: for `bbox-safe`, `la2011-safe` and `nilsson2012-depth-safe`, the
//!   composition over the method's own f32 code, for every input (the code traced, each
//!   end and cull checked by rules z3 proves);
//! - [`composition`]: for `la2011-safe`, the composition over the method's own f32
//!   code, as SMT queries on a template's ranges.

pub mod check;
pub mod composition;
pub mod enclosure;
pub mod run;
