//! Which build wrote a report, and with which expectations and baseline: what
//! `cullproof merge` holds equal across the shards of one run.
//!
//! The expectations and the baseline are named by a 64-bit FNV-1a hash of their loaded
//! contents written back as JSON (maps in key order, so the text, and the hash, depend
//! only on what the run used, not on the file's layout or on a change after loading).

use super::expect::Expectations;
use serde::{Deserialize, Serialize};

/// The version of this build (the crate's).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The tool that wrote a report.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ToolInfo {
    /// The crate version of the build (empty: unknown).
    #[serde(default)]
    pub version: String,
    /// [`hash`] of the expectations the rows were held against.
    #[serde(default)]
    pub expectations: Option<String>,
    /// [`hash`] of the baseline file loaded (None: no baseline file).
    #[serde(default)]
    pub baseline: Option<String>,
}

impl ToolInfo {
    /// This build, with these expectations and the baseline file loaded, given by its
    /// [`hash`] (None: no baseline file). The baseline comes as its hash so that this
    /// file needs nothing of `baseline.rs`, which reads reports (and a report holds a
    /// `ToolInfo`).
    pub fn of(ex: &Expectations, baseline: Option<String>) -> ToolInfo {
        ToolInfo { version: VERSION.to_string(), expectations: Some(hash(ex)), baseline }
    }
}

/// 64-bit FNV-1a of the bytes, as 16 hex digits.
pub fn fnv1a64(bytes: &[u8]) -> String {
    let h = bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| (h ^ b as u64).wrapping_mul(0x100_0000_01b3));
    format!("{h:016x}")
}

/// [`fnv1a64`] of a value's JSON text.
pub fn hash<T: Serialize>(v: &T) -> String {
    fnv1a64(&serde_json::to_vec(v).unwrap_or_default())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv_matches_the_reference_values() {
        assert_eq!(fnv1a64(b""), "cbf29ce484222325");
        assert_eq!(fnv1a64(b"a"), "af63dc4c8601ec8c");
        assert_eq!(fnv1a64(b"foobar"), "85944171f73967e8");
    }
}
