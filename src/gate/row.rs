//! A row of the gate's table, one method x regime: its counts, its standing against the
//! expectations (and the baseline), and the exact sums its means are computed from. The
//! report collects the rows (`report.rs`), the baseline stores and compares them
//! (`baseline.rs`), and `cullproof merge` adds the rows of shards (`merge.rs`).

use super::expect::{Entry, Expected, TightStat};
use crate::judge::Witness;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A row's standing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Status {
    /// Expected conservative: every case proven.
    Proven,
    /// Expected conservative: no violation, unproven cases within the stated allowance.
    ProvenExceptAllowed,
    /// Expected conservative: no violation, but more unproven cases than allowed.
    Unproven,
    /// A violation where the row is expected conservative.
    UnexpectedViolation,
    /// Expected violations, within their signature.
    KnownViolation,
    /// Expected violations that leave their signature (a new kind of bound, a margin or
    /// a rate above its cap).
    BeyondSignature,
    /// An expected violation that this run did not see (not a failure).
    ExpectedNotSeen,
    /// Expectation "unknown": reported, never failing.
    NotGated,
    /// Worse than the stored baseline for the same settings.
    Regression,
    /// No case of the row could be judged under the declared samples (snapping or
    /// placement; see [`crate::judge::Verdict::NotJudged`]): neither a failure nor a pass.
    NotJudged,
}

impl Status {
    pub fn fails(self) -> bool {
        matches!(self, Status::Unproven | Status::UnexpectedViolation | Status::BeyondSignature | Status::Regression)
    }
    pub fn text(self) -> &'static str {
        match self {
            Status::Proven => "proven",
            Status::ProvenExceptAllowed => "ok, unproven allowed",
            Status::Unproven => "UNPROVEN",
            Status::UnexpectedViolation => "UNEXPECTED VIOLATION",
            Status::KnownViolation => "known violation",
            Status::BeyondSignature => "BEYOND SIGNATURE",
            Status::ExpectedNotSeen => "expected violation not seen",
            Status::NotGated => "not gated",
            Status::Regression => "REGRESSION",
            Status::NotJudged => "not judged",
        }
    }
}

/// One kind of violated bound in a row: cases and the largest margin.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, serde::Deserialize)]
pub struct BoundStat {
    pub cases: u64,
    #[serde(with = "crate::io::num_or_inf")]
    pub max_margin: f64,
}

/// How many violations a row keeps whole (every one is counted).
pub const EXAMPLES_PER_ROW: usize = 32;

/// The row of the verdict table.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Row {
    pub method: String,
    pub regime: String,
    pub cases: u64,
    /// Cases whose every claim was certified.
    pub proven: u64,
    /// Cases with a violation (witness confirmed exactly, in the tile and the domain).
    pub violations: u64,
    /// Cases neither proven nor violated.
    pub unproven: u64,
    /// Cases that could not be judged under the declared samples (a vertex snapping
    /// cannot snap exactly, a case the viewport cannot hold): neither proven, violated
    /// nor unproven. `proven + violations + unproven + not_judged = cases`.
    #[serde(default)]
    pub not_judged: u64,
    /// Unproven cases by reason (a case may have several).
    pub unproven_by: BTreeMap<String, u64>,
    /// Violated bound kinds: cases and largest margin.
    pub bounds: BTreeMap<String, BoundStat>,
    /// Violated cases with a kind in the method's tail (above this regime's cap, within
    /// the method's largest: [`super::expect::Place::Tail`]); held to the tail rate
    /// over all of the method's rows.
    #[serde(default)]
    pub tail: u64,
    pub boundary_only: u64,
    /// Violations witnessed by an f32 sample (the rest only between f32 values).
    pub f32_witnessed: u64,
    /// Tiles judged at the method's own tile-reject limit, and those with a violation.
    pub limit_tiles: u64,
    pub limit_violations: u64,
    /// Cases in which the method culled a tile near the footprint (its limit tiles were
    /// placed), and the mean slack of its reject limit there (tile sizes beyond the
    /// footprint's extreme; larger: looser).
    pub limit_found: u64,
    pub limit_slack: f64,
    /// Per interval end kind: the proven ends probed for tightness and those with a
    /// covered sample within [`crate::judge::tile::TIGHT_DELTA`] of them (see
    /// [`crate::judge::Judgement::tight`]); checked against the expectation's least
    /// share at any settings.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub tight: BTreeMap<String, TightStat>,
    /// Mean share of the boundary tile's uniform samples the answer admits (intervals
    /// and constraints; 0 for a culled tile).
    pub admit_fraction: f64,
    /// Mean share of the (u, v, t) domain the intervals let through on the boundary
    /// tile (0 for a culled tile): the row's looseness, compared with the baseline.
    pub pass_fraction: f64,
    /// Largest margin needed over the violations (0 when none; "inf" in JSON when a
    /// covered tile was culled).
    #[serde(with = "crate::io::num_or_inf")]
    pub margin_needed: f64,
    pub expected: Expected,
    pub status: Status,
    /// What made the status (signature breaches, unproven beyond the allowance,
    /// differences from the baseline).
    pub problems: Vec<String>,
    /// The violation with the largest margin (the later case on a tie).
    pub worst: Option<Witness>,
    /// The first [`EXAMPLES_PER_ROW`] violations of the row, in case order (the
    /// library's [`crate::GateReport`] hands them out; not in the JSON report, and a
    /// merged report has none).
    #[serde(skip)]
    pub examples: Vec<Witness>,
    /// The row's sums in exact fixed point, from which its means are computed: shard
    /// reports carry them so that `cullproof merge` gives the very numbers of the
    /// unsharded run (a float sum would depend on the order of addition).
    pub sums: RowSums,
    #[serde(skip)]
    pub(crate) entry: Option<Entry>,
}

