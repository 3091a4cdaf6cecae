//! Hostile command lines: every one must end with a clear error (exit 2, the flag or
//! the file and the bad value named on stderr), never a panic, a hang, an abort or a
//! silent default. Each runs the built binary from the repository root (so the default
//! `corpus/expectations.json` is found) under a deadline; the ones that do run work use
//! the smallest settings there are.

#[allow(dead_code)]
mod common;

use common::{scratch, Run};
use std::path::Path;
use std::time::Duration;

/// No invocation here may take longer (each is an error before any work, or a tiny run).
const DEADLINE: Duration = Duration::from_secs(120);

/// `cullproof ARGS` under [`DEADLINE`]; running past it fails the test.
fn run(args: &[&str]) -> Run {
    common::run(args, DEADLINE)
}

impl Run {
    /// A usage error: exit 2 and every `needle` on stderr.
    fn usage_error(&self, needles: &[&str]) -> &Self {
        self.no_panic();
        assert_eq!(
            self.code,
            Some(2),
            "{}: expected exit 2, stderr:\n{}\nstdout:\n{}",
            self.what,
            self.stderr,
            self.stdout
        );
        // Case aside: Rust writes NaN for `nan` and inf for `Infinity`.
        let low = self.stderr.to_lowercase();
        for n in needles {
            assert!(low.contains(&n.to_lowercase()), "{}: stderr does not name `{n}`:\n{}", self.what, self.stderr);
        }
        self
    }
}

// ---------------------------------------------------------------------------
// 1. An OBJ coordinate that overflows the scene

