//! `stability`: sweep one parameter of the cases towards a method's singularity, on a
//! log scale, and watch where each culling method breaks.
//!
//! For every step of a family (see [`Family`] and `families.rs` for how each builds its
//! cases) and every method, over `cases` seeded cases:
//!
//! - **violations**: cases where the gate's own judge ([`crate::gate::judge()`], the
//!   certified side search and constraint search of `check`, with the default
//!   [`CheckConfig`]) found an interior sample, confirmed in exact arithmetic, that the
//!   method culls. **undecided**: cases where some claim could be neither confirmed nor
//!   refuted within the judge's budgets (reported, never folded into either side);
//!   **boundary-only**: only boundary samples were culled.
//! - **NaN/inf**: cases where the method's tile answer (`setup(&tri).tile(&tile)`) has a
//!   non-finite interval end (u, v, t or z) or a per-sample constraint that evaluates to
//!   NaN or +-inf on one of the uniform tile samples.
//! - **STE** (sample test efficiency): over `samples` uniform samples in the tile
//!   ([`crate::cases::generate::tile_sample`]: whole lens and shutter), `hits / tested` summed over
//!   the step's cases, where tested = the method lets the sample through (tile not
//!   empty and [`TileBounds::admits`](crate::bounds::TileBounds::admits)) and hits = tested and exactly interior
//!   ([`oracles::classify`]). Undefined ("-", `null` in JSON) when nothing was tested.
//! - **first fails at**: per method, the first step (from the benign end) with a
//!   certified violation; and the first step with a **gross** one, whose margin (the
//!   padding of the violated bound that would admit the witness, in the bound's own
//!   units: u, v, t, depth, or the constraint's value) exceeds [`GROSS_MARGIN`] or is
//!   infinite (a covered tile culled). Every published bound computed in f32 misses by a
//!   few ulps somewhere (`corpus/expectations.json` allows margins up to 1e-4 for
//!   that), so the plain first failure often sits at the benign end; the gross one is
//!   where a family's parameter breaks a method.
//!
//! Case `c` of step `s` draws everything from `cases::generate::rng_for(seed ^ family salt,
//! s * 1_000_000 + c)` (the judge's uniform samples from the same index, the STE
//! samples from a stream of their own), and results are merged in case order: a run
//! is identical at any thread count.
//!
//! Outputs: a table per family on the terminal; `<out>/<family>.md` (the same tables
//! with how the family is built and the parameter measured back from the f32 cases)
//! and `<out>/<family>.svg` (three stacked panels over the swept parameter: violation
//! rate, NaN/inf rate, STE; one line per method); with `--json FILE`, every row.

pub mod chart;
pub mod families;
#[cfg(test)]
mod tests;

pub use families::{Built, Family};

use crate::bounds::{Method, TileResult};
use crate::cases::generate::{rng_for, tile_sample};
use crate::gate::{self, CheckConfig};
use crate::model::Sample;
use indicatif::{ProgressBar, ProgressStyle};
use oracles::Coverage;
use rayon::prelude::*;
use serde::Serialize;
use std::time::Instant;

/// A violation with a larger margin (or an infinite one) is "gross": beyond the f32
/// rounding that `corpus/expectations.json` allows the published bounds (max_margin 1e-4).
pub const GROSS_MARGIN: f64 = 1e-4;

/// Mixed into the family's seed for the STE / NaN samples.
const STE_SALT: u64 = 0x57e5_a3b1_e5ed_0001;

/// Settings of a run.
#[derive(Clone)]
pub struct Config {
    pub methods: Vec<&'static dyn Method>,
    /// Steps per family (None: the family's default).
    pub steps: Option<usize>,
    pub cases: u64,
    pub seed: u64,
    pub tile: f32,
    pub samples: usize,
}

impl Config {
    pub fn new(methods: Vec<&'static dyn Method>) -> Self {
        Config { methods, steps: None, cases: 32, seed: 1, tile: 4.0, samples: 512 }
    }
}

/// One method at one step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Row {
    pub family: String,
    /// Index of the step (0 = the benign end).
    pub step: usize,
    /// The swept parameter's value at this step.
    pub parameter: f64,
    pub method: String,
    pub cases: u64,
    /// Cases with a certified violation.
    pub violations: u64,
    pub undecided: u64,
    pub boundary_only: u64,
    /// Cases whose tile answer had a non-finite end or constraint value.
    pub nonfinite: u64,
    /// Cases where the method was disabled for the triangle (full bounds).
    pub disabled: u64,
    /// Uniform samples the method let through / those of them exactly interior.
    pub tested: u64,
    pub hits: u64,
    /// hits / tested (None when tested = 0).
    pub ste: Option<f64>,
    /// Largest margin needed over the violations ("inf": a covered tile was culled; 0: none).
    #[serde(serialize_with = "crate::io::num_or_inf::serialize")]
    pub margin: f64,
    /// The bound violated with that margin.
    pub worst_bound: Option<String>,
    /// Its witness, to replay or shrink the finding (JSON only).
    pub witness: Option<RowWitness>,
}

