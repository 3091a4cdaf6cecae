//! The `cullproof` command line (thin: the work lives in the library).

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use std::path::PathBuf;

/// `corpus/expectations.json` and `corpus/baseline.json` as this binary was built with
/// them: what `check`, `merge`, `power` and `search` use outside the checkout (see
/// [`cullproof::locate`]). Included here, in the binary, so that editing them rebuilds
/// only the command, not the library and every test.
const BUILT_IN: cullproof::locate::BuiltIn = cullproof::locate::BuiltIn {
    expectations: include_str!("../corpus/expectations.json"),
    baseline: include_str!("../corpus/baseline.json"),
};

#[derive(Parser)]
#[command(name = "cullproof", version, about = "Proves or breaks the conservativeness of culling bounds for stochastic rasterization (motion blur + depth of field).", long_about = None)]
struct Cli {
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
    OracleAgree {
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
    },
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
    Check {
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
        sample: cullproof::args::SampleFlags,
        /// Write the report as JUnit XML to this file as well (one test case per method
        /// x regime; a failing row names the witness case file written beside it, in
        /// FILE's stem + `.witnesses/`).
        #[arg(long)]
        junit: Option<PathBuf>,
    },
    /// Merge the JSON reports of `check --shard K/N --json F` (all N shards of one run)
    /// into the report the unsharded run gives, number for number: prints the table,
    /// applies the expectations and (for the settings of a stored entry) the baseline,
    /// exits 1 when a row fails, like `check`. Every shard is validated first (its shard
    /// index, its counts against its rows and against the cases its settings give, no
    /// row dropped; the same build, expectations, baseline and settings as the others;
    /// each shard once): anything else, a timed run or a report written without a tool
    /// version is refused (exit 2) with an error naming the file and the field.
    Merge {
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
    },
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
    Search {
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
        corpus: cullproof::args::CorpusFlag,
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
        sample: cullproof::args::SampleFlags,
        /// Hold each violation against the method's expected signature and report only
        /// those beyond it; exit 1 when there is one.
        #[arg(long)]
        gate: bool,
        /// The expectations file (required with --gate; without it, findings are
        /// annotated when the file exists). Default: corpus/expectations.json in the
        /// cullproof checkout, the copy built into the binary anywhere else.
        #[arg(long)]
        expectations: Option<PathBuf>,
    },
    /// Symbolic counterexample search (needs z3): asks z3, in queries with a resource
    /// and a time limit each (by default many small ones: a triangle drawn for the seed,
    /// the tile left to the solver), for f32 inputs in stated ranges where the method
    /// culls a tile that the exact footprint reaches (the method's own f32 code, encoded bit for bit; see
    /// src/symbolic/). Every model becomes a case judged exactly: a confirmed violation
    /// is shrunk and written to DIR/cases/<method>/<hash>.json of the corpus (--corpus;
    /// never overwriting);
    /// a model the judge does not confirm is reported as such. Methods with an
    /// encoding: bbox, bbox-safe, la2011, la2011-safe, broken/planted-eq/bbox-safe,
    /// broken/planted-band/bbox-safe, broken/planted-no-up/la2011-safe,
    /// broken/planted-no-dn/la2011-safe.
    #[command(allow_negative_numbers = true)]
    Prove {
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
        #[arg(long, value_enum, default_value_t = cullproof::symbolic::prove::Strategy::Concolic)]
        strategy: cullproof::symbolic::prove::Strategy,
        /// Seed of the concolic plan (the report for a seed does not depend on --jobs).
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Concolic queries planned (the run stops at the first confirmed violation).
        #[arg(long, default_value_t = 4000)]
        queries: usize,
        /// Share of concolic queries that leave one triangle input free (0 to 1; the
        /// others fix the triangle and leave the tile to the solver).
        #[arg(long, default_value_t = cullproof::symbolic::prove::DEFAULT_FREE_SHARE)]
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
        /// when the same solver finds the query's ranges alone satisfiable.
        #[arg(long)]
        solvers: Option<String>,
        /// One range per input, a=LO:HI,c=LO:HI,w=LO:HI,t=LO:HI (half-open; c and w
        /// positive), queried on both x sides; default: a middle and a wide set.
        #[arg(long)]
        ranges: Option<String>,
        /// Where to write the confirmed cases (default: the corpus's cases/, see --corpus).
        #[arg(long)]
        out: Option<PathBuf>,
        #[command(flatten)]
        corpus: cullproof::args::CorpusFlag,
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
    },
    /// Re-judge case files (default: every file under the corpus's cases/, see --corpus:
    /// corpus/cases in the cullproof checkout, cullproof-corpus/cases anywhere else). The stored witness
    /// is re-decided exactly and the method judged afresh; exit 1 when a file no longer
    /// shows what it expects. A file that does not parse is an error naming the file
    /// and the field.
    Replay {
        /// Case files or directories (default: the corpus's cases/).
        paths: Vec<PathBuf>,
        #[command(flatten)]
        corpus: cullproof::args::CorpusFlag,
        /// Re-judge every file's case against this method instead of the one the file
        /// was written for (e.g. a fixed bound): one line per file, "fixed" (proven,
        /// the stored witness no longer culled), "still violated" or "unproven"; exit 1
        /// unless every file is fixed.
        #[arg(long)]
        method: Option<String>,
        /// Write the JSON report to this file ("-" for standard output).
        #[arg(long)]
        json: Option<PathBuf>,
        /// Flags given here judge the files under another sample set, snap or viewport
        /// than the one each file records.
        #[command(flatten)]
        sample: cullproof::args::SampleFlags,
    },
    /// Explain one case file: what the method answered, the exact extents of the
    /// covered set over the tile, the witness decided exactly (and by Embree); with
    /// --svg, a picture of the sample space sliced through the witness.
    Explain {
        /// The case file, or a case id: HASH or METHOD/HASH (the name `search` gives the
        /// file), looked up under the corpus's cases/ (see --corpus).
        case: PathBuf,
        #[command(flatten)]
        corpus: cullproof::args::CorpusFlag,
        /// Write the picture here (refuses to overwrite an existing file).
        #[arg(long)]
        svg: Option<PathBuf>,
        /// Flags given here explain the case under another sample set, snap or viewport
        /// than the one the file records.
        #[command(flatten)]
        sample: cullproof::args::SampleFlags,
    },
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
    Tightness(cullproof::tightness::TightnessArgs),
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
    Stability(cullproof::stability::StabilityArgs),
    /// Measure the gate's power: plant each slip of `broken/` (shrink, shrink-rel,
    /// no-coc-pad, t0-only, swap-coc, half-tile, loose) into each method and run the
    /// gate on it with the real expectations and the stored baseline; a slip is killed
    /// when the gate fails. Prints a table method x slip and the score (slips whose
    /// answers equal the method's on every case are "no effect" and left out).
    Power {
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
    },
    /// Re-run the proofs for all inputs in stated ranges (z3 and gappa scripts in
    /// src/bounds/proofs/, checked against the code's constants and formulas) and print,
    /// per method, its ranges, scripts, their verdicts and times, and its strongest
    /// verdict; exit 1 when a script is not proven or does not match the code.
    Proofs(cullproof::proofs::cli::ProofsArgs),
    /// List the culling methods under test: id, source, reconstruction flag, dimensions, outputs.
    Methods {
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
}

/// Check `--jobs` (see [`cullproof::args::jobs`]) and size the global pool.
fn set_jobs(jobs: Option<usize>) -> Result<()> {
    if let Some(j) = cullproof::args::jobs(jobs)? {
        rayon::ThreadPoolBuilder::new().num_threads(j).build_global().context("setting the thread count")?;
    }
    Ok(())
}

/// Print a located file's note (a checkout file that differs from the copy built in).
fn noted<T>(l: cullproof::locate::Located<T>) -> cullproof::locate::Located<T> {
    if let Some(n) = &l.note {
        eprintln!("{n}");
    }
    l
}

/// Is a method id known (built in or plugged)?
fn known(id: &str) -> bool {
    cullproof::bounds::by_id(id).is_some()
}

/// The expectations (required: an error says `why` when the file is missing).
fn expectations_for(given: &Option<PathBuf>, in_checkout: bool, why: &str) -> Result<cullproof::check::Expectations> {
    let ex = cullproof::locate::expectations(given.as_deref(), Some(why), in_checkout, &BUILT_IN, &known)?;
    Ok(noted(ex.expect("required expectations are loaded or an error")).value)
}

/// The baseline compared with, and the file `--write-baseline` writes.
fn baseline_for(given: &Option<PathBuf>, in_checkout: bool) -> Result<cullproof::locate::Baseline> {
    Ok(noted(cullproof::locate::baseline(given.as_deref(), in_checkout, &BUILT_IN)?).value)
}

/// The regimes of `--regime` (`all`: every one).
fn parse_regimes(name: &str) -> Result<Vec<cullproof::gen::Regime>> {
    Ok(match cullproof::args::regime(name)? {
        Some(r) => vec![r],
        None => cullproof::gen::Regime::ALL.to_vec(),
    })
}

/// Write a JSON report to `path` (checked before the run with [`check_json`]; "-" is
/// standard output), replacing an existing file only by the whole new report.
fn write_json(path: &std::path::Path, text: &str) -> Result<()> {
    if path.as_os_str() == "-" {
        println!("{text}");
        Ok(())
    } else {
        cullproof::output::write(path, text)
    }
}

/// Check a `--json` path before any work (see [`cullproof::output`]).
fn check_json(json: &Option<PathBuf>) -> Result<()> {
    match json {
        Some(p) => cullproof::output::file_or_stdout("--json", p),
        None => Ok(()),
    }
}

/// Check a `--junit` path (and its witness directory) before any work.
fn check_junit(junit: &Option<PathBuf>) -> Result<()> {
    match junit {
        Some(p) => cullproof::junit::check_path(p),
        None => Ok(()),
    }
}

/// Exit codes: 0 done (and passed), 1 a run that judged a failure (`check`,
/// `oracle-agree`, `replay`), 2 an error (a bad flag value, an unreadable file; the
/// message names the flag or the file and the value). clap's own usage errors exit 2 too.
fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e:#}");
        exit(2);
    }
    report_breaches();
}

