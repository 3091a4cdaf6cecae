//! `cullproof search`: randomized counterexample search for one method, each violation shrunk and
//! written as a case file (`--gate`: held against the method's expected signature).

use super::common::{check_json, known, noted, parse_regimes, set_jobs, write_json};
use anyhow::Result;
use std::path::PathBuf;

/// Arguments of `cullproof search`.
#[derive(clap::Args)]
pub struct SearchArgs {
    /// The method id (see `cullproof methods`), or a deliberately broken variant
    /// broken/KIND/ID with KIND one of shrink (intervals pulled in by 1e-3),
    /// shrink-rel (by 1e-5 of their width), no-coc-pad (the CoC dropped), t0-only
    /// (the motion dropped), swap-coc, half-tile, loose (see `power`).
    #[arg(long)]
    method: String,
    /// Search for about this many seconds (at most a week).
    #[arg(long, default_value_t = 30.0)]
    time: f64,
    /// Stop after this many violations.
    #[arg(long, default_value_t = 8)]
    max: usize,
    /// Keep only violations that need at least this margin (e.g. one beyond the cap
    /// the expectations allow, to back a new finding with a case file).
    #[arg(long, default_value_t = 0.0)]
    min_margin: f64,
    /// Seed of the case streams.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Only this regime.
    #[arg(long, default_value = "all")]
    regime: String,
    /// Tile size in pixels, at most 4096 (default: drawn from 1, 2, 4, 8, 16 per case).
    #[arg(long)]
    tile: Option<f32>,
    /// Where to write the shrunk cases (default: the corpus's cases/, see --corpus).
    #[arg(long)]
    out: Option<PathBuf>,
    #[command(flatten)]
    corpus: crate::cli::args::CorpusFlag,
    /// Do not write case files (report only).
    #[arg(long)]
    dry_run: bool,
    /// Write the JSON report to this file ("-" for standard output).
    #[arg(long)]
    json: Option<PathBuf>,
    /// Worker threads (default: all cores; at most 4 per core). Results do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
    #[command(flatten)]
    sample: crate::cli::args::SampleFlags,
    /// Hold each violation against the method's expected signature and report only
    /// those beyond it; exit 1 when there is one.
    #[arg(long)]
    gate: bool,
    /// The expectations file (required with --gate; without it, findings are
    /// annotated when the file exists). Default: corpus/expectations.json in the
    /// cullproof checkout, the copy built into the binary anywhere else.
    #[arg(long)]
    expectations: Option<PathBuf>,
}

/// Run `cullproof search`.
pub fn run(args: SearchArgs) -> Result<()> {
    let SearchArgs {
        method,
        time,
        max,
        min_margin,
        seed,
        regime,
        tile,
        out,
        corpus,
        dry_run,
        json,
        jobs,
        sample,
        gate,
        expectations,
    } = args;
    use crate::cli::args;
    let m = args::method("--method", &method, true)?;
    let mut cfg = crate::gate::CheckConfig::default_with(vec![m]);
    sample.parse()?.apply(&mut cfg);
    cfg.regimes = parse_regimes(&regime)?;
    if let Some(t) = tile {
        args::tile("--tile", t)?;
    }
    args::time("--time", time, args::SEARCH_MAX_TIME)?;
    args::count("--max", max as u64, u64::MAX, "violation to stop at")?;
    args::margin("--min-margin", min_margin)?;
    check_json(&json)?;
    let in_checkout = crate::gate::locate::in_checkout();
    let (out_flag, out) = match out {
        Some(o) => ("--out", o),
        None => ("--corpus", corpus.dir(in_checkout)?.join("cases")),
    };
    if !dry_run {
        crate::io::output::dir(out_flag, &out)?;
    }
    set_jobs(jobs)?;
    let why = "the expectations file is required with --gate";
    let ex = crate::gate::locate::expectations(
        expectations.as_deref(),
        gate.then_some(why),
        in_checkout,
        super::built_in(),
        &known,
    )?
    .map(noted);
    cfg.seed = seed;
    cfg.tile = tile;
    let opts = crate::search::SearchOptions {
        seconds: time,
        max_found: max,
        min_margin,
        out: (!dry_run).then_some(out.as_path()),
        progress: true,
        expectations: ex.as_ref().map(|e| (&e.value, e.name.as_str())),
        gate,
    };
    let r = crate::search::search_with(&cfg, crate::bounds::shared(m), &opts)?;
    print!("{}", crate::search::render_search(&r));
    if let Some(p) = &json {
        write_json(p, &serde_json::to_string_pretty(&r)?)?;
    }
    if gate && (r.found.iter().any(|f| f.beyond_signature) || !r.breaches.is_empty()) {
        std::process::exit(1);
    }
    Ok(())
}
