//! Bounds written in C, loaded through `include/cullproof.h`: the conservative one is
//! proven by the gate, the broken one is caught, shrunk to a case file, and the file
//! replays through the plugin.

#[allow(dead_code)]
mod common;

use cullproof::bounds::{by_id, plug, Method};
use cullproof::gate::{run, CheckConfig, Expectations};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Duration;

/// Compile `examples/c/bbox_safe.c` into a shared library (with `-DCULLPROOF_BROKEN`
/// for the broken one) in this test's target directory.
fn build(broken: bool) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let name = if broken { "libc_bbox_broken.so" } else { "libc_bbox_safe.so" };
    compile(&root.join("examples/c/bbox_safe.c"), name, if broken { &["-DCULLPROOF_BROKEN"] } else { &[] })
}

/// Compile one C file into a shared library named `name` in this test's target
/// directory, with the repository's `include/` on the path.
fn compile(src: &Path, name: &str, defines: &[&str]) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("plugins");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join(name);
    // cc reads the target from cargo's build-script environment; a test names the host.
    let rustc = std::process::Command::new(std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into()))
        .arg("-vV")
        .output()
        .expect("rustc -vV");
    let host = String::from_utf8_lossy(&rustc.stdout)
        .lines()
        .find_map(|l| l.strip_prefix("host: ").map(str::to_string))
        .expect("rustc -vV names the host");
    let compiler =
        cc::Build::new().opt_level(2).debug(false).cargo_metadata(false).target(&host).host(&host).get_compiler();
    let mut cmd = compiler.to_command();
    cmd.args(["-shared", "-fPIC", "-ffp-contract=off", "-Wall", "-Wextra", "-Werror"])
        .arg("-I")
        .arg(root.join("include"))
        .arg("-o")
        .arg(&out)
        .arg(src)
        .arg("-lm")
        .args(defines);
    let st = cmd.status().expect("a C compiler");
    assert!(st.success(), "compiling the C bound failed: {cmd:?}");
    out
}

/// Both plugins, loaded and known by their ids (once per test process).
fn plugins() -> (&'static dyn Method, &'static dyn Method) {
    static P: OnceLock<(&'static dyn Method, &'static dyn Method)> = OnceLock::new();
    *P.get_or_init(|| {
        let safe = cullproof::external::plugin::load(&build(false)).expect("load the safe plugin");
        let broken = cullproof::external::plugin::load(&build(true)).expect("load the broken plugin");
        plug(safe).unwrap();
        plug(broken).unwrap();
        (safe, broken)
    })
}

fn gate(m: &'static dyn Method, cases: u64) -> cullproof::gate::CheckReport {
    let mut cfg = CheckConfig::default_with(vec![m]);
    cfg.cases = cases;
    run(&cfg, &Expectations::default(), false)
}

#[test]
fn the_c_bound_is_known_by_its_own_id() {
    let (safe, broken) = plugins();
    assert_eq!(safe.info().id, "c-bbox-safe");
    assert_eq!(broken.info().id, "c-bbox-broken");
    assert!(by_id("c-bbox-safe").is_some() && by_id("c-bbox-broken").is_some());
    assert!(safe.info().outputs.tile_reject && !safe.info().outputs.per_sample);
    assert!(safe.info().source.contains("plugin"), "{}", safe.info().source);
    // An id cannot be taken twice.
    assert!(plug(safe).is_err());
}

#[test]
fn the_gate_proves_the_c_bbox_safe_conservative() {
    let (safe, _) = plugins();
    let r = gate(safe, 1920);
    let (proven, violations, unproven): (u64, u64, u64) =
        r.rows.iter().fold((0, 0, 0), |a, x| (a.0 + x.proven, a.1 + x.violations, a.2 + x.unproven));
    assert_eq!(violations, 0, "{:#?}", r.rows.iter().filter(|x| x.violations > 0).collect::<Vec<_>>());
    assert_eq!(unproven, 0);
    assert_eq!(proven, 1920);
    // The limit tiles were judged, so the reject itself was tested at its f32 limit.
    assert!(r.rows.iter().map(|x| x.limit_tiles).sum::<u64>() > 100);
    assert!(!r.failed());
}