/// `--plugin PATH` and `--exec 'COMMAND'` for each loaded bound, shell-quoted (single
/// quotes, an inner one written `'\''`).
fn loader_flags(plugins: &[PathBuf], execs: &[String]) -> String {
    let quote = |s: &str| format!("'{}'", s.replace('\'', "'\\''"));
    let mut out: Vec<String> = Vec::new();
    for p in plugins {
        out.push(format!("--plugin {}", quote(&p.display().to_string())));
    }
    for c in execs {
        out.push(format!("--exec {}", quote(c)));
    }
    out.join(" ")
}

/// One line per plugin that broke the contract of include/cullproof.h during the run.
fn report_breaches() {
    for b in cullproof::plugin::breaches().iter().filter(|b| b.answers > 0) {
        eprintln!("warning: {}", b.line());
    }
}

/// End the process with `code`, after the plugins' contract breaches.
fn exit(code: i32) -> ! {
    report_breaches();
    std::process::exit(code)
}

fn run() -> Result<()> {
    let cli = Cli::parse();
    // A bound in another process that fails (an error answer, a crash, silence), or a
    // plugin answer beyond a cap, stops the run from whichever worker saw it: say so as
    // an error, without a backtrace.
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if let Some(f) = info.payload().downcast_ref::<cullproof::exec::ExecFailure>() {
            eprintln!("error: {f}");
            std::process::exit(2);
        }
        if let Some(f) = info.payload().downcast_ref::<cullproof::plugin::PluginFailure>() {
            eprintln!("error: {f}");
            std::process::exit(2);
        }
        default_hook(info)
    }));
    if !cli.plugins.is_empty() {
        cullproof::args::time("--plugin-timeout", cli.plugin_timeout, 86400.0)?;
        cullproof::plugin::set_timeout(std::time::Duration::from_secs_f64(cli.plugin_timeout));
    }
    // The ids of the bounds plugged in by --plugin and --exec (what `check` gates when
    // no --method is given).
    let mut plugged: Vec<&'static str> = Vec::new();
    for p in &cli.plugins {
        plugged.push(cullproof::plugin::load_and_plug(p)?.info().id);
    }
    if !cli.execs.is_empty() {
        cullproof::args::time("--exec-timeout", cli.exec_timeout, 86400.0)?;
    }
    for c in &cli.execs {
        plugged
            .push(cullproof::exec::start_and_plug(c, std::time::Duration::from_secs_f64(cli.exec_timeout))?.info().id);
    }
    // The same flags, shell-quoted, for the commands a report tells the user to run
    // next (the JUnit re-judge hint): replay and explain need the bounds loaded too.
    let loaders = loader_flags(&cli.plugins, &cli.execs);
    match cli.cmd {
        Cmd::OracleAgree { samples, seed, json, jobs } => {
            cullproof::args::count("--samples", samples, cullproof::args::AGREE_MAX_SAMPLES, "samples")?;
            check_json(&json)?;
            set_jobs(jobs)?;
            let r = cullproof::agree::run(seed, samples, json.is_none());
            match &json {
                Some(p) => write_json(p, &serde_json::to_string_pretty(&r)?)?,
                None => print!("{}", cullproof::agree::render(&r)),
            }
            if r.total.unsettled > 0 {
                exit(1);
            }
        }
        Cmd::Check {
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
        } => {
            use cullproof::args;
            let method = method.unwrap_or_else(|| if plugged.is_empty() { "all".into() } else { plugged.join(",") });
            let methods = args::methods("--method", &method, true)?;
            let mut cfg = cullproof::check::CheckConfig::default_with(methods);
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
            let in_checkout = cullproof::locate::in_checkout();
            if write_baseline {
                anyhow::ensure!(
                    time.is_none() && (k, n) == (0, 1),
                    "--write-baseline: a baseline needs a fixed case count, not --time or --shard"
                );
                let target =
                    baseline.clone().or_else(|| in_checkout.then(|| PathBuf::from(cullproof::locate::BASELINE_FILE)));
                let Some(target) = target else {
                    anyhow::bail!(
                        "--write-baseline: no baseline file to write: the current directory is not the cullproof \
                         checkout, so the baseline is the copy built into the binary, which is read-only; pass \
                         --baseline FILE to write this run's entry to FILE (created if missing, its other entries kept)"
                    );
                };
                cullproof::output::file("--baseline", &target)?;
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
            cfg.side_budget = side_budget;
            cfg.side_stall = side_stall;
            cfg.extents.second_chance = !no_second_chance;
            cfg.constraint_budget = constraint_budget;
            cfg.limit_every = limit_every;
            let cullproof::locate::Baseline { file: base, path: base_path } = baseline_for(&baseline, in_checkout)?;
            let r = cullproof::check::run_with_baseline(&cfg, &ex, base.as_ref(), true);
            print!("{}", cullproof::check::render(&r));
            if write_baseline {
                let path = base_path.context("--write-baseline: checked before the run")?;
                let mut f = base.unwrap_or_default();
                f.record(&cfg, &r)?;
                f.save(&path)?;
                println!("wrote the baseline for these settings to {}", path.display());
            }
            if let Some(p) = &json {
                write_json(p, &serde_json::to_string_pretty(&r)?)?;
            }
            if let Some(p) = &junit {
                cullproof::junit::write(&r, p, &loaders)?;
            }
            if r.failed() {
                exit(1);
            }
        }
        Cmd::Merge { reports, expectations, baseline, json, junit } => {
            use cullproof::check::{baseline::BaselineFile, merge, Expectations};
            check_json(&json)?;
            check_junit(&junit)?;
            let in_checkout = cullproof::locate::in_checkout();
            let ex: Expectations = expectations_for(&expectations, in_checkout, "the expectations file is required")?;
            let base: Option<BaselineFile> = baseline_for(&baseline, in_checkout)?.file;
            let shards = reports.iter().map(|p| Ok((p.clone(), merge::load_report(p)?))).collect::<Result<Vec<_>>>()?;
            let r = merge::merge(shards, &ex, base.as_ref())?;
            print!("{}", cullproof::check::render(&r));
            if let Some(p) = &json {
                write_json(p, &serde_json::to_string_pretty(&r)?)?;
            }
            if let Some(p) = &junit {
                cullproof::junit::write(&r, p, &loaders)?;
            }
            if r.failed() {
                exit(1);
            }
        }
        Cmd::Search {
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
        } => {
            use cullproof::args;
            let m = args::method("--method", &method, true)?;
            let mut cfg = cullproof::check::CheckConfig::default_with(vec![m]);
            sample.parse()?.apply(&mut cfg);
            cfg.regimes = parse_regimes(&regime)?;
            if let Some(t) = tile {
                args::tile("--tile", t)?;
            }
            args::time("--time", time, args::SEARCH_MAX_TIME)?;
            args::count("--max", max as u64, u64::MAX, "violation to stop at")?;
            args::margin("--min-margin", min_margin)?;
            check_json(&json)?;
            let in_checkout = cullproof::locate::in_checkout();
            let (out_flag, out) = match out {
                Some(o) => ("--out", o),
                None => ("--corpus", corpus.dir(in_checkout)?.join("cases")),
            };
            if !dry_run {
                cullproof::output::dir(out_flag, &out)?;
            }
            set_jobs(jobs)?;
            let why = "the expectations file is required with --gate";
            let ex = cullproof::locate::expectations(
                expectations.as_deref(),
                gate.then_some(why),
                in_checkout,
                &BUILT_IN,
                &known,
            )?
            .map(noted);
            cfg.seed = seed;
            cfg.tile = tile;
            let opts = cullproof::corpus::SearchOptions {
                seconds: time,
                max_found: max,
                min_margin,
                out: (!dry_run).then_some(out.as_path()),
                progress: true,
                expectations: ex.as_ref().map(|e| (&e.value, e.name.as_str())),
                gate,
            };
            let r = cullproof::corpus::search_with(&cfg, cullproof::bounds::shared(m), &opts)?;
            print!("{}", cullproof::corpus::render_search(&r));
            if let Some(p) = &json {
                write_json(p, &serde_json::to_string_pretty(&r)?)?;
            }
            if gate && (r.found.iter().any(|f| f.beyond_signature) || !r.breaches.is_empty()) {
                std::process::exit(1);
            }
        }
        Cmd::Prove {
            method,
            symbolic,
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
        } => {
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
                None => ("--corpus", corpus.dir(cullproof::locate::in_checkout())?.join("cases")),
            };
            if !dry_run {
                cullproof::output::dir(out_flag, &out)?;
            }
            if let Some(d) = &emit_smt {
                cullproof::output::dir("--emit-smt", d)?;
            }
            let m = cullproof::args::method("--method", &method, true)?;
            use cullproof::symbolic::{family, prove};
            let fam = prove::family(m.info().id)?;
            let given = ranges.as_deref().map(|r| family::parse_ranges(fam.as_ref(), "--ranges", r)).transpose()?;
            let sets = prove::range_sets(fam.as_ref(), given);
            let plan = prove::queries(fam.as_ref(), strategy, &sets, seed, queries, free_share);
            let rlimit = match (rlimit, strategy) {
                (Some(0), _) | (None, prove::Strategy::Whole) => None,
                (Some(r), _) => Some(r),
                (None, prove::Strategy::Concolic) => Some(prove::DEFAULT_RLIMIT),
            };
            let solvers = match (solvers.as_deref(), strategy) {
                (Some(s), _) => cullproof::symbolic::solver::Solvers::parse("--solvers", s)?,
                (None, prove::Strategy::Concolic) => cullproof::symbolic::solver::Solvers::Z3,
                (None, prove::Strategy::Whole) => cullproof::symbolic::solver::Solvers::BOTH,
            };
            let limits = prove::Limits { timeout, rlimit, jobs, solvers };
            let r = prove::prove(
                m,
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
        }
        Cmd::Replay { paths, corpus, method, json, sample } => {
            let over = sample.parse()?;
            check_json(&json)?;
            let paths = if paths.is_empty() {
                let cases = corpus.dir(cullproof::locate::in_checkout())?.join("cases");
                anyhow::ensure!(
                    cases.is_dir(),
                    "{}: no such directory, so no case files to replay (`search` writes them there; pass case \
                     files or directories, or --corpus DIR)",
                    cases.display()
                );
                vec![cases]
            } else {
                paths
            };
            let files = cullproof::corpus::case_files(&paths)?;
            let cfg = cullproof::check::CheckConfig::default_with(cullproof::bounds::registry());
            if let Some(id) = method {
                anyhow::ensure!(
                    cullproof::corpus::method_of(&id).is_some(),
                    "--method {id}: no such method (see `cullproof methods`)"
                );
                let mut out = Vec::new();
                for f in &files {
                    out.push(cullproof::corpus::rejudge(f, &cfg, &over, &id)?);
                }
                for r in &out {
                    let w = match &r.witness {
                        Some(Ok((b, m))) => format!("stored witness still culled ({b}, margin {m:.3e})"),
                        Some(Err(e)) => format!("stored witness: {e}"),
                        None => "no stored witness".into(),
                    };
                    println!("{:<14} {} (found for {}): judged {}; {}", r.outcome, r.path, r.found_for, r.judged, w);
                }
                let fixed = out.iter().filter(|r| r.outcome == "fixed").count();
                println!("{} file(s) against {id}: {fixed} fixed, {} not", out.len(), out.len() - fixed);
                if let Some(p) = &json {
                    write_json(p, &serde_json::to_string_pretty(&out)?)?;
                }
                if fixed < out.len() {
                    exit(1);
                }
                return Ok(());
            }
            let mut out = Vec::new();
            for f in &files {
                out.push(cullproof::corpus::replay_with(f, &cfg, &over)?);
            }
            let bad = out.iter().filter(|r| !r.ok).count();
            for r in &out {
                let w = match &r.witness {
                    Some(Ok((b, m))) => format!("witness holds ({b}, margin {m:.3e})"),
                    Some(Err(e)) => format!("witness FAILS: {e}"),
                    None => "no witness".into(),
                };
                println!(
                    "{} {:<22} expected {:<12} judged {:<13} {}  {}{}",
                    if r.ok { "ok  " } else { "FAIL" },
                    r.method,
                    format!("{:?}", r.expected).to_lowercase(),
                    r.judged,
                    w,
                    r.path,
                    r.samples.as_ref().map_or(String::new(), |s| format!("  (samples {s})"))
                );
            }
            println!("{} file(s), {} as expected, {} not", out.len(), out.len() - bad, bad);
            if let Some(p) = &json {
                write_json(p, &serde_json::to_string_pretty(&out)?)?;
            }
            if bad > 0 {
                exit(1);
            }
        }
        Cmd::Explain { case, corpus, svg, sample } => {
            if let Some(out) = &svg {
                anyhow::ensure!(
                    std::fs::symlink_metadata(out).is_err(),
                    "--svg {}: the file exists (an existing file is never overwritten)",
                    out.display()
                );
                cullproof::output::file("--svg", out)?;
            }
            let case = cullproof::locate::case_path(&case, &corpus.dir(cullproof::locate::in_checkout())?)?;
            let mut cf = cullproof::corpus::CaseFile::load(&case)?;
            let over = sample.parse()?;
            cf.samples = over.samples.unwrap_or(cf.samples);
            cf.snap = over.snap.or(cf.snap);
            cf.viewport = over.viewport.or(cf.viewport);
            print!("{}", cullproof::corpus::describe(&cf));
            if let Some(out) = &svg {
                let m = cullproof::corpus::method_of(&cf.method).expect("checked at load");
                let w = cf.witness.as_ref().map(|w| w.sample).unwrap_or_else(|| {
                    let (x, y) = cf.tile.center();
                    [x as f64, y as f64, 0.0, 0.0, 0.5]
                });
                let caption = match &cf.witness {
                    Some(w) => format!("{} culls the witness by {:.3e}", w.bound, w.margin),
                    None => "no witness".into(),
                };
                // Under snapping the picture is of the snapped triangle the method saw.
                let (seen, _) = cullproof::check::samples::judged_triangles(cf.snap, &cf.case)
                    .map_err(|e| anyhow::anyhow!("{}: {e}", case.display()))?;
                let shown = if cf.snap.is_some() { cullproof::Case { triangle: seen, lens: None } } else { cf.case };
                let text = cullproof::explain::svg(&shown, &cf.tile, m, w, &caption)?;
                let mut f = std::fs::OpenOptions::new().write(true).create_new(true).open(out).with_context(|| {
                    format!("--svg {}: cannot create (an existing file is never overwritten)", out.display())
                })?;
                std::io::Write::write_all(&mut f, text.as_bytes())
                    .with_context(|| format!("writing {}", out.display()))?;
                println!("wrote {}", out.display());
            }
        }
        Cmd::Tightness(args) => cullproof::tightness::run_cli(&args)?,
        Cmd::Stability(args) => cullproof::stability::run_cli(&args)?,
        Cmd::Power { method, cases, seed, expectations, baseline, json, jobs } => {
            set_jobs(jobs)?;
            let methods = cullproof::args::methods("--method", &method, false)?;
            let cases = cullproof::args::count("--cases", cases, 1_000_000, "cases")?;
            check_json(&json)?;
            let in_checkout = cullproof::locate::in_checkout();
            let ex = expectations_for(&expectations, in_checkout, "the expectations file is required")?;
            let base = baseline_for(&baseline, in_checkout)?.file;
            let mut cfg = cullproof::check::CheckConfig::default_with(methods);
            cfg.cases = cases;
            cfg.seed = seed;
            let slips = cullproof::bounds::broken::KINDS;
            let r = cullproof::check::power::run(&cfg, &ex, base.as_ref(), &slips, true);
            print!("{}", cullproof::check::power::render(&r, &slips));
            if let Some(p) = &json {
                write_json(p, &serde_json::to_string_pretty(&r)?)?;
            }
        }
        Cmd::Proofs(args) => {
            if !cullproof::proofs::cli::run_cli(&args)? {
                exit(1);
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
