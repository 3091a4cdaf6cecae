//! `cullproof oracle-agree`: the two ground-truth oracles (exact coverage and Embree) checked against
//! each other on random cases; exit 1 on a disagreement beyond the f32 band.

use super::common::{check_json, exit, set_jobs, write_json};
use anyhow::Result;
use std::path::PathBuf;

/// Arguments of `cullproof oracle-agree`.
#[derive(clap::Args)]
pub struct OracleAgreeArgs {
    /// Number of samples (rounded up to whole cases of 2000 samples; 1 to 10^12).
    #[arg(long, default_value_t = 1_000_000)]
    samples: u64,
    /// Seed of the case and sample streams.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Write the JSON report to this file ("-" for standard output) instead of the table.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Worker threads (default: all cores; at most 4 per core). Results do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
}

/// Run `cullproof oracle-agree`.
pub fn run(args: OracleAgreeArgs) -> Result<()> {
    let OracleAgreeArgs { samples, seed, json, jobs } = args;
    crate::cli::args::count("--samples", samples, crate::cli::args::AGREE_MAX_SAMPLES, "samples")?;
    check_json(&json)?;
    set_jobs(jobs)?;
    let r = crate::judge::agree::run(seed, samples, json.is_none());
    match &json {
        Some(p) => write_json(p, &serde_json::to_string_pretty(&r)?)?,
        None => print!("{}", crate::judge::agree::render(&r)),
    }
    if r.total.unsettled > 0 {
        exit(1);
    }
    Ok(())
}
