//! Running a proof script: the tool is started as a child process, the script goes to
//! its standard input, and the answer is read back with a time limit. A missing tool,
//! a timeout or an answer other than "proven" is an outcome, never a pass.

use crate::bounds::proofs::{Script, Tool};
use serde::Serialize;
use std::io::{Read, Write};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// What a tool said about a script.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "status", content = "detail", rename_all = "kebab-case")]
pub enum Verdict {
    /// z3 answered `unsat` (the negated claim has no model), gappa exited 0.
    Proven,
    /// z3 answered `sat` (a counterexample exists), or gappa could not prove a property.
    Refuted(String),
    /// z3 answered `unknown`, or any other answer (the tool's output).
    Unknown(String),
    /// The time limit passed (the child was killed).
    Timeout,
    /// The tool is not installed (how to install it).
    Missing(String),
}

impl Verdict {
    /// One word for tables.
    pub fn word(&self) -> &'static str {
        match self {
            Verdict::Proven => "proven",
            Verdict::Refuted(_) => "REFUTED",
            Verdict::Unknown(_) => "UNKNOWN",
            Verdict::Timeout => "TIMEOUT",
            Verdict::Missing(_) => "MISSING",
        }
    }
}

/// A script's verdict and the wall time it took (seconds; noisy on a shared machine).
#[derive(Clone, Debug, Serialize)]
pub struct Outcome {
    pub verdict: Verdict,
    pub seconds: f64,
}

/// Run `script` with its tool, killing it after `limit`.
pub fn run(script: &Script, limit: Duration) -> Outcome {
    run_text(script.tool, &script.input(), limit)
}

/// Run `input` (a whole script, prelude included) with `tool`, killing it after `limit`.
pub fn run_text(tool: Tool, input: &str, limit: Duration) -> Outcome {
    let start = Instant::now();
    let verdict = match spawn(tool, limit) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            Verdict::Missing(format!("`{}` not found on the PATH: {}", tool.binary(), tool.install()))
        }
        Err(e) => Verdict::Missing(format!("`{}` could not be started ({e}): {}", tool.binary(), tool.install())),
        Ok(child) => finish(tool, child, input, limit),
    };
    Outcome { verdict, seconds: start.elapsed().as_secs_f64() }
}

fn spawn(tool: Tool, limit: Duration) -> std::io::Result<Child> {
    let mut cmd = Command::new(tool.binary());
    if tool == Tool::Z3 {
        // z3's own limit (milliseconds) as well as ours: it answers `timeout` cleanly.
        cmd.arg("-in").arg(format!("-t:{}", limit.as_millis().max(1)));
    }
    cmd.stdin(Stdio::piped()).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn()
}

fn finish(tool: Tool, mut child: Child, input: &str, limit: Duration) -> Verdict {
    // The scripts are a few KB: the pipe takes them whole before the tool reads.
    if let Some(mut stdin) = child.stdin.take() {
        if let Err(e) = stdin.write_all(input.as_bytes()) {
            let _ = child.kill();
            let _ = child.wait();
            return Verdict::Unknown(format!("writing the script to {}: {e}", tool.binary()));
        }
    }
    // Read both pipes on threads so that a chatty tool never blocks on a full pipe.
    let drain = |p: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut s = String::new();
            if let Some(mut p) = p {
                let _ = p.read_to_string(&mut s);
            }
            s
        })
    };
    let out = drain(child.stdout.take().map(|p| Box::new(p) as Box<dyn Read + Send>));
    let err = drain(child.stderr.take().map(|p| Box::new(p) as Box<dyn Read + Send>));
    let start = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None) if start.elapsed() > limit + Duration::from_secs(1) => {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(10)),
            Err(e) => return Verdict::Unknown(format!("waiting for {}: {e}", tool.binary())),
        }
    };
    let (out, err) = (out.join().unwrap_or_default(), err.join().unwrap_or_default());
    let Some(status) = status else { return Verdict::Timeout };
    let text =
        format!("{}{}", out.trim(), if err.trim().is_empty() { String::new() } else { format!(" {}", err.trim()) });
    match tool {
        Tool::Z3 => match out.trim() {
            "unsat" => Verdict::Proven,
            "sat" => Verdict::Refuted("z3 found a model of the negated claim".into()),
            "timeout" => Verdict::Timeout,
            _ => Verdict::Unknown(text),
        },
        Tool::Gappa if status.success() => Verdict::Proven,
        Tool::Gappa if text.contains("not satisfied") || text.contains("no contradiction") => Verdict::Refuted(text),
        Tool::Gappa => Verdict::Unknown(text),
    }
}
