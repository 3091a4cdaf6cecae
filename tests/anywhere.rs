//! Run from anywhere (issue 25, item 1): the built binary, as `cargo install --path .`
//! leaves it, run with its current directory in a fresh temporary directory outside
//! the repository. `check` passes on the expectations and the baseline built into it,
//! with the same table as in the checkout; `search` writes its case file into the
//! corpus of that directory (`./cullproof-corpus`, or `--corpus DIR`) and never into the
//! project's; `replay` with no paths replays that corpus; `explain` reads the file by
//! path and by id. `--write-baseline` outside the checkout needs `--baseline FILE`. In a
//! checkout the files on disk win, and one that differs from the built-in copy is noted.
//! A plugged bound with no expectations row is judged as in the checkout.

#[allow(dead_code)]
mod common;

use common::{scratch, Cli, Run};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Every run here is a small one (the gate on 96 or 960 cases of cheap methods, a
/// two-second search).
const DEADLINE: Duration = Duration::from_secs(300);

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh directory outside the repository (and not a checkout).
fn outside(name: &str) -> PathBuf {
    let d = scratch(name);
    let (d_abs, root_abs) = (d.canonicalize().unwrap(), root().canonicalize().unwrap());
    assert!(!d_abs.starts_with(&root_abs), "{} lies inside the repository", d.display());
    assert!(!d.join("Cargo.toml").exists());
    d
}

/// `cullproof ARGS` run in `dir`.
fn run_in(dir: &Path, args: &[&str]) -> Run {
    Cli::new(args).dir(dir).deadline(DEADLINE).run()
}

/// `cullproof ARGS` run in the repository root.
fn run_at_root(args: &[&str]) -> Run {
    Cli::new(args).deadline(DEADLINE).run()
}

impl Run {
    fn exits(&self, code: i32) -> &Self {
        self.no_panic();
        assert_eq!(
            self.code,
            Some(code),
            "{}: exit {:?}\nstdout:\n{}\nstderr:\n{}",
            self.what,
            self.code,
            self.stdout,
            self.stderr
        );
        self
    }

    fn says(&self, needles: &[&str]) -> &Self {
        let all = format!("{}{}", self.stdout, self.stderr);
        for n in needles {
            assert!(
                all.contains(n),
                "{}: does not say `{n}`:\nstdout:\n{}\nstderr:\n{}",
                self.what,
                self.stdout,
                self.stderr
            );
        }
        self
    }

    fn no_note(&self) -> &Self {
        assert!(!self.stderr.contains("note:"), "{}: an unexpected note:\n{}", self.what, self.stderr);
        self
    }

    /// The report without its first line (`cullproof check, seed 1, ... cases (shard
    /// 0/1), 0.6 s`: the one line with a wall time).
    fn table(&self) -> String {
        let first = self.stdout.lines().next().unwrap_or("");
        assert!(first.starts_with("cullproof check, seed"), "{}: not a report:\n{}", self.what, self.stdout);
        self.stdout.lines().skip(1).collect::<Vec<_>>().join("\n")
    }
}

/// Every file under `dir`, relative, with its size, sorted.
fn listing(dir: &Path) -> Vec<(String, u64)> {
    fn walk(base: &Path, d: &Path, out: &mut Vec<(String, u64)>) {
        for e in std::fs::read_dir(d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(base, &p, out);
            } else {
                let size = std::fs::metadata(&p).unwrap().len();
                out.push((p.strip_prefix(base).unwrap().display().to_string(), size));
            }
        }
    }
    let mut out = Vec::new();
    if dir.exists() {
        walk(dir, dir, &mut out);
    }
    out.sort();
    out
}

