//! `corpus/expectations.json`: what the gate expects of each method in each regime.
//!
//! ```json
//! { "la2011": {
//!     "*": { "expect": "violation", "why": "f32 rounding ...",
//!            "bounds": { "u min": 1e-4, "t max": 1e-4 }, "max_rate": 0.3 },
//!     "far-from-origin": { "expect": "violation", "why": "...",
//!            "bounds": { "u min": 0.1, "tile culled": "inf" }, "max_rate": 0.6 } },
//!   "bbox": { "*": { "expect": "conservative",
//!            "unproven": { "max_rate": 0.01, "why": "..." } } } }
//! ```
//!
//! A method or regime not listed is expected conservative with no unproven case
//! allowed. An expected violation carries its **signature**: every kind of bound it may
//! violate (see [`crate::judge::bound_kind`]) with a cap on the margin, and the
//! largest share of cases that may show a violation. A violation of another kind, a
//! larger margin or a higher rate fails the gate: a new bug in a method already known
//! to be off is still caught. A cap is "inf" (any margin) for a culled covered tile
//! ("tile culled", "NaN interval end") and for a kind whose derivation fails outright:
//! a kind seen with a margin above [`GROSS_MARGIN`] in a long search, where the
//! margins reach the whole lens or shutter and no finite cap holds under a longer
//! search. Such a kind is still gated by its presence (a kind not listed fails), by
//! the rate and by the tightness signature.
//!
//! A regime with a `max_tail_rate` also has a **tail**: a kind above its cap (or not
//! listed there) but within the largest cap the method's other regimes expected violated
//! give it is counted, not failed, and the method's cases in the tail are held to that
//! rate over all its regimes ([`Place`], [`pooled_tail_breach`]). Rare large margins of a
//! kind the method already violates elsewhere have no stable largest value, but a stable
//! rate.

use crate::cases::generate::Regime;
use crate::io::num_or_inf;
use crate::io::quote::clip;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// A margin above which a kind of bound is no rounding slip (f32 rounding of these
/// quantities stays orders of magnitude below it, and it is ten times the gate's
/// smallest planted slip, 1e-3): its cap is "inf" when a search has seen one.
pub const GROSS_MARGIN: f64 = 1e-2;

/// What a method is expected to do in a regime.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Expected {
    Conservative,
    Violation,
    /// Reported, never failing (for exploration).
    Unknown,
}

/// The unproven cases an expected-conservative row may have, and why.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Allowance {
    pub max_rate: f64,
    pub why: String,
}

impl Allowance {
    /// How many of `n` cases may be unproven under a share `rate`: `rate n` plus the
    /// counting noise of a row of n cases (three binomial standard deviations, plus 2
    /// for tiny rows), as for an expected violation's rate. No allowance (rate 0)
    /// allows none: a row expected conservative with no stated allowance must prove
    /// every case.
    pub fn cases_allowed(rate: f64, n: u64) -> f64 {
        if rate <= 0.0 {
            return 0.0;
        }
        let n = n as f64;
        rate * n + 3.0 * (rate * (1.0 - rate) * n).sqrt() + 2.0
    }
}

/// A cap on one kind of bound's margin ("inf" in JSON for a culled covered tile).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Cap(#[serde(with = "num_or_inf")] pub f64);

/// One expectation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Entry {
    pub expect: Expected,
    #[serde(default)]
    pub why: String,
    /// For an expected violation: each bound kind it may violate, with the largest
    /// margin allowed.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub bounds: BTreeMap<String, Cap>,
    /// For an expected violation: the largest share of cases with a violation (a row
    /// of n cases fails above `max_rate n + 3 sqrt(max_rate (1 - max_rate) n) + 2`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_rate: Option<f64>,
    /// For an expected violation, held by `search --gate` only: the largest share of
    /// the search's cases whose boundary tile shows a violation (the search judges
    /// the limit tiles of every case, the gate of one case in twelve, so `max_rate`,
    /// written for the gate's rows, cannot say it). Measured by a long gated search of
    /// the clean method: a slip that adds violations of kinds and margins the
    /// signature allows (ends pulled in by a rounding) shows here.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_boundary_rate: Option<f64>,
    /// For an expected violation: the largest share of the tiles judged at the
    /// method's own tile-reject limit that may show a violation (same counting noise
    /// as `max_rate`). A slip that makes the reject limit cull covered tiles more
    /// often leaves this share even when every culled tile is a kind the signature
    /// lists. Held only at the settings it was measured at
    /// ([`super::settings::Settings::measured`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_limit_rate: Option<f64>,
    /// The largest mean share of the boundary tile's uniform samples the answers may
    /// admit (intervals and constraints together; see [`super::row::Row::admit_fraction`]).
    /// A method that stops narrowing (a dropped term that makes it cull nothing) admits
    /// more than its signature allows, though it violates nothing and has no narrowed
    /// end left to probe for tightness. Held only at the settings it was
    /// measured at ([`super::settings::Settings::measured`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_admit: Option<f64>,
    /// For an expected violation: the **tail**, the largest share of the method's cases
    /// (summed over its regimes that state one) that may violate a kind of bound beyond
    /// this regime's cap but within the largest cap any of the method's regimes expected
    /// violated gives that kind (see [`Place::Tail`]). Measured from long gated searches:
    /// such findings are rare (about one case in 10^4) and their margins are unbounded,
    /// so a cap on their count holds under longer searches where a cap on their margin
    /// never did. None: no tail is allowed, and such a kind is beyond the signature.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_tail_rate: Option<f64>,
    /// Derived when the entry is looked up ([`Expectations::entry`]), never read from a
    /// file: per kind, the largest cap the method's regimes expected violated give it
    /// (the reach of the tail). Empty without `max_tail_rate`.
    #[serde(skip)]
    pub tail_caps: BTreeMap<String, Cap>,
    /// Unproven cases allowed (for an expected-conservative row; none by default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unproven: Option<Allowance>,
    /// The tightness signature: per interval end kind ("u min", ..., "t max"), the least
    /// share of the row's proven ends that have a covered sample within
    /// [`crate::judge::tile::TIGHT_DELTA`] of them. A loosened answer leaves its signature
    /// here at any seed and case count, as a new violation kind does.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub tight: BTreeMap<String, f64>,
    /// The gated searches (`search --gate`) this row's signature was held against:
    /// widened from (kinds added, caps raised) or survived unchanged.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub searched: Vec<Searched>,
}

