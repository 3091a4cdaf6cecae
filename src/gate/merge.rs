//! Merging shard reports: `cullproof merge` turns the JSON reports of `check --shard
//! K/N` (for K = 0..N-1 of one run) into the report the unsharded run gives, number for
//! number.
//!
//! Everything a row holds is a count, a maximum or a mean. Counts and maxima combine in
//! any order. The means are the reason for [`RowSums`](super::row::RowSums): a row's
//! means are computed from sums kept in fixed point (integers, see
//! [`fixed`](super::row::fixed)), and integer sums do not depend on the order of
//! addition, so the shards' sums added together are the unsharded run's sums, bit for
//! bit. The worst witness of a row is the one with the largest margin, the later case
//! on a tie, as in the unsharded run. Statuses are then recomputed from the merged
//! counts against the expectations and (when the merged run has the settings of a
//! stored baseline) the baseline, exactly as `check` does.
//!
//! Before anything is added, every shard is checked (module `validate`): against itself and
//! its declared settings (a shard index below its count, every row's cases those the
//! settings give its regime and each proven, violated or unproven, totals the sums of
//! the rows, no row dropped) and against the others (one build and one set of
//! expectations and baseline, `tool`; one run: seed, cases, methods, regimes, tile,
//! budgets; every shard exactly once). Timed runs (`--time`: their case set depends on
//! the machine) and reports without a tool version are refused. Each error names the
//! file and the field.

use super::baseline::{self, BaselineFile};
use super::expect::Expectations;
use super::report::{finish_row, CheckReport, CrossCheck};
use super::row::Row;
use super::settings::RunInfo;
use super::tool::{self, ToolInfo};
use anyhow::{anyhow, bail, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

mod validate;

/// Read one shard report (the JSON of `check --json`); errors name the file and field.
pub fn load_report(path: &Path) -> Result<CheckReport> {
    let text = std::fs::read_to_string(path).map_err(|e| anyhow!("{}: cannot read: {e}", path.display()))?;
    let de = &mut serde_json::Deserializer::from_str(&text);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let field = e.path().to_string();
        anyhow!(
            "{}: field `{}`: {} (expected the JSON report of `cullproof check --json`)",
            path.display(),
            if field == "." { "(top level)".into() } else { field },
            e.inner()
        )
    })
}