#[test]
fn an_obj_coordinate_too_large_for_the_scene_is_refused_with_file_line_and_value() {
    let dir = scratch("obj");
    let obj = dir.join("huge.obj");
    std::fs::write(
        &obj,
        "# finite in f32, but the scene would overflow\nv 0 0 0\nv 1e36 0 0\nv 0 1 0\nv 1 1 1\nf 1 2 3\nf 1 3 4\n",
    )
    .unwrap();
    let out = dir.join("out");
    let p = obj.to_str().unwrap();
    let o = out.to_str().unwrap();
    for setting in ["static", "blur", "all"] {
        run(&[
            "tightness",
            "--scene",
            p,
            "--setting",
            setting,
            "--spp",
            "1",
            "--tile",
            "8",
            "--size",
            "16x16",
            "--method",
            "bbox",
            "--certified",
            "0",
            "--no-timing",
            "--out",
            o,
        ])
        .usage_error(&["huge.obj", ":3:", "1e36", "too large"]);
    }
    // The same with every default the command has (certified tiles, timing, all methods).
    run(&["tightness", "--scene", p, "--spp", "1", "--size", "16x16", "--out", o]).usage_error(&["huge.obj", "1e36"]);
    // A mesh at the limit runs (no panic) and writes its report.
    let ok = dir.join("edge.obj");
    std::fs::write(&ok, "v 0 0 0\nv 1e15 0 0\nv 0 1e15 0\nv 1 1 1e15\nf 1 2 3\nf 1 3 4\n").unwrap();
    run(&[
        "tightness",
        "--scene",
        ok.to_str().unwrap(),
        "--spp",
        "1",
        "--tile",
        "4",
        "--size",
        "16x16",
        "--method",
        "bbox,lc",
        "--certified",
        "2",
        "--no-timing",
        "--out",
        o,
    ])
    .ran();
    assert!(out.join("ste.json").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

// ---------------------------------------------------------------------------
// 2. --tile

#[test]
fn a_bad_tile_size_is_refused_by_every_command() {
    for t in ["0", "nan", "inf", "-1", "5000", "1e30"] {
        run(&["search", "--method", "bbox", "--time", "1", "--dry-run", "--tile", t]).usage_error(&["--tile"]);
        run(&["check", "--method", "bbox", "--cases", "1", "--tile", t]).usage_error(&["--tile"]);
        run(&["stability", "--family", "sliver", "--method", "bbox", "--cases", "1", "--steps", "1", "--tile", t])
            .usage_error(&["--tile"]);
    }
    // The value is named as written where it is a number.
    run(&["search", "--method", "bbox", "--time", "1", "--dry-run", "--tile", "0"]).usage_error(&["--tile 0"]);
    run(&["check", "--method", "bbox", "--cases", "1", "--tile", "nan"]).usage_error(&["--tile NaN"]);
    run(&["search", "--method", "bbox", "--time", "1", "--dry-run", "--tile", "5000"])
        .usage_error(&["--tile 5000", "4096"]);
    // tightness takes whole pixels 1..256.
    for t in ["0", "300", "-1", "nan"] {
        run(&["tightness", "--scene", "forest", "--tile", t, "--no-timing", "--size", "16x16"])
            .usage_error(&["--tile"]);
    }
}

// ---------------------------------------------------------------------------
// 3. --jobs

#[test]
fn jobs_zero_or_beyond_the_machine_is_refused_by_every_command() {
    let dir = scratch("jobs");
    let o = dir.to_str().unwrap();
    for j in ["0", "100000", "18446744073709551615"] {
        let commands: Vec<Vec<&str>> = vec![
            vec!["oracle-agree", "--samples", "1", "--jobs", j],
            vec!["check", "--method", "bbox", "--cases", "1", "--jobs", j],
            vec!["search", "--method", "bbox", "--time", "1", "--dry-run", "--jobs", j],
            vec!["tightness", "--scene", "forest", "--size", "16x16", "--no-timing", "--out", o, "--jobs", j],
            vec!["stability", "--family", "sliver", "--cases", "1", "--steps", "1", "--out", o, "--jobs", j],
        ];
        for c in commands {
            let r = run(&c);
            r.usage_error(&["--jobs", j]);
            assert!(r.stdout.is_empty(), "{}: work started:\n{}", r.what, r.stdout);
        }
    }
    // An accepted value runs.
    run(&["check", "--method", "bbox", "--cases", "1", "--jobs", "1"]).ran();
    let _ = std::fs::remove_dir_all(&dir);
}

// ---------------------------------------------------------------------------
// 4. Counts that would exhaust memory; 7. zero counts

#[test]
fn counts_are_bounded_and_never_zero() {
    run(&["check", "--method", "bbox", "--cases", "18446744073709551615"]).usage_error(&["--cases", "at most"]);
    run(&["check", "--method", "bbox", "--cases", "1000000000000"]).usage_error(&["--cases 1000000000000", "at most"]);
    // More than 10^6 cases per shard: the run would hold them all.
    run(&["check", "--method", "bbox", "--cases", "5000000"]).usage_error(&["--cases 5000000", "per shard", "--shard"]);
    run(&["check", "--method", "bbox", "--cases", "0"]).usage_error(&["--cases 0"]);
    run(&["oracle-agree", "--samples", "18446744073709551615"]).usage_error(&["--samples", "at most"]);
    run(&["oracle-agree", "--samples", "0"]).usage_error(&["--samples 0"]);
    run(&["search", "--method", "bbox", "--time", "1", "--dry-run", "--max", "0"]).usage_error(&["--max 0"]);
    // The smallest real run of each.
    run(&["oracle-agree", "--samples", "1"]).ran();
    run(&["check", "--method", "bbox", "--cases", "1"]).ran();
}

// ---------------------------------------------------------------------------
// 5. --expectations

#[test]
fn a_missing_expectations_file_is_an_error() {
    let p = "corpus/expectationz.json";
    let r = run(&["check", "--method", "bbox", "--cases", "1", "--expectations", p]);
    r.usage_error(&["--expectations", p]);
    assert!(r.stdout.is_empty(), "the run went on:\n{}", r.stdout);
    run(&["check", "--method", "bbox", "--cases", "1", "--expectations", "/nonexistent/dir/e.json"])
        .usage_error(&["/nonexistent/dir/e.json"]);
    // A directory is not a file either.
    run(&["check", "--method", "bbox", "--cases", "1", "--expectations", "corpus"]).usage_error(&["corpus"]);
}

// ---------------------------------------------------------------------------
// 6. --time

#[test]
fn a_time_that_is_not_a_positive_number_is_refused() {
    for t in ["nan", "-1", "inf", "0", "-0"] {
        let r = run(&["check", "--method", "bbox", "--time", t]);
        r.usage_error(&["--time"]);
        assert!(r.stdout.is_empty(), "{}: ran:\n{}", r.what, r.stdout);
        run(&["search", "--method", "bbox", "--dry-run", "--time", t]).usage_error(&["--time"]);
    }
    run(&["check", "--method", "bbox", "--time", "nan"]).usage_error(&["--time NaN"]);
    run(&["check", "--method", "bbox", "--time", "1e9"]).usage_error(&["--time 1000000000", "at most"]);
    run(&["search", "--method", "bbox", "--dry-run", "--time", "1e12"]).usage_error(&["--time", "at most"]);
    // A tiny positive time runs.
    let r = run(&["search", "--method", "bbox", "--dry-run", "--time", "0.2"]);
    r.ran();
    assert!(r.stdout.contains("search bbox"), "{}", r.stdout);
}

// ---------------------------------------------------------------------------
// 8. Method lists

#[test]
fn every_command_takes_method_lists_through_one_parser() {
    let dir = scratch("methods");
    let o = dir.to_str().unwrap();
    // check takes a list (trimmed, repeats dropped).
    let r = run(&["check", "--method", "bbox, lc,bbox", "--cases", "2", "--regime", "static"]);
    r.ran();
    let lines = |m: &str| r.stdout.lines().filter(|l| l.starts_with(m)).count();
    assert!(lines("bbox ") >= 1 && lines("lc ") >= 1, "both methods in the table:\n{}", r.stdout);
    // An unknown id is named, with the known ones, by every command.
    let bad: Vec<Vec<&str>> = vec![
        vec!["check", "--method", "bbox,nope", "--cases", "1"],
        vec!["search", "--method", "nope", "--time", "1", "--dry-run"],
        vec!["tightness", "--method", "bbox,nope", "--size", "16x16", "--no-timing", "--out", o],
        vec!["stability", "--family", "sliver", "--method", "nope,bbox", "--out", o],
    ];
    for c in bad {
        run(&c).usage_error(&["--method", "`nope`", "known ids", "mam2012", "wu2013"]);
    }
    run(&["check", "--method", "bbox,,lc", "--cases", "1"]).usage_error(&["--method", "empty"]);
    // search takes exactly one, through the same parser.
    run(&["search", "--method", "bbox,lc", "--time", "1", "--dry-run"])
        .usage_error(&["--method bbox,lc", "exactly one"]);
    run(&["search", "--method", "all", "--time", "1", "--dry-run"]).usage_error(&["exactly one"]);
    // Broken variants: search, stability and check take them (a gate run on a planted
    // slip measures the gate), power does not (it plants its own); a slip of an
    // unknown method is refused.
    let r = run(&["search", "--method", "broken/shrink/bbox", "--time", "0.2", "--dry-run"]);
    r.ran();
    assert!(r.stdout.contains("broken/shrink/bbox"), "{}", r.stdout);
    let r = run(&["check", "--method", "broken/shrink/bbox", "--cases", "1"]);
    r.no_panic();
    assert!(matches!(r.code, Some(0) | Some(1)) && r.stdout.contains("broken/shrink/bbox"), "{}", r.stdout);
    run(&["check", "--method", "broken/shrink/nope", "--cases", "1"]).usage_error(&["`broken/shrink/nope`"]);
    run(&["power", "--method", "broken/shrink/bbox", "--cases", "1"]).usage_error(&["`broken/shrink/bbox`"]);
    let _ = std::fs::remove_dir_all(&dir);
}

// ---------------------------------------------------------------------------
// 9. Seeds, shards, regimes, margins

#[test]
fn seeds_shards_regimes_and_margins() {
    // The largest seed is an ordinary seed; one beyond is clap's error.
    run(&["check", "--method", "bbox", "--cases", "1", "--seed", "18446744073709551615"]).ran();
    run(&["search", "--method", "bbox", "--time", "0.2", "--dry-run", "--seed", "18446744073709551615"]).ran();
    run(&["check", "--method", "bbox", "--cases", "1", "--seed", "18446744073709551616"]).usage_error(&["--seed"]);
    run(&["check", "--method", "bbox", "--cases", "1", "--seed", "-1"]).usage_error(&["--seed", "-1"]);
    for s in ["0/0", "5/3", "3/3", "a/b", "1", "", "1/2/3", "-1/2", " / "] {
        let flag = format!("--shard={s}");
        run(&["check", "--method", "bbox", "--cases", "1", &flag]).usage_error(&["--shard", s.trim()]);
    }
    run(&["check", "--method", "bbox", "--cases", "1", "--shard", "5/3"]).usage_error(&["--shard 5/3", "below"]);
    run(&["check", "--method", "bbox", "--cases", "4", "--shard", "1/2"]).ran();
    for c in [vec!["check", "--cases", "1"], vec!["search", "--method", "bbox", "--time", "1", "--dry-run"]] {
        let mut c = c.clone();
        c.extend(["--regime", "sideways"]);
        run(&c).usage_error(&["--regime sideways", "focal-crossing"]);
    }
    for m in ["-1", "nan", "inf"] {
        run(&["search", "--method", "bbox", "--time", "1", "--dry-run", "--min-margin", m])
            .usage_error(&["--min-margin", m.trim_start_matches('-')]);
    }
    // (clap takes `-inf` after a space for a flag; with `=` it is the value.)
    run(&["search", "--method", "bbox", "--time", "1", "--dry-run", "--min-margin=-inf"])
        .usage_error(&["--min-margin -inf"]);
    run(&["check", "--method", "bbox", "--cases", "1", "--regime", "static"]).ran();
}

/// Nothing above may leave a scratch file in the repository.
#[test]
fn scratch_files_stay_out_of_the_repository() {
    assert!(!Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/expectationz.json").exists());
}
