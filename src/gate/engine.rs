//! The gate's run (what `cullproof check` does): cases x methods, judged, and each
//! method x regime row held to its expectations.
//!
//! Every case is a physical (thin-lens) triangle of one regime. Every method is judged
//! on a tile on the boundary of the footprint ([`crate::cases::make_case`]), and in turn each method
//! also on the two tiles at its own tile-reject limit ([`crate::cases::limit_tiles`]). Each answer gets one
//! of three verdicts ([`crate::judge`]): **proven** conservative (every claim certified, no gap
//! left), **violated** (an interior sample, confirmed exactly, inside the tile and the
//! lens/shutter domain, that the answer culls) or **unproven** (counted by reason).
//!
//! Each method x regime row is then held against `corpus/expectations.json`
//! ([`super::expect`]): an expected-conservative row fails on any violation and on unproven
//! cases beyond its stated allowance; an expected violation fails when it leaves its
//! signature (a bound kind not listed, a margin above its cap, a rate above its cap).
//! With a stored baseline for the same settings ([`super::baseline`]), a row also fails when it
//! shows a new kind of violated bound, a larger margin beyond noise, a higher rate, or
//! an answer that lets more of the domain through than before.
//!
//! Results depend only on the seed and the case indices, never on the thread count:
//! each case draws from its own stream, and the merge is in case order.

use super::{
    expect::Expectations,
    report::{self, CheckReport, CrossCheck},
};
use crate::cases::{try_make_case, Draw};
use crate::judge::Judgement;

use crate::bounds::{Method, MethodRef, TileResult};
use crate::cases::generate::{rng_for, tile_sample, Regime};
use crate::judge::agree::lens_tri;
use crate::judge::sample_set::SetJudge;
use crate::judge::{JudgeSettings, TileJudge};
use crate::model::{Case, Sample, SampleSet, Snap, Tile, Viewport};
use indicatif::{ProgressBar, ProgressStyle};
use oracles::extents::ExtentsConfig;
use oracles::{classify, Coverage};
use rayon::prelude::*;

/// Settings of a run.
#[derive(Clone)]
pub struct CheckConfig {
    pub methods: Vec<MethodRef>,
    pub regimes: Vec<Regime>,
    pub cases: u64,
    /// Run whole batches of cases for about this many seconds instead of `cases`.
    pub time: Option<f64>,
    pub seed: u64,
    /// Fixed tile size in pixels; None draws from 1, 2, 4, 8, 16.
    pub tile: Option<f32>,
    /// This shard `(k, n)`: cases whose index is k modulo n.
    pub shard: (u64, u64),
    /// Uniform samples per case for the per-sample constraints.
    pub samples: usize,
    /// What the judge may spend on each tile, and what it keeps.
    pub judge: JudgeSettings,
    /// Each method is also judged on the two tiles at its own tile-reject limit in one
    /// case out of this many (0: never), in turn over the regimes, at an offset fixed by
    /// its id: a method's rows do not depend on which other methods run with it.
    pub limit_every: u64,
    /// Boxes the occupancy search of a culled limit tile may use (its edge lies within a
    /// rounding of the covered set, so a sliver may stay undecided: unproven).
    pub limit_budget: usize,
    /// Screen shifts of the case tried when placing a limit tile (the one whose flip
    /// lies farthest inside the footprint's extreme is judged).
    pub limit_shifts: usize,
    /// The pixel positions the methods promise to keep ([`SampleSet::Any`]: all).
    pub sample_set: SampleSet,
    /// Vertex snapping before coverage is judged (None: none).
    pub snap: Option<Snap>,
    /// The viewport the cases are placed in (None: anywhere, as the regimes draw them).
    pub viewport: Option<Viewport>,
}

