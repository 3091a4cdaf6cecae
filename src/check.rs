//! `check`: the conservativeness gate.
//!
//! Every case is a physical (thin-lens) triangle of one regime and a screen tile placed
//! on the boundary of its footprint. Each method's tile answer is judged against the
//! ground truth of the `oracles` crate:
//!
//! - **Intervals** (u^, v^, t^, z^) and a culled tile: against certified tile extents
//!   ([`oracles::extents::TileSolver`]), computed once per case and only for the sides a
//!   method actually narrows. A side is violated when an interior sample (its witness,
//!   confirmed in exact arithmetic) lies outside it; conservative when the certified
//!   enclosure of the extreme lies inside; within the solver's resolution otherwise
//!   (counted conservative), or undecided when the solver left boxes open there.
//! - **Per-sample constraints**: sampled, not certified: uniform samples in the tile and
//!   the extents' witnesses (rounded to f32), each judged exactly. A covered sample that
//!   a constraint culls is a violation; a boundary sample culled is "boundary-only".
//!
//! Every violation witness of a physical case is also asked of Embree (a second
//! opinion, reported, never the judge). The margin needed is the smallest padding of
//! the violated bound that would admit every witness found.
//!
//! Results depend only on the seed and the case indices, never on the thread count:
//! each case draws from its own stream, and the merge is in case order.

use crate::agree::lens_tri;
use crate::bounds::{Method, TileBounds, TileResult};
use crate::csearch::{self, ConstraintVerdict};
use crate::gen::{physical_case, rng_for, samples_for, tile_sample, Regime};
use crate::model::{Case, Sample, Tile};
use indicatif::{ProgressBar, ProgressStyle};
use oracles::extents::{ExtentsConfig, Occupancy, Side, TileSolver};
use oracles::{classify, Coverage, DepthCheck};
use rand::seq::SliceRandom;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// What `corpus/expectations.json` may say of a method in a regime.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Expected {
    Conservative,
    Violation,
    Unknown,
}

/// One expectation: a bare status, or a status with the reason for it.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Entry {
    Plain(Expected),
    Explained {
        expect: Expected,
        why: String,
        /// For an expected violation: the largest margin needed that is expected (a
        /// larger one is unexpected, e.g. f32 rounding known, a gross error not).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        max_margin: Option<f64>,
    },
}

impl Entry {
    pub fn expected(&self) -> Expected {
        match self {
            Entry::Plain(e) | Entry::Explained { expect: e, .. } => *e,
        }
    }
}

/// `{ "method id": { "*": "conservative", "regime": {"expect": "violation", "why": "..."} } }`;
/// a method or regime not listed is expected conservative (published bounds claim to be).
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Expectations(pub BTreeMap<String, BTreeMap<String, Entry>>);

impl Expectations {
    /// Load from a file; an error names the file and what is wrong.
    pub fn load(path: &Path) -> anyhow::Result<Self> {
        let text =
            std::fs::read_to_string(path).map_err(|e| anyhow::anyhow!("{}: cannot read: {e}", path.display()))?;
        let ex: Expectations = serde_json::from_str(&text)
            .map_err(|e| anyhow::anyhow!("{}: not an expectations file: {e}", path.display()))?;
        for (m, regimes) in &ex.0 {
            if crate::bounds::by_id(m).is_none() {
                anyhow::bail!("{}: method `{m}` is not a known method id (see `cullproof methods`)", path.display());
            }
            for r in regimes.keys() {
                if r != "*" && !Regime::ALL.iter().any(|x| x.name() == r) {
                    anyhow::bail!("{}: method `{m}`: regime `{r}` is not a known regime", path.display());
                }
            }
        }
        Ok(ex)
    }
    /// The largest expected margin for a method in a regime, if the entry sets one.
    pub fn max_margin(&self, method: &str, regime: &str) -> Option<f64> {
        let m = self.0.get(method)?;
        match m.get(regime).or_else(|| m.get("*"))? {
            Entry::Explained { max_margin, .. } => *max_margin,
            Entry::Plain(_) => None,
        }
    }
    pub fn get(&self, method: &str, regime: &str) -> Expected {
        let Some(m) = self.0.get(method) else { return Expected::Conservative };
        m.get(regime).or_else(|| m.get("*")).map(Entry::expected).unwrap_or(Expected::Conservative)
    }
}

