//! The command line: argument parsing ([`args`]) and one file per command. The
//! binary's `main` passes in the expectations and baseline it was built with and calls
//! [`main`].

// The doc comments of the commands are their `--help` text, written for a terminal:
// `<method>` there is a placeholder, not an HTML tag.
#![allow(rustdoc::invalid_html_tags)]

pub mod args;
pub mod check;
pub mod common;
pub mod explain;
pub mod merge;
pub mod methods;
pub mod oracle_agree;
pub mod power;
pub mod proofs;
pub mod prove;
pub mod replay;
pub mod search;
pub mod stability;
pub mod tightness;

use crate::gate::locate::BuiltIn;
use anyhow::Result;
use clap::{Parser, Subcommand};
use common::{exit, loader_flags, report_breaches};
use std::path::PathBuf;
use std::sync::OnceLock;

/// `corpus/expectations.json` and `corpus/baseline.json` as the binary was built with
/// them (see [`crate::gate::locate`]): what `check`, `merge`, `power` and `search` use
/// outside the checkout. Set once by [`main`].
static BUILT_IN: OnceLock<BuiltIn> = OnceLock::new();

/// The built-in expectations and baseline, as [`main`] set them. The commands run only
/// under [`main`]; an empty default would silently stand for "no expectations".
pub fn built_in() -> &'static BuiltIn {
    BUILT_IN.get().expect("cli::main sets the built-in expectations before any command runs")
}

#[derive(Parser)]
#[command(name = "cullproof", version, about = "Proves or breaks the conservativeness of culling bounds for stochastic rasterization (motion blur + depth of field).", long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
    /// Load a culling bound from a shared library (the C interface of
    /// include/cullproof.h) and use it by its own id with --method, in every command;
    /// repeat for several.
    #[arg(long = "plugin", global = true, value_name = "LIB.so")]
    plugins: Vec<PathBuf>,
    /// Run a culling bound in another process (started with `sh -c COMMAND`, one per
    /// worker thread) that answers the JSON-lines protocol of docs/protocol.md, and use
    /// it by the id it announces with --method, in every command; repeat for several.
    #[arg(long = "exec", global = true, value_name = "COMMAND")]
    execs: Vec<String>,
    /// Seconds a process started by --exec may take for one answer before the run
    /// stops with an error naming the request.
    #[arg(long, global = true, default_value_t = 30.0, value_name = "SECONDS")]
    exec_timeout: f64,
    /// Seconds one call into a library loaded by --plugin may take before the run stops
    /// with an error naming the plugin and the call (a hung call cannot be interrupted:
    /// the process ends, exit code 2).
    #[arg(long, global = true, default_value_t = 30.0, value_name = "SECONDS")]
    plugin_timeout: f64,
}

