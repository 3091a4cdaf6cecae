//! `cullproof proofs`: list the variants proven for all inputs in their ranges, re-run
//! their scripts (with their verdicts and times) and the checks that tie the scripts
//! to the code, and print each method's strongest verdict.

use crate::bounds::proofs::{strength, variant, Script, Tool, Variant, SCRIPTS, VARIANTS};
use crate::tools::proofs::check;
use crate::tools::proofs::composition::{self, SideRun};
use crate::tools::proofs::enclosure;
use crate::tools::proofs::run::{self, Outcome, Verdict};
use anyhow::{bail, Result};
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use std::time::{Duration, Instant};

/// Arguments of `cullproof proofs`.
#[derive(clap::Args, Debug, Clone)]
pub struct ProofsArgs {
    /// Methods: `all`, or comma-separated ids (see `cullproof methods`). A method without
    /// a proof for all inputs is listed with its strength and has no scripts to run. A
    /// planted slip of a variant with a template obligation
    /// (`broken/planted-no-up/la2011-safe`, ...) runs that obligation, which must fail.
    #[arg(long, default_value = "all")]
    pub method: String,
    /// Time limit per script and per template query, in seconds (one that takes longer
    /// is a failure).
    #[arg(long, default_value_t = 300.0)]
    pub timeout: f64,
    /// Triangles (and lines) on which `bbox-safe`'s setup (and `wu2013-safe`'s lines) are
    /// compared with their scripts' formulas.
    #[arg(long, default_value_t = 20_000)]
    pub triangles: u64,
    /// Scripts run at a time (default 2; each tool uses one core).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Print the JSON report on standard output instead of the tables.
    #[arg(long)]
    pub json: bool,
}

/// One script's run.
#[derive(Clone, Debug, Serialize)]
pub struct ScriptRun {
    pub script: Script,
    pub outcome: Outcome,
}

/// One check of scripts against code.
#[derive(Clone, Debug, Serialize)]
pub struct CheckRun {
    pub name: &'static str,
    /// None when it passed, the mismatch otherwise.
    pub error: Option<String>,
    pub seconds: f64,
}

/// A method's strongest verdict, and its proof when it has one.
#[derive(Clone, Debug, Serialize)]
pub struct MethodStrength {
    pub id: &'static str,
    pub strength: &'static str,
    pub proof: Option<Variant>,
    /// Every script of the proof proven and every check passed in this run.
    pub rerun_ok: Option<bool>,
}

/// One variant's enclosure check (see [`enclosure`]).
#[derive(Clone, Debug, Serialize)]
pub struct EnclosureRun {
    pub method: &'static str,
    /// Operations of the traced tile answer.
    pub ops: usize,
    /// Output ends checked.
    pub outputs: usize,
    /// Pinned ends checked, and the lemmas they use.
    pub pins: usize,
    pub lemmas: Vec<&'static str>,
    /// Values the code chooses freely.
    pub choices: Vec<&'static str>,
    /// Each rule and how often it applied.
    pub rules: Vec<(&'static str, usize)>,
    /// Demands not met: `what` and what the value is instead (none: checked).
    pub failures: Vec<(String, String)>,
    pub seconds: f64,
}

/// Run the enclosure check of `id`, if it has one.
pub fn run_enclosure(id: &'static str) -> Option<EnclosureRun> {
    let t = Instant::now();
    let o = enclosure::check(id)?;
    Some(EnclosureRun {
        method: id,
        ops: o.ops,
        outputs: o.outputs,
        pins: o.pins,
        lemmas: o.lemmas,
        choices: o.choices,
        rules: o.rules,
        failures: o.failures.into_iter().map(|f| (f.what, f.found)).collect(),
        seconds: t.elapsed().as_secs_f64(),
    })
}

/// The whole report.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    pub scripts: Vec<ScriptRun>,
    pub checks: Vec<CheckRun>,
    /// The composition over the code on the template (see [`composition`]): one query
    /// per side of each variant that has one.
    pub composition: Vec<SideRun>,
    /// The composition over the code for every input (see [`enclosure`]): one run per
    /// variant that has one.
    pub enclosure: Vec<EnclosureRun>,
    pub methods: Vec<MethodStrength>,
    pub seconds: f64,
}

impl Report {
    /// Every script proven, every check passed and every template query proven.
    pub fn ok(&self) -> bool {
        self.scripts.iter().all(|s| s.outcome.verdict == Verdict::Proven)
            && self.checks.iter().all(|c| c.error.is_none())
            && self.composition.iter().all(|c| c.error.is_none())
            && self.enclosure.iter().all(|e| e.failures.is_empty())
    }
}

