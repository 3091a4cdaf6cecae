//! `cullproof merge` validates every shard: real shard reports written by the binary,
//! then copies tampered one way each (impossible counts, a case count of 10^12, a
//! dropped row, another version, shard 7/3 and 0/0, a shard given twice, JSON that is
//! not a report). Each is refused with exit code 2 and an error naming the file and the
//! field, never a panic; the untampered shards still merge into the unsharded run.

#[allow(dead_code)]
mod common;

use common::{Cli, Run};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The scratch directory, emptied on first use.
fn dir() -> PathBuf {
    static D: OnceLock<PathBuf> = OnceLock::new();
    D.get_or_init(|| {
        let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join("merge-shards");
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    })
    .clone()
}

/// `cullproof ARGS` with the corpus's expectations and baseline.
fn cullproof(args: &[&str]) -> Run {
    let ex = root().join("corpus/expectations.json");
    let base = root().join("corpus/baseline.json");
    Cli::new(args).args(&["--expectations", ex.to_str().unwrap(), "--baseline", base.to_str().unwrap()]).run()
}

/// `check` of a small run with `extra` flags, its JSON report written to `name`: unless
/// `extra` says otherwise, bbox and bbox-safe on 48 cases (shard K of 3 gets one case of
/// each of the 16 regimes).
fn check(name: &str, extra: &[&str]) -> PathBuf {
    let p = dir().join(name);
    let mut args = vec!["check", "--seed", "3", "--jobs", "2", "--json"];
    args.push(p.to_str().unwrap());
    for (flag, default) in [("--method", "bbox,bbox-safe"), ("--cases", "48")] {
        if !extra.contains(&flag) {
            args.extend([flag, default]);
        }
    }
    args.extend_from_slice(extra);
    let out = cullproof(&args);
    // 1: a row failed; the report is written all the same
    assert!(matches!(out.code, Some(0 | 1)), "{}", out.stderr);
    p
}

/// Shards 0, 1, 2 of 3 and the unsharded run, written once for every test.
fn shards() -> &'static [PathBuf; 4] {
    static S: OnceLock<[PathBuf; 4]> = OnceLock::new();
    S.get_or_init(|| {
        [
            check("shard-0.json", &["--shard", "0/3"]),
            check("shard-1.json", &["--shard", "1/3"]),
            check("shard-2.json", &["--shard", "2/3"]),
            check("whole.json", &[]),
        ]
    })
}

