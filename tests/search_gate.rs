//! `search --gate`: every violation the search finds is held against the method's
//! expected signature (`corpus/expectations.json`); one beyond it is shrunk, written as
//! a case file and fails the run (exit 1), one inside it is only counted. Each test runs
//! the built binary from the repository root with a short `--time`.

#[allow(dead_code)]
mod common;

use common::{scratch, Cli, Run};
use std::path::{Path, PathBuf};

/// `cullproof search --method METHOD --gate` for `time` seconds at `seed` on one job,
/// then `extra`; no deadline (the search stops itself).
fn gated_search(method: &str, time: &str, seed: &str, extra: &[&str]) -> Run {
    Cli::new(&["search", "--method", method, "--gate", "--time", time, "--seed", seed, "--jobs", "1"]).args(extra).run()
}

/// Writes `dir/expectations.json`, a signature for `la2011-safe` (so for its planted
/// slip) that lists every kind the slip can violate with a generous cap, in at most
/// `max_rate` of the cases (`why` says what it is for); then runs the slip's gated
/// search under it in the motion regime (8 s, seed 3) with `extra` flags.
fn slip_under_every_kind(dir: &Path, why: &str, max_rate: &str, extra: &[&str]) -> Run {
    let ex = dir.join("expectations.json");
    let sig = format!(
        r#"{{"expect": "violation", "why": "{why}",
        "bounds": {{"u min": 10, "u max": 10, "v min": 10, "v max": 10, "t min": 10, "t max": 10,
                   "tile culled": "inf", "NaN interval end": "inf"}}, "max_rate": {max_rate}}}"#
    );
    std::fs::write(&ex, format!(r#"{{"la2011-safe": {{"*": {sig}}}}}"#)).unwrap();
    let ex = ex.to_str().unwrap();
    let mut args = vec!["--expectations", ex, "--regime", "motion"];
    args.extend_from_slice(extra);
    gated_search("broken/shrink/la2011-safe", "8", "3", &args)
}

fn json_files(dir: &Path) -> Vec<PathBuf> {
    cullproof::search::case_files(&[dir.to_path_buf()]).unwrap_or_default()
}

/// A planted slip in a method expected conservative (a broken variant is held to the
/// expectations of the method it breaks): any violation is beyond the signature. The
/// search stops at the first finding (--max 1), writes its case file, and exits 1 with
/// a line naming the method, the regime, the kind and the margin; the file replays.
#[test]
fn a_planted_slip_is_beyond_the_signature_and_written() {
    let dir = scratch("slip");
    let report = dir.join("report.json");
    let out = dir.join("cases");
    let id = "broken/shrink/la2011-safe";
    let r = gated_search(
        id,
        "25",
        "3",
        &["--max", "1", "--out", out.to_str().unwrap(), "--json", report.to_str().unwrap()],
    );
    assert_eq!(r.code, Some(1), "stdout:\n{}\nstderr:\n{}", r.stdout, r.stderr);
    let line = r.stdout.lines().find(|l| l.starts_with("beyond the signature:")).unwrap_or_else(|| {
        panic!("no finding line:\n{}", r.stdout);
    });
    assert!(
        line.contains(id) && line.contains("margin") && line.contains("in a regime expected conservative"),
        "{line}"
    );
    let files = json_files(&out);
    assert_eq!(files.len(), 1, "one case file: {files:?}\n{}", r.stdout);
    let cf = cullproof::search::CaseFile::load(&files[0]).unwrap();
    assert_eq!(cf.method, id);
    assert!(cf.note.contains("beyond") && cf.note.contains("signature"), "{}", cf.note);
    let cfg = cullproof::gate::CheckConfig::default_with(cullproof::bounds::registry());
    let rp = cullproof::search::replay(&files[0], &cfg).unwrap();
    assert!(rp.ok, "the written case does not replay: {rp:?}");
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let f = &j["found"][0];
    assert_eq!(f["beyond_signature"], serde_json::json!(true), "{j}");
    assert!(f["cap"].is_null(), "no cap where conservative is expected: {f}");
    assert_eq!(j["gate"], serde_json::json!(true));
    std::fs::remove_dir_all(&dir).ok();
}

/// A clean -safe method stays inside its signature (expected conservative: no
/// violation at all) for a short search: exit 0, nothing found, nothing written.
#[test]
fn a_clean_safe_method_passes_a_short_gated_search() {
    let dir = scratch("safe");
    let out = dir.join("cases");
    let r = gated_search("la2011-safe", "8", "5", &["--out", out.to_str().unwrap()]);
    assert_eq!(r.code, Some(0), "stdout:\n{}\nstderr:\n{}", r.stdout, r.stderr);
    assert!(r.stdout.contains("0 finding(s) beyond the signature"), "{}", r.stdout);
    assert!(json_files(&out).is_empty());
    std::fs::remove_dir_all(&dir).ok();
}

/// `--expectations PATH` is honoured: under a signature that lists every kind the
/// slip can violate with a generous cap, the same slip is inside it: counted, not a
/// finding, exit 0. A missing file is an error naming the flag (exit 2).
#[test]
fn violations_inside_a_given_signature_are_only_counted() {
    let dir = scratch("within");
    let report = dir.join("report.json");
    let out = dir.join("cases");
    let r = slip_under_every_kind(
        &dir,
        "test: a planted slip, every kind listed",
        "1",
        &["--out", out.to_str().unwrap(), "--json", report.to_str().unwrap()],
    );
    assert_eq!(r.code, Some(0), "stdout:\n{}\nstderr:\n{}", r.stdout, r.stderr);
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert!(j["violated_cases"].as_u64().unwrap() > 0, "the slip shows no violation in 8 s: {j}");
    assert_eq!(j["beyond_cases"], serde_json::json!(0), "{j}");
    assert!(j["found"].as_array().unwrap().is_empty(), "{j}");
    assert!(j["kinds"].as_array().unwrap().iter().all(|k| k["beyond_signature"] == serde_json::json!(false)));
    assert!(json_files(&out).is_empty());

    let missing = dir.join("nope.json");
    let r = Cli::new(&[
        "search",
        "--method",
        "la2011",
        "--gate",
        "--dry-run",
        "--time",
        "1",
        "--expectations",
        missing.to_str().unwrap(),
    ])
    .run();
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(r.stderr.contains("--expectations") && r.stderr.contains("nope.json"), "{}", r.stderr);
    std::fs::remove_dir_all(&dir).ok();
}

/// The search's cases as a whole are held to the rest of the signature. A loosened
/// published method (`loose`: every narrowed end moved out by 1e-3) violates nothing,
/// but its proven ends have no covered sample next to them: the tightness signature of
/// the real expectations breaks (per regime and pooled) and the run exits 1 (the
/// breach is a line of the report: no single case witnesses it). A slip inside a signature's kinds and caps
/// but at a higher rate than it allows breaks the rate cap.
#[test]
fn a_looser_or_more_often_wrong_method_breaks_the_signature_as_a_whole() {
    let dir = scratch("whole");
    let report = dir.join("report.json");
    let r = gated_search("broken/loose/la2011", "10", "7", &["--dry-run", "--json", report.to_str().unwrap()]);
    assert_eq!(r.code, Some(1), "stdout:\n{}\nstderr:\n{}", r.stdout, r.stderr);
    assert!(
        r.stdout.lines().any(|l| l.starts_with("beyond the signature: broken/loose/la2011, looser over all regimes:")),
        "{}",
        r.stdout
    );
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert!(!j["breaches"].as_array().unwrap().is_empty(), "{j}");
    assert!(j["regimes"].as_array().unwrap().iter().any(|g| g["tight"]["u min"]["probed"].as_u64() > Some(20)));

    // The clean method on the same seed and time: no breach of the whole.
    let r = gated_search("la2011", "10", "7", &["--dry-run", "--json", report.to_str().unwrap()]);
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert!(j["breaches"].as_array().unwrap().is_empty(), "{}", r.stdout);

    // Rate: every kind listed with a generous cap, but at most 1 % of cases.
    let r = slip_under_every_kind(&dir, "test: a planted slip at a low rate cap", "0.01", &["--dry-run"]);
    assert_eq!(r.code, Some(1), "stdout:\n{}\nstderr:\n{}", r.stdout, r.stderr);
    assert!(
        r.stdout.contains("regime motion: violation rate") && r.stdout.contains("above the cap 0.01"),
        "{}",
        r.stdout
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Two slips whose every violation lies inside the published method's signature are
/// caught by its measured parts: culling covered limit tiles more often (the CoCs
/// swapped in bbox: the limit tiles' violation rate) and culling nothing at all (the
/// CoC dropped from mam2012: the admitted share). The clean methods on the same seed
/// and time leave neither.
#[test]
fn the_measured_parts_catch_slips_inside_the_signature() {
    for (slip, clean, line) in [
        ("broken/swap-coc/bbox", "bbox", "limit tiles violated"),
        ("broken/no-coc-pad/mam2012", "mam2012", "looser: the answers admit"),
    ] {
        let r = gated_search(slip, "8", "5", &["--dry-run"]);
        assert_eq!(r.code, Some(1), "stdout:\n{}\nstderr:\n{}", r.stdout, r.stderr);
        assert!(
            r.stdout
                .lines()
                .any(|l| l.starts_with(&format!("beyond the signature: {slip}, regime")) && l.contains(line)),
            "{}",
            r.stdout
        );
        let r = gated_search(clean, "8", "5", &["--dry-run"]);
        assert!(!r.stdout.contains(line), "{}", r.stdout);
    }
}

/// The tail: a kind above the regime's cap but within the largest cap another regime
/// of the method gives it is counted, written as "in the tail", and fails the search
/// only when the tail passes its rate; without a tail rate it is beyond the signature.
/// `broken/shrink/la2011-safe` pulls every end in by 1e-3: in `motion` each violation
/// is above the cap 1e-9 there and within the cap 10 of `static`.
#[test]
fn a_kind_above_its_regime_cap_is_in_the_tail_and_held_to_its_rate() {
    let kinds = ["u min", "u max", "v min", "v max", "t min", "t max"];
    let caps = |c: &str| kinds.iter().map(|k| format!(r#""{k}": {c}"#)).collect::<Vec<_>>().join(", ");
    let run = |tail: Option<&str>, tag: &str| {
        let dir = scratch(tag);
        let ex = dir.join("expectations.json");
        let rate = tail.map_or(String::new(), |t| format!(r#", "max_tail_rate": {t}"#));
        let row = |c: &str| {
            format!(
                r#"{{"expect": "violation", "why": "tail test", "bounds": {{{}, "tile culled": "inf"}}, "max_rate": 1{rate}}}"#,
                caps(c)
            )
        };
        let text = format!(r#"{{"la2011-safe": {{"motion": {}, "static": {}}}}}"#, row("1e-9"), row("10"));
        std::fs::write(&ex, text).unwrap();
        let report = dir.join("report.json");
        let args = [
            "--expectations",
            ex.to_str().unwrap(),
            "--regime",
            "motion",
            "--dry-run",
            "--json",
            report.to_str().unwrap(),
        ];
        let r = gated_search("broken/shrink/la2011-safe", "6", "3", &args);
        let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
        std::fs::remove_dir_all(&dir).ok();
        (r, j)
    };
    // a tail rate that allows every case: counted and written, never failing
    let (r, j) = run(Some("1"), "tail-all");
    assert_eq!(r.code, Some(0), "stdout:\n{}\nstderr:\n{}", r.stdout, r.stderr);
    let tail = j["tail_cases"].as_u64().unwrap();
    assert!(tail > 0 && j["beyond_cases"] == serde_json::json!(0), "{j}");
    let found = j["found"].as_array().unwrap();
    assert!(!found.is_empty() && found.iter().all(|f| f["tail"] == serde_json::json!(true)), "{j}");
    assert!(found.iter().all(|f| f["beyond_signature"] == serde_json::json!(false)), "{j}");
    let line = r.stdout.lines().find(|l| l.starts_with("in the tail: broken/shrink/la2011-safe, regime motion"));
    assert!(
        line.is_some_and(|l| l.contains("above this regime's cap 1e-9") && l.contains("largest cap 1e1")),
        "{}",
        r.stdout
    );
    // a tail rate the slip passes: the search fails with a tail breach
    let (r, j) = run(Some("0.0001"), "tail-few");
    assert_eq!(r.code, Some(1), "stdout:\n{}", r.stdout);
    let b = j["breaches"].as_array().unwrap();
    assert!(b.iter().any(|b| b.as_str().unwrap().starts_with("tail: ")), "{j}");
    // no tail rate: beyond the signature
    let (r, j) = run(None, "tail-none");
    assert_eq!(r.code, Some(1), "stdout:\n{}", r.stdout);
    assert_eq!(j["tail_cases"], serde_json::json!(0), "{j}");
    assert!(j["found"].as_array().unwrap().iter().any(|f| f["beyond_signature"] == serde_json::json!(true)), "{j}");
}
