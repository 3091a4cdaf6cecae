//! The solver portfolio: one standard SMT-LIB 2 script (logic `QF_BVFP`, nothing
//! specific to one solver) given to z3 and to Bitwuzla at once; the first `sat` or
//! `unsat` wins and the other solver is stopped. Neither answer is taken on trust: a
//! model becomes a case the exact judge decides ([`super::prove`]), and an `unsat` is
//! counted only when the same solver finds the query's hypotheses alone satisfiable
//! (an encoding whose hypotheses contradict each other would make every claim
//! `unsat`).
//!
//! z3 is the Debian binary (`z3`, or `CULLPROOF_Z3`); Bitwuzla is the PyPI wheel
//! `bitwuzla` (`pip install bitwuzla`), driven as a subprocess by a few lines of
//! Python ([`BITWUZLA_DRIVER`]) that hand the script to its SMT-LIB parser (`python3`,
//! or `CULLPROOF_PYTHON`).

use super::z3::{Answer, Run};
use anyhow::{anyhow, bail, Context, Result};
use serde::Serialize;
use std::io::{Read, Write};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// One solver of the portfolio.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Solver {
    Z3,
    Bitwuzla,
}

impl Solver {
    pub fn name(self) -> &'static str {
        match self {
            Solver::Z3 => "z3",
            Solver::Bitwuzla => "bitwuzla",
        }
    }
}

/// Which solvers a query runs on (at least one).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Solvers {
    pub z3: bool,
    pub bitwuzla: bool,
}

impl Solvers {
    pub const Z3: Solvers = Solvers { z3: true, bitwuzla: false };
    pub const BITWUZLA: Solvers = Solvers { z3: false, bitwuzla: true };
    pub const BOTH: Solvers = Solvers { z3: true, bitwuzla: true };

    /// Parse `z3`, `bitwuzla` or `z3,bitwuzla` (in any order); the error names the flag.
    pub fn parse(flag: &str, s: &str) -> Result<Solvers> {
        let mut out = Solvers { z3: false, bitwuzla: false };
        for w in s.split(',').map(str::trim) {
            match w {
                "z3" => out.z3 = true,
                "bitwuzla" => out.bitwuzla = true,
                _ => bail!(
                    "{flag} {}: `{}` is not a solver (z3, bitwuzla)",
                    crate::io::quote::clip(s),
                    crate::io::quote::clip(w)
                ),
            }
        }
        Ok(out)
    }

    pub fn list(self) -> Vec<Solver> {
        let mut v = Vec::new();
        if self.z3 {
            v.push(Solver::Z3);
        }
        if self.bitwuzla {
            v.push(Solver::Bitwuzla);
        }
        v
    }

    pub fn name(self) -> String {
        self.list().iter().map(|s| s.name()).collect::<Vec<_>>().join(",")
    }
}

/// The Python that runs Bitwuzla on a script read from standard input; the argument
/// is the time limit in milliseconds. Answers and values are printed by Bitwuzla's
/// own SMT-LIB front end (`sat`, `unsat`, `unknown`, `(get-value ...)`).
pub const BITWUZLA_DRIVER: &str = r#"
import sys
try:
    import bitwuzla as b
except ImportError as e:
    sys.stderr.write("cannot import bitwuzla (pip install bitwuzla): %s\n" % e)
    sys.exit(3)
tm = b.TermManager()
o = b.Options()
o.set(b.Option.PRODUCE_MODELS, True)
o.set(b.Option.TIME_LIMIT_PER, int(sys.argv[1]))
p = b.Parser(tm, o)
try:
    p.parse(sys.stdin.read(), False, False)
except Exception as e:
    sys.stdout.flush()
    sys.stderr.write("bitwuzla: %s\n" % e)
    sys.exit(4)
"#;

/// A finished (or stopped) solver process.
pub(crate) struct Proc {
    pub output: String,
    pub err: String,
    /// Killed by the guard (the solver overran its own limit by 10 s).
    pub killed: bool,
    /// Stopped because another solver answered first.
    pub cancelled: bool,
    pub seconds: f64,
    pub cpu_seconds: Option<f64>,
    pub status: Option<std::process::ExitStatus>,
}

/// User + system CPU seconds of a running (or exited, not yet waited-for) process.
fn process_cpu(pid: u32) -> Option<f64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    let rest = &stat[stat.rfind(')')? + 1..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let u: f64 = f.get(11)?.parse().ok()?;
    let s: f64 = f.get(12)?.parse().ok()?;
    Some((u + s) / 100.0)
}

