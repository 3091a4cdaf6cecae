//! The gate's report: a row per method x regime ([`Row`]) with the three counts, its
//! status against the expectations (and the baseline), a summary per method, the text
//! table.

use super::expect::{Allowance, Entry, Expectations, Expected};
use super::row::{fixed, Row, RowSums, Status};
use super::settings::RunInfo;
use super::CheckConfig;
use crate::cases::generate::Regime;
use crate::judge::{Judgement, Verdict};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The result of a run.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct CheckReport {
    pub seed: u64,
    pub cases: u64,
    pub shard: String,
    /// The run's methods and settings (what `cullproof merge` checks shards against).
    pub run: RunInfo,
    pub rows: Vec<Row>,
    /// Per method, the strongest verdict it reaches ([`super::strength`]): violated,
    /// machine-checked for all inputs in ranges, rounding lemmas checked (composition
    /// argued), proven on N cases, unproven.
    #[serde(default)]
    pub methods: Vec<super::strength::MethodStrength>,
    /// The sampled cross-check of Embree against the exact oracle, per regime.
    pub cross_check: Vec<CrossCheck>,
    /// Boxes the extents solver examined in all.
    pub solver_boxes: u64,
    pub seconds: f64,
    /// Whether a baseline for these settings was found and compared.
    pub baseline: Option<String>,
    /// The sample set, snapping and viewport when any differs from the default
    /// (`docs/model.md`, §7), with the cases the viewport could not place.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[serde(default)]
    pub samples: Option<super::settings::SetNote>,
    /// Per plugged method (`--plugin`) whose answers broke the contract of
    /// include/cullproof.h during the run: how many answers, of which kinds (each judged
    /// as given, as `src/external/plugin/mod.rs` says; the verdicts are unchanged).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub contract_breaches: Vec<crate::external::plugin::ContractBreaches>,
    /// The build that wrote the report and the expectations and baseline it used
    /// (absent from reports of older builds, which `cullproof merge` refuses).
    #[serde(default)]
    pub tool: Option<super::tool::ToolInfo>,
}

impl CheckReport {
    /// True when some row fails (see [`Status::fails`]).
    pub fn failed(&self) -> bool {
        self.rows.iter().any(|r| r.status.fails())
    }
}

/// The sampled cross-check of the two ground truths on one case: the gate's uniform
/// tile samples judged exactly and by Embree (physical cases only).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CrossCheck {
    pub regime: String,
    /// Samples judged by both oracles.
    pub samples: u64,
    /// Of those, exactly interior.
    pub interior: u64,
    /// Embree said hit where the exact oracle says not interior.
    pub embree_over: u64,
    /// Embree said miss on an interior sample.
    pub embree_under: u64,
}

/// Collects case results into rows, in case order.
pub(crate) struct Accumulator<'a> {
    ex: &'a Expectations,
    rows: BTreeMap<(usize, usize), Row>,
    /// Exact sums of the pass fraction, the admit fraction and the limit slack.
    pass_sum: BTreeMap<(usize, usize), RowSums>,
    cross: BTreeMap<usize, CrossCheck>,
    boxes: u64,
}

impl<'a> Accumulator<'a> {
    pub fn new(ex: &'a Expectations) -> Self {
        Accumulator { ex, rows: BTreeMap::new(), pass_sum: BTreeMap::new(), cross: BTreeMap::new(), boxes: 0 }
    }

