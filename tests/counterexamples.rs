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