/// Run `cmd` on `script` (its standard input) until it exits, `guard` passes (then it
/// is killed) or `cancel` is set (then it is stopped). Both outputs are drained on
/// their own threads, so neither a long script nor a long answer blocks.
pub(crate) fn drive(cmd: &mut Command, script: String, guard: Duration, cancel: Option<&AtomicBool>) -> Result<Proc> {
    let start = Instant::now();
    let mut child = cmd.stdin(Stdio::piped()).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn()?;
    let mut stdin = child.stdin.take().expect("piped");
    let pid = child.id();
    let writer = std::thread::spawn(move || stdin.write_all(script.as_bytes()));
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut s = String::new();
            let _ = r.read_to_string(&mut s);
            s
        })
    };
    let reader = drain(Box::new(child.stdout.take().expect("piped")));
    let err_reader = drain(Box::new(child.stderr.take().expect("piped")));
    let (mut killed, mut cancelled, mut cpu, mut status) = (false, false, None, None);
    loop {
        cpu = process_cpu(pid).or(cpu);
        if let Some(s) = child.try_wait()? {
            status = Some(s);
            break;
        }
        let stop = cancel.is_some_and(|c| c.load(Ordering::Relaxed));
        if stop || start.elapsed() > guard {
            let _ = child.kill();
            let _ = child.wait();
            (killed, cancelled) = (!stop, stop);
            break;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let output = reader.join().map_err(|_| anyhow!("reading the solver's output failed"))?;
    let err = err_reader.join().unwrap_or_default();
    // A solver that stopped early closes its input: a failed write only matters when
    // no answer came (the caller sees an empty output then).
    let _ = writer.join();
    Ok(Proc { output, err, killed, cancelled, seconds: start.elapsed().as_secs_f64(), cpu_seconds: cpu, status })
}

/// The answer on the first line of a solver's output.
pub(crate) fn first_answer(output: &str) -> Option<Answer> {
    match output.lines().next().unwrap_or("").trim() {
        "sat" => Some(Answer::Sat),
        "unsat" => Some(Answer::Unsat),
        "unknown" => Some(Answer::Unknown),
        "timeout" => Some(Answer::Timeout),
        _ => None,
    }
}

fn python() -> String {
    std::env::var("CULLPROOF_PYTHON").unwrap_or_else(|_| "python3".into())
}

/// Run Bitwuzla on `script` for at most `seconds`.
pub fn bitwuzla(script: &str, seconds: f64, cancel: Option<&AtomicBool>) -> Result<Run> {
    let ms = (seconds * 1000.0).ceil().max(1.0) as u64;
    let py = python();
    let mut cmd = Command::new(&py);
    cmd.arg("-c").arg(BITWUZLA_DRIVER).arg(ms.to_string());
    let guard = Duration::from_secs_f64(seconds + 10.0);
    let p = drive(&mut cmd, script.to_string(), guard, cancel)
        .with_context(|| format!("cannot start `{py}` for Bitwuzla (install python3 and `pip install bitwuzla`)"))?;
    let answer = match first_answer(&p.output) {
        _ if p.cancelled => Answer::Unknown,
        _ if p.killed => Answer::Timeout,
        // Bitwuzla says `unknown` at its time limit.
        Some(Answer::Unknown) if p.seconds >= 0.9 * seconds => Answer::Timeout,
        Some(a) => a,
        None if p.status.and_then(|s| s.code()) == Some(3) => bail!("{}", p.err.trim()),
        None => bail!("Bitwuzla did not answer sat/unsat/unknown: {} {}", p.output.trim(), p.err.trim()),
    };
    Ok(Run { answer, seconds: p.seconds, cpu_seconds: p.cpu_seconds, output: p.output, solver: Solver::Bitwuzla })
}

/// Run one solver.
pub fn run_one(
    solver: Solver,
    script: &str,
    seconds: f64,
    rlimit: Option<u64>,
    cancel: Option<&AtomicBool>,
) -> Result<Run> {
    match solver {
        Solver::Z3 => super::z3::run_cancellable(script, seconds, rlimit, cancel),
        Solver::Bitwuzla => bitwuzla(script, seconds, cancel),
    }
}

/// Run the portfolio: every solver of `solvers` on the same script at once; the first
/// `sat` or `unsat` wins and stops the others. With no decisive answer, the first
/// solver's (z3's when it runs) answer is returned. `rlimit` applies to z3 only (the
/// other solvers have the time limit).
pub fn run(script: &str, seconds: f64, rlimit: Option<u64>, solvers: Solvers) -> Result<Run> {
    let list = solvers.list();
    anyhow::ensure!(!list.is_empty(), "no solver chosen");
    if list.len() == 1 {
        return run_one(list[0], script, seconds, rlimit, None);
    }
    let cancel = AtomicBool::new(false);
    let (tx, rx) = std::sync::mpsc::channel();
    let results: Vec<Result<Run>> = std::thread::scope(|s| {
        let handles: Vec<_> = list
            .iter()
            .map(|&solver| {
                let (tx, cancel) = (tx.clone(), &cancel);
                s.spawn(move || {
                    let r = run_one(solver, script, seconds, rlimit, Some(cancel));
                    if r.as_ref().is_ok_and(|r| matches!(r.answer, Answer::Sat | Answer::Unsat)) {
                        cancel.store(true, Ordering::Relaxed);
                    }
                    let _ = tx.send(solver);
                    r
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().expect("a solver thread does not panic")).collect()
    });
    drop(tx);
    let order: Vec<Solver> = rx.iter().collect();
    // The first decisive answer in the order they finished.
    for solver in &order {
        let i = list.iter().position(|s| s == solver).expect("a listed solver");
        if let Ok(r) = &results[i] {
            if matches!(r.answer, Answer::Sat | Answer::Unsat) {
                return Ok(r.clone());
            }
        }
    }
    results.into_iter().next().expect("at least one solver")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solver_lists_parse_and_bad_names_are_named() {
        assert_eq!(Solvers::parse("--solvers", "z3").unwrap(), Solvers::Z3);
        assert_eq!(Solvers::parse("--solvers", "bitwuzla, z3").unwrap(), Solvers::BOTH);
        let e = Solvers::parse("--solvers", "z3,cvc9").unwrap_err().to_string();
        assert!(e.contains("--solvers") && e.contains("`cvc9`"), "{e}");
        assert_eq!(Solvers::BOTH.name(), "z3,bitwuzla");
    }

    #[test]
    fn first_lines_are_answers() {
        assert_eq!(first_answer("sat\n((x 1))"), Some(Answer::Sat));
        assert_eq!(first_answer("unsat\n"), Some(Answer::Unsat));
        assert_eq!(first_answer("(error \"x\")"), None);
    }
}
