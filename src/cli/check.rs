//! `cullproof check`: the conservativeness gate, every method judged on random cases of every regime
//! and held to the expectations and the stored baseline.

use super::common::{baseline_for, check_json, check_junit, expectations_for, finish_report, parse_regimes, set_jobs};
use anyhow::{Context, Result};
use std::path::PathBuf;

/// Arguments of `cullproof check`.
#[derive(clap::Args)]
pub struct CheckArgs {
    /// `all`, a method id (see `cullproof methods`) or ids separated by commas.
    /// Default: `all` built-in methods; with --plugin or --exec, only the plugged
    /// bounds.
    #[arg(long)]
    method: Option<String>,
    /// A regime or `all`: static, motion, defocus, both, focal-crossing, behind-lens,
    /// sliver, tiny, huge, perspective, facing-flip, huge-coc, tiny-coc,
    /// far-from-origin, degenerate, screen-parallel.
    #[arg(long, default_value = "all")]
    regime: String,
    /// Number of cases (spread over the regimes in turn): 1 to 10^9, and at most
    /// 10^6 per shard (every judgement is held until the report).
    #[arg(long, default_value_t = 9600, conflicts_with = "time")]
    cases: u64,
    /// Run for about this many seconds instead (whole batches of cases; the report
    /// says how many, and `--cases N` repeats the run exactly). At most 3600.
    #[arg(long)]
    time: Option<f64>,
    /// Seed of the case streams.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Tile size in pixels, at most 4096 (default: drawn from 1, 2, 4, 8, 16 per case).
    #[arg(long)]
    tile: Option<f32>,
    /// Worker threads (default: all cores; at most 4 per core). Results do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
    /// Run only shard K of N ("K/N"): shards of one seed partition the cases.
    #[arg(long, default_value = "0/1")]
    shard: String,
    /// Write the JSON report to this file ("-" for standard output) as well.
    #[arg(long)]
    json: Option<PathBuf>,
    /// The expectations file (it must exist). Default: corpus/expectations.json in the
    /// cullproof checkout (the current directory holds its Cargo.toml), the copy built
    /// into the binary anywhere else.
    #[arg(long)]
    expectations: Option<PathBuf>,
    /// Boxes per certified interval-side search (more: fewer undecided sides and
    /// more rounding-size witnesses, slower).
    #[arg(long, default_value_t = 2000)]
    side_budget: usize,
    /// An interval-side search gives up after this many boxes in a row that did not
    /// raise its certified bound, while no witness lies beyond the claim (a bound
    /// tight to a rounding; 0: only --side-budget stops it). Larger: more
    /// rounding-size witnesses per case, fewer cases per minute.
    #[arg(long, default_value_t = 250)]
    side_stall: usize,
    /// (The default; kept so older command lines still run.) When a side search
    /// on the exact enclosures leaves a gap, it searches again with (x, y)
    /// eliminated for each box of lens and time.
    #[arg(long, hide = true)]
    second_chance: bool,
    /// Turn off the judge's second chance: a side search on the exact enclosures
    /// that leaves a gap is not searched again with (x, y) eliminated for each box
    /// of lens and time. Fewer solver boxes (10.8 M against 13.7 M on the default
    /// gate), fewer cases decided (most behind the lens: fewer violations of published methods found,
    /// fewer proofs); the expectations and the baseline are written with it on.
    #[arg(long, conflicts_with = "second_chance")]
    no_second_chance: bool,
    /// Boxes per certified per-sample constraint search (more: fewer undecided
    /// cases for the per-sample methods, slower).
    #[arg(long, default_value_t = 2000)]
    constraint_budget: usize,
    /// Judge each method also on the two tiles at its own tile-reject limit (found
    /// by bisecting the method's tile test) in one case out of this many (0: never).
    #[arg(long, default_value_t = 12)]
    limit_every: u64,
    /// The baseline file: a run whose settings have an entry there fails on a row
    /// that got worse (a new kind of violated bound, a margin more than 2x, more
    /// violations, a looser answer). Default: corpus/baseline.json in the cullproof
    /// checkout, the copy built into the binary anywhere else.
    #[arg(long)]
    baseline: Option<PathBuf>,
    /// Rewrite the baseline entry for this run's settings with this run's rows
    /// (after a deliberate change, once the table is understood). The rest of
    /// the file is kept. It writes --baseline FILE, or corpus/baseline.json in the
    /// checkout; anywhere else give --baseline FILE (the built-in copy is read-only).
    #[arg(long)]
    write_baseline: bool,
    #[command(flatten)]
    sample: crate::cli::args::SampleFlags,
    /// Write the report as JUnit XML to this file as well (one test case per method
    /// x regime; a failing row names the witness case file written beside it, in
    /// FILE's stem + `.witnesses/`).
    #[arg(long)]
    junit: Option<PathBuf>,
}

