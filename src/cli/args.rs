//! Checks of command-line values shared by the commands: every value a command takes
//! from the user is checked here, by name, before any work starts, and a bad one is an
//! error that names the flag and the value (never a panic, a hang or a silent default).
//!
//! - [`methods`] / [`method`]: the ONE method-list parser (`all`, one id, or ids
//!   separated by commas; trimmed, deduplicated; an unknown id is an error naming it
//!   and listing the known ids).
//! - [`jobs`]: worker threads, 1 ..= [`max_jobs`] (the machine's available parallelism
//!   times [`JOBS_PER_CORE`]).
//! - [`tile`]: a tile size, finite and in (0, [`MAX_TILE`]] pixels.
//! - [`time`]: a duration, finite and in (0, max] seconds.
//! - [`count`]: a count in 1 ..= max.
//! - [`shard`]: `K/N` with 0 <= K < N.
//! - [`regime`]: a regime name or `all`.
//! - [`margin`]: a finite, non-negative margin.
//! - [`SampleFlags`]: `--samples`, `--snap`, `--viewport` (the samples a bound promises
//!   to keep), shared by `check`, `search`, `replay` and `explain`.
//! - [`CorpusFlag`]: `--corpus DIR`, the corpus of case files of `search`, `prove`,
//!   `replay` and `explain` ([`crate::gate::locate`]).

use crate::bounds::{self, Method};
use crate::cases::generate::Regime;
use crate::gate::Declared;
use crate::model::{SampleSet, Snap, Viewport};
use anyhow::{bail, ensure, Result};

/// The largest tile size (pixels) any command takes.
pub const MAX_TILE: f32 = 4096.0;

/// `check --cases`: at most this many cases in all (the case ids of the shard are
/// listed before the run; [`crate::gate::MAX_CASES`], which `merge` holds reports to).
pub const CHECK_MAX_CASES: u64 = crate::gate::MAX_CASES;

/// `check --cases`: at most this many cases per shard. A run holds every judged case's
/// judgement until the report (about 7 KB per case with every method), so 10^6 cases
/// take some 7 GB; split larger runs with `--shard K/N` (or several seeds).
pub const CHECK_MAX_CASES_PER_SHARD: u64 = 1_000_000;

/// `check --time`: at most one hour. A timed run also holds every judgement (some
/// 1.5 MB/s per 2 cores at the default budgets); longer runs: several seeds or shards.
pub const CHECK_MAX_TIME: f64 = 3600.0;

/// `search --time`: at most a week (a search keeps only its violations).
pub const SEARCH_MAX_TIME: f64 = 7.0 * 86400.0;

/// `oracle-agree --samples`: at most 10^12 samples (5 * 10^8 cases of 2000; the run
/// streams, but that is already days of work).
pub const AGREE_MAX_SAMPLES: u64 = 1_000_000_000_000;

/// `--jobs` may ask for at most this many threads per available core.
pub const JOBS_PER_CORE: usize = 4;

/// The most worker threads `--jobs` accepts on this machine:
/// `std::thread::available_parallelism() * JOBS_PER_CORE` (1 core when unknown).
pub fn max_jobs() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get()) * JOBS_PER_CORE
}

/// Check `--jobs`: None stays None (the default, all cores); 0 and values above
/// [`max_jobs`] are errors.
pub fn jobs(j: Option<usize>) -> Result<Option<usize>> {
    let Some(j) = j else { return Ok(None) };
    ensure!(j >= 1, "--jobs 0: at least one worker thread is needed");
    let max = max_jobs();
    ensure!(
        j <= max,
        "--jobs {j}: at most {max} worker threads on this machine ({} available cores x {JOBS_PER_CORE})",
        max / JOBS_PER_CORE
    );
    Ok(Some(j))
}

/// Check a tile size in pixels: finite, > 0 and at most [`MAX_TILE`].
pub fn tile(flag: &str, t: f32) -> Result<f32> {
    ensure!(
        t.is_finite() && t > 0.0 && t <= MAX_TILE,
        "{flag} {t}: the tile size must be a positive number of pixels, at most {MAX_TILE}"
    );
    Ok(t)
}

/// Check a duration in seconds: finite, > 0 and at most `max`.
pub fn time(flag: &str, t: f64, max: f64) -> Result<f64> {
    ensure!(t.is_finite() && t > 0.0, "{flag} {t}: the time must be a positive number of seconds");
    ensure!(t <= max, "{flag} {t}: at most {max} seconds");
    Ok(t)
}

/// Check a count: 1 ..= `max` (`what` says what is counted and why the limit).
pub fn count(flag: &str, n: u64, max: u64, what: &str) -> Result<u64> {
    ensure!(n >= 1, "{flag} 0: at least one {what} is needed");
    ensure!(n <= max, "{flag} {n}: at most {max} {what}");
    Ok(n)
}

/// Check a margin: finite and >= 0.
pub fn margin(flag: &str, x: f64) -> Result<f64> {
    ensure!(x.is_finite() && x >= 0.0, "{flag} {x}: a margin is a finite, non-negative padding");
    Ok(x)
}

