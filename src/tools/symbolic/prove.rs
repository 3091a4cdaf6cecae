//! `cullproof prove --symbolic`: run a method's queries through z3, each with a time
//! limit and (by default) a deterministic resource limit, on `jobs` threads, and turn
//! every model into a case that the exact judge decides. z3 is never the judge: a model
//! the judge does not confirm is reported as unconfirmed, and an `unsat` says only that
//! no input of the query's template, ranges and fixed values makes the method cull a
//! tile the exact footprint reaches (under the concolic plan, with some inputs fixed,
//! that is no statement about the ranges).
//!
//! The run stops at the first query (in plan order) whose model the judge confirms:
//! queries are handed out in order, the ones before it are finished, the ones after it
//! are not started (or their results dropped). With the resource limit every answer is
//! the same on any machine, so the report for a seed does not depend on `jobs`; only a
//! query that hits the wall-clock guard (`timeout`) is reported as a timeout, which
//! depends on the machine.

use super::bbox_query::TemplateFamily;
use super::concolic;
use super::family::{self, Family, Query};
use super::la2011_query::La2011Cull;
use super::rounding::Rounding;
use super::solver::{self, Solver, Solvers};
use super::z3::{self, Answer};
use crate::bounds::arith::F32Arith;
use crate::bounds::bbox::{Corner, PlainCorner, SafeCorner};
use crate::bounds::broken::planted::{BandSlip, EqSlip};
use crate::bounds::{shared, Method, TileResult};
use crate::gate::{judge, CheckConfig};
use crate::model::Case;
use crate::search::{shrink, CaseFile};
use anyhow::{bail, Context, Result};
use serde::Serialize;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

/// The corner rule of a method whose setup and tile reject are encoded.
#[derive(Clone, Copy, Debug)]
pub enum Rule {
    Plain,
    Safe,
    Eq,
    Band,
}

impl Corner for Rule {
    fn corner<A: F32Arith>(&self, ar: &A, a: &A::F, s: &A::F, n: &A::F, w: &A::F) -> [A::F; 2] {
        match self {
            Rule::Plain => PlainCorner.corner(ar, a, s, n, w),
            Rule::Safe => SafeCorner.corner(ar, a, s, n, w),
            Rule::Eq => EqSlip.corner(ar, a, s, n, w),
            Rule::Band => BandSlip.corner(ar, a, s, n, w),
        }
    }
}

/// The methods with a symbolic encoding (setup and tile reject, over
/// [`crate::bounds::arith::F32Arith`]) and a query family.
pub const ENCODED: [&str; 19] = [
    "bbox",
    "bbox-safe",
    "la2011",
    "la2011-safe",
    "mam2012",
    "mam2012-safe",
    "nilsson2012-depth",
    "nilsson2012-depth-safe",
    "broken/planted-eq/bbox-safe",
    "broken/planted-band/bbox-safe",
    "broken/planted-no-up/la2011-safe",
    "broken/planted-no-dn/la2011-safe",
    "broken/planted-no-up/nilsson2012-depth-safe",
    "broken/planted-no-dn/nilsson2012-depth-safe",
    "broken/planted-no-up/mam2012-safe",
    "broken/planted-no-dn/mam2012-safe",
    "wu2013-safe",
    "broken/planted-no-up/wu2013-safe",
    "broken/planted-no-dn/wu2013-safe",
];

/// The encoding of a bbox-like method, or an error naming the ones there are.
pub fn rule(id: &str) -> Result<Rule> {
    Ok(match id {
        "bbox" => Rule::Plain,
        "bbox-safe" => Rule::Safe,
        "broken/planted-eq/bbox-safe" => Rule::Eq,
        "broken/planted-band/bbox-safe" => Rule::Band,
        _ => bail!(
            "--method {id}: no symbolic encoding (methods with one: {}; encoded in part: {})",
            ENCODED.join(", "),
            PARTLY_ENCODED.join(", ")
        ),
    })
}