    pub fn add(
        &mut self,
        cfg: &CheckConfig,
        regime: Regime,
        js: Vec<Judgement>,
        pass: &[(f64, f64)],
        boxes: u64,
        cc: CrossCheck,
    ) {
        self.boxes += boxes;
        let ri = cfg.regimes.iter().position(|r| *r == regime).unwrap();
        let x =
            self.cross.entry(ri).or_insert_with(|| CrossCheck { regime: regime.name().into(), ..Default::default() });
        x.samples += cc.samples;
        x.interior += cc.interior;
        x.embree_over += cc.embree_over;
        x.embree_under += cc.embree_under;
        for (mi, j) in js.into_iter().enumerate() {
            let m = cfg.methods[mi].info().id;
            let ex = self.ex;
            let row = self.rows.entry((mi, ri)).or_insert_with(|| {
                let entry = ex.entry(m, regime.name()).scoped(super::settings::Settings::whole(cfg).measured());
                Row {
                    method: m.into(),
                    regime: regime.name().into(),
                    cases: 0,
                    proven: 0,
                    violations: 0,
                    unproven: 0,
                    not_judged: 0,
                    unproven_by: BTreeMap::new(),
                    bounds: BTreeMap::new(),
                    tail: 0,
                    boundary_only: 0,
                    f32_witnessed: 0,
                    limit_tiles: 0,
                    limit_violations: 0,
                    limit_found: 0,
                    limit_slack: 0.0,
                    tight: BTreeMap::new(),
                    admit_fraction: 0.0,
                    pass_fraction: 0.0,
                    margin_needed: 0.0,
                    expected: entry.expect,
                    status: Status::Proven,
                    problems: Vec::new(),
                    worst: None,
                    examples: Vec::new(),
                    sums: RowSums::default(),
                    entry: Some(entry),
                }
            });
            let sums = self.pass_sum.entry((mi, ri)).or_default();
            let (p, a) = pass.get(mi).copied().unwrap_or((0.0, 0.0));
            sums.pass += fixed::fraction(p);
            sums.admit += fixed::fraction(a);
            if let Some(sl) = j.limit_slack {
                sums.slack += fixed::slack(sl);
                row.limit_found += 1;
            }
            row.cases += 1;
            row.boundary_only += j.boundary_only as u64;
            row.limit_tiles += j.limit_tiles as u64;
            row.limit_violations += j.limit_violations as u64;
            match j.verdict() {
                Verdict::Proven => row.proven += 1,
                Verdict::NotJudged => row.not_judged += 1,
                Verdict::Unproven => {
                    row.unproven += 1;
                    for r in j.unproven() {
                        *row.unproven_by.entry(r.name().into()).or_insert(0) += 1;
                    }
                }
                Verdict::Violated => {
                    row.violations += 1;
                    row.f32_witnessed += j.f32_witness as u64;
                    if row.examples.len() < super::row::EXAMPLES_PER_ROW {
                        row.examples.extend(j.violation.clone());
                    }
                }
            }
            for (k, &(n, t)) in &j.tight {
                let s = row.tight.entry(k.clone()).or_default();
                s.probed += n as u64;
                s.tight += t as u64;
            }
            if row.entry.as_ref().is_some_and(|e| e.in_tail(&j.violated)) {
                row.tail += 1;
            }
            for (k, m) in &j.violated {
                let b = row.bounds.entry(k.clone()).or_default();
                b.cases += 1;
                b.max_margin = b.max_margin.max(*m);
            }
            if let Some(w) = j.violation {
                if w.margin >= row.margin_needed {
                    row.margin_needed = w.margin;
                    row.worst = Some(w);
                }
            }
        }
    }

    pub fn finish(mut self, cfg: &CheckConfig, judged: u64, seconds: f64) -> CheckReport {
        for (key, row) in self.rows.iter_mut() {
            row.sums = self.pass_sum[key];
            finish_row(row);
        }
        let (k, n) = cfg.shard;
        let mut rows: Vec<Row> = self.rows.into_values().collect();
        pooled_tightness(&mut rows);
        pooled_tail(&mut rows);
        CheckReport {
            methods: super::strength::of_rows(&rows),
            seed: cfg.seed,
            cases: judged,
            shard: format!("{k}/{n}"),
            run: RunInfo::of(cfg),
            rows,
            cross_check: self.cross.into_values().collect(),
            solver_boxes: self.boxes,
            seconds,
            baseline: None,
            samples: super::settings::SetNote::of(cfg, 0),
            contract_breaches: Vec::new(),
            tool: Some(super::tool::ToolInfo::of(self.ex, None)),
        }
    }
}

