//! `cullproof merge`: the shard reports of `check --shard K/N --json F`, validated and merged into the
//! report of the unsharded run, judged like `check`.

use super::common::{baseline_for, check_json, check_junit, expectations_for, finish_report};
use anyhow::Result;
use std::path::PathBuf;

/// Arguments of `cullproof merge`.
#[derive(clap::Args)]
pub struct MergeArgs {
    /// The shard reports (JSON of `check --json`).
    #[arg(required = true)]
    reports: Vec<PathBuf>,
    /// The expectations file (it must exist). Default: corpus/expectations.json in the
    /// cullproof checkout, the copy built into the binary anywhere else.
    #[arg(long)]
    expectations: Option<PathBuf>,
    /// The baseline file (compared when it holds the merged run's settings). Default:
    /// corpus/baseline.json in the cullproof checkout, the copy built into the binary
    /// anywhere else.
    #[arg(long)]
    baseline: Option<PathBuf>,
    /// Write the merged JSON report to this file ("-" for standard output) as well.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Write the merged report as JUnit XML to this file as well.
    #[arg(long)]
    junit: Option<PathBuf>,
}

/// Run `cullproof merge`.
pub fn run(args: MergeArgs, loaders: &str) -> Result<()> {
    let MergeArgs { reports, expectations, baseline, json, junit } = args;
    use crate::gate::{baseline::BaselineFile, merge, Expectations};
    check_json(&json)?;
    check_junit(&junit)?;
    let in_checkout = crate::gate::locate::in_checkout();
    let ex: Expectations = expectations_for(&expectations, in_checkout, "the expectations file is required")?;
    let base: Option<BaselineFile> = baseline_for(&baseline, in_checkout)?.file;
    let shards = reports.iter().map(|p| Ok((p.clone(), merge::load_report(p)?))).collect::<Result<Vec<_>>>()?;
    let r = merge::merge(shards, &ex, base.as_ref())?;
    print!("{}", crate::gate::render(&r));
    finish_report(&r, &json, &junit, loaders)
}
