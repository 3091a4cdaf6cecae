//! The strength of a method's verdict: what it covers.
//!
//! A row of the gate speaks about the cases it drew. Some `-safe` variants also carry a
//! proof for every f32 input in stated ranges ([`crate::bounds::proofs`]). Per method the
//! report states the strongest verdict it reaches, in this order:
//!
//! 1. **violated**: some case of this run has a witness confirmed exactly. A violation
//!    outranks everything, a proof included (a proven variant that is violated means
//!    the proof and the code have parted, and the gate says so).
//! 2. **machine-checked for all inputs in ranges**: the method has a proof whose rounding
//!    lemmas z3 and Gappa check and whose composition over the method's code a machine
//!    checks for every input (the enclosure check; `cullproof proofs` re-runs it all),
//!    and no case of this run contradicts it. The method's real-arithmetic derivation
//!    stays an argument.
//! 3. **rounding lemmas checked, composition argued**: the method has a proof for all
//!    inputs in its ranges whose rounding lemmas z3 and Gappa check, while how the
//!    method's code composes them is an argument (`docs/proofs.md`, the method's file)
//!    that no machine checks; no case of this run contradicts it. A change to the code
//!    that the argument no longer fits is caught only by the gate's cases.
//! 4. **proven on N cases**: every case of this run proven (certified).
//! 5. **unproven**: no violation, some cases neither proven nor violated.
//!
//! Under 2 and 3, unproven cases of the run are the judge's limits, counted and shown
//! beside the proof.

use super::row::Row;
use crate::bounds::proofs;
use serde::{Deserialize, Serialize};

/// How far a verdict reaches.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Strength {
    /// A witness confirmed exactly in this run.
    Violated,
    /// A proof for every f32 input in stated ranges, composition included, checked by
    /// machine; no violation in this run.
    MachineChecked,
    /// A proof for every f32 input in stated ranges whose rounding lemmas are checked by
    /// machine and whose composition is argued; no violation in this run.
    LemmasChecked,
    /// Every case of this run proven.
    ProvenOnCases,
    /// No violation; some cases neither proven nor violated.
    Unproven,
}

impl Strength {
    /// The short name used in tables and JSON.
    pub fn name(self) -> &'static str {
        match self {
            Strength::Violated => "violated",
            Strength::MachineChecked => "machine-checked for all inputs in ranges",
            Strength::LemmasChecked => "rounding lemmas checked, composition argued",
            Strength::ProvenOnCases => "proven on N cases",
            Strength::Unproven => "unproven",
        }
    }
}

/// One method's strongest verdict over a run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MethodStrength {
    pub method: String,
    pub strength: Strength,
    pub cases: u64,
    pub proven: u64,
    pub violations: u64,
    pub unproven: u64,
    /// Cases not judged under the declared samples (see [`crate::judge::Verdict::NotJudged`]).
    #[serde(default)]
    pub not_judged: u64,
    /// Regimes with a violation, of the regimes run.
    pub violated_regimes: u64,
    pub regimes: u64,
    /// With a proof ([`Strength::MachineChecked`], [`Strength::LemmasChecked`]): the
    /// ranges, as "inputs: range".
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ranges: Vec<String>,
    /// With a proof: the scripts of the proof.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub scripts: Vec<String>,
    /// The verdict in words, with its numbers.
    pub text: String,
}

/// The strongest verdict of each method of `rows`, in the rows' order.
pub fn of_rows(rows: &[Row]) -> Vec<MethodStrength> {
    let mut order: Vec<&str> = Vec::new();
    for r in rows {
        if !order.contains(&r.method.as_str()) {
            order.push(&r.method);
        }
    }
    order.into_iter().map(|m| of_method(m, rows.iter().filter(|r| r.method == m))).collect()
}

