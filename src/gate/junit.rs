//! The gate's report as JUnit XML, the format CI systems show natively: one test
//! suite per method, one test case per method x regime row. A failing row is a
//! `<failure>` whose text says why (the status and its problems) and, when the row
//! has a witness, names the case file written for it, which `cullproof replay FILE`
//! re-judges and `cullproof explain FILE` explains. A row that is not gated
//! (expectation "unknown") or none of whose cases could be judged under the declared
//! samples ("not judged") is `<skipped/>`.
//!
//! Witness files go to a directory beside the XML file (`gate.xml` ->
//! `gate.witnesses/<method>/<hash>.json`, the corpus's case-file format); an existing
//! file is never overwritten (the same witness has the same name).

use crate::gate::case_file::CaseFile;
use crate::gate::report::CheckReport;
use crate::gate::row::{Row, Status};
use crate::gate::CheckConfig;
use anyhow::Result;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The witness directory that goes with a JUnit file: `<stem>.witnesses` beside it.
pub fn witness_dir(junit: &Path) -> PathBuf {
    let stem = junit.file_stem().map_or_else(|| "cullproof".into(), |s| s.to_string_lossy().into_owned());
    junit.with_file_name(format!("{stem}.witnesses"))
}

/// XML text escaping (attributes and text).
fn esc(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&apos;"),
            c if (c as u32) < 0x20 && c != '\n' && c != '\t' => o.push(' '),
            c => o.push(c),
        }
    }
    o
}

/// Write a failing row's worst witness as a case file under `dir`; its path (the
/// existing file's when the same witness was written before).
fn write_witness(r: &CheckReport, row: &Row, dir: &Path) -> Result<Option<PathBuf>> {
    let Some(w) = &row.worst else { return Ok(None) };
    let mut cfg = CheckConfig::default_for(Vec::new());
    cfg.seed = r.seed;
    if let Some(n) = &r.samples {
        (cfg.sample_set, cfg.snap, cfg.viewport) = (n.set, n.snap, n.viewport);
    }
    let note = format!("the worst violation of {} / {} in a gate run ({})", row.method, row.regime, row.status.text());
    let cf = CaseFile::violation(
        &row.method,
        (w.case, w.tile),
        w,
        &cfg,
        ("check", w.case_index, row.regime.clone()),
        Vec::new(),
        note,
    );
    let path = dir.join(&cf.method).join(format!("{}.json", cf.short_hash()));
    cf.write_new(dir)?;
    Ok(Some(path))
}

/// The JUnit XML of a report; failing rows' witnesses are written under `dir`.
/// `loaders` are the flags that load the run's plugged bounds (`--plugin LIB.so`,
/// `--exec 'COMMAND'`, shell-quoted; empty for built-in methods): the re-judge hint
/// carries them, since `replay` and `explain` need the same bound loaded.
pub fn render(r: &CheckReport, dir: &Path, loaders: &str) -> Result<String> {
    let failures = r.rows.iter().filter(|x| x.status.fails()).count();
    let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        s,
        "<testsuites name=\"cullproof check\" tests=\"{}\" failures=\"{failures}\" time=\"{:.3}\">",
        r.rows.len(),
        r.seconds
    );
    let mut methods: Vec<&str> = Vec::new();
    for row in &r.rows {
        if !methods.contains(&row.method.as_str()) {
            methods.push(&row.method);
        }
    }
    for m in methods {
        let rows: Vec<&Row> = r.rows.iter().filter(|x| x.method == m).collect();
        let f = rows.iter().filter(|x| x.status.fails()).count();
        let skipped = rows.iter().filter(|x| matches!(x.status, Status::NotGated | Status::NotJudged)).count();
        let _ = writeln!(
            s,
            "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{f}\" skipped=\"{skipped}\">",
            esc(m),
            rows.len()
        );
        let strengths = if r.methods.is_empty() { crate::gate::strength::of_rows(&r.rows) } else { r.methods.clone() };
        if let Some(st) = strengths.iter().find(|x| x.method == m) {
            let _ = writeln!(
                s,
                "    <properties><property name=\"strength\" value=\"{}\"/><property name=\"verdict\" value=\"{}\"/></properties>",
                esc(st.strength.name()),
                esc(&st.text)
            );
        }
        for row in rows {
            let _ = write!(
                s,
                "    <testcase classname=\"cullproof.{}\" name=\"{}\" time=\"0\">",
                esc(&row.method),
                esc(&row.regime)
            );
            let counts = format!(
                "{} cases: {} proven, {} violated, {} unproven{} (seed {}, shard {})",
                row.cases,
                row.proven,
                row.violations,
                row.unproven,
                if row.not_judged > 0 { format!(", {} not judged", row.not_judged) } else { String::new() },
                r.seed,
                r.shard
            );
            if row.status.fails() {
                let mut text = format!("{}: {}\n{counts}\n", row.status.text(), row.problems.join("; "));
                if let Some(p) = write_witness(r, row, dir)? {
                    let pre = if loaders.is_empty() { String::new() } else { format!("{loaders} ") };
                    let _ = writeln!(
                        text,
                        "witness: {} (re-judge: cullproof {pre}replay {0}; picture: cullproof {pre}explain {0} --svg OUT.svg)",
                        p.display()
                    );
                }
                let _ = write!(
                    s,
                    "\n      <failure type=\"{}\" message=\"{}\">{}</failure>\n    ",
                    esc(row.status.text()),
                    esc(&format!("{} / {}: {}", row.method, row.regime, row.status.text())),
                    esc(&text)
                );
            } else if row.status == Status::NotGated {
                let _ = write!(s, "<skipped message=\"not gated (expectation unknown); {}\"/>", esc(&counts));
            } else if row.status == Status::NotJudged {
                let why =
                    "not judged (no case of the row can be judged under the declared samples: snapping or placement)";
                let _ = write!(s, "<skipped message=\"{}; {}\"/>", esc(why), esc(&counts));
            } else {
                let _ = write!(s, "<system-out>{}: {}</system-out>", esc(row.status.text()), esc(&counts));
            }
            s.push_str("</testcase>\n");
        }
        s.push_str("  </testsuite>\n");
    }
    s.push_str("</testsuites>\n");
    Ok(s)
}

/// Check a `--junit` path before the run ([`crate::io::output::file`]), and that its
/// witness directory ([`witness_dir`]) is a directory if it exists.
pub fn check_path(path: &Path) -> Result<()> {
    crate::io::output::file("--junit", path)?;
    let w = witness_dir(path);
    if std::fs::metadata(&w).is_ok_and(|m| !m.is_dir()) {
        anyhow::bail!(
            "--junit {}: the witness directory beside it, {}, exists and is not a directory",
            path.display(),
            w.display()
        );
    }
    Ok(())
}

/// Write the JUnit XML of a report to `path` (its witnesses beside it, see
/// [`witness_dir`]); an existing file is replaced only by the whole new one.
pub fn write(r: &CheckReport, path: &Path, loaders: &str) -> Result<()> {
    let xml = render(r, &witness_dir(path), loaders)?;
    crate::io::output::write(path, xml)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_and_names() {
        assert_eq!(esc("a<b & \"c\"'"), "a&lt;b &amp; &quot;c&quot;&apos;");
        assert_eq!(witness_dir(Path::new("out/gate.xml")), PathBuf::from("out/gate.witnesses"));
    }
}