/// The triangle and tile a query family builds around a method's cull.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum Template {
    /// A static triangle with a vertical edge (four inputs; [`super::bbox_query`]).
    Static,
    /// The same triangle moving and changing its CoC over the shutter (seven inputs;
    /// [`super::moving_query`]).
    Moving,
}

/// The cull of an encoded method, on any template.
#[derive(Clone, Copy, Debug)]
pub enum Cull {
    Bbox(Rule),
    La2011(super::la2011_query::La2011Cull),
    Mam2012(super::mam2012_query::Mam2012Cull),
    Wu2013(super::wu2013_query::Wu2013Cull),
    Nilsson2012(super::nilsson2012_query::Nilsson2012Cull),
    /// A conjunction of tests with only some parts encoded: any encoded part's cull culls
    /// the whole (a part's Empty is the conjunction's answer); the parts left out, named,
    /// can only cull more, so a model is a counterexample but an `unsat` proves nothing.
    Parts(&'static [Cull], &'static str),
}

/// The part `lc` and `mam2012-new` are searched through: `la2011`. lc's `lb2011`
/// patches are not encoded; mam2012-new's `mam2012` part is, but with it in the
/// disjunction the narrow static query timed out (Bitwuzla, 300 s) where `la2011`'s alone
/// is sat in seconds, and its hyperplane part is not.
static LA2011_PART: [Cull; 1] = [Cull::La2011(La2011Cull(Rounding::Nearest))];

/// The conjunctions encoded in part ([`Cull::Parts`]): a model is a counterexample, an
/// `unsat` is never counted.
pub const PARTLY_ENCODED: [&str; 2] = ["lc", "mam2012-new"];

impl super::bbox_query::TemplateCull for Cull {
    fn cull(
        &self,
        smt: &super::smt::Smt,
        side: super::bbox_query::Side,
        tri: &crate::bounds::arith::TriOf<String>,
        tile: &[String; 4],
    ) -> String {
        match self {
            Cull::Bbox(r) => r.cull(smt, side, tri, tile),
            Cull::La2011(c) => c.cull(smt, side, tri, tile),
            Cull::Mam2012(c) => c.cull(smt, side, tri, tile),
            Cull::Wu2013(c) => c.cull(smt, side, tri, tile),
            Cull::Nilsson2012(c) => c.cull(smt, side, tri, tile),
            Cull::Parts(parts, _) => {
                let terms: Vec<String> = parts.iter().map(|p| p.cull(smt, side, tri, tile)).collect();
                smt.any(&terms)
            }
        }
    }
    fn partial(&self) -> Option<&'static str> {
        match self {
            Cull::Parts(_, left_out) => Some(left_out),
            _ => None,
        }
    }
    fn depth(&self) -> bool {
        match self {
            Cull::Nilsson2012(c) => c.depth(),
            Cull::Parts(parts, _) => parts.iter().any(|p| p.depth()),
            _ => false,
        }
    }
}

/// The cull of a method with an encoding, or an error naming the ones there are.
pub fn cull(id: &str) -> Result<Cull> {
    if let Some(c) = super::la2011_query::cull_of(id) {
        return Ok(Cull::La2011(c));
    }
    if let Some(c) = super::nilsson2012_query::cull_of(id) {
        return Ok(Cull::Nilsson2012(c));
    }
    match id {
        "lc" => return Ok(Cull::Parts(&LA2011_PART, "lb2011's patches")),
        "mam2012-new" => return Ok(Cull::Parts(&LA2011_PART, "the mam2012 and mam2012-hyperplane parts")),
        _ => {}
    }
    if let Some(c) = super::mam2012_query::cull_of(id) {
        return Ok(Cull::Mam2012(c));
    }
    if let Some(c) = super::wu2013_query::cull_of(id) {
        return Ok(Cull::Wu2013(c));
    }
    Ok(Cull::Bbox(rule(id)?))
}