/// The worst violation of a row: the case, the tile and the covered sample culled.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RowWitness {
    /// `step * 1_000_000 + case` (the case's stream index).
    pub case_index: u64,
    pub case: crate::model::Case,
    pub tile: crate::model::Tile,
    pub sample: [f64; 5],
}

impl Row {
    pub fn violation_rate(&self) -> f64 {
        self.violations as f64 / self.cases.max(1) as f64
    }
    pub fn nonfinite_rate(&self) -> f64 {
        self.nonfinite as f64 / self.cases.max(1) as f64
    }
}

/// The parameter at one step, as requested and as measured from the f32 cases.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Step {
    pub step: usize,
    pub parameter: f64,
    pub achieved_min: f64,
    pub achieved_max: f64,
}

/// Where a method first fails.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FirstFail {
    pub method: String,
    /// The first step with a violation (None: none in the sweep).
    pub step: Option<usize>,
    pub parameter: Option<f64>,
    /// The first step with a gross violation (margin > [`GROSS_MARGIN`] or infinite).
    pub gross_step: Option<usize>,
    pub gross_parameter: Option<f64>,
    /// Steps with a violation, out of all steps.
    pub failing_steps: usize,
}

/// One family's sweep.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FamilyReport {
    pub family: String,
    pub parameter: String,
    pub construction: String,
    pub seed: u64,
    pub cases: u64,
    pub tile: f32,
    pub samples: usize,
    pub methods: Vec<String>,
    pub steps: Vec<Step>,
    pub rows: Vec<Row>,
    pub first_fails: Vec<FirstFail>,
    /// Wall time (s); not part of the comparison of two runs.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seconds: Option<f64>,
}

/// The JSON file of a run.
#[derive(Clone, Debug, Serialize)]
pub struct StabilityReport {
    /// Always "cullproof-stability".
    pub kind: &'static str,
    pub seed: u64,
    pub threads: usize,
    pub families: Vec<FamilyReport>,
    pub seconds: f64,
}

/// What one case gives one method.
#[derive(Clone, Debug, Default)]
struct Outcome {
    violation: Option<crate::judge::Witness>,
    undecided: bool,
    boundary_only: bool,
    nonfinite: bool,
    disabled: bool,
    tested: u64,
    hits: u64,
}

fn eval_case(cfg: &Config, ccfg: &CheckConfig, family: Family, step: usize, param: f64, c: u64) -> (f64, Vec<Outcome>) {
    let seed = cfg.seed ^ family.salt();
    let index = step as u64 * 1_000_000 + c;
    let mut rng = rng_for(seed, index);
    let b = family.build(param, &mut rng, c, cfg.tile);
    let (js, _) = gate::judge(ccfg, &ccfg.methods, &b.case, &b.tile, index);
    let mut srng = rng_for(seed ^ STE_SALT, index);
    let samples: Vec<Sample> = (0..cfg.samples).map(|_| tile_sample(&mut srng, &b.tile)).collect();
    let tri = b.case.triangle;
    let otri = tri.to_oracle();
    let points: Vec<[f64; 5]> = samples.iter().map(Sample::to_oracle).collect();
    let mut classes = Vec::new();
    oracles::batch::classify_batch(&otri, &points, &mut classes);
    let covered: Vec<bool> = classes.iter().map(|c| *c == Coverage::Interior).collect();
    let out = cfg
        .methods
        .iter()
        .zip(js)
        .map(|(m, j)| {
            let mut o = Outcome {
                undecided: j.verdict() == crate::judge::Verdict::Unproven,
                violation: j.violation,
                boundary_only: j.boundary_only,
                ..Default::default()
            };
            let prep = m.setup(&tri);
            o.disabled = prep.disabled().is_some();
            if let TileResult::Bounds(tb) = prep.tile(&b.tile) {
                let ends = [tb.u, tb.v, tb.t, tb.z.unwrap_or([0.0; 2])];
                o.nonfinite = ends.iter().flatten().any(|x| !x.is_finite())
                    || samples.iter().any(|s| tb.constraints.iter().any(|g| !g.eval(s).is_finite()));
                for (s, &cov) in samples.iter().zip(&covered) {
                    if tb.admits(s) {
                        o.tested += 1;
                        o.hits += cov as u64;
                    }
                }
            }
            o
        })
        .collect();
    (b.achieved, out)
}

