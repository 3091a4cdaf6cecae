//! `cullproof replay`: case files re-judged (the stored witness re-decided exactly, the method judged
//! afresh, or against another method with `--method`); exit 1 when one no longer shows what it expects.

use super::common::{check_json, exit, write_json};
use anyhow::Result;
use std::path::PathBuf;

/// Arguments of `cullproof replay`.
#[derive(clap::Args)]
pub struct ReplayArgs {
    /// Case files or directories (default: the corpus's cases/).
    paths: Vec<PathBuf>,
    #[command(flatten)]
    corpus: crate::cli::args::CorpusFlag,
    /// Re-judge every file's case against this method instead of the one the file
    /// was written for (e.g. a fixed bound): one line per file, "fixed" (proven,
    /// the stored witness no longer culled), "still violated" or "unproven"; exit 1
    /// unless every file is fixed.
    #[arg(long)]
    method: Option<String>,
    /// Write the JSON report to this file ("-" for standard output).
    #[arg(long)]
    json: Option<PathBuf>,
    /// Flags given here judge the files under another sample set, snap or viewport
    /// than the one each file records.
    #[command(flatten)]
    sample: crate::cli::args::SampleFlags,
}

/// Run `cullproof replay`.
pub fn run(args: ReplayArgs) -> Result<()> {
    let ReplayArgs { paths, corpus, method, json, sample } = args;
    let over = sample.parse()?;
    check_json(&json)?;
    let paths = if paths.is_empty() {
        let cases = corpus.dir(crate::gate::locate::in_checkout())?.join("cases");
        anyhow::ensure!(
            cases.is_dir(),
            "{}: no such directory, so no case files to replay (`search` writes them there; pass case \
             files or directories, or --corpus DIR)",
            cases.display()
        );
        vec![cases]
    } else {
        paths
    };
    let files = crate::search::case_files(&paths)?;
    let cfg = crate::gate::CheckConfig::default_with(crate::bounds::registry());
    if let Some(id) = method {
        anyhow::ensure!(
            crate::search::method_of(&id).is_some(),
            "--method {id}: no such method (see `cullproof methods`)"
        );
        let mut out = Vec::new();
        for f in &files {
            out.push(crate::search::rejudge(f, &cfg, &over, &id)?);
        }
        for r in &out {
            let w = match &r.witness {
                Some(Ok((b, m))) => format!("stored witness still culled ({b}, margin {m:.3e})"),
                Some(Err(e)) => format!("stored witness: {e}"),
                None => "no stored witness".into(),
            };
            println!("{:<14} {} (found for {}): judged {}; {}", r.outcome, r.path, r.found_for, r.judged, w);
        }
        let fixed = out.iter().filter(|r| r.outcome == "fixed").count();
        println!("{} file(s) against {id}: {fixed} fixed, {} not", out.len(), out.len() - fixed);
        if let Some(p) = &json {
            write_json(p, &serde_json::to_string_pretty(&out)?)?;
        }
        if fixed < out.len() {
            exit(1);
        }
        return Ok(());
    }
    let mut out = Vec::new();
    for f in &files {
        out.push(crate::search::replay_with(f, &cfg, &over)?);
    }
    let bad = out.iter().filter(|r| !r.ok).count();
    for r in &out {
        let w = match &r.witness {
            Some(Ok((b, m))) => format!("witness holds ({b}, margin {m:.3e})"),
            Some(Err(e)) => format!("witness FAILS: {e}"),
            None => "no witness".into(),
        };
        println!(
            "{} {:<22} expected {:<12} judged {:<13} {}  {}{}",
            if r.ok { "ok  " } else { "FAIL" },
            r.method,
            format!("{:?}", r.expected).to_lowercase(),
            r.judged,
            w,
            r.path,
            r.samples.as_ref().map_or(String::new(), |s| format!("  (samples {s})"))
        );
    }
    println!("{} file(s), {} as expected, {} not", out.len(), out.len() - bad, bad);
    if let Some(p) = &json {
        write_json(p, &serde_json::to_string_pretty(&out)?)?;
    }
    if bad > 0 {
        exit(1);
    }
    Ok(())
}
