//! Driving the `z3` binary: a script over a pipe (`z3 -in`), a time limit per query
//! (z3's own `-T:` and a wall-clock guard that kills the process), and the f32 values
//! of a model read back bit for bit.

use super::solver::{drive, first_answer, Solver};
use anyhow::{anyhow, bail, Context, Result};
use std::process::Command;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

/// What z3 answered.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Answer {
    Sat,
    Unsat,
    Unknown,
    Timeout,
    /// The query's resource limit (z3's deterministic `rlimit`) ran out.
    Budget,
}

impl Answer {
    pub fn name(self) -> &'static str {
        match self {
            Answer::Sat => "sat",
            Answer::Unsat => "unsat",
            Answer::Unknown => "unknown",
            Answer::Timeout => "timeout",
            Answer::Budget => "budget",
        }
    }
}

/// One run: the answer, the seconds it took and z3's whole output.
#[derive(Clone, Debug)]
pub struct Run {
    pub answer: Answer,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// CPU seconds z3 used (user + system, from `/proc/<pid>/stat` sampled every 10 ms
    /// while it runs, else from the waited-for children in `/proc/self/stat`; None where
    /// neither is readable). On a busy machine this is the figure to compare.
    pub cpu_seconds: Option<f64>,
    pub output: String,
    /// The solver that gave this answer.
    pub solver: Solver,
}

/// The z3 binary: `CULLPROOF_Z3` or `z3` on the PATH.
fn binary() -> String {
    std::env::var("CULLPROOF_Z3").unwrap_or_else(|_| "z3".into())
}

/// Run a script with a time limit of `seconds` (a positive number).
pub fn run(script: &str, seconds: f64) -> Result<Run> {
    run_limited(script, seconds, None)
}

/// Run a script with a time limit of `seconds` and, with `rlimit`, z3's resource limit
/// (deterministic: the same script gives the same answer on any machine and load; a
/// query that exhausts it answers [`Answer::Budget`]). The CPU seconds are this z3
/// process's own (sampled while it runs), so queries may run in parallel.
pub fn run_limited(script: &str, seconds: f64, rlimit: Option<u64>) -> Result<Run> {
    run_cancellable(script, seconds, rlimit, None)
}

/// [`run_limited`], stopped early (answer `unknown`) when `cancel` is set.
pub fn run_cancellable(script: &str, seconds: f64, rlimit: Option<u64>, cancel: Option<&AtomicBool>) -> Result<Run> {
    let bin = binary();
    let secs = seconds.ceil().max(1.0) as u64;
    let mut cmd = Command::new(&bin);
    cmd.arg("-in").arg(format!("-T:{secs}"));
    let mut script = script.to_string();
    if let Some(r) = rlimit {
        cmd.arg(format!("rlimit={r}"));
        script += "(get-info :reason-unknown)\n";
    }
    // z3 stops itself at -T; the guard only catches a z3 that does not.
    let guard = Duration::from_secs_f64(secs as f64 + 10.0);
    let p = drive(&mut cmd, script, guard, cancel).with_context(|| {
        format!("cannot start `{bin}` (install z3, e.g. `apt-get install z3`, or set CULLPROOF_Z3)")
    })?;
    let output = p.output;
    let answer = match first_answer(&output) {
        _ if p.cancelled => Answer::Unknown,
        _ if p.killed => Answer::Timeout,
        Some(Answer::Unknown)
            if rlimit.is_some() && (output.contains("resource limit") || output.contains("\"canceled\"")) =>
        {
            Answer::Budget
        }
        Some(a) => a,
        None => bail!("z3 did not answer sat/unsat/unknown/timeout: {} {}", output.trim(), p.err.trim()),
    };
    Ok(Run { answer, seconds: p.seconds, cpu_seconds: p.cpu_seconds, output, solver: Solver::Z3 })
}

/// The f32 value z3 printed for `name` in a `(get-value ...)` answer.
pub fn value(output: &str, name: &str) -> Result<f32> {
    let key = format!("({name} ");
    let at = output.find(&key).ok_or_else(|| anyhow!("z3's model has no value for `{name}`"))?;
    let rest = &output[at + key.len()..];
    let rest = rest.trim_start();
    if let Some(r) = rest.strip_prefix("(_ ") {
        let word = r.split_whitespace().next().unwrap_or("");
        return match word {
            "+zero" => Ok(0.0),
            "-zero" => Ok(-0.0),
            "+oo" => Ok(f32::INFINITY),
            "-oo" => Ok(f32::NEG_INFINITY),
            "NaN" => Ok(f32::NAN),
            w => bail!("z3's value for `{name}`: unexpected `{w}`"),
        };
    }
    let r = rest.strip_prefix("(fp ").ok_or_else(|| anyhow!("z3's value for `{name}` is not an fp literal"))?;
    let mut bits = String::new();
    for tok in r.split(|c: char| c.is_whitespace() || c == ')').filter(|t| !t.is_empty()).take(3) {
        if let Some(b) = tok.strip_prefix("#b") {
            bits += b;
        } else if let Some(h) = tok.strip_prefix("#x") {
            for ch in h.chars() {
                let d = ch.to_digit(16).ok_or_else(|| anyhow!("z3's value for `{name}`: bad hex `{h}`"))?;
                bits += &format!("{d:04b}");
            }
        } else {
            bail!("z3's value for `{name}`: unexpected `{tok}`");
        }
    }
    if bits.len() != 32 {
        bail!("z3's value for `{name}` has {} bits, not 32", bits.len());
    }
    Ok(f32::from_bits(u32::from_str_radix(&bits, 2)?))
}

/// The truth value z3 printed for `name` in a `(get-value ...)` answer.
pub fn truth(output: &str, name: &str) -> Result<bool> {
    let key = format!("({name} ");
    let at = output.find(&key).ok_or_else(|| anyhow!("z3's model has no value for `{name}`"))?;
    let rest = output[at + key.len()..].trim_start();
    if rest.starts_with("true") {
        Ok(true)
    } else if rest.starts_with("false") {
        Ok(false)
    } else {
        bail!("z3's value for `{name}` is not a truth value")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_read_bit_for_bit() {
        let out = "sat\n((a (fp #b0 #x86 #b10100000100111000000001))\n (z (_ -zero 8 24))\n (o (fp #b1 #b01111111 #b00000000000000000000000)))";
        assert_eq!(value(out, "a").unwrap().to_bits(), 0x4350_4e01);
        assert!(value(out, "z").unwrap().is_sign_negative());
        assert_eq!(value(out, "o").unwrap(), -1.0);
        assert!(value(out, "nope").is_err());
    }
}