/// Parse `--shard K/N` (0 <= K < N).
pub fn shard(s: &str) -> Result<(u64, u64)> {
    let parsed =
        s.split_once('/').and_then(|(a, b)| Some((a.trim().parse::<u64>().ok()?, b.trim().parse::<u64>().ok()?)));
    match parsed {
        Some((k, n)) if n > 0 && k < n => Ok((k, n)),
        Some((_, 0)) => bail!("--shard {s}: N must be at least 1 (expected K/N with 0 <= K < N)"),
        Some((k, n)) => bail!("--shard {s}: K = {k} must be below N = {n} (expected K/N with 0 <= K < N)"),
        None => bail!("--shard {s}: expected K/N with whole numbers 0 <= K < N, e.g. 0/4"),
    }
}

/// Parse `--regime`: None for `all`.
pub fn regime(name: &str) -> Result<Option<Regime>> {
    let name = name.trim();
    if name == "all" {
        return Ok(None);
    }
    match Regime::ALL.into_iter().find(|r| r.name() == name) {
        Some(r) => Ok(Some(r)),
        None => {
            let all: Vec<_> = Regime::ALL.iter().map(|r| r.name()).collect();
            bail!("--regime {name}: no such regime (one of: {}, all)", all.join(", "))
        }
    }
}

fn known_ids(broken: bool) -> String {
    let ids: Vec<&str> = bounds::registry().iter().map(|m| m.info().id).collect();
    let mut s = ids.join(", ");
    if broken {
        s += ", broken/shrink/ID, broken/no-coc-pad/ID";
    }
    s
}

/// The one method-list parser: `all`, one id, or ids separated by commas (each
/// trimmed; repeats dropped, first order kept; `all` in a list stands for every
/// registered method). With `broken`, the deliberately broken
/// variants `broken/shrink/ID` and `broken/no-coc-pad/ID` are accepted too. An empty
/// or unknown id is an error naming it and listing the known ids.
pub fn methods(flag: &str, s: &str, broken: bool) -> Result<Vec<&'static dyn Method>> {
    let mut out: Vec<&'static dyn Method> = Vec::new();
    let push = |m: &'static dyn Method, out: &mut Vec<&'static dyn Method>| {
        if !out.iter().any(|x| x.info().id == m.info().id) {
            out.push(m);
        }
    };
    for part in s.split(',') {
        let id = part.trim();
        if id.is_empty() {
            bail!("{flag} {s}: an empty method id (known ids: {}, all)", known_ids(broken));
        }
        if id == "all" {
            for m in bounds::registry() {
                push(m, &mut out);
            }
            continue;
        }
        let m = bounds::by_id(id).or_else(|| if broken { bounds::broken::parse(id) } else { None });
        match m {
            Some(m) => push(m, &mut out),
            None => bail!(
                "{flag} {s}: `{id}` is not a method id (known ids: {}, all; a plugin's id needs `--plugin LIB.so`)",
                known_ids(broken)
            ),
        }
    }
    Ok(out)
}

/// Exactly one method (through the same parser as [`methods`]): `all` or a list naming
/// more than one method is an error.
pub fn method(flag: &str, s: &str, broken: bool) -> Result<&'static dyn Method> {
    let ms = methods(flag, s, broken)?;
    match ms.as_slice() {
        [m] => Ok(*m),
        _ => bail!(
            "{flag} {s}: this command takes exactly one method, not {} (known ids: {})",
            ms.len(),
            known_ids(broken)
        ),
    }
}

/// `--corpus DIR`: the corpus of case files a command writes or reads (see
/// [`crate::gate::locate`]).
#[derive(Clone, Debug, Default, clap::Args)]
pub struct CorpusFlag {
    /// Your corpus directory: case files are written to and read from
    /// `DIR/cases/<method>/<hash>.json`. Default: `corpus` in the cullproof checkout (the
    /// current directory holds its Cargo.toml), `cullproof-corpus` in the current
    /// directory anywhere else.
    #[arg(long = "corpus", value_name = "DIR")]
    pub corpus: Option<std::path::PathBuf>,
}

impl CorpusFlag {
    /// The corpus directory ([`crate::gate::locate::corpus_dir`]); an empty path is an error.
    pub fn dir(&self, in_checkout: bool) -> Result<std::path::PathBuf> {
        if let Some(d) = &self.corpus {
            ensure!(!d.as_os_str().is_empty(), "--corpus: the path is empty");
        }
        Ok(crate::gate::locate::corpus_dir(self.corpus.as_deref(), in_checkout))
    }
}

