//! The stored baseline: what the gate saw on a given setting, row by row, so that a
//! later run on the same setting fails when a row gets worse.
//!
//! A run is deterministic for its settings (seed, cases, regimes, tile size, budgets),
//! so a change between two runs of the same setting is a change in a method or in the
//! judge. The gate fails a row that shows, against the baseline:
//! - a **new kind** of violated bound;
//! - a **larger margin** of a bound kind, by more than a factor [`MARGIN_FACTOR`]
//!   (rounding-size margins move by a few ulps when the solver changes how it
//!   refines);
//! - **more violations**, by more than `3 sqrt(n) + 3` for n before (the counting noise
//!   of a solver change);
//! - a **looser answer**: the mean share of the lens/shutter domain the intervals let
//!   through, or the mean share of the tile's uniform samples the answer admits
//!   (constraints included), grows by more than 1e-9 of itself (the answers do not
//!   depend on the judge, so any growth is the method's);
//! - a **looser tile reject**: the method culls a tile near the footprint in fewer
//!   cases, or its reject limit lies farther beyond the footprint's extreme on average;
//! - **proven cases** up or down beyond that noise: a weaker judge, or one that proves
//!   more, must be looked at before the baseline is rewritten.
//!
//! `cullproof check --write-baseline` rewrites the entry for the run's settings: right
//! after a deliberate change (a method fixed, the judge made stronger) once the new
//! table has been read and the changes are understood; never to silence a failure.

use super::report::CheckReport;
use super::row::{BoundStat, Row, Status};
use super::settings::Settings;
use super::CheckConfig;
use crate::io::quote::{clip, quote};
use anyhow::{anyhow, Context, Result};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// A margin may grow by this factor before it counts as a regression.
pub const MARGIN_FACTOR: f64 = 2.0;

/// The format tag of a baseline file.
pub const FORMAT: &str = "cullproof-baseline/1";

/// One row as stored.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BaseRow {
    pub method: String,
    pub regime: String,
    pub cases: u64,
    pub proven: u64,
    pub violations: u64,
    pub unproven: u64,
    pub bounds: BTreeMap<String, BoundStat>,
    pub pass_fraction: f64,
    pub admit_fraction: f64,
    pub limit_found: u64,
    pub limit_slack: f64,
}

/// The rows of one setting.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Baseline {
    pub settings: Settings,
    pub rows: Vec<BaseRow>,
}

/// A baseline file: one entry per setting.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BaselineFile {
    pub format: String,
    pub baselines: Vec<Baseline>,
}

