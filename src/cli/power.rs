//! `cullproof power`: the gate's power, each slip of `broken/` planted into each method and run through
//! the gate; a slip is killed when the gate fails.

use super::common::{baseline_for, check_json, expectations_for, set_jobs, write_json};
use anyhow::Result;
use std::path::PathBuf;

/// Arguments of `cullproof power`.
#[derive(clap::Args)]
pub struct PowerArgs {
    /// Method ids (comma-separated) or `all`.
    #[arg(long, default_value = "all")]
    method: String,
    /// Cases per gate run (the baseline applies when a stored entry has the same
    /// settings: `check --cases N --write-baseline` records one).
    #[arg(long, default_value_t = 960)]
    cases: u64,
    /// Seed of the case streams.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The expectations file. Default: corpus/expectations.json in the cullproof
    /// checkout, the copy built into the binary anywhere else.
    #[arg(long)]
    expectations: Option<PathBuf>,
    /// The baseline file. Default: corpus/baseline.json in the cullproof checkout, the
    /// copy built into the binary anywhere else.
    #[arg(long)]
    baseline: Option<PathBuf>,
    /// Write the JSON report to this file ("-" for standard output) as well.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
}

/// Run `cullproof power`.
pub fn run(args: PowerArgs) -> Result<()> {
    let PowerArgs { method, cases, seed, expectations, baseline, json, jobs } = args;
    set_jobs(jobs)?;
    let methods = crate::cli::args::methods("--method", &method, false)?;
    let cases = crate::cli::args::count("--cases", cases, 1_000_000, "cases")?;
    check_json(&json)?;
    let in_checkout = crate::gate::locate::in_checkout();
    let ex = expectations_for(&expectations, in_checkout, "the expectations file is required")?;
    let base = baseline_for(&baseline, in_checkout)?.file;
    let mut cfg = crate::gate::CheckConfig::default_with(methods);
    cfg.cases = cases;
    cfg.seed = seed;
    let slips = crate::bounds::broken::KINDS;
    let r = crate::gate::power::run(&cfg, &ex, base.as_ref(), &slips, true);
    print!("{}", crate::gate::power::render(&r, &slips));
    if let Some(p) = &json {
        write_json(p, &serde_json::to_string_pretty(&r)?)?;
    }
    Ok(())
}
