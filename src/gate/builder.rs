//! The gate as a library: run it on your own bound inside your own `cargo test`.
//!
//! ```no_run
//! use cullproof::{Gate, Method};
//! # fn my_bound() -> &'static dyn Method { cullproof::bounds::by_id("bbox-safe").unwrap() }
//! let report = Gate::new().method(my_bound()).cases(960).seed(1).run();
//! assert!(report.passed(), "{}", report.render());
//! ```
//!
//! [`Gate`] collects the settings (methods, cases, seed, regimes, tile size, budgets,
//! expectations, baseline) and runs the same judge as `cullproof check`; [`GateReport`]
//! answers per method with typed values: a [`MethodVerdict`], counts of proven /
//! violated / unproven cases with [`Unproven`] reasons, and [`Counterexample`]s whose
//! sample, case and tile can be replayed.

use crate::bounds::{Method, MethodRef};
use crate::cases::generate::Regime;
use crate::gate::baseline::BaselineFile;
use crate::gate::{self, CheckConfig, CheckReport, Expectations};
use crate::model::{Case, Sample, SampleSet, Snap, Tile, Viewport};
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

/// The settings of a gate run (a builder; every setting has the default of
/// `cullproof check`).
#[derive(Clone)]
pub struct Gate {
    cfg: CheckConfig,
    expectations: Expectations,
    baseline: Option<BaselineFile>,
    jobs: Option<usize>,
}

impl Default for Gate {
    fn default() -> Self {
        Self::new()
    }
}

impl Gate {
    /// No method yet; 9,600 cases of every regime, seed 1, every method expected
    /// conservative, no baseline.
    pub fn new() -> Self {
        Gate {
            cfg: CheckConfig::default_for(Vec::new()),
            expectations: Expectations::default(),
            baseline: None,
            jobs: None,
        }
    }
    /// Add a method: your own bound (any value implementing [`Method`]), or a built-in
    /// one (`cullproof::bounds::by_id("bbox")`).
    pub fn method(mut self, m: impl Method + 'static) -> Self {
        self.cfg.methods.push(Arc::new(m));
        self
    }
    /// Add a method already held as a [`MethodRef`].
    pub fn method_ref(mut self, m: MethodRef) -> Self {
        self.cfg.methods.push(m);
        self
    }
    /// Number of cases, spread over the regimes in turn.
    pub fn cases(mut self, n: u64) -> Self {
        self.cfg.cases = n;
        self
    }
    /// Seed of the case streams (a run is the same for a seed at any thread count).
    pub fn seed(mut self, s: u64) -> Self {
        self.cfg.seed = s;
        self
    }
    /// Only these regimes.
    pub fn regimes(mut self, r: &[Regime]) -> Self {
        self.cfg.regimes = r.to_vec();
        self
    }
    /// A fixed tile size in pixels (default: drawn from 1, 2, 4, 8, 16 per case).
    pub fn tile(mut self, px: f32) -> Self {
        self.cfg.tile = Some(px);
        self
    }
    /// The pixel positions your bound promises to keep (default [`SampleSet::Any`]:
    /// every position, the stochastic case). A violation is then a covered sample of
    /// this set that the bound culls (`docs/model.md`, §7).
    pub fn samples(mut self, set: SampleSet) -> Self {
        self.cfg.sample_set = set;
        self
    }
    /// Snap every vertex's pixel position at each motion key to the grid of 2^-`bits`
    /// pixels before coverage is judged (at most [`crate::model::samples::MAX_BITS`];
    /// larger values are clamped to it).
    pub fn snap(mut self, bits: u32) -> Self {
        self.cfg.snap = Some(Snap { bits: bits.min(crate::model::samples::MAX_BITS) });
        self
    }
    /// Place every case in this viewport (footprint inside its guard band, tiles inside
    /// the viewport).
    pub fn viewport(mut self, v: Viewport) -> Self {
        self.cfg.viewport = Some(v);
        self
    }
    /// Boxes per interval side and per constraint search (larger: fewer unproven cases,
    /// slower).
    pub fn budgets(mut self, side: usize, constraint: usize) -> Self {
        self.cfg.judge.side_budget = side;
        self.cfg.judge.constraint_budget = constraint;
        self
    }
    /// Judge each method on the tiles at its own tile-reject limit in one case of this
    /// many (0: never).
    pub fn limit_every(mut self, n: u64) -> Self {
        self.cfg.limit_every = n;
        self
    }
    /// What each method x regime is expected to show (default: conservative).
    pub fn expectations(mut self, e: Expectations) -> Self {
        self.expectations = e;
        self
    }
    /// Expectations from a file (the format of `corpus/expectations.json`; ids must be
    /// known: built-in, or added to this gate before the call).
    pub fn expectations_file(mut self, path: &Path) -> anyhow::Result<Self> {
        let ids: Vec<String> = self.cfg.methods.iter().map(|m| m.info().id.to_string()).collect();
        let known = |id: &str| crate::bounds::by_id(id).is_some() || ids.iter().any(|x| x == id);
        self.expectations = Expectations::load_with(path, &known)?;
        Ok(self)
    }
    /// Compare with a stored baseline (the format of `corpus/baseline.json`).
    pub fn baseline_file(mut self, path: &Path) -> anyhow::Result<Self> {
        self.baseline = Some(BaselineFile::load(path)?);
        Ok(self)
    }
    /// The settings as `cullproof check` holds them.
    pub fn config(&self) -> &CheckConfig {
        &self.cfg
    }
    /// Worker threads for [`run`](Self::run) (default: all cores; `jobs(0)` too). The
    /// report does not depend on it: every case's verdict is the same at any count.
    pub fn jobs(mut self, n: usize) -> Self {
        self.jobs = (n > 0).then_some(n);
        self
    }
    /// Run it (on [`jobs`](Self::jobs) threads, all cores by default; no progress bar).
    pub fn run(&self) -> GateReport {
        let go = || gate::run_with_baseline(&self.cfg, &self.expectations, self.baseline.as_ref(), false);
        let raw = match self.jobs.map(|n| rayon::ThreadPoolBuilder::new().num_threads(n).build()) {
            Some(Ok(pool)) => pool.install(go),
            // No pool could be made (the system refused threads): the global pool.
            _ => go(),
        };
        GateReport::from_check(raw)
    }
}