/// The query family of a method on a template (a new encoding adds its arm to [`cull`]).
pub fn family(id: &str, template: Template) -> Result<Box<dyn Family>> {
    let c = cull(id)?;
    Ok(match template {
        Template::Static => Box::new(TemplateFamily(c)),
        Template::Moving => Box::new(super::moving_query::MovingFamily(c)),
    })
}

/// How the queries are made.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum Strategy {
    /// Many small queries with some inputs fixed to values drawn for the seed.
    Concolic,
    /// One query per side and range set with every input free.
    Whole,
}

/// The range sets to query: the given ranges on every side, or the family's defaults
/// (side by side for each set).
pub fn range_sets(f: &dyn Family, given: Option<Vec<[f32; 2]>>) -> Vec<(usize, Vec<[f32; 2]>)> {
    let sides = 0..f.sides().len();
    match given {
        Some(r) => sides.map(|s| (s, r.clone())).collect(),
        None => {
            let per: Vec<Vec<Vec<[f32; 2]>>> = sides.clone().map(|s| f.default_ranges(s)).collect();
            let n = per.iter().map(|p| p.len()).max().unwrap_or(0);
            let mut out = Vec::new();
            for i in 0..n {
                for s in sides.clone() {
                    if let Some(r) = per[s].get(i) {
                        out.push((s, r.clone()));
                    }
                }
            }
            out
        }
    }
}

/// The share of concolic queries with a triangle input free (the others fix the
/// whole triangle; see [`concolic`]). None by default: on the bbox template such a
/// query costs about twenty fixed ones and, measured over seeds, found nothing the
/// fixed ones did not find first.
pub const DEFAULT_FREE_SHARE: f64 = 0.0;

/// The queries of a strategy over range sets (`seed`, `n` and `free_share` for the
/// concolic plan).
pub fn queries(
    f: &dyn Family,
    strategy: Strategy,
    sets: &[(usize, Vec<[f32; 2]>)],
    seed: u64,
    n: usize,
    free_share: f64,
) -> Vec<Query> {
    match strategy {
        Strategy::Whole => sets.iter().map(|(s, r)| Query::free(*s, r.clone())).collect(),
        Strategy::Concolic => concolic::plan(f, sets, seed, n, free_share),
    }
}

/// The concolic plan's default resource limit per query (z3's `rlimit`; about a
/// half a second to a second of z3 CPU for the bbox queries).
pub const DEFAULT_RLIMIT: u64 = 1_500_000;

/// The limits of each query and of the run.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Limits {
    /// Wall-clock seconds per query (z3's `-T` and a guard).
    pub timeout: f64,
    /// z3's resource limit per query (None: the time limit only).
    pub rlimit: Option<u64>,
    /// Queries run at once (each a solver process, or one per solver of the portfolio).
    pub jobs: usize,
    /// The solvers each query runs on (the first `sat` or `unsat` wins). z3 alone keeps
    /// a concolic run deterministic (its resource limit); Bitwuzla has a time limit only.
    pub solvers: Solvers,
}

/// What became of one query.
#[derive(Clone, Debug, Serialize)]
pub struct QueryReport {
    /// Its place in the plan.
    pub index: usize,
    pub side: &'static str,
    /// The free inputs' ranges and the fixed inputs' values (`a=LO:HI,c=V,...`).
    pub query: String,
    pub answer: Answer,
    /// The solver whose answer this is.
    pub solver: Solver,
    /// On `unsat`: whether the query's hypotheses alone (its ranges and fixed values,
    /// and a tile the exact footprint reaches) were found satisfiable by the same solver. An `unsat` whose hypotheses are not
    /// shown satisfiable is reported as `unknown`, with this false.
    pub hypotheses_sat: Option<bool>,
    /// An `unsat` of a method encoded in part ([`Family::partial`]): reported as
    /// `unknown`, naming the parts left out.
    pub partial_unsat: Option<&'static str>,
    /// Wall-clock seconds of the query.
    pub seconds: f64,
    /// The answering solver's CPU seconds (see [`z3::Run::cpu_seconds`]).
    pub cpu_seconds: Option<f64>,
    /// The model's inputs, in the family's order (on `sat`).
    pub inputs: Option<Vec<f32>>,
    /// The exact judge's word on the model's case: "violation (tile culled)", or why not.
    pub judged: Option<String>,
    pub confirmed: bool,
    pub shrink_steps: Vec<String>,
    /// The case file written (None: not confirmed, already in the corpus, or not asked).
    pub file: Option<String>,
}

