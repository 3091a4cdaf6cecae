//! Fail before work (issue 24, item 4): an output path that cannot be written is an
//! error before the run (exit 2, naming the option and the path), never after it; a
//! user's file at an output path survives a failed run; replay samples any finite tile;
//! a process bound's huge answer line and an OBJ face of millions of references end in
//! short, clear errors. Each runs the built binary from the repository root under a
//! deadline; a run that would check its outputs only at the end is given work that
//! takes far longer than the deadline, so it can pass only by failing first.

#[allow(dead_code)]
mod common;

use common::{scratch, Cli, Run};
use std::path::Path;
use std::time::Duration;

/// Every invocation here is an error before any work, or a tiny run.
const DEADLINE: Duration = Duration::from_secs(60);

/// `cullproof ARGS` under [`DEADLINE`]; running past it fails the test.
fn run(args: &[&str]) -> Run {
    Cli::new(args).deadline(DEADLINE).late_means("the error did not come before the work").run()
}

impl Run {
    /// Exit 2 with every `needle` on stderr, and nothing on stdout (no work reported).
    fn fails_first(&self, needles: &[&str]) -> &Self {
        self.no_panic();
        assert_eq!(self.code, Some(2), "{}: expected exit 2, stderr:\n{}", self.what, self.stderr);
        for n in needles {
            assert!(self.stderr.contains(n), "{}: stderr does not name `{n}`:\n{}", self.what, self.stderr);
        }
        assert!(self.stdout.is_empty(), "{}: work was reported before the error:\n{}", self.what, self.stdout);
        self
    }
}