/// The checks of scripts against code (see [`check`]); `z3` runs the primitives script.
pub fn run_checks(triangles: usize, bbox: bool, wu: bool, limit: Duration) -> Vec<CheckRun> {
    let timed = |name, f: &dyn Fn() -> Result<(), String>| {
        let t = Instant::now();
        let r = f();
        CheckRun { name, error: r.err(), seconds: t.elapsed().as_secs_f64() }
    };
    let mut out = vec![timed("constants of the scripts = the code's", &check::constants)];
    if bbox {
        out.push(timed("bbox-safe setup = bbox_safe.g's formula", &|| check::bbox_formula(triangles)));
    }
    if wu {
        out.push(timed("wu2013-safe lines = wu2013_safe.g's formula", &|| check::wu_formula(triangles)));
    }
    out.push(timed("prelude's nd, nu, rn = Rust's next_down, next_up, rounding (z3)", &|| {
        let o = run::run_text(Tool::Z3, &check::primitives_script(), limit);
        match o.verdict {
            Verdict::Proven => Ok(()),
            v => Err(format!("{}: {v:?}", v.word())),
        }
    }));
    out
}

/// Run the proofs of `ids` (registry ids; those without a proof are only listed).
/// `jobs` scripts run at a time.
pub fn run(ids: &[&'static str], limit: Duration, triangles: usize, jobs: usize, progress: bool) -> Report {
    let start = Instant::now();
    let chosen: Vec<&Variant> = VARIANTS.iter().filter(|v| ids.contains(&v.id)).collect();
    let scripts: Vec<&Script> = SCRIPTS.iter().filter(|s| chosen.iter().any(|v| v.scripts.contains(&s.name))).collect();
    let pb = if progress { ProgressBar::new(scripts.len() as u64 + 1) } else { ProgressBar::hidden() };
    pb.set_style(
        ProgressStyle::with_template("{msg:>16} {bar:40} {pos}/{len} scripts {elapsed_precise}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    // Two scripts at a time (each tool is single-threaded); results in script order.
    let next = std::sync::atomic::AtomicUsize::new(0);
    let done = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|sc| {
        for _ in 0..jobs.clamp(1, scripts.len().max(1)) {
            sc.spawn(|| loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                let Some(s) = scripts.get(i) else { break };
                pb.set_message(s.name);
                let o = run::run(s, limit);
                done.lock().unwrap_or_else(|e| e.into_inner()).push((i, ScriptRun { script: **s, outcome: o }));
                pb.inc(1);
            });
        }
    });
    let mut runs = done.into_inner().unwrap_or_else(|e| e.into_inner());
    runs.sort_by_key(|(i, _)| *i);
    let runs: Vec<ScriptRun> = runs.into_iter().map(|(_, r)| r).collect();
    pb.set_message("checks");
    let checks = if chosen.is_empty() {
        Vec::new()
    } else {
        let has = |id| chosen.iter().any(|v| v.id == id);
        run_checks(triangles, has("bbox-safe"), has("wu2013-safe"), limit)
    };
    let mut comp = Vec::new();
    for id in ids.iter().filter(|id| composition::applies(id)) {
        pb.set_message(format!("template {id}"));
        comp.extend(composition::run(id, limit));
    }
    pb.set_message("enclosure");
    let encl: Vec<EnclosureRun> = ids.iter().filter_map(|id| run_enclosure(id)).collect();
    pb.finish_and_clear();
    let encl_ok = |id: &str| encl.iter().filter(|e| e.method == id).all(|e| e.failures.is_empty());
    let has_encl = |id: &str| encl.iter().any(|e| e.method == id);
    let checks_ok = checks.iter().all(|c| c.error.is_none());
    let comp_ok = |id: &str| comp.iter().filter(|c| c.method == id).all(|c| c.error.is_none());
    let methods = ids
        .iter()
        .map(|&id| {
            let proof = variant(id).copied();
            let rerun_ok = match proof {
                Some(v) => Some(
                    checks_ok
                        && comp_ok(id)
                        && encl_ok(id)
                        && v.scripts.iter().all(|n| {
                            runs.iter().any(|r: &ScriptRun| r.script.name == *n && r.outcome.verdict == Verdict::Proven)
                        }),
                ),
                None => (composition::applies(id) || has_encl(id)).then(|| comp_ok(id) && encl_ok(id)),
            };
            MethodStrength { id, strength: strength(id), proof, rerun_ok }
        })
        .collect();
    Report {
        scripts: runs,
        checks,
        composition: comp,
        enclosure: encl,
        methods,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// The tables.
pub fn render(r: &Report) -> String {
    let mut s = String::from("Scripts (src/bounds/proofs/; times are wall clock):\n");
    s += &format!("{:<16} {:<22} {:<6} {:<8} {:>8}\n", "lemma", "file", "tool", "verdict", "seconds");
    for x in &r.scripts {
        s += &format!(
            "{:<16} {:<22} {:<6} {:<8} {:>8.2}\n",
            x.script.name,
            x.script.file,
            x.script.tool.binary(),
            x.outcome.verdict.word(),
            x.outcome.seconds
        );
        match &x.outcome.verdict {
            Verdict::Proven => {}
            Verdict::Refuted(d) | Verdict::Unknown(d) | Verdict::Missing(d) => s += &format!("    {d}\n"),
            Verdict::Timeout => s += "    the time limit passed (--timeout)\n",
        }
    }
    if !r.checks.is_empty() {
        s += "\nScripts against the code:\n";
        for c in &r.checks {
            s += &format!(
                "  {:<8} {:>8.2}  {}{}\n",
                if c.error.is_none() { "ok" } else { "MISMATCH" },
                c.seconds,
                c.name,
                c.error.as_deref().map(|e| format!(": {e}")).unwrap_or_default()
            );
        }
    }
    if !r.composition.is_empty() {
        s += &format!(
            "\nComposition over the code, on the template (a static triangle, {}; one query per side, \
             z3 and Bitwuzla, first answer wins):\n",
            composition::TEMPLATE_RANGES
        );
        for c in &r.composition {
            s += &format!(
                "  {:<8} {:<34} {:<6} {:<8} {:<9} {:>8.2}{}\n",
                if c.error.is_none() { "proven" } else { "FAILED" },
                c.method,
                c.side,
                c.answer,
                c.solver,
                c.seconds,
                c.error.as_deref().map(|e| format!("  {e}")).unwrap_or_default()
            );
        }
    }
    if !r.enclosure.is_empty() {
        s += "\nComposition over the code, for every input (the enclosure check: the tile answer traced; every \
              end on its side of its exact value and every cull implying its exact counterpart, by the rules of \
              `enclosure rules`):\n";
        for e in &r.enclosure {
            s += &format!(
                "  {:<8} {:<34} {} outputs (ends and culls), {} pins, {} operations {:>8.2}\n",
                if e.failures.is_empty() { "checked" } else { "FAILED" },
                e.method,
                e.outputs,
                e.pins,
                e.ops,
                e.seconds
            );
            for l in &e.lemmas {
                s += &format!("      lemma: {l}\n");
            }
            for c in &e.choices {
                s += &format!("      chosen freely: {c}\n");
            }
            for (what, found) in e.failures.iter().take(8) {
                s += &format!("      {what}: {found}\n");
            }
            if e.failures.len() > 8 {
                s += &format!("      ... and {} more\n", e.failures.len() - 8);
            }
        }
    }
    s += "\nStrongest verdict per method:\n";
    for m in &r.methods {
        match (&m.proof, m.rerun_ok) {
            (Some(v), Some(ok)) => {
                s += &format!(
                    "{:<24} {} — re-run: {}\n",
                    m.id,
                    m.strength,
                    if ok { "every script, check and template query proven" } else { "FAILED" }
                );
                for rg in v.ranges {
                    s += &format!("    {}: {}\n", rg.inputs, rg.range);
                }
                s += &format!("    scripts: {}\n", v.scripts.join(", "));
            }
            (None, Some(ok)) => {
                s += &format!(
                    "{:<24} {} — its checks over the code: {}\n",
                    m.id,
                    m.strength,
                    if ok { "proven" } else { "FAILED" }
                )
            }
            _ => s += &format!("{:<24} {}\n", m.id, m.strength),
        }
    }
    s += &format!("\n{} in {:.1} s\n", if r.ok() { "all proofs re-run" } else { "SOME PROOFS FAILED" }, r.seconds);
    s
}

/// `cullproof proofs`: exit status 1 (through the caller) when a proof failed.
pub fn run_cli(args: &ProofsArgs) -> Result<bool> {
    let methods = crate::cli::args::methods("--method", &args.method, true)?;
    crate::cli::args::time("--timeout", args.timeout, 3600.0)?;
    if args.triangles == 0 || args.triangles > 10_000_000 {
        bail!("--triangles {}: must be 1..=10000000", args.triangles);
    }
    let ids: Vec<&'static str> = methods.iter().map(|m| m.info().id).collect();
    let jobs = crate::cli::args::jobs(args.jobs)?.unwrap_or(2);
    let r = run(&ids, Duration::from_secs_f64(args.timeout), args.triangles as usize, jobs, !args.json);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
    } else {
        print!("{}", render(&r));
    }
    Ok(r.ok())
}