/// Settings of a run.
#[derive(Clone)]
pub struct CheckConfig {
    pub methods: Vec<&'static dyn Method>,
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
    /// The solver's settings; `extents.resolution` is the gap below which an interval
    /// side counts as conservative.
    pub extents: ExtentsConfig,
    /// How close to a claimed bound the search refines (finds f32-sized violations).
    pub band: f64,
    /// Boxes per interval side.
    pub side_budget: usize,
    /// An interval side gives up after this many boxes in a row that did not raise its
    /// certified bound while no witness lies beyond the claim (0: only the budget
    /// stops it). Such a side is one tight to a rounding: the rest of its budget would
    /// mostly find nothing, so the boxes go to more cases instead.
    pub side_stall: usize,
    /// Boxes per constraint search.
    pub constraint_budget: usize,
}

impl CheckConfig {
    /// The balanced default: every method and regime, about a minute on 2 cores.
    pub fn default_with(methods: Vec<&'static dyn Method>) -> Self {
        CheckConfig {
            methods,
            regimes: Regime::ALL.to_vec(),
            cases: 9600,
            time: None,
            seed: 1,
            tile: None,
            shard: (0, 1),
            samples: 512,
            // Boxes may shrink to 1e-9 of the tile and domain: as fine as the band the
            // side searches refine to, so a bound within an f32 rounding of the true
            // extreme is settled by narrow boxes instead of exhausting the budget on
            // boxes stuck at a coarser minimum (960-case gate: faster, and more of the
            // rounding-size violations found).
            extents: ExtentsConfig { resolution: 1e-3, max_boxes: 20_000, min_fraction: 1e-9 },
            band: 1e-9,
            side_budget: 2000,
            side_stall: 250,
            constraint_budget: 2000,
        }
    }
}

/// A violation, with what is needed to replay it.
#[derive(Clone, Debug, Serialize)]
pub struct Witness {
    pub case_index: u64,
    pub case: Case,
    pub tile: Tile,
    /// The interior sample the method culls (exactly confirmed).
    pub sample: [f64; 5],
    /// Which bound culls it: "tile culled", "u min", "t max", "z min", or a constraint's name.
    pub bound: String,
    /// Padding of that bound that would admit the witness ("inf" in JSON when a
    /// covered tile was culled).
    #[serde(serialize_with = "crate::corpus::num_or_inf::serialize")]
    pub margin: f64,
    /// Embree's verdict on the witness ray (None: not a physical case).
    pub embree_hit: Option<bool>,
}

/// One method on one case.
#[derive(Clone, Debug, Default)]
pub struct Judgement {
    /// The violation with the largest margin found.
    pub violation: Option<Witness>,
    /// Only boundary samples were culled.
    pub boundary_only: bool,
    /// Some claim could be neither confirmed nor refuted within the budgets.
    pub undecided: bool,
    /// Some violation is witnessed by an f32 sample (one a hardware sample generator
    /// can produce), not only by points between f32 values.
    pub f32_witness: bool,
}

/// The row of the verdict table.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Row {
    pub method: String,
    pub regime: String,
    pub cases: u64,
    pub violations: u64,
    pub boundary_only: u64,
    pub undecided: u64,
    /// Violations witnessed by an f32 sample (the rest only between f32 values).
    pub f32_witnessed: u64,
    /// Largest margin needed over the violations (0 when none; "inf" in JSON when a
    /// covered tile was culled).
    #[serde(serialize_with = "crate::corpus::num_or_inf::serialize")]
    pub margin_needed: f64,
    pub expected: Option<Expected>,
    /// The largest margin the expectation allows (None: any).
    pub expected_max_margin: Option<f64>,
    /// "ok", "known violation", "UNEXPECTED VIOLATION", "expected violation not seen".
    pub status: String,
    /// The violation with the largest margin.
    pub worst: Option<Witness>,
}

