//! Where the commands find their files, so that `cullproof` runs from any directory
//! (`cargo install --path .` and run it anywhere).
//!
//! - **The expectations and the baseline.** `corpus/expectations.json` and
//!   `corpus/baseline.json` are built into the binary (the `cullproof` command includes
//!   them when it is built; the files in the repository stay the source of truth), and
//!   given here as [`BuiltIn`]. `--expectations FILE` / `--baseline FILE` name another
//!   file, anywhere. Without them:
//!   - in the cullproof checkout ([`is_checkout`]: the current directory holds the
//!     `Cargo.toml` of the package `cullproof`) the files on disk are read, exactly as
//!     before: an edit counts at once, `check --write-baseline` rewrites
//!     `corpus/baseline.json`, a missing expectations file is an error. When a file
//!     differs from the copy built in (a binary built before the file changed), the
//!     file is used and a note says so ([`Located::note`]), so the two never differ
//!     silently;
//!   - anywhere else the built-in copies are used; `check --write-baseline` then needs
//!     `--baseline FILE` (there is no file to rewrite).
//!
//!   Built-in expectations list built-in method ids only: a plugged bound
//!   (`--plugin`, `--exec`) has no row, and a method with no row is expected
//!   conservative in every regime, in the checkout and out of it alike.
//! - **The user's corpus of case files.** `--corpus DIR` ([`corpus_dir`]; default
//!   [`CHECKOUT_CORPUS`] in the checkout, [`USER_CORPUS`] in the current directory
//!   anywhere else, never the project's corpus from outside): `search` and `prove`
//!   write case files to `DIR/cases/<method>/<hash>.json`, `replay` with no paths
//!   replays `DIR/cases`, and `explain ID` looks an id up there ([`case_path`]).

use crate::gate::baseline::BaselineFile;
use crate::gate::Expectations;
use anyhow::{bail, Result};
use std::path::{Path, PathBuf};

/// The expectations file of the checkout, relative to its root.
pub const EXPECTATIONS_FILE: &str = "corpus/expectations.json";
/// The baseline file of the checkout, relative to its root.
pub const BASELINE_FILE: &str = "corpus/baseline.json";
/// The corpus directory in the checkout: the project's own.
pub const CHECKOUT_CORPUS: &str = "corpus";
/// The corpus directory anywhere else (in the current directory).
pub const USER_CORPUS: &str = "cullproof-corpus";

/// The texts of `corpus/expectations.json` and `corpus/baseline.json` as the binary was
/// built with them.
#[derive(Clone, Copy, Debug)]
pub struct BuiltIn {
    pub expectations: &'static str,
    pub baseline: &'static str,
}

/// Is `dir` the cullproof checkout: does it hold a `Cargo.toml` whose `[package]`
/// table is named `cullproof`? (A `corpus/` directory alone is not enough: a user's
/// project may have one of its own.)
pub fn is_checkout(dir: &Path) -> bool {
    let Ok(text) = std::fs::read_to_string(dir.join("Cargo.toml")) else { return false };
    package_name(&text).as_deref() == Some("cullproof")
}

/// The `name` of the `[package]` table of a `Cargo.toml` text (the subset of TOML a
/// manifest uses for it: `name = "..."` or `name = '...'` on one line).
fn package_name(toml: &str) -> Option<String> {
    let mut in_package = false;
    for line in toml.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            let header = line.split('#').next().unwrap_or("").trim();
            in_package = header.strip_prefix('[').and_then(|h| h.strip_suffix(']')).map(str::trim) == Some("package");
            continue;
        }
        if !in_package {
            continue;
        }
        let Some((key, value)) = line.split_once('=') else { continue };
        if key.trim() != "name" {
            continue;
        }
        let value = value.trim();
        let quote = value.chars().next().filter(|c| *c == '"' || *c == '\'')?;
        let rest = &value[1..];
        return rest.find(quote).map(|end| rest[..end].to_string());
    }
    None
}

/// Is the current directory the cullproof checkout ([`is_checkout`])?
pub fn in_checkout() -> bool {
    is_checkout(Path::new("."))
}

/// What was loaded, what it is called in messages and reports, and a note to print
/// when it is a file of the checkout that differs from the copy built in.
#[derive(Debug)]
pub struct Located<T> {
    pub value: T,
    /// The file's path, or `built-in corpus/...json`.
    pub name: String,
    pub note: Option<String>,
}

/// The name of a built-in copy in messages.
fn built_in_name(file: &str) -> String {
    format!("built-in {file}")
}

fn differs_note(file: &str, flag: &str) -> String {
    format!(
        "note: {file} differs from the copy built into this binary; using the file (rebuild to build it in, or pass \
         {flag} FILE to choose another)"
    )
}

