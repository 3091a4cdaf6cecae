//! Helpers shared by the commands: flag checks run before any work, the expectations and the
//! baseline found as `locate` finds them, JSON output, and the exit path that reports plugin breaches.

use anyhow::{Context, Result};
use std::path::PathBuf;

/// Check `--jobs` (see [`crate::cli::args::jobs`]) and size the global pool.
pub fn set_jobs(jobs: Option<usize>) -> Result<()> {
    if let Some(j) = crate::cli::args::jobs(jobs)? {
        rayon::ThreadPoolBuilder::new().num_threads(j).build_global().context("setting the thread count")?;
    }
    Ok(())
}

/// Print a located file's note (a checkout file that differs from the copy built in).
pub fn noted<T>(l: crate::gate::locate::Located<T>) -> crate::gate::locate::Located<T> {
    if let Some(n) = &l.note {
        eprintln!("{n}");
    }
    l
}

/// Is a method id known (built in or plugged)?
pub fn known(id: &str) -> bool {
    crate::bounds::by_id(id).is_some()
}

/// The expectations (required: an error says `why` when the file is missing).
pub fn expectations_for(given: &Option<PathBuf>, in_checkout: bool, why: &str) -> Result<crate::gate::Expectations> {
    let ex = crate::gate::locate::expectations(given.as_deref(), Some(why), in_checkout, super::built_in(), &known)?;
    Ok(noted(ex.expect("required expectations are loaded or an error")).value)
}

/// The baseline compared with, and the file `--write-baseline` writes.
pub fn baseline_for(given: &Option<PathBuf>, in_checkout: bool) -> Result<crate::gate::locate::Baseline> {
    Ok(noted(crate::gate::locate::baseline(given.as_deref(), in_checkout, super::built_in())?).value)
}

/// The regimes of `--regime` (`all`: every one).
pub fn parse_regimes(name: &str) -> Result<Vec<crate::cases::generate::Regime>> {
    Ok(match crate::cli::args::regime(name)? {
        Some(r) => vec![r],
        None => crate::cases::generate::Regime::ALL.to_vec(),
    })
}

/// Write a JSON report to `path` (checked before the run with [`check_json`]; "-" is
/// standard output), replacing an existing file only by the whole new report.
pub fn write_json(path: &std::path::Path, text: &str) -> Result<()> {
    if path.as_os_str() == "-" {
        println!("{text}");
        Ok(())
    } else {
        crate::io::output::write(path, text)
    }
}

/// Check a `--json` path before any work (see [`crate::io::output`]).
pub fn check_json(json: &Option<PathBuf>) -> Result<()> {
    match json {
        Some(p) => crate::io::output::file_or_stdout("--json", p),
        None => Ok(()),
    }
}

/// Check a `--junit` path (and its witness directory) before any work.
pub fn check_junit(junit: &Option<PathBuf>) -> Result<()> {
    match junit {
        Some(p) => crate::gate::junit::check_path(p),
        None => Ok(()),
    }
}

/// `--plugin PATH` and `--exec 'COMMAND'` for each loaded bound, shell-quoted (single
/// quotes, an inner one written `'\''`).
pub fn loader_flags(plugins: &[PathBuf], execs: &[String]) -> String {
    let quote = |s: &str| format!("'{}'", s.replace('\'', "'\\''"));
    let mut out: Vec<String> = Vec::new();
    for p in plugins {
        out.push(format!("--plugin {}", quote(&p.display().to_string())));
    }
    for c in execs {
        out.push(format!("--exec {}", quote(c)));
    }
    out.join(" ")
}

/// One line per plugin that broke the contract of include/cullproof.h during the run.
pub fn report_breaches() {
    for b in crate::external::plugin::breaches().iter().filter(|b| b.answers > 0) {
        eprintln!("warning: {}", b.line());
    }
}

/// End the process with `code`, after the plugins' contract breaches.
pub fn exit(code: i32) -> ! {
    report_breaches();
    std::process::exit(code)
}

/// The end of `check` and `merge`: the report's JSON and JUnit files (each when asked
/// for), then exit 1 when a row failed.
pub fn finish_report(
    r: &crate::gate::CheckReport,
    json: &Option<PathBuf>,
    junit: &Option<PathBuf>,
    loaders: &str,
) -> Result<()> {
    if let Some(p) = json {
        write_json(p, &serde_json::to_string_pretty(r)?)?;
    }
    if let Some(p) = junit {
        crate::gate::junit::write(r, p, loaders)?;
    }
    if r.failed() {
        exit(1);
    }
    Ok(())
}
