//! Replaying case files: the stored witness re-decided and the case judged afresh, by
//! the method the file names or another one.

use super::*;
use crate::bounds::MethodRef;
use crate::gate::{judge, CheckConfig, Declared};
use crate::judge::Judgement;
use anyhow::Result;
use serde::Serialize;
use std::path::Path;

/// The outcome of replaying one file.
#[derive(Clone, Debug, Serialize)]
pub struct Replay {
    pub path: String,
    pub method: String,
    pub expected: Verdict,
    /// The stored witness, re-decided: Ok((bound, margin)) or why it no longer holds.
    pub witness: Option<std::result::Result<(String, f64), String>>,
    /// A fresh judgement: "violation", "proven", "unproven (reasons)".
    pub judged: String,
    pub margin: Option<f64>,
    pub ok: bool,
    /// The sample set, snap and viewport judged under, when not the defaults.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub samples: Option<String>,
}

fn judged_word(j: &Judgement) -> String {
    match j.verdict() {
        crate::judge::Verdict::Violated => "violation".into(),
        crate::judge::Verdict::Proven => "proven".into(),
        crate::judge::Verdict::NotJudged => "not judged (the case cannot be snapped)".into(),
        crate::judge::Verdict::Unproven => {
            let r: Vec<&str> = j.unproven().iter().map(|r| r.name()).collect();
            format!("unproven ({})", r.join(", "))
        }
    }
}

/// A stored witness re-decided: Ok((bound, margin)) when the method still culls it, or
/// why not; None when the file holds no witness.
pub type WitnessCheck = Option<std::result::Result<(String, f64), String>>;

/// The stored witness re-decided under `m` and a fresh judgement of `m` on the file's
/// case, under the file's settings (or those in `over`) with the whole side budget;
/// with the settings used.
fn judge_file(
    cf: &CaseFile,
    m: &MethodRef,
    cfg: &CheckConfig,
    over: &Declared,
) -> (WitnessCheck, Judgement, CheckConfig) {
    let mut cfg = cf.settings(cfg);
    cfg.judge.side_stall = 0;
    over.apply(&mut cfg);
    let witness = cf
        .witness
        .as_ref()
        .map(|w| witness_holds_in(m.as_ref(), &cf.case, &cf.tile, w.sample, cfg.sample_set, cfg.snap));
    let (mut js, _) = judge(&cfg, std::slice::from_ref(m), &cf.case, &cf.tile, cf.provenance.case_index);
    (witness, js.swap_remove(0), cfg)
}

/// Re-judge one case file, with the whole side budget (one case: no stall cut-off).
/// The file's sample set, snap and viewport are used.
pub fn replay(path: &Path, cfg: &CheckConfig) -> Result<Replay> {
    replay_with(path, cfg, &Declared::default())
}

/// [`replay()`], with the sample set, snap or viewport given in `over` in place of the
/// file's (to ask whether a case found under one set holds under another).
pub fn replay_with(path: &Path, cfg: &CheckConfig, over: &Declared) -> Result<Replay> {
    let cf = CaseFile::load(path)?;
    let m = crate::bounds::shared(method_of(&cf.method).expect("checked at load"));
    let (witness, j, cfg) = judge_file(&cf, &m, cfg, over);
    let j = &j;
    let judged = judged_word(j);
    let ok = match cf.expected {
        // The stored witness must still hold, and the fresh judgement must not
        // contradict it: a proof of conservativeness next to a witness that holds
        // would mean the judge is wrong. (Unproven is no contradiction: the fresh
        // search may run out of budget before it finds the stored sample again.)
        Verdict::Violation => matches!(witness, Some(Ok(_))) && j.verdict() != crate::judge::Verdict::Proven,
        // A conservative case must be proven afresh, and its stored witness (if any)
        // must not hold.
        Verdict::Conservative => j.verdict() == crate::judge::Verdict::Proven && !matches!(witness, Some(Ok(_))),
    };
    Ok(Replay {
        path: path.display().to_string(),
        method: cf.method,
        expected: cf.expected,
        witness,
        judged,
        margin: j.violation.as_ref().map(|w| w.margin),
        ok,
        samples: crate::gate::settings::SetNote::of(&cfg, 0).map(|n| n.key()),
    })
}

/// The outcome of re-judging one file's case against another method
/// (`replay --method ID`).
#[derive(Clone, Debug, Serialize)]
pub struct Rejudge {
    pub path: String,
    /// The method the file was written for.
    pub found_for: String,
    /// The method judged now.
    pub method: String,
    /// The stored witness (if any) under the new method: Ok((bound, margin)) when it
    /// still culls it, or why not.
    pub witness: Option<std::result::Result<(String, f64), String>>,
    /// The fresh judgement: "violation", "proven", "unproven (reasons)".
    pub judged: String,
    /// "fixed" (proven afresh, the stored witness no longer culled), "still violated"
    /// (a violation found afresh, or the stored witness still culled), "unproven" or
    /// "not judged" (the case cannot be snapped under the file's settings).
    pub outcome: &'static str,
}

/// Re-judge the case of one file against `method` in place of the file's own (under
/// the file's sample set, snap and viewport, or those in `over`), with the whole side
/// budget: does a fixed bound still cull the stored witness, and is it proven on the
/// case?
pub fn rejudge(path: &Path, cfg: &CheckConfig, over: &Declared, method: &str) -> Result<Rejudge> {
    let m = method_of(method)
        .ok_or_else(|| anyhow::anyhow!("--method {method}: no such method (see `cullproof methods`)"))?;
    rejudge_with(path, cfg, over, &crate::bounds::shared(m))
}

/// [`rejudge`] against a method held by its handle (a bound of the caller's own, not
/// in the registry).
pub fn rejudge_with(path: &Path, cfg: &CheckConfig, over: &Declared, m: &MethodRef) -> Result<Rejudge> {
    let cf = CaseFile::load_for(path, Some(m))?;
    let method = m.info().id;
    let (witness, j, _) = judge_file(&cf, m, cfg, over);
    let j = &j;
    let outcome = match (j.verdict(), &witness) {
        (crate::judge::Verdict::Violated, _) | (_, Some(Ok(_))) => "still violated",
        (crate::judge::Verdict::Proven, _) => "fixed",
        (crate::judge::Verdict::Unproven, _) => "unproven",
        (crate::judge::Verdict::NotJudged, _) => "not judged",
    };
    Ok(Rejudge {
        path: path.display().to_string(),
        found_for: cf.method,
        method: method.to_string(),
        witness,
        judged: judged_word(j),
        outcome,
    })
}