/// The tightness signature over all of a method's rows at once: per end kind, the tight
/// ends of every row that has a least share for that kind, against the sum of those
/// shares times the ends probed (a binomial test over the pooled rows, see
/// [`super::expect::least_tight`]). A row holds too few ends to see a loosening at small
/// case counts; the method's rows together do. Failing kinds turn the method's rows
/// with that kind into regressions, each naming the pooled counts.
pub(crate) fn pooled_tightness(rows: &mut [Row]) {
    let methods: std::collections::BTreeSet<String> = rows.iter().map(|r| r.method.clone()).collect();
    for method in methods {
        let failing = super::expect::pooled_looser(rows.iter().filter_map(|row| {
            let entry = row.entry.as_ref()?;
            (row.method == method && row.status != Status::NotGated).then_some((entry, &row.tight))
        }));
        for (kind, line) in failing {
            for row in
                rows.iter_mut().filter(|r| r.method == method && r.tight.get(&kind).is_some_and(|s| s.probed > 0))
            {
                if !row.status.fails() {
                    row.status = Status::Regression;
                }
                if !row.problems.contains(&line) {
                    row.problems.push(line.clone());
                }
            }
        }
    }
}

/// The tail over all of a method's rows at once ([`super::expect::pooled_tail_breach`]):
/// when the method's cases in the tail pass what its tail rates allow, every row of the
/// method with a case in the tail fails, naming the pooled count.
pub(crate) fn pooled_tail(rows: &mut [Row]) {
    let methods: std::collections::BTreeSet<String> = rows.iter().map(|r| r.method.clone()).collect();
    for method in methods {
        let line = super::expect::pooled_tail_breach(rows.iter().filter_map(|row| {
            let entry = row.entry.as_ref()?;
            (row.method == method && row.status != Status::NotGated).then_some((
                entry,
                row.tail,
                row.cases - row.not_judged,
            ))
        }));
        let Some(line) = line else { continue };
        for row in rows.iter_mut().filter(|r| r.method == method && r.tail > 0) {
            if !row.status.fails() {
                row.status = Status::BeyondSignature;
            }
            if !row.problems.contains(&line) {
                row.problems.push(line.clone());
            }
        }
    }
}

/// A row's means from its exact sums, and its status.
pub(crate) fn finish_row(row: &mut Row) {
    // The means are over the cases judged (a case not judged adds nothing to the sums).
    row.pass_fraction = fixed::mean_fraction(row.sums.pass, row.cases - row.not_judged);
    row.admit_fraction = fixed::mean_fraction(row.sums.admit, row.cases - row.not_judged);
    row.limit_slack = fixed::mean_slack(row.sums.slack, row.limit_found);
    set_status(row);
}