/// One gated search a signature was held against.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Searched {
    pub seed: u64,
    /// The search's length.
    pub seconds: f64,
    /// Cases of this regime the search judged.
    pub cases: u64,
    /// "widened" (the signature was widened from this search), "held" (nothing
    /// beyond it was found) or "tail" (cases in the method's tail, counted against its
    /// tail rate, nothing beyond).
    pub outcome: String,
}

/// Proven interval ends of one kind probed for tightness, and how many were tight.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct TightStat {
    pub probed: u64,
    pub tight: u64,
}

/// The fewest tight ends a signature allows: the expected count `mean` (the least share
/// times the ends probed, summed over rows when pooled) less three binomial standard
/// deviations (`var` the summed variances) and 2 for small counts. A loosened answer
/// has no tight end at all, so it fails wherever this is above 0.
pub fn least_tight(mean: f64, var: f64) -> f64 {
    mean - 3.0 * var.sqrt() - 2.0
}

impl Entry {
    pub fn conservative() -> Self {
        Entry {
            expect: Expected::Conservative,
            why: String::new(),
            bounds: BTreeMap::new(),
            max_rate: None,
            max_boundary_rate: None,
            max_limit_rate: None,
            max_admit: None,
            max_tail_rate: None,
            tail_caps: BTreeMap::new(),
            unproven: None,
            tight: BTreeMap::new(),
            searched: Vec::new(),
        }
    }

    /// This entry as it holds for a run: without its measured parts (the boundary-
    /// and limit-tile rate caps and the admit cap) when the run's settings are not those they were
    /// measured at (`measured` false, see [`super::settings::Settings::measured`]).
    pub fn scoped(mut self, measured: bool) -> Self {
        if !measured {
            self.max_boundary_rate = None;
            self.max_limit_rate = None;
            self.max_admit = None;
        }
        self
    }

    /// A share cap `cap` against `hits` of `n` (cases or tiles), with the counting noise
    /// of [`Entry::rate_breach`]; the line names `what` was hit.
    fn share_breach(cap: Option<f64>, what: &str, hits: u64, n: u64) -> Option<String> {
        let r = cap?;
        (n > 0 && hits as f64 > Allowance::cases_allowed(r, n))
            .then(|| format!("{what} violated {hits}/{n} = {:.3} above the cap {r}", hits as f64 / n as f64))
    }

    /// The search's boundary-tile rate cap against `violated` of `cases`.
    pub fn boundary_rate_breach(&self, violated: u64, cases: u64) -> Option<String> {
        Self::share_breach(self.max_boundary_rate, "boundary tiles", violated, cases)
    }

    /// The limit-tile rate cap against `violations` of `tiles` judged at the method's
    /// own tile-reject limit.
    pub fn limit_rate_breach(&self, violations: u64, tiles: u64) -> Option<String> {
        Self::share_breach(self.max_limit_rate, "limit tiles", violations, tiles)
    }