/// The C bound answers as the built-in bbox-safe does, tile for tile.
#[test]
fn the_c_bbox_safe_agrees_with_the_built_in_one() {
    let (safe, _) = plugins();
    let built_in = by_id("bbox-safe").unwrap();
    let cfg = CheckConfig::default_with(vec![built_in]);
    let mut culled = 0;
    for i in 0..2000 {
        let (_, case, tile) = cullproof::cases::make_case(&cfg.draw(), i);
        let tri = case.triangle;
        let (a, b) = (safe.setup(&tri), built_in.setup(&tri));
        assert_eq!(a.disabled().is_some(), b.disabled().is_some());
        let w = tile.x1 - tile.x0;
        for d in [-8.0f32, -2.0, -1.0, 0.0, 1.0, 2.0, 8.0] {
            let t = cullproof::model::Tile { x0: tile.x0 + d * w, x1: tile.x1 + d * w, ..tile };
            let (ea, eb) = (
                matches!(a.tile(&t), cullproof::bounds::TileResult::Empty),
                matches!(b.tile(&t), cullproof::bounds::TileResult::Empty),
            );
            assert_eq!(ea, eb, "case {i}, tile {t:?}");
            culled += ea as u32;
        }
    }
    assert!(culled > 100, "the comparison must include culled tiles ({culled})");
}

#[test]
fn the_broken_c_bound_is_caught_shrunk_and_replayed() {
    let (_, broken) = plugins();
    let r = gate(broken, 960);
    assert!(r.failed());
    assert!(r.rows.iter().map(|x| x.violations).sum::<u64>() > 10);
    // The search shrinks a violation to a case file, which replays through the plugin.
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("plugin-cases");
    let _ = std::fs::remove_dir_all(&out);
    let cfg = CheckConfig::default_with(vec![broken]);
    let s =
        cullproof::search::search(&cfg, cullproof::bounds::shared(broken), 30.0, 1, 0.0, Some(&out), false).unwrap();
    assert_eq!(s.found.len(), 1, "{s:?}");
    let file = PathBuf::from(s.found[0].file.as_ref().expect("a case file was written"));
    assert!(file.starts_with(out.join("c-bbox-broken")), "{}", file.display());
    let rep = cullproof::search::replay(&file, &cfg).unwrap();
    assert!(rep.ok, "{rep:?}");
    assert_eq!(rep.method, "c-bbox-broken");
    assert!(rep.judged.starts_with("violation"), "{}", rep.judged);
}

/// Write a C source into the test's target directory and compile it.
fn compile_text(text: &str, name: &str) -> PathBuf {
    compile_text_with(text, name, &[])
}

/// [`compile_text`] with compiler flags (`-D...`).
fn compile_text_with(text: &str, name: &str, defines: &[&str]) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("plugins");
    std::fs::create_dir_all(&dir).unwrap();
    let src = dir.join(format!("{name}.c"));
    std::fs::write(&src, text).unwrap();
    compile(&src, &format!("lib{name}.so"), defines)
}

fn refusal(path: &Path) -> String {
    match cullproof::external::plugin::load(path) {
        Ok(m) => panic!("{} loaded as {}", path.display(), m.info().id),
        Err(e) => format!("{e:#}"),
    }
}

#[test]
fn a_missing_file_is_refused_with_its_name() {
    let e = refusal(Path::new("/nonexistent/libnothing.so"));
    assert!(e.contains("/nonexistent/libnothing.so") && e.contains("cannot load"), "{e}");
}

#[test]
fn a_library_without_the_entry_point_is_refused() {
    let lib = compile_text("int not_a_bound(void) { return 1; }\n", "no_entry");
    let e = refusal(&lib);
    assert!(e.contains("no `cullproof_method` symbol") && e.contains("libno_entry.so"), "{e}");
}