impl CheckConfig {
    /// How this run draws its cases.
    pub fn draw(&self) -> Draw<'_> {
        Draw { seed: self.seed, regimes: &self.regimes, tile: self.tile, viewport: self.viewport }
    }

    /// The balanced default for these registry methods: every regime, about a minute
    /// on 2 cores with every method.
    pub fn default_with(methods: Vec<&'static dyn Method>) -> Self {
        Self::default_for(crate::bounds::shared_all(methods))
    }

    /// The balanced default for any methods (a user's own bounds among them).
    pub fn default_for(methods: Vec<MethodRef>) -> Self {
        CheckConfig {
            methods,
            regimes: Regime::ALL.to_vec(),
            cases: 9600,
            time: None,
            seed: 1,
            tile: None,
            shard: (0, 1),
            samples: 512,
            judge: JudgeSettings {
                // Boxes may shrink to 1e-9 of the tile and domain: fine enough to separate
                // a bound from the true extreme when they differ by an f32 rounding.
                extents: ExtentsConfig {
                    resolution: 1e-3,
                    max_boxes: 20_000,
                    min_fraction: 1e-9,
                    // On: the expectations and baselines are written with it.
                    second_chance: true,
                    occupancy_eliminates: false,
                },
                band: 0.0,
                side_budget: 2000,
                side_stall: 250,
                constraint_budget: 2000,
                constraint_min_width: 1e-9,
                witnesses_per_kind: false,
            },
            limit_every: 12,
            limit_shifts: 8,
            limit_budget: 4000,
            sample_set: SampleSet::Any,
            snap: None,
            viewport: None,
        }
    }
}

/// A run has at most this many cases in all (`check --cases`; `cullproof merge` holds
/// every shard report's run to it too).
pub const MAX_CASES: u64 = 1_000_000_000;

/// The samples a bound promises to keep, as declared (`--samples`, `--snap`,
/// `--viewport`; `docs/model.md`, §7): each None when it was not declared.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Declared {
    pub samples: Option<SampleSet>,
    pub snap: Option<Snap>,
    pub viewport: Option<Viewport>,
}

impl Declared {
    /// Put the declared values into a run's settings (values not declared leave them).
    pub fn apply(&self, cfg: &mut CheckConfig) {
        if let Some(s) = self.samples {
            cfg.sample_set = s;
        }
        if self.snap.is_some() {
            cfg.snap = self.snap;
        }
        if self.viewport.is_some() {
            cfg.viewport = self.viewport;
        }
    }
}

fn embree_for(case: &Case) -> Option<oracles::embree::EmbreeOracle> {
    lens_tri(case).and_then(|l| oracles::embree::EmbreeOracle::new(&l).ok())
}

fn uniform_samples(cfg: &CheckConfig, tile: &Tile, stream: u64, i: u64, n: usize) -> Vec<Sample> {
    let mut rng = rng_for(cfg.seed ^ stream, i);
    (0..n).map(|_| tile_sample(&mut rng, tile)).collect()
}

const UNIFORM_STREAM: u64 = 0x05ee_d5a3_b1e5;
const LIMIT_STREAM: u64 = 0x7113_e5ba_5e11;

/// What one case gives: its regime, a judgement per method, the solver's boxes and the
/// Embree cross-check.
pub(crate) struct CaseResult {
    pub(crate) regime: Regime,
    pub(crate) judgements: Vec<Judgement>,
    /// Per method: the share of the (u, v, t) domain its answer on the boundary tile
    /// lets through (0 for a culled tile), and the share of the tile's uniform samples
    /// it admits (intervals and constraints).
    pub(crate) pass: Vec<(f64, f64)>,
    pub(crate) boxes: u64,
    pub(crate) cross: CrossCheck,
    /// False for a case the viewport could not hold (every method not judged).
    pub(crate) placed: bool,
}

/// A case that cannot be judged under the declared samples (a vertex key snapping
/// cannot snap exactly, or a case the viewport cannot hold): every method not judged.
pub(crate) fn not_judged_result(cfg: &CheckConfig, regime: Regime) -> CaseResult {
    let j = Judgement::not_judged();
    CaseResult {
        regime,
        judgements: vec![j; cfg.methods.len()],
        pass: vec![(0.0, 0.0); cfg.methods.len()],
        boxes: 0,
        cross: Default::default(),
        placed: true,
    }
}