#[derive(Subcommand)]
enum Cmd {
    /// Check the two ground-truth oracles against each other: exact coverage vs Embree
    /// on random thin-lens cases of every regime of `check`, samples biased towards
    /// triangle edges. Every
    /// disagreement is settled exactly; the run fails (exit 1) if one lies farther from
    /// an edge than the documented f32 band.
    #[command(allow_negative_numbers = true)]
    OracleAgree(oracle_agree::OracleAgreeArgs),
    /// The conservativeness gate: random thin-lens cases of every regime, each method
    /// judged on a tile on the footprint's boundary and (one case in --limit-every) on the
    /// two tiles at its own tile-reject limit. Every case gets a verdict: proven (every
    /// claim certified, no gap left), violated (an interior sample, confirmed exactly,
    /// in the tile and the lens/shutter domain, that the answer culls) or unproven (by
    /// reason). Prints a table per method x regime and a summary per method; exit 1 when
    /// a row fails corpus/expectations.json (a violation where conservative is expected,
    /// unproven cases beyond the stated allowance, a violation outside its signature of
    /// bound kinds, margin caps and rate cap) or is worse than the stored baseline for
    /// the same settings.
    #[command(allow_negative_numbers = true)]
    Check(check::CheckArgs),
    /// Merge the JSON reports of `check --shard K/N --json F` (all N shards of one run)
    /// into the report the unsharded run gives, number for number: prints the table,
    /// applies the expectations and (for the settings of a stored entry) the baseline,
    /// exits 1 when a row fails, like `check`. Every shard is validated first (its shard
    /// index, its counts against its rows and against the cases its settings give, no
    /// row dropped; the same build, expectations, baseline and settings as the others;
    /// each shard once): anything else, a timed run or a report written without a tool
    /// version is refused (exit 2) with an error naming the file and the field.
    Merge(merge::MergeArgs),
    /// Randomized counterexample search for one method: random cases of every regime
    /// (or one), each judged like `check`; every violation is shrunk (freeze the motion,
    /// zero the CoC, snap coordinates to fewer mantissa bits, aspect 1, depths to w = 1,
    /// smaller tiles)
    /// while it stays a violation at least half as large, then written to
    /// DIR/cases/<method>/<hash>.json of the corpus (--corpus; an existing file is never
    /// overwritten). One file per regime and bound.
    ///
    /// With --gate, every violation is held against the method's expected signature
    /// for its regime in the expectations file (as `check` holds a row): a kind of
    /// bound the signature does not list, a margin above its cap, or any violation in
    /// a regime expected conservative is beyond it. Violations inside the signature are
    /// only counted (they neither count against --max nor stop the search); each kind
    /// beyond it is a finding (one per regime and kind), shrunk while it stays beyond,
    /// and written with that kind's own witness. Prints the kinds of bound seen per
    /// regime with their largest margins and caps, and a line per finding. The search's
    /// cases as a whole are held to the rest of the signature, as the gate judges them:
    /// on their boundary tiles the rate cap (beyond counting noise), the tightness
    /// signature (per regime and pooled) and the admitted share, on the tiles at the
    /// method's own tile-reject limit their violation rate; one line per breach (a
    /// looser or more often wrong method has no single witness, so no case file). Exit
    /// 1 when something lies beyond the signature, 0 otherwise.
    #[command(allow_negative_numbers = true)]
    Search(search::SearchArgs),
    /// Symbolic counterexample search (needs z3): asks z3, in queries with a resource
    /// and a time limit each (by default many small ones: a triangle drawn for the seed,
    /// the tile left to the solver), for f32 inputs in stated ranges where the method
    /// culls a tile that the exact footprint reaches (the method's own f32 code, encoded bit for bit; see
    /// src/tools/symbolic/). Every model becomes a case judged exactly: a confirmed violation
    /// is shrunk and written to DIR/cases/<method>/<hash>.json of the corpus (--corpus;
    /// never overwriting);
    /// a model the judge does not confirm is reported as such. Methods with an
    /// encoding: bbox, bbox-safe, la2011, la2011-safe, mam2012, mam2012-safe,
    /// nilsson2012-depth, nilsson2012-depth-safe, broken/planted-eq/bbox-safe,
    /// broken/planted-band/bbox-safe, broken/planted-no-up/M-safe and
    /// broken/planted-no-dn/M-safe for M = la2011, mam2012 and nilsson2012-depth; lc and mam2012-new through their la2011 part (a model is a
    /// counterexample, an unsat is never counted).
    #[command(allow_negative_numbers = true)]
    Prove(prove::ProveArgs),
    /// Re-judge case files (default: every file under the corpus's cases/, see --corpus:
    /// corpus/cases in the cullproof checkout, cullproof-corpus/cases anywhere else). The stored witness
    /// is re-decided exactly and the method judged afresh; exit 1 when a file no longer
    /// shows what it expects. A file that does not parse is an error naming the file
    /// and the field.
    Replay(replay::ReplayArgs),
    /// Explain one case file: what the method answered, the exact extents of the
    /// covered set over the tile, the witness decided exactly (and by Embree); with
    /// --svg, a picture of the sample space sliced through the witness.
    Explain(explain::ExplainArgs),
    /// Sample test efficiency (STE) of every culling method on a scene.
    ///
    /// STE = covered samples / samples a method lets through (Fatahalian et al. 2009):
    /// the fraction of coverage tests that hit. For each triangle of the scene
    /// (hairball, interior, forest, or an OBJ file) and each blur setting (static; blur:
    /// motion blur and depth of field; blur2: twice the shutter and the lens radius, as
    /// in Munkberg & Akenine-Möller 2012 Table 1), the tiles over the triangle's screen
    /// footprint are tested with each method, and each sample of the pattern in a tile
    /// that the method lets through is counted as tested; the exact oracle says whether
    /// it is covered. Prints STE per method x setting x tile size, the sample ceiling (an
    /// upper bound on the tightest interval-only test), the covered samples each method
    /// MISSED (culled although covered), a certified ceiling on a few tiles, and the time
    /// of an end-to-end software rasterizer per method relative to bbox on static (as
    /// Munkberg 2012 Table 2). Writes ste.md, ste.json and ste_vs_cost.svg into --out.
    #[command(allow_negative_numbers = true)]
    Tightness(tightness::TightnessArgs),
    /// Sweep one parameter towards a method's singularity, on a log scale, and report
    /// per step and method: the certified violation rate (the gate's own judge), the
    /// undecided cases, the NaN/inf rate of the tile answer, the sampled STE, and the
    /// first step at which each method fails.
    ///
    /// Families: focal (a vertex's distance to the focal plane |z0/F - 1| from 1 to
    /// 1e-7: its CoC goes to 0; the others in front of and behind the plane; lens on);
    /// w-zero (the camera depth of one vertex at one shutter end: 1 ... 1e-6, 0, -1e-6
    /// ... -1, every other decade by default, on a symmetric-log axis; motion on, lens in
    /// every other case);
    /// perspective (depth ratio w(1)/w(0) of every vertex: 1, 2, 4 ... 1024); sliver
    /// (height/base in pixels 1e-1 ... 1e-8); far (the triangle and its tile 1e1 ... 1e7
    /// px from the screen origin: f32 precision); double-root (a moving edge whose sweep
    /// grazes a tile corner tangentially, the corner's depth inside it 1e-1 ... 1e-8 px:
    /// near-double roots of gdam2010's time quadratics). Each case gets a 4 px tile on
    /// its footprint boundary (double-root: the grazed corner's tile).
    ///
    /// Prints a table per family (step value, method, violations/cases, undecided,
    /// NaN/inf rate, STE, max margin) and the first-fails table (the first violation, and
    /// the first gross one: margin > 1e-4 or a covered tile culled); writes <out>/<family>.svg (three
    /// stacked panels: violation rate, NaN/inf rate, STE, one line per method) and
    /// <out>/<family>.md (the same with how the cases are built and the parameter
    /// measured back from the f32 cases); --json FILE writes every row. Identical at any
    /// thread count.
    #[command(allow_negative_numbers = true)]
    Stability(stability::StabilityArgs),
    /// Measure the gate's power: plant each slip of `broken/` (shrink, shrink-rel,
    /// no-coc-pad, t0-only, swap-coc, half-tile, loose) into each method and run the
    /// gate on it with the real expectations and the stored baseline; a slip is killed
    /// when the gate fails. Prints a table method x slip and the score (slips whose
    /// answers equal the method's on every case are "no effect" and left out).
    Power(power::PowerArgs),
    /// Re-run the proofs for all inputs in stated ranges (z3 and gappa scripts in
    /// src/bounds/proofs/, checked against the code's constants and formulas) and print,
    /// per method, its ranges, scripts, their verdicts and times, and its strongest
    /// verdict; exit 1 when a script is not proven or does not match the code.
    Proofs(proofs::ProofsArgs),
    /// List the culling methods under test: id, source, reconstruction flag, dimensions, outputs.
    Methods(methods::MethodsArgs),
}