#[test]
fn a_library_of_another_abi_version_or_without_a_tile_test_is_refused() {
    let table = |version: &str, tile: &str| {
        format!(
            "#include \"cullproof.h\"\n\
             static void *setup(const cp_triangle *t, const char **d) {{ (void)t; (void)d; return 0; }}\n\
             static int32_t tile(const void *s, const cp_tile *t, cp_bounds *o) {{ (void)s; (void)t; (void)o; return CP_BOUNDS; }}\n\
             static const cp_method m = {{ .abi_version = {version}, .id = \"x\", .source = \"test\", \
             .outputs = CP_OUT_TILE_REJECT, .setup = setup, .tile = {tile} }};\n\
             const cp_method *cullproof_method(void) {{ (void)tile; return &m; }}\n"
        )
    };
    let e = refusal(&compile_text(&table("99", "tile"), "abi99"));
    assert!(e.contains("ABI version 99") && e.contains("speaks version 1"), "{e}");
    let e = refusal(&compile_text(&table("CULLPROOF_ABI_VERSION", "0"), "no_tile"));
    assert!(e.contains("`setup` and `tile` are required"), "{e}");
    // The same table with its tile test loads.
    let ok =
        cullproof::external::plugin::load(&compile_text(&table("CULLPROOF_ABI_VERSION", "tile"), "minimal")).unwrap();
    assert_eq!(ok.info().id, "x");
}

// ---- Plugins held to their limits: caps, the watchdog, contract breaches. ----

/// A run that must stop with exit code 2 and a message within `deadline`, never a panic
/// or an abort.
fn stops_with(args: &[&str], deadline: Duration, needles: &[&str]) -> Duration {
    let common::Run { code, stderr: err, took, .. } = common::run(args, deadline);
    assert_eq!(code, Some(2), "cullproof {}: exit {code:?} (a signal leaves none), stderr:\n{err}", args.join(" "));
    assert!(!err.contains("panicked"), "{err}");
    for n in needles {
        assert!(err.contains(n), "stderr lacks {n:?}:\n{err}");
    }
    took
}

/// A bound that sleeps 100 s in `tile()` (or, with -DSLEEP_IN_SETUP, in `setup()`).
const SLEEPER: &str = r#"#include "cullproof.h"
#include <unistd.h>
static void *setup(const cp_triangle *t, const char **d) {
    (void)t; (void)d;
#ifdef SLEEP_IN_SETUP
    sleep(100);
#endif
    return 0;
}
static int32_t tile(const void *s, const cp_tile *t, cp_bounds *o) {
    (void)s; (void)t; (void)o;
    sleep(100);
    return CP_BOUNDS;
}
static const cp_method m = { .abi_version = CULLPROOF_ABI_VERSION, .id = ID, .source = "test: sleeps",
    .outputs = CP_OUT_TILE_REJECT, .setup = setup, .tile = tile };
const cp_method *cullproof_method(void) { return &m; }
"#;

#[test]
fn a_hung_plugin_call_stops_the_run_within_the_timeout() {
    for (name, defines, call) in [
        ("sleep_tile", &["-DID=\"c-sleep-tile\""][..], "tile()"),
        ("sleep_setup", &["-DID=\"c-sleep-setup\"", "-DSLEEP_IN_SETUP"][..], "setup()"),
    ] {
        let lib = compile_text_with(SLEEPER, name, defines);
        let id = defines[0].trim_start_matches("-DID=").trim_matches('"');
        let lib = lib.to_str().unwrap();
        let took = stops_with(
            &["check", "--plugin", lib, "--method", id, "--cases", "4", "--jobs", "1", "--plugin-timeout", "1"],
            Duration::from_secs(60),
            &[lib, id, &format!("{call} did not return within 1 s"), "--plugin-timeout"],
        );
        // 1 s of timeout, at most 0.1 s until the watchdog looks again, start-up.
        assert!(took < Duration::from_secs(10), "{call}: stopped after {took:?}");
    }
}