    /// The admit cap against the mean admitted share `mean` of `cases` boundary tiles:
    /// each case's share lies in [0, 1], so its variance is at most `c (1 - c)` for a
    /// mean `c`; the mean may exceed the cap by three standard deviations of a mean of
    /// `cases` such shares, plus `2 / cases` for tiny rows.
    pub fn admit_breach(&self, mean: f64, cases: u64) -> Option<String> {
        let c = self.max_admit?;
        let n = cases as f64;
        let allowed = c + 3.0 * (c * (1.0 - c) / n).sqrt() + 2.0 / n;
        (cases > 0 && mean > allowed).then(|| {
            format!(
                "looser: the answers admit {:.1} % of the boundary tiles' samples on average, the signature at most \
                 {:.1} %",
                100.0 * mean,
                100.0 * c
            )
        })
    }
    /// Where a row's tightness leaves the signature: one line per end kind whose tight
    /// ends fall below the least share, beyond counting noise (see [`least_tight`]).
    pub fn looser(&self, tight: &BTreeMap<String, TightStat>) -> Vec<String> {
        let mut out = Vec::new();
        for (kind, &p) in &self.tight {
            let Some(s) = tight.get(kind) else { continue };
            let n = s.probed as f64;
            if s.probed > 0 && (s.tight as f64) < least_tight(p * n, p * (1.0 - p) * n) {
                out.push(format!(
                    "looser: `{kind}` has a covered sample within {:.1e} in {} of {} proven ends ({:.0} %; the \
                     signature says at least {:.0} %)",
                    crate::judge::tile::TIGHT_DELTA,
                    s.tight,
                    s.probed,
                    100.0 * s.tight as f64 / n,
                    100.0 * p
                ));
            }
        }
        out
    }
    /// The cap on one kind of bound's margin (None: the kind is not listed, or the
    /// regime is not an expected violation).
    pub fn cap(&self, kind: &str) -> Option<f64> {
        match self.expect {
            Expected::Violation => self.bounds.get(kind).map(|c| c.0),
            _ => None,
        }
    }

    /// Where one violated bound kind, with the margin it needs, stands against this
    /// signature: inside it (or a regime that is not gated), in the method's tail, or
    /// beyond it, with why: "not in the signature", "above the cap 5e-5", or "in a
    /// regime expected conservative" (where any violation is beyond).
    pub fn place(&self, kind: &str, margin: f64) -> Place {
        match self.expect {
            Expected::Unknown => Place::Inside,
            Expected::Conservative => Place::Beyond("in a regime expected conservative".into()),
            Expected::Violation => {
                let cap = self.bounds.get(kind).map(|c| c.0);
                if cap.is_some_and(|c| margin <= c) {
                    return Place::Inside;
                }
                let tail = self.tail_rate().and(self.tail_caps.get(kind)).map(|c| c.0);
                if tail.is_some_and(|t| margin <= t) {
                    return Place::Tail;
                }
                let beyond_tail = match tail {
                    Some(t) => format!(" (and the method's largest cap {t:e})"),
                    None => String::new(),
                };
                Place::Beyond(match cap {
                    None => format!("not in the signature{beyond_tail}"),
                    Some(c) => format!("above the cap {c:e}{beyond_tail}"),
                })
            }
        }
    }

    /// The tail rate this entry holds (an expected violation's `max_tail_rate`; None
    /// for any other entry).
    pub fn tail_rate(&self) -> Option<f64> {
        self.max_tail_rate.filter(|_| self.expect == Expected::Violation)
    }

    /// [`Entry::place`] when it is beyond: why; None inside the signature or in its tail.
    pub fn beyond(&self, kind: &str, margin: f64) -> Option<String> {
        match self.place(kind, margin) {
            Place::Beyond(why) => Some(why),
            _ => None,
        }
    }

    /// Whether a judgement's violated kinds put its case in the method's tail (some kind
    /// lies there, whatever the others do).
    pub fn in_tail<'k>(&self, violated: impl IntoIterator<Item = (&'k String, &'k f64)>) -> bool {
        violated.into_iter().any(|(k, &m)| self.place(k, m) == Place::Tail)
    }

    /// The rate cap against `violations` of `cases`: a row of n cases may exceed
    /// `max_rate n` by counting noise (three binomial standard deviations, plus 2 for
    /// tiny rows); beyond that, a line saying so.
    pub fn rate_breach(&self, violations: u64, cases: u64) -> Option<String> {
        let r = self.max_rate?;
        let n = cases as f64;
        let allowed = r * n + 3.0 * (r * (1.0 - r) * n).sqrt() + 2.0;
        (cases > 0 && violations as f64 > allowed).then(|| {
            format!("violation rate {violations}/{cases} = {:.3} above the cap {r}", violations as f64 / cases as f64)
        })
    }

    /// Where this row's violations leave the signature: one line per breach.
    pub fn breaches(&self, violated: &BTreeMap<String, (u64, f64)>, violations: u64, cases: u64) -> Vec<String> {
        let mut out = Vec::new();
        for (kind, &(n, m)) in violated {
            if self.beyond(kind, m).is_none() {
                continue;
            }
            match self.bounds.get(kind) {
                None => out
                    .push(format!("violates `{kind}` ({n} cases, margin {m:.3e}), which the signature does not list")),
                Some(Cap(cap)) => out.push(format!("`{kind}` margin {m:.3e} above the cap {cap:.3e}")),
            }
        }
        out.extend(self.rate_breach(violations, cases));
        out
    }
}