/// The share of the lens/shutter domain that an answer's intervals keep.
fn pass_fraction(r: &TileResult) -> f64 {
    match r {
        TileResult::Empty => 0.0,
        TileResult::Bounds(b) => {
            let w = |a: [f32; 2], lo: f64, hi: f64| {
                let (a0, a1) = ((a[0] as f64).max(lo), (a[1] as f64).min(hi));
                if a0.is_nan() || a1.is_nan() || a1 < a0 {
                    0.0
                } else {
                    (a1 - a0) / (hi - lo)
                }
            };
            w(b.u, -1.0, 1.0) * w(b.v, -1.0, 1.0) * w(b.t, 0.0, 1.0)
        }
    }
}

/// The share of `uniform` (a tile's uniform samples) that an answer admits, its
/// intervals and constraints together (0 for a culled tile; the share of the domain
/// its intervals keep when there are no samples).
fn admit_share(a: &TileResult, uniform: &[Sample]) -> f64 {
    match a {
        TileResult::Empty => 0.0,
        TileResult::Bounds(_) if uniform.is_empty() => pass_fraction(a),
        TileResult::Bounds(b) => uniform.iter().filter(|s| b.admits(s)).count() as f64 / uniform.len() as f64,
    }
}

/// Judge every method on one case: the boundary tile for all, the limit tiles for the
/// methods whose turn it is.
fn judge_case(cfg: &CheckConfig, i: u64) -> CaseResult {
    let Some((regime, case, tile)) = try_make_case(&cfg.draw(), i) else {
        // The viewport cannot hold this case: counted, not judged.
        let regime = cfg.regimes[(i % cfg.regimes.len() as u64) as usize];
        return CaseResult { placed: false, ..not_judged_result(cfg, regime) };
    };
    let Ok((seen, tri)) = crate::cases::place::judged_triangles(cfg.snap, &case) else {
        return not_judged_result(cfg, regime);
    };
    let embree = if cfg.snap.is_none() { embree_for(&case) } else { None };
    let uniform = uniform_samples(cfg, &tile, UNIFORM_STREAM, i, cfg.samples);
    let prepared: Vec<_> = cfg.methods.iter().map(|m| m.setup(&seen)).collect();
    let answers: Vec<TileResult> = prepared.iter().map(|p| p.tile(&tile)).collect();
    let mut tj =
        SetJudge::new(TileJudge::new(&cfg.judge, case, tile, i, &tri, embree.as_ref(), &uniform), cfg.sample_set);
    let mut judgements: Vec<Judgement> = answers.iter().map(|a| tj.judge(a)).collect();
    let mut boxes = tj.boxes();
    let pass = answers.iter().map(|a| (pass_fraction(a), admit_share(a, &uniform))).collect();
    let round = i / cfg.regimes.len() as u64;
    for (mi, m) in cfg.methods.iter().enumerate() {
        let salt = method_salt(m.info().id);
        if cfg.limit_every == 0 || !(round + salt).is_multiple_of(cfg.limit_every) {
            continue;
        }
        let (jl, b) = judge_limit_tiles(cfg, m.as_ref(), &case, i, salt);
        boxes += b;
        if let Some(jl) = jl {
            judgements[mi].merge(jl);
        }
    }
    CaseResult { regime, judgements, pass, boxes, cross: cross_check(&case, embree.as_ref(), &uniform), placed: true }
}

/// A number fixed by a method's id (a deliberately broken variant counts as the method
/// it breaks): where its limit tiles fall and which stream places them.
pub fn method_salt(id: &str) -> u64 {
    let inner = crate::bounds::broken::inner_id(id);
    inner.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ b as u64).wrapping_mul(0x100_0000_01b3)) >> 8
}