#[test]
fn the_plugin_timeout_is_checked_like_the_exec_timeout() {
    // Checked before any library is loaded.
    for (t, shown) in [("0", "0"), ("-1", "-1"), ("nan", "NaN"), ("inf", "inf"), ("1e9", "1000000000")] {
        stops_with(
            &["methods", "--plugin", "/nonexistent/libx.so", &format!("--plugin-timeout={t}")],
            Duration::from_secs(60),
            &[&format!("--plugin-timeout {shown}")],
        );
    }
}

/// A bound that answers 4e9 constraints.
const HUGE: &str = r#"#include "cullproof.h"
static void *setup(const cp_triangle *t, const char **d) { (void)t; (void)d; return 0; }
static int32_t tile(const void *s, const cp_tile *t, cp_bounds *o) {
    (void)s; (void)t;
    o->n_constraints = 4000000000u;
    return CP_BOUNDS;
}
static float eval(const void *ts, uint32_t m, const cp_sample *s) { (void)ts; (void)m; (void)s; return 1.0f; }
static const cp_method m = { .abi_version = CULLPROOF_ABI_VERSION, .id = "c-huge", .source = "test: 4e9 constraints",
    .outputs = CP_OUT_PER_SAMPLE, .setup = setup, .tile = tile, .eval = eval };
const cp_method *cullproof_method(void) { return &m; }
"#;

#[test]
fn too_many_constraints_stop_the_run_with_a_clear_error() {
    let lib = compile_text(HUGE, "huge");
    let lib = lib.to_str().unwrap();
    stops_with(
        &["check", "--plugin", lib, "--method", "c-huge", "--cases", "4", "--jobs", "1"],
        Duration::from_secs(120),
        &[&format!("plugin {lib} (`c-huge`): tile() answered n_constraints = 4000000000, more than the cap 4096")],
    );
    // A library caller gets the failure as a panic payload, before any allocation.
    let m = cullproof::external::plugin::load(Path::new(lib)).unwrap();
    let cfg = CheckConfig::default_with(vec![m]);
    let (_, case, tile) = cullproof::cases::make_case(&cfg.draw(), 0);
    let p = m.setup(&case.triangle);
    let Err(e) = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| p.tile(&tile))) else {
        panic!("the tile test stops")
    };
    let f = e.downcast_ref::<cullproof::external::plugin::PluginFailure>().expect("a PluginFailure payload");
    assert!(f.0.contains("n_constraints = 4000000000") && f.0.contains("cap 4096"), "{}", f.0);
}

/// A bound whose answers break the contract: on tiles with an odd floor(x0) the lens
/// interval u has a NaN end, on the others the time interval is inverted.
const BREACH: &str = r#"#include "cullproof.h"
#include <math.h>
static void *setup(const cp_triangle *t, const char **d) { (void)t; (void)d; return 0; }
static int32_t tile(const void *s, const cp_tile *t, cp_bounds *o) {
    (void)s;
    if ((long long)floorf(t->x0) & 1) {
        o->u[0] = NAN;
    } else {
        o->t[0] = 0.75f;
        o->t[1] = 0.25f;
    }
    return CP_BOUNDS;
}
static const cp_method m = { .abi_version = CULLPROOF_ABI_VERSION, .id = "c-breach", .source = "test: NaN and lo > hi",
    .outputs = CP_OUT_LENS | CP_OUT_TIME, .setup = setup, .tile = tile };
const cp_method *cullproof_method(void) { return &m; }
"#;

fn breach_plugin() -> &'static dyn Method {
    static P: OnceLock<&'static dyn Method> = OnceLock::new();
    *P.get_or_init(|| {
        cullproof::external::plugin::load(&compile_text(BREACH, "breach")).expect("load the breaching plugin")
    })
}