/// Exit codes: 0 done (and passed), 1 a run that judged a failure (`check`,
/// `oracle-agree`, `replay`), 2 an error (a bad flag value, an unreadable file; the
/// message names the flag or the file and the value). clap's own usage errors exit 2 too.
pub fn main(built_in: BuiltIn) {
    let _ = BUILT_IN.set(built_in);
    if let Err(e) = run() {
        eprintln!("error: {e:#}");
        exit(2);
    }
    report_breaches();
}

fn run() -> Result<()> {
    let cli = Cli::parse();
    // A bound in another process that fails (an error answer, a crash, silence), or a
    // plugin answer beyond a cap, stops the run from whichever worker saw it: say so as
    // an error, without a backtrace.
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if let Some(f) = info.payload().downcast_ref::<crate::external::exec::ExecFailure>() {
            eprintln!("error: {f}");
            std::process::exit(2);
        }
        if let Some(f) = info.payload().downcast_ref::<crate::external::plugin::PluginFailure>() {
            eprintln!("error: {f}");
            std::process::exit(2);
        }
        default_hook(info)
    }));
    if !cli.plugins.is_empty() {
        crate::cli::args::time("--plugin-timeout", cli.plugin_timeout, 86400.0)?;
        crate::external::plugin::set_timeout(std::time::Duration::from_secs_f64(cli.plugin_timeout));
    }
    // The ids of the bounds plugged in by --plugin and --exec (what `check` gates when
    // no --method is given).
    let mut plugged: Vec<&'static str> = Vec::new();
    for p in &cli.plugins {
        plugged.push(crate::external::plugin::load_and_plug(p)?.info().id);
    }
    if !cli.execs.is_empty() {
        crate::cli::args::time("--exec-timeout", cli.exec_timeout, 86400.0)?;
    }
    for c in &cli.execs {
        plugged.push(
            crate::external::exec::start_and_plug(c, std::time::Duration::from_secs_f64(cli.exec_timeout))?.info().id,
        );
    }
    // The same flags, shell-quoted, for the commands a report tells the user to run
    // next (the JUnit re-judge hint): replay and explain need the bounds loaded too.
    let loaders = loader_flags(&cli.plugins, &cli.execs);
    match cli.cmd {
        Cmd::OracleAgree(args) => oracle_agree::run(args)?,
        Cmd::Check(args) => check::run(args, &plugged, &loaders)?,
        Cmd::Merge(args) => merge::run(args, &loaders)?,
        Cmd::Search(args) => search::run(args)?,
        Cmd::Prove(args) => prove::run(args)?,
        Cmd::Replay(args) => replay::run(args)?,
        Cmd::Explain(args) => explain::run(args)?,
        Cmd::Tightness(args) => tightness::run_cli(&args)?,
        Cmd::Stability(args) => stability::run_cli(&args)?,
        Cmd::Power(args) => power::run(args)?,
        Cmd::Proofs(args) => {
            if !proofs::run_cli(&args)? {
                exit(1);
            }
        }
        Cmd::Methods(args) => methods::run(args)?,
    }
    Ok(())
}
