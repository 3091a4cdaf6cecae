//! The randomized counterexample search, held against the expected signatures with
//! `--gate`, and its report.

use super::*;
use crate::bounds::MethodRef;
use crate::cases::generate::Regime;
use crate::cases::try_make_case;
use crate::gate::expect::{pooled_looser, Entry, Place};
use crate::gate::{Cap, CheckConfig, Expectations};
use crate::io::num_or_inf;
use crate::judge::Judgement;
use anyhow::Result;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;

/// One case of a search: its index and regime, the boundary tile's judgement, the limit
/// tiles' (kept when its violation lies in the viewport), the limit tiles judged and
/// violated, and the share of the boundary tile's samples the answer admits.
type CaseSeen = (u64, Regime, Judgement, Option<Judgement>, (u32, u32), f64);

/// What a search found.
#[derive(Clone, Debug, Serialize)]
pub struct Found {
    pub method: String,
    pub regime: String,
    pub case_index: u64,
    pub seconds_to_first: f64,
    pub margin: f64,
    pub bound: String,
    /// The kind of bound (as `corpus/expectations.json` names it, see
    /// [`crate::judge::bound_kind`]) the finding is about.
    pub kind: String,
    pub shrink_steps: Vec<String>,
    /// Where it was written (None: the same case was already in the corpus).
    pub file: Option<String>,
    /// Beyond the method's expected signature for the regime: a kind of bound the
    /// signature does not list, a margin above its cap, or any violation where the
    /// regime is expected conservative (false when no expectations were given).
    pub beyond_signature: bool,
    /// The signature's cap on this kind's margin (null: the kind is not listed, the
    /// regime is not an expected violation, or no expectations were given).
    pub cap: Option<Cap>,
    /// Why it is beyond ("not in the signature", "above the cap 5e-5", "the regime is
    /// expected conservative"), or where it lies in the tail; empty inside the signature.
    pub signature: String,
    /// In the method's tail ([`crate::gate::expect::Place::Tail`]): above the regime's
    /// cap, within the method's largest; written for a look, failing only when the tail
    /// as a whole passes its rate (one such finding per regime and kind).
    pub tail: bool,
}

/// One kind of bound violated in one regime during a search, over every case (before
/// any dedupe or shrinking), held against the signature.
#[derive(Clone, Debug, Serialize)]
pub struct KindSeen {
    pub regime: String,
    pub kind: String,
    /// Cases that violate it (by at least the search's minimum margin).
    pub cases: u64,
    /// The largest margin seen ("inf": a covered tile culled).
    #[serde(with = "num_or_inf")]
    pub max_margin: f64,
    /// The signature's cap (null: not listed, or not an expected violation).
    pub cap: Option<Cap>,
    /// The largest margin lies beyond the signature.
    pub beyond_signature: bool,
}

/// One regime of a search: its cases, and on their boundary tiles (as the gate judges
/// them) the cases with a violation and the proven interval ends probed for tightness.
/// Under `--gate` these are held against the signature's rate cap and tightness.
#[derive(Clone, Debug, Default, Serialize)]
pub struct RegimeSeen {
    pub regime: String,
    pub cases: u64,
    /// Cases whose boundary tile shows a violation (by at least the minimum margin).
    pub violated: u64,
    /// Cases with a kind in the method's tail (over all their tiles).
    pub tail: u64,
    /// The signature's tail rate (null: none).
    pub max_tail_rate: Option<f64>,
    /// The signature's rate cap (null: none).
    pub max_rate: Option<f64>,
    /// The signature's cap on the search's boundary-tile rate (null: none, or not at
    /// these settings); the table shows it in place of `max_rate` where there is one.
    pub max_boundary_rate: Option<f64>,
    pub tight: BTreeMap<String, crate::gate::expect::TightStat>,
    /// Tiles judged at the method's own tile-reject limit, and those with a violation.
    pub limit_tiles: u64,
    pub limit_violations: u64,
    /// The signature's cap on the limit tiles' violation rate (null: none, or not at
    /// these settings).
    pub max_limit_rate: Option<f64>,
    /// Mean share of the boundary tile's uniform samples the answers admit.
    pub admit_fraction: f64,
    /// The signature's cap on that share (null: none, or not at these settings).
    pub max_admit: Option<f64>,
}