#[test]
fn contract_breaches_are_counted_and_judged_fail_safe() {
    let m = breach_plugin();
    let r = gate(m, 480);
    // A NaN end or an inverted interval culls everything: the covered samples it culls
    // are violations, and the gate fails, as before the breaches were counted.
    let (proven, violations, unproven): (u64, u64, u64) =
        r.rows.iter().fold((0, 0, 0), |a, x| (a.0 + x.proven, a.1 + x.violations, a.2 + x.unproven));
    assert!(violations > 100, "{proven} {violations} {unproven}");
    assert!(r.failed());
    let b = r.contract_breaches.iter().find(|b| b.method == "c-breach").expect("c-breach's breaches are reported");
    let (nan, inverted) = (b.kinds["tile-nan-end"], b.kinds["tile-lo-above-hi"]);
    assert!(nan > 0 && inverted > 0, "{b:?}");
    assert_eq!(b.answers, nan + inverted, "{b:?}");
    assert!(b.line().contains("answers broke the contract"), "{}", b.line());
    // The conservative C bound breaks nothing.
    let (safe, _) = plugins();
    let r = gate(safe, 96);
    assert!(r.contract_breaches.iter().all(|b| b.method != "c-bbox-safe"), "{:?}", r.contract_breaches);
}

#[test]
fn the_command_line_reports_contract_breaches_on_stderr_and_in_json() {
    let lib = compile_text(BREACH, "breach_cli");
    let json = Path::new(env!("CARGO_TARGET_TMPDIR")).join("breach-report.json");
    let common::Run { code, stderr: err, .. } = common::run(
        &[
            "check",
            "--plugin",
            lib.to_str().unwrap(),
            "--method",
            "c-breach",
            "--cases",
            "96",
            "--jobs",
            "1",
            "--json",
            json.to_str().unwrap(),
        ],
        Duration::from_secs(300),
    );
    assert_eq!(code, Some(1), "the gate fails on the violations, stderr:\n{err}");
    let line = err.lines().find(|l| l.contains("(`c-breach`)")).unwrap_or_else(|| panic!("no breach line:\n{err}"));
    assert!(line.starts_with("warning: plugin ") && line.contains("answers broke the contract"), "{line}");
    assert!(line.contains("NaN interval end") && line.contains("lo > hi"), "{line}");
    let r: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let b = &r["contract_breaches"][0];
    assert_eq!(b["method"], "c-breach");
    assert!(b["answers"].as_u64().unwrap() > 0, "{b}");
}

/// A bound whose tile test answers 7 left of x = 0, and otherwise two constraints whose
/// enclosures are not intervals (a NaN end; lo > hi) and whose first name has no NUL
/// within the cap.
const BREACH_BOX: &str = r#"#include "cullproof.h"
#include <math.h>
#include <string.h>
static char long_name[2048];
static void *setup(const cp_triangle *t, const char **d) { (void)t; (void)d; return 0; }
static int32_t tile(const void *s, const cp_tile *t, cp_bounds *o) {
    (void)s;
    if (t->x0 < 0.0f) return 7;
    o->n_constraints = 2;
    return CP_BOUNDS;
}
static float eval(const void *ts, uint32_t m, const cp_sample *s) { (void)ts; (void)m; (void)s; return 1.0f; }
static int32_t eval_box(const void *ts, uint32_t m, const cp_sample_box *b, cp_interval *out) {
    (void)ts; (void)b;
    if (m == 0) { out->lo = NAN; out->hi = 1.0; } else { out->lo = 2.0; out->hi = 1.0; }
    return 1;
}
static const char *name(const void *ts, uint32_t m) { (void)ts; return m == 0 ? long_name : "ok"; }
static const cp_method m = { .abi_version = CULLPROOF_ABI_VERSION, .id = "c-breach-box", .source = "test",
    .outputs = CP_OUT_PER_SAMPLE, .setup = setup, .tile = tile, .eval = eval, .eval_box = eval_box,
    .constraint_name = name };