/// A method's verdict over the run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MethodVerdict {
    /// Every case proven: every claim certified, no gap left.
    Proven,
    /// At least one case violated: a covered sample, confirmed exactly, that it culls.
    Violated,
    /// No violation, but some cases neither proven nor violated.
    Unproven,
    /// No case could be judged under the declared samples (every vertex beyond what
    /// snapping can snap exactly, or no case the viewport can hold): neither a failure
    /// nor a pass.
    NotJudged,
}

/// Why a case is unproven.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Unproven {
    /// A side search stopped with boxes beyond the claimed bound still open.
    SideGap,
    /// A culled tile whose occupancy was not settled.
    TileUnknown,
    /// A depth violation candidate not confirmed.
    DepthUnconfirmed,
    /// A per-sample constraint search ran out of its budget.
    ConstraintBudget,
    /// A per-sample constraint search left boxes at its smallest size.
    ConstraintResolution,
    /// Under a sample set: a violation found off the set, none found on it nearby, and
    /// too many set points in the tile to judge one by one.
    OffSet,
    /// A reason this version does not name.
    Other(String),
}

impl Unproven {
    fn parse(s: &str) -> Self {
        match s {
            "side-gap" => Unproven::SideGap,
            "tile-unknown" => Unproven::TileUnknown,
            "depth-unconfirmed" => Unproven::DepthUnconfirmed,
            "constraint-budget" => Unproven::ConstraintBudget,
            "constraint-resolution" => Unproven::ConstraintResolution,
            "off-set" => Unproven::OffSet,
            o => Unproven::Other(o.to_string()),
        }
    }
}

/// Which part of an answer a counterexample violates.
#[derive(Clone, Debug, PartialEq)]
pub enum Bound {
    UMin,
    UMax,
    VMin,
    VMax,
    TMin,
    TMax,
    ZMin,
    ZMax,
    /// The tile was culled although it holds a covered sample.
    TileCulled,
    /// An interval end was NaN (judged as culling everything).
    NanEnd,
    /// A per-sample constraint, by its name.
    Constraint(String),
}

impl Bound {
    fn parse(s: &str) -> Self {
        match s {
            "u min" => Bound::UMin,
            "u max" => Bound::UMax,
            "v min" => Bound::VMin,
            "v max" => Bound::VMax,
            "t min" => Bound::TMin,
            "t max" => Bound::TMax,
            "z min" => Bound::ZMin,
            "z max" => Bound::ZMax,
            "tile culled" => Bound::TileCulled,
            "NaN interval end" => Bound::NanEnd,
            o => Bound::Constraint(o.to_string()),
        }
    }
}