/// The whole run.
#[derive(Clone, Debug, Serialize)]
pub struct ProveReport {
    pub method: String,
    pub template: Template,
    pub strategy: Strategy,
    pub seed: u64,
    pub limits: Limits,
    /// Queries in the plan.
    pub planned: usize,
    /// The queries run, in plan order (up to the first confirmed one).
    pub queries: Vec<QueryReport>,
    /// The plan index of the first confirmed query.
    pub first_confirmed: Option<usize>,
    /// Wall-clock seconds of the whole run.
    pub seconds: f64,
    /// The answering solvers' CPU seconds over the queries reported.
    pub cpu_seconds: f64,
}

/// A query's result before the case file is written.
struct Done {
    rep: QueryReport,
    case: Option<CaseFile>,
}

/// Run one query and judge its model.
fn run_one(
    m: &'static dyn Method,
    f: &dyn Family,
    cfg: &CheckConfig,
    qi: usize,
    q: &Query,
    limits: &Limits,
    emit: Option<&Path>,
) -> Result<Done> {
    let (script, shown) = family::script(f, q);
    let side = f.sides()[q.side];
    if let Some(dir) = emit {
        let p = dir.join(format!("{}-{qi}-{side}.smt2", m.info().id.replace('/', "_")));
        std::fs::write(&p, &script).with_context(|| format!("writing {}", p.display()))?;
    }
    let run = solver::run(&script, limits.timeout, limits.rlimit, limits.solvers)?;
    let text = q.text(f);
    let (mut answer, mut hypotheses_sat, mut partial_unsat) = (run.answer, None, None);
    if let (Answer::Unsat, Some(left_out)) = (answer, f.partial()) {
        answer = Answer::Unknown;
        partial_unsat = Some(left_out);
    }
    if answer == Answer::Unsat {
        let h = solver::run_one(run.solver, &family::hypotheses_script(f, q), limits.timeout, None, None)?;
        hypotheses_sat = Some(h.answer == Answer::Sat);
        if h.answer != Answer::Sat {
            answer = Answer::Unknown;
        }
    }
    let mut rep = QueryReport {
        index: qi,
        side,
        query: text.clone(),
        answer,
        solver: run.solver,
        hypotheses_sat,
        partial_unsat,
        seconds: run.seconds,
        cpu_seconds: run.cpu_seconds,
        inputs: None,
        judged: None,
        confirmed: false,
        shrink_steps: Vec::new(),
        file: None,
    };
    let mut case_file = None;
    if run.answer == Answer::Sat {
        let mut v = Vec::new();
        let mut free = shown.iter();
        for x in &q.fixed {
            v.push(match x {
                Some(x) => *x,
                None => z3::value(&run.output, free.next().expect("one shown name per free input"))?,
            });
        }
        rep.inputs = Some(v.clone());
        let (tri, tile) = f.instance(q.side, &v);
        let case = Case { triangle: tri, lens: None };
        let mref = shared(m);
        if let Err(e) = case.validate().map_err(|e| e.to_string()).and(tile.validate().map_err(|e| e.to_string())) {
            rep.judged = Some(format!("not a valid case: {e}"));
        } else if !matches!(m.setup(&tri).tile(&tile), TileResult::Empty) && !f.depth() {
            // The f32 method does not cull the model's tile: the encoding and the
            // method disagree (never expected: they are the same code). A family that
            // also asks about depth bounds leaves a kept tile to the judge.
            rep.judged = Some("the method does not cull the model's tile (encoding mismatch)".into());
        } else {
            let (js, _) = judge(cfg, std::slice::from_ref(&mref), &case, &tile, qi as u64);
            let j = js.into_iter().next().expect("one method");
            match &j.violation {
                None => {
                    let why: Vec<&str> = j.unproven().iter().map(|r| r.name()).collect();
                    rep.judged = Some(if why.is_empty() {
                        "not confirmed: the judge certified the tile empty".into()
                    } else {
                        format!("not confirmed: unproven ({})", why.join(", "))
                    });
                }
                Some(_) => {
                    let (c, t, j, steps) = shrink(cfg, &mref, case, tile, j, qi as u64);
                    let w = j.violation.clone().expect("shrinking keeps a violation");
                    rep.confirmed = true;
                    rep.judged = Some(format!("violation ({})", w.bound));
                    rep.shrink_steps = steps.clone();
                    let inputs =
                        f.inputs().iter().zip(&v).map(|(n, x)| format!("{n} = {x:e}")).collect::<Vec<_>>().join(", ");
                    case_file = Some(CaseFile::violation(
                        m.info().id,
                        (c, t),
                        &w,
                        &CheckConfig { seed: 0, ..cfg.clone() },
                        ("symbolic", qi as u64, format!("symbolic {side} {text}")),
                        steps,
                        format!(
                            "{} model {inputs} of the {side} template (src/tools/symbolic/), confirmed by the exact judge",
                            run.solver.name()
                        ),
                    ));
                }
            }
        }
    }
    Ok(Done { rep, case: case_file })
}