/// Judge one method on the two tiles at its own tile-reject limit ([`crate::cases::limit_tiles`]); `salt`
/// picks the stream ([`method_salt`]). None when the method culls no
/// tile near the footprint. Also returns the solver's box count.
pub fn judge_limit_tiles(
    cfg: &CheckConfig,
    m: &dyn Method,
    case: &Case,
    i: u64,
    salt: u64,
) -> (Option<Judgement>, u64) {
    let mut rng = rng_for(cfg.seed ^ LIMIT_STREAM, i.wrapping_mul(64).wrapping_add(salt));
    let size = crate::cases::generate::tile_size(cfg.tile, &mut rng);
    let setup = |c: &Case| match crate::cases::place::judged_triangles(cfg.snap, c) {
        Ok((seen, _)) => m.setup(&seen),
        Err(_) => m.setup(&c.triangle),
    };
    let Some(crate::cases::limit_tiles::Limit { case: lc, prepared: p, kept, culled, slack }) =
        crate::cases::limit_tiles::limit_tiles(&setup, case, &mut rng, size, cfg.limit_shifts)
    else {
        return (None, 0);
    };
    // Under a viewport only tiles inside it, of a case inside its guard band.
    if !(crate::cases::place::placed_in(cfg.viewport, &lc, &kept)
        && crate::cases::place::placed_in(cfg.viewport, &lc, &culled))
    {
        return (None, 0);
    }
    let Ok((_, tri)) = crate::cases::place::judged_triangles(cfg.snap, &lc) else {
        return (None, 0);
    };
    let embree = if cfg.snap.is_none() { embree_for(&lc) } else { None };
    let mut out = Judgement::default();
    out.limit_slack = Some(slack);
    let mut boxes = 0;
    let lcfg = JudgeSettings {
        extents: ExtentsConfig { max_boxes: cfg.limit_budget.min(cfg.judge.extents.max_boxes), ..cfg.judge.extents },
        ..cfg.judge.clone()
    };
    for t in [culled, kept] {
        let uni = uniform_samples(cfg, &t, LIMIT_STREAM, i, cfg.samples / 4);
        let mut lj = SetJudge::new(TileJudge::new(&lcfg, lc, t, i, &tri, embree.as_ref(), &uni), cfg.sample_set);
        let mut jj = lj.judge(&p.tile(&t));
        boxes += lj.boxes();
        jj.limit_tiles = 1;
        jj.limit_violations = jj.violation.is_some() as u32;
        out.merge(jj);
    }
    (Some(out), boxes)
}

/// Judge the case's uniform tile samples with both oracles; the exact verdict settles
/// every difference (counted, never used to judge a method).
fn cross_check(case: &Case, embree: Option<&oracles::embree::EmbreeOracle>, uniform: &[Sample]) -> CrossCheck {
    let mut c = CrossCheck::default();
    let Some(embree) = embree else {
        return c;
    };
    let tri = case.triangle.to_oracle();
    for s in uniform {
        let p = s.to_oracle();
        let interior = classify(&tri, p) == Coverage::Interior;
        let hit = embree.hit(p);
        c.samples += 1;
        c.interior += interior as u64;
        c.embree_over += (hit && !interior) as u64;
        c.embree_under += (!hit && interior) as u64;
    }
    c
}

/// Judge `methods` on one case and tile (no limit tiles); `i` seeds the uniform samples
/// (and is recorded in witnesses). Returns the judgements and the solver's box count.
///
/// Under snapping the methods see the snapped triangle and the oracle judges it exactly;
/// a case that cannot be snapped is not judged ([`crate::judge::Verdict::NotJudged`]).
pub fn judge(cfg: &CheckConfig, methods: &[MethodRef], case: &Case, tile: &Tile, i: u64) -> (Vec<Judgement>, u64) {
    let (js, _, boxes) = judge_admitted(cfg, methods, case, tile, i);
    (js, boxes)
}