/// The tightness signature over several rows of one method at once: per end kind, the
/// tight ends of every row whose signature has a least share for that kind, against
/// the sum of those shares times the ends probed (one binomial test over the pooled
/// rows, see [`least_tight`]). A row holds too few ends to see a loosening at small
/// case counts; the rows together do. Returns each failing kind with its line.
pub fn pooled_looser<'a>(
    rows: impl IntoIterator<Item = (&'a Entry, &'a BTreeMap<String, TightStat>)>,
) -> Vec<(String, String)> {
    let mut pools: BTreeMap<String, (f64, f64, u64, u64)> = BTreeMap::new();
    for (entry, tight) in rows {
        for (kind, &p) in &entry.tight {
            let Some(s) = tight.get(kind) else { continue };
            let e = pools.entry(kind.clone()).or_default();
            let n = s.probed as f64;
            e.0 += p * n;
            e.1 += p * (1.0 - p) * n;
            e.2 += s.probed;
            e.3 += s.tight;
        }
    }
    pools
        .into_iter()
        .filter(|(_, (mean, var, probed, tight))| *probed > 0 && (*tight as f64) < least_tight(*mean, *var))
        .map(|(kind, (mean, _, probed, tight))| {
            let line = format!(
                "looser over all regimes: `{kind}` has a covered sample within {:.1e} in {tight} of {probed} proven \
                 ends (the signatures expect about {:.0})",
                crate::judge::tile::TIGHT_DELTA,
                mean
            );
            (kind, line)
        })
        .collect()
}

/// The search's boundary-tile rate over several regimes of one method at once: the
/// violated cases of every regime whose signature has a `max_boundary_rate`, against
/// the sum of those caps times the cases (counting noise summed as for one row, see
/// [`Allowance::cases_allowed`]). A slip that adds a few violations in every regime
/// stays inside each regime's noise and leaves the pooled count. None within it.
pub fn pooled_boundary_breach<'a>(rows: impl IntoIterator<Item = (&'a Entry, u64, u64)>) -> Option<String> {
    let (mut mean, mut var, mut violated, mut cases) = (0.0f64, 0.0f64, 0u64, 0u64);
    for (e, v, n) in rows {
        let Some(r) = e.max_boundary_rate else { continue };
        mean += r * n as f64;
        var += r * (1.0 - r) * n as f64;
        violated += v;
        cases += n;
    }
    let allowed = mean + 3.0 * var.sqrt() + 2.0;
    (cases > 0 && violated as f64 > allowed).then(|| {
        format!(
            "boundary tiles violated over all regimes with a cap: {violated} of {cases} cases, the caps allow about \
             {mean:.0} (at most {allowed:.0} with counting noise)"
        )
    })
}

/// Where a violated kind of bound stands against a regime's signature.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Place {
    /// Within the regime's cap (or the regime is not gated).
    Inside,
    /// Above the regime's cap (or not listed there) but within the largest cap the
    /// method's regimes expected violated give the kind, where the regime states a
    /// `max_tail_rate`: counted, and held to that rate over all of the method's cases.
    Tail,
    /// Beyond the signature, with why.
    Beyond(String),
}

/// The tail of one method over its regimes: the cases with a kind in the tail
/// ([`Place::Tail`]) of every regime that states a `max_tail_rate`, the cases of those
/// regimes, and how many the rates allow: the sum of the rates times the regimes' cases
/// with the counting noise of [`Allowance::cases_allowed`] summed as for one row.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TailCount {
    pub tail: u64,
    pub cases: u64,
    pub allowed: f64,
}

impl TailCount {
    /// Rows `(tail rate, cases in the tail, cases judged)` of one method; a row without
    /// a rate counts nothing.
    pub fn of(rows: impl IntoIterator<Item = (Option<f64>, u64, u64)>) -> TailCount {
        let (mut mean, mut var, mut tail, mut cases) = (0.0f64, 0.0f64, 0u64, 0u64);
        for (rate, t, n) in rows {
            let Some(r) = rate else { continue };
            mean += r * n as f64;
            var += r * (1.0 - r) * n as f64;
            tail += t;
            cases += n;
        }
        TailCount { tail, cases, allowed: mean + 3.0 * var.sqrt() + 2.0 }
    }
}

/// The tail over all regimes of one method ([`TailCount`]); a line when its cases pass
/// what the rates allow, None within it.
pub fn pooled_tail_breach<'a>(rows: impl IntoIterator<Item = (&'a Entry, u64, u64)>) -> Option<String> {
    let rates = rows.into_iter().map(|(e, t, n)| (e.tail_rate(), t, n));
    let TailCount { tail, cases, allowed } = TailCount::of(rates);
    (cases > 0 && tail as f64 > allowed).then(|| {
        format!(
            "tail: {tail} of {cases} cases violate a kind above their regime's cap (within the method's largest), the \
             tail rates allow at most {allowed:.1} with counting noise"
        )
    })
}

/// Per method id, per regime name (or `*` for every regime not listed).
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Expectations(pub BTreeMap<String, BTreeMap<String, Entry>>);

impl Expectations {
    /// Load from a file; an error names the file, the method, the regime and the field.
    /// `known` says which method ids exist.
    pub fn load_with(path: &Path, known: &dyn Fn(&str) -> bool) -> anyhow::Result<Self> {
        let text =
            std::fs::read_to_string(path).map_err(|e| anyhow::anyhow!("{}: cannot read: {e}", path.display()))?;
        Self::parse_with(&text, &path.display().to_string(), known)
    }