fn entries(d: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(d).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

const NO_DIR: &str = "/nonexistent-dir-cullproof";

// ---------------------------------------------------------------------------
// 1. Output paths are checked before the run

/// A million cases take hours; the error must come first.
#[test]
fn check_refuses_an_unwritable_junit_or_json_path_before_running_cases() {
    let x = format!("{NO_DIR}/x.xml");
    let r = run(&["check", "--method", "bbox", "--cases", "1000000", "--junit", &x]);
    r.fails_first(&["--junit", &x, "does not exist"]);
    assert!(!Path::new(&x).exists());
    let j = format!("{NO_DIR}/r.json");
    run(&["check", "--method", "bbox", "--cases", "1000000", "--json", &j]).fails_first(&["--json", &j]);
    // A directory is not a file.
    let d = scratch("check-dir");
    let ds = d.to_str().unwrap();
    run(&["check", "--method", "bbox", "--cases", "1000000", "--junit", ds]).fails_first(&["--junit", ds, "directory"]);
    // The witness directory beside the XML file must be a directory.
    std::fs::write(d.join("gate.witnesses"), "mine").unwrap();
    let g = d.join("gate.xml");
    run(&["check", "--method", "bbox", "--cases", "1000000", "--junit", g.to_str().unwrap()]).fails_first(&[
        "--junit",
        "gate.witnesses",
        "not a directory",
    ]);
    // --write-baseline: the baseline's directory, and a run that can have a baseline.
    let b = format!("{NO_DIR}/b.json");
    run(&["check", "--method", "bbox", "--cases", "1000000", "--write-baseline", "--baseline", &b])
        .fails_first(&["--baseline", &b]);
    run(&["check", "--method", "bbox", "--time", "3600", "--write-baseline"])
        .fails_first(&["--write-baseline", "--time"]);
    assert_eq!(entries(&d), ["gate.witnesses"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn every_command_checks_its_outputs_before_its_work() {
    let d = scratch("every");
    let file = d.join("a-file");
    std::fs::write(&file, "mine").unwrap();
    let f = file.to_str().unwrap();
    let under_file = format!("{f}/sub");
    let j = format!("{NO_DIR}/r.json");
    let o = d.join("out");
    let o = o.to_str().unwrap();
    let cases: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (vec!["oracle-agree", "--samples", "1000000000000", "--json", &j], vec!["--json", &j]),
        (vec!["search", "--method", "bbox", "--time", "600", "--json", &j], vec!["--json", &j]),
        (vec!["search", "--method", "bbox", "--time", "600", "--out", f], vec!["--out", f, "not a directory"]),
        (vec!["search", "--method", "bbox", "--time", "600", "--out", &under_file], vec!["--out", &under_file]),
        (vec!["power", "--method", "bbox", "--cases", "1000000", "--json", &j], vec!["--json", &j]),
        (vec!["replay", "--json", &j], vec!["--json", &j]),
        (vec!["merge", "no-such-shard.json", "--json", &j], vec!["--json", &j]),
        (vec!["merge", "no-such-shard.json", "--junit", &j], vec!["--junit", &j]),
        (vec!["prove", "--method", "bbox", "--symbolic", "--json", &j], vec!["--json", &j]),
        (vec!["prove", "--method", "bbox", "--symbolic", "--out", f], vec!["--out", f]),
        (vec!["prove", "--method", "bbox", "--symbolic", "--dry-run", "--emit-smt", f], vec!["--emit-smt", f]),
        (vec!["tightness", "--scene", "hairball", "--size", "320x240", "--out", o, "--json", &j], vec!["--json", &j]),
        (vec!["tightness", "--scene", "hairball", "--out", &under_file], vec!["--out", &under_file]),
        (vec!["stability", "--family", "focal", "--cases", "999999", "--out", o, "--json", &j], vec!["--json", &j]),
        (vec!["stability", "--family", "focal", "--cases", "999999", "--out", f], vec!["--out", f]),
    ];
    for (args, needles) in cases {
        run(&args).fails_first(&needles);
    }
    // explain never overwrites: an existing --svg file is refused before the case is read.
    let case = "corpus/cases/bbox/2b5e6ecce17e44fe.json";
    run(&["explain", case, "--svg", f]).fails_first(&["--svg", f, "exists"]);
    let svg = format!("{NO_DIR}/x.svg");
    run(&["explain", case, "--svg", &svg]).fails_first(&["--svg", &svg]);
    // Nothing was created on the way (the probe files are gone, --out was not made).
    assert_eq!(entries(&d), ["a-file"]);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine");
    let _ = std::fs::remove_dir_all(&d);
}

// ---------------------------------------------------------------------------
// 2. A user's file survives a failed run

#[test]
fn an_existing_json_file_is_not_destroyed_when_the_run_fails() {
    let d = scratch("keep");
    let p = d.join("report.json");
    let ps = p.to_str().unwrap();
    std::fs::write(&p, "my notes").unwrap();
    // Failed before the run: another output is unwritable.
    let x = format!("{NO_DIR}/x.xml");
    run(&["check", "--method", "bbox", "--cases", "1000000", "--json", ps, "--junit", &x]).fails_first(&["--junit"]);
    assert_eq!(std::fs::read_to_string(&p).unwrap(), "my notes");
    // Failed during the run: a process bound that exits on its first request.
    let dies = "read l; echo '{\"protocol\":1,\"id\":\"dies-early\"}'; read l";
    let r = run(&["--exec", dies, "check", "--method", "dies-early", "--cases", "8", "--jobs", "1", "--json", ps]);
    r.no_panic();
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(r.stderr.contains("dies-early") && r.stderr.contains("closed its output"), "{}", r.stderr);
    assert_eq!(std::fs::read_to_string(&p).unwrap(), "my notes");
    assert_eq!(entries(&d), ["report.json"]);
    // A run that succeeds replaces it with the whole report, and leaves no temporary file.
    run(&["check", "--method", "bbox", "--cases", "1", "--json", ps]).ran();
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(text.starts_with('{') && text.contains("\"rows\""), "{}", &text[..text.len().min(200)]);
    assert_eq!(entries(&d), ["report.json"]);
    let _ = std::fs::remove_dir_all(&d);
}

// ---------------------------------------------------------------------------
// 3. Replay samples any finite tile

#[test]
fn replay_takes_a_case_whose_tile_is_wider_than_f32_max() {
    let d = scratch("huge-tile");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("corpus/cases/bbox/2b5e6ecce17e44fe.json")).unwrap();
    let m = f32::MAX as f64;
    // bbox (tile test only), lb2011 and mam2012-hyperplane-ps (per-sample constraints,
    // judged on samples drawn in the tile), la2011 (lens and time intervals).
    let methods = ["bbox", "lb2011", "mam2012-hyperplane-ps", "la2011"];
    for id in methods {
        let mut cf: serde_json::Value = serde_json::from_str(&text).unwrap();
        cf["method"] = id.into();
        cf["tile"] = serde_json::json!({"x0": -m, "y0": -m, "x1": m, "y1": m});
        cf["expected"] = "conservative".into();
        cf["witness"] = serde_json::Value::Null;
        std::fs::write(d.join(format!("{id}.json")), serde_json::to_string_pretty(&cf).unwrap()).unwrap();
    }
    let r = run(&["replay", d.to_str().unwrap()]);
    r.ran();
    assert!(r.stdout.contains("4 file(s)"), "{}", r.stdout);
    for id in methods {
        assert!(r.stdout.contains(&format!("{id}.json")), "{}", r.stdout);
    }
    // And explain, which samples the same tile.
    run(&["explain", d.join("lb2011.json").to_str().unwrap()]).ran();
    let _ = std::fs::remove_dir_all(&d);
}

// ---------------------------------------------------------------------------
// 4. A process bound's huge answer line

const TEN_MB: &str = "head -c 10000000 /dev/zero | tr '\\0' x; echo";

#[test]
fn a_ten_megabyte_answer_line_gets_an_error_shorter_than_a_kilobyte() {
    // As the greeting.
    let r = run(&["--exec", TEN_MB, "check", "--method", "x", "--cases", "1"]);
    r.fails_first(&["greeting", "longer than 1048576 bytes"]);
    assert!(r.stderr.len() < 1024, "{} bytes:\n{}", r.stderr.len(), &r.stderr[..r.stderr.len().min(2000)]);
    // As the answer to a tile request.
    let cmd = format!("read l; echo '{{\"protocol\":1,\"id\":\"ten-mb\"}}'; read l; {TEN_MB}");
    let r = run(&["--exec", &cmd, "check", "--method", "ten-mb", "--cases", "1", "--jobs", "1"]);
    r.fails_first(&["exec bound `ten-mb`", "\"op\":\"tile\"", "longer than 1048576 bytes"]);
    assert!(r.stderr.len() < 1024, "{} bytes:\n{}", r.stderr.len(), &r.stderr[..r.stderr.len().min(2000)]);
}

/// A bad answer under the line limit is quoted in part: the message holds the request
/// (to reproduce it) and at most a bounded prefix of the answer.
#[test]
fn a_bad_answer_is_quoted_in_part() {
    let cmd = "read l; echo '{\"protocol\":1,\"id\":\"bad-big\"}'; read l; head -c 500000 /dev/zero | tr '\\0' y; echo";
    let r = run(&["--exec", cmd, "check", "--method", "bad-big", "--cases", "1", "--jobs", "1"]);
    r.fails_first(&["does not parse", "(500000 bytes)"]);
    let request = r.stderr.find("{\"op\"").and_then(|a| r.stderr[a..].find("}: ").map(|b| a + b + 1)).unwrap_or(0);
    assert!(r.stderr.len() < request + 1024, "{} bytes:\n{}", r.stderr.len(), &r.stderr[..r.stderr.len().min(3000)]);
    // An error answer with a long message.
    let py = "import sys, json\nsys.stdin.readline()\nprint(json.dumps({\"protocol\": 1, \"id\": \"long-error\"}), \
              flush=True)\nfor l in sys.stdin:\n    print(json.dumps({\"n\": json.loads(l)[\"n\"], \"error\": \"e\" * \
              500000}), flush=True)\n";
    let cmd = format!("python3 -c '{py}'");
    let r = run(&["--exec", &cmd, "check", "--method", "long-error", "--cases", "1", "--jobs", "1"]);
    r.fails_first(&["the process reported: eee", "(500000 bytes)"]);
    assert!(r.stderr.len() < 3000, "{} bytes", r.stderr.len());
    // A greeting that does not parse.
    let r = run(&["--exec", "head -c 300000 /dev/zero | tr '\\0' z; echo", "check", "--method", "x", "--cases", "1"]);
    r.fails_first(&["greeting answer \"zzz", "(300000 bytes)"]);
    assert!(r.stderr.len() < 1024, "{} bytes", r.stderr.len());
}

// ---------------------------------------------------------------------------
// 5. An OBJ face of millions of references

#[test]
fn an_obj_face_of_two_million_references_gets_the_cap_error() {
    let d = scratch("obj");
    let obj = d.join("huge-face.obj");
    let mut text = String::from("# one face of 2,000,000 vertex references\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf");
    for i in 0..2_000_000 {
        text += [" 1", " 2", " 3"][i % 3];
    }
    text += "\nf 1 2 3\n";
    std::fs::write(&obj, &text).unwrap();
    let out = d.join("out");
    let r = run(&[
        "tightness",
        "--scene",
        obj.to_str().unwrap(),
        "--size",
        "16x16",
        "--spp",
        "1",
        "--no-timing",
        "--out",
        out.to_str().unwrap(),
    ]);
    r.fails_first(&["huge-face.obj:5:", "2000000 vertex references", "at most 1024"]);
    assert!(r.stderr.len() < 1024, "{} bytes:\n{}", r.stderr.len(), &r.stderr[..r.stderr.len().min(2000)]);
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&d);
}
