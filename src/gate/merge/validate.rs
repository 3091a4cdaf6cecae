//! What `cullproof merge` holds every shard report to before it adds anything up: each
//! report against itself and its declared settings ([`shard`]), then the reports
//! against each other ([`together`]). An error names the file and the field.
//!
//! A shard's case count is not taken on trust: shard K of N of a run of C cases judges
//! the indices below C equal to K modulo N, case i of regime i modulo (the run's regime
//! count), so the cases of each regime follow from the settings. Each row must hold
//! those cases (fewer only where a viewport left cases unplaced, as the report counts),
//! each case must be proven, violated or unproven, and every count a row holds must fit
//! within its cases, so the sums that follow cannot overflow.

use crate::cases::generate::Regime;
use crate::gate::report::CheckReport;
use crate::gate::row::{fixed, Row};
use crate::gate::{strength, tool, MAX_CASES};
use anyhow::{bail, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// `{file}: field `{field}` {message}`.
macro_rules! refuse {
    ($p:expr, $field:expr, $($msg:tt)+) => {
        bail!("{}: field `{}` {}", $p.display(), $field, format!($($msg)+))
    };
}

/// Check every report, then the set: one run, each of its shards exactly once.
pub(super) fn shards(shards: &[(PathBuf, CheckReport)]) -> Result<()> {
    for (p, r) in shards {
        shard(p, r)?;
    }
    together(shards)
}

/// The shard `K/N` of a report's `shard` field, as `check --shard` takes it.
fn parse_shard(s: &str) -> Option<(u64, u64)> {
    let (a, b) = s.split_once('/')?;
    Some((a.trim().parse().ok()?, b.trim().parse().ok()?))
}

/// How many indices below `cases` are `k` modulo `n` and `r` modulo `m`.
fn count(cases: u64, k: u64, n: u64, r: u64, m: u64) -> u64 {
    let (n, m, k, r) = (n as u128, m as u128, k as u128, r as u128);
    let step = n / gcd(n, m) * m;
    // the first such index: k + j n for some j below m
    let Some(first) = (0..m).map(|j| k + j * n).find(|i| i % m == r) else { return 0 };
    if first >= cases as u128 {
        0
    } else {
        ((cases as u128 - 1 - first) / step + 1) as u64
    }
}

fn gcd(a: u128, b: u128) -> u128 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// One report against itself and the settings it declares.
fn shard(p: &Path, r: &CheckReport) -> Result<()> {
    match &r.tool {
        None => refuse!(
            p,
            "tool",
            "is missing: written by a tool without a version; re-run the shard with this cullproof ({})",
            tool::VERSION
        ),
        Some(t) if t.version.trim().is_empty() => {
            refuse!(
                p,
                "tool.version",
                "is empty: written by a tool without a version; re-run the shard with this cullproof ({})",
                tool::VERSION
            )
        }
        Some(_) => {}
    }
    if r.run.timed {
        refuse!(p, "run.timed", "= true: a run for a time (--time) cannot be merged (its cases depend on the machine); shard a run of --cases N");
    }
    // the shard, in both places it is written
    let [k, n] = r.run.shard;
    if n == 0 {
        refuse!(p, "run.shard", "= [{k}, {n}]: the shard count N must be at least 1");
    }
    if k >= n {
        refuse!(
            p,
            "run.shard",
            "= [{k}, {n}]: shard {k} is not below the shard count {n} (shards are numbered 0 to N-1)"
        );
    }
    match parse_shard(&r.shard) {
        None => refuse!(p, "shard", "= {:?}: expected K/N with whole numbers 0 <= K < N", r.shard),
        Some(s) if s != (k, n) => refuse!(p, "shard", "= {:?} differs from `run.shard` = [{k}, {n}]", r.shard),
        Some(_) => {}
    }
    // the settings
    let s = &r.run.settings;
    if s.cases == 0 || s.cases > MAX_CASES {
        refuse!(p, "run.settings.cases", "= {}: a run has 1 to {MAX_CASES} cases", s.cases);
    }
    if r.seed != s.seed {
        refuse!(p, "seed", "= {} differs from `run.settings.seed` = {}", r.seed, s.seed);
    }
    if s.regimes.is_empty() {
        refuse!(p, "run.settings.regimes", "is empty: a run has at least one regime");
    }
    for (i, g) in s.regimes.iter().enumerate() {
        if !Regime::ALL.iter().any(|x| x.name() == g) {
            refuse!(p, format!("run.settings.regimes[{i}]"), "= {g:?} is not a regime");
        }
        if s.regimes[..i].contains(g) {
            refuse!(p, format!("run.settings.regimes[{i}]"), "= {g:?} is listed twice");
        }
    }
    let methods = &r.run.methods;
    if methods.is_empty() {
        refuse!(p, "run.methods", "is empty: a run has at least one method");
    }
    for (i, m) in methods.iter().enumerate() {
        if methods[..i].contains(m) {
            refuse!(p, format!("run.methods[{i}]"), "= {m:?} is listed twice");
        }
    }
    let note = r.samples.as_ref().map(|x| x.key());
    if note != s.sample_set {
        refuse!(
            p,
            "samples",
            "= {} differs from `run.settings.sample_set` = {}",
            note.as_deref().unwrap_or("(the defaults)"),
            s.sample_set.as_deref().unwrap_or("(the defaults)")
        );
    }
    if r.seconds.is_nan() || r.seconds < 0.0 {
        refuse!(p, "seconds", "= {}: not a duration", r.seconds);
    }

    // the cases: those of the shard, less the ones a viewport could not place
    let nr = s.regimes.len() as u64;
    let drawn: Vec<u64> = (0..nr).map(|g| count(s.cases, k, n, g, nr)).collect();
    let total: u64 = drawn.iter().sum();
    let of_run = format!("shard {k}/{n} of a run of {} cases (`run.settings.cases`)", s.cases);
    let outside = r.samples.as_ref().map_or(0, |x| x.outside_viewport);
    if outside > 0 && r.samples.as_ref().is_some_and(|x| x.viewport.is_none()) {
        refuse!(p, "samples.outside_viewport", "= {outside}: cases outside a viewport, but the run has none");
    }
    if outside > total {
        refuse!(p, "samples.outside_viewport", "= {outside} exceeds the {total} cases of {of_run}");
    }
    if r.cases != total {
        refuse!(p, "cases", "= {}: {of_run} draws {total} cases", r.cases);
    }

    // the rows
    let mut at: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for (i, row) in r.rows.iter().enumerate() {
        let f = |x: &str| format!("rows[{i}].{x}");
        let Some(mi) = methods.iter().position(|m| *m == row.method) else {
            refuse!(p, f("method"), "= {:?} is not one of `run.methods`", row.method)
        };
        let Some(ri) = s.regimes.iter().position(|g| *g == row.regime) else {
            refuse!(p, f("regime"), "= {:?} is not one of `run.settings.regimes`", row.regime)
        };
        if let Some(j) = at.insert((mi, ri), i) {
            refuse!(
                p,
                format!("rows[{i}]"),
                "repeats the row of method {} in regime {} (rows[{j}])",
                row.method,
                row.regime
            );
        }
        row_counts(p, i, row)?;
        let c = drawn[ri];
        if row.cases != c {
            refuse!(p, f("cases"), "= {}: {of_run} has {c} cases of regime {}", row.cases, row.regime);
        }
        if let Some(w) = &row.worst {
            let i = w.case_index;
            if i >= s.cases || i % n != k || i % nr != ri as u64 {
                refuse!(p, f("worst.case_index"), "= {i} is not a case of regime {} in {of_run}", row.regime);
            }
        }
    }
    for (mi, m) in methods.iter().enumerate() {
        if let Some(ri) = (0..s.regimes.len()).find(|&ri| drawn[ri] > 0 && !at.contains_key(&(mi, ri))) {
            refuse!(
                p,
                "rows",
                "has no row for method {m} in regime {} ({of_run} has {} cases of it): a row was dropped",
                s.regimes[ri],
                drawn[ri]
            );
        }
        let sum: u64 = at.range((mi, 0)..(mi + 1, 0)).map(|(_, &i)| r.rows[i].cases).sum();
        if sum != r.cases {
            refuse!(
                p,
                "rows",
                "of method {m} hold {sum} cases, not `cases` = {}: a row was dropped or altered",
                r.cases
            );
        }
    }
    // the totals per method are the sums of its rows
    if !r.methods.is_empty() {
        let want = strength::of_rows(&r.rows);
        if r.methods.len() != want.len() {
            refuse!(p, "methods", "lists {} methods, the rows {}", r.methods.len(), want.len());
        }
        for (i, (got, w)) in r.methods.iter().zip(&want).enumerate() {
            let pairs = [
                ("method", got.method == w.method, format!("{:?}", got.method), format!("{:?}", w.method)),
                ("cases", got.cases == w.cases, got.cases.to_string(), w.cases.to_string()),
                ("proven", got.proven == w.proven, got.proven.to_string(), w.proven.to_string()),
                ("violations", got.violations == w.violations, got.violations.to_string(), w.violations.to_string()),
                ("unproven", got.unproven == w.unproven, got.unproven.to_string(), w.unproven.to_string()),
                ("not_judged", got.not_judged == w.not_judged, got.not_judged.to_string(), w.not_judged.to_string()),
            ];
            if let Some((field, _, g, w)) = pairs.into_iter().find(|x| !x.1) {
                refuse!(p, format!("methods[{i}].{field}"), "= {g} is not what its rows add up to, {w}");
            }
        }
    }
    // the cross-check: at most the uniform samples of the regime's cases
    let mut seen = vec![false; s.regimes.len()];
    for (i, c) in r.cross_check.iter().enumerate() {
        let f = |x: &str| format!("cross_check[{i}].{x}");
        let Some(ri) = s.regimes.iter().position(|g| *g == c.regime) else {
            refuse!(p, f("regime"), "= {:?} is not one of `run.settings.regimes`", c.regime)
        };
        if std::mem::replace(&mut seen[ri], true) {
            refuse!(p, f("regime"), "= {:?} is listed twice", c.regime);
        }
        let most = drawn[ri] as u128 * s.samples as u128;
        if c.samples as u128 > most {
            refuse!(p, f("samples"), "= {}: {of_run} judges at most {most} samples in regime {}", c.samples, c.regime);
        }
        if c.interior > c.samples {
            refuse!(p, f("interior"), "= {} exceeds `samples` = {}", c.interior, c.samples);
        }
        if c.embree_over > c.samples - c.interior {
            refuse!(
                p,
                f("embree_over"),
                "= {} exceeds the {} samples not interior",
                c.embree_over,
                c.samples - c.interior
            );
        }
        if c.embree_under > c.interior {
            refuse!(p, f("embree_under"), "= {} exceeds `interior` = {}", c.embree_under, c.interior);
        }
    }
    Ok(())
}

/// A row's counts against its cases.
fn row_counts(p: &Path, i: usize, row: &Row) -> Result<()> {
    let f = |x: &str| format!("rows[{i}].{x}");
    let cases = row.cases;
    if cases == 0 {
        refuse!(p, f("cases"), "= 0: the gate writes no row without cases");
    }
    let counts = [
        ("proven", row.proven),
        ("violations", row.violations),
        ("unproven", row.unproven),
        ("not_judged", row.not_judged),
    ];
    for (name, v) in counts {
        if v > cases {
            refuse!(p, f(name), "= {v} exceeds cases = {cases}");
        }
    }
    let sum: u128 = counts.iter().map(|c| c.1 as u128).sum();
    if sum != cases as u128 {
        refuse!(
            p,
            f("proven"),
            "+ violations + unproven + not_judged = {} + {} + {} + {} = {sum}, not cases = {cases} (each case is \
             exactly one of them)",
            row.proven,
            row.violations,
            row.unproven,
            row.not_judged
        );
    }
    let at_most = [
        ("f32_witnessed", row.f32_witnessed, row.violations, "violations"),
        ("tail", row.tail, row.violations, "violations"),
        ("boundary_only", row.boundary_only, cases, "cases"),
        ("limit_found", row.limit_found, cases, "cases"),
        ("limit_tiles", row.limit_tiles, cases.saturating_mul(2), "2 x cases"),
        ("limit_violations", row.limit_violations, row.limit_tiles, "limit_tiles"),
    ];
    for (name, v, most, of) in at_most {
        if v > most {
            refuse!(p, f(name), "= {v} exceeds {of} = {most}");
        }
    }
    for (why, &v) in &row.unproven_by {
        if v > row.unproven {
            refuse!(p, f(&format!("unproven_by.{why}")), "= {v} exceeds unproven = {}", row.unproven);
        }
    }
    for (kind, t) in &row.tight {
        // (the boundary tile and two limit tiles, three coordinates with two ends each)
        let most = cases.saturating_mul(18);
        if t.probed > most {
            refuse!(p, f(&format!("tight.{kind}.probed")), "= {} exceeds 18 x cases = {most}", t.probed);
        }
        if t.tight > t.probed {
            refuse!(p, f(&format!("tight.{kind}.tight")), "= {} exceeds probed = {}", t.tight, t.probed);
        }
    }
    for (kind, b) in &row.bounds {
        if b.cases > cases {
            refuse!(p, f(&format!("bounds.{kind}.cases")), "= {} exceeds cases = {cases}", b.cases);
        }
    }
    // each case adds a fraction in [0, 1] (a slack in [-1, 1] once scaled), in fixed point
    let one = fixed::fraction(1.0);
    let sums = [
        ("sums.pass", row.sums.pass, 0, (cases as i128).saturating_mul(one), "cases"),
        ("sums.admit", row.sums.admit, 0, (cases as i128).saturating_mul(one), "cases"),
        (
            "sums.slack",
            row.sums.slack,
            -(row.limit_found as i128).saturating_mul(one),
            (row.limit_found as i128).saturating_mul(one),
            "limit_found",
        ),
    ];
    for (name, v, lo, hi, of) in sums {
        if v < lo || v > hi {
            refuse!(p, f(name), "= {v} is outside {lo} to {hi}, what {of} can add up to");
        }
    }
    Ok(())
}

/// The reports against each other: one build, one set of expectations and baseline, one
/// run, every shard of it exactly once.
fn together(shards: &[(PathBuf, CheckReport)]) -> Result<()> {
    let Some((fp, first)) = shards.first() else { bail!("merge: no shard reports given") };
    let (ft, n) = (first.tool.clone().unwrap_or_default(), first.run.shard[1]);
    let mut seen: BTreeMap<u64, (usize, &Path)> = BTreeMap::new();
    for (arg, (p, r)) in shards.iter().enumerate() {
        let t = r.tool.clone().unwrap_or_default();
        let differ = |field: &str, a: &Option<String>, b: &Option<String>, why: &str| -> Result<()> {
            if a != b {
                let show = |x: &Option<String>| x.as_deref().map_or("none".into(), |s| format!("{s:?}"));
                refuse!(p, field, "= {} differs from {}'s {}: {why}", show(a), fp.display(), show(b));
            }
            Ok(())
        };
        differ("tool.version", &Some(t.version.clone()), &Some(ft.version.clone()), "shards of different builds")?;
        let same_files =
            "shards run with different files (run every shard with the same --expectations and --baseline)";
        differ("tool.expectations", &t.expectations, &ft.expectations, same_files)?;
        differ("tool.baseline", &t.baseline, &ft.baseline, same_files)?;
        if r.run.methods != first.run.methods {
            refuse!(
                p,
                "run.methods",
                "= {:?} differs from {}'s {:?}: shards of different runs",
                r.run.methods,
                fp.display(),
                first.run.methods
            );
        }
        settings_differ(p, r, fp, first)?;
        let [k, rn] = r.run.shard;
        if rn != n {
            refuse!(p, "run.shard", "= {k}/{rn}: {} is a shard of {n}", fp.display());
        }
        if let Some(&(a, other)) = seen.get(&k) {
            if same_file(other, p) {
                bail!(
                    "{} (argument {}): field `run.shard` = {k}/{n}: shard {k} is also {} (argument {}): the same file given twice",
                    p.display(),
                    arg + 1,
                    other.display(),
                    a + 1
                );
            }
            refuse!(p, "run.shard", "= {k}/{n}: shard {k} is also {} (each shard once)", other.display());
        }
        seen.insert(k, (arg, p));
    }
    if let Some(k) = (0..n).find(|k| !seen.contains_key(k)) {
        bail!("merge: shard {k}/{n} is missing (give the reports of all {n} shards)");
    }
    Ok(())
}

/// The same path, or two paths to one file.
fn same_file(a: &Path, b: &Path) -> bool {
    a == b || matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
}

/// The first field of `run.settings` where two shards differ, named.
fn settings_differ(p: &Path, r: &CheckReport, fp: &Path, first: &CheckReport) -> Result<()> {
    if r.run.settings == first.run.settings {
        return Ok(());
    }
    let obj = |x: &CheckReport| match serde_json::to_value(&x.run.settings) {
        Ok(serde_json::Value::Object(m)) => m,
        _ => Default::default(),
    };
    let (a, b) = (obj(r), obj(first));
    let null = serde_json::Value::Null;
    let key = a.keys().chain(b.keys()).find(|k| a.get(*k).unwrap_or(&null) != b.get(*k).unwrap_or(&null));
    match key {
        Some(k) => refuse!(
            p,
            format!("run.settings.{k}"),
            "= {} differs from {}'s {}: shards of different runs",
            a.get(k).unwrap_or(&null),
            fp.display(),
            b.get(k).unwrap_or(&null)
        ),
        None => refuse!(p, "run.settings", "differs from {}'s: shards of different runs", fp.display()),
    }
}

#[cfg(test)]
mod tests {
    use super::count;

    #[test]
    fn counts_follow_the_indices() {
        for cases in [1u64, 7, 48, 150, 1000] {
            for n in 1..6u64 {
                for m in 1..17u64 {
                    for k in 0..n {
                        for g in 0..m {
                            let want = (0..cases).filter(|i| i % n == k && i % m == g).count() as u64;
                            assert_eq!(count(cases, k, n, g, m), want, "{cases} {k}/{n} {g}/{m}");
                        }
                    }
                }
            }
        }
        assert_eq!(count(1_000_000_000, 0, u64::MAX, 0, 16), 1);
        assert_eq!(count(1_000_000_000, 5, u64::MAX, 5, 16), 1);
    }
}