    /// Parse the text of an expectations file; `name` (the file, or what the text is)
    /// starts every error, which then names the method, the regime and the field.
    pub fn parse_with(text: &str, name: &str, known: &dyn Fn(&str) -> bool) -> anyhow::Result<Self> {
        let raw: BTreeMap<String, BTreeMap<String, serde_json::Value>> = serde_json::from_str(text)
            .map_err(|e| anyhow::anyhow!("{name}: not an expectations file: {}", clip(&e.to_string())))?;
        let mut out = BTreeMap::new();
        for (m, regimes) in raw {
            if !known(&m) {
                anyhow::bail!("{name}: method `{}` is not a known method id (see `cullproof methods`; a plugin's id needs `--plugin LIB.so`)", clip(&m));
            }
            let mut rows = BTreeMap::new();
            for (r, v) in regimes {
                let at = format!("{name}: method `{m}`, regime `{}`", clip(&r));
                if r != "*" && !Regime::ALL.iter().any(|x| x.name() == r) {
                    anyhow::bail!("{at}: not a known regime");
                }
                // A bare status, or the whole object (whose errors name the field).
                let e = if v.is_string() {
                    match serde_json::from_value::<Expected>(v) {
                        Ok(e) => Entry { expect: e, ..Entry::conservative() },
                        Err(err) => anyhow::bail!("{at}: {}", clip(&err.to_string())),
                    }
                } else {
                    match serde_path_to_error::deserialize::<_, Entry>(v) {
                        Ok(e) => e,
                        Err(err) => {
                            let (field, why) = (err.path().to_string(), err.inner().to_string());
                            anyhow::bail!("{at}: field `{}`: {}", clip(&field), clip(&why))
                        }
                    }
                };
                Self::validate(&e).map_err(|why| anyhow::anyhow!("{at}: {why}"))?;
                rows.insert(r, e);
            }
            out.insert(m, rows);
        }
        Ok(Expectations(out))
    }

    /// Load from a file, for the built-in methods.
    pub fn load(path: &Path) -> anyhow::Result<Self> {
        Self::load_with(path, &|m| crate::bounds::by_id(m).is_some())
    }

    fn validate(e: &Entry) -> Result<(), String> {
        const ENDS: [&str; 6] = ["u min", "u max", "v min", "v max", "t min", "t max"];
        for (kind, &p) in &e.tight {
            if !ENDS.contains(&kind.as_str()) {
                return Err(format!("field `tight.{}`: not an interval end (one of {})", clip(kind), ENDS.join(", ")));
            }
            if !(0.0..=1.0).contains(&p) {
                return Err(format!("field `tight.{kind}` = {p}: a share of proven ends in [0, 1]"));
            }
        }
        if let Some(a) = &e.unproven {
            if !(0.0..=1.0).contains(&a.max_rate) {
                return Err(format!("field `unproven.max_rate` = {}: a share of cases in [0, 1]", a.max_rate));
            }
            if a.why.trim().is_empty() {
                return Err("field `unproven.why`: an allowance for unproven cases needs its reason".into());
            }
        }
        let shares = [
            ("max_boundary_rate", e.max_boundary_rate),
            ("max_limit_rate", e.max_limit_rate),
            ("max_admit", e.max_admit),
            ("max_tail_rate", e.max_tail_rate),
        ];
        for (field, v) in shares {
            if let Some(v) = v.filter(|v| !(0.0..=1.0).contains(v)) {
                return Err(format!("field `{field}` = {v}: a share in [0, 1]"));
            }
        }
        if e.expect != Expected::Violation {
            if !e.bounds.is_empty()
                || e.max_rate.is_some()
                || e.max_limit_rate.is_some()
                || e.max_boundary_rate.is_some()
                || e.max_tail_rate.is_some()
            {
                return Err(
                    "fields `bounds`, `max_rate`, `max_boundary_rate`, `max_limit_rate` and `max_tail_rate` belong to an \
                     expected violation"
                        .into(),
                );
            }
            return Ok(());
        }
        if e.why.trim().is_empty() {
            return Err("field `why`: an expected violation needs its reason".into());
        }
        if e.bounds.is_empty() {
            return Err("field `bounds`: an expected violation lists the bounds it violates, each with a cap".into());
        }
        for (k, Cap(c)) in &e.bounds {
            if c.is_nan() || *c <= 0.0 {
                return Err(format!(
                    "field `bounds.{}` = {c}: a cap is a margin > 0 (\"inf\": any margin, for a culled covered tile or a kind whose derivation fails outright)",
                    clip(k)
                ));
            }
        }
        match e.max_rate {
            Some(r) if r > 0.0 && r <= 1.0 => Ok(()),
            Some(r) => Err(format!("field `max_rate` = {r}: a share of cases in (0, 1]")),
            None => Err("field `max_rate`: an expected violation caps its rate".into()),
        }
    }

