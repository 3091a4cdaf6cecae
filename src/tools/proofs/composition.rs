//! The composition over the code, machine-checked on a template: for `la2011-safe`
//! (a variant with a symbolic encoding), the method's own f32 code (the
//! description the gate runs, written once over `F32Arith`) is emitted as one SMT-LIB 2
//! query per side of the tile, every input free in the template's ranges, asking for a
//! tile the method culls although the exact footprint reaches it. Every side must come
//! back `unsat`, with the query's hypotheses (its ranges, and a tile the exact footprint
//! reaches) shown satisfiable by the same solver (an `unsat` of contradictory
//! hypotheses, or of ranges that hold no reached tile, proves nothing). A `sat` is judged exactly and,
//! when confirmed, is a counterexample to the claim.
//!
//! Unlike the rounding lemmas (which never look at the code), this obligation reads the
//! code: a dropped outward step, a halved pad or a swapped min/max changes the query
//! and is found (`tests/proofs.rs` plants such slips). It covers the template only: a
//! static triangle with one edge on the x axis, vertex `a` on the axis, half-width
//! `c` of its circle of confusion, depth `w` and tile offset `t` in the ranges of
//! [`TEMPLATE_RANGES`]. Over every f32 input the composition is checked by the
//! enclosure check ([`super::enclosure`]); this query is a second, independent check of
//! it on the template. On wide ranges the solvers time out (measured: four
//! 200 s timeouts for `la2011-safe` on the family's default ranges). `bbox-safe` has the
//! same encoding but its template queries time out even on these ranges (both sides at
//! 600 s, about 190 s of CPU per solver, 2026-12-05), so it has no obligation here.

use crate::tools::symbolic::family::parse_ranges;
use crate::tools::symbolic::prove::{self, Limits, Strategy, Template};
use crate::tools::symbolic::solver::Solvers;
use crate::tools::symbolic::z3::Answer;
use serde::Serialize;
use std::time::Duration;

/// The template ranges the composition is checked on (names of the symbolic family:
/// `a` the vertex on the axis, `c` the CoC, `w` the depth, `t` the tile's offset).
pub const TEMPLATE_RANGES: &str = "a=128:256,c=1:2,w=1.875:2,t=96:128";

/// The variants whose composition is checked on the template.
pub const CHECKED: &[&str] = &["la2011-safe"];

/// Whether `id` has a composition obligation: a variant of [`CHECKED`], or a planted
/// slip of one (`broken/planted-*/ID`, for the tests that show the obligation fails).
pub fn applies(id: &str) -> bool {
    CHECKED.contains(&id)
        || (id.starts_with("broken/planted-")
            && CHECKED.iter().any(|c| id.ends_with(&format!("/{c}")))
            && prove::ENCODED.contains(&id))
}

/// One side's query.
#[derive(Clone, Debug, Serialize)]
pub struct SideRun {
    pub method: String,
    pub side: &'static str,
    pub ranges: &'static str,
    /// `sat`, `unsat`, `unknown`, `timeout` or `budget`.
    pub answer: &'static str,
    /// The solver whose answer it is.
    pub solver: &'static str,
    /// On `unsat`: the query's ranges, with a tile the exact footprint reaches, were found
    /// satisfiable.
    pub hypotheses_sat: Option<bool>,
    pub seconds: f64,
    /// None when the side is proven; what went wrong otherwise.
    pub error: Option<String>,
}

/// Run the obligation of `id` (see [`applies`]): one query per side, each side with
/// `limit` of wall clock, z3 and Bitwuzla side by side (the first answer wins).
pub fn run(id: &str, limit: Duration) -> Vec<SideRun> {
    let fail = |e: String| {
        vec![SideRun {
            method: id.to_string(),
            side: "-",
            ranges: TEMPLATE_RANGES,
            answer: "unknown",
            solver: "-",
            hypotheses_sat: None,
            seconds: 0.0,
            error: Some(e),
        }]
    };
    let Some(m) = crate::bounds::by_id(id).or_else(|| crate::bounds::broken::parse(id)) else {
        return fail(format!("`{id}` is not a method id"));
    };
    let fam = match prove::family(id, Template::Static) {
        Ok(f) => f,
        Err(e) => return fail(format!("{e:#}")),
    };
    let ranges = match parse_ranges(fam.as_ref(), "template", TEMPLATE_RANGES) {
        Ok(r) => r,
        Err(e) => return fail(format!("{e:#}")),
    };
    let sets = prove::range_sets(fam.as_ref(), Some(ranges));
    let plan = prove::queries(fam.as_ref(), Strategy::Whole, &sets, 1, sets.len(), 0.0);
    let limits = Limits { timeout: limit.as_secs_f64().max(1.0), rlimit: None, jobs: 2, solvers: Solvers::BOTH };
    let r = match prove::prove(m, Template::Static, Strategy::Whole, 1, &plan, limits, None, None, false) {
        Ok(r) => r,
        Err(e) => return fail(format!("{e:#}")),
    };
    let mut out: Vec<SideRun> = r
        .queries
        .iter()
        .map(|q| {
            let error = match (q.answer, q.hypotheses_sat) {
                (Answer::Unsat, Some(true)) => None,
                (Answer::Sat, _) if q.confirmed => Some(format!(
                    "counterexample: the method culls a tile the exact footprint reaches ({}; {})",
                    fam.inputs()
                        .iter()
                        .zip(q.inputs.clone().unwrap_or_default())
                        .map(|(n, v)| format!("{n}={v:e}"))
                        .collect::<Vec<_>>()
                        .join(", "),
                    q.judged.clone().unwrap_or_default()
                )),
                (Answer::Sat, _) => Some(format!(
                    "a model the exact judge did not confirm ({}): neither proof nor counterexample",
                    q.judged.clone().unwrap_or_default()
                )),
                (Answer::Unknown, Some(false)) => {
                    Some("unsat not counted: the ranges with a reached tile were not shown satisfiable".into())
                }
                (a, _) => Some(format!("{}: no answer within the limit", a.name())),
            };
            SideRun {
                method: id.to_string(),
                side: q.side,
                ranges: TEMPLATE_RANGES,
                answer: q.answer.name(),
                solver: q.solver.name(),
                hypotheses_sat: q.hypotheses_sat,
                seconds: q.seconds,
                error,
            }
        })
        .collect();
    // The run stops at the first confirmed counterexample: the sides not run are
    // failures too (nothing was shown for them).
    for (s, _) in sets.iter().skip(out.len()) {
        out.push(SideRun {
            method: id.to_string(),
            side: fam.sides()[*s],
            ranges: TEMPLATE_RANGES,
            answer: "not run",
            solver: "-",
            hypotheses_sat: None,
            seconds: 0.0,
            error: Some("not run (the run stopped at a counterexample)".into()),
        });
    }
    out
}
