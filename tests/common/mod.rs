//! The harness the integration tests share to run the built `cullproof` binary: one
//! invocation ([`Cli`]: arguments, environment, standard input, a deadline), what it
//! left ([`Run`]: exit code, stdout, stderr, wall time) with the checks every caller
//! makes of it, and scratch directories. A test file takes it with `mod common;`
//! (under `#[allow(dead_code)]` where it uses part of it).

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// How long the label of a run ([`Run::what`]) may grow before it is cut.
const WHAT_MAX: usize = 300;

/// One invocation of the built binary, run from the repository root (or [`Cli::dir`])
/// with `RUST_BACKTRACE=0`; set up with the builder methods, then [`Cli::run`].
pub struct Cli {
    args: Vec<String>,
    dir: Option<PathBuf>,
    env: Vec<(String, String)>,
    stdin: Option<Vec<u8>>,
    deadline: Option<Duration>,
    late: Option<String>,
}

impl Cli {
    /// `cullproof ARGS`: standard input empty, no deadline (it runs as long as it takes).
    pub fn new<S: AsRef<str>>(args: &[S]) -> Self {
        Cli {
            args: args.iter().map(|a| a.as_ref().to_string()).collect(),
            dir: None,
            env: Vec::new(),
            stdin: None,
            deadline: None,
            late: None,
        }
    }

    /// More arguments after the ones given so far.
    pub fn args<S: AsRef<str>>(mut self, more: &[S]) -> Self {
        self.args.extend(more.iter().map(|a| a.as_ref().to_string()));
        self
    }

    /// Run it with this current directory instead of the repository root.
    pub fn dir(mut self, dir: &Path) -> Self {
        self.dir = Some(dir.to_path_buf());
        self
    }

    /// An environment variable for the child (over the test's own environment).
    pub fn env(mut self, key: &str, value: &str) -> Self {
        self.env.push((key.to_string(), value.to_string()));
        self
    }

    /// Bytes written to the child's standard input, which is then closed.
    pub fn stdin(mut self, bytes: impl Into<Vec<u8>>) -> Self {
        self.stdin = Some(bytes.into());
        self
    }

    /// Kill the child and fail the test once it has run this long.
    pub fn deadline(mut self, deadline: Duration) -> Self {
        self.deadline = Some(deadline);
        self
    }

    /// What running past the deadline means, added to the failure message.
    pub fn late_means(mut self, why: &str) -> Self {
        self.late = Some(why.to_string());
        self
    }

    /// Run it to its end (or its deadline) and capture what it left; the test fails if
    /// the binary cannot start or runs past the deadline.
    pub fn run(self) -> Run {
        let what = format!("cullproof {}", self.args.join(" "));
        let what = match &self.dir {
            Some(d) => format!("(in {}) {what}", d.display()),
            None => what,
        };
        let what = if what.len() > WHAT_MAX {
            let cut = (0..=WHAT_MAX).rev().find(|&i| what.is_char_boundary(i)).unwrap_or(0);
            format!("{}...", &what[..cut])
        } else {
            what
        };
        let start = Instant::now();
        let mut child = Command::new(env!("CARGO_BIN_EXE_cullproof"))
            .args(&self.args)
            .current_dir(self.dir.as_deref().unwrap_or(Path::new(env!("CARGO_MANIFEST_DIR"))))
            .env("RUST_BACKTRACE", "0")
            .envs(self.env.iter().map(|(k, v)| (k, v)))
            .stdin(if self.stdin.is_some() { Stdio::piped() } else { Stdio::null() })
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("{what}: cannot start: {e}"));
        // Feed and drain the pipes on threads (a full pipe would stall the child).
        let feed = self.stdin.map(|bytes| {
            let mut pipe = child.stdin.take().unwrap();
            std::thread::spawn(move || {
                // The child may exit without reading it all: a broken pipe is its answer.
                pipe.write_all(&bytes).ok();
            })
        });
        let out = drain(child.stdout.take().unwrap());
        let err = drain(child.stderr.take().unwrap());
        let status = loop {
            if let Some(st) = child.try_wait().unwrap() {
                break st;
            }
            if let Some(deadline) = self.deadline.filter(|&d| start.elapsed() > d) {
                let _ = child.kill();
                let _ = child.wait();
                let why = self.late.as_deref().map(|w| format!(": {w}")).unwrap_or_default();
                panic!("{what}: still running after {deadline:?} (killed){why}");
            }
            std::thread::sleep(Duration::from_millis(10));
        };
        let took = start.elapsed();
        if let Some(f) = feed {
            f.join().unwrap();
        }
        Run { code: status.code(), stdout: out.join().unwrap(), stderr: err.join().unwrap(), what, took }
    }
}

/// `cullproof ARGS` under `deadline`: the shape of most calls.
pub fn run(args: &[&str], deadline: Duration) -> Run {
    Cli::new(args).deadline(deadline).run()
}

/// Read a pipe to its end on a thread, as text (invalid UTF-8 replaced).
fn drain(mut pipe: impl Read + Send + 'static) -> std::thread::JoinHandle<String> {
    std::thread::spawn(move || {
        let mut bytes = Vec::new();
        pipe.read_to_end(&mut bytes).ok();
        String::from_utf8_lossy(&bytes).into_owned()
    })
}

/// What one run of the binary left.
pub struct Run {
    /// The exit code; `None` where a signal ended it.
    pub code: Option<i32>,
    pub stdout: String,
    pub stderr: String,
    /// The command line (and the directory, when not the repository root), for failure
    /// messages (cut after 300 bytes).
    pub what: String,
    /// Wall time from the start to the exit.
    pub took: Duration,
}

impl Run {
    /// Never a panic or an abort (a signal leaves no exit code).
    pub fn no_panic(&self) -> &Self {
        assert!(
            !self.stderr.contains("panicked") && self.code.is_some() && self.code != Some(101),
            "{}: panicked or aborted (exit {:?}):\n{}",
            self.what,
            self.code,
            self.stderr
        );
        self
    }

    /// A run that did its work (0: pass, 1: a judged failure; not an error).
    pub fn ran(&self) -> &Self {
        self.no_panic();
        assert!(
            matches!(self.code, Some(0) | Some(1)),
            "{}: expected a run (exit 0 or 1), got {:?}:\n{}",
            self.what,
            self.code,
            self.stderr
        );
        self
    }
}

/// An empty scratch directory `cullproof-TEST-PID-NAME` in the system temp dir (TEST:
/// the test file), emptied first if a run before left it.
pub fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("cullproof-{}-{}-{name}", env!("CARGO_CRATE_NAME"), std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}
