//! The `cullproof` command line (thin: the work lives in the library).

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser)]
#[command(name = "cullproof", version, about = "Proves or breaks the conservativeness of culling bounds for stochastic rasterization (motion blur + depth of field).", long_about = None)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Check the two ground-truth oracles against each other: exact coverage vs Embree
    /// on random thin-lens cases (static, motion, defocus, both, focal-plane crossing,
    /// behind-lens vertices, slivers), samples biased towards triangle edges. Every
    /// disagreement is settled exactly; the run fails (exit 1) if one lies farther from
    /// an edge than the documented f32 band.
    OracleAgree {
        /// Number of samples (rounded up to whole cases of 2000 samples).
        #[arg(long, default_value_t = 1_000_000)]
        samples: u64,
        /// Seed of the case and sample streams.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Write the JSON report to this file ("-" for standard output) instead of the table.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Worker threads (default: all cores). Results do not depend on it.
        #[arg(long)]
        jobs: Option<usize>,
    },
    /// The conservativeness gate: random thin-lens cases of every regime, a tile on
    /// each footprint's boundary, every method's tile answer judged against certified
    /// tile extents (intervals, culled tiles) and exactly judged samples (per-sample
    /// constraints). Prints a verdict table per method x regime; exit 1 when a method
    /// violates where corpus/expectations.json expects it to be conservative.
    Check {
        /// A method id (see `cullproof methods`) or `all`.
        #[arg(long, default_value = "all")]
        method: String,
        /// A regime (static, motion, defocus, both, focal-crossing, behind-lens, sliver) or `all`.
        #[arg(long, default_value = "all")]
        regime: String,
        /// Number of cases (spread over the regimes in turn).
        #[arg(long, default_value_t = 280)]
        cases: u64,
        /// Seed of the case streams.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Tile size in pixels (default: drawn from 1, 2, 4, 8, 16 per case).
        #[arg(long)]
        tile: Option<f32>,
        /// Worker threads (default: all cores). Results do not depend on it.
        #[arg(long)]
        jobs: Option<usize>,
        /// Run only shard K of N ("K/N"): shards of one seed partition the cases.
        #[arg(long, default_value = "0/1")]
        shard: String,
        /// Write the JSON report to this file ("-" for standard output) as well.
        #[arg(long)]
        json: Option<PathBuf>,
        /// The expectations file.
        #[arg(long, default_value = "corpus/expectations.json")]
        expectations: PathBuf,
    },
    /// List the culling methods under test: id, source, reconstruction flag, dimensions, outputs.
    Methods {
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
}

fn set_jobs(jobs: Option<usize>) -> Result<()> {
    if let Some(j) = jobs {
        rayon::ThreadPoolBuilder::new().num_threads(j.max(1)).build_global().context("setting the thread count")?;
    }
    Ok(())
}

fn write_json(path: &PathBuf, text: &str) -> Result<()> {
    if path.as_os_str() == "-" {
        println!("{text}");
        Ok(())
    } else {
        std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))
    }
}

fn main() -> Result<()> {
    let cli = Cli::parse();
    match cli.cmd {
        Cmd::OracleAgree { samples, seed, json, jobs } => {
            set_jobs(jobs)?;
            let r = cullproof::agree::run(seed, samples, json.is_none());
            match &json {
                Some(p) => write_json(p, &serde_json::to_string_pretty(&r)?)?,
                None => print!("{}", cullproof::agree::render(&r)),
            }
            if r.total.unsettled > 0 {
                std::process::exit(1);
            }
        }
        Cmd::Check { method, regime, cases, seed, tile, jobs, shard, json, expectations } => {
            set_jobs(jobs)?;
            let methods: Vec<_> = if method == "all" {
                cullproof::bounds::registry()
            } else {
                vec![cullproof::bounds::by_id(&method)
                    .with_context(|| format!("--method {method}: no such method (see `cullproof methods`)"))?]
            };
            let mut cfg = cullproof::check::CheckConfig::default_with(methods);
            if regime != "all" {
                let r = cullproof::gen::Regime::ALL
                    .into_iter()
                    .find(|r| r.name() == regime)
                    .with_context(|| format!("--regime {regime}: no such regime"))?;
                cfg.regimes = vec![r];
            }
            if let Some(t) = tile {
                anyhow::ensure!(
                    t.is_finite() && t > 0.0,
                    "--tile {t}: the tile size must be a positive number of pixels"
                );
            }
            let (k, n) = shard
                .split_once('/')
                .and_then(|(a, b)| Some((a.parse::<u64>().ok()?, b.parse::<u64>().ok()?)))
                .filter(|(k, n)| *n > 0 && k < n)
                .with_context(|| format!("--shard {shard}: expected K/N with 0 <= K < N"))?;
            cfg.cases = cases;
            cfg.seed = seed;
            cfg.tile = tile;
            cfg.shard = (k, n);
            let ex = if expectations.exists() {
                cullproof::check::Expectations::load(&expectations)?
            } else {
                eprintln!("note: {} not found: every method is expected conservative", expectations.display());
                Default::default()
            };
            let r = cullproof::check::run(&cfg, &ex, true);
            print!("{}", cullproof::check::render(&r));
            if let Some(p) = &json {
                write_json(p, &serde_json::to_string_pretty(&r)?)?;
            }
            if r.failed() {
                std::process::exit(1);
            }
        }
        Cmd::Methods { json } => {
            let ms: Vec<_> = cullproof::bounds::registry().iter().map(|m| *m.info()).collect();
            if json {
                println!("{}", serde_json::to_string_pretty(&ms)?);
            } else {
                print!("{}", cullproof::bounds::render_methods(&ms));
            }
        }
    }
    Ok(())
}
