//! `cullproof prove`: symbolic counterexample search (z3, bitwuzla) on a method's f32 code encoded bit
//! for bit; every model judged exactly, a confirmed violation shrunk and written as a case file.

use super::common::{check_json, write_json};
use anyhow::Result;
use std::path::PathBuf;

/// Arguments of `cullproof prove`.
#[derive(clap::Args)]
pub struct ProveArgs {
    /// The method id.
    #[arg(long)]
    method: String,
    /// Search symbolically: the only mode so far, so this is the default (the flag is
    /// accepted and changes nothing).
    #[arg(long)]
    symbolic: bool,
    /// How the queries are made: `concolic` (many small queries, some inputs fixed
    /// to values drawn for the seed, the rest free) or `whole` (one query per side
    /// and range set, every input free).
    #[arg(long, value_enum, default_value_t = crate::tools::symbolic::prove::Strategy::Concolic)]
    strategy: crate::tools::symbolic::prove::Strategy,
    /// The template the queries build around the method's cull: `static` (a static
    /// triangle with a vertical edge; inputs a, c, w, t) or `moving` (the same triangle
    /// moving and changing its CoC over the shutter; inputs a0, a1, c0, c1, w0, w1, t).
    #[arg(long, value_enum, default_value_t = crate::tools::symbolic::prove::Template::Static)]
    template: crate::tools::symbolic::prove::Template,
    /// Seed of the concolic plan (the report for a seed does not depend on --jobs).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Concolic queries planned (the run stops at the first confirmed violation).
    #[arg(long, default_value_t = 4000)]
    queries: usize,
    /// Share of concolic queries that leave one triangle input free (0 to 1; the
    /// others fix the triangle and leave the tile to the solver).
    #[arg(long, default_value_t = crate::tools::symbolic::prove::DEFAULT_FREE_SHARE)]
    free_share: f64,
    /// Wall-clock seconds per query (z3's limit; 1 to 3600). A query that hits it is
    /// reported as a timeout (machine-dependent).
    #[arg(long, default_value_t = 60.0)]
    timeout: f64,
    /// z3's resource limit per query (deterministic; 0: none). Default: 1500000 for
    /// the concolic plan (about 0.5 to 1 s of z3 CPU), none for `whole`.
    #[arg(long)]
    rlimit: Option<u64>,
    /// Queries run at once (default 2; each runs one process per solver).
    #[arg(long, default_value_t = 2)]
    jobs: usize,
    /// The solvers each query runs on, first `sat` or `unsat` wins: `z3`, `bitwuzla`
    /// or `z3,bitwuzla`. Default: z3 for the concolic plan (its resource limit keeps
    /// the report the same on any machine), both for `whole`. Bitwuzla is the PyPI
    /// wheel `bitwuzla` run by `python3` (or CULLPROOF_PYTHON). An `unsat` counts only
    /// when the same solver finds the query's ranges, with a tile the exact footprint
    /// reaches, satisfiable.
    #[arg(long)]
    solvers: Option<String>,
    /// One range per input of the template, a=LO:HI,c=LO:HI,w=LO:HI,t=LO:HI (static;
    /// moving: a0, a1, c0, c1, w0, w1, t), half-open, c and w positive, queried on both
    /// x sides; default: a middle and a wide set.
    #[arg(long)]
    ranges: Option<String>,
    /// Where to write the confirmed cases (default: the corpus's cases/, see --corpus).
    #[arg(long)]
    out: Option<PathBuf>,
    #[command(flatten)]
    corpus: crate::cli::args::CorpusFlag,
    /// Do not write case files (report only).
    #[arg(long)]
    dry_run: bool,
    /// Also write each query's SMT-LIB2 script into this directory (rerun one with
    /// `z3 FILE`).
    #[arg(long, value_name = "DIR")]
    emit_smt: Option<PathBuf>,
    /// Write the JSON report to this file ("-" for standard output).
    #[arg(long)]
    json: Option<PathBuf>,
}

/// Run `cullproof prove`.
pub fn run(args: ProveArgs) -> Result<()> {
    let ProveArgs {
        method,
        symbolic,
        template,
        strategy,
        seed,
        queries,
        free_share,
        timeout,
        rlimit,
        jobs,
        solvers,
        ranges,
        out,
        corpus,
        dry_run,
        emit_smt,
        json,
    } = args;
    let _ = symbolic; // the only mode: on with or without the flag
    anyhow::ensure!(
        timeout.is_finite() && (1.0..=3600.0).contains(&timeout),
        "--timeout {timeout}: give seconds from 1 to 3600"
    );
    anyhow::ensure!((1..=64).contains(&jobs), "--jobs {jobs}: give 1 to 64");
    anyhow::ensure!((1..=1_000_000).contains(&queries), "--queries {queries}: give 1 to 1000000");
    anyhow::ensure!((0.0..=1.0).contains(&free_share), "--free-share {free_share}: give 0 to 1");
    check_json(&json)?;
    let (out_flag, out) = match out {
        Some(o) => ("--out", o),
        None => ("--corpus", corpus.dir(crate::gate::locate::in_checkout())?.join("cases")),
    };
    if !dry_run {
        crate::io::output::dir(out_flag, &out)?;
    }
    if let Some(d) = &emit_smt {
        crate::io::output::dir("--emit-smt", d)?;
    }
    let m = crate::cli::args::method("--method", &method, true)?;
    use crate::tools::symbolic::{family, prove};
    let fam = prove::family(m.info().id, template)?;
    let given = ranges.as_deref().map(|r| family::parse_ranges(fam.as_ref(), "--ranges", r)).transpose()?;
    let sets = prove::range_sets(fam.as_ref(), given);
    let plan = prove::queries(fam.as_ref(), strategy, &sets, seed, queries, free_share);
    let rlimit = match (rlimit, strategy) {
        (Some(0), _) | (None, prove::Strategy::Whole) => None,
        (Some(r), _) => Some(r),
        (None, prove::Strategy::Concolic) => Some(prove::DEFAULT_RLIMIT),
    };
    let solvers = match (solvers.as_deref(), strategy) {
        (Some(s), _) => crate::tools::symbolic::solver::Solvers::parse("--solvers", s)?,
        (None, prove::Strategy::Concolic) => crate::tools::symbolic::solver::Solvers::Z3,
        (None, prove::Strategy::Whole) => crate::tools::symbolic::solver::Solvers::BOTH,
    };
    let limits = prove::Limits { timeout, rlimit, jobs, solvers };
    let r = prove::prove(
        m,
        template,
        strategy,
        seed,
        &plan,
        limits,
        (!dry_run).then_some(out.as_path()),
        emit_smt.as_deref(),
        true,
    )?;
    print!("{}", r.render());
    if let Some(p) = &json {
        write_json(p, &serde_json::to_string_pretty(&r)?)?;
    }
    Ok(())
}
