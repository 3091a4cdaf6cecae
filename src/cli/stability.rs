//! `cullproof stability`: its arguments and the run (the sweeps live in
//! [`crate::tools::stability`]).

use crate::bounds::Method;
use crate::tools::stability::{chart, render, run_family, Config, Family, StabilityReport};
use anyhow::{ensure, Context, Result};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `cullproof stability`.
#[derive(clap::Args, Debug, Clone)]
pub struct StabilityArgs {
    /// The family to sweep (or `all`, or several separated by commas):
    /// `focal` (a vertex's distance to the focal plane |z0/F - 1| = 1 ... 1e-7, lens on),
    /// `w-zero` (a vertex's camera depth at one shutter end: 1 ... 1e-6, 0, -1e-6 ... -1,
    /// every other decade by default, every decade with --steps 15; motion on),
    /// `perspective` (depth ratio w(1)/w(0) = 1, 2, 4 ... 1024), `sliver` (height/base
    /// 1e-1 ... 1e-8), `far` (distance from the screen origin 1e1 ... 1e7 px: f32
    /// precision), `double-root` (depth of a tile corner inside a moving edge that grazes
    /// it tangentially, 1e-1 ... 1e-8 px: near-double roots of gdam2010's time quadratics).
    #[arg(long)]
    pub family: String,
    /// Methods: `all`, or comma-separated ids (see `cullproof methods`), or broken
    /// variants (broken/shrink/ID, broken/no-coc-pad/ID).
    #[arg(long, default_value = "all")]
    pub method: String,
    /// Steps per family (default: one per decade, per octave for perspective; w-zero
    /// takes floor(N/2) positive values, 0 and as many negative ones).
    #[arg(long)]
    pub steps: Option<usize>,
    /// Cases per step.
    #[arg(long, default_value_t = 32)]
    pub cases: u64,
    /// Seed of the case streams.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Tile size in pixels (at most 4096). (double-root's construction keeps all of the tile but the
    /// grazed corner uncovered for tiles up to about 12 px.)
    #[arg(long, default_value_t = 4.0)]
    pub tile: f32,
    /// Uniform samples per case for STE and the NaN/inf test.
    #[arg(long, default_value_t = 512)]
    pub samples: usize,
    /// Output directory (created if missing): `<family>.svg` and `<family>.md`.
    #[arg(long, default_value = "target/stability")]
    pub out: PathBuf,
    /// Also write every row as JSON to this file ("-": standard output).
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Worker threads (default: all cores; at most 4 per core). Results do not depend on it.
    #[arg(long)]
    pub jobs: Option<usize>,
}

/// `--method`: the shared method-list parser ([`crate::cli::args::methods`]), broken
/// variants allowed.
fn parse_methods(s: &str) -> Result<Vec<&'static dyn Method>> {
    crate::cli::args::methods("--method", s, true)
}

fn write(path: &Path, text: &str) -> Result<()> {
    crate::io::output::write(path, text)
}

/// The `stability` command.
pub fn run_cli(args: &StabilityArgs) -> Result<()> {
    let start = Instant::now();
    let families = Family::parse(&args.family)?;
    let methods = parse_methods(&args.method)?;
    crate::cli::args::tile("--tile", args.tile)?;
    ensure!((1..1_000_000).contains(&args.cases), "--cases {}: must be 1..999999", args.cases);
    if let Some(n) = args.steps {
        ensure!((1..=1000).contains(&n), "--steps {n}: must be 1..1000");
    }
    ensure!(args.samples <= 1 << 20, "--samples {}: at most 1048576", args.samples);
    let threads = crate::cli::args::jobs(args.jobs)?.unwrap_or_else(rayon::current_num_threads);
    // Every output is checked before the run (see crate::io::output), so none fails after it.
    crate::io::output::dir("--out", &args.out)?;
    for f in &families {
        for ext in ["svg", "md"] {
            let p = args.out.join(format!("{}.{ext}", f.name()));
            if p.exists() {
                crate::io::output::file("--out", &p)?;
            }
        }
    }
    if let Some(p) = &args.json {
        // (a JSON file inside the output directory the run will create is covered by
        // that directory's check)
        if !p.starts_with(&args.out) || args.out.exists() {
            crate::io::output::file_or_stdout("--json", p)?;
        }
    }
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().context("building the thread pool")?;
    let cfg = Config {
        methods: methods.clone(),
        steps: args.steps,
        cases: args.cases,
        seed: args.seed,
        tile: args.tile,
        samples: args.samples,
    };
    std::fs::create_dir_all(&args.out).with_context(|| format!("--out {}: cannot create", args.out.display()))?;
    let to_stdout = args.json.as_deref().is_some_and(|p| p.as_os_str() == "-");
    let mut reports = Vec::new();
    for f in families {
        let r = pool.install(|| run_family(&cfg, f, true));
        let text = render(&r, false);
        if to_stdout {
            eprintln!("{text}");
        } else {
            println!("{text}");
        }
        let ids: Vec<String> = r.methods.clone();
        let svg = chart::svg(&r, &ids)?;
        let (svg_path, md_path) =
            (args.out.join(format!("{}.svg", f.name())), args.out.join(format!("{}.md", f.name())));
        write(&svg_path, &svg)?;
        write(&md_path, &render(&r, true))?;
        eprintln!("wrote {} and {}", svg_path.display(), md_path.display());
        reports.push(r);
    }
    if let Some(p) = &args.json {
        let rep = StabilityReport {
            kind: "cullproof-stability",
            seed: args.seed,
            threads,
            families: reports,
            seconds: start.elapsed().as_secs_f64(),
        };
        let text = serde_json::to_string_pretty(&rep)?;
        if to_stdout {
            println!("{text}");
        } else {
            write(p, &text)?;
        }
    }
    eprintln!("stability: {:.1} s", start.elapsed().as_secs_f64());
    Ok(())
}
