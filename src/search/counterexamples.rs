//! Counterexamples of your own bound, through the library: find and shrink them
//! ([`Search`]), write each as a case file, re-judge a case file against a bound
//! ([`replay`]) and put a case in words ([`explain`]). These are the calls behind
//! `cullproof search`, `cullproof replay --method` and `cullproof explain`, open to a
//! bound written in Rust that is in no registry.
//!
//! ```no_run
//! use cullproof::counterexamples::{explain, replay, Search};
//! # let my_bound = cullproof::bounds::by_id("bbox").unwrap();
//! let found = Search::new(my_bound).seconds(20.0).write_to("my-corpus/cases").run()?;
//! for f in &found.found {
//!     let file = f.file.as_deref().expect("written");
//!     println!("{}", explain(file.as_ref(), my_bound)?);
//!     // after the fix: "fixed" once the bound is proven on the case
//!     println!("{}", replay(file.as_ref(), my_bound)?.outcome);
//! }
//! # Ok::<(), anyhow::Error>(())
//! ```

use crate::bounds::{Method, MethodRef};
use crate::cases::generate::Regime;
use crate::gate::{CheckConfig, Declared};
use crate::model::{SampleSet, Snap, Viewport};
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub use crate::search::{Found, Rejudge, SearchReport};

/// A randomized search for cases your bound gets wrong: random cases of every regime
/// (or those chosen), each judged as the gate judges it; each violation is shrunk (the
/// motion frozen, the CoC zeroed, coordinates snapped to fewer bits, smaller tiles...)
/// while it stays a violation at least half as large, and written as a case file when
/// [`write_to`](Self::write_to) names a directory. The cases drawn do not depend on
/// the thread count; how many are drawn depends on the time given.
pub struct Search {
    cfg: CheckConfig,
    method: MethodRef,
    seconds: f64,
    max: usize,
    out: Option<PathBuf>,
    jobs: Option<usize>,
}

impl Search {
    /// A search of one method: your own bound (any value implementing [`Method`]) or
    /// a built-in one (`cullproof::bounds::by_id("bbox")`). 30 s, at most 8 findings,
    /// seed 1, every regime, nothing written.
    pub fn new(m: impl Method + 'static) -> Self {
        Self::method_ref(Arc::new(m))
    }
    /// [`Search::new`] of a method already held as a [`MethodRef`].
    pub fn method_ref(m: MethodRef) -> Self {
        Search {
            cfg: CheckConfig::default_for(vec![m.clone()]),
            method: m,
            seconds: 30.0,
            max: 8,
            out: None,
            jobs: None,
        }
    }
    /// Search for about this many seconds.
    pub fn seconds(mut self, s: f64) -> Self {
        self.seconds = s;
        self
    }
    /// Stop after this many findings (one per regime and kind of bound).
    pub fn max(mut self, n: usize) -> Self {
        self.max = n;
        self
    }
    /// Seed of the case streams.
    pub fn seed(mut self, s: u64) -> Self {
        self.cfg.seed = s;
        self
    }
    /// Only these regimes.
    pub fn regimes(mut self, r: &[Regime]) -> Self {
        self.cfg.regimes = r.to_vec();
        self
    }
    /// The pixel positions your bound promises to keep (default: every position). A
    /// violation is then a covered sample of this set that the bound culls.
    pub fn samples(mut self, set: SampleSet) -> Self {
        self.cfg.sample_set = set;
        self
    }
    /// Snap every vertex's pixel position at each motion key to the grid of 2^-`bits`
    /// pixels before coverage is judged (clamped to
    /// [`crate::model::samples::MAX_BITS`]).
    pub fn snap(mut self, bits: u32) -> Self {
        self.cfg.snap = Some(Snap { bits: bits.min(crate::model::samples::MAX_BITS) });
        self
    }
    /// Place every case in this viewport (footprint inside its guard band, tiles
    /// inside the viewport).
    pub fn viewport(mut self, v: Viewport) -> Self {
        self.cfg.viewport = Some(v);
        self
    }
    /// Write each shrunk finding to `dir/<method>/<hash>.json` (an existing file is
    /// never overwritten; the directory is made when missing).
    pub fn write_to(mut self, dir: impl Into<PathBuf>) -> Self {
        self.out = Some(dir.into());
        self
    }
    /// Worker threads (0 or unset: all cores). The cases drawn do not depend on it.
    pub fn jobs(mut self, n: usize) -> Self {
        self.jobs = (n > 0).then_some(n);
        self
    }
    /// Run it. An error when the output directory cannot be made or a file cannot be
    /// written.
    pub fn run(&self) -> anyhow::Result<SearchReport> {
        if let Some(dir) = &self.out {
            crate::io::output::dir("the case directory", dir)?;
        }
        let go = || {
            crate::search::search(
                &self.cfg,
                self.method.clone(),
                self.seconds,
                self.max,
                0.0,
                self.out.as_deref(),
                false,
            )
        };
        match self.jobs.map(|n| rayon::ThreadPoolBuilder::new().num_threads(n).build()) {
            Some(Ok(pool)) => pool.install(go),
            _ => go(),
        }
    }
}

/// Re-judge a case file against a bound (the one it was found for after a fix, or
/// another): `outcome` is "fixed" (proven afresh on the case, the stored witness no
/// longer culled), "still violated" (a violation found afresh, or the stored witness
/// still culled) or "unproven". Judged under the file's sample set, snapping and
/// viewport, with the whole side budget. The file may name a method of its own that
/// no registry knows.
pub fn replay(path: &Path, m: impl Method + 'static) -> anyhow::Result<Rejudge> {
    let m: MethodRef = Arc::new(m);
    crate::search::rejudge_with(path, &CheckConfig::default_for(vec![m.clone()]), &Declared::default(), &m)
}

/// A case file in words, as `cullproof explain` prints it: the bound's answer on the
/// tile, the certified extents of the covered samples over it, and the stored witness
/// decided exactly.
pub fn explain(path: &Path, m: impl Method + 'static) -> anyhow::Result<String> {
    let m: MethodRef = Arc::new(m);
    let cf = crate::search::CaseFile::load_for(path, Some(&m))?;
    Ok(crate::search::describe_with(&cf, m.as_ref()))
}