fn of_method<'a>(method: &str, rows: impl Iterator<Item = &'a Row>) -> MethodStrength {
    let (mut cases, mut proven, mut violations, mut unproven, mut regimes, mut violated_regimes) = (0, 0, 0, 0, 0, 0);
    let mut not_judged = 0;
    for r in rows {
        cases += r.cases;
        proven += r.proven;
        violations += r.violations;
        unproven += r.unproven;
        not_judged += r.not_judged;
        regimes += 1;
        violated_regimes += (r.violations > 0) as u64;
    }
    let proof = proofs::variant(method);
    let strength = if violations > 0 {
        Strength::Violated
    } else if let Some(p) = proof {
        match p.level {
            proofs::Level::MachineChecked => Strength::MachineChecked,
            proofs::Level::LemmasChecked => Strength::LemmasChecked,
        }
    } else if unproven == 0 && proven > 0 {
        Strength::ProvenOnCases
    } else {
        Strength::Unproven
    };
    let aside = if not_judged > 0 { format!(" ({not_judged} of {cases} cases not judged)") } else { String::new() };
    let text = match strength {
        Strength::Violated => {
            let against =
                if proof.is_some() { " (contradicts its proof for all inputs: code and proof differ)" } else { "" };
            format!("violated in {violated_regimes} of {regimes} regimes ({violations} of {cases} cases){against}")
        }
        Strength::MachineChecked | Strength::LemmasChecked => {
            let run = if unproven == 0 && not_judged == 0 {
                format!("all {cases} cases proven")
            } else {
                format!("{proven} of {cases} cases proven, {unproven} unproven by the judge")
            };
            format!("{} (`cullproof proofs`); this run: {run}{aside}", strength.name())
        }
        Strength::ProvenOnCases => format!("proven on {proven} cases{aside}"),
        Strength::Unproven => format!("no violation; {unproven} of {cases} cases unproven{aside}"),
    };
    let (ranges, scripts) = match (strength, proof) {
        (Strength::MachineChecked | Strength::LemmasChecked, Some(v)) => (
            v.ranges.iter().map(|r| format!("{}: {}", r.inputs, r.range)).collect(),
            v.scripts.iter().map(|s| s.to_string()).collect(),
        ),
        _ => (Vec::new(), Vec::new()),
    };
    MethodStrength {
        method: method.to_string(),
        strength,
        cases,
        proven,
        violations,
        unproven,
        not_judged,
        violated_regimes,
        regimes,
        ranges,
        scripts,
        text,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(method: &str, proven: u64, violations: u64, unproven: u64) -> Row {
        let text = format!(
            r#"{{"method":"{method}","regime":"static","cases":{},"proven":{proven},"violations":{violations},
            "unproven":{unproven},"unproven_by":{{}},"bounds":{{}},"boundary_only":0,"f32_witnessed":0,
            "limit_tiles":0,"limit_violations":0,"limit_found":0,"limit_slack":0,"admit_fraction":0,
            "pass_fraction":0,"margin_needed":0,"expected":"conservative","status":"proven","problems":[],
            "worst":null,"sums":{{"pass":"0","admit":"0","slack":"0"}}}}"#,
            proven + violations + unproven
        );
        serde_json::from_str(&text).unwrap()
    }

    #[test]
    fn each_strength_from_its_counts() {
        let rows = vec![
            row("bbox", 9, 1, 0),
            row("bbox", 10, 0, 0),
            row("bbox-safe", 8, 0, 2),
            row("la2011", 10, 0, 0),
            row("lb2011", 9, 0, 1),
            row("gdam2010-safe", 10, 0, 0),
            row("wu2013-safe", 9, 1, 0),
            row("lb2011-safe", 10, 0, 0),
        ];
        let s = of_rows(&rows);
        let by: Vec<(&str, Strength)> = s.iter().map(|m| (m.method.as_str(), m.strength)).collect();
        assert_eq!(
            by,
            vec![
                ("bbox", Strength::Violated),
                ("bbox-safe", Strength::MachineChecked),
                ("la2011", Strength::ProvenOnCases),
                ("lb2011", Strength::Unproven),
                ("gdam2010-safe", Strength::MachineChecked),
                ("wu2013-safe", Strength::Violated),
                ("lb2011-safe", Strength::MachineChecked),
            ]
        );
        assert_eq!((s[0].cases, s[0].violated_regimes, s[0].regimes), (20, 1, 2));
        assert!(s[1].text.contains("8 of 10 cases proven") && !s[1].ranges.is_empty() && !s[1].scripts.is_empty());
        assert!(s[2].text.contains("proven on 10 cases"));
        assert!(s[4].text.contains("machine-checked") && s[4].text.contains("all 10 cases proven"));
        assert!(s[5].text.contains("contradicts its proof"));
    }
}
