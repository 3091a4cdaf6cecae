//! Bounds written in C, loaded through `include/cullproof.h`: the conservative one is
//! proven by the gate, the broken one is caught, shrunk to a case file, and the file
//! replays through the plugin.

use cullproof::bounds::{by_id, plug, Method};
use cullproof::check::{run, CheckConfig, Expectations};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

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
        let safe = cullproof::plugin::load(&build(false)).expect("load the safe plugin");
        let broken = cullproof::plugin::load(&build(true)).expect("load the broken plugin");
        plug(safe).unwrap();
        plug(broken).unwrap();
        (safe, broken)
    })
}

fn gate(m: &'static dyn Method, cases: u64) -> cullproof::check::CheckReport {
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
        let (_, case, tile) = cullproof::check::make_case(&cfg, i);
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
        cullproof::corpus::search(&cfg, cullproof::bounds::shared(broken), 30.0, 1, 0.0, Some(&out), false).unwrap();
    assert_eq!(s.found.len(), 1, "{s:?}");
    let file = PathBuf::from(s.found[0].file.as_ref().expect("a case file was written"));
    assert!(file.starts_with(out.join("c-bbox-broken")), "{}", file.display());
    let rep = cullproof::corpus::replay(&file, &cfg).unwrap();
    assert!(rep.ok, "{rep:?}");
    assert_eq!(rep.method, "c-bbox-broken");
    assert!(rep.judged.starts_with("violation"), "{}", rep.judged);
}

/// Write a C source into the test's target directory and compile it.
fn compile_text(text: &str, name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("plugins");
    std::fs::create_dir_all(&dir).unwrap();
    let src = dir.join(format!("{name}.c"));
    std::fs::write(&src, text).unwrap();
    compile(&src, &format!("lib{name}.so"), &[])
}

fn refusal(path: &Path) -> String {
    match cullproof::plugin::load(path) {
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
    let ok = cullproof::plugin::load(&compile_text(&table("CULLPROOF_ABI_VERSION", "tile"), "minimal")).unwrap();
    assert_eq!(ok.info().id, "x");
}