/// The status of a row against its expectation.
fn set_status(row: &mut Row) {
    let entry = row.entry.clone().unwrap_or_else(Entry::conservative);
    row.problems.clear();
    // Rates and allowances count the cases judged.
    let judged = row.cases - row.not_judged;
    row.status = match entry.expect {
        Expected::Unknown => Status::NotGated,
        _ if judged == 0 && row.cases > 0 => Status::NotJudged,
        Expected::Conservative if row.violations > 0 => {
            let kinds: Vec<&str> = row.bounds.keys().map(|s| s.as_str()).collect();
            row.problems.push(format!("{} violations ({})", row.violations, kinds.join(", ")));
            Status::UnexpectedViolation
        }
        Expected::Conservative if row.unproven == 0 => Status::Proven,
        Expected::Conservative => {
            let allowed = entry.unproven.as_ref().map_or(0.0, |a| a.max_rate);
            if row.unproven as f64 <= Allowance::cases_allowed(allowed, judged) {
                Status::ProvenExceptAllowed
            } else {
                row.problems.push(format!(
                    "{} of {} cases unproven ({}), allowance {}",
                    row.unproven,
                    row.cases,
                    row.unproven_by.iter().map(|(k, v)| format!("{k} {v}")).collect::<Vec<_>>().join(", "),
                    allowed
                ));
                Status::Unproven
            }
        }
        Expected::Violation if row.violations == 0 => Status::ExpectedNotSeen,
        Expected::Violation => {
            let stats: BTreeMap<String, (u64, f64)> =
                row.bounds.iter().map(|(k, b)| (k.clone(), (b.cases, b.max_margin))).collect();
            let mut br = entry.breaches(&stats, row.violations, judged);
            br.extend(entry.limit_rate_breach(row.limit_violations, row.limit_tiles));
            if br.is_empty() {
                Status::KnownViolation
            } else {
                row.problems = br;
                Status::BeyondSignature
            }
        }
    };
    // Looser than the signature allows, at any settings: a row that passes otherwise
    // fails as a regression (a row that already fails keeps its status; the lines
    // are added either way).
    if !matches!(row.status, Status::NotGated | Status::NotJudged) {
        let mut looser = entry.looser(&row.tight);
        looser.extend(entry.admit_breach(row.admit_fraction, judged));
        if !looser.is_empty() && !row.status.fails() {
            row.status = Status::Regression;
        }
        row.problems.extend(looser);
    }
}

fn fmt_margin(row: &Row) -> String {
    if row.violations == 0 {
        "-".to_string()
    } else {
        format!("{:.3e}", row.margin_needed)
    }
}

/// One line per method with cases in its tail: how many, against what its tail rate
/// allows (empty when no method has one).
fn render_tail(r: &CheckReport) -> String {
    let mut s = String::new();
    let methods: std::collections::BTreeSet<&str> =
        r.rows.iter().filter(|x| x.tail > 0).map(|x| x.method.as_str()).collect();
    for m in methods {
        let rows = r.rows.iter().filter(|x| x.method == m);
        let tail: u64 = rows.clone().map(|x| x.tail).sum();
        let c = super::expect::TailCount::of(rows.map(|x| {
            let rate = x.entry.as_ref().and_then(Entry::tail_rate);
            (rate, x.tail, x.cases - x.not_judged)
        }));
        s += &format!(
            "tail of {m}: {tail} case(s) violate a kind above their regime's cap, within the method's largest; its tail \
             rates allow {:.1} of {} cases\n",
            c.allowed, c.cases
        );
    }
    s
}

/// One line per method over all regimes: the verdict at a glance.
fn render_summary(r: &CheckReport) -> String {
    let mut s = format!(
        "\nper method, all regimes (the strongest verdict each reaches):\n{:<26} {:>6} {:>7} {:>10} {:>8} {:>11}  {}\n",
        "method", "cases", "proven", "violated", "unproven", "margin", "verdict"
    );
    let strengths = if r.methods.is_empty() { super::strength::of_rows(&r.rows) } else { r.methods.clone() };
    for m in &strengths {
        let rows: Vec<&Row> = r.rows.iter().filter(|x| x.method == m.method).collect();
        let margin = rows.iter().filter(|x| x.violations > 0).map(|x| x.margin_needed).fold(0.0, f64::max);
        let failing = rows.iter().filter(|x| x.status.fails()).count();
        let gate = if failing > 0 { format!(" — FAILS in {failing} rows") } else { String::new() };
        s += &format!(
            "{:<26} {:>6} {:>7} {:>10} {:>8} {:>11}  {}{}\n",
            m.method,
            m.cases,
            m.proven,
            m.violations,
            m.unproven,
            if m.violations == 0 { "-".to_string() } else { format!("{margin:.3e}") },
            m.text,
            gate
        );
    }
    s
}