#[test]
fn check_passes_anywhere_on_the_built_in_expectations_and_baseline() {
    let d = outside("check");
    run_in(&d, &["check", "--method", "bbox-safe", "--cases", "96"]).exits(0).says(&["verdict: PASS"]).no_note();
    // The same verdicts as in the checkout, row for row; at 960 cases the built-in
    // baseline has an entry, compared as the checkout's file is.
    for args in
        [["check", "--method", "bbox,bbox-safe", "--cases", "960"], ["check", "--method", "bbox", "--cases", "96"]]
    {
        let (here, there) = (run_in(&d, &args), run_at_root(&args));
        here.exits(0).no_note();
        there.exits(0).no_note();
        assert_eq!(here.table(), there.table(), "{} differs outside the checkout", here.what);
    }
    run_in(&d, &["check", "--method", "bbox,bbox-safe", "--cases", "960"])
        .says(&["baseline: seed 1 x 960 cases: 32 rows compared, 0 worse than stored"]);
    // Nothing was written where it ran.
    assert_eq!(listing(&d), []);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn search_replay_and_explain_use_the_corpus_of_the_current_directory() {
    let d = outside("search");
    let project = root().join("corpus");
    let before = listing(&project);
    // Nothing to replay yet: the error names the directory.
    run_in(&d, &["replay"]).exits(2).says(&["cullproof-corpus/cases", "no such directory"]);
    run_in(&d, &["search", "--method", "bbox", "--time", "2", "--max", "1", "--seed", "2"])
        .exits(0)
        .says(&["wrote cullproof-corpus/cases/bbox/"]);
    let found = listing(&d);
    assert_eq!(found.len(), 1, "{found:?}");
    let rel = &found[0].0;
    assert!(rel.starts_with("cullproof-corpus/cases/bbox/") && rel.ends_with(".json"), "{rel}");
    let hash = Path::new(rel).file_stem().unwrap().to_str().unwrap().to_string();
    // The project's corpus lacks this case (so a write there would show), and has no
    // new file.
    assert!(!before.iter().any(|(f, _)| f.ends_with(&format!("{hash}.json"))), "{hash} is in the project corpus");
    assert_eq!(listing(&project), before, "the project's corpus changed");
    // replay with no paths replays the directory's corpus, and only it.
    run_in(&d, &["replay"]).exits(0).says(&[rel, "1 file(s), 1 as expected, 0 not"]);
    // explain: by path, by id, by METHOD/id; with a picture.
    for case in [rel.clone(), hash.clone(), format!("bbox/{hash}")] {
        run_in(&d, &["explain", &case]).exits(0).says(&["bbox", "the method says"]);
    }
    run_in(&d, &["explain", &hash, "--svg", "case.svg"]).exits(0).says(&["wrote case.svg"]);
    assert!(std::fs::read_to_string(d.join("case.svg")).unwrap().starts_with("<svg"));
    run_in(&d, &["explain", "0123456789abcdef"]).exits(2).says(&["0123456789abcdef", "cullproof-corpus/cases"]);
    // --corpus DIR names another corpus, for search, replay and explain alike.
    run_in(&d, &["search", "--method", "bbox", "--time", "2", "--max", "1", "--seed", "2", "--corpus", "mine"])
        .exits(0)
        .says(&[&format!("wrote mine/cases/bbox/{hash}.json")]);
    run_in(&d, &["replay", "--corpus", "mine"]).exits(0).says(&["1 file(s), 1 as expected"]);
    run_in(&d, &["explain", &hash, "--corpus", "mine"]).exits(0).says(&["bbox"]);
    run_in(&d, &["replay", "--corpus", "none"]).exits(2).says(&["none/cases"]);
    assert_eq!(listing(&project), before, "the project's corpus changed");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn write_baseline_outside_the_checkout_needs_a_file() {
    let d = outside("baseline");
    run_in(&d, &["check", "--method", "bbox", "--cases", "96", "--write-baseline"]).exits(2).says(&[
        "--write-baseline",
        "not the cullproof checkout",
        "--baseline FILE",
    ]);
    assert_eq!(listing(&d), [], "nothing is written when the baseline has no file");
    let args = ["check", "--method", "bbox", "--cases", "96", "--baseline", "mine.json"];
    run_in(&d, &[&args[..], &["--write-baseline"]].concat()).exits(0).says(&["wrote the baseline", "mine.json"]);
    run_in(&d, &args).exits(0).says(&["baseline: seed 1 x 96 cases: 16 rows compared, 0 worse than stored"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn in_a_checkout_the_files_on_disk_win_and_a_difference_is_noted() {
    let d = outside("checkout");
    std::fs::write(d.join("Cargo.toml"), "[workspace]\n\n[package]\nname = \"cullproof\"\nversion = \"9.9.9\"\n")
        .unwrap();
    // A checkout with no expectations file: an error naming it, as before.
    run_in(&d, &["check", "--method", "bbox", "--cases", "96"])
        .exits(2)
        .says(&["corpus/expectations.json", "no such file"]);
    // Expectations that list nothing: bbox is then expected conservative and fails, and
    // the note says the file differs from the built-in copy.
    std::fs::create_dir(d.join("corpus")).unwrap();
    std::fs::write(d.join("corpus/expectations.json"), "{}\n").unwrap();
    run_in(&d, &["check", "--method", "bbox", "--cases", "96"])
        .exits(1)
        .says(&["UNEXPECTED VIOLATION", "note: corpus/expectations.json differs from the copy built into this binary"]);
    // --expectations FILE chooses, without a note.
    let real = root().join("corpus/expectations.json");
    run_in(&d, &["check", "--method", "bbox", "--cases", "96", "--expectations", real.to_str().unwrap()])
        .exits(0)
        .no_note();
    // --write-baseline writes the checkout's corpus/baseline.json; read back, it differs
    // from the built-in copy, which is noted.
    run_in(&d, &["check", "--method", "bbox-safe", "--cases", "96", "--write-baseline"])
        .exits(0)
        .says(&["wrote the baseline for these settings to corpus/baseline.json"]);
    run_in(&d, &["check", "--method", "bbox-safe", "--cases", "96"])
        .exits(0)
        .says(&["16 rows compared", "note: corpus/baseline.json differs from the copy built into this binary"]);
    // search writes into the checkout's corpus/cases.
    run_in(&d, &["search", "--method", "bbox", "--time", "2", "--max", "1", "--seed", "2"])
        .exits(0)
        .says(&["wrote corpus/cases/bbox/"]);
    // Not a checkout (another package's manifest): the built-in copies again.
    std::fs::write(d.join("Cargo.toml"), "[package]\nname = \"mine\"\n").unwrap();
    run_in(&d, &["check", "--method", "bbox", "--cases", "96"]).exits(0).no_note().says(&["verdict: PASS"]);
    let _ = std::fs::remove_dir_all(&d);
}

/// A bound plugged in by --exec has no row in the built-in expectations: it is expected
/// conservative everywhere, exactly as in the checkout.
#[test]
fn a_plugged_bound_is_judged_as_in_the_checkout() {
    let d = outside("plugged");
    let script = root().join("examples/python/bbox_exec.py");
    for (flags, code) in [("", 0), (" --broken", 1)] {
        let exec = format!("python3 {}{flags}", script.display());
        let args = ["--exec", exec.as_str(), "check", "--cases", "96", "--jobs", "2"];
        let (here, there) = (run_in(&d, &args), run_at_root(&args));
        here.exits(code).no_note();
        there.exits(code);
        assert_eq!(here.table(), there.table(), "{} differs outside the checkout", here.what);
        if code == 1 {
            here.says(&["py-bbox-broken", "UNEXPECTED VIOLATION"]);
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}
