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