/// A violation: a covered sample, confirmed in exact arithmetic, that the answer culls.
#[derive(Clone, Debug)]
pub struct Counterexample {
    pub regime: Regime,
    pub case_index: u64,
    pub case: Case,
    pub tile: Tile,
    /// The covered sample (x, y, u, v, t), exactly as the oracle decided it.
    pub sample: [f64; 5],
    pub bound: Bound,
    /// How far the bound would have to move to admit it (infinite for a culled tile).
    pub margin: f64,
    witness: crate::judge::Witness,
}

impl Counterexample {
    fn of(regime: Regime, w: &crate::judge::Witness) -> Self {
        Counterexample {
            regime,
            case_index: w.case_index,
            case: w.case,
            tile: w.tile,
            sample: w.sample,
            bound: Bound::parse(&crate::judge::bound_kind(&w.bound)),
            margin: w.margin,
            witness: w.clone(),
        }
    }
    /// The sample rounded to f32 (what hardware would hold; it may then fall on the
    /// other side of the bound when the witness lies between f32 values).
    pub fn f32_sample(&self) -> Sample {
        let p = self.sample;
        Sample::new(p[0] as f32, p[1] as f32, p[2] as f32, p[3] as f32, p[4] as f32)
    }
}

/// One method over the run.
#[derive(Clone, Debug)]
pub struct MethodReport {
    pub id: String,
    pub cases: u64,
    pub proven: u64,
    pub violated: u64,
    pub unproven: u64,
    /// Cases that could not be judged under the declared samples (a vertex snapping
    /// cannot snap exactly, a case the viewport cannot hold): neither proven, violated
    /// nor unproven.
    pub not_judged: u64,
    /// Unproven cases by reason (a case may have several).
    pub unproven_by: BTreeMap<Unproven, u64>,
    pub verdict: MethodVerdict,
    /// The strongest verdict it reaches: a proof for all inputs in ranges counts above
    /// the run's cases ([`crate::gate::strength`]).
    pub strength: crate::gate::Strength,
    /// That verdict in words, with its numbers (and, for a proof, see
    /// `raw.methods` for its ranges and scripts).
    pub strength_text: String,
    /// False when some row of this method fails its expectation (or the baseline).
    pub passed: bool,
    /// The worst counterexample of each regime with one.
    pub counterexamples: Vec<Counterexample>,
    /// Every counterexample, up to [`crate::gate::row::EXAMPLES_PER_ROW`] per regime
    /// (the first cases of each regime, in regime and case order); `violated` counts
    /// them all.
    pub every_counterexample: Vec<Counterexample>,
}

/// The typed result of a run, with the full report of `cullproof check` under it.
#[derive(Clone, Debug)]
pub struct GateReport {
    pub methods: Vec<MethodReport>,
    pub raw: CheckReport,
}