/// Exact sums behind a row's means: the pass fraction and the admit fraction (each a
/// number in [0, 1] per case) and the limit slack (per case whose limit tiles were
/// placed), in the fixed point of [`fixed`]. Written as decimal strings (JSON numbers
/// do not hold 128-bit integers).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct RowSums {
    #[serde(with = "i128_text")]
    pub pass: i128,
    #[serde(with = "i128_text")]
    pub admit: i128,
    #[serde(with = "i128_text")]
    pub slack: i128,
}

impl std::ops::Add for RowSums {
    type Output = RowSums;
    fn add(self, o: RowSums) -> RowSums {
        RowSums { pass: self.pass + o.pass, admit: self.admit + o.admit, slack: self.slack + o.slack }
    }
}

/// Fixed-point conversion of the per-case numbers a row averages.
///
/// A fraction `f` in [0, 1] becomes the integer nearest `f 2^96` (the scaling by a
/// power of two is exact in f64; only the rounding to an integer loses anything, at
/// most 2^-97 per case). A limit slack `s` (tile sizes, typically a rounding of the
/// footprint's extreme, 1e-7) is clamped to [-2^24, 2^24] and becomes the integer
/// nearest `s 2^72` (at most 2^-73 lost per case). Sums of 2^30 cases of either stay
/// below 2^127.
/// A NaN counts as 0.
pub mod fixed {
    const FRACTION_SCALE: f64 = (1u128 << 96) as f64;
    const SLACK_SCALE: f64 = (1u128 << 72) as f64;
    const SLACK_CLAMP: f64 = (1u64 << 24) as f64;

    fn to_fixed(x: f64, scale: f64) -> i128 {
        if x.is_nan() {
            0
        } else {
            (x * scale).round() as i128
        }
    }

    /// A fraction in [0, 1] (clamped to it).
    pub fn fraction(f: f64) -> i128 {
        to_fixed(f.clamp(0.0, 1.0), FRACTION_SCALE)
    }

    /// A limit slack.
    pub fn slack(s: f64) -> i128 {
        to_fixed(s.clamp(-SLACK_CLAMP, SLACK_CLAMP), SLACK_SCALE)
    }

    /// The mean of `n` fractions summed in fixed point (0 when n = 0).
    pub fn mean_fraction(sum: i128, n: u64) -> f64 {
        sum as f64 / FRACTION_SCALE / n.max(1) as f64
    }

    /// The mean of `n` slacks summed in fixed point (0 when n = 0).
    pub fn mean_slack(sum: i128, n: u64) -> f64 {
        if n == 0 {
            0.0
        } else {
            sum as f64 / SLACK_SCALE / n as f64
        }
    }
}

mod i128_text {
    use serde::{Deserialize, Deserializer, Serializer};
    pub fn serialize<S: Serializer>(v: &i128, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&v.to_string())
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<i128, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(|_| serde::de::Error::custom(format!("expected a whole number as a string, found {s:?}")))
    }
}

#[cfg(test)]
mod tests {
    use super::fixed;

    #[test]
    fn fixed_point_sums_do_not_depend_on_order() {
        let xs: Vec<f64> = (0..1000).map(|i| ((i * 7919) % 1000) as f64 / 1000.0 * 0.999 + 1e-9 * i as f64).collect();
        let fwd: i128 = xs.iter().map(|&x| fixed::fraction(x)).sum();
        let rev: i128 = xs.iter().rev().map(|&x| fixed::fraction(x)).sum();
        assert_eq!(fwd, rev);
        let mean = fixed::mean_fraction(fwd, xs.len() as u64);
        let float_mean = xs.iter().sum::<f64>() / xs.len() as f64;
        assert!((mean - float_mean).abs() < 1e-12, "{mean} vs {float_mean}");
        assert_eq!(fixed::fraction(f64::NAN), 0);
        assert_eq!(fixed::fraction(1.0), 1i128 << 96);
        assert_eq!(fixed::mean_slack(fixed::slack(-2.5) + fixed::slack(0.5), 2), -1.0);
        assert_eq!(fixed::mean_slack(0, 0), 0.0);
        assert_eq!(fixed::slack(f64::INFINITY), 1i128 << 96);
        // a slack of a rounding's size keeps its digits
        let s = 1.3689e-7;
        assert!((fixed::mean_slack(3 * fixed::slack(s), 3) - s).abs() < 1e-15 * s);
    }
}
