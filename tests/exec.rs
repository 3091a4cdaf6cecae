//! Bounds in another process (`--exec`, docs/protocol.md): the Python example is proven
//! conservative, its planted bug is caught, its declared constraint is certified, and a
//! process that fails is reported, never taken for an answer.

#[allow(dead_code)]
mod common;

use common::Cli;
use cullproof::bounds::Method;
use cullproof::gate::{run, CheckConfig, CheckReport, Expectations};
use std::path::Path;
use std::time::Duration;

fn python(args: &str) -> String {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/python/bbox_exec.py");
    format!("python3 {} {args}", script.display())
}

fn start(command: &str) -> &'static dyn Method {
    cullproof::external::exec::start(command, Duration::from_secs(30)).expect("the process starts and greets")
}

fn gate(m: &'static dyn Method, cases: u64) -> CheckReport {
    let mut cfg = CheckConfig::default_with(vec![m]);
    cfg.cases = cases;
    run(&cfg, &Expectations::default(), false)
}

fn totals(r: &CheckReport) -> (u64, u64, u64) {
    r.rows.iter().fold((0, 0, 0), |a, x| (a.0 + x.proven, a.1 + x.violations, a.2 + x.unproven))
}

#[test]
fn the_python_bound_is_proven_conservative() {
    let m = start(&python(""));
    assert_eq!(m.info().id, "py-bbox");
    assert!(m.info().outputs.tile_reject && !m.info().outputs.per_sample);
    let r = gate(m, 960);
    assert_eq!(totals(&r), (960, 0, 0));
    assert!(r.rows.iter().map(|x| x.limit_tiles).sum::<u64>() > 50);
    assert!(!r.failed());
}

#[test]
fn the_planted_bug_in_the_python_bound_is_caught() {
    let m = start(&python("--broken"));
    assert_eq!(m.info().id, "py-bbox-broken");
    let r = gate(m, 960);
    assert!(totals(&r).1 > 10, "{:?}", totals(&r));
    assert!(r.failed());
}

/// A declared affine constraint is certified (proven, not unproven), like a built-in one.
#[test]
fn a_declared_constraint_is_certified() {
    let m = start(&python("--constraint"));
    let r = gate(m, 480);
    assert_eq!(totals(&r), (480, 0, 0));
}

/// The panic payload of a run that must stop.
fn stops(f: impl FnOnce() -> CheckReport) -> Box<dyn std::any::Any + Send> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)) {
        Ok(_) => panic!("the run must stop"),
        Err(e) => e,
    }
}

fn fails_with(command: &str, cases: u64, want: &str) {
    let m = start(command);
    let e = stops(|| gate(m, cases));
    let msg = e.downcast_ref::<cullproof::external::exec::ExecFailure>().expect("an ExecFailure payload").0.clone();
    assert!(msg.starts_with("exec bound ") && msg.contains(want), "{msg}");
    assert!(msg.contains("\"op\":\"tile\""), "the request is named: {msg}");
}

const HELLO: &str = r#"import sys, json
sys.stdin.readline()
print(json.dumps({"protocol": 1, "id": "t"}), flush=True)
"#;

#[test]
fn a_process_that_exits_is_reported_with_the_request() {
    let cmd = format!("python3 -c '{HELLO}sys.stdin.readline()'");
    fails_with(&cmd, 4, "closed its output");
}

#[test]
fn an_error_answer_is_reported_with_its_message() {
    let body = r#"for line in sys.stdin:
    print(json.dumps({"n": json.loads(line)["n"], "error": "no idea"}), flush=True)"#;
    fails_with(&format!("python3 -c '{HELLO}{body}'"), 4, "the process reported: no idea");
}

#[test]
fn an_inverted_interval_is_reported_with_its_field() {
    let body = r#"for line in sys.stdin:
    print(json.dumps({"n": json.loads(line)["n"], "t": [0.75, 0.25]}), flush=True)"#;
    fails_with(
        &format!("python3 -c '{HELLO}{body}'"),
        4,
        "answer field `t` = [0.75, 0.25]: an interval needs lo <= hi",
    );
}