fn read(p: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

/// A copy of shard 1 named `name`, changed by `f`.
fn tampered(name: &str, f: impl FnOnce(&mut Value)) -> PathBuf {
    tampered_shard(1, name, f)
}

/// A copy of shard `k` named `name`, changed by `f`.
fn tampered_shard(k: usize, name: &str, f: impl FnOnce(&mut Value)) -> PathBuf {
    let mut v = read(&shards()[k]);
    f(&mut v);
    let p = dir().join(name);
    std::fs::write(&p, serde_json::to_string_pretty(&v).unwrap()).unwrap();
    p
}

fn merge(files: &[&Path]) -> Run {
    let mut args = vec!["merge"];
    args.extend(files.iter().map(|p| p.to_str().unwrap()));
    cullproof(&args)
}

/// Merging shard 0, `bad` and shard 2 exits 2 with an error naming `bad` and every
/// one of `words` (the field, the value); the error is returned.
fn refused(bad: &Path, words: &[&str]) -> String {
    let s = shards();
    let out = merge(&[&s[0], bad, &s[2]]);
    let err = out.stderr.clone();
    assert_eq!(out.code, Some(2), "{}: {err}", bad.display());
    assert!(!err.contains("panicked"), "{err}");
    let name = bad.file_name().unwrap().to_str().unwrap();
    assert!(err.contains(name), "the error names the file {name}: {err}");
    for w in words {
        assert!(err.contains(w), "the error says {w:?}: {err}");
    }
    assert!(out.stdout.is_empty(), "no table for a refused merge: {}", out.stdout);
    err
}

/// A row of shard 1 to tamper with.
fn a_row(v: &Value) -> usize {
    assert!(v["rows"].as_array().unwrap().len() > 3);
    3
}

#[test]
fn a_clean_merge_passes_and_is_the_unsharded_run() {
    let s = shards();
    let out_json = dir().join("merged.json");
    let mut args = vec!["merge", "--json", out_json.to_str().unwrap()];
    // any order
    args.extend([&s[2], &s[0], &s[1]].iter().map(|p| p.to_str().unwrap()));
    let out = cullproof(&args);
    let text = &out.stdout;
    assert_eq!(out.code, Some(0), "{text}{}", out.stderr);
    assert!(text.contains("verdict: PASS"), "{text}");
    let (mut merged, mut whole) = (read(&out_json), read(&s[3]));
    merged["seconds"] = Value::Null;
    whole["seconds"] = Value::Null;
    assert_eq!(merged, whole);
    // the fields before `tool` are those of the reports of old, in their order
    let text = std::fs::read_to_string(&s[3]).unwrap();
    let keys: Vec<&str> = text.lines().filter_map(|l| l.strip_prefix("  \"")?.split_once("\":").map(|x| x.0)).collect();
    let old =
        ["seed", "cases", "shard", "run", "rows", "methods", "cross_check", "solver_boxes", "seconds", "baseline"];
    assert_eq!(keys, old.iter().chain(&["tool"]).copied().collect::<Vec<_>>());
    // every report carries the build and the files it used
    let tool = &whole["tool"];
    assert_eq!(tool["version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(tool["expectations"].as_str().unwrap().len(), 16);
    assert_eq!(tool["baseline"].as_str().unwrap().len(), 16);
    for p in &s[..3] {
        assert_eq!(read(p)["tool"], *tool);
    }
}

#[test]
fn impossible_counts_are_refused() {
    let i = a_row(&read(&shards()[1]));
    let p = tampered("proven-exceeds.json", |v| {
        let c = v["rows"][i]["cases"].as_u64().unwrap();
        v["rows"][i]["proven"] = json!(c + 11);
    });
    refused(&p, &[&format!("rows[{i}].proven"), "exceeds cases"]);
    let p = tampered("counts-do-not-add.json", |v| {
        for f in ["proven", "violations", "unproven"] {
            v["rows"][i][f] = json!(0);
        }
    });
    refused(&p, &[&format!("rows[{i}].proven"), "+ violations + unproven", "not cases"]);
    let p = tampered("total-not-the-rows.json", |v| {
        let x = v["methods"][1]["proven"].as_u64().unwrap();
        v["methods"][1]["proven"] = json!(x + 1);
    });
    refused(&p, &["methods[1].proven", "rows add up to"]);
    let p = tampered("witness-too-many.json", |v| {
        v["rows"][i]["f32_witnessed"] = json!(v["rows"][i]["violations"].as_u64().unwrap() + 1);
    });
    refused(&p, &[&format!("rows[{i}].f32_witnessed")]);
    let p = tampered("tail-too-many.json", |v| {
        v["rows"][i]["tail"] = json!(v["rows"][i]["violations"].as_u64().unwrap() + 1);
    });
    refused(&p, &[&format!("rows[{i}].tail"), "exceeds violations"]);
}

#[test]
fn a_case_count_of_ten_to_the_twelve_is_refused() {
    let p = tampered("cases-1e12.json", |v| v["cases"] = json!(1_000_000_000_000u64));
    refused(&p, &["field `cases` = 1000000000000", "draws 16 cases"]);
    // a row of 10^12 cases whose counts add up
    let p = tampered("row-cases-1e12.json", |v| {
        let r = &mut v["rows"][0];
        let rest = r["violations"].as_u64().unwrap() + r["unproven"].as_u64().unwrap();
        r["cases"] = json!(1_000_000_000_000u64);
        r["proven"] = json!(1_000_000_000_000u64 - rest);
    });
    refused(&p, &["rows[0].cases", "has 1 cases of regime"]);
    // the settings themselves
    let p = tampered("settings-1e12.json", |v| v["run"]["settings"]["cases"] = json!(1_000_000_000_000u64));
    refused(&p, &["run.settings.cases"]);
}

#[test]
fn a_dropped_row_is_refused() {
    let p = tampered("dropped-row.json", |v| {
        v["rows"].as_array_mut().unwrap().remove(5);
    });
    refused(&p, &["field `rows`", "no row for method", "dropped"]);
}

#[test]
fn another_build_or_other_files_are_refused() {
    let p = tampered("other-version.json", |v| v["tool"]["version"] = json!("0.0.1-elsewhere"));
    refused(&p, &["tool.version", "0.0.1-elsewhere", "shard-0.json", "different builds"]);
    let p = tampered("no-version.json", |v| {
        v.as_object_mut().unwrap().remove("tool");
    });
    refused(&p, &["field `tool`", "written by a tool without a version; re-run the shard"]);
    let p = tampered("empty-version.json", |v| v["tool"]["version"] = json!(""));
    refused(&p, &["tool.version", "without a version"]);
    let p = tampered("other-expectations.json", |v| v["tool"]["expectations"] = json!("0123456789abcdef"));
    refused(&p, &["tool.expectations"]);
    let p = tampered("no-baseline.json", |v| v["tool"]["baseline"] = Value::Null);
    refused(&p, &["tool.baseline"]);
}

#[test]
fn shard_indices_out_of_range_are_refused() {
    let p = tampered("shard-7-of-3.json", |v| {
        v["shard"] = json!("7/3");
        v["run"]["shard"] = json!([7, 3]);
    });
    refused(&p, &["run.shard", "shard 7 is not below the shard count 3"]);
    let p = tampered("shard-0-of-0.json", |v| {
        v["shard"] = json!("0/0");
        v["run"]["shard"] = json!([0, 0]);
    });
    refused(&p, &["run.shard", "at least 1"]);
    // the two places a shard is written must agree
    let p = tampered("shard-string-7-of-3.json", |v| v["shard"] = json!("7/3"));
    refused(&p, &["field `shard` = \"7/3\"", "run.shard"]);
    let p = tampered("shard-string-garbage.json", |v| v["shard"] = json!("one of three"));
    refused(&p, &["field `shard`"]);
    let p = tampered("shard-huge.json", |v| {
        v["shard"] = json!(format!("1/{}", u64::MAX));
        v["run"]["shard"] = json!([1, u64::MAX]);
    });
    refused(&p, &["cases"]);
}

#[test]
fn every_shard_exactly_once() {
    let s = shards();
    // a copy of shard 0 under another name: both files are named
    let copy = dir().join("copy-of-shard-0.json");
    std::fs::copy(&s[0], &copy).unwrap();
    let out = merge(&[&s[0], &s[1], &s[2], &copy]);
    let err = &out.stderr;
    assert_eq!(out.code, Some(2), "{err}");
    assert!(err.contains("copy-of-shard-0.json: field `run.shard` = 0/3: shard 0 is also"), "{err}");
    assert!(err.contains(&format!("is also {} (each shard once)", s[0].display())), "{err}");
    // the same file twice: both arguments named
    let out = merge(&[&s[0], &s[1], &s[2], &s[0]]);
    let err = &out.stderr;
    assert_eq!(out.code, Some(2), "{err}");
    assert!(
        err.contains("(argument 4)") && err.contains("(argument 1)") && err.contains("the same file given twice"),
        "{err}"
    );
    // one missing
    let out = merge(&[&s[0], &s[2]]);
    let err = &out.stderr;
    assert_eq!(out.code, Some(2), "{err}");
    assert!(err.contains("shard 1/3 is missing"), "{err}");
    // a shard of another count
    let p = check("shard-1-of-2.json", &["--shard", "1/2"]);
    refused(&p, &["field `run.shard` = 1/2", "shard-0.json is a shard of 3"]);
    // or one forged to it
    let p = tampered("shard-1-of-4.json", |v| {
        v["shard"] = json!("1/4");
        v["run"]["shard"] = json!([1, 4]);
    });
    refused(&p, &["field `cases` = 16", "shard 1/4 of a run of 48 cases"]);
}

#[test]
fn settings_that_differ_are_named_by_field() {
    let p = check("centres-1.json", &["--shard", "1/3", "--samples", "centres"]);
    refused(&p, &["field `run.settings.sample_set` = \"centres\"", "shard-0.json", "different runs"]);
    let p = tampered("side-budget.json", |v| v["run"]["settings"]["side_budget"] = json!(1000));
    let e = refused(&p, &["field `run.settings.side_budget` = 1000", "2000"]);
    assert!(!e.contains("Settings {"), "no debug dump: {e}");
    let p = tampered("timed.json", |v| v["run"]["timed"] = json!(true));
    refused(&p, &["run.timed"]);
}

#[test]
fn what_is_not_a_report_is_refused_without_a_panic() {
    let text = std::fs::read_to_string(&shards()[1]).unwrap();
    let cut = dir().join("truncated.json");
    std::fs::write(&cut, &text[..text.len() / 2]).unwrap();
    refused(&cut, &["EOF"]);
    let bytes = dir().join("not-utf8.json");
    std::fs::write(&bytes, [0xff, 0xfe, 0x00, 0x7b]).unwrap();
    refused(&bytes, &["cannot read"]);
    let p = tampered("cases-a-string.json", |v| v["cases"] = json!("many"));
    refused(&p, &["field `cases`"]);
    let p = tampered("cases-too-big.json", |v| v["cases"] = json!(1e30));
    refused(&p, &["field `cases`"]);
    let p = tampered("cases-negative.json", |v| v["cases"] = json!(-16));
    refused(&p, &["field `cases`"]);
    let p = tampered("proven-too-big.json", |v| v["rows"][2]["proven"] = json!(u64::MAX));
    refused(&p, &["rows[2].proven"]);
    let p = tampered("sums-not-a-number.json", |v| v["rows"][2]["sums"]["pass"] = json!("lots"));
    refused(&p, &["rows[2].sums.pass"]);
    let p = tampered("sums-too-big.json", |v| v["rows"][2]["sums"]["admit"] = json!(i128::MAX.to_string()));
    refused(&p, &["rows[2].sums.admit"]);
    // sums beyond 64 bits
    let a = tampered("boxes-max.json", |v| v["solver_boxes"] = json!(u64::MAX));
    let b = tampered_shard(2, "boxes-max-too.json", |v| v["solver_boxes"] = json!(u64::MAX));
    let out = merge(&[&shards()[0], &a, &b]);
    let err = &out.stderr;
    assert_eq!(out.code, Some(2), "{err}");
    assert!(err.contains("boxes-max-too.json: field `solver_boxes`") && err.contains("exceeds 2^64"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    let p = tampered("rows-not-a-list.json", |v| v["rows"] = json!({"a": 1}));
    refused(&p, &["field `rows`"]);
}

#[test]
fn a_witness_from_another_shard_or_regime_is_refused() {
    // a planted slip has a worst witness in every row; shard 1 holds cases 1, 4, 7, ...
    let broken = check("broken-1.json", &["--shard", "1/3", "--method", "broken/shrink/bbox-safe"]);
    let v = read(&broken);
    assert_eq!(v["rows"][0]["regime"], "static");
    assert!(!v["rows"][0]["worst"].is_null());
    refused(&broken, &["field `run.methods`", "different runs"]);
    let write = |name: &str, index: u64| {
        let mut w = v.clone();
        w["rows"][0]["worst"]["case_index"] = json!(index);
        let p = dir().join(name);
        std::fs::write(&p, serde_json::to_string(&w).unwrap()).unwrap();
        p
    };
    // case 0 is shard 0's; case 1 is of regime motion; case 49 is beyond the run
    for (name, i) in [("witness-of-shard-0.json", 0), ("witness-of-motion.json", 1), ("witness-beyond.json", 49)] {
        refused(&write(name, i), &["rows[0].worst.case_index", "not a case of regime static"]);
    }
}

#[test]
fn shards_under_a_viewport_merge_with_their_unplaced_cases() {
    let vp = ["--cases", "96", "--viewport", "1920x1080+64", "--snap", "8"];
    let with = |name: &str, shard: &str| {
        let mut a = vp.to_vec();
        a.extend(["--shard", shard]);
        check(name, &a)
    };
    let s: Vec<PathBuf> = (0..3).map(|k| with(&format!("vp-{k}.json"), &format!("{k}/3"))).collect();
    let whole = with("vp-whole.json", "0/1");
    let outside: Vec<u64> = s.iter().map(|p| read(p)["samples"]["outside_viewport"].as_u64().unwrap()).collect();
    assert!(outside.iter().sum::<u64>() > 0, "some case cannot be placed: {outside:?}");
    let out_json = dir().join("vp-merged.json");
    let mut args = vec!["merge", "--json", out_json.to_str().unwrap()];
    args.extend(s.iter().map(|p| p.to_str().unwrap()));
    let out = cullproof(&args);
    assert_eq!(out.code, Some(0), "{}", out.stderr);
    let (mut merged, mut whole) = (read(&out_json), read(&whole));
    merged["seconds"] = Value::Null;
    whole["seconds"] = Value::Null;
    assert_eq!(merged, whole);
    // the unplaced cases are counted: more of them than the shard's cases is refused
    let k = outside.iter().position(|&o| o > 0).unwrap();
    let mut v = read(&s[k]);
    v["samples"]["outside_viewport"] = json!(1000);
    let bad = dir().join("vp-outside.json");
    std::fs::write(&bad, v.to_string()).unwrap();
    let mut files: Vec<&Path> = s.iter().map(|p| p.as_path()).collect();
    files[k] = &bad;
    let out = merge(&files);
    let err = &out.stderr;
    assert_eq!(out.code, Some(2), "{err}");
    assert!(err.contains("vp-outside.json: field `samples.outside_viewport` = 1000 exceeds the 32 cases"), "{err}");
}