/// Merge the shard reports of one run (each with the file it came from, for errors)
/// into the report of the whole run, with statuses against `ex` and, when it holds an
/// entry for the run's settings, the baseline `base`.
pub fn merge(
    shards: Vec<(PathBuf, CheckReport)>,
    ex: &Expectations,
    base: Option<&BaselineFile>,
) -> Result<CheckReport> {
    validate::shards(&shards)?;
    let Some((_, first)) = shards.first() else { bail!("merge: no shard reports given") };
    let run = first.run.clone();
    let regimes = &run.settings.regimes;
    let pos = |list: &[String], x: &str, what: &str, p: &Path| -> Result<usize> {
        list.iter()
            .position(|y| y == x)
            .ok_or_else(|| anyhow!("{}: a row names {what} {x:?}, not in `run`", p.display()))
    };
    let mut rows: BTreeMap<(usize, usize), Row> = BTreeMap::new();
    let mut cross: BTreeMap<usize, CrossCheck> = BTreeMap::new();
    let (mut cases, mut boxes, mut seconds) = (0u64, 0u64, 0f64);
    // Counts of validated shards add up to at most the run's; the solver's boxes and the
    // cross-check's samples are only bounded per shard, so their sums are checked.
    let add = |acc: &mut u64, v: u64, p: &Path, field: &str| -> Result<()> {
        *acc = acc.checked_add(v).ok_or_else(|| {
            anyhow!("{}: field `{field}` = {v}: added to the other shards' it exceeds 2^64", p.display())
        })?;
        Ok(())
    };
    for (p, r) in &shards {
        cases += r.cases;
        add(&mut boxes, r.solver_boxes, p, "solver_boxes")?;
        seconds = seconds.max(r.seconds);
        for (i, c) in r.cross_check.iter().enumerate() {
            let ri = pos(regimes, &c.regime, "the regime", p)?;
            let x = cross.entry(ri).or_insert_with(|| CrossCheck { regime: c.regime.clone(), ..Default::default() });
            let f = |name: &str| format!("cross_check[{i}].{name}");
            add(&mut x.samples, c.samples, p, &f("samples"))?;
            add(&mut x.interior, c.interior, p, &f("interior"))?;
            add(&mut x.embree_over, c.embree_over, p, &f("embree_over"))?;
            add(&mut x.embree_under, c.embree_under, p, &f("embree_under"))?;
        }
        for row in &r.rows {
            let key = (pos(&run.methods, &row.method, "the method", p)?, pos(regimes, &row.regime, "the regime", p)?);
            match rows.get_mut(&key) {
                None => {
                    rows.insert(key, row.clone());
                }
                Some(acc) => add_row(acc, row),
            }
        }
    }
    for row in rows.values_mut() {
        row.entry = Some(ex.entry(&row.method, &row.regime).scoped(run.settings.measured()));
        row.expected = row.entry.as_ref().map_or(row.expected, |e| e.expect);
        finish_row(row);
    }
    let samples = first.samples.clone().map(|mut n| {
        n.outside_viewport = shards.iter().filter_map(|(_, r)| r.samples.as_ref()).map(|x| x.outside_viewport).sum();
        n
    });
    let mut rows: Vec<Row> = rows.into_values().collect();
    super::report::pooled_tightness(&mut rows);
    super::report::pooled_tail(&mut rows);
    let mut rep = CheckReport {
        methods: super::strength::of_rows(&rows),
        samples,
        seed: first.seed,
        cases,
        shard: "0/1".into(),
        run: RunInfo { shard: [0, 1], ..run.clone() },
        rows,
        cross_check: cross.into_values().collect(),
        solver_boxes: boxes,
        seconds,
        baseline: None,
        contract_breaches: merge_breaches(shards.iter().map(|(_, r)| r)),
        // the shards' build (their counts); the expectations and baseline of this merge
        // (its statuses)
        tool: Some(ToolInfo {
            version: first.tool.clone().unwrap_or_default().version,
            ..ToolInfo::of(ex, base.map(tool::hash))
        }),
    };
    if let Some(b) = base {
        baseline::apply_settings(&mut rep, Some(&run.settings), b);
    }
    Ok(rep)
}

/// The shards' contract breaches summed per plugged method, in the order first seen.
fn merge_breaches<'a>(shards: impl Iterator<Item = &'a CheckReport>) -> Vec<crate::external::plugin::ContractBreaches> {
    let mut out: Vec<crate::external::plugin::ContractBreaches> = Vec::new();
    for b in shards.flat_map(|r| &r.contract_breaches) {
        match out.iter_mut().find(|o| o.method == b.method) {
            None => out.push(b.clone()),
            Some(o) => {
                o.answers += b.answers;
                for (k, n) in &b.kinds {
                    *o.kinds.entry(k.clone()).or_insert(0) += n;
                }
            }
        }
    }
    out
}

/// Fold row `o` (the same method and regime, other cases) into `acc`.
fn add_row(acc: &mut Row, o: &Row) {
    acc.cases += o.cases;
    acc.proven += o.proven;
    acc.violations += o.violations;
    acc.tail += o.tail;
    acc.unproven += o.unproven;
    acc.not_judged += o.not_judged;
    for (k, v) in &o.unproven_by {
        *acc.unproven_by.entry(k.clone()).or_insert(0) += v;
    }
    for (k, b) in &o.bounds {
        let e = acc.bounds.entry(k.clone()).or_default();
        e.cases += b.cases;
        e.max_margin = e.max_margin.max(b.max_margin);
    }
    acc.boundary_only += o.boundary_only;
    acc.f32_witnessed += o.f32_witnessed;
    acc.limit_tiles += o.limit_tiles;
    acc.limit_violations += o.limit_violations;
    acc.limit_found += o.limit_found;
    for (k, t) in &o.tight {
        let e = acc.tight.entry(k.clone()).or_default();
        e.probed += t.probed;
        e.tight += t.tight;
    }
    acc.sums = acc.sums + o.sums;
    if let Some(w) = &o.worst {
        let later = acc.worst.as_ref().is_none_or(|a| (w.margin, w.case_index) > (a.margin, a.case_index));
        if later {
            acc.margin_needed = w.margin;
            acc.worst = Some(w.clone());
        }
    }
}