impl GateReport {
    fn from_check(raw: CheckReport) -> Self {
        let mut methods: Vec<MethodReport> = Vec::new();
        for r in &raw.rows {
            let i = match methods.iter().position(|m| m.id == r.method) {
                Some(i) => i,
                None => {
                    methods.push(MethodReport {
                        id: r.method.clone(),
                        cases: 0,
                        proven: 0,
                        violated: 0,
                        unproven: 0,
                        not_judged: 0,
                        unproven_by: BTreeMap::new(),
                        verdict: MethodVerdict::Proven,
                        strength: crate::gate::Strength::Unproven,
                        strength_text: String::new(),
                        passed: true,
                        counterexamples: Vec::new(),
                        every_counterexample: Vec::new(),
                    });
                    methods.len() - 1
                }
            };
            let m = &mut methods[i];
            m.cases += r.cases;
            m.proven += r.proven;
            m.violated += r.violations;
            m.unproven += r.unproven;
            m.not_judged += r.not_judged;
            for (k, n) in &r.unproven_by {
                *m.unproven_by.entry(Unproven::parse(k)).or_insert(0) += n;
            }
            m.passed &= !r.status.fails();
            if let Some(&regime) = Regime::ALL.iter().find(|x| x.name() == r.regime) {
                m.counterexamples.extend(r.worst.as_ref().map(|w| Counterexample::of(regime, w)));
                m.every_counterexample.extend(r.examples.iter().map(|w| Counterexample::of(regime, w)));
            }
        }
        for m in &mut methods {
            m.verdict = if m.violated > 0 {
                MethodVerdict::Violated
            } else if m.unproven > 0 {
                MethodVerdict::Unproven
            } else if m.proven == 0 && m.not_judged > 0 {
                MethodVerdict::NotJudged
            } else {
                MethodVerdict::Proven
            };
            if let Some(st) = raw.methods.iter().find(|x| x.method == m.id) {
                m.strength = st.strength;
                m.strength_text = st.text.clone();
            }
        }
        GateReport { methods, raw }
    }
    /// Write every counterexample of [`MethodReport::every_counterexample`] as a case
    /// file under `dir` (`dir/<method>/<hash>.json`, the directory made when missing; a
    /// file that exists is left as it is), for `cullproof replay` / `explain` or
    /// [`crate::search::counterexamples::replay`]. Returns the paths, in the report's order.
    pub fn write_cases(&self, dir: &Path) -> anyhow::Result<Vec<std::path::PathBuf>> {
        crate::io::output::dir("the case directory", dir)?;
        let mut cfg = CheckConfig::default_for(Vec::new());
        cfg.seed = self.raw.seed;
        if let Some(n) = &self.raw.samples {
            (cfg.sample_set, cfg.snap, cfg.viewport) = (n.set, n.snap, n.viewport);
        }
        let mut out = Vec::new();
        for m in &self.methods {
            for c in &m.every_counterexample {
                let note = format!("a violation of {} in regime {} found by a gate run", m.id, c.regime.name());
                let at = ("check", c.case_index, c.regime.name().to_string());
                let cf = crate::gate::case_file::CaseFile::violation(
                    &m.id,
                    (c.case, c.tile),
                    &c.witness,
                    &cfg,
                    at,
                    Vec::new(),
                    note,
                );
                out.push(dir.join(&cf.method).join(format!("{}.json", cf.short_hash())));
                cf.write_new(dir)?;
            }
        }
        Ok(out)
    }
    /// True when every row meets its expectation (and the baseline, when given).
    pub fn passed(&self) -> bool {
        !self.raw.failed()
    }
    /// The report of one method.
    pub fn method(&self, id: &str) -> Option<&MethodReport> {
        self.methods.iter().find(|m| m.id == id)
    }
    /// The table `cullproof check` prints.
    pub fn render(&self) -> String {
        crate::gate::render(&self.raw)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bounds::{by_id, MethodInfo, Prepared, TileResult};
    use crate::model::Triangle;

    /// A user's bound in a test: culls every tile (so it is violated wherever the
    /// triangle covers the tile).
    struct CullAll;
    static INFO: MethodInfo = MethodInfo {
        id: "cull-all",
        source: "a test bound",
        reconstruction: false,
        dims: &[],
        outputs: crate::bounds::Outputs {
            tile_reject: true,
            lens: false,
            time: false,
            depth: false,
            per_sample: false,
        },
    };
    struct Nothing;
    impl Prepared for Nothing {
        fn tile(&self, _: &Tile) -> TileResult {
            TileResult::Empty
        }
    }
    impl Method for CullAll {
        fn info(&self) -> &'static MethodInfo {
            &INFO
        }
        fn setup(&self, _: &Triangle) -> Box<dyn Prepared> {
            Box::new(Nothing)
        }
    }

    #[test]
    fn a_users_bound_and_a_built_in_one_get_typed_verdicts() {
        let r = Gate::new()
            .method(CullAll)
            .method(by_id("bbox-safe").unwrap())
            .cases(64)
            .regimes(&[Regime::Static, Regime::Both])
            .run();
        assert!(!r.passed());
        let bad = r.method("cull-all").unwrap();
        assert_eq!(bad.verdict, MethodVerdict::Violated);
        assert!(bad.violated > 0 && !bad.passed);
        let cx = &bad.counterexamples[0];
        assert_eq!(cx.bound, Bound::TileCulled);
        assert!(crate::judge::in_domain(&cx.tile, cx.sample));
        let good = r.method("bbox-safe").unwrap();
        assert_eq!((good.verdict, good.proven, good.cases), (MethodVerdict::Proven, 64, 64));
        assert!(good.passed && good.counterexamples.is_empty());
        assert!(r.render().contains("cull-all"));
    }

    #[test]
    fn bound_and_reason_names_map_to_their_variants() {
        assert_eq!(Bound::parse("t max"), Bound::TMax);
        assert_eq!(Bound::parse("edge # hyperplane"), Bound::Constraint("edge # hyperplane".into()));
        assert_eq!(Unproven::parse("side-gap"), Unproven::SideGap);
        assert_eq!(Unproven::parse("new"), Unproven::Other("new".into()));
    }
}