/// The expectations: `given` (`--expectations FILE`), else the checkout's file, else the
/// built-in copy. A file that does not exist is an error naming it when `required` (the
/// reason, said in the error), and `Ok(None)` otherwise (`search` without `--gate` then
/// annotates nothing, as before). `known` says which method ids exist (the built-in ones
/// and the plugged ones).
pub fn expectations(
    given: Option<&Path>,
    required: Option<&str>,
    in_checkout: bool,
    built_in: &BuiltIn,
    known: &dyn Fn(&str) -> bool,
) -> Result<Option<Located<Expectations>>> {
    let path = match given {
        Some(p) => p.to_path_buf(),
        None if in_checkout => PathBuf::from(EXPECTATIONS_FILE),
        None => {
            let name = built_in_name(EXPECTATIONS_FILE);
            let value = Expectations::parse_with(built_in.expectations, &name, known)?;
            return Ok(Some(Located { value, name, note: None }));
        }
    };
    if !path.is_file() {
        if let Some(why) = required {
            bail!("--expectations {}: no such file ({why})", path.display());
        }
        return Ok(None);
    }
    let value = Expectations::load_with(&path, known)?;
    let note = (given.is_none() && file_differs(&path, built_in.expectations))
        .then(|| differs_note(EXPECTATIONS_FILE, "--expectations"));
    Ok(Some(Located { value, name: path.display().to_string(), note }))
}

/// The baseline a run compares with, and where `check --write-baseline` writes.
#[derive(Debug)]
pub struct Baseline {
    /// The entries compared with (None: no file at the path).
    pub file: Option<BaselineFile>,
    /// The file `--write-baseline` rewrites (None: the built-in copy, which cannot be).
    pub path: Option<PathBuf>,
}

/// The baseline: `given` (`--baseline FILE`: read when it exists, and the file
/// `--write-baseline` writes), else the checkout's file (likewise), else the built-in
/// copy (read-only).
pub fn baseline(given: Option<&Path>, in_checkout: bool, built_in: &BuiltIn) -> Result<Located<Baseline>> {
    let path = match given {
        Some(p) => p.to_path_buf(),
        None if in_checkout => PathBuf::from(BASELINE_FILE),
        None => {
            let name = built_in_name(BASELINE_FILE);
            let file = BaselineFile::parse(built_in.baseline, &name)?;
            return Ok(Located { value: Baseline { file: Some(file), path: None }, name, note: None });
        }
    };
    let file = if path.exists() { Some(BaselineFile::load(&path)?) } else { None };
    let note = (given.is_none() && file.is_some() && file_differs(&path, built_in.baseline))
        .then(|| differs_note(BASELINE_FILE, "--baseline"));
    Ok(Located { value: Baseline { file, path: Some(path.clone()) }, name: path.display().to_string(), note })
}

/// Does the file's text differ from `text` (an unreadable file counts as differing)?
fn file_differs(path: &Path, text: &str) -> bool {
    std::fs::read(path).map_or(true, |bytes| bytes != text.as_bytes())
}

/// The corpus directory: `given` (`--corpus DIR`), else [`CHECKOUT_CORPUS`] in the
/// checkout, else [`USER_CORPUS`].
pub fn corpus_dir(given: Option<&Path>, in_checkout: bool) -> PathBuf {
    match given {
        Some(d) => d.to_path_buf(),
        None if in_checkout => PathBuf::from(CHECKOUT_CORPUS),
        None => PathBuf::from(USER_CORPUS),
    }
}

/// Is `s` a case file's hash (16 lowercase hex digits, [`crate::gate::case_file::CaseFile::short_hash`])?
fn is_hash(s: &str) -> bool {
    s.len() == 16 && s.bytes().all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b))
}