/// [`judge()`], with the share of the tile's uniform samples each method's answer admits
/// (the quantity a row's `admit_fraction` averages; 0 for a case that is not judged).
pub fn judge_admitted(
    cfg: &CheckConfig,
    methods: &[MethodRef],
    case: &Case,
    tile: &Tile,
    i: u64,
) -> (Vec<Judgement>, Vec<f64>, u64) {
    let Ok((seen, tri)) = crate::cases::place::judged_triangles(cfg.snap, case) else {
        return (vec![Judgement::not_judged(); methods.len()], vec![0.0; methods.len()], 0);
    };
    let embree = if cfg.snap.is_none() { embree_for(case) } else { None };
    let uniform = uniform_samples(cfg, tile, UNIFORM_STREAM, i, cfg.samples);
    let mut tj =
        SetJudge::new(TileJudge::new(&cfg.judge, *case, *tile, i, &tri, embree.as_ref(), &uniform), cfg.sample_set);
    let (js, admit) = methods
        .iter()
        .map(|m| {
            let answer = m.setup(&seen).tile(tile);
            (tj.judge(&answer), admit_share(&answer, &uniform))
        })
        .unzip();
    (js, admit, tj.boxes())
}

/// Run the gate: judge the cases, then hold each row against the expectations and
/// (when it matches the settings) the baseline.
pub fn run(cfg: &CheckConfig, ex: &Expectations, progress: bool) -> CheckReport {
    run_with_baseline(cfg, ex, None, progress)
}

/// [`run`] with a baseline file's contents to compare against.
pub fn run_with_baseline(
    cfg: &CheckConfig,
    ex: &Expectations,
    base: Option<&super::baseline::BaselineFile>,
    progress: bool,
) -> CheckReport {
    let start = std::time::Instant::now();
    let breaches = crate::external::plugin::breaches();
    let (k, n) = cfg.shard;
    let mut results = Vec::new();
    match cfg.time {
        None => {
            let ids: Vec<u64> = (0..cfg.cases).filter(|i| i % n == k).collect();
            let pb = if progress { ProgressBar::new(ids.len() as u64) } else { ProgressBar::hidden() };
            pb.set_style(
                ProgressStyle::with_template("{bar:40} {pos}/{len} cases {elapsed_precise} eta {eta}").unwrap(),
            );
            results = ids
                .par_iter()
                .map(|&i| {
                    let r = judge_case(cfg, i);
                    pb.inc(1);
                    r
                })
                .collect();
            pb.finish_and_clear();
        }
        Some(secs) => {
            // Whole batches of case indices until the time is up: the cases judged are
            // 0..N for the N reported, so `--cases N` repeats the run exactly.
            let pb = if progress { ProgressBar::new((secs * 1000.0) as u64) } else { ProgressBar::hidden() };
            pb.set_style(ProgressStyle::with_template("{bar:40} {msg} {elapsed_precise}").unwrap());
            let batch = 256 * n;
            let mut next = 0u64;
            while start.elapsed().as_secs_f64() < secs {
                let ids: Vec<u64> = (next..next + batch).filter(|i| i % n == k).collect();
                results.par_extend(ids.par_iter().map(|&i| judge_case(cfg, i)));
                next += batch;
                pb.set_position((start.elapsed().as_secs_f64() * 1000.0) as u64);
                pb.set_message(format!("{next} cases"));
            }
            pb.finish_and_clear();
        }
    }
    // Every case drawn has its row entry; those the viewport could not hold are
    // not judged (and counted in the sample set's note).
    let drawn = results.len() as u64;
    let outside = results.iter().filter(|r| !r.placed).count() as u64;
    let mut acc = report::Accumulator::new(ex);
    for r in results {
        acc.add(cfg, r.regime, r.judgements, &r.pass, r.boxes, r.cross);
    }
    let mut rep = acc.finish(cfg, drawn, start.elapsed().as_secs_f64());
    rep.samples = super::settings::SetNote::of(cfg, outside);
    rep.contract_breaches = crate::external::plugin::breaches_since(&breaches);
    rep.tool = Some(super::tool::ToolInfo::of(ex, base.map(super::tool::hash)));
    if let Some(b) = base {
        super::baseline::apply(&mut rep, cfg, b);
    }
    rep
}