const cp_method *cullproof_method(void) {
    memset(long_name, 'a', sizeof long_name - 1);
    return &m;
}
"#;

#[test]
fn bad_answer_codes_enclosures_and_long_names_are_caught() {
    use cullproof::bounds::{SampleBox, TileResult};
    use cullproof::Interval;
    let m = cullproof::external::plugin::load(&compile_text(BREACH_BOX, "breach_box")).unwrap();
    let cfg = CheckConfig::default_with(vec![m]);
    let (_, case, _) = cullproof::cases::make_case(&cfg.draw(), 0);
    let p = m.setup(&case.triangle);
    let t = |x0: f32| cullproof::model::Tile { x0, y0: 0.0, x1: x0 + 1.0, y1: 1.0 };
    assert!(matches!(p.tile(&t(-4.0)), TileResult::Empty), "an answer of 7 is taken as CP_EMPTY");
    let TileResult::Bounds(b) = p.tile(&t(4.0)) else { panic!("CP_BOUNDS") };
    assert_eq!(b.constraints.len(), 2);
    let whole = Interval::new(f64::NEG_INFINITY, f64::INFINITY);
    let unit = Interval::new(0.0, 1.0);
    let sb = SampleBox { x: Interval::new(4.0, 5.0), y: unit, u: unit, v: unit, t: unit };
    for c in &b.constraints {
        let e = c.eval_box(&sb);
        assert_eq!((e.lo, e.hi), (whole.lo, whole.hi), "a non-interval encloses nothing");
    }
    assert_eq!(b.constraints[1].name(), "ok");
    let e = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| b.constraints[0].name())).err().unwrap();
    let f = e.downcast_ref::<cullproof::external::plugin::PluginFailure>().expect("a PluginFailure payload");
    assert!(f.0.contains("constraint_name() returned a name with no NUL within 1024 bytes"), "{}", f.0);
    let all = cullproof::external::plugin::breaches();
    let r = all.iter().find(|b| b.method == "c-breach-box").unwrap();
    assert_eq!(r.answers, 3, "{r:?}");
    for k in ["tile-answer-code", "eval-box-nan-end", "eval-box-lo-above-hi"] {
        assert_eq!(r.kinds[k], 1, "{k}: {r:?}");
    }
}

/// A bound built as with fast-math options: its library sets flush-to-zero and
/// denormals-are-zero when it loads, and its tile test sets them again on every call.
/// It answers the whole domain (conservative).
const FTZ: &str = r#"#include "cullproof.h"
#include <xmmintrin.h>
static void ftz_on(void) { _mm_setcsr(_mm_getcsr() | 0x8040); }
__attribute__((constructor)) static void at_load(void) { ftz_on(); }
static void *setup(const cp_triangle *t, const char **d) { (void)t; (void)d; return 0; }
static int32_t tile(const void *s, const cp_tile *t, cp_bounds *o) {
    (void)s; (void)t; (void)o;
    ftz_on();
    return CP_BOUNDS;
}
static const cp_method m = { .abi_version = CULLPROOF_ABI_VERSION, .id = "c-ftz", .source = "test: FTZ/DAZ",
    .outputs = CP_OUT_LENS | CP_OUT_TIME, .setup = setup, .tile = tile };
const cp_method *cullproof_method(void) { return &m; }
"#;

