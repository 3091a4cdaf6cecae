//! The library's counterexample calls on a bound of the caller's own (in no
//! registry): the example `examples/find_and_replay.rs` run as a test. A bound that
//! forgets the lens is found violated, shrunk, written under the caller's directory,
//! explained and replayed ("still violated"); its fixed version replayed on the same
//! file comes out "fixed".

#[path = "../examples/find_and_replay.rs"]
#[allow(dead_code)]
mod example;

use std::path::Path;

#[test]
fn a_rust_bound_is_found_shrunk_written_explained_and_replayed_through_the_library() {
    let dir = std::env::temp_dir().join(format!("cullproof-lib-cx-{}", std::process::id()));
    let o = example::walk(&dir, 60.0).unwrap();
    assert!(o.file.starts_with(&dir) && o.file.is_file(), "{}", o.file.display());
    assert!(o.file.to_string_lossy().contains("screen-box"), "{}", o.file.display());
    assert!(o.explained.starts_with("screen-box ("), "{}", o.explained);
    assert!(o.explained.contains("the method says: tile empty (culled)"), "{}", o.explained);
    assert_eq!(o.before, "still violated");
    assert_eq!(o.after, "fixed");
    // Nothing went into the project's corpus.
    assert!(!Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/cases/screen-box").exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// The gate hands out every counterexample (bounded per regime, all counted) and
/// writes them as case files on request; each file replays as still violated.
#[test]
fn the_gate_returns_every_counterexample_and_writes_them_on_request() {
    use cullproof::counterexamples::replay;
    use cullproof::{Gate, Regime};
    let slip = cullproof::bounds::broken::parse("broken/shrink/la2011").unwrap();
    let r = Gate::new()
        .method_ref(cullproof::bounds::shared(slip))
        .regimes(&[Regime::Motion, Regime::Both])
        .cases(80)
        .jobs(2)
        .run();
    let m = &r.methods[0];
    assert!(m.violated > 40, "{}", r.render());
    assert_eq!(m.every_counterexample.len() as u64, m.violated.min(2 * cullproof::gate::row::EXAMPLES_PER_ROW as u64));
    assert_eq!(m.counterexamples.len(), 2);
    // in regime order, then case order
    let keys: Vec<(usize, u64)> = m
        .every_counterexample
        .iter()
        .map(|c| (Regime::ALL.iter().position(|x| *x == c.regime).unwrap(), c.case_index))
        .collect();
    assert!(keys.windows(2).all(|w| w[0] < w[1]), "{keys:?}");
    let dir = std::env::temp_dir().join(format!("cullproof-gate-cases-{}", std::process::id()));
    let files = r.write_cases(&dir).unwrap();
    assert_eq!(files.len(), m.every_counterexample.len());
    for f in files.iter().take(4) {
        assert!(f.is_file(), "{}", f.display());
        assert_eq!(replay(f, slip).unwrap().outcome, "still violated", "{}", f.display());
    }
    std::fs::remove_dir_all(&dir).ok();
}
