//! The tightness signature fails a loosened answer at settings that have no stored
//! baseline: one end (t max) moved out by 1e-3 at seed 2 x 2,400 cases, while the same
//! method unchanged passes there.

#[allow(dead_code)]
mod common;

use common::Cli;

/// The exit code and stdout of `check` of `method` on 2,400 cases at seed 2.
fn gate(method: &str) -> (Option<i32>, String) {
    let out = Cli::new(&["check", "--seed", "2", "--cases", "2400", "--method", method]).run();
    (out.code, out.stdout)
}

#[test]
fn one_loosened_end_fails_without_a_baseline() {
    let (code, text) = gate("la2011-safe");
    assert_eq!(code, Some(0), "{text}");
    assert!(text.contains("baseline: none stored for these settings"), "{text}");
    assert!(!text.contains("looser"), "{text}");
    let (code, text) = gate("broken/loose-t-max/la2011-safe");
    assert_eq!(code, Some(1), "{text}");
    assert!(text.contains("looser over all regimes: `t max`"), "{text}");
    // the other ends were not moved: no line names them
    assert!(!text.contains("`u min`") && !text.contains("`t min`"), "{text}");
}