/// The verdict table.
pub fn render(r: &CheckReport) -> String {
    // The not-judged column only where some case could not be judged (snapping,
    // placement in a viewport).
    let nj = r.rows.iter().any(|x| x.not_judged > 0);
    let not_judged = |v: &dyn std::fmt::Display| if nj { format!(" {v:>10}") } else { String::new() };
    let mut s = format!(
        "cullproof check, seed {}, {} cases (shard {}), {:.1} s\n\n{:<26} {:<15} {:>6} {:>7} {:>8} {:>8}{} {:>5} {:>7} {:>11}  status\n",
        r.seed,
        r.cases,
        r.shard,
        r.seconds,
        "method",
        "regime",
        "cases",
        "proven",
        "violated",
        "unproven",
        not_judged(&"not judged"),
        "f32",
        "limit",
        "margin"
    );
    if let Some(n) = &r.samples {
        s = s.replacen("\n\n", &format!("\n{}\n\n", n.line()), 1);
    }
    let mut last = "";
    for row in &r.rows {
        let m = if row.method == last { "" } else { row.method.as_str() };
        last = &row.method;
        s += &format!(
            "{:<26} {:<15} {:>6} {:>7} {:>8} {:>8}{} {:>5} {:>7} {:>11}  {}\n",
            m,
            row.regime,
            row.cases,
            row.proven,
            row.violations,
            row.unproven,
            not_judged(&row.not_judged),
            row.f32_witnessed,
            format!("{}/{}", row.limit_violations, row.limit_tiles),
            fmt_margin(row),
            row.status.text()
        );
    }
    s += &render_summary(r);
    s += &render_tail(r);
    s += "\nproven: every claim certified (no gap left); violated: an interior sample, confirmed exactly, in the tile and\n\
          the lens/shutter domain, that the answer culls; unproven: neither (by reason in the JSON report).\n\
          margin: the padding of the violated bound that would admit every witness found (inf: a covered tile was culled).\n\
          f32: violations with a witness that is an f32 sample. limit: violations / tiles judged at the method's own\n\
          tile-reject limit.\n";
    if nj {
        s += "not judged: cases the declared samples leave no question about (a vertex that snapping cannot snap \
              exactly, a case the viewport cannot hold): neither a failure nor a pass.\n";
    }
    let (n, inside, over, under) = r
        .cross_check
        .iter()
        .fold((0, 0, 0, 0), |a, c| (a.0 + c.samples, a.1 + c.interior, a.2 + c.embree_over, a.3 + c.embree_under));
    let differ: Vec<String> = r
        .cross_check
        .iter()
        .filter(|c| c.embree_over + c.embree_under > 0)
        .map(|c| format!("{} {}", c.regime, c.embree_over + c.embree_under))
        .collect();
    s += &format!(
        "sampled cross-check: {n} uniform tile samples of physical cases judged by both oracles, {inside} interior; \
         Embree (f32) differed on {} ({over} over, {under} under{}{}), each settled by the exact oracle.\n",
        over + under,
        if differ.is_empty() { "" } else { "; by regime: " },
        differ.join(", ")
    );
    match &r.baseline {
        Some(b) => s += &format!("baseline: {b}\n"),
        None => s += "baseline: none stored for these settings (only the expectations were applied)\n",
    }
    let failing: Vec<&Row> = r.rows.iter().filter(|x| x.status.fails()).collect();
    if failing.is_empty() {
        s += "verdict: PASS — every row is proven, within its allowance of unproven cases, or within the signature \
              of its expected violations\n";
    } else {
        s += &format!("verdict: FAIL — {} method x regime rows:\n", failing.len());
        for row in failing {
            s += &format!("  {} / {}: {}: {}\n", row.method, row.regime, row.status.text(), row.problems.join("; "));
            if let Some(w) = &row.worst {
                s += &format!(
                    "    worst: case {} tile [{}, {}]x[{}, {}] sample {:?} culled by {} (margin {:.3e}, Embree {})\n",
                    w.case_index,
                    w.tile.x0,
                    w.tile.x1,
                    w.tile.y0,
                    w.tile.y1,
                    w.sample,
                    w.bound,
                    w.margin,
                    match w.embree_hit {
                        Some(true) => "hits too",
                        Some(false) => "misses",
                        None => "n/a",
                    }
                );
            }
        }
    }
    s
}