/// The claims assume round to nearest with gradual underflow. A plugin that sets
/// flush-to-zero / denormals-are-zero (at load or in a call) is reported as a contract
/// breach (`fp-environment`), and the environment is reset before any further work:
/// neither our exact oracles nor the next call run under it.
#[cfg(target_arch = "x86_64")]
#[test]
fn a_plugin_that_sets_flush_to_zero_is_reported_and_the_environment_reset() {
    #[allow(deprecated)]
    fn mxcsr() -> u32 {
        // SAFETY: reading MXCSR cannot fault on x86-64.
        unsafe { std::arch::x86_64::_mm_getcsr() }
    }
    let m = cullproof::external::plugin::load(&compile_text(FTZ, "ftz")).expect("load the FTZ plugin");
    assert_eq!(mxcsr() & 0x8040, 0, "the loading thread runs without FTZ/DAZ after the load");
    let after_load = cullproof::external::plugin::breaches();
    let b = after_load.iter().find(|b| b.method == "c-ftz").expect("the load is reported");
    assert_eq!(b.kinds["fp-environment"], 1, "{b:?}");
    let r = gate(m, 48);
    assert_eq!(mxcsr() & 0x8040, 0, "this thread runs without FTZ/DAZ after the calls");
    let b = r.contract_breaches.iter().find(|b| b.method == "c-ftz").expect("the calls are reported");
    assert!(b.kinds["fp-environment"] >= 48, "{b:?}");
    assert!(b.line().contains("flush-to-zero"), "{}", b.line());
    // The answers themselves (the whole domain) are judged as given: proven.
    assert!(r.rows.iter().all(|x| x.violations == 0), "{:?}", r.rows.iter().map(|x| x.violations).collect::<Vec<_>>());
}

/// From an empty directory outside the checkout, with only the built binary: the
/// broken C plugin is gated (fails), searched (its case file lands in the directory's
/// own corpus), explained, and replayed with `--method` against the broken bound (still
/// violated) and the fixed one (fixed); the project's corpus is unchanged.
#[test]
fn a_c_plugin_is_gated_searched_replayed_and_explained_from_an_empty_directory() {
    let (safe, broken) = (build(false), build(true));
    let d = common::scratch("plugin-anywhere");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    assert!(!d.canonicalize().unwrap().starts_with(root.canonicalize().unwrap()));
    let project: Vec<PathBuf> = cullproof::search::case_files(&[root.join("corpus/cases")]).unwrap();
    let (safe, broken) = (safe.to_str().unwrap(), broken.to_str().unwrap());
    let run = |args: &[&str]| {
        let r = common::Cli::new(args).dir(&d).deadline(Duration::from_secs(300)).run();
        r.no_panic();
        r
    };
    let r = run(&["--plugin", broken, "check", "--method", "c-bbox-broken", "--cases", "96"]);
    assert_eq!(r.code, Some(1), "{}{}", r.stdout, r.stderr);
    assert!(r.stdout.contains("UNEXPECTED VIOLATION"), "{}", r.stdout);
    let r = run(&["--plugin", broken, "search", "--method", "c-bbox-broken", "--time", "10", "--max", "1"]);
    assert_eq!(r.code, Some(0), "{}{}", r.stdout, r.stderr);
    let written = cullproof::search::case_files(&[d.join("cullproof-corpus/cases/c-bbox-broken")]).unwrap();
    assert_eq!(written.len(), 1, "{}", r.stdout);
    let file = written[0].to_str().unwrap();
    let r = run(&["--plugin", broken, "explain", file]);
    assert_eq!(r.code, Some(0), "{}{}", r.stdout, r.stderr);
    assert!(r.stdout.starts_with("c-bbox-broken (") && r.stdout.contains("a VIOLATION"), "{}", r.stdout);
    let r = run(&["--plugin", broken, "replay", "--method", "c-bbox-broken"]);
    assert_eq!(r.code, Some(1), "{}{}", r.stdout, r.stderr);
    assert!(r.stdout.contains("still violated"), "{}", r.stdout);
    let r = run(&["--plugin", broken, "--plugin", safe, "replay", "--method", "c-bbox-safe"]);
    assert_eq!(r.code, Some(0), "{}{}", r.stdout, r.stderr);
    assert!(r.stdout.contains("fixed"), "{}", r.stdout);
    assert_eq!(cullproof::search::case_files(&[root.join("corpus/cases")]).unwrap(), project);
    std::fs::remove_dir_all(&d).ok();
}
