//! `cullproof prove --symbolic`: run a method's queries through z3, one time limit
//! each, and turn every model into a case that the exact judge decides. z3 is never
//! the judge: a model the judge does not confirm is reported as unconfirmed, and an
//! `unsat` says only that no input of the query's template and ranges makes the
//! method cull a tile the exact footprint reaches.

use super::arith::F32Arith;
use super::bbox_query::{self, Query};
use super::planted::{BandSlip, EqSlip};
use super::z3::{self, Answer};
use crate::bounds::bbox::{Corner, PlainCorner, SafeCorner};
use crate::bounds::{shared, Method, TileResult};
use crate::check::{judge, CheckConfig};
use crate::corpus::{shrink, CaseFile};
use crate::model::Case;
use anyhow::{bail, Context, Result};
use serde::Serialize;
use std::path::Path;

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
/// [`super::arith::F32Arith`]).
pub const ENCODED: [&str; 4] = ["bbox", "bbox-safe", "broken/planted-eq/bbox-safe", "broken/planted-band/bbox-safe"];

/// The encoding of a method, or an error naming the ones there are.
pub fn rule(id: &str) -> Result<Rule> {
    Ok(match id {
        "bbox" => Rule::Plain,
        "bbox-safe" => Rule::Safe,
        "broken/planted-eq/bbox-safe" => Rule::Eq,
        "broken/planted-band/bbox-safe" => Rule::Band,
        _ => {
            bail!("--method {id}: no symbolic encoding (methods with one: {}, la2011, la2011-safe)", ENCODED.join(", "))
        }
    })
}

/// What became of one query.
#[derive(Clone, Debug, Serialize)]
pub struct QueryReport {
    pub side: &'static str,
    pub ranges: String,
    pub answer: Answer,
    /// Wall-clock seconds of the query.
    pub seconds: f64,
    /// z3's CPU seconds (see [`z3::Run::cpu_seconds`]).
    pub cpu_seconds: Option<f64>,
    /// The model's inputs `a, c, w, t` (on `sat`).
    pub inputs: Option<[f32; 4]>,
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
    pub timeout: f64,
    pub queries: Vec<QueryReport>,
}

/// Run the queries of `m` (each with `timeout` seconds) and judge every model; a
/// confirmed violation is shrunk and written under `out` (never overwriting). With
/// `emit`, each query's script is also written there (`<method>-<n>-<side>.smt2`, to
/// rerun with `z3 FILE`).
pub fn prove(
    m: &'static dyn Method,
    queries: &[Query],
    timeout: f64,
    out: Option<&Path>,
    emit: Option<&Path>,
    progress: bool,
) -> Result<ProveReport> {
    let la = super::la2011_query::safe_of(m.info().id);
    let rule = if la.is_some() { Rule::Plain } else { rule(m.info().id)? };
    let pb =
        if progress { indicatif::ProgressBar::new(queries.len() as u64) } else { indicatif::ProgressBar::hidden() };
    let cfg = CheckConfig::default_with(vec![m]);
    let mref = shared(m);
    let mut reports = Vec::new();
    for (qi, q) in queries.iter().enumerate() {
        pb.set_message(format!("{} {}", q.side.name(), q.ranges_text()));
        let script = la.map_or_else(|| bbox_query::script(&rule, q), |safe| super::la2011_query::script(safe, q));
        if let Some(dir) = emit {
            std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
            let p = dir.join(format!("{}-{qi}-{}.smt2", m.info().id.replace('/', "_"), q.side.name()));
            std::fs::write(&p, &script).with_context(|| format!("writing {}", p.display()))?;
        }
        let run = z3::run(&script, timeout)?;
        let mut rep = QueryReport {
            side: q.side.name(),
            ranges: q.ranges_text(),
            answer: run.answer,
            seconds: run.seconds,
            cpu_seconds: run.cpu_seconds,
            inputs: None,
            judged: None,
            confirmed: false,
            shrink_steps: Vec::new(),
            file: None,
        };
        if run.answer == Answer::Sat {
            let mut v = [0.0f32; 4];
            for (k, n) in bbox_query::INPUTS.iter().enumerate() {
                v[k] = z3::value(&run.output, n)?;
            }
            rep.inputs = Some(v);
            let (tri, tile) = bbox_query::instance(q.side, v);
            let case = Case { triangle: tri, lens: None };
            if let Err(e) = case.validate().map_err(|e| e.to_string()).and(tile.validate().map_err(|e| e.to_string())) {
                rep.judged = Some(format!("not a valid case: {e}"));
            } else if !matches!(m.setup(&tri).tile(&tile), TileResult::Empty) {
                // The f32 method does not cull the model's tile: the encoding and the
                // method disagree (never expected: they are the same code).
                rep.judged = Some("the method does not cull the model's tile (encoding mismatch)".into());
            } else {
                let (js, _) = judge(&cfg, std::slice::from_ref(&mref), &case, &tile, qi as u64);
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
                        let (c, t, j, steps) = shrink(&cfg, &mref, case, tile, j, qi as u64);
                        let w = j.violation.clone().expect("shrinking keeps a violation");
                        rep.confirmed = true;
                        rep.judged = Some(format!("violation ({})", w.bound));
                        rep.shrink_steps = steps.clone();
                        let cf = CaseFile::violation(
                            m.info().id,
                            (c, t),
                            &w,
                            &CheckConfig { seed: 0, ..cfg.clone() },
                            ("symbolic", qi as u64, format!("symbolic {} {}", q.side.name(), q.ranges_text())),
                            steps,
                            format!(
                                "z3 model a = {:e}, c = {:e}, w = {:e}, t = {:e} of the {} template (src/symbolic/bbox_query.rs), confirmed by the exact judge",
                                v[0],
                                v[1],
                                v[2],
                                v[3],
                                q.side.name()
                            ),
                        );
                        if let Some(dir) = out {
                            rep.file = cf.write_new(dir)?.map(|p| p.display().to_string());
                        }
                    }
                }
            }
        }
        reports.push(rep);
        pb.inc(1);
    }
    pb.finish_and_clear();
    Ok(ProveReport { method: m.info().id.into(), timeout, queries: reports })
}

impl ProveReport {
    /// The table: per query, the side, ranges, answer, seconds and what became of it.
    pub fn render(&self) -> String {
        let mut s = format!("prove --symbolic {} (time limit {} s per query)\n", self.method, self.timeout);
        for q in &self.queries {
            let cpu = q.cpu_seconds.map_or("-".to_string(), |c| format!("{c:.2}"));
            s += &format!(
                "  {:<6} {:<48} {:<8} {:>7.2} s (cpu {:>6} s)",
                q.side,
                q.ranges,
                q.answer.name(),
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
                Answer::Unsat => s += "  no input of this template and ranges makes the method cull a reached tile",
                Answer::Unknown | Answer::Timeout => s += "  undecided",
            }
            s.push('\n');
        }
        s
    }
}