/// The result of a search.
#[derive(Clone, Debug, Serialize)]
pub struct SearchReport {
    pub method: String,
    pub seed: u64,
    pub cases: u64,
    pub seconds: f64,
    pub found: Vec<Found>,
    /// Under `--gate`: only violations beyond the signature are findings (shrunk,
    /// written, counted against `--max`); the others are only counted.
    pub gate: bool,
    /// The expectations file the violations were held against (None: none).
    pub expectations: Option<String>,
    /// Cases with a violation (at least the minimum margin), and of those the ones
    /// with some kind of bound beyond the signature.
    pub violated_cases: u64,
    pub beyond_cases: u64,
    /// Cases with a kind in the method's tail and none beyond the signature.
    pub tail_cases: u64,
    /// Per regime and kind of bound violated (when expectations were given).
    pub kinds: Vec<KindSeen>,
    /// Per regime: cases, violated boundary tiles and tightness.
    pub regimes: Vec<RegimeSeen>,
    /// Under `--gate`: where the search's cases as a whole leave the signature (a
    /// violation rate above the cap, beyond counting noise; fewer tight ends than the
    /// tightness signature allows, per regime and pooled over the regimes), one line
    /// each. No single case witnesses these, so no case file is written for them.
    pub breaches: Vec<String>,
}

/// How a search runs (see [`search_with`]).
pub struct SearchOptions<'a> {
    /// Search for about this many seconds.
    pub seconds: f64,
    /// Stop after this many findings.
    pub max_found: usize,
    /// Ignore violations that need less margin.
    pub min_margin: f64,
    /// Where to write the shrunk cases (None: report only).
    pub out: Option<&'a Path>,
    pub progress: bool,
    /// The expectations each violation is held against, and the file's name (None:
    /// not judged).
    pub expectations: Option<(&'a Expectations, &'a str)>,
    /// Only violations beyond the signature are findings (needs `expectations`).
    pub gate: bool,
}

/// Randomized search for violations of one method: cases of the regimes in turn, in
/// parallel batches (the order of cases, hence the result, does not depend on the
/// thread count), for `seconds` or until `max_found` violations; each violation is
/// shrunk and written to `out` (never overwriting).
pub fn search(
    cfg: &CheckConfig,
    m: MethodRef,
    seconds: f64,
    max_found: usize,
    min_margin: f64,
    out: Option<&Path>,
    progress: bool,
) -> Result<SearchReport> {
    let o = SearchOptions { seconds, max_found, min_margin, out, progress, expectations: None, gate: false };
    search_with(cfg, m, &o)
}