/// Run the queries of `m` under `limits` and judge every model, stopping at the first
/// confirmed violation (in plan order); it is shrunk and written under `out` (never
/// overwriting). With `emit`, each query's script is also written there
/// (`<method>-<n>-<side>.smt2`, to rerun with `z3 FILE`).
#[allow(clippy::too_many_arguments)]
pub fn prove(
    m: &'static dyn Method,
    template: Template,
    strategy: Strategy,
    seed: u64,
    queries: &[Query],
    limits: Limits,
    out: Option<&Path>,
    emit: Option<&Path>,
    progress: bool,
) -> Result<ProveReport> {
    let f = family(m.info().id, template)?;
    let f: &dyn Family = f.as_ref();
    if let Some(dir) = emit {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    let pb =
        if progress { indicatif::ProgressBar::new(queries.len() as u64) } else { indicatif::ProgressBar::hidden() };
    pb.set_style(
        indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} queries {elapsed} {msg}")
            .expect("a valid template"),
    );
    let cfg = CheckConfig::default_with(vec![m]);
    let start = Instant::now();
    let next = AtomicUsize::new(0);
    let stop = AtomicUsize::new(usize::MAX);
    let results: Mutex<Vec<Option<Result<Done>>>> = Mutex::new((0..queries.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..limits.jobs.max(1) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::SeqCst);
                if i >= queries.len() || i > stop.load(Ordering::SeqCst) {
                    break;
                }
                let r = run_one(m, f, &cfg, i, &queries[i], &limits, emit);
                match &r {
                    Ok(d) if d.rep.confirmed => {
                        stop.fetch_min(i, Ordering::SeqCst);
                        pb.set_message(format!("confirmed at query {i}"));
                    }
                    Err(_) => {
                        stop.fetch_min(i, Ordering::SeqCst);
                    }
                    _ => {}
                }
                results.lock().expect("no worker panics")[i] = Some(r);
                pb.inc(1);
            });
        }
    });
    pb.finish_and_clear();
    let last = stop.load(Ordering::SeqCst);
    let mut reports = Vec::new();
    for (i, r) in results.into_inner().expect("no worker panics").into_iter().enumerate() {
        if i > last {
            break;
        }
        let Done { mut rep, case } = r.expect("every query up to the stop ran")?;
        if let (Some(cf), Some(dir)) = (case, out) {
            rep.file = cf.write_new(dir)?.map(|p| p.display().to_string());
        }
        reports.push(rep);
    }
    let first_confirmed = reports.iter().find(|r| r.confirmed).map(|r| r.index);
    let cpu_seconds = reports.iter().filter_map(|r| r.cpu_seconds).sum();
    Ok(ProveReport {
        method: m.info().id.into(),
        template,
        strategy,
        seed,
        limits,
        planned: queries.len(),
        queries: reports,
        first_confirmed,
        seconds: start.elapsed().as_secs_f64(),
        cpu_seconds,
    })
}

