//! Output paths: checked before a command's work starts, written when it ends.
//!
//! Every file or directory a command writes (`--json`, `--junit`, `--out`, `--svg`,
//! `--emit-smt`, the baseline of `--write-baseline`) is checked with [`file`] or [`dir`]
//! as the flags are read, so an unwritable path is an error (exit 2, naming the flag
//! and the path) before any work, never after a long run that is then lost. The check
//! leaves nothing behind: it creates and removes a probe file in the directory, and
//! opens an existing file without truncating it.
//!
//! At the end [`write`] writes through a temporary file in the target's directory,
//! renamed over the target once it is whole: an existing file is replaced only by a
//! complete new one, and stays as it was when the run or the write fails. (A device or
//! a pipe, such as `/dev/null` or a shell's process substitution, is written directly.)

use anyhow::{anyhow, bail, Result};
use std::fs;
use std::io::{ErrorKind, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Does the error say there is nothing at the path (or a file where a directory
/// should be on the way)?
fn missing(e: &std::io::Error) -> bool {
    matches!(e.kind(), ErrorKind::NotFound | ErrorKind::NotADirectory)
}

/// The directory a file path lies in (`.` for a bare name).
fn parent(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// A fresh hidden name in `dir` for a temporary file next to `base`.
fn temp_name(dir: &Path, base: &Path) -> PathBuf {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let name = base.file_name().map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    dir.join(format!(".{name}.cullproof-{}-{n}.tmp", std::process::id()))
}

/// The path a write goes to: a symbolic link's target (so the link stays a link).
fn resolved(path: &Path) -> PathBuf {
    let link = fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink());
    if link {
        fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
    } else {
        path.to_path_buf()
    }
}

/// Can a file be created in the directory `dir`? Creates and removes a probe file.
fn probe(flag: &str, path: &Path, dir: &Path) -> Result<()> {
    let p = temp_name(dir, Path::new("probe"));
    match fs::OpenOptions::new().write(true).create_new(true).open(&p) {
        Ok(f) => {
            drop(f);
            let _ = fs::remove_file(&p);
            Ok(())
        }
        Err(e) => bail!("{flag} {}: cannot create a file in the directory {}: {e}", path.display(), dir.display()),
    }
}

/// Check an output file before the run: not a directory, its directory exists and
/// takes a new file, and an existing file opens for writing (it is not changed). The
/// error names `flag` and the path.
pub fn file(flag: &str, path: &Path) -> Result<()> {
    let shown = path.display();
    if path.as_os_str().is_empty() {
        bail!("{flag}: the path is empty");
    }
    match fs::metadata(path) {
        Ok(m) if m.is_dir() => bail!("{flag} {shown}: is a directory, not a file"),
        // A device or a pipe (/dev/null, /dev/stdout, a process substitution) is written
        // as it is.
        Ok(m) if !m.is_file() => return Ok(()),
        Ok(_) => {
            fs::OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(|e| anyhow!("{flag} {shown}: the file exists and cannot be written: {e}"))?;
        }
        Err(e) if missing(&e) => {}
        Err(e) => bail!("{flag} {shown}: {e}"),
    }
    let target = resolved(path);
    let dir = parent(&target);
    match fs::metadata(dir) {
        Ok(m) if m.is_dir() => probe(flag, path, dir),
        Ok(_) => bail!("{flag} {shown}: {} is not a directory", dir.display()),
        Err(e) if missing(&e) => {
            bail!("{flag} {shown}: the directory {} does not exist", dir.display())
        }
        Err(e) => bail!("{flag} {shown}: the directory {}: {e}", dir.display()),
    }
}

/// [`file`], with `-` (standard output) accepted as well.
pub fn file_or_stdout(flag: &str, path: &Path) -> Result<()> {
    if path.as_os_str() == "-" {
        return Ok(());
    }
    file(flag, path)
}

/// Check an output directory before the run: an existing one must be a directory that
/// takes a new file; a missing one (created at the end) must have a nearest existing
/// ancestor that is a directory taking a new entry. Nothing is created. The error
/// names `flag` and the path.
pub fn dir(flag: &str, path: &Path) -> Result<()> {
    let shown = path.display();
    if path.as_os_str().is_empty() {
        bail!("{flag}: the path is empty");
    }
    match fs::metadata(path) {
        Ok(m) if m.is_dir() => return probe(flag, path, path),
        Ok(_) => bail!("{flag} {shown}: exists and is not a directory"),
        Err(e) if missing(&e) => {}
        Err(e) => bail!("{flag} {shown}: {e}"),
    }
    let mut a = parent(path);
    loop {
        match fs::metadata(a) {
            Ok(m) if m.is_dir() => return probe(flag, path, a),
            Ok(_) => bail!("{flag} {shown}: {} is not a directory", a.display()),
            Err(e) if missing(&e) && parent(a) != a => a = parent(a),
            Err(e) => bail!("{flag} {shown}: {}: {e}", a.display()),
        }
    }
}

/// Write `data` to `path`: through a temporary file in the same directory renamed over
/// `path` (an existing file keeps its permissions, and is replaced only by the whole new
/// text); a device or a pipe is written directly. The error names the path.
pub fn write(path: &Path, data: impl AsRef<[u8]>) -> Result<()> {
    let data = data.as_ref();
    let fail = |e: std::io::Error| anyhow!("writing {}: {e}", path.display());
    let meta = fs::metadata(path).ok();
    if meta.as_ref().is_some_and(|m| !m.is_file() && !m.is_dir()) {
        return fs::write(path, data).map_err(fail);
    }
    let target = resolved(path);
    let tmp = temp_name(parent(&target), &target);
    let done = (|| -> std::io::Result<()> {
        let mut f = fs::OpenOptions::new().write(true).create_new(true).open(&tmp)?;
        if let Some(m) = &meta {
            f.set_permissions(m.permissions())?;
        }
        f.write_all(data)?;
        drop(f);
        fs::rename(&tmp, &target)
    })();
    if let Err(e) = done {
        let _ = fs::remove_file(&tmp);
        return Err(fail(e));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("cullproof-output-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&d);
        fs::create_dir_all(&d).unwrap();
        d
    }

    fn entries(d: &Path) -> Vec<String> {
        let mut v: Vec<String> =
            fs::read_dir(d).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        v.sort();
        v
    }

    #[test]
    fn files_are_checked_without_a_trace() {
        let d = scratch("file");
        let p = d.join("r.json");
        file("--json", &p).unwrap();
        assert!(entries(&d).is_empty(), "{:?}", entries(&d));
        fs::write(&p, "mine").unwrap();
        file("--json", &p).unwrap();
        assert_eq!(fs::read_to_string(&p).unwrap(), "mine");
        assert_eq!(entries(&d), ["r.json"]);
        let e = file("--json", &d).unwrap_err().to_string();
        assert!(e.starts_with("--json ") && e.contains("is a directory"), "{e}");
        let e = file("--junit", Path::new("/nonexistent-dir/x.xml")).unwrap_err().to_string();
        assert!(e.contains("--junit /nonexistent-dir/x.xml") && e.contains("does not exist"), "{e}");
        let e = file("--json", &p.join("under-a-file.json")).unwrap_err().to_string();
        assert!(e.contains("not a directory"), "{e}");
        file_or_stdout("--json", Path::new("-")).unwrap();
        file("--json", Path::new("/dev/null")).unwrap();
        let _ = fs::remove_dir_all(&d);
    }

    #[test]
    fn directories_are_checked_without_being_made() {
        let d = scratch("dir");
        dir("--out", &d).unwrap();
        dir("--out", &d.join("a/b/c")).unwrap();
        assert!(!d.join("a").exists());
        fs::write(d.join("f"), "x").unwrap();
        let e = dir("--out", &d.join("f")).unwrap_err().to_string();
        assert!(e.contains("--out") && e.contains("not a directory"), "{e}");
        let e = dir("--out", &d.join("f/g")).unwrap_err().to_string();
        assert!(e.contains("not a directory"), "{e}");
        assert_eq!(entries(&d), ["f"]);
        let _ = fs::remove_dir_all(&d);
    }

    #[test]
    fn a_write_replaces_the_whole_file_and_keeps_its_mode() {
        use std::os::unix::fs::PermissionsExt;
        let d = scratch("write");
        let p = d.join("r.json");
        write(&p, "one").unwrap();
        fs::set_permissions(&p, fs::Permissions::from_mode(0o640)).unwrap();
        write(&p, "two").unwrap();
        assert_eq!(fs::read_to_string(&p).unwrap(), "two");
        assert_eq!(fs::metadata(&p).unwrap().permissions().mode() & 0o777, 0o640);
        // Through a link, the link stays and its target is written.
        let l = d.join("link.json");
        std::os::unix::fs::symlink(&p, &l).unwrap();
        write(&l, "three").unwrap();
        assert!(fs::symlink_metadata(&l).unwrap().file_type().is_symlink());
        assert_eq!(fs::read_to_string(&p).unwrap(), "three");
        assert_eq!(entries(&d), ["link.json", "r.json"]);
        assert!(write(&d.join("missing/x.json"), "x").unwrap_err().to_string().contains("missing/x.json"));
        let _ = fs::remove_dir_all(&d);
    }
}