/// The result of a run.
#[derive(Clone, Debug, Serialize)]
pub struct CheckReport {
    pub seed: u64,
    pub cases: u64,
    pub shard: String,
    pub rows: Vec<Row>,
    /// The sampled cross-check of Embree against the exact oracle, per regime.
    pub cross_check: Vec<CrossCheck>,
    /// Boxes the extents solver examined in all.
    pub solver_boxes: u64,
    pub seconds: f64,
}

impl CheckReport {
    /// True when some method violates where it is expected to be conservative.
    pub fn failed(&self) -> bool {
        self.rows.iter().any(|r| r.status == "UNEXPECTED VIOLATION")
    }
}

/// The case with index `i`: its regime, the triangle and a tile on the footprint's
/// boundary (a tile containing a sample drawn near an edge).
pub fn make_case(cfg: &CheckConfig, i: u64) -> (Regime, Case, Tile) {
    let regime = cfg.regimes[(i % cfg.regimes.len() as u64) as usize];
    let mut rng = rng_for(cfg.seed, i);
    let case = physical_case(&mut rng, regime);
    let size = cfg.tile.unwrap_or_else(|| *[1.0f32, 2.0, 4.0, 8.0, 16.0].choose(&mut rng).unwrap());
    let tile = boundary_tile(&case, &mut rng, size);
    (regime, case, tile)
}

/// A tile of `size` pixels (on the grid of that size) holding a sample drawn near an
/// edge of the triangle: where its footprint's boundary is.
pub fn boundary_tile(case: &Case, rng: &mut ChaCha8Rng, size: f32) -> Tile {
    let pts = samples_for(case, rng, 16);
    // odd indices are the edge-biased samples
    let p = pts[1 + 2 * rng.gen_range(0..8)];
    let (x0, y0) = ((p[0] as f32 / size).floor() * size, (p[1] as f32 / size).floor() * size);
    Tile::square(x0, y0, size)
}

fn f32_sample(p: [f64; 5]) -> Sample {
    Sample::new(p[0] as f32, p[1] as f32, p[2] as f32, p[3] as f32, p[4] as f32)
}

/// f32 samples around a point found beyond a bound on coordinate `axis` (0..5; 5 for a
/// depth bound, which no coordinate carries): on that axis the f32 values just beyond
/// the bound up to the point's own rounding, on the others the nearest f32 and its two
/// neighbours. The exact oracle then says whether one of them is a hardware-reachable
/// witness.
fn f32_candidates(p: [f64; 5], axis: usize, bound: f32, is_max: bool) -> Vec<Sample> {
    let near = |x: f64| {
        let r = x as f32;
        [r, r.next_down(), r.next_up()]
    };
    let mut choices: Vec<Vec<f32>> = p.iter().map(|&x| near(x).to_vec()).collect();
    if axis < 5 {
        let (a, b) = if is_max { (bound.next_up(), p[axis] as f32) } else { (p[axis] as f32, bound.next_down()) };
        let mut v: Vec<f32> = vec![a, b, p[axis] as f32];
        v.retain(|&x| if is_max { x > bound } else { x < bound });
        v.sort_by(f32::total_cmp);
        v.dedup();
        choices[axis] = v;
    } else {
        // depth: keep (u, v, t) at their nearest f32 values
        for c in choices.iter_mut().skip(2) {
            c.truncate(1);
        }
    }
    let mut out = Vec::new();
    for &x in &choices[0] {
        for &y in &choices[1] {
            for &u in &choices[2] {
                for &v in &choices[3] {
                    for &t in &choices[4] {
                        out.push(Sample::new(x, y, u, v, t));
                    }
                }
            }
        }
    }
    out
}