impl ProveReport {
    /// The table: per query (every query up to 40, else the `sat` ones), the side, the
    /// query, the answer, seconds and what became of it; then the totals.
    pub fn render(&self) -> String {
        let lim = match self.limits.rlimit {
            Some(r) => format!("rlimit {r} and {} s per query", self.limits.timeout),
            None => format!("{} s per query", self.limits.timeout),
        };
        let mut s = format!(
            "prove --symbolic {} (template {}, strategy {:?}, seed {}, {lim}, {} jobs, solvers {})\n",
            self.method,
            match self.template {
                Template::Static => "static",
                Template::Moving => "moving",
            },
            self.strategy,
            self.seed,
            self.limits.jobs,
            self.limits.solvers.name()
        )
        .replace("Concolic", "concolic")
        .replace("Whole", "whole");
        let all = self.queries.len() <= 40;
        for q in &self.queries {
            if !all && q.answer != Answer::Sat {
                continue;
            }
            let cpu = q.cpu_seconds.map_or("-".to_string(), |c| format!("{c:.2}"));
            s += &format!(
                "  {:>4} {:<6} {:<56} {:<7} {:<8} {:>7.2} s (cpu {:>6} s)",
                q.index,
                q.side,
                q.query,
                q.answer.name(),
                q.solver.name(),
                q.seconds,
                cpu
            );
            match q.answer {
                Answer::Sat => {
                    s += &format!("  {}", q.judged.as_deref().unwrap_or("-"));
                    if let Some(f) = &q.file {
                        s += &format!("; wrote {f}");
                    } else if q.confirmed {
                        s += "; not written (already in the corpus or --dry-run)";
                    }
                }
                Answer::Unsat if self.strategy == Strategy::Whole => {
                    s += "  no input of this template and ranges makes the method cull a reached tile"
                }
                Answer::Unsat => s += "  none with these fixed values",
                Answer::Unknown if q.partial_unsat.is_some() => {
                    s += &format!(
                        "  unsat not counted: only part of the method is encoded ({} left out)",
                        q.partial_unsat.unwrap_or("-")
                    )
                }
                Answer::Unknown if q.hypotheses_sat == Some(false) => {
                    s += "  unsat not counted: the ranges with a reached tile were not shown satisfiable"
                }
                Answer::Unknown | Answer::Timeout | Answer::Budget => s += "  undecided",
            }
            s.push('\n');
        }
        let count = |a: Answer| self.queries.iter().filter(|q| q.answer == a).count();
        s += &format!(
            "{} of {} planned queries run: {} sat, {} unsat, {} budget, {} timeout, {} unknown; {:.2} s wall, {:.2} s solver CPU\n",
            self.queries.len(),
            self.planned,
            count(Answer::Sat),
            count(Answer::Unsat),
            count(Answer::Budget),
            count(Answer::Timeout),
            count(Answer::Unknown)
            ,
            self.seconds,
            self.cpu_seconds
        );
        s += &match self.first_confirmed {
            Some(i) => format!("first confirmed violation: query {i}\n"),
            None if self.strategy == Strategy::Whole
                && self.queries.len() == self.planned
                && self.queries.iter().all(|q| q.answer == Answer::Unsat && q.hypotheses_sat == Some(true)) =>
            {
                "every query unsat with satisfiable ranges: no input in these ranges of the template makes the \
                 method cull a tile the exact footprint reaches\n"
                    .into()
            }
            None => "no confirmed violation within the plan (not a proof: a budget, a timeout or a fixed input is \
                     no statement for all inputs)\n"
                .into(),
        };
        s
    }
}