/// Sweep one family.
pub fn run_family(cfg: &Config, family: Family, progress: bool) -> FamilyReport {
    let start = Instant::now();
    let params = family.steps(cfg.steps);
    let mut ccfg = CheckConfig::default_with(cfg.methods.clone());
    ccfg.seed = cfg.seed ^ family.salt();
    ccfg.tile = Some(cfg.tile);
    // Few cases per step, each judged with the whole side budget: a sweep wants the
    // first rounding witness, not throughput.
    ccfg.judge.side_stall = 0;
    let jobs: Vec<(usize, u64)> = (0..params.len()).flat_map(|s| (0..cfg.cases).map(move |c| (s, c))).collect();
    let pb = if progress { ProgressBar::new(jobs.len() as u64) } else { ProgressBar::hidden() };
    pb.set_style(
        ProgressStyle::with_template("{msg:>12} {bar:40} {pos}/{len} cases {elapsed_precise} eta {eta}").unwrap(),
    );
    pb.set_message(family.name());
    let results: Vec<(f64, Vec<Outcome>)> = jobs
        .par_iter()
        .map(|&(s, c)| {
            let r = eval_case(cfg, &ccfg, family, s, params[s], c);
            pb.inc(1);
            r
        })
        .collect();
    pb.finish_and_clear();
    let ids: Vec<String> = cfg.methods.iter().map(|m| m.info().id.to_string()).collect();
    let mut rows = Vec::new();
    let mut steps = Vec::new();
    for (s, &param) in params.iter().enumerate() {
        let here = &results[s * cfg.cases as usize..(s + 1) * cfg.cases as usize];
        let ach = here.iter().map(|r| r.0);
        steps.push(Step {
            step: s,
            parameter: param,
            achieved_min: ach.clone().fold(f64::INFINITY, f64::min),
            achieved_max: ach.fold(f64::NEG_INFINITY, f64::max),
        });
        for (mi, id) in ids.iter().enumerate() {
            let mut row = Row {
                family: family.name().into(),
                step: s,
                parameter: param,
                method: id.clone(),
                cases: 0,
                violations: 0,
                undecided: 0,
                boundary_only: 0,
                nonfinite: 0,
                disabled: 0,
                tested: 0,
                hits: 0,
                ste: None,
                margin: 0.0,
                worst_bound: None,
                witness: None,
            };
            for (_, os) in here {
                let o = &os[mi];
                row.cases += 1;
                row.undecided += o.undecided as u64;
                row.boundary_only += o.boundary_only as u64;
                row.nonfinite += o.nonfinite as u64;
                row.disabled += o.disabled as u64;
                row.tested += o.tested;
                row.hits += o.hits;
                if let Some(w) = &o.violation {
                    row.violations += 1;
                    if row.worst_bound.is_none() || w.margin > row.margin {
                        row.margin = w.margin;
                        row.worst_bound = Some(w.bound.clone());
                        row.witness =
                            Some(RowWitness { case_index: w.case_index, case: w.case, tile: w.tile, sample: w.sample });
                    }
                }
            }
            row.ste = (row.tested > 0).then(|| row.hits as f64 / row.tested as f64);
            rows.push(row);
        }
    }
    let first_fails = ids
        .iter()
        .map(|id| {
            let failing: Vec<&Row> = rows.iter().filter(|r| &r.method == id && r.violations > 0).collect();
            let gross = failing.iter().find(|r| r.margin > GROSS_MARGIN);
            FirstFail {
                method: id.clone(),
                step: failing.first().map(|r| r.step),
                parameter: failing.first().map(|r| r.parameter),
                gross_step: gross.map(|r| r.step),
                gross_parameter: gross.map(|r| r.parameter),
                failing_steps: failing.len(),
            }
        })
        .collect();
    FamilyReport {
        family: family.name().into(),
        parameter: family.parameter().into(),
        construction: family.describe().into(),
        seed: cfg.seed,
        cases: cfg.cases,
        tile: cfg.tile,
        samples: cfg.samples,
        methods: ids,
        steps,
        rows,
        first_fails,
        seconds: Some(start.elapsed().as_secs_f64()),
    }
}

/// A parameter value, short: "1e-6", "0", "1024", "3.162e-4".
pub fn fmt_param(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if x.fract() == 0.0 && x.abs() < 1e5 {
        return format!("{x}");
    }
    let s = format!("{x:e}");
    if s.len() <= 8 {
        s
    } else {
        format!("{x:.3e}")
    }
}