/// Which of the method's answers culls the point, and by how much: an interval it lies
/// outside (distance in f64) or the constraint with the most negative value (evaluated
/// only when the point is an f32 sample, as hardware would see it). None when the
/// intervals and constraints admit it (depth aside).
pub fn culled_by(b: &TileBounds, p: [f64; 5]) -> Option<(String, f64)> {
    let mut worst: Option<(String, f64)> = None;
    let mut note = |name: String, d: f64| {
        if d > 0.0 && worst.as_ref().is_none_or(|w| d > w.1) {
            worst = Some((name, d));
        }
    };
    for (name, r, k) in [("u", b.u, 2), ("v", b.v, 3), ("t", b.t, 4)] {
        note(format!("{name} min"), r[0] as f64 - p[k]);
        note(format!("{name} max"), p[k] - r[1] as f64);
    }
    let s = f32_sample(p);
    if s.to_oracle() == p {
        for c in &b.constraints {
            note(c.name(), -(c.eval(&s) as f64));
        }
    }
    worst
}

/// Judge every method on one case.
fn judge_case(cfg: &CheckConfig, i: u64) -> (Regime, Vec<Judgement>, u64, CrossCheck) {
    let (regime, case, tile) = make_case(cfg, i);
    // One Embree scene and one set of uniform samples serve the judging and the
    // cross-check.
    let embree = embree_for(&case);
    let uniform = uniform_samples(cfg, &tile, i);
    let (js, boxes) = judge_with(cfg, &cfg.methods, &case, &tile, i, embree.as_ref(), &uniform);
    (regime, js, boxes, cross_check(&case, embree.as_ref(), &uniform))
}

fn embree_for(case: &Case) -> Option<oracles::embree::EmbreeOracle> {
    lens_tri(case).and_then(|l| oracles::embree::EmbreeOracle::new(&l).ok())
}

/// The sampled cross-check of the two ground truths on one case: the gate's uniform
/// tile samples judged exactly and by Embree (physical cases only).
#[derive(Clone, Debug, Default, Serialize)]
pub struct CrossCheck {
    pub regime: String,
    /// Samples judged by both oracles.
    pub samples: u64,
    /// Of those, exactly interior.
    pub interior: u64,
    /// Embree said hit where the exact oracle says not interior.
    pub embree_over: u64,
    /// Embree said miss on an interior sample.
    pub embree_under: u64,
}

