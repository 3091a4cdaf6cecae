//! `cullproof proofs`: the tool that re-runs the proofs for all inputs. What is proven,
//! by which scripts, and the checks that tie the scripts to the code are declared with
//! the bounds ([`crate::bounds::proofs`]); this module runs them and adds the one
//! obligation that needs the symbolic search.
//!
//! - [`cli`]: the command (its arguments, the runs, the report and its tables).
//! - [`composition`]: for `la2011-safe`, the composition over the method's own f32
//!   code, as SMT queries on a template's ranges.

pub mod cli;
pub mod composition;
