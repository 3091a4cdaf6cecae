//! CI at scale: shard reports merge into the report of the unsharded run (the same JSON,
//! number for number, whatever the order the shards come in), bad shard sets are
//! refused with errors naming the file, and the JUnit XML has one test case per method
//! x regime with failing rows naming a witness file that replays.

use cullproof::bounds::{by_id, Method};
use cullproof::gate::baseline::BaselineFile;
use cullproof::gate::junit;
use cullproof::gate::{merge, run_with_baseline, CheckConfig, CheckReport, Expectations};
use std::path::{Path, PathBuf};

fn expectations() -> Expectations {
    Expectations::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/expectations.json")).unwrap()
}

fn methods() -> Vec<&'static dyn Method> {
    let mut v: Vec<&'static dyn Method> =
        ["bbox", "bbox-safe", "la2011", "wu2013", "mam2012-hyperplane"].iter().map(|id| by_id(id).unwrap()).collect();
    v.push(cullproof::bounds::broken::parse("broken/shrink/bbox-safe").unwrap());
    v
}

fn config() -> CheckConfig {
    let mut cfg = CheckConfig::default_with(methods());
    cfg.cases = 150;
    cfg.seed = 5;
    cfg
}

/// The JSON of a report without its wall time (the only field a merge cannot repeat).
fn comparable(r: &CheckReport) -> serde_json::Value {
    let mut v = serde_json::to_value(r).unwrap();
    v["seconds"] = serde_json::Value::Null;
    v
}

fn scratch(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Run shard k of n and write its JSON report as `check --json` does.
fn shard(dir: &Path, k: u64, n: u64, base: Option<&BaselineFile>) -> PathBuf {
    let mut cfg = config();
    cfg.shard = (k, n);
    let r = run_with_baseline(&cfg, &expectations(), base, false);
    let p = dir.join(format!("shard{k}of{n}.json"));
    std::fs::write(&p, serde_json::to_string_pretty(&r).unwrap()).unwrap();
    p
}

fn load(paths: &[PathBuf]) -> Vec<(PathBuf, CheckReport)> {
    paths.iter().map(|p| (p.clone(), merge::load_report(p).unwrap())).collect()
}

#[test]
fn shards_merge_into_the_unsharded_report() {
    let dir = scratch("ci-merge");
    let ex = expectations();
    let whole = run_with_baseline(&config(), &ex, None, false);
    // the run has violations, unproven cases and failing rows: a merge has work to do
    assert!(whole.rows.iter().any(|r| r.violations > 0) && whole.failed());
    let paths: Vec<PathBuf> = (0..3).map(|k| shard(&dir, k, 3, None)).collect();
    let merged = merge::merge(load(&paths), &ex, None).unwrap();
    assert_eq!(comparable(&merged), comparable(&whole));
    assert_eq!(
        cullproof::gate::render(&merged).lines().skip(1).collect::<Vec<_>>(),
        cullproof::gate::render(&whole).lines().skip(1).collect::<Vec<_>>()
    );
    // any order
    let rev: Vec<PathBuf> = paths.iter().rev().cloned().collect();
    assert_eq!(comparable(&merge::merge(load(&rev), &ex, None).unwrap()), comparable(&whole));
    // a single shard of one is the run itself
    let one = shard(&dir, 0, 1, None);
    assert_eq!(comparable(&merge::merge(load(&[one]), &ex, None).unwrap()), comparable(&whole));
}

#[test]
fn merge_refuses_what_is_not_one_run() {
    let dir = scratch("ci-refuse");
    let ex = expectations();
    let a = shard(&dir, 0, 2, None);
    let b = shard(&dir, 1, 2, None);
    let err = |paths: &[PathBuf]| format!("{:#}", merge::merge(load(paths), &ex, None).unwrap_err());
    let e = err(std::slice::from_ref(&a));
    assert!(e.contains("shard 1/2 is missing"), "{e}");
    let e = err(&[a.clone(), a.clone()]);
    assert!(e.contains("also") && e.contains("shard0of2.json"), "{e}");
    // another seed
    let mut cfg = config();
    cfg.seed = 6;
    cfg.shard = (1, 2);
    let r = run_with_baseline(&cfg, &ex, None, false);
    let c = dir.join("other.json");
    std::fs::write(&c, serde_json::to_string(&r).unwrap()).unwrap();
    let e = err(&[a.clone(), c]);
    assert!(e.contains("other.json") && e.contains("run.settings"), "{e}");
    // not a report at all
    let bad = dir.join("bad.json");
    std::fs::write(&bad, r#"{"seed": 1, "cases": "many"}"#).unwrap();
    let e = format!("{:#}", merge::load_report(&bad).unwrap_err());
    assert!(e.contains("bad.json") && e.contains("cases"), "{e}");
    assert!(merge::merge(load(&[a, b]), &ex, None).is_ok());
}

#[test]
fn junit_has_a_case_per_row_and_failures_name_a_replayable_witness() {
    let dir = scratch("ci-junit");
    let ex = expectations();
    let r = run_with_baseline(&config(), &ex, None, false);
    let path = dir.join("gate.xml");
    junit::write(&r, &path, "").unwrap();
    let xml = std::fs::read_to_string(&path).unwrap();
    assert!(xml.starts_with("<?xml"));
    assert_eq!(xml.matches("<testcase ").count(), r.rows.len());
    assert_eq!(xml.matches("</testcase>").count(), r.rows.len());
    let failing: Vec<_> = r.rows.iter().filter(|x| x.status.fails()).collect();
    assert!(!failing.is_empty());
    assert_eq!(xml.matches("<failure ").count(), failing.len());
    // every suite states its method's strongest verdict
    assert_eq!(xml.matches("<property name=\"strength\"").count(), r.methods.len());
    assert!(xml.contains("value=\"machine-checked for all inputs in ranges\""), "bbox-safe has a proof");
    assert!(xml.contains("<property name=\"strength\" value=\"violated\"/>"), "the planted slip is violated");
    // the planted slip fails with a witness file that replays as a violation
    let broken = failing.iter().find(|x| x.method == "broken/shrink/bbox-safe" && x.worst.is_some()).expect("caught");
    let wdir = junit::witness_dir(&path);
    let files = cullproof::search::case_files(std::slice::from_ref(&wdir)).unwrap();
    assert!(!files.is_empty());
    let named: Vec<&PathBuf> = files.iter().filter(|f| xml.contains(&*f.display().to_string())).collect();
    assert_eq!(named.len(), files.len(), "every witness file is named in the XML");
    let mine = files
        .iter()
        .find(|f| {
            let cf = cullproof::search::CaseFile::load(f).unwrap();
            cf.method == broken.method && cf.provenance.regime == broken.regime
        })
        .expect("the broken row's witness file");
    let rep = cullproof::search::replay(mine, &config()).unwrap();
    assert!(rep.ok, "{rep:?}");
    // a second write keeps the files (never overwritten) and gives the same XML
    junit::write(&r, &path, "").unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), xml);
}