/// [`search()`], each violation held against the method's expected signature for its
/// regime (`corpus/expectations.json`, see [`crate::gate::expect`]): every kind of
/// bound it violates, with its margin. Without the gate, one finding per regime and
/// bound (one per regime, bound and side of the signature when expectations are
/// given: a violation beyond the signature is never hidden behind one inside it),
/// each annotated. With `gate`, violations inside the signature are only counted
/// (they neither stop the search nor count against `max_found`), and each kind of
/// bound beyond the signature makes a finding (one per regime and kind), shrunk while
/// it stays beyond the signature at least half as large, and written with that
/// kind's own witness.
pub fn search_with(cfg: &CheckConfig, m: MethodRef, o: &SearchOptions) -> Result<SearchReport> {
    use rayon::prelude::*;
    anyhow::ensure!(!o.gate || o.expectations.is_some(), "a gated search needs the expectations");
    let mut cfg = cfg.clone();
    cfg.judge.witnesses_per_kind = true;
    let cfg = &cfg;
    let id = m.info().id;
    let measured = crate::gate::settings::Settings::whole(cfg).measured();
    // Each regime's entry, looked up once (with its tail's reach).
    let entries: Option<BTreeMap<Regime, Entry>> = o
        .expectations
        .map(|(ex, _)| Regime::ALL.into_iter().map(|r| (r, ex.entry(id, r.name()).scoped(measured))).collect());
    let entry = |r: Regime| entries.as_ref().and_then(|m| m.get(&r));
    // The kinds of bound a judgement violates (by the minimum margin) in one place of
    // the signature, largest margin first, each with why it stands there.
    let kinds_in = |r: Regime, j: &Judgement, tail: bool| -> Vec<(String, f64, String)> {
        let Some(e) = entry(r) else { return Vec::new() };
        let mut v: Vec<_> = j
            .violated
            .iter()
            .filter(|(_, &mm)| mm >= o.min_margin)
            .filter_map(|(k, &mm)| match (e.place(k, mm), tail) {
                (Place::Beyond(why), false) => Some((k.clone(), mm, why)),
                (Place::Tail, true) => {
                    let cap =
                        e.cap(k).map_or("not listed here".to_string(), |c| format!("above this regime's cap {c:e}"));
                    let most = e.tail_caps.get(k).map_or(f64::NAN, |c| c.0);
                    Some((k.clone(), mm, format!("{cap}, within the method's largest cap {most:e}")))
                }
                _ => None,
            })
            .collect();
        v.sort_by(|a, b| b.1.total_cmp(&a.1));
        v
    };
    let beyond_kinds = |r: Regime, j: &Judgement| kinds_in(r, j, false);
    let tail_kinds = |r: Regime, j: &Judgement| kinds_in(r, j, true);
    let interesting = |r: Regime, j: &Judgement| {
        if o.gate {
            !beyond_kinds(r, j).is_empty() || !tail_kinds(r, j).is_empty()
        } else {
            j.violation.as_ref().is_some_and(|v| v.margin >= o.min_margin)
        }
    };
    let start = std::time::Instant::now();
    let pb = if o.progress { indicatif::ProgressBar::new_spinner() } else { indicatif::ProgressBar::hidden() };
    let mut found = Vec::new();
    let mut next = 0u64;
    let batch = 8 * rayon::current_num_threads() as u64;
    let mut seen = std::collections::BTreeSet::new();
    let (mut violated_cases, mut beyond_cases, mut tail_cases) = (0u64, 0u64, 0u64);
    let beyond_found = |found: &Vec<Found>| found.iter().filter(|f| !f.tail).count();
    let mut kinds: std::collections::BTreeMap<(Regime, String), (u64, f64)> = Default::default();
    let mut per_regime: BTreeMap<Regime, RegimeSeen> = BTreeMap::new();
    while start.elapsed().as_secs_f64() < o.seconds && beyond_found(&found) < o.max_found {
        let ids: Vec<u64> = (next..next + batch).collect();
        next += batch;
        // Per case: the boundary tile's judgement, and the limit tiles' when the
        // boundary tile shows nothing of interest.
        let results: Vec<CaseSeen> = ids
            .par_iter()
            .filter_map(|&i| {
                let (regime, case, tile) = try_make_case(&cfg.draw(), i)?;
                let (js, admit, _) = crate::gate::judge_admitted(cfg, std::slice::from_ref(&m), &case, &tile, i);
                let (j, admit) = (js.into_iter().next().unwrap(), admit[0]);
                // Also the tiles at the method's own tile-reject limit (the witness
                // then carries the case, moved on screen, and the tile), counted for
                // the limit-tile rate.
                let (mut limit, mut counts) = (None, (0, 0));
                if !interesting(regime, &j) {
                    if let (Some(l), _) = crate::gate::judge_limit_tiles(cfg, m.as_ref(), &case, i, 0) {
                        counts = (l.limit_tiles, l.limit_violations);
                        let w = l.violation.as_ref();
                        if w.is_some_and(|w| crate::cases::place::placed_in(cfg.viewport, &w.case, &w.tile)) {
                            limit = Some(l);
                        }
                    }
                }
                Some((i, regime, j, limit, counts, admit))
            })
            .collect();
        for (i, regime, j, limit, counts, admit) in results {
            // The boundary tile, as the gate judges it: rate, tightness and admitted
            // share; the limit tiles' rate.
            let rs = per_regime.entry(regime).or_default();
            rs.cases += 1;
            rs.admit_fraction += admit;
            rs.limit_tiles += counts.0 as u64;
            rs.limit_violations += counts.1 as u64;
            rs.violated += j.violated.values().any(|&mm| mm >= o.min_margin) as u64;
            for (k, &(n, t)) in &j.tight {
                let e = rs.tight.entry(k.clone()).or_default();
                (e.probed, e.tight) = (e.probed + n as u64, e.tight + t as u64);
            }
            // Count every kind violated in this case, over all its tiles.
            let mut all = j.clone();
            if let Some(l) = &limit {
                all.merge(l.clone());
            }
            if all.violated.values().any(|&mm| mm >= o.min_margin) {
                violated_cases += 1;
                let beyond = !beyond_kinds(regime, &all).is_empty();
                let tail = !tail_kinds(regime, &all).is_empty();
                beyond_cases += beyond as u64;
                tail_cases += (tail && !beyond) as u64;
                rs.tail += tail as u64;
                if o.expectations.is_some() {
                    for (k, &mm) in all.violated.iter().filter(|(_, &mm)| mm >= o.min_margin) {
                        let e = kinds.entry((regime, k.clone())).or_insert((0, 0.0));
                        *e = (e.0 + 1, e.1.max(mm));
                    }
                }
            }
            let f = match limit {
                Some(l) if !interesting(regime, &j) && interesting(regime, &l) => l,
                _ => j,
            };
            if !interesting(regime, &f) {
                continue;
            }
            let t_first = start.elapsed().as_secs_f64();
            let mut picks: Vec<(String, Option<(f64, String)>)> = Vec::new();
            if o.gate {
                picks.extend(beyond_kinds(regime, &f).into_iter().map(|(k, mm, why)| (k, Some((mm, why)))));
                picks.extend(tail_kinds(regime, &f).into_iter().map(|(k, mm, why)| (k, Some((mm, why)))));
            } else {
                picks.push((crate::judge::bound_kind(&f.violation.as_ref().unwrap().bound), None));
            }
            for (kind, beyond) in picks {
                if beyond_found(&found) >= o.max_found {
                    break;
                }
                let Some(w) = f.witness_of(&kind).cloned() else { continue };
                if !crate::cases::place::placed_in(cfg.viewport, &w.case, &w.tile) {
                    continue;
                }
                // One file per (regime, bound) is enough for a run; with the gate, one
                // per (regime, kind) beyond the signature; without it, a violation
                // beyond the signature is not hidden behind one inside it.
                let key = match &beyond {
                    Some(_) => (regime, kind.clone(), true),
                    None => {
                        let out = entry(regime).and_then(|e| e.beyond(&kind, w.margin)).is_some();
                        (regime, w.bound.clone(), out)
                    }
                };
                if !seen.insert(key) {
                    continue;
                }
                let (c, t, jj, steps) = match &beyond {
                    Some((mm, _)) => {
                        let (floor, e) = (0.5 * mm, entry(regime).expect("the gate has expectations"));
                        // beyond stays beyond; a tail finding stays out of the regime's cap
                        let was = e.place(&kind, *mm);
                        let keep = |j: &Judgement| {
                            j.violated.get(&kind).is_some_and(|&x| {
                                x >= floor
                                    && match e.place(&kind, x) {
                                        Place::Inside => false,
                                        Place::Tail => was == Place::Tail,
                                        Place::Beyond(_) => true,
                                    }
                            })
                        };
                        shrink_while(cfg, &m, w.case, w.tile, f.clone(), i, &keep)
                    }
                    None => shrink(cfg, &m, w.case, w.tile, f.clone(), i),
                };
                let w = match &beyond {
                    Some(_) => jj.witness_of(&kind),
                    None => jj.violation.as_ref(),
                }
                .expect("a violation")
                .clone();
                let kind = if beyond.is_some() { kind } else { crate::judge::bound_kind(&w.bound) };
                let margin = jj.violated.get(&kind).copied().unwrap_or(w.margin);
                let e = entry(regime);
                let place = e.as_ref().map_or(Place::Inside, |e| e.place(&kind, margin));
                let tail = o.gate && place == Place::Tail;
                let why = match (&place, &beyond) {
                    (Place::Beyond(why), _) => why.clone(),
                    (Place::Tail, Some((_, why))) => why.clone(),
                    _ => String::new(),
                };
                let cap = e.as_ref().and_then(|e| e.cap(&kind)).map(Cap);
                let note = if why.is_empty() {
                    String::new()
                } else {
                    let other = if crate::judge::bound_kind(&w.bound) != kind {
                        format!("; the stored witness is the case's worst ({})", w.bound)
                    } else {
                        String::new()
                    };
                    let stands = if tail { "in the tail of" } else { "beyond" };
                    format!(
                        "search: `{kind}` margin {margin:.3e} {stands} {id}'s signature in regime {} ({why}){other}",
                        regime.name()
                    )
                };
                let cf =
                    CaseFile::violation(id, (c, t), &w, cfg, ("search", i, regime.name().into()), steps.clone(), note);
                let file = match o.out {
                    Some(dir) => cf.write_new(dir)?.map(|p| p.display().to_string()),
                    None => None,
                };
                found.push(Found {
                    method: id.into(),
                    regime: regime.name().into(),
                    case_index: i,
                    seconds_to_first: t_first,
                    margin: w.margin,
                    bound: w.bound,
                    kind,
                    shrink_steps: steps,
                    file,
                    beyond_signature: !why.is_empty() && !tail,
                    cap,
                    signature: why,
                    tail,
                });
            }
        }
        pb.set_message(format!("{} cases, {} found", next, found.len()));
    }
    pb.finish_and_clear();
    let kinds = kinds
        .into_iter()
        .map(|((regime, kind), (cases, max_margin))| {
            let e = entry(regime).expect("counted only with expectations");
            KindSeen {
                regime: regime.name().into(),
                cap: e.cap(&kind).map(Cap),
                beyond_signature: e.beyond(&kind, max_margin).is_some(),
                kind,
                cases,
                max_margin,
            }
        })
        .collect();
    let mut breaches = Vec::new();
    let regimes: Vec<RegimeSeen> = per_regime
        .into_iter()
        .map(|(regime, mut seen)| {
            seen.regime = regime.name().into();
            if seen.cases > 0 {
                seen.admit_fraction /= seen.cases as f64;
            }
            if let Some(e) = entry(regime) {
                seen.max_tail_rate = e.tail_rate();
                seen.max_rate = e.max_rate;
                seen.max_boundary_rate = e.max_boundary_rate;
                seen.max_limit_rate = e.max_limit_rate;
                seen.max_admit = e.max_admit;
                if o.gate {
                    let lines = e
                        .rate_breach(seen.violated, seen.cases)
                        .into_iter()
                        .chain(e.boundary_rate_breach(seen.violated, seen.cases))
                        .chain(e.limit_rate_breach(seen.limit_violations, seen.limit_tiles))
                        .chain(e.looser(&seen.tight))
                        .chain(e.admit_breach(seen.admit_fraction, seen.cases));
                    breaches.extend(lines.map(|l| format!("regime {}: {l}", regime.name())));
                }
            }
            seen
        })
        .collect();
    if o.gate {
        let rows: Vec<(&Entry, &RegimeSeen)> = regimes
            .iter()
            .filter_map(|seen| {
                let r = Regime::ALL.into_iter().find(|r| r.name() == seen.regime)?;
                Some((entry(r)?, seen))
            })
            .collect();
        breaches.extend(pooled_looser(rows.iter().map(|(e, seen)| (*e, &seen.tight))).into_iter().map(|(_, l)| l));
        breaches.extend(crate::gate::expect::pooled_boundary_breach(
            rows.iter().map(|(e, seen)| (*e, seen.violated, seen.cases)),
        ));
        breaches
            .extend(crate::gate::expect::pooled_tail_breach(rows.iter().map(|(e, seen)| (*e, seen.tail, seen.cases))));
    }
    Ok(SearchReport {
        method: id.into(),
        seed: cfg.seed,
        cases: next,
        seconds: start.elapsed().as_secs_f64(),
        found,
        gate: o.gate,
        expectations: o.expectations.map(|(_, name)| name.to_string()),
        violated_cases,
        beyond_cases,
        tail_cases,
        kinds,
        regimes,
        breaches,
    })
}