/// The case file `explain` reads: `arg` itself when it is a path that exists or ends in
/// `.json`; else a case id, `HASH` or `METHOD/HASH` (as `search` names its files), looked
/// up under `corpus/cases`. An id found nowhere, or a `HASH` found under several
/// methods, is an error naming the id and the directory.
pub fn case_path(arg: &Path, corpus: &Path) -> Result<PathBuf> {
    let text = arg.to_string_lossy();
    if arg.exists() || text.ends_with(".json") {
        return Ok(arg.to_path_buf());
    }
    let cases = corpus.join("cases");
    let (method, hash) = match text.rsplit_once('/') {
        Some((m, h)) => (Some(m), h),
        None => (None, text.as_ref()),
    };
    if !is_hash(hash) || method.is_some_and(str::is_empty) {
        bail!(
            "{text}: no such file, and not a case id (HASH or METHOD/HASH, the hash 16 hex digits, looked up in {})",
            cases.display()
        );
    }
    if let Some(m) = method {
        let p = cases.join(m).join(format!("{hash}.json"));
        if p.is_file() {
            return Ok(p);
        }
        bail!("case id {text}: no file {} (--corpus DIR names another corpus)", p.display());
    }
    let files =
        if cases.is_dir() { crate::gate::case_file::case_files(std::slice::from_ref(&cases))? } else { Vec::new() };
    let found: Vec<PathBuf> =
        files.into_iter().filter(|f| f.file_stem().is_some_and(|s| s.to_string_lossy() == hash)).collect();
    match found.as_slice() {
        [one] => Ok(one.clone()),
        [] => {
            bail!("case id {hash}: no file {hash}.json under {} (--corpus DIR names another corpus)", cases.display())
        }
        many => bail!(
            "case id {hash}: {} files under {} ({}); give METHOD/{hash} or the path",
            many.len(),
            cases.display(),
            many.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn package_names() {
        assert_eq!(package_name("[package]\nname = \"cullproof\"\n").as_deref(), Some("cullproof"));
        let ws = "[workspace]\nmembers = [\".\"]\nname = \"x\"\n\n[package]\n# c\nname='cullproof' # the tool\n";
        assert_eq!(package_name(ws).as_deref(), Some("cullproof"));
        assert_eq!(package_name("[package]\nname = \"mine\"\n").as_deref(), Some("mine"));
        assert_eq!(package_name("[dependencies]\nname = \"cullproof\"\n"), None);
        assert_eq!(package_name("[package.metadata]\nname = \"cullproof\"\n"), None);
        assert_eq!(package_name("[package]\nversion = \"1\"\n[lib]\nname = \"cullproof\"\n"), None);
        assert_eq!(package_name("not toml at all"), None);
    }

    #[test]
    fn this_repository_is_the_checkout() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        assert!(is_checkout(root));
        assert!(!is_checkout(&root.join("docs")));
        assert!(!is_checkout(&root.join("oracles")), "the oracles crate is not the checkout");
    }

    #[test]
    fn corpus_defaults() {
        assert_eq!(corpus_dir(None, true), Path::new("corpus"));
        assert_eq!(corpus_dir(None, false), Path::new("cullproof-corpus"));
        assert_eq!(corpus_dir(Some(Path::new("mine")), true), Path::new("mine"));
    }

    /// The repository's files as if built in, and `known` for the built-in ids.
    fn repo_built_in() -> BuiltIn {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let read = |f: &str| -> &'static str { Box::leak(std::fs::read_to_string(root.join(f)).unwrap().into()) };
        BuiltIn { expectations: read(EXPECTATIONS_FILE), baseline: read(BASELINE_FILE) }
    }

    fn known(id: &str) -> bool {
        crate::bounds::by_id(id).is_some()
    }

    #[test]
    fn built_in_copies_load_as_the_files_do() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let b = repo_built_in();
        let ex = expectations(None, Some("required"), false, &b, &known).unwrap().unwrap();
        assert_eq!(ex.name, "built-in corpus/expectations.json");
        assert!(ex.note.is_none());
        let file = Expectations::load(&root.join(EXPECTATIONS_FILE)).unwrap();
        assert_eq!(crate::gate::tool::hash(&ex.value), crate::gate::tool::hash(&file));
        let base = baseline(None, false, &b).unwrap();
        assert_eq!(base.value.path, None, "the built-in baseline has no file to write");
        assert_eq!(base.value.file.unwrap(), BaselineFile::load(&root.join(BASELINE_FILE)).unwrap());
        // A file named with the flag wins, and a missing one is an error naming it only
        // when required.
        let nope = Path::new("/nonexistent-cullproof/ex.json");
        let e = expectations(Some(nope), Some("because"), false, &b, &known).unwrap_err().to_string();
        assert!(e.contains("--expectations /nonexistent-cullproof/ex.json: no such file (because)"), "{e}");
        assert!(expectations(Some(nope), None, false, &b, &known).unwrap().is_none());
        let base = baseline(Some(nope), false, &b).unwrap();
        assert!(base.value.file.is_none() && base.value.path.as_deref() == Some(nope));
        // A broken built-in text is an error naming it and the field.
        let bad = BuiltIn { expectations: "{\"nope\": {}}", baseline: "{\"format\": 1}" };
        let e = expectations(None, None, false, &bad, &known).unwrap_err().to_string();
        assert!(e.starts_with("built-in corpus/expectations.json: method `nope`"), "{e}");
        let e = baseline(None, false, &bad).unwrap_err().to_string();
        assert!(e.starts_with("built-in corpus/baseline.json: field `format`"), "{e}");
    }

    #[test]
    fn case_ids() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let corpus = root.join("corpus");
        let want = corpus.join("cases/bbox/2b5e6ecce17e44fe.json");
        assert_eq!(case_path(Path::new("2b5e6ecce17e44fe"), &corpus).unwrap(), want);
        assert_eq!(case_path(Path::new("bbox/2b5e6ecce17e44fe"), &corpus).unwrap(), want);
        assert_eq!(case_path(&want, &corpus).unwrap(), want);
        // A path ending in .json is a path, found or not (the load names it).
        assert_eq!(case_path(Path::new("nope/x.json"), &corpus).unwrap(), Path::new("nope/x.json"));
        let e = case_path(Path::new("0000000000000000"), &corpus).unwrap_err().to_string();
        assert!(e.contains("0000000000000000") && e.contains("cases"), "{e}");
        let e = case_path(Path::new("la2011/2b5e6ecce17e44fe"), &corpus).unwrap_err().to_string();
        assert!(e.contains("la2011/2b5e6ecce17e44fe.json"), "{e}");
        let e = case_path(Path::new("not-an-id"), &corpus).unwrap_err().to_string();
        assert!(e.contains("not-an-id") && e.contains("not a case id"), "{e}");
    }
}