/// Run `cullproof check`.
pub fn run(args: CheckArgs, plugged: &[&'static str], loaders: &str) -> Result<()> {
    let CheckArgs {
        method,
        regime,
        cases,
        time,
        seed,
        tile,
        jobs,
        shard,
        json,
        expectations,
        side_budget,
        side_stall,
        second_chance: _,
        no_second_chance,
        constraint_budget,
        limit_every,
        baseline,
        write_baseline,
        junit,
        sample,
    } = args;
    use crate::cli::args;
    let method = method.unwrap_or_else(|| if plugged.is_empty() { "all".into() } else { plugged.join(",") });
    let methods = args::methods("--method", &method, true)?;
    let mut cfg = crate::gate::CheckConfig::default_with(methods);
    sample.parse()?.apply(&mut cfg);
    cfg.regimes = parse_regimes(&regime)?;
    if let Some(t) = tile {
        args::tile("--tile", t)?;
    }
    let (k, n) = args::shard(&shard)?;
    args::count("--cases", cases, args::CHECK_MAX_CASES, "cases (in all)")?;
    anyhow::ensure!(
        cases.div_ceil(n) <= args::CHECK_MAX_CASES_PER_SHARD,
        "--cases {cases}: at most {} cases per shard (every judgement is held until the report, \
         about 7 KB a case); split the run with --shard K/N",
        args::CHECK_MAX_CASES_PER_SHARD
    );
    if let Some(t) = time {
        args::time("--time", t, args::CHECK_MAX_TIME)?;
    }
    // Every output is checked before the run, so none fails after it.
    check_json(&json)?;
    check_junit(&junit)?;
    let in_checkout = crate::gate::locate::in_checkout();
    if write_baseline {
        anyhow::ensure!(
            time.is_none() && (k, n) == (0, 1),
            "--write-baseline: a baseline needs a fixed case count, not --time or --shard"
        );
        let target =
            baseline.clone().or_else(|| in_checkout.then(|| PathBuf::from(crate::gate::locate::BASELINE_FILE)));
        let Some(target) = target else {
            anyhow::bail!(
                "--write-baseline: no baseline file to write: the current directory is not the cullproof \
                 checkout, so the baseline is the copy built into the binary, which is read-only; pass \
                 --baseline FILE to write this run's entry to FILE (created if missing, its other entries kept)"
            );
        };
        crate::io::output::file("--baseline", &target)?;
    }
    set_jobs(jobs)?;
    let ex = expectations_for(&expectations, in_checkout, "the expectations file is required")?;
    cfg.cases = cases;
    cfg.time = time;
    cfg.seed = seed;
    cfg.tile = tile;
    cfg.shard = (k, n);
    anyhow::ensure!(side_budget > 0, "--side-budget 0: a search needs at least one box");
    anyhow::ensure!(constraint_budget > 0, "--constraint-budget 0: a search needs at least one box");
    cfg.judge.side_budget = side_budget;
    cfg.judge.side_stall = side_stall;
    cfg.judge.extents.second_chance = !no_second_chance;
    cfg.judge.constraint_budget = constraint_budget;
    cfg.limit_every = limit_every;
    let crate::gate::locate::Baseline { file: base, path: base_path } = baseline_for(&baseline, in_checkout)?;
    let r = crate::gate::run_with_baseline(&cfg, &ex, base.as_ref(), true);
    print!("{}", crate::gate::render(&r));
    if write_baseline {
        let path = base_path.context("--write-baseline: checked before the run")?;
        let mut f = base.unwrap_or_default();
        f.record(&cfg, &r)?;
        f.save(&path)?;
        println!("wrote the baseline for these settings to {}", path.display());
    }
    finish_report(&r, &json, &junit, loaders)
}