/// The flags that declare the samples a bound promises to keep (`docs/model.md`, §7).
/// `check` and `search` take the defaults for flags not given; `replay` and `explain`
/// take what the case file records, and a flag given overrides it.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct SampleFlags {
    /// The pixel positions the bound promises to keep: any (every position, the
    /// default), centres (pixel centres), msaa2 / msaa4 / msaa8 / msaa16 (the standard
    /// MSAA patterns) or gridN (the fixed-point grid of 2^-N px, N <= 16).
    #[arg(long = "samples", value_name = "SET")]
    pub samples: Option<String>,
    /// Snap each vertex's pixel position at each motion key to the grid of 2^-BITS px
    /// (round to nearest, ties to even) before coverage is judged; 0 to 16.
    #[arg(long = "snap", value_name = "BITS")]
    pub snap: Option<String>,
    /// Place the cases in this viewport, WIDTHxHEIGHT[+GUARD] pixels from the origin (e.g.
    /// 1920x1080+64), X,Y,WIDTHxHEIGHT[+GUARD] from the corner (X, Y) (e.g.
    /// -32768,-32768,65536x65536) or centred:WIDTHxHEIGHT[+GUARD] around the origin; sides
    /// up to 131072: footprints inside the guard band, tiles inside the viewport.
    #[arg(long = "viewport", value_name = "VIEWPORT")]
    pub viewport: Option<String>,
}

impl SampleFlags {
    /// Parse the flags given into what they declare ([`Declared`]: each None when its
    /// flag was not given); a bad value is an error naming the flag and the value.
    pub fn parse(&self) -> Result<Declared> {
        Ok(Declared {
            samples: self.samples.as_deref().map(sample_set).transpose()?,
            snap: self.snap.as_deref().map(snap).transpose()?,
            viewport: self.viewport.as_deref().map(viewport).transpose()?,
        })
    }
}

/// Parse `--samples`.
pub fn sample_set(s: &str) -> Result<SampleSet> {
    s.parse().map_err(|e| anyhow::anyhow!("--samples {e}"))
}

/// Parse `--snap` (bits below the pixel, 0 to 16).
pub fn snap(s: &str) -> Result<Snap> {
    s.parse().map_err(|e| anyhow::anyhow!("--snap {e}"))
}

/// Parse `--viewport` (`WIDTHxHEIGHT[+GUARD]`).
pub fn viewport(s: &str) -> Result<Viewport> {
    s.parse().map_err(|e| anyhow::anyhow!("--viewport {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_flags_parse_or_name_the_flag() {
        let f = SampleFlags { samples: Some("msaa4".into()), snap: Some("8".into()), viewport: Some("64x32+8".into()) };
        let d = f.parse().unwrap();
        assert_eq!(d.samples, Some(SampleSet::Msaa(4)));
        assert_eq!(d.snap, Some(Snap { bits: 8 }));
        assert_eq!(d.viewport, Some(Viewport::sized(64, 32, 8)));
        assert_eq!(SampleFlags::default().parse().unwrap(), Declared::default());
        for (f, want) in [
            (SampleFlags { samples: Some("msaa5".into()), ..Default::default() }, "--samples `msaa5`"),
            (SampleFlags { snap: Some("99".into()), ..Default::default() }, "--snap `99`"),
            (SampleFlags { viewport: Some("12".into()), ..Default::default() }, "--viewport `12`"),
        ] {
            let e = f.parse().unwrap_err().to_string();
            assert!(e.starts_with(want), "{e}");
        }
    }

    #[test]
    fn method_lists() {
        assert_eq!(methods("--method", "all", false).unwrap().len(), bounds::registry().len());
        let ms = methods("--method", " bbox , lc,bbox", false).unwrap();
        let ids: Vec<_> = ms.iter().map(|m| m.info().id).collect();
        assert_eq!(ids, ["bbox", "lc"]);
        let e = methods("--method", "bbox,nope", false).err().unwrap().to_string();
        assert!(e.contains("`nope`") && e.contains("lc") && e.contains("--method"), "{e}");
        assert!(methods("--method", "bbox,,lc", false).is_err());
        assert!(methods("--method", "broken/shrink/la2011", false).is_err());
        assert_eq!(methods("--method", "broken/shrink/la2011", true).unwrap()[0].info().id, "broken/shrink/la2011");
        assert_eq!(method("--method", "lc", false).unwrap().info().id, "lc");
        assert!(method("--method", "lc,bbox", false).err().unwrap().to_string().contains("exactly one"));
        assert!(method("--method", "all", false).is_err());
        assert_eq!(method("--method", "bbox,bbox", false).unwrap().info().id, "bbox");
    }

    #[test]
    fn numbers_and_shards() {
        assert!(jobs(Some(0)).is_err());
        assert!(jobs(Some(max_jobs() + 1)).is_err());
        assert_eq!(jobs(Some(1)).unwrap(), Some(1));
        for t in [0.0, -1.0, f32::NAN, f32::INFINITY, 5000.0] {
            assert!(tile("--tile", t).is_err(), "{t}");
        }
        assert_eq!(tile("--tile", 4.0).unwrap(), 4.0);
        for t in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e9] {
            assert!(time("--time", t, 3600.0).is_err(), "{t}");
        }
        for s in ["0/0", "5/3", "a/b", "3", "1/1", ""] {
            assert!(shard(s).is_err(), "{s}");
        }
        assert_eq!(shard("1/4").unwrap(), (1, 4));
        assert!(regime("nope").is_err());
        assert_eq!(regime("all").unwrap(), None);
        assert!(margin("--min-margin", f64::NAN).is_err() && margin("--min-margin", -1.0).is_err());
        assert!(count("--cases", 0, 10, "cases").is_err() && count("--cases", 11, 10, "cases").is_err());
    }
}