#[test]
fn a_silent_process_is_reported_after_the_timeout() {
    let cmd = format!("python3 -c '{HELLO}import time\ntime.sleep(60)'");
    let m = cullproof::external::exec::start(&cmd, Duration::from_secs(3)).unwrap();
    let e = stops(|| gate(m, 2));
    let msg = e.downcast_ref::<cullproof::external::exec::ExecFailure>().expect("an ExecFailure payload").0.clone();
    assert!(msg.contains("no answer within 3 s"), "{msg}");
}

#[test]
fn a_bad_greeting_is_an_error_naming_the_command() {
    let e = cullproof::external::exec::start("python3 -c 'print(\"{}\")'", Duration::from_secs(10)).err().unwrap();
    assert!(format!("{e:#}").contains("missing field `protocol`"), "{e:#}");
    let e = cullproof::external::exec::start(
        "python3 -c 'import json; print(json.dumps({\"protocol\": 9, \"id\": \"x\"}))'",
        Duration::from_secs(10),
    )
    .err()
    .unwrap();
    assert!(format!("{e:#}").contains("protocol version 9"), "{e:#}");
}

/// `--exec` with no `--method` gates only the plugged bound, not every built-in method.
#[test]
fn exec_alone_gates_only_the_plugged_bound() {
    let json = std::env::temp_dir().join(format!("cullproof-exec-alone-{}.json", std::process::id()));
    let out =
        Cli::new(&["--exec", &python(""), "check", "--cases", "16", "--jobs", "1", "--json", json.to_str().unwrap()])
            .run();
    assert_eq!(out.code, Some(0), "{}\n{}", out.stdout, out.stderr);
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).expect("JSON");
    std::fs::remove_file(&json).ok();
    let mut ids: Vec<String> =
        j["rows"].as_array().unwrap().iter().map(|r| r["method"].as_str().unwrap().to_string()).collect();
    ids.dedup();
    assert_eq!(ids, vec!["py-bbox".to_string()], "{ids:?}");
}

/// A failing row of the JUnit report names its witness with the command that re-judges
/// it, and that command loads the same `--exec` bound: run as printed, it replays the
/// case against the bound (no "unknown method").
#[test]
fn the_junit_hint_loads_the_exec_bound() {
    let dir = std::env::temp_dir().join(format!("cullproof-exec-junit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let xml = dir.join("gate.xml");
    let out =
        Cli::new(&["--exec", &python("--broken"), "check", "--cases", "320", "--junit", xml.to_str().unwrap()]).run();
    assert_eq!(out.code, Some(1), "the planted bug fails the gate\n{}\n{}", out.stdout, out.stderr);
    let text = std::fs::read_to_string(&xml).expect("the JUnit file");
    let text = text.replace("&apos;", "'").replace("&quot;", "\"").replace("&lt;", "<").replace("&gt;", ">");
    let text = text.replace("&amp;", "&");
    let start = text.find("re-judge: ").expect("a witness with its re-judge hint") + "re-judge: ".len();
    let hint = &text[start..start + text[start..].find(';').unwrap()];
    assert!(hint.starts_with("cullproof --exec '") && hint.contains(" replay "), "{hint}");
    let cmd = hint.replacen("cullproof", env!("CARGO_BIN_EXE_cullproof"), 1);
    let replay = std::process::Command::new("sh")
        .arg("-c")
        .arg(&cmd)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("sh runs");
    let (o, e) = (String::from_utf8_lossy(&replay.stdout), String::from_utf8_lossy(&replay.stderr));
    std::fs::remove_dir_all(&dir).ok();
    assert!(matches!(replay.status.code(), Some(0 | 1)), "{cmd}\n{o}\n{e}");
    assert!(o.contains("py-bbox-broken") && !e.contains("unknown"), "{cmd}\n{o}\n{e}");
}