fn uniform_samples(cfg: &CheckConfig, tile: &Tile, i: u64) -> Vec<Sample> {
    let mut rng = rng_for(cfg.seed ^ 0x05ee_d5a3_b1e5, i);
    (0..cfg.samples).map(|_| tile_sample(&mut rng, tile)).collect()
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

/// Judge `methods` on one case and tile; `i` seeds the uniform samples (and is
/// recorded in witnesses). Returns the judgements and the solver's box count.
pub fn judge(
    cfg: &CheckConfig,
    methods: &[&'static dyn Method],
    case: &Case,
    tile: &Tile,
    i: u64,
) -> (Vec<Judgement>, u64) {
    judge_with(cfg, methods, case, tile, i, embree_for(case).as_ref(), &uniform_samples(cfg, tile, i))
}

/// [`judge`] with the case's Embree scene and uniform tile samples made by the caller.
fn judge_with(
    cfg: &CheckConfig,
    methods: &[&'static dyn Method],
    case: &Case,
    tile: &Tile,
    i: u64,
    embree: Option<&oracles::embree::EmbreeOracle>,
    uniform: &[Sample],
) -> (Vec<Judgement>, u64) {
    let (case, tile) = (*case, *tile);
    let tri = case.triangle.to_oracle();
    let tb = [tile.x0 as f64, tile.x1 as f64, tile.y0 as f64, tile.y1 as f64];
    let mut solver = TileSolver::new(&tri, tb, [[-1.0, 1.0], [-1.0, 1.0], [0.0, 1.0]], &cfg.extents);
    let witness = |sample: [f64; 5], bound: String, margin: f64| Witness {
        case_index: i,
        case,
        tile,
        sample,
        bound,
        margin,
        embree_hit: embree.map(|o| o.hit(sample)),
    };
    let mut out = Vec::with_capacity(methods.len());
    for m in methods {
        let mut j = Judgement::default();
        let consider = |j: &mut Judgement, w: Witness| {
            if j.violation.as_ref().is_none_or(|v| w.margin > v.margin) {
                j.violation = Some(w);
            }
        };
        match m.setup(&case.triangle).tile(&tile) {
            TileResult::Empty => match solver.occupancy() {
                Occupancy::Covered(w) => {
                    let s = f32_sample(w);
                    j.f32_witness = tile.contains(s.x, s.y) && classify(&tri, s.to_oracle()) == Coverage::Interior;
                    consider(&mut j, witness(w, "tile culled".into(), f64::INFINITY))
                }
                Occupancy::Unknown => j.undecided = true,
                Occupancy::Empty => {}
            },
            TileResult::Bounds(b) => {
                // Interval sides, certified.
                let sides = [(b.u, 0usize, -1.0f32, 1.0f32, "u"), (b.v, 2, -1.0, 1.0, "v"), (b.t, 4, 0.0, 1.0, "t")];
                let mut checks: Vec<(usize, f64, bool, String)> = Vec::new();
                for (r, n, lo, hi, name) in sides {
                    if r[0] > lo {
                        checks.push((n, r[0] as f64, false, format!("{name} min")));
                    }
                    if r[1] < hi {
                        checks.push((n + 1, r[1] as f64, true, format!("{name} max")));
                    }
                }
                if let Some(z) = b.z {
                    checks.push((6, z[0] as f64, false, "z min".into()));
                    checks.push((7, z[1] as f64, true, "z max".into()));
                }
                let mut found: Vec<Sample> = Vec::new();
                for (n, bound, is_max, name) in checks {
                    match solver.side(
                        n,
                        bound,
                        cfg.band,
                        cfg.side_budget,
                        (cfg.side_stall > 0).then_some(cfg.side_stall),
                    ) {
                        Side::Beyond { witness: w, value, .. } => {
                            // A depth witness is re-judged exactly against the bound.
                            let confirmed = n < 6 || {
                                let want = if is_max { DepthCheck::Above } else { DepthCheck::Below };
                                let (z0, z1) = b.z.map(|z| (z[0] as f64, z[1] as f64)).unwrap_or((f64::MIN, f64::MAX));
                                oracles::classify_depth(&tri, w, z0, z1) == want
                            };
                            if confirmed {
                                consider(&mut j, witness(w, name, (value - bound).abs()));
                                let axis = if n < 6 { [2, 3, 4][n / 2] } else { 5 };
                                let cands = f32_candidates(w, axis, bound as f32, is_max);
                                if n < 6 {
                                    found.extend(cands);
                                } else if let Some([z0, z1]) = b.z {
                                    let want = if is_max { DepthCheck::Above } else { DepthCheck::Below };
                                    j.f32_witness |= cands.iter().any(|s| {
                                        tile.contains(s.x, s.y)
                                            && oracles::classify_depth(&tri, s.to_oracle(), z0 as f64, z1 as f64)
                                                == want
                                    });
                                }
                            } else {
                                j.undecided = true;
                            }
                        }
                        Side::Within { gap, .. } => {
                            if gap > cfg.extents.resolution {
                                j.undecided = true;
                            }
                        }
                    }
                }
                // Per-sample constraints: the certified search, then the sampled
                // cross-check (uniform samples and the witnesses found).
                if !b.constraints.is_empty() {
                    match csearch::search(&tri, &tile, &b, cfg.constraint_budget, cfg.band).verdict {
                        ConstraintVerdict::Violation(s) => found.push(s),
                        ConstraintVerdict::Undecided => j.undecided = true,
                        ConstraintVerdict::Proved | ConstraintVerdict::WithinResolution => {}
                    }
                }
                if !b.constraints.is_empty() || !found.is_empty() {
                    for s in uniform.iter().chain(&found) {
                        if b.admits(s) || !tile.contains(s.x, s.y) {
                            continue;
                        }
                        match classify(&tri, s.to_oracle()) {
                            Coverage::Interior => {
                                j.f32_witness = true;
                                let (name, deficit) = culled_by(&b, s.to_oracle()).expect("not admitted");
                                consider(&mut j, witness(s.to_oracle(), name, deficit));
                            }
                            Coverage::Boundary => j.boundary_only = true,
                            Coverage::Outside => {}
                        }
                    }
                }
            }
        }
        if j.violation.is_some() {
            j.boundary_only = false;
        }
        out.push(j);
    }
    (out, solver.boxes)
}

/// One line per method over all regimes: the verdict at a glance.
fn render_summary(r: &CheckReport) -> String {
    let mut s = format!(
        "\nper method, all regimes:\n{:<24} {:>6} {:>10} {:>5} {:>9} {:>11}  {}\n",
        "method", "cases", "violations", "f32", "undecided", "margin", "status"
    );
    let mut methods: Vec<&str> = Vec::new();
    for row in &r.rows {
        if !methods.contains(&row.method.as_str()) {
            methods.push(&row.method);
        }
    }
    for m in methods {
        let rows: Vec<&Row> = r.rows.iter().filter(|x| x.method == m).collect();
        let sum = |f: fn(&Row) -> u64| rows.iter().map(|x| f(x)).sum::<u64>();
        let violations = sum(|x| x.violations);
        let margin = rows.iter().filter(|x| x.violations > 0).map(|x| x.margin_needed).fold(0.0, f64::max);
        let where_: Vec<&str> = rows.iter().filter(|x| x.violations > 0).map(|x| x.regime.as_str()).collect();
        let status = if rows.iter().any(|x| x.status == "UNEXPECTED VIOLATION") {
            "UNEXPECTED VIOLATION"
        } else if violations > 0 {
            "known violations only"
        } else {
            "no violation"
        };
        let regimes = match where_.len() {
            0 => String::new(),
            n => format!(", in {n} of {} regimes", rows.len()),
        };
        s += &format!(
            "{:<24} {:>6} {:>10} {:>5} {:>9} {:>11}  {}{}\n",
            m,
            sum(|x| x.cases),
            violations,
            sum(|x| x.f32_witnessed),
            sum(|x| x.undecided),
            if violations == 0 { "-".to_string() } else { format!("{margin:.3e}") },
            status,
            regimes
        );
    }
    s
}

/// Run the gate.
pub fn run(cfg: &CheckConfig, ex: &Expectations, progress: bool) -> CheckReport {
    let start = std::time::Instant::now();
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
    let judged = results.len() as u64;
    let mut rows: BTreeMap<(usize, usize), Row> = BTreeMap::new();
    let mut boxes = 0;
    let mut cross: BTreeMap<usize, CrossCheck> = BTreeMap::new();
    for (regime, js, b, cc) in results {
        boxes += b;
        let ri = cfg.regimes.iter().position(|r| *r == regime).unwrap();
        let x = cross.entry(ri).or_insert_with(|| CrossCheck { regime: regime.name().into(), ..Default::default() });
        x.samples += cc.samples;
        x.interior += cc.interior;
        x.embree_over += cc.embree_over;
        x.embree_under += cc.embree_under;
        let ri = cfg.regimes.iter().position(|r| *r == regime).unwrap();
        for (mi, j) in js.into_iter().enumerate() {
            let m = cfg.methods[mi].info().id;
            let row = rows.entry((mi, ri)).or_insert_with(|| Row {
                method: m.into(),
                regime: regime.name().into(),
                expected: Some(ex.get(m, regime.name())),
                expected_max_margin: ex.max_margin(m, regime.name()),
                ..Default::default()
            });
            row.cases += 1;
            row.boundary_only += j.boundary_only as u64;
            row.f32_witnessed += (j.violation.is_some() && j.f32_witness) as u64;
            row.undecided += j.undecided as u64;
            if let Some(w) = j.violation {
                row.violations += 1;
                if w.margin >= row.margin_needed {
                    row.margin_needed = w.margin;
                    row.worst = Some(w);
                }
            }
        }
    }
    let mut rows: Vec<Row> = rows.into_values().collect();
    for r in &mut rows {
        let above = r.expected_max_margin.is_some_and(|m| r.margin_needed > m);
        r.status = match (r.expected.unwrap_or(Expected::Conservative), r.violations > 0) {
            (Expected::Conservative, true) => "UNEXPECTED VIOLATION",
            (Expected::Violation, true) if above => "UNEXPECTED VIOLATION",
            (Expected::Violation, true) => "known violation",
            (Expected::Violation, false) => "expected violation not seen",
            (_, false) => "ok",
            (Expected::Unknown, true) => "violation",
        }
        .into();
    }
    CheckReport {
        seed: cfg.seed,
        cases: judged,
        shard: format!("{k}/{n}"),
        rows,
        cross_check: cross.into_values().collect(),
        solver_boxes: boxes,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// The verdict table.
pub fn render(r: &CheckReport) -> String {
    let mut s = format!(
        "cullproof check, seed {}, {} cases (shard {}), {:.1} s\n\n{:<24} {:<15} {:>6} {:>10} {:>5} {:>9} {:>9} {:>11}  status\n",
        r.seed,
        r.cases,
        r.shard,
        r.seconds,
        "method",
        "regime",
        "cases",
        "violations",
        "f32",
        "boundary",
        "undecided",
        "margin"
    );
    let mut last = "";
    for row in &r.rows {
        let m = if row.method == last { "" } else { row.method.as_str() };
        last = &row.method;
        let margin = if row.violations == 0 { "-".to_string() } else { format!("{:.3e}", row.margin_needed) };
        s += &format!(
            "{:<24} {:<15} {:>6} {:>10} {:>5} {:>9} {:>9} {:>11}  {}\n",
            m,
            row.regime,
            row.cases,
            row.violations,
            row.f32_witnessed,
            row.boundary_only,
            row.undecided,
            margin,
            row.status
        );
    }
    s += &render_summary(r);
    let unexpected: Vec<_> = r.rows.iter().filter(|x| x.status == "UNEXPECTED VIOLATION").collect();
    s += "\nmargin: the padding of the violated bound that would admit every witness found (inf: a covered tile was culled).\n";
    s += "f32: violations with a witness that is an f32 sample (the others were found only between f32 values).\n";
    let (n, inside, over, under) = r
        .cross_check
        .iter()
        .fold((0, 0, 0, 0), |a, c| (a.0 + c.samples, a.1 + c.interior, a.2 + c.embree_over, a.3 + c.embree_under));
    let differ: Vec<String> = r
        .cross_check
        .iter()
        .filter(|c| c.embree_over + c.embree_under > 0)
        .map(|c| format!("{} {}", c.regime, c.embree_over + c.embree_under))
        .collect();
    s += &format!(
        "sampled cross-check: {n} uniform tile samples of physical cases judged by both oracles, {inside} interior; \
         Embree (f32) differed on {} ({over} over, {under} under{}{}), each settled by the exact oracle.\n",
        over + under,
        if differ.is_empty() { "" } else { "; by regime: " },
        differ.join(", ")
    );
    if unexpected.is_empty() {
        s += "verdict: PASS — no method violates where corpus/expectations.json expects it to be conservative\n";
    } else {
        s += &format!(
            "verdict: FAIL — {} method x regime rows show unexpected violations; witnesses:\n",
            unexpected.len()
        );
        for row in unexpected {
            if let Some(w) = &row.worst {
                s += &format!(
                    "  {} / {}: case {} tile [{}, {}]x[{}, {}] sample {:?} culled by {} (margin {:.3e}, Embree {})\n",
                    row.method,
                    row.regime,
                    w.case_index,
                    w.tile.x0,
                    w.tile.x1,
                    w.tile.y0,
                    w.tile.y1,
                    w.sample,
                    w.bound,
                    w.margin,
                    match w.embree_hit {
                        Some(true) => "hits too",
                        Some(false) => "misses",
                        None => "n/a",
                    }
                );
            }
        }
    }
    s
}