fn fmt_margin(r: &Row) -> String {
    match r.violations {
        0 => "-".into(),
        _ if r.margin.is_infinite() => "inf".into(),
        _ => format!("{:.2e}", r.margin),
    }
}

fn fmt_ste(x: Option<f64>) -> String {
    match x {
        None => "-".into(),
        Some(v) => format!("{:.2}%", 100.0 * v),
    }
}

/// The tables of one family (plain text, or Markdown when `md`).
pub fn render(r: &FamilyReport, md: bool) -> String {
    let mut s = String::new();
    let secs = r.seconds.map(|x| format!(", {x:.1} s")).unwrap_or_default();
    let head = format!(
        "stability: {} - parameter: {}; seed {}, {} cases per step, tile {} px, {} samples per case{}",
        r.family, r.parameter, r.seed, r.cases, r.tile, r.samples, secs
    );
    if md {
        s += &format!("# {head}\n\n## How the cases are built\n\n{}\n\n", r.construction);
        s += "## Steps: the parameter as requested and as measured from the f32 cases\n\n";
        s += "| step | requested | measured min | measured max |\n|---:|---:|---:|---:|\n";
        for st in &r.steps {
            s += &format!(
                "| {} | {} | {:.6e} | {:.6e} |\n",
                st.step,
                fmt_param(st.parameter),
                st.achieved_min,
                st.achieved_max
            );
        }
        s += "\n## Per step and method\n\n";
        s += "| step value | method | violations/cases | undecided | NaN/inf rate | STE | disabled \
              | worst bound (margin) |\n";
        s += "|---:|---|---:|---:|---:|---:|---:|---|\n";
    } else {
        s += &format!("{head}\n\n");
        s += &format!(
            "{:>10}  {:<26} {:>16} {:>9} {:>12} {:>8}  {:>10}\n",
            "step value", "method", "violations/cases", "undecided", "NaN/inf rate", "STE", "max margin"
        );
    }
    let mut last = usize::MAX;
    for row in &r.rows {
        let p = if row.step == last && !md { String::new() } else { fmt_param(row.parameter) };
        last = row.step;
        let vc = format!("{}/{}", row.violations, row.cases);
        if md {
            let worst = match &row.worst_bound {
                Some(b) if row.margin.is_infinite() => format!("{b} (inf)"),
                Some(b) => format!("{b} ({:.3e})", row.margin),
                None => "-".into(),
            };
            s += &format!(
                "| {p} | {} | {vc} | {} | {:.3} | {} | {} | {worst} |\n",
                row.method,
                row.undecided,
                row.nonfinite_rate(),
                fmt_ste(row.ste),
                row.disabled
            );
        } else {
            s += &format!(
                "{p:>10}  {:<26} {vc:>16} {:>9} {:>12.3} {:>8}  {:>10}\n",
                row.method,
                row.undecided,
                row.nonfinite_rate(),
                fmt_ste(row.ste),
                fmt_margin(row)
            );
        }
    }
    if md {
        s += &format!(
            "\n## First fails at\n\n| method | first fails at | first gross failure (margin > {GROSS_MARGIN:e}) \
             | failing steps |\n|---|---:|---:|---:|\n"
        );
    } else {
        s += &format!(
            "\nfirst fails at (the first step with a certified violation; gross: with a margin > \
             {GROSS_MARGIN:e} or inf):\n  {:<26} {:>14} {:>14} {:>14}\n",
            "method", "first fails at", "first gross", "failing steps"
        );
    }
    for f in &r.first_fails {
        let at = f.parameter.map(fmt_param).unwrap_or_else(|| "-".into());
        let gross = f.gross_parameter.map(fmt_param).unwrap_or_else(|| "-".into());
        let n = format!("{}/{}", f.failing_steps, r.steps.len());
        if md {
            s += &format!("| {} | {at} | {gross} | {n} |\n", f.method);
        } else {
            s += &format!("  {:<26} {at:>14} {gross:>14} {n:>14}\n", f.method);
        }
    }
    s += "\nviolations: cases with an exactly confirmed covered sample the method culls (the gate's judge); \
          undecided: the judge's budget ran out on some claim; NaN/inf: the tile answer had a non-finite end or \
          constraint value; STE: covered / let-through uniform samples (-: none let through); max margin: the \
          padding of the violated bound that would admit the worst witness, in the bound's units (inf: a covered \
          tile culled).\n";
    s
}
