//! Driving the `z3` binary: a script over a pipe (`z3 -in`), a time limit per query
//! (z3's own `-T:` and a wall-clock guard that kills the process), and the f32 values
//! of a model read back bit for bit.

use anyhow::{anyhow, bail, Context, Result};
use std::io::{Read, Write};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

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
}

/// User + system CPU seconds of this process's waited-for children (Linux; the kernel
/// reports them in units of 1/100 s).
fn children_cpu() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let rest = &stat[stat.rfind(')')? + 1..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let cu: f64 = f.get(13)?.parse().ok()?;
    let cs: f64 = f.get(14)?.parse().ok()?;
    Some((cu + cs) / 100.0)
}

/// The z3 binary to run (`CULLPROOF_Z3` overrides `z3` on the PATH).
pub fn binary() -> String {
    std::env::var("CULLPROOF_Z3").unwrap_or_else(|_| "z3".into())
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

/// Run a script with a time limit of `seconds` (a positive number).
pub fn run(script: &str, seconds: f64) -> Result<Run> {
    run_limited(script, seconds, None)
}

/// Run a script with a time limit of `seconds` and, with `rlimit`, z3's resource limit
/// (deterministic: the same script gives the same answer on any machine and load; a
/// query that exhausts it answers [`Answer::Budget`]). The CPU seconds are this z3
/// process's own (sampled while it runs), so queries may run in parallel.
pub fn run_limited(script: &str, seconds: f64, rlimit: Option<u64>) -> Result<Run> {
    let bin = binary();
    let secs = seconds.ceil().max(1.0) as u64;
    let start = Instant::now();
    let cpu0 = children_cpu();
    let mut cmd = Command::new(&bin);
    cmd.arg("-in").arg(format!("-T:{secs}"));
    let mut script = script.to_string();
    if let Some(r) = rlimit {
        cmd.arg(format!("rlimit={r}"));
        script += "(get-info :reason-unknown)\n";
    }
    let mut child =
        cmd.stdin(Stdio::piped()).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().with_context(|| {
            format!("cannot start `{bin}` (install z3, e.g. `apt-get install z3`, or set CULLPROOF_Z3)")
        })?;
    // Feed the script and drain both outputs on their own threads: a long script and
    // a long answer must not wait for each other through full pipes.
    let mut stdin = child.stdin.take().expect("piped");
    let text = script;
    let pid = child.id();
    let mut own_cpu = None;
    let writer = std::thread::spawn(move || stdin.write_all(text.as_bytes()));
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut s = String::new();
            let _ = r.read_to_string(&mut s);
            s
        })
    };
    let reader = drain(Box::new(child.stdout.take().expect("piped")));
    let err_reader = drain(Box::new(child.stderr.take().expect("piped")));
    // z3 stops itself at -T; the guard only catches a z3 that does not.
    let guard = Duration::from_secs_f64(secs as f64 + 10.0);
    let mut killed = false;
    loop {
        own_cpu = process_cpu(pid).or(own_cpu);
        if child.try_wait()?.is_some() {
            break;
        }
        if start.elapsed() > guard {
            let _ = child.kill();
            let _ = child.wait();
            killed = true;
            break;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let output = reader.join().map_err(|_| anyhow!("reading z3's output failed"))?;
    let err = err_reader.join().unwrap_or_default();
    // A z3 that stopped early (its time limit) closes its input: a failed write then
    // only matters when no answer came.
    let written = writer.join().map_err(|_| anyhow!("writing the query to `{bin}` failed"))?;
    let seconds = start.elapsed().as_secs_f64();
    let cpu_seconds = own_cpu.or_else(|| cpu0.zip(children_cpu()).map(|(a, b)| (b - a).max(0.0)));
    let first = output.lines().next().unwrap_or("").trim();
    let answer = match first {
        _ if killed => Answer::Timeout,
        "sat" => Answer::Sat,
        "unsat" => Answer::Unsat,
        "unknown" if rlimit.is_some() && (output.contains("resource limit") || output.contains("\"canceled\"")) => {
            Answer::Budget
        }
        "unknown" => Answer::Unknown,
        "timeout" => Answer::Timeout,
        _ => {
            written.with_context(|| format!("writing the query to `{bin}`"))?;
            bail!("z3 did not answer sat/unsat/unknown/timeout: {} {}", output.trim(), err.trim())
        }
    };
    Ok(Run { answer, seconds, cpu_seconds, output })
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