    /// The entry for a method in a regime (expected conservative when not listed). A
    /// deliberately broken variant is held to the expectations of the method it breaks.
    /// With a `max_tail_rate`, the entry's `tail_caps` are filled in: per kind, the
    /// largest cap over the method's regimes expected violated.
    pub fn entry(&self, method: &str, regime: &str) -> Entry {
        let method = crate::bounds::broken::inner_id(method);
        let Some(m) = self.0.get(method) else { return Entry::conservative() };
        let Some(mut e) = m.get(regime).or_else(|| m.get("*")).cloned() else { return Entry::conservative() };
        if e.expect == Expected::Violation && e.max_tail_rate.is_some() {
            for other in m.values().filter(|o| o.expect == Expected::Violation) {
                for (k, c) in &other.bounds {
                    let t = e.tail_caps.entry(k.clone()).or_insert(*c);
                    t.0 = t.0.max(c.0);
                }
            }
        }
        e
    }

    pub fn get(&self, method: &str, regime: &str) -> Expected {
        self.entry(method, regime).expect
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(text: &str) -> std::path::PathBuf {
        let p = std::env::temp_dir().join(format!("cullproof-ex-{}-{}.json", std::process::id(), text.len()));
        std::fs::write(&p, text).unwrap();
        p
    }

    fn load(text: &str) -> anyhow::Result<Expectations> {
        let p = write(text);
        let r = Expectations::load_with(&p, &|m| m == "m");
        std::fs::remove_file(&p).ok();
        r
    }

    #[test]
    fn an_allowance_admits_counting_noise_and_no_allowance_admits_nothing() {
        assert_eq!(Allowance::cases_allowed(0.0, 600), 0.0);
        // 0.092 of 9 cases: 0.83 expected, noise lets 1 through (a small row), not 6.
        let a = Allowance::cases_allowed(0.092, 9);
        assert!((1.0..6.0).contains(&a), "{a}");
        // On 600 cases the noise is small against the rate.
        let a = Allowance::cases_allowed(0.1, 600);
        assert!(a > 60.0 && a < 60.0 + 25.0, "{a}");
    }

    #[test]
    fn an_expected_violation_needs_its_signature() {
        let e = load(r#"{"m": {"*": {"expect": "violation", "why": "w", "max_rate": 0.1}}}"#).unwrap_err().to_string();
        assert!(e.contains("`bounds`") && e.contains("regime `*`"), "{e}");
        let e = load(r#"{"m": {"*": {"expect": "violation", "why": "w", "bounds": {"u min": 1e-4}}}}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("max_rate"), "{e}");
        let e = load(r#"{"m": {"*": {"expect": "violation", "why": "w", "bounds": {"u min": 0}, "max_rate": 0.1}}}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("bounds.u min") && e.contains("> 0"), "{e}");
        // "inf": any margin (a kind whose derivation fails outright).
        load(r#"{"m": {"*": {"expect": "violation", "why": "w", "bounds": {"u min": "inf"}, "max_rate": 0.1}}}"#)
            .unwrap();
        let e = load(r#"{"m": {"*": {"expect": "violation", "bounds": {"u min": 1e-4}, "max_rate": 0.1}}}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("`why`"), "{e}");
        let e = load(r#"{"m": {"static": {"expect": "conservative", "unproven": {"max_rate": 2, "why": "x"}}}}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("unproven.max_rate") && e.contains("regime `static`"), "{e}");
        let e = load(r#"{"m": {"static": {"expect": "conservative", "bogus": 1}}}"#).unwrap_err().to_string();
        assert!(e.contains("bogus") || e.contains("unknown"), "{e}");
        let e = load(r#"{"q": {"*": "conservative"}}"#).unwrap_err().to_string();
        assert!(e.contains("`q`"), "{e}");
        let ok = load(
            r#"{"m": {"*": "conservative", "tiny": {"expect": "violation", "why": "w", "bounds": {"tile culled": "inf", "u min": 1e-4}, "max_rate": 0.1}}}"#,
        )
        .unwrap();
        assert_eq!(ok.get("m", "tiny"), Expected::Violation);
        assert_eq!(ok.get("m", "static"), Expected::Conservative);
        assert_eq!(ok.get("other", "static"), Expected::Conservative);
    }

    #[test]
    fn looser_counts_tight_ends_against_the_least_share() {
        let e = Entry { tight: [("t max".to_string(), 0.3)].into(), ..Entry::conservative() };
        let row = |probed, tight| -> BTreeMap<String, TightStat> {
            [("t max".to_string(), TightStat { probed, tight })].into()
        };
        // 30 % of 200 is 60; three deviations (19.4) and 2 below that still pass
        assert!(e.looser(&row(200, 40)).is_empty());
        let b = e.looser(&row(200, 30));
        assert!(b.len() == 1 && b[0].contains("`t max`") && b[0].contains("30 of 200"), "{b:?}");
        // a loosened end has none; a small row cannot tell
        assert_eq!(e.looser(&row(200, 0)).len(), 1);
        assert!(e.looser(&row(10, 0)).is_empty());
        // kinds without a signature, and kinds not probed, say nothing
        assert!(e.looser(&[("u min".to_string(), TightStat { probed: 500, tight: 0 })].into()).is_empty());
    }

    #[test]
    fn the_limit_rate_and_the_admitted_share_have_caps_with_counting_noise() {
        let e = Entry {
            max_boundary_rate: Some(0.1),
            max_limit_rate: Some(0.1),
            max_admit: Some(0.6),
            ..Entry::conservative()
        };
        assert_eq!(e.boundary_rate_breach(21, 100), None);
        assert!(e.boundary_rate_breach(22, 100).unwrap().contains("boundary tiles violated 22/100"));
        // 100 limit tiles at a cap of 0.1: 10 + 3 * 3 + 2 = 21 allowed.
        assert_eq!(e.limit_rate_breach(21, 100), None);
        let line = e.limit_rate_breach(22, 100).unwrap();
        assert!(line.contains("22/100") && line.contains("above the cap 0.1"), "{line}");
        assert_eq!(e.limit_rate_breach(0, 0), None);
        // 600 cases at a cap of 0.6: 0.6 + 3 * 0.02 + 2 / 600 = 0.6633 allowed.
        assert_eq!(e.admit_breach(0.66, 600), None);
        let line = e.admit_breach(0.67, 600).unwrap();
        assert!(line.starts_with("looser: the answers admit 67.0 %") && line.contains("at most 60.0 %"), "{line}");
        // Neither cap holds at settings they were not measured at.
        let off = e.clone().scoped(false);
        assert_eq!((off.limit_rate_breach(100, 100), off.admit_breach(1.0, 600)), (None, None));
        assert_eq!(off.boundary_rate_breach(100, 100), None);
        assert_eq!(e.clone().scoped(true), e);
        // Without a cap, nothing is held.
        let none = Entry::conservative();
        assert_eq!((none.limit_rate_breach(100, 100), none.admit_breach(1.0, 600)), (None, None));
    }

    #[test]
    fn the_pooled_boundary_rate_sees_what_each_regime_hides() {
        let e = Entry { max_boundary_rate: Some(0.4), ..Entry::conservative() };
        let none = Entry::conservative();
        // 16 regimes of 200 cases, each 92 violated: within each regime's noise
        // (80 + 20.8 + 2), beyond the pooled count (1280 + 83.1 + 2).
        assert_eq!(e.boundary_rate_breach(92, 200), None);
        let rows: Vec<(&Entry, u64, u64)> = (0..16).map(|_| (&e, 92, 200)).collect();
        let line = pooled_boundary_breach(rows).unwrap();
        assert!(line.contains("1472 of 3200 cases"), "{line}");
        // At the cap everywhere, or where no regime has a cap: nothing.
        assert_eq!(pooled_boundary_breach((0..16).map(|_| (&e, 80, 200))), None);
        assert_eq!(pooled_boundary_breach((0..16).map(|_| (&none, 200, 200))), None);
    }

    #[test]
    fn measured_caps_are_shares_and_the_limit_rate_belongs_to_a_violation() {
        let err = load(r#"{"m": {"*": {"expect": "conservative", "max_admit": 1.5}}}"#).unwrap_err().to_string();
        assert!(err.contains("field `max_admit` = 1.5: a share in [0, 1]"), "{err}");
        let err = load(r#"{"m": {"*": {"expect": "conservative", "max_limit_rate": 0.1}}}"#).unwrap_err().to_string();
        assert!(err.contains("`max_limit_rate`") && err.contains("belong to an expected violation"), "{err}");
        let ok = load(r#"{"m": {"*": {"expect": "conservative", "max_admit": 0.5}}}"#).unwrap();
        assert_eq!(ok.entry("m", "static").max_admit, Some(0.5));
    }

    #[test]
    fn breaches_name_the_kind_the_margin_and_the_rate() {
        let e = Entry {
            expect: Expected::Violation,
            why: "w".into(),
            bounds: [("u min".to_string(), Cap(1e-4)), ("tile culled".to_string(), Cap(f64::INFINITY))].into(),
            max_rate: Some(0.1),
            ..Entry::conservative()
        };
        let stats = |v: &[(&str, u64, f64)]| v.iter().map(|(k, n, m)| (k.to_string(), (*n, *m))).collect();
        assert!(e.breaches(&stats(&[("u min", 3, 5e-5), ("tile culled", 1, f64::INFINITY)]), 4, 100).is_empty());
        let b = e.breaches(&stats(&[("u min", 3, 2e-4)]), 3, 100);
        assert!(b.len() == 1 && b[0].contains("above the cap"), "{b:?}");
        let b = e.breaches(&stats(&[("t max", 1, 1e-9)]), 1, 100);
        assert!(b.len() == 1 && b[0].contains("`t max`"), "{b:?}");
        assert!(e.breaches(&stats(&[("u min", 11, 1e-5)]), 11, 100).is_empty(), "within counting noise");
        let b = e.breaches(&stats(&[("u min", 25, 1e-5)]), 25, 100);
        assert!(b.len() == 1 && b[0].contains("rate"), "{b:?}");
    }

    #[test]
    fn one_kind_is_judged_against_the_signature() {
        let e = Entry {
            expect: Expected::Violation,
            why: "w".into(),
            bounds: [("u min".to_string(), Cap(5e-5)), ("tile culled".to_string(), Cap(f64::INFINITY))].into(),
            max_rate: Some(0.1),
            ..Entry::conservative()
        };
        assert_eq!(e.beyond("u min", 5e-5), None);
        assert_eq!(e.beyond("u min", 1.94e-4).as_deref(), Some("above the cap 5e-5"));
        assert_eq!(e.beyond("v max", 1e-9).as_deref(), Some("not in the signature"));
        assert_eq!(e.beyond("tile culled", f64::INFINITY), None);
        assert_eq!((e.cap("u min"), e.cap("v max")), (Some(5e-5), None));
        let c = Entry::conservative();
        assert!(c.beyond("u min", 1e-12).is_some_and(|w| w.contains("conservative")));
        assert_eq!(c.cap("u min"), None);
        assert_eq!(Entry { expect: Expected::Unknown, ..Entry::conservative() }.beyond("u min", 1.0), None);
    }

    #[test]
    fn a_kind_above_its_regime_cap_is_in_the_tail_up_to_the_methods_largest_cap() {
        let text = r#"{"m": {
            "tiny": {"expect": "violation", "why": "w", "bounds": {"u min": 1e-4, "t max": "inf"}, "max_rate": 0.5,
                     "max_tail_rate": 0.001},
            "huge": {"expect": "violation", "why": "w", "bounds": {"u min": 0.3, "v max": 2e-3}, "max_rate": 0.5,
                     "max_tail_rate": 0.001},
            "sliver": {"expect": "violation", "why": "w", "bounds": {"u min": "inf"}, "max_rate": 0.5},
            "static": "conservative"}}"#;
        let ex = load(text).unwrap();
        let tiny = ex.entry("m", "tiny");
        assert_eq!(tiny.place("u min", 1e-4), Place::Inside);
        // above tiny's cap, within sliver's inf and huge's 0.3
        assert_eq!(tiny.place("u min", 1.5), Place::Tail);
        // not listed in tiny, listed in huge
        assert_eq!(tiny.place("v max", 1e-3), Place::Tail);
        let why = tiny.beyond("v max", 3e-3).unwrap();
        assert!(why.contains("not in the signature") && why.contains("largest cap 2e-3"), "{why}");
        // a kind no regime lists
        assert_eq!(tiny.beyond("v min", 1e-9).as_deref(), Some("not in the signature"));
        // no tail rate: no tail
        let sliver = ex.entry("m", "sliver");
        assert!(sliver.tail_caps.is_empty());
        assert_eq!(sliver.beyond("t max", 1e-3).as_deref(), Some("not in the signature"));
        // a regime expected conservative has none
        assert!(ex.entry("m", "static").beyond("u min", 1e-9).unwrap().contains("conservative"));
        // a row's breaches leave the tail out: the pooled count holds it
        let stats: BTreeMap<String, (u64, f64)> = [("u min".to_string(), (3, 1.5))].into();
        assert!(tiny.breaches(&stats, 3, 100).is_empty());
        let stats: BTreeMap<String, (u64, f64)> = [("v max".to_string(), (3, 0.5))].into();
        assert_eq!(tiny.breaches(&stats, 3, 100).len(), 1);
        assert!(tiny.in_tail(&BTreeMap::from([("u min".to_string(), 1.0), ("t max".to_string(), 0.1)])));
        assert!(!tiny.in_tail(&BTreeMap::from([("u min".to_string(), 1e-5)])));
        // the derived caps are never read from a file
        let e = load(
            r#"{"m": {"*": {"expect": "violation", "why": "w", "bounds": {"u min": 1}, "max_rate": 0.1,
                "tail_caps": {"u min": 2}}}}"#,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("tail_caps"), "{e}");
        let e = load(r#"{"m": {"*": {"expect": "conservative", "max_tail_rate": 0.1}}}"#).unwrap_err().to_string();
        assert!(e.contains("`max_tail_rate` belong to an expected violation"), "{e}");
    }

    #[test]
    fn the_tail_is_held_over_all_regimes_with_counting_noise() {
        let e = Entry { expect: Expected::Violation, max_tail_rate: Some(1e-4), ..Entry::conservative() };
        let none = Entry { expect: Expected::Violation, ..Entry::conservative() };
        // 16 regimes of 5,000 cases: 8 expected, 8 + 3 * 2.83 + 2 = 18.5 allowed
        assert_eq!(pooled_tail_breach((0..16).map(|_| (&e, 1, 5_000))), None);
        assert_eq!(pooled_tail_breach((0..16).map(|i| (&e, (i < 2) as u64 * 9, 5_000))), None);
        let line = pooled_tail_breach((0..16).map(|i| (&e, (i < 1) as u64 * 19, 5_000))).unwrap();
        assert!(line.contains("19 of 80000"), "{line}");
        // a small run allows 2 and a little more (3.03 of 960 cases), not 4
        assert_eq!(pooled_tail_breach([(&e, 3, 960)]), None);
        assert!(pooled_tail_breach([(&e, 4, 960)]).is_some());
        // rows without a tail rate count nothing
        assert_eq!(pooled_tail_breach([(&none, 50, 960)]), None);
    }
}