fn fmt_cap(c: Option<Cap>) -> String {
    match c {
        None => "-".into(),
        Some(Cap(c)) if c.is_infinite() => "inf".into(),
        Some(Cap(c)) => format!("{c:e}"),
    }
}

/// The tail of a gated search against its rates (None: no tail rate, or no tail case).
fn tail_line(r: &SearchReport) -> Option<String> {
    let c = crate::gate::expect::TailCount::of(r.regimes.iter().map(|g| (g.max_tail_rate, g.tail, g.cases)));
    (c.cases > 0 && c.tail > 0).then(|| {
        format!(
            "tail: {} of {} cases violate a kind above their regime's cap, within the method's largest (the tail \
             rates allow {:.1})\n",
            c.tail, c.cases, c.allowed
        )
    })
}

/// The line that names one finding beyond the signature (or in its tail).
pub fn beyond_line(f: &Found) -> String {
    format!(
        "{}: {}, regime {}: `{}` margin {:.3e} {}{}",
        if f.tail { "in the tail" } else { "beyond the signature" },
        f.method,
        f.regime,
        f.kind,
        f.margin,
        f.signature,
        f.file.as_deref().map_or(String::new(), |p| format!(" (case file {p})"))
    )
}

/// The search's report as text: a line per finding; with the gate, the kinds of bound
/// seen per regime against the signature and a line per finding beyond it.
pub fn render_search(r: &SearchReport) -> String {
    let mut s = if r.gate {
        format!(
            "search {} --gate ({}): seed {}, {} cases in {:.1} s; {} case(s) violated, {} within the signature, {} in its tail, {} beyond it; {} finding(s) beyond the signature\n",
            r.method,
            r.expectations.as_deref().unwrap_or("-"),
            r.seed,
            r.cases,
            r.seconds,
            r.violated_cases,
            r.violated_cases - r.beyond_cases - r.tail_cases,
            r.tail_cases,
            r.beyond_cases,
            r.found.iter().filter(|f| !f.tail).count()
        )
    } else {
        format!(
            "search {}: seed {}, {} cases in {:.1} s, {} violation(s)\n",
            r.method,
            r.seed,
            r.cases,
            r.seconds,
            r.found.len()
        )
    };
    for f in &r.found {
        s += &format!(
            "  {:<15} case {:>6} after {:>6.2} s: {} by {:.3e}; shrunk: {}; {}{}\n",
            f.regime,
            f.case_index,
            f.seconds_to_first,
            f.bound,
            f.margin,
            if f.shrink_steps.is_empty() { "-".to_string() } else { f.shrink_steps.join(", ") },
            f.file
                .as_deref()
                .map_or("not written (already in the corpus or --dry-run)".to_string(), |p| format!("wrote {p}")),
            if f.beyond_signature && !r.gate {
                format!(" [beyond the signature: {}]", f.signature)
            } else {
                String::new()
            }
        );
    }
    if r.gate {
        if !r.kinds.is_empty() {
            s += &format!(
                "\nkinds of bound violated (all cases, before shrinking):\n  {:<15} {:<48} {:>7} {:>11} {:>9}  status\n",
                "regime", "kind", "cases", "max margin", "cap"
            );
            for k in &r.kinds {
                s += &format!(
                    "  {:<15} {:<48} {:>7} {:>11} {:>9}  {}\n",
                    k.regime,
                    k.kind,
                    k.cases,
                    if k.max_margin.is_infinite() { "inf".to_string() } else { format!("{:.3e}", k.max_margin) },
                    fmt_cap(k.cap),
                    if k.beyond_signature { "BEYOND" } else { "within" }
                );
            }
        }
        if !r.regimes.is_empty() {
            s += &format!(
                "\nper regime, as the gate judges them (boundary tiles; limit tiles at the method's own reject limit):\n  \
                 {:<15} {:>8} {:>9} {:>9} {:>12} {:>9} {:>7} {:>9}  tight ends (share)\n",
                "regime", "cases", "violated", "rate cap", "limit", "cap", "admit", "cap"
            );
            let cap = |c: Option<f64>| c.map_or("-".to_string(), |r| r.to_string());
            for g in &r.regimes {
                let tight: Vec<String> = g
                    .tight
                    .iter()
                    .filter(|(_, t)| t.probed > 0)
                    .map(|(k, t)| format!("{k} {:.2}", t.tight as f64 / t.probed as f64))
                    .collect();
                s += &format!(
                    "  {:<15} {:>8} {:>9} {:>9} {:>12} {:>9} {:>7.3} {:>9}  {}\n",
                    g.regime,
                    g.cases,
                    g.violated,
                    cap(g.max_boundary_rate.or(g.max_rate)),
                    format!("{}/{}", g.limit_violations, g.limit_tiles),
                    cap(g.max_limit_rate),
                    g.admit_fraction,
                    cap(g.max_admit),
                    if tight.is_empty() { "-".to_string() } else { tight.join(", ") }
                );
            }
        }
        if !r.found.is_empty() || !r.breaches.is_empty() {
            s += "\n";
        }
        for f in &r.found {
            s += &beyond_line(f);
            s += "\n";
        }
        if let Some(line) = tail_line(r) {
            s += &line;
        }
        for b in &r.breaches {
            s += &format!("beyond the signature: {}, {b}\n", r.method);
        }
    }
    s
}