impl BaselineFile {
    pub fn load(path: &Path) -> Result<BaselineFile> {
        let text = std::fs::read_to_string(path).map_err(|e| anyhow!("{}: cannot read: {e}", path.display()))?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parse the text of a baseline file; `name` (the file, or what the text is) starts
    /// every error, which then names the field.
    pub fn parse(text: &str, name: &str) -> Result<BaselineFile> {
        let de = &mut serde_json::Deserializer::from_str(text);
        let f: BaselineFile = serde_path_to_error::deserialize(de).map_err(|e| {
            let (field, why) = (e.path().to_string(), e.inner().to_string());
            anyhow!("{name}: field `{}`: {}", clip(&field), clip(&why))
        })?;
        if f.format != FORMAT {
            anyhow::bail!("{name}: field `format` = {}: expected {FORMAT:?}", quote(&f.format));
        }
        Ok(f)
    }

    /// The entry for these settings.
    pub fn find(&self, s: &Settings) -> Option<&Baseline> {
        self.baselines.iter().find(|b| &b.settings == s)
    }

    /// Replace (or add) the entry for the report's settings, keeping the others.
    pub fn record(&mut self, cfg: &CheckConfig, r: &CheckReport) -> Result<()> {
        let settings = Settings::of(cfg).context("a baseline needs a fixed case count, not --time or --shard")?;
        let rows = r
            .rows
            .iter()
            .map(|x| BaseRow {
                method: x.method.clone(),
                regime: x.regime.clone(),
                cases: x.cases,
                proven: x.proven,
                violations: x.violations,
                unproven: x.unproven,
                bounds: x.bounds.clone(),
                pass_fraction: x.pass_fraction,
                admit_fraction: x.admit_fraction,
                limit_found: x.limit_found,
                limit_slack: x.limit_slack,
            })
            .collect();
        self.format = FORMAT.into();
        self.baselines.retain(|b| b.settings != settings);
        self.baselines.push(Baseline { settings, rows });
        Ok(())
    }

    /// Write to `path` through a temporary file, so a failed write never leaves half a
    /// baseline behind.
    pub fn save(&self, path: &Path) -> Result<()> {
        let text = serde_json::to_string_pretty(self)? + "\n";
        let tmp = path.with_extension("json.tmp");
        std::fs::write(&tmp, text).with_context(|| format!("writing {}", tmp.display()))?;
        std::fs::rename(&tmp, path).with_context(|| format!("renaming {} to {}", tmp.display(), path.display()))
    }
}

/// What changed in one row against its baseline row (empty: nothing worse).
pub fn compare(row: &Row, base: &BaseRow) -> Vec<String> {
    let mut out = Vec::new();
    for (k, b) in &row.bounds {
        match base.bounds.get(k) {
            None => {
                out.push(format!("new kind of violated bound `{k}` ({} cases, margin {:.3e})", b.cases, b.max_margin))
            }
            Some(o) if b.max_margin > o.max_margin * MARGIN_FACTOR => out.push(format!(
                "`{k}` margin {:.3e} -> {:.3e} (more than {MARGIN_FACTOR}x)",
                o.max_margin, b.max_margin
            )),
            Some(_) => {}
        }
    }
    let n0 = base.violations as f64;
    if row.cases == base.cases && row.violations as f64 > n0 + 3.0 * n0.sqrt() + 3.0 {
        out.push(format!("violations {} -> {} of {} cases", base.violations, row.violations, row.cases));
    }
    if row.cases != base.cases {
        return out;
    }
    let grew = |now: f64, was: f64| now > was + 1e-9 * was.abs() + 1e-300;
    if grew(row.pass_fraction, base.pass_fraction) {
        out.push(format!(
            "looser: the intervals let {:.6} of the domain through on average (was {:.6})",
            row.pass_fraction, base.pass_fraction
        ));
    }
    if grew(row.admit_fraction, base.admit_fraction) {
        out.push(format!(
            "looser: the answer admits {:.6} of the tile's uniform samples on average (was {:.6})",
            row.admit_fraction, base.admit_fraction
        ));
    }
    let beyond_noise = |now: u64, was: u64| (now as f64 - was as f64).abs() > 3.0 * (was as f64).sqrt() + 3.0;
    if row.limit_found < base.limit_found && beyond_noise(row.limit_found, base.limit_found) {
        out.push(format!(
            "looser tile reject: it culls a tile near the footprint in {} cases (was {})",
            row.limit_found, base.limit_found
        ));
    } else if row.limit_found == base.limit_found && grew(row.limit_slack, base.limit_slack) {
        out.push(format!(
            "looser tile reject: its limit lies {:.3e} tile sizes beyond the footprint on average (was {:.3e})",
            row.limit_slack, base.limit_slack
        ));
    }
    if beyond_noise(row.proven, base.proven) {
        out.push(format!(
            "proven {} -> {} of {} cases (the method or the judge changed: a judge that proves more must \
             be shown sound before the baseline is rewritten)",
            base.proven, row.proven, row.cases
        ));
    }
    out
}

/// Compare every row with the baseline for the run's settings, if there is one; rows
/// that got worse become [`Status::Regression`].
pub fn apply(r: &mut CheckReport, cfg: &CheckConfig, file: &BaselineFile) {
    apply_settings(r, Settings::of(cfg).as_ref(), file)
}

/// [`apply`] for a run with these settings (None: a timed or sharded run, compared
/// with nothing).
pub fn apply_settings(r: &mut CheckReport, settings: Option<&Settings>, file: &BaselineFile) {
    let Some(settings) = settings else {
        r.baseline = None;
        return;
    };
    let Some(b) = file.find(settings) else {
        r.baseline = None;
        return;
    };
    let mut compared = 0;
    let mut worse = 0;
    for row in &mut r.rows {
        // A deliberately broken variant is compared with the method it breaks.
        let id = crate::bounds::broken::inner_id(&row.method);
        let Some(br) = b.rows.iter().find(|x| x.method == id && x.regime == row.regime) else { continue };
        compared += 1;
        let diffs = compare(row, br);
        if !diffs.is_empty() {
            worse += 1;
            if !row.status.fails() {
                row.status = Status::Regression;
            }
            row.problems.extend(diffs);
        }
    }
    r.baseline = Some(format!(
        "seed {} x {} cases: {compared} rows compared, {worse} worse than stored",
        settings.seed, settings.cases
    ));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(violations: u64, bounds: &[(&str, f64)], pass: f64) -> Row {
        Row {
            method: "m".into(),
            regime: "static".into(),
            cases: 600,
            proven: 600 - violations,
            violations,
            unproven: 0,
            not_judged: 0,
            unproven_by: BTreeMap::new(),
            bounds: bounds.iter().map(|(k, m)| (k.to_string(), BoundStat { cases: 1, max_margin: *m })).collect(),
            tail: 0,
            boundary_only: 0,
            f32_witnessed: 0,
            limit_tiles: 0,
            limit_violations: 0,
            limit_found: 0,
            limit_slack: 0.0,
            tight: BTreeMap::new(),
            admit_fraction: pass,
            pass_fraction: pass,
            margin_needed: 0.0,
            expected: crate::gate::Expected::Violation,
            status: Status::KnownViolation,
            problems: Vec::new(),
            worst: None,
            examples: Vec::new(),
            sums: Default::default(),
            entry: None,
        }
    }

    fn base(r: &Row) -> BaseRow {
        BaseRow {
            method: r.method.clone(),
            regime: r.regime.clone(),
            cases: r.cases,
            proven: r.proven,
            violations: r.violations,
            unproven: r.unproven,
            bounds: r.bounds.clone(),
            pass_fraction: r.pass_fraction,
            admit_fraction: r.admit_fraction,
            limit_found: r.limit_found,
            limit_slack: r.limit_slack,
        }
    }

    #[test]
    fn a_row_is_compared_kind_by_kind_and_by_rate_and_looseness() {
        let b = base(&row(20, &[("u min", 1e-5)], 0.5));
        assert!(compare(&row(20, &[("u min", 1e-5)], 0.5), &b).is_empty());
        // within noise: 1.5x the margin, a few more violations, a tighter answer
        assert!(compare(&row(30, &[("u min", 1.5e-5)], 0.4), &b).is_empty());
        let d = compare(&row(20, &[("u min", 1e-5), ("t max", 1e-9)], 0.5), &b);
        assert!(d.len() == 1 && d[0].contains("new kind") && d[0].contains("t max"), "{d:?}");
        let d = compare(&row(20, &[("u min", 3e-5)], 0.5), &b);
        assert!(d.len() == 1 && d[0].contains("margin"), "{d:?}");
        let d = compare(&row(40, &[("u min", 1e-5)], 0.5), &b);
        assert!(d.len() == 1 && d[0].contains("violations 20 -> 40"), "{d:?}");
        let d = compare(&row(20, &[("u min", 1e-5)], 0.5000001), &b);
        assert!(!d.is_empty() && d.iter().all(|x| x.contains("looser")), "{d:?}");
        let mut fewer = row(20, &[("u min", 1e-5)], 0.5);
        let mut b2 = b.clone();
        b2.limit_found = 40;
        fewer.limit_found = 10;
        let d = compare(&fewer, &b2);
        assert!(d.len() == 1 && d[0].contains("looser tile reject"), "{d:?}");
        fewer.limit_found = 40;
        fewer.limit_slack = 1e-3;
        let d = compare(&fewer, &b2);
        assert!(d.len() == 1 && d[0].contains("beyond the footprint"), "{d:?}");
        let mut more = row(20, &[("u min", 1e-5)], 0.5);
        more.proven = 300;
        let d = compare(&more, &b);
        assert!(d.len() == 1 && d[0].contains("proven 580 -> 300"), "{d:?}");
    }

    #[test]
    fn saving_replaces_only_the_entry_of_the_same_settings() {
        let dir = std::env::temp_dir().join(format!("cullproof-base-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("baseline.json");
        let mut cfg = CheckConfig::default_with(vec![]);
        cfg.cases = 10;
        let rep = |n: u64| CheckReport {
            seed: 1,
            cases: 10,
            shard: "0/1".into(),
            run: crate::gate::settings::RunInfo::of(&cfg),
            rows: vec![row(n, &[], 0.5)],
            methods: vec![],
            cross_check: vec![],
            solver_boxes: 0,
            seconds: 0.0,
            baseline: None,
            samples: None,
            contract_breaches: vec![],
            tool: None,
        };
        let mut f = BaselineFile::default();
        f.record(&cfg, &rep(1)).unwrap();
        let other = CheckConfig { seed: 2, ..cfg.clone() };
        f.record(&other, &rep(2)).unwrap();
        f.record(&cfg, &rep(3)).unwrap();
        f.save(&p).unwrap();
        let g = BaselineFile::load(&p).unwrap();
        assert_eq!(g.baselines.len(), 2);
        assert_eq!(g.find(&Settings::of(&cfg).unwrap()).unwrap().rows[0].violations, 3);
        assert_eq!(g.find(&Settings::of(&other).unwrap()).unwrap().rows[0].violations, 2);
        let timed = CheckConfig { time: Some(1.0), ..cfg.clone() };
        assert!(f.record(&timed, &rep(1)).is_err());
        std::fs::write(&p, r#"{"format": "nope", "baselines": []}"#).unwrap();
        assert!(BaselineFile::load(&p).unwrap_err().to_string().contains("format"));
        std::fs::remove_dir_all(&dir).ok();
    }
}
